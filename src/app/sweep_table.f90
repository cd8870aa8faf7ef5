!> sweep_table: DIR/cases.csv, the one table of a parameter sweep, and the
!> test of a case that needs no run.  The run of every case (--cases without
!> --case) writes it after its cases; `--cases FILE --collect` writes it from
!> what has run, and scripts/sweep --collect is that call: one writer, one
!> table, whichever way the cases ran.
!>
!> Why it exists: a sweep is read as a table, a row per case; the summaries
!> it is made of are one file per case.  The table's columns must not depend
!> on which case happened to come first (a case without friction has no
!> friction lines), so their order is the summaries' own: the summary writes
!> its lines in the order the deck defines what they report (its FIX, its
!> CONTACT pairs, its RIGIDs, ...), and the columns are the union of the
!> cases' lines merged so that every case's order holds (a topological merge;
!> two columns no case has together keep the order in which the cases met them).
!>
!> The table (doc/outputs.md): case, status (the exit status; empty when the
!> case has not run or is not complete), the case's parameters as written in
!> the case table, then the summary's results one column each, named after
!> what they hold: `energy`, `reaction_B:S_fx` (the FIX statements on B:S
!> summed), `contact_force_PAIR_fx` (PAIR the pair's number or CONTACT name=),
!> `rigid_R_ux` ...; a case that failed or has not run has empty values.  It
!> is written to a temporary and renamed into place (safe_files): never seen
!> half-written.
!>
!> Programming interface
!>   case_complete(folder, summary)                   the folder holds a summary with its time_total line
!>   case_statuses(outdir, ncase, summary, status)    the statuses scripts/sweep recorded (DIR/logs)
!>   write_sweep_table(outdir, table, summary, status, solved, err)   DIR/cases.csv
module sweep_table
  use kinds, only: dp
  use strings, only: int_to_str, exact_to_str
  use errors, only: error_t, set_error, error_input
  use text_scan, only: string_t, parse_real, parse_integer
  use deck_cases, only: case_table_t
  use safe_files, only: read_file, temporary_t, create_temporary, close_temporary, commit_temporaries, &
                        discard_temporaries
  implicit none
  private
  public :: case_complete, case_statuses, write_sweep_table

  integer, parameter, public :: not_run = -1   !< a status: the case has not run, or left no complete summary

  !> One case's result columns, in its summary's order.
  type :: row_t
    integer :: n = 0                           !< columns used
    integer, allocatable :: column(:)          !< (n) index into the table's column names
    type(string_t), allocatable :: value(:)    !< (n) the values as the summary writes them
  end type row_t

contains

  !> A case that needs no run: its folder holds the summary with its
  !> time_total line, written last (the outputs are renamed into place only
  !> after a successful run).  scripts/sweep asks the same of DIR/case_N.
  !>   folder  (in) DIR/case_N
  !>   summary (in) the summary's file name ('' when unknown: never complete)
  logical function case_complete(folder, summary) result(complete)
    character(len=*), intent(in) :: folder, summary
    character(len=:), allocatable :: buf
    integer :: status
    complete = .false.
    if (len(summary) == 0) return
    call read_file(folder // '/' // summary, buf, status)
    if (status /= 0) return
    complete = index(achar(10) // buf, achar(10) // 'time_total ') > 0
  end function case_complete

  !> The statuses of a sweep's cases as scripts/sweep left them: the number
  !> in DIR/logs/case_N.status when there is one, else 0 for a complete case
  !> (run before the status files, or by `contact2d --cases`), else not_run.
  !>   outdir  (in)  DIR
  !>   ncase   (in)  the number of cases
  !>   summary (in)  the summary's file name
  !>   status  (out) (ncase) each case's exit status, or not_run
  subroutine case_statuses(outdir, ncase, summary, status)
    character(len=*), intent(in) :: outdir, summary
    integer, intent(in) :: ncase
    integer, allocatable, intent(out) :: status(:)
    character(len=:), allocatable :: buf
    integer :: n, io, k
    logical :: ok, complete
    allocate(status(ncase))
    do n = 1, ncase
      complete = case_complete(outdir // '/case_' // int_to_str(n), summary)
      status(n) = merge(0, not_run, complete)
      call read_file(outdir // '/logs/case_' // int_to_str(n) // '.status', buf, io)
      if (io /= 0) cycle
      call parse_integer(trim(adjustl(first_line(buf))), k, ok)
      if (.not. ok) k = 1                           ! a status file not a number: not a success
      if (k /= 0 .or. complete) status(n) = k       ! 0 without a complete summary: not run to the end
    end do
  end subroutine case_statuses

  !> Write DIR/cases.csv: a row per case, the columns the union of the
  !> complete cases' summary columns in their merged order.
  !>   outdir  (in)  DIR (exists)
  !>   table   (in)  the case table
  !>   summary (in)  the summary's file name in DIR/case_N
  !>   status  (in)  (ncase) each case's exit status, or not_run; values are
  !>                 read only for status 0 and a complete summary
  !>   solved  (out) the cases with status 0 and a complete summary
  !>   err     (out) allocated when the file could not be written (nothing written)
  subroutine write_sweep_table(outdir, table, summary, status, solved, err)
    character(len=*), intent(in) :: outdir, summary
    type(case_table_t), intent(in) :: table
    integer, intent(in) :: status(:)
    integer, intent(out) :: solved
    type(error_t), allocatable, intent(out) :: err
    type(row_t), allocatable :: rows(:)
    type(string_t), allocatable :: names(:)
    integer, allocatable :: order(:), at(:)
    type(temporary_t) :: tmp(1)
    character(len=:), allocatable :: line
    integer :: ncol, n, k, u, ios

    allocate(rows(table%ncase), names(16))
    ncol = 0
    solved = 0
    do n = 1, table%ncase
      allocate(rows(n)%column(0), rows(n)%value(0))
      if (status(n) /= 0) cycle
      call read_row(outdir // '/case_' // int_to_str(n) // '/' // summary, rows(n), names, ncol)
      if (rows(n)%n > 0) solved = solved + 1
    end do
    call merged_order(rows, ncol, order)
    allocate(at(ncol))

    call create_temporary(outdir, 'cases.csv', tmp(1), err)
    if (allocated(err)) return
    open(newunit=u, file=tmp(1)%io_path, status='replace', action='write', form='formatted', iostat=ios)
    if (ios == 0) then
      line = 'case,status'
      do k = 1, table%ncol
        line = line // ',' // csv_field(trim(table%name(k)))
      end do
      do k = 1, ncol
        line = line // ',' // csv_field(names(order(k))%s)
      end do
      write(u, '(a)', iostat=ios) line
    end if
    do n = 1, table%ncase
      if (ios /= 0) exit
      line = int_to_str(n) // ','
      if (status(n) /= not_run) line = line // int_to_str(status(n))
      do k = 1, table%ncol
        line = line // ',' // csv_field(table%text(k, n)%s)
      end do
      at = 0                                    ! where each column sits in this case's row
      do k = 1, rows(n)%n
        at(rows(n)%column(k)) = k
      end do
      do k = 1, ncol
        line = line // ','
        if (at(order(k)) > 0) line = line // csv_field(rows(n)%value(at(order(k)))%s)
      end do
      write(u, '(a)', iostat=ios) line
    end do
    if (ios == 0) then
      close(u, iostat=ios)
    else
      close(u)
    end if
    call close_temporary(tmp(1))
    if (ios == 0) call commit_temporaries(outdir, tmp, err)
    if (ios /= 0 .and. .not. allocated(err)) call set_error(err, outdir // ': cannot write cases.csv', error_input)
    if (allocated(err)) call discard_temporaries(tmp)
  end subroutine write_sweep_table

  !> One case's result columns from its summary (none when it cannot be read
  !> or has no time_total line); new column names join names.
  !>   path  (in)    DIR/case_N/SUMMARY
  !>   row   (inout) the case's columns and values
  !>   names (inout) the column names met so far, first met first
  !>   ncol  (inout) how many of names are used
  subroutine read_row(path, row, names, ncol)
    character(len=*), intent(in) :: path
    type(row_t), intent(inout) :: row
    type(string_t), allocatable, intent(inout) :: names(:)
    integer, intent(inout) :: ncol
    character(len=:), allocatable :: buf, line
    type(string_t), allocatable :: words(:)
    type(string_t) :: cols(6), vals(6)
    logical :: summed(6)
    integer :: status, p, q, j, nw, m
    call read_file(path, buf, status)
    if (status /= 0) return
    if (index(achar(10) // buf, achar(10) // 'time_total ') == 0) return
    p = 1
    do while (p <= len(buf))
      q = index(buf(p:), achar(10))
      if (q == 0) q = len(buf) - p + 2
      line = buf(p:p + q - 2)
      p = p + q
      call split_words(line, words, nw)
      if (nw < 2) cycle
      if (words(1)%s == 'parameter') cycle       ! the case table's own columns
      call line_columns(words, nw, cols, vals, summed, m)
      do j = 1, m
        call add_value(row, names, ncol, cols(j)%s, vals(j)%s, summed(j))
      end do
    end do
  end subroutine read_row

  !> The columns of one summary line of words w(1:nw): `KEY LABEL v1 v2 ...`
  !> as KEY_LABEL_c1, KEY_LABEL_c2, ... (the components doc/outputs.md
  !> names), `KEY VALUE` as KEY, the `estimate` lines and max_strain,
  !> max_rotation as their parts; lines of words (warnings, ADAPT steps) give none.
  !>   w      (in)  the line's words
  !>   nw     (in)  how many
  !>   cols   (out) the column names
  !>   vals   (out) their values
  !>   summed (out) the column sums over repeated lines (a boundary held by several FIX)
  !>   m      (out) how many columns the line gives (at most 6)
  subroutine line_columns(w, nw, cols, vals, summed, m)
    type(string_t), intent(in) :: w(:)
    integer, intent(in) :: nw
    type(string_t), intent(inout) :: cols(:), vals(:)
    logical, intent(out) :: summed(:)
    integer, intent(out) :: m
    character(len=8), allocatable :: parts(:)
    integer :: j
    select case (w(1)%s)
    case ('reaction', 'contact_force')
      parts = [character(len=8) :: 'fx', 'fy']
    case ('displacement')
      parts = [character(len=8) :: 'ux', 'uy']
    case ('rigid')
      parts = [character(len=8) :: 'ux', 'uy', 'rz', 'fx', 'fy', 'm']
    case ('contact_zone', 'stick_zone')
      parts = [character(len=8) :: 'x0', 'y0', 'x1', 'y1', 'length']
    case ('contact_zones', 'stick_zones')
      parts = [character(len=8) :: 'count', 'length']
    case ('peak_pressure')
      parts = [character(len=8) :: 'p', 'x', 'y']
    case ('center_of_pressure')
      parts = [character(len=8) :: 'x', 'y']
    case default
      allocate(parts(0))
    end select
    m = 0
    if (size(parts) > 0) then
      if (nw /= 2 + size(parts)) return
      do j = 3, nw
        if (.not. is_number(w(j)%s)) return
      end do
      do j = 1, size(parts)
        call put(w(1)%s // '_' // w(2)%s // '_' // trim(parts(j)), w(2 + j)%s, w(1)%s == 'reaction')
      end do
    else if (w(1)%s == 'estimate') then          ! estimate energy REL | pressure PAIR REL | cost_to_halve S DOFS
      if (nw == 4 .and. w(2)%s == 'pressure') then
        call put('estimate_pressure_' // w(3)%s, w(4)%s, .false.)
      else if (nw == 4 .and. w(2)%s == 'cost_to_halve') then
        call put('estimate_cost_to_halve_seconds', w(3)%s, .false.)
        call put('estimate_cost_to_halve_dofs', w(4)%s, .false.)
      else if (nw == 3) then
        call put('estimate_' // w(2)%s, w(3)%s, .false.)
      end if
    else if ((w(1)%s == 'max_strain' .or. w(1)%s == 'max_rotation') .and. nw == 5) then   ! VALUE BODY X Y
      call put(w(1)%s, w(2)%s, .false.)
      call put(w(1)%s // '_body', w(3)%s, .false.)
      call put(w(1)%s // '_x', w(4)%s, .false.)
      call put(w(1)%s // '_y', w(5)%s, .false.)
    else if (nw == 2) then
      call put(w(1)%s, w(2)%s, .false.)
    end if

  contains

    subroutine put(column, value, sum)
      character(len=*), intent(in) :: column, value
      logical, intent(in) :: sum
      m = m + 1
      cols(m)%s = column
      vals(m)%s = value
      summed(m) = sum
    end subroutine put

  end subroutine line_columns

  !> Column `column` of a case set to value: a summed column adds to what it
  !> holds; a column met again is numbered (COLUMN_2, ...), never overwritten.
  !>   row    (inout) the case's columns
  !>   names  (inout) the column names met so far
  !>   ncol   (inout) how many of names are used
  !>   column (in)    its name
  !>   value  (in)    its value as written
  !>   summed (in)    the column is a sum
  subroutine add_value(row, names, ncol, column, value, summed)
    type(row_t), intent(inout) :: row
    type(string_t), allocatable, intent(inout) :: names(:)
    integer, intent(inout) :: ncol
    character(len=*), intent(in) :: column, value
    logical, intent(in) :: summed
    type(string_t), allocatable :: grown_value(:)
    integer, allocatable :: grown_column(:)
    character(len=:), allocatable :: name
    integer :: c, j, k
    real(dp) :: a, b
    logical :: ok_a, ok_b
    name = column
    c = name_index(names, ncol, name)
    j = 0
    if (c > 0) j = findloc(row%column(1:row%n), c, 1)
    if (j > 0 .and. summed) then
      call parse_real(row%value(j)%s, a, ok_a)
      call parse_real(value, b, ok_b)
      if (ok_a .and. ok_b) row%value(j)%s = exact_to_str(a + b)
      return
    end if
    k = 1
    do while (j > 0)                            ! a line repeated: COLUMN_2, COLUMN_3, ...
      k = k + 1
      name = column // '_' // int_to_str(k)
      c = name_index(names, ncol, name)
      j = 0
      if (c > 0) j = findloc(row%column(1:row%n), c, 1)
    end do
    if (c == 0) then
      if (ncol == size(names)) call grow_names(names)
      ncol = ncol + 1
      names(ncol)%s = name
      c = ncol
    end if
    if (row%n == size(row%column)) then
      allocate(grown_column(max(16, 2 * row%n)), grown_value(max(16, 2 * row%n)))
      grown_column(1:row%n) = row%column(1:row%n)
      do j = 1, row%n
        call move_alloc(row%value(j)%s, grown_value(j)%s)
      end do
      call move_alloc(grown_column, row%column)
      call move_alloc(grown_value, row%value)
    end if
    row%n = row%n + 1
    row%column(row%n) = c
    row%value(row%n)%s = value
  end subroutine add_value

  !> The columns' order: every case's own order kept (a column before
  !> another in some case's summary comes before it in the table), the rest
  !> in the order the cases met them; should the cases disagree (they cannot:
  !> one deck, one writer), the first met comes first.
  !>   rows  (in)  (ncase) each case's columns in its summary's order
  !>   ncol  (in)  the columns of all cases
  !>   order (out) (ncol) the columns in table order
  subroutine merged_order(rows, ncol, order)
    type(row_t), intent(in) :: rows(:)
    integer, intent(in) :: ncol
    integer, allocatable, intent(out) :: order(:)
    logical, allocatable :: before(:,:), placed(:)
    integer, allocatable :: waiting(:)
    integer :: n, k, next
    allocate(before(ncol, ncol), placed(ncol), waiting(ncol), order(ncol))
    before = .false.                            ! before(a, b): a comes right before b in some case
    do n = 1, size(rows)
      do k = 2, rows(n)%n
        before(rows(n)%column(k - 1), rows(n)%column(k)) = .true.
      end do
    end do
    placed = .false.
    do k = 1, ncol
      waiting(k) = count(before(:, k))
    end do
    do k = 1, ncol
      next = findloc(waiting == 0 .and. .not. placed, .true., 1)
      if (next == 0) next = findloc(placed, .false., 1)
      order(k) = next
      placed(next) = .true.
      where (before(next, :)) waiting = waiting - 1
    end do
  end subroutine merged_order

  !> The index of name in names(1:ncol), 0 when absent.
  !>   names (in) the names
  !>   ncol  (in) how many are used
  !>   name  (in) the name sought
  integer function name_index(names, ncol, name) result(c)
    type(string_t), intent(in) :: names(:)
    integer, intent(in) :: ncol
    character(len=*), intent(in) :: name
    do c = 1, ncol
      if (names(c)%s == name) return
    end do
    c = 0
  end function name_index

  !> names with twice the room, its strings moved (grow_temporaries says why).
  !>   names (inout) the list
  subroutine grow_names(names)
    type(string_t), allocatable, intent(inout) :: names(:)
    type(string_t), allocatable :: grown(:)
    integer :: j
    allocate(grown(2 * size(names)))
    do j = 1, size(names)
      call move_alloc(names(j)%s, grown(j)%s)
    end do
    call move_alloc(grown, names)
  end subroutine grow_names

  !> The blank-separated words of line.
  !>   line  (in)  the line
  !>   words (out) its words
  !>   nw    (out) how many
  subroutine split_words(line, words, nw)
    character(len=*), intent(in) :: line
    type(string_t), allocatable, intent(out) :: words(:)
    integer, intent(out) :: nw
    integer :: i, start
    logical :: blank
    allocate(words(len(line) / 2 + 1))
    nw = 0
    start = 0
    do i = 1, len(line) + 1
      blank = .true.
      if (i <= len(line)) blank = line(i:i) == ' ' .or. line(i:i) == achar(9) .or. line(i:i) == achar(13)
      if (.not. blank .and. start == 0) start = i
      if (blank .and. start > 0) then
        nw = nw + 1
        words(nw)%s = line(start:i - 1)
        start = 0
      end if
    end do
  end subroutine split_words

  !> s reads as a number.
  !>   s (in) a word
  logical function is_number(s)
    character(len=*), intent(in) :: s
    real(dp) :: x
    call parse_real(s, x, is_number)
  end function is_number

  !> A CSV field: in double quotes, its own doubled, when it holds a comma, a
  !> quote or a line end.
  !>   s (in) the value
  function csv_field(s) result(f)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: f
    integer :: i
    if (scan(s, ',"' // achar(10) // achar(13)) == 0) then
      f = s
      return
    end if
    f = '"'
    do i = 1, len(s)
      f = f // s(i:i)
      if (s(i:i) == '"') f = f // '"'
    end do
    f = f // '"'
  end function csv_field

  !> The text of buf up to its first line end.
  !>   buf (in) the text
  function first_line(buf) result(line)
    character(len=*), intent(in) :: buf
    character(len=:), allocatable :: line
    integer :: q
    q = scan(buf, achar(10) // achar(13))
    line = buf
    if (q > 0) line = buf(1:q - 1)
  end function first_line

end module sweep_table
