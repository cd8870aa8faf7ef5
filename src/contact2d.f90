!> contact2d: unilateral (Signorini) contact between elastic bodies in 2D by
!> the mortar finite element method (Ben Belgacem, Hild, Laborde).
!>
!> The run reads like the algorithm, one call per step; each step module
!> says in its header what it does and why (doc/theory.md maps the paper's
!> equations to the routines):
!>   read the deck -> build the problem (meshes, laws, loads, contact pairs,
!>   rigid modes) -> assemble K_ff, f_f -> factorize (contact dofs last)
!>   -> condense the contact problem onto the slave nodes: W, q
!>   -> solve LCP(W, q) in every load step the deck needs (Lemke, PDAS, PGS;
!>   friction in order) -> recover u -> stresses, reactions, energy -> the
!>   model's assumptions checked (warnings) -> the error estimate -> (ADAPT:
!>   re-mesh from the indicators and solve again, until the target) -> VTK,
!>   contact table, summary.
!> The run's stages (options, log, problem, system, solution, results) are
!> in one run_t (run_state); each layer below is handed only the stages it
!> needs, and returns its errors: bad input exits 2, a numerical failure or
!> a problem without equilibrium exits 1, with the diagnosis (exits).
program contact2d
  use errors, only: error_t
  use exits, only: stop_on, exit_program
  use command_line, only: parse_command_line
  use threads, only: start_threads
  use run_state, only: run_t
  use run_log, only: start_clock
  use case_selection, only: select_case
  use problem_setup, only: read_input, setup_problem
  use linear_system, only: assemble_system, factorize_system, condense_system
  use run_steps, only: solve_steps, compute_results, check_contact, estimate_error
  use model_checks, only: check_model
  use setup_checks, only: check_setup
  use adaptivity, only: check_adaptable, adapt_mesh, fall_back, keep_meshes
  use gmsh_runner, only: stop_mesher
  use run_outputs, only: write_outputs
  use run_report, only: report_run
  implicit none

  type(run_t) :: run
  type(error_t), allocatable :: err

  call parse_command_line(run%opts%deck_path, run%opts%outdir, run%opts%check_only, run%log%quiet, run%opts%gmsh, &
                          run%opts%overrides, run%opts%cases_path, run%opts%case_number, run%opts%jobs, &
                          run%opts%collect)
  call start_threads(run%opts%jobs, run%opts%thread_note, err)   ! threads, BLAS threads, malloc arenas, once
  call stop_on(err)
  if (len(run%opts%cases_path) > 0) call select_case(run)   ! --cases: this run's row, or every row in turn
  call start_clock(run%log)

  call read_input(run)           ! the deck and its overrides; the output folder
  call check_adaptable(run)      ! ADAPT: every body's mesh is one gmsh can make again
  do
    mesh: block                  ! one mesh, solved; a failure leaves the block with err
      call setup_problem(run, err);  if (allocated(err)) exit mesh   ! scene, contact set, rigid modes, equations
      call assemble_system(run%prob, run%sys, run%log, err);  if (allocated(err)) exit mesh   ! K_ff, f_f - K_fd ubar
      call factorize_system(run%prob, run%sys, run%log, err);  if (allocated(err)) exit mesh  ! K_ff = L L'
      call condense_system(run%prob, run%sys, run%log, err);  if (allocated(err)) exit mesh   ! u0; W = C K^-1 C', q
      call solve_steps(run, err);  if (allocated(err)) exit mesh       ! mu (and tau), every load step the deck needs
      call compute_results(run, err);  if (allocated(err)) exit mesh   ! u = K^-1 (f - C'z) + R alpha; stresses, reactions
      call check_model(run%prob, run%res, run%log)                      ! locking, strain, rotation (warnings)
      call check_setup(run%prob, run%sol, run%res, run%log)             ! set-up mistakes: supports, mesh, steps
      call check_contact(run, err);  if (allocated(err)) exit mesh     ! small sliding (beyond: an error), polygon gaps
      call estimate_error(run)                                          ! the run's own error, element indicators
    end block mesh
    if (allocated(err)) then
      call fall_back(run, err)   ! ADAPT: the last mesh that solved; else the run ends, exit 1 (2 for input)
      exit
    end if
    if (.not. adapt_mesh(run)) exit   ! ADAPT: below target or at a limit; else every body re-meshed, solve again
  end do
  call stop_mesher()             ! gmsh's, every mesh made
  call write_outputs(run)        ! VTK, contact table, summary (and the steps' files)
  call keep_meshes(run)          ! ADAPT: the final meshes next to the outputs
  call report_run(run)           ! the run log: results, factor, timings, files written
  call exit_program(0)
end program contact2d
