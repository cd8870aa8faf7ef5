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
!> F-bar (optional argument fbar; for Q1, whose full integration locks as
!> K / mu grows, and the quadratic elements, where it is P2/P0 and Q2/P0).  The volume change of every point is
!> replaced by the element's mean dilatation J0 = int J dV0 / V0 (on the same
!> rule; rather than J at the centre, as de Souza Neto et al. take it, because
!> the mean keeps the axisymmetric patch test: there dV0 = 2 pi R dA weighs
!> the points unequally, and with the centre's J a homogeneous state leaves
!> forces on interior nodes):
!>     F_bar = (J0 / J)^(1/m) F,  m = 2 on the in-plane block (plane strain,
!>     F33 = 1 kept) or m = 3 on the whole F (axisymmetric),
!> so det F_bar = J0 at every point (F-bar: de Souza Neto, Peric, Dutko,
!> Owen 1996; with the mean, the finite-strain form of the mean dilatation).
!> f_int = int D' P(F_bar) dV0 with D = dF_bar/du is the gradient of int
!> W(F_bar) dV0, and the tangent is its exact second derivative:
!>     K = int D' A(F_bar) D + tau phi'' + phi' h' + h phi' dV0,
!> phi = (J0 / J)^(1/m), tau = sum_s P_bar_s F_s and h = G' (P_bar on the scaled
!> components), phi' and phi'' from the first and second derivatives of J and
!> J0 in u (F is linear in u).  A homogeneous deformation has J0 = J: F-bar
!> changes nothing there (the patch test holds as without it).
!>
!> The rules are the stiffness rules (elements' stiffness_rule), whose points
!> are inside the element (R > 0 in axisymmetry).  A point where J = det F <= 0
!> makes the kernel return info = the point's number: the caller cuts the
!> load step.
!>
!> Programming interface
!>   finite_strain_response(nen, xe, ue, law, axisymmetric, thick, fe, ke, info [, fbar, theta])
!>        fe = f_int(ue) (2 nen) and, when present, ke = K(ue) (2 nen, 2 nen)
!>   finite_strain_dilatation(nen, xe, ue, due, axisymmetric, j0, dj0, info)
!>        F-bar's mean dilatation J0 and dJ0/du due
!>   finite_strain_energy(nen, xe, ue, law, axisymmetric, thick, energy, info [, fbar])
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
  public :: finite_strain_dilatation

  !> F-bar's data of the element's mean dilatation (centre_state).
  type :: centre_t
    real(dp) :: jac = 1.0_dp                            !< J0 = int J dV0 / V0
    real(dp) :: dj(2 * max_nen) = 0.0_dp                !< dJ0/du
    real(dp) :: d2j(2 * max_nen, 2 * max_nen) = 0.0_dp  !< d2 J0 / du2
  end type centre_t

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
  !>   fbar         (in, optional) .true.: F-bar (module header); absent: .false.
  !>   theta        (in, optional) with fbar and ke: the element's dilatation
  !>                state, whose pressure K (theta - 1) the tangent's initial-stress
  !>                terms take instead of K (J0 - 1) (newton_step); fe is F-bar's
  pure subroutine finite_strain_response(nen, xe, ue, law, axisymmetric, thick, fe, ke, info, fbar, theta)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), thick
    type(hyperelastic_t), intent(in) :: law
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: fe(2 * nen)
    real(dp), intent(inout), optional :: ke(:,:)
    integer, intent(out) :: info
    logical, intent(in), optional :: fbar
    real(dp), intent(in), optional :: theta
    real(dp) :: xi(2, 9), w(9), dv, f(3, 3), p5(5), a5(5, 5), pt5(5)
    real(dp) :: d(5, 2 * max_nen), ad(5, 2 * max_nen), extra(2 * max_nen, 2 * max_nen)
    type(centre_t) :: c0
    integer :: q, nq, m, j, k
    logical :: bar

    m = 2 * nen
    bar = .false.
    if (present(fbar)) bar = fbar
    call stiffness_rule(nen, nq, xi, w)
    fe = 0.0_dp
    if (present(ke)) ke(1:m, 1:m) = 0.0_dp
    info = 0
    if (bar) call centre_state(nen, xe, ue, axisymmetric, c0, info, hessian=present(ke))
    if (info /= 0) return
    do q = 1, nq
      call point_state(nen, xe, ue, xi(:, q), w(q), axisymmetric, thick, bar, c0, f, d(:, 1:m), dv, k)
      if (k == 0) then
        if (present(ke) .and. present(theta) .and. bar) then
          ! the tangent's pressure: the element's dilatation state's (module header)
          call first_piola(law, f, p5, info=k)
          if (k == 0) call first_piola(law, f, pt5, a5, k, pvol=law%bulk * (theta - 1.0_dp))
        else if (present(ke)) then
          call first_piola(law, f, p5, a5, k)
          pt5 = p5
        else
          call first_piola(law, f, p5, info=k)
        end if
      end if
      if (k /= 0) then
        info = q
        return
      end if
      do j = 1, m                                    ! f_int += D' P dV0 (D = G without F-bar)
        fe(j) = fe(j) + dv * dot_product(d(:, j), p5)
      end do
      if (.not. present(ke)) cycle
      ad(:, 1:m) = matmul(a5, d(:, 1:m))
      do j = 1, m                                    ! K += D' A D dV0
        do k = 1, m
          ke(k, j) = ke(k, j) + dv * dot_product(d(:, k), ad(:, j))
        end do
      end do
      if (bar) then                                  ! K += P : d2 F_bar / du2 dV0
        call fbar_second_term(nen, xe, ue, xi(:, q), axisymmetric, c0, pt5, extra(1:m, 1:m))
        ke(1:m, 1:m) = ke(1:m, 1:m) + dv * extra(1:m, 1:m)
      end if
    end do
  end subroutine finite_strain_response

  !> The element's mean dilatation J0 at ue and its derivative along due,
  !> dJ0/du due (F-bar's J0, centre_state); info 1 when J <= 0 at a point.
  pure subroutine finite_strain_dilatation(nen, xe, ue, due, axisymmetric, j0, dj0, info)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), due(2 * nen)
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: j0, dj0
    integer, intent(out) :: info
    type(centre_t) :: c0
    call centre_state(nen, xe, ue, axisymmetric, c0, info, hessian=.false.)
    j0 = c0%jac
    dj0 = dot_product(c0%dj(1:2 * nen), due)
  end subroutine finite_strain_dilatation

  !> What F-bar needs of the element: its mean dilatation J0 = int J dV0 / V0
  !> on the stiffness rule, dJ0/du and d2 J0 / du2 (the means of G' dJ/dF and
  !> G' d2J/dF2 G).  info 1 when J0 <= 0 or J <= 0 at a point.
  !>   hessian (in, optional) .false.: d2 J0 / du2 left out (forces only; default .true.)
  pure subroutine centre_state(nen, xe, ue, axisymmetric, c0, info, hessian)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen)
    logical, intent(in) :: axisymmetric
    type(centre_t), intent(out) :: c0
    integer, intent(out) :: info
    logical, intent(in), optional :: hessian
    real(dp) :: xi(2, 9), w(9), dv, g(5, 2 * max_nen), f(3, 3), f5(5), vol, jac
    integer :: m, q, nq
    logical :: want
    want = .true.
    if (present(hessian)) want = hessian
    m = 2 * nen
    call stiffness_rule(nen, nq, xi, w)
    vol = 0.0_dp
    c0%jac = 0.0_dp
    info = 0
    do q = 1, nq
      call point_kinematics(nen, xe, ue, xi(:, q), w(q), axisymmetric, 1.0_dp, f, g(:, 1:m), dv, f5, jac)
      if (.not. (jac > 0.0_dp)) then
        info = 1
        return
      end if
      vol = vol + dv
      c0%jac = c0%jac + dv * jac
      c0%dj(1:m) = c0%dj(1:m) + dv * matmul(jacobian_gradient(f5), g(:, 1:m))
      if (want) c0%d2j(1:m, 1:m) = c0%d2j(1:m, 1:m) + &
                                   dv * matmul(transpose(g(:, 1:m)), matmul(jacobian_hessian(f5), g(:, 1:m)))
    end do
    c0%jac = c0%jac / vol
    c0%dj(1:m) = c0%dj(1:m) / vol
    c0%d2j(1:m, 1:m) = c0%d2j(1:m, 1:m) / vol
  end subroutine centre_state

  !> At one point: F, G (5, 2 nen), the weight dV0, F's reduced components and J.
  pure subroutine point_kinematics(nen, xe, ue, xi, w, axisymmetric, thick, f, g, dv, f5, jac)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), xi(2), w, thick
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: f(3, 3), g(:,:), dv, f5(5), jac
    real(dp) :: n(max_nen), dndx(2, max_nen), r
    call point_geometry(nen, xe, xi, w, axisymmetric, thick, n(1:nen), dndx(:, 1:nen), r, dv)
    call deformation_gradient(nen, n(1:nen), dndx(:, 1:nen), r, axisymmetric, ue, f)
    call gradient_operator(nen, n(1:nen), dndx(:, 1:nen), r, axisymmetric, g)
    f5 = reduced(f)
    jac = jacobian(f5)
  end subroutine point_kinematics

  !> At one point: F (F_bar with fbar), D = dF/du or dF_bar/du (5, 2 nen), the
  !> weight dV0; info 1 when J <= 0 there.
  pure subroutine point_state(nen, xe, ue, xi, w, axisymmetric, thick, fbar, c0, f, d, dv, info)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), xi(2), w, thick
    logical, intent(in) :: axisymmetric, fbar
    type(centre_t), intent(in) :: c0
    real(dp), intent(out) :: f(3, 3), d(:,:), dv
    integer, intent(out) :: info
    real(dp) :: f5(5), s(5), phi, dphi(2 * max_nen), jac, me
    integer :: m, i
    m = 2 * nen
    call point_kinematics(nen, xe, ue, xi, w, axisymmetric, thick, f, d(:, 1:m), dv, f5, jac)
    info = 0
    if (.not. fbar) return
    if (.not. (jac > 0.0_dp)) then
      info = 1
      return
    end if
    call fbar_scaling(axisymmetric, s, me)
    phi = (c0%jac / jac)**(1.0_dp / me)
    ! phi' = phi / m (dJ0 / J0 - dJ / J)
    dphi(1:m) = phi / me * (c0%dj(1:m) / c0%jac - matmul(jacobian_gradient(f5), d(:, 1:m)) / jac)
    do i = 1, m                                      ! D = (s phi + 1 - s) G + (s F) phi'
      d(:, i) = (s * phi + (1.0_dp - s)) * d(:, i) + s * f5 * dphi(i)
    end do
    f5 = (s * phi + (1.0_dp - s)) * f5
    f = 0.0_dp
    f(1, 1) = f5(1); f(1, 2) = f5(2); f(2, 1) = f5(3); f(2, 2) = f5(4); f(3, 3) = f5(5)
  end subroutine point_state

  !> P_bar : d2 F_bar / du2 at one point (module header): tau phi'' + phi' h' + h phi'.
  !>   p5 (in) P(F_bar);  extra (out) (2 nen, 2 nen)
  pure subroutine fbar_second_term(nen, xe, ue, xi, axisymmetric, c0, p5, extra)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), xi(2), p5(5)
    logical, intent(in) :: axisymmetric
    type(centre_t), intent(in) :: c0
    real(dp), intent(out) :: extra(:,:)
    real(dp) :: dv, f(3, 3), f5(5), g(5, 2 * max_nen), s(5), me, jac, phi, tau
    real(dp) :: gj(2 * max_nen), dd(2 * max_nen), dphi(2 * max_nen), h(2 * max_nen), hj(2 * max_nen, 2 * max_nen)
    integer :: m, i, j
    m = 2 * nen
    call point_kinematics(nen, xe, ue, xi, 1.0_dp, axisymmetric, 1.0_dp, f, g(:, 1:m), dv, f5, jac)
    call fbar_scaling(axisymmetric, s, me)
    phi = (c0%jac / jac)**(1.0_dp / me)
    gj(1:m) = matmul(jacobian_gradient(f5), g(:, 1:m)) / jac                 ! dJ / J
    dd(1:m) = c0%dj(1:m) / c0%jac - gj(1:m)                                  ! d ln(J0 / J)
    dphi(1:m) = phi / me * dd(1:m)
    hj(1:m, 1:m) = matmul(transpose(g(:, 1:m)), matmul(jacobian_hessian(f5), g(:, 1:m))) / jac
    tau = sum(s * p5 * f5)
    h(1:m) = matmul(s * p5, g(:, 1:m))
    do j = 1, m
      do i = 1, m
        ! phi'' = phi / m^2 dd dd' + phi / m (d2 ln J0 - d2 ln J),  d2 ln J = J''/J - (J'/J)(J'/J)'
        extra(i, j) = tau * (phi / me**2 * dd(i) * dd(j) + phi / me * ( &
                        c0%d2j(i, j) / c0%jac - c0%dj(i) * c0%dj(j) / c0%jac**2 - hj(i, j) + gj(i) * gj(j))) &
                      + dphi(i) * h(j) + h(i) * dphi(j)
      end do
    end do
  end subroutine fbar_second_term

  !> Which reduced components F-bar scales (s = 1) and the exponent's m.
  pure subroutine fbar_scaling(axisymmetric, s, me)
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: s(5), me
    if (axisymmetric) then
      s = 1.0_dp
      me = 3.0_dp
    else
      s = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 0.0_dp]
      me = 2.0_dp
    end if
  end subroutine fbar_scaling

  !> The five reduced components (11, 12, 21, 22, 33) of F.
  pure function reduced(f) result(f5)
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: f5(5)
    f5 = [f(1, 1), f(1, 2), f(2, 1), f(2, 2), f(3, 3)]
  end function reduced

  !> J = (F11 F22 - F12 F21) F33 of reduced components.
  pure real(dp) function jacobian(f5) result(jac)
    real(dp), intent(in) :: f5(5)
    jac = (f5(1) * f5(4) - f5(2) * f5(3)) * f5(5)
  end function jacobian

  !> dJ/dF in reduced components.
  pure function jacobian_gradient(f5) result(dj)
    real(dp), intent(in) :: f5(5)
    real(dp) :: dj(5)
    dj = [f5(4) * f5(5), -f5(3) * f5(5), -f5(2) * f5(5), f5(1) * f5(5), f5(1) * f5(4) - f5(2) * f5(3)]
  end function jacobian_gradient

  !> d2J/dF2 in reduced components (symmetric, zero diagonal).
  pure function jacobian_hessian(f5) result(h)
    real(dp), intent(in) :: f5(5)
    real(dp) :: h(5, 5)
    h = 0.0_dp
    h(1, 4) = f5(5); h(1, 5) = f5(4); h(2, 3) = -f5(5); h(2, 5) = -f5(3); h(3, 5) = -f5(2); h(4, 5) = f5(1)
    h = h + transpose(h)
  end function jacobian_hessian

  !> The reference centre of an element: the centroid of its corners' reference points.
  pure function centre_point(nen) result(xi)
    integer, intent(in) :: nen
    real(dp) :: xi(2)
    integer :: a, nc
    nc = corner_count(nen)
    xi = 0.0_dp
    do a = 1, nc
      xi = xi + reference_node(nen, a) / nc
    end do
  end function centre_point

  !> The element's strain energy int W dV0 on the same rule (f_int is its
  !> gradient in ue).
  !>   energy (out) the energy (0 when info /= 0)
  !>   info   (out) 0; q > 0 when J <= 0 at point q
  pure subroutine finite_strain_energy(nen, xe, ue, law, axisymmetric, thick, energy, info, fbar)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(2, nen), ue(2 * nen), thick
    type(hyperelastic_t), intent(in) :: law
    logical, intent(in) :: axisymmetric
    real(dp), intent(out) :: energy
    integer, intent(out) :: info
    logical, intent(in), optional :: fbar
    real(dp) :: xi(2, 9), w(9), dv, f(3, 3), wq, d(5, 2 * max_nen)
    type(centre_t) :: c0
    integer :: q, nq, k
    logical :: bar
    bar = .false.
    if (present(fbar)) bar = fbar
    call stiffness_rule(nen, nq, xi, w)
    energy = 0.0_dp
    info = 0
    if (bar) call centre_state(nen, xe, ue, axisymmetric, c0, info)
    if (info /= 0) return
    do q = 1, nq
      call point_state(nen, xe, ue, xi(:, q), w(q), axisymmetric, thick, bar, c0, f, d(:, 1:2 * nen), dv, k)
      wq = huge(1.0_dp)
      if (k == 0) wq = strain_energy(law, f)
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
    xi = centre_point(nen)
    call point_geometry(nen, xe, xi, 1.0_dp, axisymmetric, 1.0_dp, n(1:nen), dndx(:, 1:nen), r, dv)
    call deformation_gradient(nen, n(1:nen), dndx(:, 1:nen), r, axisymmetric, ue, f)
    jac = (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) * f(3, 3)
    stretch = largest_stretch(f)
    call cauchy_stress(law, f, sig4, info)
  end subroutine finite_strain_state

end module finite_strain_elements
