!> run_report: the run log (stdout) and the run's clock.  Every run tells the
!> user what it did: the scene it built (bodies, contact pairs, rigid modes,
!> sizes, parameters), and at the end the contact solution, energy, factor,
!> the phase timings and the files written.  The timing laps live here too:
!> a lap charges the seconds since the last one to a phase of results_t.
!>
!> Why it exists: the log's wording is long and changes for reasons of its
!> own; out of the program it leaves the program reading like the method.
!> Who may use it: the program and its step modules (run_state's list).
!>
!> Programming interface
!>   say(run, text)                  one line of the run log (nothing with -q)
!>   start_clock(run)                the run's time zero
!>   lap(run, ph)                    seconds since the last lap go to phase ph
!>   split_overlap(run)              the ordering and the assembly ran side by side: charge each
!>   say_step(run, k, method, it, active)   the line of a load step solved on its own
!>   report_scene(run)               the scene: model, bodies (the formulation of a nearly
!>                                   incompressible one), RIGIDs, pairs, steps, rigid modes, sizes
!>   report_run(run)                 the results (each pair's zone, peak pressure, stick zone), factor,
!>                                   phases, files written
!>   friction_law(kind, spec)        how a pair's tangential behaviour reads in the log
!>   add_warning(run, code, text)    a warning: stderr (unless -q) and the summary's `warning CODE text`
module run_report
  use kinds, only: dp, i8
  use strings, only: int_to_str
  use run_state, only: run_t, ph_total, ph_factor, ph_assemble, ph_lcp
  use mesh, only: is_quadratic, find_name, boundary_nodes
  use deck_reader, only: load_point
  use contact_set, only: pair_spec_t, has_friction
  use contact_condensation, only: condensed_report
  use rigid_modes, only: mode_name, motion_name
  use rigid_support, only: rigid_direction
  use deck_expressions, only: format_number
  use material, only: locking_nu
  use body, only: body_pressure_modes
  use results_writer, only: phase_names, nphase, string_t
  use threads, only: run_threads
  use system_binding, only: c2d_cpu_seconds
  use command_line, only: version
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  implicit none
  private
  public :: say, start_clock, lap, split_overlap, say_step, report_scene, report_run, friction_law
  public :: add_warning

contains

  !> A warning: the run goes on, but its answer rests on something the user
  !> must know (an assumption of the model it has left, a pair that cannot
  !> touch).  The one way warnings are given: on stderr as
  !> `contact2d: warning: TEXT [CODE]` (unless -q: only errors there), and in
  !> the summary as `warning CODE TEXT`, so that a batch script finds it.
  !> The same warning given again (a load step measured twice) is kept once.
  !>   run  (inout) its quiet flag; res%warning gains the line
  !>   code (in)    one word naming the kind: locking, large_strain, large_rotation, ...
  !>   text (in)    what is wrong and what to do, one line; FILE:LINE: first
  !>                when a deck statement is the cause
  subroutine add_warning(run, code, text)
    type(run_t), intent(inout) :: run
    character(len=*), intent(in) :: code, text
    type(string_t), allocatable :: grown(:)
    integer :: k, n
    if (.not. allocated(run%res%warning)) allocate(run%res%warning(0))
    n = size(run%res%warning)
    do k = 1, n
      if (run%res%warning(k)%s == code // ' ' // text) return
    end do
    allocate(grown(n + 1))
    do k = 1, n
      call move_alloc(run%res%warning(k)%s, grown(k)%s)
    end do
    grown(n + 1)%s = code // ' ' // text
    call move_alloc(grown, run%res%warning)
    if (.not. run%quiet) write(error_unit, '(a)') 'contact2d: warning: ' // text // ' [' // code // ']'
  end subroutine add_warning

  !> A line of the run log, unless -q.
  !>   run  (in) its quiet flag
  !>   text (in) the line
  subroutine say(run, text)
    type(run_t), intent(in) :: run
    character(len=*), intent(in) :: text
    if (.not. run%quiet) write(output_unit, '(a)') text
  end subroutine say

  !> The run's time zero: the phases are measured from here.
  subroutine start_clock(run)
    type(run_t), intent(inout) :: run
    call system_clock(run%t_start)
    run%t_phase = run%t_start
    run%c_phase = c2d_cpu_seconds()
  end subroutine start_clock

  !> Seconds since the last lap go to phase ph; the total is kept up to date.
  subroutine lap(run, ph)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: ph
    integer(i8) :: now, rate
    call system_clock(now, rate)
    run%res%time(ph) = run%res%time(ph) + real(now - run%t_phase, dp) / real(rate, dp)
    run%res%time(ph_total) = real(now - run%t_start, dp) / real(rate, dp)
    run%t_phase = now
    call lap_cpu(run, [ph], [1.0_dp])
  end subroutine lap

  !> CPU seconds (gmsh's included) since the last lap, shared between the
  !> phases ph in the given proportions; the total is the process's.
  subroutine lap_cpu(run, ph, share)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: ph(:)
    real(dp), intent(in) :: share(:)
    real(dp) :: now
    now = c2d_cpu_seconds()
    run%res%cpu(ph) = run%res%cpu(ph) + share * (now - run%c_phase)
    run%res%cpu(ph_total) = now
    run%c_phase = now
  end subroutine lap_cpu

  !> The ordering and the assembly of the values ran side by side: the
  !> ordering is charged to factor, the part of the assembly it did not hide
  !> to assemble, so that the phases still add up to the total.
  subroutine split_overlap(run)
    type(run_t), intent(inout) :: run
    integer(i8) :: now, rate
    real(dp) :: wall
    call system_clock(now, rate)
    wall = real(now - run%t_phase, dp) / real(rate, dp)
    run%res%time_assemble_values = real(run%t_asm1 - run%t_asm0, dp) / real(rate, dp)
    run%res%time_ordering = min(wall, run%factor%time_analyze)
    run%res%time(ph_factor) = run%res%time(ph_factor) + run%res%time_ordering
    run%res%time(ph_assemble) = run%res%time(ph_assemble) + (wall - run%res%time_ordering)
    run%res%time(ph_total) = real(now - run%t_start, dp) / real(rate, dp)
    run%t_phase = now
    if (wall > 0.0_dp) then
      call lap_cpu(run, [ph_factor, ph_assemble], [run%res%time_ordering, wall - run%res%time_ordering] / wall)
    else
      call lap_cpu(run, [ph_factor], [1.0_dp])
    end if
  end subroutine split_overlap

  !> The run log's line of a step solved on its own (OUTPUT steps=all).
  subroutine say_step(run, kstep, method, iterations, active)
    type(run_t), intent(in) :: run
    integer, intent(in) :: kstep, iterations, active
    character(len=*), intent(in) :: method
    character(len=160) :: line
    write(line, '(a,i0,a,i0,a,i0,a,i0,a)') 'step     ', kstep, '/', run%sc%steps, ': ' // method // ' ', iterations, &
      ' iterations, ', active, ' active'
    call say(run, trim(line))
  end subroutine say_step

  subroutine report_scene(run)
    type(run_t), intent(inout) :: run
    integer :: b, ip
    character(len=:), allocatable :: how, family
    character(len=160) :: line
    call say(run, 'contact2d ' // version // ': ' // run%deck%file)
    if (len(run%deck%title) > 0) call say(run, 'title    ' // run%deck%title)
    call report_parameters(run)
    call say(run, 'effects  ' // run%sc%effects)
    family = 'P1/Q1'                                 ! the element families of the bodies
    if (any([(is_quadratic(run%sc%bodies(b)%mesh), b = 1, size(run%sc%bodies))])) family = 'quadratic (P2/Q8/Q9)'
    if (any([(is_quadratic(run%sc%bodies(b)%mesh), b = 1, size(run%sc%bodies))]) .and. &
        .not. all([(is_quadratic(run%sc%bodies(b)%mesh), b = 1, size(run%sc%bodies))])) family = 'P1/Q1 and quadratic'
    if (run%deck%axisymmetric) then
      call say(run, 'model    axisymmetric (x = r, y = z), ' // family // ' elasticity, small deformation; ' // &
               'loads per unit area and volume, u_r = 0 on the axis; every force is for the full circle (2 pi r)')
    else if (run%deck%plane_stress) then
      call say(run, 'model    plane stress, ' // family // ' elasticity, small deformation')
    else
      call say(run, 'model    plane strain, ' // family // ' elasticity, small deformation')
    end if
    do b = 1, size(run%sc%bodies)
      ! the body name is as long as the deck made it: not part of the buffer
      write(line, '(i0,a,i0,a,i0,a)') run%sc%bodies(b)%mesh%nnode, ' nodes, ', run%sc%bodies(b)%mesh%nelem, &
        ' elements (', count(run%sc%bodies(b)%mesh%nen == 4 .or. run%sc%bodies(b)%mesh%nen >= 8), ' quadrilaterals)'
      call say(run, 'body     ' // run%sc%bodies(b)%name // ': ' // trim(line))
      call report_formulation(run, b)
    end do
    call report_supports(run)
    if (run%sc%reused_meshes > 0) call say(run, 'mesh     ' // int_to_str(run%sc%reused_meshes) // ' .geo mesh(es) ' // &
      'read from the mesh cache ' // run%gmsh%cache // ' (the same .geo, parameters and gmsh; --no-mesh-cache: mesh again)')
    call report_rigids(run)
    do ip = 1, run%cs%npair
      write(line, '(a,i0,a,i0,a,i0,a,i0,a)') 'contact  pair ', ip, ': ', size(run%cs%pair(ip)%snode), &
        ' slave nodes, ', size(run%cs%pair(ip)%mnode), ' master nodes, ', run%cs%pair(ip)%nrow, ' constrained (mortar, '
      if (run%cs%pair(ip)%spec%rigid > 0) write(line, '(a,i0,a,i0,a,i0,a)') 'contact  pair ', ip, ': ', &
        size(run%cs%pair(ip)%snode), ' slave nodes against RIGID ' // run%sc%rigids(run%cs%pair(ip)%spec%rigid)%name // &
        ' (its exact shape), ', run%cs%pair(ip)%nrow, ' constrained (mortar, '
      call say(run, trim(line) // ' ' // friction_law(run%deck%contacts(ip)%friction, run%cs%pair(ip)%spec) // ')')
      associate(pr => run%cs%pair(ip), mo => run%cs%pair(ip)%mortar)
        if (mo%first > 0) then
          write(line, '(a,es11.4,a,es11.4)') 'contact  pair ' // int_to_str(ip) // ': initial gap from ', &
            minval(mo%gap0(mo%first:mo%last)), ' to ', maxval(mo%gap0(mo%first:mo%last))
          if (pr%closed .and. mo%first == 1 .and. mo%last == size(pr%snode)) then
            line = trim(line) // ', a closed curve covered all round (no zone ends)'
          else if (any(pr%fold)) then
            line = trim(line) // ', a zone end inside a slave segment (the master''s end)'
          end if
          if (pr%spec%interference) line = trim(line) // ', interference=allow'
          if (pr%quadratic) then
            ! the quadratic operator's choices (doc/theory.md, "Quadratic traces")
            call say(run, trim(line))
            write(line, '(a,i0,a,i0,a)') 'contact  pair ' // int_to_str(ip) // ': quadratic mortar, slave degree ', &
              pr%degree(1), ', master degree ', pr%degree(2), ': non-penetration at every trace node'
          end if
          if (has_friction(pr%spec)) then
            ! the assumption the frictional rows rest on (doc/theory.md, "Friction on curved surfaces")
            call say(run, trim(line))
            write(line, '(a,f5.3,a)') 'contact  pair ' // int_to_str(ip) // ': rows along the common normal ' // &
              'w n_slave - (1 - w) n_master, w = ', pr%slave_weight, ' (from the two sides'' curvatures)'
          end if
        else
          line = 'contact  pair ' // int_to_str(ip) // ': the master faces no slave segment (no contact possible)'
        end if
        call say(run, trim(line))
      end associate
    end do
    if (run%sc%steps > 1 .and. run%cs%ntan > 0) then
      call say(run, 'steps    ' // int_to_str(run%sc%steps) // ' load steps (friction: the answer depends on the load path)')
    else if (run%sc%steps > 1 .and. any(run%sc%specs%finite)) then
      call say(run, 'steps    ' // int_to_str(run%sc%steps) // ' load steps in order (sliding=finite: each step ' // &
               'in the contact geometry it reaches; one factorization for all)')
    else if (run%sc%steps > 1 .and. run%deck%output%steps_all) then
      call say(run, 'steps    ' // int_to_str(run%sc%steps) // ' load steps, each solved at its load factors (without ' // &
               'friction the steps are independent; one factorization for all)')
    else if (run%sc%steps > 1) then
      call say(run, 'steps    ' // int_to_str(run%sc%steps) // ' load steps declared; without friction the answer does not ' // &
               'depend on the load path: the final step alone is solved')
    end if
    do ip = 1, run%fl%k
      if (any(run%split%unheld_body == run%fl%mode_body(ip))) then
        call say(run, 'rigid    body ' // run%sc%bodies(run%fl%mode_body(ip))%name // ': ' // mode_name(run%fl, &
          ip) // ' not held by FIX')
      else
        call say(run, 'rigid    body ' // run%sc%bodies(run%fl%mode_body(ip))%name // ': ' // mode_name(run%fl, ip) // &
                 ' not held by FIX: held by contact (equilibrium as an equality constraint)')
      end if
    end do
    do ip = 1, size(run%split%unheld, 2)
      b = run%split%unheld_body(ip)
      how = '(the contact normals do not resist it)'
      if (run%split%tau(b) > 1.0e-10_dp) how = '(the contact normals do not resist it beyond the contact polygon''s median ' // &
        'turning angle, ' // trim(adjustl(real_short(run%split%tau(b)))) // ' rad)'
      call say(run, 'rigid    body ' // run%sc%bodies(b)%name // ': ' // motion_name(run%fl, run%split%unheld(:, ip)) // &
        ' held by neither FIX nor contact ' // how // '; ' // int_to_str(count(run%fl%mode_body == b) - &
        count(run%split%unheld_body == b)) // ' other combination(s) held by contact')
    end do
    write(line, '(a,i0,a,i0,a,i0,a)') 'sizes    ', run%sc%ndof, ' dofs, ', run%nfree, ' free, ', run%cs%nrow, ' contact constraints'
    call say(run, trim(line))
    if (len(run%thread_note) > 0) call say(run, 'threads  ' // run%thread_note)
    ! a key kept so that old decks still read: say that it does nothing
    if (allocated(run%deck%solver%cut)) call say(run, 'note     SOLVER cut=' // run%deck%solver%cut // &
      ' is ignored: no body is cut any more (doc/performance.md, "A body cut in two: removed")')
  end subroutine report_scene

  !> The run log's line of the formulation of body b when its material is
  !> nearly incompressible (isotropic, nu > locking_nu): B-bar on the
  !> element kinds that take it (body, elements' pressure_modes), and why
  !> the others are left as they are.  Nothing for the other bodies.
  subroutine report_formulation(run, b)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: b
    character(len=:), allocatable :: text, nu
    integer :: k, count_k
    integer, parameter :: kinds_nen(5) = [4, 8, 9, 3, 6]
    character(len=*), parameter :: kind_name(5) = [character(len=20) :: '4-node quadrangles', '8-node quadrangles', &
                                                   '9-node quadrangles', '3-node triangles', '6-node triangles']
    associate (mat => run%deck%bodies(b)%material, bd => run%sc%bodies(b))
      if (.not. allocated(mat%kind)) return
      if (mat%kind /= 'isotropic' .or. mat%nu <= locking_nu) return
      nu = 'nu = ' // format_number(mat%nu) // ' > ' // format_number(locking_nu)
      if (.not. bd%bbar) then
        call say(run, 'body     ' // bd%name // ': formulation: displacement, ' // nu // ' in plane stress (the ' // &
                 'through-thickness strain takes up the change of volume: no locking)')
        return
      end if
      text = ''
      do k = 1, size(kinds_nen)
        count_k = count(bd%mesh%nen == kinds_nen(k))
        if (count_k == 0) cycle
        if (len(text) > 0) text = text // '; '
        select case (body_pressure_modes(bd, kinds_nen(k)))
        case (1)
          text = text // 'B-bar (mean dilatation) on '
        case (3)
          text = text // 'B-bar (linear pressure projection) on '
        case default
          text = text // 'displacement on '
        end select
        text = text // int_to_str(count_k) // ' ' // trim(kind_name(k))
        if (kinds_nen(k) == 3) text = text // ' (they lock: warning locking)'
      end do
      call say(run, 'body     ' // bd%name // ': formulation: ' // text // ', ' // nu)
    end associate
  end subroutine report_formulation

  !> The run log's lines of each point FORCE and each SPRING of the bodies:
  !> the point set or boundary, the values and the nodes or edges they reach.
  subroutine report_supports(run)
    type(run_t), intent(inout) :: run
    integer :: b, k, ib, nk
    integer, allocatable :: nodes(:)
    character(len=:), allocatable :: unit
    unit = 'per unit length'
    if (run%deck%axisymmetric) unit = 'per unit area'
    do b = 1, size(run%sc%bodies)
      associate (bd => run%sc%bodies(b), bdeck => run%deck%bodies(b))
        do k = 1, size(bdeck%loads)
          if (bdeck%loads(k)%kind /= load_point) cycle
          ib = find_name(bd%mesh%bnd, bdeck%loads(k)%boundary)
          call boundary_nodes(bd%mesh%bnd(ib), nodes)
          call say(run, 'force    ' // bd%name // ':' // bdeck%loads(k)%boundary // ': point force (fx, fy) = (' // &
            trim(format_number(bdeck%loads(k)%tx)) // ', ' // trim(format_number(bdeck%loads(k)%ty)) // ') at ' // &
            int_to_str(size(nodes)) // ' node(s)')
        end do
        do k = 1, size(bdeck%springs)
          associate (sp => bdeck%springs(k))
            nk = 0                                  ! its spring elements
            if (bd%springs%n > 0) nk = count(bd%springs%owner(1:bd%springs%n) == k)
            if (sp%point) then
              call say(run, 'spring   ' // bd%name // ':' // sp%boundary // ': to the ground, kx = ' // &
                trim(format_number(sp%kx)) // ', ky = ' // trim(format_number(sp%ky)) // ' at ' // &
                int_to_str(nk) // ' node(s)')
            else
              call say(run, 'spring   ' // bd%name // ':' // sp%boundary // ': elastic foundation, kn = ' // &
                trim(format_number(sp%kn)) // ', kt = ' // trim(format_number(sp%kt)) // ' ' // unit // ' on ' // &
                int_to_str(nk) // ' edges')
            end if
          end associate
        end do
      end associate
    end do
  end subroutine report_supports

  !> The run log's lines of each RIGID: its shape, reference point, which
  !> directions are prescribed and which are free (loaded or not, held by
  !> contact or not).
  subroutine report_rigids(run)
    type(run_t), intent(inout) :: run
    integer :: r, j, k
    character(len=200) :: line
    character(len=2), parameter :: dname(3) = ['ux', 'uy', 'rz']
    character(len=:), allocatable :: how
    do r = 1, size(run%sc%rigids)
      associate (sh => run%sc%rigids(r))
        select case (run%deck%rigids(r)%shape)
        case ('circle')
          write(line, '(a,g0.6,a,g0.6,a,g0.6,a)') 'circle of radius ', sh%radius, ' centred at (', sh%centre(1), ', ', &
            sh%centre(2), ')'
          if (sh%outside) then
            line = trim(line) // ', solid outside (a hole)'
          else
            line = trim(line) // ', solid inside'
          end if
        case default
          write(line, '(a,i0,a)') run%deck%rigids(r)%shape // ' of ', size(sh%pt, 2), ' points'
        end select
        write(line(len_trim(line) + 1:), '(a,g0.6,a,g0.6,a)') ', reference point (', sh%ref(1), ', ', sh%ref(2), ')'
        call say(run, 'rigid    ' // sh%name // ': ' // trim(line))
        how = ''
        do j = 1, 3
          if (run%sc%fixed(sh%dof0 + j)) then
            how = how // ', ' // dname(j) // ' prescribed'
          else
            how = how // ', ' // dname(j) // ' free'
            do k = 1, run%rsplit%k
              if (run%rsplit%dof(k) == sh%dof0 + j .and. run%sc%fext(sh%dof0 + j) /= 0.0_dp) how = how // ' (FORCE)'
            end do
          end if
        end do
        if (size(run%deck%rigids(r)%fixes) + size(run%deck%rigids(r)%forces) == 0) then
          call say(run, 'rigid    ' // sh%name // ': held fixed (no FIX, no FORCE)')
        else if (all(run%sc%fixed(sh%dof0 + 1:sh%dof0 + 3))) then
          call say(run, 'rigid    ' // sh%name // ': ' // how(3:))
        else
          call say(run, 'rigid    ' // sh%name // ': ' // how(3:) // ' (a free direction is held by contact alone: ' // &
                   'its equilibrium is an equality of the contact problem)')
        end if
      end associate
    end do
    do j = 1, size(run%rsplit%unheld, 2)
      if (run%rsplit%loaded(j)) cycle
      call say(run, 'note     RIGID ' // run%sc%rigids(run%rsplit%unheld_owner(j))%name // ': free direction (' // &
        rigid_direction(run%rsplit, run%rsplit%unheld(:, j)) // ') held by neither FIX nor contact and unloaded: its ' // &
        'motion is set to 0 (the contact normals do not resist it)')
    end do
  end subroutine report_rigids

  !> The run log's `param    name = value (origin)` lines; the summary's
  !> `parameter NAME VALUE` lines.
  subroutine report_parameters(run)
    type(run_t), intent(inout) :: run
    integer :: k
    character(len=:), allocatable :: value
    allocate(run%res%parameter(run%deck%params%n))
    do k = 1, run%deck%params%n
      value = format_number(run%deck%params%value(k))
      run%res%parameter(k)%s = trim(run%deck%params%name(k)) // ' ' // value
      call say(run, 'param    ' // trim(run%deck%params%name(k)) // ' = ' // value // ' (' // &
        trim(run%deck%params%origin(k)) // ')')
    end do
  end subroutine report_parameters

  subroutine report_run(run)
    type(run_t), intent(inout) :: run
    character(len=200) :: line
    character(len=:), allocatable :: how
    integer :: p
    if (run%cs%nrow > 0) then
      write(line, '(a,i0,a,i0,a,es10.3,a,es10.3)') 'lcp      ' // run%res%lcp_method // ': ', run%res%lcp_iterations, &
        ' iterations, ', run%res%active_nodes, ' active nodes, residual ', run%res%lcp_residual, &
        ', complementarity ', run%res%complementarity
      if (run%res%lcp_method == 'lemke' .and. run%res%lcp_iterations > 0) then
        ! Lemke's cost per pivot: O(n^2) on its dense tableau (performance.md)
        write(line(len_trim(line) + 1:), '(a,es9.3,a)') ', ', &
          run%res%time(ph_lcp) / run%res%lcp_iterations, ' s per pivot'
      end if
      call say(run, trim(line))
      write(line, '(a,es12.4,a,es12.4)') 'contact  min gap ', run%res%min_gap, ', min pressure ', run%res%min_pressure
      call say(run, trim(line))
      call report_zones(run)
    end if
    do p = 1, size(run%sc%rigids)
      write(line, '(a,3es12.4,a,3es12.4)') ': motion (ux, uy, rz) =', run%res%rigid(1:3, p), &
        ', contact force on it (fx, fy, m) =', run%res%rigid(4:6, p)
      call say(run, 'rigid    ' // run%sc%rigids(p)%name // trim(line))
    end do
    write(line, '(a,es16.8,a,i0)') 'energy   ', run%res%energy, ',  nnz(L) ', run%res%factor_nnz
    call say(run, trim(line) // ' (' // run%res%ordering // '),  peak memory ' // &
             trim(adjustl(real_fixed(run%res%memory_peak / 1048576.0_dp))) // ' MB')
    if (run%res%estimated) then
      write(line, '(a,f8.3,a)') 'estimate energy-norm error of u ', 100 * run%res%estimate_energy, &
        ' % (stress recovery; error_indicator in the VTK)'
      call say(run, trim(line))
      do p = 1, size(run%res%estimate_pressure)
        if (run%res%estimate_pressure(p) < 0.0_dp) then
          write(line, '(a,i0,a)') 'estimate pair ', p, ': no node in contact, no pressure to estimate'
        else
          write(line, '(a,i0,a,f8.3,a)') 'estimate pair ', p, ': L2 error of the contact pressure ', &
            100 * run%res%estimate_pressure(p), ' %'
        end if
        call say(run, trim(line))
      end do
    else
      call say(run, 'estimate off (ESTIMATE off): the run does not estimate its error')
    end if
    if (run%factor%nparts > 1) then
      write(line, '(a,i0,a)') 'factor   ', run%factor%nparts, ' parts (blocks of K that no entry couples: the bodies)'
      if (run%factor%side_by_side > 1) then
        write(line, '(a,i0,a)') trim(line) // ' ordered and factorized side by side on ', &
          run%factor%side_by_side, ' threads'
      else
        line = trim(line) // ' ordered and factorized one after the other'
      end if
      call say(run, trim(line))
    end if
    if (allocated(run%cd%block)) then
      how = condensed_report(run%cd)
      if (len(how) > 0) call say(run, 'condense W from L_cc by body: ' // how)
    end if
    call say(run, 'phase        seconds')
    do p = 1, nphase
      write(line, '(a,f12.4)') phase_names(p), run%res%time(p)
      call say(run, trim(line))
    end do
    if (run_threads() > 1) then
      write(line, '(a,f8.3,a,f8.3,a)') ' ordering (', run%res%time_ordering, &
        ' s, in factor) and the assembly of K (', run%res%time_assemble_values, ' s) ran side by side'
      call say(run, 'overlap  the ' // run%res%ordering // trim(line))
    end if
    do p = 1, size(run%wrote)
      call say(run, trim(run%wrote(p)))          ! the files run_outputs wrote
    end do
  end subroutine report_run

  !> Per pair, the summary's contact_zone, peak_pressure and stick_zone in
  !> words: `contact  pair 1: in contact from (x0, y0) to (x1, y1), length L,
  !> peak pressure P at (x, y)`, and `stick from ... to ..., length L`.
  subroutine report_zones(run)
    type(run_t), intent(in) :: run
    character(len=240) :: line
    integer :: p
    if (.not. allocated(run%res%zones)) return
    do p = 1, size(run%res%zones)
      associate(z => run%res%zones(p))
        if (z%contact%count == 0) then
          call say(run, 'contact  pair ' // int_to_str(p) // ': no node in contact')
          cycle
        end if
        write(line, '(a,2(a,es11.4,a,es11.4,a),a,es11.4)') 'contact  pair ' // int_to_str(p) // ': in contact', &
          ' from (', z%contact%x0(1), ', ', z%contact%x0(2), ')', ' to (', z%contact%x1(1), ', ', z%contact%x1(2), ')', &
          ', length', z%contact%length
        if (z%contact%count > 1) line = trim(line) // ' (' // int_to_str(z%contact%count) // ' zones)'
        write(line(len_trim(line) + 1:), '(a,es11.4,a,es11.4,a,es11.4,a)') ', peak pressure', z%peak(1), ' at (', &
          z%peak(2), ', ', z%peak(3), ')'
        call say(run, trim(line))
        if (.not. z%friction) cycle
        if (z%stick%count == 0) then
          call say(run, 'contact  pair ' // int_to_str(p) // ': no node sticks')
          cycle
        end if
        write(line, '(a,2(a,es11.4,a,es11.4,a),a,es11.4)') 'contact  pair ' // int_to_str(p) // ': stick', &
          ' from (', z%stick%x0(1), ', ', z%stick%x0(2), ')', ' to (', z%stick%x1(1), ', ', z%stick%x1(2), ')', &
          ', length', z%stick%length
        if (z%stick%count > 1) line = trim(line) // ' (' // int_to_str(z%stick%count) // ' zones)'
        call say(run, trim(line))
      end associate
    end do
  end subroutine report_zones

  !> How a pair's tangential behaviour is described in the log.
  function friction_law(kind, spec) result(t)
    character(len=*), intent(in) :: kind
    type(pair_spec_t), intent(in) :: spec
    character(len=:), allocatable :: t
    character(len=32) :: v
    select case (kind)
    case ('coulomb')
      write(v, '(g0.6)') spec%mu
      t = 'Coulomb friction mu = ' // trim(v)
      if (spec%mu == 0.0_dp) t = t // ': frictionless'
    case ('tresca')
      write(v, '(g0.6)') spec%tresca
      t = 'Tresca friction, slip bound ' // trim(v)
      if (spec%tresca == 0.0_dp) t = t // ': frictionless'
    case default
      t = 'frictionless'
    end select
  end function friction_law

  !> x in es10.3
  function real_short(x) result(s)
    real(dp), intent(in) :: x
    character(len=10) :: s
    write(s, '(es10.3)') x
  end function real_short

  !> x with one decimal (f10.1)
  function real_fixed(x) result(s)
    real(dp), intent(in) :: x
    character(len=10) :: s
    write(s, '(f10.1)') x
  end function real_fixed

end module run_report
