!> contact_lcp: the condensed contact problem, with or without free rigid modes.
!>
!> Without free modes it is LCP(W, q), solved by Lemke or PGS (lcp_solvers).
!> With k free modes R (see rigid_modes) it is the mixed LCP
!>     mu >= 0,  gap = q + W mu - H alpha >= 0,  mu' gap = 0,  H' mu = e,
!> H = B R (how each mode opens the gaps), e = R' f (the load along the
!> modes), alpha the modes' amplitudes: the KKT conditions of
!>     min 1/2 mu'W mu + q'mu  subject to  mu >= 0, H' mu = e.
!> It is solved in three steps, each exact or checked:
!>  1. only the combinations of the modes that the contact rows hold enter
!>     (held, decided by mode_support from H before the solve); the others
!>     are unloaded and keep amplitude 0;
!>  2. feasibility: min |H'mu - e| over mu >= 0 (nonnegative least squares,
!>     itself the LCP(H H', -H e), by Lemke); a positive minimum means the
!>     loads pull the body away from its contacts: no equilibrium, exit 1;
!>  3. the method of multipliers on the equality: for lambda given, the
!>     LCP(W + rho H H', q - H (lambda + rho e)) by the chosen solver, then
!>     lambda <- lambda - rho (H'mu - e), until H'mu = e to the tolerance;
!>     finished by the exact KKT solve on the active set (dsysv).
!>
!> Programming interface
!>   type(contact_solution_t)   mu, alpha, gap, report, notes
!>   solve_contact(w, q, h, e, held, method, opts, sol)
module contact_lcp
  use kinds, only: dp
  use lapack_interfaces, only: dpotrs, dpstrf, dsysv
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_pgs, lcp_natural_residual
  use lcp_newton, only: solve_lcp_pdas
  use strings, only: int_to_str, real_to_str
  implicit none
  private
  public :: contact_solution_t, solve_contact

  type :: contact_solution_t
    real(dp), allocatable :: mu(:)           !< (nc) multipliers, nodal forces
    real(dp), allocatable :: alpha(:)        !< (k) amplitudes of the free modes
    real(dp), allocatable :: gap(:)          !< (nc) final gaps q + W mu - H alpha
    type(lcp_report_t) :: rep                !< info 0 solved; else failure and message
    real(dp) :: equality_residual = 0        !< |H'mu - e| / max(|e|, scale)
    integer :: outer = 0                     !< multiplier iterations
  end type contact_solution_t


contains

  !> Solve the condensed contact problem.
  !>   w      (in) (nc, nc) Delassus matrix B K^# B'
  !>   q      (in) (nc) gaps without contact forces
  !>   h      (in) (nc, k) B R; k = 0 for a problem without free modes
  !>   e      (in) (k) R' f
  !>   held   (in) (k, kh) basis of the combinations of the modes that the rows
  !>               hold (mode_support); alpha = held lambda, 0 along the others
  !>   method (in) 'lemke', 'pgs' or 'pdas'
  !>   opts   (in) tolerances
  !>   sol    (out) the solution; sol%rep%info /= 0 on failure with a message
  !>   outer_limit (in, optional) multiplier iterations before the exact solve is
  !>               tried (default 100); when it does not finish them, the
  !>               iterations carry on up to outer_max in all
  subroutine solve_contact(w, q, h, e, held, method, opts, sol, outer_limit)
    real(dp), intent(in) :: w(:,:), q(:), h(:,:), e(:), held(:,:)
    character(len=*), intent(in) :: method
    type(lcp_options_t), intent(in) :: opts
    type(contact_solution_t), intent(out) :: sol
    integer, intent(in), optional :: outer_limit
    integer :: nc, k, kh, j, it, limit
    integer, parameter :: outer_max = 1000   ! multiplier iterations when the first outer_limit did not settle
    real(dp), allocatable :: hh(:,:), eh(:), lam(:), wr(:,:), qr(:), r(:)
    real(dp) :: rho, res, wdiag, hnorm
    type(lcp_report_t) :: rep
    integer :: total

    nc = size(q)
    k = size(e)
    allocate(sol%mu(nc), sol%alpha(k), sol%gap(nc))
    sol%mu = 0.0_dp
    sol%alpha = 0.0_dp
    if (k == 0) then
      call run_solver(method, w, q, opts, sol%mu, sol%rep)
      sol%gap = q + matmul(w, sol%mu)
      return
    end if

    ! 1. the held combinations only (mode_support decided them from H's
    ! rows, unheld ones are unloaded): Hh = H V_h, eh = V_h' e
    kh = size(held, 2)
    hh = matmul(h, held)
    eh = matmul(transpose(held), e)
    allocate(lam(kh))
    lam = 0.0_dp
    if (kh == 0) then
      call run_solver(method, w, q, opts, sol%mu, sol%rep)
      sol%gap = q + matmul(w, sol%mu)
      return
    end if

    ! 2. feasibility: nonnegative least squares min |Hh'mu - eh|, mu >= 0
    call solve_lcp_lemke(matmul(hh, transpose(hh)), -matmul(hh, eh), sol%mu, opts, rep)
    res = norm2(matmul(transpose(hh), sol%mu) - eh)
    if (res > 1.0e-8_dp * norm2(eh)) then
      sol%rep%info = 1
      sol%rep%message = 'no equilibrium: the loads pull a body held only by contact away from its contacts ' // &
        '(the contact forces cannot balance them; residual ' // real_to_str(res / max(norm2(eh), tiny(1.0_dp))) // ')'
      return
    end if

    ! 3. method of multipliers: rho H H' of the size of W
    wdiag = 0.0_dp
    do j = 1, nc
      wdiag = max(wdiag, w(j, j))
    end do
    hnorm = maxval(sum(hh**2, dim=1))
    rho = 10.0_dp * wdiag / max(hnorm, tiny(1.0_dp))
    wr = w + rho * matmul(hh, transpose(hh))
    total = 0
    limit = 100                        ! (not merge(outer_limit, 100, ...): merge reads an absent argument)
    if (present(outer_limit)) limit = outer_limit
    it = 0
    do
      do while (it < limit)
        it = it + 1
        qr = q - matmul(hh, lam + rho * eh)
        call run_solver(method, wr, qr, opts, sol%mu, rep)
        total = total + rep%iterations
        if (rep%info /= 0) then
          sol%rep = rep
          return
        end if
        r = matmul(transpose(hh), sol%mu) - eh
        lam = lam - rho * r
        sol%outer = it
        if (norm2(r) <= opts%tol * equality_scale(hh, eh, sol%mu)) exit
      end do
      sol%rep = rep
      sol%rep%iterations = total
      call finish_exact(w, q, hh, eh, sol%mu, lam)
      sol%equality_residual = norm2(matmul(transpose(hh), sol%mu) - eh) / equality_scale(hh, eh, sol%mu)
      ! the multipliers converge linearly, slowly on large zones: where the
      ! exact solve did not finish them, carry on up to outer_max in all
      if (sol%equality_residual <= 1.0e3_dp * opts%tol .or. limit >= outer_max .or. it < limit) exit
      limit = outer_max
    end do
    if (sol%equality_residual > 1.0e3_dp * opts%tol) then
      sol%rep%info = 2
      sol%rep%message = 'the equilibrium of a body held only by contact was not reached (relative residual ' // &
        real_to_str(sol%equality_residual) // ' after ' // int_to_str(sol%outer) // ' multiplier iterations)'
    end if
    sol%alpha = matmul(held, lam)
    sol%gap = q + matmul(w, sol%mu) - matmul(h, sol%alpha)
    sol%rep%residual = lcp_natural_residual(w, q - matmul(h, sol%alpha), sol%mu)
  end subroutine solve_contact

  !> One LCP(W, q) by Lemke or PGS.  PGS stops on its residual, which on an
  !> ill-conditioned W (stiffness contrasts) still leaves errors of order
  !> cond(W) x tol in z, or stagnates; its active set is then finished by the
  !> exact solve W_AA z_A = -q_A, kept only when it satisfies the LCP to the
  !> tolerance (z >= 0, w >= 0, smaller residual).
  !> Scale of the equality H'mu = e: the load along the modes, or the size
  !> of the contact forces that balance each other along them (e may be 0).
  pure real(dp) function equality_scale(h, e, mu) result(sc)
    real(dp), intent(in) :: h(:,:), e(:), mu(:)
    sc = max(norm2(e), maxval(abs(h)) * sum(abs(mu)), tiny(1.0_dp))
  end function equality_scale

  subroutine run_solver(method, w, q, opts, z, rep)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: w(:,:), q(:)
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: z(:)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable :: h0(:,:), e0(:), lam0(:), zf(:)
    real(dp) :: r
    if (method == 'pgs') then
      call solve_lcp_pgs(w, q, z, opts, rep)
      if (rep%info == 0 .or. rep%info == 3) then
        allocate(h0(size(q), 0), e0(0), lam0(0))
        zf = z
        call finish_exact(w, q, h0, e0, zf, lam0)
        r = lcp_natural_residual(w, q, zf)
        if (r <= opts%tol .and. r <= rep%residual) then
          z = zf
          rep%residual = r
          rep%info = 0
        end if
      end if
    else if (method == 'pdas') then
      call solve_lcp_pdas(w, q, z, opts, rep)
    else
      call solve_lcp_lemke(w, q, z, opts, rep)
    end if
  end subroutine run_solver

  !> Exact finish: on the active set A = {mu > 0} solve
  !>   [W_AA  -H_A] [mu_A  ]   [-q_A]
  !>   [-H_A'   0 ] [lambda] = [-e  ]
  !> and keep it when mu_A >= 0 (to round-off, 1e-10 of max mu) and the gaps
  !> are >= 0 (1e-10 of their scale).
  subroutine finish_exact(w, q, h, e, mu, lam)
    real(dp), intent(in) :: w(:,:), q(:), h(:,:), e(:)
    real(dp), intent(inout) :: mu(:), lam(:)
    integer, allocatable :: act(:), ipiv(:)
    real(dp), allocatable :: a(:,:), b(:,:), work(:), gap(:), mu_new(:)
    integer :: na, k, n, info, lwork
    real(dp) :: wq(1), scale
    act = pack([(n, n = 1, size(mu))], mu > 0.0_dp)
    na = size(act)
    k = size(e)
    n = na + k
    allocate(a(n, n), b(n, 1), ipiv(n))
    a = 0.0_dp
    a(1:na, 1:na) = w(act, act)
    a(1:na, na + 1:n) = -h(act, :)
    a(na + 1:n, 1:na) = -transpose(h(act, :))
    b(1:na, 1) = -q(act)
    b(na + 1:n, 1) = -e
    if (k == 0) then
      ! pure LCP: W_AA may be singular (redundant constraints): pivoted
      ! Cholesky, solve on the independent rows, zero on the dependent ones
      call solve_psd_subset(a, b(:, 1), info)
    else
      call dsysv('U', n, 1, a, n, ipiv, b, n, wq, -1, info)
      lwork = max(1, int(wq(1)))
      allocate(work(lwork))
      call dsysv('U', n, 1, a, n, ipiv, b, n, work, lwork, info)
    end if
    if (info /= 0) return
    mu_new = mu
    mu_new(act) = b(1:na, 1)
    ! a multiplier that is 0 in exact arithmetic (a degenerate or redundant
    ! row) may come out at -1e-12: round-off, set to 0; a clearly negative
    ! one means a wrong active set
    if (any(mu_new(act) < -1.0e-10_dp * maxval(abs(mu_new)))) return
    mu_new = max(mu_new, 0.0_dp)
    gap = q + matmul(w, mu_new) - matmul(h, b(na + 1:n, 1))
    scale = maxval(abs(q)) + maxval(abs(matmul(w, mu_new)))
    if (any(gap < -1.0e-10_dp * scale)) return
    mu = mu_new
    lam = b(na + 1:n, 1)
  end subroutine finish_exact

  !> x = A^+ b in the pivoted Cholesky sense: A (n, n) symmetric PSD, factorized
  !> P' A P = L L' of rank r by dpstrf; x solves on the r pivots, 0 on the rest.
  !> b is overwritten by x; info /= 0 when dpstrf fails.
  subroutine solve_psd_subset(a, b, info)
    real(dp), intent(inout) :: a(:,:), b(:)
    integer, intent(out) :: info
    integer :: n, rank
    integer, allocatable :: piv(:)
    real(dp), allocatable :: work(:), y(:)
    n = size(b)
    info = 0
    if (n == 0) return
    allocate(piv(n), work(2 * n))
    call dpstrf('L', n, a, n, piv, rank, -1.0_dp, work, info)
    if (info < 0) return
    info = 0
    y = b(piv(1:rank))
    call dpotrs('L', rank, 1, a, n, y, rank, info)
    if (info /= 0) return
    b = 0.0_dp
    b(piv(1:rank)) = y
  end subroutine solve_psd_subset


end module contact_lcp
