!> The Hertz stop law: a power-law spring without damper, acting in contact only,
!>    f = k d^p  while d > 0,   f = 0  otherwise   (p in [1, 10]; 3/2 for a sphere on a flat),
!> k in N/m^p. Continuous at an onset, released where the penetration vanishes.
module gapbeam_law_hertz
   use gapbeam_kinds, only: dp
   use gapbeam_law, only: contact_law_t, law_caps_t
   implicit none
   private
   public :: hertz_law_t

   !> The Hertz law.
   type, extends(contact_law_t) :: hertz_law_t
   contains
      procedure :: caps => hertz_caps
      procedure :: force => hertz_force
      procedure :: extended => hertz_extended
      procedure :: rate => hertz_rate
      procedure :: elastic => hertz_force_of_d
      procedure :: energy => hertz_energy
      procedure :: solve => hertz_solve
      procedure :: releases_early => hertz_never
      procedure :: jumps => hertz_never
      procedure :: onset_rate => hertz_onset_rate
   end type hertz_law_t

contains

   !> What the Hertz law can do: no damper, not piecewise linear; it is the normal law of a
   !> ring support too, whose stick stiffness must then be given (k is in N/m^p).
   pure function hertz_caps(self) result(c)
      class(hertz_law_t), intent(in) :: self   !! law
      type(law_caps_t) :: c
      c = law_caps_t(name='hertz', title='Hertz', force_text='f = k d^p in contact', piecewise_linear=.false., &
         uses_damping=.false., uses_exponent=.true., exponent_min=1.0_dp, exponent_max=10.0_dp, &
         rings=.true., linear_stiffness=.false.)
   end function hertz_caps

   pure real(dp) function hertz_force(self, k, c, p, d, dd) result(f)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness [N/m^p], unused, exponent
      real(dp), intent(in) :: d, dd               !! penetration [m], rate [m/s]
      if (d <= 0.0_dp) then
         f = 0.0_dp
      else
         f = k * d**p
      end if
   end function hertz_force

   pure real(dp) function hertz_extended(self, k, c, p, d, dd) result(f)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, unused, exponent
      real(dp), intent(in) :: d, dd               !! penetration, rate
      f = sign(k * abs(d)**p, d)
   end function hertz_extended

   pure real(dp) function hertz_rate(self, k, c, p, d, dd, ddd) result(r)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, unused, exponent
      real(dp), intent(in) :: d, dd, ddd          !! penetration, rate, its rate
      r = k * p * max(d, 0.0_dp)**(p - 1.0_dp) * dd
   end function hertz_rate

   pure real(dp) function hertz_force_of_d(self, k, c, p, d) result(e)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, unused, exponent
      real(dp), intent(in) :: d                   !! penetration
      e = 0.0_dp
      if (d > 0.0_dp) e = k * d**p
   end function hertz_force_of_d

   pure real(dp) function hertz_energy(self, k, c, p, d) result(e)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, unused, exponent
      real(dp), intent(in) :: d                   !! penetration
      e = 0.0_dp
      if (d > 0.0_dp) e = k * d**(p + 1.0_dp) / (p + 1.0_dp)
   end function hertz_energy

   !> phi(d) = d + h k d^p - d* = 0 on [0, d*]: safeguarded Newton (convex for p >= 1, so
   !> Newton from d* converges monotonically; bisection guards it); f = k d^p.
   pure real(dp) function hertz_solve(self, k, c, p, d_star, v_star, h, kappa) result(f)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, unused, exponent
      real(dp), intent(in) :: d_star, v_star      !! penetration and rate with f = 0
      real(dp), intent(in) :: h, kappa            !! compliance [m/N], [1/s]
      real(dp) :: d, dlo, dhi, phi, dphi, dn
      integer :: it
      f = 0.0_dp
      if (d_star <= 0.0_dp) return
      dlo = 0.0_dp;  dhi = d_star;  d = d_star
      do it = 1, 200
         phi = d + h * k * d**p - d_star
         if (phi > 0.0_dp) then
            dhi = d
         else
            dlo = d
         end if
         dphi = 1.0_dp + h * k * p * d**(p - 1.0_dp)
         dn = d - phi / dphi
         if (dn <= dlo .or. dn >= dhi) dn = 0.5_dp * (dlo + dhi)
         if (abs(dn - d) <= 4.0_dp * epsilon(1.0_dp) * d) then
            d = dn;  exit
         end if
         d = dn
      end do
      f = k * d**p
   end function hertz_solve

   pure logical function hertz_never(self, k, c, p) result(yes)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, unused, exponent
      yes = .false.
   end function hertz_never

   !> The force grows as k d^p: no finite rate at the onset for p > 1 (0 returned).
   pure real(dp) function hertz_onset_rate(self, k, c, p, dd) result(r)
      class(hertz_law_t), intent(in) :: self      !! law
      real(dp), intent(in) :: k, c, p             !! stiffness, unused, exponent
      real(dp), intent(in) :: dd                  !! penetration rate
      r = 0.0_dp
   end function hertz_onset_rate
end module gapbeam_law_hertz
