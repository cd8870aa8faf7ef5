!> mesh: the 2D mesh of one body, P1 triangles and Q1 quadrilaterals, or their
!> quadratic kin (6-node triangles, 8- and 9-node quadrilaterals), with named
!> boundaries (chains of edges), named point sets and named element regions.
!>
!> Node-last layouts: x(2, nnode), conn(w, nelem) with w = 4 for a linear mesh
!> and 9 when it has quadratic elements.  Element e has nen(e) = 3, 4, 6, 8 or 9
!> nodes conn(1:nen(e), e): corners counter-clockwise after finalize_mesh, then
!> the mid-side nodes (edge k from corner k to k + 1), then the centre (module
!> elements); conn(nen(e) + 1:, e) = 0.  On a quadratic mesh every boundary edge
!> has its mid-side node in mid(:).
!>
!> Programming interface
!>   type(mesh_t), type(boundary_t), type(region_t)
!>   finalize_mesh(mesh, file, diag)   drop nodes no element uses (renumbering the
!>        boundaries), orient every element counter-clockwise when the whole mesh
!>        is clockwise, and report to diag: no elements, mixed orientation
!>        (inverted elements), degenerate or non-convex elements, boundary edges
!>        or points that name nodes outside the mesh
!>   find_name(mesh%bnd, name)  index of the boundary or point set called name
!>        (mesh%reg: of the region), 0 when there is none
!>   name_list(mesh%bnd, none)  the names, 'a, b, c' (none: the text when there is none)
!>   boundary_nodes(b, nodes)   sorted distinct nodes of a boundary or point set
!>        (the mid-side nodes of its edges too)
!>   is_quadratic(mesh)         whether the mesh has 6-, 8- or 9-node elements
!>   element_area(mesh, e)      signed area of element e
!>   order_for_locality(mesh)   renumber nodes along a Hilbert curve and elements
!>        by their lowest node, so that neighbours in the mesh are neighbours in
!>        memory; the file's numbering is kept for output and messages
!>   file_item(mesh, p, element)  the node that is node p of the mesh file (with
!>        element, the element that is element p)
!>   node_in_file(mesh, a)      the number in the mesh file of node a
!>   hilbert_index(bits, x, y)  index of cell (x, y) along the Hilbert curve
!>        through a 2**bits x 2**bits grid
module mesh
  use kinds, only: dp, i8
  use strings, only: int_to_str
  use errors, only: diag_t, add_error
  use sorting, only: sort_integers, sort_by_counts
  use elements, only: corner_count, quadrature_rule, shape_at, max_nen
  implicit none
  private
  public :: mesh_t, named_t, boundary_t, region_t, finalize_mesh, find_name, name_list
  public :: boundary_nodes, element_area, mesh_size, is_quadratic
  public :: order_for_locality, file_item, node_in_file, hilbert_index, locality_min_nodes

  !> Meshes of more nodes than this are renumbered for locality.  Below it the
  !> arrays stay in the cache and the renumbering does not pay for itself
  !> (measured in doc/performance.md, "A mesh file's numbering and the solver's").
  integer, parameter :: locality_min_nodes = 65536

  !> A named boundary: a set of edges (a physical curve) or of points.
  !> What boundaries and regions share: a name, by which find_name looks them up.
  type :: named_t
    character(len=:), allocatable :: name   !< case-sensitive name
  end type named_t

  type, extends(named_t) :: boundary_t
    integer :: nseg = 0                     !< number of edges
    integer, allocatable :: seg(:,:)        !< (2, nseg) node ids of each edge
    integer, allocatable :: seg_line(:)     !< (nseg) line of each edge in its mesh file (when read)
    integer, allocatable :: mid(:)          !< (nseg) mid-side node of each edge (3-node edges of a
                                            !< quadratic mesh); not allocated on a linear mesh
    integer :: npoint = 0                   !< number of points (physical points)
    integer, allocatable :: points(:)       !< (npoint) node ids
  end type boundary_t

  !> A named set of elements (a physical surface).
  type, extends(named_t) :: region_t
    integer, allocatable :: elems(:)        !< element ids
  end type region_t

  !> The numbering of the mesh file, when order_for_locality renumbered the
  !> mesh (not allocated: the mesh keeps the file's numbering).
  type :: file_numbering_t
    integer, allocatable :: node_file(:)    !< (nnode) number in the mesh file of each node
    integer, allocatable :: file_nodes(:)   !< (nnode) node at each number of the mesh file
    integer, allocatable :: file_elems(:)   !< (nelem) element at each number of the mesh file
  end type file_numbering_t

  type :: mesh_t
    integer :: nnode = 0                    !< number of nodes
    integer :: nelem = 0                    !< number of elements
    real(dp), allocatable :: x(:,:)         !< (2, nnode) coordinates
    integer, allocatable :: nen(:)          !< (nelem) nodes per element, 3, 4, 6, 8 or 9
    integer, allocatable :: conn(:,:)       !< (4 or 9, nelem) connectivity
    integer, allocatable :: elem_line(:)    !< (nelem) line of each element in its mesh file (when read)
    type(boundary_t), allocatable :: bnd(:) !< named boundaries and point sets
    type(region_t), allocatable :: reg(:)   !< named element regions
    type(file_numbering_t) :: file          !< the mesh file's numbering (order_for_locality)
  end type mesh_t

contains

  !> Compact, orient and check a mesh just read; see the module header.
  !>   mesh (inout) the mesh; on return nodes are 1..nnode all used by elements
  !>   file (in)    name for messages
  !>   diag (inout) receives one message per defect (at most a few of each kind)
  subroutine finalize_mesh(mesh, file, diag)
    type(mesh_t), intent(inout) :: mesh
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer, allocatable :: newid(:)
    integer :: e, k, n, nneg, npos, nbad, b, nerr0
    real(dp) :: a, h2, scale
    real(dp), allocatable :: area(:)

    nerr0 = diag%count
    if (mesh%nelem <= 0) then
      call add_error(diag, file, 0, 'mesh has no 2D elements (triangles or quadrilaterals expected)')
      return
    end if
    do e = 1, mesh%nelem
      do k = 1, mesh%nen(e)
        if (mesh%conn(k, e) < 1 .or. mesh%conn(k, e) > mesh%nnode) then
          call add_error(diag, file, 0, 'element ' // int_to_str(e) // ' refers to a node that does not exist')
          return
        end if
      end do
    end do

    ! Quadratic meshes: all elements quadratic (a linear neighbour would not
    ! conform), every boundary edge with its mid-side node; linear meshes none.
    if (is_quadratic(mesh)) then
      if (any(mesh%nen <= 4)) then
        call add_error(diag, file, 0, 'mesh mixes linear and quadratic elements (all of one order expected)')
        return
      end if
    end if
    if (allocated(mesh%bnd)) then
      do b = 1, size(mesh%bnd)
        if (mesh%bnd(b)%nseg == 0) cycle
        if (is_quadratic(mesh) .and. .not. allocated(mesh%bnd(b)%mid)) then
          n = 0
        else if (is_quadratic(mesh)) then
          n = count(mesh%bnd(b)%mid(1:mesh%bnd(b)%nseg) == 0)
        else
          n = 0
          if (allocated(mesh%bnd(b)%mid)) n = count(mesh%bnd(b)%mid(1:mesh%bnd(b)%nseg) /= 0)
          if (n > 0) then
            call add_error(diag, file, 0, 'boundary "' // mesh%bnd(b)%name // &
              '" has 3-node edges on a mesh of linear elements (2-node lines expected)')
            return
          end if
          cycle
        end if
        if (n > 0 .or. .not. allocated(mesh%bnd(b)%mid)) then
          call add_error(diag, file, 0, 'boundary "' // mesh%bnd(b)%name // &
            '" has 2-node edges on a mesh of quadratic elements (3-node lines expected: mesh with gmsh -order 2)')
          return
        end if
      end do
    end if

    ! New numbering: the used nodes, in their old order.
    allocate(newid(mesh%nnode), source=0)
    do e = 1, mesh%nelem
      newid(mesh%conn(1:mesh%nen(e), e)) = 1
    end do
    n = 0
    do k = 1, mesh%nnode
      if (newid(k) /= 0) then
        n = n + 1
        newid(k) = n
        mesh%x(:, n) = mesh%x(:, k)
      end if
    end do
    if (n < mesh%nnode) then
      mesh%x = mesh%x(:, 1:n)
      do e = 1, mesh%nelem
        mesh%conn(1:mesh%nen(e), e) = newid(mesh%conn(1:mesh%nen(e), e))
      end do
      if (allocated(mesh%bnd)) then
        do b = 1, size(mesh%bnd)
          call renumber_boundary(mesh%bnd(b), newid, mesh%nnode, file, diag)
        end do
      end if
      mesh%nnode = n
    else if (allocated(mesh%bnd)) then
      do b = 1, size(mesh%bnd)
        call renumber_boundary(mesh%bnd(b), newid, mesh%nnode, file, diag)
      end do
    end if
    ! a boundary left with old node numbers (a node of no element) must not be used below
    if (diag%count > nerr0) return

    ! Boundary edges of zero length (two distinct nodes at one point).
    if (allocated(mesh%bnd)) then
      scale = maxval(abs(mesh%x(:, 1:mesh%nnode)))
      do b = 1, size(mesh%bnd)
        do k = 1, mesh%bnd(b)%nseg
          if (norm2(mesh%x(:, mesh%bnd(b)%seg(2, k)) - mesh%x(:, mesh%bnd(b)%seg(1, k))) <= 1.0e-12_dp * scale) then
            n = 0
            if (allocated(mesh%bnd(b)%seg_line)) n = mesh%bnd(b)%seg_line(k)
            call add_error(diag, file, n, 'boundary "' // mesh%bnd(b)%name // '" has a zero-length edge (nodes ' // &
              int_to_str(mesh%bnd(b)%seg(1, k)) // ' and ' // int_to_str(mesh%bnd(b)%seg(2, k)) // &
              ' at the same point; distinct points expected)')
            return
          end if
        end do
      end do
    end if

    ! Orientation: the mesh must be consistently oriented; flip it when it is
    ! clockwise throughout.  Degenerate: |area| below 1e-12 of the element's
    ! squared longest edge.
    allocate(area(mesh%nelem))
    nneg = 0; npos = 0; nbad = 0
    do e = 1, mesh%nelem
      area(e) = element_area(mesh, e)
      h2 = longest_edge2(mesh, e)
      if (.not. (abs(area(e)) > 1.0e-12_dp * h2)) then
        nbad = nbad + 1
        if (nbad <= 5) call add_error(diag, file, source_line(mesh, e), 'element ' // int_to_str(e) // &
          ' is degenerate (zero area; distinct, non-collinear nodes expected)')
      else if (area(e) < 0.0_dp) then
        nneg = nneg + 1
      else
        npos = npos + 1
      end if
    end do
    if (nbad > 0) return
    if (nneg > 0 .and. npos > 0) then
      ! report the minority as inverted
      nbad = 0
      scale = merge(1.0_dp, -1.0_dp, npos >= nneg)
      do e = 1, mesh%nelem
        if (area(e) * scale < 0.0_dp) then
          nbad = nbad + 1
          if (nbad <= 5) call add_error(diag, file, source_line(mesh, e), 'element ' // int_to_str(e) // &
            ' is inverted (its orientation is opposite to the rest of the mesh)')
        end if
      end do
      return
    end if
    if (nneg > 0) then
      do e = 1, mesh%nelem
        k = mesh%nen(e)
        if (k <= 4) then
          mesh%conn(1:k, e) = mesh%conn(k:1:-1, e)
        else                            ! corners 1, nc, ..., 2; mid-sides in reverse
          n = corner_count(k)
          mesh%conn(2:n, e) = mesh%conn(n:2:-1, e)
          mesh%conn(n + 1:2 * n, e) = mesh%conn(2 * n:n + 1:-1, e)
        end if
      end do
    end if
    ! Quadrilaterals must be strictly convex (positive Jacobian at each corner).
    nbad = 0
    do e = 1, mesh%nelem
      if (corner_count(mesh%nen(e)) /= 4) cycle
      a = min_corner_cross(mesh, e)
      if (.not. (a > 1.0e-12_dp * longest_edge2(mesh, e))) then
        nbad = nbad + 1
        if (nbad <= 5) call add_error(diag, file, source_line(mesh, e), 'quadrilateral ' // int_to_str(e) // &
          ' is not convex (a convex quadrilateral with positive corner angles below 180 degrees expected)')
      end if
    end do
    if (nbad > 0) return
    ! Quadratic elements: a mid-side node far from its edge's middle folds the
    ! element (Jacobian <= 0 somewhere); checked at the stiffness points and nodes.
    do e = 1, mesh%nelem
      if (mesh%nen(e) <= 4) cycle
      if (.not. (min_jacobian(mesh, e) > 1.0e-12_dp * longest_edge2(mesh, e))) then
        nbad = nbad + 1
        if (nbad <= 5) call add_error(diag, file, source_line(mesh, e), 'element ' // int_to_str(e) // &
          ' is folded (Jacobian <= 0 inside: a mid-side node far from its edge''s middle; ' // &
          'mid-side nodes near the middle of their edges expected)')
      end if
    end do
  end subroutine finalize_mesh

  !> Smallest Jacobian determinant of element e at its stiffness points and nodes.
  real(dp) function min_jacobian(mesh, e) result(jmin)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    real(dp), allocatable :: xi(:,:), w(:)
    real(dp), parameter :: tri_nodes(2, 6) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
      0.5_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp, 0.5_dp], [2, 6])
    real(dp), parameter :: quad_nodes(2, 9) = reshape([-1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, &
      -1.0_dp, 1.0_dp, 0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 9])
    real(dp) :: xe(2, max_nen), n(max_nen), dndx(2, max_nen), detj
    integer :: q, nen
    nen = mesh%nen(e)
    xe(:, 1:nen) = mesh%x(:, mesh%conn(1:nen, e))
    call quadrature_rule(nen, 1, xi, w)
    jmin = huge(1.0_dp)
    do q = 1, size(w)
      call shape_at(nen, xe(:, 1:nen), xi(:, q), n(1:nen), dndx(:, 1:nen), detj)
      jmin = min(jmin, detj)
    end do
    do q = 1, nen
      if (corner_count(nen) == 3) then
        call shape_at(nen, xe(:, 1:nen), tri_nodes(:, q), n(1:nen), dndx(:, 1:nen), detj)
      else
        call shape_at(nen, xe(:, 1:nen), quad_nodes(:, q), n(1:nen), dndx(:, 1:nen), detj)
      end if
      jmin = min(jmin, detj)
    end do
  end function min_jacobian

  !> Whether the mesh has quadratic elements (6, 8 or 9 nodes).
  pure logical function is_quadratic(mesh)
    type(mesh_t), intent(in) :: mesh
    is_quadratic = .false.
    if (allocated(mesh%nen)) is_quadratic = any(mesh%nen > 4)
  end function is_quadratic

  subroutine renumber_boundary(b, newid, nold, file, diag)
    type(boundary_t), intent(inout) :: b
    integer, intent(in) :: newid(:), nold
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer :: k, j
    do k = 1, b%nseg
      do j = 1, 2
        if (.not. renumbered(b%seg(j, k))) return
      end do
      if (allocated(b%mid)) then          ! the middle of a 3-node edge
        if (.not. renumbered(b%mid(k))) return
      end if
    end do
    do k = 1, b%npoint
      if (b%points(k) < 1 .or. b%points(k) > nold) then
        call add_error(diag, file, 0, 'point set "' // b%name // '" refers to a node that does not exist')
        return
      end if
      if (newid(b%points(k)) == 0) then
        call add_error(diag, file, 0, 'point set "' // b%name // &
          '" names a node that belongs to no element (a mesh node expected)')
        return
      end if
      b%points(k) = newid(b%points(k))
    end do
  contains
    !> node = newid(node) for a node of an edge; .false. (and a message) when it
    !> does not exist or belongs to no element
    logical function renumbered(node) result(ok)
      integer, intent(inout) :: node
      ok = .false.
      if (node < 1 .or. node > nold) then
        call add_error(diag, file, 0, 'boundary "' // b%name // '" refers to a node that does not exist')
        return
      end if
      if (newid(node) == 0) then
        call add_error(diag, file, 0, 'boundary "' // b%name // &
          '" has an edge whose nodes belong to no element (edges on the body''s boundary expected)')
        return
      end if
      node = newid(node)
      ok = .true.
    end function renumbered
  end subroutine renumber_boundary

  !> Renumber the nodes of a finalized mesh in the order of a Hilbert curve
  !> through their positions, and the elements by their lowest node.  A mesh
  !> generator's numbering (gmsh's: an element's three nodes some 150,000
  !> numbers apart on a million-node mesh) makes every element touch as many
  !> cache lines as it has nodes in each array that the assembly, the matrix
  !> pattern and the orderings read; in this order they are neighbours.
  !> Both orders are stable, so the result depends only on the mesh.
  subroutine order_for_locality(mesh)
    type(mesh_t), intent(inout) :: mesh
    integer, allocatable :: perm(:), key(:), inv(:)
    integer(i8), allocatable :: h(:)
    logical, allocatable :: in_reg(:)
    real(dp), allocatable :: xnew(:,:)
    integer, allocatable :: cnew(:,:), nnew(:)
    real(dp) :: lo(2), span, scale
    integer :: a, e, b, k, n, bits, top
    n = mesh%nnode
    if (n < 2 .or. mesh%nelem < 2) return
    lo = minval(mesh%x(:, 1:n), dim=2)
    span = maxval(maxval(mesh%x(:, 1:n), dim=2) - lo)
    if (.not. (span > 0.0_dp)) return
    ! a grid of 2**bits cells a side, some 16 cells per node (16 bits at most)
    bits = 2
    do while (bits < 16 .and. 4_i8**bits < 16_i8 * n)
      bits = bits + 1
    end do
    top = 2**bits - 1
    scale = real(2**bits, dp) / span
    allocate(h(n), key(max(n, mesh%nelem)))
    !$omp parallel do if(n > 65536)
    do a = 1, n
      h(a) = hilbert_index(bits, min(top, int((mesh%x(1, a) - lo(1)) * scale)), &
                           min(top, int((mesh%x(2, a) - lo(2)) * scale)))
    end do
    !$omp end parallel do
    ! nodes: by the low 16 bits of the curve index, then (stably) the high 16
    allocate(perm(max(n, mesh%nelem)), inv(max(n, mesh%nelem)), xnew(2, n))
    do a = 1, n
      perm(a) = a
    end do
    key(1:n) = int(iand(h, 65535_i8))
    call sort_by_counts(key(1:n), 65536, perm(1:n))
    key(1:n) = int(shiftr(h, 16))
    call sort_by_counts(key(1:n), 65536, perm(1:n))
    !$omp parallel if(n > 65536)
    !$omp do
    do a = 1, n
      inv(perm(a)) = a                               ! perm(new) = old, inv(old) = new
    end do
    !$omp do
    do a = 1, n
      xnew(:, a) = mesh%x(:, perm(a))
    end do
    !$omp do private(k)
    do e = 1, mesh%nelem
      do k = 1, mesh%nen(e)
        mesh%conn(k, e) = inv(mesh%conn(k, e))
      end do
    end do
    !$omp end parallel
    mesh%file%node_file = perm(1:n)
    mesh%file%file_nodes = inv(1:n)
    call move_alloc(xnew, mesh%x)
    if (allocated(mesh%bnd)) then
      do b = 1, size(mesh%bnd)
        do k = 1, mesh%bnd(b)%nseg
          mesh%bnd(b)%seg(:, k) = inv(mesh%bnd(b)%seg(:, k))
        end do
        do k = 1, mesh%bnd(b)%npoint
          mesh%bnd(b)%points(k) = inv(mesh%bnd(b)%points(k))
        end do
        if (allocated(mesh%bnd(b)%mid)) mesh%bnd(b)%mid = inv(mesh%bnd(b)%mid)
      end do
    end if
    ! elements: by their lowest node
    !$omp parallel do private(k) if(n > 65536)
    do e = 1, mesh%nelem
      perm(e) = e
      key(e) = mesh%conn(1, e)
      do k = 2, mesh%nen(e)
        key(e) = min(key(e), mesh%conn(k, e))
      end do
      key(e) = key(e) - 1
    end do
    !$omp end parallel do
    call sort_by_counts(key(1:mesh%nelem), n, perm(1:mesh%nelem))
    allocate(cnew(size(mesh%conn, 1), mesh%nelem), nnew(mesh%nelem))
    !$omp parallel do if(n > 65536)
    do e = 1, mesh%nelem
      inv(perm(e)) = e
      cnew(:, e) = mesh%conn(:, perm(e))
      nnew(e) = mesh%nen(perm(e))
    end do
    !$omp end parallel do
    mesh%file%file_elems = inv(1:mesh%nelem)
    call move_alloc(cnew, mesh%conn)
    call move_alloc(nnew, mesh%nen)
    if (allocated(mesh%elem_line)) mesh%elem_line = mesh%elem_line(perm(1:mesh%nelem))
    if (allocated(mesh%reg)) then
      allocate(in_reg(mesh%nelem))
      do b = 1, size(mesh%reg)                     ! each region's elements, ascending again
        if (size(mesh%reg(b)%elems) == mesh%nelem) then   ! the whole mesh (elements are listed once)
          do e = 1, mesh%nelem
            mesh%reg(b)%elems(e) = e
          end do
          cycle
        end if
        in_reg = .false.
        do k = 1, size(mesh%reg(b)%elems)
          in_reg(inv(mesh%reg(b)%elems(k))) = .true.
        end do
        k = 0
        do e = 1, mesh%nelem
          if (in_reg(e)) then
            k = k + 1
            mesh%reg(b)%elems(k) = e
          end if
        end do
        mesh%reg(b)%elems = mesh%reg(b)%elems(1:k)
      end do
    end if
  end subroutine order_for_locality

  !> Index along the Hilbert curve of order bits of the cell (x0, y0): two bits
  !> a level, from the top, by a table over the curve's four orientations
  !> (state = 2 swapped + reflected; q = 2 x bit + y bit).  The same index as
  !> the textbook loop that rotates the quadrant (xy2d), in fewer operations.
  pure integer(i8) function hilbert_index(bits, x0, y0) result(d)
    integer, intent(in) :: bits, x0, y0
    integer, parameter :: digit(0:3, 0:3) = reshape([0, 1, 3, 2,  2, 3, 1, 0,  0, 3, 1, 2,  2, 1, 3, 0], [4, 4])
    integer, parameter :: next(0:3, 0:3) = reshape([2, 0, 3, 0,  1, 2, 1, 3,  0, 1, 2, 2,  3, 3, 0, 1], [4, 4])
    integer :: lvl, q, st
    d = 0
    st = 0
    do lvl = bits - 1, 0, -1
      q = 2 * ibits(x0, lvl, 1) + ibits(y0, lvl, 1)
      d = ior(shiftl(d, 2), int(digit(q, st), i8))
      st = next(q, st)
    end do
  end function hilbert_index

  !> The node that is node p of the mesh file, or with element the element
  !> that is element p of the mesh file.
  pure integer function file_item(mesh, p, element) result(a)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: p
    logical, intent(in) :: element
    if (element) then
      a = mapped(mesh%file%file_elems, p)
    else
      a = mapped(mesh%file%file_nodes, p)
    end if
  end function file_item

  !> The number in the mesh file of node a.
  pure integer function node_in_file(mesh, a) result(p)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: a
    p = mapped(mesh%file%node_file, a)
  end function node_in_file

  !> map(i), or i when the map is not allocated (the file's own numbering).
  pure integer function mapped(map, i) result(j)
    integer, allocatable, intent(in) :: map(:)
    integer, intent(in) :: i
    j = i
    if (allocated(map)) j = map(i)
  end function mapped

  !> Line of element e in its mesh file, 0 when unknown (generated meshes).
  pure integer function source_line(mesh, e) result(line)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    line = 0
    if (allocated(mesh%elem_line)) line = mesh%elem_line(e)
  end function source_line

  !> Signed area of element e (shoelace formula over the corners, the straight
  !> element's; positive when counter-clockwise).
  pure real(dp) function element_area(mesh, e) result(a)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    integer :: k, n, i, j
    n = corner_count(mesh%nen(e))
    a = 0.0_dp
    do k = 1, n
      i = mesh%conn(k, e)
      j = mesh%conn(mod(k, n) + 1, e)
      a = a + mesh%x(1, i) * mesh%x(2, j) - mesh%x(1, j) * mesh%x(2, i)
    end do
    a = 0.5_dp * a
  end function element_area

  pure real(dp) function longest_edge2(mesh, e) result(h2)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    integer :: k, n
    real(dp) :: d(2)
    n = corner_count(mesh%nen(e))
    h2 = 0.0_dp
    do k = 1, n
      d = mesh%x(:, mesh%conn(mod(k, n) + 1, e)) - mesh%x(:, mesh%conn(k, e))
      h2 = max(h2, sum(d**2))
    end do
  end function longest_edge2

  !> Smallest cross product of consecutive edges at the corners of a quad
  !> (after orientation), i.e. twice the smallest corner triangle area.
  pure real(dp) function min_corner_cross(mesh, e) result(c)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    integer :: k
    real(dp) :: a(2), b(2)
    c = huge(1.0_dp)
    do k = 1, 4
      a = mesh%x(:, mesh%conn(mod(k, 4) + 1, e)) - mesh%x(:, mesh%conn(k, e))
      b = mesh%x(:, mesh%conn(mod(k + 1, 4) + 1, e)) - mesh%x(:, mesh%conn(mod(k, 4) + 1, e))
      c = min(c, a(1) * b(2) - a(2) * b(1))
    end do
  end function min_corner_cross

  !> Index of the first item of list called name; 0 when none or when list is
  !> absent (an unallocated list: mesh%bnd or mesh%reg of a mesh without any).
  pure integer function find_name(list, name) result(k)
    class(named_t), intent(in), optional :: list(:)
    character(len=*), intent(in) :: name
    k = 0
    if (.not. present(list)) return
    do k = 1, size(list)
      if (list(k)%name == name) return
    end do
    k = 0
  end function find_name

  !> The names of list, 'a, b, c'; none when it has none (or is absent: an
  !> unallocated list, mesh%bnd of a mesh without boundaries).
  pure function name_list(list, none) result(s)
    class(named_t), intent(in), optional :: list(:)
    character(len=*), intent(in) :: none
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    if (present(list)) then
      do k = 1, size(list)
        if (k > 1) s = s // ', '
        s = s // list(k)%name
      end do
    end if
    if (len(s) == 0) s = none
  end function name_list

  !> Sorted distinct node ids of a boundary's edges and points.
  subroutine boundary_nodes(b, nodes)
    type(boundary_t), intent(in) :: b
    integer, allocatable, intent(out) :: nodes(:)
    integer, allocatable :: all(:)
    integer :: n, k, i
    n = 2 * b%nseg + b%npoint
    if (allocated(b%mid)) n = n + b%nseg
    allocate(all(n))
    if (b%nseg > 0) all(1:2 * b%nseg) = reshape(b%seg(:, 1:b%nseg), [2 * b%nseg])
    if (b%npoint > 0) all(2 * b%nseg + 1:2 * b%nseg + b%npoint) = b%points(1:b%npoint)
    if (allocated(b%mid)) all(2 * b%nseg + b%npoint + 1:n) = b%mid(1:b%nseg)
    call sort_integers(all)
    k = 0
    do i = 1, n
      if (k > 0) then
        if (all(i) == all(k)) cycle
      end if
      k = k + 1
      all(k) = all(i)
    end do
    nodes = all(1:k)
  end subroutine boundary_nodes

  !> Mean edge length of the mesh, a length scale for tolerances.
  real(dp) function mesh_size(mesh) result(h)
    type(mesh_t), intent(in) :: mesh
    integer :: e
    h = 0.0_dp
    do e = 1, mesh%nelem
      h = h + sqrt(longest_edge2(mesh, e))
    end do
    h = h / max(1, mesh%nelem)
  end function mesh_size

end module mesh
