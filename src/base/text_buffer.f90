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
!>   open_text(tb, path, err)     create or replace the file
!>   open_memory(tb)              a buffer bound to no file: it grows, and
!>                                tb%buf(1:tb%used) holds the text
!>   put_text(tb, s)              append a string
!>   put_line(tb, s)              append a string and a newline
!>   put_real(tb, x)              append ' [-]d.dddddddddE+eee'
!>   put_int(tb, i)               append ' digits'
!>   put_newline(tb)
!>   close_text(tb, err)          flush and close; err when a write failed
module text_buffer
  use kinds, only: dp, i8
  use errors, only: error_t, set_error, error_input
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  implicit none
  private
  public :: text_buffer_t, open_text, open_memory, put_text, put_line, put_real, put_int, put_newline, close_text

  integer, parameter :: capacity = 262144
  character(len=2), parameter :: digit_pairs(0:99) = [character(len=2) :: &
    '00', '01', '02', '03', '04', '05', '06', '07', '08', '09', '10', '11', '12', '13', '14', '15', '16', '17', &
    '18', '19', '20', '21', '22', '23', '24', '25', '26', '27', '28', '29', '30', '31', '32', '33', '34', '35', &
    '36', '37', '38', '39', '40', '41', '42', '43', '44', '45', '46', '47', '48', '49', '50', '51', '52', '53', &
    '54', '55', '56', '57', '58', '59', '60', '61', '62', '63', '64', '65', '66', '67', '68', '69', '70', '71', &
    '72', '73', '74', '75', '76', '77', '78', '79', '80', '81', '82', '83', '84', '85', '86', '87', '88', '89', &
    '90', '91', '92', '93', '94', '95', '96', '97', '98', '99']
  !> The largest decade a real(dp) holds: 10^308 < huge(1.0_dp) < 10^309.
  integer, parameter :: top_decade = 308
  real(dp), save :: pow10(-350:top_decade)        !< 10.0_dp**s, see fill_pow10
  logical, save :: pow10_ready = .false.

  type :: text_buffer_t
    integer :: unit = 0                            !< stream unit (newunit: negative)
    logical :: opened = .false.                    !< the unit is open
    integer :: used = 0                            !< bytes pending in buf(1:used)
    logical :: ok = .true.                         !< no write has failed
    logical :: memory = .false.                    !< bound to no file (open_memory)
    character(len=:), allocatable :: buf           !< (capacity) pending bytes
  end type text_buffer_t

contains

  !> Bind tb to a new stream file path (replaced when it exists).
  !>   err (out) allocated when the file cannot be opened (tb is then bound to none)
  subroutine open_text(tb, path, err)
    type(text_buffer_t), intent(out) :: tb
    character(len=*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: err
    integer :: ios
    open(newunit=tb%unit, file=path, access='stream', form='unformatted', status='replace', &
         action='write', iostat=ios)
    tb%ok = ios == 0
    tb%opened = tb%ok
    allocate(character(len=capacity) :: tb%buf)
    tb%used = 0
    if (ios /= 0) call set_error(err, path // ': cannot open the file for writing', error_input)
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
  !> The decade e = floor(log10 |x|) comes from the binary exponent
  !> (floor((k - 1) log10 2) = ((k - 1) 78913) >> 18 for |k| < 1200) and one
  !> comparison with a power of ten; the powers of ten are those the run-time
  !> power 10.0_dp**s gives (a table, see fill_pow10), so the digits are the
  !> same as computing them directly.
  subroutine put_real(tb, x)
    type(text_buffer_t), intent(inout) :: tb
    real(dp), intent(in) :: x
    character(len=18) :: s
    integer(i8) :: n, q
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
    if (.not. pow10_ready) call fill_pow10()
    e = shifta((exponent(a) - 1) * 78913, 18)
    if (e < top_decade) then               ! (a < 10^309 always)
      if (a >= pow10(e + 1)) e = e + 1
    end if
    n = scaled_digits(a, e)
    if (n >= 10000000000_i8) then          ! rounding went up a decade
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
    ! n holds 10 digits d0 d1 ... d9: d0 '.' then d1..d9, two at a time
    do k = 8, 2, -2
      q = n / 100_i8
      s(p + 2 + k:p + 3 + k) = digit_pairs(n - 100_i8 * q)
      n = q
    end do
    q = n / 10_i8
    s(p + 3:p + 3) = achar(48 + int(n - 10_i8 * q))
    s(p + 2:p + 2) = '.'
    s(p + 1:p + 1) = achar(48 + int(q))
    s(p + 12:p + 12) = 'E'
    if (e < 0) then
      s(p + 13:p + 13) = '-'
    else
      s(p + 13:p + 13) = '+'
    end if
    k = abs(e)
    s(p + 14:p + 14) = achar(48 + k / 100)
    s(p + 15:p + 16) = digit_pairs(mod(k, 100))
    call append(tb, s(1:p + 16))
  end subroutine put_real

  !> nint(a 10^(9 - e)): the 10 leading digits of a, scaled in at most two
  !> steps so that neither factor overflows.
  integer(i8) function scaled_digits(a, e) result(n)
    real(dp), intent(in) :: a
    integer, intent(in) :: e
    integer :: s
    s = 9 - e
    if (s > 300) then                      ! (the constant 10**300 is the compiler's)
      n = nint((a * 10.0_dp**300) * pow10(s - 300), i8)
    else if (s < -300) then
      n = nint((a * 10.0_dp**(-300)) * pow10(s + 300), i8)
    else
      n = nint(a * pow10(s), i8)
    end if
  end function scaled_digits

  !> pow10(s) = 10.0_dp**s as the run-time integer power computes it (not
  !> the compiler's correctly rounded constants: the digits written stay
  !> those of the direct computation).  Filled once, by the first caller.
  !> The power of a negative exponent is the reciprocal of the positive one,
  !> so 10.0_dp**s is computed only for |s| <= 308: 10^309 overflows (a trap
  !> in the debug build).  The table stops at 10^308, which put_real never
  !> passes; below 10^-308 it holds 10^(s+308) 10^-308, subnormal, then zero.
  subroutine fill_pow10()
    integer :: s
    real(dp) :: ten
    !$omp critical (text_buffer_pow10)
    if (.not. pow10_ready) then
      ten = 10.0_dp
      do s = -top_decade, top_decade
        pow10(s) = ten**s
      end do
      do s = lbound(pow10, 1), -top_decade - 1
        pow10(s) = pow10(s + top_decade) * pow10(-top_decade)
      end do
      pow10_ready = .true.
    end if
    !$omp end critical (text_buffer_pow10)
  end subroutine fill_pow10

  subroutine put_int(tb, i)
    type(text_buffer_t), intent(inout) :: tb
    integer, intent(in) :: i
    character(len=12) :: s
    integer :: k, v, q
    k = 12
    v = abs(i)
    do
      q = v / 10
      s(k:k) = achar(48 + (v - 10 * q))
      v = q
      k = k - 1
      if (v == 0) exit
    end do
    if (i < 0) then
      s(k:k) = '-'
      k = k - 1
    end if
    s(k:k) = ' '
    call append(tb, s(k:12))
  end subroutine put_int

  !> put_text for a short string: one copy when it fits the buffer.
  subroutine append(tb, s)
    type(text_buffer_t), intent(inout) :: tb
    character(len=*), intent(in) :: s
    if (tb%used + len(s) <= len(tb%buf)) then
      tb%buf(tb%used + 1:tb%used + len(s)) = s
      tb%used = tb%used + len(s)
    else
      call put_text(tb, s)
    end if
  end subroutine append

  !> Write what is pending and close the file.
  !>   err (out) allocated when any write or the close failed
  subroutine close_text(tb, err)
    type(text_buffer_t), intent(inout) :: tb
    type(error_t), allocatable, intent(out) :: err
    integer :: ios
    if (.not. tb%memory) call flush_buffer(tb)
    if (tb%opened) then
      close(tb%unit, iostat=ios)
      if (ios /= 0) tb%ok = .false.
    end if
    tb%opened = .false.
    if (.not. tb%ok) call set_error(err, 'cannot write the file (a write or its close failed)', error_input)
  end subroutine close_text

end module text_buffer
