!> newton_step: one load step of a scene with hyperelastic bodies, solved by
!> Newton's method on the consistent tangent with a backtracking line search
!> (doc/theory.md, "Finite strain: hyperelastic bodies").  The step's loads
!> are its external forces f and the prescribed values ubar of the fixed
!> dofs; the state it starts from is the last step's u.
!>
!> Iterate (module finite_strain_assembly):
!>     K_ff(u) du_f = f_f - f_int,f(u) - K_fd(u) dubar_d,   dubar_d = ubar_d - u_d,
!>     u <- u + alpha du  (du_d = dubar_d),
!> alpha = 1, halved while the trial turns an element inside out (J <= 0) or,
!> once the prescribed values are reached, while it does not decrease the
!> residual's norm by the Armijo fraction 1e-4 alpha (at most max_halvings
!> times; the last J > 0 trial is then taken).  Converged: the prescribed
!> values reached and ||f_f - f_int,f|| <= tol * scale, scale = max(||f||,
!> ||f_int||, ||f_c||) over the bodies' dofs (the reactions count: a step
!> driven by prescribed displacements has no f) and the FORCE of the RIGIDs
!> it moves; a RIGID's moment and rotation enter divided and multiplied by
!> its size, so that every term is a force or a length and the tolerance
!> does not depend on the unit of length.  A RIGID moved by FORCE has its
!> free dofs among the equations: no element stiffens them, so they are
!> soft dofs (below) until a closed contact row holds them (augmented_tangent).
!>
!> An iterate whose tangent is not positive definite is assembled again
!> with each hyperelastic element's tangent cut to its positive part
!> (finite_strain_assembly's definite): a direction that lowers the stored
!> energy where Newton's has none (far from the equilibrium; the next
!> iterate tries the consistent tangent again).  When even that is not
!> definite, the last update went too far (the first update of a new load
!> in a nearly incompressible body, below): it is halved again (at most
!> max_halvings times) and the iteration goes on from there.  The
!> iterations counted are the solves.  A step that does not converge in
!> maxit iterations, or whose line search finds no decrease of the residual
!> twice running (a stalled iteration: the caller starts it again without
!> the predictor, or halves it), or whose tangent stays indefinite, or whose every trial
!> inverts an element, returns converged = .false. with the reason and the
!> element: the caller halves the step.  Nothing here stops the run or
!> writes a file.
!>
!> The tangent's pressure (doc/theory.md, "The tangent's pressure").  Each
!> element with F-bar keeps a dilatation theta, updated along the
!> linearization as the condensed mixed (u, theta, p) method of the mean
!> dilatation does, theta <- theta + alpha (J0(u) - theta + dJ0/du du); the
!> tangent's initial-stress terms take K (theta - 1) where F-bar's take
!> K (J0 - 1), whose error after an update is K times its square.  The
!> residual is F-bar's; theta - J0 falls as the update squared, so the last
!> iterates are Newton's.
!>
!> A load step is walked in sub-increments, each started in one of three
!> ways (start_*), by module newton_increment; solve_newton_step's guess
!> and strict are what it needs of one solve.
!>
!> Contact (optional argument specs: the CONTACT pairs, each followed as a
!> sliding=finite pair, frictionless or with friction).  Every iterate
!> rebuilds the rows C = [B; T] and the gaps g(u) of the current
!> configuration (moved_contact), adds the rows that hold the iterate to
!> its tangent (augmented_tangent: a section that only its contacts hold
!> has a tangent that is not definite by itself; where those rows stay
!> closed the iterate is unchanged) and solves its contact problem on the
!> condensed tangent, W = C_f K^-1 C_f', by Lemke's method (contact_correction;
!> with friction friction_lcp's Lemke method, the slips measured from the
!> sub-increment's start): the linear runs' machinery, on the iterate.
!> Why an LCP per iterate rather than a semismooth Newton on the whole
!> system: the tangent's factor is there already, the contact rows are few
!> (a boundary's nodes), and Lemke gives the iterate's exact active set, so
!> the outer iteration is Newton's on a fixed set near the end (quadratic).
!> Measured against a semismooth Newton (opts%contact = 'active_set', one
!> active-set step per iterate, contact_correction's active_set_step;
!> bench/newton_lcp.sh): the same answers; more iterations and CPU on the
!> O-ring and on a frictionless section in its groove; W, built either
!> way, is most of an iterate's cost.  The
!> residual then counts the contact forces -C' lam; converged also asks
!> the last correction below tol of the displacement (the gaps of the
!> linearization are then the true ones to its square), and the result
!> gives the least linearized gap and the complementarity of the last LCP.
!>
!> Programming interface
!>   type(newton_options_t)   tol, maxit, max_halvings, max_cuts, contact (lemke or active_set)
!>   type(newton_result_t)    converged, iterations, residual, bad element, reason
!>   solve_newton_step(bodies, eq, nfree, k, f, ubar, opts, u, res, err [, specs] [, guess] [, soft] [, strict])
!>   element_note(bodies, bad)  ' (body NAME, element E)' for a message, '' when bad names none
module newton_step
  use kinds, only: dp, i8
  use errors, only: error_t
  use strings, only: int_to_str
  use body, only: body_t
  use finite_strain_assembly, only: assemble_tangent, internal_force_vector, element_dilatations
  use contact_set, only: contact_set_t, pair_spec_t
  use moved_contact, only: build_moved_contact_set, row_keys
  use augmented_tangent, only: cover_rows, augment_rows
  use local_axes, only: rotate_constraint_rows
  use lcp_scaling, only: lcp_options_t, lcp_report_t
  use lcp_lemke, only: solve_lcp_lemke
  use lapack_interfaces, only: dgesv, dsyev
  use friction_lcp, only: friction_problem_t, friction_problem, solve_friction_lcp, friction_state
  use sparse_matrix, only: csc_t
  use sparse_cholesky, only: factor_t, analyze_pattern, factorize_values, solve_vector, free_factor
  implicit none
  private
  public :: newton_options_t, newton_result_t, solve_newton_step, element_note
  public :: start_predicted, start_plain, start_through

  !> How a sub-increment starts (module newton_increment): from the
  !> prediction, given up when its first tangent is not definite; from the
  !> last state; from the prediction, through an indefinite first tangent
  integer, parameter :: start_predicted = 0, start_plain = 1, start_through = 2

  type :: newton_options_t
    real(dp) :: tol = 1.0e-8_dp       !< residual / scale at convergence (SOLVER newton_tol=)
    integer :: maxit = 25             !< iterations before the step fails (SOLVER newton_maxit=)
    integer :: max_halvings = 12      !< line-search halvings per iteration
    integer :: max_cuts = 10          !< halvings of a load step's increment before it fails
    !> each iterate's contact problem: 'lemke' (Lemke's method on its LCP) or
    !> 'active_set' (semismooth Newton: the rows of the last iterate's
    !> active set as equalities, frictionless pairs only; SOLVER newton_lcp=)
    character(len=16) :: contact = 'lemke'
  end type newton_options_t

  type :: newton_result_t
    logical :: converged = .false.
    integer :: iterations = 0                 !< Newton iterations made (tangent solves)
    real(dp) :: residual = 0.0_dp             !< the last ||r_f|| / scale
    real(dp), allocatable :: history(:)       !< (iterations + 1) ||r_f|| / scale at each iterate
    integer :: bad(2) = 0                     !< (body, element) that had J <= 0, when that stopped it
    character(len=:), allocatable :: reason   !< why it did not converge ('' when it did)
    integer :: cuts = 0                       !< solve_newton_increment: halvings made
    integer :: substeps = 0                   !< solve_newton_increment: sub-increments solved
    logical :: start_refused = .false.        !< solve_newton_step: strict, and the tangent at the guess not definite
    logical :: from_guess = .false.           !< solve_newton_step: it started from the guess (no element inside out there)
    integer :: start = start_predicted        !< solve_newton_increment: how its last sub-increment with a
                                              !< prediction started (module header)
    real(dp), allocatable :: fcon(:)          !< (ndof) contact forces on the bodies, -B' lambda (contact)
    real(dp) :: gap = 0.0_dp                  !< contact: the least linearized gap after the last iterate
    real(dp) :: complementarity = 0.0_dp      !< contact: max lambda_i gap_i / (max lambda size), a length
    type(contact_set_t) :: cs                 !< contact: the rows of the last iterate (its configuration)
    real(dp), allocatable :: lambda(:)        !< contact: (nrow + ntan) their multipliers, normal then
                                              !< tangential (nodal forces)
    real(dp), allocatable :: w(:,:)           !< contact: (nrow + ntan)^2 W of the last iterate's tangent
    real(dp), allocatable :: q(:)             !< contact: (nrow + ntan) its qn (gaps without contact
                                              !< forces) and qt (contact_correction)
    real(dp), allocatable :: gaps(:)          !< contact: (nrow) its linearized gaps, q + W lambda
    real(dp), allocatable :: slip(:)          !< friction: (ntan) the slip of the sub-increment, -(qt + W_t lambda)
    integer, allocatable :: fstate(:)         !< friction: (ntan) 0 open, 1 stick, 2 slip
    character(len=:), allocatable :: notes    !< solve_newton_increment: one line per halving
  end type newton_result_t

contains

  !> One load step by Newton's method (module header).
  !>   bodies (in)    the bodies, dof0 set
  !>   eq     (in)    (ndof) free equation numbers;  nfree (in) their count, > 0
  !>   k      (inout) K_ff's pattern (build_pattern); its values are overwritten
  !>   f      (in)    (ndof) external forces of the step, solver basis
  !>   ubar   (in)    (ndof) the prescribed values of the step on the fixed dofs
  !>   opts   (in)    tolerances
  !>   u      (inout) (ndof) the last step's state on entry, this step's on exit
  !>                  (when not converged: the last iterate with J > 0)
  !>   res    (out)   the outcome
  !>   err    (out)   an allocation or factorization failure other than a non
  !>                  positive definite tangent (that one is res%reason), or the
  !>                  contact rows' failure (build_moved_contact_set)
  !>   specs  (in, optional) (npair) frictionless CONTACT pairs to follow (module header)
  !>   guess  (in, optional) (ndof) where to start instead of u (its fixed dofs at ubar),
  !>                  unless an element is inside out there
  !>   strict (in, optional) .true.: a guess whose first tangent is not definite
  !>                  ends the step at once (res%start_refused)
  subroutine solve_newton_step(bodies, eq, nfree, k, f, ubar, opts, u, res, err, specs, guess, soft, strict)
    type(body_t), intent(in) :: bodies(:)
    integer, intent(in) :: eq(:), nfree
    type(csc_t), intent(inout) :: k
    real(dp), intent(in) :: f(:), ubar(:)
    type(newton_options_t), intent(in) :: opts
    real(dp), intent(inout) :: u(:)
    type(newton_result_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: err
    type(pair_spec_t), intent(in), optional :: specs(:)
    real(dp), intent(in), optional :: guess(:)
    logical, intent(in), optional :: soft(:)
    logical, intent(in), optional :: strict
    type(factor_t) :: fac
    type(error_t), allocatable :: ferr
    real(dp), allocatable :: dubar(:), rhs(:), du_f(:), du(:), trial(:), fint(:), u_best(:)
    real(dp), allocatable :: u_prev(:), du_prev(:), u_entry(:), theta(:), j0(:), dj0(:), theta_prev(:), dtheta_prev(:)
    real(dp) :: merit, merit_trial, best, alpha, step, alpha_prev, rnorm, rnorm_trial, alpha_best
    integer :: it, i, h, bad(2), back, nb, stalled
    integer, parameter :: max_stalls = 2
    logical :: reached, analyzed, accepted, with_contact, grown, descent
    type(contact_set_t) :: cs
    logical, allocatable :: holds(:), closing(:)
    logical :: active_set, settled, same_u, refuse
    real(dp), allocatable :: target(:), arm(:)
    logical, allocatable :: soft_now(:)
    integer(i8), allocatable :: held_keys(:)

    allocate(dubar(size(u)), rhs(nfree), du_f(nfree), du(size(u)), trial(size(u)), fint(size(u)))
    allocate(res%fcon(size(u)), source=0.0_dp)
    ! the bodies' dofs come first, the RIGIDs' after them: the scales of the
    ! residual and of the correction are taken over the bodies' alone (a
    ! RIGID's moment and rotation have other units than forces and lengths,
    ! and mixed in they would make the tolerances depend on the unit of length)
    nb = maxval([(bodies(i)%dof0 + 2 * bodies(i)%mesh%nnode, i = 1, size(bodies))])
    with_contact = present(specs)
    if (with_contact) with_contact = size(specs) > 0
    ! a RIGID's rotation times its size is a length, its moment over it a
    ! force: the scale that puts a free RIGID's equations among the bodies'
    allocate(arm(size(u)), source=1.0_dp)
    if (with_contact) then
      do i = 1, size(specs)
        if (specs(i)%rigid > 0) arm(specs(i)%shape%dof0 + 3) = specs(i)%shape%length
      end do
    end if
    active_set = opts%contact == 'active_set'
    allocate(res%history(0))
    res%reason = ''
    analyzed = .false.
    u_entry = u                                       ! the slips of the sub-increment are measured from here
    if (present(guess)) then                          ! a predicted start, when no element is inside out there
      call measure(guess, merit, reached, bad, norm=rnorm)
      if (bad(1) == 0) u = guess
      res%from_guess = bad(1) == 0
    end if
    refuse = .false.                                  ! strict: such a start given up at its first tangent
    if (present(strict)) refuse = strict .and. res%from_guess
    call measure(u, merit, reached, bad, norm=rnorm)
    if (bad(1) /= 0) then
      res%bad = bad
      res%reason = 'the state the step starts from has an element with J <= 0'
      return
    end if
    ! the elements' dilatation state: J0 where the step starts, moved to the
    ! predicted start along its linearization
    i = maxval([(bodies(h)%elem0 + bodies(h)%mesh%nelem, h = 1, size(bodies))])
    allocate(theta(i), j0(i), dj0(i))
    call element_dilatations(bodies, u_entry, u - u_entry, j0, dj0, bad)   ! J > 0 at u_entry: a state reached
    theta = j0 + dj0
    res%history = [merit]
    step = huge(1.0_dp)
    back = 0
    stalled = 0
    alpha_prev = 1.0_dp
    descent = .false.
    same_u = .false.
    it = 0
    do                                                ! it counts the solves; a refactorization is not one
      if (reached .and. merit <= opts%tol .and. (.not. with_contact .or. step <= opts%tol)) exit
      if (it >= opts%maxit) exit
      ! the Newton system at u
      dubar = 0.0_dp
      do i = 1, size(u)
        if (eq(i) == 0) dubar(i) = ubar(i) - u(i)
      end do
      if (with_contact .and. .not. same_u) then
        ! the iterate's rows, and those that hold it, before K is made: they
        ! are added to it (module augmented_tangent); a retry with the
        ! elements' positive parts is at the same u, and keeps them
        call build_moved_contact_set(bodies, specs, u, cs, err)
        if (allocated(err)) return
        call rotate_constraint_rows(cs, bodies)      ! nodes in local axes (FIX un=/ut=): rows on their dofs
        call cover_rows(cs, eq, k, grown)
        if (grown .and. analyzed) then
          call free_factor(fac)
          analyzed = .false.
        end if
        call holding_rows(cs, held_keys, u, dubar, holds, target)
      end if
      same_u = .false.
      k%val = 0.0_dp
      rhs = 0.0_dp
      do i = 1, size(u)
        if (eq(i) > 0) rhs(eq(i)) = f(i)
      end do
      call assemble_tangent(bodies, u, eq, dubar, k, rhs, bad, descent, theta)
      if (bad(1) /= 0) then
        res%bad = bad
        res%reason = merge('a term of the tangent overflows   ', 'an element has J <= 0             ', bad(2) == 0)
        exit
      end if
      if (present(soft)) then
        soft_now = soft
        if (with_contact) call held_rigids(soft_now)
        call stiffen(soft_now)
      end if
      if (with_contact) call augment_rows(cs, holds, target, eq, dubar, nb, k, rhs)
      ! the pattern is the same at every iterate: one ordering and symbolic
      ! analysis, a numeric factorization per iterate (again after a failure)
      if (.not. analyzed) then
        call analyze_pattern(fac, k%n, k%colptr, k%rowind, ferr)
        if (allocated(ferr)) then
          call move_alloc(ferr, err)
          return
        end if
        analyzed = .true.
      end if
      ! a tangent that is not positive definite (or singular) leaves the
      ! analysis as it was: the next values (the elements' positive parts,
      ! a shorter update) are factorized on it; any other failure analyzes
      ! again
      call factorize_values(fac, k, ferr)
      if (allocated(ferr)) then
        if (.not. ferr%singular) then
          call free_factor(fac)
          analyzed = .false.
        end if
      end if
      if (allocated(ferr)) then
        deallocate(ferr)
        ! strict: a predicted start whose first tangent is not definite is
        ! given up (the caller starts from the last state instead)
        if (it == 0 .and. refuse) then
          res%reason = 'the tangent at the predicted start is not positive definite'
          res%start_refused = .true.
          exit
        end if
        ! not positive definite at this iterate: first each hyperelastic
        ! element's tangent cut to its positive part (a descent direction of
        ! the stored energy, where the consistent tangent has none: far from
        ! the equilibrium, or a compressed section's turn that only the
        ! contacts hold, module augmented_tangent)
        if (.not. descent) then
          descent = .true.
          same_u = .true.
          cycle
        end if
        ! then the last update went past where even that is definite (a
        ! nearly incompressible body's first update from a new load): half
        ! of it again, up to max_halvings times, before the step is given up
        if (allocated(u_prev) .and. back < opts%max_halvings) then
          back = back + 1
          alpha_prev = 0.5_dp * alpha_prev
          u = u_prev + alpha_prev * du_prev
          theta = theta_prev + alpha_prev * dtheta_prev   ! the dilatation state goes back with it
          call measure(u, merit, reached, bad, norm=rnorm)
          if (bad(1) == 0) cycle
        end if
        ! the factorization's own text speaks of rigid modes: here it is the iterate
        res%reason = 'the tangent is not positive definite at the iterate'
        exit
      end if
      back = 0
      descent = .false.
      it = it + 1
      call solve_vector(fac, rhs, du_f, err)
      if (allocated(err)) return
      du = dubar
      do i = 1, size(u)
        if (eq(i) > 0) du(i) = du_f(eq(i))
      end do
      if (with_contact) then
        call contact_correction(cs, fac, u_entry, du, res, err)
        if (allocated(err)) return
        if (len(res%reason) > 0) exit
        ! the rows the next iterate keeps closed: those pressed (lambda > 0),
        ! and with the active-set iteration those its step leaves penetrating
        settled = .true.
        if (active_set) then
          closing = res%lambda(1:res%cs%nrow) > 0.0_dp .or. res%gaps < 0.0_dp
          settled = all(closing .eqv. holds(1:res%cs%nrow))
        else
          closing = res%lambda(1:res%cs%nrow) > 0.0_dp
        end if
        held_keys = pack(row_keys(res%cs), closing)
        ! the step's size against the displacement's: the linearized gaps are
        ! the true ones to its square (an active set still moving is no answer)
        step = maxval(abs(du(1:nb))) / max(maxval(abs(u(1:nb) + du(1:nb))), tiny(1.0_dp))
        if (.not. settled) step = huge(1.0_dp)
        ! the residual with this iterate's contact forces: u has not moved
        ! since the last measure, whose internal forces are u's
        call measure(u, merit, reached, bad, fint_known=.true., norm=rnorm)
      end if
      res%iterations = it
      call element_dilatations(bodies, u, du, j0, dj0, bad)    ! J > 0 at u (measured)
      ! backtracking: J > 0 always; the Armijo decrease once ubar is reached
      alpha = 1.0_dp
      accepted = .false.
      best = huge(1.0_dp)
      do h = 0, opts%max_halvings
        trial = u + alpha * du
        if (h == 0) where (eq == 0) trial = ubar                ! the full step reaches ubar exactly
        call measure(trial, merit_trial, reached, bad, norm=rnorm_trial)
        if (bad(1) == 0) then
          ! on the residual's norm, not on the relative residual: the
          ! latter's scale (the internal forces) moves with the trial, and
          ! falls with the residual when a large volume error is corrected
          if (.not. all(dubar == 0.0_dp) .or. rnorm_trial <= (1.0_dp - 1.0e-4_dp * alpha) * rnorm) then
            accepted = .true.
            exit
          end if
          if (rnorm_trial < best) then
            u_best = trial
            alpha_best = alpha
          end if
          best = min(best, rnorm_trial)
        else
          res%bad = bad
        end if
        alpha = 0.5_dp * alpha
      end do
      if (.not. accepted) then
        if (best == huge(1.0_dp)) then
          res%reason = 'every trial of the line search turns an element inside out (J <= 0)'
          exit
        end if
        ! no decrease found: a stalled iteration (twice running) is given
        ! up, so that the caller starts the sub-increment again without the
        ! predictor, or halves it, instead of spending its iterations here
        stalled = stalled + 1
        if (stalled >= max_stalls) then
          res%reason = 'the line search finds no decrease of the residual'
          exit
        end if
        trial = u_best                                 ! the least residual with J > 0
        alpha = alpha_best
        call measure(trial, merit_trial, reached, bad, norm=rnorm_trial)
      else
        stalled = 0
      end if
      res%bad = 0
      ! the mixed update of the dilatation (module header); u and theta are
      ! where the last update started, so that one going too far can be halved
      theta_prev = theta
      dtheta_prev = alpha * (j0 - theta + dj0)
      theta = theta + dtheta_prev
      u_prev = u
      du_prev = trial - u
      alpha_prev = 1.0_dp
      u = trial
      merit = merit_trial
      rnorm = rnorm_trial
      res%history = [res%history, merit]
    end do
    res%residual = merit
    res%converged = reached .and. merit <= opts%tol .and. len(res%reason) == 0
    if (with_contact) res%converged = res%converged .and. step <= opts%tol
    if (.not. res%converged .and. len(res%reason) == 0) res%reason = 'no convergence in the iterations allowed'
    res%reason = trim(res%reason)
    if (analyzed) call free_factor(fac)
  contains
    !> k(i, i) += soft_share max_j k(j, j) on the soft dofs' equations (times
    !> the size squared on a RIGID's rotation): a body held only by contact,
    !> and a RIGID that its FORCE moves, get a definite tangent; the
    !> residual, and so the converged answer, are untouched.
    subroutine stiffen(mask)
      logical, intent(in) :: mask(:)
      ! 1e-8 left the residual's last digits to round-off in W (it stalled
      ! near 1e-8), 1e-3 slowed the iteration past its limit, on a floating
      ! ring in a groove; 1e-6 converged like a held one
      real(dp), parameter :: soft_share = 1.0e-6_dp
      real(dp) :: big
      integer :: j, p
      if (.not. any(mask)) return
      big = 0.0_dp
      do j = 1, k%n
        do p = k%colptr(j), k%colptr(j + 1) - 1
          if (k%rowind(p) == j) big = max(big, k%val(p))
        end do
      end do
      do j = 1, size(mask)
        if (.not. mask(j) .or. eq(j) == 0) cycle
        do p = k%colptr(eq(j)), k%colptr(eq(j) + 1) - 1
          if (k%rowind(p) == eq(j)) k%val(p) = k%val(p) + soft_share * big * arm(j)**2
        end do
      end do
    end subroutine stiffen

    !> A RIGID whose free dofs the rows that hold the iterate hold all (the
    !> rows' columns on them, the rotation's times the RIGID's size, of full
    !> rank) needs no soft stiffness: K~ is definite along its motion, and
    !> without the soft share the iterate is Newton's own (quadratic).
    subroutine held_rigids(mask)
      logical, intent(inout) :: mask(:)
      real(dp) :: a(3, 3), ev(3), work(64)
      integer :: ip, d, r, p, c, info, m
      logical :: free(3)
      do ip = 1, size(specs)
        if (specs(ip)%rigid == 0) cycle
        d = specs(ip)%shape%dof0
        free = mask(d + 1:d + 3)
        if (.not. any(free)) cycle
        a = 0.0_dp                                     ! sum over the holding rows of v v', v the row on the free dofs
        do r = 1, cs%nrow
          if (.not. holds(r)) cycle
          ev = 0.0_dp
          do p = cs%bptr(r), cs%bptr(r + 1) - 1
            c = cs%cdof(cs%bcol(p)) - d
            if (c >= 1 .and. c <= 3) ev(c) = ev(c) + cs%bval(p) / arm(d + c)
          end do
          where (.not. free) ev = 0.0_dp
          a = a + spread(ev, 2, 3) * spread(ev, 1, 3)
        end do
        m = count(free)
        a(1:m, 1:m) = reshape(pack(a, spread(free, 2, 3) .and. spread(free, 1, 3)), [m, m])
        call dsyev('N', 'U', m, a, 3, ev, work, size(work), info)
        if (info == 0 .and. ev(1) > 1.0e-8_dp * ev(m)) mask(d + 1:d + 3) = .false.
      end do
    end subroutine held_rigids

    !> The rows that hold the iterate at v (augmented_tangent) and their
    !> targets c_i du: a normal row the last iterate's contact problem closed
    !> (keys: its rows with lambda > 0), or, at a sub-increment's first
    !> iterate, one whose gap with the fixed dofs moved is closed or
    !> negative; its target closes its gap, h_i = g_i - c_i v.
    subroutine holding_rows(rows, keys, v, dv, mask, h)
      type(contact_set_t), intent(in) :: rows
      integer(i8), allocatable, intent(in) :: keys(:)
      real(dp), intent(in) :: v(:), dv(:)
      logical, allocatable, intent(out) :: mask(:)
      real(dp), allocatable, intent(out) :: h(:)
      integer(i8), allocatable :: now(:)
      integer :: r, p, d
      real(dp) :: moved
      allocate(mask(rows%nrow + rows%ntan), h(rows%nrow + rows%ntan))
      mask = .false.
      h = 0.0_dp
      now = row_keys(rows)
      do r = 1, rows%nrow
        h(r) = rows%g(r)
        moved = rows%g(r)
        do p = rows%bptr(r), rows%bptr(r + 1) - 1
          d = rows%cdof(rows%bcol(p))
          h(r) = h(r) - rows%bval(p) * v(d)
          moved = moved - rows%bval(p) * (v(d) + dv(d))
        end do
        if (allocated(keys)) then
          mask(r) = any(keys == now(r))
        else
          ! closed to round-off of the row's length
          mask(r) = moved <= 1.0e-10_dp * rows%weight(r)
        end if
      end do
    end subroutine holding_rows

    !> The relative residual at v, whether v's fixed dofs have their values,
    !> and the element with J <= 0 if any.
    subroutine measure(v, rel, at_target, bad_elem, fint_known, norm)
      real(dp), intent(in) :: v(:)
      real(dp), intent(out) :: rel
      logical, intent(out) :: at_target
      integer, intent(out) :: bad_elem(2)
      logical, intent(in), optional :: fint_known     !< fint is v's already (from the last call)
      real(dp), intent(out), optional :: norm         !< the residual's norm itself
      real(dp) :: rf, scale
      integer :: j
      logical :: known
      known = .false.
      if (present(fint_known)) known = fint_known
      bad_elem = 0
      if (.not. known) call internal_force_vector(bodies, v, fint, bad_elem)
      rel = huge(1.0_dp)
      at_target = .false.
      if (bad_elem(1) /= 0) return
      rf = 0.0_dp
      at_target = .true.
      do j = 1, size(v)
        if (eq(j) > 0) then
          rf = rf + ((f(j) + res%fcon(j) - fint(j)) / arm(j))**2
        else
          at_target = at_target .and. ubar(j) == v(j)
        end if
      end do
      ! a RIGID that its FORCE moves: its force and moment over its size
      ! count among the forces (one it moves by FIX has none: its reaction
      ! is no load)
      scale = max(norm2(f(1:nb)), norm2(fint(1:nb)), norm2(res%fcon(1:nb)), &
                  norm2(pack(f(nb + 1:) / arm(nb + 1:), eq(nb + 1:) > 0)), tiny(1.0_dp))
      rel = sqrt(rf) / scale
      if (present(norm)) norm = sqrt(rf)
    end subroutine measure

  !> The contact problem of one Newton iterate: the rows C = [B; T] and the
  !> gaps g(u) of the current configuration (build_moved_contact_set, as a
  !> finite-sliding pair rebuilds them), the iterate's displacement du0 (the
  !> tangent's solve without contact) corrected by the contact forces -C' lam:
  !>     du_f = du0_f - K^-1 C_f' lam,   W = C_f K^-1 C_f',
  !>     qn = g(u) - B du0,   qt = T u_s - T (u + du0),
  !> u_s the state the sub-increment started from, so that the slip of the
  !> sub-increment along the current tangents is ds = -(qt + W_t lam).
  !> Frictionless: the LCP 0 <= lam _|_ qn + W lam >= 0 by Lemke's method;
  !> with friction (tangential rows): the frictional problem of friction_lcp
  !> (Coulomb or Tresca) by its Lemke method.  res%fcon = -C' lam (all dofs),
  !> res%gap and res%complementarity of the normal rows, the rows and their
  !> multipliers, W, q = [qn; qt], the gaps, and with friction each
  !> tangential row's state and slip; res%reason when the problem is not
  !> solved.
  !>   specs (in) the pairs;  fac (in) the tangent's factor
  !>   u_s   (in) (ndof) where the sub-increment started (the slips' origin)
  !>   du    (inout) (ndof) du0 on entry (dubar on the fixed dofs), du on exit
  subroutine contact_correction(cs, fac, u_s, du, res, err)
    type(contact_set_t), intent(in) :: cs
    type(factor_t), intent(in) :: fac
    real(dp), intent(in) :: u_s(:)
    real(dp), intent(inout) :: du(:)
    type(newton_result_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: err
    type(lcp_options_t) :: lopts
    type(lcp_report_t) :: lrep
    type(friction_problem_t) :: fp
    real(dp), allocatable :: c(:,:), y(:,:), w(:,:), q(:), lam(:), gap(:)
    integer :: i, p, d, nrow, nall
    nrow = cs%nrow
    nall = nrow + cs%ntan
    res%fcon = 0.0_dp
    res%gap = 0.0_dp
    res%complementarity = 0.0_dp
    res%cs = cs
    res%lambda = [real(dp) ::]
    res%q = [real(dp) ::]
    res%gaps = [real(dp) ::]
    res%slip = [real(dp) ::]
    res%fstate = [integer ::]
    res%w = reshape([real(dp) ::], [0, 0])
    if (nrow == 0) return
    allocate(c(nfree, 1), y(nfree, nall), q(nall), lam(nall), w(nall, nall))
    do i = 1, nall
      c = 0.0_dp
      q(i) = 0.0_dp
      do p = cs%bptr(i), cs%bptr(i + 1) - 1
        d = cs%cdof(cs%bcol(p))
        if (i <= nrow) then
          q(i) = q(i) - cs%bval(p) * (u(d) + du(d))      ! g(u) - B du0 = g - B (u + du0) (rows B v <= g)
        else
          q(i) = q(i) + cs%bval(p) * (u_s(d) - u(d) - du(d))
        end if
        if (eq(d) > 0) c(eq(d), 1) = c(eq(d), 1) + cs%bval(p)
      end do
      call solve_vector(fac, c(:, 1), y(:, i), err)
      if (allocated(err)) return
    end do
    q(1:nrow) = q(1:nrow) + cs%g(1:nrow)
    ! W = C_f Y, C sparse: a row's few entries times Y's rows
    w = 0.0_dp
    do i = 1, nall
      do p = cs%bptr(i), cs%bptr(i + 1) - 1
        d = cs%cdof(cs%bcol(p))
        if (eq(d) > 0) w(i, :) = w(i, :) + cs%bval(p) * y(eq(d), :)
      end do
    end do
    if (cs%ntan == 0 .and. active_set) then
      call active_set_step(w, q, holds(1:nrow), lam, lrep)
    else if (cs%ntan == 0) then
      call solve_lcp_lemke(w, q, lam, lopts, lrep)
    else
      fp = friction_problem(q(1:nrow), q(nrow + 1:), cs%tan_row, cs%tan_mu, cs%tan_bound)
      lam = 0.0_dp
      call solve_friction_lcp(w, fp, 'lemke', lopts, lam, lrep)
    end if
    if (lrep%info /= 0) then
      res%reason = 'the contact problem of a Newton iterate is not solved (' // lrep%message // ')'
      return
    end if
    do i = 1, size(du)                                 ! du_f -= K^-1 C_f' lam
      if (eq(i) > 0) du(i) = du(i) - dot_product(y(eq(i), :), lam)
    end do
    do i = 1, nall                                     ! f_c = -C' lam
      do p = cs%bptr(i), cs%bptr(i + 1) - 1
        d = cs%cdof(cs%bcol(p))
        res%fcon(d) = res%fcon(d) - cs%bval(p) * lam(i)
      end do
    end do
    gap = q(1:nrow) + matmul(w(1:nrow, :), lam)
    res%gap = minval(gap)
    res%complementarity = maxval(abs(lam(1:nrow) * gap)) / max(maxval(abs(lam(1:nrow))), tiny(1.0_dp))
    if (cs%ntan > 0) then
      res%slip = -(q(nrow + 1:) + matmul(w(nrow + 1:, :), lam))
      deallocate(res%fstate)
      allocate(res%fstate(cs%ntan))
      call friction_state(w, fp, lam, res%fstate, err)
      if (allocated(err)) return
    end if
    res%lambda = lam
    res%q = q
    res%gaps = gap
    call move_alloc(w, res%w)
  end subroutine contact_correction

  !> One semismooth Newton step on the iterate's contact problem (the
  !> primal-dual active set method's, Hintermueller, Ito and Kunisch): the
  !> rows of A closed, W_AA lam_A = -q_A, the others open, lam = 0; no sign
  !> asked of lam_A nor of the other rows' gaps: the next iterate's A is
  !> {lam > 0} and {gap < 0} (the caller), and the iteration has converged
  !> only once A no longer changes.
  !>   w (in) W;  q (in) q;  a (in) A;  lam (out);  rep (out) info /= 0 when W_AA is singular
  subroutine active_set_step(w, q, a, lam, rep)
    real(dp), intent(in) :: w(:,:), q(:)
    logical, intent(in) :: a(:)
    real(dp), intent(out) :: lam(:)
    type(lcp_report_t), intent(out) :: rep
    integer, allocatable :: rows(:), piv(:)
    real(dp), allocatable :: waa(:,:), x(:,:)
    integer :: n, i, info
    lam = 0.0_dp
    rep%info = 0
    rows = pack([(i, i = 1, size(a))], a)
    n = size(rows)
    if (n == 0) return
    waa = w(rows, rows)
    x = reshape(-q(rows), [n, 1])
    allocate(piv(n))
    call dgesv(n, 1, waa, n, piv, x, n, info)
    if (info /= 0) then
      rep%info = 1
      rep%message = 'its active rows are dependent (W_AA singular)'
      return
    end if
    lam(rows) = x(:, 1)
  end subroutine active_set_step
  end subroutine solve_newton_step

  !> ' (body NAME, element E)' when bad names an element, else ''.
  function element_note(bodies, bad) result(s)
    type(body_t), intent(in) :: bodies(:)
    integer, intent(in) :: bad(2)
    character(len=:), allocatable :: s
    s = ''
    if (bad(1) > 0 .and. bad(2) > 0) s = ' (body ' // bodies(bad(1))%name // ', element ' // int_to_str(bad(2)) // ')'
  end function element_note

end module newton_step
