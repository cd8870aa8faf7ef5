!> contact_step: one frictionless contact problem LCP(W, q) with the free
!> modes as equality constraints (contact_lcp), by the method the deck asks
!> for; and what a solved load step hands on: its friction results and its
!> record (VTK file and table row) under OUTPUT steps=all.
!>
!> Why it exists: the step that every kind of stepping shares (the final
!> step, the earlier steps of OUTPUT steps=all, each update of finite
!> sliding).  Who may use it: the program's step modules (run_state's list).
!>
!> Programming interface
!>   solve_contact_problem(run, sol, rigid_alpha)  LCP(W, q) of the step, the free motions
!>   friction_results(run, res)   a friction step's states, slip and shear into res
!>   keep_friction_solution(run, ...)  the final friction step's solution and report into res
!>   record_step(run, kstep, fk, ubk, z, rigid_alpha, res)  an earlier step's outputs
module contact_step
  use kinds, only: dp
  use strings, only: int_to_str
  use exits, only: fail_numerical
  use run_state, only: run_t
  use run_report, only: say
  use lcp_solvers, only: lcp_options_t, lcp_report_t
  use contact_lcp, only: contact_solution_t, solve_contact
  use contact_set, only: node_traction
  use rigid_modes, only: motion_name, remove_motions
  use results_writer, only: results_t
  use linear_system, only: solve_loads
  use post_processing, only: pair_resultants, post_process, nodal_contact_fields, check_finite_results
  use run_outputs, only: write_step
  use run_estimate, only: estimate_results
  use contact_checks, only: check_step_sliding
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use held_by_contact, only: diagnose_pulled_rigid, diagnose_pulled_body, unheld_summary, step_prefix
  implicit none
  private
  public :: solve_contact_problem, friction_results, record_step, keep_friction_solution

contains

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

  !> [a 0; 0 b]: the held combinations of the bodies' modes and of the RIGIDs'
  !> free directions, side by side.
  function block_diagonal(a, b) result(c)
    real(dp), intent(in) :: a(:,:), b(:,:)
    real(dp), allocatable :: c(:,:)
    allocate(c(size(a, 1) + size(b, 1), size(a, 2) + size(b, 2)), source=0.0_dp)
    c(1:size(a, 1), 1:size(a, 2)) = a
    c(size(a, 1) + 1:, size(a, 2) + 1:) = b
  end function block_diagonal

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

  !> The final friction step's solution into the run's results: the
  !> multipliers, gaps and slips, the free motions, the states and the
  !> method's report, then friction_results.
  !>   method, iterations, rep (in) the friction solver, its iterations over all steps, its last report
  !>   z    (in)    (n + nt) normal then tangential multipliers, n = run%cs%nrow
  !>   qn   (in)    (n) the gaps without contact forces, the free motions' part included
  !>   slip (in)    (nt) T u of the final step along its tangents
  !>   body_alpha, fstate, rigid_alpha (inout) moved out (empty on exit; rigid_alpha only when floating)
  subroutine keep_friction_solution(run, method, iterations, rep, z, qn, slip, body_alpha, fstate, rigid_alpha, &
                                    floating)
    type(run_t), intent(inout) :: run
    character(len=*), intent(in) :: method
    integer, intent(in) :: iterations
    type(lcp_report_t), intent(in) :: rep
    real(dp), intent(in) :: z(:), qn(:), slip(:)
    real(dp), allocatable, intent(inout) :: body_alpha(:), rigid_alpha(:)
    integer, allocatable, intent(inout) :: fstate(:)
    logical, intent(in) :: floating
    integer :: n
    n = run%cs%nrow
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
    run%res%slip = slip
    call friction_results(run, run%res)
  end subroutine keep_friction_solution

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
end module contact_step
