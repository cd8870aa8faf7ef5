!> elements: pure element kernels of plane elasticity for the P1 triangle (the
!> paper's element, eq. (7)) and the Q1 quadrilateral.
!>
!> Element nodes xe(2, nen), counter-clockwise; element dofs ordered
!> (u1x, u1y, u2x, u2y, ...).  Strain eps = B u in Voigt form (exx, eyy, gxy).
!>
!> Programming interface
!>   quadrature_rule(nen, order, xi, w)    points xi(2, nq) and weights w(nq) on the
!>        reference element: order 1 (P1: 1 point; Q1: 2x2 Gauss) or 2 (P1:
!>        3-point degree-2 rule; Q1: 3x3 Gauss), for loads and error integrals
!>   shape_at(nen, xe, xi, n, dndx, detj)  shape functions, their x-y gradients
!>        and the Jacobian determinant at a reference point
!>   element_stiffness(nen, xe, d, thick, ke)    ke = int B' D B t dA
!>   element_force(nen, xe, d, thick, ue, fe)    fe = ke ue, without ke
!>   element_body_load(nen, xe, b, thick, fe)    fe = int N' b t dA (constant b)
!>   element_strain(nen, xe, ue, eps)            strain at the element centre
!>   edge_load(xa, xb, t, thick, fe)             fe(4) = int N' t t_h ds, constant
!>        traction t on the straight edge xa-xb
module elements
  use kinds, only: dp
  implicit none
  private
  public :: quadrature_rule, shape_at, element_stiffness, element_force, element_body_load, element_strain
  public :: edge_load, strain_operator

  !> The most nodes of an element (Q1).  The kernels run once per element:
  !> their work arrays have this fixed size, not nen, because gfortran puts
  !> arrays of run-time size on the heap (a malloc and free per call, and
  !> a lock shared with every thread that allocates meanwhile).
  integer, parameter :: max_nen = 4

contains

  !> Quadrature on the reference triangle (0,0),(1,0),(0,1) or square [-1,1]^2.
  !>   nen   (in)  3 or 4
  !>   order (in)  1: exact for the stiffness; 2: one degree more, for loads/errors
  !>   xi    (out) (2, nq) points
  !>   w     (out) (nq) weights (sum: 1/2 for the triangle, 4 for the square)
  pure subroutine quadrature_rule(nen, order, xi, w)
    integer, intent(in) :: nen, order
    real(dp), allocatable, intent(out) :: xi(:,:), w(:)
    real(dp), parameter :: g2 = 1.0_dp / sqrt(3.0_dp), g3 = sqrt(0.6_dp)
    real(dp) :: p(3), pw(3)
    integer :: i, j, k, m
    if (nen == 3) then
      if (order <= 1) then
        allocate(xi(2, 1), w(1))
        xi(:, 1) = [1.0_dp, 1.0_dp] / 3.0_dp
        w = 0.5_dp
      else
        allocate(xi(2, 3), w(3))
        xi(:, 1) = [1.0_dp / 6.0_dp, 1.0_dp / 6.0_dp]
        xi(:, 2) = [2.0_dp / 3.0_dp, 1.0_dp / 6.0_dp]
        xi(:, 3) = [1.0_dp / 6.0_dp, 2.0_dp / 3.0_dp]
        w = 1.0_dp / 6.0_dp
      end if
    else
      if (order <= 1) then
        m = 2
        p(1:2) = [-g2, g2]
        pw(1:2) = 1.0_dp
      else
        m = 3
        p = [-g3, 0.0_dp, g3]
        pw = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
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

  !> Shape functions and x-y derivatives at reference point xi.
  !>   nen  (in)  3 or 4
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
    if (nen == 3) then
      n = [1.0_dp - xi(1) - xi(2), xi(1), xi(2)]
      dndxi(:, 1) = [-1.0_dp, -1.0_dp]
      dndxi(:, 2) = [1.0_dp, 0.0_dp]
      dndxi(:, 3) = [0.0_dp, 1.0_dp]
    else
      n = 0.25_dp * [(1 - xi(1)) * (1 - xi(2)), (1 + xi(1)) * (1 - xi(2)), &
                     (1 + xi(1)) * (1 + xi(2)), (1 - xi(1)) * (1 + xi(2))]
      dndxi(:, 1) = 0.25_dp * [-(1 - xi(2)), -(1 - xi(1))]
      dndxi(:, 2) = 0.25_dp * [(1 - xi(2)), -(1 + xi(1))]
      dndxi(:, 3) = 0.25_dp * [(1 + xi(2)), (1 + xi(1))]
      dndxi(:, 4) = 0.25_dp * [-(1 + xi(2)), (1 - xi(1))]
    end if
    ! jac(i,j) = d x_i / d xi_j, and dN/dx = J^-T dN/dxi, written out: no
    ! array temporary of run-time size (see max_nen)
    jac = 0.0_dp
    do a = 1, nen
      jac(:, 1) = jac(:, 1) + xe(:, a) * dndxi(1, a)
      jac(:, 2) = jac(:, 2) + xe(:, a) * dndxi(2, a)
    end do
    detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    jinv(1, 1) = jac(2, 2) / detj
    jinv(2, 2) = jac(1, 1) / detj
    jinv(1, 2) = -jac(1, 2) / detj
    jinv(2, 1) = -jac(2, 1) / detj
    do a = 1, nen
      dndx(1, a) = jinv(1, 1) * dndxi(1, a) + jinv(2, 1) * dndxi(2, a)
      dndx(2, a) = jinv(1, 2) * dndxi(1, a) + jinv(2, 2) * dndxi(2, a)
    end do
  end subroutine shape_at

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
  !>   nq (out) 1 (P1) or 4 (Q1); xi(:, 1:nq), w(1:nq) as quadrature_rule
  pure subroutine stiffness_rule(nen, nq, xi, w)
    integer, intent(in) :: nen
    integer, intent(out) :: nq
    real(dp), intent(out) :: xi(2, 4), w(4)
    real(dp), parameter :: g = 1.0_dp / sqrt(3.0_dp)
    if (nen == 3) then
      nq = 1
      xi(:, 1) = [1.0_dp, 1.0_dp] / 3.0_dp
      w(1) = 0.5_dp
    else
      nq = 4
      xi = reshape([-g, -g, g, -g, -g, g, g, g], [2, 4])
      w = 1.0_dp
    end if
  end subroutine stiffness_rule

  !> Element stiffness ke = sum_q w_q detJ_q t B_q' D B_q (exact: 1 point for P1,
  !> 2x2 Gauss for Q1), in ke(1:2 nen, 1:2 nen) (ke may be larger: 8 x 8 for
  !> either element).
  pure subroutine element_stiffness(nen, xe, d, thick, ke)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), d(3, 3), thick
    real(dp), intent(inout) :: ke(:,:)
    real(dp) :: xi(2, 4), w(4), n(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen), db(3, 2 * max_nen), c
    integer :: q, nq, m, i, j
    m = 2 * nen
    call stiffness_rule(nen, nq, xi, w)
    ke(1:m, 1:m) = 0.0_dp
    do q = 1, nq
      call shape_at(nen, xe, xi(:, q), n, dndx, detj)
      call strain_operator(nen, dndx, b)
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
  pure subroutine element_force(nen, xe, d, thick, ue, fe)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), d(3, 3), thick, ue(2 * nen)
    real(dp), intent(out) :: fe(2 * nen)
    real(dp) :: xi(2, 4), w(4), n(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen), eps(3), sig(3), c
    integer :: q, nq, j
    call stiffness_rule(nen, nq, xi, w)
    fe = 0.0_dp
    do q = 1, nq
      call shape_at(nen, xe, xi(:, q), n, dndx, detj)
      call strain_operator(nen, dndx, b)
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

  !> Strain at the element centre (exact for P1; the centre value for Q1).
  pure subroutine element_strain(nen, xe, ue, eps)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen)
    real(dp), intent(out) :: eps(3)
    real(dp) :: n(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen), xc(2)
    integer :: j
    if (nen == 3) then
      xc = [1.0_dp, 1.0_dp] / 3.0_dp
    else
      xc = 0.0_dp
    end if
    call shape_at(nen, xe, xc, n, dndx, detj)
    call strain_operator(nen, dndx, b)
    eps = 0.0_dp
    do j = 1, 2 * nen
      eps = eps + b(:, j) * ue(j)
    end do
  end subroutine element_strain

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

end module elements
