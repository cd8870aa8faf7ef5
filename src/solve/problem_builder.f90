!> problem_builder: the problem of a deck, built: the scene (meshes, laws,
!> loads), the contact set (mortar rows per pair, nodes in local axes), the
!> free rigid modes of the bodies held only by contact (pinned to factorize
!> K^#, their combinations split into those contact holds and those it does
!> not), the RIGIDs' free directions, and the equation numbering.
!>
!> Why it exists: the problem is the solve layer's first stage; building it
!> from a deck in one call lets the application (problem_setup, which then
!> reports the scene) and the unit tests of the solve layer start from the
!> same place.  Nothing here stops the run: input errors go to diag (each at
!> its deck line), other failures return an error_t.
!>
!> Programming interface
!>   build_problem(prob, gmsh, diag, log, err)   prob%deck on entry; the problem on exit
module problem_builder
  use strings, only: int_to_str
  use errors, only: diag_t, add_error, has_errors, error_t, error_input
  use run_log, only: log_t, add_warning
  use run_phase, only: enter_phase
  use gmsh_runner, only: gmsh_options_t
  use problem, only: problem_t
  use scene, only: build_scene
  use body, only: number_equations
  use contact_set, only: build_contact_set
  use local_axes, only: rotate_constraint_rows
  use rigid_modes, only: find_floating_modes
  use mode_support, only: split_free_modes
  use rigid_support, only: split_rigid_modes
  use held_by_contact, only: check_floating_bodies, check_floating_friction_solver
  implicit none
  private
  public :: build_problem

contains

  !> The problem of prob%deck (module header); a pair that can never touch
  !> gets `warning no_contact`.
  !>   prob (inout) deck on entry; sc, cs, fl, split, rsplit, eq, nfree on exit
  !>   gmsh (in)    how .geo files are meshed (trust, time limit, cache)
  !>   diag (inout) the input errors, each at its deck line (then return)
  !>   log  (inout) the warnings
  !>   err  (out)   a failure that is not the deck's (a mesh gmsh cannot make, a
  !>                contact set that cannot be built, named by its CONTACT)
  subroutine build_problem(prob, gmsh, diag, log, err)
    type(problem_t), intent(inout) :: prob
    type(gmsh_options_t), intent(in) :: gmsh
    type(diag_t), intent(inout) :: diag
    type(log_t), intent(inout) :: log
    type(error_t), allocatable, intent(out) :: err
    logical, allocatable :: held(:)
    integer :: i
    call enter_phase('building the scene')
    call build_scene(prob%deck, gmsh, prob%sc, diag, err)
    if (has_errors(diag) .or. allocated(err)) return
    call enter_phase('building the mortar operator')
    call build_contact_set(prob%sc%bodies, prob%sc%specs, prob%cs, err)
    if (allocated(err)) then
      ! a contact-set error belongs to its CONTACT statement: bad input there
      ! at that statement's line, a numerical failure names the pair
      if (err%category == error_input .and. err%pair >= 1 .and. err%pair <= size(prob%deck%contacts)) then
        call add_error(diag, prob%deck%file, prob%deck%contacts(err%pair)%line, err%message)
        deallocate(err)
      else if (err%pair > 0) then
        err%message = 'CONTACT ' // int_to_str(err%pair) // ': ' // err%message
      end if
      return
    end if
    call rotate_constraint_rows(prob%cs, prob%sc%bodies)     ! nodes in local axes (FIX un=/ut=)
    do i = 1, prob%cs%npair
      if (prob%cs%pair(i)%nrow == 0) call add_warning(log, 'no_contact', prob%deck%file // ':' // &
        int_to_str(prob%deck%contacts(i)%line) // ': no part of the master boundary faces the slave boundary: ' // &
        'this pair can never touch (check the boundary names and the slave/master choice)')
    end do
    call enter_phase('finding the rigid modes')
    ! free rigid modes (bodies held only by contact): pin k dofs to factorize K^#
    call find_floating_modes(prob%sc%bodies, prob%sc%fixed, prob%fl)
    call check_floating_bodies(prob, diag)
    if (has_errors(diag)) return
    call split_free_modes(prob%cs, prob%sc%bodies, prob%fl, prob%sc%fext, prob%split)
    call split_rigid_modes(prob%cs, prob%sc%rigids, prob%sc%fixed, prob%sc%fext, prob%rsplit)
    call check_floating_friction_solver(prob, diag)
    if (has_errors(diag)) return
    held = prob%sc%fixed
    if (prob%fl%k > 0) held(prob%fl%pin) = .true.
    held(prob%rsplit%dof) = .true.             ! a RIGID has no stiffness: its free dofs are modes, not equations
    call number_equations(held, prob%eq, prob%nfree)
  end subroutine build_problem

end module problem_builder
