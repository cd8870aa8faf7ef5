!> point_supports: a body's FORCE and SPRING statements, resolved on its
!> mesh.  A part of scene: errors are reported at the statement's deck line.
!>
!>   FORCE point fx= fy=     the force on each node of the point set `point`
!>                           (a gmsh Physical Point, or any named set of
!>                           points), in its load group (ramp= or curve=)
!>   SPRING boundary kn= kt= a foundation on the edges of a boundary curve
!>                           (foundation's edge_spring_matrix on each edge)
!>   SPRING point kx= ky=    diag(kx, ky) at each node of a point set
!>
!> A FORCE or a point SPRING on a name with edges (a boundary curve) is an
!> error, as a foundation on a point set is: a force at each node of a curve
!> would depend on its mesh.  Forces and springs are in x, y components; the
!> scene turns the groups' forces to the nodes' local axes afterwards, and
!> body turns the springs' matrices when it assembles them.
!>
!> Programming interface
!>   apply_point_forces(deck, bdeck, bd, lg, diag)   FORCE: nodal forces in lg%fgroup
!>   apply_springs(deck, bdeck, bd, diag)                     SPRING: bd%springs
module point_supports
  use kinds, only: dp
  use errors, only: diag_t, add_error
  use deck_reader, only: deck_t, body_deck_t, load_point
  use mesh, only: boundary_nodes
  use body, only: body_t
  use foundation, only: edge_spring_matrix, add_spring
  use load_groups, only: load_groups_t, ramp_group
  use deck_boundaries, only: boundary_index, edge_normals, need_edges, need_points
  implicit none
  private
  public :: apply_point_forces, apply_springs

contains

  !> The FORCE statements of a body: fx, fy at each node of their point sets,
  !> in the load group of their ramp or curve.
  !>   deck      (in)    the deck (its file, for the messages)
  !>   bdeck     (in)    the body's statements (its loads of kind load_point)
  !>   bd        (in)    the body, its mesh and dof0
  !>   lg        (inout) the load groups: fgroup gets the forces
  !>   diag      (inout) unknown names, names that are not point sets
  subroutine apply_point_forces(deck, bdeck, bd, lg, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(body_t), intent(in) :: bd
    class(load_groups_t), intent(inout) :: lg
    type(diag_t), intent(inout) :: diag
    integer :: k, ib, i, g, d
    integer, allocatable :: nodes(:)
    do k = 1, size(bdeck%loads)
      associate(ld => bdeck%loads(k))
        if (ld%kind /= load_point) cycle
        ib = boundary_index(deck, ld%line, bd, ld%boundary, 'FORCE', need_points, diag)
        if (ib == 0) cycle
        call boundary_nodes(bd%mesh%bnd(ib), nodes)
        g = ramp_group(lg, ld%ramp, ld%curve)
        do i = 1, size(nodes)
          d = bd%dof0 + 2 * (nodes(i) - 1)
          lg%fgroup(d + 1, g) = lg%fgroup(d + 1, g) + ld%tx
          lg%fgroup(d + 2, g) = lg%fgroup(d + 2, g) + ld%ty
        end do
      end associate
    end do
  end subroutine apply_point_forces

  !> The SPRING statements of a body, as spring elements in bd%springs: one
  !> per edge of a foundation's boundary (2 or 3 nodes), one per node of a
  !> point spring's set.  Statement j of the body owns its elements.
  !>   bd (inout) the body, its mesh read; bd%springs on exit
  subroutine apply_springs(deck, bdeck, bd, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(body_t), intent(inout) :: bd
    type(diag_t), intent(inout) :: diag
    integer :: j, ib, i, s, na, nb
    integer, allocatable :: nodes(:)
    real(dp) :: ke(6, 6)
    real(dp), allocatable :: nrm(:,:)
    logical :: ok
    do j = 1, size(bdeck%springs)
      associate(sp => bdeck%springs(j), m => bd%mesh)
        if (sp%point) then
          ib = boundary_index(deck, sp%line, bd, sp%boundary, 'SPRING kx=/ky=', need_points, diag)
          if (ib == 0) cycle
          call boundary_nodes(m%bnd(ib), nodes)
          ke = 0.0_dp
          ke(1, 1) = sp%kx
          ke(2, 2) = sp%ky
          do i = 1, size(nodes)
            call add_spring(bd%springs, nodes(i:i), ke(1:2, 1:2), j)
          end do
          cycle
        end if
        ib = boundary_index(deck, sp%line, bd, sp%boundary, 'SPRING kn=/kt=', need_edges, diag)
        if (ib == 0) cycle
        ! each edge of exactly one element: its nodes are in K's pattern together
        call edge_normals(bd, ib, nrm, ok)
        if (.not. ok) then
          call add_error(diag, deck%file, sp%line, 'SPRING on "' // sp%boundary // '": an edge is not on the ' // &
                         'outer boundary of body "' // bd%name // '" (boundary edges expected)')
          cycle
        end if
        do s = 1, m%bnd(ib)%nseg
          na = m%bnd(ib)%seg(1, s)
          nb = m%bnd(ib)%seg(2, s)
          if (allocated(m%bnd(ib)%mid)) then
            call edge_spring_matrix(3, reshape([m%x(:, na), m%x(:, nb), m%x(:, m%bnd(ib)%mid(s))], [2, 3]), &
                                    sp%kn, sp%kt, bd%thick, bd%axisymmetric, ke)
            call add_spring(bd%springs, [na, nb, m%bnd(ib)%mid(s)], ke, j)
          else
            call edge_spring_matrix(2, reshape([m%x(:, na), m%x(:, nb)], [2, 2]), sp%kn, sp%kt, bd%thick, &
                                    bd%axisymmetric, ke)
            call add_spring(bd%springs, [na, nb], ke(1:4, 1:4), j)
          end if
        end do
      end associate
    end do
  end subroutine apply_springs

end module point_supports
