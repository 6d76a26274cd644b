!> Statistics over the random draws of a transient run (docs/flow.md): draws 2, 3, ... of the
!> deck's turbulence, each its own model (the record of that draw) integrated from the deck's
!> initial state over the transient and recorded periods; with the first draw (the labelled
!> run's final record) every scalar output per support becomes the mean over the draws and
!> the half-width of its 95 % confidence interval (Student t with n - 1 degrees of freedom).
!> The draws are independent of one another and of the order they run in (a draw is a pure
!> function of the seed and its number).
module gapbeam_draws_job
   use, intrinsic :: iso_fortran_env, only: output_unit
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_flow_results, only: draw_statistics_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_transient, only: integrate
   use gapbeam_draw_statistics, only: mean_half_width
   implicit none
   private
   public :: run_draws

   integer, parameter :: n_draw_outputs = 9
   !> the outputs over draws, as named under /statistics
   character(len=*), parameter :: draw_output_names(n_draw_outputs) = [character(len=24) :: &
      'impact_rate', 'peak_force', 'rms_force', 'contact_fraction', 'work_rate', &
      'normal_work_rate', 'friction_work_rate', 'wear_volume_rate', 'tip_rms_displacement']

contains

   !> The statistics of every output over the deck's &turbulence draws; res1 is the first
   !> draw's record.
   subroutine run_draws(dk, res1, stats, e)
      type(deck_t), intent(in) :: dk                      !! deck with draws >= 1
      type(transient_result_t), intent(in) :: res1        !! draw 1
      type(draw_statistics_t), allocatable, intent(out) :: stats(:)
      type(error_t), allocatable, intent(out) :: e        !! a draw failed
      type(model_t) :: model
      type(transient_result_t) :: res
      real(dp), allocatable :: u0(:), v0(:), v(:, :, :)
      real(dp) :: t_rec
      integer :: d, k, n, ns
      n = dk%turbulence%draws
      ns = size(res1%peak_force)
      t_rec = real(dk%solver%record_periods, dp) / dk%forcing%frequency_hz
      allocate(v(n, max(ns, 1), n_draw_outputs), source=0.0_dp)
      call draw_values(res1, t_rec, ns, v(1, :, :))
      do d = 2, n
         call build_model(dk, model, u0, v0, e, draw=d)
         if (.not. allocated(e)) call integrate(model, dk%solver, dk%output, u0, v0, res, e)
         if (allocated(e)) then
            e%message = 'turbulence draw ' // str(d) // ': ' // e%message
            return
         end if
         call draw_values(res, t_rec, ns, v(d, :, :))
         write(output_unit, '(a)') 'draw ' // str(d) // ' of ' // str(n) // ': done'
      end do
      allocate(stats(n_draw_outputs))
      do k = 1, n_draw_outputs
         stats(k)%name = trim(draw_output_names(k))
         stats(k)%n_draws = n
         if (k == n_draw_outputs) then
            stats(k)%values = v(:, 1:1, k)
         else
            stats(k)%values = v(:, 1:ns, k)
         end if
         allocate(stats(k)%mean(size(stats(k)%values, 2)), &
                  stats(k)%half_width(size(stats(k)%values, 2)))
         do d = 1, size(stats(k)%values, 2)
            call mean_half_width(stats(k)%values(:, d), stats(k)%mean(d), &
                                 stats(k)%half_width(d))
         end do
      end do
   end subroutine run_draws

   !> The outputs of one draw: (stop, output); the tip RMS (over the history samples) in
   !> stop 1's place.
   subroutine draw_values(res, t_rec, ns, v)
      type(transient_result_t), intent(in) :: res   !! the draw's record
      real(dp), intent(in) :: t_rec                 !! record length [s]
      integer, intent(in) :: ns                     !! stops
      real(dp), intent(out) :: v(:, :)              !! (max(ns, 1), n_draw_outputs)
      v = 0.0_dp
      if (ns > 0) then
         v(1:ns, 1) = real(res%n_impacts, dp) / t_rec
         v(1:ns, 2) = res%peak_force
         v(1:ns, 3) = res%rms_force
         v(1:ns, 4) = res%contact_fraction
         v(1:ns, 5) = res%work_rate
         if (allocated(res%normal_work_rate)) then
            v(1:ns, 6) = res%normal_work_rate
            v(1:ns, 7) = res%friction_work_rate
            v(1:ns, 8) = res%wear_volume_rate
         end if
      end if
      if (size(res%tip_displacement) > 0) v(1, 9) = sqrt(sum(res%tip_displacement**2) &
         / real(size(res%tip_displacement), dp))
   end subroutine draw_values
end module gapbeam_draws_job
