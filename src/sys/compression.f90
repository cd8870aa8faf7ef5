!> compression: zlib's compress2 block by block, for the XML VTK files
!> (src/sys/zlib_blocks.c, include/zlib_blocks.h).  A buffer is cut into
!> blocks of a fixed size, each compressed on its own (VTK's
!> vtkZLibDataCompressor layout), side by side on the run's threads.
!>
!> zlib is optional: a build without its header (Debian's zlib1g-dev) has
!> zlib_available() false, and the callers write their data uncompressed.
!>
!> Programming interface
!>   zlib_available()                          the program was built with zlib
!>   compress_blocks(raw, block, data, sizes, ok)
!>     raw   (in)  the bytes to compress
!>     block (in)  the uncompressed size of a block (>= 1); the last block is shorter
!>     data  (out) the compressed blocks one after the other
!>     sizes (out) (ceil(len(raw) / block)) the compressed size of each block
!>     ok    (out) false when zlib is missing or failed (data, sizes then empty)
module compression
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_int64_t
  use kinds, only: i8
  implicit none
  private
  public :: zlib_available, compress_blocks

  !> zlib's fastest level: on the arrays of a load history's .vtu, mostly
  !> doubles that barely compress, the default level 6 saves 1 % of the bytes
  !> for 6 times the time (doc/outputs.md, "Sizes of a load history")
  integer(c_int), parameter :: level = 1

  interface
    function c2d_zlib_available() bind(c, name='c2d_zlib_available') result(yes)
      import :: c_int
      integer(c_int) :: yes
    end function c2d_zlib_available

    function c2d_zlib_capacity(n, block) bind(c, name='c2d_zlib_capacity') result(bytes)
      import :: c_int64_t
      integer(c_int64_t), value :: n, block
      integer(c_int64_t) :: bytes
    end function c2d_zlib_capacity

    function c2d_zlib_blocks(src, n, block, level, dst, sizes, total) bind(c, name='c2d_zlib_blocks') result(status)
      import :: c_int, c_char, c_int64_t
      character(kind=c_char), intent(in) :: src(*)
      integer(c_int64_t), value :: n, block
      integer(c_int), value :: level
      character(kind=c_char), intent(out) :: dst(*)
      integer(c_int64_t), intent(out) :: sizes(*)
      integer(c_int64_t), intent(out) :: total
      integer(c_int) :: status
    end function c2d_zlib_blocks
  end interface

contains

  logical function zlib_available()
    zlib_available = c2d_zlib_available() == 1
  end function zlib_available

  subroutine compress_blocks(raw, block, data, sizes, ok)
    character(len=*), intent(in) :: raw
    integer(i8), intent(in) :: block
    character(len=:), allocatable, intent(out) :: data
    integer(i8), allocatable, intent(out) :: sizes(:)
    logical, intent(out) :: ok
    character(len=:), allocatable :: buf
    integer(c_int64_t), allocatable :: csizes(:)
    integer(c_int64_t) :: n, total
    integer(i8) :: nblock
    n = len(raw, kind=i8)
    nblock = (n + block - 1) / block
    ok = zlib_available()
    if (.not. ok) then
      allocate(character(len=0) :: data)
      allocate(sizes(0))
      return
    end if
    allocate(character(len=c2d_zlib_capacity(n, int(block, c_int64_t))) :: buf)
    allocate(csizes(max(nblock, 1_i8)))
    ok = c2d_zlib_blocks(raw, n, int(block, c_int64_t), level, buf, csizes, total) == 0
    if (.not. ok) total = 0
    data = buf(1:total)
    sizes = int(csizes(1:merge(nblock, 0_i8, ok)), i8)
  end subroutine compress_blocks

end module compression
