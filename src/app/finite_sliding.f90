!> finite_sliding: CONTACT ... sliding=finite, the load steps in order, each
!> by the fixed point of geometry updates (doc/theory.md, "Finite sliding"):
!> the rows rebuilt at the current configuration, W condensed again on the
!> factor already had, the LCP solved, until the rows, the active set and
!> the forces hold; frictionless and with friction.
!>
!> Why it exists: the geometry that follows the bodies, kept apart from the
!> small-sliding steps whose rows never change.  Who may use it:
!> contact_solve.  A step whose geometry does not settle ends the run
!> (exit 1, asking for more STEPS).
!>
!> Programming interface
!>   solve_finite_steps(run, sol, rigid_alpha)  frictionless: every step, the final one's results
!>   solve_finite_friction_steps(run)           with friction: every step, the final one into res
module finite_sliding
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t
  use exits, only: fail_numerical
  use run_state, only: run_t
  use run_report, only: say, say_step
  use scene, only: step_loads
  use contact_condensation, only: constraint_values, condense
  use lcp_solvers, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: solve_friction_lcp, friction_state, friction_problem_t, friction_problem
  use friction_newton, only: solve_friction_newton
  use friction_modes, only: solve_friction_floating, no_equilibrium
  use contact_set, only: contact_set_t
  use moved_contact, only: row_keys, build_moved_contact_set
  use rigid_modes, only: remove_motions
  use mode_support, only: split_free_modes
  use rigid_support, only: split_rigid_modes
  use results_writer, only: results_t
  use linear_system, only: solve_loads
  use post_processing, only: contact_measures
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use local_axes, only: rotate_constraint_rows
  use held_by_contact, only: split_step_modes, floating_no_equilibrium, &
                             floating_names
  use contact_step, only: solve_contact_problem, friction_results, record_step, keep_friction_solution
  implicit none
  private
  public :: solve_finite_steps, solve_finite_friction_steps

contains

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
        call split_step_modes(run, fk)
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
      if (.not. (same .and. change <= finite_tol)) call fail_unsettled(run, same, change)
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

  !> A step whose fixed point did not settle in SOLVER updates= updates:
  !> exit 1 saying why and asking for more STEPS.
  !>   same   (in) the last two updates had the same rows and active set
  !>   change (in) the contact forces' last relative change
  subroutine fail_unsettled(run, same, change)
    type(run_t), intent(in) :: run
    logical, intent(in) :: same
    real(dp), intent(in) :: change
    character(len=:), allocatable :: cause
    if (same) then
      cause = 'the contact forces still change by ' // real_to_str(change) // ' of their largest'
    else
      cause = 'the active set still changes'
    end if
    call fail_numerical(run%step_note // 'sliding=finite: the contact zone was not found again: after ' // &
      int_to_str(run%deck%solver%updates) // ' updates of the contact geometry ' // cause // ' (the step moves the ' // &
      'contact too far for the geometry of its start to find it; expected more STEPS, or more SOLVER updates=)')
  end subroutine fail_unsettled

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
      if (.not. (same .and. change <= finite_tol)) call fail_unsettled(run, same, change)
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
    call constraint_values(run%cs, uc, cu)               ! T u along the final tangents
    call keep_friction_solution(run, method, iterations, rep, z, fp%qn, cu(n + 1:), body_alpha, fstate, rigid_alpha, &
                                floating)
  end subroutine solve_finite_friction_steps
end module finite_sliding
