!> The output catalogue's entry type and the sections of the studies and the continuation
!> (work-precision, stability, model size, continuation): the part of the catalogue
!> (gapbeam_output_catalogue, whose header states the conventions of an entry) that the
!> analyses of a single point do not write.
module gapbeam_output_studies
   implicit none
   private
   public :: dataset_t, work_precision_sets, stability_sets, model_size_sets, continuation_sets

   !> One dataset.
   type :: dataset_t
      character(len=56) :: path = ''         !! absolute path (pattern)
      character(len=64) :: units = ''        !! UDUNITS-2, or '=' and words (from the deck)
      character(len=48) :: dims = ''         !! axes in C order ('' for a scalar)
      character(len=232) :: long_name = ''   !! what the values are
   end type dataset_t

   type(dataset_t), parameter :: work_precision_sets(*) = [ &
      dataset_t('/work_precision/<series>/parameter_name', '1', '', 'the setting varied along ' &
                // 'the series'), &
      dataset_t('/work_precision/<series>/parameter', '1', 'levels', 'value of the setting at ' &
                // 'each level (steps per period, a tolerance, or none)'), &
      dataset_t('/work_precision/<series>/seconds', 's', 'levels', 'elapsed time of the run ' &
                // 'at each level (best of the repeats)'), &
      dataset_t('/work_precision/<series>/error', '1', 'levels', 'relative error of the final ' &
                // 'state in the energy norm, against the exact integrator'), &
      dataset_t('/work_precision/<series>/poincare_error', '1', 'levels', 'largest error of ' &
                // 'the recorded Poincare points relative to the strain range'), &
      dataset_t('/work_precision/<series>/steps', '1', 'levels', 'accepted steps of the run'), &
      dataset_t('/work_precision/<series>/output_error', '1', 'levels', 'largest relative ' &
                // 'error of the outputs (root strain, its rate, the tip) over the whole ' &
                // 'history, against the exact integrator'), &
      dataset_t('/work_precision/<series>/strain_error', '1', 'levels', 'relative error of ' &
                // 'the root strain over the history'), &
      dataset_t('/work_precision/<series>/strain_rate_error', '1', 'levels', 'relative error ' &
                // 'of the root strain rate over the history'), &
      dataset_t('/work_precision/<series>/tip_error', '1', 'levels', 'relative error of the ' &
                // 'tip displacement over the history'), &
      dataset_t('/work_precision/<series>/status', '1', 'levels', 'status of each run: 0 ' &
                // 'done, 1 failed (an error, or a diverged run: non-finite error)'), &
      dataset_t('/work_precision/<series>/seconds_to_1e-3', 's', '', 'time to reach a ' &
                // 'relative error of 1e-3 (log-log interpolation); negative: not reached'), &
      dataset_t('/work_precision/<series>/seconds_to_1e-6', 's', '', 'time to reach a ' &
                // 'relative error of 1e-6; negative: not reached'), &
      dataset_t('/work_precision/<series>/seconds_to_output_1e-3', 's', '', 'time to reach ' &
                // 'an output error of 1e-3; negative: not reached'), &
      dataset_t('/work_precision/<series>/seconds_to_output_1e-6', 's', '', 'time to reach ' &
                // 'an output error of 1e-6; negative: not reached'), &
      dataset_t('/work_precision/<series>/seconds_to_output_1e-9', 's', '', 'time to reach ' &
                // 'an output error of 1e-9; negative: not reached')]

   type(dataset_t), parameter :: stability_sets(*) = [ &
      dataset_t('/stability/omega_dt', '1', 'n_omega_dt', 'omega dt of the spectral radius ' &
                // 'chart'), &
      dataset_t('/stability/methods', '1', 'n_methods', 'the methods of the chart'), &
      dataset_t('/stability/spectral_radius', '1', 'method=n_methods omega_dt=n_omega_dt', &
                'spectral radius of one step on the undamped test equation'), &
      dataset_t('/stability/omega_max', 'rad s-1', '', 'highest natural angular frequency of ' &
                // 'the model'), &
      dataset_t('/stability/stable_step_measured', 's', 'n_stable', 'largest stable fixed ' &
                // 'step, by bisection with real runs'), &
      dataset_t('/stability/stable_step_theory', 's', 'n_stable', 'largest stable fixed step ' &
                // 'from theory (limit / omega_max)')]

   type(dataset_t), parameter :: model_size_sets(*) = [ &
      dataset_t('/model_size/name', '1', 'n_models', 'name of each model of the ladder'), &
      dataset_t('/model_size/n_elem', '1', 'n_models', 'elements of each model''s mesh'), &
      dataset_t('/model_size/n_modes', '1', 'n_models', 'modes kept by each modal model; 0: ' &
                // 'the full finite element model'), &
      dataset_t('/model_size/n_coordinates', '1', 'n_models', 'coordinates (degrees of ' &
                // 'freedom) of each model'), &
      dataset_t('/model_size/frequency_error', '1', 'n_models', 'largest relative error of ' &
                // 'the natural frequencies below the cut-off, against the reference'), &
      dataset_t('/model_size/period', '1', 'n_models', 'detected period in forcing periods; ' &
                // '0: none'), &
      dataset_t('/model_size/label', '1', 'n_models', 'label code: p >= 1 period p, 0 ' &
                // 'undecided, -1 chaotic'), &
      dataset_t('/model_size/lyapunov', 's-1', 'n_models', 'largest Lyapunov exponent'), &
      dataset_t('/model_size/poincare_distance', '1', 'n_models', 'modified Hausdorff ' &
                // 'distance of the Poincare set to the reference''s, relative to its orbit ' &
                // 'size'), &
      dataset_t('/model_size/peak_force', 'N', 'n_models', 'largest force of stop 1'), &
      dataset_t('/model_size/seconds', 's', 'n_models', 'elapsed time of each model''s run'), &
      dataset_t('/model_size/recommended', '1', '', 'index (from 1) of the recommended model; ' &
                // '0: none meets every tolerance')]

   character(len=*), parameter :: c = '/continuation/'
   character(len=*), parameter :: var_units = '=the variable''s (1 for a pure number)'
   type(dataset_t), parameter :: continuation_sets(*) = [ &
      dataset_t(c // 'title', '1', '', '&job title'), &
      dataset_t(c // 'parameter_name', '1', '', 'the continued deck variable, e.g. &forcing ' &
                // 'frequency_hz'), &
      dataset_t(c // 'parameter2_name', '1', '', 'the second variable of the two-parameter ' &
                // 'curves ('''' when none)'), &
      dataset_t(c // 'parameter2_value', var_units, '', 'value of the second variable along ' &
                // 'the branches'), &
      dataset_t(c // 'parameter', var_units, 'n', 'the continued variable at each point'), &
      dataset_t(c // 'state', 'm', 'point=n state=n_state', 'section state x = (u_r, v_r) of ' &
                // 'each orbit: the first n_state/2 entries displacements (m for w, rad for ' &
                // 'theta), the others velocities (m s-1, rad s-1)'), &
      dataset_t(c // 'state_dofs', '1', 'n_state/2', 'dof (1-based, as in /model/dof_name) ' &
                // 'of each displacement entry of a state; the velocities follow in this order'), &
      dataset_t(c // 'period', '1', 'n', 'period of the orbit in forcing periods'), &
      dataset_t(c // 'branch', '1', 'n', 'branch of the point (1: the start branch)'), &
      dataset_t(c // 'multipliers/real', '1', 'point=n multiplier=n_state', 'real part of the ' &
                // 'Floquet multipliers of each orbit, by decreasing modulus'), &
      dataset_t(c // 'multipliers/imag', '1', 'point=n multiplier=n_state', 'imaginary part ' &
                // 'of the Floquet multipliers of each orbit'), &
      dataset_t(c // 'multipliers/modulus', '1', 'point=n multiplier=n_state', 'modulus of ' &
                // 'the Floquet multipliers of each orbit'), &
      dataset_t(c // 'stable', '1', 'n', '1: every multiplier inside the unit circle ' &
                // '(stable), 0: unstable'), &
      dataset_t(c // 'located', '1', 'n', '1: a located bifurcation point, 0: a ' &
                // 'continuation step'), &
      dataset_t(c // 'arclength', '1', 'n', 'pseudo-arclength along the branch (scaled ' &
                // 'variables)'), &
      dataset_t(c // 'iterations', '1', 'n', 'Newton iterations of the point'), &
      dataset_t(c // 'grazing', 'm', 'n', 'extremum of a stop penetration along the orbit ' &
                // 'nearest 0 (0: grazing)'), &
      dataset_t(c // 'impacts', '1', 'n', 'contact intervals of the orbit'), &
      dataset_t(c // 'poincare/strain', '1', 'point=n section=max_period', 'root strain at ' &
                // 'the p section points of each orbit (NaN beyond its period)'), &
      dataset_t(c // 'poincare/strain_rate', 's-1', 'point=n section=max_period', 'root ' &
                // 'strain rate at the section points of each orbit (NaN beyond its period)'), &
      dataset_t(c // 'poincare/tip', 'm', 'point=n section=max_period', 'tip displacement at ' &
                // 'the section points of each orbit (NaN beyond its period)'), &
      dataset_t(c // 'branches/period', '1', 'n_branches', 'period of each branch in forcing ' &
                // 'periods'), &
      dataset_t(c // 'branches/parent', '1', 'n_branches', 'branch each branch was switched ' &
                // 'from at a period doubling (0: the start branch)'), &
      dataset_t(c // 'branches/first', '1', 'n_branches', 'first point of each branch ' &
                // '(1-based)'), &
      dataset_t(c // 'branches/last', '1', 'n_branches', 'last point of each branch'), &
      dataset_t(c // 'branches/ended', '1', 'n_branches', 'why each branch stopped'), &
      dataset_t(c // 'bifurcations/kind', '1', 'n_bif', 'kind of each bifurcation: ' &
                // 'saddle_node, period_doubling, neimark_sacker, grazing or branch_point'), &
      dataset_t(c // 'bifurcations/parameter', var_units, 'n_bif', 'the continued variable at ' &
                // 'each bifurcation'), &
      dataset_t(c // 'bifurcations/period', '1', 'n_bif', 'period of the orbit there, in ' &
                // 'forcing periods'), &
      dataset_t(c // 'bifurcations/branch', '1', 'n_bif', 'branch of each bifurcation'), &
      dataset_t(c // 'bifurcations/point', '1', 'n_bif', 'point of each bifurcation in the ' &
                // 'per-point arrays (1-based)'), &
      dataset_t(c // 'bifurcations/multiplier_real', '1', 'n_bif', 'real part of the ' &
                // 'critical multiplier'), &
      dataset_t(c // 'bifurcations/multiplier_imag', '1', 'n_bif', 'imaginary part of the ' &
                // 'critical multiplier'), &
      dataset_t(c // 'bifurcations/grazing', 'm', 'n_bif', 'grazing function there (the ' &
                // 'stop penetration extremum nearest 0)'), &
      dataset_t(c // 'bifurcations/note', '1', 'n_bif', 'a note on the bifurcation, e.g. why ' &
                // 'no doubled branch starts'), &
      dataset_t(c // 'curves/kind', '1', 'n_curves', 'kind of each two-parameter curve: ' &
                // 'period_doubling, saddle_node or grazing'), &
      dataset_t(c // 'curves/period', '1', 'n_curves', 'period of the orbits on each curve'), &
      dataset_t(c // 'curves/ended', '1', 'n_curves', 'why each curve stopped (each end)'), &
      dataset_t(c // 'curves/curve_<NNN>/parameter', var_units, 'n_curve_points', 'the ' &
                // 'continued variable along curve NNN'), &
      dataset_t(c // 'curves/curve_<NNN>/parameter2', var_units, 'n_curve_points', 'the ' &
                // 'second variable along curve NNN'), &
      dataset_t(c // 'seconds', 's', '', 'elapsed time of the continuation'), &
      dataset_t(c // 'map_evaluations', '1', '', 'stroboscopic maps of p periods evaluated'), &
      dataset_t(c // 'periods_integrated', '1', '', 'forcing periods integrated in all')]

end module gapbeam_output_studies
