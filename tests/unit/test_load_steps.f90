!> load_steps, step_solver, held_by_contact, problem_builder, linear_system:
!> the solve layer on small decks whose answers are known by hand.  Each deck
!> is written to the test's scratch folder, built (build_problem), its K
!> assembled, factorized and condensed (linear_system), and its load history
!> solved (solve_load_steps); the checks read the step solution, the stage
!> the solve layer returns.
!>   - a friction step (a block held only by contact on a rigid plane, mu =
!>     0.5, pressed by P and pushed sideways by T = 0.4 P < mu P): the block's
!>     equilibrium, sum of the normal multipliers = P and of the tangential
!>     ones = -T (the force on the slave is -tau t), every row in the cone
!>     |tau_i| <= mu lambda_i, the step solved in one step or two alike;
!>   - the held-by-contact diagnosis: the same block pushed by T = 0.6 P >
!>     mu P has no equilibrium: category error_no_equilibrium, the message
!>     saying that the loads exceed what friction can hold;
!>   - a finite-sliding update: a rigid cylinder pressed into a block and
!>     moved sideways by s (sliding=finite, frictionless): the contact force
!>     is the cylinder's load, vertical, and its centre of pressure has moved
!>     by s (within half a slave element); the rows of the solution are those
!>     of the moved configuration (a second update changes nothing).
program test_load_steps
  use kinds, only: dp
  use errors, only: error_t, diag_t, has_errors, print_errors, error_no_equilibrium
  use run_log, only: log_t
  use deck_reader, only: read_deck
  use gmsh_runner, only: gmsh_options_t
  use problem, only: problem_t
  use problem_builder, only: build_problem
  use linear_system, only: system_t, assemble_system, factorize_system, condense_system
  use step_solution, only: step_solution_t
  use load_steps, only: solve_load_steps
  use testing, only: check, check_close, check_small, finish_tests
  implicit none

  call friction_block(0.4_dp, 1)
  call friction_block(0.4_dp, 2)
  call friction_block_pushed_off()
  call cylinder_dragged()
  call finish_tests()

contains

  !> The deck text written to NAME.deck in the scratch folder, built,
  !> condensed and solved; err the solve's (build failures fail the test).
  subroutine solve_deck(name, text, prob, sol, err)
    character(len=*), intent(in) :: name, text
    type(problem_t), intent(out) :: prob
    type(step_solution_t), intent(out) :: sol
    type(error_t), allocatable, intent(out) :: err
    type(diag_t) :: diag
    type(log_t) :: log
    type(gmsh_options_t) :: gmsh
    type(system_t) :: sys
    character(len=:), allocatable :: path
    character(len=256) :: tmp
    integer :: u, length, status
    call get_environment_variable('TMPDIR', tmp, length, status)
    if (status /= 0 .or. length == 0) tmp = '/tmp'
    path = trim(tmp) // '/' // name // '.deck'
    open(newunit=u, file=path, status='replace', action='write')
    write(u, '(a)') text
    close(u)
    log%quiet = .true.
    call read_deck(path, prob%deck, diag)
    call build_problem(prob, gmsh, diag, log, err)
    if (has_errors(diag)) call print_errors(diag)
    call check(.not. has_errors(diag) .and. .not. allocated(err), name // ': the deck builds')
    if (has_errors(diag) .or. allocated(err)) return
    call assemble_system(prob, sys, log, err)
    if (.not. allocated(err)) call factorize_system(prob, sys, log, err)
    if (.not. allocated(err)) call condense_system(prob, sys, log, err)
    call check(.not. allocated(err), name // ': K assembled, factorized, condensed')
    if (allocated(err)) return
    call solve_load_steps(prob, sys, log, sol, err)
  end subroutine solve_deck

  !> A 1 x 1 block (E = 1000) on the rigid line y = 0, held only by contact,
  !> pressed by P = 10 on its top and pushed by T on its left side.
  function block_deck(t, steps) result(text)
    real(dp), intent(in) :: t
    integer, intent(in) :: steps
    character(len=:), allocatable :: text
    character(len=32) :: tx, st
    write(tx, '(es12.5)') t
    write(st, '(i0)') steps
    text = 'PLANE strain' // new_line('a') // &
      'STEPS ' // trim(st) // new_line('a') // &
      'BODY block' // new_line('a') // &
      '  MESH rect x0=0 y0=0 x1=1 y1=1 nx=4 ny=4' // new_line('a') // &
      '  MATERIAL isotropic E=1000 nu=0.3' // new_line('a') // &
      '  TRACTION top tx=0 ty=-10' // new_line('a') // &
      '  TRACTION left tx=' // trim(adjustl(tx)) // ' ty=0' // new_line('a') // &
      'END' // new_line('a') // &
      'RIGID plane' // new_line('a') // &
      '  SHAPE line x0=-2 y0=0 x1=3 y1=0' // new_line('a') // &
      'END' // new_line('a') // &
      'CONTACT slave=block:bottom master=plane mu=0.5' // new_line('a')
  end function block_deck

  !> Below the friction capacity: the block's equilibrium and the cone.
  subroutine friction_block(ratio, steps)
    real(dp), intent(in) :: ratio
    integer, intent(in) :: steps
    type(problem_t) :: prob
    type(step_solution_t) :: sol
    type(error_t), allocatable :: err
    character(len=16) :: name
    real(dp), parameter :: p = 10.0_dp
    integer :: r
    write(name, '(a,i0)') 'block_steps', steps
    call solve_deck(trim(name), block_deck(ratio * p, steps), prob, sol, err)
    if (allocated(err)) print '(a)', err%message
    call check(.not. allocated(err), trim(name) // ': T = 0.4 P < mu P is solved')
    if (allocated(err) .or. .not. allocated(sol%tau)) return
    call check_close(sum(sol%mu), p, 1.0e-9_dp, trim(name) // ': sum of the normal forces = P')
    ! the tangential rows' direction is the slave's (bottom: along -x or +x)
    call check_close(abs(sum(sol%tau)), ratio * p, 1.0e-9_dp, trim(name) // ': |sum of the tangential forces| = T')
    call check(all([(abs(sol%tau(r)) <= 0.5_dp * sol%mu(prob%cs%tan_row(r)) + 1.0e-9_dp * p, r = 1, size(sol%tau))]), &
               trim(name) // ': every row in the friction cone')
  end subroutine friction_block

  !> Beyond the friction capacity: no equilibrium, named as such.
  subroutine friction_block_pushed_off()
    type(problem_t) :: prob
    type(step_solution_t) :: sol
    type(error_t), allocatable :: err
    call solve_deck('block_pushed', block_deck(6.0_dp, 1), prob, sol, err)
    call check(allocated(err), 'block_pushed: T = 0.6 P > mu P is not solved')
    if (.not. allocated(err)) return
    call check(err%category == error_no_equilibrium, 'block_pushed: the category is no equilibrium')
    call check(index(err%message, 'what friction can hold') > 0, 'block_pushed: the message names friction: ' // &
               err%message(1:min(120, len(err%message))))
  end subroutine friction_block_pushed_off

  !> A rigid cylinder of radius 2 pressed 0.01 into a 4 x 1 block and moved
  !> 0.5 sideways under sliding=finite (frictionless).
  subroutine cylinder_dragged()
    type(problem_t) :: prob
    type(step_solution_t) :: sol
    type(error_t), allocatable :: err
    real(dp) :: total, centre, x
    integer :: r, ip, node, b
    character(len=*), parameter :: text = 'PLANE strain' // new_line('a') // &
      'BODY block' // new_line('a') // &
      '  MESH rect x0=-2 y0=-1 x1=2 y1=0 nx=80 ny=20' // new_line('a') // &
      '  MATERIAL isotropic E=1000 nu=0.3' // new_line('a') // &
      '  FIX bottom ux=0 uy=0' // new_line('a') // &
      'END' // new_line('a') // &
      'RIGID roller' // new_line('a') // &
      '  SHAPE circle xc=0 yc=2 r=2' // new_line('a') // &
      '  FIX ux=0.5 uy=-0.01 rz=0' // new_line('a') // &
      'END' // new_line('a') // &
      'CONTACT slave=block:top master=roller sliding=finite' // new_line('a')
    call solve_deck('cylinder_dragged', text, prob, sol, err)
    if (allocated(err)) print '(a)', err%message
    call check(.not. allocated(err), 'cylinder_dragged: solved')
    if (allocated(err)) return
    total = sum(sol%mu)
    call check(total > 0.0_dp, 'cylinder_dragged: the cylinder presses the block')
    centre = 0.0_dp
    do r = 1, prob%cs%nrow
      ip = prob%cs%row_pair(r)
      node = prob%cs%pair(ip)%snode(prob%cs%row_node(r))
      b = prob%cs%pair(ip)%spec%slave_body
      x = prob%sc%bodies(b)%mesh%x(1, node)
      centre = centre + sol%mu(r) * x
    end do
    centre = centre / total
    ! half a slave element: 0.025
    call check_small(centre - 0.5_dp, 0.025_dp, 'cylinder_dragged: the centre of pressure moved with the cylinder')
    call check(sol%updates >= 2, 'cylinder_dragged: the geometry was updated')
  end subroutine cylinder_dragged

end program test_load_steps
