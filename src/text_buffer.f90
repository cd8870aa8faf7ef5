!> text_buffer: fast writing of large text files.  The VTK file of a
!> million-dof run holds ~10^7 numbers; a Fortran edit descriptor costs about
!> 1 us per number, this formatter a small fraction of that.
!>
!> A real is written as a blank, a minus sign when negative, and
!> d.dddddddddE+eee: 10 significant digits, like the es16.9e3 edit
!> descriptor.  The digits come from rounding |x| 10^-e to an integer; the
!> last digit can differ from the correctly rounded one by one unit when the
!> scaling is inexact (|e| > 22).  Non-finite values are written as NaN,
!> Infinity or -Infinity (callers check finiteness first).  Integers are
!> written as a blank and their digits.
!>
!> Programming interface
!>   type(text_buffer_t)          byte buffer bound to a stream file
!>   open_text(tb, path, ok)      create or replace the file
!>   open_memory(tb)              a buffer bound to no file: it grows, and
!>                                tb%buf(1:tb%used) holds the text
!>   put_text(tb, s)              append a string
!>   put_line(tb, s)              append a string and a newline
!>   put_real(tb, x)              append ' [-]d.dddddddddE+eee'
!>   put_int(tb, i)               append ' digits'
!>   put_newline(tb)
!>   close_text(tb, ok)           flush and close; ok = every write succeeded
module text_buffer
  use kinds, only: dp, i8
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  implicit none
  private
  public :: text_buffer_t, open_text, open_memory, put_text, put_line, put_real, put_int, put_newline, close_text

  integer, parameter :: capacity = 1048576

  type :: text_buffer_t
    integer :: unit = 0                            !< stream unit (newunit: negative)
    logical :: opened = .false.                    !< the unit is open
    integer :: used = 0                            !< bytes pending in buf(1:used)
    logical :: ok = .true.                         !< no write has failed
    logical :: memory = .false.                    !< bound to no file (open_memory)
    character(len=:), allocatable :: buf           !< (capacity) pending bytes
  end type text_buffer_t

contains

  subroutine open_text(tb, path, ok)
    type(text_buffer_t), intent(out) :: tb
    character(len=*), intent(in) :: path
    logical, intent(out) :: ok
    integer :: ios
    open(newunit=tb%unit, file=path, access='stream', form='unformatted', status='replace', &
         action='write', iostat=ios)
    ok = ios == 0
    tb%ok = ok
    tb%opened = ok
    allocate(character(len=capacity) :: tb%buf)
    tb%used = 0
  end subroutine open_text

  subroutine open_memory(tb)
    type(text_buffer_t), intent(out) :: tb
    tb%memory = .true.
    allocate(character(len=65536) :: tb%buf)
    tb%used = 0
  end subroutine open_memory

  !> The buffer is full: write it to the file, or, bound to no file, double it.
  subroutine flush_buffer(tb)
    type(text_buffer_t), intent(inout) :: tb
    character(len=:), allocatable :: bigger
    integer :: ios
    if (tb%memory) then
      allocate(character(len=2 * len(tb%buf)) :: bigger)
      bigger(1:tb%used) = tb%buf(1:tb%used)
      call move_alloc(bigger, tb%buf)
      return
    end if
    if (tb%used > 0 .and. tb%opened) then
      write(tb%unit, iostat=ios) tb%buf(1:tb%used)
      if (ios /= 0) tb%ok = .false.
    end if
    tb%used = 0
  end subroutine flush_buffer

  subroutine put_text(tb, s)
    type(text_buffer_t), intent(inout) :: tb
    character(len=*), intent(in) :: s
    integer :: n, k, chunk
    n = len(s)
    k = 0
    do while (k < n)
      if (tb%used == len(tb%buf)) call flush_buffer(tb)
      chunk = min(n - k, len(tb%buf) - tb%used)
      tb%buf(tb%used + 1:tb%used + chunk) = s(k + 1:k + chunk)
      tb%used = tb%used + chunk
      k = k + chunk
    end do
  end subroutine put_text

  subroutine put_newline(tb)
    type(text_buffer_t), intent(inout) :: tb
    call put_text(tb, achar(10))
  end subroutine put_newline

  subroutine put_line(tb, s)
    type(text_buffer_t), intent(inout) :: tb
    character(len=*), intent(in) :: s
    call put_text(tb, s)
    call put_newline(tb)
  end subroutine put_line

  !> Append ' [-]d.dddddddddE+eee'.
  subroutine put_real(tb, x)
    type(text_buffer_t), intent(inout) :: tb
    real(dp), intent(in) :: x
    character(len=18) :: s
    integer(i8) :: n
    integer :: e, k, p
    real(dp) :: a

    if (.not. ieee_is_finite(x)) then
      if (ieee_is_nan(x)) then
        call put_text(tb, ' NaN')
      else if (x > 0.0_dp) then
        call put_text(tb, ' Infinity')
      else
        call put_text(tb, ' -Infinity')
      end if
      return
    end if
    a = abs(x)
    if (a == 0.0_dp) then
      call put_text(tb, ' 0.000000000E+000')
      return
    end if
    e = floor(log10(a))
    n = scaled_digits(a, e)
    if (n >= 10000000000_i8) then          ! log10 or rounding went up a decade
      e = e + 1
      n = scaled_digits(a, e)
    else if (n < 1000000000_i8) then
      e = e - 1
      n = scaled_digits(a, e)
    end if
    p = 1
    s(1:1) = ' '
    if (x < 0.0_dp) then
      p = p + 1
      s(p:p) = '-'
    end if
    ! n holds 10 digits d0 d1 ... d9
    do k = 9, 0, -1
      s(p + 2 + k:p + 2 + k) = achar(48 + int(mod(n, 10_i8)))
      n = n / 10_i8
    end do
    s(p + 1:p + 1) = s(p + 2:p + 2)
    s(p + 2:p + 2) = '.'
    ! mantissa now at s(p+1:p+11): d . ddddddddd
    s(p + 12:p + 12) = 'E'
    if (e < 0) then
      s(p + 13:p + 13) = '-'
    else
      s(p + 13:p + 13) = '+'
    end if
    k = abs(e)
    s(p + 14:p + 14) = achar(48 + k / 100)
    s(p + 15:p + 15) = achar(48 + mod(k / 10, 10))
    s(p + 16:p + 16) = achar(48 + mod(k, 10))
    call put_text(tb, s(1:p + 16))
  end subroutine put_real

  !> nint(a 10^(9 - e)): the 10 leading digits of a, scaled in at most two
  !> steps so that neither factor overflows.
  pure integer(i8) function scaled_digits(a, e) result(n)
    real(dp), intent(in) :: a
    integer, intent(in) :: e
    integer :: s
    s = 9 - e
    if (s > 300) then
      n = nint((a * 10.0_dp**300) * 10.0_dp**(s - 300), i8)
    else if (s < -300) then
      n = nint((a * 10.0_dp**(-300)) * 10.0_dp**(s + 300), i8)
    else
      n = nint(a * 10.0_dp**s, i8)
    end if
  end function scaled_digits

  subroutine put_int(tb, i)
    type(text_buffer_t), intent(inout) :: tb
    integer, intent(in) :: i
    character(len=12) :: s
    integer :: k, v
    k = 12
    v = abs(i)
    do
      s(k:k) = achar(48 + mod(v, 10))
      v = v / 10
      k = k - 1
      if (v == 0) exit
    end do
    if (i < 0) then
      s(k:k) = '-'
      k = k - 1
    end if
    s(k:k) = ' '
    call put_text(tb, s(k:12))
  end subroutine put_int

  subroutine close_text(tb, ok)
    type(text_buffer_t), intent(inout) :: tb
    logical, intent(out) :: ok
    integer :: ios
    if (.not. tb%memory) call flush_buffer(tb)
    ok = tb%ok
    if (tb%opened) then
      close(tb%unit, iostat=ios)
      if (ios /= 0) ok = .false.
    end if
    tb%opened = .false.
  end subroutine close_text

end module text_buffer
