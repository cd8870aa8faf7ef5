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
!>   build_problem(run)   scene, contact set, rigid modes, equations; the scene in the run log
module problem_setup
  use strings, only: int_to_str
  use errors, only: error_t, add_error
  use run_phase, only: enter_phase
  use exits, only: stop_input_errors, fail_numerical, exit_program
  use run_state, only: run_t, ph_mesh
  use run_report, only: say, lap, report_scene, add_warning
  use run_outputs, only: make_folder
  use case_selection, only: check_overrides
  use deck_reader, only: read_deck
  use scene, only: build_scene
  use body, only: number_equations
  use contact_set, only: build_contact_set
  use local_axes, only: rotate_constraint_rows
  use rigid_modes, only: find_floating_modes
  use mode_support, only: split_free_modes
  use rigid_support, only: split_rigid_modes
  use post_processing, only: name_results
  use held_by_contact, only: check_floating_bodies, check_floating_friction_solver, check_unheld_loads, &
                             check_unheld_rigid_loads
  implicit none
  private
  public :: read_input, build_problem

contains

  !> The deck, with the -D and case-table overrides (each must name a
  !> PARAMETER), and the output folder (unless --check).  Bad input ends the
  !> run: every error found, then exit 2.
  !>   run (inout) the command line on entry; deck on exit
  subroutine read_input(run)
    type(run_t), intent(inout) :: run
    call enter_phase('reading the deck')
    call read_deck(run%deck_path, run%deck, run%diag, run%overrides)
    call check_overrides(run)
    call stop_input_errors(run%diag)
    if (.not. run%check_only) call make_folder(run%outdir, run%diag)
    call stop_input_errors(run%diag)
  end subroutine read_input

  !> The scene (meshes, laws, loads: scene), the contact set (mortar rows
  !> per pair, nodes in local axes), the free rigid modes of the bodies held
  !> only by contact (pinned to factorize K^#, their combinations split into
  !> those contact holds and those it does not), the RIGIDs' free directions,
  !> and the equation numbering; then the run log's scene.  With --check the
  !> run ends here (exit 0, nothing solved, nothing written).  A load along a
  !> motion nothing holds ends it with exit 1.
  !>   run (inout) deck on entry; sc, cs, fl, split, rsplit, eq, nfree on exit
  subroutine build_problem(run)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable :: err
    logical, allocatable :: held(:)
    integer :: i
    call enter_phase('building the scene')
    call build_scene(run%deck, run%gmsh, run%sc, run%diag, err)
    call stop_input_errors(run%diag)
    if (allocated(err)) call fail_numerical(err%message)
    call enter_phase('building the mortar operator')
    call build_contact_set(run%sc%bodies, run%sc%specs, run%cs, err)
    if (allocated(err)) call contact_error(run, err)
    call rotate_constraint_rows(run%cs, run%sc%bodies)     ! nodes in local axes (FIX un=/ut=)
    do i = 1, run%cs%npair
      if (run%cs%pair(i)%nrow == 0) call add_warning(run, 'no_contact', run%deck%file // ':' // &
        int_to_str(run%deck%contacts(i)%line) // ': no part of the master boundary faces the slave boundary: ' // &
        'this pair can never touch (check the boundary names and the slave/master choice)')
    end do
    call enter_phase('finding the rigid modes')
    ! free rigid modes (bodies held only by contact): pin k dofs to factorize K^#
    call find_floating_modes(run%sc%bodies, run%sc%fixed, run%fl)
    call check_floating_bodies(run)
    call split_free_modes(run%cs, run%sc%bodies, run%fl, run%sc%fext, run%split)
    call split_rigid_modes(run%cs, run%sc%rigids, run%sc%fixed, run%sc%fext, run%rsplit)
    call check_floating_friction_solver(run)
    held = run%sc%fixed
    if (run%fl%k > 0) held(run%fl%pin) = .true.
    held(run%rsplit%dof) = .true.             ! a RIGID has no stiffness: its free dofs are modes, not equations
    call number_equations(held, run%eq, run%nfree)
    run%res%effects = run%sc%effects
    run%res%axisymmetric = run%deck%axisymmetric
    run%res%nfree = run%nfree
    call name_results(run)
    call report_scene(run)
    if (run%check_only) then
      call say(run, 'check: the deck and its meshes are valid; nothing solved, nothing written')
      call exit_program(0)
    end if
    call check_unheld_loads(run)
    call check_unheld_rigid_loads(run)
    call lap(run, ph_mesh)
  end subroutine build_problem

  !> A contact-set error belongs to its CONTACT statement: bad input there
  !> (status 2) is reported at that statement's line (exit 2), a numerical
  !> failure names the pair (exit 1).
  !>   run (inout) deck on entry; diag
  !>   e   (in)    the error of build_contact_set, e%pair its pair
  subroutine contact_error(run, e)
    type(run_t), intent(inout) :: run
    type(error_t), intent(in) :: e
    if (e%status == 2 .and. e%pair >= 1 .and. e%pair <= size(run%deck%contacts)) then
      call add_error(run%diag, run%deck%file, run%deck%contacts(e%pair)%line, e%message)
      call stop_input_errors(run%diag)
    end if
    if (e%pair > 0) call fail_numerical('CONTACT ' // int_to_str(e%pair) // ': ' // e%message)
    call fail_numerical(e%message)
  end subroutine contact_error

end module problem_setup
