!> Small dense and banded kernels used on the time-stepping hot path (no allocation).
module gapbeam_linalg
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: dense_matvec, band_matvec

contains

   !> y = A x for a dense n x n matrix (column-oriented loop, vectorises for small n).
   pure subroutine dense_matvec(n, a, x, y)
      integer, intent(in) :: n             !! order
      real(dp), intent(in) :: a(n, n)      !! matrix
      real(dp), intent(in) :: x(n)         !! vector
      real(dp), intent(out) :: y(n)        !! result
      integer :: j
      y = 0.0_dp
      do j = 1, n
         y = y + a(:, j) * x(j)
      end do
   end subroutine dense_matvec

   !> y = A x for a symmetric matrix in LAPACK upper band storage ab(kd+1+i-j, j).
   pure subroutine band_matvec(n, kd, ab, x, y)
      integer, intent(in) :: n             !! order
      integer, intent(in) :: kd            !! semi-bandwidth
      real(dp), intent(in) :: ab(kd + 1, n) !! band storage
      real(dp), intent(in) :: x(n)         !! vector
      real(dp), intent(out) :: y(n)        !! result
      integer :: i, j
      real(dp) :: aij
      y = 0.0_dp
      do j = 1, n
         y(j) = y(j) + ab(kd + 1, j) * x(j)
         do i = max(1, j - kd), j - 1
            aij = ab(kd + 1 + i - j, j)
            y(i) = y(i) + aij * x(j)
            y(j) = y(j) + aij * x(i)
         end do
      end do
   end subroutine band_matvec
end module gapbeam_linalg
