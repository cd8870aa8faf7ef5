!> Unit tests of lcp_solvers: Lemke and PGS on LCP(W, q) against closed forms,
!> manufactured solutions (q = w0 - W z0 with z0, w0 >= 0 complementary, so z0
!> is a solution, the only one when W is definite), the KKT conditions of
!> min 1/2 z'Wz + q'z, z >= 0 checked with an independent Cholesky solve on the
!> active set, and the LCP invariants recomputed here.
program test_lcp_solvers
  use kinds, only: dp, i8
  use testing, only: check, check_close, check_small, finish_tests, urand, random_spd, random_pair, tol_round
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_pgs, &
    lcp_natural_residual, scale_lcp
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none

  interface
    subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: info
    end subroutine dposv
  end interface

  ! Tolerances, in the units of testing (tol_round: n eps scale).  W from
  ! random_spd has eigenvalues in [1e-3, 0.83] (its shift, and the largest
  ! of A'A / (3n), (1 + sqrt(1/3))^2 / 3 by Marchenko-Pastur): cond(W) <=
  ! cond_w.  Lemke ends on a direct solve of its basis: z is good to a few
  ! tens of roundings times cond(W) (tol_lemke; measured <= 8 eps).  PGS stops
  ! at a scaled residual of opts%tol: z is within cond(W) opts%tol of the
  ! solution (measured <= 4 opts%tol); on the 2 x 2 and 3 x 3 closed forms
  ! cond(W) = 3, hence 10 opts%tol.
  real(dp), parameter :: cond_w = 1.0e3_dp
  real(dp), parameter :: tol_lemke = 64 * cond_w * epsilon(1.0_dp)
  integer(i8) :: seed
  seed = 20240601_i8

  call test_scaling()
  call test_natural_residual()
  call test_tiny_closed_forms()
  call test_random_spd(5, 'n5')
  call test_random_spd(40, 'n40')
  call test_random_spd(200, 'n200')
  call test_manufactured(40)
  call test_badly_scaled(30)
  call test_degenerate()
  call test_duplicate_rows()
  call test_beale()
  call test_zero_row()
  call test_infeasible()
  call test_all_and_none_active(40)
  call test_arguments()
  call test_pgs_limits()
  call finish_tests()

contains

  ! ---------------------------------------------------------------------------
  ! Helpers
  ! ---------------------------------------------------------------------------

  !> The LCP invariants of z recomputed here, on the diagonally scaled problem
  !> (d_i = 1/sqrt(W_ii), 1 when W_ii = 0): z >= 0, natural residual
  !> ||min(zs, ws)|| / max(1, ||qs||) <= tol, and scaled complementarity.
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
    zs = z / d
    ws = d * (q + matmul(w, z))
    qs = d * q
    qscale = max(1.0_dp, maxval(abs(qs)))
    call check(all(z >= 0.0_dp) .and. all(ieee_is_finite(z)), name // ' z >= 0 and finite')
    call check_small(max(0.0_dp, -minval(ws)) / qscale, tol, name // ' w >= -tol')
    call check_small(maxval(abs(min(zs, ws))) / qscale, tol, name // ' natural residual')
    call check_small(maxval(abs(zs * ws)) / (max(1.0_dp, maxval(zs)) * qscale), tol, &
      name // ' complementarity')
  end subroutine check_lcp

  !> KKT conditions of min 1/2 z'Wz + q'z, z >= 0 for SPD W, independently: on
  !> the active set A = {z_i > 0}, W_AA x = -q_A (Cholesky, dposv) must give
  !> x = z_A > 0, and the gaps off A must be >= 0.
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
    call check_small(maxval(abs(x(:, 1) - z(act))) / maxval(abs(z)), tol_lemke, &
      name // ' KKT: z_A solves W_AA z_A = -q_A')
    call check(all(x(:, 1) > 0.0_dp), name // ' KKT: z_A > 0')
    if (size(off) > 0) then
      gap = q(off) + matmul(w(off, act), x(:, 1))
      call check(minval(gap) >= -tol_lemke * max(1.0_dp, maxval(abs(q))), &
        name // ' KKT: gaps off the active set >= 0')
    end if
  end subroutine check_kkt

  real(dp) function rel_diff(a, b)
    real(dp), intent(in) :: a(:), b(:)
    rel_diff = maxval(abs(a - b)) / max(tiny(1.0_dp), maxval(abs(b)))
  end function rel_diff

  ! ---------------------------------------------------------------------------
  ! Tests
  ! ---------------------------------------------------------------------------

  !> W = [4 2; 2 9], q = [2, 3]: d = [1/2, 1/3], Ws = [1 1/3; 1/3 1], qs = [1, 1].
  subroutine test_scaling()
    real(dp) :: w(2, 2), q(2), d(2), ws(2, 2), qs(2)
    w = reshape([4.0_dp, 2.0_dp, 2.0_dp, 9.0_dp], [2, 2])
    q = [2.0_dp, 3.0_dp]
    call scale_lcp(w, q, d, ws, qs)
    call check_close(d(1), 0.5_dp, tol_round(4), 'scale: d1 = 1/2')
    call check_close(d(2), 1.0_dp / 3.0_dp, tol_round(4), 'scale: d2 = 1/3')
    call check_close(ws(1, 1), 1.0_dp, tol_round(4), 'scale: Ws11 = 1')
    call check_close(ws(2, 2), 1.0_dp, tol_round(4), 'scale: Ws22 = 1')
    call check_close(ws(1, 2), 1.0_dp / 3.0_dp, tol_round(4), 'scale: Ws12 = 1/3')
    call check_close(ws(2, 1), 1.0_dp / 3.0_dp, tol_round(4), 'scale: Ws21 = 1/3')
    call check_close(qs(1), 1.0_dp, tol_round(4), 'scale: qs1 = 1')
    call check_close(qs(2), 1.0_dp, tol_round(4), 'scale: qs2 = 1')
  end subroutine test_scaling

  !> W = diag(4, 1), q = [1, -2], z = [1/2, 1]: zs = [1, 1], ws = [3/2, -1],
  !> qs = [1/2, -2], so r = |min(1, -1)| / 2 = 1/2.  The exact solution
  !> z = [0, 2] has r = 0.
  subroutine test_natural_residual()
    real(dp) :: w(2, 2), q(2)
    w = reshape([4.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    q = [1.0_dp, -2.0_dp]
    call check_close(lcp_natural_residual(w, q, [0.5_dp, 1.0_dp]), 0.5_dp, tol_round(4), &
      'natural residual: hand value 1/2')
    call check_small(lcp_natural_residual(w, q, [0.0_dp, 2.0_dp]), 0.0_dp, &
      'natural residual: 0 at the solution')
  end subroutine test_natural_residual

  subroutine test_tiny_closed_forms()
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    real(dp) :: w1(1, 1), w2(2, 2), z1(1), z2(2)
    integer :: solver
    character(len=5) :: tag

    w1 = 2.0_dp
    w2 = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
    opts%tol = 1.0e-13_dp
    do solver = 1, 2
      tag = merge('lemke', 'pgs  ', solver == 1)
      ! 1x1: 2 z - 4 = 0 -> z = 2.
      z1 = 0.0_dp
      call run(solver, w1, [-4.0_dp], z1, opts, rep)
      call check(rep%info == 0, trim(tag) // ' 1x1 active: info 0')
      call check_close(z1(1), 2.0_dp, 10 * opts%tol, trim(tag) // ' 1x1 active: z = 2')
      ! 1x1 with q > 0: z = 0.
      z1 = 5.0_dp
      call run(solver, w1, [3.0_dp], z1, opts, rep)
      call check(rep%info == 0 .and. z1(1) == 0.0_dp, trim(tag) // ' 1x1 inactive: z = 0')
      ! [2 1; 1 2] z = [5, 6]: z = [4/3, 7/3], both active.
      z2 = 0.0_dp
      call run(solver, w2, [-5.0_dp, -6.0_dp], z2, opts, rep)
      call check(rep%info == 0, trim(tag) // ' 2x2 both active: info 0')
      call check_small(rel_diff(z2, [4.0_dp / 3.0_dp, 7.0_dp / 3.0_dp]), 10 * opts%tol, &
        trim(tag) // ' 2x2 both active: z = [4/3, 7/3]')
      ! q = [-4, 3]: z = [2, 0], w2 = 3 + 2 = 5.
      z2 = 0.0_dp
      call run(solver, w2, [-4.0_dp, 3.0_dp], z2, opts, rep)
      call check_small(rel_diff(z2, [2.0_dp, 0.0_dp]), 10 * opts%tol, &
        trim(tag) // ' 2x2 one active: z = [2, 0]')
      ! q = [-1, -5]: both active would give z1 = -1 < 0; z = [0, 5/2], w1 = 3/2.
      z2 = 0.0_dp
      call run(solver, w2, [-1.0_dp, -5.0_dp], z2, opts, rep)
      call check_small(rel_diff(z2, [0.0_dp, 2.5_dp]), 10 * opts%tol, &
        trim(tag) // ' 2x2 one active, q both negative: z = [0, 5/2]')
    end do
  end subroutine test_tiny_closed_forms

  subroutine run(solver, w, q, z, opts, rep)
    integer, intent(in) :: solver
    real(dp), intent(in) :: w(:, :), q(:)
    real(dp), intent(inout) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(out) :: rep
    if (solver == 1) then
      call solve_lcp_lemke(w, q, z, opts, rep)
    else
      call solve_lcp_pgs(w, q, z, opts, rep)
    end if
  end subroutine run

  !> Random SPD W, random q in (-1, 1): both solvers solve, agree, satisfy KKT.
  subroutine test_random_spd(n, tag)
    integer, intent(in) :: n
    character(len=*), intent(in) :: tag
    real(dp), allocatable :: w(:, :), q(:), zl(:), zp(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i

    call random_spd(n, seed, w)
    allocate(q(n), zl(n), zp(n))
    do i = 1, n
      q(i) = 2.0_dp * urand(seed) - 1.0_dp
    end do
    call solve_lcp_lemke(w, q, zl, opts, rep)
    call check(rep%info == 0, 'random ' // tag // ' lemke: info 0')
    call check(rep%iterations > 0, 'random ' // tag // ' lemke: pivots counted')
    call check_small(rep%residual, opts%tol, 'random ' // tag // ' lemke: reported residual <= tol')
    call check_lcp(w, q, zl, tol_lemke, 'random ' // tag // ' lemke')
    call check_kkt(w, q, zl, 'random ' // tag // ' lemke')

    zp = 0.0_dp
    opts%tol = 1.0e-13_dp
    call solve_lcp_pgs(w, q, zp, opts, rep)
    call check(rep%info == 0, 'random ' // tag // ' pgs: info 0')
    call check_lcp(w, q, zp, cond_w * opts%tol, 'random ' // tag // ' pgs')
    call check_small(rel_diff(zp, zl), cond_w * opts%tol, 'random ' // tag // ' lemke and pgs agree')

    ! Over-relaxed PGS reaches the same solution.
    zp = 0.0_dp
    opts%omega = 1.5_dp
    call solve_lcp_pgs(w, q, zp, opts, rep)
    call check(rep%info == 0, 'random ' // tag // ' pgs omega 1.5: info 0')
    call check_small(rel_diff(zp, zl), cond_w * opts%tol, 'random ' // tag // ' pgs omega 1.5 agrees')
  end subroutine test_random_spd

  !> q = w0 - W z0: the unique solution is z0 (W definite).
  subroutine test_manufactured(n)
    integer, intent(in) :: n
    real(dp), allocatable :: w(:, :), q(:), z0(:), w0(:), z(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep

    call random_spd(n, seed, w)
    allocate(z0(n), w0(n), z(n))
    call random_pair(n, 0.0_dp, seed, z0, w0)
    q = w0 - matmul(w, z0)
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'manufactured lemke: info 0')
    call check_small(rel_diff(z, z0), tol_lemke, 'manufactured lemke: z = z0')
    z = 0.0_dp
    opts%tol = 1.0e-13_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 0, 'manufactured pgs: info 0')
    call check_small(rel_diff(z, z0), cond_w * opts%tol, 'manufactured pgs: z = z0')
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

    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'badly scaled lemke: info 0')
    call check_lcp(w, q, z, tol_lemke, 'badly scaled lemke')
    call check_small(rel_diff(z * dd, za), tol_lemke, 'badly scaled lemke: D z = za')
    z = 0.0_dp
    opts%tol = 1.0e-13_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 0, 'badly scaled pgs: info 0')
    call check_lcp(w, q, z, cond_w * opts%tol, 'badly scaled pgs')
    call check_small(rel_diff(z * dd, za), cond_w * opts%tol, 'badly scaled pgs: D z = za')
  end subroutine test_badly_scaled

  !> Degenerate problems: zeros in q, ties in every ratio test, z_i = w_i = 0.
  subroutine test_degenerate()
    real(dp), allocatable :: w(:, :), q(:), z(:), z0(:), w0(:), zp(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i, n

    ! q >= 0 with zeros: z = 0 (w = q, w_i = 0 where q_i = 0).
    call random_spd(6, seed, w)
    q = [0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 2.0_dp, 0.0_dp]
    allocate(z(6))
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0 .and. all(z == 0.0_dp), 'degenerate q >= 0 with zeros lemke: z = 0')
    z = 1.0_dp
    opts%tol = 1.0e-13_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 0, 'degenerate q >= 0 with zeros pgs: info 0')
    call check_small(maxval(z), cond_w * opts%tol, 'degenerate q >= 0 with zeros pgs: z = 0')

    ! W = I, q = [0, -1, 0, 0]: z = [0, 1, 0, 0], w = 0 everywhere.
    deallocate(w, z)
    n = 4
    allocate(w(n, n), z(n))
    w = 0.0_dp
    do i = 1, n
      w(i, i) = 1.0_dp
    end do
    q = [0.0_dp, -1.0_dp, 0.0_dp, 0.0_dp]
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'degenerate W = I, q with zeros lemke: info 0')
    call check_small(rel_diff(z, [0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp]), tol_round(16), &
      'degenerate W = I, q with zeros lemke: z = e2')

    ! W = I (10 x 10), q = -1: every ratio test is a 10-fold tie; z = 1.
    deallocate(w, z)
    n = 10
    allocate(w(n, n), z(n))
    w = 0.0_dp
    do i = 1, n
      w(i, i) = 1.0_dp
    end do
    q = [(-1.0_dp, i = 1, n)]
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'ties W = I, q = -1 lemke: info 0 (no cycling)')
    call check_small(rel_diff(z, [(1.0_dp, i = 1, n)]), tol_round(16), 'ties W = I, q = -1 lemke: z = 1')

    ! W = 2 I + e e' (10 x 10), q = -1: z = e / 12, w = 0.
    w = 1.0_dp
    do i = 1, n
      w(i, i) = 3.0_dp
    end do
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'ties W = 2I + ee'', q = -1 lemke: info 0 (no cycling)')
    call check_small(rel_diff(z, [(1.0_dp / 12.0_dp, i = 1, n)]), tol_round(16), &
      'ties W = 2I + ee'', q = -1 lemke: z = 1/12')
    call check(rep%iterations <= 10 * n + 100, 'ties W = 2I + ee'' lemke: within the pivot limit')

    ! W = e e' (rank one, 8 x 8), q = -1: any z >= 0 with sum z = 1 solves it.
    deallocate(w, z)
    n = 8
    allocate(w(n, n), z(n))
    w = 1.0_dp
    q = [(-1.0_dp, i = 1, n)]
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'rank-one W = ee'' lemke: info 0')
    call check_close(sum(z), 1.0_dp, tol_round(16), 'rank-one W = ee'' lemke: sum z = 1')
    call check_lcp(w, q, z, tol_round(64), 'rank-one W = ee'' lemke')

    ! Doubly degenerate manufactured solution: about a third of the indices have
    ! z0_i = w0_i = 0; the unique solution is still z0.
    deallocate(w, z)
    n = 40
    call random_spd(n, seed, w)
    allocate(z0(n), w0(n), z(n), zp(n))
    call random_pair(n, 0.35_dp, seed, z0, w0)
    q = w0 - matmul(w, z0)
    call check(count(z0 == 0.0_dp .and. w0 == 0.0_dp) >= 5, 'doubly degenerate: enough z_i = w_i = 0')
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'doubly degenerate lemke: info 0')
    call check_small(rel_diff(z, z0), tol_lemke, 'doubly degenerate lemke: z = z0')
    zp = 0.0_dp
    opts%tol = 1.0e-13_dp
    call solve_lcp_pgs(w, q, zp, opts, rep)
    call check(rep%info == 0, 'doubly degenerate pgs: info 0')
    call check_small(rel_diff(zp, z0), cond_w * opts%tol, 'doubly degenerate pgs: z = z0')
  end subroutine test_degenerate

  !> Redundant constraints: two identical rows/columns, W PSD singular.
  subroutine test_duplicate_rows()
    real(dp), allocatable :: w(:, :), b(:, :), q(:), z(:), z0(:), w0(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i, j, n

    ! [1 1 0; 1 1 0; 0 0 2], q = [-1, -1, -2]: z1 + z2 = 1, z3 = 1, w = 0.
    w = reshape([1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 2.0_dp], [3, 3])
    q = [-1.0_dp, -1.0_dp, -2.0_dp]
    allocate(z(3))
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'duplicate rows 3x3 lemke: info 0')
    call check_close(z(1) + z(2), 1.0_dp, tol_round(16), 'duplicate rows 3x3 lemke: z1 + z2 = 1')
    call check_close(z(3), 1.0_dp, tol_round(16), 'duplicate rows 3x3 lemke: z3 = 1')
    z = 0.0_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 0, 'duplicate rows 3x3 pgs: info 0')
    call check_close(z(1) + z(2), 1.0_dp, 10 * opts%tol, 'duplicate rows 3x3 pgs: z1 + z2 = 1')

    ! W = B'B with B (3n x n) whose columns 1 and 2 are equal; q = w0 - W z0.
    ! z is not unique but w = q + W z is (convex QP): w = w0.
    deallocate(z)
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
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'duplicate rows n30 lemke: info 0 (terminates)')
    call check_lcp(w, q, z, tol_lemke, 'duplicate rows n30 lemke')
    call check_small(maxval(abs(q + matmul(w, z) - w0)) / maxval(abs(q)), tol_lemke, &
      'duplicate rows n30 lemke: w = w0 (unique)')
    z = 0.0_dp
    opts%tol = 1.0e-12_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 0, 'duplicate rows n30 pgs: info 0')
    ! the residual PGS stops at, scaled here by max(1, |qs|), not by its own norm
    call check_lcp(w, q, z, 100 * opts%tol, 'duplicate rows n30 pgs')
    call check_small(maxval(abs(q + matmul(w, z) - w0)) / maxval(abs(q)), cond_w * opts%tol, &
      'duplicate rows n30 pgs: w = w0 (unique)')
  end subroutine test_duplicate_rows

  !> Beale's (1955) LP, the classic example on which the simplex method cycles
  !> under the textbook pivot rule:
  !>   min -3/4 x1 + 150 x2 - 1/50 x3 + 6 x4
  !>   s.t. 1/4 x1 - 60 x2 - 1/25 x3 + 9 x4 <= 0
  !>        1/2 x1 - 90 x2 - 1/50 x3 + 3 x4 <= 0
  !>        x3 <= 1,  x >= 0
  !> embedded in the LCP M = [I A'; -A I], q = [c; b] (the KKT system of the LP
  !> with unit proximal terms), whose q has two zeros (degenerate) and whose
  !> M is positive definite but not symmetric.  Lemke must terminate with a
  !> complementary solution (unique, M being a P-matrix).
  subroutine test_beale()
    real(dp) :: a(3, 4), m(7, 7), q(7), z(7)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i
    a = transpose(reshape([0.25_dp, -60.0_dp, -0.04_dp, 9.0_dp, &
                           0.5_dp, -90.0_dp, -0.02_dp, 3.0_dp, &
                           0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp], [4, 3]))
    m = 0.0_dp
    do i = 1, 7
      m(i, i) = 1.0_dp
    end do
    m(1:4, 5:7) = transpose(a)
    m(5:7, 1:4) = -a
    q = [-0.75_dp, 150.0_dp, -0.02_dp, 6.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]
    call solve_lcp_lemke(m, q, z, opts, rep)
    call check(rep%info == 0, 'Beale degenerate LCP lemke: info 0 (terminates)')
    ! 64 roundings on the scale of M's largest entry, 150
    call check_lcp(m, q, z, tol_round(64, 150.0_dp), 'Beale degenerate LCP lemke')
  end subroutine test_beale

  !> A zero row/column (redundant constraint) with q_i >= 0: z_i = 0 and the
  !> rest solved; W(3,:) = 0.
  subroutine test_zero_row()
    real(dp) :: w(3, 3), z(3)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: solver
    w = reshape([2.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [3, 3])
    opts%tol = 1.0e-13_dp
    do solver = 1, 2
      z = 0.0_dp
      call run(solver, w, [-5.0_dp, -6.0_dp, 0.5_dp], z, opts, rep)
      call check(rep%info == 0, trim(merge('lemke', 'pgs  ', solver == 1)) // ' zero row, q3 > 0: info 0')
      call check_small(rel_diff(z, [4.0_dp / 3.0_dp, 7.0_dp / 3.0_dp, 0.0_dp]), 10 * opts%tol, &
        trim(merge('lemke', 'pgs  ', solver == 1)) // ' zero row, q3 > 0: z = [4/3, 7/3, 0]')
      z = 0.0_dp
      call run(solver, w, [-5.0_dp, -6.0_dp, -1.0_dp], z, opts, rep)
      call check(rep%info == 1, trim(merge('lemke', 'pgs  ', solver == 1)) // ' zero row, q3 < 0: info 1')
      call check(index(rep%message, 'row/column 3') > 0, &
        trim(merge('lemke', 'pgs  ', solver == 1)) // ' zero row, q3 < 0: message names index 3')
      call check(all(ieee_is_finite(z)), trim(merge('lemke', 'pgs  ', solver == 1)) // &
        ' zero row, q3 < 0: z finite')
    end do
  end subroutine test_zero_row

  !> Infeasible LCPs.  W = [0], q = [-1]: w = -1 whatever z.  W = [1 -1; -1 1],
  !> q = [-1, -1]: w1 + w2 = -2 for every z, so w >= 0 is impossible.
  subroutine test_infeasible()
    real(dp) :: w1(1, 1), z1(1), w2(2, 2), z2(2)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep

    w1 = 0.0_dp
    call solve_lcp_lemke(w1, [-1.0_dp], z1, opts, rep)
    call check(rep%info == 1, 'infeasible W = [0] lemke: info 1')
    call check(index(rep%message, 'row/column 1') > 0, 'infeasible W = [0] lemke: message names index 1')
    z1 = 0.0_dp
    call solve_lcp_pgs(w1, [-1.0_dp], z1, opts, rep)
    call check(rep%info == 1 .and. all(ieee_is_finite(z1)), 'infeasible W = [0] pgs: info 1, z finite')

    w2 = reshape([1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp], [2, 2])
    call solve_lcp_lemke(w2, [-1.0_dp, -1.0_dp], z2, opts, rep)
    call check(rep%info == 1, 'infeasible PSD lemke: info 1')
    call check(index(rep%message, 'Lemke: ray termination at pivot') == 1, &
      'infeasible PSD lemke: ray termination message')
    call check(all(ieee_is_finite(z2)) .and. ieee_is_finite(rep%residual), 'infeasible PSD lemke: z finite')
    z2 = 0.0_dp
    call solve_lcp_pgs(w2, [-1.0_dp, -1.0_dp], z2, opts, rep)
    call check(rep%info == 2 .or. rep%info == 3, 'infeasible PSD pgs: info 2 or 3')
    call check(all(ieee_is_finite(z2)) .and. all(z2 >= 0.0_dp), 'infeasible PSD pgs: z finite')
    call check(rep%residual > opts%tol .and. ieee_is_finite(rep%residual), &
      'infeasible PSD pgs: residual reported, > tol')
    call check(allocated(rep%message), 'infeasible PSD pgs: message')
    if (allocated(rep%message)) call check(index(rep%message, 'residual') > 0, &
      'infeasible PSD pgs: message gives the residual')
  end subroutine test_infeasible

  !> q = -W z0 with z0 > 0: every constraint active, z = z0, w = 0.
  !> q > 0: none active, z = 0 (PGS started away from it).
  subroutine test_all_and_none_active(n)
    integer, intent(in) :: n
    real(dp), allocatable :: w(:, :), q(:), z0(:), z(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i

    call random_spd(n, seed, w)
    allocate(z0(n), z(n))
    do i = 1, n
      z0(i) = 0.5_dp + urand(seed)
    end do
    q = -matmul(w, z0)
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0, 'all active lemke: info 0')
    call check_small(rel_diff(z, z0), tol_lemke, 'all active lemke: z = z0')
    z = 0.0_dp
    opts%tol = 1.0e-13_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 0, 'all active pgs: info 0')
    call check_small(rel_diff(z, z0), cond_w * opts%tol, 'all active pgs: z = z0')

    ! Strongly negative q on a diagonally dominant W: all active too.
    q = [(-1.0e3_dp * (1.0_dp + urand(seed)), i = 1, n)]
    w = w + 10.0_dp * reshape([(merge(1.0_dp, 0.0_dp, mod(i - 1, n + 1) == 0), i = 1, n * n)], [n, n])
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0 .and. all(z > 0.0_dp), 'strongly negative q lemke: all active')
    call check_kkt(w, q, z, 'strongly negative q lemke')

    do i = 1, n
      q(i) = 0.1_dp + urand(seed)
    end do
    call solve_lcp_lemke(w, q, z, opts, rep)
    call check(rep%info == 0 .and. rep%iterations == 0 .and. all(z == 0.0_dp), 'none active lemke: z = 0')
    z = 1.0_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 0, 'none active pgs: info 0')
    call check_small(maxval(z), cond_w * opts%tol, 'none active pgs: z = 0')
  end subroutine test_all_and_none_active

  subroutine test_arguments()
    real(dp) :: w(2, 2), w23(2, 3), z(2), z3(3)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    w = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
    w23 = 1.0_dp
    call solve_lcp_lemke(w23, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -1, 'arguments: W not square -> info -1')
    call solve_lcp_lemke(w, [1.0_dp, 1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -2, 'arguments: q size -> info -2')
    call solve_lcp_lemke(w, [1.0_dp, 1.0_dp], z3, opts, rep)
    call check(rep%info == -3, 'arguments: z size -> info -3')
    z = 0.0_dp
    opts%omega = 2.0_dp
    call solve_lcp_pgs(w, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -4 .and. allocated(rep%message), 'arguments: omega = 2 -> info -4')
    opts%omega = 1.0_dp
    opts%tol = 0.0_dp
    call solve_lcp_lemke(w, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -4, 'arguments: tol = 0 -> info -4')
    opts%tol = 1.0e-10_dp
    w(1, 1) = -1.0_dp
    call solve_lcp_lemke(w, [1.0_dp, 1.0_dp], z, opts, rep)
    call check(rep%info == -1, 'arguments: negative diagonal -> info -1')
  end subroutine test_arguments

  !> PGS stopped by maxit: info 2, finite best iterate, residual above tol;
  !> PGS on a diverging problem: info 3, finite best iterate.
  subroutine test_pgs_limits()
    real(dp), allocatable :: w(:, :), q(:), z(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i
    call random_spd(40, seed, w)
    allocate(q(40), z(40))
    do i = 1, 40
      q(i) = 2.0_dp * urand(seed) - 1.0_dp
    end do
    z = 0.0_dp
    opts%maxit = 2
    opts%tol = 1.0e-14_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 2 .and. rep%iterations == 2, 'pgs maxit 2: info 2 after 2 sweeps')
    call check(all(ieee_is_finite(z)) .and. all(z >= 0.0_dp), 'pgs maxit 2: z finite and >= 0')
    call check(rep%residual > opts%tol, 'pgs maxit 2: residual above tol')
    call check_close(rep%residual, lcp_natural_residual(w, q, z), tol_round(16), &
      'pgs maxit 2: reported residual is that of the returned z')

    ! W = [1 -2; -2 1] (indefinite), q = [-1, -1]: the PGS iterates grow four-fold
    ! per sweep (z1 = 1 + 2 z2, z2 = 1 + 2 z1); divergence is detected, z stays finite.
    deallocate(w, z)
    allocate(w(2, 2), z(2))
    w = reshape([1.0_dp, -2.0_dp, -2.0_dp, 1.0_dp], [2, 2])
    z = 0.0_dp
    opts = lcp_options_t()
    call solve_lcp_pgs(w, [-1.0_dp, -1.0_dp], z, opts, rep)
    call check(rep%info == 3, 'pgs divergence: info 3')
    call check(all(ieee_is_finite(z)) .and. ieee_is_finite(rep%residual), 'pgs divergence: z and residual finite')
  end subroutine test_pgs_limits

end program test_lcp_solvers
