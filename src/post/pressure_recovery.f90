!> pressure_recovery: a second approximation p* of the contact pressure,
!> rebuilt on the slave trace from the mortar pressure p_h alone, whose
!> distance to p_h estimates the error of p_h (run_estimate, `estimate
!> pressure`; doc/theory.md, "Error estimate").
!>
!> Why on the trace and not from the bulk: the normal traction of a nodally
!> recovered stress is O(h) wrong on a boundary, where a patch has no outer
!> half, while the mortar pressure is often far better (a press fit's is
!> exact to 1e-4); and near a zone's free end the pressure is not smooth,
!> p ~ sqrt(distance to the end), which no polynomial recovery follows.  The
!> error of p_h is made of two parts (measured on Hertz, doc/theory.md): the
!> free ends of the zone, an O(h) error that dominates from a/h = 1 to 14
!> (a the half-width), and inside an O(h^2) (linear traces) or O(h^3)
!> (quadratic) smooth part.  p* follows each:
!>  - inside a run of nodes in contact, on each segment, the polynomial of
!>    degree q + 1 (q = 1 on linear traces, 2 on quadratic ones, whose
!>    mid-side nodes are nodes of the trace here) fitted by least squares to
!>    p_h at the q + 3 nodes of the run nearest to the segment: what the next
!>    order would give;
!>  - at a free end, where the run's last node in contact has a neighbour in
!>    the zone that is open: p* = sqrt(c (d - d0)), d the distance inward from
!>    the open node, zero for d < d0.  Past a smooth separation the gap grows
!>    as (distance)^(3/2), so gap^(2/3) of the first two open nodes, linear,
!>    extrapolated to zero, places the end (d0, kept within the end element);
!>    the gaps come from the displacements, better than the pressure.  c is the
!>    least-squares amplitude over the run's last three nodes (up to the
!>    pressure's peak).  Without two open gaps, p_h^2 linear over those nodes
!>    places the end; without that, mid-element.  This p* holds on the open
!>    segment and the run's last one;
!>  - the end of a run with no open neighbour (the end of the trace or of the
!>    effective zone: a press fit's edge, a punch's corner) is no square-root
!>    end: the interior fit reaches it, one-sided, so that a constant
!>    pressure has p* = p_h there.
!> Each segment's integral of (p_h - p*)^2 dS is exact (4-point Gauss; the
!> square root's part after the substitution d - d0 = t^2, a polynomial in t),
!> p_h linear between the nodes (as the contact table and the VTK show it).
!> What is proved and what is measured: doc/theory.md, "Error estimate".
!>
!> Programming interface
!>   trace_errors(s, p, gap, wn, zone, quadratic, d2, p2)
!>        per segment of one slave trace, int (p_h - p*)^2 dS and int p_h^2 dS
module pressure_recovery
  use kinds, only: dp
  implicit none
  private
  public :: trace_errors

  !> 4-point Gauss-Legendre on [0, 1]: exact to degree 7
  real(dp), parameter :: gx(4) = 0.5_dp + 0.5_dp * [-0.8611363115940526_dp, -0.3399810435848563_dp, &
                                                     0.3399810435848563_dp, 0.8611363115940526_dp]
  real(dp), parameter :: gw(4) = 0.5_dp * [0.3478548451374538_dp, 0.6521451548625461_dp, &
                                           0.6521451548625461_dp, 0.3478548451374538_dp]
  !> a node is in contact when its pressure is above this fraction of the trace's largest
  !> (as the contact table's status, doc/outputs.md)
  real(dp), parameter :: contact_fraction = 1.0e-12_dp
  !> nodes of the run a square-root end is fitted to
  integer, parameter :: end_nodes = 3

  !> The reconstruction p* on one segment: a polynomial in the segment's local
  !> coordinate, or a square-root end.
  type :: segment_fit_t
    logical :: root = .false.          !< a square-root end (else the polynomial)
    real(dp) :: c(0:3) = 0.0_dp        !< polynomial: p* = sum c(j) ((s - s0) / len)^j
    real(dp) :: s0 = 0.0_dp, len = 1.0_dp
    real(dp) :: send = 0.0_dp          !< root: the end's position s; p* = sqrt(amp |s - send|) on its inward side
    real(dp) :: amp = 0.0_dp
    integer :: inward = 1              !< root: +1 when the zone lies at s > send, -1 at s < send
  end type segment_fit_t

contains

  !> Per segment of one slave trace (nodes in order along it), the squared
  !> L2 distance between p_h and the reconstruction p* (module header) and
  !> p_h's own square, both with the measure dS.
  !>   s         (in)  (ns) the arc length at the nodes, increasing
  !>   p         (in)  (ns) p_h at the nodes (0 off contact)
  !>   gap       (in)  (ns) the normal gap at the nodes (used at open nodes)
  !>   wn        (in)  (ns) the measure's weight at the nodes (thickness, or 2 pi r): linear between them
  !>   zone      (in)  (ns) the node has a contact constraint of its own (the effective zone)
  !>   quadratic (in)  the trace is quadratic (its mid-side nodes listed)
  !>   d2        (out) (ns-1) int (p_h - p*)^2 dS over the segment (0 off the runs in contact)
  !>   p2        (out) (ns-1) int p_h^2 dS over segments of the zone (0 elsewhere)
  subroutine trace_errors(s, p, gap, wn, zone, quadratic, d2, p2)
    real(dp), intent(in) :: s(:), p(:), gap(:), wn(:)
    logical, intent(in) :: zone(:), quadratic
    real(dp), intent(out) :: d2(:), p2(:)
    logical, allocatable :: on(:)
    type(segment_fit_t) :: right, left
    integer :: ns, k, l, r, deg, npatch
    logical :: free_r, free_l
    ns = size(s)
    d2 = 0.0_dp
    p2 = 0.0_dp
    if (ns < 2) return
    deg = merge(3, 2, quadratic)
    npatch = deg + 2
    allocate(on(ns))
    on = zone .and. p > contact_fraction * maxval(p)
    do k = 1, ns - 1
      if (zone(k) .and. zone(k + 1)) p2(k) = segment_integral(s, p, wn, k, poly_fit_zero())
    end do
    k = 1
    do while (k <= ns)                 ! each run l..r of nodes in contact
      if (.not. on(k)) then
        k = k + 1
        cycle
      end if
      l = k
      r = k
      do while (r < ns)
        if (.not. on(r + 1)) exit
        r = r + 1
      end do
      free_r = .false.
      free_l = .false.
      if (r < ns) free_r = zone(r + 1)
      if (l > 1) free_l = zone(l - 1)
      if (free_r) then
        right = end_fit(s, p, gap, zone, on, r, r + 1, l, r, -1)
        d2(r) = segment_integral(s, p, wn, r, right)
      end if
      if (free_l) then
        left = end_fit(s, p, gap, zone, on, l, l - 1, l, r, 1)
        d2(l - 1) = segment_integral(s, p, wn, l - 1, left)
      end if
      do k = l, r - 1                  ! the run's own segments
        if (free_r .and. k == r - 1) then
          d2(k) = segment_integral(s, p, wn, k, right)
        else if (free_l .and. k == l) then
          d2(k) = segment_integral(s, p, wn, k, left)
        else
          d2(k) = segment_integral(s, p, wn, k, patch_fit(s, p, k, l, r, deg, npatch))
        end if
      end do
      k = r + 1
    end do
  end subroutine trace_errors

  !> The fit p* = 0: segment_integral then gives int p_h^2 dS.
  pure function poly_fit_zero() result(f)
    type(segment_fit_t) :: f
    f%root = .false.
    f%c = 0.0_dp
  end function poly_fit_zero

  !> The polynomial of degree deg (at most the patch's nodes less one) fitted
  !> by least squares to p_h at the npatch nodes of run l..r nearest segment k.
  !>   s, p (in) (ns) arc length and p_h at the nodes
  !>   k    (in) the segment, nodes k and k + 1, both in the run
  !>   l, r (in) the run's first and last node
  pure function patch_fit(s, p, k, l, r, deg, npatch) result(f)
    real(dp), intent(in) :: s(:), p(:)
    integer, intent(in) :: k, l, r, deg, npatch
    type(segment_fit_t) :: f
    real(dp) :: a(0:3, 0:3), b(0:3), x, xp(0:6)
    integer :: lo, hi, i, j, m, dg
    lo = max(l, k - (npatch - 2) / 2)
    hi = min(r, lo + npatch - 1)
    lo = max(l, hi - npatch + 1)
    dg = min(deg, hi - lo)
    f%root = .false.
    f%s0 = s(k)
    f%len = s(k + 1) - s(k)
    a = 0.0_dp
    b = 0.0_dp
    do i = lo, hi                      ! normal equations in the scaled coordinate: well conditioned at degree <= 3
      x = (s(i) - f%s0) / f%len
      xp(0) = 1.0_dp
      do m = 1, 2 * dg
        xp(m) = xp(m - 1) * x
      end do
      do j = 0, dg
        a(j, 0:dg) = a(j, 0:dg) + xp(j:j + dg)
        b(j) = b(j) + p(i) * xp(j)
      end do
    end do
    f%c = 0.0_dp
    call small_solve(a(0:dg, 0:dg), b(0:dg), f%c(0:dg))
  end function patch_fit

  !> The square-root end of run l..r at its node e, whose neighbour o in the
  !> zone is open (module header): where p* vanishes and its amplitude.
  !>   s, p, gap (in) (ns) arc length, p_h and gap at the nodes
  !>   zone, on  (in) (ns) the node is in the zone, in contact
  !>   e, o      (in) the run's end node and the open node next to it
  !>   l, r      (in) the run
  !>   inward    (in) +1 when the run lies at s > s(o) (a left end), -1 for a right end
  function end_fit(s, p, gap, zone, on, e, o, l, r, inward) result(f)
    real(dp), intent(in) :: s(:), p(:), gap(:)
    logical, intent(in) :: zone(:), on(:)
    integer, intent(in) :: e, o, l, r, inward
    type(segment_fit_t) :: f
    integer :: idx(end_nodes), n, i, o2
    real(dp) :: h, d(end_nodes), w(end_nodes), d0, t1, t2, sx, sy, sxx, sxy, slope, icpt
    logical :: placed
    h = abs(s(e) - s(o))
    n = 1                              ! the run's last nodes, up to the peak: the side the square root describes
    idx(1) = e
    do i = 2, end_nodes
      if (e + inward * (i - 1) < l .or. e + inward * (i - 1) > r) exit
      if (p(e + inward * (i - 1)) < p(idx(n))) exit
      n = n + 1
      idx(n) = e + inward * (i - 1)
    end do
    d(1:n) = abs(s(idx(1:n)) - s(o))
    placed = .false.
    o2 = o - inward                    ! the second open node, further out
    d0 = 0.5_dp * h
    f%amp = 0.0_dp
    if (o2 >= 1 .and. o2 <= size(s)) then
      if (zone(o2) .and. .not. on(o2) .and. gap(o) > 0.0_dp .and. gap(o2) > gap(o)) then
        t1 = gap(o)**(2.0_dp / 3.0_dp)
        t2 = gap(o2)**(2.0_dp / 3.0_dp)
        d0 = min(h, t1 * abs(s(o2) - s(o)) / (t2 - t1))
        w(1:n) = sqrt(max(0.0_dp, d(1:n) - d0))
        if (sum(w(1:n)**2) > 0.0_dp) then
          f%amp = (sum(p(idx(1:n)) * w(1:n)) / sum(w(1:n)**2))**2
          placed = .true.
        end if
      end if
    end if
    if (.not. placed .and. n >= 2) then  ! p_h^2 = slope (d - d0): least squares over the nodes
      sx = sum(d(1:n))
      sy = sum(p(idx(1:n))**2)
      sxx = sum(d(1:n)**2)
      sxy = sum(d(1:n) * p(idx(1:n))**2)
      slope = (n * sxy - sx * sy) / (n * sxx - sx * sx)
      icpt = (sy - slope * sx) / n
      if (slope > 0.0_dp) then
        d0 = min(max(-icpt / slope, 0.0_dp), h)
        f%amp = slope
        placed = .true.
      end if
    end if
    if (.not. placed) then             ! mid-element, through the last node's value
      d0 = 0.5_dp * h
      f%amp = p(e)**2 / (h - d0)
    end if
    f%root = .true.
    f%inward = inward
    f%send = s(o) + inward * d0
  end function end_fit

  !> int over segment k of (p_h - p*)^2 dS, p_h linear between the nodes,
  !> the weight wn linear too (module header: exact).
  !>   s, p, wn (in) (ns) arc length, p_h and weight at the nodes
  !>   f        (in) p* on the segment
  real(dp) function segment_integral(s, p, wn, k, f) result(v)
    real(dp), intent(in) :: s(:), p(:), wn(:)
    integer, intent(in) :: k
    type(segment_fit_t), intent(in) :: f
    real(dp) :: sa, sb, sm
    sa = s(k)
    sb = s(k + 1)
    v = 0.0_dp
    if (.not. f%root) then
      v = plain_part(sa, sb)
      return
    end if
    ! split at the end: beyond it p* = 0 (plain), before it the square root (substituted)
    sm = min(max(f%send, sa), sb)
    if (f%inward > 0) then
      v = plain_part(sa, sm) + root_part(sm, sb)
    else
      v = root_part(sa, sm) + plain_part(sm, sb)
    end if
  contains
    !> int (p_h - p*)^2 dS on [a, b] by Gauss in s (p* polynomial, or 0 past a root's end)
    real(dp) function plain_part(a, b) result(q)
      real(dp), intent(in) :: a, b
      integer :: i
      real(dp) :: x
      q = 0.0_dp
      if (b <= a) return
      do i = 1, 4
        x = a + (b - a) * gx(i)
        q = q + gw(i) * (b - a) * (ph(x) - star(x))**2 * weight(x)
      end do
    end function plain_part
    !> int (p_h - p*)^2 dS on [a, b] on the root's side, |s - send| = t^2
    real(dp) function root_part(a, b) result(q)
      real(dp), intent(in) :: a, b
      integer :: i
      real(dp) :: ta, tb, t, x
      q = 0.0_dp
      if (b <= a) return
      ta = sqrt(abs(a - f%send))
      tb = sqrt(abs(b - f%send))
      do i = 1, 4
        t = ta + (tb - ta) * gx(i)
        x = f%send + f%inward * t * t
        q = q + gw(i) * abs(tb - ta) * (ph(x) - sqrt(f%amp) * t)**2 * weight(x) * 2 * t
      end do
    end function root_part
    real(dp) function ph(x)
      real(dp), intent(in) :: x
      ph = p(k) + (p(k + 1) - p(k)) * (x - sa) / (sb - sa)
    end function ph
    real(dp) function weight(x)
      real(dp), intent(in) :: x
      weight = wn(k) + (wn(k + 1) - wn(k)) * (x - sa) / (sb - sa)
    end function weight
    real(dp) function star(x)
      real(dp), intent(in) :: x
      real(dp) :: y
      integer :: j
      star = 0.0_dp
      if (f%root) return               ! past the end
      y = (x - f%s0) / f%len
      do j = 3, 0, -1
        star = star * y + f%c(j)
      end do
    end function star
  end function segment_integral

  !> x = a \ b for a small dense system, Gaussian elimination with partial
  !> pivoting; a singular pivot leaves its unknown 0 (a patch of repeated nodes).
  pure subroutine small_solve(a, b, x)
    real(dp), intent(in) :: a(:,:), b(:)
    real(dp), intent(out) :: x(:)
    real(dp) :: m(size(b), size(b) + 1), row(size(b) + 1), scale
    integer :: n, i, j, piv
    n = size(b)
    m(:, 1:n) = a
    m(:, n + 1) = b
    scale = max(maxval(abs(a)), tiny(1.0_dp))
    do i = 1, n
      piv = i - 1 + maxloc(abs(m(i:n, i)), dim=1)
      if (piv /= i) then
        row = m(i, :)
        m(i, :) = m(piv, :)
        m(piv, :) = row
      end if
      if (abs(m(i, i)) <= 1.0e-14_dp * scale) cycle
      do j = i + 1, n
        m(j, i:) = m(j, i:) - m(j, i) / m(i, i) * m(i, i:)
      end do
    end do
    x = 0.0_dp
    do i = n, 1, -1
      if (abs(m(i, i)) <= 1.0e-14_dp * scale) cycle
      x(i) = (m(i, n + 1) - dot_product(m(i, i + 1:n), x(i + 1:n))) / m(i, i)
    end do
  end subroutine small_solve

end module pressure_recovery
