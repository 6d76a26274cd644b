!> Small dense and banded kernels used on the time-stepping hot path (no allocation), and the
!> conversion of a dense symmetric matrix to LAPACK upper band storage ab(kd+1+i-j, j) = A(i, j).
module gapbeam_linalg
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: dense_matvec, band_matvec, band_solve, dense_to_band, band_to_dense, bandwidth

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

   !> Copy the upper band of a dense symmetric matrix to LAPACK band storage.
   pure subroutine dense_to_band(a, kd, ab)
      real(dp), intent(in) :: a(:, :)                    !! dense symmetric matrix
      integer, intent(in) :: kd                          !! semi-bandwidth
      real(dp), allocatable, intent(out) :: ab(:, :)     !! (kd+1, n) upper band storage
      integer :: i, j, n
      n = size(a, 2)
      allocate(ab(kd + 1, n), source=0.0_dp)
      do j = 1, n
         do i = max(1, j - kd), j
            ab(kd + 1 + i - j, j) = a(i, j)
         end do
      end do
   end subroutine dense_to_band

   !> The dense symmetric matrix of LAPACK upper band storage.
   pure subroutine band_to_dense(ab, a)
      real(dp), intent(in) :: ab(:, :)                   !! (kd+1, n) upper band storage
      real(dp), allocatable, intent(out) :: a(:, :)      !! (n, n)
      integer :: i, j, n, kd
      kd = size(ab, 1) - 1;  n = size(ab, 2)
      allocate(a(n, n), source=0.0_dp)
      do j = 1, n
         do i = max(1, j - kd), j
            a(i, j) = ab(kd + 1 + i - j, j)
            a(j, i) = a(i, j)
         end do
      end do
   end subroutine band_to_dense

   !> Banded Cholesky solve written out (LAPACK's dpbtrs is not pure).
   pure subroutine band_solve(n, kd, fab, b)
      integer, intent(in) :: n, kd
      real(dp), intent(in) :: fab(kd + 1, n)   ! upper factor U, A = U'U
      real(dp), intent(inout) :: b(n)
      integer :: i, j
      real(dp) :: s
      ! U' z = b
      do j = 1, n
         s = b(j)
         do i = max(1, j - kd), j - 1
            s = s - fab(kd + 1 + i - j, j) * b(i)
         end do
         b(j) = s / fab(kd + 1, j)
      end do
      ! U x = z
      do j = n, 1, -1
         b(j) = b(j) / fab(kd + 1, j)
         do i = max(1, j - kd), j - 1
            b(i) = b(i) - fab(kd + 1 + i - j, j) * b(j)
         end do
      end do
   end subroutine band_solve

   !> Largest |i - j| of a non-zero entry (the semi-bandwidth of a dense matrix).
   pure integer function bandwidth(a)
      real(dp), intent(in) :: a(:, :)
      integer :: i, j
      bandwidth = 0
      do j = 1, size(a, 2)
         do i = 1, size(a, 1)
            if (a(i, j) /= 0.0_dp) bandwidth = max(bandwidth, abs(i - j))
         end do
      end do
   end function bandwidth

end module gapbeam_linalg
