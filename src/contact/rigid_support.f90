!> rigid_support: the free directions of the RIGID obstacles as exact
!> floating modes of the condensed contact problem.
!>
!> A RIGID has three dofs U = (u_x, u_y, theta) and no stiffness.  Those that
!> FIX prescribes are Dirichlet data (their motion enters q = g - B u0); the
!> free ones, loaded by FORCE F, are unknowns held only by contact, as the
!> free rigid modes of a deformable body (rigid_modes, contact_lcp): with
!> H_r = B(:, free rigid dofs) (how each free direction opens the gaps) and
!> e_r = F on them,
!>     gap = q + W mu - H_r alpha_r >= 0,  mu >= 0,  mu'gap = 0,  H_r' mu = e_r,
!> the last equation the obstacle's equilibrium: the contact forces on it,
!> -H_r' mu, balance its load.  alpha_r is its motion; no spring anywhere.
!>
!> With friction the tangential rows T join B (H_r = C(:, free dofs), C = [B; T])
!> and the step's friction LCP carries alpha_r (friction_modes), as it carries
!> the free modes of the bodies.
!> Which combinations of the free directions contact holds is decided from the
!> SVD of each RIGID's columns of H_r in comparable units: the rotation as
!> phi = L theta, L the shape's size, so that its column is H_theta / L (the
!> entries of H_theta are lever arms, a length) and a singular value is the
!> gap a motion of unit size opens, translation or rotation alike, whatever
!> the unit of length.  A right singular vector with singular value below
!> 1e-8 of the largest column norm is not held (the rotation of a circle
!> about its centre, a translation along a flat punch without friction).
!> The shapes are exact, so the threshold is a round-off one (no polygon
!> defect as in mode_support).  An unheld combination must be unloaded: the
!> load conjugate to phi is m / L, a force like the others, and
!> |v'(e / scale)| <= 1e-10 |e / scale|, else there is no equilibrium: exit 1
!> naming the obstacle and the direction.
!>
!> Programming interface
!>   type(rigid_split_t)                            free dofs, H_r, e_r, held / unheld
!>   split_rigid_modes(cs, rigids, fixed, fext, rs) build H_r, e_r and the decision
!>   rigid_direction(rs, c)                         'translation along (x, y)' / 'rotation' in words
!>   pulled_rigid(rs, owner, resid)                 the obstacle whose load pulls it off its contacts
module rigid_support
  use kinds, only: dp
  use lapack_interfaces, only: dgesvd
  use contact_set, only: contact_set_t
  use rigid_obstacle, only: rigid_shape_t
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke
  implicit none
  private
  public :: rigid_split_t, split_rigid_modes, rigid_direction, pulled_rigid

  type :: rigid_split_t
    integer :: k = 0                          !< free rigid directions, all obstacles
    integer, allocatable :: dof(:)            !< (k) their global dofs
    integer, allocatable :: owner(:)          !< (k) the RIGID of each
    integer, allocatable :: comp(:)           !< (k) 1 u_x, 2 u_y, 3 theta
    real(dp), allocatable :: scale(:)         !< (k) 1, or the shape's size L for theta (phi = L theta)
    real(dp), allocatable :: h(:,:)           !< (nrow + ntan, k) C's columns on them (C = [B; T])
    real(dp), allocatable :: e(:)             !< (k) their loads (FORCE)
    real(dp), allocatable :: held(:,:)        !< (k, kh) the combinations contact holds (orthonormal)
    real(dp), allocatable :: unheld(:,:)      !< (k, ku) those it does not hold
    integer, allocatable :: unheld_owner(:)   !< (ku) their RIGID
    logical, allocatable :: loaded(:)         !< (ku) an unheld combination carries load
  end type rigid_split_t

contains

  !> H_r, e_r and the held / unheld split of the free RIGID directions.
  !>   cs     (in)  the constraint rows (B on the rigid dofs too)
  !>   rigids (in)  (nrigid) the shapes and their dof0
  !>   fixed  (in)  (ndof) Dirichlet dofs (a RIGID's prescribed directions)
  !>   fext   (in)  (ndof) the loads of the step (FORCE on the free directions)
  !>   rs     (out) the split; rs%k = 0 when no RIGID has a free direction
  subroutine split_rigid_modes(cs, rigids, fixed, fext, rs)
    type(contact_set_t), intent(in) :: cs
    type(rigid_shape_t), intent(in) :: rigids(:)
    logical, intent(in) :: fixed(:)
    real(dp), intent(in) :: fext(:)
    type(rigid_split_t), intent(out) :: rs
    integer :: r, j, k, c, row, m, info, lwork, i, nr
    integer, allocatable :: cols(:)
    real(dp), allocatable :: a(:,:), s(:), vt(:,:), work(:), held(:,:), unheld(:,:)
    real(dp) :: u(1, 1), wq(1), ref, load, escale
    integer, allocatable :: uowner(:)
    logical, allocatable :: loaded(:)

    k = 0
    do r = 1, size(rigids)
      k = k + count(.not. fixed(rigids(r)%dof0 + 1:rigids(r)%dof0 + 3))
    end do
    rs%k = k
    nr = cs%nrow + cs%ntan
    allocate(rs%dof(k), rs%owner(k), rs%comp(k), rs%scale(k), rs%h(nr, k), rs%e(k))
    rs%h = 0.0_dp
    k = 0
    do r = 1, size(rigids)
      do j = 1, 3
        if (fixed(rigids(r)%dof0 + j)) cycle
        k = k + 1
        rs%dof(k) = rigids(r)%dof0 + j
        rs%owner(k) = r
        rs%comp(k) = j
        rs%scale(k) = merge(rigids(r)%length, 1.0_dp, j == 3)
        rs%e(k) = fext(rs%dof(k))
      end do
    end do
    ! H_r: the entries of C's rows on these dofs (friction rows hold tangential directions)
    do row = 1, nr
      do i = cs%bptr(row), cs%bptr(row + 1) - 1
        c = cs%cdof(cs%bcol(i))
        do j = 1, rs%k
          if (rs%dof(j) == c) rs%h(row, j) = rs%h(row, j) + cs%bval(i)
        end do
      end do
    end do
    allocate(held(rs%k, 0), unheld(rs%k, 0), uowner(0), loaded(0))
    do r = 1, size(rigids)
      cols = pack([(j, j = 1, rs%k)], rs%owner == r)
      m = size(cols)
      if (m == 0) cycle
      a = rs%h(:, cols)
      do j = 1, m
        a(:, j) = a(:, j) / rs%scale(cols(j))      ! d gap / d phi = H_theta / L, phi = L theta
      end do
      ref = maxval(norm2(a, dim=1))
      escale = norm2(rs%e(cols) / rs%scale(cols))
      allocate(s(min(nr, m)), vt(m, m))
      s = 0.0_dp
      vt = 0.0_dp
      do j = 1, m
        vt(j, j) = 1.0_dp
      end do
      if (nr > 0) then
        call dgesvd('N', 'A', nr, m, a, nr, s, u, 1, vt, m, wq, -1, info)
        lwork = max(1, int(wq(1)))
        allocate(work(lwork))
        call dgesvd('N', 'A', nr, m, a, nr, s, u, 1, vt, m, work, lwork, info)
        deallocate(work)
      end if
      do j = 1, m
        ! combination v (scaled units) -> in the dofs: theta = phi / L
        if (j <= size(s)) then
          if (s(j) > 1.0e-8_dp * ref .and. ref > 0.0_dp) then
            held = reshape([held, expand(rs%scale, cols, vt(j, :))], [rs%k, size(held, 2) + 1])
            cycle
          end if
        end if
        unheld = reshape([unheld, expand(rs%scale, cols, vt(j, :))], [rs%k, size(unheld, 2) + 1])
        uowner = [uowner, r]
        load = abs(dot_product(vt(j, :), rs%e(cols) / rs%scale(cols)))
        loaded = [loaded, load > 1.0e-10_dp * max(escale, tiny(1.0_dp)) .and. load > 0.0_dp]
      end do
      deallocate(s, vt)
    end do
    ! the held basis in the dofs' own units (alpha = held lambda)
    call move_alloc(held, rs%held)
    call move_alloc(unheld, rs%unheld)
    call move_alloc(uowner, rs%unheld_owner)
    call move_alloc(loaded, rs%loaded)
  contains
    !> v (on cols, scaled units: phi = L theta) as a k-vector in the dofs,
    !> v_j / scale_j (theta = phi / L), of unit length
    pure function expand(scale, cols, v) result(x)
      real(dp), intent(in) :: scale(:)
      integer, intent(in) :: cols(:)
      real(dp), intent(in) :: v(:)
      real(dp) :: x(size(scale))
      x = 0.0_dp
      x(cols) = v / scale(cols)
      x = x / norm2(x)
    end function expand
  end subroutine split_rigid_modes

  !> A combination c (k) of one RIGID's free directions in words:
  !> 'translation along (dx, dy)', 'rotation about its reference point', or both.
  function rigid_direction(rs, c) result(t)
    type(rigid_split_t), intent(in) :: rs
    real(dp), intent(in) :: c(:)
    character(len=:), allocatable :: t
    real(dp) :: a(3), tr
    character(len=32) :: bx, by
    integer :: j
    a = 0.0_dp
    do j = 1, rs%k
      a(rs%comp(j)) = a(rs%comp(j)) + c(j) * rs%scale(j)     ! phi = L theta, comparable with a translation
    end do
    tr = norm2(a(1:2))
    t = ''
    if (tr > 1.0e-8_dp * norm2(a)) then
      write(bx, '(f8.4)') a(1) / tr
      write(by, '(f8.4)') a(2) / tr
      t = 'translation along (' // trim(adjustl(bx)) // ', ' // trim(adjustl(by)) // ')'
    end if
    if (abs(a(3)) > 1.0e-8_dp * norm2(a)) then
      if (len(t) > 0) t = t // ' with '
      t = t // 'rotation about its reference point'
    end if
  end function rigid_direction

  !> The first RIGID whose load its contacts cannot balance: min |H_j' mu - e_j|
  !> over mu >= 0 (nonnegative least squares as the LCP(H_j H_j', -H_j e_j),
  !> Lemke) is not zero.  0 when each can be balanced on its own.  The columns
  !> are those of phi = L theta (H_theta / L, its load m / L), so that the
  !> residual compares forces with forces whatever the unit of length.
  !>   rs (in) the split;  owner (out) the RIGID, 0 when none;  resid (out) (3) the
  !>   unbalanced part of its load (fx, fy, m: u_x, u_y, theta order, 0 on
  !>   prescribed ones)
  subroutine pulled_rigid(rs, owner, resid)
    type(rigid_split_t), intent(in) :: rs
    integer, intent(out) :: owner
    real(dp), intent(out) :: resid(3)
    integer :: r, j
    integer, allocatable :: cols(:)
    real(dp), allocatable :: hj(:,:), ej(:), mu(:), rr(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    owner = 0
    resid = 0.0_dp
    if (rs%k == 0) return
    do r = 1, maxval(rs%owner)
      cols = pack([(j, j = 1, rs%k)], rs%owner == r)
      if (size(cols) == 0) cycle
      hj = rs%h(1:size(rs%h, 1), cols)
      ej = rs%e(cols) / rs%scale(cols)                 ! m / L: a force
      do j = 1, size(cols)
        hj(:, j) = hj(:, j) / rs%scale(cols(j))        ! H_theta / L: per unit phi
      end do
      allocate(mu(size(hj, 1)), source=0.0_dp)
      call solve_lcp_lemke(matmul(hj, transpose(hj)), -matmul(hj, ej), mu, opts, rep)
      rr = matmul(transpose(hj), mu) - ej
      if (norm2(rr) > 1.0e-8_dp * norm2(ej)) then
        owner = r
        do j = 1, size(cols)
          resid(rs%comp(cols(j))) = -rr(j) * rs%scale(cols(j))     ! back to (fx, fy, m)
        end do
        return
      end if
      deallocate(mu)
    end do
  end subroutine pulled_rigid

end module rigid_support
