!> step_solver: the contact problem of one load step on its condensed rows,
!> by the method the deck asks for or by lcp=auto's order (lcp_auto), with
!> every fallback said in the run log and kept for the summary:
!>   frictionless  LCP(W, q) with the free rigid modes of the bodies and the
!>                 RIGIDs' free directions as equality constraints (contact_lcp)
!>   friction      the friction LCP of the step (friction_lcp, friction_newton),
!>                 and with bodies or RIGIDs held only by contact the friction
!>                 LCP that carries their amplitudes (friction_modes, Lemke)
!> Every answer a method returns is checked by its certificate (certificate:
!> the contact conditions, the cone, the free motions' equilibrium, each
!> relative to the problem's own scales); one that fails it is a failed
!> attempt, as a method's own failure is.  A failure that proves the step
!> has no solution is named (held_by_contact's diagnoses; category
!> error_no_equilibrium); a failure that proves nothing ends with what was
!> tried (error_unsolved), so that the caller may split the step or give up.
!>
!> Why it exists: the step is the same whatever the kinematics (small or
!> finite sliding) and whichever step of the history it is; the load-step
!> loop (load_steps) calls it once per step or geometry update.
!>
!> Programming interface
!>   solver_options(prob)          the deck's SOLVER tolerances as lcp_options_t
!>   solve_frictionless_step(prob, w, q, kstep, split, rsplit, log, sol, err)
!>   solve_friction_step(prob, w, fp, kstep, split, rsplit, log, z, sol, shift, err)
module step_solver
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str, format_number
  use errors, only: error_t, set_error, error_no_equilibrium, error_unsolved, error_numerical
  use run_log, only: log_t, say
  use problem, only: problem_t, step_label
  use step_solution, only: step_solution_t, add_fallback
  use certificate, only: certificate_t, certify_frictionless, certify_friction, certified, certificate_tol
  use lcp_solvers, only: lcp_options_t, lcp_report_t, info_no_memory
  use lcp_auto, only: lcp_attempt_t, auto_order, friction_order, proves_no_solution, add_attempt
  use contact_lcp, only: contact_solution_t, solve_contact
  use friction_lcp, only: friction_problem_t, solve_friction_lcp
  use friction_newton, only: solve_friction_newton
  use friction_modes, only: solve_friction_floating, no_equilibrium
  use mode_support, only: mode_split_t
  use rigid_support, only: rigid_split_t
  use rigid_modes, only: motion_name
  use held_by_contact, only: diagnose_pulled, floating_no_equilibrium, floating_names, unheld_summary
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solver_options, solve_frictionless_step, solve_friction_step

  !> rep%info of an answer that fails its certificate (beyond the methods' own codes)
  integer, parameter :: info_uncertified = 7

contains

  !> The deck's SOLVER tol=, maxit=, omega= as the solvers' options.
  function solver_options(prob) result(opts)
    type(problem_t), intent(in) :: prob
    type(lcp_options_t) :: opts
    opts%tol = prob%deck%solver%tol
    opts%maxit = prob%deck%solver%maxit
    opts%omega = prob%deck%solver%omega
  end function solver_options

  !> The methods a step tries, in order: lcp=auto's (lcp_auto), or the one
  !> the deck names alone.
  !>   friction (in) the step has tangential rows;  n (in) its normal rows
  subroutine methods_to_try(prob, friction, n, methods, omegas)
    type(problem_t), intent(in) :: prob
    logical, intent(in) :: friction
    integer, intent(in) :: n
    character(len=5), allocatable, intent(out) :: methods(:)
    real(dp), allocatable, intent(out) :: omegas(:)
    if (prob%deck%solver%lcp == 'auto') then
      call auto_order(friction, n, prob%deck%solver%omega, methods, omegas)
    else
      methods = [character(len=5) :: prob%deck%solver%lcp]
      omegas = [prob%deck%solver%omega]
    end if
  end subroutine methods_to_try

  !> The frictionless contact problem of a step: LCP(W, q) with the held
  !> combinations of the bodies' free modes and the RIGIDs' free directions
  !> as equality constraints (contact_lcp).
  !>   w      (in)  (nrow, nrow) W of the step's rows
  !>   q      (in)  (nrow) the step's gaps without contact forces
  !>   kstep  (in)  the load step (messages, fallbacks)
  !>   split, rsplit (in) the step's splits of the free modes
  !>   log    (inout) the notes on unheld modes, the fallbacks
  !>   sol    (inout) on exit mu, gap, alpha, rigid_alpha, split, unheld_mode,
  !>                method, iterations, residual; fallback grows
  !>   err    (out) error_no_equilibrium (proved) or error_unsolved
  subroutine solve_frictionless_step(prob, w, q, kstep, split, rsplit, log, sol, err)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: w(:,:), q(:)
    integer, intent(in) :: kstep
    type(mode_split_t), intent(in) :: split
    type(rigid_split_t), intent(in) :: rsplit
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(inout) :: sol
    type(error_t), allocatable, intent(out) :: err
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: lcp
    type(lcp_attempt_t), allocatable :: attempts(:)
    character(len=5), allocatable :: methods(:)
    real(dp), allocatable :: omegas(:), h(:,:), e(:), held(:,:)
    integer :: j, k, n, outer

    n = prob%cs%nrow
    opts = solver_options(prob)
    ! the multipliers of a body held only by contact: 100 iterations, 1000 under
    ! finite sliding, whose cylinder under a FORCE with 446 rows needed more
    ! (doc/theory.md, "Bodies held only by contact")
    outer = merge(1000, 100, any(prob%sc%specs%finite))
    ! H = B R (how the free modes open the gaps), e = R' f (their load), the
    ! combinations that the rows hold (split); the RIGIDs' free directions
    ! join the bodies' free modes (rigid_support)
    if (rsplit%k > 0) then
      h = reshape([split%h, rsplit%h(1:n, :)], [n, prob%fl%k + rsplit%k])
      e = [split%e, rsplit%e]
      held = block_diagonal(split%held, rsplit%held)
    else
      h = split%h
      e = split%e
      held = split%held
    end if
    call methods_to_try(prob, .false., n, methods, omegas)
    allocate(attempts(0))
    do k = 1, size(methods)
      opts%omega = omegas(k)
      call solve_contact(w, q, h, e, held, trim(methods(k)), opts, lcp, outer)
      if (lcp%rep%info == 0) then
        call certify_frictionless(w, q, h, e, held, lcp%mu, lcp%alpha, sol%cert)
        if (.not. certified(sol%cert)) call uncertified(sol%cert, lcp%rep)
      end if
      call add_attempt(attempts, trim(methods(k)), omegas(k), lcp%rep)
      if (lcp%rep%info == 0 .or. lcp%rep%info == info_no_memory) exit
      if (proves_no_solution(.false., .false., trim(methods(k)), lcp%rep)) exit
    end do
    call report_fallbacks(prob, kstep, attempts, log, sol)
    sol%method = trim(methods(size(attempts)))
    sol%iterations = lcp%rep%iterations
    sol%residual = lcp%rep%residual
    if (lcp%rep%info /= 0) then
      call step_failure(prob, kstep, attempts, split, rsplit, err)
      return
    end if
    if (.not. all(ieee_is_finite(lcp%mu))) then
      call set_error(err, step_label(prob, kstep) // 'the contact multipliers are not finite')
      return
    end if
    call move_alloc(lcp%mu, sol%mu)
    call move_alloc(lcp%gap, sol%gap)
    sol%q = q
    sol%alpha = lcp%alpha(1:prob%fl%k)
    if (allocated(sol%rigid_alpha)) deallocate(sol%rigid_alpha)
    if (rsplit%k > 0) sol%rigid_alpha = lcp%alpha(prob%fl%k + 1:)
    sol%split = split
    if (allocated(sol%unheld_mode)) deallocate(sol%unheld_mode)
    allocate(sol%unheld_mode(size(split%unheld, 2)))
    do j = 1, size(split%unheld, 2)
      call say(log, 'note     body ' // prob%sc%bodies(split%unheld_body(j))%name // ': rigid mode (' // &
        motion_name(prob%fl, split%unheld(:, j)) // ') held by neither FIX nor contact and unloaded: its amplitude ' // &
        'is set to 0 (the displacement has no component along it; the pressures do not depend on it)')
      sol%unheld_mode(j)%s = unheld_summary(prob, split, j)
    end do
  end subroutine solve_frictionless_step

  !> The frictional contact problem of a step, z = [lambda; tau]: the
  !> friction LCP (friction_lcp, friction_newton) warm-started from z, or,
  !> with bodies or RIGIDs held only by contact, the friction LCP that
  !> carries the amplitudes of their held combinations (friction_modes, by
  !> Lemke), H = C R V and e = V'R'f formed from the step's splits.
  !>   w      (in)    (n + nt, n + nt) G = C K^-1 C' of the step's rows
  !>   fp     (inout) the step's friction problem; on exit its gaps and slips
  !>                  include the free motions (q - H alpha)
  !>   z      (inout) the last step's multipliers on entry (the start); the step's on exit
  !>   sol    (inout) on exit alpha, rigid_alpha, split, method, iterations,
  !>                  residual; fallback grows
  !>   shift  (out)   (n + nt) H alpha: how the free motions move the rows (0 without them)
  !>   err    (out)   error_no_equilibrium (proved) or error_unsolved
  subroutine solve_friction_step(prob, w, fp, kstep, split, rsplit, log, z, sol, shift, err)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: w(:,:)
    type(friction_problem_t), intent(inout) :: fp
    integer, intent(in) :: kstep
    type(mode_split_t), intent(in) :: split
    type(rigid_split_t), intent(in) :: rsplit
    type(log_t), intent(inout) :: log
    real(dp), intent(inout) :: z(:)
    type(step_solution_t), intent(inout) :: sol
    real(dp), allocatable, intent(out) :: shift(:)
    type(error_t), allocatable, intent(out) :: err
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(lcp_attempt_t), allocatable :: attempts(:)
    character(len=5), allocatable :: methods(:)
    real(dp), allocatable :: omegas(:), hh(:,:), eh(:), alpha(:), unbalanced(:), z0(:)
    character(len=:), allocatable :: cause
    real(dp) :: capacity
    integer :: n, nt, kb, kr, k

    n = fp%n
    nt = fp%nt
    opts = solver_options(prob)
    kb = size(split%held, 2)
    kr = 0
    if (rsplit%k > 0) kr = size(rsplit%held, 2)
    allocate(shift(n + nt), source=0.0_dp)
    sol%split = split
    sol%q = fp%qn
    if (.not. allocated(sol%alpha)) allocate(sol%alpha(prob%fl%k), source=0.0_dp)
    if (kb + kr > 0) then
      ! the bodies' held modes, then the RIGIDs' held free directions
      hh = matmul(split%h, split%held)
      eh = matmul(transpose(split%held), split%e)
      if (kr > 0) then
        hh = reshape([hh, matmul(rsplit%h, rsplit%held)], [n + nt, kb + kr])
        eh = [eh, matmul(transpose(rsplit%held), rsplit%e)]
      end if
      allocate(alpha(kb + kr))
      call solve_friction_floating(w, fp, hh, eh, opts, z, alpha, rep, unbalanced, cause, capacity)
      if (rep%info == 0) then
        shift = matmul(hh, alpha)                    ! the step's rigid motion in the gaps and slips
        fp%qn = fp%qn - shift(1:n)
        fp%qt = fp%qt - shift(n + 1:)
        call certify_friction(w, fp, z, hh, eh, sol%cert)
        if (.not. certified(sol%cert)) call uncertified(sol%cert, rep)
      end if
      sol%method = 'lemke'
      sol%iterations = rep%iterations
      sol%residual = rep%residual
      if (rep%info == no_equilibrium) then
        call set_error(err, step_label(prob, kstep) // floating_no_equilibrium(prob, split, rsplit, unbalanced, cause, &
                       capacity), &
                       error_no_equilibrium)
        return
      end if
      if (rep%info /= 0) then
        if (rep%info == info_no_memory) then
          call set_error(err, rep%message)
          err%no_memory = .true.
        else
          call set_error(err, step_label(prob, kstep) // 'no equilibrium found for the bodies held only by contact (' // &
            floating_names(prob) // '): ' // rep%message, error_unsolved)
        end if
        return
      end if
      sol%alpha = matmul(split%held, alpha(1:kb))
      if (allocated(sol%rigid_alpha)) deallocate(sol%rigid_alpha)
      if (kr > 0) sol%rigid_alpha = matmul(rsplit%held, alpha(kb + 1:))
    else
      if (prob%deck%solver%lcp == 'auto') then
        call auto_order(.true., n, opts%omega, methods, omegas)
      else
        call friction_order(prob%deck%solver%lcp, opts%omega, methods, omegas)
        methods = methods(1:1)
        omegas = omegas(1:1)
      end if
      z0 = z
      allocate(attempts(0))
      do k = 1, size(methods)
        opts%omega = omegas(k)
        z = z0
        if (methods(k) == 'pdas') then
          call solve_friction_newton(w, fp, opts, z, rep)
        else
          call solve_friction_lcp(w, fp, trim(methods(k)), opts, z, rep)
        end if
        if (rep%info == 0) then
          call certify_friction(w, fp, z, reshape([real(dp) ::], [n + nt, 0]), [real(dp) ::], sol%cert)
          if (.not. certified(sol%cert)) call uncertified(sol%cert, rep)
        end if
        call add_attempt(attempts, trim(methods(k)), omegas(k), rep)
        if (rep%info <= 0 .or. rep%info == info_no_memory) exit
        if (proves_no_solution(.true., all(fp%cmu == 0.0_dp), trim(methods(k)), rep)) exit
      end do
      call report_fallbacks(prob, kstep, attempts, log, sol)
      sol%method = trim(methods(size(attempts)))
      sol%iterations = rep%iterations
      sol%residual = rep%residual
      if (rep%info /= 0) then
        call step_failure(prob, kstep, attempts, split, rsplit, err, friction=.true.)
        return
      end if
    end if
    if (.not. all(ieee_is_finite(z))) call set_error(err, step_label(prob, kstep) // &
      'the contact multipliers are not finite')
  end subroutine solve_friction_step

  !> A method's answer that fails its certificate: a failed attempt, its
  !> report saying by how much.
  subroutine uncertified(cert, rep)
    type(certificate_t), intent(in) :: cert
    type(lcp_report_t), intent(inout) :: rep
    rep%info = info_uncertified
    rep%stopped = 'certificate'
    rep%message = 'the answer fails its certificate (complementarity ' // real_to_str(cert%complementarity) // &
      ', cone ' // real_to_str(cert%cone) // ', equilibrium ' // real_to_str(cert%equilibrium) // &
      ', each relative; certified up to ' // real_to_str(certificate_tol) // ')'
  end subroutine uncertified

  !> The error of a step whose last method failed: out of memory as it is;
  !> a proof that there is no solution named by what the load pulls off its
  !> contacts when that explains it (frictionless), else with the method's
  !> message (error_no_equilibrium); otherwise every method's failure in turn
  !> (error_unsolved).
  subroutine step_failure(prob, kstep, attempts, split, rsplit, err, friction)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    type(lcp_attempt_t), intent(in) :: attempts(:)
    type(mode_split_t), intent(in) :: split
    type(rigid_split_t), intent(in) :: rsplit
    type(error_t), allocatable, intent(out) :: err
    logical, intent(in), optional :: friction
    character(len=:), allocatable :: text
    logical :: with_friction, tresca
    integer :: k
    with_friction = .false.
    if (present(friction)) with_friction = friction
    tresca = .false.
    if (with_friction) tresca = all(prob%cs%tan_mu == 0.0_dp)
    associate (last => attempts(size(attempts)))
      if (last%rep%info == info_no_memory) then
        call set_error(err, last%rep%message)
        err%no_memory = .true.
        return
      end if
      if (proves_no_solution(with_friction, tresca, last%method, last%rep)) then
        if (.not. with_friction) call diagnose_pulled(prob, split, rsplit, kstep, err)
        if (allocated(err)) return
      end if
      text = ''
      do k = 1, size(attempts)
        if (k > 1) text = text // '; then '
        if (allocated(attempts(k)%rep%message)) then
          text = text // attempts(k)%rep%message
        else
          text = text // 'not solved by ' // attempts(k)%method // ' (info ' // int_to_str(attempts(k)%rep%info) // ')'
        end if
      end do
      if (proves_no_solution(with_friction, tresca, last%method, last%rep)) then
        call set_error(err, step_label(prob, kstep) // 'contact problem not solved: ' // text, error_no_equilibrium)
      else
        call set_error(err, step_label(prob, kstep) // 'contact problem not solved: ' // text, error_unsolved)
      end if
    end associate
  end subroutine step_failure

  !> lcp=auto's fallbacks in a load step: a log line for each method that
  !> failed, saying why and what comes next, and a fallback in sol for the
  !> summary's `lcp_fallback STEP FROM TO`.
  !>   attempts (in) the methods tried, in order
  subroutine report_fallbacks(prob, kstep, attempts, log, sol)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    type(lcp_attempt_t), intent(in) :: attempts(:)
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(inout) :: sol
    character(len=:), allocatable :: why
    integer :: k
    do k = 1, size(attempts) - 1
      associate (a => attempts(k)%rep)
        select case (trim(a%stopped))
        case ('stagnated', 'diverged')
          why = trim(a%stopped) // ' at sweep ' // int_to_str(a%iterations)
        case ('sweep limit', 'pivot limit', 'step limit')
          why = 'reached its ' // trim(a%stopped) // ' (' // int_to_str(a%iterations) // ')'
        case ('ray')
          why = 'ended on a ray after ' // int_to_str(a%iterations) // ' pivots (Coulomb: no proof that there is no solution)'
        case ('inaccurate')
          why = 'ended with a residual above tol'
        case ('singular')
          why = 'met a singular system at step ' // int_to_str(a%iterations)
        case ('certificate')
          why = 'gave an answer that fails its certificate'
        case default
          why = 'failed'
          if (a%info == info_no_memory) why = 'ran out of memory'
        end select
      end associate
      call say(log, 'lcp      step ' // int_to_str(kstep) // '/' // int_to_str(prob%sc%steps) // ': ' // &
        method_label(attempts(k)) // ' ' // why // ', residual ' // real_to_str(attempts(k)%rep%residual) // &
        ', falling back to ' // method_label(attempts(k + 1)))
      call add_fallback(sol, kstep, method_word(attempts(k)), method_word(attempts(k + 1)))
    end do
  contains
    function method_label(a) result(t)
      type(lcp_attempt_t), intent(in) :: a
      character(len=:), allocatable :: t
      t = 'Lemke'
      if (a%method == 'pdas') t = 'PDAS (semismooth Newton)'
      if (a%method == 'pgs') t = 'PGS (omega ' // format_number(a%omega) // ')'
    end function method_label
    function method_word(a) result(t)
      type(lcp_attempt_t), intent(in) :: a
      character(len=:), allocatable :: t
      t = a%method
      if (a%method == 'pgs') t = 'pgs(omega=' // format_number(a%omega) // ')'
    end function method_word
  end subroutine report_fallbacks

  !> [a 0; 0 b]: the held combinations of the bodies' modes and of the RIGIDs'
  !> free directions, side by side.
  function block_diagonal(a, b) result(c)
    real(dp), intent(in) :: a(:,:), b(:,:)
    real(dp), allocatable :: c(:,:)
    allocate(c(size(a, 1) + size(b, 1), size(a, 2) + size(b, 2)), source=0.0_dp)
    c(1:size(a, 1), 1:size(a, 2)) = a
    c(size(a, 1) + 1:, size(a, 2) + 1:) = b
  end function block_diagonal

end module step_solver
