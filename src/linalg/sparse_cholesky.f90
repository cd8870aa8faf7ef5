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
!> block elsewhere (doc/performance.md, "The Delassus matrix from the trailing
!> block of the factor").
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
!> Independent blocks.  When no entry of A couples dofs 1..s to dofs s+1..n
!> (bodies meshed each on its own, numbered one after the other: K has a
!> diagonal block per body), A is cut there into parts, each ordered and
!> factorized by its own CHOLMOD handle, the parts side by side on the OpenMP
!> threads (largest first), each with a BLAS of one thread, when the second
!> largest has side_by_side_min dofs or more.  Blocks smaller than
!> n / max_parts are merged with the next.  The caller sees one factor:
!> the pivots are [the other dofs of part 1, of part 2, ..., last(:)], so
!> that with `last` the trailing block is still L_cc, block diagonal by part,
!> in the order of `last`; `last` must then visit the parts in order (the
!> dofs of a contact interface, ascending, do), else A is kept whole.
!>
!> No part is cut further: a body cut at its top separator into two halves
!> factorized side by side, with a dense Schur complement on the separator,
!> gained wall time on two free cores and cost CPU time and 4-15 % peak
!> memory (doc/performance.md, "A body cut in two: removed").
!>
!> Errors are data: every routine returns an error_t (err) and none stops
!> the process; a singular or indefinite K gives err%equation, the dof of A
!> at the failing pivot, for the caller to locate in its mesh.
!>
!> Files.  This module (the factor, its analysis and numeric factorization),
!> sparse_cholesky_solve (a submodule: the solves and L_cc), and
!> sparse_cholesky_parts (the parts, their loops, checks and messages);
!> only these use cholmod_binding.
!>
!> Ownership.  A factor_t owns its CHOLMOD handles (common and factor, in C);
!> free_factor or the final procedure releases them.  Do not copy a factor_t by
!> assignment: both copies would hold the same handle.  The statistics stay
!> readable after free_factor.
!>
!> Programming interface
!>   type(factor_t)   opaque handles (private); ready, n, nlast, nparts, side_by_side, nnz_l,
!>                    flops, time_analyze, time_factorize, ordering,
!>                    memory_peak, min_pivot_ratio
!>   factorize(f, A, err [, last])          P A P' = L L' (the two halves below)
!>   analyze_pattern(f, n, colptr, rowind, err [, last] [, group] [, method])
!>                                          ordering (METIS or AMD) and symbolic analysis
!>   factorize_values(f, A, err)            numeric factorization of the analyzed pattern
!>   solve(f, b, x [, err])                 x = A^-1 b, b(n) or b(n, nrhs)
!>   solve_vector(f, b, x [, err])          the 1-D specific of solve
!>   solve_block(f, b, x [, err])           the 2-D specific of solve (one CHOLMOD call per part)
!>   solve_forward(f, b, y [, err])         y = L^-1 P b (the first half of solve)
!>   solve_backward(f, y, x [, err])        x = P' L'^-1 y (the second half)
!>   trailing_factor_block(f, nlast, Lcc [, err] [, first, count])
!>                                          dense L_cc after factorize(last=), or
!>                                          its diagonal sub-block first..first+count-1
!>   trailing_block_end(f, nlast, first, e [, err])  end of L_cc's diagonal block at first
!>   free_factor(f)                         release the handles
!>   factor_nnz(f), factor_flops(f), factor_memory(f), factor_ordering(f)
module sparse_cholesky
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_double, &
                                         c_int64_t, c_char, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  use kinds, only: dp, i8
  use omp_lib, only: omp_get_wtime
  use strings, only: int_to_str, i8_to_str
  use errors, only: error_t, set_error, set_out_of_memory, error_numerical
  use sparse_matrix, only: csc_t, csc_nnz, csc_check
  use cholmod_binding, only: c2d_chol_create, c2d_chol_destroy, c2d_chol_analyze, c2d_chol_factorize_values, &
                             c2d_chol_set_ordering, c2d_order_amd, c2d_order_metis, &
                             c2d_chol_stats, c2d_chol_name, c2d_name_ordering, c2d_chol_minor, c2d_chol_min_pivot_ratio, &
                             c2d_solve_whole, c2d_solve_forward, &
                             c2d_solve_backward, cholmod_ok, cholmod_not_posdef, c2d_chol_block_moved, &
                             c2d_chol_bad_argument, cholmod_out_of_memory
  use runtime_binding, only: c2d_memory_available, c2d_malloc_trim
  use sparse_cholesky_parts, only: part_t, max_parts, find_parts, local_groups, part_solve, part_trailing_range, &
                                   part_block_end, global_equation, global_pivot, &
                                   check_pattern, singular_pivot_tolerance, singular_message, ordering_bytes, &
                                   largest, parts_begin, parts_end, &
                                   status_name, trailing_status_message, c_string
  implicit none
  private
  public :: factor_t, factorize, analyze_pattern, factorize_values, solve, solve_vector, solve_block
  public :: trailing_factor_block, trailing_block_end, solve_forward, solve_backward
  public :: free_factor, factor_nnz, factor_flops, factor_memory, factor_ordering

  !> A Cholesky factor P A P' = L L' and its statistics.
  type :: factor_t
    type(part_t), allocatable, private :: part(:)  !< the parts of A (one when A does not split)
    logical :: ready = .false.            !< .true. when L is a valid numeric factor
    integer :: n = 0                      !< order of A
    integer :: nlast = 0                  !< size of the block ordered last (0: none)
    integer :: nparts = 0                 !< number of parts, each factorized on its own
    integer :: side_by_side = 1           !< threads the parts run on (1: one after the other)
    integer(i8) :: nnz_l = 0_i8           !< nnz(L), without zeros of supernodal amalgamation
    real(dp) :: flops = 0.0_dp            !< flop count of the numeric factorization
    real(dp) :: time_analyze = 0.0_dp     !< wall seconds: ordering and symbolic analysis
    real(dp) :: time_factorize = 0.0_dp   !< wall seconds: numeric factorization
    character(len=24) :: ordering = 'none' !< "metis" or "amd", "(nodes)" when grouped, "+last" with a block last
    integer(i8) :: memory_peak = 0_i8     !< peak memory of CHOLMOD, bytes
    real(dp) :: min_pivot_ratio = 0.0_dp  !< min over pivots of L(k,k)^2 / A(p_k,p_k)
    !> an analysis has freed its workspace since the last numeric
    !> factorization (what it freed goes back to the system before the next)
    logical, private :: analyzed_since = .false.
  contains
    final :: finalize_factor
  end type factor_t

  !> x = A^-1 b for one right-hand side b(n) or a block b(n, nrhs).
  interface solve
    module procedure solve_vector, solve_block
  end interface solve

  !> The solves and the trailing block, in submodule sparse_cholesky_solve
  !> (src/linalg/sparse_cholesky_solve.f90); documented there.
  interface
    module subroutine solve_vector(f, b, x, err)
      type(factor_t), intent(in) :: f
      real(dp), intent(in) :: b(:)
      real(dp), intent(out) :: x(:)
      type(error_t), allocatable, intent(out) :: err
    end subroutine solve_vector

    module subroutine solve_block(f, b, x, err)
      type(factor_t), intent(in) :: f
      real(dp), intent(in) :: b(:,:)
      real(dp), intent(out) :: x(:,:)
      type(error_t), allocatable, intent(out) :: err
    end subroutine solve_block

    module subroutine solve_forward(f, b, y, err)
      type(factor_t), intent(in) :: f
      real(dp), intent(in) :: b(:)
      real(dp), intent(out) :: y(:)
      type(error_t), allocatable, intent(out) :: err
    end subroutine solve_forward

    module subroutine solve_backward(f, y, x, err)
      type(factor_t), intent(in) :: f
      real(dp), intent(in) :: y(:)
      real(dp), intent(out) :: x(:)
      type(error_t), allocatable, intent(out) :: err
    end subroutine solve_backward

    module subroutine trailing_factor_block(f, nlast, Lcc, err, first, count)
      type(factor_t), intent(in) :: f
      integer, intent(in) :: nlast
      real(dp), allocatable, intent(out) :: Lcc(:,:)
      type(error_t), allocatable, intent(out) :: err
      integer, intent(in), optional :: first, count
    end subroutine trailing_factor_block

    module subroutine trailing_block_end(f, nlast, first, e, err)
      type(factor_t), intent(in) :: f
      integer, intent(in) :: nlast, first
      integer, intent(out) :: e
      type(error_t), allocatable, intent(out) :: err
    end subroutine trailing_block_end
  end interface

contains

  !> Factorize the symmetric positive definite A: P A P' = L L' (supernodal):
  !> analyze_pattern, then factorize_values.
  !>   f    (inout) the factor; any factor it held is freed first.  On success
  !>                f%ready = .true.; on failure f%ready = .false. and the
  !>                statistics of what was done are kept
  !>   A    (in)    symmetric matrix, upper triangle in CSC (sparse_matrix), n >= 1
  !>   err  (out)   allocated (error_numerical) when A is malformed, not positive
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
  !>   err    (out)   allocated (error_numerical) on a bad pattern or `last`, or a CHOLMOD failure
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
    integer(c_int) :: ordering
    logical :: grouped
    integer :: i, p, nthreads, levels, blas
    type(part_t), allocatable :: parts(:)
    real(dp) :: t0

    call free_factor(f)
    f%n = 0
    f%nlast = 0
    f%nparts = 0
    f%nnz_l = 0_i8
    f%flops = 0.0_dp
    f%time_analyze = 0.0_dp
    f%time_factorize = 0.0_dp
    f%ordering = 'none'
    f%memory_peak = 0_i8
    f%min_pivot_ratio = 0.0_dp
    call check_pattern(n, colptr, rowind, err, last)
    if (allocated(err)) return

    if (present(last)) then
      last_c = int(last, c_int)
    else
      allocate(last_c(0))
    end if

    grouped = present(group)
    allocate(group_c(n))
    group_c = 0
    if (grouped) then
      if (size(group) /= n .or. any(group < 1) .or. any(group > n)) then
        call set_error(err, 'sparse Cholesky: `group` must give each of the ' // int_to_str(n) // &
                       ' dofs a group in 1..' // int_to_str(n), error_numerical)
        return
      end if
    end if

    ordering = c2d_order_metis
    if (present(method)) then
      if (method == 'amd') then
        ordering = c2d_order_amd
      else if (method /= 'metis') then
        call set_error(err, 'sparse Cholesky: unknown ordering "' // method // '" (expected metis or amd)', error_numerical)
        return
      end if
    end if

    call find_parts(n, colptr, rowind, last_c, parts)
    ! each part's `last` and groups in its own numbering
    do p = 1, size(parts)
      associate (pt => parts(p))
        last_c(pt%last0 + 1:pt%last0 + pt%nlast) = last_c(pt%last0 + 1:pt%last0 + pt%nlast) - (pt%first - 1)
        if (grouped) call local_groups(group(pt%first:pt%first + pt%n - 1), group_c(pt%first:pt%first + pt%n - 1))
      end associate
    end do
    call move_alloc(parts, f%part)
    f%n = n
    f%nlast = size(last_c)
    f%nparts = size(f%part)
    do p = 1, f%nparts
      f%part(p)%handle = c2d_chol_create()
      if (.not. c_associated(f%part(p)%handle)) then
        call set_error(err, 'sparse Cholesky: CHOLMOD could not start (out of memory)', error_numerical)
        return
      end if
      f%part(p)%status = c2d_chol_set_ordering(f%part(p)%handle, ordering)
    end do

    t0 = omp_get_wtime()
    call parts_begin(f%part, nthreads, levels, blas)
    f%side_by_side = nthreads
    ! A METIS ordering splits its first level into two OpenMP tasks, which the
    ! other threads of the team take when they are free: the parts' team, or,
    ! one part after the other, the caller's (no team of one is opened then)
    if (nthreads > 1) then
      !$omp parallel do num_threads(nthreads) schedule(dynamic, 1)
      do i = 1, f%nparts
        call analyze_part(f%part(largest(f%part, i)))
      end do
      !$omp end parallel do
    else
      do i = 1, f%nparts
        call analyze_part(f%part(largest(f%part, i)))
      end do
    end if
    call parts_end(levels, blas)
    f%time_analyze = omp_get_wtime() - t0
    f%analyzed_since = .true.
    call read_statistics(f)

    do p = 1, f%nparts
      ! the codes are the C layer's variables, not constants: no select case
      if (f%part(p)%status == cholmod_ok) cycle
      if (f%part(p)%status == c2d_chol_block_moved) then
        call set_error(err, 'sparse Cholesky: the analysis did not keep the ' // int_to_str(f%nlast) &
                       // ' dofs given as `last` at the last pivots (' // status_name(f%part(p)%status) // ')', error_numerical)
        return
      else if (f%part(p)%status == cholmod_out_of_memory) then
        ! the ordering's graphs and CHOLMOD's symbolic workspace: a few
        ! integers per stored entry and per dof (an order of magnitude)
        call set_out_of_memory(err, 'ordering K (' // int_to_str(n) // ' dofs, ' // &
                               trim(merge('AMD  ', 'METIS', ordering == c2d_order_amd)) // ')', &
                               ordering_bytes(n, int(colptr(n + 1) - 1, i8)))
        return
      else
        call set_error(err, 'sparse Cholesky analysis failed: ' // status_name(f%part(p)%status) // ' (status ' &
                       // int_to_str(int(f%part(p)%status)) // ') for a matrix of order ' // int_to_str(n) &
                       // ' with ' // int_to_str(colptr(n + 1) - 1) // ' stored entries', error_numerical)
        return
      end if
    end do

  contains

    subroutine analyze_part(pt)
      type(part_t), intent(inout) :: pt
      if (pt%status == cholmod_ok) &
        pt%status = c2d_chol_analyze(pt%handle, int(pt%n, c_int), colptr(pt%first:pt%first + pt%n), &
                                     rowind(colptr(pt%first):), int(pt%first - 1, c_int), &
                                     int(pt%nlast, c_int), last_c(pt%last0 + 1:), &
                                     merge(int(pt%n, c_int), 0_c_int, grouped), group_c(pt%first:))
    end subroutine analyze_part
  end subroutine analyze_pattern

  !> The numeric factorization of A, whose pattern analyze_pattern analyzed:
  !> the second half of factorize.
  !>   f   (inout) the factor, analyzed; f%ready = .true. on success
  !>   A   (in)    the matrix with the analyzed pattern, finite values
  !>   err (out)   allocated (error_numerical) as in factorize
  subroutine factorize_values(f, A, err)
    type(factor_t), intent(inout) :: f
    type(csc_t), intent(in) :: A
    type(error_t), allocatable, intent(out) :: err
    integer(c_int) :: column, equation
    real(c_double) :: ratio
    integer :: i, j, p, nthreads, levels, blas, worst
    real(dp) :: t0, worst_ratio
    logical :: analyzed

    ! a factorization that met a pivot that is not positive leaves the
    ! analysis as it was: the next values are factorized on it
    analyzed = allocated(f%part) .and. f%n == A%n
    if (analyzed) analyzed = all(f%part%status == cholmod_ok .or. f%part%status == cholmod_not_posdef)
    if (.not. analyzed) then
      call set_error(err, 'sparse Cholesky: factorize_values without the analysis of this pattern', error_numerical)
      return
    end if
    do j = 1, A%n
      do p = A%colptr(j), A%colptr(j + 1) - 1
        if (.not. ieee_is_finite(A%val(p))) then
          call set_error(err, 'stiffness matrix has a non-finite entry at row ' // int_to_str(A%rowind(p)) &
                         // ', column ' // int_to_str(j), error_numerical)
          return
        end if
      end do
    end do
    ! The factor's size is known from the analysis: a factor that cannot fit
    ! is said before the numeric factorization starts taking the memory
    if (c2d_memory_available() >= 0 .and. factor_bytes(f) > c2d_memory_available()) then
      call set_out_of_memory(err, 'factorizing K (nnz(L) = ' // i8_to_str(f%nnz_l) // ' from the analysis; ' // &
                             i8_to_str(max(0_i8, int(c2d_memory_available(), i8)) / 1048576_i8) // &
                             ' MB available)', factor_bytes(f))
      return
    end if
    ! what the orderings freed goes back before the factors take their memory;
    ! a refactorization on the same analysis (Newton's tangents) keeps the
    ! free pages its last iterate used: returned, every iterate would fault
    ! them in again (hundreds of page faults per iterate)
    if (f%analyzed_since) call c2d_malloc_trim()
    f%analyzed_since = .false.
    t0 = omp_get_wtime()
    call parts_begin(f%part, nthreads, levels, blas)
    !$omp parallel do num_threads(nthreads) schedule(dynamic, 1) if (nthreads > 1)
    do i = 1, f%nparts
      associate (pt => f%part(largest(f%part, i)))
        pt%status = c2d_chol_factorize_values(pt%handle, int(pt%n, c_int), A%colptr(pt%first:pt%first + pt%n), &
                                              A%rowind(A%colptr(pt%first):), int(pt%first - 1, c_int), &
                                              A%val(A%colptr(pt%first):))
      end associate
    end do
    !$omp end parallel do
    call parts_end(levels, blas)
    call read_statistics(f)
    f%time_factorize = omp_get_wtime() - t0

    do p = 1, f%nparts
      if (f%part(p)%status == cholmod_ok) cycle
      if (f%part(p)%status == cholmod_not_posdef) then
        call c2d_chol_minor(f%part(p)%handle, column, equation)
        call set_singular(err, f, f%part(p), column, equation)
        return
      else if (f%part(p)%status == cholmod_out_of_memory) then
        call set_out_of_memory(err, 'factorizing K (nnz(L) = ' // i8_to_str(f%nnz_l) // ')', factor_bytes(f))
        return
      else
        call set_error(err, 'sparse Cholesky factorization failed: ' // status_name(f%part(p)%status) // &
                       ' (status ' // int_to_str(int(f%part(p)%status)) // ') for a matrix of order ' // &
                       int_to_str(A%n) // ' with ' // int_to_str(csc_nnz(A)) // ' stored entries', error_numerical)
        return
      end if
    end do

    ! a dependent column whose pivot came out tiny but positive through rounding
    worst = 1
    worst_ratio = huge(1.0_dp)
    do p = 1, f%nparts
      call c2d_chol_min_pivot_ratio(f%part(p)%handle, ratio, column, equation)
      if (ieee_is_nan(ratio)) then
        call set_error(err, 'sparse Cholesky: non-finite pivot at equation ' // &
                       int_to_str(global_equation(f%part(p), equation)) // ' (column ' // &
                       int_to_str(global_pivot(f%n, f%nlast, f%part(p), column)) // &
                       ' of the permuted matrix): overflow in the factor', error_numerical)
        err%equation = global_equation(f%part(p), equation)
        f%min_pivot_ratio = real(ratio, dp)
        return
      end if
      if (real(ratio, dp) < worst_ratio) then
        worst = p
        worst_ratio = real(ratio, dp)
      end if
    end do
    f%min_pivot_ratio = worst_ratio
    if (worst_ratio < singular_pivot_tolerance(A%n)) then
      call c2d_chol_min_pivot_ratio(f%part(worst)%handle, ratio, column, equation)
      call set_singular(err, f, f%part(worst), column, equation)
      return
    end if
    f%ready = .true.
  end subroutine factorize_values

  !> err = the diagnosis of a matrix singular or not positive definite at a
  !> part's pivot, with the equation (the dof of A) as a field.
  !>   err      (out) status 1, err%equation the dof of A
  !>   f        (in)  the factor
  !>   pt       (in)  the part where it failed
  !>   column, equation (in) the pivot and dof in the part's own numbering
  subroutine set_singular(err, f, pt, column, equation)
    type(error_t), allocatable, intent(out) :: err
    type(factor_t), intent(in) :: f
    type(part_t), intent(in) :: pt
    integer(c_int), intent(in) :: column, equation
    call set_error(err, singular_message(global_equation(pt, equation), global_pivot(f%n, f%nlast, pt, column)), error_numerical)
    err%equation = global_equation(pt, equation)
    err%singular = .true.
  end subroutine set_singular

  !> Statistics of the parts' handles into f: nnz(L), flops and CHOLMOD's
  !> peak memory summed (the parts are factorized side by side), the ordering
  !> of a part with dofs last (all parts use the same).
  subroutine read_statistics(f)
    type(factor_t), intent(inout) :: f
    integer(c_int64_t) :: lnz, memory_peak
    real(c_double) :: flops, time_analyze, time_factorize
    character(kind=c_char) :: buf(32)
    integer :: p, named
    f%nnz_l = 0_i8
    f%flops = 0.0_dp
    f%memory_peak = 0_i8
    named = 1
    do p = 1, f%nparts
      call c2d_chol_stats(f%part(p)%handle, lnz, flops, memory_peak, time_analyze, time_factorize)
      f%nnz_l = f%nnz_l + int(lnz, i8)
      f%flops = f%flops + real(flops, dp)
      f%memory_peak = f%memory_peak + int(memory_peak, i8)
      if (f%part(p)%nlast > 0 .and. f%part(named)%nlast == 0) named = p
    end do
    call c2d_chol_name(f%part(named)%handle, c2d_name_ordering, cholmod_ok, buf, int(size(buf), c_int))
    f%ordering = c_string(buf)
  end subroutine read_statistics

  !> Release the CHOLMOD handles of f (no-op when it holds none); the
  !> statistics are kept.
  !>   f (inout) the factor; on return f%ready = .false.
  subroutine free_factor(f)
    type(factor_t), intent(inout) :: f
    integer :: p
    if (allocated(f%part)) then
      do p = 1, size(f%part)
        if (c_associated(f%part(p)%handle)) call c2d_chol_destroy(f%part(p)%handle)
      end do
      deallocate(f%part)
    end if
    f%ready = .false.
  end subroutine free_factor

  !> Final procedure: a factor going out of scope releases its handles.
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

  !> Bytes the numeric factor takes, from the analysis: 8 per entry of L and
  !> about 4 for its indices and the supernodes' padding.
  pure integer(i8) function factor_bytes(f)
    type(factor_t), intent(in) :: f
    factor_bytes = 12_i8 * f%nnz_l
  end function factor_bytes

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

end module sparse_cholesky
