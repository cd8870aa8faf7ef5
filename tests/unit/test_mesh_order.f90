!> order_for_locality: the renumbered mesh is the same mesh (every element,
!> boundary edge, point and region names the same points as in the file's
!> numbering), the maps to the file's numbering are inverse permutations, and
!> neighbours in the mesh become neighbours in memory.
program test_mesh_order
  use kinds, only: dp, i8
  use mesh, only: mesh_t, order_for_locality, file_item, node_in_file, hilbert_index
  use testing, only: check, check_small, finish_tests
  implicit none
  integer, parameter :: nx = 60, ny = 40
  type(mesh_t) :: m, f
  integer, allocatable :: nperm(:), eperm(:), seen(:)
  integer :: i, j, e, p, k, a
  real(dp) :: err, r

  ! a triangulated nx x ny grid numbered as a mesh generator might: nodes and
  ! elements in a shuffled order; a boundary (bottom edges), a point set and
  ! a region of every third element
  f%nnode = (nx + 1) * (ny + 1)
  f%nelem = 2 * nx * ny
  call shuffle(f%nnode, 11, nperm)       ! nperm(grid node) = file number
  call shuffle(f%nelem, 12, eperm)
  allocate(f%x(2, f%nnode), f%conn(4, f%nelem), f%nen(f%nelem), f%elem_line(f%nelem))
  do j = 0, ny
    do i = 0, nx
      f%x(:, nperm(gid(i, j))) = [real(i, dp) * 0.7_dp, real(j, dp) * 1.3_dp]
    end do
  end do
  e = 0
  do j = 0, ny - 1
    do i = 0, nx - 1
      e = e + 1
      f%conn(:, eperm(e)) = [nperm(gid(i, j)), nperm(gid(i + 1, j)), nperm(gid(i + 1, j + 1)), 0]
      e = e + 1
      f%conn(:, eperm(e)) = [nperm(gid(i, j)), nperm(gid(i + 1, j + 1)), nperm(gid(i, j + 1)), 0]
    end do
  end do
  f%nen = 3
  f%elem_line = [(100 + e, e = 1, f%nelem)]
  allocate(f%bnd(2), f%reg(1))
  f%bnd(1)%name = 'bottom'
  f%bnd(1)%nseg = nx
  allocate(f%bnd(1)%seg(2, nx))
  do i = 0, nx - 1
    f%bnd(1)%seg(:, i + 1) = [nperm(gid(i, 0)), nperm(gid(i + 1, 0))]
  end do
  f%bnd(2)%name = 'corner'
  f%bnd(2)%npoint = 1
  f%bnd(2)%points = [nperm(gid(nx, ny))]
  f%reg(1)%name = 'thirds'
  f%reg(1)%elems = [(e, e = 1, f%nelem, 3)]

  m = f
  call order_for_locality(m)

  ! the maps: inverse permutations
  allocate(seen(max(m%nnode, m%nelem)))
  do p = 1, m%nnode
    seen(p) = file_item(m, p, element=.false.)
  end do
  call check(is_permutation(seen(1:m%nnode)), 'file_item is a permutation of the nodes')
  k = 0
  do p = 1, m%nnode
    if (node_in_file(m, file_item(m, p, element=.false.)) /= p) k = k + 1
  end do
  call check(k == 0, 'node_in_file inverts file_item')
  do p = 1, m%nelem
    seen(p) = file_item(m, p, element=.true.)
  end do
  call check(is_permutation(seen(1:m%nelem)), 'file_item is a permutation of the elements')

  ! the same mesh: points of nodes, elements, edges, point sets, regions
  err = 0
  do p = 1, m%nnode
    err = max(err, maxval(abs(m%x(:, file_item(m, p, element=.false.)) - f%x(:, p))))
  end do
  call check_small(err, 0.0_dp, 'node p of the file is at the same point')
  err = 0
  do p = 1, f%nelem
    e = file_item(m, p, element=.true.)
    do k = 1, 3
      err = max(err, maxval(abs(m%x(:, m%conn(k, e)) - f%x(:, f%conn(k, p)))))
    end do
  end do
  call check_small(err, 0.0_dp, 'element p of the file has the same corners, in the same order')
  k = 0
  do p = 1, f%nelem
    if (m%elem_line(file_item(m, p, element=.true.)) /= f%elem_line(p)) k = k + 1
  end do
  call check(k == 0, 'element p of the file keeps its source line')
  err = 0
  do k = 1, nx
    err = max(err, maxval(abs(m%x(:, m%bnd(1)%seg(:, k)) - f%x(:, f%bnd(1)%seg(:, k)))))
  end do
  call check_small(err, 0.0_dp, 'boundary edges: the same segments, in the same order')
  call check(all(m%x(:, m%bnd(2)%points(1)) == f%x(:, f%bnd(2)%points(1))), 'point set: the same point')
  call check(size(m%reg(1)%elems) == size(f%reg(1)%elems), 'region: as many elements')
  call check(all(m%reg(1)%elems(2:) > m%reg(1)%elems(:size(m%reg(1)%elems) - 1)), 'region: ascending')
  a = 0
  do k = 1, size(m%reg(1)%elems)
    if (mod(file_elem_inverse(m%reg(1)%elems(k)) - 1, 3) /= 0) a = a + 1
  end do
  call check(a == 0, 'region: the same elements')

  ! locality: an element's nodes are close in number (a shuffled file puts
  ! them a third of the mesh apart on average)
  r = spread_ratio(f)
  call check(r > 0.2_dp, 'the shuffled file is not local (mean node spread / nnode > 0.2)')
  r = spread_ratio(m)
  call check(r < 0.05_dp, 'renumbered: mean node spread within an element below 5% of the nodes')

  ! the Hilbert curve: on a 2^b x 2^b grid the indices are 0 .. 4^b - 1, each
  ! once, and consecutive indices are cells side by side
  call check(hilbert_walk(1) .and. hilbert_walk(4) .and. hilbert_walk(7), &
             'Hilbert index: a walk through every cell, one step to a side neighbour at a time')

  deallocate(nperm, eperm, seen)
  call finish_tests()

contains

  integer function gid(i, j)
    integer, intent(in) :: i, j
    gid = j * (nx + 1) + i + 1
  end function gid

  !> A permutation of 1..n (Fisher-Yates with the MINSTD generator, seed s).
  subroutine shuffle(n, s, q)
    integer, intent(in) :: n, s
    integer, allocatable, intent(out) :: q(:)
    integer :: i, j, t
    integer(8) :: state
    allocate(q(n))
    do i = 1, n
      q(i) = i
    end do
    state = s
    do i = n, 2, -1
      state = mod(state * 48271_8, 2147483647_8)          ! MINSTD: no overflow in 64 bits
      j = 1 + int(mod(state, int(i, 8)))
      t = q(i); q(i) = q(j); q(j) = t
    end do
  end subroutine shuffle

  !> q holds each of 1 .. size(q) once.
  logical function is_permutation(q)
    integer, intent(in) :: q(:)
    integer, allocatable :: count(:)
    integer :: i
    allocate(count(size(q)), source=0)
    do i = 1, size(q)
      if (q(i) >= 1 .and. q(i) <= size(q)) count(q(i)) = count(q(i)) + 1
    end do
    is_permutation = all(count == 1)
  end function is_permutation

  !> The file's number of element e of m.
  integer function file_elem_inverse(e)
    integer, intent(in) :: e
    integer :: p
    file_elem_inverse = 0
    do p = 1, m%nelem
      if (file_item(m, p, element=.true.) == e) then
        file_elem_inverse = p
        return
      end if
    end do
  end function file_elem_inverse

  !> Every cell of the 2^b grid has its own index in 0 .. 4^b - 1, and the
  !> cells of indices d and d + 1 share a side.
  logical function hilbert_walk(b) result(ok)
    integer, intent(in) :: b
    integer :: x, y, n
    integer, allocatable :: cx(:), cy(:)
    integer(i8) :: d
    n = 2**b
    allocate(cx(0:n * n - 1), cy(0:n * n - 1), source=-1)
    ok = .true.
    do x = 0, n - 1
      do y = 0, n - 1
        d = hilbert_index(b, x, y)
        if (d < 0 .or. d >= int(n, i8)**2) then
          ok = .false.
          return
        end if
        if (cx(d) >= 0) ok = .false.
        cx(d) = x
        cy(d) = y
      end do
    end do
    do d = 1, int(n, i8)**2 - 1
      if (abs(cx(d) - cx(d - 1)) + abs(cy(d) - cy(d - 1)) /= 1) ok = .false.
    end do
  end function hilbert_walk

  !> Mean over elements of (largest - smallest node number), over nnode.
  real(dp) function spread_ratio(g)
    type(mesh_t), intent(in) :: g
    integer :: e
    spread_ratio = 0
    do e = 1, g%nelem
      spread_ratio = spread_ratio + (maxval(g%conn(1:3, e)) - minval(g%conn(1:3, e)))
    end do
    spread_ratio = spread_ratio / g%nelem / g%nnode
  end function spread_ratio

end program test_mesh_order
