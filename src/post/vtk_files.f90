!> vtk_files: the VTK files of a run (DECK.md, "Outputs"; doc/outputs.md,
!> "The VTK file"): the legacy ASCII file of the last step, and with OUTPUT
!> steps=all the XML unstructured grid (.vtu) of each load step, binary and
!> zlib-compressed, which ParaView reads as a time series through a .pvd.
!>
!> Both formats write the same arrays from one list, vtk_arrays: which
!> arrays a run has (the OUTPUT fields, friction, the error estimate), their
!> names, types and components, and where their values come from.  A new
!> array goes into that list and appears in both formats.
!>
!> The rows are in the mesh files' numbering (each body's nodes and
!> elements as its file gives them, the bodies in deck order), whatever the
!> solver renumbered.
!>
!> Programming interface
!>   write_vtk(path, title, bodies, r, fields, err)      legacy ASCII (`# vtk DataFile Version 3.0`)
!>   write_vtu(path, bodies, r, fields, err, compress)   VTK XML UnstructuredGrid, raw binary
!>                                                       appended data, UInt64 headers; zlib
!>                                                       blocks unless compress = .false. or
!>                                                       the program was built without zlib
!>     fields (in) (5) displacement, contact_pressure, gap, stress, von_mises (OUTPUT fields=)
!>     err    (out) allocated (error_input) when the file cannot be written
module vtk_files
  use kinds, only: dp, i8
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64
  use body, only: body_t
  use mesh, only: file_item, node_in_file
  use strings, only: int_to_str, i8_to_str
  use errors, only: error_t, set_error
  use text_scan, only: string_t
  use threads, only: run_threads
  use text_buffer, only: text_buffer_t, open_text, open_memory, put_text, put_line, put_real, put_int, put_newline, &
                         close_text
  use compression, only: zlib_available, compress_blocks
  use results_writer, only: results_t, cannot_write
  implicit none
  private
  public :: write_vtk, write_vtu

  ! where an array's values come from (vtk_arrays, array_values)
  integer, parameter :: from_displacement = 1, from_pressure = 2, from_gap = 3, from_shear = 4, &
                        from_friction_state = 5, from_slip = 6, from_body = 7, from_stress = 8, &
                        from_von_mises = 9, from_error_indicator = 10, from_jacobian = 11, &
                        from_stretch = 12

  !> One array of the VTK files.
  type :: vtk_array_t
    character(len=:), allocatable :: name
    logical :: on_points = .true.       !< point data (one row per node), else cell data
    logical :: integers = .false.       !< integer values (legacy int, XML Int32), else double (Float64)
    logical :: vector = .false.         !< an (x, y) vector written as (x, y, 0): legacy VECTORS
    integer :: ncomp = 1                !< components held (2 for a vector)
    integer :: source = 0               !< from_*
  end type vtk_array_t

  ! the sections of the legacy file, row by row (put_rows)
  integer, parameter :: row_xy0 = 1, row_cell = 2, row_cell_type = 3, row_values = 4, row_ints = 5

  !> The rows of the VTK files and the values of the array being written.
  type :: vtk_rows_t
    integer, allocatable :: node_index(:)   !< (nnode) the solver's global node of each point row
    integer, allocatable :: elem_index(:)   !< (nelem) the solver's global element of each cell row
    integer, allocatable :: elem_body(:)    !< (nelem) the body of each cell row
    integer, allocatable :: cells(:,:)      !< (0:4 or 0:9, nelem) node count and 0-based points of each cell row
    real(dp), allocatable :: vals(:,:)      !< (ncomp, rows) the values of a double array, in row order
    integer, allocatable :: ivals(:)        !< (rows) the values of an integer array, in row order
  end type vtk_rows_t

  !> The uncompressed size of a zlib block of the XML files (VTK's own default).
  integer(i8), parameter :: zlib_block = 32768_i8

contains

  !> The arrays of a run's VTK files, in file order: point data, then cell
  !> data (the one list both formats write).
  !>   r      (in) the results (node_shear, node_fstate, node_slip with friction;
  !>               error_indicator with the estimate)
  !>   fields (in) (5) the OUTPUT fields: displacement, contact_pressure, gap, stress, von_mises
  !>   list   (out) the arrays
  subroutine vtk_arrays(r, fields, list)
    type(results_t), intent(in) :: r
    logical, intent(in) :: fields(5)
    type(vtk_array_t), allocatable, intent(out) :: list(:)
    type(vtk_array_t) :: all(12)
    integer :: n
    n = 0
    if (fields(1)) call add(vtk_array_t('displacement', vector=.true., ncomp=2, source=from_displacement))
    if (fields(2)) call add(vtk_array_t('contact_pressure', source=from_pressure))
    if (fields(3)) call add(vtk_array_t('gap', source=from_gap))
    ! friction: the shear and the state go with the pressure, the slip with the gap
    if (fields(2) .and. allocated(r%node_shear)) call add(vtk_array_t('contact_shear', source=from_shear))
    if (fields(2) .and. allocated(r%node_fstate)) &
      call add(vtk_array_t('friction_state', integers=.true., source=from_friction_state))
    if (fields(3) .and. allocated(r%node_slip)) call add(vtk_array_t('slip', source=from_slip))
    call add(vtk_array_t('body', on_points=.false., integers=.true., source=from_body))
    ! with a hyperelastic body the stress is the Cauchy stress (the linear bodies': theirs, equal to first order)
    if (allocated(r%jacobian)) then
      call add(vtk_array_t('cauchy_stress', on_points=.false., ncomp=size(r%stress, 1), source=from_stress))
    else if (fields(4)) then
      call add(vtk_array_t('stress', on_points=.false., ncomp=size(r%stress, 1), source=from_stress))
    end if
    if (fields(5)) call add(vtk_array_t('von_mises', on_points=.false., source=from_von_mises))
    if (allocated(r%error_indicator)) &
      call add(vtk_array_t('error_indicator', on_points=.false., source=from_error_indicator))
    ! finite strain: the change of volume and the largest stretch (inversion, strain limits)
    if (allocated(r%jacobian)) call add(vtk_array_t('J', on_points=.false., source=from_jacobian))
    if (allocated(r%stretch)) call add(vtk_array_t('stretch_max', on_points=.false., source=from_stretch))
    list = all(1:n)
  contains
    subroutine add(a)
      type(vtk_array_t), intent(in) :: a
      n = n + 1
      all(n) = a
    end subroutine add
  end subroutine vtk_arrays

  !> The names ParaView shows for the components of array a (none for a
  !> scalar): the displacement's (ux, uy, uz; x is r in axisymmetric
  !> analysis), the stress's in the order of the values (sxx, syy, sxy; in
  !> axisymmetric analysis srr, szz, srz, stt).
  function component_names(a) result(names)
    type(vtk_array_t), intent(in) :: a
    character(len=3), allocatable :: names(:)
    select case (a%source)
    case (from_displacement)
      names = ['ux ', 'uy ', 'uz ']
    case (from_stress)
      if (a%ncomp == 4) then
        names = ['srr', 'szz', 'srz', 'stt']
      else
        names = ['sxx', 'syy', 'sxy']
      end if
    case default
      allocate(names(0))
    end select
  end function component_names

  !> The values of array a in row order: v%vals (double) or v%ivals (integers).
  subroutine array_values(a, r, v)
    type(vtk_array_t), intent(in) :: a
    type(results_t), intent(in) :: r
    type(vtk_rows_t), intent(inout) :: v
    ! a node array (ndof / 2) runs past the points when RIGIDs add dofs: the rows take the points'
    select case (a%source)
    case (from_displacement);    call gather(r%u, 2, v%node_index, v)
    case (from_pressure);        call gather(r%node_pressure, 1, v%node_index, v)
    case (from_gap);             call gather(r%node_gap, 1, v%node_index, v)
    case (from_shear);           call gather(r%node_shear, 1, v%node_index, v)
    case (from_slip);            call gather(r%node_slip, 1, v%node_index, v)
    case (from_friction_state);  v%ivals = r%node_fstate(v%node_index)
    case (from_body);            v%ivals = v%elem_body
    case (from_stress);          call gather(r%stress, size(r%stress, 1), v%elem_index, v)
    case (from_von_mises);       call gather(r%vm, 1, v%elem_index, v)
    case (from_error_indicator); call gather(r%error_indicator, 1, v%elem_index, v)
    case (from_jacobian);        call gather(r%jacobian, 1, v%elem_index, v)
    case (from_stretch);         call gather(r%stretch, 1, v%elem_index, v)
    end select
  end subroutine array_values

  !> VTK legacy unstructured grid of every body (see DECK.md), ASCII: the
  !> arrays of vtk_arrays, a double array as SCALARS (or VECTORS, z = 0), an
  !> integer one as SCALARS int.
  subroutine write_vtk(path, title, bodies, r, fields, err)
    character(len=*), intent(in) :: path, title
    type(body_t), intent(in) :: bodies(:)
    type(results_t), intent(in) :: r
    logical, intent(in) :: fields(5)
    type(error_t), allocatable, intent(out) :: err
    type(text_buffer_t) :: tb
    type(vtk_rows_t) :: v
    type(vtk_array_t), allocatable :: list(:)
    integer :: nnode, nelem, ncon, k, i
    character(len=3), allocatable :: names(:)
    character(len=256) :: head
    logical :: in_points

    call grid_size(bodies, nnode, nelem, ncon)
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
    call point_coordinates(bodies, v)
    call put_rows(tb, row_xy0, nnode, v)
    call put_line(tb, 'CELLS ' // int_to_str(nelem) // ' ' // int_to_str(ncon))
    call put_rows(tb, row_cell, nelem, v)
    call put_line(tb, 'CELL_TYPES ' // int_to_str(nelem))
    call put_rows(tb, row_cell_type, nelem, v)
    call vtk_arrays(r, fields, list)
    in_points = .false.
    do k = 1, size(list)
      associate(a => list(k))
        if (a%on_points .and. .not. in_points) call put_line(tb, 'POINT_DATA ' // int_to_str(nnode))
        if (.not. a%on_points .and. (in_points .or. k == 1)) call put_line(tb, 'CELL_DATA ' // int_to_str(nelem))
        in_points = a%on_points
        call array_values(a, r, v)
        if (a%vector) then
          call put_line(tb, 'VECTORS ' // a%name // ' double')
          call put_rows(tb, row_xy0, size(v%vals, 2), v)
        else if (a%integers) then
          call put_line(tb, 'SCALARS ' // a%name // ' int 1')
          call put_line(tb, 'LOOKUP_TABLE default')
          call put_rows(tb, row_ints, size(v%ivals), v)
        else
          call put_line(tb, 'SCALARS ' // a%name // ' double ' // int_to_str(a%ncomp))
          call put_line(tb, 'LOOKUP_TABLE default')
          call put_rows(tb, row_values, size(v%vals, 2), v)
        end if
        names = component_names(a)
        if (size(names) > 0) then      ! VTK's legacy reader names the components (since VTK 8.1)
          call put_line(tb, 'METADATA')
          call put_line(tb, 'COMPONENT_NAMES')
          do i = 1, size(names)
            call put_line(tb, trim(names(i)))
          end do
          call put_line(tb, '')
        end if
      end associate
    end do
    call close_text(tb, err)
    if (allocated(err)) call cannot_write(path, err)
  end subroutine write_vtk

  !> VTK XML unstructured grid of every body (a .vtu file), the arrays of
  !> vtk_arrays: doubles as Float64 (a vector with 3 components, z = 0),
  !> integers as Int32; the points as Float64 (x, y, 0), the cells as Int64
  !> connectivity and offsets and UInt8 types.  Every array is appended raw
  !> (format="appended", encoding="raw") behind a UInt64 header: its byte
  !> count, or compressed, VTK's vtkZLibDataCompressor header [blocks, block
  !> size, size of the last block when partial (else 0), compressed size of
  !> each block] and the zlib blocks.
  !> The arrays are encoded in memory before the file is written (the XML
  !> header gives each array's offset in the appended data): the file's size
  !> of memory besides the run's.
  !>   compress (in, optional) .false.: no compression (default: when built with zlib)
  subroutine write_vtu(path, bodies, r, fields, err, compress)
    character(len=*), intent(in) :: path
    type(body_t), intent(in) :: bodies(:)
    type(results_t), intent(in) :: r
    logical, intent(in) :: fields(5)
    type(error_t), allocatable, intent(out) :: err
    logical, intent(in), optional :: compress
    type(text_buffer_t) :: tb
    type(vtk_rows_t) :: v
    type(vtk_array_t), allocatable :: list(:)
    type(string_t), allocatable :: blob(:)      ! (size(list) + 4) each array's encoded bytes, in file order
    integer(i8), allocatable :: offset(:)       ! (size(list) + 4) its offset in the appended data
    integer :: nnode, nelem, ncon, k, e, j
    integer :: i_points, i_conn, i_ends, i_types   ! the grid's blobs, after the arrays'
    integer(int64), allocatable :: conn(:), ends(:)
    logical :: zlib
    character(len=:), allocatable :: section

    zlib = zlib_available()
    if (present(compress)) zlib = zlib .and. compress
    call grid_size(bodies, nnode, nelem, ncon)
    call vtk_rows(bodies, nnode, nelem, v)
    call vtk_arrays(r, fields, list)
    ! (indices in variables: gfortran 11 miscompiles blob(size(list) + 1)%s = ...)
    i_points = size(list) + 1
    i_conn = size(list) + 2
    i_ends = size(list) + 3
    i_types = size(list) + 4
    allocate(blob(i_types), offset(i_types))
    do k = 1, size(list)
      call array_values(list(k), r, v)
      if (list(k)%integers) then
        blob(k)%s = encoded(int32_bytes(int(v%ivals, int32)), zlib)
      else if (list(k)%vector) then
        blob(k)%s = encoded(xy0_bytes(v%vals), zlib)
      else
        blob(k)%s = encoded(real_bytes(v%vals), zlib)
      end if
    end do
    ! the grid: points (x, y, 0), connectivity, offsets (the end of each cell's points), types
    call point_coordinates(bodies, v)
    blob(i_points)%s = encoded(xy0_bytes(v%vals), zlib)
    allocate(conn(ncon - nelem), ends(nelem))
    j = 0
    do e = 1, nelem
      conn(j + 1:j + v%cells(0, e)) = v%cells(1:v%cells(0, e), e)
      j = j + v%cells(0, e)
      ends(e) = j
    end do
    blob(i_conn)%s = encoded(int64_bytes(conn), zlib)
    blob(i_ends)%s = encoded(int64_bytes(ends), zlib)
    blob(i_types)%s = encoded(int8_bytes([(int(vtk_cell_type(v%cells(0, e)), int8), e = 1, nelem)]), zlib)
    offset(1) = 0
    do k = 2, size(blob)
      offset(k) = offset(k - 1) + len(blob(k - 1)%s, kind=i8)
    end do

    call open_text(tb, path, err)
    if (allocated(err)) return
    call put_line(tb, '<?xml version="1.0"?>')
    if (zlib) then
      call put_line(tb, '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="' // byte_order() // &
                        '" header_type="UInt64" compressor="vtkZLibDataCompressor">')
    else
      call put_line(tb, '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="' // byte_order() // &
                        '" header_type="UInt64">')
    end if
    call put_line(tb, '  <UnstructuredGrid>')
    call put_line(tb, '    <Piece NumberOfPoints="' // int_to_str(nnode) // '" NumberOfCells="' // int_to_str(nelem) // '">')
    section = ''
    do k = 1, size(list)
      associate(a => list(k))
        if (a%on_points .and. section /= 'PointData') then
          section = 'PointData'
          if (fields(1)) then
            call put_line(tb, '      <PointData Vectors="displacement">')
          else
            call put_line(tb, '      <PointData>')
          end if
        else if (.not. a%on_points .and. section /= 'CellData') then
          if (section == 'PointData') call put_line(tb, '      </PointData>')
          section = 'CellData'
          call put_line(tb, '      <CellData>')
        end if
        if (a%integers) then
          call put_line(tb, data_array('Int32', a%name, 1, offset(k)))
        else
          call put_line(tb, data_array('Float64', a%name, merge(3, a%ncomp, a%vector), offset(k), &
                                       component_names(a)))
        end if
      end associate
    end do
    call put_line(tb, '      </' // section // '>')
    call put_line(tb, '      <Points>')
    call put_line(tb, data_array('Float64', '', 3, offset(i_points)))
    call put_line(tb, '      </Points>')
    call put_line(tb, '      <Cells>')
    call put_line(tb, data_array('Int64', 'connectivity', 1, offset(i_conn)))
    call put_line(tb, data_array('Int64', 'offsets', 1, offset(i_ends)))
    call put_line(tb, data_array('UInt8', 'types', 1, offset(i_types)))
    call put_line(tb, '      </Cells>')
    call put_line(tb, '    </Piece>')
    call put_line(tb, '  </UnstructuredGrid>')
    call put_line(tb, '  <AppendedData encoding="raw">')
    call put_text(tb, '   _')
    do k = 1, size(blob)
      call put_text(tb, blob(k)%s)
      deallocate(blob(k)%s)
    end do
    call put_newline(tb)
    call put_line(tb, '  </AppendedData>')
    call put_line(tb, '</VTKFile>')
    call close_text(tb, err)
    if (allocated(err)) call cannot_write(path, err)
  end subroutine write_vtu

  !> One DataArray element of the XML file (name '': none, the points).
  !>   names (in, optional) its components' names (ComponentName0, ...)
  function data_array(type, name, ncomp, offset, names) result(line)
    character(len=*), intent(in) :: type, name
    integer, intent(in) :: ncomp
    integer(i8), intent(in) :: offset
    character(len=*), intent(in), optional :: names(:)
    character(len=:), allocatable :: line
    integer :: i
    line = '        <DataArray type="' // type // '"'
    if (len(name) > 0) line = line // ' Name="' // name // '"'
    if (ncomp > 1) line = line // ' NumberOfComponents="' // int_to_str(ncomp) // '"'
    if (present(names)) then
      do i = 1, size(names)
        line = line // ' ComponentName' // int_to_str(i - 1) // '="' // trim(names(i)) // '"'
      end do
    end if
    line = line // ' format="appended" offset="' // i8_to_str(offset) // '"/>'
  end function data_array

  !> An array's bytes as the appended data holds them: raw behind its UInt64
  !> byte count, or in zlib blocks behind their header (write_vtu).
  function encoded(raw, zlib) result(s)
    character(len=*), intent(in) :: raw
    logical, intent(in) :: zlib
    character(len=:), allocatable :: s
    character(len=:), allocatable :: data
    integer(i8), allocatable :: sizes(:)
    logical :: ok
    if (zlib) then
      call compress_blocks(raw, zlib_block, data, sizes, ok)
      if (ok) then
        ! [blocks, block size, size of a partial last block (0: none), each block's compressed size]
        s = int64_bytes(int([size(sizes, kind=i8), zlib_block, mod(len(raw, kind=i8), zlib_block), sizes], int64)) // data
        return
      end if
    end if
    s = int64_bytes([int(len(raw, kind=i8), int64)]) // raw
  end function encoded

  !> The byte order of this machine as VTK names it.
  function byte_order() result(name)
    character(len=:), allocatable :: name
    character(len=4) :: probe
    probe = transfer(1_int32, probe)
    if (probe(1:1) == achar(1)) then
      name = 'LittleEndian'
    else
      name = 'BigEndian'
    end if
  end function byte_order

  !> The bytes of x (ncomp, n), column by column.
  function real_bytes(x) result(b)
    real(dp), intent(in) :: x(:,:)
    character(len=:), allocatable :: b
    allocate(character(len=8 * size(x, kind=i8)) :: b)
    if (size(x) > 0) b = transfer(x, b)
  end function real_bytes

  !> The bytes of the vector rows xy (2, n) as (x, y, 0) triples.
  function xy0_bytes(xy) result(b)
    real(dp), intent(in) :: xy(:,:)
    character(len=:), allocatable :: b
    real(dp), allocatable :: xyz(:,:)
    allocate(xyz(3, size(xy, 2)))
    xyz(1:2, :) = xy
    xyz(3, :) = 0.0_dp
    b = real_bytes(xyz)
  end function xy0_bytes

  function int32_bytes(x) result(b)
    integer(int32), intent(in) :: x(:)
    character(len=:), allocatable :: b
    allocate(character(len=4 * size(x, kind=i8)) :: b)
    if (size(x) > 0) b = transfer(x, b)
  end function int32_bytes

  function int64_bytes(x) result(b)
    integer(int64), intent(in) :: x(:)
    character(len=:), allocatable :: b
    allocate(character(len=8 * size(x, kind=i8)) :: b)
    if (size(x) > 0) b = transfer(x, b)
  end function int64_bytes

  function int8_bytes(x) result(b)
    integer(int8), intent(in) :: x(:)
    character(len=:), allocatable :: b
    allocate(character(len=size(x, kind=i8)) :: b)
    if (size(x) > 0) b = transfer(x, b)
  end function int8_bytes

  !> Points, cells and connectivity entries (a count per cell and its points) over every body.
  pure subroutine grid_size(bodies, nnode, nelem, ncon)
    type(body_t), intent(in) :: bodies(:)
    integer, intent(out) :: nnode, nelem, ncon
    integer :: b
    nnode = 0; nelem = 0; ncon = 0
    do b = 1, size(bodies)
      nnode = nnode + bodies(b)%mesh%nnode
      nelem = nelem + bodies(b)%mesh%nelem
      ncon = ncon + bodies(b)%mesh%nelem + sum(bodies(b)%mesh%nen)
    end do
  end subroutine grid_size

  !> v%vals = the reference coordinates (x, y) of every point row.
  subroutine point_coordinates(bodies, v)
    type(body_t), intent(in) :: bodies(:)
    type(vtk_rows_t), intent(inout) :: v
    integer :: b, i, n0
    if (allocated(v%vals)) deallocate(v%vals)
    allocate(v%vals(2, size(v%node_index)))
    n0 = 0
    do b = 1, size(bodies)
      associate(m => bodies(b)%mesh)
        !$omp parallel do if(m%nnode > 4096)
        do i = 1, m%nnode
          v%vals(:, n0 + i) = m%x(:, v%node_index(n0 + i) - n0)
        end do
        !$omp end parallel do
        n0 = n0 + m%nnode
      end associate
    end do
  end subroutine point_coordinates

  !> VTK cell type of an element of nen nodes: 5 triangle, 9 quad, 22 quadratic
  !> triangle, 23 quadratic (8-node) quad, 28 biquadratic (9-node) quad; the
  !> node orders of gmsh and VTK agree for these.
  pure integer function vtk_cell_type(nen) result(t)
    integer, intent(in) :: nen
    select case (nen)
    case (3); t = 5
    case (6); t = 22
    case (8); t = 23
    case (9); t = 28
    case default; t = 9
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

  !> The rows of the VTK files: which of the solver's nodes and elements each
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

  !> Rows 1..n of one section of the legacy file (kind: row_*), formatted in
  !> chunks on the run's threads and written in order: the text is the same as
  !> one thread's, the formatting (most of the output time) is shared.  On one
  !> thread, or for one chunk, the rows go straight to the file's buffer: a
  !> chunk's own buffer would only add a copy and its fresh pages.
  subroutine put_rows(tb, kind, n, v)
    type(text_buffer_t), intent(inout) :: tb
    integer, intent(in) :: kind, n
    type(vtk_rows_t), intent(in) :: v
    integer, parameter :: chunk = 4096
    type(text_buffer_t) :: part
    integer :: c, i
    if (n <= chunk .or. run_threads() == 1) then
      do i = 1, n
        call put_row(tb, kind, i, v)
      end do
      return
    end if
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

  !> Row i of a section of the legacy file.
  subroutine put_row(tb, kind, i, v)
    type(text_buffer_t), intent(inout) :: tb
    integer, intent(in) :: kind, i
    type(vtk_rows_t), intent(in) :: v
    integer :: k
    select case (kind)
    case (row_xy0)                               ! points and VECTORS: x y 0
      call put_real(tb, v%vals(1, i))
      call put_real(tb, v%vals(2, i))
      call put_line(tb, ' 0')
    case (row_cell)
      do k = 0, v%cells(0, i)
        call put_int(tb, v%cells(k, i))
      end do
      call put_newline(tb)
    case (row_cell_type)
      call put_int(tb, vtk_cell_type(v%cells(0, i)))
      call put_newline(tb)
    case (row_values)                            ! SCALARS rows: the array's components
      do k = 1, size(v%vals, 1)
        call put_real(tb, v%vals(k, i))
      end do
      call put_newline(tb)
    case (row_ints)
      call put_int(tb, v%ivals(i))
      call put_newline(tb)
    end select
  end subroutine put_row

end module vtk_files
