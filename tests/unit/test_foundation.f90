!> foundation: the springs' matrices against their closed forms, and the
!> rigid modes that springs leave free (rigid_modes counts them).
!>   - a straight 2-node edge of length L: K_s = M (x) (kn n n' + kt t t'),
!>     M = L/6 [2 1; 1 2] the edge's consistent mass matrix, at any angle;
!>   - a straight 3-node edge: M = L/30 [4 -1 2; -1 4 2; 2 2 16];
!>   - axisymmetric, a 2-node edge from r1 to r2: M = 2 pi L/12 [3 r1 + r2,
!>     r1 + r2; r1 + r2, r1 + 3 r2];
!>   - each to n eps of its size (a computed ratio below 30, LAPACK's manner);
!>   - a 4 x 3 rectangle held by springs only: kn on its bottom leaves the
!>     translation x free (one mode), kn and kt none, a point spring kx, ky at
!>     one node the rotation about it (one mode); K R = 0 to round-off, K with
!>     the springs.
program test_foundation
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh
  use mesh_rect, only: make_rect_mesh
  use material, only: make_isotropic
  use body, only: body_t, number_equations, build_pattern, assemble_stiffness
  use foundation, only: edge_spring_matrix, add_spring
  use sparse_matrix, only: csc_t
  use rigid_modes, only: floating_t, find_floating_modes
  use testing, only: check, check_small, finish_tests, dense_symmetric
  implicit none
  real(dp), parameter :: threshold = 30.0_dp, pi = acos(-1.0_dp)
  real(dp) :: eps

  eps = epsilon(1.0_dp)
  call linear_edges()
  call quadratic_edge()
  call axisymmetric_edge()
  call held_by_springs('kn', 1)
  call held_by_springs('kn kt', 0)
  call held_by_springs('point', 1)
  call finish_tests()

contains

  !> K_s of 2-node edges at several angles against M (x) P.
  subroutine linear_edges()
    real(dp) :: ke(6, 6), want(4, 4), xe(2, 2), n(2), t(2), p(2, 2), m(2, 2), l, theta
    real(dp), parameter :: kn = 7.0_dp, kt = 3.0_dp, w = 0.5_dp
    integer :: i, a, b
    l = 1.7_dp
    do i = 0, 4
      theta = i * pi / 7.0_dp
      xe(:, 1) = [0.3_dp, -0.2_dp]
      xe(:, 2) = xe(:, 1) + l * [cos(theta), sin(theta)]
      call edge_spring_matrix(2, xe, kn, kt, w, .false., ke)
      t = [cos(theta), sin(theta)]
      n = [t(2), -t(1)]
      p = kn * spread(n, 2, 2) * spread(n, 1, 2) + kt * spread(t, 2, 2) * spread(t, 1, 2)
      m = w * l / 6.0_dp * reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
      do b = 1, 2
        do a = 1, 2
          want(2 * a - 1:2 * a, 2 * b - 1:2 * b) = m(a, b) * p
        end do
      end do
      call check_small(maxval(abs(ke(1:4, 1:4) - want)) / (maxval(abs(want)) * 4 * eps), threshold, &
                       'linear edge at angle pi*' // achar(48 + i) // '/7: K_s = M (x) (kn n n'' + kt t t'')')
    end do
  end subroutine linear_edges

  !> A straight 3-node edge (the middle node at its middle), turned by 0.4 rad.
  subroutine quadratic_edge()
    real(dp) :: ke(6, 6), want(6, 6), xe(2, 3), n(2), t(2), p(2, 2), m(3, 3), l
    real(dp), parameter :: kn = 2.0_dp, kt = 5.0_dp
    integer :: a, b
    l = 2.5_dp
    t = [cos(0.4_dp), sin(0.4_dp)]
    n = [t(2), -t(1)]
    xe(:, 1) = [1.0_dp, 1.0_dp]
    xe(:, 2) = xe(:, 1) + l * t
    xe(:, 3) = 0.5_dp * (xe(:, 1) + xe(:, 2))
    call edge_spring_matrix(3, xe, kn, kt, 1.0_dp, .false., ke)
    p = kn * spread(n, 2, 2) * spread(n, 1, 2) + kt * spread(t, 2, 2) * spread(t, 1, 2)
    m = l / 30.0_dp * reshape([4.0_dp, -1.0_dp, 2.0_dp, -1.0_dp, 4.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 16.0_dp], [3, 3])
    do b = 1, 3
      do a = 1, 3
        want(2 * a - 1:2 * a, 2 * b - 1:2 * b) = m(a, b) * p
      end do
    end do
    call check_small(maxval(abs(ke - want)) / (maxval(abs(want)) * 6 * eps), threshold, &
                     'quadratic edge: K_s = M (x) (kn n n'' + kt t t''), M = L/30 [4 -1 2; -1 4 2; 2 2 16]')
  end subroutine quadratic_edge

  !> A horizontal 2-node edge from r1 to r2 (normal along z): the z-z block is
  !> kn 2 pi L/12 [3 r1 + r2, r1 + r2; r1 + r2, r1 + 3 r2], the r-r block kt times it.
  subroutine axisymmetric_edge()
    real(dp) :: ke(6, 6), want(4, 4), m(2, 2), r1, r2, l
    real(dp), parameter :: kn = 4.0_dp, kt = 1.5_dp
    r1 = 0.5_dp
    r2 = 2.0_dp
    l = r2 - r1
    call edge_spring_matrix(2, reshape([r1, 3.0_dp, r2, 3.0_dp], [2, 2]), kn, kt, 1.0_dp, .true., ke)
    m = 2 * pi * l / 12.0_dp * reshape([3 * r1 + r2, r1 + r2, r1 + r2, r1 + 3 * r2], [2, 2])
    want = 0.0_dp
    want(1:3:2, 1:3:2) = kt * m
    want(2:4:2, 2:4:2) = kn * m
    call check_small(maxval(abs(ke(1:4, 1:4) - want)) / (maxval(abs(want)) * 4 * eps), threshold, &
                     'axisymmetric edge: K_s = 2 pi int N''N r ds (x) diag(kt, kn)')
  end subroutine axisymmetric_edge

  !> A 4 x 3 rectangle (2 x 1) with no FIX, held by springs only: the free
  !> modes, and K R = 0 with the springs in K.
  subroutine held_by_springs(how, modes_expected)
    character(len=*), intent(in) :: how
    integer, intent(in) :: modes_expected
    type(body_t) :: bd(1)
    type(diag_t) :: diag
    type(floating_t) :: fl
    type(csc_t) :: k
    type(error_t), allocatable :: err
    logical, allocatable :: fixed(:)
    integer, allocatable :: eq(:)
    real(dp), allocatable :: kd(:,:), rhs(:), zero(:)
    real(dp) :: ke(6, 6)
    integer :: n, nfree, i, a, b
    call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.0_dp, 4, 3, 'tri3 ', 'alt', bd(1)%mesh, err)
    call finalize_mesh(bd(1)%mesh, 'springs', diag)
    call make_isotropic(1000.0_dp, 0.3_dp, .false., bd(1)%law)
    n = 2 * bd(1)%mesh%nnode
    if (how == 'point') then
      ke = 0.0_dp
      ke(1, 1) = 40.0_dp
      ke(2, 2) = 60.0_dp
      call add_spring(bd(1)%springs, [1], ke(1:2, 1:2), 1)
    else
      do i = 1, bd(1)%mesh%bnd(3)%nseg             ! rect boundary 3: bottom
        a = bd(1)%mesh%bnd(3)%seg(1, i)
        b = bd(1)%mesh%bnd(3)%seg(2, i)
        call edge_spring_matrix(2, bd(1)%mesh%x(:, [a, b]), 50.0_dp, merge(20.0_dp, 0.0_dp, how == 'kn kt'), &
                                1.0_dp, .false., ke)
        call add_spring(bd(1)%springs, [a, b], ke(1:4, 1:4), 1)
      end do
    end if
    call check(bd(1)%mesh%bnd(3)%name == 'bottom', 'springs ' // how // ': rect boundary 3 is bottom')
    allocate(fixed(n), source=.false.)
    call find_floating_modes(bd, fixed, fl)
    call check(fl%k == modes_expected, 'springs ' // how // ': number of free modes')
    if (fl%k /= modes_expected .or. fl%k == 0) return
    allocate(zero(n), rhs(n), source=0.0_dp)
    call number_equations(fixed, eq, nfree)
    call build_pattern(bd, eq, nfree, k, err)
    call assemble_stiffness(bd, eq, zero, k, rhs)
    call dense_symmetric(k%colptr, k%rowind, k%val, kd)
    call check_small(maxval(abs(matmul(kd, fl%r))) / (maxval(sum(abs(kd), dim=2)) * maxval(abs(fl%r)) * n * eps), &
                     threshold, 'springs ' // how // ': ||K R||_inf / (||K||_inf ||R||_inf n eps), springs in K')
  end subroutine held_by_springs

end program test_foundation
