!> runtime_binding: raw bind(c) interfaces to the process-wide settings of a
!> run (src/sys/runtime_tuning.c, include/runtime_tuning.h; OpenBLAS under an
!> address-space limit, src/sys/blas_start.c, include/blas_start.h) and to the
!> memory the process can still have (src/sys/memory_limit.c, include/memory_limit.h).
!>
!> Programming interface
!>   c2d_runtime_start(nthreads)   once at start-up: two malloc arenas, OpenBLAS's thread count
!>   c2d_blas_threads(n) -> the thread count OpenBLAS had (0: not OpenBLAS); n <= 0 leaves it
!>   c2d_malloc_trim()             the free pages of every malloc arena back to the system
!>   c2d_memory_available() -> bytes the process can still allocate (-1 unknown)
!>   c2d_blas_start(n, left, per_thread, first) -> BLAS threads that fit an address-space limit
module runtime_binding
  use, intrinsic :: iso_c_binding, only: c_int, c_int64_t
  implicit none
  private
  public :: c2d_runtime_start, c2d_blas_threads, c2d_malloc_trim, c2d_memory_available, c2d_blas_start

  interface

    !> At most two glibc malloc arenas; OpenBLAS's thread count set to nthreads (>= 1).
    subroutine c2d_runtime_start(nthreads) bind(c, name='c2d_runtime_start')
      import :: c_int
      integer(c_int), value :: nthreads
    end subroutine c2d_runtime_start

    !> Set OpenBLAS's thread count (n <= 0: leave it); returns the count it had, 0 when not OpenBLAS.
    function c2d_blas_threads(n) bind(c, name='c2d_blas_threads') result(old)
      import :: c_int
      integer(c_int), value :: n
      integer(c_int) :: old
    end function c2d_blas_threads

    !> The free pages of every malloc arena back to the system.
    subroutine c2d_malloc_trim() bind(c, name='c2d_malloc_trim')
    end subroutine c2d_malloc_trim

    !> Bytes the process can still allocate: the smaller of the address space
    !> left under RLIMIT_AS and MemAvailable + SwapFree; -1 when unknown.
    function c2d_memory_available() bind(c, name='c2d_memory_available') result(bytes)
      import :: c_int64_t
      integer(c_int64_t) :: bytes
    end function c2d_memory_available

    !> OpenBLAS under an address-space limit (src/sys/blas_start.c): the thread
    !> count to use (<= n) with its work buffers mapped; n without a limit;
    !> 0 when not even one buffer fits.  left: the address space left (-1:
    !> no limit), per_thread: bytes of a further thread, first: of the first
    !> buffer.
    function c2d_blas_start(n, left, per_thread, first) bind(c, name='c2d_blas_start') result(used)
      import :: c_int, c_int64_t
      integer(c_int), value :: n
      integer(c_int64_t), intent(out) :: left, per_thread, first
      integer(c_int) :: used
    end function c2d_blas_start

  end interface

end module runtime_binding
