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
!>   recover_stress(bd, u, adt, sstar)     sstar(ncomp, nnode): the recovered nodal stresses of body bd
!>   energy_indicators(bd, u, adt, sstar, eta2, energy2)
!>                                         eta2(nelem) = eta_K^2 and energy2 = ||u_h||_E^2 of bd
!>   point_stress(bd, e, xe, ue, xi, sig, dv, n, adt)   sigma_h at the reference point xi of element e,
!>                                         the volume factor dV / (dxi) and the shape functions there
!>   compliance(bd, nc)                    D^-1 (nc x nc) of the body's law
!> u is the body's nodal displacement u(2, nnode) in x, y components; ncomp
!> is 3 (sxx, syy, sxy) in the plane, 4 (srr, szz, srz, stt) in axisymmetry.
module error_estimate
  use kinds, only: dp
  use body, only: body_t, axi_thermal_strain, body_pressure_modes
  use elements, only: quadrature_rule, shape_at, max_nen, reference_node, max_np, dilatation_projection, pressure_basis
  use axisymmetric_elements, only: radial_weight
  use lapack_interfaces, only: dpotrf, dpotri
  implicit none
  private
  public :: recover_stress, energy_indicators, point_stress, compliance

  !> The quadrature rule of each element size nen (3, 4, 6, 8, 9), made
  !> once per body rather than once per element.
  type :: rules_t
    integer :: nq(max_nen) = 0
    real(dp) :: xi(2, 16, max_nen) = 0.0_dp, w(16, max_nen) = 0.0_dp
  end type rules_t

contains

  !> rules: quadrature_rule(nen, order(k)) for the element sizes 3, 4, 6, 8, 9.
  subroutine make_rules(order, rules)
    integer, intent(in) :: order(5)
    type(rules_t), intent(out) :: rules
    real(dp), allocatable :: xi(:,:), w(:)
    integer :: k
    integer, parameter :: sizes(5) = [3, 4, 6, 8, 9]
    do k = 1, size(sizes)
      call quadrature_rule(sizes(k), order(k), xi, w)
      rules%nq(sizes(k)) = size(w)
      rules%xi(:, 1:size(w), sizes(k)) = xi
      rules%w(1:size(w), sizes(k)) = w
    end do
  end subroutine make_rules

  !> sigma_h(xi) = D (eps(u_h) - alpha dT eps_th) on element e of bd, and
  !> dv = detJ t (plane) or detJ 2 pi r (axisymmetric) at xi.  eps(u_h) is
  !> the strain the stiffness is made of: B u, or B_bar u on a body with
  !> B-bar (body%bbar; its volumetric part theta_bar = p(x)' G u, elements'
  !> dilatation_projection), so that sigma_h is the solution's stress.
  !>   bd  (in)  the body;  e (in) its element
  !>   xe  (in)  (2, nen) the element's nodes;  ue (in) (2, nen) their displacements, x, y
  !>   xi  (in)  (2) reference point
  !>   sig (out) (ncomp) the stress;  dv (out) the volume factor
  !>   n   (out) (nen) the shape functions at xi
  !>   adt (in)  alpha dT of the element in the state (0 without THERMAL)
  pure subroutine point_stress(bd, e, xe, ue, xi, sig, dv, n, adt)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    real(dp), intent(in) :: xe(:,:), ue(:,:), xi(2), adt
    real(dp), intent(out) :: sig(:), dv, n(:)
    real(dp) :: dndx(2, max_nen), detj, eps(3), eps4(4), r, dvol
    integer :: nen, a, np
    nen = size(xe, 2)
    np = body_pressure_modes(bd, nen)
    call shape_at(nen, xe, xi, n(1:nen), dndx(:, 1:nen), detj)
    eps = 0.0_dp                                      ! (exx, eyy, gxy) = B u, written out
    do a = 1, nen
      eps(1) = eps(1) + dndx(1, a) * ue(1, a)
      eps(2) = eps(2) + dndx(2, a) * ue(2, a)
      eps(3) = eps(3) + dndx(2, a) * ue(1, a) + dndx(1, a) * ue(2, a)
    end do
    if (bd%axisymmetric) then
      r = dot_product(n(1:nen), xe(1, :))
      if (r > 1.0e-6_dp * (maxval(xe(1, :)) - minval(xe(1, :)))) then
        eps4 = [eps, dot_product(n(1:nen), ue(1, :)) / r]         ! the hoop strain u_r / r
      else
        eps4 = [eps, eps(1)]                          ! on the axis: its limit du_r / dr
      end if
      if (np > 0) then                                ! B_bar: eps4 += m (theta_bar - theta) / 3
        dvol = (projected_dilatation(nen, xe, ue, np, .true., n(1:nen)) - (eps4(1) + eps4(2) + eps4(4))) / 3
        eps4([1, 2, 4]) = eps4([1, 2, 4]) + dvol
      end if
      if (allocated(bd%adt)) eps4 = eps4 - adt * axi_thermal_strain
      sig(1:4) = matmul(bd%law%d4, eps4)
      dv = detj * radial_weight(r)
    else
      if (np > 0) then                                ! B_bar: eps += m (theta_bar - theta) / 2
        dvol = (projected_dilatation(nen, xe, ue, np, .false., n(1:nen)) - (eps(1) + eps(2))) / 2
        eps(1:2) = eps(1:2) + dvol
      end if
      if (allocated(bd%adt)) eps = eps - adt * bd%law%eth
      sig(1:3) = matmul(bd%law%d, eps)
      dv = detj * bd%thick
    end if
  end subroutine point_stress

  !> theta_bar = p(x)' G u at the point of shape functions n: the projected
  !> volumetric strain of B-bar (elements' dilatation_projection).
  !>   nen, xe (in) the element;  ue (in) (2, nen) its displacements;  np (in) > 0
  !>   radial (in) axisymmetric;  n (in) (nen) the shape functions at the point
  pure real(dp) function projected_dilatation(nen, xe, ue, np, radial, n) result(theta)
    integer, intent(in) :: nen, np
    real(dp), intent(in) :: xe(2, nen), ue(2, nen), n(nen)
    logical, intent(in) :: radial
    real(dp) :: g(max_np, 2 * max_nen), p(max_np)
    integer :: a
    call dilatation_projection(nen, xe, np, radial, g(1:np, 1:2 * nen))
    call pressure_basis(nen, xe, np, [dot_product(n, xe(1, :)), dot_product(n, xe(2, :))], p(1:np))
    theta = 0.0_dp
    do a = 1, nen
      theta = theta + dot_product(p(1:np), g(1:np, 2 * a - 1)) * ue(1, a) + dot_product(p(1:np), g(1:np, 2 * a)) * ue(2, a)
    end do
  end function projected_dilatation

  !> sigma*(node a) = sum_K |K| sigma_h|_K(x_a) / sum_K |K| over the elements
  !> K of bd around node a, |K| the element's area.
  !>   bd (in) the body;  u (in) (2, nnode) its displacement, x, y
  !>   adt (in) (nelem) alpha dT of its elements in the state (0 without THERMAL)
  !>   sstar (out) (ncomp, nnode) the recovered nodal stresses
  subroutine recover_stress(bd, u, adt, sstar)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:), adt(:)
    real(dp), allocatable, intent(out) :: sstar(:,:)
    real(dp), allocatable :: weight(:), es(:,:,:), area(:)
    type(rules_t) :: rules
    real(dp) :: dv, n(max_nen), dndx(2, max_nen), detj, xe(2, max_nen), ue(2, max_nen)
    integer :: e, a, q, nen, nc
    nc = merge(4, 3, bd%axisymmetric)
    call make_rules([1, 1, 1, 1, 1], rules)
    allocate(sstar(nc, bd%mesh%nnode), source=0.0_dp)
    allocate(weight(bd%mesh%nnode), source=0.0_dp)
    allocate(es(nc, maxval(bd%mesh%nen), bd%mesh%nelem), area(bd%mesh%nelem))
    ! each element's stresses at its nodes, threaded; then the sums in element
    ! order, so the result does not depend on the threads (reproducible runs)
    !$omp parallel do private(e, nen, xe, ue, q, n, dndx, detj, a, dv) schedule(static)
    do e = 1, bd%mesh%nelem
      call element_values(bd, e, u, nen, xe, ue)
      area(e) = 0.0_dp
      do q = 1, rules%nq(nen)
        call shape_at(nen, xe(:, 1:nen), rules%xi(:, q, nen), n(1:nen), dndx(:, 1:nen), detj)
        area(e) = area(e) + rules%w(q, nen) * detj
      end do
      do a = 1, nen
        call point_stress(bd, e, xe(:, 1:nen), ue(:, 1:nen), reference_node(nen, a), es(:, a, e), dv, n, adt(e))
      end do
    end do
    !$omp end parallel do
    do e = 1, bd%mesh%nelem
      do a = 1, bd%mesh%nen(e)
        sstar(:, bd%mesh%conn(a, e)) = sstar(:, bd%mesh%conn(a, e)) + area(e) * es(:, a, e)
        weight(bd%mesh%conn(a, e)) = weight(bd%mesh%conn(a, e)) + area(e)
      end do
    end do
    do a = 1, bd%mesh%nnode
      if (weight(a) > 0.0_dp) sstar(:, a) = sstar(:, a) / weight(a)
    end do
  end subroutine recover_stress

  !> eta_K^2 = int_K (sigma* - sigma_h) : D^-1 (sigma* - sigma_h) dV for every
  !> element K of bd, and ||u_h||_E^2 = int sigma_h : D^-1 sigma_h dV, by a
  !> rule exact for these integrands on affine elements.
  !>   bd (in) the body;  u (in) (2, nnode);  sstar (in) (ncomp, nnode) from recover_stress
  !>   adt (in) (nelem) alpha dT of its elements in the state (0 without THERMAL)
  !>   eta2 (out) (nelem) the element indicators squared (energy)
  !>   energy2 (out) the body's energy norm of u_h squared (twice its strain energy)
  subroutine energy_indicators(bd, u, adt, sstar, eta2, energy2)
    type(body_t), intent(in) :: bd
    real(dp), intent(in) :: u(:,:), adt(:), sstar(:,:)
    real(dp), intent(out) :: eta2(:), energy2
    type(rules_t) :: rules
    real(dp) :: c(4, 4), sig(4), rec(4), dv, n(max_nen), xe(2, max_nen), ue(2, max_nen)
    real(dp), allocatable :: e2(:)
    integer :: e, q, nen, nc, a
    nc = size(sstar, 1)
    ! the lowest rule of module elements exact for |sigma* - sigma_h|^2 on an
    ! affine element: P1 (degree 2) and P2 (degree 4) the richer rules (3 and
    ! 6 points), Q1 (degree 2 in each variable) 2 x 2 and Q8, Q9 (degree 4) 3 x 3
    call make_rules([2, 1, 2, 1, 1], rules)
    c(1:nc, 1:nc) = compliance(bd, nc)
    allocate(e2(bd%mesh%nelem))
    ! threaded over the elements; each element's energy kept apart and summed
    ! in element order afterwards, so the result does not depend on the threads
    !$omp parallel do private(e, nen, xe, ue, q, sig, dv, n, rec, a) schedule(static)
    do e = 1, bd%mesh%nelem
      call element_values(bd, e, u, nen, xe, ue)
      eta2(e) = 0.0_dp
      e2(e) = 0.0_dp
      do q = 1, rules%nq(nen)
        call point_stress(bd, e, xe(:, 1:nen), ue(:, 1:nen), rules%xi(:, q, nen), sig(1:nc), dv, n(1:nen), adt(e))
        rec(1:nc) = 0.0_dp
        do a = 1, nen                                   ! sigma*(x_q) = sum_a N_a sigma*_a
          rec(1:nc) = rec(1:nc) + n(a) * sstar(:, bd%mesh%conn(a, e))
        end do
        rec(1:nc) = rec(1:nc) - sig(1:nc)
        eta2(e) = eta2(e) + rules%w(q, nen) * dv * energy_density(c, rec, nc)
        e2(e) = e2(e) + rules%w(q, nen) * dv * energy_density(c, sig, nc)
      end do
    end do
    !$omp end parallel do
    energy2 = sum(e2)
  end subroutine energy_indicators

  !> The nodes xe(2, nen) and displacements ue(2, nen) of element e of bd.
  pure subroutine element_values(bd, e, u, nen, xe, ue)
    type(body_t), intent(in) :: bd
    integer, intent(in) :: e
    real(dp), intent(in) :: u(:,:)
    integer, intent(out) :: nen
    real(dp), intent(out) :: xe(2, max_nen), ue(2, max_nen)
    nen = bd%mesh%nen(e)
    xe(:, 1:nen) = bd%mesh%x(:, bd%mesh%conn(1:nen, e))
    ue(:, 1:nen) = u(:, bd%mesh%conn(1:nen, e))
  end subroutine element_values

  !> s : D^-1 s = sum_ij s_i c_ij s_j over the first nc components, in loops
  !> of fixed-size arrays (a matmul on the run-time size nc would put a
  !> temporary on the heap at every quadrature point).
  pure real(dp) function energy_density(c, s, nc) result(w)
    real(dp), intent(in) :: c(4, 4), s(4)
    integer, intent(in) :: nc
    integer :: i, j
    w = 0.0_dp
    do j = 1, nc
      do i = 1, nc
        w = w + s(i) * c(i, j) * s(j)
      end do
    end do
  end function energy_density

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
