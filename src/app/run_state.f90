!> run_state: what one run of contact2d holds, as its stages: the options of
!> the command line, the collected input errors, the log and clock, the
!> problem, the linear system, the final step's solution, the results, the
!> files of a load history in progress and ADAPT's loop.
!>
!> Why it exists: the program reads like the method (read the deck, build
!> the problem, assemble, factorize, condense, solve the load steps, recover,
!> write), one call per step, and hands each layer below only the stages it
!> needs (problem_t, system_t, step_solution_t, results_t, log_t): no module
!> below the application knows run_t (scripts/module-graph checks the
!> layers).  Only the application's own modules take it whole.
!>
!> Programming interface
!>   type(run_t)               the run's stages
!>   type(run_options_t)       the command line and the case row
!>   type(outputs_t)           OUTPUT steps=all's files in progress, the log's `wrote` lines
!>   type(adapt_state_t)       ADAPT's loop, carried from one mesh's solve to the next
!>   type(kept_mesh_t)         ADAPT's last mesh that solved: what its outputs need
module run_state
  use kinds, only: dp
  use errors, only: diag_t
  use deck_types, only: mesh_spec_t
  use deck_expressions, only: parameter_set_t
  use gmsh_runner, only: gmsh_options_t
  use safe_files, only: temporary_t
  use text_scan, only: string_t
  use run_log, only: log_t
  use problem, only: problem_t
  use linear_system, only: system_t
  use step_solution, only: step_solution_t
  use results_writer, only: results_t
  implicit none
  private
  public :: run_t, run_options_t, outputs_t, adapt_state_t, kept_mesh_t

  !> What the command line (and the case table's row) asked for: set before
  !> the deck is read, read-only after.
  type :: run_options_t
    character(len=:), allocatable :: deck_path     !< the deck as typed
    character(len=:), allocatable :: outdir        !< the output folder (-o; DIR/case_N with --cases)
    logical :: check_only = .false.                !< --check: validate, solve nothing, write nothing
    type(gmsh_options_t) :: gmsh                   !< --trust-geo, --gmsh-timeout, the mesh cache
    type(parameter_set_t) :: overrides             !< -D name=value and the --cases row
    character(len=:), allocatable :: cases_path    !< --cases FILE.csv ('' when none)
    integer :: case_number = 0                     !< --case N (0: none given)
    logical :: collect = .false.                   !< --collect: write DIR/cases.csv from what has run, run nothing
    integer :: jobs = 0                            !< -j N: threads of the run (0: the environment's)
    character(len=:), allocatable :: thread_note   !< what a memory limit changed in the thread count ('' none)
  end type run_options_t

  !> The files of OUTPUT steps=all written as the steps are solved, and the
  !> run log's `wrote` lines.
  type :: outputs_t
    type(temporary_t), allocatable :: step_tmp(:,:) !< (2, steps) the temporaries of each step's .vtu and contact table
    real(dp), allocatable :: step_table(:,:)       !< (ncol, steps) the rows of NAME_steps.csv
    integer, allocatable :: zone_sets(:,:)         !< (2, npair) the zones each pair has columns for (step_table)
    character(len=:), allocatable :: wrote(:)      !< the run log's `wrote` lines
  end type outputs_t

  !> A mesh that solved, kept by ADAPT while the next one is solved: when
  !> that one fails, the run ends with this one's outputs.
  type :: kept_mesh_t
    type(problem_t) :: prob                        !< its problem (meshes, contact rows)
    type(step_solution_t) :: sol                   !< its final step's solution
    type(results_t) :: res                         !< its results
    type(outputs_t) :: out                         !< its load history's files in progress
    type(string_t), allocatable :: warning(:)      !< its warnings
  end type kept_mesh_t

  !> ADAPT's loop (adaptivity), carried from one mesh's solve to the next.
  type :: adapt_state_t
    integer :: step = 0                            !< meshes solved so far
    real(dp) :: cpu0 = 0                           !< CPU seconds (gmsh's included) when this mesh's step began
    real(dp), allocatable :: time0(:)              !< (nphase) log%cpu when this mesh's step began
    real(dp) :: energy_prev = -1, dofs_prev = -1   !< the previous mesh's energy estimate and dofs (< 0: none)
    real(dp) :: pressure_prev = -1                 !< and its estimate of the ADAPT quantity (< 0: none)
    logical :: capped = .false.                    !< this mesh was made coarser than asked, to keep within max_dofs
    type(mesh_spec_t), allocatable :: geo(:)       !< (nbody) each body's mesh as the deck gives it: what gmsh re-meshes
    type(kept_mesh_t), allocatable :: kept         !< the last mesh that solved (from the second mesh on)
  end type adapt_state_t

  type :: run_t
    type(run_options_t) :: opts                    !< the command line and the case row
    type(diag_t) :: diag                           !< the input errors collected so far
    type(log_t) :: log                             !< the run log, its quiet flag, the clock, the warnings
    type(problem_t) :: prob                        !< deck, scene, contact set, free modes, equations
    type(system_t) :: sys                          !< K's factor, u0, W, q
    type(step_solution_t) :: sol                   !< the final load step's solution
    type(results_t) :: res                         !< what the files report
    type(outputs_t) :: out                         !< a load history's files in progress
    type(adapt_state_t) :: adapt                   !< ADAPT's loop
  end type run_t

end module run_state
