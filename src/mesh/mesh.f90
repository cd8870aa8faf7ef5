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
!>        is clockwise, and report to diag: no elements, linear and quadratic
!>        mixed, boundary edges or points that name nodes outside the mesh,
!>        zero-length boundary edges, mixed orientation (inverted elements),
!>        degenerate, non-convex or folded elements.  Its steps, one routine
!>        each, in this order: check_element_nodes, check_element_order,
!>        drop_unused_nodes, check_boundary_edges, check_orientation
!>        (reverse_orientation), bad_shapes (non-convex, then folded);
!>        report_elements writes the first five of each kind of bad element
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
  use elements, only: corner_count, quadrature_rule, shape_at, max_nen, reference_node
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

  !> Compact, orient and check a mesh just read; see the module header.  The
  !> steps run in this order, each only when the ones before found nothing:
  !> the later ones index nodes and coordinates the earlier ones vouch for.
  !>   mesh (inout) the mesh; on return nodes are 1..nnode all used by elements
  !>   file (in)    name for messages
  !>   diag (inout) receives one message per defect (at most a few of each kind)
  subroutine finalize_mesh(mesh, file, diag)
    type(mesh_t), intent(inout) :: mesh
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer :: nerr0
    logical :: clockwise
    nerr0 = diag%count
    call check_element_nodes(mesh, file, diag)
    if (diag%count > nerr0) return
    call check_element_order(mesh, file, diag)
    if (diag%count > nerr0) return
    call drop_unused_nodes(mesh, file, diag)
    ! a boundary left with old node numbers (a node of no element) must not be used below
    if (diag%count > nerr0) return
    call check_boundary_edges(mesh, file, diag)
    if (diag%count > nerr0) return
    call check_orientation(mesh, file, diag, clockwise)
    if (diag%count > nerr0) return
    if (clockwise) call reverse_orientation(mesh)
    call report_elements(mesh, file, bad_shapes(mesh, folded=.false.), 'quadrilateral', ' is not convex (a ' // &
      'convex quadrilateral with positive corner angles below 180 degrees expected)', diag)
    if (diag%count > nerr0) return
    call report_elements(mesh, file, bad_shapes(mesh, folded=.true.), 'element', ' is folded (Jacobian <= 0 ' // &
      'inside: a mid-side node far from its edge''s middle; mid-side nodes near the middle of their edges expected)', diag)
  end subroutine finalize_mesh

  !> A mesh with elements, each naming nodes 1..nnode; the first defect is reported.
  !>   mesh (in)    the mesh as read
  !>   file (in)    name for messages;  diag (inout) the defect
  subroutine check_element_nodes(mesh, file, diag)
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer :: e, k
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
  end subroutine check_element_nodes

  !> Elements and boundary edges of one order.  Quadratic meshes: all
  !> elements quadratic (a linear neighbour would not conform), every boundary
  !> edge with its mid-side node; linear meshes none.  The first defect is reported.
  !>   mesh (in)    the mesh as read
  !>   file (in)    name for messages;  diag (inout) the defect
  subroutine check_element_order(mesh, file, diag)
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer :: b
    logical :: quadratic, two_node, three_node
    quadratic = is_quadratic(mesh)
    if (quadratic .and. any(mesh%nen <= 4)) then
      call add_error(diag, file, 0, 'mesh mixes linear and quadratic elements (all of one order expected)')
      return
    end if
    if (.not. allocated(mesh%bnd)) return
    do b = 1, size(mesh%bnd)
      associate(bd => mesh%bnd(b))
        if (bd%nseg == 0) cycle
        two_node = .not. allocated(bd%mid)          ! some edge without its mid-side node
        if (.not. two_node) two_node = any(bd%mid(1:bd%nseg) == 0)
        three_node = .false.                        ! some edge with one
        if (allocated(bd%mid)) three_node = any(bd%mid(1:bd%nseg) /= 0)
        if (quadratic .and. two_node) then
          call add_error(diag, file, 0, 'boundary "' // bd%name // '" has 2-node edges on a mesh of quadratic ' // &
            'elements (3-node lines expected: mesh with gmsh -order 2)')
          return
        else if (.not. quadratic .and. three_node) then
          call add_error(diag, file, 0, 'boundary "' // bd%name // &
            '" has 3-node edges on a mesh of linear elements (2-node lines expected)')
          return
        end if
      end associate
    end do
  end subroutine check_element_order

  !> Drop the nodes no element uses and number the others 1..nnode in their
  !> old order, in the elements and the boundaries alike.  A boundary that
  !> names a node that does not exist or belongs to no element is reported
  !> (and keeps old numbers: the caller must stop).
  !>   mesh (inout) elements' nodes 1..nnode (check_element_nodes); on return
  !>                every node is used by an element
  !>   file (in)    name for messages;  diag (inout) one defect per boundary at most
  subroutine drop_unused_nodes(mesh, file, diag)
    type(mesh_t), intent(inout) :: mesh
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer, allocatable :: newid(:)
    integer :: e, k, n, b
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
    end if
    if (allocated(mesh%bnd)) then
      do b = 1, size(mesh%bnd)
        call renumber_boundary(mesh%bnd(b), newid, file, diag)
      end do
    end if
    mesh%nnode = n
  end subroutine drop_unused_nodes

  !> The nodes of boundary b in the new numbering: node = newid(node), or
  !> the first defect reported (then b is left partly renumbered).
  !>   b     (inout) a boundary or point set of the mesh
  !>   newid (in)    (old nnode) new number of each old node, 0 for a node of no element
  !>   file  (in)    name for messages;  diag (inout) the defect
  subroutine renumber_boundary(b, newid, file, diag)
    type(boundary_t), intent(inout) :: b
    integer, intent(in) :: newid(:)
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer :: k, j, nk, edge(3)
    do k = 1, b%nseg
      nk = 2
      edge(1:2) = b%seg(:, k)
      if (allocated(b%mid)) then          ! the middle of a 3-node edge
        nk = 3
        edge(3) = b%mid(k)
      end if
      do j = 1, nk
        select case (new_number(newid, edge(j)))
        case (-1)
          call add_error(diag, file, 0, 'boundary "' // b%name // '" refers to a node that does not exist')
          return
        case (0)
          call add_error(diag, file, 0, 'boundary "' // b%name // &
            '" has an edge whose nodes belong to no element (edges on the body''s boundary expected)')
          return
        end select
      end do
      b%seg(:, k) = newid(edge(1:2))
      if (nk == 3) b%mid(k) = newid(edge(3))
    end do
    do k = 1, b%npoint
      select case (new_number(newid, b%points(k)))
      case (-1)
        call add_error(diag, file, 0, 'point set "' // b%name // '" refers to a node that does not exist')
        return
      case (0)
        call add_error(diag, file, 0, 'point set "' // b%name // &
          '" names a node that belongs to no element (a mesh node expected)')
        return
      end select
      b%points(k) = newid(b%points(k))
    end do
  end subroutine renumber_boundary

  !> The new number of old node a: newid(a), 0 when it belongs to no element,
  !> -1 when it does not exist (outside 1..size(newid)).
  pure integer function new_number(newid, a) result(n)
    integer, intent(in) :: newid(:), a
    n = -1
    if (a >= 1 .and. a <= size(newid)) n = newid(a)
  end function new_number

  !> No boundary edge of zero length (two distinct nodes at one point: the
  !> edge would have no normal); the first one is reported at its file line.
  !>   mesh (in)    the mesh, its boundaries renumbered (drop_unused_nodes)
  !>   file (in)    name for messages;  diag (inout) the defect
  subroutine check_boundary_edges(mesh, file, diag)
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer :: b, k, line
    real(dp) :: scale
    if (.not. allocated(mesh%bnd)) return
    scale = maxval(abs(mesh%x(:, 1:mesh%nnode)))
    do b = 1, size(mesh%bnd)
      associate(bd => mesh%bnd(b))
        do k = 1, bd%nseg
          if (norm2(mesh%x(:, bd%seg(2, k)) - mesh%x(:, bd%seg(1, k))) <= 1.0e-12_dp * scale) then
            line = 0
            if (allocated(bd%seg_line)) line = bd%seg_line(k)
            call add_error(diag, file, line, 'boundary "' // bd%name // '" has a zero-length edge (nodes ' // &
              int_to_str(bd%seg(1, k)) // ' and ' // int_to_str(bd%seg(2, k)) // &
              ' at the same point; distinct points expected)')
            return
          end if
        end do
      end associate
    end do
  end subroutine check_boundary_edges

  !> The elements' orientation: every element of nonzero area (|area| above
  !> 1e-12 of its squared longest edge, else degenerate), all of one sign
  !> (else the minority is reported as inverted).
  !>   mesh      (in)    the mesh
  !>   file      (in)    name for messages;  diag (inout) the defects (report_elements)
  !>   clockwise (out)   every element is clockwise (the mesh is to be reversed)
  subroutine check_orientation(mesh, file, diag, clockwise)
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: clockwise
    integer :: e, nneg, npos
    real(dp), allocatable :: area(:)
    logical, allocatable :: degenerate(:)
    clockwise = .false.
    allocate(area(mesh%nelem), degenerate(mesh%nelem))
    do e = 1, mesh%nelem
      area(e) = element_area(mesh, e)
      degenerate(e) = .not. (abs(area(e)) > 1.0e-12_dp * longest_edge2(mesh, e))
    end do
    if (any(degenerate)) then
      call report_elements(mesh, file, degenerate, 'element', &
        ' is degenerate (zero area; distinct, non-collinear nodes expected)', diag)
      return
    end if
    nneg = count(area < 0.0_dp)
    npos = mesh%nelem - nneg
    if (nneg > 0 .and. npos > 0) then            ! the minority is inverted
      call report_elements(mesh, file, area * merge(1.0_dp, -1.0_dp, npos >= nneg) < 0.0_dp, 'element', &
        ' is inverted (its orientation is opposite to the rest of the mesh)', diag)
      return
    end if
    clockwise = nneg > 0
  end subroutine check_orientation

  !> Every element turned the other way round: corners 1, nc, ..., 2 and the
  !> mid-side nodes in reverse (edge k keeps its mid-side node), the centre kept.
  !>   mesh (inout) the mesh; conn reversed
  subroutine reverse_orientation(mesh)
    type(mesh_t), intent(inout) :: mesh
    integer :: e, k, n
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
  end subroutine reverse_orientation

  !> The elements of one shape defect: quadrilaterals not strictly convex (a
  !> corner's cross product, the Jacobian there, not above 1e-12 of the
  !> squared longest edge), or quadratic elements folded by a mid-side node
  !> far from its edge's middle (the Jacobian not above that somewhere: at a
  !> stiffness point or a node, min_jacobian).  The second is asked only of
  !> a mesh without the first: a corner's zero Jacobian would divide by zero.
  !>   mesh   (in)     the mesh, counter-clockwise (reverse_orientation)
  !>   folded (in)     .false.: the non-convex quadrilaterals; .true.: the folded elements
  !>   bad    (result) (nelem) .true. at those elements
  function bad_shapes(mesh, folded) result(bad)
    type(mesh_t), intent(in) :: mesh
    logical, intent(in) :: folded
    logical :: bad(mesh%nelem)
    integer :: e
    do e = 1, mesh%nelem
      bad(e) = .false.
      if (folded) then
        if (mesh%nen(e) > 4) bad(e) = .not. (min_jacobian(mesh, e) > 1.0e-12_dp * longest_edge2(mesh, e))
      else if (corner_count(mesh%nen(e)) == 4) then
        bad(e) = .not. (min_corner_cross(mesh, e) > 1.0e-12_dp * longest_edge2(mesh, e))
      end if
    end do
  end function bad_shapes

  !> One message per bad element, `noun E text` at its line in the mesh
  !> file, for the first five of them: enough to find the defect, not a
  !> flood from a mesh that has it everywhere.
  !>   mesh (in)    the mesh (its elements' file lines)
  !>   file (in)    name for messages
  !>   bad  (in)    (nelem) the elements to report
  !>   noun (in)    'element' or 'quadrilateral';  text (in) what is wrong (what was expected)
  !>   diag (inout) the messages
  subroutine report_elements(mesh, file, bad, noun, text, diag)
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: file
    logical, intent(in) :: bad(:)
    character(len=*), intent(in) :: noun, text
    type(diag_t), intent(inout) :: diag
    integer :: e, n
    n = 0
    do e = 1, size(bad)
      if (.not. bad(e)) cycle
      n = n + 1
      if (n > 5) return
      call add_error(diag, file, source_line(mesh, e), noun // ' ' // int_to_str(e) // text)
    end do
  end subroutine report_elements

  !> Smallest Jacobian determinant of element e at its stiffness points and
  !> nodes (elements' reference_node).
  real(dp) function min_jacobian(mesh, e) result(jmin)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    real(dp), allocatable :: xi(:,:), w(:)
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
      call shape_at(nen, xe(:, 1:nen), reference_node(nen, q), n(1:nen), dndx(:, 1:nen), detj)
      jmin = min(jmin, detj)
    end do
  end function min_jacobian

  !> Whether the mesh has quadratic elements (6, 8 or 9 nodes).
  pure logical function is_quadratic(mesh)
    type(mesh_t), intent(in) :: mesh
    is_quadratic = .false.
    if (allocated(mesh%nen)) is_quadratic = any(mesh%nen > 4)
  end function is_quadratic

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
