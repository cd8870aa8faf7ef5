!> sorting: the sorts and searches of the readers, the mesh, body and the
!> active-set solver, one of each: a stable merge sort of integer key columns
!> (lexicographic), its binary search, duplicate marking, a heap sort of
!> indices by a real key, an insertion sort for a few integers, and text
!> packed into key columns so that names sort by the same routine.
!>
!> A merge sort rather than LAPACK's dlasrt: the readers need a permutation
!> (dlasrt sorts values in place) of multi-word keys, and a stable one (the
!> first of equal keys in file order leads: repeated elements, names).
!> A heap sort for indices by a real key: in place, no workspace, O(n log n)
!> at worst, and ties broken by the index, so that the order is total and does
!> not depend on the algorithm.  Integers of any number sort by the same
!> routine (sort_integers); sort_small is for a handful (an element's nodes),
!> where an insertion sort without workspace is quickest.  A counting sort for
!> small integer keys over a whole mesh (mesh: order_for_locality, a Hilbert
!> index 16 bits at a time): linear time, stable, so that two passes sort by a
!> two-word key.
!>
!> Programming interface
!>   sort_columns(keys, perm, stat)   perm: keys(:, perm) ascending, stable
!>   search_columns(keys, perm, key)  the first column equal to key, 0 when none
!>   mark_repeated(keys, repeated, stat)  repeated(i): an earlier column equals column i
!>   sort_by_key(idx, key)            idx reordered: key(idx) ascending, ties by index
!>   sort_integers(a)                 integers ascending, in place, any number
!>   sort_by_counts(key, nkey, perm)  perm reordered: key(perm) ascending, stable, O(n + nkey)
!>   sort_small(a)                    a few integers ascending, in place
!>   text_key_words(text)             key words a text needs
!>   pack_text(text, key)             the text as key words: sorted as Fortran
!>                                    compares strings (blanks padded, byte order)
!>   number_classes(leader, class, n)  classes of an equivalence numbered by their leaders
module sorting
  use kinds, only: dp, i8
  implicit none
  private
  public :: sort_columns, search_columns, mark_repeated, sort_by_key, sort_integers, sort_by_counts, sort_small
  public :: text_key_words, pack_text, number_classes

  integer, parameter :: bytes_per_word = 7     !< 56 bits a key word: words stay >= 0

contains

  !> Lexicographic keys(:, i) < keys(:, j).
  pure logical function column_less(keys, i, j) result(less)
    integer(i8), intent(in) :: keys(:,:)
    integer, intent(in) :: i, j
    integer :: r
    less = .false.
    do r = 1, size(keys, 1)
      if (keys(r, i) /= keys(r, j)) then
        less = keys(r, i) < keys(r, j)
        return
      end if
    end do
  end function column_less

  !> Lexicographic keys(:, i) < key.
  pure logical function column_less_than_key(keys, i, key) result(less)
    integer(i8), intent(in) :: keys(:,:)
    integer, intent(in) :: i
    integer(i8), intent(in) :: key(:)
    integer :: r
    less = .false.
    do r = 1, size(keys, 1)
      if (keys(r, i) /= key(r)) then
        less = keys(r, i) < key(r)
        return
      end if
    end do
  end function column_less_than_key

  !> Stable bottom-up merge sort of the columns of keys, lexicographically.
  !> Two runs already in order are not merged, so that sorted input costs O(n).
  !>   keys (in)  (m, n) one key per column
  !>   perm (out) (n) keys(:, perm) is ascending; equal keys keep their order
  !>   stat (out) 0, or the allocation's status when memory ran out (perm is
  !>        then not allocated)
  subroutine sort_columns(keys, perm, stat)
    integer(i8), intent(in) :: keys(:,:)
    integer, allocatable, intent(out) :: perm(:)
    integer, intent(out) :: stat
    integer, allocatable :: tmp(:)
    integer :: n, i
    integer(i8) :: width, lo, mid, hi, a, b, k

    n = size(keys, 2)
    allocate(perm(n), tmp(n), stat=stat)
    if (stat /= 0) return
    do i = 1, n
      perm(i) = i
    end do
    width = 1
    do while (width < n)
      lo = 1
      do while (lo <= n)
        mid = min(lo + width - 1, int(n, i8))
        hi = min(lo + 2 * width - 1, int(n, i8))
        if (mid < hi) then
          if (.not. column_less(keys, perm(mid + 1), perm(mid))) then
            lo = lo + 2 * width
            cycle
          end if
          a = lo
          b = mid + 1
          k = lo
          do while (a <= mid .and. b <= hi)
            if (column_less(keys, perm(b), perm(a))) then
              tmp(k) = perm(b)
              b = b + 1
            else
              tmp(k) = perm(a)
              a = a + 1
            end if
            k = k + 1
          end do
          do while (a <= mid)
            tmp(k) = perm(a)
            a = a + 1
            k = k + 1
          end do
          do while (b <= hi)
            tmp(k) = perm(b)
            b = b + 1
            k = k + 1
          end do
          perm(lo:hi) = tmp(lo:hi)
        end if
        lo = lo + 2 * width
      end do
      width = 2 * width
    end do
  end subroutine sort_columns

  !> Column of keys equal to key (the first in file order), 0 when none.
  !>   keys (in) (m, n); perm (in) (n) from sort_columns(keys); key (in) (m)
  pure integer function search_columns(keys, perm, key) result(found)
    integer(i8), intent(in) :: keys(:,:)
    integer, intent(in) :: perm(:)
    integer(i8), intent(in) :: key(:)
    integer :: lo, hi, mid, r
    found = 0
    lo = 1
    hi = size(perm) + 1
    do while (lo < hi)
      mid = lo + (hi - lo) / 2
      if (column_less_than_key(keys, perm(mid), key)) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
    if (lo <= size(perm)) then
      do r = 1, size(key)
        if (keys(r, perm(lo)) /= key(r)) return
      end do
      found = perm(lo)
    end if
  end function search_columns

  !> repeated(i) = .true. when an earlier column of keys equals column i.
  !>   stat (out) 0, or the allocation's status when memory ran out
  subroutine mark_repeated(keys, repeated, stat)
    integer(i8), intent(in) :: keys(:,:)
    logical, intent(out) :: repeated(:)
    integer, intent(out) :: stat
    integer, allocatable :: perm(:)
    integer :: i
    repeated = .false.
    call sort_columns(keys, perm, stat)
    if (stat /= 0) return
    do i = 2, size(perm)
      if (all(keys(:, perm(i)) == keys(:, perm(i - 1)))) repeated(perm(i)) = .true.
    end do
  end subroutine mark_repeated

  !> Heap sort of the indices idx by increasing key(idx), ties by index.
  !>   idx (inout) (n) distinct indices into key; on exit key(idx) ascending,
  !>               an index before a larger one of the same key
  !>   key (in)    the keys, key(i) for each i in idx (no NaN)
  subroutine sort_by_key(idx, key)
    integer, intent(inout) :: idx(:)
    real(dp), intent(in) :: key(:)
    integer :: n, i, last, t
    n = size(idx)
    do i = n / 2, 1, -1                                ! build a max-heap
      call sift_down(i, n)
    end do
    do last = n, 2, -1                                 ! move the largest to the end
      t = idx(1)
      idx(1) = idx(last)
      idx(last) = t
      call sift_down(1, last - 1)
    end do
  contains
    logical function before(a, b)
      integer, intent(in) :: a, b
      before = key(a) < key(b) .or. (key(a) == key(b) .and. a < b)
    end function before
    !> Move idx(start) down the heap idx(start:finish) below the larger child.
    subroutine sift_down(start, finish)
      integer, intent(in) :: start, finish
      integer :: root, child, v
      root = start
      v = idx(root)
      do
        child = 2 * root
        if (child > finish) exit
        if (child < finish) then
          if (before(idx(child), idx(child + 1))) child = child + 1
        end if
        if (.not. before(v, idx(child))) exit
        idx(root) = idx(child)
        root = child
      end do
      idx(root) = v
    end subroutine sift_down
  end subroutine sort_by_key

  !> Integers ascending, in place, any number of them: sort_by_key with the
  !> values as keys (a default integer is exact in real(dp)).
  !>   a (inout) (n) the integers
  subroutine sort_integers(a)
    integer, intent(inout) :: a(:)
    integer, allocatable :: idx(:)
    integer :: i
    allocate(idx(size(a)))                  ! not automatic: a mesh's boundary may be large
    do i = 1, size(a)
      idx(i) = i
    end do
    call sort_by_key(idx, real(a, dp))
    a = a(idx)
  end subroutine sort_integers

  !> Stable counting sort: perm reordered so that key(perm) is ascending,
  !> equal keys keeping their order.
  !>   key  (in)    the keys, key(i) in 0 .. nkey - 1 for each i in perm
  !>   nkey (in)    the number of key values
  !>   perm (inout) (n) indices into key
  subroutine sort_by_counts(key, nkey, perm)
    integer, intent(in) :: key(:), nkey
    integer, intent(inout) :: perm(:)
    integer, allocatable :: start(:), out(:)
    integer :: i, k
    allocate(start(0:nkey), source=0)
    do i = 1, size(perm)
      k = key(perm(i))
      start(k + 1) = start(k + 1) + 1
    end do
    do k = 1, nkey
      start(k) = start(k) + start(k - 1)
    end do
    allocate(out(size(perm)))
    do i = 1, size(perm)
      k = key(perm(i))
      start(k) = start(k) + 1
      out(start(k)) = perm(i)
    end do
    perm = out
  end subroutine sort_by_counts

  !> Insertion sort of a few integers, ascending.
  pure subroutine sort_small(a)
    integer, intent(inout) :: a(:)
    integer :: i, j
    integer :: v
    do i = 2, size(a)
      v = a(i)
      j = i - 1
      do while (j >= 1)
        if (a(j) <= v) exit
        a(j + 1) = a(j)
        j = j - 1
      end do
      a(j + 1) = v
    end do
  end subroutine sort_small

  !> Key words of a text: ceiling(len / 7), at least 1.
  pure integer function text_key_words(text) result(n)
    character(len=*), intent(in) :: text
    n = max(1, (len(text) + bytes_per_word - 1) / bytes_per_word)
  end function text_key_words

  !> The bytes of text, 7 a word, the first byte highest, padded with blanks to
  !> size(key) words: comparing key columns lexicographically compares the
  !> texts as Fortran does (the shorter padded with blanks, bytes unsigned).
  !>   text (in)  at most 7 size(key) characters
  !>   key  (out) (nword) the packed text, nword >= text_key_words(text)
  pure subroutine pack_text(text, key)
    character(len=*), intent(in) :: text
    integer(i8), intent(out) :: key(:)
    integer :: w, j, p, byte
    do w = 1, size(key)
      key(w) = 0
      do j = 1, bytes_per_word
        p = (w - 1) * bytes_per_word + j
        byte = iachar(' ')
        if (p <= len(text)) byte = iand(iachar(text(p:p)), 255)
        key(w) = key(w) * 256 + byte
      end do
    end do
  end subroutine pack_text

  !> Number the classes of an equivalence given by a leader per item, in the
  !> order of their leaders (mark_repeated's rep, a sort's runs).
  !>   leader (in)  (n) leader(i) = i for the first item of a class, an earlier
  !>                item of the same class (itself led by the first) otherwise
  !>   class  (out) (n) class(i) the number of i's class, 1 .. nclass
  !>   nclass (out) the number of classes
  pure subroutine number_classes(leader, class, nclass)
    integer, intent(in) :: leader(:)
    integer, intent(out) :: class(:)
    integer, intent(out) :: nclass
    integer :: i
    nclass = 0
    do i = 1, size(leader)
      if (leader(i) == i) then
        nclass = nclass + 1
        class(i) = nclass
      else
        class(i) = class(leader(i))
      end if
    end do
  end subroutine number_classes

end module sorting
