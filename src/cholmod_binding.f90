!> cholmod_binding: raw bind(c) interfaces to the C shim over CHOLMOD
!> (src/cholmod_shim.c, include/cholmod_shim.h), and the status codes it returns.
!>
!> This is the lowest of three layers: C shim, these interfaces, and the
!> Fortran API in sparse_cholesky.  Use sparse_cholesky; only it should call
!> these routines.  Every index passed here is 1-based; arrays are passed by
!> address, scalars by value; character results come back as NUL-terminated
!> c_char arrays.
!>
!> Ownership: c2d_chol_create returns a handle that owns a cholmod_common and
!> the factor; exactly one c2d_chol_destroy must release it.
!>
!> Programming interface (see include/cholmod_shim.h for the details)
!>   c2d_chol_create() -> handle          c2d_chol_destroy(handle)
!>   c2d_chol_factorize(handle, n, colptr, rowind, val, nlast, last) -> status
!>   c2d_chol_set_ordering(handle, method) -> status   method: c2d_order_metis, c2d_order_amd
!>   c2d_chol_analyze(handle, n, colptr, rowind, offset, nlast, last, ngroup, group) -> status
!>   c2d_chol_separator(handle, n, colptr, rowind, offset, nlast, last, group, side) -> status
!>   c2d_chol_factorize_values(handle, n, colptr, rowind, offset, val) -> status
!>   c2d_chol_minor(handle, column, equation)
!>   c2d_chol_stats(handle, lnz, flops, memory_peak, time_analyze, time_factorize)
!>   c2d_chol_min_pivot_ratio(handle, ratio, column, equation)
!>   c2d_chol_ordering_name(handle, buf, len)   c2d_chol_status_name(status, buf, len)
!>   c2d_chol_solve(handle, n, nrhs, b, x) -> status
!>   c2d_chol_solve_half(handle, half, n, nrhs, b, x) -> status   (c2d_solve_whole / _forward / _backward)
!>   c2d_chol_trailing_range(handle, nlast, first, count, lcc) -> status
!>   c2d_chol_trailing_block_end(handle, nlast, first, last_row) -> status
!>   c2d_blas_threads(n) -> the thread count OpenBLAS had (0: not OpenBLAS)
!>   c2d_blas_park()   end OpenBLAS's spinning worker threads (restarted by the next threaded call)
!>   c2d_malloc_arenas()   c2d_malloc_trim()   at most two glibc malloc arenas; free pages back
!>   c2d_metis_per_thread() -> 1 when METIS draws its random numbers per thread
!>   c2d_memory_available() -> bytes the process can still allocate (-1 unknown)
!>   c2d_blas_start(n, left, per_thread, first) -> BLAS threads that fit an address-space limit
!>   status codes: cholmod_ok, cholmod_not_posdef, c2d_chol_* (shim codes)
module cholmod_binding
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_int64_t, c_char
  implicit none
  private
  public :: c2d_chol_create, c2d_chol_destroy, c2d_chol_factorize, c2d_chol_minor
  public :: c2d_chol_analyze, c2d_chol_separator, c2d_chol_factorize_values, c2d_chol_set_ordering
  public :: c2d_order_metis, c2d_order_amd
  public :: c2d_chol_stats, c2d_chol_min_pivot_ratio, c2d_chol_ordering_name
  public :: c2d_chol_status_name, c2d_chol_solve
  public :: c2d_chol_trailing_range, c2d_chol_trailing_block_end
  public :: c2d_chol_solve_half, c2d_solve_whole, c2d_solve_forward, c2d_solve_backward
  public :: cholmod_ok, cholmod_not_posdef, cholmod_out_of_memory, cholmod_too_large
  public :: c2d_chol_no_handle, c2d_chol_no_factor, c2d_chol_not_super_ll
  public :: c2d_chol_block_moved, c2d_chol_bad_argument, c2d_blas_threads, c2d_blas_park, c2d_malloc_arenas, c2d_malloc_trim
  public :: c2d_metis_per_thread, c2d_memory_available, c2d_blas_start

  ! fill-reducing orderings (cholmod_shim.h)
  integer(c_int), parameter :: c2d_order_metis = 0     !< METIS nested dissection
  integer(c_int), parameter :: c2d_order_amd = 1       !< approximate minimum degree

  ! the halves of a solve (cholmod_shim.h)
  integer(c_int), parameter :: c2d_solve_whole = 0     !< x = A^-1 b
  integer(c_int), parameter :: c2d_solve_forward = 1   !< y = L^-1 P b
  integer(c_int), parameter :: c2d_solve_backward = 2  !< x = P' L'^-1 y

  ! CHOLMOD status codes (cholmod_core.h)
  integer(c_int), parameter :: cholmod_ok = 0             !< success
  integer(c_int), parameter :: cholmod_not_posdef = 1     !< warning: matrix not positive definite
  integer(c_int), parameter :: cholmod_out_of_memory = -2 !< failure: out of memory
  integer(c_int), parameter :: cholmod_too_large = -3     !< failure: integer overflow
  ! shim codes (cholmod_shim.h)
  integer(c_int), parameter :: c2d_chol_no_handle = -100     !< handle not created
  integer(c_int), parameter :: c2d_chol_no_factor = -101     !< no valid numeric factor
  integer(c_int), parameter :: c2d_chol_not_super_ll = -102  !< L not supernodal LL'
  integer(c_int), parameter :: c2d_chol_block_moved = -103   !< last block not at the last pivots
  integer(c_int), parameter :: c2d_chol_bad_argument = -104  !< inconsistent argument

  interface

    !> New handle (cholmod_start, supernodal settings); c_null_ptr when out of memory.
    function c2d_chol_create() bind(c, name='c2d_chol_create') result(handle)
      import :: c_ptr
      type(c_ptr) :: handle
    end function c2d_chol_create

    !> Free factor and common; a null handle is a no-op.
    subroutine c2d_chol_destroy(handle) bind(c, name='c2d_chol_destroy')
      import :: c_ptr
      type(c_ptr), value :: handle
    end subroutine c2d_chol_destroy

    !> Analyze and factorize; returns the status (cholmod_ok on success).
    function c2d_chol_factorize(handle, n, colptr, rowind, val, nlast, last) &
        bind(c, name='c2d_chol_factorize') result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), value :: n
      integer(c_int), intent(in) :: colptr(*)
      integer(c_int), intent(in) :: rowind(*)
      real(c_double), intent(in) :: val(*)
      integer(c_int), value :: nlast
      integer(c_int), intent(in) :: last(*)
      integer(c_int) :: status
    end function c2d_chol_factorize

    !> The ordering of the next analyses (c2d_order_*); returns the status.
    function c2d_chol_set_ordering(handle, method) bind(c, name='c2d_chol_set_ordering') result(status)
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int), value :: method
      integer(c_int) :: status
    end function c2d_chol_set_ordering

    !> Ordering and symbolic analysis of the pattern; returns the status.
    function c2d_chol_analyze(handle, n, colptr, rowind, offset, nlast, last, ngroup, group) &
        bind(c, name='c2d_chol_analyze') result(status)
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int), value :: n
      integer(c_int), intent(in) :: colptr(*)
      integer(c_int), intent(in) :: rowind(*)
      integer(c_int), value :: offset
      integer(c_int), value :: nlast
      integer(c_int), intent(in) :: last(*)
      integer(c_int), value :: ngroup
      integer(c_int), intent(in) :: group(*)
      integer(c_int) :: status
    end function c2d_chol_analyze

    !> The top vertex separator of the node graph without `last`: side(k) = 0, 1
    !> (the halves), 2 (the separator) or 3 (`last`); returns the status.
    function c2d_chol_separator(handle, n, colptr, rowind, offset, nlast, last, group, side) &
        bind(c, name='c2d_chol_separator') result(status)
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int), value :: n
      integer(c_int), intent(in) :: colptr(*)
      integer(c_int), intent(in) :: rowind(*)
      integer(c_int), value :: offset
      integer(c_int), value :: nlast
      integer(c_int), intent(in) :: last(*)
      integer(c_int), intent(in) :: group(*)
      integer(c_int), intent(out) :: side(*)
      integer(c_int) :: status
    end function c2d_chol_separator

    !> Numeric factorization of the analyzed pattern's values; returns the status.
    function c2d_chol_factorize_values(handle, n, colptr, rowind, offset, val) &
        bind(c, name='c2d_chol_factorize_values') result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), value :: n
      integer(c_int), intent(in) :: colptr(*)
      integer(c_int), intent(in) :: rowind(*)
      integer(c_int), value :: offset
      real(c_double), intent(in) :: val(*)
      integer(c_int) :: status
    end function c2d_chol_factorize_values

    !> Failing pivot (column of P A P') and its dof; 0, 0 when none.
    subroutine c2d_chol_minor(handle, column, equation) bind(c, name='c2d_chol_minor')
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int), intent(out) :: column, equation
    end subroutine c2d_chol_minor

    !> nnz(L), flop count, peak memory (bytes), analysis and factorization seconds.
    subroutine c2d_chol_stats(handle, lnz, flops, memory_peak, time_analyze, time_factorize) &
        bind(c, name='c2d_chol_stats')
      import :: c_ptr, c_int64_t, c_double
      type(c_ptr), value :: handle
      integer(c_int64_t), intent(out) :: lnz
      real(c_double), intent(out) :: flops
      integer(c_int64_t), intent(out) :: memory_peak
      real(c_double), intent(out) :: time_analyze, time_factorize
    end subroutine c2d_chol_stats

    !> min_k L(k,k)^2 / A(p_k,p_k), its pivot and dof (NaN ratio: non-finite L(k,k)).
    subroutine c2d_chol_min_pivot_ratio(handle, ratio, column, equation) &
        bind(c, name='c2d_chol_min_pivot_ratio')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      real(c_double), intent(out) :: ratio
      integer(c_int), intent(out) :: column, equation
    end subroutine c2d_chol_min_pivot_ratio

    !> Name of the ordering used, NUL-terminated in buf(1:len).
    subroutine c2d_chol_ordering_name(handle, buf, len) bind(c, name='c2d_chol_ordering_name')
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: handle
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value :: len
    end subroutine c2d_chol_ordering_name

    !> Name of a status code, NUL-terminated in buf(1:len).
    subroutine c2d_chol_status_name(status, buf, len) bind(c, name='c2d_chol_status_name')
      import :: c_int, c_char
      integer(c_int), value :: status
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value :: len
    end subroutine c2d_chol_status_name

    !> x = A \ b for b(n, nrhs) column-major; returns the status.
    function c2d_chol_solve(handle, n, nrhs, b, x) bind(c, name='c2d_chol_solve') result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), value :: n, nrhs
      real(c_double), intent(in) :: b(*)
      real(c_double), intent(inout) :: x(*)
      integer(c_int) :: status
    end function c2d_chol_solve

    !> The whole solve or one half (forward: y = L \ P b; backward: x = P' (L' \ y)).
    function c2d_chol_solve_half(handle, half, n, nrhs, b, x) bind(c, name='c2d_chol_solve_half') result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), value :: half, n, nrhs
      real(c_double), intent(in) :: b(*)
      real(c_double), intent(inout) :: x(*)
      integer(c_int) :: status
    end function c2d_chol_solve_half

    !> The diagonal sub-block first..first+count-1 of L_cc, (count, count); returns the status.
    function c2d_chol_trailing_range(handle, nlast, first, count, lcc) bind(c, name='c2d_chol_trailing_range') &
        result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), value :: nlast, first, count
      real(c_double), intent(inout) :: lcc(*)
      integer(c_int) :: status
    end function c2d_chol_trailing_range

    !> The last row of the diagonal block of L_cc that starts at `first`; returns the status.
    function c2d_chol_trailing_block_end(handle, nlast, first, last_row) bind(c, name='c2d_chol_trailing_block_end') &
        result(status)
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int), value :: nlast, first
      integer(c_int), intent(out) :: last_row
      integer(c_int) :: status
    end function c2d_chol_trailing_block_end

    !> Set OpenBLAS's thread count (n <= 0: leave it); returns the count it had, 0 when not OpenBLAS.
    function c2d_blas_threads(n) bind(c, name='c2d_blas_threads') result(old)
      import :: c_int
      integer(c_int), value :: n
      integer(c_int) :: old
    end function c2d_blas_threads

    !> End OpenBLAS's worker threads, which spin for a while after each
    !> call and take a core from the OpenMP threads; the next threaded BLAS
    !> call starts them again.  Nothing when the BLAS is not OpenBLAS.
    subroutine c2d_blas_park() bind(c, name='c2d_blas_park')
    end subroutine c2d_blas_park

    !> At most two glibc malloc arenas for all threads.
    subroutine c2d_malloc_arenas() bind(c, name='c2d_malloc_arenas')
    end subroutine c2d_malloc_arenas

    !> The free pages of every malloc arena back to the system.
    subroutine c2d_malloc_trim() bind(c, name='c2d_malloc_trim')
    end subroutine c2d_malloc_trim

    !> 1 when METIS orderings draw from a random sequence per thread (they
    !> may run side by side and give what each gives alone), 0 when METIS
    !> calls run one at a time instead.
    function c2d_metis_per_thread() bind(c, name='c2d_metis_per_thread') result(yes)
      import :: c_int
      integer(c_int) :: yes
    end function c2d_metis_per_thread

    !> Bytes the process can still allocate: the smaller of the address space
    !> left under RLIMIT_AS and MemAvailable + SwapFree; -1 when unknown.
    function c2d_memory_available() bind(c, name='c2d_memory_available') result(bytes)
      import :: c_int64_t
      integer(c_int64_t) :: bytes
    end function c2d_memory_available

    !> OpenBLAS under an address-space limit (src/blas_start.c): the thread
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

end module cholmod_binding
