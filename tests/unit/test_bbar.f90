!> The B-bar kernels (elements: pressure_modes, dilatation_projection,
!> replace_dilatation; the kernels' optional np) against closed forms: the
!> projected dilatation of fields whose dilatation lies in the pressure space
!> (the mean of a uniform strain on a distorted Q1, a linear dilatation on a
!> parallelogram Q9, the hoop strain of u_r = r in axisymmetry), a uniform strain
!> kept by B_bar, the rigid modes (and only they) in the kernel of the B-bar
!> stiffness, and the stiffness's volumetric energy cut down: at nu = 0.4999
!> a bending mode of Q1 costs lambda without B-bar, mu with it.
program test_bbar
  use kinds, only: dp
  use material, only: elasticity_t, make_isotropic
  use elements, only: pressure_modes, dilatation_projection, replace_dilatation, pressure_basis, element_stiffness, &
                      element_strain, max_nen, max_np, shape_at, strain_operator
  use axisymmetric_elements, only: axi_element_stiffness, axi_element_strain
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  implicit none
  type(elasticity_t) :: law
  real(dp) :: xq(2, 4), x9(2, 9), g(max_np, 2 * max_nen), u(18), p(max_np), theta, ke(8, 8), ke0(8, 8)
  real(dp) :: eps(3), eps4(4), n(9), dndx(2, 9), detj, b(3, 18), xi(2), rig(8, 3)
  integer :: a

  call check(pressure_modes(3) == 0 .and. pressure_modes(4) == 1 .and. pressure_modes(6) == 0 .and. &
             pressure_modes(8) == 3 .and. pressure_modes(9) == 3, 'pressure_modes: Q1 1, Q8 and Q9 3, triangles 0')

  ! a distorted Q1 and the uniform strain of u = (0.3 x + 0.2 y, -0.1 x + 0.5 y): theta_bar = 0.8
  xq = reshape([0.0_dp, 0.0_dp, 1.3_dp, 0.2_dp, 1.1_dp, 0.9_dp, 0.2_dp, 1.2_dp], [2, 4])
  do a = 1, 4
    u(2 * a - 1:2 * a) = [0.3_dp * xq(1, a) + 0.2_dp * xq(2, a), -0.1_dp * xq(1, a) + 0.5_dp * xq(2, a)]
  end do
  call dilatation_projection(4, xq, 1, .false., g(1:1, 1:8))
  call check_close(dot_product(g(1, 1:8), u(1:8)), 0.8_dp, tol_round(8), 'Q1: mean dilatation of a uniform strain')
  call element_strain(4, xq, u(1:8), eps, 1)
  call check_small(maxval(abs(eps - [0.3_dp, 0.5_dp, 0.1_dp])), tol_round(8), 'Q1: B_bar keeps a uniform strain')
  ! a bilinear field: theta = 1 + y varies; theta_bar is its mean, not a point value
  u = 0.0_dp
  do a = 1, 4
    u(2 * a - 1) = xq(1, a) * xq(2, a)                 ! u_x = x y: theta = y (+ 0)
    u(2 * a) = xq(2, a)                                ! u_y = y:   theta = y + 1
  end do
  call dilatation_projection(4, xq, 1, .false., g(1:1, 1:8))
  theta = dot_product(g(1, 1:8), u(1:8))
  xi = [0.3_dp, -0.6_dp]
  call shape_at(4, xq, xi, n(1:4), dndx(:, 1:4), detj)
  call strain_operator(4, dndx(:, 1:4), b(:, 1:8))
  call replace_dilatation(4, xq, 1, g(1:1, 1:8), n(1:4), b(:, 1:8))
  eps = matmul(b(:, 1:8), u(1:8))
  call check_close(eps(1) + eps(2), theta, tol_round(8), 'Q1: the trace of B_bar u is theta_bar at any point')

  ! a Q9 and u = (x^2 / 2, 0): theta = x, linear, in P_e: theta_bar = x
  ! (x^2 is in the Q9 space of an affine element: a parallelogram, mid-side nodes at the middles)
  x9 = reshape([0.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, 2.5_dp, 1.5_dp, 0.5_dp, 1.5_dp, &
                1.0_dp, 0.0_dp, 2.25_dp, 0.75_dp, 1.5_dp, 1.5_dp, 0.25_dp, 0.75_dp, 1.25_dp, 0.75_dp], [2, 9])
  u = 0.0_dp
  do a = 1, 9
    u(2 * a - 1) = 0.5_dp * x9(1, a)**2
  end do
  call dilatation_projection(9, x9, 3, .false., g(1:3, 1:18))
  call pressure_basis(9, x9, 3, [1.7_dp, 0.2_dp], p(1:3))
  call check_close(dot_product(p(1:3), matmul(g(1:3, 1:18), u(1:18))), 1.7_dp, tol_round(16), &
                   'Q9: a linear dilatation is its own projection (theta_bar = x at x = 1.7)')

  ! axisymmetric: u_r = r, u_z = 0 on a Q1 off the axis: err = ett = 1, theta = 2
  xq = reshape([1.0_dp, 0.0_dp, 1.5_dp, 0.1_dp, 1.4_dp, 0.7_dp, 0.9_dp, 0.6_dp], [2, 4])
  u = 0.0_dp
  do a = 1, 4
    u(2 * a - 1) = xq(1, a)
  end do
  call dilatation_projection(4, xq, 1, .true., g(1:1, 1:8))
  call check_close(dot_product(g(1, 1:8), u(1:8)), 2.0_dp, tol_round(8), 'axisymmetric Q1: theta_bar of u_r = r is 2')
  call axi_element_strain(4, xq, u(1:8), eps4, 1)
  call check_small(maxval(abs(eps4 - [1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp])), tol_round(8), &
                   'axisymmetric Q1: B4_bar keeps u_r = r')

  ! the B-bar stiffness at nu = 0.4999: symmetric, 3 zero eigenvalues (rigid modes), 5 positive
  call make_isotropic(1000.0_dp, 0.4999_dp, .false., law)
  xq = reshape([0.0_dp, 0.0_dp, 1.3_dp, 0.2_dp, 1.1_dp, 0.9_dp, 0.2_dp, 1.2_dp], [2, 4])
  call element_stiffness(4, xq, law%d, 1.0_dp, ke, 1)
  call check_small(maxval(abs(ke - transpose(ke))) / maxval(abs(ke)), tol_round(64), 'Q1 B-bar ke symmetric')
  do a = 1, 4                                           ! the rigid modes: x, y translations, rotation
    rig(2 * a - 1:2 * a, 1) = [1.0_dp, 0.0_dp]
    rig(2 * a - 1:2 * a, 2) = [0.0_dp, 1.0_dp]
    rig(2 * a - 1:2 * a, 3) = [-xq(2, a), xq(1, a)]
  end do
  call check_small(maxval(abs(matmul(ke, rig))) / maxval(abs(ke)), tol_round(64), 'Q1 B-bar ke: the rigid modes cost nothing')
  ! ke + c R R' positive definite (Cholesky succeeds): nothing else is free, rank 5
  ke0 = ke + maxval(abs(ke)) * matmul(rig, transpose(rig))
  call check(positive_definite(ke0), 'Q1 B-bar ke: no other zero-energy mode (rank 5)')
  ! a bending mode u_x = x y (theta = y, mean 0 on the square): with B, lambda int y^2; with B_bar, mu only
  xq = reshape([-1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp], [2, 4])
  u = 0.0_dp
  do a = 1, 4
    u(2 * a - 1) = xq(1, a) * xq(2, a)
  end do
  call element_stiffness(4, xq, law%d, 1.0_dp, ke, 1)
  call element_stiffness(4, xq, law%d, 1.0_dp, ke0)
  call check(dot_product(u(1:8), matmul(ke0, u(1:8))) > 1.0e3_dp * dot_product(u(1:8), matmul(ke, u(1:8))), &
             'Q1 bending mode at nu = 0.4999: B-bar energy 1000 times below the locked one')
  call axi_element_stiffness(4, xq + spread([3.0_dp, 0.0_dp], 2, 4), law%d4, ke, 1)
  call check_small(maxval(abs(ke - transpose(ke))) / maxval(abs(ke)), tol_round(64), 'axisymmetric Q1 B-bar ke symmetric')
  call finish_tests()

contains

  !> Cholesky of a symmetric matrix succeeds with pivots above 1e-8 of its largest entry.
  logical function positive_definite(m) result(ok)
    real(dp), intent(in) :: m(:,:)
    real(dp) :: l(size(m, 1), size(m, 1)), d
    integer :: i, j
    l = 0.0_dp
    ok = .false.
    do j = 1, size(m, 1)
      d = m(j, j) - dot_product(l(j, 1:j - 1), l(j, 1:j - 1))
      if (d <= 1.0e-8_dp * maxval(abs(m))) return
      l(j, j) = sqrt(d)
      do i = j + 1, size(m, 1)
        l(i, j) = (m(i, j) - dot_product(l(i, 1:j - 1), l(j, 1:j - 1))) / l(j, j)
      end do
    end do
    ok = .true.
  end function positive_definite

end program test_bbar
