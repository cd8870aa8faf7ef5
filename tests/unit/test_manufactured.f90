!> Manufactured solution of plane-strain elasticity on the unit square:
!>   u = (sin(pi x) sin(pi y), sin(pi x) cos(pi y)),  f = -div sigma(u)
!>   = -((lam + mu) grad div u + mu lap u),
!> Dirichlet data u on the whole boundary.  On three uniform refinements the
!> L2 error must fall like h^2 and the H1 seminorm error like h (P1 and Q1),
!> like h^3 and h^2 for the quadratic elements (P2 tri6 and Q9 quad9, on
!> coarser meshes: 4, 8, 16 cells a side).
!> Set MMS_LEVELS=N in the environment to print a longer table (for studies).
program test_manufactured
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use elements, only: quadrature_rule, shape_at
  use body, only: body_t, number_equations, build_pattern, assemble_stiffness, element_dofs
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, factorize, solve
  use testing, only: check, finish_tests, tol_round
  implicit none
  real(dp), parameter :: pi = acos(-1.0_dp), e_mod = 1000.0_dp, nu = 0.3_dp
  real(dp) :: lam, mu, el2(8), eh1(8), rate_l2, rate_h1, p
  integer :: nlev, lev, ielem, stat, n
  character(len=16) :: buf
  character(len=5), parameter :: kinds_name(4) = ['tri3 ', 'quad4', 'tri6 ', 'quad9']

  lam = e_mod * nu / ((1 + nu) * (1 - 2 * nu))
  mu = e_mod / (2 * (1 + nu))
  nlev = 3
  call get_environment_variable('MMS_LEVELS', buf, status=stat)
  if (stat == 0) read(buf, *) nlev
  nlev = max(3, min(nlev, 8))
  do ielem = 1, 4
    write(*, '(a)') '# ' // trim(kinds_name(ielem)) // ':   n        h          L2 error      H1 error'
    p = merge(1.0_dp, 2.0_dp, ielem <= 2)              ! polynomial degree
    do lev = 1, nlev
      n = merge(4 * 2**lev, 2 * 2**lev, ielem <= 2)
      call solve_level(n, trim(kinds_name(ielem)), el2(lev), eh1(lev))
      write(*, '(a,i6,es12.4,2es14.6)') '# ', n, 1.0_dp / n, el2(lev), eh1(lev)
    end do
    rate_l2 = log(el2(nlev - 1) / el2(nlev)) / log(2.0_dp)
    rate_h1 = log(eh1(nlev - 1) / eh1(nlev)) / log(2.0_dp)
    write(*, '(a,2f8.4)') '# observed rates L2, H1: ', rate_l2, rate_h1
    call check(rate_l2 > p + 0.9_dp .and. rate_l2 < p + 1.15_dp, 'manufactured ' // trim(kinds_name(ielem)) // &
               ': L2 rate ' // achar(49 + nint(p)))
    call check(rate_h1 > p - 0.05_dp .and. rate_h1 < p + 0.15_dp, 'manufactured ' // trim(kinds_name(ielem)) // &
               ': H1 rate ' // achar(48 + nint(p)))
  end do
  call finish_tests()

contains

  pure function exact(x) result(u)
    real(dp), intent(in) :: x(2)
    real(dp) :: u(2)
    u = [sin(pi * x(1)) * sin(pi * x(2)), sin(pi * x(1)) * cos(pi * x(2))]
  end function exact

  pure function exact_grad(x) result(g)   ! g(i, j) = d u_i / d x_j
    real(dp), intent(in) :: x(2)
    real(dp) :: g(2, 2)
    real(dp) :: sx, cx, sy, cy
    sx = sin(pi * x(1)); cx = cos(pi * x(1)); sy = sin(pi * x(2)); cy = cos(pi * x(2))
    g(1, :) = pi * [cx * sy, sx * cy]
    g(2, :) = pi * [cx * cy, -sx * sy]
  end function exact_grad

  pure function force(x) result(f)
    real(dp), intent(in) :: x(2)
    real(dp) :: f(2)
    real(dp) :: sx, cx, sy, cy, gdiv(2), lap(2)
    sx = sin(pi * x(1)); cx = cos(pi * x(1)); sy = sin(pi * x(2)); cy = cos(pi * x(2))
    gdiv = pi**2 * [-sx * sy - cx * sy, cx * cy - sx * cy]     ! grad div u
    lap = -2.0_dp * pi**2 * [sx * sy, sx * cy]                 ! laplacian of u
    f = -((lam + mu) * gdiv + mu * lap)
  end function force

  subroutine solve_level(n, elem, el2, eh1)
    integer, intent(in) :: n
    character(len=*), intent(in) :: elem
    real(dp), intent(out) :: el2, eh1
    type(body_t) :: bd(1)
    type(diag_t) :: diag
    type(csc_t) :: k
    type(factor_t) :: f
    type(error_t), allocatable :: err
    logical, allocatable :: fixed(:)
    integer, allocatable :: eq(:)
    real(dp), allocatable :: ubar(:), rhs(:,:), x(:,:), u(:), xi(:,:), w(:)
    real(dp) :: shp(9), dndx(2, 9), detj, xq(2), uh(2), gh(2, 2)
    integer :: nd, nfree, i, e, q, nen, a
    integer :: dofs(18)

    call make_rect_mesh(0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, n, n, elem, 'alt', bd(1)%mesh, err)
    call finalize_mesh(bd(1)%mesh, 'mms', diag)
    call make_isotropic(e_mod, nu, .false., bd(1)%law)
    nd = 2 * bd(1)%mesh%nnode
    allocate(fixed(nd), ubar(nd), u(nd))
    do i = 1, bd(1)%mesh%nnode
      associate(p => bd(1)%mesh%x(:, i))
        ubar(2 * i - 1:2 * i) = exact(p)
        ! nodes on a side of a unit-size mesh: their coordinate is exact to round-off
        fixed(2 * i - 1:2 * i) = min(p(1), p(2), 1 - p(1), 1 - p(2)) < tol_round(16)
      end associate
    end do
    call number_equations(fixed, eq, nfree)
    call build_pattern(bd, eq, nfree, k, err)
    allocate(rhs(nfree, 1), x(nfree, 1))
    rhs = 0.0_dp
    ! consistent load of the variable body force, quadrature_rule order 2
    do e = 1, bd(1)%mesh%nelem
      nen = bd(1)%mesh%nen(e)
      call quadrature_rule(nen, 2, xi, w)
      call element_dofs(bd(1), e, dofs)
      do q = 1, size(w)
        call shape_at(nen, bd(1)%mesh%x(:, bd(1)%mesh%conn(1:nen, e)), xi(:, q), shp(1:nen), dndx(:, 1:nen), detj)
        xq = matmul(bd(1)%mesh%x(:, bd(1)%mesh%conn(1:nen, e)), shp(1:nen))
        uh = force(xq)
        do a = 1, nen
          do i = 1, 2
            if (eq(dofs(2 * a - 2 + i)) > 0) rhs(eq(dofs(2 * a - 2 + i)), 1) = rhs(eq(dofs(2 * a - 2 + i)), 1) &
              + w(q) * detj * shp(a) * uh(i)
          end do
        end do
      end do
    end do
    call assemble_stiffness(bd, eq, ubar, k, rhs(:, 1))
    call factorize(f, k, err)
    if (allocated(err)) then
      el2 = huge(1.0_dp); eh1 = huge(1.0_dp)
      return
    end if
    call solve(f, rhs, x, err)
    u = ubar
    do i = 1, nd
      if (eq(i) > 0) u(i) = x(eq(i), 1)
    end do
    ! errors by quadrature_rule order 2
    el2 = 0.0_dp; eh1 = 0.0_dp
    do e = 1, bd(1)%mesh%nelem
      nen = bd(1)%mesh%nen(e)
      call quadrature_rule(nen, 2, xi, w)
      call element_dofs(bd(1), e, dofs)
      do q = 1, size(w)
        call shape_at(nen, bd(1)%mesh%x(:, bd(1)%mesh%conn(1:nen, e)), xi(:, q), shp(1:nen), dndx(:, 1:nen), detj)
        xq = matmul(bd(1)%mesh%x(:, bd(1)%mesh%conn(1:nen, e)), shp(1:nen))
        uh = [dot_product(shp(1:nen), u(dofs(1:2 * nen:2))), dot_product(shp(1:nen), u(dofs(2:2 * nen:2)))]
        gh(1, :) = matmul(dndx(:, 1:nen), u(dofs(1:2 * nen:2)))
        gh(2, :) = matmul(dndx(:, 1:nen), u(dofs(2:2 * nen:2)))
        el2 = el2 + w(q) * detj * sum((uh - exact(xq))**2)
        eh1 = eh1 + w(q) * detj * sum((gh - exact_grad(xq))**2)
      end do
    end do
    el2 = sqrt(el2); eh1 = sqrt(eh1)
  end subroutine solve_level

end program test_manufactured
