!> contact_set: the rows of B u <= g built by build_contact_set for two
!> bodies meshed each on its own (a lower square, 6 x 6, and an upper one, 4 x
!> 4 or 6 x 6), the lower top the slave, the upper bottom the master, checked
!> against invariants of the method rather than against stored numbers:
!>   - pi_h^1 reproduces constants (Ben Belgacem, Hild, Laborde: v - pi_h^1 v
!>     is orthogonal to the multipliers, and a constant is its own projection),
!>     so a translation of both bodies together gives B u = 0, and a
!>     translation of the upper body by (0, -d) gives B u = d on every row
!>     (the penetration d), on conforming and non-conforming meshes alike;
!>   - with the upper body lifted by h, the initial gaps are g = h;
!>   - on a flat slave every row's normal is (0, 1): the slave entries of B
!>     are 0 on the x dofs and sum to 1 on the y dofs of a row;
!>   - a pair with friction has one tangential row per normal row, and a
!>     sliding of the upper body by (s, 0) gives T u = s (t = (-n_y, n_x));
!>   - one row per slave node, the contact dofs ascending and distinct.
!> Checks compare with tolerances scaled by the unit roundoff (n eps).
program test_contact_set
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh, find_name
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use body, only: body_t
  use contact_set, only: contact_set_t, pair_spec_t, build_contact_set
  use contact_condensation, only: constraint_values
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none
  real(dp), parameter :: threshold = 30.0_dp

  call run_case(6, 0.0_dp, .false., 'conforming')
  call run_case(4, 0.0_dp, .false., 'non-conforming')
  call run_case(4, 0.05_dp, .false., 'non-conforming, gap 0.05')
  call run_case(4, 0.0_dp, .true., 'non-conforming, friction')
  call finish_tests()

contains

  !> One pair: the lower square [0,1]^2 (6 x 6, slave: its top) and the upper
  !> square [0,1] x [1+h, 2+h] (m x m, master: its bottom).
  subroutine run_case(m, h, friction, name)
    integer, intent(in) :: m
    real(dp), intent(in) :: h
    logical, intent(in) :: friction
    character(len=*), intent(in) :: name
    type(body_t) :: bd(2)
    type(diag_t) :: diag
    type(error_t), allocatable :: err
    type(pair_spec_t) :: spec(1)
    type(contact_set_t) :: cs
    real(dp), allocatable :: u(:), bu(:), sx(:), sy(:)
    integer :: i, n, r, k, nslave
    real(dp) :: eps, d

    eps = epsilon(1.0_dp)
    call make_rect_mesh(0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 6, 6, 'tri3', 'right', bd(1)%mesh, err)
    if (.not. allocated(err)) call make_rect_mesh(0.0_dp, 1.0_dp + h, 1.0_dp, 2.0_dp + h, m, m, 'tri3', 'alt', &
                                                  bd(2)%mesh, err)
    call check(.not. allocated(err), name // ': meshes')
    if (allocated(err)) return
    do i = 1, 2
      call finalize_mesh(bd(i)%mesh, 'contact_set', diag)
      call make_isotropic(1000.0_dp, 0.3_dp, .false., bd(i)%law)
    end do
    bd(2)%dof0 = 2 * bd(1)%mesh%nnode
    n = bd(2)%dof0 + 2 * bd(2)%mesh%nnode

    spec(1)%slave_body = 1
    spec(1)%slave_bnd = find_name(bd(1)%mesh%bnd, 'top')
    spec(1)%master_body = 2
    spec(1)%master_bnd = find_name(bd(2)%mesh%bnd, 'bottom')
    spec(1)%gap_zero = h == 0.0_dp
    if (friction) spec(1)%mu = 0.3_dp
    call build_contact_set(bd, spec, cs, err)
    call check(.not. allocated(err), name // ': contact set built')
    if (allocated(err)) then
      print '(a)', '  ' // err%message
      return
    end if

    ! nodes on a side of a unit-size mesh: their coordinate is exact to round-off
    nslave = count(abs(bd(1)%mesh%x(2, :) - 1.0_dp) < tol_round(16))
    call check(cs%nrow == nslave, name // ': one row per slave node (' // int_to_str(cs%nrow) // ' of ' // &
               int_to_str(nslave) // ')')
    call check(cs%ntan == merge(cs%nrow, 0, friction), name // ': tangential rows with friction only')
    call check(all(cs%cdof(2:) > cs%cdof(:cs%ncdof - 1)) .and. cs%cdof(1) >= 1 .and. cs%cdof(cs%ncdof) <= n, &
               name // ': contact dofs ascending, distinct, in range')

    ! a translation of both bodies: no relative motion
    allocate(u(n), bu(cs%nrow + cs%ntan))
    u(1::2) = 0.37_dp
    u(2::2) = -0.81_dp
    call constraint_values(cs, u, bu)
    call check_small(maxval(abs(bu)) / (0.81_dp * n * eps), threshold, &
                     name // ': |B u| / (|u| n eps) for a common translation')

    ! the upper body moved down by d: penetration d on every normal row
    d = 0.01_dp
    u = 0.0_dp
    u(bd(2)%dof0 + 2::2) = -d
    call constraint_values(cs, u, bu)
    call check_small(maxval(abs(bu(:cs%nrow) - d)) / (d * n * eps), threshold, &
                     name // ': |B u - d| / (d n eps) for the upper body moved by (0, -d)')

    ! the initial gaps
    call check_small(maxval(abs(cs%g - h)) / (n * eps), threshold, name // ': |g - h| / (n eps)')

    ! the normal of a flat slave: (0, 1) in each row's slave entries
    allocate(sx(cs%nrow), sy(cs%nrow))
    sx = 0.0_dp
    sy = 0.0_dp
    do r = 1, cs%nrow
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        if (cs%cdof(cs%bcol(k)) > bd(2)%dof0) cycle
        if (mod(cs%cdof(cs%bcol(k)), 2) == 1) then
          sx(r) = sx(r) + cs%bval(k)
        else
          sy(r) = sy(r) + cs%bval(k)
        end if
      end do
    end do
    call check_small(maxval(abs(sx)) / eps + maxval(abs(sy - 1.0_dp)) / eps, threshold, &
                     name // ': slave normal (0, 1) on every row')

    if (friction) then
      u = 0.0_dp
      u(bd(2)%dof0 + 1::2) = 0.02_dp
      call constraint_values(cs, u, bu)
      call check_small(maxval(abs(bu(cs%nrow + 1:) - 0.02_dp)) / (0.02_dp * n * eps), threshold, &
                       name // ': |T u - s| / (s n eps) for the upper body sliding by (s, 0)')
      call check_small(maxval(abs(bu(:cs%nrow))) / (0.02_dp * n * eps), threshold, &
                       name // ': sliding leaves B u = 0')
    end if
  end subroutine run_case

end program test_contact_set
