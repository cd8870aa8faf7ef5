!> sorting: sort_by_key, sort_integers and sort_by_counts against small cases
!> sorted by hand and, on random input, against the definition of the order:
!> the result is a permutation of the input (every index once, the same
!> multiset of values) and consecutive entries are in order (keys ascending,
!> ties by increasing index, or in input order for the stable counting sort).
program test_sorting
  use kinds, only: dp, i8
  use sorting, only: sort_by_key, sort_integers, sort_by_counts, sort_small
  use testing, only: check, finish_tests, urand
  implicit none
  integer, parameter :: n = 2000
  integer :: idx(n), perm(n), ikey(n), a(n), b(n), i, m
  integer :: empty(0), hand(5), two(2), four(4)
  real(dp) :: key(n)
  integer(i8) :: state
  logical :: ok

  ! by hand: keys 3 1 2 1 3 -> the 1s (2, 4), the 2 (3), the 3s (1, 5)
  hand = [1, 2, 3, 4, 5]
  call sort_by_key(hand, [3.0_dp, 1.0_dp, 2.0_dp, 1.0_dp, 3.0_dp])
  call check(all(hand == [2, 4, 3, 1, 5]), 'sort_by_key: 3 1 2 1 3 by hand, ties by index')
  hand = [5, 4, 3, 2, 1]                  ! the ties come out by index whatever the order in
  call sort_by_key(hand, [3.0_dp, 1.0_dp, 2.0_dp, 1.0_dp, 3.0_dp])
  call check(all(hand == [2, 4, 3, 1, 5]), 'sort_by_key: the same from reversed indices')
  two = [2, 4]                            ! a subset of the indices
  call sort_by_key(two, [0.0_dp, -1.0_dp, 0.0_dp, -2.0_dp])
  call check(all(two == [4, 2]), 'sort_by_key: a subset of the indices, negative keys')
  call sort_by_key(empty, key)
  call sort_integers(empty)
  call sort_by_counts(ikey, 1, empty)
  call check(size(empty) == 0, 'empty arrays')

  ! random keys with many ties (20 values) in random index order
  state = 12345_i8
  do i = 1, n
    key(i) = real(int(20.0_dp * urand(state)), dp) - 10.0_dp
    idx(i) = i
  end do
  do i = n, 2, -1                         ! Fisher-Yates shuffle of the indices
    m = 1 + int(real(i, dp) * urand(state))
    m = min(m, i)
    call swap(idx(i), idx(m))
  end do
  call sort_by_key(idx, key)
  ok = is_permutation(idx)
  do i = 2, n
    ok = ok .and. (key(idx(i - 1)) < key(idx(i)) .or. (key(idx(i - 1)) == key(idx(i)) .and. idx(i - 1) < idx(i)))
  end do
  call check(ok, 'sort_by_key: 2000 random keys with ties: a permutation, keys ascending, ties by index')

  ! integers: ascending, and the same values as before (counted per value)
  do i = 1, n
    a(i) = int(1000.0_dp * urand(state)) - 500
  end do
  b = a
  call sort_integers(a)
  ok = all(a(2:n) >= a(1:n - 1))
  do i = -500, 499
    ok = ok .and. count(a == i) == count(b == i)
  end do
  call check(ok, 'sort_integers: 2000 random integers ascending, the same values')
  hand = [huge(1), -huge(1), 0, 7, -huge(1)]
  call sort_integers(hand)
  call check(all(hand == [-huge(1), -huge(1), 0, 7, huge(1)]), 'sort_integers: the extreme integers exactly')
  b = a(n:1:-1)
  call sort_small(b)
  call check(all(b == a), 'sort_integers and sort_small agree')

  ! counting sort: stable, so two passes sort by (high, low)
  do i = 1, n
    ikey(i) = int(256.0_dp * urand(state))
    perm(i) = i
  end do
  call sort_by_counts(mod(ikey, 16), 16, perm)
  call sort_by_counts(ikey / 16, 16, perm)
  ok = is_permutation(perm)
  do i = 2, n
    ok = ok .and. (ikey(perm(i - 1)) < ikey(perm(i)) .or. (ikey(perm(i - 1)) == ikey(perm(i)) .and. &
                                                           perm(i - 1) < perm(i)))
  end do
  call check(ok, 'sort_by_counts: two stable passes of 4 bits sort 8-bit keys, ties in input order')
  four = [4, 1, 3, 2]
  call sort_by_counts([1, 0, 1, 0], 2, four)
  call check(all(four == [4, 2, 1, 3]), 'sort_by_counts: keys 1 0 1 0 from 4 1 3 2 by hand, stable')

  call finish_tests()

contains

  subroutine swap(x, y)
    integer, intent(inout) :: x, y
    integer :: t
    t = x; x = y; y = t
  end subroutine swap

  !> Every index 1 .. size(p) once.
  logical function is_permutation(p)
    integer, intent(in) :: p(:)
    logical :: seen(size(p))
    integer :: k
    seen = .false.
    is_permutation = .true.
    do k = 1, size(p)
      if (p(k) < 1 .or. p(k) > size(p)) then
        is_permutation = .false.
        return
      end if
      if (seen(p(k))) is_permutation = .false.
      seen(p(k)) = .true.
    end do
  end function is_permutation
end program test_sorting
