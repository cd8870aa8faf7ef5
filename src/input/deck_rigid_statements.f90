!> deck_rigid_statements: the statements of a RIGID ... END block, one
!> handler each (rows in deck_statements' table; read_keys has checked their
!> keys before a handler runs).
!>
!>   RIGID name                     opens the block (deck%rigids grows by one)
!>   SHAPE line x0= y0= x1= y1= | circle xc= yc= r= [solid=inside|outside] | polyline points=x1:y1,...
!>   REF x= y=                      the reference point (default: the circle's centre, the first point)
!>   FIX [ux=] [uy=] [rz=] [ramp=|curve=]    prescribed motion (none given: held fixed)
!>   FORCE [fx=] [fy=] [m=] [ramp=|curve=]   load of the free directions
!>
!> Programming interface (statement handlers, deck_syntax's statement_handler)
!>   do_rigid, do_rigid_shape, do_rigid_ref, do_rigid_load (FIX and FORCE)
module deck_rigid_statements
  use kinds, only: dp
  use strings, only: int_to_str
  use deck_types, only: deck_t, rigid_deck_t, rigid_load_t
  use deck_syntax, only: state_t, stmt_t, key_values_t, report, read_keys, require_key, check_extra_words, &
                         check_no_pairs, check_name, form_word, quoted
  use text_scan, only: parse_real, lower
  implicit none
  private
  public :: do_rigid, do_rigid_shape, do_rigid_ref, do_rigid_load

contains

  !> RIGID name: opens a rigid obstacle's block (SHAPE, REF, FIX, FORCE, END).
  subroutine do_rigid(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(rigid_deck_t) :: rg
    integer :: r
    logical :: ok

    s%block_line = st%line
    s%block_name = ''
    if (st%nword > 0) s%block_name = st%word(1)%s
    rg%line = st%line
    rg%name = ''
    rg%shape = ''
    allocate(rg%points(2, 0), rg%fixes(0), rg%forces(0))
    if (st%nword == 0) then
      call report(s, st%line, 'missing rigid obstacle name (expected ' // st%usage // ')')
    else
      call check_name(s, st, st%word(1)%s, 'rigid obstacle', ok)
      if (ok) rg%name = st%word(1)%s
      call check_extra_words(s, st, 1, st%usage)
      do r = 1, size(deck%rigids)
        if (ok .and. deck%rigids(r)%name == rg%name .and. len(deck%rigids(r)%name) == len(rg%name)) &
          call report(s, st%line, 'duplicate RIGID name ' // quoted(rg%name) // ' (first at line ' // &
                      int_to_str(deck%rigids(r)%line) // '; expected a new name)')
      end do
    end if
    call check_no_pairs(s, st)
    deck%rigids = [deck%rigids, rg]
  end subroutine do_rigid

  !> SHAPE line x0= y0= x1= y1= | circle xc= yc= r= [solid=inside|outside] | polyline points=x1:y1,x2:y2,...
  !> One row for the three shapes: a key of another shape is refused by name
  !> ("does not belong") rather than as unknown.
  subroutine do_rigid_shape(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    logical :: allowed(9)
    character(len=:), allocatable :: kind
    integer :: k

    associate (rg => deck%rigids(size(deck%rigids)))
    rg%shape_line = st%line
    kind = form_word(s, st, 'shape')
    if (len(kind) == 0) return
    call read_keys(s, st, v)
    allowed = .false.
    select case (kind)
    case ('line')
      allowed(1:4) = .true.
      do k = 1, 4
        call require_key(s, st, v%seen(k), trim(st%keys(k)%name), 'SHAPE line', 'SHAPE line x0= y0= x1= y1=')
      end do
      rg%points = reshape(v%x(1:4), [2, 2])
      if (all(rg%points(:, 1) == rg%points(:, 2)) .and. all(v%seen(1:4))) &
        call report(s, st%line, 'SHAPE line of zero length (expected two different end points)')
    case ('circle')
      allowed(5:8) = .true.
      do k = 5, 7
        call require_key(s, st, v%seen(k), trim(st%keys(k)%name), 'SHAPE circle', 'SHAPE circle xc= yc= r=')
      end do
      rg%centre = v%x(5:6)
      if (v%ok(7)) rg%radius = v%x(7)
      rg%outside = v%ok(8) .and. v%text(8)%s == 'outside'
    case ('polyline')
      allowed(9) = .true.
      call require_key(s, st, v%seen(9), 'points', 'SHAPE polyline', 'SHAPE polyline points=x1:y1,x2:y2,...')
      if (allocated(v%text(9)%s)) call get_points(v%text(9)%s)
    case default
      call report(s, st%line, 'unknown shape ' // quoted(st%word(1)%s) // ' (expected line, circle or polyline)')
      return
    end select
    rg%shape = kind
    do k = 1, 9
      if (v%seen(k) .and. .not. allowed(k)) call report(s, st%line, 'key ' // quoted(trim(st%keys(k)%name)) // &
        ' does not belong to SHAPE ' // kind // ' (expected ' // st%usage // ')')
    end do
    end associate
  contains
    !> points=x1:y1,x2:y2,...: at least two points, consecutive ones different.
    subroutine get_points(text)
      character(len=*), intent(in) :: text
      integer :: p, q, colon, n, j
      real(dp) :: x, y
      logical :: okx, oky
      real(dp), allocatable :: pts(:,:)
      allocate(pts(2, 0))
      p = 1
      n = 0
      do while (p <= len(text))
        q = index(text(p:), ',')
        if (q == 0) then
          q = len(text) + 1
        else
          q = p + q - 1
        end if
        colon = index(text(p:q - 1), ':')
        okx = .false.
        oky = .false.
        if (colon > 1) then
          call parse_real(text(p:p + colon - 2), x, okx)
          call parse_real(text(p + colon:q - 1), y, oky)
        end if
        if (.not. (okx .and. oky)) then
          call report(s, st%line, 'bad point ' // quoted(text(p:q - 1)) // ' in points= (expected x:y with ' // &
                      'two finite numbers, points separated by commas)')
          return
        end if
        n = n + 1
        pts = reshape([pts, x, y], [2, n])
        p = q + 1
      end do
      if (n < 2) then
        call report(s, st%line, 'SHAPE polyline with ' // int_to_str(n) // ' point (expected at least two points)')
        return
      end if
      do j = 1, n - 1
        if (all(pts(:, j) == pts(:, j + 1))) then
          call report(s, st%line, 'SHAPE polyline repeats point ' // int_to_str(j) // ' (expected consecutive ' // &
                      'points to differ)')
          return
        end if
      end do
      deck%rigids(size(deck%rigids))%points = pts
    end subroutine get_points
  end subroutine do_rigid_shape

  !> REF x= y=: the reference point (default: the circle's centre, the first point)
  subroutine do_rigid_ref(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    associate (rg => deck%rigids(size(deck%rigids)))
      rg%ref_line = st%line
      call read_keys(s, st, v)
      rg%ref = v%x
      rg%has_ref = .true.
    end associate
  end subroutine do_rigid_ref

  !> FIX [ux=] [uy=] [rz=] [ramp=|curve=] (none given: all three 0) or
  !> FORCE [fx=] [fy=] [m=] [ramp=|curve=] (at least one) of a RIGID; each
  !> direction in one FIX or one FORCE at most.
  !> The open RIGID block is the last RIGID read.
  subroutine do_rigid_load(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(key_values_t) :: v
    integer :: j
    type(rigid_load_t) :: ld
    logical :: is_fix

    is_fix = st%what == 'FIX'
    associate (rg => deck%rigids(size(deck%rigids)), what => st%what, usage => st%usage)
    call read_keys(s, st, v)
    ld%value = v%x(1:3)
    ld%ramp = v%ramp
    ld%curve_name = v%curve
    ld%line = st%line
    ld%has = v%seen(1:3)
    if (is_fix .and. .not. any(v%seen(1:3))) ld%has = .true.        ! FIX alone: held fixed
    if (.not. is_fix .and. .not. any(v%seen(1:3))) call report(s, st%line, 'FORCE without a component (expected ' // &
                                                             usage // ')')
    ! a direction is prescribed by one FIX or loaded by one FORCE
    do j = 1, size(rg%fixes)
      if (any(ld%has .and. rg%fixes(j)%has)) call report(s, st%line, what // ' names a direction that the FIX at ' // &
        'line ' // int_to_str(rg%fixes(j)%line) // ' prescribes (expected each of ux/fx, uy/fy, rz/m in one ' // &
        'FIX or FORCE of the RIGID)')
    end do
    do j = 1, size(rg%forces)
      if (any(ld%has .and. rg%forces(j)%has)) call report(s, st%line, what // ' names a direction that the FORCE ' // &
        'at line ' // int_to_str(rg%forces(j)%line) // ' loads (expected each of ux/fx, uy/fy, rz/m in one ' // &
        'FIX or FORCE of the RIGID)')
    end do
    if (is_fix) then
      rg%fixes = [rg%fixes, ld]
    else
      rg%forces = [rg%forces, ld]
    end if
    end associate
  end subroutine do_rigid_load

end module deck_rigid_statements
