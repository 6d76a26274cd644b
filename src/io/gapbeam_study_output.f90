!> Result files of the studies: HDF5, one gnuplot-ready table per work-precision series,
!> the spectral-radius table, and a plain-text summary. The files of one run form an output
!> set (gapbeam_output_set): put in place together, or not at all.
module gapbeam_study_output
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t, write_failed
   use gapbeam_files, only: write_table, write_text_file
   use gapbeam_output_set, only: output_set_t
   use gapbeam_results, only: series_result_t, stable_step_t, candidate_t, cpu_to_reach, &
      label_text
   use gapbeam_parameters, only: parameter_set_t
   use gapbeam_file_info, only: write_file_info, write_parameter_set
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
   subroutine write_work_precision(prefix, title, deck_text, results, reference, err, params)
      character(len=*), intent(in) :: prefix, title, deck_text   !! output, title, deck
      type(series_result_t), intent(in) :: results(:)            !! series
      character(len=*), intent(in) :: reference                  !! series for the ratios
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(parameter_set_t), intent(in), optional :: params      !! /parameters
      type(output_set_t) :: set
      character(len=:), allocatable :: suffixes(:)
      character(len=:), allocatable :: names
      integer :: s, width
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
      call set%begin(prefix, suffixes, err);  if (allocated(err)) return
      call work_precision_h5(set, deck_text, results, err, params)
      do s = 1, size(results)
         if (allocated(err)) exit
         call write_table(set%temp(1 + s), title // ': ' // results(s)%name, &
            [character(len=18) :: 'seconds', 'error', 'poincare_error', 'steps', 'parameter', &
            'output_error', 'strain_error', 'strain_rate_error', 'tip_error'], &
            [character(len=18) :: 's', '-', '-', '-', results(s)%parameter_name, '-', '-', '-', &
            '-'], &
            ok_rows(results(s)), err, in_place=.true.)
      end do
      names = ''
      do s = 1, size(results)
         names = names // ' ' // results(s)%name
      end do
      if (.not. allocated(err)) call write_table(set%temp(set%size() - 1), title // ': failed ' &
         // 'or diverged runs (error not finite); series numbers:' // names, &
         [character(len=16) :: 'series', 'seconds', 'parameter', 'steps', 'status'], &
         [character(len=16) :: '-', 's', '-', '-', '1: failed'], failed_rows(results), err, &
         in_place=.true.)
      if (.not. allocated(err)) call write_text_file(set%temp(set%size()), title &
         // new_line('a') // work_precision_summary(results, reference), err, in_place=.true.)
      call set%finish(err)
   end subroutine write_work_precision

   !> PREFIX.h5 of a work-precision study, under the set's temporary name.
   subroutine work_precision_h5(set, deck_text, results, err, params)
      type(output_set_t), intent(in) :: set                      !! file 1 is the .h5
      character(len=*), intent(in) :: deck_text                  !! deck
      type(series_result_t), intent(in) :: results(:)            !! series
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(parameter_set_t), intent(in), optional :: params      !! /parameters
      type(h5_writer_t) :: h5
      character(len=:), allocatable :: g
      integer :: s
      call h5%create(set%temp(1), err, in_place=.true.);  if (allocated(err)) return
      call study_head(h5, set, 'work_precision', deck_text, err, params)
      if (write_failed(h5, err)) return
      do s = 1, size(results)
         g = '/work_precision/' // results(s)%name
         call h5%write_text(g // '/parameter_name', results(s)%parameter_name, err, &
                            'the setting varied along the series')
         if (write_failed(h5, err)) return
         call h5%write(g // '/parameter', results(s)%parameter, '1', err, 'value of the ' &
            // 'setting at each level (steps per period, a tolerance, or none)')
         if (write_failed(h5, err)) return
         call h5%write(g // '/seconds', results(s)%seconds, 's', err, 'elapsed time of the ' &
            // 'run at each level (best of the repeats)')
         if (write_failed(h5, err)) return
         call h5%write(g // '/error', results(s)%error, '1', err, 'relative error of the ' &
            // 'final state in the energy norm, against the exact integrator')
         if (write_failed(h5, err)) return
         call h5%write(g // '/poincare_error', results(s)%poincare_error, '1', err, 'largest ' &
            // 'error of the recorded Poincare points relative to the strain range')
         if (write_failed(h5, err)) return
         call h5%write(g // '/steps', results(s)%steps, '1', err, 'accepted steps of the run')
         if (write_failed(h5, err)) return
         call h5%write(g // '/output_error', results(s)%output_error, '1', err, 'largest ' &
            // 'relative error of the outputs (root strain, its rate, the tip) over the whole ' &
            // 'history, against the exact integrator')
         if (write_failed(h5, err)) return
         call h5%write(g // '/strain_error', [results(s)%output_errors(1, :)], '1', err, &
                       'relative error of the root strain over the history')
         if (write_failed(h5, err)) return
         call h5%write(g // '/strain_rate_error', [results(s)%output_errors(2, :)], '1', err, &
                       'relative error of the root strain rate over the history')
         if (write_failed(h5, err)) return
         call h5%write(g // '/tip_error', [results(s)%output_errors(3, :)], '1', err, &
                       'relative error of the tip displacement over the history')
         if (write_failed(h5, err)) return
         call h5%write(g // '/status', results(s)%status, '1', err, 'status of each run: 0 ' &
            // 'done, 1 failed (an error, or a diverged run: non-finite error)')
         if (write_failed(h5, err)) return
         call h5%write(g // '/seconds_to_1e-3', cpu_to_reach(results(s), 1.0e-3_dp), 's', err, &
                       'time to reach a relative error of 1e-3 (log-log interpolation); ' &
                       // 'negative: not reached')
         if (write_failed(h5, err)) return
         call h5%write(g // '/seconds_to_1e-6', cpu_to_reach(results(s), 1.0e-6_dp), 's', err, &
                       'time to reach a relative error of 1e-6; negative: not reached')
         if (write_failed(h5, err)) return
         call h5%write(g // '/seconds_to_output_1e-3', cpu_to_reach(results(s), 1.0e-3_dp, &
                       .true.), 's', err, 'time to reach an output error of 1e-3; negative: ' &
                       // 'not reached')
         if (write_failed(h5, err)) return
         call h5%write(g // '/seconds_to_output_1e-6', cpu_to_reach(results(s), 1.0e-6_dp, &
                       .true.), 's', err, 'time to reach an output error of 1e-6; negative: ' &
                       // 'not reached')
         if (write_failed(h5, err)) return
         call h5%write(g // '/seconds_to_output_1e-9', cpu_to_reach(results(s), 1.0e-9_dp, &
                       .true.), 's', err, 'time to reach an output error of 1e-9; negative: ' &
                       // 'not reached')
         if (write_failed(h5, err)) return
      end do
      call h5%close(err)
   end subroutine work_precision_h5

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

   !> Root attributes, /deck, /run/files and /parameters of a study file.
   subroutine study_head(h5, set, analysis, deck_text, err, params)
      type(h5_writer_t), intent(inout) :: h5                     !! writer, file created
      type(output_set_t), intent(in) :: set                      !! the set (for /run/files)
      character(len=*), intent(in) :: analysis                   !! analysis word
      character(len=*), intent(in) :: deck_text                  !! deck
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(parameter_set_t), intent(in), optional :: params      !! /parameters
      call write_file_info(h5, analysis, deck_text, err);  if (allocated(err)) return
      call h5%write_text('/deck', deck_text, err, 'the effective deck text: deck file and ' &
         // 'command-line overrides');  if (allocated(err)) return
      call set%record(h5, err);  if (allocated(err)) return
      if (present(params)) call write_parameter_set(h5, params, err)
   end subroutine study_head

   !> PREFIX.h5, PREFIX.spectral_radius.dat, PREFIX.stability.txt.
   subroutine write_stability(prefix, title, deck_text, methods, omega_dt, rho, steps, &
                              omega_max, err, params)
      character(len=*), intent(in) :: prefix, title, deck_text   !! output, title, deck
      character(len=*), intent(in) :: methods(:)                 !! methods of the chart
      real(dp), intent(in) :: omega_dt(:), rho(:, :)             !! chart
      type(stable_step_t), intent(in) :: steps(:)                !! stable steps
      real(dp), intent(in) :: omega_max                          !! highest mode [rad/s]
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(parameter_set_t), intent(in), optional :: params      !! /parameters
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      character(len=:), allocatable :: text
      character(len=24), allocatable :: names(:), units(:)
      character(len=160) :: line
      integer :: m
      call set%begin(prefix, [character(len=20) :: '.h5', '.spectral_radius.dat', &
                     '.stability.txt'], err)
      if (allocated(err)) return
      call h5%create(set%temp(1), err, in_place=.true.)
      if (.not. allocated(err)) call stability_h5(h5, set, deck_text, methods, omega_dt, rho, &
                                                  steps, omega_max, err, params)
      if (.not. allocated(err)) then
         allocate(names(1 + size(methods)), units(1 + size(methods)))
         names(1) = 'omega_dt';  units(1) = '-'
         names(2:) = methods;  units(2:) = '-'
         call write_table(set%temp(2), title // ': spectral radius of one step, undamped ' &
            // 'test equation', names, units, reshape([omega_dt, reshape(rho, [size(rho)])], &
            [size(omega_dt), 1 + size(methods)]), err, in_place=.true.)
      end if
      if (.not. allocated(err)) then
         text = title // new_line('a') // 'largest stable fixed step, bisection with real runs ' &
            // '(3000 steps of free undamped vibration from a random displacement), ' &
            // 'omega_max = ' // str(omega_max) // ' rad/s' // new_line('a') &
            // '  method                 measured [s]    theory [s]   limit   ratio' &
            // new_line('a')
         do m = 1, size(steps)
            write(line, '(2x, a20, 2es15.6, f8.4, f9.5)') steps(m)%name, steps(m)%measured, &
               steps(m)%theory, steps(m)%limit, steps(m)%measured / steps(m)%theory
            text = text // trim(line) // new_line('a')
         end do
         call write_text_file(set%temp(3), text, err, in_place=.true.)
      end if
      call set%finish(err)
   end subroutine write_stability

   !> The datasets of write_stability.
   subroutine stability_h5(h5, set, deck_text, methods, omega_dt, rho, steps, omega_max, err, &
                           params)
      type(h5_writer_t), intent(inout) :: h5                     !! writer, file created
      type(output_set_t), intent(in) :: set                      !! the set (for /run/files)
      character(len=*), intent(in) :: deck_text                  !! deck
      character(len=*), intent(in) :: methods(:)                 !! methods of the chart
      real(dp), intent(in) :: omega_dt(:), rho(:, :)             !! chart
      type(stable_step_t), intent(in) :: steps(:)                !! stable steps
      real(dp), intent(in) :: omega_max                          !! highest mode [rad/s]
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(parameter_set_t), intent(in), optional :: params      !! /parameters
      integer :: m
      call study_head(h5, set, 'stability', deck_text, err, params)
      if (write_failed(h5, err)) return
      call h5%write('/stability/omega_dt', omega_dt, '1', err, 'omega dt of the spectral ' &
         // 'radius chart');  if (write_failed(h5, err)) return
      call h5%write('/stability/methods', methods, '1', err, 'the methods of the chart')
      if (write_failed(h5, err)) return
      call h5%write('/stability/spectral_radius', rho, '1', err, 'spectral radius ' &
         // 'of one step on the undamped test equation', 'method omega_dt')
      if (write_failed(h5, err)) return
      call h5%write('/stability/omega_max', omega_max, 'rad s-1', err, 'highest natural ' &
         // 'angular frequency of the model');  if (write_failed(h5, err)) return
      call h5%write('/stability/stable_step_measured', [(steps(m)%measured, m = 1, size(steps))], &
                    's', err, 'largest stable fixed step, by bisection with real runs')
      if (write_failed(h5, err)) return
      call h5%write('/stability/stable_step_theory', [(steps(m)%theory, m = 1, size(steps))], &
                    's', err, 'largest stable fixed step from theory (limit / omega_max)')
      if (write_failed(h5, err)) return
      call h5%close(err)
   end subroutine stability_h5

   !> PREFIX.h5, PREFIX.model_size.dat (one row per candidate), PREFIX.model_size.txt.
   subroutine write_model_size(prefix, title, deck_text, cands, best, err, params)
      character(len=*), intent(in) :: prefix, title, deck_text   !! output, title, deck
      type(candidate_t), intent(in) :: cands(:)                  !! the ladder
      integer, intent(in) :: best                                !! recommended (0: none)
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(parameter_set_t), intent(in), optional :: params      !! /parameters
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      character(len=:), allocatable :: text
      character(len=200) :: line
      real(dp), allocatable :: cols(:, :)
      integer :: k, n
      n = size(cands)
      call set%begin(prefix, [character(len=16) :: '.h5', '.model_size.dat', &
                     '.model_size.txt'], err)
      if (allocated(err)) return
      call h5%create(set%temp(1), err, in_place=.true.)
      if (.not. allocated(err)) call model_size_h5(h5, set, deck_text, cands, best, err, params)
      if (allocated(err)) then
         call set%finish(err)
         return
      end if
      allocate(cols(n, 9))
      do k = 1, n
         cols(k, :) = [real(k, dp), real(cands(k)%n_coordinates, dp), cands(k)%seconds, &
            cands(k)%poincare_distance, cands(k)%frequency_error, real(cands(k)%label, dp), &
            cands(k)%lyapunov, cands(k)%peak_force, merge(1.0_dp, 0.0_dp, cands(k)%acceptable)]
      end do
      call write_table(set%temp(2), title // ': model-size ladder (candidate ' &
         // 'numbers as in the .txt report)', [character(len=20) :: 'candidate', &
         'coordinates', 'seconds', 'poincare_distance', 'frequency_error', 'label', 'lyapunov', &
         'peak_force', 'acceptable'], [character(len=20) :: '-', '-', 's', '-', '-', &
         'p|0|-1', '1/s', 'N', '1|0'], cols, err, in_place=.true.)
      if (allocated(err)) then
         call set%finish(err)
         return
      end if
      text = title // new_line('a') // '  #  model                 coords  f-error   label      ' &
         // 'lambda[1/s]  Poincare-dist  peak F [N]   time [s]  ok' // new_line('a')
      do k = 1, n
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
      call write_text_file(set%temp(3), text, err, in_place=.true.)
      call set%finish(err)
   end subroutine write_model_size

   !> The datasets of write_model_size.
   subroutine model_size_h5(h5, set, deck_text, cands, best, err, params)
      type(h5_writer_t), intent(inout) :: h5                     !! writer, file created
      type(output_set_t), intent(in) :: set                      !! the set (for /run/files)
      character(len=*), intent(in) :: deck_text                  !! deck
      type(candidate_t), intent(in) :: cands(:)                  !! the ladder
      integer, intent(in) :: best                                !! recommended (0: none)
      type(error_t), allocatable, intent(out) :: err             !! I/O failure
      type(parameter_set_t), intent(in), optional :: params      !! /parameters
      character(len=24), allocatable :: names(:)
      integer :: k, n
      n = size(cands)
      allocate(names(n))
      do k = 1, n
         names(k) = cands(k)%name
      end do
      call study_head(h5, set, 'model_size', deck_text, err, params)
      if (write_failed(h5, err)) return
      call h5%write('/model_size/name', names, '1', err, 'name of each model of the ladder')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/n_elem', [(cands(k)%n_elem, k = 1, n)], '1', err, &
                    'elements of each model''s mesh')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/n_modes', [(cands(k)%n_modes, k = 1, n)], '1', err, &
                    'modes kept by each modal model; 0: the full finite element model')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/n_coordinates', [(cands(k)%n_coordinates, k = 1, n)], '1', &
                    err, 'coordinates (degrees of freedom) of each model')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/frequency_error', [(cands(k)%frequency_error, k = 1, n)], &
                    '1', err, 'largest relative error of the natural frequencies below the ' &
                    // 'cut-off, against the reference');  if (write_failed(h5, err)) return
      call h5%write('/model_size/period', [(cands(k)%period, k = 1, n)], '1', err, &
                    'detected period in forcing periods; 0: none')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/label', [(cands(k)%label, k = 1, n)], '1', err, &
                    'label code: p >= 1 period p, 0 undecided, -1 chaotic')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/lyapunov', [(cands(k)%lyapunov, k = 1, n)], 's-1', err, &
                    'largest Lyapunov exponent')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/poincare_distance', [(cands(k)%poincare_distance, k = 1, n)], &
                    '1', err, 'modified Hausdorff distance of the Poincare set to the ' &
                    // 'reference''s, relative to its orbit size')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/peak_force', [(cands(k)%peak_force, k = 1, n)], 'N', err, &
                    'largest force of stop 1')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/seconds', [(cands(k)%seconds, k = 1, n)], 's', err, &
                    'elapsed time of each model''s run')
      if (write_failed(h5, err)) return
      call h5%write('/model_size/recommended', best, '1', err, 'index (from 1) of the ' &
         // 'recommended model; 0: none meets every tolerance')
      if (write_failed(h5, err)) return
      call h5%close(err);  if (allocated(err)) return
   end subroutine model_size_h5
end module gapbeam_study_output
