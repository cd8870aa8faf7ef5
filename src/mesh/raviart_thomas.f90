!> raviart_thomas: the Raviart-Thomas space RT_m on a triangle in a
!> monomial basis, and the Gauss rules on a segment and a triangle that the
!> stress reconstruction (module stress_equilibration) integrates with.
!>
!> RT_m(K) = P_m(K)^2 + x P~_m(K) (P~_m: the homogeneous polynomials of
!> degree m), dimension (m + 1)(m + 3), its divergence onto P_m(K), its
!> normal trace on each edge in P_m (Raviart and Thomas, 1977; Boffi,
!> Brezzi and Fortin, "Mixed finite element methods", 2013, 2.3.1).  The
!> monomials are in the coordinates (x - xc) / h of the triangle's centre
!> xc and size h, so that the small dense systems built on them stay well
!> scaled.
!>
!> Programming interface
!>   rt_basis(m, xc, h, x, phi, divphi)   the (m + 1)(m + 3) basis fields at x and their divergence
!>   monomials(m, xc, h, x, mono)         the (m + 1)(m + 2) / 2 monomials of degree <= m at x
!>   triangle_rule(x, n, nq, xq, wq)      n x n collapsed Gauss points on a triangle (degree 2 n - 1)
!>   gauss_points(n, x, w)                Gauss-Legendre on 0..1, n <= 8
module raviart_thomas
  use kinds, only: dp
  implicit none
  private
  public :: rt_basis, monomials, triangle_rule, gauss_points

  real(dp), parameter :: pi = 3.14159265358979323846_dp

  !> The Gauss-Legendre rules of 4, 5 and 6 points on 0..1, the ones the
  !> reconstruction asks for (gauss_points' own Newton iteration, printed).
  real(dp), parameter :: x4(4) = [ &
    0.06943184420297371_dp, 0.33000947820757187_dp, 0.66999052179242813_dp, &
    0.93056815579702623_dp]
  real(dp), parameter :: w4(4) = [ &
    0.17392742256872687_dp, 0.32607257743127305_dp, 0.32607257743127305_dp, &
    0.17392742256872687_dp]
  real(dp), parameter :: x5(5) = [ &
    0.04691007703066802_dp, 0.23076534494715845_dp, 0.50000000000000000_dp, &
    0.76923465505284150_dp, 0.95308992296933193_dp]
  real(dp), parameter :: w5(5) = [ &
    0.11846344252809450_dp, 0.23931433524968324_dp, 0.28444444444444444_dp, &
    0.23931433524968324_dp, 0.11846344252809450_dp]
  real(dp), parameter :: x6(6) = [ &
    0.03376524289842397_dp, 0.16939530676686770_dp, 0.38069040695840151_dp, &
    0.61930959304159849_dp, 0.83060469323313235_dp, 0.96623475710157603_dp]
  real(dp), parameter :: w6(6) = [ &
    0.08566224618958525_dp, 0.18038078652406930_dp, 0.23395696728634552_dp, &
    0.23395696728634552_dp, 0.18038078652406930_dp, 0.08566224618958525_dp]

contains

  !> The RT_m basis in monomials at x: (mu, 0), (0, mu) for the monomials
  !> mu of degree <= m and (xi mu, eta mu) for those of degree m, xi and
  !> eta the coordinates from the centre xc over h; phi(2, nrt), its
  !> divergence divphi(nrt).
  pure subroutine rt_basis(m, xc, h, x, phi, divphi)
    integer, intent(in) :: m
    real(dp), intent(in) :: xc(2), h, x(2)
    real(dp), intent(out) :: phi(:,:), divphi(:)
    real(dp) :: px(0:4), py(0:4), mu
    integer :: d, p, j
    call powers(m, xc, h, x, px, py)
    j = 0
    do d = 0, m
      do p = d, 0, -1
        mu = px(p) * py(d - p)
        phi(:, j + 1) = [mu, 0.0_dp]
        phi(:, j + 2) = [0.0_dp, mu]
        divphi(j + 1) = 0
        divphi(j + 2) = 0
        if (p > 0) divphi(j + 1) = p * px(max(p - 1, 0)) * py(d - p) / h
        if (d - p > 0) divphi(j + 2) = (d - p) * px(p) * py(max(d - p - 1, 0)) / h
        j = j + 2
      end do
    end do
    do p = m, 0, -1
      mu = px(p) * py(m - p)
      j = j + 1
      phi(:, j) = [px(1) * mu, py(1) * mu]
      divphi(j) = (m + 2) * mu / h                     ! Euler: div(x mu) = (2 + m) mu
    end do
  end subroutine rt_basis

  !> The monomials of degree <= m at x, in rt_basis's order (1 first, the
  !> pure power of eta of degree m last).
  pure subroutine monomials(m, xc, h, x, mono)
    integer, intent(in) :: m
    real(dp), intent(in) :: xc(2), h, x(2)
    real(dp), intent(out) :: mono(:)
    real(dp) :: px(0:4), py(0:4)
    integer :: d, p, j
    call powers(m, xc, h, x, px, py)
    j = 0
    do d = 0, m
      do p = d, 0, -1
        j = j + 1
        mono(j) = px(p) * py(d - p)
      end do
    end do
  end subroutine monomials

  !> The powers 0..m+1 of the scaled coordinates of x.
  pure subroutine powers(m, xc, h, x, px, py)
    integer, intent(in) :: m
    real(dp), intent(in) :: xc(2), h, x(2)
    real(dp), intent(out) :: px(0:4), py(0:4)
    integer :: k
    px(0) = 1
    py(0) = 1
    do k = 1, min(m + 1, 4)
      px(k) = px(k - 1) * (x(1) - xc(1)) / h
      py(k) = py(k - 1) * (x(2) - xc(2)) / h
    end do
  end subroutine powers

  !> A rule on the triangle x(2, 3) from n x n Gauss points collapsed onto
  !> it (exact for degree 2 n - 1): points xq(2, n^2), weights wq (sum: the area).
  pure subroutine triangle_rule(x, n, nq, xq, wq)
    real(dp), intent(in) :: x(2, 3)
    integer, intent(in) :: n
    integer, intent(out) :: nq
    real(dp), intent(out) :: xq(:,:), wq(:)
    real(dp) :: gx(8), gw(8), det, b
    integer :: i, j
    call gauss_points(n, gx, gw)
    det = abs((x(1, 2) - x(1, 1)) * (x(2, 3) - x(2, 1)) - (x(2, 2) - x(2, 1)) * (x(1, 3) - x(1, 1)))
    nq = 0
    do i = 1, n
      do j = 1, n
        nq = nq + 1
        b = gx(j) * (1 - gx(i))
        xq(:, nq) = x(:, 1) + gx(i) * (x(:, 2) - x(:, 1)) + b * (x(:, 3) - x(:, 1))
        wq(nq) = gw(i) * gw(j) * (1 - gx(i)) * det
      end do
    end do
  end subroutine triangle_rule

  !> Gauss-Legendre points and weights on 0..1, n <= 8 (Newton on P_n).
  pure subroutine gauss_points(n, x, w)
    integer, intent(in) :: n
    real(dp), intent(out) :: x(:), w(:)
    real(dp) :: z, p0, p1, p2, dp1
    integer :: i, k, it
    select case (n)
    case (4)
      x(1:4) = x4
      w(1:4) = w4
      return
    case (5)
      x(1:5) = x5
      w(1:5) = w5
      return
    case (6)
      x(1:6) = x6
      w(1:6) = w6
      return
    end select
    do i = 1, n
      z = cos(pi * (i - 0.25_dp) / (n + 0.5_dp))
      do it = 1, 100
        p0 = 1
        p1 = z
        do k = 2, n
          p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k
          p0 = p1
          p1 = p2
        end do
        if (n == 1) p0 = 1
        dp1 = n * (z * p1 - p0) / (z * z - 1)
        if (abs(p1 / dp1) < 1.0e-15_dp) exit
        z = z - p1 / dp1
      end do
      x(i) = (1 - z) / 2
      w(i) = 1 / ((1 - z * z) * dp1**2)
    end do
  end subroutine gauss_points

end module raviart_thomas
