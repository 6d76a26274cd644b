!> How to solve and what to record: every settings type a deck (or the command line) gives to
!> an analysis, with the words each choice accepts.
!>
!> Defaults live here only; the deck reader starts from them. Nothing numerical here.
module gapbeam_settings
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: job_t, calibrate_t, solver_settings_t, output_settings_t, initial_state_t, &
      diagnostics_settings_t, reduction_settings_t, model_size_settings_t, sweep_settings_t, &
      study_settings_t, batch_options_t, starts_given, initial_value_t, &
      wear_settings_t
   public :: default_series, default_elements, default_modes
   public :: stop_solution_words, step_control_words, linear_solver_words, method_words
   public :: initial_state_words, analysis_words, calibration_words, sweep_mode_words, &
      sweep_direction_words, sweep_axis_words, series_words, start_words

   !> the method words: 'auto' and every method of the registry (gapbeam_capabilities'
   !> method_table, in its order; a test checks that they agree)
   character(len=*), parameter :: method_words = "'auto', 'newmark', 'hht', 'generalized_alpha', " &
      // "'central_difference', 'linear_acceleration', 'fox_goodwin', 'rk4', 'rk45', " &
      // "'exponential', 'exact'"
   character(len=*), parameter :: stop_solution_words = "'condensed', 'fixed_point'"
   character(len=*), parameter :: step_control_words = "'auto', 'error', 'fixed', 'half_step', " &
      // "'embedded'"
   character(len=*), parameter :: linear_solver_words = "'auto', 'dense', 'banded'"
   character(len=*), parameter :: initial_state_words = "'rest', 'given', 'rotation', " &
      // "'translation', 'file'"
   character(len=*), parameter :: analysis_words = "'modes', 'calibrate', 'transient', " &
      // "'sweep', 'work_precision', 'stability', 'model_size', 'continuation'"
   character(len=*), parameter :: calibration_words = &
      "'root_k_theta', 'spring', 'thickness', 'width'"
   character(len=*), parameter :: sweep_mode_words = "'independent', 'continuation'"
   character(len=*), parameter :: sweep_direction_words = "'up', 'down'"
   character(len=*), parameter :: sweep_axis_words = "'frequency', 'amplitude', 'x', 'y'"
   character(len=*), parameter :: start_words = "'deck', 'rest', 'up', 'down', 'random'"
   character(len=*), parameter :: series_words = "'newmark_half_step', 'newmark_fixed', " &
      // "'newmark_fixed_no_events', 'paper', 'hht', 'generalized_alpha', 'central_difference', " &
      // "'linear_acceleration', 'fox_goodwin', 'rk4', 'rk45', 'exact', 'newmark_error', " &
      // "'hht_error', 'generalized_alpha_error', 'auto'"

   !> &study series when the deck gives none.
   character(len=32), parameter :: default_series(10) = [character(len=32) :: 'auto', &
      'newmark_error', 'hht_error', 'generalized_alpha_error', 'rk45', 'newmark_half_step', &
      'newmark_fixed', 'paper', 'rk4', 'exact']
   !> &model_size ladders when the deck gives none.
   integer, parameter :: default_elements(7) = [2, 3, 4, 6, 8, 15, 30]
   integer, parameter :: default_modes(6) = [1, 2, 3, 4, 5, 6]

   !> &job: what to run and where the results go.
   type :: job_t
      character(len=32)  :: analysis = 'modes'   !! analysis word
      character(len=256) :: title = ''           !! title for plots and files
      character(len=256) :: output = ''          !! output path prefix ('' -> results/<deck stem>)
   end type job_t

   !> &calibrate: which parameter to fit to a target first frequency.
   type :: calibrate_t
      character(len=16) :: parameter = 'root_k_theta'   !! see calibration_words
      integer  :: index = 1                             !! spring index for 'spring'
      real(dp) :: target_f1_hz = 0.0_dp                 !! target first frequency [Hz]
   end type calibrate_t

   !> Time integration settings.
   type :: solver_settings_t
      !> integrator: 'auto' takes the exact integrator when every stop is piecewise linear
      !> (bilinear), else 'newmark' with error control at `tolerance`
      character(len=24) :: method = 'auto'
      !> relative accuracy asked of every error-controlled method (local error per forcing
      !> period of the root strain, the tip and contact displacements, relative to their ranges)
      real(dp) :: tolerance = 1.0e-4_dp
      real(dp) :: newmark_delta = 0.5_dp              !! Newmark delta (gamma in other texts) [-]
      real(dp) :: newmark_alpha = 0.25_dp             !! Newmark alpha (beta in other texts) [-]
      real(dp) :: hht_alpha = -0.05_dp                !! HHT alpha in [-1/3, 0] [-]
      real(dp) :: rho_infinity = 0.8_dp               !! generalized-alpha rho_inf in [0, 1] [-]
      real(dp) :: rk_rtol = 1.0e-6_dp                 !! rk45 relative tolerance [-]
      real(dp) :: rk_atol = 1.0e-12_dp                !! rk45 absolute tolerance [m, m/s]
      real(dp) :: energy_bound = 1.0e8_dp             !! divergence: energy / scale above this
      character(len=16) :: stop_solution = 'condensed'   !! 'condensed' or 'fixed_point'
      real(dp) :: fp_tolerance = 1.0e-6_dp            !! fixed point: relative change of F_NL [-]
      integer  :: fp_max_iterations = 50              !! fixed point: iterations before a halving
      !> 'auto' ('error' for the Newmark family, HHT, generalized-alpha and rk45, 'fixed' for
      !> central_difference and rk4), 'error' (local error estimate against `tolerance`),
      !> 'fixed', 'half_step' (the paper's residual rule), 'embedded' (rk45: same as 'error')
      character(len=16) :: step_control = 'auto'
      integer  :: steps_per_period = 256              !! largest step = T / steps_per_period
      real(dp) :: half_step_tolerance = 0.01_dp       !! residual / largest force term per dof [-]
      real(dp) :: residual_floor = 1.0e-3_dp          !! force scale floor / the largest scale [-]
      integer  :: max_halvings = 20                   !! smallest step = largest / 2^max_halvings
      integer  :: grow_after = 4                      !! comfortable steps before doubling [-]
      real(dp) :: grow_ratio = 0.25_dp                !! 'comfortable': ratio below this [-]
      logical  :: locate_events = .true.              !! split steps at contact onset/release
      character(len=16) :: linear_solver = 'auto'     !! 'auto', 'dense' or 'banded'
      integer  :: transient_periods = 200             !! forcing periods discarded [-]
      integer  :: record_periods = 1000               !! forcing periods recorded [-]
   end type solver_settings_t

   !> What is recorded.
   type :: output_settings_t
      real(dp) :: poincare_phase_deg = 0.0_dp   !! forcing phase of the Poincare section [deg]
      integer  :: samples_per_period = 64       !! history samples per forcing period [-]
      integer  :: history_periods = 20          !! periods of history kept (start of record) [-]
      logical  :: write_text = .true.           !! gnuplot-ready .dat files next to the HDF5
      real(dp) :: filter_cutoff_hz = 0.0_dp     !! low-pass before Poincare sampling (0: off) [Hz]
      integer  :: filter_order = 4              !! Butterworth order of that filter [-]
      integer  :: filter_samples_per_period = 256  !! filter sampling rate / forcing frequency [-]
      !> energy balance over the record (input work, Rayleigh, contact-damper and friction
      !> dissipation, change of stored energy; Gauss quadrature on the dense output)
      logical  :: energy_balance = .false.
      logical  :: state_history = .false.       !! keep every dof at the history samples
      integer  :: shape_points = 8              !! points per element of the deflected shape [-]
   end type output_settings_t

   !> Initial state relative to the base: at rest, given values at listed dofs, a rigid-body
   !> field (a rotation about the root, a translation; per plane), or the final state of an
   !> earlier run's file (read with the deck: file_u, file_v, file_time).
   type :: initial_state_t
      character(len=16) :: kind = 'rest'            !! see initial_state_words
      integer, allocatable :: node(:)               !! nodes of the given values
      integer, allocatable :: dof(:)                !! dof codes of the given values
      real(dp), allocatable :: displacement(:)      !! [m or rad]
      real(dp), allocatable :: velocity(:)          !! [m/s or rad/s]
      real(dp) :: angular_velocity = 0.0_dp         !! 'rotation': rate in the w plane [rad/s]
      real(dp) :: angular_velocity_v = 0.0_dp       !! 'rotation': rate in the v plane [rad/s]
      real(dp) :: angle = 0.0_dp                    !! 'rotation': angle in the w plane [rad]
      real(dp) :: angle_v = 0.0_dp                  !! 'rotation': angle in the v plane [rad]
      real(dp) :: translation_velocity = 0.0_dp     !! 'translation': w velocity [m/s]
      real(dp) :: translation_velocity_v = 0.0_dp   !! 'translation': v velocity [m/s]
      character(len=256) :: initial_file = ''       !! 'file': an earlier transient run's .h5
      ! read from initial_file by the deck reader (not deck variables)
      real(dp), allocatable :: file_u(:)            !! its /final/u [m, rad]
      real(dp), allocatable :: file_v(:)            !! its /final/v [m/s, rad/s]
      real(dp) :: file_time = 0.0_dp                !! its /final/time [s]
   end type initial_state_t

   !> One entry of &initial as the deck gives it (the defaults of an entry).
   type :: initial_value_t
      integer :: node = -1                          !! node index [-]
      integer :: dof = 1                            !! dof code (1: w, as dof_w)
      real(dp) :: displacement = 0.0_dp             !! [m or rad]
      real(dp) :: velocity = 0.0_dp                 !! [m/s or rad/s]
   end type initial_value_t

   !> How a forced run is classified and its label certified: the settling test, period
   !> detection, the adaptive Lyapunov exponent, the independent re-checks and the starts.
   !> Zero (or negative, where said) means 'automatic' for the variables that say so.
   type :: diagnostics_settings_t
      integer  :: period_max = 64                 !! largest period looked for [periods]
      !> repeat distance / orbit size [-]; 0: from the integration accuracy (1e-6 for the
      !> exact and fixed-step methods, 10 x the tolerance for error control, within 1e-6..1e-2)
      real(dp) :: period_tolerance = 0.0_dp
      integer  :: period_points = 64              !! last Poincare points tested (>= 2p) [-]
      integer  :: lyapunov_periods = 100          !! first periods averaged (0: no exponent) [-]
      integer  :: lyapunov_max_periods = 0        !! most periods averaged (0: 20 x the first) [-]
      real(dp) :: lyapunov_rel_error = 0.1_dp     !! stop when sigma <= this x |lambda| [-]
      real(dp) :: lyapunov_abs_error = 0.05_dp    !! ... or when sigma <= this [1/s]
      real(dp) :: lyapunov_perturbation = 1.0e-7_dp  !! initial separation / state norm [-]
      !> independent starts of the exponent (1: one trajectory): each further start begins
      !> where the previous one's reference ended, displaced and run alone until it has
      !> diverged; lambda and sigma combine the starts (not run on a confidently stable orbit)
      integer  :: lyapunov_starts = 1
      real(dp) :: chaos_sigmas = 3.0_dp           !! chaotic: lambda > chaos_sigmas * uncertainty
      integer  :: settle_windows = 2              !! windows of the record compared (0: no test)
      real(dp) :: settle_tolerance = 0.1_dp       !! window statistics agree within this [-]
      !> most forcing periods discarded in all, the deck's transient included, while the
      !> windows disagree (0: 10 x transient_periods, at least transient + record periods)
      integer  :: transient_max_periods = 0
      logical  :: certify = .true.                !! re-check every label independently
      real(dp) :: certify_ratio = 10.0_dp         !! accuracy check: settings tightened by this
      real(dp) :: certify_perturbation = 1.0e-3_dp  !! perturbed start: size / state norm [-]
      !> a chaotic label is certified only when the chaos persists over this multiple of the
      !> periods before its record and the record (the run continued; 0: no persistence check)
      real(dp) :: certify_persistence = 2.0_dp
      real(dp) :: orbit_tolerance = 0.01_dp       !! same periodic orbit: distance / size [-]
      !> initial states of every point, the first one labelled and certified: 'deck' (&initial),
      !> 'rest', 'up' and 'down' (a sweep's neighbour below / above along its lines), 'random'
      !> (random_starts seeded states); '' ends the list (none given: one start, from the sweep
      !> mode, or 'deck')
      character(len=8) :: starts(8) = ''
      integer  :: random_starts = 4               !! states for each 'random' [-]
      integer  :: random_seed = 1                 !! seed of the random states [-]
      real(dp) :: random_amplitude = 0.0_dp       !! tip scale of a random state (0: A_pp) [m]
   end type diagnostics_settings_t

   !> Which model the analysis integrates: the full finite element model or a modal one.
   type :: reduction_settings_t
      character(len=16) :: kind = 'none'          !! 'none', 'modal' or 'auto'
      integer  :: n_modes = 4                     !! modes of the open structure kept [-]
      !> modal: keep the modes up to this frequency in each plane, 0: n_modes instead [Hz]
      real(dp) :: cutoff_hz = 0.0_dp
      logical  :: static_correction = .true.      !! residual flexibility at each stop dof
      !> auto: a transient run also runs a richer cut-off and prints the work-rate difference
      logical  :: convergence_check = .true.
   end type reduction_settings_t

   !> &model_size: the ladder and the tolerances.
   type :: model_size_settings_t
      integer, allocatable :: elements(:)           !! element counts of the ladder
      integer, allocatable :: modes(:)              !! mode counts of the modal models
      real(dp) :: cutoff_hz = 100.0_dp              !! frequencies compared below this [Hz]
      real(dp) :: frequency_tolerance = 0.02_dp     !! largest relative frequency error [-]
      real(dp) :: poincare_tolerance = 0.05_dp      !! largest Poincare distance [-]
      real(dp) :: force_tolerance = 0.10_dp         !! largest relative peak-force error [-]
   end type model_size_settings_t

   !> &sweep: what to sweep and how.
   type :: sweep_settings_t
      character(len=16) :: mode = 'independent'      !! 'independent' or 'continuation'
      character(len=16) :: direction = 'up'          !! continuation: 'up' or 'down'
      character(len=16) :: axis = 'frequency'        !! continuation lines run along this axis
      real(dp), allocatable :: frequency_hz(:)       !! frequency axis [Hz] (or the &forcing one)
      real(dp), allocatable :: amplitude_pp(:)       !! amplitude axis, peak to peak [m] (or one)
      !> the two axes, numeric deck variables by name (gapbeam_deck_variable): x (fastest) is
      !> '&forcing frequency_hz' and y '&forcing amplitude_pp' unless x_variable / y_variable
      !> name others; an axis may name several variables of one unit, separated by commas
      !> ('&stops gap(1), &stops gap(2)'), all set to the axis value
      character(len=160) :: x_variable = '&forcing frequency_hz'
      character(len=160) :: y_variable = '&forcing amplitude_pp'
      real(dp), allocatable :: x(:)                  !! values of the x axis [its unit]
      real(dp), allocatable :: y(:)                  !! values of the y axis [its unit]
      ! the axes as the deck gives them (read_deck makes frequency_hz, amplitude_pp, x, y)
      real(dp) :: frequency_start_hz = 0.0_dp        !! first frequency of a range [Hz]
      real(dp) :: frequency_end_hz = 0.0_dp          !! last frequency of a range [Hz]
      integer :: n_frequency = 0                     !! frequencies of the range (0: none)
      real(dp) :: amplitude_start_pp = 0.0_dp        !! first amplitude of a range [m]
      real(dp) :: amplitude_end_pp = 0.0_dp          !! last amplitude of a range [m]
      integer :: n_amplitude = 0                     !! amplitudes of the range (0: none)
      real(dp), allocatable :: x_values(:)           !! x axis as a list [its unit]
      real(dp), allocatable :: y_values(:)           !! y axis as a list [its unit]
      real(dp) :: x_start = 0.0_dp                   !! first x of a range [its unit]
      real(dp) :: x_end = 0.0_dp                     !! last x of a range
      integer :: n_x = 0                             !! x values of the range (0: none)
      real(dp) :: y_start = 0.0_dp                   !! first y of a range [its unit]
      real(dp) :: y_end = 0.0_dp                     !! last y of a range
      integer :: n_y = 0                             !! y values of the range (0: none)
      logical :: progress = .true.                   !! progress on standard error
      integer :: chunk = 0                           !! work items between checkpoints (0: auto)
      logical :: checkpoint = .true.                 !! write finished points as they come
   end type sweep_settings_t

   !> &wear: the wear depth in the tube wall over years of operation (the scar geometry is per
   !> support, in &stops).
   type :: wear_settings_t
      real(dp) :: years = 0.0_dp              !! operating time (0: no depth) [a]
      real(dp) :: wall_thickness = 0.0_dp     !! tube wall thickness [m]
      real(dp) :: tube_diameter = 0.0_dp      !! tube outer diameter (0: &flow's) [m]
      real(dp) :: wall_fraction = 0.4_dp      !! the depth whose time is reported, of the wall [-]
      integer :: depth_points = 51            !! times of /wear/depth from 0 to years [-]
   end type wear_settings_t

   !> &study: what the work-precision and stability studies compare.
   type :: study_settings_t
      character(len=32), allocatable :: series(:)   !! series words
      integer :: levels = 8                         !! settings per series [-]
      integer :: periods = 10                       !! horizon from rest [forcing periods]
      integer :: base_steps = 64                    !! coarsest fixed steps per period [-]
      real(dp) :: tolerance_start = 0.1_dp          !! loosest half-step tolerance [-]
      !> loosest &solver tolerance of the error-controlled series (rk45, newmark_error,
      !> hht_error, generalized_alpha_error, auto), divided by 10 per level [-]
      real(dp) :: rtol_start = 1.0e-2_dp
      integer :: repeats = 3                        !! timing repeats of short runs [-]
      real(dp) :: omega_dt_min = 1.0e-2_dp          !! stability chart range [-]
      real(dp) :: omega_dt_max = 1.0e3_dp           !! [-]
      integer :: n_omega_dt = 101                   !! points of the chart [-]
   end type study_settings_t

   !> Options from the command line (not the deck): a job array's shard, a time limit, and
   !> the progress lines.
   type :: batch_options_t
      integer :: shard_index = 1                     !! this process's shard (--shard I/N)
      integer :: shard_count = 1                     !! number of shards
      real(dp) :: time_limit_s = 0.0_dp              !! stop after this [s], 0: none
      logical :: quiet = .false.                     !! no progress lines (--quiet)
      real(dp) :: progress_interval_s = 0.0_dp       !! between progress lines [s], 0: default
      character(len=:), allocatable :: shard_costs   !! --shard-costs FILE.h5: deal the points
                                                     !! to the shards by these costs
   end type batch_options_t

contains

   !> Starts per point that `diag` asks for ('random' counts random_starts); 0 when none is
   !> given (a run then has its one default start).
   pure integer function starts_given(diag) result(n)
      type(diagnostics_settings_t), intent(in) :: diag   !! settings
      integer :: j
      n = 0
      do j = 1, size(diag%starts)
         if (len_trim(diag%starts(j)) == 0) exit
         if (diag%starts(j) == 'random') then
            n = n + diag%random_starts
         else
            n = n + 1
         end if
      end do
   end function starts_given
end module gapbeam_settings
