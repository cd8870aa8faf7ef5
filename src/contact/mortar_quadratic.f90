!> mortar_quadratic: the mortar operator pi_h of one contact pair when either side's
!> trace is quadratic (3-node edges of tri6, quad8, quad9 bodies, straight or curved
!> as the mesh places the mid-side node), following P. Hild and P. Laborde,
!> "Quadratic finite element methods for unilateral contact problems", Appl. Numer.
!> Math. 41 (2002) 401-421, with the nodal non-penetration condition (doc/theory.md,
!> "Quadratic traces").  It fills the same mortar_t as mortar_operator, so that the
!> rows B u <= g, the condensation and the LCP are the ones of the linear case.
!> Its four steps below (intersection, quadrature, multipliers, projection) share
!> one pairing of the curved traces; the linear operator (mortar_operator) stays
!> apart, exact with straight segments and the seed paper's own construction.
!>
!> Traces (trace_geometry).  A trace of degree p (1 or 2) is the chain of its nodes
!>    x_1..x_n in order along the boundary, element e holding the nodes p(e-1)+1 .. pe+1
!>    (for p = 2: corner, mid-side node, corner).  On element e, s in [0, 1]:
!>       x(s) = sum_k N_k(s) x_k,   p = 1: N = (1-s, s),
!>       p = 2: N = ((1-s)(1-2s), 4s(1-s), s(2s-1))   (isoparametric: curved edges kept).
!>    phi_i (slave) and chi_j (master) are these shape functions on the traces.
!> 1. Intersection.  Master element f faces slave element e when their chords'
!>    outward normals point against each other, -n_f.n_e > 0.2 (within 78 degrees
!>    of opposite): a curved slave element at a right angle to the master would
!>    otherwise pair with all of it along its normal, a fold in the cover.  The master's end points are
!>    projected onto the slave curve along the slave's normal field: s solves
!>    (y - x(s)).x'(s) = 0 (Newton from the chord's value; linear on a straight e).
!>    On the overlap [lo, hi] of [0, 1] with the projected interval, a slave point
!>    x(s) is paired with the master point y(r(s)) where the line x(s) + tau n(s)
!>    meets element f (Newton in r; linear on a straight f).
!> 2. Quadrature.  Each overlap is integrated with 4-point Gauss-Legendre in s with
!>    the weight |x'(s)|.  On straight edges r(s) is affine, the integrands
!>    phi_i phi_l and phi_i chi_j are polynomials of degree <= 4 and |x'| is
!>    constant: the rule (exact to degree 7) is exact.  On a curved edge |x'(s)|
!>    is the square root of a quadratic and r(s) is not polynomial: the relative
!>    error falls as h^6 (measured in tests/unit/test_mortar_quadratic.f90, the
!>    figures in doc/theory.md, "Quadratic traces").
!> 3. Zone and multipliers.  The zone is the slave elements with a covered part,
!>    zone nodes z = 0..Z (Z = p times the element count).  The multiplier space
!>    M_h is the continuous space of degree p on the zone, of degree p - 1 on its
!>    two end elements (Hild-Laborde's end condition; constants for Z = p):
!>       p = 1: psi_1 = phi_0 + phi_1, psi_k = phi_k, psi_{Z-1} = phi_{Z-1} + phi_Z;
!>       p = 2: psi_1 = phi_0 + phi_1/2, psi_2 = phi_1/2 + phi_2, psi_k = phi_k,
!>              psi_{Z-2} = phi_{Z-2} + phi_{Z-1}/2, psi_{Z-1} = phi_{Z-1}/2 + phi_Z;
!>    dim M_h = Z - 1 = the interior nodes, and M_h holds the constants.
!> 4. Projection, eq. (8) of the linear case carried over: for a master trace phi,
!>       (pi phi)(x_0) = phi(y_0),  (pi phi)(x_Z) = phi(y_Z),
!>       int_cov (phi - pi phi) psi_k = 0,  k = 1..Z-1,
!>    y_0 (y_Z) the master point paired with the start (end) of the zone's cover.
!>    Where the master ends inside a zone-end element (at s = c, more than
!>    tol_sliver from its node), the zone's mesh is the slave's cut there, as in
!>    the linear operator: the end element is the part [c, 1] (or [0, c]) of the
!>    slave element, its zone nodes the points at s = c, (1 + c)/2, 1 (or 0, c/2,
!>    c), on which the slave trace is the element's own quadratic (nothing is
!>    approximated: mortar_operator's zone_node_terms gives them), the zone's
!>    shape functions those of the part, and y_0 the master's end point.  A
!>    shorter uncovered sliver is below what the mesh resolves: the end node
!>    stays, the master's end value extended over it.
!>    D v = C H - E_0 c_0 - E_Z c_Z with D = C G (interior columns), G_ml = int phi_m
!>    phi_l, H_mj = int phi_m chi_j, C the coefficients of psi on phi; D is banded
!>    (p + 1 off-diagonals) and solved by LAPACK dgbsv for all master columns.
!>    pi reproduces the traces of degree p and int pi phi = int_cov phi: the
!>    contact patch test holds to round-off on straight non-matching edges.
!> 5. A closed slave curve that the master covers all round: M_h the periodic
!>    space of degree p, D = G cyclic, solved by bordering (banded dgbsv on the
!>    first Z - p nodes, a p x p Schur complement by dgesv).
!> 6. Rows (contact_set): B_i u = n_i.u1(x_i) - n_i.sum_j P_ij u2(y_j) <= gap0_i at
!>    every zone node i, corners and mid-side nodes (the nodal condition), with
!>    gap0_i = n_i.((P y)_i - x_i) from the curved geometry and n_i the unit normal
!>    of the curve at x_i (the mean of the two elements' at a corner).  A
!>    frictional pair (quadratic_common_normals) pairs the points along the
!>    common normals n_c = w n1 - (1 - w) n2 (mortar_geometry's trace_common_normals),
!>    interpolated over each slave element by its shape functions: the master's
!>    points in 1. and 2. are where the line x(s) + tau n_c(s) meets it, and the
!>    normal rows and the tangential rows T_i (t_i = n_c turned a quarter turn)
!>    take n_c at each zone node.
!> 7. Axisymmetric pairs (x = r): every integral of 2.-4. and the weights carry
!>    2 pi r(s), r(s) the slave point's radius: on a straight edge the
!>    integrands become of degree 5, within the 4-point rule's 7.  A zone end on
!>    the axis is a point inside the contact surface (mortar_operator, 8.): no
!>    end condition, the end element keeps its full degree, the axis is the
!>    node's normal; a quadratic corner hat there weighs nothing,
!>    int (1 - s)(1 - 2s) s ds = 0, and its multiplier is read with the
!>    mid-side node's (contact_set: node_rows).

!> Programming interface
!>   build_mortar_quadratic(xs, ps, sn_out, xm, pm, mn_out, gap_zero, mortar, mcov, err
!>                          [, pairing] [, axisymmetric])
!>         the operator in a mortar_t (cut: where the zone ends inside an element;
!>         degree = ps; inter is left empty) and mcov(j) = int_cov chi_j
!>   quadratic_common_normals(xs, ps, sn_out, xm, pm, mn_out, nc, w)
!>         a frictional pair's pairing directions at the slave trace's nodes
!>   multiplier_terms(ps, z, axis_end, k, m, c, nt)
!>         the multiplier basis function psi_k on the zone nodes (3.), its terms
!>   gauss4   the 4-point Gauss-Legendre rule on [0, 1] of its quadrature (2.)
module mortar_quadratic
  use kinds, only: dp
  use lapack_interfaces, only: dgbsv, dgesv
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, set_error, error_input, error_numerical
  use sorting, only: sort_by_key
  use mortar_geometry, only: tol_overlap, tol_piece, tol_sliver, arc_digits, trace_common_normals
  use trace_geometry, only: trace_point, trace_shape, chord_side, trace_normals, ray_on_element, cross
  use mortar_operator, only: mortar_t, start_mortar, start_periodic, set_initial_gaps
  use axisymmetric_elements, only: radial_weight
  implicit none
  private
  public :: build_mortar_quadratic, quadratic_common_normals, multiplier_terms, gauss4

  real(dp), parameter :: min_facing = 0.2_dp       ! -n_master.n_slave of the chords above which they face

  !> 4-point Gauss-Legendre on [0, 1]: points and weights.
  real(dp), parameter :: gauss4(2, 4) = reshape([ &
    0.5_dp - 0.5_dp * 0.86113631159405257522_dp, 0.5_dp * 0.34785484513745385737_dp, &
    0.5_dp - 0.5_dp * 0.33998104358485626480_dp, 0.5_dp * 0.65214515486254614263_dp, &
    0.5_dp + 0.5_dp * 0.33998104358485626480_dp, 0.5_dp * 0.65214515486254614263_dp, &
    0.5_dp + 0.5_dp * 0.86113631159405257522_dp, 0.5_dp * 0.34785484513745385737_dp], [2, 4])

  !> The two traces of a pair and how their points are paired.
  type :: traces_t
    real(dp), allocatable :: xs(:,:), xm(:,:)  !< (2, ns), (2, nm) trace nodes
    real(dp), allocatable :: sn(:,:), mn(:,:)  !< outward unit chord normals of their elements
    integer :: ps = 1, pm = 1                  !< degrees
    real(dp), allocatable :: pairing(:,:)      !< (2, ns) a frictional pair's common normals; not
                                               !< allocated: pairing along the slave curve's normal
    logical :: axisymmetric = .false.          !< integrals weighted by 2 pi r (module header, 7.)
  end type traces_t

  !> One overlap of a slave element e with a master element f.
  type :: overlap_t
    integer :: e = 0, f = 0
    real(dp) :: lo = 0.0_dp, hi = 0.0_dp      !< slave coordinates of its ends
    real(dp) :: rlo = 0.0_dp, rhi = 0.0_dp    !< master coordinates paired with them
  end type overlap_t

contains

  !> Build the operator; see the module header.
  !>   xs     (in)  (2, ns) slave trace nodes in order;  ps (in) its degree, 1 or 2
  !>   sn_out (in)  (2, (ns-1)/ps) outward unit normal of each slave element's chord
  !>   xm     (in)  (2, nm) master trace nodes;  pm (in) its degree
  !>   mn_out (in)  (2, (nm-1)/pm) outward unit chord normals of the master elements
  !>   gap_zero (in) .true.: gap0 = 0 (the boundaries coincide)
  !>   mortar (out) the operator (fields as mortar_operator's mortar_t; cut(1) > 0 or
  !>                cut(2) < 1 where the zone ends inside its first or last element)
  !>   mcov   (out) (nm) int over the covered zone of each master shape function
  !>   err    (out) error_input for a master that folds or leaves a hole; error_numerical when
  !>                LAPACK finds D singular
  !>   pairing (in, optional) (2, ns) a frictional pair's common normals
  !>                (quadratic_common_normals): points paired and rows along them (6.)
  !>   axisymmetric (in, optional) x is the radius: integrals weighted by 2 pi r (7.)
  subroutine build_mortar_quadratic(xs, ps, sn_out, xm, pm, mn_out, gap_zero, mortar, mcov, err, &
                                    pairing, axisymmetric)
    real(dp), intent(in) :: xs(:,:), sn_out(:,:), xm(:,:), mn_out(:,:)
    integer, intent(in) :: ps, pm
    logical, intent(in) :: gap_zero
    type(mortar_t), intent(out) :: mortar
    real(dp), allocatable, intent(out) :: mcov(:)
    type(error_t), allocatable, intent(out) :: err
    real(dp), intent(in), optional :: pairing(:,:)
    logical, intent(in), optional :: axisymmetric
    type(traces_t) :: t
    type(overlap_t), allocatable :: ov(:)
    integer :: ns, nm, nes, e, k, nov, efirst, elast, i0
    integer, allocatable :: ncover(:)
    logical :: closed
    real(dp) :: lo, hi

    t = traces_t(xs, xm, sn_out, mn_out, ps, pm)
    if (present(pairing)) t%pairing = pairing
    if (present(axisymmetric)) t%axisymmetric = axisymmetric
    ns = size(xs, 2)
    nm = size(xm, 2)
    nes = (ns - 1) / ps
    call start_mortar(mortar, ns, nm)
    mortar%degree = ps
    mortar%axisymmetric = t%axisymmetric
    allocate(mcov(nm), source=0.0_dp)
    closed = all(xs(:, 1) == xs(:, ns))

    ! Arc length and nodal normals of the slave curve (a frictional pair: its common normals).
    mortar%arc(1) = 0.0_dp
    do e = 1, nes
      if (ps == 2) mortar%arc(2 * e) = mortar%arc(2 * e - 1) + curve_length(xs, ps, e, 0.0_dp, 0.5_dp)
      mortar%arc(ps * e + 1) = mortar%arc(ps * (e - 1) + 1) + curve_length(xs, ps, e, 0.0_dp, 1.0_dp)
    end do
    call trace_normals(xs, ps, sn_out, mortar%normal)
    if (allocated(t%pairing)) mortar%normal = t%pairing

    call intersect_traces(t, ov, nov)
    if (nov == 0) return

    ! Coverage per slave element: folds and holes.
    allocate(ncover(nes), source=0)
    do k = 1, nov
      ncover(ov(k)%e) = ncover(ov(k)%e) + 1
      if (k > 1) then
        if (ov(k - 1)%e == ov(k)%e .and. ov(k)%lo < ov(k - 1)%hi - tol_overlap) then
          call set_error(err, 'master boundary covers the slave boundary twice near arc length ' // &
            real_to_str(mortar%arc(ps * (ov(k)%e - 1) + 1), arc_digits) // &
            ' (a master boundary that faces the slave once, without folds, expected)', error_input)
          return
        end if
      end if
    end do
    if (closed .and. all(ncover > 0)) then
      call build_periodic_quadratic(mortar, t, ov(1:nov), err)
      if (allocated(err)) return
    else
      efirst = ov(1)%e
      elast = ov(nov)%e
      do e = efirst, elast
        if (ncover(e) == 0) then
          call set_error(err, 'master boundary leaves a gap opposite the slave boundary at arc length ' // &
            real_to_str(mortar%arc(ps * (e - 1) + 1), arc_digits) // &
            ' (a master that covers the slave contact zone without holes expected)', error_input)
          return
        end if
      end do
      ! a covered piece shorter than tol_piece of a zone-end element is left out
      if (elast > efirst .and. 1.0_dp - ov(1)%lo < tol_piece) then
        ov = pack(ov(1:nov), ov(1:nov)%e /= efirst)
        nov = size(ov)
        efirst = efirst + 1
      end if
      if (elast > efirst .and. maxval(ov(1:nov)%hi, mask=ov(1:nov)%e == elast) < tol_piece) then
        ov = pack(ov(1:nov), ov(1:nov)%e /= elast)
        nov = size(ov)
        elast = elast - 1
      end if
      ! a master that stops inside a zone-end element: the zone's mesh is the
      ! slave's cut there (module header, 4.); a cover short of the end node
      ! by less than tol_sliver reaches it, the master's end value extended
      mortar%cut = [ov(1)%lo, ov(nov)%hi]
      if (mortar%cut(1) <= tol_sliver) mortar%cut(1) = 0.0_dp
      if (mortar%cut(2) >= 1.0_dp - tol_sliver) mortar%cut(2) = 1.0_dp
      ! the rows of a cut element's zone nodes act at points inside it: the
      ! direction field there (the curve's normal, or the interpolated pairing)
      do k = 0, ps
        if (mortar%cut(1) > 0.0_dp .and. k < ps) then
          call zone_part(mortar, efirst, efirst, elast, lo, hi)
          mortar%normal(:, ps * (efirst - 1) + 1 + k) = slave_direction(t, efirst, lo + k * (hi - lo) / ps)
        end if
        if (mortar%cut(2) < 1.0_dp .and. k > 0) then
          call zone_part(mortar, elast, efirst, elast, lo, hi)
          mortar%normal(:, ps * (elast - 1) + 1 + k) = slave_direction(t, elast, lo + k * (hi - lo) / ps)
        end if
      end do
      call build_open_quadratic(mortar, t, ov(1:nov), efirst, elast, err)
      if (allocated(err)) return
    end if

    ! master integrals over the cover (the single-row and resolution checks of contact_set)
    do k = 1, nov
      call add_master_integrals(t, ov(k), mcov)
    end do
    ! weights over the full zone elements
    do e = 1, nes
      i0 = ps * (e - 1) + 1
      if (.not. all(mortar%constrained(i0:i0 + ps))) cycle
      call add_shape_integrals(t, e, mortar%weight(i0:i0 + ps))
    end do
    if (closed .and. mortar%first == 1 .and. mortar%last == ns) then
      mortar%weight(1) = mortar%weight(1) + mortar%weight(ns)
      mortar%weight(ns) = mortar%weight(1)
    end if

    ! initial normal gaps from the curved geometry: gap0_i = n_i.((P y)_i - x_i)
    if (.not. gap_zero) call set_initial_gaps(mortar, xs, xm, mortar%first, mortar%last, 1, nm)
  end subroutine build_mortar_quadratic

  !> The common normals of a frictional pair on quadratic traces (module
  !> header, 6.): the cover of this operator (intersect_traces) tells which
  !> elements face each other, mortar_geometry's trace_common_normals does the
  !> rest, as on polylines.
  !>   xs, ps, sn_out, xm, pm, mn_out (in) the traces, as build_mortar_quadratic
  !>   nc (out) (2, ns) unit common normals; the slave normal where no master faces
  !>   w  (out) the weight of the slave normal
  subroutine quadratic_common_normals(xs, ps, sn_out, xm, pm, mn_out, nc, w)
    real(dp), intent(in) :: xs(:,:), sn_out(:,:), xm(:,:), mn_out(:,:)
    integer, intent(in) :: ps, pm
    real(dp), allocatable, intent(out) :: nc(:,:)
    real(dp), intent(out) :: w
    type(overlap_t), allocatable :: ov(:)
    logical, allocatable :: sface(:), mface(:)
    integer :: nov
    call intersect_traces(traces_t(xs, xm, sn_out, mn_out, ps, pm), ov, nov)
    allocate(sface(size(sn_out, 2)), mface(size(mn_out, 2)), source=.false.)
    sface(ov(1:nov)%e) = .true.
    mface(ov(1:nov)%f) = .true.
    call trace_common_normals(xs, ps, sn_out, sface, xm, pm, mn_out, mface, nc, w)
  end subroutine quadratic_common_normals

  !> The operator on an open zone, slave elements efirst..elast (module header, 3.-4.).
  subroutine build_open_quadratic(mortar, t, ov, efirst, elast, err)
    type(mortar_t), intent(inout) :: mortar
    type(traces_t), intent(in) :: t
    type(overlap_t), intent(in) :: ov(:)
    integer, intent(in) :: efirst, elast
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: g(:,:), h(:,:), c(:,:), ab(:,:), rhs(:,:)
    integer, allocatable :: ipiv(:)
    integer :: z, i0, nz, k, m, l, kl, ldab, info, jlo, jhi, nc, klo, khi, ps, pm
    real(dp) :: nr(3), lo, hi

    ps = t%ps
    pm = t%pm
    i0 = ps * (efirst - 1) + 1                  ! trace index of zone node 0
    z = ps * (elast - efirst + 1)
    mortar%first = i0
    mortar%last = i0 + z
    mortar%constrained(i0:i0 + z) = .true.
    jlo = minval(pm * (ov%f - 1) + 1)
    jhi = maxval(pm * ov%f + 1)
    nc = jhi - jlo + 1
    ! G (z+1, z+1) and H (z+1, nc) over the covered parts with the zone's shape
    ! functions (a cut end element's on its zone part), zone numbering 0..z
    allocate(g(0:z, 0:z), h(0:z, nc), source=0.0_dp)
    do k = 1, size(ov)
      call zone_part(mortar, ov(k)%e, efirst, elast, lo, hi)
      call add_mass(t, ov(k), lo, hi, ps * (ov(k)%e - efirst), jlo, g, h)
    end do
    do m = 0, z
      mortar%covered_weight(i0 + m) = sum(g(m, :))
    end do
    mortar%zone_weight(i0:i0 + z) = mortar%covered_weight(i0:i0 + z)
    ! a zone end on the axis (7.) is a point inside the contact surface: no end
    ! condition, the end element keeps its full degree, the normal is the axis'
    if (t%axisymmetric .and. elast > efirst) then
      mortar%axis_end = [t%xs(1, i0) == 0.0_dp .and. mortar%cut(1) == 0.0_dp, &
                         t%xs(1, i0 + z) == 0.0_dp .and. mortar%cut(2) == 1.0_dp]
      if (mortar%axis_end(1)) mortar%normal(:, i0) = [0.0_dp, sign(1.0_dp, mortar%normal(2, i0))]
      if (mortar%axis_end(2)) mortar%normal(:, i0 + z) = [0.0_dp, sign(1.0_dp, mortar%normal(2, i0 + z))]
      ! a quadratic corner function on the axis has no weight: int (1-s)(1-2s) s ds = 0
      ! (its pressure is read with the mid-side node's, contact_set: node_rows)
      if (ps == 2) then
        if (mortar%axis_end(1)) mortar%zone_weight(i0) = 0.0_dp
        if (mortar%axis_end(2)) mortar%zone_weight(i0 + z) = 0.0_dp
        mortar%covered_weight(i0:i0 + z) = mortar%zone_weight(i0:i0 + z)
      end if
    end if
    ! end rows: the master trace at the points paired with the cover's two ends
    ! (where the zone is cut, the master's end point: exact)
    if (.not. mortar%axis_end(1)) then
      call trace_shape(pm, ov(1)%rlo, nr)
      mortar%P(i0, pm * (ov(1)%f - 1) + 1:pm * ov(1)%f + 1) = nr(1:pm + 1)
    end if
    k = size(ov)
    if (.not. mortar%axis_end(2)) then
      call trace_shape(pm, ov(k)%rhi, nr)
      mortar%P(i0 + z, pm * (ov(k)%f - 1) + 1:pm * ov(k)%f + 1) = &
        mortar%P(i0 + z, pm * (ov(k)%f - 1) + 1:pm * ov(k)%f + 1) + nr(1:pm + 1)
    end if
    ! the unknown nodal values klo..khi: the interior nodes, and a zone end on the axis
    klo = merge(0, 1, mortar%axis_end(1))
    khi = merge(z, z - 1, mortar%axis_end(2))
    nz = khi - klo + 1
    if (nz < 1) return
    call multiplier_coefficients(ps, z, mortar%axis_end, c)
    ! D = C G (the unknowns' columns), right-hand sides C H - E_0 P_0 - E_Z P_Z
    kl = ps + 1
    ldab = 3 * kl + 1
    allocate(ab(ldab, nz), source=0.0_dp)
    allocate(rhs(nz, nc))
    rhs = matmul(c(klo:khi, 0:z), h)
    do k = 1, nz
      do l = max(1, k - kl), min(nz, k + kl)
        ab(2 * kl + 1 + k - l, l) = dot_product(c(klo + k - 1, 0:z), g(0:z, klo + l - 1))
      end do
      if (klo == 1) rhs(k, :) = rhs(k, :) - dot_product(c(klo + k - 1, 0:z), g(0:z, 0)) * mortar%P(i0, jlo:jhi)
      if (khi == z - 1) rhs(k, :) = rhs(k, :) - dot_product(c(klo + k - 1, 0:z), g(0:z, z)) * mortar%P(i0 + z, jlo:jhi)
    end do
    allocate(ipiv(nz))
    call dgbsv(nz, kl, kl, nc, ab, ldab, ipiv, rhs, nz, info)
    if (info /= 0) then
      call set_error(err, 'mortar matrix D of the quadratic contact zone is singular (LAPACK dgbsv info ' // &
        int_to_str(info) // ')', error_numerical)
      return
    end if
    mortar%P(i0 + klo:i0 + khi, jlo:jhi) = rhs
  end subroutine build_open_quadratic

  !> The operator on a closed slave curve covered all round (module header, 5.):
  !> zone nodes 0..Z-1 = trace nodes 1..Z, node Z = node 0.
  subroutine build_periodic_quadratic(mortar, t, ov, err)
    type(mortar_t), intent(inout) :: mortar
    type(traces_t), intent(in) :: t
    type(overlap_t), intent(in) :: ov(:)
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: g(:,:), h(:,:), ab(:,:), rhs(:,:), s(:,:), dab(:,:), dba(:,:)
    integer, allocatable :: ipiv(:)
    integer :: z, na, nb, k, l, kl, ldab, info, jlo, jhi, nc, m, ps, pm

    ps = t%ps
    pm = t%pm
    z = mortar%ns - 1
    call start_periodic(mortar, z / ps, 'element', err)
    if (allocated(err)) return
    jlo = minval(pm * (ov%f - 1) + 1)
    jhi = maxval(pm * ov%f + 1)
    nc = jhi - jlo + 1
    allocate(g(0:z, 0:z), h(0:z, nc), source=0.0_dp)
    do k = 1, size(ov)
      call add_mass(t, ov(k), 0.0_dp, 1.0_dp, ps * (ov(k)%e - 1), jlo, g, h)
    end do
    ! fold node z onto node 0 (periodic)
    g(0, :) = g(0, :) + g(z, :)
    g(:, 0) = g(:, 0) + g(:, z)
    h(0, :) = h(0, :) + h(z, :)
    do m = 0, z - 1
      mortar%covered_weight(m + 1) = sum(g(m, 0:z - 1))
    end do
    mortar%covered_weight(z + 1) = mortar%covered_weight(1)
    mortar%zone_weight = mortar%covered_weight
    ! bordering: unknowns A = 0..z-1-ps (banded, no wrap), B = the last ps nodes
    nb = ps
    na = z - nb
    kl = ps
    ldab = 3 * kl + 1
    allocate(ab(ldab, na), source=0.0_dp)
    do k = 1, na
      do l = max(1, k - kl), min(na, k + kl)
        ab(2 * kl + 1 + k - l, l) = g(k - 1, l - 1)
      end do
    end do
    dab = g(0:na - 1, na:z - 1)                  ! (na, nb)
    dba = g(na:z - 1, 0:na - 1)                  ! (nb, na)
    allocate(rhs(na, nc + nb))
    rhs(:, 1:nc) = h(0:na - 1, :)
    rhs(:, nc + 1:nc + nb) = dab
    allocate(ipiv(max(na, nb)))
    call dgbsv(na, kl, kl, nc + nb, ab, ldab, ipiv, rhs, na, info)
    if (info == 0) then
      s = g(na:z - 1, na:z - 1) - matmul(dba, rhs(:, nc + 1:nc + nb))     ! Schur complement (nb, nb)
      h(na:z - 1, :) = h(na:z - 1, :) - matmul(dba, rhs(:, 1:nc))
      call dgesv(nb, nc, s, nb, ipiv, h(na:z - 1, :), nb, info)
    end if
    if (info /= 0) then
      call set_error(err, 'mortar matrix D of the closed quadratic contact curve is singular (LAPACK info ' // &
        int_to_str(info) // ')', error_numerical)
      return
    end if
    mortar%P(na + 1:z, jlo:jhi) = h(na:z - 1, :)
    mortar%P(1:na, jlo:jhi) = rhs(:, 1:nc) - matmul(rhs(:, nc + 1:nc + nb), h(na:z - 1, :))
    mortar%P(z + 1, :) = mortar%P(1, :)
  end subroutine build_periodic_quadratic

  !> Coefficients C(k, m) of the multiplier basis psi_k = sum_m C(k, m) phi_m,
  !> k = 0..z (the rows of the unknowns are used: 1..z-1, and a zone end on the
  !> axis), m = 0..z (module header, 3.), row by row from multiplier_terms.
  subroutine multiplier_coefficients(ps, z, axis_end, c)
    integer, intent(in) :: ps, z
    logical, intent(in) :: axis_end(2)
    real(dp), allocatable, intent(out) :: c(:,:)
    integer :: k, m(0:z), nt
    real(dp) :: ck(0:z)
    allocate(c(0:z, 0:z), source=0.0_dp)
    do k = 0, z
      call multiplier_terms(ps, z, axis_end, k, m, ck, nt)
      c(k, m(0:nt - 1)) = ck(0:nt - 1)
    end do
  end subroutine multiplier_coefficients

  !> The multiplier basis function psi_k on the zone nodes 0..z (module header,
  !> 3.): psi_k = sum_t c(t) phi_m(t), t < nt, the terms on distinct nodes.
  !> Degree p - 1 on an end element that is an edge of the zone (not on the
  !> axis), the constants on a one-element zone; at most 3 terms, z + 1 on a
  !> one-element zone.
  !>   ps (in) the degree, 1 or 2;  z (in) the last zone node;  axis_end (in) the zone ends on the axis
  !>   k  (in) 0..z;  m, c (out) (0:) nodes and coefficients, at least z + 1 long;  nt (out) the terms
  subroutine multiplier_terms(ps, z, axis_end, k, m, c, nt)
    integer, intent(in) :: ps, z, k
    logical, intent(in) :: axis_end(2)
    integer, intent(out) :: m(0:), nt
    real(dp), intent(out) :: c(0:)
    integer :: j
    m(0) = k
    c(0) = 1.0_dp
    nt = 1
    if (z == ps .and. .not. any(axis_end)) then  ! one element: the constants
      if (k == 1) then
        nt = z + 1
        m(0:z) = [(j, j = 0, z)]
        c(0:z) = 1.0_dp
      end if
    else if (ps == 1) then
      if (.not. axis_end(1) .and. k == 1) call add_term(0, 1.0_dp)
      if (.not. axis_end(2) .and. k == z - 1) call add_term(z, 1.0_dp)
    else                                        ! degree 1 on the end elements
      if (.not. axis_end(1)) then
        if (k == 1) then
          c(0) = 0.5_dp
          call add_term(0, 1.0_dp)
        end if
        if (k == 2) call add_term(1, 0.5_dp)
      end if
      if (.not. axis_end(2)) then
        if (k == z - 1) then
          c(0) = 0.5_dp
          call add_term(z, 1.0_dp)
        end if
        if (k == z - 2) call add_term(z - 1, 0.5_dp)
      end if
    end if
  contains
    subroutine add_term(node, coef)
      integer, intent(in) :: node
      real(dp), intent(in) :: coef
      m(nt) = node
      c(nt) = coef
      nt = nt + 1
    end subroutine add_term
  end subroutine multiplier_terms

  !> The zone's part [lo, hi] of slave element e (zone elements efirst..elast):
  !> [cut(1), 1] on the first, [0, cut(2)] on the last, [0, 1] elsewhere.
  pure subroutine zone_part(mortar, e, efirst, elast, lo, hi)
    type(mortar_t), intent(in) :: mortar
    integer, intent(in) :: e, efirst, elast
    real(dp), intent(out) :: lo, hi
    lo = 0.0_dp
    hi = 1.0_dp
    if (e == efirst) lo = mortar%cut(1)
    if (e == elast) hi = mortar%cut(2)
  end subroutine zone_part

  !> Add the integrals of one overlap to G (slave x slave) and H (slave x
  !> master), with the zone's shape functions of the element's part [lo, hi].
  !>   m0 (in) zone index of the slave element's first node;  jlo (in) master index of H's column 1
  subroutine add_mass(t, o, lo, hi, m0, jlo, g, h)
    type(traces_t), intent(in) :: t
    type(overlap_t), intent(in) :: o
    real(dp), intent(in) :: lo, hi
    integer, intent(in) :: m0, jlo
    real(dp), intent(inout) :: g(0:, 0:), h(0:, :)
    real(dp) :: s, r, w, ns(3), nr(3)
    integer :: q, a, b, j0
    j0 = t%pm * (o%f - 1) + 1 - jlo + 1
    do q = 1, size(gauss4, 2)
      call pair_point(t, o, q, s, r, w)
      call trace_shape(t%ps, (s - lo) / (hi - lo), ns)
      call trace_shape(t%pm, r, nr)
      do a = 1, t%ps + 1
        do b = 1, t%ps + 1
          g(m0 + a - 1, m0 + b - 1) = g(m0 + a - 1, m0 + b - 1) + w * ns(a) * ns(b)
        end do
        do b = 1, t%pm + 1
          h(m0 + a - 1, j0 + b - 1) = h(m0 + a - 1, j0 + b - 1) + w * ns(a) * nr(b)
        end do
      end do
    end do
  end subroutine add_mass

  !> mcov(j) += int over the overlap of chi_j.
  subroutine add_master_integrals(t, o, mcov)
    type(traces_t), intent(in) :: t
    type(overlap_t), intent(in) :: o
    real(dp), intent(inout) :: mcov(:)
    real(dp) :: s, r, w, nr(3)
    integer :: q, j0
    j0 = t%pm * (o%f - 1) + 1
    do q = 1, size(gauss4, 2)
      call pair_point(t, o, q, s, r, w)
      call trace_shape(t%pm, r, nr)
      mcov(j0:j0 + t%pm) = mcov(j0:j0 + t%pm) + w * nr(1:t%pm + 1)
    end do
  end subroutine add_master_integrals

  !> w(0:p) += int over slave element e of its shape functions (ds, or 2 pi r ds).
  subroutine add_shape_integrals(t, e, w)
    type(traces_t), intent(in) :: t
    integer, intent(in) :: e
    real(dp), intent(inout) :: w(:)
    real(dp) :: y(2), dy(2), nn(3), wq
    integer :: q
    do q = 1, size(gauss4, 2)
      call trace_point(t%xs, t%ps, e, gauss4(1, q), y, dy)
      call trace_shape(t%ps, gauss4(1, q), nn)
      wq = gauss4(2, q) * norm2(dy)
      if (t%axisymmetric) wq = radial_weight(wq * y(1))
      w(1:t%ps + 1) = w(1:t%ps + 1) + wq * nn(1:t%ps + 1)
    end do
  end subroutine add_shape_integrals

  !> Gauss point q of an overlap: the slave coordinate s, the paired master
  !> coordinate r (where the line x(s) + tau d(s) meets master element f, d
  !> the slave direction field) and the quadrature weight
  !> w = w_q (hi - lo) |x'(s)|, times 2 pi r(s) when axisymmetric.
  subroutine pair_point(t, o, q, s, r, w)
    type(traces_t), intent(in) :: t
    type(overlap_t), intent(in) :: o
    integer, intent(in) :: q
    real(dp), intent(out) :: s, r, w
    real(dp) :: x(2), dx(2)
    s = o%lo + gauss4(1, q) * (o%hi - o%lo)
    call trace_point(t%xs, t%ps, o%e, s, x, dx)
    r = o%rlo + gauss4(1, q) * (o%rhi - o%rlo)
    call ray_on_element(t%xm, t%pm, o%f, x, slave_direction(t, o%e, s), r)
    w = gauss4(2, q) * (o%hi - o%lo) * norm2(dx)
    if (t%axisymmetric) w = radial_weight(w * x(1))
  end subroutine pair_point

  !> The unit pairing direction at the point s of slave element e: the
  !> curve's outward normal, or for a frictional pair the common normals of
  !> the element's nodes interpolated by its shape functions.
  function slave_direction(t, e, s) result(d)
    type(traces_t), intent(in) :: t
    integer, intent(in) :: e
    real(dp), intent(in) :: s
    real(dp) :: d(2), x(2), dx(2), nn(3)
    integer :: i0
    if (allocated(t%pairing)) then
      i0 = t%ps * (e - 1) + 1
      call trace_shape(t%ps, s, nn)
      d = matmul(t%pairing(:, i0:i0 + t%ps), nn(1:t%ps + 1))
    else
      call trace_point(t%xs, t%ps, e, s, x, dx)
      d = chord_side(t%xs, t%ps, e, t%sn(:, e)) * [dx(2), -dx(1)]
    end if
    d = d / norm2(d)
  end function slave_direction

  !> Intersect the slave and master traces (module header, 1.): the overlaps,
  !> ordered by slave element and increasing lo.
  subroutine intersect_traces(t, ov, nov)
    type(traces_t), intent(in) :: t
    type(overlap_t), allocatable, intent(out) :: ov(:)
    integer, intent(out) :: nov
    type(overlap_t), allocatable :: tmp(:)
    type(overlap_t) :: o
    integer :: nes, nem, e, f, i, n0
    real(dp) :: sa, sb, x(2), dx(2)
    real(dp), allocatable :: sv(:)
    integer, allocatable :: order(:)

    nes = (size(t%xs, 2) - 1) / t%ps
    nem = (size(t%xm, 2) - 1) / t%pm
    allocate(ov(max(16, nes + nem)), sv(nem + 1))
    nov = 0
    do e = 1, nes
      do f = 1, nem + 1                         ! each master corner's slave coordinate on e
        sv(f) = project_on_element(t, e, t%xm(:, t%pm * (f - 1) + 1))
      end do
      n0 = nov
      do f = 1, nem
        if (dot_product(t%mn(:, f), t%sn(:, e)) >= -min_facing) cycle
        sa = sv(f)
        sb = sv(f + 1)
        o%lo = max(0.0_dp, min(sa, sb))
        o%hi = min(1.0_dp, max(sa, sb))
        if (o%hi - o%lo <= tol_overlap) cycle
        o%e = e
        o%f = f
        ! master coordinates at the overlap's ends: along the rays from x(lo), x(hi)
        o%rlo = min(1.0_dp, max(0.0_dp, (o%lo - sa) / (sb - sa)))
        o%rhi = min(1.0_dp, max(0.0_dp, (o%hi - sa) / (sb - sa)))
        call trace_point(t%xs, t%ps, e, o%lo, x, dx)
        call ray_on_element(t%xm, t%pm, f, x, slave_direction(t, e, o%lo), o%rlo)
        call trace_point(t%xs, t%ps, e, o%hi, x, dx)
        call ray_on_element(t%xm, t%pm, f, x, slave_direction(t, e, o%hi), o%rhi)
        o%rlo = min(1.0_dp, max(0.0_dp, o%rlo))
        o%rhi = min(1.0_dp, max(0.0_dp, o%rhi))
        if (nov == size(ov)) then
          allocate(tmp(2 * size(ov)))
          tmp(1:nov) = ov(1:nov)
          call move_alloc(tmp, ov)
        end if
        nov = nov + 1
        ov(nov) = o
      end do
      if (nov - n0 > 1) then                    ! by increasing lo within element e, equal ones in master order
        order = [(i, i = 1, nov - n0)]
        call sort_by_key(order, ov(n0 + 1:nov)%lo)
        ov(n0 + 1:nov) = ov(n0 + order)
      end if
    end do
  end subroutine intersect_traces

  !> The slave coordinate s of element e whose pairing line passes through y:
  !> cross(y - x(s), d(s)) = 0, d the direction field (the normal [x'_2, -x'_1],
  !> i.e. (y - x(s)).x'(s) = 0, or the interpolated common normals); Newton from
  !> the chord's projection (exact in one step on a straight element without
  !> pairing); may lie outside [0, 1], and is the chord's projection where
  !> that is more than an element beyond it.
  real(dp) function project_on_element(t, e, y) result(s)
    type(traces_t), intent(in) :: t
    integer, intent(in) :: e
    real(dp), intent(in) :: y(2)
    real(dp) :: xa(2), xb(2), pt(2), d1(2), d2(2), dir(2), ddir(2), f, df, nn(3), dn(3)
    integer :: it, i0, p
    p = t%ps
    i0 = p * (e - 1) + 1
    xa = t%xs(:, i0)
    xb = t%xs(:, i0 + p)
    s = dot_product(y - xa, xb - xa) / dot_product(xb - xa, xb - xa)
    if (p == 1 .and. .not. allocated(t%pairing)) return
    ! a point far beyond the element stays there: Newton on the extrapolated
    ! curve (and pairing field) could find a spurious root inside it
    if (s < -1.0_dp .or. s > 2.0_dp) return
    do it = 1, 20
      call trace_point(t%xs, p, e, s, pt, d1)
      d2 = 0.0_dp
      if (p == 2) d2 = 4.0_dp * (t%xs(:, i0) - 2.0_dp * t%xs(:, i0 + 1) + t%xs(:, i0 + 2))
      if (allocated(t%pairing)) then
        call trace_shape(p, s, nn, dn)
        dir = matmul(t%pairing(:, i0:i0 + p), nn(1:p + 1))
        ddir = matmul(t%pairing(:, i0:i0 + p), dn(1:p + 1))
      else
        dir = [d1(2), -d1(1)]
        ddir = [d2(2), -d2(1)]
      end if
      f = cross(y - pt, dir)
      df = -cross(d1, dir) + cross(y - pt, ddir)
      if (df == 0.0_dp) exit
      s = s - f / df
      if (abs(f / df) < 1.0e-15_dp) exit
    end do
  end function project_on_element

  !> Length of element e of a trace between s = a and s = b (4-point Gauss).
  real(dp) function curve_length(x, p, e, a, b) result(l)
    real(dp), intent(in) :: x(:,:), a, b
    integer, intent(in) :: p, e
    real(dp) :: y(2), dy(2)
    integer :: q
    l = 0.0_dp
    do q = 1, size(gauss4, 2)
      call trace_point(x, p, e, a + gauss4(1, q) * (b - a), y, dy)
      l = l + gauss4(2, q) * (b - a) * norm2(dy)
    end do
  end function curve_length

end module mortar_quadratic
