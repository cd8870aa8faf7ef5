!> Unit tests of rigid_obstacle: the signed distance and normal of each shape
!> at points with known answers, the orientation of a line from the slave's
!> normals, and the projection pi_h^1 d of the gap (eq. (8)) against
!> independent facts: exact on a distance that is linear along the slave (a
!> tilted line), the constant gap of a circle about a concentric closed
!> polygon reproduced by the periodic projection, the defining orthogonality
!> int (pi d - d) psi_k = 0 on an open slave, the row's rigid terms.
program test_rigid_obstacle
  use kinds, only: dp
  use errors, only: error_t
  use mortar_operator, only: mortar_t
  use rigid_obstacle, only: rigid_shape_t, shape_line, shape_circle, shape_polyline, signed_distance, orient_shape, &
                            build_rigid_mortar, rigid_terms
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  implicit none

  call test_distances()
  call test_orientation()
  call test_linear_gap()
  call test_circle_periodic()
  call test_orthogonality()
  call test_terms()
  call finish_tests()

contains

  subroutine test_distances()
    type(rigid_shape_t) :: sh
    real(dp) :: d, n(2)
    sh%kind = shape_circle
    sh%centre = [1.0_dp, 2.0_dp]
    sh%radius = 0.5_dp
    call signed_distance(sh, [1.0_dp, 3.0_dp], d, n)
    call check_close(d, 0.5_dp, tol_round(4), 'circle: distance outside')
    call check_small(norm2(n - [0.0_dp, 1.0_dp]), tol_round(4), 'circle: radial normal')
    sh%outside = .true.
    call signed_distance(sh, [1.0_dp, 2.25_dp], d, n)
    call check_close(d, 0.25_dp, tol_round(4), 'hole: distance inside the hole')
    call check_small(norm2(n - [0.0_dp, -1.0_dp]), tol_round(4), 'hole: normal towards the centre')
    ! a polyline die: solid above the path (-1,1) -> (-1,0) -> (1,0) -> (1,1) (side +1: on its left)
    sh = rigid_shape_t()
    sh%kind = shape_polyline
    sh%pt = reshape([-1.0_dp, 1.0_dp, -1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp], [2, 4])
    sh%side = 1.0_dp
    sh%length = 2.0_dp
    call signed_distance(sh, [0.3_dp, -0.2_dp], d, n)
    call check_close(d, 0.2_dp, tol_round(4), 'polyline: below its flat')
    call check_small(norm2(n - [0.0_dp, -1.0_dp]), tol_round(4), 'polyline: the flat''s normal')
    call signed_distance(sh, [0.3_dp, 0.1_dp], d, n)
    call check_close(d, -0.1_dp, tol_round(4), 'polyline: inside the die')
    call signed_distance(sh, [1.3_dp, -0.4_dp], d, n)
    call check_close(d, 0.5_dp, tol_round(4), 'polyline: beyond the corner, the distance to it')
    call check_small(norm2(n - [0.6_dp, -0.8_dp]), tol_round(4), 'polyline: beyond the corner, the radial normal')
    call signed_distance(sh, [1.0_dp, 0.0_dp], d, n, hint=[0.0_dp, -1.0_dp])
    call check(d == 0.0_dp .and. all(n == [0.0_dp, -1.0_dp]), 'polyline: on the corner, the hint''s direction')
  end subroutine test_distances

  !> A line with the slave below it, given either way: the solid is above.
  subroutine test_orientation()
    type(rigid_shape_t) :: sh
    real(dp) :: xs(2, 3), nout(2, 2), d, n(2)
    integer :: k
    xs = reshape([0.0_dp, 0.0_dp, 0.5_dp, 0.0_dp, 1.0_dp, 0.0_dp], [2, 3])     ! the slave on the line
    nout = reshape([0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp], [2, 2])                   ! facing up
    do k = 1, 2
      sh = rigid_shape_t()
      sh%kind = shape_line
      sh%length = 3.0_dp
      if (k == 1) sh%pt = reshape([-1.0_dp, 0.0_dp, 2.0_dp, 0.0_dp], [2, 2])
      if (k == 2) sh%pt = reshape([2.0_dp, 0.0_dp, -1.0_dp, 0.0_dp], [2, 2])
      call orient_shape(sh, xs, nout)
      call signed_distance(sh, [0.5_dp, -0.1_dp], d, n)
      call check(d > 0.0_dp .and. n(2) < 0.0_dp, 'line: the solid above the slave that faces up')
    end do
  end subroutine test_orientation

  !> A tilted line over a straight slave: d is linear along the slave, so
  !> pi_h^1 d = d at the nodes (the projection reproduces the trace space).
  subroutine test_linear_gap()
    type(rigid_shape_t) :: sh
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    real(dp) :: xs(2, 7), nout(2, 6), d, n(2)
    integer :: i
    xs(1, :) = [0.0_dp, 0.1_dp, 0.35_dp, 0.5_dp, 0.62_dp, 0.8_dp, 1.0_dp]
    xs(2, :) = 0.0_dp
    nout(1, :) = 0.0_dp
    nout(2, :) = 1.0_dp
    sh%kind = shape_line
    sh%pt = reshape([-1.0_dp, 0.1_dp, 2.0_dp, 0.4_dp], [2, 2])
    sh%length = 3.0_dp
    call orient_shape(sh, xs, nout)
    call build_rigid_mortar(xs, nout, sh, mo, err)
    call check(.not. allocated(err), 'tilted line: built')
    do i = 1, 7
      call signed_distance(sh, xs(:, i), d, n)
      call check_close(mo%gap0(i), d, tol_round(16), 'tilted line: pi_h d = d at the nodes')
      call check_small(norm2(mo%normal(:, i) + n), tol_round(4), 'tilted line: the row direction is -n_r')
    end do
    call check_close(sum(mo%zone_weight(1:7)), 1.0_dp, tol_round(4), 'tilted line: the weights add up to the length')
  end subroutine test_linear_gap

  !> A regular 40-gon inscribed in r = 1 inside a hole of radius 1.1: the
  !> distance is 0.1 at the nodes and more between them, and the periodic
  !> projection of d equals the closed form of the L2 projection of a
  !> rotation-invariant function: the mean over a segment of d times the hats,
  !> integrated here by a fine midpoint rule.
  subroutine test_circle_periodic()
    type(rigid_shape_t) :: sh
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    integer, parameter :: m = 40, nq = 20000
    real(dp) :: xs(2, m + 1), nout(2, m), t, s, x(2), fsum, lseg, pi
    integer :: i, q
    pi = acos(-1.0_dp)
    do i = 1, m + 1
      t = 2 * pi * real(i - 1, dp) / m
      xs(:, i) = [cos(t), sin(t)]
    end do
    xs(:, m + 1) = xs(:, 1)
    do i = 1, m
      t = 2 * pi * (real(i, dp) - 0.5_dp) / m
      nout(:, i) = [cos(t), sin(t)]
    end do
    sh%kind = shape_circle
    sh%radius = 1.1_dp
    sh%outside = .true.
    call build_rigid_mortar(xs, nout, sh, mo, err)
    call check(.not. allocated(err), 'hole: built')
    ! by symmetry pi d is a constant c with c int phi_k = int phi_k d: c = mean of d
    lseg = norm2(xs(:, 2) - xs(:, 1))
    fsum = 0.0_dp
    do q = 1, nq
      s = (real(q, dp) - 0.5_dp) / nq
      x = (1 - s) * xs(:, 1) + s * xs(:, 2)
      fsum = fsum + (1.1_dp - norm2(x))
    end do
    ! the midpoint rule's error on the mean: (lseg / nq)^2 / 24 max |d''|, and
    ! |d''| <= 1 / |x| <= 1 / cos(pi / m) along a chord of the unit circle;
    ! twice that (measured: the bound itself, 2.5e-12)
    do i = 1, m + 1
      call check_small(abs(mo%gap0(i) - fsum / nq), (lseg / nq)**2 / 12 / cos(pi / m), &
                       'hole: periodic pi_h d = the mean distance')
    end do
  end subroutine test_circle_periodic

  !> On an open, non-uniform slave under a circle: the interior rows satisfy
  !> int (pi d - d) psi_k = 0 (psi_k with the end segments' modification),
  !> evaluated by a fine midpoint rule; the end values are d itself.
  subroutine test_orthogonality()
    type(rigid_shape_t) :: sh
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    integer, parameter :: ns = 9, nq = 4000
    real(dp) :: xs(2, ns), nout(2, ns - 1), d, n(2), s, x(2), pid, resid(ns), phi(ns), l
    integer :: e, q
    xs(1, :) = [-1.0_dp, -0.7_dp, -0.5_dp, -0.2_dp, 0.0_dp, 0.15_dp, 0.4_dp, 0.8_dp, 1.0_dp]
    xs(2, :) = 0.0_dp
    nout(1, :) = 0.0_dp
    nout(2, :) = 1.0_dp
    sh%kind = shape_circle
    sh%centre = [0.1_dp, 1.2_dp]
    sh%radius = 1.0_dp
    call build_rigid_mortar(xs, nout, sh, mo, err)
    call signed_distance(sh, xs(:, 1), d, n)
    call check_close(mo%gap0(1), d, tol_round(4), 'open: the end value is d(a1)')
    call signed_distance(sh, xs(:, ns), d, n)
    call check_close(mo%gap0(ns), d, tol_round(4), 'open: the end value is d(a2)')
    resid = 0.0_dp
    do e = 1, ns - 1
      l = xs(1, e + 1) - xs(1, e)
      do q = 1, nq
        s = (real(q, dp) - 0.5_dp) / nq
        x = (1 - s) * xs(:, e) + s * xs(:, e + 1)
        call signed_distance(sh, x, d, n)
        pid = (1 - s) * mo%gap0(e) + s * mo%gap0(e + 1)
        phi = 0.0_dp
        phi(e) = 1 - s
        phi(e + 1) = s
        resid = resid + (pid - d) * phi * l / nq
      end do
    end do
    ! psi_2 = phi_1 + phi_2, psi_{ns-1} = phi_{ns-1} + phi_ns
    resid(2) = resid(2) + resid(1)
    resid(ns - 1) = resid(ns - 1) + resid(ns)
    ! the midpoint rule's error, l^3 / (24 nq^2) max |((pi d - d) phi)''| per
    ! element, with |((pi d - d) phi)''| <= 3 max |d''| <= 3 / 1.2 (the line is
    ! 1.2 from the centre), over the two elements of a psi_k, l <= 0.4:
    ! 2 x 0.4^3 / (24 nq^2) x 2.5 (measured 8.6e-11 of 1.0e-9)
    call check_small(maxval(abs(resid(2:ns - 1))), 2 * 0.4_dp**3 / (24 * real(nq, dp)**2) * 2.5_dp, &
                     'open: int (pi d - d) psi_k = 0 (eq. (8))')
  end subroutine test_orthogonality

  subroutine test_terms()
    type(rigid_shape_t) :: sh
    real(dp) :: c(3)
    sh%ref = [1.0_dp, 2.0_dp]
    c = rigid_terms(sh, [3.0_dp, 5.0_dp], [0.6_dp, 0.8_dp])
    ! U(x) = (ux - theta (y - yr), uy + theta (x - xr)): along v, theta's term v . (-(3), 2)
    call check_small(norm2(c - [0.6_dp, 0.8_dp, 0.6_dp * (-3.0_dp) + 0.8_dp * 2.0_dp]), tol_round(4), &
                     'terms: the motion of x along v per unit ux, uy, theta')
  end subroutine test_terms

end program test_rigid_obstacle
