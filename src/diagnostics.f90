!> diagnostics: user-error collection and the program's exit paths.
!>
!> contact2d reports bad input as
!>     contact2d: error: FILE:LINE: what is wrong (what was expected)
!> collects every such error it can find before stopping, and then exits with
!> status 2.  Numerical failures exit with status 1.
!>
!> Programming interface
!>   type(diag_t)         list of collected messages (file, line, text)
!>   add_error(d, file, line, text [, echo])
!>                        append one message; line <= 0 prints FILE: only;
!>                        echo, when present, is the offending input line, printed
!>                        indented under the message
!>   has_errors(d)        .true. when at least one message was collected
!>   print_errors(d)      write every message to stderr, in order
!>   stop_input_errors(d) print them and exit 2 (only when there are any)
!>   fail_numerical(text) print `contact2d: error: text` and exit 1
!>   exit_program(status) terminate with the given status, printing nothing
!>   type(error_t)        a mid-level error: message, exit status (1 or 2), the equation or pair it names,
!>                        whether K is singular or memory ran out
!>   printable(text)      text with control and non-ASCII bytes replaced by '?'
!>   set_out_of_memory(err, phase, bytes)
!>                        err = `out of memory while PHASE (about N MB needed)`, status 1, no_memory
!>   real_to_str(x)       4 significant digits, any exponent (1.000E-05, 1.000E-300)
module diagnostics
  use kinds, only: dp, i8
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private
  public :: diag_t, add_error, has_errors, print_errors, stop_input_errors
  public :: fail_numerical, exit_program, error_t, set_error, set_out_of_memory, int_to_str, i8_to_str, real_to_str
  public :: printable

  !> One collected message.
  type :: message_t
    character(len=:), allocatable :: text   !< full formatted line(s)
  end type message_t


  type :: diag_t
    integer :: count = 0                       !< number of messages held
    type(message_t), allocatable :: items(:)   !< (capacity) the messages
  end type diag_t

  !> A mid-level error: callers test allocated(err) and return.  The fields
  !> after the message carry what a caller needs to act on it, so that no
  !> caller reads them back out of the text.
  type :: error_t
    character(len=:), allocatable :: message  !< text after `contact2d: error: `
    integer :: status = 1                      !< exit status: 1 numerical, 2 input
    integer :: equation = 0                    !< the free equation (row of K) it names, 0: none
    integer :: pair = 0                        !< the contact pair (its CONTACT statement, 1-based) it names, 0: none
    logical :: singular = .false.              !< K singular or not positive definite (at equation, when > 0)
    logical :: no_memory = .false.             !< an allocation failed (set_out_of_memory)
  end type error_t

  interface
    subroutine c_exit(status) bind(c, name="exit")
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

contains

  !> Append one message `FILE:LINE: text` to d.
  !>   d     (inout) the list
  !>   file  (in)    file name as the user knows it
  !>   line  (in)    1-based line number; <= 0 omits it
  !>   text  (in)    what is wrong (what was expected)
  !>   echo  (in, optional) the offending line, printed under the message
  subroutine add_error(d, file, line, text, echo)
    type(diag_t), intent(inout) :: d
    character(len=*), intent(in) :: file
    integer, intent(in) :: line
    character(len=*), intent(in) :: text
    character(len=*), intent(in), optional :: echo
    type(message_t), allocatable :: grown(:)
    character(len=:), allocatable :: s

    if (.not. allocated(d%items)) allocate(d%items(16))
    if (d%count == size(d%items)) then
      allocate(grown(2 * size(d%items)))
      grown(1:d%count) = d%items(1:d%count)
      call move_alloc(grown, d%items)
    end if
    if (line > 0) then
      s = 'contact2d: error: ' // file // ':' // int_to_str(line) // ': ' // text
    else
      s = 'contact2d: error: ' // file // ': ' // text
    end if
    if (present(echo)) then
      if (len_trim(echo) > 0) s = s // new_line('a') // '    ' // trim(printable(echo))
    end if
    d%count = d%count + 1
    d%items(d%count)%text = s
  end subroutine add_error

  !> Replace control and non-ASCII bytes by '?' so an echoed line is printable.
  pure function printable(line) result(s)
    character(len=*), intent(in) :: line
    character(len=len(line)) :: s
    integer :: i, c
    s = line
    do i = 1, len(s)
      c = iachar(s(i:i))
      if (c < 32 .or. c > 126) s(i:i) = '?'
    end do
  end function printable

  logical function has_errors(d)
    type(diag_t), intent(in) :: d
    has_errors = d%count > 0
  end function has_errors

  subroutine print_errors(d)
    type(diag_t), intent(in) :: d
    integer :: i
    do i = 1, d%count
      write(error_unit, '(a)') d%items(i)%text
    end do
    flush(error_unit)
  end subroutine print_errors

  !> Print the collected input errors and exit 2; return when there are none.
  subroutine stop_input_errors(d)
    type(diag_t), intent(in) :: d
    if (d%count == 0) return
    call print_errors(d)
    call exit_program(2)
  end subroutine stop_input_errors

  !> Numerical failure: print the diagnostic and exit 1.
  subroutine fail_numerical(text)
    character(len=*), intent(in) :: text
    write(error_unit, '(a)') 'contact2d: error: ' // text
    flush(error_unit)
    call exit_program(1)
  end subroutine fail_numerical

  !> Terminate with `status`, printing nothing (unlike STOP).
  subroutine exit_program(status)
    integer, intent(in) :: status
    flush(error_unit)
    call c_exit(int(status, c_int))
  end subroutine exit_program

  !> Fill err with a message and status (2 input, 1 numerical).
  subroutine set_error(err, message, status)
    type(error_t), allocatable, intent(out) :: err
    character(len=*), intent(in) :: message
    integer, intent(in), optional :: status
    allocate(err)
    err%message = message
    if (present(status)) err%status = status
  end subroutine set_error

  !> Exhausted memory is a diagnosis, not a crash: the run ends with exit 1 and
  !> `out of memory while PHASE (about N MB needed)`.
  !>   err    (out) the error, status 1
  !>   phase  (in)  what the program was doing ('meshing body "b"', 'factorizing K')
  !>   bytes  (in)  what that phase needs (an estimate), >= 0
  subroutine set_out_of_memory(err, phase, bytes)
    type(error_t), allocatable, intent(out) :: err
    character(len=*), intent(in) :: phase
    integer(i8), intent(in) :: bytes
    call set_error(err, 'out of memory while ' // phase // ' (about ' // &
                   i8_to_str(max(1_i8, (bytes + 1048575_i8) / 1048576_i8)) // ' MB needed)', 1)
    err%no_memory = .true.
  end subroutine set_out_of_memory

  !> Decimal text of an integer, no blanks.
  pure function int_to_str(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function int_to_str

  !> Decimal text of a 64-bit integer (counts beyond 2**31: nnz(L), file tags).
  pure function i8_to_str(i) result(s)
    integer(i8), intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function i8_to_str

  !> Short scientific text of a real (4 significant digits), for messages.
  function real_to_str(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    integer :: e, k
    ! room for a 3-digit exponent (es10.3 writes 1e-300 as `1.000-300`), then
    ! the exponent's leading zero dropped down to two digits: 1.000E-05
    write(buf, '(es12.3e3)') x
    s = trim(adjustl(buf))
    e = scan(s, 'E')
    if (e > 0 .and. len(s) >= e + 4) then
      k = e + 2
      if (s(k:k) == '0') s = s(1:k - 1) // s(k + 1:)
    end if
  end function real_to_str

end module diagnostics
