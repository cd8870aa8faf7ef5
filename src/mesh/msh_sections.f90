!> msh_sections: the sections of a gmsh MSH ASCII file (format 2.2 or 4.1)
!> read into msh_data_t, every line checked: $MeshFormat, $PhysicalNames,
!> $Entities and $PartitionedEntities (4.1), $Nodes, and $Elements
!> (msh_elements); other sections ($Periodic, $NodeData, ...) are skipped.
!>
!>   - nodes: tags may be sparse and in any order; node k is the k-th node of
!>     the file; every z must vanish up to 1e-10 of the mesh extent
!>     max(xmax - xmin, ymax - ymin).  Dense tags (max tag <= 2 nnode + 1000,
!>     as gmsh writes them) are indexed by a table tag -> node, others by
!>     sorting them for a binary search;
!>   - MSH 4.1: the physical tags of an element are those of its entity,
!>     listed in $Entities, or in $PartitionedEntities for a partitioned mesh
!>     (gmsh -part N: the partitioning is ignored); node blocks with
!>     parametric coordinates are accepted.
!>
!> The section readers share their arguments: t (inout) the file and the
!> reading position, d (inout) what has been read, and err (out) the first
!> defect of the file or a failed allocation (reading then stops).
!>
!> Programming interface
!>   read_sections(t, d, err)   every section of the loaded file t into d
module msh_sections
  use kinds, only: dp, i8
  use strings, only: int_to_str, i8_to_str, real_to_str
  use errors, only: error_t
  use text_scan, only: scan_integer
  use sorting, only: sort_columns
  use msh_text, only: msh_text_t, advance_line, remaining_lines, item, quoted_item, read_data_line, &
                      expect_section_end, fail, fail_at, file_error, get_integer, get_count, get_real, &
                      msh_real, read_block_header, scan_data_lines, allocation_failed, no_integers, &
                      no_reals, no_lower_bounds, end_blocks, read_block_line, &
                      get_dimension_tag
  use msh_data, only: msh_data_t, push_record
  use msh_elements, only: read_elements_22, read_elements_41
  implicit none
  private
  public :: read_sections

  real(dp), parameter :: z_tolerance = 1.0e-10_dp  !< |z| / extent allowed

contains

  !> Read every section of the file into d, checking each line.
  subroutine read_sections(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    logical :: more, partitioned
    character(len=:), allocatable :: w

    ! The first line that is not blank must open $MeshFormat.
    do
      call advance_line(t, more, err)
      if (allocated(err)) return
      if (.not. more) then
        call file_error('the mesh file holds only blank lines (a gmsh MSH file starting with '// &
          '$MeshFormat expected)', err)
        return
      end if
      if (t%ntok > 0) exit
    end do
    if (t%ntok /= 1 .or. item(t, 1) /= '$MeshFormat') then
      call fail(t, 'not a gmsh MSH file ($MeshFormat expected on the first line)', err)
      return
    end if
    call read_mesh_format(t, d, err)
    if (allocated(err)) return

    do
      call advance_line(t, more, err)
      if (allocated(err)) return
      if (.not. more) exit
      if (t%ntok == 0) cycle
      w = item(t, 1)
      if (w(1:1) /= '$') then
        call fail(t, 'unexpected text outside a section (a section header such as $Nodes expected)', err)
        return
      end if
      if (t%ntok /= 1) then
        call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (a section header alone on its line expected)', err)
        return
      end if
      select case (w)
      case ('$MeshFormat')
        call fail(t, 'second $MeshFormat section (one per file expected)', err)
        return
      case ('$PhysicalNames')
        if (.not. first_section(d%have_names)) return
        call read_physical_names(t, d, err)
      case ('$Entities', '$PartitionedEntities')
        ! $PartitionedEntities (gmsh -part) comes after $Entities and replaces it
        partitioned = w == '$PartitionedEntities'
        if (.not. d%v41) then
          call expect_section_end(t, w(2:), err, skip=.true.)
        else if (merge(d%have_partitions, d%have_entities, partitioned)) then
          call fail(t, 'second ' // w // ' section (one per file expected)', err)
          return
        else if (d%have_nodes .or. d%have_elements .or. (partitioned .neqv. d%have_entities)) then
          call fail(t, w // ' out of place (' // trim(merge('after $Entities and before', &
            'before                    ', partitioned)) // ' $Nodes and $Elements expected)', err)
          return
        else
          d%have_entities = .true.
          d%have_partitions = partitioned
          call read_entities(t, d, partitioned, err)
        end if
      case ('$Nodes')
        if (.not. first_section(d%have_nodes)) return
        if (d%v41) then
          call read_nodes_41(t, d, err)
        else
          call read_nodes_22(t, d, err)
        end if
        if (.not. allocated(err)) call check_nodes(t, d, err)
      case ('$Elements')
        if (.not. first_section(d%have_elements)) return
        if (.not. d%have_nodes) then
          call fail(t, '$Elements before $Nodes (the $Nodes section expected first)', err)
          return
        end if
        if (d%v41) then
          call read_elements_41(t, d, err)
        else
          call read_elements_22(t, d, err)
        end if
      case default
        if (len(w) >= 4) then
          if (w(2:4) == 'End') then
            call fail(t, 'unexpected ' // quoted_item(t, 1) // ' (no section of that name is open)', err)
            return
          end if
        end if
        call expect_section_end(t, w(2:), err, skip=.true.)
      end select
      if (allocated(err)) return
    end do

    if (.not. d%have_nodes) then
      call file_error('no $Nodes section (a gmsh mesh with $Nodes and $Elements sections expected)', err)
      return
    end if
    if (.not. d%have_elements) then
      call file_error('no $Elements section (a 2D mesh expected: mesh with gmsh -2)', err)
      return
    end if
  contains
    !> Section w is the first of its name in the file (seen false, then set);
    !> a second one is reported.
    logical function first_section(seen)
      logical, intent(inout) :: seen
      first_section = .not. seen
      if (seen) call fail(t, 'second ' // w // ' section (one per file expected)', err)
      seen = .true.
    end function first_section
  end subroutine read_sections

  !> $MeshFormat: `version file-type data-size`, then $EndMeshFormat.
  subroutine read_mesh_format(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    real(dp) :: version
    integer(i8) :: filetype, datasize

    call read_data_line(t, 'MeshFormat', 3, 'version file-type data-size, e.g. 4.1 0 8', err)
    if (allocated(err)) return
    if (msh_real(item(t, 1), version) /= 0) then
      call fail(t, 'bad MSH version ' // quoted_item(t, 1) // ' (2.2 or 4.1 expected)', err)
      return
    end if
    if (abs(version - 2.2_dp) < 1.0e-9_dp) then
      d%v41 = .false.
    else if (abs(version - 4.1_dp) < 1.0e-9_dp) then
      d%v41 = .true.
    else
      call fail(t, 'unsupported MSH version ' // quoted_item(t, 1) // &
        ' (2.2 or 4.1 expected: gmsh -format msh22 or -format msh41)', err)
      return
    end if
    if (.not. scan_integer(item(t, 2), filetype)) filetype = -1
    if (filetype == 1) then
      call fail(t, 'binary MSH file (ASCII expected: gmsh -format msh22 or -format msh41 without -bin)', err)
      return
    else if (filetype /= 0) then
      call fail(t, 'bad file type ' // quoted_item(t, 2) // ' (0 for ASCII expected)', err)
      return
    end if
    if (.not. scan_integer(item(t, 3), datasize)) datasize = -1
    if (datasize <= 0) then
      call fail(t, 'bad data size ' // quoted_item(t, 3) // ' (a positive integer, usually 8, expected)', err)
      return
    end if
    call expect_section_end(t, 'MeshFormat', err)
  end subroutine read_mesh_format

  !> $PhysicalNames: count, then `dimension tag "name"` lines.
  subroutine read_physical_names(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    integer :: n, k, stat
    integer(i8) :: dim, tag, q1, q2

    call read_data_line(t, 'PhysicalNames', 1, 'the number of physical names', err)
    if (allocated(err)) return
    call get_count(t, 1, 'number of physical names', remaining_lines(t), n, err)
    if (allocated(err)) return
    allocate(d%name_key(2, n), d%name_text(n), stat=stat)
    if (allocation_failed(stat, 32_i8 * n, err)) return
    do k = 1, n
      call read_data_line(t, 'PhysicalNames', 0, 'dimension tag "name"', err)
      if (allocated(err)) return
      if (t%ntok < 3) then
        call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (3 expected: dimension tag "name")', err)
        return
      end if
      call get_dimension_tag(t, 1, 'physical', dim, tag, err)
      if (allocated(err)) return
      q1 = t%tbeg(3)
      q2 = t%tend(t%ntok)
      if (t%buf(q1:q1) /= '"' .or. q2 <= q1 .or. t%buf(q2:q2) /= '"') then
        call fail(t, 'bad physical name (a name in double quotes expected)', err)
        return
      end if
      d%name_key(:, k) = [dim, tag]
      d%name_text(k)%s = t%buf(q1 + 1:q2 - 1)
    end do
    call sort_columns(d%name_key, d%name_perm, stat)
    if (allocation_failed(stat, 8_i8 * n, err)) return
    call expect_section_end(t, 'PhysicalNames', err)
  end subroutine read_physical_names

  !> $Entities (4.1): the physical tags of every point, curve, surface, volume.
  !> $PartitionedEntities (4.1, written by gmsh -part N): the same for the
  !> entities of the partitions, which then replace those of $Entities (the
  !> $Nodes and $Elements blocks name them).  Lines come first
  !> (numPartitions; numGhostEntities, then `tag partition` each), and each entity line
  !> begins `tag parentDim parentTag numPartitions partitionTags...` before
  !> what $Entities has.  The partitioning itself is not kept: the mesh is
  !> the one that was partitioned.  An entity of a partition keeps the
  !> physical tags it lists only when its parent has its dimension: the
  !> curves and points gmsh adds where partitions meet list the tags of their
  !> parent surface or curve, which would name the wrong group.
  !>   partitioned (in) .true. for $PartitionedEntities
  subroutine read_entities(t, d, partitioned, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    logical, intent(in) :: partitioned
    type(error_t), allocatable, intent(out) :: err
    character(len=*), parameter :: what(0:3) = [character(len=18) :: 'number of points', &
      'number of curves', 'number of surfaces', 'number of volumes']
    character(len=*), parameter :: parent = 'tag parentDim parentTag numPartitions partitionTags'
    character(len=:), allocatable :: point_line, entity_line, section
    integer :: counts(0:3), dim, k, j, nent, nfixed, left, o, stat
    integer(i8) :: nphys, nbound, tag, btag, phys, pdim, npart, v
    real(dp) :: r
    character(len=:), allocatable :: line_what

    point_line = 'tag x y z numPhysicalTags physicalTags'
    entity_line = 'tag minX minY minZ maxX maxY maxZ numPhysicalTags physicalTags numBounding boundingTags'
    section = 'Entities'
    if (partitioned) then
      point_line = parent // point_line(4:)
      entity_line = parent // entity_line(4:)
      section = 'PartitionedEntities'
      call read_data_line(t, section, 1, 'numPartitions', err)
      if (allocated(err)) return
      call get_integer(t, 1, 'number of partitions', 1_i8, huge(1_i8), v, err)
      if (allocated(err)) return
      call read_data_line(t, section, 1, 'numGhostEntities', err)
      if (allocated(err)) return
      call get_integer(t, 1, 'number of ghost entities', 0_i8, int(remaining_lines(t), i8), v, err)
      if (allocated(err)) return
      do k = 1, int(v)
        call read_data_line(t, section, 2, 'ghostEntityTag partition', err)
        if (allocated(err)) return
      end do
      ! the partitions' entities replace those of $Entities
      deallocate(d%ent_key, d%ent_first, d%ent_count, d%ent_perm)
      d%ent_phys%n = 0
    end if
    call read_data_line(t, section, 4, 'numPoints numCurves numSurfaces numVolumes', err)
    if (allocated(err)) return
    left = remaining_lines(t)
    do dim = 0, 3
      call get_count(t, dim + 1, trim(what(dim)), left, counts(dim), err)
      if (allocated(err)) return
    end do
    if (sum(int(counts, i8)) > int(left, i8)) then
      call fail(t, 'entity counts are more than the rest of the file holds (at most ' // int_to_str(left) // &
        ' entities in all expected; truncated file?)', err)
      return
    end if
    nent = sum(counts)
    allocate(d%ent_key(2, nent), d%ent_first(nent), d%ent_count(nent), stat=stat)
    if (allocation_failed(stat, 24_i8 * nent, err)) return
    nent = 0
    do dim = 0, 3
      do k = 1, counts(dim)
        if (dim == 0) then
          line_what = point_line
        else
          line_what = entity_line
        end if
        call read_data_line(t, section, 0, line_what, err)
        if (allocated(err)) return
        ! o: the items before the coordinates that a partition's entity adds
        o = 0
        pdim = dim
        if (partitioned) then
          if (t%ntok < 4) then
            call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least 4 expected: ' // &
              line_what // ')', err)
            return
          end if
          call get_dimension_tag(t, 2, 'parent', pdim, v, err)
          if (allocated(err)) return
          call get_integer(t, 4, 'number of partitions', 0_i8, int(t%ntok - 4, i8), npart, err)
          if (allocated(err)) return
          o = 3 + int(npart)
        end if
        nfixed = merge(4, 7, dim == 0) + o
        if (t%ntok < nfixed + 1) then
          call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least ' // &
            int_to_str(nfixed + 1) // ' expected: ' // line_what // ')', err)
          return
        end if
        call get_integer(t, 1, 'entity tag', -huge(1_i8), huge(1_i8), tag, err)
        if (allocated(err)) return
        do j = 2 + o, nfixed
          call get_real(t, j, 'a coordinate', r, err)
          if (allocated(err)) return
        end do
        call get_integer(t, nfixed + 1, 'number of physical tags', 0_i8, int(t%ntok - nfixed - 1, i8), nphys, err)
        if (allocated(err)) return
        if (dim == 0) then
          if (t%ntok /= nfixed + 1 + nphys) then
            call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // &
              int_to_str(nfixed + 1 + int(nphys)) // ' expected: ' // point_line // ')', err)
            return
          end if
        else
          if (t%ntok < nfixed + 2 + nphys) then
            call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least ' // &
              int_to_str(nfixed + 2 + int(nphys)) // ' expected: ' // entity_line // ')', err)
            return
          end if
          call get_integer(t, nfixed + 2 + int(nphys), 'number of bounding entities', 0_i8, &
            huge(1_i8), nbound, err)
          if (allocated(err)) return
          if (t%ntok /= nfixed + 2 + nphys + nbound) then
            call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // &
              trim(i8_to_str(nfixed + 2 + nphys + nbound)) // ' expected: ' // entity_line // ')', err)
            return
          end if
          do j = nfixed + 3 + int(nphys), t%ntok
            call get_integer(t, j, 'bounding entity tag', -huge(1_i8), huge(1_i8), btag, err)
            if (allocated(err)) return
          end do
        end if
        nent = nent + 1
        d%ent_key(:, nent) = [int(dim, i8), tag]
        d%ent_first(nent) = d%ent_phys%n + 1
        if (pdim /= dim) nphys = 0            ! where partitions meet: no group of its own
        d%ent_count(nent) = int(nphys)
        do j = nfixed + 2, nfixed + 1 + int(nphys)
          call get_integer(t, j, 'physical tag', -huge(1_i8), huge(1_i8), phys, err)
          if (allocated(err)) return
          call push_record(d%ent_phys, [phys], err)
          if (allocated(err)) return
        end do
      end do
    end do
    call sort_columns(d%ent_key, d%ent_perm, stat)
    if (allocation_failed(stat, 8_i8 * nent, err)) return
    call expect_section_end(t, section, err)
  end subroutine read_entities

  !> $Nodes of MSH 2.2: count, then `tag x y z` lines.
  subroutine read_nodes_22(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    integer :: n, k, first, stat
    real(dp), allocatable :: xyz(:,:)
    logical :: fast

    call read_data_line(t, 'Nodes', 1, 'the number of nodes', err)
    if (allocated(err)) return
    call get_count(t, 1, 'number of nodes', remaining_lines(t), n, err)
    if (allocated(err)) return
    call allocate_nodes(d, n, err)
    if (allocated(err)) return
    first = t%ln + 1
    allocate(xyz(3, n), stat=stat)
    if (allocation_failed(stat, 24_i8 * n, err)) return
    call scan_data_lines(t, n, [1_i8], 3, d%ntag, xyz, fast)
    if (fast) then
      do k = 1, n
        d%x(:, k) = xyz(1:2, k)
        d%z(k) = xyz(3, k)
        d%tag_line(k) = first + k - 1
        d%coord_line(k) = first + k - 1
      end do
      call expect_section_end(t, 'Nodes', err)
      return
    end if
    do k = 1, n
      call read_data_line(t, 'Nodes', 4, 'node-tag x y z', err)
      if (allocated(err)) return
      call get_integer(t, 1, 'node tag', 1_i8, huge(1_i8), d%ntag(1, k), err)
      if (allocated(err)) return
      d%tag_line(k) = t%ln
      call get_coordinates(t, 2, d%x(:, k), d%z(k), err)
      if (allocated(err)) return
      d%coord_line(k) = t%ln
    end do
    call expect_section_end(t, 'Nodes', err)
  end subroutine read_nodes_22

  !> $Nodes of MSH 4.1: `numEntityBlocks numNodes minNodeTag maxNodeTag`, then
  !> per block `entityDim entityTag parametric numNodesInBlock`, the tags one per
  !> line, then the coordinates `x y z` followed by entityDim parametric
  !> coordinates when parametric = 1.
  subroutine read_nodes_41(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    integer :: nblock, n, b, m, k, j, i, header, nitem, first, stat
    integer(i8) :: dim, param, tag
    real(dp) :: r
    real(dp), allocatable :: xyz(:,:)
    character(len=:), allocatable :: line_what
    logical :: fast

    call read_block_header(t, 'Nodes', 'node', 2, nblock, n, err)
    if (allocated(err)) return
    header = t%ln
    call allocate_nodes(d, n, err)
    if (allocated(err)) return
    k = 0
    do b = 1, nblock
      call read_block_line(t, 'Nodes', 'entityDim entityTag parametric numNodesInBlock', dim, tag, err)
      if (allocated(err)) return
      call get_integer(t, 3, 'parametric flag', 0_i8, 1_i8, param, err)
      if (allocated(err)) return
      call get_count(t, 4, 'number of nodes in the block', n - k, m, err)
      if (allocated(err)) return
      first = t%ln + 1
      call scan_data_lines(t, m, [1_i8], 0, d%ntag(:, k + 1:k + m), no_reals, fast)
      if (fast) then
        do j = 1, m
          d%tag_line(k + j) = first + j - 1
        end do
      else
        do j = k + 1, k + m
          call read_data_line(t, 'Nodes', 1, 'node-tag', err)
          if (allocated(err)) return
          call get_integer(t, 1, 'node tag', 1_i8, huge(1_i8), d%ntag(1, j), err)
          if (allocated(err)) return
          d%tag_line(j) = t%ln
        end do
      end if
      nitem = 3 + int(param * dim)
      first = t%ln + 1
      allocate(xyz(3, m), stat=stat)
      if (allocation_failed(stat, 24_i8 * m, err)) return
      call scan_data_lines(t, m, no_lower_bounds, nitem, no_integers, xyz, fast)
      if (fast) then
        d%x(:, k + 1:k + m) = xyz(1:2, :)
        d%z(k + 1:k + m) = xyz(3, :)
        do j = 1, m
          d%coord_line(k + j) = first + j - 1
        end do
      else
        if (nitem == 3) then
          line_what = 'x y z'
        else
          line_what = 'x y z and ' // i8_to_str(dim) // ' parametric coordinates'
        end if
        do j = k + 1, k + m
          call read_data_line(t, 'Nodes', nitem, line_what, err)
          if (allocated(err)) return
          call get_coordinates(t, 1, d%x(:, j), d%z(j), err)
          if (allocated(err)) return
          do i = 4, nitem
            call get_real(t, i, 'a parametric coordinate', r, err)
            if (allocated(err)) return
          end do
          d%coord_line(j) = t%ln
        end do
      end if
      deallocate(xyz)
      k = k + m
    end do
    call end_blocks(t, 'Nodes', 'node', header, k, n, err)
  end subroutine read_nodes_41

  !> The node arrays of d for n nodes; err when memory ran out.
  subroutine allocate_nodes(d, n, err)
    type(msh_data_t), intent(inout) :: d
    integer, intent(in) :: n
    type(error_t), allocatable, intent(out) :: err
    integer :: stat
    d%nnode = n
    allocate(d%x(2, n), d%z(n), d%ntag(1, n), d%tag_line(n), d%coord_line(n), stat=stat)
    if (allocation_failed(stat, 40_i8 * n, err)) return
  end subroutine allocate_nodes

  !> x, y, z from items k, k+1, k+2 of the current line.
  subroutine get_coordinates(t, k, xy, z, err)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    real(dp), intent(out) :: xy(2), z
    type(error_t), allocatable, intent(out) :: err
    call get_real(t, k, 'x', xy(1), err)
    if (allocated(err)) return
    call get_real(t, k + 1, 'y', xy(2), err)
    if (allocated(err)) return
    call get_real(t, k + 2, 'z', z, err)
  end subroutine get_coordinates

  !> After $Nodes: index the tags, report the first duplicate tag or the first
  !> node off the plane z = 0, whichever comes first in the file.
  !> Dense tags (max tag <= 2 nnode + 1000, as gmsh writes them) are indexed by
  !> a table tag -> node, others by sorting them for a binary search.  Either
  !> way the duplicate reported is the node of the earliest line whose tag an
  !> earlier node has.
  subroutine check_nodes(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    integer :: i, dup_line, z_line, dup_node, z_node, stat
    integer(i8) :: max_tag, tag
    real(dp) :: extent

    dup_line = huge(1)
    dup_node = 0
    max_tag = 0
    do i = 1, d%nnode
      max_tag = max(max_tag, d%ntag(1, i))
    end do
    if (max_tag <= 2_i8 * d%nnode + 1000_i8) then
      allocate(d%tag_index(max_tag), source=0, stat=stat)
      if (allocation_failed(stat, 4_i8 * max_tag, err)) return
      do i = 1, d%nnode
        tag = d%ntag(1, i)
        if (d%tag_index(tag) == 0) then
          d%tag_index(tag) = i
        else if (dup_node == 0) then
          dup_line = d%tag_line(i)
          dup_node = i
        end if
      end do
    else
      call sort_columns(d%ntag, d%tag_perm, stat)
      if (allocation_failed(stat, 8_i8 * d%nnode, err)) return
      do i = 2, d%nnode
        if (d%ntag(1, d%tag_perm(i)) == d%ntag(1, d%tag_perm(i - 1))) then
          if (d%tag_line(d%tag_perm(i)) < dup_line) then
            dup_line = d%tag_line(d%tag_perm(i))
            dup_node = d%tag_perm(i)
          end if
        end if
      end do
    end if
    z_line = huge(1)
    z_node = 0
    if (d%nnode > 0) then
      extent = max(maxval(d%x(1, :)) - minval(d%x(1, :)), maxval(d%x(2, :)) - minval(d%x(2, :)))
      do i = 1, d%nnode
        if (abs(d%z(i)) > z_tolerance * extent) then
          z_line = d%coord_line(i)
          z_node = i
          exit
        end if
      end do
    end if
    if (dup_node == 0 .and. z_node == 0) return
    if (dup_line < z_line) then
      call fail_at(t, dup_line, 'duplicate node tag ' // i8_to_str(d%ntag(1, dup_node)) // &
        ' (each node tag defined once expected)', err)
    else
      call fail_at(t, z_line, 'node ' // i8_to_str(d%ntag(1, z_node)) // ' has z = ' // real_to_str(d%z(z_node)) // &
        ' (a planar mesh in z = 0 expected)', err)
    end if
  end subroutine check_nodes

end module msh_sections
