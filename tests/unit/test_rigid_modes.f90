!> rigid_modes: the free rigid modes of one body and the dofs pinned to
!> factorize K^#, on a 4 x 3 rectangle (P1 and Q1) held by FIX on nothing,
!> one point, one point in x only, one edge, one edge in x only.  Checks, in
!> LAPACK's manner (a computed ratio below a threshold of 30):
!>   - the number of modes: 3, 1, 2, 0, 1;
!>   - K R = 0 to round-off: ||K R||_inf / (||K||_inf ||R||_inf n eps), K the
!>     stiffness of the whole body (no dof held), R zero on the held dofs;
!>   - the columns of R have unit length, and R'R = I where the modes are
!>     orthogonal by construction (no FIX: the translations and the rotation
!>     about the centroid; a single mode);
!>   - the pinned dofs are well conditioned: sigma_min(R(pin, :)) >=
!>     0.1 / sqrt(n) (bounded below by |det| / ||R(pin, :)||_F^(k-1)), and
!>     K with the held and the pinned dofs removed is positive definite and
!>     gives a generalized inverse: K K^# b = b for b = K v in the range of
!>     K, to round-off.
program test_rigid_modes
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use body, only: body_t, number_equations, build_pattern, assemble_stiffness
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, factorize, solve
  use rigid_modes, only: floating_t, find_floating_modes
  use testing, only: check, check_small, finish_tests, dense_symmetric, tol_round
  implicit none
  real(dp), parameter :: threshold = 30.0_dp
  character(len=*), parameter :: holds(5) = ['none    ', 'point   ', 'point ux', 'edge    ', 'edge ux ']
  integer, parameter :: modes_expected(5) = [3, 1, 2, 0, 1]
  integer :: h, quads

  do quads = 0, 1
    do h = 1, size(holds)
      call run_case(quads == 1, h)
    end do
  end do
  call finish_tests()

contains

  subroutine run_case(quads, h)
    logical, intent(in) :: quads
    integer, intent(in) :: h
    type(body_t) :: bd(1)
    type(diag_t) :: diag
    type(floating_t) :: fl
    type(csc_t) :: k, kp
    type(factor_t) :: f
    type(error_t), allocatable :: err
    logical, allocatable :: fixed(:), held(:)
    integer, allocatable :: eq(:), eqp(:)
    real(dp), allocatable :: kd(:,:), kr(:,:), zero(:), v(:), b(:), x(:,:), rhs(:,:), u(:), rp(:,:)
    integer :: n, nfree, i, kk
    real(dp) :: eps, ratio, smin
    character(len=:), allocatable :: name

    name = merge('Q1', 'P1', quads) // ' FIX ' // trim(holds(h))
    eps = epsilon(1.0_dp)
    call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.0_dp, 4, 3, merge('quad4', 'tri3 ', quads), 'alt', bd(1)%mesh, err)
    call finalize_mesh(bd(1)%mesh, 'modes', diag)
    call make_isotropic(1000.0_dp, 0.3_dp, .false., bd(1)%law)
    n = 2 * bd(1)%mesh%nnode
    allocate(fixed(n))
    fixed = .false.
    do i = 1, bd(1)%mesh%nnode
      associate(xy => bd(1)%mesh%x(:, i))
        select case (trim(holds(h)))
        case ('point')
          if (i == 1) fixed(2 * i - 1:2 * i) = .true.
        case ('point ux')
          if (i == 1) fixed(2 * i - 1) = .true.
        case ('edge')
          ! nodes on a side of a unit-size mesh: their coordinate is exact to round-off
          if (abs(xy(1)) < tol_round(16)) fixed(2 * i - 1:2 * i) = .true.
        case ('edge ux')
          if (abs(xy(1)) < tol_round(16)) fixed(2 * i - 1) = .true.
        end select
      end associate
    end do
    call find_floating_modes(bd, fixed, fl)
    call check(fl%k == modes_expected(h), name // ': number of free modes')
    if (fl%k /= modes_expected(h)) return
    if (fl%k == 0) return
    call check(all(fl%mode_body == 1) .and. size(fl%r, 1) == n .and. size(fl%pin) == fl%k, &
               name // ': modes of body 1, one pinned dof each')
    call check(all(abs(fl%r(pack([(i, i = 1, n)], fixed), :)) == 0.0_dp), name // ': R = 0 on the held dofs')
    call check(.not. any(fixed(fl%pin)), name // ': pinned dofs are free dofs')

    ! K of the whole body, dense
    allocate(zero(n), held(n))
    zero = 0.0_dp
    held = .false.
    call number_equations(held, eq, nfree)
    call build_pattern(bd, eq, nfree, k, err)
    allocate(rhs(nfree, 1))
    rhs = 0.0_dp
    call assemble_stiffness(bd, eq, zero, k, rhs(:, 1))
    call dense_symmetric(k%colptr, k%rowind, k%val, kd)
    kr = matmul(kd, fl%r)
    ratio = maxval(abs(kr)) / (maxval(sum(abs(kd), dim=2)) * maxval(abs(fl%r)) * n * eps)
    call check_small(ratio, threshold, name // ': ||K R||_inf / (||K||_inf ||R||_inf n eps)')
    ratio = maxval(abs(norm2(fl%r, dim=1) - 1.0_dp)) / (n * eps)
    call check_small(ratio, threshold, name // ': columns of R of unit length')
    if (fl%k == 1 .or. fl%k == 3) then
      ratio = maxval(abs(matmul(transpose(fl%r), fl%r) - identity(fl%k))) / (n * eps)
      call check_small(ratio, threshold, name // ': R''R = I')
    end if

    ! the pinned rows of R: well conditioned.  sigma_min >= |det| /
    ! sigma_max^(k-1) >= |det| / ||.||_F^(k-1), a lower bound with no SVD
    ! (LAPACK's SVD may trap in the debug build: it relies on IEEE overflow)
    rp = fl%r(fl%pin, :)
    kk = fl%k
    smin = abs(determinant(rp)) / norm2(rp)**(kk - 1)
    call check(smin >= 0.1_dp / sqrt(real(n, dp)), name // ': sigma_min(R(pin, :)) >= 0.1 / sqrt(n)')

    ! K^#: K without the held and the pinned dofs; K K^# b = b for b = K v
    held = fixed
    held(fl%pin) = .true.
    call number_equations(held, eqp, nfree)
    call build_pattern(bd, eqp, nfree, kp, err)
    deallocate(rhs)
    allocate(rhs(nfree, 1), x(nfree, 1))
    rhs = 0.0_dp
    call assemble_stiffness(bd, eqp, zero, kp, rhs(:, 1))
    call factorize(f, kp, err)
    call check(.not. allocated(err), name // ': K with the pinned dofs held is positive definite')
    if (allocated(err)) return
    allocate(v(n), u(n))
    v = [(sin(1.3_dp * i) + 0.5_dp, i = 1, n)]
    where (fixed) v = 0.0_dp
    b = matmul(kd, v)                               ! in the range of K; zero work on R
    do i = 1, n
      if (eqp(i) > 0) rhs(eqp(i), 1) = b(i)
    end do
    call solve(f, rhs, x, err)
    u = 0.0_dp
    do i = 1, n
      if (eqp(i) > 0) u(i) = x(eqp(i), 1)
    end do
    ! the residual on the dofs that are not held by FIX (the reactions there are free)
    ratio = maxval(abs(pack(matmul(kd, u) - b, .not. fixed))) / &
            (maxval(sum(abs(kd), dim=2)) * maxval(abs(u)) * n * eps)
    call check_small(ratio, threshold, name // ': K K^# b = b for b in range(K)')
  end subroutine run_case

  !> det(a) of a 1 x 1, 2 x 2 or 3 x 3 matrix.
  pure real(dp) function determinant(a) result(d)
    real(dp), intent(in) :: a(:,:)
    select case (size(a, 1))
    case (1)
      d = a(1, 1)
    case (2)
      d = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
    case default
      d = a(1, 1) * (a(2, 2) * a(3, 3) - a(2, 3) * a(3, 2)) - a(1, 2) * (a(2, 1) * a(3, 3) - a(2, 3) * a(3, 1)) &
          + a(1, 3) * (a(2, 1) * a(3, 2) - a(2, 2) * a(3, 1))
    end select
  end function determinant

  pure function identity(m) result(a)
    integer, intent(in) :: m
    real(dp) :: a(m, m)
    integer :: i
    a = 0.0_dp
    do i = 1, m
      a(i, i) = 1.0_dp
    end do
  end function identity

end program test_rigid_modes
