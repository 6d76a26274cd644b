!> The fast Fourier transform of a power-of-two length: iterative radix-2 (Cooley-Tukey,
!> decimation in time, bit-reversed input order), in place, O(n log n).
!>
!> Convention: forward (sign = -1) X_k = sum_j x_j exp(-2 pi i j k / n); backward (sign = +1)
!> x_j = sum_k X_k exp(+2 pi i j k / n), unscaled (backward after forward gives n x). The
!> twiddle factors are computed directly per stage from cos/sin of the angle (no recurrence),
!> so the round-off grows as log n.
module gapbeam_fft
   use gapbeam_kinds, only: dp, pi
   implicit none
   private
   public :: fft, next_power_of_two

contains

   !> Smallest power of two >= n (n >= 1).
   pure integer function next_power_of_two(n) result(p)
      integer, intent(in) :: n   !! length
      p = 1
      do while (p < n)
         p = 2 * p
      end do
   end function next_power_of_two

   !> In-place transform of x (size a power of two); sign = -1 forward, +1 backward.
   pure subroutine fft(x, sign)
      complex(dp), intent(inout) :: x(:)   !! data, replaced by its transform
      integer, intent(in) :: sign          !! -1 or +1
      integer :: n, i, j, k, m, half, step
      complex(dp) :: t, w
      real(dp) :: ang
      n = size(x)
      if (n <= 1) return
      if (iand(n, n - 1) /= 0) error stop 'gapbeam_fft:fft: length is not a power of two'
      ! bit-reversal permutation
      j = 0
      do i = 0, n - 2
         if (i < j) then
            t = x(i + 1);  x(i + 1) = x(j + 1);  x(j + 1) = t
         end if
         k = n / 2
         do while (k <= j)
            j = j - k
            k = k / 2
         end do
         j = j + k
      end do
      ! butterflies
      half = 1
      do while (half < n)
         step = 2 * half
         do m = 0, half - 1
            ang = real(sign, dp) * pi * real(m, dp) / real(half, dp)
            w = cmplx(cos(ang), sin(ang), dp)
            do i = m, n - 1, step
               t = w * x(i + half + 1)
               x(i + half + 1) = x(i + 1) - t
               x(i + 1) = x(i + 1) + t
            end do
         end do
         half = step
      end do
   end subroutine fft
end module gapbeam_fft
