!> Causal digital Butterworth low-pass filter for recorded signals (strain, displacement).
!>
!> Moon & Shaw low-pass filtered their strain signals at 40 Hz with an analogue filter before
!> taking Poincare maps. `lowpass_t` is the digital counterpart: the analogue Butterworth
!> prototype of order N mapped to the z-plane by the bilinear transform with pre-warping, run
!> as a cascade of second-order sections. Usage, one sample at a time in time order:
!>
!>     call design_lowpass(4, 40.0_dp, 1.0_dp / dt, f, err);  if (allocated(err)) return
!>     do i = 1, n
!>        strain_filtered(i) = f%apply(strain(i))
!>     end do
!>
!> One `lowpass_t` per signal (it carries the signal's history); `f%reset()` restarts it.
!>
!> **Analogue prototype.** |H_a(i w)|^2 = 1 / (1 + (w/W_c)^(2N)). Its N poles lie on the left
!> half of the circle of radius W_c, at s_k = W_c exp(i pi (2k + N - 1) / (2N)), k = 1..N, and
!> all N zeros are at infinity. The conjugate pair (k, N + 1 - k), k = 1..N/2, gives the section
!> W_c^2 / (s^2 + 2 zeta_k W_c s + W_c^2) with damping ratio zeta_k = sin((2k - 1) pi / (2N));
!> odd N adds the real pole s = -W_c, i.e. the first-order section W_c / (s + W_c).
!>
!> **Bilinear transform with pre-warping.** s = 2 f_s (1 - z^-1) / (1 + z^-1) maps the whole
!> imaginary axis onto the unit circle, analogue frequency w_a to digital frequency w [rad/s]
!> through w_a = 2 f_s tan(w / (2 f_s)): no aliasing, but a warped frequency axis. Designing
!> the prototype at the pre-warped W_c = 2 f_s tan(pi f_c / f_s) puts the -3 dB point of the
!> digital filter exactly at f_c. With K = tan(pi f_c / f_s) each section becomes
!>
!>     biquad:       K^2 (1 + 2 z^-1 + z^-2) / (a0 + 2 (K^2 - 1) z^-1 + (1 - 2 zeta K + K^2) z^-2),
!>                   a0 = 1 + 2 zeta K + K^2
!>     first order:  K (1 + z^-1) / ((1 + K) + (K - 1) z^-1)
!>
!> normalised to a0 = 1. The digital gain is exactly the analogue one on the warped axis,
!> |H(f)| = 1 / sqrt(1 + (tan(pi f / f_s) / tan(pi f_c / f_s))^(2N)): equal at 0 and f_c, flatter
!> in the pass band and falling faster in the stop band than the analogue target (the zeros at
!> infinity land on z = -1, so the gain is zero at the Nyquist frequency f_s/2). The difference
!> grows with f_c / f_s and with N: at 4 f_c for N = 5 the digital gain is 0.4 % below the
!> analogue one at f_s = 250 f_c, 34 % below at f_s = 25 f_c (`test_filter` prints the numbers).
!> Sample at f_s >= 10 f_c, better more (f_s <= 2.2 f_c is refused).
!>
!> **Pairing and order of the sections.** Each section takes one conjugate pole pair (or the
!> real pole) and two (one) of the zeros at z = -1. The sections run from the most damped to the
!> least damped (first-order section first, then zeta_k decreasing), so the resonant section
!> (Q = 1 / (2 zeta_1), peaking near f_c) sees an already low-passed signal. Every section has
!> unit DC gain: its numerator is g (1/4, 1/2, 1/4) (first order: g (1/2, 1/2)) with
!> g = 1 + a1 + a2 computed from the stored, rounded denominator, so the DC gain of the
!> implemented filter is 1 to rounding (without this, 1 + a1 + a2 ~ 4 K^2 cancels and the DC
!> gain would be off by ~eps / K^2). Each section runs in direct form II transposed,
!>
!>     y = b0 x + s1;   s1 = b1 x - a1 y + s2;   s2 = b2 x - a2 y
!>
!> whose two states stay of the order of the signal.
!>
!> **Delay.** The filter is causal, like the experiment's analogue filter: the output never
!> depends on later input, and the filtered signal lags the raw one. At low frequency the lag
!> is the group delay tau_0 = 1 / (2 pi f_c sin(pi / (2N))) (digital: 2 pi f_c replaced by
!> 2 f_s tan(pi f_c / f_s); `lowpass_group_delay` returns it from the coefficients); for
!> f_c = 40 Hz: N = 1: 3.98 ms, 2: 5.63 ms, 3: 7.96 ms, 4: 10.40 ms, 5: 12.88 ms, 6: 15.37 ms,
!> 8: 20.40 ms. Nearer f_c the delay is larger (for N >= 2 it peaks below f_c: at 0.64 f_c for
!> N = 2, closer to f_c for higher N). A Poincare map of the filtered signal taken at forcing
!> phase phi therefore sees the forcing-frequency component of the raw response at the earlier
!> phase phi + arg H(f_forcing) (arg H < 0; `lowpass_response` gives H), and each harmonic
!> with its own lag. The slowest pole decays as exp(-t / tau_0), so the first several tau_0 of
!> a record (or after `reset`) are the filter's own transient: discard them.
!>
!> Units: frequencies in Hz, delays in s. Orders 1..12.
module gapbeam_filter
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   implicit none
   private
   public :: lowpass_t, design_lowpass, lowpass_gain, lowpass_response, lowpass_group_delay, &
      butterworth_gain

   !> Highest filter order accepted by `design_lowpass`.
   integer, parameter, public :: max_filter_order = 12
   integer, parameter :: max_sections = 6    ! (max_filter_order + 1) / 2

   !> A causal digital Butterworth low-pass filter: designed by `design_lowpass`, fed one sample
   !> at a time by `apply`. Copying it copies the state.
   type :: lowpass_t
      integer :: order = 0                  !! analogue order N (1..12); 0: not designed [-]
      real(dp) :: cutoff_hz = 0.0_dp        !! -3 dB frequency [Hz]
      real(dp) :: sample_rate_hz = 0.0_dp   !! sampling rate of the input [Hz]
      integer :: n_sections = 0             !! number of sections, (N + 1) / 2 [-]
      !> numerators (b0, b1, b2) of the sections, in the order they are applied [-]
      real(dp) :: b(0:2, max_sections) = 0.0_dp
      !> denominators (a1, a2) of the sections, a0 = 1 [-]
      real(dp) :: a(2, max_sections) = 0.0_dp
      !> direct form II transposed states (s1, s2) of the sections [signal unit]
      real(dp) :: s(2, max_sections) = 0.0_dp
   contains
      !> Zero the states: the next sample starts from rest.
      procedure :: reset => lowpass_reset
      !> Push one sample, return the filtered sample: `y = f%apply(x)`.
      procedure :: apply => lowpass_apply
   end type lowpass_t

contains

   !> Design a Butterworth low-pass filter of order `order` with its -3 dB point at `cutoff_hz`
   !> for a signal sampled at `sample_rate_hz`: bilinear transform of the analogue prototype
   !> with frequency pre-warping (see the module header). The states start at zero.
   subroutine design_lowpass(order, cutoff_hz, sample_rate_hz, f, err)
      integer, intent(in) :: order                   !! analogue order N, 1..12 [-]
      real(dp), intent(in) :: cutoff_hz              !! -3 dB frequency, > 0, < 0.45 f_s [Hz]
      real(dp), intent(in) :: sample_rate_hz         !! sampling rate of the input [Hz]
      type(lowpass_t), intent(out) :: f              !! designed filter (default one on error)
      type(error_t), allocatable, intent(out) :: err !! why the design was refused
      character(len=*), parameter :: here = 'gapbeam_filter:design_lowpass: '
      real(dp) :: k, k2, zeta, a0, a1, a2, g
      integer :: j, m

      if (order < 1 .or. order > max_filter_order) then
         call fatal_error(err, here // 'order must be in 1..' // str(max_filter_order) &
            // ', got ' // str(order))
         return
      end if
      if (.not. (sample_rate_hz > 0.0_dp .and. sample_rate_hz <= huge(1.0_dp))) then
         call fatal_error(err, here // 'sample_rate_hz must be > 0 and finite, got ' &
            // str(sample_rate_hz))
         return
      end if
      if (.not. (cutoff_hz > 0.0_dp)) then
         call fatal_error(err, here // 'cutoff_hz must be > 0, got ' // str(cutoff_hz))
         return
      end if
      if (.not. (cutoff_hz < 0.45_dp * sample_rate_hz)) then
         call fatal_error(err, here // 'cutoff_hz = ' // str(cutoff_hz) &
            // ' Hz must be < 0.45 x sample_rate_hz = ' // str(0.45_dp * sample_rate_hz) &
            // ' Hz (Nyquist frequency ' // str(0.5_dp * sample_rate_hz) // ' Hz): the ' &
            // 'sampling rate must be at least ~2.2x the cutoff, better 10x')
         return
      end if

      f%order = order
      f%cutoff_hz = cutoff_hz
      f%sample_rate_hz = sample_rate_hz
      f%n_sections = (order + 1) / 2
      k = tan(pi * cutoff_hz / sample_rate_hz)     ! pre-warped W_c / (2 f_s)
      k2 = k * k
      m = 0
      if (mod(order, 2) == 1) then                 ! real pole -W_c: first-order section
         m = 1
         a1 = (k - 1.0_dp) / (1.0_dp + k)
         g = 1.0_dp + a1                           ! DC gain 1 for the stored a1
         f%b(:, m) = [0.5_dp * g, 0.5_dp * g, 0.0_dp]
         f%a(:, m) = [a1, 0.0_dp]
      end if
      do j = order / 2, 1, -1                      ! conjugate pairs, most damped first
         zeta = sin(pi * real(2 * j - 1, dp) / real(2 * order, dp))
         a0 = 1.0_dp + 2.0_dp * zeta * k + k2
         a1 = 2.0_dp * (k2 - 1.0_dp) / a0
         a2 = (1.0_dp - 2.0_dp * zeta * k + k2) / a0
         g = (1.0_dp + a1) + a2                    ! exact in floating point for small K
         m = m + 1
         f%b(:, m) = [0.25_dp * g, 0.5_dp * g, 0.25_dp * g]
         f%a(:, m) = [a1, a2]
      end do
   end subroutine design_lowpass

   !> Zero the states of all sections.
   pure subroutine lowpass_reset(self)
      class(lowpass_t), intent(inout) :: self   !! filter to restart
      self%s = 0.0_dp
   end subroutine lowpass_reset

   !> Push one input sample through the cascade and return the output sample.
   !> An input that has been zero since the design (or `reset`) gives exactly zero.
   function lowpass_apply(self, x) result(y)
      class(lowpass_t), intent(inout) :: self   !! filter; its states advance by one sample
      real(dp), intent(in) :: x                 !! input sample [signal unit]
      real(dp) :: y                             !! filtered sample [signal unit]
      real(dp) :: v
      integer :: j
      if (self%n_sections == 0) &
         error stop 'gapbeam_filter:apply: filter not designed (call design_lowpass first)'
      v = x
      do j = 1, self%n_sections
         y = self%b(0, j) * v + self%s(1, j)
         self%s(1, j) = self%b(1, j) * v - self%a(1, j) * y + self%s(2, j)
         self%s(2, j) = self%b(2, j) * v - self%a(2, j) * y
         v = y
      end do
      y = v
   end function lowpass_apply

   !> Complex frequency response H(e^(i 2 pi f / f_s)) of the designed digital filter, from the
   !> section coefficients. arg H < 0 is the phase lag of a sinusoid at `freq_hz`.
   pure function lowpass_response(f, freq_hz) result(h)
      type(lowpass_t), intent(in) :: f   !! designed filter
      real(dp), intent(in) :: freq_hz    !! frequency [Hz]
      complex(dp) :: h                   !! response [-]
      complex(dp) :: z1, z2
      real(dp) :: w
      integer :: j
      if (f%n_sections == 0) &
         error stop 'gapbeam_filter:lowpass_response: filter not designed'
      w = 2.0_dp * pi * freq_hz / f%sample_rate_hz     ! [rad/sample]
      z1 = cmplx(cos(w), -sin(w), dp)                   ! z^-1
      z2 = cmplx(cos(2.0_dp * w), -sin(2.0_dp * w), dp) ! z^-2
      h = (1.0_dp, 0.0_dp)
      do j = 1, f%n_sections
         h = h * ((f%b(0, j) + f%b(1, j) * z1 + f%b(2, j) * z2) &
                  / ((1.0_dp + f%a(1, j) * z1) + f%a(2, j) * z2))
      end do
   end function lowpass_response

   !> Gain |H(e^(i 2 pi f / f_s))| of the designed digital filter, from the section coefficients.
   pure function lowpass_gain(f, freq_hz) result(g)
      type(lowpass_t), intent(in) :: f   !! designed filter
      real(dp), intent(in) :: freq_hz    !! frequency [Hz]
      real(dp) :: g                      !! gain [-]
      g = abs(lowpass_response(f, freq_hz))
   end function lowpass_gain

   !> Group delay of the designed digital filter at zero frequency, from the section
   !> coefficients: the lag of a slowly varying signal. For a polynomial sum_n p_n z^-n it is
   !> sum_n n p_n / sum_n p_n samples; the sections add numerator minus denominator delays.
   pure function lowpass_group_delay(f) result(tau)
      type(lowpass_t), intent(in) :: f   !! designed filter
      real(dp) :: tau                    !! group delay at 0 Hz [s]
      integer :: j
      if (f%n_sections == 0) &
         error stop 'gapbeam_filter:lowpass_group_delay: filter not designed'
      tau = 0.0_dp
      do j = 1, f%n_sections
         tau = tau + (f%b(1, j) + 2.0_dp * f%b(2, j)) / ((f%b(0, j) + f%b(1, j)) + f%b(2, j)) &
                   - (f%a(1, j) + 2.0_dp * f%a(2, j)) / ((1.0_dp + f%a(1, j)) + f%a(2, j))
      end do
      tau = tau / f%sample_rate_hz
   end function lowpass_group_delay

   !> Gain of the analogue Butterworth design target, 1 / sqrt(1 + (f/f_c)^(2N)).
   elemental function butterworth_gain(order, cutoff_hz, freq_hz) result(g)
      integer, intent(in) :: order       !! order N [-]
      real(dp), intent(in) :: cutoff_hz  !! -3 dB frequency [Hz]
      real(dp), intent(in) :: freq_hz    !! frequency [Hz]
      real(dp) :: g                      !! gain [-]
      real(dp) :: r, q
      r = abs(freq_hz) / cutoff_hz
      if (r <= 1.0_dp) then
         g = 1.0_dp / sqrt(1.0_dp + r**(2 * order))
      else                               ! written in 1/r: no overflow far in the stop band
         q = (1.0_dp / r)**order
         g = q / sqrt(1.0_dp + q * q)
      end if
   end function butterworth_gain
end module gapbeam_filter
