!> boundary_chain: a boundary of a body as one chain of nodes, the trace a
!> contact pair is built on: its edges ordered into an open or closed
!> polyline, the outward normal of each segment, and the mid-side nodes of a
!> quadratic trace put between their corners.  Kept apart from contact_set,
!> which builds the constraint rows on these chains.
!>
!> Programming interface
!>   chain_boundary(mesh, ib, nodes, why)   order the edges of boundary ib into
!>        one polyline; why is set (non-empty) when they do not form one
!>   boundary_polyline(bd, ib, nodes, x, nout, why)  polyline, coordinates and
!>        outward unit normals of its segments
!>   trace_chain(mesh, ib, nodes, p)   the chain with its mid-side nodes (degree p)
module boundary_chain
  use kinds, only: dp
  use strings, only: int_to_str
  use mesh, only: mesh_t
  use body, only: body_t, node_elements, edge_outward_normal
  implicit none
  private
  public :: chain_boundary, boundary_polyline, trace_chain

contains

  !> Order the edges of boundary ib of mesh into one chain of nodes, open or
  !> closed (then its last node is its first).
  !>   nodes (out) the chain (nseg + 1 nodes), in the edges' own direction when
  !>               possible; why (out) '' on success, else the reason
  subroutine chain_boundary(mesh, ib, nodes, why)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: ib
    integer, allocatable, intent(out) :: nodes(:)
    character(len=:), allocatable, intent(out) :: why
    integer, allocatable :: deg(:), ptr(:), adj(:), fill(:)
    integer :: nseg, s, a, b, start, prev, cur, k, nxt, nends
    logical, allocatable :: used(:)

    why = ''
    nseg = mesh%bnd(ib)%nseg
    if (nseg < 1) then
      why = 'it has no edges (a boundary curve expected, not a point set)'
      return
    end if
    allocate(deg(mesh%nnode), source=0)
    do s = 1, nseg
      a = mesh%bnd(ib)%seg(1, s); b = mesh%bnd(ib)%seg(2, s)
      if (a == b) then
        why = 'it has a zero-length edge'
        return
      end if
      deg(a) = deg(a) + 1; deg(b) = deg(b) + 1
    end do
    if (any(deg > 2)) then
      why = 'it branches (three or more edges meet at a node)'
      return
    end if
    nends = count(deg == 1)
    if (nends > 2) then
      why = 'it is made of ' // int_to_str(nends / 2) // ' separate pieces (one connected curve expected)'
      return
    end if
    ! adjacency lists (two at most per node)
    allocate(ptr(mesh%nnode + 1), fill(mesh%nnode))
    ptr(1) = 1
    do a = 1, mesh%nnode
      ptr(a + 1) = ptr(a) + deg(a)
    end do
    allocate(adj(2 * nseg))
    fill = ptr(1:mesh%nnode)
    do s = 1, nseg
      a = mesh%bnd(ib)%seg(1, s); b = mesh%bnd(ib)%seg(2, s)
      adj(fill(a)) = s; fill(a) = fill(a) + 1
      adj(fill(b)) = s; fill(b) = fill(b) + 1
    end do
    ! start at the end node that is the first node of its edge, if any
    start = 0
    do s = 1, nseg
      a = mesh%bnd(ib)%seg(1, s)
      if (deg(a) == 1) then
        start = a
        exit
      end if
    end do
    if (start == 0) then
      do a = 1, mesh%nnode
        if (deg(a) == 1) then
          start = a
          exit
        end if
      end do
    end if
    if (nends == 0) start = mesh%bnd(ib)%seg(1, 1)      ! a closed curve: nodes(nseg + 1) = nodes(1)
    allocate(nodes(nseg + 1), used(nseg))
    used = .false.
    nodes(1) = start
    prev = 0
    cur = start
    do k = 1, nseg
      nxt = 0
      do s = ptr(cur), ptr(cur + 1) - 1
        if (.not. used(adj(s))) then
          nxt = adj(s)
          exit
        end if
      end do
      if (nxt == 0) then
        why = 'it is made of separate pieces (one connected curve expected)'
        return
      end if
      used(nxt) = .true.
      if (mesh%bnd(ib)%seg(1, nxt) == cur) then
        cur = mesh%bnd(ib)%seg(2, nxt)
      else
        cur = mesh%bnd(ib)%seg(1, nxt)
      end if
      nodes(k + 1) = cur
    end do
    if (prev /= 0) why = ''
  end subroutine chain_boundary

  !> Polyline of boundary ib of body bd with the outward unit normal of each
  !> segment (pointing away from the element that owns the edge).
  subroutine boundary_polyline(bd, ib, nodes, x, nout, why)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: ib
    integer, allocatable, intent(out) :: nodes(:)
    real(dp), allocatable, intent(out) :: x(:,:), nout(:,:)
    character(len=:), allocatable, intent(out) :: why
    integer, allocatable :: eptr(:), elist(:)
    integer :: s, owner, n

    call chain_boundary(bd%mesh, ib, nodes, why)
    if (len(why) > 0) return
    n = size(nodes)
    x = bd%mesh%x(:, nodes)
    allocate(nout(2, n - 1))
    call node_elements(bd%mesh, eptr, elist)
    do s = 1, n - 1
      call edge_outward_normal(bd%mesh, eptr, elist, nodes(s), nodes(s + 1), nout(:, s), owner)
      if (owner < 0) then
        why = 'an edge lies inside the body (edges on the body''s outer boundary expected)'
        return
      else if (owner == 0) then
        why = 'an edge is not an edge of any element'
        return
      end if
    end do
  end subroutine boundary_polyline

  !> The trace of boundary ib as a chain of nodes with the mid-side nodes of
  !> its 3-node edges between their corners (degree 2), or the corners alone on
  !> a linear mesh (degree 1); nodes on entry is the chain of corners.
  !>   nodes (inout) the chain;  p (out) its degree
  subroutine trace_chain(mesh, ib, nodes, p)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: ib
    integer, allocatable, intent(inout) :: nodes(:)
    integer, intent(out) :: p
    integer, allocatable :: edge_of(:,:), chain(:)
    integer :: s, a, b, k, n, slot
    p = 1
    if (.not. allocated(mesh%bnd(ib)%mid)) return
    p = 2
    allocate(edge_of(2, mesh%nnode), source=0)   ! the (at most two) edges at each node
    do s = 1, mesh%bnd(ib)%nseg
      do k = 1, 2
        a = mesh%bnd(ib)%seg(k, s)
        slot = merge(1, 2, edge_of(1, a) == 0)
        edge_of(slot, a) = s
      end do
    end do
    n = size(nodes)
    allocate(chain(2 * n - 1))
    do k = 1, n - 1
      a = nodes(k)
      b = nodes(k + 1)
      chain(2 * k - 1) = a
      do slot = 1, 2
        s = edge_of(slot, a)
        if (s == 0) cycle
        if (any(mesh%bnd(ib)%seg(:, s) == b)) chain(2 * k) = mesh%bnd(ib)%mid(s)
      end do
    end do
    chain(2 * n - 1) = nodes(n)
    call move_alloc(chain, nodes)
  end subroutine trace_chain

end module boundary_chain
