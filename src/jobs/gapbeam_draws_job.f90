!> Statistics over the random draws of a transient run (docs/flow.md): draws 2, 3, ... of the
!> deck's turbulence (gapbeam_draws), each its own model (the record of that draw) integrated
!> from the deck's initial state over the transient and recorded periods; with the first draw
!> (the labelled run's final record) every scalar output per support becomes the mean over the
!> draws and the half-width of its 95 % confidence interval (Student t with n - 1 degrees of
!> freedom). The draws are independent of one another and of the order they run in (a draw is
!> a pure function of the seed and its number).
module gapbeam_draws_job
   use, intrinsic :: iso_fortran_env, only: output_unit
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_flow_results, only: draw_statistics_t
   use gapbeam_deck_variable, only: deck_variable_t
   use gapbeam_draws, only: collect_draws, draw_statistics
   implicit none
   private
   public :: run_draws

contains

   !> The statistics of every output over the deck's &turbulence draws; res1 is the first
   !> draw's record, (u0, v0) the deck's initial state.
   subroutine run_draws(dk, u0, v0, res1, stats, e)
      type(deck_t), intent(in) :: dk                      !! deck with a turbulence spectrum
      real(dp), intent(in) :: u0(:), v0(:)                !! the deck's initial state
      type(transient_result_t), intent(in) :: res1        !! draw 1
      type(draw_statistics_t), allocatable, intent(out) :: stats(:)
      type(error_t), allocatable, intent(out) :: e        !! a draw failed
      type(deck_variable_t) :: none(0)
      real(dp), allocatable :: vals(:, :, :)
      real(dp) :: t_rec, nothing(0)
      t_rec = real(dk%solver%record_periods, dp) / dk%forcing%frequency_hz
      call collect_draws(dk, none, nothing, u0, v0, dk%output, res1, t_rec, vals, e)
      if (allocated(e)) return
      stats = draw_statistics(vals, size(res1%peak_force))
      write(output_unit, '(a)') str(size(vals, 1)) // ' draws done'
   end subroutine run_draws
end module gapbeam_draws_job
