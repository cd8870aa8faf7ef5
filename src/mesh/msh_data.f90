!> msh_data: what the sections of a gmsh MSH file hold, as read, before the
!> mesh is built from it (msh_mesh): the nodes and their tags, the physical
!> names, the entities of MSH 4.1, and the elements, boundary edges and points
!> as growing tables of integer records.
!>
!> Programming interface
!>   type(msh_data_t)                  the sections' content (see its components)
!>   type(record_list_t)               a growing table of integer records
!>   type(string_t)                    a character string of any length (text_scan's)
!>   raw_width                         width of an element record
!>   reserve_records(list, width, capacity, err), ensure_room(list, width, nmore, err),
!>   push_record(list, rec, err)       grow and fill a table; err (out of memory, with
!>                                     the bytes asked for) when memory ran out (the
!>                                     list is then unchanged)
!>   node_of_tag(d, tag)               node of a node tag, 0 when none
module msh_data
  use kinds, only: dp, i8
  use errors, only: error_t, set_out_of_memory
  use sorting, only: search_columns
  use text_scan, only: string_t
  implicit none
  private
  public :: msh_data_t, record_list_t, string_t, raw_width
  public :: reserve_records, ensure_room, push_record, node_of_tag

  integer, parameter :: raw_width = 11             !< nen, 9 nodes, line: an element read

  !> A growing table of integer records of a fixed width.
  type :: record_list_t
    integer :: n = 0                          !< number of records held
    integer(i8), allocatable :: v(:,:)        !< (width, capacity) the records
  end type record_list_t

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

  !> Make room for capacity records of the given width in an empty list.
  !>   err (out) allocated when the allocation failed (the list is then unchanged)
  subroutine reserve_records(list, width, capacity, err)
    type(record_list_t), intent(inout) :: list
    integer, intent(in) :: width, capacity
    type(error_t), allocatable, intent(out) :: err
    integer :: stat
    if (allocated(list%v)) return
    allocate(list%v(width, max(capacity, 64)), stat=stat)
    if (stat /= 0) call set_out_of_memory(err, 'reading a mesh file', record_bytes(list, width, capacity))
  end subroutine reserve_records

  !> Room in a list of records of a given width for nmore more records: the
  !> capacity doubles (or grows to what is needed).
  !>   err (out) allocated when the allocation failed (the list is then unchanged)
  subroutine ensure_room(list, width, nmore, err)
    type(record_list_t), intent(inout) :: list
    integer, intent(in) :: width, nmore
    type(error_t), allocatable, intent(out) :: err
    integer(i8), allocatable :: grown(:,:)
    integer :: stat
    if (.not. allocated(list%v)) then
      allocate(list%v(width, max(nmore, 64)), stat=stat)
      if (stat /= 0) call set_out_of_memory(err, 'reading a mesh file', record_bytes(list, width, nmore))
      return
    end if
    if (list%n + nmore > size(list%v, 2)) then
      allocate(grown(width, max(2 * list%n, list%n + nmore)), stat=stat)
      if (stat /= 0) then
        call set_out_of_memory(err, 'reading a mesh file', record_bytes(list, width, nmore))
        return
      end if
      grown(:, 1:list%n) = list%v(:, 1:list%n)
      call move_alloc(grown, list%v)
    end if
  end subroutine ensure_room

  !> Bytes ensure_room(list, width, nmore) allocates at most (for the message
  !> when it fails).
  pure integer(i8) function record_bytes(list, width, nmore) result(bytes)
    type(record_list_t), intent(in) :: list
    integer, intent(in) :: width, nmore
    bytes = 8_i8 * width * max(2_i8 * list%n, int(list%n, i8) + nmore, 64_i8)
  end function record_bytes

  !> Append one record to a list (width = size(rec), fixed by the first push).
  !>   err (out) allocated when the list could not grow (it is then unchanged)
  subroutine push_record(list, rec, err)
    type(record_list_t), intent(inout) :: list
    integer(i8), intent(in) :: rec(:)
    type(error_t), allocatable, intent(out) :: err
    call ensure_room(list, size(rec), 1, err)
    if (allocated(err)) return
    list%n = list%n + 1
    list%v(:, list%n) = rec
  end subroutine push_record

  !> Node of a node tag, 0 when no node has it (tags are distinct here: the
  !> $Nodes section passed check_nodes, which indexed them).
  pure integer function node_of_tag(d, tag) result(node)
    type(msh_data_t), intent(in) :: d
    integer(i8), intent(in) :: tag
    node = 0
    if (allocated(d%tag_index)) then
      if (tag >= 1 .and. tag <= size(d%tag_index, kind=i8)) node = d%tag_index(tag)
    else
      node = search_columns(d%ntag, d%tag_perm, [tag])
    end if
  end function node_of_tag

end module msh_data
