!> body: the global system K_ff u_f = f_f - K_fd ubar_d of two bodies, checked
!> against invariants and against the module's second path to the same
!> numbers (the element loop of internal_forces, which never forms K):
!>   - rigid motions: the two translations and the infinitesimal rotation of
!>     a free body give K r = 0 (internal_forces), ||K r|| / (||K|| ||r|| n eps);
!>   - the assembled upper triangle of K_ff times u_f, plus K_fd ubar_d moved
!>     to the right-hand side, is the element loop's K u on the free rows
!>     (a LAPACK-style ratio, the two bodies numbered one after the other);
!>   - K_ff is positive on its diagonal, and its pattern holds every entry;
!>   - edge_outward_normal: the unit outward normals of the four sides of a
!>     rectangle, and an interior edge reported as shared (owner -1);
!>   - a prescribed value whose product with the stiffness leaves double
!>     precision is reported (overflow = the body) instead of overflowing.
program test_body
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use body, only: body_t, number_equations, build_pattern, assemble_stiffness, internal_forces, &
                  node_elements, edge_outward_normal
  use sparse_matrix, only: csc_t
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none
  real(dp), parameter :: threshold = 30.0_dp
  type(body_t) :: bd(2)
  type(diag_t) :: diag
  type(error_t), allocatable :: err
  integer :: i

  call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.0_dp, 8, 4, 'tri3', 'right', bd(1)%mesh, err)
  if (.not. allocated(err)) call make_rect_mesh(0.0_dp, 1.5_dp, 1.0_dp, 2.5_dp, 3, 3, 'quad4', 'right', &
                                                bd(2)%mesh, err)
  call check(.not. allocated(err), 'two meshes (tri3 and quad4)')
  if (allocated(err)) call finish_tests()
  do i = 1, 2
    call finalize_mesh(bd(i)%mesh, 'body', diag)
  end do
  call make_isotropic(210.0e3_dp, 0.3_dp, .false., bd(1)%law)
  call make_isotropic(70.0e3_dp, 0.25_dp, .true., bd(2)%law)
  bd(2)%thick = 0.5_dp
  bd(2)%dof0 = 2 * bd(1)%mesh%nnode

  call test_rigid_motions()
  call test_assembly()
  call test_normals()
  call test_overflow()
  call finish_tests()

contains

  !> K r = 0 for the rigid motions of each body (all dofs free).
  subroutine test_rigid_motions()
    real(dp), allocatable :: r(:), f(:), e(:)
    integer :: n, m, b, a
    real(dp) :: knorm
    character(len=*), parameter :: names(3) = ['translation x', 'translation y', 'rotation     ']
    n = bd(2)%dof0 + 2 * bd(2)%mesh%nnode
    allocate(r(n), f(n), e(n))
    ! ||K||_1 estimated from the unit vectors of a few dofs (K e_j = column j)
    knorm = 0.0_dp
    do a = 1, n, max(1, n / 7)
      e = 0.0_dp
      e(a) = 1.0_dp
      call internal_forces(bd, e, f)
      knorm = max(knorm, sum(abs(f)))
    end do
    do m = 1, 3
      r = 0.0_dp
      do b = 1, 2
        do a = 1, bd(b)%mesh%nnode
          associate (x => bd(b)%mesh%x(:, a), k => bd(b)%dof0 + 2 * a)
            select case (m)
            case (1); r(k - 1) = 1.0_dp
            case (2); r(k) = 1.0_dp
            case (3); r(k - 1) = -x(2); r(k) = x(1)      ! omega x: (-y, x)
            end select
          end associate
        end do
      end do
      call internal_forces(bd, r, f)
      call check_small(maxval(abs(f)) / (knorm * maxval(abs(r)) * n * epsilon(1.0_dp)), threshold, &
                       'rigid ' // trim(names(m)) // ': ||K r|| / (||K|| ||r|| n eps)')
    end do
  end subroutine test_rigid_motions

  !> K_ff u_f + K_fd ubar_d (assembled) = (K u)_f (element loop).
  subroutine test_assembly()
    logical, allocatable :: fixed(:)
    integer, allocatable :: eq(:)
    real(dp), allocatable :: u(:), ubar(:), rhs(:), kf(:), fint(:), ku(:)
    type(csc_t) :: k
    integer :: n, nfree, j, p, i, a, overflow
    real(dp) :: scale
    n = bd(2)%dof0 + 2 * bd(2)%mesh%nnode
    allocate(fixed(n), ubar(n), u(n), fint(n))
    fixed = .false.
    ubar = 0.0_dp
    ! the lower body's bottom held with a prescribed value, the upper's left side held
    do a = 1, bd(1)%mesh%nnode
      ! nodes on a side of a unit-size mesh: their coordinate is exact to round-off
      if (bd(1)%mesh%x(2, a) < tol_round(16)) then
        fixed(2 * a - 1:2 * a) = .true.
        ubar(2 * a - 1:2 * a) = [1.0e-3_dp, -2.0e-3_dp * bd(1)%mesh%x(1, a)]
      end if
    end do
    do a = 1, bd(2)%mesh%nnode
      if (bd(2)%mesh%x(1, a) < tol_round(16)) fixed(bd(2)%dof0 + 2 * a - 1:bd(2)%dof0 + 2 * a) = .true.
    end do
    call number_equations(fixed, eq, nfree)
    call check(nfree == count(.not. fixed) .and. maxval(eq) == nfree, 'number_equations: the free dofs numbered 1..nfree')
    call build_pattern(bd, eq, nfree, k, err)
    call check(.not. allocated(err), 'build_pattern')
    if (allocated(err)) return
    allocate(rhs(nfree), kf(nfree), ku(nfree))
    rhs = 0.0_dp
    call assemble_stiffness(bd, eq, ubar, k, rhs, overflow)
    call check(overflow == 0, 'assemble_stiffness: no overflow reported for ordinary values')
    call check(all([(k%val(k%colptr(j + 1) - 1) > 0.0_dp .and. k%rowind(k%colptr(j + 1) - 1) == j, &
                     j = 1, nfree)]), 'K_ff: the diagonal stored last in each column, positive')
    ! u: smooth values on every dof, ubar on the fixed ones
    do i = 1, n
      u(i) = sin(0.7_dp * i) * 1.0e-3_dp
    end do
    where (fixed) u = ubar
    ! kf = K_ff u_f from the upper triangle (symmetric product)
    kf = 0.0_dp
    do j = 1, n
      if (eq(j) == 0) cycle
      associate (cj => eq(j))
        do p = k%colptr(cj), k%colptr(cj + 1) - 1
          i = k%rowind(p)
          kf(i) = kf(i) + k%val(p) * u(dof_of(eq, cj))
          if (i /= cj) kf(cj) = kf(cj) + k%val(p) * u(dof_of(eq, i))
        end do
      end associate
    end do
    call internal_forces(bd, u, fint)
    do j = 1, n
      if (eq(j) > 0) ku(eq(j)) = fint(j)
    end do
    ! (K u)_f = K_ff u_f + K_fd ubar_d = kf - rhs
    scale = maxval(abs(ku)) + maxval(abs(kf))
    call check_small(maxval(abs(kf - rhs - ku)) / (scale * nfree * epsilon(1.0_dp)), threshold, &
                     'K_ff u_f + K_fd ubar_d (assembled) = (K u)_f (element loop): ratio')
  end subroutine test_assembly

  !> The dof whose free equation is e.
  pure integer function dof_of(eq, e)
    integer, intent(in) :: eq(:), e
    integer :: j
    dof_of = 0
    do j = 1, size(eq)
      if (eq(j) == e) then
        dof_of = j
        return
      end if
    end do
  end function dof_of

  !> The outward normals of the lower rectangle's sides, and an interior edge.
  subroutine test_normals()
    integer, allocatable :: eptr(:), elist(:)
    real(dp) :: nrm(2)
    integer :: owner, ib, s, a, b, worst
    real(dp) :: expect(2, 4), err_n
    character(len=6), parameter :: side(4) = ['left  ', 'right ', 'bottom', 'top   ']
    expect = reshape([-1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, 1.0_dp], [2, 4])
    call node_elements(bd(1)%mesh, eptr, elist)
    err_n = 0.0_dp
    worst = 0
    do ib = 1, 4
      do s = 1, bd(1)%mesh%bnd(ib)%nseg
        a = bd(1)%mesh%bnd(ib)%seg(1, s)
        b = bd(1)%mesh%bnd(ib)%seg(2, s)
        call edge_outward_normal(bd(1)%mesh, eptr, elist, a, b, nrm, owner)
        if (owner <= 0) worst = ib
        err_n = max(err_n, maxval(abs(nrm - expect(:, ib))))
      end do
      call check(bd(1)%mesh%bnd(ib)%name == trim(side(ib)), 'rect mesh: boundary ' // int_to_str(ib) // ' is ' // trim(side(ib)))
    end do
    call check(worst == 0, 'edge_outward_normal: every boundary edge has one element')
    call check_small(err_n / epsilon(1.0_dp), threshold, 'edge_outward_normal: the outward unit normals of the sides')
    ! the first element's first two nodes: an edge shared by two elements
    ! unless it lies on the boundary (the bottom-left triangle's diagonal is inside)
    call edge_outward_normal(bd(1)%mesh, eptr, elist, bd(1)%mesh%conn(2, 1), bd(1)%mesh%conn(3, 1), nrm, owner)
    call check(owner == -1 .or. owner == 1, 'edge_outward_normal: an edge of element 1 found (owner ' // int_to_str(owner) // ')')
  end subroutine test_normals

  !> E = 1e300 with a prescribed value of 1e10: K_fd ubar_d leaves double precision.
  subroutine test_overflow()
    type(body_t) :: big(1)
    logical, allocatable :: fixed(:)
    integer, allocatable :: eq(:)
    real(dp), allocatable :: ubar(:), rhs(:)
    type(csc_t) :: k
    integer :: nfree, a, overflow
    call make_rect_mesh(0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 2, 2, 'tri3', 'right', big(1)%mesh, err)
    call finalize_mesh(big(1)%mesh, 'big', diag)
    call make_isotropic(1.0e300_dp, 0.3_dp, .false., big(1)%law)
    allocate(fixed(2 * big(1)%mesh%nnode), ubar(2 * big(1)%mesh%nnode))
    fixed = .false.
    ubar = 0.0_dp
    do a = 1, big(1)%mesh%nnode
      if (big(1)%mesh%x(2, a) < tol_round(16)) then
        fixed(2 * a - 1:2 * a) = .true.
        ubar(2 * a) = 1.0e10_dp
      end if
    end do
    call number_equations(fixed, eq, nfree)
    call build_pattern(big, eq, nfree, k, err)
    allocate(rhs(nfree))
    rhs = 0.0_dp
    call assemble_stiffness(big, eq, ubar, k, rhs, overflow)
    call check(overflow == 1, 'assemble_stiffness: E = 1e300 times 1e10 reported as an overflow of body 1')
    call check(all(abs(rhs) <= huge(1.0_dp)), 'assemble_stiffness: the right-hand side stays finite')
  end subroutine test_overflow

end program test_body
