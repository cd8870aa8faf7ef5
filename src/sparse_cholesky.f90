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
!> Cut parts.  A part of split_min dofs or more that is larger than twice the
!> other parts together (a body alone, or one much larger than the others:
!> one thread would factorize it while the other waits) is cut at a vertex
!> separator of its node graph (METIS_ComputeVertexSeparator: the top level
!> of a nested dissection, whatever the ordering) into two halves, each a
!> CHOLMOD factor of its own, ordered by the part's method (METIS, or AMD
!> with CAMD's constraint) with the separator's and the `last` dofs coupled
!> to it ordered last; the separator and `last` are then condensed
!> into one dense factor (split_factor).  The halves are work items of the
!> loop over the parts like any part.  The part's pivots are [half 1, half 2,
!> separator, its `last`], so the trailing block is still L_cc.  The rule is
!> on sizes only: the factor is the same on any number of threads.
!>
!> Ownership.  A factor_t owns its CHOLMOD handles (common and factor, in C);
!> free_factor or the final procedure releases them.  Do not copy a factor_t by
!> assignment: both copies would hold the same handle.  The statistics stay
!> readable after free_factor.
!>
!> Programming interface
!>   type(factor_t)   opaque handles (private); ready, n, nlast, nparts, ncut, separator, side_by_side, nnz_l,
!>                    flops, time_analyze, time_factorize, ordering,
!>                    memory_peak, min_pivot_ratio
!>   factorize(f, A, err [, last])          P A P' = L L' (the two halves below)
!>   analyze_pattern(f, n, colptr, rowind, err [, last] [, group] [, method] [, cut])
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
!>   set_split_min(n)                       cut parts from n dofs on (default 200,000)
!>   factor_nnz(f), factor_flops(f), factor_memory(f), factor_ordering(f)
module sparse_cholesky
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_double, &
                                         c_int64_t, c_char, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  use kinds, only: dp, i8
  use omp_lib, only: omp_get_max_active_levels, omp_set_max_active_levels, omp_get_active_level, &
                     omp_get_max_threads, omp_get_wtime
  use diagnostics, only: error_t, set_error, set_out_of_memory, int_to_str, i8_to_str, fail_numerical
  use sparse_matrix, only: csc_t, csc_nnz, csc_check
  use split_factor, only: split_t, split_analyze, split_factorize_half, split_finish, split_solve, &
                          split_trailing_range, split_block_end, split_stats, split_failure, split_min_ratio, split_free
  use cholmod_binding, only: c2d_chol_create, c2d_chol_destroy, c2d_chol_analyze, c2d_chol_factorize_values, &
                             c2d_chol_minor, c2d_chol_set_ordering, c2d_order_amd, c2d_order_metis, &
                             c2d_chol_stats, c2d_chol_min_pivot_ratio, c2d_chol_ordering_name, &
                             c2d_chol_status_name, c2d_chol_solve, &
                             c2d_chol_trailing_range, c2d_chol_trailing_block_end, &
                             c2d_chol_solve_half, c2d_solve_whole, c2d_solve_forward, c2d_solve_backward, &
                             cholmod_ok, cholmod_not_posdef, c2d_chol_block_moved, &
                             c2d_chol_not_super_ll, c2d_chol_bad_argument, &
                             c2d_blas_threads, cholmod_out_of_memory, c2d_memory_available
  implicit none
  private
  public :: factor_t, factorize, analyze_pattern, factorize_values, solve, solve_vector, solve_block
  public :: trailing_factor_block, trailing_block_end, solve_forward, solve_backward
  public :: free_factor, factor_nnz, factor_flops, factor_memory, factor_ordering, set_split_min

  !> Floor of the order in the singularity tolerance (see singular_pivot_tolerance).
  integer, parameter :: tolerance_order_floor = 1000

  !> At most this many parts; smaller independent blocks are merged.
  integer, parameter :: max_parts = 16

  !> Parts run side by side only when the second largest has this many dofs:
  !> below it, starting the threads and setting the BLAS to one thread (a few
  !> ms, and idle threads spinning against the working ones) cost more than
  !> the part saves: input/patch.deck's factorization took 0.6 ms one part
  !> after the other and 1-30 ms side by side.
  integer, parameter :: side_by_side_min = 10000

  !> A part of this many dofs or more, larger than twice the other parts
  !> together (a body alone, or one much larger than the others), is cut at
  !> its top separator into two halves factorized side by side (split_factor):
  !> else one core would wait while it is factorized.  A rule on sizes, not
  !> on threads: the factor is the same on any number of threads.
  !> set_split_min changes it (the unit tests cut small matrices).
  integer, protected :: split_min = 200000

  !> One part of A: the diagonal block A(first:first+n-1, first:first+n-1),
  !> which no entry couples to the rest, with its own CHOLMOD handle.
  type :: part_t
    type(c_ptr) :: handle = c_null_ptr    !< owned CHOLMOD handle (common + L)
    integer :: first = 1                  !< its dofs: first..first+n-1
    integer :: n = 0                      !< their number
    integer :: nlast = 0                  !< its dofs in `last`: last(last0+1:last0+nlast)
    integer :: last0 = 0
    integer :: rest0 = 0                  !< its other dofs: pivots rest0+1..rest0+n-nlast
    integer(c_int) :: status = 0          !< status of its last CHOLMOD call
    logical :: cut = .false.              !< cut in two halves (split_factor)
    type(split_t), allocatable :: split   !< the halves, when cut
  end type part_t

  !> A Cholesky factor P A P' = L L' and its statistics.
  type :: factor_t
    type(part_t), allocatable, private :: part(:)  !< the parts of A (one when A does not split)
    logical :: ready = .false.            !< .true. when L is a valid numeric factor
    integer :: n = 0                      !< order of A
    integer :: nlast = 0                  !< size of the block ordered last (0: none)
    integer :: nparts = 0                 !< number of parts, each factorized on its own
    integer :: ncut = 0                   !< parts cut in two halves (split_factor)
    integer :: separator = 0              !< dofs of their separators
    integer :: side_by_side = 1           !< threads the parts run on (1: one after the other)
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
  !>   cut    (in, optional) .false.: no part is cut in two halves (default
  !>          .true.: a large part that dwarfs the others is, see "Cut parts")
  subroutine analyze_pattern(f, n, colptr, rowind, err, last, group, method, cut)
    type(factor_t), intent(inout) :: f
    integer, intent(in) :: n
    integer, intent(in) :: colptr(:), rowind(:)
    type(error_t), allocatable, intent(out) :: err
    integer, intent(in), optional :: last(:)
    integer, intent(in), optional :: group(:)
    character(len=*), intent(in), optional :: method
    logical, intent(in), optional :: cut
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
                       ' dofs a group in 1..' // int_to_str(n), 1)
        return
      end if
    end if

    ordering = c2d_order_metis
    if (present(method)) then
      if (method == 'amd') then
        ordering = c2d_order_amd
      else if (method /= 'metis') then
        call set_error(err, 'sparse Cholesky: unknown ordering "' // method // '" (expected metis or amd)', 1)
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
        call set_error(err, 'sparse Cholesky: CHOLMOD could not start (out of memory)', 1)
        return
      end if
      f%part(p)%status = c2d_chol_set_ordering(f%part(p)%handle, ordering)
    end do

    do p = 1, f%nparts
      associate (pt => f%part(p))
        pt%cut = grouped .and. pt%n >= split_min .and. pt%n > 2 * (n - pt%n)
        if (present(cut)) pt%cut = pt%cut .and. cut
      end associate
    end do

    t0 = omp_get_wtime()
    call parts_begin(f, nthreads, levels, blas)
    f%side_by_side = nthreads
    ! A METIS ordering splits its first level into two OpenMP tasks, which the
    ! other threads of the team take when they are free: the parts' team, or,
    ! one part after the other, the caller's (no team of one is opened then)
    if (nthreads > 1) then
      !$omp parallel do num_threads(nthreads) schedule(dynamic, 1)
      do i = 1, f%nparts
        call analyze_part(f%part(largest(f, i)))
      end do
      !$omp end parallel do
    else
      do i = 1, f%nparts
        call analyze_part(f%part(largest(f, i)))
      end do
    end if
    call parts_end(levels, blas)
    f%time_analyze = omp_get_wtime() - t0
    call read_statistics(f)

    do p = 1, f%nparts
      select case (f%part(p)%status)
      case (cholmod_ok)
        continue
      case (c2d_chol_block_moved)
        call set_error(err, 'sparse Cholesky: the analysis did not keep the ' // int_to_str(f%nlast) &
                       // ' dofs given as `last` at the last pivots (' // status_name(f%part(p)%status) // ')', 1)
        return
      case (cholmod_out_of_memory)
        ! the ordering's graphs and CHOLMOD's symbolic workspace: a few
        ! integers per stored entry and per dof (an order of magnitude)
        call set_out_of_memory(err, 'ordering K (' // int_to_str(n) // ' dofs, ' // &
                               trim(merge('AMD  ', 'METIS', ordering == c2d_order_amd)) // ')', &
                               ordering_bytes(n, int(colptr(n + 1) - 1, i8)))
        return
      case default
        call set_error(err, 'sparse Cholesky analysis failed: ' // status_name(f%part(p)%status) // ' (status ' &
                       // int_to_str(int(f%part(p)%status)) // ') for a matrix of order ' // int_to_str(n) &
                       // ' with ' // int_to_str(colptr(n + 1) - 1) // ' stored entries', 1)
        return
      end select
    end do

  contains

    subroutine analyze_part(pt)
      type(part_t), intent(inout) :: pt
      if (pt%cut .and. pt%status == cholmod_ok) then
        allocate(pt%split)
        pt%status = split_analyze(pt%split, pt%handle, ordering, pt%n, colptr(pt%first:pt%first + pt%n), &
                                  rowind(colptr(pt%first):), pt%first - 1, last_c(pt%last0 + 1:pt%last0 + pt%nlast), &
                                  group_c(pt%first:pt%first + pt%n - 1))
        if (pt%status == cholmod_ok) return
        ! no two halves to cut it into (a degenerate graph) or a half's analysis
        ! failed: the part is analyzed whole, which reports a failure of its own
        call split_free(pt%split)
        deallocate(pt%split)
        pt%cut = .false.
        pt%status = cholmod_ok
      end if
      if (pt%status == cholmod_ok) &
        pt%status = c2d_chol_analyze(pt%handle, int(pt%n, c_int), colptr(pt%first:pt%first + pt%n), &
                                     rowind(colptr(pt%first):), int(pt%first - 1, c_int), &
                                     int(pt%nlast, c_int), last_c(pt%last0 + 1:), &
                                     merge(int(pt%n, c_int), 0_c_int, grouped), group_c(pt%first:))
    end subroutine analyze_part
  end subroutine analyze_pattern

  !> The parts of a pattern: the finest cut into diagonal blocks that no entry
  !> couples, blocks of fewer than n / max_parts dofs merged with the next.
  !> A single part when `last` does not visit the parts in order.
  !>   n, colptr, rowind (in) the pattern (checked)
  !>   last  (in)  (nlast) dofs ordered last
  !>   parts (out) first, n, nlast, last0 and rest0 of each part
  subroutine find_parts(n, colptr, rowind, last, parts)
    integer, intent(in) :: n, colptr(:), rowind(:)
    integer(c_int), intent(in) :: last(:)
    type(part_t), allocatable, intent(out) :: parts(:)
    integer, allocatable :: span(:), part_of(:)
    integer :: j, q, i, np, start, open, target

    ! span(s) = the number of entries (i, j) with min(i, j) <= s < max(i, j)
    allocate(span(n + 1))
    span = 0
    do j = 1, n
      do q = colptr(j), colptr(j + 1) - 1
        i = rowind(q)
        span(min(i, j)) = span(min(i, j)) + 1
        span(max(i, j)) = span(max(i, j)) - 1
      end do
    end do
    target = max(1, n / max_parts)
    allocate(part_of(n))
    np = 0
    start = 1
    open = 0
    do j = 1, n
      open = open + span(j)
      if (j == n .or. (open == 0 .and. j - start + 1 >= target)) then
        np = np + 1
        part_of(start:j) = np
        start = j + 1
      end if
    end do
    ! `last` must visit the parts in order
    do q = 2, size(last)
      if (part_of(last(q)) < part_of(last(q - 1))) then
        np = 1
        part_of = 1
        exit
      end if
    end do

    allocate(parts(np))
    start = 1
    do q = 1, np
      parts(q)%first = start
      do while (start <= n)
        if (part_of(start) /= q) exit
        start = start + 1
      end do
      parts(q)%n = start - parts(q)%first
    end do
    do q = 1, size(last)
      parts(part_of(last(q)))%nlast = parts(part_of(last(q)))%nlast + 1
    end do
    do q = 2, np
      parts(q)%last0 = parts(q - 1)%last0 + parts(q - 1)%nlast
      parts(q)%rest0 = parts(q - 1)%rest0 + parts(q - 1)%n - parts(q - 1)%nlast
    end do
  end subroutine find_parts

  !> A part's groups renumbered 1, 2, ... in order of first appearance.
  subroutine local_groups(group, local)
    integer, intent(in) :: group(:)
    integer(c_int), intent(out) :: local(:)
    integer, allocatable :: number(:)
    integer :: i, ng
    allocate(number(minval(group):maxval(group)))
    number = 0
    ng = 0
    do i = 1, size(group)
      if (number(group(i)) == 0) then
        ng = ng + 1
        number(group(i)) = ng
      end if
      local(i) = int(number(group(i)), c_int)
    end do
  end subroutine local_groups

  !> The index of the i-th largest part (loops start with the largest).
  pure integer function largest(f, i)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: i
    integer :: p, rank
    do p = 1, size(f%part)
      rank = count(f%part%n > f%part(p)%n) + count(f%part(1:p - 1)%n == f%part(p)%n) + 1
      if (rank == i) then
        largest = p
        return
      end if
    end do
    largest = i
  end function largest

  !> Begin a loop over the parts of f: nthreads to run it on (one thread per
  !> part, at most the OpenMP threads), CHOLMOD's own OpenMP loops kept on
  !> the thread that calls it, and, on several threads, a BLAS of one thread
  !> each.  CHOLMOD's loops ask for 4 threads (CHOLMOD_OMP_NUM_THREADS, set
  !> when the library was built), whatever OMP_NUM_THREADS says; on 2 cores
  !> those teams cost 13-20 % of the numeric factorization (hertz_1e5 and
  !> hertz_1e6 of bench/contact.sh, the same factor to the bit).  A second
  !> BLAS thread inside one factor gains nothing at 1e5-1e6 dofs
  !> (doc/performance.md).  Give levels and blas back to parts_end.  (The
  !> parts' allocations on other threads take malloc arenas of their own: a
  !> program should call c2d_malloc_arenas first.)
  subroutine parts_begin(f, nthreads, levels, blas)
    type(factor_t), intent(in) :: f
    integer, intent(out) :: nthreads, levels, blas
    integer, allocatable :: item(:,:)
    call work_items(f, item)
    nthreads = min(size(item, 2), omp_get_max_threads())
    if (size(item, 2) > 1) then
      if (item(3, 2) < side_by_side_min) nthreads = 1
    end if
    levels = omp_get_max_active_levels()
    blas = 0
    if (nthreads > 1) then
      call omp_set_max_active_levels(omp_get_active_level() + 1)   ! this loop's team, none inside it
      blas = int(c2d_blas_threads(1_c_int))
    else
      nthreads = 1
      call omp_set_max_active_levels(omp_get_active_level())
    end if
  end subroutine parts_begin

  !> The work of a loop over the parts: item(:, k) = [part, half (0: the
  !> whole part), dofs], a cut part giving its two halves, largest first.
  subroutine work_items(f, item)
    type(factor_t), intent(in) :: f
    integer, allocatable, intent(out) :: item(:,:)
    integer :: p, k, h, j
    integer :: tmp(3)
    allocate(item(3, size(f%part) + count(f%part%cut)))
    k = 0
    do p = 1, size(f%part)
      if (f%part(p)%cut) then
        do h = 1, 2
          k = k + 1
          if (allocated(f%part(p)%split)) then
            item(:, k) = [p, h, f%part(p)%split%half(h)%n]
          else                            ! before the analysis cuts it
            item(:, k) = [p, h, f%part(p)%n / 2]
          end if
        end do
      else
        k = k + 1
        item(:, k) = [p, 0, f%part(p)%n]
      end if
    end do
    do k = 2, size(item, 2)               ! stable insertion sort, largest first
      tmp = item(:, k)
      j = k - 1
      do while (j >= 1)
        if (item(3, j) >= tmp(3)) exit
        item(:, j + 1) = item(:, j)
        j = j - 1
      end do
      item(:, j + 1) = tmp
    end do
  end subroutine work_items

  subroutine parts_end(levels, blas)
    integer, intent(in) :: levels, blas
    integer(c_int) :: old
    call omp_set_max_active_levels(levels)
    if (blas > 0) old = c2d_blas_threads(int(blas, c_int))
  end subroutine parts_end

  !> The numeric factorization of A, whose pattern analyze_pattern analyzed:
  !> the second half of factorize.
  !>   f   (inout) the factor, analyzed; f%ready = .true. on success
  !>   A   (in)    the matrix with the analyzed pattern, finite values
  !>   err (out)   allocated (status 1) as in factorize
  subroutine factorize_values(f, A, err)
    type(factor_t), intent(inout) :: f
    type(csc_t), intent(in) :: A
    type(error_t), allocatable, intent(out) :: err
    integer(c_int) :: column, equation
    real(c_double) :: ratio
    integer :: i, j, p, nthreads, levels, blas, worst
    integer, allocatable :: item(:,:)
    real(dp) :: t0, worst_ratio
    logical :: analyzed

    analyzed = allocated(f%part) .and. f%n == A%n
    if (analyzed) analyzed = all(f%part%status == cholmod_ok)
    if (.not. analyzed) then
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
    ! The factor's size is known from the analysis: a factor that cannot fit
    ! is said before the numeric factorization starts taking the memory
    if (c2d_memory_available() >= 0 .and. factor_bytes(f) > c2d_memory_available()) then
      call set_out_of_memory(err, 'factorizing K (nnz(L) = ' // i8_to_str(f%nnz_l) // ' from the analysis; ' // &
                             i8_to_str(max(0_i8, int(c2d_memory_available(), i8)) / 1048576_i8) // &
                             ' MB available)', factor_bytes(f))
      return
    end if
    t0 = omp_get_wtime()
    call work_items(f, item)
    call parts_begin(f, nthreads, levels, blas)
    !$omp parallel do num_threads(nthreads) schedule(dynamic, 1) if (nthreads > 1)
    do i = 1, size(item, 2)
      associate (pt => f%part(item(1, i)))
        if (item(2, i) == 0) then
          pt%status = c2d_chol_factorize_values(pt%handle, int(pt%n, c_int), A%colptr(pt%first:pt%first + pt%n), &
                                                A%rowind(A%colptr(pt%first):), int(pt%first - 1, c_int), &
                                                A%val(A%colptr(pt%first):))
        else
          call split_factorize_half(pt%split, item(2, i), A%val(A%colptr(pt%first):A%colptr(pt%first + pt%n) - 1))
        end if
      end associate
    end do
    !$omp end parallel do
    call parts_end(levels, blas)
    ! the dense block of each cut part, on every BLAS thread
    do p = 1, f%nparts
      associate (pt => f%part(p))
        if (pt%cut) pt%status = split_finish(pt%split, A%val(A%colptr(pt%first):A%colptr(pt%first + pt%n) - 1))
      end associate
    end do
    call read_statistics(f)
    f%time_factorize = omp_get_wtime() - t0

    do p = 1, f%nparts
      select case (f%part(p)%status)
      case (cholmod_ok)
        continue
      case (cholmod_not_posdef)
        call part_minor(f%part(p), column, equation)
        call set_error(err, singular_message(global_equation(f%part(p), equation), &
                                             global_pivot(f, f%part(p), column)), 1)
        return
      case (cholmod_out_of_memory)
        call set_out_of_memory(err, 'factorizing K (nnz(L) = ' // i8_to_str(f%nnz_l) // ')', factor_bytes(f))
        return
      case default
        call set_error(err, 'sparse Cholesky factorization failed: ' // status_name(f%part(p)%status) // &
                       ' (status ' // int_to_str(int(f%part(p)%status)) // ') for a matrix of order ' // &
                       int_to_str(A%n) // ' with ' // int_to_str(csc_nnz(A)) // ' stored entries', 1)
        return
      end select
    end do

    ! a dependent column whose pivot came out tiny but positive through rounding
    worst = 1
    worst_ratio = huge(1.0_dp)
    do p = 1, f%nparts
      call part_min_ratio(f%part(p), ratio, column, equation)
      if (ieee_is_nan(ratio)) then
        call set_error(err, 'sparse Cholesky: non-finite pivot at equation ' // &
                       int_to_str(global_equation(f%part(p), equation)) // ' (column ' // &
                       int_to_str(global_pivot(f, f%part(p), column)) // &
                       ' of the permuted matrix): overflow in the factor', 1)
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
      call part_min_ratio(f%part(worst), ratio, column, equation)
      call set_error(err, singular_message(global_equation(f%part(worst), equation), &
                                           global_pivot(f, f%part(worst), column)), 1)
      return
    end if
    f%ready = .true.

  contains

    !> The failing pivot and dof of a part (its own numbering).
    subroutine part_minor(pt, column, equation)
      type(part_t), intent(in) :: pt
      integer(c_int), intent(out) :: column, equation
      integer :: c, e
      if (pt%cut) then
        call split_failure(pt%split, c, e)
        column = int(c, c_int)
        equation = int(e, c_int)
      else
        call c2d_chol_minor(pt%handle, column, equation)
      end if
    end subroutine part_minor

    !> The least pivot ratio of a part, its pivot and dof.
    subroutine part_min_ratio(pt, ratio, column, equation)
      type(part_t), intent(in) :: pt
      real(c_double), intent(out) :: ratio
      integer(c_int), intent(out) :: column, equation
      real(dp) :: r
      integer :: c, e
      if (pt%cut) then
        call split_min_ratio(pt%split, A%val(A%colptr(pt%first):A%colptr(pt%first + pt%n) - 1), r, c, e)
        ratio = real(r, c_double)
        column = int(c, c_int)
        equation = int(e, c_int)
      else
        call c2d_chol_min_pivot_ratio(pt%handle, ratio, column, equation)
      end if
    end subroutine part_min_ratio
  end subroutine factorize_values

  !> The dof of A of a part's equation (1-based within the part).
  pure integer function global_equation(pt, equation)
    type(part_t), intent(in) :: pt
    integer(c_int), intent(in) :: equation
    global_equation = pt%first - 1 + int(equation)
  end function global_equation

  !> The pivot of P A P' of a part's pivot (1-based within the part).
  pure integer function global_pivot(f, pt, column)
    type(factor_t), intent(in) :: f
    type(part_t), intent(in) :: pt
    integer(c_int), intent(in) :: column
    if (column <= pt%n - pt%nlast) then
      global_pivot = pt%rest0 + int(column)
    else
      global_pivot = f%n - f%nlast + pt%last0 + int(column) - (pt%n - pt%nlast)
    end if
  end function global_pivot

  !> Statistics of the parts' handles into f: nnz(L), flops and CHOLMOD's
  !> peak memory summed (the parts are factorized side by side), the ordering
  !> of a part with dofs last (all parts use the same).
  subroutine read_statistics(f)
    type(factor_t), intent(inout) :: f
    integer(c_int64_t) :: lnz, memory_peak
    real(c_double) :: flops, time_analyze, time_factorize
    character(kind=c_char) :: buf(32)
    integer :: p, named, k
    integer(i8) :: cut_lnz, cut_memory
    real(dp) :: cut_flops
    f%nnz_l = 0_i8
    f%flops = 0.0_dp
    f%memory_peak = 0_i8
    named = 1
    f%ncut = 0
    f%separator = 0
    do p = 1, f%nparts
      if (f%part(p)%cut) then
        call split_stats(f%part(p)%split, cut_lnz, cut_flops, cut_memory)
        f%nnz_l = f%nnz_l + cut_lnz
        f%flops = f%flops + cut_flops
        f%memory_peak = f%memory_peak + cut_memory
        f%ncut = f%ncut + 1
        f%separator = f%separator + f%part(p)%split%nsep
      else
        call c2d_chol_stats(f%part(p)%handle, lnz, flops, memory_peak, time_analyze, time_factorize)
        f%nnz_l = f%nnz_l + int(lnz, i8)
        f%flops = f%flops + real(flops, dp)
        f%memory_peak = f%memory_peak + int(memory_peak, i8)
      end if
      if (f%part(p)%nlast > 0 .and. f%part(named)%nlast == 0) named = p
    end do
    if (f%part(named)%cut) then
      call c2d_chol_ordering_name(f%part(named)%split%half(1)%handle, buf, int(size(buf), c_int))
    else
      call c2d_chol_ordering_name(f%part(named)%handle, buf, int(size(buf), c_int))
    end if
    f%ordering = c_string(buf)
    ! a cut part's halves order their share of the separator last: "+last"
    ! names the caller's `last` only
    k = index(f%ordering, '+last')
    if (f%nlast == 0 .and. k > 0) f%ordering = f%ordering(1:k - 1)
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

  !> X = A^-1 B for a block of right-hand sides, one CHOLMOD solve per part.
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
    integer(c_int), allocatable :: status(:)

    if (.not. f%ready) then
      msg = 'sparse Cholesky solve: no valid factor (factorize failed or was not called)'
    else if (size(b, 1) /= f%n .or. size(x, 1) /= f%n .or. size(x, 2) /= size(b, 2)) then
      msg = 'sparse Cholesky solve: blocks of ' // int_to_str(size(b, 1)) // ' and ' // int_to_str(size(x, 1)) &
            // ' rows (' // int_to_str(size(b, 2)) // ' and ' // int_to_str(size(x, 2)) &
            // ' columns) for a factor of order ' // int_to_str(f%n)
    else
      if (size(b, 2) == 0) return
      call solve_parts(f, c2d_solve_whole, size(b, 2), b, x, status)
      msg = solve_status(f, status)
      if (len(msg) == 0) return
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
    integer(c_int), allocatable :: status(:)

    if (.not. f%ready) then
      msg = 'sparse Cholesky solve: no valid factor (factorize failed or was not called)'
    else if (size(b) /= f%n .or. size(x) /= f%n) then
      msg = 'sparse Cholesky solve: vectors of size ' // int_to_str(size(b)) // ' and ' // int_to_str(size(x)) &
            // ' for a factor of order ' // int_to_str(f%n)
    else
      call solve_parts(f, half, 1, b, x, status)
      msg = solve_status(f, status)
      if (len(msg) == 0) return
    end if
    call report(msg, err)
  end subroutine solve_half

  !> x = the solve or one of its halves for the columns of b, part by part
  !> (side by side on the OpenMP threads when A has several parts), with
  !> each part's status in status(:).  In the pivot order of y
  !> (forward output, backward input) the part's other dofs are
  !> rest0+1..rest0+n-nlast and its `last` dofs n-nlast+last0+1.., as its
  !> own y has them one after the other.
  subroutine solve_parts(f, half, m, b, x, status)
    type(factor_t), intent(in) :: f
    integer(c_int), intent(in) :: half
    integer, intent(in) :: m
    real(dp), intent(in) :: b(f%n, m)
    real(dp), intent(inout) :: x(f%n, m)
    integer(c_int), allocatable, intent(out) :: status(:)
    real(dp), allocatable :: bp(:,:), xp(:,:)
    integer :: i, p, nthreads, levels, blas, r0, l0, nr

    allocate(status(f%nparts))
    call parts_begin(f, nthreads, levels, blas)
    if (f%nparts == 1) then                 ! the part's own order is A's: no copy
      status(1) = part_solve(f%part(1), half, m, b, x)
      call parts_end(levels, blas)
      return
    end if
    !$omp parallel do num_threads(nthreads) schedule(dynamic, 1) if (nthreads > 1) private(bp, xp, r0, l0, nr, p)
    do i = 1, f%nparts
      p = largest(f, i)
      associate (pt => f%part(p))
        nr = pt%n - pt%nlast
        r0 = pt%rest0
        l0 = f%n - f%nlast + pt%last0
        allocate(bp(pt%n, m), xp(pt%n, m))
        if (half == c2d_solve_backward) then          ! y in pivot order
          bp(1:nr, :) = b(r0 + 1:r0 + nr, :)
          bp(nr + 1:, :) = b(l0 + 1:l0 + pt%nlast, :)
        else                                          ! b in the order of A
          bp = b(pt%first:pt%first + pt%n - 1, :)
        end if
        status(p) = part_solve(pt, half, m, bp, xp)
        if (half == c2d_solve_forward) then
          x(r0 + 1:r0 + nr, :) = xp(1:nr, :)
          x(l0 + 1:l0 + pt%nlast, :) = xp(nr + 1:, :)
        else
          x(pt%first:pt%first + pt%n - 1, :) = xp
        end if
        deallocate(bp, xp)
      end associate
    end do
    !$omp end parallel do
    call parts_end(levels, blas)
  end subroutine solve_parts

  !> A part's solve or one of its halves, for m columns.
  function part_solve(pt, half, m, b, x) result(status)
    type(part_t), intent(in) :: pt
    integer(c_int), intent(in) :: half
    integer, intent(in) :: m
    real(dp), intent(in) :: b(pt%n, m)
    real(dp), intent(inout) :: x(pt%n, m)
    integer(c_int) :: status
    if (pt%cut) then
      status = split_solve(pt%split, half, m, b, x)
    else
      status = c2d_chol_solve_half(pt%handle, half, int(pt%n, c_int), int(m, c_int), b, x)
    end if
  end function part_solve

  !> '' when every part's solve succeeded, else the message of the first failure.
  function solve_status(f, status) result(msg)
    type(factor_t), intent(in) :: f
    integer(c_int), intent(in) :: status(:)
    character(len=:), allocatable :: msg
    integer :: p
    msg = ''
    do p = 1, f%nparts
      if (status(p) /= cholmod_ok) then
        msg = 'sparse Cholesky solve failed: ' // status_name(status(p)) // ' (status ' // &
              int_to_str(int(status(p))) // ')'
        return
      end if
    end do
  end function solve_status

  !> The trailing block L_cc of L, for a factor computed with `last`: rows and
  !> columns of the last nlast pivots, in the order of `last`, so that
  !>     (A^-1)(last, last) = (L_cc L_cc')^-1,  L_cc L_cc' = Schur complement on last.
  !>   f     (in)  a factor from factorize(f, A, err, last) with f%ready
  !>   nlast (in)  size(last) given to factorize
  !>   Lcc   (out) (nlast, nlast) lower triangular, zero above the diagonal
  !>   err   (out, optional) allocated when f has no such block (no `last`,
  !>         another nlast, factor not supernodal LL', block not at the end);
  !>         when absent a failure stops the program through fail_numerical
  !>   first, count (in, optional) only the diagonal sub-block on rows and
  !>         columns first..first+count-1 of L_cc
  subroutine trailing_factor_block(f, nlast, Lcc, err, first, count)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: nlast
    real(dp), allocatable, intent(out) :: Lcc(:,:)
    type(error_t), allocatable, intent(out), optional :: err
    integer, intent(in), optional :: first, count
    character(len=:), allocatable :: msg
    real(dp), allocatable :: block(:,:)
    integer(c_int) :: status
    integer :: k1, m, p, lo, hi, st
    type(error_t), allocatable :: oom

    k1 = 1
    m = nlast
    if (present(first)) k1 = first
    if (present(count)) m = count
    msg = trailing_check(f, nlast)
    if (len(msg) == 0 .and. (k1 < 1 .or. m < 1 .or. k1 - 1 + m > nlast)) &
      msg = trailing_status_message(c2d_chol_bad_argument)
    if (len(msg) == 0) then
      allocate(Lcc(m, m), source=0.0_dp, stat=st)
      if (st /= 0) then
        call set_out_of_memory(oom, 'condensing the contact problem (the factor''s contact block L_cc of ' // &
                               int_to_str(m) // ' x ' // int_to_str(m) // ')', 8_i8 * int(m, i8) * int(m, i8))
        call report(oom%message, err)
        return
      end if
      status = cholmod_ok
      ! L_cc is block diagonal by part: each part's piece of the range from its own factor
      do p = 1, f%nparts
        associate (pt => f%part(p))
          lo = max(k1, pt%last0 + 1)
          hi = min(k1 + m - 1, pt%last0 + pt%nlast)
          if (lo > hi) cycle
          if (lo == k1 .and. hi == k1 + m - 1) then
            status = part_trailing_range(pt, lo - pt%last0, m, Lcc)
          else
            allocate(block(hi - lo + 1, hi - lo + 1))
            status = part_trailing_range(pt, lo - pt%last0, hi - lo + 1, block)
            Lcc(lo - k1 + 1:hi - k1 + 1, lo - k1 + 1:hi - k1 + 1) = block
            deallocate(block)
          end if
        end associate
        if (status /= cholmod_ok) exit
      end do
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
    integer :: p

    e = first
    status = c2d_chol_bad_argument
    msg = trailing_check(f, nlast)
    if (len(msg) == 0 .and. (first < 1 .or. first > nlast)) msg = trailing_status_message(status)
    if (len(msg) == 0) then
      do p = 1, f%nparts
        associate (pt => f%part(p))
          if (first > pt%last0 .and. first <= pt%last0 + pt%nlast) then
            if (pt%cut) then
              status = split_block_end(pt%split, pt%nlast, first - pt%last0, last_row)
            else
              status = c2d_chol_trailing_block_end(pt%handle, int(pt%nlast, c_int), int(first - pt%last0, c_int), &
                                                   last_row)
            end if
            e = pt%last0 + int(last_row)
            exit
          end if
        end associate
      end do
      if (status == cholmod_ok) return
      msg = trailing_status_message(status)
    end if
    call report(msg, err)
  end subroutine trailing_block_end

  !> Rows and columns first..first+count-1 of a part's trailing block.
  function part_trailing_range(pt, first, count, block) result(status)
    type(part_t), intent(in) :: pt
    integer, intent(in) :: first, count
    real(dp), intent(out) :: block(count, count)
    integer(c_int) :: status
    if (pt%cut) then
      status = split_trailing_range(pt%split, pt%nlast, first, count, block)
    else
      status = c2d_chol_trailing_range(pt%handle, int(pt%nlast, c_int), int(first, c_int), int(count, c_int), block)
    end if
  end function part_trailing_range

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


  !> Release the CHOLMOD handles of f (no-op when it holds none); the
  !> statistics are kept.
  !>   f (inout) the factor; on return f%ready = .false.
  subroutine free_factor(f)
    type(factor_t), intent(inout) :: f
    integer :: p
    if (allocated(f%part)) then
      do p = 1, size(f%part)
        if (c_associated(f%part(p)%handle)) call c2d_chol_destroy(f%part(p)%handle)
        if (allocated(f%part(p)%split)) call split_free(f%part(p)%split)
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

  !> Cut parts of split_min_dofs dofs or more (split_min); the unit tests
  !> lower it to cut small matrices.
  subroutine set_split_min(n)
    integer, intent(in) :: n
    split_min = n
  end subroutine set_split_min

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

  !> Bytes an ordering of an n-by-n pattern with nnz stored entries takes,
  !> about: the symmetric graph (both triangles) and its coarser copies in
  !> METIS, CHOLMOD's symbolic workspace; 4-byte integers.
  pure integer(i8) function ordering_bytes(n, nnz)
    integer, intent(in) :: n
    integer(i8), intent(in) :: nnz
    ordering_bytes = 4_i8 * (4_i8 * nnz + 20_i8 * n)
  end function ordering_bytes

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
