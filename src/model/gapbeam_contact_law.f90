!> Stop (gap-support) laws: force magnitude and tangent from the penetration.
!>
!> A one-sided contact acts at one dof with a direction s = +1 (the stop is met when the dof
!> moves in +w, u >= gap) or s = -1 (u <= -gap). Its penetration is d = s*u - gap (d > 0: in
!> contact) and the force on the structure is -s*f with f >= 0 the magnitude returned here.
!> Displacements are relative to the base; the stops move with the base.
!>
!> * bilinear: f = max(0, k d + c d') while d > 0, else 0 (the damper never pulls);
!> * hertz:    f = k d^p while d > 0, else 0.
module gapbeam_contact_law
   use gapbeam_kinds, only: dp
   use gapbeam_description, only: law_bilinear
   use gapbeam_model, only: model_t
   implicit none
   private
   public :: contact_force, solve_scalar_contact, solve_contacts

   

contains

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

   !> Exact contact forces of an implicit step with several contacts: projected (non-linear)
   !> Gauss-Seidel over the contacts with the exact scalar solve, which converges because the
   !> forces minimise a strictly convex function (H is positive definite).
   !>
   !> With the forces f, contact c's penetration and rate are affine:
   !>    d_c = dstar_c - s_c w sum_o H(slot_c, slot_o) s_o f_o,   d'_c = vstar_c - kappa (...)
   !> (H = E' Kbar^-1 E of the step, w the weight of the step's end in the instant where the
   !> law is evaluated: 1 for Newmark, 1 - alpha_f for the alpha methods). Contact `hold` is
   !> held open (0: none). Starts from the given f.
   pure subroutine solve_contacts(model, hmat, w, kappa, dstar, vstar, f, hold)
      type(model_t), intent(in) :: model       !! model (contacts)
      real(dp), intent(in) :: hmat(:, :)       !! (n_slots, n_slots) compliance at the slots
      real(dp), intent(in) :: w                !! weight of the step's end [-]
      real(dp), intent(in) :: kappa            !! d(rate)/d(displacement) of the scheme [1/s]
      real(dp), intent(in) :: dstar(:)         !! penetrations with zero forces [m]
      real(dp), intent(in) :: vstar(:)         !! their rates [m/s]
      real(dp), intent(inout) :: f(:)          !! force magnitudes (in: first guess) [N]
      integer, intent(in) :: hold              !! contact held open (0: none)
      integer :: c, o, si, sweep
      real(dp) :: shift, fold, change, fmax
      do sweep = 1, 1000
         change = 0.0_dp;  fmax = 0.0_dp
         do c = 1, model%n_contacts
            si = model%c_slot(c)
            shift = 0.0_dp
            do o = 1, model%n_contacts
               if (o /= c) shift = shift + hmat(si, model%c_slot(o)) * model%c_sign(o) * f(o)
            end do
            shift = model%c_sign(c) * w * shift
            fold = f(c)
            f(c) = solve_scalar_contact(model%c_law(c), model%c_k(c), model%c_c(c), &
               model%c_p(c), dstar(c) - shift, vstar(c) - kappa * shift, w * hmat(si, si), kappa)
            if (c == hold) f(c) = 0.0_dp
            change = max(change, abs(f(c) - fold));  fmax = max(fmax, f(c))
         end do
         if (change <= 1.0e-14_dp * fmax .or. fmax == 0.0_dp) exit
      end do
   end subroutine solve_contacts
end module gapbeam_contact_law
