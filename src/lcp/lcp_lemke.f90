!> lcp_lemke: LCP(W, q) by Lemke's complementary pivoting.
!>
!> Complementary pivoting on the tableau [I, -Ws, -e | qs] of the scaled
!> problem (lcp_scaling; rows w - Ws zs - e z0 = qs, covering vector e =
!> ones), dense, one rank-1 update (dger) per pivot, O(n^2) per pivot.  The
!> minimum ratio test is lexicographic: ties in the ratio are broken by the
!> rows of the current basis inverse, which the tableau carries in its w
!> columns; this rules out cycling on degenerate problems.  z0 leaves at once
!> when it ties.  For a PSD W, termination on a ray proves that the LCP has
!> no solution.  On success the basic solution is refined by two steps of
!> iterative refinement with the tableau's basis inverse, tiny negative z are
!> set to zero, and w = q + W z is recomputed.
!>
!> Why it exists: the exact pivoting method, kept whole in one file (the
!> tableau, its pivot, ratio test and refinement).  Who may use it: through
!> lcp_solvers.
!>
!> Programming interface
!>   solve_lcp_lemke(W, q, z, opts, rep)          z intent(out); W PSD, zero rows dropped
!>   solve_lcp_lemke_scaled(M, q, d, z, opts, rep)  on D M D, D q with the caller's d, no row dropped:
!>                                                for a non-symmetric M (frictional contact)
module lcp_lemke
  use kinds, only: dp
  use lapack_interfaces, only: daxpy, dgemv, dger
  use strings, only: int_to_str
  use lcp_scaling, only: lcp_options_t, lcp_report_t, scaled_lcp_t, prepare_lcp, measure_solution, scale_of, &
                         set_report, report_out_of_memory, residual_outcome, check_lcp_options
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_lcp_lemke, solve_lcp_lemke_scaled

  real(dp), parameter :: pivot_ratio = 1.0e-11_dp          ! smallest pivot, relative to the column
  real(dp), parameter :: tie_ratio = 1.0e-12_dp            ! relative width of a tie

contains

  !> Solve LCP(W, q) by Lemke's complementary pivoting (lexicographic, covering
  !> vector ones) on the scaled problem.
  !>   W     (in)  (n, n) PSD matrix, finite
  !>   q     (in)  (n) finite
  !>   z     (out) (n) the solution when rep%info = 0 or 4; on failure the z part
  !>               of the last almost-complementary point (finite, >= 0); zero
  !>               on an argument error or a zero row with negative q_i
  !>   opts  (in)  tol, maxit (omega is not used)
  !>   rep   (out) info 0 solved, 1 no solution (ray termination or infeasible
  !>               zero row), 2 pivot limit, 4 residual above tol, -k argument k
  !>               invalid; iterations = pivots; residual; complementarity; message
  subroutine solve_lcp_lemke(W, q, z, opts, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(out) :: rep
    type(scaled_lcp_t) :: p

    z = 0.0_dp
    call prepare_lcp(W, q, z, opts, .false., p, rep)
    if (rep%info /= 0) return
    call lemke_solution(W, q, p, opts, 'W ill-conditioned', z, rep)
  end subroutine solve_lcp_lemke

  !> Solve LCP(M, q) by Lemke's complementary pivoting (lexicographic, covering
  !> vector ones) on the problem scaled with a scaling chosen by the caller,
  !>     Ms = D M D,   qs = D q,   z = D zs,   D = diag(d),
  !> keeping every row: unlike solve_lcp_lemke, a zero diagonal entry does not
  !> mark a redundant row, so M may be any square matrix, e.g. the
  !> non-symmetric LCP of frictional contact whose slip rows have a zero
  !> diagonal.  d should make Ms of unit size.  Residual and complementarity
  !> are those of the module header with this d (the scaled natural residual).
  !>   M     (in)  (n, n) finite
  !>   q     (in)  (n) finite
  !>   d     (in)  (n) the scaling, finite and > 0
  !>   z     (out) (n) the solution when rep%info = 0 or 4; on failure the z part
  !>               of the last almost-complementary point (finite, >= 0); zero
  !>               on an argument error
  !>   opts  (in)  tol, maxit (0: 10 n + 100 pivots); omega is not used
  !>   rep   (out) info 0 solved, 1 ray termination (no solution exists when M is
  !>               copositive-plus, e.g. positive semi-definite; otherwise none
  !>               was found), 2 pivot limit, 4 residual above tol, -k argument k
  !>               invalid; iterations = pivots; residual; complementarity; message
  subroutine solve_lcp_lemke_scaled(M, q, d, z, opts, rep)
    real(dp), intent(in) :: M(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: d(:)
    real(dp), intent(out) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(out) :: rep
    type(scaled_lcp_t) :: p
    integer :: n, i, j, st

    z = 0.0_dp
    rep%info = 0
    n = size(q)
    if (size(M, 1) /= n .or. size(M, 2) /= n) then
      call set_report(rep, -1, 'LCP: M is ' // int_to_str(size(M, 1)) // ' x ' // int_to_str(size(M, 2)) // &
        ' (expected ' // int_to_str(n) // ' x ' // int_to_str(n) // ', the size of q)')
    else if (.not. all(ieee_is_finite(M))) then
      call set_report(rep, -1, 'LCP: M has non-finite entries')
    else if (.not. all(ieee_is_finite(q))) then
      call set_report(rep, -2, 'LCP: q has non-finite entries')
    else if (size(d) /= n) then
      call set_report(rep, -3, 'LCP: d has ' // int_to_str(size(d)) // ' entries (expected ' // &
        int_to_str(n) // ')')
    else if (.not. all(ieee_is_finite(d) .and. d > 0.0_dp)) then
      call set_report(rep, -3, 'LCP: the scaling d has entries that are not finite and > 0')
    else if (size(z) /= n) then
      call set_report(rep, -4, 'LCP: z has ' // int_to_str(size(z)) // ' entries (expected ' // &
        int_to_str(n) // ')')
    else
      call check_lcp_options(opts, -5, rep)
    end if
    if (rep%info /= 0) return

    ! Every row kept: the scaled problem is the whole of D M D.
    p%n = n
    p%m = n
    allocate(p%d(n), p%rows(n), p%ws(n, n), p%qs(n), stat=st)
    if (st /= 0) then
      call report_out_of_memory(rep, 'scaling the LCP (' // int_to_str(n) // ' rows)', &
                                8.0_dp * real(n, dp) * real(n, dp))
      return
    end if
    p%d = d
    p%rows = [(i, i = 1, n)]
    do j = 1, n
      p%ws(:, j) = d * M(:, j) * d(j)                  ! (D M D)_ij = d_i M_ij d_j
    end do
    p%qs = d * q                                       ! qs = D q
    p%qscale = 1.0_dp
    if (n > 0) p%qscale = scale_of(maxval(abs(p%qs)))

    call lemke_solution(M, q, p, opts, 'M ill-conditioned or badly scaled', z, rep)
    if (rep%info == 1) then
      rep%message = 'Lemke: ray termination after ' // int_to_str(rep%iterations) // &
        ' pivots (no solution found; when M is copositive-plus, e.g. positive semi-definite,' // &
        ' the LCP has none)'
    end if
  end subroutine solve_lcp_lemke_scaled

  !> Lemke on the scaled problem p of LCP(W, q), z read off, polished and
  !> measured, and the outcome of a finished run.
  !>   W, q   (in)    the problem
  !>   p      (in)    its scaled form (prepare_lcp, or every row kept)
  !>   opts   (in)    tol, maxit (0: 10 n + 100 pivots)
  !>   cause  (in)    what a residual above tol points to
  !>   z      (inout) zero on entry; z = D zs on the rows kept on exit
  !>   rep    (inout) info 0 solved, 1 ray, 2 pivot limit, 4 residual above tol;
  !>                  iterations, residual, complementarity, message
  subroutine lemke_solution(W, q, p, opts, cause, z, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    type(scaled_lcp_t), intent(in) :: p
    type(lcp_options_t), intent(in) :: opts
    character(len=*), intent(in) :: cause
    real(dp), intent(inout) :: z(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: zs(:)
    integer :: maxit

    maxit = opts%maxit
    if (maxit == 0) maxit = 10 * p%n + 100
    allocate(zs(p%m))
    call lemke_scaled(p, maxit, zs, rep)
    z(p%rows) = p%d(p%rows) * zs                      ! z = D zs
    where (z < 0.0_dp) z = 0.0_dp                     ! polish: tiny negatives
    call measure_solution(W, q, p%d, z, rep)

    if (rep%info == 0) call residual_outcome(rep, opts%tol, 'Lemke: solved in ' // int_to_str(rep%iterations) // &
      ' pivots', 'Lemke: terminated after ' // int_to_str(rep%iterations) // ' pivots', cause)
  end subroutine lemke_solution

  !> Lemke's algorithm on the scaled problem p (p%m > 0 rows).
  !>   p      (in)    the scaled problem
  !>   maxit  (in)    pivot limit, > 0
  !>   zs     (out)   (m) the z part of the final basic solution, >= 0
  !>   rep    (inout) info (0, 1 ray, 2 limit), iterations, message on failure
  subroutine lemke_scaled(p, maxit, zs, rep)
    type(scaled_lcp_t), intent(in) :: p
    integer, intent(in) :: maxit
    real(dp), intent(out) :: zs(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: t(:, :), xb(:)
    integer, allocatable :: basis(:)
    integer :: m, jz0, jrhs, i, r, entering, leaving, npiv, st
    real(dp) :: qmin

    m = p%m
    zs = 0.0_dp
    rep%iterations = 0
    if (m == 0) return
    if (all(p%qs >= 0.0_dp)) return                   ! z = 0, w = q >= 0

    ! Tableau [I, -Ws, -e | qs]: columns 1..m w, m+1..2m z, jz0 z0, jrhs the rhs.
    jz0 = 2 * m + 1
    jrhs = 2 * m + 2
    allocate(t(m, jrhs), basis(m), stat=st)
    if (st /= 0) then
      call report_out_of_memory(rep, 'solving the LCP by Lemke (a tableau of ' // int_to_str(m) // ' rows)', &
                                8.0_dp * real(m, dp) * real(jrhs, dp))
      return
    end if
    t = 0.0_dp
    do i = 1, m
      t(i, i) = 1.0_dp
      basis(i) = i
    end do
    t(:, m + 1:2 * m) = -p%ws
    t(:, jz0) = -1.0_dp
    t(:, jrhs) = p%qs

    ! First pivot: z0 enters at the row of the most negative q; among exact ties
    ! the last row, which keeps every row (rhs, B^-1 row) lexicographically positive.
    qmin = minval(p%qs)
    r = 0
    do i = 1, m
      if (p%qs(i) == qmin) r = i
    end do
    call pivot(t, r, jz0)
    leaving = basis(r)
    basis(r) = jz0
    npiv = 1
    entering = complement(leaving, m)

    do
      if (npiv >= maxit) then
        rep%info = 2
        rep%stopped = 'pivot limit'
        rep%message = 'Lemke: pivot limit ' // int_to_str(maxit) // &
          ' reached without a solution (degenerate or ill-conditioned W)'
        exit
      end if
      call lexicographic_ratio_test(t, m, entering, basis, maxval(abs(p%qs)), r)
      if (r == 0) then
        rep%info = 1
        rep%stopped = 'ray'
        rep%message = 'Lemke: ray termination at pivot ' // int_to_str(npiv + 1) // &
          ' (the LCP has no solution: no z >= 0 gives q + W z >= 0 when W is positive' // &
          ' semi-definite; entering ' // variable_name(entering, m, p%rows) // ')'
        exit
      end if
      call pivot(t, r, entering)
      npiv = npiv + 1
      leaving = basis(r)
      basis(r) = entering
      if (leaving == jz0) exit                        ! z0 = 0: complementary solution
      entering = complement(leaving, m)
    end do
    rep%iterations = npiv

    allocate(xb(m))
    xb = t(:, jrhs)
    if (rep%info == 0) call refine_basic_solution(p, t(:, 1:m), basis, xb)
    do i = 1, m
      if (basis(i) > m .and. basis(i) <= 2 * m) zs(basis(i) - m) = max(0.0_dp, xb(i))
    end do
  end subroutine lemke_scaled

  !> The complement of tableau variable v (w_i <-> z_i); z0 has none.
  pure integer function complement(v, m)
    integer, intent(in) :: v, m
    if (v <= m) then
      complement = v + m
    else
      complement = v - m
    end if
  end function complement

  !> 'z(i)' or 'w(i)' with the original index i, for messages.
  function variable_name(v, m, rows) result(s)
    integer, intent(in) :: v, m
    integer, intent(in) :: rows(:)
    character(len=:), allocatable :: s
    if (v <= m) then
      s = 'w(' // int_to_str(rows(v)) // ')'
    else if (v <= 2 * m) then
      s = 'z(' // int_to_str(rows(v - m)) // ')'
    else
      s = 'z0'
    end if
  end function variable_name

  !> Gauss-Jordan pivot of the tableau on t(r, e):  row r /= t(r, e), then
  !> t <- t - t(:, e) t(r, :) on the other rows (one rank-1 update, dger).
  subroutine pivot(t, r, e)
    real(dp), intent(inout) :: t(:, :)
    integer, intent(in) :: r, e
    real(dp), allocatable :: col(:), row(:)
    integer :: m, nc

    m = size(t, 1)
    nc = size(t, 2)
    t(r, :) = t(r, :) / t(r, e)
    row = t(r, :)
    col = t(:, e)
    col(r) = 0.0_dp
    call dger(m, nc, -1.0_dp, col, 1, row, 1, t, m)  ! t = t - col row'
    t(:, e) = 0.0_dp
    t(r, e) = 1.0_dp
  end subroutine pivot

  !> Lexicographic minimum ratio test for entering column e.  Among the rows
  !> with t(i, e) > 0, the leaving row minimises (rhs_i, B^-1(i, :)) / t(i, e)
  !> lexicographically (B^-1 = t(:, 1:m)); z0 leaves whenever its row ties.
  !>   t      (in)  (m, 2m+2) tableau
  !>   m      (in)  rows
  !>   e      (in)  entering column
  !>   basis  (in)  (m) basic variable of each row
  !>   qnorm  (in)  ||qs||_inf > 0, the scale of the basic values
  !>   r      (out) leaving row; 0 when no entry of column e is positive (ray)
  subroutine lexicographic_ratio_test(t, m, e, basis, qnorm, r)
    real(dp), intent(in) :: t(:, :)
    integer, intent(in) :: m, e
    integer, intent(in) :: basis(:)
    real(dp), intent(in) :: qnorm
    integer, intent(out) :: r
    real(dp), allocatable :: ratio(:)
    integer, allocatable :: cand(:)
    real(dp) :: ptol, theta, vmin, v
    integer :: i, k, nc, nk, jz0, jrhs

    jz0 = 2 * m + 1
    jrhs = 2 * m + 2
    r = 0
    ptol = pivot_ratio * max(1.0_dp, maxval(abs(t(:, e))))
    allocate(cand(m), ratio(m))
    nc = 0
    do i = 1, m
      if (t(i, e) > ptol) then
        nc = nc + 1
        cand(nc) = i
        ratio(nc) = max(t(i, jrhs), 0.0_dp) / t(i, e)
      end if
    end do
    if (nc == 0) return

    ! Primary ratio: keep the ties.
    theta = minval(ratio(1:nc))
    nk = 0
    do k = 1, nc
      if (ratio(k) <= theta + tie_ratio * max(theta, qnorm)) then
        nk = nk + 1
        cand(nk) = cand(k)
      end if
    end do
    do k = 1, nk
      if (basis(cand(k)) == jz0) then
        r = cand(k)
        return
      end if
    end do

    ! Lexicographic tie-break on the columns of B^-1.
    k = 0
    do while (nk > 1 .and. k < m)
      k = k + 1
      vmin = huge(1.0_dp)
      do i = 1, nk
        vmin = min(vmin, t(cand(i), k) / t(cand(i), e))
      end do
      nc = 0
      do i = 1, nk
        v = t(cand(i), k) / t(cand(i), e)
        if (v <= vmin + tie_ratio * max(1.0_dp, abs(vmin))) then
          nc = nc + 1
          cand(nc) = cand(i)
        end if
      end do
      nk = nc
    end do

    ! Still tied only through round-off: take the largest pivot.
    r = cand(1)
    do i = 2, nk
      if (t(cand(i), e) > t(r, e)) r = cand(i)
    end do
  end subroutine lexicographic_ratio_test

  !> Iterative refinement of the final basic solution:  B xb = qs with B the
  !> basis columns of [I, -Ws] and binv = B^-1 as carried by the tableau;
  !> xb <- xb + binv (qs - B xb), kept only while the residual decreases.
  !>   p      (in)    the scaled problem
  !>   binv   (in)    (m, m) basis inverse
  !>   basis  (in)    (m) basic variables (no z0)
  !>   xb     (inout) (m) basic values
  subroutine refine_basic_solution(p, binv, basis, xb)
    type(scaled_lcp_t), intent(in) :: p
    real(dp), intent(in) :: binv(:, :)
    integer, intent(in) :: basis(:)
    real(dp), intent(inout) :: xb(:)
    real(dp), allocatable :: res(:), xnew(:)
    real(dp) :: rnorm, rnew
    integer :: step, m

    m = p%m
    allocate(res(m), xnew(m))
    call basis_residual(p, basis, xb, res)
    rnorm = maxval(abs(res))
    do step = 1, 2
      if (rnorm == 0.0_dp) exit
      xnew = xb
      call dgemv('N', m, m, 1.0_dp, binv, m, res, 1, 1.0_dp, xnew, 1)   ! x = x + B^-1 r
      call basis_residual(p, basis, xnew, res)
      rnew = maxval(abs(res))
      if (.not. rnew < rnorm) exit
      xb = xnew
      rnorm = rnew
    end do
  end subroutine refine_basic_solution

  !> res = qs - B xb, B the basis columns of [I, -Ws].
  subroutine basis_residual(p, basis, xb, res)
    type(scaled_lcp_t), intent(in) :: p
    integer, intent(in) :: basis(:)
    real(dp), intent(in) :: xb(:)
    real(dp), intent(out) :: res(:)
    integer :: k, m

    m = p%m
    res = p%qs
    do k = 1, m
      if (basis(k) <= m) then
        res(basis(k)) = res(basis(k)) - xb(k)                       ! column e_j of w_j
      else
        call daxpy(m, xb(k), p%ws(:, basis(k) - m), 1, res, 1)     ! column -Ws(:, j) of z_j
      end if
    end do
  end subroutine basis_residual

end module lcp_lemke
