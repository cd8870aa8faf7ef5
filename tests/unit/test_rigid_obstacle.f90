!> Unit tests of rigid_obstacle: the signed distance and normal of each shape
!> at points with known answers, the orientation of a line from the slave's
!> normals, and the projection pi_h^1 d of the gap (eq. (8)) against
!> independent facts: exact on a distance that is linear along the slave (a
!> tilted line), the constant gap of a circle about a concentric closed
!> polygon reproduced by the periodic projection, the defining orthogonality
!> int (pi d - d) psi_k = 0 on an open slave, the row's rigid terms; on a
!> quadratic trace in axisymmetry (weight 2 pi r): a linear distance
!> reproduced with an end on the axis, the weights adding up to the annulus'
!> area, and the orthogonality with the quadratic multiplier space; on a
!> closed quadratic trace the periodic projection's orthogonality.
program test_rigid_obstacle
  use kinds, only: dp
  use errors, only: error_t
  use mortar_operator, only: mortar_t
  use trace_geometry, only: trace_point, trace_shape
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
  call test_quadratic_axis()
  call test_quadratic_orthogonality()
  call test_quadratic_periodic()
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
    call build_rigid_mortar(xs, 1, nout, sh, .false., mo, err)
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
    call build_rigid_mortar(xs, 1, nout, sh, .false., mo, err)
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
    call build_rigid_mortar(xs, 1, nout, sh, .false., mo, err)
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

  !> A quadratic slave on r in [0, 1] (4 elements, uneven, the mid-side nodes
  !> off the middles but on the axis element) under a tilted line, axisymmetric: pi_h d = d at every
  !> node (d is linear along the trace, in the space whatever the weight),
  !> the weights add up to int 2 pi r dr = pi, and the end on the axis has
  !> the axis as its normal and a corner hat of no weight.
  subroutine test_quadratic_axis()
    type(rigid_shape_t) :: sh
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    real(dp) :: xs(2, 9), nout(2, 4), d, n(2), pi
    integer :: i
    pi = acos(-1.0_dp)
    xs(1, :) = [0.0_dp, 0.125_dp, 0.25_dp, 0.3_dp, 0.45_dp, 0.6_dp, 0.7_dp, 0.9_dp, 1.0_dp]
    xs(2, :) = 0.0_dp
    nout(1, :) = 0.0_dp
    nout(2, :) = 1.0_dp
    sh%kind = shape_line
    sh%pt = reshape([-1.0_dp, 0.1_dp, 2.0_dp, 0.4_dp], [2, 2])
    sh%length = 3.0_dp
    call orient_shape(sh, xs(:, 1:9:2), nout)
    call build_rigid_mortar(xs, 2, nout, sh, .true., mo, err)
    call check(.not. allocated(err), 'quadratic axisymmetric: built')
    do i = 1, 9
      call signed_distance(sh, xs(:, i), d, n)
      call check_close(mo%gap0(i), d, tol_round(64), 'quadratic axisymmetric: pi_h d = d at the nodes')
    end do
    call check_close(sum(mo%zone_weight), pi, tol_round(16), 'quadratic axisymmetric: the weights add up to pi')
    call check(mo%axis_end(1) .and. .not. mo%axis_end(2), 'quadratic axisymmetric: the first end is on the axis')
    call check_small(norm2(mo%normal(:, 1) - [0.0_dp, 1.0_dp]), tol_round(4), 'quadratic axisymmetric: axial normal')
    call check_small(mo%zone_weight(1), tol_round(4), &
                     'quadratic axisymmetric: the corner hat on the axis weighs 0 (int (1-s)(1-2s) s ds)')
  end subroutine test_quadratic_axis

  !> A quadratic slave on r in [0.5, 1.5] (4 elements) under a circle,
  !> axisymmetric: the end values are d, and int (pi d - d) psi_k 2 pi r ds = 0
  !> for the quadratic multiplier space (psi_1 = phi_0 + phi_1/2, psi_2 =
  !> phi_1/2 + phi_2, psi_k = phi_k, psi_6 = phi_6 + phi_7/2, psi_7 = phi_7/2 +
  !> phi_8), by a fine midpoint rule.
  subroutine test_quadratic_orthogonality()
    type(rigid_shape_t) :: sh
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    integer, parameter :: nq = 4000
    real(dp) :: xs(2, 9), nout(2, 4), d, n(2), s, x(2), dx(2), nn(3), pid, res(0:8), psi(7), w, pi
    integer :: e, q, i
    pi = acos(-1.0_dp)
    xs(1, :) = [0.5_dp, 0.6_dp, 0.75_dp, 0.85_dp, 0.95_dp, 1.1_dp, 1.2_dp, 1.35_dp, 1.5_dp]
    xs(2, :) = 0.0_dp
    nout(1, :) = 0.0_dp
    nout(2, :) = 1.0_dp
    sh%kind = shape_circle
    sh%centre = [0.8_dp, 1.2_dp]
    sh%radius = 1.0_dp
    call build_rigid_mortar(xs, 2, nout, sh, .true., mo, err)
    call check(.not. allocated(err), 'quadratic orthogonality: built')
    call signed_distance(sh, xs(:, 1), d, n)
    call check_close(mo%gap0(1), d, tol_round(4), 'quadratic orthogonality: the end value is d(a1)')
    res = 0.0_dp
    do e = 1, 4
      do q = 1, nq
        s = (real(q, dp) - 0.5_dp) / nq
        call trace_point(xs, 2, e, s, x, dx)
        call trace_shape(2, s, nn)
        call signed_distance(sh, x, d, n)
        i = 2 * (e - 1)
        pid = dot_product(nn, mo%gap0(i + 1:i + 3))
        w = norm2(dx) / nq * 2 * pi * x(1)
        res(i:i + 2) = res(i:i + 2) + (pid - d) * nn * w
      end do
    end do
    psi = [res(0) + res(1) / 2, res(1) / 2 + res(2), res(3), res(4), res(5), res(6) + res(7) / 2, res(7) / 2 + res(8)]
    ! the midpoint rule's error, h^2 / 24 of the second derivative's integral:
    ! below 1e-9 here (|d''| <= 1 / 1.2, the line is 1.2 below the centre)
    call check_small(maxval(abs(psi)), 1.0e-8_dp, 'quadratic orthogonality: int (pi d - d) psi_k 2 pi r = 0')
  end subroutine test_quadratic_orthogonality

  !> A closed quadratic trace, 12 elements with their nodes on the unit circle
  !> (curved), off-centre inside a hole of radius 1.3: the periodic
  !> projection satisfies int (pi d - d) phi_k = 0 for every node k (the
  !> closed curve's multiplier space is the whole periodic trace space), by a
  !> fine midpoint rule, and its last node repeats its first.
  subroutine test_quadratic_periodic()
    type(rigid_shape_t) :: sh
    type(mortar_t) :: mo
    type(error_t), allocatable :: err
    integer, parameter :: m = 12, nq = 4000
    real(dp) :: xs(2, 2 * m + 1), nout(2, m), t, s, x(2), dx(2), nn(3), d, n(2), res(0:2 * m), pi
    integer :: i, e, q
    pi = acos(-1.0_dp)
    do i = 1, 2 * m + 1
      t = pi * real(i - 1, dp) / m
      xs(:, i) = [cos(t), sin(t)]
    end do
    xs(:, 2 * m + 1) = xs(:, 1)
    do e = 1, m
      t = pi * (2 * real(e, dp) - 1) / m
      nout(:, e) = [cos(t), sin(t)]
    end do
    sh%kind = shape_circle
    sh%centre = [0.1_dp, -0.05_dp]
    sh%radius = 1.3_dp
    sh%outside = .true.
    call build_rigid_mortar(xs, 2, nout, sh, .false., mo, err)
    call check(.not. allocated(err), 'quadratic periodic: built')
    call check_close(mo%gap0(2 * m + 1), mo%gap0(1), tol_round(4), 'quadratic periodic: the last node is the first')
    res = 0.0_dp
    do e = 1, m
      do q = 1, nq
        s = (real(q, dp) - 0.5_dp) / nq
        call trace_point(xs, 2, e, s, x, dx)
        call trace_shape(2, s, nn)
        call signed_distance(sh, x, d, n)
        i = 2 * (e - 1)
        res(i:i + 2) = res(i:i + 2) + (dot_product(nn, mo%gap0(i + 1:i + 3)) - d) * nn * norm2(dx) / nq
      end do
    end do
    res(0) = res(0) + res(2 * m)
    ! the midpoint rule's error on each integral, h^2 / 24 of the second
    ! derivative's integral over an element (h = 1 / nq of an arc of pi / 6):
    ! below 1e-9 here
    call check_small(maxval(abs(res(0:2 * m - 1))), 1.0e-9_dp, 'quadratic periodic: int (pi d - d) phi_k = 0')
  end subroutine test_quadratic_periodic

end program test_rigid_obstacle
