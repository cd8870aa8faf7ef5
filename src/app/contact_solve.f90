!> contact_solve: the contact problem of a run, once W and q are condensed:
!> the choice of method (SOLVER lcp=, auto from the measured crossovers), the
!> load stepping (OUTPUT steps=all without friction, the friction steps with
!> it), the bodies and RIGIDs held only by contact (their mode amplitudes as
!> unknowns or equality constraints) and the diagnoses when no equilibrium
!> exists, naming the body, the RIGID or the direction.
!>
!> Why it exists: it is the method's decision layer between the condensed
!> problem and the solvers (contact_lcp, friction_lcp, friction_modes); the
!> program calls it once.  Who may use it: the program and its step modules
!> (run_state's list).  No equilibrium or an unsolved problem ends the run
!> (exit 1 with the diagnosis), as the program would; input the solvers
!> cannot take ends it with exit 2 at the SOLVER line.
!>
!> The step itself is contact_step's, finite sliding finite_sliding's, and
!> the diagnoses of bodies held only by contact held_by_contact's.
!>
!> Programming interface
!>   solve_contact_lcp(run)      the contact problem, every load step it needs
module contact_solve
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t
  use exits, only: fail_numerical
  use run_state, only: run_t, ph_lcp
  use run_report, only: say, say_step, lap
  use scene, only: step_loads
  use load_groups, only: group_factor
  use contact_condensation, only: constraint_values
  use lcp_solvers, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: solve_friction_lcp, friction_state, friction_problem_t, friction_problem
  use friction_auto, only: friction_attempt_t, solve_friction_auto
  use friction_newton, only: solve_friction_newton
  use friction_modes, only: solve_friction_floating, no_equilibrium
  use mode_support, only: mode_split_t, split_free_modes
  use rigid_support, only: split_rigid_modes
  use results_writer, only: results_t, string_t
  use deck_expressions, only: format_number
  use linear_system, only: solve_loads
  use post_processing, only: contact_measures
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use run_phase, only: enter_phase
  use held_by_contact, only: split_step_modes, floating_no_equilibrium, &
                             floating_names
  use contact_step, only: solve_contact_problem, friction_results, record_step, keep_friction_solution
  use finite_sliding, only: solve_finite_steps, solve_finite_friction_steps
  implicit none
  private
  public :: solve_contact_lcp

contains

  !> The contact problem of the run, by the method the deck asks for:
  !> frictionless, LCP(W, q) with the free rigid modes as equality
  !> constraints (contact_lcp), the final step alone unless OUTPUT steps=all
  !> asks for every step; with friction, the load steps in order, each a
  !> friction LCP warm-started from the last (friction_lcp, friction_modes).
  !> Without contact only the earlier steps of OUTPUT steps=all are solved.
  !> Each earlier step's results are its own, recorded (its VTK file and
  !> table row) and dropped; only the final step's are kept in res.
  !>   run (inout) W, q, the splits on entry; res%mu (tau, slip), gaps and the contact measures on exit
  subroutine solve_contact_lcp(run)
    type(run_t), intent(inout) :: run
    type(results_t) :: final
    real(dp), allocatable :: rigid_alpha(:)
    call enter_phase('solving the LCP')
    if (.not. run%with_contact) then
      if (run%deck%output%steps_all) call solve_earlier_steps(run)
      return
    end if
    if (run%cs%ntan > 0 .and. any(run%sc%specs%finite)) then
      call enter_phase('solving the friction LCP')
      call solve_finite_friction_steps(run)             ! sliding=finite with friction: every step, in order
    else if (run%cs%ntan > 0) then
      call enter_phase('solving the friction LCP')
      call solve_friction_steps(run)
    else if (any(run%sc%specs%finite)) then
      call solve_finite_steps(run, final, rigid_alpha)     ! sliding=finite: every step, in order
      call keep_solution(final, rigid_alpha, run)
      run%step_iterations = run%res%lcp_iterations
      if (run%deck%output%steps_all) then
        call contact_measures(run, run%res)
        call say_step(run, run%sc%steps, run%res%lcp_method, run%step_iterations, run%res%active_nodes)
        deallocate(run%res%pressure, run%res%status)
      end if
    else
      if (run%deck%output%steps_all) call solve_earlier_steps(run)
      call solve_contact_problem(run, final, rigid_alpha)
      call keep_solution(final, rigid_alpha, run)
      run%step_iterations = run%res%lcp_iterations
      if (run%deck%output%steps_all) then
        call contact_measures(run, run%res)
        call say_step(run, run%sc%steps, run%res%lcp_method, run%step_iterations, run%res%active_nodes)
        deallocate(run%res%pressure, run%res%status)         ! measured again below, as without steps
      end if
    end if
    call contact_measures(run, run%res)
    call lap(run, ph_lcp)
  end subroutine solve_contact_lcp

  !> The final step's solution into the run's results: mu, gaps, the
  !> amplitudes of the free modes, the unheld modes, the method's report,
  !> and the RIGIDs' free motion.
  !>   sol         (inout) solve_contact_problem's results (moved out: empty on exit)
  !>   rigid_alpha (inout) its RIGIDs' free motion (moved out)
  subroutine keep_solution(sol, rigid_alpha, run)
    type(results_t), intent(inout) :: sol
    real(dp), allocatable, intent(inout) :: rigid_alpha(:)
    type(run_t), intent(inout) :: run
    call move_alloc(sol%mu, run%res%mu)
    call move_alloc(sol%gap, run%res%gap)
    call move_alloc(sol%alpha, run%res%alpha)
    call move_alloc(sol%unheld_mode, run%res%unheld_mode)
    run%res%lcp_method = sol%lcp_method
    run%res%lcp_iterations = sol%lcp_iterations
    run%res%lcp_residual = sol%lcp_residual
    call move_alloc(rigid_alpha, run%rigid_alpha)
  end subroutine keep_solution

  !> OUTPUT steps=all without friction: steps 1 .. n-1, each an independent
  !> solve at its load factors with the factorization and W of the final
  !> step (only the right-hand side changes): u0_k = K^-1 f_k, q_k = g - B u0_k,
  !> LCP(W, q_k), u_k = K^-1 (f_k - B' mu_k).  Each step's results are its
  !> own (step), written to its VTK file and table row; res is not touched
  !> (the final step is solved next).
  subroutine solve_earlier_steps(run)
    type(run_t), intent(inout) :: run
    type(results_t) :: step, none
    type(mode_split_t) :: split_n
    real(dp), allocatable :: fk(:), ubk(:), u0k(:), cq(:), q_n(:), rigid_alpha(:)
    integer :: kstep
    split_n = run%split
    if (allocated(run%q)) q_n = run%q
    allocate(fk(run%sc%ndof), ubk(run%sc%ndof), u0k(run%sc%ndof), cq(run%cs%nrow + run%cs%ntan))
    do kstep = 1, run%sc%steps - 1
      step = none
      run%step_note = 'load step ' // int_to_str(kstep) // ' of ' // int_to_str(run%sc%steps) // ': '
      call step_loads(run%sc, kstep, fk, ubk)
      call solve_loads(run, fk, ubk, [real(dp) ::], u0k)
      if (run%with_contact) then
        call constraint_values(run%cs, u0k, cq)
        run%q = run%cs%g - cq(1:run%cs%nrow)                   ! gaps without contact forces
        call split_step_modes(run, fk)
        call solve_contact_problem(run, step, rigid_alpha)
        call contact_measures(run, step)
        run%step_iterations = step%lcp_iterations
        call record_step(run, kstep, fk, ubk, step%mu, rigid_alpha, step)
        call say_step(run, kstep, step%lcp_method, run%step_iterations, step%active_nodes)
      else
        run%step_iterations = 0
        call record_step(run, kstep, fk, ubk, [real(dp) ::], rigid_alpha, step)
      end if
    end do
    run%split = split_n
    if (run%rsplit%k > 0) call split_rigid_modes(run%cs, run%sc%rigids, run%sc%fixed, run%sc%fext, run%rsplit)
    if (allocated(q_n)) run%q = q_n
    run%step_note = 'load step ' // int_to_str(run%sc%steps) // ' of ' // int_to_str(run%sc%steps) // ': '
    call step_loads(run%sc, run%sc%steps, fk, ubk)         ! the bodies' thermal strains of the final step
  end subroutine solve_earlier_steps

  !> Frictional contact in load steps: at step k the loads are the ramps'
  !> factors times their loads, the slip of the step is measured from the
  !> tangential displacement T u of step k-1, and the condensed friction LCP
  !> (normal and tangential multipliers, friction_lcp) is solved, warm-started
  !> from step k-1.  With OUTPUT steps=all each earlier step's results are
  !> its own (step), recorded and dropped; res holds the final step's.
  subroutine solve_friction_steps(run)
    type(run_t), intent(inout) :: run
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    character(len=:), allocatable :: method, first
    real(dp), allocatable :: z(:), cu(:), qn(:), qt(:), sprev(:), fk(:), ubk(:)
    real(dp), allocatable :: hh(:,:), eg(:,:), eh(:), alpha(:), unbalanced(:), body_alpha(:), rigid_alpha(:)
    integer, allocatable :: fstate(:)
    character(len=:), allocatable :: cause
    integer :: n, nt, kstep, g, iterations
    logical :: floating
    type(results_t) :: step, none
    character(len=200) :: line
    type(error_t), allocatable :: err
    type(friction_problem_t) :: fp
    type(friction_attempt_t), allocatable :: attempts(:)
    logical :: auto

    n = run%cs%nrow
    nt = run%cs%ntan
    opts%tol = run%deck%solver%tol
    opts%maxit = run%deck%solver%maxit
    opts%omega = run%deck%solver%omega
    method = run%deck%solver%lcp
    ! lcp=auto: the primal-dual active set method first, the fastest at every
    ! size measured (bench/friction.sh, doc/performance.md, "The friction
    ! solvers": 3 to 20 times Lemke from 68 to 516 unknowns of Lemke's LCP,
    ! and PGS stalls on a plate sheared with mu = 1), then Lemke and PGS when
    ! it fails (solve_friction_auto): the default fails only where every
    ! method does
    auto = method == 'auto'
    if (auto) method = 'pdas'
    first = method
    ! bodies held only by contact: the amplitudes of the held combinations of
    ! their modes are unknowns of the friction LCP (friction_modes), against
    ! H = C R V and the load e = V'R'f of each ramp
    allocate(body_alpha(run%fl%k), source=0.0_dp)
    floating = size(run%split%held, 2) + size(run%rsplit%held, 2) > 0
    if (floating) then
      method = 'lemke'
      call say(run, 'friction ' // int_to_str(size(run%split%held, 2) + size(run%rsplit%held, 2)) // ' rigid-mode amplitudes ' // &
        'of the bodies and RIGIDs held only by contact are unknowns of each step''s friction LCP, solved by ' // &
        'Lemke (' // int_to_str(n + 3 * nt + 2 * (size(run%split%held, 2) + size(run%rsplit%held, 2))) // ' unknowns)')
      ! the bodies' held modes, then the RIGIDs' held free directions (their FORCE per ramp)
      hh = reshape([matmul(run%split%h, run%split%held), matmul(run%rsplit%h, run%rsplit%held)], &
                   [n + nt, size(run%split%held, 2) + size(run%rsplit%held, 2)])
      eg = reshape([transpose(matmul(transpose(run%split%held), matmul(transpose(run%fl%r), run%sc%fgroup))), &
                    transpose(matmul(transpose(run%rsplit%held), run%sc%fgroup(run%rsplit%dof, :)))], &
                   [size(run%sc%ramp, 2), size(hh, 2)])
      eg = transpose(eg)
      allocate(eh(size(hh, 2)), alpha(size(hh, 2)))
    end if
    allocate(z(n + nt), cu(n + nt), qn(n), qt(nt), sprev(nt), fstate(nt))
    if (run%deck%output%steps_all) allocate(fk(run%sc%ndof), ubk(run%sc%ndof))
    z = 0.0_dp
    sprev = 0.0_dp
    iterations = 0
    do kstep = 1, run%sc%steps
      cu = 0.0_dp
      do g = 1, size(run%sc%ramp, 2)
        cu = cu + group_factor(run%sc, g, kstep) * run%cu0(:, g)
      end do
      qn = run%cs%g - cu(1:n)                          ! gaps without contact forces
      qt = sprev - cu(n + 1:)                      ! minus the slip of the step without contact forces
      fp = friction_problem(qn, qt, run%cs%tan_row, run%cs%tan_mu, run%cs%tan_bound)
      if (floating) then
        eh = 0.0_dp
        do g = 1, size(run%sc%ramp, 2)
          eh = eh + group_factor(run%sc, g, kstep) * eg(:, g)
        end do
        call solve_friction_floating(run%w, fp, hh, eh, opts, z, alpha, rep, unbalanced, cause)
        if (rep%info == no_equilibrium) call fail_numerical('friction, load step ' // int_to_str(kstep) // ' of ' // &
          int_to_str(run%sc%steps) // ': ' // floating_no_equilibrium(run, unbalanced, cause))
        if (rep%info /= 0 .and. .not. rep%no_memory) call fail_numerical('friction, load step ' &
          // int_to_str(kstep) // ' of ' // int_to_str(run%sc%steps) // ': no equilibrium found for the bodies held ' // &
          'only by contact (' // floating_names(run) // '): ' // rep%message)
        cu = cu + matmul(hh, alpha)                ! C u0 + C R alpha: the step's rigid motion
        qn = run%cs%g - cu(1:n)
        qt = qt - matmul(hh(n + 1:, :), alpha)
        fp = friction_problem(qn, qt, run%cs%tan_row, run%cs%tan_mu, run%cs%tan_bound)
        body_alpha = matmul(run%split%held, alpha(1:size(run%split%held, 2)))
        rigid_alpha = matmul(run%rsplit%held, alpha(size(run%split%held, 2) + 1:))
      else if (auto) then
        call solve_friction_auto(run%w, fp, first, opts, z, rep, attempts)
        method = attempts(size(attempts))%method
        call report_fallbacks(run, kstep, attempts)
      else if (method == 'pdas') then
        call solve_friction_newton(run%w, fp, opts, z, rep)
      else
        call solve_friction_lcp(run%w, fp, method, opts, z, rep)
      end if
      iterations = iterations + rep%iterations
      if (rep%info /= 0 .and. rep%no_memory) call fail_numerical(rep%message)
      if (rep%info /= 0) call fail_numerical('friction, load step ' // int_to_str(kstep) // ' of ' // &
        int_to_str(run%sc%steps) // ': contact problem not solved: ' // rep%message)
      if (.not. all(ieee_is_finite(z))) call fail_numerical('friction, load step ' // int_to_str(kstep) // &
        ': the contact multipliers are not finite')
      sprev = cu(n + 1:) - matmul(run%w(n + 1:, :), z)  ! T u_k = T u0_k - T K^-1 C' z
      call friction_state(run%w, fp, z, fstate, err)
      if (allocated(err)) call fail_numerical(err%message)
      write(line, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,es9.2)') 'step     ', kstep, '/', run%sc%steps, ': ' // method // ' ', &
        rep%iterations, ' iterations, ', count(z(1:n) > 0.0_dp), ' active, ', count(fstate == 2), &
        ' slipping, residual ', rep%residual
      call say(run, trim(line))
      run%step_iterations = rep%iterations
      if (run%deck%output%steps_all .and. kstep < run%sc%steps) then
        ! this step's displacement, fields and row (the final step is the run's own)
        step = none
        step%mu = z(1:n)
        step%tau = z(n + 1:)
        step%fstate = fstate
        step%gap = qn + matmul(run%w(1:n, :), z)
        step%alpha = body_alpha
        step%slip = sprev
        step%fstate = fstate
        call friction_results(run, step)
        call contact_measures(run, step)
        call step_loads(run%sc, kstep, fk, ubk)
        call record_step(run, kstep, fk, ubk, z, rigid_alpha, step)
        call step_loads(run%sc, run%sc%steps, fk, ubk)
      end if
    end do
    call keep_friction_solution(run, method, iterations, rep, z, qn, sprev, body_alpha, fstate, rigid_alpha, floating)
  end subroutine solve_friction_steps

  !> lcp=auto's fallbacks in a load step (solve_friction_auto): a log line
  !> for each method that failed, saying why and what comes next, and a
  !> summary line `lcp_fallback STEP FROM TO` for each.
  !>   kstep    (in) the step
  !>   attempts (in) the methods tried, in order
  subroutine report_fallbacks(run, kstep, attempts)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: kstep
    type(friction_attempt_t), intent(in) :: attempts(:)
    type(string_t), allocatable :: lines(:)
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
        case default
          why = 'failed'
          if (a%no_memory) why = 'ran out of memory'
        end select
      end associate
      call say(run, 'lcp      step ' // int_to_str(kstep) // '/' // int_to_str(run%sc%steps) // ': ' // &
        method_label(attempts(k)) // ' ' // why // ', residual ' // real_to_str(attempts(k)%rep%residual) // &
        ', falling back to ' // method_label(attempts(k + 1)))
      if (.not. allocated(run%res%lcp_fallback)) allocate(run%res%lcp_fallback(0))
      allocate(lines(size(run%res%lcp_fallback) + 1))
      lines(1:size(run%res%lcp_fallback)) = run%res%lcp_fallback
      lines(size(lines))%s = int_to_str(kstep) // ' ' // method_word(attempts(k)) // ' ' // method_word(attempts(k + 1))
      call move_alloc(lines, run%res%lcp_fallback)
    end do
  contains
    function method_label(a) result(t)
      type(friction_attempt_t), intent(in) :: a
      character(len=:), allocatable :: t
      t = 'Lemke'
      if (a%method == 'pdas') t = 'PDAS (semismooth Newton)'
      if (a%method == 'pgs') t = 'PGS (omega ' // format_number(a%omega) // ')'
    end function method_label
    function method_word(a) result(t)
      type(friction_attempt_t), intent(in) :: a
      character(len=:), allocatable :: t
      t = a%method
      if (a%method == 'pgs') t = 'pgs(omega=' // format_number(a%omega) // ')'
    end function method_word
  end subroutine report_fallbacks
end module contact_solve
