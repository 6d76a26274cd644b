!> The basis rule of `&reduction kind = 'auto'`: the cut-off frequency of the modes kept,
!> from the forcing, the contact stiffnesses and the tolerance; and what a reduction kept.
!>
!> **The rule.** The reference frequency is the highest the supports and the forcing impose:
!> f_ref = max(f_c, 5 f), f the forcing frequency and f_c the largest contact frequency of a
!> support dof j, sqrt((k_s + k_c) / m_s) / 2 pi, where psi = K^-1 e_j is the static shape of
!> the open structure under a force at j, k_s = 1 / psi_j its stiffness there, m_s =
!> psi' M psi / psi_j^2 its mass (Rayleigh's quotient) and k_c the stiffest law on that dof (the
!> normal or the stick stiffness of a ring; a Hertz law's tangent where its force moves the
!> structure by the gap). The cut-off is f_cut = c f_ref with c = 4 at tolerances from 1e-4 up
!> and c = 4 (1e-4 / tolerance)^0.6 below. An impact lasts about half a period of the contact
!> frequency, so its spectrum reaches a few times f_c: on the multispan tube (f_c = 222 Hz) at
!> 7 Hz and 0.05 mm, a periodic orbit, cut-offs of 0.27, 0.45, 0.68 and 0.9 f_c changed the
!> orbit (558, 439, 243 and 186 impacts at baffle 2 in 20 periods, for the full model's 120),
!> 1.35 f_c kept it with peak forces 11 % off, 2 f_c 6 % off, and 3.2 f_c gave every work rate
!> and peak force within 0.6 % of the full model; on the rattling cantilever of the tests
!> (f_ref = 5 x 40 Hz) 3.1
!> f_ref (2 modes per plane) left the friction work rate 45 % off and 3.4 f_ref (3 modes) within
!> 0.2 %. The work-rate errors fall about as f_cut^-1.7, so a 10 x tighter tolerance takes
!> 10^0.6 = 4 x the cut-off (docs/tubes.md, scripts/bench_tubes.sh).
module gapbeam_reduction_rule
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dpotrf, dpotrs
   use gapbeam_model, only: model_t
   use gapbeam_description, only: law_bilinear
   implicit none
   private
   public :: reduction_info_t, auto_cutoff, contact_frequencies, reduction_text

   !> What a reduction kept, and why.
   type :: reduction_info_t
      character(len=16) :: kind = 'none'          !! 'none', 'modal' or 'auto'
      real(dp) :: cutoff_hz = 0.0_dp              !! cut-off (0: n_modes) [Hz]
      integer :: planes = 1                       !! planes of motion
      integer :: modes_per_plane = 0              !! modes of the open structure kept
      integer :: modes_available = 0              !! modes with mass in each plane
      integer :: n_static = 0                     !! static modes per plane
      integer :: n_full = 0                       !! dofs of the finite element model
      integer :: n_reduced = 0                    !! coordinates of the integrated model
      real(dp) :: highest_mode_hz = 0.0_dp        !! highest kept mode [Hz]
      real(dp) :: f_max_hz = 0.0_dp               !! highest frequency of the reduced model [Hz]
      real(dp) :: contact_hz = 0.0_dp             !! highest contact frequency estimate [Hz]
      real(dp) :: forcing_hz = 0.0_dp             !! forcing frequency [Hz]
      real(dp) :: factor = 0.0_dp                 !! cut-off / reference frequency [-]
   end type reduction_info_t

   !> harmonics of the forcing the basis covers at least
   integer, parameter :: forcing_harmonics = 5
   !> cut-off / the reference frequency at tolerances from reference_tolerance up
   real(dp), parameter :: base_factor = 4.0_dp
   real(dp), parameter :: reference_tolerance = 1.0e-4_dp
   !> below it the factor grows as (reference_tolerance / tolerance)**tolerance_power: the
   !> truncation error of the work rates falls about as (cut-off)^-1.7 (measured)
   real(dp), parameter :: tolerance_power = 0.6_dp

contains

   !> One line saying what the reduction kept (and for kind 'auto', by which rule).
   function reduction_text(info, tolerance) result(t)
      type(reduction_info_t), intent(in) :: info       !! what the build kept
      real(dp), intent(in) :: tolerance                !! the solver's tolerance [-]
      character(len=:), allocatable :: t
      t = 'model: modal'
      if (info%kind == 'auto') t = t // " (&reduction kind = 'auto'), cut-off " &
         // str(info%cutoff_hz) // ' Hz = ' // str(info%factor) // ' x max(contact ' &
         // 'frequency ' // str(info%contact_hz) // ' Hz, ' // str(forcing_harmonics) &
         // ' x forcing ' // str(info%forcing_hz) // ' Hz) at tolerance ' // str(tolerance)
      if (info%kind == 'modal' .and. info%cutoff_hz > 0.0_dp) t = t // ', cut-off ' &
         // str(info%cutoff_hz) // ' Hz'
      t = t // ': ' // str(info%modes_per_plane) // ' modes (up to ' &
         // str(info%highest_mode_hz) // ' Hz) + ' // str(info%n_static) // ' static modes ' &
         // trim(merge('per plane', '         ', info%planes > 1)) // ', ' // str(info%n_reduced) &
         // ' coordinates of ' // str(info%n_full) // ' dofs; highest frequency ' &
         // str(info%f_max_hz) // ' Hz'
   end function reduction_text

   !> The cut-off of kind 'auto' (see the module header) in info%cutoff_hz, with its inputs.
   subroutine auto_cutoff(full, tolerance, info, err)
      type(model_t), intent(in) :: full                !! full model
      real(dp), intent(in) :: tolerance                !! the solver's tolerance [-]
      type(reduction_info_t), intent(inout) :: info    !! cut-off and its inputs set
      type(error_t), allocatable, intent(out) :: err   !! singular stiffness
      real(dp), allocatable :: fc(:)
      call contact_frequencies(full, fc, err);  if (allocated(err)) return
      info%forcing_hz = full%omega / (2.0_dp * pi)
      info%contact_hz = 0.0_dp
      if (size(fc) > 0) info%contact_hz = maxval(fc)
      info%factor = base_factor * max(1.0_dp, (reference_tolerance / tolerance)**tolerance_power)
      info%cutoff_hz = info%factor * max(info%contact_hz, forcing_harmonics * info%forcing_hz)
   end subroutine auto_cutoff

   !> The contact frequency of each contact dof (slot): the static deflection shape psi =
   !> K^-1 e_j under a force there, its stiffness k_s = 1 / psi_j and mass m_s = psi' M psi /
   !> psi_j^2 (the Rayleigh quotient), with the stiffest contact law on that dof k_c beside it:
   !> f_j = sqrt((k_s + k_c) / m_s) / 2 pi [Hz].
   subroutine contact_frequencies(full, fc, err)
      type(model_t), intent(in) :: full                !! full model
      real(dp), allocatable, intent(out) :: fc(:)      !! per slot [Hz]
      type(error_t), allocatable, intent(out) :: err   !! singular stiffness
      real(dp), allocatable :: kf(:, :), psi(:, :)
      real(dp) :: ks, ms, kc
      integer :: n, ns, j, info, c, r
      n = full%n;  ns = full%n_slots
      allocate(fc(ns), source=0.0_dp)
      if (ns == 0) return
      kf = full%sys%k
      allocate(psi(n, ns), source=0.0_dp)
      do j = 1, ns
         psi(full%slot_dof(j), j) = 1.0_dp
      end do
      call dpotrf('U', n, kf, n, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_reduction_rule: the stiffness is not positive ' &
            // 'definite (dpotrf info=' // str(info) // ')')
         return
      end if
      call dpotrs('U', n, ns, kf, n, psi, n, info)
      do j = 1, ns
         ks = 1.0_dp / psi(full%slot_dof(j), j)
         ms = dot_product(psi(:, j), matmul(full%sys%m, psi(:, j))) &
              / psi(full%slot_dof(j), j)**2
         kc = 0.0_dp
         do c = 1, full%n_contacts
            if (full%c_slot(c) == j) kc = max(kc, linear_stiffness(full%c_law(c), full%c_k(c), &
               full%c_p(c), full%c_gap(c), ks))
         end do
         do r = 1, full%n_rings
            if (any(full%r_slot(:, r) == j)) kc = max(kc, linear_stiffness(full%r_law(r), &
               full%r_k(r), full%r_p(r), full%r_gap(r), ks), full%r_kt(r))
         end do
         if (ms > 0.0_dp) fc(j) = sqrt((ks + kc) / ms) / (2.0_dp * pi)
      end do
   end subroutine contact_frequencies

   !> The stiffness of a contact law to compare with the structure's k_s: the bilinear k; for
   !> Hertz (F = k d^p) the tangent p k d^(p-1) at the penetration d where F = k_s g (the
   !> force that moves the structure by the gap g, at least 1 micrometre) [N/m].
   pure real(dp) function linear_stiffness(law, k, p, gap, ks) result(kl)
      integer, intent(in) :: law          !! law code
      real(dp), intent(in) :: k, p        !! law stiffness and exponent
      real(dp), intent(in) :: gap         !! gap [m]
      real(dp), intent(in) :: ks          !! the structure's stiffness there [N/m]
      real(dp) :: d
      if (law == law_bilinear) then
         kl = k
      else
         d = (ks * max(gap, 1.0e-6_dp) / k)**(1.0_dp / p)
         kl = p * k * d**(p - 1.0_dp)
      end if
   end function linear_stiffness
end module gapbeam_reduction_rule
