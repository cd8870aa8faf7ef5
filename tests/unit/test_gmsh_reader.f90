!> test_gmsh_reader: unit tests of module gmsh_reader.
!>
!> References, all independent of the reader:
!>   - structured (transfinite) gmsh meshes whose counts follow from the
!>     geometry: a unit square with n nodes per side has n**2 nodes and
!>     2 (n-1)**2 triangles; the mixed rectangle has 2 n**2 - n nodes, (n-1)**2
!>     quadrangles and 2 (n-1)**2 triangles;
!>   - areas: the sum of the element areas equals the domain area (1, 2), or for
!>     the disk the area of the polygon of its rim edges (shoelace formula), which
!>     is at most that of the regular polygon with as many sides, N/2 sin(2 pi/N);
!>   - the MSH 2.2 and 4.1 files of the same gmsh mesh give the same mesh;
!>   - hand-written files with sparse node tags (tests/unit/data/sparse_*.msh);
!>   - each malformed mesh tests/bad/mesh_*.msh gives the one error line of its
!>     .expect file; truncated, mutated and random files never crash the reader.
!> Data provenance: tests/unit/data/README.md.  Run from the repository root.
program test_gmsh_reader
  use kinds, only: dp, i8
  use strings, only: int_to_str
  use errors, only: diag_t, error_t
  use elements, only: quadrature_rule, shape_at
  use mesh, only: mesh_t, finalize_mesh, find_name, element_area, boundary_nodes
  use gmsh_reader, only: read_gmsh_file
  use gmsh_runner, only: gmsh_options_t, mesh_geo_file
  use sorting, only: sort_small
  use testing, only: check, check_close, check_small, finish_tests, tol_round
  implicit none

  character(len=*), parameter :: data_dir = 'tests/unit/data/'
  character(len=:), allocatable :: tmp

  tmp = scratch_prefix()
  call test_square()
  call test_mixed()
  call test_disk()
  call test_second_order('annulus_tri6_22.msh', 6, 9)
  call test_second_order('annulus_quad9_22.msh', 9, 10)
  call test_second_order('annulus_quad8_41.msh', 8, 16)
  call test_sparse_tags()
  call test_number_notations()
  call test_far_tags()
  call test_correct_rounding()
  call test_geo_meshing()
  call test_bad_meshes()
  call test_robustness()
  deallocate(tmp)
  call finish_tests()

contains

  !> A second-order mesh of the quarter annulus 1 <= r <= 2 (data/README.md):
  !> elements of nen nodes (gmsh type etype), 3-node boundary edges whose
  !> nodes on the inner arc, middle included, lie on the unit circle, and an
  !> area (the quadrature of det J over the curved elements) of 3 pi / 4.
  subroutine test_second_order(file, nen, etype)
    character(len=*), intent(in) :: file
    integer, intent(in) :: nen, etype
    type(mesh_t) :: m
    type(diag_t) :: d
    real(dp), allocatable :: xi(:,:), w(:)
    real(dp) :: shp(9), dndx(2, 9), detj, area, rdev
    integer :: ib, e, q, k
    character(len=:), allocatable :: what
    what = file // ' (type ' // int_to_str(etype) // ')'
    call read_gmsh_file(data_dir // file, m, d)
    if (d%count == 0) call finalize_mesh(m, file, d)
    call check(d%count == 0, what // ': read and finalized without error')
    if (d%count > 0) return
    call check(all(m%nen == nen) .and. size(m%conn, 1) == 9, what // ': every element has ' // int_to_str(nen) // ' nodes')
    ib = find_name(m%bnd, 'inner')
    call check(ib > 0, what // ': boundary "inner" found')
    if (ib == 0) return
    call check(allocated(m%bnd(ib)%mid) .and. m%bnd(ib)%nseg == 3, what // ': 3 three-node edges on "inner"')
    if (.not. allocated(m%bnd(ib)%mid)) return
    rdev = 0
    do k = 1, m%bnd(ib)%nseg
      rdev = max(rdev, abs(norm2(m%x(:, m%bnd(ib)%mid(k))) - 1), abs(norm2(m%x(:, m%bnd(ib)%seg(1, k))) - 1))
    end do
    call check_small(rdev, tol_round(16), what // ': ends and middles of the inner edges on the unit circle')
    area = 0
    do e = 1, m%nelem
      call quadrature_rule(nen, 2, xi, w)
      do q = 1, size(w)
        call shape_at(nen, m%x(:, m%conn(1:nen, e)), xi(:, q), shp(1:nen), dndx(:, 1:nen), detj)
        area = area + w(q) * detj
      end do
    end do
    print '(a,es10.2)', '# ' // what // ': area - 3 pi / 4 = ', area - 0.75_dp * acos(-1.0_dp)
    call check_small(abs(area - 0.75_dp * acos(-1.0_dp)), 2.0e-3_dp, what // ': area of the curved elements near 3 pi / 4')
  end subroutine test_second_order

  !> Unit square, n = 4 nodes per side, 2.2 and 4.1.
  subroutine test_square()
    type(mesh_t) :: m22, m41
    type(diag_t) :: d22, d41, dfin
    integer, parameter :: n = 4
    character(len=6), parameter :: sides(4) = [character(len=6) :: 'bottom', 'right', 'top', 'left']
    integer :: k, ib, ic

    call read_gmsh_file(data_dir // 'square_22.msh', m22, d22)
    call read_gmsh_file(data_dir // 'square_41.msh', m41, d41)
    call check(d22%count == 0 .and. d41%count == 0, 'square: both files read without error')
    call check(m41%nnode == n**2 .and. m22%nnode == n**2, 'square: n**2 nodes')
    call check(m41%nelem == 2 * (n - 1)**2 .and. m22%nelem == 2 * (n - 1)**2, &
      'square: 2 (n-1)**2 triangles (2.2 repeats each of them for its two physical surfaces)')
    call check(all(m41%nen == 3) .and. all(m41%conn(4, :) == 0), 'square: triangles have nen = 3, conn(4,:) = 0')
    call check(size(m41%bnd) == 5, 'square: 4 physical curves + 1 physical point')
    do k = 1, 4
      ib = find_name(m41%bnd, trim(sides(k)))
      call check(ib > 0, 'square: boundary ' // trim(sides(k)) // ' exists')
      if (ib == 0) cycle
      call check(m41%bnd(ib)%nseg == n - 1 .and. m41%bnd(ib)%npoint == 0, &
        'square: boundary ' // trim(sides(k)) // ' has n-1 edges')
      ic = merge(2, 1, k == 1 .or. k == 3)
      call check_small(maxval(abs(m41%x(ic, pack(m41%bnd(ib)%seg, .true.)) - merge(1.0_dp, 0.0_dp, k == 2 .or. k == 3))), &
        tol_round(16), 'square: boundary ' // trim(sides(k)) // ' lies on its side')
      call check_close(total_length(m41, ib), 1.0_dp, tol_round(16), 'square: boundary ' // trim(sides(k)) // ' has length 1')
    end do
    ib = find_name(m41%bnd, 'corner')
    call check(ib > 0, 'square: physical point corner exists')
    if (ib > 0) then
      call check(m41%bnd(ib)%npoint == 1 .and. m41%bnd(ib)%nseg == 0, 'square: corner holds one point, no edge')
      call check_small(maxval(abs(m41%x(:, m41%bnd(ib)%points(1)))), 0.0_dp, 'square: corner is at (0,0)')
    end if
    call check(find_name(m41%reg, 'body') > 0 .and. find_name(m41%reg, '7') > 0 .and. size(m41%reg) == 2, &
      'square: regions "body" and unnamed 7 (named "7")')
    if (find_name(m41%reg, '7') > 0) call check(size(m41%reg(find_name(m41%reg, '7'))%elems) == m41%nelem, &
      'square: region 7 holds every element')
    call check(same_mesh(m22, m41), 'square: MSH 2.2 and 4.1 give the same mesh')
    call finalize_mesh(m41, 'square_41.msh', dfin)
    call check(dfin%count == 0, 'square: finalize_mesh finds no defect')
    call check_close(total_area(m41), 1.0_dp, tol_round(16), 'square: element areas sum to 1')
  end subroutine test_square

  !> Two unit squares, quadrangles (recombined) and triangles, n = 4.
  subroutine test_mixed()
    type(mesh_t) :: m22, m41
    type(diag_t) :: d22, d41, dfin
    integer, parameter :: n = 4
    integer :: ib, ir, e
    real(dp) :: err

    call read_gmsh_file(data_dir // 'mixed_22.msh', m22, d22)
    call read_gmsh_file(data_dir // 'mixed_41.msh', m41, d41)
    call check(d22%count == 0 .and. d41%count == 0, 'mixed: both files read without error')
    call check(m41%nnode == 2 * n**2 - n .and. m22%nnode == 2 * n**2 - n, 'mixed: 2 n**2 - n nodes')
    call check(m41%nelem == 3 * (n - 1)**2 .and. m22%nelem == 3 * (n - 1)**2, 'mixed: 3 (n-1)**2 elements')
    call check(count(m41%nen == 4) == (n - 1)**2 .and. count(m41%nen == 3) == 2 * (n - 1)**2, &
      'mixed: (n-1)**2 quadrangles and 2 (n-1)**2 triangles')
    call check(all(m41%conn(4, :) == 0 .eqv. m41%nen == 3), 'mixed: conn(4,:) = 0 exactly for triangles')
    ir = find_name(m41%reg, 'quads')
    call check(ir > 0, 'mixed: region quads exists')
    if (ir > 0) call check(size(m41%reg(ir)%elems) == (n - 1)**2 .and. all(m41%nen(m41%reg(ir)%elems) == 4), &
      'mixed: region quads holds the quadrangles')
    ir = find_name(m41%reg, 'whole')
    if (ir > 0) call check(size(m41%reg(ir)%elems) == m41%nelem, 'mixed: region whole holds every element')
    call check(size(m41%bnd) == 2, 'mixed: physical point and curve named "right" make one boundary')
    ib = find_name(m41%bnd, 'right')
    if (ib > 0) then
      call check(m41%bnd(ib)%nseg == n - 1 .and. m41%bnd(ib)%npoint == 1, 'mixed: right has n-1 edges and 1 point')
      call check_small(maxval(abs(m41%x(:, m41%bnd(ib)%points(1)) - [2.0_dp, 0.0_dp])), 0.0_dp, &
        'mixed: the point of right is (2,0)')
    end if
    ib = find_name(m41%bnd, 'bottom')
    if (ib > 0) then
      call check(m41%bnd(ib)%nseg == 2 * (n - 1), 'mixed: bottom has 2 (n-1) edges')
      call check_close(total_length(m41, ib), 2.0_dp, tol_round(16), 'mixed: bottom has length 2')
    end if
    call check(same_mesh(m22, m41), 'mixed: MSH 2.2 and 4.1 give the same mesh (element order aside)')
    call finalize_mesh(m41, 'mixed_41.msh', dfin)
    call check(dfin%count == 0, 'mixed: finalize_mesh finds no defect')
    call check_close(total_area(m41), 2.0_dp, tol_round(16), 'mixed: element areas sum to 2')
    err = 0.0_dp
    do e = 1, m41%nelem
      if (m41%nen(e) == 4) err = max(err, abs(element_area(m41, e) - 1.0_dp / 9.0_dp))
    end do
    ! measured 833 eps: the thirds of the grid come from gmsh's text, not the nearest doubles
    call check_small(err, tol_round(8192), 'mixed: each quadrangle of the 3x3 grid has area 1/9')
  end subroutine test_mixed

  !> Unit disk, unstructured, surface in no physical group (Mesh.SaveAll).
  subroutine test_disk()
    type(mesh_t) :: m22, m41
    type(diag_t) :: d22, d41, dfin
    integer, allocatable :: nodes(:), uses(:)
    integer :: ib, k, nseg
    real(dp) :: polygon, pi, r

    pi = 4.0_dp * atan(1.0_dp)
    call read_gmsh_file(data_dir // 'disk_22.msh', m22, d22)
    call read_gmsh_file(data_dir // 'disk_41.msh', m41, d41)
    call check(d22%count == 0 .and. d41%count == 0, 'disk: both files read without error')
    call check(m41%nelem > 0 .and. all(m41%nen == 3), 'disk: triangles outside any physical surface are read')
    call check(size(m41%reg) == 0, 'disk: no physical surface, no region')
    call check(size(m22%bnd) == 0, 'disk: MSH 2.2 with SaveAll carries no physical tags (gmsh writes 0)')
    call check(same_nodes_elements(m22, m41), 'disk: MSH 2.2 and 4.1 give the same nodes and elements')
    ib = find_name(m41%bnd, 'rim')
    call check(ib > 0, 'disk: boundary rim exists')
    if (ib == 0) return
    nseg = m41%bnd(ib)%nseg
    r = 0.0_dp
    do k = 1, nseg
      r = max(r, maxval(abs(norm2(m41%x(:, m41%bnd(ib)%seg(:, k)), dim=1) - 1.0_dp)))
    end do
    call check_small(r, tol_round(16), 'disk: rim nodes lie on the unit circle')
    call boundary_nodes(m41%bnd(ib), nodes)
    allocate(uses(m41%nnode), source=0)
    do k = 1, nseg
      uses(m41%bnd(ib)%seg(:, k)) = uses(m41%bnd(ib)%seg(:, k)) + 1
    end do
    call check(size(nodes) == nseg .and. all(uses(nodes) == 2), 'disk: rim is a closed chain')
    polygon = 0.0_dp
    do k = 1, nseg
      associate(a => m41%x(:, m41%bnd(ib)%seg(1, k)), b => m41%x(:, m41%bnd(ib)%seg(2, k)))
        polygon = polygon + 0.5_dp * (a(1) * b(2) - a(2) * b(1))   ! shoelace
      end associate
    end do
    call check(polygon > 0.0_dp, 'disk: rim edges run counter-clockwise, as the arcs')
    call finalize_mesh(m41, 'disk_41.msh', dfin)
    call check(dfin%count == 0, 'disk: finalize_mesh finds no defect')
    call check_close(total_area(m41), abs(polygon), tol_round(16), 'disk: element areas sum to the rim polygon area')
    call check(abs(polygon) <= 0.5_dp * nseg * sin(2.0_dp * pi / nseg) + tol_round(16 * nseg) .and. abs(polygon) > 0.9_dp * pi, &
      'disk: rim polygon area below the regular polygon''s, close to pi')
  end subroutine test_disk

  !> Hand-written files: sparse tags 10 30 20 7 1000, CRLF lines and skipped
  !> sections (2.2), parametric node blocks (4.1), no $PhysicalNames.
  subroutine test_sparse_tags()
    type(mesh_t) :: m(2)
    type(diag_t) :: d(2)
    character(len=*), parameter :: files(2) = ['sparse_22.msh', 'sparse_41.msh']
    real(dp), parameter :: xref(2, 5) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, &
      0.0_dp, 1.0_dp, 5.0_dp, 5.0_dp], [2, 5])
    integer :: k, ib, ip, ir

    do k = 1, 2
      call read_gmsh_file(data_dir // files(k), m(k), d(k))
      call check(d(k)%count == 0, files(k) // ': read without error')
      call check(m(k)%nnode == 5, files(k) // ': 5 nodes, the unused one included')
      if (m(k)%nnode /= 5) cycle
      call check_small(maxval(abs(m(k)%x - xref)), 0.0_dp, files(k) // ': nodes in file order')
      call check(m(k)%nelem == 2, files(k) // ': 2 triangles')
      if (m(k)%nelem /= 2) cycle
      call check(all(m(k)%conn(:, 1) == [1, 2, 3, 0]) .and. all(m(k)%conn(:, 2) == [1, 3, 4, 0]), &
        files(k) // ': tags 10 30 20 7 map to nodes 1 2 3 4, file node order kept')
      ib = find_name(m(k)%bnd, '2')
      ip = find_name(m(k)%bnd, '3')
      ir = find_name(m(k)%reg, '1')
      call check(ib > 0 .and. ip > 0 .and. ir > 0, files(k) // ': unnamed groups named by their numbers')
      if (ib > 0) call check(m(k)%bnd(ib)%nseg == 1, files(k) // ': boundary 2 has one edge')
      if (ib > 0) call check(all(m(k)%bnd(ib)%seg(:, 1) == [1, 2]), files(k) // ': its edge is (10,30) = (1,2)')
      if (ip > 0) call check(m(k)%bnd(ip)%npoint == 1, files(k) // ': point set 3 has one point')
      if (ip > 0) call check(m(k)%bnd(ip)%points(1) == 4, files(k) // ': its point is tag 7 = node 4')
      if (ir > 0) call check(all(m(k)%reg(ir)%elems == [1, 2]), files(k) // ': region 1 = elements 1, 2')
    end do
    call check(same_mesh(m(1), m(2)), 'sparse: MSH 2.2 and 4.1 give the same mesh')
  end subroutine test_sparse_tags

  !> Coordinates in Fortran and C notations are read to their values.
  subroutine test_number_notations()
    type(mesh_t) :: m
    type(diag_t) :: d
    character(len=*), parameter :: lf = achar(10)
    character(len=:), allocatable :: path

    path = tmp // 'numbers.msh'
    call write_text(path, '$MeshFormat' // lf // '2.2 0 8' // lf // '$EndMeshFormat' // lf // &
      '$Nodes' // lf // '3' // lf // '1 -0 +.5e-0 0.0' // lf // '2 2.5D0 1E+00 -0e0' // lf // &
      '3 5. 0.25d+1 1e-320' // lf // '$EndNodes' // lf // '$Elements' // lf // '1' // lf // &
      '1 2 0 1 2 3' // lf // '$EndElements' // lf)
    call read_gmsh_file(path, m, d)
    call check(d%count == 0 .and. m%nnode == 3, 'numbers: -0 +.5e-0 2.5D0 1E+00 5. 0.25d+1 1e-320 accepted')
    if (m%nnode == 3) call check_small(maxval(abs(m%x - reshape([0.0_dp, 0.5_dp, 2.5_dp, 1.0_dp, 5.0_dp, 2.5_dp], &
      [2, 3]))), 0.0_dp, 'numbers: values exact')
    call check(m%nelem == 1 .and. size(m%reg) == 0, 'numbers: element with no tags, no region')
    call delete_file(path)
  end subroutine test_number_notations

  !> Node tags far above the number of nodes, so that they are found by a
  !> search of the sorted tags rather than by a table: sparse_22.msh and
  !> sparse_41.msh with every tag t written as 10**12 + t give the same mesh;
  !> a duplicate and an undefined far tag are reported as near ones are.
  subroutine test_far_tags()
    type(mesh_t) :: m22, m41, ref
    type(diag_t) :: d, dref
    character(len=*), parameter :: lf = achar(10)
    character(len=*), parameter :: head22 = '$MeshFormat' // lf // '2.2 0 8' // lf // '$EndMeshFormat' // lf
    character(len=*), parameter :: t7 = '1000000000007', t10 = '1000000000010', t20 = '1000000000020', &
      t30 = '1000000000030', t1000 = '1000000001000'
    character(len=:), allocatable :: path

    path = tmp // 'far_tags.msh'
    call read_gmsh_file(data_dir // 'sparse_22.msh', ref, dref)
    call write_text(path, head22 // '$Nodes' // lf // '5' // lf // t10 // ' 0 0 0' // lf // t30 // ' 1 0 0' // lf // &
      t20 // ' 1 1 0' // lf // t7 // ' 0 1 0' // lf // t1000 // ' 5 5 0' // lf // '$EndNodes' // lf // &
      '$Elements' // lf // '4' // lf // '1 2 2 1 4 ' // t10 // ' ' // t30 // ' ' // t20 // lf // &
      '2 2 2 1 4 ' // t10 // ' ' // t20 // ' ' // t7 // lf // '3 1 2 2 8 ' // t10 // ' ' // t30 // lf // &
      '4 15 2 3 5 ' // t7 // lf // '$EndElements' // lf)
    call read_gmsh_file(path, m22, d)
    call check(d%count == 0 .and. dref%count == 0, 'far tags: MSH 2.2 read without error')
    call check(same_mesh(m22, ref), 'far tags: MSH 2.2 gives the mesh of sparse_22.msh (tags 10 30 20 7 1000)')

    call write_text(path, '$MeshFormat' // lf // '4.1 0 8' // lf // '$EndMeshFormat' // lf // '$Nodes' // lf // &
      '1 5 ' // t7 // ' ' // t1000 // lf // '2 1 0 5' // lf // t10 // lf // t30 // lf // t20 // lf // t7 // lf // &
      t1000 // lf // '0 0 0' // lf // '1 0 0' // lf // '1 1 0' // lf // '0 1 0' // lf // '5 5 0' // lf // &
      '$EndNodes' // lf // '$Elements' // lf // '1 2 1 2' // lf // '2 1 2 2' // lf // '1 ' // t10 // ' ' // t30 // &
      ' ' // t20 // lf // '2 ' // t10 // ' ' // t20 // ' ' // t7 // lf // '$EndElements' // lf)
    d = diag_t()
    call read_gmsh_file(path, m41, d)
    call check(d%count == 0 .and. m41%nnode == 5 .and. m41%nelem == 2, 'far tags: MSH 4.1 read without error')
    if (m41%nelem == 2 .and. m41%nnode == 5) then
      call check(all(m41%conn(:, 1) == [1, 2, 3, 0]) .and. all(m41%conn(:, 2) == [1, 3, 4, 0]) .and. &
        all(m41%x == ref%x), 'far tags: MSH 4.1 maps the tags to nodes 1 2 3 4 in file order')
    end if

    call write_text(path, head22 // '$Nodes' // lf // '3' // lf // t10 // ' 0 0 0' // lf // t30 // ' 1 0 0' // lf // &
      t10 // ' 1 1 0' // lf // '$EndNodes' // lf // '$Elements' // lf // '1' // lf // '1 2 0 ' // t10 // ' ' // &
      t30 // ' ' // t20 // lf // '$EndElements' // lf)
    d = diag_t()
    call read_gmsh_file(path, m22, d)
    call check(d%count == 1 .and. m22%nnode == 0, 'far tags: a duplicate tag gives one error')
    if (d%count == 1) call check(index(d%items(1)%text, 'far_tags.msh:8: duplicate node tag ' // t10 // &
      ' (each node tag defined once expected)') > 0, 'far tags: the duplicate is reported at its line')

    call write_text(path, head22 // '$Nodes' // lf // '3' // lf // t10 // ' 0 0 0' // lf // t30 // ' 1 0 0' // lf // &
      t20 // ' 1 1 0' // lf // '$EndNodes' // lf // '$Elements' // lf // '1' // lf // '1 2 0 ' // t10 // ' ' // &
      t30 // ' ' // t7 // lf // '$EndElements' // lf)
    d = diag_t()
    call read_gmsh_file(path, m22, d)
    call check(d%count == 1 .and. m22%nnode == 0, 'far tags: an undefined tag gives one error')
    if (d%count == 1) call check(index(d%items(1)%text, 'far_tags.msh:12: element refers to undefined node tag ' // &
      t7 // ' (a node tag defined in $Nodes expected)') > 0, 'far tags: the undefined tag is reported at its line')
    call delete_file(path)
  end subroutine test_far_tags

  !> Coordinates are the doubles nearest to their texts, bit for bit as the
  !> Fortran library's list-directed read of the same text gives them: hard
  !> cases (ties to even at 2**53, 17 to 20 digits, exponents beyond 22, one
  !> digit off a tie) and 3000 pseudo-random texts of 1 to 20 digits with a
  !> point anywhere and exponents from -25 to 25.
  subroutine test_correct_rounding()
    integer, parameter :: nhand = 20, nrandom = 3000
    character(len=*), parameter :: hand(nhand) = [character(len=40) :: '9007199254740993', '9007199254740995', &
      '-0.9007199254740993', '1.00000000000000011', '1.000000000000000111', '1e23', '9.999999999999999e22', &
      '0.30000000000000004', '8.98846567431158e15', '-4.4501477170144023e-15', '123456789012345678e-30', &
      '2.2250738585072011e-10', '7.0064923216240862e-46', '1.7976931348623157e99', '4.35679585e-7', '0.1', &
      '18014398509481985', '1.00000000000000000000000000001', '90071992547409930e-1', '9007199254740995000e-3']
    character(len=*), parameter :: lf = achar(10)
    character(len=40) :: text(nhand + nrandom)
    character(len=:), allocatable :: body, path
    type(mesh_t) :: m
    type(diag_t) :: d
    real(dp) :: v
    integer(i8) :: state
    integer :: k, nwrong, ios

    state = 20240601_i8
    text(1:nhand) = hand
    do k = nhand + 1, nhand + nrandom
      text(k) = random_decimal(state)
    end do
    body = ''
    do k = 1, size(text)
      body = body // itoa(k) // ' ' // trim(text(k)) // ' 0 0' // lf
    end do
    path = tmp // 'rounding.msh'
    call write_text(path, '$MeshFormat' // lf // '2.2 0 8' // lf // '$EndMeshFormat' // lf // '$Nodes' // lf // &
      itoa(size(text)) // lf // body // '$EndNodes' // lf // '$Elements' // lf // '1' // lf // '1 2 0 1 2 3' // lf // &
      '$EndElements' // lf)
    call read_gmsh_file(path, m, d)
    call check(d%count == 0 .and. m%nnode == size(text), 'rounding: ' // itoa(size(text)) // ' coordinates read')
    if (m%nnode == size(text)) then
      nwrong = 0
      do k = 1, size(text)
        read(text(k), *, iostat=ios) v
        if (ios /= 0 .or. transfer(m%x(1, k), 1_i8) /= transfer(v, 1_i8)) nwrong = nwrong + 1
      end do
      call check(nwrong == 0, 'rounding: each coordinate has the bits of read(text, *) (' // itoa(nwrong) // &
        ' differ)')
    end if
    call delete_file(path)
  end subroutine test_correct_rounding

  !> A decimal text [-]digits[.digits][e|d exponent], 1 to 20 digits, the first
  !> one nonzero; state (inout) of a Park-Miller generator.
  function random_decimal(state) result(s)
    integer(i8), intent(inout) :: state
    character(len=40) :: s
    character(len=24) :: digits
    integer :: nd, k, point

    nd = 1 + next_int(state, 20)
    digits = ''
    do k = 1, nd
      digits(k:k) = achar(iachar('0') + merge(1 + next_int(state, 9), next_int(state, 10), k == 1))
    end do
    point = next_int(state, nd + 1)
    s = digits(1:point) // '.' // digits(point + 1:nd)
    if (point == nd .and. next_int(state, 2) == 0) s = digits(1:nd)
    if (next_int(state, 3) > 0) s = trim(s) // merge('e', 'd', next_int(state, 4) > 0) // itoa(next_int(state, 51) - 25)
    if (next_int(state, 2) == 0) s = '-' // trim(s)
  end function random_decimal

  !> A pseudo-random integer in 0 .. n - 1 (Park-Miller, state < 2**31).
  integer function next_int(state, n)
    integer(i8), intent(inout) :: state
    integer, intent(in) :: n
    state = mod(48271_i8 * state, 2147483647_i8)
    next_int = int(mod(state, int(n, i8)))
  end function next_int

  !> mesh_geo_file (gmsh_runner): -setnumber, default values, a path with a
  !> quote, failure.
  subroutine test_geo_meshing()
    type(mesh_t) :: m
    type(diag_t) :: d
    character(len=:), allocatable :: msh, log, geo
    type(error_t), allocatable :: err
    type(gmsh_options_t) :: opts
    character(len=8) :: no_names(0)
    real(dp) :: no_values(0)
    integer :: ib

    msh = tmp // 'square.msh'
    log = tmp // 'square.log'
    call mesh_geo_file(data_dir // 'square.geo', 1, ['n'], [6.0_dp], opts, data_dir, msh, log, err)
    call check(.not. allocated(err), 'geo: gmsh meshes square.geo with -setnumber n 6' // failure(err))
    if (.not. allocated(err)) then
      call read_gmsh_file(msh, m, d)
      call check(d%count == 0 .and. m%nnode == 36 .and. m%nelem == 50, 'geo: n = 6 gives 36 nodes, 50 triangles')
      ib = find_name(m%bnd, 'bottom')
      if (ib > 0) call check(m%bnd(ib)%nseg == 5, 'geo: bottom has n-1 = 5 edges')
    end if
    call delete_file(log)
    call mesh_geo_file(data_dir // 'square.geo', 1, no_names, no_values, opts, data_dir, msh, log, err)
    call check(.not. allocated(err), 'geo: gmsh meshes square.geo with no parameter' // failure(err))
    if (.not. allocated(err)) then
      call read_gmsh_file(msh, m, d)
      call check(d%count == 0 .and. m%nnode == 16 .and. m%nelem == 18, 'geo: default n = 4 gives 16 nodes, 18 triangles')
    end if

    ! A path with a blank and a single quote must reach gmsh intact.
    geo = tmp // 'it''s a square.geo'
    call write_text(geo, 'DefineConstant[ n = 2 ];' // achar(10) // &
      'Point(1) = {0,0,0,1}; Point(2) = {2,0,0,1}; Point(3) = {2,1,0,1}; Point(4) = {0,1,0,1};' // achar(10) // &
      'Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};' // achar(10) // &
      'Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};' // achar(10) // &
      'Transfinite Curve{1,2,3,4} = n; Transfinite Surface{1}; Recombine Surface{1};' // achar(10))
    call delete_file(log)
    call mesh_geo_file(geo, 1, ['n'], [3.0_dp], opts, tmp, msh, log, err)
    call check(.not. allocated(err), 'geo: gmsh meshes a path with a blank and a quote' // failure(err))
    if (.not. allocated(err)) then
      call read_gmsh_file(msh, m, d)
      call check(d%count == 0 .and. m%nelem == 4 .and. all(m%nen == 4), 'geo: n = 3 recombined gives 4 quadrangles')
      call finalize_mesh(m, msh, d)
      call check_close(total_area(m), 2.0_dp, tol_round(16), 'geo: area of the 2 x 1 rectangle')
    end if
    call delete_file(geo)

    call delete_file(log)
    call mesh_geo_file(tmp // 'no such file.geo', 1, ['n'], [3.0_dp], opts, tmp, msh, log, err)
    call check(allocated(err), 'geo: a missing .geo file fails')
    if (allocated(err)) call check(index(err%message, 'cannot find') == 1, 'geo: message says the .geo is missing: ' // &
                                   err%message)
    call delete_file(msh)
    call delete_file(log)
  end subroutine test_geo_meshing

  !> Each tests/bad/mesh_NAME.msh gives exactly the line of mesh_NAME.expect.
  subroutine test_bad_meshes()
    character(len=24), parameter :: names(26) = [character(len=24) :: &
      '3d', '41_block_count', '41_parametric', '41_undefined_entity', 'bad_format_line', 'binary_format', &
      'binary_garbage', 'duplicate_node', 'duplicate_section', 'empty', 'format_eof', 'huge_count', 'inf', &
      'missing_endelements', 'missing_nodes', 'nan', 'negative_count', 'no_2d', 'not_msh', 'overflow', &
      'text_number', 'truncated', 'undefined_node', 'version30', 'wrong_items', 'z_nonzero']
    type(mesh_t) :: m
    type(diag_t) :: d
    character(len=:), allocatable :: base, got, want
    integer :: k, p

    do k = 1, size(names)
      base = 'tests/bad/mesh_' // trim(names(k))
      d = diag_t()
      call read_gmsh_file(base // '.msh', m, d)
      call check(d%count == 1 .and. m%nnode == 0 .and. m%nelem == 0, &
        'bad mesh ' // trim(names(k)) // ': one error, empty mesh')
      if (d%count < 1) cycle
      got = d%items(1)%text
      p = index(got, new_line('a'))
      if (p > 0) got = got(1:p - 1)
      p = index(got, 'tests/bad/')
      if (p > 0) got = got(1:p - 1) // got(p + len('tests/bad/'):)
      want = first_line(base // '.expect')
      call check(got == want, 'bad mesh ' // trim(names(k)) // ': "' // got // '"')
    end do
  end subroutine test_bad_meshes

  !> Truncated, mutated and random files: one error or a mesh, never a crash.
  subroutine test_robustness()
    character(len=:), allocatable :: good, text, path
    character(len=*), parameter :: lf = achar(10)
    character(len=*), parameter :: alphabet = '0123456789$-+.eE "' // achar(10) // achar(13) // achar(0) // achar(9)
    type(mesh_t) :: m
    type(diag_t) :: d
    real(dp) :: u(4)
    integer :: k, j, nbad, ntry, pos, nchange, seed_size
    integer, allocatable :: seed(:)

    call random_seed(size=seed_size)
    allocate(seed(seed_size))
    seed = [(7919 * k + 17, k = 1, seed_size)]
    call random_seed(put=seed)
    path = tmp // 'fuzz.msh'
    nbad = 0
    ntry = 0
    do j = 1, 2
      if (j == 1) good = read_text(data_dir // 'square_41.msh')
      if (j == 2) good = read_text(data_dir // 'mixed_22.msh')
      ! every prefix (step 3 bytes)
      do k = 0, len(good), 3
        call write_text(path, good(1:k))
        call read_one(path, ntry, nbad)
      end do
      ! 300 copies with 1 to 3 bytes changed
      do k = 1, 300
        text = good
        call random_number(u)
        nchange = 1 + int(3 * u(1))
        do pos = 1, nchange
          call random_number(u)
          if (u(3) < 0.7_dp) then
            text(1 + int(u(1) * len(text)):1 + int(u(1) * len(text))) = alphabet(1 + int(u(2) * len(alphabet)):&
              1 + int(u(2) * len(alphabet)))
          else
            text(1 + int(u(1) * len(text)):1 + int(u(1) * len(text))) = achar(int(256 * u(2)))
          end if
        end do
        call write_text(path, text)
        call read_one(path, ntry, nbad)
      end do
    end do
    ! random bytes, alone or after a valid $MeshFormat
    do k = 1, 40
      text = random_bytes(1 + 50 * k)
      if (mod(k, 2) == 0) text = '$MeshFormat' // lf // '4.1 0 8' // lf // '$EndMeshFormat' // lf // text
      call write_text(path, text)
      call read_one(path, ntry, nbad)
    end do
    call check(nbad == 0, 'robustness: ' // itoa(ntry) // ' truncated, mutated and random files each give one error '// &
      'or a mesh')

    ! one line of 300000 characters: the echo is cut
    call write_text(path, '$MeshFormat' // lf // repeat('7', 300000) // lf)
    d = diag_t()
    call read_gmsh_file(path, m, d)
    call check(d%count == 1, 'robustness: a 300000-character line is reported')
    if (d%count == 1) call check(len(d%items(1)%text) < 400, 'robustness: its echo is shortened')
    d = diag_t()
    call read_gmsh_file(tmp // 'no such file.msh', m, d)
    call check(d%count == 1, 'robustness: a missing file is reported')
    if (d%count == 1) call check(index(d%items(1)%text, 'no such file.msh: cannot open') > 0, &
      'robustness: a missing file is reported without line number')
    d = diag_t()
    call read_gmsh_file('tests/unit/data', m, d)
    call check(d%count == 1 .and. m%nnode == 0, 'robustness: a folder is reported, not read')
    call delete_file(path)
  end subroutine test_robustness

  !> Read path; count the try, and a bad outcome (neither one error and an empty
  !> mesh, nor no error and some elements).
  subroutine read_one(path, ntry, nbad)
    character(len=*), intent(in) :: path
    integer, intent(inout) :: ntry, nbad
    type(mesh_t) :: m
    type(diag_t) :: d
    call read_gmsh_file(path, m, d)
    ntry = ntry + 1
    if (.not. ((d%count == 1 .and. m%nnode == 0 .and. m%nelem == 0) .or. (d%count == 0 .and. m%nelem > 0))) then
      nbad = nbad + 1
    end if
  end subroutine read_one

  ! ---------------------------------------------------------------------------
  ! helpers
  ! ---------------------------------------------------------------------------

  !> Same nodes, same elements (in any order), same boundaries and regions.
  logical function same_mesh(a, b) result(same)
    type(mesh_t), intent(in) :: a, b
    integer, allocatable :: emap(:), ea(:), eb(:)
    integer :: k, j
    same = same_nodes_elements(a, b, emap)
    if (.not. same) return
    same = size(a%bnd) == size(b%bnd) .and. size(a%reg) == size(b%reg)
    if (.not. same) return
    do k = 1, size(a%bnd)
      j = find_name(b%bnd, a%bnd(k)%name)
      if (j == 0) then
        same = .false.
        return
      end if
      same = a%bnd(k)%nseg == b%bnd(j)%nseg .and. a%bnd(k)%npoint == b%bnd(j)%npoint
      if (.not. same) return
      same = all(a%bnd(k)%seg == b%bnd(j)%seg) .and. all(a%bnd(k)%points == b%bnd(j)%points)
      if (.not. same) return
    end do
    do k = 1, size(a%reg)
      j = find_name(b%reg, a%reg(k)%name)
      if (j == 0) then
        same = .false.
        return
      end if
      ea = emap(a%reg(k)%elems)
      eb = b%reg(j)%elems
      same = size(ea) == size(eb)
      if (.not. same) return
      call sort_small(ea)
      call sort_small(eb)
      same = all(ea == eb)
      if (.not. same) return
    end do
  end function same_mesh

  !> Same node coordinates in the same order; same elements (node lists) in any
  !> order.  emap(e) = element of b equal to element e of a.
  logical function same_nodes_elements(a, b, emap) result(same)
    type(mesh_t), intent(in) :: a, b
    integer, allocatable, intent(out), optional :: emap(:)
    integer, allocatable :: map(:)
    logical, allocatable :: taken(:)
    integer :: e, f
    same = a%nnode == b%nnode .and. a%nelem == b%nelem
    if (.not. same) return
    same = maxval(abs(a%x - b%x)) <= tol_round(32)
    if (.not. same) return
    allocate(map(a%nelem), source=0)
    allocate(taken(b%nelem), source=.false.)
    do e = 1, a%nelem
      do f = 1, b%nelem
        if (taken(f)) cycle
        if (a%nen(e) == b%nen(f) .and. all(a%conn(:, e) == b%conn(:, f))) then
          map(e) = f
          taken(f) = .true.
          exit
        end if
      end do
      if (map(e) == 0) then
        same = .false.
        return
      end if
    end do
    if (present(emap)) emap = map
  end function same_nodes_elements

  real(dp) function total_area(m) result(a)
    type(mesh_t), intent(in) :: m
    integer :: e
    a = 0.0_dp
    do e = 1, m%nelem
      a = a + element_area(m, e)
    end do
  end function total_area

  real(dp) function total_length(m, ib) result(s)
    type(mesh_t), intent(in) :: m
    integer, intent(in) :: ib
    integer :: k
    s = 0.0_dp
    do k = 1, m%bnd(ib)%nseg
      s = s + norm2(m%x(:, m%bnd(ib)%seg(2, k)) - m%x(:, m%bnd(ib)%seg(1, k)))
    end do
  end function total_length

  !> Folder for scratch files: $TMPDIR or /tmp, with a name prefix.
  function scratch_prefix() result(p)
    character(len=:), allocatable :: p
    character(len=512) :: dir
    integer :: n, status
    call get_environment_variable('TMPDIR', dir, n, status)
    if (status /= 0 .or. n == 0) dir = '/tmp'
    p = trim(dir) // '/test_gmsh_reader_'
  end function scratch_prefix

  !> Whole file as a string ('' when it cannot be read).
  function read_text(path) result(text)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: text
    integer :: u, ios, n
    text = ''
    open(newunit=u, file=path, access='stream', form='unformatted', action='read', status='old', iostat=ios)
    if (ios /= 0) return
    inquire(unit=u, size=n)
    if (n > 0) then
      deallocate(text)
      allocate(character(len=n) :: text)
      read(u, iostat=ios) text
    end if
    close(u)
  end function read_text

  !> First line of a text file, without its end of line.
  function first_line(path) result(line)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: line
    integer :: p
    line = read_text(path)
    p = index(line, achar(10))
    if (p > 0) line = line(1:p - 1)
  end function first_line

  subroutine write_text(path, text)
    character(len=*), intent(in) :: path, text
    integer :: u
    open(newunit=u, file=path, access='stream', form='unformatted', action='write', status='replace')
    write(u) text
    close(u)
  end subroutine write_text

  subroutine delete_file(path)
    character(len=*), intent(in) :: path
    integer :: u, ios
    logical :: there
    inquire(file=path, exist=there)
    if (.not. there) return
    open(newunit=u, file=path, status='old', iostat=ios)
    if (ios == 0) close(u, status='delete', iostat=ios)
  end subroutine delete_file

  function random_bytes(n) result(s)
    integer, intent(in) :: n
    character(len=n) :: s
    real(dp) :: u
    integer :: i
    do i = 1, n
      call random_number(u)
      s(i:i) = achar(int(256 * u))
    end do
  end function random_bytes

  !> ': message' of err when allocated, else ''.
  function failure(err) result(s)
    type(error_t), allocatable, intent(in) :: err
    character(len=:), allocatable :: s
    s = ''
    if (allocated(err)) s = ': ' // err%message
  end function failure

  function itoa(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function itoa

end program test_gmsh_reader
