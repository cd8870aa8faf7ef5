!> results_writer: the results of a run (results_t) and the output files of
!> DECK.md but the VTK files (vtk_files): the contact table (CSV), the
!> summary, the ParaView collection and the step table.  The caller writes each to a
!> temporary of its own and commits them all only after every one was
!> written (safe_files), so a failed run never leaves half-written files nor
!> overwrites the outputs of an earlier successful run.
!>
!> Programming interface
!>   type(results_t)      everything a run computed that the files report
!>   type(string_t)       one string of any length (text_scan's; results_t's lists of names)
!>   write_contact_csv(path, cs, r, err)
!>   write_summary(path, r, err)
!>   write_pvd(path, files, times, err)    ParaView collection of the per-step VTK files
!>   write_step_table(path, header, table, whole, err)   NAME_steps.csv: one row per load step
!> Each writer returns err (error_input) when its file cannot be opened or written.
module results_writer
  use kinds, only: dp, i8
  use contact_set, only: contact_set_t, row_of_node, state_row_of_node, node_rows, node_traction
  use strings, only: int_to_str, i8_to_str, exact_to_str
  use errors, only: error_t, set_error, error_input
  use text_scan, only: string_t
  use contact_zones, only: pair_zones_t, zone_t
  use run_log, only: nphase, phase_names
  implicit none
  private
  public :: results_t, string_t, write_contact_csv, write_summary, write_pvd, write_step_table, cannot_write
  public :: peak_memory

  !> What a run found, for the writers.  Its lists of names and lines are
  !> arrays of string_t, not deferred-length character arrays: gfortran 12's
  !> assignment of a derived type loses the elements of such an array
  !> component (NUL bytes in the copy), and results_t is copied while the
  !> load steps are solved (each step's results start from an empty one).
  type :: results_t
    character(len=:), allocatable :: effects     !< effects simulated
    logical :: axisymmetric = .false.            !< forces for the full circle (summary force_basis)
    type(string_t), allocatable :: parameter(:) !< (nparam) 'NAME VALUE' of each deck PARAMETER
    integer :: nfree = 0                         !< free equations
    real(dp), allocatable :: u(:)                !< (ndof) displacements
    real(dp), allocatable :: stress(:,:)         !< (3, nelem) sxx syy sxy per element, or
                                                 !< (4, nelem) srr szz srz stt (axisymmetric)
    real(dp), allocatable :: vm(:)               !< (nelem) von Mises
    real(dp), allocatable :: jacobian(:)         !< (nelem) finite strain: J = det F at each element's centre
                                                 !< (unallocated: no hyperelastic body)
    real(dp), allocatable :: stretch(:)          !< (nelem) finite strain: the largest principal stretch there
    real(dp), allocatable :: newton(:,:)         !< (3, steps) finite strain: step, Newton iterations, residual
    real(dp), allocatable :: adt(:)              !< (nelem) the state's thermal strain alpha dT per element
                                                 !< (0 without THERMAL): what its stresses subtract
    real(dp), allocatable :: node_pressure(:)    !< (ndof/2) contact pressure at nodes (0 elsewhere)
    real(dp), allocatable :: node_gap(:)         !< (ndof/2) final gap at slave nodes (0 elsewhere)
    real(dp), allocatable :: mu(:)               !< (nrow) multipliers (nodal forces)
    real(dp), allocatable :: alpha(:)            !< (k) amplitudes of the free rigid modes
    type(string_t), allocatable :: unheld_mode(:) !< (nu) 'BODY KIND X Y' of each rigid motion held by
                                                 !< neither FIX nor contact (summary unheld_mode)
    real(dp), allocatable :: gap(:)              !< (nrow) final gaps
    real(dp), allocatable :: pressure(:)         !< (nrow) pressures mu / w
    integer, allocatable :: status(:)            !< (nrow) 1 contact, 0 open
    ! friction (allocated with size ntan > 0 only when a pair has friction)
    real(dp), allocatable :: tau(:)              !< (ntan) tangential multipliers (nodal forces)
    real(dp), allocatable :: shear(:)            !< (ntan) shear traction on the slave along t, -tau / w
    real(dp), allocatable :: slip(:)             !< (ntan) relative tangential displacement T u (slave - master)
    integer, allocatable :: fstate(:)            !< (ntan) 0 open, 1 stick, 2 slip (in the last step)
    integer, allocatable :: tan_of_row(:)        !< (nrow) tangential row of each normal row, 0 if none
    real(dp), allocatable :: node_shear(:)       !< (ndof/2) shear traction at slave nodes (0 elsewhere)
    integer, allocatable :: node_fstate(:)       !< (ndof/2) fstate at slave nodes (0 elsewhere)
    real(dp), allocatable :: node_slip(:)        !< (ndof/2) slip at slave nodes (0 elsewhere)
    integer :: steps = 1                         !< load steps solved
    integer :: stick_nodes = 0, slip_nodes = 0   !< friction states at the end
    real(dp), allocatable :: reaction(:,:)       !< (2, nfix)
    real(dp), allocatable :: contact_force(:,:)  !< (2, npair) resultant of the contact forces on each
                                                 !< pair's slave body, -sum_i (mu_i n_i + tau_i t_i)
    type(string_t), allocatable :: fix_label(:) !< (nfix) BODY:BOUNDARY
    type(string_t), allocatable :: spring_label(:) !< (nspring) BODY:NAME of each SPRING statement
    real(dp), allocatable :: spring_force(:,:)   !< (2, nspring) force of each SPRING on its body, x, y
    type(string_t), allocatable :: fix_boundary(:) !< (nfb) the distinct BODY:BOUNDARY of the FIXes, deck order
    real(dp), allocatable :: boundary_u(:,:)     !< (2, nfb) mean ux, uy of each one's nodes (summary displacement)
    type(string_t), allocatable :: pair_label(:) !< (npair) each CONTACT's name= ('' or unallocated: its
                                                 !< number), the PAIR of the summary's per-pair lines
    type(pair_zones_t), allocatable :: zones(:)  !< (npair) contact zone, peak pressure, centre of pressure,
                                                 !< stick zone of each pair (contact_zones)
    type(string_t), allocatable :: rigid_name(:) !< (nrigid) the RIGID obstacles
    real(dp), allocatable :: rigid(:,:)          !< (6, nrigid) ux uy rz of the reference point, fx fy m the
                                                 !< contact force on the obstacle (summary rigid)
    real(dp) :: energy = 0
    ! the model's assumptions (model_checks): the largest strain and rotation
    real(dp) :: max_strain(3) = 0                !< largest principal strain magnitude, x, y where
    real(dp) :: max_rotation(3) = 0              !< largest |(du_y/dx - du_x/dy) / 2| (rad), x, y where
    character(len=:), allocatable :: max_strain_body, max_rotation_body   !< the body of each
    type(string_t), allocatable :: warning(:)    !< (nwarn) 'CODE text' of each warning (run_report add_warning)
    logical :: estimated = .false.               !< the error was estimated (ESTIMATE, on by default)
    real(dp) :: estimate_energy = 0              !< estimated relative energy-norm error of u_h
    real(dp) :: estimate_energy_bound = -1       !< its guaranteed upper bound (module energy_bound), -1: none
    real(dp), allocatable :: error_indicator(:)  !< (nelem) each element's share eta_K / ||u||_E of it:
                                                 !< the sum of their squares is estimate_energy^2
    real(dp), allocatable :: estimate_zone(:)     !< (npair) its zone's own term, -1 where no zone
                                                  !< (run_estimate; ADAPT sizes a zone's strip on it)
    real(dp), allocatable :: estimate_pressure(:) !< (npair) estimated relative L2 error of the contact
                                                 !< pressure over the pair's zone; < 0: no zone in contact
    real(dp) :: cost_seconds = -1, cost_dofs = -1  !< estimate cost_to_halve: predicted cpu_total and dofs
                                                 !< of a run with half the energy error (< 0: none)
    real(dp), allocatable :: adapt(:,:)          !< (3, nstep) ADAPT: dofs, estimate, CPU seconds of each step
    character(len=:), allocatable :: adapt_result   !< ADAPT: 'reached' or 'stopped WHY'
    character(len=:), allocatable :: lcp_method
    integer :: lcp_iterations = 0
    real(dp) :: lcp_residual = 0
    type(string_t), allocatable :: lcp_fallback(:) !< 'STEP FROM TO' of each lcp=auto fallback (step_solver)
    real(dp) :: complementarity = 0, min_gap = 0, min_pressure = 0
    real(dp) :: certificate(3) = 0               !< the final step's certificate: complementarity, cone,
                                                 !< equilibrium, relative (certificate; 0 without contact)
    integer :: contact_nodes = 0, active_nodes = 0, redundant = 0
    integer(i8) :: factor_nnz = 0
    integer :: factor_parts = 0                  !< parts of K factorized on their own (the bodies)
    integer :: factor_threads = 1                !< threads the parts ran on (1: one after the other)
    character(len=:), allocatable :: condense_text  !< how W was condensed by body (the run log; '' none)
    character(len=:), allocatable :: ordering    !< fill-reducing ordering used, e.g. amd(nodes)+last
    integer, allocatable :: condense_block(:,:)  !< (3, blocks of L_cc reached by rows): dofs, rows,
                                                 !< 1 by its inverse / 0 by triangular solves
    real(dp) :: time(nphase) = 0                 !< seconds per phase_names
    real(dp) :: cpu(nphase) = 0                  !< CPU seconds per phase_names (gmsh's included)
    real(dp) :: memory_peak = 0                  !< peak resident memory, bytes (0 when unknown)
    real(dp) :: factor_memory = 0                !< CHOLMOD's peak memory for the factor, bytes
    real(dp) :: time_solve = 0                   !< seconds of the one solve u0 = K^-1 f (inside a phase)
    real(dp) :: time_ordering = 0                !< seconds of the ordering and analysis (inside factor)
    real(dp) :: time_assemble_values = 0         !< seconds of the assembly of K's values, which ran
                                                 !< beside the ordering (partly inside factor)
  end type results_t

contains

  !> Contact table: one row per slave node of each pair, along the boundary.
  !> Slave nodes with no master opposite (no constraint row) have empty gap0
  !> and gap fields and status -1.
  subroutine write_contact_csv(path, cs, r, err)
    character(len=*), intent(in) :: path
    type(contact_set_t), intent(in) :: cs
    type(results_t), intent(in) :: r
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios, ip, i, row, t, rows(3), nr
    real(dp), allocatable :: tforce(:)
    character(len=32) :: sx(4)
    character(len=:), allocatable :: extra
    logical :: friction
    call open_for_writing(path, u, err)
    if (allocated(err)) return
    friction = allocated(r%tau)
    if (friction) then
      allocate(tforce(cs%nrow), source=0.0_dp)
      tforce(cs%tan_row) = -r%tau              ! the force on the slave is -tau t
    end if
    if (friction) then                         ! friction: three more columns
      write(u, '(a)') 'pair,s,x,y,gap0,gap,pressure,status,shear,slip,friction_state'
    else
      write(u, '(a)') 'pair,s,x,y,gap0,gap,pressure,status'
    end if
    do ip = 1, cs%npair
      associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
        do i = 1, size(pr%snode)
          ! a closed curve lists its first node once: at the end when the row is there, else at the start
          if (pr%closed .and. i == merge(1, size(pr%snode), pr%row(size(pr%snode)))) cycle
          write(sx(1), '(es24.16e3)') mo%arc(i)
          write(sx(2), '(es24.16e3)') pr%xs(1, i)
          write(sx(3), '(es24.16e3)') pr%xs(2, i)
          row = row_of_node(cs, ip, i)
          extra = ''
          if (friction) then
            extra = ',0,,0'                    ! no tangential row: no shear, no slip, open
            if (row > 0) then
              t = r%tan_of_row(state_row_of_node(cs, ip, i))
              if (t > 0) extra = ',' // exact_to_str(node_traction(cs, ip, i, tforce)) // ',' // exact_to_str(r%slip(t)) // ',' // &
                                 int_to_str(r%fstate(t))
            end if
          end if
          if (row > 0) then
            call node_rows(cs, ip, i, rows, nr)           ! in contact where any of its rows is
            write(u, '(a,i0,a)') int_to_str(ip) // ',' // trim(adjustl(sx(1))) // ',' // &
              trim(adjustl(sx(2))) // ',' // trim(adjustl(sx(3))) // ',' // exact_to_str(mo%gap0(i)) // ',' // &
              exact_to_str(minval(r%gap(rows(1:nr)))) // ',' // exact_to_str(node_traction(cs, ip, i, r%mu)) // ',', &
              maxval(r%status(rows(1:nr))), extra
          else
            write(u, '(a)') int_to_str(ip) // ',' // trim(adjustl(sx(1))) // ',' // &
              trim(adjustl(sx(2))) // ',' // trim(adjustl(sx(3))) // ',,,0,-1' // extra
          end if
        end do
      end associate
    end do
    close(u, iostat=ios)
    if (ios /= 0) call cannot_write(path, err)
  end subroutine write_contact_csv

  !> err: path cannot be written (error_input).
  subroutine cannot_write(path, err)
    character(len=*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: err
    call set_error(err, path // ': cannot write the file', error_input)
  end subroutine cannot_write

  !> A `KEY TEXT` line of the summary for each text of a list, none when the
  !> list is not allocated.
  !>   u     (in) the summary's unit
  !>   key   (in) the lines' key
  !>   texts (in) the list
  subroutine write_lines(u, key, texts)
    integer, intent(in) :: u
    character(len=*), intent(in) :: key
    type(string_t), allocatable, intent(in) :: texts(:)
    integer :: k
    if (.not. allocated(texts)) return
    do k = 1, size(texts)
      write(u, '(a)') key // ' ' // texts(k)%s
    end do
  end subroutine write_lines

  !> A `KEY LABEL X Y` line of the summary for each label, with the two
  !> components of its column of xy; none when either is not allocated.
  !>   u      (in) the summary's unit
  !>   key    (in) the lines' key
  !>   labels (in) (n) the labels
  !>   xy     (in) (2, n) the components
  subroutine write_labelled(u, key, labels, xy)
    integer, intent(in) :: u
    character(len=*), intent(in) :: key
    type(string_t), allocatable, intent(in) :: labels(:)
    real(dp), allocatable, intent(in) :: xy(:, :)
    integer :: k
    if (.not. (allocated(labels) .and. allocated(xy))) return
    do k = 1, size(labels)
      write(u, '(a)') key // ' ' // labels(k)%s // ' ' // exact_to_str(xy(1, k)) // ' ' // exact_to_str(xy(2, k))
    end do
  end subroutine write_labelled

  !> A new formatted file of every writer here, replacing any at path:
  !> err (cannot_write) when it cannot be opened.
  !>   path (in)  the file
  !>   u    (out) its unit, open for writing when err is not allocated
  !>   err  (out) the failure
  subroutine open_for_writing(path, u, err)
    character(len=*), intent(in) :: path
    integer, intent(out) :: u
    type(error_t), allocatable, intent(out) :: err
    integer :: ios
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    if (ios /= 0) call cannot_write(path, err)
  end subroutine open_for_writing


  !> The summary: one `key value...` per line (DECK.md), plus extra keys.
  subroutine write_summary(path, r, err)
    character(len=*), intent(in) :: path
    type(results_t), intent(in) :: r
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios, k, j
    call open_for_writing(path, u, err)
    if (allocated(err)) return
    write(u, '(a)') 'effects ' // r%effects
    write(u, '(a)') 'force_basis ' // trim(merge('full_circle       ', 'per_unit_thickness', r%axisymmetric))
    call write_lines(u, 'parameter', r%parameter)
    write(u, '(a,i0)') 'dofs ', size(r%u)
    write(u, '(a,i0)') 'free_dofs ', r%nfree
    write(u, '(a,i0)') 'contact_nodes ', r%contact_nodes
    write(u, '(a,i0)') 'active_nodes ', r%active_nodes
    write(u, '(a,i0)') 'redundant_constraints ', r%redundant
    write(u, '(a)') 'lcp_method ' // r%lcp_method
    write(u, '(a,i0)') 'lcp_iterations ', r%lcp_iterations
    write(u, '(a,a)') 'lcp_residual ', exact_to_str(r%lcp_residual)
    call write_lines(u, 'lcp_fallback', r%lcp_fallback)
    if (allocated(r%newton)) then
      do k = 1, size(r%newton, 2)
        write(u, '(a,i0,a,i0,a)') 'newton ', nint(r%newton(1, k)), ' ', nint(r%newton(2, k)), ' ' // &
          exact_to_str(r%newton(3, k))
      end do
    end if
    write(u, '(a,a)') 'complementarity ', exact_to_str(r%complementarity)
    write(u, '(a)') 'certificate complementarity ' // exact_to_str(r%certificate(1)) // ' cone ' // &
      exact_to_str(r%certificate(2)) // ' equilibrium ' // exact_to_str(r%certificate(3))
    write(u, '(a,a)') 'min_gap ', exact_to_str(r%min_gap)
    write(u, '(a,a)') 'min_pressure ', exact_to_str(r%min_pressure)
    if (allocated(r%tau)) then
      write(u, '(a,i0)') 'steps ', r%steps
      write(u, '(a,i0)') 'stick_nodes ', r%stick_nodes
      write(u, '(a,i0)') 'slip_nodes ', r%slip_nodes
    end if
    write(u, '(a,a)') 'energy ', exact_to_str(r%energy)
    if (r%estimated) then
      write(u, '(a,a)') 'estimate energy ', exact_to_str(r%estimate_energy)
      if (r%estimate_energy_bound >= 0.0_dp) write(u, '(a,a)') 'estimate energy_bound ', exact_to_str(r%estimate_energy_bound)
      do k = 1, size(r%estimate_pressure)
        if (r%estimate_pressure(k) >= 0.0_dp) &
          write(u, '(a)') 'estimate pressure ' // pair_name(r, k) // ' ' // exact_to_str(r%estimate_pressure(k))
      end do
      if (r%cost_dofs > 0.0_dp) write(u, '(a)') 'estimate cost_to_halve ' // exact_to_str(r%cost_seconds) // ' ' // &
        i8_to_str(nint(r%cost_dofs, i8))
    end if
    if (allocated(r%adapt)) then
      do k = 1, size(r%adapt, 2)
        write(u, '(a,i0,a)') 'adapt ', k, ' dofs ' // i8_to_str(nint(r%adapt(1, k), i8)) // ' estimate ' // &
          exact_to_str(r%adapt(2, k)) // ' cpu ' // exact_to_str(r%adapt(3, k))
      end do
    end if
    if (allocated(r%adapt_result)) write(u, '(a)') 'adapt_result ' // r%adapt_result
    call write_labelled(u, 'reaction', r%fix_label, r%reaction)
    call write_labelled(u, 'spring', r%spring_label, r%spring_force)
    if (allocated(r%contact_force)) then
      do k = 1, size(r%contact_force, 2)
        write(u, '(a)') 'contact_force ' // pair_name(r, k) // ' ' // exact_to_str(r%contact_force(1, k)) // ' ' // &
          exact_to_str(r%contact_force(2, k))
      end do
    end if
    call write_labelled(u, 'displacement', r%fix_boundary, r%boundary_u)
    if (allocated(r%zones)) then
      do k = 1, size(r%zones)
        associate(z => r%zones(k))
          call write_zone(u, 'contact', pair_name(r, k), z%contact)
          do j = 1, z%contact%count
            write(u, '(a)') 'peak_pressure ' // pair_name(r, k) // ' ' // exact_to_str(z%peak(1, j)) // ' ' // &
              exact_to_str(z%peak(2, j)) // ' ' // exact_to_str(z%peak(3, j))
          end do
          do j = 1, z%contact%count
            write(u, '(a)') 'center_of_pressure ' // pair_name(r, k) // ' ' // exact_to_str(z%centre(1, j)) // ' ' // &
              exact_to_str(z%centre(2, j))
          end do
          if (z%friction) call write_zone(u, 'stick', pair_name(r, k), z%stick)
        end associate
      end do
    end if
    if (allocated(r%rigid_name)) then
      do k = 1, size(r%rigid_name)
        write(u, '(a)') 'rigid ' // r%rigid_name(k)%s // ' ' // exact_to_str(r%rigid(1, k)) // ' ' // exact_to_str(r%rigid(2, &
          k)) // &
          ' ' // exact_to_str(r%rigid(3, k)) // ' ' // exact_to_str(r%rigid(4, k)) // ' ' // exact_to_str(r%rigid(5, k)) // &
            ' ' // exact_to_str(r%rigid(6, k))
      end do
    end if
    call write_lines(u, 'unheld_mode', r%unheld_mode)
    if (allocated(r%max_strain_body)) write(u, '(a)') 'max_strain ' // exact_to_str(r%max_strain(1)) // ' ' // &
      r%max_strain_body // ' ' // exact_to_str(r%max_strain(2)) // ' ' // exact_to_str(r%max_strain(3))
    if (allocated(r%max_rotation_body)) write(u, '(a)') 'max_rotation ' // exact_to_str(r%max_rotation(1)) // ' ' // &
      r%max_rotation_body // ' ' // exact_to_str(r%max_rotation(2)) // ' ' // exact_to_str(r%max_rotation(3))
    call write_lines(u, 'warning', r%warning)
    write(u, '(a,i0)') 'factor_nnz ', r%factor_nnz
    if (allocated(r%ordering)) write(u, '(a)') 'factor_ordering ' // r%ordering
    if (allocated(r%condense_block)) then
      do k = 1, size(r%condense_block, 2)
        write(u, '(a,i0,a,i0,a)') 'condense_block ', r%condense_block(1, k), ' ', r%condense_block(2, k), ' ' // &
          trim(merge('inverse', 'solve  ', r%condense_block(3, k) == 1))
      end do
    end if
    write(u, '(a,a)') 'memory_peak_mb ', exact_to_str(r%memory_peak / 1048576.0_dp)
    write(u, '(a,a)') 'factor_memory_mb ', exact_to_str(r%factor_memory / 1048576.0_dp)
    do k = 1, nphase
      write(u, '(a,a)') 'time_' // trim(phase_names(k)) // ' ', exact_to_str(r%time(k))
    end do
    write(u, '(a,a)') 'cpu_total ', exact_to_str(r%cpu(nphase))
    write(u, '(a,a)') 'time_solve ', exact_to_str(r%time_solve)
    write(u, '(a,a)') 'time_ordering ', exact_to_str(r%time_ordering)
    write(u, '(a,a)') 'time_assemble_values ', exact_to_str(r%time_assemble_values)
    close(u, iostat=ios)
    if (ios /= 0) call cannot_write(path, err)
  end subroutine write_summary

  !> A pair's zone lines in the summary: `KIND_zone PAIR x0 y0 x1 y1 LENGTH`
  !> per zone in order along the slave boundary, then always `KIND_zones PAIR
  !> COUNT TOTAL` (doc/outputs.md).
  !>   u    (in) the summary's unit
  !>   kind (in) 'contact' or 'stick'
  !>   pair (in) the pair's label (pair_name)
  !>   z    (in) the zones
  subroutine write_zone(u, kind, pair, z)
    integer, intent(in) :: u
    character(len=*), intent(in) :: kind, pair
    type(zone_t), intent(in) :: z
    integer :: j
    do j = 1, z%count
      write(u, '(a)') kind // '_zone ' // pair // ' ' // exact_to_str(z%x0(1, j)) // ' ' // &
        exact_to_str(z%x0(2, j)) // ' ' // exact_to_str(z%x1(1, j)) // ' ' // exact_to_str(z%x1(2, j)) // ' ' // &
        exact_to_str(z%length(j))
    end do
    write(u, '(a,i0,a)') kind // '_zones ' // pair // ' ', z%count, ' ' // exact_to_str(z%total)
  end subroutine write_zone

  !> The PAIR of pair k's summary lines: its CONTACT's name= when it has one,
  !> else its number (1, 2, ...), so a deck without names keeps its lines.
  !>   r (in) the results (r%pair_label)
  !>   k (in) the pair
  function pair_name(r, k) result(label)
    type(results_t), intent(in) :: r
    integer, intent(in) :: k
    character(len=:), allocatable :: label
    label = int_to_str(k)
    if (.not. allocated(r%pair_label)) return
    if (k > size(r%pair_label)) return
    if (.not. allocated(r%pair_label(k)%s)) return
    if (len(r%pair_label(k)%s) > 0) label = r%pair_label(k)%s
  end function pair_name

  !> A ParaView collection (.pvd) of the per-step VTK files: the dataset of
  !> step k is files(k), at time times(k).
  !>   path  (in)  file to write
  !>   files (in)  (nstep) names relative to the .pvd's folder
  !>   times (in)  (nstep) each step's time, increasing (ParaView sorts and merges equal ones)
  !>   err   (out) allocated when not written completely
  subroutine write_pvd(path, files, times, err)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: files(:)
    real(dp), intent(in) :: times(:)
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios, k
    logical :: ok
    call open_for_writing(path, u, err)
    if (allocated(err)) return
    write(u, '(a)', iostat=ios) '<?xml version="1.0"?>'
    write(u, '(a)', iostat=ios) '<VTKFile type="Collection" version="0.1">'
    write(u, '(a)', iostat=ios) '  <Collection>'
    do k = 1, size(files)
      write(u, '(a)', iostat=ios) '    <DataSet timestep="' // exact_to_str(times(k)) // '" file="' // trim(files(k)) // '"/>'
    end do
    write(u, '(a)', iostat=ios) '  </Collection>'
    write(u, '(a)', iostat=ios) '</VTKFile>'
    ok = ios == 0
    close(u, iostat=ios)
    if (.not. ok .or. ios /= 0) call cannot_write(path, err)
  end subroutine write_pvd

  !> The table of the load steps (CSV): the header line, then one row per
  !> step; the columns marked whole (the step, counts) are written as integers.
  !>   header (in) the header line;  table (in) (ncol, nstep) the rows
  !>   whole  (in) (ncol) the column holds integers
  subroutine write_step_table(path, header, table, whole, err)
    character(len=*), intent(in) :: path, header
    real(dp), intent(in) :: table(:,:)
    logical, intent(in) :: whole(:)
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios, k, c, nc
    logical :: ok
    character(len=:), allocatable :: line
    call open_for_writing(path, u, err)
    if (allocated(err)) return
    write(u, '(a)', iostat=ios) header
    nc = size(table, 1)
    do k = 1, size(table, 2)
      line = ''
      do c = 1, nc
        if (c > 1) line = line // ','
        if (whole(c)) then
          line = line // int_to_str(nint(table(c, k)))
        else
          line = line // exact_to_str(table(c, k))
        end if
      end do
      write(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
    end do
    ok = ios == 0
    close(u, iostat=ios)
    if (.not. ok .or. ios /= 0) call cannot_write(path, err)
  end subroutine write_step_table

  !> Peak resident set size of this process in bytes (VmHWM of
  !> /proc/self/status on Linux); 0 when it cannot be read.
  real(dp) function peak_memory() result(bytes)
    integer :: u, ios
    character(len=256) :: line
    real(dp) :: kb
    bytes = 0.0_dp
    open(newunit=u, file='/proc/self/status', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:6) == 'VmHWM:') then
        read(line(7:), *, iostat=ios) kb
        if (ios == 0) bytes = kb * 1024.0_dp
        exit
      end if
    end do
    close(u)
  end function peak_memory

end module results_writer
