!> The dense output of the exact integrator: one window of a linear segment, evaluated from
!> the closed form at any instant inside (every term of the segment's sum of exponentials).
module gapbeam_exact_piece
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_model, only: model_t
   use gapbeam_observer, only: piece_t
   use gapbeam_exact_modes, only: open_modes_t, to_physical
   use gapbeam_exact_config, only: config_t
   use gapbeam_exact_segment, only: segment_t, segment_values, segment_state
   implicit none
   private
   public :: exact_piece_t

   !> A window of a segment: closed-form dense output.
   type, extends(piece_t) :: exact_piece_t
      type(segment_t), pointer :: sg => null()        !! the segment
      type(config_t), pointer :: cf => null()         !! its configuration
      type(open_modes_t), pointer :: om => null()     !! open structure
      type(model_t), pointer :: model => null()       !! model
      real(dp) :: t0 = 0.0_dp                         !! time of the segment's start [s]
      real(dp) :: omega = 0.0_dp                      !! forcing [rad/s]
      integer(int64) :: mask = 0                      !! active contacts
   contains
      procedure :: sample => exact_sample
      procedure :: state_at => exact_state
   end type exact_piece_t

contains

   !> Outputs at t from the closed form (every term).
   subroutine exact_sample(self, t, strain, rate, tip, tip_velocity, force)
      class(exact_piece_t), intent(in) :: self          !! piece
      real(dp), intent(in) :: t                         !! instant [s]
      real(dp), intent(out) :: strain, rate, tip, tip_velocity   !! outputs
      real(dp), intent(out) :: force(:)                 !! contact force magnitudes [N]
      real(dp) :: val(0:1, self%om%nb), d, dd
      integer :: c, b
      call segment_values(self%sg, t - self%t0, val)
      strain = val(0, self%om%b_strain);  rate = val(1, self%om%b_strain)
      tip = val(0, self%om%b_tip);  tip_velocity = val(1, self%om%b_tip)
      associate (m => self%model)
         do c = 1, m%n_contacts
            force(c) = 0.0_dp
            if (.not. btest(self%mask, c - 1)) cycle
            b = self%om%cslot(c)
            d = m%c_sign(c) * val(0, b) - m%c_gap(c)
            dd = m%c_sign(c) * val(1, b)
            force(c) = max(0.0_dp, m%c_k(c) * d + m%c_c(c) * dd)
         end do
      end associate
   end subroutine exact_sample

   !> Displacement and velocity of every dof at t from the closed form.
   subroutine exact_state(self, t, u, v)
      class(exact_piece_t), intent(in) :: self          !! piece
      real(dp), intent(in) :: t                         !! instant [s]
      real(dp), intent(out) :: u(:), v(:)               !! state
      real(dp) :: eta(self%om%nr), vel(self%om%nr)
      call segment_state(self%cf, self%sg, t - self%t0, eta, vel)
      call to_physical(self%om, eta, vel, u, v)
   end subroutine exact_state
end module gapbeam_exact_piece
