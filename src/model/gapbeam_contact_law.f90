!> The contacts of a model through their laws: force, exact condensed solve, energy.
!>
!> A one-sided contact c acts at dof c_dof(c) with a direction s = c_sign(c) = +1 (the stop is
!> met when the dof moves in +w, u >= gap) or -1 (u <= -gap). Its penetration is
!> d = s*u - gap (d > 0: in contact) and the force on the structure is -s*f with f >= 0 the
!> magnitude its law returns (core/gapbeam_law; the laws and what each can do are registered
!> in core/gapbeam_laws). Displacements are relative to the base; the stops move with the base.
!>
!> Every caller reaches a contact's law through the procedures here (or the law object itself,
!> `model%laws(model%c_law(c))%law`): no code tests which law it is.
module gapbeam_contact_law
   use gapbeam_kinds, only: dp
   use gapbeam_model, only: model_t
   implicit none
   private
   public :: contact_force, contact_solve, contact_energy, contact_elastic, &
      contact_releases_early, contact_jumps, solve_contacts

contains

   !> Force magnitude f >= 0 of contact c at penetration d and rate dd.
   pure real(dp) function contact_force(model, c, d, dd) result(f)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: c             !! contact
      real(dp), intent(in) :: d            !! penetration [m]
      real(dp), intent(in) :: dd           !! penetration rate [m/s]
      f = model%laws(model%c_law(c))%law%force(model%c_k(c), model%c_c(c), model%c_p(c), d, dd)
   end function contact_force

   !> Exact force of contact c inside an implicit step with no other contact force:
   !> d = d_star - h f, d' = v_star - kappa h f (see contact_law_t%solve).
   pure real(dp) function contact_solve(model, c, d_star, v_star, h, kappa) result(f)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: c             !! contact
      real(dp), intent(in) :: d_star       !! penetration with zero contact force [m]
      real(dp), intent(in) :: v_star       !! its rate [m/s]
      real(dp), intent(in) :: h            !! compliance [m/N]
      real(dp), intent(in) :: kappa        !! d(rate)/d(displacement) of the scheme [1/s]
      f = model%laws(model%c_law(c))%law%solve(model%c_k(c), model%c_c(c), model%c_p(c), &
                                                d_star, v_star, h, kappa)
   end function contact_solve

   !> Elastic energy stored in contact c at penetration d [J].
   pure real(dp) function contact_energy(model, c, d) result(e)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: c             !! contact
      real(dp), intent(in) :: d            !! penetration [m]
      e = model%laws(model%c_law(c))%law%energy(model%c_k(c), model%c_c(c), model%c_p(c), d)
   end function contact_energy

   !> Elastic part of the force of contact c at penetration d (f less its damper's share) [N].
   pure real(dp) function contact_elastic(model, c, d) result(e)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: c             !! contact
      real(dp), intent(in) :: d            !! penetration [m]
      e = model%laws(model%c_law(c))%law%elastic(model%c_k(c), model%c_c(c), model%c_p(c), d)
   end function contact_elastic

   !> Can the force of contact c vanish while it penetrates (a damper: released where the
   !> force, not the penetration, reaches zero)?
   pure logical function contact_releases_early(model, c) result(yes)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: c             !! contact
      yes = model%laws(model%c_law(c))%law%releases_early(model%c_k(c), model%c_c(c), &
                                                           model%c_p(c))
   end function contact_releases_early

   !> Does the force of contact c jump at an onset (a damper's c d')?
   pure logical function contact_jumps(model, c) result(yes)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: c             !! contact
      yes = model%laws(model%c_law(c))%law%jumps(model%c_k(c), model%c_c(c), model%c_p(c))
   end function contact_jumps

   !> Exact contact forces of an implicit step with several contacts: projected (non-linear)
   !> Gauss-Seidel over the contacts with each law's exact scalar solve, which converges
   !> because the forces minimise a strictly convex function (H is positive definite).
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
            f(c) = contact_solve(model, c, dstar(c) - shift, vstar(c) - kappa * shift, &
                                 w * hmat(si, si), kappa)
            if (c == hold) f(c) = 0.0_dp
            change = max(change, abs(f(c) - fold));  fmax = max(fmax, f(c))
         end do
         if (change <= 1.0e-14_dp * fmax .or. fmax == 0.0_dp) exit
      end do
   end subroutine solve_contacts
end module gapbeam_contact_law
