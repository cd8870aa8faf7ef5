!> lapack_interfaces: explicit interfaces of the BLAS and LAPACK routines
!> contact2d calls (reference BLAS/LAPACK argument lists, double precision),
!> so that every call is checked by the compiler.  Linked from the system's
!> libraries (OpenBLAS, LAPACK); nothing is implemented here.
!>
!> Programming interface: the routines below, by their standard names.
!>   BLAS    daxpy, drot, dgemv, dger, dtrsv, dtrsm, dtrmm, dsyrk
!>   LAPACK  dgtsv, dgbsv, dgesv, dpotrf, dlauum, dpotri, dpotrs, dpstrf, dsysv, dgesvd, dgeqp3
module lapack_interfaces
  use kinds, only: dp
  implicit none
  private
  public :: daxpy, drot, dgemv, dger, dtrsv, dtrsm, dtrmm, dsyrk, dgtsv, dpotrf, dlauum, dpotri, dpotrs, dpstrf, &
            dsysv, dgesvd, dgeqp3, dgbsv, dgesv, dlasrt

  interface
    subroutine daxpy(n, alpha, x, incx, y, incy)
      import :: dp
      integer, intent(in) :: n, incx, incy
      real(dp), intent(in) :: alpha, x(*)
      real(dp), intent(inout) :: y(*)
    end subroutine daxpy
    subroutine drot(n, x, incx, y, incy, c, s)
      import :: dp
      integer, intent(in) :: n, incx, incy
      real(dp), intent(inout) :: x(*), y(*)
      real(dp), intent(in) :: c, s
    end subroutine drot
    subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
      import :: dp
      character, intent(in) :: trans
      integer, intent(in) :: m, n, lda, incx, incy
      real(dp), intent(in) :: alpha, a(lda, *), x(*), beta
      real(dp), intent(inout) :: y(*)
    end subroutine dgemv
    subroutine dger(m, n, alpha, x, incx, y, incy, a, lda)
      import :: dp
      integer, intent(in) :: m, n, incx, incy, lda
      real(dp), intent(in) :: alpha, x(*), y(*)
      real(dp), intent(inout) :: a(lda, *)
    end subroutine dger
    subroutine dtrsv(uplo, trans, diag, n, a, lda, x, incx)
      import :: dp
      character, intent(in) :: uplo, trans, diag
      integer, intent(in) :: n, lda, incx
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: x(*)
    end subroutine dtrsv
    subroutine dtrsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
      import :: dp
      character, intent(in) :: side, uplo, transa, diag
      integer, intent(in) :: m, n, lda, ldb
      real(dp), intent(in) :: alpha, a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
    end subroutine dtrsm
    subroutine dsyrk(uplo, trans, n, k, alpha, a, lda, beta, c, ldc)
      import :: dp
      character, intent(in) :: uplo, trans
      integer, intent(in) :: n, k, lda, ldc
      real(dp), intent(in) :: alpha, a(lda, *), beta
      real(dp), intent(inout) :: c(ldc, *)
    end subroutine dsyrk
    !> LAPACK: solve A X = B for a general tridiagonal A (LU with partial pivoting).
    subroutine dgtsv(n, nrhs, dl, d, du, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, nrhs, ldb
      real(dp), intent(inout) :: dl(*), d(*), du(*), b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgtsv
    !> BLAS: B = alpha op(A) B or alpha B op(A), A triangular.
    subroutine dtrmm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
      import :: dp
      character, intent(in) :: side, uplo, transa, diag
      integer, intent(in) :: m, n, lda, ldb
      real(dp), intent(in) :: alpha, a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
    end subroutine dtrmm
    !> LAPACK: U U' (uplo 'U') or L' L (uplo 'L') in place of the triangle.
    subroutine dlauum(uplo, n, a, lda, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dlauum
    subroutine dpotrf(uplo, n, a, lda, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotrf
    !> LAPACK: the inverse of A = L L' (uplo 'L') from its Cholesky factor, in place.
    subroutine dpotri(uplo, n, a, lda, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotri
    subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dpotrs
    subroutine dpstrf(uplo, n, a, lda, piv, rank, tol, work, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: piv(*), rank, info
      real(dp), intent(in) :: tol
      real(dp), intent(inout) :: work(*)
    end subroutine dpstrf
    subroutine dsysv(uplo, n, nrhs, a, lda, ipiv, b, ldb, work, lwork, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb, lwork
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: ipiv(*), info
      real(dp), intent(out) :: work(*)
    end subroutine dsysv
    subroutine dgesvd(jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, work, lwork, info)
      import :: dp
      character, intent(in) :: jobu, jobvt
      integer, intent(in) :: m, n, lda, ldu, ldvt, lwork
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: s(*), u(ldu, *), vt(ldvt, *), work(*)
      integer, intent(out) :: info
    end subroutine dgesvd
    subroutine dgeqp3(m, n, a, lda, jpvt, tau, work, lwork, info)
      import :: dp
      integer, intent(in) :: m, n, lda, lwork
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(inout) :: jpvt(*)
      real(dp), intent(out) :: tau(*), work(*)
      integer, intent(out) :: info
    end subroutine dgeqp3
    subroutine dgbsv(n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, kl, ku, nrhs, ldab, ldb
      real(dp), intent(inout) :: ab(ldab, *), b(ldb, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgbsv
    subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgesv
    subroutine dlasrt(id, n, d, info)
      import :: dp
      character(len=1), intent(in) :: id
      integer, intent(in) :: n
      real(dp), intent(inout) :: d(*)
      integer, intent(out) :: info
    end subroutine dlasrt
  end interface

end module lapack_interfaces
