!> sparse_cholesky: sparse direct solution of K u = f for the symmetric
!> positive definite stiffness matrix K, by CHOLMOD's supernodal Cholesky
!> factorization
!>     P K P' = L L'                      (P a fill-reducing permutation)
!>     u = P' L'^-1 L^-1 P f              (forward and back substitution)
!>
!> Ordering.  By default P is METIS nested dissection followed by the
!> elimination-tree postorder; with `group` (analyze_pattern), METIS orders
!> the graph of the dof groups (the mesh nodes) and a group's dofs follow
!> one another.  With `last` (a set of dofs, e.g. the dofs of
!> a contact interface), P = [METIS order of the other dofs, last(:)] with no
!> postorder, so the block c = last occupies the last pivots of L.  Then, with
!> r the other dofs,
!>     L = [ L_rr  0    ]      K_cc - K_cr K_rr^-1 K_rc = L_cc L_cc'
!>         [ L_cr  L_cc ]      (K^-1)_cc = (L_cc L_cc')^-1
!> and trailing_factor_block returns L_cc: the Schur complement on the
!> interface, and the interface block of K^-1, come without any solve.  The
!> price is fill: the other dofs are ordered without the freedom to put the
!> block elsewhere (nnz(L) about 14 % above plain METIS for a 100 x 100 grid
!> with one edge last).
!>
!> Failure checks.  CHOLMOD reports "not positive definite" as a warning: the
!> call returns TRUE with Common->status = CHOLMOD_NOT_POSDEF and L->minor < n;
!> both are checked, and the failing pivot is mapped back to the dof of K.  A
!> singular K whose dependent pivot comes out tiny but positive through
!> rounding (a rigid-body mode; about half of the singular meshes tried) is
!> caught by the pivot ratio L(k,k)^2 / K(p_k,p_k), which is >= 1 / cond(K)
!> for an SPD matrix and of the order of the unit roundoff u for a dependent
!> column: K is reported singular when the ratio is below max(n, 1000) u.
!> Any other status != CHOLMOD_OK (out of memory, too large) is reported with
!> CHOLMOD's code name.
!>
!> Ownership.  A factor_t owns its CHOLMOD handle (common and factor, in C);
!> free_factor or the final procedure releases it.  Do not copy a factor_t by
!> assignment: both copies would hold the same handle.  The statistics stay
!> readable after free_factor.
!>
!> Programming interface
!>   type(factor_t)   opaque handle (private); ready, n, nlast, nnz_l, flops,
!>                    time_analyze, time_factorize, ordering, memory_peak,
!>                    min_pivot_ratio
!>   factorize(f, A, err [, last])          P A P' = L L' (the two halves below)
!>   analyze_pattern(f, n, colptr, rowind, err [, last] [, group] [, method])
!>                                          ordering (METIS or AMD) and symbolic analysis
!>   factorize_values(f, A, err)            numeric factorization of the analyzed pattern
!>   solve(f, b, x [, err])                 x = A^-1 b, b(n) or b(n, nrhs)
!>   solve_vector(f, b, x [, err])          the 1-D specific of solve
!>   solve_block(f, b, x [, err])           the 2-D specific of solve (one CHOLMOD call)
!>   solve_forward(f, b, y [, err])         y = L^-1 P b (the first half of solve)
!>   solve_backward(f, y, x [, err])        x = P' L'^-1 y (the second half)
!>   trailing_factor_block(f, nlast, Lcc [, err] [, first, count])
!>                                          dense L_cc after factorize(last=), or
!>                                          its diagonal sub-block first..first+count-1
!>   trailing_block_end(f, nlast, first, e [, err])  end of L_cc's diagonal block at first
!>   free_factor(f)                         release the handle
!>   factor_nnz(f), factor_flops(f), factor_memory(f), factor_ordering(f)
module sparse_cholesky
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_double, &
                                         c_int64_t, c_char, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  use kinds, only: dp, i8
  use omp_lib, only: omp_get_max_active_levels, omp_set_max_active_levels
  use diagnostics, only: error_t, set_error, int_to_str, fail_numerical
  use sparse_matrix, only: csc_t, csc_nnz, csc_check
  use cholmod_binding, only: c2d_chol_create, c2d_chol_destroy, c2d_chol_analyze, c2d_chol_factorize_values, &
                             c2d_chol_minor, c2d_chol_set_ordering, c2d_order_amd, &
                             c2d_chol_stats, c2d_chol_min_pivot_ratio, c2d_chol_ordering_name, &
                             c2d_chol_status_name, c2d_chol_solve, &
                             c2d_chol_trailing_range, c2d_chol_trailing_block_end, &
                             c2d_chol_solve_half, c2d_solve_whole, c2d_solve_forward, c2d_solve_backward, &
                             cholmod_ok, cholmod_not_posdef, c2d_chol_block_moved, &
                             c2d_chol_not_super_ll
  implicit none
  private
  public :: factor_t, factorize, analyze_pattern, factorize_values, solve, solve_vector, solve_block
  public :: trailing_factor_block, trailing_block_end, solve_forward, solve_backward
  public :: free_factor, factor_nnz, factor_flops, factor_memory, factor_ordering

  !> Floor of the order in the singularity tolerance (see singular_pivot_tolerance).
  integer, parameter :: tolerance_order_floor = 1000

  !> A Cholesky factor P A P' = L L' and its statistics.
  type :: factor_t
    type(c_ptr), private :: handle = c_null_ptr  !< owned CHOLMOD handle (common + L)
    logical :: ready = .false.            !< .true. when L is a valid numeric factor
    integer :: n = 0                      !< order of A
    integer :: nlast = 0                  !< size of the block ordered last (0: none)
    integer(i8) :: nnz_l = 0_i8           !< nnz(L), without zeros of supernodal amalgamation
    real(dp) :: flops = 0.0_dp            !< flop count of the numeric factorization
    real(dp) :: time_analyze = 0.0_dp     !< wall seconds: ordering and symbolic analysis
    real(dp) :: time_factorize = 0.0_dp   !< wall seconds: numeric factorization
    character(len=24) :: ordering = 'none' !< "metis" or "amd", "(nodes)" when grouped, "+last" with a block last
    integer(i8) :: memory_peak = 0_i8     !< peak memory of CHOLMOD, bytes
    real(dp) :: min_pivot_ratio = 0.0_dp  !< min over pivots of L(k,k)^2 / A(p_k,p_k)
  contains
    final :: finalize_factor
  end type factor_t

  !> x = A^-1 b for one right-hand side b(n) or a block b(n, nrhs).
  interface solve
    module procedure solve_vector, solve_block
  end interface solve

contains

  !> Factorize the symmetric positive definite A: P A P' = L L' (supernodal):
  !> analyze_pattern, then factorize_values.
  !>   f    (inout) the factor; any factor it held is freed first.  On success
  !>                f%ready = .true.; on failure f%ready = .false. and the
  !>                statistics of what was done are kept
  !>   A    (in)    symmetric matrix, upper triangle in CSC (sparse_matrix), n >= 1
  !>   err  (out)   allocated (status 1) when A is malformed, not positive
  !>                definite or singular to working precision, or CHOLMOD fails
  !>   last (in, optional) (nlast) distinct dofs 1..n to be ordered last, in
  !>                this order; the other dofs get a METIS ordering of their
  !>                submatrix.  Needed for trailing_factor_block
  subroutine factorize(f, A, err, last)
    type(factor_t), intent(inout) :: f
    type(csc_t), intent(in) :: A
    type(error_t), allocatable, intent(out) :: err
    integer, intent(in), optional :: last(:)
    call csc_check(A, err)
    if (allocated(err)) return
    call analyze_pattern(f, A%n, A%colptr, A%rowind, err, last)
    if (allocated(err)) return
    call factorize_values(f, A, err)
  end subroutine factorize

  !> The ordering and symbolic analysis of a pattern: the first half of
  !> factorize, which reads no values (they may be assembled meanwhile, in
  !> another thread: only colptr and rowind are read).
  !>   f      (inout) the factor; any factor it held is freed first
  !>   n      (in)    order, >= 1
  !>   colptr (in)    (n+1) column pointers of the upper triangle (1-based)
  !>   rowind (in)    row indices, sorted per column
  !>   err    (out)   allocated (status 1) on a bad pattern or `last`, or a CHOLMOD failure
  !>   last   (in, optional) as in factorize
  !>   group  (in, optional) (n) group of each dof, 1 <= group <= n (its mesh
  !>          node): METIS orders the graph of the groups, half the time of
  !>          the dof graph for two dofs per node, and a group's dofs stay together
  !>   method (in, optional) 'metis' (default: nested dissection) or 'amd'
  !>          (approximate minimum degree: cheaper to compute, more fill on
  !>          large meshes)
  subroutine analyze_pattern(f, n, colptr, rowind, err, last, group, method)
    type(factor_t), intent(inout) :: f
    integer, intent(in) :: n
    integer, intent(in) :: colptr(:), rowind(:)
    type(error_t), allocatable, intent(out) :: err
    integer, intent(in), optional :: last(:)
    integer, intent(in), optional :: group(:)
    character(len=*), intent(in), optional :: method
    integer(c_int), allocatable :: last_c(:), group_c(:)
    integer(c_int) :: status, nlast, ngroup
    integer :: levels

    call free_factor(f)
    f%n = 0
    f%nlast = 0
    f%nnz_l = 0_i8
    f%flops = 0.0_dp
    f%time_analyze = 0.0_dp
    f%time_factorize = 0.0_dp
    f%ordering = 'none'
    f%memory_peak = 0_i8
    f%min_pivot_ratio = 0.0_dp
    call check_pattern(n, colptr, rowind, err, last)
    if (allocated(err)) return

    nlast = 0
    if (present(last)) then
      nlast = int(size(last), c_int)
      last_c = int(last, c_int)
    else
      allocate(last_c(1))
      last_c = 0
    end if

    ngroup = 0
    if (present(group)) then
      if (size(group) /= n .or. any(group < 1) .or. any(group > n)) then
        call set_error(err, 'sparse Cholesky: `group` must give each of the ' // int_to_str(n) // &
                       ' dofs a group in 1..' // int_to_str(n), 1)
        return
      end if
      ngroup = int(n, c_int)
      group_c = int(group, c_int)
    else
      allocate(group_c(1))
      group_c = 0
    end if

    f%handle = c2d_chol_create()
    if (.not. c_associated(f%handle)) then
      call set_error(err, 'sparse Cholesky: CHOLMOD could not start (out of memory)', 1)
      return
    end if
    f%n = n
    f%nlast = int(nlast)
    status = cholmod_ok
    if (present(method)) then
      if (method == 'amd') then
        status = c2d_chol_set_ordering(f%handle, c2d_order_amd)
      else if (method /= 'metis') then
        call set_error(err, 'sparse Cholesky: unknown ordering "' // method // '" (expected metis or amd)', 1)
        return
      end if
    end if
    if (status == cholmod_ok) then
      levels = cholmod_serial_begin()
      status = c2d_chol_analyze(f%handle, int(n, c_int), colptr, rowind, nlast, last_c, ngroup, group_c)
      call cholmod_serial_end(levels)
    end if
    call read_statistics(f)

    select case (status)
    case (cholmod_ok)
      continue
    case (c2d_chol_block_moved)
      call set_error(err, 'sparse Cholesky: the analysis did not keep the ' // int_to_str(int(nlast)) &
                     // ' dofs given as `last` at the last pivots (' // status_name(status) // ')', 1)
    case default
      call set_error(err, 'sparse Cholesky analysis failed: ' // status_name(status) // ' (status ' &
                     // int_to_str(int(status)) // ') for a matrix of order ' // int_to_str(n) &
                     // ' with ' // int_to_str(colptr(n + 1) - 1) // ' stored entries', 1)
    end select
  end subroutine analyze_pattern

  !> The numeric factorization of A, whose pattern analyze_pattern analyzed:
  !> the second half of factorize.
  !>   f   (inout) the factor, analyzed; f%ready = .true. on success
  !>   A   (in)    the matrix with the analyzed pattern, finite values
  !>   err (out)   allocated (status 1) as in factorize
  subroutine factorize_values(f, A, err)
    type(factor_t), intent(inout) :: f
    type(csc_t), intent(in) :: A
    type(error_t), allocatable, intent(out) :: err
    integer(c_int) :: status, column, equation
    real(c_double) :: ratio
    integer :: j, p, levels

    if (.not. c_associated(f%handle) .or. f%n /= A%n) then
      call set_error(err, 'sparse Cholesky: factorize_values without the analysis of this pattern', 1)
      return
    end if
    do j = 1, A%n
      do p = A%colptr(j), A%colptr(j + 1) - 1
        if (.not. ieee_is_finite(A%val(p))) then
          call set_error(err, 'stiffness matrix has a non-finite entry at row ' // int_to_str(A%rowind(p)) &
                         // ', column ' // int_to_str(j), 1)
          return
        end if
      end do
    end do
    levels = cholmod_serial_begin()
    status = c2d_chol_factorize_values(f%handle, int(A%n, c_int), A%colptr, A%rowind, A%val)
    call cholmod_serial_end(levels)
    call read_statistics(f)

    select case (status)
    case (cholmod_ok)
      continue
    case (cholmod_not_posdef)
      call c2d_chol_minor(f%handle, column, equation)
      call set_error(err, singular_message(int(equation), int(column)), 1)
      return
    case default
      call set_error(err, 'sparse Cholesky factorization failed: ' // status_name(status) // ' (status ' &
                     // int_to_str(int(status)) // ') for a matrix of order ' // int_to_str(A%n) &
                     // ' with ' // int_to_str(csc_nnz(A)) // ' stored entries', 1)
      return
    end select

    ! a dependent column whose pivot came out tiny but positive through rounding
    call c2d_chol_min_pivot_ratio(f%handle, ratio, column, equation)
    f%min_pivot_ratio = real(ratio, dp)
    if (ieee_is_nan(ratio)) then
      call set_error(err, 'sparse Cholesky: non-finite pivot at equation ' // int_to_str(int(equation)) &
                     // ' (column ' // int_to_str(int(column)) // ' of the permuted matrix): overflow in the factor', 1)
      return
    end if
    if (ratio < singular_pivot_tolerance(A%n)) then
      call set_error(err, singular_message(int(equation), int(column)), 1)
      return
    end if
    f%ready = .true.
  end subroutine factorize_values

  !> CHOLMOD's OpenMP loops ask for 4 threads (CHOLMOD_OMP_NUM_THREADS, set
  !> when the library was built), whatever OMP_NUM_THREADS says.  On 2 cores
  !> those teams of 4 cost 13-20 % of the numeric factorization (hertz_1e5 and
  !> hertz_1e6 of bench/contact.sh, the same factor to the bit).  With
  !> max-active-levels 0 every parallel region opened inside a CHOLMOD call runs
  !> on the calling thread; the BLAS inside the supernodal factorization keeps
  !> its own threads.  Returns the setting to give back to cholmod_serial_end.
  integer function cholmod_serial_begin() result(levels)
    levels = omp_get_max_active_levels()
    call omp_set_max_active_levels(0)
  end function cholmod_serial_begin

  subroutine cholmod_serial_end(levels)
    integer, intent(in) :: levels
    call omp_set_max_active_levels(levels)
  end subroutine cholmod_serial_end

  !> Statistics of the handle into f (after each half of the factorization).
  subroutine read_statistics(f)
    type(factor_t), intent(inout) :: f
    integer(c_int64_t) :: lnz, memory_peak
    real(c_double) :: flops, time_analyze, time_factorize
    character(kind=c_char) :: buf(32)
    call c2d_chol_stats(f%handle, lnz, flops, memory_peak, time_analyze, time_factorize)
    f%nnz_l = int(lnz, i8)
    f%flops = real(flops, dp)
    f%memory_peak = int(memory_peak, i8)
    f%time_analyze = real(time_analyze, dp)
    f%time_factorize = real(time_factorize, dp)
    call c2d_chol_ordering_name(f%handle, buf, int(size(buf), c_int))
    f%ordering = c_string(buf)
  end subroutine read_statistics

  !> Checks of a pattern and `last` before CHOLMOD sees them.
  subroutine check_pattern(n, colptr, rowind, err, last)
    integer, intent(in) :: n
    integer, intent(in) :: colptr(:), rowind(:)
    type(error_t), allocatable, intent(out) :: err
    integer, intent(in), optional :: last(:)
    logical, allocatable :: seen(:)
    integer :: j, k

    if (n < 1) then
      call set_error(err, 'sparse Cholesky: empty matrix (order 0)', 1)
      return
    end if
    if (size(colptr) /= n + 1) then
      call set_error(err, 'sparse Cholesky: ' // int_to_str(size(colptr)) // ' column pointers for order ' // &
                     int_to_str(n), 1)
      return
    end if
    do j = 1, n
      if (colptr(j) < 1 .or. colptr(j + 1) < colptr(j) .or. colptr(j + 1) - 1 > size(rowind)) then
        call set_error(err, 'sparse Cholesky: bad column pointers at column ' // int_to_str(j), 1)
        return
      end if
    end do
    if (.not. present(last)) return
    allocate(seen(n))
    seen = .false.
    do k = 1, size(last)
      if (last(k) < 1 .or. last(k) > n) then
        call set_error(err, 'sparse Cholesky: dof ' // int_to_str(last(k)) // ' in `last` is out of range 1..' &
                       // int_to_str(n), 1)
        return
      end if
      if (seen(last(k))) then
        call set_error(err, 'sparse Cholesky: dof ' // int_to_str(last(k)) // ' appears twice in `last`', 1)
        return
      end if
      seen(last(k)) = .true.
    end do
  end subroutine check_pattern

  !> Tolerance on the pivot ratio L(k,k)^2 / A(p_k,p_k) below which A is
  !> singular to working precision: max(n, 1000) u, u the unit roundoff (the
  !> n u of LAPACK's DPSTRF, relative here to each dof's own diagonal).  For an
  !> SPD matrix the ratio is >= 1 / cond(A); for a dependent column it is the
  !> rounding left of a zero pivot, a few 1e-14 to 1e-13 on meshes of 1e4 to
  !> 1e5 dofs.
  !>   n (in) order of A
  pure real(dp) function singular_pivot_tolerance(n)
    integer, intent(in) :: n
    singular_pivot_tolerance = real(max(n, tolerance_order_floor), dp) * epsilon(1.0_dp)
  end function singular_pivot_tolerance

  !> The diagnostic for a singular or indefinite matrix.
  pure function singular_message(equation, column) result(msg)
    integer, intent(in) :: equation, column
    character(len=:), allocatable :: msg
    msg = 'stiffness matrix is singular or not positive definite at equation ' // int_to_str(equation) &
          // ' (column ' // int_to_str(column) // ' of the permuted matrix is dependent: a rigid-body mode' &
          // ' not held by FIX or contact)'
  end function singular_message

  !> x = A^-1 b for one right-hand side.
  !>   f   (in)  a factor with f%ready
  !>   b   (in)  (n) right-hand side
  !>   x   (out) (n) solution
  !>   err (out, optional) allocated on failure; when absent a failure stops
  !>       the program through fail_numerical (exit status 1)
  subroutine solve_vector(f, b, x, err)
    type(factor_t), intent(in) :: f
    real(dp), intent(in) :: b(:)
    real(dp), intent(out) :: x(:)
    type(error_t), allocatable, intent(out), optional :: err
    call solve_half(f, c2d_solve_whole, b, x, err)
  end subroutine solve_vector

  !> X = A^-1 B for a block of right-hand sides, in one CHOLMOD solve.
  !>   f   (in)  a factor with f%ready
  !>   b   (in)  (n, nrhs) right-hand sides, nrhs >= 0
  !>   x   (out) (n, nrhs) solutions
  !>   err (out, optional) as for solve_vector
  subroutine solve_block(f, b, x, err)
    type(factor_t), intent(in) :: f
    real(dp), intent(in) :: b(:,:)
    real(dp), intent(out) :: x(:,:)
    type(error_t), allocatable, intent(out), optional :: err
    character(len=:), allocatable :: msg
    integer(c_int) :: status
    integer :: levels

    if (.not. f%ready) then
      msg = 'sparse Cholesky solve: no valid factor (factorize failed or was not called)'
    else if (size(b, 1) /= f%n .or. size(x, 1) /= f%n .or. size(x, 2) /= size(b, 2)) then
      msg = 'sparse Cholesky solve: blocks of ' // int_to_str(size(b, 1)) // ' and ' // int_to_str(size(x, 1)) &
            // ' rows (' // int_to_str(size(b, 2)) // ' and ' // int_to_str(size(x, 2)) &
            // ' columns) for a factor of order ' // int_to_str(f%n)
    else
      if (size(b, 2) == 0) return
      levels = cholmod_serial_begin()
      status = c2d_chol_solve(f%handle, int(f%n, c_int), int(size(b, 2), c_int), b, x)
      call cholmod_serial_end(levels)
      if (status == cholmod_ok) return
      msg = 'sparse Cholesky solve failed: ' // status_name(status) // ' (status ' // int_to_str(int(status)) // ')'
    end if
    call report(msg, err)
  end subroutine solve_block

  !> y = L^-1 P b, the forward half of a solve.  With `last`, y(n-nlast+1:)
  !> belongs to the trailing block: L^-1 P maps a vector that is zero off the
  !> `last` dofs to [0; L_cc^-1 v], and the backward half ends with
  !> x(last) = L_cc'^-1 y(n-nlast+1:).
  !>   f (in) a factor with f%ready; b (in) (n); y (out) (n); err as for solve_vector
  subroutine solve_forward(f, b, y, err)
    type(factor_t), intent(in) :: f
    real(dp), intent(in) :: b(:)
    real(dp), intent(out) :: y(:)
    type(error_t), allocatable, intent(out), optional :: err
    call solve_half(f, c2d_solve_forward, b, y, err)
  end subroutine solve_forward

  !> x = P' L'^-1 y, the backward half: solve_backward(solve_forward(b)) = A^-1 b.
  !>   f (in) a factor with f%ready; y (in) (n); x (out) (n); err as for solve_vector
  subroutine solve_backward(f, y, x, err)
    type(factor_t), intent(in) :: f
    real(dp), intent(in) :: y(:)
    real(dp), intent(out) :: x(:)
    type(error_t), allocatable, intent(out), optional :: err
    call solve_half(f, c2d_solve_backward, y, x, err)
  end subroutine solve_backward

  !> x = the solve or one of its halves (half: c2d_solve_*) for one vector.
  subroutine solve_half(f, half, b, x, err)
    type(factor_t), intent(in) :: f
    integer(c_int), intent(in) :: half
    real(dp), intent(in) :: b(:)
    real(dp), intent(out) :: x(:)
    type(error_t), allocatable, intent(out), optional :: err
    character(len=:), allocatable :: msg
    integer(c_int) :: status
    integer :: levels

    if (.not. f%ready) then
      msg = 'sparse Cholesky solve: no valid factor (factorize failed or was not called)'
    else if (size(b) /= f%n .or. size(x) /= f%n) then
      msg = 'sparse Cholesky solve: vectors of size ' // int_to_str(size(b)) // ' and ' // int_to_str(size(x)) &
            // ' for a factor of order ' // int_to_str(f%n)
    else
      levels = cholmod_serial_begin()
      status = c2d_chol_solve_half(f%handle, half, int(f%n, c_int), 1_c_int, b, x)
      call cholmod_serial_end(levels)
      if (status == cholmod_ok) return
      msg = 'sparse Cholesky solve failed: ' // status_name(status) // ' (status ' // int_to_str(int(status)) // ')'
    end if
    call report(msg, err)
  end subroutine solve_half

  !> The trailing block L_cc of L, for a factor computed with `last`: rows and
  !> columns of the last nlast pivots, in the order of `last`, so that
  !>     (A^-1)(last, last) = (L_cc L_cc')^-1,  L_cc L_cc' = Schur complement on last.
  !>   f     (in)  a factor from factorize(f, A, err, last) with f%ready
  !>   nlast (in)  size(last) given to factorize
  !>   Lcc   (out) (nlast, nlast) lower triangular, zero above the diagonal
  !>   err   (out, optional) allocated when f has no such block (no `last`,
  !>         another nlast, factor not supernodal LL', block not at the end);
  !>         when absent a failure stops the program through fail_numerical
  subroutine trailing_factor_block(f, nlast, Lcc, err, first, count)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: nlast
    real(dp), allocatable, intent(out) :: Lcc(:,:)
    type(error_t), allocatable, intent(out), optional :: err
    integer, intent(in), optional :: first, count
    character(len=:), allocatable :: msg
    integer(c_int) :: status
    integer :: k1, m

    k1 = 1
    m = nlast
    if (present(first)) k1 = first
    if (present(count)) m = count
    msg = trailing_check(f, nlast)
    if (len(msg) == 0) then
      allocate(Lcc(max(m, 0), max(m, 0)))
      status = c2d_chol_trailing_range(f%handle, int(nlast, c_int), int(k1, c_int), int(m, c_int), Lcc)
      if (status == cholmod_ok) return
      deallocate(Lcc)
      msg = trailing_status_message(status)
    end if
    call report(msg, err)
  end subroutine trailing_factor_block

  !> The last row e of the diagonal block of L_cc that starts at row and
  !> column `first`: L_cc(e+1:, first:e) = 0 (K couples no two bodies: one
  !> block per body).  f, nlast and err as for trailing_factor_block.
  subroutine trailing_block_end(f, nlast, first, e, err)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: nlast, first
    integer, intent(out) :: e
    type(error_t), allocatable, intent(out), optional :: err
    character(len=:), allocatable :: msg
    integer(c_int) :: status, last_row

    e = first
    msg = trailing_check(f, nlast)
    if (len(msg) == 0) then
      status = c2d_chol_trailing_block_end(f%handle, int(nlast, c_int), int(first, c_int), last_row)
      e = int(last_row)
      if (status == cholmod_ok) return
      msg = trailing_status_message(status)
    end if
    call report(msg, err)
  end subroutine trailing_block_end

  !> '' when f can have a trailing block of nlast dofs, else why not.
  function trailing_check(f, nlast) result(msg)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: nlast
    character(len=:), allocatable :: msg
    msg = ''
    if (.not. f%ready) then
      msg = 'trailing factor block: no valid factor (factorize failed or was not called)'
    else if (f%nlast == 0) then
      msg = 'trailing factor block: the factor was computed without `last`'
    else if (nlast /= f%nlast) then
      msg = 'trailing factor block: ' // int_to_str(nlast) // ' dofs asked, the factor has ' &
            // int_to_str(f%nlast) // ' ordered last'
    end if
  end function trailing_check

  function trailing_status_message(status) result(msg)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: msg
    if (status == c2d_chol_not_super_ll) then
      msg = 'trailing factor block: the factor is not stored as supernodal LL'' (LDL'' or simplicial)'
    else if (status == c2d_chol_block_moved) then
      msg = 'trailing factor block: the `last` dofs are not the last pivots of the factor'
    else
      msg = 'trailing factor block: ' // status_name(status) // ' (status ' // int_to_str(int(status)) // ')'
    end if
  end function trailing_status_message


  !> Release the CHOLMOD handle of f (no-op when it holds none); the
  !> statistics are kept.
  !>   f (inout) the factor; on return f%ready = .false.
  subroutine free_factor(f)
    type(factor_t), intent(inout) :: f
    if (c_associated(f%handle)) call c2d_chol_destroy(f%handle)
    f%handle = c_null_ptr
    f%ready = .false.
  end subroutine free_factor

  !> Final procedure: a factor going out of scope releases its handle.
  subroutine finalize_factor(f)
    type(factor_t), intent(inout) :: f
    call free_factor(f)
  end subroutine finalize_factor

  !> nnz(L) of the last factorization (without amalgamation zeros).
  pure integer(i8) function factor_nnz(f)
    type(factor_t), intent(in) :: f
    factor_nnz = f%nnz_l
  end function factor_nnz

  !> Flop count of the last numeric factorization.
  pure real(dp) function factor_flops(f)
    type(factor_t), intent(in) :: f
    factor_flops = f%flops
  end function factor_flops

  !> Peak memory used by CHOLMOD for this factor, bytes.
  pure integer(i8) function factor_memory(f)
    type(factor_t), intent(in) :: f
    factor_memory = f%memory_peak
  end function factor_memory

  !> Name of the ordering used: "metis" or "amd", with "(nodes)" when the
  !> node graph was ordered and "+last" with a block last (e.g.
  !> "amd(nodes)+last"), or the name of CHOLMOD's own choice.
  pure function factor_ordering(f) result(name)
    type(factor_t), intent(in) :: f
    character(len=:), allocatable :: name
    name = trim(f%ordering)
  end function factor_ordering

  !> Hand msg to err when present, else stop with exit status 1.
  subroutine report(msg, err)
    character(len=*), intent(in) :: msg
    type(error_t), allocatable, intent(out), optional :: err
    if (present(err)) then
      call set_error(err, msg, 1)
    else
      call fail_numerical(msg)
    end if
  end subroutine report

  !> Name of a CHOLMOD or shim status code.
  function status_name(status) result(name)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: name
    character(kind=c_char) :: buf(32)
    call c2d_chol_status_name(status, buf, int(size(buf), c_int))
    name = c_string(buf)
  end function status_name

  !> Fortran string of a NUL-terminated c_char array.
  pure function c_string(buf) result(s)
    character(kind=c_char), intent(in) :: buf(:)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(buf)
      if (buf(k) == c_null_char) exit
      s = s // buf(k)
    end do
  end function c_string

end module sparse_cholesky
