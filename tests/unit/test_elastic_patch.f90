!> Patch test of plane elasticity: a linear displacement field prescribed on
!> the boundary of a distorted mesh is reproduced inside to round-off, with the
!> exact constant stress, for P1 and Q1, plane strain and plane stress,
!> isotropic and rotated orthotropic laws.  Also: the internal forces of the
!> solution balance (sum of reactions = 0, moment = 0).
program test_elastic_patch
  use kinds, only: dp
  use diagnostics, only: diag_t, error_t
  use mesh, only: mesh_t, finalize_mesh
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic, make_orthotropic
  use body, only: body_t, number_equations, build_pattern, assemble_stiffness, element_response
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, factorize, solve
  use testing, only: check, check_small, finish_tests
  implicit none
  integer :: ielem, ilaw
  character(len=80) :: name
  character(len=*), parameter :: elems(3) = ['tri3 right', 'tri3 alt  ', 'quad4     ']
  character(len=*), parameter :: laws(4) = ['iso strain  ', 'iso stress  ', 'ortho strain', 'ortho stress']

  do ielem = 1, 3
    do ilaw = 1, 4
      name = 'patch ' // trim(elems(ielem)) // ' ' // trim(laws(ilaw))
      call run_patch(ielem, ilaw, trim(name))
    end do
  end do
  call finish_tests()

contains

  subroutine run_patch(ielem, ilaw, name)
    integer, intent(in) :: ielem, ilaw
    character(len=*), intent(in) :: name
    type(body_t) :: bd(1)
    type(diag_t) :: diag
    type(csc_t) :: k
    type(factor_t) :: f
    type(error_t), allocatable :: err
    logical, allocatable :: fixed(:)
    integer, allocatable :: eq(:)
    real(dp), allocatable :: ubar(:), rhs(:,:), x(:,:), u(:), fint(:), stress(:,:), vm(:)
    real(dp) :: a(3), b(3), eps(3), sexact(3), h, r(2), moment, umax
    integer :: n, nfree, i, nx, ny, ix, iy
    logical :: boundary

    nx = 5; ny = 4
    if (ielem == 1) call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.5_dp, nx, ny, .false., 'right', bd(1)%mesh, err)
    if (ielem == 2) call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.5_dp, nx, ny, .false., 'alt', bd(1)%mesh, err)
    if (ielem == 3) call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.5_dp, nx, ny, .true., 'right', bd(1)%mesh, err)
    ! distort the interior nodes (deterministic pseudo-random shifts up to 0.25 h)
    h = 0.375_dp
    do i = 1, bd(1)%mesh%nnode
      ix = mod(i - 1, nx + 1); iy = (i - 1) / (nx + 1)
      if (ix == 0 .or. ix == nx .or. iy == 0 .or. iy == ny) cycle
      bd(1)%mesh%x(:, i) = bd(1)%mesh%x(:, i) + 0.25_dp * h * [sin(7.1_dp * i), cos(3.3_dp * i)]
    end do
    call finalize_mesh(bd(1)%mesh, 'patch', diag)
    call check(diag%count == 0, name // ': distorted mesh valid')
    select case (ilaw)
    case (1)
      call make_isotropic(1000.0_dp, 0.3_dp, .false., bd(1)%law)
    case (2)
      call make_isotropic(1000.0_dp, 0.3_dp, .true., bd(1)%law)
    case (3)
      call make_orthotropic(5000.0_dp, 800.0_dp, 800.0_dp, 0.28_dp, 0.28_dp, 0.4_dp, 300.0_dp, 30.0_dp, .false., bd(1)%law)
    case default
      call make_orthotropic(5000.0_dp, 800.0_dp, 800.0_dp, 0.28_dp, 0.28_dp, 0.4_dp, 300.0_dp, -50.0_dp, .true., bd(1)%law)
    end select
    if (ilaw == 2 .or. ilaw == 4) bd(1)%thick = 0.7_dp
    ! u = (a1 + a2 x + a3 y, b1 + b2 x + b3 y)
    a = [1.0e-3_dp, 2.0e-3_dp, -1.5e-3_dp]
    b = [-2.0e-3_dp, 0.5e-3_dp, 3.0e-3_dp]
    n = 2 * bd(1)%mesh%nnode
    allocate(fixed(n), ubar(n), u(n), fint(n))
    do i = 1, bd(1)%mesh%nnode
      associate(xy => bd(1)%mesh%x(:, i))
        ubar(2 * i - 1) = a(1) + a(2) * xy(1) + a(3) * xy(2)
        ubar(2 * i) = b(1) + b(2) * xy(1) + b(3) * xy(2)
        boundary = abs(xy(1)) < 1e-12_dp .or. abs(xy(1) - 2) < 1e-12_dp .or. abs(xy(2)) < 1e-12_dp &
                   .or. abs(xy(2) - 1.5_dp) < 1e-12_dp
      end associate
      fixed(2 * i - 1:2 * i) = boundary
    end do
    call number_equations(fixed, eq, nfree)
    call build_pattern(bd, eq, nfree, k, err)
    allocate(rhs(nfree, 1), x(nfree, 1))
    rhs = 0.0_dp
    call assemble_stiffness(bd, eq, ubar, k, rhs(:, 1))
    call factorize(f, k, err)
    call check(.not. allocated(err), name // ': factorized')
    if (allocated(err)) return
    call solve(f, rhs, x)
    u = ubar
    do i = 1, n
      if (eq(i) > 0) u(i) = x(eq(i), 1)
    end do
    umax = maxval(abs(ubar))
    call check_small(maxval(abs(u - ubar)) / umax, 1.0e-12_dp, name // ': displacement exact')
    allocate(stress(3, bd(1)%mesh%nelem), vm(bd(1)%mesh%nelem))
    call element_response(bd, u, fint, stress, vm)
    eps = [a(2), b(3), a(3) + b(2)]
    sexact = matmul(bd(1)%law%d, eps)
    call check_small(maxval(abs(stress - spread(sexact, 2, bd(1)%mesh%nelem))) / maxval(abs(sexact)), 1.0e-11_dp, &
                     name // ': stress exact')
    r = [sum(fint(1::2)), sum(fint(2::2))]
    moment = sum(bd(1)%mesh%x(1, :) * fint(2::2) - bd(1)%mesh%x(2, :) * fint(1::2))
    call check_small(maxval(abs([r, moment])) / maxval(abs(fint)), 1.0e-12_dp, name // ': reactions in equilibrium')
    call check_small(maxval(abs(pack(fint, .not. fixed))) / maxval(abs(fint)), 1.0e-11_dp, &
                     name // ': free dofs in equilibrium')
  end subroutine run_patch

end program test_elastic_patch
