!> elements: pure element kernels of plane elasticity for the P1 triangle (the
!> paper's element, eq. (7)), the Q1 quadrilateral and the isoparametric
!> quadratic elements: the 6-node triangle (P2, nen = 6), the 8-node serendipity
!> quadrilateral (nen = 8) and the 9-node Lagrange quadrilateral (Q2, nen = 9).
!>
!> Element nodes xe(2, nen), corners first, counter-clockwise, then the
!> mid-side nodes (node nc + k on the edge from corner k to corner k + 1), then
!> the centre (Q2): gmsh's and VTK's order.  A quadratic element is mapped from
!> the reference element by its own shape functions, so an edge whose mid-side
!> node is off the chord is curved.  Element dofs ordered (u1x, u1y, u2x, u2y,
!> ...).  Strain eps = B u in Voigt form (exx, eyy, gxy).
!>
!> Stiffness rules, exact on straight-sided (affine) elements: P1 1 point, Q1
!> 2x2 Gauss, P2 the 3-point degree-2 rule, Q8 and Q9 3x3 Gauss.
!>
!> B-bar (doc/theory.md, "Nearly incompressible materials").  With np > 0
!> pressure modes (pressure_modes: 1 on Q1, the mean dilatation; 0 on the
!> others) the kernels take eps = B_bar u in place of B u: the volumetric
!> strain theta = m' B u (m = (1, 1, 0); in axisymmetry (1, 1, 0, 1), the
!> hoop strain included) replaced by its L2 projection onto the np
!> polynomials p(x) = (1, x - x_c, y - y_c) of the element,
!>     B_bar = B + m (p' G - m' B) / k,  G = M^-1 int p m' B dV,  M = int p p' dV,
!> k = 2 in the plane (the in-plane trace), 3 in axisymmetry; the deviatoric
!> strain is kept.  The kernels' optional argument np selects it.
!>
!> Programming interface
!>   quadrature_rule(nen, order, xi, w)    points xi(2, nq) and weights w(nq) on the
!>        reference element: order 1, the stiffness rule, or 2, a richer rule
!>        for loads and error integrals (P1: 3 points, degree 2; Q1: 3x3 Gauss;
!>        P2: Dunavant's 6 points, degree 4; Q8, Q9: 4x4 Gauss)
!>   corner_count(nen)                     3 (triangles) or 4 (quadrilaterals)
!>   reference_node(nen, a)                the reference coordinates of node a
!>   stiffness_rule(nen, nq, xi, w)        the order-1 rule in fixed-size arrays
!>   shape_at(nen, xe, xi, n, dndx, detj)  shape functions, their x-y gradients
!>        and the Jacobian determinant at a reference point
!>   element_stiffness(nen, xe, d, thick, ke [, np])   ke = int B' D B t dA (B_bar with np > 0)
!>   element_force(nen, xe, d, thick, ue, fe [, np])   fe = ke ue, without ke
!>   element_body_load(nen, xe, b, thick, fe)    fe = int N' b t dA (constant b)
!>   element_strain(nen, xe, ue, eps [, np])     strain at the element centre
!>        (reference centroid (1/3, 1/3) or (0, 0)): the element's stress for output
!>   pressure_modes(nen)                   the B-bar pressure modes of an element kind
!>   dilatation_projection(nen, xe, np, radial, g)   G (np, 2 nen): theta_bar = p(x)' G u
!>   replace_dilatation(nen, xe, np, g, n, b)        B -> B_bar at one point
!>   pressure_basis(nen, xe, np, x, p)               p(x) (np) of the element
!>   edge_load(xa, xb, t, thick, fe)             fe(4) = int N' t t_h ds, constant
!>        traction t on the straight edge xa-xb
!>   edge_load_quadratic(xe, t, pr, thick, fe)   fe(6) = int N' (t + pr n_r) t_h ds
!>        on the 3-node edge xe(2, 3) (ends, then middle; curved when the middle
!>        is off the chord), 3-point Gauss; n_r the unit normal to the right of
!>        the direction end 1 -> end 2 (a pressure follows the curve)
module elements
  use kinds, only: dp
  implicit none
  private
  public :: quadrature_rule, shape_at, element_stiffness, element_force, element_body_load, element_strain
  public :: edge_load, edge_load_quadratic, strain_operator, corner_count, max_nen, stiffness_rule, reference_node
  public :: pressure_modes, dilatation_projection, replace_dilatation, pressure_basis, max_np

  !> The most nodes of an element (Q9).  The kernels run once per element:
  !> their work arrays have this fixed size, not nen, because gfortran puts
  !> arrays of run-time size on the heap (a malloc and free per call, and
  !> a lock shared with every thread that allocates meanwhile).
  integer, parameter :: max_nen = 9

  !> The most pressure modes of the B-bar kernels: a linear pressure (1, x, y).
  integer, parameter :: max_np = 3

contains

  !> Quadrature on the reference triangle (0,0),(1,0),(0,1) or square [-1,1]^2.
  !>   nen   (in)  3, 4, 6, 8 or 9
  !>   order (in)  1: the stiffness rule (stiffness_rule); 2: the richer rule
  !>               for loads and error integrals (module header)
  !>   xi    (out) (2, nq) points
  !>   w     (out) (nq) weights (sum: 1/2 for the triangle, 4 for the square)
  pure subroutine quadrature_rule(nen, order, xi, w)
    integer, intent(in) :: nen, order
    real(dp), allocatable, intent(out) :: xi(:,:), w(:)
    real(dp), parameter :: g2 = 1.0_dp / sqrt(3.0_dp), g3 = sqrt(0.6_dp)
    real(dp), parameter :: g4(4) = [-0.8611363115940526_dp, -0.3399810435848563_dp, &
                                    0.3399810435848563_dp, 0.8611363115940526_dp]
    real(dp), parameter :: w4(4) = [0.3478548451374538_dp, 0.6521451548625461_dp, &
                                    0.6521451548625461_dp, 0.3478548451374538_dp]
    ! Dunavant's degree-4 rule: two orbits (a, a, 1 - 2a) of three points
    real(dp), parameter :: ta = 0.445948490915965_dp, tb = 0.091576213509771_dp
    real(dp), parameter :: wa = 0.223381589678011_dp / 2, wb = 0.109951743655322_dp / 2
    real(dp) :: p(4), pw(4)
    integer :: i, j, k, m
    if (corner_count(nen) == 3) then
      if (order <= 1 .and. nen == 3) then
        allocate(xi(2, 1), w(1))
        xi(:, 1) = [1.0_dp, 1.0_dp] / 3.0_dp
        w = 0.5_dp
      else if (order <= 1 .or. nen == 3) then
        allocate(xi(2, 3), w(3))
        xi(:, 1) = [1.0_dp / 6.0_dp, 1.0_dp / 6.0_dp]
        xi(:, 2) = [2.0_dp / 3.0_dp, 1.0_dp / 6.0_dp]
        xi(:, 3) = [1.0_dp / 6.0_dp, 2.0_dp / 3.0_dp]
        w = 1.0_dp / 6.0_dp
      else
        allocate(xi(2, 6), w(6))
        xi = reshape([ta, ta, 1 - 2 * ta, ta, ta, 1 - 2 * ta, &
                      tb, tb, 1 - 2 * tb, tb, tb, 1 - 2 * tb], [2, 6])
        w = [wa, wa, wa, wb, wb, wb]
      end if
    else
      if (order <= 1 .and. nen == 4) then
        m = 2
        p(1:2) = [-g2, g2]
        pw(1:2) = 1.0_dp
      else if (order <= 1 .or. nen == 4) then
        m = 3
        p(1:3) = [-g3, 0.0_dp, g3]
        pw(1:3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
      else
        m = 4
        p = g4
        pw = w4
      end if
      allocate(xi(2, m * m), w(m * m))
      k = 0
      do j = 1, m
        do i = 1, m
          k = k + 1
          xi(:, k) = [p(i), p(j)]
          w(k) = pw(i) * pw(j)
        end do
      end do
    end if
  end subroutine quadrature_rule

  !> Corners of an element of nen nodes: 3 (P1, P2) or 4 (Q1, Q8, Q9).
  pure integer function corner_count(nen) result(nc)
    integer, intent(in) :: nen
    nc = merge(3, 4, nen == 3 .or. nen == 6)
  end function corner_count

  !> The reference coordinates of node a (1..nen) of an element, in the node
  !> order of the module header: where shape function a is 1.
  pure function reference_node(nen, a) result(xi)
    integer, intent(in) :: nen, a
    real(dp) :: xi(2)
    real(dp), parameter :: ts(6) = [0.0_dp, 1.0_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp], &
                           tt(6) = [0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.5_dp, 0.5_dp], &
                           qs(9) = [-1, 1, 1, -1, 0, 1, 0, -1, 0], qt(9) = [-1, -1, 1, 1, -1, 0, 1, 0, 0]
    if (corner_count(nen) == 3) then
      xi = [ts(a), tt(a)]
    else
      xi = [qs(a), qt(a)]
    end if
  end function reference_node

  !> Shape functions and x-y derivatives at reference point xi.
  !>   nen  (in)  3, 4, 6, 8 or 9
  !>   xe   (in)  (2, nen) node coordinates
  !>   xi   (in)  (2) reference point
  !>   n    (out) (nen) shape function values
  !>   dndx (out) (2, nen) gradients in x, y
  !>   detj (out) Jacobian determinant (> 0 for a valid element)
  pure subroutine shape_at(nen, xe, xi, n, dndx, detj)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), xi(2)
    real(dp), intent(out) :: n(nen), dndx(2, nen), detj
    real(dp) :: dndxi(2, max_nen), jac(2, 2), jinv(2, 2)
    integer :: a
    call reference_shape(nen, xi, n, dndxi)
    ! jac(i,j) = d x_i / d xi_j, and dN/dx = J^-T dN/dxi, written out: no
    ! array temporary of run-time size (see max_nen)
    jac = 0.0_dp
    do a = 1, nen
      jac(:, 1) = jac(:, 1) + xe(:, a) * dndxi(1, a)
      jac(:, 2) = jac(:, 2) + xe(:, a) * dndxi(2, a)
    end do
    detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    if (detj == 0.0_dp) then             ! a collapsed element (the mesh checks report it): no gradient
      dndx(:, 1:nen) = 0.0_dp
      return
    end if
    jinv(1, 1) = jac(2, 2) / detj
    jinv(2, 2) = jac(1, 1) / detj
    jinv(1, 2) = -jac(1, 2) / detj
    jinv(2, 1) = -jac(2, 1) / detj
    do a = 1, nen
      dndx(1, a) = jinv(1, 1) * dndxi(1, a) + jinv(2, 1) * dndxi(2, a)
      dndx(2, a) = jinv(1, 2) * dndxi(1, a) + jinv(2, 2) * dndxi(2, a)
    end do
  end subroutine shape_at

  !> Shape functions n(1:nen) and their reference gradients dndxi(2, 1:nen).
  pure subroutine reference_shape(nen, xi, n, dndxi)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xi(2)
    real(dp), intent(out) :: n(nen), dndxi(:,:)
    ! reference position (-1, 0, 1) of the quadrilaterals' nodes: corners, mid-sides, centre
    real(dp), parameter :: qs(9) = [-1, 1, 1, -1, 0, 1, 0, -1, 0], qt(9) = [-1, -1, 1, 1, -1, 0, 1, 0, 0]
    real(dp) :: l(3), dl(2, 3), s, t, ls(3), lt(3), dls(3), dlt(3)
    integer :: a, i, j, k
    select case (nen)
    case (3)
      n = [1.0_dp - xi(1) - xi(2), xi(1), xi(2)]
      dndxi(:, 1) = [-1.0_dp, -1.0_dp]
      dndxi(:, 2) = [1.0_dp, 0.0_dp]
      dndxi(:, 3) = [0.0_dp, 1.0_dp]
    case (6)
      ! area coordinates L_i: corners L_i (2 L_i - 1), mid-sides 4 L_i L_j
      l = [1.0_dp - xi(1) - xi(2), xi(1), xi(2)]
      dl = reshape([-1.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 3])
      do i = 1, 3
        j = mod(i, 3) + 1
        n(i) = l(i) * (2 * l(i) - 1)
        dndxi(:, i) = (4 * l(i) - 1) * dl(:, i)
        n(3 + i) = 4 * l(i) * l(j)
        dndxi(:, 3 + i) = 4 * (l(j) * dl(:, i) + l(i) * dl(:, j))
      end do
    case (4)
      n = 0.25_dp * [(1 - xi(1)) * (1 - xi(2)), (1 + xi(1)) * (1 - xi(2)), &
                     (1 + xi(1)) * (1 + xi(2)), (1 - xi(1)) * (1 + xi(2))]
      dndxi(:, 1) = 0.25_dp * [-(1 - xi(2)), -(1 - xi(1))]
      dndxi(:, 2) = 0.25_dp * [(1 - xi(2)), -(1 + xi(1))]
      dndxi(:, 3) = 0.25_dp * [(1 + xi(2)), (1 + xi(1))]
      dndxi(:, 4) = 0.25_dp * [-(1 + xi(2)), (1 - xi(1))]
    case (8)
      s = xi(1); t = xi(2)
      do a = 1, 4                ! corners: (1 + s sa)(1 + t ta)(s sa + t ta - 1) / 4
        n(a) = 0.25_dp * (1 + s * qs(a)) * (1 + t * qt(a)) * (s * qs(a) + t * qt(a) - 1)
        dndxi(1, a) = 0.25_dp * qs(a) * (1 + t * qt(a)) * (2 * s * qs(a) + t * qt(a))
        dndxi(2, a) = 0.25_dp * qt(a) * (1 + s * qs(a)) * (s * qs(a) + 2 * t * qt(a))
      end do
      do a = 5, 8                ! mid-sides: (1 - s^2)(1 + t ta) / 2 or (1 + s sa)(1 - t^2) / 2
        if (qs(a) == 0) then
          n(a) = 0.5_dp * (1 - s * s) * (1 + t * qt(a))
          dndxi(:, a) = [-s * (1 + t * qt(a)), 0.5_dp * (1 - s * s) * qt(a)]
        else
          n(a) = 0.5_dp * (1 + s * qs(a)) * (1 - t * t)
          dndxi(:, a) = [0.5_dp * qs(a) * (1 - t * t), -t * (1 + s * qs(a))]
        end if
      end do
    case default                 ! 9: products of the 1D quadratics at -1, 0, 1
      s = xi(1); t = xi(2)
      ls = [0.5_dp * s * (s - 1), 1 - s * s, 0.5_dp * s * (s + 1)]
      dls = [s - 0.5_dp, -2 * s, s + 0.5_dp]
      lt = [0.5_dp * t * (t - 1), 1 - t * t, 0.5_dp * t * (t + 1)]
      dlt = [t - 0.5_dp, -2 * t, t + 0.5_dp]
      do a = 1, 9
        i = nint(qs(a)) + 2
        k = nint(qt(a)) + 2
        n(a) = ls(i) * lt(k)
        dndxi(:, a) = [dls(i) * lt(k), ls(i) * dlt(k)]
      end do
    end select
  end subroutine reference_shape

  !> Strain operator B(3, 2 nen) from shape gradients: eps = B u.
  pure subroutine strain_operator(nen, dndx, b)
    integer, intent(in) :: nen
    real(dp), intent(in) :: dndx(2, nen)
    real(dp), intent(out) :: b(3, 2 * nen)
    integer :: a
    b = 0.0_dp
    do a = 1, nen
      b(1, 2 * a - 1) = dndx(1, a)
      b(2, 2 * a) = dndx(2, a)
      b(3, 2 * a - 1) = dndx(2, a)
      b(3, 2 * a) = dndx(1, a)
    end do
  end subroutine strain_operator

  !> The stiffness rule (quadrature_rule order 1) in fixed-size arrays, for
  !> the kernels called once per element: no allocation there.
  !>   nq (out) 1 (P1), 4 (Q1), 3 (P2) or 9 (Q8, Q9); xi(:, 1:nq), w(1:nq) as quadrature_rule
  pure subroutine stiffness_rule(nen, nq, xi, w)
    integer, intent(in) :: nen
    integer, intent(out) :: nq
    real(dp), intent(out) :: xi(2, 9), w(9)
    real(dp), parameter :: g = 1.0_dp / sqrt(3.0_dp), g3(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
    real(dp), parameter :: w3(3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
    integer :: i, j
    select case (nen)
    case (3)
      nq = 1
      xi(:, 1) = [1.0_dp, 1.0_dp] / 3.0_dp
      w(1) = 0.5_dp
    case (4)
      nq = 4
      xi(:, 1:4) = reshape([-g, -g, g, -g, -g, g, g, g], [2, 4])
      w(1:4) = 1.0_dp
    case (6)                                  ! degree 2: B' D B of an affine P2
      nq = 3
      xi(:, 1:3) = reshape([1.0_dp, 1.0_dp, 4.0_dp, 1.0_dp, 1.0_dp, 4.0_dp], [2, 3]) / 6.0_dp
      w(1:3) = 1.0_dp / 6.0_dp
    case default                              ! 3x3 Gauss: degree 4 in each variable (Q9 on a parallelogram)
      nq = 9
      do j = 1, 3
        do i = 1, 3
          xi(:, 3 * (j - 1) + i) = [g3(i), g3(j)]
          w(3 * (j - 1) + i) = w3(i) * w3(j)
        end do
      end do
    end select
  end subroutine stiffness_rule

  !> Element stiffness ke = sum_q w_q detJ_q t B_q' D B_q (stiffness_rule: exact
  !> on straight-sided elements), in ke(1:2 nen, 1:2 nen) (ke may be larger:
  !> 2 max_nen x 2 max_nen for any element).
  !>   np (in, optional) > 0: B_bar with np pressure modes (module header); 0 or absent: B
  pure subroutine element_stiffness(nen, xe, d, thick, ke, np)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), d(3, 3), thick
    real(dp), intent(inout) :: ke(:,:)
    integer, intent(in), optional :: np
    real(dp) :: xi(2, 9), w(9), n(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen), db(3, 2 * max_nen), c
    real(dp) :: g(max_np, 2 * max_nen)
    integer :: q, nq, m, i, j, npr
    m = 2 * nen
    npr = modes(np)
    call stiffness_rule(nen, nq, xi, w)
    if (npr > 0) call dilatation_projection(nen, xe, npr, .false., g(1:npr, 1:m))
    ke(1:m, 1:m) = 0.0_dp
    do q = 1, nq
      call shape_at(nen, xe, xi(:, q), n, dndx, detj)
      call strain_operator(nen, dndx, b)
      if (npr > 0) call replace_dilatation(nen, xe, npr, g(1:npr, 1:m), n(1:nen), b(:, 1:m))
      c = w(q) * detj * thick
      do j = 1, m                  ! db = D B, ke += c B' D B (no temporary: see max_nen)
        db(:, j) = d(:, 1) * b(1, j) + d(:, 2) * b(2, j) + d(:, 3) * b(3, j)
        do i = 1, m
          ke(i, j) = ke(i, j) + c * (b(1, i) * db(1, j) + b(2, i) * db(2, j) + b(3, i) * db(3, j))
        end do
      end do
    end do
  end subroutine element_stiffness

  !> Element forces fe = ke ue = sum_q w_q detJ_q t B_q' (D (B_q ue)), without
  !> forming ke (the same rule as element_stiffness).
  !>   np (in, optional) as element_stiffness
  pure subroutine element_force(nen, xe, d, thick, ue, fe, np)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), d(3, 3), thick, ue(2 * nen)
    real(dp), intent(out) :: fe(2 * nen)
    integer, intent(in), optional :: np
    real(dp) :: xi(2, 9), w(9), n(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen), eps(3), sig(3), c
    real(dp) :: g(max_np, 2 * max_nen)
    integer :: q, nq, j, npr
    npr = modes(np)
    call stiffness_rule(nen, nq, xi, w)
    if (npr > 0) call dilatation_projection(nen, xe, npr, .false., g(1:npr, 1:2 * nen))
    fe = 0.0_dp
    do q = 1, nq
      call shape_at(nen, xe, xi(:, q), n, dndx, detj)
      call strain_operator(nen, dndx, b)
      if (npr > 0) call replace_dilatation(nen, xe, npr, g(1:npr, 1:2 * nen), n(1:nen), b(:, 1:2 * nen))
      eps = 0.0_dp
      do j = 1, 2 * nen
        eps = eps + b(:, j) * ue(j)
      end do
      sig = d(:, 1) * eps(1) + d(:, 2) * eps(2) + d(:, 3) * eps(3)
      c = w(q) * detj * thick
      do j = 1, 2 * nen
        fe(j) = fe(j) + c * (sig(1) * b(1, j) + sig(2) * b(2, j) + sig(3) * b(3, j))
      end do
    end do
  end subroutine element_force

  !> Consistent nodal forces of a constant body force b (force per unit volume).
  pure subroutine element_body_load(nen, xe, bf, thick, fe)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), bf(2), thick
    real(dp), intent(out) :: fe(2 * nen)
    real(dp), allocatable :: xi(:,:), w(:)
    real(dp) :: n(max_nen), dndx(2, max_nen), detj
    integer :: q, a
    call quadrature_rule(nen, 2, xi, w)
    fe = 0.0_dp
    do q = 1, size(w)
      call shape_at(nen, xe, xi(:, q), n, dndx, detj)
      do a = 1, nen
        fe(2 * a - 1:2 * a) = fe(2 * a - 1:2 * a) + (w(q) * detj * thick * n(a)) * bf
      end do
    end do
  end subroutine element_body_load

  !> Strain at the element centre, the reference centroid (exact for P1; the
  !> centre value for the others: the element's stress in the output).
  !>   np (in, optional) as element_stiffness: the B_bar strain, the one the
  !>        stiffness is made of
  pure subroutine element_strain(nen, xe, ue, eps, np)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen)
    real(dp), intent(out) :: eps(3)
    integer, intent(in), optional :: np
    real(dp) :: n(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen), xc(2), g(max_np, 2 * max_nen)
    integer :: j, npr
    if (corner_count(nen) == 3) then
      xc = [1.0_dp, 1.0_dp] / 3.0_dp
    else
      xc = 0.0_dp
    end if
    call shape_at(nen, xe, xc, n, dndx, detj)
    call strain_operator(nen, dndx, b)
    npr = modes(np)
    if (npr > 0) then
      call dilatation_projection(nen, xe, npr, .false., g(1:npr, 1:2 * nen))
      call replace_dilatation(nen, xe, npr, g(1:npr, 1:2 * nen), n(1:nen), b(:, 1:2 * nen))
    end if
    eps = 0.0_dp
    do j = 1, 2 * nen
      eps = eps + b(:, j) * ue(j)
    end do
  end subroutine element_strain

  !> np when present, else 0: the kernels' optional pressure modes.
  pure integer function modes(np)
    integer, intent(in), optional :: np
    modes = 0
    if (present(np)) modes = np
  end function modes

  !> The pressure modes of the B-bar formulation of an element kind: 1 (the
  !> mean dilatation) on the 4-node quadrangle, which locks without it; 0 on
  !> the others.  The 3-node triangle's strain is constant: its mean is
  !> itself, B-bar changes nothing, and it locks still.  The quadratic
  !> elements have enough displacement modes to follow div u = 0 (within
  !> 1 % of Lame's cylinder at nu = 0.4999, doc/theory.md).
  pure integer function pressure_modes(nen) result(np)
    integer, intent(in) :: nen
    np = merge(1, 0, nen == 4) + merge(3, 0, nen >= 8)
  end function pressure_modes

  !> p(x) = (1, (x - x_c) / h, (y - y_c) / h)(1:np): the pressure modes of an
  !> element at the point x, x_c the mean of its corners and h the larger side
  !> of their bounding box (the scale keeps M well conditioned).
  !>   nen (in) 3..9;  xe (in) (2, nen) its nodes;  np (in) 1..max_np
  !>   x   (in) (2) the point;  p (out) (np)
  pure subroutine pressure_basis(nen, xe, np, x, p)
    integer, intent(in) :: nen, np
    real(dp), intent(in) :: xe(2, nen), x(2)
    real(dp), intent(out) :: p(np)
    real(dp) :: xc(2), h
    integer :: nc
    p(1) = 1.0_dp
    if (np == 1) return
    nc = corner_count(nen)
    xc = sum(xe(:, 1:nc), dim=2) / nc
    h = max(maxval(xe(1, 1:nc)) - minval(xe(1, 1:nc)), maxval(xe(2, 1:nc)) - minval(xe(2, 1:nc)))
    p(2:3) = (x - xc) / h
  end subroutine pressure_basis

  !> G (np, 2 nen) = M^-1 int p m' B dV, M = int p p' dV, on the stiffness
  !> rule: theta_bar(x) = p(x)' G u is the L2 projection of the volumetric
  !> strain onto the element's pressure modes (1: its mean, the mean
  !> dilatation).  dV = dA in the plane (the thickness cancels); radial:
  !> dV = r dA and theta includes the hoop strain u_r / r (axisymmetric_elements).
  !>   nen (in) 3..9;  xe (in) (2, nen) (r, z when radial);  np (in) 1..max_np
  !>   radial (in) axisymmetric;  g (out) (np, 2 nen)
  pure subroutine dilatation_projection(nen, xe, np, radial, g)
    integer, intent(in) :: nen, np
    real(dp), intent(in) :: xe(2, nen)
    logical, intent(in) :: radial
    real(dp), intent(out) :: g(np, 2 * nen)
    real(dp) :: xi(2, 9), w(9), n(max_nen), dndx(2, max_nen), detj, p(max_np), mm(max_np, max_np), c, r
    real(dp) :: bv(2 * max_nen)
    integer :: q, nq, a, i, j
    call stiffness_rule(nen, nq, xi, w)
    mm = 0.0_dp
    g = 0.0_dp
    do q = 1, nq
      call shape_at(nen, xe, xi(:, q), n, dndx, detj)
      c = w(q) * detj
      do a = 1, nen                              ! bv = m' B: theta = bv u
        bv(2 * a - 1) = dndx(1, a)
        bv(2 * a) = dndx(2, a)
      end do
      if (radial) then
        r = dot_product(n(1:nen), xe(1, :))
        do a = 1, nen
          bv(2 * a - 1) = bv(2 * a - 1) + n(a) / r   ! the hoop strain u_r / r
        end do
        c = c * r
      end if
      call pressure_basis(nen, xe, np, [dot_product(n(1:nen), xe(1, :)), dot_product(n(1:nen), xe(2, :))], p(1:np))
      do j = 1, np
        mm(1:np, j) = mm(1:np, j) + c * p(1:np) * p(j)
        g(j, :) = g(j, :) + (c * p(j)) * bv(1:2 * nen)
      end do
    end do
    ! G = M^-1 G by Cholesky, M (np <= 3) symmetric positive definite on a valid element
    do j = 1, np
      mm(j, j) = sqrt(mm(j, j) - dot_product(mm(j, 1:j - 1), mm(j, 1:j - 1)))
      do i = j + 1, np
        mm(i, j) = (mm(i, j) - dot_product(mm(i, 1:j - 1), mm(j, 1:j - 1))) / mm(j, j)
      end do
    end do
    do j = 1, np                                 ! L y = g
      do i = 1, j - 1
        g(j, :) = g(j, :) - mm(j, i) * g(i, :)
      end do
      g(j, :) = g(j, :) / mm(j, j)
    end do
    do j = np, 1, -1                             ! L' x = y
      do i = j + 1, np
        g(j, :) = g(j, :) - mm(i, j) * g(i, :)
      end do
      g(j, :) = g(j, :) / mm(j, j)
    end do
  end subroutine dilatation_projection

  !> B -> B_bar = B + m (p(x)' G - m' B) / k at one point (module header):
  !> the volumetric strain m' B u replaced by theta_bar(x), the deviatoric
  !> strain kept.  b has 3 rows (exx, eyy, gxy; m = (1, 1, 0), k = 2) or 4
  !> (axisymmetric, ett last; m = (1, 1, 0, 1), k = 3).
  !>   nen (in);  xe (in) (2, nen);  np (in) 1..max_np;  g (in) (np, 2 nen) from dilatation_projection
  !>   n   (in) (nen) the shape functions at the point
  !>   b   (inout) (3 or 4, 2 nen) B on entry, B_bar on exit
  pure subroutine replace_dilatation(nen, xe, np, g, n, b)
    integer, intent(in) :: nen, np
    real(dp), intent(in) :: xe(2, nen), g(np, 2 * nen), n(nen)
    real(dp), intent(inout) :: b(:,:)
    real(dp) :: p(max_np), dv
    integer :: j
    call pressure_basis(nen, xe, np, [dot_product(n, xe(1, :)), dot_product(n, xe(2, :))], p(1:np))
    if (size(b, 1) == 4) then
      do j = 1, 2 * nen
        dv = (dot_product(p(1:np), g(:, j)) - (b(1, j) + b(2, j) + b(4, j))) / 3.0_dp
        b(1, j) = b(1, j) + dv
        b(2, j) = b(2, j) + dv
        b(4, j) = b(4, j) + dv
      end do
    else
      do j = 1, 2 * nen
        dv = (dot_product(p(1:np), g(:, j)) - (b(1, j) + b(2, j))) / 2.0_dp
        b(1, j) = b(1, j) + dv
        b(2, j) = b(2, j) + dv
      end do
    end if
  end subroutine replace_dilatation

  !> Nodal forces of a constant traction t on the straight edge xa-xb (2-node
  !> line, linear shape functions): half of t |xb - xa| thick to each node.
  pure subroutine edge_load(xa, xb, t, thick, fe)
    real(dp), intent(in) :: xa(2), xb(2), t(2), thick
    real(dp), intent(out) :: fe(4)
    real(dp) :: l
    l = norm2(xb - xa)
    fe(1:2) = 0.5_dp * l * thick * t
    fe(3:4) = fe(1:2)
  end subroutine edge_load

  !> Nodal forces of a traction on the 3-node edge xe(:, 1:3) (ends 1, 2, then
  !> the middle 3): the force per unit length t + pr n_r, with n_r(s) the
  !> unit normal to the right of the edge's direction (1 -> 2) at each point
  !> of a curved edge, integrated with 3-point Gauss (exact for a constant t
  !> on a straight edge: degree 2).
  !>   xe    (in)  (2, 3) node coordinates
  !>   t     (in)  (2) constant traction, global axes
  !>   pr    (in)  normal traction along n_r (a pressure p pushing into the
  !>               body whose outward normal is n_r: pr = -p)
  !>   thick (in)  thickness
  !>   fe    (out) (6) forces on end 1, end 2, middle (x, y each)
  !>   radial (in, optional) .true.: the weight is thick r(s), r = x the radius
  !>               (axisymmetric_elements, thick = 2 pi; exact to degree 3 then)
  pure subroutine edge_load_quadratic(xe, t, pr, thick, fe, radial)
    real(dp), intent(in) :: xe(2, 3), t(2), pr, thick
    real(dp), intent(out) :: fe(6)
    logical, intent(in), optional :: radial
    real(dp), parameter :: g3(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
    real(dp), parameter :: w3(3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
    real(dp) :: s, n(3), dn(3), tang(2), f(2), w
    integer :: q, a
    logical :: by_radius
    by_radius = .false.
    if (present(radial)) by_radius = radial
    fe = 0.0_dp
    do q = 1, 3
      s = g3(q)
      n = [0.5_dp * s * (s - 1), 0.5_dp * s * (s + 1), 1 - s * s]
      dn = [s - 0.5_dp, s + 0.5_dp, -2 * s]
      tang = xe(:, 1) * dn(1) + xe(:, 2) * dn(2) + xe(:, 3) * dn(3)      ! dx/ds
      f = t * norm2(tang) + pr * [tang(2), -tang(1)]                     ! (t + pr n_r) |dx/ds|
      w = thick
      if (by_radius) w = thick * dot_product(n, xe(1, :))
      do a = 1, 3
        fe(2 * a - 1:2 * a) = fe(2 * a - 1:2 * a) + (w3(q) * w * n(a)) * f
      end do
    end do
  end subroutine edge_load_quadratic

end module elements
