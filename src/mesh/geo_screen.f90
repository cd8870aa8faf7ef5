!> geo_screen: refuse a .geo that reaches outside meshing, before gmsh runs it.
!>
!> A .geo is a program in gmsh's language, and gmsh runs what it says: shell
!> commands (SystemCall), files written (Printf > FILE, Save, Print,
!> CreateDir), files read (Include, Merge of any path), other programs
!> (OnelabRun, Solver.Executable).  The screen reads the .geo the way gmsh's
!> lexer does (comments and strings skipped, words compared with their case)
!> and reports each such statement as FILE:LINE with the line echoed:
!>   - SystemCall, NonBlockingSystemCall, OnelabRun, Save, Print, CreateDir,
!>     SendToServer, Exit: refused wherever they are;
!>   - Printf(...) > FILE and >> FILE: refused (Printf to the log is fine);
!>   - Include, Merge, MergeWithBoundingBox, ShapeFromFile: only of a string
!>     literal naming an existing file inside the allowed folder (the deck's),
!>     resolved as gmsh does (relative to the including file) with every link
!>     followed; an included .geo or .opt is screened in turn;
!>   - options that name programs or files (Solver.*, *FileName*,
!>     *Executable*, *Command*, *Editor*, *WebBrowser*, *Socket*): refused.
!> This is a list of what is known to reach outside, not a proof that nothing
!> else does; the sandbox of gmsh_runner confines what it misses.
!>
!> Programming interface
!>   screen_geo(path, allowed, diag)   path: the .geo; allowed: the folder
!>        (absolute, links resolved) its Include/Merge may read; errors to diag
module geo_screen
  use kinds, only: i8
  use strings, only: int_to_str, ends_with
  use errors, only: diag_t, add_error
  use safe_files, only: read_file, real_path, folder_of
  implicit none
  private
  public :: screen_geo

  integer, parameter :: max_depth = 8            !< Include nesting screened
  integer, parameter :: max_echo = 200           !< characters of a line echoed
  character(len=*), parameter :: lift = ' (a .geo that only builds geometry and meshes it expected; ' // &
                                        '--trust-geo lets gmsh run it as it is)'

  !> where the scan is in one file
  type :: cursor_t
    character(len=:), allocatable :: path        !< the file, for messages
    character(len=:), allocatable :: buf         !< its bytes
    integer(i8) :: p = 1                         !< next byte
    integer :: line = 1                          !< line of byte p
  end type cursor_t

contains

  !> Screen the .geo file at path (see the module header).
  !>   path    (in)    the .geo file, as the deck names it (messages use it)
  !>   allowed (in)    absolute folder, links resolved: what Include may read
  !>   diag    (inout) one error per statement refused
  subroutine screen_geo(path, allowed, diag)
    character(len=*), intent(in) :: path, allowed
    type(diag_t), intent(inout) :: diag
    call screen_file(path, allowed, 0, diag)
  end subroutine screen_geo

  recursive subroutine screen_file(path, allowed, depth, diag)
    character(len=*), intent(in) :: path, allowed
    integer, intent(in) :: depth
    type(diag_t), intent(inout) :: diag
    type(cursor_t) :: c
    character(len=:), allocatable :: word
    integer :: status, line
    integer(i8) :: n

    c%path = path
    call read_file(path, c%buf, status)
    if (status /= 0) then
      call add_error(diag, path, 0, 'cannot read the .geo file (a readable regular file expected)')
      return
    end if
    n = len(c%buf, kind=i8)
    do while (c%p <= n)
      select case (c%buf(c%p:c%p))
      case (achar(10))
        c%line = c%line + 1
        c%p = c%p + 1
      case ('/')
        call skip_comment(c)
      case ('"')
        call skip_string(c)
      case ('A':'Z', 'a':'z', '_')
        line = c%line
        call take_word(c, word)
        call screen_word(c, word, line, allowed, depth, diag)
      case ('0':'9')
        call take_word(c, word)                  ! a number: 1e5 holds no word
      case default
        c%p = c%p + 1
      end select
    end do
  end subroutine screen_file

  !> Judge one word of the .geo (line: where it starts).
  recursive subroutine screen_word(c, word, line, allowed, depth, diag)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: word, allowed
    integer, intent(in) :: line, depth
    type(diag_t), intent(inout) :: diag
    character(len=:), allocatable :: what
    what = ''
    select case (word)
    case ('SystemCall', 'NonBlockingSystemCall')
      what = word // ' runs a shell command'
    case ('OnelabRun')
      what = 'OnelabRun runs a program'
    case ('SendToServer')
      what = 'SendToServer talks to a program'
    case ('Save')
      what = 'Save writes a file'
    case ('Print')
      what = 'Print writes an image file'
    case ('CreateDir')
      what = 'CreateDir makes a folder'
    case ('Exit')
      what = 'Exit ends gmsh before the mesh is written'
    case ('Printf')
      if (redirected(c)) what = 'Printf > FILE writes a file'
    case ('Include', 'Merge', 'MergeWithBoundingBox', 'ShapeFromFile')
      call screen_read(c, word, line, allowed, depth, diag)
    case default
      if (index(word, '.') > 0) then
        if (word(1:min(7, len(word))) == 'Solver.' .or. index(word, 'FileName') > 0 .or. &
            index(word, 'Executable') > 0 .or. index(word, 'Command') > 0 .or. index(word, 'Editor') > 0 .or. &
            index(word, 'WebBrowser') > 0 .or. index(word, 'Socket') > 0) &
          what = 'the option ' // word // ' names a program or a file gmsh may run or write'
      end if
    end select
    if (len(what) > 0) call refuse(c, line, what, diag)
  end subroutine screen_word

  !> Include "FILE" and its kind: FILE must be a literal inside allowed.
  recursive subroutine screen_read(c, word, line, allowed, depth, diag)
    type(cursor_t), intent(inout) :: c
    character(len=*), intent(in) :: word, allowed
    integer, intent(in) :: line, depth
    type(diag_t), intent(inout) :: diag
    character(len=:), allocatable :: name, path, real
    logical :: found
    integer(i8) :: q
    call skip_blanks(c)
    if (c%p <= len(c%buf, kind=i8)) then
      if (c%buf(c%p:c%p) == '(') c%p = c%p + 1        ! ShapeFromFile("...")
    end if
    call skip_blanks(c)
    name = ''
    found = .false.
    if (c%p <= len(c%buf, kind=i8)) then
      if (c%buf(c%p:c%p) == '"') then
        q = c%p
        call skip_string(c)
        name = c%buf(q + 1:c%p - 2)
        call skip_blanks(c)
        if (c%p <= len(c%buf, kind=i8)) found = index(';)', c%buf(c%p:c%p)) > 0 .and. index(name, '\') == 0
      end if
    end if
    if (.not. found) then
      call refuse(c, line, word // ' of a computed name (a file name in double quotes expected)', diag)
      return
    end if
    if (name(1:min(1, len(name))) == '/') then
      path = name
    else
      path = folder_of(c%path) // '/' // name
    end if
    call real_path(path, real, found)
    if (.not. found) then
      call refuse(c, line, word // ' of "' // name // '", which does not exist', diag)
    else if (real(1:min(len(real), len(allowed) + 1)) /= allowed // '/' .and. allowed /= '/') then
      call refuse(c, line, word // ' of "' // name // '", outside the deck''s folder ' // allowed, diag)
    else if (word == 'Include' .or. ends_with(real, '.geo') .or. ends_with(real, '.opt')) then
      if (depth >= max_depth) then
        call refuse(c, line, word // ' nested deeper than ' // int_to_str(max_depth) // ' files', diag)
      else
        call screen_file(path, allowed, depth + 1, diag)      ! gmsh reads it as a script
      end if
    end if
  end subroutine screen_read

  !> After Printf: ( ... ) followed by > or >>.
  logical function redirected(c)
    type(cursor_t), intent(inout) :: c
    integer :: level
    integer(i8) :: n
    redirected = .false.
    n = len(c%buf, kind=i8)
    call skip_blanks(c)
    if (c%p > n) return
    if (c%buf(c%p:c%p) /= '(') return
    level = 0
    do while (c%p <= n)
      select case (c%buf(c%p:c%p))
      case ('"')
        call skip_string(c)
        cycle
      case ('(')
        level = level + 1
      case (')')
        level = level - 1
      case (achar(10))
        c%line = c%line + 1
      end select
      c%p = c%p + 1
      if (level == 0) exit
    end do
    call skip_blanks(c)
    if (c%p <= n) redirected = c%buf(c%p:c%p) == '>'
  end function redirected

  !> Report the statement at line, the line echoed.
  subroutine refuse(c, line, what, diag)
    type(cursor_t), intent(in) :: c
    integer, intent(in) :: line
    character(len=*), intent(in) :: what
    type(diag_t), intent(inout) :: diag
    call add_error(diag, c%path, line, what // ': refused' // lift, echo=line_text(c%buf, line))
  end subroutine refuse

  !> Line k of buf (at most max_echo characters).
  function line_text(buf, k) result(s)
    character(len=*), intent(in) :: buf
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    integer(i8) :: p, q
    integer :: i
    p = 1
    do i = 2, k
      q = index(buf(p:), achar(10), kind=i8)
      if (q == 0) exit
      p = p + q
    end do
    q = index(buf(p:), achar(10), kind=i8)
    if (q == 0) q = len(buf, kind=i8) - p + 2
    s = buf(p:p + min(q - 2, int(max_echo, i8) - 1))
  end function line_text

  !> At '/': a // or /* */ comment is skipped, else the '/' alone.
  subroutine skip_comment(c)
    type(cursor_t), intent(inout) :: c
    integer(i8) :: n, q
    n = len(c%buf, kind=i8)
    if (c%p + 1 > n) then
      c%p = c%p + 1
      return
    end if
    select case (c%buf(c%p + 1:c%p + 1))
    case ('/')
      q = index(c%buf(c%p:), achar(10), kind=i8)
      c%p = merge(n + 1, c%p + q - 1, q == 0)
    case ('*')
      q = index(c%buf(c%p + 2:), '*/', kind=i8)
      q = merge(n + 1, c%p + 2 + q + 1, q == 0)
      c%line = c%line + count_lines(c%buf(c%p:min(q - 1, n)))
      c%p = q
    case default
      c%p = c%p + 1
    end select
  end subroutine skip_comment

  !> At '"': past the closing quote (backslash escapes honoured).
  subroutine skip_string(c)
    type(cursor_t), intent(inout) :: c
    integer(i8) :: n
    n = len(c%buf, kind=i8)
    c%p = c%p + 1
    do while (c%p <= n)
      select case (c%buf(c%p:c%p))
      case ('\')
        c%p = c%p + 1
        if (c%p <= n) then
          if (c%buf(c%p:c%p) == achar(10)) c%line = c%line + 1
        end if
      case ('"')
        c%p = c%p + 1
        return
      case (achar(10))
        c%line = c%line + 1
      end select
      c%p = c%p + 1
    end do
  end subroutine skip_string

  subroutine skip_blanks(c)
    type(cursor_t), intent(inout) :: c
    do while (c%p <= len(c%buf, kind=i8))
      select case (c%buf(c%p:c%p))
      case (' ', achar(9), achar(13))
      case (achar(10))
        c%line = c%line + 1
      case default
        return
      end select
      c%p = c%p + 1
    end do
  end subroutine skip_blanks

  !> A word: letters, digits, '_' and '.' (General.Option).
  subroutine take_word(c, word)
    type(cursor_t), intent(inout) :: c
    character(len=:), allocatable, intent(out) :: word
    integer(i8) :: q
    q = c%p
    do while (c%p <= len(c%buf, kind=i8))
      select case (c%buf(c%p:c%p))
      case ('A':'Z', 'a':'z', '0':'9', '_', '.')
        c%p = c%p + 1
      case default
        exit
      end select
    end do
    word = c%buf(q:c%p - 1)
  end subroutine take_word

  pure integer function count_lines(s)
    character(len=*), intent(in) :: s
    integer :: i
    count_lines = 0
    do i = 1, len(s)
      if (s(i:i) == achar(10)) count_lines = count_lines + 1
    end do
  end function count_lines

end module geo_screen
