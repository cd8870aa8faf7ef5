!> fix_dofs: the Dirichlet dofs of a body's FIX statements.  FIX ux= uy=
!> holds a node along x and y; FIX un= ut= along the boundary's nodal normal
!> n and tangent t = (-n_y, n_x) (on a quadratic mesh the mid-side nodes
!> too, each with the normal of its curved edge), and puts the node in those
!> local axes (body%axes: its dofs become u.n, u.t; local_axes turns the
!> contact rows, body the forces).  FIX statements that share a node must hold it along
!> the same or perpendicular directions, with equal values.  A part of scene:
!> errors are reported at the FIX's deck line.
!>
!> Programming interface
!>   apply_fixes(deck, bdeck, group, ifix0, bd, fixed, ugroup, fix_owner, diag)
!>        the FIX statements of one body: fixed dofs, their values in their
!>        load groups, the FIX owning each, the nodes' local axes
module fix_dofs
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: diag_t, add_error
  use deck_reader, only: deck_t, body_deck_t
  use mesh, only: boundary_nodes, node_in_file
  use body, only: body_t
  use deck_boundaries, only: boundary_index, edge_normals, need_any, need_edges
  implicit none
  private
  public :: apply_fixes

contains

  !> Dirichlet dofs of the FIX statements of a body.  A component of a FIX
  !> fixes the displacement along a direction d: e_x, e_y (ux=, uy=), or the
  !> boundary's nodal normal n and t = (-n_y, n_x) (un=, ut=; n the
  !> normalized sum of the outward normals of the boundary's edges at the
  !> node, nodal_normals).  A node keeps one pair of axes: those of the first FIX in local
  !> axes that reaches it while none of its dofs is fixed, else x, y; a later
  !> FIX must hold it along one of those axes (up to sign: a rectangle's
  !> corner), else an error.
  !>   deck      (in)    the deck (its file, for the messages)
  !>   bdeck     (in)    the body's statements
  !>   group     (in)    (size(bdeck%fixes)) the load group of each FIX (load_groups)
  !>   ifix0     (in)    the FIX statements of the bodies before this one: FIX k is ifix0 + k
  !>   bd        (inout) the body (its dof0, mesh); its axes on exit when a FIX is in local axes
  !>   fixed     (inout) (ndof) the Dirichlet dofs
  !>   ugroup    (inout) (ndof, ngroup) the prescribed values of each load group
  !>   fix_owner (inout) (ndof) the FIX of each fixed dof (the first one)
  !>   diag      (inout) unknown boundaries, conflicting FIX statements
  subroutine apply_fixes(deck, bdeck, group, ifix0, bd, fixed, ugroup, fix_owner, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    integer, intent(in) :: group(:), ifix0
    type(body_t), intent(inout) :: bd
    logical, intent(inout) :: fixed(:)
    real(dp), intent(inout) :: ugroup(:,:)
    integer, intent(inout) :: fix_owner(:)
    type(diag_t), intent(inout) :: diag
    real(dp), parameter :: same = 1.0e-9_dp       ! |cos| within this of 1: the same axis
    integer :: k, ib, i, dof, c, a, slot
    integer, allocatable :: nodes(:)
    logical :: has(2), bad
    real(dp) :: val(2), v, d(2), q(2, 2), p(2)
    real(dp), allocatable :: nn(:,:)
    do k = 1, size(bdeck%fixes)
      associate(fx => bdeck%fixes(k))
        if (fx%local) then
          ib = boundary_index(deck, fx%line, bd, fx%boundary, 'FIX un=/ut=', need_edges, diag)
        else
          ib = boundary_index(deck, fx%line, bd, fx%boundary, 'FIX', need_any, diag)
        end if
        if (ib == 0) cycle
        call boundary_nodes(bd%mesh%bnd(ib), nodes)
        if (fx%local) then
          call nodal_normals(bd, ib, nodes, nn, bad)
          if (bad) then
            call add_error(diag, deck%file, fx%line, 'FIX un=/ut= on "' // fx%boundary // '": an edge is not on the ' // &
              'outer boundary of body "' // bd%name // '" or the edge normals at a node cancel (a boundary ' // &
              'curve with an outward normal at every node expected)')
            cycle
          end if
          if (.not. allocated(bd%axes)) allocate(bd%axes(2, bd%mesh%nnode), source=0.0_dp)
        end if
        has = [fx%has_ux, fx%has_uy]
        val = [fx%ux, fx%uy]
        node_loop: do i = 1, size(nodes)
          a = nodes(i)
          dof = bd%dof0 + 2 * (a - 1)
          if (fx%local .and. .not. any(fixed(dof + 1:dof + 2))) then
            if (all(bd%axes(:, a) == 0.0_dp)) bd%axes(:, a) = nn(:, i)     ! the node's axes: this FIX's
          end if
          q = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
          if (allocated(bd%axes)) then
            if (any(bd%axes(:, a) /= 0.0_dp)) q = reshape([bd%axes(:, a), -bd%axes(2, a), bd%axes(1, a)], [2, 2])
          end if
          do c = 1, 2
            if (.not. has(c)) cycle
            if (fx%local) then                          ! direction of component c
              d = nn(:, i)
              if (c == 2) d = [-nn(2, i), nn(1, i)]
            else
              d = 0.0_dp
              d(c) = 1.0_dp
            end if
            p = matmul(transpose(q), d)                 ! d in the node's axes
            if (abs(abs(p(1)) - 1.0_dp) <= same) then
              slot = 1
            else if (abs(abs(p(2)) - 1.0_dp) <= same) then
              slot = 2
            else
              call add_error(diag, deck%file, fx%line, 'FIX ' // fx%boundary // ' holds node ' // &
                int_to_str(node_in_file(bd%mesh, a)) // ' along ' // direction(d) // ', which is neither axis of ' // &
                'the node set by an earlier FIX, ' // direction(q(:, 1)) // ' and ' // direction(q(:, 2)) // &
                ' (expected FIX statements sharing a node to hold it along the same or perpendicular directions)')
              exit node_loop
            end if
            v = sign(1.0_dp, p(slot)) * val(c)
            dof = bd%dof0 + 2 * (a - 1) + slot
            if (fixed(dof)) then
              if (sum(ugroup(dof, :)) /= v .or. (v /= 0.0_dp .and. ugroup(dof, group(k)) /= v)) then
                call add_error(diag, deck%file, fx%line, 'FIX ' // fx%boundary // ' gives node ' // &
                  int_to_str(node_in_file(bd%mesh, a)) // ' a value that conflicts with an earlier ' // &
                  'FIX (equal values where FIX statements share nodes expected)')
                exit node_loop
              end if
            else
              fixed(dof) = .true.
              ugroup(dof, group(k)) = v
              fix_owner(dof) = ifix0 + k
            end if
          end do
        end do node_loop
      end associate
    end do
  end subroutine apply_fixes

  !> '(dx, dy)' for messages.
  function direction(d) result(t)
    real(dp), intent(in) :: d(2)
    character(len=:), allocatable :: t
    character(len=16) :: bx, by
    write(bx, '(f8.4)') d(1)
    write(by, '(f8.4)') d(2)
    t = '(' // trim(adjustl(bx)) // ', ' // trim(adjustl(by)) // ')'
  end function direction

  !> Unit normal at each node of boundary ib: the normalized sum of the outward
  !> unit normals of the boundary's edges at the node.  On a 3-node edge
  !> (quadratic mesh, boundary_t%mid) each node takes the normal of the
  !> edge's own curve x(s) = sum_a N_a(s) x_a at it (s = -1, 1 at the ends,
  !> 0 at the middle): the mid-side node the normal of the curve there, the
  !> corners the sum over their two edges as on a linear mesh; on a straight
  !> edge every one is the chord's normal.  The side, outward, is the chord's
  !> (deck_boundaries: edge_normals).
  !>   nodes (in) the boundary's nodes (boundary_nodes: mid-side ones included)
  !>   nn    (out) (2, size(nodes))
  !>   bad   (out) an edge not on the body's outer boundary, or a zero sum
  subroutine nodal_normals(bd, ib, nodes, nn, bad)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: ib, nodes(:)
    real(dp), allocatable, intent(out) :: nn(:,:)
    logical, intent(out) :: bad
    integer, allocatable :: slot(:)
    integer :: s, na, nb, i, k, nodes3(3)
    real(dp) :: xe(2, 3), tang(2), nk(2)
    real(dp), allocatable :: nrm(:,:)
    logical :: ok
    ! dN/ds of the 3-node edge (ends -1, 1, middle 0) at s = -1, 1, 0: the tangent at each node
    real(dp), parameter :: dn(3, 3) = reshape([-1.5_dp, -0.5_dp, 2.0_dp, 0.5_dp, 1.5_dp, -2.0_dp, &
                                               -0.5_dp, 0.5_dp, 0.0_dp], [3, 3])
    allocate(nn(2, size(nodes)), source=0.0_dp)
    call edge_normals(bd, ib, nrm, ok)
    bad = .not. ok
    if (bad) return
    allocate(slot(bd%mesh%nnode), source=0)
    do i = 1, size(nodes)
      slot(nodes(i)) = i
    end do
    do s = 1, bd%mesh%bnd(ib)%nseg
      na = bd%mesh%bnd(ib)%seg(1, s)
      nb = bd%mesh%bnd(ib)%seg(2, s)
      if (.not. allocated(bd%mesh%bnd(ib)%mid)) then
        nn(:, slot(na)) = nn(:, slot(na)) + nrm(:, s)
        nn(:, slot(nb)) = nn(:, slot(nb)) + nrm(:, s)
        cycle
      end if
      nodes3 = [na, nb, bd%mesh%bnd(ib)%mid(s)]
      xe = bd%mesh%x(:, nodes3)
      do k = 1, 3
        tang = matmul(xe, dn(:, k))                     ! dx/ds at node k
        nk = [tang(2), -tang(1)] / norm2(tang)
        if (dot_product(nk, nrm(:, s)) < 0.0_dp) nk = -nk     ! outward, as the chord's normal
        nn(:, slot(nodes3(k))) = nn(:, slot(nodes3(k))) + nk
      end do
    end do
    do i = 1, size(nodes)
      if (norm2(nn(:, i)) < 1.0e-8_dp) then
        bad = .true.
        return
      end if
      nn(:, i) = nn(:, i) / norm2(nn(:, i))
    end do
  end subroutine nodal_normals

end module fix_dofs
