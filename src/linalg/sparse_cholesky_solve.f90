!> sparse_cholesky_solve: the solves x = A^-1 b and their halves, and the
!> trailing block L_cc, of a factor of sparse_cholesky (a submodule: it reads
!> the factor's parts, which stay private to sparse_cholesky).  See
!> sparse_cholesky's header for the factor, its parts and their pivots.
submodule (sparse_cholesky) sparse_cholesky_solve
  implicit none

contains

  !> x = A^-1 b for one right-hand side.
  !>   f   (in)  a factor with f%ready
  !>   b   (in)  (n) right-hand side
  !>   x   (out) (n) solution
  !>   err (out) allocated (error_numerical) on failure: no valid factor, sizes that
  !>       do not match, or CHOLMOD's error
  module procedure solve_vector
    call solve_half(f, c2d_solve_whole, b, x, err)
  end procedure solve_vector

  !> X = A^-1 B for a block of right-hand sides, one CHOLMOD solve per part.
  !>   f   (in)  a factor with f%ready
  !>   b   (in)  (n, nrhs) right-hand sides, nrhs >= 0
  !>   x   (out) (n, nrhs) solutions
  !>   err (out) as for solve_vector
  module procedure solve_block
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
    call set_error(err, msg, error_numerical)
  end procedure solve_block

  !> y = L^-1 P b, the forward half of a solve.  With `last`, y(n-nlast+1:)
  !> belongs to the trailing block: L^-1 P maps a vector that is zero off the
  !> `last` dofs to [0; L_cc^-1 v], and the backward half ends with
  !> x(last) = L_cc'^-1 y(n-nlast+1:).
  !>   f (in) a factor with f%ready; b (in) (n); y (out) (n); err as for solve_vector
  module procedure solve_forward
    call solve_half(f, c2d_solve_forward, b, y, err)
  end procedure solve_forward

  !> x = P' L'^-1 y, the backward half: solve_backward(solve_forward(b)) = A^-1 b.
  !>   f (in) a factor with f%ready; y (in) (n); x (out) (n); err as for solve_vector
  module procedure solve_backward
    call solve_half(f, c2d_solve_backward, y, x, err)
  end procedure solve_backward

  !> x = the solve or one of its halves (half: c2d_solve_*) for one vector.
  subroutine solve_half(f, half, b, x, err)
    type(factor_t), intent(in) :: f
    integer(c_int), intent(in) :: half
    real(dp), intent(in) :: b(:)
    real(dp), intent(out) :: x(:)
    type(error_t), allocatable, intent(out) :: err
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
    call set_error(err, msg, error_numerical)
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
    call parts_begin(f%part, nthreads, levels, blas)
    if (f%nparts == 1) then                 ! the part's own order is A's: no copy
      status(1) = part_solve(f%part(1), half, m, b, x)
      call parts_end(levels, blas)
      return
    end if
    !$omp parallel do num_threads(nthreads) schedule(dynamic, 1) if (nthreads > 1) private(bp, xp, r0, l0, nr, p)
    do i = 1, f%nparts
      p = largest(f%part, i)
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
  !>   err   (out) allocated when f has no such block (no `last`,
  !>         another nlast, factor not supernodal LL', block not at the end)
  !>   first, count (in, optional) only the diagonal sub-block on rows and
  !>         columns first..first+count-1 of L_cc
  module procedure trailing_factor_block
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
        call move_alloc(oom, err)
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
    call set_error(err, msg, error_numerical)
  end procedure trailing_factor_block

  !> The last row e of the diagonal block of L_cc that starts at row and
  !> column `first`: L_cc(e+1:, first:e) = 0 (K couples no two bodies: one
  !> block per body).  f, nlast and err as for trailing_factor_block.
  module procedure trailing_block_end
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
            status = part_block_end(pt, first - pt%last0, last_row)
            e = pt%last0 + int(last_row)
            exit
          end if
        end associate
      end do
      if (status == cholmod_ok) return
      msg = trailing_status_message(status)
    end if
    call set_error(err, msg, error_numerical)
  end procedure trailing_block_end


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

end submodule sparse_cholesky_solve
