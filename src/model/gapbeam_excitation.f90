!> Harmonic base excitation u_b(t) = (A_pp/2) sin(Omega t).
!>
!> The equations are written in coordinates relative to the base, so the load is
!> P(t) = -M r u_b''(t) = M r (A_pp/2) Omega^2 sin(Omega t); the stops move with the base.
module gapbeam_excitation
   use gapbeam_kinds, only: dp, pi
   implicit none
   private
   public :: forcing_t, base_acceleration, load_factor, forcing_period, forcing_omega

   !> Harmonic base motion.
   type :: forcing_t
      real(dp) :: frequency_hz = 10.0_dp    !! forcing frequency f [Hz]
      real(dp) :: amplitude_pp = 0.0_dp     !! base displacement, peak to peak [m]
   end type forcing_t

contains

   !> Angular frequency Omega [rad/s].
   pure real(dp) function forcing_omega(f)
      type(forcing_t), intent(in) :: f   !! forcing
      forcing_omega = 2.0_dp * pi * f%frequency_hz
   end function forcing_omega

   !> Forcing period [s].
   pure real(dp) function forcing_period(f)
      type(forcing_t), intent(in) :: f   !! forcing
      forcing_period = 1.0_dp / f%frequency_hz
   end function forcing_period

   !> Base acceleration u_b''(t) [m/s^2].
   pure real(dp) function base_acceleration(f, t)
      type(forcing_t), intent(in) :: f   !! forcing
      real(dp), intent(in) :: t          !! time [s]
      real(dp) :: w
      w = forcing_omega(f)
      base_acceleration = -0.5_dp * f%amplitude_pp * w**2 * sin(w * t)
   end function base_acceleration

   !> Scalar s(t) with P(t) = s(t) * (M r): s = -u_b''(t) [m/s^2].
   pure real(dp) function load_factor(f, t)
      type(forcing_t), intent(in) :: f   !! forcing
      real(dp), intent(in) :: t          !! time [s]
      load_factor = -base_acceleration(f, t)
   end function load_factor
end module gapbeam_excitation
