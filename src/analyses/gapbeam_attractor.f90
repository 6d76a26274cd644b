!> The attractor of a forced run: its period (from the Poincare points), its largest Lyapunov
!> exponent and its label.
!>
!> Largest Lyapunov exponent: Benettin's method with a reference and a perturbed trajectory
!> renormalised once per forcing period.
!>
!> One integrator object, built once, advances both trajectories one forcing period at a time
!> with the run's method (the trapezoidal rule for the explicit ones) and FIXED steps
!> (T / steps_per_period, events located), or exactly, so that the two follow the same
!> discrete map: an adaptive step sequence would differ between them and its local errors
!> would swamp a small separation. The forcing is T-periodic, so every period starts at t = 0
!> (the forcing phase stays exact). The separation is measured in the energy norm
!> ||(u, v)||^2 = u'Ku + v'Mv, started at `perturbation` times the norm of the state, and
!> rescaled to that size after every period (both states restart there in equilibrium);
!> lambda = sum ln(d_k / d_0) / (N T). The uncertainty is the standard error of the mean over
!> 10 blocks of periods, and the running estimate after each period is returned to show its
!> convergence.
module gapbeam_attractor
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_model, only: model_t, energy_norm
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t, diagnostics_settings_t
   use gapbeam_results, only: lyapunov_t, transient_result_t, point_result_t
   use gapbeam_diagnostics, only: detect_period, classify
   use gapbeam_integrator, only: integrator_t, make_integrator, start_state
   use gapbeam_progress, only: monitor_t
   implicit none
   private
   public :: largest_lyapunov, point_diagnostics

contains

   !> Period, Lyapunov exponent and label of a finished transient run. A `monitor` is told the
   !> forcing periods integrated by the exponent's two trajectories (2 per period).
   subroutine point_diagnostics(model, cfg, diag, res, pr, err, monitor)
      type(model_t), intent(in) :: model                !! model at this forcing
      type(solver_settings_t), intent(in) :: cfg         !! solver settings
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      type(transient_result_t), intent(in) :: res        !! the run
      type(point_result_t), intent(inout) :: pr          !! period, exponent, label set
      type(error_t), allocatable, intent(out) :: err     !! solver failure in the exponent
      class(monitor_t), intent(inout), optional :: monitor   !! told the progress
      type(lyapunov_t) :: lyap
      real(dp) :: sx, sy
      sx = res%strain_max - res%strain_min
      sy = res%strain_rate_max - res%strain_rate_min
      pr%period = detect_period(res%p_strain, res%p_strain_rate, diag%period_max, &
                                diag%period_tolerance, diag%period_points, sx, sy)
      pr%u_end = res%u;  pr%v_end = res%v
      if (diag%lyapunov_periods > 0) then
         call largest_lyapunov(model, cfg, res%u, res%v, diag%lyapunov_periods, &
            diag%lyapunov_perturbation, lyap, pr%u_end, pr%v_end, err, monitor)
         if (allocated(err)) return
         pr%lyapunov = lyap%exponent
         pr%lyapunov_error = lyap%uncertainty
         pr%lyapunov_running = lyap%running
      else
         allocate(pr%lyapunov_running(0))
      end if
      pr%label = classify(pr%period, pr%lyapunov, pr%lyapunov_error, diag%chaos_sigmas)
   end subroutine point_diagnostics

   !> Largest Lyapunov exponent from the state (u, v) at a period boundary.
   subroutine largest_lyapunov(model, cfg, u, v, n_periods, perturbation, lyap, u_end, v_end, &
                               err, monitor)
      type(model_t), intent(in) :: model               !! model
      type(solver_settings_t), intent(in) :: cfg       !! solver settings (steps_per_period)
      real(dp), intent(in) :: u(:), v(:)               !! state on the attractor
      integer, intent(in) :: n_periods                 !! periods averaged
      real(dp), intent(in) :: perturbation             !! initial separation, relative [-]
      type(lyapunov_t), intent(out) :: lyap            !! result
      real(dp), allocatable, intent(out) :: u_end(:), v_end(:)  !! reference state at the end
      type(error_t), allocatable, intent(out) :: err   !! solver failure
      class(monitor_t), intent(inout), optional :: monitor   !! told 2k after period k
      class(integrator_t), allocatable :: integ
      type(state_t) :: sa, sb
      real(dp), allocatable :: ua(:), va(:), du(:), dv(:), logs(:)
      real(dp) :: d0, d, period, x_norm
      integer :: k

      period = 2.0_dp * pi / model%omega
      call make_integrator(model, lyapunov_settings(cfg), integ, err)
      if (allocated(err)) return
      x_norm = energy_norm(model, u, v)
      if (x_norm == 0.0_dp) x_norm = 1.0_dp
      d0 = perturbation * x_norm
      ! first direction: along the velocity and displacement of the reference state
      du = u;  dv = v
      d = energy_norm(model, du, dv)
      if (d == 0.0_dp) then
         du = 1.0_dp;  dv = 0.0_dp;  d = energy_norm(model, du, dv)
      end if
      ua = u;  va = v
      allocate(lyap%running(n_periods), logs(n_periods))
      do k = 1, n_periods
         ! both start each period in equilibrium, so that the acceleration the methods carry
         ! is the same function of (u, v) in both: the map compared is that of (u, v)
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
         lyap%running(k) = sum(logs(1:k)) / (real(k, dp) * period)
         if (present(monitor)) call monitor%update(real(2 * k, dp))
      end do
      lyap%exponent = lyap%running(n_periods)
      lyap%uncertainty = block_standard_error(logs, period)
      u_end = ua;  v_end = va
   end subroutine largest_lyapunov

   !> The settings of the two trajectories: fixed steps with events; the explicit methods are
   !> only conditionally stable at T/steps_per_period, so the exponent (a property of the model)
   !> is then taken with the trapezoidal rule.
   pure function lyapunov_settings(cfg) result(one)
      type(solver_settings_t), intent(in) :: cfg   !! the run's settings
      type(solver_settings_t) :: one
      one = cfg
      select case (cfg%method)
      case ('rk4', 'rk45', 'central_difference')
         one%method = 'newmark';  one%newmark_delta = 0.5_dp;  one%newmark_alpha = 0.25_dp
         one%stop_solution = 'condensed'
      end select
      one%step_control = 'fixed'
      one%locate_events = .true.
   end function lyapunov_settings

   !> Standard error of the mean exponent over 10 blocks of periods [1/s].
   pure real(dp) function block_standard_error(logs, period) result(se)
      real(dp), intent(in) :: logs(:)     !! ln(d_k / d_0) per period
      real(dp), intent(in) :: period      !! forcing period [s]
      real(dp) :: block(10), mean, var
      integer :: nb, b, per_block
      nb = min(10, size(logs))
      per_block = size(logs) / nb
      do b = 1, nb
         block(b) = sum(logs((b - 1) * per_block + 1:b * per_block)) / (per_block * period)
      end do
      mean = sum(block(1:nb)) / nb
      var = 0.0_dp
      if (nb > 1) var = sum((block(1:nb) - mean)**2) / (nb - 1)
      se = sqrt(var / nb)
   end function block_standard_error
end module gapbeam_attractor
