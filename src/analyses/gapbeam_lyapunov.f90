!> Largest Lyapunov exponent of a forced run (Benettin's method with a reference and a
!> perturbed trajectory renormalised once per forcing period).
!>
!> Both trajectories are advanced one forcing period at a time with the run's method (the
!> trapezoidal rule for the explicit ones) and FIXED steps (T / steps_per_period, events
!> located), or by the exact integrator, so that the two follow the same
!> discrete map: an adaptive step sequence would differ between them and its local errors
!> would swamp a small separation. The separation is measured in the energy norm
!> ||(u, v)||^2 = u'Ku + v'Mv, started at `perturbation` times the norm of the state, and
!> rescaled to that size after every period; lambda = sum ln(d_k / d_0) / (N T).
!> The uncertainty is the standard error of the mean over 10 blocks of periods, and the
!> running estimate after each period is returned to show its convergence.
module gapbeam_lyapunov
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_problem, only: problem_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t
   use gapbeam_transient, only: transient_result_t
   use gapbeam_integrate, only: integrate
   implicit none
   private
   public :: lyapunov_t, largest_lyapunov

   !> Estimate of the largest Lyapunov exponent.
   type :: lyapunov_t
      real(dp) :: exponent = 0.0_dp              !! lambda [1/s]
      real(dp) :: uncertainty = 0.0_dp           !! standard error over 10 blocks [1/s]
      real(dp), allocatable :: running(:)        !! estimate after each period [1/s]
   end type lyapunov_t

contains

   !> Largest Lyapunov exponent from the state (u, v) at a period boundary.
   subroutine largest_lyapunov(prob, cfg, u, v, n_periods, perturbation, lyap, u_end, v_end, err)
      type(problem_t), intent(in) :: prob              !! model
      type(solver_settings_t), intent(in) :: cfg       !! solver settings (steps_per_period)
      real(dp), intent(in) :: u(:), v(:)               !! state on the attractor
      integer, intent(in) :: n_periods                 !! periods averaged
      real(dp), intent(in) :: perturbation             !! initial separation, relative [-]
      type(lyapunov_t), intent(out) :: lyap            !! result
      real(dp), allocatable, intent(out) :: u_end(:), v_end(:)  !! reference state at the end
      type(error_t), allocatable, intent(out) :: err   !! solver failure
      type(solver_settings_t) :: one
      type(output_settings_t) :: quiet
      type(transient_result_t) :: ra, rb
      real(dp), allocatable :: ua(:), va(:), ub(:), vb(:), du(:), dv(:), logs(:)
      real(dp) :: d0, d, period, block(10), mean, var, x_norm
      integer :: k, nb, b, per_block

      period = 2.0_dp * pi / prob%omega
      one = cfg
      ! the explicit methods are only conditionally stable at T/steps_per_period: the
      ! exponent (a property of the model) is then taken with the trapezoidal rule
      select case (cfg%method)
      case ('rk4', 'rk45', 'central_difference')
         one%method = 'newmark';  one%newmark_delta = 0.5_dp;  one%newmark_alpha = 0.25_dp
         one%stop_solution = 'condensed'
      end select
      one%step_control = 'fixed'
      one%locate_events = .true.
      one%transient_periods = 0
      one%record_periods = 1
      quiet%history_periods = 0
      quiet%samples_per_period = 1
      ua = u;  va = v
      x_norm = energy_norm(prob, ua, va)
      if (x_norm == 0.0_dp) x_norm = 1.0_dp
      d0 = perturbation * x_norm
      ! first direction: along the velocity and displacement of the reference state
      du = ua;  dv = va
      d = energy_norm(prob, du, dv)
      if (d == 0.0_dp) then
         du = 1.0_dp;  dv = 0.0_dp;  d = energy_norm(prob, du, dv)
      end if
      ub = ua + du * (d0 / d);  vb = va + dv * (d0 / d)
      allocate(lyap%running(n_periods), logs(n_periods))
      do k = 1, n_periods
         call integrate(prob, one, quiet, ua, va, ra, err);  if (allocated(err)) return
         call integrate(prob, one, quiet, ub, vb, rb, err);  if (allocated(err)) return
         ua = ra%u;  va = ra%v
         du = rb%u - ua;  dv = rb%v - va
         d = energy_norm(prob, du, dv)
         if (d == 0.0_dp) then
            logs(k) = log(tiny(1.0_dp))
            du = ua;  dv = va;  d = max(energy_norm(prob, du, dv), tiny(1.0_dp))
         else
            logs(k) = log(d / d0)
         end if
         ub = ua + du * (d0 / d);  vb = va + dv * (d0 / d)
         lyap%running(k) = sum(logs(1:k)) / (real(k, dp) * period)
      end do
      lyap%exponent = lyap%running(n_periods)
      ! standard error over 10 blocks
      nb = min(10, n_periods)
      per_block = n_periods / nb
      do b = 1, nb
         block(b) = sum(logs((b - 1) * per_block + 1:b * per_block)) / (per_block * period)
      end do
      mean = sum(block(1:nb)) / nb
      var = 0.0_dp
      if (nb > 1) var = sum((block(1:nb) - mean)**2) / (nb - 1)
      lyap%uncertainty = sqrt(var / nb)
      u_end = ua;  v_end = va
   end subroutine largest_lyapunov

   !> Energy norm sqrt(u'Ku + v'Mv).
   real(dp) function energy_norm(prob, u, v)
      type(problem_t), intent(in) :: prob
      real(dp), intent(in) :: u(:), v(:)
      energy_norm = sqrt(max(0.0_dp, dot_product(u, matmul(prob%sys%k, u)) &
                         + dot_product(v, matmul(prob%sys%m, v))))
   end function energy_norm
end module gapbeam_lyapunov
