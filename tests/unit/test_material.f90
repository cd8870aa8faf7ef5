!> Elasticity tensors against their closed forms.
program test_material
  use kinds, only: dp
  use material, only: elasticity_t, make_isotropic, make_orthotropic, out_of_plane_stress, von_mises
  use testing, only: check_close, check_small, finish_tests, tol_round
  implicit none
  type(elasticity_t) :: a, b, c
  real(dp) :: e, nu, lam, mu, dref(3, 3), sig(3)

  e = 210.0_dp; nu = 0.3_dp
  lam = e * nu / ((1 + nu) * (1 - 2 * nu)); mu = e / (2 * (1 + nu))
  ! plane strain: D = [[lam+2mu, lam, 0], [lam, lam+2mu, 0], [0, 0, mu]]
  call make_isotropic(e, nu, .false., a)
  dref = reshape([lam + 2 * mu, lam, 0.0_dp, lam, lam + 2 * mu, 0.0_dp, 0.0_dp, 0.0_dp, mu], [3, 3])
  call check_small(maxval(abs(a%d - dref)) / e, tol_round(16), 'isotropic plane strain D')
  ! plane stress: D = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]]
  call make_isotropic(e, nu, .true., b)
  dref = e / (1 - nu**2) * reshape([1.0_dp, nu, 0.0_dp, nu, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, (1 - nu) / 2], [3, 3])
  call check_small(maxval(abs(b%d - dref)) / e, tol_round(16), 'isotropic plane stress D')
  ! an isotropic law is invariant under rotation
  call make_orthotropic(e, e, e, nu, nu, nu, mu, 37.0_dp, .false., c)
  call check_small(maxval(abs(c%d - a%d)) / e, tol_round(16), 'isotropic law rotation-invariant')
  ! orthotropic rotated by 90 degrees swaps the axes
  call make_orthotropic(100.0_dp, 10.0_dp, 10.0_dp, 0.25_dp, 0.25_dp, 0.3_dp, 5.0_dp, 90.0_dp, .true., b)
  call make_orthotropic(10.0_dp, 100.0_dp, 10.0_dp, 0.025_dp, 0.25_dp, 0.3_dp, 5.0_dp, 0.0_dp, .true., c)
  call check_small(maxval(abs(b%d - c%d)) / 100.0_dp, tol_round(16), 'orthotropic 90 degrees = swapped axes')
  ! plane stress orthotropic: D11 = E1 / (1 - nu12 nu21), nu21 = nu12 E2/E1
  call make_orthotropic(100.0_dp, 10.0_dp, 10.0_dp, 0.25_dp, 0.25_dp, 0.3_dp, 5.0_dp, 0.0_dp, .true., b)
  call check_close(b%d(1, 1), 100.0_dp / (1 - 0.25_dp * 0.025_dp), tol_round(16), 'orthotropic plane stress D11')
  call check_close(b%d(3, 3), 5.0_dp, tol_round(16), 'orthotropic G12')
  ! plane strain isotropic: sigma_zz = nu (sxx + syy)
  sig = [3.0_dp, -1.0_dp, 2.0_dp]
  call check_close(out_of_plane_stress(a, sig), nu * 2.0_dp, tol_round(16), 'plane strain sigma_zz')
  ! von Mises of a uniaxial plane stress state is |sigma|
  call make_isotropic(e, nu, .true., b)
  call check_close(von_mises(b, [-7.0_dp, 0.0_dp, 0.0_dp]), 7.0_dp, tol_round(16), 'von Mises uniaxial')
  call check_close(von_mises(b, [0.0_dp, 0.0_dp, 2.0_dp]), sqrt(3.0_dp) * 2.0_dp, tol_round(16), 'von Mises pure shear')
  call finish_tests()
end program test_material
