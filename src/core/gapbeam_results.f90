!> What analyses produce: the result types of every analysis, in one place at the bottom of the
!> dependency graph, so that writers, tests and analyses share them without depending on each
!> other.
module gapbeam_results
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: modes_t, transient_result_t, allocate_result, lyapunov_t, point_result_t, &
      series_result_t, stable_step_t, candidate_t, label_text, cpu_to_reach, certificate_text, &
      on_trajectory_clock
   public :: dispute_kind, dispute_none, dispute_contradiction, dispute_transient, dispute_other
   public :: label_chaotic, label_undecided, label_unsettled, label_failed
   public :: certificate_none, certificate_certified, certificate_disputed

   integer, parameter :: label_chaotic = -1     !! label code of a chaotic response
   ! what disputes a certificate (dispute_kind; the charts mark each with its own marker)
   integer, parameter :: dispute_none = 0           !! certified, or no certificate
   integer, parameter :: dispute_contradiction = 1  !! the label contradicts its own evidence
   integer, parameter :: dispute_transient = 2      !! a chaotic transient settled on a period
   integer, parameter :: dispute_other = 3          !! a check disagreed (accuracy, perturbed)
   integer, parameter :: label_undecided = 0    !! neither periodic nor provably chaotic
   integer, parameter :: label_unsettled = -2   !! the transient did not settle
   integer, parameter :: label_failed = -3      !! the run failed (no label)
   integer, parameter :: certificate_none = 0       !! not checked (off, or the point failed)
   integer, parameter :: certificate_certified = 1  !! independent checks agree
   integer, parameter :: certificate_disputed = 2   !! a check disagrees (or failed)

   !> Natural frequencies and mode shapes of the open structure.
   type :: modes_t
      integer :: n_modes = 0                       !! number of finite-frequency modes
      real(dp), allocatable :: omega2(:)           !! eigenvalues omega^2 [rad^2/s^2]
      real(dp), allocatable :: frequency_hz(:)     !! natural frequencies [Hz]
      real(dp), allocatable :: shapes(:, :)        !! (n_dof, n_modes) mass-normalised shapes
      real(dp), allocatable :: participation(:)    !! phi' M r, base-excitation factor [kg^0.5]
      real(dp), allocatable :: effective_mass(:)   !! (phi' M r)^2 [kg]
      real(dp) :: total_mass = 0.0_dp              !! r' M r, mass moving with the base [kg]
   end type modes_t

   !> Everything a transient run produces.
   type :: transient_result_t
      real(dp), allocatable :: time(:)              !! history sample times [s]
      real(dp), allocatable :: strain(:)            !! root strain [-]
      real(dp), allocatable :: strain_filtered(:)   !! low-pass filtered root strain (if asked) [-]
      real(dp), allocatable :: strain_rate(:)       !! root strain rate [1/s]
      real(dp), allocatable :: tip_displacement(:)  !! tip w relative to the base [m]
      real(dp), allocatable :: stop_force(:, :)     !! (samples, stops) contact force [N]
      !> (dofs, samples) every dof at the history samples (&output state_history), else
      !> unallocated [m, rad]
      real(dp), allocatable :: history_u(:, :)
      real(dp), allocatable :: p_time(:)            !! Poincare sample times [s]
      real(dp), allocatable :: p_strain(:)          !! Poincare root strain [-]
      real(dp), allocatable :: p_strain_rate(:)     !! Poincare root strain rate [1/s]
      real(dp), allocatable :: p_tip(:)             !! Poincare tip displacement [m]
      real(dp), allocatable :: p_tip_velocity(:)    !! Poincare tip velocity [m/s]
      character(len=:), allocatable :: method       !! the method that ran
      character(len=:), allocatable :: method_reason  !! why ('auto')
      integer(int64) :: steps_accepted = 0          !! Newmark solves accepted (sub-steps too)
      integer(int64) :: steps_rejected = 0          !! steps rejected by the control
      integer(int64) :: events = 0                  !! steps split at a contact event
      integer(int64) :: factorizations = 0          !! Kbar factorizations
      integer(int64) :: fp_iterations = 0           !! fixed-point iterations
      real(dp) :: cpu_seconds = 0.0_dp              !! CPU time of the run (its thread) [s]
      real(dp) :: wall_seconds = 0.0_dp             !! elapsed time of the run [s]
      real(dp) :: setup_seconds = 0.0_dp            !! CPU time of the model's set-up [s]
      real(dp) :: dt_smallest = 0.0_dp              !! smallest step used [s]
      real(dp) :: dt_largest = 0.0_dp               !! largest step used [s]
      integer, allocatable :: n_impacts(:)          !! per stop: contact onsets in the record
      real(dp), allocatable :: peak_force(:)        !! per stop [N]
      real(dp), allocatable :: rms_force(:)         !! per stop [N]
      real(dp), allocatable :: contact_fraction(:)  !! per stop: time in contact / record [-]
      real(dp), allocatable :: impulse_per_period(:)!! per stop [N s]
      real(dp), allocatable :: work_rate(:)         !! per stop: (1/T) int f |d'| dt [W]
      real(dp), allocatable :: first_contact_time(:) !! per stop: first onset, -1 if none [s]
      ! wear, per stop, over the record (/wear)
      !> normal work rate W_N = (1/T) int f_n |v_t| dt, v_t the tangential velocity [W]
      real(dp), allocatable :: normal_work_rate(:)
      !> sliding distance over the record: the friction slider's travel, or int |v_t| dt in
      !> contact without friction [m]
      real(dp), allocatable :: sliding_distance(:)
      real(dp), allocatable :: friction_work(:)     !! friction dissipation over the record [J]
      real(dp), allocatable :: friction_work_rate(:)  !! its mean rate [W]
      real(dp), allocatable :: wear_volume_rate(:)  !! Archard: wear_coefficient W_N [m^3/s]
      real(dp), allocatable :: stick_fraction(:)    !! time stuck / time in contact [-]
      ! orbits at the stops' nodes at the history samples (two-plane models)
      real(dp), allocatable :: orbit_w(:, :)        !! (samples, stops) w of the node [m]
      real(dp), allocatable :: orbit_v(:, :)        !! (samples, stops) v of the node [m]
      real(dp), allocatable :: tangential_force(:, :) !! (samples, stops) friction force [N]
      ! energy balance over the record (&output energy_balance)
      logical :: has_energy = .false.               !! the balance was computed
      real(dp) :: input_work = 0.0_dp               !! work of the loads (relative frame) [J]
      real(dp) :: rayleigh_dissipation = 0.0_dp     !! int v'Cv dt [J]
      real(dp) :: contact_damping_dissipation = 0.0_dp  !! contact dampers [J]
      real(dp) :: friction_dissipation = 0.0_dp     !! friction [J]
      real(dp) :: stored_energy_change = 0.0_dp     !! kinetic + strain + contact springs [J]
      real(dp) :: strain_min = huge(1.0_dp)         !! root strain range over the record [-]
      real(dp) :: strain_max = -huge(1.0_dp)        !! (step ends) [-]
      real(dp) :: strain_rate_min = huge(1.0_dp)    !! root strain rate range [1/s]
      real(dp) :: strain_rate_max = -huge(1.0_dp)   !! [1/s]
      real(dp), allocatable :: u(:), v(:), a(:)     !! final state
      real(dp) :: t_end = 0.0_dp                    !! final time [s]
   end type transient_result_t

   !> Estimate of the largest Lyapunov exponent.
   type :: lyapunov_t
      real(dp) :: exponent = 0.0_dp              !! lambda [1/s]
      real(dp) :: uncertainty = 0.0_dp           !! standard error over 10 blocks [1/s]
      real(dp), allocatable :: running(:)        !! estimate after each period [1/s]
      integer :: periods = 0                     !! periods averaged [-]
      logical :: converged = .false.             !! the uncertainty met its target
      !> periods not counted: the two trajectories' step sequences differed (ring supports,
      !> error control; gapbeam_exponent_pair)
      integer :: discordant = 0
      integer :: retried = 0                     !! periods run again from the other side
      integer :: starts = 1                      !! independent starts combined [-]
      integer :: lead = 0                        !! periods run but not averaged (lead-ins)
      !> standard error from the spread of the starts' exponents (0: one start) [1/s]
      real(dp) :: spread = 0.0_dp
      !> root strain [-] and its rate [1/s] of the reference trajectory at the end of each
      !> period (forcing phase 0): (2, periods)
      real(dp), allocatable :: section(:, :)
   end type lyapunov_t

   !> Everything one point produces.
   type :: point_result_t
      integer :: status = 0                          !! 0 done, 1 failed
      character(len=:), allocatable :: message       !! failure message
      integer :: period = 0                          !! detected period (0: none)
      integer :: label = 0                           !! classify() code
      real(dp) :: lyapunov = 0.0_dp                  !! largest exponent [1/s]
      real(dp) :: lyapunov_error = 0.0_dp            !! its standard error [1/s]
      real(dp), allocatable :: lyapunov_running(:)   !! running estimate [1/s]
      integer, allocatable :: n_impacts(:)           !! per stop [-]
      real(dp), allocatable :: peak_force(:)         !! per stop [N]
      real(dp), allocatable :: rms_force(:)          !! per stop [N]
      real(dp), allocatable :: contact_fraction(:)   !! per stop [-]
      real(dp), allocatable :: impulse_per_period(:) !! per stop [N s]
      real(dp), allocatable :: work_rate(:)          !! per stop [W]
      real(dp), allocatable :: normal_work_rate(:)   !! per stop [W]
      real(dp), allocatable :: sliding_distance(:)   !! per stop, over the record [m]
      real(dp), allocatable :: friction_work_rate(:) !! per stop [W]
      real(dp), allocatable :: wear_volume_rate(:)   !! per stop [m^3/s]
      real(dp), allocatable :: p_strain(:)           !! Poincare root strain [-]
      real(dp), allocatable :: p_strain_rate(:)      !! Poincare root strain rate [1/s]
      real(dp), allocatable :: u_end(:), v_end(:)    !! final state at a period boundary
      integer(int64) :: steps = 0                    !! Newmark steps of the point
      real(dp) :: seconds = 0.0_dp                   !! elapsed time of the point [s]
      ! --- the evidence of the label
      character(len=:), allocatable :: method        !! the method that ran (resolved)
      integer :: lyapunov_periods = 0                !! periods averaged for lambda [-]
      integer :: lyapunov_converged = 0              !! 1: sigma met its target, 0: stopped at max
      integer :: lyapunov_dropped = 0                !! periods not counted (step sequences differ)
      integer :: lyapunov_rerun = 0                  !! periods run again from the other side
      integer :: lyapunov_starts = 0                 !! independent starts combined (0: none)
      real(dp) :: lyapunov_spread = 0.0_dp           !! sigma from the starts' spread [1/s]
      integer :: lyapunov_lead = 0                   !! its periods run, not averaged [-]
      integer :: period_max_tested = 0               !! periods 1..this were tried [-]
      real(dp) :: period_tolerance = 0.0_dp          !! repeat tolerance used [-]
      integer :: closest_period = 0                  !! the period that repeats best [-]
      real(dp) :: repeat_distance = 0.0_dp           !! its largest repeat distance / size [-]
      integer :: transient_periods = 0               !! periods discarded in all [-]
      integer :: settle_windows = 0                  !! windows compared (0: no test) [-]
      real(dp) :: window_difference = 0.0_dp         !! largest difference / orbit size [-]
      integer :: settled = 0                         !! 1: windows agree (or no test), 0: not
      real(dp) :: strain_range = 0.0_dp              !! orbit size: root strain range [-]
      real(dp) :: strain_rate_range = 0.0_dp         !! root strain rate range [1/s]
      real(dp) :: seconds_label = 0.0_dp             !! CPU time of the labelled run [s]
      ! --- the certificate: an accuracy check and a perturbed start
      integer :: certificate = 0                     !! certificate_* code
      character(len=:), allocatable :: certificate_reason  !! why (one line)
      character(len=:), allocatable :: accuracy_method  !! the accuracy check's method ('' none)
      integer :: accuracy_label = 0                  !! its label (label_failed: it failed)
      real(dp) :: accuracy_lyapunov = 0.0_dp         !! its exponent [1/s]
      real(dp) :: accuracy_lyapunov_error = 0.0_dp   !! its standard error [1/s]
      real(dp) :: accuracy_distance = 0.0_dp         !! its orbit / statistics distance [-]
      integer :: perturbed_label = 0                 !! the perturbed start's label
      real(dp) :: perturbed_lyapunov = 0.0_dp        !! its exponent [1/s]
      real(dp) :: perturbed_lyapunov_error = 0.0_dp  !! its standard error [1/s]
      real(dp) :: perturbed_distance = 0.0_dp        !! its orbit / statistics distance [-]
      real(dp) :: seconds_certify = 0.0_dp           !! CPU time of the checks [s]
      ! --- coexisting attractors: every start and the distinct attractors they reached
      integer, allocatable :: start_label(:)         !! label of each start
      integer, allocatable :: start_attractor(:)     !! attractor each start reached (0: failed)
      real(dp), allocatable :: start_lyapunov(:)     !! exponent of each start [1/s]
      integer :: n_attractors = 0                    !! distinct attractors found
      integer, allocatable :: attractor_label(:)     !! label of each attractor
      real(dp), allocatable :: attractor_fraction(:) !! fraction of the starts reaching it [-]
      real(dp), allocatable :: attractor_lyapunov(:) !! exponent of its first start [1/s]
      !> periods each start ran before its final record (the deck's transient and the
      !> settling extensions: a chaotic transient lengthens it)
      integer, allocatable :: start_transient(:)
      !> mean of start_transient over the starts that reached each attractor [periods]
      real(dp), allocatable :: attractor_transient(:)
      ! --- the values of the sweep axes at this point
      real(dp) :: x = 0.0_dp                         !! x axis value [its unit]
      real(dp) :: y = 0.0_dp                         !! y axis value [its unit]
      real(dp) :: f1_open_hz = 0.0_dp                !! first frequency of the point's model [Hz]
      ! --- statistics over random draws (&turbulence draws > 1, docs/flow.md)
      integer :: n_draws = 0                         !! draws taken (0: none)
      real(dp), allocatable :: draw_mean(:, :)       !! (stop, output) mean over the draws
      real(dp), allocatable :: draw_ci(:, :)         !! its 95 % half-width (Student t)
   end type point_result_t

   !> One series of the work-precision study.
   type :: series_result_t
      character(len=:), allocatable :: name          !! series word
      character(len=:), allocatable :: parameter_name  !! what varies
      real(dp), allocatable :: parameter(:)          !! its values
      real(dp), allocatable :: seconds(:)            !! CPU time of a run [s]
      real(dp), allocatable :: error(:)              !! final-state error [-]
      real(dp), allocatable :: poincare_error(:)     !! Poincare points error [-]
      !> largest error over the sampled history of the root strain, its rate and the tip
      !> displacement, relative to their ranges in the reference [-]
      real(dp), allocatable :: output_error(:)
      real(dp), allocatable :: output_errors(:, :)   !! (3, levels): the three separately [-]
      real(dp), allocatable :: steps(:)              !! steps accepted [-]
      integer, allocatable :: status(:)              !! 0 done, 1 failed (e.g. unstable)
   end type series_result_t

   !> Measured and theoretical largest stable step of a method.
   type :: stable_step_t
      character(len=:), allocatable :: name          !! method
      real(dp) :: measured = 0.0_dp                  !! by bisection [s]
      real(dp) :: theory = 0.0_dp                    !! limit / omega_max [s]
      real(dp) :: limit = 0.0_dp                     !! omega_max dt at the limit [-]
   end type stable_step_t

   !> One model of the ladder and how it did.
   type :: candidate_t
      character(len=:), allocatable :: name          !! e.g. '4 elements', '3 modes + static'
      integer :: n_elem = 0                          !! elements of its mesh
      integer :: n_modes = 0                         !! 0: full model; else modes kept
      logical :: static_correction = .false.         !! modal: residual flexibility added
      integer :: n_coordinates = 0                   !! size of the integrated model
      integer :: n_compared = 0                      !! frequencies below the cut-off compared
      real(dp) :: frequency_error = 0.0_dp           !! largest relative error below cut-off
      integer :: period = 0                          !! detected period
      integer :: label = 0                           !! label code
      real(dp) :: lyapunov = 0.0_dp                  !! largest exponent [1/s]
      real(dp) :: poincare_distance = 0.0_dp         !! to the finest model's set [-]
      real(dp) :: peak_force = 0.0_dp                !! stop 1 [N]
      real(dp) :: strain_range = 0.0_dp              !! root strain range over the record [-]
      real(dp) :: strain_rate_range = 0.0_dp         !! root strain rate range [1/s]
      real(dp) :: seconds = 0.0_dp                   !! elapsed time of the run [s]
      logical :: acceptable = .false.                !! meets every tolerance
      integer :: status = 0                          !! 0 done, 1 failed
      character(len=:), allocatable :: message       !! failure
   end type candidate_t

contains

   !> Allocate the result arrays: history (n_hist samples), Poincare (n_poinc points) and the
   !> per-stop statistics (ns stops), zeroed; first contact times -1 (none yet).
   subroutine allocate_result(res, n_hist, n_poinc, ns)
      type(transient_result_t), intent(inout) :: res   !! results
      integer, intent(in) :: n_hist, n_poinc, ns        !! sizes
      allocate(res%time(n_hist), res%strain(n_hist), res%strain_rate(n_hist), &
               res%tip_displacement(n_hist), res%stop_force(n_hist, ns))
      allocate(res%p_time(n_poinc), res%p_strain(n_poinc), res%p_strain_rate(n_poinc), &
               res%p_tip(n_poinc), res%p_tip_velocity(n_poinc))
      allocate(res%n_impacts(ns), source=0)
      allocate(res%first_contact_time(ns), source=-1.0_dp)
      allocate(res%peak_force(ns), source=0.0_dp)
      allocate(res%normal_work_rate(ns), res%sliding_distance(ns), res%friction_work(ns), &
               res%friction_work_rate(ns), res%wear_volume_rate(ns), res%stick_fraction(ns), &
               source=0.0_dp)
      allocate(res%orbit_w(n_hist, ns), res%orbit_v(n_hist, ns), &
               res%tangential_force(n_hist, ns), source=0.0_dp)
   end subroutine allocate_result

   !> Text of a certificate code: 'certified', 'disputed', 'none'.
   pure function certificate_text(code) result(t)
      integer, intent(in) :: code    !! certificate code
      character(len=:), allocatable :: t
      select case (code)
      case (certificate_certified);  t = 'certified'
      case (certificate_disputed);  t = 'disputed'
      case default;  t = 'none'
      end select
   end function certificate_text

   !> What disputes a certificate, from its code and reason (gapbeam_certify writes the
   !> reasons: 'disputed: the label ... contradicts ...' for a contradiction within the
   !> point's own evidence, 'disputed: chaotic transient, then period N after M periods' for a
   !> chaos that did not persist, otherwise a check's disagreement).
   pure integer function dispute_kind(code, reason) result(kind)
      integer, intent(in) :: code                 !! certificate code
      character(len=*), intent(in) :: reason      !! certificate reason
      kind = dispute_none
      if (code /= certificate_disputed) return
      if (index(reason, 'disputed: chaotic transient') == 1) then
         kind = dispute_transient
      else if (index(reason, 'disputed: the label ') == 1 .and. &
               index(reason, ' contradicts ') > 0) then
         kind = dispute_contradiction
      else
         kind = dispute_other
      end if
   end function dispute_kind

   !> Text of a label code: 'period_3', 'chaotic', 'undecided', 'unsettled', 'failed'.
   pure function label_text(code) result(t)
      integer, intent(in) :: code    !! label code
      character(len=:), allocatable :: t
      character(len=12) :: buf
      if (code == label_chaotic) then
         t = 'chaotic'
      else if (code == label_undecided) then
         t = 'undecided'
      else if (code == label_unsettled) then
         t = 'unsettled'
      else if (code == label_failed) then
         t = 'failed'
      else
         write(buf, '(i0)') code
         t = 'period_' // trim(buf)
      end if
   end function label_text

   !> CPU time for a series to reach an error level (log-log interpolation between the runs
   !> that bracket it); a negative number when the series never reaches it. The error is the
   !> final-state one, or with `output` the output error (strain, rate, tip over the history).
   pure real(dp) function cpu_to_reach(sr, level, output) result(t)
      type(series_result_t), intent(in) :: sr      !! series
      real(dp), intent(in) :: level                !! error level [-]
      logical, intent(in), optional :: output      !! measure the output error
      real(dp), allocatable :: e(:)
      integer :: k
      real(dp) :: w
      t = -1.0_dp
      e = sr%error
      if (present(output)) then
         if (output .and. allocated(sr%output_error)) e = sr%output_error
      end if
      do k = 1, size(e)
         if (sr%status(k) /= 0) cycle
         if (e(k) <= level) then
            if (k > 1) then
               if (sr%status(k - 1) == 0 .and. e(k - 1) > level .and. e(k) > 0.0_dp) then
                  w = log(level / e(k - 1)) / log(e(k) / e(k - 1))
                  t = exp(log(sr%seconds(k - 1)) + w * (log(sr%seconds(k)) &
                      - log(sr%seconds(k - 1))))
                  return
               end if
            end if
            t = sr%seconds(k)
            return
         end if
      end do
   end function cpu_to_reach

   !> The results with their times on the clock of the whole trajectory: `res` is the final
   !> record of a run that began `transient_periods` periods before it counted from the start
   !> of the trajectory, however many periods the run that made the record integrated before
   !> it (an extension of a settling test starts at t = 0 from the end of the previous one).
   pure function on_trajectory_clock(res, transient_periods, record_periods, period) result(r)
      type(transient_result_t), intent(in) :: res      !! final record, on its run's clock
      integer, intent(in) :: transient_periods         !! periods before the record, in all
      integer, intent(in) :: record_periods            !! periods of the record
      real(dp), intent(in) :: period                   !! forcing period [s]
      type(transient_result_t) :: r
      real(dp) :: shift
      r = res
      ! the periods the record's own run integrated before the record: its end less the record
      shift = real(transient_periods - (nint(res%t_end / period) - record_periods), dp) * period
      if (shift == 0.0_dp) return
      r%time = res%time + shift
      r%p_time = res%p_time + shift
      r%t_end = res%t_end + shift
      where (res%first_contact_time >= 0.0_dp) r%first_contact_time = res%first_contact_time &
                                                                        + shift
   end function on_trajectory_clock
end module gapbeam_results
