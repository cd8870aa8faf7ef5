!> contact2d: unilateral (Signorini) contact between elastic bodies in 2D by
!> the mortar finite element method (Ben Belgacem, Hild, Laborde).
!>
!> The run reads like the algorithm, one call per step; each step module
!> says in its header what it does and why (doc/theory.md maps the paper's
!> equations to the routines):
!>   read the deck -> build the scene (meshes, laws, loads, contact pairs,
!>   rigid modes) -> assemble K_ff, f_f -> factorize (contact dofs last)
!>   -> condense the contact problem onto the slave nodes: W, q
!>   -> solve LCP(W, q) (Lemke, PDAS, PGS; friction in load steps)
!>   -> recover u -> stresses, reactions, energy -> the model's assumptions
!>   checked (warnings) -> the error estimate -> (ADAPT: re-mesh from the
!>   indicators and solve again, until the target) -> VTK, contact table, summary.
!> Everything the steps hand each other is in one run_t (run_state).  The
!> run log says what was done; bad input exits 2, a numerical failure or a
!> problem without equilibrium exits 1, with the diagnosis.
program contact2d
  use errors, only: error_t
  use exits, only: fail_numerical, exit_program
  use command_line, only: parse_command_line
  use threads, only: start_threads
  use run_state, only: run_t
  use case_selection, only: select_case
  use problem_setup, only: read_input, build_problem
  use linear_system, only: assemble_system, factorize_system, condense_system, recover_system
  use contact_solve, only: solve_contact_lcp
  use post_processing, only: compute_results
  use model_checks, only: check_model
  use contact_checks, only: check_contact_model
  use run_estimate, only: estimate_error
  use adaptivity, only: check_adaptable, adapt_mesh, keep_meshes
  use run_outputs, only: write_outputs
  use run_report, only: start_clock, report_run
  implicit none

  type(run_t) :: run
  type(error_t), allocatable :: err

  call parse_command_line(run%deck_path, run%outdir, run%check_only, run%quiet, run%gmsh, run%overrides, &
                          run%cases_path, run%case_number, run%jobs)
  call start_threads(run%jobs, run%thread_note, err)   ! threads, BLAS threads, malloc arenas, once
  if (allocated(err)) call fail_numerical(err%message)
  if (len(run%cases_path) > 0) call select_case(run)   ! --cases: this run's row, or every row in turn
  call start_clock(run)

  call read_input(run)           ! the deck and its overrides; the output folder
  call check_adaptable(run)      ! ADAPT: every body's mesh is one gmsh can make again
  do
    call build_problem(run)      ! scene, contact set, rigid modes, equations (--check ends here)
    call assemble_system(run)    ! K_ff and f_f - K_fd ubar; the fill-reducing ordering beside it
    call factorize_system(run)   ! K_ff = L L'
    call condense_system(run)    ! u0 = K^-1 f; W = C K^-1 C', q = g - C u0
    call solve_contact_lcp(run)  ! mu (and tau) from LCP(W, q), every load step the deck asks for
    call recover_system(run)     ! u = K^-1 (f - C' z) + the rigid motions
    call compute_results(run)    ! stresses, reactions, energy, contact fields
    call check_model(run)        ! the model's assumptions: locking, strain, rotation (warnings)
    call check_contact_model(run, run%sc%steps)   ! small sliding (exit 1 beyond), polygon gaps (warning)
    call estimate_error(run)     ! the run's own error: recovered stresses, element indicators
    if (.not. adapt_mesh(run)) exit   ! ADAPT: below target or at a limit; else every body re-meshed, solve again
  end do
  call write_outputs(run)        ! VTK, contact table, summary (and the steps' files)
  call keep_meshes(run)          ! ADAPT: the final meshes next to the outputs
  call report_run(run)           ! the run log: results, factor, timings, files written
  call exit_program(0)
end program contact2d
