!> results_writer: the output files of DECK.md — the VTK legacy file, the
!> contact table (CSV) and the summary.  The caller writes each to a
!> temporary of its own and commits them all only after every one was
!> written (safe_files), so a failed run never leaves half-written files nor
!> overwrites the outputs of an earlier successful run.
!>
!> Programming interface
!>   type(results_t)      everything a run computed that the files report
!>   type(string_t)       one string of any length (text_scan's; results_t's lists of names)
!>   write_vtk(path, title, bodies, r, fields, err)
!>   write_contact_csv(path, cs, r, err)
!>   write_summary(path, r, err)
!>   write_pvd(path, files, err)           ParaView collection of the per-step VTK files
!>   write_step_table(path, header, table, whole, err)   NAME_steps.csv: one row per load step
!> Each writer returns err (status 2) when its file cannot be opened or written.
module results_writer
  use kinds, only: dp, i8
  use body, only: body_t
  use mesh, only: file_item, node_in_file
  use contact_set, only: contact_set_t, row_of_node, node_rows, node_traction
  use strings, only: int_to_str
  use errors, only: error_t, set_error
  use text_scan, only: string_t
  use contact_zones, only: pair_zones_t, zone_t
  use text_buffer, only: text_buffer_t, open_text, open_memory, put_text, put_line, put_real, put_int, put_newline, &
                         close_text
  implicit none
  private
  public :: results_t, string_t, write_vtk, write_contact_csv, write_summary, write_pvd, write_step_table
  public :: phase_names, nphase, peak_memory

  integer, parameter :: nphase = 9
  character(len=8), parameter :: phase_names(nphase) = &
    [character(len=8) :: 'mesh', 'assemble', 'factor', 'condense', 'lcp', 'recover', 'estimate', 'output', 'total']

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
    integer :: steps = 1                         !< load steps solved
    integer :: stick_nodes = 0, slip_nodes = 0   !< friction states at the end
    real(dp), allocatable :: reaction(:,:)       !< (2, nfix)
    real(dp), allocatable :: contact_force(:,:)  !< (2, npair) resultant of the contact forces on each
                                                 !< pair's slave body, -sum_i (mu_i n_i + tau_i t_i)
    type(string_t), allocatable :: fix_label(:) !< (nfix) BODY:BOUNDARY
    type(string_t), allocatable :: fix_boundary(:) !< (nfb) the distinct BODY:BOUNDARY of the FIXes, deck order
    real(dp), allocatable :: boundary_u(:,:)     !< (2, nfb) mean ux, uy of each one's nodes (summary displacement)
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
    real(dp), allocatable :: error_indicator(:)  !< (nelem) each element's share eta_K / ||u||_E of it:
                                                 !< the sum of their squares is estimate_energy^2
    real(dp), allocatable :: estimate_pressure(:) !< (npair) estimated relative L2 error of the contact
                                                 !< pressure over the pair's zone; < 0: no zone in contact
    character(len=:), allocatable :: lcp_method
    integer :: lcp_iterations = 0
    real(dp) :: lcp_residual = 0
    real(dp) :: complementarity = 0, min_gap = 0, min_pressure = 0
    integer :: contact_nodes = 0, active_nodes = 0, redundant = 0
    integer(i8) :: factor_nnz = 0
    character(len=:), allocatable :: ordering    !< fill-reducing ordering used, e.g. amd(nodes)+last
    integer, allocatable :: condense_block(:,:)  !< (3, blocks of L_cc reached by rows): dofs, rows,
                                                 !< 1 by its inverse / 0 by triangular solves
    real(dp) :: time(nphase) = 0                 !< seconds per phase_names
    real(dp) :: memory_peak = 0                  !< peak resident memory, bytes (0 when unknown)
    real(dp) :: factor_memory = 0                !< CHOLMOD's peak memory for the factor, bytes
    real(dp) :: time_solve = 0                   !< seconds of the one solve u0 = K^-1 f (inside a phase)
    real(dp) :: time_ordering = 0                !< seconds of the ordering and analysis (inside factor)
    real(dp) :: time_assemble_values = 0         !< seconds of the assembly of K's values, which ran
                                                 !< beside the ordering (partly inside factor)
  end type results_t

  ! the sections of the VTK file, row by row (put_rows)
  integer, parameter :: row_point = 1, row_cell = 2, row_cell_type = 3, row_displacement = 4, &
                        row_values = 5, row_body = 6

  !> The rows of the VTK file, in the mesh files' numbering (each body's
  !> nodes and elements as its file gives them, the bodies in deck order).
  type :: vtk_rows_t
    integer, allocatable :: node_index(:)   !< (nnode) the solver's global node of each point row
    integer, allocatable :: elem_index(:)   !< (nelem) the solver's global element of each cell row
    integer, allocatable :: elem_body(:)    !< (nelem) the body of each cell row
    integer, allocatable :: cells(:,:)      !< (0:4 or 0:9, nelem) node count and 0-based points of each cell row
    real(dp), allocatable :: vals(:,:)      !< (ncomp, rows) the values of the section being written
  end type vtk_rows_t

contains

  !> VTK legacy unstructured grid of every body (see DECK.md), ASCII.
  subroutine write_vtk(path, title, bodies, r, fields, err)
    character(len=*), intent(in) :: path, title
    type(body_t), intent(in) :: bodies(:)
    type(results_t), intent(in) :: r
    logical, intent(in) :: fields(5)   !< displacement, contact_pressure, gap, stress, von_mises
    type(error_t), allocatable, intent(out) :: err
    type(text_buffer_t) :: tb
    type(vtk_rows_t) :: v
    integer :: b, nnode, nelem, ncon, i
    character(len=256) :: head

    nnode = 0; nelem = 0; ncon = 0
    do b = 1, size(bodies)
      nnode = nnode + bodies(b)%mesh%nnode
      nelem = nelem + bodies(b)%mesh%nelem
      ncon = ncon + bodies(b)%mesh%nelem + sum(bodies(b)%mesh%nen)
    end do
    call open_text(tb, path, err)
    if (allocated(err)) return
    call vtk_rows(bodies, nnode, nelem, v)
    head = title
    if (len_trim(head) == 0) head = 'contact2d'
    call put_line(tb, '# vtk DataFile Version 3.0')
    call put_line(tb, trim(head))
    call put_line(tb, 'ASCII')
    call put_line(tb, 'DATASET UNSTRUCTURED_GRID')
    call put_line(tb, 'POINTS ' // int_to_str(nnode) // ' double')
    allocate(v%vals(2, nnode))
    nnode = 0
    do b = 1, size(bodies)
      associate(m => bodies(b)%mesh)
        !$omp parallel do if(m%nnode > 4096)
        do i = 1, m%nnode
          v%vals(:, nnode + i) = m%x(:, v%node_index(nnode + i) - nnode)
        end do
        !$omp end parallel do
        nnode = nnode + m%nnode
      end associate
    end do
    call put_rows(tb, row_point, nnode, v)
    call put_line(tb, 'CELLS ' // int_to_str(nelem) // ' ' // int_to_str(ncon))
    call put_rows(tb, row_cell, nelem, v)
    call put_line(tb, 'CELL_TYPES ' // int_to_str(nelem))
    call put_rows(tb, row_cell_type, nelem, v)
    if (any(fields(1:3))) call put_line(tb, 'POINT_DATA ' // int_to_str(nnode))
    if (fields(1)) then
      call put_line(tb, 'VECTORS displacement double')
      call gather(r%u, 2, v%node_index, v)
      call put_rows(tb, row_displacement, nnode, v)
    end if
    if (fields(2)) call put_scalars(tb, 'contact_pressure', r%node_pressure, v%node_index, v)
    if (fields(3)) call put_scalars(tb, 'gap', r%node_gap, v%node_index, v)
    if (fields(2) .and. allocated(r%node_shear)) call put_scalars(tb, 'contact_shear', r%node_shear, v%node_index, v)
    call put_line(tb, 'CELL_DATA ' // int_to_str(nelem))
    call put_line(tb, 'SCALARS body int 1')
    call put_line(tb, 'LOOKUP_TABLE default')
    call put_rows(tb, row_body, nelem, v)
    if (fields(4)) then
      call put_line(tb, 'SCALARS stress double ' // int_to_str(size(r%stress, 1)))
      call put_line(tb, 'LOOKUP_TABLE default')
      call gather(r%stress, size(r%stress, 1), v%elem_index, v)
      call put_rows(tb, row_values, nelem, v)
    end if
    if (fields(5)) call put_scalars(tb, 'von_mises', r%vm, v%elem_index, v)
    if (allocated(r%error_indicator)) call put_scalars(tb, 'error_indicator', r%error_indicator, v%elem_index, v)
    call close_text(tb, err)
    if (allocated(err)) call cannot_write(path, err)
  end subroutine write_vtk

  !> VTK cell type of an element of nen nodes: 5 triangle, 9 quad, 22 quadratic
  !> triangle, 23 quadratic (8-node) quad, 28 biquadratic (9-node) quad; the
  !> node orders of gmsh and VTK agree for these.
  pure function vtk_cell_type(nen) result(t)
    integer, intent(in) :: nen
    character(len=3) :: t
    select case (nen)
    case (3); t = ' 5'
    case (6); t = ' 22'
    case (8); t = ' 23'
    case (9); t = ' 28'
    case default; t = ' 9'
    end select
  end function vtk_cell_type

  !> The most nodes of an element over all bodies (4 or 9: the width of the cell rows).
  pure integer function max_cell_nodes(bodies) result(w)
    type(body_t), intent(in) :: bodies(:)
    integer :: b
    w = 4
    do b = 1, size(bodies)
      if (bodies(b)%mesh%nelem > 0) w = max(w, maxval(bodies(b)%mesh%nen))
    end do
  end function max_cell_nodes

  !> The rows of the VTK file: which of the solver's nodes and elements each
  !> point and cell row shows, and each cell's points in the files' numbering.
  subroutine vtk_rows(bodies, nnode, nelem, v)
    type(body_t), intent(in) :: bodies(:)
    integer, intent(in) :: nnode, nelem       !< over all bodies
    type(vtk_rows_t), intent(out) :: v
    integer :: b, p, e, k, n0, e0
    allocate(v%node_index(nnode), v%elem_index(nelem), v%elem_body(nelem), v%cells(0:max_cell_nodes(bodies), nelem))
    n0 = 0; e0 = 0
    do b = 1, size(bodies)
      associate(m => bodies(b)%mesh)
        do p = 1, m%nnode
          v%node_index(n0 + p) = n0 + file_item(m, p, element=.false.)
        end do
        !$omp parallel do private(e, k) if(m%nelem > 4096)
        do p = 1, m%nelem
          e = file_item(m, p, element=.true.)
          v%elem_index(e0 + p) = e0 + e
          v%elem_body(e0 + p) = b
          v%cells(:, e0 + p) = 0
          v%cells(0, e0 + p) = m%nen(e)
          do k = 1, m%nen(e)
            v%cells(k, e0 + p) = n0 + node_in_file(m, m%conn(k, e)) - 1
          end do
        end do
        !$omp end parallel do
        n0 = n0 + m%nnode
        e0 = e0 + m%nelem
      end associate
    end do
  end subroutine vtk_rows

  !> v%vals(:, i) = src(:, index(i)): a section's values in the order of its rows.
  !> src is (ncomp, *): ncomp values per node or element, in the solver's order.
  subroutine gather(src, ncomp, index, v)
    integer, intent(in) :: ncomp
    real(dp), intent(in) :: src(ncomp, *)
    integer, intent(in) :: index(:)
    type(vtk_rows_t), intent(inout) :: v
    integer :: i
    if (allocated(v%vals)) deallocate(v%vals)
    allocate(v%vals(ncomp, size(index)))
    !$omp parallel do if(size(index) > 4096)
    do i = 1, size(index)
      v%vals(:, i) = src(:, index(i))
    end do
    !$omp end parallel do
  end subroutine gather

  !> One SCALARS array, a value per line; index: the rows' nodes or elements.
  subroutine put_scalars(tb, name, values, index, v)
    type(text_buffer_t), intent(inout) :: tb
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: values(:)
    integer, intent(in) :: index(:)
    type(vtk_rows_t), intent(inout) :: v
    call put_line(tb, 'SCALARS ' // name // ' double 1')
    call put_line(tb, 'LOOKUP_TABLE default')
    call gather(values, 1, index, v)
    ! a row per point or cell: a node array (ndof / 2) runs past the points when RIGIDs add dofs
    call put_rows(tb, row_values, size(index), v)
  end subroutine put_scalars

  !> Rows 1..n of one section of the VTK file (kind: row_*), formatted in
  !> chunks on the run's threads and written in order: the text is the same as
  !> one thread's, the formatting (most of the output time) is shared.
  subroutine put_rows(tb, kind, n, v)
    type(text_buffer_t), intent(inout) :: tb
    integer, intent(in) :: kind, n
    type(vtk_rows_t), intent(in) :: v
    integer, parameter :: chunk = 4096
    type(text_buffer_t) :: part
    integer :: c, i
    !$omp parallel do ordered schedule(static, 1) private(part, i) &
    !$omp if(n > chunk)
    do c = 0, (n - 1) / chunk
      call open_memory(part)
      do i = c * chunk + 1, min((c + 1) * chunk, n)
        call put_row(part, kind, i, v)
      end do
      !$omp ordered
      call put_text(tb, part%buf(1:part%used))
      !$omp end ordered
    end do
    !$omp end parallel do
  end subroutine put_rows

  !> Row i of a section of the VTK file.
  subroutine put_row(tb, kind, i, v)
    type(text_buffer_t), intent(inout) :: tb
    integer, intent(in) :: kind, i
    type(vtk_rows_t), intent(in) :: v
    integer :: k
    select case (kind)
    case (row_point, row_displacement)
      call put_real(tb, v%vals(1, i))
      call put_real(tb, v%vals(2, i))
      call put_line(tb, ' 0')
    case (row_cell)
      do k = 0, v%cells(0, i)
        call put_int(tb, v%cells(k, i))
      end do
      call put_newline(tb)
    case (row_cell_type)
      call put_line(tb, trim(vtk_cell_type(v%cells(0, i))))
    case (row_values)                            ! SCALARS rows: the section's components
      do k = 1, size(v%vals, 1)
        call put_real(tb, v%vals(k, i))
      end do
      call put_newline(tb)
    case (row_body)
      call put_int(tb, v%elem_body(i))
      call put_newline(tb)
    end select
  end subroutine put_row

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
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    if (ios /= 0) then
      call cannot_write(path, err)
      return
    end if
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
              t = r%tan_of_row(row)
              if (t > 0) extra = ',' // num(node_traction(cs, ip, i, tforce)) // ',' // num(r%slip(t)) // ',' // &
                                 int_to_str(r%fstate(t))
            end if
          end if
          if (row > 0) then
            call node_rows(cs, ip, i, rows, nr)           ! in contact where any of its rows is
            write(u, '(a,i0,a)') int_to_str(ip) // ',' // trim(adjustl(sx(1))) // ',' // &
              trim(adjustl(sx(2))) // ',' // trim(adjustl(sx(3))) // ',' // num(mo%gap0(i)) // ',' // &
              num(minval(r%gap(rows(1:nr)))) // ',' // num(node_traction(cs, ip, i, r%mu)) // ',', &
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

  !> err: path cannot be written (status 2).
  subroutine cannot_write(path, err)
    character(len=*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: err
    call set_error(err, path // ': cannot write the file', 2)
  end subroutine cannot_write

  function num(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    write(buf, '(es24.16e3)') x
    s = trim(adjustl(buf))
  end function num

  !> The summary: one `key value...` per line (DECK.md), plus extra keys.
  subroutine write_summary(path, r, err)
    character(len=*), intent(in) :: path
    type(results_t), intent(in) :: r
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios, k
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    if (ios /= 0) then
      call cannot_write(path, err)
      return
    end if
    write(u, '(a)') 'effects ' // r%effects
    write(u, '(a)') 'force_basis ' // trim(merge('full_circle       ', 'per_unit_thickness', r%axisymmetric))
    if (allocated(r%parameter)) then
      do k = 1, size(r%parameter)
        write(u, '(a)') 'parameter ' // r%parameter(k)%s
      end do
    end if
    write(u, '(a,i0)') 'dofs ', size(r%u)
    write(u, '(a,i0)') 'free_dofs ', r%nfree
    write(u, '(a,i0)') 'contact_nodes ', r%contact_nodes
    write(u, '(a,i0)') 'active_nodes ', r%active_nodes
    write(u, '(a,i0)') 'redundant_constraints ', r%redundant
    write(u, '(a)') 'lcp_method ' // r%lcp_method
    write(u, '(a,i0)') 'lcp_iterations ', r%lcp_iterations
    write(u, '(a,a)') 'lcp_residual ', num(r%lcp_residual)
    write(u, '(a,a)') 'complementarity ', num(r%complementarity)
    write(u, '(a,a)') 'min_gap ', num(r%min_gap)
    write(u, '(a,a)') 'min_pressure ', num(r%min_pressure)
    if (allocated(r%tau)) then
      write(u, '(a,i0)') 'steps ', r%steps
      write(u, '(a,i0)') 'stick_nodes ', r%stick_nodes
      write(u, '(a,i0)') 'slip_nodes ', r%slip_nodes
    end if
    write(u, '(a,a)') 'energy ', num(r%energy)
    if (r%estimated) then
      write(u, '(a,a)') 'estimate energy ', num(r%estimate_energy)
      do k = 1, size(r%estimate_pressure)
        if (r%estimate_pressure(k) >= 0.0_dp) &
          write(u, '(a,i0,a)') 'estimate pressure ', k, ' ' // num(r%estimate_pressure(k))
      end do
    end if
    do k = 1, size(r%fix_label)
      write(u, '(a)') 'reaction ' // r%fix_label(k)%s // ' ' // num(r%reaction(1, k)) // ' ' // num(r%reaction(2, k))
    end do
    if (allocated(r%contact_force)) then
      do k = 1, size(r%contact_force, 2)
        write(u, '(a,i0,a)') 'contact_force ', k, ' ' // num(r%contact_force(1, k)) // ' ' // num(r%contact_force(2, k))
      end do
    end if
    if (allocated(r%boundary_u)) then
      do k = 1, size(r%fix_boundary)
        write(u, '(a)') 'displacement ' // r%fix_boundary(k)%s // ' ' // num(r%boundary_u(1, k)) // ' ' // &
          num(r%boundary_u(2, k))
      end do
    end if
    if (allocated(r%zones)) then
      do k = 1, size(r%zones)
        call write_zone(u, 'contact', k, r%zones(k)%contact)
        if (r%zones(k)%contact%count > 0) then
          write(u, '(a,i0,a)') 'peak_pressure ', k, ' ' // num(r%zones(k)%peak(1)) // ' ' // num(r%zones(k)%peak(2)) // &
            ' ' // num(r%zones(k)%peak(3))
          write(u, '(a,i0,a)') 'center_of_pressure ', k, ' ' // num(r%zones(k)%centre(1)) // ' ' // &
            num(r%zones(k)%centre(2))
        end if
        if (r%zones(k)%friction) call write_zone(u, 'stick', k, r%zones(k)%stick)
      end do
    end if
    if (allocated(r%rigid_name)) then
      do k = 1, size(r%rigid_name)
        write(u, '(a)') 'rigid ' // r%rigid_name(k)%s // ' ' // num(r%rigid(1, k)) // ' ' // num(r%rigid(2, k)) // &
          ' ' // num(r%rigid(3, k)) // ' ' // num(r%rigid(4, k)) // ' ' // num(r%rigid(5, k)) // ' ' // num(r%rigid(6, k))
      end do
    end if
    if (allocated(r%unheld_mode)) then
      do k = 1, size(r%unheld_mode)
        write(u, '(a)') 'unheld_mode ' // r%unheld_mode(k)%s
      end do
    end if
    if (allocated(r%max_strain_body)) write(u, '(a)') 'max_strain ' // num(r%max_strain(1)) // ' ' // &
      r%max_strain_body // ' ' // num(r%max_strain(2)) // ' ' // num(r%max_strain(3))
    if (allocated(r%max_rotation_body)) write(u, '(a)') 'max_rotation ' // num(r%max_rotation(1)) // ' ' // &
      r%max_rotation_body // ' ' // num(r%max_rotation(2)) // ' ' // num(r%max_rotation(3))
    if (allocated(r%warning)) then
      do k = 1, size(r%warning)
        write(u, '(a)') 'warning ' // r%warning(k)%s
      end do
    end if
    write(u, '(a,i0)') 'factor_nnz ', r%factor_nnz
    if (allocated(r%ordering)) write(u, '(a)') 'factor_ordering ' // r%ordering
    if (allocated(r%condense_block)) then
      do k = 1, size(r%condense_block, 2)
        write(u, '(a,i0,a,i0,a)') 'condense_block ', r%condense_block(1, k), ' ', r%condense_block(2, k), ' ' // &
          trim(merge('inverse', 'solve  ', r%condense_block(3, k) == 1))
      end do
    end if
    write(u, '(a,a)') 'memory_peak_mb ', num(r%memory_peak / 1048576.0_dp)
    write(u, '(a,a)') 'factor_memory_mb ', num(r%factor_memory / 1048576.0_dp)
    do k = 1, nphase
      write(u, '(a,a)') 'time_' // trim(phase_names(k)) // ' ', num(r%time(k))
    end do
    write(u, '(a,a)') 'time_solve ', num(r%time_solve)
    write(u, '(a,a)') 'time_ordering ', num(r%time_ordering)
    write(u, '(a,a)') 'time_assemble_values ', num(r%time_assemble_values)
    close(u, iostat=ios)
    if (ios /= 0) call cannot_write(path, err)
  end subroutine write_summary

  !> A zone's summary lines: `KIND_zone PAIR x0 y0 x1 y1 LENGTH` when any node
  !> is in it, and always `KIND_zones PAIR COUNT TOTAL` (doc/outputs.md).
  subroutine write_zone(u, kind, k, z)
    integer, intent(in) :: u, k
    character(len=*), intent(in) :: kind
    type(zone_t), intent(in) :: z
    if (z%count > 0) write(u, '(a,i0,a)') kind // '_zone ', k, ' ' // num(z%x0(1)) // ' ' // num(z%x0(2)) // ' ' // &
      num(z%x1(1)) // ' ' // num(z%x1(2)) // ' ' // num(z%length)
    write(u, '(a,i0,a,i0,a)') kind // '_zones ', k, ' ', z%count, ' ' // num(z%total)
  end subroutine write_zone

  !> A ParaView collection (.pvd) of the per-step VTK files: the dataset of
  !> step k is files(k), at timestep k.
  !>   path  (in)  file to write;  files (in) (nstep) names relative to the .pvd's folder
  !>   err   (out) allocated when not written completely
  subroutine write_pvd(path, files, err)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: files(:)
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios, k
    logical :: ok
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    if (ios /= 0) then
      call cannot_write(path, err)
      return
    end if
    write(u, '(a)', iostat=ios) '<?xml version="1.0"?>'
    write(u, '(a)', iostat=ios) '<VTKFile type="Collection" version="0.1">'
    write(u, '(a)', iostat=ios) '  <Collection>'
    do k = 1, size(files)
      write(u, '(a,i0,a)', iostat=ios) '    <DataSet timestep="', k, '" file="' // trim(files(k)) // '"/>'
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
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    if (ios /= 0) then
      call cannot_write(path, err)
      return
    end if
    write(u, '(a)', iostat=ios) header
    nc = size(table, 1)
    do k = 1, size(table, 2)
      line = ''
      do c = 1, nc
        if (c > 1) line = line // ','
        if (whole(c)) then
          line = line // int_to_str(nint(table(c, k)))
        else
          line = line // num(table(c, k))
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
