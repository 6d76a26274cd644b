!> Explicit interfaces of the LAPACK routines gapbeam calls (with `implicit-external = false`
!> a call without an interface here does not compile). Callers check every `info`.
module gapbeam_lapack
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: dsygv, dsbgv, dpotrf, dpotrs, dpbtrf, dpbtrs, dgesv, dgeev
   public :: zgesv

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
   end interface
end module gapbeam_lapack
