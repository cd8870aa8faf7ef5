!> Axisymmetric kernels and the r-weighted mortar rule against closed forms:
!> D4 of an isotropic law, the rigid and the uniform-strain modes of B4, the
!> full-circle edge and body loads, and segment_rule's exactness for the
!> polynomial degrees the mortar integrals create.
program test_axisymmetric
  use kinds, only: dp
  use material, only: elasticity_t, make_isotropic, make_orthotropic, von_mises_4
  use axisymmetric_elements, only: radial_weight, axi_element_stiffness, axi_element_force, axi_edge_load, &
                                   axi_element_body_load, axi_element_strain
  use mortar_operator, only: segment_rule
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  implicit none
  real(dp), parameter :: pi = acos(-1.0_dp)
  type(elasticity_t) :: a, b
  real(dp) :: e, nu, lam, mu, dref(4, 4), xe(2, 4), xt(2, 3), ke(8, 8), u(8), f(8), fe(4), eps(4)
  real(dp) :: s(4), w(4), exact, sum_q, r0, r1
  integer :: nq, k, deg, i

  ! isotropic D4 (rr, zz, rz, tt): lam + 2 mu on the normal diagonal, lam off it, mu for grz
  e = 210.0_dp; nu = 0.3_dp
  lam = e * nu / ((1 + nu) * (1 - 2 * nu)); mu = e / (2 * (1 + nu))
  call make_isotropic(e, nu, .false., a)
  dref = lam
  dref(3, :) = 0.0_dp; dref(:, 3) = 0.0_dp
  dref(1, 1) = lam + 2 * mu; dref(2, 2) = lam + 2 * mu; dref(4, 4) = lam + 2 * mu; dref(3, 3) = mu
  call check_small(maxval(abs(a%d4 - dref)) / e, tol_round(16), 'isotropic D4 = 3D law on (rr, zz, rz, tt)')
  call make_orthotropic(e, e, e, nu, nu, nu, mu, 29.0_dp, .false., b)
  call check_small(maxval(abs(b%d4 - a%d4)) / e, tol_round(16), 'isotropic D4 invariant under the in-plane rotation')
  call check_close(von_mises_4([0.0_dp, 0.0_dp, 0.0_dp, 5.0_dp]), 5.0_dp, tol_round(16), 'von Mises of a pure hoop stress')

  ! a Q1 ring element away from the axis and a P1 one touching it
  xe = reshape([1.0_dp, 0.0_dp, 1.5_dp, 0.1_dp, 1.4_dp, 0.7_dp, 0.9_dp, 0.6_dp], [2, 4])
  xt = reshape([0.0_dp, 0.0_dp, 0.5_dp, 0.1_dp, 0.0_dp, 0.4_dp], [2, 3])
  call axi_element_stiffness(4, xe, a%d4, ke)
  call check_small(maxval(abs(ke - transpose(ke))) / maxval(abs(ke)), tol_round(16), 'Q1 ke symmetric')
  u = 0.0_dp; u(2::2) = 1.0_dp                       ! rigid translation along z: no force
  call check_small(maxval(abs(matmul(ke, u))) / maxval(abs(ke)), tol_round(16), 'Q1: translation along z is rigid')
  u = 0.0_dp; u(1::2) = 1.0_dp                       ! u_r = 1 strains the hoop: a force
  call check(dot_product(u, matmul(ke, u)) > 1.0e-2_dp * maxval(abs(ke)), &
             'Q1: translation along r is not rigid (hoop strain energy > 0)')
  ! u_r = c r, u_z = d z: err = ett = c, ezz = d at every point
  do i = 1, 4
    u(2 * i - 1) = 2.0e-3_dp * xe(1, i)
    u(2 * i) = -1.0e-3_dp * xe(2, i)
  end do
  call axi_element_strain(4, xe, u, eps)
  ! 16 roundings of the largest strain, 2e-3
  call check_small(maxval(abs(eps - [2.0e-3_dp, -1.0e-3_dp, 0.0_dp, 2.0e-3_dp])), tol_round(16, 2.0e-3_dp), &
                   'Q1: linear field strain')
  call axi_element_force(4, xe, a%d4, u, f)
  call check_small(maxval(abs(f - matmul(ke, u))) / maxval(abs(f)), tol_round(16), 'Q1: element force = ke u')

  ! loads: a traction per unit area on an edge, full circle: sum = t 2 pi r_mid L
  call axi_edge_load([0.0_dp, 0.0_dp], [2.0_dp, 0.0_dp], [0.0_dp, -3.0_dp], fe)
  call check_close(fe(2) + fe(4), -3.0_dp * 2 * pi * 1.0_dp * 2.0_dp, tol_round(16), 'edge load = t 2 pi r_mid L')
  call check_close(fe(4) / fe(2), 2.0_dp, tol_round(16), 'edge load from the axis: 1/3 and 2/3 of it')
  ! a body force per unit volume on the P1 triangle: sum = b 2 pi r_centroid area
  call axi_element_body_load(3, xt, [0.0_dp, 2.0_dp], f(1:6))
  call check_close(sum(f(2:6:2)), 2.0_dp * radial_weight(0.5_dp / 3.0_dp) * 0.5_dp * 0.5_dp * 0.4_dp, tol_round(16), &
                   'body load = b 2 pi r_c A (Pappus)')

  ! segment_rule: exact for s^k, k <= degree, times 2 pi r(s) on [s1, s2]
  r0 = 0.3_dp; r1 = 1.7_dp
  do deg = 1, 6
    do k = 0, deg
      call segment_rule([r0, 0.0_dp], [r1, 0.0_dp], 0.2_dp, 0.9_dp, deg, .true., s, w, nq)
      sum_q = sum(w(1:nq) * s(1:nq)**k)
      ! int_{0.2}^{0.9} s^k 2 pi ((1 - s) r0 + s r1) L ds, L = r1 - r0
      exact = 2 * pi * (r1 - r0) * (r0 * (0.9_dp**(k + 1) - 0.2_dp**(k + 1)) / (k + 1) + &
              (r1 - r0) * (0.9_dp**(k + 2) - 0.2_dp**(k + 2)) / (k + 2))
      call check_close(sum_q, exact, tol_round(16), 'segment_rule with 2 pi r exact for degree ' // char(48 + deg) // &
                       ', s^' // char(48 + k))
    end do
  end do
  call segment_rule([r0, 0.0_dp], [r1, 0.0_dp], 0.0_dp, 1.0_dp, 2, .true., s, w, nq)
  call check_close(real(nq, dp), 2.0_dp, 0.0_dp, 'P1 mortar products with 2 pi r: 2 points (degree 3)')
  call segment_rule([r0, 0.0_dp], [r1, 0.0_dp], 0.0_dp, 1.0_dp, 4, .true., s, w, nq)
  call check_close(real(nq, dp), 3.0_dp, 0.0_dp, 'quadratic mortar products with 2 pi r: 3 points (degree 5)')
  call finish_tests()
end program test_axisymmetric
