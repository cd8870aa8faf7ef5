!> lcp_solvers: the linear complementarity problem of frictionless contact.
!>
!> LCP(W, q): find z in R^n with
!>     z >= 0,   w = q + W z >= 0,   z'w = 0,
!> where W (n x n) is the Delassus matrix B K^-1 B' of the condensed mortar
!> contact problem (symmetric positive semi-definite, entries are compliances)
!> and q = g - B K^-1 f the gap of the unconstrained solution.  z is the vector
!> of nodal contact forces mu, w the final normal gaps.  For symmetric W this is
!> the KKT system of the convex QP  min 1/2 z'Wz + q'z  subject to z >= 0.
!>
!> Scaling.  W's entries may span many orders of magnitude, so both solvers work
!> on the symmetrically scaled problem
!>     Ws = D W D,   qs = D q,   z = D zs,   ws = D w,   D = diag(1/sqrt(W_ii)),
!> which has a unit diagonal (and |Ws_ij| <= 1 when W is PSD).  A row whose
!> diagonal is zero (W_ii <= 1e-30 max_j W_jj) is a redundant constraint: for a
!> PSD W its whole row and column vanish, w_i = q_i whatever z, and z_i = 0 is
!> taken; it is scaled with d_i = 1/sqrt(max_j W_jj).  If such a row has
!> qs_i < -tol ||qs||_inf the LCP has no solution (info = 1).
!> Tolerances are relative to the scaled problem; the measures reported are
!>     residual         r = || min(zs, ws) ||_inf / ||qs||_inf  (1 in place of
!>                      ||qs|| when q = 0): scale-free, whatever the units of q
!>                      (the natural residual: r = 0 iff z solves the LCP),
!>     complementarity  max_i |zs_i ws_i| / (max_i |zs_i| max_i |qs_i|)
!>                      (zs_i ws_i = z_i w_i; 0 when z = 0; divided by
!>                      max_i |zs_i|**2 instead when q = 0).
!>
!> Lemke.  Complementary pivoting on the tableau [I, -Ws, -e | qs] (rows
!> w - Ws zs - e z0 = qs, covering vector e = ones), dense, one rank-1 update
!> (dger) per pivot, O(n^2) per pivot.  The minimum ratio test is lexicographic:
!> ties in the ratio are broken by the rows of the current basis inverse, which
!> the tableau carries in its w columns; this rules out cycling on degenerate
!> problems.  z0 leaves at once when it ties.  For a PSD W, termination on a
!> ray proves that the LCP has no solution.  On success the basic solution is
!> refined by two steps of iterative refinement with the tableau's basis
!> inverse, tiny negative z are set to zero, and w = q + W z is recomputed.
!>
!> PGS.  Projected Gauss-Seidel with over-relaxation omega on the scaled
!> problem, zs_i <- max(0, zs_i - omega ws_i / Ws_ii), with ws = qs + Ws zs kept
!> up to date column by column (daxpy) and recomputed every 50 sweeps; the
!> natural residual is checked after every sweep.  Divergence (iterates beyond
!> 1e150 or the residual grown by 1e6 over its minimum) and stagnation (the best
!> residual not decreased by a factor 0.999 over max(1000, 10 n) sweeps) stop
!> with info = 3; z then holds the best iterate.
!>
!> Programming interface
!>   type(lcp_options_t)  tol (1e-10, on the scaled residual), maxit (0: default,
!>                        Lemke 10 n + 100 pivots, PGS min(1e5, max(1e4, 1e10/n^2))
!>                        sweeps), omega (1, PGS relaxation, 0 < omega < 2)
!>   type(lcp_report_t)   info, iterations, residual, complementarity, message
!>       info  0 solved; 1 no solution (Lemke ray termination, or a zero row of W
!>             with a negative q_i); 2 iteration limit; 3 PGS divergence or
!>             stagnation; 4 Lemke terminated but the residual exceeds tol (loss
!>             of accuracy); -k argument k invalid
!>   solve_lcp_lemke(W, q, z, opts, rep)   z intent(out)
!>   solve_lcp_pgs(W, q, z, opts, rep)     z intent(inout): initial guess, clipped to >= 0
!>   lcp_natural_residual(W, q, z)         the residual r above
!>   scale_lcp(W, q, d, Ws, qs)            the symmetric diagonal scaling
!>   solve_lcp_lemke_scaled(M, q, d, z, opts, rep)
!>                                         Lemke on D M D, D q with a scaling d
!>                                         given by the caller and no row removed:
!>                                         for LCPs with zero diagonal entries or a
!>                                         non-symmetric M (frictional contact)
!> W need not be symmetric for Lemke and PGS to run (both use W's columns), but
!> the convergence of PGS and the meaning of ray termination assume W PSD.
!> No routine prints anything; every outcome is in the report.
module lcp_solvers
  use kinds, only: dp, i8
  use lapack_interfaces, only: daxpy, dgemv, dger
  use diagnostics, only: int_to_str, real_to_str, error_t, set_out_of_memory
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: lcp_options_t, lcp_report_t
  public :: solve_lcp_lemke, solve_lcp_pgs, lcp_natural_residual, scale_lcp, measure_solution
  public :: solve_lcp_lemke_scaled, pgs_outcome, set_report, out_of_memory
  public :: pgs_monitor_t, pgs_watch_start, pgs_watch_iterate, pgs_watch_progress, pgs_refresh_sweeps
  public :: max_diagonal, negative_diagonal

  !> Solver settings.
  type :: lcp_options_t
    real(dp) :: tol = 1.0e-10_dp   !< tolerance on the scaled natural residual, > 0
    integer :: maxit = 0           !< pivot / sweep limit, >= 0; 0 selects the default
    real(dp) :: omega = 1.0_dp     !< PGS relaxation, 0 < omega < 2
  end type lcp_options_t

  !> Outcome of a solve.
  type :: lcp_report_t
    integer :: info = 0                      !< 0 solved, > 0 failure, < 0 argument -info invalid
    integer :: iterations = 0                !< Lemke pivots or PGS sweeps
    real(dp) :: residual = 0.0_dp            !< scaled natural residual of the returned z
    real(dp) :: complementarity = 0.0_dp     !< scaled complementarity of the returned z
    character(len=:), allocatable :: message !< one-line summary or diagnostic
  end type lcp_report_t

  !> The scaled problem restricted to the rows with a positive diagonal.
  type :: scaled_lcp_t
    integer :: n = 0                      !< size of the original problem
    integer :: m = 0                      !< number of rows kept
    real(dp), allocatable :: d(:)         !< (n) scaling D
    integer, allocatable :: rows(:)       !< (m) original indices of the rows kept
    real(dp), allocatable :: ws(:, :)     !< (m, m) (D W D)(rows, rows)
    real(dp), allocatable :: qs(:)        !< (m) (D q)(rows)
    real(dp) :: qscale = 1.0_dp           !< ||D q||_inf over all n rows (1 when q = 0)
  end type scaled_lcp_t

  real(dp), parameter :: diag_zero_ratio = 1.0e-30_dp      ! W_ii below this * max diag: zero row
  real(dp), parameter :: diag_negative_ratio = 1.0e-8_dp   ! W_ii below -this * max diag: not PSD
  real(dp), parameter :: pivot_ratio = 1.0e-11_dp          ! Lemke: smallest pivot, relative to the column
  real(dp), parameter :: tie_ratio = 1.0e-12_dp            ! Lemke: relative width of a tie
  real(dp), parameter :: divergence_factor = 1.0e6_dp      ! PGS: residual growth over its minimum
  real(dp), parameter :: stagnation_factor = 0.999_dp      ! PGS: decrease expected per window
  real(dp), parameter :: iterate_bound = 1.0e150_dp        ! PGS: iterates beyond this diverge
  integer, parameter :: pgs_refresh_sweeps = 50            ! PGS: recompute the gaps from scratch

  !> The stop tests that every PGS loop shares (this module's and the friction
  !> sweeps of friction_lcp): the best iterate, divergence, stagnation.
  type :: pgs_monitor_t
    real(dp) :: tol = 0.0_dp               !< residual target
    real(dp) :: best = 0.0_dp              !< smallest residual so far
    real(dp) :: reference = 0.0_dp         !< best at the start of the stagnation window
    integer :: window = 0                  !< stagnation window (sweeps)
    integer :: last_progress = 0           !< sweep of the last 0.1% decrease of best
    real(dp), allocatable :: xbest(:)      !< the iterate of residual best
  end type pgs_monitor_t


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
    real(dp), allocatable :: zs(:)
    integer :: maxit

    z = 0.0_dp
    call prepare_lcp(W, q, size(z), opts, .false., p, rep)
    if (rep%info < 0) return
    if (rep%info > 0) then
      call measure_solution(W, q, p%d, z, rep)
      return
    end if
    maxit = opts%maxit
    if (maxit == 0) maxit = 10 * p%n + 100

    allocate(zs(p%m))
    call lemke_scaled(p, maxit, zs, rep)
    z(p%rows) = p%d(p%rows) * zs                      ! z = D zs
    where (z < 0.0_dp) z = 0.0_dp                     ! polish: tiny negatives
    call measure_solution(W, q, p%d, z, rep)

    if (rep%info == 0) then
      if (rep%residual > opts%tol) then
        rep%info = 4
        rep%message = 'Lemke: terminated after ' // int_to_str(rep%iterations) // &
          ' pivots but the residual ' // real_to_str(rep%residual) // ' exceeds tol ' // &
          real_to_str(opts%tol) // ' (W ill-conditioned)'
      else
        rep%message = 'Lemke: solved in ' // int_to_str(rep%iterations) // ' pivots, residual ' // &
          real_to_str(rep%residual)
      end if
    end if
  end subroutine solve_lcp_lemke

  !> Solve LCP(W, q) by projected Gauss-Seidel with over-relaxation on the
  !> scaled problem.
  !>   W     (in)    (n, n) PSD matrix, finite
  !>   q     (in)    (n) finite
  !>   z     (inout) (n) on entry the initial guess (negative or non-finite
  !>                 entries are taken as 0); on exit the solution when
  !>                 rep%info = 0, otherwise the best iterate (finite, >= 0);
  !>                 unchanged on an argument error
  !>   opts  (in)    tol, maxit, omega
  !>   rep   (out)   info 0 converged, 1 infeasible zero row, 2 sweep limit,
  !>                 3 divergence or stagnation, -k argument k invalid;
  !>                 iterations = sweeps; residual; complementarity; message
  subroutine solve_lcp_pgs(W, q, z, opts, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(inout) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(out) :: rep
    type(scaled_lcp_t) :: p
    real(dp), allocatable :: zs(:)
    integer :: maxit, k, window, stop_reason

    call prepare_lcp(W, q, size(z), opts, .true., p, rep)
    if (rep%info < 0) return
    if (rep%info > 0) then
      z = 0.0_dp
      call measure_solution(W, q, p%d, z, rep)
      return
    end if
    maxit = opts%maxit
    if (maxit == 0) maxit = nint(min(1.0e5_dp, max(1.0e4_dp, 1.0e10_dp / real(max(p%m, 1), dp)**2)))
    window = max(1000, 10 * p%m)

    allocate(zs(p%m))
    do k = 1, p%m                                     ! zs = max(0, D^-1 z)
      zs(k) = 0.0_dp
      if (ieee_is_finite(z(p%rows(k)))) zs(k) = max(0.0_dp, z(p%rows(k)) / p%d(p%rows(k)))
    end do
    call pgs_scaled(p, opts%tol, opts%omega, maxit, window, zs, rep%iterations, stop_reason)
    z = 0.0_dp
    z(p%rows) = p%d(p%rows) * zs
    call measure_solution(W, q, p%d, z, rep)

    call pgs_outcome(stop_reason, maxit, window, opts%tol, 'PGS', 'z', 'LCP', rep)
  end subroutine solve_lcp_pgs

  !> info and message of a projected Gauss-Seidel run from its stop reason
  !> (0 converged, 2 sweep limit, 3 divergence, other: stagnation).
  !>   reason  (in)    stop reason
  !>   maxit, window (in) the sweep limit and the stagnation window
  !>   tol     (in)    the residual target
  !>   label   (in)    the method's name in the message ('PGS')
  !>   iterate (in)    the name of the returned iterate ('z')
  !>   problem (in)    what may have no solution ('LCP')
  !>   rep     (inout) iterations and residual set on entry; info, message set
  subroutine pgs_outcome(reason, maxit, window, tol, label, iterate, problem, rep)
    integer, intent(in) :: reason, maxit, window
    real(dp), intent(in) :: tol
    character(len=*), intent(in) :: label, iterate, problem
    type(lcp_report_t), intent(inout) :: rep
    select case (reason)
    case (0)
      rep%info = 0
      rep%message = label // ': converged in ' // int_to_str(rep%iterations) // ' sweeps, residual ' // &
        real_to_str(rep%residual)
    case (2)
      rep%info = 2
      rep%message = label // ': sweep limit ' // int_to_str(maxit) // ' reached, residual ' // &
        real_to_str(rep%residual) // ' > tol ' // real_to_str(tol) // '; ' // iterate // ' is the best iterate'
    case (3)
      rep%info = 3
      rep%message = label // ': divergence at sweep ' // int_to_str(rep%iterations) // ' (the ' // problem // &
        ' may have no solution); ' // iterate // ' is the best iterate, residual ' // real_to_str(rep%residual)
    case default
      rep%info = 3
      rep%message = label // ': stagnation at sweep ' // int_to_str(rep%iterations) // ', residual ' // &
        real_to_str(rep%residual) // ' not decreasing over ' // int_to_str(window) // ' sweeps (the ' // &
        problem // ' may have no solution); ' // iterate // ' is the best iterate'
    end select
  end subroutine pgs_outcome

  !> Scaled natural residual r = ||min(zs, ws)||_inf / ||qs||_inf of a
  !> candidate z (zs = D^-1 z, ws = D (q + W z), qs = D q, D as in scale_lcp).
  !> r = 0 exactly when z solves LCP(W, q).
  !>   W  (in) (n, n)
  !>   q  (in) (n)
  !>   z  (in) (n) candidate, finite
  !>   r  (result) the residual; huge(1.0_dp) when the sizes do not match
  function lcp_natural_residual(W, q, z) result(r)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: z(:)
    real(dp) :: r
    type(lcp_report_t) :: rep
    real(dp), allocatable :: d(:)

    r = huge(1.0_dp)
    if (size(W, 1) /= size(q) .or. size(W, 2) /= size(q) .or. size(z) /= size(q)) return
    allocate(d(size(q)))
    call scaling_vector(W, d)
    call measure_solution(W, q, d, z, rep)
    r = rep%residual
  end function lcp_natural_residual

  !> Symmetric diagonal scaling Ws = D W D, qs = D q, D = diag(d) with
  !> d_i = 1/sqrt(W_ii); a row with W_ii <= 1e-30 max_j W_jj (a zero row of a PSD
  !> matrix) gets d_i = 1/sqrt(max_j W_jj) (1 when W has no positive diagonal).
  !>   W   (in)  (n, n)
  !>   q   (in)  (n)
  !>   d   (out) (n) the scaling, > 0
  !>   Ws  (out) (n, n) D W D (unit diagonal on the rows with a positive diagonal)
  !>   qs  (out) (n) D q
  subroutine scale_lcp(W, q, d, Ws, qs)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: d(:)
    real(dp), intent(out) :: Ws(:, :)
    real(dp), intent(out) :: qs(:)
    integer :: j

    call scaling_vector(W, d)
    do j = 1, size(q)
      Ws(:, j) = d * W(:, j) * d(j)                   ! (D W D)_ij = d_i W_ij d_j
    end do
    qs = d * q
  end subroutine scale_lcp

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
    real(dp), allocatable :: zs(:)
    integer :: n, i, j, maxit, st

    z = 0.0_dp
    rep%info = 0
    n = size(q)
    if (size(M, 1) /= n .or. size(M, 2) /= n) then
      call set_report(rep, -1, 'LCP: M is ' // int_to_str(size(M, 1)) // ' x ' // int_to_str(size(M, 2)) // &
        ' (expected ' // int_to_str(n) // ' x ' // int_to_str(n) // ', the size of q)')
      return
    else if (.not. all(ieee_is_finite(M))) then
      call set_report(rep, -1, 'LCP: M has non-finite entries')
      return
    else if (.not. all(ieee_is_finite(q))) then
      call set_report(rep, -2, 'LCP: q has non-finite entries')
      return
    else if (size(d) /= n) then
      call set_report(rep, -3, 'LCP: d has ' // int_to_str(size(d)) // ' entries (expected ' // &
        int_to_str(n) // ')')
      return
    else if (.not. all(ieee_is_finite(d) .and. d > 0.0_dp)) then
      call set_report(rep, -3, 'LCP: the scaling d has entries that are not finite and > 0')
      return
    else if (size(z) /= n) then
      call set_report(rep, -4, 'LCP: z has ' // int_to_str(size(z)) // ' entries (expected ' // &
        int_to_str(n) // ')')
      return
    else if (.not. (ieee_is_finite(opts%tol) .and. opts%tol > 0.0_dp)) then
      call set_report(rep, -5, 'LCP: tol = ' // real_to_str(opts%tol) // ' (expected tol > 0)')
      return
    else if (opts%maxit < 0) then
      call set_report(rep, -5, 'LCP: maxit = ' // int_to_str(opts%maxit) // ' (expected >= 0)')
      return
    end if

    ! Every row kept: the scaled problem is the whole of D M D.
    p%n = n
    p%m = n
    allocate(p%d(n), p%rows(n), p%ws(n, n), p%qs(n), zs(n), stat=st)
    if (st /= 0) then
      call set_report(rep, 3, out_of_memory('scaling the LCP (' // int_to_str(n) // ' rows)', &
                                            8.0_dp * real(n, dp) * real(n, dp)))
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
    maxit = opts%maxit
    if (maxit == 0) maxit = 10 * n + 100

    call lemke_scaled(p, maxit, zs, rep)
    z = d * zs                                         ! z = D zs
    where (z < 0.0_dp) z = 0.0_dp
    call measure_solution(M, q, d, z, rep)

    select case (rep%info)
    case (0)
      if (rep%residual > opts%tol) then
        rep%info = 4
        rep%message = 'Lemke: terminated after ' // int_to_str(rep%iterations) // &
          ' pivots but the residual ' // real_to_str(rep%residual) // ' exceeds tol ' // &
          real_to_str(opts%tol) // ' (M ill-conditioned or badly scaled)'
      else
        rep%message = 'Lemke: solved in ' // int_to_str(rep%iterations) // ' pivots, residual ' // &
          real_to_str(rep%residual)
      end if
    case (1)
      rep%message = 'Lemke: ray termination after ' // int_to_str(rep%iterations) // &
        ' pivots (no solution found; when M is copositive-plus, e.g. positive semi-definite,' // &
        ' the LCP has none)'
    end select
  end subroutine solve_lcp_lemke_scaled

  ! ---------------------------------------------------------------------------
  ! Internals
  ! ---------------------------------------------------------------------------

  !> The scale of the scaled q: its largest entry, 1 when q = 0.
  pure real(dp) function scale_of(qmax) result(sc)
    real(dp), intent(in) :: qmax
    sc = qmax
    if (.not. (sc > 0.0_dp)) sc = 1.0_dp
  end function scale_of

  !> d_i = 1/sqrt(W_ii), or 1/sqrt(max diag) on a zero row (see scale_lcp).
  pure subroutine scaling_vector(W, d)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(out) :: d(:)
    real(dp) :: dmax
    integer :: i

    dmax = max_diagonal(W)
    do i = 1, size(d)
      if (is_zero_row(W(i, i), dmax)) then
        if (dmax > 0.0_dp) then
          d(i) = 1.0_dp / sqrt(dmax)
        else
          d(i) = 1.0_dp
        end if
      else
        d(i) = 1.0_dp / sqrt(W(i, i))
      end if
    end do
  end subroutine scaling_vector

  pure function max_diagonal(W) result(dmax)
    real(dp), intent(in) :: W(:, :)
    real(dp) :: dmax
    integer :: i
    dmax = 0.0_dp
    do i = 1, min(size(W, 1), size(W, 2))
      dmax = max(dmax, W(i, i))
    end do
  end function max_diagonal

  !> The first i with W(i,i) < 0 beyond round-off (|W(i,i)| > 1e-8 of the
  !> largest diagonal entry): W is then not positive semi-definite; 0 if none.
  pure integer function negative_diagonal(W) result(bad)
    real(dp), intent(in) :: W(:, :)
    real(dp) :: dmax
    integer :: i
    dmax = max_diagonal(W)
    bad = 0
    do i = 1, min(size(W, 1), size(W, 2))
      if (W(i, i) < 0.0_dp .and. abs(W(i, i)) > diag_negative_ratio * dmax) then
        bad = i
        return
      end if
    end do
  end function negative_diagonal

  pure logical function is_zero_row(wii, dmax)
    real(dp), intent(in) :: wii, dmax
    is_zero_row = wii <= diag_zero_ratio * dmax
  end function is_zero_row

  !> Check the arguments, scale, and split off the zero rows.
  !>   W, q       (in)  the problem
  !>   nz         (in)  size of the caller's z
  !>   opts       (in)  options
  !>   check_omega(in)  .true. for PGS
  !>   p          (out) the scaled problem on the rows kept (d set whenever the
  !>                    sizes are valid)
  !>   rep        (out) info -1..-4 on an invalid argument (message set); 1 when
  !>                    a zero row has a clearly negative q_i; 0 otherwise
  subroutine prepare_lcp(W, q, nz, opts, check_omega, p, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    integer, intent(in) :: nz
    type(lcp_options_t), intent(in) :: opts
    logical, intent(in) :: check_omega
    type(scaled_lcp_t), intent(out) :: p
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: qs_all(:)
    real(dp) :: dmax
    integer :: n, i, j, nbad, first_bad, st

    rep%info = 0
    n = size(q)
    if (size(W, 1) /= size(W, 2)) then
      call set_report(rep, -1, 'LCP: W is not square (' // int_to_str(size(W, 1)) // ' x ' // &
        int_to_str(size(W, 2)) // ')')
      return
    else if (size(W, 1) /= n) then
      call set_report(rep, -2, 'LCP: q has ' // int_to_str(n) // ' entries, W is ' // &
        int_to_str(size(W, 1)) // ' x ' // int_to_str(size(W, 1)))
      return
    else if (nz /= n) then
      call set_report(rep, -3, 'LCP: z has ' // int_to_str(nz) // ' entries (expected ' // &
        int_to_str(n) // ')')
      return
    end if
    if (.not. (ieee_is_finite(opts%tol) .and. opts%tol > 0.0_dp)) then
      call set_report(rep, -4, 'LCP: tol = ' // real_to_str(opts%tol) // ' (expected tol > 0)')
      return
    else if (opts%maxit < 0) then
      call set_report(rep, -4, 'LCP: maxit = ' // int_to_str(opts%maxit) // ' (expected >= 0)')
      return
    end if
    if (check_omega) then
      if (.not. (opts%omega > 0.0_dp .and. opts%omega < 2.0_dp)) then
        call set_report(rep, -4, 'LCP: omega = ' // real_to_str(opts%omega) // &
          ' (expected 0 < omega < 2)')
        return
      end if
    end if
    if (.not. all(ieee_is_finite(W))) then
      call set_report(rep, -1, 'LCP: W has non-finite entries')
      return
    else if (.not. all(ieee_is_finite(q))) then
      call set_report(rep, -2, 'LCP: q has non-finite entries')
      return
    end if
    dmax = max_diagonal(W)
    i = negative_diagonal(W)
    if (i > 0) then
      call set_report(rep, -1, 'LCP: W(' // int_to_str(i) // ',' // int_to_str(i) // ') = ' // &
        real_to_str(W(i, i)) // ' < 0 (W must be positive semi-definite)')
      return
    end if

    p%n = n
    allocate(p%d(n), qs_all(n))
    call scaling_vector(W, p%d)
    qs_all = p%d * q                                    ! qs = D q
    p%qscale = 1.0_dp
    if (n > 0) p%qscale = scale_of(maxval(abs(qs_all)))

    ! Zero rows: z_i = 0, feasible only when q_i is not clearly negative.
    p%m = 0
    nbad = 0
    first_bad = 0
    do i = 1, n
      if (is_zero_row(W(i, i), dmax)) then
        if (qs_all(i) < -opts%tol * p%qscale) then
          nbad = nbad + 1
          if (first_bad == 0) first_bad = i
        end if
      else
        p%m = p%m + 1
      end if
    end do
    if (nbad > 0) then
      call set_report(rep, 1, 'LCP: row/column ' // int_to_str(first_bad) // &
        ' of W is zero (redundant constraint) but q(' // int_to_str(first_bad) // ') = ' // &
        real_to_str(q(first_bad)) // ' < 0: the LCP has no solution (' // int_to_str(nbad) // &
        ' such row(s))')
      return
    end if

    allocate(p%rows(p%m), p%ws(p%m, p%m), p%qs(p%m), stat=st)
    if (st /= 0) then
      call set_report(rep, 3, out_of_memory('scaling the LCP (' // int_to_str(p%m) // ' rows)', &
                                            8.0_dp * real(p%m, dp) * real(p%m, dp)))
      return
    end if
    p%m = 0
    do i = 1, n
      if (.not. is_zero_row(W(i, i), dmax)) then
        p%m = p%m + 1
        p%rows(p%m) = i
      end if
    end do
    do j = 1, p%m
      p%ws(:, j) = p%d(p%rows) * W(p%rows, p%rows(j)) * p%d(p%rows(j))   ! (D W D)(rows, rows)
    end do
    p%qs = qs_all(p%rows)
  end subroutine prepare_lcp

  !> rep%info = info, rep%message = message.
  !> `out of memory while PHASE (about N MB needed)`, the program's wording
  !> for an allocation that failed (diagnostics: set_out_of_memory).
  function out_of_memory(phase, bytes) result(message)
    character(len=*), intent(in) :: phase
    real(dp), intent(in) :: bytes
    character(len=:), allocatable :: message
    type(error_t), allocatable :: err
    call set_out_of_memory(err, phase, int(min(bytes, 9.0e18_dp), i8))
    message = err%message
  end function out_of_memory

  subroutine set_report(rep, info, message)
    type(lcp_report_t), intent(inout) :: rep
    integer, intent(in) :: info
    character(len=*), intent(in) :: message
    rep%info = info
    rep%message = message
  end subroutine set_report

  !> Residual and complementarity of z on the scaled problem (module header).
  !>   W, q  (in)    the problem, (n, n) and (n)
  !>   d     (in)    (n) the scaling
  !>   z     (in)    (n) candidate
  !>   rep   (inout) residual and complementarity set
  subroutine measure_solution(W, q, d, z, rep)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: d(:)
    real(dp), intent(in) :: z(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: gap(:), zs(:), ws(:)
    real(dp) :: prod, zmax, qmax
    integer :: n

    n = size(q)
    rep%residual = 0.0_dp
    rep%complementarity = 0.0_dp
    if (n == 0) return
    allocate(gap(n), zs(n), ws(n))
    gap = q
    call dgemv('N', n, n, 1.0_dp, W, n, z, 1, 1.0_dp, gap, 1) ! w = q + W z
    zs = z / d                                                ! zs = D^-1 z
    ws = d * gap                                              ! ws = D w
    qmax = maxval(abs(d * q))
    rep%residual = maxval(abs(min(zs, ws))) / scale_of(qmax)
    prod = maxval(abs(zs * ws))
    zmax = maxval(abs(zs))
    if (prod > 0.0_dp) then
      if (qmax > 0.0_dp) then
        rep%complementarity = prod / (zmax * qmax)
      else
        rep%complementarity = prod / zmax**2
      end if
    end if
  end subroutine measure_solution

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
      rep%info = 3
      rep%message = out_of_memory('solving the LCP by Lemke (a tableau of ' // int_to_str(m) // ' rows)', &
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
        rep%message = 'Lemke: pivot limit ' // int_to_str(maxit) // &
          ' reached without a solution (degenerate or ill-conditioned W)'
        exit
      end if
      call lexicographic_ratio_test(t, m, entering, basis, maxval(abs(p%qs)), r)
      if (r == 0) then
        rep%info = 1
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

  !> Projected SOR sweeps on the scaled problem.
  !>   p       (in)    the scaled problem
  !>   tol     (in)    residual target (normalised by p%qscale)
  !>   omega   (in)    relaxation, 0 < omega < 2
  !>   maxit   (in)    sweep limit
  !>   window  (in)    stagnation window (sweeps)
  !>   zs      (inout) (m) initial guess >= 0; on exit the solution or best iterate
  !>   sweeps  (out)   sweeps done
  !>   reason  (out)   0 converged, 2 limit, 3 divergence, 4 stagnation
  subroutine pgs_scaled(p, tol, omega, maxit, window, zs, sweeps, reason)
    type(scaled_lcp_t), intent(in) :: p
    real(dp), intent(in) :: tol, omega
    integer, intent(in) :: maxit, window
    real(dp), intent(inout) :: zs(:)
    integer, intent(out) :: sweeps, reason
    type(pgs_monitor_t) :: mon
    real(dp), allocatable :: ws(:)
    real(dp) :: res, znew, dz
    integer :: m, i, sweep

    m = p%m
    sweeps = 0
    reason = 0
    if (m == 0) return
    allocate(ws(m))
    call update_gap(p, zs, ws)
    res = maxval(abs(min(zs, ws))) / p%qscale
    call pgs_watch_start(mon, tol, window, zs, res)
    if (res <= tol) return

    reason = 2
    do sweep = 1, maxit
      sweeps = sweep
      do i = 1, m
        znew = max(0.0_dp, zs(i) - omega * ws(i) / p%ws(i, i))   ! projected SOR update
        dz = znew - zs(i)
        if (dz /= 0.0_dp) then
          zs(i) = znew
          call daxpy(m, dz, p%ws(:, i), 1, ws, 1)                 ! ws = ws + dz Ws(:, i)
        end if
      end do
      if (mod(sweep, pgs_refresh_sweeps) == 0) call update_gap(p, zs, ws)

      res = maxval(abs(min(zs, ws))) / p%qscale
      reason = pgs_watch_iterate(mon, zs, ws, res)
      if (reason >= 0) exit
      if (res <= tol) then
        call update_gap(p, zs, ws)                    ! confirm without drift
        res = maxval(abs(min(zs, ws))) / p%qscale
        if (res <= tol) then
          reason = 0
          exit
        end if
      end if
      reason = pgs_watch_progress(mon, sweep, res)
      if (reason >= 0) exit
      reason = 2
    end do
    if (reason /= 0) zs = mon%xbest
  end subroutine pgs_scaled

  !> Start watching a PGS loop at its initial iterate x of residual res.
  pure subroutine pgs_watch_start(mon, tol, window, x, res)
    type(pgs_monitor_t), intent(out) :: mon
    real(dp), intent(in) :: tol, x(:), res
    integer, intent(in) :: window
    mon%tol = tol
    mon%window = window
    mon%best = res
    mon%reference = res
    mon%last_progress = 0
    mon%xbest = x
  end subroutine pgs_watch_start

  !> After a sweep: 3 (divergence) when the iterate x or its gaps v are not
  !> finite or beyond iterate_bound; otherwise -1, and x is kept when its
  !> residual res is the smallest so far.
  integer function pgs_watch_iterate(mon, x, v, res) result(reason)
    type(pgs_monitor_t), intent(inout) :: mon
    real(dp), intent(in) :: x(:), v(:), res
    reason = -1
    if (.not. (all(ieee_is_finite(x)) .and. all(ieee_is_finite(v)))) then
      reason = 3
    else if (maxval(abs(x)) > iterate_bound .or. maxval(abs(v)) > iterate_bound) then
      reason = 3
    else if (res < mon%best) then
      mon%best = res
      mon%xbest = x
    end if
  end function pgs_watch_iterate

  !> After a sweep that did not converge: 3 (divergence) when the residual
  !> res grew by divergence_factor over the best, 4 (stagnation) when the best
  !> fell by less than 0.1% over the last window sweeps, otherwise -1.
  integer function pgs_watch_progress(mon, sweep, res) result(reason)
    type(pgs_monitor_t), intent(inout) :: mon
    integer, intent(in) :: sweep
    real(dp), intent(in) :: res
    reason = -1
    if (res > divergence_factor * max(mon%best, mon%tol)) then
      reason = 3
    else if (mon%best < stagnation_factor * mon%reference) then
      mon%reference = mon%best
      mon%last_progress = sweep
    else if (sweep - mon%last_progress >= mon%window) then
      reason = 4
    end if
  end function pgs_watch_progress

  !> ws = qs + Ws zs.
  subroutine update_gap(p, zs, ws)
    type(scaled_lcp_t), intent(in) :: p
    real(dp), intent(in) :: zs(:)
    real(dp), intent(out) :: ws(:)
    ws = p%qs
    call dgemv('N', p%m, p%m, 1.0_dp, p%ws, p%m, zs, 1, 1.0_dp, ws, 1)
  end subroutine update_gap

end module lcp_solvers
