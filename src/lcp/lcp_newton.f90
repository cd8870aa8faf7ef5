!> lcp_newton: the primal-dual active set method (semismooth Newton) for the
!> linear complementarity problem of frictionless contact.
!>
!> LCP(W, q): find z >= 0 with w = q + W z >= 0 and z'w = 0, W (n x n) the
!> symmetric positive semi-definite Delassus matrix (conventions, scaling and
!> residual as in lcp_scaling).  The method works on the scaled problem
!>     Ws = D W D,  qs = D q,  D = diag(1/sqrt(W_ii))        (scale_lcp)
!> and is Newton's method on the semismooth equation
!>     F(zs) = zs - max(0, zs - c ws) = 0,   ws = qs + Ws zs,   c = 1,
!> whose generalized Jacobian is fixed by the active set
!>     A = { i : zs_i - c ws_i > 0 },   I = the complement.
!> One Newton step from (zs, ws) (Hintermueller, Ito & Kunisch, SIAM J. Optim.
!> 13 (2003) 865-888) is
!>     Ws_AA zs_A = -qs_A,   zs_I = 0,   ws = qs + Ws zs,            (1)
!> and the next active set is {i in A : zs_i > 0} u {i in I : ws_i < 0}: every
!> infeasible index changes side (block principal pivoting; after the first
!> step the sequence no longer depends on c).  The start is zs = 0, ws = qs,
!> so A_0 = {qs_i < 0}.  The iteration stops when no index is infeasible
!> (the active set repeats), i.e. zs_A >= -delta and ws_I >= -delta with
!> delta = tol ||qs||_inf / 10, and the natural residual
!> ||min(zs, ws)||_inf / ||qs||_inf (lcp_natural_residual; 1 in place of
!> ||qs|| when q = 0) is at most tol.
!>
!> Linear algebra.  Ws_AA = L L' is kept as a dense lower Cholesky factor in
!> the order in which the indices joined A, and changed rather than recomputed:
!>   - indices joining A are appended as one block,
!>         L21 = Ws_NA L11^-T (dtrsm),  L22 L22' = Ws_NN - L21 L21' (dsyrk, dpotrf),
!>     O(|A|^2 k) for k new indices; a factor from scratch is the case |A| = 0;
!>   - an index leaving A at position k deletes row k of L, and Givens rotations
!>     of the columns k..|A| restore the triangle, O((|A| - k)^2 + k (|A| - k));
!>   - when that is dearer than re-factoring the trailing part (the factor is
!>     truncated before the first position that changes and the rest appended
!>     again as one block, at BLAS-3 speed), that is done instead; the choice is
!>     a flop count with the rotations weighted by givens_weight (measured).
!> Each solve (1) is dpotrs with the factor, then up to two steps of iterative
!> refinement with the true Ws; if the refined residual on A is still above
!> delta after updates, the factor is recomputed from scratch.
!>
!> Redundant constraints.  When Ws_AA would be singular (duplicate or linearly
!> dependent rows of B), the appended block is factored by pivoted Cholesky
!> (dpstrf) and the indices whose pivot (in the Schur complement) is below
!> pivot_tol are left out of A, i.e. kept at z_i = 0; w_i is then a constant
!> and the answer is accepted when it is >= -delta.
!>
!> Safeguards.  The plain iteration converges for M-matrices and in practice
!> for contact problems, but can cycle on a general symmetric positive definite
!> W (3 x 3 examples exist).  Every active set visited is remembered (a 2 x 61
!> bit hash); when the plain iteration comes back to one, only the infeasible
!> index of least number changes side (Murty's least-index principal pivoting,
!> finite for P-matrices, hence for SPD W) until the number of infeasible
!> indices falls below its smallest value so far, as in the hybrid method of
!> Judice & Pires (Comput. Oper. Res. 21 (1994) 587-596), whose own trigger
!> (that number not decreasing) would fire on contact problems, where it stays
!> at about two while the contact zone shrinks node by node.  The scheme is
!> finite for SPD W.  If a single-index phase repeats an active set (W singular,
!> not a P-matrix) or a step cannot change the active set (a redundant
!> constraint stays infeasible), the problem is handed to solve_lcp_lemke and
!> the message says so.
!>
!> One file of about 820 lines: the active-set iteration and the Cholesky
!> factor of Ws_AA it updates in place (append, delete, truncate) are one
!> algorithm sharing one private type; apart, neither would read alone.
!>
!> Programming interface
!>   solve_lcp_pdas(W, q, z, opts, rep [, factor_mode] [, stats])
!>       W (n, n) symmetric PSD, q (n), z (n) out; opts%tol, opts%maxit (Newton steps,
!>       0: 10 n + 100; omega is not used); rep as for solve_lcp_lemke:
!>       info 0 solved, 1 no solution (zero row of W with q_i < 0, or the Lemke
!>       fallback ended on a ray), 2 step limit, 3 cycling or stagnation that the
!>       Lemke fallback could not resolve, 4 stopped with a residual above tol
!>       (W ill-conditioned), -k argument k invalid; iterations = Newton steps
!>       (linear solves (1)); residual, complementarity as in lcp_solvers.
!>   factor_mode  pdas_factor_auto (default), pdas_factor_refactor (factor from
!>       scratch every step), pdas_factor_update (never refactor once started)
!>   type(pdas_stats_t)  counts of exchanges, factorizations, updates, refinements
!> No routine prints anything.
module lcp_newton
  use kinds, only: dp, i8
  use lapack_interfaces, only: dpotrf, dpotrs, dpstrf, drot, dsyrk, dtrsm
  use strings, only: int_to_str, real_to_str
  use lcp_solvers, only: lcp_options_t, lcp_report_t, scale_lcp, solve_lcp_lemke, lcp_natural_residual, &
                         measure_solution, set_report, max_diagonal
  use lcp_scaling, only: check_lcp_sizes, check_lcp_values, residual_outcome, lcp_gaps
  use sorting, only: sort_by_key, sort_integers
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: solve_lcp_pdas, pdas_stats_t
  public :: pdas_factor_auto, pdas_factor_refactor, pdas_factor_update

  integer, parameter :: pdas_factor_auto = 0      !< update or refactor, whichever costs fewer flops
  integer, parameter :: pdas_factor_refactor = 1  !< factor Ws_AA from scratch at every step
  integer, parameter :: pdas_factor_update = 2    !< append / delete only (after the first factor)

  !> What a solve did (informational; iterations are also in the report).
  type :: pdas_stats_t
    integer :: steps = 0                 !< Newton steps = linear solves (1)
    integer :: full_exchanges = 0        !< steps after which every infeasible index changed side
    integer :: single_exchanges = 0      !< steps after which one index changed side (safeguard)
    integer :: factorizations = 0        !< factors of Ws_AA from scratch
    integer :: trailing_refactors = 0    !< factors truncated and their trailing part recomputed
    integer :: appended = 0              !< indices appended to a non-empty factor
    integer :: deleted = 0               !< indices deleted by Givens rotations
    integer :: redundant = 0             !< indices kept out of A as linearly dependent (all steps)
    integer :: refinements = 0           !< iterative refinement steps
    integer :: max_active = 0            !< largest |A| factored
    logical :: lemke_fallback = .false.  !< the answer comes from solve_lcp_lemke
  end type pdas_stats_t

  !> Dense Cholesky factor of Ws_AA in the order the indices joined A.
  type :: active_factor_t
    integer :: p = 0                     !< |A|, rows of the factor in use
    integer :: cap = 0                   !< leading dimension of l
    real(dp), allocatable :: l(:, :)     !< (cap, cap) lower factor in l(1:p, 1:p); zero elsewhere
    integer, allocatable :: order(:)     !< (m) order(k): index at position k, k <= p
    integer, allocatable :: pos(:)       !< (m) position of index i in A, 0 when i is not in A
    logical :: fresh = .false.           !< computed from scratch since the last update
  end type active_factor_t

  real(dp), parameter :: diag_zero_ratio = 1.0e-30_dp      ! W_ii below this * max diag: zero row
  real(dp), parameter :: pivot_tol = 1.0e-12_dp            ! smallest Schur pivot of Ws_AA (unit diagonal)
  real(dp), parameter :: delta_ratio = 0.1_dp              ! delta = delta_ratio tol ||qs||
  real(dp), parameter :: givens_weight = 8.0_dp            ! cost of a rotation flop in dpotrf flops
  real(dp), parameter :: symmetry_tol = 1.0e-8_dp          ! largest |Ws_ij - Ws_ji| accepted
  integer(i8), parameter :: hash_prime = 2305843009213693951_i8   ! 2**61 - 1


contains

  !> Solve LCP(W, q) by the primal-dual active set method on the scaled
  !> problem, with factor updates, the least-index safeguard and a Lemke
  !> fallback (module header).
  !>   W            (in)  (n, n) symmetric PSD matrix, finite (scaled entries
  !>                      symmetric to 1e-8)
  !>   q            (in)  (n) finite
  !>   z            (out) (n) the solution when rep%info = 0 or 4; otherwise the
  !>                      iterate of smallest residual (finite, >= 0); zero on an
  !>                      argument error or an infeasible zero row
  !>   opts         (in)  tol > 0; maxit >= 0 Newton steps (0: 10 n + 100)
  !>   rep          (out) info 0 solved, 1 no solution, 2 step limit, 3 cycling or
  !>                      stagnation not resolved by Lemke, 4 residual above tol,
  !>                      -k argument k invalid; iterations = Newton steps;
  !>                      residual; complementarity; message
  !>   factor_mode  (in, optional) pdas_factor_auto (default), pdas_factor_refactor
  !>                      or pdas_factor_update
  !>   stats        (out, optional) counts (pdas_stats_t)
  subroutine solve_lcp_pdas(W, q, z, opts, rep, factor_mode, stats)
    real(dp), intent(in) :: W(:, :)
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: z(:)
    type(lcp_options_t), intent(in) :: opts
    type(lcp_report_t), intent(out) :: rep
    integer, intent(in), optional :: factor_mode
    type(pdas_stats_t), intent(out), optional :: stats
    type(pdas_stats_t) :: st
    type(lcp_report_t) :: lemke_rep
    type(lcp_options_t) :: lemke_opts
    real(dp), allocatable :: d(:), wsf(:, :), qsf(:), ws(:, :), qs(:), zs(:), zl(:)
    integer, allocatable :: rows(:)
    real(dp) :: dmax, qscale, pdas_residual, asym
    integer :: n, m, i, j, mode, maxit, nbad, first_bad, outcome
    character(len=:), allocatable :: why

    z = 0.0_dp
    rep%info = 0
    rep%iterations = 0
    mode = pdas_factor_auto
    if (present(factor_mode)) mode = factor_mode
    n = size(q)
    call check_lcp_sizes(W, q, size(z), opts, rep)
    if (rep%info == 0 .and. (mode < pdas_factor_auto .or. mode > pdas_factor_update)) &
      call set_report(rep, -6, 'PDAS: factor_mode = ' // int_to_str(mode) // ' (expected 0, 1 or 2)')
    if (rep%info == 0) call check_lcp_values(W, q, rep)
    if (rep%info < 0) then
      if (present(stats)) stats = st
      return
    end if
    dmax = max_diagonal(W)

    ! Scale; zero rows of W (redundant constraints) are set aside with z_i = 0.
    allocate(d(n), wsf(n, n), qsf(n))
    call scale_lcp(W, q, d, wsf, qsf)
    call largest_asymmetry(wsf, asym, i, j)
    if (asym > symmetry_tol) then
      call set_report(rep, -1, 'PDAS: W is not symmetric: W(' // int_to_str(i) // ',' // int_to_str(j) // &
        ') and W(' // int_to_str(j) // ',' // int_to_str(i) // ') differ by ' // real_to_str(asym) // &
        ' of sqrt(W_ii W_jj) (use Lemke for a non-symmetric W)')
      if (present(stats)) stats = st
      return
    end if
    qscale = 1.0_dp                                    ! ||qs||_inf, 1 when q = 0
    if (n > 0) then
      if (maxval(abs(qsf)) > 0.0_dp) qscale = maxval(abs(qsf))
    end if
    m = 0
    nbad = 0
    first_bad = 0
    do i = 1, n
      if (W(i, i) <= diag_zero_ratio * dmax) then
        if (qsf(i) < -opts%tol * qscale) then
          nbad = nbad + 1
          if (first_bad == 0) first_bad = i
        end if
      else
        m = m + 1
      end if
    end do
    if (nbad > 0) then
      call measure_solution(W, q, d, z, rep)
      call set_report(rep, 1, 'LCP: row/column ' // int_to_str(first_bad) // &
        ' of W is zero (redundant constraint) but q(' // int_to_str(first_bad) // ') = ' // &
        real_to_str(q(first_bad)) // ' < 0: the LCP has no solution (' // int_to_str(nbad) // &
        ' such row(s))')
      if (present(stats)) stats = st
      return
    end if
    rows = pack([(i, i = 1, n)], .not. ([(W(i, i), i = 1, n)] <= diag_zero_ratio * dmax))
    if (m == n) then
      call move_alloc(wsf, ws)
      call move_alloc(qsf, qs)
    else
      allocate(ws(m, m))
      do j = 1, m
        ws(:, j) = wsf(rows, rows(j))
      end do
      qs = qsf(rows)
      deallocate(wsf, qsf)
    end if

    maxit = opts%maxit
    if (maxit == 0) maxit = 10 * n + 100
    allocate(zs(m))
    call pdas_scaled(ws, qs, qscale, delta_ratio * opts%tol * qscale, maxit, mode, zs, st, outcome, why)
    deallocate(ws, qs)
    z(rows) = d(rows) * zs                             ! z = D zs
    where (z < 0.0_dp) z = 0.0_dp
    call measure_solution(W, q, d, z, rep)
    rep%iterations = st%steps
    pdas_residual = rep%residual

    select case (outcome)
    case (0)
      call residual_outcome(rep, opts%tol, 'PDAS: solved in ' // int_to_str(st%steps) // ' Newton steps', &
        'PDAS: active set settled after ' // int_to_str(st%steps) // ' Newton steps', 'W ill-conditioned')
      if (st%single_exchanges > 0) rep%message = rep%message // '; ' // &
        int_to_str(st%single_exchanges) // ' single-index steps against cycling'
      if (st%redundant > 0) rep%message = rep%message // '; ' // int_to_str(st%redundant) // &
        ' linearly dependent constraint(s) kept out of the active set (W_AA singular)'
    case (2)
      rep%info = 2
      rep%message = 'PDAS: Newton step limit ' // int_to_str(maxit) // ' reached, residual ' // &
        real_to_str(rep%residual) // ' > tol ' // real_to_str(opts%tol) // '; z is the best iterate'
    case default
      ! Cycling or stagnation: Lemke decides (it terminates for PSD W).
      allocate(zl(n))
      lemke_opts = opts
      lemke_opts%maxit = 0
      call solve_lcp_lemke(W, q, zl, lemke_opts, lemke_rep)
      st%lemke_fallback = .true.
      select case (lemke_rep%info)
      case (0, 1, 4)
        z = zl
        rep = lemke_rep
        rep%iterations = st%steps
        rep%message = 'PDAS: ' // why // ' after ' // int_to_str(st%steps) // &
          ' Newton steps; Lemke fallback: ' // lemke_rep%message
      case default
        if (lemke_rep%residual < pdas_residual) then
          z = zl
          call measure_solution(W, q, d, z, rep)
        end if
        rep%info = 3
        rep%iterations = st%steps
        rep%message = 'PDAS: ' // why // ' after ' // int_to_str(st%steps) // &
          ' Newton steps, and the Lemke fallback failed (' // lemke_rep%message // &
          '); z is the better of the two, residual ' // real_to_str(rep%residual)
      end select
    end select
    if (present(stats)) stats = st
  end subroutine solve_lcp_pdas

  ! ---------------------------------------------------------------------------
  ! Internals
  ! ---------------------------------------------------------------------------

  !> The active set iteration on the scaled problem (all diagonals positive).
  !>   ws       (in)    (m, m) scaled matrix, unit diagonal
  !>   qs       (in)    (m) scaled q
  !>   qscale   (in)    ||qs||_inf (1 when qs = 0)
  !>   delta    (in)    feasibility tolerance on zs_A and ws_I, > 0
  !>   maxit    (in)    Newton step limit, > 0
  !>   mode     (in)    factor mode (pdas_factor_*)
  !>   zs       (out)   (m) last iterate on success, else the best one
  !>   st       (inout) counts
  !>   outcome  (out)   0 no infeasible index, 2 step limit, 3 cycling or stagnation
  !>   why      (out)   for outcome 3: what happened
  subroutine pdas_scaled(ws, qs, qscale, delta, maxit, mode, zs, st, outcome, why)
    real(dp), intent(in) :: ws(:, :)
    real(dp), intent(in) :: qs(:)
    real(dp), intent(in) :: qscale, delta
    integer, intent(in) :: maxit, mode
    real(dp), intent(out) :: zs(:)
    type(pdas_stats_t), intent(inout) :: st
    integer, intent(out) :: outcome
    character(len=:), allocatable, intent(out) :: why
    type(active_factor_t) :: f
    real(dp), allocatable :: gap(:), zbest(:)
    integer, allocatable :: leaving(:), joining(:), rejected(:)
    integer(i8), allocatable :: table(:, :), phase_hash(:, :), visited(:, :)
    integer(i8) :: hash(2), hash_before(2)
    real(dp) :: res, best_res
    integer :: m, i, ninf, best_ninf, nphase, nvisit, nrej, p_before
    logical :: single

    m = size(qs)
    zs = 0.0_dp
    outcome = 0
    why = ''
    if (m == 0) return
    allocate(gap(m), zbest(m), phase_hash(2, 64), visited(2, 64))
    gap = qs                                           ! ws at zs = 0
    if (all(qs >= -delta)) return                      ! z = 0 solves it
    zbest = zs
    best_res = maxval(abs(min(zs, gap))) / qscale

    call hash_table(m, table)
    f%cap = 0
    allocate(f%order(m), f%pos(m))
    f%pos = 0
    joining = pack([(i, i = 1, m)], qs < 0.0_dp)       ! A_0 = {zs - c ws > 0} at zs = 0
    call sort_by_key(joining, qs)                      ! deepest first, likely leavers last
    call append_indices(f, ws, joining, rejected, nrej)
    st%factorizations = st%factorizations + 1
    st%redundant = st%redundant + nrej
    st%max_active = f%p
    f%fresh = .true.
    hash = set_hash(table, f)
    nvisit = 1
    visited(:, 1) = hash

    best_ninf = huge(1)
    nphase = 0
    single = .false.
    do
      st%steps = st%steps + 1
      call solve_active(f, ws, qs, delta, zs, gap, st)
      res = maxval(abs(min(zs, gap))) / qscale
      if (res < best_res) then
        best_res = res
        zbest = zs
      end if

      ! Infeasible indices: zs_i < 0 on A, ws_i < 0 off A.
      leaving = pack(f%order(1:f%p), zs(f%order(1:f%p)) < -delta)
      joining = pack([(i, i = 1, m)], f%pos == 0 .and. gap < -delta)
      ninf = size(leaving) + size(joining)
      if (ninf == 0) then
        where (zs < 0.0_dp) zs = 0.0_dp
        outcome = 0
        return
      end if
      if (st%steps >= maxit) then
        outcome = 2
        exit
      end if

      ! Every infeasible index changes side until an active set repeats; then
      ! only the least one (Murty) until ninf is below its smallest value so far.
      if (single .and. ninf < best_ninf) single = .false.
      best_ninf = min(best_ninf, ninf)
      if (single) then
        i = m + 1
        if (size(leaving) > 0) i = minval(leaving)
        if (size(joining) > 0) i = min(i, minval(joining))
        if (f%pos(i) > 0) then
          leaving = [i]
          joining = [integer ::]
        else
          leaving = [integer ::]
          joining = [i]
        end if
        st%single_exchanges = st%single_exchanges + 1
      else
        st%full_exchanges = st%full_exchanges + 1
      end if

      p_before = f%p
      hash_before = hash
      call change_active_set(f, ws, zs, gap, leaving, joining, mode, rejected, nrej, st)
      hash = set_hash(table, f)
      if (f%p == p_before .and. all(hash == hash_before)) then
        outcome = 3
        why = 'stagnation (an infeasible constraint is linearly dependent on the active ones)'
        exit
      end if
      if (single) then
        if (any(phase_hash(1, 1:nphase) == hash(1) .and. phase_hash(2, 1:nphase) == hash(2))) then
          outcome = 3
          why = 'cycling (an active set repeated in the single-index phase: W is not positive definite)'
          exit
        end if
        call push_hash(phase_hash, nphase, hash)
      else
        if (any(visited(1, 1:nvisit) == hash(1) .and. visited(2, 1:nvisit) == hash(2))) then
          single = .true.                              ! the plain iteration cycles
          nphase = 0
        end if
        call push_hash(visited, nvisit, hash)
      end if
    end do
    zs = zbest
  end subroutine pdas_scaled

  !> One linear solve (1) with refinement: zs_A from the factor, zs_I = 0,
  !> gap = qs + Ws zs; refined while the residual on A exceeds delta / 100,
  !> and refactored from scratch once if it stays above delta.
  !>   f      (inout) the factor of Ws_AA (recomputed when inaccurate)
  !>   ws     (in)    (m, m) scaled matrix
  !>   qs     (in)    (m) scaled q
  !>   delta  (in)    feasibility tolerance, > 0
  !>   zs     (out)   (m) the Newton iterate, zero off A
  !>   gap    (out)   (m) ws = qs + Ws zs
  !>   st     (inout) counts (refinements, factorizations)
  subroutine solve_active(f, ws, qs, delta, zs, gap, st)
    type(active_factor_t), intent(inout) :: f
    real(dp), intent(in) :: ws(:, :)
    real(dp), intent(in) :: qs(:)
    real(dp), intent(in) :: delta
    real(dp), intent(out) :: zs(:)
    real(dp), intent(out) :: gap(:)
    type(pdas_stats_t), intent(inout) :: st
    real(dp), allocatable :: b(:), znew(:), gnew(:)
    integer, allocatable :: act(:), rejected(:)
    real(dp) :: resa, resnew
    integer :: m, p, info, step, attempt, nrej

    m = size(qs)
    do attempt = 1, 2
      p = f%p
      zs = 0.0_dp
      if (p > 0) then
        b = -qs(f%order(1:p))
        call dpotrs('L', p, 1, f%l, f%cap, b, p, info)   ! Ws_AA zs_A = -qs_A
        zs(f%order(1:p)) = b
      end if
      call lcp_gaps(ws, qs, zs, gap)
      if (p == 0) return
      resa = maxval(abs(gap(f%order(1:p))))
      if (.not. allocated(gnew)) allocate(znew(m), gnew(m))
      do step = 1, 2
        if (resa <= 0.01_dp * delta) exit
        b = -gap(f%order(1:p))
        call dpotrs('L', p, 1, f%l, f%cap, b, p, info)   ! Ws_AA e = -r_A
        znew = zs
        znew(f%order(1:p)) = znew(f%order(1:p)) + b        ! zs_A + e
        call lcp_gaps(ws, qs, znew, gnew)
        resnew = maxval(abs(gnew(f%order(1:p))))
        st%refinements = st%refinements + 1
        if (.not. resnew < resa) exit
        zs = znew
        gap = gnew
        resa = resnew
      end do
      if (resa <= delta .or. attempt == 2 .or. f%fresh) return
      ! Accumulated update error: factor the same set from scratch.
      act = f%order(1:p)
      call truncate_factor(f, 0)
      call append_indices(f, ws, act, rejected, nrej)
      f%fresh = .true.
      st%factorizations = st%factorizations + 1
      st%redundant = st%redundant + nrej
    end do
  end subroutine solve_active

  !> The largest |a_ij - a_ji| and where (i > j), by 64 x 64 tiles.
  !>   a     (in)  (n, n)
  !>   asym  (out) max |a_ij - a_ji|, 0 when n < 2
  !>   imax, jmax (out) its position
  subroutine largest_asymmetry(a, asym, imax, jmax)
    real(dp), intent(in) :: a(:, :)
    real(dp), intent(out) :: asym
    integer, intent(out) :: imax, jmax
    integer, parameter :: tile = 64
    integer :: n, i0, j0, i, j
    n = size(a, 1)
    asym = 0.0_dp
    imax = 1
    jmax = 1
    do j0 = 1, n, tile
      do i0 = j0, n, tile
        do j = j0, min(j0 + tile - 1, n)
          do i = max(i0, j + 1), min(i0 + tile - 1, n)
            if (abs(a(i, j) - a(j, i)) > asym) then
              asym = abs(a(i, j) - a(j, i))
              imax = i
              jmax = j
            end if
          end do
        end do
      end do
    end do
  end subroutine largest_asymmetry

  !> A <- (A \ leaving) u joining, by Givens deletions, a trailing re-factor or
  !> a factor from scratch (module header), then one block append.  Blocks are
  !> appended in order of confidence (survivors by decreasing zs, newcomers by
  !> increasing ws), so that the indices most likely to leave next sit at the
  !> end of the factor, where deleting them is cheap.
  !>   f         (inout) the factor
  !>   ws        (in)    (m, m) scaled matrix
  !>   zs, gap   (in)    (m) the current iterate and its ws
  !>   leaving   (in)    indices in A that leave
  !>   joining   (in)    indices not in A that join
  !>   mode      (in)    pdas_factor_*
  !>   rejected  (out)   (nrej) joining indices kept out as linearly dependent
  !>   nrej      (out)   their number
  !>   st        (inout) counts
  subroutine change_active_set(f, ws, zs, gap, leaving, joining, mode, rejected, nrej, st)
    type(active_factor_t), intent(inout) :: f
    real(dp), intent(in) :: ws(:, :)
    real(dp), intent(in) :: zs(:), gap(:)
    integer, intent(in) :: leaving(:), joining(:)
    integer, intent(in) :: mode
    integer, allocatable, intent(out) :: rejected(:)
    integer, intent(out) :: nrej
    type(pdas_stats_t), intent(inout) :: st
    integer, allocatable :: positions(:), kept(:), incoming(:), newcomers(:)
    integer :: p, r, k, kmin, j
    real(dp) :: cost_givens, cost_trailing, k0, b
    logical :: use_givens, from_scratch

    p = f%p
    r = size(leaving)
    allocate(positions(r))
    positions = f%pos(leaving)
    kmin = p + 1
    if (r > 0) kmin = minval(positions)

    select case (mode)
    case (pdas_factor_refactor)
      use_givens = .false.
      kmin = 1
    case (pdas_factor_update)
      use_givens = .true.
    case default
      ! Flops: rotations 3 (p - k)^2 plus the row shift k (p - k) per deletion,
      ! weighted; the trailing re-factor of b = p - kmin + 1 - r indices after
      ! k0 = kmin - 1 kept ones: k0^2 b + k0 b^2 + b^3 / 3.
      cost_givens = 0.0_dp
      do j = 1, r
        k = positions(j)
        cost_givens = cost_givens + givens_weight * (3.0_dp * real(p - k, dp)**2 + real(k, dp) * real(p - k, dp))
      end do
      k0 = real(kmin - 1, dp)
      b = real(p - kmin + 1 - r, dp)
      cost_trailing = k0**2 * b + k0 * b**2 + b**3 / 3.0_dp
      use_givens = cost_givens <= cost_trailing
    end select

    if (r == 0 .and. mode /= pdas_factor_refactor) use_givens = .true.
    from_scratch = .false.
    newcomers = joining
    call sort_by_key(newcomers, gap)                    ! most violated first
    if (use_givens) then
      call sort_integers(positions)
      positions = positions(size(positions):1:-1)     ! largest first: a deletion moves no position still to come
      do j = 1, r                                       ! highest position first
        call delete_position(f, positions(j))
      end do
      st%deleted = st%deleted + r
      incoming = newcomers
    else
      ! Keep positions 1..kmin-1, append the survivors after them and the newcomers.
      kept = pack(f%order(kmin:p), .not. is_member(f%order(kmin:p), leaving, size(f%pos)))
      call sort_by_key(kept, -zs)                       ! largest force first
      call truncate_factor(f, kmin - 1)
      incoming = [kept, newcomers]
      from_scratch = kmin == 1
      if (from_scratch) then
        st%factorizations = st%factorizations + 1
      else
        st%trailing_refactors = st%trailing_refactors + 1
      end if
    end if
    call append_indices(f, ws, incoming, rejected, nrej)
    f%fresh = from_scratch
    if (.not. from_scratch) st%appended = st%appended + count(.not. is_member(joining, rejected, size(f%pos)))
    st%redundant = st%redundant + nrej
    st%max_active = max(st%max_active, f%p)
  end subroutine change_active_set

  !> inside(k) = a(k) is one of s(:); indices in 1..m.
  function is_member(a, s, m) result(inside)
    integer, intent(in) :: a(:), s(:)
    integer, intent(in) :: m
    logical :: inside(size(a))
    logical, allocatable :: mark(:)
    allocate(mark(m))
    mark = .false.
    mark(s) = .true.
    inside = mark(a)
  end function is_member

  !> Append the indices new(:) to the factor as one block:
  !>     L21 = Ws_NA L11^-T,   L22 L22' = Ws_NN - L21 L21',
  !> by dpotrf, or by pivoted Cholesky (dpstrf) when a pivot falls below
  !> pivot_tol; the indices left over then are not appended.
  !>   f         (inout) the factor
  !>   ws        (in)    (m, m) scaled matrix
  !>   new       (in)    (k) indices not in A
  !>   rejected  (out)   (nrej) the indices not appended (linearly dependent)
  !>   nrej      (out)   their number
  subroutine append_indices(f, ws, new, rejected, nrej)
    type(active_factor_t), intent(inout) :: f
    real(dp), intent(in) :: ws(:, :)
    integer, intent(in) :: new(:)
    integer, allocatable, intent(out) :: rejected(:)
    integer, intent(out) :: nrej
    real(dp), allocatable :: y(:, :), s(:, :), s0(:, :), work(:)
    integer, allocatable :: piv(:)
    integer :: p, k, r, i, j, info
    logical :: ok

    p = f%p
    k = size(new)
    nrej = 0
    allocate(rejected(0))
    if (k == 0) return
    allocate(y(max(p, 1), k), s(k, k))
    do j = 1, k
      if (p > 0) y(1:p, j) = ws(f%order(1:p), new(j))
      s(:, j) = ws(new, new(j))
    end do
    if (p > 0) then
      call dtrsm('L', 'L', 'N', 'N', p, k, 1.0_dp, f%l, f%cap, y, p)        ! Y = L11^-1 Ws_AN
      call dsyrk('L', 'T', k, p, -1.0_dp, y, p, 1.0_dp, s, k)               ! S = Ws_NN - Y'Y
    end if
    s0 = s
    call dpotrf('L', k, s, k, info)                                         ! S = L22 L22'
    ok = info == 0
    if (ok) ok = minval([(s(i, i), i = 1, k)])**2 >= pivot_tol
    allocate(piv(k))
    if (ok) then
      piv = [(i, i = 1, k)]
      r = k
    else
      s = s0
      allocate(work(2 * k))
      call dpstrf('L', k, s, k, piv, r, pivot_tol, work, info)             ! P'SP = L22 L22', rank r
      if (info < 0) r = 0
    end if

    call reserve_capacity(f, p + r, size(ws, 1))
    do i = 1, r
      if (p > 0) f%l(p + i, 1:p) = y(1:p, piv(i))                           ! L21 = Y(:, piv)'
      f%l(p + i, p + 1:p + i) = s(i, 1:i)                                   ! L22, lower part
      f%order(p + i) = new(piv(i))
      f%pos(new(piv(i))) = p + i
    end do
    f%p = p + r
    nrej = k - r
    if (nrej > 0) rejected = new(piv(r + 1:k))
  end subroutine append_indices

  !> Delete position k from the factor: drop row k of L, then rotate the
  !> columns (i, i+1), i = k..p-1, to zero the superdiagonal that leaves;
  !> the last column becomes zero.
  subroutine delete_position(f, k)
    type(active_factor_t), intent(inout) :: f
    integer, intent(in) :: k
    real(dp) :: c, s, r, g
    integer :: p, i, j

    p = f%p
    do j = 1, p                                        ! L~(i, j) = L(i + 1, j), i >= k
      do i = max(k, j - 1), p - 1
        f%l(i, j) = f%l(i + 1, j)
      end do
      f%l(p, j) = 0.0_dp
    end do
    do i = k, p - 1                                    ! L~ <- L~ G_i: zero L~(i, i + 1)
      g = f%l(i, i + 1)
      r = hypot(f%l(i, i), g)
      if (r > 0.0_dp) then
        c = f%l(i, i) / r
        s = g / r
      else
        c = 1.0_dp
        s = 0.0_dp
      end if
      f%l(i, i) = r
      f%l(i, i + 1) = 0.0_dp
      if (p - 1 - i > 0) call drot(p - 1 - i, f%l(i + 1, i), 1, f%l(i + 1, i + 1), 1, c, s)
    end do
    f%l(1:p, p) = 0.0_dp
    f%pos(f%order(k)) = 0
    do i = k, p - 1
      f%order(i) = f%order(i + 1)
      f%pos(f%order(i)) = i
    end do
    f%p = p - 1
  end subroutine delete_position

  !> Keep the first k0 positions of the factor (a valid factor of their block).
  subroutine truncate_factor(f, k0)
    type(active_factor_t), intent(inout) :: f
    integer, intent(in) :: k0
    integer :: j
    if (f%p > k0) then
      f%pos(f%order(k0 + 1:f%p)) = 0
      do j = 1, f%p
        f%l(max(k0 + 1, j):f%p, j) = 0.0_dp
      end do
    end if
    f%p = min(f%p, k0)
  end subroutine truncate_factor

  !> Make the leading dimension of the factor at least need (at most m),
  !> growing geometrically; the factor is kept.
  subroutine reserve_capacity(f, need, m)
    type(active_factor_t), intent(inout) :: f
    integer, intent(in) :: need, m
    real(dp), allocatable :: grown(:, :)
    integer :: cap
    if (need <= f%cap .and. allocated(f%l)) return
    cap = min(m, max(need, 2 * f%cap, 32))
    allocate(grown(cap, cap))
    grown = 0.0_dp
    if (f%p > 0) grown(1:f%p, 1:f%p) = f%l(1:f%p, 1:f%p)
    call move_alloc(grown, f%l)
    f%cap = cap
  end subroutine reserve_capacity

  !> Random table for set hashing: hash(A) = sum_{i in A} table(:, i) mod 2**61 - 1,
  !> two independent words (Park-Miller draws, 61 bits each).
  subroutine hash_table(m, table)
    integer, intent(in) :: m
    integer(i8), allocatable, intent(out) :: table(:, :)
    integer(i8) :: state
    integer :: i, k
    allocate(table(2, m))
    state = 20240611_i8
    do i = 1, m
      do k = 1, 2
        state = mod(16807_i8 * state, 2147483647_i8)
        table(k, i) = state * 1073741824_i8                 ! 31 bits shifted by 30
        state = mod(16807_i8 * state, 2147483647_i8)
        table(k, i) = mod(table(k, i) + state, hash_prime)
      end do
    end do
  end subroutine hash_table

  !> The two hash words of the active set held by f (order-independent).
  function set_hash(table, f) result(hash)
    integer(i8), intent(in) :: table(:, :)
    type(active_factor_t), intent(in) :: f
    integer(i8) :: hash(2)
    integer :: k
    hash = 0_i8
    do k = 1, f%p
      hash = mod(hash + table(:, f%order(k)), hash_prime)
    end do
  end function set_hash

  !> Append hash to list(:, 1:count), growing the list when full.
  subroutine push_hash(list, count, hash)
    integer(i8), allocatable, intent(inout) :: list(:, :)
    integer, intent(inout) :: count
    integer(i8), intent(in) :: hash(2)
    integer(i8), allocatable :: grown(:, :)
    if (count == size(list, 2)) then
      allocate(grown(2, 2 * size(list, 2)))
      grown(:, 1:count) = list(:, 1:count)
      call move_alloc(grown, list)
    end if
    count = count + 1
    list(:, count) = hash
  end subroutine push_hash

end module lcp_newton
