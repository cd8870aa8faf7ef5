!> mortar_operator: the discrete contact constraint K_h of one contact pair, built on
!> the geometry of two boundary polylines by the mortar method of F. Ben Belgacem,
!> P. Hild and P. Laborde, "Approximation of the unilateral contact problem by the
!> mortar finite element method" (C. R. Acad. Sci. Paris).
!>
!> Setting.  The slave (non-mortar) side is the paper's side 1: its boundary polyline
!> x_1..x_ns carries the P1 hats phi_i and the Lagrange multipliers.  The master
!> (mortar) side 2 is the polyline y_1..y_nm with hats chi_j.  The normal traces of
!> V_h^l, eq. (7), on the contact zone are the continuous piecewise linear functions
!> W_h^l on these 1D meshes.  The discrete convex is
!>     K_h = { v_h : v_h^1.n^1 + pi_h^1 (v_h^2.n^2) <= 0 on Gamma_c }        (K_h, eq. (10))
!> and this module builds the matrix P of pi_h^1 restricted to the master traces.
!>
!> 1. Segment intersection ("1D segment quadrature", module mortar_geometry): the
!>    sub-segments on which every slave hat and master hat is linear, so that 2-point
!>    Gauss integrates each product exactly.
!> 2. Effective contact zone Gamma_c.  The slave segments with a positive covered length
!>    form the zone, slave nodes first..last, renumbered x_0 = a1, ..., x_n = a2
!>    (n = last - first segments).  An uncovered slave segment inside the zone (a hole)
!>    is an input error; no coverage at all gives first = last = 0 (no contact).
!>    Where the master ends inside a slave segment (its end projects to the point
!>    (1 - c) x_0 + c x_1), the zone's mesh is the slave mesh cut there (cut(1) = c,
!>    cut(2) likewise at the other end): items 3 to 5 hold on it, the cut node's trace
!>    being the slave's linear interpolation (zone_node_terms).  A cover that stops
!>    short of the end node by less than tol_sliver of the segment is stretched to it;
!>    a covered piece shorter than tol_piece is left out (doc/theory.md, Zone ends;
!>    the two tolerances are mortar_geometry's, shared with mortar_quadratic).
!> 3. Multiplier space M_h^1 (continuous P1, constant on the two end segments):
!>       psi_1 = phi_0 + phi_1,  psi_k = phi_k (2 <= k <= n-2),  psi_{n-1} = phi_{n-1} + phi_n;
!>    for n = 2, psi_1 = phi_0 + phi_1 + phi_2 = 1; for n = 1 there is no multiplier
!>    beyond the two end conditions.  M_h^1 contains the constants.
!> 4. Projection pi_h^1, eq. (8): for a master trace phi = sum_j c_j chi_j,
!>       (pi phi)(a_i) = phi(a_i), i = 1, 2,
!>       integral_{Gamma_c} (phi - pi phi) psi_k = 0, k = 1..n-1.
!>    With v the interior nodal values of pi phi:
!>       D v = M c - E_0 (pi phi)(a1) - E_n (pi phi)(a2),
!>       D_kl = int psi_k phi_l (k, l = 1..n-1),  M_kj = int psi_k chi_j,
!>       E_0k = int psi_k phi_0,  E_nk = int psi_k phi_n,
!>    all integrals over the covered part of Gamma_c only (the sub-segments), so that
!>    pi 1 = 1 and int (pi phi) = int phi hold exactly even where the master covers only
!>    part of an end segment.  D is tridiagonal, symmetric positive definite (no holes);
!>    it is solved by LAPACK dgtsv for all master columns, 128 at a time:
!>       P(interior, :) = D^-1 (M - E_0 P(first, :) - E_n P(last, :)).
!>    End values: phi(a_i) is the master trace at the master point hit by the line
!>    through a_i along the slave nodal normal (the facing master segment nearest along
!>    that line).  When that line misses the master (the master stops short of a_i)
!>    the master trace is extended by a constant: the value at the master point that
!>    bounds the covered part of the end segment, i.e. the master's end point.
!> 5. Initial normal gap (gap=geometry): with the slave nodal normal n_i used for both
!>    sides (the usual small-deformation choice; n^2 = -n^1 on a flat interface),
!>       gap0_i = n_i . ( sum_j P(i,j) y_j - x_i ),  i = first..last;
!>    gap=zero is the paper's setting (coinciding boundaries), gap0 = 0.
!>    Constraint row of slave node i (the caller assembles it on the displacements):
!>       B_i u = n_i . u^1(x_i) - n_i . sum_j P(i,j) u^2(y_j) <= gap0_i.
!> 6. A closed slave curve that the master covers all round (build_periodic): no zone
!>    ends, M_h^1 the periodic P1 space, D cyclic, solved by bordering.
!> 7. A frictional pair passes its common normals (mortar_geometry: common_normals) as
!>    `pairing`: the projection onto the slave segments and the rows go along them.
!>
!> 8. Axisymmetric pairs (axisymmetric=.true., x = r): every integral above is
!>    over the surface of revolution, ds -> 2 pi r ds, r the slave point's
!>    radius, which is linear in the slave coordinate s.  D, M, E and the
!>    weights then integrate polynomials of one degree more (3 on P1 traces):
!>    segment_rule picks the Gauss-Legendre rule exact for it, so pi 1 = 1 and
!>    P' zone_weight = master weights hold to round-off (the patch test).
!>    A zone end on the axis (r = 0) is a point inside the contact surface,
!>    not its edge: there the multiplier space keeps the end node's own hat
!>    (psi_0 = phi_0, no end condition (pi phi)(a1) = phi(a1)), pi phi's value
!>    there is one more unknown of D v = M c - E_n c(a2), and the node's
!>    normal is the axis direction (axis_end).
!>
!> Programming interface
!>   type(mortar_t)        the operator of one pair (fields commented below)
!>   build_mortar(xs, ns_out, xm, nm_out, gap_zero, mortar, err [, pairing] [, axisymmetric])
!>                         check the polylines, intersect, build pi_h^1, gaps, weights;
!>                         err (error_input) for geometric input problems, (error_numerical) when
!>                         the LAPACK solve fails
!>   segment_rule(xa, xb, s1, s2, degree, axisymmetric, s, w, nq)
!>                         Gauss-Legendre points and weights on the part [s1, s2] of the
!>                         straight segment xa-xb, exact for polynomials of the given
!>                         degree in s times the radial weight 2 pi r(s) when axisymmetric
!>   zone_node_terms(mo, i, node, coef, nt), zone_point(mo, xs, i)
!>                         the slave nodes (and weights) and the point of zone node i
module mortar_operator
  use kinds, only: dp
  use lapack_interfaces, only: dgtsv
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, set_error, error_input, error_numerical
  use mortar_geometry, only: intersection_t, intersect_segments, check_polyline, &
                             tol_overlap, tol_piece, tol_sliver, arc_digits
  use trace_geometry, only: ray_hit
  use axisymmetric_elements, only: radial_weight
  implicit none
  private
  public :: mortar_t, build_mortar, start_mortar, start_periodic, set_initial_gaps, zone_node_terms, zone_point, &
            segment_rule

  !> The mortar operator of one contact pair.
  type :: mortar_t
    integer :: ns = 0                         !< slave polyline nodes
    integer :: nm = 0                         !< master polyline nodes
    integer :: first = 0, last = 0            !< effective zone: slave nodes first..last; 0/0 when none
    real(dp), allocatable :: normal(:,:)      !< (2, ns) unit outward slave nodal normals
    real(dp), allocatable :: P(:,:)           !< (ns, nm) pi_h^1: (pi phi)(x_i) = sum_j P(i,j) c_j; zero rows off the zone
    real(dp), allocatable :: gap0(:)          !< (ns) initial normal gap n_i.((P y)_i - x_i); 0 for gap=zero or off the zone
    real(dp), allocatable :: weight(:)        !< (ns) w_i = int phi_i over the zone (full segments first..last)
    real(dp), allocatable :: covered_weight(:) !< (ns) int phi_i over the covered part only
    real(dp), allocatable :: zone_weight(:)   !< (ns) int of the zone's hat i (the slave mesh cut at the zone's
                                              !< ends, 4.): the row weights, P' zone_weight = master weights
    real(dp) :: cut(2) = [0.0_dp, 1.0_dp]     !< slave coordinates of the zone's ends on segments first and
                                              !< last-1: cut(1) > 0 or cut(2) < 1 where the zone ends inside
                                              !< a slave segment (the master stops there)
    real(dp), allocatable :: arc(:)           !< (ns) arc length along the slave polyline from node 1
    logical, allocatable :: constrained(:)    !< (ns) true for first..last
    integer :: degree = 1                     !< degree of the slave trace: 1, or 2 (mortar_quadratic), whose
                                              !< cut end elements have their zone nodes at s = cut + k (hi - lo) / 2
    logical :: axisymmetric = .false.         !< integrals weighted by 2 pi r (module header, 8.)
    logical :: axis_end(2) = .false.          !< the zone's first / last node is on the axis (8.)
    type(intersection_t) :: inter             !< the sub-segments used for the integrals
  end type mortar_t

contains

  !> Size an operator for ns slave and nm master nodes, every field zero and no
  !> node constrained: the start of both builders (linear and quadratic traces).
  !>   mortar (inout) the operator; its arrays (re)allocated
  !>   ns, nm (in)    slave and master polyline nodes
  subroutine start_mortar(mortar, ns, nm)
    type(mortar_t), intent(inout) :: mortar
    integer, intent(in) :: ns, nm
    mortar%ns = ns
    mortar%nm = nm
    allocate(mortar%normal(2, ns), mortar%P(ns, nm), mortar%gap0(ns), mortar%weight(ns), mortar%arc(ns))
    allocate(mortar%covered_weight(ns), mortar%zone_weight(ns), mortar%constrained(ns))
    mortar%P = 0.0_dp
    mortar%gap0 = 0.0_dp
    mortar%weight = 0.0_dp
    mortar%covered_weight = 0.0_dp
    mortar%zone_weight = 0.0_dp
    mortar%constrained = .false.
  end subroutine start_mortar

  !> The start of both periodic builders (a closed slave curve covered all
  !> round): every node constrained, the zone the whole curve.
  !>   mortar (inout) the operator from start_mortar; out: first, last, constrained
  !>   nelem  (in)    the curve's slave elements, at least 3 (fewer: err)
  !>   what   (in)    the elements' name in the message: 'segment' or 'element'
  !>   err    (out)   error_input for fewer than 3 elements
  subroutine start_periodic(mortar, nelem, what, err)
    type(mortar_t), intent(inout) :: mortar
    integer, intent(in) :: nelem
    character(len=*), intent(in) :: what
    type(error_t), allocatable, intent(out) :: err
    if (nelem < 3) then
      call set_error(err, 'closed slave boundary has ' // int_to_str(nelem) // ' ' // what // &
        '(s) (at least 3 expected on a closed contact curve)', error_input)
      return
    end if
    mortar%first = 1
    mortar%last = mortar%ns
    mortar%constrained = .true.
  end subroutine start_periodic

  !> Initial normal gaps (gap=geometry, module header, 5.) of both builders:
  !>     gap0_i = n_i . ( sum_j P(i,j) y_j - x_i ),  i = i1..i2,
  !> x_i the point of zone node i (zone_point).
  !>   mortar   (inout) in: P, normal, the zone; out: gap0(i1:i2)
  !>   xs, xm   (in)    (2, ns) slave and (2, nm) master trace nodes
  !>   i1, i2   (in)    the rows, within the zone
  !>   jlo, jhi (in)    the master columns that can be nonzero in those rows
  subroutine set_initial_gaps(mortar, xs, xm, i1, i2, jlo, jhi)
    type(mortar_t), intent(inout) :: mortar
    real(dp), intent(in) :: xs(:,:), xm(:,:)
    integer, intent(in) :: i1, i2, jlo, jhi
    real(dp), allocatable :: py(:,:)
    integer :: i
    allocate(py(i1:i2, 2))
    py = matmul(mortar%P(i1:i2, jlo:jhi), transpose(xm(:, jlo:jhi)))   ! (P y)_i, componentwise
    do i = i1, i2
      mortar%gap0(i) = dot_product(mortar%normal(:, i), py(i, :) - zone_point(mortar, xs, i))
    end do
  end subroutine set_initial_gaps

  !> Build the mortar operator pi_h^1 (eq. (8)) of one contact pair, its effective
  !> zone, nodal normals, weights and initial gaps; see the module header.
  !>   xs       (in)  (2, ns) slave polyline nodes in order along the boundary, ns >= 2
  !>   ns_out   (in)  (2, ns-1) outward unit normal of each slave segment (from the slave body)
  !>   xm       (in)  (2, nm) master polyline nodes in order, nm >= 2
  !>   nm_out   (in)  (2, nm-1) outward unit normal of each master segment (from the master body)
  !>   gap_zero (in)  .true.: the boundaries coincide (the paper's setting), gap0 = 0
  !>   mortar   (out) the operator; contents unspecified when err is returned
  !>   err      (out) allocated on failure: error_input for bad geometry (sizes, zero-length
  !>                  segments, normals, holes or folds in the master cover), 1 when the
  !>                  tridiagonal solve fails
  !>   pairing  (in, optional) (2, ns) the common normals of a frictional pair (7.)
  !>   axisymmetric (in, optional) x is the radius: integrals over the surface of
  !>                  revolution (8.); default .false.
  subroutine build_mortar(xs, ns_out, xm, nm_out, gap_zero, mortar, err, pairing, axisymmetric)
    real(dp), intent(in) :: xs(:,:), ns_out(:,:), xm(:,:), nm_out(:,:)
    logical, intent(in) :: gap_zero
    type(mortar_t), intent(out) :: mortar
    type(error_t), allocatable, intent(out) :: err
    real(dp), intent(in), optional :: pairing(:,:)
    logical, intent(in), optional :: axisymmetric
    integer :: ns, nm, i, e, k, first, last, f, jlo, jhi, info
    integer, allocatable :: ncover(:)
    logical :: ext(2)
    real(dp) :: r, y(2)
    real(dp), allocatable :: seglen(:)

    call check_polyline(xs, ns_out, 'slave', err)
    if (allocated(err)) return
    call check_polyline(xm, nm_out, 'master', err)
    if (allocated(err)) return

    ns = size(xs, 2)
    nm = size(xm, 2)
    if (present(axisymmetric)) mortar%axisymmetric = axisymmetric
    call start_mortar(mortar, ns, nm)

    ! Arc length and nodal normals (normalized sum of the adjacent segment normals).
    allocate(seglen(ns - 1))
    mortar%arc(1) = 0.0_dp
    do e = 1, ns - 1
      seglen(e) = norm2(xs(:, e + 1) - xs(:, e))
      mortar%arc(e + 1) = mortar%arc(e) + seglen(e)
    end do
    mortar%normal(:, 1) = ns_out(:, 1)
    mortar%normal(:, ns) = ns_out(:, ns - 1)
    do i = 2, ns - 1
      y = ns_out(:, i - 1) + ns_out(:, i)
      mortar%normal(:, i) = y / norm2(y)
    end do
    if (all(xs(:, 1) == xs(:, ns)) .and. .not. present(pairing)) then   ! a closed curve: its first node is its last
      y = ns_out(:, ns - 1) + ns_out(:, 1)
      mortar%normal(:, 1) = y / norm2(y)
      mortar%normal(:, ns) = mortar%normal(:, 1)
    end if

    if (present(pairing)) mortar%normal = pairing
    call intersect_segments(xs, ns_out, xm, nm_out, mortar%inter, pairing)
    if (mortar%inter%nsub == 0) return

    ! Coverage per slave segment; double cover (folds) and holes.
    allocate(ncover(ns - 1), source=0)
    do k = 1, mortar%inter%nsub
      e = mortar%inter%slave_seg(k)
      ncover(e) = ncover(e) + 1
      if (k > 1) then
        if (mortar%inter%slave_seg(k - 1) == e .and. &
            mortar%inter%s(1, k) < mortar%inter%s(2, k - 1) - tol_overlap) then
          call set_error(err, 'master boundary covers the slave boundary twice between arc length ' // &
            real_to_str(mortar%arc(e) + mortar%inter%s(1, k) * seglen(e), arc_digits) // ' and ' // &
            real_to_str(mortar%arc(e) + min(mortar%inter%s(2, k - 1), mortar%inter%s(2, k)) * seglen(e), arc_digits) // &
            ' (a master boundary that faces the slave once, without folds, expected)', error_input)
          return
        end if
      end if
    end do
    ! A closed slave curve covered all round: the periodic zone (module header, 6.).
    if (all(xs(:, 1) == xs(:, ns)) .and. all(ncover > 0)) then
      call build_periodic(mortar, xs, xm, seglen, gap_zero, err)
      return
    end if
    first = mortar%inter%slave_seg(1)
    last = mortar%inter%slave_seg(mortar%inter%nsub) + 1
    e = first
    do while (e < last)
      if (ncover(e) == 0) then
        k = e
        do while (ncover(k + 1) == 0)
          k = k + 1
        end do
        call set_error(err, 'master boundary leaves a gap opposite the slave boundary between arc length ' // &
          real_to_str(mortar%arc(e), arc_digits) // ' and ' // real_to_str(mortar%arc(k + 1), arc_digits) // &
          ' (a master that covers the slave contact zone without holes expected)', error_input)
        return
      end if
      e = e + 1
    end do
    ! A zone end inside a slave segment (the master stops there): a piece
    ! shorter than tol_piece of its segment is left out of the zone, the rows
    ! at its two ends would be nearly the same constraint (module header, 2.).
    if (last - first > 1) then
      if (1.0_dp - mortar%inter%s(1, 1) < tol_piece) then
        call drop_pieces(mortar%inter, first)
        first = first + 1
      end if
    end if
    if (last - first > 1) then
      if (maxval(mortar%inter%s(2, 1:mortar%inter%nsub), &
                 mask=mortar%inter%slave_seg(1:mortar%inter%nsub) == last - 1) < tol_piece) then
        call drop_pieces(mortar%inter, last - 1)
        last = last - 1
      end if
    end if
    mortar%first = first
    mortar%last = last
    mortar%constrained(first:last) = .true.
    ! A master that stops short of a zone end node by less than tol_sliver of
    ! the segment is extended to it by a constant (its end value): a sliver the
    ! mesh cannot resolve, most often the sag of two polygons that approximate
    ! one curve (module header, 2.).
    call extend_sliver(mortar%inter, .true., ext(1))
    call extend_sliver(mortar%inter, .false., ext(2))
    mortar%cut(1) = mortar%inter%s(1, 1)
    mortar%cut(2) = mortar%inter%s(2, mortar%inter%nsub)
    if (mortar%cut(1) <= tol_overlap) mortar%cut(1) = 0.0_dp
    if (mortar%cut(2) >= 1.0_dp - tol_overlap) mortar%cut(2) = 1.0_dp
    ! the row of a cut end acts at a point inside a segment: its normal is the segment's
    if (.not. present(pairing)) then
      if (mortar%cut(1) > 0.0_dp) mortar%normal(:, first) = ns_out(:, first)
      if (mortar%cut(2) < 1.0_dp) mortar%normal(:, last) = ns_out(:, last - 1)
    end if
    ! a zone end on the axis is no end of the surface of revolution (8.): its
    ! normal is the axis', and its value of pi phi an unknown like the others
    if (mortar%axisymmetric .and. last - first >= 2) then
      mortar%axis_end = [xs(1, first) == 0.0_dp .and. mortar%cut(1) == 0.0_dp, &
                         xs(1, last) == 0.0_dp .and. mortar%cut(2) == 1.0_dp]
      if (mortar%axis_end(1)) mortar%normal(:, first) = [0.0_dp, sign(1.0_dp, mortar%normal(2, first))]
      if (mortar%axis_end(2)) mortar%normal(:, last) = [0.0_dp, sign(1.0_dp, mortar%normal(2, last))]
    end if

    ! Lumped weights over the full zone segments.
    do e = first, last - 1
      call add_hat_integrals(mortar, xs, seglen, e, e + 1)
    end do

    ! End rows: the master trace at the zone's ends, eq. (8) first line.  A cut
    ! end is where the master ends: its value is the master's end point.
    if (mortar%cut(1) > 0.0_dp .or. ext(1)) then
      f = mortar%inter%master_seg(1)
      r = mortar%inter%r(1, 1)
    else
      call end_row(xs(:, first), mortar%normal(:, first), xm, nm_out, mortar%inter, first, .true., f, r)
    end if
    if (.not. mortar%axis_end(1)) then
      mortar%P(first, f) = 1.0_dp - r
      mortar%P(first, f + 1) = r
    end if
    jlo = f
    jhi = f + 1
    if (mortar%cut(2) < 1.0_dp .or. ext(2)) then
      k = mortar%inter%nsub
      f = mortar%inter%master_seg(k)
      r = mortar%inter%r(2, k)
    else
      call end_row(xs(:, last), mortar%normal(:, last), xm, nm_out, mortar%inter, last - 1, .false., f, r)
    end if
    if (.not. mortar%axis_end(2)) then
      mortar%P(last, f) = mortar%P(last, f) + (1.0_dp - r)
      mortar%P(last, f + 1) = mortar%P(last, f + 1) + r
    end if
    jlo = min(jlo, f, minval(mortar%inter%master_seg(1:mortar%inter%nsub)))
    jhi = max(jhi, f + 1, maxval(mortar%inter%master_seg(1:mortar%inter%nsub)) + 1)

    ! Interior rows: D v = M c - E_0 c(a1) - E_n c(a2), eq. (8) second line.
    call project_interior(mortar, xs, jlo, jhi, info)
    if (info /= 0) then
      call set_error(err, 'mortar matrix D of the contact zone is singular (LAPACK dgtsv info ' // &
        int_to_str(info) // ')', error_numerical)
      return
    end if

    ! Initial normal gap, gap=geometry, at the zone's nodes (a cut end: at its point).
    if (.not. gap_zero) call set_initial_gaps(mortar, xs, xm, first, last, jlo, jhi)
  end subroutine build_mortar

  !> Assemble D, M, E_0, E_n on the sub-segments (segment_rule, exact) with the
  !> zone's hats (a cut end segment rescaled to the zone's part of it) and solve
  !> for the interior rows of P; also accumulate covered_weight and zone_weight.
  !>   mortar (inout) in: first, last, end rows of P, inter; out: interior rows of P
  !>   xs     (in)    (2, ns) slave polyline (its radii in the axisymmetric case)
  !>   jlo, jhi (in)  range of master columns that can be nonzero
  !>   info   (out)   0, or the dgtsv info when D is singular
  subroutine project_interior(mortar, xs, jlo, jhi, info)
    type(mortar_t), intent(inout) :: mortar
    real(dp), intent(in) :: xs(:,:)
    integer, intent(in) :: jlo, jhi
    integer, intent(out) :: info
    integer, parameter :: chunk = 128
    real(dp), allocatable :: dl(:), dd(:), du(:), e0(:), en(:), cl(:), cd(:), cu(:)
    integer :: ci
    real(dp) :: sq, wa, v, lo, hi, phi(0:1), sp(4), wp(4), phip(0:1, 4), chip(0:1, 4)
    integer :: n, first, last, k, m, f, q, ia, ib, a, b, kp, ns, nq, klo, khi, nu

    info = 0
    first = mortar%first
    last = mortar%last
    ns = mortar%ns
    n = last - first
    ! the unknown nodal values klo..khi of pi phi: the interior nodes, and a
    ! zone end on the axis (8.), whose hat is then a multiplier of its own
    klo = merge(0, 1, mortar%axis_end(1))
    khi = merge(n, n - 1, mortar%axis_end(2))
    nu = khi - klo + 1
    allocate(dl(max(nu - 1, 1)), dd(max(nu, 1)), du(max(nu - 1, 1)), e0(max(nu, 1)), en(max(nu, 1)))
    dl = 0.0_dp; dd = 0.0_dp; du = 0.0_dp; e0 = 0.0_dp; en = 0.0_dp

    do k = 1, mortar%inter%nsub
      m = mortar%inter%slave_seg(k) - first + 1          ! zone segment m: local nodes m-1, m
      f = mortar%inter%master_seg(k)
      lo = 0.0_dp                                        ! the zone's part [lo, hi] of the segment
      hi = 1.0_dp
      if (m == 1) lo = mortar%cut(1)
      if (m == n) hi = mortar%cut(2)
      call subsegment_points(mortar, xs, k, sp, wp, phip, chip, nq)
      do q = 1, nq
        mortar%covered_weight(first + m - 1:first + m) = mortar%covered_weight(first + m - 1:first + m) &
                                                         + wp(q) * phip(:, q)
        sq = (sp(q) - lo) / (hi - lo)                      ! the zone's hats: a cut segment is rescaled
        phi = [1.0_dp - sq, sq]
        do ia = 0, 1
          a = m - 1 + ia
          wa = wp(q) * phi(ia)
          mortar%zone_weight(first + a) = mortar%zone_weight(first + a) + wa
          if (n < 2) cycle
          kp = max(klo, min(khi, a))                       ! phi_a is part of psi_kp
          do ib = 0, 1
            b = m - 1 + ib
            v = wa * phi(ib)
            if (b < klo) then
              e0(kp - klo + 1) = e0(kp - klo + 1) + v      ! E_0 = int psi_k phi_0
            else if (b > khi) then
              en(kp - klo + 1) = en(kp - klo + 1) + v      ! E_n = int psi_k phi_n
            else if (b == kp) then
              dd(kp - klo + 1) = dd(kp - klo + 1) + v      ! D_kk
            else if (b == kp + 1) then
              du(kp - klo + 1) = du(kp - klo + 1) + v      ! D_k,k+1
            else
              dl(b - klo + 1) = dl(b - klo + 1) + v        ! D_k,k-1 (b = k-1)
            end if
          end do
          ! M_kj = int psi_k chi_j, accumulated in row first+kp of P
          mortar%P(first + kp, f) = mortar%P(first + kp, f) + wa * chip(0, q)
          mortar%P(first + kp, f + 1) = mortar%P(first + kp, f + 1) + wa * chip(1, q)
        end do
      end do
    end do
    if (n < 2) return

    ! Right-hand sides M - E_0 P(first,:) - E_n P(last,:), then v = D^-1 (...).
    do f = jlo, jhi
      if (klo == 1) mortar%P(first + 1:first + khi, f) = mortar%P(first + 1:first + khi, f) - e0(1:nu) * mortar%P(first, f)
      if (khi == n - 1) mortar%P(first + klo:last - 1, f) = mortar%P(first + klo:last - 1, f) - en(1:nu) * mortar%P(last, f)
    end do
    ! dgtsv's elimination runs along the rows across all its right-hand
    ! sides: in chunks of 128 master columns a row's pieces stay in cache,
    ! and the chunks run on the threads side by side.  Each chunk eliminates
    ! its own copy of D the same way, so every column gets the same digits.
    !$omp parallel do private(cl, cd, cu, ci) reduction(max:info) schedule(dynamic)
    do f = jlo, jhi, chunk
      cl = dl
      cd = dd
      cu = du
      call dgtsv(nu, min(chunk, jhi - f + 1), cl, cd, cu, mortar%P(first + klo, f), ns, ci)
      info = max(info, ci)
    end do
    !$omp end parallel do
  end subroutine project_interior

  !> The operator on a closed slave curve that the master covers all round:
  !> no zone ends, the multiplier space is the periodic P1 space (psi_k =
  !> phi_k, k = 1..n, node n+1 = node 1), pi_h^1 is the L2 projection onto it,
  !>    D v = M c,   D_kl = int phi_k phi_l (cyclic tridiagonal),  M_kj = int phi_k chi_j,
  !> solved by bordering: the last unknown eliminated, the tridiagonal rest by
  !> dgtsv with one more right-hand side.  Row n+1 of P repeats row 1.
  !>   mortar (inout) in: ns, nm, inter, arrays allocated; out: the operator
  !>   xs, xm (in) the polylines;  seglen (in) (ns-1) slave segment lengths
  !>   gap_zero (in) as build_mortar;  err (out) error_input for fewer than 3 segments, error_numerical when D is singular
  subroutine build_periodic(mortar, xs, xm, seglen, gap_zero, err)
    type(mortar_t), intent(inout) :: mortar
    real(dp), intent(in) :: xs(:,:), xm(:,:), seglen(:)
    logical, intent(in) :: gap_zero
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: dd(:), du(:), dl(:), rhs(:,:), b(:)
    real(dp) :: piv, sp(4), wp(4), phi(0:1, 4), chi(0:1, 4)
    integer :: n, k, e, f, q, ia, node(0:1), jlo, jhi, nc, info, nq

    n = mortar%ns - 1
    call start_periodic(mortar, n, 'segment', err)
    if (allocated(err)) return
    do e = 1, n
      call add_hat_integrals(mortar, xs, seglen, e, e + 1)
    end do
    mortar%weight(1) = mortar%weight(1) + mortar%weight(mortar%ns)
    allocate(dd(n), du(n), source=0.0_dp)
    do k = 1, mortar%inter%nsub                          ! D, M on the sub-segments (segment_rule, exact)
      e = mortar%inter%slave_seg(k)
      f = mortar%inter%master_seg(k)
      node = [e, modulo(e, n) + 1]
      call subsegment_points(mortar, xs, k, sp, wp, phi, chi, nq)
      do q = 1, nq
        do ia = 0, 1
          mortar%covered_weight(node(ia)) = mortar%covered_weight(node(ia)) + wp(q) * phi(ia, q)
          dd(node(ia)) = dd(node(ia)) + wp(q) * phi(ia, q) * phi(ia, q)
          mortar%P(node(ia), f) = mortar%P(node(ia), f) + wp(q) * phi(ia, q) * chi(0, q)
          mortar%P(node(ia), f + 1) = mortar%P(node(ia), f + 1) + wp(q) * phi(ia, q) * chi(1, q)
        end do
        du(e) = du(e) + wp(q) * phi(0, q) * phi(1, q)    ! D_e,e+1 (e = n: D_n,1)
      end do
    end do
    mortar%zone_weight(1:n) = mortar%covered_weight(1:n)
    ! bordering: T X = [M(1:n-1, :) | b],  b = D(1:n-1, n) = du(n-1) e_(n-1) + du(n) e_1
    jlo = minval(mortar%inter%master_seg(1:mortar%inter%nsub))
    jhi = maxval(mortar%inter%master_seg(1:mortar%inter%nsub)) + 1
    nc = jhi - jlo + 1
    allocate(rhs(n - 1, nc + 1), b(n - 1), source=0.0_dp)
    b(1) = du(n)
    b(n - 1) = b(n - 1) + du(n - 1)
    rhs(:, 1:nc) = mortar%P(1:n - 1, jlo:jhi)
    rhs(:, nc + 1) = b
    dl = du(1:n - 2)
    call dgtsv(n - 1, nc + 1, dl, dd(1:n - 1), du(1:n - 2), rhs, n - 1, info)
    piv = dd(n) - dot_product(b, rhs(:, nc + 1))          ! Schur complement of T in D
    if (info /= 0 .or. .not. piv > 0.0_dp) then
      call set_error(err, 'mortar matrix D of the closed contact curve is singular (LAPACK dgtsv info ' // &
        int_to_str(info) // ')', error_numerical)
      return
    end if
    do f = 1, nc
      mortar%P(n, jlo + f - 1) = (mortar%P(n, jlo + f - 1) - dot_product(b, rhs(:, f))) / piv
      mortar%P(1:n - 1, jlo + f - 1) = rhs(:, f) - rhs(:, nc + 1) * mortar%P(n, jlo + f - 1)
    end do
    mortar%P(mortar%ns, :) = mortar%P(1, :)
    mortar%zone_weight(mortar%ns) = mortar%zone_weight(1)
    mortar%covered_weight(mortar%ns) = mortar%covered_weight(1)
    if (.not. gap_zero) then
      call set_initial_gaps(mortar, xs, xm, 1, n, jlo, jhi)
      mortar%gap0(mortar%ns) = mortar%gap0(1)
    end if
  end subroutine build_periodic

  !> The quadrature points of sub-segment k of mortar%inter for the products
  !> of two P1 hats (degree 2 in s; 3 with the radial weight): slave
  !> coordinates s, weights w, and the slave and master hats there, the
  !> master coordinate r being linear in s on a sub-segment; nq points.
  !>   s, w (out) (4) slave coordinates and weights
  !>   phi  (out) (0:1, 4) phi(:, q) = [1 - s_q, s_q], the slave segment's two hats
  !>   chi  (out) (0:1, 4) chi(:, q) = [1 - r_q, r_q], the master segment's two hats
  pure subroutine subsegment_points(mortar, xs, k, s, w, phi, chi, nq)
    type(mortar_t), intent(in) :: mortar
    real(dp), intent(in) :: xs(:,:)
    integer, intent(in) :: k
    real(dp), intent(out) :: s(4), w(4), phi(0:1, 4), chi(0:1, 4)
    integer, intent(out) :: nq
    integer :: e, q
    real(dp) :: xi(4), r(4)
    associate(inter => mortar%inter)
      e = inter%slave_seg(k)
      call segment_rule(xs(:, e), xs(:, e + 1), inter%s(1, k), inter%s(2, k), 2, mortar%axisymmetric, s, w, nq, xi)
      r(1:nq) = 0.5_dp * (inter%r(1, k) + inter%r(2, k)) + (0.5_dp * xi(1:nq)) * (inter%r(2, k) - inter%r(1, k))
    end associate
    do q = 1, nq
      phi(:, q) = [1.0_dp - s(q), s(q)]
      chi(:, q) = [1.0_dp - r(q), r(q)]
    end do
  end subroutine subsegment_points

  !> Gauss-Legendre rule on the part [s1, s2] of the straight segment xa-xb
  !> (x(s) = (1 - s) xa + s xb), exact for every polynomial of the given
  !> degree in s, times the radial weight 2 pi r(s) (r = x(1), linear in s:
  !> one degree more) when axisymmetric: int f ds ~ sum_q w_q f(s_q), ds the
  !> arc length.  The P1 mortar integrals are degree 2; the quadratic ones 4.
  !>   xa, xb (in) (2) the segment's ends;  s1, s2 (in) 0 <= s1 < s2 <= 1
  !>   degree (in) 0..7 (minus one when axisymmetric)
  !>   axisymmetric (in) weight 2 pi r(s)
  !>   s, w   (out) (4) points in [s1, s2] and weights, the first nq of them
  !>   nq     (out) 1..4 points: degree + 1 (+ 1) <= 2 nq
  !>   xi     (out, optional) (4) the points on the reference interval [-1, 1]
  !>                (a coordinate linear in s is c = (c1 + c2)/2 + xi (c2 - c1)/2)
  pure subroutine segment_rule(xa, xb, s1, s2, degree, axisymmetric, s, w, nq, xi)
    real(dp), intent(in) :: xa(2), xb(2), s1, s2
    integer, intent(in) :: degree
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: s(4), w(4)
    integer, intent(out) :: nq
    real(dp), intent(out), optional :: xi(4)
    ! Gauss-Legendre on [-1, 1]: points g(k, n) and weights gw(k, n) of the n-point rule
    real(dp), parameter :: g(4, 4) = reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, &
      -0.57735026918962576451_dp, 0.57735026918962576451_dp, 0.0_dp, 0.0_dp, &
      -0.77459666924148337704_dp, 0.0_dp, 0.77459666924148337704_dp, 0.0_dp, &
      -0.86113631159405257522_dp, -0.33998104358485626480_dp, 0.33998104358485626480_dp, &
      0.86113631159405257522_dp], [4, 4])
    real(dp), parameter :: gw(4, 4) = reshape([2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, &
      1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, &
      0.55555555555555555556_dp, 0.88888888888888888889_dp, 0.55555555555555555556_dp, 0.0_dp, &
      0.34785484513745385737_dp, 0.65214515486254614263_dp, 0.65214515486254614263_dp, &
      0.34785484513745385737_dp], [4, 4])
    real(dp) :: half
    integer :: q
    nq = min(4, (degree + merge(1, 0, axisymmetric)) / 2 + 1)
    half = 0.5_dp * (s2 - s1)
    s = 0.0_dp
    w = 0.0_dp
    if (present(xi)) xi = g(:, nq)
    do q = 1, nq
      s(q) = 0.5_dp * (s1 + s2) + half * g(q, nq)
      w(q) = gw(q, nq) * half * norm2(xb - xa)
      if (axisymmetric) w(q) = w(q) * radial_weight((1.0_dp - s(q)) * xa(1) + s(q) * xb(1))
    end do
  end subroutine segment_rule

  !> Lumped weights of slave nodes a, b (the ends of segment e): int phi ds
  !> over the whole segment, 2 pi r ds when axisymmetric
  !> (L (2 r_a + r_b) / 6 per unit angle).
  subroutine add_hat_integrals(mortar, xs, seglen, a, b)
    type(mortar_t), intent(inout) :: mortar
    real(dp), intent(in) :: xs(:,:), seglen(:)
    integer, intent(in) :: a, b
    if (mortar%axisymmetric) then
      mortar%weight(a) = mortar%weight(a) + radial_weight(seglen(a) * (2.0_dp * xs(1, a) + xs(1, b)) / 6.0_dp)
      mortar%weight(b) = mortar%weight(b) + radial_weight(seglen(a) * (xs(1, a) + 2.0_dp * xs(1, b)) / 6.0_dp)
    else
      mortar%weight(a) = mortar%weight(a) + 0.5_dp * seglen(a)
      mortar%weight(b) = mortar%weight(b) + 0.5_dp * seglen(a)
    end if
  end subroutine add_hat_integrals

  !> The point of zone node i (first..last): the slave node, or for a cut end
  !> the point of its segment (element) where the zone ends.
  pure function zone_point(mo, xs, i) result(x)
    type(mortar_t), intent(in) :: mo
    real(dp), intent(in) :: xs(:,:)
    integer, intent(in) :: i
    real(dp) :: x(2)
    integer :: node(3), nt, t
    real(dp) :: coef(3)
    call zone_node_terms(mo, i, node, coef, nt)
    x = 0.0_dp
    do t = 1, nt
      x = x + coef(t) * xs(:, node(t))
    end do
  end function zone_point

  !> The slave nodes and coefficients that give the slave trace at zone node
  !> i: the node itself (nt = 1), or, for a zone node of a cut end segment,
  !> the two ends of its segment with the linear interpolation weights
  !> (nt = 2); on a quadratic trace (degree 2) the zone nodes of a cut end
  !> element are its points at s = lo, (lo + hi) / 2, hi (lo = cut(1) on the
  !> zone's first element, hi = cut(2) on its last), each the element's three
  !> nodes with the quadratic shape functions at s (nt = 3).
  !>   mo   (in)  the operator
  !>   i    (in)  zone node, first..last
  !>   node (out) (nt) slave trace indices;  coef (out) (nt) their weights;  nt (out) 1, 2 or 3
  pure subroutine zone_node_terms(mo, i, node, coef, nt)
    type(mortar_t), intent(in) :: mo
    integer, intent(in) :: i
    integer, intent(out) :: node(3), nt
    real(dp), intent(out) :: coef(3)
    integer :: i0
    real(dp) :: lo, hi, s
    nt = 1
    node = i
    coef = [1.0_dp, 0.0_dp, 0.0_dp]
    if (mo%degree == 2) then
      if (mo%cut(1) > 0.0_dp .and. i - mo%first < 2) then
        i0 = mo%first                              ! the zone's first element, trace nodes i0..i0+2
      else if (mo%cut(2) < 1.0_dp .and. mo%last - i < 2) then
        i0 = mo%last - 2
      else
        return
      end if
      lo = 0.0_dp
      hi = 1.0_dp
      if (i0 == mo%first) lo = mo%cut(1)
      if (i0 + 2 == mo%last) hi = mo%cut(2)
      s = lo + 0.5_dp * real(i - i0, dp) * (hi - lo)
      nt = 3
      node = [i0, i0 + 1, i0 + 2]
      coef = [(1.0_dp - s) * (1.0_dp - 2.0_dp * s), 4.0_dp * s * (1.0_dp - s), s * (2.0_dp * s - 1.0_dp)]
    else if (i == mo%first .and. mo%cut(1) > 0.0_dp) then
      nt = 2
      node(1:2) = [i, i + 1]
      coef(1:2) = [1.0_dp - mo%cut(1), mo%cut(1)]
    else if (i == mo%last .and. mo%cut(2) < 1.0_dp) then
      nt = 2
      node(1:2) = [i - 1, i]
      coef(1:2) = [1.0_dp - mo%cut(2), mo%cut(2)]
    end if
  end subroutine zone_node_terms

  !> Where the cover of the zone's first (at_start) or last slave segment stops
  !> short of the segment's end node by less than tol_sliver, the master's end
  !> piece is stretched to the node: its sub-segment is given the node as its
  !> end, the master coordinates unchanged (the master is not made longer; its
  !> end segment faces a little more of the slave).
  !>   inter    (inout) the sub-segments, ordered
  !>   at_start (in)    the zone's first segment (s -> 0) or its last (s -> 1)
  !>   done     (out)   whether the piece was stretched
  subroutine extend_sliver(inter, at_start, done)
    type(intersection_t), intent(inout) :: inter
    logical, intent(in) :: at_start
    logical, intent(out) :: done
    integer :: n
    n = inter%nsub
    if (at_start) then
      done = inter%s(1, 1) > tol_overlap .and. inter%s(1, 1) < tol_sliver
      if (done) inter%s(1, 1) = 0.0_dp
    else
      done = inter%s(2, n) < 1.0_dp - tol_overlap .and. inter%s(2, n) > 1.0_dp - tol_sliver
      if (done) inter%s(2, n) = 1.0_dp
    end if
  end subroutine extend_sliver

  !> Remove the sub-segments on slave segment e from inter (they stay ordered).
  subroutine drop_pieces(inter, e)
    type(intersection_t), intent(inout) :: inter
    integer, intent(in) :: e
    logical :: keep(inter%nsub)
    integer :: n
    keep = inter%slave_seg(1:inter%nsub) /= e
    n = count(keep)
    inter%slave_seg(1:n) = pack(inter%slave_seg(1:inter%nsub), keep)
    inter%master_seg(1:n) = pack(inter%master_seg(1:inter%nsub), keep)
    inter%s(1, 1:n) = pack(inter%s(1, 1:inter%nsub), keep)
    inter%s(2, 1:n) = pack(inter%s(2, 1:inter%nsub), keep)
    inter%r(1, 1:n) = pack(inter%r(1, 1:inter%nsub), keep)
    inter%r(2, 1:n) = pack(inter%r(2, 1:inter%nsub), keep)
    inter%nsub = n
  end subroutine drop_pieces

  !> The master point that gives the end value (pi phi)(a) = phi(a), eq. (8): the
  !> nearest hit of the line a + tau n on a master segment facing n; when there is
  !> none, the master point bounding the covered part of the end slave segment.
  !>   a       (in)  (2) end node of the zone
  !>   n       (in)  (2) its unit nodal normal
  !>   xm      (in)  (2, nm) master nodes
  !>   nm_out  (in)  (2, nm-1) master segment normals
  !>   inter   (in)  the sub-segments (at least one on segment eend)
  !>   eend    (in)  the zone's end slave segment
  !>   at_start (in) .true. for a1 (lowest s on eend), .false. for a2 (highest s)
  !>   f       (out) master segment holding the point
  !>   r       (out) its master coordinate in [0, 1]
  subroutine end_row(a, n, xm, nm_out, inter, eend, at_start, f, r)
    real(dp), intent(in) :: a(2), n(2), xm(:,:), nm_out(:,:)
    type(intersection_t), intent(in) :: inter
    integer, intent(in) :: eend
    logical, intent(in) :: at_start
    integer, intent(out) :: f
    real(dp), intent(out) :: r
    integer :: k

    call ray_hit(xm, 1, nm_out, a, n, f, r)
    if (f > 0) return

    ! Constant extension of the master trace beyond its end: its value at the
    ! master end of the first (a1) or last (a2) sub-segment on eend.
    k = findloc(inter%slave_seg(1:inter%nsub), eend, dim=1, back=.not. at_start)
    if (k == 0) return
    f = inter%master_seg(k)
    r = inter%r(merge(1, 2, at_start), k)
  end subroutine end_row

end module mortar_operator
