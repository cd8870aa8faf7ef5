!> mesh_rect: the built-in structured mesh of `MESH rect` (DECK.md).
!>
!> nx by ny cells on [x0,x1] x [y0,y1].  Linear elements (tri3, quad4): node
!> (i, j), i = 0..nx, j = 0..ny, has number j (nx+1) + i + 1.  Quadratic ones
!> (tri6, quad8, quad9): the grid is twice as fine, (i, j), i = 0..2nx,
!> j = 0..2ny, number j (2nx+1) + i + 1, the odd rows and columns the mid-side
!> and centre nodes (straight edges, mid-side nodes at the middle; quad8 leaves
!> the centres out, finalize_mesh drops them).  Cells are quadrilaterals
!> (quad4, quad8, quad9) or split into two triangles (tri3, tri6) along the
!> diagonal: `right` from the lower-left to the upper-right corner, `left` from
!> the lower-right to the upper-left, `alt` alternating like a chess board.
!> Boundaries: left, right, bottom, top (edges, ordered along the boundary in
!> the direction of increasing x or y; quadratic meshes give each edge its
!> mid-side node).
!>
!> Programming interface
!>   make_rect_mesh(x0, y0, x1, y1, nx, ny, elem, diag, mesh, err)
!>   write_rect_geo(x0, y0, x1, y1, elem, name, path, err)
!>        the same rectangle as a gmsh .geo (its boundaries Physical Curves of the
!>        same names, its elements of the same kind), for a mesh gmsh makes again
!>        (ADAPT); the element order to ask of gmsh is that of elem
!>
!> The arrays scale with nx*ny (1e8 cells are accepted): an allocation that
!> fails is an out-of-memory error with the mesh's size, not a runtime abort.
module mesh_rect
  use kinds, only: dp, i8
  use mesh, only: mesh_t
  use errors, only: error_t, set_out_of_memory, set_error, error_numerical
  implicit none
  private
  public :: make_rect_mesh, write_rect_geo

contains

  !>   x0, y0, x1, y1 (in) corners, x1 > x0, y1 > y0
  !>   nx, ny  (in) cells per direction, >= 1
  !>   elem    (in) 'tri3', 'quad4', 'tri6', 'quad8' or 'quad9'
  !>   diag    (in) 'right', 'left' or 'alt' (triangles only)
  !>   mesh    (out) the mesh, counter-clockwise elements
  !>   err     (out) allocated when the memory ran out (error_numerical)
  subroutine make_rect_mesh(x0, y0, x1, y1, nx, ny, elem, diag, mesh, err)
    real(dp), intent(in) :: x0, y0, x1, y1
    integer, intent(in) :: nx, ny
    character(len=*), intent(in) :: elem
    character(len=*), intent(in) :: diag
    type(mesh_t), intent(out) :: mesh
    type(error_t), allocatable, intent(out) :: err
    integer :: i, j, e, n1, n2, n3, n4, m1, m2, m3, m4, mc, stat, g, gx, gy, width, b, d, nen, cell(9)
    !> The two triangles of a cell, split(:, t, d): corners then mid-sides as
    !> positions in cell = [n1 n2 n3 n4 m1 m2 m3 m4 mc]; d = 1 the diagonal
    !> n1-n3, d = 2 the diagonal n2-n4; each counter-clockwise.
    integer, parameter :: split(6, 2, 2) = reshape([1, 2, 3, 5, 6, 9,   1, 3, 4, 9, 7, 8, &
                                                    1, 2, 4, 5, 9, 8,   2, 3, 4, 6, 7, 9], [6, 2, 2])
    logical :: rising, quads, quadratic
    integer(i8) :: bytes

    quads = elem(1:1) == 'q'
    quadratic = elem == 'tri6' .or. elem == 'quad8' .or. elem == 'quad9'
    g = merge(2, 1, quadratic)                 ! grid steps per cell
    width = merge(9, 4, quadratic)
    gx = g * nx; gy = g * ny
    mesh%nnode = (gx + 1) * (gy + 1)
    mesh%nelem = merge(nx * ny, 2 * nx * ny, quads)
    ! x(2, nnode) reals, nen and conn(width, nelem) integers, the boundary segments
    bytes = 16_i8 * mesh%nnode + 4_i8 * (width + 1) * mesh%nelem + 24_i8 * (nx + ny)
    allocate(mesh%x(2, mesh%nnode), stat=stat)
    if (stat == 0) allocate(mesh%nen(mesh%nelem), mesh%conn(width, mesh%nelem), stat=stat)
    if (stat /= 0) then
      call set_out_of_memory(err, 'meshing a rectangle of ' // trim(cells()) // ' cells', bytes)
      return
    end if
    do j = 0, gy
      do i = 0, gx
        mesh%x(:, node(i, j)) = [x0 + (x1 - x0) * real(i, dp) / gx, y0 + (y1 - y0) * real(j, dp) / gy]
        ! exact end coordinates, free of round-off
        if (i == gx) mesh%x(1, node(i, j)) = x1
        if (j == gy) mesh%x(2, node(i, j)) = y1
      end do
    end do

    mesh%conn = 0
    e = 0
    do j = 0, gy - g, g
      do i = 0, gx - g, g
        n1 = node(i, j); n2 = node(i + g, j); n3 = node(i + g, j + g); n4 = node(i, j + g)
        m1 = node(i + 1, j); m2 = node(i + g, j + 1); m3 = node(i + 1, j + g); m4 = node(i, j + 1)
        mc = node(i + 1, j + 1)                   ! (the m's and mc: quadratic elements only)
        cell = [n1, n2, n3, n4, m1, m2, m3, m4, mc]
        if (quads) then
          e = e + 1
          select case (elem)
          case ('quad8')
            nen = 8
          case ('quad9')
            nen = 9
          case default
            nen = 4
          end select
          mesh%nen(e) = nen
          mesh%conn(1:nen, e) = cell(1:nen)
          cycle
        end if
        select case (diag)
        case ('left')
          rising = .false.
        case ('alt')
          rising = mod(i / g + j / g, 2) == 0
        case default
          rising = .true.
        end select
        d = merge(1, 2, rising)
        nen = merge(6, 3, quadratic)
        mesh%conn(1:nen, e + 1) = cell(split(1:nen, 1, d))
        mesh%conn(1:nen, e + 2) = cell(split(1:nen, 2, d))
        mesh%nen(e + 1:e + 2) = nen
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
    if (quadratic) then
      do b = 1, 4
        allocate(mesh%bnd(b)%mid(mesh%bnd(b)%nseg))
      end do
    end if
    do j = 0, ny - 1
      mesh%bnd(1)%seg(:, j + 1) = [node(0, g * j), node(0, g * j + g)]
      mesh%bnd(2)%seg(:, j + 1) = [node(gx, g * j), node(gx, g * j + g)]
      if (quadratic) then
        mesh%bnd(1)%mid(j + 1) = node(0, g * j + 1)
        mesh%bnd(2)%mid(j + 1) = node(gx, g * j + 1)
      end if
    end do
    do i = 0, nx - 1
      mesh%bnd(3)%seg(:, i + 1) = [node(g * i, 0), node(g * i + g, 0)]
      mesh%bnd(4)%seg(:, i + 1) = [node(g * i, gy), node(g * i + g, gy)]
      if (quadratic) then
        mesh%bnd(3)%mid(i + 1) = node(g * i + 1, 0)
        mesh%bnd(4)%mid(i + 1) = node(g * i + 1, gy)
      end if
    end do
    allocate(mesh%reg(0))

  contains
    function cells() result(t)
      character(len=40) :: t
      write(t, '(i0,a,i0)') nx, ' x ', ny
    end function cells

    !> Node (ii, jj) of the grid; 0 off the grid (the mid-side names of a
    !> linear cell, never stored)
    pure integer function node(ii, jj)
      integer, intent(in) :: ii, jj
      node = 0
      if (ii <= gx .and. jj <= gy) node = jj * (gx + 1) + ii + 1
    end function node
  end subroutine make_rect_mesh

  !> The rectangle of MESH rect as a .geo: the four sides the Physical Curves
  !> bottom, right, top, left, the surface the Physical Surface NAME;
  !> quadrilaterals recombined from gmsh's triangles (quad4, quad8, quad9),
  !> quad8 without its centre nodes.  Sizes are left to the mesh gmsh is given
  !> (a background mesh).
  !>   x0, y0, x1, y1 (in) corners;  elem (in) as make_rect_mesh's
  !>   name (in) the body (the surface's name);  path (in) the .geo to write
  !>   err  (out) allocated when the file cannot be written
  subroutine write_rect_geo(x0, y0, x1, y1, elem, name, path, err)
    real(dp), intent(in) :: x0, y0, x1, y1
    character(len=*), intent(in) :: elem, name, path
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios
    character(len=*), parameter :: fp = '(a,i0,a,es24.16e3,a,es24.16e3,a)'
    open(newunit=u, file=path, status='replace', action='write', iostat=ios)
    if (ios == 0) write(u, fp, iostat=ios) 'Point(', 1, ') = {', x0, ', ', y0, ', 0};'
    if (ios == 0) write(u, fp, iostat=ios) 'Point(', 2, ') = {', x1, ', ', y0, ', 0};'
    if (ios == 0) write(u, fp, iostat=ios) 'Point(', 3, ') = {', x1, ', ', y1, ', 0};'
    if (ios == 0) write(u, fp, iostat=ios) 'Point(', 4, ') = {', x0, ', ', y1, ', 0};'
    if (ios == 0) write(u, '(a)', iostat=ios) 'Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};'
    if (ios == 0) write(u, '(a)', iostat=ios) 'Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};'
    if (ios == 0) write(u, '(a)', iostat=ios) 'Physical Curve("bottom") = {1}; Physical Curve("right") = {2};'
    if (ios == 0) write(u, '(a)', iostat=ios) 'Physical Curve("top") = {3}; Physical Curve("left") = {4};'
    if (ios == 0) write(u, '(a)', iostat=ios) 'Physical Surface("' // name // '") = {1};'
    if (elem(1:min(4, len(elem))) == 'quad') then
      ! gmsh's default algorithm: 4.8's Frontal-Delaunay for quads (Algorithm 8) crashes on a background mesh
      if (ios == 0) write(u, '(a)', iostat=ios) 'Recombine Surface{1};'
    end if
    if (elem == 'quad8' .and. ios == 0) write(u, '(a)', iostat=ios) 'Mesh.SecondOrderIncomplete = 1;'
    if (ios == 0) then
      close(u, iostat=ios)
    else
      close(u)
    end if
    if (ios /= 0) call set_error(err, 'cannot write "' // path // '"', error_numerical)
  end subroutine write_rect_geo

end module mesh_rect
