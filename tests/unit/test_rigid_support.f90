!> rigid_support: the free directions of a RIGID obstacle and which of them
!> contact holds, on a case worked by hand.  A flat punch, the line from
!> (-0.5, 1) to (1.5, 1) with its reference point at (0.5, 1) and size 2,
!> rests on the top of a square [0,1]^2 (the slave, 4 x 4 elements): row i,
!> at slave node x_i, has the direction n_i = (0, 1), so its entries on the
!> punch's dofs (u_x, u_y, theta) are -(0, 1, x_i - 0.5) (rigid_obstacle's
!> -[n_x, n_y, n . (-(y_i - y_r), x_i - x_r)]).  Hence:
!>   - H_r is that, entry by entry;
!>   - frictionless, all three free: the sinking and the tilting are held,
!>     the slide along the flat is not; the unheld combination is (+-1, 0, 0)
!>     and reads 'translation along (1.0000, 0.0000)' (or -1);
!>   - a downward FORCE leaves the slide unloaded, a sideways one loads it;
!>   - with friction the tangential rows hold the slide: all three held;
!>   - theta prescribed: two free dofs (u_x, u_y), comp = (1, 2);
!>   - pulled_rigid: the rows push the punch up only (H_r' mu = -(sum mu,
!>     sum mu (x_i - 0.5)) with mu >= 0), so a FORCE (0, -1) with a moment M
!>     is balanced while |M| <= 1/2 (the lever of the half width) and pulls
!>     the punch off beyond; a FORCE (0, +1) pulls it off with the whole load
!>     unbalanced, resid = (0, 1, 0).
!> The same cases at other units of length (every length, the punch's size
!> among them, times L; forces times L, moments times L^2, as a change of
!> unit with the stresses kept): the decisions must not change.  The
!> rotation's column is H_theta / L (phi = L theta), so its singular value
!> stays that of a translation; scaled by L instead (the old rule) the slide
!> and the sinking looked unheld at L = 1e5 and the tilting at L = 1e-4.
program test_rigid_support
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh, find_name
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use body, only: body_t
  use contact_set, only: contact_set_t, pair_spec_t, build_contact_set
  use rigid_obstacle, only: rigid_shape_t, shape_line
  use rigid_support, only: rigid_split_t, split_rigid_modes, rigid_direction, pulled_rigid
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none
  character(len=*), parameter :: dof_names(3) = ['u_x  ', 'u_y  ', 'theta']
  real(dp), parameter :: scales(3) = [1.0e-4_dp, 1.0e3_dp, 1.0e5_dp]
  character(len=32) :: lname
  integer :: k

  call run_case(.false., [.false., .false., .false.], [0.0_dp, -1.0_dp, 0.0_dp], 'free, down')
  call run_case(.false., [.false., .false., .false.], [1.0_dp, -1.0_dp, 0.0_dp], 'free, sideways')
  call run_case(.true., [.false., .false., .false.], [0.0_dp, -1.0_dp, 0.0_dp], 'free, friction')
  call run_case(.false., [.false., .false., .true.], [0.0_dp, -1.0_dp, 0.0_dp], 'theta fixed')
  call run_case(.false., [.false., .false., .false.], [0.0_dp, -1.0_dp, 0.45_dp], 'free, moment 0.45')
  call run_case(.false., [.false., .false., .false.], [0.0_dp, -1.0_dp, 0.55_dp], 'free, moment 0.55')
  call run_case(.false., [.false., .false., .false.], [0.0_dp, 1.0_dp, 0.0_dp], 'free, up')
  do k = 1, size(scales)
    write(lname, '(a, es7.0)') ', L = ', scales(k)
    call run_case(.false., [.false., .false., .false.], [0.0_dp, -1.0_dp, 0.0_dp], 'free, down' // trim(lname), scales(k))
    call run_case(.false., [.false., .false., .false.], [1.0_dp, -1.0_dp, 0.0_dp], 'free, sideways' // trim(lname), &
                  scales(k))
    call run_case(.false., [.false., .false., .false.], [0.0_dp, -1.0_dp, 0.45_dp], 'free, moment 0.45' // trim(lname), &
                  scales(k))
    call run_case(.false., [.false., .false., .false.], [0.0_dp, -1.0_dp, 0.55_dp], 'free, moment 0.55' // trim(lname), &
                  scales(k))
    call run_case(.false., [.false., .false., .false.], [0.0_dp, 1.0_dp, 0.0_dp], 'free, up' // trim(lname), scales(k))
  end do
  call finish_tests()

contains

  !> The square, the punch with the given prescribed directions (fix) and
  !> FORCE (force: F_x, F_y, moment), and the checks that apply; at the unit
  !> of length scale (default 1): lengths times it, the force times it, the
  !> moment times its square.
  subroutine run_case(friction, fix, force0, name, scale)
    logical, intent(in) :: friction, fix(3)
    real(dp), intent(in) :: force0(3)
    character(len=*), intent(in) :: name
    real(dp), intent(in), optional :: scale
    type(body_t) :: bd(1)
    type(diag_t) :: diag
    type(error_t), allocatable :: err
    type(pair_spec_t) :: spec(1)
    type(contact_set_t) :: cs
    type(rigid_split_t) :: rs
    type(rigid_shape_t) :: sh
    logical, allocatable :: fixed(:)
    real(dp), allocatable :: fext(:), expect(:,:)
    real(dp) :: resid(3), xi, el, force(3)
    integer :: i, n, r, j, owner, nfree
    logical :: pulled
    character(len=:), allocatable :: words

    el = 1.0_dp
    if (present(scale)) el = scale
    force = force0 * [el, el, el**2]
    call make_rect_mesh(0.0_dp, 0.0_dp, el, el, 4, 4, 'tri3', 'right', bd(1)%mesh, err)
    call check(.not. allocated(err), name // ': mesh')
    if (allocated(err)) return
    call finalize_mesh(bd(1)%mesh, 'rigid_support', diag)
    call make_isotropic(1000.0_dp, 0.3_dp, .false., bd(1)%law)

    sh%name = 'punch'
    sh%kind = shape_line
    sh%pt = reshape([-0.5_dp, 1.0_dp, 1.5_dp, 1.0_dp], [2, 2]) * el
    sh%ref = [0.5_dp, 1.0_dp] * el
    sh%length = 2.0_dp * el
    sh%dof0 = 2 * bd(1)%mesh%nnode
    n = sh%dof0 + 3

    spec(1)%slave_body = 1
    spec(1)%slave_bnd = find_name(bd(1)%mesh%bnd, 'top')
    spec(1)%rigid = 1
    spec(1)%shape = sh
    spec(1)%gap_zero = .true.
    if (friction) spec(1)%mu = 0.3_dp
    call build_contact_set(bd, spec, cs, err)
    call check(.not. allocated(err), name // ': contact set built')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      return
    end if

    allocate(fixed(n), fext(n))
    fixed = .false.
    do i = 1, bd(1)%mesh%nnode
      if (bd(1)%mesh%x(2, i) == 0.0_dp) fixed(2 * i - 1:2 * i) = .true.
    end do
    fixed(sh%dof0 + 1:sh%dof0 + 3) = fix
    fext = 0.0_dp
    fext(sh%dof0 + 1:sh%dof0 + 3) = force
    call split_rigid_modes(cs, [sh], fixed, fext, rs)

    nfree = count(.not. fix)
    call check(rs%k == nfree, name // ': one free direction per dof not prescribed')
    if (rs%k /= nfree) return
    call check(all(rs%comp == pack([1, 2, 3], .not. fix)) .and. all(rs%owner == 1) .and. &
               all(rs%dof == sh%dof0 + rs%comp), name // ': the free directions, in dof order')
    call check(all(rs%e == pack(force, .not. fix)), name // ': e_r = the FORCE on them')

    ! H_r on the normal rows, by hand: -(0, 1, x_i - 0.5)
    allocate(expect(cs%nrow, 3))
    do r = 1, cs%nrow
      xi = cs%pair(1)%xs(1, cs%row_node(r))
      expect(r, :) = -[0.0_dp, 1.0_dp, xi - 0.5_dp * el]
    end do
    call check(cs%nrow == 5, name // ': a row at each of the 5 slave nodes')
    do j = 1, rs%k
      call check_small(maxval(abs(rs%h(1:cs%nrow, j) - expect(:, rs%comp(j)))), tol_round(8, merge(el, 1.0_dp, j == 3)), &
                       name // ': H_r column ' // trim(dof_names(rs%comp(j))) // ' by hand')
    end do

    if (friction) then
      call check(size(rs%held, 2) == 3 .and. size(rs%unheld, 2) == 0, name // ': all three held')
      return
    end if
    call check(size(rs%held, 2) == nfree - 1 .and. size(rs%unheld, 2) == 1, &
               name // ': every free direction held but the slide')
    if (size(rs%unheld, 2) /= 1) return
    ! the unheld combination in the dofs' units: the slide, u_x alone
    call check_small(maxval(abs(abs(rs%unheld(:, 1)) - merge(1.0_dp, 0.0_dp, rs%comp == 1))), tol_round(8), &
                     name // ': the unheld combination is the slide (+-1, 0, 0)')
    call check(rs%unheld_owner(1) == 1, name // ': of the punch')
    words = rigid_direction(rs, rs%unheld(:, 1))
    call check(words == 'translation along (1.0000, 0.0000)' .or. words == 'translation along (-1.0000, 0.0000)', &
               name // ': described as the translation along (+-1, 0): ' // words)
    call check(rs%loaded(1) .eqv. (force(1) /= 0.0_dp), name // ': the slide loaded exactly when F_x /= 0')

    ! F_y <= 0 is balanced by sum mu = -F_y, its moment while |M| <= -F_y / 2;
    ! F_x never (no row sees u_x)
    call pulled_rigid(rs, owner, resid)
    pulled = force(1) /= 0.0_dp .or. force(2) > 0.0_dp .or. abs(force(3)) > -0.5_dp * el * force(2)
    call check(owner == merge(1, 0, pulled), name // ': ' // trim(merge('pulled off its contacts   ', &
                                                                      'balanced by its contacts  ', pulled)))
    if (force(2) > 0.0_dp .and. owner == 1) &
      call check_small(maxval(abs(resid - [0.0_dp, force(2), 0.0_dp])), tol_round(8, el), &
                       name // ': all of the lift is unbalanced, resid = (0, 1, 0)')
  end subroutine run_case

end program test_rigid_support
