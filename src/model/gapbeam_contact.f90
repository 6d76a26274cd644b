!> Stop (gap-support) laws: force magnitude and tangent from the penetration.
!>
!> A one-sided contact acts at one dof with a direction s = +1 (the stop is met when the dof
!> moves in +w, u >= gap) or s = -1 (u <= -gap). Its penetration is d = s*u - gap (d > 0: in
!> contact) and the force on the structure is -s*f with f >= 0 the magnitude returned here.
!> Displacements are relative to the base; the stops move with the base.
!>
!> * bilinear: f = max(0, k d + c d') while d > 0, else 0 (the damper never pulls);
!> * hertz:    f = k d^p while d > 0, else 0.
module gapbeam_contact
   use gapbeam_kinds, only: dp
   use gapbeam_model, only: dof_w
   implicit none
   private
   public :: stop_t, contact_force, solve_scalar_contact, law_bilinear, law_hertz
   public :: stop_side_words, stop_law_words, law_code

   integer, parameter :: law_bilinear = 1   !! code of the bilinear law
   integer, parameter :: law_hertz = 2      !! code of the Hertz law
   character(len=*), parameter :: stop_side_words = "'positive', 'negative', 'both'"
   character(len=*), parameter :: stop_law_words = "'bilinear', 'hertz'"

   !> A stop as the deck gives it ('both' sides means two one-sided contacts).
   type :: stop_t
      integer  :: node = -1                     !! node index [-]
      integer  :: dof = dof_w                   !! dof code (dof_w or dof_theta)
      character(len=16) :: side = 'positive'    !! 'positive', 'negative' or 'both'
      character(len=16) :: law = 'bilinear'     !! 'bilinear' or 'hertz'
      real(dp) :: gap = 0.0_dp                  !! clearance [m or rad]
      real(dp) :: stiffness = 0.0_dp            !! k [N/m] (bilinear) or [N/m^p] (hertz)
      real(dp) :: damping = 0.0_dp              !! contact damper c [N s/m] (bilinear only)
      real(dp) :: exponent = 1.5_dp             !! Hertz exponent p [-]
      real(dp) :: rule_factor = 0.0_dp          !! > 0: k = factor * calibrated spring [-]
      real(dp) :: rule_f1_ratio = 0.0_dp        !! rule target: f1 / f1(open structure) [-]
      real(dp) :: rule_f1_hz = 0.0_dp           !! rule target: f1 [Hz] (if ratio not given)
   end type stop_t

contains

   !> Law code of a word; 0 if unknown.
   pure integer function law_code(word)
      character(len=*), intent(in) :: word   !! 'bilinear' or 'hertz'
      select case (trim(word))
      case ('bilinear')
         law_code = law_bilinear
      case ('hertz')
         law_code = law_hertz
      case default
         law_code = 0
      end select
   end function law_code

   !> Contact force magnitude f >= 0 for penetration d and its rate d_dot.
   elemental function contact_force(law, k, c, p, d, d_dot) result(f)
      integer, intent(in) :: law      !! law_bilinear or law_hertz
      real(dp), intent(in) :: k       !! stiffness
      real(dp), intent(in) :: c       !! damper [N s/m] (bilinear)
      real(dp), intent(in) :: p       !! exponent (hertz)
      real(dp), intent(in) :: d       !! penetration [m]
      real(dp), intent(in) :: d_dot   !! penetration rate [m/s]
      real(dp) :: f
      if (d <= 0.0_dp) then
         f = 0.0_dp
      else if (law == law_bilinear) then
         f = max(0.0_dp, k * d + c * d_dot)
      else
         f = k * d**p
      end if
   end function contact_force

   !> Exact contact force of one contact inside an implicit step.
   !>
   !> The step gives the penetration and its rate as affine functions of the force,
   !> d = d_star - h f and d' = v_star - kappa h f (h > 0: compliance of the step's effective
   !> stiffness at the contact, kappa = delta/(alpha dt) for Newmark). The unique f >= 0 with
   !> f = law(d, d') is found in closed form (bilinear; if the damper would push on at d <= 0
   !> the contact sits at d = 0) or by a safeguarded Newton iteration on d (Hertz, p >= 1,
   !> convex in d, so Newton from d_star converges monotonically; bisection guards it).
   pure function solve_scalar_contact(law, k, c, p, d_star, v_star, h, kappa) result(f)
      integer, intent(in) :: law        !! law_bilinear or law_hertz
      real(dp), intent(in) :: k         !! stiffness
      real(dp), intent(in) :: c         !! damper (bilinear)
      real(dp), intent(in) :: p         !! exponent (hertz)
      real(dp), intent(in) :: d_star    !! penetration with zero contact force [m]
      real(dp), intent(in) :: v_star    !! penetration rate with zero contact force [m/s]
      real(dp), intent(in) :: h         !! compliance [m/N]
      real(dp), intent(in) :: kappa     !! d(rate)/d(displacement) of the scheme [1/s]
      real(dp) :: f
      real(dp) :: lam, d, dlo, dhi, phi, dphi, dn
      integer :: it
      f = 0.0_dp
      if (d_star <= 0.0_dp) return
      if (law == law_bilinear) then
         lam = k * d_star + c * v_star
         if (lam <= 0.0_dp) return
         f = lam / (1.0_dp + (k + c * kappa) * h)
         if (d_star - h * f <= 0.0_dp) f = d_star / h
      else
         ! phi(d) = d + h k d^p - d_star = 0 on [0, d_star]
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
      end if
   end function solve_scalar_contact
end module gapbeam_contact
