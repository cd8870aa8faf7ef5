!> friction_modes: one load step with the rigid-mode amplitudes as unknowns,
!> on a block touching a flat at two slave nodes x = -1, +1 with unit
!> compliance (G = I, q = 0) and the block's three modes held by contact:
!> tx moves the two tangential rows, ty the two normal rows, the rotation
!> the normal rows with levers -1, +1.  The load along the modes is
!> e = (Q, N, M), so H'z = e reads tau1 + tau2 = Q, lambda1 + lambda2 = N,
!> lambda2 - lambda1 = M.  Closed forms:
!>   - Coulomb mu = 0.5, e = (0.3, 2, 0.4): lambda = (0.8, 1.2), both nodes
!>     stick with tau = (0.15, 0.15) (ds = alpha_x - tau = 0), and the gaps
!>     closed give alpha = (0.15, 1.0, 0.2);
!>   - Q = 1.5 > mu N = 1: no equilibrium (info 5), cause 'friction', the
!>     unbalanced load along tx only, the capacity mu N = 1 (N = 2 fixed by
!>     the equilibrium along ty);
!>   - N = -1 (the load pulls the block off): no equilibrium, cause 'contact';
!>   - Tresca bound 0.5 per node: Q = 0.8 sticks with tau = (0.4, 0.4),
!>     Q = 1.2 has no equilibrium (cause 'friction', capacity 2 x 0.5 = 1).
!> A press fit (test_press_fit): two slave nodes pressed by an interference,
!> qn = (-0.4, -0.6), the block's only mode a translation along the contact
!> (H = (0, 0, 1, 1)': no normal row moves), Coulomb mu = 0.2, G = [I cI; cI
!> I] (c couples each node's slip to its gap).  The normal forces grow
!> without bound in no balance: the fit presses against itself.  With every
!> node slipping (tau = mu lambda) its gaps close at lambda = -qn / (1 + c
!> mu), so the capacity is mu N = mu / (1 + c mu), N = sum lambda; a push
!> P = 1.05 mu N has no equilibrium (capacity mu N, the unbalanced load
!> P - mu N), P = 0.95 mu N is solved; c = 0 and c = 0.5.
!> Every solved case is also checked against its own conditions by
!> friction_lcp's residual with q - H alpha, and H'z = e to round-off.
program test_friction_modes
  use kinds, only: dp
  use lcp_solvers, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: friction_problem_t, friction_problem, friction_residual
  use friction_modes, only: solve_friction_floating, no_equilibrium
  use testing, only: check, check_small, finish_tests, unit_roundoff
  implicit none
  real(dp) :: g(4, 4), h(4, 3)
  integer :: i
  ! closed forms of a 4 x 4 problem with entries of order 1, solved exactly
  ! (active-set finish): 16 roundings (measured <= 0.25 eps)
  real(dp), parameter :: tol = 16 * unit_roundoff

  g = 0.0_dp
  do i = 1, 4
    g(i, i) = 1.0_dp
  end do
  h = 0.0_dp
  h(3:4, 1) = 1.0_dp                       ! tx: the tangential rows
  h(1:2, 2) = 1.0_dp                       ! ty: the normal rows
  h(1, 3) = -1.0_dp                        ! rotation: levers -1, +1
  h(2, 3) = 1.0_dp

  call solved('coulomb stick', [0.5_dp, 0.5_dp], [0.0_dp, 0.0_dp], [0.3_dp, 2.0_dp, 0.4_dp], &
              [0.8_dp, 1.2_dp, 0.15_dp, 0.15_dp], [0.15_dp, 1.0_dp, 0.2_dp])
  call refused('coulomb beyond mu N', [0.5_dp, 0.5_dp], [0.0_dp, 0.0_dp], [1.5_dp, 2.0_dp, 0.0_dp], 'friction')
  call refused('coulomb pulled off', [0.5_dp, 0.5_dp], [0.0_dp, 0.0_dp], [0.0_dp, -1.0_dp, 0.0_dp], 'contact')
  call solved('tresca stick', [0.0_dp, 0.0_dp], [0.5_dp, 0.5_dp], [0.8_dp, 2.0_dp, 0.0_dp], &
              [1.0_dp, 1.0_dp, 0.4_dp, 0.4_dp], [0.4_dp, 1.0_dp, 0.0_dp])
  call refused('tresca beyond the bound', [0.0_dp, 0.0_dp], [0.5_dp, 0.5_dp], [1.2_dp, 2.0_dp, 0.0_dp], 'friction')
  call check_capacity('coulomb beyond mu N', [0.5_dp, 0.5_dp], [0.0_dp, 0.0_dp], [1.5_dp, 2.0_dp, 0.0_dp], 1.0_dp)
  call check_capacity('tresca beyond the bound', [0.0_dp, 0.0_dp], [0.5_dp, 0.5_dp], [1.2_dp, 2.0_dp, 0.0_dp], 1.0_dp)
  call test_press_fit(0.0_dp, 'press fit')
  call test_press_fit(0.5_dp, 'press fit, coupled')
  call finish_tests()

contains

  !> The step with q = 0 and the load e (tol 1e-10).
  subroutine solve_case(cmu, bound, e, lam, alpha, rep, unbalanced, cause, capacity)
    real(dp), intent(in) :: cmu(2), bound(2), e(3)
    real(dp), intent(out) :: lam(4), alpha(3)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable, intent(out) :: unbalanced(:)
    character(len=:), allocatable, intent(out) :: cause
    real(dp), intent(out), optional :: capacity
    type(lcp_options_t) :: opts
    opts%tol = 1.0e-10_dp
    call solve_friction_floating(g, friction_problem([0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], [1, 2], cmu, bound), h, e, &
                                 opts, lam, alpha, rep, unbalanced, cause, capacity)
  end subroutine solve_case

  !> A step without equilibrium whose capacity along tx is cap_exact: the
  !> load along tx exceeds it by the unbalanced load.
  subroutine check_capacity(name, cmu, bound, e, cap_exact)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: cmu(2), bound(2), e(3), cap_exact
    type(lcp_report_t) :: rep
    real(dp) :: lam(4), alpha(3), cap
    real(dp), allocatable :: unbalanced(:)
    character(len=:), allocatable :: cause
    call solve_case(cmu, bound, e, lam, alpha, rep, unbalanced, cause, cap)
    call check(rep%info == no_equilibrium, name // ': no equilibrium (info 5)')
    call check_small(abs(cap - cap_exact) / cap_exact, tol, name // ': capacity along tx, closed form')
    call check_small(maxval(abs(unbalanced - [e(1) - cap_exact, 0.0_dp, 0.0_dp])) / e(1), tol, &
                     name // ': unbalanced load = the load along tx minus the capacity')
  end subroutine check_capacity

  !> The press fit of the module header at coupling c: its capacity mu N
  !> against the hand value, and the pushes on either side of it.
  subroutine test_press_fit(c, name)
    real(dp), intent(in) :: c
    character(len=*), intent(in) :: name
    real(dp), parameter :: mu = 0.2_dp, qn(2) = [-0.4_dp, -0.6_dp]
    real(dp) :: gf(4, 4), hf(4, 1), lam(4), alpha(1), cap, cap_exact
    real(dp), allocatable :: unbalanced(:)
    character(len=:), allocatable :: cause
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(friction_problem_t) :: prob
    integer :: i
    gf = 0.0_dp
    do i = 1, 4
      gf(i, i) = 1.0_dp
    end do
    gf(1, 3) = c
    gf(3, 1) = c
    gf(2, 4) = c
    gf(4, 2) = c
    hf(:, 1) = [0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp]
    prob = friction_problem(qn, [0.0_dp, 0.0_dp], [1, 2], [mu, mu], [0.0_dp, 0.0_dp])
    cap_exact = mu * sum(-qn) / (1.0_dp + c * mu)              ! mu N, N = sum lambda at full slip
    opts%tol = 1.0e-10_dp

    call solve_friction_floating(gf, prob, hf, [1.05_dp * cap_exact], opts, lam, alpha, rep, unbalanced, cause, cap)
    call check(rep%info == no_equilibrium .and. cause == 'friction', &
               name // ' P = 1.05 mu N: no equilibrium, cause friction')
    call check_small(abs(cap - cap_exact) / cap_exact, tol, name // ' P = 1.05 mu N: capacity = mu N')
    call check_small(abs(unbalanced(1) - 0.05_dp * cap_exact) / cap_exact, tol, &
                     name // ' P = 1.05 mu N: unbalanced load = P - mu N')

    call solve_friction_floating(gf, prob, hf, [0.95_dp * cap_exact], opts, lam, alpha, rep, unbalanced, cause, cap)
    call check(rep%info == 0, name // ' P = 0.95 mu N: solved')
    call check(cap == 0.0_dp .and. cause == '', name // ' P = 0.95 mu N: no capacity, no cause')
    call check_small(abs(lam(3) + lam(4) - 0.95_dp * cap_exact) / cap_exact, tol, &
                     name // ' P = 0.95 mu N: friction forces carry the push')
    call check_small(friction_residual(gf, friction_problem(qn - matmul(hf(1:2, :), alpha), &
                     -matmul(hf(3:4, :), alpha), [1, 2], [mu, mu], [0.0_dp, 0.0_dp]), lam), tol, &
                     name // ' P = 0.95 mu N: friction conditions with q - H alpha')
  end subroutine test_press_fit

  subroutine solved(name, cmu, bound, e, lam_exact, alpha_exact)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: cmu(2), bound(2), e(3), lam_exact(4), alpha_exact(3)
    type(lcp_report_t) :: rep
    real(dp) :: lam(4), alpha(3)
    real(dp), allocatable :: unbalanced(:)
    character(len=:), allocatable :: cause
    call solve_case(cmu, bound, e, lam, alpha, rep, unbalanced, cause)
    call check(rep%info == 0, name // ': solved (info 0)')
    call check_small(maxval(abs(lam - lam_exact)) / maxval(abs(lam_exact)), tol, name // ': forces, closed form')
    call check_small(maxval(abs(alpha - alpha_exact)) / maxval(abs(alpha_exact)), tol, &
                     name // ': mode amplitudes, closed form')
    call check_small(maxval(abs(matmul(transpose(h), lam) - e)) / maxval(abs(e)), tol, name // ': H''z = e')
    call check_small(friction_residual(g, friction_problem(-matmul(h(1:2, :), alpha), -matmul(h(3:4, :), alpha), [1, 2], &
                                                          cmu, bound), lam), tol, name // ': friction conditions with q - H alpha')
  end subroutine solved

  subroutine refused(name, cmu, bound, e, cause_exact)
    character(len=*), intent(in) :: name, cause_exact
    real(dp), intent(in) :: cmu(2), bound(2), e(3)
    type(lcp_report_t) :: rep
    real(dp) :: lam(4), alpha(3)
    real(dp), allocatable :: unbalanced(:)
    character(len=:), allocatable :: cause
    call solve_case(cmu, bound, e, lam, alpha, rep, unbalanced, cause)
    call check(rep%info == no_equilibrium, name // ': no equilibrium (info 5)')
    call check(cause == cause_exact, name // ': cause ' // cause_exact)
    if (cause_exact == 'friction') then
      call check(unbalanced(1) > 0.0_dp .and. maxval(abs(unbalanced(2:3))) <= tol * unbalanced(1), &
                 name // ': the unbalanced load is along tx (+x) only')
    else
      call check(unbalanced(2) < 0.0_dp, name // ': the unbalanced load pulls along -y')
    end if
  end subroutine refused

end program test_friction_modes
