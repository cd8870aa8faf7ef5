!> contact_lcp: solve_contact on small problems solved by hand, with each of
!> the three solvers (lemke, pgs, pdas).  Each answer is checked against the
!> hand solution and against the conditions it must satisfy whatever the
!> solver (complementarity: mu >= 0, gap >= 0, mu'gap = 0; the equilibrium
!> H'mu = e; gap = q + W mu - H alpha as returned):
!>   - no free modes, LCP(W, q) with a known active set: 2 x 2 with one
!>     contact closed, mu = (1/2, 0), gap = (0, 3/2); 3 x 3 tridiagonal with
!>     two closed, mu = (14/15, 19/15, 0);
!>   - one free mode (a rigid block on two supports, compliance W = I, load e
!>     pressing it down, H = (1, 1)'): with the second support 1/2 lower both
!>     close, alpha = 5/4, mu = (5/4, 3/4); 3 lower, only the first closes,
!>     alpha = 2, mu = (2, 0), gap = (0, 1);
!>   - two free modes (sinking and tilting, H = [1 -1; 1 1], e = (2, 1/2)):
!>     both close, alpha = (1, 1/4), mu = (3/4, 5/4);
!>   - a load that pulls the block off its supports (e = -1): no equilibrium,
!>     info 1, whatever the solver;
!>   - a mode no row holds (H = 0, held of no column): alpha = 0 and mu the
!>     plain LCP's.
!>   - units: a footing on three supports at x = (-1, 0, 1) L, W = I, sinking
!>     and tilting modes (H = [1, x L]), load P = 3 and a moment 2.4 L (the
!>     moment's unit is the length's times the force's): the left support
!>     lifts off, mu = (0, 0.6, 2.4), alpha = (0.6, 1.8 / L), gap1 = 1.2, the
!>     same dimensionless answer (mu, alpha_1, L alpha_2) at L = 1e-3, 1, 1e3,
!>     1e5 to 1e-10; the load pulled off at every L;
!>   - working rows: a block sinking onto 6 supports at gaps 0, 0.5, ..., 2.5
!>     among 194 far ones (gaps 100 + i), W = I, P = 6: the first rows (q <= 0
!>     and the balance's) do not hold it, the check of the others brings the
!>     rest in, alpha = 2.2, mu = alpha - q on the five closed; without modes,
!>     a coupled pair (W = [1 -1.5; -1.5 4], q = (-1, 1.2)) among 98 far rows,
!>     where the second row (q = 1.2 > the deepest penetration 1) closes only
!>     under the first's force: mu = (44, 6) / 35; both with more than one
!>     round and fewer rows than all;
!>   - a start: the solution's own mu starts a solve that ends in one Newton
!>     step; a start with no contact (mu = 0) has no active row to hold the
!>     load: the modes move until the first row closes, and the answer is the
!>     same.
!> The solvers end on an exact solve of the active set (the active-set Newton
!> method's KKT solve, or PGS's finish), so the answers are good to
!> round-off: tolerances of a few tens of eps times the size of the answer.
program test_contact_lcp
  use kinds, only: dp
  use lcp_solvers, only: lcp_options_t
  use contact_lcp, only: contact_solution_t, solve_contact
  use strings, only: int_to_str, real_to_str
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none
  character(len=*), parameter :: methods(3) = ['lemke', 'pgs  ', 'pdas ']
  integer :: m

  do m = 1, size(methods)
    call no_modes_2x2(trim(methods(m)))
    call no_modes_3x3(trim(methods(m)))
    call block_on_two_supports(trim(methods(m)), 0.5_dp, [1.25_dp, 0.75_dp], [1.25_dp])
    call block_on_two_supports(trim(methods(m)), 3.0_dp, [2.0_dp, 0.0_dp], [2.0_dp])
    call sinking_and_tilting(trim(methods(m)))
    call pulled_off(trim(methods(m)))
    call unheld_mode(trim(methods(m)))
    call footing_at_scales(trim(methods(m)))
    call block_among_far_rows(trim(methods(m)))
    call pair_among_far_rows(trim(methods(m)))
    call started(trim(methods(m)))
  end do
  call finish_tests()

contains

  !> The conditions of the mixed LCP on sol, and sol against the hand
  !> solution (mu_ref, alpha_ref).  Round-off tolerances: 32 eps of the
  !> answer's size (a dense solve of at most 5 unknowns, condition <= 3);
  !> alpha component by component, as its entries may have different units.
  subroutine check_solution(name, w, q, h, e, sol, mu_ref, alpha_ref)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: w(:,:), q(:), h(:,:), e(:), mu_ref(:), alpha_ref(:)
    type(contact_solution_t), intent(in) :: sol
    real(dp) :: fscale, gscale
    fscale = max(maxval(abs(mu_ref)), 1.0_dp)
    gscale = maxval(abs(q)) + maxval(abs(matmul(w, mu_ref)))
    call check(sol%rep%info == 0, name // ': solved (info 0)')
    if (sol%rep%info /= 0) then
      if (allocated(sol%rep%message)) print '(a)', '  ' // sol%rep%message
      return
    end if
    call check_small(maxval(abs(sol%mu - mu_ref)), tol_round(32, fscale), name // ': mu by hand')
    if (size(alpha_ref) > 0) &
      call check_small(maxval(abs(sol%alpha - alpha_ref) / max(abs(alpha_ref), tiny(1.0_dp))), tol_round(32), &
                       name // ': alpha by hand (relative, each)')
    call check_small(maxval(abs(sol%gap - (q + matmul(w, sol%mu) - matmul(h, sol%alpha)))), tol_round(8, gscale), &
                     name // ': gap = q + W mu - H alpha')
    call check(all(sol%mu >= 0.0_dp), name // ': mu >= 0')
    call check_small(max(0.0_dp, -minval(sol%gap)), tol_round(32, gscale), name // ': gap >= 0')
    call check_small(maxval(abs(sol%mu * sol%gap)), tol_round(32, fscale * gscale), name // ': mu_i gap_i = 0')
    if (size(e) > 0) call check_small(equilibrium_ratio(h, e, sol%mu), tol_round(32), &
                                      name // ': equilibrium H''mu = e (each component against its terms)')
  end subroutine check_solution

  !> max_j |(H'mu - e)_j| / (|e_j| + sum_i |H_ij mu_i|): each component of the
  !> equilibrium (a force, a moment) against the size of its own terms.
  real(dp) function equilibrium_ratio(h, e, mu) result(r)
    real(dp), intent(in) :: h(:,:), e(:), mu(:)
    integer :: j
    r = 0.0_dp
    do j = 1, size(e)
      r = max(r, abs(dot_product(h(:, j), mu) - e(j)) / max(abs(e(j)) + sum(abs(h(:, j) * mu)), tiny(1.0_dp)))
    end do
  end function equilibrium_ratio

  !> W = [2 1; 1 2], q = (-1, 1): contact 1 closed, mu1 = -q1 / W11 = 1/2,
  !> gap2 = q2 + W21 mu1 = 3/2 > 0 (and contact 2 closed instead, or both,
  !> gives a negative force: the active set is unique).
  subroutine no_modes_2x2(method)
    character(len=*), intent(in) :: method
    real(dp) :: w(2, 2), h(2, 0), e(0), held(0, 0)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    w = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
    call solve_contact(w, [-1.0_dp, 1.0_dp], h, e, held, method, opts, sol)
    call check_solution('2x2 ' // method, w, [-1.0_dp, 1.0_dp], h, e, sol, [0.5_dp, 0.0_dp], [real(dp) ::])
    call check_small(maxval(abs(sol%gap - [0.0_dp, 1.5_dp])), tol_round(8, 1.5_dp), '2x2 ' // method // ': gap = (0, 3/2)')
  end subroutine no_modes_2x2

  !> W = tridiag(1, 4, 1), q = (-5, -6, 3): contacts 1 and 2 closed,
  !> [4 1; 1 4] mu = (5, 6): mu = (14, 19) / 15; gap3 = 3 + 19/15 > 0.
  subroutine no_modes_3x3(method)
    character(len=*), intent(in) :: method
    real(dp) :: w(3, 3), q(3), h(3, 0), e(0), held(0, 0)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    w = reshape([4.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 4.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 4.0_dp], [3, 3])
    q = [-5.0_dp, -6.0_dp, 3.0_dp]
    call solve_contact(w, q, h, e, held, method, opts, sol)
    call check_solution('3x3 ' // method, w, q, h, e, sol, [14.0_dp, 19.0_dp, 0.0_dp] / 15.0_dp, [real(dp) ::])
    call check_small(abs(sol%gap(3) - (3.0_dp + 19.0_dp / 15.0_dp)), tol_round(8, 5.0_dp), &
                     '3x3 ' // method // ': gap3 = 3 + 19/15')
  end subroutine no_modes_3x3

  !> A rigid block held only by two supports: alpha its sinking (closing both
  !> gaps, H = (1, 1)'), e = 2 its weight, W = I the supports' compliance,
  !> initial gaps (0, d).  Both closed: mu = (alpha, alpha - d), mu1 + mu2 = 2,
  !> so alpha = 1 + d/2, valid while mu2 = 1 - d/2 >= 0 (d <= 2); beyond, only
  !> the first closes: mu = (2, 0), alpha = 2, gap2 = d - 2.
  subroutine block_on_two_supports(method, d, mu_ref, alpha_ref)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: d, mu_ref(2), alpha_ref(1)
    real(dp) :: w(2, 2), h(2, 1), held(1, 1)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    character(len=:), allocatable :: name
    name = 'block, second support ' // merge('1/2 lower', '3 lower  ', d < 1.0_dp) // ' ' // method
    w = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    h = 1.0_dp
    held = 1.0_dp
    call solve_contact(w, [0.0_dp, d], h, [2.0_dp], held, method, opts, sol)
    call check_solution(trim(name), w, [0.0_dp, d], h, [2.0_dp], sol, mu_ref, alpha_ref)
  end subroutine block_on_two_supports

  !> Two modes: sinking (1, 1)' and tilting (-1, 1)' of a block on two
  !> supports, W = I, q = 0, e = (2, 1/2) (weight and a moment).  Both closed:
  !> mu = H alpha and H'H alpha = e, H'H = 2 I: alpha = (1, 1/4),
  !> mu = (1 - 1/4, 1 + 1/4).
  subroutine sinking_and_tilting(method)
    character(len=*), intent(in) :: method
    real(dp) :: w(2, 2), h(2, 2), held(2, 2)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    w = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    h = reshape([1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp], [2, 2])
    held = w
    call solve_contact(w, [0.0_dp, 0.0_dp], h, [2.0_dp, 0.5_dp], held, method, opts, sol)
    call check_solution('sinking and tilting ' // method, w, [0.0_dp, 0.0_dp], h, [2.0_dp, 0.5_dp], sol, &
                        [0.75_dp, 1.25_dp], [1.0_dp, 0.25_dp])
  end subroutine sinking_and_tilting

  !> The block's load lifts it (e = -1): H'mu = mu1 + mu2 = -1 has no
  !> solution with mu >= 0.
  subroutine pulled_off(method)
    character(len=*), intent(in) :: method
    real(dp) :: w(2, 2), h(2, 1), held(1, 1)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    w = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    h = 1.0_dp
    held = 1.0_dp
    call solve_contact(w, [0.0_dp, 0.5_dp], h, [-1.0_dp], held, method, opts, sol)
    call check(sol%rep%info == 1, 'block pulled off ' // method // ': no equilibrium (info 1)')
    if (sol%rep%info == 1) call check(index(sol%rep%message, 'no equilibrium') > 0, &
                                      'block pulled off ' // method // ': the message says so')
  end subroutine pulled_off

  !> A mode the rows do not see (H = 0: a slide along a frictionless flat),
  !> unloaded and not held (held has no column): alpha = 0 and mu is the
  !> plain LCP's, the 2 x 2 of no_modes_2x2.
  subroutine unheld_mode(method)
    character(len=*), intent(in) :: method
    real(dp) :: w(2, 2), h(2, 1), held(1, 0)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    w = reshape([2.0_dp, 1.0_dp, 1.0_dp, 2.0_dp], [2, 2])
    h = 0.0_dp
    call solve_contact(w, [-1.0_dp, 1.0_dp], h, [0.0_dp], held, method, opts, sol)
    call check(size(sol%alpha) == 1, 'unheld mode ' // method // ': one amplitude')
    if (size(sol%alpha) /= 1) return
    call check(sol%alpha(1) == 0.0_dp, 'unheld mode ' // method // ': alpha = 0')
    call check_solution('unheld mode ' // method, w, [-1.0_dp, 1.0_dp], h, [0.0_dp], sol, [0.5_dp, 0.0_dp], [0.0_dp])
  end subroutine unheld_mode

  !> The footing of the header at the unit of length L: H = [1, x L] with
  !> x = (-1, 0, 1), e = (3, 2.4 L), W = I, q = 0.  By hand: all three
  !> closed would give mu1 = 1 - 1.2 < 0; with the left one open,
  !> 2 a + L b = 3 and a + L b = 2.4 (the moment), a = 0.6, L b = 1.8,
  !> mu = (0, 0.6, 2.4), gap1 = -(a - L b) = 1.2.  The dimensionless answer
  !> (mu, a, L b) must not depend on L; and e = (-3, 0) pulls it off at each L.
  subroutine footing_at_scales(method)
    character(len=*), intent(in) :: method
    real(dp), parameter :: scales(4) = [1.0e-3_dp, 1.0_dp, 1.0e3_dp, 1.0e5_dp]
    real(dp) :: w(3, 3), h(3, 2), held(2, 2), q(3), x(3), e(2), ref(5), got(5)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    character(len=:), allocatable :: name
    integer :: i
    w = 0.0_dp
    held = 0.0_dp
    do i = 1, 3
      w(i, i) = 1.0_dp
    end do
    held(1, 1) = 1.0_dp
    held(2, 2) = 1.0_dp
    x = [-1.0_dp, 0.0_dp, 1.0_dp]
    q = 0.0_dp
    do i = 1, size(scales)
      name = 'footing at L = ' // trim(real_to_str(scales(i))) // ' ' // method
      h(:, 1) = 1.0_dp
      h(:, 2) = x * scales(i)
      e = [3.0_dp, 2.4_dp * scales(i)]
      call solve_contact(w, q, h, e, held, method, opts, sol)
      call check_solution(name, w, q, h, e, sol, [0.0_dp, 0.6_dp, 2.4_dp], [0.6_dp, 1.8_dp / scales(i)])
      if (sol%rep%info /= 0) cycle
      call check_small(abs(sol%gap(1) - 1.2_dp), tol_round(32, 2.4_dp), name // ': the left support open by 1.2')
      got = [sol%mu, sol%alpha(1), sol%alpha(2) * scales(i)]
      if (i == 1) ref = got
      call check_small(maxval(abs(got - ref)) / maxval(abs(ref)), 1.0e-10_dp, &
                       name // ': (mu, alpha_1, L alpha_2) as at L = 1e-3 to 1e-10')
      call check(sol%equality_residual <= tol_round(64), name // ': equilibrium to round-off (scale-free measure)')
      call solve_contact(w, q, h, [-3.0_dp, 0.0_dp], held, method, opts, sol)
      call check(sol%rep%info == 1, name // ': pulled up, no equilibrium (info 1)')
    end do
  end subroutine footing_at_scales

  !> A block (one mode, sinking: H = 1) on 6 supports at gaps 0, 0.5, ...,
  !> 2.5 among 194 far rows (gaps 100 + i), W = I, load P = 6.  By hand: the
  !> supports with q_i < alpha close, mu_i = alpha - q_i, sum mu_i = 6:
  !> four closed give alpha = 2.25 > 2, five give 5 alpha - 5 = 6,
  !> alpha = 2.2 in [2, 2.5): mu = (2.2, 1.7, 1.2, 0.7, 0.2, 0, ...).  The
  !> first working rows (q <= 0 and the balance's) cannot be all: the check
  !> of the others must add rows (more than one round), and the far rows stay
  !> out (fewer working rows than half).
  subroutine block_among_far_rows(method)
    character(len=*), intent(in) :: method
    integer, parameter :: n = 200
    real(dp) :: w(n, n), h(n, 1), held(1, 1), q(n), mu_ref(n)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    integer :: i
    w = 0.0_dp
    do i = 1, n
      w(i, i) = 1.0_dp
      q(i) = 100.0_dp + i
    end do
    q(1:6) = [0.0_dp, 0.5_dp, 1.0_dp, 1.5_dp, 2.0_dp, 2.5_dp]
    h = 1.0_dp
    held = 1.0_dp
    mu_ref = 0.0_dp
    mu_ref(1:5) = 2.2_dp - q(1:5)
    call solve_contact(w, q, h, [6.0_dp], held, method, opts, sol)
    call check_solution('block among far rows ' // method, w, q, h, [6.0_dp], sol, mu_ref, [2.2_dp])
    call check(sol%rounds > 1, 'block among far rows ' // method // ': the first rows were refined (' // &
               int_to_str(sol%rounds) // ' rounds)')
    call check(2 * sol%rows < n, 'block among far rows ' // method // ': the far rows stayed out (' // &
               int_to_str(sol%rows) // ' working rows)')
  end subroutine block_among_far_rows

  !> Without modes: W = [1 -1.5; -1.5 4] on two rows (SPD) and the identity
  !> on 98 far rows (gaps 100 + i), q = (-1, 1.2, ...).  Row 2 is not in
  !> the first working rows (1.2 > the deepest penetration 1) but the first
  !> row's force pulls it shut: alone, mu1 = 1 and gap2 = 1.2 - 1.5 < 0.  Both
  !> closed: [1 -1.5; -1.5 4] mu = (1, -1.2), mu = (4 - 1.8, 1.5 - 1.2) / 1.75
  !> = (44, 6) / 35 >= 0.
  subroutine pair_among_far_rows(method)
    character(len=*), intent(in) :: method
    integer, parameter :: n = 100
    real(dp) :: w(n, n), q(n), mu_ref(n), h(n, 0), e(0), held(0, 0)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    integer :: i
    w = 0.0_dp
    do i = 1, n
      w(i, i) = 1.0_dp
      q(i) = 100.0_dp + i
    end do
    w(1:2, 1:2) = reshape([1.0_dp, -1.5_dp, -1.5_dp, 4.0_dp], [2, 2])
    q(1:2) = [-1.0_dp, 1.2_dp]
    mu_ref = 0.0_dp
    mu_ref(1:2) = [44.0_dp, 6.0_dp] / 35.0_dp
    call solve_contact(w, q, h, e, held, method, opts, sol)
    call check_solution('pair among far rows ' // method, w, q, h, e, sol, mu_ref, [real(dp) ::])
    call check(sol%rounds == 2 .and. sol%rows == 2, 'pair among far rows ' // method // &
               ': the second row joined in a second round, the far rows stayed out (' // &
               int_to_str(sol%rounds) // ' rounds, ' // int_to_str(sol%rows) // ' rows)')
  end subroutine pair_among_far_rows

  !> Starts: the footing at L = 1 from its own solution ends in one Newton
  !> step; from a start with no contact (mu = 0: no active row holds the
  !> load) the modes move until rows close, to the same answer.
  subroutine started(method)
    character(len=*), intent(in) :: method
    real(dp) :: w(3, 3), h(3, 2), held(2, 2), q(3), e(2), mu_ref(3), a_ref(2)
    type(lcp_options_t) :: opts
    type(contact_solution_t) :: sol
    integer :: i
    w = 0.0_dp
    held = 0.0_dp
    do i = 1, 3
      w(i, i) = 1.0_dp
    end do
    held(1, 1) = 1.0_dp
    held(2, 2) = 1.0_dp
    h(:, 1) = 1.0_dp
    h(:, 2) = [-1.0_dp, 0.0_dp, 1.0_dp]
    q = [0.5_dp, 0.5_dp, 0.5_dp]                       ! hovering: the solution is the footing's, alpha_1 + 0.5
    e = [3.0_dp, 2.4_dp]
    mu_ref = [0.0_dp, 0.6_dp, 2.4_dp]
    a_ref = [1.1_dp, 1.8_dp]
    call solve_contact(w, q, h, e, held, method, opts, sol, mu_start=mu_ref)
    call check_solution('started from the solution ' // method, w, q, h, e, sol, mu_ref, a_ref)
    if (method /= 'lemke') call check(sol%outer == 1, 'started from the solution ' // method // &
                                      ': one Newton step (' // int_to_str(sol%outer) // ')')
    call solve_contact(w, q, h, e, held, method, opts, sol, mu_start=[0.0_dp, 0.0_dp, 0.0_dp])
    call check_solution('started with no contact ' // method, w, q, h, e, sol, mu_ref, a_ref)
  end subroutine started

end program test_contact_lcp
