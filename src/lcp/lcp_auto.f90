!> lcp_auto: SOLVER lcp=auto, the one policy for every law and kinematics:
!> which method solves a load step first and which ones follow when it fails
!> without proving that the step has no solution, so that the default fails
!> only where every method does.
!>
!> The methods: 'lemke', exact in a finite number of pivots but dense and
!> O(n^3) in all; 'pdas', the primal-dual active set (semismooth Newton)
!> method, a few dense solves, globalised with friction (friction_newton: a
!> damped Newton method once a partition comes back); 'pgs', (nonsmooth)
!> Gauss-Seidel, cheap sweeps but thousands of them, and for Coulomb with a
!> large mu it may stall where the others solve (a plate sheared on a rigid
!> plane with mu = 1 stalls at omega = 1, 0.7 and 0.5 and converges at 0.3 on
!> a coarse mesh, stalls at every omega on finer ones: bench/friction.sh);
!> 'fixpt', friction only, the fixed point on the Tresca threshold
!> (friction_fixed_point): a Tresca problem, a convex QP, solved exactly for
!> the bounds of the last normal forces, until they settle; convergent for
!> Tresca and for a small mu, linear, the slowest.  The orders (auto_order):
!>   frictionless, up to 100 rows  lemke, pdas, pgs (omega)
!>   frictionless, above            pdas, lemke, pgs (omega)
!>   friction                       pdas, lemke, pgs (omega), pgs (fallback_omega), fixpt
!> the measured crossovers of doc/performance.md ("The three LCP solvers":
!> up to about 100 constraints the three tie and Lemke's exact pivoting is
!> kept; above, PDAS needs a few Newton steps where the others need many
!> pivots or sweeps; "The friction solvers": PDAS is 3 to 20 times Lemke from
!> 68 to 516 unknowns), the second PGS run left out when omega <=
!> fallback_omega, and the fixed point last, as the one method whose
!> convergence does not depend on round-off (Lemke's ties) or on the
!> conditioning of G (PGS).  A method the deck names (lcp=lemke, pdas, pgs)
!> is tried alone, first by friction_order with that method first.
!>
!> A failure that proves that the step has no solution ends the sequence
!> (proves_no_solution): without friction, info 1 of any method (Lemke's ray
!> on a positive semi-definite W, a zero row of W with a negative gap); with
!> friction, a zero normal row of G with a negative gap (PGS reports it as
!> such, info 1) and Lemke's ray on a Tresca problem (its LCP is positive
!> semi-definite).  So does an argument error.  Each iterative method starts
!> from the lam given on entry (the previous step's solution).
!>
!> Why it exists: the choice among the methods and its order are a policy of
!> their own, above the methods (lcp_lemke, lcp_newton, lcp_pgs,
!> friction_lcp, friction_newton, friction_fixed_point), which know nothing
!> of each other; solve_friction_method is the one place that maps a
!> friction method's name to its routine, and method_label to its name in a
!> log line.
!>
!> Programming interface
!>   type(lcp_attempt_t)     method, omega, rep: one method tried
!>   auto_order(friction, n, omega, methods, omegas)   lcp=auto's order
!>   friction_order(first, omega, methods, omegas)     the friction order from a first method
!>   proves_no_solution(friction, tresca, method, rep) a failure that ends the sequence
!>   add_attempt(attempts, method, omega, rep)         one attempt more on the list
!>   solve_friction_method(g, prob, method, omega, opts, lam, rep)   one attempt by its method's name
!>   method_label(method, omega)                       its name in a log line
!>   solve_friction_auto(g, prob, first, opts, lam, rep, attempts)  a friction step by the order
!>   fallback_omega          the relaxation of the second PGS run (0.3)
!> No routine prints anything.
module lcp_auto
  use kinds, only: dp
  use lcp_scaling, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: friction_problem_t, solve_friction_lcp, check_friction_problem
  use friction_newton, only: solve_friction_newton
  use friction_fixed_point, only: solve_friction_fixed_point
  use strings, only: format_number
  implicit none
  private
  public :: lcp_attempt_t, auto_order, friction_order, proves_no_solution, add_attempt, solve_friction_auto
  public :: solve_friction_method, method_label
  public :: fallback_omega, lemke_max_rows

  !> The relaxation of the second PGS run: on the plate sheared on a rigid
  !> plane with mu = 1 (bench/friction.sh, 128 x 40 elements) PGS stalls at
  !> omega = 1, 0.7 and 0.5 and converges at 0.3 in about 400 sweeps.
  real(dp), parameter :: fallback_omega = 0.3_dp
  !> frictionless: Lemke first up to this many rows, PDAS above (module header)
  integer, parameter :: lemke_max_rows = 100

  !> One method tried, and its outcome.
  type :: lcp_attempt_t
    character(len=:), allocatable :: method        !< 'lemke', 'pdas', 'pgs' or 'fixpt'
    real(dp) :: omega = 1.0_dp                     !< the PGS relaxation it ran with
    type(lcp_report_t) :: rep                      !< its report
  end type lcp_attempt_t

contains

  !> lcp=auto's methods for a load step, in the order they are tried
  !> (module header).
  !>   friction (in)  the step has tangential rows
  !>   n        (in)  its normal rows
  !>   omega    (in)  the deck's PGS relaxation
  !>   methods  (out) the methods, in order
  !>   omegas   (out) the PGS relaxation of each
  subroutine auto_order(friction, n, omega, methods, omegas)
    logical, intent(in) :: friction
    integer, intent(in) :: n
    real(dp), intent(in) :: omega
    character(len=5), allocatable, intent(out) :: methods(:)
    real(dp), allocatable, intent(out) :: omegas(:)
    if (friction) then
      call friction_order('pdas', omega, methods, omegas)
    else if (n <= lemke_max_rows) then
      methods = [character(len=5) :: 'lemke', 'pdas', 'pgs']
      omegas = [omega, omega, omega]
    else
      methods = [character(len=5) :: 'pdas', 'lemke', 'pgs']
      omegas = [omega, omega, omega]
    end if
  end subroutine auto_order

  !> The friction methods from a first one: then the others, PGS at omega
  !> and at fallback_omega (the second left out when omega is no larger: the
  !> same relaxation twice over would fail twice over), the fixed point on
  !> the Tresca threshold last.
  !>   first  (in)  'lemke', 'pdas', 'pgs' or 'fixpt'
  subroutine friction_order(first, omega, methods, omegas)
    character(len=*), intent(in) :: first
    real(dp), intent(in) :: omega
    character(len=5), allocatable, intent(out) :: methods(:)
    real(dp), allocatable, intent(out) :: omegas(:)
    character(len=5) :: order(5)
    real(dp) :: relax(5), low
    integer :: k, n
    low = min(omega, fallback_omega)
    select case (first)
    case ('lemke')
      order = [character(len=5) :: 'lemke', 'pdas', 'pgs', 'pgs', 'fixpt']
      relax = [omega, omega, omega, low, omega]
    case ('pdas')
      order = [character(len=5) :: 'pdas', 'lemke', 'pgs', 'pgs', 'fixpt']
      relax = [omega, omega, omega, low, omega]
    case ('fixpt')
      order = [character(len=5) :: 'fixpt', 'pdas', 'lemke', 'pgs', 'pgs']
      relax = [omega, omega, omega, omega, low]
    case default
      order = [character(len=5) :: 'pgs', 'pgs', 'pdas', 'lemke', 'fixpt']
      relax = [omega, low, omega, omega, omega]
    end select
    allocate(methods(5), omegas(5))
    n = 0
    do k = 1, 5
      if (n > 0) then
        if (order(k) == 'pgs' .and. methods(n) == 'pgs' .and. omegas(n) == relax(k)) cycle
      end if
      n = n + 1
      methods(n) = order(k)
      omegas(n) = relax(k)
    end do
    methods = methods(1:n)
    omegas = omegas(1:n)
  end subroutine friction_order

  !> .true. when a failed report of method shows that the step has no
  !> solution (module header): without friction info 1 of any method; with
  !> friction info 1 from PGS (a zero normal row with a negative gap) or from
  !> Lemke on a Tresca problem.  Lemke's ray on a Coulomb problem with such a
  !> row goes on to the other methods; PGS finds the row at once.
  !>   friction (in) the step has tangential rows
  !>   tresca   (in) every friction row is Tresca's (no Coulomb coefficient)
  logical function proves_no_solution(friction, tresca, method, rep)
    logical, intent(in) :: friction, tresca
    character(len=*), intent(in) :: method
    type(lcp_report_t), intent(in) :: rep
    if (.not. friction) then
      proves_no_solution = rep%info == 1
    else
      proves_no_solution = rep%info == 1 .and. (method == 'pgs' .or. tresca)
    end if
  end function proves_no_solution

  !> One attempt more at the end of the list.  (Not attempts = [attempts,
  !> lcp_attempt_t(...)]: gfortran leaks the constructor's temporary of
  !> a type with allocatable components.)
  subroutine add_attempt(attempts, method, omega, rep)
    type(lcp_attempt_t), allocatable, intent(inout) :: attempts(:)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: omega
    type(lcp_report_t), intent(in) :: rep
    type(lcp_attempt_t), allocatable :: grown(:)
    integer :: n
    n = size(attempts)
    allocate(grown(n + 1))
    grown(1:n) = attempts
    grown(n + 1)%method = method
    grown(n + 1)%omega = omega
    grown(n + 1)%rep = rep
    call move_alloc(grown, attempts)
  end subroutine add_attempt

  !> One load step of contact with friction by an attempt of the order, its
  !> method and relaxation, as lcp_attempt_t names it (module header): 'pdas'
  !> friction_newton, 'fixpt' friction_fixed_point, 'lemke' and 'pgs'
  !> friction_lcp.
  !>   g, prob (in)    the problem, as in friction_lcp's solve_friction_lcp
  !>   method  (in)    'lemke', 'pdas', 'pgs' or 'fixpt'
  !>   omega   (in)    the attempt's PGS relaxation, in place of opts%omega
  !>   opts    (in)    tol, maxit (the method's own limit when 0)
  !>   lam     (inout) the start of the iterative methods; the solution or
  !>                   the method's last iterate
  !>   rep     (out)   the method's report (info -3 for an unknown method)
  subroutine solve_friction_method(g, prob, method, omega, opts, lam, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: omega
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: lam(:)
    type(lcp_report_t), intent(out) :: rep
    type(lcp_options_t) :: o
    o = opts
    o%omega = omega
    select case (method)
    case ('pdas')
      call solve_friction_newton(g, prob, o, lam, rep)
    case ('fixpt')
      call solve_friction_fixed_point(g, prob, o, lam, rep)
    case default
      call solve_friction_lcp(g, prob, method, o, lam, rep)
    end select
  end subroutine solve_friction_method

  !> The name of a method in a log line: 'Lemke', 'PDAS (semismooth
  !> Newton)', 'PGS (omega 0.3)', 'fixed point on the Tresca threshold'.
  !>   method (in) 'lemke', 'pdas', 'pgs' or 'fixpt'
  !>   omega  (in) its PGS relaxation
  function method_label(method, omega) result(t)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: omega
    character(len=:), allocatable :: t
    select case (method)
    case ('pdas')
      t = 'PDAS (semismooth Newton)'
    case ('pgs')
      t = 'PGS (omega ' // format_number(omega) // ')'
    case ('fixpt')
      t = 'fixed point on the Tresca threshold'
    case default
      t = 'Lemke'
    end select
  end function method_label

  !> One load step by the first method, then the others (module header).
  !>   g, prob (in)    the problem, as in friction_lcp's solve_friction_lcp
  !>   first   (in)    'lemke', 'pdas', 'pgs' or 'fixpt': the method tried first
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
    type(lcp_attempt_t), allocatable, intent(out) :: attempts(:)
    character(len=5), allocatable :: methods(:)
    real(dp), allocatable :: omegas(:), lam0(:)
    character(len=:), allocatable :: failures
    integer :: k

    allocate(attempts(0))
    call check_friction_problem(g, prob, rep)
    if (rep%info < 0) return
    call friction_order(first, opts%omega, methods, omegas)
    lam0 = lam
    do k = 1, size(methods)
      lam = lam0
      call solve_friction_method(g, prob, trim(methods(k)), omegas(k), opts, lam, rep)
      call add_attempt(attempts, trim(methods(k)), omegas(k), rep)
      if (rep%info <= 0 .or. proves_no_solution(.true., all(prob%cmu == 0.0_dp), trim(methods(k)), rep)) exit
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

end module lcp_auto
