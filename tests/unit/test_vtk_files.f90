!> vtk_files: the binary layout of the XML VTK file (.vtu), checked against
!> VTK's description of the format (raw appended data, header_type UInt64):
!>   - uncompressed (the writer of a build without zlib): each array is its
!>     byte count as a UInt64, then its values; the displacement array holds
!>     (u_x, u_y, 0) of every point bit for bit, the connectivity the cells'
!>     points, and the array offsets of the XML header follow each other;
!>   - compressed (vtkZLibDataCompressor): each array's header [blocks, block
!>     size, size of the last partial block, compressed sizes] describes the
!>     array's uncompressed byte count (two blocks here, the second partial)
!>     and its compressed bytes end where the next array starts;
!>   - both files list the same arrays, and the compressed one is smaller.
!> A mesh of two bodies (tri3 and quad4, 1,706 points) and results made up
!> from the coordinates: u = (x + 2 y, x y), so the expected bytes are known.
!> Values read back through zlib are checked by tests/effects/paraview and
!> tests/effects/history (ParaView's reader, Python's zlib).
program test_vtk_files
  use kinds, only: dp, i8
  use, intrinsic :: iso_fortran_env, only: int64
  use errors, only: diag_t, error_t
  use mesh, only: finalize_mesh
  use mesh_rect, only: make_rect_mesh
  use body, only: body_t
  use results_writer, only: results_t
  use vtk_files, only: write_vtu
  use compression, only: zlib_available
  use safe_files, only: read_file
  use testing, only: check, finish_tests
  implicit none
  type(body_t) :: bd(2)
  type(diag_t) :: diag
  type(error_t), allocatable :: err
  type(results_t) :: r
  character(len=*), parameter :: plain = 'test_vtk_files_plain.vtu', zipped = 'test_vtk_files_zlib.vtu'
  character(len=:), allocatable :: a, z
  integer :: i, nnode, nelem, status

  call make_rect_mesh(0.0_dp, 0.0_dp, 2.0_dp, 1.0_dp, 40, 20, 'tri3', 'right', bd(1)%mesh, err)
  if (.not. allocated(err)) call make_rect_mesh(0.5_dp, 1.0_dp, 1.5_dp, 1.5_dp, 24, 24, 'quad4', 'right', &
                                                bd(2)%mesh, err)
  call check(.not. allocated(err), 'two meshes (tri3 and quad4)')
  if (allocated(err)) call finish_tests()
  do i = 1, 2
    call finalize_mesh(bd(i)%mesh, 'body', diag)
  end do
  bd(2)%dof0 = 2 * bd(1)%mesh%nnode
  bd(2)%elem0 = bd(1)%mesh%nelem
  nnode = bd(1)%mesh%nnode + bd(2)%mesh%nnode
  nelem = bd(1)%mesh%nelem + bd(2)%mesh%nelem
  call make_results()

  call write_vtu(plain, bd, r, [.true., .true., .true., .true., .true.], err, compress=.false.)
  call check(.not. allocated(err), 'uncompressed .vtu written')
  call read_file(plain, a, status)
  call check(status == 0, 'uncompressed .vtu read back')
  call check_plain(a)
  if (zlib_available()) then
    call write_vtu(zipped, bd, r, [.true., .true., .true., .true., .true.], err)
    call check(.not. allocated(err), 'compressed .vtu written')
    call read_file(zipped, z, status)
    call check(status == 0, 'compressed .vtu read back')
    call check_zipped(a, z)
  else
    write(*, '(a)') 'SKIP compressed .vtu: this build has no zlib'
  end if
  call remove(plain)
  call remove(zipped)
  if (allocated(a)) deallocate(a)       ! the main program's own: freed before finish_tests stops it
  if (allocated(z)) deallocate(z)
  call finish_tests()

contains

  !> u = (x + 2 y, x y); pressures, gaps, stresses from the coordinates too.
  subroutine make_results()
    integer :: b, k, g
    allocate(r%u(2 * nnode), r%node_pressure(nnode), r%node_gap(nnode), r%stress(3, nelem), r%vm(nelem))
    g = 0
    do b = 1, 2
      do k = 1, bd(b)%mesh%nnode
        g = g + 1
        associate(x => bd(b)%mesh%x(1, k), y => bd(b)%mesh%x(2, k))
          r%u(2 * g - 1) = x + 2 * y
          r%u(2 * g) = x * y
          r%node_pressure(g) = merge(x, 0.0_dp, b == 2)
          r%node_gap(g) = 0.0_dp
        end associate
      end do
    end do
    do k = 1, nelem
      r%stress(:, k) = [real(k, dp), -real(k, dp), 0.5_dp * k]
      r%vm(k) = sqrt(real(k, dp))
    end do
  end subroutine make_results

  !> The uncompressed layout, and the displacement and connectivity values.
  subroutine check_plain(f)
    character(len=*), intent(in) :: f
    integer(i8), allocatable :: off(:)
    integer(i8) :: start, n
    real(dp), allocatable :: d(:)
    integer(int64), allocatable :: conn(:)
    integer :: k, e, j
    logical :: ok
    call check(index(f, 'compressor=') == 0, 'uncompressed: no compressor named')
    call check(index(f, 'header_type="UInt64"') > 0, 'uncompressed: header_type UInt64')
    call offsets(f, off, start)
    call check(size(off) == 10, 'uncompressed: 10 arrays (3 point, 3 cell, points, connectivity, offsets, types)')
    if (size(off) /= 10) return
    ok = .true.
    do k = 1, size(off) - 1                        ! each array: its count, then its bytes, then the next
      n = uint64_at(f, start + off(k))
      ok = ok .and. off(k + 1) == off(k) + 8 + n
    end do
    call check(ok, 'uncompressed: each array is its UInt64 byte count and that many bytes')
    n = uint64_at(f, start + off(1))
    call check(n == 24_i8 * nnode, 'uncompressed: displacement holds 3 doubles per point')
    d = transfer(f(start + off(1) + 8:start + off(1) + 7 + n), 1.0_dp, 3 * nnode)
    call check(all(d(1::3) == r%u(1::2)) .and. all(d(2::3) == r%u(2::2)) .and. all(d(3::3) == 0.0_dp), &
               'uncompressed: displacement = (u_x, u_y, 0) of every point, bit for bit')
    n = uint64_at(f, start + off(8))
    conn = transfer(f(start + off(8) + 8:start + off(8) + 7 + n), 1_int64, int(n / 8))
    ok = size(conn) == 3 * bd(1)%mesh%nelem + 4 * bd(2)%mesh%nelem
    if (ok) then
      j = 0
      do e = 1, bd(1)%mesh%nelem
        ok = ok .and. all(conn(j + 1:j + 3) == bd(1)%mesh%conn(1:3, e) - 1)
        j = j + 3
      end do
      do e = 1, bd(2)%mesh%nelem
        ok = ok .and. all(conn(j + 1:j + 4) == bd(2)%mesh%conn(1:4, e) - 1 + bd(1)%mesh%nnode)
        j = j + 4
      end do
    end if
    call check(ok, 'uncompressed: connectivity = the cells'' 0-based points, body 2 after body 1')
    call check(f(len(f) - 10:) == '</VTKFile>' // achar(10), 'uncompressed: the file ends with </VTKFile>')
  end subroutine check_plain

  !> The compressed layout against the uncompressed file's byte counts.
  subroutine check_zipped(f, c)
    character(len=*), intent(in) :: f, c
    integer(i8), allocatable :: offp(:), offz(:)
    integer(i8) :: startp, startz, n, nblock, block, last, sizes, at
    integer :: k, j
    logical :: ok
    call check(index(c, 'compressor="vtkZLibDataCompressor"') > 0, 'compressed: vtkZLibDataCompressor named')
    call offsets(f, offp, startp)
    call offsets(c, offz, startz)
    call check(size(offz) == size(offp), 'compressed: the same arrays as uncompressed')
    if (size(offz) /= size(offp)) return
    ok = .true.
    do k = 1, size(offz) - 1
      n = uint64_at(f, startp + offp(k))               ! the array's uncompressed bytes
      at = startz + offz(k)
      nblock = uint64_at(c, at)
      block = uint64_at(c, at + 8)
      last = uint64_at(c, at + 16)
      ok = ok .and. block == 32768 .and. nblock == (n + block - 1) / block .and. last == mod(n, block)
      sizes = 0
      do j = 1, int(nblock)
        sizes = sizes + uint64_at(c, at + 16 + 8 * j)
      end do
      ok = ok .and. offz(k + 1) == offz(k) + 24 + 8 * nblock + sizes
      if (k == 1) call check(nblock == 2 .and. last == 24_i8 * nnode - 32768, &
                             'compressed: displacement in two blocks, the second partial')
    end do
    call check(ok, 'compressed: each header gives the blocks of the uncompressed size, and the next array follows them')
    call check(len(c) < len(f), 'compressed: the file is smaller than uncompressed')
  end subroutine check_zipped

  !> The offsets of the DataArray elements in file order, and the position
  !> (1-based) of the first byte of the appended data.
  subroutine offsets(f, off, start)
    character(len=*), intent(in) :: f
    integer(i8), allocatable, intent(out) :: off(:)
    integer(i8), intent(out) :: start
    integer :: p, q, head
    integer(i8) :: v
    head = index(f, '<AppendedData')
    start = index(f(head:), '_') + head
    allocate(off(0))
    p = 1
    do
      q = index(f(p:head), 'offset="')
      if (q == 0) exit
      p = p + q - 1 + len('offset="')
      read(f(p:p + index(f(p:), '"') - 2), *) v
      off = [off, v]
    end do
  end subroutine offsets

  !> The little-endian UInt64 at byte position p (1-based).
  integer(i8) function uint64_at(f, p) result(v)
    character(len=*), intent(in) :: f
    integer(i8), intent(in) :: p
    v = transfer(f(p:p + 7), 1_i8)
  end function uint64_at

  subroutine remove(path)
    character(len=*), intent(in) :: path
    integer :: u, ios
    open(newunit=u, file=path, status='old', iostat=ios)
    if (ios == 0) close(u, status='delete')
  end subroutine remove

end program test_vtk_files
