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
!> runtime_binding (src/runtime_tuning.c): at most two glibc malloc arenas
!> (the parts of a factor allocate on the threads; each further arena keeps
!> freed pages resident) and OpenBLAS's thread count.
!>
!> Programming interface
!>   start_threads(jobs)   jobs > 0: use jobs threads; 0: the OpenMP default
!>   run_threads()         the number of threads the run uses (>= 1)
module threads
  use, intrinsic :: iso_c_binding, only: c_int
  use omp_lib, only: omp_set_num_threads, omp_get_max_threads
  use runtime_binding, only: c2d_runtime_start
  implicit none
  private
  public :: start_threads, run_threads

contains

  !> Set the run's thread count, once, before any parallel region.
  !>   jobs  (in) number of threads, >= 1; 0 keeps the OpenMP default
  !>         (OMP_NUM_THREADS, else one per core)
  subroutine start_threads(jobs)
    integer, intent(in) :: jobs
    if (jobs > 0) call omp_set_num_threads(jobs)
    ! OpenBLAS reads OPENBLAS_NUM_THREADS or OMP_NUM_THREADS when it loads,
    ! not -j: give it the run's count
    call c2d_runtime_start(int(run_threads(), c_int))
  end subroutine start_threads

  !> The number of threads the run uses (OpenMP's, outside any parallel region).
  integer function run_threads()
    run_threads = max(1, omp_get_max_threads())
  end function run_threads

end module threads
