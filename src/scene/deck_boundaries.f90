!> deck_boundaries: the boundary a deck statement names (FIX, TRACTION,
!> PRESSURE, CONTACT), found in its body's mesh, or an input error at the
!> statement's line: an unknown name (with the names the mesh has), or a
!> point set where the statement needs edges.  A part of scene.
!>
!> Programming interface
!>   boundary_index(deck, line, bd, name, what, curve, diag)   boundary `name` of body bd, 0 on error
module deck_boundaries
  use errors, only: diag_t, add_error
  use deck_reader, only: deck_t
  use mesh, only: find_name, name_list
  use body, only: body_t
  implicit none
  private
  public :: boundary_index

contains

  !> Boundary index of `name` in body bd, reporting at `line` when unknown,
  !> or when a curve is asked for and it is a point set (no edges).
  !>   deck  (in)    the deck (its file, for the message)
  !>   line  (in)    the deck line of the statement
  !>   bd    (in)    the body, its mesh read
  !>   name  (in)    the boundary's name;  what (in) the statement, for the message
  !>   curve (in)    the statement needs edges: a point set is an error
  !>   diag  (inout) the error
  !>   ib    (result) the boundary in bd%mesh%bnd, 0 on error
  integer function boundary_index(deck, line, bd, name, what, curve, diag) result(ib)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    type(body_t), intent(in) :: bd
    character(len=*), intent(in) :: name, what
    logical, intent(in) :: curve
    type(diag_t), intent(inout) :: diag
    ib = find_name(bd%mesh%bnd, name)
    if (ib == 0) then
      call add_error(diag, deck%file, line, what // ': unknown boundary "' // name // '" in body "' // &
                     bd%name // '" (expected one of: ' // name_list(bd%mesh%bnd, 'none: the mesh names no boundary') // ')')
    else if (curve .and. bd%mesh%bnd(ib)%nseg == 0) then
      call add_error(diag, deck%file, line, what // ': "' // name // '" in body "' // bd%name // &
                     '" is a point set (a boundary curve with edges expected)')
      ib = 0
    end if
  end function boundary_index

end module deck_boundaries
