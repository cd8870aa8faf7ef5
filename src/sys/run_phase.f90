!> run_phase: the step of the run that an out-of-memory diagnosis names.
!>
!> Most allocations that grow with the problem have stat= and say their own
!> phase and sizes (errors: set_out_of_memory).  The others, which the code
!> does not check, end in src/sys/fortran_oom.c (a runtime's failed
!> allocation, a write through the null pointer it returned), which knows
!> only what the program told it last: the step boundaries of src/app/ call
!> enter_phase, and a failure then reads `contact2d: error: out of memory
!> while PHASE (...) (about N MB needed)`.  A C global rather than the source
!> file the runtime names, because not every runtime names one (flang's
!> unchecked ALLOCATE, a reallocation on assignment) and the step is what the
!> reader of the message wants.
!>
!> Programming interface
!>   enter_phase(phase)   phase: what the run does from now on, as the
!>                        message says it ("factorizing K"); 95 characters kept
module run_phase
  use, intrinsic :: iso_c_binding, only: c_char, c_size_t
  implicit none
  private
  public :: enter_phase

  interface
    !> include/fortran_oom.h: the phase, phase(1:length), copied.
    subroutine c2d_set_phase(phase, length) bind(c, name='c2d_set_phase')
      import :: c_char, c_size_t
      character(kind=c_char), intent(in) :: phase(*)
      integer(c_size_t), value :: length
    end subroutine c2d_set_phase
  end interface

contains

  !> The run enters a step; phase (in): its name as the diagnosis says it.
  subroutine enter_phase(phase)
    character(len=*), intent(in) :: phase
    call c2d_set_phase(phase, len(phase, kind=c_size_t))
  end subroutine enter_phase
end module run_phase
