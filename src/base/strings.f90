!> strings: the one way to write a number or an echoed line as text, for
!> messages, logs and summaries.
!>
!> Programming interface
!>   int_to_str(i)        decimal text of an integer, no blanks
!>   i8_to_str(i)         the same for a 64-bit integer (nnz(L), file tags)
!>   real_to_str(x [, digits])  scientific, 4 significant digits unless digits
!>                        says otherwise, any exponent (1.000E-05, 1.000E-300)
!>   exact_to_str(x)      scientific with 17 significant digits, three-digit
!>                        exponent (es24.16e3): what files that are read back
!>                        carry (the summary, tables, gnuplot's data)
!>   fixed_to_str(x, decimals)  fixed point (f0.d): 73.8 for megabytes
!>   format_number(x)     the shortest decimal that reads back to x (deck values
!>                        echoed: 0.25, 1e-7, 200000)
!>   printable(text)      text with control and non-ASCII bytes replaced by '?'
!>   starts_with(s, prefix), ends_with(s, suffix)   whether s begins / ends with it
module strings
  use kinds, only: dp, i8
  implicit none
  private
  public :: int_to_str, i8_to_str, real_to_str, exact_to_str, fixed_to_str, format_number, printable
  public :: starts_with, ends_with

contains

  !> Replace control and non-ASCII bytes by '?' so an echoed line is printable.
  pure function printable(line) result(s)
    character(len=*), intent(in) :: line
    character(len=len(line)) :: s
    integer :: i, c
    s = line
    do i = 1, len(s)
      c = iachar(s(i:i))
      if (c < 32 .or. c > 126) s(i:i) = '?'
    end do
  end function printable

  !> Decimal text of an integer, no blanks.
  pure function int_to_str(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function int_to_str

  !> Decimal text of a 64-bit integer (counts beyond 2**31: nnz(L), file tags).
  pure function i8_to_str(i) result(s)
    integer(i8), intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function i8_to_str

  !> Short scientific text of a real, for messages: 1.000E-05, -2.500E+300.
  !>   x      (in) the number
  !>   digits (in, optional) significant digits, 2 to 17 (clamped); 4 when
  !>          absent.  More where a message must tell close values apart, such
  !>          as an arc length along a long boundary (mortar_operator).
  function real_to_str(x, digits) result(s)
    real(dp), intent(in) :: x
    integer, intent(in), optional :: digits
    character(len=:), allocatable :: s
    character(len=40) :: buf
    character(len=16) :: form
    integer :: d, e, k
    d = 4
    if (present(digits)) d = max(2, min(17, digits))
    ! room for a 3-digit exponent (es10.3 writes 1e-300 as `1.000-300`), then
    ! the exponent's leading zero dropped down to two digits: 1.000E-05
    write(form, '(a, i0, a, i0, a)') '(es', d + 8, '.', d - 1, 'e3)'
    write(buf, form) x
    s = trim(adjustl(buf))
    e = scan(s, 'E')
    if (e > 0 .and. len(s) >= e + 4) then
      k = e + 2
      if (s(k:k) == '0') s = s(1:k - 1) // s(k + 1:)
    end if
  end function real_to_str

  !> x with 17 significant digits and a three-digit exponent, as the
  !> summary and the tables write every real: read back, it is x exactly.
  function exact_to_str(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    write(buf, '(es24.16e3)') x
    s = trim(adjustl(buf))
  end function exact_to_str

  !> x in fixed point with the given decimals (f0.d), a zero before the point.
  function fixed_to_str(x, decimals) result(s)
    real(dp), intent(in) :: x
    integer, intent(in) :: decimals
    character(len=:), allocatable :: s
    character(len=48) :: buf, form
    write(form, '(a,i0,a)') '(f0.', max(0, decimals), ')'
    write(buf, form) x
    s = trim(adjustl(buf))
    if (s(1:1) == '.') s = '0' // s
    if (len(s) > 1) then
      if (s(1:2) == '-.') s = '-0' // s(2:)
    end if
  end function fixed_to_str

  !> The shortest decimal that reads back to x exactly: integers as integers
  !> (up to 1e15), else up to 17 significant digits, with an exponent outside
  !> 1e-4 <= |x| < 1e15 ('0.25', '1e-07' style: '1e-7', '2.5e+20' as '2.5e20').
  function format_number(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=40) :: buf, fmt
    character(len=:), allocatable :: digits
    integer :: d, e, epos, ios, point
    real(dp) :: y

    if (x == 0.0_dp) then
      s = '0'
      return
    end if
    if (x == aint(x) .and. abs(x) < 1.0e15_dp) then
      write(buf, '(i0)') nint(x, kind=selected_int_kind(18))
      s = trim(buf)
      return
    end if
    ! near huge(x) a shorter form can round up past it: 17 digits only there
    do d = merge(17, 1, abs(x) >= 1.0e308_dp), 17
      write(fmt, '(a,i0,a,i0,a)') '(es', d + 10, '.', d - 1, 'e3)'
      write(buf, fmt) x
      read(buf, *, iostat=ios) y
      if (ios == 0 .and. y == x) exit
    end do
    buf = adjustl(buf)
    epos = index(buf, 'E')
    read(buf(epos + 1:), *) e                       ! x = m.mmm * 10^e
    digits = ''
    do point = 1, epos - 1
      if (index('0123456789', buf(point:point)) > 0) digits = digits // buf(point:point)
    end do
    do while (len(digits) > 1 .and. digits(len(digits):len(digits)) == '0')
      digits = digits(1:len(digits) - 1)
    end do
    s = ''
    if (x < 0.0_dp) s = '-'
    if (e >= -4 .and. e < 15) then
      if (e < 0) then
        s = s // '0.' // repeat('0', -e - 1) // digits
      else if (len(digits) > e + 1) then
        s = s // digits(1:e + 1) // '.' // digits(e + 2:)
      else
        s = s // digits // repeat('0', e + 1 - len(digits))
      end if
    else
      s = s // digits(1:1)
      if (len(digits) > 1) s = s // '.' // digits(2:)
      write(buf, '(i0)') e
      s = s // 'e' // trim(buf)
    end if
  end function format_number

  !> Whether s begins with prefix (case and blanks as they are).
  pure logical function starts_with(s, prefix)
    character(len=*), intent(in) :: s, prefix
    starts_with = len(s) >= len(prefix)
    if (starts_with) starts_with = s(1:len(prefix)) == prefix
  end function starts_with

  !> Whether s ends with suffix (case and blanks as they are).
  pure logical function ends_with(s, suffix)
    character(len=*), intent(in) :: s, suffix
    ends_with = len(s) >= len(suffix)
    if (ends_with) ends_with = s(len(s) - len(suffix) + 1:) == suffix
  end function ends_with

end module strings
