!> sparse_matrix: symmetric sparse matrices in compressed sparse column (CSC)
!> form, upper triangle stored, as the stiffness matrix K is handed to the
!> sparse Cholesky factorization.
!>
!> Storage of a symmetric n-by-n matrix A (1-based):
!>   column j holds the entries A(i, j) with i <= j, at positions
!>   p = colptr(j) .. colptr(j+1)-1: row rowind(p), value val(p);
!>   colptr(1) = 1, colptr(n+1) - 1 = nnz; rows strictly ascending in a column.
!> The strictly lower triangle is implied by symmetry, A(j, i) = A(i, j).
!>
!> Programming interface
!>   type(csc_t)                         the matrix (n, colptr, rowind, val)
!>   csc_nnz(A)                          number of stored entries (upper triangle)
!>   csc_symv(A, x, y)                   y = A x, using both triangles
!>   csc_from_triplets(n, rows, cols, vals, A)
!>                                       assemble (i, j, a) triplets, either
!>                                       triangle, duplicates summed
!>   csc_check(A, err)                   structural check of the storage above
module sparse_matrix
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: error_t, set_error, error_numerical
  implicit none
  private
  public :: csc_t, csc_nnz, csc_symv, csc_from_triplets, csc_check

  !> Symmetric matrix, upper triangle (row <= col), compressed columns, 1-based.
  type :: csc_t
    integer :: n = 0                     !< order of the matrix
    integer, allocatable :: colptr(:)    !< (n+1) column pointers, colptr(1) = 1
    integer, allocatable :: rowind(:)    !< (nnz) rows, ascending within each column
    real(dp), allocatable :: val(:)      !< (nnz) values
  end type csc_t

contains

  !> Number of stored entries (upper triangle with the diagonal) of A.
  !>   A (in) the matrix; 0 when it holds no columns
  pure integer function csc_nnz(A)
    type(csc_t), intent(in) :: A
    csc_nnz = 0
    if (A%n < 1 .or. .not. allocated(A%colptr)) return
    csc_nnz = A%colptr(A%n + 1) - 1
  end function csc_nnz

  !> y = A x for the symmetric A stored by its upper triangle.
  !>   A (in)  the matrix, order n
  !>   x (in)  (n) vector
  !>   y (out) (n) the product A x
  pure subroutine csc_symv(A, x, y)
    type(csc_t), intent(in) :: A
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    integer :: i, j, p

    y = 0.0_dp
    do j = 1, A%n
      do p = A%colptr(j), A%colptr(j + 1) - 1
        i = A%rowind(p)
        y(i) = y(i) + A%val(p) * x(j)                 ! upper part: y_i += a_ij x_j
        if (i /= j) y(j) = y(j) + A%val(p) * x(i)     ! mirrored:   y_j += a_ij x_i
      end do
    end do
  end subroutine csc_symv

  !> Assemble a symmetric matrix from triplets (rows(k), cols(k), vals(k)).
  !> An entry given in the lower triangle (i > j) counts as A(j, i); entries
  !> at the same position are summed, so an element-by-element assembly that
  !> adds each off-diagonal coupling once, in either triangle, is what it takes.
  !> Give each off-diagonal pair in one triangle only: (i, j) and (j, i) both
  !> given would be summed into one stored entry, counting the coupling twice.
  !>   n     (in)  order of the matrix, n >= 0
  !>   rows  (in)  (nt) row indices, 1..n
  !>   cols  (in)  (nt) column indices, 1..n
  !>   vals  (in)  (nt) values
  !>   A     (out) the matrix, rows ascending and distinct within each column
  pure subroutine csc_from_triplets(n, rows, cols, vals, A)
    integer, intent(in) :: n
    integer, intent(in) :: rows(:), cols(:)
    real(dp), intent(in) :: vals(:)
    type(csc_t), intent(out) :: A
    integer, allocatable :: rowptr(:), byrow(:), ti(:), tj(:), bycol(:)
    integer :: k, nt, i, j, p, q, prev

    nt = size(rows)
    ! (ti, tj) = the position in the upper triangle
    allocate(ti(nt), tj(nt))
    ti = min(rows, cols)
    tj = max(rows, cols)

    ! counting sort by row, then a stable counting sort by column: within each
    ! column the triplets come out in ascending row order
    allocate(rowptr(n + 2), byrow(nt), bycol(nt))
    rowptr = 0
    do k = 1, nt
      rowptr(ti(k) + 2) = rowptr(ti(k) + 2) + 1
    end do
    rowptr(1) = 1
    do i = 2, n + 2
      rowptr(i) = rowptr(i) + rowptr(i - 1)          ! rowptr(i+1) = first slot of row i
    end do
    do k = 1, nt
      byrow(rowptr(ti(k) + 1)) = k
      rowptr(ti(k) + 1) = rowptr(ti(k) + 1) + 1
    end do
    allocate(A%colptr(n + 1))
    A%n = n
    A%colptr = 0
    do k = 1, nt
      A%colptr(tj(k)) = A%colptr(tj(k)) + 1
    end do
    ! colptr(j) = first slot of column j in bycol
    p = 1
    do j = 1, n
      q = A%colptr(j)
      A%colptr(j) = p
      p = p + q
    end do
    A%colptr(n + 1) = p
    do k = 1, nt
      q = byrow(k)
      bycol(A%colptr(tj(q))) = q
      A%colptr(tj(q)) = A%colptr(tj(q)) + 1
    end do
    ! shift back: colptr(j) is now the end of column j
    do j = n, 1, -1
      A%colptr(j + 1) = A%colptr(j)
    end do
    A%colptr(1) = 1

    ! merge equal rows of each column
    allocate(A%rowind(nt), A%val(nt))
    p = 0
    do j = 1, n
      q = A%colptr(j)
      A%colptr(j) = p + 1
      prev = 0
      do k = q, A%colptr(j + 1) - 1
        if (ti(bycol(k)) == prev) then
          A%val(p) = A%val(p) + vals(bycol(k))          ! duplicate: a_ij += v
        else
          p = p + 1
          A%rowind(p) = ti(bycol(k))
          A%val(p) = vals(bycol(k))
          prev = ti(bycol(k))
        end if
      end do
    end do
    A%colptr(n + 1) = p + 1
    A%rowind = A%rowind(1:p)
    A%val = A%val(1:p)
  end subroutine csc_from_triplets

  !> Check the storage of A (see the module header); err describes the first
  !> defect found.
  !>   A   (in)  the matrix
  !>   err (out) allocated (error_numerical) when A is malformed
  subroutine csc_check(A, err)
    type(csc_t), intent(in) :: A
    type(error_t), allocatable, intent(out) :: err
    integer :: j, p, nnz

    if (A%n < 0) then
      call set_error(err, 'sparse matrix: negative order ' // int_to_str(A%n), error_numerical)
      return
    end if
    if (.not. allocated(A%colptr)) then
      call set_error(err, 'sparse matrix: column pointers not allocated', error_numerical)
      return
    end if
    if (size(A%colptr) < A%n + 1) then
      call set_error(err, 'sparse matrix: ' // int_to_str(size(A%colptr)) // ' column pointers for order ' &
                     // int_to_str(A%n) // ' (n+1 expected)', error_numerical)
      return
    end if
    if (A%colptr(1) /= 1) then
      call set_error(err, 'sparse matrix: colptr(1) = ' // int_to_str(A%colptr(1)) // ' (1 expected)', error_numerical)
      return
    end if
    do j = 1, A%n
      if (A%colptr(j + 1) < A%colptr(j)) then
        call set_error(err, 'sparse matrix: column pointers decrease at column ' // int_to_str(j), error_numerical)
        return
      end if
    end do
    nnz = A%colptr(A%n + 1) - 1
    if (.not. allocated(A%rowind) .or. .not. allocated(A%val)) then
      call set_error(err, 'sparse matrix: row indices or values not allocated', error_numerical)
      return
    end if
    if (size(A%rowind) < nnz .or. size(A%val) < nnz) then
      call set_error(err, 'sparse matrix: ' // int_to_str(nnz) // ' entries announced, row indices or values shorter', &
        error_numerical)
      return
    end if
    do j = 1, A%n
      do p = A%colptr(j), A%colptr(j + 1) - 1
        if (A%rowind(p) < 1 .or. A%rowind(p) > j) then
          call set_error(err, 'sparse matrix: row ' // int_to_str(A%rowind(p)) // ' in column ' // int_to_str(j) &
                         // ' (upper triangle expected, 1 <= row <= column)', error_numerical)
          return
        end if
        if (p > A%colptr(j)) then
          if (A%rowind(p) <= A%rowind(p - 1)) then
            call set_error(err, 'sparse matrix: rows not strictly ascending in column ' // int_to_str(j), error_numerical)
            return
          end if
        end if
      end do
    end do
  end subroutine csc_check

end module sparse_matrix
