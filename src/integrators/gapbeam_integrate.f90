!> One entry point for a transient run with any method: the event-driven exact integrator for
!> method 'exact', the stepping driver (gapbeam_transient) for every other.
module gapbeam_integrate
   use gapbeam_error, only: error_t
   use gapbeam_problem, only: problem_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t
   use gapbeam_transient, only: transient_result_t, run_transient
   use gapbeam_exact, only: run_exact
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: integrate

contains

   !> Integrate from (u0, v0) at t = 0 over the deck's transient and recorded periods.
   subroutine integrate(prob, cfg, out, u0, v0, res, err)
      type(problem_t), intent(in) :: prob              !! model
      type(solver_settings_t), intent(in) :: cfg       !! method and settings
      type(output_settings_t), intent(in) :: out       !! what to record
      real(dp), intent(in) :: u0(:), v0(:)             !! initial state relative to the base
      type(transient_result_t), intent(out) :: res     !! results
      type(error_t), allocatable, intent(out) :: err   !! numerical failure
      if (cfg%method == 'exact') then
         call run_exact(prob, cfg, out, u0, v0, res, err)
      else
         call run_transient(prob, cfg, out, u0, v0, res, err)
      end if
   end subroutine integrate
end module gapbeam_integrate
