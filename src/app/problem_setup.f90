!> problem_setup: the first two steps of a run, from the deck to the
!> problem the linear algebra takes: read the deck (with its overrides) and
!> build the scene, the contact set, the rigid modes and the equations.
!>
!> Why it exists: what a run assumes about its bodies (held by FIX, by
!> contact, or by nothing) is decided here once and told in the run log, so
!> that the program reads "read the deck, build the problem".  Who may use
!> it: the program.  Bad input ends the run (exit 2, every error found), a
!> load nothing can hold ends it with exit 1, as the program would.
!>
!> Programming interface
!>   read_input(run)      the deck, its overrides checked, the output folder
!>   setup_problem(run)   scene, contact set, rigid modes, equations; the scene in the run log
module problem_setup
  use errors, only: error_t
  use run_phase, only: enter_phase
  use exits, only: stop_input_errors, exit_program
  use run_state, only: run_t
  use run_log, only: say, lap, ph_mesh
  use run_report, only: report_scene
  use run_outputs, only: make_folder
  use case_selection, only: check_overrides
  use deck_reader, only: read_deck
  use problem_builder, only: build_problem
  use post_processing, only: name_results
  use held_by_contact, only: check_unheld_loads
  use steps_plot, only: check_plot_column
  implicit none
  private
  public :: read_input, setup_problem

contains

  !> The deck, with the -D and case-table overrides (each must name a
  !> PARAMETER), and the output folder (unless --check).  Bad input ends the
  !> run: every error found, then exit 2.
  !>   run (inout) the command line on entry; deck on exit
  subroutine read_input(run)
    type(run_t), intent(inout) :: run
    call enter_phase('reading the deck')
    call read_deck(run%opts%deck_path, run%prob%deck, run%diag, run%opts%overrides)
    call check_overrides(run)
    call stop_input_errors(run%diag)
    if (.not. run%opts%check_only) call make_folder(run%opts%outdir, run%diag)
    call stop_input_errors(run%diag)
  end subroutine read_input

  !> The problem of the deck (problem_builder: scene, contact set, free
  !> modes, splits, equations) and the run log's scene.  With --check the run
  !> ends here (exit 0, nothing solved, nothing written).  Bad input ends it
  !> with exit 2 (every error found); a problem that cannot be built or a
  !> load along a motion nothing holds is returned.
  !>   run (inout) the deck on entry; the problem on exit
  !>   err (out)   the failure
  subroutine setup_problem(run, err)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable, intent(out) :: err
    call build_problem(run%prob, run%opts%gmsh, run%diag, run%log, err)
    call stop_input_errors(run%diag)
    if (allocated(err)) return
    call check_plot_column(run%prob, run%diag)     ! OUTPUT x=: a column of the steps table, before the solve
    call stop_input_errors(run%diag)
    run%res%effects = run%prob%sc%effects
    run%res%axisymmetric = run%prob%deck%axisymmetric
    run%res%nfree = run%prob%nfree
    call name_results(run%prob, run%res)
    call report_scene(run)
    if (run%opts%check_only) then
      call say(run%log, 'check: the deck and its meshes are valid; nothing solved, nothing written')
      call exit_program(0)
    end if
    call check_unheld_loads(run%prob, run%prob%split, run%prob%rsplit, 0, err)
    if (allocated(err)) return
    call lap(run%log, ph_mesh)
  end subroutine setup_problem

end module problem_setup
