!> strings: the one way to write a number or an echoed line as text, for
!> messages, logs and summaries.
!>
!> Programming interface
!>   int_to_str(i)        decimal text of an integer, no blanks
!>   i8_to_str(i)         the same for a 64-bit integer (nnz(L), file tags)
!>   real_to_str(x [, digits])  scientific, 4 significant digits unless digits
!>                        says otherwise, any exponent (1.000E-05, 1.000E-300)
!>   printable(text)      text with control and non-ASCII bytes replaced by '?'
module strings
  use kinds, only: dp, i8
  implicit none
  private
  public :: int_to_str, i8_to_str, real_to_str, printable

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

end module strings
