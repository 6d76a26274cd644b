!> The stated error of an exponent against sequences whose error of the mean is known: white
!> noise, an AR(1) sequence (integrated autocorrelation time 4.5 and 19.5 periods), a sequence
!> periodic over whole orbit periods (its oscillation is no noise) and one whose period is not
!> known to the estimator. Each noisy case is run over 40 deterministic realisations: the RMS
!> of the stated sigma against the known one, and the RMS of (lambda - true) / sigma (near 1
!> for an honest error bar), within stated factors.
program test_exponent_sigma
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_testing, only: check, check_le, finish, note
   use gapbeam_error, only: str
   use gapbeam_attractor, only: exponent_estimate
   implicit none
   integer, parameter :: n = 20000, reps = 40
   integer(int64) :: seed = 20261129_int64

   call ar1_errors_are_honest(0.0_dp, 'white noise')
   call ar1_errors_are_honest(0.8_dp, 'AR(1) phi = 0.8')
   call ar1_errors_are_honest(0.95_dp, 'AR(1) phi = 0.95')
   call periodic_sequence_has_no_error()
   call finish('test_exponent_sigma')

contains

   !> A uniform number in (0, 1) (Park and Miller's minimal standard, deterministic).
   real(dp) function uniform()
      seed = modulo(48271_int64 * seed, 2147483647_int64)
      uniform = real(seed, dp) / 2147483647.0_dp
   end function uniform

   !> A standard normal number (Box and Muller).
   real(dp) function normal()
      normal = sqrt(-2.0_dp * log(uniform())) * cos(2.0_dp * pi * uniform())
   end function normal

   !> x_k = mu + phi x_(k-1) + e_k, e_k ~ N(0, 1), started in its stationary law: the standard
   !> error of the mean of the m values the estimator keeps is 1 / ((1 - phi) sqrt(m)) to
   !> O(1/m) (the integrated autocorrelation time is (1 + phi) / (2 (1 - phi))).
   subroutine ar1_errors_are_honest(phi, name)
      real(dp), intent(in) :: phi
      character(len=*), intent(in) :: name
      real(dp), parameter :: mu = 3.0_dp, period = 1.0_dp
      real(dp) :: x(n), lambda, sigma, known, ratio2, z2
      integer :: r, k, m
      m = n - n / 10
      known = 1.0_dp / ((1.0_dp - phi) * sqrt(real(m, dp)))
      ratio2 = 0.0_dp;  z2 = 0.0_dp
      do r = 1, reps
         x(1) = normal() / sqrt(1.0_dp - phi**2)
         do k = 2, n
            x(k) = phi * x(k - 1) + normal()
         end do
         call exponent_estimate(mu + x, period, 1, lambda, sigma)
         ratio2 = ratio2 + (sigma / known)**2
         z2 = z2 + ((lambda - mu) / sigma)**2
      end do
      ratio2 = sqrt(ratio2 / reps);  z2 = sqrt(z2 / reps)
      call note(name // ': RMS stated / known sigma ' // str(ratio2) // ', RMS (lambda - mu) / sigma ' &
                // str(z2) // ' over ' // str(reps) // ' records of ' // str(n))
      ! sigma is the larger of two estimates: at most 35 % high on average, at most 15 % low
      call check_le(name // ': RMS stated sigma / known >= 0.85', 0.85_dp, ratio2)
      call check_le(name // ': RMS stated sigma / known <= 1.35', ratio2, 1.35_dp)
      ! a sigma estimated from about 9 degrees of freedom makes z a Student t (RMS sqrt(9/7) =
      ! 1.13); over 40 records its RMS scatters by about 0.13: 1.4 is 2 of those above
      call check_le(name // ': RMS (lambda - mu) / sigma <= 1.4', z2, 1.4_dp)
      call check_le(name // ': RMS (lambda - mu) / sigma >= 0.5', 0.5_dp, z2)
   end subroutine ar1_errors_are_honest

   !> A period-7 orbit's stretchings (a large oscillation within the orbit period, the same sum
   !> over each): sigma at round-off; and the same sequence given as q = 1 (its period not
   !> found): sigma bounded by the oscillation's own error of the mean, amplitude x q / m.
   subroutine periodic_sequence_has_no_error()
      integer, parameter :: q = 7
      real(dp), parameter :: a = 5.0_dp, mu = -0.4_dp
      real(dp) :: x(2003), lambda, sigma
      integer :: k, m
      do k = 1, size(x)
         x(k) = mu + a * sin(2.0_dp * pi * k / q) + 0.5_dp * a * cos(6.0_dp * pi * k / q)
      end do
      call exponent_estimate(x, 1.0_dp, q, lambda, sigma)
      m = size(x) - size(x) / 10
      call check_le('period 7, q = 7: sigma at round-off', sigma, 1.0e-12_dp)
      call check_le('period 7, q = 7: |lambda - mu| <= a q / m', abs(lambda - mu), &
                    1.5_dp * a * q / m)
      call exponent_estimate(x, 1.0_dp, 1, lambda, sigma)
      call note('period 7 given as q = 1: sigma ' // str(sigma) // ', |lambda - mu| ' // &
                str(abs(lambda - mu)))
      call check_le('period 7, q = 1: sigma <= 1.5 a q / m', sigma, 1.5_dp * a * q / m)
   end subroutine periodic_sequence_has_no_error
end program test_exponent_sigma
