!> adaptivity: ADAPT, the adaptive loop around a run's solve.
!>
!> After the solve of a mesh and its error estimate, the loop records the
!> step (`adapt STEP dofs N estimate REL cpu SECONDS`) and stops when the
!> estimate of the chosen quantity is below the target, or a limit is hit
!> (max_steps, max_dofs, an estimate that no longer falls, gmsh failing):
!> the outputs are then this last mesh's.  Otherwise every body is meshed
!> again by gmsh from its .geo, with the sizes of the optimal mesh for the
!> target (module size_field) as a background mesh (gmsh -bgm), and the run
!> starts again from the scene on the new meshes.
!>
!> What it aims at.  quantity=energy: the energy error target, times 0.85
!> so that one step usually suffices.  quantity=pressure: the pressure
!> error is the contact zones' ends', where the energy indicators ask for
!> little, so the zones are sized as a hand-graded mesh is (refine_zones:
!> the strip's size cut by target / estimate, growing linearly away from
!> it), and the bulk keeps the energy indicators' field, aimed at the energy
!> error cut by the square root of that ratio (bulk_rate; doc/theory.md).
!> The energy rates are the elements' orders, or the rate observed between
!> the last two meshes when lower (a singularity's).  One step refines an
!> element at most 8 times (the zones' strips at most 200 times) and
!> coarsens it at most 4 times.
!>
!> The load history.  Each mesh is solved with the deck's whole history
!> (every load step): with friction the final state depends on it, and
!> without, a deck's STEPS are its own choice.  A deck that wants a cheaper
!> loop gives the adaptive run one step and re-runs the history on the final
!> mesh, which is kept for that (NAME_BODY.msh next to the outputs).
!>
!> Why it exists: the program reads "solve, estimate, adapt again"; the
!> bookkeeping of the loop (restarting the run on new meshes, what survives
!> from one mesh to the next, the meshes kept) is here.  Who may use it: the
!> program.
!>
!> Programming interface
!>   check_adaptable(run)   with ADAPT, every body's mesh is one gmsh can make again:
!>                          a .geo, or an .msh with its .geo beside it (else exit 2)
!>   adapt_mesh(run)        after a solve and its estimate: .true. when the bodies were
!>                          meshed again and the run must solve again
!>   fall_back(run, err)    a mesh failed: with ADAPT, back to the last mesh that solved (its
!>                          outputs, a warning); else, and on the first mesh, the run ends
!>   keep_meshes(run)       the final meshes next to the outputs, NAME_BODY.msh
module adaptivity
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, add_error
  use exits, only: stop_input_errors, exit_program, fail_numerical, stop_on
  use run_state, only: run_t, kept_mesh_t
  use run_log, only: say, add_warning
  use run_estimate, only: element_rates
  use run_phase, only: enter_phase
  use deck_types, only: mesh_spec_t
  use mesh, only: is_quadratic
  use elements, only: corner_count
  use mesh_rect, only: write_rect_geo
  use geo_screen, only: screen_geo
  use gmsh_runner, only: mesh_geo_file
  use size_field, only: optimal_scales, element_count, element_size, write_background
  use sparse_cholesky, only: free_factor
  use safe_files, only: file_kind, c2d_regular, private_folder, real_path, read_file, temporary_t, create_temporary, &
                        close_temporary, commit_temporaries, discard_temporaries
  use system_binding, only: c2d_cpu_seconds
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private
  public :: check_adaptable, adapt_mesh, fall_back, keep_meshes

  real(dp), parameter :: aim = 0.85_dp                 !< the fraction of the target one step aims at
  real(dp), parameter :: finest = 0.125_dp, coarsest = 4.0_dp   !< one step's bounds on the size's change
  !> the share of max_dofs a mesh is aimed at: gmsh's meshes come out a few
  !> percent off the count asked (1.1-1.5 % over at 500,000 dofs, bench/peers.sh)
  real(dp), parameter :: dofs_margin = 0.9_dp
  !> quantity=pressure: the fraction of the target the zone's size aims at, on linear and on quadratic
  !> traces (the error at a free end moves with where the end falls in its elements, the coarse first
  !> mesh's estimate included: aimed this low, the next mesh lands below the target, and a further mesh,
  !> which costs as much as the one before, is rarely needed; a quadratic trace's estimate is the end's
  !> alone and swings the most, a linear trace's has the bulk's share, which bulk_rate takes below the
  !> target), the smallest size ratio asked there in one step (low enough not to cap a first step from a
  !> coarse quadratic zone to a target 100 times below its estimate), the zone size's growth with the
  !> distance from the zone on linear and on quadratic traces (the hand-graded mesh's 0.2 on linear ones,
  !> doc/accuracy-cost.md; a quadratic trace's end error does not change when its neighbours grow twice
  !> as fast, for a third fewer dofs), and kappa in e_p ~ e_E^kappa for the energy error asked of the
  !> bulk (measured on Hertz, P1 and P2: the bulk's share of the pressure error falls about as e_E^2)
  real(dp), parameter :: aim_linear = 0.75_dp, aim_quadratic = 0.6_dp, zone_finest = 0.005_dp, &
                         slope_linear = 0.2_dp, slope_quadratic = 0.4_dp, bulk_rate = 2.0_dp
  !> quantity=pressure on linear elements: the bulk's energy goal need not be below
  !> bulk_linear sqrt(aim target).  The pressure estimate is sqrt(e_zone^2 + E^4), E the energy
  !> estimate (doc/theory.md, "The contact pressure"), so E^2 = bulk_linear^2 aim target leaves the
  !> bulk a quarter of the squared budget (bulk_linear^4 = 0.24) and the zone the rest; bulk_rate's
  !> goal, taken from the coarse first mesh's estimate (the zone's ends' error), asks the bulk for
  !> about half that E, and four times the bulk's dofs: on Hertz P1 from hc 0.05, 97,344 dofs and
  !> 0.20 % at a 0.3 % target against 41,190 dofs and 0.23 % with this floor
  !> (doc/accuracy-cost.md).  A quadratic body's E is small and its E^2 negligible: its goal stays.
  real(dp), parameter :: bulk_linear = 0.7_dp
  real(dp), parameter :: stall = 0.95_dp               !< an estimate above stall times the last one: no progress

contains

  !> With ADAPT, the mesh of every body as gmsh makes it again: its .geo
  !> (MESH rect is refused by the deck's checks), or for an .msh the .geo of
  !> the same name beside it; else exit 2 at the MESH line.
  !>   run (inout) the deck on entry; run%adapt%geo on exit
  subroutine check_adaptable(run)
    type(run_t), intent(inout) :: run
    character(len=:), allocatable :: geo, work
    type(error_t), allocatable :: err
    integer :: b
    if (.not. run%prob%deck%adapt%on) return
    allocate(run%adapt%geo(size(run%prob%deck%bodies)))
    do b = 1, size(run%prob%deck%bodies)
      associate (ms => run%prob%deck%bodies(b)%mesh)
        run%adapt%geo(b) = ms
        if (ms%is_geo) cycle
        if (ms%kind == 'rect') then           ! the rectangle as a .geo of the run's own
          call private_folder(work, err)
          if (.not. allocated(err)) call write_rect_geo(ms%x0, ms%y0, ms%x1, ms%y1, ms%elem, &
            run%prob%deck%bodies(b)%name, work // '/rect_' // run%prob%deck%bodies(b)%name // '.geo', err)
          if (allocated(err)) call fail_numerical('ADAPT: ' // err%message)
          run%adapt%geo(b)%kind = 'gmsh'
          run%adapt%geo(b)%path = work // '/rect_' // run%prob%deck%bodies(b)%name // '.geo'
          run%adapt%geo(b)%is_geo = .true.
          run%adapt%geo(b)%order = merge(2, 1, ms%elem == 'tri6' .or. ms%elem == 'quad8' .or. ms%elem == 'quad9')
          run%adapt%geo(b)%set_names = [character(len=64) ::]
          run%adapt%geo(b)%set_values = [real(dp) ::]
          call say(run%log, 'adapt    body ' // run%prob%deck%bodies(b)%name // ': MESH rect re-meshed by gmsh (' // &
                   ms%elem // ', unstructured) from the second mesh on')
          cycle
        end if
        geo = ms%path(1:len(ms%path) - 4) // '.geo'
        if (file_kind(geo) == c2d_regular) then
          run%adapt%geo(b)%path = geo
          run%adapt%geo(b)%is_geo = .true.
          call say(run%log, 'adapt    body ' // run%prob%deck%bodies(b)%name // ': re-meshed from ' // &
                   ms%file(1:len(ms%file) - 4) // '.geo, beside its mesh ' // ms%file)
        else
          call add_error(run%diag, run%prob%deck%file, ms%line, 'ADAPT re-meshes every body with gmsh, and body "' // &
            run%prob%deck%bodies(b)%name // '" has the mesh "' // ms%file // '" without its .geo (expected ' // &
            ms%file(1:len(ms%file) - 4) // '.geo beside it, or MESH gmsh file=NAME.geo)')
        end if
      end associate
    end do
    call stop_input_errors(run%diag)
    run%adapt%cpu0 = 0.0_dp                    ! the first mesh's step: from the program's start
  end subroutine check_adaptable

  !> After the solve of a mesh and its estimate: record the step, stop (the
  !> outputs are this mesh's) or mesh every body again and start the run
  !> over (module header).
  !>   run (inout) the results and the estimate on entry; a fresh run on the
  !>               new meshes when the result is .true.
  logical function adapt_mesh(run) result(again)
    type(run_t), intent(inout) :: run
    real(dp) :: est, cpu, dofs, prev
    again = .false.
    if (.not. run%prob%deck%adapt%on) return
    associate (a => run%adapt, ad => run%prob%deck%adapt)
      a%step = a%step + 1
      est = quantity_estimate(run)
      cpu = c2d_cpu_seconds() - a%cpu0
      dofs = real(run%prob%sc%ndof, dp)
      call record_step(run, dofs, est, cpu)
      prev = huge(1.0_dp)                      ! the last mesh's estimate (none before the first)
      if (a%step > 1) prev = run%res%adapt(2, a%step - 1)
      if (est < 0.0_dp) then
        call finish(run, 'stopped no_estimate', 'ADAPT quantity=pressure: no pair has a zone in contact, ' // &
                    'no pressure error to adapt to; the results are those of the deck''s mesh')
      else if (est <= ad%target) then
        call finish(run, 'reached', '')
      else if (est > prev .and. allocated(a%kept)) then
        ! the new mesh is worse than the last: its outputs would be a step back
        call restore_kept(run)
        call finish(run, 'stopped no_progress', 'ADAPT stopped: mesh ' // int_to_str(a%step) // &
          '''s estimate ' // real_to_str(est, 3) // ' is above mesh ' // int_to_str(a%step - 1) // '''s ' // &
          real_to_str(prev, 3) // ' (the outputs are those of mesh ' // &
          int_to_str(a%step - 1) // ', the lower estimate)')
      else if (a%capped) then
        call finish(run, 'stopped max_dofs', 'ADAPT stopped at max_dofs=' // int_to_str(ad%max_dofs) // &
          ': the target ' // real_to_str(ad%target, 3) // ' needs more dofs; the estimate reached is ' // &
          real_to_str(est, 3) // ' (the outputs are this last mesh''s, kept next to them)')
      else if (a%step >= ad%max_steps) then
        call finish(run, 'stopped max_steps', 'ADAPT stopped after max_steps=' // int_to_str(ad%max_steps) // &
          ' meshes above the target ' // real_to_str(ad%target, 3) // ': the estimate reached is ' // &
          real_to_str(est, 3) // ' (the outputs are this last mesh''s)')
      else if (est > stall * prev) then
        call finish(run, 'stopped no_progress', 'ADAPT stopped: the estimate ' // real_to_str(est, 3) // &
          ' fell by less than 5 % from the last mesh''s ' // real_to_str(prev, 3) // &
          ' (the outputs are this last mesh''s)')
      else
        again = remesh(run, est)
      end if
    end associate
  end function adapt_mesh

  !> The estimate ADAPT watches: the energy error, or the largest pressure
  !> error over the pairs in contact (< 0 when none is).
  real(dp) function quantity_estimate(run) result(est)
    type(run_t), intent(in) :: run
    if (run%prob%deck%adapt%quantity == 'pressure') then
      est = -1.0_dp
      if (allocated(run%res%estimate_pressure)) then
        if (size(run%res%estimate_pressure) > 0) est = maxval(run%res%estimate_pressure)
      end if
    else
      est = run%res%estimate_energy
    end if
  end function quantity_estimate

  !> One `adapt` line: the summary's (res%adapt) and the run log's.
  subroutine record_step(run, dofs, est, cpu)
    type(run_t), intent(inout) :: run
    real(dp), intent(in) :: dofs, est, cpu
    real(dp), allocatable :: rows(:,:)
    integer :: n
    n = 0
    if (allocated(run%res%adapt)) n = size(run%res%adapt, 2)
    allocate(rows(3, n + 1))
    if (n > 0) rows(:, 1:n) = run%res%adapt
    rows(:, n + 1) = [dofs, est, cpu]
    call move_alloc(rows, run%res%adapt)
    call say(run%log, 'adapt    mesh ' // int_to_str(run%adapt%step) // ': ' // int_to_str(nint(dofs)) // ' dofs, ' // &
             run%prob%deck%adapt%quantity // ' error estimate ' // real_to_str(100 * est, 4) // ' %, ' // &
             real_to_str(cpu, 3) // ' s CPU (gmsh''s included)')
  end subroutine record_step

  !> The loop ends here: adapt_result, and a warning unless the target was reached.
  subroutine finish(run, result, warning)
    type(run_t), intent(inout) :: run
    character(len=*), intent(in) :: result, warning
    run%res%adapt_result = result
    call say(run%log, 'adapt    ' // result // ' (target ' // real_to_str(run%prob%deck%adapt%target, 3) // ', ' // &
             run%prob%deck%adapt%quantity // ')')
    if (len(warning) > 0) call add_warning(run%log, 'adapt_stopped', warning)
  end subroutine finish

  !> Mesh every body again for the target (module header) and start the run
  !> over on the new meshes; .false. (and the loop ends, these results kept)
  !> when gmsh cannot.
  logical function remesh(run, est) result(done)
    type(run_t), intent(inout) :: run
    real(dp), intent(in) :: est
    type(error_t), allocatable :: err
    real(dp), allocatable :: rate(:), s(:), h(:), cap(:)
    character(len=:), allocatable :: work, stem, deck_folder
    real(dp) :: goal, predicted, hmin, hmax
    integer :: b, e, e0
    logical :: found
    done = .false.
    call enter_phase('re-meshing (ADAPT)')
    associate (a => run%adapt, ad => run%prob%deck%adapt)
      a%cpu0 = c2d_cpu_seconds()                  ! gmsh's re-meshing is the next mesh's cost
      a%time0 = run%log%cpu
      goal = aim * ad%target
      if (ad%quantity == 'pressure') goal = run%res%estimate_energy * (aim * ad%target / est)**(1 / bulk_rate)
      if (ad%quantity == 'pressure' .and. .not. any([(is_quadratic(run%prob%sc%bodies(b)%mesh), &
                                                       b = 1, size(run%prob%sc%bodies))])) &
        goal = max(goal, bulk_linear * sqrt(aim * ad%target))
      rate = element_rates(run%prob, run%res%estimate_energy, a%energy_prev, a%dofs_prev)
      allocate(s(run%prob%sc%nelem))
      call optimal_scales(run%res%error_indicator**2, rate, goal**2, finest, coarsest, s)
      allocate(cap(run%prob%sc%ndof / 2))
      cap = huge(1.0_dp)
      if (ad%quantity == 'pressure') call refine_zones(run, s, cap)
      predicted = run%prob%sc%ndof * element_count(s) / run%prob%sc%nelem
      if (predicted > dofs_margin * ad%max_dofs) then   ! as fine as max_dofs allows, and the loop's last mesh
        s = s * sqrt(predicted / (dofs_margin * ad%max_dofs))
        cap = huge(1.0_dp)       ! the zones' nodal sizes go too: their count is the rougher, and this mesh must fit
        a%capped = .true.
        call say(run%log, 'adapt    the target asks for about ' // int_to_str(nint(predicted)) // ' dofs: the next ' // &
                 'mesh is made coarser, within max_dofs=' // int_to_str(ad%max_dofs))
      end if
      a%energy_prev = run%res%estimate_energy
      a%pressure_prev = est
      a%dofs_prev = real(run%prob%sc%ndof, dp)
      call private_folder(work, err)
      call real_path(run%prob%deck%dir, deck_folder, found)
      if (.not. found) deck_folder = run%prob%deck%dir
      do b = 1, size(run%prob%sc%bodies)
        if (allocated(err)) exit
        associate (bd => run%prob%sc%bodies(b), g => a%geo(b), bdeck => run%prob%deck%bodies(b))
          if (.not. g%is_geo) cycle
          e0 = bd%elem0
          h = [(s(e0 + e) * element_size(bd%mesh, e), e = 1, bd%mesh%nelem)]
          stem = work // '/adapt' // int_to_str(a%step + 1) // '_' // bdeck%name
          call write_background(bd%mesh, bdeck%dx, bdeck%dy, h, stem // '.pos', hmin, hmax, err, &
                                cap(bd%dof0 / 2 + 1:bd%dof0 / 2 + bd%mesh%nnode))
          if (allocated(err)) exit
          if (.not. run%opts%gmsh%trust_geo .and. bdeck%mesh%kind == 'gmsh' .and. .not. bdeck%mesh%is_geo .and. &
              a%step == 1) then
            call screen_geo(g%path, deck_folder, run%diag)     ! the .geo found beside an .msh: screened once
            call stop_input_errors(run%diag)
          end if
          call mesh_geo_file(g%path, merge(2, 1, is_quadratic(bd%mesh)), g%set_names, g%set_values, run%opts%gmsh, &
                             deck_folder, stem // '.msh', stem // '.log', err, background=stem // '.pos', &
                             size_range=[0.5_dp * hmin, hmax])
          if (allocated(err)) then
            err%message = 'gmsh could not mesh body "' // bdeck%name // '" again: ' // err%message
            exit
          end if
          bdeck%mesh%kind = 'gmsh'
          bdeck%mesh%file = stem // '.msh'
          bdeck%mesh%path = stem // '.msh'
          bdeck%mesh%is_geo = .false.
        end associate
      end do
    end associate
    if (allocated(err)) then
      call finish(run, 'stopped remesh_failed', 'ADAPT stopped: ' // err%message // ' (the outputs are this ' // &
                  'last mesh''s)')
      return
    end if
    call restart(run)
    done = .true.
  end function remesh

  !> quantity=pressure: the sizes around every contact zone, on both sides,
  !> as an expert grades them by hand (doc/theory.md, "Adaptive meshes"):
  !> the pressure error is the zone's free ends' (O(h) at a square-root end,
  !> on linear and quadratic traces alike, from a/h = 1 to 14 on Hertz),
  !> where the energy indicators ask for little.  The strip of the zone (its
  !> slave nodes and one slave segment past each end) is given the size
  !> h_z = h_now * aim_zone * target / estimate_pair, h_now its longest slave
  !> element (the rate in h being 1; aim_zone is aim_linear or aim_quadratic
  !> by the slave's elements), and the size may grow away from the
  !> strip at most linearly, h_z + slope * d at the distance d (slope_linear
  !> or slope_quadratic likewise; measured
  !> where the solution has moved the nodes, as `moved` says why): a band
  !> along the trace, not a box of the zone's width in depth (which would
  !> cost that width squared over h_z^2 elements).  An element's ratio is
  !> only ever lowered here (the energy indicators' ask stays where finer).
  !> The size is set at the nodes: an element's mean, at its centroid, would
  !> leave the trace's nodes h_z + slope h / 3, many times h_z when the
  !> zone is refined much in one step.
  !>   run (in)    the solved mesh, its node pressures and pressure estimates
  !>   s   (inout) (nelem, every body) the size ratio of each element, for the count of the next
  !>               mesh: lowered to sqrt(cap_min cap_max) over its size, cap_min and cap_max its
  !>               corners' (the count of a size growing linearly across it is within a factor
  !>               2 of area / (cap_min cap_max); the mean of the caps would miss the fine layer)
  !>   cap (out)   (ndof / 2, every body) the largest size at each node (huge away from the zones)
  subroutine refine_zones(run, s, cap)
    type(run_t), intent(in) :: run
    real(dp), intent(inout) :: s(:)
    real(dp), intent(out) :: cap(:)
    real(dp), allocatable :: p(:,:)
    real(dp) :: hz, d, est, aim_zone, slope
    integer :: ip, k, b, e, ns, nc, np, n, n0
    logical, allocatable :: seg(:)
    cap = huge(1.0_dp)
    if (.not. allocated(run%res%node_pressure)) return
    do ip = 1, run%prob%cs%npair
      associate (pr => run%prob%cs%pair(ip))
        ns = size(pr%snode)
        if (ns < 2) cycle
        est = -1.0_dp
        ! the zone's own term: the bodies' share of estimate pressure
        ! (estimate_energy^2, run_estimate) is the bulk goal's to cut, not the strip's
        if (allocated(run%res%estimate_zone)) then
          if (size(run%res%estimate_zone) >= ip) est = run%res%estimate_zone(ip)
        end if
        if (est <= 0.0_dp) cycle
        ! the strip: the slave segments with a node in contact, and the next one past each end
        allocate(seg(ns - 1))
        do k = 1, ns - 1
          seg(k) = in_contact(k - 1) .or. in_contact(k) .or. in_contact(k + 1) .or. in_contact(k + 2)
        end do
        if (.not. any(seg)) then
          deallocate(seg)
          cycle
        end if
        hz = 0.0_dp
        np = 0
        allocate(p(4, count(seg)))
        do k = 1, ns - 1
          if (.not. seg(k)) cycle
          np = np + 1
          p(1:2, np) = moved(pr%spec%slave_body, pr%snode(k), pr%xs(:, k))
          p(3:4, np) = moved(pr%spec%slave_body, pr%snode(k + 1), pr%xs(:, k + 1))
          hz = max(hz, norm2(pr%xs(:, k + 1) - pr%xs(:, k)))
        end do
        ! on quadratic elements the trace's nodes are an element's corners and its midpoints
        aim_zone = aim_linear
        slope = slope_linear
        if (is_quadratic(run%prob%sc%bodies(pr%spec%slave_body)%mesh)) then
          hz = 2 * hz
          aim_zone = aim_quadratic
          slope = slope_quadratic
        end if
        hz = hz * max(zone_finest, aim_zone * run%prob%deck%adapt%target / est)
        do b = 1, size(run%prob%sc%bodies)
          if (b /= pr%spec%slave_body .and. b /= pr%spec%master_body) cycle
          associate (m => run%prob%sc%bodies(b)%mesh, e0 => run%prob%sc%bodies(b)%elem0)
            n0 = run%prob%sc%bodies(b)%dof0 / 2
            do n = 1, m%nnode
              d = huge(1.0_dp)
              do k = 1, np
                d = min(d, segment_distance(moved(b, n, m%x(:, n)), p(1:2, k), p(3:4, k)))
              end do
              cap(n0 + n) = min(cap(n0 + n), hz + slope * d)
            end do
            do e = 1, m%nelem
              nc = corner_count(m%nen(e))
              s(e0 + e) = min(s(e0 + e), max(zone_finest, sqrt(minval(cap(n0 + m%conn(1:nc, e))) * &
                                                          maxval(cap(n0 + m%conn(1:nc, e)))) / element_size(m, e)))
            end do
          end associate
        end do
        deallocate(seg, p)
      end associate
    end do
  contains
    !> Node n of body b where the solution has moved it, x + u: the distances
    !> to the strip are measured there, where the master's surface lies on the
    !> slave's over the whole zone.  In the initial configuration a curved
    !> master leaves the slave's strip by its initial gap (x^2 / 2R on Hertz),
    !> and its nodes at the zone's ends would be graded as if far from it.
    pure function moved(b, n, x) result(y)
      integer, intent(in) :: b, n
      real(dp), intent(in) :: x(2)
      real(dp) :: y(2)
      integer :: i
      i = run%prob%sc%bodies(b)%dof0 + 2 * n
      y = x
      if (allocated(run%res%u)) y = x + run%res%u(i - 1:i)
    end function moved
    !> Slave node k of the pair in contact (false off the trace's ends).
    pure logical function in_contact(k)
      integer, intent(in) :: k
      associate (pr => run%prob%cs%pair(ip), sb => run%prob%sc%bodies(run%prob%cs%pair(ip)%spec%slave_body))
        in_contact = .false.
        if (k < 1 .or. k > size(pr%snode)) return
        in_contact = run%res%node_pressure(sb%dof0 / 2 + pr%snode(k)) > 0.0_dp
      end associate
    end function in_contact
    !> The distance from x to the segment [a, b].
    pure real(dp) function segment_distance(x, a, b) result(dist)
      real(dp), intent(in) :: x(2), a(2), b(2)
      real(dp) :: t, l2
      l2 = sum((b - a)**2)
      t = 0.0_dp
      if (l2 > 0.0_dp) t = min(1.0_dp, max(0.0_dp, dot_product(x - a, b - a) / l2))
      dist = norm2(x - a - t * (b - a))
    end function segment_distance
  end subroutine refine_zones

  !> A fresh run on the deck's new meshes: the options of the command line
  !> and the deck as they were, the log (its clock: phases add up over the
  !> meshes; the warnings are the last mesh's own), the loop's state, ADAPT's
  !> lines of the summary.  The mesh just solved is kept (adapt%kept) until
  !> the next one has solved.
  subroutine restart(run)
    type(run_t), intent(inout) :: run
    type(run_t) :: next
    type(kept_mesh_t), allocatable :: kept
    call free_factor(run%sys%factor)
    next%opts = run%opts
    next%diag = run%diag
    next%log = run%log
    if (allocated(next%log%warning)) deallocate(next%log%warning)
    next%prob%deck = run%prob%deck
    call move_alloc(run%adapt%kept, kept)
    next%adapt = run%adapt
    if (.not. allocated(kept)) allocate(kept)
    call keep_mesh_state(run, kept)
    call move_alloc(kept%res%adapt, next%res%adapt)
    call move_alloc(kept, next%adapt%kept)
    run = next
  end subroutine restart

  !> What the outputs of a mesh that solved need, moved into kept.
  subroutine keep_mesh_state(run, kept)
    type(run_t), intent(inout) :: run
    type(kept_mesh_t), intent(inout) :: kept
    kept%prob = run%prob
    call move_alloc(run%out%step_tmp, kept%out%step_tmp)
    call move_alloc(run%out%step_table, kept%out%step_table)
    call move_alloc(run%out%zone_sets, kept%out%zone_sets)
    kept%sol = run%sol
    kept%res = run%res
    if (allocated(kept%warning)) deallocate(kept%warning)
    if (allocated(run%log%warning)) kept%warning = run%log%warning
  end subroutine keep_mesh_state

  !> A mesh failed (err): without ADAPT, or on its first mesh, the run ends
  !> (exit by err's category).  Otherwise the run goes back to the last mesh
  !> that solved, whose outputs are then written, with `adapt_result stopped
  !> solve_failed` and a warning naming the failure: a finer mesh that a
  !> solver cannot take does not lose the answer already had.
  !>   run (inout) the failed mesh's state on entry; the kept mesh's on exit
  !>   err (in)    the failure
  subroutine fall_back(run, err)
    type(run_t), intent(inout) :: run
    type(error_t), allocatable, intent(in) :: err
    integer :: k
    if (.not. allocated(run%adapt%kept)) call stop_on(err)
    if (allocated(run%out%step_tmp)) then         ! the failed mesh's step files go
      do k = 1, size(run%out%step_tmp, 2)
        call discard_temporaries(run%out%step_tmp(:, k))
      end do
      deallocate(run%out%step_tmp)
    end if
    call restore_kept(run)
    call say(run%log, 'adapt    mesh ' // int_to_str(run%adapt%step + 1) // ' failed: ' // err%message)
    call finish(run, 'stopped solve_failed', 'ADAPT stopped: mesh ' // int_to_str(run%adapt%step + 1) // &
      ' could not be solved (' // err%message // '); the outputs are those of mesh ' // int_to_str(run%adapt%step) // &
      ', the last that solved')
  end subroutine fall_back

  !> Back to the kept mesh (the last that solved before this one): its
  !> problem, solution, results, step files and warnings become the run's;
  !> the summary's ADAPT lines stay those of every mesh.  The current
  !> mesh's step files must be gone already, or are discarded here.
  !>   run (inout) the current mesh's state on entry; the kept mesh's on exit
  subroutine restore_kept(run)
    type(run_t), intent(inout) :: run
    integer :: k
    if (allocated(run%out%step_tmp)) then
      do k = 1, size(run%out%step_tmp, 2)
        call discard_temporaries(run%out%step_tmp(:, k))
      end do
      deallocate(run%out%step_tmp)
    end if
    associate (kept => run%adapt%kept)
      run%prob = kept%prob
      run%sol = kept%sol
      call move_alloc(run%res%adapt, kept%res%adapt)
      run%res = kept%res
      if (allocated(kept%out%step_tmp)) call move_alloc(kept%out%step_tmp, run%out%step_tmp)
      if (allocated(kept%out%step_table)) call move_alloc(kept%out%step_table, run%out%step_table)
      if (allocated(kept%out%zone_sets)) call move_alloc(kept%out%zone_sets, run%out%zone_sets)
      if (allocated(run%log%warning)) deallocate(run%log%warning)
      if (allocated(kept%warning)) run%log%warning = kept%warning
    end associate
    deallocate(run%adapt%kept)
  end subroutine restore_kept

  !> The final meshes next to the outputs, NAME_BODY.msh, when ADAPT made
  !> them (the deck's own meshes are the user's already): a new run can take
  !> them with MESH gmsh file=.  Written and committed like the outputs.
  !>   run (inout) the deck's meshes on entry; run%out%wrote gets a line
  subroutine keep_meshes(run)
    type(run_t), intent(inout) :: run
    type(temporary_t), allocatable :: tmp(:)
    type(error_t), allocatable :: err
    character(len=:), allocatable :: buf, names, line
    integer :: b, n, status, u, ios
    if (.not. run%prob%deck%adapt%on .or. run%adapt%step <= 1) return
    allocate(tmp(size(run%prob%deck%bodies)))
    n = 0
    names = ''
    do b = 1, size(run%prob%deck%bodies)
      associate (ms => run%prob%deck%bodies(b)%mesh)
        if (ms%is_geo .or. .not. run%adapt%geo(b)%is_geo) cycle
        call read_file(ms%path, buf, status)
        if (status /= 0) then
          call fail_write(run, tmp(1:n))
          return
        end if
        n = n + 1
        call create_temporary(run%opts%outdir, run%prob%deck%name // '_' // run%prob%deck%bodies(b)%name // '.msh', tmp(n), err)
        if (allocated(err)) then
          call fail_write(run, tmp(1:n))
          return
        end if
        open(newunit=u, file=tmp(n)%io_path, access='stream', form='unformatted', status='replace', iostat=ios)
        if (ios == 0) write(u, iostat=ios) buf
        if (ios == 0) close(u, iostat=ios)
        call close_temporary(tmp(n))
        if (ios /= 0) then
          call fail_write(run, tmp(1:n))
          return
        end if
        names = names // merge(', ', '  ', len(names) > 0) // run%prob%deck%name // '_' // run%prob%deck%bodies(b)%name // '.msh'
      end associate
    end do
    call commit_temporaries(run%opts%outdir, tmp(1:n), err)
    if (allocated(err)) then
      call fail_write(run, tmp(1:n))
      return
    end if
    line = 'wrote    ' // trim(adjustl(names)) // ' (the adapted meshes)'
    if (n > 0) run%out%wrote = [character(len=max(len(run%out%wrote), len(line))) :: run%out%wrote, line]
  end subroutine keep_meshes

  !> The meshes could not be written: the same message and exit as the outputs'.
  subroutine fail_write(run, tmp)
    type(run_t), intent(in) :: run
    type(temporary_t), intent(inout) :: tmp(:)
    call discard_temporaries(tmp)
    write(error_unit, '(a)') 'contact2d: error: ' // run%opts%outdir // ': cannot write the output files ' // &
      '(a writable folder expected)'
    call exit_program(2)
  end subroutine fail_write

end module adaptivity
