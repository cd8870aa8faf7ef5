! Reallocations on assignment, which gfortran does not check (no stat=, no
! call to the runtime's error routine): the result of malloc or realloc is
! written through as it is.  Built by ./check with src/sys/fortran_oom.c and the
! program's link flags, run under an address-space limit.
!   grow copy N     a(10) assigned b(N): a reallocated to N reals
!   grow fresh N    an unallocated c assigned b(N): a malloc
!   grow string K   s = s // s, K times: a deferred-length string doubled
program grow
  implicit none
  real(8), allocatable :: a(:), b(:), c(:)
  character(len=:), allocatable :: s
  character(len=32) :: mode, arg
  integer :: n, i

  call get_command_argument(1, mode)
  call get_command_argument(2, arg)
  read(arg, *) n
  allocate(a(10), b(n), stat=i)
  if (i /= 0) stop 3
  a = 1
  b = 2
  select case (mode)
  case ('copy')
    a = b
    print '(a, i0, a, f0.1)', 'copied ', size(a), ', last ', a(n)
  case ('fresh')
    c = b
    print '(a, i0, a, f0.1)', 'copied ', size(c), ', last ', c(n)
  case ('string')
    s = 'x'
    do i = 1, n
      s = s // s
    end do
    print '(a, i0, 2a)', 'length ', len(s), ', last ', s(len(s):)
  end select
end program grow
