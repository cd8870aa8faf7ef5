!> mortar_geometry: the geometry of a contact pair's two boundary polylines that the
!> mortar operator is built on (mortar_operator): their checks, the intersection of
!> the two 1D meshes, nodal normals, and the common normal of a frictional pair, on
!> polylines and on quadratic traces alike (trace_geometry).
!>
!> Segment intersection ("1D segment quadrature", `intersect_segments`).  For each slave segment
!>    [x_a, x_b] (length L, unit tangent t, outward unit normal n) every master segment
!>    that faces it (n_master . n < 0) is projected onto the slave segment's line along
!>    n: s(y) = (y - x_a).t / L.  The overlap of the projected interval with [0, 1], when
!>    longer than 1e-10, is a sub-segment; on it the slave hats (affine in s) and the
!>    master hats (affine in the master coordinate r, itself affine in s) are both
!>    linear, so 2-point Gauss on each sub-segment integrates every product
!>    phi_i chi_j and phi_i phi_l exactly.  A master part counts whatever its distance
!>    along n (initial gaps may be large); a slave part covered twice (a master that
!>    folds back in front of the slave) is rejected.
!> Common normal (`trace_common_normals`, doc/theory.md "Friction on curved surfaces"):
!>    n_c = normalize(w n1 - (1 - w) n2), w = k2 / (k1 + k2) from the two traces'
!>    mean curvatures over the parts that face: the direction along which two curved
!>    surfaces approach, which pairs the points that meet.  One algorithm for either
!>    trace degree: the master's normals are interpolated by its shape functions; the
!>    facing parts are the cover of the pair's operator, given by the caller.
!>
!> Programming interface
!>   type(intersection_t)  the list of sub-segments of the two 1D meshes
!>   intersect_segments(xs, ns_out, xm, nm_out, inter [, pairing])
!>                         the sub-segment list (valid polylines assumed)
!>   check_polyline(x, nrm, side, err)   a polyline and its segment normals usable
!>   common_normals(xs, ns_out, xm, nm_out, nc, w)   a frictional pair's pairing directions
!>                         on two polylines
!>   trace_common_normals(xs, ps, sn_out, sface, xm, pm, mn_out, mface, nc, w)
!>                         the same on traces of degree ps and pm, their facing elements given
!>   mean_curvature(x, nrm, seg)         mean curvature of the marked segments of a polyline (convex > 0)
!>   pairing_weight(k1, k2)              the slave normal's weight in the common normal
!>   tol_overlap, tol_piece, tol_sliver  the tolerances of the cover, relative to a slave
!>                         segment (element): shared by the linear and quadratic operators
!>   arc_digits            significant digits of an arc length in the operators' messages
module mortar_geometry
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: error_t, set_error, error_input
  use sorting, only: sort_by_key
  use trace_geometry, only: trace_shape, chord_side, trace_normals, ray_hit, cross
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: intersection_t, intersect_segments, check_polyline, common_normals, trace_common_normals
  public :: mean_curvature, pairing_weight
  public :: tol_overlap, tol_piece, tol_sliver, arc_digits

  !> Sub-segments of the intersection of the slave and master 1D meshes, ordered by
  !> slave segment and, within one, by increasing s.
  type :: intersection_t
    integer :: nsub = 0                       !< number of sub-segments
    integer, allocatable :: slave_seg(:)      !< (nsub) slave segment e (nodes e, e+1)
    integer, allocatable :: master_seg(:)     !< (nsub) master segment f (nodes f, f+1)
    real(dp), allocatable :: s(:,:)           !< (2, nsub) slave coordinates of the ends, 0 <= s(1) < s(2) <= 1
    real(dp), allocatable :: r(:,:)           !< (2, nsub) master coordinates at the same ends (y = (1-r) y_f + r y_f+1)
  end type intersection_t

  real(dp), parameter :: tol_unit = 1.0e-8_dp      ! |n| = 1 and n.t = 0 up to this
  real(dp), parameter :: tol_length = 1.0e-12_dp   ! zero length, relative to the polyline's extent
  real(dp), parameter :: tol_overlap = 1.0e-10_dp  ! shortest sub-segment / double cover, relative to L
  ! The zone's ends (doc/theory.md, "Zone ends"), in both operators (mortar_operator,
  ! mortar_quadratic), relative to the zone-end slave segment or element:
  ! a covered piece shorter than tol_piece is left out of the zone, since the rows
  ! at its two ends would be nearly the same constraint;
  real(dp), parameter :: tol_piece = 1.0e-3_dp
  ! a master that stops short of the end node by less than tol_sliver reaches it:
  ! such a sliver is below anything the mesh resolves, most often the sag of two
  ! polygons that approximate one curve; a longer uncovered piece is an end of
  ! the master inside the element, its end value extended over the piece.
  real(dp), parameter :: tol_sliver = 2.0e-2_dp
  ! An arc length in a message (real_to_str) points at a place on the slave
  ! boundary: 6 digits tell one segment from the next on a boundary of 10^4 of them.
  integer, parameter :: arc_digits = 6

contains

  !> The common normals of a frictional pair on two polylines: the cover of
  !> the linear operator (intersect_segments) tells which segments face each
  !> other, trace_common_normals does the rest.
  !>   xs, ns_out, xm, nm_out (in) the polylines and segment normals, as build_mortar
  !>   nc (out) (2, ns) unit common normals; the slave nodal normal where no master faces
  !>   w  (out) the weight of the slave normal
  subroutine common_normals(xs, ns_out, xm, nm_out, nc, w)
    real(dp), intent(in) :: xs(:,:), ns_out(:,:), xm(:,:), nm_out(:,:)
    real(dp), allocatable, intent(out) :: nc(:,:)
    real(dp), intent(out) :: w
    type(intersection_t) :: inter
    logical, allocatable :: sface(:), mface(:)
    call intersect_segments(xs, ns_out, xm, nm_out, inter)
    allocate(sface(size(ns_out, 2)), mface(size(nm_out, 2)), source=.false.)
    sface(inter%slave_seg(1:inter%nsub)) = .true.
    mface(inter%master_seg(1:inter%nsub)) = .true.
    call trace_common_normals(xs, 1, ns_out, sface, xm, 1, nm_out, mface, nc, w)
  end subroutine common_normals

  !> The common normal of a frictional pair at each slave node, on traces of
  !> either degree (doc/theory.md, "Friction on curved surfaces"): the direction
  !> along which the two surfaces approach, which pairs the points that meet and
  !> is the normal of the slip's tangent plane.  Near the first contact of two
  !> surfaces of curvatures k1 (slave) and k2 (master), their normals at a
  !> distance x are tilted by k1 x and -k2 x from it, so
  !>    n_c = normalize(w n1 - (1 - w) n2),   w = pairing_weight(k1, k2),
  !> n1 the slave nodal normal, n2 the master's nodal normals interpolated by
  !> its shape functions at the point the line x_i + tau n_c meets (re-cast a
  !> few times: each pass moves it closer to the point the common normal
  !> meets), k1, k2 the mean curvatures of the elements that face the other
  !> trace (trace_curvature).  The facing elements are the cover of the pair's
  !> operator, which the caller computes (common_normals for two polylines,
  !> mortar_quadratic's quadratic_common_normals otherwise).
  !>   xs (in) (2, ns) slave trace nodes;  ps (in) its degree, 1 or 2
  !>   sn_out (in) (2, (ns-1)/ps) outward unit normals of the slave elements' chords
  !>   sface (in) ((ns-1)/ps) the slave elements the master faces
  !>   xm, pm, mn_out, mface (in) the same for the master trace
  !>   nc (out) (2, ns) unit common normals; the slave nodal normal where no master faces
  !>   w  (out) the weight of the slave normal (1/2 where no master faces)
  subroutine trace_common_normals(xs, ps, sn_out, sface, xm, pm, mn_out, mface, nc, w)
    real(dp), intent(in) :: xs(:,:), sn_out(:,:), xm(:,:), mn_out(:,:)
    integer, intent(in) :: ps, pm
    logical, intent(in) :: sface(:), mface(:)
    real(dp), allocatable, intent(out) :: nc(:,:)
    real(dp), intent(out) :: w
    real(dp), allocatable :: n1(:,:), n2(:,:)
    real(dp) :: k1, k2, y(2), r, m(2), nn(3)
    integer :: i, e, f, k, iter

    call pairing_normals(xs, ps, sn_out, n1)
    call pairing_normals(xm, pm, mn_out, n2)
    nc = n1
    w = 0.5_dp
    if (.not. any(sface)) return
    k1 = trace_curvature(xs, ps, sn_out, sface)
    k2 = trace_curvature(xm, pm, mn_out, mface)
    w = pairing_weight(k1, k2)
    do i = 1, size(xs, 2)
      e = (i - 1) / ps + 1                        ! the elements that hold node i: e, and e - 1 at a corner
      if (.not. (sface(min(e, size(sface))) .or. (mod(i - 1, ps) == 0 .and. sface(max(e - 1, 1))))) cycle
      do iter = 1, 4
        call ray_hit(xm, pm, mn_out, xs(:, i), nc(:, i), f, r)
        if (f == 0) exit
        ! the master's nodal normals interpolated: continuous across its corners
        ! (a curve's own normal kinks there), a node's own on a node
        if (r < 1.0e-8_dp) r = 0.0_dp
        if (r > 1.0_dp - 1.0e-8_dp) r = 1.0_dp
        call trace_shape(pm, r, nn)
        m = nn(1) * n2(:, pm * (f - 1) + 1)
        do k = 2, pm + 1
          m = m + nn(k) * n2(:, pm * (f - 1) + k)
        end do
        m = m / norm2(m)
        y = w * n1(:, i) - (1.0_dp - w) * m
        if (.not. norm2(y) > 0.0_dp) exit
        nc(:, i) = y / norm2(y)
      end do
    end do
  end subroutine trace_common_normals

  !> The nodal normals a trace's common normals start from: on a polyline its
  !> nodal_normals, from the segment normals as given (trace_normals would
  !> recompute them from the coordinates, equal but for round-off), on a
  !> quadratic trace the curve's (trace_normals).
  subroutine pairing_normals(x, p, nout, n)
    real(dp), intent(in) :: x(:,:), nout(:,:)
    integer, intent(in) :: p
    real(dp), allocatable, intent(out) :: n(:,:)
    if (p == 1) then
      call nodal_normals(x, nout, n)
    else
      call trace_normals(x, p, nout, n)
    end if
  end subroutine pairing_normals

  !> Mean curvature (convex > 0) of the marked elements of a trace of degree p:
  !> mean_curvature on the polygon of its nodes (mid-side nodes included), the
  !> segment normals of a polyline as given, those of a quadratic trace's
  !> polygon on the side of its chord normals.
  !>   x (in) (2, np) nodes;  p (in) degree;  nout (in) (2, (np-1)/p) outward chord normals
  !>   marked (in) ((np-1)/p) the elements to average over
  real(dp) function trace_curvature(x, p, nout, marked) result(k)
    real(dp), intent(in) :: x(:,:), nout(:,:)
    integer, intent(in) :: p
    logical, intent(in) :: marked(:)
    real(dp), allocatable :: nseg(:,:)
    logical, allocatable :: seg(:)
    real(dp) :: c(2), sigma
    integer :: np, e, j, i
    if (p == 1) then
      k = mean_curvature(x, nout, marked)
      return
    end if
    np = size(x, 2)
    allocate(nseg(2, np - 1), seg(np - 1))
    do e = 1, (np - 1) / p
      sigma = chord_side(x, p, e, nout(:, e))
      do j = 1, p
        i = p * (e - 1) + j
        c = x(:, i + 1) - x(:, i)
        nseg(:, i) = sigma * [c(2), -c(1)] / norm2(c)
        seg(i) = marked(e)
      end do
    end do
    k = mean_curvature(x, nseg, seg)
  end function trace_curvature

  !> The weight w of the slave normal in the common normal w n1 - (1 - w) n2
  !> (common_normals) from the mean curvatures k1 (slave) and k2 (master),
  !> convex > 0: k2 / (k1 + k2), 1/2 when they agree to tol_curv (a polygon's
  !> curvature is no better; mirror images then pair exactly), when k1 + k2 is
  !> not positive or both are flat; 1 or 0 when one side is flat to tol_curv
  !> of the other.  Shared by the linear and quadratic operators.
  pure real(dp) function pairing_weight(k1, k2) result(w)
    real(dp), intent(in) :: k1, k2
    real(dp), parameter :: tol_curv = 5.0e-2_dp
    if (abs(k1 - k2) <= tol_curv * 0.5_dp * (abs(k1) + abs(k2)) .or. .not. k1 + k2 > 0.0_dp) then
      w = 0.5_dp
    else if (abs(k1) <= tol_curv * abs(k2)) then
      w = 1.0_dp
    else if (abs(k2) <= tol_curv * abs(k1)) then
      w = 0.0_dp
    else
      w = min(1.0_dp, max(0.0_dp, k2 / (k1 + k2)))
    end if
  end function pairing_weight

  !> Unit nodal normals of a polyline: the normalized sum of the two segment
  !> normals at a node, the segment's own at an end (a closed curve has none).
  subroutine nodal_normals(x, nrm, n)
    real(dp), intent(in) :: x(:,:), nrm(:,:)
    real(dp), allocatable, intent(out) :: n(:,:)
    real(dp) :: y(2)
    integer :: np, i
    np = size(x, 2)
    allocate(n(2, np))
    n(:, 1) = nrm(:, 1)
    n(:, np) = nrm(:, np - 1)
    do i = 2, np - 1
      y = nrm(:, i - 1) + nrm(:, i)
      n(:, i) = y / norm2(y)
    end do
    if (all(x(:, 1) == x(:, np))) then
      y = nrm(:, np - 1) + nrm(:, 1)
      n(:, 1) = y / norm2(y)
      n(:, np) = n(:, 1)
    end if
  end subroutine nodal_normals

  !> Mean curvature of the segments of a polyline marked in seg (convex > 0):
  !> the turning of the outward normal along the tangent, summed over
  !> consecutive marked segments, over their half lengths.
  real(dp) function mean_curvature(x, nrm, seg) result(k)
    real(dp), intent(in) :: x(:,:), nrm(:,:)
    logical, intent(in) :: seg(:)
    real(dp) :: turn, length, ta(2), tb(2)
    integer :: e
    turn = 0.0_dp
    length = 0.0_dp
    do e = 1, size(seg) - 1
      if (.not. (seg(e) .and. seg(e + 1))) cycle
      ta = x(:, e + 1) - x(:, e)
      tb = x(:, e + 2) - x(:, e + 1)
      turn = turn + dot_product(nrm(:, e + 1) - nrm(:, e), ta / norm2(ta) + tb / norm2(tb)) * 0.5_dp
      length = length + 0.5_dp * (norm2(ta) + norm2(tb))
    end do
    k = 0.0_dp
    if (length > 0.0_dp) k = turn / length
  end function mean_curvature

  !> Intersect the slave and master 1D meshes: for each slave segment, the master
  !> segments facing it projected along its normal onto its line (module header, 1.).
  !> The polylines are assumed valid (as checked by build_mortar).
  !>   xs     (in)  (2, ns) slave nodes;  ns_out (in) (2, ns-1) slave segment normals
  !>   xm     (in)  (2, nm) master nodes; nm_out (in) (2, nm-1) master segment normals
  !>   inter  (out) the sub-segments, ordered by slave segment and increasing s
  !>   pairing (in, optional) (2, ns) unit nodal pairing directions: the master is
  !>                  projected onto segment e along their sum, not along its normal
  subroutine intersect_segments(xs, ns_out, xm, nm_out, inter, pairing)
    real(dp), intent(in) :: xs(:,:), ns_out(:,:), xm(:,:), nm_out(:,:)
    type(intersection_t), intent(out) :: inter
    real(dp), intent(in), optional :: pairing(:,:)
    integer :: nss, nms, e, f, nc, i, j, cap
    real(dp) :: xa(2), t(2), d(2), length, sa, sb, lo, hi
    real(dp), allocatable :: clo(:), chi(:), rlo(:), rhi(:), sm(:)
    integer, allocatable :: cf(:), order(:)

    nss = size(xs, 2) - 1
    nms = size(xm, 2) - 1
    allocate(clo(nms), chi(nms), rlo(nms), rhi(nms), cf(nms), order(nms), sm(nms + 1))
    cap = max(16, nss + nms)
    allocate(inter%slave_seg(cap), inter%master_seg(cap), inter%s(2, cap), inter%r(2, cap))
    inter%nsub = 0
    do e = 1, nss
      xa = xs(:, e)
      t = xs(:, e + 1) - xa
      length = norm2(t)
      t = t / length
      nc = 0
      if (present(pairing)) then           ! projected along the pairing direction d
        d = pairing(:, e) + pairing(:, e + 1)
        do f = 1, nms + 1
          sm(f) = cross(xm(:, f) - xa, d) / cross(xs(:, e + 1) - xa, d)
        end do
      else
        do f = 1, nms + 1                  ! each master node's coordinate along segment e, once
          sm(f) = dot_product(xm(:, f) - xa, t) / length
        end do
      end if
      do f = 1, nms
        if (dot_product(nm_out(:, f), ns_out(:, e)) >= 0.0_dp) cycle   ! not facing
        sa = sm(f)
        sb = sm(f + 1)
        lo = max(0.0_dp, min(sa, sb))
        hi = min(1.0_dp, max(sa, sb))
        if (hi - lo <= tol_overlap) cycle
        nc = nc + 1
        clo(nc) = lo
        chi(nc) = hi
        rlo(nc) = min(1.0_dp, max(0.0_dp, (lo - sa) / (sb - sa)))   ! y = y_f + r (y_f+1 - y_f)
        rhi(nc) = min(1.0_dp, max(0.0_dp, (hi - sa) / (sb - sa)))
        cf(nc) = f
      end do
      ! by increasing lo; equal ones in master order
      order(1:nc) = [(i, i = 1, nc)]
      call sort_by_key(order(1:nc), clo(1:nc))
      if (inter%nsub + nc > cap) then
        cap = max(2 * cap, inter%nsub + nc)
        call grow_intersection(inter, cap)
      end if
      do j = 1, nc
        i = order(j)
        inter%nsub = inter%nsub + 1
        inter%slave_seg(inter%nsub) = e
        inter%master_seg(inter%nsub) = cf(i)
        inter%s(:, inter%nsub) = [clo(i), chi(i)]
        inter%r(:, inter%nsub) = [rlo(i), rhi(i)]
      end do
    end do
  end subroutine intersect_segments

  !> Check one polyline and its segment normals; err (error_input) on the first defect.
  !>   x     (in)  (2, np) nodes
  !>   nrm   (in)  (2, np-1) outward unit segment normals
  !>   side  (in)  'slave' or 'master', for messages
  !>   err   (out) allocated when the polyline is not usable
  subroutine check_polyline(x, nrm, side, err)
    real(dp), intent(in) :: x(:,:), nrm(:,:)
    character(len=*), intent(in) :: side
    type(error_t), allocatable, intent(out) :: err
    integer :: np, k
    real(dp) :: scale, length, t(2), orient, c

    np = size(x, 2)
    if (size(x, 1) /= 2 .or. size(nrm, 1) /= 2) then
      call set_error(err, side // ' boundary coordinates or normals are not 2D (arrays (2, n) expected)', error_input)
      return
    end if
    if (np < 2) then
      call set_error(err, side // ' boundary has ' // int_to_str(np) // &
        ' node(s) (at least 2 nodes, one segment, expected)', error_input)
      return
    end if
    if (size(nrm, 2) /= np - 1) then
      call set_error(err, side // ' boundary has ' // int_to_str(size(nrm, 2)) // ' segment normals for ' // &
        int_to_str(np) // ' nodes (one normal per segment, ' // int_to_str(np - 1) // ', expected)', error_input)
      return
    end if
    if (.not. (all(ieee_is_finite(x)) .and. all(ieee_is_finite(nrm)))) then
      call set_error(err, side // ' boundary has non-finite coordinates or normals (finite numbers expected)', error_input)
      return
    end if
    scale = max(maxval(x(1, :)) - minval(x(1, :)), maxval(x(2, :)) - minval(x(2, :)))
    orient = 0.0_dp
    do k = 1, np - 1
      t = x(:, k + 1) - x(:, k)
      length = norm2(t)
      if (length <= tol_length * scale) then
        call set_error(err, 'zero-length segment on the ' // side // ' boundary at node ' // int_to_str(k) // &
          ' (distinct consecutive nodes expected)', error_input)
        return
      end if
      t = t / length
      if (abs(norm2(nrm(:, k)) - 1.0_dp) > tol_unit) then
        call set_error(err, 'normal of ' // side // ' segment ' // int_to_str(k) // &
          ' is not a unit vector (outward unit normals expected)', error_input)
        return
      end if
      if (abs(dot_product(nrm(:, k), t)) > tol_unit) then
        call set_error(err, 'normal of ' // side // ' segment ' // int_to_str(k) // &
          ' is not perpendicular to the segment (outward unit normals expected)', error_input)
        return
      end if
      c = cross(t, nrm(:, k))                              ! +1 or -1: the side of the normal
      if (k == 1) then
        orient = c
      else if (c * orient < 0.0_dp) then
        call set_error(err, 'normals of the ' // side // ' boundary change side at segment ' // int_to_str(k) // &
          ' (outward normals, all on the body''s side, expected)', error_input)
        return
      end if
      if (k > 1) then
        if (dot_product(nrm(:, k - 1), nrm(:, k)) <= -1.0_dp + tol_unit) then
          call set_error(err, side // ' boundary turns back on itself at node ' // int_to_str(k) // &
            ' (a boundary without folds expected)', error_input)
          return
        end if
      end if
    end do
  end subroutine check_polyline

  !> Enlarge the arrays of inter to capacity cap, keeping the first nsub entries.
  subroutine grow_intersection(inter, cap)
    type(intersection_t), intent(inout) :: inter
    integer, intent(in) :: cap
    integer, allocatable :: ia(:)
    real(dp), allocatable :: ra(:,:)
    integer :: n
    n = inter%nsub
    allocate(ia(cap)); ia(1:n) = inter%slave_seg(1:n); call move_alloc(ia, inter%slave_seg)
    allocate(ia(cap)); ia(1:n) = inter%master_seg(1:n); call move_alloc(ia, inter%master_seg)
    allocate(ra(2, cap)); ra(:, 1:n) = inter%s(:, 1:n); call move_alloc(ra, inter%s)
    allocate(ra(2, cap)); ra(:, 1:n) = inter%r(:, 1:n); call move_alloc(ra, inter%r)
  end subroutine grow_intersection

end module mortar_geometry
