!> deck_reader: read a contact2d input deck (doc/deck.md, DECK.md) into deck_t and
!> check everything that can be checked without reading the meshes.
!>
!> Syntax.  One statement per line: a keyword, then positional words and key=value
!> pairs separated by blanks or tabs.  Keywords, keys and the fixed words (rect, gmsh,
!> isotropic, strain, tri3, ...) are case-insensitive; names of bodies, boundaries and
!> files are case-sensitive.  '!' and '#' start a comment anywhere on a line, TITLE
!> included.  Blank lines are ignored, CRLF line endings and a UTF-8 byte-order mark
!> are accepted.  Blanks around '=' are allowed (`E = 2e5`) when unambiguous.
!> Numbers are Fortran or C reals (200000, 2e5, 2.0d5, -1.5E-3, .5, 5.) with
!> |x| < 1e308; NaN, Inf, hexadecimal and trailing characters are rejected.
!> Names (bodies, boundaries, output files) are made of [A-Za-z0-9_.-].
!>
!> Statements (keys in brackets are optional, with their default):
!>   PARAMETER name=expression ...     then ${expression} anywhere in a later line,
!>                                      replaced before the line is split (deck_expressions)
!>   TITLE free text                                     default ''
!>   PLANE strain | PLANE stress [thickness=1] | PLANE axisymmetric   default strain
!>   BODY name ... END                                    at least one
!>     MESH rect [x0=0] [y0=0] [x1=1] [y1=1] nx= ny= [elem=tri3|quad4|tri6|quad8|quad9]
!>          [diag=right|left|alt]      (diag only with triangles; boundaries left, right, bottom, top)
!>     MESH gmsh file=NAME.msh | file=NAME.geo [name=number ...]
!>     MATERIAL isotropic E= nu=
!>     MATERIAL orthotropic E1= E2= nu12= G12= [angle=0] [E3=E2] [nu13=nu12] [nu23=nu12]
!>     DENSITY rho=
!>     FIX boundary [ux=] [uy=] [ramp=0:STEPS]     (neither ux nor uy: ux = uy = 0)
!>     FIX boundary [un=] [ut=] [ramp=0:STEPS]     (local axes of the boundary; not with ux, uy)
!>     TRACTION boundary [tx=0] [ty=0] [ramp=0:STEPS]   (at least one of tx, ty)
!>     TRACTION boundary [tn=0] [tt=0] [ramp=0:STEPS]   (the edges' axes; not with tx, ty)
!>     PRESSURE boundary p= [ramp=0:STEPS]
!>     BODYFORCE [fx=0] [fy=0] [ramp=0:STEPS]      (at least one of fx, fy)
!>     THERMAL alpha= dT= [region=NAME] [curve=NAME]
!>     OFFSET [dx=0] [dy=0]              (at least one)
!>     FORCE point [fx=0] [fy=0] [ramp=0:STEPS]    (at least one of fx, fy; point: a point set)
!>     SPRING boundary kn= [kt=0]        (an elastic foundation, kn, kt >= 0)
!>     SPRING point [kx=0] [ky=0]        (a spring to the ground, at least one of kx, ky >= 0)
!>   GRAVITY [gx=0] [gy=0] [ramp=0:STEPS]          (at least one of gx, gy)
!>   CONTACT slave=body:boundary master=body:boundary|RIGIDNAME [gap=geometry|zero]
!>           [mu=number | tresca=number]           (default frictionless)
!>           [interference=allow|reject] [sliding=small|finite]
!>   RIGID name ... END                  SHAPE, REF, FIX, FORCE (deck_rigid_statements)
!>   SOLVER [lcp=auto|lemke|pgs|pdas] [tol=1e-10] [maxit=0] [omega=1] [ordering=auto|metis|amd]
!>          [condense=auto|solve|inverse] [cut=auto|off] [updates=30]
!>   STEPS n                             default 1; 1 <= n <= 100000
!>   CURVE name t0:v0 t1:v1 ...          load factor v against the step t (t increasing)
!>   ESTIMATE [on|off|bound]             default on
!>   ADAPT target= [quantity=energy|pressure] [max_steps=10] [max_dofs=2000000]
!>   OUTPUT [vtk=NAME.vtk] [contact=NAME_contact.csv] [summary=NAME.summary] [fields=LIST] [steps=last|all]
!>          [plot=none|png] [x=COLUMN]
!>                                      (NAME: deck file name without folder and
!>                                      extension; '.vtk' is appended to vtk= if missing)
!> TITLE, PLANE, GRAVITY, SOLVER, STEPS, OUTPUT: at most once each, outside BODY blocks.
!> MESH, MATERIAL, DENSITY, BODYFORCE, OFFSET: at most once per body; FIX, TRACTION,
!> PRESSURE, THERMAL, FORCE, SPRING: any number.  Statements may come in any order (CONTACT before the
!> BODY it names, STEPS after the ramps it bounds).
!>
!> Grammar.  Each statement is a row of a table (deck_statements), with the
!> block it stands in (the top level, BODY, RIGID, or anywhere), the block it
!> opens, whether it may come once, its words and its keys with their types
!> and ranges (number, integer, k0:k1, NAME, a|b|c; E > 0, -1 < nu < 0.5).
!> The dispatcher here checks from the row where a statement stands (a
!> top-level statement inside a block is read, with a "missing END?" hint; a
!> block statement outside its block is refused) and its repetition ("second
!> X"), picks the row of its form (MESH rect, MATERIAL isotropic), and runs its
!> handler, which has read_keys (deck_syntax) check and convert the words and
!> keys of its row, then checks the rules between keys.  A new statement is a
!> row and a handler; a new block is a row that opens it and rows whose block
!> it is; END closes whatever block is open.
!>
!> The reader's parts: deck_types (the deck as data), deck_syntax (lines,
!> words, keys, messages), deck_statements (the table and the top-level
!> statements), deck_body_statements and deck_rigid_statements (the blocks'
!> statements), deck_checks (what needs the whole deck, the defaults).
!>
!> Checks beyond the syntax: value ranges (E > 0, -1 < nu < 0.5, orthotropic
!> compliance positive definite, in plane strain with the out-of-plane terms too,
!> x1 > x0, nx, ny positive integers, 0 < omega < 2, ...); one MESH and one MATERIAL per
!> body; block structure; gmsh files exist; boundary names of rect meshes; CONTACT
!> bodies exist and the two sides differ; every body is held by a FIX or a SPRING,
!> directly or through CONTACT with a held body; every ramp ends at step STEPS at the latest.  Errors are
!> collected (at most max_errors), sorted by line and handed to diag as
!> `FILE:LINE: what is wrong (what was expected)` with the line echoed.
!>
!> Programming interface
!>   the types of deck_types (deck_t and its parts), load_traction, load_pressure,
!>   load_point, curve_factor, re-exported: the reader's callers use deck_reader alone
!>   read_deck(path, deck, diag [, overrides])   parse and check the deck file `path`
!>   path_too_long(path, reserve)   '' or why a path cannot name a file (deck_checks)
module deck_reader
  use strings, only: int_to_str
  use errors, only: diag_t
  use safe_files, only: open_input, kind_name, folder_of, c2d_regular, c2d_missing, c2d_unreadable
  use deck_types, only: fix_t, load_t, mesh_spec_t, material_t, body_deck_t, contact_deck_t, solver_deck_t, &
                        output_deck_t, deck_t, curve_t, curve_factor, rigid_deck_t, rigid_load_t, &
                        load_traction, load_pressure, load_point, spring_deck_t
  use deck_expressions, only: parameter_set_t, substitute
  use deck_syntax, only: state_t, stmt_t, statement_t, string_t, report, hand_over, store_echo, split_words, &
                         join_equals, classify_words, find_statement, quoted, max_line_len
  use deck_statements, only: define_statements
  use deck_checks, only: finish_checks, cut_statement_lists, fill_defaults, path_too_long
  use text_scan, only: is_blank, lower, upper
  use, intrinsic :: iso_fortran_env, only: iostat_eor, iostat_end, int64
  implicit none
  private
  public :: fix_t, load_t, mesh_spec_t, material_t, body_deck_t, contact_deck_t
  public :: solver_deck_t, output_deck_t, deck_t, curve_t, read_deck, curve_factor, rigid_deck_t, rigid_load_t
  public :: load_traction, load_pressure, load_point, spring_deck_t, path_too_long

contains

  ! ================================================================ entry point

  !> Read and check the deck file `path`.
  !>   path  (in)    deck file as given on the command line
  !>   deck  (out)   the parsed deck; every allocatable component is allocated on
  !>                 return, also when errors were found (then the values are partial)
  !>   diag  (inout) receives every error, sorted by line; file-level errors
  !>                 (cannot open, no BODY) have line 0
  !>   overrides (in, optional) values replacing the defaults of PARAMETERs of
  !>                 these names, with their origins ('-D', 'case N'); names the
  !>                 deck does not declare are the caller's to report
  subroutine read_deck(path, deck, diag, overrides)
    character(len=*), intent(in) :: path
    type(deck_t), intent(out) :: deck
    type(diag_t), intent(inout) :: diag
    type(parameter_set_t), intent(in), optional :: overrides
    type(state_t) :: s
    type(statement_t), allocatable :: table(:)
    character(len=:), allocatable :: line
    integer :: u, ios, kind
    integer(int64) :: fsize
    logical :: readable

    deck%file = path
    call split_path(path, deck%dir, deck%name)
    allocate(deck%bodies(0), deck%contacts(0), deck%curves(0), deck%rigids(0))
    allocate(s%errs(16), s%echo(64), s%slave_name(4), s%master_name(4))
    if (present(overrides)) s%overrides = overrides
    call define_statements(table)
    allocate(s%first_line(size(table)), s%block_first(size(table)), source=0)

    readable = .false.
    ! a FIFO or a device would block or never end: refused before it is read
    call open_input(path, u, .false., kind)
    if (kind == c2d_missing) then
      call report(s, 0, 'cannot open the deck: no such file (expected an existing deck file)')
    else
      if (kind /= c2d_regular .and. kind /= c2d_unreadable) then
        call report(s, 0, 'the deck is ' // kind_name(kind) // ', not a regular file: refused (a deck file expected)')
      else if (kind /= c2d_regular) then
        call report(s, 0, 'cannot open the deck (expected a readable file)')
      else
        readable = .true.
        do
          call read_line(u, line, ios)
          if (ios == iostat_end) exit
          if (ios == 0 .and. len(line) > max_line_len) then
            call store_echo(s, line)
            call report(s, s%nline, 'line longer than ' // int_to_str(max_line_len) // &
                        ' characters (expected a text deck; is this a binary file?)')
            readable = .false.
            exit
          end if
          if (ios /= 0) then
            call report(s, 0, 'cannot read the deck after line ' // int_to_str(s%nline) // &
                        ' (expected a readable text file)')
            readable = .false.
            exit
          end if
          call process_line(s, deck, line, table)
          if (s%gave_up) exit
        end do
        close(u)
        if (s%nline == 0 .and. s%nerr == 0) then
          inquire(file=path, size=fsize)
          if (fsize /= 0) then
            call report(s, 0, 'cannot read the deck (expected a text file, not a folder)')
            readable = .false.
          end if
        end if
      end if
    end if
    call cut_statement_lists(s, deck)
    if (readable .and. .not. s%gave_up) call finish_checks(s, deck)
    call fill_defaults(deck)
    call hand_over(s, deck%file, diag)
  end subroutine read_deck

  !> Read one line (non-advancing, in chunks); strip a final CR.  Reading stops
  !> after max_line_len + 1 characters, so that a file without line ends
  !> (/dev/zero, a large binary file) cannot exhaust the memory.
  !>   u     (in)  connected formatted unit
  !>   line  (out) the line without its end-of-line characters; longer than
  !>               max_line_len when the line was cut there
  !>   ios   (out) 0 a line was read, iostat_end no more lines, other: read error
  subroutine read_line(u, line, ios)
    integer, intent(in) :: u
    character(len=:), allocatable, intent(out) :: line
    integer, intent(out) :: ios
    character(len=4096) :: chunk
    character(len=:), allocatable :: buf, grown
    integer :: n, used

    allocate(character(len=4096) :: buf)
    used = 0
    do
      read(u, '(a)', advance='no', size=n, iostat=ios) chunk
      if (ios /= 0 .and. ios /= iostat_eor .and. ios /= iostat_end) return
      if (used + n > len(buf)) then
        allocate(character(len=2 * (used + n)) :: grown)
        grown(1:used) = buf(1:used)
        call move_alloc(grown, buf)
      end if
      buf(used + 1:used + n) = chunk(1:n)
      used = used + n
      if (ios == 0 .and. used > max_line_len) exit
      if (ios == 0) cycle
      if (ios == iostat_end .and. used == 0) return
      exit
    end do
    ios = 0
    if (used > 0) then
      if (buf(used:used) == achar(13)) used = used - 1
    end if
    line = buf(1:used)
  end subroutine read_line

  !> Folder and bare name of a path: 'a/b/c.deck' -> 'a/b', 'c'; 'c.deck' -> '.', 'c'.
  subroutine split_path(path, dir, name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: dir, name
    integer :: slash, dot
    dir = folder_of(path)
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    dot = index(name, '.', back=.true.)
    if (dot > 1) name = name(1:dot - 1)
    if (len(name) == 0) name = 'contact2d'
  end subroutine split_path

  ! ================================================================ lines and statements

  !> Split one line into a statement and dispatch it.
  subroutine process_line(s, deck, raw, table)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(in) :: raw
    type(statement_t), intent(in) :: table(:)
    character(len=:), allocatable :: text
    type(string_t), allocatable :: tok(:)
    type(stmt_t) :: st
    character(len=:), allocatable :: kw
    integer :: i, ntok, kwend

    text = raw
    if (s%nline == 0 .and. len(text) >= 3) then    ! UTF-8 byte-order mark
      if (text(1:3) == char(239) // char(187) // char(191)) text = text(4:)
    end if
    call store_echo(s, text)
    if (index(text, achar(0)) > 0) then            ! binary file: one message, stop
      call report(s, s%nline, 'NUL byte in the deck (expected a text file; is this a binary file?)')
      s%gave_up = .true.
      return
    end if
    i = scan(text, '!#')
    if (i > 0) text = text(1:i - 1)
    if (index(text, '${') > 0) then                ! ${expression}: the line as the parameters make it
      if (.not. substituted(s, deck, text)) return
    end if
    do i = 1, len(text)
      if (is_blank(text(i:i))) text(i:i) = ' '
    end do
    call split_words(text, tok, ntok)
    if (ntok == 0) return

    st%line = s%nline
    st%keyword = tok(1)%s
    kwend = index(text, tok(1)%s) + len(tok(1)%s)
    st%rest = trim(adjustl(text(kwend:)))
    call join_equals(tok, ntok)
    call classify_words(tok, ntok, st)
    kw = upper(st%keyword)
    call dispatch(s, deck, st, kw, table)
  end subroutine process_line

  !> Replace each ${expression} of text by its value; .false. (the error
  !> reported) when an expression is bad.
  logical function substituted(s, deck, text)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    character(len=:), allocatable, intent(inout) :: text
    character(len=:), allocatable :: out, message
    call substitute(text, deck%params, out, message)
    substituted = .not. allocated(message)
    if (substituted) then
      call move_alloc(out, text)
    else
      call report(s, s%nline, message)
    end if
  end function substituted

  !> Check where statement st stands and how often, then run its row's handler.
  !>   kw    (in) its keyword in upper case
  !>   table (in) the grammar
  subroutine dispatch(s, deck, st, kw, table)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(inout) :: st
    character(len=*), intent(in) :: kw
    type(statement_t), intent(in) :: table(:)
    character(len=:), allocatable :: list
    integer :: k, first

    k = find_statement(table, kw, s%block)
    if (k == 0) then
      k = find_statement(table, kw, '?')
      if (k == 0) then
        list = ''
        do k = 1, size(table)
          if (find_statement(table, table(k)%keyword, '?') /= k) cycle
          if (k > 1) list = list // ', '
          list = list // trim(table(k)%keyword)
        end do
        call report(s, st%line, 'unknown keyword ' // quoted(st%keyword) // ' (expected one of ' // list // ')')
        if (s%block == 'BODY' .and. s%cur > 0) then
          if (.not. allocated(s%unknown_body)) allocate(s%unknown_body(0))
          s%unknown_body = [s%unknown_body, s%cur]
        end if
        return
      end if
      if (table(k)%block /= '') then            ! a block statement outside its block
        call report(s, st%line, 'statement ' // kw // ' outside a ' // trim(table(k)%block) // ' block (expected ' // &
                    'inside ' // trim(table(k)%block) // ' ... END)')
        return
      end if
      if (.not. s%end_hinted) then              ! a top-level statement inside a block: read as such
        if (table(k)%opens /= '') then
          call report(s, st%line, kw // ' inside ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                      ' opened at line ' // int_to_str(s%block_line) // ' (missing END?)')
        else
          call report(s, st%line, 'statement ' // kw // ' inside ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                      ' opened at line ' // int_to_str(s%block_line) // ' (expected after the END of the ' // &
                      lower(trim(s%block)) // ' block; missing END?)')
          s%end_hinted = .true.
        end if
      end if
    end if
    associate (row => table(k))
      if (row%once) then
        if (row%block == '') then
          first = s%first_line(k)
          s%first_line(k) = merge(first, st%line, first > 0)
        else
          first = s%block_first(k)
          s%block_first(k) = merge(first, st%line, first > 0)
        end if
        if (first > 0 .and. row%block == '') then
          call report(s, st%line, 'second ' // kw // ' (first at line ' // int_to_str(first) // '; expected ' // &
                      row%expected // ')')
          return
        else if (first > 0) then
          call report(s, st%line, 'second ' // kw // ' in ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                      ' (first at line ' // int_to_str(first) // '; expected ' // row%expected // ')')
          return
        end if
      end if
      if (row%opens /= '') then                 ! its handler names the block (block_name, block_line)
        s%block = row%opens
        s%block_first = 0
        s%end_hinted = .false.
      end if
      if (.not. associated(row%run)) then       ! END
        call close_block(s, st)
        return
      end if
    end associate
    k = find_form(table, k, st)
    st%what = trim(table(k)%keyword)
    if (table(k)%form /= '') st%what = st%what // ' ' // trim(table(k)%form)
    st%usage = table(k)%usage
    st%words = table(k)%words
    st%keys = table(k)%keys
    call table(k)%run(s, deck, st)
  end subroutine dispatch

  !> The row of statement st's form: the row of keyword table(k)%keyword in
  !> the same block whose form is st's first word; k itself (the form-less
  !> row, which reports a missing or unknown form) when none is.
  pure integer function find_form(table, k, st) result(j)
    type(statement_t), intent(in) :: table(:)
    integer, intent(in) :: k
    type(stmt_t), intent(in) :: st
    if (st%nword > 0) then
      do j = k + 1, size(table)
        if (table(j)%keyword /= table(k)%keyword .or. table(j)%block /= table(k)%block) exit
        if (table(j)%form == lower(st%word(1)%s)) return
      end do
    end if
    j = k
  end function find_form

  !> END: closes the open block (BODY ... END).
  subroutine close_block(s, st)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    if (s%block == '') then
      call report(s, st%line, 'END without an open BODY (expected END only to close a BODY block)')
      return
    end if
    if (st%nword > 0) then
      call report(s, st%line, 'unexpected word ' // quoted(st%word(1)%s) // ' after END (expected END alone)')
    else if (st%npair > 0) then
      call report(s, st%line, 'unexpected ' // quoted(st%key(1)%s // '=' // st%value(1)%s) // &
                  ' after END (expected END alone)')
    end if
    s%cur = 0
    s%block = ''
    s%end_hinted = .false.
  end subroutine close_block

end module deck_reader
