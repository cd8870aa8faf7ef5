!> hyperelastic_step: one load step of a scene with a hyperelastic body, for
!> the load-step loop (load_steps): Newton's method on the whole scene from
!> the last step's state (newton_step, with its cut-back), every CONTACT
!> pair following the bodies, and the step's answer put where the linear
!> steps put theirs (doc/theory.md, "Hyperelastic bodies in finite strain").
!>
!> What a step hands on: its displacement whole (sol%u: it is not the
!> linear recovery's K^-1 (f - C'mu)), the contact rows of its last iterate
!> as prob%cs with their multipliers, gaps and W (sys%w, sys%q: what the
!> contact measures of the linear steps read), its Newton figures (one row
!> of sol%newton per step) and its certificate: the complementarity of the
!> last LCP, and as equilibrium the Newton residual (the contact forces
!> included), both relative.
!>
!> What it does not solve, said before the first step (error_input): a
!> body with a rigid motion that neither FIX nor contact holds.  A body held
!> only by contact, and a RIGID moved by its FORCE, have their free dofs
!> among Newton's equations as soft dofs (newton_step); a step whose loads
!> push a RIGID along a direction that nothing holds has no equilibrium
!> (error_no_equilibrium, as in a linear step).  With friction the step's
!> tangential forces, states and slips (those of its last sub-increment) and
!> the cone's violation in the certificate.
!>
!> Programming interface
!>   check_hyperelastic_scene(prob, err)        a body held only by contact, named
!>   type(newton_history_t)                     what the steps of a history share
!>   solve_hyperelastic_step(prob, sys, t0, kstep, f1, ubar1, u, hist, log, sol, err)
!>                                              the state at t1 from u at t0
module hyperelastic_step
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, set_error, error_input, error_unsolved
  use run_log, only: log_t, say
  use problem, only: problem_t, step_label
  use linear_system, only: system_t
  use step_solution, only: step_solution_t
  use scene, only: step_forces
  use body, only: build_pattern, number_equations
  use sparse_matrix, only: csc_t
  use newton_step, only: newton_options_t, newton_result_t, element_note, start_predicted, start_through
  use newton_increment, only: solve_newton_increment
  use contact_set, only: contact_set_t
  use augmented_tangent, only: cover_dofs
  use held_by_contact, only: split_step_modes
  use mode_support, only: mode_split_t
  use rigid_support, only: rigid_split_t
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: newton_equations, solve_hyperelastic_step

  !> What the steps of a history share: Newton's equations, the soft dofs and
  !> the tangent's pattern (made once, at the first step), and where the last
  !> step started (its increment predicts the next one's).
  type, public :: newton_history_t
    logical :: ready = .false.
    integer, allocatable :: eq(:)              !< (ndof) Newton's equation of each dof, 0 when fixed
    integer :: nfree = 0
    logical, allocatable :: soft(:)            !< (ndof) pinned dofs of bodies held only by contact, free dofs of RIGIDs
    type(csc_t) :: k                           !< the tangent's pattern
    real(dp), allocatable :: u_prior(:)        !< (ndof) where the last step started (unallocated: none)
    integer :: start = start_predicted         !< how the last step's sub-increments started (newton_step)
  end type newton_history_t

contains

  !> The Newton iteration's equations: every dof a FIX does not hold (the
  !> linear runs' pins of a body held only by contact are not supports), and
  !> soft, the pinned dofs of the bodies held only by contact (newton_step
  !> stiffens their diagonal in the linear solves), said in the log; a body
  !> with a rigid motion neither FIX nor contact holds is an input error at
  !> its MATERIAL line.
  subroutine newton_equations(prob, log, eq, nfree, soft, err)
    type(problem_t), intent(in) :: prob
    type(log_t), intent(inout) :: log
    integer, allocatable, intent(out) :: eq(:)
    integer, intent(out) :: nfree
    logical, allocatable, intent(out) :: soft(:)
    type(error_t), allocatable, intent(out) :: err
    integer :: k, b, r
    if (allocated(prob%split%unheld)) then
      if (size(prob%split%unheld, 2) > 0) then
        ! a motion that neither FIX nor contact holds: no tangent, however stiffened, decides it
        b = prob%split%unheld_body(1)
        call set_error(err, prob%deck%file // ':' // int_to_str(prob%deck%bodies(b)%material%line) // ': body ' // &
          prob%deck%bodies(b)%name // ' has a rigid motion that neither FIX nor contact holds, in a scene with a ' // &
          'hyperelastic body: Newton''s method cannot decide it (expected a FIX that holds it, e.g. on a ' // &
          'symmetry line)', error_input)
        return
      end if
    end if
    call number_equations(prob%sc%fixed, eq, nfree)
    allocate(soft(prob%sc%ndof), source=.false.)
    do r = 1, size(prob%sc%rigids)
      associate (d => prob%sc%rigids(r)%dof0)
        if (all(eq(d + 1:d + 3) == 0)) cycle
        soft(d + 1:d + 3) = eq(d + 1:d + 3) > 0
        call say(log, 'newton   RIGID ' // prob%sc%rigids(r)%name // ' is moved by its FORCE along ' // &
          free_words(eq(d + 1:d + 3) > 0) // ': those dofs are among Newton''s equations; in the linear solves ' // &
          'they get a stiffness (a share of the tangent''s largest diagonal, times the RIGID''s size squared ' // &
          'for the rotation) until a closed contact holds them, so that each tangent is definite (the ' // &
          'residual, and so the answer, are those of the exact equilibrium)')
      end associate
    end do
    do k = 1, prob%fl%k
      soft(prob%fl%pin(k)) = .true.
      b = prob%fl%mode_body(k)
      if (count(prob%fl%mode_body(1:k) == b) > 1) cycle
      call say(log, 'newton   body ' // prob%sc%bodies(b)%name // ' is held by contact alone: in the linear ' // &
        'solves its pinned dofs get a stiffness (a share of the tangent''s largest diagonal), so that each ' // &
        'tangent is definite (the residual, and so the answer, are those of the exact equilibrium)')
    end do
  contains
    !> 'ux, uy and rz' of the free ones
    function free_words(free) result(w)
      logical, intent(in) :: free(3)
      character(len=:), allocatable :: w
      character(len=2), parameter :: names(3) = ['ux', 'uy', 'rz']
      integer :: j, m
      w = ''
      m = 0
      do j = 1, 3
        if (.not. free(j)) cycle
        m = m + 1
        if (m == 1) then
          w = names(j)
        else if (m == count(free)) then
          w = w // ' and ' // names(j)
        else
          w = w // ', ' // names(j)
        end if
      end do
    end function free_words
  end subroutine newton_equations

  !> The state at the load point of f1, ubar1 from the one at t0 (module header).
  !>   t0    (in)    where the step starts (u balances its loads)
  !>   kstep (in)    the deck's step (messages, sol%newton)
  !>   f1, ubar1 (in) the loads where it ends (solver basis)
  !>   u     (inout) (ndof) the state at t0; at t1 on exit
  !>   hist  (inout) the history's Newton equations and pattern (made at the first
  !>                 step) and where the last step started; where this one started on exit
  !>   sol   (inout) the step's answer (module header)
  !>   err   (out)   the step not solved (error_unsolved: Newton's reason and
  !>                 the element that stopped it), or a failure of the solve
  subroutine solve_hyperelastic_step(prob, sys, t0, kstep, f1, ubar1, u, hist, log, sol, err)
    type(problem_t), intent(inout) :: prob
    type(system_t), intent(inout) :: sys
    real(dp), intent(in) :: t0, f1(:), ubar1(:)
    integer, intent(in) :: kstep
    real(dp), intent(inout) :: u(:)
    type(newton_history_t), intent(inout) :: hist
    type(log_t), intent(inout) :: log
    type(step_solution_t), intent(inout) :: sol
    type(error_t), allocatable, intent(out) :: err
    type(newton_options_t) :: opts
    type(newton_result_t) :: res
    real(dp), allocatable :: f0(:), ubar0(:), u_start(:)
    integer :: i, n
    logical :: grown
    character(len=:), allocatable :: line
    type(mode_split_t) :: split
    type(rigid_split_t) :: rsplit

    allocate(f0(size(u)), ubar0(size(u)))
    call step_forces(prob%sc, t0, f0, ubar0)
    if (.not. hist%ready) then
      call newton_equations(prob, log, hist%eq, hist%nfree, hist%soft, err)
      if (allocated(err)) return
      call build_pattern(prob%sc%bodies, hist%eq, hist%nfree, hist%k, err)
      if (allocated(err)) return
      do i = 1, size(prob%sc%rigids)                 ! a RIGID's free dofs: no element gives their diagonal
        n = prob%sc%rigids(i)%dof0
        call cover_dofs([n + 1, n + 2, n + 3], hist%eq, hist%k, grown)
      end do
      hist%ready = .true.
    end if
    ! a load along a RIGID's direction that neither its FIX nor the contacts
    ! hold (the rows of the initial configuration) has no equilibrium
    if (prob%rsplit%k > 0) then
      call split_step_modes(prob, kstep, f1, split, rsplit, err)
      if (allocated(err)) return
    end if
    opts%tol = prob%deck%solver%newton_tol
    opts%maxit = prob%deck%solver%newton_maxit
    if (allocated(prob%deck%solver%newton_lcp)) opts%contact = prob%deck%solver%newton_lcp
    u_start = u
    associate (eq => hist%eq, nfree => hist%nfree, k => hist%k, soft => hist%soft)
      if (allocated(hist%u_prior)) then              ! the last step's increment predicts this one's
        call solve_newton_increment(prob%sc%bodies, eq, nfree, k, f0, f1, ubar0, ubar1, opts, u, res, err, &
                                    prob%sc%specs, hist%u_prior, soft, hist%start)
      else
        call solve_newton_increment(prob%sc%bodies, eq, nfree, k, f0, f1, ubar0, ubar1, opts, u, res, err, &
                                    prob%sc%specs, soft=soft)
      end if
    end associate
    if (allocated(err)) then
      err%message = step_label(prob, kstep) // err%message
      return
    end if
    ! a step that started otherwise than the last: said, and the next starts so
    if (allocated(hist%u_prior) .and. res%converged .and. res%start /= hist%start) then
      if (res%start == start_through) then
        line = 'from the prediction, through its tangent that is not positive definite (from the last state ' // &
               'Newton''s method did not converge)'
      else
        line = 'from the last state (from the start the last step''s increment predicts, the tangent was not ' // &
               'positive definite or Newton''s method did not converge)'
      end if
      call say(log, 'newton   ' // step_label(prob, kstep) // 'started ' // line // '; the next steps start so')
      hist%start = res%start
    end if
    call move_alloc(u_start, hist%u_prior)
    ! each halving of the step, as it was made
    if (len(res%notes) > 0) then
      line = res%notes
      do while (len(line) > 0)
        i = index(line, new_line('a'))
        call say(log, 'newton   ' // step_label(prob, kstep) // line(1:i - 1))
        line = line(i + 1:)
      end do
    end if
    if (.not. res%converged) then
      call set_error(err, step_label(prob, kstep) // 'Newton''s method did not converge: ' // res%reason // &
        trim(element_note(prob%sc%bodies, res%bad)) // ', with the increment halved down to 1/' // &
        int_to_str(2**opts%max_cuts) // ' of the step (expected more STEPS, or a motion the mesh can take)', &
        error_unsolved)
      return
    end if
    if (.not. all(ieee_is_finite(u))) then
      call set_error(err, step_label(prob, kstep) // 'the displacement is not finite')
      return
    end if
    call say(log, 'newton   load step ' // int_to_str(kstep) // ' of ' // int_to_str(prob%sc%steps) // ': ' // &
      int_to_str(res%iterations) // ' iterations in ' // int_to_str(res%substeps) // ' increments, residual ' // &
      real_to_str(res%residual) // '; its last residuals:' // history_text(res%history))
    ! the answer where the linear steps put theirs
    sol%step = kstep
    sol%u = u
    sol%method = 'newton'
    sol%iterations = res%iterations
    sol%total_iterations = sol%total_iterations + res%iterations
    sol%residual = res%residual
    sol%cert%equilibrium = res%residual
    sol%cert%cone = 0.0_dp
    sol%cert%complementarity = 0.0_dp
    if (.not. allocated(sol%newton)) allocate(sol%newton(3, 0))
    sol%newton = reshape([sol%newton, real(kstep, dp), real(res%iterations, dp), res%residual], &
                         [3, size(sol%newton, 2) + 1])
    if (allocated(res%lambda)) then
      prob%cs = res%cs
      n = res%cs%nrow
      sol%mu = res%lambda(1:n)
      sol%gap = res%gaps
      sol%q = res%q
      sys%w = res%w
      sys%q = res%q
      if (n > 0) sol%cert%complementarity = res%complementarity / max(maxval(abs(res%q(1:n))), tiny(1.0_dp))
      if (res%cs%ntan > 0) then
        ! friction: the tangential forces, the last sub-increment's slips and
        ! states, and the cone's violation relative to the largest bound
        sol%tau = res%lambda(n + 1:)
        sol%slip = res%slip
        sol%fstate = res%fstate
        sol%cert%cone = cone_violation(res%cs, res%lambda)
      else
        if (allocated(sol%tau)) deallocate(sol%tau, sol%slip, sol%fstate)
      end if
    end if
  end subroutine solve_hyperelastic_step

  !> max_k (|tau_k| - b_k)+ / max_k b_k, b_k = mu_k lambda_trow(k) + bound_k:
  !> how far the friction forces leave Coulomb's (or Tresca's) cone.
  pure real(dp) function cone_violation(cs, lam) result(v)
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: lam(:)
    real(dp) :: b(cs%ntan)
    integer :: k
    do k = 1, cs%ntan
      b(k) = cs%tan_mu(k) * lam(cs%tan_row(k)) + cs%tan_bound(k)
    end do
    v = 0.0_dp
    if (maxval(b) <= 0.0_dp) return
    do k = 1, cs%ntan
      v = max(v, abs(lam(cs%nrow + k)) - b(k))
    end do
    v = v / maxval(b)
  end function cone_violation


  !> ' 1.2e-02 3.4e-05 ...': the relative residuals of the step's last
  !> iterates (quadratic convergence reads as the exponent doubling).
  function history_text(h) result(s)
    real(dp), allocatable, intent(in) :: h(:)
    character(len=:), allocatable :: s
    character(len=12) :: w
    integer :: i, first
    s = ''
    if (.not. allocated(h)) return
    first = max(1, size(h) - 7)
    do i = first, size(h)
      write(w, '(es9.2)') h(i)
      s = s // ' ' // trim(adjustl(w))
    end do
  end function history_text

end module hyperelastic_step
