!> Unit tests of lcp_newton: the primal-dual active set method on LCP(W, q)
!> against closed forms, manufactured solutions (q = w0 - W z0 with z0, w0 >= 0
!> complementary: z0 is the solution, the only one when W is definite), Lemke,
!> enumeration of all 2**n complementary bases on tiny problems, the KKT
!> conditions checked with an independent Cholesky solve on the active set, and
!> the LCP invariants recomputed here.  Ends with an informational table
!> (lines starting with '#') of Newton steps, Lemke pivots and PGS sweeps and
!> their CPU times on contact-like Delassus matrices, n = 100 and 500; with
!> the environment variable LCP_BENCH=1 also n = 2000 and 5000 (minutes:
!> Lemke's dense tableau is O(n^2) per pivot and needs about n/2 pivots).
program test_lcp_newton
  use kinds, only: dp, i8
  use testing, only: check, check_close, check_small, finish_tests, urand, random_spd, random_pair, tol_round, &
    unit_roundoff
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_pgs, &
    lcp_natural_residual
  use lcp_newton, only: solve_lcp_pdas, pdas_stats_t, pdas_factor_auto, pdas_factor_refactor, &
    pdas_factor_update
  use lapack_interfaces, only: dpotrf
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: iso_fortran_env, only: output_unit
  implicit none

  interface
    subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: info
    end subroutine dposv
    subroutine dptsv(n, nrhs, d, e, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, nrhs, ldb
      real(dp), intent(inout) :: d(*), e(*), b(ldb, *)
      integer, intent(out) :: info
    end subroutine dptsv
  end interface

  ! Tolerances, in the units of testing (tol_round: n eps scale).  PDAS and
  ! Lemke end on direct solves, so z is good to round-off times a condition:
  ! W from random_spd has eigenvalues in [1e-3, 0.83] (its shift, and
  ! (1 + sqrt(1/3))^2 / 3 by Marchenko-Pastur), cond(W) <= cond_w, hence
  ! tol_direct (measured <= 185 eps); the contact-like W_AA reach cond
  ! 1e5 at n = 200 and 300 (cond_contact) and 7e6 at n = 5000 (cond_bench).
  real(dp), parameter :: cond_w = 1.0e3_dp, cond_contact = 1.0e5_dp, cond_bench = 7.0e6_dp
  real(dp), parameter :: tol_direct = 64 * cond_w * epsilon(1.0_dp)
  integer(i8) :: seed
  seed = 20240611_i8

  call test_tiny_closed_forms()
  call test_random_spd(5, 'n5')
  call test_random_spd(40, 'n40')
  call test_random_spd(200, 'n200')
  call test_random_spd(1000, 'n1000')
  call test_manufactured(60)
  call test_badly_scaled(30)
  call test_degenerate()
  call test_duplicate_rows()
  call test_zero_row_and_infeasible()
  call test_all_and_none_active(40)
  call test_arguments()
  call test_step_limit()
  call test_cycling_safeguard()
  call test_lemke_fallback()
  call test_update_equals_refactor()
  call test_contact_problems()
  call benchmark_table()
  call finish_tests()

contains

  ! ---------------------------------------------------------------------------
  ! Helpers
  ! ---------------------------------------------------------------------------

  !> The LCP invariants of z recomputed here, on the diagonally scaled problem
  !> (d_i = 1/sqrt(W_ii), 1 when W_ii = 0), relative to ||qs||_inf (1 when
  !> q = 0): z >= 0 and finite, w >= -tol, natural residual and scaled
  !> complementarity <= tol.
  subroutine check_lcp(w, q, z, tol, name)
    real(dp), intent(in) :: w(:, :), q(:), z(:), tol
    character(len=*), intent(in) :: name
    real(dp), allocatable :: d(:), zs(:), ws(:), qs(:)
    real(dp) :: qscale
    integer :: i, n
    n = size(q)
    allocate(d(n))
    do i = 1, n
      d(i) = 1.0_dp
      if (w(i, i) > 0.0_dp) d(i) = 1.0_dp / sqrt(w(i, i))
    end do
    call check(all(z >= 0.0_dp) .and. all(ieee_is_finite(z)), name // ' z >= 0 and finite')
    if (.not. all(ieee_is_finite(z))) return
    zs = z / d
    ws = d * (q + matmul(w, z))
    qs = d * q
    qscale = maxval(abs(qs))
    if (.not. qscale > 0.0_dp) qscale = 1.0_dp
    call check_small(max(0.0_dp, -minval(ws)) / qscale, tol, name // ' w >= -tol')
    call check_small(maxval(abs(min(zs, ws))) / qscale, tol, name // ' natural residual')
    call check_small(maxval(abs(zs * ws)) / (max(tiny(1.0_dp), maxval(zs)) * qscale), tol, &
      name // ' complementarity')
  end subroutine check_lcp

  !> KKT conditions of min 1/2 z'Wz + q'z, z >= 0 for SPD W, independently: on
  !> the active set A = {z_i > 0}, W_AA x = -q_A (dposv) must give x = z_A > 0,
  !> and the gaps off A must be >= 0.
  subroutine check_kkt(w, q, z, name)
    real(dp), intent(in) :: w(:, :), q(:), z(:)
    character(len=*), intent(in) :: name
    integer, allocatable :: act(:), off(:)
    real(dp), allocatable :: waa(:, :), x(:, :), gap(:)
    integer :: i, na, info
    act = pack([(i, i = 1, size(q))], z > 0.0_dp)
    off = pack([(i, i = 1, size(q))], .not. (z > 0.0_dp))
    na = size(act)
    if (na == 0) then
      call check(all(q >= 0.0_dp), name // ' KKT: z = 0 needs q >= 0')
      return
    end if
    waa = w(act, act)
    allocate(x(na, 1))
    x(:, 1) = -q(act)
    call dposv('U', na, 1, waa, na, x, na, info)
    call check(info == 0, name // ' KKT: W_AA is positive definite')
    call check_small(maxval(abs(x(:, 1) - z(act))) / maxval(abs(z)), tol_direct, &
      name // ' KKT: z_A solves W_AA z_A = -q_A')
    call check(all(x(:, 1) > 0.0_dp), name // ' KKT: z_A > 0')
    if (size(off) > 0) then
      gap = q(off) + matmul(w(off, act), x(:, 1))
      call check(minval(gap) >= -tol_direct * max(1.0_dp, maxval(abs(q))), &
        name // ' KKT: gaps off the active set >= 0')
    end if
  end subroutine check_kkt

  real(dp) function rel_diff(a, b)
    real(dp), intent(in) :: a(:), b(:)
    rel_diff = maxval(abs(a - b)) / max(tiny(1.0_dp), maxval(abs(b)))
  end function rel_diff

  !> Reference solution of a tiny LCP with definite W by enumeration: the one
  !> complementary basis (A subset of 1..n) with z_A = -W_AA^-1 q_A >= 0 and
  !> w >= 0 (unique for a P-matrix).
  subroutine enumerate_lcp(w, q, z, found)
    real(dp), intent(in) :: w(:, :), q(:)
    real(dp), intent(out) :: z(:)
    integer, intent(out) :: found
    real(dp), allocatable :: waa(:, :), x(:, :), zc(:), g(:)
    integer, allocatable :: act(:)
    integer :: n, code, i, info
    n = size(q)
    found = 0
    z = 0.0_dp
    allocate(zc(n))
    do code = 0, 2**n - 1
      act = pack([(i, i = 1, n)], [(btest(code, i - 1), i = 1, n)])
      zc = 0.0_dp
      if (size(act) > 0) then
        waa = w(act, act)
        x = reshape(-q(act), [size(act), 1])
        call dposv('U', size(act), 1, waa, size(act), x, size(act), info)
        if (info /= 0) cycle
        zc(act) = x(:, 1)
      end if
      g = q + matmul(w, zc)
      ! a candidate by a small dense solve: accepted to round-off, with room
      if (all(zc >= -tol_round(4096)) .and. all(g >= -tol_round(4096))) then
        found = found + 1
        z = max(zc, 0.0_dp)
      end if
    end do
  end subroutine enumerate_lcp

  !> Processor time of the process, s (all threads; run the table with
  !> OPENBLAS_NUM_THREADS=1 for single-thread times that a busy machine does not
  !> inflate).
  real(dp) function process_time()
    real(dp) :: t
    call cpu_time(t)
    process_time = t
  end function process_time

  ! ---------------------------------------------------------------------------
  ! Tests
  ! ---------------------------------------------------------------------------

  !> Closed forms; the step counts follow by hand from A_0 = {q_i < 0}.
  subroutine test_tiny_closed_forms()
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    real(dp) :: w1(1, 1), w2(2, 2), z1(1), z2(2)

    w1 = 2.0_dp
    w2 = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
    opts%tol = 1.0e-13_dp
    ! 1x1: 2 z - 4 = 0 -> z = 2, one step.
    call solve_lcp_pdas(w1, [-4.0_dp], z1, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 1, 'pdas 1x1 active: info 0, 1 step')
    call check_close(z1(1), 2.0_dp, tol_round(16), 'pdas 1x1 active: z = 2')
    ! 1x1 with q > 0: z = 0 without a step.
    call solve_lcp_pdas(w1, [3.0_dp], z1, opts, rep)
    call check(rep%info == 0 .and. z1(1) == 0.0_dp .and. rep%iterations == 0, 'pdas 1x1 inactive: z = 0, 0 steps')
    ! [2 1; 1 2] z = [5, 6]: z = [4/3, 7/3], both active, one step.
    call solve_lcp_pdas(w2, [-5.0_dp, -6.0_dp], z2, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 1, 'pdas 2x2 both active: info 0, 1 step')
    call check_small(rel_diff(z2, [4.0_dp / 3.0_dp, 7.0_dp / 3.0_dp]), tol_round(16), &
      'pdas 2x2 both active: z = [4/3, 7/3]')
    ! q = [-4, 3]: A_0 = {1}, z = [2, 0], w2 = 5, one step.
    call solve_lcp_pdas(w2, [-4.0_dp, 3.0_dp], z2, opts, rep)
    call check(rep%iterations == 1, 'pdas 2x2 one active: 1 step')
    call check_small(rel_diff(z2, [2.0_dp, 0.0_dp]), tol_round(16), 'pdas 2x2 one active: z = [2, 0]')
    ! q = [-1, -5]: A_0 = {1, 2} gives z = [-1, 3]; index 1 leaves; A = {2}:
    ! z = [0, 5/2], w1 = 3/2.  Two steps.
    call solve_lcp_pdas(w2, [-1.0_dp, -5.0_dp], z2, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 2, 'pdas 2x2 q both negative: info 0, 2 steps')
    call check_small(rel_diff(z2, [0.0_dp, 2.5_dp]), tol_round(16), 'pdas 2x2 q both negative: z = [0, 5/2]')
    call check(index(rep%message, 'PDAS: solved in 2 Newton steps') == 1, 'pdas 2x2: message')
    ! Empty problem.
    block
      real(dp) :: w0(0, 0), z0(0), q0(0)
      call solve_lcp_pdas(w0, q0, z0, opts, rep)
      call check(rep%info == 0 .and. rep%iterations == 0, 'pdas n = 0: info 0')
    end block
  end subroutine test_tiny_closed_forms

  !> Random SPD W, random q in (-1, 1): PDAS agrees with Lemke to tol_direct and
  !> satisfies KKT; the reported residual is that of the returned z.
  subroutine test_random_spd(n, tag)
    integer, intent(in) :: n
    character(len=*), intent(in) :: tag
    real(dp), allocatable :: w(:, :), q(:), zl(:), zn(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep, repl
    type(pdas_stats_t) :: st
    integer :: i

    call random_spd(n, seed, w)
    allocate(q(n), zl(n), zn(n))
    do i = 1, n
      q(i) = 2.0_dp * urand(seed) - 1.0_dp
    end do
    call solve_lcp_lemke(w, q, zl, opts, repl)
    call solve_lcp_pdas(w, q, zn, opts, rep, stats=st)
    call check(repl%info == 0, 'random ' // tag // ' lemke reference: info 0')
    call check(rep%info == 0, 'random ' // tag // ' pdas: info 0')
    call check(rep%iterations == st%steps .and. rep%iterations > 0, 'random ' // tag // ' pdas: steps counted')
    call check(.not. st%lemke_fallback, 'random ' // tag // ' pdas: no Lemke fallback')
    call check_small(rep%residual, opts%tol, 'random ' // tag // ' pdas: reported residual <= tol')
    call check_close(rep%residual, lcp_natural_residual(w, q, zn), tol_round(16), &
      'random ' // tag // ' pdas: reported residual is that of z', floor=unit_roundoff)
    call check_lcp(w, q, zn, tol_direct, 'random ' // tag // ' pdas')
    call check_small(rel_diff(zn, zl), tol_direct, 'random ' // tag // ' pdas = lemke')
    if (n <= 200) call check_kkt(w, q, zn, 'random ' // tag // ' pdas')
  end subroutine test_random_spd

  !> q = w0 - W z0: the unique solution is z0 (W definite), in every factor mode.
  subroutine test_manufactured(n)
    integer, intent(in) :: n
    real(dp), allocatable :: w(:, :), q(:), z0(:), w0(:), z(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: mode
    character(len=8), parameter :: names(0:2) = ['auto    ', 'refactor', 'update  ']

    call random_spd(n, seed, w)
    allocate(z0(n), w0(n), z(n))
    call random_pair(n, 0.0_dp, seed, z0, w0)
    q = w0 - matmul(w, z0)
    do mode = pdas_factor_auto, pdas_factor_update
      call solve_lcp_pdas(w, q, z, opts, rep, factor_mode=mode)
      call check(rep%info == 0, 'manufactured ' // trim(names(mode)) // ': info 0')
      call check_small(rel_diff(z, z0), tol_direct, 'manufactured ' // trim(names(mode)) // ': z = z0')
    end do
  end subroutine test_manufactured

  !> W = D A D, q = D qa with D = 10^(-6 .. 6): the solution is z = za / D
  !> where za solves LCP(A, qa) (w = D wa), za manufactured.
  subroutine test_badly_scaled(n)
    integer, intent(in) :: n
    real(dp), allocatable :: a(:, :), w(:, :), qa(:), q(:), za(:), wa(:), z(:), dd(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i, j

    call random_spd(n, seed, a)
    allocate(za(n), wa(n), z(n), dd(n), w(n, n))
    call random_pair(n, 0.0_dp, seed, za, wa)
    qa = wa - matmul(a, za)
    do i = 1, n
      dd(i) = 10.0_dp**(-6.0_dp + 12.0_dp * real(i - 1, dp) / real(n - 1, dp))
    end do
    do j = 1, n
      w(:, j) = dd * a(:, j) * dd(j)
    end do
    q = dd * qa
    call check(maxval([(w(i, i), i = 1, n)]) / minval([(w(i, i), i = 1, n)]) > 1.0e22_dp, &
      'badly scaled: diagonal spans more than 22 decades')
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0, 'badly scaled pdas: info 0')
    call check_lcp(w, q, z, tol_direct, 'badly scaled pdas')
    call check_small(rel_diff(z * dd, za), tol_direct, 'badly scaled pdas: D z = za')
  end subroutine test_badly_scaled

  !> Degenerate problems: zeros in q, z_i = w_i = 0, singular W.
  subroutine test_degenerate()
    real(dp), allocatable :: w(:, :), q(:), z(:), z0(:), w0(:), zl(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(pdas_stats_t) :: st
    integer :: i, n

    ! q >= 0 with zeros: z = 0, no step.
    call random_spd(6, seed, w)
    q = [0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 2.0_dp, 0.0_dp]
    allocate(z(6))
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0 .and. all(z == 0.0_dp) .and. rep%iterations == 0, &
      'degenerate q >= 0 with zeros pdas: z = 0, 0 steps')

    ! W = I, q = [0, -1, 0, 0]: z = e2, w = 0 everywhere; one step.
    deallocate(w, z)
    n = 4
    allocate(w(n, n), z(n))
    w = 0.0_dp
    do i = 1, n
      w(i, i) = 1.0_dp
    end do
    q = [0.0_dp, -1.0_dp, 0.0_dp, 0.0_dp]
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 1, 'degenerate W = I, q with zeros pdas: info 0, 1 step')
    call check_small(rel_diff(z, [0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp]), tol_round(4), &
      'degenerate W = I, q with zeros pdas: z = e2')

    ! W = 2 I + e e' (10 x 10), q = -1: z = e / 12, w = 0; one step.
    deallocate(w, z)
    n = 10
    allocate(w(n, n), z(n))
    w = 1.0_dp
    do i = 1, n
      w(i, i) = 3.0_dp
    end do
    q = [(-1.0_dp, i = 1, n)]
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 1, 'W = 2I + ee'', q = -1 pdas: info 0, 1 step')
    call check_small(rel_diff(z, [(1.0_dp / 12.0_dp, i = 1, n)]), tol_round(32), 'W = 2I + ee'', q = -1 pdas: z = 1/12')

    ! W = e e' (rank one, 8 x 8), q = -1: any z >= 0 with sum z = 1 solves it;
    ! seven constraints are linearly dependent on the first.
    deallocate(w, z)
    n = 8
    allocate(w(n, n), z(n))
    w = 1.0_dp
    q = [(-1.0_dp, i = 1, n)]
    call solve_lcp_pdas(w, q, z, opts, rep, stats=st)
    call check(rep%info == 0, 'rank-one W = ee'' pdas: info 0')
    call check_close(sum(z), 1.0_dp, tol_round(16), 'rank-one W = ee'' pdas: sum z = 1')
    call check_lcp(w, q, z, tol_round(64), 'rank-one W = ee'' pdas')
    call check(st%redundant == 7 .and. .not. st%lemke_fallback, 'rank-one W = ee'' pdas: 7 redundant, no fallback')
    call check(index(rep%message, 'linearly dependent') > 0, 'rank-one W = ee'' pdas: message reports redundancy')

    ! Doubly degenerate manufactured solution: about a third of the indices have
    ! z0_i = w0_i = 0; the unique solution is still z0.
    deallocate(w, z)
    n = 40
    call random_spd(n, seed, w)
    allocate(z0(n), w0(n), z(n), zl(n))
    call random_pair(n, 0.35_dp, seed, z0, w0)
    q = w0 - matmul(w, z0)
    call check(count(z0 == 0.0_dp .and. w0 == 0.0_dp) >= 5, 'doubly degenerate: enough z_i = w_i = 0')
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0, 'doubly degenerate pdas: info 0')
    call check_small(rel_diff(z, z0), tol_direct, 'doubly degenerate pdas: z = z0')
  end subroutine test_degenerate

  !> Redundant constraints: identical rows/columns, W PSD singular.
  subroutine test_duplicate_rows()
    real(dp), allocatable :: w(:, :), b(:, :), q(:), z(:), z0(:), w0(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(pdas_stats_t) :: st
    integer :: i, j, n

    ! [1 1 0; 1 1 0; 0 0 2], q = [-1, -1, -2]: z1 + z2 = 1, z3 = 1, w = 0.
    allocate(w(3, 3), z(3))
    w = reshape([1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 2.0_dp], [3, 3])
    q = [-1.0_dp, -1.0_dp, -2.0_dp]
    call solve_lcp_pdas(w, q, z, opts, rep, stats=st)
    call check(rep%info == 0, 'duplicate rows 3x3 pdas: info 0')
    call check_close(z(1) + z(2), 1.0_dp, tol_round(16), 'duplicate rows 3x3 pdas: z1 + z2 = 1')
    call check_close(z(3), 1.0_dp, tol_round(16), 'duplicate rows 3x3 pdas: z3 = 1')
    call check(st%redundant == 1 .and. .not. st%lemke_fallback, 'duplicate rows 3x3 pdas: 1 redundant, no fallback')

    ! W = B'B with B (3n x n) whose columns 1, 2 and 5, 7 are equal; q = w0 - W z0.
    ! z is not unique but w = q + W z is (convex QP): w = w0.
    deallocate(w, z)
    n = 30
    allocate(b(3 * n, n), z0(n), w0(n), z(n))
    do j = 1, n
      do i = 1, 3 * n
        b(i, j) = 2.0_dp * urand(seed) - 1.0_dp
      end do
    end do
    b(:, 2) = b(:, 1)
    b(:, 7) = b(:, 5)
    w = matmul(transpose(b), b) / real(3 * n, dp)
    call random_pair(n, 0.2_dp, seed, z0, w0)
    z0(1) = 0.7_dp
    w0(1) = 0.0_dp
    z0(2) = 0.0_dp
    w0(2) = 0.0_dp
    q = w0 - matmul(w, z0)
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0, 'duplicate rows n30 pdas: info 0')
    call check_lcp(w, q, z, tol_direct, 'duplicate rows n30 pdas')
    call check_small(maxval(abs(q + matmul(w, z) - w0)) / maxval(abs(q)), tol_direct, &
      'duplicate rows n30 pdas: w = w0 (unique)')
  end subroutine test_duplicate_rows

  !> A zero row/column with q_i >= 0 (z_i = 0, the rest solved) and with
  !> q_i < 0 (no solution); a PSD W with no feasible z (via the Lemke fallback).
  subroutine test_zero_row_and_infeasible()
    real(dp) :: w(3, 3), z(3), w1(1, 1), z1(1), w2(2, 2), z2(2)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(pdas_stats_t) :: st

    w = reshape([2.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [3, 3])
    call solve_lcp_pdas(w, [-5.0_dp, -6.0_dp, 0.5_dp], z, opts, rep)
    call check(rep%info == 0, 'pdas zero row, q3 > 0: info 0')
    call check_small(rel_diff(z, [4.0_dp / 3.0_dp, 7.0_dp / 3.0_dp, 0.0_dp]), tol_round(16), &
      'pdas zero row, q3 > 0: z = [4/3, 7/3, 0]')
    call solve_lcp_pdas(w, [-5.0_dp, -6.0_dp, -1.0_dp], z, opts, rep)
    call check(rep%info == 1 .and. index(rep%message, 'row/column 3') > 0, &
      'pdas zero row, q3 < 0: info 1, message names index 3')
    call check(all(ieee_is_finite(z)) .and. ieee_is_finite(rep%residual), 'pdas zero row, q3 < 0: z finite')

    w1 = 0.0_dp
    call solve_lcp_pdas(w1, [-1.0_dp], z1, opts, rep)
    call check(rep%info == 1, 'pdas infeasible W = [0]: info 1')

    ! W = [1 -1; -1 1], q = [-1, -1]: w1 + w2 = -2 for every z.
    w2 = reshape([1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp], [2, 2])
    call solve_lcp_pdas(w2, [-1.0_dp, -1.0_dp], z2, opts, rep, stats=st)
    call check(rep%info == 1, 'pdas infeasible PSD: info 1')
    call check(st%lemke_fallback .and. index(rep%message, 'Lemke fallback: Lemke: ray termination') > 0, &
      'pdas infeasible PSD: decided by the Lemke fallback, message says so')
    call check(all(ieee_is_finite(z2)) .and. ieee_is_finite(rep%residual), 'pdas infeasible PSD: z finite')
  end subroutine test_zero_row_and_infeasible

  !> q = -W z0 with z0 > 0: every constraint active, z = z0 in one step.
  !> q > 0: none active, z = 0 in no step.
  subroutine test_all_and_none_active(n)
    integer, intent(in) :: n
    real(dp), allocatable :: w(:, :), q(:), z0(:), z(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i

    call random_spd(n, seed, w)
    w = w + 0.5_dp                                   ! + ee'/2: positive entries, so q < 0
    allocate(z0(n), z(n))
    do i = 1, n
      z0(i) = 0.5_dp + urand(seed)
    end do
    q = -matmul(w, z0)
    call check(all(q < 0.0_dp), 'all active: q < 0 (A_0 = all)')
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 1, 'all active pdas: info 0, 1 step')
    call check_small(rel_diff(z, z0), tol_direct, 'all active pdas: z = z0')

    do i = 1, n
      q(i) = 0.1_dp + urand(seed)
    end do
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 0 .and. all(z == 0.0_dp), 'none active pdas: z = 0, 0 steps')
  end subroutine test_all_and_none_active

  subroutine test_arguments()
    real(dp) :: w(2, 2), w23(2, 3), z(2), z3(3)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    w = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
    w23 = 1.0_dp
    call solve_lcp_pdas(w23, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -1, 'pdas arguments: W not square -> info -1')
    call solve_lcp_pdas(w, [1.0_dp, 1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -2, 'pdas arguments: q size -> info -2')
    call solve_lcp_pdas(w, [1.0_dp, 1.0_dp], z3, opts, rep)
    call check(rep%info == -3, 'pdas arguments: z size -> info -3')
    opts%tol = 0.0_dp
    call solve_lcp_pdas(w, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -4 .and. allocated(rep%message), 'pdas arguments: tol = 0 -> info -4')
    opts%tol = 1.0e-10_dp
    opts%maxit = -1
    call solve_lcp_pdas(w, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -4, 'pdas arguments: maxit < 0 -> info -4')
    opts%maxit = 0
    call solve_lcp_pdas(w, [1.0_dp, 1.0_dp], z, opts, rep, factor_mode=7)
    call check(rep%info == -6, 'pdas arguments: factor_mode 7 -> info -6')
    w(1, 1) = -1.0_dp
    call solve_lcp_pdas(w, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -1, 'pdas arguments: negative diagonal -> info -1')
    w = reshape([2.0_dp, 1.0_dp, 0.5_dp, 2.0_dp], [2, 2])
    call solve_lcp_pdas(w, [-1.0_dp, -1.0_dp], z, opts, rep)
    call check(rep%info == -1 .and. index(rep%message, 'not symmetric') > 0, &
      'pdas arguments: non-symmetric W -> info -1, message')
    w(1, 1) = 2.0_dp
    w(2, 1) = ieee_value_nan()
    call solve_lcp_pdas(w, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -1 .and. all(z == 0.0_dp), 'pdas arguments: NaN in W -> info -1, z = 0')
  end subroutine test_arguments

  real(dp) function ieee_value_nan()
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    ieee_value_nan = ieee_value(1.0_dp, ieee_quiet_nan)
  end function ieee_value_nan

  !> maxit = 1 on a problem that needs more steps: info 2, finite z >= 0 and
  !> the reported residual is that of the returned z.
  subroutine test_step_limit()
    real(dp), allocatable :: w(:, :), q(:), z(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    call contact_problem('half-plane', 200, w, q)
    allocate(z(200))
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 0 .and. rep%iterations > 1, 'step limit setup: more than one step needed')
    opts%maxit = 1
    call solve_lcp_pdas(w, q, z, opts, rep)
    call check(rep%info == 2 .and. rep%iterations == 1, 'pdas maxit 1: info 2 after 1 step')
    call check(all(ieee_is_finite(z)) .and. all(z >= 0.0_dp), 'pdas maxit 1: z finite and >= 0')
    call check(rep%residual > opts%tol, 'pdas maxit 1: residual above tol')
    call check_close(rep%residual, lcp_natural_residual(w, q, z), tol_round(16), &
      'pdas maxit 1: reported residual is that of the returned z')
  end subroutine test_step_limit

  !> An SPD matrix on which the plain active set iteration (every infeasible
  !> index changes side) cycles with period 3, shown here by an independent
  !> implementation; the least-index safeguard must solve it without Lemke.
  !> W = [9 -12 -9; -12 21 20; -9 20 25] (eigenvalues 0.50, 5.90, 48.6), q = [4 -5 -1].
  subroutine test_cycling_safeguard()
    real(dp) :: w(3, 3), q(3), z(3), zref(3), zc(3), g(3)
    real(dp), allocatable :: waa(:, :), x(:, :)
    integer, allocatable :: act(:)
    logical :: amask(3), fmask(3)
    integer :: history(30), it, k, found, code, info, i, period
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(pdas_stats_t) :: st

    w = reshape([9.0_dp, -12.0_dp, -9.0_dp, -12.0_dp, 21.0_dp, 20.0_dp, -9.0_dp, 20.0_dp, 25.0_dp], [3, 3])
    q = [4.0_dp, -5.0_dp, -1.0_dp]
    period = 0
    amask = q < 0.0_dp
    do it = 1, 30
      code = 0
      do i = 1, 3
        if (amask(i)) code = ibset(code, i - 1)
      end do
      do k = 1, it - 2
        if (history(k) == code) period = it - k
      end do
      if (period > 0) exit
      history(it) = code
      act = pack([1, 2, 3], amask)
      zc = 0.0_dp
      if (size(act) > 0) then
        waa = w(act, act)
        x = reshape(-q(act), [size(act), 1])
        call dposv('U', size(act), 1, waa, size(act), x, size(act), info)
        zc(act) = x(:, 1)
      end if
      g = q + matmul(w, zc)
      fmask = (amask .and. zc < 0.0_dp) .or. (.not. amask .and. g < 0.0_dp)
      if (.not. any(fmask)) exit
      amask = amask .neqv. fmask
    end do
    call check(period == 3, 'cycling example: plain active set iteration cycles (period 3)')

    call enumerate_lcp(w, q, zref, found)
    call check(found == 1, 'cycling example: one complementary solution by enumeration')
    call solve_lcp_pdas(w, q, z, opts, rep, stats=st)
    call check(rep%info == 0, 'cycling example pdas: info 0')
    call check_small(rel_diff(z, zref), tol_round(16), 'cycling example pdas: z = enumerated solution')
    call check(st%single_exchanges > 0 .and. .not. st%lemke_fallback, &
      'cycling example pdas: solved by the least-index safeguard, no Lemke')
    call check(index(rep%message, 'single-index steps') > 0, 'cycling example pdas: message says so')
    do k = pdas_factor_refactor, pdas_factor_update
      call solve_lcp_pdas(w, q, z, opts, rep, factor_mode=k)
      call check(rep%info == 0 .and. rel_diff(z, zref) <= tol_round(64), &
        'cycling example pdas: same in factor mode ' // achar(iachar('0') + k))
    end do
  end subroutine test_cycling_safeguard

  !> Singular PSD W (rank 2, W = G'G with G 2 x 3) where the active set method
  !> cannot finish and Lemke must.  Both solutions are unique (the null vector
  !> of W would change z_i where w_i > 0) and checked by hand.
  !> Stagnation: W = [4 2 2; 2 5 -1; 2 -1 2] (null vector (-3/2, 1, 2)),
  !> q = -1: z = [0, 1/3, 2/3], w = [1, 0, 0]; an infeasible index is linearly
  !> dependent on the active ones.
  !> Cycling: W = [5 4 -2; 4 5 -1; -2 -1 1] (null vector (-2, 1, -3)),
  !> q = [-2, -1, -3]: z = [8, 0, 19], w = [0, 12, 0]; the single-index phase
  !> repeats an active set.
  subroutine test_lemke_fallback()
    real(dp) :: w(3, 3), z(3)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    type(pdas_stats_t) :: st

    w = reshape([4.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 5.0_dp, -1.0_dp, 2.0_dp, -1.0_dp, 2.0_dp], [3, 3])
    call check_small(maxval(abs(matmul(w, [-1.5_dp, 1.0_dp, 2.0_dp]))), 0.0_dp, 'stagnation example: W singular')
    call solve_lcp_pdas(w, [-1.0_dp, -1.0_dp, -1.0_dp], z, opts, rep, stats=st)
    call check(rep%info == 0, 'stagnation example: info 0')
    call check_small(rel_diff(z, [0.0_dp, 1.0_dp / 3.0_dp, 2.0_dp / 3.0_dp]), tol_round(16), &
      'stagnation example: z = [0, 1/3, 2/3]')
    call check(st%lemke_fallback .and. index(rep%message, 'stagnation') > 0 .and. &
      index(rep%message, 'Lemke fallback: Lemke: solved') > 0, 'stagnation example: Lemke fallback, message says so')

    w = reshape([5.0_dp, 4.0_dp, -2.0_dp, 4.0_dp, 5.0_dp, -1.0_dp, -2.0_dp, -1.0_dp, 1.0_dp], [3, 3])
    call check_small(maxval(abs(matmul(w, [-2.0_dp, 1.0_dp, -3.0_dp]))), 0.0_dp, 'cycling example (singular): W singular')
    call solve_lcp_pdas(w, [-2.0_dp, -1.0_dp, -3.0_dp], z, opts, rep, stats=st)
    call check(rep%info == 0, 'cycling example (singular): info 0')
    call check_small(rel_diff(z, [8.0_dp, 0.0_dp, 19.0_dp]), tol_round(16), 'cycling example (singular): z = [8, 0, 19]')
    call check(st%lemke_fallback .and. st%single_exchanges > 0 .and. index(rep%message, 'cycling') > 0 .and. &
      index(rep%message, 'Lemke fallback: Lemke: solved') > 0, 'cycling example (singular): Lemke fallback, message says so')
  end subroutine test_lemke_fallback

  !> The update path (appends, Givens deletions, trailing re-factors) gives the
  !> answer of re-factoring at every step, with the same number of steps; the
  !> two differ by round-off amplified by cond(W_AA) (about 1e5 for the
  !> foundation kernel at n = 300), hence 4 eps cond_contact (measured 0.35).
  subroutine test_update_equals_refactor()
    real(dp), allocatable :: w(:, :), q(:), za(:), zr(:), zu(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: repa, repr, repu
    type(pdas_stats_t) :: sta, str, stu
    integer :: n, kind_w
    character(len=10), parameter :: kinds_w(2) = ['half-plane', 'foundation']

    do kind_w = 1, 2
      n = 300
      call contact_problem(kinds_w(kind_w), n, w, q)
      allocate(za(n), zr(n), zu(n))
      call solve_lcp_pdas(w, q, za, opts, repa, pdas_factor_auto, sta)
      call solve_lcp_pdas(w, q, zr, opts, repr, pdas_factor_refactor, str)
      call solve_lcp_pdas(w, q, zu, opts, repu, pdas_factor_update, stu)
      call check(repa%info == 0 .and. repr%info == 0 .and. repu%info == 0, &
        trim(kinds_w(kind_w)) // ' update vs refactor: all info 0')
      call check(str%factorizations == str%steps .and. str%deleted == 0 .and. str%appended == 0, &
        trim(kinds_w(kind_w)) // ' refactor mode: one factor per step, no update')
      call check(stu%factorizations == 1 .and. stu%deleted > 0, &
        trim(kinds_w(kind_w)) // ' update mode: one factor, then deletions only')
      call check(repa%iterations == repr%iterations .and. repu%iterations == repr%iterations, &
        trim(kinds_w(kind_w)) // ' update vs refactor: same number of Newton steps')
      call check_small(rel_diff(zu, zr), tol_round(4, cond_contact), trim(kinds_w(kind_w)) // ' update mode = refactor mode')
      call check_small(rel_diff(za, zr), tol_round(4, cond_contact), trim(kinds_w(kind_w)) // ' auto mode = refactor mode')
      deallocate(za, zr, zu)
    end do

    ! A random SPD problem with many exchanges per step.
    n = 150
    call random_spd(n, seed, w)
    q = [(2.0_dp * urand(seed) - 1.0_dp, kind_w = 1, n)]
    allocate(zr(n), zu(n))
    call solve_lcp_pdas(w, q, zr, opts, repr, pdas_factor_refactor)
    call solve_lcp_pdas(w, q, zu, opts, repu, pdas_factor_update, stu)
    call check(repr%info == 0 .and. repu%info == 0 .and. stu%deleted > 0 .and. stu%appended > 0, &
      'random n150 update mode: info 0, deletions and appends')
    call check_small(rel_diff(zu, zr), tol_round(32), 'random n150 update mode = refactor mode')
  end subroutine test_update_equals_refactor

  !> Contact-like LCP with a manufactured solution (module comment of
  !> contact_problem): all three solvers recover z0.
  subroutine test_contact_problems()
    real(dp), allocatable :: w(:, :), q(:), z0(:), z(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: kind_w, n, info
    real(dp), allocatable :: c(:, :)
    character(len=10), parameter :: kinds_w(2) = ['half-plane', 'foundation']

    n = 200
    do kind_w = 1, 2
      call contact_problem(kinds_w(kind_w), n, w, q, z0)
      c = w
      call dpotrf('L', n, c, n, info)
      call check(info == 0, trim(kinds_w(kind_w)) // ' n200: W is positive definite')
      call check(count(z0 > 0.0_dp) == n / 2, trim(kinds_w(kind_w)) // ' n200: half the nodes in contact')
      allocate(z(n))
      call solve_lcp_pdas(w, q, z, opts, rep)
      call check(rep%info == 0, trim(kinds_w(kind_w)) // ' n200 pdas: info 0')
      call check_small(rel_diff(z, z0), tol_round(16, cond_contact), trim(kinds_w(kind_w)) // ' n200 pdas: z = z0')
      call solve_lcp_lemke(w, q, z, opts, rep)
      call check_small(rel_diff(z, z0), tol_round(16, cond_contact), trim(kinds_w(kind_w)) // ' n200 lemke: z = z0')
      z = 0.0_dp
      call solve_lcp_pgs(w, q, z, opts, rep)
      call check(rep%info == 0 .or. rep%info == 2, trim(kinds_w(kind_w)) // ' n200 pgs: converged or limit')
      deallocate(z)
    end do
  end subroutine test_contact_problems

  !> Contact-like Delassus matrices on n nodes x_i = -1 + (i - 1/2) h, h = 2/n,
  !> with a manufactured solution, half the nodes in contact (|x| < 1/2):
  !>   half-plane  W_ij = 1/(pi h) int_{e_j} log(4 / |x_i - s|) ds, the surface
  !>               compliance of an elastic half-plane (element-integrated
  !>               pressure, kernel shifted by log 4 so that it is positive
  !>               definite on [-1, 1]); cond(W) ~ n
  !>   foundation  W = K^-1, K = tridiag(-1, 2, -1)/h + h I, a string on a soft
  !>               elastic foundation, ends fixed; cond(W) ~ n^2
  !> z0_i = h sqrt(1/4 - x_i^2) on the contact (Hertz-like), w0_i = c (|x_i| - 1/2)^(3/2)
  !> outside, c = max(W z0); q = w0 - W z0.
  subroutine contact_problem(kind_w, n, w, q, z0_out)
    character(len=*), intent(in) :: kind_w
    integer, intent(in) :: n
    real(dp), allocatable, intent(out) :: w(:, :), q(:)
    real(dp), allocatable, intent(out), optional :: z0_out(:)
    real(dp), parameter :: pi = 3.14159265358979323846_dp
    real(dp), allocatable :: x(:), z0(:), w0(:), wz(:), dg(:), off(:)
    real(dp) :: h, delta
    integer :: i, j, info

    h = 2.0_dp / real(n, dp)
    allocate(x(n), w(n, n), z0(n), w0(n))
    x = [(-1.0_dp + (real(i, dp) - 0.5_dp) * h, i = 1, n)]
    if (kind_w == 'half-plane') then
      do j = 1, n
        do i = 1, n
          delta = x(j) - x(i)
          w(i, j) = (h * log(4.0_dp) + antiderivative(delta + 0.5_dp * h) - antiderivative(delta - 0.5_dp * h)) &
            / (pi * h)
        end do
      end do
    else
      allocate(dg(n), off(max(n - 1, 1)))
      dg = 2.0_dp / h + h
      off = -1.0_dp / h
      w = 0.0_dp
      do i = 1, n
        w(i, i) = 1.0_dp
      end do
      call dptsv(n, n, dg, off, w, n, info)             ! W = K^-1
      do j = 1, n                                        ! symmetrize the round-off
        do i = j + 1, n
          w(i, j) = 0.5_dp * (w(i, j) + w(j, i))
          w(j, i) = w(i, j)
        end do
      end do
    end if
    z0 = 0.0_dp
    w0 = 0.0_dp
    where (abs(x) < 0.5_dp) z0 = h * sqrt(0.25_dp - x**2)
    allocate(wz(n))
    wz = matmul(w, z0)
    where (abs(x) > 0.5_dp) w0 = maxval(wz) * (abs(x) - 0.5_dp)**1.5_dp
    q = w0 - wz
    if (present(z0_out)) z0_out = z0
  end subroutine contact_problem

  !> F(t) = int_0^t -log|s| ds = t - t log|t|, F(0) = 0.
  pure real(dp) function antiderivative(t)
    real(dp), intent(in) :: t
    if (t == 0.0_dp) then
      antiderivative = 0.0_dp
    else
      antiderivative = t - t * log(abs(t))
    end if
  end function antiderivative

  !> Informational: Newton steps / pivots / sweeps and CPU time of the three
  !> solvers on the contact-like problems; also checks that PDAS and Lemke
  !> found z0.  z is determined to about cond(W) eps: cond(W) reaches 7e6 for
  !> the foundation kernel at n = 5000, where z and z0 (both with residual
  !> 1e-15) differ by 2e-8, hence the comparison to 64 eps cond_bench, 1e-7.
  subroutine benchmark_table()
    integer, parameter :: sizes(4) = [100, 500, 2000, 5000]
    integer, parameter :: pgs_cap = 5000
    character(len=10), parameter :: kinds_w(2) = ['half-plane', 'foundation']
    real(dp), allocatable :: w(:, :), q(:), z0(:), z(:)
    type(lcp_options_t) :: opts, pgs_opts
    type(lcp_report_t) :: rep
    type(pdas_stats_t) :: st
    character(len=16) :: env
    integer :: k, n, kind_w, nmax, env_len, env_status
    real(dp) :: t0, t_pdas, t_lemke, t_pgs, t_ref
    integer :: it_ref
    character(len=20) :: ref_text
    logical :: bench

    call get_environment_variable('LCP_BENCH', env, env_len, env_status)
    bench = env_status == 0 .and. env(1:max(env_len, 1)) == '1'
    nmax = 500
    if (bench) nmax = 5000
    pgs_opts%tol = 1.0e-10_dp
    pgs_opts%maxit = pgs_cap
    write(output_unit, '(a)') '# Contact-like LCP (manufactured, half the nodes in contact), tol 1e-10, CPU time in s'
    write(output_unit, '(a)') '# kernel         n contact |  PDAS steps     time  refactor-each-step |' // &
      ' Lemke pivots     time |  PGS sweeps     time  residual'
    do kind_w = 1, 2
      do k = 1, size(sizes)
        n = sizes(k)
        if (n > nmax) cycle
        call contact_problem(kinds_w(kind_w), n, w, q, z0)
        allocate(z(n))
        t0 = process_time()
        call solve_lcp_pdas(w, q, z, opts, rep, stats=st)
        t_pdas = process_time() - t0
        call check(rep%info == 0 .and. rep%residual <= opts%tol .and. rel_diff(z, z0) <= tol_round(64, cond_bench), &
          'benchmark ' // trim(kinds_w(kind_w)) // ' n' // itoa(n) // ' pdas: z = z0')
        ! Re-factoring at every step costs steps x |A|^3 / 3 flops: only when affordable.
        t_ref = -1.0_dp
        it_ref = -1
        if (real(st%steps, dp) * real(st%max_active, dp)**3 / 3.0_dp <= 1.0e11_dp) then
          t0 = process_time()
          call solve_lcp_pdas(w, q, z, opts, rep, pdas_factor_refactor)
          t_ref = process_time() - t0
          it_ref = rep%iterations
          call check(rep%info == 0 .and. it_ref == st%steps .and. rel_diff(z, z0) <= tol_round(64, cond_bench), &
            'benchmark ' // trim(kinds_w(kind_w)) // ' n' // itoa(n) // ' pdas refactor mode: same steps, z = z0')
        end if
        t0 = process_time()
        call solve_lcp_lemke(w, q, z, opts, rep)
        t_lemke = process_time() - t0
        call check(rep%info == 0 .and. rel_diff(z, z0) <= tol_round(64, cond_bench), &
          'benchmark ' // trim(kinds_w(kind_w)) // ' n' // itoa(n) // ' lemke: z = z0')
        ref_text = '           (not run)'
        if (t_ref >= 0.0_dp) write(ref_text, '(f20.4)') t_ref
        write(output_unit, '(a, a10, i6, i8, a, i12, f9.4, a20, a, i13, f9.4, a)', advance='no') '# ', &
          kinds_w(kind_w), n, count(z0 > 0.0_dp), ' |', st%steps, t_pdas, ref_text, ' |', rep%iterations, t_lemke, ' |'
        z = 0.0_dp
        t0 = process_time()
        call solve_lcp_pgs(w, q, z, pgs_opts, rep)
        t_pgs = process_time() - t0
        write(output_unit, '(i12, a1, f8.4, es10.2)') rep%iterations, merge('*', ' ', rep%info /= 0), &
          t_pgs, rep%residual
        write(output_unit, '(a, i0, a, i0, a, i0, a, i0, a, i0, a, i0, a, i0, a, i0)') '#     PDAS: max |A| ', &
          st%max_active, ', full exchanges ', st%full_exchanges, ', single ', st%single_exchanges, &
          ', factors ', st%factorizations, ', trailing re-factors ', st%trailing_refactors, &
          ', appended ', st%appended, ', Givens deletions ', st%deleted, ', refinements ', st%refinements
        deallocate(z)
      end do
    end do
    write(output_unit, '(a, i0, a)') '# * PGS stopped before tol (cap ', pgs_cap, &
      ' sweeps, or stagnation); refactor-each-step not run above 1e11 flops;' // &
      ' n = 2000 and 5000 only with LCP_BENCH=1;' // &
      ' single-thread times with OPENBLAS_NUM_THREADS=1'
  end subroutine benchmark_table

  function itoa(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function itoa

end program test_lcp_newton
