!> Explicit interfaces of the LAPACK (and BLAS) routines gapbeam calls (with `implicit-external = false`
!> a call without an interface here does not compile). Callers check every `info`.
module gapbeam_lapack
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: dsygv, dsbgv, dpotrf, dpotrs, dpbtrf, dpbtrs, dgesv, dgeev
   public :: zgesv, dsyevd, dsygst, dtrtrs, dgbtrf, dgbtrs, zgemm, dgemm

   interface
      !> Generalized symmetric-definite eigenproblem A x = lambda B x.
      subroutine dsygv(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, info)
         import :: dp
         integer,   intent(in)    :: itype, n, lda, ldb, lwork
         character, intent(in)    :: jobz, uplo
         real(dp),  intent(inout) :: a(lda, *), b(ldb, *)
         real(dp),  intent(out)   :: w(*), work(*)
         integer,   intent(out)   :: info
      end subroutine dsygv


      !> General eigenproblem.
      subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
         import :: dp
         character, intent(in)    :: jobvl, jobvr
         integer,   intent(in)    :: n, lda, ldvl, ldvr, lwork
         real(dp),  intent(inout) :: a(lda, *)
         real(dp),  intent(out)   :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
         integer,   intent(out)   :: info
      end subroutine dgeev

      !> Cholesky factorization of a dense SPD matrix.
      subroutine dpotrf(uplo, n, a, lda, info)
         import :: dp
         character, intent(in)    :: uplo
         integer,   intent(in)    :: n, lda
         real(dp),  intent(inout) :: a(lda, *)
         integer,   intent(out)   :: info
      end subroutine dpotrf

      !> Solve with a dense Cholesky factor.
      subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
         import :: dp
         character, intent(in)    :: uplo
         integer,   intent(in)    :: n, nrhs, lda, ldb
         real(dp),  intent(in)    :: a(lda, *)
         real(dp),  intent(inout) :: b(ldb, *)
         integer,   intent(out)   :: info
      end subroutine dpotrs


      !> Generalized symmetric-definite banded eigenproblem A x = lambda B x (B positive
      !> definite); eigenvalues ascending in w.
      subroutine dsbgv(jobz, uplo, n, ka, kb, ab, ldab, bb, ldbb, w, z, ldz, work, info)
         import :: dp
         character, intent(in)    :: jobz, uplo
         integer,   intent(in)    :: n, ka, kb, ldab, ldbb, ldz
         real(dp),  intent(inout) :: ab(ldab, *), bb(ldbb, *)
         real(dp),  intent(out)   :: w(*), z(ldz, *), work(*)
         integer,   intent(out)   :: info
      end subroutine dsbgv

      !> Cholesky factorization of a banded SPD matrix.
      subroutine dpbtrf(uplo, n, kd, ab, ldab, info)
         import :: dp
         character, intent(in)    :: uplo
         integer,   intent(in)    :: n, kd, ldab
         real(dp),  intent(inout) :: ab(ldab, *)
         integer,   intent(out)   :: info
      end subroutine dpbtrf

      !> Solve with a banded Cholesky factor.
      subroutine dpbtrs(uplo, n, kd, nrhs, ab, ldab, b, ldb, info)
         import :: dp
         character, intent(in)    :: uplo
         integer,   intent(in)    :: n, kd, nrhs, ldab, ldb
         real(dp),  intent(in)    :: ab(ldab, *)
         real(dp),  intent(inout) :: b(ldb, *)
         integer,   intent(out)   :: info
      end subroutine dpbtrs

      !> General linear solve.
      subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: dp
         integer,  intent(in)    :: n, nrhs, lda, ldb
         real(dp), intent(inout) :: a(lda, *), b(ldb, *)
         integer,  intent(out)   :: ipiv(*), info
      end subroutine dgesv



      !> Complex general linear solve (LU with partial pivoting).
      subroutine zgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: dp
         integer,     intent(in)    :: n, nrhs, lda, ldb
         complex(dp), intent(inout) :: a(lda, *), b(ldb, *)
         integer,     intent(out)   :: ipiv(*), info
      end subroutine zgesv

      !> All eigenvalues and eigenvectors of a symmetric matrix (divide and conquer).
      subroutine dsyevd(jobz, uplo, n, a, lda, w, work, lwork, iwork, liwork, info)
         import :: dp
         character, intent(in)    :: jobz, uplo
         integer,   intent(in)    :: n, lda, lwork, liwork
         real(dp),  intent(inout) :: a(lda, *)
         real(dp),  intent(out)   :: w(*), work(*)
         integer,   intent(out)   :: iwork(*), info
      end subroutine dsyevd

      !> Reduce a symmetric-definite generalized problem to standard form with a Cholesky
      !> factor (itype 1: A <- U^-T A U^-1).
      subroutine dsygst(itype, uplo, n, a, lda, b, ldb, info)
         import :: dp
         integer,   intent(in)    :: itype, n, lda, ldb
         character, intent(in)    :: uplo
         real(dp),  intent(inout) :: a(lda, *)
         real(dp),  intent(in)    :: b(ldb, *)
         integer,   intent(out)   :: info
      end subroutine dsygst

      !> Solve a triangular system.
      subroutine dtrtrs(uplo, trans, diag, n, nrhs, a, lda, b, ldb, info)
         import :: dp
         character, intent(in)    :: uplo, trans, diag
         integer,   intent(in)    :: n, nrhs, lda, ldb
         real(dp),  intent(in)    :: a(lda, *)
         real(dp),  intent(inout) :: b(ldb, *)
         integer,   intent(out)   :: info
      end subroutine dtrtrs

      !> LU factorization of a general band matrix.
      subroutine dgbtrf(m, n, kl, ku, ab, ldab, ipiv, info)
         import :: dp
         integer,  intent(in)    :: m, n, kl, ku, ldab
         real(dp), intent(inout) :: ab(ldab, *)
         integer,  intent(out)   :: ipiv(*), info
      end subroutine dgbtrf

      !> Solve with a band LU factorization.
      subroutine dgbtrs(trans, n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb, info)
         import :: dp
         character, intent(in)    :: trans
         integer,   intent(in)    :: n, kl, ku, nrhs, ldab, ldb
         real(dp),  intent(in)    :: ab(ldab, *)
         integer,   intent(in)    :: ipiv(*)
         real(dp),  intent(inout) :: b(ldb, *)
         integer,   intent(out)   :: info
      end subroutine dgbtrs

      !> Complex matrix product C = alpha op(A) op(B) + beta C (BLAS).
      subroutine zgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
         import :: dp
         character,   intent(in)    :: transa, transb
         integer,     intent(in)    :: m, n, k, lda, ldb, ldc
         complex(dp), intent(in)    :: alpha, beta, a(lda, *), b(ldb, *)
         complex(dp), intent(inout) :: c(ldc, *)
      end subroutine zgemm

      !> Real matrix product C = alpha op(A) op(B) + beta C (BLAS).
      subroutine dgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
         import :: dp
         character,   intent(in)    :: transa, transb
         integer,     intent(in)    :: m, n, k, lda, ldb, ldc
         real(dp),    intent(in)    :: alpha, beta, a(lda, *), b(ldb, *)
         real(dp),    intent(inout) :: c(ldc, *)
      end subroutine dgemm
   end interface
end module gapbeam_lapack
