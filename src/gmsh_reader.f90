!> gmsh_reader: read a gmsh mesh file (MSH ASCII, format 2.2 or 4.1) into a
!> mesh_t (gmsh_runner runs gmsh on a .geo file).
!>
!> What is read
!>   - nodes: tags may be sparse and in any order; node k of the mesh is the k-th
!>     node of the file, x(1:2, k) its coordinates; every z must vanish up to
!>     1e-10 of the mesh extent max(xmax - xmin, ymax - ymin);
!>   - 2D elements: 3-node triangles (type 2) and 4-node quadrangles (type 3), or
!>     second order: 6-node triangles (9), 8-node (16) and 9-node (10)
!>     quadrangles, with the mid-side nodes where gmsh put them (curved edges), all
!>     of them, in the file's node order; MSH 2.2 repeats an element once per
!>     physical group holding it, so elements with the same node set are merged
!>     (hash table of the sorted node sets, O(n));
!>   - physical groups: a physical curve gives a boundary_t whose edges are its
!>     2-node lines (type 1) or 3-node lines (type 8: ends, then the middle, kept
!>     as the edge's mid-side node); a physical point gives a boundary_t whose points are
!>     its point elements (type 15); a physical surface gives a region_t of element
!>     indices.  A group is named from $PhysicalNames, else by its number ("3");
!>     groups of the same name (e.g. a physical point and a physical curve) make
!>     one boundary_t.  Boundaries and regions come in order of (dimension, tag).
!>   - MSH 4.1: the physical tags of an element are those of its entity, listed in
!>     $Entities, or in $PartitionedEntities for a partitioned mesh (gmsh -part N:
!>     the partitioning is ignored); node blocks with parametric coordinates are accepted.
!>   Unknown sections ($Periodic, $NodeData, ...) are skipped.  The mesh is left as
!>   read: compaction of unused nodes, orientation and quality checks are the
!>   caller's (finalize_mesh of module mesh).
!>
!> Errors
!>   The whole file is read into memory and split into lines first, so any line
!>   length and any byte are safe and every count read from the file is checked
!>   against the number of lines left before anything is allocated from it.
!>   Numbers are validated character by character before they are converted (so
!>   that no overflow can occur in the conversion) and must be finite and of
!>   magnitude below 1e100.  A real is the double nearest to its text, as an
!>   internal read gives it; the common texts (up to 18 significant digits,
!>   moderate exponents) are converted exactly with integer arithmetic, the
!>   others by an internal read.  The first defect found is reported to diag as
!>   `FILE:LINE: what is wrong (what was expected)` with the line echoed, and
!>   reading stops; the mesh is then returned empty.
!>
!> The section readers below share their arguments: t (inout) the file and the
!> reading position, d (inout) what has been read, diag (inout) the messages, and
!> ok (out) .false. once an error has been reported (reading then stops).
!>
!> Speed
!>   Items are parsed in place in the file's buffer (no substring copies), node
!>   tags are looked up in a table tag -> node when they are dense (else by a
!>   binary search of the sorted tags), and repeated elements are found by a
!>   counting sort on their lowest node: reading costs O(file size).  The file
!>   is split into lines on the threads, and so are the data lines of a block
!>   (nodes, and 2D elements of MSH 4.1): a fast path that accepts exactly
!>   what the line-by-line reading accepts and, on any defect, leaves the
!>   block to it, so that messages are built on one thread only.
!>
!> Programming interface
!>   read_gmsh_file(path, mesh, diag)
!>        read the MSH file path into mesh; errors go to diag
module gmsh_reader
  use kinds, only: dp, i8
  use diagnostics, only: diag_t, add_error, int_to_str, i8_to_str, real_to_str, printable
  use text_scan, only: scan_integer, scan_real, line_items, is_blank
  use sorting, only: sort_columns, search_columns, mark_repeated, sort_small, text_key_words, pack_text
  use safe_files, only: read_file
  use mesh, only: mesh_t
  implicit none
  private
  public :: read_gmsh_file

  real(dp), parameter :: z_tolerance = 1.0e-10_dp  !< |z| / extent allowed
  integer, parameter :: max_decimal_exponent = 99  !< numbers below 1e100 in magnitude
  integer, parameter :: max_number_length = 200    !< longest accepted number item
  integer, parameter :: echo_length = 100          !< characters of a line echoed
  integer, parameter :: quote_length = 40          !< characters of an item quoted
  integer, parameter :: raw_width = 11             !< nen, 9 nodes, line: an element read
  integer, parameter :: max_fast_items = 8         !< items of a line on the fast path
  integer, parameter :: fast_parallel_min = 4096   !< lines parsed on the threads from
  integer(i8), parameter :: fast_parallel_bytes = 262144  !< files split into lines on the threads from
  integer(i8) :: no_integers(0, 0)                 !< iv of scan_data_lines for no integers
  real(dp) :: no_reals(0, 0)                       !< rv of scan_data_lines for no reals
  integer(i8) :: no_lower_bounds(0)                !< lo of scan_data_lines for no integers
  character(len=*), parameter :: order_hint = &
    'triangles of 3 or 6 nodes, quads of 4, 8 or 9 nodes and 2- or 3-node lines expected; mesh with gmsh -order 1 or 2'

  !> A character string of any length.
  type :: string_t
    character(len=:), allocatable :: s
  end type string_t

  !> A growing table of integer records of a fixed width.
  type :: record_list_t
    integer :: n = 0                          !< number of records held
    integer(i8), allocatable :: v(:,:)        !< (width, capacity) the records
  end type record_list_t

  !> The file in memory, split into lines, and the reading position.
  type :: msh_text_t
    character(len=:), allocatable :: path     !< file name for messages
    character(len=:), allocatable :: buf      !< the whole file
    integer(i8), allocatable :: lbeg(:)       !< (nline) first byte of each line
    integer(i8), allocatable :: lend(:)       !< (nline) last byte, lbeg - 1 when empty
    integer :: nline = 0                      !< number of lines
    integer :: ln = 0                         !< current line, 0 before the first
    integer :: ntok = 0                       !< number of items on the current line
    integer(i8), allocatable :: tbeg(:)       !< (capacity) first byte of each item
    integer(i8), allocatable :: tend(:)       !< (capacity) last byte of each item
  end type msh_text_t

  !> What the sections hold, as read.
  type :: msh_data_t
    logical :: v41 = .false.                  !< format 4.1 (else 2.2)
    logical :: have_names = .false.           !< $PhysicalNames seen
    logical :: have_entities = .false.        !< $Entities seen
    logical :: have_partitions = .false.      !< $PartitionedEntities seen (gmsh -part)
    logical :: have_nodes = .false.           !< $Nodes seen
    logical :: have_elements = .false.        !< $Elements seen
    integer :: nnode = 0                      !< number of nodes
    real(dp), allocatable :: x(:,:)           !< (2, nnode) coordinates x, y
    real(dp), allocatable :: z(:)             !< (nnode) coordinate z
    integer(i8), allocatable :: ntag(:,:)     !< (1, nnode) node tags
    integer, allocatable :: tag_line(:)       !< (nnode) line of each node tag
    integer, allocatable :: coord_line(:)     !< (nnode) line of each node's coordinates
    integer, allocatable :: tag_index(:)      !< (max tag) node of each tag, 0 for none, when the
                                              !< tags are dense (max tag <= 2 nnode + 1000)
    integer, allocatable :: tag_perm(:)       !< (nnode) else: ntag(1, tag_perm) ascending
    integer(i8), allocatable :: tag_sorted(:) !< (nnode) and ntag(1, tag_perm), for the search
    integer(i8), allocatable :: name_key(:,:) !< (2, nname) dimension, tag of each name
    type(string_t), allocatable :: name_text(:) !< (nname) physical names
    integer, allocatable :: name_perm(:)      !< (nname) name_key sorted
    integer(i8), allocatable :: ent_key(:,:)  !< (2, nent) dimension, tag of each entity
    integer, allocatable :: ent_first(:)      !< (nent) first physical in ent_phys
    integer, allocatable :: ent_count(:)      !< (nent) number of physical tags
    integer, allocatable :: ent_perm(:)       !< (nent) ent_key sorted
    type(record_list_t) :: ent_phys           !< (1, *) physical tags of the entities
    type(record_list_t) :: raw                !< (raw_width, *) nen, 9 nodes, line of each 2D
                                              !< element read
    type(record_list_t) :: region_pairs       !< (2, *) physical tag, raw element
    type(record_list_t) :: edges              !< (5, *) physical tag, node, node, line, middle node (0: none)
    type(record_list_t) :: points             !< (2, *) physical tag, node
  end type msh_data_t

contains

  ! ---------------------------------------------------------------------------
  ! Reading a mesh file
  ! ---------------------------------------------------------------------------

  !> Read a gmsh MSH ASCII file (format 2.2 or 4.1) into a mesh.
  !>   path (in)    file to open; also the name used in messages
  !>   mesh (out)   nodes, elements, named boundaries and regions as in the file;
  !>                empty (nnode = nelem = 0) when an error was found
  !>   diag (inout) receives one message for the first defect of the file
  subroutine read_gmsh_file(path, mesh, diag)
    character(len=*), intent(in) :: path
    type(mesh_t), intent(out) :: mesh
    type(diag_t), intent(inout) :: diag
    type(msh_text_t) :: t
    type(msh_data_t) :: d
    logical :: ok

    t%path = path
    call load_text(t, diag, ok)
    if (.not. ok) return
    call read_sections(t, d, diag, ok)
    if (.not. ok) return
    call build_mesh(d, mesh)
  end subroutine read_gmsh_file

  !> Read the file into t%buf and find its lines (LF or CRLF ends).
  subroutine load_text(t, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    character, parameter :: lf = achar(10), cr = achar(13)
    integer :: status, n, k, c
    integer(i8) :: p, q, nbytes, nlf, chunk_end(2), chunk_lf(2)

    ok = .false.
    call read_file(t%path, t%buf, status)
    select case (status)
    case (1)
      call add_error(diag, t%path, 0, 'cannot open the mesh file (an existing, readable gmsh .msh file expected)')
      return
    case (2)
      call add_error(diag, t%path, 0, 'cannot read the mesh file (a readable regular file expected)')
      return
    case (3)
      call add_error(diag, t%path, 0, 'mesh file too large to hold in memory (a smaller mesh expected)')
      return
    case (4)
      call add_error(diag, t%path, 0, 'the mesh file is not a regular file (a FIFO, a device or a folder): ' // &
                     'refused (a gmsh .msh file expected)')
      return
    end select
    nbytes = len(t%buf, kind=i8)
    if (nbytes == 0) then
      call add_error(diag, t%path, 0, 'the mesh file is empty (a gmsh MSH file starting with $MeshFormat expected)')
      return
    end if

    ! Count the lines: one per LF, plus an unterminated last line.  The file is
    ! scanned in two halves side by side, LF counts first, then the lines.
    chunk_end = [nbytes / 2, nbytes]
    chunk_lf = 0
    !$omp parallel do if(nbytes > fast_parallel_bytes) private(p, q)
    do c = 1, 2
      q = 0                                          ! a register, not the shared array
      do p = merge(1_i8, chunk_end(1) + 1, c == 1), chunk_end(c)
        q = q + merge(1_i8, 0_i8, t%buf(p:p) == lf)   ! no branch to mispredict
      end do
      chunk_lf(c) = q
    end do
    !$omp end parallel do
    nlf = sum(chunk_lf)
    if (t%buf(nbytes:nbytes) /= lf) nlf = nlf + 1
    if (nlf > int(huge(1), i8) - 4_i8) then
      call add_error(diag, t%path, 0, 'mesh file has too many lines (fewer than 2**31 expected)')
      return
    end if
    n = int(nlf)
    ! Line k runs from lbeg(k) to the byte before its LF (or to the end of the
    ! file), less a CR before the LF.
    allocate(t%lbeg(n), t%lend(n))
    t%lbeg(1) = 1
    !$omp parallel do if(nbytes > fast_parallel_bytes) private(p, k)
    do c = 1, 2
      k = int(merge(0_i8, chunk_lf(1), c == 1))      ! the LFs before the chunk
      do p = merge(1_i8, chunk_end(1) + 1, c == 1), chunk_end(c)
        if (t%buf(p:p) == lf) then
          k = k + 1
          t%lend(k) = p - 1
          if (p > 1) then
            if (t%buf(p - 1:p - 1) == cr) t%lend(k) = p - 2
          end if
          if (k < n) t%lbeg(k + 1) = p + 1
        end if
      end do
    end do
    !$omp end parallel do
    if (t%buf(nbytes:nbytes) /= lf) then
      t%lend(n) = nbytes
      if (t%buf(nbytes:nbytes) == cr) t%lend(n) = nbytes - 1
    end if
    t%nline = n
    t%ln = 0
    allocate(t%tbeg(16), t%tend(16))
    ok = .true.
  end subroutine load_text

  !> Read every section of the file into d, checking each line.
  subroutine read_sections(t, d, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    logical :: more, partitioned
    character(len=:), allocatable :: w

    ok = .false.
    ! The first line that is not blank must open $MeshFormat.
    do
      call advance_line(t, more)
      if (.not. more) then
        call add_error(diag, t%path, 0, 'the mesh file holds only blank lines (a gmsh MSH file starting with '// &
          '$MeshFormat expected)')
        return
      end if
      if (t%ntok > 0) exit
    end do
    if (t%ntok /= 1 .or. item(t, 1) /= '$MeshFormat') then
      call fail(t, diag, 'not a gmsh MSH file ($MeshFormat expected on the first line)')
      return
    end if
    call read_mesh_format(t, d, diag, ok)
    if (.not. ok) return

    ok = .false.
    do
      call advance_line(t, more)
      if (.not. more) exit
      if (t%ntok == 0) cycle
      w = item(t, 1)
      if (w(1:1) /= '$') then
        call fail(t, diag, 'unexpected text outside a section (a section header such as $Nodes expected)')
        return
      end if
      if (t%ntok /= 1) then
        call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (a section header alone on its line expected)')
        return
      end if
      select case (w)
      case ('$MeshFormat')
        call fail(t, diag, 'second $MeshFormat section (one per file expected)')
        return
      case ('$PhysicalNames')
        if (d%have_names) then
          call fail(t, diag, 'second $PhysicalNames section (one per file expected)')
          return
        end if
        d%have_names = .true.
        call read_physical_names(t, d, diag, ok)
      case ('$Entities', '$PartitionedEntities')
        ! $PartitionedEntities (gmsh -part) comes after $Entities and replaces it
        partitioned = w == '$PartitionedEntities'
        if (.not. d%v41) then
          call skip_section(t, diag, w(2:), ok)
        else if (merge(d%have_partitions, d%have_entities, partitioned)) then
          call fail(t, diag, 'second ' // w // ' section (one per file expected)')
          return
        else if (d%have_nodes .or. d%have_elements .or. (partitioned .neqv. d%have_entities)) then
          call fail(t, diag, w // ' out of place (' // trim(merge('after $Entities and before', &
            'before                    ', partitioned)) // ' $Nodes and $Elements expected)')
          return
        else
          d%have_entities = .true.
          d%have_partitions = partitioned
          call read_entities(t, d, diag, partitioned, ok)
        end if
      case ('$Nodes')
        if (d%have_nodes) then
          call fail(t, diag, 'second $Nodes section (one per file expected)')
          return
        end if
        d%have_nodes = .true.
        if (d%v41) then
          call read_nodes_41(t, d, diag, ok)
        else
          call read_nodes_22(t, d, diag, ok)
        end if
        if (ok) call check_nodes(t, d, diag, ok)
      case ('$Elements')
        if (d%have_elements) then
          call fail(t, diag, 'second $Elements section (one per file expected)')
          return
        end if
        if (.not. d%have_nodes) then
          call fail(t, diag, '$Elements before $Nodes (the $Nodes section expected first)')
          return
        end if
        d%have_elements = .true.
        if (d%v41) then
          call read_elements_41(t, d, diag, ok)
        else
          call read_elements_22(t, d, diag, ok)
        end if
      case default
        if (len(w) >= 4) then
          if (w(2:4) == 'End') then
            call fail(t, diag, 'unexpected ' // quoted_item(t, 1) // ' (no section of that name is open)')
            return
          end if
        end if
        call skip_section(t, diag, w(2:), ok)
      end select
      if (.not. ok) return
      ok = .false.
    end do

    if (.not. d%have_nodes) then
      call add_error(diag, t%path, 0, 'no $Nodes section (a gmsh mesh with $Nodes and $Elements sections expected)')
      return
    end if
    if (.not. d%have_elements) then
      call add_error(diag, t%path, 0, 'no $Elements section (a 2D mesh expected: mesh with gmsh -2)')
      return
    end if
    ok = .true.
  end subroutine read_sections

  !> $MeshFormat: `version file-type data-size`, then $EndMeshFormat.
  subroutine read_mesh_format(t, d, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    real(dp) :: version
    integer(i8) :: filetype, datasize

    call read_data_line(t, diag, 'MeshFormat', 3, 'version file-type data-size, e.g. 4.1 0 8', ok)
    if (.not. ok) return
    ok = .false.
    if (msh_real(item(t, 1), version) /= 0) then
      call fail(t, diag, 'bad MSH version ' // quoted_item(t, 1) // ' (2.2 or 4.1 expected)')
      return
    end if
    if (abs(version - 2.2_dp) < 1.0e-9_dp) then
      d%v41 = .false.
    else if (abs(version - 4.1_dp) < 1.0e-9_dp) then
      d%v41 = .true.
    else
      call fail(t, diag, 'unsupported MSH version ' // quoted_item(t, 1) // &
        ' (2.2 or 4.1 expected: gmsh -format msh22 or -format msh41)')
      return
    end if
    if (.not. scan_integer(item(t, 2), filetype)) filetype = -1
    if (filetype == 1) then
      call fail(t, diag, 'binary MSH file (ASCII expected: gmsh -format msh22 or -format msh41 without -bin)')
      return
    else if (filetype /= 0) then
      call fail(t, diag, 'bad file type ' // quoted_item(t, 2) // ' (0 for ASCII expected)')
      return
    end if
    if (.not. scan_integer(item(t, 3), datasize)) datasize = -1
    if (datasize <= 0) then
      call fail(t, diag, 'bad data size ' // quoted_item(t, 3) // ' (a positive integer, usually 8, expected)')
      return
    end if
    call expect_section_end(t, diag, 'MeshFormat', ok)
  end subroutine read_mesh_format

  !> $PhysicalNames: count, then `dimension tag "name"` lines.
  subroutine read_physical_names(t, d, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    integer :: n, k
    integer(i8) :: dim, tag, q1, q2

    call read_data_line(t, diag, 'PhysicalNames', 1, 'the number of physical names', ok)
    if (.not. ok) return
    call get_count(t, diag, 1, 'number of physical names', remaining_lines(t), n, ok)
    if (.not. ok) return
    allocate(d%name_key(2, n), d%name_text(n))
    do k = 1, n
      call read_data_line(t, diag, 'PhysicalNames', 0, 'dimension tag "name"', ok)
      if (.not. ok) return
      if (t%ntok < 3) then
        call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (3 expected: dimension tag "name")')
        ok = .false.
        return
      end if
      call get_integer(t, diag, 1, 'physical dimension', 0_i8, 3_i8, dim, ok)
      if (.not. ok) return
      call get_integer(t, diag, 2, 'physical tag', -huge(1_i8), huge(1_i8), tag, ok)
      if (.not. ok) return
      q1 = t%tbeg(3)
      q2 = t%tend(t%ntok)
      if (t%buf(q1:q1) /= '"' .or. q2 <= q1 .or. t%buf(q2:q2) /= '"') then
        call fail(t, diag, 'bad physical name (a name in double quotes expected)')
        ok = .false.
        return
      end if
      d%name_key(:, k) = [dim, tag]
      d%name_text(k)%s = t%buf(q1 + 1:q2 - 1)
    end do
    call sort_columns(d%name_key, d%name_perm)
    call expect_section_end(t, diag, 'PhysicalNames', ok)
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
  subroutine read_entities(t, d, diag, partitioned, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(in) :: partitioned
    logical, intent(out) :: ok
    character(len=*), parameter :: what(0:3) = [character(len=18) :: 'number of points', &
      'number of curves', 'number of surfaces', 'number of volumes']
    character(len=*), parameter :: parent = 'tag parentDim parentTag numPartitions partitionTags'
    character(len=:), allocatable :: point_line, entity_line, section
    integer :: counts(0:3), dim, k, j, nent, nfixed, left, o
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
      call read_data_line(t, diag, section, 1, 'numPartitions', ok)
      if (.not. ok) return
      call get_integer(t, diag, 1, 'number of partitions', 1_i8, huge(1_i8), v, ok)
      if (.not. ok) return
      call read_data_line(t, diag, section, 1, 'numGhostEntities', ok)
      if (.not. ok) return
      call get_integer(t, diag, 1, 'number of ghost entities', 0_i8, int(remaining_lines(t), i8), v, ok)
      if (.not. ok) return
      do k = 1, int(v)
        call read_data_line(t, diag, section, 2, 'ghostEntityTag partition', ok)
        if (.not. ok) return
      end do
      ! the partitions' entities replace those of $Entities
      deallocate(d%ent_key, d%ent_first, d%ent_count, d%ent_perm)
      d%ent_phys%n = 0
    end if
    call read_data_line(t, diag, section, 4, 'numPoints numCurves numSurfaces numVolumes', ok)
    if (.not. ok) return
    left = remaining_lines(t)
    do dim = 0, 3
      call get_count(t, diag, dim + 1, trim(what(dim)), left, counts(dim), ok)
      if (.not. ok) return
    end do
    if (sum(int(counts, i8)) > int(left, i8)) then
      call fail(t, diag, 'entity counts are more than the rest of the file holds (at most ' // int_to_str(left) // &
        ' entities in all expected; truncated file?)')
      ok = .false.
      return
    end if
    nent = sum(counts)
    allocate(d%ent_key(2, nent), d%ent_first(nent), d%ent_count(nent))
    nent = 0
    do dim = 0, 3
      do k = 1, counts(dim)
        if (dim == 0) then
          line_what = point_line
        else
          line_what = entity_line
        end if
        call read_data_line(t, diag, section, 0, line_what, ok)
        if (.not. ok) return
        ok = .false.
        ! o: the items before the coordinates that a partition's entity adds
        o = 0
        pdim = dim
        if (partitioned) then
          if (t%ntok < 4) then
            call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least 4 expected: ' // &
              line_what // ')')
            return
          end if
          call get_integer(t, diag, 2, 'parent dimension', 0_i8, 3_i8, pdim, ok)
          if (.not. ok) return
          call get_integer(t, diag, 3, 'parent tag', -huge(1_i8), huge(1_i8), v, ok)
          if (.not. ok) return
          call get_integer(t, diag, 4, 'number of partitions', 0_i8, int(t%ntok - 4, i8), npart, ok)
          if (.not. ok) return
          ok = .false.
          o = 3 + int(npart)
        end if
        nfixed = merge(4, 7, dim == 0) + o
        if (t%ntok < nfixed + 1) then
          call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least ' // &
            int_to_str(nfixed + 1) // ' expected: ' // line_what // ')')
          return
        end if
        call get_integer(t, diag, 1, 'entity tag', -huge(1_i8), huge(1_i8), tag, ok)
        if (.not. ok) return
        do j = 2 + o, nfixed
          call get_real(t, diag, j, 'a coordinate', r, ok)
          if (.not. ok) return
        end do
        call get_integer(t, diag, nfixed + 1, 'number of physical tags', 0_i8, int(t%ntok - nfixed - 1, i8), nphys, ok)
        if (.not. ok) return
        if (dim == 0) then
          if (t%ntok /= nfixed + 1 + nphys) then
            call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // &
              int_to_str(nfixed + 1 + int(nphys)) // ' expected: ' // point_line // ')')
            ok = .false.
            return
          end if
        else
          if (t%ntok < nfixed + 2 + nphys) then
            call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least ' // &
              int_to_str(nfixed + 2 + int(nphys)) // ' expected: ' // entity_line // ')')
            ok = .false.
            return
          end if
          call get_integer(t, diag, nfixed + 2 + int(nphys), 'number of bounding entities', 0_i8, &
            huge(1_i8), nbound, ok)
          if (.not. ok) return
          if (t%ntok /= nfixed + 2 + nphys + nbound) then
            call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // &
              trim(i8_to_str(nfixed + 2 + nphys + nbound)) // ' expected: ' // entity_line // ')')
            ok = .false.
            return
          end if
          do j = nfixed + 3 + int(nphys), t%ntok
            call get_integer(t, diag, j, 'bounding entity tag', -huge(1_i8), huge(1_i8), btag, ok)
            if (.not. ok) return
          end do
        end if
        nent = nent + 1
        d%ent_key(:, nent) = [int(dim, i8), tag]
        d%ent_first(nent) = d%ent_phys%n + 1
        if (pdim /= dim) nphys = 0            ! where partitions meet: no group of its own
        d%ent_count(nent) = int(nphys)
        do j = nfixed + 2, nfixed + 1 + int(nphys)
          call get_integer(t, diag, j, 'physical tag', -huge(1_i8), huge(1_i8), phys, ok)
          if (.not. ok) return
          call push_record(d%ent_phys, [phys])
        end do
      end do
    end do
    call sort_columns(d%ent_key, d%ent_perm)
    call expect_section_end(t, diag, section, ok)
  end subroutine read_entities

  !> $Nodes of MSH 2.2: count, then `tag x y z` lines.
  subroutine read_nodes_22(t, d, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    integer :: n, k, first
    real(dp), allocatable :: xyz(:,:)
    logical :: fast

    call read_data_line(t, diag, 'Nodes', 1, 'the number of nodes', ok)
    if (.not. ok) return
    call get_count(t, diag, 1, 'number of nodes', remaining_lines(t), n, ok)
    if (.not. ok) return
    call allocate_nodes(d, n)
    first = t%ln + 1
    allocate(xyz(3, n))
    call scan_data_lines(t, n, [1_i8], 3, d%ntag, xyz, fast)
    if (fast) then
      d%x = xyz(1:2, :)
      d%z = xyz(3, :)
      d%tag_line = [(first + k, k = 0, n - 1)]
      d%coord_line = d%tag_line
      call expect_section_end(t, diag, 'Nodes', ok)
      return
    end if
    do k = 1, n
      call read_data_line(t, diag, 'Nodes', 4, 'node-tag x y z', ok)
      if (.not. ok) return
      call get_integer(t, diag, 1, 'node tag', 1_i8, huge(1_i8), d%ntag(1, k), ok)
      if (.not. ok) return
      d%tag_line(k) = t%ln
      call get_coordinates(t, diag, 2, d%x(:, k), d%z(k), ok)
      if (.not. ok) return
      d%coord_line(k) = t%ln
    end do
    call expect_section_end(t, diag, 'Nodes', ok)
  end subroutine read_nodes_22

  !> $Nodes of MSH 4.1: `numEntityBlocks numNodes minNodeTag maxNodeTag`, then
  !> per block `entityDim entityTag parametric numNodesInBlock`, the tags one per
  !> line, then the coordinates `x y z` followed by entityDim parametric
  !> coordinates when parametric = 1.
  subroutine read_nodes_41(t, d, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    integer :: nblock, n, b, m, k, j, i, left, header, nitem, first
    integer(i8) :: dim, param, tag
    real(dp) :: r
    real(dp), allocatable :: xyz(:,:)
    character(len=:), allocatable :: line_what
    logical :: fast

    call read_data_line(t, diag, 'Nodes', 4, 'numEntityBlocks numNodes minNodeTag maxNodeTag', ok)
    if (.not. ok) return
    header = t%ln
    left = remaining_lines(t)
    call get_count(t, diag, 1, 'number of node blocks', left, nblock, ok)
    if (.not. ok) return
    call get_count(t, diag, 2, 'number of nodes', left, n, ok)
    if (.not. ok) return
    if (int(nblock, i8) + 2_i8 * n > int(left, i8)) then
      call fail(t, diag, 'node counts are more than the rest of the file holds (numEntityBlocks + 2 numNodes <= ' // &
        int_to_str(left) // ' expected; truncated file?)')
      ok = .false.
      return
    end if
    call get_integer(t, diag, 3, 'minimum node tag', -huge(1_i8), huge(1_i8), tag, ok)
    if (.not. ok) return
    call get_integer(t, diag, 4, 'maximum node tag', -huge(1_i8), huge(1_i8), tag, ok)
    if (.not. ok) return
    call allocate_nodes(d, n)
    k = 0
    do b = 1, nblock
      call read_data_line(t, diag, 'Nodes', 4, 'entityDim entityTag parametric numNodesInBlock', ok)
      if (.not. ok) return
      call get_integer(t, diag, 1, 'entity dimension', 0_i8, 3_i8, dim, ok)
      if (.not. ok) return
      call get_integer(t, diag, 2, 'entity tag', -huge(1_i8), huge(1_i8), tag, ok)
      if (.not. ok) return
      call get_integer(t, diag, 3, 'parametric flag', 0_i8, 1_i8, param, ok)
      if (.not. ok) return
      call get_count(t, diag, 4, 'number of nodes in the block', n - k, m, ok)
      if (.not. ok) return
      first = t%ln + 1
      call scan_data_lines(t, m, [1_i8], 0, d%ntag(:, k + 1:k + m), no_reals, fast)
      if (fast) then
        d%tag_line(k + 1:k + m) = [(first + j, j = 0, m - 1)]
      else
        do j = k + 1, k + m
          call read_data_line(t, diag, 'Nodes', 1, 'node-tag', ok)
          if (.not. ok) return
          call get_integer(t, diag, 1, 'node tag', 1_i8, huge(1_i8), d%ntag(1, j), ok)
          if (.not. ok) return
          d%tag_line(j) = t%ln
        end do
      end if
      nitem = 3 + int(param * dim)
      first = t%ln + 1
      allocate(xyz(3, m))
      call scan_data_lines(t, m, no_lower_bounds, nitem, no_integers, xyz, fast)
      if (fast) then
        d%x(:, k + 1:k + m) = xyz(1:2, :)
        d%z(k + 1:k + m) = xyz(3, :)
        d%coord_line(k + 1:k + m) = [(first + j, j = 0, m - 1)]
      else
        if (nitem == 3) then
          line_what = 'x y z'
        else
          line_what = 'x y z and ' // i8_to_str(dim) // ' parametric coordinates'
        end if
        do j = k + 1, k + m
          call read_data_line(t, diag, 'Nodes', nitem, line_what, ok)
          if (.not. ok) return
          call get_coordinates(t, diag, 1, d%x(:, j), d%z(j), ok)
          if (.not. ok) return
          do i = 4, nitem
            call get_real(t, diag, i, 'a parametric coordinate', r, ok)
            if (.not. ok) return
          end do
          d%coord_line(j) = t%ln
        end do
      end if
      deallocate(xyz)
      k = k + m
    end do
    if (k /= n) then
      call fail_at(t, diag, header, 'the node blocks hold ' // int_to_str(k) // ' nodes, the header announces ' // &
        int_to_str(n) // ' (equal counts expected)')
      ok = .false.
      return
    end if
    call expect_section_end(t, diag, 'Nodes', ok)
  end subroutine read_nodes_41

  subroutine allocate_nodes(d, n)
    type(msh_data_t), intent(inout) :: d
    integer, intent(in) :: n
    d%nnode = n
    allocate(d%x(2, n), d%z(n), d%ntag(1, n), d%tag_line(n), d%coord_line(n))
  end subroutine allocate_nodes

  !> x, y, z from items k, k+1, k+2 of the current line.
  subroutine get_coordinates(t, diag, k, xy, z, ok)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: k
    real(dp), intent(out) :: xy(2), z
    logical, intent(out) :: ok
    call get_real(t, diag, k, 'x', xy(1), ok)
    if (.not. ok) return
    call get_real(t, diag, k + 1, 'y', xy(2), ok)
    if (.not. ok) return
    call get_real(t, diag, k + 2, 'z', z, ok)
  end subroutine get_coordinates

  !> After $Nodes: index the tags, report the first duplicate tag or the first
  !> node off the plane z = 0, whichever comes first in the file.
  !> Dense tags (max tag <= 2 nnode + 1000, as gmsh writes them) are indexed by
  !> a table tag -> node, others by sorting them for a binary search.  Either
  !> way the duplicate reported is the node of the earliest line whose tag an
  !> earlier node has.
  subroutine check_nodes(t, d, diag, ok)
    type(msh_text_t), intent(in) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    integer :: i, dup_line, z_line, dup_node, z_node
    integer(i8) :: max_tag, tag
    real(dp) :: extent

    dup_line = huge(1)
    dup_node = 0
    max_tag = 0
    do i = 1, d%nnode
      max_tag = max(max_tag, d%ntag(1, i))
    end do
    if (max_tag <= 2_i8 * d%nnode + 1000_i8) then
      allocate(d%tag_index(max_tag), source=0)
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
      call sort_columns(d%ntag, d%tag_perm)
      allocate(d%tag_sorted(d%nnode))
      do i = 1, d%nnode
        d%tag_sorted(i) = d%ntag(1, d%tag_perm(i))
      end do
      do i = 2, d%nnode
        if (d%tag_sorted(i) == d%tag_sorted(i - 1)) then
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
    ok = dup_node == 0 .and. z_node == 0
    if (ok) return
    if (dup_line < z_line) then
      call fail_at(t, diag, dup_line, 'duplicate node tag ' // i8_to_str(d%ntag(1, dup_node)) // &
        ' (each node tag defined once expected)')
    else
      call fail_at(t, diag, z_line, 'node ' // i8_to_str(d%ntag(1, z_node)) // ' has z = ' // real_to_str(d%z(z_node)) // &
        ' (a planar mesh in z = 0 expected)')
    end if
  end subroutine check_nodes

  !> $Elements of MSH 2.2: count, then `number type ntags tags... nodes...`.
  subroutine read_elements_22(t, d, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    character(len=*), parameter :: what = 'elm-number elm-type number-of-tags tags node-tags'
    integer :: n, k, header, etype, nn, j
    integer(i8) :: v, ntags, phys(1)

    phys = 0

    call read_data_line(t, diag, 'Elements', 1, 'the number of elements', ok)
    if (.not. ok) return
    header = t%ln
    call get_count(t, diag, 1, 'number of elements', remaining_lines(t), n, ok)
    if (.not. ok) return
    call reserve_records(d%raw, raw_width, n)
    do k = 1, n
      call read_data_line(t, diag, 'Elements', 0, what, ok)
      if (.not. ok) return
      ok = .false.
      if (t%ntok < 3) then
        call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least 3 expected: ' // what // ')')
        return
      end if
      call get_integer(t, diag, 1, 'element number', -huge(1_i8), huge(1_i8), v, ok)
      if (.not. ok) return
      call get_element_type(t, diag, 2, -1, etype, nn, ok)
      if (.not. ok) return
      call get_integer(t, diag, 3, 'number of tags', 0_i8, huge(1_i8), ntags, ok)
      if (.not. ok) return
      if (3_i8 + ntags + nn /= t%ntok) then
        call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // &
          trim(i8_to_str(3_i8 + ntags + nn)) // ' expected: 3 + ' // trim(i8_to_str(ntags)) // ' tags + ' // &
          int_to_str(nn) // ' nodes for element type ' // int_to_str(etype) // ')')
        ok = .false.
        return
      end if
      do j = 4, 3 + int(ntags)
        call get_integer(t, diag, j, 'tag', -huge(1_i8), huge(1_i8), v, ok)
        if (.not. ok) return
        if (j == 4) phys(1) = v
      end do
      if (ntags >= 1 .and. phys(1) /= 0) then
        call add_element(t, d, diag, etype, 4 + int(ntags), phys, ok)
      else
        call add_element(t, d, diag, etype, 4 + int(ntags), phys(1:0), ok)
      end if
      if (.not. ok) return
    end do
    call expect_section_end(t, diag, 'Elements', ok)
    if (.not. ok) return
    call check_some_2d(t, d, diag, header - 1, ok)
  end subroutine read_elements_22

  !> $Elements of MSH 4.1: `numEntityBlocks numElements minTag maxTag`, then per
  !> block `entityDim entityTag elementType numElementsInBlock` and the elements
  !> `tag node-tags`.
  subroutine read_elements_41(t, d, diag, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    logical, intent(out) :: ok
    integer :: nblock, n, b, m, k, j, left, header, etype, nn, ient, first, count
    integer(i8) :: dim, tag, v
    integer(i8), allocatable :: phys(:)
    character(len=:), allocatable :: line_what
    logical :: fast

    call read_data_line(t, diag, 'Elements', 4, 'numEntityBlocks numElements minElementTag maxElementTag', ok)
    if (.not. ok) return
    header = t%ln
    left = remaining_lines(t)
    call get_count(t, diag, 1, 'number of element blocks', left, nblock, ok)
    if (.not. ok) return
    call get_count(t, diag, 2, 'number of elements', left, n, ok)
    if (.not. ok) return
    if (int(nblock, i8) + n > int(left, i8)) then
      call fail(t, diag, 'element counts are more than the rest of the file holds (numEntityBlocks + numElements <= ' // &
        int_to_str(left) // ' expected; truncated file?)')
      ok = .false.
      return
    end if
    call reserve_records(d%raw, raw_width, n)
    call get_integer(t, diag, 3, 'minimum element tag', -huge(1_i8), huge(1_i8), tag, ok)
    if (.not. ok) return
    call get_integer(t, diag, 4, 'maximum element tag', -huge(1_i8), huge(1_i8), tag, ok)
    if (.not. ok) return
    k = 0
    do b = 1, nblock
      call read_data_line(t, diag, 'Elements', 4, 'entityDim entityTag elementType numElementsInBlock', ok)
      if (.not. ok) return
      call get_integer(t, diag, 1, 'entity dimension', 0_i8, 3_i8, dim, ok)
      if (.not. ok) return
      call get_integer(t, diag, 2, 'entity tag', -huge(1_i8), huge(1_i8), tag, ok)
      if (.not. ok) return
      call get_element_type(t, diag, 3, int(dim), etype, nn, ok)
      if (.not. ok) return
      call get_count(t, diag, 4, 'number of elements in the block', n - k, m, ok)
      if (.not. ok) return
      ! The physical tags of the block: those of its entity.
      allocate(phys(0))
      if (d%have_entities) then
        ient = search_columns(d%ent_key, d%ent_perm, [dim, tag])
        if (ient == 0) then
          call fail(t, diag, 'element block on undefined entity ' // i8_to_str(tag) // ' of dimension ' // &
            i8_to_str(dim) // ' (an entity listed in $Entities expected)')
          ok = .false.
          return
        end if
        first = d%ent_first(ient)
        count = d%ent_count(ient)
        if (count > 0) phys = d%ent_phys%v(1, first:first + count - 1)
      end if
      fast = .false.
      if (etype == 2 .or. etype == 3) call scan_elements(t, d, m, nn, phys, fast)
      if (.not. fast) then
        line_what = 'element-tag and ' // int_to_str(nn) // ' node tags'
        do j = 1, m
          call read_data_line(t, diag, 'Elements', 1 + nn, line_what, ok)
          if (.not. ok) return
          call get_integer(t, diag, 1, 'element tag', -huge(1_i8), huge(1_i8), v, ok)
          if (.not. ok) return
          call add_element(t, d, diag, etype, 2, phys, ok)
          if (.not. ok) return
        end do
      end if
      deallocate(phys)
      k = k + m
    end do
    if (k /= n) then
      call fail_at(t, diag, header, 'the element blocks hold ' // int_to_str(k) // ' elements, the header announces ' // &
        int_to_str(n) // ' (equal counts expected)')
      ok = .false.
      return
    end if
    call expect_section_end(t, diag, 'Elements', ok)
    if (.not. ok) return
    call check_some_2d(t, d, diag, header - 1, ok)
  end subroutine read_elements_41

  !> Report a mesh without 2D elements at the $Elements line.
  subroutine check_some_2d(t, d, diag, header, ok)
    type(msh_text_t), intent(in) :: t
    type(msh_data_t), intent(in) :: d
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: header
    logical, intent(out) :: ok
    ok = d%raw%n > 0
    if (.not. ok) call fail_at(t, diag, header, &
      'no 2D elements (triangles or quadrilaterals expected: mesh with gmsh -2)')
  end subroutine check_some_2d

  !> Element type from item k: a supported type (1, 2, 3, 8, 9, 10, 15, 16) of dimension dim
  !> (any when dim < 0); nn its number of nodes.
  subroutine get_element_type(t, diag, k, dim, etype, nn, ok)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: k, dim
    integer, intent(out) :: etype, nn
    logical, intent(out) :: ok
    integer(i8) :: v
    character(len=:), allocatable :: kind_text

    etype = 0
    nn = 0
    call get_integer(t, diag, k, 'element type', -huge(1_i8), huge(1_i8), v, ok)
    if (.not. ok) return
    ok = .false.
    if (v < 0 .or. v > 1000) then
      call fail(t, diag, 'unsupported element type ' // quoted_item(t, k) // ' (' // order_hint // ')')
      return
    end if
    etype = int(v)
    select case (etype)
    case (1)
      nn = 2
    case (2)
      nn = 3
    case (3)
      nn = 4
    case (15)
      nn = 1
    case (8)
      nn = 3
    case (9)
      nn = 6
    case (16)
      nn = 8
    case (10)
      nn = 9
    case default
      kind_text = element_description(etype)
      if (len(kind_text) == 0) then
        call fail(t, diag, 'unsupported element type ' // int_to_str(etype) // ' (' // order_hint // ')')
      else if (element_is_3d(etype)) then
        call fail(t, diag, 'unsupported element type ' // int_to_str(etype) // ', a ' // kind_text // &
          ' (a 2D mesh expected: mesh with gmsh -2)')
      else
        call fail(t, diag, 'unsupported element type ' // int_to_str(etype) // ', a ' // kind_text // &
          ' (' // order_hint // ')')
      end if
      return
    end select
    if (dim >= 0 .and. dim /= element_dimension(etype)) then
      call fail(t, diag, 'element type ' // int_to_str(etype) // ' in a block of dimension ' // int_to_str(dim) // &
        ' (the dimension of the element type expected)')
      return
    end if
    ok = .true.
  end subroutine get_element_type

  !> Record one element of a supported type whose node tags are items
  !> kfirst.. of the current line; phys are its physical tags.
  subroutine add_element(t, d, diag, etype, kfirst, phys, ok)
    type(msh_text_t), intent(in) :: t
    type(msh_data_t), intent(inout) :: d
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: etype, kfirst
    integer(i8), intent(in) :: phys(:)
    logical, intent(out) :: ok
    integer(i8) :: tag, node(9)
    integer :: k, nn, idx, p

    nn = t%ntok - kfirst + 1
    node = 0
    do k = 1, nn
      call get_integer(t, diag, kfirst + k - 1, 'node tag', 1_i8, huge(1_i8), tag, ok)
      if (.not. ok) return
      idx = node_of_tag(d, tag)
      if (idx == 0) then
        call fail(t, diag, 'element refers to undefined node tag ' // i8_to_str(tag) // &
          ' (a node tag defined in $Nodes expected)')
        ok = .false.
        return
      end if
      node(k) = idx
    end do
    select case (etype)
    case (15)
      do p = 1, size(phys)
        call push_record(d%points, [phys(p), node(1)])
      end do
    case (1, 8)                       ! node(3): the middle of a 3-node line, 0 for a 2-node line
      do p = 1, size(phys)
        call push_record(d%edges, [phys(p), node(1), node(2), int(t%ln, i8), node(3)])
      end do
    case (2, 3, 9, 16, 10)
      call push_record(d%raw, [int(nn, i8), node, int(t%ln, i8)])
      do p = 1, size(phys)
        call push_record(d%region_pairs, [phys(p), int(d%raw%n, i8)])
      end do
    end select
    ok = .true.
  end subroutine add_element

  !> Skip an unknown section up to its $End line.
  subroutine skip_section(t, diag, name, ok)
    type(msh_text_t), intent(inout) :: t
    type(diag_t), intent(inout) :: diag
    character(len=*), intent(in) :: name
    logical, intent(out) :: ok
    logical :: more
    ok = .false.
    do
      call advance_line(t, more)
      if (.not. more) then
        call report_end_of_file(t, diag, name)
        return
      end if
      if (t%ntok >= 1) then
        if (t%buf(t%tbeg(1):t%tend(1)) == '$End' // name) exit
      end if
    end do
    ok = .true.
  end subroutine skip_section

  ! ---------------------------------------------------------------------------
  ! From the records read to mesh_t
  ! ---------------------------------------------------------------------------

  !> Merge repeated 2D elements, fill the mesh and its named sets.
  subroutine build_mesh(d, mesh)
    type(msh_data_t), intent(in) :: d
    type(mesh_t), intent(out) :: mesh
    integer, allocatable :: rep(:), elem_of_raw(:)
    integer :: nraw, r, nelem, width

    ! Elements with the same node set are one element, represented by the first
    ! of them in the file.
    nraw = d%raw%n
    call find_repeated_elements(d, rep)
    allocate(elem_of_raw(nraw))
    nelem = 0
    do r = 1, nraw
      if (rep(r) == r) then
        nelem = nelem + 1
        elem_of_raw(r) = nelem
      else
        elem_of_raw(r) = elem_of_raw(rep(r))
      end if
    end do

    mesh%nnode = d%nnode
    mesh%x = d%x
    mesh%nelem = nelem
    width = 4                                 ! conn(4, *), or conn(9, *) with quadratic elements
    if (nraw > 0) then
      if (any(d%raw%v(1, 1:nraw) > 4)) width = 9
    end if
    allocate(mesh%nen(nelem), mesh%conn(width, nelem), mesh%elem_line(nelem))
    do r = 1, nraw
      if (rep(r) /= r) cycle
      mesh%nen(elem_of_raw(r)) = int(d%raw%v(1, r))
      mesh%conn(:, elem_of_raw(r)) = int(d%raw%v(2:1 + width, r))
      mesh%elem_line(elem_of_raw(r)) = int(d%raw%v(raw_width, r))
    end do
    call build_boundaries(d, mesh)
    call build_regions(d, elem_of_raw, mesh)
  end subroutine build_mesh

  !> rep(r) = the first raw element with the node set of raw element r (r when
  !> no earlier one has it).  Two elements with the same node set have the
  !> same lowest node: the elements' keys (lowest node, nen, the other nodes
  !> ascending, element) are sorted by lowest node with a stable counting sort
  !> in two levels, on its high bits, then within each of those buckets on
  !> its low bits, so that every pass stays in the cache (gmsh numbers the
  !> nodes of an element far apart: a hash table, or a counting sort in one
  !> level, missed the cache on every element).  Each run of one lowest node
  !> is then compared pairwise when it is short, by sorting its keys when it
  !> is not (a fan of many elements at a node).
  subroutine find_repeated_elements(d, rep)
    type(msh_data_t), intent(in) :: d
    integer, allocatable, intent(out) :: rep(:)
    integer, parameter :: pairwise_max = 16, low_bits = 10
    integer, allocatable :: first(:), perm(:), item(:,:), sorted(:,:)
    integer(i8), allocatable :: keys(:,:)
    integer :: nraw, nhigh, r, lo, h, i, j, m, p0, q, key(4), low_first(0:2**low_bits)
    logical :: leads(pairwise_max)

    nraw = d%raw%n
    nhigh = shiftr(max(d%nnode - 1, 0), low_bits) + 1
    allocate(rep(nraw), first(0:nhigh), item(6, nraw), sorted(6, nraw))
    ! level 1: buckets of the high bits of lowest node - 1, in file order
    first = 0
    do r = 1, nraw                            ! (only the lowest node is needed here)
      lo = int(minval(d%raw%v(2:1 + d%raw%v(1, r), r)))
      h = shiftr(lo - 1, low_bits)
      first(h + 1) = first(h + 1) + 1
    end do
    first(0) = 1
    do h = 1, nhigh
      first(h) = first(h) + first(h - 1)
    end do
    do r = 1, nraw
      call split_key(d%raw%v(:, r), lo, key)
      h = shiftr(lo - 1, low_bits)
      q = first(h)
      item(:, q) = [lo, key, r]
      first(h) = q + 1
      rep(r) = r
    end do
    ! first(h) is now where bucket h + 1 starts; level 2: the low bits
    do h = nhigh - 1, 1, -1
      first(h) = first(h - 1)
    end do
    first(0) = 1
    first(nhigh) = nraw + 1
    do h = 0, nhigh - 1
      low_first = 0
      do i = first(h), first(h + 1) - 1
        j = iand(item(1, i) - 1, 2**low_bits - 1)
        low_first(j + 1) = low_first(j + 1) + 1
      end do
      low_first(0) = first(h)
      do j = 1, 2**low_bits
        low_first(j) = low_first(j) + low_first(j - 1)
      end do
      do i = first(h), first(h + 1) - 1
        j = iand(item(1, i) - 1, 2**low_bits - 1)
        sorted(:, low_first(j)) = item(:, i)
        low_first(j) = low_first(j) + 1
      end do
    end do
    ! runs of one lowest node, in file order within the run
    p0 = 1
    do while (p0 <= nraw)
      m = 1
      do while (p0 + m <= nraw)
        if (sorted(1, p0 + m) /= sorted(1, p0)) exit
        m = m + 1
      end do
      if (m > 1 .and. m <= pairwise_max) then
        leads(1:m) = .true.                          ! (not rep: it is in file order)
        do i = 2, m
          do j = 1, i - 1
            if (.not. leads(j)) cycle
            if (all(sorted(2:5, p0 - 1 + j) == sorted(2:5, p0 - 1 + i))) then
              rep(sorted(6, p0 - 1 + i)) = sorted(6, p0 - 1 + j)
              leads(i) = .false.
              exit
            end if
          end do
        end do
      else if (m > 1) then
        ! a stable sort: equal keys in file order, the first of each run leads it
        keys = int(sorted(2:5, p0:p0 + m - 1), i8)
        call sort_columns(keys, perm)
        do i = 2, m
          if (all(keys(:, perm(i)) == keys(:, perm(i - 1)))) &
            rep(sorted(6, p0 - 1 + perm(i))) = rep(sorted(6, p0 - 1 + perm(i - 1)))
        end do
      end if
      p0 = p0 + m
    end do
  end subroutine find_repeated_elements

  !> A raw element record (nen, 9 nodes, line) as its lowest node lo and the
  !> rest of its key: nen and its next three nodes ascending, 0 for none (two
  !> distinct elements of a conforming mesh share at most an edge's 3 nodes).
  pure subroutine split_key(rec, lo, key)
    integer(i8), intent(in) :: rec(:)
    integer, intent(out) :: lo, key(4)
    integer(i8) :: a(9)
    integer :: nen
    nen = int(rec(1))
    a = rec(2:10)
    call sort_small(a(1:nen))
    lo = int(a(1))
    key = [nen, int(a(2:4))]
  end subroutine split_key

  !> Boundaries from the edges (physical curves) and points (physical points).
  subroutine build_boundaries(d, mesh)
    type(msh_data_t), intent(in) :: d
    type(mesh_t), intent(inout) :: mesh
    integer(i8), allocatable :: gkeys(:,:), keys(:,:)
    integer, allocatable :: set_of(:), nseg(:), npt(:)
    logical, allocatable :: dup(:)
    type(string_t), allocatable :: set_name(:)
    integer :: ne, np, i, b, nset, r
    logical :: quadratic_edges

    ne = d%edges%n
    np = d%points%n
    quadratic_edges = .false.                 ! 3-node lines: every edge gets its middle (0: none)
    if (ne > 0) quadratic_edges = any(d%edges%v(5, 1:ne) /= 0)
    allocate(gkeys(2, ne + np))
    do i = 1, ne
      gkeys(:, i) = [1_i8, d%edges%v(1, i)]
    end do
    do i = 1, np
      gkeys(:, ne + i) = [0_i8, d%points%v(1, i)]
    end do
    call name_sets(d, gkeys, set_of, set_name)
    nset = size(set_name)

    ! An edge (or point) twice in one set, from groups of the same name, counts once.
    allocate(keys(3, ne + np), dup(ne + np))
    do i = 1, ne
      keys(:, i) = [int(set_of(i), i8), minval(d%edges%v(2:3, i)), maxval(d%edges%v(2:3, i))]
    end do
    do i = 1, np
      keys(:, ne + i) = [int(set_of(ne + i), i8), -1_i8, d%points%v(2, i)]
    end do
    call mark_repeated(keys, dup)

    allocate(nseg(nset), npt(nset))
    nseg = 0
    npt = 0
    do i = 1, ne
      if (.not. dup(i)) nseg(set_of(i)) = nseg(set_of(i)) + 1
    end do
    do i = 1, np
      if (.not. dup(ne + i)) npt(set_of(ne + i)) = npt(set_of(ne + i)) + 1
    end do
    allocate(mesh%bnd(nset))
    do b = 1, nset
      mesh%bnd(b)%name = set_name(b)%s
      allocate(mesh%bnd(b)%seg(2, nseg(b)), mesh%bnd(b)%points(npt(b)), mesh%bnd(b)%seg_line(nseg(b)))
      if (quadratic_edges) allocate(mesh%bnd(b)%mid(nseg(b)))
    end do
    do i = 1, ne
      if (dup(i)) cycle
      b = set_of(i)
      r = mesh%bnd(b)%nseg + 1
      mesh%bnd(b)%nseg = r
      mesh%bnd(b)%seg(:, r) = int(d%edges%v(2:3, i))
      mesh%bnd(b)%seg_line(r) = int(d%edges%v(4, i))
      if (quadratic_edges) mesh%bnd(b)%mid(r) = int(d%edges%v(5, i))
    end do
    do i = 1, np
      if (dup(ne + i)) cycle
      b = set_of(ne + i)
      r = mesh%bnd(b)%npoint + 1
      mesh%bnd(b)%npoint = r
      mesh%bnd(b)%points(r) = int(d%points%v(2, i))
    end do
  end subroutine build_boundaries

  !> Regions from the physical surfaces: sorted distinct element indices.
  !> Each region's elements are gathered in file order, which is ascending
  !> when no element is repeated; only a region that is not gets sorted.
  subroutine build_regions(d, elem_of_raw, mesh)
    type(msh_data_t), intent(in) :: d
    integer, intent(in) :: elem_of_raw(:)
    type(mesh_t), intent(inout) :: mesh
    integer(i8), allocatable :: gkeys(:,:), keys(:,:)
    integer, allocatable :: set_of(:), perm(:), nel(:)
    type(string_t), allocatable :: set_name(:)
    integer :: n, i, k, s, nset, e, m

    n = d%region_pairs%n
    allocate(gkeys(2, n))
    do i = 1, n
      gkeys(:, i) = [2_i8, d%region_pairs%v(1, i)]
    end do
    call name_sets(d, gkeys, set_of, set_name)
    nset = size(set_name)
    allocate(nel(nset), mesh%reg(nset))
    nel = 0
    do i = 1, n
      nel(set_of(i)) = nel(set_of(i)) + 1
    end do
    do s = 1, nset
      mesh%reg(s)%name = set_name(s)%s
      allocate(mesh%reg(s)%elems(nel(s)))
    end do
    nel = 0
    do i = 1, n
      s = set_of(i)
      nel(s) = nel(s) + 1
      mesh%reg(s)%elems(nel(s)) = elem_of_raw(d%region_pairs%v(2, i))
    end do
    do s = 1, nset
      associate (el => mesh%reg(s)%elems)
        m = size(el)
        if (all(el(2:m) > el(1:m - 1))) cycle
        keys = reshape(int(el, i8), [1, m])
        call sort_columns(keys, perm)
        k = 0
        do i = 1, m
          e = int(keys(1, perm(i)))
          if (k > 0) then
            if (e == el(k)) cycle
          end if
          k = k + 1
          el(k) = e
        end do
      end associate
      mesh%reg(s)%elems = mesh%reg(s)%elems(1:k)
    end do
  end subroutine build_regions

  !> Group records by physical group (dimension, tag), name each group from
  !> $PhysicalNames (else by its number) and merge groups of equal name.
  !>   d        (in)  the names read
  !>   gkeys    (in)  (2, n) dimension and physical tag of each record
  !>   set_of   (out) (n) named set of each record, 1..size(set_name)
  !>   set_name (out) (nset) the sets' names, in order of their first (dimension, tag)
  subroutine name_sets(d, gkeys, set_of, set_name)
    type(msh_data_t), intent(in) :: d
    integer(i8), intent(in) :: gkeys(:,:)
    integer, allocatable, intent(out) :: set_of(:)
    type(string_t), allocatable, intent(out) :: set_name(:)
    integer, allocatable :: perm(:), run_of(:), group_of_run(:), nperm(:), leader(:), set_of_group(:)
    integer(i8), allocatable :: gkey(:,:), run_key(:,:), name_key(:,:)
    type(string_t), allocatable :: gname(:)
    integer :: n, nrun, ng, i, g, nset, nw

    ! Runs of equal keys first (the records of a block share their group), so
    ! that only the runs are sorted.
    n = size(gkeys, 2)
    allocate(run_of(n), run_key(2, n))
    nrun = 0
    do i = 1, n
      if (nrun > 0) then
        if (all(gkeys(:, i) == run_key(:, nrun))) then
          run_of(i) = nrun
          cycle
        end if
      end if
      nrun = nrun + 1
      run_key(:, nrun) = gkeys(:, i)
      run_of(i) = nrun
    end do
    call sort_columns(run_key(:, 1:nrun), perm)
    allocate(group_of_run(nrun), gkey(2, nrun))
    ng = 0
    do i = 1, nrun
      if (i == 1) then
        ng = 1
        gkey(:, 1) = run_key(:, perm(1))
      else if (any(run_key(:, perm(i)) /= gkey(:, ng))) then
        ng = ng + 1
        gkey(:, ng) = run_key(:, perm(i))
      end if
      group_of_run(perm(i)) = ng
    end do
    allocate(gname(ng))
    do g = 1, ng
      gname(g)%s = physical_name(d, gkey(:, g))
    end do
    ! Stable sort of the names: the first group of each run of equal names leads it.
    nw = 1
    do g = 1, ng
      nw = max(nw, text_key_words(gname(g)%s))
    end do
    allocate(name_key(nw, ng))
    do g = 1, ng
      call pack_text(gname(g)%s, name_key(:, g))
    end do
    call sort_columns(name_key, nperm)
    allocate(leader(ng), set_of_group(ng))
    do i = 1, ng
      leader(nperm(i)) = nperm(i)
      if (i > 1) then
        if (gname(nperm(i))%s == gname(nperm(i - 1))%s) leader(nperm(i)) = leader(nperm(i - 1))
      end if
    end do
    nset = count([(leader(g) == g, g = 1, ng)])
    allocate(set_name(nset))
    nset = 0
    do g = 1, ng
      if (leader(g) == g) then
        nset = nset + 1
        set_of_group(g) = nset
        set_name(nset)%s = gname(g)%s
      else
        set_of_group(g) = set_of_group(leader(g))
      end if
    end do
    allocate(set_of(n))
    do i = 1, n
      set_of(i) = set_of_group(group_of_run(run_of(i)))
    end do
  end subroutine name_sets

  !> Name of physical group key = (dimension, tag): from $PhysicalNames, else the tag.
  function physical_name(d, key) result(name)
    type(msh_data_t), intent(in) :: d
    integer(i8), intent(in) :: key(2)
    character(len=:), allocatable :: name
    integer :: k
    k = 0
    if (allocated(d%name_key)) k = search_columns(d%name_key, d%name_perm, key)
    if (k > 0) then
      name = d%name_text(k)%s
      if (len_trim(name) > 0) return
    end if
    name = i8_to_str(key(2))
  end function physical_name

  ! ---------------------------------------------------------------------------
  ! Lines and items
  ! ---------------------------------------------------------------------------

  !> The fast path of a block of nl data lines after the current one: each
  !> line must hold exactly size(lo) integers, item k at least lo(k), then nr
  !> reals, all as the line-by-line reading accepts them.  The lines are
  !> parsed on the threads (no string is built there: see scene.f90).
  !>   iv (out) (size(lo), nl) the integers of each line
  !>   rv (out) (*, nl) the first size(rv, 1) reals of each line
  !>   ok (out) .false., t unchanged, when a line does not qualify: the caller
  !>            then reads the block line by line, which reports the first
  !>            defect as always; else t%ln is the block's last line
  subroutine scan_data_lines(t, nl, lo, nr, iv, rv, ok)
    type(msh_text_t), intent(inout) :: t
    integer, intent(in) :: nl, nr
    integer(i8), intent(in) :: lo(:)
    integer(i8), intent(inout) :: iv(:,:)
    real(dp), intent(inout) :: rv(:,:)
    logical, intent(out) :: ok
    integer :: ni, n, j, k, l0
    integer(i8) :: b(max_fast_items + 1), e(max_fast_items + 1)
    real(dp) :: r

    ni = size(lo)
    ok = ni + nr <= max_fast_items .and. int(t%ln, i8) + nl <= t%nline
    if (.not. ok) return
    l0 = t%ln
    !$omp parallel do if(nl > fast_parallel_min) &
    !$omp private(b, e, n, k, r) reduction(.and.: ok)
    do j = 1, nl
      if (.not. ok) cycle
      call line_items(t%buf, t%lbeg(l0 + j), t%lend(l0 + j), b, e, n)
      ok = n == ni + nr
      do k = 1, merge(ni, 0, ok)
        ok = scan_integer(t%buf(b(k):e(k)), iv(k, j))
        if (ok) ok = iv(k, j) >= lo(k)
        if (.not. ok) exit
      end do
      do k = 1, merge(nr, 0, ok)
        ok = msh_real(t%buf(b(ni + k):e(ni + k)), r) == 0
        if (.not. ok) exit
        if (k <= size(rv, 1)) rv(k, j) = r
      end do
    end do
    !$omp end parallel do
    if (ok) t%ln = l0 + nl
  end subroutine scan_data_lines

  !> The fast path of a block of m elements of MSH 4.1 (`tag` and nn node
  !> tags a line) of a 2D type, whose physical tags are phys: as
  !> scan_data_lines, then every node tag must be defined.  ok = .false.
  !> (t and d unchanged) when a line does not qualify.
  subroutine scan_elements(t, d, m, nn, phys, ok)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    integer, intent(in) :: m, nn
    integer(i8), intent(in) :: phys(:)
    logical, intent(out) :: ok
    integer(i8), allocatable :: ev(:,:)
    integer :: l0, j, q, node, r0, np

    l0 = t%ln
    allocate(ev(1 + nn, m))
    call scan_data_lines(t, m, [-huge(1_i8), (1_i8, q = 1, nn)], 0, ev, no_reals, ok)
    if (.not. ok) return
    r0 = d%raw%n
    call ensure_room(d%raw, raw_width, m)
    !$omp parallel do if(m > fast_parallel_min) &
    !$omp private(q, node) reduction(.and.: ok)
    do j = 1, m
      d%raw%v(:, r0 + j) = 0
      d%raw%v(1, r0 + j) = nn
      d%raw%v(raw_width, r0 + j) = l0 + j
      do q = 1, nn
        node = node_of_tag(d, ev(1 + q, j))
        if (node == 0) ok = .false.
        d%raw%v(1 + q, r0 + j) = node
      end do
    end do
    !$omp end parallel do
    if (.not. ok) then
      t%ln = l0
      return
    end if
    d%raw%n = r0 + m
    np = size(phys)
    call ensure_room(d%region_pairs, 2, m * np)
    do j = 1, m
      do q = 1, np
        d%region_pairs%v(:, d%region_pairs%n + q) = [phys(q), int(r0 + j, i8)]
      end do
      d%region_pairs%n = d%region_pairs%n + np
    end do
  end subroutine scan_elements

  subroutine advance_line(t, more)
    type(msh_text_t), intent(inout) :: t
    logical, intent(out) :: more
    integer :: n
    integer(i8), allocatable :: grown(:)

    more = t%ln < t%nline
    t%ntok = 0
    if (.not. more) return
    t%ln = t%ln + 1
    do
      call line_items(t%buf, t%lbeg(t%ln), t%lend(t%ln), t%tbeg, t%tend, n)
      if (n <= size(t%tbeg)) exit
      allocate(grown(2 * size(t%tbeg)))               ! more items than held: grow, split again
      call move_alloc(grown, t%tbeg)
      allocate(grown(2 * size(t%tend)))
      call move_alloc(grown, t%tend)
    end do
    t%ntok = n
  end subroutine advance_line

  !> Lines after the current one.
  pure integer function remaining_lines(t) result(n)
    type(msh_text_t), intent(in) :: t
    n = t%nline - t%ln
  end function remaining_lines

  !> Item k of the current line.
  function item(t, k) result(s)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    s = t%buf(t%tbeg(k):t%tend(k))
  end function item

  !> Item k of the current line, in double quotes, printable and shortened.
  function quoted_item(t, k) result(s)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    integer(i8) :: last
    last = min(t%tend(k), t%tbeg(k) + quote_length - 1)
    s = '"' // printable(t%buf(t%tbeg(k):last))
    if (last < t%tend(k)) s = s // '...'
    s = s // '"'
  end function quoted_item

  !> Next line of a section, holding data: not a $ line, nexpected items (any
  !> number when nexpected = 0).
  !>   section   (in) section name without $, for the end-of-file message
  !>   what      (in) description of the expected line
  subroutine read_data_line(t, diag, section, nexpected, what, ok)
    type(msh_text_t), intent(inout) :: t
    type(diag_t), intent(inout) :: diag
    character(len=*), intent(in) :: section, what
    integer, intent(in) :: nexpected
    logical, intent(out) :: ok
    logical :: more

    ok = .false.
    call advance_line(t, more)
    if (.not. more) then
      call report_end_of_file(t, diag, section)
      return
    end if
    if (t%ntok > 0) then
      if (t%buf(t%tbeg(1):t%tbeg(1)) == '$') then
        call fail(t, diag, 'unexpected ' // quoted_item(t, 1) // ' (' // what // &
          ' expected, as many lines as the counts announce)')
        return
      end if
    end if
    if (nexpected > 0 .and. t%ntok /= nexpected) then
      call fail(t, diag, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // int_to_str(nexpected) // &
        ' expected: ' // what // ')')
      return
    end if
    ok = .true.
  end subroutine read_data_line

  !> The next line must be $End<section>.
  subroutine expect_section_end(t, diag, section, ok)
    type(msh_text_t), intent(inout) :: t
    type(diag_t), intent(inout) :: diag
    character(len=*), intent(in) :: section
    logical, intent(out) :: ok
    logical :: more

    ok = .false.
    call advance_line(t, more)
    if (.not. more) then
      call report_end_of_file(t, diag, section)
      return
    end if
    if (t%ntok == 1) then
      if (item(t, 1) == '$End' // section) then
        ok = .true.
        return
      end if
    end if
    if (t%ntok > 0) then
      if (t%buf(t%tbeg(1):t%tbeg(1)) == '$') then
        call fail(t, diag, 'unexpected ' // quoted_item(t, 1) // ' ($End' // section // ' expected)')
        return
      end if
    end if
    call fail(t, diag, 'more lines than the counts announce ($End' // section // ' expected)')
  end subroutine expect_section_end

  subroutine report_end_of_file(t, diag, section)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    character(len=*), intent(in) :: section
    call add_error(diag, t%path, t%nline, 'unexpected end of file inside $' // section // &
      ' ($End' // section // ' expected)')
  end subroutine report_end_of_file

  !> Report text at the current line, echoing it.
  subroutine fail(t, diag, text)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    character(len=*), intent(in) :: text
    call fail_at(t, diag, t%ln, text)
  end subroutine fail

  !> Report text at a given line, echoing it.
  subroutine fail_at(t, diag, line, text)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: line
    character(len=*), intent(in) :: text
    integer(i8) :: b, e
    if (line < 1 .or. line > t%nline) then
      call add_error(diag, t%path, line, text)
      return
    end if
    b = t%lbeg(line)
    e = t%lend(line)
    if (e - b + 1 > echo_length) then
      call add_error(diag, t%path, line, text, echo=t%buf(b:b + echo_length - 1) // ' ...')
    else
      call add_error(diag, t%path, line, text, echo=t%buf(b:e))
    end if
  end subroutine fail_at

  ! ---------------------------------------------------------------------------
  ! Numbers
  ! ---------------------------------------------------------------------------

  !> Integer item k in [lo, hi]; else a message naming what.
  subroutine get_integer(t, diag, k, what, lo, hi, v, ok)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: k
    character(len=*), intent(in) :: what
    integer(i8), intent(in) :: lo, hi
    integer(i8), intent(out) :: v
    logical, intent(out) :: ok
    character(len=:), allocatable :: expected

    ok = scan_integer(t%buf(t%tbeg(k):t%tend(k)), v)
    if (ok) ok = v >= lo .and. v <= hi
    if (ok) return
    if (lo == 0 .and. hi == huge(1_i8)) then
      expected = 'a non-negative integer'
    else if (lo == 1 .and. hi == huge(1_i8)) then
      expected = 'a positive integer'
    else if (lo == -huge(1_i8) .and. hi == huge(1_i8)) then
      expected = 'an integer'
    else
      expected = 'an integer from ' // i8_to_str(lo) // ' to ' // i8_to_str(hi)
    end if
    call fail(t, diag, 'bad ' // what // ' ' // quoted_item(t, k) // ' (' // expected // ' expected)')
  end subroutine get_integer

  !> A count from item k, at least 0 and at most maxcount (what the rest of the
  !> file can hold).
  subroutine get_count(t, diag, k, what, maxcount, n, ok)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: k, maxcount
    character(len=*), intent(in) :: what
    integer, intent(out) :: n
    logical, intent(out) :: ok
    integer(i8) :: v
    n = 0
    call get_integer(t, diag, k, what, 0_i8, huge(1_i8), v, ok)
    if (.not. ok) return
    if (v > max(maxcount, 0)) then
      call fail(t, diag, what // ' ' // i8_to_str(v) // ' is more than the rest of the file holds (at most ' // &
        int_to_str(max(maxcount, 0)) // ' expected; truncated file?)')
      ok = .false.
      return
    end if
    n = int(v)
  end subroutine get_count

  !> Real item k: finite, of magnitude below 1e100; else a message naming what.
  subroutine get_real(t, diag, k, what, v, ok)
    type(msh_text_t), intent(in) :: t
    type(diag_t), intent(inout) :: diag
    integer, intent(in) :: k
    character(len=*), intent(in) :: what
    real(dp), intent(out) :: v
    logical, intent(out) :: ok
    select case (msh_real(t%buf(t%tbeg(k):t%tend(k)), v))
    case (0)
      ok = .true.
      return
    case (2)
      call fail(t, diag, 'non-finite number ' // quoted_item(t, k) // ' (a finite real number expected for ' // &
        what // ')')
    case (3)
      call fail(t, diag, 'number out of range ' // quoted_item(t, k) // ' (a real number of magnitude below 1e' // &
        int_to_str(max_decimal_exponent + 1) // ' expected for ' // what // ')')
    case default
      call fail(t, diag, 'bad number ' // quoted_item(t, k) // ' (a real number expected for ' // what // ')')
    end select
    ok = .false.
  end subroutine get_real

  !> A real of the file: text_scan's scan_real with magnitudes below 1e100 and
  !> at most max_number_length characters.
  !>   returns 0 ok, 1 not a number, 2 NaN or Inf, 3 magnitude 1e100 or more
  integer function msh_real(s, v) result(status)
    character(len=*), intent(in) :: s
    real(dp), intent(out) :: v
    v = 0.0_dp
    status = 1
    if (len(s) > max_number_length) return
    status = scan_real(s, v, max_decimal_exponent)
  end function msh_real


  ! ---------------------------------------------------------------------------
  ! Element types
  ! ---------------------------------------------------------------------------

  pure integer function element_dimension(etype)
    integer, intent(in) :: etype
    select case (etype)
    case (15)
      element_dimension = 0
    case (1, 8)
      element_dimension = 1
    case default
      element_dimension = 2
    end select
  end function element_dimension

  pure logical function element_is_3d(etype)
    integer, intent(in) :: etype
    select case (etype)
    case (4:7, 11:14, 17:19, 29:31, 92, 93)
      element_is_3d = .true.
    case default
      element_is_3d = .false.
    end select
  end function element_is_3d

  !> gmsh's name of an element type, '' when not known here.
  function element_description(etype) result(s)
    integer, intent(in) :: etype
    character(len=:), allocatable :: s
    select case (etype)
    case (4);  s = '4-node tetrahedron'
    case (5);  s = '8-node hexahedron'
    case (6);  s = '6-node prism'
    case (7);  s = '5-node pyramid'
    case (8);  s = '3-node second-order line'
    case (9);  s = '6-node second-order triangle'
    case (10); s = '9-node second-order quadrangle'
    case (11); s = '10-node second-order tetrahedron'
    case (12); s = '27-node second-order hexahedron'
    case (13); s = '18-node second-order prism'
    case (14); s = '14-node second-order pyramid'
    case (16); s = '8-node second-order quadrangle'
    case (17); s = '20-node second-order hexahedron'
    case (18); s = '15-node second-order prism'
    case (19); s = '13-node second-order pyramid'
    case (20); s = '9-node third-order incomplete triangle'
    case (21); s = '10-node third-order triangle'
    case (22); s = '12-node fourth-order incomplete triangle'
    case (23); s = '15-node fourth-order triangle'
    case (24); s = '15-node fifth-order incomplete triangle'
    case (25); s = '21-node fifth-order triangle'
    case (26); s = '4-node third-order line'
    case (27); s = '5-node fourth-order line'
    case (28); s = '6-node fifth-order line'
    case (29); s = '20-node third-order tetrahedron'
    case (30); s = '35-node fourth-order tetrahedron'
    case (31); s = '56-node fifth-order tetrahedron'
    case (92); s = '64-node third-order hexahedron'
    case (93); s = '125-node fourth-order hexahedron'
    case default; s = ''
    end select
  end function element_description

  ! ---------------------------------------------------------------------------
  ! Records, sorting and searching
  ! ---------------------------------------------------------------------------

  !> Make room for capacity records of the given width in an empty list.
  subroutine reserve_records(list, width, capacity)
    type(record_list_t), intent(inout) :: list
    integer, intent(in) :: width, capacity
    if (.not. allocated(list%v)) allocate(list%v(width, max(capacity, 64)))
  end subroutine reserve_records

  !> Room in a list of records of a given width for nmore more records.
  subroutine ensure_room(list, width, nmore)
    type(record_list_t), intent(inout) :: list
    integer, intent(in) :: width, nmore
    integer(i8), allocatable :: grown(:,:)
    if (.not. allocated(list%v)) allocate(list%v(width, max(nmore, 64)))
    if (list%n + nmore > size(list%v, 2)) then
      allocate(grown(width, max(2 * list%n, list%n + nmore)))
      grown(:, 1:list%n) = list%v(:, 1:list%n)
      call move_alloc(grown, list%v)
    end if
  end subroutine ensure_room

  !> Append one record to a list (width = size(rec), fixed by the first push).
  subroutine push_record(list, rec)
    type(record_list_t), intent(inout) :: list
    integer(i8), intent(in) :: rec(:)
    call ensure_room(list, size(rec), 1)
    list%n = list%n + 1
    list%v(:, list%n) = rec
  end subroutine push_record

  !> Node of a node tag, 0 when no node has it (tags are distinct here: the
  !> $Nodes section passed check_nodes).
  pure integer function node_of_tag(d, tag) result(node)
    type(msh_data_t), intent(in) :: d
    integer(i8), intent(in) :: tag
    integer :: lo, hi, mid
    node = 0
    if (allocated(d%tag_index)) then
      if (tag >= 1 .and. tag <= size(d%tag_index, kind=i8)) node = d%tag_index(tag)
      return
    end if
    ! binary search for the first sorted tag >= tag
    lo = 1
    hi = d%nnode + 1
    do while (lo < hi)
      mid = lo + (hi - lo) / 2
      if (d%tag_sorted(mid) < tag) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
    if (lo <= d%nnode) then
      if (d%tag_sorted(lo) == tag) node = d%tag_perm(lo)
    end if
  end function node_of_tag

end module gmsh_reader
