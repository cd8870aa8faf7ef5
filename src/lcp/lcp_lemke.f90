!> lcp_lemke: LCP(W, q) by Lemke's complementary pivoting.
!>
!> Complementary pivoting on the tableau B^-1 [I, -Ws, -e | qs] of the scaled
!> problem (lcp_scaling; rows w - Ws zs - e z0 = qs, B the columns of the
!> basic variables), dense, one rank-1 update (dger) per pivot, O(n^2) per
!> pivot.  The covering vector is e = ones on the scaled rows: positive on
!> every row, so z0 = -min(qs) makes the first point feasible, and of the
!> size of the scaled data (unit diagonal), so that no row's ratio is
!> favoured by its units.  The minimum ratio test is lexicographic: ties in
!> the ratio are broken by the rows of the current basis inverse, which the
!> tableau carries in its w columns; this rules out cycling on degenerate
!> problems.
!>
!> Round-off.  Each pivot is a Gauss-Jordan step, and after many of them on
!> an ill-conditioned basis the tableau's numbers are off by far more than
!> the rounding of one step (3.4e-8 relative after 26 pivots has been seen
!> on a friction LCP, where an exact tie between z0's row and another row
!> then looked like no tie, and the run went past the solution to a ray
!> with z0 = 2e-13 of the data).  Lemke's decisions are therefore taken on
!> what the data say:
!>  - the drift |qs - B xb| of the basic solution xb, relative to |qs| +
!>    |B| |xb|, is measured every drift_period pivots and after a small
!>    pivot; above drift_ratio the tableau is recomputed from the data,
!>    B^-1 [I, -Ws, -e | qs] by an LU factorization of B (dgesv), at most
!>    once in m pivots (may_refresh);
!>  - z0 is preferred among ties: when z0 leaving at its own ratio would
!>    push no basic value below zero by more than the error of the tableau's
!>    numbers (an a-posteriori bound from the data, z0_ties), the tie is
!>    exact but for round-off, and z0 leaves.  Such ties are also built into
!>    some problems: the two rows w_+ = a'z - b, w_- = b - a'z of an equality
!>    add up to w_+ + w_- = 2 z0 on every tableau.  The point is refined on
!>    its basis; the run ends there when its natural residual is at
!>    round-off.  Otherwise the pivot is undone and the ordinary row leaves,
!>    and the point, when within tol, is kept aside: it is the answer if the
!>    ordinary path ends on a ray or the pivot limit, or less accurately;
!>  - a ray is declared only on a tableau recomputed from the data, and not
!>    when z0 is at round-off there: the point with z0 dropped is refined
!>    and taken when its natural residual is within tol.
!> A genuine ray is returned as the direction y >= 0 of its z part (ray):
!> for a positive semi-definite W it satisfies W'y <= 0 and q'y < 0,
!> Farkas' proof that no z >= 0 has q + W z >= 0 (lcp_scaling:
!> certifies_infeasible checks it for any W).
!> On success the basic solution is refined by two steps of iterative
!> refinement with the tableau's basis inverse, tiny negative z are set to
!> zero, and w = q + W z is recomputed.
!>
!> Why it exists: the exact pivoting method; its path (which variable enters
!> and leaves, when it stops) is here, the tableau's algebra and round-off
!> guards in lemke_tableau.  Who may use it: through lcp_solvers.
!>
!> Programming interface
!>   solve_lcp_lemke(W, q, z, opts, rep [, ray])        z intent(out); W PSD, zero rows dropped
!>   solve_lcp_lemke_scaled(M, q, d, z, opts, rep [, ray])  on D M D, D q with the caller's d, no row
!>                                                    dropped: for a non-symmetric M (frictional contact)
!>   ray (out, optional) the ray's direction when rep%info = 1 (ray termination), 0 otherwise
module lcp_lemke
  use kinds, only: dp
  use strings, only: int_to_str
  use lcp_scaling, only: lcp_options_t, lcp_report_t, scaled_lcp_t, prepare_lcp, measure_solution, scale_of, &
                         set_report, report_out_of_memory, residual_outcome, check_lcp_options
  use lemke_tableau, only: tableau_t, initial_tableau, complement, variable_name, pivot, lexicographic_ratio_test, &
                           z0_exit_violation, try_z0_exit, watch_drift, may_refresh, refresh_tableau, &
                           solves_without_z0, ray_direction, refine_basic_solution, basic_z, zs_residual, z0_ties, &
                           pivot_ratio, tie_ratio, near_tie_ratio, small_pivot_ratio, drift_period
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_lcp_lemke, solve_lcp_lemke_scaled

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
  !>   ray   (out, optional) (n) on ray termination the ray's z part y >= 0
  !>               (largest entry 1; W'y <= 0 and q'y < 0 up to round-off, a
  !>               proof that the LCP has no solution: certifies_infeasible);
  !>               0 otherwise
  subroutine solve_lcp_lemke(W, q, z, opts, rep, ray)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(out) :: rep
    real(dp), intent(out), optional :: ray(:)
    type(scaled_lcp_t) :: p

    z = 0.0_dp
    if (present(ray)) ray = 0.0_dp
    call prepare_lcp(W, q, z, opts, .false., p, rep)
    if (rep%info /= 0) return
    ! an absent ray is not passed on: gfortran's descriptor of an absent
    ! assumed-shape array trips the undefined-behaviour sanitizer
    if (present(ray)) then
      call lemke_solution(W, q, p, opts, 'W ill-conditioned', z, rep, ray)
    else
      call lemke_solution(W, q, p, opts, 'W ill-conditioned', z, rep)
    end if
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
  !>   ray   (out, optional) (n) on ray termination the ray's z part y >= 0,
  !>               largest entry 1: q + M (z + s y) stays >= 0 along it for the
  !>               s Lemke could reach; a proof of infeasibility when
  !>               certifies_infeasible(M, q, y) (always, to round-off, when M
  !>               is positive semi-definite); 0 otherwise
  subroutine solve_lcp_lemke_scaled(M, q, d, z, opts, rep, ray)
    real(dp), intent(in) :: M(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: d(:)
    real(dp), intent(out) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(out) :: rep
    real(dp), intent(out), optional :: ray(:)
    type(scaled_lcp_t) :: p
    integer :: n, i, j, st

    z = 0.0_dp
    if (present(ray)) ray = 0.0_dp
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

    ! an absent ray is not passed on: gfortran's descriptor of an absent
    ! assumed-shape array trips the undefined-behaviour sanitizer
    if (present(ray)) then
      call lemke_solution(M, q, p, opts, 'M ill-conditioned or badly scaled', z, rep, ray)
    else
      call lemke_solution(M, q, p, opts, 'M ill-conditioned or badly scaled', z, rep)
    end if
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
  !>   ray    (inout, optional) (n) the ray's z part, D dzs scaled to a largest
  !>                  entry 1, when info = 1, 0 otherwise; left as it is when
  !>                  of another size (both callers' ray)
  subroutine lemke_solution(W, q, p, opts, cause, z, rep, ray)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    type(scaled_lcp_t), intent(in) :: p
    type(lcp_options_t), intent(in) :: opts
    character(len=*), intent(in) :: cause
    real(dp), intent(inout) :: z(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), intent(inout), optional :: ray(:)
    real(dp), allocatable :: zs(:), dzs(:), y(:)
    integer :: maxit

    maxit = opts%maxit
    if (maxit == 0) maxit = 10 * p%n + 100
    allocate(zs(p%m), dzs(p%m), y(size(q)))
    call lemke_scaled(p, maxit, opts%tol, zs, rep, dzs)
    z(p%rows) = p%d(p%rows) * zs                      ! z = D zs
    where (z < 0.0_dp) z = 0.0_dp                     ! polish: tiny negatives
    y = 0.0_dp
    if (rep%info == 1) then
      y(p%rows) = p%d(p%rows) * dzs                   ! y = D dzs
      if (maxval(y) > 0.0_dp) y = y / maxval(y)
    end if
    if (present(ray)) then
      if (size(ray) == size(y)) ray = y
    end if
    call measure_solution(W, q, p%d, z, rep)

    if (rep%info == 0) call residual_outcome(rep, opts%tol, 'Lemke: solved in ' // int_to_str(rep%iterations) // &
      ' pivots', 'Lemke: terminated after ' // int_to_str(rep%iterations) // ' pivots', cause)
  end subroutine lemke_solution

  !> Lemke's algorithm on the scaled problem p (p%m > 0 rows), with the
  !> decisions of the module header (drift, z0's near-ties, rays).
  !>   p      (in)    the scaled problem
  !>   maxit  (in)    pivot limit, > 0
  !>   tol    (in)    the natural residual a point must reach to end the run
  !>                  other than by z0's ordinary exit
  !>   zs     (out)   (m) the z part of the final basic solution, >= 0
  !>   rep    (inout) info (0, 1 ray, 2 limit, info_no_memory), iterations,
  !>                  message on failure
  !>   dzs    (out)   (m) on a ray the z part of its direction (scaled), >= 0
  subroutine lemke_scaled(p, maxit, tol, zs, rep, dzs)
    type(scaled_lcp_t), intent(in) :: p
    integer, intent(in) :: maxit
    real(dp), intent(in) :: tol
    real(dp), intent(out) :: zs(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), intent(out) :: dzs(:)
    type(tableau_t) :: tb
    real(dp), allocatable :: xb(:), zs_kept(:)
    integer :: m, jz0, jrhs, i, r, r0, entering, leaving, npiv, st
    real(dp) :: qmin, qnorm, violation, res_kept
    logical :: done, small_pivot

    m = p%m
    zs = 0.0_dp
    dzs = 0.0_dp
    rep%iterations = 0
    if (m == 0) return
    if (all(p%qs >= 0.0_dp)) return                   ! z = 0, w = q >= 0

    jz0 = 2 * m + 1
    jrhs = 2 * m + 2
    qnorm = maxval(abs(p%qs))
    tb%m = m
    allocate(tb%t(m, jrhs), tb%basis(m), stat=st)
    if (st /= 0) then
      call report_out_of_memory(rep, 'solving the LCP by Lemke (a tableau of ' // int_to_str(m) // ' rows)', &
                                8.0_dp * real(m, dp) * real(jrhs, dp))
      return
    end if
    call initial_tableau(p, tb%t)
    tb%basis = [(i, i = 1, m)]

    ! First pivot: z0 enters at the row of the most negative q; among exact ties
    ! the last row, which keeps every row (rhs, B^-1 row) lexicographically positive.
    qmin = minval(p%qs)
    r = 0
    do i = 1, m
      if (p%qs(i) == qmin) r = i
    end do
    call pivot(tb%t, r, jz0)
    leaving = tb%basis(r)
    tb%basis(r) = jz0
    npiv = 1
    entering = complement(leaving, m)
    small_pivot = .false.
    done = .false.
    res_kept = huge(1.0_dp)                           ! no z0 exit kept aside yet
    allocate(zs_kept(m), source=0.0_dp)

    do
      if (npiv >= maxit) then
        rep%info = 2
        rep%stopped = 'pivot limit'
        rep%message = 'Lemke: pivot limit ' // int_to_str(maxit) // &
          ' reached without a solution (degenerate or ill-conditioned W)'
        exit
      end if
      if (mod(npiv, drift_period) == 0 .or. small_pivot) call watch_drift(p, tb, npiv)
      call lexicographic_ratio_test(tb%t, m, entering, tb%basis, qnorm, r)
      if (r > 0) then
        if (tb%basis(r) == jz0) then                 ! z0 leaves: complementary solution
          call pivot(tb%t, r, entering)
          tb%basis(r) = entering
          npiv = npiv + 1
          exit
        end if
      end if

      ! z0 tied with the ordinary row to round-off: z0 leaves
      r0 = findloc(tb%basis, jz0, dim=1)
      violation = z0_exit_violation(tb%t, entering, r0)
      if (violation < huge(1.0_dp)) violation = violation / qnorm     ! huge: z0 cannot leave here
      if (violation <= near_tie_ratio) then
        if (z0_ties(p, tb, entering, r0)) then
          call try_z0_exit(p, tb, r0, entering, tol, done, zs_kept, res_kept)
          if (done) then
            npiv = npiv + 1
            exit
          end if
        end if
      end if
      ! a ray: decided on a tableau recomputed from the data
      if (r == 0 .and. may_refresh(tb, npiv, .true.)) then
        call refresh_tableau(p, tb, npiv)
        if (tb%refreshed == npiv) cycle                ! redo the ratio test on it
      end if

      if (r == 0) then
        ! z0 at round-off of the data: the point with z0 dropped may be a solution
        if (solves_without_z0(p, tb, tol)) exit
        rep%info = 1
        rep%stopped = 'ray'
        rep%message = 'Lemke: ray termination at pivot ' // int_to_str(npiv + 1) // &
          ' (the LCP has no solution: no z >= 0 gives q + W z >= 0 when W is positive' // &
          ' semi-definite; entering ' // variable_name(entering, m, p%rows) // ')'
        call ray_direction(tb, entering, dzs)
        exit
      end if
      small_pivot = tb%t(r, entering) < small_pivot_ratio * maxval(abs(tb%t(:, entering)))
      call pivot(tb%t, r, entering)
      npiv = npiv + 1
      leaving = tb%basis(r)
      tb%basis(r) = entering
      entering = complement(leaving, m)
    end do
    rep%iterations = npiv

    allocate(xb(m))
    xb = tb%t(:, jrhs)
    if (rep%info == 0) call refine_basic_solution(p, tb%t(:, 1:m), tb%basis, xb)
    zs = basic_z(tb%basis, xb, m)
    ! a z0 exit kept aside: the answer when the run failed or ended less accurate
    if (res_kept <= tol) then
      if (rep%info == 1 .or. rep%info == 2) then
        zs = zs_kept
        dzs = 0.0_dp
        rep%info = 0
        rep%stopped = ''
      else if (rep%info == 0) then
        if (res_kept < zs_residual(p, zs)) zs = zs_kept
      end if
    end if
  end subroutine lemke_scaled


end module lcp_lemke
