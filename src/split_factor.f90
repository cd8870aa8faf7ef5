!> split_factor: a part of a sparse Cholesky factor (sparse_cholesky) cut at
!> the top vertex separator of its node graph, so that the two halves are
!> factorized side by side, each by its own CHOLMOD handle.  With H1, H2 the
!> halves, T = [the separator; the part's `last` dofs] and the pivots
!> [H1, H2, T]:
!>     L = [ L1  0   0  ]       L_i L_i' = A(H_i,H_i)   (in the half's own order)
!>         [ 0   L2  0  ]       L_T L_T' = S = A(T,T) - B1 B1' - B2 B2'
!>         [ B1  B2  L_T]
!> Half i is the principal submatrix of A on H_i and T_i, the dofs of T coupled
!> to H_i, analyzed with T_i last: its factor is [L_i 0; B_i(T_i,:) M_i], with
!>     M_i M_i' = A(T_i,T_i) - B_i B_i'.
!> So B_i B_i' = A(T_i,T_i) - M_i M_i' and S = A(T,T) + sum_i (M_i M_i' -
!> A(T_i,T_i)) on T_i, factorized densely (LAPACK, threaded BLAS).  The
!> solves read B_i through M_i: the half's forward solve of [b(H_i); 0] ends
!> in z with M_i z = -B_i y_i.  The block of `last` is the trailing block of
!> L_T, as in an unsplit factor.
!>
!> The price: each half factorizes its dense block M_i (|T_i|^3/3 flops) and
!> forms M_i M_i' (as much again), and S is factorized (|T|^3/3); the gain is
!> the two halves side by side (doc/performance.md, "A body cut in two").
!>
!> All indices are the part's own (1..n); 1-based.  A part of
!> sparse_cholesky's implementation (with sparse_cholesky_parts): only these
!> factor modules use cholmod_binding.
module split_factor
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_double, c_int64_t
  use kinds, only: dp, i8
  use cholmod_binding, only: c2d_chol_create, c2d_chol_destroy, c2d_chol_analyze, c2d_chol_separator, &
                             c2d_chol_factorize_values, c2d_chol_set_ordering, c2d_chol_trailing_range, &
                             c2d_chol_solve_half, c2d_chol_stats, c2d_chol_minor, c2d_chol_min_pivot_ratio, &
                             c2d_solve_whole, c2d_solve_forward, c2d_solve_backward, &
                             cholmod_ok, cholmod_not_posdef, cholmod_out_of_memory, c2d_chol_bad_argument
  use lapack_interfaces, only: dpotrf, dlauum, dtrsm, dtrmm
  implicit none
  private
  public :: split_t, split_analyze, split_factorize_half, split_finish, split_solve
  public :: split_trailing_range, split_block_end, split_stats, split_failure, split_min_ratio, split_free

  !> One half: the principal submatrix of the part on its dofs.
  type :: half_t
    type(c_ptr) :: handle = c_null_ptr
    integer :: n = 0                       !< its dofs: nh of H_i, then n - nh of T_i
    integer :: nh = 0
    integer, allocatable :: dof(:)         !< (n) the part's dof of each
    integer, allocatable :: tpos(:)        !< (n - nh) position in T of its T_i dofs
    integer, allocatable :: colptr(:)      !< (n + 1) its upper triangle (CSC)
    integer, allocatable :: rowind(:)
    integer, allocatable :: src(:)         !< the part's entry of each of its entries
                                           !< (the pattern is freed once factorized)
    real(dp), allocatable :: m(:,:)        !< M_i, lower triangular
    integer(c_int) :: status = cholmod_ok
  end type half_t

  !> A dense block (an array of two of them: one per half).
  type :: block_t
    real(dp), allocatable :: a(:,:)
  end type block_t

  !> A part cut in two halves and its dense block on T.
  type :: split_t
    type(half_t) :: half(2)
    integer :: n = 0                       !< the part's dofs
    integer :: nt = 0                      !< |T|
    integer :: nsep = 0                    !< dofs of the separator (first in T)
    integer, allocatable :: tdof(:)        !< (nt) the part's dof of each dof of T
    integer, allocatable :: tt(:,:)        !< (3, :) entries of A(T,T): rows a >= b in T, the part's entry
    real(dp), allocatable :: ls(:,:)       !< L_T (nt, nt), lower triangular
    integer :: info = 0                    !< column of L_T where S was not positive definite (0: none)
  end type split_t

contains

  !> Cut the part at its top separator and analyze the two halves.
  !>   sp      (out) the split part, its halves analyzed
  !>   handle  (in)  the part's CHOLMOD handle (its workspace for the separator)
  !>   method  (in)  the ordering of the halves (c2d_order_metis or c2d_order_amd)
  !>   n, colptr, rowind, offset  the part's pattern, as c2d_chol_analyze takes it
  !>   last    (in)  (nlast) the part's dofs ordered last
  !>   group   (in)  (n) the node of each dof, 1..n
  !> Returns CHOLMOD's or the shim's status.
  function split_analyze(sp, handle, method, n, colptr, rowind, offset, last, group) result(status)
    type(split_t), intent(out) :: sp
    type(c_ptr), intent(in) :: handle
    integer(c_int), intent(in) :: method
    integer, intent(in) :: n, offset
    integer, intent(in) :: colptr(:), rowind(:)
    integer(c_int), intent(in) :: last(:), group(:)
    integer(c_int) :: status
    integer(c_int), allocatable :: side(:)
    integer, allocatable :: tpos(:), deg(:), nbr(:), ent(:), inhalf(:,:)
    integer :: j, q, r, i, k, base, nlast, ntt

    nlast = size(last)
    sp%n = n
    allocate(side(n))
    status = c2d_chol_separator(handle, int(n, c_int), colptr, rowind, int(offset, c_int), int(nlast, c_int), &
                                last, group, side)
    if (status /= cholmod_ok) return
    if (count(side == 0) == 0 .or. count(side == 1) == 0) then
      status = c2d_chol_bad_argument
      return
    end if

    ! T = [the separator, ascending; last(:)]
    sp%nsep = count(side == 2)
    sp%nt = sp%nsep + nlast
    allocate(sp%tdof(sp%nt), tpos(n))
    tpos = 0
    k = 0
    do j = 1, n
      if (side(j) == 2) then
        k = k + 1
        sp%tdof(k) = j
      end if
    end do
    sp%tdof(sp%nsep + 1:) = int(last)
    do k = 1, sp%nt
      tpos(sp%tdof(k)) = k
    end do

    ! both triangles of the pattern: nbr(deg(j):deg(j+1)-1), ent = the entry
    base = colptr(1)
    allocate(deg(n + 1))
    deg = 0
    ntt = 0
    do j = 1, n
      do q = colptr(j) - base + 1, colptr(j + 1) - base
        r = rowind(q) - offset
        deg(j) = deg(j) + 1
        if (r /= j) deg(r) = deg(r) + 1
        if (tpos(r) > 0 .and. tpos(j) > 0) ntt = ntt + 1
      end do
    end do
    call counts_to_starts(deg)
    allocate(nbr(deg(n + 1) - 1), ent(deg(n + 1) - 1), sp%tt(3, ntt))
    ntt = 0
    do j = 1, n
      do q = colptr(j) - base + 1, colptr(j + 1) - base
        r = rowind(q) - offset
        nbr(deg(j)) = r
        ent(deg(j)) = q
        deg(j) = deg(j) + 1
        if (r /= j) then
          nbr(deg(r)) = j
          ent(deg(r)) = q
          deg(r) = deg(r) + 1
        end if
        if (tpos(r) > 0 .and. tpos(j) > 0) then
          ntt = ntt + 1
          sp%tt(:, ntt) = [max(tpos(r), tpos(j)), min(tpos(r), tpos(j)), q]
        end if
      end do
    end do
    do j = n, 1, -1
      deg(j + 1) = deg(j)
    end do
    deg(1) = 1

    ! T_i: the dofs of T coupled to H_i
    allocate(inhalf(sp%nt, 2))
    inhalf = 0
    do j = 1, n
      if (side(j) > 1) cycle
      do q = deg(j), deg(j + 1) - 1
        if (tpos(nbr(q)) > 0) inhalf(tpos(nbr(q)), side(j) + 1) = 1
      end do
    end do

    do i = 1, 2
      sp%half(i)%handle = c2d_chol_create()
      if (.not. c_associated(sp%half(i)%handle)) then
        status = cholmod_out_of_memory
        return
      end if
      sp%half(i)%status = c2d_chol_set_ordering(sp%half(i)%handle, method)
    end do
    ! the halves side by side: another thread of the caller's team takes one
    ! when it is free (an orphaned task runs at once)
    !$omp task default(shared)
    call build_half(sp%half(2), 1)
    call analyze_half(sp%half(2))
    !$omp end task
    call build_half(sp%half(1), 0)
    call analyze_half(sp%half(1))
    !$omp taskwait
    status = sp%half(1)%status
    if (status == cholmod_ok) status = sp%half(2)%status

  contains

    !> The dofs and the upper triangle of half h (side s), entries sorted.
    subroutine build_half(h, s)
      type(half_t), intent(inout) :: h
      integer, intent(in) :: s
      integer, allocatable :: loc(:)
      integer :: jj, d, m, a, t, q           ! (all local: the two halves are built at once)
      h%nh = count(side == s)
      h%n = h%nh + sum(inhalf(:, s + 1))
      allocate(h%dof(h%n), h%tpos(h%n - h%nh), loc(n))
      loc = 0
      m = 0
      do d = 1, n
        if (side(d) == s) then
          m = m + 1
          h%dof(m) = d
        end if
      end do
      do t = 1, sp%nt
        if (inhalf(t, s + 1) == 0) cycle
        m = m + 1
        h%dof(m) = sp%tdof(t)
        h%tpos(m - h%nh) = t
      end do
      do m = 1, h%n
        loc(h%dof(m)) = m
      end do
      allocate(h%colptr(h%n + 1))
      h%colptr(1) = 1
      do jj = 1, h%n
        d = h%dof(jj)
        m = 0
        do q = deg(d), deg(d + 1) - 1
          a = loc(nbr(q))
          if (a > 0 .and. a <= jj) m = m + 1
        end do
        h%colptr(jj + 1) = h%colptr(jj) + m
      end do
      allocate(h%rowind(h%colptr(h%n + 1) - 1), h%src(h%colptr(h%n + 1) - 1))
      do jj = 1, h%n
        d = h%dof(jj)
        m = h%colptr(jj)
        do q = deg(d), deg(d + 1) - 1
          a = loc(nbr(q))
          if (a > 0 .and. a <= jj) then
            h%rowind(m) = a
            h%src(m) = ent(q)
            m = m + 1
          end if
        end do
        call sort_pairs(h%rowind(h%colptr(jj):h%colptr(jj + 1) - 1), h%src(h%colptr(jj):h%colptr(jj + 1) - 1))
      end do
    end subroutine build_half

    subroutine analyze_half(h)
      type(half_t), intent(inout) :: h
      integer(c_int), allocatable :: lastc(:), groupc(:), number(:)
      integer :: m, ng, stat
      if (h%status /= cholmod_ok) return
      allocate(lastc(h%n - h%nh), groupc(h%n), number(n), stat=stat)
      if (stat /= 0) then
        h%status = cholmod_out_of_memory
        return
      end if
      lastc = [(int(m, c_int), m = h%nh + 1, h%n)]
      number = 0
      ng = 0
      do m = 1, h%n
        if (number(group(h%dof(m))) == 0) then
          ng = ng + 1
          number(group(h%dof(m))) = ng
        end if
        groupc(m) = int(number(group(h%dof(m))), c_int)
      end do
      ! colptr and rowind as they are (default integers are c_int, as for A in
      ! sparse_cholesky): int(..., c_int) made copies in temporaries that
      ! gfortran allocates unchecked, a crash instead of a status when memory is short
      h%status = c2d_chol_analyze(h%handle, int(h%n, c_int), h%colptr, h%rowind, 0_c_int, &
                                  int(h%n - h%nh, c_int), lastc, int(h%n, c_int), groupc)
    end subroutine analyze_half
  end function split_analyze

  !> Degrees in deg(1:n) to start positions: deg(j) = 1 + sum(deg(1:j-1)).
  subroutine counts_to_starts(deg)
    integer, intent(inout) :: deg(:)
    integer :: j, s, d
    s = 1
    do j = 1, size(deg)
      d = deg(j)
      deg(j) = s
      s = s + d
    end do
  end subroutine counts_to_starts

  !> Sort key ascending, carrying val (insertion sort: a column has few entries).
  pure subroutine sort_pairs(key, val)
    integer, intent(inout) :: key(:), val(:)
    integer :: i, j, k, v
    do i = 2, size(key)
      k = key(i)
      v = val(i)
      j = i - 1
      do while (j >= 1)
        if (key(j) <= k) exit
        key(j + 1) = key(j)
        val(j + 1) = val(j)
        j = j - 1
      end do
      key(j + 1) = k
      val(j + 1) = v
    end do
  end subroutine sort_pairs

  !> The numeric factorization of half i from the part's values val (entries
  !> in the order of the part's pattern), and its block M_i.
  subroutine split_factorize_half(sp, i, val)
    type(split_t), intent(inout) :: sp
    integer, intent(in) :: i
    real(dp), intent(in) :: val(:)
    real(c_double), allocatable :: hv(:)
    integer :: nt, stat
    associate (h => sp%half(i))
      nt = h%n - h%nh
      allocate(hv(size(h%src)), stat=stat)
      if (stat /= 0) then
        h%status = cholmod_out_of_memory
        return
      end if
      hv = real(val(h%src), c_double)
      deallocate(h%src)               ! a factor takes its values once (c2d_chol_factorize_values)
      h%status = c2d_chol_factorize_values(h%handle, int(h%n, c_int), h%colptr, h%rowind, 0_c_int, hv)
      deallocate(hv, h%colptr, h%rowind)
      if (h%status /= cholmod_ok) return
      allocate(h%m(nt, nt))
      if (nt > 0) h%status = c2d_chol_trailing_range(h%handle, int(nt, c_int), 1_c_int, int(nt, c_int), h%m)
    end associate
  end subroutine split_factorize_half

  !> S = A(T,T) + sum_i (M_i M_i' - A(T_i,T_i)) and its Cholesky factor L_T,
  !> after both halves.  Returns the status (cholmod_not_posdef with sp%info
  !> the column of L_T when S is not positive definite).
  function split_finish(sp, val) result(status)
    type(split_t), intent(inout) :: sp
    real(dp), intent(in) :: val(:)
    integer(c_int) :: status
    real(dp), allocatable :: u(:,:)
    integer :: i, k, a, b, nt, t, info, both
    logical, allocatable :: in(:,:)

    status = sp%half(1)%status
    if (status == cholmod_ok) status = sp%half(2)%status
    if (status /= cholmod_ok) return
    nt = sp%nt
    allocate(sp%ls(nt, nt), in(nt, 2))
    sp%ls = 0.0_dp
    in = .false.
    do i = 1, 2
      associate (h => sp%half(i))
        t = h%n - h%nh
        if (t == 0) cycle
        in(h%tpos, i) = .true.
        ! M M' = J (U U') J with U = J M J upper triangular (J: the reversal):
        ! LAPACK's dlauum forms U U'
        allocate(u(t, t))
        do b = 1, t
          u(:, b) = h%m(t:1:-1, t + 1 - b)
        end do
        call dlauum('U', t, u, t, info)
        do b = 1, t
          do a = b, t
            sp%ls(h%tpos(a), h%tpos(b)) = sp%ls(h%tpos(a), h%tpos(b)) + u(t + 1 - a, t + 1 - b)
          end do
        end do
        deallocate(u)
      end associate
    end do
    do k = 1, size(sp%tt, 2)
      a = sp%tt(1, k)
      b = sp%tt(2, k)
      both = count(in(a, :) .and. in(b, :))
      sp%ls(a, b) = sp%ls(a, b) + real(1 - both, dp) * val(sp%tt(3, k))
    end do
    info = 0
    if (nt > 0) call dpotrf('L', nt, sp%ls, nt, info)
    do b = 2, nt
      sp%ls(1:b - 1, b) = 0.0_dp
    end do
    sp%info = info
    status = cholmod_ok
    if (info > 0) status = cholmod_not_posdef
  end function split_finish

  !> The part's solve or one of its halves (half: c2d_solve_*) for m columns:
  !> b and x in the part's order (forward input, backward output) or in its
  !> pivot order [H1, H2, T].
  function split_solve(sp, half, m, b, x) result(status)
    type(split_t), intent(in) :: sp
    integer(c_int), intent(in) :: half
    integer, intent(in) :: m
    real(dp), intent(in) :: b(sp%n, m)
    real(dp), intent(out) :: x(sp%n, m)
    integer(c_int) :: status
    real(dp), allocatable :: y(:,:)
    if (half == c2d_solve_whole) then
      allocate(y(sp%n, m))
      status = forward(b, y)
      if (status == cholmod_ok) status = backward(y, x)
    else if (half == c2d_solve_forward) then
      status = forward(b, x)
    else
      status = backward(b, x)
    end if

  contains

    !> y = L^-1 P b: each half forward (side by side when a team of two
    !> can be had), then L_T y_T = b_T + sum_i M_i z_i(T_i).
    function forward(bb, yy) result(st)
      real(dp), intent(in) :: bb(:,:)
      real(dp), intent(out) :: yy(:,:)
      integer(c_int) :: st
      type(block_t) :: zt(2)
      integer(c_int) :: sth(2)
      real(dp), allocatable :: rt(:,:)
      integer :: i
      !$omp parallel do schedule(static, 1)
      do i = 1, 2
        sth(i) = half_forward(i, bb, yy, zt(i)%a)
      end do
      !$omp end parallel do
      st = sth(1)
      if (st == cholmod_ok) st = sth(2)
      if (st /= cholmod_ok) return
      allocate(rt(sp%nt, m))
      rt = bb(sp%tdof, :)
      do i = 1, 2
        if (size(zt(i)%a, 1) > 0) rt(sp%half(i)%tpos, :) = rt(sp%half(i)%tpos, :) + zt(i)%a
      end do
      if (sp%nt > 0) call dtrsm('L', 'L', 'N', 'N', sp%nt, m, 1.0_dp, sp%ls, sp%nt, rt, sp%nt)
      yy(sp%n - sp%nt + 1:, :) = rt
    end function forward

    !> Half i forward: y(H_i) into yy, and zt = M_i z(T_i) = -B_i y_i.
    function half_forward(i, bb, yy, zt) result(st)
      integer, intent(in) :: i
      real(dp), intent(in) :: bb(:,:)
      real(dp), intent(inout) :: yy(:,:)
      real(dp), allocatable, intent(out) :: zt(:,:)
      integer(c_int) :: st
      real(dp), allocatable :: bh(:,:), zh(:,:)
      integer :: off, t
      associate (h => sp%half(i))
        t = h%n - h%nh
        off = 0
        if (i == 2) off = sp%half(1)%nh
        allocate(bh(h%n, m), zh(h%n, m), zt(t, m))
        bh = 0.0_dp
        bh(1:h%nh, :) = bb(h%dof(1:h%nh), :)
        st = c2d_chol_solve_half(h%handle, c2d_solve_forward, int(h%n, c_int), int(m, c_int), bh, zh)
        if (st /= cholmod_ok) return
        yy(off + 1:off + h%nh, :) = zh(1:h%nh, :)
        if (t > 0) then
          call dtrmm('L', 'L', 'N', 'N', t, m, 1.0_dp, h%m, t, zh(h%nh + 1, 1), h%n)
          zt = zh(h%nh + 1:, :)
        end if
      end associate
    end function half_forward

    !> x = P' L'^-1 y: x_T = L_T'^-1 y_T, then each half backward from
    !> [y(H_i); M_i' x(T_i)] (side by side when a team of two can be had).
    function backward(yy, xx) result(st)
      real(dp), intent(in) :: yy(:,:)
      real(dp), intent(out) :: xx(:,:)
      integer(c_int) :: st
      integer(c_int) :: sth(2)
      real(dp), allocatable :: xt(:,:)
      integer :: i
      allocate(xt(sp%nt, m))
      xt = yy(sp%n - sp%nt + 1:, :)
      if (sp%nt > 0) call dtrsm('L', 'L', 'T', 'N', sp%nt, m, 1.0_dp, sp%ls, sp%nt, xt, sp%nt)
      xx(sp%tdof, :) = xt
      !$omp parallel do schedule(static, 1)
      do i = 1, 2
        sth(i) = half_backward(i, yy, xt, xx)
      end do
      !$omp end parallel do
      st = sth(1)
      if (st == cholmod_ok) st = sth(2)
    end function backward

    !> Half i backward: x(H_i) into xx.
    function half_backward(i, yy, xt, xx) result(st)
      integer, intent(in) :: i
      real(dp), intent(in) :: yy(:,:), xt(:,:)
      real(dp), intent(inout) :: xx(:,:)
      integer(c_int) :: st
      real(dp), allocatable :: yh(:,:), xh(:,:)
      integer :: off, t
      associate (h => sp%half(i))
        t = h%n - h%nh
        off = 0
        if (i == 2) off = sp%half(1)%nh
        allocate(yh(h%n, m), xh(h%n, m))
        yh(1:h%nh, :) = yy(off + 1:off + h%nh, :)
        yh(h%nh + 1:, :) = xt(h%tpos, :)
        if (t > 0) call dtrmm('L', 'L', 'T', 'N', t, m, 1.0_dp, h%m, t, yh(h%nh + 1, 1), h%n)
        st = c2d_chol_solve_half(h%handle, c2d_solve_backward, int(h%n, c_int), int(m, c_int), yh, xh)
        if (st /= cholmod_ok) return
        xx(h%dof(1:h%nh), :) = xh(1:h%nh, :)
      end associate
    end function half_backward
  end function split_solve

  !> Rows and columns first..first+count-1 of the trailing block (the part's
  !> `last`, nlast of them) of L_T into lcc(count, count).
  function split_trailing_range(sp, nlast, first, count, lcc) result(status)
    type(split_t), intent(in) :: sp
    integer, intent(in) :: nlast, first, count
    real(dp), intent(out) :: lcc(count, count)
    integer(c_int) :: status
    integer :: k0
    status = c2d_chol_bad_argument
    if (.not. allocated(sp%ls) .or. nlast /= sp%nt - sp%nsep) return
    if (first < 1 .or. count < 1 .or. first - 1 + count > nlast) return
    k0 = sp%nsep + first - 1
    lcc = sp%ls(k0 + 1:k0 + count, k0 + 1:k0 + count)
    status = cholmod_ok
  end function split_trailing_range

  !> The last row (within the trailing block) of its diagonal block that
  !> starts at `first`.
  function split_block_end(sp, nlast, first, last_row) result(status)
    type(split_t), intent(in) :: sp
    integer, intent(in) :: nlast, first
    integer(c_int), intent(out) :: last_row
    integer(c_int) :: status
    integer :: j, e, r
    status = c2d_chol_bad_argument
    last_row = int(first, c_int)
    if (.not. allocated(sp%ls) .or. nlast /= sp%nt - sp%nsep .or. first < 1 .or. first > nlast) return
    e = sp%nsep + first
    j = e
    do while (j <= e)
      do r = sp%nt, e + 1, -1
        if (sp%ls(r, j) /= 0.0_dp) then
          e = r
          exit
        end if
      end do
      j = j + 1
    end do
    last_row = int(e - sp%nsep, c_int)
    status = cholmod_ok
  end function split_block_end

  !> nnz(L), flops and memory (bytes) of the split part: the halves' factors
  !> without their blocks M_i, and L_T; M_i M_i' and L_T in the flops.
  subroutine split_stats(sp, lnz, flops, memory)
    type(split_t), intent(in) :: sp
    integer(i8), intent(out) :: lnz, memory
    real(dp), intent(out) :: flops
    integer(c_int64_t) :: hl, hm
    real(c_double) :: hf, ta, tf
    real(dp) :: t
    integer :: i
    t = real(sp%nt, dp)
    lnz = int(sp%nt, i8) * int(sp%nt + 1, i8) / 2
    flops = t**3 / 3.0_dp
    memory = 8_i8 * int(sp%nt, i8)**2
    do i = 1, 2
      if (.not. c_associated(sp%half(i)%handle)) cycle
      call c2d_chol_stats(sp%half(i)%handle, hl, hf, hm, ta, tf)
      t = real(sp%half(i)%n - sp%half(i)%nh, dp)
      lnz = lnz + int(hl, i8) - int(t * (t + 1.0_dp) / 2.0_dp, i8)
      flops = flops + real(hf, dp) + t**3 / 3.0_dp
      memory = memory + int(hm, i8) + int(8.0_dp * t * t, i8)
    end do
  end subroutine split_stats

  !> Where the factorization failed: the pivot (of [H1, H2, T]) and the
  !> part's dof; 0, 0 when it did not.
  subroutine split_failure(sp, column, equation)
    type(split_t), intent(in) :: sp
    integer, intent(out) :: column, equation
    integer(c_int) :: c, e
    integer :: i
    column = 0
    equation = 0
    do i = 1, 2
      if (sp%half(i)%status == cholmod_not_posdef) then
        call c2d_chol_minor(sp%half(i)%handle, c, e)
        call half_pivot(sp, i, int(c), int(e), column, equation)
        return
      end if
    end do
    if (sp%info > 0) then
      column = sp%n - sp%nt + sp%info
      equation = sp%tdof(sp%info)
    end if
  end subroutine split_failure

  !> The least L(k,k)^2 / A(p_k,p_k) over the halves' pivots (H_i and T_i)
  !> and over L_T, with its pivot and dof as split_failure gives them; val: the
  !> part's values, entries in the order of its pattern (A(t,t) for L_T).
  subroutine split_min_ratio(sp, val, ratio, column, equation)
    type(split_t), intent(in) :: sp
    real(dp), intent(in) :: val(:)
    real(dp), intent(out) :: ratio
    integer, intent(out) :: column, equation
    real(c_double) :: r
    integer(c_int) :: c, e
    real(dp) :: d
    integer :: i, k
    ratio = huge(1.0_dp)
    column = 0
    equation = 0
    do i = 1, 2
      call c2d_chol_min_pivot_ratio(sp%half(i)%handle, r, c, e)
      if (.not. (real(r, dp) >= ratio)) then
        ratio = real(r, dp)
        call half_pivot(sp, i, int(c), int(e), column, equation)
      end if
    end do
    do k = 1, size(sp%tt, 2)
      if (sp%tt(1, k) /= sp%tt(2, k)) cycle
      i = sp%tt(1, k)
      d = val(sp%tt(3, k))
      r = 0.0_dp
      if (d > 0.0_dp) r = sp%ls(i, i)**2 / d
      if (.not. (real(r, dp) >= ratio)) then
        ratio = real(r, dp)
        column = sp%n - sp%nt + i
        equation = sp%tdof(i)
      end if
    end do
  end subroutine split_min_ratio

  !> A half's pivot c and dof e (1-based, its own) as the part's.
  pure subroutine half_pivot(sp, i, c, e, column, equation)
    type(split_t), intent(in) :: sp
    integer, intent(in) :: i, c, e
    integer, intent(out) :: column, equation
    equation = 0
    if (e >= 1) equation = sp%half(i)%dof(e)
    if (c <= sp%half(i)%nh) then
      column = c
      if (i == 2) column = column + sp%half(1)%nh
    else
      column = sp%n - sp%nt + sp%half(i)%tpos(c - sp%half(i)%nh)
    end if
  end subroutine half_pivot

  !> Release the halves' handles.
  subroutine split_free(sp)
    type(split_t), intent(inout) :: sp
    integer :: i
    do i = 1, 2
      if (c_associated(sp%half(i)%handle)) call c2d_chol_destroy(sp%half(i)%handle)
      sp%half(i)%handle = c_null_ptr
    end do
  end subroutine split_free

end module split_factor
