!> lcp_pgs: LCP(W, q) by projected Gauss-Seidel, and the stop tests every
!> PGS loop shares.
!>
!> Projected Gauss-Seidel with over-relaxation omega on the scaled problem
!> (lcp_scaling), zs_i <- max(0, zs_i - omega ws_i / Ws_ii), with ws = qs + Ws zs
!> kept up to date column by column (daxpy) and recomputed every 50 sweeps;
!> the natural residual is checked after every sweep.  Divergence (iterates
!> beyond 1e150 or the residual grown by 1e6 over its minimum) and stagnation
!> (the best residual not decreased by a factor 0.999 over max(1000, 10 n)
!> sweeps) stop with info = 3; z then holds the best iterate.
!>
!> Why it exists: the iterative method and its monitor (best iterate,
!> divergence, stagnation), which friction_lcp's block sweeps use too.  Who
!> may use it: through lcp_solvers.
!>
!> Programming interface
!>   solve_lcp_pgs(W, q, z, opts, rep)     z intent(inout): initial guess, clipped to >= 0
!>   pgs_outcome(reason, maxit, window, tol, label, iterate, problem, rep)   info and message
!>   type(pgs_monitor_t), pgs_watch_start, pgs_watch_iterate, pgs_watch_progress, pgs_refresh_sweeps
module lcp_pgs
  use kinds, only: dp
  use lapack_interfaces, only: daxpy, dgemv
  use diagnostics, only: int_to_str, real_to_str
  use lcp_scaling, only: lcp_options_t, lcp_report_t, scaled_lcp_t, prepare_lcp, measure_solution
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_lcp_pgs, pgs_outcome
  public :: pgs_monitor_t, pgs_watch_start, pgs_watch_iterate, pgs_watch_progress, pgs_refresh_sweeps

  real(dp), parameter :: divergence_factor = 1.0e6_dp      ! residual growth over its minimum
  real(dp), parameter :: stagnation_factor = 0.999_dp      ! decrease expected per window
  real(dp), parameter :: iterate_bound = 1.0e150_dp        ! iterates beyond this diverge
  integer, parameter :: pgs_refresh_sweeps = 50            ! recompute the gaps from scratch

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

  !> ws = qs + Ws zs.
  subroutine update_gap(p, zs, ws)
    type(scaled_lcp_t), intent(in) :: p
    real(dp), intent(in) :: zs(:)
    real(dp), intent(out) :: ws(:)
    ws = p%qs
    call dgemv('N', p%m, p%m, 1.0_dp, p%ws, p%m, zs, 1, 1.0_dp, ws, 1)
  end subroutine update_gap

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

end module lcp_pgs
