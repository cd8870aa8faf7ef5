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
!>     unbalanced load along tx only;
!>   - N = -1 (the load pulls the block off): no equilibrium, cause 'contact';
!>   - Tresca bound 0.5 per node: Q = 0.8 sticks with tau = (0.4, 0.4),
!>     Q = 1.2 has no equilibrium (cause 'friction').
!> Every solved case is also checked against its own conditions by
!> friction_lcp's residual with q - H alpha, and H'z = e to round-off.
program test_friction_modes
  use kinds, only: dp
  use lcp_solvers, only: lcp_options_t, lcp_report_t
  use friction_lcp, only: friction_problem, friction_residual
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
  call finish_tests()

contains

  !> The step with q = 0 and the load e (tol 1e-10).
  subroutine solve_case(cmu, bound, e, lam, alpha, rep, unbalanced, cause)
    real(dp), intent(in) :: cmu(2), bound(2), e(3)
    real(dp), intent(out) :: lam(4), alpha(3)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable, intent(out) :: unbalanced(:)
    character(len=:), allocatable, intent(out) :: cause
    type(lcp_options_t) :: opts
    opts%tol = 1.0e-10_dp
    call solve_friction_floating(g, friction_problem([0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], [1, 2], cmu, bound), h, e, &
                                 opts, lam, alpha, rep, unbalanced, cause)
  end subroutine solve_case

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
