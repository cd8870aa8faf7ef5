!> testing: checks for the unit-test programs.  Each check prints one line
!> `PASS name` or `FAIL name: detail`; finish_tests exits 1 when any failed.
!> tests/run-tests counts the lines.
!>
!> Each check's verdict is a pure function (is_small, is_close) that the
!> check prints, so test_testing can show that a check fails where it must.
!>
!> Tolerances are stated in units of the round-off, as LAPACK's tests do:
!> tol_round(n, scale) = n eps scale, n the number of roundings the computed
!> value may gather (a small count, a size, or a condition estimate times
!> one) and scale the size of the data it is measured against (a norm, a
!> largest entry; 1 when the checked value is already relative).
module testing
  use kinds, only: dp, i8
  use, intrinsic :: iso_fortran_env, only: output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  implicit none
  private
  public :: check, check_close, check_small, finish_tests
  public :: is_small, is_close, tol_round, unit_roundoff
  public :: urand, random_spd, random_pair, dense_symmetric

  !> eps, the distance from 1 to the next larger real(dp): 2^-52
  real(dp), parameter :: unit_roundoff = epsilon(1.0_dp)

  integer, save :: nfail = 0
contains

  subroutine check(cond, name)
    logical, intent(in) :: cond
    character(len=*), intent(in) :: name
    if (cond) then
      write(output_unit, '(a)') 'PASS ' // name
    else
      write(output_unit, '(a)') 'FAIL ' // name
      nfail = nfail + 1
    end if
  end subroutine check

  !> n eps scale: a tolerance of n roundings on a quantity of size scale
  !> (scale defaults to 1, for a value that is already relative).
  !>   n     (in) roundings the value may gather, >= 1 (a count, a size, or a
  !>              condition estimate times one)
  !>   scale (in, optional) the size it is measured against, > 0
  pure real(dp) function tol_round(n, scale) result(tol)
    integer, intent(in) :: n
    real(dp), intent(in), optional :: scale
    tol = n * unit_roundoff
    if (present(scale)) tol = tol * scale
  end function tol_round

  !> The verdict of check_close: |a - b| <= rtol max(|b|, floor), a a number.
  pure logical function is_close(a, b, rtol, floor) result(ok)
    real(dp), intent(in) :: a, b, rtol
    real(dp), intent(in), optional :: floor
    real(dp) :: scale
    ok = .false.
    if (ieee_is_nan(a) .or. ieee_is_nan(b)) return
    scale = abs(b)
    if (present(floor)) scale = max(scale, floor)
    ok = abs(a - b) <= rtol * scale
  end function is_close

  !> The verdict of check_small: |a| <= tol, a a number.  |a|, not a: an
  !> error measure that comes out far below zero (a signed difference, a
  !> value too low) is as wrong as one far above.
  pure logical function is_small(a, tol) result(ok)
    real(dp), intent(in) :: a, tol
    ok = .false.
    if (ieee_is_nan(a)) return
    ok = abs(a) <= tol
  end function is_small

  !> PASS when |a - b| <= rtol * max(|b|, floor) (no floor: |b|).
  subroutine check_close(a, b, rtol, name, floor)
    real(dp), intent(in) :: a, b, rtol
    character(len=*), intent(in) :: name
    real(dp), intent(in), optional :: floor
    character(len=120) :: detail
    if (is_close(a, b, rtol, floor)) then
      write(output_unit, '(a)') 'PASS ' // name
    else
      write(detail, '(a,es12.5,a,es12.5,a,es9.2)') ': got ', a, ' expected ', b, ' rtol ', rtol
      write(output_unit, '(a)') 'FAIL ' // name // trim(detail)
      nfail = nfail + 1
    end if
  end subroutine check_close

  !> PASS when |a| <= tol (a is an error measure, of either sign; NaN fails).
  subroutine check_small(a, tol, name)
    real(dp), intent(in) :: a, tol
    character(len=*), intent(in) :: name
    character(len=80) :: detail
    if (is_small(a, tol)) then
      write(output_unit, '(a)') 'PASS ' // name
    else
      write(detail, '(a,es12.5,a,es9.2)') ': |', a, '| > ', tol
      write(output_unit, '(a)') 'FAIL ' // name // trim(detail)
      nfail = nfail + 1
    end if
  end subroutine check_small

  subroutine finish_tests()
    flush(output_unit)
    if (nfail > 0) error stop 1
  end subroutine finish_tests
  !> The dense symmetric matrix a (n, n) of the upper triangle stored by
  !> compressed columns (colptr (n+1), rowind, val: a csc_t's arrays).
  subroutine dense_symmetric(colptr, rowind, val, a)
    integer, intent(in) :: colptr(:), rowind(:)
    real(dp), intent(in) :: val(:)
    real(dp), allocatable, intent(out) :: a(:,:)
    integer :: n, j, p
    n = size(colptr) - 1
    allocate(a(n, n), source=0.0_dp)
    do j = 1, n
      do p = colptr(j), colptr(j + 1) - 1
        a(rowind(p), j) = val(p)
        a(j, rowind(p)) = val(p)
      end do
    end do
  end subroutine dense_symmetric

  !> Park-Miller minimal standard generator, uniform in (0, 1).
  real(dp) function urand(state)
    integer(i8), intent(inout) :: state
    state = mod(16807_i8 * state, 2147483647_i8)
    urand = real(state, dp) / 2147483647.0_dp
  end function urand

  !> W = A'A / (3n) + 1e-3 I with A (3n x n) uniform in (-1, 1): SPD, well conditioned.
  subroutine random_spd(n, state, w)
    integer, intent(in) :: n
    integer(i8), intent(inout) :: state
    real(dp), allocatable, intent(out) :: w(:, :)
    real(dp), allocatable :: a(:, :)
    integer :: i, j
    allocate(a(3 * n, n))
    do j = 1, n
      do i = 1, 3 * n
        a(i, j) = 2.0_dp * urand(state) - 1.0_dp
      end do
    end do
    w = matmul(transpose(a), a) / real(3 * n, dp)
    do i = 1, n
      w(i, i) = w(i, i) + 1.0e-3_dp
    end do
  end subroutine random_spd

  !> Complementary z0, w0 >= 0: each index is active (z0 > 0), open (w0 > 0), or
  !> with probability pboth both zero (degenerate).
  subroutine random_pair(n, pboth, state, z0, w0)
    integer, intent(in) :: n
    real(dp), intent(in) :: pboth
    integer(i8), intent(inout) :: state
    real(dp), intent(out) :: z0(:), w0(:)
    integer :: i
    real(dp) :: u
    do i = 1, n
      u = urand(state)
      z0(i) = 0.0_dp
      w0(i) = 0.0_dp
      if (u < pboth) cycle
      if (urand(state) < 0.5_dp) then
        z0(i) = 0.1_dp + urand(state)
      else
        w0(i) = 0.1_dp + urand(state)
      end if
    end do
  end subroutine random_pair

end module testing
