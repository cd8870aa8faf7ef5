!> text_scan: the text layer of the readers (deck_reader, deck_expressions,
!> deck_cases and the MSH readers): character classes, case, the items of a
!> line, and numbers read strictly from their text.
!>
!> Numbers.  An integer is [+-]digits; a real is [+-]digits[.digits] or
!> [+-].digits, then an optional exponent (e|E|d|D)[+-]digits: Fortran and C
!> notation, nothing else (no blanks, no hexadecimal, no NaN or Inf).  The text
!> is checked character by character first, and its decimal magnitude bounded,
!> so that no conversion can overflow.  The value is the double nearest to the
!> text, exactly what the Fortran runtime's internal read gives; the runtime's
!> read is the reference and the fallback.  It is not the only path because
!> it costs about a microsecond a number and a mesh file holds millions of
!> numbers: the texts of up to 18 significant digits and moderate exponents
!> (every number gmsh writes) are rounded once in integer and double
!> arithmetic (Clinger's fast path and two integer variants, decimal_to_real),
!> with bit-identical results; the figure is in doc/performance.md ("Reading
!> the mesh file").
!>
!> Programming interface
!>   scan_integer(s, v)              logical: s is an integer of at most 18
!>                                   significant digits; v (integer(i8)) its value
!>   scan_real(s, v, max_exponent)   status 0 ok, 1 not a number, 2 NaN or Inf,
!>                                   3 magnitude 10**(max_exponent + 1) or more
!>   parse_real(s, x, ok)            the deck's real: at most 400 characters,
!>                                   |x| < 1e308, the sign of a zero kept
!>   line_items(buf, first, last, b, e, n)
!>                                   the blank-separated items of buf(first:last)
!>   parse_integer(s, k, ok)         the deck's integer: at most 9 significant digits
!>   is_blank(c), is_digit(c), is_letter(c), lower(s), upper(s)
!>   is_name(s)                      [A-Za-z0-9_.-]+ (bodies, boundaries, files)
!>   is_identifier(s)                [A-Za-z_][A-Za-z0-9_]*, at most 64 (.geo variables)
!>   is_printable(s), ends_with_ci(s, suffix)
!>   type(string_t)                  one string of its own length (%s), for
!>                                   arrays of strings: gfortran 12 does not copy
!>                                   arrays of deferred-length strings safely
module text_scan
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp, i8
  implicit none
  private
  public :: scan_integer, scan_real, parse_real, line_items
  public :: is_blank, is_digit, is_letter, lower, upper
  public :: parse_integer, is_name, is_identifier, is_printable, ends_with_ci
  public :: string_t

  !> One string of its own length; an array of them is a list of strings.
  type :: string_t
    character(len=:), allocatable :: s
  end type string_t

  integer, parameter :: max_deck_number_length = 400   !< longest number of a deck value
  integer, parameter :: max_deck_exponent = 307        !< deck values below 1e308 in magnitude

contains

  ! ---------------------------------------------------------------------------
  ! Numbers
  ! ---------------------------------------------------------------------------

  !> Strict decimal integer: optional sign, then digits only; .false. when not
  !> an integer or beyond 18 significant digits.
  logical function scan_integer(s, v) result(ok)
    character(len=*), intent(in) :: s
    integer(i8), intent(out) :: v
    integer :: p, ndig
    logical :: negative
    v = 0
    ok = .false.
    p = 1
    negative = .false.
    if (len(s) == 0) return
    if (s(1:1) == '+' .or. s(1:1) == '-') then
      negative = s(1:1) == '-'
      p = 2
    end if
    if (p > len(s)) return
    ndig = 0
    do while (p <= len(s))
      if (.not. is_digit(s(p:p))) return
      if (ndig > 0 .or. s(p:p) /= '0') ndig = ndig + 1
      if (ndig > 18) return
      v = 10 * v + (iachar(s(p:p)) - iachar('0'))
      p = p + 1
    end do
    if (negative) v = -v
    ok = .true.
  end function scan_integer

  !> Real number in Fortran or C notation ([+-]digits[.digits][(e|d)[+-]digits],
  !> or [+-].digits[...]).  The text is checked and its decimal magnitude
  !> computed before any conversion, so that the conversion cannot overflow.
  !> The value is the double nearest to the text (ties to even), as the
  !> internal read gives it: from the first 18 significant digits w and the
  !> decimal exponent e, value = w 10**e, by decimal_to_real when no nonzero
  !> digit was dropped and w 10**e can be rounded exactly in 64-bit integer and
  !> double arithmetic (the common case), else by the internal read.  A zero
  !> is +0 whatever its sign.
  !>   s            (in)  the text, nothing else (no blanks)
  !>   v            (out) the value when status = 0, else 0
  !>   max_exponent (in)  magnitudes of 10**(max_exponent + 1) and more are refused
  !>                      (at most 307: the conversion must not overflow)
  !>   returns 0 ok, 1 not a number, 2 NaN or Inf, 3 magnitude 10**(max_exponent + 1) or more
  integer function scan_real(s, v, max_exponent) result(status)
    character(len=*), intent(in) :: s
    real(dp), intent(out) :: v
    integer, intent(in) :: max_exponent
    integer, parameter :: max_significand_digits = 18   !< w < 10**18 < 2**63
    integer :: p, n, nint, nfrac, first_nonzero, mag, ios, exponent, nexp_digits, digit, nsig, shift
    integer(i8) :: w
    logical :: nonzero, negative_exponent, exact, done
    character :: c

    v = 0.0_dp
    status = 1
    n = len(s)
    if (n == 0) return
    p = 1
    if (s(1:1) == '+' .or. s(1:1) == '-') p = 2
    if (p <= n) then
      if (.not. is_digit(s(p:p)) .and. s(p:p) /= '.') then
        if (same_lower_text(s(p:), 'nan') .or. same_lower_text(s(p:), 'inf') .or. &
            same_lower_text(s(p:), 'infinity') .or. same_lower_text(s(p:min(n, p + 3)), 'nan(')) status = 2
        return
      end if
    end if
    ! digits [. digits]; the digits read are w 10**shift (exactly, while exact)
    nint = 0
    nfrac = 0
    nonzero = .false.
    first_nonzero = 0
    mag = 0
    w = 0
    nsig = 0
    shift = 0
    exact = .true.
    do while (p <= n)
      c = s(p:p)
      if (.not. is_digit(c)) exit
      digit = iachar(c) - iachar('0')
      if (digit /= 0 .and. .not. nonzero) then
        nonzero = .true.
        first_nonzero = nint + 1
      end if
      nint = nint + 1
      if (nonzero) then
        if (nsig < max_significand_digits) then
          w = 10 * w + digit
          nsig = nsig + 1
        else
          shift = shift + 1
          if (digit /= 0) exact = .false.
        end if
      end if
      p = p + 1
    end do
    if (nonzero) mag = nint - first_nonzero
    if (p <= n) then
      if (s(p:p) == '.') then
        p = p + 1
        do while (p <= n)
          c = s(p:p)
          if (.not. is_digit(c)) exit
          digit = iachar(c) - iachar('0')
          nfrac = nfrac + 1
          if (digit /= 0 .and. .not. nonzero) then
            nonzero = .true.
            mag = -nfrac
          end if
          if (.not. nonzero) then
            shift = shift - 1
          else if (nsig < max_significand_digits) then
            w = 10 * w + digit
            nsig = nsig + 1
            shift = shift - 1
          else if (digit /= 0) then
            exact = .false.
          end if
          p = p + 1
        end do
      end if
    end if
    if (nint + nfrac == 0) return
    ! [(e|d) [+-] digits]
    exponent = 0
    if (p <= n) then
      c = s(p:p)
      if (c /= 'e' .and. c /= 'E' .and. c /= 'd' .and. c /= 'D') return
      p = p + 1
      negative_exponent = .false.
      if (p <= n) then
        if (s(p:p) == '+' .or. s(p:p) == '-') then
          negative_exponent = s(p:p) == '-'
          p = p + 1
        end if
      end if
      if (p > n) return
      nexp_digits = 0
      do while (p <= n)
        if (.not. is_digit(s(p:p))) return
        if (nexp_digits > 0 .or. s(p:p) /= '0') nexp_digits = nexp_digits + 1
        if (nexp_digits <= 6) exponent = 10 * exponent + (iachar(s(p:p)) - iachar('0'))
        p = p + 1
      end do
      if (nexp_digits > 6) exponent = 9999999
      if (negative_exponent) exponent = -exponent
    end if
    if (.not. nonzero) then
      status = 0
      return
    end if
    if (mag + exponent > max_exponent) then
      status = 3
      return
    end if
    if (mag + exponent < -325) then                ! below 1e-324: the nearest double is 0
      status = 0
      return
    end if
    status = 0
    if (exact) then
      call decimal_to_real(w, shift + exponent, v, done)
      if (done) then
        if (s(1:1) == '-') v = -v
        return
      end if
    end if
    read(s, *, iostat=ios) v
    if (ios /= 0) then
      v = 0.0_dp
      status = 1
      return
    end if
    if (.not. ieee_is_finite(v)) then
      v = 0.0_dp
      status = 2
    end if
  end function scan_real

  !> A deck's real: scan_real's text of at most 400 characters and magnitude
  !> below 1e308; "-0" is -0 as the internal read gives it.
  !>   str (in)  the text
  !>   x   (out) the value when ok, else 0
  !>   ok  (out) str is such a number
  subroutine parse_real(str, x, ok)
    character(len=*), intent(in) :: str
    real(dp), intent(out) :: x
    logical, intent(out) :: ok
    x = 0.0_dp
    ok = len(str) <= max_deck_number_length
    if (.not. ok) return
    ok = scan_real(str, x, max_deck_exponent) == 0
    if (ok .and. x == 0.0_dp .and. str(1:1) == '-') x = -0.0_dp
  end subroutine parse_real

  !> v = w 10**e rounded to the nearest double, ties to even, when one exact
  !> rounding does it (Clinger's fast path and two integer variants of it):
  !>   - w <= 2**53 and |e| <= 22: w and 10**|e| are doubles, so one IEEE
  !>     product or quotient is the rounded value;
  !>   - 0 <= e <= 27 and w 5**e < 2**63: w 10**e = (w 5**e) 2**e, rounded once
  !>     in the conversion of the integer w 5**e;
  !>   - -22 <= e < 0: w 10**e = (w / 5**(-e)) 2**e, the quotient rounded by
  !>     rounded_quotient.
  !> Scaling by a power of 2 is exact here (no overflow, no subnormal).
  !>   w    (in)  the decimal significand, 1 <= w < 10**18
  !>   e    (in)  the decimal exponent, |e| < 1000
  !>   v    (out) w 10**e rounded, when done
  !>   done (out) .false. when none of the cases applies (v is then 0)
  pure subroutine decimal_to_real(w, e, v, done)
    integer(i8), intent(in) :: w
    integer, intent(in) :: e
    real(dp), intent(out) :: v
    logical, intent(out) :: done
    integer :: k
    integer(i8), parameter :: two_53 = 2_i8**53
    real(dp), parameter :: power_of_ten(0:22) = [1.0e0_dp, 1.0e1_dp, 1.0e2_dp, 1.0e3_dp, 1.0e4_dp, 1.0e5_dp, &
      1.0e6_dp, 1.0e7_dp, 1.0e8_dp, 1.0e9_dp, 1.0e10_dp, 1.0e11_dp, 1.0e12_dp, 1.0e13_dp, 1.0e14_dp, 1.0e15_dp, &
      1.0e16_dp, 1.0e17_dp, 1.0e18_dp, 1.0e19_dp, 1.0e20_dp, 1.0e21_dp, 1.0e22_dp]
    integer(i8), parameter :: power_of_five(0:27) = [(5_i8**k, k = 0, 27)]

    v = 0.0_dp
    done = .true.
    if (w <= two_53 .and. abs(e) <= 22) then
      if (e >= 0) then
        v = real(w, dp) * power_of_ten(e)
      else
        v = real(w, dp) / power_of_ten(-e)
      end if
    else if (e >= 0 .and. e <= 27) then
      done = w <= huge(w) / power_of_five(e)
      if (done) v = scale(real(w * power_of_five(e), dp), e)
    else if (e < 0 .and. e >= -22) then
      v = scale(rounded_quotient(w, power_of_five(-e)), e)
    else
      done = .false.
    end if
  end subroutine decimal_to_real

  !> The double nearest to w / q, ties to even, by long division: the quotient
  !> is developed to 55 bits (53 of the significand, a round bit and one more)
  !> and a sticky bit for the rest.
  !>   w (in) 1 <= w < 2**62;  q (in) 1 <= q < 2**52
  pure real(dp) function rounded_quotient(w, q) result(v)
    integer(i8), intent(in) :: w, q
    integer(i8) :: a, r, low_bits
    integer :: nbit, m, e2
    logical :: sticky, up

    a = w / q                                     ! w / q = (a + r / q) 2**e2
    r = w - a * q
    e2 = 0
    sticky = .false.
    nbit = int(bit_size(a)) - leadz(a)
    if (nbit > 55) then
      m = nbit - 55
      sticky = ibits(a, 0, m) /= 0
      a = shiftr(a, m)
      e2 = m
      nbit = 55
    end if
    do while (nbit < 55)
      m = min(55 - nbit, 10)                      ! r 2**m < 2**62
      r = shiftl(r, m)
      a = shiftl(a, m) + r / q
      r = r - (r / q) * q
      e2 = e2 - m
      nbit = int(bit_size(a)) - leadz(a)
    end do
    sticky = sticky .or. r /= 0
    low_bits = iand(a, 3_i8)
    up = low_bits == 3 .or. (low_bits == 2 .and. (sticky .or. btest(a, 2)))
    a = shiftr(a, 2)
    if (up) a = a + 1
    v = scale(real(a, dp), e2 + 2)
  end function rounded_quotient

  pure logical function is_letter(c)
    character, intent(in) :: c
    is_letter = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z')
  end function is_letter

  !> s with A-Z in lower case.
  pure function lower(s) result(t)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    t = shift_letters(s, 'A', 32)
  end function lower

  !> s with a-z in upper case.
  pure function upper(s) result(t)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    t = shift_letters(s, 'a', -32)
  end function upper

  !> s with the 26 letters from first moved by offset in the code table.
  pure function shift_letters(s, first, offset) result(t)
    character(len=*), intent(in) :: s
    character, intent(in) :: first
    integer, intent(in) :: offset
    character(len=len(s)) :: t
    integer :: i, c
    t = s
    do i = 1, len(t)
      c = iachar(t(i:i)) - iachar(first)
      if (c >= 0 .and. c < 26) t(i:i) = achar(iachar(t(i:i)) + offset)
    end do
  end function shift_letters

  pure logical function is_digit(c)
    character, intent(in) :: c
    is_digit = c >= '0' .and. c <= '9'
  end function is_digit

  !> a == b as Fortran compares strings (the shorter padded with blanks), with
  !> the letters A-Z of a taken in lower case; b is in lower case.
  pure logical function same_lower_text(a, b) result(same)
    character(len=*), intent(in) :: a, b
    character :: x, y
    integer :: i, c
    same = .false.
    do i = 1, max(len(a), len(b))
      x = ' '
      y = ' '
      if (i <= len(a)) x = a(i:i)
      if (i <= len(b)) y = b(i:i)
      c = iachar(x)
      if (c >= iachar('A') .and. c <= iachar('Z')) x = achar(c + 32)
      if (x /= y) return
    end do
    same = .true.
  end function same_lower_text

  ! ---------------------------------------------------------------------------
  ! Items of a line
  ! ---------------------------------------------------------------------------

  !> The items of the text buf(first:last): n items, item k from byte b(k) to
  !> e(k); n = size(b) + 1 when there are more than b holds.
  pure subroutine line_items(buf, first, last, b, e, n)
    character(len=*), intent(in) :: buf
    integer(i8), intent(in) :: first, last
    integer(i8), intent(out) :: b(:), e(:)
    integer, intent(out) :: n
    integer(i8) :: p
    p = first
    n = 0
    do
      do while (p <= last)
        if (.not. is_blank(buf(p:p))) exit
        p = p + 1
      end do
      if (p > last .or. n == size(b)) exit
      n = n + 1
      b(n) = p
      do while (p <= last)
        if (is_blank(buf(p:p))) exit
        p = p + 1
      end do
      e(n) = p - 1
    end do
    if (p <= last) n = n + 1
  end subroutine line_items


  !> c is a space, TAB, LF, VT, FF or CR (on the byte code: a comparison with the
  !> blank ' ' would cost a call to len_trim).
  pure logical function is_blank(c)
    character, intent(in) :: c
    integer :: code
    code = iachar(c)
    is_blank = code == 32 .or. (code >= 9 .and. code <= 13)
  end function is_blank

  !> Read an integer: [sign] digits, at most 9 significant digits.
  subroutine parse_integer(str, k, ok)
    character(len=*), intent(in) :: str
    integer, intent(out) :: k
    logical, intent(out) :: ok
    integer(i8) :: v
    k = 0
    ok = scan_integer(str, v)
    if (ok) ok = abs(v) < 1000000000_i8
    if (ok) k = int(v)
  end subroutine parse_integer

  !> Names: [A-Za-z0-9_.-]+
  pure logical function is_name(s)
    character(len=*), intent(in) :: s
    integer :: i
    is_name = len(s) > 0
    do i = 1, len(s)
      if (.not. (is_digit(s(i:i)) .or. is_letter(s(i:i)) .or. index('_.-', s(i:i)) > 0)) then
        is_name = .false.
        return
      end if
    end do
  end function is_name

  !> .geo variable: [A-Za-z_][A-Za-z0-9_]*, at most 64 characters.
  pure logical function is_identifier(s)
    character(len=*), intent(in) :: s
    integer :: i
    is_identifier = len(s) > 0 .and. len(s) <= 64
    if (.not. is_identifier) return
    is_identifier = is_letter(s(1:1)) .or. s(1:1) == '_'
    do i = 2, len(s)
      if (.not. (is_digit(s(i:i)) .or. is_letter(s(i:i)) .or. s(i:i) == '_')) is_identifier = .false.
    end do
  end function is_identifier

  !> No control characters (bytes >= 128 allowed).
  pure logical function is_printable(s)
    character(len=*), intent(in) :: s
    integer :: i
    is_printable = .true.
    do i = 1, len(s)
      if (iachar(s(i:i)) < 32 .or. iachar(s(i:i)) == 127) is_printable = .false.
    end do
  end function is_printable

  pure logical function ends_with_ci(s, suffix)
    character(len=*), intent(in) :: s, suffix
    ends_with_ci = .false.
    if (len(s) < len(suffix)) return
    ends_with_ci = lower(s(len(s) - len(suffix) + 1:)) == lower(suffix)
  end function ends_with_ci

end module text_scan
