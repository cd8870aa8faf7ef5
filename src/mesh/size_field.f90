!> size_field: the element sizes an adaptive re-mesh asks of gmsh, from the
!> error indicators, and the background mesh that carries them to gmsh.
!>
!> The optimal mesh (doc/theory.md, "Adaptive meshes").  Element K, with
!> relative indicator eta_K (sum_K eta_K^2 = estimate^2), re-meshed with
!> elements of s_K times its size, leaves an error eta_K^2 s_K^(2 p_K) there
!> (p_K the rate of the energy error in h: the element's order on a smooth
!> solution) and puts about s_K^-2 elements in its place.  The fewest
!> elements for a total error T^2 are (Lagrange)
!>     s_K = (mu / eta_K^2)^(1 / (2 p_K + 2)),   mu such that sum_K eta_K^2 s_K^(2 p_K) = T^2,
!> and mu is found by Newton's method on log mu, kept in a bracket by
!> bisection, since that sum grows with mu (also with the bounds smin <= s_K
!> <= smax of one step, and with orders that differ from body to body, where
!> no closed form is left).
!>
!> Why it exists: the adaptive loop (app/adaptivity) and the prediction of
!> the cost of the next digit (app/run_estimate) ask the same question, how
!> many elements a given error needs; gmsh answers where to put them.  Who
!> may use it: the app layer.
!>
!> Programming interface
!>   optimal_scales(eta2, rate, target2, smin, smax, s)   s_K of the fewest elements for the error target2
!>   element_count(s)                                    sum_K s_K^-2, the new mesh's elements
!>   element_size(mesh, e)                               mean length of element e's straight corner edges
!>   write_background(mesh, dx, dy, h, path, hmin, hmax, err[, cap])
!>        a gmsh post-processing view (.pos) of the nodal sizes of the element sizes h on the mesh
!>        shifted by -(dx, dy), at most cap at each node; hmin, hmax the smallest and largest size written
module size_field
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: error_t, set_error, error_numerical
  use mesh, only: mesh_t
  use elements, only: corner_count
  implicit none
  private
  public :: optimal_scales, element_count, element_size, write_background

contains

  !> The scales s_K of the mesh with the fewest elements whose error is
  !> target2 (module header), within [smin, smax].  When even smin
  !> everywhere leaves more error than target2, s = smin; when smax
  !> everywhere leaves less, s = smax.
  !>   eta2    (in)  (nelem) the relative indicators squared
  !>   rate    (in)  (nelem) the energy error's rate in h of each element (its order; > 0)
  !>   target2 (in)  the total relative error sought, squared (> 0)
  !>   smin, smax (in) bounds of one step, 0 < smin <= 1 <= smax
  !>   s       (out) (nelem) the scales
  pure subroutine optimal_scales(eta2, rate, target2, smin, smax, s)
    real(dp), intent(in) :: eta2(:), rate(:), target2, smin, smax
    real(dp), intent(out) :: s(:)
    real(dp) :: leta(size(eta2)), lo, hi, t, f, df, dt, ltarget
    integer :: it
    ! in logarithms: element k leaves exp(leta_k + 2 p_k log s_k), with
    ! log s_k = (log mu - leta_k) / (2 p_k + 2) within [log smin, log smax];
    ! an element without error (eta2 = 0) leaves none at any size
    where (eta2 > 0.0_dp)
      leta = log(eta2)
    elsewhere
      leta = -huge(1.0_dp)
    end where
    ltarget = log(target2)
    ! log mu spans what the indicators and the bounds can ask for
    lo = log(tiny(1.0_dp)) / 2
    hi = -lo
    call error_at(lo, f, df)
    if (f >= target2) then
      s = smin
      return
    end if
    call error_at(hi, f, df)
    if (f <= target2) then
      s = smax
      return
    end if
    ! Newton on log f(log mu) - log target2 (f increases with mu, and its
    ! logarithm is nearly linear in log mu: a few steps), kept inside the
    ! bracket [lo, hi] by bisection, to the resolution of log mu, far below
    ! any mesh size's; lo always leaves at most the target
    t = 0.5_dp * (lo + hi)
    do it = 1, 200
      call error_at(t, f, df)
      if (f > target2) then
        hi = t
      else
        lo = t
      end if
      if (hi - lo < 1.0e-12_dp) exit
      if (f > 0.0_dp .and. df > 0.0_dp) then
        dt = (ltarget - log(f)) * f / df
        if (abs(dt) < 0.25e-12_dp) dt = sign(0.25e-12_dp, dt)   ! close the bracket around a converged t
        t = t + dt
        if (.not. (t > lo .and. t < hi)) t = 0.5_dp * (lo + hi)
      else                                  ! every element at a bound: f is flat here
        t = 0.5_dp * (lo + hi)
      end if
    end do
    call scales(lo, s)
  contains
    pure subroutine scales(log_mu, sk)
      real(dp), intent(in) :: log_mu
      real(dp), intent(out) :: sk(:)
      integer :: k
      do k = 1, size(eta2)
        if (eta2(k) > 0.0_dp) then
          sk(k) = min(smax, max(smin, exp((log_mu - leta(k)) / (2 * rate(k) + 2))))
        else
          sk(k) = smax                      ! no error there: as coarse as one step allows
        end if
      end do
    end subroutine scales
    !> The error the scales of log_mu leave, f, and its derivative in log mu, df.
    pure subroutine error_at(log_mu, f, df)
      real(dp), intent(in) :: log_mu
      real(dp), intent(out) :: f, df
      real(dp) :: ls, c, term
      integer :: k
      f = 0.0_dp
      df = 0.0_dp
      do k = 1, size(eta2)
        if (.not. eta2(k) > 0.0_dp) cycle
        c = 1.0_dp / (2 * rate(k) + 2)
        ls = (log_mu - leta(k)) * c
        if (ls <= log(smin)) then
          term = exp(leta(k) + 2 * rate(k) * log(smin))
        else if (ls >= log(smax)) then
          term = exp(leta(k) + 2 * rate(k) * log(smax))
        else
          term = exp(leta(k) + 2 * rate(k) * ls)
          df = df + term * 2 * rate(k) * c
        end if
        f = f + term
      end do
    end subroutine error_at
  end subroutine optimal_scales

  !> The elements of the mesh the scales ask for: sum_K s_K^-2.
  pure real(dp) function element_count(s) result(n)
    real(dp), intent(in) :: s(:)
    n = sum(1.0_dp / s**2)
  end function element_count

  !> The size of element e: the mean length of its corner-to-corner edges
  !> (what gmsh's mesh size means: the length of the edges it makes).
  pure real(dp) function element_size(m, e) result(h)
    type(mesh_t), intent(in) :: m
    integer, intent(in) :: e
    integer :: nc, a
    nc = corner_count(m%nen(e))
    h = 0.0_dp
    do a = 1, nc
      h = h + norm2(m%x(:, m%conn(mod(a, nc) + 1, e)) - m%x(:, m%conn(a, e)))
    end do
    h = h / nc
  end function element_size

  !> The background mesh gmsh meshes to (gmsh -bgm): a list-based
  !> post-processing view of scalar triangles (ST), the mesh's elements
  !> (quadrilaterals as two triangles, corners only), with the size at each
  !> corner the mean of the sizes asked of the elements around it (a size
  !> field continuous across elements, as gmsh interpolates it).
  !>   m      (in)  the mesh (in the solver's coordinates)
  !>   dx, dy (in)  the body's OFFSET: the view is in the .geo's coordinates, x - (dx, dy)
  !>   h      (in)  (nelem) the size asked of each element
  !>   path   (in)  the .pos file to write
  !>   hmin, hmax (out) the smallest and largest nodal size written
  !>   err    (out) allocated when the file cannot be written
  !>   cap    (in, optional) (nnode) the largest size at each node, over the elements' mean
  subroutine write_background(m, dx, dy, h, path, hmin, hmax, err, cap)
    type(mesh_t), intent(in) :: m
    real(dp), intent(in) :: dx, dy, h(:)
    real(dp), intent(in), optional :: cap(:)
    character(len=*), intent(in) :: path
    real(dp), intent(out) :: hmin, hmax
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: hsum(:), count(:)
    integer :: e, a, nc, u, ios
    integer, parameter :: split(3, 2) = reshape([1, 2, 3, 1, 3, 4], [3, 2])
    allocate(hsum(m%nnode), count(m%nnode), source=0.0_dp)
    do e = 1, m%nelem
      do a = 1, corner_count(m%nen(e))
        hsum(m%conn(a, e)) = hsum(m%conn(a, e)) + h(e)
        count(m%conn(a, e)) = count(m%conn(a, e)) + 1
      end do
    end do
    where (count > 0) hsum = hsum / count
    if (present(cap)) hsum = min(hsum, cap)
    hmin = minval(hsum, mask=count > 0)
    hmax = maxval(hsum, mask=count > 0)
    open(newunit=u, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) then
      call set_error(err, 'cannot write the size field "' // path // '"', error_numerical)
      return
    end if
    write(u, '(a)', iostat=ios) 'View "size" {'
    do e = 1, m%nelem
      nc = corner_count(m%nen(e))
      do a = 1, nc - 2
        if (ios == 0) call write_triangle(m%conn(split(:, a), e))
      end do
    end do
    if (ios == 0) write(u, '(a)', iostat=ios) '};'
    close(u)
    if (ios /= 0) call set_error(err, 'cannot write the size field "' // path // '" (error ' // int_to_str(ios) // ')', &
      error_numerical)
  contains
    subroutine write_triangle(v)
      integer, intent(in) :: v(3)
      write(u, '(a,9(es24.16e3,a),3(es24.16e3,a))', iostat=ios) 'ST(', &
        m%x(1, v(1)) - dx, ',', m%x(2, v(1)) - dy, ',', 0.0_dp, ',', &
        m%x(1, v(2)) - dx, ',', m%x(2, v(2)) - dy, ',', 0.0_dp, ',', &
        m%x(1, v(3)) - dx, ',', m%x(2, v(3)) - dy, ',', 0.0_dp, '){', &
        hsum(v(1)), ',', hsum(v(2)), ',', hsum(v(3)), '};'
    end subroutine write_triangle
  end subroutine write_background

end module size_field
