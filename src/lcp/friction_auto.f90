!> friction_auto: SOLVER lcp=auto with friction, one load step by a first
!> method and, when it fails without proving that the step has no solution,
!> by the others in turn, so that the default fails only where every method
!> does.
!>
!> The methods (friction_lcp, friction_newton): 'lemke', exact in a finite
!> number of pivots but dense and O((n + 3 nt)^3) in all; 'pdas', the
!> primal-dual active set (semismooth Newton) method, a few dense solves of at most n + nt
!> unknowns, convergent near a solution only; 'pgs', nonsmooth Gauss-Seidel,
!> cheap sweeps but thousands of them, and for Coulomb with a large mu it
!> may stall where the others solve (a plate sheared on a rigid plane with
!> mu = 1 stalls at omega = 1, 0.7 and 0.5 and converges at 0.3 on a coarse
!> mesh, stalls at every omega on finer ones: bench/friction.sh).  The orders:
!>     first 'lemke'   lemke, pdas, pgs (omega), pgs (fallback_omega)
!>     first 'pdas'    pdas, lemke, pgs (omega), pgs (fallback_omega)
!>     first 'pgs'     pgs (omega), pgs (fallback_omega), pdas, lemke
!> the second PGS run left out when omega <= fallback_omega.  A failure that
!> proves that the step has no solution ends the sequence: a zero normal row
!> of G with a negative gap (PGS reports it as such, info 1) and Lemke's ray
!> termination on a Tresca problem (its LCP is positive semi-definite).  So
!> does an argument error.  Each iterative method starts from the lam given
!> on entry (the previous step's solution).
!>
!> Why it exists: the choice among the methods and its order are a policy of
!> their own, above the methods (friction_lcp, friction_newton), which know
!> nothing of each other.
!>
!> Programming interface
!>   type(friction_attempt_t)  method, omega, rep: one method tried
!>   solve_friction_auto(g, prob, first, opts, lam, rep, attempts)
!>   fallback_omega            the relaxation of the second PGS run (0.3)
!> No routine prints anything.
module friction_auto
  use kinds, only: dp
  use lcp_scaling, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: friction_problem_t, solve_friction_lcp, check_friction_problem
  use friction_newton, only: solve_friction_newton
  implicit none
  private
  public :: friction_attempt_t, solve_friction_auto, fallback_omega

  !> The relaxation of the second PGS run: on the plate sheared on a rigid
  !> plane with mu = 1 (bench/friction.sh, 128 x 40 elements) PGS stalls at
  !> omega = 1, 0.7 and 0.5 and converges at 0.3 in about 400 sweeps.
  real(dp), parameter :: fallback_omega = 0.3_dp

  !> One method tried by solve_friction_auto, and its outcome.
  type :: friction_attempt_t
    character(len=:), allocatable :: method        !< 'lemke', 'pdas' or 'pgs'
    real(dp) :: omega = 1.0_dp                     !< the PGS relaxation it ran with
    type(lcp_report_t) :: rep                      !< its report
  end type friction_attempt_t

contains

  !> One attempt more at the end of the list.  (Not attempts = [attempts,
  !> friction_attempt_t(...)]: gfortran leaks the constructor's temporary of
  !> a type with allocatable components.)
  subroutine add_attempt(attempts, method, omega, rep)
    type(friction_attempt_t), allocatable, intent(inout) :: attempts(:)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: omega
    type(lcp_report_t), intent(in) :: rep
    type(friction_attempt_t), allocatable :: grown(:)
    integer :: n
    n = size(attempts)
    allocate(grown(n + 1))
    grown(1:n) = attempts
    grown(n + 1)%method = method
    grown(n + 1)%omega = omega
    grown(n + 1)%rep = rep
    call move_alloc(grown, attempts)
  end subroutine add_attempt

  !> One load step by the first method, then the others (module header).
  !>   g, prob (in)    the problem, as in friction_lcp's solve_friction_lcp
  !>   first   (in)    'lemke', 'pdas' or 'pgs': the method tried first
  !>   opts    (in)    tol, maxit (each method's own limit when 0), omega
  !>                   (the first PGS run's relaxation)
  !>   lam     (inout) on entry the starting point of the iterative methods; on
  !>                   exit the solution of the method that solved the step,
  !>                   else the last method's iterate
  !>   rep     (out)   the report of the method that solved the step (info 0),
  !>                   or of the last one tried, its message then naming every
  !>                   attempt's failure in turn
  !>   attempts (out)  the methods tried, in order, with their reports; the
  !>                   last is the one whose lam is returned
  subroutine solve_friction_auto(g, prob, first, opts, lam, rep, attempts)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    character(len=*), intent(in) :: first
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: lam(:)
    type(lcp_report_t), intent(out) :: rep
    type(friction_attempt_t), allocatable, intent(out) :: attempts(:)
    character(len=5) :: order(4)
    real(dp) :: omegas(4), low
    real(dp), allocatable :: lam0(:)
    type(lcp_options_t) :: o
    character(len=:), allocatable :: failures
    integer :: k

    allocate(attempts(0))
    call check_friction_problem(g, prob, rep)
    if (rep%info < 0) return
    low = min(opts%omega, fallback_omega)
    select case (first)
    case ('lemke')
      order = [character(len=5) :: 'lemke', 'pdas', 'pgs', 'pgs']
      omegas = [opts%omega, opts%omega, opts%omega, low]
    case ('pdas')
      order = [character(len=5) :: 'pdas', 'lemke', 'pgs', 'pgs']
      omegas = [opts%omega, opts%omega, opts%omega, low]
    case default
      order = [character(len=5) :: 'pgs', 'pgs', 'pdas', 'lemke']
      omegas = [opts%omega, low, opts%omega, opts%omega]
    end select
    lam0 = lam
    do k = 1, 4
      ! the same relaxation twice over would fail twice over
      if (size(attempts) > 0) then
        associate (last => attempts(size(attempts)))
          if (order(k) == 'pgs' .and. last%method == 'pgs' .and. last%omega == omegas(k)) cycle
        end associate
      end if
      o = opts
      o%omega = omegas(k)
      lam = lam0
      if (order(k) == 'pdas') then
        call solve_friction_newton(g, prob, o, lam, rep)
      else
        call solve_friction_lcp(g, prob, trim(order(k)), o, lam, rep)
      end if
      call add_attempt(attempts, trim(order(k)), omegas(k), rep)
      if (rep%info <= 0 .or. proves_no_solution(prob, trim(order(k)), rep)) exit
    end do
    if (rep%info > 0 .and. size(attempts) > 1) then
      ! every method failed: the message names each failure in turn
      failures = ''
      do k = 1, size(attempts) - 1
        if (allocated(attempts(k)%rep%message)) failures = failures // attempts(k)%rep%message // '; then '
      end do
      if (allocated(rep%message)) rep%message = failures // rep%message
    end if
  end subroutine solve_friction_auto

  !> .true. when a failed report of method on prob shows that the step has no
  !> solution: info 1 from PGS (a zero normal row with a negative gap) or from
  !> Lemke on a Tresca problem.  Lemke's ray on a Coulomb problem with such a
  !> row goes on to the other methods; PGS finds the row at once.
  logical function proves_no_solution(prob, method, rep)
    type(friction_problem_t), intent(in) :: prob
    character(len=*), intent(in) :: method
    type(lcp_report_t), intent(in) :: rep
    proves_no_solution = rep%info == 1 .and. (method == 'pgs' .or. all(prob%cmu == 0.0_dp))
  end function proves_no_solution

end module friction_auto
