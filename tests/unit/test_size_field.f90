!> size_field: optimal_scales against the Lagrange conditions it solves.
!> With one rate p for every element and no bound reached the multiplier has
!> a closed form, mu = (T^2 / sum_K eta_K^(2/(p+1)))^((p+1)/p), and
!> s_K = (mu / eta_K^2)^(1/(2p+2)); otherwise, on random indicators with
!> rates 1 and 2 and the bounds of one step, the scales must leave the error
!> target (to the bracket's resolution, never above it), lie within the
!> bounds, share one multiplier eta_K^2 s_K^(2p_K+2) where no bound is
!> reached, and agree with a plain bisection written here.  The ends: a
!> target the coarsest sizes already meet gives smax everywhere, one the
!> finest cannot meet gives smin; an element without error gets smax.
program test_size_field
  use kinds, only: dp, i8
  use size_field, only: optimal_scales, element_count
  use testing, only: check, check_close, finish_tests, urand
  implicit none
  integer, parameter :: n = 400
  real(dp), parameter :: smin = 0.125_dp, smax = 4.0_dp
  real(dp) :: eta2(n), rate(n), s(n), sb(n), mu, t2, e2, m(n)
  integer(i8) :: state
  integer :: k, trial
  logical :: free(n)

  ! one rate, bounds far away: the closed form
  state = 2024_i8
  do k = 1, n
    eta2(k) = 10.0_dp**(-6.0_dp * urand(state))
  end do
  eta2 = eta2 / sum(eta2)
  rate = 1.0_dp
  t2 = 0.25_dp
  call optimal_scales(eta2, rate, t2, 1.0e-6_dp, 1.0e6_dp, s)
  mu = (t2 / sum(eta2**(1.0_dp / 2.0_dp)))**2.0_dp
  call check_close(maxval(abs(s / (mu / eta2)**0.25_dp - 1.0_dp)), 0.0_dp, 1.0_dp, &
                   'p = 1, no bound: the closed form s_K = (mu / eta_K^2)^(1/4)', 1.0e-10_dp)
  rate = 2.0_dp
  call optimal_scales(eta2, rate, t2, 1.0e-6_dp, 1.0e6_dp, s)
  mu = (t2 / sum(eta2**(1.0_dp / 3.0_dp)))**1.5_dp
  call check_close(maxval(abs(s / (mu / eta2)**(1.0_dp / 6.0_dp) - 1.0_dp)), 0.0_dp, 1.0_dp, &
                   'p = 2, no bound: the closed form s_K = (mu / eta_K^2)^(1/6)', 1.0e-10_dp)

  ! rates 1 and 2, bounds reached, a few elements without error
  do trial = 1, 5
    do k = 1, n
      eta2(k) = 10.0_dp**(-8.0_dp * urand(state))
      rate(k) = merge(1.0_dp, 2.0_dp, urand(state) < 0.5_dp)
    end do
    eta2(1:n:97) = 0.0_dp
    eta2 = eta2 / sum(eta2)
    ! a target between what the finest and the coarsest scales leave
    mu = 0.3_dp + 0.4_dp * urand(state)
    t2 = sum(eta2 * smin**(2 * rate))**(1.0_dp - mu) * sum(eta2 * smax**(2 * rate))**mu
    call optimal_scales(eta2, rate, t2, smin, smax, s)
    e2 = sum(eta2 * s**(2 * rate))
    call check(e2 <= t2 .and. e2 > t2 * (1.0_dp - 1.0e-10_dp), 'trial ' // achar(48 + trial) // &
               ': the error left is the target, not above it')
    call check(all(s >= smin .and. s <= smax), 'trial ' // achar(48 + trial) // ': the scales within the bounds')
    call check(all(s(1:n:97) == smax), 'trial ' // achar(48 + trial) // ': no error: smax')
    free = eta2 > 0.0_dp .and. s > smin * (1.0_dp + 1.0e-12_dp) .and. s < smax * (1.0_dp - 1.0e-12_dp)
    m = 0.0_dp
    where (free) m = eta2 * s**(2 * rate + 2)
    call check(count(free) > n / 4 .and. count(free) < n, 'trial ' // achar(48 + trial) // &
               ': some scales at a bound, most not')
    call check_close(maxval(m, free) / minval(m, free), 1.0_dp, 1.0e-10_dp, 'trial ' // achar(48 + trial) // &
                     ': one multiplier eta_K^2 s_K^(2 p_K + 2) where no bound is reached')
    call bisection(eta2, rate, t2, sb)
    call check_close(maxval(abs(s / sb - 1.0_dp)), 0.0_dp, 1.0_dp, 'trial ' // achar(48 + trial) // &
                     ': the scales of a plain bisection', 1.0e-9_dp)
  end do

  ! the ends
  call optimal_scales(eta2, rate, 1.0e3_dp, smin, smax, s)
  call check(all(s == smax), 'a target the coarsest sizes meet: smax everywhere')
  call optimal_scales(eta2, rate, 1.0e-30_dp, smin, smax, s)
  call check(all(s == smin .or. eta2 == 0.0_dp), 'a target the finest sizes cannot meet: smin')
  call check_close(element_count([0.5_dp, 2.0_dp]), 4.25_dp, 1.0e-15_dp, 'element_count: sum s^-2')

  call finish_tests()

contains

  !> The same problem by bisection on log mu, 200 halvings of [-700, 700].
  subroutine bisection(eta2, rate, t2, s)
    real(dp), intent(in) :: eta2(:), rate(:), t2
    real(dp), intent(out) :: s(:)
    real(dp) :: lo, hi, mid
    integer :: it
    lo = -700.0_dp
    hi = 700.0_dp
    do it = 1, 200
      mid = 0.5_dp * (lo + hi)
      call at(mid, s)
      if (sum(eta2 * s**(2 * rate)) > t2) then
        hi = mid
      else
        lo = mid
      end if
    end do
    call at(lo, s)
  end subroutine bisection

  subroutine at(log_mu, s)
    real(dp), intent(in) :: log_mu
    real(dp), intent(out) :: s(:)
    where (eta2 > 0.0_dp)
      s = min(smax, max(smin, exp((log_mu - log(max(eta2, tiny(1.0_dp)))) / (2 * rate + 2))))
    elsewhere
      s = smax
    end where
  end subroutine at

end program test_size_field
