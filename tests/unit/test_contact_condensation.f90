!> contact_condensation: W = C K^-1 C' and q = g - C u0 from the factor with
!> the contact dofs last, against a dense computation (LAPACK dpotrf/dpotrs on
!> K assembled dense), as LAPACK's tests do it: the ratio
!>     ||W - W_dense||_1 / (||W_dense||_1 n eps)
!> (n the number of free dofs) must stay below a threshold of 30, and the
!> same for q.  Two bodies (the blocks of the patch test, meshed 6 x 6 and
!> 4 x 4: L_cc has one diagonal block per body) pressed together by a
!> prescribed displacement, constraint rows built by hand: normal rows
!> joining each lower top node to the two upper bottom nodes around it, and,
!> in the second case, tangential rows after them.  Each case is condensed
!> by triangular solves, by the blocks' inverses and by the automatic choice.
!> Also: the recovery u = K^-1 (f - C' mu) against the dense solve.
program test_contact_condensation
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use body, only: body_t, number_equations, build_pattern, assemble_stiffness
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, factorize, solve_forward
  use contact_set, only: contact_set_t
  use contact_condensation, only: contact_equations, condense, recover, condensed_t
  use lapack_interfaces, only: dpotrf, dpotrs
  use testing, only: check, check_small, finish_tests, dense_symmetric, tol_round
  implicit none
  real(dp), parameter :: threshold = 30.0_dp
  character(len=*), parameter :: ways(3) = ['solve  ', 'inverse', 'auto   ']
  integer :: way, pass

  do pass = 1, 2
    do way = 1, size(ways)
      call run_case(pass == 2, trim(ways(way)))
    end do
  end do
  call finish_tests()

contains

  subroutine run_case(friction, way)
    logical, intent(in) :: friction
    character(len=*), intent(in) :: way
    type(body_t) :: bd(2)
    type(diag_t) :: diag
    type(csc_t) :: k
    type(factor_t) :: f
    type(contact_set_t) :: cs
    type(condensed_t) :: cd
    type(error_t), allocatable :: err
    logical, allocatable :: fixed(:)
    integer, allocatable :: eq(:), last(:), lower_top(:), upper_bottom(:)
    real(dp), allocatable :: ubar(:), rhs(:), y(:), u0(:), w(:,:), q(:), kd(:,:), bd_t(:,:), x(:,:), &
                             wd(:,:), ud(:), qd(:), mu(:), u(:), fd(:,:)
    integer :: n, nfree, nc, i, j, r, p, c, info, ntop, nbot
    real(dp) :: xl, t, eps, ratio
    character(len=:), allocatable :: name

    name = trim(merge('friction ', 'normal   ', friction)) // ' condense=' // trim(way)
    eps = epsilon(1.0_dp)
    call make_rect_mesh(0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 6, 6, 'tri3', 'right', bd(1)%mesh, err)
    call make_rect_mesh(0.0_dp, 1.0_dp, 1.0_dp, 2.0_dp, 4, 4, 'tri3', 'alt', bd(2)%mesh, err)
    do i = 1, 2
      call finalize_mesh(bd(i)%mesh, 'condense', diag)
      call make_isotropic(1000.0_dp * i, 0.3_dp, .false., bd(i)%law)
    end do
    bd(2)%dof0 = 2 * bd(1)%mesh%nnode
    n = bd(2)%dof0 + 2 * bd(2)%mesh%nnode
    allocate(fixed(n), ubar(n))
    fixed = .false.
    ubar = 0.0_dp
    ! lower: bottom held; upper: top pushed down and sideways
    do i = 1, bd(1)%mesh%nnode
      ! nodes on a side of a unit-size mesh: their coordinate is exact to round-off
      if (bd(1)%mesh%x(2, i) < tol_round(16)) fixed(2 * i - 1:2 * i) = .true.
    end do
    do i = 1, bd(2)%mesh%nnode
      if (bd(2)%mesh%x(2, i) > 2.0_dp - tol_round(16)) then
        fixed(bd(2)%dof0 + 2 * i - 1:bd(2)%dof0 + 2 * i) = .true.
        ubar(bd(2)%dof0 + 2 * i - 1:bd(2)%dof0 + 2 * i) = [0.002_dp, -0.01_dp]
      end if
    end do
    lower_top = pack([(i, i = 1, bd(1)%mesh%nnode)], abs(bd(1)%mesh%x(2, :) - 1.0_dp) < tol_round(16))
    upper_bottom = pack([(i, i = 1, bd(2)%mesh%nnode)], abs(bd(2)%mesh%x(2, :) - 1.0_dp) < tol_round(16))
    ntop = size(lower_top)
    nbot = size(upper_bottom)
    call check(diag%count == 0 .and. ntop == 7 .and. nbot == 5, name // ': meshes and contact sides')

    ! contact dofs: both dofs of the nodes on the two sides, ascending
    cs%ncdof = 2 * (ntop + nbot)
    cs%cdof = [([2 * lower_top(i) - 1, 2 * lower_top(i)], i = 1, ntop), &
               ([bd(2)%dof0 + 2 * upper_bottom(i) - 1, bd(2)%dof0 + 2 * upper_bottom(i)], i = 1, nbot)]
    call check(all(cs%cdof(2:) > cs%cdof(:size(cs%cdof) - 1)), name // ': contact dofs ascending')
    ! row i: u_y(lower node i) - [(1 - t) u_y(a) + t u_y(b)] of the upper nodes
    ! a, b around it (a mortar-like row; columns index cdof), g_i = 0.001 i
    cs%nrow = ntop
    cs%ntan = merge(ntop, 0, friction)
    nc = cs%nrow + cs%ntan
    allocate(cs%bptr(nc + 1), cs%bcol(3 * nc), cs%bval(3 * nc), cs%g(cs%nrow))
    cs%bptr(1) = 1
    p = 0
    do r = 1, nc
      i = mod(r - 1, ntop) + 1
      c = merge(2, 1, r <= cs%nrow)              ! u_y for normal rows, u_x for tangential rows
      xl = bd(1)%mesh%x(1, lower_top(i))
      j = min(nbot - 1, int(xl * (nbot - 1)) + 1)   ! the upper segment [j, j + 1] over xl
      t = (xl - bd(2)%mesh%x(1, upper_bottom(j))) / &
          (bd(2)%mesh%x(1, upper_bottom(j + 1)) - bd(2)%mesh%x(1, upper_bottom(j)))
      p = p + 1; cs%bcol(p) = 2 * (i - 1) + c; cs%bval(p) = 1.0_dp
      p = p + 1; cs%bcol(p) = 2 * ntop + 2 * (j - 1) + c; cs%bval(p) = -(1.0_dp - t)
      p = p + 1; cs%bcol(p) = 2 * ntop + 2 * j + c; cs%bval(p) = -t
      cs%bptr(r + 1) = p + 1
      if (r <= cs%nrow) cs%g(r) = 0.001_dp * r
    end do

    call number_equations(fixed, eq, nfree)
    call build_pattern(bd, eq, nfree, k, err)
    allocate(rhs(nfree))
    rhs = 0.0_dp
    call assemble_stiffness(bd, eq, ubar, k, rhs)
    call contact_equations(cs, eq, last)
    call factorize(f, k, err, last)
    call check(.not. allocated(err), name // ': factorized, contact dofs last')
    if (allocated(err)) return
    allocate(y(nfree), u0(n))
    call solve_forward(f, rhs, y, err)
    u0 = ubar
    call condense(cs, eq, f, y, u0, w, q, cd, err, way)
    call check(.not. allocated(err), name // ': condensed')
    if (allocated(err)) return

    ! the dense reference: K from its upper triangle, C' on the free dofs
    call dense_symmetric(k%colptr, k%rowind, k%val, kd)
    allocate(bd_t(nfree, nc), fd(nfree, 1))
    bd_t = 0.0_dp
    do r = 1, nc
      do p = cs%bptr(r), cs%bptr(r + 1) - 1
        i = eq(cs%cdof(cs%bcol(p)))
        if (i > 0) bd_t(i, r) = bd_t(i, r) + cs%bval(p)
      end do
    end do
    call dpotrf('L', nfree, kd, nfree, info)
    call check(info == 0, name // ': dense K positive definite')
    x = bd_t
    call dpotrs('L', nfree, nc, kd, nfree, x, nfree, info)
    wd = matmul(transpose(bd_t), x)                  ! W = C K^-1 C'
    ratio = norm1(w - wd) / (norm1(wd) * nfree * eps)
    call check_small(ratio, threshold, name // ': ||W - W_dense||_1 / (||W||_1 n eps)')
    call check_small(maxval(abs(w - transpose(w))) / maxval(abs(w)) / eps, 1.0_dp, name // ': W symmetric')
    ! q = g - C u0, u0 = K^-1 f on the free dofs, the prescribed values on the others
    fd(:, 1) = rhs
    call dpotrs('L', nfree, 1, kd, nfree, fd, nfree, info)
    allocate(ud(n))
    ud = ubar
    do i = 1, n
      if (eq(i) > 0) ud(i) = fd(eq(i), 1)
    end do
    allocate(qd(nc))
    do r = 1, nc
      qd(r) = 0.0_dp
      if (r <= cs%nrow) qd(r) = cs%g(r)
      do p = cs%bptr(r), cs%bptr(r + 1) - 1
        qd(r) = qd(r) - cs%bval(p) * ud(cs%cdof(cs%bcol(p)))
      end do
    end do
    ratio = maxval(abs(q - qd)) / ((maxval(abs(cs%g)) + 2.0_dp * maxval(abs(ud))) * nfree * eps)
    call check_small(ratio, threshold, name // ': |q - q_dense| / ((|g| + |C| |u0|) n eps)')

    ! the recovery: u = K^-1 (f - C' mu) for some multipliers
    allocate(mu(nc), u(n))
    mu = [(0.5_dp + 0.1_dp * r, r = 1, nc)]
    call recover(eq, f, y, cd, u0, mu, u, err)
    fd(:, 1) = rhs - matmul(bd_t, mu)
    call dpotrs('L', nfree, 1, kd, nfree, fd, nfree, info)
    ud = ubar
    do i = 1, n
      if (eq(i) > 0) ud(i) = fd(eq(i), 1)
    end do
    ratio = maxval(abs(u - ud)) / (maxval(abs(ud)) * nfree * eps)
    call check_small(ratio, threshold, name // ': recovery |u - u_dense| / (|u| n eps)')
  end subroutine run_case

  !> ||a||_1, the largest column sum (LAPACK's dlange('1')).
  pure real(dp) function norm1(a)
    real(dp), intent(in) :: a(:,:)
    norm1 = maxval(sum(abs(a), dim=1))
  end function norm1

end program test_contact_condensation
