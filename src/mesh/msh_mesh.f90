!> msh_mesh: the mesh_t a gmsh MSH file makes, from what its sections held
!> (msh_data_t).
!>
!>   - 2D elements: MSH 2.2 repeats an element once per physical group holding
!>     it, so elements with the same node set are one element, the first of
!>     them in the file (find_repeated_elements);
!>   - a physical curve gives a boundary_t whose edges are its 2-node lines or
!>     3-node lines (ends, then the middle, kept as the edge's mid-side node); a
!>     physical point gives a boundary_t whose points are its point elements; a
!>     physical surface gives a region_t of element indices.  A group is named
!>     from $PhysicalNames, else by its number ("3"); groups of the same name
!>     (e.g. a physical point and a physical curve) make one boundary_t.
!>     Boundaries and regions come in order of (dimension, tag).
!>   The mesh is left as read: compaction of unused nodes, orientation and
!>   quality checks are the caller's (finalize_mesh of module mesh).
!>
!> Programming interface
!>   build_mesh(d, mesh, err)         the mesh of d; err when an allocation
!>                                    failed (out of memory, with its size; mesh empty)
module msh_mesh
  use kinds, only: i8
  use errors, only: error_t, set_out_of_memory
  use mesh, only: mesh_t
  use sorting, only: sort_columns, search_columns, mark_repeated, sort_small, text_key_words, pack_text, &
                     number_classes
  use strings, only: int_to_str, i8_to_str
  use msh_data, only: msh_data_t, string_t, raw_width
  implicit none
  private
  public :: build_mesh

contains

  !> Merge repeated 2D elements, fill the mesh and its named sets.
  !>   d    (in)  what the sections held
  !>   mesh (out) the mesh; empty when memory ran out
  !>   err  (out) allocated when an allocation failed (no_memory, its bytes)
  subroutine build_mesh(d, mesh, err)
    type(msh_data_t), intent(in) :: d
    type(mesh_t), intent(out) :: mesh
    type(error_t), allocatable, intent(out) :: err
    type(mesh_t) :: empty
    integer(i8) :: oom
    call fill_mesh(d, mesh, oom)
    if (oom == 0) return
    mesh = empty
    call set_out_of_memory(err, 'building the mesh', oom)
  end subroutine build_mesh

  !> build_mesh's work; the helpers below record a failed allocation in oom.
  !>   oom  (out) 0, or the size in bytes of an allocation that failed (mesh partial)
  subroutine fill_mesh(d, mesh, oom)
    type(msh_data_t), intent(in) :: d
    type(mesh_t), intent(out) :: mesh
    integer(i8), intent(out) :: oom
    integer, allocatable :: rep(:), elem_of_raw(:)
    integer :: nraw, r, nelem, width, stat

    ! Elements with the same node set are one element, represented by the first
    ! of them in the file.
    oom = 0
    nraw = d%raw%n
    call find_repeated_elements(d, rep, oom)
    if (oom > 0) return
    allocate(elem_of_raw(nraw), stat=stat)
    if (failed(stat, 4_i8 * nraw, oom)) return
    call number_classes(rep, elem_of_raw, nelem)

    mesh%nnode = d%nnode
    allocate(mesh%x(2, d%nnode), stat=stat)
    if (failed(stat, 16_i8 * d%nnode, oom)) return
    mesh%x = d%x
    mesh%nelem = nelem
    width = 4                                 ! conn(4, *), or conn(9, *) with quadratic elements
    if (nraw > 0) then
      if (any(d%raw%v(1, 1:nraw) > 4)) width = 9
    end if
    allocate(mesh%nen(nelem), mesh%conn(width, nelem), mesh%elem_line(nelem), stat=stat)
    if (failed(stat, 4_i8 * (width + 2) * nelem, oom)) return
    do r = 1, nraw
      if (rep(r) /= r) cycle
      mesh%nen(elem_of_raw(r)) = int(d%raw%v(1, r))
      mesh%conn(:, elem_of_raw(r)) = int(d%raw%v(2:1 + width, r))
      mesh%elem_line(elem_of_raw(r)) = int(d%raw%v(raw_width, r))
    end do
    call build_boundaries(d, mesh, oom)
    if (oom > 0) return
    call build_regions(d, elem_of_raw, mesh, oom)
  end subroutine fill_mesh

  !> stat /= 0: an allocation of about bytes failed, recorded in oom.
  logical function failed(stat, bytes, oom)
    integer, intent(in) :: stat
    integer(i8), intent(in) :: bytes
    integer(i8), intent(inout) :: oom
    failed = stat /= 0
    if (failed) oom = max(bytes, 1_i8)
  end function failed

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
  subroutine find_repeated_elements(d, rep, oom)
    type(msh_data_t), intent(in) :: d
    integer, allocatable, intent(out) :: rep(:)
    integer(i8), intent(inout) :: oom
    integer, parameter :: pairwise_max = 16, low_bits = 10
    integer, allocatable :: first(:), perm(:), item(:,:), sorted(:,:)
    integer(i8), allocatable :: keys(:,:)
    integer :: nraw, nhigh, r, lo, h, i, j, m, p0, q, key(4), low_first(0:2**low_bits), stat
    logical :: leads(pairwise_max)

    nraw = d%raw%n
    nhigh = shiftr(max(d%nnode - 1, 0), low_bits) + 1
    allocate(rep(nraw), first(0:nhigh), item(6, nraw), sorted(6, nraw), stat=stat)
    if (failed(stat, 52_i8 * nraw + 4_i8 * nhigh, oom)) return
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
        if (allocated(keys)) deallocate(keys)
        allocate(keys(4, m), stat=stat)
        if (failed(stat, 32_i8 * m, oom)) return
        keys = int(sorted(2:5, p0:p0 + m - 1), i8)
        call sort_columns(keys, perm, stat)
        if (failed(stat, 8_i8 * m, oom)) return
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
    integer :: a(9), nen
    nen = int(rec(1))
    a = int(rec(2:10))                        ! node numbers: default integers
    call sort_small(a(1:nen))
    lo = a(1)
    key = [nen, a(2:4)]
  end subroutine split_key

  !> Boundaries from the edges (physical curves) and points (physical points).
  subroutine build_boundaries(d, mesh, oom)
    type(msh_data_t), intent(in) :: d
    type(mesh_t), intent(inout) :: mesh
    integer(i8), intent(inout) :: oom
    integer(i8), allocatable :: gkeys(:,:), keys(:,:)
    integer, allocatable :: set_of(:), nseg(:), npt(:)
    logical, allocatable :: dup(:)
    type(string_t), allocatable :: set_name(:)
    integer :: ne, np, i, b, nset, r, stat
    logical :: quadratic_edges

    ne = d%edges%n
    np = d%points%n
    quadratic_edges = .false.                 ! 3-node lines: every edge gets its middle (0: none)
    if (ne > 0) quadratic_edges = any(d%edges%v(5, 1:ne) /= 0)
    allocate(gkeys(2, ne + np), stat=stat)
    if (failed(stat, 16_i8 * (ne + np), oom)) return
    do i = 1, ne
      gkeys(:, i) = [1_i8, d%edges%v(1, i)]
    end do
    do i = 1, np
      gkeys(:, ne + i) = [0_i8, d%points%v(1, i)]
    end do
    call name_sets(d, gkeys, set_of, set_name, oom)
    if (oom > 0) return
    nset = size(set_name)

    ! An edge (or point) twice in one set, from groups of the same name, counts once.
    allocate(keys(3, ne + np), dup(ne + np), stat=stat)
    if (failed(stat, 28_i8 * (ne + np), oom)) return
    do i = 1, ne
      keys(:, i) = [int(set_of(i), i8), minval(d%edges%v(2:3, i)), maxval(d%edges%v(2:3, i))]
    end do
    do i = 1, np
      keys(:, ne + i) = [int(set_of(ne + i), i8), -1_i8, d%points%v(2, i)]
    end do
    call mark_repeated(keys, dup, stat)
    if (failed(stat, 8_i8 * (ne + np), oom)) return

    allocate(nseg(nset), npt(nset), stat=stat)
    if (failed(stat, 8_i8 * nset, oom)) return
    nseg = 0
    npt = 0
    do i = 1, ne
      if (.not. dup(i)) nseg(set_of(i)) = nseg(set_of(i)) + 1
    end do
    do i = 1, np
      if (.not. dup(ne + i)) npt(set_of(ne + i)) = npt(set_of(ne + i)) + 1
    end do
    allocate(mesh%bnd(nset), stat=stat)
    if (failed(stat, 256_i8 * nset, oom)) return
    do b = 1, nset
      mesh%bnd(b)%name = set_name(b)%s
      allocate(mesh%bnd(b)%seg(2, nseg(b)), mesh%bnd(b)%points(npt(b)), mesh%bnd(b)%seg_line(nseg(b)), stat=stat)
      if (stat == 0 .and. quadratic_edges) allocate(mesh%bnd(b)%mid(nseg(b)), stat=stat)
      if (failed(stat, 16_i8 * nseg(b) + 4_i8 * npt(b), oom)) return
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
  subroutine build_regions(d, elem_of_raw, mesh, oom)
    type(msh_data_t), intent(in) :: d
    integer, intent(in) :: elem_of_raw(:)
    type(mesh_t), intent(inout) :: mesh
    integer(i8), intent(inout) :: oom
    integer(i8), allocatable :: gkeys(:,:), keys(:,:)
    integer, allocatable :: set_of(:), perm(:), nel(:)
    type(string_t), allocatable :: set_name(:)
    integer :: n, i, k, s, nset, e, m, stat

    n = d%region_pairs%n
    allocate(gkeys(2, n), stat=stat)
    if (failed(stat, 16_i8 * n, oom)) return
    do i = 1, n
      gkeys(:, i) = [2_i8, d%region_pairs%v(1, i)]
    end do
    call name_sets(d, gkeys, set_of, set_name, oom)
    if (oom > 0) return
    nset = size(set_name)
    allocate(nel(nset), mesh%reg(nset), stat=stat)
    if (failed(stat, 64_i8 * nset, oom)) return
    nel = 0
    do i = 1, n
      nel(set_of(i)) = nel(set_of(i)) + 1
    end do
    do s = 1, nset
      mesh%reg(s)%name = set_name(s)%s
      allocate(mesh%reg(s)%elems(nel(s)), stat=stat)
      if (failed(stat, 4_i8 * nel(s), oom)) return
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
        if (allocated(keys)) deallocate(keys)
        allocate(keys(1, m), stat=stat)
        if (failed(stat, 8_i8 * m, oom)) return
        keys(1, :) = int(el, i8)
        call sort_columns(keys, perm, stat)
        if (failed(stat, 8_i8 * m, oom)) return
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
  subroutine name_sets(d, gkeys, set_of, set_name, oom)
    type(msh_data_t), intent(in) :: d
    integer(i8), intent(in) :: gkeys(:,:)
    integer, allocatable, intent(out) :: set_of(:)
    type(string_t), allocatable, intent(out) :: set_name(:)
    integer(i8), intent(inout) :: oom
    integer, allocatable :: perm(:), run_of(:), group_of_run(:), nperm(:), leader(:), set_of_group(:)
    integer(i8), allocatable :: gkey(:,:), run_key(:,:), name_key(:,:)
    type(string_t), allocatable :: gname(:)
    integer :: n, nrun, ng, i, g, nset, nw, stat

    ! Runs of equal keys first (the records of a block share their group), so
    ! that only the runs are sorted.
    n = size(gkeys, 2)
    allocate(run_of(n), run_key(2, n), stat=stat)
    if (failed(stat, 20_i8 * n, oom)) return
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
    call sort_columns(run_key(:, 1:nrun), perm, stat)
    if (stat == 0) allocate(group_of_run(nrun), gkey(2, nrun), stat=stat)
    if (failed(stat, 28_i8 * nrun, oom)) return
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
    allocate(gname(ng), stat=stat)
    if (failed(stat, 64_i8 * ng, oom)) return
    do g = 1, ng
      gname(g)%s = physical_name(d, gkey(:, g))
    end do
    ! Stable sort of the names: the first group of each run of equal names leads it.
    nw = 1
    do g = 1, ng
      nw = max(nw, text_key_words(gname(g)%s))
    end do
    allocate(name_key(nw, ng), stat=stat)
    if (failed(stat, 8_i8 * nw * ng, oom)) return
    do g = 1, ng
      call pack_text(gname(g)%s, name_key(:, g))
    end do
    call sort_columns(name_key, nperm, stat)
    if (stat == 0) allocate(leader(ng), set_of_group(ng), stat=stat)
    if (failed(stat, 16_i8 * ng, oom)) return
    do i = 1, ng
      leader(nperm(i)) = nperm(i)
      if (i > 1) then
        if (gname(nperm(i))%s == gname(nperm(i - 1))%s) leader(nperm(i)) = leader(nperm(i - 1))
      end if
    end do
    nset = count([(leader(g) == g, g = 1, ng)])
    allocate(set_name(nset), stat=stat)
    if (failed(stat, 64_i8 * nset, oom)) return
    call number_classes(leader, set_of_group, nset)
    do g = 1, ng
      if (leader(g) == g) set_name(set_of_group(g))%s = gname(g)%s
    end do
    allocate(set_of(n), stat=stat)
    if (failed(stat, 4_i8 * n, oom)) return
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

end module msh_mesh
