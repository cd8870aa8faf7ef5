!> mode_support: which free rigid modes of a body the contact rows hold, on a
!> case decided by hand.  A lower square [0,1]^2 held by FIX on its bottom
!> edge carries an upper square [0,1] x [1,2] held by nothing: the upper body
!> has three free modes (two translations, a rotation), the lower none.  The
!> contact is the lower top (slave) against the upper bottom (master), a
!> flat of the upper body's whole width.
!>   - H = C R: the upper body translated by (0, 1) opens every gap by 1
!>     (H c = -1 on every row, c the modes' combination of that motion) and
!>     translated by (1, 0) opens none (H c = 0);
!>   - frictionless: the sinking and the tilting press on the flat, the slide
!>     along it does not, so two combinations are held and one is not, and
!>     the unheld one, as a motion R v, is a uniform translation along x;
!>     the flat's polylines do not turn, so tau = 1e-10 (round-off) on both
!>     bodies;
!>   - its load, v'e, is the resultant along x: 0 for a weight on the upper
!>     body (not loaded), 5 for a push of 1 on each of its 5 top nodes
!>     (loaded: no equilibrium);
!>   - with friction the tangential rows hold the slide too: all three held,
!>     held the identity (the modes themselves).
!> e = R'f is checked against the resultant: e'(R't_y) = the total y load,
!> R having orthonormal columns for a body without FIX.
!> The resolution of a curve on a finely meshed flat: the bottom arc of a
!> sector of the disk of radius 1 about c = (0, 1) (60 degrees in 8
!> segments, each turning by pi/24) rests on the top of a block meshed at
!> h = 1/32, the arc the slave.  Its rows turn by pi/24 at 7 nodes, the 33
!> covered flat nodes by 0: pooled, the median would be 0 and tau 1e-10; the
!> rougher side decides, tau = pi/24 for both bodies, and the rotation of the
!> sector about c (every normal passes through c, up to the polygon's
!> defect) is not held: its motion u(x) is normal to x - c at every node, to
!> within that defect.
!> The weight on the sector's top nodes, symmetric about x = 0, does not load
!> it.
program test_mode_support
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh, find_name
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use body, only: body_t
  use contact_set, only: contact_set_t, pair_spec_t, build_contact_set
  use rigid_modes, only: floating_t, find_floating_modes
  use mode_support, only: mode_split_t, split_free_modes
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none

  call run_case(.false., 'weight')
  call run_case(.false., 'side push')
  call run_case(.true., 'weight')
  call arc_on_fine_flat()
  call finish_tests()

contains

  subroutine run_case(friction, load)
    logical, intent(in) :: friction
    character(len=*), intent(in) :: load
    type(body_t) :: bd(2)
    type(diag_t) :: diag
    type(error_t), allocatable :: err
    type(pair_spec_t) :: spec(1)
    type(contact_set_t) :: cs
    type(floating_t) :: fl
    type(mode_split_t) :: sp
    logical, allocatable :: fixed(:)
    real(dp), allocatable :: fext(:), tx(:), ty(:), cx(:), cy(:), motion(:), ident(:,:)
    integer :: i, n, nr, k, n2
    real(dp) :: hscale
    character(len=:), allocatable :: name

    name = trim(merge('friction,    ', 'no friction, ', friction)) // ' ' // load
    call make_rect_mesh(0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 4, 4, 'tri3', 'right', bd(1)%mesh, err)
    if (.not. allocated(err)) call make_rect_mesh(0.0_dp, 1.0_dp, 1.0_dp, 2.0_dp, 4, 4, 'tri3', 'alt', bd(2)%mesh, err)
    call check(.not. allocated(err), name // ': meshes')
    if (allocated(err)) return
    do i = 1, 2
      call finalize_mesh(bd(i)%mesh, 'mode_support', diag)
      call make_isotropic(1000.0_dp, 0.3_dp, .false., bd(i)%law)
    end do
    bd(2)%dof0 = 2 * bd(1)%mesh%nnode
    n2 = bd(2)%mesh%nnode
    n = bd(2)%dof0 + 2 * n2

    ! the lower body's bottom edge held; the upper body free
    allocate(fixed(n), fext(n))
    fixed = .false.
    do i = 1, bd(1)%mesh%nnode
      if (bd(1)%mesh%x(2, i) == 0.0_dp) fixed(2 * i - 1:2 * i) = .true.
    end do
    call find_floating_modes(bd, fixed, fl)
    call check(fl%k == 3 .and. all(fl%mode_body == 2), name // ': three free modes, all of the upper body')
    if (fl%k /= 3) return
    k = fl%k

    spec(1)%slave_body = 1
    spec(1)%slave_bnd = find_name(bd(1)%mesh%bnd, 'top')
    spec(1)%master_body = 2
    spec(1)%master_bnd = find_name(bd(2)%mesh%bnd, 'bottom')
    spec(1)%gap_zero = .true.
    if (friction) spec(1)%mu = 0.3_dp
    call build_contact_set(bd, spec, cs, err)
    call check(.not. allocated(err), name // ': contact set built')
    if (allocated(err)) return
    nr = cs%nrow + cs%ntan

    ! loads on the upper body's top nodes: a weight (0, -1) or a push (1, 0) each
    fext = 0.0_dp
    do i = 1, n2
      if (bd(2)%mesh%x(2, i) /= 2.0_dp) cycle
      if (load == 'weight') then
        fext(bd(2)%dof0 + 2 * i) = -1.0_dp
      else
        fext(bd(2)%dof0 + 2 * i - 1) = 1.0_dp
      end if
    end do

    call split_free_modes(cs, bd, fl, fext, sp)
    call check(size(sp%h, 1) == nr .and. size(sp%h, 2) == k .and. size(sp%e) == k, name // ': H (nrow + ntan, k), e (k)')
    call check(size(sp%held, 2) + size(sp%unheld, 2) == k, name // ': held + unheld = k')

    ! the translations of the upper body as combinations of the modes: c = R't
    allocate(tx(n), ty(n))
    tx = 0.0_dp
    ty = 0.0_dp
    tx(bd(2)%dof0 + 1::2) = 1.0_dp
    ty(bd(2)%dof0 + 2::2) = 1.0_dp
    cx = matmul(transpose(fl%r), tx)
    cy = matmul(transpose(fl%r), ty)
    call check_small(maxval(abs(matmul(fl%r, cy) - ty)), tol_round(8 * n2), name // ': R R''t_y = t_y (t_y a mode)')
    hscale = maxval(abs(sp%h))
    call check_small(maxval(abs(matmul(sp%h(1:cs%nrow, :), cy) + 1.0_dp)), tol_round(8 * n2), &
                     name // ': H c = -1 on every normal row for the lift (0, 1)')
    call check_small(maxval(abs(matmul(sp%h(1:cs%nrow, :), cx))), tol_round(8 * n2, hscale), &
                     name // ': H c = 0 on the normal rows for the slide (1, 0)')
    call check_small(dot_product(sp%e, cy) - sum(fext(bd(2)%dof0 + 2::2)), tol_round(8 * n2, real(n2, dp)), &
                     name // ': e''(R''t_y) = the total y load')
    call check(all(sp%tau == 1.0e-10_dp), name // ': tau = 1e-10 on a flat contact (no turning)')

    if (friction) then
      call check(size(sp%held, 2) == 3 .and. size(sp%unheld, 2) == 0, name // ': all three held')
      allocate(ident(k, k), source=0.0_dp)
      do i = 1, k
        ident(i, i) = 1.0_dp
      end do
      if (size(sp%held, 2) == 3) call check(all(sp%held == ident), name // ': held = the modes themselves')
      return
    end if

    call check(size(sp%held, 2) == 2 .and. size(sp%unheld, 2) == 1, name // ': two held (sinking, tilting), one not')
    if (size(sp%unheld, 2) /= 1) return
    call check(sp%unheld_body(1) == 2, name // ': the unheld combination is of the upper body')
    ! as a motion, R v: v has a unit rms motion (its scaled length 1), so
    ! R v = +-t_x, the unit slide along x (R's columns orthonormal)
    motion = matmul(fl%r, sp%unheld(:, 1))
    call check_small(maxval(abs(motion - sign(1.0_dp, motion(bd(2)%dof0 + 1)) * tx)), tol_round(8 * n2), &
                     name // ': the unheld motion R v = +-(1, 0) at every node (the slide)')
    call check_small(maxval(abs(matmul(sp%h, sp%unheld(:, 1)))), tol_round(8 * n2, hscale), &
                     name // ': H v = 0 for the unheld v')
    ! the held ones: H held of full rank 2 (its Gram determinant well above 0)
    associate(hh => matmul(sp%h, sp%held))
      call check(abs(determinant2(matmul(transpose(hh), hh))) > 1.0e-6_dp * sum(hh**2)**2, &
                 name // ': H times the held basis has rank 2')
    end associate
    ! the load along it: v'e = +-t_x'f, the resultant along x
    call check_small(abs(dot_product(sp%unheld(:, 1), sp%e)) - abs(sum(fext(bd(2)%dof0 + 1::2))), &
                     tol_round(8 * n2, real(n2, dp)), name // ': the load along the slide is the x resultant')
    if (load == 'weight') then
      call check(.not. sp%loaded(1), name // ': the weight does not load the slide')
    else
      call check(sp%loaded(1), name // ': the push loads the slide (no equilibrium)')
    end if
  end subroutine run_case

  !> The sector's arc on the fine flat of the header.
  subroutine arc_on_fine_flat()
    real(dp), parameter :: pi = acos(-1.0_dp), span = pi / 3.0_dp, thick = 0.25_dp, c(2) = [0.0_dp, 1.0_dp]
    character(len=*), parameter :: name = 'arc on a fine flat'
    type(body_t) :: bd(2)
    type(diag_t) :: diag
    type(error_t), allocatable :: err
    type(pair_spec_t) :: spec(1)
    type(contact_set_t) :: cs
    type(floating_t) :: fl
    type(mode_split_t) :: sp
    logical, allocatable :: fixed(:)
    real(dp), allocatable :: fext(:), motion(:)
    real(dp) :: theta, r, radial
    integer :: i, n, n2, b

    call make_rect_mesh(-1.0_dp, -0.5_dp, 1.0_dp, 0.0_dp, 64, 4, 'tri3', 'right', bd(1)%mesh, err)
    if (.not. allocated(err)) call make_rect_mesh(0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 8, 2, 'tri3', 'right', bd(2)%mesh, err)
    call check(.not. allocated(err), name // ': meshes')
    if (allocated(err)) return
    ! the unit square (u, v) onto the sector: theta = -pi/2 + (u - 1/2) span,
    ! radius 1 - thick v about c, so that v = 0 is the arc (the 'bottom')
    do i = 1, bd(2)%mesh%nnode
      theta = -0.5_dp * pi + (bd(2)%mesh%x(1, i) - 0.5_dp) * span
      r = 1.0_dp - thick * bd(2)%mesh%x(2, i)
      bd(2)%mesh%x(:, i) = c + r * [cos(theta), sin(theta)]
    end do
    do b = 1, 2
      call finalize_mesh(bd(b)%mesh, 'mode_support', diag)
      call make_isotropic(1000.0_dp, 0.3_dp, .false., bd(b)%law)
    end do
    call check(diag%count == 0, name // ': the sector is a valid mesh')
    if (diag%count /= 0) return
    bd(2)%dof0 = 2 * bd(1)%mesh%nnode
    n2 = bd(2)%mesh%nnode
    n = bd(2)%dof0 + 2 * n2
    allocate(fixed(n), fext(n))
    fixed = .false.
    do i = 1, bd(1)%mesh%nnode
      if (bd(1)%mesh%x(2, i) == -0.5_dp) fixed(2 * i - 1:2 * i) = .true.
    end do
    call find_floating_modes(bd, fixed, fl)
    call check(fl%k == 3, name // ': the sector floats (three modes)')
    if (fl%k /= 3) return
    spec(1)%slave_body = 2
    spec(1)%slave_bnd = find_name(bd(2)%mesh%bnd, 'bottom')
    spec(1)%master_body = 1
    spec(1)%master_bnd = find_name(bd(1)%mesh%bnd, 'top')
    call build_contact_set(bd, spec, cs, err)
    call check(.not. allocated(err), name // ': contact set built')
    if (allocated(err)) return
    fext = 0.0_dp
    do i = 1, n2
      if (abs(norm2(bd(2)%mesh%x(:, i) - c) - (1.0_dp - thick)) < 1.0e-12_dp) fext(bd(2)%dof0 + 2 * i) = -1.0_dp
    end do
    call split_free_modes(cs, bd, fl, fext, sp)
    call check_small(maxval(abs(sp%tau - span / 8.0_dp)) / (span / 8.0_dp), tol_round(64), &
                     name // ': tau = the arc''s turning angle pi/24 (the rougher side), on both bodies')
    call check(size(sp%unheld, 2) == 1, name // ': one combination not held')
    if (size(sp%unheld, 2) /= 1) return
    motion = matmul(fl%r, sp%unheld(:, 1))
    radial = 0.0_dp
    do i = 1, n2
      radial = max(radial, abs(dot_product(motion(bd(2)%dof0 + 2 * i - 1:bd(2)%dof0 + 2 * i), bd(2)%mesh%x(:, i) - c)))
    end do
    ! v is known to within its singular value over the held ones' (Wedin),
    ! of the order of the polygon's defect: the radial part of its motion is
    ! below the turning angle, where a slide along x would give 1
    call check_small(radial / maxval(abs(motion)), span / 8.0_dp, &
                     name // ': the unheld motion is the rotation about the arc''s centre (|u . (x - c)| < tau |u|)')
    call check(.not. sp%loaded(1), name // ': the symmetric weight does not load it')
  end subroutine arc_on_fine_flat

  pure real(dp) function determinant2(a)
    real(dp), intent(in) :: a(2, 2)
    determinant2 = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
  end function determinant2

end program test_mode_support
