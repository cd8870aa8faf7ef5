!> threads: how many threads the run uses, set once at start-up.
!>
!> One policy for the whole program: `-j N` on the command line, else the
!> OpenMP default (OMP_NUM_THREADS, else every core).  start_threads sets
!> OpenMP's thread count (omp_set_num_threads) and OpenBLAS's to that number;
!> every parallel region then takes the default team (regions keep only their
!> size thresholds, `if(n > ...)`), and the loops that give each thread a
!> part of their own (the bodies' factorizations) ask run_threads how many
!> there are.  The count lives in the OpenMP run time, not here.
!>
!> It also makes the process-wide settings of the run once, through
!> runtime_binding (src/sys/runtime_tuning.c): at most two glibc malloc arenas
!> (the parts of a factor allocate on the threads; each further arena keeps
!> freed pages resident) and OpenBLAS's thread count.
!>
!> Under an address-space limit (ulimit -v) the threads cost memory: each
!> further one a BLAS work buffer and two stacks.  The count is then lowered
!> to what fits and OpenBLAS's buffers are mapped at once (src/sys/blas_start.c:
!> OpenBLAS hangs or ends the process when it cannot map or start them
!> later); a limit too tight for a single buffer ends the run with the
!> out-of-memory diagnosis before anything is read.
!>
!> Programming interface
!>   start_threads(jobs, note, err)
!>                         jobs > 0: use jobs threads; 0: the OpenMP default;
!>                         note: what the memory limit changed ('' when
!>                         nothing), for the run log; err: out of memory
!>   run_threads()         the number of threads the run uses (>= 1)
module threads
  use, intrinsic :: iso_c_binding, only: c_int, c_int64_t
  use omp_lib, only: omp_set_num_threads, omp_get_max_threads
  use runtime_binding, only: c2d_runtime_start, c2d_blas_start
  use strings, only: int_to_str, i8_to_str
  use errors, only: error_t, set_out_of_memory
  use kinds, only: i8
  implicit none
  private
  public :: start_threads, run_threads

contains

  !> Set the run's thread count, once, before any parallel region.
  !>   jobs  (in)  number of threads, >= 1; 0 keeps the OpenMP default
  !>               (OMP_NUM_THREADS, else one per core)
  !>   note  (out) '' or, when an address-space limit lowered the count,
  !>               what it did and why (for the run log)
  !>   err   (out) allocated when the limit leaves no room for the BLAS's
  !>               first work buffer (`out of memory while starting ...`)
  subroutine start_threads(jobs, note, err)
    integer, intent(in) :: jobs
    character(len=:), allocatable, intent(out) :: note
    type(error_t), allocatable, intent(out) :: err
    integer :: asked, used
    integer(c_int64_t) :: left, per_thread, first
    note = ''
    if (jobs > 0) call omp_set_num_threads(jobs)
    asked = run_threads()
    used = int(c2d_blas_start(int(asked, c_int), left, per_thread, first))
    if (used == 0) then
      call set_out_of_memory(err, 'starting the BLAS (its work buffer; the address-space limit leaves ' // &
                             i8_to_str(int(left, i8) / 1048576_i8) // ' MB)', int(first, i8))
      return
    end if
    if (used < asked) then
      call omp_set_num_threads(used)
      note = int_to_str(used) // ' of ' // int_to_str(asked) // ' asked: the address-space limit leaves ' // &
        i8_to_str(int(left, i8) / 1048576_i8) // ' MB and each further thread reserves about ' // &
        i8_to_str(int(per_thread, i8) / 1048576_i8) // ' MB (a BLAS work buffer, two stacks)'
    end if
    ! OpenBLAS reads OPENBLAS_NUM_THREADS or OMP_NUM_THREADS when it loads,
    ! not -j: give it the run's count, and bound the malloc arenas (after
    ! c2d_blas_start, which under a limit sets the count to what fits)
    call c2d_runtime_start(int(run_threads(), c_int))
  end subroutine start_threads

  !> The number of threads the run uses (OpenMP's, outside any parallel region).
  integer function run_threads()
    run_threads = max(1, omp_get_max_threads())
  end function run_threads

end module threads
