!> mesh_rect: the built-in structured mesh of `MESH rect` (DECK.md).
!>
!> nx by ny cells on [x0,x1] x [y0,y1]; node (i, j), i = 0..nx, j = 0..ny, has
!> number j (nx+1) + i + 1.  Cells are quadrilaterals (elem=quad4) or split into
!> two triangles (elem=tri3) along the diagonal: `right` from the lower-left to
!> the upper-right corner, `left` from the lower-right to the upper-left, `alt`
!> alternating like a chess board.  Boundaries: left, right, bottom, top (edges,
!> ordered along the boundary in the direction of increasing x or y).
!>
!> Programming interface
!>   make_rect_mesh(x0, y0, x1, y1, nx, ny, quads, diag, mesh, err)
!>
!> The arrays scale with nx*ny (1e8 cells are accepted): an allocation that
!> fails is an out-of-memory error with the mesh's size, not a runtime abort.
module mesh_rect
  use kinds, only: dp, i8
  use mesh, only: mesh_t
  use diagnostics, only: error_t, set_out_of_memory
  implicit none
  private
  public :: make_rect_mesh

contains

  !>   x0, y0, x1, y1 (in) corners, x1 > x0, y1 > y0
  !>   nx, ny  (in) cells per direction, >= 1
  !>   quads   (in) .true. quad4 cells, .false. tri3
  !>   diag    (in) 'right', 'left' or 'alt' (tri3 only)
  !>   mesh    (out) the mesh, counter-clockwise elements
  !>   err     (out) allocated when the memory ran out (status 1)
  subroutine make_rect_mesh(x0, y0, x1, y1, nx, ny, quads, diag, mesh, err)
    real(dp), intent(in) :: x0, y0, x1, y1
    integer, intent(in) :: nx, ny
    logical, intent(in) :: quads
    character(len=*), intent(in) :: diag
    type(mesh_t), intent(out) :: mesh
    type(error_t), allocatable, intent(out) :: err
    integer :: i, j, e, n1, n2, n3, n4, stat
    logical :: rising
    integer(i8) :: bytes

    mesh%nnode = (nx + 1) * (ny + 1)
    mesh%nelem = merge(nx * ny, 2 * nx * ny, quads)
    ! x(2, nnode) reals, nen and conn(4, nelem) integers, the boundary segments
    bytes = 16_i8 * mesh%nnode + 20_i8 * mesh%nelem + 16_i8 * (nx + ny)
    allocate(mesh%x(2, mesh%nnode), stat=stat)
    if (stat == 0) allocate(mesh%nen(mesh%nelem), mesh%conn(4, mesh%nelem), stat=stat)
    if (stat /= 0) then
      call set_out_of_memory(err, 'meshing a rectangle of ' // trim(cells()) // ' cells', bytes)
      return
    end if
    do j = 0, ny
      do i = 0, nx
        mesh%x(:, node(i, j)) = [x0 + (x1 - x0) * real(i, dp) / nx, y0 + (y1 - y0) * real(j, dp) / ny]
        ! exact end coordinates, free of round-off
        if (i == nx) mesh%x(1, node(i, j)) = x1
        if (j == ny) mesh%x(2, node(i, j)) = y1
      end do
    end do

    mesh%conn = 0
    e = 0
    do j = 0, ny - 1
      do i = 0, nx - 1
        n1 = node(i, j); n2 = node(i + 1, j); n3 = node(i + 1, j + 1); n4 = node(i, j + 1)
        if (quads) then
          e = e + 1
          mesh%nen(e) = 4
          mesh%conn(:, e) = [n1, n2, n3, n4]
          cycle
        end if
        select case (diag)
        case ('left')
          rising = .false.
        case ('alt')
          rising = mod(i + j, 2) == 0
        case default
          rising = .true.
        end select
        if (rising) then            ! diagonal n1-n3
          mesh%conn(1:3, e + 1) = [n1, n2, n3]
          mesh%conn(1:3, e + 2) = [n1, n3, n4]
        else                        ! diagonal n2-n4
          mesh%conn(1:3, e + 1) = [n1, n2, n4]
          mesh%conn(1:3, e + 2) = [n2, n3, n4]
        end if
        mesh%nen(e + 1:e + 2) = 3
        e = e + 2
      end do
    end do

    allocate(mesh%bnd(4))
    mesh%bnd(1)%name = 'left'
    mesh%bnd(2)%name = 'right'
    mesh%bnd(3)%name = 'bottom'
    mesh%bnd(4)%name = 'top'
    mesh%bnd(1)%nseg = ny; mesh%bnd(2)%nseg = ny
    mesh%bnd(3)%nseg = nx; mesh%bnd(4)%nseg = nx
    allocate(mesh%bnd(1)%seg(2, ny), mesh%bnd(2)%seg(2, ny), mesh%bnd(3)%seg(2, nx), mesh%bnd(4)%seg(2, nx))
    allocate(mesh%bnd(1)%points(0), mesh%bnd(2)%points(0), mesh%bnd(3)%points(0), mesh%bnd(4)%points(0))
    do j = 0, ny - 1
      mesh%bnd(1)%seg(:, j + 1) = [node(0, j), node(0, j + 1)]
      mesh%bnd(2)%seg(:, j + 1) = [node(nx, j), node(nx, j + 1)]
    end do
    do i = 0, nx - 1
      mesh%bnd(3)%seg(:, i + 1) = [node(i, 0), node(i + 1, 0)]
      mesh%bnd(4)%seg(:, i + 1) = [node(i, ny), node(i + 1, ny)]
    end do
    allocate(mesh%reg(0))

  contains
    function cells() result(t)
      character(len=40) :: t
      write(t, '(i0,a,i0)') nx, ' x ', ny
    end function cells

    pure integer function node(ii, jj)
      integer, intent(in) :: ii, jj
      node = jj * (nx + 1) + ii + 1
    end function node
  end subroutine make_rect_mesh

end module mesh_rect
