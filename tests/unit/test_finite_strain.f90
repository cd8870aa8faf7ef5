!> The hyperelastic law and the total Lagrangian kernels against what they
!> must be independently of their algebra:
!>   - P = dW/dF and A = dP/dF against central differences of W and of P
!>     (neo-Hookean and Mooney-Rivlin, a general F with a hoop stretch);
!>   - the reference state: S = 0 and A = the linear law of lambda = K - 2 mu / 3, mu;
!>   - objectivity: W, the Cauchy stress's invariants and sigma' = Q sigma Q'
!>     under a large rigid rotation Q of a stretched state;
!>   - f_int = d(int W dV0)/du and K = d f_int / du against central differences
!>     on every element kind, plane strain and axisymmetric, distorted elements;
!>   - the tangent with the volumetric pressure of a dilatation state (the
!>     mixed iteration's, pvol and theta): P and A move by (pvol - U'(J)) times
!>     dJ/dF and d2J/dF2 (central differences of J), the element's tangent
!>     with theta = J0 is the consistent one, and its J0 and dJ0/du du
!>     against central differences;
!>   - the patch test in finite strain: a homogeneous deformation of a distorted
!>     four-element patch leaves no force on its interior node, and the edge's
!>     nodal forces add up to the nominal stress times the reference length.
!> Central differences of step h have an error O(h^2) (third derivatives of
!> order one here) plus O(eps / h) of round-off: h = 1e-5 gives about 1e-10
!> relative; the tolerance 1e-7 leaves three decades, and a wrong term of the
!> tangent (an order-one error) fails it by six.
program test_finite_strain
  use kinds, only: dp
  use hyperelastic, only: hyperelastic_t, make_hyperelastic, strain_energy, first_piola, second_piola, &
                          cauchy_stress, largest_stretch, reduced_index, initial_moduli
  use finite_strain_elements, only: finite_strain_response, finite_strain_energy, finite_strain_state, &
                                    finite_strain_dilatation
  use elements, only: reference_node, shape_at
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  implicit none
  real(dp), parameter :: fd_tol = 1.0e-7_dp, h = 1.0e-5_dp
  type(hyperelastic_t) :: neo, mooney
  real(dp) :: f(3, 3)
  integer :: kind_index
  integer, parameter :: kinds(5) = [3, 4, 6, 8, 9]

  call make_hyperelastic(0.5_dp, 0.0_dp, 10.0_dp, neo)          ! mu = 1, K = 10
  call make_hyperelastic(0.3_dp, 0.15_dp, 50.0_dp, mooney)
  f = reshape([1.2_dp, -0.15_dp, 0.0_dp, 0.25_dp, 0.85_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.1_dp], [3, 3])
  call check_law(neo, f, 'neo-Hookean')
  call check_law(mooney, f, 'Mooney-Rivlin')
  call check_reference(neo, 'neo-Hookean')
  call check_reference(mooney, 'Mooney-Rivlin')
  call check_objectivity(mooney)
  call check_moduli()
  do kind_index = 1, size(kinds)
    call check_element(kinds(kind_index), .false., .false.)
    call check_element(kinds(kind_index), .true., .false.)
  end do
  call check_element(4, .false., .true.)
  call check_element(4, .true., .true.)
  call check_element(9, .false., .true.)
  call check_element(9, .true., .true.)
  call check_element(8, .false., .true.)
  call check_element(6, .false., .true.)
  call check_element(6, .true., .true.)
  call check_patch(.false., .false.)
  call check_patch(.true., .false.)
  call check_patch(.false., .true.)
  call check_patch(.true., .true.)
  call check_fbar_volume()
  call check_pressure_state(neo, f, 'neo-Hookean')
  call check_pressure_state(mooney, f, 'Mooney-Rivlin')
  call check_theta_element(4, .false.)
  call check_theta_element(4, .true.)
  call check_theta_element(9, .false.)
  call check_inverted()
  call finish_tests()

contains

  !> P against dW/dF and A against dP/dF by central differences.
  subroutine check_law(law, f, what)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    character(len=*), intent(in) :: what
    real(dp) :: p5(5), a5(5, 5), pp(5), pm(5), ap(5, 5), s(3, 3), fp(3, 3), fm(3, 3), dw(5), da(5, 5)
    integer :: n, info
    call first_piola(law, f, p5, a5, info)
    call check(info == 0, what // ': J > 0 accepted')
    do n = 1, 5
      fp = f
      fm = f
      fp(reduced_index(1, n), reduced_index(2, n)) = fp(reduced_index(1, n), reduced_index(2, n)) + h
      fm(reduced_index(1, n), reduced_index(2, n)) = fm(reduced_index(1, n), reduced_index(2, n)) - h
      dw(n) = (strain_energy(law, fp) - strain_energy(law, fm)) / (2 * h)
      call first_piola(law, fp, pp, ap, info)
      call first_piola(law, fm, pm, ap, info)
      da(:, n) = (pp - pm) / (2 * h)
    end do
    call check_small(maxval(abs(p5 - dw)) / maxval(abs(p5)), fd_tol, what // ': P = dW/dF (central differences)')
    call check_small(maxval(abs(a5 - da)) / maxval(abs(a5)), fd_tol, what // ': A = dP/dF (central differences)')
    call check_small(maxval(abs(a5 - transpose(a5))) / maxval(abs(a5)), tol_round(64), what // ': A symmetric')
    call second_piola(law, f, s, info=info)
    call check_small(maxval(abs(s - transpose(s))) / maxval(abs(s)), tol_round(16), what // ': S symmetric')
  end subroutine check_law

  !> With pvol in place of U'(J) = K (J - 1): P + (pvol - U') dJ/dF and
  !> A + (pvol - U') d2J/dF2, dJ/dF and d2J/dF2 by central differences of J.
  subroutine check_pressure_state(law, f, what)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    character(len=*), intent(in) :: what
    real(dp) :: p5(5), a5(5, 5), pt(5), at(5, 5), dj(5), d2j(5, 5), fp(3, 3), fm(3, 3), jac, pvol, dp5
    integer :: n, m, info
    ! J is linear in each component of F: central differences of any step
    ! are exact but for round-off, O(eps / hj^2) on the second ones
    real(dp), parameter :: hj = 0.1_dp
    jac = jacobian3(f)
    pvol = law%bulk * (jac - 1.0_dp) + 0.7_dp * law%bulk
    call first_piola(law, f, p5, a5, info)
    call first_piola(law, f, pt, at, info, pvol=pvol)
    dp5 = pvol - law%bulk * (jac - 1.0_dp)
    do n = 1, 5
      fp = f
      fm = f
      fp(reduced_index(1, n), reduced_index(2, n)) = fp(reduced_index(1, n), reduced_index(2, n)) + hj
      fm(reduced_index(1, n), reduced_index(2, n)) = fm(reduced_index(1, n), reduced_index(2, n)) - hj
      dj(n) = (jacobian3(fp) - jacobian3(fm)) / (2 * hj)
      do m = 1, 5
        d2j(m, n) = (cofactor(fp, m) - cofactor(fm, m)) / (2 * hj)
      end do
    end do
    call check_small(maxval(abs(pt - p5 - dp5 * dj)) / maxval(abs(pt)), tol_round(1024), &
                     what // ': P with a pressure state = P + (p - U'') dJ/dF')
    call check_small(maxval(abs(at - a5 - dp5 * d2j)) / maxval(abs(at)), tol_round(1024), &
                     what // ': A with a pressure state = A + (p - U'') d2J/dF2')
    call first_piola(law, f, pt, at, info, pvol=law%bulk * (jac - 1.0_dp))
    call check_small(maxval(abs(at - a5)) / maxval(abs(a5)), tol_round(256), &
                     what // ': A with the pressure U''(J) is the consistent one')
  end subroutine check_pressure_state

  !> det F of a plane or axisymmetric F (F13 = F23 = F31 = F32 = 0).
  pure real(dp) function jacobian3(f) result(jac)
    real(dp), intent(in) :: f(3, 3)
    jac = (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) * f(3, 3)
  end function jacobian3

  !> dJ/dF's reduced component m, by central differences of J (exact: J is
  !> linear in each component).
  pure real(dp) function cofactor(f, m) result(c)
    real(dp), intent(in) :: f(3, 3)
    integer, intent(in) :: m
    real(dp) :: fp(3, 3), fm(3, 3)
    real(dp), parameter :: hj = 0.1_dp
    fp = f
    fm = f
    fp(reduced_index(1, m), reduced_index(2, m)) = fp(reduced_index(1, m), reduced_index(2, m)) + hj
    fm(reduced_index(1, m), reduced_index(2, m)) = fm(reduced_index(1, m), reduced_index(2, m)) - hj
    c = (jacobian3(fp) - jacobian3(fm)) / (2 * hj)
  end function cofactor

  !> An F-bar element: J0 and dJ0/du du against central differences of J0
  !> (theta itself), the tangent with theta = J0 the consistent one, with
  !> another theta the same forces and a different tangent.
  subroutine check_theta_element(nen, axisymmetric)
    integer, intent(in) :: nen
    logical, intent(in) :: axisymmetric
    real(dp) :: xe(2, nen), ue(2 * nen), due(2 * nen), fe(2 * nen), ft(2 * nen), ke(2 * nen, 2 * nen)
    real(dp) :: kt(2 * nen, 2 * nen), j0, dj0, jp, jm, dum
    integer :: j, info
    character(len=40) :: what
    write(what, '(a, i0, a)') 'element ', nen, merge(' axisymmetric', ' plane strain', axisymmetric)
    call distorted_element(nen, xe)
    do j = 1, nen
      ue(2 * j - 1) = 0.2_dp * xe(2, j) - 0.1_dp * (xe(1, j) - 1.5_dp) + 0.02_dp * sin(3.0_dp * j)
      ue(2 * j) = -0.25_dp * (xe(2, j) - 0.3_dp) + 0.1_dp * (xe(1, j) - 1.5_dp)**2 + 0.02_dp * cos(2.0_dp * j)
      due(2 * j - 1) = 0.03_dp * cos(1.7_dp * j)
      due(2 * j) = -0.02_dp * sin(2.3_dp * j)
    end do
    call finite_strain_dilatation(nen, xe, ue, due, axisymmetric, j0, dj0, info)
    call check(info == 0, trim(what) // ': J0 at a deformed state')
    call finite_strain_dilatation(nen, xe, ue + h * due, due, axisymmetric, jp, dum, info)
    call finite_strain_dilatation(nen, xe, ue - h * due, due, axisymmetric, jm, dum, info)
    call check_small(abs(dj0 - (jp - jm) / (2 * h)) / abs(dj0), fd_tol, trim(what) // ': dJ0/du du')
    call finite_strain_response(nen, xe, ue, mooney, axisymmetric, 1.0_dp, fe, ke, info, .true.)
    call finite_strain_response(nen, xe, ue, mooney, axisymmetric, 1.0_dp, ft, kt, info, .true., theta=j0)
    call check_small(maxval(abs(kt - ke)) / maxval(abs(ke)), tol_round(1024), &
                     trim(what) // ': the tangent with theta = J0 is the consistent one')
    call finite_strain_response(nen, xe, ue, mooney, axisymmetric, 1.0_dp, ft, kt, info, .true., theta=j0 + 0.1_dp)
    call check_small(maxval(abs(ft - fe)) / maxval(abs(fe)), tol_round(16), trim(what) // ': theta leaves f_int as it is')
    call check(maxval(abs(kt - ke)) > 1.0e-3_dp * maxval(abs(ke)), trim(what) // ': theta moves the tangent')
    call check_small(maxval(abs(kt - transpose(kt))) / maxval(abs(kt)), tol_round(256), &
                     trim(what) // ': the tangent with theta symmetric')
  end subroutine check_theta_element

  !> F = I: no stress, and A the linear law (lambda = K - 2 mu/3): A_1111 =
  !> K + 4 mu/3, A_1122 = K - 2 mu/3, A_1212 = A_1221 = mu.
  subroutine check_reference(law, what)
    type(hyperelastic_t), intent(in) :: law
    character(len=*), intent(in) :: what
    real(dp) :: eye(3, 3), p5(5), a5(5, 5), mu, kb, ref(4)
    integer :: info, i
    eye = 0.0_dp
    do i = 1, 3
      eye(i, i) = 1.0_dp
    end do
    call first_piola(law, eye, p5, a5, info)
    mu = 2 * (law%c10 + law%c01)
    kb = law%bulk
    call check_small(maxval(abs(p5)) / kb, tol_round(64), what // ': no stress at F = I')
    ref = [kb + 4 * mu / 3, kb - 2 * mu / 3, mu, mu]
    call check_small(maxval(abs([a5(1, 1), a5(1, 4), a5(2, 2), a5(2, 3)] - ref)) / kb, tol_round(64), &
                     what // ': A at F = I is the linear law (K, mu)')
    call check_close(a5(5, 5), kb + 4 * mu / 3, tol_round(64), what // ': A_3333 at F = I')
  end subroutine check_reference

  !> A large rigid rotation Q (1.1 rad in the plane) of a stretched state:
  !> the same W, sigma' = Q sigma Q', the same invariants tr sigma and det.
  subroutine check_objectivity(law)
    type(hyperelastic_t), intent(in) :: law
    real(dp) :: f0(3, 3), q(3, 3), s0(4), s1(4), m0(2, 2), m1(2, 2), rot(2, 2)
    integer :: info
    f0 = reshape([1.3_dp, 0.1_dp, 0.0_dp, -0.2_dp, 0.75_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
    q = 0.0_dp
    q(1, 1) = cos(1.1_dp); q(2, 1) = sin(1.1_dp); q(1, 2) = -q(2, 1); q(2, 2) = q(1, 1); q(3, 3) = 1.0_dp
    call check_close(strain_energy(law, matmul(q, f0)), strain_energy(law, f0), tol_round(64), &
                     'objectivity: W(Q F) = W(F)')
    call cauchy_stress(law, f0, s0, info)
    call cauchy_stress(law, matmul(q, f0), s1, info)
    m0 = reshape([s0(1), s0(3), s0(3), s0(2)], [2, 2])
    m1 = reshape([s1(1), s1(3), s1(3), s1(2)], [2, 2])
    rot = q(1:2, 1:2)
    call check_small(maxval(abs(m1 - matmul(rot, matmul(m0, transpose(rot))))) / maxval(abs(s0)), tol_round(64), &
                     'objectivity: sigma(Q F) = Q sigma(F) Q''')
    call check_close(s1(1) + s1(2) + s1(4), s0(1) + s0(2) + s0(4), tol_round(256), &
                     'objectivity: tr sigma unchanged')
    call check_close(s1(1) * s1(2) - s1(3)**2, s0(1) * s0(2) - s0(3)**2, tol_round(256), &
                     'objectivity: in-plane det sigma unchanged')
    call check_close(s1(4), s0(4), tol_round(256), 'objectivity: sigma_zz unchanged')
    call check_close(largest_stretch(matmul(q, f0)), largest_stretch(f0), tol_round(16), &
                     'objectivity: largest stretch unchanged')
  end subroutine check_objectivity

  !> The small-strain moduli: E = 9 K mu / (3 K + mu), nu = (3K - 2mu) / (2 (3K + mu)).
  subroutine check_moduli()
    type(hyperelastic_t) :: law
    real(dp) :: e, nu
    call make_hyperelastic(0.5_dp, 0.0_dp, 1000.0_dp, law)
    call initial_moduli(law, e, nu)
    call check_close(e / (2 * (1 + nu)), 1.0_dp, tol_round(16), 'initial moduli: E / 2 (1 + nu) = mu')
    call check_close(e / (3 * (1 - 2 * nu)), 1000.0_dp, tol_round(4096), 'initial moduli: E / 3 (1 - 2 nu) = K')
  end subroutine check_moduli

  !> A distorted element of nen nodes: its reference nodes mapped by a
  !> smooth distortion (curved edges on the quadratic ones), shifted to
  !> x >= 0.5 (axisymmetric: away from the axis).
  subroutine distorted_element(nen, xe)
    integer, intent(in) :: nen
    real(dp), intent(out) :: xe(2, nen)
    real(dp) :: xi(2)
    integer :: a
    do a = 1, nen
      xi = reference_node(nen, a)
      xe(1, a) = 1.5_dp + 0.8_dp * xi(1) + 0.15_dp * xi(2) + 0.05_dp * xi(2)**2
      xe(2, a) = 0.3_dp + 0.1_dp * xi(1) + 0.7_dp * xi(2) - 0.04_dp * xi(1)**2
    end do
  end subroutine distorted_element

  !> f_int against the differences of the energy, K against those of f_int.
  subroutine check_element(nen, axisymmetric, fbar)
    integer, intent(in) :: nen
    logical, intent(in) :: axisymmetric, fbar
    real(dp) :: xe(2, nen), ue(2 * nen), up(2 * nen), um(2 * nen), fe(2 * nen), fp(2 * nen), fm(2 * nen)
    real(dp) :: ke(2 * nen, 2 * nen), kd(2 * nen, 2 * nen), gd(2 * nen), ep, em
    integer :: j, info, i1, i2
    character(len=40) :: what
    write(what, '(a, i0, a, a)') 'element ', nen, merge(' axisymmetric', ' plane strain', axisymmetric), &
      merge(' F-bar', '      ', fbar)
    call distorted_element(nen, xe)
    do j = 1, nen                                    ! a smooth large deformation plus a ripple
      ue(2 * j - 1) = 0.2_dp * xe(2, j) - 0.1_dp * (xe(1, j) - 1.5_dp) + 0.02_dp * sin(3.0_dp * j)
      ue(2 * j) = -0.25_dp * (xe(2, j) - 0.3_dp) + 0.1_dp * (xe(1, j) - 1.5_dp)**2 + 0.02_dp * cos(2.0_dp * j)
    end do
    call finite_strain_response(nen, xe, ue, mooney, axisymmetric, 1.0_dp, fe, ke, info, fbar)
    call check(info == 0, trim(what) // ': no inverted point')
    do j = 1, 2 * nen
      up = ue; um = ue
      up(j) = up(j) + h
      um(j) = um(j) - h
      call finite_strain_energy(nen, xe, up, mooney, axisymmetric, 1.0_dp, ep, i1, fbar)
      call finite_strain_energy(nen, xe, um, mooney, axisymmetric, 1.0_dp, em, i2, fbar)
      gd(j) = (ep - em) / (2 * h)
      call finite_strain_response(nen, xe, up, mooney, axisymmetric, 1.0_dp, fp, info=i1, fbar=fbar)
      call finite_strain_response(nen, xe, um, mooney, axisymmetric, 1.0_dp, fm, info=i2, fbar=fbar)
      kd(:, j) = (fp - fm) / (2 * h)
    end do
    call check_small(maxval(abs(fe - gd)) / maxval(abs(fe)), fd_tol, trim(what) // ': f_int = dE/du')
    call check_small(maxval(abs(ke - kd)) / maxval(abs(ke)), fd_tol, trim(what) // ': K = df_int/du')
    call check_small(maxval(abs(ke - transpose(ke))) / maxval(abs(ke)), tol_round(256), trim(what) // ': K symmetric')
  end subroutine check_element

  !> Four Q1 on a 2 x 2 patch of [1, 2] x [0, 1] whose interior node is moved
  !> off the centre, under u = (F0 - I) X, F0 = [[1.25, 0.3], [-0.1, 0.8]]
  !> in plane strain (axisymmetric: u_r = (lr - 1) R, u_z = (lz - 1) Z: a
  !> homogeneous state with the hoop stretch lr, as a linear field must be).
  !> Every point has the same P: no force on the interior node, and the
  !> forces on the right edge (X = 2) add up to P11 and P21 times its length
  !> (times 2 pi R in axisymmetry).
  subroutine check_patch(axisymmetric, fbar)
    logical, intent(in) :: axisymmetric, fbar
    real(dp) :: x(2, 9), u(18), fsum(18), xe(2, 4), ue(8), fe(8), f0(3, 3), p5(5), a5(5, 5), sig4(4), jac, lam
    integer :: conn(4, 4), e, a, info, ierr
    character(len=20) :: what
    what = merge('axisymmetric', 'plane strain', axisymmetric)
    if (fbar) what = trim(what) // ' F-bar'
    x = reshape([1.0_dp, 0.0_dp, 1.5_dp, 0.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, 0.5_dp, 1.58_dp, 0.43_dp, 2.0_dp, 0.5_dp, &
                 1.0_dp, 1.0_dp, 1.5_dp, 1.0_dp, 2.0_dp, 1.0_dp], [2, 9])
    conn = reshape([1, 2, 5, 4, 2, 3, 6, 5, 4, 5, 8, 7, 5, 6, 9, 8], [4, 4])
    f0 = 0.0_dp
    if (axisymmetric) then
      f0(1, 1) = 1.2_dp; f0(2, 2) = 0.8_dp; f0(3, 3) = 1.2_dp
    else
      f0(1:2, 1:2) = reshape([1.25_dp, -0.1_dp, 0.3_dp, 0.8_dp], [2, 2]); f0(3, 3) = 1.0_dp
    end if
    do a = 1, 9
      u(2 * a - 1:2 * a) = matmul(f0(1:2, 1:2), x(:, a)) - x(:, a)
    end do
    fsum = 0.0_dp
    ierr = 0
    do e = 1, 4
      xe = x(:, conn(:, e))
      do a = 1, 4
        ue(2 * a - 1:2 * a) = u(2 * conn(a, e) - 1:2 * conn(a, e))
      end do
      call finite_strain_response(4, xe, ue, mooney, axisymmetric, 1.0_dp, fe, info=info, fbar=fbar)
      ierr = max(ierr, info)
      do a = 1, 4
        fsum(2 * conn(a, e) - 1:2 * conn(a, e)) = fsum(2 * conn(a, e) - 1:2 * conn(a, e)) + fe(2 * a - 1:2 * a)
      end do
      call finite_strain_state(4, xe, ue, mooney, axisymmetric, sig4, jac, lam, info)
      ierr = max(ierr, info)
    end do
    call check(ierr == 0, 'patch ' // trim(what) // ': no inverted point')
    call first_piola(mooney, f0, p5, a5, info)
    call check_small(maxval(abs(fsum(9:10))) / maxval(abs(p5)), tol_round(256), &
                     'patch ' // trim(what) // ': no force on the interior node')
    if (axisymmetric) then          ! int_0^1 P11 2 pi R dZ at R = 2, and no P21
      call check_close(fsum(5) + fsum(11) + fsum(17), p5(1) * 2 * acos(-1.0_dp) * 2, tol_round(256), &
                       'patch axisymmetric: right edge force = P11 2 pi R')
    else
      call check_close(fsum(5) + fsum(11) + fsum(17), p5(1), tol_round(256), &
                       'patch plane strain: right edge force x = P11 L')
      call check_close(fsum(6) + fsum(12) + fsum(18), p5(3), tol_round(256), &
                       'patch plane strain: right edge force y = P21 L')
    end if
    call check_close(jac, f0(1, 1) * f0(2, 2) * f0(3, 3) - f0(1, 2) * f0(2, 1) * f0(3, 3), tol_round(16), &
                     'patch ' // trim(what) // ': J of the state')
  end subroutine check_patch

  !> F-bar on a Q1 under a non-homogeneous field: the element energy with
  !> F-bar equals the one of the same law at every point's F scaled to the
  !> centre's J (computed here from the definition, plane strain: in-plane
  !> block times (J0/J)^(1/2)); and a field whose J varies differs from the
  !> plain energy (F-bar is not a no-op).
  subroutine check_fbar_volume()
    real(dp) :: xe(2, 4), ue(8), e_bar, e_plain, e_ref, xi(2, 4), detj, f(3, 3), f0(3, 3), jr
    integer :: info, q, a
    xe = reshape([0.0_dp, 0.0_dp, 1.2_dp, 0.1_dp, 1.1_dp, 0.9_dp, -0.1_dp, 1.0_dp], [2, 4])
    do a = 1, 4
      ue(2 * a - 1) = 0.1_dp * xe(1, a) * xe(2, a)
      ue(2 * a) = -0.15_dp * xe(2, a) + 0.05_dp * xe(1, a)
    end do
    call finite_strain_energy(4, xe, ue, neo, .false., 1.0_dp, e_bar, info, .true.)
    call finite_strain_energy(4, xe, ue, neo, .false., 1.0_dp, e_plain, info)
    f0 = q1_gradient(xe, ue, [0.0_dp, 0.0_dp], detj)
    xi = reshape([-1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp], [2, 4]) / sqrt(3.0_dp)
    e_ref = 0.0_dp
    do q = 1, 4
      f = q1_gradient(xe, ue, xi(:, q), detj)
      jr = (f0(1, 1) * f0(2, 2) - f0(1, 2) * f0(2, 1)) / (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1))
      f(1:2, 1:2) = sqrt(jr) * f(1:2, 1:2)
      e_ref = e_ref + strain_energy(neo, f) * detj
    end do
    call check_close(e_bar, e_ref, tol_round(256), 'F-bar Q1: the energy of F scaled to the centre''s J')
    call check(abs(e_bar - e_plain) > 1.0e-6_dp * abs(e_plain), 'F-bar Q1: differs from the plain energy when J varies')
  end subroutine check_fbar_volume

  !> F of a plane-strain Q1 at reference point p, and det J of its map there.
  function q1_gradient(xe, ue, p, detj) result(g)
    real(dp), intent(in) :: xe(2, 4), ue(8), p(2)
    real(dp), intent(out) :: detj
    real(dp) :: g(3, 3), n(4), dndx(2, 4)
    integer :: b
    call shape_at(4, xe, p, n, dndx, detj)
    g = 0.0_dp
    g(1, 1) = 1.0_dp; g(2, 2) = 1.0_dp; g(3, 3) = 1.0_dp
    do b = 1, 4
      g(1, 1:2) = g(1, 1:2) + ue(2 * b - 1) * dndx(:, b)
      g(2, 1:2) = g(2, 1:2) + ue(2 * b) * dndx(:, b)
    end do
  end function q1_gradient

  !> An element turned inside out: info names the point, no NaN.
  subroutine check_inverted()
    real(dp) :: xe(2, 4), ue(8), fe(8), ke(8, 8)
    integer :: info
    xe = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp], [2, 4])
    ue = 0.0_dp
    ue(6) = -1.5_dp; ue(8) = -1.5_dp                  ! the top pushed below the bottom
    call finite_strain_response(4, xe, ue, neo, .false., 1.0_dp, fe, ke, info)
    call check(info > 0, 'inverted element: info names a point with J <= 0')
  end subroutine check_inverted

end program test_finite_strain
