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
!> The solvers end on an exact solve of the active set (finish_exact, dsysv /
!> pivoted Cholesky), so the answers are good to round-off: tolerances of a
!> few tens of eps times the size of the answer.
program test_contact_lcp
  use kinds, only: dp
  use lcp_solvers, only: lcp_options_t
  use contact_lcp, only: contact_solution_t, solve_contact
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
  end do
  call finish_tests()

contains

  !> The conditions of the mixed LCP on sol, and sol against the hand
  !> solution (mu_ref, alpha_ref).  Round-off tolerances: 32 eps of the
  !> answer's size (a dense solve of at most 5 unknowns, condition <= 3).
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
      call check_small(maxval(abs(sol%alpha - alpha_ref)), tol_round(32, maxval(abs(alpha_ref))), name // ': alpha by hand')
    call check_small(maxval(abs(sol%gap - (q + matmul(w, sol%mu) - matmul(h, sol%alpha)))), tol_round(8, gscale), &
                     name // ': gap = q + W mu - H alpha')
    call check(all(sol%mu >= 0.0_dp), name // ': mu >= 0')
    call check_small(max(0.0_dp, -minval(sol%gap)), tol_round(32, gscale), name // ': gap >= 0')
    call check_small(maxval(abs(sol%mu * sol%gap)), tol_round(32, fscale * gscale), name // ': mu_i gap_i = 0')
    if (size(e) > 0) call check_small(maxval(abs(matmul(transpose(h), sol%mu) - e)), tol_round(32, fscale), &
                                      name // ': equilibrium H''mu = e')
  end subroutine check_solution

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

end program test_contact_lcp
