!> The deck table's settings groups: how to solve, what to record, how to classify, what to
!> sweep, study and continue (see gapbeam_deck_table).
submodule (gapbeam_deck_table) gapbeam_deck_table_settings
   use gapbeam_description, only: beam_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t, initial_state_t, &
      initial_value_t, diagnostics_settings_t, reduction_settings_t, model_size_settings_t, &
      sweep_settings_t, study_settings_t, stop_solution_words, step_control_words, &
      wear_settings_t, &
      linear_solver_words, method_words, initial_state_words, sweep_mode_words, &
      sweep_direction_words, sweep_axis_words, series_words, start_words, default_series, &
      default_elements, default_modes
   use gapbeam_continuation_types, only: continuation_settings_t, &
      continuation_direction_words, continuation_start_words, jacobian_words, curve_kind_words
   implicit none

contains

   module subroutine walk_settings(v, deck)
      class(deck_visitor_t), intent(inout) :: v
      type(deck_t), intent(inout) :: deck
      call walk_solver(v, deck%solver)
      call walk_initial(v, deck%initial, deck%structure%beam%n_elem)
      call walk_output(v, deck%output)
      call walk_diagnostics(v, deck%diagnostics)
      call walk_sweep(v, deck%sweep)
      call v%begin_group('reduction', 'integrate a modal model instead of the finite ' &
         // 'element model')
      call v%word('kind', deck%reduction%kind, "'none', 'modal', 'auto'", meaning="'modal': " &
         // 'the model projected on the lowest modes of the open structure (in each plane) ' &
         // "and the static modes of the supports; 'auto': the same with the cut-off of the " &
         // 'basis rule (docs/methods.md), printed with a convergence check')
      call v%int('n_modes', deck%reduction%n_modes, lo=1, hi=100000, note='at most the ' &
         // 'modes with mass', meaning="modes kept in each plane (kind = 'modal', cutoff_hz = 0)")
      call v%real('cutoff_hz', deck%reduction%cutoff_hz, 'Hz', lo=1.0e-3_dp, &
         hi=max_frequency_hz, zero=.true., meaning="kind = 'modal': keep the modes up to " &
         // 'this frequency in each plane (at least one); 0: n_modes instead')
      call v%logical('static_correction', deck%reduction%static_correction, &
         meaning='add the residual flexibility of each support dof (both directions of a ' &
         // 'ring) and point-force dof: exact static contact flexibility with few modes')
      call v%logical('convergence_check', deck%reduction%convergence_check, &
         meaning="kind = 'auto', transient runs: also run the model with 1.5 x the cut-off " &
         // 'and print the work rates of both and their difference')
      call v%end_group()
      call walk_study(v, deck%study)
      call walk_model_size(v, deck%model_size)
      call walk_continuation(v, deck%continuation)
      call walk_wear(v, deck%wear)
   end subroutine walk_settings

   subroutine walk_wear(v, w)
      class(deck_visitor_t), intent(inout) :: v
      type(wear_settings_t), intent(inout) :: w
      call v%begin_group('wear', 'wear depth in the tube wall over years, from the Archard ' &
         // 'volume rate and the support geometry of &stops (docs/flow.md)')
      call v%real('years', w%years, 'year', lo=0.0_dp, hi=1.0e4_dp, design=.true., &
         meaning='operating time (Julian years; 0: no depth)')
      call v%real('wall_thickness', w%wall_thickness, 'm', lo=0.0_dp, hi=1.0e3_dp, &
         positive=w%years > 0.0_dp, note='> 0 with years > 0', &
         meaning='tube wall thickness')
      call v%real('tube_diameter', w%tube_diameter, 'm', lo=0.0_dp, hi=1.0e3_dp, &
         meaning="tube outer diameter (0: &flow's)")
      call v%real('wall_fraction', w%wall_fraction, '1', lo=0.0_dp, lo_open=.true., &
         hi=1.0_dp, meaning='the time to wear this fraction of the wall is reported')
      call v%int('depth_points', w%depth_points, lo=2, hi=100000, &
         meaning='times of the depth history, 0 to years')
      call v%end_group()
   end subroutine walk_wear

   subroutine walk_solver(v, s)
      class(deck_visitor_t), intent(inout) :: v
      type(solver_settings_t), intent(inout) :: s
      call v%begin_group('solver', 'time integration')
      call v%word('method', s%method, method_words, meaning="integrator; 'auto': the exact " &
         // "integrator for piecewise-linear stops, else on a reduced model with such laws " &
         // "'exponential' (tolerance at most 1e-4), else 'newmark' with error control " &
         // '(docs/methods.md)')
      call v%real('tolerance', s%tolerance, '1', lo=1.0e-12_dp, hi=0.5_dp, meaning='accuracy ' &
         // 'asked of every error-controlled method (local error per period, relative)', &
         note="with method = 'rk45' and no tolerance, rk_rtol stands in for it")
      call v%real('newmark_delta', s%newmark_delta, '1', lo=0.5_dp, hi=1.0_dp, &
         meaning='Newmark delta (gamma in other texts)')
      call v%real('newmark_alpha', s%newmark_alpha, '1', lo=1.0e-3_dp, hi=1.0_dp, &
         meaning='Newmark alpha (beta in other texts)')
      call v%real('hht_alpha', s%hht_alpha, '1', lo=-1.0_dp / 3.0_dp, hi=0.0_dp, &
         meaning="HHT alpha (method = 'hht')")
      call v%real('rho_infinity', s%rho_infinity, '1', lo=0.0_dp, hi=1.0_dp, meaning='spectral ' &
         // "radius at infinite omega dt (method = 'generalized_alpha')")
      call v%real('rk_rtol', s%rk_rtol, '1', lo=1.0e-14_dp, hi=1.0_dp, &
         meaning="relative tolerance of method = 'rk45'")
      call v%real('rk_atol', s%rk_atol, 'm', lo=0.0_dp, hi=1.0_dp, &
         meaning="absolute tolerance of method = 'rk45' (m, m/s)")
      call v%real('energy_bound', s%energy_bound, '1', lo=1.0_dp, hi=1.0e300_dp, &
         meaning='divergence: energy above this many times its largest value in the first period')
      call v%word('stop_solution', s%stop_solution, stop_solution_words, &
         note="'fixed_point' with method = 'newmark' only", meaning='exact condensed ' &
         // "stop-force solution, or the paper's fixed-point iteration")
      call v%real('fp_tolerance', s%fp_tolerance, '1', lo=1.0e-15_dp, hi=0.1_dp, &
         meaning='fixed point: converged when the change of F is below this x max F')
      call v%int('fp_max_iterations', s%fp_max_iterations, lo=1, hi=100000, &
         meaning='fixed point: iterations before the step is halved')
      call v%word('step_control', s%step_control, step_control_words, note="'half_step' " &
         // "with 'newmark'; 'central_difference', 'rk4': 'fixed'; 'rk45': 'error', 'embedded'", &
         meaning="'auto', local error against tolerance, fixed steps, the paper's " &
         // 'half-step residual, or the embedded estimate of rk45')
      call v%int('steps_per_period', s%steps_per_period, lo=4, hi=100000000, &
         meaning='largest step T/steps_per_period (the step with fixed steps)')
      call v%real('half_step_tolerance', s%half_step_tolerance, '1', lo=1.0e-8_dp, &
         hi=10.0_dp, meaning='half-step residual allowed / the largest force term per dof')
      call v%real('residual_floor', s%residual_floor, '1', lo=0.0_dp, hi=1.0_dp, &
         meaning='floor of the per-dof force scale / the largest scale')
      call v%int('max_halvings', s%max_halvings, lo=0, hi=40, &
         meaning='smallest step = largest / 2^max_halvings')
      call v%int('grow_after', s%grow_after, lo=1, hi=100000, &
         meaning='comfortable steps in a row before the step doubles')
      call v%real('grow_ratio', s%grow_ratio, '1', lo=0.0_dp, hi=1.0_dp, &
         meaning='a step is comfortable when its half-step ratio is below this')
      call v%logical('locate_events', s%locate_events, &
         meaning='split steps at contact onset and release')
      call v%word('linear_solver', s%linear_solver, linear_solver_words, meaning="effective " &
         // "stiffness factorisation; 'auto': dense up to 60 dofs, banded above")
      call v%int('transient_periods', s%transient_periods, lo=0, hi=max_periods, &
         unit='periods', meaning='forcing periods integrated and discarded before the record')
      call v%int('record_periods', s%record_periods, lo=1, hi=max_periods, unit='periods', &
         why='every recorded period keeps its Poincare point', &
         meaning='forcing periods recorded (Poincare points and statistics)')
      call v%end_group()
   end subroutine walk_solver

   subroutine walk_initial(v, ini, n_elem)
      class(deck_visitor_t), intent(inout) :: v
      type(initial_state_t), intent(inout) :: ini
      integer, intent(in) :: n_elem          !! elements of the mesh (node range)
      type(initial_value_t) :: proto
      integer :: n, i, m
      call v%begin_group('initial', 'initial state relative to the base (list)', .true.)
      call v%word('kind', ini%kind, initial_state_words, meaning="'rest': u = u' = 0 " &
         // "relative to the base; 'given': the listed values, zero elsewhere; 'rotation': " &
         // "a rigid rotation about the root; 'translation': a rigid translational velocity; " &
         // "'file': the final state of an earlier transient run (initial_file)")
      call v%real('angular_velocity', ini%angular_velocity, 'rad/s', lo=-big, hi=big, &
         note="kind = 'rotation'", meaning='rigid rotation rate about the root in the w ' &
         // "plane: w' = Omega x, theta' = Omega at every free dof")
      call v%real('angular_velocity_v', ini%angular_velocity_v, 'rad/s', lo=-big, hi=big, &
         note="kind = 'rotation', planes = 2", meaning="the same in the v plane: v' = " &
         // "Omega_v x, theta_v' = Omega_v")
      call v%real('angle', ini%angle, 'rad', lo=-big, hi=big, note="kind = 'rotation'; " &
         // 'not with a clamped root or a supported tip (it would move a fixed dof)', &
         meaning='rigid rotation angle about the root in the w plane: w = angle x, theta = ' &
         // 'angle (small rotations)')
      call v%real('angle_v', ini%angle_v, 'rad', lo=-big, hi=big, note="kind = 'rotation', " &
         // 'planes = 2; as angle', meaning='the same in the v plane')
      call v%real('translation_velocity', ini%translation_velocity, 'm/s', lo=-big, hi=big, &
         note="kind = 'translation'", meaning="rigid translational velocity in w: w' = V, " &
         // "theta' = 0 at every free dof (the supports hold their own dofs)")
      call v%real('translation_velocity_v', ini%translation_velocity_v, 'm/s', lo=-big, &
         hi=big, note="kind = 'translation', planes = 2", meaning="the same in v: v' = V_v")
      call v%text('initial_file', ini%initial_file, note="kind = 'file'; a transient run's " &
         // 'file of the same structure, full model', meaning='HDF5 file of an earlier ' &
         // 'transient run whose final state (/final/u, /final/v at /final/time) starts this ' &
         // 'one; relative to the working directory')
      m = 0
      if (allocated(ini%node)) m = size(ini%node)
      n = v%entries(m, max_initial_entries)
      if (n < 0) then
         call v%at(1)
         call entry(v, n_elem, proto%node, proto%dof, proto%displacement, proto%velocity)
      else
         if (.not. allocated(ini%node) .or. n /= m) then
            call resize_int(ini%node, n, proto%node)
            call resize_int(ini%dof, n, proto%dof)
            call resize_real(ini%displacement, n, proto%displacement)
            call resize_real(ini%velocity, n, proto%velocity)
         end if
         do i = 1, n
            call v%at(i)
            call entry(v, n_elem, ini%node(i), ini%dof(i), ini%displacement(i), ini%velocity(i))
         end do
      end if
      call v%end_group()
   contains
      subroutine entry(v, n_elem, node, dof, u, du)
         class(deck_visitor_t), intent(inout) :: v
         integer, intent(in) :: n_elem
         integer, intent(inout) :: node, dof
         real(dp), intent(inout) :: u, du
         call v%int('node', node, lo=node_lo(v), hi=node_hi(v, n_elem), why=mesh(n_elem), &
            required=.true., note='1..n_elem+1, a free dof; ' &
            // 'each (node, dof) once', meaning='node of a given value')
         call v%code('dof', dof, dof_words, note="'v', 'theta_v' with planes = 2", &
            meaning='degree of freedom')
         call v%real('displacement', u, 'm', lo=-big, hi=big, meaning='initial displacement ' &
            // 'relative to the base (rad on a rotation)')
         call v%real('velocity', du, 'm/s', lo=-big, hi=big, meaning='initial velocity ' &
            // 'relative to the base (rad/s on a rotation)')
      end subroutine entry
   end subroutine walk_initial

   subroutine walk_output(v, o)
      class(deck_visitor_t), intent(inout) :: v
      type(output_settings_t), intent(inout) :: o
      call v%begin_group('output', 'what a transient run (or a sweep point) records')
      call v%real('poincare_phase_deg', o%poincare_phase_deg, 'deg', lo=0.0_dp, hi=360.0_dp, &
         meaning='forcing phase of the Poincare section (0: the base at mid-stroke moving ' &
         // 'towards +w)')
      call v%int('samples_per_period', o%samples_per_period, lo=1, hi=100000, &
         meaning='history samples per forcing period')
      call v%int('history_periods', o%history_periods, lo=0, unit='periods', &
         note='with samples_per_period at most 5e8 samples', meaning='forcing periods of ' &
         // 'history kept from the start of the record (at most record_periods)')
      call v%logical('write_text', o%write_text, meaning='also write the gnuplot-ready .dat ' &
         // 'tables')
      call v%real('filter_cutoff_hz', o%filter_cutoff_hz, 'Hz', lo=0.0_dp, meaning='low-pass ' &
         // 'Butterworth filter of the root strain before Poincare sampling (0: off)')
      call v%int('filter_order', o%filter_order, lo=1, hi=12, meaning='Butterworth order')
      call v%int('filter_samples_per_period', o%filter_samples_per_period, lo=16, hi=1000000, &
         note='a multiple of samples_per_period', meaning='filter sampling rate / forcing ' &
         // 'frequency')
      call v%logical('state_history', o%state_history, note="needs &reduction kind = 'none'", &
         meaning='also keep every dof and the deflected shape at the history samples ' &
         // '(PREFIX.xdmf for ParaView)')
      call v%int('shape_points', o%shape_points, lo=1, hi=1000, meaning='points per element ' &
         // 'of the deflected shape (the nodes among them)')
      call v%logical('energy_balance', o%energy_balance, meaning='also the energy balance of ' &
         // 'the record (/energy)')
      call v%end_group()
   end subroutine walk_output

   subroutine walk_diagnostics(v, d)
      class(deck_visitor_t), intent(inout) :: v
      type(diagnostics_settings_t), intent(inout) :: d
      character(len=len(d%starts)), allocatable :: starts(:)
      integer :: n
      call v%begin_group('diagnostics', 'settling, period, Lyapunov exponent, label, ' &
         // 'certificate, starts (docs/labels.md)')
      call v%int('period_max', d%period_max, lo=1, hi=1000, unit='periods', &
         meaning='largest period tried')
      call v%real('period_tolerance', d%period_tolerance, '1', lo=1.0e-12_dp, hi=0.5_dp, &
         zero=.true., meaning='repeat distance / orbit size accepted as periodic (0: from the ' &
         // 'accuracy of the method)')
      call v%int('period_points', d%period_points, lo=1, hi=max_periods, &
         meaning='last Poincare points tested')
      call v%int('lyapunov_periods', d%lyapunov_periods, lo=0, hi=max_periods, &
         unit='periods', why='every period keeps its running estimate', note='0 with ring ' &
         // 'supports (their default)', meaning='first periods averaged for the exponent ' &
         // '(0: no exponent, no label chaotic)')
      call v%int('lyapunov_max_periods', d%lyapunov_max_periods, lo=0, hi=max_periods, &
         unit='periods', why='0: 20 x lyapunov_periods', note='0, or >= lyapunov_periods', &
         meaning='most periods averaged (0: 20 x lyapunov_periods)')
      call v%real('lyapunov_rel_error', d%lyapunov_rel_error, '1', lo=0.0_dp, hi=10.0_dp, &
         meaning='stop averaging when sigma <= this x |lambda| ...')
      call v%real('lyapunov_abs_error', d%lyapunov_abs_error, '1/s', lo=0.0_dp, hi=1.0e6_dp, &
         meaning='... or when sigma <= this')
      call v%real('lyapunov_perturbation', d%lyapunov_perturbation, '1', lo=1.0e-14_dp, &
         hi=1.0e-2_dp, meaning='separation of the perturbed trajectory / state norm')
      call v%int('lyapunov_starts', d%lyapunov_starts, lo=1, hi=64, meaning='independent ' &
         // 'starts of the exponent, combined: lambda their mean, sigma from their spread ' &
         // 'and their own (1: one trajectory; not run on a confidently stable orbit)')
      call v%real('chaos_sigmas', d%chaos_sigmas, '1', lo=0.0_dp, hi=100.0_dp, &
         meaning='chaotic: lambda > 0 and lambda > chaos_sigmas x sigma')
      call v%int('settle_windows', d%settle_windows, lo=2, hi=100, zero=.true., &
         why='0: no settling test; 1 is not allowed', meaning='windows of the record ' &
         // 'compared (0: no settling test)')
      call v%real('settle_tolerance', d%settle_tolerance, '1', lo=1.0e-6_dp, hi=10.0_dp, &
         meaning='windows agree when their statistics differ by at most this x orbit size')
      call v%int('transient_max_periods', d%transient_max_periods, lo=0, hi=max_periods, &
         unit='periods', why='0: 10 x &solver transient_periods', meaning='most periods ' &
         // 'discarded in all while the windows disagree (0: 10 x transient_periods)')
      call v%logical('certify', d%certify, meaning='re-check every label independently')
      call v%real('certify_ratio', d%certify_ratio, '1', lo=1.5_dp, hi=1.0e4_dp, &
         meaning='accuracy check: settings tightened by this factor')
      call v%real('certify_perturbation', d%certify_perturbation, '1', lo=1.0e-12_dp, &
         hi=1.0_dp, meaning='perturbed start: size / energy norm of the state')
      call v%real('certify_persistence', d%certify_persistence, '1', lo=0.0_dp, hi=100.0_dp, &
         meaning='chaos must persist over this multiple of the transient and record periods ' &
         // '(0: no check)')
      call v%real('orbit_tolerance', d%orbit_tolerance, '1', lo=1.0e-12_dp, hi=1.0_dp, &
         meaning='two periodic orbits are the same within this x orbit size')
      n = findloc(len_trim(d%starts) > 0, .true., dim=1, back=.true.)
      starts = d%starts(1:n)
      call v%word_list('starts', starts, size(d%starts), start_words, &
         [character(len=len(d%starts)) ::], note="each once; 'up', 'down' only in a sweep", &
         meaning='the starts of every point (none: one start)')
      if (size(starts) <= size(d%starts)) then
         d%starts = '';  d%starts(1:size(starts)) = starts
      end if
      call v%int('random_starts', d%random_starts, lo=1, hi=1000, &
         meaning="states of a 'random' start")
      call v%int('random_seed', d%random_seed, meaning='seed of the random starts and of the ' &
         // 'perturbed check')
      call v%real('random_amplitude', d%random_amplitude, 'm', lo=0.0_dp, hi=big, &
         meaning='tip scale of a random start (0: the base amplitude A_pp)')
      call v%end_group()
   end subroutine walk_diagnostics

   subroutine walk_sweep(v, s)
      class(deck_visitor_t), intent(inout) :: v
      type(sweep_settings_t), intent(inout) :: s
      call v%begin_group('sweep', "the points of analysis = 'sweep'")
      call v%word('mode', s%mode, sweep_mode_words, meaning="'independent': every point from " &
         // "&initial; 'continuation': lines, each point from the previous one's final state")
      call v%word('direction', s%direction, sweep_direction_words, meaning='lines in axis ' &
         // "order ('up') or reversed")
      call v%word('axis', s%axis, sweep_axis_words, meaning="the lines of 'up'/'down' starts " &
         // "(or of mode 'continuation') run along this axis")
      call v%text('x_variable', s%x_variable, note='several of one unit, comma separated; no ' &
         // '&forcing one among several', meaning='the x axis (fastest): numeric deck ' &
         // "variables by name, e.g. '&stops gap(1)'")
      call v%text('y_variable', s%y_variable, note='as x_variable, none of its variables', &
         meaning='the y axis')
      call v%real_list('x_values', s%x_values, max_axis_values, note='each in the ' &
         // "variable's range; not with n_x", meaning='x values as a list (not a forcing ' &
         // 'variable)')
      call v%real_list('y_values', s%y_values, max_axis_values, note="each in the variable's " &
         // 'range; not with n_y', meaning='y values as a list')
      call v%real('x_start', s%x_start, meaning='first x of a range (n_x values, both ends)')
      call v%real('x_end', s%x_end, meaning='last x of the range')
      call v%int('n_x', s%n_x, lo=0, hi=1000000, meaning='values of the x range (0: none)')
      call v%real('y_start', s%y_start, meaning='first y of a range')
      call v%real('y_end', s%y_end, meaning='last y of the range')
      call v%int('n_y', s%n_y, lo=0, hi=1000000, meaning='values of the y range (0: none)')
      call v%real_list('frequency_hz', s%frequency_hz, max_axis_values, 'Hz', lo=0.0_dp, &
         hi=max_frequency_hz, lo_open=.true., note='not with n_frequency > 0', &
         meaning='frequency axis as a list (default: &forcing frequency_hz)')
      call v%real('frequency_start_hz', s%frequency_start_hz, 'Hz', lo=0.0_dp, &
         hi=max_frequency_hz, positive=s%n_frequency > 0 .and. s%n_frequency <= 1000000, &
         note='> 0 when n_frequency > 0', &
         meaning='first frequency of a range')
      call v%real('frequency_end_hz', s%frequency_end_hz, 'Hz', lo=0.0_dp, &
         hi=max_frequency_hz, positive=s%n_frequency > 1 .and. s%n_frequency <= 1000000, &
         note='> 0 when n_frequency > 1', &
         meaning='last frequency of the range')
      call v%int('n_frequency', s%n_frequency, lo=0, hi=1000000, &
         meaning='frequencies of the range (0: no range)')
      call v%real_list('amplitude_pp', s%amplitude_pp, max_axis_values, 'm', &
         lo=min_amplitude_pp, zero=.true., note='not with n_amplitude > 0; a point whose base ' &
         // 'motion diverges is a failed point', meaning='base amplitude axis (peak to peak) ' &
         // 'as a list (default: &forcing amplitude_pp)')
      call v%real('amplitude_start_pp', s%amplitude_start_pp, 'm', lo=min_amplitude_pp, &
         zero=.true., meaning='first amplitude of a range')
      call v%real('amplitude_end_pp', s%amplitude_end_pp, 'm', lo=min_amplitude_pp, &
         zero=.true., meaning='last amplitude of the range')
      call v%int('n_amplitude', s%n_amplitude, lo=0, hi=1000000, &
         meaning='amplitudes of the range (0: no range)')
      call v%logical('progress', s%progress, meaning='progress lines on standard error ' &
         // '(also --quiet, --progress S)')
      call v%int('chunk', s%chunk, lo=0, hi=1000000, unit='work items', &
         meaning='work items between checkpoints and time-limit checks (0: automatic)')
      call v%logical('checkpoint', s%checkpoint, meaning='append every finished point to ' &
         // 'PREFIX.checkpoint and resume from it')
      call v%end_group()
   end subroutine walk_sweep

   subroutine walk_study(v, s)
      class(deck_visitor_t), intent(inout) :: v
      type(study_settings_t), intent(inout) :: s
      call v%begin_group('study', 'work-precision and stability studies')
      call v%word_list('series', s%series, 16, series_words, default_series, &
         meaning='methods compared (docs/methods.md, Studies)')
      call v%int('levels', s%levels, lo=1, hi=30, meaning='settings per series')
      call v%int('periods', s%periods, lo=1, hi=max_periods, unit='periods', &
         meaning="horizon from the deck's initial state")
      call v%int('base_steps', s%base_steps, lo=4, hi=100000000, meaning='coarsest fixed ' &
         // 'steps per period; level k uses base_steps x 2^(k-1)')
      call v%real('tolerance_start', s%tolerance_start, '1', lo=1.0e-12_dp, hi=10.0_dp, &
         meaning='loosest half-step tolerance; level k: x 10^(-(k-1)/2)')
      call v%real('rtol_start', s%rtol_start, '1', lo=1.0e-12_dp, hi=0.5_dp, meaning='loosest ' &
         // '&solver tolerance of the error-controlled series; level k: x 10^(-(k-1))')
      call v%int('repeats', s%repeats, lo=1, hi=100, meaning='timing: best of this many runs ' &
         // 'shorter than 0.2 s')
      call v%real('omega_dt_min', s%omega_dt_min, '1', lo=0.0_dp, lo_open=.true., &
         hi=1.0e12_dp, meaning='range of the spectral-radius chart, from ...')
      call v%real('omega_dt_max', s%omega_dt_max, '1', lo=0.0_dp, lo_open=.true., &
         hi=1.0e12_dp, note='>= omega_dt_min', meaning='... to')
      call v%int('n_omega_dt', s%n_omega_dt, lo=2, hi=100000, meaning='points of that chart ' &
         // '(log spaced)')
      call v%end_group()
   end subroutine walk_study

   subroutine walk_model_size(v, m)
      class(deck_visitor_t), intent(inout) :: v
      type(model_size_settings_t), intent(inout) :: m
      call v%begin_group('model_size', 'the model-size ladder')
      call v%int_list('elements', m%elements, 16, default_elements, lo=0, hi=10000, &
         note='0 entries skipped', meaning='meshes compared; the largest is the reference')
      call v%int_list('modes', m%modes, 16, default_modes, lo=0, hi=10000, &
         note='0 entries skipped', meaning='modal models of the finest mesh, each with and ' &
         // 'without the static correction')
      call v%real('cutoff_hz', m%cutoff_hz, 'Hz', lo=0.0_dp, lo_open=.true., &
         meaning='natural frequencies compared below this')
      call v%real('frequency_tolerance', m%frequency_tolerance, '1', lo=0.0_dp, &
         lo_open=.true., meaning='largest relative frequency error below the cut-off')
      call v%real('poincare_tolerance', m%poincare_tolerance, '1', lo=0.0_dp, lo_open=.true., &
         meaning='largest Poincare-set distance')
      call v%real('force_tolerance', m%force_tolerance, '1', lo=0.0_dp, lo_open=.true., &
         meaning='largest relative error of the peak stop force')
      call v%end_group()
   end subroutine walk_model_size

   subroutine walk_continuation(v, c)
      class(deck_visitor_t), intent(inout) :: v
      type(continuation_settings_t), intent(inout) :: c
      character(len=len(c%curves)), allocatable :: curves(:)
      integer :: n
      call v%begin_group('continuation', 'periodic orbits, their stability and bifurcation ' &
         // 'curves (docs/continuation.md)')
      call v%text('parameter', c%parameter, note='a design variable present in the deck', &
         meaning="the continued variable, '&group name' or '&group name(i)'")
      call v%real('parameter_min', c%parameter_min, note='< parameter_max, the deck value ' &
         // 'inside', meaning='branches end below this (its unit)')
      call v%real('parameter_max', c%parameter_max, meaning='... and above this')
      call v%word('direction', c%direction, continuation_direction_words, &
         meaning='from the start towards increasing or decreasing values, or both')
      call v%word('start', c%start, continuation_start_words, meaning="start orbit: after " &
         // "the deck's transient, or the &initial state as a section point")
      call v%int('period', c%period, lo=0, hi=1024, unit='periods', note="<= max_period; " &
         // ">= 1 with start = 'given'", why='0: detected from the transient', &
         meaning='period of the start orbit (0: detected)')
      call v%int('transient_periods', c%transient_periods, lo=-1, hi=max_periods, &
         unit='periods', why="-1: &solver's transient_periods", &
         meaning="transient before the start (-1: &solver's)")
      call v%real('step', c%step, lo=0.0_dp, meaning='first step, in the variable (0: range/200)')
      call v%real('step_min', c%step_min, lo=0.0_dp, note='< step_max', &
         meaning='smallest step (0: range x 1e-7)')
      call v%real('step_max', c%step_max, lo=0.0_dp, meaning='largest step (0: range / 50)')
      call v%int('max_points', c%max_points, lo=2, hi=1000000, meaning='points per branch')
      call v%real('tolerance', c%tolerance, '1', lo=1.0e-15_dp, hi=1.0e-2_dp, &
         meaning='Newton: residual / orbit size')
      call v%int('max_iterations', c%max_iterations, lo=1, hi=100, &
         meaning='Newton iterations per point')
      call v%word('jacobian', c%jacobian, jacobian_words, note="'exact' needs method 'exact' " &
         // "or 'auto'", meaning='monodromy from the exact integrator, or by central ' &
         // 'differences of the map')
      call v%real('fd_step', c%fd_step, '1', lo=1.0e-12_dp, hi=1.0e-2_dp, &
         meaning='relative step of the differences')
      call v%real('locate_tolerance', c%locate_tolerance, lo=0.0_dp, &
         meaning='bifurcations located to this (0: range x 1e-7)')
      call v%logical('switch_period_doubling', c%switch_period_doubling, &
         meaning='follow the doubled branch at each period doubling')
      call v%int('max_period', c%max_period, lo=1, hi=1024, unit='periods', &
         meaning='longest period followed')
      call v%int('unstable_points', c%unstable_points, lo=0, hi=1000000, &
         why='0: doubled branches are followed however unstable', meaning='a doubled branch ' &
         // 'ends after this many unstable orbits in a row (0: never)')
      call v%int('grazing_samples', c%grazing_samples, lo=8, hi=1000000, &
         meaning="samples of each contact's d' per period for the extrema of d")
      call v%text('parameter2', c%parameter2, note='not parameter; needs curves', &
         meaning="second variable of the two-parameter curves ('': none)")
      call v%real('parameter2_min', c%parameter2_min, note='< parameter2_max, the deck value ' &
         // 'inside', meaning='curves end below this')
      call v%real('parameter2_max', c%parameter2_max, meaning='... and above this')
      n = findloc(len_trim(c%curves) > 0, .true., dim=1, back=.true.)
      curves = c%curves(1:n)
      call v%word_list('curves', curves, size(c%curves), curve_kind_words, &
         [character(len=len(c%curves)) ::], note='with parameter2', &
         meaning='kinds continued in two parameters from the located bifurcations')
      if (size(curves) <= size(c%curves)) then
         c%curves = '';  c%curves(1:size(curves)) = curves
      end if
      call v%int('curve_max_points', c%curve_max_points, lo=2, hi=1000000, &
         meaning='points per curve (each way)')
      call v%real('curve_step', c%curve_step, '1', lo=0.0_dp, hi=1.0_dp, &
         meaning='largest curve step, scaled (0: 0.02)')
      call v%text('overlay', c%overlay, meaning='prefix of a sweep drawn under the charts by ' &
         // 'scripts/plot.sh')
      call v%end_group()
   end subroutine walk_continuation

   !> `a` of size n, its first entries kept, new ones `fill`.
   pure subroutine resize_int(a, n, fill)
      integer, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n, fill
      integer, allocatable :: t(:)
      integer :: m
      allocate(t(n))
      t = fill
      m = 0
      if (allocated(a)) m = min(n, size(a))
      if (m > 0) t(1:m) = a(1:m)
      call move_alloc(t, a)
   end subroutine resize_int

   !> `a` of size n, its first entries kept, new ones `fill`.
   pure subroutine resize_real(a, n, fill)
      real(dp), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      real(dp), intent(in) :: fill
      real(dp), allocatable :: t(:)
      integer :: m
      allocate(t(n))
      t = fill
      m = 0
      if (allocated(a)) m = min(n, size(a))
      if (m > 0) t(1:m) = a(1:m)
      call move_alloc(t, a)
   end subroutine resize_real
end submodule gapbeam_deck_table_settings
