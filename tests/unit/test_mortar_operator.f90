!> Unit tests of mortar_operator: pi_h^1 (eq. (8)) on conforming, non-matching,
!> partially overlapping and curved interfaces, against independent facts (identity,
!> pi 1 = 1, integral preservation, reproduction of linear functions, the defining
!> orthogonality (8) evaluated by an exact Simpson rule on the merged breakpoints,
!> closed-form gaps), the input errors, and the steps both builders share.
program test_mortar_operator
  use kinds, only: dp, i8
  use errors, only: error_t, error_input
  use mortar_operator, only: mortar_t, build_mortar, start_mortar, start_periodic, set_initial_gaps
  use lapack_interfaces, only: dlasrt
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  implicit none

  integer :: seed = 12345

  call test_conforming()
  call test_nonmatching_flat()
  call test_master_shorter()
  call test_slave_shorter_rotated()
  call test_small_zones()
  call test_curved()
  call test_errors()
  call test_shared_steps()
  call finish_tests()

contains

  ! ---------------------------------------------------------------- helpers

  !> Uniform pseudo-random number in [0, 1) (a fixed linear congruential sequence).
  real(dp) function rnd()
    seed = int(mod(69069_i8 * seed + 1_i8, 2147483647_i8))   ! in 64 bits: no overflow
    rnd = real(seed, dp) / 2147483647.0_dp
  end function rnd

  !> Points xi t + eta nv on a line: (2, n).
  function on_line(xi, eta, t, nv) result(x)
    real(dp), intent(in) :: xi(:), eta, t(2), nv(2)
    real(dp) :: x(2, size(xi))
    integer :: i
    do i = 1, size(xi)
      x(:, i) = xi(i) * t + eta * nv
    end do
  end function on_line

  !> Unit segment normals, left (-t_y, t_x) or right (t_y, -t_x) of the direction of travel.
  function segment_normals(x, left) result(nrm)
    real(dp), intent(in) :: x(:,:)
    logical, intent(in) :: left
    real(dp) :: nrm(2, size(x, 2) - 1), t(2)
    integer :: k
    do k = 1, size(x, 2) - 1
      t = x(:, k + 1) - x(:, k)
      t = t / norm2(t)
      if (left) then
        nrm(:, k) = [-t(2), t(1)]
      else
        nrm(:, k) = [t(2), -t(1)]
      end if
    end do
  end function segment_normals

  !> Piecewise linear interpolant of (xn, v) at x; xn ascending; 0 outside [xn(1), xn(n)].
  real(dp) function interp(xn, v, x)
    real(dp), intent(in) :: xn(:), v(:), x
    integer :: k
    interp = 0.0_dp
    do k = 1, size(xn) - 1
      if (x >= xn(k) .and. x <= xn(k + 1)) then
        interp = v(k) + (v(k + 1) - v(k)) * (x - xn(k)) / (xn(k + 1) - xn(k))
        return
      end if
    end do
  end function interp

  !> Sorted breakpoints: lo, hi and every node of a and b strictly inside (lo, hi).
  function breakpoints(a, b, lo, hi) result(p)
    real(dp), intent(in) :: a(:), b(:), lo, hi
    real(dp), allocatable :: p(:)
    integer :: i, info
    p = [lo, hi]
    do i = 1, size(a)
      if (a(i) > lo .and. a(i) < hi) p = [p, a(i)]
    end do
    do i = 1, size(b)
      if (b(i) > lo .and. b(i) < hi) p = [p, b(i)]
    end do
    call dlasrt('I', size(p), p, info)
  end function breakpoints

  !> int_lo^hi f g dx for f, g piecewise linear on (xf, vf), (xg, vg): Simpson on each
  !> piece between merged breakpoints, exact for these piecewise quadratics.
  real(dp) function integral_product(xf, vf, xg, vg, lo, hi) result(s)
    real(dp), intent(in) :: xf(:), vf(:), xg(:), vg(:), lo, hi
    real(dp), allocatable :: p(:)
    real(dp) :: a, b, m
    integer :: i
    p = breakpoints(xf, xg, lo, hi)
    s = 0.0_dp
    do i = 1, size(p) - 1
      a = p(i); b = p(i + 1); m = 0.5_dp * (a + b)
      s = s + (b - a) / 6.0_dp * (interp(xf, vf, a) * interp(xg, vg, a) + &
          4.0_dp * interp(xf, vf, m) * interp(xg, vg, m) + interp(xf, vf, b) * interp(xg, vg, b))
    end do
  end function integral_product

  !> Largest |int psi_k (pi phi - phi)| over k = 1..n-1 on the covered part [lo, hi],
  !> relative to max|c| (hi - lo): the defining orthogonality of eq. (8) on the
  !> zone's mesh, the slave nodes first..last with the end nodes moved to lo
  !> and hi where the cover ends inside an end segment.
  !>   xs1 (ns) slave 1D coordinates ascending, v (ns) nodal values of pi phi on the zone's mesh,
  !>   xm1 (nm) master 1D coordinates ascending, c (nm) master nodal values.
  real(dp) function orthogonality_defect(xs1, first, last, v, xm1, c, lo, hi) result(worst)
    real(dp), intent(in) :: xs1(:), v(:), xm1(:), c(:), lo, hi
    integer, intent(in) :: first, last
    real(dp), allocatable :: psi(:), xz(:)
    integer :: n, k, l
    n = last - first
    worst = 0.0_dp
    xz = xs1
    xz(first) = max(xz(first), lo)
    xz(last) = min(xz(last), hi)
    allocate(psi(size(xs1)))
    do k = 1, n - 1
      psi = 0.0_dp
      do l = 0, n
        if (max(1, min(n - 1, l)) == k) psi(first + l) = 1.0_dp   ! psi_k = sum of phi_l
      end do
      worst = max(worst, abs(integral_product(xz, psi, xz, v, lo, hi) - &
                             integral_product(xz, psi, xm1, c, lo, hi)))
    end do
    worst = worst / (maxval(abs(c)) * (hi - lo))
  end function orthogonality_defect

  !> int_lo^hi of the hats of the ascending 1D mesh xn: (size(xn)).
  function hat_integrals(xn, lo, hi) result(w)
    real(dp), intent(in) :: xn(:), lo, hi
    real(dp) :: w(size(xn)), e(size(xn)), one(2)
    integer :: j
    one = 1.0_dp
    do j = 1, size(xn)
      e = 0.0_dp
      e(j) = 1.0_dp
      w(j) = integral_product(xn, e, [lo, hi], one, lo, hi)
    end do
  end function hat_integrals

  ! ---------------------------------------------------------------- tests

  !> Same nodes on a tilted line, master in reverse order with opposite normals:
  !> P is the permutation matrix, gap0 = 0.
  subroutine test_conforming()
    real(dp), parameter :: xi(6) = [0.0_dp, 0.7_dp, 1.5_dp, 2.0_dp, 3.1_dp, 4.0_dp]
    real(dp) :: t(2), nv(2), xs(2, 6), xm(2, 6), perm(6, 6)
    type(mortar_t) :: m
    type(error_t), allocatable :: err
    integer :: i
    t = [cos(0.3_dp), sin(0.3_dp)]
    nv = [-t(2), t(1)]
    xs = on_line(xi, 0.0_dp, t, nv)
    xm = xs(:, 6:1:-1)
    call build_mortar(xs, segment_normals(xs, .true.), xm, segment_normals(xm, .true.), .false., m, err)
    call check(.not. allocated(err), 'conforming: no error')
    if (allocated(err)) return
    call check(m%first == 1 .and. m%last == 6, 'conforming: zone is the whole slave boundary')
    perm = 0.0_dp
    do i = 1, 6
      perm(i, 7 - i) = 1.0_dp
    end do
    call check_small(maxval(abs(m%P - perm)), tol_round(16), 'conforming: P is the identity permutation')
    call check_small(maxval(abs(m%gap0)), tol_round(16), 'conforming: gap0 = 0 (gap=geometry, coinciding)')
    call check_small(maxval(abs(m%normal - spread(nv, 2, 6))), tol_round(16), 'conforming: nodal normals')
    call check_close(m%arc(6), 4.0_dp, tol_round(16), 'conforming: arc length')
  end subroutine test_conforming

  !> Slave 7 segments, master 4, both on y = 1 over [0, 3.5], interior nodes perturbed.
  subroutine test_nonmatching_flat()
    real(dp) :: xi_s(8), xi_m(5), xs(2, 8), xm(2, 5), c(5), w2(5), v(8)
    real(dp), parameter :: ex(2) = [1.0_dp, 0.0_dp], ey(2) = [0.0_dp, 1.0_dp]
    type(mortar_t) :: m, mg
    type(error_t), allocatable :: err
    integer :: i, j
    real(dp) :: a, b
    do i = 1, 8
      xi_s(i) = 0.5_dp * (i - 1)
      if (i > 1 .and. i < 8) xi_s(i) = xi_s(i) + 0.15_dp * (2.0_dp * rnd() - 1.0_dp)
    end do
    do j = 1, 5
      xi_m(j) = 0.875_dp * (j - 1)
      if (j > 1 .and. j < 5) xi_m(j) = xi_m(j) + 0.3_dp * (2.0_dp * rnd() - 1.0_dp)
    end do
    xs = on_line(xi_s, 1.0_dp, ex, ey)
    xm = on_line(xi_m, 1.0_dp, ex, ey)
    ! slave body below (normal +y, left of +x), master above (normal -y, right of +x)
    call build_mortar(xs, segment_normals(xs, .true.), xm, segment_normals(xm, .false.), .true., m, err)
    call check(.not. allocated(err), 'non-matching: no error')
    if (allocated(err)) return
    call check(m%first == 1 .and. m%last == 8, 'non-matching: zone is the whole slave boundary')
    call check(all(m%constrained), 'non-matching: all slave nodes constrained')
    call check_small(maxval(abs(matmul(m%P, [(1.0_dp, j = 1, 5)]) - 1.0_dp)), tol_round(16), &
      'non-matching: pi(1) = 1')
    ! master lumped weights (h_{j-1} + h_j)/2
    w2 = 0.0_dp
    do j = 1, 4
      w2(j) = w2(j) + 0.5_dp * (xi_m(j + 1) - xi_m(j))
      w2(j + 1) = w2(j + 1) + 0.5_dp * (xi_m(j + 1) - xi_m(j))
    end do
    call check_small(maxval(abs(matmul(m%weight, m%P) - w2)) / maxval(w2), tol_round(16), &
      'non-matching: w'' P = w2'' (integral preservation)')
    call check_small(maxval(abs(m%weight - hat_integrals(xi_s, 0.0_dp, 3.5_dp))), tol_round(16), &
      'non-matching: lumped slave weights')
    call check(all(m%gap0 == 0.0_dp), 'non-matching: gap0 = 0 for gap=zero')
    ! a linear function lies in both trace spaces: pi reproduces it at every node
    a = 0.7_dp; b = -1.3_dp
    c = a + b * xi_m
    v = matmul(m%P, c)
    call check_small(abs(v(1) - (a + b * xi_s(1))) + abs(v(8) - (a + b * xi_s(8))), tol_round(16), &
      'non-matching: pi of a linear function exact at the end points')
    call check_small(maxval(abs(v - (a + b * xi_s))), tol_round(16), &
      'non-matching: pi reproduces a linear function at every slave node')
    call check_small(orthogonality_defect(xi_s, 1, 8, v, xi_m, c, 0.0_dp, 3.5_dp), tol_round(16), &
      'non-matching: int psi_k (pi phi - phi) = 0, phi linear (eq. 8)')
    ! a general master P1 function
    do j = 1, 5
      c(j) = 2.0_dp * rnd() - 1.0_dp
    end do
    v = matmul(m%P, c)
    call check_small(abs(v(1) - c(1)) + abs(v(8) - c(5)), tol_round(16), &
      'non-matching: pi phi = phi at a1 and a2')
    call check_small(orthogonality_defect(xi_s, 1, 8, v, xi_m, c, 0.0_dp, 3.5_dp), tol_round(16), &
      'non-matching: int psi_k (pi phi - phi) = 0, phi random P1 (eq. 8)')
    ! gap=geometry on coinciding boundaries
    call build_mortar(xs, segment_normals(xs, .true.), xm, segment_normals(xm, .false.), .false., mg, err)
    call check(.not. allocated(err), 'non-matching: gap=geometry no error')
    if (allocated(err)) return
    call check_small(maxval(abs(mg%gap0)), tol_round(16), 'non-matching: gap0 = 0 for coinciding lines')
  end subroutine test_nonmatching_flat

  !> Master [2.5, 7.3] inside the slave [0, 10]: the zone is slave nodes 3..9 (x = 2..8),
  !> end values are the master end values (constant extension), integrals over [2.5, 7.3].
  subroutine test_master_shorter()
    real(dp) :: xi_s(11), xs(2, 11), xm(2, 7), c(7), v(11), w2(7), wc(11), xi_asc(7), wz(7)
    real(dp), parameter :: xi_m(7) = [7.3_dp, 6.6_dp, 5.9_dp, 5.0_dp, 4.1_dp, 3.2_dp, 2.5_dp]
    real(dp), parameter :: ex(2) = [1.0_dp, 0.0_dp], ey(2) = [0.0_dp, 1.0_dp]
    type(mortar_t) :: m
    type(error_t), allocatable :: err
    integer :: i, j
    xi_s = [(real(i - 1, dp), i = 1, 11)]
    xs = on_line(xi_s, 0.0_dp, ex, ey)
    xm = on_line(xi_m, 0.0_dp, ex, ey)          ! reverse order; body above: normal -y, left of -x
    call build_mortar(xs, segment_normals(xs, .true.), xm, segment_normals(xm, .true.), .true., m, err)
    call check(.not. allocated(err), 'master shorter: no error')
    if (allocated(err)) return
    call check(m%first == 3 .and. m%last == 9, 'master shorter: zone is slave nodes 3..9')
    call check(count(m%constrained) == 7 .and. all(m%constrained(3:9)), 'master shorter: constrained flags')
    call check(all(m%P(1:2, :) == 0.0_dp) .and. all(m%P(10:11, :) == 0.0_dp), &
      'master shorter: rows off the zone are zero')
    call check_small(maxval(abs(sum(m%P(3:9, :), dim=2) - 1.0_dp)), tol_round(32), 'master shorter: pi(1) = 1')
    call check_small(abs(m%P(3, 7) - 1.0_dp) + abs(m%P(9, 1) - 1.0_dp) + sum(abs(m%P(3, 1:6))) + &
      sum(abs(m%P(9, 2:7))), tol_round(16), 'master shorter: end values from the master end points')
    ! weights: full segments for w, covered part [2.5, 7.3] for covered_weight
    call check_small(maxval(abs(m%weight - [0.0_dp, 0.0_dp, 0.5_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, &
      0.5_dp, 0.0_dp, 0.0_dp])), tol_round(4), 'master shorter: lumped weights of the zone')
    wc = hat_integrals(xi_s, 2.5_dp, 7.3_dp)
    call check_small(maxval(abs(m%covered_weight - wc)), tol_round(16), 'master shorter: covered weights')
    xi_asc = xi_m(7:1:-1)
    w2 = hat_integrals(xi_asc, 2.5_dp, 7.3_dp)
    w2 = w2(7:1:-1)
    ! the zone's mesh: nodes 3..9 with the ends moved to the master's ends 2.5 and 7.3
    call check_small(m%cut(1) - 0.5_dp, tol_round(16), 'master shorter: the zone starts inside segment 3')
    call check_small(m%cut(2) - 0.3_dp, tol_round(16), 'master shorter: the zone ends inside segment 8')
    wz = hat_integrals([2.5_dp, 3.0_dp, 4.0_dp, 5.0_dp, 6.0_dp, 7.0_dp, 7.3_dp], 2.5_dp, 7.3_dp)
    call check_small(maxval(abs(m%zone_weight(3:9) - wz)) + sum(abs(m%zone_weight(1:2))) + &
      sum(abs(m%zone_weight(10:11))), tol_round(16), 'master shorter: zone weights (the zone''s hats)')
    call check_small(maxval(abs(matmul(m%zone_weight, m%P) - w2)) / maxval(w2), tol_round(32), &
      'master shorter: zone_weight'' P = int chi_j over the overlap')
    do j = 1, 7
      c(j) = 2.0_dp * rnd() - 1.0_dp
    end do
    v = matmul(m%P, c)
    call check_small(orthogonality_defect(xi_s, 3, 9, v, xi_asc, c(7:1:-1), 2.5_dp, 7.3_dp), tol_round(16), &
      'master shorter: int psi_k (pi phi - phi) = 0 over the covered part (eq. 8)')
  end subroutine test_master_shorter

  !> Slave [3, 6] inside the master [0, 10], on a line at 30 degrees, master offset by
  !> 0.1 along the slave normal (gap=geometry): gap0 = 0.1; end values by the normal ray.
  subroutine test_slave_shorter_rotated()
    real(dp), parameter :: xi_s(5) = [3.0_dp, 3.6_dp, 4.5_dp, 5.2_dp, 6.0_dp]
    real(dp), parameter :: xi_m(8) = [0.0_dp, 1.3_dp, 2.9_dp, 4.0_dp, 5.5_dp, 7.1_dp, 8.4_dp, 10.0_dp]
    real(dp) :: t(2), nv(2), xs(2, 5), xm(2, 8), c(8), v(5), e(8), w2(8)
    type(mortar_t) :: m
    type(error_t), allocatable :: err
    integer :: j
    real(dp) :: worst
    t = [cos(acos(-1.0_dp) / 6.0_dp), sin(acos(-1.0_dp) / 6.0_dp)]
    nv = [-t(2), t(1)]
    xs = on_line(xi_s, 0.0_dp, t, nv)
    xm = on_line(xi_m, 0.1_dp, t, nv)
    call build_mortar(xs, segment_normals(xs, .true.), xm, segment_normals(xm, .false.), .false., m, err)
    call check(.not. allocated(err), 'slave shorter: no error')
    if (allocated(err)) return
    call check(m%first == 1 .and. m%last == 5, 'slave shorter: zone is the whole slave boundary')
    call check_small(maxval(abs(sum(m%P, dim=2) - 1.0_dp)), tol_round(16), 'slave shorter: pi(1) = 1')
    call check_small(maxval(abs(m%gap0 - 0.1_dp)), tol_round(16), 'slave shorter: gap0 = 0.1 (parallel offset)')
    worst = 0.0_dp
    do j = 1, 8
      e = 0.0_dp
      e(j) = 1.0_dp
      worst = max(worst, abs(m%P(1, j) - interp(xi_m, e, 3.0_dp)), abs(m%P(5, j) - interp(xi_m, e, 6.0_dp)))
    end do
    call check_small(worst, tol_round(16), 'slave shorter: end rows = master hats at a1, a2')
    w2 = hat_integrals(xi_m, 3.0_dp, 6.0_dp)
    call check_small(maxval(abs(matmul(m%weight, m%P) - w2)) / maxval(w2), tol_round(16), &
      'slave shorter: w'' P = int chi_j over the overlap')
    c = 0.4_dp + 0.25_dp * xi_m
    v = matmul(m%P, c)
    call check_small(maxval(abs(v - (0.4_dp + 0.25_dp * xi_s))), tol_round(32), &
      'slave shorter: pi reproduces a linear function')
    do j = 1, 8
      c(j) = 2.0_dp * rnd() - 1.0_dp
    end do
    v = matmul(m%P, c)
    call check_small(orthogonality_defect(xi_s, 1, 5, v, xi_m, c, 3.0_dp, 6.0_dp), tol_round(16), &
      'slave shorter: int psi_k (pi phi - phi) = 0 (eq. 8)')
  end subroutine test_slave_shorter_rotated

  !> Zones of one segment (no interior node) and of two (psi_1 = 1).
  subroutine test_small_zones()
    real(dp), parameter :: xi_m(4) = [-0.2_dp, 0.3_dp, 0.55_dp, 1.4_dp]
    real(dp), parameter :: ex(2) = [1.0_dp, 0.0_dp], ey(2) = [0.0_dp, 1.0_dp]
    real(dp) :: xm(2, 4), x1(2, 2), x2(2, 3), c(4), v(3), e(4), worst
    type(mortar_t) :: m
    type(error_t), allocatable :: err
    integer :: j
    xm = on_line(xi_m, 0.0_dp, ex, ey)
    x1 = on_line([0.0_dp, 1.0_dp], 0.0_dp, ex, ey)
    call build_mortar(x1, segment_normals(x1, .true.), xm, segment_normals(xm, .false.), .true., m, err)
    call check(.not. allocated(err), 'one segment: no error')
    if (allocated(err)) return
    worst = 0.0_dp
    do j = 1, 4
      e = 0.0_dp
      e(j) = 1.0_dp
      worst = max(worst, abs(m%P(1, j) - interp(xi_m, e, 0.0_dp)), abs(m%P(2, j) - interp(xi_m, e, 1.0_dp)))
    end do
    call check(m%first == 1 .and. m%last == 2, 'one segment: zone')
    call check_small(worst, tol_round(16), 'one segment: both rows are end values')

    x2 = on_line([0.0_dp, 0.4_dp, 1.0_dp], 0.0_dp, ex, ey)
    call build_mortar(x2, segment_normals(x2, .true.), xm, segment_normals(xm, .false.), .true., m, err)
    call check(.not. allocated(err), 'two segments: no error')
    if (allocated(err)) return
    call check_small(maxval(abs(sum(m%P, dim=2) - 1.0_dp)), tol_round(16), 'two segments: pi(1) = 1')
    c = [0.3_dp, -1.0_dp, 0.8_dp, 0.1_dp]
    v = matmul(m%P, c)
    call check_small(orthogonality_defect([0.0_dp, 0.4_dp, 1.0_dp], 1, 3, v, xi_m, c, 0.0_dp, 1.0_dp), &
      tol_round(16), 'two segments: int (pi phi - phi) = 0 (psi_1 = 1)')
  end subroutine test_small_zones

  !> Flat slave y = 0 on [-4, 4] (coarse, h = 8/N), master a polyline on the circle
  !> x^2 + (y-1)^2 = 1, y <= 1 (400 chords, uniform in angle, a node at x = 0).
  !> gap=geometry gives gap0 = pi_h^1 of the master height g_h (the chord polyline).
  !> For an L2-type projection on a uniform mesh the nodal error is
  !> pi g - g = -h^2 g''/12 + O(h^4) (from M v = b: v + h^2 v''/6 = g + h^2 g''/12);
  !> the chords add at most h_m^2 g''/8 ~ 1e-5, and the singular ends (|x| -> 1, where
  !> g'' is unbounded) perturb the nodes of |x| < 0.5 through a decay factor
  !> (2 - sqrt 3)^k ~ 0.27^k, k >= 4.  Hence the bound |gap0_i - g(x_i)| <= h^2 max g''/6
  !> (twice the leading term) for |x_i| < 0.5, with g(x) = 1 - sqrt(1 - x^2),
  !> g'' = (1 - x^2)^(-3/2) <= 1.54.  At x = 0: gap0 = -h^2/12 to leading order (the
  !> projection is not exact at the contact point even with a master node there).
  subroutine test_curved()
    real(dp) :: g0(2), h(2)
    call curved_case(70, g0(1), h(1))
    call curved_case(142, g0(2), h(2))
    call check_close(g0(1) / g0(2), (h(1) / h(2))**2, 0.05_dp, 'curved: gap0(0) converges as h^2')
  end subroutine test_curved

  subroutine curved_case(nseg, gap_at_0, h)
    integer, intent(in) :: nseg
    real(dp), intent(out) :: gap_at_0, h
    integer, parameter :: nmseg = 400
    real(dp), allocatable :: xs(:,:), xm(:,:), nm_out(:,:), xi_s(:), v(:)
    real(dp) :: pi, th, th2, worst, gmax
    type(mortar_t) :: m
    type(error_t), allocatable :: err
    integer :: i, j, first, last, i0
    character(len=8) :: tag
    write(tag, '(a,i0,a)') '(N=', nseg, ')'
    pi = acos(-1.0_dp)
    h = 8.0_dp / nseg
    allocate(xs(2, nseg + 1), xi_s(nseg + 1), xm(2, nmseg + 1), nm_out(2, nmseg))
    do i = 1, nseg + 1
      xi_s(i) = -4.0_dp + h * (i - 1)
    end do
    i0 = nseg / 2 + 1
    xi_s(i0) = 0.0_dp
    xs(1, :) = xi_s
    xs(2, :) = 0.0_dp
    do j = 1, nmseg + 1
      th = -0.5_dp * pi + pi * (j - 1) / nmseg
      xm(:, j) = [sin(th), 1.0_dp - cos(th)]
    end do
    xm(:, nmseg / 2 + 1) = 0.0_dp
    do j = 1, nmseg
      th = -0.5_dp * pi + pi * (j - 1) / nmseg
      th2 = -0.5_dp * pi + pi * j / nmseg
      nm_out(:, j) = [sin(0.5_dp * (th + th2)), -cos(0.5_dp * (th + th2))]  ! away from the centre (0, 1)
    end do
    call build_mortar(xs, segment_normals(xs, .true.), xm, nm_out, .false., m, err)
    call check(.not. allocated(err), 'curved: no error ' // trim(tag))
    gap_at_0 = 1.0_dp
    if (allocated(err)) return
    ! zone: the slave segments containing [-1, 1]
    first = floor(3.0_dp / h) + 1
    last = ceiling(5.0_dp / h) + 1
    call check(m%first == first .and. m%last == last, 'curved: zone ' // trim(tag))
    call check_small(maxval(abs(sum(m%P(first:last, :), dim=2) - 1.0_dp)), tol_round(128), 'curved: pi(1) = 1 ' // &
      trim(tag))
    call check_small(abs(m%gap0(first) - 1.0_dp) + abs(m%gap0(last) - 1.0_dp), tol_round(16), &
      'curved: end gaps = height of the master end points ' // trim(tag))
    v = m%gap0
    call check_small(orthogonality_defect(xi_s, first, last, v, xm(1, :), xm(2, :), -1.0_dp, 1.0_dp), tol_round(16), &
      'curved: int psi_k (gap0 - g_h) = 0 (eq. 8) ' // trim(tag))
    gmax = (1.0_dp - 0.25_dp)**(-1.5_dp)
    worst = 0.0_dp
    do i = first, last
      if (abs(xi_s(i)) < 0.5_dp) worst = max(worst, abs(m%gap0(i) - (1.0_dp - sqrt(1.0_dp - xi_s(i)**2))))
    end do
    call check_small(worst, h**2 * gmax / 6.0_dp, 'curved: |gap0 - (1 - sqrt(1 - x^2))| <= h^2 max g''''/6 ' // &
      trim(tag))
    gap_at_0 = m%gap0(i0)
    call check_close(gap_at_0, -h**2 / 12.0_dp, 0.1_dp, 'curved: gap0(0) = -h^2/12 to leading order ' // trim(tag))
  end subroutine curved_case

  !> Input errors (status 2) and a pair that never touches (no error, empty zone).
  subroutine test_errors()
    real(dp) :: xs(2, 4), xm(2, 2), xf(2, 4), nrm(2, 3)
    type(mortar_t) :: m
    type(error_t), allocatable :: err
    xm = reshape([-1.0_dp, 1.0_dp, 9.0_dp, 1.0_dp], [2, 2])

    xs = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 2.0_dp, 0.0_dp], [2, 4])
    nrm = reshape([0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp], [2, 3])
    call build_mortar(xs, nrm, xm, segment_normals(xm, .false.), .false., m, err)
    call check(allocated(err), 'error: zero-length slave segment detected')
    if (allocated(err)) then
      call check(err%category == error_input .and. index(err%message, &
        'zero-length segment on the slave boundary at node 2 (distinct consecutive nodes expected)') > 0, &
        'error: zero-length segment message and status 2')
    end if

    xf = reshape([0.0_dp, 1.0_dp, 2.0_dp, 1.0_dp, 2.0_dp, 1.0_dp, 3.0_dp, 1.0_dp], [2, 4])
    xs(:, 1:2) = reshape([0.0_dp, 0.0_dp, 3.0_dp, 0.0_dp], [2, 2])
    call build_mortar(xs(:, 1:2), segment_normals(xs(:, 1:2), .true.), xf, nrm, .false., m, err)
    call check(allocated(err), 'error: zero-length master segment detected')
    if (allocated(err)) call check(err%category == error_input .and. index(err%message, 'master boundary at node 2') > 0, &
      'error: zero-length master segment message')

    ! stepped slave: the riser x = 4 has nothing opposite -> a hole at arc length 4..5
    xs = reshape([0.0_dp, 0.0_dp, 4.0_dp, 0.0_dp, 4.0_dp, -1.0_dp, 8.0_dp, -1.0_dp], [2, 4])
    nrm = reshape([0.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 3])
    call build_mortar(xs, nrm, xm, segment_normals(xm, .false.), .false., m, err)
    call check(allocated(err), 'error: hole in the master cover detected')
    if (allocated(err)) then
      call check(err%category == error_input .and. index(err%message, &
        'master boundary leaves a gap opposite the slave boundary between arc length 4.00000E+00 and 5.00000E+00') > 0, &
        'error: hole message (arc lengths 4 and 5 to 6 digits) and status 2')
    end if

    ! master folding back over itself in front of a flat slave
    xs = reshape([0.0_dp, 0.0_dp, 3.0_dp, 0.0_dp, 6.0_dp, 0.0_dp, 9.0_dp, 0.0_dp], [2, 4])
    xf = reshape([0.0_dp, 1.0_dp, 5.0_dp, 1.0_dp, 3.0_dp, 2.0_dp, 8.0_dp, 2.0_dp], [2, 4])
    call build_mortar(xs, segment_normals(xs, .true.), xf, segment_normals(xf, .false.), .false., m, err)
    call check(allocated(err), 'error: master folding back detected')
    if (allocated(err)) call check(err%category == error_input .and. index(err%message, 'twice') > 0, &
      'error: fold message and status 2')

    call build_mortar(xs(:, 1:1), nrm(:, 1:0), xm, segment_normals(xm, .false.), .false., m, err)
    call check(allocated(err), 'error: one-node slave boundary detected')

    nrm = segment_normals(xs, .true.)
    nrm(:, 2) = 1.1_dp * nrm(:, 2)
    call build_mortar(xs, nrm, xm, segment_normals(xm, .false.), .false., m, err)
    call check(allocated(err), 'error: non-unit normal detected')
    if (allocated(err)) call check(index(err%message, 'not a unit vector') > 0, 'error: non-unit normal message')

    nrm = segment_normals(xs, .true.)
    nrm(:, 3) = -nrm(:, 3)
    call build_mortar(xs, nrm, xm, segment_normals(xm, .false.), .false., m, err)
    call check(allocated(err), 'error: normals changing side detected')

    call build_mortar(xs, segment_normals(xs, .true.), xm, segment_normals(xm, .false.), .false., m, err)
    call check(.not. allocated(err), 'error: valid pair accepted')

    ! master far to the right: no overlap, no error, empty zone
    xf = reshape([20.0_dp, 1.0_dp, 21.0_dp, 1.0_dp, 22.0_dp, 1.0_dp, 23.0_dp, 1.0_dp], [2, 4])
    call build_mortar(xs, segment_normals(xs, .true.), xf, segment_normals(xf, .false.), .false., m, err)
    call check(.not. allocated(err) .and. m%first == 0 .and. m%last == 0 .and. .not. any(m%constrained) .and. &
      all(m%P == 0.0_dp), 'no overlap: empty zone, no error')
  end subroutine test_errors

  !> The steps the P1 and the quadratic builders share, alone: a closed
  !> curve needs three elements; gap0_i = n_i.((P y)_i - x_i) on a made-up P
  !> that puts the master line y = 1 above slave nodes on y = 0 (gap 1).
  subroutine test_shared_steps()
    type(mortar_t) :: m
    type(error_t), allocatable :: err
    real(dp) :: xs(2, 3), xm(2, 2)

    call start_mortar(m, 3, 2)
    call start_periodic(m, 2, 'segment', err)
    call check(allocated(err), 'shared steps: two segments cannot close a curve')
    if (allocated(err)) call check(err%category == error_input .and. index(err%message, 'has 2 segment(s)') > 0, &
                                   'shared steps: the message names the two segments')
    call start_periodic(m, 3, 'element', err)
    call check(.not. allocated(err), 'shared steps: three elements close a curve')
    call check(m%first == 1 .and. m%last == 3 .and. all(m%constrained), 'shared steps: the whole curve constrained')

    xs = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 2.0_dp, 0.0_dp], [2, 3])
    xm = reshape([0.0_dp, 1.0_dp, 2.0_dp, 1.0_dp], [2, 2])
    m%P = reshape([1.0_dp, 0.5_dp, 0.0_dp, 0.0_dp, 0.5_dp, 1.0_dp], [3, 2])
    m%normal = spread([0.0_dp, 1.0_dp], 2, 3)
    call set_initial_gaps(m, xs, xm, 2, 3, 1, 2)
    call check(m%gap0(1) == 0.0_dp, 'shared steps: gap0 only on the rows asked')
    call check_small(maxval(abs(m%gap0(2:3) - 1.0_dp)), tol_round(4), 'shared steps: gap0 = 1 above the slave')
  end subroutine test_shared_steps

end program test_mortar_operator
