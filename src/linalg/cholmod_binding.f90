!> cholmod_binding: raw bind(c) interfaces to the C layer over CHOLMOD, and
!> the codes it returns and takes: the handle and its factor (src/linalg/cholmod_factor.c,
!> include/cholmod_factor.h) and the reading of the
!> factor (src/linalg/factor_inspection.c, include/factor_inspection.h).  The
!> process-wide settings are runtime_binding's.
!>
!> This is the lowest of three layers: the C layer, these interfaces, and the
!> Fortran API in sparse_cholesky.  Use sparse_cholesky; only it should call
!> these routines.  Every index passed here is 1-based; arrays are passed by
!> address, scalars by value; character results come back as NUL-terminated
!> c_char arrays.
!>
!> Ownership: c2d_chol_create returns a handle that owns a cholmod_common and
!> the factor; exactly one c2d_chol_destroy must release it.
!>
!> Programming interface (see the headers above for the details)
!>   c2d_chol_create() -> handle          c2d_chol_destroy(handle)
!>   c2d_chol_set_ordering(handle, method) -> status   method: c2d_order_metis, c2d_order_amd
!>   c2d_chol_analyze(handle, n, colptr, rowind, offset, nlast, last, ngroup, group) -> status
!>   c2d_chol_factorize_values(handle, n, colptr, rowind, offset, val) -> status
!>   c2d_chol_minor(handle, column, equation)
!>   c2d_chol_stats(handle, lnz, flops, memory_peak, time_analyze, time_factorize)
!>   c2d_chol_min_pivot_ratio(handle, ratio, column, equation)
!>   c2d_chol_name(handle, what, status, buf, len)   what: c2d_name_ordering, c2d_name_status
!>   c2d_chol_solve_half(handle, half, n, nrhs, b, x) -> status   (c2d_solve_whole / _forward / _backward)
!>   c2d_chol_trailing_range(handle, nlast, first, count, lcc) -> status
!>   c2d_chol_trailing_block_end(handle, nlast, first, last_row) -> status
!>   c2d_metis_per_thread() -> 1 when METIS draws its random numbers per thread
!>   status codes: cholmod_ok, cholmod_not_posdef, ... (CHOLMOD's), c2d_chol_* (the C layer's):
!>   the C layer's variables, bound by name, like the selectors c2d_order_*, c2d_name_*, c2d_solve_*
module cholmod_binding
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_int64_t, c_char
  implicit none
  private
  public :: c2d_chol_create, c2d_chol_destroy, c2d_chol_minor
  public :: c2d_chol_analyze, c2d_chol_factorize_values, c2d_chol_set_ordering
  public :: c2d_order_metis, c2d_order_amd
  public :: c2d_chol_stats, c2d_chol_min_pivot_ratio, c2d_chol_name, c2d_name_ordering, c2d_name_status
  public :: c2d_chol_trailing_range, c2d_chol_trailing_block_end
  public :: c2d_chol_solve_half, c2d_solve_whole, c2d_solve_forward, c2d_solve_backward
  public :: cholmod_ok, cholmod_not_posdef, cholmod_out_of_memory, cholmod_too_large
  public :: c2d_chol_no_handle, c2d_chol_no_factor, c2d_chol_not_super_ll
  public :: c2d_chol_block_moved, c2d_chol_bad_argument
  public :: c2d_metis_per_thread

  ! The codes of the C layer are its variables (cholmod_factor.h), bound by
  ! name: CHOLMOD's status codes as cholmod.h defines them and the C layer's
  ! own as cholmod_factor.h does, so that no value is copied here to drift
  ! from the library's.  Variables, not constants: they cannot label a
  ! `select case`; protected: only the C side sets them.  Without an
  ! initializer here, gfortran and flang emit each as a common symbol, so the
  ! C definition is the one linked (test_sparse_cholesky checks the values
  ! are CHOLMOD's, named and distinct, not zeros of an unlinked C side).

  ! fill-reducing orderings
  integer(c_int), bind(c, name='c2d_order_metis'), protected :: c2d_order_metis  !< METIS nested dissection
  integer(c_int), bind(c, name='c2d_order_amd'), protected :: c2d_order_amd      !< approximate minimum degree

  ! what c2d_chol_name names
  integer(c_int), bind(c, name='c2d_name_ordering'), protected :: c2d_name_ordering  !< the ordering of the handle's factor
  integer(c_int), bind(c, name='c2d_name_status'), protected :: c2d_name_status      !< a status code

  ! the halves of a solve
  integer(c_int), bind(c, name='c2d_solve_whole'), protected :: c2d_solve_whole        !< x = A^-1 b
  integer(c_int), bind(c, name='c2d_solve_forward'), protected :: c2d_solve_forward    !< y = L^-1 P b
  integer(c_int), bind(c, name='c2d_solve_backward'), protected :: c2d_solve_backward  !< x = P' L'^-1 y

  ! CHOLMOD status codes (0 success, > 0 a warning, < 0 a failure)
  integer(c_int), bind(c, name='c2d_cholmod_ok'), protected :: cholmod_ok                  !< success
  integer(c_int), bind(c, name='c2d_cholmod_not_posdef'), protected :: cholmod_not_posdef  !< matrix not positive definite
  integer(c_int), bind(c, name='c2d_cholmod_out_of_memory'), protected :: cholmod_out_of_memory  !< out of memory
  integer(c_int), bind(c, name='c2d_cholmod_too_large'), protected :: cholmod_too_large    !< integer overflow
  ! the C layer's codes (all <= -100)
  integer(c_int), bind(c, name='c2d_chol_no_handle'), protected :: c2d_chol_no_handle        !< handle not created
  integer(c_int), bind(c, name='c2d_chol_no_factor'), protected :: c2d_chol_no_factor        !< no valid numeric factor
  integer(c_int), bind(c, name='c2d_chol_not_super_ll'), protected :: c2d_chol_not_super_ll  !< L not supernodal LL'
  integer(c_int), bind(c, name='c2d_chol_block_moved'), protected :: c2d_chol_block_moved    !< last block not at the last pivots
  integer(c_int), bind(c, name='c2d_chol_bad_argument'), protected :: c2d_chol_bad_argument  !< inconsistent argument

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
      integer(c_int), value :: n, offset, nlast, ngroup
      integer(c_int), intent(in) :: colptr(*), rowind(*), last(*), group(*)
      integer(c_int) :: status
    end function c2d_chol_analyze

    !> Numeric factorization of the analyzed pattern's values; returns the status.
    function c2d_chol_factorize_values(handle, n, colptr, rowind, offset, val) &
        bind(c, name='c2d_chol_factorize_values') result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), value :: n, offset
      integer(c_int), intent(in) :: colptr(*), rowind(*)
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

    !> A name, NUL-terminated in buf(1:len): what = c2d_name_ordering, the
    !> ordering of the handle's factor; what = c2d_name_status, the name of
    !> the status code (handle unused).
    subroutine c2d_chol_name(handle, what, status, buf, len) bind(c, name='c2d_chol_name')
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: handle
      integer(c_int), value :: what, status
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value :: len
    end subroutine c2d_chol_name


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

    !> 1 when METIS orderings draw from a random sequence per thread (they
    !> may run side by side and give what each gives alone), 0 when METIS
    !> calls run one at a time instead.
    function c2d_metis_per_thread() bind(c, name='c2d_metis_per_thread') result(yes)
      import :: c_int
      integer(c_int) :: yes
    end function c2d_metis_per_thread

  end interface

end module cholmod_binding
