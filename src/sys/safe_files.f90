!> safe_files: the run's files as a careful batch tool makes them (the C side
!> is src/sys/file_guard.c).
!>
!> Inputs are refused unless they are regular files (a FIFO, a device or a
!> folder would block or never end), checked before and after they are
!> opened.  Outputs are written to temporaries of their own, made in the
!> output folder with O_CREAT|O_EXCL under unique names that no OUTPUT name
!> can take (they hold a '~'), so that no symbolic link planted there is
!> followed and no output overwrites another's temporary; they are renamed
!> into place at the commit, under an exclusive lock of the output folder.
!> Whatever the run leaves uncommitted (temporaries, the private folder of
!> gmsh's files) is removed at exit and on SIGINT, SIGTERM and SIGHUP.
!>
!> A file opened here is handed to Fortran as /proc/self/fd/N: the path names
!> the very file the descriptor holds, not whatever the original path names
!> by the time Fortran opens it.
!>
!> Programming interface
!>   file_kind(path)                       c2d_regular, c2d_missing, c2d_fifo, ... (stat)
!>   kind_name(kind)                       'a FIFO', 'a device', 'a folder', ... for messages
!>   open_input(path, unit, stream, kind)  open a regular file for reading (stream:
!>                                         unformatted stream, else formatted sequential);
!>                                         kind /= c2d_regular: not opened
!>   read_file(path, buf, status)          the bytes of a regular file
!>   make_folders(path, err)               mkdir -p, without a shell
!>   private_folder(path, err)             the run's private folder (made once)
!>   real_path(path, real, found)          realpath(3); found: the path exists
!>   file_stamp(path, stamp, found)        'SIZE MTIME_NS' of a file (stat): changes when it is replaced
!>   folder_of(path)                       the folder part of path ('.' when none)
!>   type(temporary_t)                     an output temporary and its final name
!>   create_temporary(dir, name, t, err)   a temporary for the output dir/name
!>   grow_temporaries(t, n)                n blank temporaries added at the end of t
!>   close_temporary(t)                    done writing it (its descriptor closed)
!>   commit_temporaries(dir, t, err)       rename each into place, all or none, under
!>                                         the folder's lock
!> A call that fails returns an error_t (error_input: the folder does not take
!> the files); the callers say which folder the user should look at.
!>   discard_temporaries(t)                remove them
module safe_files
  use, intrinsic :: iso_c_binding, only: c_int, c_long_long, c_null_char
  use kinds, only: i8
  use errors, only: error_t, set_error, error_input
  use system_binding, only: c2d_find_program, c2d_file_kind, c2d_open_input, c2d_close, c2d_make_folders, c2d_private_folder, &
                            c2d_create_temporary, c2d_forget_temporary, c2d_lock_folder, c2d_unlock_folder, &
                            c2d_real_path, c2d_file_stamp, c_unlink, c_rename, c2d_regular, c2d_missing, c2d_fifo, c2d_device, &
                            c2d_folder, c2d_socket, c2d_unreadable
  implicit none
  private
  public :: find_program
  public :: file_kind, kind_name, open_input, read_file, make_folders, private_folder, real_path, folder_of, file_stamp
  public :: temporary_t, create_temporary, grow_temporaries, close_temporary, commit_temporaries, discard_temporaries
  public :: c2d_regular, c2d_missing, c2d_fifo, c2d_device, c2d_folder, c2d_socket, c2d_unreadable

  integer, parameter :: path_max = 4096          !< longest path C hands back (PATH_MAX)

  type :: temporary_t
    character(len=:), allocatable :: path        !< the temporary, dir/.NAME~XXXXXX ('' when none)
    character(len=:), allocatable :: io_path     !< /proc/self/fd/N: what the writers open
    character(len=:), allocatable :: final       !< dir/NAME, its name once committed
    integer :: fd = -1                           !< its descriptor until close_temporary
  end type temporary_t

contains

  integer function file_kind(path)
    character(len=*), intent(in) :: path
    file_kind = c2d_file_kind(path // c_null_char)
  end function file_kind

  !> What a file of kind k is, for a message ('a FIFO', 'missing', ...).
  function kind_name(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    select case (k)
    case (c2d_regular);  s = 'a regular file'
    case (c2d_missing);  s = 'missing'
    case (c2d_fifo);     s = 'a FIFO (named pipe)'
    case (c2d_device);   s = 'a device'
    case (c2d_folder);   s = 'a folder'
    case (c2d_socket);   s = 'a socket'
    case default;        s = 'not readable'
    end select
  end function kind_name

  !> Open a regular file for reading.
  !>   path   (in)  the file
  !>   unit   (out) the Fortran unit, when kind = c2d_regular
  !>   stream (in)  .true.: unformatted stream; .false.: formatted sequential
  !>   kind   (out) c2d_regular (opened) or why not (c2d_missing, c2d_fifo, ...)
  subroutine open_input(path, unit, stream, kind)
    character(len=*), intent(in) :: path
    integer, intent(out) :: unit
    logical, intent(in) :: stream
    integer, intent(out) :: kind
    integer(c_int) :: fd
    integer :: ios
    unit = -1
    kind = c2d_open_input(path // c_null_char, fd)
    if (kind /= c2d_regular) return
    if (stream) then
      open(newunit=unit, file=fd_path(fd), access='stream', form='unformatted', action='read', status='old', &
           iostat=ios)
    else
      open(newunit=unit, file=fd_path(fd), access='sequential', form='formatted', action='read', status='old', &
           iostat=ios)
    end if
    if (c2d_close(fd) /= 0) continue          ! Fortran holds a descriptor of its own
    if (ios /= 0) kind = c2d_unreadable
  end subroutine open_input

  !> The bytes of a regular file.
  !>   status (out) 0 read, 1 cannot open, 2 cannot read, 3 too large for memory,
  !>                4 not a regular file (a FIFO, a device, a folder)
  subroutine read_file(path, buf, status)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: buf
    integer, intent(out) :: status
    integer(i8), parameter :: slice = 1048576
    integer :: u, ios, st, kind
    integer(i8) :: nbytes, first
    call open_input(path, u, .true., kind)
    if (kind /= c2d_regular) then
      status = merge(4, 1, kind == c2d_fifo .or. kind == c2d_device .or. kind == c2d_folder .or. kind == c2d_socket)
      return
    end if
    inquire(unit=u, size=nbytes)
    if (nbytes < 0) then
      close(u)
      status = 2
      return
    end if
    allocate(character(len=nbytes) :: buf, stat=st)
    if (st /= 0) then
      close(u)
      status = 3
      return
    end if
    ! in slices of 1 MiB: flang's runtime stages a read through a buffer of
    ! the read's size, which it allocates without a way to report failure
    status = 0
    do first = 1_i8, nbytes, slice
      read(u, iostat=ios) buf(first:min(first + slice - 1, nbytes))
      if (ios /= 0) then
        status = 2
        exit
      end if
    end do
    close(u)
  end subroutine read_file

  !> Make folder path and its missing parents; err when it is not a folder now.
  subroutine make_folders(path, err)
    character(len=*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: err
    if (c2d_make_folders(path // c_null_char) /= 0) call set_error(err, path // ': cannot create the folder', error_input)
  end subroutine make_folders

  !> The run's private folder for temporary files (gmsh's meshes and logs):
  !> made on the first call under $TMPDIR (else /tmp), removed at exit.
  !>   path (out) the folder ('' when err)
  !>   err  (out) allocated when it cannot be made
  subroutine private_folder(path, err)
    character(len=:), allocatable, intent(out) :: path
    type(error_t), allocatable, intent(out) :: err
    character(len=path_max) :: buf
    integer(c_int) :: n
    n = c2d_private_folder(buf, int(len(buf), c_int))
    path = ''
    if (n > 0) then
      path = buf(1:n)
    else
      call set_error(err, 'cannot make a private folder in $TMPDIR (or /tmp)', error_input)
    end if
  end subroutine private_folder

  !> The absolute path of path with every link resolved; found = it exists
  !> (a value the callers act on in their own ways, not an error).
  subroutine real_path(path, real, found)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: real
    logical, intent(out) :: found
    character(len=path_max) :: buf
    found = c2d_real_path(path // c_null_char, buf, int(len(buf), c_int)) == 0
    real = ''
    if (found) real = buf(1:index(buf, c_null_char) - 1)
  end subroutine real_path

  !> A stamp of the file at path: its size and modification time in
  !> nanoseconds, 'SIZE MTIME_NS' (stat, links followed), which changes when
  !> the file is replaced; found = path exists.
  subroutine file_stamp(path, stamp, found)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: stamp
    logical, intent(out) :: found
    integer(c_long_long) :: size, mtime
    character(len=48) :: buf
    found = c2d_file_stamp(path // c_null_char, size, mtime) == 0
    stamp = ''
    if (.not. found) return
    write(buf, '(i0,1x,i0)') size, mtime
    stamp = trim(buf)
  end subroutine file_stamp

  !> The folder part of path: 'a/b' for 'a/b/c', '/' for '/c', '.' for 'c'.
  pure function folder_of(path) result(dir)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: dir
    integer :: k
    k = index(path, '/', back=.true.)
    if (k == 0) then
      dir = '.'
    else if (k == 1) then
      dir = '/'
    else
      dir = path(1:k - 1)
    end if
  end function folder_of

  !> t grown by n blank temporaries at its end.  An array constructor
  !> (t = [t, ...]) would do it in one line, but gfortran leaks the strings of
  !> the constructor's own temporary when the type has allocatable components.
  subroutine grow_temporaries(t, n)
    type(temporary_t), allocatable, intent(inout) :: t(:)
    integer, intent(in) :: n
    type(temporary_t), allocatable :: grown(:)
    integer :: i
    allocate(grown(size(t) + n))
    do i = 1, size(t)
      grown(i) = t(i)
    end do
    call move_alloc(grown, t)
  end subroutine grow_temporaries

  !> A new temporary in folder dir for the output named name.
  !>   dir  (in)  the output folder (exists)
  !>   name (in)  the output's file name in dir
  !>   t    (out) the temporary: t%io_path to write it, t%final = dir/name
  !>   err  (out) allocated when it could not be made (t%path = '')
  subroutine create_temporary(dir, name, t, err)
    character(len=*), intent(in) :: dir, name
    type(temporary_t), intent(out) :: t
    type(error_t), allocatable, intent(out) :: err
    character(len=path_max) :: buf
    integer(c_int) :: fd
    t%final = dir // '/' // name
    t%path = ''
    t%io_path = ''
    if (c2d_create_temporary(dir // c_null_char, name // c_null_char, buf, int(len(buf), c_int), fd) /= 0) then
      call set_error(err, dir // ': cannot create a file for ' // name, error_input)
      return
    end if
    t%path = buf(1:index(buf, c_null_char) - 1)
    t%fd = fd
    t%io_path = fd_path(fd)
  end subroutine create_temporary

  !> The writers are done with t: its descriptor is closed.
  subroutine close_temporary(t)
    type(temporary_t), intent(inout) :: t
    if (t%fd < 0) return
    if (c2d_close(int(t%fd, c_int)) /= 0) continue
    t%fd = -1
  end subroutine close_temporary

  !> Rename every temporary to its final name, all or none: under an
  !> exclusive lock of folder dir (another run committing into it waits), an
  !> existing final is first moved aside to a temporary of its own; when any
  !> rename fails, what was renamed is undone and the earlier outputs are
  !> restored, err allocated.  Temporaries not made are skipped.
  subroutine commit_temporaries(dir, t, err)
    character(len=*), intent(in) :: dir
    type(temporary_t), intent(inout) :: t(:)
    type(error_t), allocatable, intent(out) :: err
    type(temporary_t) :: aside(size(t))
    logical :: saved(size(t)), moved(size(t))
    integer(c_int) :: lock
    integer :: i, j
    logical :: ok
    type(error_t), allocatable :: aside_err
    character(len=*), parameter :: cannot = ': cannot put the output files in place'
    saved = .false.
    moved = .false.
    do i = 1, size(t)                       ! a folder in the way: fail before touching anything
      if (.not. made(t(i))) cycle
      if (file_kind(t(i)%final) == c2d_folder) then
        call set_error(err, dir // cannot, error_input)
        return
      end if
    end do
    lock = c2d_lock_folder(dir // c_null_char)
    if (lock < 0) then
      call set_error(err, dir // cannot, error_input)
      return
    end if
    ok = .true.
    do i = 1, size(t)
      if (.not. made(t(i))) cycle
      if (file_kind(t(i)%final) /= c2d_missing) then   ! a link at the name is moved aside, not followed
        call create_temporary(dir, final_name(t(i)%final), aside(i), aside_err)
        ok = .not. allocated(aside_err)
        if (ok) call close_temporary(aside(i))
        if (ok) ok = c_rename(t(i)%final // c_null_char, aside(i)%path // c_null_char) == 0
        if (.not. ok) exit
        saved(i) = .true.
      end if
      if (c_rename(t(i)%path // c_null_char, t(i)%final // c_null_char) /= 0) then
        ok = .false.
        exit
      end if
      moved(i) = .true.
    end do
    do j = size(t), 1, -1
      if (ok) then                          ! success: the earlier outputs go, the temporaries are the outputs
        if (moved(j)) call c2d_forget_temporary(t(j)%path // c_null_char)
        if (saved(j)) call remove_file(aside(j)%path)
      else                                  ! undo: new outputs back to their temporaries, old ones in place
        if (moved(j)) then
          if (c_rename(t(j)%final // c_null_char, t(j)%path // c_null_char) /= 0) continue
        end if
        if (saved(j)) then
          if (c_rename(aside(j)%path // c_null_char, t(j)%final // c_null_char) == 0) &
            call c2d_forget_temporary(aside(j)%path // c_null_char)
        end if
      end if
      if (made(aside(j)) .and. .not. saved(j)) call remove_file(aside(j)%path)
    end do
    call c2d_unlock_folder(lock)
    if (.not. ok) call set_error(err, dir // cannot, error_input)
  end subroutine commit_temporaries

  !> Remove the temporaries that were made (their descriptors closed).
  subroutine discard_temporaries(t)
    type(temporary_t), intent(inout) :: t(:)
    integer :: i
    do i = 1, size(t)
      call close_temporary(t(i))
      if (made(t(i))) call remove_file(t(i)%path)
    end do
  end subroutine discard_temporaries

  !> t was made (create_temporary succeeded).
  pure logical function made(t)
    type(temporary_t), intent(in) :: t
    made = .false.
    if (allocated(t%path)) made = len(t%path) > 0
  end function made

  !> Remove a temporary of this run and forget it.
  subroutine remove_file(path)
    character(len=*), intent(in) :: path
    if (c_unlink(path // c_null_char) /= 0) continue
    call c2d_forget_temporary(path // c_null_char)
  end subroutine remove_file

  !> The last component of a path.
  pure function final_name(path) result(name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: name
    name = path(index(path, '/', back=.true.) + 1:)
  end function final_name

  !> /proc/self/fd/N
  function fd_path(fd) result(p)
    integer(c_int), intent(in) :: fd
    character(len=:), allocatable :: p
    character(len=16) :: buf
    write(buf, '(i0)') fd
    p = '/proc/self/fd/' // trim(buf)
  end function fd_path

  !> The path of a program on PATH.
  subroutine find_program(name, path, found)
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: path
    logical, intent(out) :: found
    character(len=4096) :: buf
    found = c2d_find_program(name // c_null_char, buf, int(len(buf), c_int)) == 0
    path = ''
    if (found) path = buf(1:index(buf, c_null_char) - 1)
  end subroutine find_program

end module safe_files
