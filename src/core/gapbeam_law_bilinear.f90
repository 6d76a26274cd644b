!> The bilinear stop law: a linear spring k with a linear damper c, acting in contact only,
!>    f = max(0, k d + c d')  while d > 0,   f = 0  otherwise,
!> so the damper never pulls: with a damper the contact releases where k d + c d' reaches
!> zero, before the penetration does, and the force jumps to c d' at an onset.
module gapbeam_law_bilinear
   use gapbeam_kinds, only: dp
   use gapbeam_law, only: contact_law_t, law_caps_t
   implicit none
   private
   public :: bilinear_law_t

   !> The bilinear law.
   type, extends(contact_law_t) :: bilinear_law_t
   contains
      procedure :: caps => bilinear_caps
      procedure :: force => bilinear_force
      procedure :: extended => bilinear_extended
      procedure :: rate => bilinear_rate
      procedure :: elastic => bilinear_elastic
      procedure :: energy => bilinear_energy
      procedure :: solve => bilinear_solve
      procedure :: releases_early => bilinear_damped
      procedure :: jumps => bilinear_damped
      procedure :: onset_rate => bilinear_onset_rate
   end type bilinear_law_t

contains

   !> What the bilinear law can do: everything; it is the piecewise-linear law.
   pure function bilinear_caps(self) result(c)
      class(bilinear_law_t), intent(in) :: self   !! law
      type(law_caps_t) :: c
      c = law_caps_t(name='bilinear', title='bilinear', force_text='f = max(0, k d + c d'') in contact', &
         piecewise_linear=.true., uses_damping=.true., uses_exponent=.false., rings=.true., &
         linear_stiffness=.true.)
   end function bilinear_caps

   pure real(dp) function bilinear_force(self, k, c, p, d, dd) result(f)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness [N/m], damper [N s/m], unused
      real(dp), intent(in) :: d, dd               !! penetration [m], rate [m/s]
      if (d <= 0.0_dp) then
         f = 0.0_dp
      else
         f = max(0.0_dp, k * d + c * dd)
      end if
   end function bilinear_force

   pure real(dp) function bilinear_extended(self, k, c, p, d, dd) result(f)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, damper, unused
      real(dp), intent(in) :: d, dd               !! penetration, rate
      f = k * d + c * dd
   end function bilinear_extended

   pure real(dp) function bilinear_rate(self, k, c, p, d, dd, ddd) result(r)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, damper, unused
      real(dp), intent(in) :: d, dd, ddd          !! penetration, rate, its rate
      r = k * dd + c * ddd
   end function bilinear_rate

   pure real(dp) function bilinear_elastic(self, k, c, p, d) result(e)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, damper, unused
      real(dp), intent(in) :: d                   !! penetration
      e = k * max(d, 0.0_dp)
   end function bilinear_elastic

   pure real(dp) function bilinear_energy(self, k, c, p, d) result(e)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, damper, unused
      real(dp), intent(in) :: d                   !! penetration
      e = 0.0_dp
      if (d > 0.0_dp) e = 0.5_dp * k * d**2
   end function bilinear_energy

   !> Closed form: f = (k d* + c v*) / (1 + (k + c kappa) h); if the damper would push on
   !> at d <= 0 the contact sits at d = 0 (f = d* / h).
   pure real(dp) function bilinear_solve(self, k, c, p, d_star, v_star, h, kappa) result(f)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, damper, unused
      real(dp), intent(in) :: d_star, v_star      !! penetration and rate with f = 0
      real(dp), intent(in) :: h, kappa            !! compliance [m/N], [1/s]
      real(dp) :: lam
      f = 0.0_dp
      if (d_star <= 0.0_dp) return
      lam = k * d_star + c * v_star
      if (lam <= 0.0_dp) return
      f = lam / (1.0_dp + (k + c * kappa) * h)
      if (d_star - h * f <= 0.0_dp) f = d_star / h
   end function bilinear_solve

   !> With a damper the force jumps at an onset and can vanish before the penetration does.
   pure logical function bilinear_damped(self, k, c, p) result(yes)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, damper, unused
      yes = c > 0.0_dp
   end function bilinear_damped

   pure real(dp) function bilinear_onset_rate(self, k, c, p, dd) result(r)
      class(bilinear_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, damper, unused
      real(dp), intent(in) :: dd                  !! penetration rate
      r = k * max(dd, 0.0_dp)
   end function bilinear_onset_rate
end module gapbeam_law_bilinear
