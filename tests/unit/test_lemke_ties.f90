!> Unit tests of Lemke's method (lcp_lemke) where round-off decides: exact
!> ties that the tableau's rank-1 updates blur, and rays.
!>  - Two friction LCPs of contact2d's own skate (tests/unit/data/skate_*.txt,
!>    provenance in data/README.md) on which the pivoting of 3f1a867 ended on
!>    a ray, although the problems have solutions (an exact-arithmetic replay
!>    solves the first in 27 pivots): a tie between z0's row and a degenerate
!>    row, 3.4e-8 apart after the updates.  Lemke must solve them; the
!>    solution is checked by the natural residual recomputed here from M, q
!>    and d, and for the floating block also by its equilibrium rows
!>    w_a+ = w_a- = 0 (the two rows of an equality, w_a+ + w_a- = 2 z0 on
!>    every tableau: the built-in tie).
!>  - A small floating block with that built-in tie: two normal rows, one
!>    mode, solved against its closed form.
!>  - A genuine ray: a positive semi-definite LCP with no feasible point (W
!>    y0 = 0, q'y0 < 0 for y0 = ones).  info 1, and the direction returned is
!>    Farkas' certificate y >= 0, W'y <= 0, q'y < 0, checked here from W and q;
!>    certifies_infeasible accepts it and refuses a vector that is not one.
program test_lemke_ties
  use kinds, only: dp, i8
  use testing, only: check, check_close, check_small, finish_tests, urand, tol_round
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_lemke_scaled
  use lcp_scaling, only: certifies_infeasible
  implicit none

  ! The skate LCPs' solutions are basic solutions refined on the data:
  ! measured natural residuals 2e-16.  1e-12 leaves room for another BLAS's
  ! roundings and still fails every point short of z0's exit: the near-ties
  ! Lemke passes on these problems are 1e-12 to 1e-7 of the data apart.
  real(dp), parameter :: tol_skate = 1.0e-12_dp
  integer(i8) :: seed
  seed = 20251206_i8

  call test_skate('tests/unit/data/skate_friction_lcp.txt', 'skate friction LCP, step 4', 0)
  call test_skate('tests/unit/data/skate_floating_lcp.txt', 'skate floating LCP, step 6', 2)
  call test_floating_block()
  call test_psd_ray(8)
  call finish_tests()

contains

  !> M, q, d of a file of tests/unit/data (data/README.md).
  subroutine read_lcp(path, m, q, d)
    character(len=*), intent(in) :: path
    real(dp), allocatable, intent(out) :: m(:,:), q(:), d(:)
    integer :: u, n
    open(newunit=u, file=path, status='old', action='read')
    read(u, *) n
    allocate(m(n, n), q(n), d(n))
    read(u, *) q
    read(u, *) d
    read(u, *) m
    close(u)
  end subroutine read_lcp

  !> The scaled natural residual max |min(z/d, d w)| / max |d q|, w = q + M z.
  real(dp) function natural_residual(m, q, d, z) result(r)
    real(dp), intent(in) :: m(:,:), q(:), d(:), z(:)
    real(dp), allocatable :: w(:)
    w = q + matmul(m, z)
    r = maxval(abs(min(z / d, d * w))) / maxval(abs(d * q))
  end function natural_residual

  !> One of the skate's LCPs: solved, to round-off, by the natural residual
  !> recomputed here; the last neq rows (an equality written as two
  !> inequalities) at zero.
  subroutine test_skate(path, name, neq)
    character(len=*), intent(in) :: path, name
    integer, intent(in) :: neq
    real(dp), allocatable :: m(:,:), q(:), d(:), z(:), w(:), y(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: n

    call read_lcp(path, m, q, d)
    n = size(q)
    allocate(z(n), y(n))
    call solve_lcp_lemke_scaled(m, q, d, z, opts, rep, y)
    call check(rep%info == 0, name // ': solved (info 0), not a ray')
    call check(all(z >= 0.0_dp), name // ': z >= 0')
    call check_small(natural_residual(m, q, d, z), tol_skate, name // ': natural residual, recomputed')
    call check(all(y == 0.0_dp), name // ': no ray direction when solved')
    if (neq > 0) then
      w = q + matmul(m, z)
      call check_small(maxval(abs(d(n - neq + 1:) * w(n - neq + 1:))) / maxval(abs(d * q)), tol_skate, &
                       name // ': the equilibrium rows w_a+ = w_a- = 0')
    end if
  end subroutine test_skate

  !> A block held by two normal rows only (no friction), G = [2 1; 1 2],
  !> gaps qn = (0.3, -0.1), its vertical translation (H = (1, 1)') loaded by
  !> e = 3: friction_modes' LCP z = [lambda; a+; a-],
  !>     M = [G -H H; H' 0 0; -H' 0 0],  q = [qn; -e; e].
  !> Both rows in contact: G lambda = alpha H - qn and H'lambda = e give
  !> alpha = (3 e + qn1 + qn2) / 2 = 4.6 and lambda = G^-1 (alpha H - qn) =
  !> (1.3, 1.7).  Every tableau has w_a+ + w_a- = 2 z0, so the last pivot is a
  !> tie between z0's row and a w_a row.
  subroutine test_floating_block()
    real(dp) :: m(4, 4), q(4), d(4), z(4), w(4)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    m = 0.0_dp
    m(1:2, 1:2) = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
    m(1:2, 3) = -1.0_dp
    m(1:2, 4) = 1.0_dp
    m(3, 1:2) = 1.0_dp
    m(4, 1:2) = -1.0_dp
    q = [0.3_dp, -0.1_dp, -3.0_dp, 3.0_dp]
    d = [1.0_dp / sqrt(2.0_dp), 1.0_dp / sqrt(2.0_dp), sqrt(2.0_dp), sqrt(2.0_dp)]   ! friction_modes' d
    call solve_lcp_lemke_scaled(m, q, d, z, opts, rep)
    call check(rep%info == 0, 'floating block: solved (info 0)')
    ! a handful of roundings on data of size 3
    call check_close(z(1), 1.3_dp, tol_round(16), 'floating block: lambda1 = 1.3')
    call check_close(z(2), 1.7_dp, tol_round(16), 'floating block: lambda2 = 1.7')
    call check_close(z(3) - z(4), 4.6_dp, tol_round(16), 'floating block: alpha = a+ - a- = 4.6')
    w = q + matmul(m, z)
    call check_small(maxval(abs(w)), tol_round(16, 3.0_dp), 'floating block: every w = 0 (both in contact, H''z = e)')
  end subroutine test_floating_block

  !> W = C C' (n x n, rank 3) with C' y0 = 0 for y0 = ones, q random with
  !> q'y0 < 0: W y0 = 0, so y0 is Farkas' certificate that no z >= 0 has
  !> q + W z >= 0.  Lemke, plain and scaled, ends on a ray whose direction
  !> must be a certificate too.
  subroutine test_psd_ray(n)
    integer, intent(in) :: n
    real(dp) :: c(n, 3), w(n, n), q(n), z(n), y(n), y0(n), d(n)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: i, j
    do j = 1, 3
      do i = 1, n
        c(i, j) = 2.0_dp * urand(seed) - 1.0_dp
      end do
      c(:, j) = c(:, j) - sum(c(:, j)) / n              ! C' y0 = 0
    end do
    w = matmul(c, transpose(c))
    do i = 1, n
      q(i) = 2.0_dp * urand(seed) - 1.0_dp
    end do
    q = q - (sum(q) / n + 0.5_dp)                       ! q'y0 = -n / 2
    y0 = 1.0_dp

    call check(certifies_infeasible(w, q, y0), 'psd ray: certifies_infeasible accepts y0 = ones')
    call check(.not. certifies_infeasible(w, q, y0 - 2.0_dp * merge(1.0_dp, 0.0_dp, [(i == 1, i = 1, n)])), &
               'psd ray: certifies_infeasible refuses a y with a negative entry')
    call check(.not. certifies_infeasible(w, -q, y0), 'psd ray: certifies_infeasible refuses y0 when q''y0 > 0')

    call solve_lcp_lemke(w, q, z, opts, rep, y)
    call check(rep%info == 1 .and. rep%stopped == 'ray', 'psd ray lemke: ray termination (info 1)')
    call check_ray(w, q, y, 'psd ray lemke')
    do i = 1, n
      d(i) = 1.0_dp / sqrt(w(i, i))
    end do
    call solve_lcp_lemke_scaled(w, q, d, z, opts, rep, y)
    call check(rep%info == 1, 'psd ray lemke scaled: ray termination (info 1)')
    call check_ray(w, q, y, 'psd ray lemke scaled')
  end subroutine test_psd_ray

  !> y is Farkas' certificate for (W, q), each inequality checked here to
  !> the round-off of its terms (64 roundings of |W|'y and |q|'y: the ray is
  !> read off a tableau of a few pivots on data of unit size).
  subroutine check_ray(w, q, y, name)
    real(dp), intent(in) :: w(:,:), q(:), y(:)
    character(len=*), intent(in) :: name
    call check(all(y >= 0.0_dp) .and. maxval(y) == 1.0_dp, name // ': direction y >= 0, largest entry 1')
    call check(all(matmul(transpose(w), y) <= tol_round(64) * matmul(transpose(abs(w)), y)), &
               name // ': W''y <= 0 (to round-off)')
    call check(dot_product(q, y) < -tol_round(64) * dot_product(abs(q), y), name // ': q''y < 0')
    call check(certifies_infeasible(w, q, y), name // ': certifies_infeasible accepts it')
  end subroutine check_ray

end program test_lemke_ties
