!> friction_fixed_point: one load step of frictional 2D contact by the fixed
!> point on the Tresca threshold, each Tresca problem solved exactly as the
!> convex QP it is.
!>
!> The problem and its scaled form are friction_lcp's and tresca_newton's
!> (scaled_friction_t: Gs, qs, s = D^-1 lam, v = qs + Gs s, bs0, mus, qscale).
!> With Coulomb's bounds frozen at the normal forces of the last iterate,
!>     bs_k^l = max(0, bs0_k + mus_k s_trow(k)^l),
!> the step's conditions are those of a Tresca problem, the KKT conditions of
!> a convex QP over a box (tresca_newton's module header), which has a
!> solution whenever the contact rows can hold the load.  It is solved by
!> friction_newton's method with these bounds and mus = 0
!> (solve_scaled_newton): primal-dual active set steps, and, should a
!> partition come back, the projected Newton method, which converges from
!> any start.  Its solution is s^{l+1}, and the iteration
!>     s^{l+1} = T(bs(s^l))
!> is repeated until the normal forces settle, i.e. until the residual r of
!> friction_lcp (with the bounds of s^{l+1} itself) is at most tol: r = 0
!> exactly at a fixed point, which is a solution of the Coulomb step.  T is
!> Lipschitz in the bounds, with a constant proportional to mu and to the
!> coupling of the normal and the tangential rows of G, so for small mu it
!> is a contraction: the fixed point exists, is unique, and the iteration
!> converges linearly (the argument by which Necas, Jarusek and Haslinger
!> proved existence for small friction; Haslinger, Hlavacek & Necas,
!> Handbook of Numerical Analysis IV, 1996, for the discrete problem).  Each
!> Tresca problem starts from the last solution, whose active and slipping
!> rows mostly stay: two to five Newton steps a problem on the skate of
!> doc/theory.md ("Friction near its limit").  With Tresca friction (every
!> cmu = 0) the bounds do not move and the first problem is the answer.
!>
!> Why it exists: it is the one friction method with a convergence proof
!> (for Tresca always, for Coulomb with small mu), and the slowest: linear
!> in the outer iterations, where the semismooth Newton method of
!> friction_newton is quadratic near a solution.  lcp=auto tries it last
!> (lcp_auto's friction_order).
!>
!> Stops: info 0 solved; 2 the step limit (Newton steps, default 500); 3 a singular QP (linearly dependent contact rows: stopped
!> 'singular') or an outer iteration that no longer contracts (r not halved
!> over 20 outer iterations: mu too large for the coupling in G, or no
!> solution; stopped 'stagnated'); 4 a QP that cannot decrease its objective
!> (round-off above tol, stopped 'inaccurate').  No failure shows that the
!> step has no solution.
!>
!> Programming interface
!>   solve_friction_fixed_point(g, prob, opts, lam, rep)
!>     g, prob as friction_lcp's solve_friction_lcp (check_friction_problem
!>     first: info -1, -2 with its message); opts%tol on friction_lcp's
!>     residual, opts%maxit the limit of Newton steps (0: 500);
!>     lam in: the starting point, out: the solution or the last iterate;
!>     rep: info above, iterations = Newton steps (linear solves),
!>     residual and complementarity of lam, message.
!> No routine prints anything.
module friction_fixed_point
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str
  use lcp_scaling, only: lcp_options_t, lcp_report_t, report_out_of_memory
  use friction_lcp, only: friction_problem_t, measure_friction
  use tresca_newton, only: scaled_friction_t, friction_residual_scaled, coulomb_bounds
  use friction_newton, only: solve_scaled_newton, newton_outcome_t, start_scaled
  implicit none
  private
  public :: solve_friction_fixed_point

  integer, parameter :: default_steps = 500    ! Newton steps when opts%maxit = 0
  !> The outer iteration stagnates when r has not been halved over this many
  !> outer iterations (a contraction of factor 0.97 or worse).
  integer, parameter :: stagnation_window = 20
  !> Each QP is solved to this fraction of tol, so that what is left of r at
  !> the end is the move of the bounds.
  real(dp), parameter :: inner_fraction = 0.5_dp

contains

  !> One load step by the fixed point on the Tresca threshold (module header).
  !>   g     (in)    (n+nt, n+nt) G, symmetric PSD, finite
  !>   prob  (in)    the step's problem
  !>   opts  (in)    tol (> 0), maxit (>= 0; 0: 500 Newton steps)
  !>   lam   (inout) (n+nt) starting point (negative lambda taken as 0); the
  !>                 solution when rep%info = 0, else the last iterate
  !>   rep   (out)   info 0 solved, 2 step limit, 3 singular QP or no
  !>                 contraction, 4 round-off, -1 / -2 g or prob invalid,
  !>                 -4 lam of the wrong size; iterations (Newton steps),
  !>                 residual, complementarity, message
  subroutine solve_friction_fixed_point(g, prob, opts, lam, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: lam(:)
    type(lcp_report_t), intent(out) :: rep
    type(scaled_friction_t) :: p
    type(newton_outcome_t) :: out
    real(dp), allocatable :: s(:), v(:), bs(:), zero(:)
    real(dp) :: r, best
    integer :: m, maxit, st, steps, outer, last_progress

    allocate(bs(prob%nt), zero(prob%nt), stat=st)
    call start_scaled(g, prob, 'friction fixed point', lam, st, p, s, v, rep)
    if (rep%info /= 0) return
    m = prob%n + prob%nt
    maxit = opts%maxit
    if (maxit == 0) maxit = default_steps
    zero = 0.0_dp
    r = friction_residual_scaled(p, p%bs0, p%mus, s, v)
    best = r
    last_progress = 0
    steps = 0
    outer = 0
    rep%info = 0
    do while (r > opts%tol)
      outer = outer + 1
      call coulomb_bounds(p, p%bs0, p%mus, s, bs)      ! the threshold of the last iterate
      call solve_scaled_newton(p, bs, zero, inner_fraction * opts%tol, maxit, s, v, steps, out)
      select case (out%info)
      case (0)
      case (2)
        rep%info = 2
        rep%stopped = 'step limit'
      case (3)
        rep%info = 3
        rep%stopped = 'singular'
      case (4)
        rep%info = 4
        rep%stopped = 'inaccurate'
      case default
        rep%info = out%info
      end select
      if (rep%info /= 0) exit
      r = friction_residual_scaled(p, p%bs0, p%mus, s, v)   ! with the bounds of s itself
      if (r <= 0.5_dp * best) then
        best = r
        last_progress = outer
      else if (outer - last_progress >= stagnation_window) then
        rep%info = 3
        rep%stopped = 'stagnated'
        exit
      end if
    end do
    rep%iterations = steps
    lam = p%d * s
    call measure_friction(g, prob, lam, rep)
    select case (rep%info)
    case (0)
      rep%message = 'friction fixed point: solved in ' // int_to_str(outer) // ' Tresca problems (' // &
        int_to_str(steps) // ' Newton steps), residual ' // real_to_str(rep%residual)
    case (2)
      rep%message = 'friction fixed point: step limit ' // int_to_str(maxit) // ' reached after ' // &
        int_to_str(outer) // ' Tresca problems, residual ' // real_to_str(rep%residual) // not_a_proof()
    case (3)
      if (rep%stopped == 'singular') then
        rep%message = 'friction fixed point: Tresca problem ' // int_to_str(outer) // ': ' // out%failure
      else
        rep%message = 'friction fixed point: no contraction, residual ' // real_to_str(rep%residual) // &
          ' not halved over ' // int_to_str(stagnation_window) // ' Tresca problems' // not_a_proof()
      end if
    case (4)
      rep%message = 'friction fixed point: Tresca problem ' // int_to_str(outer) // ': ' // out%failure
    case default
      call report_out_of_memory(rep, 'the Newton step of the friction LCP (' // int_to_str(m) // ' rows)', &
                                8.0_dp * real(m, dp) * real(m, dp))
    end select
  end subroutine solve_friction_fixed_point

  !> The tail of a failure message: the fixed point converges for small mu
  !> only, so its failure proves nothing.
  function not_a_proof() result(t)
    character(len=:), allocatable :: t
    t = ' (the fixed point converges for a small friction coefficient only, which does not show that ' // &
      'there is no solution)'
  end function not_a_proof

end module friction_fixed_point
