!> strings: real_to_str against texts written out by hand from the numbers'
!> decimal expansions (so not by the edit descriptor under test), and its
!> read-back to within half a unit of the last digit kept.
program test_strings
  use kinds, only: dp
  use strings, only: real_to_str, int_to_str, printable
  use testing, only: check, finish_tests
  implicit none
  real(dp) :: x, back
  character(len=40) :: text
  integer :: d, ios
  logical :: ok

  ! the default, 4 significant digits, the exponent in two digits or three
  call check(real_to_str(1.0e-5_dp) == '1.000E-05', 'real_to_str: 1e-5')
  call check(real_to_str(-2.5_dp) == '-2.500E+00', 'real_to_str: -2.5')
  call check(real_to_str(0.0_dp) == '0.000E+00', 'real_to_str: 0')
  call check(real_to_str(123456.0_dp) == '1.235E+05', 'real_to_str: rounds to 4 digits')
  call check(real_to_str(1.0e-300_dp) == '1.000E-300', 'real_to_str: 3-digit exponent')
  call check(real_to_str(-6.02214076e23_dp) == '-6.022E+23', 'real_to_str: -6.02214076e23')

  ! digits: as many significant digits, clamped to 2..17
  call check(real_to_str(4.0_dp, 6) == '4.00000E+00', 'real_to_str: 4 to 6 digits')
  call check(real_to_str(1234.5678_dp, 6) == '1.23457E+03', 'real_to_str: 1234.5678 to 6 digits')
  call check(real_to_str(1.0e-5_dp, 4) == real_to_str(1.0e-5_dp), 'real_to_str: digits = 4 is the default')
  call check(real_to_str(0.126_dp, 1) == '1.3E-01', &
             'real_to_str: digits below 2 clamped to 2')
  call check(real_to_str(0.1_dp, 40) == '1.0000000000000001E-01', 'real_to_str: digits above 17 clamped to 17')
  call check(real_to_str(-1.0e-300_dp, 6) == '-1.00000E-300', 'real_to_str: 6 digits, 3-digit exponent')

  ! read back: within half a unit of the last digit kept, for each digits
  ok = .true.
  x = -3.14159265358979_dp * 1.0e-7_dp
  do d = 2, 17
    text = real_to_str(x, d)
    read(text, *, iostat=ios) back
    ok = ok .and. ios == 0 .and. abs(back - x) <= 0.5_dp * 10.0_dp**(1 - d) * abs(x) * (1.0_dp + 1.0e-12_dp)
  end do
  call check(ok, 'real_to_str: read back within half a unit of the last digit, digits 2 to 17')

  call check(int_to_str(-42) == '-42', 'int_to_str: -42')
  call check(printable('a' // achar(9) // 'b' // achar(127)) == 'a?b?', 'printable: tab and DEL')

  call finish_tests()
end program test_strings
