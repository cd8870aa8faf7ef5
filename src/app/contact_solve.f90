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
!> Programming interface
!>   solve_contact_lcp(run)      the contact problem, every load step it needs
!>   check_floating_bodies(run)  a body with a free rigid mode must be in a CONTACT (exit 2)
!>   check_floating_friction_solver(run)  lcp=pgs refused for friction on bodies held only by contact (exit 2)
!>   check_unheld_loads(run)     no load along a rigid mode nothing holds (exit 1)
!>   check_unheld_rigid_loads(run)  no load along a RIGID's direction nothing holds (exit 1)
module contact_solve
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, add_error
  use exits, only: stop_input_errors, fail_numerical
  use run_state, only: run_t, ph_lcp
  use run_report, only: say, say_step, lap
  use scene, only: step_loads
  use load_groups, only: group_factor
  use contact_condensation, only: constraint_values, condense
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke
  use friction_lcp, only: solve_friction_lcp, friction_state, friction_problem_t, friction_problem
  use friction_auto, only: friction_attempt_t, solve_friction_auto
  use friction_newton, only: solve_friction_newton
  use friction_modes, only: solve_friction_floating, no_equilibrium
  use contact_lcp, only: contact_solution_t, solve_contact
  use contact_set, only: row_keys, node_traction, build_moved_contact_set, contact_set_t
  use rigid_modes, only: mode_name, motion_name, describe_motion, remove_motions
  use mode_support, only: mode_split_t, split_free_modes
  use rigid_support, only: split_rigid_modes, rigid_direction, pulled_rigid
  use results_writer, only: results_t, string_t
  use deck_expressions, only: format_number
  use linear_system, only: solve_loads
  use post_processing, only: pair_resultants, post_process, contact_measures, nodal_contact_fields, &
                             check_finite_results
  use run_outputs, only: write_step
  use run_estimate, only: estimate_results
  use contact_checks, only: check_step_sliding
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use run_phase, only: enter_phase
  use local_axes, only: rotate_constraint_rows
  implicit none
  private
  public :: solve_contact_lcp, check_floating_bodies, check_floating_friction_solver, check_unheld_loads, &
            check_unheld_rigid_loads

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

  !> The condensed contact problem LCP(W, q) of the step by the chosen
  !> method (with the free rigid modes as equality constraints).
  !>   run         (inout) W, q and the splits of the step on entry
  !>   sol         (out)   the step's mu, gap, alpha (the bodies' free modes),
  !>                       unheld_mode and the method's report (lcp_*)
  !>   rigid_alpha (out)   (rsplit%k) the RIGIDs' free motion
  subroutine solve_contact_problem(run, sol, rigid_alpha)
    type(run_t), intent(inout) :: run
    type(results_t), intent(out) :: sol
    real(dp), allocatable, intent(out) :: rigid_alpha(:)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: lcp
    character(len=:), allocatable :: method
    integer :: j, outer

    opts%tol = run%deck%solver%tol
    opts%maxit = run%deck%solver%maxit
    opts%omega = run%deck%solver%omega
    ! the multipliers of a body held only by contact: 100 iterations, 1000 under
    ! finite sliding, whose cylinder under a FORCE with 446 rows needed more
    ! (doc/theory.md, "Bodies held only by contact")
    outer = merge(1000, 100, any(run%sc%specs%finite))
    method = run%deck%solver%lcp
    ! lcp=auto from the measured crossovers (doc/performance.md, "The three LCP
    ! solvers"): up to about 100 constraints the three tie and Lemke's exact
    ! pivoting is kept; above, the primal-dual active set method needs a few
    ! Newton steps where the others need many pivots or sweeps
    if (method == 'auto') then
      if (run%cs%nrow <= 100) then
        method = 'lemke'
      else
        method = 'pdas'
      end if
    end if
    ! H = B R (how the free modes open the gaps), e = R' f (their load), the
    ! combinations that the rows hold: mode_support (split)
    if (run%rsplit%k > 0) then
      ! the RIGIDs' free directions join the bodies' free modes (rigid_support)
      call solve_contact(run%w, run%q, reshape([run%split%h, run%rsplit%h(1:run%cs%nrow, :)], [run%cs%nrow, &
        run%fl%k + run%rsplit%k]), &
                         [run%split%e, run%rsplit%e], &
                         block_diagonal(run%split%held, run%rsplit%held), method, opts, lcp, outer)
    else
      call solve_contact(run%w, run%q, run%split%h, run%split%e, run%split%held, method, opts, lcp, outer)
    end if
    sol%lcp_method = method
    sol%lcp_iterations = lcp%rep%iterations
    sol%lcp_residual = lcp%rep%residual
    if (lcp%rep%info /= 0) then
      if (lcp%rep%info == 1 .and. run%rsplit%k > 0) call diagnose_pulled_rigid(run)
      if (lcp%rep%info == 1 .and. run%fl%k > 0) call diagnose_pulled_body(run)
      if (allocated(lcp%rep%message)) then
        if (lcp%rep%no_memory) call fail_numerical(lcp%rep%message)
        call fail_numerical(step_prefix(run) // 'contact problem not solved: ' // lcp%rep%message)
      else
        call fail_numerical(step_prefix(run) // 'contact problem not solved by ' // method // ' (info ' // &
                            int_to_str(lcp%rep%info) // ')')
      end if
    end if
    if (.not. all(ieee_is_finite(lcp%mu))) call fail_numerical('the contact multipliers are not finite')
    call move_alloc(lcp%mu, sol%mu)
    rigid_alpha = lcp%alpha(run%fl%k + 1:)
    sol%alpha = lcp%alpha(1:run%fl%k)
    allocate(sol%unheld_mode(size(run%split%unheld, 2)))
    do j = 1, size(run%split%unheld, 2)
      call say(run, 'note     body ' // run%sc%bodies(run%split%unheld_body(j))%name // ': rigid mode (' // &
        motion_name(run%fl, run%split%unheld(:, j)) // ') held by neither FIX nor contact and unloaded: its amplitude ' // &
        'is set to 0 (the displacement has no component along it; the pressures do not depend on it)')
      sol%unheld_mode(j)%s = unheld_summary(run, j)
    end do

    call move_alloc(lcp%gap, sol%gap)
  end subroutine solve_contact_problem

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
        if (run%fl%k > 0) then
          call split_free_modes(run%cs, run%sc%bodies, run%fl, fk, run%split)
          call check_unheld_loads(run)
        end if
        if (run%rsplit%k > 0) then
          call split_rigid_modes(run%cs, run%sc%rigids, run%sc%fixed, fk, run%rsplit)
          call check_unheld_rigid_loads(run)
        end if
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

  !> CONTACT sliding=finite (frictionless): the load steps in
  !> order, each solved in the configuration the contact has reached.  In
  !> step k, from the current displacement u_c (step k's loads on the last
  !> step's contact forces and geometry), the pairing, normals and gaps are
  !> rebuilt at x + u_c (build_moved_contact_set: B_c, g = g(u_c) + B_c u_c),
  !> W = B_c K^-1 B_c' is condensed again on the same factor (the contact
  !> dofs do not change: every node of a finite pair's boundaries is one),
  !> q = g - B_c u0_k, the LCP solved and u_c = K^-1 (f_k - B_c' mu) + the
  !> free motions.  The fixed point stops when the rows (row_keys) and the
  !> active set are those of the previous update
  !> and the contact forces changed by less than finite_tol of their largest
  !> (doc/theory.md, "Finite sliding"); after SOLVER updates= updates the
  !> step is too large for the zone to be found again: exit 1 asking for
  !> more STEPS.  Earlier steps are recorded with OUTPUT steps=all.
  !>   run         (inout) the factor, y, u0 on entry; cs, w, q, cd, the splits of the final step on exit
  !>   sol         (out)   the final step's results, as solve_contact_problem
  !>   rigid_alpha (out)   the final step's RIGID free motion
  subroutine solve_finite_steps(run, sol, rigid_alpha)
    type(run_t), intent(inout) :: run
    type(results_t), intent(out) :: sol
    real(dp), allocatable, intent(out) :: rigid_alpha(:)
    real(dp), parameter :: finite_tol = 1.0e-8_dp
    type(results_t) :: step, none
    type(contact_set_t) :: moved
    type(error_t), allocatable :: err
    real(dp), allocatable :: fk(:), ubk(:), u0k(:), cq(:), uc(:), mu_prev(:)
    logical, allocatable :: active_prev(:)
    integer(i8), allocatable :: keys(:), keys_prev(:)
    integer :: kstep, it, updates
    integer(i8) :: t0, t1, rate
    real(dp) :: change, t_geometry, t_condense, t_lcp
    logical :: same
    integer :: finite_updates
    character(len=:), allocatable :: cause
    finite_updates = run%deck%solver%updates
    allocate(fk(run%sc%ndof), ubk(run%sc%ndof), u0k(run%sc%ndof), uc(run%sc%ndof), source=0.0_dp)
    t_geometry = 0
    t_condense = 0
    t_lcp = 0
    updates = 0
    do kstep = 1, run%sc%steps
      run%step_note = 'load step ' // int_to_str(kstep) // ' of ' // int_to_str(run%sc%steps) // ': '
      call step_loads(run%sc, kstep, fk, ubk)
      call solve_loads(run, fk, ubk, [real(dp) ::], u0k)
      if (kstep > 1) then
        ! the first configuration of the step: its loads and prescribed motion
        ! on the last step's contact forces, so that the bodies move with what
        ! drives them (a carriage moved alone would drag its body's edge)
        call solve_loads(run, fk, ubk, step%mu, uc)
        if (run%fl%k > 0) uc = uc + matmul(run%fl%r, step%alpha)
        call remove_motions(run%fl, run%split%unheld, uc)
        if (allocated(rigid_alpha)) uc(run%rsplit%dof) = rigid_alpha
      else
        uc = u0k                                         ! the step's loads and motion without contact
      end if
      do it = 1, finite_updates
        call system_clock(t0, rate)
        call build_moved_contact_set(run%sc%bodies, run%sc%specs, uc, moved, err)
        if (allocated(err)) call fail_numerical(run%step_note // 'sliding=finite: the contact geometry cannot be ' // &
          'rebuilt: ' // err%message)
        call rotate_constraint_rows(moved, run%sc%bodies)     ! nodes in local axes (FIX un=/ut=)
        call check_contact_dofs(run, moved)
        call move_alloc_set(moved, run%cs)
        call system_clock(t1)
        t_geometry = t_geometry + real(t1 - t0, dp) / real(rate, dp)
        ! W = B K^-1 B' on the factor of K (q from the final loads is replaced)
        call condense(run%cs, run%eq, run%factor, run%y, run%u0, run%w, run%q, run%cd, err, run%deck%solver%condense)
        if (allocated(err)) call fail_numerical(err%message)
        allocate(cq(run%cs%nrow))
        call constraint_values(run%cs, u0k, cq)
        run%q = run%cs%g - cq                                 ! gaps without contact forces
        deallocate(cq)
        if (run%fl%k > 0) then
          call split_free_modes(run%cs, run%sc%bodies, run%fl, fk, run%split)
          call check_unheld_loads(run)
        end if
        if (run%rsplit%k > 0) then
          call split_rigid_modes(run%cs, run%sc%rigids, run%sc%fixed, fk, run%rsplit)
          call check_unheld_rigid_loads(run)
        end if
        call system_clock(t0)
        t_condense = t_condense + real(t0 - t1, dp) / real(rate, dp)
        step = none
        call solve_contact_problem(run, step, rigid_alpha)
        call system_clock(t1)
        t_lcp = t_lcp + real(t1 - t0, dp) / real(rate, dp)
        updates = updates + 1
        ! the displacement of this update: the next configuration
        call solve_loads(run, fk, ubk, step%mu, uc)
        if (run%fl%k > 0) uc = uc + matmul(run%fl%r, step%alpha)
        call remove_motions(run%fl, run%split%unheld, uc)
        if (allocated(rigid_alpha)) uc(run%rsplit%dof) = rigid_alpha
        if (.not. all(ieee_is_finite(uc))) call fail_numerical(run%step_note // 'the displacement is not finite')
        same = .false.
        change = huge(1.0_dp)
        keys = row_keys(run%cs)
        if (same_rows(keys, keys_prev)) then
          same = all((step%mu > 0.0_dp) .eqv. active_prev)
          change = maxval(abs(step%mu - mu_prev)) / max(maxval(abs(step%mu)), tiny(1.0_dp))
        end if
        mu_prev = step%mu
        active_prev = step%mu > 0.0_dp
        call move_alloc(keys, keys_prev)
        if (same .and. change <= finite_tol) exit
      end do
      if (.not. (same .and. change <= finite_tol)) then
        if (same) then
          cause = 'the contact forces still change by ' // real_to_str(change) // ' of their largest'
        else
          cause = 'the active set still changes'
        end if
        call fail_numerical(run%step_note // 'sliding=finite: the contact zone was not found again: after ' // &
          int_to_str(finite_updates) // ' updates of the contact geometry ' // cause // ' (the step moves the ' // &
          'contact too far for the geometry of its start to find it; expected more STEPS, or more SOLVER updates=)')
      end if
      call say(run, 'finite   ' // run%step_note // int_to_str(it) // ' updates of the contact geometry')
      deallocate(mu_prev, active_prev, keys_prev)
      if (kstep < run%sc%steps .and. run%deck%output%steps_all) then
        call contact_measures(run, step)
        run%step_iterations = step%lcp_iterations
        call record_step(run, kstep, fk, ubk, step%mu, rigid_alpha, step)
        call say_step(run, kstep, step%lcp_method, run%step_iterations, step%active_nodes)
      end if
    end do
    call say(run, 'finite   ' // int_to_str(updates) // ' geometry updates in ' // int_to_str(run%sc%steps) // &
      ' steps: rebuild ' // real_to_str(t_geometry) // ' s, condensation ' // real_to_str(t_condense) // ' s, LCP ' // &
      real_to_str(t_lcp) // ' s')
    sol = step
  contains
    !> cs <- moved (moved is left empty)
    subroutine move_alloc_set(from, to)
      type(contact_set_t), intent(inout) :: from
      type(contact_set_t), intent(inout) :: to
      to = from
    end subroutine move_alloc_set
  end subroutine solve_finite_steps

  !> Rows of two rebuilds that are the same rows, in the same order
  pure logical function same_rows(keys, keys_prev)
    integer(i8), intent(in) :: keys(:)
    integer(i8), allocatable, intent(in) :: keys_prev(:)
    same_rows = .false.
    if (.not. allocated(keys_prev)) return
    if (size(keys) /= size(keys_prev)) return
    same_rows = all(keys == keys_prev)
  end function same_rows

  !> A rebuilt contact set must touch the dofs the factorization put last
  !> (contact_set marks every node of a finite pair's boundaries): else the
  !> condensation would read the wrong block of the factor.
  subroutine check_contact_dofs(run, moved)
    type(run_t), intent(in) :: run
    type(contact_set_t), intent(in) :: moved
    logical :: ok
    ok = moved%ncdof == run%cs%ncdof
    if (ok) ok = all(moved%cdof == run%cs%cdof)
    if (.not. ok) call fail_numerical(run%step_note // &
      'sliding=finite: the rebuilt contact rows do not match the factorization''s contact dofs')
  end subroutine check_contact_dofs

  !> CONTACT sliding=finite with friction: the load steps in
  !> order, each by the fixed point of solve_finite_steps on the friction
  !> LCP.  At every update the rows C_c = [B_c; T_c] are rebuilt at x + u_c
  !> and the slip of the step is measured along the current tangents from
  !> the last step's displacement u_{k-1}: qt = T_c u_{k-1} - T_c u0_k, so
  !> that the stick/slip history follows the moving pairing (the tangential
  !> force of a node is carried by its row, the node's own).  Bodies and
  !> RIGIDs held only by contact: their held amplitudes are unknowns of the
  !> friction LCP (friction_modes, Lemke), H and e formed again at every
  !> update.  The results of the final step fill res as solve_friction_steps.
  subroutine solve_finite_friction_steps(run)
    type(run_t), intent(inout) :: run
    real(dp), parameter :: finite_tol = 1.0e-8_dp
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(friction_problem_t) :: fp
    type(contact_set_t) :: moved
    type(error_t), allocatable :: err
    type(results_t) :: step, none
    real(dp), allocatable :: fk(:), ubk(:), u0k(:), uc(:), uprev(:), cu(:), cp(:), qn(:), qt(:), z(:), zprev(:)
    real(dp), allocatable :: hh(:,:), eh(:), alpha(:), unbalanced(:), body_alpha(:), rigid_alpha(:)
    integer, allocatable :: fstate(:)
    logical, allocatable :: active_prev(:)
    integer(i8), allocatable :: keys(:), keys_prev(:)
    logical :: rows_held
    character(len=:), allocatable :: cause, method
    integer :: n, nt, kstep, it, iterations, kb, kr
    real(dp) :: change
    logical :: same, floating
    character(len=200) :: line

    opts%tol = run%deck%solver%tol
    opts%maxit = run%deck%solver%maxit
    opts%omega = run%deck%solver%omega
    method = run%deck%solver%lcp
    if (method == 'auto') method = 'pdas'
    n = run%cs%nrow
    nt = run%cs%ntan
    floating = size(run%split%held, 2) + size(run%rsplit%held, 2) > 0
    if (floating) method = 'lemke'
    allocate(fk(run%sc%ndof), ubk(run%sc%ndof), u0k(run%sc%ndof), uc(run%sc%ndof), uprev(run%sc%ndof), source=0.0_dp)
    allocate(cu(n + nt), cp(n + nt), z(n + nt), fstate(nt), body_alpha(run%fl%k))
    z = 0.0_dp
    body_alpha = 0.0_dp
    iterations = 0
    do kstep = 1, run%sc%steps
      run%step_note = 'load step ' // int_to_str(kstep) // ' of ' // int_to_str(run%sc%steps) // ': '
      call step_loads(run%sc, kstep, fk, ubk)
      call solve_loads(run, fk, ubk, [real(dp) ::], u0k)
      if (kstep > 1) then                                ! as solve_finite_steps: the last step's forces
        call solve_loads(run, fk, ubk, z, uc)
        if (run%fl%k > 0) uc = uc + matmul(run%fl%r, body_alpha)
        call remove_motions(run%fl, run%split%unheld, uc)
        if (allocated(rigid_alpha)) uc(run%rsplit%dof) = rigid_alpha
      else
        uc = u0k
      end if
      do it = 1, run%deck%solver%updates
        call build_moved_contact_set(run%sc%bodies, run%sc%specs, uc, moved, err)
        if (allocated(err)) call fail_numerical(run%step_note // 'sliding=finite: the contact geometry cannot be ' // &
          'rebuilt: ' // err%message)
        call rotate_constraint_rows(moved, run%sc%bodies)     ! nodes in local axes (FIX un=/ut=)
        call check_contact_dofs(run, moved)
        run%cs = moved
        keys = row_keys(run%cs)
        rows_held = same_rows(keys, keys_prev)
        if (.not. rows_held) then
          ! the zone gained or lost rows: their unknowns start again from 0
          n = run%cs%nrow
          nt = run%cs%ntan
          deallocate(cu, cp, z, fstate)
          allocate(cu(n + nt), cp(n + nt), z(n + nt), fstate(nt))
          z = 0.0_dp
          if (allocated(zprev)) deallocate(zprev)
          if (allocated(active_prev)) deallocate(active_prev)
        end if
        call move_alloc(keys, keys_prev)
        call condense(run%cs, run%eq, run%factor, run%y, run%u0, run%w, run%q, run%cd, err, run%deck%solver%condense)
        if (allocated(err)) call fail_numerical(err%message)
        call constraint_values(run%cs, u0k, cu)
        call constraint_values(run%cs, uprev, cp)
        qn = run%cs%g - cu(1:n)                          ! gaps without contact forces
        qt = cp(n + 1:) - cu(n + 1:)                     ! minus the step's slip without contact forces, current tangents
        fp = friction_problem(qn, qt, run%cs%tan_row, run%cs%tan_mu, run%cs%tan_bound)
        if (allocated(zprev)) then
          zprev = z
        else
          allocate(zprev, source=z)
        end if
        if (floating) then
          if (run%fl%k > 0) call split_free_modes(run%cs, run%sc%bodies, run%fl, fk, run%split)
          if (run%rsplit%k > 0) call split_rigid_modes(run%cs, run%sc%rigids, run%sc%fixed, fk, run%rsplit)
          kb = size(run%split%held, 2)
          kr = size(run%rsplit%held, 2)
          hh = reshape([matmul(run%split%h, run%split%held), matmul(run%rsplit%h, run%rsplit%held)], [n + nt, kb + kr])
          eh = [matmul(transpose(run%split%held), run%split%e), matmul(transpose(run%rsplit%held), run%rsplit%e)]
          if (allocated(alpha)) deallocate(alpha)
          allocate(alpha(kb + kr))
          call solve_friction_floating(run%w, fp, hh, eh, opts, z, alpha, rep, unbalanced, cause)
          if (rep%info == no_equilibrium) call fail_numerical('friction, ' // run%step_note // &
            floating_no_equilibrium(run, unbalanced, cause))
          if (rep%info /= 0 .and. .not. rep%no_memory) call fail_numerical('friction, ' // run%step_note // &
            'no equilibrium found for the bodies held only by contact (' // floating_names(run) // '): ' // rep%message)
          body_alpha = matmul(run%split%held, alpha(1:kb))
          rigid_alpha = matmul(run%rsplit%held, alpha(kb + 1:))
          fp%qn = fp%qn - matmul(hh(1:n, :), alpha)      ! the step's rigid motion in the gaps and slips
          fp%qt = fp%qt - matmul(hh(n + 1:, :), alpha)
        else if (method == 'pdas') then
          call solve_friction_newton(run%w, fp, opts, z, rep)
        else
          call solve_friction_lcp(run%w, fp, method, opts, z, rep)
        end if
        iterations = iterations + rep%iterations
        if (rep%info /= 0 .and. rep%no_memory) call fail_numerical(rep%message)
        if (rep%info /= 0) call fail_numerical('friction, ' // run%step_note // 'contact problem not solved: ' // rep%message)
        if (.not. all(ieee_is_finite(z))) call fail_numerical('friction, ' // run%step_note // &
          'the contact multipliers are not finite')
        call solve_loads(run, fk, ubk, z, uc)
        if (run%fl%k > 0) uc = uc + matmul(run%fl%r, body_alpha)
        call remove_motions(run%fl, run%split%unheld, uc)
        if (allocated(rigid_alpha)) uc(run%rsplit%dof) = rigid_alpha
        same = .false.
        change = huge(1.0_dp)
        if (allocated(active_prev)) then
          same = all((z(1:n) > 0.0_dp) .eqv. active_prev)
          change = maxval(abs(z - zprev)) / max(maxval(abs(z)), tiny(1.0_dp))
        end if
        active_prev = z(1:n) > 0.0_dp
        if (same .and. change <= finite_tol) exit
      end do
      if (.not. (same .and. change <= finite_tol)) then
        if (same) then
          cause = 'the contact forces still change by ' // real_to_str(change) // ' of their largest'
        else
          cause = 'the active set still changes'
        end if
        call fail_numerical(run%step_note // 'sliding=finite: the contact zone was not found again: after ' // &
          int_to_str(run%deck%solver%updates) // ' updates of the contact geometry ' // cause // ' (the step ' // &
          'moves the contact too far for the geometry of its start to find it; expected more STEPS, or more ' // &
          'SOLVER updates=)')
      end if
      deallocate(active_prev)
      call friction_state(run%w, fp, z, fstate, err)
      if (allocated(err)) call fail_numerical(err%message)
      call say(run, 'finite   ' // run%step_note // int_to_str(it) // ' updates of the contact geometry')
      write(line, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,es9.2)') 'step     ', kstep, '/', run%sc%steps, ': ' // method // ' ', &
        rep%iterations, ' iterations, ', count(z(1:n) > 0.0_dp), ' active, ', count(fstate == 2), &
        ' slipping, residual ', rep%residual
      call say(run, trim(line))
      run%step_iterations = rep%iterations
      if (run%deck%output%steps_all .and. kstep < run%sc%steps) then
        step = none
        step%mu = z(1:n)
        step%tau = z(n + 1:)
        step%gap = fp%qn + matmul(run%w(1:n, :), z)
        step%alpha = body_alpha
        step%fstate = fstate
        call constraint_values(run%cs, uc, cu)
        step%slip = cu(n + 1:)                               ! T u along the step's tangents
        call friction_results(run, step)
        call contact_measures(run, step)
        call record_step(run, kstep, fk, ubk, z, rigid_alpha, step)
      end if
      uprev = uc
    end do
    run%step_note = 'load step ' // int_to_str(run%sc%steps) // ' of ' // int_to_str(run%sc%steps) // ': '
    call move_alloc(body_alpha, run%res%alpha)
    call move_alloc(fstate, run%res%fstate)
    if (floating) call move_alloc(rigid_alpha, run%rigid_alpha)
    run%res%lcp_method = method
    run%res%lcp_iterations = iterations
    run%res%lcp_residual = rep%residual
    run%res%steps = run%sc%steps
    run%res%mu = z(1:n)
    run%res%tau = z(n + 1:)
    run%res%gap = fp%qn + matmul(run%w(1:n, :), z)
    call constraint_values(run%cs, uc, cu)
    run%res%slip = cu(n + 1:)                             ! T u along the final tangents
    call friction_results(run, run%res)
  end subroutine solve_finite_friction_steps

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
    call move_alloc(body_alpha, run%res%alpha)
    call move_alloc(fstate, run%res%fstate)
    if (floating) call move_alloc(rigid_alpha, run%rigid_alpha)
    run%res%lcp_method = method
    run%res%lcp_iterations = iterations
    run%res%lcp_residual = rep%residual
    run%res%steps = run%sc%steps
    run%res%mu = z(1:n)
    run%res%tau = z(n + 1:)
    run%res%gap = qn + matmul(run%w(1:n, :), z)
    run%res%slip = sprev
    call friction_results(run, run%res)
  end subroutine solve_friction_steps

  !> A step's friction results from its tangential multipliers and states:
  !> the shear traction and tangential row of each row, the stick and slip counts.
  !>   res (inout) tau, fstate on entry; shear, tan_of_row, stick_nodes, slip_nodes on exit
  subroutine friction_results(run, res)
    type(run_t), intent(in) :: run
    type(results_t), intent(inout) :: res
    real(dp), allocatable :: tforce(:)
    integer :: r, k
    allocate(res%shear(run%cs%ntan), res%tan_of_row(run%cs%nrow))
    res%tan_of_row = 0
    allocate(tforce(run%cs%nrow), source=0.0_dp)
    tforce(run%cs%tan_row) = -res%tau                     ! the force on the slave is -tau t
    do r = 1, run%cs%ntan
      k = run%cs%tan_row(r)
      res%tan_of_row(k) = r
      if (run%cs%weight(k) > 0.0_dp) then
        res%shear(r) = tforce(k) / run%cs%weight(k)
      else                    ! a hat without weight (a quadratic trace's node on the axis): with its neighbour's
        res%shear(r) = node_traction(run%cs, run%cs%row_pair(k), run%cs%row_node(k), tforce)
      end if
    end do
    res%stick_nodes = count(res%fstate == 1)
    res%slip_nodes = count(res%fstate == 2)
  end subroutine friction_results

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

  !> One step's displacement from its multipliers z, its post-processing,
  !> VTK file and table row, all on the step's own results.
  !>   z           (in)    the step's multipliers (mu, or mu and tau)
  !>   rigid_alpha (in)    the step's RIGID motion (unallocated: none)
  !>   res         (inout) the step's results: mu, gap, alpha (and tau) and the
  !>                       contact measures on entry; u and what the files report on exit
  subroutine record_step(run, kstep, fk, ubk, z, rigid_alpha, res)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: kstep
    real(dp), intent(in) :: fk(:), ubk(:), z(:)
    real(dp), allocatable, intent(in) :: rigid_alpha(:)
    type(results_t), intent(inout) :: res
    allocate(res%u(run%sc%ndof))
    call solve_loads(run, fk, ubk, z, res%u)
    if (run%fl%k > 0) res%u = res%u + matmul(run%fl%r, res%alpha)
    call remove_motions(run%fl, run%split%unheld, res%u)
    if (allocated(rigid_alpha)) res%u(run%rsplit%dof) = rigid_alpha
    if (.not. all(ieee_is_finite(res%u))) call fail_numerical('load step ' // int_to_str(kstep) // &
      ': the displacement is not finite (overflow in the solve)')
    call pair_resultants(run, z, res)
    call post_process(run, fk, res)
    call nodal_contact_fields(run, res)
    call estimate_results(run, res)                        ! the step's error_indicator
    call check_finite_results(run, res)
    call check_step_sliding(run, res, kstep)                ! the slide against small sliding (exit 1 beyond)
    call write_step(run, kstep, res)
  end subroutine record_step

  !> A body whose FIX leaves a rigid mode free must be held by a CONTACT.
  subroutine check_floating_bodies(run)
    type(run_t), intent(inout) :: run
    integer :: j, ip, b
    logical :: in_contact
    do j = 1, run%fl%k
      b = run%fl%mode_body(j)
      in_contact = .false.
      do ip = 1, size(run%sc%specs)
        if (run%sc%specs(ip)%slave_body == b .or. run%sc%specs(ip)%master_body == b) in_contact = .true.
      end do
      if (.not. in_contact .and. size(run%deck%bodies(b)%springs) == 0) call add_error(run%diag, run%deck%file, &
        run%deck%bodies(b)%line, 'body "' // run%sc%bodies(b)%name // &
        '": its FIX statements leave a rigid-body mode free (' // mode_name(run%fl, j) // ') and no CONTACT holds ' // &
        'the body (a FIX that blocks it, or a CONTACT, expected)')
      if (.not. in_contact .and. size(run%deck%bodies(b)%springs) > 0) call add_error(run%diag, run%deck%file, &
        run%deck%bodies(b)%line, 'body "' // run%sc%bodies(b)%name // &
        '": its FIX and SPRING statements leave a rigid-body mode free (' // mode_name(run%fl, j) // ') and no ' // &
        'CONTACT holds the body (a FIX or a SPRING that resists it, or a CONTACT, expected)')
    end do
    call stop_input_errors(run%diag)
  end subroutine check_floating_bodies

  !> A body held only by contact in a scene with friction: the friction LCP
  !> with its mode amplitudes is solved by Lemke (friction_modes); lcp=pgs
  !> is refused at the SOLVER line (exit 2).
  subroutine check_floating_friction_solver(run)
    type(run_t), intent(inout) :: run
    if (run%cs%ntan == 0 .or. run%deck%solver%lcp /= 'pgs') return
    if (size(run%split%held, 2) == 0 .and. size(run%rsplit%held, 2) > 0) then
      call add_error(run%diag, run%deck%file, run%deck%solver%line, 'lcp=pgs with friction on a RIGID under FORCE is not ' // &
        'supported (expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
      call stop_input_errors(run%diag)
    end if
    if (size(run%split%held, 2) == 0) return
    call add_error(run%diag, run%deck%file, run%deck%solver%line, &
      'lcp=pgs with friction on a body held only by contact (body "' // &
      run%sc%bodies(run%fl%mode_body(1))%name // '": ' // mode_name(run%fl, 1) // ' not held by FIX) is not supported ' // &
      '(expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
    call stop_input_errors(run%diag)
  end subroutine check_floating_friction_solver

  !> A rigid motion that neither FIX nor contact holds must carry no load:
  !> else no static equilibrium exists (exit 1, naming the body and motion).
  subroutine check_unheld_loads(run)
    type(run_t), intent(inout) :: run
    integer :: j
    character(len=16) :: buf
    do j = 1, size(run%split%unheld, 2)
      if (.not. run%split%loaded(j)) cycle
      write(buf, '(es10.3)') run%split%load(j)
      call fail_numerical(step_prefix(run) // 'no equilibrium: body "' // run%sc%bodies(run%split%unheld_body(j))%name // &
        '" is loaded along ' // &
        'a rigid mode (' // motion_name(run%fl, run%split%unheld(:, j)) // ') that neither FIX nor contact holds ' // &
        '(frictionless contact holds only normal to the contact surface; load along it ' // trim(adjustl(buf)) // &
        ' of the loads'' scale)')
    end do
  end subroutine check_unheld_loads

  !> A RIGID's free direction that contact does not hold must carry no load
  !> (exit 1 naming the obstacle and the direction); an unloaded one keeps 0.
  subroutine check_unheld_rigid_loads(run)
    type(run_t), intent(inout) :: run
    integer :: j
    do j = 1, size(run%rsplit%unheld, 2)
      if (.not. run%rsplit%loaded(j)) cycle
      call fail_numerical(step_prefix(run) // 'no equilibrium: RIGID "' // run%sc%rigids(run%rsplit%unheld_owner(j))%name // &
        '" is loaded along a direction (' // rigid_direction(run%rsplit, run%rsplit%unheld(:, j)) // ') that neither its ' // &
        'FIX nor its contacts hold (frictionless contact pushes only normal to the contact surface; expected FIX ' // &
        'on that direction, or a load the contact normals can balance)')
    end do
  end subroutine check_unheld_rigid_loads

  !> The contact problem has no solution because some load pulls a body off its
  !> contacts: when it is a RIGID's FORCE, say which RIGID and which way.
  subroutine diagnose_pulled_rigid(run)
    type(run_t), intent(inout) :: run
    integer :: owner
    real(dp) :: resid(3)
    character(len=80) :: buf
    call pulled_rigid(run%rsplit, owner, resid)
    if (owner == 0) return
    write(buf, '(a,es10.3,a,es10.3,a,es10.3,a)') '(', resid(1), ', ', resid(2), ', ', resid(3), ')'
    call fail_numerical(step_prefix(run) // 'no equilibrium: the FORCE on RIGID "' // run%sc%rigids(owner)%name // &
      '" pulls it away from its contacts: contact can only push, and the part (fx, fy, m) = ' // trim(buf) // &
      ' of its load cannot be balanced by any contact pressure (expected a FORCE that presses the obstacle ' // &
      'on the slave boundary)')
  end subroutine diagnose_pulled_rigid

  !> The contact problem has no solution because some load pulls a body held
  !> only by contact off its contacts: name the body and the motion it would
  !> make.  The closest balance of its loads by contact forces alone,
  !> min |Hh' mu - eh| over mu >= 0 (the test of contact_lcp, a nonnegative
  !> least squares solved as the LCP of its normal equations), leaves the
  !> unbalanced load r = eh - Hh' mu; the body that carries most of it and the
  !> motion along it are named, as for a frictional step.
  subroutine diagnose_pulled_body(run)
    type(run_t), intent(inout) :: run
    real(dp), allocatable :: hh(:,:), eh(:), mu(:), r(:), c(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: owner
    if (size(run%split%held, 2) == 0) return
    hh = matmul(run%split%h(1:run%cs%nrow, :), run%split%held)    ! Hh = H V_h on the normal rows
    eh = matmul(transpose(run%split%held), run%split%e)             ! eh = V_h' e
    allocate(mu(run%cs%nrow), source=0.0_dp)
    call solve_lcp_lemke(matmul(hh, transpose(hh)), -matmul(hh, eh), mu, opts, rep)
    if (rep%info /= 0) return
    r = eh - matmul(transpose(hh), mu)
    if (norm2(r) <= 1.0e-8_dp * norm2(eh)) return        ! the bodies balance: a RIGID, or the coupling of several
    call largest_owner(run%split%held, r, run%fl%mode_body, c, owner)
    call fail_numerical(step_prefix(run) // no_equilibrium_text('contact', '', 'the loads pull body "' // &
      run%sc%bodies(owner)%name // '"', motion_name(run%fl, c), 'the loads'))
  end subroutine diagnose_pulled_body

  !> The diagnosis of a frictional step without equilibrium from the unbalanced
  !> load along the held combinations (the bodies' modes, then the RIGIDs'
  !> free directions): the body or the RIGID that carries most of it, and
  !> the motion of that one alone.
  !>   unbalanced (in) e - H'z at the closest balance, along the held combinations
  !>   cause      (in) 'friction' (the cone is too small) or 'contact'
  function floating_no_equilibrium(run, unbalanced, cause) result(t)
    type(run_t), intent(in) :: run
    real(dp), intent(in) :: unbalanced(:)
    character(len=*), intent(in) :: cause
    character(len=:), allocatable :: t
    real(dp), allocatable :: c(:)
    integer :: kb, owner
    logical :: on_body
    kb = size(run%split%held, 2)
    on_body = .false.
    if (kb > 0) on_body = maxval(abs(unbalanced(1:kb))) >= maxval(abs(unbalanced(kb + 1:)), mask=.true.) .or. &
                          size(unbalanced) == kb
    if (on_body) then
      call largest_owner(run%split%held, unbalanced(1:kb), run%fl%mode_body, c, owner)
      t = no_equilibrium_text(cause, 'the loads on body "' // run%sc%bodies(owner)%name // '" exceed', &
                              'the loads pull body "' // run%sc%bodies(owner)%name // '"', motion_name(run%fl, c), &
                              'the loads')
    else
      call largest_owner(run%rsplit%held, unbalanced(kb + 1:), run%rsplit%owner, c, owner)
      t = no_equilibrium_text(cause, 'the FORCE on RIGID "' // run%sc%rigids(owner)%name // '" exceeds', &
                              'the FORCE on RIGID "' // run%sc%rigids(owner)%name // '" pulls it', &
                              rigid_direction(run%rsplit, c), 'its load')
    end if
  end function floating_no_equilibrium

  !> The unbalanced load in the modes' (or directions') amplitudes, c = H u,
  !> kept on the owner (body or RIGID) with the largest amplitude.
  !>   held     (in)  (k, m) the held combinations
  !>   u        (in)  (m) the unbalanced load along them
  !>   owner_of (in)  (k) the owner of each mode or direction
  !>   c        (out) (k) H u on that owner's modes, 0 on the others
  !>   owner    (out) that owner
  subroutine largest_owner(held, u, owner_of, c, owner)
    real(dp), intent(in) :: held(:,:), u(:)
    integer, intent(in) :: owner_of(:)
    real(dp), allocatable, intent(out) :: c(:)
    integer, intent(out) :: owner
    c = matmul(held, u)
    owner = owner_of(maxloc(abs(c), dim=1))
    c = merge(c, 0.0_dp, owner_of == owner)
  end subroutine largest_owner

  !> The sentence of a step without static equilibrium, one per cause.
  !>   cause  (in) 'friction' (the friction cone is too small) or 'contact'
  !>          (the load pulls away from the contacts)
  !>   held   (in) who exceeds the cone, with the verb: 'the loads on body "A" exceed'
  !>   pulled (in) who is pulled off, with the verb: 'the loads pull body "A"'
  !>   motion (in) the motion it would make
  !>   load   (in) what is not balanced: 'the loads', 'its load'
  function no_equilibrium_text(cause, held, pulled, motion, load) result(t)
    character(len=*), intent(in) :: cause, held, pulled, motion, load
    character(len=:), allocatable :: t
    if (cause == 'friction') then
      t = 'no equilibrium: ' // held // ' what friction can hold: it would move by ' // motion // &
        ' (the contact forces within the friction cone cannot balance ' // load // ')'
    else
      t = 'no equilibrium: ' // pulled // ' away from its contacts: it would move by ' // motion // &
        ' (no contact force balances ' // load // ', whatever the friction)'
    end if
  end function no_equilibrium_text

  !> Who is held only by contact, for messages: each body with a free rigid
  !> mode (body "A"), then each RIGID with a free direction (RIGID "B"),
  !> comma-separated.  A scene whose only floating part is a RIGID under
  !> FORCE has no floating body: the RIGID must still be named.
  function floating_names(run) result(t)
    type(run_t), intent(in) :: run
    character(len=:), allocatable :: t
    integer :: b, r
    t = ''
    do b = 1, size(run%sc%bodies)
      if (.not. any(run%fl%mode_body == b)) cycle
      if (len(t) > 0) t = t // ', '
      t = t // 'body "' // run%sc%bodies(b)%name // '"'
    end do
    do r = 1, size(run%sc%rigids)
      if (run%rsplit%k == 0) exit
      if (.not. any(run%rsplit%owner == r)) cycle
      if (len(t) > 0) t = t // ', '
      t = t // 'RIGID "' // run%sc%rigids(r)%name // '"'
    end do
  end function floating_names

  !> 'BODY KIND X Y' of unheld combination j for the summary: KIND rotation
  !> (X Y its centre) or translation (X Y its unit direction).
  function unheld_summary(run, j) result(t)
    type(run_t), intent(in) :: run
    integer, intent(in) :: j
    character(len=:), allocatable :: t, kind
    real(dp) :: point(2)
    character(len=32) :: bx, by
    call describe_motion(run%fl, run%split%unheld(:, j), kind, point)
    write(bx, '(es24.16e3)') point(1)
    write(by, '(es24.16e3)') point(2)
    t = run%sc%bodies(run%split%unheld_body(j))%name // ' ' // kind // ' ' // trim(adjustl(bx)) // ' ' // trim(adjustl(by))
  end function unheld_summary

  !> 'load step k of n: ' while the steps of OUTPUT steps=all are solved, else ''.
  function step_prefix(run) result(t)
    type(run_t), intent(in) :: run
    character(len=:), allocatable :: t
    t = ''
    if (allocated(run%step_note)) t = run%step_note
  end function step_prefix

  !> [a 0; 0 b]: the held combinations of the bodies' modes and of the RIGIDs'
  !> free directions, side by side.
  function block_diagonal(a, b) result(c)
    real(dp), intent(in) :: a(:,:), b(:,:)
    real(dp), allocatable :: c(:,:)
    allocate(c(size(a, 1) + size(b, 1), size(a, 2) + size(b, 2)), source=0.0_dp)
    c(1:size(a, 1), 1:size(a, 2)) = a
    c(size(a, 1) + 1:, size(a, 2) + 1:) = b
  end function block_diagonal

end module contact_solve
