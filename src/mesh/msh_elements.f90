!> msh_elements: the $Elements section of a gmsh MSH file (format 2.2 or 4.1)
!> into the records of msh_data: 2D elements (3-node triangles, type 2; 4-node
!> quadrangles, 3; second order: 6-node triangles, 9; 8- and 9-node
!> quadrangles, 16 and 10), boundary lines (2-node, 1; 3-node, 8) and points
!> (15), each with its physical tags.  MSH 2.2 gives an element's physical tag
!> on its line (the first tag); MSH 4.1 gives its entity, whose physical tags
!> are listed in $Entities.  Other types are refused with gmsh's name of the
!> type and what to do.
!>
!> The section readers share their arguments: t (inout) the file and the
!> reading position, d (inout) what has been read, and err (out) the first
!> defect of the file or a failed allocation (reading then stops).
!>
!> Programming interface
!>   read_elements_22(t, d, err), read_elements_41(t, d, err)
module msh_elements
  use kinds, only: i8
  use strings, only: int_to_str, i8_to_str
  use errors, only: error_t
  use msh_text, only: msh_text_t, read_data_line, expect_section_end, remaining_lines, quoted_item, fail, fail_at, &
                      get_integer, get_count, read_block_header, scan_data_lines, allocation_failed, &
                      no_reals, fast_parallel_min, end_blocks, read_block_line
  use msh_data, only: msh_data_t, raw_width, reserve_records, ensure_room, push_record, node_of_tag
  use sorting, only: search_columns
  implicit none
  private
  public :: read_elements_22, read_elements_41

  character(len=*), parameter :: order_hint = &
    'triangles of 3 or 6 nodes, quads of 4, 8 or 9 nodes and 2- or 3-node lines expected; mesh with gmsh -order 1 or 2'

contains

  !> $Elements of MSH 2.2: count, then `number type ntags tags... nodes...`.
  subroutine read_elements_22(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    character(len=*), parameter :: what = 'elm-number elm-type number-of-tags tags node-tags'
    integer :: n, k, header, etype, nn, j
    integer(i8) :: v, ntags, phys(1)

    phys = 0

    call read_data_line(t, 'Elements', 1, 'the number of elements', err)
    if (allocated(err)) return
    header = t%ln
    call get_count(t, 1, 'number of elements', remaining_lines(t), n, err)
    if (allocated(err)) return
    call reserve_records(d%raw, raw_width, n, err)
    if (allocated(err)) return
    do k = 1, n
      call read_data_line(t, 'Elements', 0, what, err)
      if (allocated(err)) return
      if (t%ntok < 3) then
        call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (at least 3 expected: ' // what // ')', err)
        return
      end if
      call get_integer(t, 1, 'element number', -huge(1_i8), huge(1_i8), v, err)
      if (allocated(err)) return
      call get_element_type(t, 2, -1, etype, nn, err)
      if (allocated(err)) return
      call get_integer(t, 3, 'number of tags', 0_i8, huge(1_i8), ntags, err)
      if (allocated(err)) return
      if (3_i8 + ntags + nn /= t%ntok) then
        call fail(t, 'wrong number of items: ' // int_to_str(t%ntok) // ' (' // &
          trim(i8_to_str(3_i8 + ntags + nn)) // ' expected: 3 + ' // trim(i8_to_str(ntags)) // ' tags + ' // &
          int_to_str(nn) // ' nodes for element type ' // int_to_str(etype) // ')', err)
        return
      end if
      do j = 4, 3 + int(ntags)
        call get_integer(t, j, 'tag', -huge(1_i8), huge(1_i8), v, err)
        if (allocated(err)) return
        if (j == 4) phys(1) = v
      end do
      if (ntags >= 1 .and. phys(1) /= 0) then
        call add_element(t, d, etype, 4 + int(ntags), phys, err)
      else
        call add_element(t, d, etype, 4 + int(ntags), phys(1:0), err)
      end if
      if (allocated(err)) return
    end do
    call expect_section_end(t, 'Elements', err)
    if (allocated(err)) return
    call check_some_2d(t, d, header - 1, err)
  end subroutine read_elements_22

  !> $Elements of MSH 4.1: `numEntityBlocks numElements minTag maxTag`, then per
  !> block `entityDim entityTag elementType numElementsInBlock` and the elements
  !> `tag node-tags`.
  subroutine read_elements_41(t, d, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    type(error_t), allocatable, intent(out) :: err
    integer :: nblock, n, b, m, k, j, header, etype, nn, ient, first, count, stat
    integer(i8) :: dim, tag, v
    integer(i8), allocatable :: phys(:)
    character(len=:), allocatable :: line_what
    logical :: fast

    call read_block_header(t, 'Elements', 'element', 1, nblock, n, err)
    if (allocated(err)) return
    header = t%ln
    call reserve_records(d%raw, raw_width, n, err)
    if (allocated(err)) return
    k = 0
    do b = 1, nblock
      call read_block_line(t, 'Elements', 'entityDim entityTag elementType numElementsInBlock', dim, tag, err)
      if (allocated(err)) return
      call get_element_type(t, 3, int(dim), etype, nn, err)
      if (allocated(err)) return
      call get_count(t, 4, 'number of elements in the block', n - k, m, err)
      if (allocated(err)) return
      ! The physical tags of the block: those of its entity.
      allocate(phys(0), stat=stat)
      if (allocation_failed(stat, 8_i8, err)) return
      if (d%have_entities) then
        ient = search_columns(d%ent_key, d%ent_perm, [dim, tag])
        if (ient == 0) then
          call fail(t, 'element block on undefined entity ' // i8_to_str(tag) // ' of dimension ' // &
            i8_to_str(dim) // ' (an entity listed in $Entities expected)', err)
          return
        end if
        first = d%ent_first(ient)
        count = d%ent_count(ient)
        if (count > 0) then
          deallocate(phys)
          allocate(phys(count), stat=stat)
          if (allocation_failed(stat, 8_i8 * count, err)) return
          phys = d%ent_phys%v(1, first:first + count - 1)
        end if
      end if
      fast = .false.
      if (etype == 2 .or. etype == 3) call scan_elements(t, d, m, nn, phys, fast, err)
      if (allocated(err)) return
      if (.not. fast) then
        line_what = 'element-tag and ' // int_to_str(nn) // ' node tags'
        do j = 1, m
          call read_data_line(t, 'Elements', 1 + nn, line_what, err)
          if (allocated(err)) return
          call get_integer(t, 1, 'element tag', -huge(1_i8), huge(1_i8), v, err)
          if (allocated(err)) return
          call add_element(t, d, etype, 2, phys, err)
          if (allocated(err)) return
        end do
      end if
      deallocate(phys)
      k = k + m
    end do
    call end_blocks(t, 'Elements', 'element', header, k, n, err)
    if (allocated(err)) return
    call check_some_2d(t, d, header - 1, err)
  end subroutine read_elements_41

  !> Report a mesh without 2D elements at the $Elements line.
  subroutine check_some_2d(t, d, header, err)
    type(msh_text_t), intent(in) :: t
    type(msh_data_t), intent(in) :: d
    integer, intent(in) :: header
    type(error_t), allocatable, intent(out) :: err
    if (d%raw%n == 0) call fail_at(t, header, &
      'no 2D elements (triangles or quadrilaterals expected: mesh with gmsh -2)', err)
  end subroutine check_some_2d

  !> Element type from item k: a supported type (1, 2, 3, 8, 9, 10, 15, 16) of dimension dim
  !> (any when dim < 0); nn its number of nodes.
  subroutine get_element_type(t, k, dim, etype, nn, err)
    type(msh_text_t), intent(in) :: t
    integer, intent(in) :: k, dim
    integer, intent(out) :: etype, nn
    type(error_t), allocatable, intent(out) :: err
    integer(i8) :: v
    character(len=:), allocatable :: kind_text

    etype = 0
    nn = 0
    call get_integer(t, k, 'element type', -huge(1_i8), huge(1_i8), v, err)
    if (allocated(err)) return
    if (v < 0 .or. v > 1000) then
      call fail(t, 'unsupported element type ' // quoted_item(t, k) // ' (' // order_hint // ')', err)
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
        call fail(t, 'unsupported element type ' // int_to_str(etype) // ' (' // order_hint // ')', err)
      else if (element_is_3d(etype)) then
        call fail(t, 'unsupported element type ' // int_to_str(etype) // ', a ' // kind_text // &
          ' (a 2D mesh expected: mesh with gmsh -2)', err)
      else
        call fail(t, 'unsupported element type ' // int_to_str(etype) // ', a ' // kind_text // &
          ' (' // order_hint // ')', err)
      end if
      return
    end select
    if (dim >= 0 .and. dim /= element_dimension(etype)) then
      call fail(t, 'element type ' // int_to_str(etype) // ' in a block of dimension ' // int_to_str(dim) // &
        ' (the dimension of the element type expected)', err)
      return
    end if
  end subroutine get_element_type

  !> Record one element of a supported type whose node tags are items
  !> kfirst.. of the current line; phys are its physical tags.
  subroutine add_element(t, d, etype, kfirst, phys, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    integer, intent(in) :: etype, kfirst
    integer(i8), intent(in) :: phys(:)
    type(error_t), allocatable, intent(out) :: err
    integer(i8) :: tag, node(9)
    integer :: k, nn, idx, p

    nn = t%ntok - kfirst + 1
    node = 0
    do k = 1, nn
      call get_integer(t, kfirst + k - 1, 'node tag', 1_i8, huge(1_i8), tag, err)
      if (allocated(err)) return
      idx = node_of_tag(d, tag)
      if (idx == 0) then
        call fail(t, 'element refers to undefined node tag ' // i8_to_str(tag) // &
          ' (a node tag defined in $Nodes expected)', err)
        return
      end if
      node(k) = idx
    end do
    select case (etype)
    case (15)
      do p = 1, size(phys)
        call push_record(d%points, [phys(p), node(1)], err)
        if (allocated(err)) return
      end do
    case (1, 8)                       ! node(3): the middle of a 3-node line, 0 for a 2-node line
      do p = 1, size(phys)
        call push_record(d%edges, [phys(p), node(1), node(2), int(t%ln, i8), node(3)], err)
        if (allocated(err)) return
      end do
    case (2, 3, 9, 16, 10)
      call push_record(d%raw, [int(nn, i8), node, int(t%ln, i8)], err)
      if (allocated(err)) return
      do p = 1, size(phys)
        call push_record(d%region_pairs, [phys(p), int(d%raw%n, i8)], err)
        if (allocated(err)) return
      end do
    end select
  end subroutine add_element

  !> The fast path of a block of m elements of MSH 4.1 (`tag` and nn node
  !> tags a line) of a 2D type, whose physical tags are phys: as
  !> scan_data_lines, then every node tag must be defined.
  !>   done (out) .false. (t and d unchanged) when a line does not qualify
  !>   err  (out) allocated when memory ran out (the reading then stops)
  subroutine scan_elements(t, d, m, nn, phys, done, err)
    type(msh_text_t), intent(inout) :: t
    type(msh_data_t), intent(inout) :: d
    integer, intent(in) :: m, nn
    integer(i8), intent(in) :: phys(:)
    logical, intent(out) :: done
    type(error_t), allocatable, intent(out) :: err
    integer(i8), allocatable :: ev(:,:)
    integer :: l0, j, q, node, r0, np, stat

    l0 = t%ln
    done = .false.
    allocate(ev(1 + nn, m), stat=stat)
    if (allocation_failed(stat, 8_i8 * (1 + nn) * m, err)) return
    call scan_data_lines(t, m, [-huge(1_i8), (1_i8, q = 1, nn)], 0, ev, no_reals, done)
    if (.not. done) return
    r0 = d%raw%n
    call ensure_room(d%raw, raw_width, m, err)
    if (allocated(err)) then
      done = .false.
      return
    end if
    !$omp parallel do if(m > fast_parallel_min) &
    !$omp private(q, node) reduction(.and.: done)
    do j = 1, m
      d%raw%v(:, r0 + j) = 0
      d%raw%v(1, r0 + j) = nn
      d%raw%v(raw_width, r0 + j) = l0 + j
      do q = 1, nn
        node = node_of_tag(d, ev(1 + q, j))
        if (node == 0) done = .false.
        d%raw%v(1 + q, r0 + j) = node
      end do
    end do
    !$omp end parallel do
    if (.not. done) then
      t%ln = l0
      return
    end if
    d%raw%n = r0 + m
    np = size(phys)
    call ensure_room(d%region_pairs, 2, m * np, err)
    if (allocated(err)) return
    do j = 1, m
      do q = 1, np
        d%region_pairs%v(:, d%region_pairs%n + q) = [phys(q), int(r0 + j, i8)]
      end do
      d%region_pairs%n = d%region_pairs%n + np
    end do
  end subroutine scan_elements

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
    !> gmsh's element types other than the 2D ones and points (gmsh's manual, MSH format)
    integer, parameter :: types(29) = [ &
      4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 16, 17, 18, 19, 20, &
      21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 92, 93 ]
    character(len=40), parameter :: descriptions(29) = [character(len=40) :: &
      '4-node tetrahedron', '8-node hexahedron', &
      '6-node prism', '5-node pyramid', &
      '3-node second-order line', '6-node second-order triangle', &
      '9-node second-order quadrangle', '10-node second-order tetrahedron', &
      '27-node second-order hexahedron', '18-node second-order prism', &
      '14-node second-order pyramid', '8-node second-order quadrangle', &
      '20-node second-order hexahedron', '15-node second-order prism', &
      '13-node second-order pyramid', '9-node third-order incomplete triangle', &
      '10-node third-order triangle', '12-node fourth-order incomplete triangle', &
      '15-node fourth-order triangle', '15-node fifth-order incomplete triangle', &
      '21-node fifth-order triangle', '4-node third-order line', &
      '5-node fourth-order line', '6-node fifth-order line', &
      '20-node third-order tetrahedron', '35-node fourth-order tetrahedron', &
      '56-node fifth-order tetrahedron', '64-node third-order hexahedron', &
      '125-node fourth-order hexahedron' ]
    integer :: k
    s = ''
    do k = 1, size(types)
      if (types(k) == etype) s = trim(descriptions(k))
    end do
  end function element_description

end module msh_elements
