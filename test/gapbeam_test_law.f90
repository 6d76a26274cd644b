!> A contact law that exists only in the tests: the Hunt-Crossley law, a power-law spring
!> whose damper is scaled by the penetration,
!>    f = d^p max(0, k + c d')  while d > 0,   f = 0  otherwise,
!> so the force is continuous at an onset (no jump, unlike the bilinear damper) and the
!> contact releases where k + c d' reaches zero. k [N/m^p], c [N s/m^(p+1)], p in [1, 3].
!>
!> It shows that a law is one module and one registry line: test_contact adds it to a
!> model with `add_law` (gapbeam_laws) and nothing in src/ names it.
module gapbeam_test_law
   use gapbeam_kinds, only: dp
   use gapbeam_law, only: contact_law_t, law_caps_t
   implicit none
   private
   public :: hunt_crossley_law_t

   !> The Hunt-Crossley law.
   type, extends(contact_law_t) :: hunt_crossley_law_t
   contains
      procedure :: caps => hc_caps
      procedure :: force => hc_force
      procedure :: extended => hc_extended
      procedure :: rate => hc_rate
      procedure :: elastic => hc_elastic
      procedure :: energy => hc_energy
      procedure :: solve => hc_solve
      procedure :: releases_early => hc_damped
      procedure :: jumps => hc_never
      procedure :: onset_rate => hc_onset_rate
   end type hunt_crossley_law_t

contains

   !> Not piecewise linear (the exact integrator refuses it), a damper, an exponent in
   !> [1, 3], not a ring support's normal law.
   pure function hc_caps(self) result(c)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      type(law_caps_t) :: c
      c = law_caps_t(name='hunt_crossley', title='Hunt-Crossley', &
         force_text='f = d^p max(0, k + c d'') in contact', piecewise_linear=.false., &
         uses_damping=.true., uses_exponent=.true., exponent_min=1.0_dp, exponent_max=3.0_dp, &
         rings=.false., linear_stiffness=.false.)
   end function hc_caps

   pure real(dp) function hc_force(self, k, c, p, d, dd) result(f)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      real(dp), intent(in) :: d, dd                    !! penetration, rate
      f = 0.0_dp
      if (d > 0.0_dp) f = d**p * max(0.0_dp, k + c * dd)
   end function hc_force

   pure real(dp) function hc_extended(self, k, c, p, d, dd) result(f)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      real(dp), intent(in) :: d, dd                    !! penetration, rate
      f = sign(abs(d)**p, d) * (k + c * dd)
   end function hc_extended

   pure real(dp) function hc_rate(self, k, c, p, d, dd, ddd) result(r)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      real(dp), intent(in) :: d, dd, ddd               !! penetration, rate, its rate
      r = p * max(d, 0.0_dp)**(p - 1.0_dp) * dd * (k + c * dd) + max(d, 0.0_dp)**p * c * ddd
   end function hc_rate

   pure real(dp) function hc_elastic(self, k, c, p, d) result(e)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      real(dp), intent(in) :: d                        !! penetration
      e = k * max(d, 0.0_dp)**p
   end function hc_elastic

   pure real(dp) function hc_energy(self, k, c, p, d) result(e)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      real(dp), intent(in) :: d                        !! penetration
      e = k * max(d, 0.0_dp)**(p + 1.0_dp) / (p + 1.0_dp)
   end function hc_energy

   !> With d = d* - h f and d' = v* - kappa h f = v* - kappa (d* - d):
   !> psi(d) = d^p max(0, k + c (v* - kappa (d* - d))) - (d* - d) / h = 0 on [0, d*]. psi is
   !> increasing (every term is), psi(0) < 0 <= psi(d*): one root, by Newton safeguarded with
   !> bisection.
   pure real(dp) function hc_solve(self, k, c, p, d_star, v_star, h, kappa) result(f)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      real(dp), intent(in) :: d_star, v_star, h, kappa !! see contact_law_t%solve
      real(dp) :: lo, hi, d, g, psi, dpsi, dn
      integer :: it
      f = 0.0_dp
      if (d_star <= 0.0_dp) return
      if (k + c * v_star <= 0.0_dp) return          ! released at d = d*: f = 0 solves it
      lo = 0.0_dp;  hi = d_star;  d = d_star
      do it = 1, 200
         g = max(0.0_dp, k + c * (v_star - kappa * (d_star - d)))
         psi = d**p * g - (d_star - d) / h
         if (psi > 0.0_dp) then
            hi = d
         else
            lo = d
         end if
         dpsi = p * d**(p - 1.0_dp) * g + 1.0_dp / h
         if (g > 0.0_dp) dpsi = dpsi + d**p * c * kappa
         dn = d - psi / dpsi
         if (dn <= lo .or. dn >= hi) dn = 0.5_dp * (lo + hi)
         if (abs(dn - d) <= 4.0_dp * epsilon(1.0_dp) * d) then
            d = dn;  exit
         end if
         d = dn
      end do
      f = (d_star - d) / h
   end function hc_solve

   pure logical function hc_damped(self, k, c, p) result(yes)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      yes = c > 0.0_dp
   end function hc_damped

   pure logical function hc_never(self, k, c, p) result(yes)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      yes = .false.
   end function hc_never

   !> The force grows as k d^p: k d' for p = 1, no finite rate for p > 1 (0 returned).
   pure real(dp) function hc_onset_rate(self, k, c, p, dd) result(r)
      class(hunt_crossley_law_t), intent(in) :: self   !! law
      real(dp), intent(in) :: k, c, p                  !! stiffness, damping, exponent
      real(dp), intent(in) :: dd                       !! penetration rate
      r = 0.0_dp
      if (p == 1.0_dp) r = (k + c * dd) * max(dd, 0.0_dp)
   end function hc_onset_rate
end module gapbeam_test_law
