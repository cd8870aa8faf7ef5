!> msh_text: a gmsh MSH ASCII file as text: the file in memory split into
!> lines, the items of the current line, the numbers read from them, and the
!> messages `FILE:LINE: what is wrong (what was expected)` with the line echoed.
!>
!> The whole file is read into memory and split into lines first, so any line
!> length and any byte are safe, and every count read from the file can be
!> checked against the number of lines left before anything is allocated from
!> it (get_count).  Numbers are text_scan's: validated character by character
!> before they are converted, finite and of magnitude below 1e100.  Items are
!> parsed in place in the file's buffer (no substring copies).  The file is
!> split into lines on the threads, and so are the data lines of a block
!> (scan_data_lines): a fast path that accepts exactly what the line-by-line
!> reading accepts and, on any defect, leaves the block to it, so that
!> messages are built on one thread only (no deferred-length string is built
!> inside a parallel region: doc/robustness.md).
!>
!> Every routine that can fail returns an error_t, its last argument: a
!> defect of the file with the line it names (err%line, 0 for the file as a
!> whole) and that line as read (err%echo), or, when an allocation failed, an
!> out-of-memory error (err%no_memory, err%bytes); gmsh_reader turns it into
!> the message.  The reading stops at the first.
!>
!> Programming interface
!>   type(msh_text_t)              the file, its lines, the current line's items
!>   load_text(t, err)             read t%path and split it into lines
!>   advance_line(t, more, err)    the next line and its items (more: there was one)
!>   read_data_line(t, section, nexpected, what, err)
!>                                 the next line of a section, nexpected items
!>   expect_section_end(t, section, err [, skip]), end_of_file(t, section, err)
!>   remaining_lines(t), item(t, k), quoted_item(t, k)
!>   get_integer, get_count, get_real (t, k, what, ..., err)   item k as a number
!>   msh_real(s, v)                scan_real with the file's bounds (status)
!>   read_block_header(t, section, item, lines_per_item, nblock, n, err)
!>                                 the header of a section of entity blocks (4.1)
!>   scan_data_lines(t, nl, lo, nr, iv, rv, done)   a block's data lines, fast path
!>   fail(t, text, err), fail_at(t, line, text, err)   a defect at a line
!>   file_error(t, text, err)      a defect of the file as a whole
!>   out_of_memory(bytes, err)     a failed allocation
!>   allocation_failed(stat, bytes, err)   stat /= 0: err is that failure
module msh_text
  use kinds, only: dp, i8
  use strings, only: int_to_str, i8_to_str, printable
  use errors, only: error_t, set_error, set_out_of_memory, error_input
  use safe_files, only: read_file
  use text_scan, only: scan_integer, scan_real, line_items, upper
  implicit none
  private
  public :: msh_text_t, load_text, advance_line, remaining_lines, item, quoted_item, read_data_line
  public :: expect_section_end, end_blocks, end_of_file, fail, fail_at, file_error, get_integer, get_count
  public :: get_real, msh_real, read_block_line, get_dimension_tag
  public :: read_block_header, scan_data_lines, out_of_memory, allocation_failed, no_integers, no_reals, no_lower_bounds
  public :: fast_parallel_min

  integer, parameter :: max_decimal_exponent = 99  !< numbers below 1e100 in magnitude
  integer, parameter :: max_number_length = 200    !< longest accepted number item
  integer, parameter :: echo_length = 100          !< characters of a line echoed
  integer, parameter :: quote_length = 40          !< characters of an item quoted
  integer, parameter :: max_fast_items = 8         !< items of a line on the fast path
  integer, parameter :: fast_parallel_min = 4096   !< lines parsed on the threads from
  integer(i8), parameter :: fast_parallel_bytes = 262144  !< files split into lines on the threads from
  integer(i8) :: no_integers(0, 0)                 !< iv of scan_data_lines for no integers
  real(dp) :: no_reals(0, 0)                       !< rv of scan_data_lines for no reals
  integer(i8) :: no_lower_bounds(0)                !< lo of scan_data_lines for no integers

  !> The file in memory, split into lines, and the reading position.
  type :: msh_text_t
    character(len=:), allocatable :: path     !< file name for messages
    character(len=:), allocatable :: buf      !< the whole file
    integer(i8), allocatable :: lbeg(:)       !< (nline) first byte of each line
    integer(i8), allocatable :: lend(:)       !< (nline) last byte, lbeg - 1 when empty
    integer :: nline = 0                      !< number of lines
    integer :: ln = 0                         !< current line, 0 before the first
    integer :: ntok = 0                       !< number of items on the current line
    integer(i8), allocatable :: tbeg(:)       !< (capacity) first byte of each item
    integer(i8), allocatable :: tend(:)       !< (capacity) last byte of each item
  end type msh_text_t

contains

  !> Read the file into t%buf and find its lines (LF or CRLF ends).
  subroutine load_text(t, err)
    type(msh_text_t), intent(inout) :: t
    type(error_t), allocatable, intent(out) :: err
    character, parameter :: lf = achar(10), cr = achar(13)
    integer :: status, n, k, c, stat
    integer(i8) :: p, q, nbytes, nlf, chunk_end(2), chunk_lf(2)

    call read_file(t%path, t%buf, status)
    select case (status)
    case (1)
      call file_error('cannot open the mesh file (an existing, readable gmsh .msh file expected)', err)
      return
    case (2)
      call file_error('cannot read the mesh file (a readable regular file expected)', err)
      return
    case (3)
      inquire(file=t%path, size=nbytes)
      call out_of_memory(nbytes, err)
      return
    case (4)
      call file_error('the mesh file is not a regular file (a FIFO, a device or a folder): ' // &
                      'refused (a gmsh .msh file expected)', err)
      return
    end select
    nbytes = len(t%buf, kind=i8)
    if (nbytes == 0) then
      call file_error('the mesh file is empty (a gmsh MSH file starting with $MeshFormat expected)', err)
      return
    end if

    ! Count the lines: one per LF, plus an unterminated last line.  The file is
    ! scanned in two halves side by side, LF counts first, then the lines.
    chunk_end = [nbytes / 2, nbytes]
    chunk_lf = 0
    !$omp parallel do if(nbytes > fast_parallel_bytes) private(p, q)
    do c = 1, 2
      q = 0                                          ! a register, not the shared array
      do p = merge(1_i8, chunk_end(1) + 1, c == 1), chunk_end(c)
        q = q + merge(1_i8, 0_i8, t%buf(p:p) == lf)   ! no branch to mispredict
      end do
      chunk_lf(c) = q
    end do
    !$omp end parallel do
    nlf = sum(chunk_lf)
    if (t%buf(nbytes:nbytes) /= lf) nlf = nlf + 1
    if (nlf > int(huge(1), i8) - 4_i8) then
      call file_error('mesh file has too many lines (fewer than 2**31 expected)', err)
      return
    end if
    n = int(nlf)
    ! Line k runs from lbeg(k) to the byte before its LF (or to the end of the
    ! file), less a CR before the LF.
    allocate(t%lbeg(n), t%lend(n), stat=stat)
    if (stat /= 0) then
      call out_of_memory(16_i8 * n, err)
      return
    end if
    t%lbeg(1) = 1
    !$omp parallel do if(nbytes > fast_parallel_bytes) private(p, k)
    do c = 1, 2
      k = int(merge(0_i8, chunk_lf(1), c == 1))      ! the LFs before the chunk
      do p = merge(1_i8, chunk_end(1) + 1, c == 1), chunk_end(c)
        if (t%buf(p:p) == lf) then
          k = k + 1
          t%lend(k) = p - 1
          if (p > 1) then
            if (t%buf(p - 1:p - 1) == cr) t%lend(k) = p - 2
          end if
          if (k < n) t%lbeg(k + 1) = p + 1
        end if
      end do
    end do
    !$omp end parallel do
    if (t%buf(nbytes:nbytes) /= lf) then
      t%lend(n) = nbytes
      if (t%buf(nbytes:nbytes) == cr) t%lend(n) = nbytes - 1
    end if
    t%nline = n
    t%ln = 0
    allocate(t%tbeg(16), t%tend(16), stat=stat)
    if (stat /= 0) then
      call out_of_memory(256_i8, err)
      return
    end if
  end subroutine load_text

  !> The next line and its items.
  !>   more (out) there was a next line (t%ln is it)
  !>   err  (out) allocated when memory ran out (more is then .false.)
  subroutine advance_line(t, more, err)
    type(msh_text_t), intent(inout) :: t
    logical, intent(out) :: more
    type(error_t), allocatable, intent(out) :: err
    integer :: n, stat
    integer(i8), allocatable :: grown(:)

    more = t%ln < t%nline
    t%ntok = 0
    if (.not. more) return
    t%ln = t%ln + 1
    do
      call line_items(t%buf, t%lbeg(t%ln), t%lend(t%ln), t%tbeg, t%tend, n)
      if (n <= size(t%tbeg)) exit
      allocate(grown(2 * size(t%tbeg)), stat=stat)    ! more items than held: grow, split again
      if (stat == 0) call move_alloc(grown, t%tbeg)
      if (stat == 0) allocate(grown(2 * size(t%tend)), stat=stat)
      if (stat /= 0) then                             ! the reading stops here
        call out_of_memory(32_i8 * size(t%tbeg), err)
        t%ln = t%nline
        more = .false.
        return
      end if
      call move_alloc(grown, t%tend)
    end do
    t%ntok = n
  end subroutine advance_line

  !> Lines after the current one.
  pure integer function remaining_lines(t) result(n)
    type(msh_text_t), intent(in) :: t
    n = t%nline - t%ln
  end function remaining_lines

  !> Item k of the current line.
  function item(t, k) result(s)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    s = t%buf(t%tbeg(k):t%tend(k))
  end function item

  !> Item k of the current line, in double quotes, printable and shortened.
  function quoted_item(t, k) result(s)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    integer(i8) :: last
    last = min(t%tend(k), t%tbeg(k) + quote_length - 1)
    s = '"' // printable(t%buf(t%tbeg(k):last))
    if (last < t%tend(k)) s = s // '...'
    s = s // '"'
  end function quoted_item

  !> Next line of a section, holding data: not a $ line, nexpected items (any
  !> number when nexpected = 0).
  !>   section   (in) section name without $, for the end-of-file message
  !>   what      (in) description of the expected line
  subroutine read_data_line(t, section, nexpected, what, err)
    type(msh_text_t), intent(inout) :: t
    character(len=*), intent(in) :: section, what
    integer, intent(in) :: nexpected
    type(error_t), allocatable, intent(out) :: err

    call next_section_line(t, section, err)
    if (allocated(err)) return
    if (is_section_line(t)) then
      call fail(t, 'unexpected ' // quoted_item(t, 1) // ' (' // what // &
        ' expected, as many lines as the counts announce)', err)
    else if (nexpected > 0 .and. t%ntok /= nexpected) then
      call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // int_to_str(nexpected) // &
        ' expected: ' // what // ')', err)
    end if
  end subroutine read_data_line

  !> The end of a section: the next line must be $End<section>, alone; with
  !> skip (a section this reader does not know) the lines up to the first that
  !> begins with $End<section> are passed over.
  subroutine expect_section_end(t, section, err, skip)
    type(msh_text_t), intent(inout) :: t
    character(len=*), intent(in) :: section
    type(error_t), allocatable, intent(out) :: err
    logical, intent(in), optional :: skip
    logical :: skipping

    skipping = .false.
    if (present(skip)) skipping = skip
    do
      call next_section_line(t, section, err)
      if (allocated(err)) return
      if (is_end_line(t, section, alone=.not. skipping)) return
      if (.not. skipping) exit
    end do
    if (is_section_line(t)) then
      call fail(t, 'unexpected ' // quoted_item(t, 1) // ' ($End' // section // ' expected)', err)
    else
      call fail(t, 'more lines than the counts announce ($End' // section // ' expected)', err)
    end if
  end subroutine expect_section_end

  !> The current line is $End<section> (with alone, and nothing else).
  pure logical function is_end_line(t, section, alone)
    type(msh_text_t), intent(in) :: t
    character(len=*), intent(in) :: section
    logical, intent(in) :: alone
    is_end_line = .false.
    if (t%ntok < 1 .or. (alone .and. t%ntok /= 1)) return
    is_end_line = t%buf(t%tbeg(1):t%tend(1)) == '$End' // section
  end function is_end_line

  !> The line that opens an entity block (MSH 4.1): four items, the entity's
  !> dimension (0 to 3) and tag first.
  !>   section (in) 'Nodes' or 'Elements';  form (in) the line's items, for messages
  !>   dim, tag (out) the first two items
  subroutine read_block_line(t, section, form, dim, tag, err)
    type(msh_text_t), intent(inout) :: t
    character(len=*), intent(in) :: section, form
    integer(i8), intent(out) :: dim, tag
    type(error_t), allocatable, intent(out) :: err
    call read_data_line(t, section, 4, form, err)
    if (.not. allocated(err)) call get_dimension_tag(t, 1, 'entity', dim, tag, err)
  end subroutine read_block_line

  !> Items k and k + 1 of the current line: a dimension (0 to 3) and a tag,
  !> called what // ' dimension' and what // ' tag' in messages.
  subroutine get_dimension_tag(t, k, what, dim, tag, err)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    character(len=*), intent(in) :: what
    integer(i8), intent(out) :: dim, tag
    type(error_t), allocatable, intent(out) :: err
    call get_integer(t, k, what // ' dimension', 0_i8, 3_i8, dim, err)
    if (.not. allocated(err)) call get_integer(t, k + 1, what // ' tag', -huge(1_i8), huge(1_i8), tag, err)
  end subroutine get_dimension_tag

  !> The end of a section of entity blocks: the items of the blocks add up
  !> to the count of the header line, then $End<section>.
  !>   section (in) 'Nodes' or 'Elements';  item_name (in) 'node' or 'element'
  !>   header  (in) the header line;  k, n (in) the items read, announced
  subroutine end_blocks(t, section, item_name, header, k, n, err)
    type(msh_text_t), intent(inout) :: t
    character(len=*), intent(in) :: section, item_name
    integer, intent(in) :: header, k, n
    type(error_t), allocatable, intent(out) :: err
    if (k /= n) then
      call fail_at(t, header, 'the ' // item_name // ' blocks hold ' // int_to_str(k) // ' ' // item_name // &
        's, the header announces ' // int_to_str(n) // ' (equal counts expected)', err)
      return
    end if
    call expect_section_end(t, section, err)
  end subroutine end_blocks

  !> The header line of a section of entity blocks (MSH 4.1 $Nodes, $Elements):
  !> `numEntityBlocks numItems minItemTag maxItemTag`, the counts checked
  !> against the lines left (a block takes a line, an item lines_per_item).
  !>   section (in)  'Nodes' or 'Elements';  item (in) 'node' or 'element'
  !>   lines_per_item (in) 2 for nodes (tag, coordinates), 1 for elements
  !>   nblock, n (out) the counts of blocks and items; t%ln is the header line
  subroutine read_block_header(t, section, item_name, lines_per_item, nblock, n, err)
    type(msh_text_t), intent(inout) :: t
    character(len=*), intent(in) :: section, item_name
    integer, intent(in) :: lines_per_item
    integer, intent(out) :: nblock, n
    type(error_t), allocatable, intent(out) :: err
    character(len=:), allocatable :: noun, factor
    integer(i8) :: tag
    integer :: left

    n = 0
    nblock = 0
    noun = upper(item_name(1:1)) // item_name(2:)
    call read_data_line(t, section, 4, 'numEntityBlocks num' // noun // 's min' // noun // 'Tag max' // noun // &
      'Tag', err)
    if (allocated(err)) return
    left = remaining_lines(t)
    call get_count(t, 1, 'number of ' // item_name // ' blocks', left, nblock, err)
    if (allocated(err)) return
    call get_count(t, 2, 'number of ' // item_name // 's', left, n, err)
    if (allocated(err)) return
    if (int(nblock, i8) + int(lines_per_item, i8) * n > int(left, i8)) then
      factor = ''
      if (lines_per_item > 1) factor = int_to_str(lines_per_item) // ' '
      call fail(t, item_name // ' counts are more than the rest of the file holds (numEntityBlocks + ' // &
        factor // 'num' // noun // 's <= ' // int_to_str(left) // ' expected; truncated file?)', err)
      return
    end if
    call get_integer(t, 3, 'minimum ' // item_name // ' tag', -huge(1_i8), huge(1_i8), tag, err)
    if (allocated(err)) return
    call get_integer(t, 4, 'maximum ' // item_name // ' tag', -huge(1_i8), huge(1_i8), tag, err)
  end subroutine read_block_header

  !> Move to the next line inside $section; err at the end of the file.
  subroutine next_section_line(t, section, err)
    type(msh_text_t), intent(inout) :: t
    character(len=*), intent(in) :: section
    type(error_t), allocatable, intent(out) :: err
    logical :: more
    call advance_line(t, more, err)
    if (.not. more .and. .not. allocated(err)) call end_of_file(t, section, err)
  end subroutine next_section_line

  !> The current line's first item begins with $ (a section line).
  pure logical function is_section_line(t)
    type(msh_text_t), intent(in) :: t
    is_section_line = .false.
    if (t%ntok > 0) is_section_line = t%buf(t%tbeg(1):t%tbeg(1)) == '$'
  end function is_section_line

  !> The file ends inside $section: err at its last line, not echoed.
  subroutine end_of_file(t, section, err)
    type(msh_text_t), intent(in) :: t
    character(len=*), intent(in) :: section
    type(error_t), allocatable, intent(out) :: err
    call set_error(err, 'unexpected end of file inside $' // section // ' ($End' // section // ' expected)', error_input)
    err%line = t%nline
  end subroutine end_of_file

  !> A defect of the file as a whole (no line): err, error_input.
  subroutine file_error(text, err)
    character(len=*), intent(in) :: text
    type(error_t), allocatable, intent(out) :: err
    call set_error(err, text, error_input)
  end subroutine file_error

  !> A defect at the current line: err, the line echoed.
  subroutine fail(t, text, err)
    type(msh_text_t), intent(in) :: t
    character(len=*), intent(in) :: text
    type(error_t), allocatable, intent(out) :: err
    call fail_at(t, t%ln, text, err)
  end subroutine fail

  !> A defect at a given line: err, the line echoed (when the file has it).
  subroutine fail_at(t, line, text, err)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: line
    character(len=*), intent(in) :: text
    type(error_t), allocatable, intent(out) :: err
    integer(i8) :: b, e
    call set_error(err, text, error_input)
    err%line = line
    if (line < 1 .or. line > t%nline) return
    b = t%lbeg(line)
    e = t%lend(line)
    if (e - b + 1 > echo_length) then
      err%echo = t%buf(b:b + echo_length - 1) // ' ...'
    else
      err%echo = t%buf(b:e)
    end if
  end subroutine fail_at

  !> Integer item k in [lo, hi]; else a message naming what.
  subroutine get_integer(t, k, what, lo, hi, v, err)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    character(len=*), intent(in) :: what
    integer(i8), intent(in) :: lo, hi
    integer(i8), intent(out) :: v
    type(error_t), allocatable, intent(out) :: err
    character(len=:), allocatable :: expected
    logical :: ok

    ok = scan_integer(t%buf(t%tbeg(k):t%tend(k)), v)
    if (ok) ok = v >= lo .and. v <= hi
    if (ok) return
    if (lo == 0 .and. hi == huge(1_i8)) then
      expected = 'a non-negative integer'
    else if (lo == 1 .and. hi == huge(1_i8)) then
      expected = 'a positive integer'
    else if (lo == -huge(1_i8) .and. hi == huge(1_i8)) then
      expected = 'an integer'
    else
      expected = 'an integer from ' // i8_to_str(lo) // ' to ' // i8_to_str(hi)
    end if
    call fail(t, 'bad ' // what // ' ' // quoted_item(t, k) // ' (' // expected // ' expected)', err)
  end subroutine get_integer

  !> A count from item k, at least 0 and at most maxcount (what the rest of the
  !> file can hold).
  subroutine get_count(t, k, what, maxcount, n, err)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k, maxcount
    character(len=*), intent(in) :: what
    integer, intent(out) :: n
    type(error_t), allocatable, intent(out) :: err
    integer(i8) :: v
    n = 0
    call get_integer(t, k, what, 0_i8, huge(1_i8), v, err)
    if (allocated(err)) return
    if (v > max(maxcount, 0)) then
      call fail(t, what // ' ' // i8_to_str(v) // ' is more than the rest of the file holds (at most ' // &
        int_to_str(max(maxcount, 0)) // ' expected; truncated file?)', err)
      return
    end if
    n = int(v)
  end subroutine get_count

  !> Real item k: finite, of magnitude below 1e100; else a message naming what.
  subroutine get_real(t, k, what, v, err)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    character(len=*), intent(in) :: what
    real(dp), intent(out) :: v
    type(error_t), allocatable, intent(out) :: err
    select case (msh_real(t%buf(t%tbeg(k):t%tend(k)), v))
    case (0)
      return
    case (2)
      call fail(t, 'non-finite number ' // quoted_item(t, k) // ' (a finite real number expected for ' // &
        what // ')', err)
    case (3)
      call fail(t, 'number out of range ' // quoted_item(t, k) // ' (a real number of magnitude below 1e' // &
        int_to_str(max_decimal_exponent + 1) // ' expected for ' // what // ')', err)
    case default
      call fail(t, 'bad number ' // quoted_item(t, k) // ' (a real number expected for ' // what // ')', err)
    end select
  end subroutine get_real

  !> A real of the file: text_scan's scan_real with magnitudes below 1e100 and
  !> at most max_number_length characters.
  !>   returns 0 ok, 1 not a number, 2 NaN or Inf, 3 magnitude 1e100 or more
  integer function msh_real(s, v) result(status)
    character(len=*), intent(in) :: s
    real(dp), intent(out) :: v
    v = 0.0_dp
    status = 1
    if (len(s) > max_number_length) return
    status = scan_real(s, v, max_decimal_exponent)
  end function msh_real

  !> The fast path of a block of nl data lines after the current one: each
  !> line must hold exactly size(lo) integers, item k at least lo(k), then nr
  !> reals, all as the line-by-line reading accepts them.  The lines are
  !> parsed on the threads (no string is built there: see scene.f90).
  !>   iv (out) (size(lo), nl) the integers of each line
  !>   rv (out) (*, nl) the first size(rv, 1) reals of each line
  !>   done (out) .false., t unchanged, when a line does not qualify: the caller
  !>            then reads the block line by line, which reports the first
  !>            defect as always; else t%ln is the block's last line
  subroutine scan_data_lines(t, nl, lo, nr, iv, rv, done)
    type(msh_text_t), intent(inout) :: t
    integer, intent(in) :: nl, nr
    integer(i8), intent(in) :: lo(:)
    integer(i8), intent(inout) :: iv(:,:)
    real(dp), intent(inout) :: rv(:,:)
    logical, intent(out) :: done
    integer :: ni, n, j, k, l0
    integer(i8) :: b(max_fast_items + 1), e(max_fast_items + 1)
    real(dp) :: r

    ni = size(lo)
    done = ni + nr <= max_fast_items .and. int(t%ln, i8) + nl <= t%nline
    if (.not. done) return
    l0 = t%ln
    !$omp parallel do if(nl > fast_parallel_min) &
    !$omp private(b, e, n, k, r) reduction(.and.: done)
    do j = 1, nl
      if (.not. done) cycle
      call line_items(t%buf, t%lbeg(l0 + j), t%lend(l0 + j), b, e, n)
      done = n == ni + nr
      do k = 1, merge(ni, 0, done)
        done = scan_integer(t%buf(b(k):e(k)), iv(k, j))
        if (done) done = iv(k, j) >= lo(k)
        if (.not. done) exit
      end do
      do k = 1, merge(nr, 0, done)
        done = msh_real(t%buf(b(ni + k):e(ni + k)), r) == 0
        if (.not. done) exit
        if (k <= size(rv, 1)) rv(k, j) = r
      end do
    end do
    !$omp end parallel do
    if (done) t%ln = l0 + nl
  end subroutine scan_data_lines

  !> .true. when stat reports a failed allocation of about bytes, err then
  !> that failure (out_of_memory): `if (allocation_failed(stat, bytes, err))
  !> return` after an allocate(..., stat=stat).
  logical function allocation_failed(stat, bytes, err) result(failed)
    integer, intent(in) :: stat
    integer(i8), intent(in) :: bytes
    type(error_t), allocatable, intent(inout) :: err
    failed = stat /= 0
    if (failed) call out_of_memory(bytes, err)
  end function allocation_failed

  !> An allocation of bytes failed: err (no_memory, error_numerical), which
  !> read_gmsh_file reports as out of memory while reading the file.
  subroutine out_of_memory(bytes, err)
    integer(i8), intent(in) :: bytes
    type(error_t), allocatable, intent(out) :: err
    call set_out_of_memory(err, 'reading a mesh file', bytes)
  end subroutine out_of_memory

end module msh_text
