!> text_buffer against the es17.9e3 edit descriptor and integer i0.
program test_text_buffer
  use kinds, only: dp
  use text_buffer, only: text_buffer_t, open_text, open_memory, put_text, put_real, put_int, put_newline, close_text
  use errors, only: error_t
  use testing, only: check, finish_tests
  implicit none
  type(text_buffer_t) :: tb
  real(dp) :: x(12), y
  integer :: i, u, ios, nbad, ints(5), j
  type(error_t), allocatable :: err
  character(len=64) :: line, ref
  character(len=*), parameter :: path = 'test_text_buffer.tmp'

  x = [1.0_dp, -1.0_dp, 0.0_dp, 123456.789_dp, -9.9999999999e-7_dp, 1.0e300_dp, 2.5e-310_dp, &
       -4.2e-120_dp, 9.9999999996_dp, 0.1_dp, 6.02214076e23_dp, -1.0e-5_dp]
  ints = [0, 7, -13, 2147483647, -2147483647]
  call open_text(tb, path, err)
  call check(.not. allocated(err), 'open')
  do i = 1, size(x)
    call put_real(tb, x(i))
    call put_newline(tb)
  end do
  do i = 1, 20000
    call random_number(y)
    y = (y - 0.5_dp) * 10.0_dp**(int(40 * y) - 20)
    call put_real(tb, y)
    call put_newline(tb)
  end do
  do i = 1, size(ints)
    call put_int(tb, ints(i))
    call put_newline(tb)
  end do
  call close_text(tb, err)
  call check(.not. allocated(err), 'close')
  ! read back: every number equals the value written to 10 significant digits
  open(newunit=u, file=path, status='old', action='read')
  nbad = 0
  do i = 1, size(x)
    read(u, '(a)') line
    write(ref, '(es17.9e3)') x(i)
    if (adjustl(line) /= adjustl(ref)) then
      nbad = nbad + 1
      write(*, '(a)') '# ' // trim(line) // ' vs ' // trim(ref)
    end if
  end do
  call check(nbad == 0, 'chosen values equal es17.9e3')
  nbad = 0
  do i = 1, 20000
    read(u, '(a)') line
    read(line, *, iostat=ios) y
    if (ios /= 0) nbad = nbad + 1
  end do
  call check(nbad == 0, 'random values read back')
  do i = 1, size(ints)
    read(u, *) j
    call check(j == ints(i), 'integer read back')
  end do
  close(u, status='delete')
  ! the decade comes from the binary exponent and a table of powers of ten:
  ! at and next to every power of ten (and just below it, where rounding to
  ! 10 digits goes up a decade) the mantissa must be in [1, 10) and the value
  ! right to the 10 digits; exactly the edit descriptor's digits while the
  ! scaling is exact (|exponent| <= 22)
  block
    type(text_buffer_t) :: mem
    real(dp) :: v(4), back, mant
    integer :: k, m, pos, nbad_exact, nbad_form, nbad_value
    nbad_exact = 0; nbad_form = 0; nbad_value = 0
    do k = -307, 307
      v(1) = 10.0_dp**k
      v(2) = nearest(v(1), 1.0_dp)
      v(3) = nearest(v(1), -1.0_dp)
      v(4) = v(1) * (1.0_dp - 4.0e-11_dp)
      do m = 1, 4
        call open_memory(mem)
        call put_real(mem, v(m))
        line = mem%buf(1:mem%used)
        read(line, *, iostat=ios) back
        pos = index(line, 'E')
        read(line(1:pos - 1), *, iostat=ios) mant
        if (ios /= 0 .or. .not. (mant >= 1.0_dp .and. mant < 10.0_dp) .or. line(3:3) /= '.') nbad_form = nbad_form + 1
        if (.not. abs(back - v(m)) <= 1.0e-9_dp * v(m)) nbad_value = nbad_value + 1
        if (abs(k) <= 21) then
          write(ref, '(es17.9e3)') v(m)
          if (adjustl(line) /= adjustl(ref)) then
            nbad_exact = nbad_exact + 1
            write(*, '(a)') '# ' // trim(line) // ' vs ' // trim(ref)
          end if
        end if
      end do
    end do
    call check(nbad_form == 0, 'powers of ten and their neighbours: d.ddddddddd, mantissa in [1, 10)')
    call check(nbad_value == 0, 'powers of ten and their neighbours: the value to 10 digits')
    call check(nbad_exact == 0, 'powers of ten and their neighbours up to 1e21: equal es17.9e3')
  end block
  ! a buffer bound to no file grows and keeps every byte: 20000 lines of
  ! ' 1.000000000E+000' and a newline (18 bytes each) are 360000 bytes
  block
    type(text_buffer_t) :: mem
    character(len=18), parameter :: row = ' 1.000000000E+000' // achar(10)
    call open_memory(mem)
    do i = 1, 20000
      call put_real(mem, 1.0_dp)
      call put_newline(mem)
    end do
    call check(mem%used == 20000 * 18, 'memory buffer: 360000 bytes kept')
    nbad = 0
    do i = 1, 20000
      if (mem%buf(18 * (i - 1) + 1:18 * i) /= row) nbad = nbad + 1
    end do
    call check(nbad == 0, 'memory buffer: every row as written')
    call put_text(mem, 'end')
    call check(mem%buf(mem%used - 2:mem%used) == 'end', 'memory buffer: text appended after growth')
  end block
  call finish_tests()
end program test_text_buffer
