!> friction_lcp: one load step of frictional 2D contact (Coulomb or Tresca),
!> condensed onto the contact rows.
!>
!> Rows.  n normal rows (one per constrained slave node) and nt tangential rows
!> (nt <= n in 2D); tangential row k belongs to normal row trow(k).  G, of size
!> (n+nt) x (n+nt), symmetric positive semi-definite, is the Delassus matrix
!> C K^-1 C' of the stacked rows C = [B; T]; lam = [lambda (n); tau (nt)] holds
!> the normal contact forces and the tangential (friction) forces.  With
!> q = [qn; qt]
!>     normal gap       w_i  = qn_i + (G lam)_i                    i <= n
!>     slip increment   ds_k = -(qt_k + (G lam)_{n+k})             k <= nt
!>     friction bound   b_k  = bound_k + cmu_k lambda_{trow(k)}
!> (Tresca: bound_k >= 0 given, cmu_k = 0; Coulomb: bound_k = 0, cmu_k = mu >= 0)
!> and the conditions of contact with friction are
!>     lambda >= 0,  w >= 0,  lambda_i w_i = 0                     (Signorini)
!>     |tau_k| <= b_k,  ds_k = 0 where |tau_k| < b_k,
!>     tau_k = b_k sign(ds_k) where ds_k /= 0                      (Coulomb's law)
!> so a friction force tau_k > 0 goes with a slip ds_k >= 0.  For Tresca they
!> are the KKT conditions of the convex QP
!>     min 1/2 lam'G lam + q'lam   subject to  lambda >= 0,  |tau| <= bound
!> (ds is minus the gradient in tau); Coulomb's bound depends on lambda, and
!> the problem is a quasi-variational inequality: for large mu and strong
!> normal-tangential coupling in G it may have several solutions or none.
!>
!> Scaling.  As in lcp_solvers (scale_lcp on G): d_i = 1/sqrt(G_ii), and
!> d_i = 1/sqrt(max_j G_jj) on a zero row (G_ii <= 1e-30 max_j G_jj: for a PSD G
!> the whole row vanishes);
!>     Gs = D G D,  qs = D q,  s = D^-1 lam,  v = qs + Gs s,
!> so that v_i = d_i w_i, v_{n+k} = -d_{n+k} ds_k, and the scaled bound is
!>     bs_k = b_k / d_{n+k} = bound_k / d_{n+k} + cmu_k (d_i / d_{n+k}) s_i,  i = trow(k).
!> Measures of a candidate lam (both methods report these, for the lam returned):
!>     residual  r = max( max_i |min(s_i, v_i)|,
!>                        max_k |s_{n+k} - clamp(s_{n+k} - v_{n+k}, -bs_k, bs_k)| ) / qscale
!>               with qscale = max(||qs||_inf, max_k bound_k / d_{n+k}) (1 when
!>               both vanish) and bs_k taken as max(bs_k, 0).  The normal part is
!>               lcp_solvers' natural residual; the tangential part is
!>               |tau - clamp(tau + ds / G_tt, -b, b)| in the same scaled force
!>               units (a zero row takes the unit step).  r = 0 exactly when lam
!>               satisfies every condition above, and r is scale-free: unchanged
!>               when lengths, forces or single rows of C are rescaled;
!>     complementarity  max( max_i |s_i v_i|, max_k |bs_k |v_{n+k}| + s_{n+k} v_{n+k}| )
!>               / (max(max_j |s_j|, max_k bound_k / d_{n+k}) qscale), 0 when the
!>               numerator is 0; the tangential
!>               term is b |ds| - tau ds (zero when the friction force opposes
!>               the slip at full strength) in scaled units.
!>
!> Lemke (method 'lemke').  The classical LCP of 2D friction (Klarbring 1986;
!> Stewart & Trinkle 1996 with the two tangent directions, exact in 2D):
!>     z = [lambda; beta+; beta-; sigma]  (n + 3 nt),  tau = beta+ - beta-,
!>     M = [  Gnn   Gnt  -Gnt  0 ]      q = [  qn   ]    w = q + M z:
!>         [  Gtn   Gtt  -Gtt  I ]          [  qt   ]    w_beta+ = sigma - ds
!>         [ -Gtn  -Gtt   Gtt  I ]          [ -qt   ]    w_beta- = sigma + ds
!>         [  Cm   -I    -I    0 ]          [ bound ]    w_sigma = b - beta+ - beta-
!> with Cm (nt x n) holding cmu_k in column trow(k).  Its complementarity
!> conditions give sigma >= |ds|; sigma > 0 forces beta+ + beta- = b; beta+ > 0
!> forces sigma = ds and beta- > 0 sigma = -ds; hence ds > 0 gives tau = b,
!> ds < 0 gives tau = -b, and ds = 0 leaves |tau| <= b: exactly the conditions
!> above, sigma being the slip magnitude.  M is not symmetric and its sigma
!> rows have a zero diagonal, so it is solved by solve_lcp_lemke_scaled (no row
!> removed) with d = [dn; dt; dt; 1/dt], dn, dt the scaling of G above: the
!> diagonal blocks of D M D are unit-sized and the I blocks stay I.  On return
!> tau is projected onto [-b, b] (beta+ + beta- <= b holds to round-off only;
!> this polish is the counterpart of setting tiny negative z to zero).  For Tresca
!> M is positive semi-definite (the G part is E'GE, E = [I 0 0; 0 I -I], the I
!> blocks are skew), so Lemke solves it and ray termination proves that there
!> is no solution; for Coulomb M is only copositive and ray termination means
!> that Lemke found none: it proves nothing, unless the ray's direction y
!> is Farkas' certificate that no z >= 0 has q + M z >= 0 (M'y <= 0,
!> q'y < 0: lcp_scaling's certifies_infeasible), which the message then
!> says.  Dense, O((n + 3 nt)^2) per pivot.
!>
!> PGS (method 'pgs').  Nonsmooth (block projected) Gauss-Seidel (Moreau,
!> Jean) on the scaled problem, with relaxation omega: the normal rows in
!> order, each followed by the tangential rows of its node,
!>     s_i     <- max(0, s_i - omega v_i / Gs_ii)
!>     s_{n+k} <- clamp(s_{n+k} - omega v_{n+k} / Gs_{n+k,n+k}, -bs_k, bs_k)
!> with the current bs_k (the lambda just updated) and v kept up to date column
!> by column (daxpy), recomputed every 50 sweeps (lcp_pgs' run_pgs drives the
!> sweeps).  Each update minimises the Tresca QP in one variable; at stick
!> v_{n+k} = -d ds_k = 0 and tau stays.  A zero row takes the unit step.  The residual r is checked after every sweep
!> and confirmed with v recomputed.  Divergence (iterates beyond 1e150 or r
!> grown by 1e6 over its minimum) and stagnation (the best r not decreased by
!> a factor 0.999 over max(1000, 10 (n + nt)) sweeps) stop with info 3, the
!> sweep limit with info 2; lam then holds the best iterate.  PGS converges
!> for Tresca (a convex QP with box constraints), slowly when G is ill-
!> conditioned; for Coulomb it is a fixed-point iteration that usually
!> converges for moderate mu and may stagnate for large mu with strong
!> coupling (reported, info 3), where Lemke still finds a solution.
!>
!> Stick and slip.  friction_state classifies each tangential row with the
!> relative tolerance state_tol = 1e-8 on the scaled quantities:
!>     open  (0)  s_i <= state_tol qscale and bs_k <= state_tol qscale: no normal
!>                force and no friction force available, the node is not in
!>                contact (for Tresca, only when also bound_k = 0);
!>     slip  (2)  otherwise, when |v_{n+k}| = d |ds_k| > state_tol qscale;
!>     stick (1)  otherwise.
!>
!> Why it exists, as one file: the frictional contact problem of a step in
!> its one scaled form, with the two solvers that read that form directly
!> (Lemke on its LCP, PGS on its sweeps) and the residual, state and forces
!> every friction solver is judged by; splitting the form from its measures
!> would put the one definition of r in two places.  friction_newton and
!> friction_fixed_point build on it.
!>
!> Programming interface
!>   type(friction_problem_t)   one step's problem beside G: n, nt, qn, qt,
!>       trow, cmu, bound (the symbols above); built by
!>   friction_problem(qn, qt, trow, cmu, bound), checked against G by
!>   check_friction_problem(g, prob, rep)   info -1 (G) or -2 (prob) with the message
!>   solve_friction_lcp(g, prob, method, opts, lam, rep)
!>       method 'lemke' or 'pgs'; opts and rep are lcp_solvers' lcp_options_t
!>       (tol on r, maxit, omega) and lcp_report_t (info, iterations: pivots or
!>       sweeps, residual r, complementarity, message).  info 0 solved; 1 no
!>       solution (Lemke ray termination, or a zero normal row of G with
!>       qn_i < 0); 2 pivot / sweep limit; 3 PGS divergence or stagnation;
!>       4 Lemke terminated with r > tol; -k argument k invalid.  With nt = 0
!>       the call is solve_lcp_lemke or solve_lcp_pgs on (g, qn), unchanged.
!>   friction_residual(g, prob, lam)        the residual r
!>   bounded_residual(n, trow, bs0, mus, qscale, s, v)   r of a scaled iterate
!>   scale_bounds(prob, d, qs, n, nt, trow, bs0, mus, qscale)   a scaled form's sizes and bounds
!>   measure_friction(g, prob, lam, rep)    r and the complementarity measure into rep
!>                                          (for friction_newton, the PDAS of these steps)
!>   friction_state(g, prob, lam, state, err)
!>       state(nt): state_open (0), state_stick (1) or state_slip (2)
!>   friction_lcp_system(g, prob, m, q, d)  Lemke's LCP (M, q) and its scaling d
!>   friction_forces(prob, z, lam)          lam = [lambda; tau] read off Lemke's z
!> No routine prints anything; every outcome is in the report.
module friction_lcp
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, set_out_of_memory
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_pgs, pgs_outcome, &
    solve_lcp_lemke_scaled, scale_lcp, set_report, pgs_problem_t, run_pgs, pgs_set_row, pgs_limits, &
    negative_diagonal
  use lcp_scaling, only: residual_outcome, report_out_of_memory, scaling_vector, lcp_gaps, info_no_memory, &
    certifies_infeasible
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: friction_problem_t, friction_problem, check_friction_problem, state_open, state_stick, state_slip
  public :: solve_friction_lcp, friction_residual, friction_state, friction_lcp_system, friction_forces
  public :: measure_friction, bounded_residual, scale_bounds

  integer, parameter :: state_open = 0    !< not in contact, no friction force available
  integer, parameter :: state_stick = 1   !< no slip: ds = 0, |tau| <= b
  integer, parameter :: state_slip = 2    !< slip: ds /= 0, tau = b sign(ds)

  !> One load step's friction problem (module header) but G, which the
  !> caller keeps (the run's dense Delassus matrix, the same for every step).
  type :: friction_problem_t
    integer :: n = 0                     !< normal rows
    integer :: nt = 0                    !< tangential rows
    real(dp), allocatable :: qn(:)       !< (n) normal gaps of the unconstrained solution
    real(dp), allocatable :: qt(:)       !< (nt) tangential right-hand side: ds = -(qt + (G lam)_t)
    integer, allocatable :: trow(:)      !< (nt) normal row of each tangential row, 1..n
    real(dp), allocatable :: cmu(:)      !< (nt) friction coefficients, >= 0 (0 for Tresca)
    real(dp), allocatable :: bound(:)    !< (nt) Tresca bounds, >= 0 (0 for Coulomb)
  end type friction_problem_t

  !> The scaled problem (module header), which method 'pgs' sweeps (run_pgs).
  type, extends(pgs_problem_t) :: scaled_friction_t
    integer :: n = 0                     !< normal rows
    integer :: nt = 0                    !< tangential rows
    real(dp), allocatable :: d(:)        !< (n+nt) scaling D
    real(dp), allocatable :: gs(:, :)    !< (n+nt, n+nt) D G D
    real(dp), allocatable :: qs(:)       !< (n+nt) D [qn; qt]
    real(dp), allocatable :: step(:)     !< (n+nt) 1 / Gs_ii, 1 on a zero row
    logical, allocatable :: zero(:)      !< (n+nt) .true. on a zero row of G
    integer, allocatable :: trow(:)      !< (nt) normal row of each tangential row
    real(dp), allocatable :: bs0(:)      !< (nt) bound_k / d_{n+k}
    real(dp), allocatable :: mus(:)      !< (nt) cmu_k d_{trow(k)} / d_{n+k}
    integer, allocatable :: tfirst(:)    !< (n+1) tangential rows of normal row i are
    integer, allocatable :: tlist(:)     !< (nt)  tlist(tfirst(i) : tfirst(i+1) - 1)
    real(dp) :: qscale = 1.0_dp          !< max(||qs||_inf, max bs0), 1 when 0
  contains
    procedure :: sweep => friction_sweep
    procedure :: residual => scaled_residual
  end type scaled_friction_t

  real(dp), parameter :: state_tol = 1.0e-8_dp             ! friction_state: relative tolerance


contains

  !> The friction problem of one load step, its sizes taken from qn and qt.
  !>   qn     (in)  (n) normal gaps of the unconstrained solution
  !>   qt     (in)  (nt) tangential right-hand side (ds = -(qt + (G lam)_t))
  !>   trow   (in)  (nt) normal row of each tangential row
  !>   cmu    (in)  (nt) friction coefficients (0 for Tresca)
  !>   bound  (in)  (nt) Tresca bounds (0 for Coulomb)
  !> The values are checked against G by check_friction_problem.
  pure function friction_problem(qn, qt, trow, cmu, bound) result(prob)
    real(dp), intent(in) :: qn(:), qt(:), cmu(:), bound(:)
    integer, intent(in) :: trow(:)
    type(friction_problem_t) :: prob
    prob%n = size(qn)
    prob%nt = size(qt)
    allocate(prob%qn, source=qn)
    allocate(prob%qt, source=qt)
    allocate(prob%trow, source=trow)
    allocate(prob%cmu, source=cmu)
    allocate(prob%bound, source=bound)
  end function friction_problem

  !> Check G and the problem, the first bad entry reported.
  !>   g     (in)    (n+nt, n+nt) Delassus matrix G: finite, no negative
  !>                 diagonal entry beyond round-off (negative_diagonal)
  !>   prob  (in)    the problem: qn, qt finite; trow, cmu, bound of nt
  !>                 entries, 1 <= trow <= n, cmu and bound finite and >= 0
  !>   rep   (inout) info -1 (G) or -2 (prob) with the message; 0 when valid
  subroutine check_friction_problem(g, prob, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    type(lcp_report_t), intent(inout) :: rep
    integer :: n, nt, nrow, i

    rep%info = 0
    n = prob%n
    nt = prob%nt
    nrow = n + nt
    if (size(prob%qn) /= n .or. size(prob%qt) /= nt) then
      call set_report(rep, -2, 'friction LCP: qn and qt have ' // int_to_str(size(prob%qn)) // ' and ' // &
        int_to_str(size(prob%qt)) // ' entries (expected n = ' // int_to_str(n) // ' and nt = ' // &
        int_to_str(nt) // ')')
      return
    end if
    if (size(g, 1) /= nrow .or. size(g, 2) /= nrow) then
      call set_report(rep, -1, 'friction LCP: G is ' // int_to_str(size(g, 1)) // ' x ' // &
        int_to_str(size(g, 2)) // ' (expected ' // int_to_str(nrow) // ' x ' // int_to_str(nrow) // &
        ', n + nt from qn and qt)')
      return
    else if (.not. all(ieee_is_finite(g))) then
      call set_report(rep, -1, 'friction LCP: G has non-finite entries')
      return
    end if
    i = negative_diagonal(g)
    if (i > 0) then
      call set_report(rep, -1, 'friction LCP: G(' // int_to_str(i) // ',' // int_to_str(i) // &
        ') < 0 (G must be positive semi-definite)')
      return
    end if
    if (.not. all(ieee_is_finite(prob%qn))) then
      call set_report(rep, -2, 'friction LCP: qn has non-finite entries')
    else if (.not. all(ieee_is_finite(prob%qt))) then
      call set_report(rep, -2, 'friction LCP: qt has non-finite entries')
    else if (size(prob%trow) /= nt) then
      call set_report(rep, -2, 'friction LCP: trow has ' // int_to_str(size(prob%trow)) // &
        ' entries (expected nt = ' // int_to_str(nt) // ')')
    else if (any(prob%trow < 1 .or. prob%trow > n)) then
      call set_report(rep, -2, 'friction LCP: trow has entries outside 1..' // int_to_str(n))
    else if (size(prob%cmu) /= nt) then
      call set_report(rep, -2, 'friction LCP: cmu has ' // int_to_str(size(prob%cmu)) // &
        ' entries (expected nt = ' // int_to_str(nt) // ')')
    else if (.not. all(ieee_is_finite(prob%cmu) .and. prob%cmu >= 0.0_dp)) then
      call set_report(rep, -2, 'friction LCP: cmu has entries that are not finite and >= 0')
    else if (size(prob%bound) /= nt) then
      call set_report(rep, -2, 'friction LCP: bound has ' // int_to_str(size(prob%bound)) // &
        ' entries (expected nt = ' // int_to_str(nt) // ')')
    else if (.not. all(ieee_is_finite(prob%bound) .and. prob%bound >= 0.0_dp)) then
      call set_report(rep, -2, 'friction LCP: bound has entries that are not finite and >= 0')
    end if
  end subroutine check_friction_problem

  !> Solve one load step of contact with Coulomb or Tresca friction (module
  !> header) by Lemke on the friction LCP or by nonsmooth Gauss-Seidel.
  !>   g       (in)    (n+nt, n+nt) Delassus matrix G, symmetric PSD, finite
  !>   prob    (in)    qn, qt, trow, cmu, bound (check_friction_problem)
  !>   method  (in)    'lemke' or 'pgs'
  !>   opts    (in)    tol (> 0, on r), maxit (>= 0; 0: Lemke 10 (n + 3 nt) + 100
  !>                   pivots, PGS min(1e5, max(1e4, 1e10 / (n + nt)^2)) sweeps),
  !>                   omega (PGS, 0 < omega < 2)
  !>   lam     (inout) (n+nt) [lambda; tau].  On entry the initial guess of PGS
  !>                   (non-finite entries taken as 0, negative lambda as 0;
  !>                   ignored by Lemke).  On exit the solution when rep%info = 0
  !>                   (or 4, inaccurate); on failure Lemke's last almost-
  !>                   complementary point or PGS's best iterate (finite); zero
  !>                   when a zero normal row makes the problem infeasible (PGS);
  !>                   unchanged on an argument error.  With nt = 0 as z of
  !>                   solve_lcp_lemke / solve_lcp_pgs
  !>   rep     (out)   info 0 solved, 1 no solution, 2 iteration limit, 3 PGS
  !>                   divergence or stagnation, 4 Lemke residual above tol, -k
  !>                   argument k invalid; iterations (pivots or sweeps);
  !>                   residual r and complementarity of the lam returned; message
  subroutine solve_friction_lcp(g, prob, method, opts, lam, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    character(len=*), intent(in) :: method
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: lam(:)
    type(lcp_report_t), intent(out) :: rep
    type(scaled_friction_t) :: p
    integer :: info, nrow

    call check_friction_problem(g, prob, rep)
    if (rep%info < 0) return
    nrow = prob%n + prob%nt
    if (method /= 'lemke' .and. method /= 'pgs') then
      call set_report(rep, -3, 'friction LCP: method ''' // method // ''' (expected ''lemke'' or ''pgs'')')
    else if (.not. (ieee_is_finite(opts%tol) .and. opts%tol > 0.0_dp)) then
      call set_report(rep, -4, 'friction LCP: tol is not finite and > 0')
    else if (opts%maxit < 0) then
      call set_report(rep, -4, 'friction LCP: maxit = ' // int_to_str(opts%maxit) // ' (expected >= 0)')
    else if (method == 'pgs' .and. .not. (opts%omega > 0.0_dp .and. opts%omega < 2.0_dp)) then
      call set_report(rep, -4, 'friction LCP: omega is not in (0, 2)')
    else if (size(lam) /= nrow) then
      call set_report(rep, -5, 'friction LCP: lam has ' // int_to_str(size(lam)) // ' entries (expected n + nt = ' // &
        int_to_str(nrow) // ')')
    end if
    if (rep%info < 0) return

    ! Without tangential rows this is the frictionless LCP(Gnn, qn).
    if (prob%nt == 0) then
      if (method == 'lemke') then
        call solve_lcp_lemke(g, prob%qn, lam, opts, rep)
      else
        call solve_lcp_pgs(g, prob%qn, lam, opts, rep)
      end if
      return
    end if

    call scale_friction(g, prob, p, info)
    if (info /= 0) then
      call report_out_of_memory(rep, 'scaling the friction LCP (' // int_to_str(size(g, 1)) // ' rows)', &
                                scaled_bytes(size(g, 1)))
      lam = 0.0_dp
      return
    end if
    if (method == 'lemke') then
      call friction_lemke(g, prob, p, opts, lam, rep)
    else
      call friction_pgs(p, opts, lam, rep)
    end if
  end subroutine solve_friction_lcp


  !> Scale-free natural residual r (module header) of a candidate lam.
  !> r = 0 exactly when lam solves the frictional contact problem.
  !>   g, prob  (in) the problem, as in solve_friction_lcp
  !>   lam  (in)     (n+nt) candidate, finite
  !>   r    (result) the residual; huge(1.0_dp) when g, prob or lam's size are
  !>        invalid or the scaled copy of g does not fit in memory
  function friction_residual(g, prob, lam) result(r)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    real(dp), intent(in) :: lam(:)
    real(dp) :: r
    type(scaled_friction_t) :: p
    real(dp), allocatable :: s(:), v(:)
    integer :: info

    r = huge(1.0_dp)
    if (.not. valid_problem(g, prob, size(lam))) return
    call scale_friction(g, prob, p, info)
    if (info /= 0) return
    s = lam / p%d                                      ! s = D^-1 lam
    allocate(v(size(s)))
    call lcp_gaps(p%gs, p%qs, s, v)                    ! v = qs + Gs s
    r = scaled_residual(p, s, v)
  end function friction_residual

  !> The residual r and the complementarity measure (module header) of a
  !> candidate lam into rep, for a method of another module (friction_newton).
  !>   g, prob  (in)    the problem, as in solve_friction_lcp
  !>   lam      (in)    (n+nt) candidate, finite
  !>   rep      (inout) residual and complementarity set (huge(1.0_dp) when the
  !>                    sizes are invalid or the scaled copy of g does not fit)
  subroutine measure_friction(g, prob, lam, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    real(dp), intent(in) :: lam(:)
    type(lcp_report_t), intent(inout) :: rep
    type(scaled_friction_t) :: p
    integer :: info
    rep%residual = huge(1.0_dp)
    rep%complementarity = huge(1.0_dp)
    if (.not. valid_problem(g, prob, size(lam))) return
    call scale_friction(g, prob, p, info)
    if (info /= 0) return
    call measure_scaled(p, lam / p%d, rep)
  end subroutine measure_friction

  !> Stick / slip state of each tangential row of a (solved) lam, decided with
  !> the relative tolerance state_tol = 1e-8 (module header).
  !>   g, prob  (in) the problem, as in solve_friction_lcp
  !>   lam    (in)  (n+nt) the forces, finite
  !>   state  (out) (nt) state_open (0), state_stick (1) or state_slip (2);
  !>                -1 everywhere when g, prob or the sizes are invalid
  !>   err    (out) allocated when the scaled copy of g does not fit in memory
  !>                (`out of memory while ...`, status 1; state is -1 then)
  subroutine friction_state(g, prob, lam, state, err)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    real(dp), intent(in) :: lam(:)
    integer, intent(out) :: state(:)
    type(error_t), allocatable, intent(out) :: err
    type(scaled_friction_t) :: p
    real(dp), allocatable :: s(:), v(:)
    real(dp) :: bk, small
    integer :: k, i, j, n, info

    state = -1
    if (.not. valid_problem(g, prob, size(lam))) return
    if (size(state) /= prob%nt) return
    call scale_friction(g, prob, p, info)
    if (info /= 0) then
      call set_out_of_memory(err, 'measuring the friction states (' // int_to_str(size(g, 1)) // ' rows)', &
                             int(min(scaled_bytes(size(g, 1)), 9.0e18_dp), i8))
      return
    end if
    n = p%n
    s = lam / p%d
    allocate(v(size(s)))
    call lcp_gaps(p%gs, p%qs, s, v)                    ! v = qs + Gs s
    small = state_tol * p%qscale
    do k = 1, p%nt
      i = p%trow(k)
      j = n + k
      bk = max(0.0_dp, p%bs0(k) + p%mus(k) * s(i))    ! bs_k
      if (s(i) <= small .and. bk <= small) then
        state(k) = state_open
      else if (abs(v(j)) > small) then                ! |v_{n+k}| = d |ds_k|
        state(k) = state_slip
      else
        state(k) = state_stick
      end if
    end do
  end subroutine friction_state

  !> The friction LCP of method 'lemke' (module header) and its scaling, for
  !> Lemke on D M D, D q (solve_lcp_lemke_scaled).
  !>   g     (in)  (n+nt, n+nt) G
  !>   prob  (in)  the problem, valid (check_friction_problem)
  !>   m     (out) (n+3nt, n+3nt) M
  !>   q     (out) (n+3nt) [qn; qt; -qt; bound]
  !>   d     (out) (n+3nt) [dn; dt; dt; 1/dt], dn and dt the scaling of G (scale_lcp)
  subroutine friction_lcp_system(g, prob, m, q, d)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    real(dp), intent(out) :: m(:, :)
    real(dp), intent(out) :: q(:)
    real(dp), intent(out) :: d(:)
    real(dp), allocatable :: dg(:)
    integer :: n, nt, jp, jm, js, k

    n = prob%n
    nt = prob%nt
    jp = n                                             ! beta+ = z(jp+1 : jp+nt)
    jm = n + nt                                        ! beta- = z(jm+1 : jm+nt)
    js = n + 2 * nt                                    ! sigma = z(js+1 : js+nt)
    m = 0.0_dp
    ! Normal rows:  w = qn + Gnn lambda + Gnt (beta+ - beta-).
    m(1:n, 1:n) = g(1:n, 1:n)
    m(1:n, jp + 1:jp + nt) = g(1:n, n + 1:n + nt)
    m(1:n, jm + 1:jm + nt) = -g(1:n, n + 1:n + nt)
    ! beta+ rows:  w = qt + Gtn lambda + Gtt tau + sigma = sigma - ds.
    m(jp + 1:jp + nt, 1:n) = g(n + 1:n + nt, 1:n)
    m(jp + 1:jp + nt, jp + 1:jp + nt) = g(n + 1:n + nt, n + 1:n + nt)
    m(jp + 1:jp + nt, jm + 1:jm + nt) = -g(n + 1:n + nt, n + 1:n + nt)
    ! beta- rows:  w = -qt - Gtn lambda - Gtt tau + sigma = sigma + ds.
    m(jm + 1:jm + nt, 1:jm + nt) = -m(jp + 1:jp + nt, 1:jm + nt)
    do k = 1, nt
      m(jp + k, js + k) = 1.0_dp
      m(jm + k, js + k) = 1.0_dp
      ! sigma rows:  w = bound + cmu lambda_trow - beta+ - beta- = b - (beta+ + beta-).
      m(js + k, prob%trow(k)) = prob%cmu(k)
      m(js + k, jp + k) = -1.0_dp
      m(js + k, jm + k) = -1.0_dp
    end do
    q = [prob%qn, prob%qt, -prob%qt, prob%bound]
    allocate(dg(n + nt))
    call scaling_vector(g, dg)                         ! 1/sqrt(G_ii), as scale_lcp
    d = [dg, dg(n + 1:n + nt), 1.0_dp / dg(n + 1:n + nt)]        ! [dn; dt; dt; 1/dt]
  end subroutine friction_lcp_system

  !> lam = [lambda; tau] read off a solution z = [lambda; beta+; beta-; ...] of
  !> the friction LCP (module header): tau = beta+ - beta-, polished onto
  !> [-b, b] (beta+ + beta- <= b holds only to round-off, and both may be
  !> basic at a round-off level when b = 0).
  !>   prob  (in)  the problem
  !>   z     (in)  (>= n+2nt) Lemke's solution
  !>   lam   (out) (n+nt) the forces
  pure subroutine friction_forces(prob, z, lam)
    type(friction_problem_t), intent(in) :: prob
    real(dp), intent(in) :: z(:)
    real(dp), intent(out) :: lam(:)
    real(dp) :: bk
    integer :: n, k

    n = prob%n
    lam(1:n) = z(1:n)                                  ! lambda
    do k = 1, prob%nt
      bk = prob%bound(k) + prob%cmu(k) * lam(prob%trow(k))
      lam(n + k) = min(bk, max(-bk, z(n + k) - z(n + prob%nt + k)))
    end do
  end subroutine friction_forces

  ! ---------------------------------------------------------------------------
  ! Internals
  ! ---------------------------------------------------------------------------

  !> .true. when the sizes of g, prob and lam (nlam entries) agree and trow is
  !> in range: what the measures need.  The values are not scanned here (G is
  !> the run's largest array and the measures run after every solve, which
  !> checked them: check_friction_problem).
  logical function valid_problem(g, prob, nlam)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    integer, intent(in) :: nlam
    integer :: nrow
    nrow = prob%n + prob%nt
    valid_problem = size(g, 1) == nrow .and. size(g, 2) == nrow .and. nlam == nrow .and. &
      size(prob%qn) == prob%n .and. size(prob%qt) == prob%nt .and. size(prob%trow) == prob%nt .and. &
      size(prob%cmu) == prob%nt .and. size(prob%bound) == prob%nt
    if (valid_problem) valid_problem = all(prob%trow >= 1 .and. prob%trow <= prob%n)
  end function valid_problem

  !> Build the scaled problem (module header) from valid arguments.
  !>   g, prob  (in) the problem, as in solve_friction_lcp
  !>   p     (out) the scaled problem
  !>   info  (out) 0; 1 when its arrays (about scaled_bytes(n + nt)) cannot
  !>               be allocated, p then holds nothing
  subroutine scale_friction(g, prob, p, info)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    type(scaled_friction_t), intent(out) :: p
    integer, intent(out) :: info
    integer :: n, nt, nrow, i, k
    real(dp), allocatable :: q(:)

    n = prob%n
    nt = prob%nt
    nrow = n + nt
    ! the dense copy Gs is as large as g: a failed allocation is a diagnosis
    allocate(p%d(nrow), p%gs(nrow, nrow), p%qs(nrow), p%step(nrow), p%zero(nrow), q(nrow), &
             p%trow(nt), p%bs0(nt), p%mus(nt), p%tfirst(n + 1), p%tlist(nt), stat=info)
    if (info /= 0) then
      info = 1
      return
    end if
    q(1:n) = prob%qn
    q(n + 1:) = prob%qt
    call scale_lcp(g, q, p%d, p%gs, p%qs)              ! Gs = D G D, qs = D q
    ! scale_lcp leaves Gs_ii = 1 (to round-off) on a row with a positive
    ! diagonal and Gs_ii <= 1e-30 on a zero row.
    do i = 1, nrow
      p%zero(i) = .not. (p%gs(i, i) > 0.5_dp)
      p%step(i) = 1.0_dp
      if (.not. p%zero(i)) p%step(i) = 1.0_dp / p%gs(i, i)
    end do

    call scale_bounds(prob, p%d, p%qs, p%n, p%nt, p%trow, p%bs0, p%mus, p%qscale)

    ! Tangential rows of each normal row, in order (counting sort on trow).
    p%tfirst = 0
    do k = 1, nt
      p%tfirst(p%trow(k) + 1) = p%tfirst(p%trow(k) + 1) + 1
    end do
    p%tfirst(1) = 1
    do i = 1, n
      p%tfirst(i + 1) = p%tfirst(i + 1) + p%tfirst(i)
    end do
    block
      integer, allocatable :: next(:)
      next = p%tfirst(1:n)
      do k = 1, nt
        p%tlist(next(p%trow(k))) = k
        next(p%trow(k)) = next(p%trow(k)) + 1
      end do
    end block
  end subroutine scale_friction

  !> What every scaled form of a step shares beside D, Gs and qs (module
  !> header): its sizes, the bounds' parts bs0 = bound / d_t and
  !> mus = cmu d_n / d_t, and qscale; for this module's scaled problem and
  !> tresca_newton's.
  !>   prob    (in)  the step's problem, valid
  !>   d, qs   (in)  (n+nt) the scaling and the scaled q
  !>   n, nt   (out) normal and tangential rows
  !>   trow    (out) (nt) the normal row of each tangential row
  !>   bs0, mus (out) (nt) the bounds' parts
  !>   qscale  (out) max(||qs||_inf, max bs0), 1 when 0
  pure subroutine scale_bounds(prob, d, qs, n, nt, trow, bs0, mus, qscale)
    type(friction_problem_t), intent(in) :: prob
    real(dp), intent(in) :: d(:), qs(:)
    integer, intent(out) :: n, nt, trow(:)
    real(dp), intent(out) :: bs0(:), mus(:), qscale
    integer :: k
    n = prob%n
    nt = prob%nt
    trow = prob%trow
    do k = 1, nt
      bs0(k) = prob%bound(k) / d(n + k)                                ! bound / d_t
      mus(k) = prob%cmu(k) * d(prob%trow(k)) / d(n + k)                ! cmu d_n / d_t
    end do
    qscale = 0.0_dp
    if (n + nt > 0) qscale = maxval(abs(qs))
    if (nt > 0) qscale = max(qscale, maxval(bs0))
    if (.not. (qscale > 0.0_dp)) qscale = 1.0_dp
  end subroutine scale_bounds

  !> Bytes of the scaled problem of nrow rows: Gs and five vectors.
  pure real(dp) function scaled_bytes(nrow)
    integer, intent(in) :: nrow
    scaled_bytes = 8.0_dp * real(nrow, dp) * real(nrow + 5, dp)
  end function scaled_bytes

  !> The residual r of (s, v = qs + Gs s) (module header).
  pure function scaled_residual(p, s, v) result(r)
    class(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: s(:), v(:)
    real(dp) :: r
    r = bounded_residual(p%n, p%trow, p%bs0, p%mus, p%qscale, s, v)
  end function scaled_residual

  !> The residual r (module header) of a scaled iterate s with gaps v, for
  !> the bounds bs_k = max(0, bs0_k + mus_k s_trow(k)): the one formula of
  !> this module's scaled problem and of tresca_newton's, whose bounds may
  !> be a Tresca problem's (bs0 and zeros).
  !>   n        (in)  normal rows; the tangential rows follow them
  !>   trow     (in)  (nt) the normal row of each tangential row
  !>   bs0, mus (in)  (nt) the bounds' parts
  !>   qscale   (in)  the scale r is relative to, > 0
  !>   s, v     (in)  (n+nt) the iterate and its gaps
  pure function bounded_residual(n, trow, bs0, mus, qscale, s, v) result(r)
    integer, intent(in) :: n, trow(:)
    real(dp), intent(in) :: bs0(:), mus(:), qscale, s(:), v(:)
    real(dp) :: r
    real(dp) :: bk
    integer :: i, k, j

    r = 0.0_dp
    do i = 1, n
      r = max(r, abs(min(s(i), v(i))))                              ! min(lambda_s, w_s)
    end do
    do k = 1, size(trow)
      j = n + k
      bk = max(0.0_dp, bs0(k) + mus(k) * s(trow(k)))                ! bs_k
      r = max(r, abs(s(j) - min(bk, max(-bk, s(j) - v(j)))))        ! tau - clamp(tau + ds, -b, b)
    end do
    r = r / qscale
  end function bounded_residual

  !> The complementarity measure of (s, v) (module header).
  pure function scaled_complementarity(p, s, v) result(c)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: s(:), v(:)
    real(dp) :: c
    real(dp) :: bk, prod, smax
    integer :: i, k, j

    c = 0.0_dp
    if (p%n + p%nt == 0) return
    prod = 0.0_dp
    do i = 1, p%n
      prod = max(prod, abs(s(i) * v(i)))                            ! lambda w
    end do
    do k = 1, p%nt
      j = p%n + k
      bk = max(0.0_dp, p%bs0(k) + p%mus(k) * s(p%trow(k)))
      prod = max(prod, abs(bk * abs(v(j)) + s(j) * v(j)))           ! b |ds| - tau ds
    end do
    ! the force scale: max |s|, or the largest Tresca bound when every force
    ! is zero (lam = 0 with a bound left unused against a slip: prod > 0)
    smax = maxval(abs(s))
    if (p%nt > 0) smax = max(smax, maxval(p%bs0))
    if (prod > 0.0_dp) c = prod / (smax * p%qscale)
  end function scaled_complementarity

  !> residual and complementarity of scaled iterate s into rep.
  subroutine measure_scaled(p, s, rep)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: s(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: v(:)
    allocate(v(size(s)))
    call lcp_gaps(p%gs, p%qs, s, v)                    ! v = qs + Gs s
    rep%residual = scaled_residual(p, s, v)
    rep%complementarity = scaled_complementarity(p, s, v)
  end subroutine measure_scaled

  !> Method 'lemke': build the friction LCP (module header), solve it with
  !> solve_lcp_lemke_scaled, and read lam = [lambda; beta+ - beta-] off z.
  !>   g, prob (in)   the problem
  !>   p      (in)    its scaled form (the zero rows, the measures)
  !>   opts   (in)    tol, maxit
  !>   lam    (out)   (n+nt) the solution, or the last almost-complementary point
  !>   rep    (inout) the report
  subroutine friction_lemke(g, prob, p, opts, lam, rep)
    real(dp), intent(in) :: g(:, :)
    type(friction_problem_t), intent(in) :: prob
    type(scaled_friction_t), intent(in) :: p
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(out) :: lam(:)
    type(lcp_report_t), intent(inout) :: rep
    type(lcp_report_t) :: lrep
    real(dp), allocatable :: m(:, :), q(:), d(:), z(:), y(:)
    integer :: nz, st, nbad, first_bad

    nz = p%n + 3 * p%nt
    allocate(m(nz, nz), q(nz), d(nz), z(nz), y(nz), stat=st)
    if (st /= 0) then
      call report_out_of_memory(rep, 'solving the friction LCP by Lemke (' // int_to_str(nz) // ' unknowns)', &
                                8.0_dp * real(nz, dp) * real(nz, dp))
      lam = 0.0_dp
      return
    end if
    call friction_lcp_system(g, prob, m, q, d)
    call solve_lcp_lemke_scaled(m, q, d, z, opts, lrep, y)   ! maxit 0: 10 nz + 100 pivots
    call friction_forces(prob, z, lam)
    call measure_scaled(p, lam / p%d, rep)
    rep%iterations = lrep%iterations

    select case (lrep%info)
    case (0, 4)
      call residual_outcome(rep, opts%tol, 'friction Lemke: solved in ' // int_to_str(rep%iterations) // &
        ' pivots (LCP of size ' // int_to_str(nz) // ')', 'friction Lemke: terminated after ' // &
        int_to_str(rep%iterations) // ' pivots', 'G ill-conditioned')
    case (1)
      rep%info = 1
      rep%stopped = 'ray'
      rep%message = 'friction Lemke: ray termination after ' // int_to_str(rep%iterations) // ' pivots: '
      ! Name the obvious cause when there is one: a zero normal row of G
      ! (w_i = qn_i whatever lam) with a negative gap.
      first_bad = infeasible_row(p, opts%tol, nbad)
      if (nbad > 0) then
        rep%message = rep%message // 'row/column ' // int_to_str(first_bad) // ' of G is zero but qn(' // &
          int_to_str(first_bad) // ') = ' // real_to_str(prob%qn(first_bad)) // ' < 0: no solution (' // &
          int_to_str(nbad) // ' such row(s))'
      else if (all(prob%cmu == 0.0_dp)) then
        rep%message = rep%message // 'no solution (Tresca: the friction LCP is positive semi-definite)'
      else if (certifies_infeasible(m, q, y)) then
        ! Farkas: y >= 0, M'y <= 0, q'y < 0, so no z >= 0 has q + M z >= 0
        rep%message = rep%message // 'no solution (the ray proves that no forces satisfy the ' // &
          'contact conditions, even without complementarity)'
      else
        ! Coulomb's M is copositive, not positive semi-definite: its ray is
        ! no certificate, and the step may well have a solution
        rep%message = rep%message // 'no solution found (Coulomb: the friction LCP is copositive only, ' // &
          'so the ray does not prove that the step has none)'
      end if
    case default
      rep%info = lrep%info
      rep%stopped = lrep%stopped
      ! out of memory keeps the program's wording (`out of memory while ...`)
      if (lrep%info == info_no_memory) then
        rep%message = lrep%message
      else
        rep%message = 'friction ' // lrep%message
      end if
    end select
  end subroutine friction_lemke

  !> The first zero normal row of G (w_i = qn_i whatever lam) whose gap is
  !> clearly negative (qs_i < -tol qscale): the problem has no solution; 0 if none.
  !>   p     (in)  the scaled problem
  !>   tol   (in)  the residual target
  !>   nbad  (out) how many such rows
  integer function infeasible_row(p, tol, nbad) result(first_bad)
    type(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: tol
    integer, intent(out) :: nbad
    integer :: i
    nbad = 0
    first_bad = 0
    do i = 1, p%n
      if (p%zero(i) .and. p%qs(i) < -tol * p%qscale) then
        nbad = nbad + 1
        if (first_bad == 0) first_bad = i
      end if
    end do
  end function infeasible_row

  !> Method 'pgs': nonsmooth Gauss-Seidel on the scaled problem.
  !>   p      (in)    the scaled problem
  !>   opts   (in)    tol, maxit, omega
  !>   lam    (inout) initial guess on entry; solution or best iterate on exit
  !>   rep    (inout) the report
  subroutine friction_pgs(p, opts, lam, rep)
    type(scaled_friction_t), intent(in) :: p
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(inout) :: lam(:)
    type(lcp_report_t), intent(inout) :: rep
    real(dp), allocatable :: s(:)
    integer :: nrow, i, maxit, window, reason, nbad, first_bad

    nrow = p%n + p%nt
    ! A zero normal row (w_i = qn_i whatever lam) with a clearly negative gap
    ! cannot be closed: no solution.
    first_bad = infeasible_row(p, opts%tol, nbad)
    if (nbad > 0) then
      lam = 0.0_dp
      call measure_scaled(p, lam, rep)
      call set_report(rep, 1, 'friction PGS: row/column ' // int_to_str(first_bad) // &
        ' of G is zero but qn(' // int_to_str(first_bad) // ') = ' // real_to_str(p%qs(first_bad) / p%d(first_bad)) // &
        ' < 0: no solution (' // int_to_str(nbad) // ' such row(s))')
      return
    end if

    call pgs_limits(opts%maxit, nrow, maxit, window)
    allocate(s(nrow))
    do i = 1, nrow                                     ! s = D^-1 lam, lambda >= 0
      s(i) = 0.0_dp
      if (ieee_is_finite(lam(i))) s(i) = lam(i) / p%d(i)
      if (i <= p%n) s(i) = max(0.0_dp, s(i))
    end do
    call run_pgs(p, p%gs, p%qs, opts%tol, opts%omega, maxit, window, s, rep%iterations, reason)
    lam = p%d * s                                      ! lam = D s
    call measure_scaled(p, s, rep)

    call pgs_outcome(reason, maxit, window, opts%tol, 'friction PGS', 'lam', 'problem', rep)
  end subroutine friction_pgs

  !> One nonsmooth Gauss-Seidel sweep (module header): the normal rows in
  !> order, each followed by the tangential rows of its node.
  !>   p      (in)    the scaled problem
  !>   omega  (in)    relaxation, 0 < omega < 2
  !>   s      (inout) (n+nt) the iterate, s_i >= 0 on the normal rows
  !>   v      (inout) (n+nt) its gaps qs + Gs s, kept up to date
  subroutine friction_sweep(p, omega, s, v)
    class(scaled_friction_t), intent(in) :: p
    real(dp), intent(in) :: omega
    real(dp), intent(inout) :: s(:), v(:)
    real(dp) :: bk
    integer :: n, i, j, kk, k

    n = p%n
    do i = 1, n
      call pgs_set_row(p%gs, i, max(0.0_dp, s(i) - omega * v(i) * p%step(i)), s, v)      ! lambda_i projected
      do kk = p%tfirst(i), p%tfirst(i + 1) - 1
        k = p%tlist(kk)
        j = n + k
        bk = p%bs0(k) + p%mus(k) * s(i)                                        ! bs_k with the new lambda_i
        call pgs_set_row(p%gs, j, min(bk, max(-bk, s(j) - omega * v(j) * p%step(j))), s, v)   ! tau_k clamped
      end do
    end do
  end subroutine friction_sweep

end module friction_lcp
