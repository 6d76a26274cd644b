!> Rayleigh damping C = beta M + gamma K of the linear structure (beam and boundary springs,
!> never the stop springs), given directly or fitted to two (frequency, ratio) pairs.
module gapbeam_damping
   use gapbeam_kinds, only: dp, pi
   implicit none
   private
   public :: damping_t, rayleigh_from_ratios, modal_damping_ratio, damping_words

   character(len=*), parameter :: damping_words = "'none', 'rayleigh', 'ratios'"

   !> Damping description; after `rayleigh_from_ratios` only the coefficients matter.
   type :: damping_t
      character(len=16) :: model = 'none'          !! 'none', 'rayleigh' or 'ratios'
      real(dp) :: mass_coefficient = 0.0_dp        !! beta in C = beta M + gamma K [1/s]
      real(dp) :: stiffness_coefficient = 0.0_dp   !! gamma [s]
      real(dp) :: frequency1_hz = 0.0_dp           !! 'ratios': first frequency [Hz]
      real(dp) :: ratio1 = 0.0_dp                  !! 'ratios': damping ratio at frequency1 [-]
      real(dp) :: frequency2_hz = 0.0_dp           !! 'ratios': second frequency [Hz]
      real(dp) :: ratio2 = 0.0_dp                  !! 'ratios': damping ratio at frequency2 [-]
   end type damping_t

contains

   !> Coefficients (beta, gamma) with zeta(f) = beta/(2 omega) + gamma omega/2 through two pairs.
   pure subroutine rayleigh_from_ratios(f1, z1, f2, z2, beta, gamma)
      real(dp), intent(in) :: f1, z1, f2, z2   !! frequencies [Hz] and ratios [-]
      real(dp), intent(out) :: beta            !! mass coefficient [1/s]
      real(dp), intent(out) :: gamma           !! stiffness coefficient [s]
      real(dp) :: w1, w2
      w1 = 2.0_dp * pi * f1;  w2 = 2.0_dp * pi * f2
      beta = 2.0_dp * w1 * w2 * (z1 * w2 - z2 * w1) / (w2**2 - w1**2)
      gamma = 2.0_dp * (z2 * w2 - z1 * w1) / (w2**2 - w1**2)
   end subroutine rayleigh_from_ratios

   !> Modal damping ratio of Rayleigh damping at a frequency [-].
   elemental function modal_damping_ratio(beta, gamma, f_hz) result(zeta)
      real(dp), intent(in) :: beta    !! mass coefficient [1/s]
      real(dp), intent(in) :: gamma   !! stiffness coefficient [s]
      real(dp), intent(in) :: f_hz    !! frequency [Hz]
      real(dp) :: zeta, w
      w = 2.0_dp * pi * f_hz
      zeta = beta / (2.0_dp * w) + gamma * w / 2.0_dp
   end function modal_damping_ratio
end module gapbeam_damping
