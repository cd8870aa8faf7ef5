!> load_steps: the load history of a run, one loop for every kinematics and
!> law.  Step k has the loads of its ramps' factors (scene's step_loads); its
!> contact rows are the initial ones (sliding=small) or those of the
!> configuration the bodies reach (sliding=finite: a fixed point of geometry
!> updates, doc/theory.md, "Finite sliding"); its contact problem is solved
!> by step_solver, frictionless or with friction, with the free motions of
!> what contact alone holds.
!>
!> Step k's loads are its forces and prescribed values (scene's
!> step_forces); its thermal strains are the recorder's to take
!> (step_thermal_strains): nothing here changes the scene.
!>
!> Which steps are solved.  Friction (the answer depends on the path) and
!> finite sliding (each step starts where the last ended) solve every step in
!> order; a frictionless small-sliding history solves only its final step,
!> its answer being independent of the path, unless OUTPUT steps=all asks
!> for every step (each then solved alone at its load factors, with the
!> factorization and W of the final step: only the right-hand side changes).
!>
!> The gaps of step k without contact forces, g - B u0_k:
!>   the final loads on the initial rows    q of the condensation itself
!>   friction on the initial rows           C u0 of each ramp, combined by the
!>                                          step's factors (no solve)
!>   otherwise                              u0_k = K^-1 f_k, one solve
!> With friction the slip of the step is measured from the last step's
!> tangential displacement T u_{k-1} (the history), along the step's rows.
!>
!> Geometry updates (sliding=finite).  From the current displacement u_c
!> (step k's loads on the last step's contact forces and free motions; step
!> 1: u0_1) the rows are rebuilt at x + u_c (build_moved_contact_set), W
!> condensed again on the same factor, the step solved and u_c recovered,
!> until the rows (row_keys) and the active set are those of the previous
!> update and the multipliers changed by at most finite_tol of their
!> largest.  After SOLVER updates= updates the step is too large for the zone
!> to be found again (error_unsolved asking for more STEPS).  A change of
!> rows restarts the friction multipliers from 0 (they belong to rows).
!>
!> A step that fails without a proof that it has no solution (error_unsolved)
!> in a history whose path matters (friction, finite sliding) is solved again
!> in two halves, from the last state to the middle of the step, then to its
!> end (the load factors are linear in between: load_groups' group_factor at
!> a fractional step), each half split again in turn when it fails, at most
!> max_splits times deep; each split is said in the run log.  A smaller
!> increment is what the friction methods and the geometry updates need when
!> a step crosses too much at once (a side load raised past what friction
!> holds, a contact zone that moves by more than it is wide).
!>
!> A scene with a hyperelastic body solves every step in order by Newton's
!> method on the whole scene (hyperelastic_step), each step from the last
!> one's state; Newton halves its own steps, so such a step is not split
!> here.
!>
!> Each solved step other than the final one is handed to the caller's
!> recorder (OUTPUT steps=all), with its loads and solution, before the next
!> one is solved; the final step's solution is returned.  Nothing here writes
!> a file or stops the run.
!>
!> Programming interface
!>   solve_load_steps(prob, sys, log, sol, err, recorder)   every step the history needs
!>   type(step_load_t)              the loads of a step (or of a point between two)
!>   type(step_recorder_t)          what keeps the other steps: extended by the caller,
!>                                  its record(prob, sys, load, sol, log, err) deferred
module load_steps
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str, format_number
  use errors, only: error_t, set_error, error_unsolved
  use run_log, only: log_t, say
  use problem, only: problem_t, step_label
  use linear_system, only: system_t, solve_loads, add_free_motions, condense_rows
  use step_solution, only: step_solution_t, multipliers
  use step_solver, only: solve_frictionless_step, solve_friction_step
  use held_by_contact, only: split_step_modes
  use scene, only: step_forces
  use load_groups, only: group_factor
  use contact_set, only: contact_set_t
  use contact_condensation, only: constraint_values
  use moved_contact, only: row_keys, build_moved_contact_set
  use local_axes, only: rotate_constraint_rows
  use mode_support, only: mode_split_t
  use rigid_support, only: rigid_split_t
  use friction_lcp, only: friction_problem_t, friction_problem, friction_state
  use hyperelastic_step, only: solve_hyperelastic_step, newton_history_t
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_load_steps

  !> the relative change of the multipliers below which a finite step settles
  real(dp), parameter :: finite_tol = 1.0e-8_dp
  !> how many times a failed step is halved, at most (an eighth of a step)
  integer, parameter :: max_splits = 3

  !> The loads of a load step, or of a point between two (a split step).
  type, public :: step_load_t
    integer :: kstep = 0                       !< the deck's step (messages, records)
    real(dp) :: t = 0                          !< the load point: kstep, or between kstep - 1 and kstep
    real(dp), allocatable :: f(:)              !< (ndof) external forces at t (solver basis)
    real(dp), allocatable :: ubar(:)           !< (ndof) prescribed values at t
  end type step_load_t

  !> What keeps the solved steps other than the final one (OUTPUT
  !> steps=all): the caller extends it with what it writes them to.
  type, abstract, public :: step_recorder_t
  contains
    procedure(record_step), deferred :: record
  end type step_recorder_t

  abstract interface
    !> A solved load step other than the final one, for the caller to keep:
    !> its loads (load%kstep, 1 .. steps - 1), its solution on the rows of
    !> prob%cs (unallocated multipliers: no contact); err when it could not
    !> be kept (the run then ends).
    subroutine record_step(self, prob, sys, load, sol, log, err)
      import :: step_recorder_t, problem_t, system_t, step_load_t, step_solution_t, log_t, error_t
      class(step_recorder_t), intent(inout) :: self
      type(problem_t), intent(in) :: prob
      type(system_t), intent(in) :: sys
      type(step_load_t), intent(in) :: load
      type(step_solution_t), intent(in) :: sol
      type(log_t), intent(inout) :: log
      type(error_t), allocatable, intent(out) :: err
    end subroutine record_step
  end interface

  !> What a step hands the next: the friction history and the configuration.
  type :: history_t
    real(dp), allocatable :: z(:)              !< (n + nt) the last step's multipliers (the start)
    real(dp), allocatable :: slip(:)           !< (nt) T u of the last step along its rows (small sliding)
    real(dp), allocatable :: u(:)              !< (ndof) the last step's displacement (finite sliding)
    type(newton_history_t) :: newton           !< finite strain: Newton's equations, pattern, last start
    integer(i8), allocatable :: keys(:)        !< the last update's rows (finite sliding: row_keys)
  end type history_t

  !> The seconds of a finite-sliding history, by part.
  type :: finite_clock_t
    real(dp) :: geometry = 0, condense = 0, lcp = 0
    integer :: updates = 0
  end type finite_clock_t

contains

  !> Every load step the history needs (module header), the final one's
  !> solution returned.
  !>   prob   (inout) the contact rows follow the bodies under sliding=finite
  !>   sys    (inout) W, q, cd of the current rows
  !>   log    (inout) the steps' lines
  !>   sol    (out)   the final step's solution: multipliers, gaps, slips and
  !>                  states, free motions, method, iterations (total), fallbacks
  !>   err    (out)   the first step that failed, named
  !>   recorder (inout, optional) the caller's recorder of the other steps
  !>                  (OUTPUT steps=all); absent: they are not kept
  subroutine solve_load_steps(prob, sys, log, sol, err, recorder)
    type(problem_t), intent(inout) :: prob
    type(system_t), intent(inout) :: sys
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(out) :: sol
    type(error_t), allocatable, intent(out) :: err
    class(step_recorder_t), intent(inout), optional :: recorder
    type(history_t) :: past
    type(finite_clock_t) :: clock
    type(step_load_t) :: load
    integer :: kstep, first
    logical :: finite, friction, steps_all, hyper
    integer, allocatable :: before(:)

    finite = any(prob%sc%specs%finite)
    friction = prob%cs%ntan > 0
    hyper = any(prob%sc%bodies%finite)
    steps_all = prob%deck%output%steps_all
    allocate(load%f(prob%sc%ndof), load%ubar(prob%sc%ndof))
    first = prob%sc%steps                          ! path-independent: the final step alone
    if (friction) call say_floating(prob, log)
    if (friction .or. finite .or. steps_all .or. hyper) first = 1
    do kstep = first, prob%sc%steps
      load%kstep = kstep
      if (.not. (sys%with_contact .or. hyper)) then   ! nothing to solve: the loads alone
        load%t = real(kstep, dp)
        call step_forces(prob%sc, load%t, load%f, load%ubar)
        sol%step = kstep
        sol%method = 'none'
      else
        call solve_increment(prob, sys, real(kstep - 1, dp), real(kstep, dp), 0, load, past, log, sol, clock, err)
      end if
      if (allocated(err)) return
      if (friction .and. sys%with_contact) call count_slip_entries(prob, kstep, sol, before)
      if (kstep < prob%sc%steps .and. steps_all .and. present(recorder)) then
        call recorder%record(prob, sys, load, sol, log, err)
        if (allocated(err)) return
      end if
    end do
    if (finite .and. sys%with_contact .and. .not. hyper) call say(log, 'finite   ' // int_to_str(clock%updates) // &
      ' geometry updates in ' // int_to_str(prob%sc%steps) // ' steps: rebuild ' // real_to_str(clock%geometry) // &
      ' s, condensation ' // real_to_str(clock%condense) // ' s, LCP ' // real_to_str(clock%lcp) // ' s')
  end subroutine solve_load_steps

  !> Per friction pair, a load step that both made the contact and dragged
  !> it: most of the pair's rows in contact at the step's end came into
  !> contact during the step across an initial gap (a zone that grows with
  !> the load; rows of gap 0, a flat pair's, all touch at the first load
  !> and a proportional load then scales the answer), the step ends
  !> in partial slip, and the pair's tangential force is more than
  !> drag_share of what friction can carry (|sum tau| against sum mu_c mu).
  !> One step from open to a dragged zone gives an answer that depends on
  !> how its loads would have followed each other, which one step cannot
  !> say (setup_checks' few_steps).  A press alone (no net shear) and a drag
  !> of a zone already made are not counted: the second ends where its steps
  !> lead, however few (doc/theory.md, "Monitors of the set-up").
  !>   sol    (inout) the step's mu, tau, fstate on entry; slip_entries, slip_entry_pair,
  !>                  slip_entry_step: the step and pair with the most rows entered so
  !>   before (inout) the friction states before the step (unallocated: none); the step's on exit
  subroutine count_slip_entries(prob, kstep, sol, before)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    type(step_solution_t), intent(inout) :: sol
    integer, allocatable, intent(inout) :: before(:)
    real(dp), parameter :: drag_share = 0.1_dp   ! a symmetric press leaves round-off; a drag, tens of %
    integer :: ip, t, entered, touching, nstick, nslip
    real(dp) :: q, cap, gtol
    if (.not. (allocated(sol%fstate) .and. allocated(sol%tau) .and. allocated(sol%mu))) return
    if (.not. allocated(before)) allocate(before(size(sol%fstate)), source=0)
    if (size(before) /= size(sol%fstate)) then   ! sliding=finite rebuilt the rows: no row to follow
      before = sol%fstate
      return
    end if
    do ip = 1, prob%cs%npair
      associate (xs => prob%cs%pair(ip)%xs)
        gtol = 1.0e-9_dp * sum(norm2(xs(:, 2:) - xs(:, :size(xs, 2) - 1), dim=1))   ! round-off of a flat pair's gaps
      end associate
      entered = 0
      touching = 0
      nstick = 0
      nslip = 0
      q = 0.0_dp
      cap = 0.0_dp
      do t = 1, prob%cs%ntan
        if (prob%cs%row_pair(prob%cs%tan_row(t)) /= ip) cycle
        if (sol%fstate(t) == 0) cycle
        touching = touching + 1
        if (before(t) == 0 .and. prob%cs%g(prob%cs%tan_row(t)) > gtol) entered = entered + 1
        if (sol%fstate(t) == 1) nstick = nstick + 1
        if (sol%fstate(t) == 2) nslip = nslip + 1
        q = q + sol%tau(t)
        cap = cap + prob%cs%tan_mu(t) * sol%mu(prob%cs%tan_row(t)) + prob%cs%tan_bound(t)
      end do
      if (nstick == 0 .or. nslip == 0 .or. 2 * entered <= touching) cycle
      if (abs(q) <= drag_share * cap) cycle
      if (entered > sol%slip_entries) then
        sol%slip_entries = entered
        sol%slip_entry_pair = ip
        sol%slip_entry_step = kstep
      end if
    end do
    before = sol%fstate
  end subroutine count_slip_entries

  !> With friction, what contact alone holds is solved with the contacts:
  !> the run log says how many amplitudes join each step's friction LCP.
  subroutine say_floating(prob, log)
    type(problem_t), intent(in) :: prob
    type(log_t), intent(inout) :: log
    integer :: held
    held = size(prob%split%held, 2) + size(prob%rsplit%held, 2)
    if (held == 0) return
    call say(log, 'friction ' // int_to_str(held) // ' rigid-mode amplitudes ' // &
      'of the bodies and RIGIDs held only by contact are unknowns of each step''s friction LCP, solved by ' // &
      'Lemke (' // int_to_str(prob%cs%nrow + 3 * prob%cs%ntan + 2 * held) // ' unknowns)')
  end subroutine say_floating

  !> The state at step t1 from the state at t0 (past, sol): one step, or,
  !> when it fails without a proof and the path matters, two halves, each
  !> split again when it fails, at most max_splits deep (module header).
  !>   t0, t1 (in)    where the increment starts and ends (t1 = load%kstep at the top)
  !>   splits (in)    how many times this increment was halved already
  !>   load   (inout) the deck's step being solved on entry; its loads at t1 on exit
  recursive subroutine solve_increment(prob, sys, t0, t1, splits, load, past, log, sol, clock, err)
    type(problem_t), intent(inout) :: prob
    type(system_t), intent(inout) :: sys
    real(dp), intent(in) :: t0, t1
    integer, intent(in) :: splits
    type(step_load_t), intent(inout) :: load
    type(history_t), intent(inout) :: past
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(inout) :: sol
    type(finite_clock_t), intent(inout) :: clock
    type(error_t), allocatable, intent(out) :: err
    type(history_t) :: saved
    type(step_solution_t) :: saved_sol
    type(contact_set_t) :: saved_rows
    logical :: finite, path
    real(dp) :: tm
    character(len=:), allocatable :: why
    if (any(prob%sc%bodies%finite)) then          ! Newton's method, which halves its own steps
      load%t = t1
      call step_forces(prob%sc, t1, load%f, load%ubar)
      if (.not. allocated(past%u)) allocate(past%u(prob%sc%ndof), source=0.0_dp)
      call solve_hyperelastic_step(prob, sys, t0, load%kstep, load%f, load%ubar, past%u, past%newton, log, sol, err)
      return
    end if
    finite = any(prob%sc%specs%finite)
    path = finite .or. prob%cs%ntan > 0
    if (path) then                                ! the state to go back to
      saved = past
      saved_sol = sol
      if (finite) saved_rows = prob%cs
    end if
    load%t = t1
    call step_forces(prob%sc, t1, load%f, load%ubar)
    if (finite) then
      call solve_finite_step(prob, sys, load, past, log, sol, clock, err)
    else
      call solve_small_step(prob, sys, load, past, log, sol, err)
    end if
    if (.not. allocated(err)) return
    if (.not. path .or. err%category /= error_unsolved .or. splits >= max_splits) return
    tm = 0.5_dp * (t0 + t1)
    why = err%message
    if (index(why, step_label(prob, load%kstep)) == 1) why = why(len(step_label(prob, load%kstep)) + 1:)
    call say(log, 'split    ' // step_label(prob, load%kstep) // 'not solved from ' // step_text(t0) // ' to ' // &
      step_text(t1) // ' at once (' // why // '): solved in two halves, through ' // step_text(tm))
    deallocate(err)
    past = saved
    sol = saved_sol
    if (finite) prob%cs = saved_rows
    call solve_increment(prob, sys, t0, tm, splits + 1, load, past, log, sol, clock, err)
    if (allocated(err)) return
    call solve_increment(prob, sys, tm, t1, splits + 1, load, past, log, sol, clock, err)
  end subroutine solve_increment

  !> A step, whole or a fraction of one, as the log says it: 3, 2.5, 2.25.
  function step_text(t) result(s)
    real(dp), intent(in) :: t
    character(len=:), allocatable :: s
    if (t == aint(t)) then
      s = int_to_str(nint(t))
    else
      s = format_number(t)
    end if
  end function step_text

  !> A load point on the initial rows (sliding=small).
  !>   load (in)    the deck's step, the load point t and its loads
  !>   past (inout) the friction history: the last step's z and T u; this step's on exit
  subroutine solve_small_step(prob, sys, load, past, log, sol, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(in) :: sys
    type(step_load_t), intent(in) :: load
    type(history_t), intent(inout) :: past
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(inout) :: sol
    type(error_t), allocatable, intent(out) :: err
    type(mode_split_t) :: split
    type(rigid_split_t) :: rsplit
    type(friction_problem_t) :: fp
    real(dp), allocatable :: cu(:), shift(:)
    integer :: n, nt, g

    n = prob%cs%nrow
    nt = prob%cs%ntan
    sol%step = load%kstep
    ! C u0_k: the final loads' from the condensation; with friction each
    ! ramp's combined (no solve); else one solve
    allocate(cu(n + nt))
    if (allocated(sys%cu0)) then
      cu = 0.0_dp
      do g = 1, size(prob%sc%ramp, 2)
        cu = cu + group_factor(prob%sc, g, load%t) * sys%cu0(:, g)
      end do
    else if (load%t < prob%sc%steps) then
      call free_constraint_values(prob, sys, load%f, load%ubar, cu, err)
      if (allocated(err)) return
    end if
    ! the splits of the free modes: the problem's own are the final loads' on these rows
    if (load%t < prob%sc%steps) then
      call split_step_modes(prob, load%kstep, load%f, split, rsplit, err)
      if (allocated(err)) return
    else
      split = prob%split
      rsplit = prob%rsplit
    end if
    if (nt == 0) then
      if (load%t < prob%sc%steps) then
        call solve_frictionless_step(prob, sys%w, prob%cs%g - cu(1:n), load%kstep, split, rsplit, log, sol, err)
      else
        call solve_frictionless_step(prob, sys%w, sys%q, load%kstep, split, rsplit, log, sol, err)
      end if
      sol%total_iterations = sol%total_iterations + sol%iterations
      return
    end if
    if (.not. allocated(past%z)) then
      allocate(past%z(n + nt), source=0.0_dp)
      allocate(past%slip(nt), source=0.0_dp)
    end if
    ! gaps without contact forces; minus the slip of the step without them
    fp = friction_problem(prob%cs%g - cu(1:n), past%slip - cu(n + 1:), prob%cs%tan_row, prob%cs%tan_mu, &
                          prob%cs%tan_bound)
    call solve_friction_step(prob, sys%w, fp, load%kstep, split, rsplit, log, past%z, sol, shift, err)
    if (allocated(err)) return
    sol%total_iterations = sol%total_iterations + sol%iterations
    cu = cu + shift                                          ! C u0 + C R alpha: the step's rigid motion
    past%slip = cu(n + 1:) - matmul(sys%w(n + 1:, :), past%z)   ! T u_k = T u0_k - T K^-1 C' z
    call keep_friction_step(prob, sys%w, fp, load%kstep, past%z, past%slip, log, sol, err)
  end subroutine solve_small_step

  !> A load point by the fixed point of geometry updates (sliding=finite,
  !> module header).
  !>   load  (in)    the deck's step, the load point t and its loads
  !>   past  (inout) the last step's multipliers and displacement; this step's on exit
  !>   clock (inout) the seconds by part, the updates
  subroutine solve_finite_step(prob, sys, load, past, log, sol, clock, err)
    type(problem_t), intent(inout) :: prob
    type(system_t), intent(inout) :: sys
    type(step_load_t), intent(in) :: load
    type(history_t), intent(inout) :: past
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(inout) :: sol
    type(finite_clock_t), intent(inout) :: clock
    type(error_t), allocatable, intent(out) :: err
    type(mode_split_t) :: split
    type(rigid_split_t) :: rsplit
    type(friction_problem_t) :: fp
    real(dp), allocatable :: u0k(:), uc(:), cu(:), cp(:), z_prev(:), shift(:)
    logical, allocatable :: active_prev(:)
    integer(i8), allocatable :: keys(:)
    integer(i8) :: t0, t1, rate
    integer :: it, n, nt
    real(dp) :: change
    logical :: same, friction

    friction = prob%cs%ntan > 0
    sol%step = load%kstep
    allocate(u0k(prob%sc%ndof), uc(prob%sc%ndof))
    call solve_loads(prob, sys, load%f, load%ubar, [real(dp) ::], u0k, err)
    if (allocated(err)) return
    if (.not. allocated(past%u)) allocate(past%u(prob%sc%ndof), source=0.0_dp)
    if (allocated(sol%mu)) then
      ! the first configuration of the step: its loads and prescribed motion
      ! on the last step's contact forces, so that the bodies move with what
      ! drives them (a carriage moved alone would drag its body's edge)
      call solve_loads(prob, sys, load%f, load%ubar, multipliers(sol), uc, err)
      if (allocated(err)) return
      call add_free_motions(prob, sol, uc)
    else
      uc = u0k                                         ! the first step's loads and motion without contact
    end if
    same = .false.
    change = huge(1.0_dp)
    do it = 1, prob%deck%solver%updates
      call system_clock(t0, rate)
      call move_rows(prob, uc, load%kstep, err)
      if (allocated(err)) return
      n = prob%cs%nrow
      nt = prob%cs%ntan
      keys = row_keys(prob%cs)
      if (.not. same_rows(keys, past%keys)) then
        ! the zone gained or lost rows: their unknowns start again from 0
        if (allocated(past%z)) deallocate(past%z)
        allocate(past%z(n + nt), source=0.0_dp)
        if (allocated(active_prev)) deallocate(active_prev)
      end if
      call system_clock(t1)
      clock%geometry = clock%geometry + real(t1 - t0, dp) / real(rate, dp)
      ! W = C K^-1 C' on the factor of K (q from the final loads is replaced)
      call condense_rows(prob, sys, err)
      if (allocated(err)) return
      allocate(cu(n + nt), cp(n + nt))
      call constraint_values(prob%cs, u0k, cu)
      call split_step_modes(prob, load%kstep, load%f, split, rsplit, err)
      if (allocated(err)) return
      call system_clock(t0)
      clock%condense = clock%condense + real(t0 - t1, dp) / real(rate, dp)
      z_prev = past%z
      if (friction) then
        call constraint_values(prob%cs, past%u, cp)
        ! gaps without contact forces; minus the step's slip without them, current tangents
        fp = friction_problem(prob%cs%g - cu(1:n), cp(n + 1:) - cu(n + 1:), prob%cs%tan_row, prob%cs%tan_mu, &
                              prob%cs%tan_bound)
        call solve_friction_step(prob, sys%w, fp, load%kstep, split, rsplit, log, past%z, sol, shift, err)
      else
        call solve_frictionless_step(prob, sys%w, prob%cs%g - cu(1:n), load%kstep, split, rsplit, log, sol, err)
        if (.not. allocated(err)) past%z = sol%mu
      end if
      if (allocated(err)) return
      sol%total_iterations = sol%total_iterations + sol%iterations
      call system_clock(t1)
      clock%lcp = clock%lcp + real(t1 - t0, dp) / real(rate, dp)
      clock%updates = clock%updates + 1
      ! the displacement of this update: the next configuration
      if (friction) then
        sol%mu = past%z(1:n)
        sol%tau = past%z(n + 1:)
      end if
      call solve_loads(prob, sys, load%f, load%ubar, past%z, uc, err)
      if (allocated(err)) return
      call add_free_motions(prob, sol, uc)
      if (.not. all(ieee_is_finite(uc))) then
        call set_error(err, step_label(prob, load%kstep) // 'the displacement is not finite')
        return
      end if
      same = .false.
      change = huge(1.0_dp)
      if (allocated(active_prev) .and. same_rows(keys, past%keys)) then
        same = all((past%z(1:n) > 0.0_dp) .eqv. active_prev)
        change = maxval(abs(past%z - z_prev)) / max(maxval(abs(past%z)), tiny(1.0_dp))
      end if
      active_prev = past%z(1:n) > 0.0_dp
      call move_alloc(keys, past%keys)
      deallocate(cu, cp)
      if (same .and. change <= finite_tol) exit
    end do
    if (.not. (same .and. change <= finite_tol)) then
      call unsettled(prob, load%kstep, same, change, err)
      return
    end if
    sol%updates = min(it, prob%deck%solver%updates)
    call say(log, 'finite   load step ' // step_text(load%t) // ' of ' // int_to_str(prob%sc%steps) // ': ' // &
             int_to_str(sol%updates) // ' updates of the contact geometry')
    past%u = uc
    if (.not. friction) return
    allocate(cu(n + nt))
    call constraint_values(prob%cs, uc, cu)
    call keep_friction_step(prob, sys%w, fp, load%kstep, past%z, cu(n + 1:), log, sol, err)
  end subroutine solve_finite_step

  !> The contact rows rebuilt at the configuration x + u (finite sliding),
  !> nodes in local axes turned, into prob%cs.  The rebuilt rows must touch
  !> the dofs the factorization put last (contact_set marks every node of a
  !> finite pair's boundaries): else the condensation would read the wrong
  !> block of the factor.
  subroutine move_rows(prob, u, kstep, err)
    type(problem_t), intent(inout) :: prob
    real(dp), intent(in) :: u(:)
    integer, intent(in) :: kstep
    type(error_t), allocatable, intent(out) :: err
    type(contact_set_t) :: moved
    logical :: ok
    call build_moved_contact_set(prob%sc%bodies, prob%sc%specs, u, moved, err)
    if (allocated(err)) then
      err%message = step_label(prob, kstep) // 'sliding=finite: the contact geometry cannot be rebuilt: ' // err%message
      return
    end if
    call rotate_constraint_rows(moved, prob%sc%bodies)     ! nodes in local axes (FIX un=/ut=)
    ok = moved%ncdof == prob%cs%ncdof
    if (ok) ok = all(moved%cdof == prob%cs%cdof)
    if (.not. ok) then
      call set_error(err, step_label(prob, kstep) // &
        'sliding=finite: the rebuilt contact rows do not match the factorization''s contact dofs')
      return
    end if
    prob%cs = moved
  end subroutine move_rows

  !> A step whose fixed point did not settle in SOLVER updates= updates:
  !> error_unsolved saying why and asking for more STEPS.
  !>   same   (in) the last two updates had the same rows and active set
  !>   change (in) the multipliers' last relative change
  subroutine unsettled(prob, kstep, same, change, err)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    logical, intent(in) :: same
    real(dp), intent(in) :: change
    type(error_t), allocatable, intent(out) :: err
    character(len=:), allocatable :: cause
    if (same) then
      cause = 'the contact forces still change by ' // real_to_str(change) // ' of their largest'
    else
      cause = 'the active set still changes'
    end if
    call set_error(err, step_label(prob, kstep) // 'sliding=finite: the contact zone was not found again: after ' // &
      int_to_str(prob%deck%solver%updates) // ' updates of the contact geometry ' // cause // ' (the step moves the ' // &
      'contact too far for the geometry of its start to find it; expected more STEPS, or more SOLVER updates=)', &
      error_unsolved)
  end subroutine unsettled

  !> Rows of two rebuilds that are the same rows, in the same order
  pure logical function same_rows(keys, keys_prev)
    integer(i8), intent(in) :: keys(:)
    integer(i8), allocatable, intent(in) :: keys_prev(:)
    same_rows = .false.
    if (.not. allocated(keys_prev)) return
    if (size(keys) /= size(keys_prev)) return
    same_rows = all(keys == keys_prev)
  end function same_rows

  !> C u0_k of a step's loads, by one solve: u0_k = K^-1 (f_k - K_fd ubar_k).
  !>   cu (out) (nrow + ntan)
  subroutine free_constraint_values(prob, sys, fk, ubk, cu, err)
    type(problem_t), intent(in) :: prob
    type(system_t), intent(in) :: sys
    real(dp), intent(in) :: fk(:), ubk(:)
    real(dp), intent(out) :: cu(:)
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: u0k(:)
    allocate(u0k(prob%sc%ndof))
    call solve_loads(prob, sys, fk, ubk, [real(dp) ::], u0k, err)
    if (allocated(err)) return
    call constraint_values(prob%cs, u0k, cu)
  end subroutine free_constraint_values

  !> A solved friction step into its solution: the multipliers, the gaps,
  !> the slips and the states of its rows, and its line of the run log.
  !>   fp   (in) the step's problem, the free motions included
  !>   z    (in) (n + nt) its multipliers
  !>   slip (in) (nt) T u of the step along its rows
  subroutine keep_friction_step(prob, w, fp, kstep, z, slip, log, sol, err)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: w(:,:)
    type(friction_problem_t), intent(in) :: fp
    integer, intent(in) :: kstep
    real(dp), intent(in) :: z(:), slip(:)
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(inout) :: sol
    type(error_t), allocatable, intent(out) :: err
    character(len=200) :: line
    integer :: n
    n = fp%n
    sol%mu = z(1:n)
    sol%tau = z(n + 1:)
    sol%gap = fp%qn + matmul(w(1:n, :), z)
    sol%slip = slip
    if (allocated(sol%fstate)) deallocate(sol%fstate)
    allocate(sol%fstate(fp%nt))
    call friction_state(w, fp, z, sol%fstate, err)
    if (allocated(err)) return
    write(line, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,es9.2)') 'step     ', kstep, '/', prob%sc%steps, ': ' // sol%method // &
      ' ', sol%iterations, ' iterations, ', count(z(1:n) > 0.0_dp), ' active, ', count(sol%fstate == 2), &
      ' slipping, residual ', sol%residual
    call say(log, trim(line))
  end subroutine keep_friction_step

end module load_steps
