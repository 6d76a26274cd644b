!> Studies that chart speed against accuracy and test stability where methods fail.
!>
!> Work-precision: each series (a method with one setting varied over a ladder: the number of
!> fixed steps per period, or a tolerance) runs the same case from rest over the same horizon;
!> its error is measured against the exact event-driven integrator (the reference: the
!> model must be piecewise linear), as the relative energy-norm error of the final state and
!> the largest error of the recorded Poincare points relative to the strain range, and its
!> cost as elapsed time on one core (best of `repeats` runs when a run is short).
!> Stability: the spectral radius of one step against omega dt on the undamped test equation
!> for each method, and the largest stable fixed step found by bisection with real runs on the
!> deck's model against the theory of the conditionally stable methods.
module gapbeam_studies
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t, energy_norm
   use gapbeam_settings, only: solver_settings_t, output_settings_t, study_settings_t
   use gapbeam_results, only: transient_result_t, series_result_t, stable_step_t
   use gapbeam_capabilities, only: method_caps_t, method_table, method_caps, method_exists, &
      exact_method, is_exact
   use gapbeam_integrator, only: refusal
   use gapbeam_transient, only: integrate
   use gapbeam_stability, only: spectral_radius, largest_stable_step
   implicit none
   private
   public :: work_precision, stability_study, stability_series

contains

   !> Settings of series `name` at ladder level k (1 = coarsest); false if unknown.
   logical function series_setting(name, k, st, base, cfg, param, pname) result(known)
      character(len=*), intent(in) :: name
      integer, intent(in) :: k
      type(study_settings_t), intent(in) :: st
      type(solver_settings_t), intent(in) :: base
      type(solver_settings_t), intent(out) :: cfg
      real(dp), intent(out) :: param
      character(len=:), allocatable, intent(out) :: pname
      type(method_caps_t) :: c
      integer :: n
      cfg = base
      known = .true.
      n = st%base_steps * 2**(k - 1)
      cfg%step_control = 'fixed';  cfg%locate_events = .true.
      cfg%steps_per_period = n;  param = n;  pname = 'steps per period'
      select case (name)
      case ('newmark_half_step', 'paper')
         cfg%method = 'newmark';  cfg%step_control = 'half_step'
         cfg%steps_per_period = st%base_steps
         cfg%half_step_tolerance = st%tolerance_start * 10.0_dp**(-0.5_dp * (k - 1))
         param = cfg%half_step_tolerance;  pname = 'half-step tolerance'
         if (name == 'paper') then
            cfg%stop_solution = 'fixed_point';  cfg%locate_events = .false.
         end if
      case ('newmark_fixed')
         cfg%method = 'newmark'
      case ('newmark_fixed_no_events')
         cfg%method = 'newmark';  cfg%locate_events = .false.
      case ('rk45', 'newmark_error', 'hht_error', 'generalized_alpha_error', 'auto')
         ! error control at tolerance rtol_start 10^-(k-1)
         select case (name)
         case ('newmark_error')
            cfg%method = 'newmark'
         case ('hht_error')
            cfg%method = 'hht'
         case ('generalized_alpha_error')
            cfg%method = 'generalized_alpha'
         case default
            cfg%method = name
         end select
         cfg%step_control = 'auto';  cfg%stop_solution = 'condensed'
         cfg%steps_per_period = st%base_steps
         cfg%tolerance = st%rtol_start * 10.0_dp**(-(k - 1))
         cfg%rk_atol = 0.0_dp
         param = cfg%tolerance;  pname = 'tolerance'
      case default
         ! any method of the registry by its name: fixed steps (an exact one: no parameter)
         known = method_exists(name)
         if (known) then
            c = method_caps(name)
            cfg%method = name
            if (c%newmark_delta >= 0.0_dp) cfg%newmark_delta = c%newmark_delta
            if (c%newmark_alpha >= 0.0_dp) cfg%newmark_alpha = c%newmark_alpha
            if (c%exact) then
               param = 0.0_dp;  pname = '-'
            end if
         end if
      end select
      c = method_caps(cfg%method)
      if (.not. c%fixed_point) cfg%stop_solution = 'condensed'
   end function series_setting

   !> The work-precision study of the deck's case.
   subroutine work_precision(model, base, out, u0, v0, st, results, err)
      type(model_t), intent(in) :: model              !! model
      type(solver_settings_t), intent(in) :: base      !! deck's solver settings
      type(output_settings_t), intent(in) :: out       !! recording (Poincare phase)
      real(dp), intent(in) :: u0(:), v0(:)             !! initial state
      type(study_settings_t), intent(in) :: st         !! study
      type(series_result_t), allocatable, intent(out) :: results(:)  !! one per series
      type(error_t), allocatable, intent(out) :: err   !! the reference cannot run
      type(solver_settings_t) :: cfg
      type(output_settings_t) :: o
      type(transient_result_t) :: ref, res
      type(error_t), allocatable :: e
      real(dp) :: param, t, norm_ref, srange
      character(len=:), allocatable :: pname, why
      integer :: s, k, nl
      o = out;  o%history_periods = st%periods     ! the whole horizon sampled
      cfg = base;  cfg%method = exact_method();  cfg%step_control = 'fixed'
      why = refusal(model, cfg)
      if (len(why) > 0) then
         call fatal_error(err, 'work_precision: the reference is the exact integrator, ' &
            // 'which refuses this model: ' // why)
         return
      end if
      cfg%transient_periods = 0;  cfg%record_periods = st%periods
      call integrate(model, cfg, o, u0, v0, ref, err)
      if (allocated(err)) return
      norm_ref = energy_norm(model, ref%u, ref%v)
      srange = max(ref%strain_max - ref%strain_min, tiny(1.0_dp))
      allocate(results(size(st%series)))
      do s = 1, size(st%series)
         nl = st%levels
         ! an exact method has no parameter to vary; 'auto' is the exact one here
         if (is_exact(st%series(s)) .or. st%series(s) == 'auto') nl = 1
         results(s)%name = trim(st%series(s))
         allocate(results(s)%parameter(nl), results(s)%seconds(nl), results(s)%error(nl), &
                  results(s)%poincare_error(nl), results(s)%steps(nl), results(s)%status(nl), &
                  results(s)%output_error(nl), results(s)%output_errors(3, nl))
         do k = 1, nl
            if (.not. series_setting(trim(st%series(s)), k, st, base, cfg, param, pname)) then
               call fatal_error(err, "work_precision: unknown series '" // trim(st%series(s)) &
                  // "'")
               return
            end if
            results(s)%parameter_name = pname
            cfg%transient_periods = 0;  cfg%record_periods = st%periods
            results(s)%parameter(k) = param
            call timed_run(model, cfg, o, u0, v0, st%repeats, res, t, e)
            results(s)%seconds(k) = t
            if (allocated(e)) then
               results(s)%status(k) = 1
               results(s)%error(k) = huge(1.0_dp);  results(s)%poincare_error(k) = huge(1.0_dp)
               results(s)%output_error(k) = huge(1.0_dp)
               results(s)%output_errors(:, k) = huge(1.0_dp)
               results(s)%steps(k) = 0.0_dp
               deallocate(e)
               cycle
            end if
            results(s)%status(k) = 0
            results(s)%steps(k) = real(res%steps_accepted, dp)
            results(s)%error(k) = energy_norm(model, res%u - ref%u, res%v - ref%v) / norm_ref
            results(s)%poincare_error(k) = maxval(abs(res%p_strain - ref%p_strain)) / srange
            results(s)%output_errors(:, k) = output_errors(res, ref)
            results(s)%output_error(k) = maxval(results(s)%output_errors(:, k))
            ! a diverged run (NaN or Inf) reaches no accuracy: it failed
            if (.not. (ieee_is_finite(results(s)%error(k)) .and. &
                       ieee_is_finite(results(s)%poincare_error(k)))) results(s)%status(k) = 1
         end do
      end do
   end subroutine work_precision

   !> Largest errors over the sampled history of the root strain, its rate and the tip
   !> displacement, each relative to the reference's range of that output.
   function output_errors(res, ref) result(e)
      type(transient_result_t), intent(in) :: res, ref   !! run, reference (same samples)
      real(dp) :: e(3)
      e(1) = maxval(abs(res%strain - ref%strain)) / range_of(ref%strain)
      e(2) = maxval(abs(res%strain_rate - ref%strain_rate)) / range_of(ref%strain_rate)
      e(3) = maxval(abs(res%tip_displacement - ref%tip_displacement)) &
             / range_of(ref%tip_displacement)
   end function output_errors

   pure real(dp) function range_of(x) result(r)
      real(dp), intent(in) :: x(:)
      r = max(maxval(x) - minval(x), tiny(1.0_dp))
   end function range_of

   !> Run and time: CPU seconds, the best of `repeats` when the run is shorter than 0.2 s.
   subroutine timed_run(model, cfg, out, u0, v0, repeats, res, seconds, err)
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      type(output_settings_t), intent(in) :: out
      real(dp), intent(in) :: u0(:), v0(:)
      integer, intent(in) :: repeats
      type(transient_result_t), intent(out) :: res
      real(dp), intent(out) :: seconds
      type(error_t), allocatable, intent(out) :: err
      integer :: r
      real(dp) :: t
      seconds = huge(1.0_dp)
      do r = 1, max(1, repeats)
         call integrate(model, cfg, out, u0, v0, res, err)
         t = res%cpu_seconds
         seconds = min(seconds, t)
         if (allocated(err) .or. t > 0.2_dp) exit
      end do
   end subroutine timed_run


   !> Spectral radius against omega dt for each method, and the largest stable fixed steps.
   subroutine stability_study(model, st, methods, omega_dt, rho, steps, err)
      type(model_t), intent(in) :: model                  !! model for the stable steps
      type(study_settings_t), intent(in) :: st             !! chart range
      character(len=*), intent(in) :: methods(:)           !! series words (stability_series)
      real(dp), allocatable, intent(out) :: omega_dt(:)    !! chart abscissae [-]
      real(dp), allocatable, intent(out) :: rho(:, :)      !! (points, methods) [-]
      type(stable_step_t), allocatable, intent(out) :: steps(:)  !! conditionally stable ones
      type(error_t), allocatable, intent(out) :: err       !! a method cannot run
      type(solver_settings_t) :: cfg, base
      type(study_settings_t) :: one
      real(dp) :: param
      character(len=:), allocatable :: pname
      type(method_caps_t), allocatable :: t(:)
      integer :: i, m, ns, j
      logical :: known
      one = st;  one%base_steps = 64
      allocate(omega_dt(st%n_omega_dt), rho(st%n_omega_dt, size(methods)))
      do i = 1, st%n_omega_dt
         omega_dt(i) = st%omega_dt_min * (st%omega_dt_max / st%omega_dt_min)**(real(i - 1, dp) &
                       / max(1, st%n_omega_dt - 1))
      end do
      do m = 1, size(methods)
         known = series_setting(trim(methods(m)), 1, one, base, cfg, param, pname)
         if (known) known = .not. is_exact(cfg%method)
         if (.not. known) then
            call fatal_error(err, "stability: no amplification matrix for '" // trim(methods(m)) &
               // "'")
            return
         end if
         do i = 1, size(omega_dt)
            call spectral_radius(cfg, omega_dt(i), rho(i, m), err)
            if (allocated(err)) return
         end do
      end do
      ! the largest stable step of every conditionally stable method of the registry (those
      ! charted through another method's amplification matrix aside)
      t = method_table()
      t = pack(t, [(t(j)%stability_limit > 0.0_dp .and. len_trim(t(j)%stability_with) == 0, &
                    j = 1, size(t))])
      allocate(steps(size(t)))
      do ns = 1, size(t)
         known = series_setting(trim(t(ns)%name), 1, one, base, cfg, param, pname)
         steps(ns)%name = trim(t(ns)%name)
         steps(ns)%limit = t(ns)%stability_limit
         steps(ns)%theory = t(ns)%stability_limit / model%omega_max
         call largest_stable_step(model, cfg, 0.5_dp * steps(ns)%theory, 3000, 1.0e-4_dp, &
                                  steps(ns)%measured, err)
         if (allocated(err)) return
      end do
   end subroutine stability_study

   !> The series of the stability study: every one of `series` that names a one-step method
   !> (its fixed-step amplification matrix; an exact method has none and is left out), or an
   !> error naming the first series that names no method ('auto' chooses one per model).
   subroutine stability_series(series, methods, err)
      character(len=*), intent(in) :: series(:)                !! the deck's series words
      character(len=32), allocatable, intent(out) :: methods(:) !! those charted
      type(error_t), allocatable, intent(out) :: err           !! a series without a method
      type(study_settings_t) :: st
      type(solver_settings_t) :: cfg, base
      real(dp) :: param
      character(len=:), allocatable :: pname
      logical :: keep(size(series))
      integer :: j
      do j = 1, size(series)
         keep(j) = series_setting(trim(series(j)), 1, st, base, cfg, param, pname)
         if (keep(j)) keep(j) = method_exists(cfg%method)
         if (.not. keep(j)) then
            call fatal_error(err, 'group &study: series(' // str(j) // ") = '" &
               // trim(series(j)) // "': analysis = 'stability' charts the amplification " &
               // 'matrix of one method, and this series names none (' &
               // "'auto' chooses one per model): give &study series, e.g. 'newmark_fixed', " &
               // "'hht', 'generalized_alpha', 'central_difference', 'rk4' (without &study " &
               // 'series the list is the work-precision study''s, which starts with ''auto'')')
            return
         end if
         keep(j) = .not. is_exact(cfg%method)
      end do
      methods = pack(series, keep)
   end subroutine stability_series
end module gapbeam_studies
