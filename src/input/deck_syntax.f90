!> deck_syntax: the deck reader's grammar machinery, shared by the statement
!> handlers (deck_statements, deck_body_statements, deck_rigid_statements) and
!> the whole-deck checks (deck_checks).
!>
!> Lines and words.  A line (comments cut, ${...} replaced) is split at blanks
!> into its keyword, positional words and key=value pairs (stmt_t); `key = value`
!> is joined when unambiguous.
!>
!> Errors.  report() collects `what is wrong (what was expected)` at a deck line;
!> hand_over() passes them to diag sorted by line, each with its line echoed:
!> the one place a FILE:LINE message is made.
!>
!> The table.  Each statement is a row (statement_t): its keyword, the form
!> word that selects it (MESH rect, MATERIAL isotropic), the block it stands
!> in, the block it opens, whether it may come once, the number of positional
!> words it takes, its usage line and its keys.  Each key (key_t) carries its
!> type (number, integer, choice a|b|c, ramp k0:k1, curve NAME, name, text),
!> whether it is required and the range of its value.  read_keys() checks a
!> statement's words and keys against its row in one place: extra words,
!> unknown, repeated and empty keys, required keys, numbers, integers, choices,
!> ranges, names, ramps and curves, each with its message; the handler then
!> finds the values converted (key_values_t) and checks the rules between keys.
!>
!> Programming interface
!>   string_t (text_scan's), stmt_t, state_t, statement_t, key_t, key_values_t, statement_handler
!>   report(s, line, text [, echo]), hand_over(s, file, diag)
!>   store_echo, split_words, join_equals, classify_words      one line into a stmt_t
!>   add_row, find_statement                                    the table
!>   real_key, integer_key, choice_key, ramp_key, curve_key, name_key, text_key
!>   read_keys(s, st, v [, what])                               a statement's words and keys
!>   check_extra_words, check_no_pairs, require_key, check_name, form_word, find_key, join_list
!>   cut, quoted, shown                                         user text in messages
!>   max_mu, max_steps, max_line_len, ramp_unset               the reader's limits
module deck_syntax
  use kinds, only: dp, i8
  use strings, only: int_to_str, format_number
  use errors, only: diag_t, add_error
  use deck_types, only: deck_t
  use deck_expressions, only: parameter_set_t
  use text_scan, only: parse_real, parse_integer, line_items, lower, is_name, string_t
  implicit none
  private
  public :: string_t, stmt_t, state_t, statement_t, key_t, key_values_t, statement_handler
  public :: report, hand_over, store_echo, split_words, join_equals, classify_words
  public :: add_row, find_statement
  public :: real_key, integer_key, choice_key, ramp_key, curve_key, name_key, text_key, read_keys
  public :: check_extra_words, check_no_pairs, require_key, check_name, form_word, find_key, join_list
  public :: cut, quoted, shown
  public :: max_mu, max_steps, max_line_len, ramp_unset

  integer, parameter :: max_errors = 100    ! stop reading after this many errors
  integer, parameter :: echo_len = 160      ! echoed lines are cut after this many chars
  integer, parameter :: quote_len = 40      ! quoted user text is cut after this many chars
  integer, parameter :: max_line_len = 1048576   !< longer lines: not a deck (e.g. /dev/zero, binary)
  integer, parameter :: max_steps = 100000  !< largest STEPS n
  real(dp), parameter :: max_mu = 1.0e3_dp  !< largest Coulomb coefficient mu=
  !> ramp(2) = 0 marks a ramp= not (validly) given until fill_defaults sets [0, steps]
  integer, parameter :: ramp_unset(2) = [0, 0]

  ! key_t%kind
  integer, parameter :: key_number = 1, key_integer = 2, key_choice = 3, key_ramp = 4, key_curve = 5, &
                        key_name = 6, key_text = 7

  !> One error before sorting by line.
  type :: err_t
    integer :: line = 0
    logical :: echo = .true.                  ! echo the deck line under the message
    character(len=:), allocatable :: text
  end type err_t

  !> One key of a statement: its name, the type of its value and its range.
  type :: key_t
    character(len=12) :: name = ''             !< canonical spelling (compared case-insensitively)
    integer :: kind = key_text                 !< key_number, key_integer, key_choice, ...
    logical :: required = .false.              !< a missing key is an error
    character(len=40) :: form = ''             !< the value's form for messages: number, a|b|c, k0:k1, NAME, ...
    logical :: has_lo = .false., has_hi = .false.   !< number: bounded below, above
    logical :: lo_strict = .false., hi_strict = .false.   !< number: x > lo rather than x >= lo (and x < hi)
    real(dp) :: lo = 0, hi = 0                 !< number: the bounds
    integer :: at_least = 0                    !< integer: the smallest value
    character(len=32) :: note = ''             !< number: said after the range; name: what the name is
  end type key_t

  !> The keys of one statement as read_keys found them, in the order of its row.
  type :: key_values_t
    logical, allocatable :: seen(:)            !< (nkey) the key was written (possibly without a value)
    logical, allocatable :: ok(:)              !< (nkey) its value was given and is valid
    type(string_t), allocatable :: text(:)       !< (nkey) the value as written, allocated when given and
                                               !< non-empty; a choice's value in its canonical spelling
    real(dp), allocatable :: x(:)              !< (nkey) a number key's value when ok
    integer, allocatable :: k(:)               !< (nkey) an integer key's value when ok
    integer :: ramp(2) = ramp_unset            !< ramp=k0:k1; ramp_unset when absent or bad
    character(len=:), allocatable :: curve     !< curve=NAME; '' when absent or bad
  end type key_values_t

  !> One statement split into words.
  type :: stmt_t
    integer :: line = 0
    character(len=:), allocatable :: keyword   !< as written
    character(len=:), allocatable :: rest      !< text after the keyword (TITLE)
    integer :: nword = 0                       !< positional words after the keyword
    type(string_t), allocatable :: word(:)
    integer :: npair = 0                       !< key=value pairs
    type(string_t), allocatable :: key(:), value(:)
    ! from the statement's row (dispatch)
    character(len=:), allocatable :: what      !< the statement for messages: 'FIX', 'MESH rect'
    character(len=:), allocatable :: usage     !< its usage line, for messages
    integer :: words = -1                      !< positional words it takes (-1: its handler checks)
    type(key_t), allocatable :: keys(:)        !< its keys
  end type stmt_t

  !> Reader state, local to one read_deck call.
  type :: state_t
    integer :: nerr = 0
    type(err_t), allocatable :: errs(:)
    logical :: gave_up = .false.
    integer :: nline = 0
    type(string_t), allocatable :: echo(:)      !< (nline) cut lines for echoing
    integer :: nbody = 0, ncontact = 0
    integer :: cur = 0                        !< body whose block is open, 0 outside
    logical :: end_hinted = .false.           !< a "missing END?" was said for the open block
    character(len=8) :: block = ''            !< the open block's keyword ('BODY'), '' at the top level
    character(len=:), allocatable :: block_name   !< its name, for messages
    integer :: block_line = 0                 !< its opening line
    integer, allocatable :: first_line(:)     !< (nrow) line of each top-level statement seen (once rows)
    integer, allocatable :: block_first(:)    !< (nrow) the same in the open block
    logical :: contact_bad = .false.          !< some CONTACT statement had an error
    integer, allocatable :: unknown_body(:)   !< bodies whose block holds an unknown keyword (a misspelt
                                              !< MESH or MATERIAL: "has no ..." would be its echo)
    logical :: steps_bad = .false.            !< the STEPS statement had an error
    type(string_t), allocatable :: slave_name(:), master_name(:)   !< (ncontact) body names
    type(parameter_set_t) :: overrides        !< -D and --cases values of declared parameters
  end type state_t

  !> The routine that reads one statement into the deck (a row's handler).
  abstract interface
    subroutine statement_handler(s, deck, st)
      import :: state_t, deck_t, stmt_t
      type(state_t), intent(inout) :: s
      type(deck_t), intent(inout) :: deck
      type(stmt_t), intent(in) :: st
    end subroutine statement_handler
  end interface

  !> One row of the deck's grammar: a statement (or one form of it), where it
  !> may stand, how often, its words and keys and the routine that reads it.
  type :: statement_t
    character(len=12) :: keyword = ''          !< upper case
    character(len=16) :: form = ''             !< the first word that selects this row (lower case), '' none
    character(len=8) :: block = ''             !< block it stands in: '' the top level, 'BODY', '*' anywhere
    character(len=8) :: opens = ''             !< block it opens, '' none (END closes the open block)
    logical :: once = .false.                  !< at most once: per deck, or per block inside a block
    integer :: words = -1                      !< positional words it takes; -1: its handler checks them
    character(len=:), allocatable :: expected  !< what the "second ..." message expects
    character(len=:), allocatable :: usage     !< its usage line, for messages
    type(key_t), allocatable :: keys(:)        !< its keys; none when they vary (MESH gmsh, PARAMETER)
    procedure(statement_handler), pointer, nopass :: run => null()   !< its handler; none for END
  end type statement_t

contains

  ! ================================================================ errors

  !> Collect one error at `line` (0: file level); the line is echoed under it.
  subroutine report(s, line, text, echo)
    type(state_t), intent(inout) :: s
    integer, intent(in) :: line
    character(len=*), intent(in) :: text
    logical, intent(in), optional :: echo
    type(err_t), allocatable :: grown(:)
    integer :: i

    if (s%gave_up) return
    if (s%nerr + 2 > size(s%errs)) then
      allocate(grown(2 * size(s%errs)))
      do i = 1, s%nerr
        grown(i)%line = s%errs(i)%line
        grown(i)%echo = s%errs(i)%echo
        call move_alloc(s%errs(i)%text, grown(i)%text)
      end do
      call move_alloc(grown, s%errs)
    end if
    s%nerr = s%nerr + 1
    s%errs(s%nerr)%line = line
    s%errs(s%nerr)%text = text
    if (present(echo)) s%errs(s%nerr)%echo = echo
    if (s%nerr == max_errors) then
      s%nerr = s%nerr + 1
      s%errs(s%nerr)%line = line
      s%errs(s%nerr)%text = 'too many errors, stopped reading the deck (fix these first)'
      s%gave_up = .true.
    end if
  end subroutine report

  !> Hand the collected errors to diag, stably sorted by line.
  subroutine hand_over(s, file, diag)
    type(state_t), intent(inout) :: s
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer, allocatable :: order(:)
    integer :: i, j, k, ln

    allocate(order(s%nerr))
    do i = 1, s%nerr
      order(i) = i
    end do
    do i = 2, s%nerr                       ! insertion sort: stable, few items
      k = order(i)
      j = i - 1
      do while (j >= 1)
        if (s%errs(order(j))%line <= s%errs(k)%line) exit
        order(j + 1) = order(j)
        j = j - 1
      end do
      order(j + 1) = k
    end do
    do i = 1, s%nerr
      k = order(i)
      ln = s%errs(k)%line
      if (ln > 0 .and. ln <= s%nline .and. s%errs(k)%echo) then
        call add_error(diag, file, ln, s%errs(k)%text, echo=s%echo(ln)%s)
      else
        call add_error(diag, file, ln, s%errs(k)%text)
      end if
    end do
  end subroutine hand_over

  ! ================================================================ lines and words

  !> Keep a printable, cut copy of the current line for echoing under messages.
  subroutine store_echo(s, raw)
    type(state_t), intent(inout) :: s
    character(len=*), intent(in) :: raw
    type(string_t), allocatable :: grown(:)
    character(len=:), allocatable :: e
    integer :: i

    s%nline = s%nline + 1
    if (s%nline > size(s%echo)) then
      allocate(grown(2 * size(s%echo)))
      do i = 1, size(s%echo)
        call move_alloc(s%echo(i)%s, grown(i)%s)
      end do
      call move_alloc(grown, s%echo)
    end if
    e = clipped(raw, echo_len, ' ...')
    do i = 1, len(e)
      if (e(i:i) == achar(9)) e(i:i) = ' '
    end do
    s%echo(s%nline)%s = e
  end subroutine store_echo

  !> Blank-separated words of text (text_scan's items of a line).
  subroutine split_words(text, tok, ntok)
    character(len=*), intent(in) :: text
    type(string_t), allocatable, intent(out) :: tok(:)
    integer, intent(out) :: ntok
    integer(i8), allocatable :: b(:), e(:)
    integer :: k

    allocate(b(len(text) / 2 + 1), e(len(text) / 2 + 1))     ! a word and a blank at least each
    call line_items(text, 1_i8, len(text, i8), b, e, ntok)
    allocate(tok(ntok))
    do k = 1, ntok
      tok(k)%s = text(b(k):e(k))
    end do
  end subroutine split_words

  !> Join `key = value`, `key= value` and `key =value` into one word key=value,
  !> when that is unambiguous (the neighbours carry no '=' of their own); the
  !> keyword tok(1) is never joined.
  subroutine join_equals(tok, ntok)
    type(string_t), intent(inout) :: tok(:)
    integer, intent(inout) :: ntok
    type(string_t), allocatable :: out(:)
    integer :: i, n
    logical :: prev_plain, next_plain

    allocate(out(ntok))
    n = 1
    out(1)%s = tok(1)%s
    i = 2
    do while (i <= ntok)
      prev_plain = n >= 2
      if (prev_plain) prev_plain = index(out(n)%s, '=') == 0
      next_plain = i < ntok
      if (next_plain) next_plain = index(tok(i + 1)%s, '=') == 0
      if (tok(i)%s == '=' .and. prev_plain .and. next_plain) then          ! key = value
        out(n)%s = out(n)%s // '=' // tok(i + 1)%s
        i = i + 2
      else if (tok(i)%s(1:1) == '=' .and. prev_plain) then                ! key =value, key =
        out(n)%s = out(n)%s // tok(i)%s
        i = i + 1
      else if (ends_with_lone_equals(tok(i)%s) .and. next_plain) then     ! key= value
        n = n + 1
        out(n)%s = tok(i)%s // tok(i + 1)%s
        i = i + 2
      else
        n = n + 1
        out(n)%s = tok(i)%s
        i = i + 1
      end if
    end do
    do i = 1, n
      call move_alloc(out(i)%s, tok(i)%s)
    end do
    ntok = n
  end subroutine join_equals

  !> True for 'key=' (one '=', at the end, after at least one character).
  pure logical function ends_with_lone_equals(w)
    character(len=*), intent(in) :: w
    ends_with_lone_equals = .false.
    if (len(w) < 2) return
    ends_with_lone_equals = index(w, '=') == len(w)
  end function ends_with_lone_equals

  !> Sort the words after the keyword into positional words and key=value pairs.
  subroutine classify_words(tok, ntok, st)
    type(string_t), intent(in) :: tok(:)
    integer, intent(in) :: ntok
    type(stmt_t), intent(inout) :: st
    integer :: i, eq

    allocate(st%word(ntok), st%key(ntok), st%value(ntok))
    do i = 2, ntok
      eq = index(tok(i)%s, '=')
      if (eq == 0) then
        st%nword = st%nword + 1
        st%word(st%nword)%s = tok(i)%s
      else
        st%npair = st%npair + 1
        st%key(st%npair)%s = tok(i)%s(1:eq - 1)
        st%value(st%npair)%s = tok(i)%s(eq + 1:)
      end if
    end do
  end subroutine classify_words

  ! ================================================================ the table

  !> Append a row to the table.
  !>   keyword (in) upper case;  block (in) '' top level, 'BODY', 'RIGID', '*' anywhere
  !>   run (in, optional) the handler (END has none: the dispatcher closes the block)
  !>   form, once, opens, words, expected, usage, keys (in, optional): see statement_t
  subroutine add_row(table, keyword, block, run, form, once, opens, words, expected, usage, keys)
    type(statement_t), allocatable, intent(inout) :: table(:)
    character(len=*), intent(in) :: keyword, block
    procedure(statement_handler), optional :: run
    character(len=*), intent(in), optional :: form, opens, expected, usage
    logical, intent(in), optional :: once
    integer, intent(in), optional :: words
    type(key_t), intent(in), optional :: keys(:)
    type(statement_t) :: row
    type(statement_t), allocatable :: grown(:)

    row%keyword = keyword
    row%block = block
    if (present(run)) row%run => run
    if (present(form)) row%form = form
    if (present(once)) row%once = once
    if (present(opens)) row%opens = opens
    if (present(words)) row%words = words
    row%expected = 'at most one'
    if (present(expected)) row%expected = expected
    row%usage = ''
    if (present(usage)) row%usage = usage
    if (present(keys)) then
      row%keys = keys
    else
      allocate(row%keys(0))
    end if
    allocate(grown(size(table) + 1))
    grown(1:size(table)) = table
    grown(size(grown)) = row
    call move_alloc(grown, table)
  end subroutine add_row

  !> Row of keyword kw standing in block (a row of block '*' stands anywhere);
  !> with block = '?', the first row of kw wherever it stands; 0 when none.
  !> The first row of a keyword is its entry: the one without a form.
  pure integer function find_statement(table, kw, block) result(k)
    type(statement_t), intent(in) :: table(:)
    character(len=*), intent(in) :: kw, block
    do k = 1, size(table)
      if (table(k)%keyword /= kw) cycle
      if (block == '?' .or. table(k)%block == block .or. table(k)%block == '*') return
    end do
    k = 0
  end function find_statement

  ! ================================================================ keys of a row

  !> A number key, optionally bounded: gt/ge (x > gt, x >= ge), lt/le (x < lt, x <= le).
  !>   note (in, optional) said after the range in the message (', a shear stress')
  pure function real_key(name, required, gt, ge, lt, le, note) result(key)
    character(len=*), intent(in) :: name
    logical, intent(in), optional :: required
    real(dp), intent(in), optional :: gt, ge, lt, le
    character(len=*), intent(in), optional :: note
    type(key_t) :: key
    key = key_t(name=name, kind=key_number, form='number')
    if (present(required)) key%required = required
    if (present(gt)) key = bounded(key, .true., gt, .true.)
    if (present(ge)) key = bounded(key, .true., ge, .false.)
    if (present(lt)) key = bounded(key, .false., lt, .true.)
    if (present(le)) key = bounded(key, .false., le, .false.)
    if (present(note)) key%note = note
  end function real_key

  pure function bounded(key, below, x, strict) result(b)
    type(key_t), intent(in) :: key
    logical, intent(in) :: below, strict
    real(dp), intent(in) :: x
    type(key_t) :: b
    b = key
    if (below) then
      b%has_lo = .true.; b%lo = x; b%lo_strict = strict
    else
      b%has_hi = .true.; b%hi = x; b%hi_strict = strict
    end if
  end function bounded

  !> An integer key, at least at_least (default 1).
  pure function integer_key(name, required, at_least) result(key)
    character(len=*), intent(in) :: name
    logical, intent(in), optional :: required
    integer, intent(in), optional :: at_least
    type(key_t) :: key
    key = key_t(name=name, kind=key_integer, form='integer', at_least=1)
    if (present(required)) key%required = required
    if (present(at_least)) key%at_least = at_least
  end function integer_key

  !> A key taking one of the words of choices ('a|b|c', case-insensitive).
  pure function choice_key(name, choices) result(key)
    character(len=*), intent(in) :: name, choices
    type(key_t) :: key
    key = key_t(name=name, kind=key_choice, form=choices)
  end function choice_key

  !> ramp=k0:k1, the statement's load ramp.
  pure function ramp_key() result(key)
    type(key_t) :: key
    key = key_t(name='ramp', kind=key_ramp, form='k0:k1')
  end function ramp_key

  !> curve=NAME, the statement's load curve (not with ramp=).
  pure function curve_key() result(key)
    type(key_t) :: key
    key = key_t(name='curve', kind=key_curve, form='NAME', note='curve')
  end function curve_key

  !> A key naming something (what: 'region'), made of [A-Za-z0-9_.-].
  pure function name_key(name, what) result(key)
    character(len=*), intent(in) :: name, what
    type(key_t) :: key
    key = key_t(name=name, kind=key_name, form='NAME', note=what)
  end function name_key

  !> A key whose value its handler reads (form: how it is written, for messages).
  pure function text_key(name, form, required) result(key)
    character(len=*), intent(in) :: name, form
    logical, intent(in), optional :: required
    type(key_t) :: key
    key = key_t(name=name, kind=key_text, form=form)
    if (present(required)) key%required = required
  end function text_key

  !> Check statement st against the words and keys of its row (st%words,
  !> st%keys) and convert the values: the one place where a word or a key
  !> is refused.  In this order: words beyond st%words; per pair, an empty
  !> key, an unknown key, a repeated key, an empty value; required keys
  !> missing; per key of the row, its value's type and range.
  !>   st   (in)  the statement, with its row's words, keys and usage
  !>   v    (out) the keys as found (key_values_t), in the order of st%keys
  !>   what (in, optional) the statement for messages, instead of st%what
  subroutine read_keys(s, st, v, what)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(key_values_t), intent(out) :: v
    character(len=*), intent(in), optional :: what
    character(len=:), allocatable :: w
    integer :: i, k, n

    w = st%what
    if (present(what)) w = what
    n = size(st%keys)
    allocate(v%seen(n), v%ok(n), v%text(n), v%x(n), v%k(n))
    v%seen = .false.
    v%ok = .false.
    v%x = 0
    v%k = 0
    v%curve = ''
    if (st%words >= 0) call check_extra_words(s, st, st%words, st%usage)
    do i = 1, st%npair
      if (len(st%key(i)%s) == 0) then
        call report(s, st%line, 'missing key before ' // quoted('=' // st%value(i)%s) // ' (expected key=value)')
        cycle
      end if
      k = find_key(st%key(i)%s, st%keys%name)
      if (k == 0) then
        call report(s, st%line, 'unknown key ' // quoted(st%key(i)%s) // ' for ' // w // ' (expected ' // &
                    join_list(st%keys%name, ', ') // ')')
        cycle
      end if
      if (v%seen(k)) then
        call report(s, st%line, 'duplicate key ' // quoted(trim(st%keys(k)%name)) // ' (expected each key at most once)')
        cycle
      end if
      v%seen(k) = .true.
      if (len(st%value(i)%s) == 0) then
        call report(s, st%line, 'missing value for ' // quoted(trim(st%keys(k)%name)) // ' (expected ' // &
                    trim(st%keys(k)%name) // '=' // trim(st%keys(k)%form) // ')')
        cycle
      end if
      v%text(k)%s = st%value(i)%s
    end do
    do k = 1, n
      if (st%keys(k)%required) call require_key(s, st, v%seen(k), trim(st%keys(k)%name), w, st%usage)
    end do
    do k = 1, n
      if (.not. allocated(v%text(k)%s)) cycle
      call convert(st%keys(k), v%text(k), v%ok(k), v%x(k), v%k(k))
    end do
  contains
    !> The value of one key: its type, then its range.
    subroutine convert(key, text, ok, x, j)
      type(key_t), intent(in) :: key
      type(string_t), intent(inout) :: text
      logical, intent(out) :: ok
      real(dp), intent(out) :: x
      integer, intent(out) :: j
      character(len=:), allocatable :: name
      integer :: c, r

      name = trim(key%name)
      ok = .false.
      select case (key%kind)
      case (key_number)
        call parse_real(text%s, x, ok)
        if (.not. ok) then
          x = 0
          call report(s, st%line, 'bad number ' // quoted(text%s) // ' for ' // quoted(name) // &
                      ' (expected a finite number)')
          return
        end if
        if (key%has_lo) ok = x > key%lo .or. (.not. key%lo_strict .and. x == key%lo)
        if (key%has_hi .and. ok) ok = x < key%hi .or. (.not. key%hi_strict .and. x == key%hi)
        if (.not. ok) call report(s, st%line, 'bad value ' // name // '=' // cut(text%s) // ' (expected ' // &
                                  range_text(key) // trim(key%note) // ')')
      case (key_integer)
        call parse_integer(text%s, j, ok)
        if (ok) ok = j >= key%at_least
        if (ok) return
        if (key%at_least == 1) then
          call report(s, st%line, 'bad value ' // name // '=' // cut(text%s) // ' (expected a positive integer)')
        else
          call report(s, st%line, 'bad value ' // name // '=' // cut(text%s) // ' (expected an integer >= ' // &
                      int_to_str(key%at_least) // ')')
        end if
      case (key_choice)
        c = choice_index(text%s, key%form)
        ok = c > 0
        if (ok) then
          text%s = choice_word(key%form, c)
        else
          call report(s, st%line, 'bad value ' // name // '=' // cut(text%s) // ' (expected ' // name // '=' // &
                      trim(key%form) // ')')
        end if
      case (key_ramp)
        call read_ramp(text%s, ok)
      case (key_curve)
        r = find_key('ramp', st%keys%name)
        if (r > 0) then
          if (allocated(v%text(r)%s)) then
            call report(s, st%line, 'ramp= and curve= together (expected one load path per statement: ' // &
                        'ramp=k0:k1 or curve=NAME)')
            return
          end if
        end if
        call check_name(s, st, text%s, trim(key%note), ok)
        if (ok) v%curve = text%s
      case (key_name)
        call check_name(s, st, text%s, trim(key%note), ok)
      case default
        ok = .true.
      end select
    end subroutine convert

    !> ramp=k0:k1 with integers 0 <= k0 < k1; k1 <= STEPS is checked after the
    !> whole deck (check_ramps).
    subroutine read_ramp(text, ok)
      character(len=*), intent(in) :: text
      logical, intent(out) :: ok
      integer :: colon, k0, k1
      logical :: ok0, ok1
      colon = index(text, ':')
      ok0 = .false.
      ok1 = .false.
      if (colon > 1 .and. colon < len(text)) then
        call parse_integer(text(1:colon - 1), k0, ok0)
        call parse_integer(text(colon + 1:), k1, ok1)
      end if
      if (ok0) ok0 = k0 >= 0
      if (ok1) ok1 = k1 >= 0
      ok = .false.
      if (.not. (ok0 .and. ok1)) then
        call report(s, st%line, 'bad ramp ' // quoted(text) // ' (expected ramp=k0:k1 with integers ' // &
                    '0 <= k0 < k1 <= STEPS n)')
      else if (k0 >= k1) then
        call report(s, st%line, 'bad ramp ' // quoted(text) // ' (expected ramp=k0:k1 with k0 < k1: the load ' // &
                    'rises from step k0 to step k1)')
      else
        v%ramp = [k0, k1]
        ok = .true.
      end if
    end subroutine read_ramp
  end subroutine read_keys

  !> The range of a number key as the messages say it: 'E > 0', '-1 < nu < 0.5'.
  function range_text(key) result(t)
    type(key_t), intent(in) :: key
    character(len=:), allocatable :: t
    if (key%has_lo .and. key%has_hi) then
      t = trim(format_number(key%lo)) // ' ' // trim(merge('< ', '<=', key%lo_strict)) // ' ' // trim(key%name) // &
          ' ' // trim(merge('< ', '<=', key%hi_strict)) // ' ' // trim(format_number(key%hi))
    else if (key%has_lo) then
      t = trim(key%name) // ' ' // trim(merge('> ', '>=', key%lo_strict)) // ' ' // trim(format_number(key%lo))
    else
      t = trim(key%name) // ' ' // trim(merge('< ', '<=', key%hi_strict)) // ' ' // trim(format_number(key%hi))
    end if
  end function range_text

  !> Index of word (case-insensitive) among the '|'-separated choices, 0 when none.
  pure integer function choice_index(word, choices) result(c)
    character(len=*), intent(in) :: word, choices
    integer :: n
    c = 0
    n = 1
    do while (len(choice_word(choices, n)) > 0)
      if (lower(word) == choice_word(choices, n)) then
        c = n
        return
      end if
      n = n + 1
    end do
  end function choice_index

  !> The n-th word of 'a|b|c' ('' past the last).
  pure function choice_word(choices, n) result(w)
    character(len=*), intent(in) :: choices
    integer, intent(in) :: n
    character(len=:), allocatable :: w
    integer :: i, p, q
    p = 1
    do i = 1, n - 1
      q = index(choices(p:), '|')
      if (q == 0) then
        w = ''
        return
      end if
      p = p + q
    end do
    q = index(choices(p:), '|')
    if (q == 0) then
      w = trim(choices(p:))
    else
      w = choices(p:p + q - 2)
    end if
  end function choice_word

  ! ================================================================ helpers for handlers

  !> Index of key (case-insensitive) in names, 0 when absent.
  pure integer function find_key(key, names) result(k)
    character(len=*), intent(in) :: key, names(:)
    do k = 1, size(names)
      if (lower(key) == lower(trim(names(k)))) return
    end do
    k = 0
  end function find_key

  !> 'a, b, c' (separator ', ') or 'a|b|c' (separator '|') from a list of padded names.
  pure function join_list(names, separator) result(s)
    character(len=*), intent(in) :: names(:), separator
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(names)
      if (k > 1) s = s // separator
      s = s // trim(names(k))
    end do
  end function join_list

  !> Report a missing required key.
  subroutine require_key(s, st, seen, name, what, usage)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    logical, intent(in) :: seen
    character(len=*), intent(in) :: name, what, usage
    if (.not. seen) call report(s, st%line, 'missing key ' // quoted(name) // ' for ' // what // &
                                ' (expected ' // usage // ')')
  end subroutine require_key

  !> The first word of a statement with forms (PLANE strain, SHAPE line) in
  !> lower case; '' when it has none, reported: 'missing NOUN kind (expected
  !> the statement's usage)'.
  function form_word(s, st, noun) result(kind)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    character(len=*), intent(in) :: noun
    character(len=:), allocatable :: kind
    kind = ''
    if (st%nword > 0) then
      kind = lower(st%word(1)%s)
    else
      call report(s, st%line, 'missing ' // noun // ' kind (expected ' // st%usage // ')')
    end if
  end function form_word

  !> Report words after the first nmax positional words, and (when nmax = 0) any.
  subroutine check_extra_words(s, st, nmax, usage)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    integer, intent(in) :: nmax
    character(len=*), intent(in) :: usage
    if (st%nword > nmax) call report(s, st%line, 'unexpected word ' // quoted(st%word(nmax + 1)%s) // &
                                     ' (expected ' // usage // ')')
  end subroutine check_extra_words

  !> Report the first key=value pair of a statement that takes none.
  subroutine check_no_pairs(s, st)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    if (st%npair > 0) call report(s, st%line, 'unexpected ' // quoted(st%key(1)%s // '=' // st%value(1)%s) // &
                                  ' (expected ' // st%usage // ')')
  end subroutine check_no_pairs

  !> Check a name (body, boundary) and report when bad; ok false when bad.
  subroutine check_name(s, st, name, what, ok)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    character(len=*), intent(in) :: name, what
    logical, intent(out) :: ok
    ok = is_name(name)
    if (.not. ok) call report(s, st%line, 'bad ' // what // ' name ' // quoted(name) // &
                              ' (expected letters, digits, _ . - only)')
  end subroutine check_name

  ! ================================================================ numbers and text

  !> User text for a message: control and non-ASCII bytes as '?', cut after quote_len.
  pure function cut(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    integer :: i
    t = clipped(s, quote_len, '...')
    do i = 1, len(t)
      if (iachar(t(i:i)) < 32 .or. iachar(t(i:i)) > 126) t(i:i) = '?'
    end do
  end function cut

  !> s cut after n characters, marked by suffix when cut.
  pure function clipped(s, n, suffix) result(t)
    character(len=*), intent(in) :: s, suffix
    integer, intent(in) :: n
    character(len=:), allocatable :: t
    if (len(s) > n) then
      t = s(1:n) // suffix
    else
      t = s
    end if
  end function clipped

  !> "text", printable and cut.
  pure function quoted(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    t = '"' // cut(s) // '"'
  end function quoted

  !> Value as written, or a default text when not given.
  pure function shown(val, default) result(t)
    type(string_t), intent(in) :: val
    character(len=*), intent(in) :: default
    character(len=:), allocatable :: t
    if (allocated(val%s)) then
      t = cut(val%s)
    else
      t = default
    end if
  end function shown

end module deck_syntax
