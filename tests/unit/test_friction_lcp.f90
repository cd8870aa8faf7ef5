!> Unit tests of friction_lcp (and lcp_solvers' solve_lcp_lemke_scaled): one
!> node against values computed by hand, Tresca (a strictly convex QP: Lemke
!> and PGS must agree) and Coulomb on random SPD Delassus matrices, checked by
!> an independent test of every contact condition written here (no scaling,
!> no call to the module's own residual), the frictionless limits mu = 0 and
!> nt = 0 against lcp_solvers, and the failures that must be reported.  The
!> primal-dual active set method of friction_newton on the same random
!> problems (Tresca: Lemke's unique answer; Coulomb: every condition), and
!> lcp_auto's order (a singular system hands the step to Lemke).  Its
!> globalisation and the fixed point on the Tresca threshold
!> (friction_fixed_point) on small problems whose full Newton steps come
!> back to a partition, with answers in closed form: the Coulomb and the
!> Tresca branch, the fixed point on Tresca and on Coulomb problems, where it
!> does not contract, and the same iterations when the units change.
program test_friction_lcp
  use kinds, only: dp, i8
  use errors, only: error_t
  use testing, only: check, check_close, check_small, finish_tests, urand, random_spd, tol_round, unit_roundoff
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_pgs, solve_lcp_lemke_scaled
  use friction_lcp, only: friction_problem_t, friction_problem, solve_friction_lcp, friction_residual, &
    friction_state, state_open, state_stick, state_slip
  use friction_newton, only: solve_friction_newton
  use friction_fixed_point, only: solve_friction_fixed_point
  use lcp_auto, only: lcp_attempt_t, solve_friction_auto, method_label
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none

  ! Tolerances, in the units of testing (tol_round: n eps scale).  G from
  ! random_spd has eigenvalues in [1e-3, 0.83] (its shift, and
  ! (1 + sqrt(1/3))^2 / 3 by Marchenko-Pastur): cond(G) <= cond_w.  Lemke
  ! ends on a direct solve, so its answer is good to round-off times cond(G)
  ! (tol_direct; measured <= 3 eps); PGS stops at a residual of opts%tol and
  ! is within cond(G) opts%tol (measured <= 9 opts%tol).
  real(dp), parameter :: cond_w = 1.0e3_dp
  real(dp), parameter :: tol_direct = 64 * cond_w * epsilon(1.0_dp)
  integer(i8) :: seed
  seed = 20240917_i8

  call test_lemke_scaled()
  call test_residual_hand_value()
  call test_one_node()
  call test_sign_convention()
  call test_tresca_random(5, 5, 'n5', .false.)
  call test_tresca_random(12, 12, 'n12 reversed trow', .true.)
  call test_tresca_random(12, 8, 'n12 nt8', .false.)
  call test_tresca_random(30, 30, 'n30', .false.)
  call test_coulomb_random(10, 0.2_dp, 'n10 coupled')
  call test_coulomb_random(25, 0.2_dp, 'n25 coupled')
  call test_coulomb_random(25, 0.0_dp, 'n25 decoupled')
  call test_pdas_random(12, 12, 1.0_dp, 0.0_dp, 'tresca n12')
  call test_pdas_random(30, 20, 1.0_dp, 0.0_dp, 'tresca n30 nt20')
  call test_pdas_random(25, 25, 0.2_dp, 0.3_dp, 'coulomb n25 mu 0.3')
  call test_pdas_random(25, 25, 0.2_dp, 0.8_dp, 'coulomb n25 mu 0.8')
  call test_pdas_random(25, 25, 0.0_dp, 0.8_dp, 'coulomb n25 decoupled mu 0.8')
  call test_auto_order()
  call test_newton_cycle_coulomb()
  call test_newton_cycle_tresca()
  call test_fixed_point_coulomb()
  call test_fixed_point_no_contraction()
  call test_zero_tangential_row()
  call test_frictionless_limits(15)
  call test_failures()
  call test_arguments()
  call finish_tests()

contains

  ! ---------------------------------------------------------------------------
  ! Helpers
  ! ---------------------------------------------------------------------------

  !> Random SPD G ((n+nt) x (n+nt)) whose normal-tangential blocks are scaled
  !> by t in [0, 1]: t G + (1 - t) blockdiag(Gnn, Gtt), still SPD.
  subroutine random_delassus(n, nt, t, state, g)
    integer, intent(in) :: n, nt
    real(dp), intent(in) :: t
    integer(i8), intent(inout) :: state
    real(dp), allocatable, intent(out) :: g(:, :)
    call random_spd(n + nt, state, g)
    g(1:n, n + 1:n + nt) = t * g(1:n, n + 1:n + nt)
    g(n + 1:n + nt, 1:n) = t * g(n + 1:n + nt, 1:n)
  end subroutine random_delassus

  subroutine random_vector(state, lo, hi, x)
    integer(i8), intent(inout) :: state
    real(dp), intent(in) :: lo, hi
    real(dp), intent(out) :: x(:)
    integer :: i
    do i = 1, size(x)
      x(i) = lo + (hi - lo) * urand(state)
    end do
  end subroutine random_vector

  !> Every condition of contact with friction, checked on the unscaled
  !> quantities with relative tolerance tol (gaps and slips relative to
  !> max |q|, forces relative to max(|lam|, bound)):
  !>   lambda >= 0, w >= 0, lambda_i w_i = 0 (one of them zero),
  !>   |tau_k| <= b_k, and for every k either ds_k = 0 (stick) or
  !>   tau_k = b_k sign(ds_k) (slip against the friction force).
  subroutine check_conditions(g, prob, lam, tol, name)
    real(dp), intent(in) :: g(:, :), lam(:), tol
    type(friction_problem_t), intent(in) :: prob
    character(len=*), intent(in) :: name
    real(dp), allocatable :: w(:), ds(:), b(:), lambda(:), tau(:)
    real(dp) :: gscale, fscale, worst
    integer :: n, nt, k

    n = size(prob%qn)
    nt = size(prob%qt)
    call check(all(ieee_is_finite(lam)), name // ': lam finite')
    allocate(lambda(n), tau(nt))
    lambda(:) = lam(1:n)
    tau(:) = lam(n + 1:n + nt)
    w = prob%qn + matmul(g(1:n, :), lam)
    ds = -(prob%qt + matmul(g(n + 1:n + nt, :), lam))
    b = prob%bound + prob%cmu * lambda(prob%trow)
    gscale = max(tiny(1.0_dp), maxval(abs(prob%qn)))
    if (nt > 0) gscale = max(gscale, maxval(abs(prob%qt)))
    fscale = max(tiny(1.0_dp), maxval(abs(lam)))
    if (nt > 0) fscale = max(fscale, maxval(prob%bound))
    call check_small(max(0.0_dp, -minval(lambda)) / fscale, tol, name // ': lambda >= 0')
    call check_small(max(0.0_dp, -minval(w)) / gscale, tol, name // ': w >= 0')
    call check_small(maxval(min(abs(lambda) / fscale, abs(w) / gscale)), tol, name // ': lambda_i w_i = 0')
    if (nt == 0) return
    call check_small(max(0.0_dp, maxval(abs(tau) - b)) / fscale, tol, name // ': |tau| <= b')
    worst = 0.0_dp
    do k = 1, nt
      worst = max(worst, min(abs(ds(k)) / gscale, abs(tau(k) - b(k) * sign(1.0_dp, ds(k))) / fscale))
    end do
    call check_small(worst, tol, name // ': stick (ds = 0) or slip (tau = b sign(ds))')
  end subroutine check_conditions

  real(dp) function rel_diff(a, b)
    real(dp), intent(in) :: a(:), b(:)
    rel_diff = maxval(abs(a - b)) / max(tiny(1.0_dp), maxval(abs(b)))
  end function rel_diff

  function identity_rows(n) result(t)
    integer, intent(in) :: n
    integer, allocatable :: t(:)
    integer :: k
    t = [(k, k = 1, n)]
  end function identity_rows

  ! ---------------------------------------------------------------------------
  ! Tests
  ! ---------------------------------------------------------------------------

  !> solve_lcp_lemke_scaled: with d = 1/sqrt(diag W) on an SPD W it is
  !> solve_lcp_lemke (bit for bit); it keeps zero-diagonal rows that
  !> solve_lcp_lemke drops; ray termination; argument checks.
  subroutine test_lemke_scaled()
    real(dp), allocatable :: w(:, :), q(:), z(:), zref(:), d(:)
    real(dp) :: m2(2, 2), z2(2), w2(2)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep, ref
    integer :: i, n

    n = 20
    call random_spd(n, seed, w)
    allocate(q(n), z(n), zref(n), d(n))
    call random_vector(seed, -1.0_dp, 1.0_dp, q)
    d = [(1.0_dp / sqrt(w(i, i)), i = 1, n)]
    call solve_lcp_lemke(w, q, zref, opts, ref)
    call solve_lcp_lemke_scaled(w, q, d, z, opts, rep)
    call check(rep%info == 0 .and. ref%info == 0, 'lemke scaled n20: info 0')
    call check(all(z == zref), 'lemke scaled n20: z identical to solve_lcp_lemke')
    call check(rep%iterations == ref%iterations .and. rep%iterations > 0, &
      'lemke scaled n20: same pivots as solve_lcp_lemke')
    call check(rep%residual == ref%residual, 'lemke scaled n20: same residual')

    ! M = [0 1; -1 0] (skew, zero diagonal), q = [-1, 1]: w1 = z2 - 1,
    ! w2 = 1 - z1; z = (0, 1) or (1, 1) solve it.  solve_lcp_lemke drops both
    ! rows as redundant and reports row 1 infeasible.
    m2 = reshape([0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp], [2, 2])
    call solve_lcp_lemke(m2, [-1.0_dp, 1.0_dp], z2, opts, rep)
    call check(rep%info == 1, 'lemke scaled zero diagonal: solve_lcp_lemke drops the rows (info 1)')
    call solve_lcp_lemke_scaled(m2, [-1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], z2, opts, rep)
    call check(rep%info == 0, 'lemke scaled zero diagonal: info 0')
    w2 = [-1.0_dp, 1.0_dp] + matmul(m2, z2)
    call check_close(z2(2), 1.0_dp, tol_round(16), 'lemke scaled zero diagonal: z2 = 1')
    call check(all(z2 >= 0.0_dp) .and. all(w2 >= -tol_round(32)) .and. maxval(abs(z2 * w2)) <= tol_round(32), &
      'lemke scaled zero diagonal: complementary')

    ! [1 -1; -1 1], q = -1: w1 + w2 = -2 for every z (PSD, infeasible).
    m2 = reshape([1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp], [2, 2])
    call solve_lcp_lemke_scaled(m2, [-1.0_dp, -1.0_dp], [1.0_dp, 1.0_dp], z2, opts, rep)
    call check(rep%info == 1, 'lemke scaled infeasible: info 1')
    call check(index(rep%message, 'ray termination') > 0, 'lemke scaled infeasible: ray termination message')
    call check(all(ieee_is_finite(z2)), 'lemke scaled infeasible: z finite')

    call solve_lcp_lemke_scaled(m2, [1.0_dp, 1.0_dp], [1.0_dp, 0.0_dp], z2, opts, rep)
    call check(rep%info == -3, 'lemke scaled arguments: d = 0 -> info -3')
    call solve_lcp_lemke_scaled(m2, [1.0_dp, 1.0_dp], [1.0_dp], z2, opts, rep)
    call check(rep%info == -3, 'lemke scaled arguments: d size -> info -3')
    call solve_lcp_lemke_scaled(m2, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -4, 'lemke scaled arguments: z size -> info -4')
    call solve_lcp_lemke_scaled(m2, [1.0_dp, 1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp, 1.0_dp], z2, opts, rep)
    call check(rep%info == -1, 'lemke scaled arguments: M size -> info -1')
  end subroutine test_lemke_scaled

  !> G = I, qn = -1, qt = 0, mu = 1/2.  lam = [1, 1/2]: w = 0, ds = -1/2,
  !> b = 1/2, tangential residual |1/2 - clamp(1/2 - 1/2, -1/2, 1/2)| = 1/2,
  !> qscale = 1: r = 1/2.  lam = [1, 0] is the solution: r = 0.
  subroutine test_residual_hand_value()
    real(dp) :: g(2, 2)
    g = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    call check_close(friction_residual(g, friction_problem([-1.0_dp], [0.0_dp], [1], [0.5_dp], [0.0_dp]), [1.0_dp, 0.5_dp]), &
      0.5_dp, tol_round(4), 'residual: hand value 1/2')
    call check_small(friction_residual(g, friction_problem([-1.0_dp], [0.0_dp], [1], [0.5_dp], [0.0_dp]), [1.0_dp, 0.0_dp]), &
      0.0_dp, 'residual: 0 at the solution')
    call check(friction_residual(g, friction_problem([-1.0_dp], [0.0_dp], [2], [0.5_dp], [0.0_dp]), [1.0_dp, 0.0_dp]) == &
      huge(1.0_dp), 'residual: trow out of range -> huge')
  end subroutine test_residual_hand_value

  !> One node, G = [2 1/2; 1/2 1], qn = -2, qt = -1/10, both methods.
  !> Stick: G [lambda; tau] = [2; 1/10] gives lambda = 39/35, tau = -16/35,
  !>   admissible when |tau| <= mu lambda, i.e. mu >= 16/39: mu = 0.8 sticks.
  !> Slip (mu = 0.2): tau = -mu lambda, 2 lambda + tau/2 = 2 gives
  !>   lambda = 20/19, tau = -4/19, ds = -(qt + lambda/2 + tau) = -4.1/19 < 0.
  !> Open: qn = 1 gives lambda = tau = 0 (b = 0) although ds = 1/10 /= 0.
  !> Tresca bound 0.3: tau = -0.3, lambda = (2 + 0.15)/2 = 1.075,
  !>   ds = -(-0.1 + 0.5375 - 0.3) = -0.1375 < 0; bound 0.5 sticks as above.
  subroutine test_one_node()
    real(dp) :: g(2, 2)
    integer :: method
    character(len=5) :: tag
    g = reshape([2.0_dp, 0.5_dp, 0.5_dp, 1.0_dp], [2, 2])
    do method = 1, 2
      tag = merge('lemke', 'pgs  ', method == 1)
      call one_case(g, trim(tag), -2.0_dp, -0.1_dp, 0.8_dp, 0.0_dp, 39.0_dp / 35.0_dp, -16.0_dp / 35.0_dp, &
        state_stick, 'coulomb mu 0.8 stick')
      call one_case(g, trim(tag), -2.0_dp, -0.1_dp, 0.2_dp, 0.0_dp, 20.0_dp / 19.0_dp, -4.0_dp / 19.0_dp, &
        state_slip, 'coulomb mu 0.2 slip')
      call one_case(g, trim(tag), 1.0_dp, -0.1_dp, 0.2_dp, 0.0_dp, 0.0_dp, 0.0_dp, state_open, 'coulomb open')
      call one_case(g, trim(tag), -2.0_dp, -0.1_dp, 0.0_dp, 0.3_dp, 1.075_dp, -0.3_dp, state_slip, 'tresca 0.3 slip')
      call one_case(g, trim(tag), -2.0_dp, -0.1_dp, 0.0_dp, 0.5_dp, 39.0_dp / 35.0_dp, -16.0_dp / 35.0_dp, &
        state_stick, 'tresca 0.5 stick')
    end do
  end subroutine test_one_node

  !> One single-node case of test_one_node, solved and checked.
  subroutine one_case(g, method_name, qn, qt, mu, bnd, lambda, tau, st, name)
    real(dp), intent(in) :: g(:, :)
    character(len=*), intent(in) :: method_name, name
    real(dp), intent(in) :: qn, qt, mu, bnd, lambda, tau
    integer, intent(in) :: st
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    real(dp) :: lam(2)
    integer :: state(1)
    type(error_t), allocatable :: err
    character(len=:), allocatable :: full
    type(friction_problem_t) :: prob
    full = 'one node ' // method_name // ' ' // name
    opts%tol = 1.0e-14_dp
    prob = friction_problem([qn], [qt], [1], [mu], [bnd])
    lam = [5.0_dp, 1.0_dp]
    call solve_friction_lcp(g, prob, method_name, opts, lam, rep)
    call check(rep%info == 0, full // ': info 0')
    call check_close(lam(1), lambda, tol_round(512), full // ': lambda by hand', floor=1.0_dp)
    call check_close(lam(2), tau, tol_round(256), full // ': tau by hand', floor=1.0_dp)
    call friction_state(g, prob, lam, state, err)
    call check(.not. allocated(err) .and. state(1) == st, full // ': state')
    call check_conditions(g, prob, lam, tol_round(512), full)
  end subroutine one_case

  !> G = diag(2, 1) (decoupled), qn = -2 so lambda = 1, mu = 0.3, b = 0.3.
  !> qt = 1: sticking needs tau = -1, too large: slip with tau = -0.3 and
  !> ds = -(1 - 0.3) = -0.7; qt = -1: tau = +0.3 with ds = +0.7 (tau > 0 goes
  !> with ds > 0); qt = 0.2: stick, tau = -0.2, ds = 0.
  subroutine test_sign_convention()
    real(dp) :: g(2, 2), lam(2)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: method
    character(len=5) :: tag
    g = reshape([2.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    opts%tol = 1.0e-14_dp
    do method = 1, 2
      tag = merge('lemke', 'pgs  ', method == 1)
      lam = 0.0_dp
      call solve_friction_lcp(g, friction_problem([-2.0_dp], [1.0_dp], [1], [0.3_dp], [0.0_dp]), trim(tag), opts, lam, rep)
      call check(rep%info == 0 .and. abs(lam(1) - 1.0_dp) <= tol_round(256) .and. abs(lam(2) + 0.3_dp) <= tol_round(256), &
        'sign ' // trim(tag) // ': qt = 1 slips with tau = -0.3 (ds = -0.7)')
      lam = 0.0_dp
      call solve_friction_lcp(g, friction_problem([-2.0_dp], [-1.0_dp], [1], [0.3_dp], [0.0_dp]), trim(tag), opts, lam, rep)
      call check(rep%info == 0 .and. abs(lam(1) - 1.0_dp) <= tol_round(256) .and. abs(lam(2) - 0.3_dp) <= tol_round(256), &
        'sign ' // trim(tag) // ': qt = -1 slips with tau = +0.3 (ds = +0.7)')
      lam = 0.0_dp
      call solve_friction_lcp(g, friction_problem([-2.0_dp], [0.2_dp], [1], [0.3_dp], [0.0_dp]), trim(tag), opts, lam, rep)
      call check(rep%info == 0 .and. abs(lam(1) - 1.0_dp) <= tol_round(256) .and. abs(lam(2) + 0.2_dp) <= tol_round(256), &
        'sign ' // trim(tag) // ': qt = 0.2 sticks with tau = -0.2 (ds = 0)')
    end do
  end subroutine test_sign_convention

  !> Tresca on random SPD G with full normal-tangential coupling: the QP is
  !> strictly convex, so Lemke and PGS (also over-relaxed, also warm-started)
  !> must agree; every condition holds.
  subroutine test_tresca_random(n, nt, tag, reversed)
    integer, intent(in) :: n, nt
    character(len=*), intent(in) :: tag
    logical, intent(in) :: reversed
    real(dp), allocatable :: g(:, :), qn(:), qt(:), cmu(:), bound(:), lam_l(:), lam_p(:)
    integer, allocatable :: trow(:)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: k
    character(len=:), allocatable :: name

    name = 'tresca ' // tag
    call random_delassus(n, nt, 1.0_dp, seed, g)
    allocate(qn(n), qt(nt), bound(nt), lam_l(n + nt), lam_p(n + nt))
    call random_vector(seed, -1.0_dp, 1.0_dp, qn)
    call random_vector(seed, -1.0_dp, 1.0_dp, qt)
    call random_vector(seed, 0.05_dp, 0.5_dp, bound)
    cmu = [(0.0_dp, k = 1, nt)]
    if (reversed) then
      trow = [(n + 1 - k, k = 1, nt)]
    else
      trow = [(k + (n - nt) / 2, k = 1, nt)]
    end if
    prob = friction_problem(qn, qt, trow, cmu, bound)

    call solve_friction_lcp(g, prob, 'lemke', opts, lam_l, rep)
    call check(rep%info == 0, name // ' lemke: info 0')
    call check(rep%iterations > 0, name // ' lemke: pivots counted')
    call check_small(rep%residual, opts%tol, name // ' lemke: reported residual <= tol')
    ! the same residual computed twice: equal to round-off, relative, or
    ! absolute (floor eps) when the residual itself is at round-off
    call check_close(rep%residual, friction_residual(g, prob, lam_l), tol_round(16), &
      name // ' lemke: reported residual is that of lam', floor=unit_roundoff)
    call check_conditions(g, prob, lam_l, tol_direct, name // ' lemke')

    opts%tol = 1.0e-13_dp
    lam_p = 0.0_dp
    call solve_friction_lcp(g, prob, 'pgs', opts, lam_p, rep)
    call check(rep%info == 0, name // ' pgs: info 0')
    call check(rep%iterations > 0, name // ' pgs: sweeps counted')
    call check_conditions(g, prob, lam_p, cond_w * opts%tol, name // ' pgs')
    call check_small(rel_diff(lam_p, lam_l), cond_w * opts%tol, name // ': lemke and pgs agree')

    lam_p = 0.0_dp
    opts%omega = 1.3_dp
    call solve_friction_lcp(g, prob, 'pgs', opts, lam_p, rep)
    call check(rep%info == 0, name // ' pgs omega 1.3: info 0')
    call check_small(rel_diff(lam_p, lam_l), cond_w * opts%tol, name // ' pgs omega 1.3: agrees')

    ! Warm start from the solution (the previous load step): at most one sweep.
    lam_p = lam_l
    opts%omega = 1.0_dp
    opts%tol = 1.0e-10_dp
    call solve_friction_lcp(g, prob, 'pgs', opts, lam_p, rep)
    call check(rep%info == 0 .and. rep%iterations <= 1, name // ' pgs warm start: converged at once')
  end subroutine test_tresca_random

  !> Coulomb with mu = 0.1, 0.3, 0.8 on random SPD G whose normal-tangential
  !> coupling is scaled by t: Lemke solves and satisfies every condition; PGS
  !> too when it converges; the states are consistent with the forces.  With
  !> t = 0 the solution is unique (lambda from the frictionless LCP, then a
  !> Tresca problem with b = mu lambda): the methods agree, and lambda is
  !> solve_lcp_lemke's.
  subroutine test_coulomb_random(n, t, tag)
    integer, intent(in) :: n
    real(dp), intent(in) :: t
    character(len=*), intent(in) :: tag
    real(dp), parameter :: mus(3) = [0.1_dp, 0.3_dp, 0.8_dp]
    real(dp), allocatable :: g(:, :), gnn(:, :), qn(:), qt(:), cmu(:), bound(:), lam_l(:), lam_p(:), zref(:), b(:)
    integer, allocatable :: trow(:), state(:)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: imu, k
    character(len=:), allocatable :: name
    character(len=8) :: mtxt
    logical :: consistent
    type(error_t), allocatable :: err

    call random_delassus(n, n, t, seed, g)
    allocate(qn(n), qt(n), lam_l(2 * n), lam_p(2 * n), state(n))
    call random_vector(seed, -1.0_dp, 1.0_dp, qn)
    call random_vector(seed, -1.0_dp, 1.0_dp, qt)
    trow = identity_rows(n)
    bound = [(0.0_dp, k = 1, n)]
    do imu = 1, size(mus)
      write(mtxt, '(f3.1)') mus(imu)
      name = 'coulomb ' // tag // ' mu ' // trim(mtxt)
      cmu = [(mus(imu), k = 1, n)]
      prob = friction_problem(qn, qt, trow, cmu, bound)
      opts = lcp_options_t()
      call solve_friction_lcp(g, prob, 'lemke', opts, lam_l, rep)
      call check(rep%info == 0, name // ' lemke: info 0')
      call check(rep%iterations > 0, name // ' lemke: pivots counted')
      call check_conditions(g, prob, lam_l, tol_direct, name // ' lemke')

      ! States: slip has |tau| = b, stick |tau| <= b, open lambda = 0.
      call friction_state(g, prob, lam_l, state, err)
      call check(.not. allocated(err), name // ' lemke: states measured')
      b = cmu * lam_l(1:n)
      consistent = .true.
      do k = 1, n
        select case (state(k))
        case (state_open)
          consistent = consistent .and. lam_l(k) <= tol_direct * maxval(lam_l)
        case (state_stick)
          consistent = consistent .and. abs(lam_l(n + k)) <= b(k) * (1.0_dp + tol_direct) + tol_round(32)
        case (state_slip)
          consistent = consistent .and. abs(abs(lam_l(n + k)) - b(k)) <= tol_direct * maxval(lam_l)
        case default
          consistent = .false.
        end select
      end do
      call check(consistent, name // ' lemke: states consistent with the forces')
      call check(count(state == state_slip) > 0 .and. count(state == state_open) > 0, &
        name // ': open and slipping nodes present')

      opts%tol = 1.0e-12_dp
      lam_p = 0.0_dp
      call solve_friction_lcp(g, prob, 'pgs', opts, lam_p, rep)
      call check(rep%info >= 0 .and. rep%info /= 1 .and. all(ieee_is_finite(lam_p)), &
        name // ' pgs: converged or reported, lam finite')
      if (rep%info == 0) then
        call check_conditions(g, prob, lam_p, cond_w * opts%tol, name // ' pgs')
      else
        call check(rep%residual > opts%tol, name // ' pgs: not converged and residual > tol')
      end if
      if (t == 0.0_dp) then
        call check(rep%info == 0, name // ' pgs: info 0 (decoupled)')
        call check_small(rel_diff(lam_p, lam_l), cond_w * opts%tol, name // ': lemke and pgs agree (unique)')
        allocate(zref(n))
        gnn = g(1:n, 1:n)
        call solve_lcp_lemke(gnn, qn, zref, lcp_options_t(), rep)
        call check_small(rel_diff(lam_l(1:n), zref), tol_direct, name // ': lambda is the frictionless one')
        deallocate(zref)
      end if
    end do
  end subroutine test_coulomb_random

  !> friction_newton on a random problem (coupling t, Coulomb mu, or Tresca
  !> when mu = 0): it solves it (info 0, every condition of check_conditions
  !> to round-off times cond(G)), in a few steps; with Tresca or t = 0 the
  !> answer is unique and equals Lemke's; from the solution it stops after
  !> one step; with maxit = 1 from zero it reports the step limit (info 2)
  !> without claiming that there is no solution.
  subroutine test_pdas_random(n, nt, t, mu, tag)
    integer, intent(in) :: n, nt
    real(dp), intent(in) :: t, mu
    character(len=*), intent(in) :: tag
    real(dp), allocatable :: g(:, :), qn(:), qt(:), cmu(:), bound(:), lam(:), lam_l(:)
    integer, allocatable :: trow(:)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: k
    character(len=:), allocatable :: name

    name = 'pdas ' // tag
    call random_delassus(n, nt, t, seed, g)
    allocate(qn(n), qt(nt), bound(nt), lam(n + nt), lam_l(n + nt))
    call random_vector(seed, -1.0_dp, 1.0_dp, qn)
    call random_vector(seed, -1.0_dp, 1.0_dp, qt)
    if (mu > 0.0_dp) then
      bound = 0.0_dp
      cmu = [(mu, k = 1, nt)]
    else
      call random_vector(seed, 0.05_dp, 0.5_dp, bound)
      cmu = [(0.0_dp, k = 1, nt)]
    end if
    trow = [(k + (n - nt) / 2, k = 1, nt)]
    prob = friction_problem(qn, qt, trow, cmu, bound)

    lam = 0.0_dp
    call solve_friction_newton(g, prob, opts, lam, rep)
    call check(rep%info == 0, name // ': info 0')
    call check(rep%iterations > 0 .and. rep%iterations <= 20, name // ': a few Newton steps')
    call check_small(rep%residual, opts%tol, name // ': reported residual <= tol')
    call check_close(rep%residual, friction_residual(g, prob, lam), tol_round(16), &
      name // ': reported residual is that of lam', floor=unit_roundoff)
    call check_conditions(g, prob, lam, tol_direct, name)
    if (mu == 0.0_dp .or. t == 0.0_dp) then
      call solve_friction_lcp(g, prob, 'lemke', opts, lam_l, rep)
      call check_small(rel_diff(lam, lam_l), tol_direct, name // ': = Lemke (unique)')
    end if

    ! warm start from the solution: the partition repeats after one step
    call solve_friction_newton(g, prob, opts, lam, rep)
    call check(rep%info == 0 .and. rep%iterations == 1, name // ' warm start: one step')

    opts%maxit = 1
    lam = 0.0_dp
    call solve_friction_newton(g, prob, opts, lam, rep)
    call check(rep%info == 2 .and. trim(rep%stopped) == 'step limit' .and. all(ieee_is_finite(lam)) .and. &
      index(rep%message, 'does not show that there is none') > 0, name // ' maxit 1: step limit, no claim')
  end subroutine test_pdas_random

  !> lcp_auto: first 'pdas' on a problem with two identical normal rows
  !> (G singular: two pairs over the same node) meets a singular system and
  !> hands the step to Lemke, which solves it; first 'pgs' with maxit = 1
  !> fails PGS at omega 1 and 0.3, PDAS and Lemke in that order, the message
  !> naming each; a zero normal row with a negative gap ends the sequence at
  !> once (a proof); an explicit omega of 0.3 is not run twice.
  subroutine test_auto_order()
    real(dp), allocatable :: g(:, :), g2(:, :), lam(:), lam_l(:)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(lcp_attempt_t), allocatable :: att(:)
    integer :: i, j, n, nt, m

    ! rows 1 and 2 the same normal row (a duplicate), each with its tangential row
    n = 3
    nt = 3
    m = n + nt
    call random_spd(m, seed, g2)
    allocate(g(m, m))
    g = g2
    g(2, :) = g(1, :)
    g(:, 2) = g(:, 1)
    g(5, :) = g(4, :)
    g(:, 5) = g(:, 4)
    prob = friction_problem([-0.5_dp, -0.5_dp, 0.3_dp], [0.2_dp, 0.2_dp, -0.1_dp], [1, 2, 3], &
                            [0.3_dp, 0.3_dp, 0.3_dp], [0.0_dp, 0.0_dp, 0.0_dp])
    allocate(lam(m), lam_l(m))
    lam = 0.0_dp
    call solve_friction_auto(g, prob, 'pdas', opts, lam, rep, att)
    call check(size(att) == 2, 'auto singular: two attempts')
    if (size(att) == 2) then
      call check(att(1)%method == 'pdas' .and. att(1)%rep%info == 3 .and. trim(att(1)%rep%stopped) == 'singular', &
        'auto singular: pdas met a singular system')
      call check(att(2)%method == 'lemke' .and. att(2)%rep%info == 0 .and. rep%info == 0, &
        'auto singular: Lemke solved the step')
    end if
    call check_conditions(g, prob, lam, tol_direct, 'auto singular')

    ! every method fails: the order and the message
    call random_spd(m, seed, g)
    prob = friction_problem([-0.5_dp, -0.4_dp, -0.3_dp], [0.2_dp, -0.3_dp, 0.1_dp], [1, 2, 3], &
                            [0.5_dp, 0.5_dp, 0.5_dp], [0.0_dp, 0.0_dp, 0.0_dp])
    opts%maxit = 1
    lam = 0.0_dp
    call solve_friction_auto(g, prob, 'pgs', opts, lam, rep, att)
    call check(size(att) == 5, 'auto maxit 1: five attempts')
    if (size(att) == 5) then
      call check(att(1)%method == 'pgs' .and. att(1)%omega == 1.0_dp .and. att(2)%method == 'pgs' .and. &
        att(2)%omega == 0.3_dp .and. att(3)%method == 'pdas' .and. att(4)%method == 'lemke' .and. &
        att(5)%method == 'fixpt', 'auto maxit 1: pgs (1), pgs (0.3), pdas, lemke, fixpt')
      call check(all([(att(i)%rep%info > 0, i = 1, 5)]) .and. rep%info > 0, 'auto maxit 1: every method failed')
      i = index(rep%message, 'friction PGS: sweep limit')
      j = index(rep%message, 'then friction Lemke')
      call check(i == 1 .and. j > i .and. index(rep%message, 'then friction Newton') > i .and. &
        index(rep%message, 'then friction fixed point') > j, 'auto maxit 1: the message names each failure in turn')
    end if
    call check(method_label('fixpt', 1.0_dp) == 'fixed point on the Tresca threshold' .and. &
      method_label('pgs', 0.3_dp) == 'PGS (omega 0.3)', 'auto: the methods'' names in a log line')
    opts%omega = 0.3_dp
    call solve_friction_auto(g, prob, 'pdas', opts, lam, rep, att)
    call check(size(att) == 4, 'auto omega 0.3: PGS at 0.3 run once')
    if (size(att) == 4) call check(att(3)%method == 'pgs' .and. att(4)%method == 'fixpt', &
      'auto omega 0.3: pdas, lemke, pgs (0.3), fixpt')

    ! a zero normal row with a negative gap: no solution, shown at once
    g = g2
    g(1, :) = 0.0_dp
    g(:, 1) = 0.0_dp
    opts = lcp_options_t()
    call solve_friction_auto(g, friction_problem([-0.5_dp, -0.4_dp, -0.3_dp], [0.2_dp, -0.3_dp, 0.1_dp], [1, 2, 3], &
      [0.0_dp, 0.0_dp, 0.0_dp], [0.1_dp, 0.1_dp, 0.1_dp]), 'pgs', opts, lam, rep, att)
    call check(size(att) == 1 .and. rep%info == 1, 'auto zero row: PGS shows there is no solution, nothing more tried')
  end subroutine test_auto_order

  !> Two nodes, Coulomb mu = 0.2, G on the rows (lambda1, lambda2, tau1, tau2)
  !>     [  1.1 -2.4  1.5 -0.5 ]
  !>     [ -2.4  8.8 -4.9  0.8 ]     qn = (-0.1, -0.1),  qt = (0.1, 0.5)
  !>     [  1.5 -4.9  3.2 -0.6 ]
  !>     [ -0.5  0.8 -0.6  0.4 ]
  !> (one of the problems of this size with one-decimal entries on which the
  !> full Newton steps from zero come back to a partition, an endless cycle
  !> without the globalisation).  Both nodes slip backwards: tau = -lambda/5
  !> and (Gnn - Gnt/5) lambda = -qn, [0.8 -2.3; -1.42 8.64] lambda = (0.1, 0.1),
  !> give lambda = (547, 111)/1823, with ds = -(qt + G(3:4, :) lam) < 0.
  !> The method says that it globalised, ends on that answer, and takes the
  !> same steps when G is multiplied by 1e3 and q by 1e-3 (units changed).
  subroutine test_newton_cycle_coulomb()
    real(dp) :: g(4, 4), lam(4), lam_ref(4)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep, rep_units
    g = reshape([1.1_dp, -2.4_dp, 1.5_dp, -0.5_dp, -2.4_dp, 8.8_dp, -4.9_dp, 0.8_dp, &
                 1.5_dp, -4.9_dp, 3.2_dp, -0.6_dp, -0.5_dp, 0.8_dp, -0.6_dp, 0.4_dp], [4, 4])
    prob = friction_problem([-0.1_dp, -0.1_dp], [0.1_dp, 0.5_dp], [1, 2], [0.2_dp, 0.2_dp], [0.0_dp, 0.0_dp])
    lam_ref(1:2) = [547.0_dp, 111.0_dp] / 1823.0_dp
    lam_ref(3:4) = -lam_ref(1:2) / 5.0_dp
    lam = 0.0_dp
    call solve_friction_newton(g, prob, opts, lam, rep)
    call check(rep%info == 0, 'newton cycle coulomb: info 0')
    call check(index(rep%message, 'came back') > 0 .and. index(rep%message, 'damped Newton') > 0, &
      'newton cycle coulomb: the full steps came back to a partition, then damped steps')
    call check_small(rel_diff(lam, lam_ref), tol_direct, 'newton cycle coulomb: lam = the closed form')
    call check_conditions(g, prob, lam, tol_direct, 'newton cycle coulomb')
    ! the same problem in other units: G x 1e3, q x 1e-3, lam x 1e-6
    prob%qn = prob%qn * 1.0e-3_dp
    prob%qt = prob%qt * 1.0e-3_dp
    lam = 0.0_dp
    call solve_friction_newton(g * 1.0e3_dp, prob, opts, lam, rep_units)
    call check(rep_units%info == 0 .and. rep_units%iterations == rep%iterations, &
      'newton cycle coulomb: the same steps in other units')
    call check_small(rel_diff(lam * 1.0e6_dp, lam_ref), tol_direct, 'newton cycle coulomb: other units, lam scaled')
  end subroutine test_newton_cycle_coulomb

  !> Two nodes, Tresca bounds 0.5, G on the rows (lambda1, lambda2, tau1, tau2)
  !>     [ 2.7 2.7 1.2 2.1 ]
  !>     [ 2.7 2.9 1.6 2.5 ]     qn = (-0.5, -0.2),  qt = (-0.2, -0.1)
  !>     [ 1.2 1.6 1.8 1.8 ]
  !>     [ 2.1 2.5 1.8 2.9 ]
  !> (found as the problem above: the full steps from zero cycle).  Node 1 in
  !> contact, node 2 open, both tangential rows sticking: G on the rows
  !> (1, 3, 4) times (lambda1, tau1, tau2) = (0.5, 0.2, 0.1) gives
  !> lam = (37, 0, 25, -39)/96, |tau| < 0.5, w2 = 23.2/96 > 0; G is SPD,
  !> the QP strictly convex, so this is the only solution (Lemke's).  The
  !> method ends by projected Newton on the QP; the fixed point on the Tresca
  !> threshold solves the one Tresca problem to the same answer.
  subroutine test_newton_cycle_tresca()
    real(dp) :: g(4, 4), lam(4), lam_ref(4), lam_l(4)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    g = reshape([2.7_dp, 2.7_dp, 1.2_dp, 2.1_dp, 2.7_dp, 2.9_dp, 1.6_dp, 2.5_dp, &
                 1.2_dp, 1.6_dp, 1.8_dp, 1.8_dp, 2.1_dp, 2.5_dp, 1.8_dp, 2.9_dp], [4, 4])
    prob = friction_problem([-0.5_dp, -0.2_dp], [-0.2_dp, -0.1_dp], [1, 2], [0.0_dp, 0.0_dp], [0.5_dp, 0.5_dp])
    lam_ref = [37.0_dp, 0.0_dp, 25.0_dp, -39.0_dp] / 96.0_dp
    lam = 0.0_dp
    call solve_friction_newton(g, prob, opts, lam, rep)
    call check(rep%info == 0, 'newton cycle tresca: info 0')
    call check(index(rep%message, 'came back') > 0 .and. index(rep%message, 'projected Newton') > 0, &
      'newton cycle tresca: the full steps came back to a partition, then projected Newton')
    call check_small(rel_diff(lam, lam_ref), tol_direct, 'newton cycle tresca: lam = the closed form')
    call check_conditions(g, prob, lam, tol_direct, 'newton cycle tresca')
    call solve_friction_lcp(g, prob, 'lemke', opts, lam_l, rep)
    call check(rep%info == 0, 'newton cycle tresca: Lemke solves it')
    call check_small(rel_diff(lam_l, lam_ref), tol_direct, 'newton cycle tresca: Lemke, the same answer')
    lam = 0.0_dp
    call solve_friction_fixed_point(g, prob, opts, lam, rep)
    call check(rep%info == 0 .and. index(rep%message, 'solved in 1 Tresca problems') > 0, &
      'fixed point tresca: one Tresca problem')
    call check_small(rel_diff(lam, lam_ref), tol_direct, 'fixed point tresca: lam = the closed form')
  end subroutine test_newton_cycle_tresca

  !> The fixed point on the Tresca threshold on Coulomb problems with known
  !> answers.  One node of test_one_node: G = [2 1/2; 1/2 1], qn = -2,
  !> qt = -1/10: mu = 0.2 slips with lambda = 20/19, tau = -4/19, mu = 0.8
  !> sticks with lambda = 39/35, tau = -16/35.  Three nodes, mu = 0.5, G on
  !> the rows (lambda1..3, tau1..3)
  !>     [ 0.7 0.3 0.9 1.4 0.7 0.8 ]
  !>     [ 0.3 0.6 0.8 1.2 0.5 0.9 ]
  !>     [ 0.9 0.8 4.5 3.7 1.9 3.7 ]   qn = (-0.2, -0.4, -0.6)
  !>     [ 1.4 1.2 3.7 4.2 2.0 3.3 ]   qt = (-0.4, 0.2, 0.2)
  !>     [ 0.7 0.5 1.9 2.0 1.4 1.8 ]
  !>     [ 0.8 0.9 3.7 3.3 1.8 3.4 ]
  !> (found as above; the Newton steps cycle, and the damped steps stop
  !> short of it): every node slips backwards, tau = -lambda/2, and
  !> (Gnn - Gnt/2) lambda = -qn gives lambda = (828, 1540, 684)/1325.  Both
  !> methods end there, the fixed point in the same iterations in other units.
  subroutine test_fixed_point_coulomb()
    real(dp) :: g1(2, 2), lam1(2), g(6, 6), lam(6), lam_ref(6)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep, rep_units
    g1 = reshape([2.0_dp, 0.5_dp, 0.5_dp, 1.0_dp], [2, 2])
    lam1 = [5.0_dp, 1.0_dp]
    call solve_friction_fixed_point(g1, friction_problem([-2.0_dp], [-0.1_dp], [1], [0.2_dp], [0.0_dp]), opts, &
      lam1, rep)
    call check(rep%info == 0, 'fixed point one node mu 0.2: info 0')
    call check_small(rel_diff(lam1, [20.0_dp, -4.0_dp] / 19.0_dp), 1.0e2_dp * opts%tol, &
      'fixed point one node mu 0.2: slip, lambda = 20/19, tau = -4/19')
    lam1 = 0.0_dp
    call solve_friction_fixed_point(g1, friction_problem([-2.0_dp], [-0.1_dp], [1], [0.8_dp], [0.0_dp]), opts, &
      lam1, rep)
    call check(rep%info == 0, 'fixed point one node mu 0.8: info 0')
    call check_small(rel_diff(lam1, [39.0_dp, -16.0_dp] / 35.0_dp), 1.0e2_dp * opts%tol, &
      'fixed point one node mu 0.8: stick, lambda = 39/35, tau = -16/35')

    g = reshape([0.7_dp, 0.3_dp, 0.9_dp, 1.4_dp, 0.7_dp, 0.8_dp, &
                 0.3_dp, 0.6_dp, 0.8_dp, 1.2_dp, 0.5_dp, 0.9_dp, &
                 0.9_dp, 0.8_dp, 4.5_dp, 3.7_dp, 1.9_dp, 3.7_dp, &
                 1.4_dp, 1.2_dp, 3.7_dp, 4.2_dp, 2.0_dp, 3.3_dp, &
                 0.7_dp, 0.5_dp, 1.9_dp, 2.0_dp, 1.4_dp, 1.8_dp, &
                 0.8_dp, 0.9_dp, 3.7_dp, 3.3_dp, 1.8_dp, 3.4_dp], [6, 6])
    prob = friction_problem([-0.2_dp, -0.4_dp, -0.6_dp], [-0.4_dp, 0.2_dp, 0.2_dp], [1, 2, 3], &
                            [0.5_dp, 0.5_dp, 0.5_dp], [0.0_dp, 0.0_dp, 0.0_dp])
    lam_ref(1:3) = [828.0_dp, 1540.0_dp, 684.0_dp] / 1325.0_dp
    lam_ref(4:6) = -lam_ref(1:3) / 2.0_dp
    lam = 0.0_dp
    call solve_friction_fixed_point(g, prob, opts, lam, rep)
    call check(rep%info == 0, 'fixed point three nodes: info 0')
    call check_small(rel_diff(lam, lam_ref), 1.0e2_dp * opts%tol, 'fixed point three nodes: lam = the closed form')
    call check_conditions(g, prob, lam, 1.0e2_dp * opts%tol, 'fixed point three nodes')
    lam = 0.0_dp
    call solve_friction_newton(g, prob, opts, lam, rep_units)
    call check(rep_units%info == 0 .and. index(rep_units%message, 'came back') > 0, &
      'newton three nodes: solved after a cycle')
    call check_small(rel_diff(lam, lam_ref), tol_direct, 'newton three nodes: lam = the closed form')
    ! other units: G x 1e-3, q x 1e3, lam x 1e6
    prob%qn = prob%qn * 1.0e3_dp
    prob%qt = prob%qt * 1.0e3_dp
    lam = 0.0_dp
    call solve_friction_fixed_point(g * 1.0e-3_dp, prob, opts, lam, rep_units)
    call check(rep_units%info == 0 .and. rep_units%iterations == rep%iterations .and. &
      rep_units%message(1:40) == rep%message(1:40), 'fixed point three nodes: the same iterations in other units')
    call check_small(rel_diff(lam * 1.0e-6_dp, lam_ref), 1.0e2_dp * opts%tol, &
      'fixed point three nodes: other units, lam scaled')
  end subroutine test_fixed_point_coulomb

  !> Two nodes, mu = 0.5, G on the rows (lambda1, lambda2, tau1, tau2)
  !>     [  1.0 0.1 -0.1  1.0 ]
  !>     [  0.1 0.1  0.1  0.0 ]     qn = (-0.4, -0.3),  qt = (0.5, 0.3)
  !>     [ -0.1 0.1  0.4 -0.2 ]
  !>     [  1.0 0.0 -0.2  1.4 ]
  !> tau2 pushes node 1 as hard as lambda1 does (G(1,4) = G(1,1)): with
  !> mu = 0.5 the fixed point on the Tresca threshold is no contraction and
  !> stops so (info 3, 'stagnated') without claiming that there is no
  !> solution.  The Newton method finds one: both nodes slip backwards,
  !> tau = -lambda/2, (Gnn - Gnt/2) lambda = -qn gives lambda = (32, 59)/25.
  subroutine test_fixed_point_no_contraction()
    real(dp) :: g(4, 4), lam(4), lam_ref(4)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    g = reshape([1.0_dp, 0.1_dp, -0.1_dp, 1.0_dp, 0.1_dp, 0.1_dp, 0.1_dp, 0.0_dp, &
                 -0.1_dp, 0.1_dp, 0.4_dp, -0.2_dp, 1.0_dp, 0.0_dp, -0.2_dp, 1.4_dp], [4, 4])
    prob = friction_problem([-0.4_dp, -0.3_dp], [0.5_dp, 0.3_dp], [1, 2], [0.5_dp, 0.5_dp], [0.0_dp, 0.0_dp])
    lam_ref(1:2) = [32.0_dp, 59.0_dp] / 25.0_dp
    lam_ref(3:4) = -lam_ref(1:2) / 2.0_dp
    lam = 0.0_dp
    call solve_friction_fixed_point(g, prob, opts, lam, rep)
    call check(rep%info == 3 .and. trim(rep%stopped) == 'stagnated' .and. all(ieee_is_finite(lam)), &
      'fixed point no contraction: info 3, stagnated')
    call check(index(rep%message, 'no contraction') > 0 .and. &
      index(rep%message, 'does not show that there is no solution') > 0, 'fixed point no contraction: no claim')
    lam = 0.0_dp
    call solve_friction_newton(g, prob, opts, lam, rep)
    call check(rep%info == 0, 'fixed point no contraction: Newton solves it')
    call check_small(rel_diff(lam, lam_ref), tol_direct, 'fixed point no contraction: Newton, the closed form')
  end subroutine test_fixed_point_no_contraction

  !> A tangential row with a zero row/column in G (ds_k = -qt_k whatever lam):
  !> with qt_k = -0.2 the node slips, tau_k = +b_k.
  subroutine test_zero_tangential_row()
    integer, parameter :: n = 8, kz = 3
    real(dp), allocatable :: g(:, :), qn(:), qt(:), cmu(:), bound(:), lam(:)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: method, k
    character(len=5) :: tag

    call random_delassus(n, n, 0.3_dp, seed, g)
    g(n + kz, :) = 0.0_dp
    g(:, n + kz) = 0.0_dp
    allocate(qn(n), qt(n), lam(2 * n))
    call random_vector(seed, -1.0_dp, 1.0_dp, qn)
    call random_vector(seed, -1.0_dp, 1.0_dp, qt)
    qn(kz) = -1.0_dp
    qt(kz) = -0.2_dp
    cmu = [(0.3_dp, k = 1, n)]
    bound = [(0.0_dp, k = 1, n)]
    prob = friction_problem(qn, qt, identity_rows(n), cmu, bound)
    opts%tol = 1.0e-12_dp
    do method = 1, 2
      tag = merge('lemke', 'pgs  ', method == 1)
      lam = 0.0_dp
      call solve_friction_lcp(g, prob, trim(tag), opts, lam, rep)
      call check(rep%info == 0, 'zero tangential row ' // trim(tag) // ': info 0')
      call check_conditions(g, prob, lam, cond_w * opts%tol, 'zero tangential row ' // trim(tag))
      call check(lam(kz) > 0.0_dp, 'zero tangential row ' // trim(tag) // ': node in contact')
      call check_close(lam(n + kz), 0.3_dp * lam(kz), tol_round(16), 'zero tangential row ' // trim(tag) // &
        ': tau = +mu lambda')
    end do
  end subroutine test_zero_tangential_row

  !> mu = 0: tau = 0 and lambda solves LCP(Gnn, qn) although G couples the
  !> rows; nt = 0: the result of solve_lcp_lemke / solve_lcp_pgs, bit for bit.
  subroutine test_frictionless_limits(n)
    integer, intent(in) :: n
    real(dp), allocatable :: g(:, :), gnn(:, :), qn(:), qt(:), zero(:), lam(:), zref(:), empty(:)
    integer, allocatable :: none(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep, ref
    integer :: k

    call random_delassus(n, n, 1.0_dp, seed, g)
    allocate(qn(n), qt(n), lam(2 * n), zref(n), empty(0), none(0))
    call random_vector(seed, -1.0_dp, 1.0_dp, qn)
    call random_vector(seed, -1.0_dp, 1.0_dp, qt)
    zero = [(0.0_dp, k = 1, n)]
    gnn = g(1:n, 1:n)
    call solve_lcp_lemke(gnn, qn, zref, opts, ref)
    call solve_friction_lcp(g, friction_problem(qn, qt, identity_rows(n), zero, zero), 'lemke', opts, lam, rep)
    call check(rep%info == 0, 'mu = 0 lemke: info 0')
    call check(maxval(abs(lam(n + 1:))) <= tol_round(32) * maxval(lam(1:n)), 'mu = 0 lemke: tau = 0')
    call check_small(rel_diff(lam(1:n), zref), tol_direct, 'mu = 0 lemke: lambda frictionless')
    lam = 1.0_dp
    opts%tol = 1.0e-13_dp
    call solve_friction_lcp(g, friction_problem(qn, qt, identity_rows(n), zero, zero), 'pgs', opts, lam, rep)
    call check(rep%info == 0 .and. all(lam(n + 1:) == 0.0_dp), 'mu = 0 pgs: info 0, tau = 0')
    call check_small(rel_diff(lam(1:n), zref), cond_w * opts%tol, 'mu = 0 pgs: lambda frictionless')

    ! nt = 0.
    opts = lcp_options_t()
    deallocate(lam)
    allocate(lam(n))
    call solve_friction_lcp(gnn, friction_problem(qn, empty, none, empty, empty), 'lemke', opts, lam, rep)
    call check(all(lam == zref) .and. rep%info == ref%info .and. rep%iterations == ref%iterations .and. &
      rep%residual == ref%residual, 'nt = 0 lemke: identical to solve_lcp_lemke')
    zref = 0.5_dp
    call solve_lcp_pgs(gnn, qn, zref, opts, ref)
    lam = 0.5_dp
    call solve_friction_lcp(gnn, friction_problem(qn, empty, none, empty, empty), 'pgs', opts, lam, rep)
    call check(all(lam == zref) .and. rep%info == ref%info .and. rep%iterations == ref%iterations .and. &
      rep%residual == ref%residual, 'nt = 0 pgs: identical to solve_lcp_pgs')
  end subroutine test_frictionless_limits

  !> A normal row whose row/column of G is zero: with qn_i < 0 there is no
  !> solution (info 1, Lemke by ray termination); with qn_i > 0, lambda_i = 0.
  !> PGS with maxit = 2: info 2, the best iterate finite, residual reported.
  subroutine test_failures()
    integer, parameter :: n = 6, iz = 3
    real(dp), allocatable :: g(:, :), qn(:), qt(:), cmu(:), bound(:), lam(:)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: method, k
    character(len=5) :: tag

    call random_delassus(n, n, 0.5_dp, seed, g)
    g(iz, :) = 0.0_dp
    g(:, iz) = 0.0_dp
    allocate(qn(n), qt(n), lam(2 * n))
    call random_vector(seed, -1.0_dp, 1.0_dp, qn)
    call random_vector(seed, -1.0_dp, 1.0_dp, qt)
    cmu = [(0.3_dp, k = 1, n)]
    bound = [(0.0_dp, k = 1, n)]
    do method = 1, 2
      tag = merge('lemke', 'pgs  ', method == 1)
      qn(iz) = -0.5_dp
      prob = friction_problem(qn, qt, identity_rows(n), cmu, bound)
      lam = 0.0_dp
      call solve_friction_lcp(g, prob, trim(tag), opts, lam, rep)
      call check(rep%info == 1, 'zero normal row, qn < 0 ' // trim(tag) // ': info 1')
      call check(index(rep%message, 'row/column 3') > 0, 'zero normal row, qn < 0 ' // trim(tag) // &
        ': message names row 3')
      call check(all(ieee_is_finite(lam)) .and. ieee_is_finite(rep%residual), &
        'zero normal row, qn < 0 ' // trim(tag) // ': lam and residual finite')
      qn(iz) = 0.5_dp
      prob = friction_problem(qn, qt, identity_rows(n), cmu, bound)
      lam = 0.0_dp
      opts%tol = 1.0e-12_dp
      call solve_friction_lcp(g, prob, trim(tag), opts, lam, rep)
      call check(rep%info == 0 .and. lam(iz) == 0.0_dp .and. lam(n + iz) == 0.0_dp, &
        'zero normal row, qn > 0 ' // trim(tag) // ': solved, lambda = tau = 0 there')
      call check_conditions(g, prob, lam, cond_w * opts%tol, 'zero normal row, qn > 0 ' // trim(tag))
      opts = lcp_options_t()
    end do
    call check(index(rep%message, 'PGS') > 0, 'messages name the method')

    deallocate(g, qn, qt, lam)
    call random_delassus(30, 30, 1.0_dp, seed, g)
    allocate(qn(30), qt(30), lam(60))
    call random_vector(seed, -1.0_dp, 1.0_dp, qn)
    call random_vector(seed, -1.0_dp, 1.0_dp, qt)
    cmu = [(0.3_dp, k = 1, 30)]
    bound = [(0.0_dp, k = 1, 30)]
    prob = friction_problem(qn, qt, identity_rows(30), cmu, bound)
    lam = 0.0_dp
    opts%maxit = 2
    opts%tol = 1.0e-14_dp
    call solve_friction_lcp(g, prob, 'pgs', opts, lam, rep)
    call check(rep%info == 2 .and. rep%iterations == 2, 'pgs maxit 2: info 2 after 2 sweeps')
    call check(all(ieee_is_finite(lam)) .and. all(lam(1:30) >= 0.0_dp), 'pgs maxit 2: best iterate finite')
    call check(rep%residual > opts%tol, 'pgs maxit 2: residual above tol')
    call check_close(rep%residual, friction_residual(g, prob, lam), &
      tol_round(16), 'pgs maxit 2: reported residual is that of lam')
    call check(index(rep%message, 'sweep limit') > 0, 'pgs maxit 2: message')

    opts%maxit = 3
    call solve_friction_lcp(g, prob, 'lemke', opts, lam, rep)
    call check(rep%info == 2 .and. all(ieee_is_finite(lam)), 'lemke maxit 3: info 2, lam finite')
    call test_unclosable()
  end subroutine test_failures

  !> Two normal rows that no forces close, Gnn = [1 -1; -1 1] (PSD, no zero
  !> row), qn = (-1, -1): w1 + w2 = -2 whatever lambda and tau (Gnt = 0), one
  !> tangential row on node 1, Coulomb mu = 0.3.  Lemke ends on a ray, and
  !> its direction, y = (1, 1) on lambda, is Farkas' certificate: the message
  !> says that there is no solution, not that none was found.  The same step
  !> made feasible (Gnn = [1 -1; -1 1.5], qn = (-1, 1)) is solved.
  subroutine test_unclosable()
    real(dp) :: g(3, 3), lam(3)
    type(friction_problem_t) :: prob
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    g = 0.0_dp
    g(1:2, 1:2) = reshape([1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp], [2, 2])
    g(3, 3) = 1.0_dp
    prob = friction_problem([-1.0_dp, -1.0_dp], [0.5_dp], [1], [0.3_dp], [0.0_dp])
    lam = 0.0_dp
    call solve_friction_lcp(g, prob, 'lemke', opts, lam, rep)
    call check(rep%info == 1 .and. rep%stopped == 'ray', 'unclosable rows, coulomb lemke: ray termination (info 1)')
    call check(index(rep%message, 'no solution (the ray proves') > 0 .and. index(rep%message, 'found') == 0, &
      'unclosable rows, coulomb lemke: the message says the ray proves that there is no solution')
    g(2, 2) = 1.5_dp
    prob = friction_problem([-1.0_dp, 1.0_dp], [0.5_dp], [1], [0.3_dp], [0.0_dp])
    call solve_friction_lcp(g, prob, 'lemke', opts, lam, rep)
    call check(rep%info == 0, 'closable rows, coulomb lemke: solved')
    call check_conditions(g, prob, lam, tol_direct, 'closable rows, coulomb lemke')
  end subroutine test_unclosable

  !> Every argument check: info -1 G, -2 the problem (each of its arrays),
  !> -3 method, -4 options, -5 lam; lam unchanged.
  subroutine test_arguments()
    real(dp) :: g(4, 4), lam(4), lam3(3)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(friction_problem_t) :: prob, bad
    integer :: i
    g = 0.0_dp
    do i = 1, 4
      g(i, i) = 1.0_dp
    end do
    prob = friction_problem([-1.0_dp, -1.0_dp], [0.1_dp, 0.1_dp], [1, 2], [0.3_dp, 0.3_dp], [0.0_dp, 0.0_dp])
    call check(prob%n == 2 .and. prob%nt == 2, 'arguments: friction_problem takes n and nt from qn and qt')
    lam = 7.0_dp
    call solve_friction_lcp(g, prob, 'newton', opts, lam, rep)
    call check(rep%info == -3 .and. all(lam == 7.0_dp), 'arguments: unknown method -> -3, lam unchanged')
    bad = prob
    bad%trow = [1, 3]
    call solve_friction_lcp(g, bad, 'lemke', opts, lam, rep)
    call check(rep%info == -2 .and. all(lam == 7.0_dp), 'arguments: trow out of range -> -2, lam unchanged')
    bad = prob
    bad%trow = [1]
    call solve_friction_lcp(g, bad, 'lemke', opts, lam, rep)
    call check(rep%info == -2 .and. index(rep%message, 'trow has 1 entries') > 0, 'arguments: trow size -> -2')
    bad = prob
    bad%cmu = [0.3_dp, -0.3_dp]
    call solve_friction_lcp(g, bad, 'lemke', opts, lam, rep)
    call check(rep%info == -2 .and. index(rep%message, 'cmu') > 0, 'arguments: negative cmu -> -2')
    bad = prob
    bad%bound = [0.0_dp, -1.0_dp]
    call solve_friction_lcp(g, bad, 'lemke', opts, lam, rep)
    call check(rep%info == -2 .and. index(rep%message, 'bound') > 0, 'arguments: negative bound -> -2')
    bad = prob
    bad%nt = 1
    call solve_friction_lcp(g, bad, 'lemke', opts, lam, rep)
    call check(rep%info == -2, 'arguments: nt not the size of qt -> -2')
    call check(friction_residual(g, bad, lam) == huge(1.0_dp), 'arguments: residual of an invalid problem -> huge')
    call solve_friction_lcp(g, prob, 'lemke', opts, lam3, rep)
    call check(rep%info == -5, 'arguments: lam size -> -5')
    call solve_friction_lcp(g(1:3, 1:3), prob, 'lemke', opts, lam, rep)
    call check(rep%info == -1, 'arguments: G size -> -1')
    g(3, 3) = -1.0e-3_dp
    call solve_friction_lcp(g, prob, 'lemke', opts, lam, rep)
    call check(rep%info == -1 .and. index(rep%message, 'G(3,3) < 0') > 0, &
               'arguments: negative diagonal G(3,3) -> -1, named')
    g(3, 3) = -1.0e-12_dp
    call solve_friction_lcp(g, prob, 'lemke', opts, lam, rep)
    call check(rep%info /= -1, 'arguments: G(3,3) = -1e-12 is round-off, accepted')
    g(3, 3) = 1.0_dp
    opts%omega = 2.0_dp
    call solve_friction_lcp(g, prob, 'pgs', opts, lam, rep)
    call check(rep%info == -4 .and. allocated(rep%message), 'arguments: omega = 2 -> -4')
  end subroutine test_arguments

end program test_friction_lcp
