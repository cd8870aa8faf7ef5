!> system_binding: the raw bind(c) interfaces of src/sys/file_guard.c and
!> src/sys/process_runner.c (see include/file_guard.h, include/process_runner.h),
!> and of the libc calls used with them.  Strings go to C NUL-terminated;
!> paths come back in caller buffers, NUL-terminated.  The Fortran-facing
!> API is in safe_files and gmsh_runner.
module system_binding
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_double, c_long_long
  implicit none
  private
  public :: c2d_file_kind, c2d_open_input, c2d_close, c2d_make_folders, c2d_private_folder, &
            c2d_create_temporary, c2d_forget_temporary, c2d_lock_folder, c2d_unlock_folder, c2d_real_path, &
            c2d_file_stamp, c2d_find_program, c2d_run_program, c2d_cpu_seconds, &
            c2d_server_start, c2d_server_running, c2d_server_call, c2d_server_stop, c_unlink, c_rename
  public :: c2d_regular, c2d_missing, c2d_fifo, c2d_device, c2d_folder, c2d_socket, c2d_unreadable
  public :: c2d_run_exited, c2d_run_signaled, c2d_run_timeout, c2d_run_not_started

  ! file kinds (file_guard.h)
  integer(c_int), parameter :: c2d_regular = 0, c2d_missing = 1, c2d_fifo = 2, c2d_device = 3, c2d_folder = 4, &
                               c2d_socket = 5, c2d_unreadable = 6
  ! how a program ended (process_runner.h)
  integer(c_int), parameter :: c2d_run_exited = 0, c2d_run_signaled = 1, c2d_run_timeout = 2, c2d_run_not_started = 3

  interface
    integer(c_int) function c2d_file_kind(path) bind(c, name='c2d_file_kind')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c2d_file_kind

    integer(c_int) function c2d_open_input(path, fd) bind(c, name='c2d_open_input')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), intent(out) :: fd
    end function c2d_open_input

    integer(c_int) function c2d_close(fd) bind(c, name='c2d_close')
      import :: c_int
      integer(c_int), value :: fd
    end function c2d_close

    integer(c_int) function c2d_make_folders(path) bind(c, name='c2d_make_folders')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c2d_make_folders

    integer(c_int) function c2d_private_folder(path, length) bind(c, name='c2d_private_folder')
      import :: c_int, c_char
      character(kind=c_char), intent(out) :: path(*)
      integer(c_int), value :: length
    end function c2d_private_folder

    integer(c_int) function c2d_create_temporary(dir, name, path, length, fd) bind(c, name='c2d_create_temporary')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: dir(*), name(*)
      character(kind=c_char), intent(out) :: path(*)
      integer(c_int), value :: length
      integer(c_int), intent(out) :: fd
    end function c2d_create_temporary

    subroutine c2d_forget_temporary(path) bind(c, name='c2d_forget_temporary')
      import :: c_char
      character(kind=c_char), intent(in) :: path(*)
    end subroutine c2d_forget_temporary

    integer(c_int) function c2d_lock_folder(dir) bind(c, name='c2d_lock_folder')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: dir(*)
    end function c2d_lock_folder

    subroutine c2d_unlock_folder(fd) bind(c, name='c2d_unlock_folder')
      import :: c_int
      integer(c_int), value :: fd
    end subroutine c2d_unlock_folder

    integer(c_int) function c2d_real_path(path, real, length) bind(c, name='c2d_real_path')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(out) :: real(*)
      integer(c_int), value :: length
    end function c2d_real_path

    integer(c_int) function c2d_file_stamp(path, size, mtime_ns) bind(c, name='c2d_file_stamp')
      import :: c_int, c_char, c_long_long
      character(kind=c_char), intent(in) :: path(*)
      integer(c_long_long), intent(out) :: size, mtime_ns
    end function c2d_file_stamp

    integer(c_int) function c2d_find_program(name, path, length) bind(c, name='c2d_find_program')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: name(*)
      character(kind=c_char), intent(out) :: path(*)
      integer(c_int), value :: length
    end function c2d_find_program

    integer(c_int) function c2d_run_program(args, nargs, log_path, timeout, how, status) bind(c, name='c2d_run_program')
      import :: c_int, c_char, c_double
      character(kind=c_char), intent(in) :: args(*), log_path(*)
      integer(c_int), value :: nargs
      real(c_double), value :: timeout
      integer(c_int), intent(out) :: how, status
    end function c2d_run_program

    integer(c_int) function c2d_server_start(args, nargs, log_path, status) bind(c, name='c2d_server_start')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: args(*), log_path(*)
      integer(c_int), value :: nargs
      integer(c_int), intent(out) :: status
    end function c2d_server_start

    integer(c_int) function c2d_server_running() bind(c, name='c2d_server_running')
      import :: c_int
    end function c2d_server_running

    integer(c_int) function c2d_server_call(request, length, timeout, how, status) bind(c, name='c2d_server_call')
      import :: c_int, c_char, c_double
      character(kind=c_char), intent(in) :: request(*)
      integer(c_int), value :: length
      real(c_double), value :: timeout
      integer(c_int), intent(out) :: how, status
    end function c2d_server_call

    subroutine c2d_server_stop() bind(c, name='c2d_server_stop')
    end subroutine c2d_server_stop

    real(c_double) function c2d_cpu_seconds() bind(c, name='c2d_cpu_seconds')
      import :: c_double
    end function c2d_cpu_seconds

    integer(c_int) function c_unlink(path) bind(c, name='unlink')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_unlink

    integer(c_int) function c_rename(from, to) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: from(*), to(*)
    end function c_rename
  end interface

end module system_binding
