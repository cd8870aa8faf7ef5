!> error_estimate: an a posteriori estimate of the energy-norm error of the
!> displacement, by stress recovery (Zienkiewicz and Zhu, Int. J. Numer.
!> Meth. Engng 24, 1987), element by element.
!>
!> The finite element stress sigma_h = D eps(u_h) jumps between elements; the
!> exact stress is continuous.  A continuous stress sigma* recovered from
!> sigma_h is much closer to the exact one than sigma_h is, so the energy
!> norm of their difference estimates the error:
!>     eta_K^2 = int_K (sigma* - sigma_h) : D^-1 (sigma* - sigma_h) dV,
!>     ||u - u_h||_E^2 ~ eta^2 = sum_K eta_K^2,
!> dV = t dA in the plane, 2 pi r dA in axisymmetry.  sigma* is the element
!> stresses at each node averaged over the elements around it (weighted by
!> their areas), interpolated by the element's own shape functions: for P1
!> and Q1 the nodal average of a stress constant or nearly so per element,
!> which is superconvergent at the nodes of a regular mesh; for the quadratic
!> elements the same average at every node, mid-side nodes included.  The
!> estimate is asymptotically exact where sigma* converges faster than
!> sigma_h, and is a heuristic, not a bound, near corner singularities and
!> on boundaries, where the average is one-sided (doc/theory.md, "Error
!> estimate", with the effectivities measured).
!>
!> Each body is recovered on its own: a contact interface is a boundary of
!> both bodies, whose stresses are not averaged across it.
!>
!> Programming interface
!>   recover_stress(bd, u, sstar)          sstar(ncomp, nnode): the recovered nodal stresses of body bd
!>   energy_indicators(bd, u, sstar, eta2, energy2)
!>                                         eta2(nelem) = eta_K^2 and energy2 = ||u_h||_E^2 of bd
!>   point_stress(bd, e, xi, u, sig, dv)   sigma_h at the reference point xi of element e, and
!>                                         the volume factor dV / (dxi) there
!> u is the body's nodal displacement u(2, nnode) in x, y components; ncomp
!> is 3 (sxx, syy, sxy) in the plane, 4 (srr, szz, srz, stt) in axisymmetry.
module error_estimate
  use kinds, only: dp
  use body, only: body_t, axi_thermal_strain
  use elements, only: quadrature_rule, shape_at, strain_operator, max_nen, reference_node
  use axisymmetric_elements, only: axi_point_strain, radial_weight
  use lapack_interfaces, only: dpotrf, dpotri
  implicit none
  private
  public :: recover_stress, energy_indicators, point_stress

  !> The quadrature rule of each element size nen (3, 4, 6, 8, 9), made
  !> once per body rather than once per element.
  type :: rules_t
    integer :: nq(max_nen) = 0
    real(dp) :: xi(2, 16, max_nen) = 0.0_dp, w(16, max_nen) = 0.0_dp
  end type rules_t

contains

  !> rules: quadrature_rule(nen, order) for every element size.
  subroutine make_rules(order, rules)
    integer, intent(in) :: order
    type(rules_t), intent(out) :: rules
    real(dp), allocatable :: xi(:,:), w(:)
    integer :: k
    integer, parameter :: sizes(5) = [3, 4, 6, 8, 9]
    do k = 1, size(sizes)
      call quadrature_rule(sizes(k), order, xi, w)
      rules%nq(sizes(k)) = size(w)
      rules%xi(:, 1:size(w), sizes(k)) = xi
      rules%w(1:size(w), sizes(k)) = w
    end do
  end subroutine make_rules

  !> sigma_h(xi) = D (eps(u_h) - alpha dT eps_th) on element e of bd, and
  !> dv = detJ t (plane) or detJ 2 pi r (axisymmetric) at xi.
  !>   bd  (in)  the body;  e (in) its element;  xi (in) (2) reference point
  !>   u   (in)  (2, nnode) the body's displacement, x, y components
  !>   sig (out) (ncomp) the stress;  dv (out) the volume factor
  pure subroutine point_stress(bd, e, xi, u, sig, dv)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    real(dp), intent(in) :: xi(2), u(:,:)
    real(dp), intent(out) :: sig(:), dv
    real(dp) :: xe(2, max_nen), ue(2 * max_nen), n(max_nen), dndx(2, max_nen), detj, b(3, 2 * max_nen)
    real(dp) :: eps(3), eps4(4)
    integer :: nen, a
    nen = bd%mesh%nen(e)
    do a = 1, nen
      xe(:, a) = bd%mesh%x(:, bd%mesh%conn(a, e))
      ue(2 * a - 1:2 * a) = u(:, bd%mesh%conn(a, e))
    end do
    call shape_at(nen, xe(:, 1:nen), xi, n(1:nen), dndx(:, 1:nen), detj)
    if (bd%axisymmetric) then
      call axi_point_strain(nen, xe(:, 1:nen), xi, ue(1:2 * nen), eps4)
      if (allocated(bd%adt)) eps4 = eps4 - bd%adt(e) * axi_thermal_strain
      sig(1:4) = matmul(bd%law%d4, eps4)
      dv = detj * radial_weight(dot_product(n(1:nen), xe(1, 1:nen)))
    else
      call strain_operator(nen, dndx(:, 1:nen), b(:, 1:2 * nen))
      eps = matmul(b(:, 1:2 * nen), ue(1:2 * nen))
      if (allocated(bd%adt)) eps = eps - bd%adt(e) * bd%law%eth
      sig(1:3) = matmul(bd%law%d, eps)
      dv = detj * bd%thick
    end if
  end subroutine point_stress

  !> sigma*(node a) = sum_K |K| sigma_h|_K(x_a) / sum_K |K| over the elements
  !> K of bd around node a, |K| the element's area.
  !>   bd (in) the body;  u (in) (2, nnode) its displacement, x, y
  !>   sstar (out) (ncomp, nnode) the recovered nodal stresses
  subroutine recover_stress(bd, u, sstar)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:)
    real(dp), allocatable, intent(out) :: sstar(:,:)
    real(dp), allocatable :: weight(:)
    type(rules_t) :: rules
    real(dp) :: sig(4), dv, area, n(max_nen), dndx(2, max_nen), detj, xe(2, max_nen)
    integer :: e, a, q, nen, nc
    nc = merge(4, 3, bd%axisymmetric)
    call make_rules(1, rules)
    allocate(sstar(nc, bd%mesh%nnode), source=0.0_dp)
    allocate(weight(bd%mesh%nnode), source=0.0_dp)
    do e = 1, bd%mesh%nelem
      nen = bd%mesh%nen(e)
      xe(:, 1:nen) = bd%mesh%x(:, bd%mesh%conn(1:nen, e))
      area = 0.0_dp
      associate (xi => rules%xi(:, :, nen), w => rules%w(:, nen))
        do q = 1, rules%nq(nen)
          call shape_at(nen, xe(:, 1:nen), xi(:, q), n(1:nen), dndx(:, 1:nen), detj)
          area = area + w(q) * detj
        end do
      end associate
      do a = 1, nen
        call point_stress(bd, e, reference_node(nen, a), u, sig(1:nc), dv)
        sstar(:, bd%mesh%conn(a, e)) = sstar(:, bd%mesh%conn(a, e)) + area * sig(1:nc)
        weight(bd%mesh%conn(a, e)) = weight(bd%mesh%conn(a, e)) + area
      end do
    end do
    do a = 1, bd%mesh%nnode
      if (weight(a) > 0.0_dp) sstar(:, a) = sstar(:, a) / weight(a)
    end do
  end subroutine recover_stress

  !> eta_K^2 = int_K (sigma* - sigma_h) : D^-1 (sigma* - sigma_h) dV for every
  !> element K of bd, and ||u_h||_E^2 = int sigma_h : D^-1 sigma_h dV, with
  !> the richer quadrature rule of module elements (order 2).
  !>   bd (in) the body;  u (in) (2, nnode);  sstar (in) (ncomp, nnode) from recover_stress
  !>   eta2 (out) (nelem) the element indicators squared (energy)
  !>   energy2 (out) the body's energy norm of u_h squared (twice its strain energy)
  subroutine energy_indicators(bd, u, sstar, eta2, energy2)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:), sstar(:,:)
    real(dp), intent(out) :: eta2(:), energy2
    type(rules_t) :: rules
    real(dp) :: c(4, 4), sig(4), rec(4), dv, n(max_nen), dndx(2, max_nen), detj, xe(2, max_nen)
    integer :: e, q, nen, nc, a
    nc = size(sstar, 1)
    call make_rules(2, rules)
    c(1:nc, 1:nc) = compliance(bd, nc)
    energy2 = 0.0_dp
    do e = 1, bd%mesh%nelem
      nen = bd%mesh%nen(e)
      xe(:, 1:nen) = bd%mesh%x(:, bd%mesh%conn(1:nen, e))
      eta2(e) = 0.0_dp
      do q = 1, rules%nq(nen)
        associate (xq => rules%xi(:, q, nen), wq => rules%w(q, nen))
        call point_stress(bd, e, xq, u, sig(1:nc), dv)
        call shape_at(nen, xe(:, 1:nen), xq, n(1:nen), dndx(:, 1:nen), detj)
        rec(1:nc) = 0.0_dp
        do a = 1, nen                                   ! sigma*(x_q) = sum_a N_a sigma*_a
          rec(1:nc) = rec(1:nc) + n(a) * sstar(:, bd%mesh%conn(a, e))
        end do
        rec(1:nc) = rec(1:nc) - sig(1:nc)
        eta2(e) = eta2(e) + wq * dv * dot_product(rec(1:nc), matmul(c(1:nc, 1:nc), rec(1:nc)))
        energy2 = energy2 + wq * dv * dot_product(sig(1:nc), matmul(c(1:nc, 1:nc), sig(1:nc)))
        end associate
      end do
    end do
  end subroutine energy_indicators

  !> D^-1, the compliance of the body's law (D symmetric positive definite;
  !> Cholesky, then the inverse from the factor).
  function compliance(bd, nc) result(c)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: nc
    real(dp) :: c(nc, nc)
    integer :: i, j, info
    if (nc == 4) then
      c = bd%law%d4
    else
      c = bd%law%d
    end if
    call dpotrf('L', nc, c, nc, info)
    if (info == 0) call dpotri('L', nc, c, nc, info)
    if (info /= 0) then            ! not positive definite: the law was checked by the deck reader
      c = 0.0_dp
      return
    end if
    do j = 2, nc
      do i = 1, j - 1
        c(i, j) = c(j, i)
      end do
    end do
  end function compliance

end module error_estimate
