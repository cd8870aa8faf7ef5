!> problem: the problem a run solves, as the layers below the application
!> hand it to the solver: the deck, the scene built from it, the contact
!> rows, the bodies' free rigid modes and the RIGIDs' free directions, and
!> the numbering of the equations.
!>
!> Why it exists: the solve layer works on explicit stages (problem, linear
!> system, step solution) and never on the run's own state; this is the
!> first stage, built once per mesh by the application (problem_setup) and
!> read by every step.  Under sliding=finite the contact rows `cs` follow
!> the bodies: the load-step loop rebuilds them at every geometry update,
!> the one part of a problem that a solve changes.
!>
!> The splits `split` and `rsplit` are those of the deck's final loads on
!> the initial rows: what the run log and the checks before the solve speak
!> of.  Each load step makes its own (held_by_contact's split_step_modes).
!>
!> Programming interface
!>   type(problem_t)              deck, scene, contact set, free modes, splits, equations
!>   step_label(prob, kstep)      'load step k of n: ', the prefix of a step's messages
module problem
  use strings, only: int_to_str
  use deck_reader, only: deck_t
  use scene, only: scene_t
  use contact_set, only: contact_set_t
  use rigid_modes, only: floating_t
  use mode_support, only: mode_split_t
  use rigid_support, only: rigid_split_t
  implicit none
  private
  public :: problem_t, step_label

  type :: problem_t
    type(deck_t) :: deck                           !< the deck, overrides applied
    type(scene_t) :: sc                            !< bodies, dofs, loads, pair specifications
    type(contact_set_t) :: cs                      !< the contact rows (the current ones under sliding=finite)
    type(floating_t) :: fl                         !< the bodies' free rigid modes (held only by contact)
    type(mode_split_t) :: split                    !< those modes that contact holds, and those it does not
    type(rigid_split_t) :: rsplit                  !< the RIGIDs' free directions: floating modes loaded by FORCE
    integer, allocatable :: eq(:)                  !< (ndof) free equation of each dof, 0 when fixed
    integer :: nfree = 0                           !< free equations
  end type problem_t

contains

  !> The prefix of every message about one load step, 'load step k of n: '
  !> (after FILE:LINE: when the message names a deck statement).
  !>   kstep (in) the step, 1 .. steps
  function step_label(prob, kstep) result(t)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    character(len=:), allocatable :: t
    t = 'load step ' // int_to_str(kstep) // ' of ' // int_to_str(prob%sc%steps) // ': '
  end function step_label

end module problem
