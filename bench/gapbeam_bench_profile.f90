!> The observer of gapbeam_bench_tubes' profile: accepted steps sorted by the contact state of
!> the supports over the step (every ring and contact open, or one in contact).
module gapbeam_bench_profile
   use gapbeam_kinds, only: dp
   use gapbeam_observer, only: piece_t, observer_t
   implicit none
   private
   public :: profile_t

   !> Steps and time with every support open and with a support in contact.
   type, extends(observer_t) :: profile_t
      integer :: n_open = 0, n_contact = 0        !! accepted steps [-]
      real(dp) :: t_open = 0.0_dp, t_contact = 0.0_dp  !! their total length [s]
   contains
      procedure :: observe => profile_observe
   end type profile_t

contains

   !> Count one accepted step.
   subroutine profile_observe(self, piece)
      class(profile_t), intent(inout) :: self    !! profile
      class(piece_t), intent(in) :: piece        !! the step
      logical :: contact
      contact = any(piece%r_mode > 0) .or. any(piece%f_b > 0.0_dp) .or. any(piece%f_a > 0.0_dp)
      if (contact) then
         self%n_contact = self%n_contact + 1
         self%t_contact = self%t_contact + (piece%tb - piece%ta)
      else
         self%n_open = self%n_open + 1
         self%t_open = self%t_open + (piece%tb - piece%ta)
      end if
   end subroutine profile_observe
end module gapbeam_bench_profile
