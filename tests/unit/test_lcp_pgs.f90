!> Unit tests of lcp_pgs's stop on a run too slow to end: an LCP whose W is
!> a rank-2 part 1e6 times its elastic part (a body held only by soft
!> springs: W = 1e-6 E + U C U', U = [1, x], the rigid translation and
!> rotation of the contact rows) converges at about 1 - 1e-7 per sweep, and
!> PGS stops at the end of its third window, the first that it measures the
!> rate on, naming the rate and the cause, with a finite best iterate; the
!> same W without the rank-2 part converges; the rate and the stop do not
!> depend on the units of W and q.
program test_lcp_pgs
  use kinds, only: dp
  use testing, only: check, check_small, finish_tests
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_pgs, solve_lcp_lemke
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none

  call test_soft_modes()
  call finish_tests()

contains

  !> W = 1e-6 E + U C U' on n = 9 rows at x_i = (i - 5)/4: E_ij =
  !> exp(-4 |x_i - x_j|) (SPD: the exponential kernel), U = [1, x],
  !> C = diag(8, 1); q = -W z* with z*_i = 1 + x_i/2 > 0, so z* is the
  !> solution (w = 0).  The window is max(1000, 10 n) = 1000 sweeps.
  subroutine test_soft_modes()
    integer, parameter :: n = 9
    real(dp) :: w(n, n), e(n, n), x(n), zs(n), q(n), z(n), zl(n)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep, rep_units, rep_stiff
    integer :: i, j
    x = [(real(i - 5, dp) / 4.0_dp, i = 1, n)]
    do j = 1, n
      do i = 1, n
        e(i, j) = exp(-4.0_dp * abs(x(i) - x(j)))
      end do
    end do
    do j = 1, n
      do i = 1, n
        w(i, j) = 1.0e-6_dp * e(i, j) + 8.0_dp + x(i) * x(j)
      end do
    end do
    zs = 1.0_dp + x / 2.0_dp
    q = -matmul(w, zs)

    call solve_lcp_lemke(w, q, zl, opts, rep)
    call check(rep%info == 0 .and. maxval(abs(zl - zs)) <= 1.0e-4_dp, 'soft modes: Lemke finds z*')

    z = 0.0_dp
    call solve_lcp_pgs(w, q, z, opts, rep)
    call check(rep%info == 3 .and. trim(rep%stopped) == 'stagnated', 'soft modes: PGS stops, info 3')
    call check(index(rep%message, 'PGS: too slow at sweep 3000') == 1 .and. &
      index(rep%message, 'of itself per sweep') > 0 .and. &
      index(rep%message, 'ill-conditioned') > 0 .and. index(rep%message, 'does not show that it has no solution') > 0, &
      'soft modes: the message names the rate and the cause')
    call check(rep%iterations == 3000, 'soft modes: stopped at the end of the third window, not at the limit')
    call check(all(ieee_is_finite(z)) .and. all(z >= 0.0_dp) .and. rep%residual > opts%tol, &
      'soft modes: the best iterate, finite, >= 0, residual above tol')

    ! other units: W x 1e3, q x 1e-3: the same sweeps and the same residual
    z = 0.0_dp
    call solve_lcp_pgs(w * 1.0e3_dp, q * 1.0e-3_dp, z, opts, rep_units)
    call check(rep_units%info == rep%info .and. rep_units%iterations == rep%iterations, &
      'soft modes: the same stop in other units')
    call check_small(rep_units%residual / rep%residual - 1.0_dp, 1.0e-6_dp, &
      'soft modes: the same residual in other units')

    ! without the soft modes (W = E, well conditioned): converged
    q = -matmul(e, zs)
    z = 0.0_dp
    call solve_lcp_pgs(e, q, z, opts, rep_stiff)
    call check(rep_stiff%info == 0, 'stiff: PGS converges')
    ! E is well conditioned: the error is within a few times the residual's tol
    call check_small(maxval(abs(z - zs)) / maxval(zs), 1.0e2_dp * opts%tol, 'stiff: z = z*')
  end subroutine test_soft_modes

end program test_lcp_pgs
