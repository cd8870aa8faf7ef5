!> deck_checks: what can be checked only once the whole deck is read, and the
!> deck's defaults.
!>
!>   open block at the end, bodies with a MESH and a MATERIAL, orthotropic
!>   compliance in plane strain, rect boundary names, CONTACT bodies and
!>   RIGIDs resolved, rigid-body modes (every body held by a FIX, directly or
!>   through CONTACT), ramps within STEPS, curve names resolved, RIGIDs with a
!>   SHAPE, output names distinct and not too long, PLANE axisymmetric loads,
!>   ADAPT with the error estimate.
!>
!> Programming interface
!>   finish_checks(s, deck)         every check above, reported through deck_syntax
!>   cut_statement_lists(s, deck)   FIX and load lists cut to their counts
!>   fill_defaults(deck)            every character component allocated, ramps resolved
!>   path_too_long(path, reserve)   '' or what makes path an impossible file name
module deck_checks
  use kinds, only: dp
  use strings, only: int_to_str, format_number
  use deck_types, only: deck_t, body_deck_t, contact_deck_t, rigid_load_t
  use deck_syntax, only: state_t, report, quoted, ramp_unset
  use text_scan, only: is_name
  use deck_body_statements, only: plane_compliance_ok, strain_compliance_ok
  implicit none
  private
  public :: finish_checks, cut_statement_lists, fill_defaults, path_too_long

contains

  !> Checks that need the whole deck: open block, bodies complete, rect boundary
  !> names, plane-strain compliance, CONTACT bodies, rigid-body modes, ramps within
  !> STEPS, curves, RIGIDs, output names, PLANE axisymmetric, ADAPT.
  subroutine finish_checks(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    integer :: b, i
    logical :: resolved, rect, unknown

    if (s%block /= '' .and. .not. s%end_hinted) &
      call report(s, s%nline, 'missing END for ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                  ' opened at line ' // int_to_str(s%block_line) // &
                  ' (expected END before the end of the file)', echo=.false.)
    if (s%nbody == 0) then
      call report(s, 0, 'deck has no BODY (at least one BODY ... END block expected)')
      return
    end if

    do b = 1, s%nbody
      associate (body => deck%bodies(b))
        rect = is_name(body%name) .and. allocated(body%mesh%kind)
        if (rect) rect = body%mesh%kind == 'rect'
        do i = 1, size(body%fixes)
          call check_statement(body, body%fixes(i)%boundary, body%fixes(i)%ramp, body%fixes(i)%line)
        end do
        do i = 1, size(body%loads)
          call check_statement(body, body%loads(i)%boundary, body%loads(i)%ramp, body%loads(i)%line)
        end do
        do i = 1, size(body%springs)
          if (rect) call check_rect_boundary(s, body, body%springs(i)%boundary, body%springs(i)%line)
        end do
        if (.not. is_name(body%name)) cycle
        ! a body block with an unknown keyword: that statement is most likely its
        ! misspelt MESH or MATERIAL, already reported at its own line; "has no
        ! MATERIAL" at the BODY line would come first and point the user elsewhere
        unknown = .false.
        if (allocated(s%unknown_body)) unknown = any(s%unknown_body == b)
        if (body%mesh%line == 0 .and. .not. unknown) call report(s, body%line, 'body ' // quoted(body%name) // &
                                             ' has no MESH (expected a MESH statement in its BODY block)')
        if (body%material%line == 0 .and. .not. unknown) call report(s, body%line, 'body ' // quoted(body%name) // &
                                                 ' has no MATERIAL (expected a MATERIAL statement in its BODY block)')
        if (.not. deck%plane_stress .and. allocated(body%material%kind)) then
          if (body%material%kind == 'orthotropic') then
            if (plane_compliance_ok(body%material) .and. .not. strain_compliance_ok(body%material)) &
              call report(s, body%material%line, 'orthotropic compliance not positive definite for PLANE ' // &
                          'strain (expected 1 - nu12^2 E2/E1 - nu23^2 E3/E2 - nu13^2 E3/E1 - ' // &
                          '2 nu12 nu23 nu13 E3/E1 > 0)')
          end if
        end if
      end associate
    end do

    call resolve_contacts(s, deck, resolved)
    if (resolved) call check_finite_strain_scene(s, deck)
    if (resolved .and. .not. s%contact_bad) call check_rigid_modes(s, deck)
    call check_ramps(s, deck)
    call resolve_curves(s, deck)
    call check_rigids(s, deck)
    call check_output_names(s, deck)
    if (deck%axisymmetric) call check_axisymmetric(s, deck)
    if (deck%adapt%on) call check_adapt(s, deck)
  contains
    !> A FIX or load of a body: its boundary (rect meshes), its ramp's end.
    subroutine check_statement(body, boundary, ramp, line)
      type(body_deck_t), intent(in) :: body
      character(len=*), intent(in) :: boundary
      integer, intent(in) :: ramp(2), line
      if (rect) call check_rect_boundary(s, body, boundary, line)
      if (.not. s%steps_bad) call check_ramp_end(s, deck, ramp, line)
    end subroutine check_statement
  end subroutine finish_checks

  !> A scene with a hyperelastic body is solved by Newton's method on the
  !> whole scene (doc/theory.md, "Hyperelastic bodies in finite strain"):
  !> every CONTACT follows the bodies (sliding=finite implied; sliding=small,
  !> the pairing of the initial configuration, and gap=zero, the initial
  !> gaps, are errors); the laws need F33 (plane strain or axisymmetric, not
  !> plane stress); and ADAPT, whose estimators are linear elasticity's, is
  !> not available.
  subroutine check_finite_strain_scene(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    integer :: i, b
    character(len=:), allocatable :: name
    name = ''
    do b = 1, s%nbody
      if (.not. is_hyperelastic(deck%bodies(b))) cycle
      if (len(name) == 0) name = deck%bodies(b)%name
      if (deck%plane_stress) call report(s, deck%bodies(b)%material%line, 'MATERIAL ' // &
        deck%bodies(b)%material%kind // ' in PLANE stress (expected PLANE strain or axisymmetric: the law needs ' // &
        'the through-thickness stretch F33, which plane stress leaves unknown)')
    end do
    if (len(name) == 0) return
    do i = 1, s%ncontact
      associate (c => deck%contacts(i))
        if (c%small_given) then
          call report(s, c%line, 'sliding=small in a scene with the hyperelastic body ' // quoted(name) // &
                      ' (expected sliding=finite, implied: a body in finite strain moves its contact zone)')
        else if (c%gap_zero) then
          call report(s, c%line, 'gap=zero in a scene with the hyperelastic body ' // quoted(name) // &
                      ' (expected gap=geometry: its pairs measure the gaps in the current configuration)')
        end if
        c%finite = .true.
        if (allocated(deck%solver%newton_lcp)) then
          if (deck%solver%newton_lcp == 'active_set' .and. (c%mu > 0 .or. c%tresca > 0)) &
            call report(s, deck%solver%line, 'newton_lcp=active_set with the ' // c%friction // &
                        ' friction of the CONTACT at line ' // int_to_str(c%line) // ' (expected frictionless pairs, ' // &
                        'or newton_lcp=lemke: the active-set iteration has no friction cone)')
        end if
      end associate
    end do
    if (deck%adapt%on) call report(s, deck%adapt%line, 'ADAPT in a scene with the hyperelastic body ' // &
      quoted(name) // ' (its error estimators are those of linear elasticity)')
  end subroutine check_finite_strain_scene

  !> The body's MATERIAL is neo_hookean or mooney_rivlin (solved in finite strain).
  pure logical function is_hyperelastic(body)
    type(body_deck_t), intent(in) :: body
    is_hyperelastic = .false.
    if (.not. allocated(body%material%kind)) return
    is_hyperelastic = body%material%kind == 'neo_hookean' .or. body%material%kind == 'mooney_rivlin'
  end function is_hyperelastic

  !> ADAPT against the rest of the deck: it is driven by the error estimate
  !> (not with ESTIMATE off) and quantity=pressure needs a CONTACT.  (That
  !> gmsh can make every mesh again, an .msh with its .geo beside it, is
  !> checked with the files, in the adaptive loop's setup.)
  subroutine check_adapt(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    if (.not. deck%estimate) call report(s, deck%adapt%line, 'ADAPT needs the error estimate, which ESTIMATE off ' // &
      'at line ' // int_to_str(deck%estimate_line) // ' turns off (expected one of them)')
    if (deck%adapt%quantity == 'pressure' .and. size(deck%contacts) == 0) call report(s, deck%adapt%line, &
      'ADAPT quantity=pressure but the deck has no CONTACT (expected quantity=energy, or a CONTACT pair)')
  end subroutine check_adapt

  !> What PLANE axisymmetric cannot take: gravity off the axis (a load that
  !> depends on the angle theta, not a solid of revolution's), and a RIGID
  !> moved or loaded across the axis or turned (FIX ux=/rz=, FORCE fx=/m=
  !> other than 0: a solid of revolution moves along its axis only; the
  !> scene holds u_x and theta at 0).  The bodies' r >= 0 is checked with
  !> their meshes (scene).
  subroutine check_axisymmetric(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer :: r, k
    if (deck%gravity_line > 0 .and. deck%gx /= 0.0_dp) &
      call report(s, deck%gravity_line, 'GRAVITY gx= ' // trim(format_number(deck%gx)) // ' across the axis in ' // &
                  'PLANE axisymmetric (line ' // int_to_str(deck%plane_line) // ') (gravity along the axis z ' // &
                  'expected: gx=0, gy=...)')
    do r = 1, size(deck%rigids)
      do k = 1, size(deck%rigids(r)%fixes)
        call check_rigid_axial(deck%rigids(r)%fixes(k), 'FIX', ['ux', 'rz'], deck%rigids(r)%name)
      end do
      do k = 1, size(deck%rigids(r)%forces)
        call check_rigid_axial(deck%rigids(r)%forces(k), 'FORCE', ['fx', 'm '], deck%rigids(r)%name)
      end do
    end do
  contains
    ! the statement's x and rotation components: absent or 0
    subroutine check_rigid_axial(ld, what, keys, name)
      type(rigid_load_t), intent(in) :: ld
      character(len=*), intent(in) :: what, keys(2), name
      character(len=:), allocatable :: along
      integer :: j, c
      along = 'uy='
      if (what == 'FORCE') along = 'fy='
      do j = 1, 2
        c = merge(1, 3, j == 1)
        if (ld%has(c) .and. ld%value(c) /= 0.0_dp) &
          call report(s, ld%line, 'RIGID ' // quoted(name) // ' ' // what // ' ' // trim(keys(j)) // '=' // &
            trim(format_number(ld%value(c))) // ' in PLANE axisymmetric (line ' // int_to_str(deck%plane_line) // &
            ') (a RIGID of revolution moves along the axis only: ' // trim(keys(j)) // '=0 or absent, ' // along // &
            ' along the axis)')
      end do
    end subroutine check_rigid_axial
  end subroutine check_axisymmetric

  !> BODYFORCE and GRAVITY ramps end at step STEPS at the latest (those of FIX
  !> and loads: finish_checks; k0 < k1 and k0 >= 0 were checked with the
  !> statement).  Nothing is said when STEPS itself was bad.
  subroutine check_ramps(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer :: b

    if (s%steps_bad) return
    do b = 1, s%nbody
      associate (body => deck%bodies(b))
        if (body%bodyforce_line > 0) call check_ramp_end(s, deck, body%bodyforce_ramp, body%bodyforce_line)
      end associate
    end do
    if (deck%gravity_line > 0) call check_ramp_end(s, deck, deck%gravity_ramp, deck%gravity_line)
  end subroutine check_ramps

  !> Every curve=NAME names a CURVE of the deck (index into deck%curves).
  subroutine resolve_curves(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    integer :: b, i
    do b = 1, s%nbody
      associate (body => deck%bodies(b))
        do i = 1, size(body%fixes)
          body%fixes(i)%curve = curve_index(s, deck, body%fixes(i)%curve_name, body%fixes(i)%line)
        end do
        do i = 1, size(body%loads)
          body%loads(i)%curve = curve_index(s, deck, body%loads(i)%curve_name, body%loads(i)%line)
        end do
        do i = 1, size(body%thermals)
          body%thermals(i)%curve = curve_index(s, deck, body%thermals(i)%curve_name, body%thermals(i)%line)
        end do
        body%bodyforce_curve = curve_index(s, deck, body%bodyforce_curve_name, body%bodyforce_line)
      end associate
    end do
    deck%gravity_curve = curve_index(s, deck, deck%gravity_curve_name, deck%gravity_line)
  end subroutine resolve_curves

  !> Report ramp(2) > STEPS at the line of the statement holding the ramp.
  subroutine check_ramp_end(s, deck, ramp, line)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: ramp(2), line
    character(len=:), allocatable :: text

    if (ramp(2) <= deck%steps) return
    text = 'ramp=' // int_to_str(ramp(1)) // ':' // int_to_str(ramp(2)) // ' ends after the last load step'
    if (deck%steps_line > 0) then
      call report(s, line, text // ' (expected k1 <= ' // int_to_str(deck%steps) // ', the STEPS value at line ' // &
                  int_to_str(deck%steps_line) // ')')
    else
      call report(s, line, text // ' (expected k1 <= 1, as STEPS defaults to 1 when absent)')
    end if
  end subroutine check_ramp_end

  !> A rect mesh names its boundaries left, right, bottom, top.
  subroutine check_rect_boundary(s, body, name, line)
    type(state_t), intent(inout) :: s
    type(body_deck_t), intent(in) :: body
    character(len=*), intent(in) :: name
    integer, intent(in) :: line
    if (len(name) == 0) return
    select case (name)
    case ('left', 'right', 'bottom', 'top')
    case default
      call report(s, line, 'unknown boundary ' // quoted(name) // ' of BODY ' // quoted(body%name) // &
                  ' (expected one of left, right, bottom, top for MESH rect)')
    end select
  end subroutine check_rect_boundary

  !> Body indices of the CONTACT statements; duplicates; rect boundary names.
  subroutine resolve_contacts(s, deck, resolved)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    logical, intent(out) :: resolved
    integer :: i, j, b
    character(len=:), allocatable :: known

    resolved = .true.
    known = ''
    do b = 1, s%nbody
      if (.not. is_name(deck%bodies(b)%name)) cycle
      if (len(known) > 0) known = known // ', '
      known = known // deck%bodies(b)%name
    end do
    if (len(known) > 200) known = known(1:200) // ' ...'
    do i = 1, s%ncontact
      associate (c => deck%contacts(i))
        c%slave_body = find_body(deck, s%nbody, s%slave_name(i)%s)
        if (len(c%master_boundary) == 0) then         ! master=RIGIDNAME
          do j = 1, size(deck%rigids)
            if (deck%rigids(j)%name == s%master_name(i)%s .and. &
                len(deck%rigids(j)%name) == len(s%master_name(i)%s)) c%master_rigid = j
          end do
          if (c%master_rigid == 0) call report(s, c%line, 'unknown RIGID ' // quoted(s%master_name(i)%s) // &
            ' in CONTACT master= (expected master=body:boundary or the name of a RIGID block)')
          if (c%slave_body == 0) call report(s, c%line, 'unknown body ' // quoted(s%slave_name(i)%s) // &
                                             ' in CONTACT (expected one of ' // known // ')')
          if (c%slave_body == 0 .or. c%master_rigid == 0) then
            resolved = .false.
          else
            call check_contact_side(s, deck%bodies(c%slave_body), c%slave_boundary, c%line)
            do j = 1, i - 1
              if (deck%contacts(j)%master_rigid == c%master_rigid .and. deck%contacts(j)%slave_body == c%slave_body &
                  .and. deck%contacts(j)%slave_boundary == c%slave_boundary) &
                call report(s, c%line, 'duplicate CONTACT (same slave boundary and RIGID as at line ' // &
                            int_to_str(deck%contacts(j)%line) // '; expected each pair once)')
            end do
          end if
          cycle
        end if
        c%master_body = find_body(deck, s%nbody, s%master_name(i)%s)
        if (c%slave_body == 0) call report(s, c%line, 'unknown body ' // quoted(s%slave_name(i)%s) // &
                                           ' in CONTACT (expected one of ' // known // ')')
        if (c%master_body == 0 .and. s%master_name(i)%s /= s%slave_name(i)%s) &
          call report(s, c%line, 'unknown body ' // quoted(s%master_name(i)%s) // ' in CONTACT (expected one of ' // &
                      known // ')')
        if (c%slave_body == 0 .or. c%master_body == 0) then
          resolved = .false.
          cycle
        end if
        call check_contact_side(s, deck%bodies(c%slave_body), c%slave_boundary, c%line)
        call check_contact_side(s, deck%bodies(c%master_body), c%master_boundary, c%line)
        do j = 1, i - 1
          if (same_pair(c, deck%contacts(j))) then
            call report(s, c%line, 'duplicate CONTACT (same two boundaries as at line ' // &
                        int_to_str(deck%contacts(j)%line) // '; expected each pair once)')
            exit
          end if
        end do
      end associate
    end do
  end subroutine resolve_contacts

  subroutine check_contact_side(s, body, boundary, line)
    type(state_t), intent(inout) :: s
    type(body_deck_t), intent(in) :: body
    character(len=*), intent(in) :: boundary
    integer, intent(in) :: line
    if (.not. allocated(body%mesh%kind)) return
    if (body%mesh%kind == 'rect') call check_rect_boundary(s, body, boundary, line)
  end subroutine check_contact_side

  !> Two CONTACTs join the same two boundaries (in either role).
  pure logical function same_pair(a, b)
    type(contact_deck_t), intent(in) :: a, b
    same_pair = .false.
    if (a%master_rigid > 0 .or. b%master_rigid > 0) return
    same_pair = (a%slave_body == b%slave_body .and. a%slave_boundary == b%slave_boundary .and. &
                 a%master_body == b%master_body .and. a%master_boundary == b%master_boundary) .or. &
                (a%slave_body == b%master_body .and. a%slave_boundary == b%master_boundary .and. &
                 a%master_body == b%slave_body .and. a%master_boundary == b%slave_boundary)
  end function same_pair

  pure integer function find_body(deck, nbody, name) result(b)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: nbody
    character(len=*), intent(in) :: name
    do b = 1, nbody
      if (deck%bodies(b)%name == name .and. len(deck%bodies(b)%name) == len(name)) return
    end do
    b = 0
  end function find_body

  !> Every body must be held: a FIX of its own, or a CONTACT chain to a body with a
  !> FIX.  A body with neither FIX nor CONTACT, and a group of bodies joined by
  !> CONTACT none of which has a FIX, has rigid-body modes.
  subroutine check_rigid_modes(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer, allocatable :: group(:)
    logical, allocatable :: in_contact(:), on_rigid(:)
    integer :: b, i, g, a, c, nmem
    logical :: held, changed
    character(len=:), allocatable :: members

    allocate(group(s%nbody), in_contact(s%nbody))
    in_contact = .false.
    do b = 1, s%nbody
      group(b) = b
    end do
    allocate(on_rigid(s%nbody), source=.false.)
    do i = 1, s%ncontact
      in_contact(deck%contacts(i)%slave_body) = .true.
      if (deck%contacts(i)%master_rigid > 0) then
        on_rigid(deck%contacts(i)%slave_body) = .true.   ! a RIGID holds what touches it (checked when solved)
        cycle
      end if
      in_contact(deck%contacts(i)%master_body) = .true.
    end do
    changed = .true.                          ! label propagation: group = smallest member
    do while (changed)
      changed = .false.
      do i = 1, s%ncontact
        if (deck%contacts(i)%master_rigid > 0) cycle
        a = deck%contacts(i)%slave_body
        c = deck%contacts(i)%master_body
        if (group(a) /= group(c)) then
          group(a) = min(group(a), group(c))
          group(c) = group(a)
          changed = .true.
        end if
      end do
    end do
    do b = 1, s%nbody
      if (.not. is_name(deck%bodies(b)%name)) cycle
      if (size(deck%bodies(b)%fixes) + size(deck%bodies(b)%springs) > 0) cycle
      if (.not. in_contact(b)) then
        call report(s, deck%bodies(b)%line, 'body ' // quoted(deck%bodies(b)%name) // ' has no FIX and is in no ' // &
                    'CONTACT (rigid-body modes: expected FIX on a boundary, a SPRING, or a CONTACT that holds the body)')
        cycle
      end if
      g = group(b)
      if (g /= b) cycle                      ! report each group once, at its first body
      held = .false.
      members = ''
      nmem = 0
      do a = 1, s%nbody
        if (group(a) /= g) cycle
        if (size(deck%bodies(a)%fixes) + size(deck%bodies(a)%springs) > 0 .or. on_rigid(a)) held = .true.
        nmem = nmem + 1
        if (nmem > 1) members = members // ', '
        members = members // quoted(deck%bodies(a)%name)
      end do
      if (.not. held) call report(s, deck%bodies(b)%line, 'no FIX on any of the bodies ' // members // &
                                  ' held together by CONTACT (rigid-body modes: expected FIX on a boundary ' // &
                                  'of at least one of them)')
    end do
  end subroutine check_rigid_modes

  !> The three output files must have different names.
  subroutine check_output_names(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    character(len=:), allocatable :: v, c, m, stem
    integer :: line
    call fill_defaults(deck)
    v = deck%output%vtk
    c = deck%output%contact
    m = deck%output%summary
    line = deck%output%line
    if (v == c .and. len(v) == len(c)) then
      call report(s, line, 'OUTPUT files must differ (vtk and contact are both ' // quoted(v) // ')')
    else if (v == m .and. len(v) == len(m)) then
      call report(s, line, 'OUTPUT files must differ (vtk and summary are both ' // quoted(v) // ')')
    else if (c == m .and. len(c) == len(m)) then
      call report(s, line, 'OUTPUT files must differ (contact and summary are both ' // quoted(c) // ')')
    else if (deck%output%steps_all) then
      ! steps=all adds STEM.pvd and STEM_steps.csv (STEM: the vtk name without .vtk)
      v = v(1:len(v) - 4)
      if (c == v // '.pvd' .or. m == v // '.pvd' .or. c == v // '_steps.csv' .or. m == v // '_steps.csv') &
        call report(s, line, 'OUTPUT files must differ (steps=all writes ' // quoted(v // '.pvd') // ' and ' // &
                    quoted(v // '_steps.csv') // ', which contact= or summary= names too)')
    end if
    if (deck%output%plot) then
      ! plot=png adds STEM_pressure.png and STEM_steps.png
      stem = deck%output%vtk(1:len(deck%output%vtk) - 4)
      if (c == stem // '_pressure.png' .or. m == stem // '_pressure.png' .or. c == stem // '_steps.png' .or. &
          m == stem // '_steps.png') &
        call report(s, line, 'OUTPUT files must differ (plot=png writes ' // quoted(stem // '_pressure.png') // &
                    ' and ' // quoted(stem // '_steps.png') // ', which contact= or summary= names too)')
    end if
    ! each is written as NAME.part first, then renamed: 5 bytes kept for that
    if (len(path_too_long(v, 5)) > 0) call report(s, line, 'OUTPUT vtk: ' // path_too_long(v, 5))
    if (len(path_too_long(c, 5)) > 0) call report(s, line, 'OUTPUT contact: ' // path_too_long(c, 5))
    if (len(path_too_long(m, 5)) > 0) call report(s, line, 'OUTPUT summary: ' // path_too_long(m, 5))
  end subroutine check_output_names

  !> '' when the system can take path as a file name, else what is wrong: a
  !> component longer than NAME_MAX (255 bytes) or a path longer than PATH_MAX
  !> (4096), which open() refuses with ENAMETOOLONG whatever the folder.
  !>   path    (in) the name, as it will be opened
  !>   reserve (in) bytes the program adds to the last name (a temporary suffix)
  function path_too_long(path, reserve) result(msg)
    character(len=*), intent(in) :: path
    integer, intent(in) :: reserve
    character(len=:), allocatable :: msg
    integer, parameter :: name_max = 255, path_max = 4096
    integer :: i, first, limit
    msg = ''
    if (len(path) + reserve >= path_max) then
      msg = 'the path is ' // int_to_str(len(path)) // ' characters long (fewer than ' // &
            int_to_str(path_max - reserve) // ' expected: PATH_MAX)'
      return
    end if
    first = 1
    do i = 1, len(path) + 1
      if (i <= len(path)) then
        if (path(i:i) /= '/') cycle
      end if
      limit = name_max - merge(reserve, 0, i > len(path))
      if (i - first > limit) then
        msg = 'the name "' // path(first:first + 19) // '..." is ' // int_to_str(i - first) // &
              ' characters long (at most ' // int_to_str(limit) // ' expected: NAME_MAX'
        if (limit < name_max) msg = msg // ' is 255, less ' // int_to_str(reserve) // ' for the temporary suffix .part'
        msg = msg // ')'
        return
      end if
      first = i + 1
    end do
  end function path_too_long

  !> The index into deck%curves of curve=NAME (0 when absent or empty), reported
  !> with the deck's curve names when unknown.
  integer function curve_index(s, deck, name, line) result(curve)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    character(len=:), allocatable, intent(in) :: name
    integer, intent(in) :: line
    character(len=:), allocatable :: known
    integer :: c
    curve = 0
    if (.not. allocated(name)) return
    if (len(name) == 0) return
    do c = 1, size(deck%curves)
      if (deck%curves(c)%name == name .and. len(deck%curves(c)%name) == len(name)) then
        curve = c
        return
      end if
    end do
    known = ''
    do c = 1, size(deck%curves)
      if (c > 1) known = known // ', '
      known = known // deck%curves(c)%name
    end do
    if (size(deck%curves) == 0) then
      known = 'a CURVE statement of that name; the deck has none'
    else
      known = 'one of ' // known
    end if
    call report(s, line, 'unknown curve ' // quoted(name) // ' (expected ' // known // ')')
  end function curve_index

  !> After the whole deck: every RIGID has a SHAPE and a name no BODY has; the
  !> RIGIDs' ramps end by STEPS and their curves exist.
  subroutine check_rigids(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    integer :: r, b
    do r = 1, size(deck%rigids)
      associate (rg => deck%rigids(r))
        if (len(rg%name) == 0) cycle
        if (rg%shape_line == 0) call report(s, rg%line, 'RIGID ' // quoted(rg%name) // ' has no SHAPE (expected ' // &
                                            'SHAPE line|circle|polyline in its block)')
        do b = 1, s%nbody
          if (deck%bodies(b)%name == rg%name .and. len(deck%bodies(b)%name) == len(rg%name)) &
            call report(s, rg%line, 'RIGID ' // quoted(rg%name) // ' has the name of the BODY at line ' // &
                        int_to_str(deck%bodies(b)%line) // ' (expected a name of its own)')
        end do
        do b = 1, size(rg%fixes)
          call finish_load(rg%fixes(b))
        end do
        do b = 1, size(rg%forces)
          call finish_load(rg%forces(b))
        end do
      end associate
    end do
  contains
    subroutine finish_load(ld)
      type(rigid_load_t), intent(inout) :: ld
      call check_ramp_end(s, deck, ld%ramp, ld%line)
      if (ld%ramp(2) == ramp_unset(2)) ld%ramp = [0, deck%steps]
      ld%curve = curve_index(s, deck, ld%curve_name, ld%line)
    end subroutine finish_load
  end subroutine check_rigids

  !> Cut each body's FIX and load lists, grown by doubling while reading, to the
  !> statements they hold: from here on size() is the count.
  subroutine cut_statement_lists(s, deck)
    type(state_t), intent(in) :: s
    type(deck_t), intent(inout) :: deck
    integer :: b

    if (.not. allocated(deck%bodies)) return
    do b = 1, min(s%nbody, size(deck%bodies))
      associate (body => deck%bodies(b))
        if (allocated(body%fixes)) body%fixes = body%fixes(1:body%nfix)
        if (allocated(body%loads)) body%loads = body%loads(1:body%nload)
      end associate
    end do
  end subroutine cut_statement_lists

  !> Allocate every character component left unset; resolve the ramps not given
  !> (or not valid) to [0, steps].
  subroutine fill_defaults(deck)
    type(deck_t), intent(inout) :: deck
    integer :: b, i
    if (.not. allocated(deck%title)) deck%title = ''
    if (.not. allocated(deck%solver%lcp)) deck%solver%lcp = 'auto'
    if (.not. allocated(deck%solver%ordering)) deck%solver%ordering = 'auto'
    if (.not. allocated(deck%solver%condense)) deck%solver%condense = 'auto'
    if (.not. allocated(deck%output%vtk)) deck%output%vtk = deck%name // '.vtk'
    if (.not. allocated(deck%output%contact)) deck%output%contact = deck%name // '_contact.csv'
    if (.not. allocated(deck%output%summary)) deck%output%summary = deck%name // '.summary'
    do b = 1, size(deck%bodies)
      associate (body => deck%bodies(b), m => deck%bodies(b)%mesh)
        if (.not. allocated(body%name)) body%name = ''
        if (.not. allocated(m%kind)) m%kind = ''
        if (.not. allocated(m%elem)) m%elem = ''
        if (.not. allocated(m%diag)) m%diag = ''
        if (.not. allocated(m%file)) m%file = ''
        if (.not. allocated(m%path)) m%path = ''
        if (.not. allocated(m%set_names)) allocate(m%set_names(0))
        if (.not. allocated(m%set_values)) allocate(m%set_values(0))
        if (.not. allocated(body%material%kind)) body%material%kind = ''
        if (.not. allocated(body%fixes)) allocate(body%fixes(0))
        if (.not. allocated(body%loads)) allocate(body%loads(0))
        if (.not. allocated(body%thermals)) allocate(body%thermals(0))
        if (.not. allocated(body%springs)) allocate(body%springs(0))
        do i = 1, size(body%fixes)
          if (.not. allocated(body%fixes(i)%boundary)) body%fixes(i)%boundary = ''
          if (body%fixes(i)%ramp(2) == ramp_unset(2)) body%fixes(i)%ramp = [0, deck%steps]
        end do
        do i = 1, size(body%loads)
          if (body%loads(i)%ramp(2) == ramp_unset(2)) body%loads(i)%ramp = [0, deck%steps]
        end do
        if (body%bodyforce_line == 0 .or. body%bodyforce_ramp(2) == ramp_unset(2)) &
          body%bodyforce_ramp = [0, deck%steps]
      end associate
    end do
    if (deck%gravity_line == 0 .or. deck%gravity_ramp(2) == ramp_unset(2)) deck%gravity_ramp = [0, deck%steps]
    do i = 1, size(deck%rigids)
      associate (rg => deck%rigids(i))
        if (.not. allocated(rg%name)) rg%name = ''
        if (.not. allocated(rg%shape)) rg%shape = ''
        if (.not. allocated(rg%points)) allocate(rg%points(2, 0))
        if (.not. allocated(rg%fixes)) allocate(rg%fixes(0))
        if (.not. allocated(rg%forces)) allocate(rg%forces(0))
        do b = 1, size(rg%fixes)
          if (rg%fixes(b)%ramp(2) == ramp_unset(2)) rg%fixes(b)%ramp = [0, deck%steps]
        end do
        do b = 1, size(rg%forces)
          if (rg%forces(b)%ramp(2) == ramp_unset(2)) rg%forces(b)%ramp = [0, deck%steps]
        end do
      end associate
    end do
    do i = 1, size(deck%contacts)
      if (.not. allocated(deck%contacts(i)%slave_boundary)) deck%contacts(i)%slave_boundary = ''
      if (.not. allocated(deck%contacts(i)%master_boundary)) deck%contacts(i)%master_boundary = ''
      if (.not. allocated(deck%contacts(i)%friction)) deck%contacts(i)%friction = 'none'
    end do
  end subroutine fill_defaults

end module deck_checks
