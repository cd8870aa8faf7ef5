!> lemke_tableau: the tableau of lcp_lemke's complementary pivoting and the
!> guards that keep its decisions on what the data say.
!>
!> The tableau B^-1 [I, -Ws, -e | qs] of the scaled problem (lcp_scaling),
!> its rank-1 pivot, the lexicographic minimum ratio test, and the round-off
!> measures lcp_lemke's header describes: the drift of the basic solution and
!> the tableau recomputed from the data by an LU factorization of the basis
!> (dgesv), z0's exit weighed at a tie against an a-posteriori error bound
!> (z0_ties), the basic solution refined on its basis, a ray's direction.
!>
!> Why it exists: lcp_lemke's path (which variable enters and leaves, when
!> it stops) reads as the algorithm when the tableau's algebra is apart; the
!> two are one method and are used together only.  Who may use it: lcp_lemke.
!>
!> Programming interface
!>   type(tableau_t)                                the tableau (m, t, basis, refreshed)
!>   initial_tableau(p, t)                          [I, -Ws, -e | qs] of the all-w basis
!>   complement(v, m), variable_name(v, m, rows)    the complement of variable v, its name for messages
!>   pivot(t, r, e)                                 Gauss-Jordan on row r, column e (one dger)
!>   lexicographic_ratio_test(t, m, e, basis, qnorm, r)   the leaving row of entering column e (0: ray)
!>   z0_exit_violation(t, e, r0), z0_ties(p, tb, e, r0)   how far below zero z0's exit would push a basic value
!>   try_z0_exit(p, tb, r0, e, tol, done, zs_kept, res_kept)  z0 leaves at a tie when the data agree
!>   watch_drift(p, tb, npiv), may_refresh, refresh_tableau(p, tb, npiv)   the drift and the recomputation
!>   solves_without_z0(p, tb, tol), ray_direction(tb, e, dzs)   a ray's point with z0 dropped, its direction
!>   refine_basic_solution(p, binv, basis, xb), basic_z(basis, xb, m), zs_residual(p, zs)
!>   and the pivoting's tolerances (pivot_ratio, tie_ratio, near_tie_ratio, small_pivot_ratio, drift_period)
module lemke_tableau
  use kinds, only: dp
  use lapack_interfaces, only: daxpy, dgemv, dger, dgesv
  use strings, only: int_to_str
  use lcp_scaling, only: scaled_lcp_t
  implicit none
  private
  public :: tableau_t, initial_tableau, complement, variable_name, pivot, lexicographic_ratio_test, &
            z0_exit_violation, try_z0_exit, watch_drift, may_refresh, refresh_tableau, solves_without_z0, &
            ray_direction, refine_basic_solution, basic_z, zs_residual, z0_ties
  public :: pivot_ratio, tie_ratio, near_tie_ratio, small_pivot_ratio, drift_period

  ! Tolerances of the pivoting, on the scaled data (entries of unit size):
  ! smallest pivot, relative to its column: an entry below it is the
  ! round-off of a zero
  real(dp), parameter :: pivot_ratio = 1.0e-11_dp
  ! relative width of a tie between two blocking rows in the lexicographic test
  real(dp), parameter :: tie_ratio = 1.0e-12_dp
  ! z0's exit is weighed (z0_ties, O(m^2)) only when it would push no basic
  ! value below -near_tie_ratio ||qs||: wider than the tableau's errors seen
  ! (3.4e-8 after a run of rank-1 updates, 5e-10 on a singular basis)
  real(dp), parameter :: near_tie_ratio = 1.0e-6_dp
  ! drift of the basic solution above which the tableau is recomputed: a
  ! fresh tableau has ~ m eps, and the ratio test must tell ties of 1e-12
  real(dp), parameter :: drift_ratio = 1.0e-12_dp
  ! a pivot below this fraction of its column's largest entry amplifies the
  ! tableau's errors by its inverse: the drift is measured after it
  real(dp), parameter :: small_pivot_ratio = 1.0e-4_dp
  ! z0's exit at a tie ends the run at once when its refined point's natural
  ! residual is within a thousand roundings (exact ties measure 2e-16 on the
  ! skate's LCPs); a point within tol only is kept aside, in case the
  ! ordinary path fails or ends less accurate (a singular W: the window of
  ! z0_ties is then wide, 5e-10, and such a point is good to 5e-12 only)
  real(dp), parameter :: exact_ratio = 1.0e3_dp * epsilon(1.0_dp)
  ! roundings of one entry of the data or of a product |B| |x| in the
  ! a-posteriori error bound of z0_ties
  real(dp), parameter :: tie_roundoffs = 8.0_dp
  ! pivots between two measures of the drift (each costs about m * (z basic)
  ! flops, a fraction of one pivot's 4 m^2)
  integer, parameter :: drift_period = 16

  !> The tableau of the scaled problem and its basis.
  type :: tableau_t
    integer :: m = 0                      !< rows
    real(dp), allocatable :: t(:, :)      !< (m, 2m+2) B^-1 [I, -Ws, -e | qs]
    integer, allocatable :: basis(:)      !< (m) basic variable of each row: 1..m w, m+1..2m z, 2m+1 z0
    integer :: refreshed = 0              !< pivot count at the last recomputation (0: never)
  end type tableau_t

contains

  !> The tableau of the all-w basis, [I, -Ws, -e | qs], e = ones.
  subroutine initial_tableau(p, t)
    type(scaled_lcp_t), intent(in) :: p
    real(dp), intent(out) :: t(:, :)
    integer :: m, i
    m = p%m
    t = 0.0_dp
    do i = 1, m
      t(i, i) = 1.0_dp
    end do
    t(:, m + 1:2 * m) = -p%ws
    t(:, 2 * m + 1) = -1.0_dp
    t(:, 2 * m + 2) = p%qs
  end subroutine initial_tableau

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

  !> How far below zero z0 leaving at its own ratio would push the other
  !> basic values: max_i (theta0 t(i, e) - rhs_i), theta0 = rhs_r0 / t(r0, e);
  !> huge when z0 cannot leave on column e (t(r0, e) not positive).
  !>   t   (in) (m, 2m+2) tableau
  !>   e   (in) entering column
  !>   r0  (in) z0's row
  pure real(dp) function z0_exit_violation(t, e, r0) result(v)
    real(dp), intent(in) :: t(:, :)
    integer, intent(in) :: e, r0
    real(dp) :: theta0
    integer :: i, jrhs
    v = huge(1.0_dp)
    jrhs = size(t, 2)
    if (.not. t(r0, e) > pivot_ratio * max(1.0_dp, maxval(abs(t(:, e))))) return
    theta0 = max(t(r0, jrhs), 0.0_dp) / t(r0, e)
    v = 0.0_dp
    do i = 1, size(t, 1)
      if (i /= r0) v = max(v, theta0 * t(i, e) - t(i, jrhs))   ! -(rhs_i - theta0 t(i, e))
    end do
  end function z0_exit_violation

  !> Whether z0's exit on column e ties with the ordinary one to round-off:
  !> every basic value it would push below zero, v_i = theta0 t(i, e) - rhs_i
  !> (theta0 = rhs_r0 / t(r0, e)), is within the error of the tableau's
  !> numbers, bounded a posteriori from the data:  for x = rhs or t(:, e),
  !> solutions of B x = b with b = qs or the entering column of [I, -Ws],
  !>     |x - x_exact| <= |B^-1| (|b - B x| + c eps (|b| + |B| |x|)),
  !> c = tie_roundoffs, B^-1 as the tableau carries it.
  !>   p, tb  (in) the scaled problem and its tableau
  !>   e, r0  (in) the entering column, z0's row
  logical function z0_ties(p, tb, e, r0) result(ties)
    type(scaled_lcp_t), intent(in) :: p
    type(tableau_t), intent(in) :: tb
    integer, intent(in) :: e, r0
    real(dp), allocatable :: b(:), err_rhs(:), err_col(:), rhs(:), col(:)
    real(dp) :: theta0, err_theta0
    integer :: m, i

    m = tb%m
    ties = .false.
    allocate(rhs(m), col(m), b(m))
    rhs = tb%t(:, 2 * m + 2)
    col = tb%t(:, e)
    if (.not. col(r0) > 0.0_dp) return
    err_rhs = solution_error(p, tb, p%qs, rhs)
    b = 0.0_dp
    if (e <= m) then
      b(e) = 1.0_dp                                    ! w_e: e_e
    else
      b = -p%ws(:, e - m)                              ! z_j: -Ws(:, j)
    end if
    err_col = solution_error(p, tb, b, col)
    theta0 = max(rhs(r0), 0.0_dp) / col(r0)
    err_theta0 = (err_rhs(r0) + theta0 * err_col(r0)) / col(r0)
    ties = .true.
    do i = 1, m
      if (i == r0) cycle
      if (theta0 * col(i) - rhs(i) > err_rhs(i) + theta0 * err_col(i) + abs(col(i)) * err_theta0) ties = .false.
    end do
  end function z0_ties

  !> The a-posteriori error bound |B^-1| (|b - B x| + c eps (|b| + |B| |x|))
  !> of x as a solution of B x = b (z0_ties).
  function solution_error(p, tb, b, x) result(err)
    type(scaled_lcp_t), intent(in) :: p
    type(tableau_t), intent(in) :: tb
    real(dp), intent(in) :: b(:), x(:)
    real(dp), allocatable :: err(:)
    real(dp), allocatable :: res(:), size_bx(:)
    integer :: k, m, j
    m = tb%m
    allocate(res(m), size_bx(m))
    res = b
    size_bx = abs(b)
    do k = 1, m
      j = tb%basis(k)
      if (j <= m) then
        res(j) = res(j) - x(k)                                          ! column e_j
        size_bx(j) = size_bx(j) + abs(x(k))
      else if (j <= 2 * m) then
        res = res + x(k) * p%ws(:, j - m)                               ! column -Ws(:, j)
        size_bx = size_bx + abs(x(k)) * abs(p%ws(:, j - m))
      else
        res = res + x(k)                                                ! column -e
        size_bx = size_bx + abs(x(k))
      end if
    end do
    err = matmul(abs(tb%t(:, 1:m)), abs(res) + tie_roundoffs * epsilon(1.0_dp) * size_bx)
  end function solution_error

  !> Pivot z0 out of row r0 on column e and refine the basic solution on the
  !> data: kept when its natural residual is at round-off (exact_ratio);
  !> otherwise the tableau is left as it was, and the point, when within
  !> tol, is kept aside if it is the best so far.
  !>   p     (in)    the scaled problem
  !>   tb    (inout) the tableau
  !>   r0, e (in)    z0's row, the entering column
  !>   tol   (in)    the residual target
  !>   done  (out)   .true. when the pivot is kept (the run ends solved)
  !>   zs_kept, res_kept (inout) the best point kept aside and its residual
  subroutine try_z0_exit(p, tb, r0, e, tol, done, zs_kept, res_kept)
    type(scaled_lcp_t), intent(in) :: p
    type(tableau_t), intent(inout) :: tb
    integer, intent(in) :: r0, e
    real(dp), intent(in) :: tol
    logical, intent(out) :: done
    real(dp), intent(inout) :: zs_kept(:), res_kept
    real(dp), allocatable :: saved(:, :), xb(:), zs(:)
    real(dp) :: res
    integer :: m, st

    done = .false.
    m = tb%m
    allocate(saved(m, 2 * m + 2), xb(m), zs(m), stat=st)   ! the pivot must be reversible
    if (st /= 0) return
    saved = tb%t
    call pivot(tb%t, r0, e)
    tb%basis(r0) = e
    xb = tb%t(:, 2 * m + 2)
    call refine_basic_solution(p, tb%t(:, 1:m), tb%basis, xb)
    zs = basic_z(tb%basis, xb, m)
    res = zs_residual(p, zs)
    done = res <= exact_ratio
    if (.not. done) then
      tb%t = saved
      tb%basis(r0) = 2 * m + 1
      if (res <= tol .and. res < res_kept) then
        zs_kept = zs
        res_kept = res
      end if
    end if
  end subroutine try_z0_exit

  !> .true. when the current point with z0 dropped solves the problem to tol:
  !> the basic solution refined on the data (z0's column included), then
  !> measured without z0.
  logical function solves_without_z0(p, tb, tol) result(ok)
    type(scaled_lcp_t), intent(in) :: p
    type(tableau_t), intent(in) :: tb
    real(dp), intent(in) :: tol
    real(dp), allocatable :: xb(:)
    allocate(xb(tb%m))
    xb = tb%t(:, 2 * tb%m + 2)
    call refine_basic_solution(p, tb%t(:, 1:tb%m), tb%basis, xb)
    ok = zs_residual(p, basic_z(tb%basis, xb, tb%m)) <= tol
  end function solves_without_z0

  !> The z part of the basic solution xb, negative values taken as 0 (z0
  !> and w are not in it).
  pure function basic_z(basis, xb, m) result(zs)
    integer, intent(in) :: basis(:), m
    real(dp), intent(in) :: xb(:)
    real(dp) :: zs(m)
    integer :: i
    zs = 0.0_dp
    do i = 1, m
      if (basis(i) > m .and. basis(i) <= 2 * m) zs(basis(i) - m) = max(0.0_dp, xb(i))
    end do
  end function basic_z

  !> The natural residual ||min(zs, qs + Ws zs)||_inf / qscale of zs >= 0.
  real(dp) function zs_residual(p, zs) result(res)
    type(scaled_lcp_t), intent(in) :: p
    real(dp), intent(in) :: zs(:)
    real(dp), allocatable :: ws(:)
    integer :: m
    m = p%m
    allocate(ws(m))
    ws = p%qs
    call dgemv('N', m, m, 1.0_dp, p%ws, m, zs, 1, 1.0_dp, ws, 1)   ! ws = qs + Ws zs
    res = maxval(abs(min(zs, ws))) / p%qscale
  end function zs_residual

  !> The z part of the ray of entering column e: the entering variable grows
  !> by 1, the basic ones by -t(:, e) (>= 0 up to the round-off of ptol).
  subroutine ray_direction(tb, e, dzs)
    type(tableau_t), intent(in) :: tb
    integer, intent(in) :: e
    real(dp), intent(out) :: dzs(:)
    integer :: i, m
    m = tb%m
    dzs = 0.0_dp
    if (e > m .and. e <= 2 * m) dzs(e - m) = 1.0_dp
    do i = 1, m
      if (tb%basis(i) > m .and. tb%basis(i) <= 2 * m) dzs(tb%basis(i) - m) = max(0.0_dp, -tb%t(i, e))
    end do
  end subroutine ray_direction

  !> Whether the tableau may be recomputed at pivot npiv: once per pivot,
  !> and (but for a ray, which ends the run or is refuted) only after m
  !> pivots since the last time or the start: a recomputation costs about
  !> as much as m pivots (an LU of B and a solve with 2m+2 right-hand
  !> sides), so it at most doubles a run, and a run shorter than m pivots,
  !> whose tableau has had no time to drift far, is never recomputed.
  logical function may_refresh(tb, npiv, ray)
    type(tableau_t), intent(in) :: tb
    integer, intent(in) :: npiv
    logical, intent(in) :: ray
    if (tb%refreshed == npiv) then
      may_refresh = .false.
    else if (ray) then
      may_refresh = .true.
    else
      may_refresh = npiv - tb%refreshed >= max(drift_period, tb%m)
    end if
  end function may_refresh

  !> Measure the drift of the basic solution and recompute the tableau when
  !> it exceeds drift_ratio (and may_refresh allows it).
  subroutine watch_drift(p, tb, npiv)
    type(scaled_lcp_t), intent(in) :: p
    type(tableau_t), intent(inout) :: tb
    integer, intent(in) :: npiv
    real(dp), allocatable :: res(:)
    real(dp) :: scale
    if (.not. may_refresh(tb, npiv, .false.)) return
    allocate(res(tb%m))
    call basis_residual(p, tb%basis, tb%t(:, 2 * tb%m + 2), res, scale)
    if (maxval(abs(res)) > drift_ratio * scale) call refresh_tableau(p, tb, npiv)
  end subroutine watch_drift

  !> Recompute the tableau from the data, t = B^-1 [I, -Ws, -e | qs] with B
  !> the basis columns of [I, -Ws, -e] (LU with partial pivoting, dgesv).
  !> Left as it is when B's copy cannot be allocated or B is singular (a
  !> zero pivot of its LU; the rank-1 updates then carry on).
  !>   p     (in)    the scaled problem
  !>   tb    (inout) the tableau; refreshed = npiv when recomputed
  !>   npiv  (in)    the pivot count
  subroutine refresh_tableau(p, tb, npiv)
    type(scaled_lcp_t), intent(in) :: p
    type(tableau_t), intent(inout) :: tb
    integer, intent(in) :: npiv
    real(dp), allocatable :: b(:, :), x(:, :)
    integer, allocatable :: ipiv(:)
    integer :: m, k, info, st

    m = tb%m
    allocate(b(m, m), x(m, 1), ipiv(m), stat=st)
    if (st /= 0) return
    ! B singular leaves the tableau alone: try it on one column first
    call basis_matrix(p, tb%basis, b)
    x(:, 1) = p%qs
    call dgesv(m, 1, b, m, ipiv, x, m, info)
    if (info /= 0) return
    call basis_matrix(p, tb%basis, b)
    call initial_tableau(p, tb%t)
    call dgesv(m, 2 * m + 2, b, m, ipiv, tb%t, m, info)   ! t = B^-1 [I, -Ws, -e | qs]
    do k = 1, m                                          ! the basic columns exactly
      tb%t(:, tb%basis(k)) = 0.0_dp
      tb%t(k, tb%basis(k)) = 1.0_dp
    end do
    tb%refreshed = npiv
  end subroutine refresh_tableau

  !> B: the columns of [I, -Ws, -e] of the basic variables, in row order.
  subroutine basis_matrix(p, basis, b)
    type(scaled_lcp_t), intent(in) :: p
    integer, intent(in) :: basis(:)
    real(dp), intent(out) :: b(:, :)
    integer :: k, m
    m = p%m
    b = 0.0_dp
    do k = 1, m
      if (basis(k) <= m) then
        b(basis(k), k) = 1.0_dp                       ! w_j: e_j
      else if (basis(k) <= 2 * m) then
        b(:, k) = -p%ws(:, basis(k) - m)              ! z_j: -Ws(:, j)
      else
        b(:, k) = -1.0_dp                             ! z0: -e
      end if
    end do
  end subroutine basis_matrix

  !> Iterative refinement of the basic solution:  B xb = qs with B the
  !> basis columns of [I, -Ws, -e] and binv = B^-1 as carried by the tableau;
  !> xb <- xb + binv (qs - B xb), kept only while the residual decreases.
  !>   p      (in)    the scaled problem
  !>   binv   (in)    (m, m) basis inverse
  !>   basis  (in)    (m) basic variables
  !>   xb     (inout) (m) basic values
  subroutine refine_basic_solution(p, binv, basis, xb)
    type(scaled_lcp_t), intent(in) :: p
    real(dp), intent(in) :: binv(:, :)
    integer, intent(in) :: basis(:)
    real(dp), intent(inout) :: xb(:)
    real(dp), allocatable :: res(:), xnew(:)
    real(dp) :: rnorm, rnew, scale
    integer :: step, m

    m = p%m
    allocate(res(m), xnew(m))
    call basis_residual(p, basis, xb, res, scale)
    rnorm = maxval(abs(res))
    do step = 1, 2
      if (rnorm == 0.0_dp) exit
      xnew = xb
      call dgemv('N', m, m, 1.0_dp, binv, m, res, 1, 1.0_dp, xnew, 1)   ! x = x + B^-1 r
      call basis_residual(p, basis, xnew, res, scale)
      rnew = maxval(abs(res))
      if (.not. rnew < rnorm) exit
      xb = xnew
      rnorm = rnew
    end do
  end subroutine refine_basic_solution

  !> res = qs - B xb, B the basis columns of [I, -Ws, -e]; scale = ||qs||_inf +
  !> sum_k |xb_k| ||B(:, k)||_inf, the size of what the residual is a
  !> difference of.
  subroutine basis_residual(p, basis, xb, res, scale)
    type(scaled_lcp_t), intent(in) :: p
    integer, intent(in) :: basis(:)
    real(dp), intent(in) :: xb(:)
    real(dp), intent(out) :: res(:)
    real(dp), intent(out) :: scale
    integer :: k, m

    m = p%m
    res = p%qs
    scale = maxval(abs(p%qs))
    do k = 1, m
      if (basis(k) <= m) then
        res(basis(k)) = res(basis(k)) - xb(k)                       ! column e_j of w_j
        scale = scale + abs(xb(k))
      else if (basis(k) <= 2 * m) then
        call daxpy(m, xb(k), p%ws(:, basis(k) - m), 1, res, 1)     ! column -Ws(:, j) of z_j
        scale = scale + abs(xb(k)) * maxval(abs(p%ws(:, basis(k) - m)))
      else
        res = res + xb(k)                                            ! column -e of z0
        scale = scale + abs(xb(k))
      end if
    end do
  end subroutine basis_residual

end module lemke_tableau
