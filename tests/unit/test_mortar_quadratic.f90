!> Unit tests of mortar_quadratic: pi_h on quadratic and mixed traces, against
!> independent facts: reproduction of the traces' own polynomials on straight
!> non-matching edges (exact quadrature), pi 1 = 1, integral preservation
!> (sum_i w_i (P c)_i = sum_j mcov_j c_j), closed-form gaps, and on curved arcs
!> the quadrature error of the 4-point rule measured against a composite rule
!> of 64 panels per element (module header, 2.), and the periodic zone.
program test_mortar_quadratic
  use kinds, only: dp
  use errors, only: error_t
  use mortar_operator, only: mortar_t, zone_point
  use mortar_quadratic, only: build_mortar_quadratic, gauss4
  use trace_geometry, only: trace_point
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  implicit none

  real(dp), parameter :: pi = 3.14159265358979323846_dp

  call test_straight(2, 2)
  call test_straight(1, 2)
  call test_straight(2, 1)
  call test_cut(2, 2)
  call test_cut(1, 2)
  call test_cut(2, 1)
  call test_axisymmetric(2, 2)
  call test_axisymmetric(1, 2)
  call test_curved_quadrature()
  call test_periodic()
  call finish_tests()

contains

  !> A trace of degree p on y = y0 over [0, 1] with nel elements whose corners
  !> are perturbed (non-uniform), mid-side nodes at the middle.
  function flat_trace(p, nel, y0, shift) result(x)
    integer, intent(in) :: p, nel
    real(dp), intent(in) :: y0, shift
    real(dp) :: x(2, p * nel + 1), c(nel + 1)
    integer :: e
    do e = 0, nel
      c(e + 1) = (real(e, dp) + shift * sin(7.0_dp * e)) / nel
    end do
    c(1) = 0.0_dp
    c(nel + 1) = 1.0_dp
    do e = 1, nel
      x(:, p * (e - 1) + 1) = [c(e), y0]
      if (p == 2) x(:, p * (e - 1) + 2) = [0.5_dp * (c(e) + c(e + 1)), y0]
    end do
    x(:, p * nel + 1) = [1.0_dp, y0]
  end function flat_trace

  function constant_normals(nel, n) result(nrm)
    integer, intent(in) :: nel
    real(dp), intent(in) :: n(2)
    real(dp) :: nrm(2, nel)
    integer :: e
    do e = 1, nel
      nrm(:, e) = n
    end do
  end function constant_normals

  !> Straight non-matching traces: the slave (degree ps, 7 elements) on y = 0
  !> facing up, the master (degree pm, 5 elements) on y = 0.1 facing down.
  !> pi reproduces the polynomials of degree min(ps, pm) exactly, rows sum to
  !> one, integrals are preserved, the gap is 0.1.
  subroutine test_straight(ps, pm)
    integer, intent(in) :: ps, pm
    real(dp), allocatable :: xs(:,:), xm(:,:), mcov(:), c(:), v(:)
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    character(len=16) :: tag
    integer :: deg
    xs = flat_trace(ps, 7, 0.0_dp, 0.2_dp)
    xm = flat_trace(pm, 5, 0.1_dp, -0.25_dp)
    write(tag, '(a,i0,a,i0,a)') '(', ps, ' on ', pm, ')'
    call build_mortar_quadratic(xs, ps, constant_normals(7, [0.0_dp, 1.0_dp]), xm, pm, &
                                constant_normals(5, [0.0_dp, -1.0_dp]), .false., mo, mcov, err)
    call check(.not. allocated(err), 'straight ' // trim(tag) // ': built')
    if (allocated(err)) return
    call check(mo%first == 1 .and. mo%last == size(xs, 2) &
               .and. all(mo%cut == [0.0_dp, 1.0_dp]), &
               'straight ' // trim(tag) // ': the zone is the whole slave')
    call check_small(maxval(abs(sum(mo%P, dim=2) - 1.0_dp)), tol_round(64), 'straight ' // trim(tag) // ': pi 1 = 1')
    deg = min(ps, pm)
    c = poly(xm(1, :), deg)
    v = matmul(mo%P, c)
    call check_small(maxval(abs(v - poly(xs(1, :), deg))), tol_round(64), &
                     'straight ' // trim(tag) // ': pi reproduces the polynomials of the common degree')
    c = cos(5.0_dp * xm(1, :))
    call check_close(dot_product(mo%zone_weight, matmul(mo%P, c)), dot_product(mcov, c), tol_round(16), &
                     'straight ' // trim(tag) // ': int pi phi = int phi')
    call check_close(sum(mcov), 1.0_dp, tol_round(16), 'straight ' // trim(tag) // ': the master integrals sum to the length')
    call check_small(maxval(abs(mo%gap0 - 0.1_dp)), tol_round(16), 'straight ' // trim(tag) // ': gap0 = 0.1')
  end subroutine test_straight

  !> 1 + 2x - 3x^2 (degree 2) or 1 + 2x (degree 1) at the points x.
  function poly(x, deg) result(f)
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: deg
    real(dp) :: f(size(x))
    f = 1.0_dp + 2.0_dp * x
    if (deg == 2) f = f - 3.0_dp * x**2
  end function poly

  !> An arc of radius r from angle a0 to a1 as a trace of degree 2 with nel
  !> elements, nodes on the circle (mid-side nodes at the middle angle).
  function arc_trace(r, a0, a1, nel) result(x)
    real(dp), intent(in) :: r, a0, a1
    integer, intent(in) :: nel
    real(dp) :: x(2, 2 * nel + 1), a
    integer :: k
    do k = 0, 2 * nel
      a = a0 + (a1 - a0) * k / (2.0_dp * nel)
      x(:, k + 1) = r * [cos(a), sin(a)]
    end do
  end function arc_trace

  function chord_normals(x, outward) result(nrm)
    real(dp), intent(in) :: x(:,:)
    real(dp), intent(in) :: outward     ! +1: away from the origin, -1: towards it
    real(dp) :: nrm(2, (size(x, 2) - 1) / 2), m(2)
    integer :: e
    do e = 1, size(nrm, 2)
      m = x(:, 2 * e + 1) - x(:, 2 * e - 1)
      nrm(:, e) = [m(2), -m(1)] / norm2(m)
      if (dot_product(nrm(:, e), x(:, 2 * e)) * outward < 0.0_dp) nrm(:, e) = -nrm(:, e)
    end do
  end function chord_normals

  !> The quadrature error on curved edges: the weights int phi_i |x'| ds of a
  !> quarter circle (slave, radius 1.001, nel elements), by the operator's
  !> 4-point rule (weight: whole elements; covered_weight: through the pairing
  !> with a master arc of radius 1 and 17 elements) and by a composite rule of
  !> 64 panels per element.  The largest relative errors are printed for
  !> nel = 4, 8, 16; below 2e-9 at 8, and falling as h^6 (measured ratio 63
  !> per halving; the rule is exact to degree 7, the relative error h^6).
  !> A master (degree pm, 5 elements over [0.13, 0.87], y = 0.1) that ends
  !> inside the first and last elements of the slave (degree ps, 7 elements
  !> over [0, 1], y = 0): the zone is the slave cut at the master's ends
  !> (module header, 4.).  The cut ends' zone points are x = 0.13 and 0.87,
  !> pi reproduces the polynomials of degree min(ps, pm) at every zone point,
  !> pi 1 = 1, int pi phi = int phi with the zone's weights, the gap is 0.1.
  subroutine test_cut(ps, pm)
    integer, intent(in) :: ps, pm
    real(dp), allocatable :: xs(:,:), xm(:,:), mcov(:), c(:), v(:), xz(:)
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    character(len=16) :: tag
    integer :: deg, i
    real(dp) :: pt(2)
    xs = flat_trace(ps, 7, 0.0_dp, 0.0_dp)
    xm = flat_trace(pm, 5, 0.1_dp, -0.25_dp)
    xm(1, :) = 0.13_dp + 0.74_dp * xm(1, :)
    write(tag, '(a,i0,a,i0,a)') '(', ps, ' on ', pm, ')'
    call build_mortar_quadratic(xs, ps, constant_normals(7, [0.0_dp, 1.0_dp]), xm, pm, &
                                constant_normals(5, [0.0_dp, -1.0_dp]), .false., mo, mcov, err)
    call check(.not. allocated(err), 'cut ' // trim(tag) // ': built')
    if (allocated(err)) return
    call check(mo%first == 1 .and. mo%last == size(xs, 2), 'cut ' // trim(tag) // ': the zone spans the slave''s elements')
    call check_small(norm2(zone_point(mo, xs, mo%first) - [0.13_dp, 0.0_dp]) + &
                     norm2(zone_point(mo, xs, mo%last) - [0.87_dp, 0.0_dp]), tol_round(16), &
                     'cut ' // trim(tag) // ': the zone ends where the master ends')
    allocate(xz(mo%first:mo%last))
    do i = mo%first, mo%last
      pt = zone_point(mo, xs, i)
      xz(i) = pt(1)
    end do
    call check_small(maxval(abs(sum(mo%P, dim=2) - 1.0_dp)), tol_round(64), 'cut ' // trim(tag) // ': pi 1 = 1')
    deg = min(ps, pm)
    c = poly(xm(1, :), deg)
    v = matmul(mo%P, c)
    call check_small(maxval(abs(v - poly(xz, deg))), tol_round(64), &
                     'cut ' // trim(tag) // ': pi reproduces the polynomials of the common degree at the zone points')
    call check_close(dot_product(mo%zone_weight, v), dot_product(mcov, c), tol_round(64), &
                     'cut ' // trim(tag) // ': int pi phi = int phi (the zone''s weights)')
    call check_close(sum(mo%zone_weight), 0.74_dp, tol_round(16), 'cut ' // trim(tag) // ': the zone is 0.74 long')
    call check_small(maxval(abs(mo%gap0 - 0.1_dp)), tol_round(16), 'cut ' // trim(tag) // ': gap0 = 0.1')
  end subroutine test_cut

  !> Axisymmetric (x the radius): the slave (degree ps, 7 elements over
  !> r in [0, 1], z = 0) under the master (degree pm, 5 elements, z = 0.1).
  !> The weights int phi_i 2 pi r ds against Simpson's rule, exact for the
  !> cubic phi_i r (corner 2 pi L r / 6, mid-side node 2 pi L 4 r_m / 6 on a
  !> quadratic element); pi 1 = 1 and int pi phi 2 pi r = int phi 2 pi r
  !> (exact quadrature, degree 5 <= 7); the zone's first node on the axis
  !> gets the axis as its normal (module header, 7.).
  subroutine test_axisymmetric(ps, pm)
    integer, intent(in) :: ps, pm
    real(dp), allocatable :: xs(:,:), xm(:,:), mcov(:), c(:), v(:), w(:)
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    character(len=16) :: tag
    integer :: deg, e, i0
    real(dp) :: l
    xs = flat_trace(ps, 7, 0.0_dp, 0.2_dp)
    xm = flat_trace(pm, 5, 0.1_dp, -0.25_dp)
    write(tag, '(a,i0,a,i0,a)') '(', ps, ' on ', pm, ')'
    call build_mortar_quadratic(xs, ps, constant_normals(7, [0.0_dp, 1.0_dp]), xm, pm, &
                                constant_normals(5, [0.0_dp, -1.0_dp]), .false., mo, mcov, err, axisymmetric=.true.)
    call check(.not. allocated(err), 'axisymmetric ' // trim(tag) // ': built')
    if (allocated(err)) return
    allocate(w(size(xs, 2)), source=0.0_dp)
    do e = 1, 7
      i0 = ps * (e - 1) + 1
      l = xs(1, i0 + ps) - xs(1, i0)
      if (ps == 1) then                         ! int phi r over a segment: L (2 r_a + r_b) / 6
        w(i0) = w(i0) + 2 * pi * l * (2 * xs(1, i0) + xs(1, i0 + 1)) / 6
        w(i0 + 1) = w(i0 + 1) + 2 * pi * l * (xs(1, i0) + 2 * xs(1, i0 + 1)) / 6
      else
        w(i0:i0 + 2) = w(i0:i0 + 2) + 2 * pi * l * [xs(1, i0), 4 * xs(1, i0 + 1), xs(1, i0 + 2)] / 6
      end if
    end do
    call check_small(maxval(abs(mo%weight - w)) / pi, tol_round(64), &
                     'axisymmetric ' // trim(tag) // ': weights int phi_i 2 pi r ds (Simpson, exact)')
    call check_close(sum(mo%zone_weight), pi, tol_round(16), 'axisymmetric ' // trim(tag) // ': the zone''s area is pi')
    call check_small(maxval(abs(sum(mo%P, dim=2) - 1.0_dp)), tol_round(64), 'axisymmetric ' // trim(tag) // ': pi 1 = 1')
    deg = min(ps, pm)
    c = poly(xm(1, :), deg)
    v = matmul(mo%P, c)
    call check_close(dot_product(mo%zone_weight, v), dot_product(mcov, c), tol_round(64), &
                     'axisymmetric ' // trim(tag) // ': int pi phi 2 pi r = int phi 2 pi r')
    call check(mo%axis_end(1) .and. .not. mo%axis_end(2) .and. all(mo%normal(:, 1) == [0.0_dp, 1.0_dp]), &
               'axisymmetric ' // trim(tag) // ': the zone''s end on the axis has no end condition, the axis as normal')
  end subroutine test_axisymmetric

  !> The covered weights are compared at the nodes off the two end elements,
  !> whose cover starts a hair inside them (the arcs' normals at the ends are
  !> those of their interpolants, not exactly radial).
  subroutine test_curved_quadrature()
    integer, parameter :: levels(3) = [4, 8, 16]
    real(dp), allocatable :: xs(:,:), xm(:,:), mcov(:), w(:)
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    real(dp) :: errw(3), errc(3), y(2), dy(2), s, nn(3)
    integer :: l, nel, e, k, q, n
    do l = 1, 3
      nel = levels(l)
      xs = arc_trace(1.001_dp, 0.0_dp, 0.5_dp * pi, nel)
      xm = arc_trace(1.0_dp, 0.0_dp, 0.5_dp * pi, 17)
      call build_mortar_quadratic(xs, 2, chord_normals(xs, 1.0_dp), xm, 2, chord_normals(xm, -1.0_dp), &
                                  .false., mo, mcov, err)
      call check(.not. allocated(err), 'curved: built')
      if (allocated(err)) return
      n = size(xs, 2)
      allocate(w(n), source=0.0_dp)
      do e = 1, nel
        do k = 0, 63
          do q = 1, 4
            s = (k + gauss4(1, q)) / 64.0_dp
            call trace_point(xs, 2, e, s, y, dy)
            nn = [(1.0_dp - s) * (1.0_dp - 2.0_dp * s), 4.0_dp * s * (1.0_dp - s), s * (2.0_dp * s - 1.0_dp)]
            w(2 * e - 1:2 * e + 1) = w(2 * e - 1:2 * e + 1) + gauss4(2, q) / 64.0_dp * norm2(dy) * nn
          end do
        end do
      end do
      errw(l) = maxval(abs(mo%weight - w) / w)
      errc(l) = maxval(abs(mo%covered_weight(4:n - 3) - w(4:n - 3)) / w(4:n - 3))
      write(*, '(a,i0,a,es9.2,a,es9.2)') 'INFO curved quadrature: ', nel, ' elements per quarter, largest ' // &
        'relative error of int phi_i |x''| ds: whole elements ', errw(l), ', through the pairing ', errc(l)
      deallocate(w)
    end do
    call check_small(errw(2), 2.0e-9_dp, 'curved: the 4-point rule''s error on 8 elements per quarter below 2e-9')
    call check_small(errc(2), 2.0e-9_dp, 'curved: the same through the pairing with the master')
    call check(errw(3) < errw(2) / 48.0_dp .and. errw(2) < errw(1) / 48.0_dp, &
               'curved: the rule''s error falls as h^6 (ratio above 48 per halving)')
  end subroutine test_curved_quadrature

  !> A closed circle (slave, radius 1.001, 24 elements) in a closed circle
  !> (master, radius 1, 19 elements): the periodic zone covers every node,
  !> pi 1 = 1, the gap is the interference -0.001 up to the deviation of the
  !> two quadratic interpolants from their circles (measured here on 200
  !> points per element), integrals preserved.
  subroutine test_periodic()
    real(dp), allocatable :: xs(:,:), xm(:,:), mcov(:), c(:)
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    real(dp) :: dev
    xs = arc_trace(1.001_dp, 0.0_dp, 2.0_dp * pi, 24)
    xm = arc_trace(1.0_dp, 0.1_dp, 0.1_dp + 2.0_dp * pi, 19)
    xs(:, size(xs, 2)) = xs(:, 1)
    xm(:, size(xm, 2)) = xm(:, 1)
    call build_mortar_quadratic(xs, 2, chord_normals(xs, 1.0_dp), xm, 2, chord_normals(xm, -1.0_dp), &
                                .false., mo, mcov, err)
    call check(.not. allocated(err), 'periodic: built')
    if (allocated(err)) return
    call check(mo%first == 1 .and. mo%last == size(xs, 2), 'periodic: every slave node in the zone')
    call check_small(maxval(abs(sum(mo%P, dim=2) - 1.0_dp)), tol_round(32), 'periodic: pi 1 = 1')
    dev = deviation(xs, 1.001_dp) + deviation(xm, 1.0_dp)
    write(*, '(a,es9.2,a,es9.2)') 'INFO periodic: largest |gap0 + 0.001| ', maxval(abs(mo%gap0 + 0.001_dp)), &
      ', the interpolants'' deviation from the circles ', dev
    call check_small(maxval(abs(mo%gap0 + 0.001_dp)), dev, 'periodic: gap0 = -0.001 up to the interpolation of the circles')
    c = xm(1, :)**2
    call check_close(dot_product(mo%zone_weight(1:size(xs, 2) - 1), matmul(mo%P(1:size(xs, 2) - 1, :), c)), &
                     dot_product(mcov, c), tol_round(16), 'periodic: int pi phi = int phi')
  end subroutine test_periodic

  !> Largest | |x(s)| - r | over the elements of a degree-2 trace, 200 points each.
  real(dp) function deviation(x, r) result(d)
    real(dp), intent(in) :: x(:,:), r
    real(dp) :: y(2), dy(2)
    integer :: e, k
    d = 0.0_dp
    do e = 1, (size(x, 2) - 1) / 2
      do k = 0, 200
        call trace_point(x, 2, e, k / 200.0_dp, y, dy)
        d = max(d, abs(norm2(y) - r))
      end do
    end do
  end function deviation

end program test_mortar_quadratic
