!> Random draws of one case (a transient run, or a sweep point): the scalar outputs of every
!> draw and their statistics over the draws (docs/flow.md).
!>
!> Draw 1 is the case's labelled run (its final record); draws 2, 3, ... are integrated from
!> the case's start (the same state as draw 1's) over the transient and recorded periods, each
!> with its own model: the case's model with the turbulence record of that draw
!> (gapbeam_deck_parameter: the deck with the case's values, rebuilt). A draw is a pure
!> function of (seed, draw number, the case's values): the same on any thread, in any order
!> and in any shard; the points of a sweep share their draws (common random numbers: draw d
!> has the same phases at every point, so differences between points are not clouded by the
!> draws' scatter).
!>
!> With &turbulence draws_target_ci > 0, draws are added one at a time after the first
!> `draws` until the relative 95 % half-width (Student t) of every watched output is at most
!> the target, or `draws_max` are taken. Watched: the tip's RMS displacement and, for every
!> support that some draw touched, its impact and normal work rates (the outputs wear is
!> computed from). The stopping rule looks at the draws already taken, so the interval of the
!> final count is slightly optimistic (sequential stopping); the count is a pure function of
!> the draws, hence as reproducible as they are.
module gapbeam_draws
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: output_settings_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_flow_results, only: draw_statistics_t, n_draw_outputs, draw_output_names, &
      response_psd_t
   use gapbeam_response_psd, only: add_draw_psd, finish_psd
   use gapbeam_deck_variable, only: deck_variable_t
   use gapbeam_deck_parameter, only: model_with_values
   use gapbeam_transient, only: integrate
   use gapbeam_draw_statistics, only: mean_half_width, relative_half_width
   implicit none
   private
   public :: n_draw_outputs, draw_output_names, draw_values, run_draw, draws_enough, &
      draw_statistics, draws_wanted, collect_draws

   !> the outputs the target half-width watches
   integer, parameter :: watched(3) = [5, 6, 9]

contains

   !> Whether the deck asks for statistics over draws.
   pure logical function draws_wanted(deck)
      type(deck_t), intent(in) :: deck   !! deck
      draws_wanted = deck%turbulence%spectrum /= 'none' .and. (deck%turbulence%draws > 1 .or. &
                     deck%turbulence%draws_target_ci > 0.0_dp)
   end function draws_wanted

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
      if (allocated(res%tip_displacement)) then
         if (size(res%tip_displacement) > 0) v(1, 9) = sqrt(sum(res%tip_displacement**2) &
            / real(size(res%tip_displacement), dp))
      end if
   end subroutine draw_values

   !> Draw `d` of the case: the deck's model with vars = values and that draw's record,
   !> integrated from (u, v) with the output settings `out`.
   subroutine run_draw(deck, vars, values, d, u, v, out, res, err)
      type(deck_t), intent(in) :: deck                   !! deck
      type(deck_variable_t), intent(in) :: vars(:)       !! the case's variables (none: the deck)
      real(dp), intent(in) :: values(:)                  !! their values
      integer, intent(in) :: d                           !! draw number
      real(dp), intent(in) :: u(:), v(:)                 !! the case's start
      type(output_settings_t), intent(in) :: out         !! what the run records
      type(transient_result_t), intent(out) :: res       !! the draw's final record
      type(error_t), allocatable, intent(out) :: err     !! build or solver failure
      type(model_t) :: model
      call model_with_values(deck, vars, values, model, err, draw=d)
      if (.not. allocated(err)) call integrate(model, deck%solver, out, u, v, res, err)
      if (allocated(err)) err%message = 'turbulence draw ' // str(d) // ': ' // err%message
   end subroutine run_draw

   !> Whether the draws taken, vals(1:n, :, :), are enough: n >= draws and, with a target,
   !> every watched output within it (or n = draws_max).
   pure logical function draws_enough(deck, vals, n) result(enough)
      type(deck_t), intent(in) :: deck                   !! deck
      real(dp), intent(in) :: vals(:, :, :)              !! (draw, stop, output)
      integer, intent(in) :: n                           !! draws taken
      integer :: j, k
      enough = n >= deck%turbulence%draws
      if (.not. enough .or. deck%turbulence%draws_target_ci <= 0.0_dp) return
      if (n >= deck%turbulence%draws_max) return
      do k = 1, size(watched)
         do j = 1, size(vals, 2)
            if (watched(k) == n_draw_outputs .and. j > 1) cycle
            if (all(vals(1:n, j, watched(k)) == 0.0_dp)) cycle   ! untouched: nothing to watch
            if (relative_half_width(vals(1:n, j, watched(k))) &
                > deck%turbulence%draws_target_ci) enough = .false.
         end do
      end do
   end function draws_enough

   !> Draws 2, 3, ... of a case whose draw 1 is `res1`, until draws_enough: vals(draw, stop,
   !> output) of every draw taken.
   subroutine collect_draws(deck, vars, values, u, v, out, res1, t_rec, vals, err, rows, psd)
      type(deck_t), intent(in) :: deck                   !! deck
      type(deck_variable_t), intent(in) :: vars(:)       !! the case's variables
      real(dp), intent(in) :: values(:)                  !! their values
      real(dp), intent(in) :: u(:), v(:)                 !! the case's start
      type(output_settings_t), intent(in) :: out         !! what a draw records
      type(transient_result_t), intent(in) :: res1       !! draw 1's final record
      real(dp), intent(in) :: t_rec                      !! record length [s]
      real(dp), allocatable, intent(out) :: vals(:, :, :)
      type(error_t), allocatable, intent(out) :: err     !! a draw failed
      !> with psd: the rows of its series (gapbeam_response_psd; `out` keeps the state history)
      real(dp), intent(in), optional :: rows(:, :)
      type(response_psd_t), intent(inout), optional :: psd   !! the response PSD over the draws
      type(transient_result_t) :: res
      real(dp), allocatable :: grown(:, :, :)
      integer :: ns, n
      ns = size(res1%peak_force)
      allocate(vals(max(deck%turbulence%draws, 2), max(ns, 1), n_draw_outputs))
      call draw_values(res1, t_rec, ns, vals(1, :, :))
      if (present(psd)) call add_draw_psd(deck, res1, rows, psd, err)
      if (allocated(err)) return
      n = 1
      do while (.not. draws_enough(deck, vals, n))
         n = n + 1
         if (n > size(vals, 1)) then
            allocate(grown(2 * size(vals, 1), size(vals, 2), size(vals, 3)))
            grown(1:n - 1, :, :) = vals(1:n - 1, :, :)
            call move_alloc(grown, vals)
         end if
         call run_draw(deck, vars, values, n, u, v, out, res, err)
         if (allocated(err)) return
         call draw_values(res, t_rec, ns, vals(n, :, :))
         if (present(psd)) call add_draw_psd(deck, res, rows, psd, err)
         if (allocated(err)) return
      end do
      vals = vals(1:n, :, :)
      if (present(psd)) call finish_psd(psd)
   end subroutine collect_draws

   !> The statistics of every output over the draws vals(draw, stop, output): ns items (the
   !> stops), the tip RMS one.
   function draw_statistics(vals, ns) result(stats)
      real(dp), intent(in) :: vals(:, :, :)              !! (draw, stop, output)
      integer, intent(in) :: ns                          !! stops
      type(draw_statistics_t), allocatable :: stats(:)
      integer :: k, j, n_items
      allocate(stats(n_draw_outputs))
      do k = 1, n_draw_outputs
         stats(k)%name = trim(draw_output_names(k))
         stats(k)%n_draws = size(vals, 1)
         n_items = ns
         if (k == n_draw_outputs) n_items = 1
         stats(k)%values = vals(:, 1:n_items, k)
         allocate(stats(k)%mean(n_items), stats(k)%half_width(n_items))
         do j = 1, n_items
            call mean_half_width(vals(:, j, k), stats(k)%mean(j), stats(k)%half_width(j))
         end do
      end do
   end function draw_statistics
end module gapbeam_draws
