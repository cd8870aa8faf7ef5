!> held_by_contact: the bodies and RIGIDs held only by contact (free rigid
!> modes, free directions under FORCE): the checks before the solve, a load
!> step's splits of their modes, and the diagnoses when no equilibrium
!> exists.  A body whose FIX leaves a mode free must be in a CONTACT (an
!> input error), a load along what nothing holds has no equilibrium, and a
!> FORCE or a load that pulls a body or RIGID off its contacts is named with
!> its direction.
!>
!> Why it exists: the messages that say which body, RIGID and direction a
!> failed equilibrium is about, shared by every kind of load step.  Nothing
!> here stops the run: input errors go to the caller's diag_t, the absence
!> of an equilibrium returns an error_t of category error_no_equilibrium.
!>
!> Programming interface
!>   check_floating_bodies(prob, diag)    a body with a free rigid mode must be in a CONTACT
!>   check_floating_friction_solver(prob, diag)  lcp=pgs refused for friction on what contact alone holds
!>   split_step_modes(prob, kstep, fk, split, rsplit, err)  a step's splits of the free modes under
!>                                        its loads fk, each checked for loads along what nothing holds
!>   check_unheld_loads(prob, split, rsplit, kstep, err)    no load along what nothing holds
!>   diagnose_pulled(prob, split, rsplit, kstep, err)       what a load pulls off its contacts
!>   floating_no_equilibrium(prob, split, rsplit, unbalanced, cause)  a friction step's diagnosis
!>   floating_names(prob)                 the bodies and RIGIDs held only by contact, for messages
!>   unheld_summary(prob, split, j)       the summary line of unheld mode j
module held_by_contact
  use kinds, only: dp
  use strings, only: exact_to_str, real_to_str
  use errors, only: diag_t, add_error, error_t, set_error, error_no_equilibrium
  use problem, only: problem_t, step_label
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke
  use rigid_modes, only: mode_name, motion_name, describe_motion
  use rigid_support, only: rigid_split_t, rigid_direction, pulled_rigid, split_rigid_modes
  use mode_support, only: mode_split_t, split_free_modes
  implicit none
  private
  public :: check_floating_bodies, check_floating_friction_solver, split_step_modes, check_unheld_loads, &
            diagnose_pulled, floating_no_equilibrium, floating_names, unheld_summary

contains

  !> A body whose FIX leaves a rigid mode free must be held by a CONTACT.
  !>   diag (inout) an input error at the BODY line of each body that is not
  subroutine check_floating_bodies(prob, diag)
    type(problem_t), intent(in) :: prob
    type(diag_t), intent(inout) :: diag
    integer :: j, ip, b
    logical :: in_contact
    do j = 1, prob%fl%k
      b = prob%fl%mode_body(j)
      in_contact = .false.
      do ip = 1, size(prob%sc%specs)
        if (prob%sc%specs(ip)%slave_body == b .or. prob%sc%specs(ip)%master_body == b) in_contact = .true.
      end do
      if (in_contact) cycle
      if (size(prob%deck%bodies(b)%springs) == 0) then
        call add_error(diag, prob%deck%file, prob%deck%bodies(b)%line, 'body "' // prob%sc%bodies(b)%name // &
          '": its FIX statements leave a rigid-body mode free (' // mode_name(prob%fl, j) // ') and no CONTACT holds ' // &
          'the body (a FIX that blocks it, or a CONTACT, expected)')
      else
        call add_error(diag, prob%deck%file, prob%deck%bodies(b)%line, 'body "' // prob%sc%bodies(b)%name // &
          '": its FIX and SPRING statements leave a rigid-body mode free (' // mode_name(prob%fl, j) // ') and no ' // &
          'CONTACT holds the body (a FIX or a SPRING that resists it, or a CONTACT, expected)')
      end if
    end do
  end subroutine check_floating_bodies

  !> A body or RIGID held only by contact in a scene with friction: the
  !> friction LCP with its mode amplitudes is solved by Lemke
  !> (friction_modes); lcp=pgs is an input error at the SOLVER line.
  subroutine check_floating_friction_solver(prob, diag)
    type(problem_t), intent(in) :: prob
    type(diag_t), intent(inout) :: diag
    if (prob%cs%ntan == 0 .or. prob%deck%solver%lcp /= 'pgs') return
    if (size(prob%split%held, 2) == 0 .and. size(prob%rsplit%held, 2) > 0) then
      call add_error(diag, prob%deck%file, prob%deck%solver%line, 'lcp=pgs with friction on a RIGID under FORCE is ' // &
        'not supported (expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
      return
    end if
    if (size(prob%split%held, 2) == 0) return
    call add_error(diag, prob%deck%file, prob%deck%solver%line, &
      'lcp=pgs with friction on a body held only by contact (body "' // &
      prob%sc%bodies(prob%fl%mode_body(1))%name // '": ' // mode_name(prob%fl, 1) // ' not held by FIX) is not ' // &
      'supported (expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
  end subroutine check_floating_friction_solver

  !> A load step's splits of the free modes, the bodies' (H = B R, their
  !> held and unheld combinations) and the RIGIDs', for the step's loads fk
  !> and the current rows, each checked: no load along what nothing holds.
  !>   kstep  (in)  the load step (for the message)
  !>   fk     (in)  (ndof) the step's loads
  !>   split  (out) the bodies' split (empty when no body floats)
  !>   rsplit (out) the RIGIDs' split (the problem's when no RIGID direction is free)
  !>   err    (out) error_no_equilibrium: a load along what nothing holds
  subroutine split_step_modes(prob, kstep, fk, split, rsplit, err)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    real(dp), intent(in) :: fk(:)
    type(mode_split_t), intent(out) :: split
    type(rigid_split_t), intent(out) :: rsplit
    type(error_t), allocatable, intent(out) :: err
    if (prob%fl%k > 0) then
      call split_free_modes(prob%cs, prob%sc%bodies, prob%fl, fk, split)
    else
      split = prob%split
    end if
    if (prob%rsplit%k > 0) then
      call split_rigid_modes(prob%cs, prob%sc%rigids, prob%sc%fixed, fk, rsplit)
    else
      rsplit = prob%rsplit
    end if
    call check_unheld_loads(prob, split, rsplit, kstep, err)
  end subroutine split_step_modes

  !> A rigid motion that neither FIX nor contact holds must carry no load,
  !> nor a RIGID's free direction that contact does not hold: else no static
  !> equilibrium exists (error_no_equilibrium naming the body or RIGID and
  !> the motion); an unloaded one keeps amplitude 0.
  !>   kstep (in) the load step (0: before the solve, no step named)
  subroutine check_unheld_loads(prob, split, rsplit, kstep, err)
    type(problem_t), intent(in) :: prob
    type(mode_split_t), intent(in) :: split
    type(rigid_split_t), intent(in) :: rsplit
    integer, intent(in) :: kstep
    type(error_t), allocatable, intent(out) :: err
    integer :: j
    character(len=16) :: buf
    do j = 1, size(split%unheld, 2)
      if (.not. split%loaded(j)) cycle
      write(buf, '(es10.3)') split%load(j)
      call set_error(err, prefix(prob, kstep) // 'no equilibrium: body "' // &
        prob%sc%bodies(split%unheld_body(j))%name // '" is loaded along a rigid mode (' // &
        motion_name(prob%fl, split%unheld(:, j)) // ') that neither FIX nor contact holds ' // &
        '(frictionless contact holds only normal to the contact surface; load along it ' // trim(adjustl(buf)) // &
        ' of the loads'' scale)', error_no_equilibrium)
      return
    end do
    if (rsplit%k == 0) return
    do j = 1, size(rsplit%unheld, 2)
      if (.not. rsplit%loaded(j)) cycle
      call set_error(err, prefix(prob, kstep) // 'no equilibrium: RIGID "' // &
        prob%sc%rigids(rsplit%unheld_owner(j))%name // '" is loaded along a direction (' // &
        rigid_direction(rsplit, rsplit%unheld(:, j)) // ') that neither its FIX nor its contacts hold ' // &
        '(frictionless contact pushes only normal to the contact surface; expected FIX on that direction, or a ' // &
        'load the contact normals can balance)', error_no_equilibrium)
      return
    end do
  end subroutine check_unheld_loads

  !> The frictionless contact problem of a step has no solution (Lemke's ray):
  !> when some load pulls a RIGID or a body held only by contact off its
  !> contacts, say which and which way (error_no_equilibrium); err stays
  !> unallocated when neither explains it.
  !>   For a RIGID: the part (fx, fy, m) of its FORCE that no contact
  !>   pressure balances (rigid_support's pulled_rigid).  For a body: the
  !>   closest balance of its loads by contact forces alone, min |Hh' mu - eh|
  !>   over mu >= 0 (the test of contact_lcp, a nonnegative least squares
  !>   solved as the LCP of its normal equations), leaves the unbalanced load
  !>   r = eh - Hh' mu; the body that carries most of it and the motion along
  !>   it are named, as for a frictional step.
  subroutine diagnose_pulled(prob, split, rsplit, kstep, err)
    type(problem_t), intent(in) :: prob
    type(mode_split_t), intent(in) :: split
    type(rigid_split_t), intent(in) :: rsplit
    integer, intent(in) :: kstep
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: hh(:,:), eh(:), mu(:), r(:), c(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: owner
    real(dp) :: resid(3)
    character(len=80) :: buf
    if (rsplit%k > 0) then
      call pulled_rigid(rsplit, owner, resid)
      if (owner > 0) then
        write(buf, '(a,es10.3,a,es10.3,a,es10.3,a)') '(', resid(1), ', ', resid(2), ', ', resid(3), ')'
        call set_error(err, prefix(prob, kstep) // 'no equilibrium: the FORCE on RIGID "' // &
          prob%sc%rigids(owner)%name // '" pulls it away from its contacts: contact can only push, and the part ' // &
          '(fx, fy, m) = ' // trim(buf) // ' of its load cannot be balanced by any contact pressure (expected a ' // &
          'FORCE that presses the obstacle on the slave boundary)', error_no_equilibrium)
        return
      end if
    end if
    if (prob%fl%k == 0 .or. size(split%held, 2) == 0) return
    hh = matmul(split%h(1:prob%cs%nrow, :), split%held)    ! Hh = H V_h on the normal rows
    eh = matmul(transpose(split%held), split%e)             ! eh = V_h' e
    allocate(mu(prob%cs%nrow), source=0.0_dp)
    call solve_lcp_lemke(matmul(hh, transpose(hh)), -matmul(hh, eh), mu, opts, rep)
    if (rep%info /= 0) return
    r = eh - matmul(transpose(hh), mu)
    if (norm2(r) <= 1.0e-8_dp * norm2(eh)) return        ! the bodies balance: a RIGID, or the coupling of several
    call largest_owner(split%held, r, prob%fl%mode_body, c, owner)
    call set_error(err, prefix(prob, kstep) // no_equilibrium_text('contact', '', 'the loads pull body "' // &
      prob%sc%bodies(owner)%name // '"', motion_name(prob%fl, c), 'the loads'), error_no_equilibrium)
  end subroutine diagnose_pulled

  !> The diagnosis of a frictional step without equilibrium from the unbalanced
  !> load along the held combinations (the bodies' modes, then the RIGIDs'
  !> free directions): the body or the RIGID that carries most of it, and
  !> the motion of that one alone.
  !>   unbalanced (in) e - H'z at the closest balance, along the held combinations
  !>   cause      (in) 'friction' (the cone is too small) or 'contact'
  !>   capacity   (in) with cause 'friction', the capacity C of friction_modes
  !>              along the unbalanced load (0: not known)
  function floating_no_equilibrium(prob, split, rsplit, unbalanced, cause, capacity) result(t)
    type(problem_t), intent(in) :: prob
    type(mode_split_t), intent(in) :: split
    type(rigid_split_t), intent(in) :: rsplit
    real(dp), intent(in) :: unbalanced(:), capacity
    character(len=*), intent(in) :: cause
    character(len=:), allocatable :: t
    real(dp), allocatable :: c(:)
    real(dp) :: a(3), size_u
    integer :: kb, owner, j
    logical :: on_body
    kb = size(split%held, 2)
    size_u = norm2(unbalanced)
    on_body = .false.
    if (kb > 0) on_body = maxval(abs(unbalanced(1:kb))) >= maxval(abs(unbalanced(kb + 1:)), mask=.true.) .or. &
                          size(unbalanced) == kb
    ! a: the motion along unit u in (u_x, u_y, rotation) of one unit of the
    ! combination's amplitude, to turn C (per unit amplitude) into a force
    ! or a moment
    a = 0.0_dp
    if (on_body) then
      call largest_owner(split%held, unbalanced(1:kb), prob%fl%mode_body, c, owner)
      do j = 1, prob%fl%k
        a = a + c(j) / size_u * prob%fl%coef(:, j) / prob%fl%norm(j)
      end do
      if (a(3) /= 0.0_dp) a(3) = a(3) / prob%fl%length(maxloc(abs(c), dim=1))   ! r3's rotation is theta L
      t = no_equilibrium_text(cause, 'the loads on body "' // prob%sc%bodies(owner)%name // '" exceed', &
                              'the loads pull body "' // prob%sc%bodies(owner)%name // '"', motion_name(prob%fl, c), &
                              'the loads', capacity_text(capacity, a))
    else
      call largest_owner(rsplit%held, unbalanced(kb + 1:), rsplit%owner, c, owner)
      do j = 1, rsplit%k
        a(rsplit%comp(j)) = a(rsplit%comp(j)) + c(j) / size_u
      end do
      t = no_equilibrium_text(cause, 'the FORCE on RIGID "' // prob%sc%rigids(owner)%name // '" exceeds', &
                              'the FORCE on RIGID "' // prob%sc%rigids(owner)%name // '" pulls it', &
                              rigid_direction(rsplit, c), 'its load', capacity_text(capacity, a))
    end if
  end function floating_no_equilibrium

  !> The largest load friction holds along the motion, in words: ', a force
  !> of about F' (a translation) or ', a moment of about M' (a rotation);
  !> '' when it is not known.  The capacity C is a generalized force along a
  !> unit combination of the modes, whose motion is a: C = F |a_xy| for a
  !> translation, M a_theta for a rotation.
  !>   capacity (in) C, 0 when not known;  a (in) (3) u_x, u_y, theta of the motion
  function capacity_text(capacity, a) result(t)
    real(dp), intent(in) :: capacity, a(3)
    character(len=:), allocatable :: t
    t = ''
    if (.not. capacity > 0.0_dp) return
    if (abs(a(3)) * 1.0e8_dp <= norm2(a(1:2))) then
      t = ', a force of about ' // real_to_str(capacity / norm2(a(1:2)))
    else if (norm2(a(1:2)) == 0.0_dp) then
      t = ', a moment of about ' // real_to_str(capacity / abs(a(3)))
    end if
  end function capacity_text

  !> The unbalanced load in the modes' (or directions') amplitudes, c = H u,
  !> kept on the owner (body or RIGID) with the largest amplitude.
  !>   held     (in)  (k, m) the held combinations
  !>   u        (in)  (m) the unbalanced load along them
  !>   owner_of (in)  (k) the owner of each mode or direction
  !>   c        (out) (k) H u on that owner's modes, 0 on the others
  !>   owner    (out) that owner
  subroutine largest_owner(held, u, owner_of, c, owner)
    real(dp), intent(in) :: held(:,:), u(:)
    integer, intent(in) :: owner_of(:)
    real(dp), allocatable, intent(out) :: c(:)
    integer, intent(out) :: owner
    c = matmul(held, u)
    owner = owner_of(maxloc(abs(c), dim=1))
    c = merge(c, 0.0_dp, owner_of == owner)
  end subroutine largest_owner

  !> The sentence of a step without static equilibrium, one per cause.
  !>   cause  (in) 'friction' (the friction cone is too small) or 'contact'
  !>          (the load pulls away from the contacts)
  !>   held   (in) who exceeds the cone, with the verb: 'the loads on body "A" exceed'
  !>   pulled (in) who is pulled off, with the verb: 'the loads pull body "A"'
  !>   motion (in) the motion it would make
  !>   load   (in) what is not balanced: 'the loads', 'its load'
  !>   limit  (in, optional) the largest load friction holds, capacity_text
  function no_equilibrium_text(cause, held, pulled, motion, load, limit) result(t)
    character(len=*), intent(in) :: cause, held, pulled, motion, load
    character(len=*), intent(in), optional :: limit
    character(len=:), allocatable :: t
    if (cause == 'friction') then
      t = 'no equilibrium: ' // held // ' what friction can hold'
      if (present(limit)) t = t // limit
      t = t // ': it would move by ' // motion // &
        ' (the contact forces within the friction cone cannot balance ' // load // ')'
    else
      t = 'no equilibrium: ' // pulled // ' away from its contacts: it would move by ' // motion // &
        ' (no contact force balances ' // load // ', whatever the friction)'
    end if
  end function no_equilibrium_text

  !> Who is held only by contact, for messages: each body with a free rigid
  !> mode (body "A"), then each RIGID with a free direction (RIGID "B"),
  !> comma-separated.  A scene whose only floating part is a RIGID under
  !> FORCE has no floating body: the RIGID must still be named.
  function floating_names(prob) result(t)
    type(problem_t), intent(in) :: prob
    character(len=:), allocatable :: t
    integer :: b, r
    t = ''
    do b = 1, size(prob%sc%bodies)
      if (.not. any(prob%fl%mode_body == b)) cycle
      if (len(t) > 0) t = t // ', '
      t = t // 'body "' // prob%sc%bodies(b)%name // '"'
    end do
    do r = 1, size(prob%sc%rigids)
      if (prob%rsplit%k == 0) exit
      if (.not. any(prob%rsplit%owner == r)) cycle
      if (len(t) > 0) t = t // ', '
      t = t // 'RIGID "' // prob%sc%rigids(r)%name // '"'
    end do
  end function floating_names

  !> 'BODY KIND X Y' of unheld combination j for the summary: KIND rotation
  !> (X Y its centre) or translation (X Y its unit direction).
  function unheld_summary(prob, split, j) result(t)
    type(problem_t), intent(in) :: prob
    type(mode_split_t), intent(in) :: split
    integer, intent(in) :: j
    character(len=:), allocatable :: t, kind
    real(dp) :: point(2)
    call describe_motion(prob%fl, split%unheld(:, j), kind, point)
    t = prob%sc%bodies(split%unheld_body(j))%name // ' ' // kind // ' ' // exact_to_str(point(1)) // ' ' // &
      exact_to_str(point(2))
  end function unheld_summary

  !> The step's label, or none before the solve (kstep 0).
  function prefix(prob, kstep) result(t)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep
    character(len=:), allocatable :: t
    t = ''
    if (kstep > 0) t = step_label(prob, kstep)
  end function prefix

end module held_by_contact
