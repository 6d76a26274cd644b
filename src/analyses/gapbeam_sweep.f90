!> The forcing sweep: a line or grid of (frequency, amplitude) points, each run to its
!> attractor and classified, in parallel with OpenMP.
!>
!> Points are numbered with the frequency fastest: p = i_f + (i_a - 1) n_f. In mode
!> 'independent' every point starts from the deck's initial state and is one work item; in
!> mode 'continuation' each line (all frequencies of one amplitude, or all amplitudes of one
!> frequency) is one work item, swept up or down, each point starting from the final state of
!> the one before, as in an experiment. A work item runs serially on one thread, so results
!> are bitwise identical for any number of threads and any schedule. Work items are dealt to
!> shards round robin (item k belongs to shard mod(k-1, N) + 1).
module gapbeam_sweep
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t, diagnostics_settings_t, &
      sweep_settings_t
   use gapbeam_results, only: transient_result_t, point_result_t, lyapunov_t
   use gapbeam_transient, only: integrate
   use gapbeam_attractor, only: point_diagnostics
   use gapbeam_deck, only: deck_t
   use gapbeam_deck_variable, only: deck_variable_t
   use gapbeam_deck_parameter, only: model_with_values
   implicit none
   private
   public :: n_points, n_items, item_points, point_forcing, run_point, run_items

contains

   !> Number of points of the sweep.
   pure integer function n_points(sw)
      type(sweep_settings_t), intent(in) :: sw   !! sweep
      n_points = size(sw%frequency_hz) * size(sw%amplitude_pp)
   end function n_points

   !> Number of work items (points, or lines in continuation mode).
   pure integer function n_items(sw)
      type(sweep_settings_t), intent(in) :: sw   !! sweep
      if (sw%mode == 'continuation') then
         if (sw%axis == 'frequency') then
            n_items = size(sw%amplitude_pp)
         else
            n_items = size(sw%frequency_hz)
         end if
      else
         n_items = n_points(sw)
      end if
   end function n_items

   !> Points of work item k, in the order they are run.
   pure function item_points(sw, k) result(pts)
      type(sweep_settings_t), intent(in) :: sw   !! sweep
      integer, intent(in) :: k                   !! work item
      integer, allocatable :: pts(:)
      integer :: nf, na, j
      nf = size(sw%frequency_hz);  na = size(sw%amplitude_pp)
      if (sw%mode /= 'continuation') then
         pts = [k]
      else if (sw%axis == 'frequency') then
         pts = [(j + (k - 1) * nf, j = 1, nf)]
      else
         pts = [(k + (j - 1) * nf, j = 1, na)]
      end if
      if (sw%mode == 'continuation' .and. sw%direction == 'down') pts = pts(size(pts):1:-1)
   end function item_points

   !> Forcing frequency and amplitude of point p.
   pure subroutine point_forcing(sw, p, f_hz, a_pp)
      type(sweep_settings_t), intent(in) :: sw   !! sweep
      integer, intent(in) :: p                   !! point
      real(dp), intent(out) :: f_hz, a_pp        !! [Hz], [m]
      integer :: nf
      nf = size(sw%frequency_hz)
      f_hz = sw%frequency_hz(mod(p - 1, nf) + 1)
      a_pp = sw%amplitude_pp((p - 1) / nf + 1)
   end subroutine point_forcing

   !> Run one point from (u0, v0): transient, record, diagnostics. With `deck` and `vars` the
   !> amplitude-axis value `a_pp` is the value of every variable of `vars` instead (the model
   !> rebuilt from the deck with them set: gapbeam_deck_parameter).
   subroutine run_point(base, cfg, out, diag, f_hz, a_pp, u0, v0, pr, deck, vars)
      type(model_t), intent(in) :: base                !! model (forcing replaced)
      type(solver_settings_t), intent(in) :: cfg         !! solver settings
      type(output_settings_t), intent(in) :: out         !! recording settings
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      real(dp), intent(in) :: f_hz, a_pp                 !! forcing [Hz], [m]
      real(dp), intent(in) :: u0(:), v0(:)               !! initial state
      type(point_result_t), intent(out) :: pr            !! result
      type(deck_t), intent(in), optional :: deck         !! deck of `base`
      type(deck_variable_t), intent(in), optional :: vars(:)   !! variables the axis sets
      type(model_t) :: model
      type(transient_result_t) :: res
      type(output_settings_t) :: o
      type(error_t), allocatable :: err
      integer(int64) :: c0, c1, rate
      call system_clock(c0, rate)
      if (present(vars)) then
         call model_with_values(deck, vars, spread(a_pp, 1, size(vars)), model, err)
      else
         model = base
         model%half_amplitude = 0.5_dp * a_pp
      end if
      model%omega = 2.0_dp * pi * f_hz
      o = out
      o%history_periods = 0
      if (.not. allocated(err)) call integrate(model, cfg, o, u0, v0, res, err)
      if (.not. allocated(err)) then
         pr%n_impacts = res%n_impacts;  pr%peak_force = res%peak_force
         pr%rms_force = res%rms_force;  pr%contact_fraction = res%contact_fraction
         pr%impulse_per_period = res%impulse_per_period;  pr%work_rate = res%work_rate
         pr%normal_work_rate = res%normal_work_rate
         pr%sliding_distance = res%sliding_distance
         pr%friction_work_rate = res%friction_work_rate
         pr%wear_volume_rate = res%wear_volume_rate
         pr%p_strain = res%p_strain;  pr%p_strain_rate = res%p_strain_rate
         pr%steps = res%steps_accepted
         call point_diagnostics(model, cfg, diag, res, pr, err)
      end if
      if (allocated(err)) then
         pr%status = 1
         pr%message = err%message
         call fill_failed(pr, base%n_stops, cfg%record_periods, u0, v0)
      end if
      call system_clock(c1)
      pr%seconds = real(c1 - c0, dp) / real(rate, dp)
   end subroutine run_point

   !> A failed point keeps NaN results of the right shapes.
   subroutine fill_failed(pr, ns, nrec, u0, v0)
      type(point_result_t), intent(inout) :: pr
      integer, intent(in) :: ns, nrec
      real(dp), intent(in) :: u0(:), v0(:)
      real(dp) :: nan
      nan = transfer(-2251799813685248_int64, 1.0_dp)
      pr%period = 0;  pr%label = 0;  pr%lyapunov = nan;  pr%lyapunov_error = nan
      if (allocated(pr%n_impacts)) deallocate(pr%n_impacts)
      allocate(pr%n_impacts(ns), source=0)
      pr%peak_force = spread(nan, 1, ns);  pr%rms_force = pr%peak_force
      pr%contact_fraction = pr%peak_force;  pr%impulse_per_period = pr%peak_force
      pr%work_rate = pr%peak_force
      pr%normal_work_rate = pr%peak_force;  pr%sliding_distance = pr%peak_force
      pr%friction_work_rate = pr%peak_force;  pr%wear_volume_rate = pr%peak_force
      pr%p_strain = spread(nan, 1, nrec);  pr%p_strain_rate = pr%p_strain
      if (.not. allocated(pr%lyapunov_running)) allocate(pr%lyapunov_running(0))
      pr%u_end = u0;  pr%v_end = v0
   end subroutine fill_failed

   !> Run work items `items` in parallel (OpenMP, dynamic schedule, one item per thread at a
   !> time); results(p) is written only by the thread that runs point p. No I/O in here.
   !> In continuation mode a line's first point starts from (u0, v0) and every later one from
   !> the final state of the point before; with `first`, `last` only positions first..last of
   !> each line are run, the point before `first` having been run already (its final state is
   !> in `results`), so a line run in several calls gives the same results as in one.
   subroutine run_items(base, sw, cfg, out, diag, items, u0, v0, results, first, last, deck, &
                        vars)
      type(model_t), intent(in) :: base                !! model
      type(sweep_settings_t), intent(in) :: sw           !! sweep
      type(solver_settings_t), intent(in) :: cfg         !! solver settings
      type(output_settings_t), intent(in) :: out         !! recording settings
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      integer, intent(in) :: items(:)                    !! work items to run
      real(dp), intent(in) :: u0(:), v0(:)               !! initial state of every item
      type(point_result_t), intent(inout) :: results(:)  !! indexed by point
      integer, intent(in), optional :: first, last       !! positions along each line to run
      type(deck_t), intent(in), optional :: deck         !! deck of `base` (with `vars`)
      type(deck_variable_t), intent(in), optional :: vars(:)   !! variables the amplitude
                                                         !! axis sets (run_point)
      integer :: i, j, p, j1, j2
      integer, allocatable :: pts(:)
      real(dp), allocatable :: u(:), v(:)
      real(dp) :: f_hz, a_pp
      j1 = 1;  j2 = huge(1)
      if (present(first)) j1 = max(1, first)
      if (present(last)) j2 = last
      !$omp parallel do default(none) schedule(dynamic, 1) &
      !$omp shared(base, sw, cfg, out, diag, items, u0, v0, results, j1, j2, deck, vars) &
      !$omp private(i, j, p, pts, u, v, f_hz, a_pp)
      do i = 1, size(items)
         pts = item_points(sw, items(i))
         if (j1 > 1 .and. j1 <= size(pts) .and. sw%mode == 'continuation') then
            u = results(pts(j1 - 1))%u_end;  v = results(pts(j1 - 1))%v_end
         else
            u = u0;  v = v0
         end if
         do j = j1, min(j2, size(pts))
            p = pts(j)
            call point_forcing(sw, p, f_hz, a_pp)
            if (present(vars)) then
               call run_point(base, cfg, out, diag, f_hz, a_pp, u, v, results(p), deck, vars)
            else
               call run_point(base, cfg, out, diag, f_hz, a_pp, u, v, results(p))
            end if
            if (sw%mode == 'continuation') then
               u = results(p)%u_end;  v = results(p)%v_end
            end if
         end do
      end do
      !$omp end parallel do
   end subroutine run_items
end module gapbeam_sweep
