!> errors: how an error travels across module boundaries.
!>
!> contact2d reports bad input as
!>     contact2d: error: FILE:LINE: what is wrong (what was expected)
!> collects every such error it can find before stopping (diag_t), and then
!> exits with status 2.  A mid-level routine that fails returns an error_t
!> (its last argument, intent(out), allocatable: the caller tests
!> allocated(err) and returns); only the application layer (app/exits)
!> ends the process.
!>
!> Programming interface
!>   type(diag_t)         list of collected messages (file, line, text)
!>   add_error(d, file, line, text [, echo])
!>                        append one message; line <= 0 prints FILE: only;
!>                        echo, when present, is the offending input line, printed
!>                        indented under the message
!>   has_errors(d)        .true. when at least one message was collected
!>   print_errors(d)      write every message to stderr, in order
!>   type(error_t)        a mid-level error: message, category, the input line, equation or
!>                        pair it names, whether K is singular or memory ran out (and how much)
!>   error_numerical, error_input, error_no_equilibrium, error_unsolved, error_model
!>                        the categories: what kind of failure (the application maps them
!>                        to exit statuses: 2 for input, 1 for the others)
!>   set_error(err, message [, category])
!>                        err = message, category error_numerical unless given
!>   set_out_of_memory(err, phase, bytes)
!>                        err = `out of memory while PHASE (about N MB needed)`, error_numerical, no_memory
module errors
  use kinds, only: i8
  use strings, only: int_to_str, i8_to_str, printable
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private
  public :: diag_t, add_error, has_errors, print_errors, error_t, set_error, set_out_of_memory
  public :: error_numerical, error_input, error_no_equilibrium, error_unsolved, error_model

  !> What kind of failure an error_t is: the application decides what each
  !> means for the run (exit 2 for input, 1 for the others; a fallback may
  !> follow an unsolved step, never a proved absence of equilibrium).
  integer, parameter :: error_numerical = 1       !< a numerical failure (singular K, overflow, ...)
  integer, parameter :: error_input = 2           !< bad input: the deck, a mesh, an option
  integer, parameter :: error_no_equilibrium = 3  !< proved: no static equilibrium exists
  integer, parameter :: error_unsolved = 4        !< a solver failed without proving anything
  integer, parameter :: error_model = 5           !< the answer leaves the model's assumptions

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
    integer :: category = error_numerical      !< error_numerical, error_input, ... (above)
    integer :: equation = 0                    !< the free equation (row of K) it names, 0: none
    integer :: pair = 0                        !< the contact pair (its CONTACT statement, 1-based) it names, 0: none
    integer :: line = 0                        !< the line of the input file it names, 0: the file as a whole
    character(len=:), allocatable :: echo      !< that line as read, for the message (unallocated: none)
    logical :: singular = .false.              !< K singular or not positive definite (at equation, when > 0)
    logical :: no_memory = .false.             !< an allocation failed (set_out_of_memory)
    integer(i8) :: bytes = 0                   !< what that allocation needed, bytes (set_out_of_memory)
  end type error_t

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

  !> Fill err with a message and its category (error_numerical by default).
  subroutine set_error(err, message, category)
    type(error_t), allocatable, intent(out) :: err
    character(len=*), intent(in) :: message
    integer, intent(in), optional :: category
    allocate(err)
    err%message = message
    if (present(category)) err%category = category
  end subroutine set_error

  !> Exhausted memory is a diagnosis, not a crash: the run ends with exit 1 and
  !> `out of memory while PHASE (about N MB needed)`.
  !>   err    (out) the error, error_numerical, no_memory
  !>   phase  (in)  what the program was doing ('meshing body "b"', 'factorizing K')
  !>   bytes  (in)  what that phase needs (an estimate), >= 0
  subroutine set_out_of_memory(err, phase, bytes)
    type(error_t), allocatable, intent(out) :: err
    character(len=*), intent(in) :: phase
    integer(i8), intent(in) :: bytes
    call set_error(err, 'out of memory while ' // phase // ' (about ' // &
                   i8_to_str(max(1_i8, (bytes + 1048575_i8) / 1048576_i8)) // ' MB needed)', error_numerical)
    err%no_memory = .true.
    err%bytes = bytes
  end subroutine set_out_of_memory

end module errors
