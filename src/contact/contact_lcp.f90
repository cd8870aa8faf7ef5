!> contact_lcp: the condensed contact problem, with or without free rigid modes.
!>
!> Without free modes it is LCP(W, q), solved by Lemke, PGS or PDAS
!> (lcp_solvers).  With k free modes R (see rigid_modes, rigid_support) it is
!> the mixed LCP
!>     mu >= 0,  gap = q + W mu - H alpha >= 0,  mu' gap = 0,  H' mu = e,
!> H = B R (how each mode opens the gaps), e = R' f (the load along the
!> modes), alpha the modes' amplitudes: the KKT conditions of
!>     min 1/2 mu'W mu + q'mu  subject to  mu >= 0, H' mu = e.
!> It is solved in four steps, each exact or checked:
!>  1. only the combinations of the modes that the contact rows hold enter
!>     (held, decided by mode_support and rigid_support before the solve);
!>     the others are unloaded and keep amplitude 0;
!>  2. the problem is made dimensionless: Ws = D W D, qs = D q with
!>     D = diag(1/sqrt(W_ii)) (lcp_scaling), and Hn = D H C with C the
!>     diagonal that gives Hn's columns unit length, en = C e, the
!>     amplitudes C^-1 alpha.  D^-1 mu, the gaps D gap, en and Hn C^-1 alpha
!>     then share one unit, so that no test below weighs a force against a
!>     moment or a length against an angle:
!>     a change of the unit of length (a RIGID's rotation column, whose
!>     entries are lever arms, grows with it) leaves the problem unchanged;
!>  3. feasibility: min |Hn'mu - en| over mu >= 0 (nonnegative least squares,
!>     itself the LCP(Hn Hn', -Hn en), by Lemke), on the first working rows
!>     (below; a balance there is one of the whole), on all rows when those
!>     have none; a minimum above 1e-8 |en| on all rows means the loads pull
!>     a body away from its contacts: no equilibrium;
!>  4. the mixed LCP itself, exactly (mixed_lcp): the active-set Newton
!>     method on the KKT system of the active rows with the amplitudes free,
!>     started from the previous solution when the caller gives one (else
!>     from qs < 0 and the rows of step 3's balance); Lemke on the LCP of the
!>     split amplitude when it cycles or stalls.  lcp=lemke takes Lemke first
!>     and the Newton method from its active set (one step: round-off).
!>
!> The rows the solve works on follow the contact zone, with free modes or
!> without.  A row whose gap no
!> displacement of the loads can close only makes the dense solve larger
!> (a disk's whole rim named as the slave against a V-groove: 1024 rows, 72
!> touching).  The working rows are first those whose gap q_i is at most the
!> deepest penetration max(0, -min q) (plus 1e-8 max |q|: a row that touches
!> has q_i = 0 to round-off, of either sign), with the rows of the start (the
!> previous solution's active set, step 3's balance); the problem is solved
!> on them alone (the others at mu_i = 0), every other row is checked,
!> D gap_i >= -tol/10 of the problem's size, and the violated ones join, with
!> every row whose gap is at most the deepest violation, for a new solve
!> started from the last, until none is violated: the answer is then that of
!> the whole problem (its rows outside carry no force and are open).  When
!> the working rows are more than half of the rows, all are taken (nothing
!> to gain); after 20 rounds too.  A failure on the working rows is retried
!> on all of them before it is reported.
!>
!> Programming interface
!>   type(contact_solution_t)   mu, alpha, gap, report, measures
!>   solve_contact(w, q, h, e, held, method, opts, sol [, outer_limit] [, mu_start])
module contact_lcp
  use kinds, only: dp
  use lapack_interfaces, only: dpotrs, dpstrf
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_pgs, lcp_natural_residual, &
                         scaling_vector
  use lcp_newton, only: solve_lcp_pdas
  use mixed_lcp, only: solve_mixed_newton, solve_mixed_lemke
  use strings, only: int_to_str, real_to_str
  implicit none
  private
  public :: contact_solution_t, solve_contact

  type :: contact_solution_t
    real(dp), allocatable :: mu(:)           !< (nc) multipliers, nodal forces
    real(dp), allocatable :: alpha(:)        !< (k) amplitudes of the free modes
    real(dp), allocatable :: gap(:)          !< (nc) final gaps q + W mu - H alpha
    type(lcp_report_t) :: rep                !< info 0 solved; else failure and message
    real(dp) :: equality_residual = 0        !< max_j |(Hn'mus - en)_j| / max(|en_j| + sum_i |Hn_ij mus_i|, max|qs|)
    integer :: outer = 0                     !< Newton steps of the mixed solve (all rounds)
    integer :: rows = 0                      !< working rows of the last round (nc: all)
    integer :: rounds = 0                    !< solves on growing working rows
  end type contact_solution_t

  integer, parameter :: max_rounds = 20            ! working-row rounds before all rows are taken
  real(dp), parameter :: delta_ratio = 0.1_dp      ! the check of the rows outside: D gap_i >= -delta_ratio tol size
  real(dp), parameter :: balance_tol = 1.0e-8_dp   ! |Hn'mu - en| above balance_tol |en| at the best balance: none
  real(dp), parameter :: touch_ratio = 1.0e-8_dp   ! |q_i| below touch_ratio max |q|: a row that touches


contains

  !> Solve the condensed contact problem.
  !>   w      (in) (nc, nc) Delassus matrix B K^# B', symmetric PSD
  !>   q      (in) (nc) gaps without contact forces
  !>   h      (in) (nc, k) B R; k = 0 for a problem without free modes
  !>   e      (in) (k) R' f
  !>   held   (in) (k, kh) basis of the combinations of the modes that the rows
  !>               hold (mode_support, rigid_support); alpha = held lambda, 0
  !>               along the others
  !>   method (in) 'lemke', 'pgs' or 'pdas'
  !>   opts   (in) tolerances
  !>   sol    (out) the solution; sol%rep%info /= 0 on failure with a message
  !>               (1: no solution, proved; 2, 3, 4: not solved)
  !>   outer_limit (in, optional) accepted and not used: the mixed problem is
  !>               solved exactly, with no multiplier iterations to limit
  !>   mu_start (in, optional) (nc) a previous solution of rows with the same
  !>               meaning (the last load step's mu): its active set starts the
  !>               solve and the working rows; ignored when of another size
  subroutine solve_contact(w, q, h, e, held, method, opts, sol, outer_limit, mu_start)
    real(dp), intent(in) :: w(:,:), q(:), h(:,:), e(:), held(:,:)
    character(len=*), intent(in) :: method
    type(lcp_options_t), intent(in) :: opts
    type(contact_solution_t), intent(out) :: sol
    integer, intent(in), optional :: outer_limit
    real(dp), intent(in), optional :: mu_start(:)
    logical, allocatable :: start(:)
    integer :: nc, k

    nc = size(q)
    k = size(e)
    allocate(sol%mu(nc), sol%alpha(k), sol%gap(nc))
    sol%mu = 0.0_dp
    sol%alpha = 0.0_dp
    allocate(start(nc))
    start = .false.
    if (present(mu_start)) then
      if (size(mu_start) == nc) start = mu_start > 0.0_dp
    end if
    if (present(outer_limit)) continue                 ! kept for the callers; nothing to limit
    if (k == 0) then
      call solve_without_modes(w, q, method, opts, start, sol)
      return
    end if
    if (size(held, 2) == 0) then                       ! no held combination: unloaded, amplitude 0
      call solve_without_modes(w, q, method, opts, start, sol)
      return
    end if
    call solve_with_modes(w, q, h, e, held, method, opts, start, present(mu_start), sol)
  end subroutine solve_contact

  !> LCP(W, q) on growing working rows (module header).
  !>   start (in) (nc) rows of a previous active set
  !>   sol   (inout) mu, gap, rep, rows, rounds
  subroutine solve_without_modes(w, q, method, opts, start, sol)
    real(dp), intent(in) :: w(:,:), q(:)
    character(len=*), intent(in) :: method
    type(lcp_options_t), intent(in) :: opts
    logical, intent(in) :: start(:)
    type(contact_solution_t), intent(inout) :: sol
    logical, allocatable :: work_rows(:)
    integer, allocatable :: rows(:)
    real(dp), allocatable :: d(:), zr(:), g(:)
    real(dp) :: delta
    integer :: nc, i, total
    logical :: done

    nc = size(q)
    allocate(work_rows(nc), d(nc))
    work_rows = first_rows(q, start)
    if (nc > 0) call scaling_vector(w, d)
    total = 0
    do
      sol%rounds = sol%rounds + 1
      rows = pack([(i, i = 1, nc)], work_rows)
      zr = sol%mu(rows)                                  ! PGS starts from it; the others from 0
      call run_solver(method, w(rows, rows), q(rows), opts, zr, sol%rep)
      total = total + sol%rep%iterations
      sol%rep%iterations = total
      sol%mu = 0.0_dp
      sol%mu(rows) = zr
      sol%rows = size(rows)
      if (sol%rep%info /= 0 .and. size(rows) < nc) then
        work_rows = .true.                               ! on all rows before it counts
        cycle
      end if
      if (sol%rep%info /= 0 .or. size(rows) == nc) exit
      g = q + matmul(w(:, rows), zr)
      delta = delta_ratio * opts%tol * max(maxval(abs(d * q)), tiny(1.0_dp))
      call grow_rows(g, d, delta, sol%rounds >= max_rounds, work_rows, done)
      if (done) then
        sol%rep%residual = lcp_natural_residual(w, q, sol%mu)
        exit
      end if
    end do
    sol%gap = q + matmul(w, sol%mu)
  end subroutine solve_without_modes

  !> The mixed LCP (steps 2 to 4 of the module header) on growing working rows.
  !>   start (in) (nc) the previous solution's active set;  warm (in) one was given
  !>   sol   (inout) every field
  subroutine solve_with_modes(w, q, h, e, held, method, opts, start, warm, sol)
    real(dp), intent(in) :: w(:,:), q(:), h(:,:), e(:), held(:,:)
    character(len=*), intent(in) :: method
    type(lcp_options_t), intent(in) :: opts
    logical, intent(in) :: start(:), warm
    type(contact_solution_t), intent(inout) :: sol
    real(dp), allocatable :: d(:), hh(:,:), eh(:), hn(:,:), en(:), cn(:), qs(:), mub(:), ws(:,:), mus(:), mur(:), &
                             alpha(:), g(:), ar(:)
    logical, allocatable :: work_rows(:), act(:)
    integer, allocatable :: rows(:)
    real(dp) :: res, delta
    integer :: nc, kh, j, i, total, steps
    logical :: done

    nc = size(q)
    kh = size(held, 2)
    ! 2. dimensionless: Ws = D W D, qs = D q, Hn = D Hh C (unit columns), en = C eh
    hh = matmul(h, held)
    eh = matmul(transpose(held), e)
    allocate(d(nc), hn(nc, kh), cn(kh))
    if (nc > 0) call scaling_vector(w, d)
    qs = d * q
    do j = 1, kh
      hn(:, j) = d * hh(:, j)
      cn(j) = norm2(hn(:, j))
      if (cn(j) == 0.0_dp) cn(j) = 1.0_dp                ! no row sees it: Hn'mu = en fails in step 3 unless en_j = 0
      hn(:, j) = hn(:, j) / cn(j)
    end do
    en = eh / cn

    ! 3. feasibility: nonnegative least squares min |Hn'mu - en|, mu >= 0, on
    ! the first working rows (a balance there is one of the whole), on all
    ! rows when they have none (the proof that there is none)
    if (warm) then
      act = start
    else
      act = qs < 0.0_dp
    end if
    allocate(work_rows(nc))
    work_rows = first_rows(q, act)
    call best_balance(hn, en, work_rows, opts, mub, res)
    if (res > balance_tol * norm2(en) .and. .not. all(work_rows)) call best_balance(hn, en, [(.true., i = 1, nc)], &
                                                                                     opts, mub, res)
    if (res > balance_tol * norm2(en)) then
      sol%rep%info = 1
      sol%rep%message = 'no equilibrium: the loads pull a body held only by contact away from its contacts ' // &
        '(the contact forces cannot balance them; residual ' // real_to_str(res / max(norm2(en), tiny(1.0_dp))) // ')'
      return
    end if

    ! 4. the mixed LCP on growing working rows, started from the previous
    ! active set or from qs < 0 and the balance's rows
    if (.not. warm) act = act .or. mub > 0.0_dp
    work_rows = work_rows .or. mub > 0.0_dp
    if (2 * count(work_rows) > nc) work_rows = .true.
    allocate(mus(nc), alpha(kh))
    mus = 0.0_dp
    alpha = 0.0_dp
    total = 0
    steps = 0
    do
      sol%rounds = sol%rounds + 1
      rows = pack([(i, i = 1, nc)], work_rows)
      allocate(ws(size(rows), size(rows)), mur(size(rows)), ar(kh))
      do j = 1, size(rows)
        ws(:, j) = d(rows) * w(rows, rows(j)) * d(rows(j))          ! (D W D)_ij
      end do
      call solve_mixed(method, ws, qs(rows), hn(rows, :), en, act(rows), opts, mur, ar, sol%rep, steps)
      deallocate(ws)
      total = total + sol%rep%iterations
      sol%rep%iterations = total
      sol%outer = sol%outer + steps
      sol%rows = size(rows)
      if (sol%rep%info /= 0 .and. size(rows) < nc) then
        work_rows = .true.                               ! on all rows before it counts
        deallocate(mur, ar)
        cycle
      end if
      mus = 0.0_dp
      mus(rows) = mur
      alpha = ar
      deallocate(mur, ar)
      if (sol%rep%info /= 0 .or. size(rows) == nc) exit
      ! the rows outside: D gap = qs + D W D mus - Hn alpha
      g = (qs + d * matmul(w(:, rows), d(rows) * mus(rows)) - matmul(hn, alpha))
      delta = delta_ratio * opts%tol * max(maxval(abs(qs - matmul(hn, alpha))), maxval(abs(mus)), tiny(1.0_dp))
      act = mus > 0.0_dp .or. (.not. work_rows .and. g < -delta)
      call grow_rows(g / d, d, delta, sol%rounds >= max_rounds, work_rows, done)
      if (done) exit
    end do
    if (sol%rep%info /= 0) return

    ! back to the problem's units: mu = D mus, alpha = held C^-1 alpha_n
    sol%mu = d * mus
    sol%alpha = matmul(held, alpha / cn)
    sol%gap = q + matmul(w, sol%mu) - matmul(h, sol%alpha)
    sol%rep%residual = lcp_natural_residual(w, q - matmul(h, sol%alpha), sol%mu)
    ! in the dimensionless unknowns (mus = mu / d, Hn's unit columns), each
    ! equation against its own terms or, when the load along it is nil and
    ! the forces are round-off (a body that only floats off), the scale of
    ! the gaps qs, the forces' own scale here
    sol%equality_residual = equality_residual(hn, en, mus, maxval(abs(qs)))
    if (sol%equality_residual > 1.0e3_dp * opts%tol) then
      sol%rep%info = 2
      sol%rep%message = 'the equilibrium of a body held only by contact was not reached (relative residual ' // &
        real_to_str(sol%equality_residual) // ' after ' // int_to_str(sol%outer) // ' active-set steps)'
    else if (sol%rep%residual > opts%tol) then
      sol%rep%info = 4
      sol%rep%message = 'the contact problem with free modes ended with a residual ' // &
        real_to_str(sol%rep%residual) // ' above tol ' // real_to_str(opts%tol) // ' (' // sol%rep%message // ')'
    end if
  end subroutine solve_with_modes

  !> The closest balance of the loads by contact forces on some rows:
  !> min |Hn'mu - en| over mu >= 0, 0 off the rows (nonnegative least squares,
  !> as the LCP of its normal equations, LCP(Hn Hn', -Hn en), by Lemke).
  !>   on  (in)  (nc) the rows that may carry a force
  !>   mu  (out) (nc) the balance;  res (out) |Hn'mu - en|
  subroutine best_balance(hn, en, on, opts, mu, res)
    real(dp), intent(in) :: hn(:,:), en(:)
    logical, intent(in) :: on(:)
    type(lcp_options_t), intent(in) :: opts
    real(dp), allocatable, intent(out) :: mu(:)
    real(dp), intent(out) :: res
    type(lcp_report_t) :: rep
    real(dp), allocatable :: hr(:,:), mr(:)
    integer, allocatable :: rows(:)
    integer :: i
    rows = pack([(i, i = 1, size(on))], on)
    hr = hn(rows, :)
    allocate(mu(size(on)), mr(size(rows)))
    mu = 0.0_dp
    call solve_lcp_lemke(matmul(hr, transpose(hr)), -matmul(hr, en), mr, opts, rep)
    mu(rows) = mr
    res = norm2(matmul(transpose(hn), mu) - en)
  end subroutine best_balance

  !> The mixed LCP on the working rows by the method's order: lcp=lemke by
  !> Lemke, its active set then solved exactly by the Newton method (one
  !> step); the others by the Newton method from act, Lemke when it fails.
  !>   ws, qs, hn, en (in) the dimensionless problem on the working rows
  !>   act   (in)  (m) the active set to start from
  !>   mu    (out) (m);  alpha (out) (k)
  !>   rep   (out) info 0 solved; iterations = Newton steps + Lemke pivots
  !>   steps (out) Newton steps
  subroutine solve_mixed(method, ws, qs, hn, en, act, opts, mu, alpha, rep, steps)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: ws(:,:), qs(:), hn(:,:), en(:)
    logical, intent(in) :: act(:)
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(out) :: mu(:), alpha(:)
    type(lcp_report_t), intent(out) :: rep
    integer, intent(out) :: steps
    type(lcp_report_t) :: rl, rn
    real(dp), allocatable :: mul(:), al(:)

    allocate(mul(size(qs)), al(size(en)))
    if (method == 'lemke') then
      call solve_mixed_lemke(ws, qs, hn, en, opts, mul, al, rl)
      if (rl%info == 0 .or. rl%info == 4) then
        call solve_mixed_newton(ws, qs, hn, en, mul > 0.0_dp, opts, mu, alpha, rn)
      else
        call solve_mixed_newton(ws, qs, hn, en, act, opts, mu, alpha, rn)
      end if
    else
      call solve_mixed_newton(ws, qs, hn, en, act, opts, mu, alpha, rn)
      if (rn%info /= 0) call solve_mixed_lemke(ws, qs, hn, en, opts, mul, al, rl)
    end if
    steps = rn%iterations
    if (rn%info == 0) then
      rep = rn
      if (method == 'lemke') rep%message = 'Lemke: ' // int_to_str(rl%iterations) // ' pivots, ' // &
        'then exact on its active set (' // rn%message // ')'
    else if (rl%info == 0 .or. rl%info == 4) then
      mu = mul
      alpha = al
      rep = rl
      rep%message = rn%message // '; Lemke: ' // rl%message
    else
      rep = rl
      if (rn%info /= 0 .and. allocated(rl%message)) rep%message = rn%message // '; Lemke: ' // rl%message
      if (rn%info /= 0 .and. .not. allocated(rl%message)) rep = rn
    end if
    rep%iterations = rn%iterations + rl%iterations
  end subroutine solve_mixed

  !> The first working rows: the gaps at most the deepest penetration,
  !> max(0, -min q), or within touch_ratio of the largest gap of zero (the
  !> rows that touch, whose q is 0 up to round-off of either sign), and the
  !> rows of the start; all rows when that is more than half of them.
  function first_rows(q, start) result(on)
    real(dp), intent(in) :: q(:)
    logical, intent(in) :: start(:)
    logical, allocatable :: on(:)
    real(dp) :: margin
    margin = 0.0_dp
    if (size(q) > 0) margin = max(0.0_dp, -minval(q)) + touch_ratio * maxval(abs(q))
    on = q <= margin .or. start
    if (2 * count(on) > size(q)) on = .true.
  end function first_rows

  !> The check of the rows outside the working ones, and their growth.
  !>   g      (in)    (nc) the gaps of the solution on the working rows (all rows)
  !>   d      (in)    (nc) D: d g is the dimensionless gap
  !>   delta  (in)    a row outside is violated when d_i g_i < -delta
  !>   last   (in)    the last round: all rows when one is violated
  !>   on     (inout) (nc) the working rows; the violated ones join, with every
  !>                  row whose gap is at most the deepest violation
  !>   done   (out)   no row outside is violated
  subroutine grow_rows(g, d, delta, last, on, done)
    real(dp), intent(in) :: g(:), d(:), delta
    logical, intent(in) :: last
    logical, intent(inout) :: on(:)
    logical, intent(out) :: done
    logical, allocatable :: violated(:)
    real(dp) :: margin
    allocate(violated(size(g)))
    violated = .not. on .and. d * g < -delta
    done = .not. any(violated)
    if (done) return
    margin = maxval(-g, mask=violated)
    on = on .or. g <= margin
    if (2 * count(on) > size(g) .or. last) on = .true.
  end subroutine grow_rows

  !> max_j |(H'mu - e)_j| / max(|e_j| + sum_i |H_ij mu_i|, floor): each
  !> component of the equilibrium against the size of its own terms, or the
  !> problem's force scale when they are smaller (a nil load balanced by
  !> round-off forces is balanced); 0 where all its terms and floor are 0.
  !>   h (in) (n, k) the columns;  e (in) (k) the loads;  mu (in) (n) the forces
  !>   floor (in) the force scale below which terms are round-off
  pure real(dp) function equality_residual(h, e, mu, floor) result(r)
    real(dp), intent(in) :: h(:,:), e(:), mu(:), floor
    real(dp) :: sc
    integer :: j
    r = 0.0_dp
    do j = 1, size(e)
      sc = max(abs(e(j)) + sum(abs(h(:, j) * mu)), floor)
      if (sc > 0.0_dp) r = max(r, abs(dot_product(h(:, j), mu) - e(j)) / sc)
    end do
  end function equality_residual

  !> One LCP(W, q) by Lemke, PGS or PDAS.  PGS stops on its residual, which on
  !> an ill-conditioned W (stiffness contrasts) still leaves errors of order
  !> cond(W) x tol in z, or stagnates; its active set is then finished by the
  !> exact solve W_AA z_A = -q_A, kept only when it satisfies the LCP to the
  !> tolerance (z >= 0, w >= 0, smaller residual).
  !>   z (inout) PGS's start; the solution on exit
  subroutine run_solver(method, w, q, opts, z, rep)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: w(:,:), q(:)
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: z(:)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable :: zf(:)
    real(dp) :: r
    if (method == 'pgs') then
      call solve_lcp_pgs(w, q, z, opts, rep)
      if (rep%info == 0 .or. rep%info == 3) then
        zf = z
        call finish_active(w, q, zf)
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

  !> Exact finish of an LCP's active set A = {z > 0}: W_AA z_A = -q_A (W_AA
  !> may be singular, redundant constraints: pivoted Cholesky, solve on the
  !> independent rows, zero on the dependent ones), kept when z_A >= 0 (to
  !> round-off, 1e-10 of max z) and the gaps are >= 0 (1e-10 of their scale).
  subroutine finish_active(w, q, z)
    real(dp), intent(in) :: w(:,:), q(:)
    real(dp), intent(inout) :: z(:)
    integer, allocatable :: act(:)
    real(dp), allocatable :: a(:,:), b(:), gap(:), z_new(:)
    integer :: na, info, n
    real(dp) :: scale
    act = pack([(n, n = 1, size(z))], z > 0.0_dp)
    na = size(act)
    a = w(act, act)
    b = -q(act)
    call solve_psd_subset(a, b, info)
    if (info /= 0) return
    z_new = z
    z_new(act) = b
    ! a multiplier that is 0 in exact arithmetic (a degenerate or redundant
    ! row) may come out at -1e-12: round-off, set to 0; a clearly negative
    ! one means a wrong active set
    if (any(z_new(act) < -1.0e-10_dp * maxval(abs(z_new)))) return
    z_new = max(z_new, 0.0_dp)
    gap = q + matmul(w, z_new)
    scale = maxval(abs(q)) + maxval(abs(matmul(w, z_new)))
    if (any(gap < -1.0e-10_dp * scale)) return
    z = z_new
  end subroutine finish_active

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
