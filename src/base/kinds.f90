!> kinds: the one real kind of contact2d and the integer kinds used with C.
!>
!> Programming interface
!>   dp   real kind of every floating-point quantity (IEEE double)
!>   i8   64-bit integer kind, for counts that may exceed 2**31 (nnz of a factor)
module kinds
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private
  public :: dp, i8

  integer, parameter :: dp = real64
  integer, parameter :: i8 = int64
end module kinds
