!> tresca_newton: one load step's friction problem in the scaled form that the
!> Newton-type friction methods share (friction_newton, friction_fixed_point),
!> and the Tresca problem with given bounds solved as the convex QP it is, by
!> the projected Newton method.
!>
!> The scaled problem.  The symbols are friction_lcp's: G, q = [qn; qt],
!> trow, cmu, bound, lam = [lambda; tau], and with d_i = 1/sqrt(G_ii)
!> (scaling_vector, as friction_lcp)
!>     Gs = D G D,  qs = D q,  s = D^-1 lam,  v = qs + Gs s,
!>     bs_k = bs0_k + mus_k s_trow(k),  bs0_k = bound_k / d_{n+k},
!>     mus_k = cmu_k d_trow(k) / d_{n+k},
!> qscale = max(||qs||_inf, max_k bs0_k) (1 when both vanish), and the
!> residual r of friction_lcp, computed here on (s, v) by friction_residual_scaled:
!>     r = max( max_i |min(s_i, v_i)|,
!>              max_k |s_{n+k} - clamp(s_{n+k} - v_{n+k}, -bs_k, bs_k)| ) / qscale,
!> bs_k taken as max(bs_k, 0).  Every quantity is in the units of qs, so a
!> test "x <= t qscale" or a ratio of two of them does not depend on the
!> deck's units.
!>
!> The Tresca problem.  With the bounds bs >= 0 given (Tresca's, or Coulomb's
!> frozen at some lambda), the conditions of the step are the KKT conditions
!> of the convex QP (friction_lcp's module header)
!>     min f(s) = 1/2 s'Gs s + qs's   over the box   s_i >= 0 (i <= n),
!>                                                    |s_{n+k}| <= bs_k,
!> whose gradient is v; r above is ||s - P(s - v)||_inf / qscale, P the
!> projection onto the box.  solve_tresca_qp solves it by the projected Newton
!> method (Bertsekas, SIAM J. Control Optim. 20 (1982) 221-246; Kelley,
!> Iterative Methods for Optimization, SIAM 1999, sec. 5.5), from a start
!> projected onto the box, so that every iterate is feasible:
!>     w = ||s - P(s - v)||_inf,  eps = w,
!>     B = the rows within eps of a bound that v pushes against it (and the
!>         rows whose bound is 0), F = the others;
!>     d_F = -Gs_FF^-1 v_F (Cholesky),  d_B = -v_B (Gs_ii = 1: a gradient step);
!>     s <- P(s + alpha d), alpha = 1, 1/2, 1/4, ... the first with
!>         f(s) - f(P(s + alpha d)) >= sigma (alpha v_F'(-d_F) + v_B'(s_B - P(s + alpha d)_B)).
!> f decreases at every step; every limit point satisfies the KKT conditions
!> (Bertsekas, prop. 2), which for a convex QP make it a minimiser; once B is
!> the set of bound rows of the solution the full step is taken and lands on
!> it, so the method ends after finitely many steps on a non-degenerate
!> problem.  The difference f(s) - f(s') is computed as -1/2 (s' - s)'(v + v'),
!> free of the cancellation of two large values of f.  It stops with
!> info 0 when r <= tol, 2 at the step limit, 3 when Gs_FF is not positive
!> definite (G singular on the free rows: linearly dependent contact rows),
!> 5 when the line search cannot decrease f (alpha below 2^-40: round-off
!> at a point whose residual is still above tol).
!>
!> Programming interface
!>   type(scaled_friction_t)                 the scaled problem (above)
!>   scale_friction_problem(g, prob, p, info)   build it (info 1: out of memory)
!>   friction_residual_scaled(p, bs0, mus, s, v)   r of (s, v) with the bounds bs0 + mus lambda
!>   coulomb_bounds(p, bs0, mus, s, bs)     bs_k = max(0, bs0_k + mus_k s_trow(k))
!>   solve_tresca_qp(p, bs, tol, maxit, s, v, steps, info)   the Tresca QP with bounds bs
!>   tresca_solved, tresca_step_limit, tresca_singular, tresca_stalled   its info values
!> No routine prints anything.
module tresca_newton
  use kinds, only: dp
  use lapack_interfaces, only: dpotrf, dpotrs
  use lcp_scaling, only: scaling_vector, lcp_gaps
  use friction_lcp, only: friction_problem_t, bounded_residual, scale_bounds
  implicit none
  private
  public :: scaled_friction_t, scale_friction_problem, friction_residual_scaled, coulomb_bounds, solve_tresca_qp
  public :: tresca_solved, tresca_step_limit, tresca_singular, tresca_stalled

  integer, parameter :: tresca_solved = 0        !< r <= tol
  integer, parameter :: tresca_step_limit = 2    !< maxit steps without r <= tol
  integer, parameter :: tresca_singular = 3      !< Gs_FF not positive definite
  integer, parameter :: tresca_stalled = 5       !< no decrease of f along the projected arc

  !> Armijo's fraction of the predicted decrease, and the smallest step
  !> (2^-40: below it the decrease is round-off of f at the iterate's scale).
  real(dp), parameter :: armijo = 1.0e-4_dp
  real(dp), parameter :: smallest_step = 2.0_dp**(-40)

  !> One load step's friction problem, scaled (module header).
  type :: scaled_friction_t
    integer :: n = 0                       !< normal rows
    integer :: nt = 0                      !< tangential rows
    real(dp), allocatable :: d(:)          !< (n+nt) D, d_i = 1/sqrt(G_ii)
    real(dp), allocatable :: gs(:, :)      !< (n+nt, n+nt) Gs = D G D
    real(dp), allocatable :: qs(:)         !< (n+nt) D q
    real(dp), allocatable :: bs0(:)        !< (nt) bound_k / d_{n+k}
    real(dp), allocatable :: mus(:)        !< (nt) cmu_k d_trow(k) / d_{n+k}
    integer, allocatable :: trow(:)        !< (nt) normal row of each tangential row
    real(dp) :: qscale = 1.0_dp            !< max(||qs||_inf, max bs0), 1 when 0
  end type scaled_friction_t

contains

  !> The scaled problem of a valid step (check_friction_problem).
  !>   g     (in)  (n+nt, n+nt) G
  !>   prob  (in)  the step's problem
  !>   p     (out) its scaled form
  !>   info  (out) 0; 1 when Gs (as large as G) cannot be allocated
  subroutine scale_friction_problem(g, prob, p, info)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    type(scaled_friction_t), intent(out) :: p
    integer, intent(out) :: info
    integer :: n, nt, m, j
    n = prob%n
    nt = prob%nt
    m = n + nt
    allocate(p%d(m), p%gs(m, m), p%qs(m), p%bs0(nt), p%mus(nt), p%trow(nt), stat=info)
    if (info /= 0) then
      info = 1
      return
    end if
    call scaling_vector(g, p%d)                        ! d_i = 1/sqrt(G_ii)
    do j = 1, m
      p%gs(:, j) = p%d * g(:, j) * p%d(j)              ! Gs = D G D
    end do
    p%qs(1:n) = p%d(1:n) * prob%qn
    p%qs(n + 1:) = p%d(n + 1:) * prob%qt
    call scale_bounds(prob, p%d, p%qs, p%n, p%nt, p%trow, p%bs0, p%mus, p%qscale)
  end subroutine scale_friction_problem

  !> friction_lcp's residual r of the scaled iterate s with gaps v = qs + Gs s,
  !> for the bounds bs_k = bs0_k + mus_k s_trow(k) (p%bs0 and p%mus, or a
  !> Tresca problem's bounds and zeros).
  pure function friction_residual_scaled(p, bs0, mus, s, v) result(r)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:), s(:), v(:)
    real(dp) :: r
    r = bounded_residual(p%n, p%trow, bs0, mus, p%qscale, s, v)
  end function friction_residual_scaled

  !> Coulomb's bounds at the normal forces of s: bs_k = max(0, bs0_k + mus_k s_trow(k)).
  !>   p         (in)  the scaled problem (its trow)
  !>   bs0, mus  (in)  (nt) the bounds' parts (p%bs0, p%mus)
  !>   s         (in)  (n+nt) a scaled iterate
  !>   bs        (out) (nt) the bounds
  pure subroutine coulomb_bounds(p, bs0, mus, s, bs)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs0(:), mus(:), s(:)
    real(dp), intent(out) :: bs(:)
    integer :: k
    do k = 1, p%nt
      bs(k) = max(0.0_dp, bs0(k) + mus(k) * s(p%trow(k)))
    end do
  end subroutine coulomb_bounds

  !> The Tresca problem with bounds bs by the projected Newton method (module
  !> header).
  !>   p      (in)    the scaled problem (its bs0 and mus are not used)
  !>   bs     (in)    (nt) the bounds, >= 0
  !>   tol    (in)    the target of r (relative to p%qscale), > 0
  !>   maxit  (in)    the limit of steps (counted in steps, >= 0)
  !>   s      (inout) (n+nt) on entry the start (projected onto the box); on
  !>                  exit the last iterate, feasible
  !>   v      (out)   (n+nt) its gaps qs + Gs s
  !>   steps  (inout) the steps done (linear solves), incremented
  !>   info   (out)   tresca_solved, tresca_step_limit, tresca_singular or
  !>                  tresca_stalled
  subroutine solve_tresca_qp(p, bs, tol, maxit, s, v, steps, info)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: bs(:), tol
    integer, intent(in) :: maxit
    real(dp), intent(inout) :: s(:)
    real(dp), intent(out) :: v(:)
    integer, intent(inout) :: steps
    integer, intent(out) :: info
    real(dp), allocatable :: lo(:), hi(:), dir(:), trial(:), vt(:), a(:, :), rhs(:)
    integer, allocatable :: free(:)
    logical, allocatable :: bind(:)
    real(dp) :: w, eps, alpha, slope, gain, want
    integer :: m, nf, i, j

    m = p%n + p%nt
    allocate(lo(m), hi(m), dir(m), trial(m), vt(m), bind(m))
    lo(1:p%n) = 0.0_dp
    hi(1:p%n) = huge(1.0_dp)
    lo(p%n + 1:) = -bs
    hi(p%n + 1:) = bs
    s = min(hi, max(lo, s))                            ! the start, feasible
    call lcp_gaps(p%gs, p%qs, s, v)
    do
      w = 0.0_dp
      if (m > 0) w = maxval(abs(s - min(hi, max(lo, s - v))))   ! ||s - P(s - v)||_inf
      if (w <= tol * p%qscale) then
        info = tresca_solved
        return
      end if
      if (steps >= maxit) then
        info = tresca_step_limit
        return
      end if
      ! the binding rows B and the free rows F
      eps = w
      do i = 1, m
        bind(i) = hi(i) <= lo(i) .or. (s(i) - lo(i) <= eps .and. v(i) > 0.0_dp) .or. &
                  (hi(i) - s(i) <= eps .and. v(i) < 0.0_dp)
      end do
      free = pack([(i, i = 1, m)], .not. bind)
      nf = size(free)
      ! d_F = -Gs_FF^-1 v_F, d_B = -v_B
      dir = -v
      slope = 0.0_dp
      if (nf > 0) then
        allocate(a(nf, nf), rhs(nf))
        do j = 1, nf
          a(:, j) = p%gs(free, free(j))
        end do
        rhs = -v(free)
        call dpotrf('L', nf, a, nf, info)
        if (info /= 0) then
          info = tresca_singular
          return
        end if
        call dpotrs('L', nf, 1, a, nf, rhs, nf, info)
        dir(free) = rhs
        slope = -dot_product(v(free), rhs)               ! v_F'(-d_F) >= 0
        deallocate(a, rhs)
      end if
      steps = steps + 1
      ! Armijo along the projected arc
      alpha = 1.0_dp
      do
        trial = min(hi, max(lo, s + alpha * dir))
        call lcp_gaps(p%gs, p%qs, trial, vt)
        gain = -0.5_dp * dot_product(trial - s, v + vt)  ! f(s) - f(trial)
        want = armijo * (alpha * slope + dot_product(merge(v, 0.0_dp, bind), s - trial))
        if (gain >= want .and. gain > 0.0_dp) exit
        alpha = 0.5_dp * alpha
        if (alpha < smallest_step) then
          info = tresca_stalled
          return
        end if
      end do
      s = trial
      v = vt
    end do
  end subroutine solve_tresca_qp

end module tresca_newton
