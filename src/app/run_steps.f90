!> run_steps: the steps of the program between the condensed problem and the
!> files, on the run's stages: the load history (every step the deck needs,
!> each earlier one recorded under OUTPUT steps=all as it is solved), the
!> final state's results, the monitors of the model and the run's own error
!> estimate.
!>
!> Why it exists: the solve layer returns its answers and errors; what a
!> run does with them (the files of a recorded step, the results of the
!> final state) is the application's.  Each failure is returned to the
!> program, which decides (exits' stop_on, or ADAPT's last mesh that solved).
!>
!> Programming interface
!>   solve_steps(run, err)      the load steps (load_steps), the final step's solution in run%sol
!>   compute_results(run, err)  u of the final step and its results, the factor's figures
!>   check_contact(run, err)    the monitors of the contact model after the final step
!>   estimate_error(run)        the run's error estimate, timed as phase estimate
module run_steps
  use kinds, only: dp
  use errors, only: error_t
  use run_state, only: run_t, outputs_t
  use run_log, only: log_t, lap, say, ph_lcp, ph_output, ph_estimate
  use run_phase, only: enter_phase
  use problem, only: problem_t, step_label
  use linear_system, only: system_t, recover_solution, step_displacement
  use step_solution, only: step_solution_t
  use load_steps, only: solve_load_steps, step_recorder_t, step_load_t
  use contact_checks, only: check_contact_model
  use post_processing, only: take_solution, contact_measures, state_results
  use run_estimate, only: estimate_results
  use energy_bound, only: bound_energy_error
  use results_writer, only: results_t
  use sparse_cholesky, only: factor_nnz, factor_memory, factor_ordering
  use contact_condensation, only: condensed_report
  use run_outputs, only: write_step
  use scene, only: step_thermal_strains
  use run_report, only: say_step
  implicit none
  private
  public :: solve_steps, compute_results, check_contact, estimate_error

  !> The earlier steps of OUTPUT steps=all, kept as files while the history
  !> is solved: their outputs in progress and the folder they go to.
  type, extends(step_recorder_t) :: step_files_t
    type(outputs_t) :: out                         !< the run's outputs in progress
    character(len=:), allocatable :: outdir        !< the output folder
  contains
    procedure :: record => record_step_files
  end type step_files_t

contains

  !> Every load step the deck needs (load_steps): the final step's solution
  !> into run%sol and its contact measures into run%res (before the
  !> recovery frees W); each earlier step of OUTPUT steps=all recorded as it
  !> is solved (record).
  subroutine solve_steps(run, err)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable, intent(out) :: err
    type(step_files_t) :: files
    call enter_phase('solving the LCP')
    if (run%prob%cs%ntan > 0) call enter_phase('solving the friction LCP')
    files%outdir = run%opts%outdir
    call solve_load_steps(run%prob, run%sys, run%log, run%sol, err, files)
    call move_out(files%out, run%out)
    if (allocated(err)) return
    call take_solution(run%prob, run%sol, run%res)
    run%res%steps = run%prob%sc%steps
    if (run%sys%with_contact) then
      call contact_measures(run%prob, run%sys%w, run%sol, run%res)
      if (run%prob%deck%output%steps_all .and. run%prob%cs%ntan == 0) &
        call say_step(run%log, run%prob%sc%steps, run%prob%sc%steps, run%res%lcp_method, run%sol%iterations, &
                      run%res%active_nodes)
      call lap(run%log, ph_lcp)
    else
      run%res%lcp_method = 'none'                ! no contact: no LCP time (u0's solve goes to recover)
    end if
  end subroutine solve_steps

  !> The outputs in progress handed back to the run (from is left empty).
  subroutine move_out(from, to)
    type(outputs_t), intent(inout) :: from, to
    if (allocated(from%step_tmp)) call move_alloc(from%step_tmp, to%step_tmp)
    if (allocated(from%step_table)) call move_alloc(from%step_table, to%step_table)
    if (allocated(from%zone_sets)) call move_alloc(from%zone_sets, to%zone_sets)
  end subroutine move_out

  !> An earlier step of OUTPUT steps=all: its displacement, its results and
  !> error estimate, the slide check, its VTK file, contact table and row of
  !> the step table.
  subroutine record_step_files(self, prob, sys, load, sol, log, err)
    class(step_files_t), intent(inout) :: self
    type(problem_t), intent(in) :: prob
    type(system_t), intent(in) :: sys
    type(step_load_t), intent(in) :: load
    type(step_solution_t), intent(in) :: sol
    type(log_t), intent(inout) :: log
    type(error_t), allocatable, intent(out) :: err
    type(results_t) :: step
    call step_displacement(prob, sys, load%f, load%ubar, sol, step%u, err)
    if (allocated(err)) then
      err%message = step_label(prob, load%kstep) // err%message
      return
    end if
    call take_solution(prob, sol, step)
    allocate(step%adt(prob%sc%nelem))
    call step_thermal_strains(prob%sc, load%t, step%adt)
    if (sys%with_contact) call contact_measures(prob, sys%w, sol, step)
    call state_results(prob, load%f, step, err)
    if (allocated(err)) return
    call estimate_results(prob, step)                     ! the step's error_indicator
    call check_contact_model(prob, step%u, step%mu, load%kstep, log, err)   ! the slide against small sliding
    if (allocated(err)) return
    call write_step(self%out, self%outdir, prob, load%kstep, step, sol%iterations)
    if (sys%with_contact .and. prob%cs%ntan == 0) &
      call say_step(log, load%kstep, prob%sc%steps, step%lcp_method, sol%iterations, step%active_nodes)
  end subroutine record_step_files

  !> The final state: u from the final step's multipliers and free motions,
  !> the results (state_results) and the figures of the factorization and
  !> of the solves.
  subroutine compute_results(run, err)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable, intent(out) :: err
    call recover_solution(run%prob, run%sys, run%sol, run%log, run%res%u, err)
    if (allocated(err)) return
    call enter_phase('computing the results')
    allocate(run%res%adt(run%prob%sc%nelem))
    call step_thermal_strains(run%prob%sc, real(run%prob%sc%steps, dp), run%res%adt)
    call state_results(run%prob, run%prob%sc%fext, run%res, err)
    if (allocated(err)) return
    run%res%factor_nnz = factor_nnz(run%sys%factor)
    run%res%ordering = factor_ordering(run%sys%factor)
    run%res%factor_memory = real(factor_memory(run%sys%factor), dp)
    run%res%factor_parts = run%sys%factor%nparts
    run%res%factor_threads = run%sys%factor%side_by_side
    if (allocated(run%sys%cd%block)) run%res%condense_text = condensed_report(run%sys%cd)
    if (allocated(run%sys%blocks)) run%res%condense_block = run%sys%blocks
    run%res%time_solve = run%sys%time_solve
    run%res%time_ordering = run%sys%time_ordering
    run%res%time_assemble_values = run%sys%time_assemble_values
  end subroutine compute_results

  !> The monitors of the contact model after the final step: the slide of
  !> each small-sliding pair (exit 1 beyond it), the polygon gaps (warning).
  subroutine check_contact(run, err)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable, intent(out) :: err
    call check_contact_model(run%prob, run%res%u, run%res%mu, run%prob%sc%steps, run%log, err)
  end subroutine check_contact

  !> The error estimate of the run's final state, timed as phase estimate.
  subroutine estimate_error(run)
    type(run_t), intent(inout) :: run
    character(len=:), allocatable :: why
    call lap(run%log, ph_output)                 ! the results computed so far: output, as before
    if (run%prob%deck%estimate) call enter_phase('estimating the error')
    call estimate_results(run%prob, run%res)
    if (run%prob%deck%estimate .and. any(run%prob%sc%bodies(:)%finite)) call say(run%log, 'estimate not computed: ' // &
      'the estimators are those of linear elasticity, and a hyperelastic body is solved in finite strain')
    if (run%res%estimated .and. run%prob%deck%estimate_bound) then
      call bound_energy_error(run%prob, run%res, why)
      ! ESTIMATE bound asked for a figure: its absence is said, with why
      if (len(why) > 0) call say(run%log, 'estimate energy_bound not computed: ' // why)
    end if
    if (run%res%estimated) call lap(run%log, ph_estimate)
  end subroutine estimate_error

end module run_steps
