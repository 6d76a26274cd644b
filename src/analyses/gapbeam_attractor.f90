!> The attractor of a forced run and the evidence for its label: the run itself, extended
!> until the transient has settled; its period (from the Poincare points); its largest
!> Lyapunov exponent, averaged until its standard error meets a target; and the label.
!>
!> Settling: the record is cut into windows whose statistics (gapbeam_diagnostics) are
!> compared; while they differ by more than `settle_tolerance` of the orbit size the run goes
!> on for another record (the transient grows by record_periods) up to `transient_max_periods`;
!> a run that never settles is labelled 'unsettled'. A settled run with a confidently negative
!> exponent but no period yet (a weakly stable orbit still converging) is run on for the
!> periods its exponent says it needs to converge to the period tolerance, within the same
!> budget.
!>
!> Largest Lyapunov exponent: Benettin's method with a reference and a perturbed trajectory
!> renormalised once per forcing period. One integrator object, built once, advances both
!> trajectories one forcing period at a time with the run's method (the trapezoidal rule for
!> the explicit ones) and FIXED steps (T / steps_per_period, events located), or exactly, so
!> that the two follow the same discrete map: an adaptive step sequence would differ between
!> them and its local errors would swamp a small separation. The forcing is T-periodic, so
!> every period starts at t = 0 (the forcing phase stays exact). The separation is measured in
!> the energy norm ||(u, v)||^2 = u'Ku + v'Mv, started at `perturbation` times the norm of the
!> state, and rescaled to that size after every period (both states restart there in
!> equilibrium); lambda = sum ln(d_k / d_0) / ((N - N_a) T) over the periods after the first
!> N_a = max(q, N / 10) (the separation aligning with the most expanding direction). The
!> uncertainty sigma is the larger of the standard errors from 10 batches of the rest and from
!> overlapping batches of a quarter of it, whole multiples of the orbit's period q when a
!> period was found; see exponent_estimate. N starts at `lyapunov_periods` and grows (to
!> the N that sigma ~ 1/sqrt(N) predicts, with a 20 % margin, at most 4 x at a time) until
!> sigma <= max(lyapunov_abs_error, lyapunov_rel_error |lambda|) or N = lyapunov_max_periods;
!> a record that met its target is then doubled (within lyapunov_max_periods) and lambda and
!> sigma are those of the whole, so that the stop's own luck is half of what is reported.
!> With lyapunov_starts = K > 1 this is done from K independent starts, combined (their
!> spread and their own sigmas; see largest_lyapunov and combine_starts).
module gapbeam_attractor
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_model, only: model_t, energy_norm
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t, diagnostics_settings_t, output_settings_t
   use gapbeam_results, only: lyapunov_t, transient_result_t, point_result_t
   use gapbeam_diagnostics, only: period_search, classify, window_difference, repeat_distance
   use gapbeam_integrator, only: integrator_t, start_state, resolve_method
   use gapbeam_capabilities, only: method_caps_t, method_caps
   use gapbeam_transient, only: integrate, integrator_cache_t
   use gapbeam_clock, only: thread_cpu_seconds
   use gapbeam_progress, only: monitor_t
   use gapbeam_exponent_pair, only: pair_t, pair_start, pair_period
   use gapbeam_starts, only: uniform_numbers
   implicit none
   private
   public :: point_diagnostics, diagnose, persistence, exponent_estimate, combine_starts, &
      auto_period_tolerance

   !> a further start of the exponent is displaced by this x its state's energy norm [-]
   real(dp), parameter :: start_displacement = 1.0e-3_dp
   integer, parameter :: stream_starts = 900000000   !! generator streams of those directions

   !> A monitor told the work of one phase shifted by the work of the phases before it.
   type, extends(monitor_t) :: shifted_monitor_t
      class(monitor_t), pointer :: inner => null()   !! the caller's monitor
      real(dp) :: offset = 0.0_dp                    !! forcing periods integrated before
   contains
      procedure :: update => shifted_update
   end type shifted_monitor_t

contains

   !> Tell the caller's monitor `offset + done`.
   subroutine shifted_update(self, done, t, dt)
      class(shifted_monitor_t), intent(inout) :: self   !! shifted monitor
      real(dp), intent(in) :: done                      !! work of this phase
      real(dp), intent(in), optional :: t               !! simulated time [s]
      real(dp), intent(in), optional :: dt              !! step [s]
      call self%inner%update(self%offset + done, t, dt)
   end subroutine shifted_update

   !> Run from (u0, v0) until settled, then period, exponent and label with their evidence.
   !> `res` is the final record (its history, Poincare points and impact statistics). A
   !> `monitor` is told the forcing periods integrated: the runs', and the exponent's two
   !> trajectories (2 per period); the extensions and an adaptive exponent make them more
   !> than the deck's transient, record and lyapunov periods. Every run and the exponent use
   !> the integrators of `cache` (this model's; a local one when absent): one integrator per
   !> settings for the whole diagnosis, nothing rebuilt for an extension.
   subroutine diagnose(model, cfg, out, diag, u0, v0, res, pr, err, monitor, cache)
      type(model_t), intent(in) :: model                !! model
      type(solver_settings_t), intent(in) :: cfg         !! solver settings
      type(output_settings_t), intent(in) :: out         !! what to record
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      real(dp), intent(in) :: u0(:), v0(:)               !! initial state
      type(transient_result_t), intent(out) :: res       !! the final record
      type(point_result_t), intent(inout) :: pr          !! label, evidence, statistics
      type(error_t), allocatable, intent(out) :: err     !! solver failure
      class(monitor_t), intent(inout), optional, target :: monitor   !! told the progress
      type(integrator_cache_t), intent(inout), optional, target :: cache   !! integrators
      type(integrator_cache_t), target :: own
      type(integrator_cache_t), pointer :: ic
      type(solver_settings_t) :: more
      type(shifted_monitor_t) :: watch
      real(dp), allocatable :: u(:), v(:)
      real(dp) :: cpu0, tol, period, rate, distance, pending
      real(dp), allocatable :: section(:, :)
      integer :: budget, discarded, added, p, n_more, run_steps, tries, attempt
      logical :: settled

      cpu0 = thread_cpu_seconds()
      ic => own
      if (present(cache)) ic => cache
      period = 2.0_dp * pi / model%omega
      tol = auto_period_tolerance(model, cfg, diag)
      budget = transient_budget(cfg, diag)
      if (present(monitor)) watch%inner => monitor
      call run(cfg, u0, v0)
      if (allocated(err)) return
      pr%method = res%method
      run_steps = int(res%steps_accepted)
      discarded = cfg%transient_periods     ! periods before the final record
      added = 0                             ! periods added to the deck's transient
      more = cfg
      more%transient_periods = 0
      do attempt = 1, 8
         ! the settling test: another record while the windows disagree
         do
            call label_record(res, diag, tol, pr, p, settled, pending)
            if (settled .or. cfg%transient_periods + added + cfg%record_periods > budget) exit
            u = res%u;  v = res%v
            call run(more, u, v)
            if (allocated(err)) return
            run_steps = run_steps + int(res%steps_accepted)
            discarded = discarded + cfg%record_periods
            added = added + cfg%record_periods
         end do
         if (present(monitor)) then
            call exponent(model, cfg, diag, res%u, res%v, pr, err, section, watch, ic)
            watch%offset = watch%offset &
                           + 2.0_dp * real(pr%lyapunov_periods + pr%lyapunov_lead, dp)
         else
            call exponent(model, cfg, diag, res%u, res%v, pr, err, section, cache=ic)
         end if
         if (allocated(err)) return
         ! the exponent's own periods (the trajectory continued) must show the same attractor:
         ! a long chaotic transient that falls onto an orbit during them is no chaos. Their
         ! section points (phase 0) in two windows, each at least 100 periods
         if (.not. settled .or. diag%settle_windows < 2 .or. size(section, 2) < 200) exit
         if (window_difference(section(1, :), section(2, :), 2, pr%period, pr%strain_range, &
             pr%strain_rate_range) <= diag%settle_tolerance) exit
         if (cfg%transient_periods + added + cfg%record_periods > budget) then
            settled = .false.;  pr%settled = 0
            exit
         end if
         ! the attractor changed: a new record from the exponent's end, and all again
         u = pr%u_end;  v = pr%v_end
         call run(more, u, v)
         if (allocated(err)) return
         run_steps = run_steps + int(res%steps_accepted)
         discarded = discarded + cfg%record_periods + pr%lyapunov_periods + pr%lyapunov_lead
         added = added + cfg%record_periods
      end do
      ! still changing after every attempt: not settled
      if (attempt > 8) then
         settled = .false.;  pr%settled = 0
      end if
      ! a settled run, stable with confidence, whose orbit has not converged yet (no period
      ! within the tolerance, or a period p whose divisor d repeats nearly, within
      ! sqrt(tolerance): an orbit of period d still losing a slowly decaying component): run
      ! on for the periods its contraction needs (at the exponent's rate, or the slower rate
      ! the repeat distance showed), while the distance shrinks and the budget lasts
      if (settled .and. pending > tol .and. diag%lyapunov_periods > 0 .and. &
          pr%lyapunov + diag%chaos_sigmas * pr%lyapunov_error < 0.0_dp) then
         discarded = discarded + cfg%record_periods + pr%lyapunov_periods + pr%lyapunov_lead
         rate = -pr%lyapunov * period
         u = pr%u_end;  v = pr%v_end
         do tries = 1, 8
            n_more = ceiling(1.5_dp * log(pending / tol) / rate)
            n_more = max(1, min(n_more, budget - cfg%transient_periods - added))
            if (budget - cfg%transient_periods - added < 1) exit
            more%transient_periods = n_more
            distance = pending
            call run(more, u, v)
            if (allocated(err)) return
            run_steps = run_steps + int(res%steps_accepted)
            discarded = discarded + n_more
            added = added + n_more
            call label_record(res, diag, tol, pr, p, settled, pending)
            u = res%u;  v = res%v
            pr%u_end = u;  pr%v_end = v
            if (.not. (pending > tol) .or. .not. (pending < distance)) exit
            ! the rate the distance showed over the periods between the two records
            rate = min(rate, log(distance / pending) / real(n_more + cfg%record_periods, dp))
            discarded = discarded + cfg%record_periods
            added = added + cfg%record_periods
         end do
      end if
      pr%transient_periods = discarded
      pr%label = classify(pr%period, pr%lyapunov, pr%lyapunov_error, diag%chaos_sigmas, &
                          pr%settled == 1, diag%lyapunov_periods > 0)
      call copy_statistics(res, pr)
      pr%steps = run_steps
      pr%seconds_label = thread_cpu_seconds() - cpu0

   contains

      !> One run of c from (ua, va) into res (err set on failure), told to the monitor.
      subroutine run(c, ua, va)
         type(solver_settings_t), intent(in) :: c     !! settings of this run
         real(dp), intent(in) :: ua(:), va(:)         !! start
         if (present(monitor)) then
            call integrate(model, c, out, ua, va, res, err, monitor=watch, cache=ic)
            watch%offset = watch%offset + real(c%transient_periods, dp) &
                           + real(c%record_periods, dp)
         else
            call integrate(model, c, out, ua, va, res, err, cache=ic)
         end if
      end subroutine run
   end subroutine diagnose

   !> Persistence of a diagnosed point's chaos: its trajectory continued from pr%u_end,
   !> pr%v_end (the end of the exponent's periods) for at least n_periods more, in records of
   !> cfg%record_periods each searched for a period (as diagnose's records). `found`: the period
   !> of the first record that repeats within the tolerance and whose windows agree (0: none);
   !> `after`: the periods from the point's start to the end of that record (or of the last
   !> one run). A period found is confirmed by up to 3 further records (an orbit still losing
   !> a slowly decaying component repeats first at a multiple of its period): the period of
   !> the last record that repeats, until two agree.
   subroutine persistence(model, cfg, out, diag, pr, n_periods, found, after, err, cache)
      type(model_t), intent(in) :: model                 !! model
      type(solver_settings_t), intent(in) :: cfg         !! the run's settings
      type(output_settings_t), intent(in) :: out         !! what to record (no history)
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      type(point_result_t), intent(in) :: pr             !! the diagnosed point
      integer, intent(in) :: n_periods                   !! periods to continue at least
      integer, intent(out) :: found                      !! period settled on (0: none)
      integer, intent(out) :: after                      !! periods from the start
      type(error_t), allocatable, intent(out) :: err     !! solver failure
      type(integrator_cache_t), intent(inout), optional :: cache   !! this model's integrators
      type(solver_settings_t) :: c
      type(transient_result_t) :: res
      type(point_result_t) :: scratch
      real(dp), allocatable :: u(:), v(:)
      real(dp) :: tol
      integer :: k, n_rec, p
      logical :: settled
      found = 0
      after = pr%transient_periods + cfg%record_periods + pr%lyapunov_periods &
              + pr%lyapunov_lead
      if (n_periods <= 0 .or. .not. allocated(pr%u_end)) return
      tol = auto_period_tolerance(model, cfg, diag)
      c = cfg
      c%transient_periods = 0
      c%record_periods = max(1, cfg%record_periods)
      n_rec = (n_periods + c%record_periods - 1) / c%record_periods
      u = pr%u_end;  v = pr%v_end
      do k = 1, n_rec
         call integrate(model, c, out, u, v, res, err, cache=cache)
         if (allocated(err)) return
         after = after + c%record_periods
         call label_record(res, diag, tol, scratch, p, settled)
         u = res%u;  v = res%v
         if (p > 0 .and. settled) then
            found = p
            exit
         end if
      end do
      if (found == 0) return
      ! an orbit still losing a slowly decaying component repeats first at a multiple of its
      ! period: up to 3 further records, the period of the last one that repeats
      do k = 1, 3
         call integrate(model, c, out, u, v, res, err, cache=cache)
         if (allocated(err)) return
         call label_record(res, diag, tol, scratch, p, settled)
         if (p > 0 .and. settled) then
            if (p == found) exit
            found = p
         end if
         u = res%u;  v = res%v
      end do
   end subroutine persistence

   !> Period, Lyapunov exponent and label of a finished transient run (no extension: the
   !> settling test is reported, and an unsettled record is labelled so).
   !> A `monitor` is told the forcing periods integrated by the exponent's two trajectories.
   subroutine point_diagnostics(model, cfg, diag, res, pr, err, monitor)
      type(model_t), intent(in) :: model                !! model at this forcing
      type(solver_settings_t), intent(in) :: cfg         !! solver settings
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      type(transient_result_t), intent(in) :: res        !! the run
      type(point_result_t), intent(inout) :: pr          !! period, exponent, label set
      type(error_t), allocatable, intent(out) :: err     !! solver failure in the exponent
      class(monitor_t), intent(inout), optional :: monitor   !! told 2k after period k
      integer :: p
      logical :: settled
      call label_record(res, diag, auto_period_tolerance(model, cfg, diag), pr, p, settled)
      call exponent(model, cfg, diag, res%u, res%v, pr, err, monitor=monitor)
      if (allocated(err)) return
      pr%transient_periods = cfg%transient_periods
      pr%method = res%method
      pr%label = classify(pr%period, pr%lyapunov, pr%lyapunov_error, diag%chaos_sigmas, &
                          pr%settled == 1, diag%lyapunov_periods > 0)
   end subroutine point_diagnostics

   !> Period search and settling test of a record, with their evidence in pr. `pending` is
   !> the distance still to converge: the closest repeat distance when no period is found;
   !> with a period p, the repeat distance of its largest divisor d < p that repeats within
   !> sqrt(tol) (0 when none does).
   subroutine label_record(res, diag, tol, pr, p, settled, pending)
      type(transient_result_t), intent(in) :: res        !! the record
      type(diagnostics_settings_t), intent(in) :: diag   !! settings
      real(dp), intent(in) :: tol                        !! period tolerance [-]
      type(point_result_t), intent(inout) :: pr          !! evidence set
      integer, intent(out) :: p                          !! period (0: none)
      logical, intent(out) :: settled                    !! windows agree (or no test)
      real(dp), intent(out), optional :: pending         !! distance still to converge [-]
      real(dp) :: sx, sy, dd
      integer :: d
      sx = res%strain_max - res%strain_min
      sy = res%strain_rate_max - res%strain_rate_min
      call period_search(res%p_strain, res%p_strain_rate, diag%period_max, tol, &
         diag%period_points, sx, sy, p, pr%closest_period, pr%repeat_distance, &
         pr%period_max_tested)
      pr%period = p
      pr%period_tolerance = tol
      pr%strain_range = sx;  pr%strain_rate_range = sy
      pr%settle_windows = 0;  pr%window_difference = 0.0_dp
      if (diag%settle_windows >= 2 .and. size(res%p_strain) >= diag%settle_windows) then
         pr%settle_windows = diag%settle_windows
         pr%window_difference = window_difference(res%p_strain, res%p_strain_rate, &
                                                  diag%settle_windows, p, sx, sy)
      end if
      settled = pr%window_difference <= diag%settle_tolerance
      pr%settled = merge(1, 0, settled)
      if (.not. present(pending)) return
      if (p == 0) then
         pending = pr%repeat_distance
         if (pending >= huge(1.0_dp)) pending = 0.0_dp
         return
      end if
      pending = 0.0_dp
      do d = p / 2, 1, -1
         if (mod(p, d) /= 0) cycle
         dd = repeat_distance(res%p_strain, res%p_strain_rate, d, diag%period_points, sx, sy)
         if (dd <= sqrt(tol)) then
            pending = dd
            return
         end if
      end do
   end subroutine label_record

   !> The exponent from (u, v) into pr (0 +- 0 over 0 periods when none is asked); pr%u_end,
   !> pr%v_end: the reference state after the exponent's periods.
   subroutine exponent(model, cfg, diag, u, v, pr, err, section, monitor, cache)
      type(model_t), intent(in) :: model                 !! model
      type(solver_settings_t), intent(in) :: cfg         !! solver settings
      type(diagnostics_settings_t), intent(in) :: diag   !! settings
      real(dp), intent(in) :: u(:), v(:)                 !! state on the attractor
      type(point_result_t), intent(inout) :: pr          !! exponent and its evidence
      type(error_t), allocatable, intent(out) :: err     !! solver failure
      !> root strain and its rate at the end of each of the exponent's periods (2, N)
      real(dp), allocatable, intent(out), optional :: section(:, :)
      class(monitor_t), intent(inout), optional :: monitor   !! told 2k after period k
      type(integrator_cache_t), intent(inout), optional :: cache   !! this model's integrators
      type(lyapunov_t) :: lyap
      if (present(section)) allocate(section(2, 0))
      pr%u_end = u;  pr%v_end = v
      pr%lyapunov = 0.0_dp;  pr%lyapunov_error = 0.0_dp
      pr%lyapunov_periods = 0;  pr%lyapunov_converged = 0
      pr%lyapunov_dropped = 0;  pr%lyapunov_rerun = 0;  pr%lyapunov_starts = 0
      pr%lyapunov_spread = 0.0_dp;  pr%lyapunov_lead = 0
      if (diag%lyapunov_periods > 0) then
         call largest_lyapunov(model, cfg, u, v, diag, lyap, pr%u_end, pr%v_end, err, &
                               pr%period, monitor, cache)
         if (allocated(err)) return
         if (present(section)) section = lyap%section
         pr%lyapunov = lyap%exponent
         pr%lyapunov_error = lyap%uncertainty
         pr%lyapunov_running = lyap%running
         pr%lyapunov_periods = lyap%periods
         pr%lyapunov_converged = merge(1, 0, lyap%converged)
         pr%lyapunov_dropped = lyap%discordant;  pr%lyapunov_rerun = lyap%retried
         pr%lyapunov_starts = lyap%starts;  pr%lyapunov_spread = lyap%spread
         pr%lyapunov_lead = lyap%lead
      else
         pr%lyapunov_running = [real(dp) ::]
      end if
   end subroutine exponent

   !> Impact statistics and Poincare points of the final record into pr.
   subroutine copy_statistics(res, pr)
      type(transient_result_t), intent(in) :: res     !! the record
      type(point_result_t), intent(inout) :: pr       !! point
      pr%n_impacts = res%n_impacts;  pr%peak_force = res%peak_force
      pr%rms_force = res%rms_force;  pr%contact_fraction = res%contact_fraction
      pr%impulse_per_period = res%impulse_per_period;  pr%work_rate = res%work_rate
      pr%normal_work_rate = res%normal_work_rate;  pr%sliding_distance = res%sliding_distance
      pr%friction_work_rate = res%friction_work_rate
      pr%wear_volume_rate = res%wear_volume_rate
      pr%p_strain = res%p_strain;  pr%p_strain_rate = res%p_strain_rate
   end subroutine copy_statistics

   !> Period tolerance: the deck's, or from the accuracy of the method that runs: 1e-6 for an
   !> exact integrator and for fixed steps (a periodic orbit of a deterministic map repeats to
   !> round-off), 10 x the tolerance for error control (every error-controlled method, rk45 and
   !> the exponential method too: their steps are controlled at `tolerance`, as Newmark's),
   !> 1e-3 for the paper's half-step residual rule (not an accuracy); within [1e-6, 1e-2].
   !> The deck's tolerance, not the one method 'auto' tightens it to (the exponential
   !> integrator runs at no looser than 1e-4): the labels are those of the accuracy asked,
   !> and a run more accurate than asked must not find fewer periods (at the map's 1e-3,
   !> 10 x 1e-4 left a period-1 orbit still settling, repeat 8e-3, undecided).
   real(dp) function auto_period_tolerance(model, cfg, diag) result(tol)
      type(model_t), intent(in) :: model                 !! model (its stop laws)
      type(solver_settings_t), intent(in) :: cfg         !! solver settings
      type(diagnostics_settings_t), intent(in) :: diag   !! settings
      type(solver_settings_t) :: eff
      type(method_caps_t) :: c
      character(len=:), allocatable :: reason
      if (diag%period_tolerance > 0.0_dp) then
         tol = diag%period_tolerance
         return
      end if
      call resolve_method(model, cfg, eff, reason)
      c = method_caps(eff%method)
      if (c%exact .or. eff%step_control == 'fixed') then
         tol = 1.0e-6_dp
      else if (eff%step_control == 'half_step') then
         tol = 1.0e-3_dp
      else
         tol = 10.0_dp * max(eff%tolerance, cfg%tolerance)
      end if
      tol = min(1.0e-2_dp, max(1.0e-6_dp, tol))
   end function auto_period_tolerance

   !> Most periods discarded in all: the deck's, else 10 x transient_periods (at least the
   !> transient and one record).
   pure integer function transient_budget(cfg, diag) result(n)
      type(solver_settings_t), intent(in) :: cfg         !! horizon
      type(diagnostics_settings_t), intent(in) :: diag   !! settings
      if (diag%transient_max_periods > 0) then
         n = max(diag%transient_max_periods, cfg%transient_periods)
      else
         n = int(min(10_int64 * cfg%transient_periods, int(huge(1), int64) / 2))
         n = max(n, cfg%transient_periods + cfg%record_periods)
      end if
   end function transient_budget

   !> Most periods averaged for the exponent: the deck's, else 20 x lyapunov_periods.
   pure integer function lyapunov_budget(diag) result(n)
      type(diagnostics_settings_t), intent(in) :: diag   !! settings
      if (diag%lyapunov_max_periods > 0) then
         n = max(diag%lyapunov_max_periods, diag%lyapunov_periods)
      else
         n = int(min(20_int64 * diag%lyapunov_periods, int(huge(1), int64) / 2))
      end if
   end function lyapunov_budget

   !> Largest Lyapunov exponent from the state (u, v) at a period boundary, averaged until its
   !> standard error meets the target of `diag` (or its most periods), from
   !> `diag%lyapunov_starts` independent starts (see combine_starts). Start 1 is the state
   !> given; start j > 1 begins where the reference of start j - 1 ended, displaced by
   !> start_displacement of its energy norm in a seeded random direction and run alone until
   !> the displacement has grown to the attractor's size (decorrelation_periods), so that the
   !> starts are trajectories of their own, spread along the attractor. Each start averages
   !> until its own sigma meets sqrt(K) x the target (K starts of N / K periods meet the
   !> target of one start of N), at most max(lyapunov_periods, the budget / K) periods. Start
   !> 1 probes: confidently stable (lambda + chaos_sigmas sigma < 0) after its first
   !> lyapunov_periods, it is what one start would be, and when it ends so the others are
   !> not run (displaced starts return to the same orbit, and its stretchings repeat, which
   !> the batch means see whole); otherwise those periods are its lead-in.
   subroutine largest_lyapunov(model, cfg, u, v, diag, lyap, u_end, v_end, err, orbit_period, &
                               monitor, cache)
      type(model_t), intent(in) :: model               !! model
      type(solver_settings_t), intent(in) :: cfg       !! solver settings (steps_per_period)
      real(dp), intent(in) :: u(:), v(:)               !! state on the attractor
      type(diagnostics_settings_t), intent(in) :: diag !! periods, targets, perturbation
      type(lyapunov_t), intent(out) :: lyap            !! result
      real(dp), allocatable, intent(out) :: u_end(:), v_end(:)  !! reference state at the end
      type(error_t), allocatable, intent(out) :: err   !! solver failure
      !> period of the orbit (0 or absent: none): blocks are whole multiples of it
      integer, intent(in), optional :: orbit_period
      class(monitor_t), intent(inout), optional :: monitor   !! told 2k after period k
      !> this model's integrators (the pair's is built once and reused)
      type(integrator_cache_t), intent(inout), optional, target :: cache
      type(integrator_cache_t), target :: own
      class(integrator_t), pointer :: integ
      type(lyapunov_t), allocatable :: part(:)
      real(dp), allocatable :: ua(:), va(:), u1(:), v1(:)
      real(dp) :: period, spread, done, rate
      integer :: q, n_k, n_decor, j, n_starts, lead

      period = 2.0_dp * pi / model%omega
      q = 1
      if (present(orbit_period)) q = max(1, orbit_period)
      if (present(cache)) then
         call cache%get(model, lyapunov_settings(model, cfg), integ, err)
      else
         call own%get(model, lyapunov_settings(model, cfg), integ, err)
      end if
      if (allocated(err)) return
      n_starts = max(1, diag%lyapunov_starts)
      spread = sqrt(real(n_starts, dp))
      n_k = lyapunov_budget(diag)
      if (n_starts > 1) n_k = max(diag%lyapunov_periods, n_k / n_starts)
      allocate(part(n_starts))
      done = 0.0_dp
      lead = 0
      call one_start(model, integ, u, v, diag, period, q, n_k, spread, lead, part(1), ua, va, &
                     err, monitor, done, probe=n_starts > 1)
      if (allocated(err)) return
      done = done + 2.0_dp * real(lead + part(1)%periods, dp)
      j = 1
      n_decor = 0
      if (part(1)%exponent + diag%chaos_sigmas * part(1)%uncertainty >= 0.0_dp) then
         ! periods until a displacement of start_displacement has grown by 1 / itself twice
         ! over at the first start's rate (or its sigma, when lambda is within its noise)
         rate = max(part(1)%exponent, part(1)%uncertainty) * period
         n_decor = 4 * diag%lyapunov_periods
         if (rate > 0.0_dp) n_decor = min(n_decor, max(diag%lyapunov_periods, &
            ceiling(2.0_dp * log(1.0_dp / start_displacement) / rate)))
         do j = 2, n_starts
            u1 = ua;  v1 = va
            call displace_start(model, diag%random_seed, j, u1, v1)
            call one_start(model, integ, u1, v1, diag, period, q, n_k, spread, n_decor, &
                           part(j), ua, va, err, monitor, done)
            if (allocated(err)) return
            done = done + 2.0_dp * real(n_decor + part(j)%periods, dp)
         end do
         j = n_starts
      end if
      call combine_starts(part(1:j), period, lyap)
      lyap%lead = lead + (j - 1) * n_decor
      lyap%converged = lyap%uncertainty <= max(diag%lyapunov_abs_error, &
                                               diag%lyapunov_rel_error * abs(lyap%exponent))
      if (j == 1) lyap%converged = part(1)%converged
      u_end = ua;  v_end = va
   end subroutine largest_lyapunov

   !> The starts' exponents combined: lambda their mean weighted by their periods (the mean
   !> stretching over all of them); sigma the larger of the standard error from their spread
   !> (sum n_j (lambda_j - lambda)^2 / ((K - 1) sum n_j): the starts as independent estimates
   !> whose variances go as 1 / n_j) and the one from their own sigmas (sqrt(sum (n_j
   !> sigma_j)^2) / sum n_j). The running estimate, the sections and the counts run over the
   !> starts in order.
   subroutine combine_starts(part, period, lyap)
      type(lyapunov_t), intent(in) :: part(:)    !! the starts
      real(dp), intent(in) :: period             !! forcing period [s]
      type(lyapunov_t), intent(out) :: lyap      !! combined
      real(dp), allocatable :: w(:)
      real(dp) :: within, total
      integer :: j, n, k
      if (size(part) == 1) then
         lyap = part(1)
         return
      end if
      w = real(part%periods, dp)
      total = sum(w)
      lyap%starts = size(part)
      lyap%exponent = sum(w * part%exponent) / total
      lyap%spread = sqrt(sum(w * (part%exponent - lyap%exponent)**2) &
                         / (real(size(part) - 1, dp) * total))
      within = sqrt(sum((w * part%uncertainty)**2)) / total
      lyap%uncertainty = max(lyap%spread, within)
      lyap%periods = sum(part%periods)
      lyap%discordant = sum(part%discordant)
      lyap%retried = sum(part%retried)
      allocate(lyap%running(lyap%periods), lyap%section(2, lyap%periods))
      ! the running estimate over the starts in order: their running sums joined
      total = 0.0_dp
      n = 0
      do j = 1, size(part)
         do k = 1, part(j)%periods
            lyap%section(:, n + k) = part(j)%section(:, k)
            lyap%running(n + k) = (total + part(j)%running(k) * real(k, dp) * period) &
                                  / (real(n + k, dp) * period)
         end do
         n = n + part(j)%periods
         total = total + part(j)%running(part(j)%periods) * real(part(j)%periods, dp) * period
      end do
   end subroutine combine_starts

   !> The state (u, v) displaced by start_displacement of its energy norm in the seeded
   !> random direction of start j (u and v uniform in [-1, 1), scaled).
   subroutine displace_start(model, seed, j, u, v)
      type(model_t), intent(in) :: model               !! model
      integer, intent(in) :: seed                      !! &diagnostics random_seed
      integer, intent(in) :: j                         !! the start
      real(dp), intent(inout) :: u(:), v(:)            !! state
      real(dp), allocatable :: du(:), dv(:)
      real(dp) :: x, d
      du = uniform_numbers(seed, stream_starts + 2 * j, size(u))
      dv = uniform_numbers(seed, stream_starts + 2 * j + 1, size(v))
      x = energy_norm(model, u, v)
      d = energy_norm(model, du, dv)
      if (x > 0.0_dp .and. d > 0.0_dp) then
         u = u + du * (start_displacement * x / d);  v = v + dv * (start_displacement * x / d)
      end if
   end subroutine displace_start

   !> One start of the exponent from (u, v): Benettin's pair averaged until sigma meets
   !> `spread` x the target (the target itself while the estimate is confidently stable), at
   !> most n_max periods, then the record doubled (module header); its first `lead` periods
   !> are run but not averaged. A `probe` (the first of several starts) decides its lead-in
   !> after its first lyapunov_periods: confidently stable there, it goes on as a single start
   !> would (no lead-in, the target itself: a stable orbit gets what one start gives it);
   !> otherwise those periods become its lead-in (`lead` returned). (ua, va): the reference
   !> state at the end. The monitor is told done + 2k after period k.
   subroutine one_start(model, integ, u, v, diag, period, q, n_max, spread, lead, lyap, ua, &
                        va, err, monitor, done, probe)
      type(model_t), intent(in) :: model               !! model
      class(integrator_t), intent(inout) :: integ      !! the exponent's integrator
      real(dp), intent(in) :: u(:), v(:)               !! state on the attractor
      type(diagnostics_settings_t), intent(in) :: diag !! periods, targets, perturbation
      real(dp), intent(in) :: period                   !! forcing period [s]
      integer, intent(in) :: q                         !! orbit period (1: none)
      integer, intent(in) :: n_max                     !! most periods
      real(dp), intent(in) :: spread                   !! target factor (sqrt of the starts)
      integer, intent(inout) :: lead                   !! periods run first, not averaged
      type(lyapunov_t), intent(out) :: lyap            !! result of this start
      real(dp), allocatable, intent(out) :: ua(:), va(:)   !! reference state at the end
      type(error_t), allocatable, intent(out) :: err   !! solver failure
      class(monitor_t), intent(inout), optional :: monitor   !! told done + 2k
      real(dp), intent(in) :: done                     !! work before this start
      logical, intent(in), optional :: probe           !! decide the lead-in (above)
      type(state_t) :: sa, sb
      type(pair_t) :: pair
      real(dp), allocatable :: du(:), dv(:), logs(:), strain(:, :)
      logical, allocatable :: counted(:)
      real(dp) :: d0, d, x_norm, target, sigma, lambda, scale
      integer :: k, n, n_next, m, room
      logical :: rings, confirming, deciding

      x_norm = energy_norm(model, u, v)
      if (x_norm == 0.0_dp) x_norm = 1.0_dp
      d0 = diag%lyapunov_perturbation * x_norm
      ! first direction: along the velocity and displacement of the reference state
      du = u;  dv = v
      d = energy_norm(model, du, dv)
      if (d == 0.0_dp) then
         du = 1.0_dp;  dv = 0.0_dp;  d = energy_norm(model, du, dv)
      end if
      ua = u;  va = v
      room = lead + n_max
      deciding = .false.
      if (present(probe)) deciding = probe
      if (deciding) room = diag%lyapunov_periods + n_max
      scale = spread
      allocate(logs(room), strain(2, room))
      allocate(counted(room), source=.true.)
      ! ring supports: whole states carried from period to period (gapbeam_exponent_pair)
      rings = model%n_rings > 0
      if (rings) call pair_start(model, u, v, d0, pair)
      k = 0
      confirming = .false.
      n = min(diag%lyapunov_periods, n_max)
      do
         do while (k < lead + n)
            k = k + 1
            if (rings) then
               call pair_period(model, integ, period, pair, logs(k), counted(k), err)
               if (allocated(err)) return
               ua = pair%a%u;  va = pair%a%v
            else
               ! both start each period in equilibrium, so that the acceleration the methods
               ! carry is the same function of (u, v) in both: the map compared is that of (u, v)
               call start_state(model, 0.0_dp, ua, va, sa)
               call start_state(model, 0.0_dp, ua + du * (d0 / d), va + dv * (d0 / d), sb)
               call integ%advance(sa, period, err=err);  if (allocated(err)) return
               call integ%advance(sb, period, err=err);  if (allocated(err)) return
               ua = sa%u;  va = sa%v
               du = sb%u - ua;  dv = sb%v - va
               d = energy_norm(model, du, dv)
               if (d == 0.0_dp) then
                  logs(k) = log(tiny(1.0_dp))
                  du = ua;  dv = va;  d = max(energy_norm(model, du, dv), tiny(1.0_dp))
               else
                  logs(k) = log(d / d0)
               end if
            end if
            strain(1, k) = dot_product(model%sys%strain_row, ua)
            strain(2, k) = dot_product(model%sys%strain_row, va)
            if (present(monitor)) call monitor%update(done + real(2 * k, dp))
         end do
         call exponent_estimate(pack(logs(lead + 1:lead + n), counted(lead + 1:lead + n)), &
                                period, q, lambda, sigma)
         if (deciding) then
            deciding = .false.
            if (lambda + diag%chaos_sigmas * sigma < 0.0_dp) then
               scale = 1.0_dp
            else
               lead = k
               cycle
            end if
         end if
         if (confirming) exit
         target = max(diag%lyapunov_abs_error, diag%lyapunov_rel_error * abs(lambda))
         lyap%converged = sigma <= target
         if (.not. (lambda + diag%chaos_sigmas * sigma < 0.0_dp)) target = scale * target
         if (n >= n_max) exit
         if (sigma <= target) then
            ! the target met: the record doubled and lambda, sigma taken from the whole of it,
            ! so that a stop on a lucky low sigma (or a high lambda, whose target is larger)
            ! is only half of what is reported
            confirming = .true.
            n = min(n_max, 2 * n)
            cycle
         end if
         ! sigma ~ 1/sqrt(N): the N that meets the target, 20 % more, whole blocks of 10
         if (target > 0.0_dp) then
            n_next = int(min(real(n_max, dp), 1.2_dp * real(n, dp) * (sigma / target)**2))
         else
            n_next = n_max
         end if
         ! at most 4 x at a time: early on, sigma also carries the 1/N start-up bias
         n_next = min(n_next, 4 * n)
         n_next = max(n_next, n + max(10, diag%lyapunov_periods / 2))
         n_next = min(n_max, 10 * ((n_next + 9) / 10))
         n = n_next
      end do
      lyap%periods = n
      lyap%section = strain(:, lead + 1:lead + n)
      lyap%uncertainty = sigma
      lyap%discordant = count(.not. counted(1:lead + n))
      lyap%retried = pair%retried
      allocate(lyap%running(n))
      d = 0.0_dp
      m = 0
      do k = 1, n
         if (counted(lead + k)) then
            d = d + logs(lead + k);  m = m + 1
         end if
         lyap%running(k) = d / (real(max(m, 1), dp) * period)
      end do
      lyap%exponent = lambda
   end subroutine one_start

   !> The settings of the two trajectories: the method that runs (method 'auto' resolved
   !> first, so that a deck whose 'auto' is the exact integrator gets the exact exponent and
   !> not the default method's at fixed steps, which 'auto' with step_control 'fixed' would
   !> choose), with fixed steps and events; a method whose registry entry names another for
   !> the exponent (the explicit methods, only conditionally stable at T/steps_per_period)
   !> hands it to that one, with the trapezoidal rule's parameters (the exponent is a property
   !> of the model).
   function lyapunov_settings(model, cfg) result(one)
      type(model_t), intent(in) :: model           !! model (what 'auto' resolves to)
      type(solver_settings_t), intent(in) :: cfg   !! the run's settings
      type(solver_settings_t) :: one
      type(method_caps_t) :: c
      character(len=:), allocatable :: reason
      call resolve_method(model, cfg, one, reason)
      ! ring supports: the run's own method and step control (only error control ends steps
      ! at every stick-slip switch; gapbeam_exponent_pair)
      if (model%n_rings > 0) return
      c = method_caps(one%method)
      if (len_trim(c%lyapunov_with) > 0) then
         one%method = c%lyapunov_with;  one%newmark_delta = 0.5_dp;  one%newmark_alpha = 0.25_dp
         one%stop_solution = 'condensed'
      end if
      one%step_control = 'fixed'
      one%locate_events = .true.
   end function lyapunov_settings

   !> The exponent and its standard error from the stretchings ln(d_k / d_0) of n periods.
   !>
   !> The first n_a = max(q, n / 10) periods are discarded: the separation starts along the
   !> state, not along the most expanding direction, and those periods would bias the mean by
   !> O(1/n) (on a stable orbit the first periods contract much faster than the orbit does).
   !> sigma is the larger of two standard errors over the rest, both from whole orbit periods q
   !> (sums over an orbit period are what repeats; its oscillation within is not noise): the
   !> means of 10 consecutive batches, and overlapping batch means of a quarter of the record.
   !> The stretchings of a chaotic record stay correlated over hundreds of periods (the 9.8 Hz
   !> beam: the variance of a batch mean still grows from batches of 10 to 500 periods), which
   !> batches of a tenth of a short record miss; the longer overlapping batches see more of
   !> it, and are steadier than 4 disjoint batches would be.
   pure subroutine exponent_estimate(logs, period, q, lambda, sigma)
      real(dp), intent(in) :: logs(:)     !! ln(d_k / d_0) per period
      real(dp), intent(in) :: period      !! forcing period [s]
      integer, intent(in) :: q            !! orbit period (1: none)
      real(dp), intent(out) :: lambda     !! exponent [1/s]
      real(dp), intent(out) :: sigma      !! its standard error [1/s]
      integer :: n, na, m, len_b, qq
      n = size(logs)
      na = min(max(q, n / 10), n - 1)
      if (n < 2) na = 0
      m = n - na
      lambda = sum(logs(na + 1:n)) / (real(m, dp) * period)
      ! 10 batches of whole orbit periods (fewer when the record is shorter than 10 q)
      len_b = m / 10
      if (q > 1 .and. len_b >= q) len_b = (len_b / q) * q
      sigma = batch_standard_error(logs(na + 1:n), max(1, len_b))
      ! overlapping batches of a quarter of the record, whole orbit periods, starting at every
      ! orbit period (q = 1 where the record is shorter than 8 orbit periods)
      qq = q
      if (m < 8 * qq) qq = 1
      sigma = max(sigma, overlapping_standard_error(logs(na + 1:n), qq, max(1, m / (4 * qq))))
      sigma = sigma / period
   end subroutine exponent_estimate

   !> Standard error of the mean of x from the means of its consecutive batches of len_b
   !> (the last m mod len_b values, if any, in no batch).
   pure real(dp) function batch_standard_error(x, len_b) result(se)
      real(dp), intent(in) :: x(:)     !! series
      integer, intent(in) :: len_b     !! batch length
      real(dp), allocatable :: b(:)
      real(dp) :: mean
      integer :: nb, i
      nb = size(x) / max(1, len_b)
      se = 0.0_dp
      if (nb < 2) return
      allocate(b(nb))
      do i = 1, nb
         b(i) = sum(x((i - 1) * len_b + 1:i * len_b)) / len_b
      end do
      mean = sum(b) / nb
      se = sqrt(sum((b - mean)**2) / (nb - 1) / nb)
   end function batch_standard_error

   !> Standard error of the mean of x from overlapping batch means (Meketon and Schmeiser):
   !> y_j the sums of x over whole blocks of q values (the last size(x) mod q in none), the
   !> batches every run of b consecutive y: the variance of the mean of y is
   !> b / ((J - b) (J - b + 1)) sum (Y_i - mean)^2 over the J - b + 1 batch means Y_i; / q for x.
   pure real(dp) function overlapping_standard_error(x, q, b) result(se)
      real(dp), intent(in) :: x(:)     !! series
      integer, intent(in) :: q         !! block length (the orbit period; 1: none)
      integer, intent(in) :: b         !! batch length in blocks
      real(dp), allocatable :: c(:)
      real(dp) :: mean, s
      integer :: nj, j
      nj = size(x) / max(1, q)
      se = 0.0_dp
      if (b < 1 .or. nj - b < 1) return
      allocate(c(0:nj))
      c(0) = 0.0_dp
      do j = 1, nj
         c(j) = c(j - 1) + sum(x((j - 1) * q + 1:j * q))
      end do
      mean = c(nj) / nj
      s = 0.0_dp
      do j = 0, nj - b
         s = s + ((c(j + b) - c(j)) / b - mean)**2
      end do
      se = sqrt(real(b, dp) * s / (real(nj - b, dp) * real(nj - b + 1, dp))) / q
   end function overlapping_standard_error
end module gapbeam_attractor
