!> sparse_cholesky_parts: the parts of a sparse Cholesky factor
!> (sparse_cholesky): the diagonal blocks of A that no entry couples (the
!> bodies of a scene), each with its own CHOLMOD handle, and the checks and
!> messages of the factor.
!>
!> A part of sparse_cholesky's implementation, not a public API: only
!> sparse_cholesky uses it (with cholmod_binding, which only these factor
!> modules use).  The numbering: a part's dofs are first..first+n-1 of A;
!> its pivots are rest0+1..rest0+n-nlast (its other dofs) and, in the
!> trailing block of A's factor, last0+1..last0+nlast (its `last` dofs).
!>
!> Programming interface
!>   type(part_t)                                 one part: handle, dofs, status, halves
!>   find_parts(n, colptr, rowind, last, parts)   the finest cut into uncoupled blocks
!>   local_groups(group, local)                   a part's groups numbered 1, 2, ...
!>   part_solve(pt, half, m, b, x)                the solve or a half of it, m columns
!>   part_trailing_range(pt, first, count, block) rows and columns of its L_cc
!>   part_block_end(pt, first, last_row)          end of a diagonal block of its L_cc
!>   global_equation(pt, equation), global_pivot(n, nlast, pt, column)
!>                                                a part's dof and pivot in A's numbering
!>   check_pattern(n, colptr, rowind, err [, last])    a pattern checked before CHOLMOD sees it
!>   singular_pivot_tolerance(n), singular_message(equation, column)
!>   ordering_bytes(n, nnz), status_name(status), trailing_status_message(status), c_string(buf)
!>   largest(part, i)                             the index of the i-th largest part
!>   parts_begin(part, nthreads, levels, blas), parts_end(levels, blas)
!>                                                a loop over the parts: its threads, CHOLMOD's
!>                                                and the BLAS's kept to one thread each
module sparse_cholesky_parts
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int, c_double, c_char, c_null_char
  use kinds, only: dp, i8
  use omp_lib, only: omp_get_max_active_levels, omp_set_max_active_levels, omp_get_active_level, &
                     omp_get_max_threads
  use runtime_binding, only: c2d_blas_threads
  use strings, only: int_to_str
  use errors, only: error_t, set_error, error_numerical
  use cholmod_binding, only: c2d_chol_solve_half, c2d_chol_trailing_range, c2d_chol_trailing_block_end, &
                             c2d_chol_name, c2d_name_status, &
                             c2d_chol_not_super_ll, c2d_chol_block_moved
  implicit none
  private
  public :: part_t, max_parts, find_parts, local_groups, part_solve, part_trailing_range, part_block_end
  public :: global_equation, global_pivot
  public :: check_pattern, singular_pivot_tolerance, singular_message, ordering_bytes
  public :: status_name, trailing_status_message, c_string
  public :: largest, parts_begin, parts_end, side_by_side_min

  !> Floor of the order in the singularity tolerance (see singular_pivot_tolerance).
  integer, parameter :: tolerance_order_floor = 1000

  !> At most this many parts; smaller independent blocks are merged.
  integer, parameter :: max_parts = 16

  !> Parts run side by side only when the second largest has this many dofs:
  !> below it, starting the threads and setting the BLAS to one thread cost
  !> more than the part saves (doc/performance.md, "Bodies factorized side by
  !> side").
  integer, parameter :: side_by_side_min = 10000

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
  end type part_t

contains

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

  !> The dof of A of a part's equation (1-based within the part).
  pure integer function global_equation(pt, equation)
    type(part_t), intent(in) :: pt
    integer(c_int), intent(in) :: equation
    global_equation = pt%first - 1 + int(equation)
  end function global_equation

  !> The pivot of P A P' of a part's pivot (1-based within the part).
  !>   n, nlast (in) the order of A and the size of its block ordered last
  pure integer function global_pivot(n, nlast, pt, column)
    integer, intent(in) :: n, nlast
    type(part_t), intent(in) :: pt
    integer(c_int), intent(in) :: column
    if (column <= pt%n - pt%nlast) then
      global_pivot = pt%rest0 + int(column)
    else
      global_pivot = n - nlast + pt%last0 + int(column) - (pt%n - pt%nlast)
    end if
  end function global_pivot

  !> Checks of a pattern and `last` before CHOLMOD sees them.
  subroutine check_pattern(n, colptr, rowind, err, last)
    integer, intent(in) :: n
    integer, intent(in) :: colptr(:), rowind(:)
    type(error_t), allocatable, intent(out) :: err
    integer, intent(in), optional :: last(:)
    logical, allocatable :: seen(:)
    integer :: j, k

    if (n < 1) then
      call set_error(err, 'sparse Cholesky: empty matrix (order 0)', error_numerical)
      return
    end if
    if (size(colptr) /= n + 1) then
      call set_error(err, 'sparse Cholesky: ' // int_to_str(size(colptr)) // ' column pointers for order ' // &
                     int_to_str(n), error_numerical)
      return
    end if
    do j = 1, n
      if (colptr(j) < 1 .or. colptr(j + 1) < colptr(j) .or. colptr(j + 1) - 1 > size(rowind)) then
        call set_error(err, 'sparse Cholesky: bad column pointers at column ' // int_to_str(j), error_numerical)
        return
      end if
    end do
    if (.not. present(last)) return
    allocate(seen(n))
    seen = .false.
    do k = 1, size(last)
      if (last(k) < 1 .or. last(k) > n) then
        call set_error(err, 'sparse Cholesky: dof ' // int_to_str(last(k)) // ' in `last` is out of range 1..' &
                       // int_to_str(n), error_numerical)
        return
      end if
      if (seen(last(k))) then
        call set_error(err, 'sparse Cholesky: dof ' // int_to_str(last(k)) // ' appears twice in `last`', error_numerical)
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

  !> A part's solve or one of its halves, for m columns.
  function part_solve(pt, half, m, b, x) result(status)
    type(part_t), intent(in) :: pt
    integer(c_int), intent(in) :: half
    integer, intent(in) :: m
    real(dp), intent(in) :: b(pt%n, m)
    real(dp), intent(inout) :: x(pt%n, m)
    integer(c_int) :: status
    status = c2d_chol_solve_half(pt%handle, half, int(pt%n, c_int), int(m, c_int), b, x)
  end function part_solve

  !> Rows and columns first..first+count-1 of a part's trailing block.
  function part_trailing_range(pt, first, count, block) result(status)
    type(part_t), intent(in) :: pt
    integer, intent(in) :: first, count
    real(dp), intent(out) :: block(count, count)
    integer(c_int) :: status
    status = c2d_chol_trailing_range(pt%handle, int(pt%nlast, c_int), int(first, c_int), int(count, c_int), block)
  end function part_trailing_range

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

  !> Bytes an ordering of an n-by-n pattern with nnz stored entries takes,
  !> about: the symmetric graph (both triangles) and its coarser copies in
  !> METIS, CHOLMOD's symbolic workspace; 4-byte integers.
  pure integer(i8) function ordering_bytes(n, nnz)
    integer, intent(in) :: n
    integer(i8), intent(in) :: nnz
    ordering_bytes = 4_i8 * (4_i8 * nnz + 20_i8 * n)
  end function ordering_bytes

  !> Name of a CHOLMOD or shim status code.
  function status_name(status) result(name)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: name
    character(kind=c_char) :: buf(32)
    call c2d_chol_name(c_null_ptr, c2d_name_status, status, buf, int(size(buf), c_int))
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

  !> The end of the diagonal block of a part's trailing block that starts at
  !> `first` (1-based within the part's `last` dofs).
  !>   pt       (in)  the part, factorized with its `last` dofs
  !>   first    (in)  1 <= first <= pt%nlast
  !>   last_row (out) the block's last row, in the part's `last` numbering
  !>   status   (result) cholmod_ok or the C layer's code
  function part_block_end(pt, first, last_row) result(status)
    type(part_t), intent(in) :: pt
    integer, intent(in) :: first
    integer(c_int), intent(out) :: last_row
    integer(c_int) :: status
    status = c2d_chol_trailing_block_end(pt%handle, int(pt%nlast, c_int), int(first, c_int), last_row)
  end function part_block_end

  !> The index of the i-th largest part (loops start with the largest).
  pure integer function largest(part, i)
    type(part_t), intent(in) :: part(:)
    integer, intent(in) :: i
    integer :: p, rank
    do p = 1, size(part)
      rank = count(part%n > part(p)%n) + count(part(1:p - 1)%n == part(p)%n) + 1
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
  !> when the library was built), whatever OMP_NUM_THREADS says: more threads
  !> than cores, for the same factor to the bit; and a second BLAS thread
  !> inside one factor of a 2D mesh gains little (doc/performance.md, "Where
  !> the time goes").  Give levels and blas back to parts_end.  (The
  !> parts' allocations on other threads take malloc arenas of their own: a
  !> program should bound them first: threads' start_threads.)
  subroutine parts_begin(part, nthreads, levels, blas)
    type(part_t), intent(in) :: part(:)
    integer, intent(out) :: nthreads, levels, blas
    nthreads = min(size(part), omp_get_max_threads())
    if (size(part) > 1) then
      if (part(largest(part, 2))%n < side_by_side_min) nthreads = 1
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

  subroutine parts_end(levels, blas)
    integer, intent(in) :: levels, blas
    integer(c_int) :: old
    call omp_set_max_active_levels(levels)
    if (blas > 0) old = c2d_blas_threads(int(blas, c_int))
  end subroutine parts_end

end module sparse_cholesky_parts
