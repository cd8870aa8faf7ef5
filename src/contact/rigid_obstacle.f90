!> rigid_obstacle: a rigid obstacle's exact shape, its signed distance, and
!> the constraint rows of a deformable slave boundary against it.
!>
!> A RIGID is a body with three dofs, the motion of its reference point x_r:
!> U = (u_x, u_y, theta), and zero stiffness.  Its points move by
!>     U(x) = (u_x - theta (y - y_r), u_y + theta (x - x_r))
!> (small rotations).  The obstacle is known exactly: its signed distance
!> d(x) (> 0 outside the solid) and the outward unit normal n_r(x) = grad d
!> at the nearest point of its boundary; no polygon stands in for it.
!>   line      the segment x0-x1, its solid the strip behind it (the side away
!>             from the slave); beyond its ends the distance is to the end point
!>   circle    d = |x - c| - r (solid inside), r - |x - c| (solid=outside: a hole)
!>   polyline  open polygon, solid on the side away from the slave; at a vertex
!>             the side is that of the angle-weighted pseudo-normal (the sum of
!>             the two segments' normals), beyond its ends as for a line
!>
!> The mortar side is the deformable slave (the paper's side 1) with its
!> multiplier space M_h^1 as for two bodies: on a trace of degree p (P1
!> polylines, or the 3-node edges of quadratic elements, curved as the mesh
!> places their mid-side nodes: trace_geometry) the space of mortar_quadratic
!> (3.), continuous of degree p, of degree p - 1 on the two end elements of an
!> open slave boundary, periodic on a closed one; the whole slave boundary is
!> the zone (the obstacle has no end the slave could pass).  Row i, at slave
!> trace node x_i (corners and mid-side nodes: the nodal condition) with the
!> direction n_i = -n_r(x_i) (the slave's outward normal as the exact shape
!> makes it):
!>     B_i u = n_i . u1(x_i) - n_i . U(x_i) <= g_i,   g_i = (pi_h d)(x_i),
!> pi_h the mortar projection onto the slave trace space (eq. (8)): the end
!> values pointwise, the interior ones by D v = C (int phi d) - E_0 d(a1) - E_n d(a2)
!> (D = C G, G the trace's mass matrix, C the multiplier coefficients).
!> The rigid motion is linear in x, so of degree p along the slave trace, and
!> pi_h U = U at the nodes: its part of the row is n_i . U(x_i), three entries
!> on the rigid's dofs,
!>     -[n_i,x,  n_i,y,  n_i . (-(y_i - y_r), x_i - x_r)].
!> A frictional row takes t_i = (-n_i,y, n_i,x) instead of n_i.
!> Axisymmetric (x = r): every integral (G, int phi d, the weights int phi_i)
!> is over the surface of revolution, ds -> 2 pi r ds, as for two bodies
!> (mortar_operator, 8.); an end of the slave trace on the axis is a point
!> inside the contact surface: no end condition, its normal the axis, and a
!> quadratic corner hat there weighs nothing (its pressure read with its
!> mid-side neighbour's, contact_set: node_rows).  Of the three motions only
!> u_y (along the axis) is axisymmetric: the scene holds u_x and theta.
!>
!> Programming interface
!>   type(rigid_shape_t)                         the shape, its reference point and dofs
!>   signed_distance(sh, x, d, n)                d(x) and n_r(x)
!>   orient_shape(sh, xs, ns_out)                line/polyline: the solid on the side the slave faces
!>   build_rigid_mortar(xs, ps, ns_out, sh, axisymmetric, mortar, err)
!>                                               the mortar_t of a slave trace against sh
!>   rigid_terms(sh, x, v)                       the motion of x along v per unit ux, uy, theta
module rigid_obstacle
  use kinds, only: dp
  use lapack_interfaces, only: dgbsv, dgesv
  use strings, only: int_to_str
  use errors, only: error_t, set_error, error_numerical
  use mortar_operator, only: mortar_t
  use mortar_quadratic, only: multiplier_terms
  use trace_geometry, only: trace_point, trace_shape, trace_normals
  use axisymmetric_elements, only: radial_weight
  implicit none
  private
  public :: rigid_shape_t, shape_line, shape_circle, shape_polyline
  public :: signed_distance, orient_shape, build_rigid_mortar, rigid_terms

  integer, parameter :: shape_line = 1, shape_circle = 2, shape_polyline = 3
  ! two distances within this ratio are a tie (signed_distance)
  real(dp), parameter :: tie_ratio = 1.0e-12_dp

  type :: rigid_shape_t
    character(len=:), allocatable :: name     !< the RIGID's name
    integer :: kind = 0                       !< shape_line, shape_circle or shape_polyline
    real(dp), allocatable :: pt(:,:)          !< (2, np) line: its ends; polyline: its points
    real(dp) :: centre(2) = 0, radius = 0     !< circle
    logical :: outside = .false.              !< circle: solid outside (a hole)
    real(dp) :: side = 1                      !< line/polyline: +1 solid on the left of pt(:,k) -> pt(:,k+1), -1 right
    real(dp) :: ref(2) = 0                    !< reference point x_r
    real(dp) :: length = 1                    !< size of the shape (rotation scale in messages and tests)
    integer :: dof0 = 0                       !< its dofs dof0+1, +2, +3: u_x, u_y, theta
  end type rigid_shape_t

  ! Gauss-Legendre, 4 points on [0, 1], for the integrals of d on slave segments
  real(dp), parameter :: gx(4) = [0.0694318442029737_dp, 0.3300094782075719_dp, 0.6699905217924281_dp, &
                                  0.9305681557970263_dp]
  real(dp), parameter :: gw(4) = [0.1739274225687269_dp, 0.3260725774312731_dp, 0.3260725774312731_dp, &
                                  0.1739274225687269_dp]
  integer, parameter :: nsub = 4             ! sub-intervals per segment (d has kinks at corners)

contains

  !> Signed distance of x to the obstacle and the outward normal there.
  !>   sh   (in)  the shape;  x (in) (2) a point
  !>   d    (out) > 0 outside the solid, < 0 inside
  !>   n    (out) (2) unit outward normal of the solid at the point nearest x (grad d)
  !>   hint (in, optional) (2) unit direction for n when x lies on a corner of
  !>        the shape (grad d is not defined there): minus the slave's normal
  pure subroutine signed_distance(sh, x, d, n, hint)
    type(rigid_shape_t), intent(in) :: sh
    real(dp), intent(in) :: x(2)
    real(dp), intent(out) :: d, n(2)
    real(dp), intent(in), optional :: hint(2)
    real(dp) :: r(2), rn, best, t, p(2), e(2), ne(2), pn(2), len2, s
    integer :: k, kbest, np
    real(dp) :: tbest
    if (sh%kind == shape_circle) then
      r = x - sh%centre
      rn = norm2(r)
      if (rn > 0.0_dp) then
        n = r / rn
      else
        n = [0.0_dp, 1.0_dp]
      end if
      d = rn - sh%radius
      if (sh%outside) then
        d = -d
        n = -n
      end if
      return
    end if
    np = size(sh%pt, 2)
    best = huge(1.0_dp)
    kbest = 1
    tbest = 0.0_dp
    do k = 1, np - 1                          ! nearest point over the segments
      e = sh%pt(:, k + 1) - sh%pt(:, k)
      len2 = dot_product(e, e)
      t = min(1.0_dp, max(0.0_dp, dot_product(x - sh%pt(:, k), e) / len2))
      p = sh%pt(:, k) + t * e
      ! a later segment wins only when nearer by more than round-off: a point
      ! on the bisector of two segments (above a V's apex) is a tie, and its
      ! row's normal must not depend on the rounding of the deck's units
      if (norm2(x - p) < best * (1.0_dp - tie_ratio)) then
        best = norm2(x - p)
        kbest = k
        tbest = t
      end if
    end do
    k = kbest
    if (tbest == 1.0_dp .and. k < np - 1) then
      k = k + 1                              ! an inner vertex: as the start of the next segment
      tbest = 0.0_dp
    end if
    e = sh%pt(:, k + 1) - sh%pt(:, k)
    ne = -sh%side * [-e(2), e(1)] / norm2(e)  ! outward normal of segment k
    p = sh%pt(:, k) + tbest * e
    if (tbest > 0.0_dp .and. tbest < 1.0_dp) then
      d = dot_product(x - p, ne)
      n = ne
      return
    end if
    ! a vertex: the side from the pseudo-normal (inner vertex) or the end segment's normal
    pn = ne
    if (tbest == 0.0_dp .and. k > 1) then
      e = sh%pt(:, k) - sh%pt(:, k - 1)
      pn = ne - sh%side * [-e(2), e(1)] / norm2(e)
    end if
    r = x - p
    s = merge(1.0_dp, -1.0_dp, dot_product(r, pn) >= 0.0_dp)
    d = s * norm2(r)
    if (norm2(r) > 1.0e-12_dp * sh%length) then
      n = s * r / norm2(r)
    else if (present(hint)) then              ! on the corner: the slave's own direction
      d = 0.0_dp
      n = hint
    else
      n = pn / norm2(pn)
    end if
  end subroutine signed_distance

  !> A line or polyline has its solid on the side away from the slave body,
  !> the side its outward normals point to: side is set from the vote of the
  !> slave segments, each the cosine between its outward normal and the outward
  !> normal that side = +1 gives the obstacle there, weighted by its length
  !> over (its distance to the obstacle + its length), so that the segments
  !> facing the obstacle decide (a slave lying on the line, gap=zero, too).
  !> A circle is left as it is.
  !>   sh (inout) the shape;  xs (in) (2, ns) slave nodes;  ns_out (in) (2, ns-1) their outward normals
  pure subroutine orient_shape(sh, xs, ns_out)
    type(rigid_shape_t), intent(inout) :: sh
    real(dp), intent(in) :: xs(:,:), ns_out(:,:)
    real(dp) :: d, n(2), total, l, xm(2)
    integer :: e
    if (sh%kind == shape_circle) return
    sh%side = 1.0_dp
    total = 0.0_dp
    do e = 1, size(xs, 2) - 1
      xm = 0.5_dp * (xs(:, e) + xs(:, e + 1))
      l = norm2(xs(:, e + 1) - xs(:, e))
      call signed_distance(sh, xm, d, n)
      ! the slave faces the obstacle when its normal opposes the obstacle's
      total = total - dot_product(ns_out(:, e), n) * l / (abs(d) + l)
    end do
    if (total < 0.0_dp) sh%side = -1.0_dp
  end subroutine orient_shape

  !> The motion of point x along v per unit of each rigid dof:
  !> [v_x, v_y, v . (-(y - y_r), x - x_r)].
  pure function rigid_terms(sh, x, v) result(c)
    type(rigid_shape_t), intent(in) :: sh
    real(dp), intent(in) :: x(2), v(2)
    real(dp) :: c(3)
    c = [v(1), v(2), -v(1) * (x(2) - sh%ref(2)) + v(2) * (x(1) - sh%ref(1))]
  end function rigid_terms

  !> The mortar operator of a slave trace against a rigid obstacle (module
  !> header): the whole trace is the zone, the normals n_i = -n_r(x_i), the
  !> gaps pi_h d, the weights int phi_i (2 pi r) ds.  P is not allocated (no
  !> master mesh).
  !>   xs     (in)  (2, ns) slave trace nodes (trace_geometry: corners, and the
  !>                mid-side nodes between them when ps = 2); closed when
  !>                xs(:, ns) = xs(:, 1) and it has at least 3 elements
  !>   ps     (in)  the trace's degree, 1 or 2
  !>   ns_out (in)  (2, (ns-1)/ps) outward unit chord normals of the slave elements
  !>   sh     (in)  the obstacle (oriented)
  !>   axisymmetric (in) x is the radius: integrals weighted by 2 pi r
  !>   mortar (out) first = 1, last = ns, normal, gap0, weights, arc, degree, axis_end
  !>   err    (out) allocated when the banded solve fails (error_numerical)
  subroutine build_rigid_mortar(xs, ps, ns_out, sh, axisymmetric, mortar, err)
    real(dp), intent(in) :: xs(:,:), ns_out(:,:)
    integer, intent(in) :: ps
    type(rigid_shape_t), intent(in) :: sh
    logical, intent(in) :: axisymmetric
    type(mortar_t), intent(out) :: mortar
    type(error_t), allocatable, intent(out) :: err
    integer :: ns, nel, i, info, z
    real(dp) :: d, n(2)
    real(dp), allocatable :: gb(:,:), bd(:), dnode(:), hint(:,:)
    logical :: closed

    ns = size(xs, 2)
    nel = (ns - 1) / ps
    z = ns - 1
    closed = nel >= 3 .and. all(xs(:, 1) == xs(:, ns))
    mortar%ns = ns
    mortar%nm = 0
    mortar%first = 1
    mortar%last = ns
    mortar%degree = ps
    mortar%axisymmetric = axisymmetric
    allocate(mortar%normal(2, ns), mortar%gap0(ns), mortar%covered_weight(ns), mortar%zone_weight(ns), &
             mortar%constrained(ns), dnode(0:z))
    mortar%constrained = .true.
    call trace_integrals(xs, ps, sh, axisymmetric, gb, bd, mortar%weight, mortar%arc)
    call trace_normals(xs, ps, ns_out, hint)
    do i = 1, ns
      ! the slave's nodal normal: the direction at a node that lies on a corner
      call signed_distance(sh, xs(:, i), d, n, -hint(:, i))
      dnode(i - 1) = d
      mortar%normal(:, i) = -n
    end do
    if (closed) then                          ! node ns is node 1
      mortar%weight(1) = mortar%weight(1) + mortar%weight(ns)
      mortar%weight(ns) = mortar%weight(1)
      call project_periodic(ps, gb, bd, mortar%gap0, info)
    else
      ! a trace end on the axis is a point inside the contact surface
      ! (mortar_operator, 8.): no end condition there, its normal the axis'
      mortar%axis_end = axisymmetric .and. nel > 1 .and. [xs(1, 1) == 0.0_dp, xs(1, ns) == 0.0_dp]
      do i = 1, 2
        if (.not. mortar%axis_end(i)) cycle
        associate(nrm => mortar%normal(:, merge(1, ns, i == 1)))
          nrm = [0.0_dp, sign(1.0_dp, nrm(2))]
        end associate
      end do
      call project_open(ps, mortar%axis_end, gb, bd, dnode, mortar%gap0, info)
    end if
    mortar%covered_weight = mortar%weight
    mortar%zone_weight = mortar%weight
    if (info /= 0) then
      call set_error(err, 'mortar matrix D of the slave boundary against RIGID ' // sh%name // ' is singular ' // &
                     '(LAPACK info ' // int_to_str(info) // ')', error_numerical)
      return
    end if
  end subroutine build_rigid_mortar

  !> The integrals over the slave trace (composite 4-point Gauss, nsub parts an
  !> element: d has kinks at the obstacle's corners), each with the radial
  !> weight 2 pi r when axisymmetric:
  !>   G_kl = int phi_k phi_l  (band: gb(o, k) = G(k, k+o), |o| <= ps, nodes 0..ns-1),
  !>   b_k = int phi_k d,  weight_k = int phi_k,  arc the arc length from node 1.
  subroutine trace_integrals(xs, ps, sh, axisymmetric, gb, bd, weight, arc)
    real(dp), intent(in) :: xs(:,:)
    integer, intent(in) :: ps
    type(rigid_shape_t), intent(in) :: sh
    logical, intent(in) :: axisymmetric
    real(dp), allocatable, intent(out) :: gb(:,:), bd(:), weight(:), arc(:)
    integer :: ns, e, j, q, a, b, i0
    real(dp) :: s, x(2), dx(2), d, n(2), w, wl, nn(3), len
    ns = size(xs, 2)
    allocate(gb(-ps:ps, 0:ns - 1), bd(0:ns - 1), weight(ns), arc(ns), source=0.0_dp)
    do e = 1, (ns - 1) / ps
      i0 = ps * (e - 1)                         ! zone index of the element's first node
      len = 0.0_dp
      do j = 1, nsub
        do q = 1, 4
          s = (real(j - 1, dp) + gx(q)) / nsub
          call trace_point(xs, ps, e, s, x, dx)
          call trace_shape(ps, s, nn)
          call signed_distance(sh, x, d, n)
          wl = gw(q) / nsub * norm2(dx)
          w = wl
          if (axisymmetric) w = radial_weight(wl * x(1))
          do a = 0, ps
            do b = 0, ps
              gb(b - a, i0 + a) = gb(b - a, i0 + a) + w * nn(a + 1) * nn(b + 1)
            end do
            bd(i0 + a) = bd(i0 + a) + w * nn(a + 1) * d
            weight(i0 + a + 1) = weight(i0 + a + 1) + w * nn(a + 1)
          end do
          len = len + wl
        end do
        if (ps == 2 .and. 2 * j == nsub) arc(i0 + 2) = arc(i0 + 1) + len
      end do
      arc(i0 + ps + 1) = arc(i0 + 1) + len
    end do
  end subroutine trace_integrals

  !> pi_h d on an open slave trace (eq. (8); mortar_quadratic, 3.-4., for the
  !> multiplier space): v_0 = d(x_0), v_z = d(x_z) (not at an end on the axis),
  !>     sum_l D_kl v_l = C_k b - C_k G_0 d(x_0) - C_k G_z d(x_z),  D = C G,
  !> k over the unknowns (the interior nodes, and an end on the axis), C_k the
  !> coefficients of psi_k (multiplier_terms); D is banded (ps + 1 off-diagonals).
  !>   ps (in) the degree;  axis_end (in) the ends on the axis
  !>   gb, bd (in) G's band and b (trace_integrals);  dnode (in) (0:z) d at the nodes
  !>   v (out) (z+1) pi_h d at the nodes;  info (out) dgbsv's
  subroutine project_open(ps, axis_end, gb, bd, dnode, v, info)
    integer, intent(in) :: ps
    logical, intent(in) :: axis_end(2)
    real(dp), intent(in) :: gb(-ps:, 0:), bd(0:), dnode(0:)
    real(dp), intent(out) :: v(:)
    integer, intent(out) :: info
    integer :: z, klo, khi, nz, k, l, t, kl, ldab, nt
    integer, allocatable :: m(:), ipiv(:)
    real(dp), allocatable :: c(:), ab(:,:), rhs(:,:)
    z = size(dnode) - 1
    v = dnode
    info = 0
    klo = merge(0, 1, axis_end(1))
    khi = merge(z, z - 1, axis_end(2))
    nz = khi - klo + 1
    if (nz < 1) return
    kl = ps + 1
    ldab = 3 * kl + 1
    allocate(m(0:z), ipiv(nz))
    allocate(c(0:z), ab(ldab, nz), rhs(nz, 1), source=0.0_dp)
    do k = klo, khi
      call multiplier_terms(ps, z, axis_end, k, m, c, nt)
      do t = 0, nt - 1
        ! row m(t) of G: its band, the known end values on the right
        do l = max(0, m(t) - ps), min(z, m(t) + ps)
          if (l < klo .or. l > khi) then
            rhs(k - klo + 1, 1) = rhs(k - klo + 1, 1) - c(t) * gb(l - m(t), m(t)) * dnode(l)
          else
            ab(2 * kl + 1 + k - l, l - klo + 1) = ab(2 * kl + 1 + k - l, l - klo + 1) + c(t) * gb(l - m(t), m(t))
          end if
        end do
        rhs(k - klo + 1, 1) = rhs(k - klo + 1, 1) + c(t) * bd(m(t))
      end do
    end do
    call dgbsv(nz, kl, kl, 1, ab, ldab, ipiv, rhs, nz, info)
    if (info == 0) v(klo + 1:khi + 1) = rhs(:, 1)
  end subroutine project_open

  !> pi_h d on a closed slave trace (node z = node 0): G v = b with G the
  !> cyclic mass matrix, by bordering: banded dgbsv on the first z - ps nodes,
  !> a ps x ps Schur complement by dgesv for the last ps.
  !>   ps (in) the degree;  gb, bd (in) G's band and b on the open nodes 0..z
  !>   v (out) (z+1) pi_h d at the nodes, v(z+1) = v(1);  info (out) LAPACK's
  subroutine project_periodic(ps, gb, bd, v, info)
    integer, intent(in) :: ps
    real(dp), intent(in) :: gb(-ps:, 0:), bd(0:)
    real(dp), intent(out) :: v(:)
    integer, intent(out) :: info
    integer :: z, na, i, o, k, l, ldab
    integer, allocatable :: ipiv(:)
    real(dp), allocatable :: ab(:,:), rhs(:,:), dba(:,:), s(:,:), y(:,:), bc(:)
    z = size(bd) - 1
    na = z - ps
    ldab = 3 * ps + 1
    allocate(bc(0:z - 1))
    bc = bd(0:z - 1)
    bc(0) = bc(0) + bd(z)
    allocate(ab(ldab, na), rhs(na, 1 + ps), dba(ps, na), s(ps, ps), source=0.0_dp)
    allocate(ipiv(max(na, ps)))
    ! G of the closed trace, node z folded onto node 0, in four blocks: the
    ! first na nodes (banded), the last ps nodes, and the two couplings
    do i = 0, z
      do o = max(-ps, -i), min(ps, z - i)
        k = modulo(i, z)
        l = modulo(i + o, z)
        if (k < na .and. l < na) then
          ab(2 * ps + 1 + k - l, l + 1) = ab(2 * ps + 1 + k - l, l + 1) + gb(o, i)
        else if (k < na) then
          rhs(k + 1, 1 + l - na + 1) = rhs(k + 1, 1 + l - na + 1) + gb(o, i)
        else if (l < na) then
          dba(k - na + 1, l + 1) = dba(k - na + 1, l + 1) + gb(o, i)
        else
          s(k - na + 1, l - na + 1) = s(k - na + 1, l - na + 1) + gb(o, i)
        end if
      end do
    end do
    rhs(:, 1) = bc(0:na - 1)
    call dgbsv(na, ps, ps, 1 + ps, ab, ldab, ipiv, rhs, na, info)
    if (info /= 0) return
    s = s - matmul(dba, rhs(:, 2:))                  ! Schur complement (ps, ps)
    y = reshape(bc(na:z - 1) - matmul(dba, rhs(:, 1)), [ps, 1])
    call dgesv(ps, 1, s, ps, ipiv, y, ps, info)
    if (info /= 0) return
    v(na + 1:z) = y(:, 1)
    v(1:na) = rhs(:, 1) - matmul(rhs(:, 2:), y(:, 1))
    v(z + 1) = v(1)
  end subroutine project_periodic

end module rigid_obstacle
