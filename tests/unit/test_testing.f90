!> testing: the checks themselves can fail.  A check that cannot fail makes
!> every test built on it unable to fail, so each verdict (is_small,
!> is_close: what check_small and check_close print) is tried on values that
!> must fail and on values that must pass:
!>   - is_small takes |a|: a value far below zero fails as one far above
!>     (the defect this guards against: check_small(x - 0.5, tol) passed for
!>     every x < 0.5);
!>   - NaN fails both, and so does an infinity;
!>   - the bounds are inclusive (|a| = tol passes), and tol_round is n eps
!>     scale.
program test_testing
  use kinds, only: dp
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, ieee_negative_inf
  use testing, only: check, is_small, is_close, tol_round, unit_roundoff, finish_tests
  implicit none
  real(dp) :: nan, inf, tol

  nan = ieee_value(1.0_dp, ieee_quiet_nan)
  inf = ieee_value(1.0_dp, ieee_positive_inf)
  tol = 1.0_dp / 1024

  call check(.not. is_small(-1.0_dp, tol), 'is_small: -1 is not small (a value far below zero fails)')
  call check(.not. is_small(-2 * tol, tol), 'is_small: -2 tol is not small')
  call check(.not. is_small(2 * tol, tol), 'is_small: 2 tol is not small')
  call check(.not. is_small(nan, tol), 'is_small: NaN fails')
  call check(.not. is_small(inf, tol) .and. .not. is_small(ieee_value(1.0_dp, ieee_negative_inf), tol), &
             'is_small: +-Inf fail')
  call check(is_small(-tol, tol) .and. is_small(tol, tol) .and. is_small(0.0_dp, tol), &
             'is_small: -tol, 0 and tol pass (bounds inclusive)')
  call check(.not. is_small(0.3_dp - 0.5_dp, tol), 'is_small: x - 0.5 for x = 0.3 fails (the old check passed it)')

  call check(.not. is_close(0.9_dp, 1.0_dp, tol) .and. .not. is_close(1.1_dp, 1.0_dp, tol), &
             'is_close: 10% off either side fails')
  call check(is_close(1.0_dp + tol / 2, 1.0_dp, tol) .and. is_close(1.0_dp - tol / 2, 1.0_dp, tol), &
             'is_close: within rtol either side passes')
  call check(.not. is_close(nan, 1.0_dp, tol) .and. .not. is_close(1.0_dp, nan, tol), 'is_close: NaN fails')
  call check(.not. is_close(tol, 0.0_dp, tol), 'is_close: b = 0 without a floor needs a = 0')
  call check(is_close(tol * tol, 0.0_dp, tol, floor=1.0_dp), 'is_close: the floor scales a b = 0')

  call check(tol_round(4) == 4 * unit_roundoff .and. tol_round(3, 8.0_dp) == 24 * unit_roundoff, &
             'tol_round(n, scale) = n eps scale')
  call check(unit_roundoff == 2.0_dp**(-52), 'unit_roundoff = 2^-52')
  call finish_tests()
end program test_testing
