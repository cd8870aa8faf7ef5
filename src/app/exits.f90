!> exits: the program's exit paths, for the application layer alone.  A
!> library module never stops the process: it returns an error_t (base/errors)
!> and the run pipeline decides.
!>
!> Programming interface
!>   stop_input_errors(d) print the collected input errors and exit 2 (only when there are any)
!>   stop_on(err)         print `contact2d: error: MESSAGE` and exit by its category: 2 for
!>                        input, 1 for the others (only when err is allocated)
!>   fail_numerical(text) print `contact2d: error: text` and exit 1
!>   exit_program(status) terminate with the given status, printing nothing
module exits
  use errors, only: diag_t, print_errors, error_t, error_input
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private
  public :: stop_input_errors, stop_on, fail_numerical, exit_program

  interface
    subroutine c_exit(status) bind(c, name="exit")
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

contains

  !> Print the collected input errors and exit 2; return when there are none.
  subroutine stop_input_errors(d)
    type(diag_t), intent(in) :: d
    if (d%count == 0) return
    call print_errors(d)
    call exit_program(2)
  end subroutine stop_input_errors

  !> An error that came back to the program ends the run: input errors with
  !> status 2, every other kind (numerical, no equilibrium, unsolved, a
  !> broken assumption of the model) with status 1.  Nothing when err is
  !> not allocated.
  subroutine stop_on(err)
    type(error_t), allocatable, intent(in) :: err
    if (.not. allocated(err)) return
    write(error_unit, '(a)') 'contact2d: error: ' // err%message
    flush(error_unit)
    call exit_program(merge(2, 1, err%category == error_input))
  end subroutine stop_on

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

end module exits
