!> deck_boundaries: the boundary a deck statement names (FIX, TRACTION,
!> PRESSURE, CONTACT, FORCE, SPRING), found in its body's mesh, or an input
!> error at the statement's line: an unknown name (with the names the mesh
!> has), a point set where the statement needs edges, or a boundary curve
!> where it needs a point set; and the outward normals of a boundary's
!> edges, for the statements that act along them (PRESSURE, TRACTION tn=
!> tt=, SPRING kn= kt=, FIX un= ut=).  A part of scene.
!>
!> Programming interface
!>   boundary_index(deck, line, bd, name, what, need, diag)   boundary `name` of body bd, 0 on error;
!>        need: need_any, need_edges (a boundary curve) or need_points (a point set)
!>   edge_normals(bd, ib, nrm, ok)   outward unit normal of each edge of boundary ib
module deck_boundaries
  use kinds, only: dp
  use errors, only: diag_t, add_error
  use deck_reader, only: deck_t
  use mesh, only: find_name, name_list
  use body, only: body_t, node_elements, edge_outward_normal
  implicit none
  private
  public :: boundary_index, edge_normals, need_any, need_edges, need_points

  !> What a statement needs the name it gives to be (boundary_index).
  integer, parameter :: need_any = 0      !< a boundary curve or a point set
  integer, parameter :: need_edges = 1    !< a boundary curve (edges)
  integer, parameter :: need_points = 2   !< a point set (a gmsh Physical Point)

contains

  !> Boundary index of `name` in body bd, reporting at `line` when unknown,
  !> or when it is not of the kind the statement needs.
  !>   deck  (in)    the deck (its file, for the message)
  !>   line  (in)    the deck line of the statement
  !>   bd    (in)    the body, its mesh read
  !>   name  (in)    the boundary's name;  what (in) the statement, for the message
  !>   need  (in)    need_any; need_edges: a point set is an error; need_points:
  !>                 a boundary curve is an error
  !>   diag  (inout) the error
  !>   ib    (result) the boundary in bd%mesh%bnd, 0 on error
  integer function boundary_index(deck, line, bd, name, what, need, diag) result(ib)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    type(body_t), intent(in) :: bd
    character(len=*), intent(in) :: name, what
    integer, intent(in) :: need
    type(diag_t), intent(inout) :: diag
    character(len=:), allocatable :: wrong
    ib = find_name(bd%mesh%bnd, name)
    if (ib == 0) then
      call add_error(diag, deck%file, line, what // ': unknown boundary "' // name // '" in body "' // &
                     bd%name // '" (expected one of: ' // name_list(bd%mesh%bnd, 'none: the mesh names no boundary') // ')')
      return
    end if
    wrong = ''
    if (need == need_edges .and. bd%mesh%bnd(ib)%nseg == 0) then
      wrong = 'is a point set (a boundary curve with edges expected)'
    else if (need == need_points .and. bd%mesh%bnd(ib)%nseg > 0) then
      wrong = 'is a boundary curve (a point set expected: a gmsh Physical Point)'
    end if
    if (len(wrong) > 0) then
      call add_error(diag, deck%file, line, what // ': "' // name // '" in body "' // bd%name // '" ' // wrong)
      ib = 0
    end if
  end function boundary_index

  !> The outward unit normal of each edge of boundary ib of bd: the chord's
  !> normal, pointing out of the one element that has the edge (body:
  !> edge_outward_normal).
  !>   bd  (in)  the body, its mesh finalized
  !>   ib  (in)  a boundary curve of bd%mesh
  !>   nrm (out) (2, nseg) the normals (incomplete when not ok)
  !>   ok  (out) every edge is on the body's outer boundary (of exactly one element)
  subroutine edge_normals(bd, ib, nrm, ok)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: ib
    real(dp), allocatable, intent(out) :: nrm(:,:)
    logical, intent(out) :: ok
    integer, allocatable :: eptr(:), elist(:)
    integer :: s, owner
    call node_elements(bd%mesh, eptr, elist)
    allocate(nrm(2, bd%mesh%bnd(ib)%nseg))
    ok = .false.
    do s = 1, bd%mesh%bnd(ib)%nseg
      call edge_outward_normal(bd%mesh, eptr, elist, bd%mesh%bnd(ib)%seg(1, s), bd%mesh%bnd(ib)%seg(2, s), &
                               nrm(:, s), owner)
      if (owner <= 0) return
    end do
    ok = .true.
  end subroutine edge_normals

end module deck_boundaries
