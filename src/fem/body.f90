!> body: elastic bodies and the global system of plane elasticity, eq. (1) and
!> the bilinear form a(.,.) of (6), discretized by (7).  Knows no deck.
!>
!> Global dofs: body b's node a, component c (1 = x, 2 = y) is dof
!> bodies(b)%dof0 + 2 (a - 1) + c.  Dirichlet dofs (fixed(dof)) are eliminated
!> symmetrically: the free equations eq(dof) = 1..nfree number the free dofs in
!> dof order, and
!>     K_ff u_f = f_f - K_fd ubar_d.
!> K_ff is stored as the upper triangle of a compressed-column matrix whose
!> pattern comes from the node adjacency of each mesh (no triplets, no dense N x N).
!>
!> Local axes.  A node held by FIX un=/ut= (doc/theory.md, "Supports in local
!> axes") has its two dofs in the axes (n, t) of its nodal normal n, t =
!> (-n_y, n_x): bd%axes(:, a) = n, [0, 0] for a node in global axes.  Every
!> routine here works in that solver basis: K = Q' K_xy Q element by element,
!> fint = Q' K_xy (Q u), so a prescribed un is an ordinary Dirichlet dof and is
!> eliminated like ux.  to_global_axes turns a solver-basis vector (a
!> displacement, a nodal force) into x, y components, to_local_axes back.
!>
!> Springs (SPRING, module foundation): each body's spring elements join K
!> beside its elements, in assemble_stiffness, internal_forces and
!> element_response alike (their matrices in x, y turned to a node's local
!> axes as the elements' are), so that K u, the reactions and the energy
!> count them; spring_reactions gives each SPRING statement's force on the body.
!>
!> Axisymmetric bodies (body%axisymmetric): the same routines on the kernels
!> of module axisymmetric_elements (x = r, y = z, the law's D4, integrals
!> over the full circle); the caller holds u_r = 0 on the axis.
!>
!> Nearly incompressible bodies (body%bbar, set by the scene when nu > 0.45
!> in plane strain or axisymmetry): the kernels' B-bar strain on the element
!> kinds that lock without it (elements' pressure_modes: the 4-node
!> quadrangle's mean dilatation), in the stiffness, the forces and the
!> stresses alike (doc/theory.md, "Nearly incompressible materials").
!>
!> Programming interface
!>   type(body_t)                      one body: name, mesh, law, thickness, dof0
!>   number_equations(fixed, eq, nfree)
!>   build_pattern(bodies, eq, nfree, k)            pattern of K_ff, values 0
!>   assemble_stiffness(bodies, eq, ubar, k, rhs [, overflow])   add K_ff to k, subtract K_fd ubar from rhs
!>   internal_forces(bodies, u, fint)               fint = K u (all dofs, element by element)
!>   element_response(bodies, u, fint [, stress, vm, adt])  both in one element loop (OpenMP, reproducible);
!>                                                  adt the state's thermal strains
!>   thermal_loads(bd, f)                           f += int B' D eps0 t dA (THERMAL), x, y axes
!>   spring_reactions(bd, u, r)                     r(:, j) = force of SPRING j of bd on it, x, y
!>   to_global_axes(bodies, v), to_local_axes(bodies, v)   v (ndof) between the solver basis and x, y
!>   body_pressure_modes(bd, nen)                   the B-bar pressure modes of bd's elements of nen nodes
!>   node_elements(mesh, ptr, list)                 elements around each node (CSR)
!>   scatter_element(m, dofs, ke, eq, ubar, k, rhs, ok)   one element matrix into K_ff and rhs
!>   scatter_springs(bd, eq, ubar, k, rhs, ok)      bd's springs likewise
!>   element_coordinates(m, e, xe), rotate_element_matrix(bd, e, ke),
!>   rotate_element_vector(bd, e, v, to_global), add_spring_forces(bd, u, f)
!>        the pieces of the assembly, for the finite-strain one (finite_strain_assembly)
!>   find_row(k, row, col)                          position of K's entry (row, col), row <= col in
!>                                                  the pattern (else where it would go)
!>   edge_outward_normal(mesh, eptr, elist, a, b, nrm, owner)  unit normal of edge a-b
!>        pointing out of its element; owner = that element, 0 when no element has
!>        the edge, -1 when two do (an interior edge)
module body
  use kinds, only: dp, i8
  use strings, only: int_to_str
  use errors, only: error_t, set_out_of_memory
  use mesh, only: mesh_t
  use sorting, only: sort_small
  use material, only: elasticity_t, von_mises
  use elements, only: element_stiffness, element_force, element_strain, quadrature_rule, shape_at, strain_operator, &
                      max_nen, pressure_modes
  use axisymmetric_elements, only: axi_element_stiffness, axi_element_force, axi_element_strain, axi_thermal_load
  use material, only: von_mises_4
  use sparse_matrix, only: csc_t
  use foundation, only: spring_set_t
  use hyperelastic, only: hyperelastic_t
  implicit none
  private
  public :: body_t, number_equations, build_pattern, assemble_stiffness, internal_forces
  public :: node_elements, element_dofs, edge_outward_normal, element_response
  public :: thermal_loads, to_global_axes, to_local_axes, axi_thermal_strain, body_pressure_modes, spring_reactions
  public :: scatter_element, scatter_springs, element_coordinates, rotate_element_matrix, rotate_element_vector
  public :: add_spring_forces, find_row

  type :: body_t
    character(len=:), allocatable :: name  !< as in the deck
    type(mesh_t) :: mesh                   !< its mesh
    type(elasticity_t) :: law              !< elasticity tensor (finite: the law's small-strain limit)
    logical :: finite = .false.            !< hyperelastic, solved in finite strain (module
                                           !< finite_strain_elements): rubber holds its law
    type(hyperelastic_t) :: rubber         !< the hyperelastic law when finite
    real(dp) :: thick = 1.0_dp             !< thickness (1 in plane strain)
    logical :: axisymmetric = .false.      !< x = r, y = z, solid of revolution (PLANE axisymmetric)
    logical :: bbar = .false.              !< B-bar strain on the elements of pressure_modes > 0
                                           !< (nearly incompressible: module header)
    integer :: dof0 = 0                    !< global dof offset
    integer :: elem0 = 0                   !< global element offset (output order)
    real(dp), allocatable :: adt(:)        !< (nelem) alpha dT per element; allocated only
                                           !< when the body has a THERMAL statement
    real(dp), allocatable :: axes(:,:)     !< (2, nnode) unit normal n of a node whose dofs are
                                           !< (u.n, u.t), [0, 0] in x, y; allocated only when a
                                           !< FIX un=/ut= holds some node of the body
    type(spring_set_t) :: springs          !< its springs to the ground (SPRING); n = 0 when none
  end type body_t


  !> Axisymmetric thermal strain per unit alpha dT, (err, ezz, grz, ett): an
  !> isotropic expansion, the same in any axes of the r-z plane.
  real(dp), parameter :: axi_thermal_strain(4) = [1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp]

  !> The elements around each node of a mesh (node_elements).
  type :: node_elements_t
    integer, allocatable :: ptr(:), list(:)
  end type node_elements_t

contains

  !> The pressure modes of the kernels for bd's elements of nen nodes: those
  !> of elements' pressure_modes when bd%bbar, else 0 (the strain B u).
  pure integer function body_pressure_modes(bd, nen) result(np)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: nen
    np = 0
    if (bd%bbar) np = pressure_modes(nen)
  end function body_pressure_modes

  !> Free equation numbers: eq(dof) = rank among free dofs, 0 for fixed dofs.
  subroutine number_equations(fixed, eq, nfree)
    logical, intent(in) :: fixed(:)
    integer, allocatable, intent(out) :: eq(:)
    integer, intent(out) :: nfree
    integer :: i
    allocate(eq(size(fixed)))
    nfree = 0
    do i = 1, size(fixed)
      if (fixed(i)) then
        eq(i) = 0
      else
        nfree = nfree + 1
        eq(i) = nfree
      end if
    end do
  end subroutine number_equations

  !> Global dofs of element e of body bd, (2 nen).
  pure subroutine element_dofs(bd, e, dofs)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    integer, intent(out) :: dofs(:)
    integer :: a
    do a = 1, bd%mesh%nen(e)
      dofs(2 * a - 1) = bd%dof0 + 2 * (bd%mesh%conn(a, e) - 1) + 1
      dofs(2 * a) = dofs(2 * a - 1) + 1
    end do
  end subroutine element_dofs

  !> Elements around each node: list(ptr(a):ptr(a+1)-1).
  subroutine node_elements(mesh, ptr, list)
    type(mesh_t), intent(in) :: mesh
    integer, allocatable, intent(out) :: ptr(:), list(:)
    integer :: e, k, a
    integer, allocatable :: next(:)
    allocate(ptr(mesh%nnode + 1), source=0)
    do e = 1, mesh%nelem
      do k = 1, mesh%nen(e)
        a = mesh%conn(k, e)
        ptr(a + 1) = ptr(a + 1) + 1
      end do
    end do
    ptr(1) = 1
    do a = 1, mesh%nnode
      ptr(a + 1) = ptr(a + 1) + ptr(a)
    end do
    allocate(list(ptr(mesh%nnode + 1) - 1), next(mesh%nnode))
    next = ptr(1:mesh%nnode)
    do e = 1, mesh%nelem
      do k = 1, mesh%nen(e)
        a = mesh%conn(k, e)
        list(next(a)) = e
        next(a) = next(a) + 1
      end do
    end do
  end subroutine node_elements

  !> Pattern of the upper triangle of K_ff from the node adjacency of every mesh.
  !>   bodies (in)  the bodies, dof0 set
  !>   eq     (in)  (ndof) free equation numbers
  !>   nfree  (in)  number of free equations
  !>   k      (out) n = nfree, colptr, rowind (sorted), val = 0
  !>   err    (out) allocated when the memory for K ran out (error_numerical)
  subroutine build_pattern(bodies, eq, nfree, k, err)
    type(body_t), intent(in) :: bodies(:)
    integer, intent(in) :: eq(:), nfree
    type(csc_t), intent(out) :: k
    type(error_t), allocatable, intent(out) :: err
    integer :: b, pass, col, nnz, stat
    type(node_elements_t), allocatable :: around(:)

    allocate(around(size(bodies)))            ! the elements around each node, for both passes
    do b = 1, size(bodies)
      call node_elements(bodies(b)%mesh, around(b)%ptr, around(b)%list)
    end do
    k%n = nfree
    allocate(k%colptr(nfree + 1))
    k%colptr = 0
    ! pass 1 counts entries per column, pass 2 fills the row indices
    do pass = 1, 2
      if (pass == 2) then
        k%colptr(1) = 1
        do col = 1, nfree
          k%colptr(col + 1) = k%colptr(col + 1) + k%colptr(col)
        end do
        nnz = k%colptr(nfree + 1) - 1
        ! K's entries, the largest arrays before the factor: one that does not
        ! fit is reported with K's size (12 bytes per entry)
        allocate(k%rowind(nnz), k%val(nnz), stat=stat)
        if (stat /= 0) then
          call set_out_of_memory(err, 'assembling K (' // int_to_str(nnz) // ' entries)', 12_i8 * nnz)
          return
        end if
      end if
      do b = 1, size(bodies)
        call pattern_pass(bodies(b), around(b), pass, eq, k)
      end do
    end do
  end subroutine build_pattern

  !> One pass of build_pattern over the nodes of one body, on the run's threads
  !> (a node writes only its own two columns): pass 1 counts the entries of
  !> each column into k%colptr(col + 1), pass 2 writes their rows (and zero
  !> values) from k%colptr(col) on.
  subroutine pattern_pass(bd, around, pass, eq, k)
    type(body_t), intent(in) :: bd
    type(node_elements_t), intent(in) :: around
    integer, intent(in) :: pass, eq(:)
    type(csc_t), intent(inout) :: k
    integer :: a, j, c, cb, col, row, nb, p, e, ie
    integer, allocatable :: mark(:), nbr(:)

    associate(m => bd%mesh, d0 => bd%dof0, eptr => around%ptr, elist => around%list)
      !$omp parallel private(mark, nbr, nb, ie, e, j, c, col, p, cb, row) &
      !$omp if(m%nnode > 20000)
      allocate(mark(m%nnode), nbr(64))
      mark = 0
      !$omp do schedule(static)
      do a = 1, m%nnode
        ! distinct neighbour nodes of a (a included), ascending
        nb = 0
        do ie = eptr(a), eptr(a + 1) - 1
          e = elist(ie)
          do j = 1, m%nen(e)
            if (mark(m%conn(j, e)) /= a) then
              mark(m%conn(j, e)) = a
              nb = nb + 1
              if (nb > size(nbr)) call grow(nbr)
              nbr(nb) = m%conn(j, e)
            end if
          end do
        end do
        call sort_small(nbr(1:nb))
        do c = 1, 2
          col = eq(d0 + 2 * (a - 1) + c)
          if (col == 0) cycle
          p = k%colptr(col)
          do j = 1, nb
            do cb = 1, 2
              row = eq(d0 + 2 * (nbr(j) - 1) + cb)
              if (row == 0 .or. row > col) cycle
              if (pass == 1) then
                k%colptr(col + 1) = k%colptr(col + 1) + 1
              else
                k%rowind(p) = row
                k%val(p) = 0.0_dp
                p = p + 1
              end if
            end do
          end do
        end do
      end do
      !$omp end do
      deallocate(mark, nbr)
      !$omp end parallel
    end associate
  end subroutine pattern_pass

  subroutine grow(a)
    integer, allocatable, intent(inout) :: a(:)
    integer, allocatable :: t(:)
    allocate(t(2 * size(a)))
    t(1:size(a)) = a
    call move_alloc(t, a)
  end subroutine grow

  !> Add the element stiffnesses into k (pattern from build_pattern) and move
  !> the prescribed values to the right-hand side: rhs_f -= K_fd ubar_d.
  !>   bodies (in) ; eq (in) (ndof) ; ubar (in) (ndof) prescribed values (fixed dofs)
  !>   k      (inout) values accumulated
  !>   rhs    (inout) (nfree) right-hand side
  !>   overflow (out, optional) the first body whose K_fd ubar_d would leave
  !>          the range of double precision (its terms then left out), 0 when
  !>          none.  Tested before each product and sum, so that no overflow
  !>          happens: a debug build traps on one
  subroutine assemble_stiffness(bodies, eq, ubar, k, rhs, overflow)
    type(body_t), intent(in) :: bodies(:)
    integer, intent(in) :: eq(:)
    real(dp), intent(in) :: ubar(:)
    type(csc_t), intent(inout) :: k
    real(dp), intent(inout) :: rhs(:)
    integer, intent(out), optional :: overflow
    integer :: b, e, nen
    integer :: dofs(2 * max_nen)
    real(dp) :: ke(2 * max_nen, 2 * max_nen), xe(2, max_nen)
    logical :: ok
    if (present(overflow)) overflow = 0
    do b = 1, size(bodies)
      associate(m => bodies(b)%mesh)
        do e = 1, m%nelem
          nen = m%nen(e)
          call element_coordinates(m, e, xe)
          if (bodies(b)%axisymmetric) then
            call axi_element_stiffness(nen, xe(:, 1:nen), bodies(b)%law%d4, ke, body_pressure_modes(bodies(b), nen))
          else
            call element_stiffness(nen, xe(:, 1:nen), bodies(b)%law%d, bodies(b)%thick, ke, &
                                   body_pressure_modes(bodies(b), nen))
          end if
          if (allocated(bodies(b)%axes)) call rotate_element_matrix(bodies(b), e, ke)   ! Q' K Q
          call element_dofs(bodies(b), e, dofs)
          call scatter_element(2 * nen, dofs, ke, eq, ubar, k, rhs, ok)
          if (.not. ok .and. present(overflow)) then
            if (overflow == 0) overflow = b
          end if
        end do
        call scatter_springs(bodies(b), eq, ubar, k, rhs, ok)
        if (.not. ok .and. present(overflow)) then
          if (overflow == 0) overflow = b
        end if
      end associate
    end do
  end subroutine assemble_stiffness

  !> The springs of bd into k and rhs (scatter_element): their nodes share an
  !> element (an edge's) or are one node, so that their entries are in the
  !> elements' pattern.
  !>   ok (out) .false. when a term of K_fd ubar_d was left out (overflow)
  subroutine scatter_springs(bd, eq, ubar, k, rhs, ok)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: eq(:)
    real(dp), intent(in) :: ubar(:)
    type(csc_t), intent(inout) :: k
    real(dp), intent(inout) :: rhs(:)
    logical, intent(out) :: ok
    real(dp) :: ke(2 * max_nen, 2 * max_nen)
    integer :: dofs(2 * max_nen), i
    logical :: ok_i
    ok = .true.
    do i = 1, bd%springs%n
      call spring_matrix(bd, i, ke, dofs)
      call scatter_element(2 * bd%springs%nen(i), dofs, ke, eq, ubar, k, rhs, ok_i)
      ok = ok .and. ok_i
    end do
  end subroutine scatter_springs

  !> An element matrix ke (m x m, on the global dofs dofs) into k on the free
  !> dofs (the upper triangle), and rhs_f -= K_fd ubar_d for the fixed ones.
  !>   m    (in)    2 nen
  !>   dofs (in)    (m) global dofs;  ke (in) (>= m, >= m) the matrix, solver basis
  !>   eq   (in)    (ndof) free equation numbers;  ubar (in) (ndof) values on the fixed dofs
  !>   k    (inout) values accumulated (pattern of build_pattern)
  !>   rhs  (inout) (nfree)
  !>   ok   (out)   .false. when a term K_fd ubar_d would overflow (left out)
  subroutine scatter_element(m, dofs, ke, eq, ubar, k, rhs, ok)
    integer, intent(in) :: m, dofs(:), eq(:)
    real(dp), intent(in) :: ke(:,:), ubar(:)
    type(csc_t), intent(inout) :: k
    real(dp), intent(inout) :: rhs(:)
    logical, intent(out) :: ok
    integer :: p, q, ep, eq_q, pos
    real(dp) :: term
    logical :: fits
    ok = .true.
    do q = 1, m
      eq_q = eq(dofs(q))
      do p = 1, m
        ep = eq(dofs(p))
        if (ep == 0) cycle
        if (eq_q == 0) then
          call in_range(ke(p, q), ubar(dofs(q)), rhs(ep), term, fits)
          if (fits) then
            rhs(ep) = rhs(ep) - term                          ! f_f -= K_fd ubar_d
          else
            ok = .false.
          end if
        else if (ep <= eq_q) then
          pos = find_row(k, ep, eq_q)
          k%val(pos) = k%val(pos) + ke(p, q)
        end if
      end do
    end do
  end subroutine scatter_element

  !> Spring element i of bd: its matrix in the solver basis (Q' K Q at the
  !> nodes in local axes) and its dofs, two per node.
  !>   ke   (out) (2 max_nen, 2 max_nen), ke(1:2 nen, 1:2 nen) set
  !>   dofs (out) (2 max_nen), dofs(1:2 nen) set
  pure subroutine spring_matrix(bd, i, ke, dofs)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: i
    real(dp), intent(out) :: ke(:,:)
    integer, intent(out) :: dofs(:)
    integer :: a, nen
    nen = bd%springs%nen(i)
    ke(1:2 * nen, 1:2 * nen) = bd%springs%k(1:2 * nen, 1:2 * nen, i)
    if (allocated(bd%axes)) call rotate_node_matrix(bd, bd%springs%nodes(1:nen, i), ke)
    do a = 1, nen
      dofs(2 * a - 1) = bd%dof0 + 2 * (bd%springs%nodes(a, i) - 1) + 1
      dofs(2 * a) = dofs(2 * a - 1) + 1
    end do
  end subroutine spring_matrix

  !> f += K_s u over the springs of bd (solver basis).
  pure subroutine add_spring_forces(bd, u, f)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:)
    real(dp), intent(inout) :: f(:)
    real(dp) :: ke(2 * max_nen, 2 * max_nen)
    integer :: dofs(2 * max_nen), i, n
    do i = 1, bd%springs%n
      n = 2 * bd%springs%nen(i)
      call spring_matrix(bd, i, ke, dofs)
      f(dofs(1:n)) = f(dofs(1:n)) + matmul(ke(1:n, 1:n), u(dofs(1:n)))
    end do
  end subroutine add_spring_forces

  !> The force of each SPRING statement of bd on the body, -K_s u summed over
  !> its spring elements, in x, y components (the force of a foundation that
  !> holds the body up is positive along y, as a FIX's reaction).
  !>   u (in)  (ndof) displacement, solver basis
  !>   r (out) (2, nspring) one column per SPRING statement of the body
  subroutine spring_reactions(bd, u, r)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: r(:,:)
    real(dp) :: ue(6), fe(6), q(2, 2)
    integer :: i, a, n, d
    logical :: local
    r = 0.0_dp
    do i = 1, bd%springs%n
      n = bd%springs%nen(i)
      do a = 1, n
        d = bd%dof0 + 2 * (bd%springs%nodes(a, i) - 1)
        ue(2 * a - 1:2 * a) = u(d + 1:d + 2)
        call axes_of_node(bd, bd%springs%nodes(a, i), q, local)
        if (local) ue(2 * a - 1:2 * a) = matmul(q, ue(2 * a - 1:2 * a))      ! Q u: x, y components
      end do
      fe(1:2 * n) = matmul(bd%springs%k(1:2 * n, 1:2 * n, i), ue(1:2 * n))
      do a = 1, n
        r(:, bd%springs%owner(i)) = r(:, bd%springs%owner(i)) - fe(2 * a - 1:2 * a)
      end do
    end do
  end subroutine spring_reactions

  !> ok = .true. with term = a * x when both a * x and s - a * x are finite,
  !> tested without computing an overflowing value.
  pure subroutine in_range(a, x, s, term, ok)
    real(dp), intent(in) :: a, x, s
    real(dp), intent(out) :: term
    logical, intent(out) :: ok
    term = 0.0_dp
    ok = abs(x) <= 1.0_dp                       ! (no short-circuit .or.: |x| > 1 before dividing)
    if (.not. ok) ok = abs(a) <= huge(1.0_dp) / abs(x)
    if (.not. ok) return
    term = a * x
    ok = abs(s) <= huge(1.0_dp) - abs(term)
  end subroutine in_range

  !> The node coordinates of element e of m into xe(:, 1:nen), gathered node
  !> by node (an array section with a vector subscript would make an array
  !> temporary on the heap at every element).
  pure subroutine element_coordinates(m, e, xe)
    type(mesh_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp), intent(inout) :: xe(:,:)
    integer :: a
    do a = 1, m%nen(e)
      xe(:, a) = m%x(:, m%conn(a, e))
    end do
  end subroutine element_coordinates

  !> ke = Q' ke Q for the nodes of element e in local axes (Q = [n t] on
  !> their two dofs, the identity elsewhere).
  pure subroutine rotate_element_matrix(bd, e, ke)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    real(dp), intent(inout) :: ke(:,:)
    call rotate_node_matrix(bd, bd%mesh%conn(1:bd%mesh%nen(e), e), ke)
  end subroutine rotate_element_matrix

  !> ke = Q' ke Q for the matrix on the nodes given (dofs 2a-1, 2a of node a).
  pure subroutine rotate_node_matrix(bd, nodes, ke)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: nodes(:)
    real(dp), intent(inout) :: ke(:,:)
    integer :: a, i, n
    real(dp) :: q(2, 2)
    logical :: local
    n = 2 * size(nodes)
    do a = 1, size(nodes)
      call axes_of_node(bd, nodes(a), q, local)
      if (.not. local) cycle
      i = 2 * a - 1
      ke(i:i + 1, 1:n) = matmul(transpose(q), ke(i:i + 1, 1:n))
      ke(1:n, i:i + 1) = matmul(ke(1:n, i:i + 1), q)
    end do
  end subroutine rotate_node_matrix

  !> v = Q v (to_global) or v = Q' v on the nodes of element e in local axes.
  pure subroutine rotate_element_vector(bd, e, v, to_global)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    real(dp), intent(inout) :: v(:)
    logical, intent(in) :: to_global
    integer :: a, i
    real(dp) :: q(2, 2)
    logical :: local
    do a = 1, bd%mesh%nen(e)
      call axes_of_node(bd, bd%mesh%conn(a, e), q, local)
      if (.not. local) cycle
      i = 2 * a - 1
      v(i:i + 1) = turn(q, v(i:i + 1), to_global)
    end do
  end subroutine rotate_element_vector

  !> Q v (to_global) or Q' v.
  pure function turn(q, v, to_global) result(w)
    real(dp), intent(in) :: q(2, 2), v(2)
    logical, intent(in) :: to_global
    real(dp) :: w(2)
    if (to_global) then
      w = matmul(q, v)
    else
      w = matmul(v, q)                            ! Q' v
    end if
  end function turn

  !> Q = [n t] of node a, t = (-n_y, n_x); local false when a is in x, y axes.
  pure subroutine axes_of_node(bd, a, q, local)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: a
    real(dp), intent(out) :: q(2, 2)
    logical, intent(out) :: local
    local = .false.
    q = 0.0_dp
    if (.not. allocated(bd%axes)) return
    if (all(bd%axes(:, a) == 0.0_dp)) return
    local = .true.
    q(:, 1) = bd%axes(:, a)
    q(:, 2) = [-bd%axes(2, a), bd%axes(1, a)]
  end subroutine axes_of_node

  !> v (ndof, solver basis) to x, y components: v_a = Q_a v_a at every node
  !> in local axes.
  subroutine to_global_axes(bodies, v)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(inout) :: v(:)
    call rotate_nodes(bodies, v, .true.)
  end subroutine to_global_axes

  !> v (ndof, x, y components) to the solver basis: v_a = Q_a' v_a.
  subroutine to_local_axes(bodies, v)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(inout) :: v(:)
    call rotate_nodes(bodies, v, .false.)
  end subroutine to_local_axes

  subroutine rotate_nodes(bodies, v, to_global)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(inout) :: v(:)
    logical, intent(in) :: to_global
    integer :: b, a, i
    real(dp) :: q(2, 2)
    logical :: local
    do b = 1, size(bodies)
      if (.not. allocated(bodies(b)%axes)) cycle
      do a = 1, bodies(b)%mesh%nnode
        call axes_of_node(bodies(b), a, q, local)
        if (.not. local) cycle
        i = bodies(b)%dof0 + 2 * a - 1
        v(i:i + 1) = turn(q, v(i:i + 1), to_global)
      end do
    end do
  end subroutine rotate_nodes

  !> Position of (row, col) in k by bisection over the sorted column.
  pure integer function find_row(k, row, col) result(pos)
    type(csc_t), intent(in) :: k
    integer, intent(in) :: row, col
    integer :: lo, hi, mid
    lo = k%colptr(col)
    hi = k%colptr(col + 1) - 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (k%rowind(mid) < row) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
    pos = lo
  end function find_row

  !> fint = K u over all dofs, element by element and spring by spring
  !> (reactions, energy).
  subroutine internal_forces(bodies, u, fint)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: fint(:)
    integer :: b, e, nen
    integer :: dofs(2 * max_nen)
    real(dp) :: fe(2 * max_nen), xe(2, max_nen), ue(2 * max_nen)
    fint = 0.0_dp
    do b = 1, size(bodies)
      associate(m => bodies(b)%mesh)
        do e = 1, m%nelem
          nen = m%nen(e)
          call element_dofs(bodies(b), e, dofs)
          call element_coordinates(m, e, xe)
          ue(1:2 * nen) = u(dofs(1:2 * nen))
          if (allocated(bodies(b)%axes)) call rotate_element_vector(bodies(b), e, ue, .true.)    ! Q u
          if (bodies(b)%axisymmetric) then
            call axi_element_force(nen, xe(:, 1:nen), bodies(b)%law%d4, ue(1:2 * nen), fe(1:2 * nen), &
                                   body_pressure_modes(bodies(b), nen))
          else
            call element_force(nen, xe(:, 1:nen), bodies(b)%law%d, bodies(b)%thick, ue(1:2 * nen), fe(1:2 * nen), &
                               body_pressure_modes(bodies(b), nen))
          end if
          if (allocated(bodies(b)%axes)) call rotate_element_vector(bodies(b), e, fe, .false.)   ! Q' f
          fint(dofs(1:2 * nen)) = fint(dofs(1:2 * nen)) + fe(1:2 * nen)
        end do
        call add_spring_forces(bodies(b), u, fint)
      end associate
    end do
  end subroutine internal_forces

  !> Outward unit normal of the edge a-b (see the module header).
  subroutine edge_outward_normal(mesh, eptr, elist, a, b, nrm, owner)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: eptr(:), elist(:), a, b
    real(dp), intent(out) :: nrm(2)
    integer, intent(out) :: owner
    integer :: ie, e
    real(dp) :: t(2), xc(2)
    owner = 0
    nrm = 0.0_dp
    do ie = eptr(a), eptr(a + 1) - 1
      e = elist(ie)
      if (any(mesh%conn(1:mesh%nen(e), e) == b)) then
        if (owner /= 0) then
          owner = -1
          return
        end if
        owner = e
      end if
    end do
    if (owner == 0) return
    t = mesh%x(:, b) - mesh%x(:, a)
    nrm = [t(2), -t(1)] / norm2(t)
    xc = sum(mesh%x(:, mesh%conn(1:mesh%nen(owner), owner)), dim=2) / mesh%nen(owner)
    if (dot_product(nrm, xc - mesh%x(:, a)) > 0.0_dp) nrm = -nrm
  end subroutine edge_outward_normal

  !> Nodal forces of the thermal strains, f = int B' D eps0 t dA, added to f
  !> (eps0 = alpha dT eth per element; the body must have adt allocated);
  !> axisymmetric: eps0 = alpha dT (1, 1, 0, 1), the hoop strain included.
  !> With B-bar (bd%bbar) the same: eps0 is constant on the element, and
  !> int (B_bar - B)' dV D eps0 = 0 since the projection keeps constants.
  subroutine thermal_loads(bd, f)
    type(body_t), intent(in) :: bd
    real(dp), intent(inout) :: f(:)
    real(dp), allocatable :: xi(:,:), w(:)
    real(dp) :: shp(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen), s0(3), fe(2 * max_nen)
    integer :: e, nen, q
    integer :: dofs(2 * max_nen)
    associate(m => bd%mesh)
      do e = 1, m%nelem
        if (bd%adt(e) == 0.0_dp) cycle
        nen = m%nen(e)
        if (bd%axisymmetric) then                         ! int B4' D4 eps0 2 pi r dA
          call element_dofs(bd, e, dofs)
          call axi_thermal_load(nen, m%x(:, m%conn(1:nen, e)), matmul(bd%law%d4, axi_thermal_strain) * bd%adt(e), &
                                fe(1:2 * nen))
          f(dofs(1:2 * nen)) = f(dofs(1:2 * nen)) + fe(1:2 * nen)
          cycle
        end if
        s0 = matmul(bd%law%d, bd%law%eth) * bd%adt(e)     ! D eps0
        call quadrature_rule(nen, 1, xi, w)
        call element_dofs(bd, e, dofs)
        do q = 1, size(w)
          call shape_at(nen, m%x(:, m%conn(1:nen, e)), xi(:, q), shp(1:nen), dndx(:, 1:nen), detj)
          call strain_operator(nen, dndx(:, 1:nen), b(:, 1:2 * nen))
          f(dofs(1:2 * nen)) = f(dofs(1:2 * nen)) + (w(q) * detj * bd%thick) * matmul(transpose(b(:, 1:2 * nen)), s0)
        end do
      end do
    end associate
  end subroutine thermal_loads

  !> Stresses, von Mises and internal forces fint = K u in one element loop,
  !> stress(3, nelem) sxx syy sxy, or stress(4, nelem) srr szz srz stt for
  !> axisymmetric bodies,
  !> threaded with OpenMP.  The element forces are kept per element and added
  !> into fint afterwards in element order, so the result does not depend on
  !> the threads' timing (bit-for-bit reproducible runs).
  subroutine element_response(bodies, u, fint, stress, vm, adt)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: fint(:)
    real(dp), intent(out), optional :: stress(:,:), vm(:)    !< skipped when absent
    real(dp), intent(in), optional :: adt(:)      !< (nelem) the state's alpha dT per element (bodies(b)%elem0 + e);
                                                  !< needed with stress when a body has THERMAL
    integer :: b, e, nen, ge
    integer :: dofs(2 * max_nen)
    real(dp) :: eps(3), eps4(4), xe(2, max_nen), ue(2 * max_nen)
    real(dp), allocatable :: fe(:,:)
    fint = 0.0_dp
    do b = 1, size(bodies)
      associate(m => bodies(b)%mesh, bd => bodies(b))
        allocate(fe(2 * maxval(m%nen), m%nelem))
        !$omp parallel do private(e, nen, ge, dofs, eps, eps4, xe, ue) schedule(static)
        do e = 1, m%nelem
          nen = m%nen(e)
          ge = bd%elem0 + e
          call element_dofs(bd, e, dofs)
          call element_coordinates(m, e, xe)
          ue(1:2 * nen) = u(dofs(1:2 * nen))
          if (allocated(bd%axes)) call rotate_element_vector(bd, e, ue, .true.)            ! Q u
          if (bd%axisymmetric) then
            call axi_element_force(nen, xe(:, 1:nen), bd%law%d4, ue(1:2 * nen), fe(1:2 * nen, e), &
                                   body_pressure_modes(bd, nen))
          else
            call element_force(nen, xe(:, 1:nen), bd%law%d, bd%thick, ue(1:2 * nen), fe(1:2 * nen, e), &
                               body_pressure_modes(bd, nen))
          end if
          if (allocated(bd%axes)) call rotate_element_vector(bd, e, fe(:, e), .false.)     ! Q' f
          if (.not. present(stress)) cycle
          if (bd%axisymmetric) then                     ! (srr, szz, srz, stt) = D4 (eps - alpha dT eth4)
            call axi_element_strain(nen, xe(:, 1:nen), ue(1:2 * nen), eps4, body_pressure_modes(bd, nen))
            if (allocated(bd%adt)) eps4 = eps4 - adt(ge) * axi_thermal_strain
            stress(1:4, ge) = matmul(bd%law%d4, eps4)
            vm(ge) = von_mises_4(stress(1:4, ge))
            cycle
          end if
          call element_strain(nen, xe(:, 1:nen), ue(1:2 * nen), eps, body_pressure_modes(bd, nen))
          if (allocated(bd%adt)) then                   ! sigma = D (eps - alpha dT eth)
            stress(:, ge) = matmul(bd%law%d, eps - adt(ge) * bd%law%eth)
            vm(ge) = von_mises(bd%law, stress(:, ge), adt(ge))
          else
            stress(:, ge) = matmul(bd%law%d, eps)
            vm(ge) = von_mises(bd%law, stress(:, ge))
          end if
        end do
        !$omp end parallel do
        do e = 1, m%nelem                               ! fint += fe, in element order
          nen = m%nen(e)
          call element_dofs(bd, e, dofs)
          fint(dofs(1:2 * nen)) = fint(dofs(1:2 * nen)) + fe(1:2 * nen, e)
        end do
        call add_spring_forces(bd, u, fint)
        deallocate(fe)
      end associate
    end do
  end subroutine element_response

end module body
