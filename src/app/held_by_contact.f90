!> held_by_contact: the bodies and RIGIDs that only contact holds, and the
!> diagnoses when it cannot: a body with a free rigid mode must be in a
!> CONTACT (exit 2), lcp=pgs is refused for friction on such bodies (exit 2),
!> no load may act along a motion nothing holds (exit 1), and a FORCE or a
!> load that pulls a body or RIGID off its contacts is named with its
!> direction (exit 1).
!>
!> Why it exists: the messages that say which body, RIGID and direction a
!> failed equilibrium is about, shared by every kind of contact step
!> (contact_step, finite_sliding, contact_solve).  Who may use it: the
!> program's step modules (run_state's list).
!>
!> Programming interface
!>   check_floating_bodies(run)  a body with a free rigid mode must be in a CONTACT (exit 2)
!>   check_floating_friction_solver(run)  lcp=pgs refused for friction on bodies held only by contact (exit 2)
!>   check_unheld_loads(run)     no load along a rigid mode nothing holds (exit 1)
!>   check_unheld_rigid_loads(run)  no load along a RIGID's direction nothing holds (exit 1)
!>   split_step_modes(run, fk)   a step's splits of the free modes (bodies, RIGIDs) under its loads fk,
!>                               each checked for loads along what nothing holds
!>   diagnose_pulled_rigid(run), diagnose_pulled_body(run)  exit 1 naming what pulls off its contacts
!>   floating_no_equilibrium(run, unbalanced, cause)  the text of a friction step without equilibrium
!>   floating_names(run)         the bodies and RIGIDs held only by contact, for messages
!>   unheld_summary(run, j)      the summary line of unheld mode j
!>   step_prefix(run)            'load step k of n: ' in stepped runs, else ''
module held_by_contact
  use kinds, only: dp
  use errors, only: add_error
  use exits, only: stop_input_errors, fail_numerical
  use run_state, only: run_t
  use lcp_solvers, only: lcp_options_t, lcp_report_t, solve_lcp_lemke
  use rigid_modes, only: mode_name, motion_name, describe_motion
  use rigid_support, only: rigid_direction, pulled_rigid, split_rigid_modes
  use mode_support, only: split_free_modes
  implicit none
  private
  public :: check_floating_bodies, check_floating_friction_solver, check_unheld_loads, split_step_modes, &
            check_unheld_rigid_loads, diagnose_pulled_rigid, diagnose_pulled_body, floating_no_equilibrium, &
            floating_names, unheld_summary, step_prefix

contains

  !> A body whose FIX leaves a rigid mode free must be held by a CONTACT.
  subroutine check_floating_bodies(run)
    type(run_t), intent(inout) :: run
    integer :: j, ip, b
    logical :: in_contact
    do j = 1, run%fl%k
      b = run%fl%mode_body(j)
      in_contact = .false.
      do ip = 1, size(run%sc%specs)
        if (run%sc%specs(ip)%slave_body == b .or. run%sc%specs(ip)%master_body == b) in_contact = .true.
      end do
      if (.not. in_contact .and. size(run%deck%bodies(b)%springs) == 0) call add_error(run%diag, run%deck%file, &
        run%deck%bodies(b)%line, 'body "' // run%sc%bodies(b)%name // &
        '": its FIX statements leave a rigid-body mode free (' // mode_name(run%fl, j) // ') and no CONTACT holds ' // &
        'the body (a FIX that blocks it, or a CONTACT, expected)')
      if (.not. in_contact .and. size(run%deck%bodies(b)%springs) > 0) call add_error(run%diag, run%deck%file, &
        run%deck%bodies(b)%line, 'body "' // run%sc%bodies(b)%name // &
        '": its FIX and SPRING statements leave a rigid-body mode free (' // mode_name(run%fl, j) // ') and no ' // &
        'CONTACT holds the body (a FIX or a SPRING that resists it, or a CONTACT, expected)')
    end do
    call stop_input_errors(run%diag)
  end subroutine check_floating_bodies

  !> A body held only by contact in a scene with friction: the friction LCP
  !> with its mode amplitudes is solved by Lemke (friction_modes); lcp=pgs
  !> is refused at the SOLVER line (exit 2).
  subroutine check_floating_friction_solver(run)
    type(run_t), intent(inout) :: run
    if (run%cs%ntan == 0 .or. run%deck%solver%lcp /= 'pgs') return
    if (size(run%split%held, 2) == 0 .and. size(run%rsplit%held, 2) > 0) then
      call add_error(run%diag, run%deck%file, run%deck%solver%line, 'lcp=pgs with friction on a RIGID under FORCE is not ' // &
        'supported (expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
      call stop_input_errors(run%diag)
    end if
    if (size(run%split%held, 2) == 0) return
    call add_error(run%diag, run%deck%file, run%deck%solver%line, &
      'lcp=pgs with friction on a body held only by contact (body "' // &
      run%sc%bodies(run%fl%mode_body(1))%name // '": ' // mode_name(run%fl, 1) // ' not held by FIX) is not supported ' // &
      '(expected lcp=lemke or lcp=auto, which solve it by Lemke''s method)')
    call stop_input_errors(run%diag)
  end subroutine check_floating_friction_solver

  !> A load step's splits of the free modes, the bodies' (H = B R, their
  !> held and unheld combinations) and the RIGIDs', for the step's loads fk
  !> and the current rows, each checked: no load along what nothing holds.
  subroutine split_step_modes(run, fk)
    type(run_t), intent(inout) :: run
    real(dp), intent(in) :: fk(:)
    if (run%fl%k > 0) then
      call split_free_modes(run%cs, run%sc%bodies, run%fl, fk, run%split)
      call check_unheld_loads(run)
    end if
    if (run%rsplit%k > 0) then
      call split_rigid_modes(run%cs, run%sc%rigids, run%sc%fixed, fk, run%rsplit)
      call check_unheld_rigid_loads(run)
    end if
  end subroutine split_step_modes

  !> A rigid motion that neither FIX nor contact holds must carry no load:
  !> else no static equilibrium exists (exit 1, naming the body and motion).
  subroutine check_unheld_loads(run)
    type(run_t), intent(inout) :: run
    integer :: j
    character(len=16) :: buf
    do j = 1, size(run%split%unheld, 2)
      if (.not. run%split%loaded(j)) cycle
      write(buf, '(es10.3)') run%split%load(j)
      call fail_numerical(step_prefix(run) // 'no equilibrium: body "' // run%sc%bodies(run%split%unheld_body(j))%name // &
        '" is loaded along ' // &
        'a rigid mode (' // motion_name(run%fl, run%split%unheld(:, j)) // ') that neither FIX nor contact holds ' // &
        '(frictionless contact holds only normal to the contact surface; load along it ' // trim(adjustl(buf)) // &
        ' of the loads'' scale)')
    end do
  end subroutine check_unheld_loads

  !> A RIGID's free direction that contact does not hold must carry no load
  !> (exit 1 naming the obstacle and the direction); an unloaded one keeps 0.
  subroutine check_unheld_rigid_loads(run)
    type(run_t), intent(inout) :: run
    integer :: j
    do j = 1, size(run%rsplit%unheld, 2)
      if (.not. run%rsplit%loaded(j)) cycle
      call fail_numerical(step_prefix(run) // 'no equilibrium: RIGID "' // run%sc%rigids(run%rsplit%unheld_owner(j))%name // &
        '" is loaded along a direction (' // rigid_direction(run%rsplit, run%rsplit%unheld(:, j)) // ') that neither its ' // &
        'FIX nor its contacts hold (frictionless contact pushes only normal to the contact surface; expected FIX ' // &
        'on that direction, or a load the contact normals can balance)')
    end do
  end subroutine check_unheld_rigid_loads

  !> The contact problem has no solution because some load pulls a body off its
  !> contacts: when it is a RIGID's FORCE, say which RIGID and which way.
  subroutine diagnose_pulled_rigid(run)
    type(run_t), intent(inout) :: run
    integer :: owner
    real(dp) :: resid(3)
    character(len=80) :: buf
    call pulled_rigid(run%rsplit, owner, resid)
    if (owner == 0) return
    write(buf, '(a,es10.3,a,es10.3,a,es10.3,a)') '(', resid(1), ', ', resid(2), ', ', resid(3), ')'
    call fail_numerical(step_prefix(run) // 'no equilibrium: the FORCE on RIGID "' // run%sc%rigids(owner)%name // &
      '" pulls it away from its contacts: contact can only push, and the part (fx, fy, m) = ' // trim(buf) // &
      ' of its load cannot be balanced by any contact pressure (expected a FORCE that presses the obstacle ' // &
      'on the slave boundary)')
  end subroutine diagnose_pulled_rigid

  !> The contact problem has no solution because some load pulls a body held
  !> only by contact off its contacts: name the body and the motion it would
  !> make.  The closest balance of its loads by contact forces alone,
  !> min |Hh' mu - eh| over mu >= 0 (the test of contact_lcp, a nonnegative
  !> least squares solved as the LCP of its normal equations), leaves the
  !> unbalanced load r = eh - Hh' mu; the body that carries most of it and the
  !> motion along it are named, as for a frictional step.
  subroutine diagnose_pulled_body(run)
    type(run_t), intent(inout) :: run
    real(dp), allocatable :: hh(:,:), eh(:), mu(:), r(:), c(:)
    type(lcp_options_t) :: opts
    type(lcp_report_t) :: rep
    integer :: owner
    if (size(run%split%held, 2) == 0) return
    hh = matmul(run%split%h(1:run%cs%nrow, :), run%split%held)    ! Hh = H V_h on the normal rows
    eh = matmul(transpose(run%split%held), run%split%e)             ! eh = V_h' e
    allocate(mu(run%cs%nrow), source=0.0_dp)
    call solve_lcp_lemke(matmul(hh, transpose(hh)), -matmul(hh, eh), mu, opts, rep)
    if (rep%info /= 0) return
    r = eh - matmul(transpose(hh), mu)
    if (norm2(r) <= 1.0e-8_dp * norm2(eh)) return        ! the bodies balance: a RIGID, or the coupling of several
    call largest_owner(run%split%held, r, run%fl%mode_body, c, owner)
    call fail_numerical(step_prefix(run) // no_equilibrium_text('contact', '', 'the loads pull body "' // &
      run%sc%bodies(owner)%name // '"', motion_name(run%fl, c), 'the loads'))
  end subroutine diagnose_pulled_body

  !> The diagnosis of a frictional step without equilibrium from the unbalanced
  !> load along the held combinations (the bodies' modes, then the RIGIDs'
  !> free directions): the body or the RIGID that carries most of it, and
  !> the motion of that one alone.
  !>   unbalanced (in) e - H'z at the closest balance, along the held combinations
  !>   cause      (in) 'friction' (the cone is too small) or 'contact'
  function floating_no_equilibrium(run, unbalanced, cause) result(t)
    type(run_t), intent(in) :: run
    real(dp), intent(in) :: unbalanced(:)
    character(len=*), intent(in) :: cause
    character(len=:), allocatable :: t
    real(dp), allocatable :: c(:)
    integer :: kb, owner
    logical :: on_body
    kb = size(run%split%held, 2)
    on_body = .false.
    if (kb > 0) on_body = maxval(abs(unbalanced(1:kb))) >= maxval(abs(unbalanced(kb + 1:)), mask=.true.) .or. &
                          size(unbalanced) == kb
    if (on_body) then
      call largest_owner(run%split%held, unbalanced(1:kb), run%fl%mode_body, c, owner)
      t = no_equilibrium_text(cause, 'the loads on body "' // run%sc%bodies(owner)%name // '" exceed', &
                              'the loads pull body "' // run%sc%bodies(owner)%name // '"', motion_name(run%fl, c), &
                              'the loads')
    else
      call largest_owner(run%rsplit%held, unbalanced(kb + 1:), run%rsplit%owner, c, owner)
      t = no_equilibrium_text(cause, 'the FORCE on RIGID "' // run%sc%rigids(owner)%name // '" exceeds', &
                              'the FORCE on RIGID "' // run%sc%rigids(owner)%name // '" pulls it', &
                              rigid_direction(run%rsplit, c), 'its load')
    end if
  end function floating_no_equilibrium

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
  function no_equilibrium_text(cause, held, pulled, motion, load) result(t)
    character(len=*), intent(in) :: cause, held, pulled, motion, load
    character(len=:), allocatable :: t
    if (cause == 'friction') then
      t = 'no equilibrium: ' // held // ' what friction can hold: it would move by ' // motion // &
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
  function floating_names(run) result(t)
    type(run_t), intent(in) :: run
    character(len=:), allocatable :: t
    integer :: b, r
    t = ''
    do b = 1, size(run%sc%bodies)
      if (.not. any(run%fl%mode_body == b)) cycle
      if (len(t) > 0) t = t // ', '
      t = t // 'body "' // run%sc%bodies(b)%name // '"'
    end do
    do r = 1, size(run%sc%rigids)
      if (run%rsplit%k == 0) exit
      if (.not. any(run%rsplit%owner == r)) cycle
      if (len(t) > 0) t = t // ', '
      t = t // 'RIGID "' // run%sc%rigids(r)%name // '"'
    end do
  end function floating_names

  !> 'BODY KIND X Y' of unheld combination j for the summary: KIND rotation
  !> (X Y its centre) or translation (X Y its unit direction).
  function unheld_summary(run, j) result(t)
    type(run_t), intent(in) :: run
    integer, intent(in) :: j
    character(len=:), allocatable :: t, kind
    real(dp) :: point(2)
    character(len=32) :: bx, by
    call describe_motion(run%fl, run%split%unheld(:, j), kind, point)
    write(bx, '(es24.16e3)') point(1)
    write(by, '(es24.16e3)') point(2)
    t = run%sc%bodies(run%split%unheld_body(j))%name // ' ' // kind // ' ' // trim(adjustl(bx)) // ' ' // trim(adjustl(by))
  end function unheld_summary

  !> 'load step k of n: ' while the steps of OUTPUT steps=all are solved, else ''.
  function step_prefix(run) result(t)
    type(run_t), intent(in) :: run
    character(len=:), allocatable :: t
    t = ''
    if (allocated(run%step_note)) t = run%step_note
  end function step_prefix
end module held_by_contact
