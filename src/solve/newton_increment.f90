!> newton_increment: one load step of a scene with hyperelastic bodies,
!> walked in sub-increments of Newton solves (module newton_step), halving
!> what fails (doc/theory.md, "Finite strain: hyperelastic bodies").  Its
!> own job beside newton_step's one solve: where each solve starts and how
!> much of the step it takes.
!>
!> Predictor (u_prior; solve_newton_step's guess and strict).
!> A sub-increment starts from the last one's displacement per unit of load
!> factor times its own (the secant predictor), its fixed dofs at their
!> values, unless an element is inside out there; when the predicted start
!> fails, the same sub-increment is solved again from where it started
!> before it is halved.  Three starts (start_*): the prediction, given up at
!> once when its first tangent is not definite (an extrapolated contact
!> zone can make it so, on the O-ring); the last state; the prediction
!> again, through that indefinite tangent (the elements' positive parts; on
!> a section held by its hoop it is the start that converges).  A failed
!> start tries the next untried one before the increment is halved, and the
!> one that converged is where the next sub-increment, and through
!> res%start the caller's next step, begin.
!>
!> Cut-back.  A load step from the loads (f0,
!> ubar0) to (f1, ubar1) is walked in sub-increments of the load factor t,
!> the loads linear in t: a sub-increment that fails is halved (u restored
!> to where it started), and after a success the next one may double again,
!> up to what is left of the step.  A sub-increment below 2^-max_cuts of the
!> step ends the step unconverged, with the last failure's reason and
!> element.  Each halving is written as a line into the result's notes for
!> the caller's log.  Why halving cures: the first iterate of a step moves
!> the prescribed values by the linear tangent, whose volume error is of
!> the order of the increment squared; times K of a nearly incompressible
!> body it becomes a pressure whose initial-stress stiffness makes the next
!> tangent indefinite (not factorizable) when the increment is too large.
!>
!> Programming interface
!>   solve_newton_increment(bodies, eq, nfree, k, f0, f1, ubar0, ubar1, opts, u, res, err [, specs]
!>                          [, u_prior] [, soft] [, start])
!>        from the loads (f0, ubar0) at u to (f1, ubar1), halving what fails
module newton_increment
  use kinds, only: dp
  use errors, only: error_t
  use strings, only: real_to_str
  use body, only: body_t
  use contact_set, only: pair_spec_t
  use sparse_matrix, only: csc_t
  use newton_step, only: newton_options_t, newton_result_t, solve_newton_step, element_note, start_predicted, &
                         start_plain, start_through
  implicit none
  private
  public :: solve_newton_increment

contains

  !> A load step from (f0, ubar0) to (f1, ubar1) with cut-back (module header).
  !>   f0, f1, ubar0, ubar1 (in) (ndof) the loads at its start (u balances them) and end
  !>   u    (inout) (ndof) the state at the start; on exit at the end (converged) or
  !>                where the last sub-increment that converged left it
  !>   res  (out)   converged, the iterations summed over the sub-increments, the
  !>                last residual, cuts, substeps, notes; reason and bad of the
  !>                failure that ended it
  !>   u_prior (in, optional) (ndof) the state the previous load step started from:
  !>                its increment u - u_prior predicts this step's first one
  !>   start  (in, optional) start_*: how a predicted sub-increment starts first
  !>                (default start_predicted); res%start: how the last one did
  !>   other arguments as solve_newton_step
  subroutine solve_newton_increment(bodies, eq, nfree, k, f0, f1, ubar0, ubar1, opts, u, res, err, specs, u_prior, &
                                    soft, start)
    type(body_t), intent(in) :: bodies(:)
    integer, intent(in) :: eq(:), nfree
    type(csc_t), intent(inout) :: k
    real(dp), intent(in) :: f0(:), f1(:), ubar0(:), ubar1(:)
    type(newton_options_t), intent(in) :: opts
    real(dp), intent(inout) :: u(:)
    type(newton_result_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: err
    type(pair_spec_t), intent(in), optional :: specs(:)
    real(dp), intent(in), optional :: u_prior(:)
    logical, intent(in), optional :: soft(:)
    integer, intent(in), optional :: start
    type(newton_result_t) :: sub
    real(dp), allocatable :: u_start(:), rate(:), guess(:), ubar_t(:)
    real(dp) :: t, dt, t1
    real(dp), parameter :: full = 1.0_dp
    integer :: kind, pref
    logical :: tried(start_predicted:start_through)

    res%notes = ''
    res%reason = ''
    allocate(res%history(0))
    ! the secant predictor: the last increment's displacement per unit of
    ! load factor, its volume change already that of the body's response
    ! (a first iterate from u alone moves the prescribed values through the
    ! linear tangent, whose volume error times K can make the next tangent
    ! indefinite in a nearly incompressible body)
    if (present(u_prior)) rate = u - u_prior
    pref = start_predicted                           ! the start a sub-increment with a prediction tries first
    if (present(start)) pref = start
    kind = merge(pref, start_plain, allocated(rate))
    tried = .false.
    t = 0.0_dp
    dt = full
    do while (t < full)
      dt = min(dt, full - t)                         ! a halving then always shortens the attempt
      t1 = t + dt
      if (full - t1 <= 1.0e-12_dp) t1 = full
      u_start = u
      ubar_t = (1 - t1) * ubar0 + t1 * ubar1
      tried(kind) = .true.
      if (kind /= start_plain) then
        guess = u + (t1 - t) * rate
        where (eq == 0) guess = ubar_t
        call solve_newton_step(bodies, eq, nfree, k, (1 - t1) * f0 + t1 * f1, ubar_t, opts, u, sub, err, specs, guess, &
                               soft, strict=kind == start_predicted)
        ! a strict start that iterated is a start through: not worth another
        ! try; one whose guess had an element inside out was a plain start
        if (kind == start_predicted .and. .not. sub%start_refused) tried(start_through) = .true.
        if (.not. sub%from_guess) tried = .true.
      else
        call solve_newton_step(bodies, eq, nfree, k, (1 - t1) * f0 + t1 * f1, ubar_t, opts, u, sub, err, specs, &
                               soft=soft)
      end if
      if (allocated(err)) return
      res%iterations = res%iterations + sub%iterations
      res%residual = sub%residual
      if (sub%converged) then
        res%substeps = res%substeps + 1
        res%history = sub%history                    ! the last sub-increment's (its convergence)
        res%fcon = sub%fcon
        res%gap = sub%gap
        res%complementarity = sub%complementarity
        if (allocated(sub%lambda)) then                ! the last iterate's contact problem
          res%cs = sub%cs
          res%lambda = sub%lambda
          res%w = sub%w
          res%q = sub%q
          res%gaps = sub%gaps
          if (allocated(sub%fstate)) then
            res%fstate = sub%fstate
            res%slip = sub%slip
          end if
        end if
        if (allocated(rate)) pref = kind             ! the next sub-increment starts as this one did
        res%start = pref
        rate = (u - u_start) / (t1 - t)
        kind = pref
        tried = .false.
        t = t1
        dt = min(2 * dt, full)                       ! the next sub-increment may be larger again
        cycle
      end if
      u = u_start
      ! the other starts of the same increment, before it is halved: from the
      ! last state, then through the prediction's indefinite tangent
      if (allocated(rate)) then
        if (.not. tried(start_plain)) then
          kind = start_plain
          cycle
        else if (.not. tried(start_through)) then
          kind = start_through
          cycle
        end if
      end if
      kind = merge(pref, start_plain, allocated(rate))
      tried = .false.
      res%bad = sub%bad
      res%reason = sub%reason
      if (dt <= 2.0_dp**(-opts%max_cuts)) return      ! cutting no longer helps
      dt = 0.5_dp * dt
      res%cuts = res%cuts + 1
      res%notes = res%notes // 'Newton: ' // sub%reason // trim(element_note(bodies, sub%bad)) // &
                  ' at load factor ' // real_to_str(t1) // ' of the step: the increment is halved to ' // &
                  real_to_str(dt) // new_line('a')
    end do
    res%converged = .true.
    res%reason = ''
    res%bad = 0
  end subroutine solve_newton_increment

end module newton_increment
