!> Unit tests of trace_geometry and of the common normal over the trace degree
!> (mortar_geometry: trace_common_normals), against closed forms and symmetry:
!>   - ray_hit on a straight segment: the hit of a line, by hand; a segment
!>     whose normal does not face the line is passed over; of two segments
!>     in line, the nearer;
!>   - ray_hit on a curved element, the parabola x(s) = (s, 0.4 s (1 - s)):
!>     a vertical line at x = 0.3 meets it at s = 0.3;
!>   - trace_shape: a partition of unity that interpolates the nodes, and
!>     its derivatives (a central difference);
!>   - common normals of two mirror images (a circular arc above its mirror
!>     image below y = 0), traces of degree 1 and of degree 2 alike, and of
!>     either degree on either side: the weight 1/2 (same degrees); the apex
!>     pairs straight across; nodes placed symmetrically about the apex get
!>     mirror-image normals; and the common normal leans far less than the
!>     slave normal (the two surfaces approach along -y);
!>   - a flat slave on a curved master: weight 1, the slave normal.
program test_trace_geometry
  use kinds, only: dp
  use trace_geometry, only: trace_point, trace_shape, ray_hit
  use mortar_geometry, only: trace_common_normals
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none

  call test_straight_hits()
  call test_curved_hit()
  call test_shapes()
  call test_mirror_images(1, 1)
  call test_mirror_images(2, 2)
  call test_mirror_images(2, 1)
  call test_mirror_images(1, 2)
  call test_flat_slave(1)
  call test_flat_slave(2)
  call finish_tests()

contains

  subroutine test_straight_hits()
    real(dp) :: x(2, 3), nout(2, 2), r
    integer :: f
    ! two segments in line along y = 1, outward normal (0, -1)
    x = reshape([0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 2.0_dp, 1.0_dp], [2, 3])
    nout = reshape([0.0_dp, -1.0_dp, 0.0_dp, -1.0_dp], [2, 2])
    ! from (1.25, 0) along (0, 1): segment 2 at r = 0.25
    call ray_hit(x, 1, nout, [1.25_dp, 0.0_dp], [0.0_dp, 1.0_dp], f, r)
    call check(f == 2, 'straight: the line meets segment 2')
    call check_small(r - 0.25_dp, tol_round(4), 'straight: at r = 0.25')
    ! the same line along (0, -1): the normals do not face it
    call ray_hit(x, 1, nout, [1.25_dp, 2.0_dp], [0.0_dp, -1.0_dp], f, r)
    call check(f == 0, 'straight: a segment whose normal does not face the line is passed over')
    ! a slanted line from (0.5, 0) along (0.6, 0.8): y = 1 at x = 0.5 + 0.75 (segment 2, r = 0.25)
    call ray_hit(x, 1, nout, [0.5_dp, 0.0_dp], [0.6_dp, 0.8_dp], f, r)
    call check(f == 2, 'straight, slanted: segment 2')
    call check_small(r - 0.25_dp, tol_round(8), 'straight, slanted: at r = 0.25')
    ! beyond the trace's end: no hit
    call ray_hit(x, 1, nout, [2.5_dp, 0.0_dp], [0.0_dp, 1.0_dp], f, r)
    call check(f == 0, 'straight: a line beyond the end misses')
    ! a trace that folds back under itself: of the two segments across the line, the nearer
    block
      real(dp) :: x2(2, 4), n2(2, 3)
      x2 = reshape([0.0_dp, 1.0_dp, 3.0_dp, 1.0_dp, 3.0_dp, 0.5_dp, 0.0_dp, 0.5_dp], [2, 4])
      n2 = reshape([0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, -1.0_dp], [2, 3])
      call ray_hit(x2, 1, n2, [1.5_dp, 0.0_dp], [0.0_dp, 1.0_dp], f, r)
      call check(f == 3, 'straight: of two segments across the line, the nearer')
      call check_small(r - 0.5_dp, tol_round(4), 'straight: the nearer at r = 0.5')
    end block
  end subroutine test_straight_hits

  subroutine test_curved_hit()
    real(dp) :: x(2, 3), nout(2, 1), r, y(2), dy(2)
    integer :: f
    ! x(s) = (s, 0.4 s (1 - s)): the mid-side node at (0.5, 0.1)
    x = reshape([0.0_dp, 0.0_dp, 0.5_dp, 0.1_dp, 1.0_dp, 0.0_dp], [2, 3])
    nout(:, 1) = [0.0_dp, 1.0_dp]
    call ray_hit(x, 2, nout, [0.3_dp, 1.0_dp], [0.0_dp, -1.0_dp], f, r)
    call check(f == 1, 'curved: the line meets the element')
    call check_small(r - 0.3_dp, tol_round(8), 'curved: at s = 0.3')
    call trace_point(x, 2, 1, r, y, dy)
    call check_small(y(2) - 0.4_dp * 0.3_dp * 0.7_dp, tol_round(8), 'curved: the hit lies on the parabola')
    ! the chord's hit (s = 0.3 too here) is not the curve's away from the apex:
    ! a slanted line from (0, 1) along (0.6, -0.8)
    call ray_hit(x, 2, nout, [0.0_dp, 1.0_dp], [0.6_dp, -0.8_dp], f, r)
    call trace_point(x, 2, 1, r, y, dy)
    call check_small((y(1) - 0.0_dp) * (-0.8_dp) - (y(2) - 1.0_dp) * 0.6_dp, tol_round(16), &
                     'curved, slanted: the hit lies on the line')
  end subroutine test_curved_hit

  subroutine test_shapes()
    real(dp) :: n(3), dn(3), np(3), nm(3), s, h, err
    integer :: p, k
    h = 1.0e-6_dp
    do p = 1, 2
      err = 0.0_dp
      do k = 0, p                                   ! N_j(node k) = delta_jk
        call trace_shape(p, real(k, dp) / p, n)
        n(k + 1) = n(k + 1) - 1.0_dp
        err = max(err, maxval(abs(n(1:p + 1))))
      end do
      call check_small(err, tol_round(4), 'shape: N_j(node k) = delta_jk, degree ' // achar(48 + p))
      s = 0.37_dp
      call trace_shape(p, s, n)
      call check_small(sum(n(1:p + 1)) - 1.0_dp, tol_round(8), 'shape: partition of unity, degree ' // achar(48 + p))
      call trace_shape(p, s, n, dn)
      call trace_shape(p, s + h, np)
      call trace_shape(p, s - h, nm)
      ! central difference: exact for a quadratic up to its round-off eps / h
      call check_small(maxval(abs((np - nm) / (2 * h) - dn)), 1.0e-9_dp, &
                       'shape: derivative = central difference, degree ' // achar(48 + p))
    end do
  end subroutine test_shapes

  !> A circular arc of radius R above the x axis (centre (0, R + g)), from
  !> angle -t0 to t0, and its mirror image below; ne elements of degree ps on
  !> the slave, pm on the master, the nodes at equal angles (the mid-side
  !> nodes on the circle).
  subroutine test_mirror_images(ps, pm)
    integer, intent(in) :: ps, pm
    integer, parameter :: ne = 8
    real(dp), parameter :: rad = 1.0_dp, gap = 1.0e-3_dp, t0 = 0.4_dp
    real(dp) :: xs(2, ps * ne + 1), xm(2, pm * ne + 1), sn(2, ne), mn(2, ne), c(2), w, tilt
    real(dp), allocatable :: nc(:,:)
    logical :: face(ne)
    integer :: i, n, e
    character(len=24) :: tag
    write(tag, '(a,i0,a,i0)') 'degrees ', ps, ' on ', pm
    n = ps * ne + 1
    call arc_nodes(rad, gap, t0, xs)
    call arc_nodes(rad, gap, t0, xm)
    xm(2, :) = -xm(2, :)
    do e = 1, ne                                   ! chord normals: slave below, master above
      c = xs(:, ps * e + 1) - xs(:, ps * (e - 1) + 1)
      sn(:, e) = [c(2), -c(1)] / norm2(c)
      c = xm(:, pm * e + 1) - xm(:, pm * (e - 1) + 1)
      mn(:, e) = [-c(2), c(1)] / norm2(c)
    end do
    face = .true.
    call trace_common_normals(xs, ps, sn, face, xm, pm, mn, face, nc, w)
    if (ps == pm) call check_small(w - 0.5_dp, 0.0_dp, 'mirror images, ' // trim(tag) // ': weight 1/2')
    call check_small(norm2(nc(:, (n + 1) / 2) - [0.0_dp, -1.0_dp]), tol_round(8), &
                     'mirror images, ' // trim(tag) // ': the apex pairs straight across')
    call check_small(maxval(abs(nc(1, :) + nc(1, n:1:-1))) + maxval(abs(nc(2, :) - nc(2, n:1:-1))), &
                     tol_round(64), 'mirror images, ' // trim(tag) // ': symmetric nodes, mirror-image normals')
    ! inside, away from the ends (whose lines leave the master), each pass
    ! shrinks the lean by a factor near twice the node's gap over R (< 0.2
    ! here): after four passes below 1e-3 of the slave normal's own
    tilt = 0.0_dp
    do i = ps + 1, n - ps
      if (2 * i == n + 1) cycle                      ! the apex: no lean
      tilt = max(tilt, abs(nc(1, i)) / (abs(xs(1, i)) / rad))
    end do
    call check_small(tilt, 1.0e-3_dp, 'mirror images, ' // trim(tag) // ': the common normal leans far less')
  end subroutine test_mirror_images

  !> Nodes of the arc of radius rad, centre (0, rad + gap), angles -t0..t0,
  !> equally spaced: nodes k and m + 1 - k at opposite angles, exactly.
  subroutine arc_nodes(rad, gap, t0, x)
    real(dp), intent(in) :: rad, gap, t0
    real(dp), intent(out) :: x(:,:)
    real(dp) :: t
    integer :: k, m
    m = size(x, 2)
    do k = 1, m
      t = t0 * real(2 * k - m - 1, dp) / (m - 1)
      x(:, k) = [rad * sin(t), rad + gap - rad * cos(t)]
    end do
  end subroutine arc_nodes

  !> A flat slave y = 1e-3 (normal (0, -1)) on the arc of test_mirror_images
  !> mirrored (convex master): the master alone is curved, weight 1.
  subroutine test_flat_slave(p)
    integer, intent(in) :: p
    integer, parameter :: ne = 6
    real(dp) :: xs(2, p * ne + 1), xm(2, p * ne + 1), sn(2, ne), mn(2, ne), t, c(2), w
    real(dp), allocatable :: nc(:,:)
    logical :: face(ne)
    integer :: i, n, e
    character(len=8) :: tag
    n = p * ne + 1
    write(tag, '(a,i0)') 'degree ', p
    do i = 1, n
      t = -0.3_dp + 0.6_dp * (i - 1) / (n - 1)
      xs(:, i) = [-0.35_dp + 0.7_dp * (i - 1) / (n - 1), 1.0e-3_dp]
      xm(:, i) = [sin(t), cos(t) - 1.0_dp]
    end do
    do e = 1, ne
      sn(:, e) = [0.0_dp, -1.0_dp]
      c = xm(:, p * e + 1) - xm(:, p * (e - 1) + 1)
      mn(:, e) = [-c(2), c(1)] / norm2(c)
    end do
    face = .true.
    call trace_common_normals(xs, p, sn, face, xm, p, mn, face, nc, w)
    call check_small(w - 1.0_dp, 0.0_dp, 'flat slave, ' // trim(tag) // ': weight 1')
    call check_small(maxval(abs(nc(1, :))) + maxval(abs(nc(2, :) + 1.0_dp)), tol_round(4), &
                     'flat slave, ' // trim(tag) // ': the slave normal')
  end subroutine test_flat_slave

end program test_trace_geometry
