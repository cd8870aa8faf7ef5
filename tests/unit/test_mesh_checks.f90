!> Unit tests of finalize_mesh (module mesh) on meshes written here, one
!> step of it each:
!>
!> - drop_unused_nodes: a node of no element is dropped, the others keep
!>   their order, and every element, boundary edge and point set names the
!>   same points as before;
!> - reverse_orientation: a mesh clockwise throughout comes back
!>   counter-clockwise (every element of positive area), quadrilaterals
!>   and 6-node triangles, whose mid-side node k stays the middle of
!>   corners k and k + 1;
!> - each defect is reported, alone, with its own message: no elements, an
!>   element or a point set naming a node that does not exist, linear and
!>   quadratic elements mixed, 2-node edges on a quadratic mesh, an edge of
!>   a node of no element, a zero-length edge, a degenerate, an inverted
!>   (the minority), a non-convex and a folded element.
program test_mesh_checks
  use kinds, only: dp
  use errors, only: diag_t
  use mesh, only: mesh_t, finalize_mesh, element_area
  use testing, only: check, check_small, finish_tests
  implicit none
  type(mesh_t) :: m, m0
  type(diag_t) :: d
  real(dp) :: err
  integer :: e, k

  ! two unit quadrilaterals, clockwise, node 3 used by no element; a
  ! boundary along the bottom and a point set at the top right corner
  call make_mesh(m, reshape([0, 0, 1, 0, 9, 9, 2, 0, 0, 1, 1, 1, 2, 1], [2, 7]), &
                 reshape([1, 5, 6, 2,  2, 6, 7, 4], [4, 2]), [4, 4])
  call add_boundary(m, 'bottom', reshape([1, 2, 2, 4], [2, 2]))
  call add_points(m, 'corner', [7])
  m0 = m
  call finalize(m, d)
  call check(d%count == 0, 'quads: no defect')
  call check(m%nnode == 6 .and. size(m%x, 2) == 6, 'quads: the unused node dropped')
  call check(all(m%x(:, 1:2) == m0%x(:, 1:2)) .and. all(m%x(:, 3:6) == m0%x(:, 4:7)), &
             'quads: the other nodes in their order')
  call check(all([(element_area(m, e) > 0.0_dp, e = 1, m%nelem)]), 'quads: every element counter-clockwise')
  err = 0.0_dp
  do e = 1, m%nelem                                  ! the same corners, the other way round
    do k = 1, 4
      err = max(err, maxval(abs(m%x(:, m%conn(k, e)) - m0%x(:, m0%conn(5 - k, e)))))
    end do
  end do
  call check_small(err, 0.0_dp, 'quads: each element''s corners reversed')
  err = 0.0_dp
  do k = 1, 2
    err = max(err, maxval(abs(m%x(:, m%bnd(1)%seg(:, k)) - m0%x(:, m0%bnd(1)%seg(:, k)))))
  end do
  err = max(err, maxval(abs(m%x(:, m%bnd(2)%points(1)) - m0%x(:, m0%bnd(2)%points(1)))))
  call check_small(err, 0.0_dp, 'quads: the boundary edges and the point at the same points')

  ! a 6-node triangle, clockwise: corners (0,0) (0,1) (1,0), mid-side nodes after them
  call make_mesh(m, reshape([0, 0, 0, 2, 2, 0, 0, 1, 1, 1, 1, 0], [2, 6]), reshape([1, 2, 3, 4, 5, 6, 0, 0, 0], [9, 1]), [6])
  call finalize(m, d)
  call check(d%count == 0 .and. element_area(m, 1) > 0.0_dp, 'tri6: reversed, no defect')
  err = 0.0_dp
  do k = 1, 3
    err = max(err, maxval(abs(m%x(:, m%conn(3 + k, 1)) - &
                             0.5_dp * (m%x(:, m%conn(k, 1)) + m%x(:, m%conn(mod(k, 3) + 1, 1))))))
  end do
  call check_small(err, 0.0_dp, 'tri6: mid-side node k the middle of corners k and k + 1')

  ! the defects, one mesh each
  call make_mesh(m, reshape([0, 0, 1, 0, 0, 1], [2, 3]), reshape([integer ::], [4, 0]), [integer ::])
  call expect(m, 'mesh has no 2D elements', 'no elements')
  call make_mesh(m, reshape([0, 0, 1, 0, 0, 1], [2, 3]), reshape([1, 2, 9, 0], [4, 1]), [3])
  call expect(m, 'element 1 refers to a node that does not exist', 'an element''s node outside the mesh')
  call make_mesh(m, reshape([0, 0, 1, 0, 0, 1], [2, 3]), reshape([1, 2, 3, 0], [4, 1]), [3])
  call add_points(m, 'far', [4])
  call expect(m, 'point set "far" refers to a node that does not exist', 'a point outside the mesh')
  call make_mesh(m, reshape([0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 2], [2, 7]), &
                 reshape([1, 2, 3, 4, 5, 6, 0, 0, 0,  2, 7, 3, 0, 0, 0, 0, 0, 0], [9, 2]), [6, 3])
  call expect(m, 'mixes linear and quadratic elements', 'linear and quadratic mixed')
  call make_mesh(m, reshape([0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1], [2, 6]), reshape([1, 2, 3, 4, 5, 6, 0, 0, 0], [9, 1]), [6])
  call add_boundary(m, 'base', reshape([1, 2], [2, 1]))
  call expect(m, 'boundary "base" has 2-node edges on a mesh of quadratic elements', '2-node edges, quadratic mesh')
  call make_mesh(m, reshape([0, 0, 1, 0, 0, 1, 5, 5], [2, 4]), reshape([1, 2, 3, 0], [4, 1]), [3])
  call add_boundary(m, 'loose', reshape([2, 4], [2, 1]))
  call expect(m, 'boundary "loose" has an edge whose nodes belong to no element', 'an edge off the elements')
  call make_mesh(m, reshape([0, 0, 1, 0, 0, 1, 1, 0, 1, 1], [2, 5]), reshape([1, 2, 3, 0,  4, 5, 3, 0], [4, 2]), [3, 3])
  call add_boundary(m, 'seam', reshape([2, 4], [2, 1]))
  call expect(m, 'boundary "seam" has a zero-length edge (nodes 2 and 4', 'a zero-length edge')
  call make_mesh(m, reshape([0, 0, 1, 0, 2, 0, 0, 1], [2, 4]), reshape([1, 2, 3, 0,  1, 2, 4, 0], [4, 2]), [3, 3])
  call expect(m, 'element 1 is degenerate', 'a degenerate element')
  call make_mesh(m, reshape([0, 0, 1, 0, 1, 1, 0, 1, 2, 0], [2, 5]), &
                 reshape([1, 2, 3, 0,  1, 3, 4, 0,  2, 3, 5, 0], [4, 3]), [3, 3, 3])
  call expect(m, 'element 3 is inverted', 'the minority inverted')
  call make_mesh(m, reshape([0, 0, 4, 0, 1, 1, 0, 4], [2, 4]), reshape([1, 2, 3, 4], [4, 1]), [4])
  call expect(m, 'quadrilateral 1 is not convex', 'a non-convex quadrilateral')
  call make_mesh(m, reshape([0, 0, 2, 0, 0, 2, 1, 3, 1, 1, 0, 1], [2, 6]), reshape([1, 2, 3, 4, 5, 6, 0, 0, 0], [9, 1]), [6])
  call expect(m, 'element 1 is folded', 'a folded 6-node triangle')
  call finish_tests()

contains

  !> m = nodes x (2, nnode) and elements conn (4 or 9, nelem) of nen nodes.
  subroutine make_mesh(m, x, conn, nen)
    type(mesh_t), intent(out) :: m
    integer, intent(in) :: x(:,:), conn(:,:), nen(:)
    m%nnode = size(x, 2)
    m%nelem = size(conn, 2)
    m%x = real(x, dp)
    m%conn = conn
    m%nen = nen
    allocate(m%bnd(0))
  end subroutine make_mesh

  subroutine add_boundary(m, name, seg)
    type(mesh_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    integer, intent(in) :: seg(:,:)
    integer :: n
    n = size(m%bnd) + 1
    call grow(m, n)
    m%bnd(n)%name = name
    m%bnd(n)%nseg = size(seg, 2)
    m%bnd(n)%seg = seg
  end subroutine add_boundary

  subroutine add_points(m, name, points)
    type(mesh_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    integer, intent(in) :: points(:)
    integer :: n
    n = size(m%bnd) + 1
    call grow(m, n)
    m%bnd(n)%name = name
    m%bnd(n)%npoint = size(points)
    m%bnd(n)%points = points
  end subroutine add_points

  !> m%bnd with room for n boundaries (the new ones empty).
  subroutine grow(m, n)
    type(mesh_t), intent(inout) :: m
    integer, intent(in) :: n
    type(mesh_t) :: t
    allocate(t%bnd(n))
    t%bnd(1:size(m%bnd)) = m%bnd
    call move_alloc(t%bnd, m%bnd)
  end subroutine grow

  subroutine finalize(m, d)
    type(mesh_t), intent(inout) :: m
    type(diag_t), intent(out) :: d
    call finalize_mesh(m, 'test.msh', d)
    if (d%count > 0) print '(a)', d%items(1)%text
  end subroutine finalize

  !> finalize_mesh reports one defect, its message containing text.
  subroutine expect(m, text, name)
    type(mesh_t), intent(inout) :: m
    character(len=*), intent(in) :: text, name
    type(diag_t) :: d
    call finalize_mesh(m, 'test.msh', d)
    if (d%count /= 1) then
      call check(.false., name // ': one message (got ' // achar(48 + min(d%count, 9)) // ')')
      return
    end if
    call check(index(d%items(1)%text, text) > 0, name // ': ' // text)
    if (index(d%items(1)%text, text) == 0) print '(a)', d%items(1)%text
  end subroutine expect
end program test_mesh_checks
