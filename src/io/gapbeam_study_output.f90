!> Result files of the studies: HDF5 (every dataset described by the output catalogue, with
!> the deck, its parameters and its model), one gnuplot-ready table per work-precision
!> series, the spectral-radius table, and a plain-text summary. The files of one run form an
!> output set (gapbeam_output_set): put in place together, or not at all.
module gapbeam_study_output
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_output_set, only: output_set_t
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: series_result_t, stable_step_t, candidate_t, cpu_to_reach, &
      label_text
   use gapbeam_parameters, only: run_parameters, stiffness_units
   use gapbeam_file_info, only: write_parameter_set, write_model
   implicit none
   private
   public :: write_work_precision, write_stability, work_precision_summary, write_model_size

contains

   !> Summary: per series the CPU time to reach output errors of 1e-2, 1e-3, 1e-6 and 1e-9
   !> and the ratio to the reference series.
   function work_precision_summary(results, reference) result(text)
      type(series_result_t), intent(in) :: results(:)   !! series
      character(len=*), intent(in) :: reference          !! series the ratios refer to
      character(len=:), allocatable :: text
      integer :: s, j, r
      real(dp) :: t, tr
      character(len=200) :: line
      real(dp), parameter :: levels(4) = [1.0e-2_dp, 1.0e-3_dp, 1.0e-6_dp, 1.0e-9_dp]
      r = 0
      do s = 1, size(results)
         if (results(s)%name == reference) r = s
      end do
      text = 'CPU time to reach an output error (the largest error of the root strain, its ' &
         // 'rate and the tip' // new_line('a') // 'displacement over the sampled history, ' &
         // 'relative to their ranges; log-log interpolation between runs);' // new_line('a') &
         // 'ratio: time / time of ' // reference // '; failed: every run of the series ' &
         // 'failed or diverged' // new_line('a') // '  series                   ' &
         // '     t(1e-2) [s]  ratio   t(1e-3) [s]  ratio   t(1e-6) [s]  ratio   t(1e-9) [s]  ratio' &
         // new_line('a')
      do s = 1, size(results)
         write(line, '(2x, a24)') results(s)%name
         do j = 1, size(levels)
            t = cpu_to_reach(results(s), levels(j), output=.true.)
            tr = -1.0_dp
            if (r > 0) tr = cpu_to_reach(results(r), levels(j), output=.true.)
            if (all(results(s)%status /= 0)) then
               line = trim(line) // '         failed      -'
            else if (t < 0.0_dp) then
               line = trim(line) // '    not reached      -'
            else if (tr > 0.0_dp .and. t / tr < 999.5_dp) then
               write(line(len_trim(line) + 1:), '(es14.3, f7.1)') t, t / tr
            else if (tr > 0.0_dp) then
               write(line(len_trim(line) + 1:), '(es14.3, es7.0)') t, t / tr
            else
               write(line(len_trim(line) + 1:), '(es14.3, a7)') t, '-'
            end if
         end do
         text = text // trim(line) // new_line('a')
      end do
   end function work_precision_summary

   !> PREFIX.h5, PREFIX.wp_<series>.dat (the runs that succeeded), PREFIX.work_precision_failed.dat
   !> (the runs that failed or diverged: marked on the chart, never taken for results),
   !> PREFIX.work_precision.txt.
   subroutine write_work_precision(deck, model, results, reference, err)
      type(deck_t), intent(in) :: deck                           !! the deck
      type(model_t), intent(in) :: model                         !! its model
      type(series_result_t), intent(in) :: results(:)            !! series
      character(len=*), intent(in) :: reference                  !! series for the ratios
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      character(len=:), allocatable :: suffixes(:), names, title, g
      integer :: s, width
      title = trim(deck%job%title)
      width = len('.work_precision_failed.dat')
      do s = 1, size(results)
         width = max(width, len('.wp_' // results(s)%name // '.dat'))
      end do
      allocate(character(len=width) :: suffixes(size(results) + 3))
      suffixes(1) = '.h5'
      do s = 1, size(results)
         suffixes(1 + s) = '.wp_' // results(s)%name // '.dat'
      end do
      suffixes(size(suffixes) - 1) = '.work_precision_failed.dat'
      suffixes(size(suffixes)) = '.work_precision.txt'
      call set%begin(deck%job%output, suffixes)
      call study_head(set, h5, 'work_precision', deck, model)
      do s = 1, size(results)
         g = '/work_precision/' // results(s)%name
         call h5%put(g // '/parameter_name', results(s)%parameter_name)
         call h5%put(g // '/parameter', results(s)%parameter)
         call h5%put(g // '/seconds', results(s)%seconds)
         call h5%put(g // '/error', results(s)%error)
         call h5%put(g // '/poincare_error', results(s)%poincare_error)
         call h5%put(g // '/steps', results(s)%steps)
         call h5%put(g // '/output_error', results(s)%output_error)
         call h5%put(g // '/strain_error', [results(s)%output_errors(1, :)])
         call h5%put(g // '/strain_rate_error', [results(s)%output_errors(2, :)])
         call h5%put(g // '/tip_error', [results(s)%output_errors(3, :)])
         call h5%put(g // '/status', results(s)%status)
         call h5%put(g // '/seconds_to_1e-3', cpu_to_reach(results(s), 1.0e-3_dp))
         call h5%put(g // '/seconds_to_1e-6', cpu_to_reach(results(s), 1.0e-6_dp))
         call h5%put(g // '/seconds_to_output_1e-3', cpu_to_reach(results(s), 1.0e-3_dp, .true.))
         call h5%put(g // '/seconds_to_output_1e-6', cpu_to_reach(results(s), 1.0e-6_dp, .true.))
         call h5%put(g // '/seconds_to_output_1e-9', cpu_to_reach(results(s), 1.0e-9_dp, .true.))
      end do
      call set%close_h5(h5)
      names = ''
      do s = 1, size(results)
         call set%table(trim(suffixes(1 + s)), title // ': ' // results(s)%name, &
            [character(len=18) :: 'seconds', 'error', 'poincare_error', 'steps', 'parameter', &
            'output_error', 'strain_error', 'strain_rate_error', 'tip_error'], &
            [character(len=18) :: 's', '-', '-', '-', results(s)%parameter_name, '-', '-', '-', &
            '-'], ok_rows(results(s)))
         names = names // ' ' // results(s)%name
      end do
      call set%table('.work_precision_failed.dat', title // ': failed or diverged runs (error ' &
         // 'not finite); series numbers:' // names, [character(len=16) :: 'series', 'seconds', &
         'parameter', 'steps', 'status'], [character(len=16) :: '-', 's', '-', '-', &
         '1: failed'], failed_rows(results))
      call set%text('.work_precision.txt', title // new_line('a') &
         // work_precision_summary(results, reference))
      call set%finish(err)
   end subroutine write_work_precision

   !> The rows of a series' table: the runs that succeeded, with finite errors (a failed or
   !> diverged run is in PREFIX.work_precision_failed.dat instead).
   function ok_rows(series) result(rows)
      type(series_result_t), intent(in) :: series                !! one series
      real(dp), allocatable :: rows(:, :)
      logical, allocatable :: keep(:)
      keep = run_ok(series)
      allocate(rows(count(keep), 9))
      rows(:, 1) = pack(series%seconds, keep)
      rows(:, 2) = pack(series%error, keep)
      rows(:, 3) = pack(series%poincare_error, keep)
      rows(:, 4) = pack(series%steps, keep)
      rows(:, 5) = pack(series%parameter, keep)
      rows(:, 6) = pack(series%output_error, keep)
      rows(:, 7) = pack(series%output_errors(1, :), keep)
      rows(:, 8) = pack(series%output_errors(2, :), keep)
      rows(:, 9) = pack(series%output_errors(3, :), keep)
   end function ok_rows

   !> Which runs of a series succeeded with finite errors.
   function run_ok(series) result(ok)
      type(series_result_t), intent(in) :: series                !! one series
      logical, allocatable :: ok(:)
      ok = series%status == 0 .and. ieee_is_finite(series%error) &
           .and. ieee_is_finite(series%poincare_error) .and. ieee_is_finite(series%output_error)
   end function run_ok

   !> The runs that failed or diverged, every series: (series number, seconds, parameter,
   !> steps, 1), so that a chart can mark them; finite numbers only.
   function failed_rows(results) result(rows)
      type(series_result_t), intent(in) :: results(:)            !! every series
      real(dp), allocatable :: rows(:, :)
      logical, allocatable :: bad(:)
      real(dp) :: secs
      integer :: s, k, n
      n = 0
      do s = 1, size(results)
         n = n + count(.not. run_ok(results(s)))
      end do
      allocate(rows(n, 5))
      n = 0
      do s = 1, size(results)
         bad = .not. run_ok(results(s))
         do k = 1, size(bad)
            if (.not. bad(k)) cycle
            n = n + 1
            secs = results(s)%seconds(k)
            if (.not. ieee_is_finite(secs)) secs = 0.0_dp
            rows(n, :) = [real(s, dp), secs, results(s)%parameter(k), &
                          real(results(s)%steps(k), dp), 1.0_dp]
            if (.not. ieee_is_finite(rows(n, 3))) rows(n, 3) = 0.0_dp
            if (.not. ieee_is_finite(rows(n, 4))) rows(n, 4) = 0.0_dp
         end do
      end do
   end function failed_rows

   !> The .h5 of a study: root attributes, /deck, /run/files, /parameters and /model.
   subroutine study_head(set, h5, analysis, deck, model)
      type(output_set_t), intent(in) :: set                      !! the set
      type(h5_writer_t), intent(inout) :: h5                     !! writer, not open
      character(len=*), intent(in) :: analysis                   !! analysis word
      type(deck_t), intent(in) :: deck                           !! the deck
      type(model_t), intent(in) :: model                         !! its model
      call set%open_h5(h5, analysis, deck%text, deck%warnings)
      call write_parameter_set(h5, run_parameters(deck, model%stop_stiffness, &
         model%f1_open_hz, model%omega_max / (2.0_dp * pi), model%n))
      call write_model(h5, model, stiffness_units(deck))
   end subroutine study_head

   !> PREFIX.h5, PREFIX.spectral_radius.dat, PREFIX.stability.txt.
   subroutine write_stability(deck, model, methods, omega_dt, rho, steps, err)
      type(deck_t), intent(in) :: deck                           !! the deck
      type(model_t), intent(in) :: model                         !! its model
      character(len=*), intent(in) :: methods(:)                 !! methods of the chart
      real(dp), intent(in) :: omega_dt(:), rho(:, :)             !! chart
      type(stable_step_t), intent(in) :: steps(:)                !! stable steps
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      character(len=:), allocatable :: text, title
      character(len=24), allocatable :: names(:), units(:)
      character(len=160) :: line
      integer :: m
      title = trim(deck%job%title)
      call set%begin(deck%job%output, [character(len=20) :: '.h5', '.spectral_radius.dat', &
                     '.stability.txt'])
      call study_head(set, h5, 'stability', deck, model)
      call h5%put('/stability/omega_dt', omega_dt)
      call h5%put('/stability/methods', methods)
      call h5%put('/stability/spectral_radius', rho)
      call h5%put('/stability/omega_max', model%omega_max)
      call h5%put('/stability/stable_step_measured', [(steps(m)%measured, m = 1, size(steps))])
      call h5%put('/stability/stable_step_theory', [(steps(m)%theory, m = 1, size(steps))])
      call set%close_h5(h5)
      allocate(names(1 + size(methods)), units(1 + size(methods)))
      names(1) = 'omega_dt';  units(1) = '-'
      names(2:) = methods;  units(2:) = '-'
      call set%table('.spectral_radius.dat', title // ': spectral radius of one step, ' &
         // 'undamped test equation', names, units, reshape([omega_dt, reshape(rho, &
         [size(rho)])], [size(omega_dt), 1 + size(methods)]))
      text = title // new_line('a') // 'largest stable fixed step, bisection with real runs ' &
         // '(3000 steps of free undamped vibration from a random displacement), ' &
         // 'omega_max = ' // str(model%omega_max) // ' rad/s' // new_line('a') &
         // '  method                 measured [s]    theory [s]   limit   ratio' // new_line('a')
      do m = 1, size(steps)
         write(line, '(2x, a20, 2es15.6, f8.4, f9.5)') steps(m)%name, steps(m)%measured, &
            steps(m)%theory, steps(m)%limit, steps(m)%measured / steps(m)%theory
         text = text // trim(line) // new_line('a')
      end do
      call set%text('.stability.txt', text)
      call set%finish(err)
   end subroutine write_stability

   !> PREFIX.h5, PREFIX.model_size.dat (one row per candidate), PREFIX.model_size.txt.
   subroutine write_model_size(deck, model, cands, best, err)
      type(deck_t), intent(in) :: deck                           !! the deck
      type(model_t), intent(in) :: model                         !! its model
      type(candidate_t), intent(in) :: cands(:)                  !! the ladder
      integer, intent(in) :: best                                !! recommended (0: none)
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      character(len=24), allocatable :: names(:)
      real(dp), allocatable :: cols(:, :)
      integer :: k, n
      n = size(cands)
      allocate(names(n), cols(n, 9))
      do k = 1, n
         names(k) = cands(k)%name
         cols(k, :) = [real(k, dp), real(cands(k)%n_coordinates, dp), cands(k)%seconds, &
            cands(k)%poincare_distance, cands(k)%frequency_error, real(cands(k)%label, dp), &
            cands(k)%lyapunov, cands(k)%peak_force, merge(1.0_dp, 0.0_dp, cands(k)%acceptable)]
      end do
      call set%begin(deck%job%output, [character(len=16) :: '.h5', '.model_size.dat', &
                     '.model_size.txt'])
      call study_head(set, h5, 'model_size', deck, model)
      call h5%put('/model_size/name', names)
      call h5%put('/model_size/n_elem', [(cands(k)%n_elem, k = 1, n)])
      call h5%put('/model_size/n_modes', [(cands(k)%n_modes, k = 1, n)])
      call h5%put('/model_size/n_coordinates', [(cands(k)%n_coordinates, k = 1, n)])
      call h5%put('/model_size/frequency_error', [(cands(k)%frequency_error, k = 1, n)])
      call h5%put('/model_size/period', [(cands(k)%period, k = 1, n)])
      call h5%put('/model_size/label', [(cands(k)%label, k = 1, n)])
      call h5%put('/model_size/lyapunov', [(cands(k)%lyapunov, k = 1, n)])
      call h5%put('/model_size/poincare_distance', [(cands(k)%poincare_distance, k = 1, n)])
      call h5%put('/model_size/peak_force', [(cands(k)%peak_force, k = 1, n)])
      call h5%put('/model_size/seconds', [(cands(k)%seconds, k = 1, n)])
      call h5%put('/model_size/recommended', best)
      call set%close_h5(h5)
      call set%table('.model_size.dat', trim(deck%job%title) // ': model-size ladder ' &
         // '(candidate numbers as in the .txt report)', [character(len=20) :: 'candidate', &
         'coordinates', 'seconds', 'poincare_distance', 'frequency_error', 'label', 'lyapunov', &
         'peak_force', 'acceptable'], [character(len=20) :: '-', '-', 's', '-', '-', &
         'p|0|-1', '1/s', 'N', '1|0'], cols)
      call set%text('.model_size.txt', model_size_report(trim(deck%job%title), cands, best))
      call set%finish(err)
   end subroutine write_model_size

   !> The plain-text report of the model-size ladder.
   function model_size_report(title, cands, best) result(text)
      character(len=*), intent(in) :: title                      !! the run's title
      type(candidate_t), intent(in) :: cands(:)                  !! the ladder
      integer, intent(in) :: best                                !! recommended (0: none)
      character(len=:), allocatable :: text
      character(len=200) :: line
      integer :: k
      text = title // new_line('a') // '  #  model                 coords  f-error   label      ' &
         // 'lambda[1/s]  Poincare-dist  peak F [N]   time [s]  ok' // new_line('a')
      do k = 1, size(cands)
         if (cands(k)%status /= 0) then
            write(line, '(i3, 2x, a20, a)') k, cands(k)%name, '  failed: ' // cands(k)%message
         else if (cands(k)%frequency_error > 1.0e300_dp) then
            ! fewer modes below the cut-off than the reference: no frequency comparison
            write(line, '(i3, 2x, a20, i7, a10, 2x, a10, es12.3, es15.3, es12.4, es11.3, l4)') &
               k, cands(k)%name, cands(k)%n_coordinates, '    n/a  ', &
               label_text(cands(k)%label), cands(k)%lyapunov, cands(k)%poincare_distance, &
               cands(k)%peak_force, cands(k)%seconds, cands(k)%acceptable
         else
            write(line, '(i3, 2x, a20, i7, es10.2, 2x, a10, es12.3, es15.3, es12.4, es11.3, l4)') &
               k, cands(k)%name, cands(k)%n_coordinates, cands(k)%frequency_error, &
               label_text(cands(k)%label), cands(k)%lyapunov, cands(k)%poincare_distance, &
               cands(k)%peak_force, cands(k)%seconds, cands(k)%acceptable
         end if
         text = text // trim(line) // new_line('a')
      end do
      if (best > 0) then
         text = text // 'recommended: ' // cands(best)%name // ' (' &
            // str(cands(best)%n_coordinates) // ' coordinates)' // new_line('a')
      else
         text = text // 'recommended: none meets every tolerance' // new_line('a')
      end if
   end function model_size_report
end module gapbeam_study_output
