!> trace_geometry: a boundary trace of degree p as the mortar operators see it,
!> its points, shape functions, nodal normals, and where a line meets it.
!>
!> A trace of degree p (1 or 2) is the chain of its nodes x_1..x_n in order along
!> the boundary, element e holding the nodes p(e-1)+1 .. pe+1 (for p = 2: corner,
!> mid-side node, corner).  On element e, s in [0, 1]:
!>    x(s) = sum_k N_k(s) x_k,   p = 1: N = (1-s, s),
!>    p = 2: N = ((1-s)(1-2s), 4s(1-s), s(2s-1))   (isoparametric: curved edges kept).
!> A trace of degree 1 is a polyline (mortar_geometry); the quadratic operator
!> (mortar_quadratic) takes either degree on either side, and the common normal
!> of a frictional pair (mortar_geometry: trace_common_normals) is written once
!> for both.  Each element carries the outward unit normal of its chord, nout(:, e),
!> which tells the side of the body.
!>
!> Programming interface
!>   trace_point(x, p, e, s, y, dy)     point and derivative of element e at s
!>   trace_shape(p, s, n [, dn])        the p + 1 shape functions at s [and their derivatives]
!>   chord_side(x, p, e, nout)          +1 or -1: the side of [x'_2, -x'_1] the outward normal lies on
!>   trace_normals(x, p, nout, n)       unit outward nodal normals of the curve
!>   ray_on_element(x, p, f, a, d, r)   where the line a + tau d meets element f (Newton in r)
!>   ray_hit(x, p, nout, a, d, f, r)    the nearest hit of a line on the elements that face it
!>   cross(u, v)                        z-component of the cross product of two plane vectors
module trace_geometry
  use kinds, only: dp
  implicit none
  private
  public :: trace_point, trace_shape, chord_side, trace_normals, ray_on_element, ray_hit, cross

  real(dp), parameter :: tol_ray = 1.0e-10_dp      ! slack on the element coordinate of a ray hit

contains

  !> Point y and derivative dy = dx/ds of element e of a trace of degree p at s.
  pure subroutine trace_point(x, p, e, s, y, dy)
    real(dp), intent(in) :: x(:,:), s
    integer, intent(in) :: p, e
    real(dp), intent(out) :: y(2), dy(2)
    integer :: i0
    i0 = p * (e - 1) + 1
    if (p == 1) then
      y = (1.0_dp - s) * x(:, i0) + s * x(:, i0 + 1)
      dy = x(:, i0 + 1) - x(:, i0)
    else
      y = (1.0_dp - s) * (1.0_dp - 2.0_dp * s) * x(:, i0) + 4.0_dp * s * (1.0_dp - s) * x(:, i0 + 1) &
          + s * (2.0_dp * s - 1.0_dp) * x(:, i0 + 2)
      dy = (4.0_dp * s - 3.0_dp) * x(:, i0) + (4.0_dp - 8.0_dp * s) * x(:, i0 + 1) + (4.0_dp * s - 1.0_dp) * x(:, i0 + 2)
    end if
  end subroutine trace_point

  !> Shape functions of a trace element of degree p at s (p + 1 values), and
  !> their derivatives d/ds when dn is present.
  pure subroutine trace_shape(p, s, n, dn)
    integer, intent(in) :: p
    real(dp), intent(in) :: s
    real(dp), intent(out) :: n(3)
    real(dp), intent(out), optional :: dn(3)
    n = 0.0_dp
    if (p == 1) then
      n(1:2) = [1.0_dp - s, s]
    else
      n = [(1.0_dp - s) * (1.0_dp - 2.0_dp * s), 4.0_dp * s * (1.0_dp - s), s * (2.0_dp * s - 1.0_dp)]
    end if
    if (.not. present(dn)) return
    dn = 0.0_dp
    if (p == 1) then
      dn(1:2) = [-1.0_dp, 1.0_dp]
    else
      dn = [4.0_dp * s - 3.0_dp, 4.0_dp - 8.0_dp * s, 4.0_dp * s - 1.0_dp]
    end if
  end subroutine trace_shape

  !> +1 or -1: the side of [x'_2, -x'_1] on which element e's outward chord normal nout lies.
  pure real(dp) function chord_side(x, p, e, nout) result(side)
    real(dp), intent(in) :: x(:,:), nout(2)
    integer, intent(in) :: p, e
    real(dp) :: t(2)
    t = x(:, p * e + 1) - x(:, p * (e - 1) + 1)
    side = sign(1.0_dp, dot_product([t(2), -t(1)], nout))
  end function chord_side

  !> Unit outward nodal normals of a trace: the curve's normal at each node,
  !> the mean of its two elements' at a corner (a closed trace's first node
  !> is its last).
  !>   x (in) (2, np) nodes;  p (in) degree;  nout (in) (2, (np-1)/p) outward chord normals
  !>   n (out) (2, np) unit nodal normals
  subroutine trace_normals(x, p, nout, n)
    real(dp), intent(in) :: x(:,:), nout(:,:)
    integer, intent(in) :: p
    real(dp), allocatable, intent(out) :: n(:,:)
    real(dp) :: sigma, y(2), dy(2), t(2)
    integer :: np, e, k, i
    np = size(x, 2)
    allocate(n(2, np), source=0.0_dp)
    do e = 1, (np - 1) / p
      sigma = chord_side(x, p, e, nout(:, e))
      do k = 0, p
        call trace_point(x, p, e, real(k, dp) / p, y, dy)
        t = sigma * [dy(2), -dy(1)]
        if (dot_product(t, nout(:, e)) > 16 * epsilon(1.0_dp) * norm2(x(:, p * e + 1) - x(:, p * (e - 1) + 1))) then
          n(:, p * (e - 1) + 1 + k) = n(:, p * (e - 1) + 1 + k) + t / norm2(t)
        else
          ! a quadratic element whose mid-side node sits at a quarter point
          ! has x' = 0 at its corner (the map is singular there, as crack-tip
          ! elements are made), and round-off may turn x' there either way:
          ! its chord's normal stands in for the tangent's
          n(:, p * (e - 1) + 1 + k) = n(:, p * (e - 1) + 1 + k) + nout(:, e)
        end if
      end do
    end do
    if (all(x(:, 1) == x(:, np))) then
      n(:, 1) = n(:, 1) + n(:, np)
      n(:, np) = n(:, 1)
    end if
    do i = 1, np
      n(:, i) = n(:, i) / norm2(n(:, i))
    end do
  end subroutine trace_normals

  !> The coordinate r of element f where the line a + tau d meets it:
  !> cross(y(r) - a, d) = 0, Newton from r on entry (exact in one step on a
  !> straight element).
  !>   x (in) (2, np) trace nodes;  p (in) degree;  f (in) the element
  !>   a, d (in) (2) point and direction of the line;  r (inout) start, then the hit
  subroutine ray_on_element(x, p, f, a, d, r)
    real(dp), intent(in) :: x(:,:), a(2), d(2)
    integer, intent(in) :: p, f
    real(dp), intent(inout) :: r
    real(dp) :: y(2), dy(2), g, dg
    integer :: it
    do it = 1, 20
      call trace_point(x, p, f, r, y, dy)
      g = (y(1) - a(1)) * d(2) - (y(2) - a(2)) * d(1)
      dg = dy(1) * d(2) - dy(2) * d(1)
      if (dg == 0.0_dp) exit
      r = r - g / dg
      if (abs(g / dg) < 1.0e-15_dp) exit
    end do
  end subroutine ray_on_element

  !> The nearest hit of the line a + tau d on an element of a trace whose
  !> chord normal faces d (nout . d < 0).  The chord's hit is exact on a
  !> straight element; on a curved one it starts a Newton on the curve
  !> (ray_on_element), the chords a little beyond the element [-0.5, 1.5]
  !> included, since a curve may reach further than its chord.
  !>   x (in) (2, np) trace nodes;  p (in) degree;  nout (in) (2, (np-1)/p) outward chord normals
  !>   a, d (in) (2) point and unit direction of the line
  !>   f (out) the element, 0 when the line misses the trace;  r (out) its coordinate in [0, 1]
  subroutine ray_hit(x, p, nout, a, d, f, r)
    real(dp), intent(in) :: x(:,:), nout(:,:), a(2), d(2)
    integer, intent(in) :: p
    integer, intent(out) :: f
    real(dp), intent(out) :: r
    real(dp) :: ya(2), yb(2), y(2), dy(2), den, rr, best, tau
    integer :: g
    f = 0
    r = 0.0_dp
    best = huge(1.0_dp)
    do g = 1, size(nout, 2)
      if (dot_product(nout(:, g), d) >= 0.0_dp) cycle
      ya = x(:, p * (g - 1) + 1)
      yb = x(:, p * g + 1)
      den = cross(d, yb - ya)
      if (abs(den) <= 1.0e-12_dp * norm2(yb - ya)) cycle      ! element along the line
      rr = -cross(d, ya - a) / den                           ! a + tau d = ya + rr (yb - ya)
      if (p > 1) then
        if (rr < -0.5_dp .or. rr > 1.5_dp) cycle
        call ray_on_element(x, p, g, a, d, rr)
      end if
      if (rr < -tol_ray .or. rr > 1.0_dp + tol_ray) cycle
      if (p == 1) then
        tau = cross(ya - a, yb - ya) / den
      else
        call trace_point(x, p, g, rr, y, dy)
        tau = dot_product(y - a, d)
      end if
      if (abs(tau) < best) then
        best = abs(tau)
        f = g
        r = min(1.0_dp, max(0.0_dp, rr))
      end if
    end do
  end subroutine ray_hit

  !> z-component of the cross product of two plane vectors.
  pure real(dp) function cross(u, v)
    real(dp), intent(in) :: u(2), v(2)
    cross = u(1) * v(2) - u(2) * v(1)
  end function cross

end module trace_geometry
