!> The jobs of the gapbeam program, one per analysis: build what the analysis needs from the
!> deck, run it, print a summary and write the result files. The sweep job is in
!> gapbeam_sweep_job.
module gapbeam_jobs
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t, add_warning
   use gapbeam_warning_text, only: warning_length, warning_prefix, untouched_stop_warnings, &
      untouched_evidence
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_description, only: structure_t, beam_ei, beam_rho_a, beam_mass, &
      modal_damping_ratio, dof_w, modal_ratio, beam_is_timoshenko, beam_shear_coefficient, &
      beam_shear_stiffness, n_psd_nodes
   use gapbeam_model, only: system_t, model_t
   use gapbeam_results, only: modes_t, transient_result_t, point_result_t, series_result_t, &
      stable_step_t, candidate_t, label_text
   use gapbeam_assembly, only: assemble
   use gapbeam_eigen, only: solve_modes
   use gapbeam_calibration, only: calibrate_parameter, first_frequency
   use gapbeam_model_builder, only: build_model, resolve_stop_stiffness
   use gapbeam_reduction_rule, only: reduction_info_t, reduction_text
   use gapbeam_reduction_check, only: reduction_check_t, check_reduction, check_lines
   use gapbeam_clock, only: thread_cpu_seconds
   use gapbeam_point, only: label_point
   use gapbeam_settings, only: batch_options_t, output_settings_t
   use gapbeam_progress_meter, only: meter_t
   use gapbeam_parameters, only: forcing_text
   use gapbeam_studies, only: work_precision, stability_study, stability_series
   use gapbeam_capabilities, only: method_caps_t, method_caps
   use gapbeam_model_size, only: model_size_study
   use gapbeam_report, only: write_modes, write_transient, write_calibration
   use gapbeam_deck_rules_flow, only: deck_wear_depth
   use gapbeam_flow_results, only: wear_depth_t, draw_statistics_t, flow_modes_t, response_psd_t
   use gapbeam_flow_load, only: deck_flow_modes
   use gapbeam_draws_job, only: run_draws
   use gapbeam_study_output, only: write_work_precision, write_stability, &
      work_precision_summary, write_model_size
   implicit none
   private
   public :: run_modes, run_calibrate, run_transient_analysis, run_work_precision, &
      run_stability, run_model_size

contains

   subroutine describe_structure(st)
      type(structure_t), intent(in) :: st
      write(output_unit, '(a)') 'beam: L = ' // str(st%beam%length) // ' m, ' &
         // str(st%beam%n_elem) // ' elements, EI = ' // str(beam_ei(st%beam)) &
         // ' N m^2, rho A = ' // str(beam_rho_a(st%beam)) // ' kg/m, mass = ' &
         // str(beam_mass(st%beam)) // ' kg, ' // trim(st%beam%mass_matrix) // ' mass' &
         // rotary_text(st)
      if (beam_is_timoshenko(st%beam)) write(output_unit, '(a)') 'Timoshenko beam: G = ' &
         // str(st%beam%shear_modulus) // ' Pa, k = ' // str(beam_shear_coefficient(st%beam)) &
         // ', k G A = ' // str(beam_shear_stiffness(st%beam)) // ' N, phi = 12 EI/(k G A le^2) = ' &
         // str(12.0_dp * beam_ei(st%beam) / (beam_shear_stiffness(st%beam) &
         * (st%beam%length / real(st%beam%n_elem, dp))**2))
      if (st%root%condition == 'spring') then
         write(output_unit, '(a)') 'root: rotational spring k_theta = ' // str(st%root%k_theta) &
            // ' N m/rad (kappa = k_theta L / EI = ' &
            // str(st%root%k_theta * st%beam%length / beam_ei(st%beam)) // ')'
      else
         write(output_unit, '(a)') 'root: ' // trim(st%root%condition)
      end if
      if (st%tip%condition == 'spring') then
         write(output_unit, '(a)') 'tip: pinned, rotational spring k_theta = ' &
            // str(st%tip%k_theta) // ' N m/rad'
      else if (st%tip%condition /= 'free') then
         write(output_unit, '(a)') 'tip: ' // trim(st%tip%condition)
      end if
      if (st%beam%planes > 1 .or. st%beam%added_mass > 0.0_dp) write(output_unit, '(a)') &
         'planes of motion: ' // str(st%beam%planes) // '; added mass ' &
         // str(st%beam%added_mass) // ' kg/m (mass per length ' &
         // str(beam_rho_a(st%beam) + st%beam%added_mass) // ' kg/m)'
   end subroutine describe_structure

   function rotary_text(st) result(t)
      type(structure_t), intent(in) :: st
      character(len=:), allocatable :: t
      t = ''
      if (st%beam%mass_matrix == 'lumped') t = ' (rotary inertia: ' &
         // trim(st%beam%rotary_inertia) // ')'
   end function rotary_text

   subroutine run_modes(dk, e)
      type(deck_t), intent(in) :: dk
      type(error_t), allocatable, intent(out) :: e
      type(system_t) :: sys
      type(modes_t) :: modes
      real(dp), allocatable :: k_stop(:)
      real(dp) :: f1_open
      integer :: j, n_print
      character(len=120) :: line
      type(flow_modes_t) :: fm
      call describe_structure(dk%structure)
      call assemble(dk%structure, sys)
      call solve_modes(sys, modes, e)
      if (allocated(e)) return
      n_print = modes%n_modes
      if (dk%n_print_modes > 0) n_print = min(n_print, dk%n_print_modes)
      write(output_unit, '(a)') 'dofs: ' // str(sys%n_dof) // ', finite modes: ' &
         // str(modes%n_modes)
      write(output_unit, '(a)') ' mode   frequency [Hz]   f/f1      participation [kg^0.5]' &
         // '   effective mass [%]'
      do j = 1, n_print
         write(line, '(i5, f16.4, f10.4, es22.6, f17.3)') j, modes%frequency_hz(j), &
            modes%frequency_hz(j) / modes%frequency_hz(1), modes%participation(j), &
            100.0_dp * modes%effective_mass(j) / modes%total_mass
         write(output_unit, '(a)') trim(line)
      end do
      if (dk%damping%model == 'modal') then
         write(output_unit, '(a)') 'modal damping: zeta of mode 1 = ' &
            // str(modal_ratio(dk%damping%modal_ratios, 1)) // ' (+ Rayleigh beta = ' &
            // str(dk%damping%mass_coefficient) // ' 1/s, gamma = ' &
            // str(dk%damping%stiffness_coefficient) // ' s); zeta(f1) = ' &
            // str(modal_ratio(dk%damping%modal_ratios, 1) + modal_damping_ratio( &
            dk%damping%mass_coefficient, dk%damping%stiffness_coefficient, modes%frequency_hz(1)))
      else if (dk%damping%model /= 'none') then
         write(output_unit, '(a)') 'Rayleigh damping: beta = ' // str(dk%damping%mass_coefficient) &
            // ' 1/s, gamma = ' // str(dk%damping%stiffness_coefficient) // ' s; zeta(f1) = ' &
            // str(modal_damping_ratio(dk%damping%mass_coefficient, &
            dk%damping%stiffness_coefficient, modes%frequency_hz(1)))
      end if
      call resolve_stop_stiffness(dk%structure, dk%stops, k_stop, f1_open, e)
      if (allocated(e)) return
      do j = 1, size(dk%stops)
         write(output_unit, '(a)') 'stop ' // str(j) // ' at node ' // str(dk%stops(j)%node) &
            // ': stiffness ' // str(k_stop(j)) // ' N/m' // rule_text(dk%stops(j)%rule_factor)
      end do
      if (dk%flow%fluid_elastic == 'connors' .and. dk%flow%fluid_density > 0.0_dp .and. &
          dk%flow%tube_diameter > 0.0_dp) then
         call deck_flow_modes(dk, sys, dk%damping%mass_coefficient, &
                              dk%damping%stiffness_coefficient, fm, e)
         if (allocated(e)) return
         call print_flow_modes(dk, fm, n_print)
         call write_modes(dk, sys, modes, k_stop, e, fm)
      else
         call write_modes(dk, sys, modes, k_stop, e)
      end if
   end subroutine run_modes

   !> The fluid-elastic data of the first n modes of the open structure (Connors).
   subroutine print_flow_modes(dk, fm, n)
      type(deck_t), intent(in) :: dk            !! deck
      type(flow_modes_t), intent(in) :: fm      !! flow modes
      integer, intent(in) :: n                  !! modes printed (at most)
      character(len=120) :: line
      integer :: j
      write(output_unit, '(a)') 'cross flow (Connors, K = ' // str(dk%flow%connors_constant) &
         // ', rho = ' // str(dk%flow%fluid_density) // ' kg/m^3, D = ' &
         // str(dk%flow%tube_diameter) // ' m) at U = ' // str(dk%flow%velocity) // ' m/s:'
      write(output_unit, '(a)') ' mode plane  frequency [Hz]   zeta_s     (U_e/U)^2   ' &
         // 'U_c [m/s]    zeta_fe at U'
      do j = 1, min(n, fm%n_modes)
         write(line, '(i5, a6, f16.4, es11.3, es13.4, es13.5, es14.4)') j, &
            trim(merge('w', 'v', fm%plane(j) == 1)), fm%frequency_hz(j), &
            fm%structural_ratio(j), fm%velocity_ratio(j), &
            min(fm%critical_velocity(j), 9.99e99_dp), fm%fluid_ratio(j)
         write(output_unit, '(a)') trim(line)
      end do
   end subroutine print_flow_modes

   !> The method and the &solver parameters its registry entry says it reads:
   !> 'newmark (delta 0.5, alpha 0.25), stop force condensed'.
   function method_text(dk) result(t)
      type(deck_t), intent(in) :: dk
      character(len=:), allocatable :: t
      type(method_caps_t) :: c
      character(len=:), allocatable :: rest, pair
      integer :: eq, sp, n
      c = method_caps(dk%solver%method)
      t = trim(dk%solver%method)
      rest = trim(adjustl(c%parameters))
      n = 0
      do while (len(rest) > 0)
         sp = index(rest, ' ')
         if (sp == 0) sp = len(rest) + 1
         pair = rest(:sp - 1)
         rest = trim(adjustl(rest(min(sp, len(rest)) + 1:)))
         eq = index(pair, '=')
         n = n + 1
         if (n == 1) then
            t = t // ' ('
         else
            t = t // ', '
         end if
         t = t // pair(:eq - 1) // ' ' // str(solver_value(dk%solver, pair(eq + 1:)))
      end do
      if (n > 0) t = t // ')'
      if (c%fixed_point) t = t // ', stop force ' // trim(dk%solver%stop_solution)
   end function method_text

   !> A numeric &solver variable by name.
   real(dp) function solver_value(cfg, name) result(x)
      type(solver_settings_t), intent(in) :: cfg       !! settings
      character(len=*), intent(in) :: name             !! variable
      select case (name)
      case ('newmark_delta');  x = cfg%newmark_delta
      case ('newmark_alpha');  x = cfg%newmark_alpha
      case ('hht_alpha');  x = cfg%hht_alpha
      case ('rho_infinity');  x = cfg%rho_infinity
      case ('rk_rtol');  x = cfg%rk_rtol
      case ('rk_atol');  x = cfg%rk_atol
      case default
         error stop 'gapbeam_jobs:solver_value: a registry entry names an unknown &solver ' &
            // 'variable'
      end select
   end function solver_value

   function rule_text(factor) result(t)
      real(dp), intent(in) :: factor
      character(len=:), allocatable :: t
      t = ''
      if (factor > 0.0_dp) t = ' (rule: ' // str(factor) // ' x the lowest spring raising f1 ' &
         // 'to the target)'
   end function rule_text

   subroutine run_calibrate(dk, e)
      type(deck_t), intent(in) :: dk
      type(error_t), allocatable, intent(out) :: e
      real(dp) :: value, f1
      type(structure_t) :: st
      type(system_t) :: sys
      character(len=:), allocatable :: units
      call describe_structure(dk%structure)
      call calibrate_parameter(dk%structure, dk%calibrate%parameter, dk%calibrate%index, &
                               dk%calibrate%target_f1_hz, value, e)
      if (allocated(e)) then      ! name the deck variables the calibration starts from
         e%message = "group &calibrate: parameter = '" // trim(dk%calibrate%parameter) &
            // "', target_f1_hz = " // str(dk%calibrate%target_f1_hz) // ', starting from ' &
            // start_text(dk) // ': ' // e%message
         return
      end if
      st = dk%structure
      select case (dk%calibrate%parameter)
      case ('root_k_theta')
         st%root%k_theta = value;  units = 'N m rad-1'
      case ('spring')
         st%springs(dk%calibrate%index)%stiffness = value
         units = trim(merge('N m-1    ', 'N m rad-1', st%springs(dk%calibrate%index)%dof == dof_w))
      case ('thickness')
         st%beam%thickness = value;  units = 'm'
      case ('width')
         st%beam%width = value;  units = 'm'
      end select
      call first_frequency(st, f1, e)
      if (allocated(e)) return
      write(output_unit, '(a)') 'calibrated ' // trim(dk%calibrate%parameter) // ' = ' &
         // str(value) // ' ' // units // ' gives f1 = ' // str(f1) // ' Hz (target ' &
         // str(dk%calibrate%target_f1_hz) // ' Hz)'
      call assemble(st, sys)
      call write_calibration(dk, sys, value, units, f1, e)
   end subroutine run_calibrate

   !> The deck variable a calibration starts from, with its value ('&beam width = 0.01').
   function start_text(dk) result(t)
      type(deck_t), intent(in) :: dk                   !! the deck
      character(len=:), allocatable :: t
      select case (dk%calibrate%parameter)
      case ('root_k_theta')
         t = '&root k_theta = ' // str(dk%structure%root%k_theta)
      case ('spring')
         t = '&springs stiffness(' // str(dk%calibrate%index) // ') = ' &
            // str(dk%structure%springs(dk%calibrate%index)%stiffness)
      case ('thickness')
         t = '&beam thickness = ' // str(dk%structure%beam%thickness)
      case ('width')
         t = '&beam width = ' // str(dk%structure%beam%width)
      case default
         t = 'the deck'
      end select
   end function start_text

   subroutine run_work_precision(dk, e)
      type(deck_t), intent(in) :: dk
      type(error_t), allocatable, intent(out) :: e
      type(model_t) :: model
      type(series_result_t), allocatable :: results(:)
      real(dp), allocatable :: u0(:), v0(:)
      character(len=:), allocatable :: ref
      call describe_structure(dk%structure)
      call build_model(dk, model, u0, v0, e)
      if (allocated(e)) return
      write(output_unit, '(a)') 'work-precision: ' // str(size(dk%study%series)) // ' series x ' &
         // str(dk%study%levels) // ' levels, ' // str(dk%study%periods) // ' forcing periods ' &
         // 'from the initial state; reference: the exact integrator'
      call work_precision(model, dk%solver, dk%output, u0, v0, dk%study, results, e)
      if (allocated(e)) return
      ! ratios to the default method when it is charted, else to the first series
      ref = trim(dk%study%series(1))
      if (any(dk%study%series == 'auto')) ref = 'auto'
      write(output_unit, '(a)') work_precision_summary(results, ref)
      call write_work_precision(dk, model, results, ref, e)
   end subroutine run_work_precision

   subroutine run_stability(dk, e)
      type(deck_t), intent(in) :: dk
      type(error_t), allocatable, intent(out) :: e
      type(model_t) :: model
      type(stable_step_t), allocatable :: steps(:)
      real(dp), allocatable :: omega_dt(:), rho(:, :), u0(:), v0(:)
      character(len=32), allocatable :: methods(:)
      integer :: k
      call describe_structure(dk%structure)
      call build_model(dk, model, u0, v0, e)
      if (allocated(e)) return
      call stability_series(dk%study%series, methods, e)
      if (allocated(e)) return
      call stability_study(model, dk%study, methods, omega_dt, rho, steps, e)
      if (allocated(e)) return
      do k = 1, size(steps)
         write(output_unit, '(a)') 'largest stable step, ' // steps(k)%name // ': ' &
            // str(steps(k)%measured) // ' s measured, ' // str(steps(k)%theory) &
            // ' s theory (' // str(steps(k)%limit) // '/omega_max), ratio ' &
            // str(steps(k)%measured / steps(k)%theory)
      end do
      call write_stability(dk, model, methods, omega_dt, rho, steps, e)
   end subroutine run_stability

   subroutine run_model_size(dk, e)
      type(deck_t), intent(in) :: dk
      type(error_t), allocatable, intent(out) :: e
      type(candidate_t), allocatable :: cands(:)
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:)
      integer :: best, k
      call describe_structure(dk%structure)
      call build_model(dk, model, u0, v0, e)          ! the deck's model, for the file
      if (allocated(e)) return
      write(output_unit, '(a)') 'model size: ' // str(size(dk%model_size%elements)) &
         // ' meshes and ' // str(2 * size(dk%model_size%modes)) // ' modal models against ' &
         // 'the ' // str(maxval(dk%model_size%elements)) // '-element model'
      call model_size_study(dk, dk%model_size, cands, best, e)
      if (allocated(e)) return
      do k = 1, size(cands)
         if (cands(k)%status /= 0) then
            write(output_unit, '(a)') '  ' // cands(k)%name // ': failed: ' // cands(k)%message
         else
            write(output_unit, '(a)') '  ' // cands(k)%name // ': ' &
               // str(cands(k)%n_coordinates) // ' coordinates, f-error ' &
               // str(cands(k)%frequency_error) // ', ' // label_text(cands(k)%label) &
               // ', lambda ' // str(cands(k)%lyapunov) // ' 1/s, Poincare distance ' &
               // str(cands(k)%poincare_distance) // ', peak force ' &
               // str(cands(k)%peak_force) // ' N, ' // str(cands(k)%seconds) // ' s' &
               // trim(merge(' ok', '   ', cands(k)%acceptable))
         end if
      end do
      if (best > 0) then
         write(output_unit, '(a)') 'recommended: ' // cands(best)%name
      else
         write(output_unit, '(a)') 'recommended: none meets every tolerance'
      end if
      call write_model_size(dk, model, cands, best, e)
   end subroutine run_model_size

   !> The stops a transient run never touched in its record: a warning each (on standard
   !> error, and in the deck copy `dw` whose warnings the file stores) and the label's
   !> certificate reason saying that its label is that of the beam without them.
   subroutine untouched_stops(dk, res, diag, dw)
      type(deck_t), intent(in) :: dk                   !! deck
      type(transient_result_t), intent(in) :: res      !! the run
      type(point_result_t), intent(inout) :: diag      !! its label: reason extended
      type(deck_t), intent(out) :: dw                  !! dk with the warnings added
      character(len=warning_length), allocatable :: lines(:)
      integer :: k
      dw = dk
      if (.not. allocated(res%n_impacts) .or. .not. allocated(res%contact_fraction)) return
      lines = untouched_stop_warnings(res%n_impacts, res%contact_fraction, &
                                      dk%solver%record_periods)
      do k = 1, size(lines)
         call add_warning(dw, trim(lines(k)))
         write(error_unit, '(a)') warning_prefix // trim(lines(k))
      end do
      if (size(lines) > 0 .and. allocated(diag%certificate_reason)) diag%certificate_reason = &
         diag%certificate_reason // untouched_evidence(res%n_impacts, res%contact_fraction)
   end subroutine untouched_stops

   !> The label of a transient run, its evidence and its certificate, on standard output.
   subroutine print_label(diag)
      type(point_result_t), intent(in) :: diag         !! diagnosed run
      integer :: k
      character(len=:), allocatable :: lambda, found
      ! 'period 3 found' or 'no period found', up to the largest period tried
      found = 'no period found'
      if (diag%period > 0) found = 'period ' // str(diag%period) // ' found'
      ! no exponent asked for (lyapunov_periods = 0; the default with ring supports): say so
      if (diag%lyapunov_periods == 0) then
         write(output_unit, '(a)') 'attractor: ' // label_text(diag%label) // ' (' // found &
            // ' up to ' // str(diag%period_max_tested) // '; no ' &
            // 'Lyapunov exponent: lyapunov_periods = 0)'
         lambda = 'no exponent'
      else
         write(output_unit, '(a)') 'attractor: ' // label_text(diag%label) // ' (' // found &
            // ' up to ' // str(diag%period_max_tested) &
            // '; largest Lyapunov exponent ' // str(diag%lyapunov) // ' +- ' &
            // str(diag%lyapunov_error) // ' 1/s over ' // str(diag%lyapunov_periods) &
            // ' periods)'
         lambda = 'lambda ' // trim(merge('met its target     ', 'stopped at its most', &
            diag%lyapunov_converged == 1)) // ' (' // str(diag%lyapunov_periods) // ' periods)'
         if (diag%lyapunov_starts > 1) lambda = lambda // ' from ' &
            // str(diag%lyapunov_starts) // ' independent starts (their spread: sigma ' &
            // str(diag%lyapunov_spread) // ' 1/s)'
         if (diag%lyapunov_rerun + diag%lyapunov_dropped > 0) lambda = lambda // ', ' &
            // str(diag%lyapunov_rerun) // ' periods rerun and ' // str(diag%lyapunov_dropped) &
            // ' dropped (the pair''s step sequences differed)'
      end if
      write(output_unit, '(a)') 'evidence: periods 1..' // str(diag%period_max_tested) &
         // ' tried at tolerance ' // str(diag%period_tolerance) // ' (closest: period ' &
         // str(diag%closest_period) // ' at ' // str(diag%repeat_distance) // '); ' &
         // str(diag%settle_windows) // ' windows differ by ' // str(diag%window_difference) &
         // ' of the orbit size (' // trim(merge('settled    ', 'not settled', &
         diag%settled == 1)) // ') after ' // str(diag%transient_periods) // ' transient ' &
         // 'periods; ' // lambda // untouched_tail(diag)
      write(output_unit, '(a)') 'certificate: ' // cert_reason(diag)
      if (allocated(diag%start_label)) then
         if (size(diag%start_label) > 1) then
            write(output_unit, '(a)') 'attractors: ' // str(diag%n_attractors) // ' found by ' &
               // str(size(diag%start_label)) // ' starts'
            do k = 1, diag%n_attractors
               write(output_unit, '(a)') '  ' // str(k) // ': ' &
                  // label_text(diag%attractor_label(k)) // ', lambda ' &
                  // str(diag%attractor_lyapunov(k)) // ' 1/s, reached by ' &
                  // str(nint(100.0_dp * diag%attractor_fraction(k))) // ' % of the starts'
            end do
         end if
      end if
   end subroutine print_label

   !> The label's evidence about stops never met in its record ('' when all were met).
   function untouched_tail(diag) result(t)
      type(point_result_t), intent(in) :: diag         !! diagnosed run
      character(len=:), allocatable :: t
      t = ''
      if (allocated(diag%n_impacts) .and. allocated(diag%contact_fraction)) &
         t = untouched_evidence(diag%n_impacts, diag%contact_fraction)
   end function untouched_tail

   !> The certificate's reason, or why there is none.
   function cert_reason(diag) result(t)
      type(point_result_t), intent(in) :: diag         !! diagnosed run
      character(len=:), allocatable :: t
      t = 'none: certification is off (&diagnostics certify = .false.)'
      if (allocated(diag%certificate_reason)) t = diag%certificate_reason
   end function cert_reason

   !> A transient run, its attractor, its files. Progress lines (`batch`: --quiet, --progress)
   !> count the forcing periods integrated: the run's, then the exponent's two trajectories.
   subroutine run_transient_analysis(dk, e, batch)
      type(deck_t), intent(in) :: dk
      type(error_t), allocatable, intent(out) :: e
      type(batch_options_t), intent(in), optional :: batch   !! progress options
      type(batch_options_t) :: opt
      type(meter_t) :: meter
      real(dp) :: n_run
      type(model_t) :: model
      type(transient_result_t) :: res
      type(point_result_t) :: diag
      character(len=:), allocatable :: failures(:)
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: setup
      integer :: j
      type(draw_statistics_t), allocatable :: stats(:)
      type(response_psd_t) :: psd
      type(output_settings_t) :: out
      type(reduction_info_t) :: reduced
      type(reduction_check_t) :: check
      type(deck_t) :: dw
      call describe_structure(dk%structure)
      setup = thread_cpu_seconds()
      call build_model(dk, model, u0, v0, e, reduced)
      if (allocated(e)) return
      setup = thread_cpu_seconds() - setup
      if (dk%reduction%kind /= 'none') write(output_unit, '(a)') &
         reduction_text(reduced, dk%solver%tolerance)
      write(output_unit, '(a)') 'forcing: ' // forcing_text(dk) // '; f1 (stops open) = ' &
         // str(model%f1_open_hz) // ' Hz; highest mode ' &
         // str(model%omega_max / (2.0_dp * pi)) &
         // ' Hz'
      do j = 1, model%n_stops
         write(output_unit, '(a)') 'stop ' // str(j) // ': stiffness ' &
            // str(model%stop_stiffness(j)) // ' N/m, gap ' // str(dk%stops(j)%gap) // ' m'
      end do
      write(output_unit, '(a)') 'solver: ' // method_text(dk) // ', step control ' &
         // trim(dk%solver%step_control) // ', T/' // str(dk%solver%steps_per_period) &
         // ', events ' // merge('located', 'ignored', dk%solver%locate_events)
      if (present(batch)) opt = batch
      n_run = real(dk%solver%transient_periods, dp) + real(dk%solver%record_periods, dp)
      call meter%start('transient', 'periods', &
         n_run + 2.0_dp * real(dk%diagnostics%lyapunov_periods, dp), 0.0_dp, &
         .not. opt%quiet, opt%progress_interval_s)
      ! the point pipeline: every start labelled, the first certified, attractors grouped
      out = dk%output   ! the response PSD needs every dof at the history samples
      if (n_psd_nodes(dk%turbulence) > 0) out%state_history = .true.
      call label_point(model, dk%solver, out, dk%diagnostics, u0, v0, 1, res, diag, e, &
                       failures, meter)
      ! settling, convergence and an adaptive exponent may have run more than the estimate
      meter%total = max(meter%total, meter%done)
      call meter%finish(meter%done)
      if (allocated(e)) return
      write(output_unit, '(a)') 'steps: ' // str(int(res%steps_accepted)) // ' accepted, ' &
         // str(int(res%steps_rejected)) // ' rejected, ' // str(int(res%events)) &
         // ' split at contact events; dt from ' // str(res%dt_smallest) // ' to ' &
         // str(res%dt_largest) // ' s; ' // str(int(res%factorizations)) // ' factorizations' &
         // ' (the last record)'
      if (dk%solver%stop_solution == 'fixed_point') write(output_unit, '(a)') &
         'fixed-point iterations: ' // str(int(res%fp_iterations))
      write(output_unit, '(a)') 'method: ' // res%method // ' (' // res%method_reason // ')'
      res%setup_seconds = setup
      write(output_unit, '(a)') 'cpu: ' // str(res%cpu_seconds) // ' s, wall ' &
         // str(res%wall_seconds) // ' s for the last record (set-up: ' // str(setup) &
         // ' s cpu); ' // str(diag%seconds_label) // ' s cpu for the label'
      do j = 1, model%n_stops
         write(output_unit, '(a)') 'stop ' // str(j) // ': ' // str(res%n_impacts(j)) &
            // ' impacts in ' // str(dk%solver%record_periods) // ' periods, peak force ' &
            // str(res%peak_force(j)) // ' N, rms ' // str(res%rms_force(j)) // ' N, contact ' &
            // str(100.0_dp * res%contact_fraction(j)) // ' % of the time, impulse/period ' &
            // str(res%impulse_per_period(j)) // ' N s, work rate ' // str(res%work_rate(j)) // ' W'
         if (model%sys%planes > 1) write(output_unit, '(a)') '        wear: normal work rate ' &
            // str(res%normal_work_rate(j)) // ' W, sliding ' // str(res%sliding_distance(j)) &
            // ' m in ' // str(dk%solver%record_periods) // ' periods, friction work rate ' &
            // str(res%friction_work_rate(j)) // ' W, stick ' &
            // str(100.0_dp * res%stick_fraction(j)) // ' % of the contact time, wear volume ' &
            // 'rate ' // str(res%wear_volume_rate(j)) // ' m^3/s'
         if (dk%wear%years > 0.0_dp) call print_wear_depth(dk, res%wear_volume_rate, j)
      end do
      if (res%has_energy) write(output_unit, '(a)') 'energy over the record: input ' &
         // str(res%input_work) // ' J = Rayleigh ' // str(res%rayleigh_dissipation) &
         // ' J + contact dampers ' // str(res%contact_damping_dissipation) // ' J + friction ' &
         // str(res%friction_dissipation) // ' J + stored ' // str(res%stored_energy_change) &
         // ' J; imbalance ' // str(res%input_work - res%rayleigh_dissipation &
         - res%contact_damping_dissipation - res%friction_dissipation &
         - res%stored_energy_change) // ' J'
      if (dk%reduction%kind == 'auto' .and. dk%reduction%convergence_check) then
         call check_reduction(dk, reduced, model, res, diag%transient_periods, check, e)
         if (allocated(e)) return
         write(output_unit, '(a)') check_lines(check, diag%period > 0)
      end if
      do j = 1, size(failures)
         write(output_unit, '(a)') trim(failures(j))
      end do
      call untouched_stops(dk, res, diag, dw)
      if (allocated(meter%warning)) call add_warning(dw, meter%warning)
      call print_label(diag)
      if (dk%turbulence%spectrum /= 'none' .and. n_psd_nodes(dk%turbulence) > 0) then
         call run_draws(dk, u0, v0, out, res, stats, e, psd)
         if (allocated(e)) return
         if (.not. dk%output%state_history) deallocate(res%history_u)
         call print_draws(stats)
         call write_transient(dw, model, res, diag, e, stats, psd)
      else if (dk%turbulence%spectrum /= 'none') then
         call run_draws(dk, u0, v0, out, res, stats, e)
         if (allocated(e)) return
         call print_draws(stats)
         call write_transient(dw, model, res, diag, e, stats)
      else
         call write_transient(dw, model, res, diag, e)
      end if
      if (allocated(e)) return
      block
         character(len=:), allocatable :: files
         files = trim(dk%job%output) // '.h5'
         if (dk%output%write_text) files = files // ', .history.dat, .poincare.dat'
         if (dk%output%write_text .and. model%sys%planes > 1) files = files // ', .orbit.dat, ' &
            // '.supports.dat'
         if (dk%output%state_history) files = files // ', .xdmf'
         if (dk%output%state_history .and. dk%output%write_text) files = files // ', .shape.dat'
         write(output_unit, '(a)') 'files: ' // files
      end block
   end subroutine run_transient_analysis

   !> The wear depth of stop j after &wear years and the time to &wear wall_fraction.
   subroutine print_wear_depth(dk, volume_rate, j)
      type(deck_t), intent(in) :: dk            !! the deck (&wear years > 0)
      real(dp), intent(in) :: volume_rate(:)    !! per stop [m^3/s]
      integer, intent(in) :: j                  !! the stop
      type(wear_depth_t) :: wd
      character(len=:), allocatable :: when
      wd = deck_wear_depth(dk, volume_rate)
      when = 'never'
      if (wd%years_to_fraction(j) < huge(1.0_dp)) when = str(wd%years_to_fraction(j)) // ' years'
      write(output_unit, '(a)') '        wear depth (' // trim(dk%stops(j)%support) // '): ' &
         // str(wd%depth(size(wd%depth, 1), j)) // ' m after ' // str(dk%wear%years) &
         // ' years; ' // str(100.0_dp * dk%wear%wall_fraction) // ' % of the wall ' &
         // str(dk%wear%wall_thickness) // ' m in ' // when
   end subroutine print_wear_depth

   !> Each output over the draws: its mean and the half-width of its 95 % interval per stop.
   subroutine print_draws(stats)
      type(draw_statistics_t), intent(in) :: stats(:)   !! over the draws
      integer :: k, j
      character(len=:), allocatable :: line
      write(output_unit, '(a)') 'statistics over ' // str(stats(1)%n_draws) // ' draws ' &
         // '(mean +- 95 % half-width; per stop):'
      do k = 1, size(stats)
         line = '  ' // stats(k)%name // ':'
         do j = 1, size(stats(k)%mean)
            line = line // ' ' // str(stats(k)%mean(j)) // ' +- ' // str(stats(k)%half_width(j))
         end do
         write(output_unit, '(a)') line
      end do
   end subroutine print_draws
end module gapbeam_jobs
