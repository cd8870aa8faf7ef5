!> deck_cases: the case table of a parameter sweep (--cases FILE.csv): read,
!> checked, and a row as parameter overrides.  It runs nothing: which case a
!> run solves, and the run of every case in turn, are case_selection's (src/app).
!>
!> The table is comma-separated: a header row of parameter names, then one row
!> per case, each field a number (Fortran or C notation).  Blank lines and
!> lines starting with '#' are skipped; blanks around fields, a UTF-8
!> byte-order mark and CRLF line ends are accepted; the header's names may be
!> in double quotes.  Cases are numbered 1, 2, ... in row order.  Every row is
!> checked whichever case runs, so that all the cases of a sweep fail alike on
!> a bad table: errors are `FILE.csv:LINE: what is wrong (what was expected)`.
!>
!> Programming interface
!>   type(case_table_t)                      names, values (and their text), lines of the table
!>   read_case_table(path, table, diag)      read and check FILE.csv
!>   case_parameters(table, n, set)          row n as overrides with origin 'case n'
module deck_cases
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: diag_t, add_error
  use deck_expressions, only: parameter_set_t, add_parameter, is_parameter_name
  use text_scan, only: parse_real, string_t
  use safe_files, only: read_file
  implicit none
  private
  public :: case_table_t, read_case_table, case_parameters

  !> The case table.
  type :: case_table_t
    character(len=:), allocatable :: file       !< path as given (in messages)
    integer :: ncol = 0, ncase = 0
    character(len=64), allocatable :: name(:)   !< (ncol) header names
    real(dp), allocatable :: value(:,:)         !< (ncol, ncase) the rows
    type(string_t), allocatable :: text(:,:)    !< (ncol, ncase) each value as written, blanks and quotes
                                                !< around it removed (the sweep table echoes it)
    integer :: header_line = 0                  !< line of the header
    integer, allocatable :: line(:)             !< (ncase) line of each row
  end type case_table_t

  integer, parameter :: max_table_bytes = 64 * 1048576   ! a larger file is not a case table
  integer, parameter :: field_len = 400                  ! a longer field is neither a name nor a number

contains

  !> Read and check the case table `path`.
  !>   path  (in)    FILE.csv as given on the command line
  !>   table (out)   its header and rows (complete only when no error was added)
  !>   diag  (inout) receives `FILE.csv:LINE: ...` for each bad row (at most 20)
  subroutine read_case_table(path, table, diag)
    character(len=*), intent(in) :: path
    type(case_table_t), intent(out) :: table
    type(diag_t), intent(inout) :: diag
    character(len=:), allocatable :: buf, line
    character(len=field_len), allocatable :: fields(:)
    integer :: status, p, q, lineno, nf, k, nerr, cap, j
    real(dp) :: x
    logical :: ok
    real(dp), allocatable :: grown(:,:)
    integer, allocatable :: grown_line(:)
    type(string_t), allocatable :: grown_text(:,:)

    table%file = path
    nerr = 0
    allocate(table%name(0), table%value(0, 0), table%line(0), table%text(0, 0))
    call read_file(path, buf, status)
    if (status /= 0) then
      call add_error(diag, path, 0, 'cannot read the case table (expected a readable CSV file)')
      return
    end if
    if (len(buf) > max_table_bytes .or. index(buf, achar(0)) > 0) then
      call add_error(diag, path, 0, 'not a case table (expected a text CSV file)')
      return
    end if
    if (len(buf) >= 3) then                              ! UTF-8 byte-order mark
      if (buf(1:3) == char(239) // char(187) // char(191)) buf = buf(4:)
    end if
    p = 1
    lineno = 0
    do while (p <= len(buf) .and. nerr < 20)
      q = index(buf(p:), achar(10))
      if (q == 0) then
        q = len(buf) + 1
      else
        q = p + q - 1
      end if
      line = buf(p:q - 1)
      p = q + 1
      lineno = lineno + 1
      if (len(line) > 0) then
        if (line(len(line):len(line)) == achar(13)) line = line(1:len(line) - 1)
      end if
      if (len_trim(line) == 0) cycle
      if (adjustl(line(1:1)) == '#') cycle
      call split_fields(line, fields, nf)
      if (table%header_line == 0) then                   ! the header
        table%header_line = lineno
        table%ncol = nf
        deallocate(table%name, table%value, table%text)
        allocate(table%name(nf), table%value(nf, 0), table%text(nf, 0))
        do k = 1, nf
          if (.not. is_parameter_name(trim(fields(k)))) then
            call bad(lineno, 'bad parameter name "' // printable_field(fields(k)) // '" in the header (expected ' // &
                     'a name declared by PARAMETER in the deck)')
          else if (any(table%name(1:k - 1) == fields(k))) then
            call bad(lineno, 'parameter "' // printable_field(fields(k)) // '" twice in the header ' // &
                     '(expected each name once)')
          end if
          table%name(k) = fields(k)(1:len(table%name))
        end do
        cycle
      end if
      if (nf /= table%ncol) then
        call bad(lineno, int_to_str(nf) // ' fields (expected ' // int_to_str(table%ncol) // ', one per name of ' // &
                 'the header)')
        cycle
      end if
      table%ncase = table%ncase + 1
      if (table%ncase > size(table%line)) then
        cap = max(16, 2 * size(table%line))
        allocate(grown(table%ncol, cap), grown_line(cap), grown_text(table%ncol, cap))
        grown(:, 1:table%ncase - 1) = table%value(:, 1:table%ncase - 1)
        grown_line(1:table%ncase - 1) = table%line(1:table%ncase - 1)
        do j = 1, table%ncase - 1                      ! (moved, not copied: grow_temporaries says why)
          do k = 1, table%ncol
            call move_alloc(table%text(k, j)%s, grown_text(k, j)%s)
          end do
        end do
        call move_alloc(grown, table%value)
        call move_alloc(grown_line, table%line)
        call move_alloc(grown_text, table%text)
      end if
      table%line(table%ncase) = lineno
      do k = 1, nf
        call parse_real(trim(fields(k)), x, ok)
        if (.not. ok) then
          call bad(lineno, 'bad number "' // printable_field(fields(k)) // '" for ' // trim(table%name(k)) // &
                   ' (expected a number such as 2, 2.5, 2e5, 2.0d5)')
          x = 0
        end if
        table%value(k, table%ncase) = x
        table%text(k, table%ncase)%s = trim(fields(k))
      end do
    end do
    if (table%header_line == 0) then
      call add_error(diag, path, 0, 'empty case table (expected a header row of parameter names, then one row ' // &
                     'per case)')
    else if (table%ncase == 0 .and. nerr == 0) then
      call bad(table%header_line, 'no case after the header (expected one row per case)')
    end if

  contains

    subroutine bad(at, text)
      integer, intent(in) :: at
      character(len=*), intent(in) :: text
      nerr = nerr + 1
      call add_error(diag, path, at, text)
    end subroutine bad

  end subroutine read_case_table

  !> Row n of the table as parameter values of origin 'case n'.
  subroutine case_parameters(table, n, set)
    type(case_table_t), intent(in) :: table
    integer, intent(in) :: n
    type(parameter_set_t), intent(inout) :: set
    integer :: k
    do k = 1, table%ncol
      call add_parameter(set, trim(table%name(k)), table%value(k, n), 'case ' // int_to_str(n))
    end do
  end subroutine case_parameters

  !> The comma-separated fields of line, blanks and double quotes around each removed.
  subroutine split_fields(line, fields, nf)
    character(len=*), intent(in) :: line
    character(len=field_len), allocatable, intent(out) :: fields(:)
    integer, intent(out) :: nf
    integer :: i, start, k
    character(len=:), allocatable :: f

    nf = 1
    do i = 1, len(line)
      if (line(i:i) == ',') nf = nf + 1
    end do
    allocate(fields(nf))
    start = 1
    k = 0
    do i = 1, len(line) + 1
      if (i <= len(line)) then
        if (line(i:i) /= ',') cycle
      end if
      k = k + 1
      f = trim(adjustl(untab(line(start:i - 1))))
      if (len(f) >= 2) then
        if (f(1:1) == '"' .and. f(len(f):len(f)) == '"') f = f(2:len(f) - 1)
      end if
      if (len(f) > field_len) f = '?'                  ! not a name, not a number
      fields(k) = f
      start = i + 1
    end do
  end subroutine split_fields

  pure function untab(s) result(t)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    integer :: i
    t = s
    do i = 1, len(t)
      if (t(i:i) == achar(9)) t(i:i) = ' '
    end do
  end function untab

  !> A field for a message: trimmed, printable, cut after 40 characters.
  pure function printable_field(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    integer :: i
    t = trim(s)
    if (len(t) > 40) t = t(1:40) // '...'
    do i = 1, len(t)
      if (iachar(t(i:i)) < 32 .or. iachar(t(i:i)) > 126) t(i:i) = '?'
    end do
  end function printable_field

end module deck_cases
