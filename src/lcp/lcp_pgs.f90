!> lcp_pgs: LCP(W, q) by projected Gauss-Seidel, and the sweep driver every
!> PGS loop shares.
!>
!> Projected Gauss-Seidel with over-relaxation omega on the scaled problem
!> (lcp_scaling), zs_i <- max(0, zs_i - omega ws_i / Ws_ii), with ws = qs + Ws zs
!> kept up to date column by column (daxpy) and recomputed every 50 sweeps;
!> the natural residual is checked after every sweep.  Divergence (iterates
!> beyond 1e150 or the residual grown by 1e6 over its minimum) and stagnation
!> (the smallest residual of a window of max(1000, 10 n) sweeps not 0.1%
!> below that of the window before, from the third window on) stop with
!> info = 3; z then holds the
!> best iterate.  So does a run too slow to end (solve_lcp_pgs; run_pgs's
!> slow_stop): at the end of every window the rate rho per sweep between
!> the two minima is measured, and when reaching tol at that rate would
!> take more than slow_factor = 10 times the sweep limit, the sweeps stop
!> (and a stagnation is reported as such a stop, with its rate: PGS
!> converges on a PSD LCP, so no progress means too slow).  Gauss-
!> Seidel converges at about 1 - 1/cond(Ws) per sweep, and a Ws dominated
!> by a few large eigenvalues, as a body held only by soft springs makes
!> it (its rigid motion gives a rank-2 part 1e6 times the elastic one:
!> doc/theory.md, "Friction near its limit"), gives rho = 1 - 1e-6: the
!> message names the rate and the cause, and the caller's exact finish on
!> the best iterate's active set (contact_lcp) or another method takes
!> over, 100 times sooner than at the sweep limit.  A correction along the
!> dominant eigenvectors of Ws does not help: the slow error lies in the
!> small, elastic eigenvalues that the soft part hides.
!>
!> Why it exists: the iterative method and its driver (the gaps refreshed,
!> the convergence test confirmed on fresh gaps, the best iterate, divergence,
!> stagnation, the stop reasons), which friction_lcp's block sweeps share:
!> a problem says how it sweeps and measures its residual (an extension of
!> pgs_problem_t), run_pgs does the rest on its matrix and vector.  The two
!> are deferred bindings rather than procedure arguments because the sweeps
!> need their problem's data, and an internal procedure passed as an argument
!> would need an executable stack (gfortran's trampolines).  Who may use it:
!> through lcp_solvers.
!>
!> Programming interface
!>   solve_lcp_pgs(W, q, z, opts, rep)     z intent(inout): initial guess, clipped to >= 0
!>   type, abstract :: pgs_problem_t       deferred sweep(omega, s, v), residual(s, v)
!>   run_pgs(prob, a, q, tol, omega, maxit, window, x, sweeps, reason [, slow_stop] [, rate])
!>                                         the sweeps until a stop
!>   pgs_set_row(a, j, xnew, x, v)         x_j <- xnew with v = q + A x kept up to date
!>   pgs_limits(maxit_opt, m, maxit, window)   the sweep limit and the stagnation window
!>   pgs_outcome(reason, maxit, window, tol, label, iterate, problem, rep [, rate])   info and message
module lcp_pgs
  use kinds, only: dp
  use lapack_interfaces, only: daxpy
  use strings, only: int_to_str, real_to_str
  use lcp_scaling, only: lcp_options_t, lcp_report_t, scaled_lcp_t, prepare_lcp, measure_solution, lcp_gaps
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_lcp_pgs, pgs_outcome, pgs_problem_t, run_pgs, pgs_set_row, pgs_limits

  real(dp), parameter :: divergence_factor = 1.0e6_dp      ! residual growth over its minimum
  real(dp), parameter :: stagnation_factor = 0.999_dp      ! decrease expected per window
  real(dp), parameter :: iterate_bound = 1.0e150_dp        ! iterates beyond this diverge
  !> A run stops as too slow when reaching tol at its measured rate would
  !> take more than this many times the sweep limit.
  real(dp), parameter :: slow_factor = 10.0_dp
  integer, parameter :: reason_too_slow = 5                ! run_pgs's reason: too slow to end
  integer, parameter :: pgs_refresh_sweeps = 50            ! recompute the gaps from scratch

  !> A problem that projected Gauss-Seidel solves (run_pgs): its iterate s
  !> and its gaps v = q + A s, both of the problem's size; what a sweep
  !> projects onto and how the residual is measured are the extension's.
  type, abstract :: pgs_problem_t
  contains
    procedure(sweep_interface), deferred :: sweep        !< one sweep: x and v updated
    procedure(residual_interface), deferred :: residual  !< the scale-free residual of (x, v)
  end type pgs_problem_t

  !> p the problem, s its (scaled) iterate, v the gaps of s, omega the relaxation.
  abstract interface
    subroutine sweep_interface(p, omega, s, v)
      import :: pgs_problem_t, dp
      class(pgs_problem_t), intent(in) :: p
      real(dp), intent(in) :: omega
      real(dp), intent(inout) :: s(:), v(:)
    end subroutine sweep_interface
    function residual_interface(p, s, v) result(r)
      import :: pgs_problem_t, dp
      class(pgs_problem_t), intent(in) :: p
      real(dp), intent(in) :: s(:), v(:)
      real(dp) :: r
    end function residual_interface
  end interface

  !> LCP(W, q) for run_pgs: the scaled problem on the rows kept (lcp_scaling).
  type, extends(pgs_problem_t) :: pgs_lcp_t
    type(scaled_lcp_t) :: lcp
  contains
    procedure :: sweep => lcp_sweep
    procedure :: residual => lcp_residual
  end type pgs_lcp_t

  !> The stop tests of run_pgs: the best iterate, divergence, stagnation,
  !> a run too slow to end.
  type :: pgs_monitor_t
    real(dp) :: tol = 0.0_dp               !< residual target
    real(dp) :: best = 0.0_dp              !< smallest residual so far
    real(dp), allocatable :: xbest(:)      !< the iterate of residual best
    integer :: window = 0                  !< the window of the progress tests (sweeps)
    integer :: window_start = 0            !< sweep at the start of the current window
    real(dp) :: window_min = 0.0_dp        !< smallest residual of the current window
    real(dp) :: last_min = 0.0_dp          !< of the window before (the start's residual at first)
    real(dp) :: rate = 1.0_dp              !< (window_min / last_min)^(1/window) of the last window
    logical :: slow_stop = .false.         !< stop a run too slow to end
    integer :: maxit = 0                   !< the sweep limit
  end type pgs_monitor_t


contains

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
    type(pgs_lcp_t) :: prob
    real(dp), allocatable :: zs(:)
    real(dp) :: rate
    integer :: maxit, k, window, stop_reason

    call prepare_lcp(W, q, z, opts, .true., prob%lcp, rep)
    if (rep%info /= 0) return
    associate (p => prob%lcp)
      call pgs_limits(opts%maxit, p%m, maxit, window)
      allocate(zs(p%m))
      do k = 1, p%m                                     ! zs = max(0, D^-1 z)
        zs(k) = 0.0_dp
        if (ieee_is_finite(z(p%rows(k)))) zs(k) = max(0.0_dp, z(p%rows(k)) / p%d(p%rows(k)))
      end do
      call run_pgs(prob, p%ws, p%qs, opts%tol, opts%omega, maxit, window, zs, rep%iterations, stop_reason, &
                   slow_stop=.true., rate=rate)
      z = 0.0_dp
      z(p%rows) = p%d(p%rows) * zs
      call measure_solution(W, q, p%d, z, rep)
    end associate

    call pgs_outcome(stop_reason, maxit, window, opts%tol, 'PGS', 'z', 'LCP', rep, rate)
  end subroutine solve_lcp_pgs

  !> info and message of a projected Gauss-Seidel run from its stop reason
  !> (0 converged, 2 sweep limit, 3 divergence, 5 too slow, other: stagnation).
  !>   reason  (in)    stop reason
  !>   maxit, window (in) the sweep limit and the stagnation window
  !>   tol     (in)    the residual target
  !>   label   (in)    the method's name in the message ('PGS')
  !>   iterate (in)    the name of the returned iterate ('z')
  !>   problem (in)    what is solved ('LCP', 'problem'), for the message
  !>   rep     (inout) iterations and residual set on entry; info, message set
  !>   rate    (in, optional) run_pgs's rate, named in the message of a run
  !>                   too slow
  subroutine pgs_outcome(reason, maxit, window, tol, label, iterate, problem, rep, rate)
    integer, intent(in) :: reason, maxit, window
    real(dp), intent(in) :: tol
    character(len=*), intent(in) :: label, iterate, problem
    type(lcp_report_t), intent(inout) :: rep
    real(dp), intent(in), optional :: rate
    character(len=:), allocatable :: pace
    select case (reason)
    case (0)
      rep%info = 0
      rep%message = label // ': converged in ' // int_to_str(rep%iterations) // ' sweeps, residual ' // &
        real_to_str(rep%residual)
    case (2)
      rep%info = 2
      rep%stopped = 'sweep limit'
      rep%message = label // ': sweep limit ' // int_to_str(maxit) // ' reached, residual ' // &
        real_to_str(rep%residual) // ' > tol ' // real_to_str(tol) // '; ' // iterate // ' is the best iterate'
    case (3)
      rep%info = 3
      rep%stopped = 'diverged'
      rep%message = label // ': divergence at sweep ' // int_to_str(rep%iterations) // '; ' // iterate // &
        ' is the best iterate, residual ' // real_to_str(rep%residual) // not_a_proof(problem)
    case (reason_too_slow)
      rep%info = 3
      rep%stopped = 'stagnated'
      pace = ''
      if (present(rate)) then
        if (rate < 1.0_dp) then
          pace = ', falling by ' // real_to_str(1.0_dp - rate) // ' of itself per sweep'
        else
          pace = ', not falling over the last ' // int_to_str(window) // ' sweeps'
        end if
      end if
      rep%message = label // ': too slow at sweep ' // int_to_str(rep%iterations) // ', residual ' // &
        real_to_str(rep%residual) // pace // ': at this rate tol ' // real_to_str(tol) // ' needs more than ' // &
        int_to_str(nint(slow_factor)) // ' times the sweep limit ' // int_to_str(maxit) // &
        '; Gauss-Seidel converges at about 1 - 1/cond ' // &
        'per sweep, and this ' // problem // ' is ill-conditioned (a body held only by soft springs, for ' // &
        'instance); ' // iterate // ' is the best iterate (this does not show that it has no solution: try ' // &
        'lcp=pdas or lcp=lemke)'
    case default
      rep%info = 3
      rep%stopped = 'stagnated'
      rep%message = label // ': stagnation at sweep ' // int_to_str(rep%iterations) // ', residual ' // &
        real_to_str(rep%residual) // ' not decreasing over ' // int_to_str(window) // ' sweeps; ' // iterate // &
        ' is the best iterate' // not_a_proof(problem)
    end select
  end subroutine pgs_outcome

  !> The tail of a divergence or stagnation message: PGS that does not
  !> converge proves nothing about the problem (with Coulomb friction and a
  !> large mu it stalls on problems that Lemke solves, and on an
  !> ill-conditioned one it crawls at about 1 - 1/cond per sweep), so the
  !> message says so and what to try instead.
  !>   problem (in) what is being solved ('LCP', 'problem')
  function not_a_proof(problem) result(t)
    character(len=*), intent(in) :: problem
    character(len=:), allocatable :: t
    t = ' (PGS does not converge on this ' // problem // ', which does not show that it has no solution: ' // &
      'a large friction coefficient or an ill-conditioned matrix (a body held only by soft springs) stalls it; ' // &
      'try lcp=pdas or lcp=lemke, or PGS with a smaller omega)'
  end function not_a_proof

  !> The sweep limit and the stagnation window of a PGS run on m unknowns.
  !>   maxit_opt (in)  the caller's limit, >= 0; 0 selects
  !>                   min(1e5, max(1e4, 1e10 / m^2))
  !>   m         (in)  the unknowns, >= 0
  !>   maxit     (out) the sweep limit
  !>   window    (out) the stagnation window, max(1000, 10 m) sweeps
  pure subroutine pgs_limits(maxit_opt, m, maxit, window)
    integer, intent(in) :: maxit_opt, m
    integer, intent(out) :: maxit, window
    maxit = maxit_opt
    if (maxit == 0) maxit = nint(min(1.0e5_dp, max(1.0e4_dp, 1.0e10_dp / real(max(m, 1), dp)**2)))
    window = max(1000, 10 * m)
  end subroutine pgs_limits

  !> Projected Gauss-Seidel sweeps on prob until they converge or stop
  !> (module header): the gaps v = q + A x recomputed every pgs_refresh_sweeps
  !> sweeps, the residual checked after every sweep and a converged one
  !> confirmed on recomputed gaps.
  !>   prob    (in)    the problem (its sweep and residual)
  !>   a       (in)    (m, m) its matrix A, which prob%sweep keeps v up to date with
  !>   q       (in)    (m) its vector q
  !>   tol     (in)    residual target
  !>   omega   (in)    relaxation, 0 < omega < 2 (passed to prob%sweep)
  !>   maxit   (in)    sweep limit
  !>   window  (in)    stagnation window (sweeps)
  !>   x       (inout) the initial guess, feasible; on exit the solution or the
  !>                   best iterate
  !>   sweeps  (out)   sweeps done
  !>   reason  (out)   0 converged, 2 limit, 3 divergence, 4 stagnation, 5 too
  !>                   slow (only with slow_stop)
  !>   slow_stop (in, optional) .true.: stop a run too slow to end (module
  !>                   header); default .false.
  !>   rate    (out, optional) the factor per sweep of the best residual over
  !>                   the last window measured (1 when none was)
  subroutine run_pgs(prob, a, q, tol, omega, maxit, window, x, sweeps, reason, slow_stop, rate)
    class(pgs_problem_t), intent(in) :: prob
    real(dp), intent(in) :: a(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(in) :: tol, omega
    integer, intent(in) :: maxit, window
    real(dp), intent(inout) :: x(:)
    integer, intent(out) :: sweeps, reason
    logical, intent(in), optional :: slow_stop
    real(dp), intent(out), optional :: rate
    type(pgs_monitor_t) :: mon
    real(dp), allocatable :: v(:)
    real(dp) :: res
    integer :: sweep

    sweeps = 0
    reason = 0
    if (present(rate)) rate = 1.0_dp
    if (size(x) == 0) return
    allocate(v(size(x)))
    call lcp_gaps(a, q, x, v)
    res = prob%residual(x, v)
    call pgs_watch_start(mon, tol, window, x, res)
    mon%maxit = maxit
    if (present(slow_stop)) mon%slow_stop = slow_stop
    if (res <= tol) return

    reason = 2
    do sweep = 1, maxit
      sweeps = sweep
      call prob%sweep(omega, x, v)
      if (mod(sweep, pgs_refresh_sweeps) == 0) call lcp_gaps(a, q, x, v)

      res = prob%residual(x, v)
      reason = pgs_watch_iterate(mon, x, v, res)
      if (reason >= 0) exit
      if (res <= tol) then
        call lcp_gaps(a, q, x, v)                     ! confirm without drift
        res = prob%residual(x, v)
        if (res <= tol) then
          reason = 0
          exit
        end if
      end if
      reason = pgs_watch_progress(mon, sweep, res)
      if (reason >= 0) exit
      reason = 2
    end do
    if (reason /= 0) x = mon%xbest
    if (present(rate)) rate = mon%rate
  end subroutine run_pgs

  !> The update of one unknown: x_j <- xnew, and the gaps v = q + A x kept up
  !> to date with column j of A (nothing when x_j does not change).
  !>   a     (in)    (m, m) the matrix A
  !>   j     (in)    the unknown, 1..m
  !>   xnew  (in)    its new value
  !>   x     (inout) (m) the iterate
  !>   v     (inout) (m) its gaps
  subroutine pgs_set_row(a, j, xnew, x, v)
    real(dp), intent(in), contiguous :: a(:, :)   ! column j goes to daxpy without a copy
    integer, intent(in) :: j
    real(dp), intent(in) :: xnew
    real(dp), intent(inout) :: x(:), v(:)
    real(dp) :: delta
    delta = xnew - x(j)
    if (delta /= 0.0_dp) then
      x(j) = xnew
      call daxpy(size(v), delta, a(:, j), 1, v, 1)   ! v = v + delta A(:, j)
    end if
  end subroutine pgs_set_row

  !> One projected SOR sweep on LCP(Ws, qs): zs_i <- max(0, zs_i - omega ws_i / Ws_ii).
  subroutine lcp_sweep(p, omega, s, v)
    class(pgs_lcp_t), intent(in) :: p
    real(dp), intent(in) :: omega
    real(dp), intent(inout) :: s(:), v(:)
    integer :: i
    do i = 1, p%lcp%m
      call pgs_set_row(p%lcp%ws, i, max(0.0_dp, s(i) - omega * v(i) / p%lcp%ws(i, i)), s, v)
    end do
  end subroutine lcp_sweep

  !> The natural residual ||min(zs, ws)||_inf / qscale.
  function lcp_residual(p, s, v) result(r)
    class(pgs_lcp_t), intent(in) :: p
    real(dp), intent(in) :: s(:), v(:)
    real(dp) :: r
    r = maxval(abs(min(s, v))) / p%lcp%qscale
  end function lcp_residual

  !> Start watching a PGS loop at its initial iterate x of residual res.
  pure subroutine pgs_watch_start(mon, tol, window, x, res)
    type(pgs_monitor_t), intent(out) :: mon
    real(dp), intent(in) :: tol, x(:), res
    integer, intent(in) :: window
    mon%tol = tol
    mon%window = window
    mon%best = res
    mon%xbest = x
    mon%window_start = 0
    mon%window_min = huge(1.0_dp)
    mon%last_min = res
    mon%rate = 1.0_dp
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
  !> res grew by divergence_factor over the best; at the end of a window of
  !> mon%window sweeps from the third on, 4 (stagnation; 5 with
  !> mon%slow_stop) when its smallest residual is not 0.1% below the window
  !> before's, 5 (too slow, with mon%slow_stop) when at the rate between the
  !> two reaching tol would take more than slow_factor times the sweep
  !> limit; otherwise -1.  The windows' minima, not the best so far, and the
  !> first window ignored: the residual of Gauss-Seidel is not monotone, and
  !> a dip in the first sweeps below the slow decrease that follows would
  !> read as no progress at all.
  integer function pgs_watch_progress(mon, sweep, res) result(reason)
    type(pgs_monitor_t), intent(inout) :: mon
    integer, intent(in) :: sweep
    real(dp), intent(in) :: res
    real(dp) :: need
    reason = -1
    if (res > divergence_factor * max(mon%best, mon%tol)) then
      reason = 3
      return
    end if
    mon%window_min = min(mon%window_min, res)
    if (sweep - mon%window_start < mon%window) return
    if (sweep <= 2 * mon%window) then
      ! the first window holds the start's transient, the second is the
      ! first reference
      mon%last_min = mon%window_min
      mon%window_min = huge(1.0_dp)
      mon%window_start = sweep
      return
    end if
    ! the end of a window: window_min = last_min rate^(sweeps)
    if (mon%window_min > 0.0_dp .and. mon%last_min > 0.0_dp) &
      mon%rate = (mon%window_min / mon%last_min)**(1.0_dp / real(sweep - mon%window_start, dp))
    if (.not. (mon%window_min < stagnation_factor * mon%last_min)) then
      reason = 4
      ! with slow_stop the problem is one that PGS solves (W PSD): no
      ! progress is a rate too slow
      if (mon%slow_stop) reason = reason_too_slow
    else if (mon%slow_stop .and. mon%rate < 1.0_dp .and. mon%window_min > mon%tol) then
      need = log(mon%tol / mon%window_min) / log(mon%rate)       ! sweeps to tol at this rate
      if (need > slow_factor * real(mon%maxit, dp)) reason = reason_too_slow
    end if
    mon%last_min = mon%window_min
    mon%window_min = huge(1.0_dp)
    mon%window_start = sweep
  end function pgs_watch_progress

end module lcp_pgs
