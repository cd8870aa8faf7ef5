!> finite_strain_elements: the total Lagrangian kernels of a hyperelastic
!> element (module hyperelastic's law) in plane strain and axisymmetry, on the
!> shape functions and stiffness rules of module elements (P1, Q1, P2, Q8, Q9;
!> doc/theory.md, "Finite strain").
!>
!> On the reference configuration X (the mesh) with displacement u = sum N_a u_a:
!>     F = I + grad_X u (in-plane),  F33 = 1 (plane strain) or 1 + u_r / R (axisymmetric),
!>     f_int,a = int P : dF/du_a dV0,   K_ab = int (dF/du_a) : A : (dF/du_b) dV0,
!> P the first Piola-Kirchhoff stress, A = dP/dF, dV0 = t dA (plane strain, t
!> the thickness) or 2 pi R dA (axisymmetric: the full circle, as module
!> axisymmetric_elements).  dF/du is the operator G (5, 2 nen) on the reduced
!> components (11, 12, 21, 22, 33) of module hyperelastic: column 2a - 1 (u_x
!> of node a) is (dN_a/dX, dN_a/dY, 0, 0, N_a / R), the last entry in
!> axisymmetry only; column 2a is (0, 0, dN_a/dX, dN_a/dY, 0).  K is the
!> consistent tangent of f_int: the material and the geometric (initial
!> stress) stiffness together, symmetric.
!>
!> The rules are the stiffness rules (elements' stiffness_rule), whose points
!> are inside the element (R > 0 in axisymmetry).  A point where J = det F <= 0
!> makes the kernel return info = the point's number: the caller cuts the
!> load step.
!>
!> Programming interface
!>   finite_strain_response(nen, xe, ue, law, axisymmetric, thick, fe, ke, info)
!>        fe = f_int(ue) (2 nen) and, when present, ke = K(ue) (2 nen, 2 nen)
!>   finite_strain_energy(nen, xe, ue, law, axisymmetric, thick, energy, info)
!>        int W dV0, the potential whose gradient is f_int
!>   finite_strain_state(nen, xe, ue, law, axisymmetric, sig4, jac, stretch, info)
!>        at the element centre: Cauchy stress (xx, yy, xy, zz), J, the largest stretch
!>   deformation_gradient(nen, n, dndx, r, axisymmetric, ue, f)   F at one point
module finite_strain_elements
  use kinds, only: dp
  use elements, only: shape_at, stiffness_rule, max_nen, reference_node, corner_count
  use axisymmetric_elements, only: radial_weight
  use hyperelastic, only: hyperelastic_t, strain_energy, first_piola, cauchy_stress, largest_stretch
  implicit none
  private
  public :: finite_strain_response, finite_strain_energy, finite_strain_state, deformation_gradient

contains

  !> F at one point: I + sum_a u_a (x) grad N_a in the plane, F33 = 1 or 1 + u_r / R.
  !>   nen  (in)  3, 4, 6, 8 or 9
  !>   n    (in)  (nen) shape functions at the point
  !>   dndx (in)  (2, nen) their gradients in the reference configuration
  !>   r    (in)  the point's reference radius X (> 0; axisymmetric only)
  !>   ue   (in)  (2 nen) nodal displacements (u1x, u1y, u2x, ...)
  !>   f    (out) (3, 3) the deformation gradient
  pure subroutine deformation_gradient(nen, n, dndx, r, axisymmetric, ue, f)
    integer, intent(in) :: nen
    real(dp), intent(in) :: n(nen), dndx(2, nen), r, ue(2 * nen)
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: f(3, 3)
    integer :: a
    f = 0.0_dp
    f(1, 1) = 1.0_dp
    f(2, 2) = 1.0_dp
    f(3, 3) = 1.0_dp
    do a = 1, nen
      f(1, 1:2) = f(1, 1:2) + ue(2 * a - 1) * dndx(:, a)       ! F_iJ += u_a,i dN_a/dX_J
      f(2, 1:2) = f(2, 1:2) + ue(2 * a) * dndx(:, a)
      if (axisymmetric) f(3, 3) = f(3, 3) + ue(2 * a - 1) * n(a) / r
    end do
  end subroutine deformation_gradient

  !> The gradient operator G (5, 2 nen) of the module header at one point.
  pure subroutine gradient_operator(nen, n, dndx, r, axisymmetric, g)
    integer, intent(in) :: nen
    real(dp), intent(in) :: n(nen), dndx(2, nen), r
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: g(5, 2 * nen)
    integer :: a
    g = 0.0_dp
    do a = 1, nen
      g(1:2, 2 * a - 1) = dndx(:, a)
      g(3:4, 2 * a) = dndx(:, a)
      if (axisymmetric) g(5, 2 * a - 1) = n(a) / r
    end do
  end subroutine gradient_operator

  !> The point's shape functions, gradients, radius and weight w_q detJ dV0.
  pure subroutine point_geometry(nen, xe, xi, w, axisymmetric, thick, n, dndx, r, dv)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), xi(2), w, thick
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: n(nen), dndx(2, nen), r, dv
    real(dp) :: detj
    call shape_at(nen, xe, xi, n, dndx, detj)
    r = dot_product(n, xe(1, :))
    if (axisymmetric) then
      dv = w * detj * radial_weight(r)
    else
      dv = w * detj * thick
    end if
  end subroutine point_geometry

  !> Internal forces and consistent tangent of one element.
  !>   nen          (in)  3, 4, 6, 8 or 9
  !>   xe           (in)  (2, nen) reference node coordinates (x, y) or (r, z)
  !>   ue           (in)  (2 nen) nodal displacements
  !>   law          (in)  the hyperelastic law
  !>   axisymmetric (in)  .true.: F33 = 1 + u_r / R and dV0 = 2 pi R dA
  !>   thick        (in)  thickness (plane strain; ignored in axisymmetry)
  !>   fe           (out) (2 nen) f_int
  !>   ke           (out, optional) at least (2 nen, 2 nen): its leading block is K
  !>   info         (out) 0; q > 0 when J <= 0 at point q (fe, ke incomplete)
  pure subroutine finite_strain_response(nen, xe, ue, law, axisymmetric, thick, fe, ke, info)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), thick
    type(hyperelastic_t), intent(in) :: law
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: fe(2 * nen)
    real(dp), intent(inout), optional :: ke(:,:)
    integer, intent(out) :: info
    real(dp) :: xi(2, 9), w(9), n(max_nen), dndx(2, max_nen), r, dv, f(3, 3), p5(5), a5(5, 5)
    real(dp) :: g(5, 2 * max_nen), ag(5, 2 * max_nen)
    integer :: q, nq, m, j, k

    m = 2 * nen
    call stiffness_rule(nen, nq, xi, w)
    fe = 0.0_dp
    if (present(ke)) ke(1:m, 1:m) = 0.0_dp
    info = 0
    do q = 1, nq
      call point_geometry(nen, xe, xi(:, q), w(q), axisymmetric, thick, n(1:nen), dndx(:, 1:nen), r, dv)
      call deformation_gradient(nen, n(1:nen), dndx(:, 1:nen), r, axisymmetric, ue, f)
      call first_piola(law, f, p5, a5, k)
      if (k /= 0) then
        info = q
        return
      end if
      call gradient_operator(nen, n(1:nen), dndx(:, 1:nen), r, axisymmetric, g(:, 1:m))
      do j = 1, m                                    ! f_int += G' P dV0
        fe(j) = fe(j) + dv * dot_product(g(:, j), p5)
      end do
      if (.not. present(ke)) cycle
      ag(:, 1:m) = matmul(a5, g(:, 1:m))
      do j = 1, m                                    ! K += G' A G dV0
        do k = 1, m
          ke(k, j) = ke(k, j) + dv * dot_product(g(:, k), ag(:, j))
        end do
      end do
    end do
  end subroutine finite_strain_response

  !> The element's strain energy int W dV0 on the same rule (f_int is its
  !> gradient in ue).
  !>   energy (out) the energy (0 when info /= 0)
  !>   info   (out) 0; q > 0 when J <= 0 at point q
  pure subroutine finite_strain_energy(nen, xe, ue, law, axisymmetric, thick, energy, info)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), thick
    type(hyperelastic_t), intent(in) :: law
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: energy
    integer, intent(out) :: info
    real(dp) :: xi(2, 9), w(9), n(max_nen), dndx(2, max_nen), r, dv, f(3, 3), wq
    integer :: q, nq
    call stiffness_rule(nen, nq, xi, w)
    energy = 0.0_dp
    info = 0
    do q = 1, nq
      call point_geometry(nen, xe, xi(:, q), w(q), axisymmetric, thick, n(1:nen), dndx(:, 1:nen), r, dv)
      call deformation_gradient(nen, n(1:nen), dndx(:, 1:nen), r, axisymmetric, ue, f)
      wq = strain_energy(law, f)
      if (wq == huge(1.0_dp)) then
        info = q
        energy = 0.0_dp
        return
      end if
      energy = energy + dv * wq
    end do
  end subroutine finite_strain_energy

  !> The element's state for output, at its reference centre (the centroid of
  !> its corners' reference element: (1/3, 1/3) or (0, 0)).
  !>   sig4    (out) Cauchy stress (xx, yy, xy, zz); axisymmetric (rr, zz, rz, tt)
  !>   jac     (out) J = det F
  !>   stretch (out) the largest principal stretch
  !>   info    (out) 0; 1 when J <= 0 there (sig4 zero)
  pure subroutine finite_strain_state(nen, xe, ue, law, axisymmetric, sig4, jac, stretch, info)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen)
    type(hyperelastic_t), intent(in) :: law
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: sig4(4), jac, stretch
    integer, intent(out) :: info
    real(dp) :: xi(2), n(max_nen), dndx(2, max_nen), r, dv, f(3, 3)
    integer :: a, nc
    nc = corner_count(nen)
    xi = 0.0_dp
    do a = 1, nc
      xi = xi + reference_node(nen, a) / nc
    end do
    call point_geometry(nen, xe, xi, 1.0_dp, axisymmetric, 1.0_dp, n(1:nen), dndx(:, 1:nen), r, dv)
    call deformation_gradient(nen, n(1:nen), dndx(:, 1:nen), r, axisymmetric, ue, f)
    jac = (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) * f(3, 3)
    stretch = largest_stretch(f)
    call cauchy_stress(law, f, sig4, info)
  end subroutine finite_strain_state

end module finite_strain_elements
