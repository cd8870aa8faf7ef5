!> axisymmetric_elements: the element kernels of axisymmetric elasticity
!> (PLANE axisymmetric) for every element of module elements (P1, Q1, P2, Q8,
!> Q9), on the same shape functions and rules.
!>
!> Coordinates x = (r, z), r >= 0; displacement (u_r, u_z) independent of the
!> angle theta.  Strain in the order (err, ezz, grz, ett):
!>     err = du_r/dr,  ezz = du_z/dz,  grz = du_r/dz + du_z/dr,  ett = u_r / r,
!> eps = B4 u, B4 the plane strain operator B with the hoop row N_a / r on the
!> u_r dofs.  Every integral is over the solid of revolution, dV = 2 pi r dA
!> and dS = 2 pi r ds: stiffness, nodal forces and reactions are those of the
!> full circle (doc/theory.md, "Axisymmetric analysis").
!>
!> Rules.  The stiffness rule of module elements (stiffness_rule): its points
!> are inside the element, never on the axis, so u_r / r is finite at each of
!> them; the element passes the patch test (the rule integrates d(r N_a)/dr
!> exactly on straight-sided elements).  Loads per unit volume take the richer
!> rule (quadrature_rule order 2: N r of degree 2 on P1, exact); loads per
!> unit area on a straight 2-node edge are integrated in closed form
!> (N_a r is quadratic in the arc length), on a 3-node edge by 3-point Gauss.
!>
!> B-bar: with np > 0 pressure modes (elements' pressure_modes) B4 becomes
!> B4_bar, the volumetric strain err + ezz + ett (the hoop strain included)
!> replaced by its projection weighted by r (elements' replace_dilatation);
!> the optional argument np of the kernels selects it.
!>
!> Programming interface
!>   radial_weight(r)                          2 pi r, the measure of the full circle
!>   axi_element_stiffness(nen, xe, d4, ke [, np])   ke = int B4' D4 B4 2 pi r dA
!>   axi_element_force(nen, xe, d4, ue, fe [, np])   fe = ke ue, without ke
!>   axi_element_body_load(nen, xe, b, fe)     fe = int N' b 2 pi r dA (constant b)
!>   axi_thermal_load(nen, xe, s0, fe)         fe = int B4' s0 2 pi r dA (constant stress s0)
!>   axi_element_strain(nen, xe, ue, eps4 [, np])    (err, ezz, grz, ett) at the element centre
!>   axi_edge_load(xa, xb, t, fe)              fe(4) = int N' t 2 pi r ds on the edge xa-xb
!>   axi_edge_load_quadratic(xe, t, pr, fe)    as elements' edge_load_quadratic, 2 pi r ds
module axisymmetric_elements
  use kinds, only: dp
  use elements, only: shape_at, stiffness_rule, quadrature_rule, corner_count, max_nen, strain_operator, &
                      edge_load_quadratic, max_np, dilatation_projection, replace_dilatation
  implicit none
  private
  public :: radial_weight, axi_element_stiffness, axi_element_force, axi_element_body_load, axi_thermal_load
  public :: axi_element_strain, axi_edge_load, axi_edge_load_quadratic

  real(dp), parameter :: two_pi = 2.0_dp * acos(-1.0_dp)

contains

  !> 2 pi r: the length of the circle of radius r, the weight that turns an
  !> integral over the r-z section into one over the solid of revolution.
  pure elemental real(dp) function radial_weight(r) result(w)
    real(dp), intent(in) :: r
    w = two_pi * r
  end function radial_weight

  !> B4(4, 2 nen) at one point: elements' plane strain operator B and the hoop
  !> row N_a / r on the u_r dofs.
  !>   n (in) (nen) shape functions;  dndx (in) (2, nen) gradients;  r (in) > 0 the radius
  pure subroutine axi_strain_operator(nen, n, dndx, r, b)
    integer, intent(in) :: nen
    real(dp), intent(in) :: n(nen), dndx(2, nen), r
    real(dp), intent(out) :: b(4, 2 * nen)
    real(dp) :: b3(3, 2 * max_nen)
    integer :: a
    call strain_operator(nen, dndx, b3(:, 1:2 * nen))
    b(1:3, :) = b3(:, 1:2 * nen)
    b(4, :) = 0.0_dp
    do a = 1, nen
      b(4, 2 * a - 1) = n(a) / r
    end do
  end subroutine axi_strain_operator

  !> Element stiffness ke(1:2 nen, 1:2 nen) = sum_q w_q detJ_q 2 pi r_q B4' D4 B4.
  !>   nen (in) 3, 4, 6, 8 or 9;  xe (in) (2, nen) nodes (r, z);  d4 (in) (4, 4) the law
  !>   ke  (inout) at least (2 nen, 2 nen); the leading block is overwritten
  !>   np  (in, optional) > 0: B4_bar with np pressure modes; 0 or absent: B4
  pure subroutine axi_element_stiffness(nen, xe, d4, ke, np)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), d4(4, 4)
    real(dp), intent(inout) :: ke(:,:)
    integer, intent(in), optional :: np
    real(dp) :: xi(2, 9), w(9), n(max_nen), dndx(2, max_nen), detj, b(4, 2 * max_nen), db(4, 2 * max_nen), c, r
    real(dp) :: g(max_np, 2 * max_nen)
    integer :: q, nq, m, i, j, npr
    m = 2 * nen
    npr = 0
    if (present(np)) npr = np
    call stiffness_rule(nen, nq, xi, w)
    if (npr > 0) call dilatation_projection(nen, xe, npr, .true., g(1:npr, 1:m))
    ke(1:m, 1:m) = 0.0_dp
    do q = 1, nq
      call shape_at(nen, xe, xi(:, q), n(1:nen), dndx(:, 1:nen), detj)
      r = dot_product(n(1:nen), xe(1, :))
      call axi_strain_operator(nen, n(1:nen), dndx(:, 1:nen), r, b(:, 1:m))
      if (npr > 0) call replace_dilatation(nen, xe, npr, g(1:npr, 1:m), n(1:nen), b(:, 1:m))
      c = w(q) * detj * radial_weight(r)
      do j = 1, m                  ! db = D4 B4, ke += c B4' D4 B4
        db(:, j) = matmul(d4, b(:, j))
        do i = 1, m
          ke(i, j) = ke(i, j) + c * dot_product(b(:, i), db(:, j))
        end do
      end do
    end do
  end subroutine axi_element_stiffness

  !> Element forces fe = ke ue = sum_q w_q detJ_q 2 pi r_q B4' D4 B4 ue, without ke.
  !>   np (in, optional) as axi_element_stiffness
  pure subroutine axi_element_force(nen, xe, d4, ue, fe, np)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), d4(4, 4), ue(2 * nen)
    real(dp), intent(out) :: fe(2 * nen)
    integer, intent(in), optional :: np
    integer :: npr
    npr = 0
    if (present(np)) npr = np
    call stress_forces(nen, xe, d4, ue, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], npr, fe)
  end subroutine axi_element_force

  !> fe = sum_q w_q detJ_q 2 pi r_q B4' (D4 B4 ue + s0): the nodal forces of the
  !> stress of ue plus a constant stress s0, on the stiffness rule; B4_bar
  !> with np > 0 pressure modes (a constant s0 gives the same forces with
  !> either: int (B4_bar - B4) dV s0 = 0, the projection keeps constants).
  pure subroutine stress_forces(nen, xe, d4, ue, s0, np, fe)
    integer, intent(in) :: nen, np
    real(dp), intent(in) :: xe(2, nen), d4(4, 4), ue(2 * nen), s0(4)
    real(dp), intent(out) :: fe(2 * nen)
    real(dp) :: xi(2, 9), w(9), n(max_nen), dndx(2, max_nen), detj, b(4, 2 * max_nen), sig(4), r
    real(dp) :: g(max_np, 2 * max_nen)
    integer :: q, nq, m
    m = 2 * nen
    call stiffness_rule(nen, nq, xi, w)
    if (np > 0) call dilatation_projection(nen, xe, np, .true., g(1:np, 1:m))
    fe = 0.0_dp
    do q = 1, nq
      call shape_at(nen, xe, xi(:, q), n(1:nen), dndx(:, 1:nen), detj)
      r = dot_product(n(1:nen), xe(1, :))
      call axi_strain_operator(nen, n(1:nen), dndx(:, 1:nen), r, b(:, 1:m))
      if (np > 0) call replace_dilatation(nen, xe, np, g(1:np, 1:m), n(1:nen), b(:, 1:m))
      sig = matmul(d4, matmul(b(:, 1:m), ue)) + s0
      fe = fe + (w(q) * detj * radial_weight(r)) * matmul(sig, b(:, 1:m))
    end do
  end subroutine stress_forces

  !> Nodal forces of a constant body force b (per unit volume), int N' b 2 pi r dA.
  pure subroutine axi_element_body_load(nen, xe, bf, fe)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), bf(2)
    real(dp), intent(out) :: fe(2 * nen)
    real(dp), allocatable :: xi(:,:), w(:)
    real(dp) :: n(max_nen), dndx(2, max_nen), detj, c
    integer :: q, a
    call quadrature_rule(nen, 2, xi, w)
    fe = 0.0_dp
    do q = 1, size(w)
      call shape_at(nen, xe, xi(:, q), n(1:nen), dndx(:, 1:nen), detj)
      c = w(q) * detj * radial_weight(dot_product(n(1:nen), xe(1, :)))
      do a = 1, nen
        fe(2 * a - 1:2 * a) = fe(2 * a - 1:2 * a) + (c * n(a)) * bf
      end do
    end do
  end subroutine axi_element_body_load

  !> Nodal forces int B4' s0 2 pi r dA of a constant initial stress s0 (4)
  !> (a thermal strain eps0: s0 = D4 eps0), on the stiffness rule.
  pure subroutine axi_thermal_load(nen, xe, s0, fe)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), s0(4)
    real(dp), intent(out) :: fe(2 * nen)
    real(dp) :: ue(2 * max_nen), d0(4, 4)
    ue = 0.0_dp                                      ! no displacement: the stress is s0
    d0 = 0.0_dp
    call stress_forces(nen, xe, d0, ue(1:2 * nen), s0, 0, fe)
  end subroutine axi_thermal_load

  !> Strain (err, ezz, grz, ett) at the element centre (reference centroid),
  !> the element's stress for output.
  !>   np (in, optional) as axi_element_stiffness: the B4_bar strain
  pure subroutine axi_element_strain(nen, xe, ue, eps4, np)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen)
    real(dp), intent(out) :: eps4(4)
    integer, intent(in), optional :: np
    real(dp) :: n(max_nen), dndx(2, max_nen), detj, b(4, 2 * max_nen), xc(2), g(max_np, 2 * max_nen)
    if (corner_count(nen) == 3) then
      xc = [1.0_dp, 1.0_dp] / 3.0_dp
    else
      xc = 0.0_dp
    end if
    call shape_at(nen, xe, xc, n(1:nen), dndx(:, 1:nen), detj)
    call axi_strain_operator(nen, n(1:nen), dndx(:, 1:nen), dot_product(n(1:nen), xe(1, :)), b(:, 1:2 * nen))
    if (present(np)) then
      if (np > 0) then
        call dilatation_projection(nen, xe, np, .true., g(1:np, 1:2 * nen))
        call replace_dilatation(nen, xe, np, g(1:np, 1:2 * nen), n(1:nen), b(:, 1:2 * nen))
      end if
    end if
    eps4 = matmul(b(:, 1:2 * nen), ue)
  end subroutine axi_element_strain

  !> Nodal forces of a constant traction t (per unit area) on the straight
  !> edge xa-xb of the section, int N_a t 2 pi r ds in closed form: with r
  !> linear along the edge, int N_a r ds = L (2 r_a + r_b) / 6.
  pure subroutine axi_edge_load(xa, xb, t, fe)
    real(dp), intent(in) :: xa(2), xb(2), t(2)
    real(dp), intent(out) :: fe(4)
    real(dp) :: l
    l = norm2(xb - xa)
    fe(1:2) = (radial_weight(l * (2.0_dp * xa(1) + xb(1)) / 6.0_dp)) * t
    fe(3:4) = (radial_weight(l * (xa(1) + 2.0_dp * xb(1)) / 6.0_dp)) * t
  end subroutine axi_edge_load

  !> Nodal forces of a traction per unit area t + pr n_r on the 3-node edge
  !> xe(:, 1:3) (ends, then middle), 3-point Gauss with the weight 2 pi r(s)
  !> (exact for a constant t on a straight edge: degree 3); arguments as
  !> elements' edge_load_quadratic without the thickness.
  pure subroutine axi_edge_load_quadratic(xe, t, pr, fe)
    real(dp), intent(in) :: xe(2, 3), t(2), pr
    real(dp), intent(out) :: fe(6)
    call edge_load_quadratic(xe, t, pr, two_pi, fe, radial=.true.)
  end subroutine axi_edge_load_quadratic

end module axisymmetric_elements
