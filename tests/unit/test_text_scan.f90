!> text_scan and sorting, each against an independent reference:
!> - scan_real against the Fortran runtime's internal read (the reference its
!>   header names) on 200,000 texts: random doubles over 600 decades written
!>   with 17, 18, 19 and 25 significant digits (past the fast path's 18), in
!>   E, D and plain notation, and the edges (powers of ten, 2**53 + 1, the
!>   subnormals, ties of the fast path's division); bit-identical values;
!> - what must be refused (status 1, 2 or 3) and what the deck's parse_real
!>   adds (the bound 1e308, the sign of -0);
!> - scan_integer at the 18-digit bound;
!> - sort_columns against the definition (ascending, equal keys in input
!>   order) on random keys with many ties, and pack_text: the packed keys of
!>   random strings order them exactly as Fortran's string comparison does.
program test_text_scan
  use kinds, only: dp, i8
  use text_scan, only: scan_real, scan_integer, parse_real
  use sorting, only: sort_columns, pack_text, text_key_words
  use testing, only: check, finish_tests, urand
  implicit none
  integer(i8) :: state
  integer :: i, k, nbad, ios, status
  real(dp) :: x, y, ref
  character(len=64) :: text
  character(len=*), parameter :: formats(6) = [character(len=12) :: '(es24.16e3)', '(es25.17e3)', &
                                                '(es26.18e3)', '(es33.24e3)', '(d25.17)'  , '(f40.20)']
  logical :: ok

  ! --- scan_real against the internal read
  state = 20261126_i8
  nbad = 0
  do i = 1, 200000
    x = (urand(state) + 0.05_dp) * 10.0_dp**(int(600 * urand(state)) - 300)
    if (urand(state) < 0.5_dp) x = -x
    k = 1 + mod(i, size(formats))
    if (k == 6 .and. (abs(x) > 1.0e15_dp .or. abs(x) < 1.0e-10_dp)) k = 2
    if (k == 5 .and. (abs(x) >= 1.0e98_dp .or. abs(x) < 1.0e-98_dp)) k = 2   ! d25.17 drops the D past 99
    write(text, formats(k)) x
    text = adjustl(text)
    read(text, *, iostat=ios) ref
    status = scan_real(trim(text), y, 307)
    if (ios /= 0 .or. status /= 0 .or. .not. same_bits(y, ref)) then
      nbad = nbad + 1
      if (nbad <= 3) print '(a, i0, 2es26.17)', '# ' // trim(text) // ' status ', status, y, ref
    end if
  end do
  call check(nbad == 0, 'scan_real: 200000 random texts bit-identical to the internal read')
  nbad = 0
  call compare('1e22')
  call compare('1e23')
  call compare('9007199254740993')                   ! 2**53 + 1: a tie, rounds to even
  call compare('9007199254740993e-5')
  call compare('123456789012345678e-22')              ! the integer long division
  call compare('2.2250738585072011e-308')
  call compare('4.9406564584124654e-324')             ! the least subnormal
  call compare('2.4703282292062328e-324')             ! just below its half: 0
  call compare('1.7976931348623157e307')
  call compare('0.000000000000000000000000000001234567890123456789012345')
  call compare('1234567890123456789012345678901234567890')
  call compare('.5')
  call compare('5.')
  call compare('+3.25D-2')
  call check(nbad == 0, 'scan_real: edge texts bit-identical to the internal read')

  ! --- refused texts
  call check(all(statuses(['        ', '.       ', '1e      ', '1.5x    ', '0x10    ', '1       ', &
                           '--1     ', '1e+     '], [0, 0, 0, 0, 0, 1, 0, 0]) == 1), &
             'scan_real: not numbers: status 1')
  call check(all(statuses(['NaN     ', '-inf    ', 'Infinity'], [0, 0, 0]) == 2), 'scan_real: NaN and Inf: status 2')
  ok = all(statuses(['1e100     ', '-1e1000000'], [0, 0]) == 3)
  if (ok) ok = all(statuses(['9.99e99'], [0]) == 0)
  call check(ok, &
             'scan_real: magnitude bound 10**(max_exponent + 1): status 3')
  status = scan_real('1e-1000000', y, 99)
  call check(status == 0 .and. .not. abs(y) > 0.0_dp, 'scan_real: far below the subnormals: 0')
  call parse_real('1e308', y, ok)
  call check(.not. ok, 'parse_real: 1e308 refused (|x| < 1e308 expected)')
  call parse_real('-0.0', y, ok)
  call check(ok .and. .not. abs(y) > 0.0_dp .and. sign(1.0_dp, y) < 0.0_dp, 'parse_real: -0.0 keeps its sign')
  call parse_real(repeat('1', 401), y, ok)
  call check(.not. ok, 'parse_real: a text of 401 characters refused')

  ! --- integers
  call check(all([int_of('999999999999999999'), int_of('-000000000000000000000012')] == &
                 [999999999999999999_i8, -12_i8]), 'scan_integer: 18 significant digits, leading zeros')
  call check(all([int_of('1000000000000000000'), int_of('+'), int_of('1.0'), int_of('')] == -huge(1_i8)), &
             'scan_integer: refused texts')

  call test_sort_columns()
  call test_pack_text()
  call finish_tests()

contains

  logical function same_bits(a, b)
    real(dp), intent(in) :: a, b
    same_bits = transfer(a, 1_i8) == transfer(b, 1_i8)
  end function same_bits

  !> scan_real(t) equals the internal read of t, bit for bit.
  subroutine compare(t)
    character(len=*), intent(in) :: t
    real(dp) :: v, r
    integer :: st, io
    read(t, *, iostat=io) r
    st = scan_real(t, v, 307)
    if (io /= 0 .or. st /= 0 .or. .not. same_bits(v, r)) then
      nbad = nbad + 1
      print '(a, i0, 2es26.17)', '# ' // t // ' status ', st, v, r
    end if
  end subroutine compare

  !> scan_real's status on each text, trimmed and then followed by blanks(k) blanks.
  function statuses(texts, blanks) result(st)
    character(len=*), intent(in) :: texts(:)
    integer, intent(in) :: blanks(:)
    integer :: st(size(texts)), j
    real(dp) :: v
    do j = 1, size(texts)
      st(j) = scan_real(trim(texts(j)) // repeat(' ', blanks(j)), v, 99)
    end do
  end function statuses

  integer(i8) function int_of(t)
    character(len=*), intent(in) :: t
    if (.not. scan_integer(t, int_of)) int_of = -huge(1_i8)
  end function int_of

  !> Random keys of 2 rows with many ties: keys(:, perm) ascending, and
  !> equal keys in input order (stable).
  subroutine test_sort_columns()
    integer, parameter :: n = 5000
    integer(i8) :: keys(2, n)
    integer, allocatable :: perm(:)
    integer :: j, st
    logical :: good
    do j = 1, n
      keys(1, j) = int(7 * urand(state), i8)
      keys(2, j) = int(5 * urand(state), i8) - 2
    end do
    call sort_columns(keys, perm, st)
    good = st == 0 .and. size(perm) == n
    do j = 2, merge(n, 0, good)
      if (keys(1, perm(j - 1)) /= keys(1, perm(j))) then
        good = good .and. keys(1, perm(j - 1)) < keys(1, perm(j))
      else if (keys(2, perm(j - 1)) /= keys(2, perm(j))) then
        good = good .and. keys(2, perm(j - 1)) < keys(2, perm(j))
      else
        good = good .and. perm(j - 1) < perm(j)
      end if
    end do
    call check(good, 'sort_columns: ascending and stable on 5000 keys with ties')
  end subroutine test_sort_columns

  !> pack_text keys compare as the strings do (Fortran: blank padding, byte order).
  subroutine test_pack_text()
    integer, parameter :: n = 400, width = 4
    character(len=20) :: words(n)
    integer(i8) :: keys(width, n)
    integer :: j, m, c, bad
    logical :: less_keys
    character(len=*), parameter :: alphabet = ' abAB_09' // char(9) // char(200)
    do j = 1, n
      words(j) = ''
      do m = 1, 1 + int(12 * urand(state))
        c = 1 + int(len(alphabet) * urand(state))
        words(j)(m:m) = alphabet(c:c)
      end do
      call pack_text(trim(words(j)), keys(:, j))
    end do
    bad = 0
    do j = 1, n - 1
      do m = j + 1, n
        less_keys = any(keys(:, j) /= keys(:, m))
        if (less_keys) less_keys = keys(first_difference(keys, j, m), j) < keys(first_difference(keys, j, m), m)
        if ((words(j) < words(m)) .neqv. less_keys) bad = bad + 1
        if ((words(j) == words(m)) .neqv. all(keys(:, j) == keys(:, m))) bad = bad + 1
      end do
    end do
    call check(bad == 0 .and. text_key_words('12345678') == 2, 'pack_text: keys order 400 random strings as they compare')
  end subroutine test_pack_text

  !> The first row where columns a and b of keys differ (the last when none).
  pure integer function first_difference(keys, a, b) result(r)
    integer(i8), intent(in) :: keys(:,:)
    integer, intent(in) :: a, b
    do r = 1, size(keys, 1) - 1
      if (keys(r, a) /= keys(r, b)) return
    end do
  end function first_difference

end program test_text_scan
