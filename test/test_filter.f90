!> Butterworth low-pass filter: designed gain, measured gain and phase, delay, causality, errors.
!>
!> For orders 2, 4, 5 and f_c = 40 Hz at f_s = 1 kHz and 10 kHz: the gain computed from the
!> section coefficients is 1 at DC and 1/sqrt(2) at f_c, and follows the warped Butterworth law
!> 1/sqrt(1 + (tan(pi f/f_s)/tan(pi f_c/f_s))^(2N)). The filter is then driven by a unit sine at
!> 0.25, 1, 2 and 4 f_c; after 1.5 s (over 100 time constants of the slowest pole) the amplitude
!> and phase are fitted by least squares over 1 s (an integer number of periods, where the
!> sampled sine and cosine are exactly orthogonal) and compared with `lowpass_response`, and
!> with the analogue target 1/sqrt(1 + (f/f_c)^(2N)): to 3 % at 10 kHz, while at any rate the
!> stop band must be at least as attenuated as the target. A ramp checks the low-frequency
!> delay: its steady output is the input delayed by the group delay at 0 Hz.
program test_filter
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_filter, only: lowpass_t, design_lowpass, lowpass_gain, lowpass_response, &
      lowpass_group_delay, butterworth_gain
   implicit none
   real(dp), parameter :: fc = 40.0_dp                         ! cutoff [Hz]
   integer, parameter :: orders(3) = [2, 4, 5]
   real(dp), parameter :: rates(2) = [1000.0_dp, 10000.0_dp]   ! sampling rates [Hz]
   real(dp), parameter :: ratios(4) = [0.25_dp, 1.0_dp, 2.0_dp, 4.0_dp]   ! f / f_c
   integer :: i, j

   do j = 1, size(rates)
      do i = 1, size(orders)
         call designed_gain(orders(i), rates(j))
         call measured_gain(orders(i), rates(j))
         call ramp_delay(orders(i), rates(j))
      end do
   end do
   call causality()
   call design_errors()
   call analogue_target()
   call finish('test_filter')

contains

   !> Label of one design, e.g. 'N=4, fs=10000 Hz'.
   function label(order, fs) result(s)
      integer, intent(in) :: order
      real(dp), intent(in) :: fs
      character(len=:), allocatable :: s
      s = 'N=' // str(order) // ', fs=' // str(fs) // ' Hz'
   end function label

   !> Design a filter that must be accepted.
   subroutine design_ok(order, fs, f)
      integer, intent(in) :: order
      real(dp), intent(in) :: fs
      type(lowpass_t), intent(out) :: f
      type(error_t), allocatable :: err
      call design_lowpass(order, fc, fs, f, err)
      if (allocated(err)) then
         call check(label(order, fs) // ': design_lowpass succeeds', .false., err%message)
         error stop 'test_filter: cannot go on without a filter'
      end if
   end subroutine design_ok

   !> Gain from the coefficients: 1 at DC, 1/sqrt(2) at f_c, 0 at Nyquist, warped Butterworth.
   subroutine designed_gain(order, fs)
      integer, intent(in) :: order
      real(dp), intent(in) :: fs
      type(lowpass_t) :: f
      real(dp) :: freq, want, worst
      integer :: k
      call design_ok(order, fs, f)
      call check(label(order, fs) // ': (N+1)/2 sections', f%n_sections == (order + 1) / 2)
      call check_close(label(order, fs) // ': designed gain at f_c = 1/sqrt(2)', &
         lowpass_gain(f, fc), 1.0_dp / sqrt(2.0_dp), atol=1.0e-10_dp)
      call check_close(label(order, fs) // ': designed DC gain = 1', lowpass_gain(f, 0.0_dp), &
         1.0_dp, atol=1.0e-12_dp)
      call check_le(label(order, fs) // ': designed gain at Nyquist = 0', &
         lowpass_gain(f, 0.5_dp * fs), 1.0e-12_dp)
      worst = 0.0_dp
      do k = 1, 99                             ! 0.005 .. 0.495 f_s
         freq = 0.005_dp * real(k, dp) * fs
         want = 1.0_dp / sqrt(1.0_dp + (tan(pi * freq / fs) / tan(pi * fc / fs))**(2 * order))
         worst = max(worst, abs(lowpass_gain(f, freq) - want) / want)
      end do
      call check_le(label(order, fs) // ': gain = warped Butterworth law up to f_s/2 (rel.)', &
         worst, 1.0e-9_dp)
   end subroutine designed_gain

   !> Drive with a unit sine, fit amplitude and phase of the steady output, compare.
   subroutine measured_gain(order, fs)
      integer, intent(in) :: order
      real(dp), intent(in) :: fs
      type(lowpass_t) :: f
      real(dp) :: freq, amp, phase, g_design, g_analogue, dphi
      complex(dp) :: h
      integer :: k
      character(len=:), allocatable :: name
      call design_ok(order, fs, f)
      do k = 1, size(ratios)
         freq = ratios(k) * fc
         call reset_and_fit(f, freq, amp, phase)
         h = lowpass_response(f, freq)
         g_design = abs(h)
         g_analogue = butterworth_gain(order, fc, freq)
         name = label(order, fs) // ', f=' // str(freq) // ' Hz'
         call note(name // ': measured gain ' // str(amp) // ', designed ' // str(g_design) &
            // ', analogue ' // str(g_analogue) // ', measured/analogue - 1 = ' &
            // str(amp / g_analogue - 1.0_dp))
         call check_close(name // ': measured gain = lowpass_gain', amp, lowpass_gain(f, freq), &
            rtol=1.0e-6_dp)
         dphi = phase - atan2(aimag(h), real(h, dp))
         call check_le(name // ': |measured phase - arg H| (mod 2 pi) [rad]', &
            abs(atan2(sin(dphi), cos(dphi))), 1.0e-6_dp)
         if (fs >= 10000.0_dp) then
            call check_close(name // ': measured gain = analogue target to 3 %', amp, &
               g_analogue, rtol=0.03_dp)
         end if
         if (freq > fc) then
            call check_le(name // ': stop band at least as attenuated as analogue', amp, &
               g_analogue)
         end if
      end do
   end subroutine measured_gain

   !> Reset, feed sin(2 pi freq t) for 1.5 s, then fit y = amp sin(2 pi freq t + phase) over
   !> the next 1 s (an integer number of periods for an integer freq in Hz).
   subroutine reset_and_fit(f, freq, amp, phase)
      type(lowpass_t), intent(inout) :: f
      real(dp), intent(in) :: freq             ! [Hz]
      real(dp), intent(out) :: amp, phase      ! [-], [rad]
      real(dp) :: w, y, cs, sn
      integer :: n, n_settle, n_fit
      n_settle = nint(1.5_dp * f%sample_rate_hz)
      n_fit = nint(f%sample_rate_hz)
      w = 2.0_dp * pi * freq / f%sample_rate_hz
      call f%reset()
      cs = 0.0_dp
      sn = 0.0_dp
      do n = 0, n_settle + n_fit - 1
         y = f%apply(sin(w * real(n, dp)))
         if (n >= n_settle) then
            sn = sn + y * sin(w * real(n, dp))
            cs = cs + y * cos(w * real(n, dp))
         end if
      end do
      sn = 2.0_dp * sn / real(n_fit, dp)       ! amp cos(phase)
      cs = 2.0_dp * cs / real(n_fit, dp)       ! amp sin(phase)
      amp = hypot(sn, cs)
      phase = atan2(cs, sn)
   end subroutine reset_and_fit

   !> A ramp x_n = n comes out as x_n - tau f_s once the transient has died.
   subroutine ramp_delay(order, fs)
      integer, intent(in) :: order
      real(dp), intent(in) :: fs
      type(lowpass_t) :: f
      real(dp) :: lag, tau, tau_digital, tau_analogue, y
      integer :: n, n_settle, n_avg
      call design_ok(order, fs, f)
      n_settle = nint(1.5_dp * fs)
      n_avg = 100
      lag = 0.0_dp
      do n = 0, n_settle + n_avg - 1
         y = f%apply(real(n, dp))
         if (n >= n_settle) lag = lag + (real(n, dp) - y)
      end do
      lag = lag / real(n_avg, dp) / fs                            ! [s]
      tau = lowpass_group_delay(f)
      tau_digital = 1.0_dp / (2.0_dp * fs * tan(pi * fc / fs) * sin(pi / real(2 * order, dp)))
      tau_analogue = 1.0_dp / (2.0_dp * pi * fc * sin(pi / real(2 * order, dp)))
      call note(label(order, fs) // ': low-frequency delay ' // str(1.0e3_dp * tau) &
         // ' ms (analogue filter ' // str(1.0e3_dp * tau_analogue) // ' ms)')
      call check_close(label(order, fs) // ': ramp lag = lowpass_group_delay [s]', lag, tau, &
         rtol=1.0e-6_dp)
      call check_close(label(order, fs) // ': group delay = 1/(2 fs tan(pi fc/fs) sin(pi/2N))', &
         tau, tau_digital, rtol=1.0e-9_dp)
      call check_close(label(order, fs) // ': group delay = analogue 1/(2 pi fc sin(pi/2N))', &
         tau, tau_analogue, rtol=0.01_dp)
   end subroutine ramp_delay

   !> Output before the first non-zero input is exactly zero; later input never changes
   !> earlier output; reset returns to the zero state.
   subroutine causality()
      integer, parameter :: n0 = 100, n = 400
      type(lowpass_t) :: f, fresh
      real(dp) :: x1(n), x2(n), y1(n), y2(n), h1(n), h2(n)
      integer :: k
      call design_ok(4, 1000.0_dp, f)
      fresh = f
      x1 = 0.0_dp
      x1(n0 + 1:) = [(sin(0.3_dp * real(k, dp)) + 0.5_dp, k = 1, n - n0)]
      do k = 1, n
         y1(k) = f%apply(x1(k))
      end do
      call check('causal: output before the first non-zero input is exactly 0', &
         all(y1(1:n0) == 0.0_dp))
      call check('causal: output at the first non-zero input is non-zero (b0 > 0)', &
         y1(n0 + 1) /= 0.0_dp)
      x2 = x1
      x2(n0 + 51:) = -3.0_dp                     ! change the input after sample n0 + 50
      call f%reset()
      call check('reset: all states are zero', all(f%s == 0.0_dp))
      do k = 1, n
         y2(k) = f%apply(x2(k))
      end do
      call check('causal: reset restarts from rest (output of the same input is identical)', &
         all(y2(1:n0 + 50) == y1(1:n0 + 50)))
      call check('causal: a later change of the input does not change earlier output', &
         all(y2(1:n0 + 50) == y1(1:n0 + 50)) .and. y2(n0 + 51) /= y1(n0 + 51))
      call f%reset()
      do k = 1, n
         y1(k) = f%apply(0.0_dp)
      end do
      call check('reset: zero input after reset gives exactly zero output', all(y1 == 0.0_dp))
      h1 = 0.0_dp
      h1(1) = 1.0_dp
      h2 = h1
      do k = 1, n
         h1(k) = f%apply(h1(k))
         h2(k) = fresh%apply(h2(k))
      end do
      call check('reset: impulse response after reset = that of a new filter (bitwise)', &
         all(h1 == h2))
      call check_close('impulse response sums to the DC gain 1', sum(h1), 1.0_dp, &
         rtol=1.0e-9_dp)
   end subroutine causality

   !> Bad parameters are refused with a message naming the parameter and its value.
   subroutine design_errors()
      type(lowpass_t) :: f
      type(error_t), allocatable :: err
      call design_lowpass(0, fc, 1000.0_dp, f, err)
      call check('order 0 refused', allocated(err))
      if (allocated(err)) call check('order 0: message names order and value: ' &
         // err%message, index(err%message, 'order') > 0 .and. index(err%message, 'got 0') > 0)
      call design_lowpass(13, fc, 1000.0_dp, f, err)
      call check('order 13 refused', allocated(err))
      if (allocated(err)) call check('order 13: message names order and value', &
         index(err%message, 'order') > 0 .and. index(err%message, '13') > 0)
      call check('refused design leaves the default filter', f%order == 0 &
         .and. f%n_sections == 0)
      call design_lowpass(4, 600.0_dp, 1000.0_dp, f, err)
      call check('cutoff 600 Hz above Nyquist (500 Hz) refused', allocated(err))
      if (allocated(err)) call check('cutoff above Nyquist: message names cutoff_hz, value ' &
         // 'and the 2.2x rule: ' // err%message, index(err%message, 'cutoff_hz') > 0 &
         .and. index(err%message, '600') > 0 .and. index(err%message, '2.2x') > 0)
      call design_lowpass(4, 450.0_dp, 1000.0_dp, f, err)
      call check('cutoff = 0.45 x sample rate refused', allocated(err))
      call design_lowpass(4, 449.0_dp, 1000.0_dp, f, err)
      call check('cutoff just below 0.45 x sample rate accepted', .not. allocated(err))
      call design_lowpass(4, 0.0_dp, 1000.0_dp, f, err)
      call check('cutoff 0 refused', allocated(err))
      if (allocated(err)) call check('cutoff 0: message names cutoff_hz', &
         index(err%message, 'cutoff_hz') > 0)
      call design_lowpass(4, fc, -1.0_dp, f, err)
      call check('negative sample rate refused', allocated(err))
      if (allocated(err)) call check('negative sample rate: message names sample_rate_hz', &
         index(err%message, 'sample_rate_hz') > 0)
      call design_lowpass(1, fc, 1000.0_dp, f, err)
      call check('order 1 accepted', .not. allocated(err))
      call design_lowpass(12, fc, 1000.0_dp, f, err)
      call check('order 12 accepted', .not. allocated(err))
      if (.not. allocated(err)) call check_close('order 12: designed gain at f_c = 1/sqrt(2)', &
         lowpass_gain(f, fc), 1.0_dp / sqrt(2.0_dp), atol=1.0e-10_dp)
   end subroutine design_errors

   !> The analogue target itself.
   subroutine analogue_target()
      call check_close('butterworth_gain at 0 = 1', butterworth_gain(4, fc, 0.0_dp), 1.0_dp, &
         rtol=1.0e-15_dp)
      call check_close('butterworth_gain at f_c = 1/sqrt(2)', butterworth_gain(5, fc, fc), &
         1.0_dp / sqrt(2.0_dp), rtol=1.0e-15_dp)
      call check_close('butterworth_gain N=1 at 2 f_c = 1/sqrt(5)', &
         butterworth_gain(1, fc, 2.0_dp * fc), 1.0_dp / sqrt(5.0_dp), rtol=1.0e-15_dp)
      call check_close('butterworth_gain N=12 at 1e6 f_c = 1e-72 (no overflow)', &
         butterworth_gain(12, fc, 1.0e6_dp * fc), 1.0e-72_dp, rtol=1.0e-12_dp)
   end subroutine analogue_target
end program test_filter
