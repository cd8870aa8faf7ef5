!> step_solution: what a solved load step hands on, to the next step (the
!> friction history, the configuration under sliding=finite) and to the
!> results: the contact multipliers, gaps and slips, the free motions, the
!> method that solved it with its figures, and the fallbacks lcp=auto took.
!>
!> Why it exists: the solve layer returns its answer as a value of its own,
!> not by writing into the run's results, so that each step's answer can be
!> kept, recorded or dropped by whoever asked for it.
!>
!> Programming interface
!>   type(step_solution_t)   the answer of one load step
!>   type(fallback_t)        one change of method inside a step (lcp=auto)
!>   multipliers(sol)        [mu, tau]: the normal then the tangential multipliers
!>   add_fallback(sol, kstep, from, to)   one fallback more
module step_solution
  use kinds, only: dp
  use text_scan, only: string_t
  use mode_support, only: mode_split_t
  use certificate, only: certificate_t
  implicit none
  private
  public :: step_solution_t, fallback_t, multipliers, add_fallback

  !> One change of method inside a load step: lcp=auto tried `from`, which
  !> failed without proving that the step has no solution, then `to`.
  type :: fallback_t
    integer :: step = 0                            !< the load step
    character(len=:), allocatable :: from, to      !< the methods ('pgs(omega=0.3)' with its relaxation)
  end type fallback_t

  type :: step_solution_t
    integer :: step = 0                            !< the load step solved
    real(dp), allocatable :: mu(:)                 !< (nrow) normal multipliers (nodal forces)
    real(dp), allocatable :: tau(:)                !< (ntan) tangential multipliers (unallocated without friction)
    real(dp), allocatable :: gap(:)                !< (nrow) final gaps
    real(dp), allocatable :: q(:)                  !< (nrow) the gaps without contact forces nor free motions
    real(dp), allocatable :: slip(:)               !< (ntan) T u of the step along its tangents
    integer, allocatable :: fstate(:)              !< (ntan) 0 open, 1 stick, 2 slip
    real(dp), allocatable :: alpha(:)              !< (fl%k) amplitudes of the bodies' free modes
    real(dp), allocatable :: rigid_alpha(:)        !< (rsplit%k) the RIGIDs' free motion (unallocated: none)
    type(mode_split_t) :: split                    !< the step's split of the bodies' free modes (its
                                                   !< unheld combinations carry no motion)
    type(string_t), allocatable :: unheld_mode(:)  !< (nu) 'BODY KIND X Y' of each unheld combination
    character(len=:), allocatable :: method        !< the method that solved the step
    integer :: iterations = 0                      !< its iterations (pivots, sweeps, Newton steps)
    integer :: total_iterations = 0                !< iterations of every step so far, this one included
    real(dp) :: residual = 0                       !< its natural residual (scaled)
    type(certificate_t) :: cert                    !< the answer checked against its conditions (certificate)
    integer :: updates = 0                         !< sliding=finite: geometry updates of the step
    type(fallback_t), allocatable :: fallback(:)   !< every fallback of the steps so far
    integer :: slip_entries = 0                    !< friction: rows of a pair that came into contact in a load
                                                   !< step that also dragged them into partial slip (load_steps)
    integer :: slip_entry_pair = 0                 !< that pair
    integer :: slip_entry_step = 0                 !< that load step (0: none)
    real(dp), allocatable :: u(:)                  !< (ndof) the step's displacement when its solve gives it
                                                   !< whole (finite strain); unallocated: recovered from mu
    real(dp), allocatable :: newton(:,:)           !< (3, steps so far) finite strain: step, Newton
                                                   !< iterations, residual of each step
  end type step_solution_t

contains

  !> z = [mu, tau]: the multipliers of every row, normal then tangential.
  function multipliers(sol) result(z)
    type(step_solution_t), intent(in) :: sol
    real(dp), allocatable :: z(:)
    if (allocated(sol%tau)) then
      z = [sol%mu, sol%tau]
    else
      z = sol%mu
    end if
  end function multipliers

  !> One fallback more at the end of sol%fallback.
  subroutine add_fallback(sol, kstep, from, to)
    type(step_solution_t), intent(inout) :: sol
    integer, intent(in) :: kstep
    character(len=*), intent(in) :: from, to
    type(fallback_t), allocatable :: grown(:)
    integer :: n
    if (.not. allocated(sol%fallback)) allocate(sol%fallback(0))
    n = size(sol%fallback)
    allocate(grown(n + 1))
    grown(1:n) = sol%fallback
    grown(n + 1)%step = kstep
    grown(n + 1)%from = from
    grown(n + 1)%to = to
    call move_alloc(grown, sol%fallback)
  end subroutine add_fallback

end module step_solution
