!> run_report: what the run log (stdout) says of the scene and of the
!> results.  Every run tells the user what it did: the scene it built
!> (bodies, contact pairs, rigid modes, sizes, parameters), and at the end
!> the contact solution, energy, factor, the phase timings and the files
!> written.  The log itself, its clock and the warnings are run_log's.
!>
!> Why it exists: the log's wording is long and changes for reasons of its
!> own; out of the program it leaves the program reading like the method.
!> Who may use it: the program and its application modules.
!>
!> Programming interface
!>   say_step(log, k, n, method, it, active)   the line of a frictionless load step solved on its own
!>   report_scene(run)               the scene: model, bodies (the formulation of a nearly
!>                                   incompressible one), RIGIDs, pairs, steps, rigid modes, sizes
!>   report_run(run)                 the results (each pair's zone, peak pressure, stick zone), factor,
!>                                   phases, files written
!>   friction_law(kind, spec)        how a pair's tangential behaviour reads in the log
module run_report
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str, fixed_to_str, format_number
  use run_state, only: run_t
  use run_log, only: log_t, say, ph_lcp, nphase, phase_names
  use mesh, only: is_quadratic, find_name, boundary_nodes
  use deck_reader, only: load_point
  use contact_set, only: pair_spec_t, has_friction
  use rigid_modes, only: mode_name, motion_name
  use rigid_support, only: rigid_direction
  use contact_zones, only: zone_t
  use material, only: locking_nu
  use body, only: body_pressure_modes
  use threads, only: run_threads
  use command_line, only: version
  use gmsh_runner, only: gmsh_runs
  implicit none
  private
  public :: say_step, report_scene, report_run, friction_law

contains

  !> The run log's line of a frictionless step solved on its own (OUTPUT
  !> steps=all, sliding=finite); a friction step's is the solve layer's.
  !>   kstep, steps (in) the step and the number of steps
  subroutine say_step(log, kstep, steps, method, iterations, active)
    type(log_t), intent(in) :: log
    integer, intent(in) :: kstep, steps, iterations, active
    character(len=*), intent(in) :: method
    character(len=160) :: line
    write(line, '(a,i0,a,i0,a,i0,a,i0,a)') 'step     ', kstep, '/', steps, ': ' // method // ' ', iterations, &
      ' iterations, ', active, ' active'
    call say(log, trim(line))
  end subroutine say_step

  subroutine report_scene(run)
    type(run_t), intent(inout) :: run
    integer :: b, ip
    character(len=:), allocatable :: how, family, kinematics, method
    character(len=160) :: line
    call say(run%log, 'contact2d ' // version // ': ' // run%prob%deck%file)
    if (len(run%prob%deck%title) > 0) call say(run%log, 'title    ' // run%prob%deck%title)
    call report_parameters(run)
    call say(run%log, 'effects  ' // run%prob%sc%effects)
    family = 'P1/Q1'                                 ! the element families of the bodies
    if (any([(is_quadratic(run%prob%sc%bodies(b)%mesh), b = 1, size(run%prob%sc%bodies))])) family = 'quadratic (P2/Q8/Q9)'
    if (any([(is_quadratic(run%prob%sc%bodies(b)%mesh), b = 1, size(run%prob%sc%bodies))]) .and. &
        .not. all([(is_quadratic(run%prob%sc%bodies(b)%mesh), b = 1, size(run%prob%sc%bodies))])) family = 'P1/Q1 and quadratic'
    kinematics = 'small deformation'
    if (any(run%prob%sc%bodies(:)%finite)) kinematics = 'finite strain of the hyperelastic bodies ' // &
      '(total Lagrangian, Newton), small deformation of the others'
    if (run%prob%deck%axisymmetric) then
      call say(run%log, 'model    axisymmetric (x = r, y = z), ' // family // ' elasticity, ' // kinematics // '; ' // &
               'loads per unit area and volume, u_r = 0 on the axis; every force is for the full circle (2 pi r)')
    else if (run%prob%deck%plane_stress) then
      call say(run%log, 'model    plane stress, ' // family // ' elasticity, ' // kinematics)
    else
      call say(run%log, 'model    plane strain, ' // family // ' elasticity, ' // kinematics)
    end if
    do b = 1, size(run%prob%sc%bodies)
      ! the body name is as long as the deck made it: not part of the buffer
      write(line, '(i0,a,i0,a,i0,a)') run%prob%sc%bodies(b)%mesh%nnode, ' nodes, ', run%prob%sc%bodies(b)%mesh%nelem, &
        ' elements (', count(run%prob%sc%bodies(b)%mesh%nen == 4 .or. run%prob%sc%bodies(b)%mesh%nen >= 8), ' quadrilaterals)'
      call say(run%log, 'body     ' // run%prob%sc%bodies(b)%name // ': ' // trim(line))
      call report_formulation(run, b)
    end do
    call report_supports(run)
    if (run%prob%sc%reused_meshes > 0) call say(run%log, 'mesh     ' // int_to_str(run%prob%sc%reused_meshes) // &
      ' .geo mesh(es) ' // &
      'read from the mesh cache ' // run%opts%gmsh%cache // ' (the same .geo, parameters and gmsh; --no-mesh-cache: mesh again)')
    call report_gmsh(run)
    call report_rigids(run)
    do ip = 1, run%prob%cs%npair
      write(line, '(a,i0,a,i0,a,i0,a,i0,a)') 'contact  pair ', ip, ': ', size(run%prob%cs%pair(ip)%snode), &
        ' slave nodes, ', size(run%prob%cs%pair(ip)%mnode), ' master nodes, ', run%prob%cs%pair(ip)%nrow, ' constrained (mortar, '
      if (run%prob%cs%pair(ip)%spec%rigid > 0) write(line, '(a,i0,a,i0,a,i0,a)') 'contact  pair ', ip, ': ', &
        size(run%prob%cs%pair(ip)%snode), ' slave nodes against RIGID ' // &
          run%prob%sc%rigids(run%prob%cs%pair(ip)%spec%rigid)%name // &
        ' (its exact shape), ', run%prob%cs%pair(ip)%nrow, ' constrained (mortar, '
      call say(run%log, trim(line) // ' ' // friction_law(run%prob%deck%contacts(ip)%friction, run%prob%cs%pair(ip)%spec) // ')')
      associate(pr => run%prob%cs%pair(ip), mo => run%prob%cs%pair(ip)%mortar)
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
            call say(run%log, trim(line))
            write(line, '(a,i0,a,i0,a)') 'contact  pair ' // int_to_str(ip) // ': quadratic mortar, slave degree ', &
              pr%degree(1), ', master degree ', pr%degree(2), ': non-penetration at every trace node'
            if (pr%spec%rigid > 0) write(line, '(a,i0,a)') 'contact  pair ' // int_to_str(ip) // &
              ': quadratic mortar, slave degree ', pr%degree(1), ' against the exact shape: non-penetration at ' // &
              'every trace node'
          end if
          if (has_friction(pr%spec)) then
            ! the assumption the frictional rows rest on (doc/theory.md, "Friction on curved surfaces")
            call say(run%log, trim(line))
            write(line, '(a,f5.3,a)') 'contact  pair ' // int_to_str(ip) // ': rows along the common normal ' // &
              'w n_slave - (1 - w) n_master, w = ', pr%slave_weight, ' (from the two sides'' curvatures)'
          end if
        else
          line = 'contact  pair ' // int_to_str(ip) // ': the master faces no slave segment (no contact possible)'
        end if
        call say(run%log, trim(line))
      end associate
    end do
    if (any(run%prob%sc%bodies(:)%finite)) then
      call say(run%log, 'steps    ' // int_to_str(run%prob%sc%steps) // ' load steps in order (finite strain: ' // &
        'Newton''s method from the last step''s state, a new tangent and contact geometry at each iterate; ' // &
        'a step that fails is halved)')
      associate (sv => run%prob%deck%solver)
        method = 'lemke'
        if (allocated(sv%newton_lcp)) method = sv%newton_lcp
        call say(run%log, 'newton   converged: residual <= newton_tol = ' // format_number(sv%newton_tol) // &
          ' of the load, the last correction <= ' // format_number(sv%newton_tol) // ' of the displacement' // &
          ' (the linearized gaps then exact to its square), within newton_maxit = ' // int_to_str(sv%newton_maxit) // &
          ' iterations; each iterate''s contact problem by newton_lcp = ' // method)
      end associate
    else if (run%prob%sc%steps > 1 .and. run%prob%cs%ntan > 0) then
      call say(run%log, 'steps    ' // int_to_str(run%prob%sc%steps) // &
        ' load steps (friction: the answer depends on the load path)')
    else if (run%prob%sc%steps > 1 .and. any(run%prob%sc%specs%finite)) then
      call say(run%log, 'steps    ' // int_to_str(run%prob%sc%steps) // ' load steps in order (sliding=finite: each step ' // &
               'in the contact geometry it reaches; one factorization for all)')
    else if (run%prob%sc%steps > 1 .and. run%prob%deck%output%steps_all) then
      call say(run%log, 'steps    ' // int_to_str(run%prob%sc%steps) // &
        ' load steps, each solved at its load factors (without ' // &
               'friction the steps are independent; one factorization for all)')
    else if (run%prob%sc%steps > 1) then
      call say(run%log, 'steps    ' // int_to_str(run%prob%sc%steps) // &
        ' load steps declared; without friction the answer does not ' // &
               'depend on the load path: the final step alone is solved')
    end if
    do ip = 1, run%prob%fl%k
      if (any(run%prob%split%unheld_body == run%prob%fl%mode_body(ip))) then
        call say(run%log, 'rigid    body ' // run%prob%sc%bodies(run%prob%fl%mode_body(ip))%name // ': ' // mode_name(run%prob%fl, &
          ip) // ' not held by FIX')
      else
        call say(run%log, 'rigid    body ' // run%prob%sc%bodies(run%prob%fl%mode_body(ip))%name // ': ' // &
          mode_name(run%prob%fl, ip) // &
                 ' not held by FIX: held by contact (equilibrium as an equality constraint)')
      end if
    end do
    do ip = 1, size(run%prob%split%unheld, 2)
      b = run%prob%split%unheld_body(ip)
      how = '(the contact normals do not resist it)'
      if (run%prob%split%tau(b) > 1.0e-10_dp) how = '(the contact normals do not resist it beyond the contact ' // &
        'polygon''s median turning angle, ' // real_to_str(run%prob%split%tau(b)) // ' rad)'
      call say(run%log, 'rigid    body ' // run%prob%sc%bodies(b)%name // ': ' // motion_name(run%prob%fl, &
        run%prob%split%unheld(:, ip)) // &
        ' held by neither FIX nor contact ' // how // '; ' // int_to_str(count(run%prob%fl%mode_body == b) - &
        count(run%prob%split%unheld_body == b)) // ' other combination(s) held by contact')
    end do
    write(line, '(a,i0,a,i0,a,i0,a)') 'sizes    ', run%prob%sc%ndof, ' dofs, ', run%prob%nfree, ' free, ', run%prob%cs%nrow, &
      ' contact constraints'
    call say(run%log, trim(line))
    if (len(run%opts%thread_note) > 0) call say(run%log, 'threads  ' // run%opts%thread_note)
    ! a key kept so that old decks still read: say that it does nothing
    if (allocated(run%prob%deck%solver%cut)) call say(run%log, 'note     SOLVER cut=' // run%prob%deck%solver%cut // &
      ' is ignored: no body is cut any more (doc/performance.md, "A body cut in two: removed")')
  end subroutine report_scene

  !> The run log's line of the formulation of body b when its material is
  !> nearly incompressible (isotropic, nu > locking_nu): B-bar on the
  !> element kinds that take it (body, elements' pressure_modes), and why
  !> the others are left as they are; a hyperelastic body whose initial nu
  !> is above locking_nu (bd%bbar): F-bar on every kind but the 3-node
  !> triangle (finite_strain_assembly).  Nothing for the other bodies.
  subroutine report_formulation(run, b)
    type(run_t), intent(inout) :: run
    integer, intent(in) :: b
    character(len=:), allocatable :: text, nu
    integer :: k, count_k
    integer, parameter :: kinds_nen(5) = [4, 8, 9, 3, 6]
    character(len=*), parameter :: kind_name(5) = [character(len=20) :: '4-node quadrangles', '8-node quadrangles', &
                                                   '9-node quadrangles', '3-node triangles', '6-node triangles']
    associate (mat => run%prob%deck%bodies(b)%material, bd => run%prob%sc%bodies(b))
      if (.not. allocated(mat%kind)) return
      if (bd%finite .and. bd%bbar) then
        text = ''
        do k = 1, size(kinds_nen)
          count_k = count(bd%mesh%nen == kinds_nen(k))
          if (count_k == 0) cycle
          if (len(text) > 0) text = text // '; '
          text = text // merge('displacement on           ', 'F-bar (mean dilatation) on', kinds_nen(k) == 3)
          text = trim(text) // ' ' // int_to_str(count_k) // ' ' // trim(kind_name(k))
          if (kinds_nen(k) == 3) text = text // ' (they lock as K / mu grows)'
        end do
        call say(run%log, 'body     ' // bd%name // ': formulation: ' // text // ', finite strain, initial nu > ' // &
                 format_number(locking_nu))
        return
      end if
      if (mat%kind /= 'isotropic' .or. mat%nu <= locking_nu) return
      nu = 'nu = ' // format_number(mat%nu) // ' > ' // format_number(locking_nu)
      if (.not. bd%bbar) then
        call say(run%log, 'body     ' // bd%name // ': formulation: displacement, ' // nu // ' in plane stress (the ' // &
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
      call say(run%log, 'body     ' // bd%name // ': formulation: ' // text // ', ' // nu)
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
    if (run%prob%deck%axisymmetric) unit = 'per unit area'
    do b = 1, size(run%prob%sc%bodies)
      associate (bd => run%prob%sc%bodies(b), bdeck => run%prob%deck%bodies(b))
        do k = 1, size(bdeck%loads)
          if (bdeck%loads(k)%kind /= load_point) cycle
          ib = find_name(bd%mesh%bnd, bdeck%loads(k)%boundary)
          call boundary_nodes(bd%mesh%bnd(ib), nodes)
          call say(run%log, 'force    ' // bd%name // ':' // bdeck%loads(k)%boundary // ': point force (fx, fy) = (' // &
            trim(format_number(bdeck%loads(k)%tx)) // ', ' // trim(format_number(bdeck%loads(k)%ty)) // ') at ' // &
            int_to_str(size(nodes)) // ' node(s)')
        end do
        do k = 1, size(bdeck%springs)
          associate (sp => bdeck%springs(k))
            nk = 0                                  ! its spring elements
            if (bd%springs%n > 0) nk = count(bd%springs%owner(1:bd%springs%n) == k)
            if (sp%point) then
              call say(run%log, 'spring   ' // bd%name // ':' // sp%boundary // ': to the ground, kx = ' // &
                trim(format_number(sp%kx)) // ', ky = ' // trim(format_number(sp%ky)) // ' at ' // &
                int_to_str(nk) // ' node(s)')
            else
              call say(run%log, 'spring   ' // bd%name // ':' // sp%boundary // ': elastic foundation, kn = ' // &
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
    do r = 1, size(run%prob%sc%rigids)
      associate (sh => run%prob%sc%rigids(r))
        select case (run%prob%deck%rigids(r)%shape)
        case ('circle')
          write(line, '(a,g0.6,a,g0.6,a,g0.6,a)') 'circle of radius ', sh%radius, ' centred at (', sh%centre(1), ', ', &
            sh%centre(2), ')'
          if (sh%outside) then
            line = trim(line) // ', solid outside (a hole)'
          else
            line = trim(line) // ', solid inside'
          end if
        case default
          write(line, '(a,i0,a)') run%prob%deck%rigids(r)%shape // ' of ', size(sh%pt, 2), ' points'
        end select
        write(line(len_trim(line) + 1:), '(a,g0.6,a,g0.6,a)') ', reference point (', sh%ref(1), ', ', sh%ref(2), ')'
        call say(run%log, 'rigid    ' // sh%name // ': ' // trim(line))
        how = ''
        do j = 1, 3
          if (run%prob%deck%axisymmetric .and. j /= 2) then
            how = how // ', ' // dname(j) // ' held (PLANE axisymmetric: along the axis only)'
          else if (run%prob%sc%fixed(sh%dof0 + j)) then
            how = how // ', ' // dname(j) // ' prescribed'
          else
            how = how // ', ' // dname(j) // ' free'
            do k = 1, run%prob%rsplit%k
              if (run%prob%rsplit%dof(k) == sh%dof0 + j .and. run%prob%sc%fext(sh%dof0 + j) /= 0.0_dp) how = how // ' (FORCE)'
            end do
          end if
        end do
        if (size(run%prob%deck%rigids(r)%fixes) + size(run%prob%deck%rigids(r)%forces) == 0) then
          call say(run%log, 'rigid    ' // sh%name // ': held fixed (no FIX, no FORCE)')
        else if (all(run%prob%sc%fixed(sh%dof0 + 1:sh%dof0 + 3))) then
          call say(run%log, 'rigid    ' // sh%name // ': ' // how(3:))
        else
          call say(run%log, 'rigid    ' // sh%name // ': ' // how(3:) // ' (a free direction is held by contact alone: ' // &
                   'its equilibrium is an equality of the contact problem)')
        end if
      end associate
    end do
    do j = 1, size(run%prob%rsplit%unheld, 2)
      if (run%prob%rsplit%loaded(j)) cycle
      call say(run%log, 'note     RIGID ' // run%prob%sc%rigids(run%prob%rsplit%unheld_owner(j))%name // ': free direction (' // &
        rigid_direction(run%prob%rsplit, run%prob%rsplit%unheld(:, j)) // &
          ') held by neither FIX nor contact and unloaded: its ' // &
        'motion is set to 0 (the contact normals do not resist it)')
    end do
  end subroutine report_rigids

  !> The run log's `param    name = value (origin)` lines; the summary's
  !> `parameter NAME VALUE` lines.
  subroutine report_parameters(run)
    type(run_t), intent(inout) :: run
    integer :: k
    character(len=:), allocatable :: value
    allocate(run%res%parameter(run%prob%deck%params%n))
    do k = 1, run%prob%deck%params%n
      value = format_number(run%prob%deck%params%value(k))
      run%res%parameter(k)%s = trim(run%prob%deck%params%name(k)) // ' ' // value
      call say(run%log, 'param    ' // trim(run%prob%deck%params%name(k)) // ' = ' // value // ' (' // &
        trim(run%prob%deck%params%origin(k)) // ')')
    end do
  end subroutine report_parameters

  subroutine report_run(run)
    type(run_t), intent(inout) :: run
    character(len=200) :: line
    integer :: p
    if (run%prob%cs%nrow > 0) then
      write(line, '(a,i0,a,i0,a,es10.3,a,es10.3)') 'lcp      ' // run%res%lcp_method // ': ', run%res%lcp_iterations, &
        ' iterations, ', run%res%active_nodes, ' active nodes, residual ', run%res%lcp_residual, &
        ', complementarity ', run%res%complementarity
      if (run%res%lcp_method == 'lemke' .and. run%res%lcp_iterations > 0) then
        ! Lemke's cost per pivot: O(n^2) on its dense tableau (performance.md)
        write(line(len_trim(line) + 1:), '(a,es9.3,a)') ', ', &
          run%log%time(ph_lcp) / run%res%lcp_iterations, ' s per pivot'
      end if
      call say(run%log, trim(line))
      write(line, '(a,es12.4,a,es12.4)') 'contact  min gap ', run%res%min_gap, ', min pressure ', run%res%min_pressure
      call say(run%log, trim(line))
      call report_zones(run)
    end if
    do p = 1, size(run%prob%sc%rigids)
      write(line, '(a,3es12.4,a,3es12.4)') ': motion (ux, uy, rz) =', run%res%rigid(1:3, p), &
        ', contact force on it (fx, fy, m) =', run%res%rigid(4:6, p)
      call say(run%log, 'rigid    ' // run%prob%sc%rigids(p)%name // trim(line))
    end do
    write(line, '(a,es16.8,a,i0)') 'energy   ', run%res%energy, ',  nnz(L) ', run%res%factor_nnz
    call say(run%log, trim(line) // ' (' // run%res%ordering // '),  peak memory ' // &
             fixed_to_str(run%res%memory_peak / 1048576.0_dp, 1) // ' MB')
    if (run%res%estimated) then
      write(line, '(a,f8.3,a)') 'estimate energy-norm error of u ', 100 * run%res%estimate_energy, &
        ' % (stress recovery; error_indicator in the VTK)'
      call say(run%log, trim(line))
      do p = 1, size(run%res%estimate_pressure)
        if (run%res%estimate_pressure(p) < 0.0_dp) then
          write(line, '(a,i0,a)') 'estimate pair ', p, ': no node in contact, no pressure to estimate'
        else
          write(line, '(a,i0,a,f8.3,a)') 'estimate pair ', p, ': L2 error of the contact pressure ', &
            100 * run%res%estimate_pressure(p), ' %'
        end if
        call say(run%log, trim(line))
      end do
    else
      call say(run%log, 'estimate off (ESTIMATE off): the run does not estimate its error')
    end if
    if (run%res%factor_parts > 1) then
      write(line, '(a,i0,a)') 'factor   ', run%res%factor_parts, ' parts (blocks of K that no entry couples: the bodies)'
      if (run%res%factor_threads > 1) then
        write(line, '(a,i0,a)') trim(line) // ' ordered and factorized side by side on ', &
          run%res%factor_threads, ' threads'
      else
        line = trim(line) // ' ordered and factorized one after the other'
      end if
      call say(run%log, trim(line))
    end if
    if (allocated(run%res%condense_text)) then
      if (len(run%res%condense_text) > 0) call say(run%log, 'condense W from L_cc by body: ' // run%res%condense_text)
    end if
    call say(run%log, 'phase        seconds')
    do p = 1, nphase
      write(line, '(a,f12.4)') phase_names(p), run%log%time(p)
      call say(run%log, trim(line))
    end do
    if (run_threads() > 1) then
      write(line, '(a,f8.3,a,f8.3,a)') ' ordering (', run%res%time_ordering, &
        ' s, in factor) and the assembly of K (', run%res%time_assemble_values, ' s) ran side by side'
      call say(run%log, 'overlap  the ' // run%res%ordering // trim(line))
    end if
    do p = 1, size(run%out%wrote)
      call say(run%log, trim(run%out%wrote(p)))          ! the files run_outputs wrote
    end do
  end subroutine report_run

  !> Per pair, the summary's contact_zone, peak_pressure and stick_zone in
  !> words: `contact  pair 1: in contact from (x0, y0) to (x1, y1), length L,
  !> peak pressure P at (x, y)`, and `stick from ... to ..., length L`; a line
  !> per zone, named `pair 1, zone 2 of 3` when there are several.
  subroutine report_zones(run)
    type(run_t), intent(in) :: run
    character(len=240) :: line
    integer :: p, j
    if (.not. allocated(run%res%zones)) return
    do p = 1, size(run%res%zones)
      associate(z => run%res%zones(p))
        if (z%contact%count == 0) then
          call say(run%log, 'contact  pair ' // int_to_str(p) // ': no node in contact')
          cycle
        end if
        do j = 1, z%contact%count
          line = zone_words(p, 'in contact', z%contact, j)
          write(line(len_trim(line) + 1:), '(a,es11.4,a,es11.4,a,es11.4,a)') ', peak pressure', z%peak(1, j), ' at (', &
            z%peak(2, j), ', ', z%peak(3, j), ')'
          call say(run%log, trim(line))
        end do
        if (.not. z%friction) cycle
        if (z%stick%count == 0) then
          call say(run%log, 'contact  pair ' // int_to_str(p) // ': no node sticks')
          cycle
        end if
        do j = 1, z%stick%count
          call say(run%log, trim(zone_words(p, 'stick', z%stick, j)))
        end do
      end associate
    end do
  end subroutine report_zones

  !> Zone j of report_zones in words: `contact  pair P: WHAT from (x0, y0)
  !> to (x1, y1), length L`, the pair `pair P, zone J of N` when it has
  !> several.
  !>   p    (in) the pair
  !>   what (in) 'in contact' or 'stick'
  !>   zone (in) the zones, count > 0
  !>   j    (in) the zone, 1 .. count
  function zone_words(p, what, zone, j) result(line)
    integer, intent(in) :: p, j
    character(len=*), intent(in) :: what
    type(zone_t), intent(in) :: zone
    character(len=240) :: line
    character(len=:), allocatable :: who
    who = 'contact  pair ' // int_to_str(p)
    if (zone%count > 1) who = who // ', zone ' // int_to_str(j) // ' of ' // int_to_str(zone%count)
    write(line, '(a,2(a,es11.4,a,es11.4,a),a,es11.4)') who // ': ' // what, &
      ' from (', zone%x0(1, j), ', ', zone%x0(2, j), ')', ' to (', zone%x1(1, j), ', ', zone%x1(2, j), ')', &
      ', length', zone%length(j)
  end function zone_words

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


  !> How gmsh made the run's meshes (module gmsh_runner): through the mesher
  !> or a process each, and in which sandbox.
  subroutine report_gmsh(run)
    type(run_t), intent(in) :: run
    integer :: served, alone
    logical :: sandboxed
    character(len=:), allocatable :: how
    call gmsh_runs(served, alone, sandboxed)
    if (served + alone == 0) return
    how = ''
    if (served > 0) how = int_to_str(served) // ' by contact2d-mesher (libgmsh, one process for them)'
    if (served > 0 .and. alone > 0) how = how // ', '
    if (alone > 0) how = how // int_to_str(alone) // ' by a gmsh process each'
    if (sandboxed) then
      how = how // '; in the sandbox (bubblewrap)'
    else if (run%opts%gmsh%trust_geo) then
      how = how // '; no sandbox (--trust-geo)'
    else
      how = how // '; no sandbox (bubblewrap cannot make namespaces here; the .geo screen alone)'
    end if
    call say(run%log, 'mesh     ' // int_to_str(served + alone) // ' .geo mesh(es) made by gmsh: ' // how)
  end subroutine report_gmsh

end module run_report
