!> lapack_interfaces: explicit interfaces of the BLAS and LAPACK routines
!> contact2d calls (reference BLAS/LAPACK argument lists, double precision),
!> so that every call is checked by the compiler.  Linked from the system's
!> libraries (OpenBLAS, LAPACK); nothing is implemented here.  The dummies
!> are declared as the reference sources declare them: the scalar
!> arguments, then the array arguments; dpotrf and dpotri, whose argument
!> lists are the same, share one abstract interface.
!>
!> Programming interface: the routines below, by their standard names.
!>   BLAS    daxpy, drot, dgemv, dger, dtrsv, dtrsm, dsyrk
!>   LAPACK  dgtsv, dgbsv, dgesv, dpotrf, dpotri, dpotrs, dpstrf, dsysv, dsyev, dgesvd, dgeqp3, dlasrt
module lapack_interfaces
  use kinds, only: dp
  implicit none
  private
  public :: daxpy, drot, dgemv, dger, dtrsv, dtrsm, dsyrk, dgtsv, dpotrf, dpotri, dpotrs, dpstrf, &
            dsysv, dsyev, dgesvd, dgeqp3, dgbsv, dgesv, dlasrt

  !> The argument list that dpotrf and dpotri share: the triangle uplo of
  !> a(lda, n) replaced in place, info = 0 or the failing column.
  abstract interface
    subroutine triangle_in_place(uplo, n, a, lda, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      integer, intent(out) :: info
      real(dp), intent(inout) :: a(lda, *)
    end subroutine triangle_in_place
  end interface

  !> LAPACK: the Cholesky factor of A in place (dpotrf); the inverse of
  !> A = L L' (uplo 'L') from its Cholesky factor, in place (dpotri).
  procedure(triangle_in_place) :: dpotrf, dpotri

  interface
    !> BLAS: y = alpha x + y.
    subroutine daxpy(n, alpha, x, incx, y, incy)
      import :: dp
      integer, intent(in) :: n, incx, incy
      real(dp), intent(in) :: alpha
      real(dp), intent(in) :: x(*)
      real(dp), intent(inout) :: y(*)
    end subroutine daxpy
    !> BLAS: the plane rotation [x y] = [x y] [c -s; s c].
    subroutine drot(n, x, incx, y, incy, c, s)
      import :: dp
      integer, intent(in) :: n, incx, incy
      real(dp), intent(in) :: c, s
      real(dp), intent(inout) :: x(*), y(*)
    end subroutine drot
    !> BLAS: y = alpha op(A) x + beta y.
    subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
      import :: dp
      character, intent(in) :: trans
      integer, intent(in) :: m, n, lda, incx, incy
      real(dp), intent(in) :: alpha, beta
      real(dp), intent(in) :: a(lda, *), x(*)
      real(dp), intent(inout) :: y(*)
    end subroutine dgemv
    !> BLAS: A = alpha x y' + A.
    subroutine dger(m, n, alpha, x, incx, y, incy, a, lda)
      import :: dp
      integer, intent(in) :: m, n, incx, incy, lda
      real(dp), intent(in) :: alpha
      real(dp), intent(in) :: x(*), y(*)
      real(dp), intent(inout) :: a(lda, *)
    end subroutine dger
    !> BLAS: x = op(A)^-1 x, A triangular.
    subroutine dtrsv(uplo, trans, diag, n, a, lda, x, incx)
      import :: dp
      character, intent(in) :: uplo, trans, diag
      integer, intent(in) :: n, lda, incx
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: x(*)
    end subroutine dtrsv
    !> BLAS: B = alpha op(A)^-1 B or alpha B op(A)^-1, A triangular.
    subroutine dtrsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
      import :: dp
      character, intent(in) :: side, uplo, transa, diag
      integer, intent(in) :: m, n, lda, ldb
      real(dp), intent(in) :: alpha
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
    end subroutine dtrsm
    !> BLAS: C = alpha A A' + beta C or alpha A' A + beta C, C symmetric.
    subroutine dsyrk(uplo, trans, n, k, alpha, a, lda, beta, c, ldc)
      import :: dp
      character, intent(in) :: uplo, trans
      integer, intent(in) :: n, k, lda, ldc
      real(dp), intent(in) :: alpha, beta
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: c(ldc, *)
    end subroutine dsyrk
    !> LAPACK: solve A X = B for a general tridiagonal A (LU with partial pivoting).
    subroutine dgtsv(n, nrhs, dl, d, du, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, nrhs, ldb
      integer, intent(out) :: info
      real(dp), intent(inout) :: dl(*), d(*), du(*), b(ldb, *)
    end subroutine dgtsv
    !> LAPACK: solve A X = B for a general band matrix A (LU with partial pivoting).
    subroutine dgbsv(n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, kl, ku, nrhs, ldab, ldb
      integer, intent(out) :: info
      integer, intent(out) :: ipiv(*)
      real(dp), intent(inout) :: ab(ldab, *), b(ldb, *)
    end subroutine dgbsv
    !> LAPACK: solve A X = B for a general A (LU with partial pivoting).
    subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, nrhs, lda, ldb
      integer, intent(out) :: info
      integer, intent(out) :: ipiv(*)
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
    end subroutine dgesv
    !> LAPACK: solve A X = B with the Cholesky factor of A from dpotrf.
    subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      integer, intent(out) :: info
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
    end subroutine dpotrs
    !> LAPACK: Cholesky factorization with complete pivoting of a semidefinite A.
    subroutine dpstrf(uplo, n, a, lda, piv, rank, tol, work, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(in) :: tol
      integer, intent(out) :: rank, info
      integer, intent(out) :: piv(*)
      real(dp), intent(inout) :: a(lda, *), work(*)
    end subroutine dpstrf
    !> LAPACK: solve A X = B for a symmetric indefinite A (Bunch-Kaufman).
    subroutine dsysv(uplo, n, nrhs, a, lda, ipiv, b, ldb, work, lwork, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb, lwork
      integer, intent(out) :: info
      integer, intent(out) :: ipiv(*)
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      real(dp), intent(out) :: work(*)
    end subroutine dsysv
    !> LAPACK: the eigenvalues w (ascending) and, jobz = 'V', the eigenvectors
    !> (in a's columns) of a symmetric matrix, from its triangle uplo.
    subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
      import :: dp
      character, intent(in) :: jobz, uplo
      integer, intent(in) :: n, lda, lwork
      integer, intent(out) :: info
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: w(*), work(*)
    end subroutine dsyev
    !> LAPACK: the singular value decomposition A = U S V'.
    subroutine dgesvd(jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, work, lwork, info)
      import :: dp
      character, intent(in) :: jobu, jobvt
      integer, intent(in) :: m, n, lda, ldu, ldvt, lwork
      integer, intent(out) :: info
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: s(*), u(ldu, *), vt(ldvt, *), work(*)
    end subroutine dgesvd
    !> LAPACK: the QR factorization with column pivoting A P = Q R.
    subroutine dgeqp3(m, n, a, lda, jpvt, tau, work, lwork, info)
      import :: dp
      integer, intent(in) :: m, n, lda, lwork
      integer, intent(out) :: info
      integer, intent(inout) :: jpvt(*)
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: tau(*), work(*)
    end subroutine dgeqp3
    !> LAPACK: sort d in increasing (id 'I') or decreasing (id 'D') order.
    subroutine dlasrt(id, n, d, info)
      import :: dp
      character(len=1), intent(in) :: id
      integer, intent(in) :: n
      integer, intent(out) :: info
      real(dp), intent(inout) :: d(*)
    end subroutine dlasrt
  end interface

end module lapack_interfaces
