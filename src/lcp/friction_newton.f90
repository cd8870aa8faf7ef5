!> friction_newton: one load step of frictional 2D contact (Coulomb or
!> Tresca) by the primal-dual active set method, a semismooth Newton method
!> on the complementarity functions of the step, globalised.
!>
!> The problem and its symbols are friction_lcp's: G, [qn; qt], trow, cmu,
!> bound, lam = [lambda; tau], and the scaled problem Gs = D G D, qs = D q,
!> s = D^-1 lam, v = qs + Gs s, bs_k = bound_k / d_{n+k} + mus_k s_{trow(k)}
!> with mus_k = cmu_k d_{trow(k)} / d_{n+k} (tresca_newton's scaled_friction_t).
!> The conditions of the step are the zeros of (c = 1 on the scaled problem,
!> whose diagonal is 1)
!>     F_i = s_i - max(0, s_i - c v_i)                       normal rows
!>     F_j = s_j - clamp(s_j - c v_j, -b_k, b_k)             tangential rows, j = n + k,
!>           b_k = bs0_k + mus_k max(0, s_i - c v_i)         i = trow(k)
!> (s_j - c v_j = tau + c ds in scaled units), and their generalized Newton
!> step is fixed by a partition of the rows (Hueber, Stadler & Wohlmuth,
!> SIAM J. Sci. Comput. 30 (2008) 572-596, in 2D):
!>     A      normal rows in contact (s_i - c v_i > 0):       v_i = 0
!>     I      the other normal rows:                           s_i = 0
!>     St     sticking tangential rows:                        v_j = 0
!>     Sl     slipping rows, with a sign sg_k:                 s_j = sg_k bs_k
!> (a tangential row whose bound vanishes, Coulomb's open node, is in Sl
!> with tau = 0).  The step solves these m = n + nt linear equations:
!> s_I = 0 and s_Sl = sg (bound/d + mus s_trow) are substituted, which
!> leaves the rows A u St of Gs on the unknowns s_A, s_St, a dense
!> non-symmetric system (the slip columns add mus Gs(:, j) sg to the
!> columns of their normal rows) solved by LU (dgesv), O(|A u St|^3) per
!> step.
!>
!> Full steps.  The next partition is read off the new (s, v): A from
!> s_i - c v_i, the bound b from the predicted normal force max(0, s_i - c v_i);
!> a sticking row whose force exceeds b slips with the sign of its force, a
!> slipping row whose slip turns against its force (sg v_j > 0, ds = -v_j)
!> sticks.  This is the tangential rule above in the limit c -> 0: with
!> c = 1 a slipping row whose slip came out against its force went straight
!> to the opposite slip, and on a plate sheared with mu = 1 (bench/friction.sh)
!> sixty rows flipped sign at every step, a cycle of two partitions.  The
!> start takes the rows at their bound (|s_j| >= b (1 - 1e-9), b > 0) as
!> slipping, the others as sticking: from the previous step's solution, the
!> partition of that solution (a step of its own when its slipping rows were
!> taken at their bound to round-off only: 3 or 4 steps in place of 1 on
!> random Coulomb problems).  The iteration stops when the partition repeats and
!> the residual of friction_lcp is below tol.  Starting from the caller's lam
!> (the previous load step's solution) it needs 4 to 14 steps on that plate
!> where PGS needs hundreds of sweeps or stalls.
!>
!> Cycles.  The next partition is a function of the last one alone (the
!> step's system, then the rule above), so a partition seen before means an
!> endless cycle: near the friction limit, where every row of a skate pushed
!> sideways sits at |tau| = mu lambda with tiny slips (the side load at or
!> just below mu N), the full steps visit the same few partitions for ever.
!> Every partition visited is kept (one byte per row and step); at the first
!> one seen again the method globalises, from the iterate it has:
!>   Tresca (every cmu = 0): the step is the convex QP of tresca_newton,
!>     solved by its projected Newton method, monotone in the QP's objective,
!>     which converges from any start;
!>   Coulomb: damped Newton on the merit theta = ||F||_2^2 with F above.  The
!>     partition is F's piece at the iterate (A: s_i - v_i > 0; Sl when
!>     |s_j - v_j| > b, with its sign; St otherwise), whose system gives the
!>     Newton point s^N; F is affine on the piece, so along d = s^N - s
!>     F(s + t d) = (1 - t) F(s) until the piece changes, and the step
!>     t = 1, 1/2, 1/4, ... is the first with
!>         theta(s + t d) <= (1 - 2 sigma t) theta(s),  sigma = 1e-4
!>     (Armijo; v is affine in s, so a trial costs O(m)).  The full step is
!>     taken near a solution, where the method is Newton's again.  When no
!>     step down to 2^-30 decreases theta (a kink of F, or a stationary point
!>     of theta that is no solution: Coulomb's problem is not monotone),
!>     steps of the fixed point on the Tresca threshold take over: the Tresca
!>     problem with the bounds frozen at the iterate's normal forces,
!>     b_k = bs0_k + mus_k max(0, s_i), solved by this very method with
!>     mus = 0 (a recursion of depth one: full steps, then projected Newton
!>     on a cycle; friction_fixed_point iterates the same map), until the
!>     residual is below a tenth of its value where the damped steps
!>     stopped; then damped steps again.
!> On random Coulomb problems of 2 to 4 nodes with a dominant rank-1 part in
!> G (doc/theory.md, "Friction (beyond the paper)") the full steps alone
!> failed on 15 %, the globalised method on 0.3 %; with Tresca bounds on
!> 0.7 % and 0.005 %.  Where the full steps converge the path is theirs,
!> step for step.
!> Every test is a ratio of quantities in the units of qs, so the path does
!> not depend on the deck's units.
!>
!> The step limit counts linear solves, the projected Newton steps included;
!> the method stops with info 2 at the limit, 3 when the system of a full
!> step is singular (lcp=auto then falls back on Lemke's method), 4 when
!> the projected Newton method cannot decrease its objective any more
!> (round-off at a residual above tol).  Convergence from any start is
!> proved for Tresca; for Coulomb it is not (and solutions need not exist
!> for large mu): a failure does not show that there is no solution.
!>
!> Programming interface
!>   solve_friction_newton(g, prob, opts, lam, rep)
!>     g, prob as friction_lcp's solve_friction_lcp (check_friction_problem
!>     first: info -1, -2 with its message); opts%tol on
!>     friction_lcp's residual, opts%maxit the step limit (0: 50); lam in:
!>     the starting point, out: the solution or the last iterate; rep: info
!>     0 solved, 2 step limit, 3 singular partition or out of memory, 4 no
!>     decrease of the merit, < 0 g, prob or lam invalid,
!>     iterations = steps (linear solves), residual and complementarity of lam.
!>   solve_scaled_newton(p, bs0, mus, tol, maxit, s, v, steps, out)
!>     the same on tresca_newton's scaled problem p with the bounds
!>     bs0 + mus lambda (friction_fixed_point's Tresca problems: its bounds
!>     and zeros); type(newton_outcome_t) out: info, the step of the cycle,
!>     the fixed-point steps, the failure's text.
!>   start_scaled(g, prob, method, lam, st, p, s, v, rep)
!>     the arguments checked, p scaled and the start s, v of both methods
!> No routine prints anything.
module friction_newton
  use kinds, only: dp
  use lapack_interfaces, only: dgesv
  use strings, only: int_to_str, real_to_str
  use lcp_scaling, only: lcp_options_t, lcp_report_t, lcp_gaps, report_out_of_memory, set_report, info_no_memory
  use friction_lcp, only: friction_problem_t, measure_friction, check_friction_problem
  use tresca_newton, only: scaled_friction_t, scale_friction_problem, friction_residual_scaled, coulomb_bounds, &
    solve_tresca_qp, tresca_solved, tresca_step_limit, tresca_singular
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_friction_newton, solve_scaled_newton, newton_outcome_t, start_scaled

  integer, parameter :: default_steps = 50     ! step limit when opts%maxit = 0
  !> At the start a row within this relative distance of its bound is taken
  !> as slipping: from the previous step's solution its force is at its bound
  !> only to round-off.
  real(dp), parameter :: start_tol = 1.0e-9_dp
  !> Armijo's fraction of the decrease of theta predicted by the Newton step,
  !> and the smallest damping tried before a fixed-point step.
  real(dp), parameter :: armijo = 1.0e-4_dp
  real(dp), parameter :: smallest_damping = 2.0_dp**(-30)
  !> Where the damped Newton steps stop, fixed-point steps take over until
  !> the residual is below this fraction of its value there.
  real(dp), parameter :: leave_fixed_point = 0.1_dp
  integer, parameter :: row_inactive = 0, row_active = 1       ! normal rows: I, A
  integer, parameter :: row_stick = 2, row_slip = 3            ! tangential rows: St, Sl

  !> How solve_scaled_newton ended.
  type :: newton_outcome_t
    integer :: info = 2                  !< 0 solved, 2 step limit, 3 singular, 4 no decrease, info_no_memory
    integer :: cycle_step = 0            !< the step whose partition had been seen before (0: none)
    integer :: fixed_steps = 0           !< fixed-point steps of the Coulomb globalisation
    character(len=:), allocatable :: failure   !< what failed (info 3, 4), for the message
  end type newton_outcome_t

contains

  !> One load step by the primal-dual active set method (module header).
  !>   g     (in)    (n+nt, n+nt) G, symmetric PSD, finite
  !>   prob  (in)    the step's problem, valid
  !>   opts  (in)    tol (> 0), maxit (>= 0; 0: 50 steps)
  !>   lam   (inout) (n+nt) starting point (negative lambda taken as 0);
  !>                 the solution when rep%info = 0, else the last iterate
  !>   rep   (out)   info 0 solved, 2 step limit, 3 singular or out of memory,
  !>                 4 no decrease of the merit, -1 / -2 g or prob invalid
  !>                 (check_friction_problem), -4 lam of the wrong size;
  !>                 iterations (steps), residual, complementarity, message
  subroutine solve_friction_newton(g, prob, opts, lam, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: lam(:)
    type(lcp_report_t), intent(out) :: rep
    type(scaled_friction_t) :: p
    type(newton_outcome_t) :: out
    real(dp), allocatable :: s(:), v(:)
    integer :: m, maxit, st, steps

    st = 0
    call start_scaled(g, prob, 'friction Newton', lam, st, p, s, v, rep)
    if (rep%info /= 0) return
    m = prob%n + prob%nt
    maxit = opts%maxit
    if (maxit == 0) maxit = default_steps
    steps = 0
    call solve_scaled_newton(p, p%bs0, p%mus, opts%tol, maxit, s, v, steps, out)
    rep%iterations = steps
    rep%info = out%info
    lam = p%d * s
    call measure_friction(g, prob, lam, rep)
    select case (rep%info)
    case (0)
      rep%message = 'friction Newton: solved in ' // int_to_str(rep%iterations) // ' steps, residual ' // &
        real_to_str(rep%residual) // globalised(out, all(prob%cmu == 0.0_dp))
    case (2)
      rep%stopped = 'step limit'
      rep%message = 'friction Newton: no convergence in ' // int_to_str(maxit) // ' steps (residual ' // &
        real_to_str(rep%residual) // globalised(out, all(prob%cmu == 0.0_dp)) // &
        '; the method converges only near a solution with Coulomb friction, which does not show that there is none)'
    case (3)
      rep%stopped = 'singular'
      rep%message = 'friction Newton: ' // out%failure
    case (4)
      rep%stopped = 'inaccurate'
      rep%message = 'friction Newton: ' // out%failure
    case default
      call report_out_of_memory(rep, 'the Newton step of the friction LCP (' // int_to_str(m) // ' rows)', &
                                8.0_dp * real(m, dp) * real(m, dp))
    end select
  end subroutine solve_friction_newton

  !> The start of the methods on the scaled problem, this module's and
  !> friction_fixed_point's: the arguments checked, the problem scaled, and
  !> s = D^-1 lam (a non-finite entry and a negative lambda taken as 0) with
  !> its gaps.
  !>   g, prob, lam (in) as solve_friction_newton
  !>   method (in)    the method's name, at the head of an argument error
  !>   st     (in)    0, or the failed status of the caller's own workspace,
  !>                  which is then out of memory as the scaling is
  !>   p      (out)   the scaled problem
  !>   s, v   (out)   (n+nt) the start and its gaps
  !>   rep    (inout) info < 0 on an argument error (check_friction_problem;
  !>                  -4 lam of the wrong size), info_no_memory when out of
  !>                  memory; else unchanged
  subroutine start_scaled(g, prob, method, lam, st, p, s, v, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: lam(:)
    integer, intent(inout) :: st
    type(scaled_friction_t), intent(out) :: p
    real(dp), allocatable, intent(out) :: s(:), v(:)
    type(lcp_report_t), intent(inout) :: rep
    integer :: m, i

    call check_friction_problem(g, prob, rep)
    if (rep%info < 0) return
    m = prob%n + prob%nt
    if (size(lam) /= m) then
      call set_report(rep, -4, method // ': lam has ' // int_to_str(size(lam)) // ' entries (expected n + nt = ' // &
        int_to_str(m) // ')')
      return
    end if
    if (st == 0) call scale_friction_problem(g, prob, p, st)
    if (st == 0) allocate(s(m), v(m), stat=st)
    if (st /= 0) then
      call report_out_of_memory(rep, 'scaling the friction LCP (' // int_to_str(m) // ' rows)', &
                                8.0_dp * real(m, dp) * real(m + 8, dp))
      return
    end if
    do i = 1, m                                        ! s = D^-1 lam, lambda >= 0
      s(i) = 0.0_dp
      if (ieee_is_finite(lam(i))) s(i) = lam(i) / p%d(i)
      if (i <= prob%n) s(i) = max(0.0_dp, s(i))
    end do
    call lcp_gaps(p%gs, p%qs, s, v)
  end subroutine start_scaled

  !> The note of a message on the globalisation, '' when the full steps did.
  function globalised(out, tresca) result(t)
    type(newton_outcome_t), intent(in) :: out
    logical, intent(in) :: tresca
    character(len=:), allocatable :: t
    t = ''
    if (out%cycle_step == 0) return
    if (tresca) then
      t = ' (a partition came back at step ' // int_to_str(out%cycle_step) // &
        ', then projected Newton on the Tresca QP)'
    else
      t = ' (a partition came back at step ' // int_to_str(out%cycle_step) // ', then damped Newton steps and ' // &
        int_to_str(out%fixed_steps) // ' fixed-point steps)'
    end if
  end function globalised

  !> The method of the module header on the scaled problem p with the bounds
  !> bs_k = bs0_k + mus_k s_trow(k): the step's own (p%bs0, p%mus), or a
  !> Tresca problem's (bounds and zeros: friction_fixed_point, and the
  !> fixed-point steps of the Coulomb globalisation, by recursion).
  !>   p        (in)    the scaled problem
  !>   bs0, mus (in)    (nt) the bounds' parts, >= 0; every mus = 0: Tresca
  !>   tol      (in)    the target of the residual r, > 0
  !>   maxit    (in)    the step limit (steps counted from their value on entry)
  !>   s, v     (inout) (n+nt) the iterate, s_i >= 0 on the normal rows, and
  !>                    its gaps; on exit the solution or the last iterate
  !>   steps    (inout) steps done (linear solves), incremented
  !>   out      (out)   info, the step of the cycle, the fixed-point steps
  recursive subroutine solve_scaled_newton(p, bs0, mus, tol, maxit, s, v, steps, out)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:), tol
    integer, intent(in) :: maxit
    real(dp), intent(inout) :: s(:), v(:)
    integer, intent(inout) :: steps
    type(newton_outcome_t), intent(out) :: out
    type(newton_outcome_t) :: inner
    real(dp), allocatable :: sn(:), bs(:), zero(:)
    integer, allocatable :: kind(:), next(:), sg(:), nsg(:)
    character(len=1), allocatable :: seen(:, :)
    integer :: n, m, st, info, nseen
    real(dp) :: r, stuck
    logical :: same, tresca, full, fixing

    n = p%n
    m = n + p%nt
    tresca = all(mus == 0.0_dp)
    allocate(sn(m), bs(p%nt), zero(p%nt), kind(m), next(m), sg(p%nt), nsg(p%nt), stat=st)
    if (st == 0) allocate(seen(m, 8), stat=st)
    if (st /= 0) then
      out%info = info_no_memory
      return
    end if
    zero = 0.0_dp
    call pdas_partition(p, bs0, mus, s, v, .true., kind, sg)
    nseen = 0
    call remember(kind, sg, seen, nseen)

    full = .true.
    fixing = .false.
    stuck = 0.0_dp
    out%info = 2
    do while (steps < maxit)
      if (full) then
        ! a full step to the point of the partition
        steps = steps + 1
        call newton_point(p, bs0, mus, kind, sg, .true., sn, info)
        if (info /= 0) then
          out%info = info
          out%failure = 'the system of step ' // int_to_str(steps) // ' is singular (linearly dependent contact rows)'
          return
        end if
        s = sn
        call lcp_gaps(p%gs, p%qs, s, v)
        next = kind
        nsg = sg
        call pdas_partition(p, bs0, mus, s, v, .false., next, nsg)
        same = all(next == kind) .and. all(nsg == sg .or. next(n + 1:) /= row_slip)
        kind = next
        sg = nsg
        if (same) then
          if (friction_residual_scaled(p, bs0, mus, s, v) <= tol) then
            out%info = 0
            return
          end if
        end if
        if (was_seen(kind, sg, seen, nseen)) then
          full = .false.                               ! a cycle: globalise from here
          out%cycle_step = steps
        else
          call remember(kind, sg, seen, nseen)
        end if
        cycle
      else if (tresca) then
        ! the convex QP by projected Newton, from the projection of s
        call solve_tresca_qp(p, max(0.0_dp, bs0), tol, maxit, s, v, steps, info)
        select case (info)
        case (tresca_solved)
          out%info = 0
        case (tresca_step_limit)
          out%info = 2
        case (tresca_singular)
          out%info = 3
          out%failure = 'the Tresca QP is singular at step ' // int_to_str(steps) // ' (linearly dependent contact rows)'
        case default
          out%info = 4
          out%failure = 'projected Newton on the Tresca QP cannot decrease its objective at step ' // &
            int_to_str(steps) // ' (round-off)'
        end select
        return
      else if (.not. fixing) then
        steps = steps + 1
        call damped_step(p, bs0, mus, s, v, kind, sg, info)
        if (info == info_no_memory) then
          out%info = info
          return
        end if
      else
        ! a step of the fixed point on the Tresca threshold, until r falls
        ! below leave_fixed_point of its value where Newton stopped
        out%fixed_steps = out%fixed_steps + 1
        call coulomb_bounds(p, bs0, mus, s, bs)
        call solve_scaled_newton(p, bs, zero, tol, maxit, s, v, steps, inner)
        if (inner%info == 3 .or. inner%info == 4) then
          out%info = inner%info
          out%failure = 'in the fixed-point step at step ' // int_to_str(steps) // ', ' // inner%failure
          return
        else if (inner%info == info_no_memory) then
          out%info = info_no_memory
          return
        end if
      end if
      ! after a damped or a fixed-point step: solved, or which of the two comes next
      r = friction_residual_scaled(p, bs0, mus, s, v)
      if (r <= tol) then
        out%info = 0
        return
      end if
      if (fixing) then
        fixing = r > leave_fixed_point * stuck
      else if (info /= 0) then
        fixing = .true.                                ! theta does not decrease
        stuck = r
      end if
    end do
  end subroutine solve_scaled_newton

  !> The full step's partition of the rows at (s, v) (module header), the
  !> tangential rows from their class before (kind, sg on entry; first:
  !> .true. for the starting point, where they have none).
  !>   p        (in)    the scaled problem
  !>   bs0, mus (in)    (nt) the bounds' parts
  !>   s, v     (in)    (n+nt) the iterate and its gaps
  !>   first    (in)    the start's rule
  !>   kind     (inout) (n+nt) row_inactive / row_active (normal rows),
  !>                    row_stick / row_slip (tangential rows)
  !>   sg       (inout) (nt) the sign of each slipping row
  pure subroutine pdas_partition(p, bs0, mus, s, v, first, kind, sg)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:), s(:), v(:)
    logical, intent(in) :: first
    integer, intent(inout) :: kind(:), sg(:)
    real(dp) :: b
    integer :: i, k, j, n
    n = p%n
    do i = 1, n
      kind(i) = merge(row_active, row_inactive, s(i) - v(i) > 0.0_dp)
    end do
    do k = 1, p%nt
      j = n + k
      i = p%trow(k)
      b = bs0(k)
      if (kind(i) == row_active) b = b + mus(k) * max(0.0_dp, s(i) - v(i))
      if (b <= 0.0_dp) then
        kind(j) = row_slip                             ! no bound: tau = 0
        sg(k) = 1
      else if (.not. first .and. kind(j) == row_slip) then
        ! a slipping row sticks when its slip turns against its force
        ! (ds = -v_j, sg ds < 0), and never flips sign in one step
        if (real(sg(k), dp) * v(j) > 0.0_dp) kind(j) = row_stick
      else if (abs(s(j)) >= b * (1.0_dp - merge(start_tol, 0.0_dp, first)) .and. &
               (.not. first .or. s(j) /= 0.0_dp)) then
        kind(j) = row_slip                             ! a sticking row beyond its bound slips
        sg(k) = int(sign(1.0_dp, s(j)))
      else
        kind(j) = row_stick
        sg(k) = 0
      end if
    end do
  end subroutine pdas_partition

  !> The piece of F at (s, v) (module header): A where s_i - v_i > 0, Sl with
  !> the sign of s_j - v_j where |s_j - v_j| > b (or b = 0), St otherwise.
  !>   p, bs0, mus, s, v  (in)  as pdas_partition
  !>   kind     (out) (n+nt) the rows' classes
  !>   sg       (out) (nt) the signs of the slipping rows (0 when sticking)
  pure subroutine piece_partition(p, bs0, mus, s, v, kind, sg)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:), s(:), v(:)
    integer, intent(out) :: kind(:), sg(:)
    real(dp) :: b, y
    integer :: i, k, j
    do i = 1, p%n
      kind(i) = merge(row_active, row_inactive, s(i) - v(i) > 0.0_dp)
    end do
    do k = 1, p%nt
      j = p%n + k
      i = p%trow(k)
      b = bs0(k) + mus(k) * max(0.0_dp, s(i) - v(i))
      y = s(j) - v(j)                                  ! tau + ds, scaled
      if (b <= 0.0_dp) then
        kind(j) = row_slip
        sg(k) = 1
      else if (abs(y) > b) then
        kind(j) = row_slip
        sg(k) = int(sign(1.0_dp, y))
      else
        kind(j) = row_stick
        sg(k) = 0
      end if
    end do
  end subroutine piece_partition

  !> theta = ||F(s)||_2^2 (module header), from s and its gaps v.
  pure function merit(p, bs0, mus, s, v) result(theta)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:), s(:), v(:)
    real(dp) :: theta
    real(dp) :: b
    integer :: i, k, j
    theta = 0.0_dp
    do i = 1, p%n
      theta = theta + (s(i) - max(0.0_dp, s(i) - v(i)))**2
    end do
    do k = 1, p%nt
      j = p%n + k
      i = p%trow(k)
      b = bs0(k) + mus(k) * max(0.0_dp, s(i) - v(i))
      theta = theta + (s(j) - min(b, max(-b, s(j) - v(j))))**2
    end do
  end function merit

  !> The point of a partition: the solution of its m linear equations (module
  !> header) by LU on the rows A u St.
  !>   p, bs0, mus (in) the scaled problem and its bounds' parts
  !>   kind  (in)  (n+nt) the partition
  !>   sg    (in)  (nt) the signs of the slipping rows
  !>   clip  (in)  .true.: a slipping row's force is sg max(0, bs_k), as the
  !>               full steps have it; .false.: sg bs_k, the point of the
  !>               affine piece (the Newton point of the damped steps)
  !>   s     (out) (n+nt) the point
  !>   info  (out) 0; 3 singular; info_no_memory
  subroutine newton_point(p, bs0, mus, kind, sg, clip, s, info)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:)
    integer, intent(in) :: kind(:), sg(:)
    logical, intent(in) :: clip
    real(dp), intent(out) :: s(:)
    integer, intent(out) :: info
    real(dp), allocatable :: a(:, :), r(:)
    integer, allocatable :: unk(:), col(:), ipiv(:)
    real(dp) :: b
    integer :: n, m, nu, i, j, k, st

    n = p%n
    m = n + p%nt
    allocate(col(m))
    ! the unknowns: the rows of A and St, in order
    nu = 0
    col = 0
    do i = 1, m
      if (kind(i) == row_active .or. kind(i) == row_stick) then
        nu = nu + 1
        col(i) = nu
      end if
    end do
    allocate(unk(nu))
    do i = 1, m
      if (col(i) > 0) unk(col(i)) = i
    end do
    ! Gs(A u St, A u St) with the slip columns folded into their normal rows'
    allocate(a(nu, nu), r(nu), ipiv(nu), stat=st)
    if (st /= 0) then
      info = info_no_memory
      return
    end if
    do j = 1, nu
      a(:, j) = p%gs(unk, unk(j))
    end do
    r = -p%qs(unk)
    do k = 1, p%nt
      j = n + k
      if (kind(j) /= row_slip) cycle
      r = r - p%gs(unk, j) * real(sg(k), dp) * bs0(k)                   ! s_j = sg (bs0 + mus s_i)
      i = p%trow(k)
      if (col(i) > 0) a(:, col(i)) = a(:, col(i)) + p%gs(unk, j) * real(sg(k), dp) * mus(k)
    end do
    info = 0
    if (nu > 0) then
      call dgesv(nu, 1, a, nu, ipiv, r, nu, info)
      if (info /= 0) then
        info = 3
        return
      end if
    end if
    do i = 1, m
      if (col(i) > 0) then
        s(i) = r(col(i))
      else if (i <= n) then
        s(i) = 0.0_dp
      end if
    end do
    do k = 1, p%nt
      j = n + k
      if (kind(j) /= row_slip) cycle
      b = bs0(k)
      if (col(p%trow(k)) > 0) b = b + mus(k) * s(p%trow(k))
      if (clip) b = max(0.0_dp, b)
      s(j) = real(sg(k), dp) * b
    end do
  end subroutine newton_point

  !> One damped Newton step on theta (module header): the Newton point of F's
  !> piece at s, then the largest of t = 1, 1/2, ... 2^-30 that passes
  !> Armijo's test.
  !>   p, bs0, mus (in) the scaled problem and its bounds' parts
  !>   s, v     (inout) (n+nt) the iterate and its gaps, moved when info = 0
  !>   kind, sg (out)   the piece's partition
  !>   info     (out)   0 a step taken; 3 the piece's system is singular; 5 no
  !>                    step decreases theta; info_no_memory
  subroutine damped_step(p, bs0, mus, s, v, kind, sg, info)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:)
    real(dp), intent(inout) :: s(:), v(:)
    integer, intent(out) :: kind(:), sg(:)
    integer, intent(out) :: info
    real(dp), allocatable :: sn(:), vn(:), st(:), vt(:)
    real(dp) :: theta, t
    integer :: m

    m = size(s)
    allocate(sn(m), vn(m), st(m), vt(m))
    call piece_partition(p, bs0, mus, s, v, kind, sg)
    call newton_point(p, bs0, mus, kind, sg, .false., sn, info)
    if (info /= 0) return
    call lcp_gaps(p%gs, p%qs, sn, vn)
    theta = merit(p, bs0, mus, s, v)
    t = 1.0_dp
    do
      st = s + t * (sn - s)
      vt = v + t * (vn - v)                            ! v is affine in s
      if (merit(p, bs0, mus, st, vt) <= (1.0_dp - 2.0_dp * armijo * t) * theta) exit
      t = 0.5_dp * t
      if (t < smallest_damping) then
        info = 5
        return
      end if
    end do
    s = st
    call lcp_gaps(p%gs, p%qs, s, v)                    ! fresh gaps, no drift
  end subroutine damped_step

  !> The partition as one character per row: 'I', 'A' (normal rows), 'S'
  !> (stick), '+', '-' (slip with its sign).
  pure function partition_code(kind, sg, n) result(code)
    integer, intent(in) :: kind(:), sg(:), n
    character(len=1) :: code(size(kind))
    integer :: i
    do i = 1, size(kind)
      select case (kind(i))
      case (row_inactive)
        code(i) = 'I'
      case (row_active)
        code(i) = 'A'
      case (row_stick)
        code(i) = 'S'
      case default
        code(i) = merge('+', '-', sg(i - n) >= 0)
      end select
    end do
  end function partition_code

  !> Add the partition (kind, sg) to seen(:, 1:nseen), growing seen when full.
  subroutine remember(kind, sg, seen, nseen)
    integer, intent(in) :: kind(:), sg(:)
    character(len=1), allocatable, intent(inout) :: seen(:, :)
    integer, intent(inout) :: nseen
    character(len=1), allocatable :: grown(:, :)
    if (nseen == size(seen, 2)) then
      allocate(grown(size(seen, 1), 2 * size(seen, 2)))
      grown(:, 1:nseen) = seen(:, 1:nseen)
      call move_alloc(grown, seen)
    end if
    nseen = nseen + 1
    seen(:, nseen) = partition_code(kind, sg, size(kind) - size(sg))
  end subroutine remember

  !> .true. when the partition (kind, sg) is among seen(:, 1:nseen).
  logical function was_seen(kind, sg, seen, nseen)
    integer, intent(in) :: kind(:), sg(:)
    character(len=1), intent(in) :: seen(:, :)
    integer, intent(in) :: nseen
    character(len=1) :: code(size(kind))
    integer :: k
    code = partition_code(kind, sg, size(kind) - size(sg))
    was_seen = .false.
    do k = 1, nseen
      if (all(seen(:, k) == code)) then
        was_seen = .true.
        return
      end if
    end do
  end function was_seen

end module friction_newton
