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
   use gapbeam_settings, only: output_settings_t
   use gapbeam_flow_results, only: response_psd_t
   use gapbeam_response_psd, only: psd_rows
   implicit none
   private
   public :: run_draws

contains

   !> The statistics of every output over the deck's &turbulence draws; res1 is the first
   !> draw's record, (u0, v0) the deck's initial state.
   subroutine run_draws(dk, u0, v0, out, res1, stats, e, psd)
      type(deck_t), intent(in) :: dk                      !! deck with a turbulence spectrum
      real(dp), intent(in) :: u0(:), v0(:)                !! the deck's initial state
      type(output_settings_t), intent(in) :: out          !! what draw 1 recorded
      type(transient_result_t), intent(in) :: res1        !! draw 1
      type(draw_statistics_t), allocatable, intent(out) :: stats(:)
      type(error_t), allocatable, intent(out) :: e        !! a draw failed
      !> with &turbulence psd_nodes: the response PSD over the draws (draw 1 with its state
      !> history)
      type(response_psd_t), intent(out), optional :: psd
      type(deck_variable_t) :: none(0)
      real(dp), allocatable :: vals(:, :, :), rows(:, :)
      real(dp) :: t_rec, nothing(0)
      t_rec = real(dk%solver%record_periods, dp) / dk%forcing%frequency_hz
      if (present(psd)) then
         call psd_rows(dk, rows, psd, e)
         if (.not. allocated(e)) call collect_draws(dk, none, nothing, u0, v0, out, res1, &
                                                    t_rec, vals, e, rows, psd)
      else
         call collect_draws(dk, none, nothing, u0, v0, out, res1, t_rec, vals, e)
      end if
      if (allocated(e)) return
      stats = draw_statistics(vals, size(res1%peak_force))
      write(output_unit, '(a)') str(size(vals, 1)) // ' draws done'
   end subroutine run_draws
end module gapbeam_draws_job
