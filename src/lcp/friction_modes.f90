!> friction_modes: one load step of frictional contact when some bodies are
!> held only by contact (force control), the free rigid modes' amplitudes
!> carried as unknowns of the friction LCP.
!>
!> With the free modes R of the bodies that FIX does not hold (rigid_modes),
!> K^# the generalized inverse that the pinned dofs give, the stacked rows
!> C = [B; T] (n normal, nt tangential, friction_lcp) and z = [lambda; tau],
!>     u = K^# (f - C'z) + R alpha,      R'(f - C'z) = 0,
!> the second equation the equilibrium of the floating bodies, which the
!> normal AND the friction forces must supply.  With G = C K^# C',
!> H = C R (kh held combinations of the modes, mode_support) and e = R'f,
!> the gaps and the slip increments of the step become
!>     v = q + G z - H alpha,   gap = v(1:n),   ds = -v(n+1:n+nt),
!>     H'z = e,
!> and the friction conditions of friction_lcp apply to (z, v).  For Tresca
!> these are the KKT conditions of the convex QP
!>     min 1/2 z'G z + q'z   s.t.  lambda >= 0, |tau| <= bound, H'z = e,
!> alpha being the multiplier of the equality; for Coulomb the bound is
!> mu lambda.  No spring is added: the modes are exact, as in the
!> frictionless mixed LCP of contact_lcp.
!>
!> Both steps by Lemke's method (lexicographic); the existence tests only
!> when the step's LCP ends on a ray (it is a large, degenerate problem).
!>  1. Existence.  A static equilibrium needs contact forces in the friction
!>     cone that balance the load along the modes: min |H'z - e| over
!>     lambda >= 0, |tau| <= bound + cmu lambda, written with
!>     y = [lambda; beta+; beta-] >= 0, tau = beta+ - beta-, A = H'E =
!>     [Hn', Ht', -Ht'] and the cone rows c(y) = bound + Cm lambda - beta+ -
!>     beta- >= 0 (multipliers s) as the LCP of its KKT conditions
!>         M = [ A'A   -Gc' ]    q = [ -A'e  ]     Gc = [Cm, -I, -I],
!>             [ Gc     0   ]        [ bound ]
!>     (positive semi-definite: the off-diagonal blocks are skew, so Lemke
!>     solves it).  A positive minimum means no equilibrium: the unbalanced
!>     load e - H'z is returned.  The same problem without the cone rows
!>     (unlimited friction) tells the two causes apart: the load exceeds
!>     what friction can hold (feasible without the cone), or it pulls the
!>     body off its contacts or along a frictionless direction (infeasible
!>     even then).
!> 1b. Capacity.  Test 1 lets the normal forces grow without bound, and a
!>     fit or a wedge balances any load that way: its normal forces press
!>     against each other and carry no load along the modes, while their
!>     friction would carry all of it.  The normal forces are in fact fixed
!>     by the step's normal problem.  Along a unit combination u of the held
!>     modes, with every tangential row slipping at its bound the way u
!>     pulls, tau = S (bound + Cm lambda), S = diag(sign(Ht u)), they solve
!>         v_n = qn + Gnt S bound + (Gnn + Gnt S Cm) lambda - Hn W beta >= 0,
!>         lambda >= 0,  lambda' v_n = 0,
!>         W'(Hn' lambda + Ht' tau) = W'e,
!>     W an orthonormal basis of the combinations orthogonal to u (their
!>     equilibrium, amplitudes beta), written as an LCP with beta = b+ - b-
!>     as in step 2.  The capacity along u is what these contact forces
!>     exert along it, C = u'(Hn' lambda + Ht' tau) = sum_k |(Ht u)_k| b_k
!>     when Hn u = 0.  u is the part of e that no normal row holds (e minus
!>     its projection on range(Hn')), or the slip direction of test 1: a
!>     load u'e > C exceeds what friction can hold, and C is returned (the
!>     press fit pushed out: C = mu N, N the fit's normal force).  The
!>     coupling Gnt of the slip to the normal forces is taken at the limit
!>     state; it is exact when every row slips there, and the capacity is an
!>     estimate ("about") otherwise.
!>  2. The step.  The friction LCP of friction_lcp extended by alpha =
!>     a+ - a-, a+, a- >= 0, and the two rows w_a+ = H'z - e, w_a- = e - H'z:
!>         z = [lambda; beta+; beta-; sigma; a+; a-]   (n + 3 nt + 2 kh)
!>         M = [  Gnn   Gnt  -Gnt  0  -Hn   Hn ]   q = [  qn   ]
!>             [  Gtn   Gtt  -Gtt  I  -Ht   Ht ]       [  qt   ]
!>             [ -Gtn  -Gtt   Gtt  I   Ht  -Ht ]       [ -qt   ]
!>             [  Cm   -I    -I    0   0    0  ]       [ bound ]
!>             [  Hn'   Ht'  -Ht'  0   0    0  ]       [ -e    ]
!>             [ -Hn'  -Ht'   Ht'  0   0    0  ]       [  e    ]
!>     The alpha blocks are skew (the H columns against the H' rows), so for
!>     Tresca M stays positive semi-definite and a ray proves that there is
!>     no solution; for Coulomb M is copositive only, and the ray proves
!>     nothing unless it is Farkas' certificate of infeasibility
!>     (certifies_infeasible).  The columns of a+ and a- are opposite, so at
!>     most one of each pair is basic: alpha is unique in the basis, and the
!>     equality holds as w_a+ = w_a- = 0.  The two rows add up to
!>     w_a+ + w_a- = 2 z0 on every tableau (covering vector ones): each
!>     complementary solution is reached through an exact tie between z0's
!>     row and a w_a row, which lcp_lemke resolves for z0.
!>     Scaling d = [dn; dt; dt; 1/dt; da; da], dn and dt 1/sqrt(G_ii) as in
!>     friction_lcp, da_j = 1 / max_i |d_i H_ij| (the scaled column of H of
!>     unit size).
!> The solution is accepted when friction_lcp's residual of (z, q - H alpha)
!> and the relative equality residual |H'z - e| / max(|e|, |H| |z|) are
!> both below tol.
!>
!> Programming interface
!>   solve_friction_floating(g, prob, h, e, opts, lam, alpha, rep, unbalanced, cause [, capacity])
!>       prob the step's friction_problem_t (friction_lcp)
!>       rep%info 0 solved; 5 no equilibrium (unbalanced, cause, and with cause
!>       'friction' the capacity); 1 Lemke's ray after the existence tests
!>       (Coulomb: none found); 4 inaccurate; 2 pivot limit
module friction_modes
  use kinds, only: dp
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke, solve_lcp_lemke_scaled, set_report, &
    scaling_vector, info_no_memory
  use lcp_scaling, only: certifies_infeasible
  use friction_lcp, only: friction_problem_t, check_friction_problem, friction_residual, friction_lcp_system, &
    friction_forces
  use strings, only: int_to_str, real_to_str
  use lapack_interfaces, only: dgesvd
  implicit none
  private
  public :: solve_friction_floating, no_equilibrium

  integer, parameter :: no_equilibrium = 5     !< rep%info: no contact forces balance the loads
  real(dp), parameter :: reach_tol = 1.0e-8_dp  !< relative residual of the existence test
  ! a singular value of normal rows' Hn below this fraction of the largest
  ! is round-off: its combination of the modes moves none of those rows
  real(dp), parameter :: rank_ratio = 1.0e-8_dp

contains

  !> One load step of frictional contact with floating bodies (module header).
  !>   g      (in)  (n+nt, n+nt) G = C K^# C', symmetric PSD
  !>   prob   (in)  qn (n) normal gaps without contact forces, g - B K^# f;
  !>                qt (nt) T u_{k-1} - T K^# f; trow, cmu (0 for Tresca),
  !>                bound (0 for Coulomb) (friction_lcp)
  !>   h      (in)  (n+nt, kh) C R V, V the held combinations, kh >= 1
  !>   e      (in)  (kh) V'R'f, the load along them
  !>   opts   (in)  tol (on both residuals), maxit (0: 10 size + 100 pivots)
  !>   lam    (out) (n+nt) [lambda; tau]
  !>   alpha  (out) (kh) amplitudes of the held combinations
  !>   rep    (out) info 0 solved; no_equilibrium when no forces in the cone
  !>                balance e; 1 ray termination; 2 pivot limit; 3 out of
  !>                memory; 4 residual above tol; -1 g or -2 prob invalid
  !>                (check_friction_problem).  residual: friction_lcp's r
  !>   unbalanced (out) (kh) what the contacts leave of the load, e - H'z at
  !>                the closest balance; with cause 'friction' (u'e - C) u,
  !>                u the unit direction of the slip and C the capacity along
  !>                it (0 unless info = 5)
  !>   cause  (out) 'friction': the load exceeds what friction can hold;
  !>                'contact': it pulls the body away from its contacts (or
  !>                along a direction no friction row resists); '' when solved
  !>   capacity (out, optional) with info = 5 and cause 'friction', C: the
  !>                largest load along u = unbalanced / |unbalanced| that the
  !>                contact forces hold, in the units of e (the load along u
  !>                is C + |unbalanced|, so C / (C + |unbalanced|) is the
  !>                fraction of it they hold); 0 otherwise
  subroutine solve_friction_floating(g, prob, h, e, opts, lam, alpha, rep, unbalanced, cause, capacity)
    real(dp), intent(in) :: g(:,:), h(:,:), e(:)
    type(friction_problem_t), intent(in) :: prob
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(out) :: lam(:), alpha(:)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable, intent(out) :: unbalanced(:)
    character(len=:), allocatable, intent(out) :: cause
    real(dp), intent(out), optional :: capacity
    real(dp), allocatable :: z(:), r(:), u(:)
    type(lcp_report_t) :: rep_b
    type(friction_problem_t) :: shifted
    real(dp) :: eq_res, cap
    integer :: n, nt, kh
    logical :: proved, held

    n = prob%n
    nt = prob%nt
    kh = size(e)
    lam = 0.0_dp
    alpha = 0.0_dp
    cause = ''
    if (present(capacity)) capacity = 0.0_dp
    allocate(unbalanced(kh), source=0.0_dp)
    call check_friction_problem(g, prob, rep)
    if (rep%info < 0) return

    ! the step: the extended friction LCP
    call extended_lemke(g, prob, h, e, opts, lam, alpha, rep, proved)
    if (rep%info == 1) then
      ! no solution found: is there a balance within the friction cone at all?
      call closest_balance(h, e, prob, .true., opts, z, rep_b)
      if (rep_b%info /= 0) return
      r = e - matmul(transpose(h), z)
      if (norm2(r) > reach_tol * norm2(e)) then
        ! none, even with unbounded normal forces: the motion that friction
        ! fails to hold keeps the loaded contacts closed
        unbalanced = along_contact(h(1:n, :), z(1:n), r)
        cause = 'friction'
        ! unlimited friction: does the cone or the contact fail?
        call closest_balance(h, e, prob, .false., opts, z, rep_b)
        if (rep_b%info == 0) then
          if (norm2(e - matmul(transpose(h), z)) > reach_tol * norm2(e)) then
            cause = 'contact'
            unbalanced = e - matmul(transpose(h), z)
          end if
        end if
        if (cause == 'friction') then
          ! the capacity along the slip, with the normal forces the step gives
          u = unbalanced / norm2(unbalanced)
          call friction_capacity(g, prob, h, e, u, opts, cap, held)
          if (held .and. dot_product(u, e) > cap) then
            unbalanced = (dot_product(u, e) - cap) * u
            if (present(capacity)) capacity = cap
          end if
        end if
        call set_report(rep, no_equilibrium, 'no contact forces within the friction cone balance the loads ' // &
          '(relative residual ' // real_to_str(norm2(r) / norm2(e)) // ')')
        return
      end if

      ! A balance exists if the normal forces may grow without bound; they
      ! may not: the capacity along the load that no normal row holds, with
      ! the normal forces of the step's normal problem (module header, 1b).
      u = normal_free_part(h(1:n, :), e)
      if (norm2(u) > reach_tol * norm2(e)) then
        u = u / norm2(u)
        call friction_capacity(g, prob, h, e, u, opts, cap, held)
        if (held .and. dot_product(u, e) - cap > reach_tol * norm2(e)) then
          cause = 'friction'
          unbalanced = (dot_product(u, e) - cap) * u
          if (present(capacity)) capacity = cap
          call set_report(rep, no_equilibrium, 'the load that no normal force carries exceeds what friction ' // &
            'can hold: its capacity, with the normal forces of the step''s normal problem and every contact ' // &
            'slipping, is about ' // real_to_str(cap / dot_product(u, e)) // ' times the load')
          return
        end if
      end if
      if (proved) then
        ! Lemke's ray is itself a certificate: no z >= 0 has q + M z >= 0
        call set_report(rep, 1, rep%message // '; the ray is Farkas'' certificate that the step''s LCP has ' // &
          'no feasible point')
      else if (any(prob%cmu /= 0.0_dp)) then
        rep%message = rep%message // '; the loads can be balanced by contact forces ' // &
          'within the friction cone, so this does not prove that no equilibrium exists'
      else
        ! Tresca: the step is a convex QP whose feasible set (a balance in
        ! the cone) is not empty, and whose objective is bounded below on it
        ! when G is definite on the normal rows: it has a solution, and the
        ! ray is round-off's.  The balance may need huge amplitudes (a
        ! couple on a ring around a shaft, balanced only through the
        ! faceting of the two circles: the solution turns the ring by
        ! hundreds of radians), and the tableau of such a step is at the
        ! edge of what double precision resolves.
        rep%message = 'friction Lemke with rigid-mode amplitudes: ray termination after ' // &
          int_to_str(rep%iterations) // ' pivots, although the loads can be balanced by contact forces ' // &
          'within the friction bounds (Tresca: the step is then a feasible convex problem, so the ray most ' // &
          'likely comes from round-off; ' // &
          'the equilibrium is at the edge of what the contacts can hold, e.g. a moment balanced only ' // &
          'through the faceting of a curved contact)'
      end if
      return
    end if
    if (rep%info /= 0 .and. rep%info /= 4) return
    shifted = prob                                       ! the step's q - H alpha
    shifted%qn = prob%qn - matmul(h(1:n, :), alpha)
    shifted%qt = prob%qt - matmul(h(n + 1:n + nt, :), alpha)
    rep%residual = friction_residual(g, shifted, lam)
    eq_res = norm2(matmul(transpose(h), lam) - e) / max(norm2(e), maxval(abs(h)) * sum(abs(lam)), tiny(1.0_dp))
    if (rep%residual <= opts%tol .and. eq_res <= opts%tol) then
      rep%info = 0
      rep%message = 'friction Lemke with ' // int_to_str(kh) // ' rigid-mode amplitudes: solved in ' // &
        int_to_str(rep%iterations) // ' pivots, residual ' // real_to_str(rep%residual) // ', equilibrium ' // &
        real_to_str(eq_res)
    else
      rep%info = 4
      rep%message = 'friction Lemke with rigid-mode amplitudes: residual ' // real_to_str(rep%residual) // &
        ', equilibrium residual ' // real_to_str(eq_res) // ' above tol ' // real_to_str(opts%tol) // &
        ' after ' // int_to_str(rep%iterations) // ' pivots'
    end if
  end subroutine solve_friction_floating

  !> The part of r (kh) in the null space of the normal rows that carry a
  !> force (lambda > 0): the rigid motion along the contact surface, which
  !> opens or closes no loaded gap.  The closest balance in the cone leaves
  !> e - H'z normal to the cone's face, tilted off the slip direction by the
  !> friction angle; this is the slip direction itself.  r itself when its
  !> part there is below 1e-3 of it (no such motion: a rotation about a
  !> contact point, say).
  function along_contact(hn, lambda, r) result(t)
    real(dp), intent(in) :: hn(:,:), lambda(:), r(:)
    real(dp), allocatable :: t(:)
    integer :: i
    t = r
    if (count(lambda > 0.0_dp) == 0 .or. size(r) == 0) return
    t = normal_free_part(hn(pack([(i, i = 1, size(lambda))], lambda > 0.0_dp), :), r)
    if (norm2(t) <= 1.0e-3_dp * norm2(r)) t = r
  end function along_contact

  !> r (kh) minus its part in range(Hn'): its part along the combinations of
  !> the modes that move none of the rows of hn (singular values of hn below
  !> rank_ratio of the largest count as zero); r when hn has no row.
  function normal_free_part(hn, r) result(t)
    real(dp), intent(in) :: hn(:,:), r(:)
    real(dp), allocatable :: t(:)
    real(dp), allocatable :: a(:,:), s(:), vt(:,:), work(:)
    real(dp) :: u1(1, 1), wq(1)
    integer :: na, kh, info, rank
    t = r
    na = size(hn, 1)
    kh = size(r)
    if (na == 0 .or. kh == 0) return
    a = hn
    allocate(s(min(na, kh)), vt(kh, kh))
    call dgesvd('N', 'A', na, kh, a, na, s, u1, 1, vt, kh, wq, -1, info)
    allocate(work(max(1, int(wq(1)))))
    call dgesvd('N', 'A', na, kh, a, na, s, u1, 1, vt, kh, work, size(work), info)
    if (info /= 0) return
    rank = count(s > rank_ratio * maxval(s))
    t = r - matmul(transpose(vt(1:rank, :)), matmul(vt(1:rank, :), r))    ! r minus its part in range(Hn')
  end function normal_free_part

  !> The friction capacity along the unit combination u (module header, 1b):
  !> the normal problem with every tangential row slipping at its bound the
  !> way u pulls and the other combinations in equilibrium, by Lemke, and
  !> C = u'(Hn' lambda + Ht' tau) of its contact forces.
  !>   g, prob, h, e  (in) as in solve_friction_floating
  !>   u     (in)  (kh) unit vector
  !>   opts  (in)  tol, maxit
  !>   cap   (out) the capacity C along u, in the units of e
  !>   held  (out) .true. when the normal problem was solved (cap valid)
  subroutine friction_capacity(g, prob, h, e, u, opts, cap, held)
    real(dp), intent(in) :: g(:,:), h(:,:), e(:), u(:)
    type(friction_problem_t), intent(in) :: prob
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(out) :: cap
    logical, intent(out) :: held
    real(dp), allocatable :: sgn(:), tcm(:,:), tau0(:), w(:,:), hw(:,:), a(:,:), ew(:), m(:,:), q(:), d(:), &
      z(:), dg(:), tau(:), s1(:), vt(:,:), work(:), ut(:,:)
    real(dp) :: u1(1, 1), wq(1), bk
    type(lcp_report_t) :: rep
    type(lcp_options_t) :: o
    integer :: n, nt, kh, kw, k, j, info, nz

    n = prob%n
    nt = prob%nt
    kh = size(e)
    kw = kh - 1
    cap = 0.0_dp
    held = .false.
    ! tau = S (bound + Cm lambda) = tau0 + tcm lambda, S = diag(sign(Ht u))
    sgn = matmul(h(n + 1:n + nt, :), u)
    where (sgn > 0.0_dp)
      sgn = 1.0_dp
    elsewhere (sgn < 0.0_dp)
      sgn = -1.0_dp
    end where
    allocate(tcm(nt, n), source=0.0_dp)
    do k = 1, nt
      tcm(k, prob%trow(k)) = sgn(k) * prob%cmu(k)
    end do
    tau0 = sgn * prob%bound
    ! W: the combinations orthogonal to u, the last kw right singular vectors of u'
    allocate(w(kh, kw))
    if (kw > 0) then
      ut = reshape(u, [1, kh])
      allocate(s1(1), vt(kh, kh))
      call dgesvd('N', 'A', 1, kh, ut, 1, s1, u1, 1, vt, kh, wq, -1, info)
      allocate(work(max(1, int(wq(1)))))
      call dgesvd('N', 'A', 1, kh, ut, 1, s1, u1, 1, vt, kh, work, size(work), info)
      if (info /= 0) return
      w = transpose(vt(2:kh, :))
    end if
    hw = matmul(h(1:n, :), w)                                               ! Hn W
    a = matmul(transpose(w), transpose(h(1:n, :)) + matmul(transpose(h(n + 1:n + nt, :)), tcm))   ! W'(Hn' + Ht' S Cm)
    ew = matmul(transpose(w), e - matmul(transpose(h(n + 1:n + nt, :)), tau0))                    ! W'(e - Ht' S bound)

    ! LCP in z = [lambda; b+; b-], beta = b+ - b-
    nz = n + 2 * kw
    allocate(m(nz, nz), q(nz), d(nz), z(nz), dg(n + nt), source=0.0_dp)
    m(1:n, 1:n) = g(1:n, 1:n) + matmul(g(1:n, n + 1:n + nt), tcm)          ! Gnn + Gnt S Cm
    m(1:n, n + 1:n + kw) = -hw
    m(1:n, n + kw + 1:nz) = hw
    m(n + 1:n + kw, 1:n) = a
    m(n + kw + 1:nz, 1:n) = -a
    q(1:n) = prob%qn + matmul(g(1:n, n + 1:n + nt), tau0)                   ! qn + Gnt S bound
    q(n + 1:n + kw) = -ew
    q(n + kw + 1:nz) = ew
    call scaling_vector(g, dg)                                              ! 1/sqrt(G_ii), as friction_lcp
    d(1:n) = dg(1:n)
    do j = 1, kw
      bk = maxval(abs(dg(1:n) * hw(:, j)))
      d(n + j) = 1.0_dp
      if (bk > 0.0_dp) d(n + j) = 1.0_dp / bk
      d(n + kw + j) = d(n + j)
    end do
    o = opts
    o%maxit = 0
    call solve_lcp_lemke_scaled(m, q, d, z, o, rep)
    if (rep%info /= 0) return
    tau = tau0 + matmul(tcm, z(1:n))
    cap = dot_product(u, matmul(transpose(h(1:n, :)), z(1:n)) + matmul(transpose(h(n + 1:n + nt, :)), tau))
    held = .true.
  end subroutine friction_capacity

  !> The contact forces z = [lambda; tau] closest to balancing e: min |H'z - e|
  !> over lambda >= 0 and, when cone, |tau| <= bound + cmu lambda (module
  !> header, step 1).
  !>   h, e, prob  (in) as in solve_friction_floating (qn and qt unused)
  !>   cone (in)  .false.: unlimited friction (tau free)
  !>   opts (in)  tol, maxit
  !>   z    (out) (n+nt) the minimizer
  !>   rep  (out) info 0, or Lemke's failure
  subroutine closest_balance(h, e, prob, cone, opts, z, rep)
    real(dp), intent(in) :: h(:,:), e(:)
    type(friction_problem_t), intent(in) :: prob
    logical, intent(in) :: cone
    type(lcp_options_t), intent(in) :: opts
    real(dp), allocatable, intent(out) :: z(:)
    type(lcp_report_t), intent(out) :: rep
    real(dp), allocatable :: a(:,:), m(:,:), q(:), d(:), y(:)
    integer :: n, nt, ny, nx, k, kh
    type(lcp_options_t) :: o

    n = prob%n
    nt = prob%nt
    kh = size(e)
    ny = n + 2 * nt
    allocate(a(kh, ny))
    a(:, 1:n) = transpose(h(1:n, :))                        ! A = H'E = [Hn', Ht', -Ht']
    a(:, n + 1:n + nt) = transpose(h(n + 1:, :))
    a(:, n + nt + 1:) = -transpose(h(n + 1:, :))
    o = opts
    o%maxit = 0
    if (.not. cone) then
      allocate(y(ny))
      call solve_lcp_lemke(matmul(transpose(a), a), -matmul(transpose(a), e), y, o, rep)
    else
      nx = ny + nt
      allocate(m(nx, nx), q(nx), d(nx), y(nx), stat=k)
      if (k /= 0) then
        call set_report(rep, info_no_memory, 'out of memory in the existence test of the friction equilibrium')
        return
      end if
      m = 0.0_dp
      m(1:ny, 1:ny) = matmul(transpose(a), a)
      q(1:ny) = -matmul(transpose(a), e)
      q(ny + 1:) = prob%bound
      do k = 1, nt
        ! cone row k: c = bound + cmu lambda_trow - beta+ - beta-;  -Gc' in the y rows
        m(ny + k, prob%trow(k)) = prob%cmu(k)
        m(ny + k, n + k) = -1.0_dp
        m(ny + k, n + nt + k) = -1.0_dp
        m(prob%trow(k), ny + k) = -prob%cmu(k)
        m(n + k, ny + k) = 1.0_dp
        m(n + nt + k, ny + k) = 1.0_dp
      end do
      call scaling_vector(m(1:ny, 1:ny), d(1:ny))              ! d_i = 1/sqrt((A'A)_ii)
      d(ny + 1:) = 1.0_dp / d(n + 1:n + nt)
      call solve_lcp_lemke_scaled(m, q, d, y, o, rep)
    end if
    if (rep%info == 4) rep%info = 0            ! the balance is measured by the caller
    allocate(z(n + nt))
    z(1:n) = y(1:n)
    z(n + 1:) = y(n + 1:n + nt) - y(n + nt + 1:n + 2 * nt)
  end subroutine closest_balance

  !> Step 2 (module header): the friction LCP extended by the mode amplitudes,
  !> solved by solve_lcp_lemke_scaled; lam and alpha read off its z.
  !>   g, prob, h, e  (in) as in solve_friction_floating
  !>   opts  (in)  tol, maxit (0: 10 (n + 3 nt + 2 kh) + 100 pivots)
  !>   lam   (out) (n+nt) [lambda; tau], tau polished onto [-b, b]
  !>   alpha (out) (kh) a+ - a-
  !>   rep   (out) Lemke's report (info 1: ray termination, with the message)
  !>   proved (out) .true. when the ray is Farkas' certificate that the LCP
  !>               has no feasible point (certifies_infeasible)
  subroutine extended_lemke(g, prob, h, e, opts, lam, alpha, rep, proved)
    real(dp), intent(in) :: g(:,:), h(:,:), e(:)
    type(friction_problem_t), intent(in) :: prob
    type(lcp_options_t), intent(in) :: opts
    real(dp), intent(out) :: lam(:), alpha(:)
    type(lcp_report_t), intent(out) :: rep
    logical, intent(out) :: proved
    real(dp), allocatable :: m(:,:), q(:), d(:), z(:), y(:)
    real(dp) :: bk
    integer :: n, nt, kh, nz, jp, jm, js, ja, jb, j, st, nr

    n = prob%n
    nt = prob%nt
    kh = size(e)
    nr = n + nt
    nz = n + 3 * nt + 2 * kh
    jp = n                               ! beta+
    jm = n + nt                          ! beta-
    js = n + 2 * nt                      ! sigma
    ja = n + 3 * nt                      ! a+
    jb = ja + kh                         ! a-
    proved = .false.
    allocate(m(nz, nz), q(nz), d(nz), z(nz), y(nz), stat=st)
    if (st /= 0) then
      call set_report(rep, info_no_memory, 'out of memory: solving the friction LCP with rigid modes by Lemke (' // &
        int_to_str(nz) // ' unknowns)')
      return
    end if
    m = 0.0_dp
    call friction_lcp_system(g, prob, m(1:ja, 1:ja), q(1:ja), d(1:ja))    ! friction_lcp's LCP and scaling
    ! v = q + G z - H alpha in the normal and beta+ rows, minus that in the beta- rows
    m(1:n, ja + 1:ja + kh) = -h(1:n, :)
    m(jp + 1:jp + nt, ja + 1:ja + kh) = -h(n + 1:nr, :)
    m(jm + 1:jm + nt, ja + 1:ja + kh) = h(n + 1:nr, :)
    m(1:jm + nt, jb + 1:jb + kh) = -m(1:jm + nt, ja + 1:ja + kh)
    ! w_a+ = H'z - e = Hn' lambda + Ht' (beta+ - beta-) - e; w_a- its negative
    m(ja + 1:ja + kh, 1:n) = transpose(h(1:n, :))
    m(ja + 1:ja + kh, jp + 1:jp + nt) = transpose(h(n + 1:nr, :))
    m(ja + 1:ja + kh, jm + 1:jm + nt) = -transpose(h(n + 1:nr, :))
    m(jb + 1:jb + kh, 1:js) = -m(ja + 1:ja + kh, 1:js)
    q(ja + 1:) = [-e, e]
    do j = 1, kh
      bk = maxval(abs(d(1:nr) * h(:, j)))                    ! d(1:nr) = 1/sqrt(G_ii)
      d(ja + j) = 1.0_dp
      if (bk > 0.0_dp) d(ja + j) = 1.0_dp / bk
      d(jb + j) = d(ja + j)
    end do

    call solve_lcp_lemke_scaled(m, q, d, z, opts, rep, y)
    call friction_forces(prob, z, lam)
    alpha = z(ja + 1:ja + kh) - z(jb + 1:jb + kh)
    if (rep%info == 1) then
      proved = certifies_infeasible(m, q, y)
      rep%message = 'friction Lemke with rigid-mode amplitudes: ray termination after ' // &
        int_to_str(rep%iterations) // ' pivots: '
      if (all(prob%cmu == 0.0_dp)) then
        rep%message = rep%message // 'no solution (Tresca: the LCP is positive semi-definite)'
      else
        rep%message = rep%message // 'no solution found (Coulomb: the LCP is copositive only, so its ray ' // &
          'proves nothing)'
      end if
    end if
  end subroutine extended_lemke

end module friction_modes
