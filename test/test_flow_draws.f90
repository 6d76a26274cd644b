!> Random draws of the flow excitation in sweeps and transient runs (docs/flow.md):
!> * draws inside sweep points: a sweep over &flow velocity of the linear cantilever tube
!>   (test/decks/tube_turbulence.nml, Connors damping, a short-correlation load) with 3 draws
!>   per point writes /sweep/statistics; each point's mean and half-width equal those of the
!>   draws run one by one (the point's model with that draw's record, from the deck's start);
!>   the file is the same bit for bit on 1 and 2 threads, from two shards merged, and after a
!>   run stopped by its time limit and resumed from its checkpoint; the tube responds more at
!>   the velocity nearer its critical one.
!> * the target half-width: the stopping rule on made-up draws (it stops at the first count
!>   whose watched outputs are all within the target, skips untouched supports, stops at
!>   draws_max), and on the tube: the count reached is the first within the target.
!> * the response PSD at a node: the periodogram of any length (Bluestein) against a direct
!>   DFT and Parseval; on the linear tube (no contact) the tip's PSD against the analytic modal
!>   frequency response S(f) sum_m |H_tip(f) L_m|^2: fully correlated, every harmonic of one
!>   draw; short correlation, the mean of 8 draws in bands of 5 harmonics within the 99 %
!>   interval the draws state; Welch's estimate holds the variance of the periodogram's.
program test_flow_draws
   !$ use omp_lib, only: omp_set_num_threads
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_results, only: transient_result_t, point_result_t
   use gapbeam_settings, only: batch_options_t, output_settings_t
   use gapbeam_sweep, only: sweep_plan_t, make_plan
   use gapbeam_sweep_job, only: run_sweep_job
   use gapbeam_sweep_output, only: sweep_file_t, read_sweep, merge_sweep
   use gapbeam_files, only: remove_file, file_exists
   use gapbeam_flow_results, only: n_draw_outputs
   use gapbeam_draws, only: run_draw, draw_values, draws_enough, collect_draws
   use gapbeam_draw_statistics, only: mean_half_width, relative_half_width
   use gapbeam_model_builder, only: build_model
   use gapbeam_model, only: model_t
   use gapbeam_deck_variable, only: deck_variable_t
   use gapbeam_kinds, only: pi
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_random, only: splitmix64, stream_key
   use gapbeam_draw_statistics, only: periodogram_psd, dft, student_t_quantile
   use gapbeam_flow_results, only: response_psd_t
   use gapbeam_response_psd, only: psd_rows, add_draw_psd, finish_psd, segment_length
   use gapbeam_eigen, only: solve_modes
   use gapbeam_results, only: modes_t
   use gapbeam_model, only: global_dof
   use gapbeam_description, only: dof_w
   use gapbeam_turbulence, only: load_shapes, turbulence_psd
   implicit none
   character(len=*), parameter :: buffet = 'test/decks/tube_turbulence.nml'

   call mixer()
   call sweep_with_draws()
   call stopping_rule()
   call target_on_the_tube()
   call periodogram_of_a_line()
   call response_psd_linear_tube()
   call finish('test_flow_draws')

contains

   !> The counter-based mixer: SplitMix64's published first output, keys that differ by draw
   !> and substream (the wrapping version gave one key at -O3).
   subroutine mixer()
      call check('mixer: SplitMix64 of 0 = 0xE220A8397B1DCDAF (its first output from seed 0)', &
                 splitmix64(0_int64) == -2152535657050944081_int64)
      call check('mixer: the keys of draws 1, 2 and of another substream differ', &
                 stream_key(3, 1, 2097153) /= stream_key(3, 2, 2097153) .and. &
                 stream_key(3, 1, 2097153) /= stream_key(3, 1, 1048577))
      call check('mixer: stream_key(3, 1, 2097153) = 7579640446160460174 (its value on 64-bit ' &
                 // 'wrapping arithmetic)', stream_key(3, 1, 2097153) == 7579640446160460174_int64)
   end subroutine mixer

   !> The overrides of the velocity sweep with draws, output PREFIX.
   function sweep_overrides(prefix) result(ov)
      character(len=*), intent(in) :: prefix
      character(len=200) :: ov(7)
      ov(1) = "&job analysis = 'sweep', output = '" // prefix // "' /"
      ov(2) = '&flow fluid_density = 1000.0, tube_diameter = 0.019, connors_constant = 3.0, ' &
         // 'velocity = 1.0 /'
      ov(3) = '&turbulence draws = 3, correlation_length = 0.05, frequency_resolution_hz = 4.0 /'
      ov(4) = "&sweep x_variable = '&flow velocity', x_values = 0.5, 1.4, amplitude_pp = 0.0, " &
         // 'progress = .false., chunk = 1 /'
      ov(5) = '&output write_text = .false. /'
      ov(6) = '&solver transient_periods = 1 /'
      ov(7) = '&forcing frequency_hz = 4.0 /'   ! a record of 0.25 s, one period of the load
   end function sweep_overrides

   !> Run the sweep through the job driver (shard i of n, time limit); complete on return.
   subroutine sweep_job(prefix, shard, n_shards, limit, complete)
      character(len=*), intent(in) :: prefix
      integer, intent(in) :: shard, n_shards
      real(dp), intent(in) :: limit
      logical, intent(out) :: complete
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      integer :: n_failed
      complete = .false.
      call read_deck(buffet, sweep_overrides(prefix), deck, err)
      if (.not. allocated(err)) call run_sweep_job(deck, batch_options_t(shard_index=shard, &
         shard_count=n_shards, time_limit_s=limit, quiet=.true.), complete, n_failed, err)
      if (allocated(err)) call check('sweep ' // prefix // ' runs', .false., err%message)
   end subroutine sweep_job

   !> Do the points of a sweep file have exactly the statistics of `want`?
   logical function same_statistics(path, want) result(same)
      character(len=*), intent(in) :: path
      type(point_result_t), intent(in) :: want(:)
      type(sweep_file_t) :: sf
      type(point_result_t), allocatable :: got(:)
      type(error_t), allocatable :: err
      integer :: k
      same = .false.
      call read_sweep(path, sf, got, err)
      if (allocated(err)) return
      if (size(got) /= size(want)) return
      do k = 1, size(want)
         if (got(k)%n_draws /= want(k)%n_draws) return
         if (.not. (allocated(got(k)%draw_mean) .and. allocated(want(k)%draw_mean))) return
         if (any(got(k)%draw_mean /= want(k)%draw_mean)) return
         if (any(got(k)%draw_ci /= want(k)%draw_ci)) return
      end do
      same = .true.
   end function same_statistics

   !> A velocity sweep with 3 draws per point: the statistics, threads, shards, checkpoint.
   subroutine sweep_with_draws()
      character(len=*), parameter :: base = 'test_flow_draws_sweep'
      type(sweep_file_t) :: sf
      type(point_result_t), allocatable :: pts(:)
      type(error_t), allocatable :: err
      type(deck_t) :: deck
      type(sweep_plan_t) :: plan
      type(model_t) :: model
      type(transient_result_t) :: res
      type(output_settings_t) :: o
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: x(3), v(1, n_draw_outputs), mean, hw, velocity(2)
      logical :: complete
      integer :: p, d
      !$ call omp_set_num_threads(1)
      call sweep_job(base, 1, 1, 0.0_dp, complete)
      call check('sweep with draws: completes', complete .and. file_exists(base // '.h5'))
      if (.not. complete) return
      call read_sweep(base // '.h5', sf, pts, err)
      call check('sweep with draws: the file reads', .not. allocated(err))
      if (allocated(err)) return
      call check('sweep with draws: every point has 3 draws', all(pts%n_draws == 3))
      if (.not. all(pts%n_draws == 3)) return
      ! each point against its draws run one by one
      call read_deck(buffet, sweep_overrides(base), deck, err)
      if (.not. allocated(err)) call make_plan(deck, plan, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err)
      if (allocated(err)) return
      o = deck%output
      o%history_periods = deck%solver%record_periods
      velocity = [0.5_dp, 1.4_dp]
      do p = 1, 2
         do d = 1, 3
            call run_draw(deck, plan%set, [velocity(p), 0.0_dp], d, u0, v0, o, res, err)
            if (allocated(err)) then
               call check('sweep with draws: a draw runs alone', .false., err%message)
               return
            end if
            call draw_values(res, 0.25_dp, 1, v)
            x(d) = v(1, n_draw_outputs)
         end do
         call mean_half_width(x, mean, hw)
         call check_close('sweep with draws: point ' // str(p) // ': mean tip RMS = the draws ' &
                          // 'run alone', pts(p)%draw_mean(1, n_draw_outputs), mean, 1.0e-12_dp)
         call check_close('sweep with draws: point ' // str(p) // ': its 95 % half-width', &
                          pts(p)%draw_ci(1, n_draw_outputs), hw, 1.0e-12_dp)
         call check('sweep with draws: point ' // str(p) // ': the draws differ', hw > 0.0_dp)
         call note('sweep with draws: U = ' // str(velocity(p)) // ' m/s: tip RMS ' // str(mean) &
                   // ' +- ' // str(hw) // ' m (3 draws)')
      end do
      call check('sweep with draws: nearer U_c (1.66 m/s) the tube responds more', &
                 pts(2)%draw_mean(1, n_draw_outputs) > pts(1)%draw_mean(1, n_draw_outputs))
      !$ call omp_set_num_threads(2)
      call sweep_job(base // '_2t', 1, 1, 0.0_dp, complete)
      call check('sweep with draws: 2 threads give the same statistics bit for bit', &
                 complete .and. same_statistics(base // '_2t.h5', pts))
      !$ call omp_set_num_threads(1)
      call sweep_job(base // '_part', 1, 2, 0.0_dp, complete)
      call sweep_job(base // '_part', 2, 2, 0.0_dp, complete)
      call merge_sweep(base // '_merged', [character(len=64) :: base // '_part.shard_2_of_2.h5', &
         base // '_part.shard_1_of_2.h5'], .false., err)
      call check('sweep with draws: two shards merge', .not. allocated(err))
      call check('sweep with draws: the merged shards have the same statistics', &
                 same_statistics(base // '_merged.h5', pts))
      call sweep_job(base // '_resume', 1, 1, 1.0e-9_dp, complete)
      call check('sweep with draws: a time limit stops it, the checkpoint kept', &
                 .not. complete .and. file_exists(base // '_resume.checkpoint'))
      call sweep_job(base // '_resume', 1, 1, 0.0_dp, complete)
      call check('sweep with draws: resumed from the checkpoint, the same statistics', &
                 complete .and. same_statistics(base // '_resume.h5', pts))
      call remove_file(base // '.h5')
      call remove_file(base // '_2t.h5')
      call remove_file(base // '_merged.h5')
      call remove_file(base // '_part.shard_1_of_2.h5')
      call remove_file(base // '_part.shard_2_of_2.h5')
      call remove_file(base // '_resume.h5')
   end subroutine sweep_with_draws

   !> The stopping rule of draws_target_ci on made-up draws of 2 stops.
   subroutine stopping_rule()
      type(deck_t) :: deck
      real(dp) :: vals(12, 2, n_draw_outputs)
      integer :: n, d
      deck%turbulence%spectrum = 'table'
      deck%turbulence%draws = 3
      deck%turbulence%draws_target_ci = 0.1_dp
      deck%turbulence%draws_max = 12
      vals = 0.0_dp
      ! stop 1's work rate 1 +- 0.1 alternating; stop 2 untouched; the tip 1 exactly
      do d = 1, 12
         vals(d, 1, 5) = 1.0_dp + 0.1_dp * (-1.0_dp)**d
         vals(d, 1, 6) = 2.0_dp
         vals(d, 1, n_draw_outputs) = 1.0_dp
      end do
      n = first_enough(deck, vals)
      call check('stopping rule: not before draws = 3', .not. draws_enough(deck, vals, 2))
      call check('stopping rule: stops at the first count within the target (' // str(n) &
                 // ')', n < 12 .and. relative_half_width(vals(1:n, 1, 5)) <= 0.1_dp .and. &
                 relative_half_width(vals(1:n - 1, 1, 5)) > 0.1_dp)
      call check('stopping rule: an untouched support does not hold it up', n < 12)
      vals(:, 2, 6) = [(real(mod(d, 2), dp), d = 1, 12)]   ! stop 2 now scattered: 1, 0, 1, ...
      call check('stopping rule: a scattered support holds it up to draws_max', &
                 first_enough(deck, vals) == 12)
      deck%turbulence%draws_target_ci = 0.0_dp
      call check('stopping rule: without a target, draws = 3 draws', &
                 first_enough(deck, vals) == 3)
   end subroutine stopping_rule

   !> The first count at which draws_enough holds.
   integer function first_enough(deck, vals) result(n)
      type(deck_t), intent(in) :: deck
      real(dp), intent(in) :: vals(:, :, :)
      do n = 1, size(vals, 1)
         if (draws_enough(deck, vals, n)) return
      end do
   end function first_enough

   !> The target on the tube (transient, short correlation): the count collect_draws reaches
   !> is the first whose tip RMS is within the target.
   subroutine target_on_the_tube()
      type(deck_t) :: deck
      type(model_t) :: model
      type(transient_result_t) :: res1
      type(error_t), allocatable :: err
      type(deck_variable_t) :: none(0)
      real(dp) :: nothing(0)
      real(dp), allocatable :: u0(:), v0(:), vals(:, :, :)
      integer :: n
      real(dp), parameter :: target = 0.1_dp
      call read_deck(buffet, [character(len=160) :: '&turbulence draws = 2, ' &
         // 'correlation_length = 0.05, draws_target_ci = 0.1, draws_max = 8, ' &
         // 'frequency_resolution_hz = 4.0 /', '&solver transient_periods = 1 /', &
         '&forcing frequency_hz = 4.0 /'], deck, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err)
      if (.not. allocated(err)) call run_draw(deck, none, nothing, 1, u0, v0, deck%output, &
                                              res1, err)
      if (.not. allocated(err)) call collect_draws(deck, none, nothing, u0, v0, deck%output, &
                                                   res1, 0.25_dp, vals, err)
      call check('target half-width: the draws run', .not. allocated(err))
      if (allocated(err)) return
      n = size(vals, 1)
      call note('target half-width ' // str(target) // ': ' // str(n) // ' draws, tip RMS ' &
                // 'relative half-width ' // str(relative_half_width(vals(:, 1, n_draw_outputs))))
      call check('target half-width: within the target, or draws_max', n == 8 .or. &
                 relative_half_width(vals(:, 1, n_draw_outputs)) <= target)
      call check('target half-width: one draw fewer is not within it', n == 2 .or. &
                 relative_half_width(vals(1:n - 1, 1, n_draw_outputs)) > target)
      call check('target half-width: more than the first draws were needed', n > 2)
   end subroutine target_on_the_tube

   !> The periodogram of 300 samples (not a power of two): its DFT against the direct sum,
   !> a sinusoid on a bin at its frequency, Parseval.
   subroutine periodogram_of_a_line()
      integer, parameter :: n = 300
      real(dp) :: x(n), dt, var, err_dft
      real(dp), allocatable :: f(:), p(:)
      complex(dp) :: z(n), direct
      integer :: j, k
      dt = 1.0e-3_dp
      do j = 1, n
         x(j) = 2.0_dp * cos(2.0_dp * pi * 17.0_dp * (j - 1) / n + 0.3_dp) &
                + 0.5_dp * sin(2.0_dp * pi * 41.0_dp * (j - 1) / n) + 0.1_dp * mod(j * 7, 11)
      end do
      z = dft(cmplx(x, 0.0_dp, dp))
      err_dft = 0.0_dp
      do k = 0, n - 1
         direct = sum([(x(j + 1) * exp(cmplx(0.0_dp, -2.0_dp * pi * real(mod(j * k, n), dp) &
                                               / n, dp)), j = 0, n - 1)])
         err_dft = max(err_dft, abs(z(k + 1) - direct))
      end do
      call check_le('periodogram: Bluestein DFT of 300 samples = the direct sum (relative to ' &
                    // 'the largest)', err_dft / maxval(abs(z)), 1.0e-12_dp)
      call periodogram_psd(x, dt, f, p)
      var = sum((x - sum(x) / n)**2) / n
      call check_close('periodogram: sum of P df = variance (Parseval)', sum(p) / (n * dt), &
                       var, 1.0e-12_dp)
      call check_close('periodogram: frequency of bin 17', f(18), 17.0_dp / (n * dt), 1.0e-14_dp)
      call check('periodogram: the cosine of amplitude 2 holds the largest bin', &
                 maxloc(p, 1) == 18)
   end subroutine periodogram_of_a_line

   !> The analytic tip PSD S(f_k) sum_m |H_tip(f_k) L_m|^2 [m^2/Hz] at f_k = k df.
   subroutine analytic_tip_psd(deck, f, s_ref, ok)
      type(deck_t), intent(in) :: deck
      real(dp), intent(in) :: f(:)
      real(dp), allocatable, intent(out) :: s_ref(:)
      logical, intent(out) :: ok
      type(model_t) :: model
      type(modes_t) :: modes
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), shapes(:, :), gm(:, :)
      integer, allocatable :: plane_of(:), rank_in_plane(:)
      complex(dp) :: h
      real(dp) :: w, sk
      integer :: k, m, j, tip
      call build_model(deck, model, u0, v0, err)
      if (.not. allocated(err)) call solve_modes(model%sys, modes, err)
      if (.not. allocated(err)) call load_shapes(model%sys, deck%turbulence, shapes, &
                                                 plane_of, rank_in_plane, err)
      ok = .not. allocated(err)
      if (.not. ok) return
      tip = global_dof(model%sys, model%sys%n_node, dof_w)
      gm = matmul(transpose(modes%shapes), shapes)
      allocate(s_ref(size(f)), source=0.0_dp)
      do k = 1, size(f)
         w = 2.0_dp * pi * f(k)
         sk = turbulence_psd(deck%turbulence, deck%flow, f(k))
         if (sk <= 0.0_dp) cycle
         do m = 1, size(shapes, 2)
            h = (0.0_dp, 0.0_dp)
            do j = 1, modes%n_modes
               h = h + modes%shapes(tip, j) * gm(j, m) / cmplx(modes%omega2(j) - w * w, &
                   w * (model%beta + model%gamma * modes%omega2(j)), dp)
            end do
            s_ref(k) = s_ref(k) + sk * abs(h)**2
         end do
      end do
   end subroutine analytic_tip_psd

   !> The mean over Welch's segments (gapbeam_response_psd: segment_length, hop half of it)
   !> of sum ((x - segment mean) w)^2 / sum w^2, x = row' u at the history samples.
   real(dp) function hann_mean_square(deck, res, row) result(ms)
      type(deck_t), intent(in) :: deck
      type(transient_result_t), intent(in) :: res
      real(dp), intent(in) :: row(:)
      real(dp), allocatable :: x(:), w(:), seg(:)
      real(dp) :: dt
      integer :: n, m, start, i, count
      n = size(res%time)
      dt = res%time(2) - res%time(1)
      x = matmul(row, res%history_u(:, 1:n))
      m = segment_length(deck, n, dt)
      w = [(0.5_dp - 0.5_dp * cos(2.0_dp * pi * i / m), i = 0, m - 1)]
      ms = 0.0_dp;  count = 0;  start = 1
      do while (start + m - 1 <= n)
         seg = x(start:start + m - 1)
         seg = (seg - sum(seg) / m) * w
         ms = ms + sum(seg**2) / sum(w**2)
         count = count + 1
         start = start + m / 2
      end do
      ms = ms / count
   end function hann_mean_square

   !> The tip PSD of the linear tube against the analytic modal response.
   subroutine response_psd_linear_tube()
      character(len=160) :: ov(4)
      type(deck_t) :: deck
      type(model_t) :: model
      type(response_psd_t) :: psd, welch
      type(transient_result_t) :: res1
      type(error_t), allocatable :: err
      type(output_settings_t) :: o
      type(deck_variable_t) :: none(0)
      real(dp), allocatable :: u0(:), v0(:), rows(:, :), s_ref(:), vals(:, :, :), band(:)
      real(dp) :: nothing(0), peak, mean, hw, t99, z_max, var_p, var_w
      integer :: k, b, n_in, n_bands
      logical :: ok
      ov(1) = '&turbulence psd_nodes = 9, psd_method = ''periodogram'', ' &
         // 'frequency_resolution_hz = 4.0 /'
      ov(2) = '&forcing frequency_hz = 4.0 /   ! one period of the record, 0.25 s'
      ov(3) = '&solver transient_periods = 2 /'
      ov(4) = '&damping ratio1 = 0.05, ratio2 = 0.05 /   ! the start-up decays as 4e-4 in 0.5 s'
      ! fully correlated: one draw, every harmonic
      call read_deck(buffet, ov, deck, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err)
      if (.not. allocated(err)) call psd_rows(deck, rows, psd, err)
      o = deck%output
      o%state_history = .true.
      if (.not. allocated(err)) call run_draw(deck, none, nothing, 1, u0, v0, o, res1, err)
      if (.not. allocated(err)) call add_draw_psd(deck, res1, rows, psd, err)
      call check('response PSD: the tip''s periodogram of one draw', .not. allocated(err))
      if (allocated(err)) return
      call finish_psd(psd)
      call analytic_tip_psd(deck, psd%frequency_hz, s_ref, ok)
      if (.not. ok) return
      peak = maxval(s_ref)
      call check('response PSD: one series (node 9, w), bins 4 Hz apart', size(psd%psd, 2) == 1 &
                 .and. psd%nodes(1) == 9 .and. abs(psd%frequency_hz(2) - 4.0_dp) < 1.0e-9_dp)
      call check_le('response PSD, fully correlated: every bin = S |H L|^2 (relative to the ' &
                    // 'peak)', maxval(abs(psd%psd(:, 1) - s_ref)) / peak, 5.0e-3_dp)
      call note('response PSD, fully correlated: peak ' // str(maxval(psd%psd(:, 1))) &
                // ' m^2/Hz at ' // str(psd%frequency_hz(maxloc(psd%psd(:, 1), 1))) &
                // ' Hz, analytic ' // str(peak) // ' at ' // str(psd%frequency_hz(maxloc(s_ref, &
                1))) // ' Hz')
      ! Welch on the same draw: the variance (its integral) against the periodogram's
      welch%method = 'welch'
      welch%nodes = psd%nodes;  welch%planes = psd%planes
      call add_draw_psd(deck, res1, rows, welch, err)
      if (allocated(err)) return
      var_p = sum(psd%draws(:, 1, 1)) * psd%frequency_hz(2)
      var_w = sum(welch%draws(:, 1, 1)) * welch%frequency_hz(2)
      call check_close('response PSD: Welch''s integral = the Hann-weighted mean square of ' &
                       // 'its segments (Parseval)', var_w, hann_mean_square(deck, res1, &
                       rows(:, 1)), 1.0e-12_dp)
      call note('response PSD: Welch (' // str(size(welch%frequency_hz)) // ' bins of ' &
                // str(welch%frequency_hz(2)) // ' Hz) variance ' // str(var_w) // ', the ' &
                // 'periodogram''s ' // str(var_p) // ' m^2 (short segments lose the lowest ' &
                // 'harmonics with their means)')
      ! short correlation: 8 draws, bands of 5 harmonics against their 99 % intervals
      deck%turbulence%correlation_length = 0.05_dp
      deck%turbulence%draws = 8
      call psd_rows(deck, rows, psd, err)
      if (.not. allocated(err)) call run_draw(deck, none, nothing, 1, u0, v0, o, res1, err)
      if (.not. allocated(err)) call collect_draws(deck, none, nothing, u0, v0, o, res1, &
                                                   0.25_dp, vals, err, rows, psd)
      call check('response PSD, short correlation: 8 draws run', .not. allocated(err))
      if (allocated(err)) return
      call analytic_tip_psd(deck, psd%frequency_hz, s_ref, ok)
      if (.not. ok) return
      t99 = student_t_quantile(0.995_dp, 7)
      n_bands = 0;  n_in = 0;  z_max = 0.0_dp
      do b = 0, size(s_ref) / 5 - 1
         if (all(s_ref(5 * b + 1:5 * b + 5) == 0.0_dp)) cycle
         band = [(sum(psd%draws(5 * b + 1:5 * b + 5, 1, k)) / 5.0_dp, k = 1, 8)]
         call mean_half_width(band, mean, hw)
         hw = hw * t99 / student_t_quantile(0.975_dp, 7)
         n_bands = n_bands + 1
         if (abs(mean - sum(s_ref(5 * b + 1:5 * b + 5)) / 5.0_dp) <= hw) n_in = n_in + 1
         z_max = max(z_max, abs(mean - sum(s_ref(5 * b + 1:5 * b + 5)) / 5.0_dp) / hw)
      end do
      call check('response PSD, short correlation: each band of 5 harmonics within the 99 % ' &
                 // 'interval of 8 draws (' // str(n_in) // ' of ' // str(n_bands) // ')', &
                 n_bands >= 6 .and. n_in == n_bands)
      call note('response PSD, short correlation: the largest |mean - analytic| / (99 % ' &
                // 'half-width) over the bands ' // str(z_max))
   end subroutine response_psd_linear_tube
end program test_flow_draws
