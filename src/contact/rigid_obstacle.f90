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
!> multiplier space M_h^1 as for two bodies (mortar_operator): P1 hats,
!> constant on the two end segments of an open slave boundary, periodic on a
!> closed one; the whole slave boundary is the zone (the obstacle has no end
!> the slave could pass).  Row i, at slave node x_i with the direction
!> n_i = -n_r(x_i) (the slave's outward normal as the exact shape makes it):
!>     B_i u = n_i . u1(x_i) - n_i . U(x_i) <= g_i,   g_i = (pi_h^1 d)(x_i),
!> pi_h^1 the mortar projection onto the slave trace space (eq. (8)): the end
!> values pointwise, the interior ones by D v = int psi_k d - E_0 d(a1) - E_n d(a2).
!> The rigid motion is linear along each slave segment, so pi_h^1 U = U at the
!> nodes: its part of the row is n_i . U(x_i), three entries on the rigid's dofs,
!>     -[n_i,x,  n_i,y,  n_i . (-(y_i - y_r), x_i - x_r)].
!> A frictional row takes t_i = (-n_i,y, n_i,x) instead of n_i.
!>
!> Programming interface
!>   type(rigid_shape_t)                         the shape, its reference point and dofs
!>   signed_distance(sh, x, d, n)                d(x) and n_r(x)
!>   orient_shape(sh, xs, ns_out)                line/polyline: the solid on the side the slave faces
!>   build_rigid_mortar(xs, sh, mortar, err)     the mortar_t of a slave polyline against sh
!>   rigid_terms(sh, x, v)                       the motion of x along v per unit ux, uy, theta
module rigid_obstacle
  use kinds, only: dp
  use lapack_interfaces, only: dgtsv
  use strings, only: int_to_str
  use errors, only: error_t, set_error, error_numerical
  use mortar_operator, only: mortar_t
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

  !> The mortar operator of a slave polyline against a rigid obstacle (module
  !> header): the whole polyline is the zone, the normals n_i = -n_r(x_i), the
  !> gaps pi_h^1 d, the weights int phi_i.  P is not allocated (no master mesh).
  !>   xs     (in)  (2, ns) slave polyline, ns >= 2; closed when xs(:, ns) = xs(:, 1)
  !>   ns_out (in)  (2, ns-1) outward unit normals of the slave segments
  !>   sh     (in)  the obstacle (oriented)
  !>   mortar (out) first = 1, last = ns, normal, gap0, weights, arc
  !>   err    (out) allocated when the tridiagonal solve fails (error_numerical)
  subroutine build_rigid_mortar(xs, ns_out, sh, mortar, err)
    real(dp), intent(in) :: xs(:,:), ns_out(:,:)
    type(rigid_shape_t), intent(in) :: sh
    type(mortar_t), intent(out) :: mortar
    type(error_t), allocatable, intent(out) :: err
    integer :: ns, e, i, info
    real(dp) :: d, n(2), y(2)
    real(dp), allocatable :: seglen(:), dnode(:), fint(:,:)
    logical :: closed

    ns = size(xs, 2)
    closed = ns > 3 .and. all(xs(:, 1) == xs(:, ns))
    mortar%ns = ns
    mortar%nm = 0
    mortar%first = 1
    mortar%last = ns
    allocate(mortar%normal(2, ns), mortar%gap0(ns), mortar%weight(ns), mortar%covered_weight(ns), &
             mortar%zone_weight(ns), mortar%arc(ns), mortar%constrained(ns), seglen(ns - 1), dnode(ns))
    mortar%constrained = .true.
    mortar%arc(1) = 0.0_dp
    mortar%weight = 0.0_dp
    do e = 1, ns - 1
      seglen(e) = norm2(xs(:, e + 1) - xs(:, e))
      mortar%arc(e + 1) = mortar%arc(e) + seglen(e)
      mortar%weight(e:e + 1) = mortar%weight(e:e + 1) + 0.5_dp * seglen(e)
    end do
    if (closed) then                          ! node ns is node 1
      mortar%weight(1) = mortar%weight(1) + mortar%weight(ns)
      mortar%weight(ns) = mortar%weight(1)
    end if
    mortar%covered_weight = mortar%weight
    mortar%zone_weight = mortar%weight
    do i = 1, ns
      ! the slave's nodal normal: the direction at a node that lies on a corner
      y = ns_out(:, max(1, i - 1)) + ns_out(:, min(ns - 1, i))
      if (closed .and. (i == 1 .or. i == ns)) y = ns_out(:, 1) + ns_out(:, ns - 1)
      call signed_distance(sh, xs(:, i), d, n, -y / norm2(y))
      dnode(i) = d
      mortar%normal(:, i) = -n
    end do
    call hat_integrals(xs, sh, fint)          ! fint(1:2, e) = int over segment e of d phi_e, d phi_{e+1}
    if (closed) then
      call project_periodic(seglen, fint, mortar%gap0, info)
    else
      call project_open(seglen, fint, dnode, mortar%gap0, info)
    end if
    if (info /= 0) then
      call set_error(err, 'mortar matrix D of the slave boundary against RIGID ' // sh%name // ' is singular ' // &
                     '(LAPACK dgtsv info ' // int_to_str(info) // ')', error_numerical)
      return
    end if
  end subroutine build_rigid_mortar

  !> fint(1, e), fint(2, e): int over slave segment e of d times the hat of its
  !> first and second node (composite 4-point Gauss: d has kinks at corners).
  subroutine hat_integrals(xs, sh, fint)
    real(dp), intent(in) :: xs(:,:)
    type(rigid_shape_t), intent(in) :: sh
    real(dp), allocatable, intent(out) :: fint(:,:)
    integer :: e, j, q
    real(dp) :: s, x(2), d, n(2), l
    allocate(fint(2, size(xs, 2) - 1), source=0.0_dp)
    do e = 1, size(xs, 2) - 1
      l = norm2(xs(:, e + 1) - xs(:, e))
      do j = 1, nsub
        do q = 1, 4
          s = (real(j - 1, dp) + gx(q)) / nsub
          x = (1.0_dp - s) * xs(:, e) + s * xs(:, e + 1)
          call signed_distance(sh, x, d, n)
          fint(:, e) = fint(:, e) + gw(q) * l / nsub * d * [1.0_dp - s, s]
        end do
      end do
    end do
  end subroutine hat_integrals

  !> pi_h^1 d on an open slave polyline (eq. (8)): v(1) = d(a1), v(ns) = d(a2),
  !> D v_int = int psi_k d - E_0 d(a1) - E_n d(a2), psi_2 = phi_1 + phi_2,
  !> psi_{ns-1} = phi_{ns-1} + phi_ns (both when ns = 3), D_kl = int psi_k phi_l.
  subroutine project_open(seglen, fint, dnode, v, info)
    real(dp), intent(in) :: seglen(:), fint(:,:), dnode(:)
    real(dp), intent(out) :: v(:)
    integer, intent(out) :: info
    integer :: ns, m, k, j
    real(dp), allocatable :: mdiag(:), moff(:), bphi(:), dl(:), dd(:), du(:), b(:,:), c(:,:)
    ns = size(dnode)
    v = 0.0_dp
    v(1) = dnode(1)
    v(ns) = dnode(ns)
    info = 0
    m = ns - 2                                 ! interior unknowns, nodes 2..ns-1
    if (m <= 0) return
    ! P1 mass matrix of the slave polyline (tridiagonal) and int phi_j d
    allocate(mdiag(ns), moff(ns - 1), bphi(ns), source=0.0_dp)
    do j = 1, ns - 1
      mdiag(j) = mdiag(j) + seglen(j) / 3.0_dp
      mdiag(j + 1) = mdiag(j + 1) + seglen(j) / 3.0_dp
      moff(j) = seglen(j) / 6.0_dp
      bphi(j) = bphi(j) + fint(1, j)
      bphi(j + 1) = bphi(j + 1) + fint(2, j)
    end do
    ! c(k, l) = int psi_k phi_l for the rows k = 2..ns-1, columns l = k-1..k+1
    ! (and the end columns that the end multipliers add: 1 and ns)
    allocate(c(2:ns - 1, ns), source=0.0_dp)
    allocate(b(m, 1))
    do k = 2, ns - 1
      c(k, k - 1) = moff(k - 1)
      c(k, k) = mdiag(k)
      c(k, k + 1) = moff(k)
      b(k - 1, 1) = bphi(k)
    end do
    ! psi_2 adds phi_1, psi_{ns-1} adds phi_ns
    c(2, 1) = c(2, 1) + mdiag(1)
    c(2, 2) = c(2, 2) + moff(1)
    b(1, 1) = b(1, 1) + bphi(1)
    c(ns - 1, ns) = c(ns - 1, ns) + mdiag(ns)
    c(ns - 1, ns - 1) = c(ns - 1, ns - 1) + moff(ns - 1)
    b(m, 1) = b(m, 1) + bphi(ns)
    b(:, 1) = b(:, 1) - c(2:ns - 1, 1) * dnode(1) - c(2:ns - 1, ns) * dnode(ns)
    allocate(dl(max(1, m - 1)), dd(m), du(max(1, m - 1)))
    do k = 2, ns - 1
      dd(k - 1) = c(k, k)
      if (k < ns - 1) du(k - 1) = c(k, k + 1)
      if (k > 2) dl(k - 2) = c(k, k - 1)
    end do
    call dgtsv(m, 1, dl, dd, du, b, m, info)
    if (info == 0) v(2:ns - 1) = b(:, 1)
  end subroutine project_open

  !> pi_h^1 d on a closed slave polyline (node ns = node 1): M v = int phi d with
  !> M the cyclic P1 mass matrix, solved by Sherman-Morrison on two dgtsv solves.
  subroutine project_periodic(seglen, fint, v, info)
    real(dp), intent(in) :: seglen(:), fint(:,:)
    real(dp), intent(out) :: v(:)
    integer, intent(out) :: info
    integer :: n, j
    real(dp), allocatable :: dd(:), dl(:), du(:), b(:,:)
    real(dp) :: alpha, gamma
    n = size(seglen)                           ! unknowns: nodes 1..n (node n+1 = node 1)
    allocate(dd(n), dl(n - 1), du(n - 1), b(n, 2), source=0.0_dp)
    do j = 1, n
      dd(j) = dd(j) + seglen(j) / 3.0_dp
      dd(modulo(j, n) + 1) = dd(modulo(j, n) + 1) + seglen(j) / 3.0_dp
      b(j, 1) = b(j, 1) + fint(1, j)
      b(modulo(j, n) + 1, 1) = b(modulo(j, n) + 1, 1) + fint(2, j)
    end do
    do j = 1, n - 1
      dl(j) = seglen(j) / 6.0_dp
      du(j) = seglen(j) / 6.0_dp
    end do
    alpha = seglen(n) / 6.0_dp                 ! the corners M(1, n) = M(n, 1)
    ! M = T + u u'/gamma with u = (gamma, 0, ..., 0, alpha): T has
    ! dd(1) - gamma and dd(n) - alpha^2 / gamma on its diagonal
    gamma = -dd(1)
    dd(1) = dd(1) - gamma
    dd(n) = dd(n) - alpha * alpha / gamma
    b(:, 2) = 0.0_dp
    b(1, 2) = gamma
    b(n, 2) = alpha
    call dgtsv(n, 2, dl, dd, du, b, n, info)
    if (info /= 0) return
    ! x = y - (v'y / (1 + v'z)) z, v = (1, 0, ..., 0, alpha / gamma)
    v(1:n) = b(:, 1) - (b(1, 1) + alpha / gamma * b(n, 1)) / (1.0_dp + b(1, 2) + alpha / gamma * b(n, 2)) * b(:, 2)
    v(n + 1) = v(1)
  end subroutine project_periodic

end module rigid_obstacle
