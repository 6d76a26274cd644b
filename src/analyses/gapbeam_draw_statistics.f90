!> Statistics over random draws: the mean of an output with the half-width of its two-sided
!> 95 % confidence interval (Student t, n - 1 degrees of freedom, the draws independent), and
!> the one-sided power spectral density of a sampled signal by Welch's method.
!>
!> * Half-width: t_{0.975, n-1} s / n^(1/2), s the sample standard deviation. The t quantile
!>   solves F(t) = p, F(t) = 1 - I_{nu/(nu+t^2)}(nu/2, 1/2) / 2 (t > 0), I the regularised
!>   incomplete beta function (continued fraction, modified Lentz), by bisection safeguarding
!>   Newton to 1e-12; t_{0.975} = 12.706 (1 degree of freedom), 2.262 (9), 1.960 (infinite).
!> * Welch: segments of n_seg samples (a power of two), Hann window, 50 % overlap, each
!>   segment's mean removed; P(f_k) = 2 |X_k|^2 / (f_s sum w^2) at f_k = k f_s / n_seg,
!>   0 < k < n_seg/2 (k = 0 and n_seg/2 without the 2), averaged over the segments; its
!>   integral over f is the signal's variance (Parseval, for the windowed segments).
!> * Periodogram: the whole signal of n samples (any n), no window, mean removed;
!>   P(f_k) = 2 |X_k|^2 dt / n at f_k = k / (n dt), 0 < k < n/2 (k = 0 and n/2 without the 2):
!>   its sum times 1/(n dt) is the variance exactly (Parseval), and a signal periodic in the
!>   n samples has no leakage. The DFT of any length by Bluestein's chirp z-transform (three
!>   power-of-two FFTs of length >= 2n - 1).
module gapbeam_draw_statistics
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_fft, only: fft, next_power_of_two
   implicit none
   private
   public :: student_t_quantile, mean_half_width, welch_psd, relative_half_width, &
      periodogram_psd, dft

contains

   !> Regularised incomplete beta function I_x(a, b).
   pure real(dp) function incomplete_beta(x, a, b) result(r)
      real(dp), intent(in) :: x      !! in [0, 1]
      real(dp), intent(in) :: a, b   !! > 0
      real(dp) :: front
      if (x <= 0.0_dp) then
         r = 0.0_dp
         return
      end if
      if (x >= 1.0_dp) then
         r = 1.0_dp
         return
      end if
      front = exp(log_gamma(a + b) - log_gamma(a) - log_gamma(b) + a * log(x) &
                  + b * log(1.0_dp - x))
      if (x < (a + 1.0_dp) / (a + b + 2.0_dp)) then
         r = front * beta_fraction(x, a, b) / a
      else
         r = 1.0_dp - front * beta_fraction(1.0_dp - x, b, a) / b
      end if
   end function incomplete_beta

   !> The continued fraction of I_x(a, b) (modified Lentz).
   pure real(dp) function beta_fraction(x, a, b) result(h)
      real(dp), intent(in) :: x, a, b
      real(dp), parameter :: tiny_v = 1.0e-300_dp
      real(dp) :: c, d, del, aa
      integer :: m, m2
      c = 1.0_dp
      d = 1.0_dp - (a + b) * x / (a + 1.0_dp)
      if (abs(d) < tiny_v) d = tiny_v
      d = 1.0_dp / d
      h = d
      do m = 1, 1000
         m2 = 2 * m
         aa = m * (b - m) * x / ((a + m2 - 1.0_dp) * (a + m2))
         d = 1.0_dp + aa * d;  if (abs(d) < tiny_v) d = tiny_v
         c = 1.0_dp + aa / c;  if (abs(c) < tiny_v) c = tiny_v
         d = 1.0_dp / d
         h = h * d * c
         aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0_dp))
         d = 1.0_dp + aa * d;  if (abs(d) < tiny_v) d = tiny_v
         c = 1.0_dp + aa / c;  if (abs(c) < tiny_v) c = tiny_v
         d = 1.0_dp / d
         del = d * c
         h = h * del
         if (abs(del - 1.0_dp) < 1.0e-15_dp) exit
      end do
   end function beta_fraction

   !> Student's t distribution function at t > 0 with nu degrees of freedom.
   pure real(dp) function t_cdf(t, nu) result(f)
      real(dp), intent(in) :: t, nu
      f = 1.0_dp - 0.5_dp * incomplete_beta(nu / (nu + t * t), 0.5_dp * nu, 0.5_dp)
   end function t_cdf

   !> The p-quantile (p in (0.5, 1)) of Student's t with nu >= 1 degrees of freedom.
   pure real(dp) function student_t_quantile(p, nu) result(t)
      real(dp), intent(in) :: p    !! probability, e.g. 0.975
      integer, intent(in) :: nu    !! degrees of freedom
      real(dp) :: lo, hi, f, dens, x
      integer :: it
      x = real(nu, dp)
      lo = 0.0_dp;  hi = 1.0_dp
      do while (t_cdf(hi, x) < p)
         lo = hi;  hi = 2.0_dp * hi
      end do
      t = 0.5_dp * (lo + hi)
      do it = 1, 200
         f = t_cdf(t, x) - p
         if (f > 0.0_dp) then
            hi = t
         else
            lo = t
         end if
         if (hi - lo <= 1.0e-13_dp * hi) exit
         dens = exp(log_gamma(0.5_dp * (x + 1.0_dp)) - log_gamma(0.5_dp * x)) &
                / sqrt(x * pi) * (1.0_dp + t * t / x)**(-0.5_dp * (x + 1.0_dp))
         t = t - f / dens
         if (t <= lo .or. t >= hi) t = 0.5_dp * (lo + hi)
      end do
   end function student_t_quantile

   !> Mean of x and the half-width of its 95 % confidence interval (0 for one value).
   pure subroutine mean_half_width(x, mean, half_width)
      real(dp), intent(in) :: x(:)          !! values of the draws
      real(dp), intent(out) :: mean         !! their mean
      real(dp), intent(out) :: half_width   !! t_{0.975, n-1} s / n^(1/2)
      integer :: n
      real(dp) :: s2
      n = size(x)
      mean = 0.0_dp;  half_width = 0.0_dp
      if (n == 0) return
      mean = sum(x) / real(n, dp)
      if (n < 2) return
      s2 = sum((x - mean)**2) / real(n - 1, dp)
      half_width = student_t_quantile(0.975_dp, n - 1) * sqrt(s2 / real(n, dp))
   end subroutine mean_half_width

   !> The half-width relative to |mean| (huge when the mean is zero and the half-width not).
   pure real(dp) function relative_half_width(x) result(r)
      real(dp), intent(in) :: x(:)          !! values of the draws
      real(dp) :: m, hw
      call mean_half_width(x, m, hw)
      if (hw == 0.0_dp) then
         r = 0.0_dp
      else if (m == 0.0_dp) then
         r = huge(1.0_dp)
      else
         r = hw / abs(m)
      end if
   end function relative_half_width

   !> Welch's one-sided PSD of x sampled every dt, segments of n_seg samples (a power of two,
   !> at most size(x)): frequencies k / (n_seg dt), k = 0..n_seg/2 (in elements 1..n_seg/2+1)
   !> [Hz], and the density [unit^2/Hz].
   pure subroutine welch_psd(x, dt, n_seg, f, psd)
      real(dp), intent(in) :: x(:)                   !! samples
      real(dp), intent(in) :: dt                     !! sample interval [s]
      integer, intent(in) :: n_seg                   !! segment length
      real(dp), allocatable, intent(out) :: f(:)     !! frequencies [Hz]
      real(dp), allocatable, intent(out) :: psd(:)   !! density
      real(dp) :: w(n_seg), seg(n_seg), norm
      complex(dp) :: z(n_seg)
      integer :: i, k, start, n_avg, half
      half = n_seg / 2
      allocate(psd(half + 1), source=0.0_dp)
      f = [(real(k, dp) / (real(n_seg, dp) * dt), k = 0, half)]
      w = [(0.5_dp - 0.5_dp * cos(2.0_dp * pi * real(i, dp) / real(n_seg, dp)), &
            i = 0, n_seg - 1)]
      norm = sum(w**2) / dt          ! f_s sum w^2
      n_avg = 0
      start = 1
      do while (start + n_seg - 1 <= size(x))
         seg = x(start:start + n_seg - 1)
         seg = (seg - sum(seg) / real(n_seg, dp)) * w
         z = cmplx(seg, 0.0_dp, dp)
         call fft(z, -1)
         do k = 0, half
            psd(k + 1) = psd(k + 1) + abs(z(k + 1))**2
         end do
         n_avg = n_avg + 1
         start = start + half
      end do
      if (n_avg == 0) return
      psd = psd / (real(n_avg, dp) * norm)
      psd(2:half) = 2.0_dp * psd(2:half)
   end subroutine welch_psd

   !> The forward DFT X_k = sum_j x_j exp(-2 pi i j k / n) of any length n (Bluestein: with
   !> w_m = exp(i pi m^2 / n), X_k = conj(w_k) sum_j (x_j conj(w_j)) w_(k-j), the convolution
   !> by power-of-two FFTs; m^2 reduced modulo 2n in integers, so the chirp is exact).
   pure function dft(x) result(xk)
      complex(dp), intent(in) :: x(:)         !! signal
      complex(dp) :: xk(size(x))
      complex(dp), allocatable :: a(:), b(:), w(:)
      integer :: n, m, j
      integer(int64) :: q
      n = size(x)
      if (n == 0) return
      if (iand(n, n - 1) == 0) then
         xk = x
         call fft(xk, -1)
         return
      end if
      allocate(w(0:n - 1))
      do j = 0, n - 1
         q = mod(int(j, int64) * int(j, int64), 2_int64 * n)
         w(j) = exp(cmplx(0.0_dp, pi * real(q, dp) / real(n, dp), dp))
      end do
      m = next_power_of_two(2 * n - 1)
      allocate(a(m), b(m), source=(0.0_dp, 0.0_dp))
      a(1:n) = x * conjg(w)
      b(1:n) = w
      do j = 1, n - 1
         b(m - j + 1) = w(j)
      end do
      call fft(a, -1)
      call fft(b, -1)
      a = a * b
      call fft(a, +1)
      xk = conjg(w) * a(1:n) / real(m, dp)
   end function dft

   !> The one-sided periodogram of x sampled every dt (the module header): frequencies
   !> k / (n dt), k = 0..n/2 [Hz], and the density [unit^2/Hz].
   pure subroutine periodogram_psd(x, dt, f, psd)
      real(dp), intent(in) :: x(:)                   !! samples
      real(dp), intent(in) :: dt                     !! sample interval [s]
      real(dp), allocatable, intent(out) :: f(:)     !! frequencies [Hz]
      real(dp), allocatable, intent(out) :: psd(:)   !! density
      complex(dp), allocatable :: z(:)
      integer :: n, half, k
      n = size(x)
      half = n / 2
      f = [(real(k, dp) / (real(n, dp) * dt), k = 0, half)]
      z = dft(cmplx(x - sum(x) / real(max(n, 1), dp), 0.0_dp, dp))
      psd = [(abs(z(k + 1))**2 * dt / real(n, dp), k = 0, half)]
      if (mod(n, 2) == 0) then
         psd(2:half) = 2.0_dp * psd(2:half)
      else
         psd(2:half + 1) = 2.0_dp * psd(2:half + 1)
      end if
   end subroutine periodogram_psd
end module gapbeam_draw_statistics
