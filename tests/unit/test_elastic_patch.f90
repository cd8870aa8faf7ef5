!> Patch test of plane elasticity: a linear displacement field prescribed on
!> the boundary of a distorted mesh is reproduced inside to round-off, with the
!> exact constant stress, for P1 and Q1, plane strain and plane stress,
!> isotropic and rotated orthotropic laws.  Also: the internal forces of the
!> solution balance (sum of reactions = 0, moment = 0).
!> Patch test of plane elasticity: a linear displacement field prescribed on
!> the boundary of a distorted mesh is reproduced inside to round-off, with the
!> exact constant stress, for P1, Q1, P2 (tri6), Q8 (quad8) and Q9 (quad9),
!> plane strain and plane stress, isotropic and rotated orthotropic laws.  The
!> quadratic elements are tried on distorted straight-sided meshes, on the same
!> meshes with the interior mid-side nodes moved off the chords (curved edges),
!> and on second-order gmsh meshes of a quarter annulus (mid-side nodes on the
!> arcs).  Also: the internal forces of the solution balance (sum of reactions
!> = 0, moment = 0).
program test_elastic_patch
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use mesh, only: mesh_t, finalize_mesh, boundary_nodes
  use mesh_rect, only: make_rect_mesh
  use gmsh_reader, only: read_gmsh_file
  use gmsh_runner, only: gmsh_options_t, mesh_geo_file
  use safe_files, only: private_folder
  use material, only: make_isotropic, make_orthotropic
  use body, only: body_t, number_equations, build_pattern, assemble_stiffness, element_response
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, factorize, solve
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none
  integer :: ielem, ilaw
  character(len=80) :: name
  character(len=*), parameter :: elems(14) = [character(len=20) :: 'tri3 right', 'tri3 alt', 'quad4', &
    'tri6 right', 'tri6 alt', 'quad8', 'quad9', 'tri6 curved', 'quad8 curved', 'quad9 curved', &
    'gmsh tri6', 'gmsh quad8', 'gmsh quad9', 'none']
  character(len=*), parameter :: laws(4) = ['iso strain  ', 'iso stress  ', 'ortho strain', 'ortho stress']
  character(len=:), allocatable :: tmp
  type(error_t), allocatable :: err

  call private_folder(tmp, err)
  call check(.not. allocated(err), 'a private folder for the gmsh meshes')
  do ielem = 1, 13
    do ilaw = 1, 4
      name = 'patch ' // trim(elems(ielem)) // ' ' // trim(laws(ilaw))
      call run_patch(trim(elems(ielem)), ilaw, trim(name))
    end do
  end do
  deallocate(tmp)                                ! saved, never freed at the end (LeakSanitizer)
  call finish_tests()

contains

  !> A distorted rect mesh of [0,2] x [0,1.5], 5 x 4 cells: the interior corner
  !> nodes shifted up to 0.25 h, the mid-side nodes at the middle of the new
  !> straight edges (centres at the mean of the corners), or, curved, the
  !> interior mid-side nodes moved off the chords by up to 0.05 h.
  subroutine distorted_rect(kind, m)
    character(len=*), intent(in) :: kind
    type(mesh_t), intent(out) :: m
    type(error_t), allocatable :: err
    integer, parameter :: nx = 5, ny = 4
    character(len=:), allocatable :: elem, diag
    real(dp), parameter :: h = 0.375_dp
    integer :: i, ix, iy, g, gx, gy
    logical :: curved
    elem = kind(1:index(kind // ' ', ' ') - 1)
    diag = 'right'
    if (index(kind, 'alt') > 0) diag = 'alt'
    curved = index(kind, 'curved') > 0
    call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.5_dp, nx, ny, elem, diag, m, err)
    g = merge(1, 2, elem == 'tri3' .or. elem == 'quad4')
    gx = g * nx; gy = g * ny
    do i = 1, m%nnode                                ! corners
      ix = mod(i - 1, gx + 1); iy = (i - 1) / (gx + 1)
      if (ix == 0 .or. ix == gx .or. iy == 0 .or. iy == gy) cycle
      if (mod(ix, g) /= 0 .or. mod(iy, g) /= 0) cycle
      m%x(:, i) = m%x(:, i) + 0.25_dp * h * [sin(7.1_dp * i), cos(3.3_dp * i)]
    end do
    if (g == 1) return
    do i = 1, m%nnode                                ! mid-sides and centres
      ix = mod(i - 1, gx + 1); iy = (i - 1) / (gx + 1)
      if (mod(ix, 2) == 1 .and. mod(iy, 2) == 0) then
        m%x(:, i) = 0.5_dp * (m%x(:, i - 1) + m%x(:, i + 1))
      else if (mod(ix, 2) == 0 .and. mod(iy, 2) == 1) then
        m%x(:, i) = 0.5_dp * (m%x(:, i - gx - 1) + m%x(:, i + gx + 1))
      else if (mod(ix, 2) == 1 .and. mod(iy, 2) == 1) then
        m%x(:, i) = 0.25_dp * (m%x(:, i - gx - 2) + m%x(:, i - gx) + m%x(:, i + gx) + m%x(:, i + gx + 2))
      end if
      if (curved .and. ix > 0 .and. ix < gx .and. iy > 0 .and. iy < gy .and. (mod(ix, 2) == 1 .or. mod(iy, 2) == 1)) &
        m%x(:, i) = m%x(:, i) + 0.05_dp * h * [cos(5.3_dp * i), sin(2.9_dp * i)]
    end do
  end subroutine distorted_rect

  !> A second-order gmsh mesh of tests/unit/data/annulus_quarter.geo.
  subroutine gmsh_annulus(kind, ilaw, m, ok)
    character(len=*), intent(in) :: kind
    integer, intent(in) :: ilaw             !< names gmsh's log, which must not exist
    type(mesh_t), intent(out) :: m
    logical, intent(out) :: ok
    type(gmsh_options_t) :: opts
    type(diag_t) :: d
    type(error_t), allocatable :: err
    real(dp) :: quads, incomplete
    quads = merge(0.0_dp, 1.0_dp, kind == 'gmsh tri6')
    incomplete = merge(1.0_dp, 0.0_dp, kind == 'gmsh quad8')
    call mesh_geo_file('tests/unit/data/annulus_quarter.geo', 2, [character(len=10) :: 'n', 'quads', 'incomplete'], &
                       [4.0_dp, quads, incomplete], opts, 'tests/unit/data', tmp // '/annulus.msh', &
                       tmp // '/annulus_' // kind(6:) // achar(48 + ilaw) // '.log', err)
    ok = .not. allocated(err)
    if (ok) then
      call check(ok, kind // ': gmsh -order 2 meshes annulus_quarter.geo')
    else
      call check(ok, kind // ': gmsh -order 2 meshes annulus_quarter.geo ' // err%message)
      return
    end if
    call read_gmsh_file(tmp // '/annulus.msh', m, d)
    ok = d%count == 0
    call check(ok, kind // ': the second-order mesh is read')
  end subroutine gmsh_annulus

  subroutine run_patch(kind, ilaw, name)
    character(len=*), intent(in) :: kind
    integer, intent(in) :: ilaw
    character(len=*), intent(in) :: name
    type(body_t) :: bd(1)
    type(diag_t) :: diag
    type(csc_t) :: k
    type(factor_t) :: f
    type(error_t), allocatable :: err
    logical, allocatable :: fixed(:)
    integer, allocatable :: eq(:), nodes(:)
    real(dp), allocatable :: ubar(:), rhs(:,:), x(:,:), u(:), fint(:), stress(:,:), vm(:)
    real(dp) :: a(3), b(3), eps(3), sexact(3), r(2), moment, umax
    integer :: n, nfree, i, ib, nen
    logical :: ok

    if (kind(1:4) == 'gmsh') then
      call gmsh_annulus(kind, ilaw, bd(1)%mesh, ok)
      if (.not. ok) return
    else
      call distorted_rect(kind, bd(1)%mesh)
    end if
    call finalize_mesh(bd(1)%mesh, 'patch', diag)
    call check(diag%count == 0, name // ': distorted mesh valid')
    if (diag%count > 0) return
    nen = maxval(bd(1)%mesh%nen)
    call check(all(bd(1)%mesh%nen == nen) .and. nen == merge(3, 0, kind(1:4) == 'tri3') + &
               merge(4, 0, kind(1:5) == 'quad4') + merge(6, 0, index(kind, 'tri6') > 0) + &
               merge(8, 0, index(kind, 'quad8') > 0) + merge(9, 0, index(kind, 'quad9') > 0), &
               name // ': elements of the expected kind')
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
      end associate
    end do
    fixed = .false.                                  ! every node of every named boundary
    do ib = 1, size(bd(1)%mesh%bnd)
      call boundary_nodes(bd(1)%mesh%bnd(ib), nodes)
      fixed(2 * nodes - 1) = .true.
      fixed(2 * nodes) = .true.
    end do
    call number_equations(fixed, eq, nfree)
    call build_pattern(bd, eq, nfree, k, err)
    allocate(rhs(nfree, 1), x(nfree, 1))
    rhs = 0.0_dp
    call assemble_stiffness(bd, eq, ubar, k, rhs(:, 1))
    call factorize(f, k, err)
    call check(.not. allocated(err), name // ': factorized')
    if (allocated(err)) return
    call solve(f, rhs, x, err)
    u = ubar
    do i = 1, n
      if (eq(i) > 0) u(i) = x(eq(i), 1)
    end do
    umax = maxval(abs(ubar))
    ! a solve with K: round-off amplified by cond(K) of these small patches,
    ! sums over the nodes for the reactions (measured <= 40 eps; 8 times that)
    call check_small(maxval(abs(u - ubar)) / umax, tol_round(128), name // ': displacement exact')
    allocate(stress(3, bd(1)%mesh%nelem), vm(bd(1)%mesh%nelem))
    call element_response(bd, u, fint, stress, vm)
    eps = [a(2), b(3), a(3) + b(2)]
    sexact = matmul(bd(1)%law%d, eps)
    call check_small(maxval(abs(stress - spread(sexact, 2, bd(1)%mesh%nelem))) / maxval(abs(sexact)), tol_round(256), &
                     name // ': stress exact')
    r = [sum(fint(1::2)), sum(fint(2::2))]
    moment = sum(bd(1)%mesh%x(1, :) * fint(2::2) - bd(1)%mesh%x(2, :) * fint(1::2))
    call check_small(maxval(abs([r, moment])) / maxval(abs(fint)), tol_round(256), name // ': reactions in equilibrium')
    call check_small(maxval(abs(pack(fint, .not. fixed))) / maxval(abs(fint)), tol_round(512), &
                     name // ': free dofs in equilibrium')
  end subroutine run_patch

end program test_elastic_patch
