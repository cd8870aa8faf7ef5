!> mixed_lcp: the mixed LCP of contact with free modes, exactly, on a
!> dimensionless problem.
!>
!> Find mu (m), alpha (k) with
!>     mu >= 0,  g = qs + Ws mu - Hn alpha >= 0,  mu'g = 0,  Hn'mu = en,
!> the KKT conditions of  min 1/2 mu'Ws mu + qs'mu  subject to  mu >= 0,
!> Hn'mu = en.  The caller (contact_lcp) makes it dimensionless: Ws = D W D
!> has a unit diagonal (D = diag(1/sqrt(W_ii)), lcp_scaling), Hn = D H C has
!> columns of unit length (C diagonal), so that mu, g, qs, en and Hn alpha
!> all have one unit and every test below compares like with like.
!>
!> Active-set (semismooth) Newton.  The primal-dual active set method of
!> lcp_newton (Hintermueller, Ito & Kunisch, SIAM J. Optim. 13 (2003) 865-888)
!> with alpha a free unknown: for the active set A (mu_I = 0 off it) one step
!> solves the KKT system
!>     [ Ws_AA  -Hn_A ] [mu_A ]   [-qs_A]
!>     [-Hn_A'    0   ] [alpha] = [-en  ],                                  (1)
!> then g = qs + Ws mu - Hn alpha on every row, and the next active set is
!> {i in A : mu_i > -delta} u {i not in A : g_i < -delta}; it stops when no
!> index is infeasible (mu_A >= -delta, g_I >= -delta), delta = tol/10 of the
!> size of the terms (qs, mu, Hn alpha, en).  No penalty, so no unit: the
!> answer is the exact solution of (1) on the final active set.
!> (1) is solved with its second row added rho times to the first,
!>     (Ws_AA + rho Hn_A Hn_A') mu_A - Hn_A alpha = -(qs_A - rho Hn_A en),
!> which changes nothing where Hn_A'mu_A = en and makes the block definite
!> where Ws_AA is only semi-definite (a row on a dof that a body's free modes
!> pin has W_ii = 0 and is held by Hn alone); rho = 1 / max_i |Hn_i|^2 gives
!> the added part a largest diagonal entry of 1, as Ws's.  Then through the
!> pivoted Cholesky factor of that block, L L' (dpstrf), and the SVD of
!> Y = L^-1 Hn_A = U S V' (dgesvd): with y = L' mu_A and
!> c = L^-1 (qs_A - rho Hn_A en), y = Y alpha - c and Y'y = en give
!>     V_j'alpha = V_j'en / s_j^2 + U_j'c / s_j,                            (2)
!> then y = Y alpha - c and mu_A = L^-T y, whose condition is that of Y, not
!> of Y'Y.  Two degenerate cases are handled rather than failed:
!>  - a combination V_j that the active rows do not hold, s_j <= 1e-10 s_1
!>    (no row of A yet, or one row for three modes): its amplitude keeps its
!>    last value; when the load along it, V_j'(en - Hn_A'mu_A), is not zero,
!>    the modes move along it (the load's way) until the first row closes
!>    (a ratio test, as a primal active-set method does), and that row joins A;
!>  - a row of A that depends on the others (pivot below 1e-12: its rows of
!>    Ws and Hn both, a redundant constraint) keeps mu_i = 0, as in
!>    lcp_newton, and must end with g_i >= -delta.
!> Every active set visited is remembered (two 31-bit hashes); a repeat
!> (cycling), a set that cannot change while a row is infeasible, or the step
!> limit ends the method with info 3, and the caller turns to Lemke.
!>
!> Lemke.  The same problem as the LCP of the free amplitude split in two,
!> alpha = a+ - a- (Cottle, Pang & Stone, The Linear Complementarity Problem,
!> sect. 1.2):
!>     M = [Ws -Hn Hn; Hn' 0 0; -Hn' 0 0],  q = [qs; -en; en],  z = [mu; a+; a-],
!> whose last rows say Hn'mu - en >= 0 and <= 0.  M is copositive-plus (its
!> symmetric part is [Ws 0 0; 0 0 0; 0 0 0], PSD), so Lemke ends on a
!> solution or on a ray that proves there is none; finite, dense, the slow
!> and sure way.
!>
!> Programming interface
!>   solve_mixed_newton(ws, qs, hn, en, act, opts, mu, alpha, rep)
!>   solve_mixed_lemke(ws, qs, hn, en, opts, mu, alpha, rep)
!> Both report in an lcp_report_t: info 0 solved, 1 no solution (Lemke's
!> ray), 2 step or pivot limit, 3 the Newton method cycled or stalled, 4
!> Lemke's residual above tol; iterations = Newton steps or pivots.
!> No routine prints anything.
module mixed_lcp
  use kinds, only: dp, i8
  use lapack_interfaces, only: dpstrf, dtrsm, dtrsv, dgesvd
  use strings, only: int_to_str, real_to_str
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke_scaled
  implicit none
  private
  public :: solve_mixed_newton, solve_mixed_lemke

  real(dp), parameter :: pivot_tol = 1.0e-12_dp      ! smallest pivot of the block (unit diagonal): a dependent row
  real(dp), parameter :: hold_ratio = 1.0e-10_dp     ! s_j <= hold_ratio s_1: V_j not held by the active rows
  real(dp), parameter :: delta_ratio = 0.1_dp        ! delta = delta_ratio tol (size of the terms), as lcp_newton
  integer(i8), parameter :: hash_prime(2) = [2147483647_i8, 2147483629_i8]   ! set_hash's moduli

contains

  !> The mixed LCP by the active-set Newton method (module header).
  !>   ws    (in)    (m, m) symmetric PSD, unit diagonal (0 on a zero row)
  !>   qs    (in)    (m) gaps without contact forces
  !>   hn    (in)    (m, k) how the modes open the gaps, columns of unit length (or 0)
  !>   en    (in)    (k) the loads along the modes
  !>   act   (in)    (m) the active set to start from (a previous solution's
  !>                 mu > 0, or qs < 0 and the rows of a feasible balance)
  !>   opts  (in)    tol (delta above); maxit (Newton steps, 0: 10 m + 100)
  !>   mu    (out)   (m) the solution, >= 0 (on failure the last iterate)
  !>   alpha (out)   (k) the amplitudes
  !>   rep   (out)   info 0, 1, 2 or 3 (module header); iterations = steps; message
  subroutine solve_mixed_newton(ws, qs, hn, en, act, opts, mu, alpha, rep)
    real(dp), intent(in) :: ws(:,:), qs(:), hn(:,:), en(:)
    logical, intent(in) :: act(:)
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(out) :: mu(:), alpha(:)
    type(lcp_report_t), intent(out) :: rep
    logical, allocatable :: on(:), next(:), dependent(:)
    real(dp), allocatable :: g(:), lam(:), vs(:,:), hv(:), ratio(:)
    integer(i8), allocatable :: seen(:,:)
    integer(i8) :: hash(2)
    real(dp) :: delta, scale, load_tol, t, s
    integer :: m, k, step, maxit, j, i, nseen, ndep
    logical :: loaded, moved

    m = size(qs)
    k = size(en)
    mu = 0.0_dp
    alpha = 0.0_dp
    rep%info = 0
    rep%iterations = 0
    maxit = opts%maxit
    if (maxit == 0) maxit = 10 * m + 100
    on = act
    allocate(seen(2, 16))
    nseen = 0
    ndep = 0
    do step = 1, maxit
      rep%iterations = step
      call solve_active_kkt(ws, qs, hn, en, on, alpha, mu, dependent, vs, lam)
      ndep = max(ndep, count(dependent))
      g = qs + matmul(ws, mu) - matmul(hn, alpha)                  ! g = qs + Ws mu - Hn alpha
      scale = max(maxval(abs(qs)), maxval(abs(mu)), maxval(abs(matmul(hn, alpha))), maxval(abs(en)), tiny(1.0_dp))
      delta = delta_ratio * opts%tol * scale
      load_tol = opts%tol * max(norm2(en), norm2(mu), tiny(1.0_dp))
      ! the largest load along a combination the active rows do not hold
      j = 0
      if (size(lam) > 0) then
        j = maxloc(abs(lam), dim=1)
        if (abs(lam(j)) <= load_tol) j = 0
      end if
      loaded = j > 0
      if (.not. loaded .and. all(mu >= -delta .or. .not. on) .and. all(g >= -delta .or. (on .and. .not. dependent))) then
        mu = max(mu, 0.0_dp)
        rep%message = 'active-set Newton: solved in ' // int_to_str(step) // ' steps'
        if (ndep > 0) rep%message = rep%message // '; ' // int_to_str(ndep) // &
          ' linearly dependent row(s) kept out of the active set'
        return
      end if
      next = (on .and. mu > -delta) .or. (.not. on .and. g < -delta)
      moved = .false.
      if (loaded) then
        ! move along V_j, the way its load pulls, until the first row closes:
        ! the rows with s (Hn V_j)_i > 0 close at t = g_i / (s (Hn V_j)_i)
        s = sign(1.0_dp, lam(j))
        hv = s * matmul(hn, vs(:, j))
        allocate(ratio(m))
        ratio = huge(1.0_dp)
        do i = 1, m
          if (.not. on(i) .and. hv(i) > hold_ratio * maxval(abs(hv))) ratio(i) = max(g(i), 0.0_dp) / hv(i)
        end do
        i = minloc(ratio, dim=1)
        if (ratio(i) == huge(1.0_dp)) then           ! a balance exists (the caller's test): round-off
          call stalled(rep, 'no row closes along a combination of the modes the loads pull', step)
          return
        end if
        t = ratio(i)
        alpha = alpha + t * s * vs(:, j)
        next(i) = .true.
        deallocate(ratio)
        moved = .true.
      end if
      if (all(next .eqv. on) .and. .not. moved) then
        call stalled(rep, 'a row stays infeasible that the active set cannot take (linearly dependent on the others)', &
                     step)
        return
      end if
      hash = set_hash(next)
      if (any(seen(1, 1:nseen) == hash(1) .and. seen(2, 1:nseen) == hash(2)) .and. .not. moved) then
        call stalled(rep, 'an active set came back (cycling)', step)
        return
      end if
      if (nseen == size(seen, 2)) seen = reshape([seen, 0_i8 * seen], [2, 2 * nseen])
      nseen = nseen + 1
      seen(:, nseen) = hash
      on = next
    end do
    rep%info = 2
    rep%message = 'active-set Newton: step limit ' // int_to_str(maxit) // ' reached'
  end subroutine solve_mixed_newton

  !> The report of a Newton run that cannot go on (info 3: the caller turns
  !> to Lemke), `active-set Newton: WHY after STEP steps`.
  !>   rep  (inout) info and message set
  !>   why  (in)    what stopped it
  !>   step (in)    the steps done
  subroutine stalled(rep, why, step)
    type(lcp_report_t), intent(inout) :: rep
    character(len=*), intent(in) :: why
    integer, intent(in) :: step
    rep%info = 3
    rep%message = 'active-set Newton: ' // why // ' after ' // int_to_str(step) // ' steps'
  end subroutine stalled

  !> One Newton step: the KKT system (1) on the active set, by (2).
  !>   on        (in)    (m) the active set
  !>   alpha     (inout) (k) in: the amplitudes kept along what A does not hold;
  !>                     out: the step's amplitudes
  !>   mu        (out)   (m) the step's multipliers, 0 off A and on dependent rows
  !>   dependent (out)   (m) the rows of A kept at 0 (they depend on the others)
  !>   vs        (out)   (k, ns) the combinations A does not hold (orthonormal)
  !>   lam       (out)   (ns) the load along each that A leaves unbalanced
  subroutine solve_active_kkt(ws, qs, hn, en, on, alpha, mu, dependent, vs, lam)
    real(dp), intent(in) :: ws(:,:), qs(:), hn(:,:), en(:)
    logical, intent(in) :: on(:)
    real(dp), intent(inout) :: alpha(:)
    real(dp), intent(out) :: mu(:)
    logical, allocatable, intent(out) :: dependent(:)
    real(dp), allocatable, intent(out) :: vs(:,:), lam(:)
    integer, allocatable :: a(:), piv(:), rows(:)
    real(dp), allocatable :: l(:,:), y(:,:), ysvd(:,:), c(:), yv(:), s(:), u(:,:), vt(:,:), va(:), work(:), qr(:)
    logical, allocatable :: held(:)
    real(dp) :: wq(1), rho
    integer :: m, k, na, r, j, info, nsv

    m = size(qs)
    k = size(en)
    a = pack([(j, j = 1, m)], on)
    na = size(a)
    mu = 0.0_dp
    allocate(dependent(m))
    dependent = .false.
    r = 0
    allocate(qr(m))
    qr = qs
    if (na > 0) then
      ! Ws_AA + rho Hn_A Hn_A', qs_A - rho Hn_A en: the equilibrium added to
      ! the gap rows, rho making its largest diagonal entry 1 as Ws's
      rho = 0.0_dp
      if (k > 0) rho = maxval(sum(hn(a, :)**2, dim=2))
      if (rho > 0.0_dp) rho = 1.0_dp / rho
      l = ws(a, a)
      if (k > 0) then
        l = l + rho * matmul(hn(a, :), transpose(hn(a, :)))
        qr(a) = qs(a) - rho * matmul(hn(a, :), en)
      end if
      allocate(piv(na), work(2 * na))
      call dpstrf('L', na, l, na, piv, r, pivot_tol, work, info)     ! P' (Ws_AA + rho Hn_A Hn_A') P = L L'
      if (info < 0) r = 0
      dependent(a(piv(r + 1:na))) = .true.
      rows = a(piv(1:r))
    else
      allocate(rows(0), l(1, 1))
    end if
    ! Y = L^-1 Hn_R, c = L^-1 (qs_R - rho Hn_R en)
    allocate(y(r, k), c(r))
    if (r > 0) then
      y = hn(rows, :)
      c = qr(rows)
      if (k > 0) call dtrsm('L', 'L', 'N', 'N', r, k, 1.0_dp, l, size(l, 1), y, r)
      call dtrsv('L', 'N', 'N', r, l, size(l, 1), c, 1)
    end if
    ! Y = U S V'
    nsv = min(r, k)
    allocate(s(k), u(max(r, 1), max(nsv, 1)), vt(k, k))
    s = 0.0_dp
    u = 0.0_dp
    vt = 0.0_dp
    do j = 1, k
      vt(j, j) = 1.0_dp
    end do
    if (nsv > 0) then
      ysvd = y
      call dgesvd('S', 'A', r, k, ysvd, r, s(1:nsv), u, r, vt, k, wq, -1, info)
      if (allocated(work)) deallocate(work)
      allocate(work(max(1, int(wq(1)))))
      call dgesvd('S', 'A', r, k, ysvd, r, s(1:nsv), u, r, vt, k, work, size(work), info)
      if (info /= 0) s = 0.0_dp
    end if
    allocate(held(k), va(k))
    held = .false.
    if (k > 0) held = s > hold_ratio * s(1) .and. s > 0.0_dp
    if (k > 0) then
      do j = 1, k
        if (held(j)) then
          va(j) = dot_product(vt(j, :), en) / s(j)**2 + dot_product(u(1:r, j), c) / s(j)     ! (2)
        else
          va(j) = dot_product(vt(j, :), alpha)                                                 ! kept
        end if
      end do
      alpha = matmul(transpose(vt), va)
    end if
    ! y = Y alpha - c, mu_R = L^-T y
    if (r > 0) then
      yv = matmul(y, alpha) - c
      c = yv
      call dtrsv('L', 'T', 'N', r, l, size(l, 1), yv, 1)
      mu(rows) = yv
    end if
    ! the load that A leaves along what it does not hold: V_j'(en - Y'y)
    vs = transpose(vt(pack([(j, j = 1, size(held))], .not. held), :))
    allocate(lam(size(vs, 2)))
    if (size(vs, 2) > 0) then
      if (r > 0) then
        lam = matmul(transpose(vs), en - matmul(transpose(y), c))
      else
        lam = matmul(transpose(vs), en)
      end if
    end if
  end subroutine solve_active_kkt

  !> The mixed LCP by Lemke on the LCP of the split amplitude (module header).
  !>   ws, qs, hn, en (in) as for solve_mixed_newton
  !>   opts  (in)  tol, maxit (pivots, 0: 10 (m + 2k) + 100)
  !>   mu    (out) (m) the solution (on failure the last almost-complementary point)
  !>   alpha (out) (k) a+ - a-
  !>   rep   (out) solve_lcp_lemke_scaled's: info 0 solved, 1 ray (no solution),
  !>               2 pivot limit, 4 residual above tol; iterations = pivots
  subroutine solve_mixed_lemke(ws, qs, hn, en, opts, mu, alpha, rep)
    real(dp), intent(in) :: ws(:,:), qs(:), hn(:,:), en(:)
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(out) :: mu(:), alpha(:)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable :: mm(:,:), qq(:), d(:), z(:)
    integer :: m, k, n
    m = size(qs)
    k = size(en)
    n = m + 2 * k
    allocate(mm(n, n), source=0.0_dp)
    mm(1:m, 1:m) = ws
    mm(1:m, m + 1:m + k) = -hn
    mm(1:m, m + k + 1:n) = hn
    mm(m + 1:m + k, 1:m) = transpose(hn)
    mm(m + k + 1:n, 1:m) = -transpose(hn)
    qq = [qs, -en, en]
    allocate(d(n), z(n))
    d = 1.0_dp                                                ! already dimensionless
    call solve_lcp_lemke_scaled(mm, qq, d, z, opts, rep)
    mu = z(1:m)
    alpha = z(m + 1:m + k) - z(m + k + 1:n)
  end subroutine solve_mixed_lemke

  !> Two hashes of the rows in a set (multiplicative, modulo the primes
  !> 2**31 - 1 and 2**31 - 19: every product fits in 63 bits).
  pure function set_hash(on) result(h)
    logical, intent(in) :: on(:)
    integer(i8) :: h(2)
    integer :: i
    h = [1_i8, 7_i8]
    do i = 1, size(on)
      if (.not. on(i)) cycle
      h(1) = modulo(h(1) * 48271_i8 + int(i, i8), hash_prime(1))
      h(2) = modulo(h(2) * 69621_i8 + int(i, i8), hash_prime(2))
    end do
  end function set_hash

end module mixed_lcp
