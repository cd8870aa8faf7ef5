!> body_loads: a body's TRACTION, PRESSURE, BODYFORCE, GRAVITY and THERMAL
!> statements, resolved on its mesh into the nodal forces of their load
!> groups (load_groups: fgroup).  A part of scene: errors are reported at the
!> statement's deck line.  FORCE and SPRING are point_supports'.
!>
!> The forces are the consistent nodal forces of the elements' kernels:
!> edge loads on each edge of the named boundary (2 or 3 nodes), body loads
!> on each element, the thermal strains' int B' D eps0 (body: thermal_loads);
!> in PLANE axisymmetric the axisymmetric kernels, integrals over the full
!> circle 2 pi r.  They are in x, y components; the scene turns them to the
!> nodes' local axes afterwards.
!>
!> Programming interface
!>   apply_edge_loads(deck, bdeck, bd, lg, diag)   TRACTION, PRESSURE: nodal forces in lg%fgroup
!>   apply_body_loads(deck, bdeck, bd, lg)         BODYFORCE, GRAVITY (rho g): the same
!>   apply_thermal(deck, bdeck, bd, lg, adt1, group, diag)   THERMAL: the strains' nodal
!>        forces in lg%fgroup; alpha dT at load factor 1 and the load group per element
module body_loads
  use kinds, only: dp
  use errors, only: diag_t, add_error, has_errors
  use deck_reader, only: deck_t, body_deck_t, LOAD_TRACTION, LOAD_PRESSURE, LOAD_POINT
  use mesh, only: find_name, name_list
  use elements, only: element_body_load, edge_load, edge_load_quadratic, max_nen
  use axisymmetric_elements, only: axi_element_body_load, axi_edge_load, axi_edge_load_quadratic
  use body, only: body_t, element_dofs, thermal_loads
  use load_groups, only: load_groups_t, ramp_group
  use deck_boundaries, only: boundary_index, edge_normals, need_edges
  implicit none
  private
  public :: apply_edge_loads, apply_body_loads, apply_thermal

contains

  !> The surface loads of a body: TRACTION (x, y components, or tn, tt along
  !> each edge's outward normal n and t = (-n_y, n_x)) and PRESSURE (t = -p n,
  !> following a curved edge's normal), each edge's consistent nodal forces
  !> (elements: edge_load, edge_load_quadratic; axisymmetric: on the circle
  !> 2 pi r) in the load group of the statement's ramp or curve.  FORCE is
  !> point_supports'.
  !>   deck  (in)    the deck (its file, for the messages)
  !>   bdeck (in)    the body's statements, its loads
  !>   bd    (in)    the body, its mesh and dof0
  !>   lg    (inout) the load groups: fgroup gets the forces
  !>   diag  (inout) unknown boundaries, edges not on the body's outer boundary
  subroutine apply_edge_loads(deck, bdeck, bd, lg, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(body_t), intent(in) :: bd
    class(load_groups_t), intent(inout) :: lg
    type(diag_t), intent(inout) :: diag
    integer :: k, ib, s, na, nb, nm, g
    real(dp) :: t(2), fe(6), chord(2), pr
    real(dp), allocatable :: nrm(:,:)
    logical :: ok, along_normal
    associate(m => bd%mesh)
      do k = 1, size(bdeck%loads)
        associate(ld => bdeck%loads(k))
          if (ld%kind == LOAD_POINT) cycle                 ! FORCE: point_supports
          ib = boundary_index(deck, ld%line, bd, ld%boundary, merge('TRACTION', 'PRESSURE', ld%kind == LOAD_TRACTION), &
                              need_edges, diag)
          if (ib == 0) cycle
          along_normal = ld%kind == LOAD_PRESSURE .or. ld%local
          if (along_normal) then
            call edge_normals(bd, ib, nrm, ok)
            if (.not. ok) then
              call add_error(diag, deck%file, ld%line, merge('PRESSURE', 'TRACTION', ld%kind == LOAD_PRESSURE) // &
                ' on "' // ld%boundary // '": an edge is not on the outer boundary of body "' // bd%name // &
                '" (boundary edges expected)')
              cycle
            end if
          end if
          g = ramp_group(lg, ld%ramp, ld%curve)
          do s = 1, m%bnd(ib)%nseg
            na = m%bnd(ib)%seg(1, s)
            nb = m%bnd(ib)%seg(2, s)
            pr = 0.0_dp
            if (.not. along_normal) then
              t = [ld%tx, ld%ty]
            else if (ld%kind == LOAD_TRACTION) then       ! tn n + tt t, t = (-n_y, n_x)
              t = ld%tx * nrm(:, s) + ld%ty * [-nrm(2, s), nrm(1, s)]
            else
              t = -ld%p * nrm(:, s)                       ! positive pressure pushes into the body
              if (allocated(m%bnd(ib)%mid)) then
                ! a curved edge: the pressure follows the edge's normal, outward on the
                ! right of na -> nb when the chord's right normal points outward
                chord = m%x(:, nb) - m%x(:, na)
                pr = -ld%p * sign(1.0_dp, dot_product(nrm(:, s), [chord(2), -chord(1)]))
                t = 0.0_dp
              end if
            end if
            if (allocated(m%bnd(ib)%mid) .and. bd%axisymmetric) then
              nm = m%bnd(ib)%mid(s)
              call axi_edge_load_quadratic(reshape([m%x(:, na), m%x(:, nb), m%x(:, nm)], [2, 3]), t, pr, fe(1:6))
            else if (allocated(m%bnd(ib)%mid)) then       ! 3-node edge, 3-point Gauss
              nm = m%bnd(ib)%mid(s)
              call edge_load_quadratic(reshape([m%x(:, na), m%x(:, nb), m%x(:, nm)], [2, 3]), t, pr, bd%thick, fe(1:6))
            else if (bd%axisymmetric) then                ! per unit area, on the circle 2 pi r
              call axi_edge_load(m%x(:, na), m%x(:, nb), t, fe(1:4))
            else
              call edge_load(m%x(:, na), m%x(:, nb), t, bd%thick, fe(1:4))
            end if
            associate(f => lg%fgroup(:, g))
              f(bd%dof0 + 2 * (na - 1) + [1, 2]) = f(bd%dof0 + 2 * (na - 1) + [1, 2]) + fe(1:2)
              f(bd%dof0 + 2 * (nb - 1) + [1, 2]) = f(bd%dof0 + 2 * (nb - 1) + [1, 2]) + fe(3:4)
              if (allocated(m%bnd(ib)%mid)) &
                f(bd%dof0 + 2 * (nm - 1) + [1, 2]) = f(bd%dof0 + 2 * (nm - 1) + [1, 2]) + fe(5:6)
            end associate
          end do
        end associate
      end do
    end associate
  end subroutine apply_edge_loads

  !> The volume loads of a body: BODYFORCE and GRAVITY (rho g, with its
  !> DENSITY), in one element loop when they share a ramp or curve.
  !>   deck  (in)    the deck (GRAVITY)
  !>   bdeck (in)    the body's statements
  !>   bd    (in)    the body, its mesh and dof0
  !>   lg    (inout) the load groups: fgroup gets the forces
  subroutine apply_body_loads(deck, bdeck, bd, lg)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(body_t), intent(in) :: bd
    class(load_groups_t), intent(inout) :: lg
    logical :: gravity
    integer :: g
    gravity = deck%has_gravity .and. bdeck%has_density
    if (bdeck%has_bodyforce .and. gravity .and. all(bdeck%bodyforce_ramp == deck%gravity_ramp) .and. &
        bdeck%bodyforce_curve == deck%gravity_curve) then
      g = ramp_group(lg, deck%gravity_ramp, deck%gravity_curve)
      call add_body_load(bd, [bdeck%fx, bdeck%fy] + bdeck%rho * [deck%gx, deck%gy], lg%fgroup(:, g))
      return
    end if
    if (bdeck%has_bodyforce) then
      g = ramp_group(lg, bdeck%bodyforce_ramp, bdeck%bodyforce_curve)
      call add_body_load(bd, [bdeck%fx, bdeck%fy], lg%fgroup(:, g))
    end if
    if (gravity) then
      g = ramp_group(lg, deck%gravity_ramp, deck%gravity_curve)
      call add_body_load(bd, bdeck%rho * [deck%gx, deck%gy], lg%fgroup(:, g))
    end if
  end subroutine apply_body_loads

  !> f += the nodal forces of the body force density bf (per unit volume) on
  !> every element of bd (elements: element_body_load; axisymmetric on the
  !> circle 2 pi r).
  !>   bd (in)    the body
  !>   bf (in)    (2) the force per unit volume, x, y
  !>   f  (inout) (ndof) a load group's forces
  subroutine add_body_load(bd, bf, f)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: bf(2)
    real(dp), intent(inout) :: f(:)
    integer :: e, nen
    integer :: dofs(2 * max_nen)
    real(dp) :: fe(2 * max_nen)
    associate(m => bd%mesh)
      do e = 1, m%nelem
        nen = m%nen(e)
        if (bd%axisymmetric) then
          call axi_element_body_load(nen, m%x(:, m%conn(1:nen, e)), bf, fe(1:2 * nen))
        else
          call element_body_load(nen, m%x(:, m%conn(1:nen, e)), bf, bd%thick, fe(1:2 * nen))
        end if
        call element_dofs(bd, e, dofs)
        f(dofs(1:2 * nen)) = f(dofs(1:2 * nen)) + fe(1:2 * nen)
      end do
    end associate
  end subroutine add_body_load

  !> alpha dT per element from the THERMAL statements of a body: the one
  !> without region= sets every element, those with region= set their region's
  !> elements (a region statement overrides the whole-body one there).  Each
  !> statement follows its curve= (else the ramp 0:STEPS): its elements' nodal
  !> forces go to that load group, and alpha dT and the group per element
  !> are kept for the steps' strains (scene: step_thermal_strains).
  !>   deck  (in)    the deck (STEPS; its file, for the messages)
  !>   bdeck (in)    the body's statements, some THERMAL
  !>   bd    (inout) the body; its adt on exit alpha dT at load factor 1
  !>   lg    (inout) the load groups: fgroup gets the strains' nodal forces
  !>   adt1  (out)   (nelem) alpha dT of each element at load factor 1 (not
  !>                 allocated when diag has errors)
  !>   group (out)   (nelem) the load group of each element's THERMAL
  !>   diag  (inout) unknown regions
  subroutine apply_thermal(deck, bdeck, bd, lg, adt1, group, diag)
    type(deck_t), intent(in) :: deck
    type(body_deck_t), intent(in) :: bdeck
    type(body_t), intent(inout) :: bd
    class(load_groups_t), intent(inout) :: lg
    real(dp), allocatable, intent(out) :: adt1(:)
    integer, allocatable, intent(out) :: group(:)
    type(diag_t), intent(inout) :: diag
    integer :: k, ir, g
    allocate(bd%adt(bd%mesh%nelem), source=0.0_dp)
    allocate(group(bd%mesh%nelem), source=1)
    do k = 1, size(bdeck%thermals)
      if (len(bdeck%thermals(k)%region) == 0) then
        bd%adt = bdeck%thermals(k)%alpha * bdeck%thermals(k)%dt
        group = ramp_group(lg, [0, deck%steps], bdeck%thermals(k)%curve)
      end if
    end do
    do k = 1, size(bdeck%thermals)
      associate(th => bdeck%thermals(k))
        if (len(th%region) == 0) cycle
        ir = find_name(bd%mesh%reg, th%region)
        if (ir == 0) then
          call add_error(diag, deck%file, th%line, 'THERMAL: unknown region "' // th%region // '" in body "' // &
                         bd%name // '" (expected one of: ' // &
                         name_list(bd%mesh%reg, 'none: the mesh names no physical surface') // ')')
          cycle
        end if
        bd%adt(bd%mesh%reg(ir)%elems) = th%alpha * th%dt
        group(bd%mesh%reg(ir)%elems) = ramp_group(lg, [0, deck%steps], th%curve)
      end associate
    end do
    if (has_errors(diag)) return
    ! the nodal forces of each group's elements (adt masked to them) go to its
    ! column: body's thermal_loads reads the strains from the body
    adt1 = bd%adt
    do g = 1, size(lg%ramp, 2)
      if (.not. any(group == g)) cycle
      bd%adt = merge(adt1, 0.0_dp, group == g)
      call thermal_loads(bd, lg%fgroup(:, g))
    end do
    bd%adt = adt1
  end subroutine apply_thermal

end module body_loads
