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
!> 1. Segment intersection ("1D segment quadrature").  For each slave segment
!>    [x_a, x_b] (length L, unit tangent t, outward unit normal n) every master segment
!>    that faces it (n_master . n < 0) is projected onto the slave segment's line along
!>    n: s(y) = (y - x_a).t / L.  The overlap of the projected interval with [0, 1], when
!>    longer than 1e-10, is a sub-segment; on it the slave hats (affine in s) and the
!>    master hats (affine in the master coordinate r, itself affine in s) are both
!>    linear, so 2-point Gauss on each sub-segment integrates every product
!>    phi_i chi_j and phi_i phi_l exactly.  A master part counts whatever its distance
!>    along n (initial gaps may be large); a slave part covered twice (a master that
!>    folds back in front of the slave) is rejected.
!> 2. Effective contact zone Gamma_c.  The slave segments with a positive covered length
!>    form the zone, slave nodes first..last, renumbered x_0 = a1, ..., x_n = a2
!>    (n = last - first segments).  An uncovered slave segment inside the zone (a hole)
!>    is an input error; no coverage at all gives first = last = 0 (no contact).
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
!>
!> Programming interface
!>   type(mortar_t)        the operator of one pair (fields commented below)
!>   type(intersection_t)  the list of sub-segments of the two 1D meshes
!>   build_mortar(xs, ns_out, xm, nm_out, gap_zero, mortar, err)
!>                         check the polylines, intersect, build pi_h^1, gaps, weights;
!>                         err (status 2) for geometric input problems, (status 1) when
!>                         the LAPACK solve fails
!>   intersect_segments(xs, ns_out, xm, nm_out, inter)
!>                         the sub-segment list alone (valid polylines assumed)
module mortar_operator
  use kinds, only: dp
  use lapack_interfaces, only: dgtsv
  use diagnostics, only: error_t, set_error, int_to_str
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: mortar_t, intersection_t, build_mortar, intersect_segments, common_normals, zone_node_terms, zone_point

  !> Sub-segments of the intersection of the slave and master 1D meshes, ordered by
  !> slave segment and, within one, by increasing s.
  type :: intersection_t
    integer :: nsub = 0                       !< number of sub-segments
    integer, allocatable :: slave_seg(:)      !< (nsub) slave segment e (nodes e, e+1)
    integer, allocatable :: master_seg(:)     !< (nsub) master segment f (nodes f, f+1)
    real(dp), allocatable :: s(:,:)           !< (2, nsub) slave coordinates of the ends, 0 <= s(1) < s(2) <= 1
    real(dp), allocatable :: r(:,:)           !< (2, nsub) master coordinates at the same ends (y = (1-r) y_f + r y_f+1)
  end type intersection_t

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
    type(intersection_t) :: inter             !< the sub-segments used for the integrals
  end type mortar_t

  real(dp), parameter :: tol_unit = 1.0e-8_dp      ! |n| = 1 and n.t = 0 up to this
  real(dp), parameter :: tol_length = 1.0e-12_dp   ! zero length, relative to the polyline's extent
  real(dp), parameter :: tol_overlap = 1.0e-10_dp  ! shortest sub-segment / double cover, relative to L
  real(dp), parameter :: tol_ray = 1.0e-10_dp      ! slack on the master coordinate of a ray hit
  real(dp), parameter :: tol_piece = 1.0e-3_dp     ! shortest covered piece of a zone-end segment kept
  real(dp), parameter :: tol_sliver = 2.0e-2_dp    ! longest uncovered piece of a zone-end segment extended


contains

  !> Build the mortar operator pi_h^1 (eq. (8)) of one contact pair, its effective
  !> zone, nodal normals, weights and initial gaps; see the module header.
  !>   xs       (in)  (2, ns) slave polyline nodes in order along the boundary, ns >= 2
  !>   ns_out   (in)  (2, ns-1) outward unit normal of each slave segment (from the slave body)
  !>   xm       (in)  (2, nm) master polyline nodes in order, nm >= 2
  !>   nm_out   (in)  (2, nm-1) outward unit normal of each master segment (from the master body)
  !>   gap_zero (in)  .true.: the boundaries coincide (the paper's setting), gap0 = 0
  !>   mortar   (out) the operator; contents unspecified when err is returned
  !>   err      (out) allocated on failure: status 2 for bad geometry (sizes, zero-length
  !>                  segments, normals, holes or folds in the master cover), 1 when the
  !>                  tridiagonal solve fails
  subroutine build_mortar(xs, ns_out, xm, nm_out, gap_zero, mortar, err, pairing)
    real(dp), intent(in) :: xs(:,:), ns_out(:,:), xm(:,:), nm_out(:,:)
    logical, intent(in) :: gap_zero
    type(mortar_t), intent(out) :: mortar
    type(error_t), allocatable, intent(out) :: err
    real(dp), intent(in), optional :: pairing(:,:)
    integer :: ns, nm, i, e, k, first, last, f, jlo, jhi, info
    integer, allocatable :: ncover(:)
    logical :: ext(2)
    real(dp) :: r, y(2)
    real(dp), allocatable :: seglen(:), py(:,:)

    call check_polyline(xs, ns_out, 'slave', err)
    if (allocated(err)) return
    call check_polyline(xm, nm_out, 'master', err)
    if (allocated(err)) return

    ns = size(xs, 2)
    nm = size(xm, 2)
    mortar%ns = ns
    mortar%nm = nm
    allocate(mortar%normal(2, ns), mortar%P(ns, nm), mortar%gap0(ns), mortar%weight(ns))
    allocate(mortar%covered_weight(ns), mortar%zone_weight(ns), mortar%arc(ns), mortar%constrained(ns))
    mortar%P = 0.0_dp
    mortar%zone_weight = 0.0_dp
    mortar%gap0 = 0.0_dp
    mortar%weight = 0.0_dp
    mortar%covered_weight = 0.0_dp
    mortar%constrained = .false.

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
            real_to_str(mortar%arc(e) + mortar%inter%s(1, k) * seglen(e)) // ' and ' // &
            real_to_str(mortar%arc(e) + min(mortar%inter%s(2, k - 1), mortar%inter%s(2, k)) * seglen(e)) // &
            ' (a master boundary that faces the slave once, without folds, expected)', 2)
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
          real_to_str(mortar%arc(e)) // ' and ' // real_to_str(mortar%arc(k + 1)) // &
          ' (a master that covers the slave contact zone without holes expected)', 2)
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

    ! Lumped weights over the full zone segments.
    do e = first, last - 1
      mortar%weight(e) = mortar%weight(e) + 0.5_dp * seglen(e)
      mortar%weight(e + 1) = mortar%weight(e + 1) + 0.5_dp * seglen(e)
    end do

    ! End rows: the master trace at the zone's ends, eq. (8) first line.  A cut
    ! end is where the master ends: its value is the master's end point.
    if (mortar%cut(1) > 0.0_dp .or. ext(1)) then
      f = mortar%inter%master_seg(1)
      r = mortar%inter%r(1, 1)
    else
      call end_row(xs(:, first), mortar%normal(:, first), xm, nm_out, mortar%inter, first, .true., f, r)
    end if
    mortar%P(first, f) = 1.0_dp - r
    mortar%P(first, f + 1) = r
    jlo = f
    jhi = f + 1
    if (mortar%cut(2) < 1.0_dp .or. ext(2)) then
      k = mortar%inter%nsub
      f = mortar%inter%master_seg(k)
      r = mortar%inter%r(2, k)
    else
      call end_row(xs(:, last), mortar%normal(:, last), xm, nm_out, mortar%inter, last - 1, .false., f, r)
    end if
    mortar%P(last, f) = mortar%P(last, f) + (1.0_dp - r)
    mortar%P(last, f + 1) = mortar%P(last, f + 1) + r
    jlo = min(jlo, f, minval(mortar%inter%master_seg(1:mortar%inter%nsub)))
    jhi = max(jhi, f + 1, maxval(mortar%inter%master_seg(1:mortar%inter%nsub)) + 1)

    ! Interior rows: D v = M c - E_0 c(a1) - E_n c(a2), eq. (8) second line.
    call project_interior(mortar, seglen, jlo, jhi, info)
    if (info /= 0) then
      call set_error(err, 'mortar matrix D of the contact zone is singular (LAPACK dgtsv info ' // &
        int_to_str(info) // ')', 1)
      return
    end if

    ! Initial normal gap, gap=geometry, at the zone's nodes (a cut end: at its point).
    if (.not. gap_zero) then
      allocate(py(first:last, 2))
      py = matmul(mortar%P(first:last, jlo:jhi), transpose(xm(:, jlo:jhi)))   ! (P y)_i, componentwise
      do i = first, last
        mortar%gap0(i) = dot_product(mortar%normal(:, i), py(i, :) - zone_point(mortar, xs, i))
      end do
    end if
  end subroutine build_mortar

  !> Assemble D, M, E_0, E_n on the sub-segments (2-point Gauss, exact) with the
  !> zone's hats (a cut end segment rescaled to the zone's part of it) and solve
  !> for the interior rows of P; also accumulate covered_weight and zone_weight.
  !>   mortar (inout) in: first, last, end rows of P, inter; out: interior rows of P
  !>   seglen (in)    (ns-1) slave segment lengths
  !>   jlo, jhi (in)  range of master columns that can be nonzero
  !>   info   (out)   0, or the dgtsv info when D is singular
  subroutine project_interior(mortar, seglen, jlo, jhi, info)
    type(mortar_t), intent(inout) :: mortar
    real(dp), intent(in) :: seglen(:)
    integer, intent(in) :: jlo, jhi
    integer, intent(out) :: info
    integer, parameter :: chunk = 128
    real(dp), allocatable :: dl(:), dd(:), du(:), e0(:), en(:), cl(:), cd(:), cu(:)
    integer :: ci
    real(dp) :: sq, rq, wq, wa, v, lo, hi, phi(0:1), chi(0:1)
    integer :: n, first, last, k, m, f, q, ia, ib, a, b, kp, ns

    info = 0
    first = mortar%first
    last = mortar%last
    ns = mortar%ns
    n = last - first
    allocate(dl(max(n - 2, 1)), dd(max(n - 1, 1)), du(max(n - 2, 1)), e0(max(n - 1, 1)), en(max(n - 1, 1)))
    dl = 0.0_dp; dd = 0.0_dp; du = 0.0_dp; e0 = 0.0_dp; en = 0.0_dp

    do k = 1, mortar%inter%nsub
      m = mortar%inter%slave_seg(k) - first + 1          ! zone segment m: local nodes m-1, m
      f = mortar%inter%master_seg(k)
      wq = 0.5_dp * (mortar%inter%s(2, k) - mortar%inter%s(1, k)) * seglen(mortar%inter%slave_seg(k))
      lo = 0.0_dp                                        ! the zone's part [lo, hi] of the segment
      hi = 1.0_dp
      if (m == 1) lo = mortar%cut(1)
      if (m == n) hi = mortar%cut(2)
      do q = -1, 1, 2
        call gauss_point(mortar%inter, k, q, sq, rq)
        chi = [1.0_dp - rq, rq]
        phi = [1.0_dp - sq, sq]
        mortar%covered_weight(first + m - 1:first + m) = mortar%covered_weight(first + m - 1:first + m) + wq * phi
        sq = (sq - lo) / (hi - lo)                         ! the zone's hats: a cut segment is rescaled
        phi = [1.0_dp - sq, sq]
        do ia = 0, 1
          a = m - 1 + ia
          wa = wq * phi(ia)
          mortar%zone_weight(first + a) = mortar%zone_weight(first + a) + wa
          if (n < 2) cycle
          kp = max(1, min(n - 1, a))                       ! phi_a is part of psi_kp
          do ib = 0, 1
            b = m - 1 + ib
            v = wa * phi(ib)
            if (b == 0) then
              e0(kp) = e0(kp) + v                          ! E_0 = int psi_k phi_0
            else if (b == n) then
              en(kp) = en(kp) + v                          ! E_n = int psi_k phi_n
            else if (b == kp) then
              dd(kp) = dd(kp) + v                          ! D_kk
            else if (b == kp + 1) then
              du(kp) = du(kp) + v                          ! D_k,k+1
            else
              dl(b) = dl(b) + v                            ! D_k,k-1 (b = k-1)
            end if
          end do
          ! M_kj = int psi_k chi_j, accumulated in row first+kp of P
          mortar%P(first + kp, f) = mortar%P(first + kp, f) + wa * chi(0)
          mortar%P(first + kp, f + 1) = mortar%P(first + kp, f + 1) + wa * chi(1)
        end do
      end do
    end do
    if (n < 2) return

    ! Right-hand sides M - E_0 P(first,:) - E_n P(last,:), then v = D^-1 (...).
    do f = jlo, jhi
      mortar%P(first + 1:last - 1, f) = mortar%P(first + 1:last - 1, f) - e0(1:n - 1) * mortar%P(first, f) &
                                        - en(1:n - 1) * mortar%P(last, f)
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
      call dgtsv(n - 1, min(chunk, jhi - f + 1), cl, cd, cu, mortar%P(first + 1, f), ns, ci)
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
  !>   gap_zero (in) as build_mortar;  err (out) status 2 for fewer than 3 segments, 1 when D is singular
  subroutine build_periodic(mortar, xs, xm, seglen, gap_zero, err)
    type(mortar_t), intent(inout) :: mortar
    real(dp), intent(in) :: xs(:,:), xm(:,:), seglen(:)
    logical, intent(in) :: gap_zero
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: dd(:), du(:), dl(:), rhs(:,:), b(:), py(:,:)
    real(dp) :: sq, rq, wq, phi(0:1), chi(0:1), piv
    integer :: n, k, e, f, q, ia, ib, node(0:1), jlo, jhi, nc, info, i

    n = mortar%ns - 1
    if (n < 3) then
      call set_error(err, 'closed slave boundary has ' // int_to_str(n) // &
        ' segment(s) (at least 3 expected on a closed contact curve)', 2)
      return
    end if
    mortar%first = 1
    mortar%last = mortar%ns
    mortar%constrained = .true.
    do e = 1, n
      mortar%weight(e) = mortar%weight(e) + 0.5_dp * seglen(e)
      mortar%weight(e + 1) = mortar%weight(e + 1) + 0.5_dp * seglen(e)
    end do
    mortar%weight(1) = mortar%weight(1) + mortar%weight(mortar%ns)
    allocate(dd(n), du(n), source=0.0_dp)
    do k = 1, mortar%inter%nsub                          ! D, M on the sub-segments, 2-point Gauss (exact)
      e = mortar%inter%slave_seg(k)
      f = mortar%inter%master_seg(k)
      node = [e, modulo(e, n) + 1]
      wq = 0.5_dp * (mortar%inter%s(2, k) - mortar%inter%s(1, k)) * seglen(e)
      do q = -1, 1, 2
        call gauss_point(mortar%inter, k, q, sq, rq)
        phi = [1.0_dp - sq, sq]
        chi = [1.0_dp - rq, rq]
        do ia = 0, 1
          mortar%covered_weight(node(ia)) = mortar%covered_weight(node(ia)) + wq * phi(ia)
          do ib = 0, 1
            if (ib == ia) dd(node(ia)) = dd(node(ia)) + wq * phi(ia) * phi(ib)
          end do
          mortar%P(node(ia), f) = mortar%P(node(ia), f) + wq * phi(ia) * chi(0)
          mortar%P(node(ia), f + 1) = mortar%P(node(ia), f + 1) + wq * phi(ia) * chi(1)
        end do
        du(e) = du(e) + wq * phi(0) * phi(1)             ! D_e,e+1 (e = n: D_n,1)
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
        int_to_str(info) // ')', 1)
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
      allocate(py(n, 2))
      py = matmul(mortar%P(1:n, jlo:jhi), transpose(xm(:, jlo:jhi)))
      do i = 1, n
        mortar%gap0(i) = dot_product(mortar%normal(:, i), py(i, :) - xs(:, i))
      end do
      mortar%gap0(mortar%ns) = mortar%gap0(1)
    end if
  end subroutine build_periodic

  !> The common normal of a frictional pair at each slave node (module header,
  !> 7.): the direction along which the two surfaces approach, which pairs the
  !> points that meet and is the normal of the slip's tangent plane.  Near the
  !> first contact of two surfaces of curvatures k1 (slave) and k2 (master),
  !> their normals at a distance x are tilted by k1 x and -k2 x from it, so
  !>    n_c = normalize(w n1 - (1 - w) n2),   w = k2 / (k1 + k2)  in [0, 1],
  !> n1 the slave nodal normal, n2 the master normal at the point its ray
  !> meets.  k1, k2 are the mean curvatures of the two polylines over the
  !> part of them that faces the other (convex > 0).  w = 1/2 (the bisector)
  !> when they agree to tol_curv (a polygon's curvature is no better; mirror
  !> images then pair exactly), when k1 + k2 is not positive (conforming
  !> surfaces, whose normals are parallel anyway) and on flat pairs; w = 1 or
  !> 0 when one side is flat to tol_curv of the other.
  !>   xs, ns_out, xm, nm_out (in) the polylines and segment normals, as build_mortar
  !>   nc (out) (2, ns) unit common normals; the slave nodal normal where no master faces
  !>   w  (out) the weight of the slave normal
  subroutine common_normals(xs, ns_out, xm, nm_out, nc, w)
    real(dp), intent(in) :: xs(:,:), ns_out(:,:), xm(:,:), nm_out(:,:)
    real(dp), allocatable, intent(out) :: nc(:,:)
    real(dp), intent(out) :: w
    real(dp), parameter :: tol_curv = 5.0e-2_dp
    type(intersection_t) :: inter
    real(dp), allocatable :: n1(:,:), n2(:,:)
    logical, allocatable :: sface(:), mface(:)
    real(dp) :: k1, k2, y(2), rr, m(2)
    integer :: ns, nm, i, f, iter

    ns = size(xs, 2)
    nm = size(xm, 2)
    call nodal_normals(xs, ns_out, n1)
    call nodal_normals(xm, nm_out, n2)
    nc = n1
    w = 0.5_dp
    call intersect_segments(xs, ns_out, xm, nm_out, inter)
    if (inter%nsub == 0) return
    allocate(sface(ns - 1), mface(nm - 1), source=.false.)
    sface(inter%slave_seg(1:inter%nsub)) = .true.
    mface(inter%master_seg(1:inter%nsub)) = .true.
    k1 = mean_curvature(xs, ns_out, sface)
    k2 = mean_curvature(xm, nm_out, mface)
    if (abs(k1 - k2) <= tol_curv * 0.5_dp * (abs(k1) + abs(k2)) .or. .not. k1 + k2 > 0.0_dp) then
      w = 0.5_dp
    else if (abs(k1) <= tol_curv * abs(k2)) then
      w = 1.0_dp
    else if (abs(k2) <= tol_curv * abs(k1)) then
      w = 0.0_dp
    else
      w = min(1.0_dp, max(0.0_dp, k2 / (k1 + k2)))
    end if
    do i = 1, ns
      if (.not. (any(sface(max(1, i - 1):min(ns - 1, i))))) cycle
      ! the master point on the ray along the current estimate, a few times:
      ! each pass moves it closer to the point the common normal meets
      do iter = 1, 4
        call ray_hit(xs(:, i), nc(:, i), xm, nm_out, f, rr)
        if (f == 0) exit
        if (rr < 1.0e-8_dp) rr = 0.0_dp                    ! on a master node: its normal exactly
        if (rr > 1.0_dp - 1.0e-8_dp) rr = 1.0_dp
        m = (1.0_dp - rr) * n2(:, f) + rr * n2(:, f + 1)
        m = m / norm2(m)
        y = w * n1(:, i) - (1.0_dp - w) * m
        if (.not. norm2(y) > 0.0_dp) exit
        nc(:, i) = y / norm2(y)
      end do
    end do
  end subroutine common_normals

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

  !> Gauss point q (-1 or +1) of the 2-point rule on sub-segment k: its slave
  !> coordinate s and master coordinate r (each of the two weighs half the
  !> sub-segment's length).
  pure subroutine gauss_point(inter, k, q, s, r)
    type(intersection_t), intent(in) :: inter
    integer, intent(in) :: k, q
    real(dp), intent(out) :: s, r
    real(dp), parameter :: gauss = 0.57735026918962576451_dp   ! 1/sqrt(3)
    s = 0.5_dp * (inter%s(1, k) + inter%s(2, k)) + real(q, dp) * gauss * 0.5_dp * (inter%s(2, k) - inter%s(1, k))
    r = 0.5_dp * (inter%r(1, k) + inter%r(2, k)) + real(q, dp) * gauss * 0.5_dp * (inter%r(2, k) - inter%r(1, k))
  end subroutine gauss_point

  !> The point of zone node i (first..last): the slave node, or for a cut end
  !> the point of its segment where the zone ends.
  pure function zone_point(mo, xs, i) result(x)
    type(mortar_t), intent(in) :: mo
    real(dp), intent(in) :: xs(:,:)
    integer, intent(in) :: i
    real(dp) :: x(2)
    integer :: node(2), nt
    real(dp) :: coef(2)
    call zone_node_terms(mo, i, node, coef, nt)
    x = coef(1) * xs(:, node(1))
    if (nt == 2) x = x + coef(2) * xs(:, node(2))
  end function zone_point

  !> The slave nodes and coefficients that give the slave trace at zone node
  !> i: the node itself (nt = 1), or for a cut end the two ends of its segment
  !> with the linear interpolation weights (nt = 2).
  !>   mo   (in)  the operator
  !>   i    (in)  zone node, first..last
  !>   node (out) (nt) slave polyline indices;  coef (out) (nt) their weights;  nt (out) 1 or 2
  pure subroutine zone_node_terms(mo, i, node, coef, nt)
    type(mortar_t), intent(in) :: mo
    integer, intent(in) :: i
    integer, intent(out) :: node(2), nt
    real(dp), intent(out) :: coef(2)
    nt = 1
    node = i
    coef = [1.0_dp, 0.0_dp]
    if (i == mo%first .and. mo%cut(1) > 0.0_dp) then
      nt = 2
      node = [i, i + 1]
      coef = [1.0_dp - mo%cut(1), mo%cut(1)]
    else if (i == mo%last .and. mo%cut(2) < 1.0_dp) then
      nt = 2
      node = [i - 1, i]
      coef = [1.0_dp - mo%cut(2), mo%cut(2)]
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

    call ray_hit(a, n, xm, nm_out, f, r)
    if (f > 0) return

    ! Constant extension of the master trace beyond its end.
    if (at_start) then
      do k = 1, inter%nsub
        if (inter%slave_seg(k) == eend) then
          f = inter%master_seg(k)
          r = inter%r(1, k)
          return
        end if
      end do
    else
      do k = inter%nsub, 1, -1
        if (inter%slave_seg(k) == eend) then
          f = inter%master_seg(k)
          r = inter%r(2, k)
          return
        end if
      end do
    end if
  end subroutine end_row

  !> The nearest hit of the line a + tau n on a master segment facing n.
  !>   a, n (in) (2) point and unit direction;  xm, nm_out (in) master nodes and segment normals
  !>   f (out) the master segment, 0 when the line misses the master;  r (out) its coordinate in [0, 1]
  subroutine ray_hit(a, n, xm, nm_out, f, r)
    real(dp), intent(in) :: a(2), n(2), xm(:,:), nm_out(:,:)
    integer, intent(out) :: f
    real(dp), intent(out) :: r
    real(dp) :: d(2), w(2), den, tau, rr, best
    integer :: g
    f = 0
    r = 0.0_dp
    best = huge(1.0_dp)
    do g = 1, size(xm, 2) - 1
      if (dot_product(nm_out(:, g), n) >= 0.0_dp) cycle
      d = xm(:, g + 1) - xm(:, g)
      w = xm(:, g) - a
      den = cross(n, d)
      if (abs(den) <= 1.0e-12_dp * norm2(d)) cycle        ! segment along the ray
      rr = -cross(n, w) / den                              ! a + tau n = y_g + rr d
      if (rr < -tol_ray .or. rr > 1.0_dp + tol_ray) cycle
      tau = cross(w, d) / den
      if (abs(tau) < best) then
        best = abs(tau)
        f = g
        r = min(1.0_dp, max(0.0_dp, rr))
      end if
    end do
  end subroutine ray_hit

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
    integer, allocatable :: cf(:)

    nss = size(xs, 2) - 1
    nms = size(xm, 2) - 1
    allocate(clo(nms), chi(nms), rlo(nms), rhi(nms), cf(nms), sm(nms + 1))
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
      ! insertion sort by lo
      do i = 2, nc
        j = i
        do while (j > 1)
          if (clo(j - 1) <= clo(j)) exit
          call swap_real(clo(j - 1), clo(j))
          call swap_real(chi(j - 1), chi(j))
          call swap_real(rlo(j - 1), rlo(j))
          call swap_real(rhi(j - 1), rhi(j))
          call swap_int(cf(j - 1), cf(j))
          j = j - 1
        end do
      end do
      if (inter%nsub + nc > cap) then
        cap = max(2 * cap, inter%nsub + nc)
        call grow_intersection(inter, cap)
      end if
      do i = 1, nc
        inter%nsub = inter%nsub + 1
        inter%slave_seg(inter%nsub) = e
        inter%master_seg(inter%nsub) = cf(i)
        inter%s(:, inter%nsub) = [clo(i), chi(i)]
        inter%r(:, inter%nsub) = [rlo(i), rhi(i)]
      end do
    end do
  end subroutine intersect_segments

  !> Check one polyline and its segment normals; err (status 2) on the first defect.
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
      call set_error(err, side // ' boundary coordinates or normals are not 2D (arrays (2, n) expected)', 2)
      return
    end if
    if (np < 2) then
      call set_error(err, side // ' boundary has ' // int_to_str(np) // &
        ' node(s) (at least 2 nodes, one segment, expected)', 2)
      return
    end if
    if (size(nrm, 2) /= np - 1) then
      call set_error(err, side // ' boundary has ' // int_to_str(size(nrm, 2)) // ' segment normals for ' // &
        int_to_str(np) // ' nodes (one normal per segment, ' // int_to_str(np - 1) // ', expected)', 2)
      return
    end if
    if (.not. (all(ieee_is_finite(x)) .and. all(ieee_is_finite(nrm)))) then
      call set_error(err, side // ' boundary has non-finite coordinates or normals (finite numbers expected)', 2)
      return
    end if
    scale = max(maxval(x(1, :)) - minval(x(1, :)), maxval(x(2, :)) - minval(x(2, :)))
    orient = 0.0_dp
    do k = 1, np - 1
      t = x(:, k + 1) - x(:, k)
      length = norm2(t)
      if (length <= tol_length * scale) then
        call set_error(err, 'zero-length segment on the ' // side // ' boundary at node ' // int_to_str(k) // &
          ' (distinct consecutive nodes expected)', 2)
        return
      end if
      t = t / length
      if (abs(norm2(nrm(:, k)) - 1.0_dp) > tol_unit) then
        call set_error(err, 'normal of ' // side // ' segment ' // int_to_str(k) // &
          ' is not a unit vector (outward unit normals expected)', 2)
        return
      end if
      if (abs(dot_product(nrm(:, k), t)) > tol_unit) then
        call set_error(err, 'normal of ' // side // ' segment ' // int_to_str(k) // &
          ' is not perpendicular to the segment (outward unit normals expected)', 2)
        return
      end if
      c = cross(t, nrm(:, k))                              ! +1 or -1: the side of the normal
      if (k == 1) then
        orient = c
      else if (c * orient < 0.0_dp) then
        call set_error(err, 'normals of the ' // side // ' boundary change side at segment ' // int_to_str(k) // &
          ' (outward normals, all on the body''s side, expected)', 2)
        return
      end if
      if (k > 1) then
        if (dot_product(nrm(:, k - 1), nrm(:, k)) <= -1.0_dp + tol_unit) then
          call set_error(err, side // ' boundary turns back on itself at node ' // int_to_str(k) // &
            ' (a boundary without folds expected)', 2)
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

  !> z-component of the cross product of two plane vectors.
  pure real(dp) function cross(u, v)
    real(dp), intent(in) :: u(2), v(2)
    cross = u(1) * v(2) - u(2) * v(1)
  end function cross

  pure subroutine swap_real(a, b)
    real(dp), intent(inout) :: a, b
    real(dp) :: c
    c = a; a = b; b = c
  end subroutine swap_real

  pure subroutine swap_int(a, b)
    integer, intent(inout) :: a, b
    integer :: c
    c = a; a = b; b = c
  end subroutine swap_int

  !> Short decimal text of a real (6 significant digits, trailing zeros dropped), for messages.
  function real_to_str(v) result(s)
    real(dp), intent(in) :: v
    character(len=:), allocatable :: s
    character(len=32) :: buf
    integer :: k
    write(buf, '(g0.6)') v
    s = trim(adjustl(buf))
    if (index(s, '.') > 0 .and. scan(s, 'EeDd') == 0) then
      k = len_trim(s)
      do while (s(k:k) == '0')
        k = k - 1
      end do
      if (s(k:k) == '.') k = k - 1
      s = s(1:k)
    end if
  end function real_to_str

end module mortar_operator
