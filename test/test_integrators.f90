!> The integrator family: observed orders on a smooth linear case, spectral radii (rho_inf of
!> HHT and generalized-alpha), and the largest stable step of the conditionally stable methods
!> against theory, measured by bisection with real runs on the 4- and 15-element models.
program test_integrators
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_full_model, initial_vectors
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_stability, only: spectral_radius, largest_stable_step
   use gapbeam_test_runs, only: run_deck
   implicit none
   character(len=*), parameter :: ref = 'test/decks/moon_shaw_10p5hz_half_element.nml'
   character(len=*), parameter :: linear = "&stops rule_factor = 0.0, stiffness = 1.0, " &
      // "gap = 10.0 / &damping model = 'ratios', frequency1_hz = 4.3, ratio1 = 0.02, " &
      // "frequency2_hz = 26.0, ratio2 = 0.02 /"
   character(len=*), parameter :: short = "&solver transient_periods = 0, record_periods = 2 /"

   call orders_on_a_linear_case()
   call spectral_radii()
   call stable_steps()
   call divergence_is_reported()
   call finish('test_integrators')

contains

   subroutine run(overrides, model, res, ok, message)
      character(len=*), intent(in) :: overrides(:)
      type(model_t), intent(out) :: model
      type(transient_result_t), intent(out) :: res
      logical, intent(out), optional :: ok
      character(len=:), allocatable, intent(out), optional :: message
      type(error_t), allocatable :: err
      call run_deck(ref, overrides, model, res, err)
      if (present(ok)) then
         ok = .not. allocated(err)
         if (present(message) .and. allocated(err)) message = err%message
      else if (allocated(err)) then
         call check('run succeeds', .false., err%message)
         call finish('test_integrators')
      end if
   end subroutine run

   real(dp) function state_error(r, rr)
      type(transient_result_t), intent(in) :: r, rr
      state_error = max(maxval(abs(r%u - rr%u)) / maxval(abs(rr%u)), &
                        maxval(abs(r%v - rr%v)) / maxval(abs(rr%v)))
   end function state_error

   !> Each method at N and 2N steps per period against a fine trapezoidal reference.
   subroutine orders_on_a_linear_case()
      type(model_t) :: model
      type(transient_result_t) :: r_ref, r1, r2
      real(dp) :: e1, e2, order, e_tol(2)
      integer :: k
      character(len=300) :: m
      character(len=*), parameter :: methods(6) = [character(len=80) :: &
         "method = 'newmark'", "method = 'newmark', newmark_alpha = 0.1666666666666667", &
         "method = 'hht', hht_alpha = -0.1", "method = 'generalized_alpha', rho_infinity = 0.8", &
         "method = 'central_difference'", "method = 'rk4'"]
      integer, parameter :: n1(6) = [256, 256, 256, 256, 256, 256]
      real(dp), parameter :: want(6) = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 4.0_dp]
      ! reference: RK4 at T/8192 (the trapezoidal rule at such steps is limited by round-off in
      ! a = (u1 - u0)/(alpha dt^2) - ..., about 1e-6 relative)
      call run([character(len=300) :: linear, short, "&solver method = 'rk4', step_control = " &
         // "'fixed', steps_per_period = 8192, locate_events = .false. /"], model, r_ref)
      do k = 1, size(methods)
         m = '&solver ' // trim(methods(k)) // ", step_control = 'fixed', locate_events = " &
            // '.false., steps_per_period = '
         call run([character(len=300) :: linear, short, trim(m) // str(n1(k)) // ' /'], model, r1)
         call run([character(len=300) :: linear, short, trim(m) // str(2 * n1(k)) // ' /'], &
                  model, r2)
         e1 = state_error(r1, r_ref);  e2 = state_error(r2, r_ref)
         order = log(e1 / e2) / log(2.0_dp)
         call note(trim(methods(k)) // ': error ' // str(e1) // ' (T/' // str(n1(k)) // '), ' &
            // str(e2) // ' (T/' // str(2 * n1(k)) // '): order ' // str(order))
         call check_close('order of ' // trim(methods(k)) // ' on the smooth linear case', &
            order, want(k), atol=0.2_dp)
      end do
      ! RK45 meets its tolerance
      do k = 1, 2
         m = "&solver method = 'rk45', step_control = 'embedded', locate_events = .false., " &
            // 'steps_per_period = 64, rk_rtol = ' // str(10.0_dp**(-1 - 3 * k)) // ' /'
         call run([character(len=300) :: linear, short, m], model, r1)
         e_tol(k) = state_error(r1, r_ref)
         call note('rk45 with rtol ' // str(10.0_dp**(-1 - 3 * k)) // ': error ' // str(e_tol(k)) &
            // ' after 2 periods, ' // str(int(r1%steps_accepted)) // ' steps')
      end do
      ! rk_rtol stands in for &solver tolerance on rk45 decks; the estimate is the embedded
      ! fourth-order one while the fifth-order solution is kept, so the error is far below
      call check_le('rk45 with rk_rtol 1e-4 meets its tolerance', e_tol(1), 1.0e-4_dp)
      call check('rk45: a tighter tolerance gives a smaller error', e_tol(2) < 0.1_dp * e_tol(1))
   end subroutine orders_on_a_linear_case

   !> rho_inf of HHT and generalized-alpha at omega dt = 1e4; the trapezoidal rule keeps 1.
   subroutine spectral_radii()
      type(solver_settings_t) :: cfg
      type(error_t), allocatable :: err
      real(dp) :: rho
      cfg%method = 'hht';  cfg%hht_alpha = -0.1_dp
      call spectral_radius(cfg, 1.0e6_dp, rho, err)
      call check_close('HHT alpha = -0.1: spectral radius at omega dt = 1e6 is (1+a)/(1-a)', &
         rho, 0.9_dp / 1.1_dp, rtol=1.0e-3_dp)
      cfg%method = 'generalized_alpha';  cfg%rho_infinity = 0.6_dp
      call spectral_radius(cfg, 1.0e6_dp, rho, err)
      call check_close('generalized-alpha: spectral radius at omega dt = 1e6 is rho_inf = 0.6', &
         rho, 0.6_dp, rtol=1.0e-3_dp)
      cfg%method = 'newmark'
      call spectral_radius(cfg, 1.0e3_dp, rho, err)
      call check_close('trapezoidal: spectral radius 1 at omega dt = 1e3 (bounded, no damping)', &
         rho, 1.0_dp, rtol=1.0e-12_dp)
      cfg%method = 'central_difference'
      call spectral_radius(cfg, 1.999_dp, rho, err)
      call check_le('central difference: stable at omega dt = 1.999', rho, 1.0_dp + 1.0e-12_dp)
      call spectral_radius(cfg, 2.001_dp, rho, err)
      call check('central difference: unstable at omega dt = 2.001', rho > 1.0_dp + 1.0e-6_dp)
      cfg%method = 'rk4'
      call spectral_radius(cfg, 2.0_dp * sqrt(2.0_dp) * 1.001_dp, rho, err)
      call check('RK4: unstable just above omega dt = 2 sqrt(2)', rho > 1.0_dp)
      call spectral_radius(cfg, 2.0_dp * sqrt(2.0_dp) * 0.999_dp, rho, err)
      call check_le('RK4: |R| <= 1 just below omega dt = 2 sqrt(2)', rho, 1.0_dp)
   end subroutine spectral_radii

   !> Largest stable fixed step by bisection with real runs, against theory from omega_max.
   subroutine stable_steps()
      type(model_t) :: model
      type(transient_result_t) :: res
      type(solver_settings_t) :: cfg
      type(error_t), allocatable :: err
      real(dp) :: dt, theory
      integer :: k, ne
      character(len=*), parameter :: names(4) = [character(len=24) :: 'central_difference', &
         'linear acceleration', 'Fox-Goodwin', 'rk4']
      real(dp), parameter :: limit(4) = [2.0_dp, 2.0_dp * sqrt(3.0_dp), sqrt(6.0_dp), &
                                         2.0_dp * sqrt(2.0_dp)]
      do ne = 1, 2
         call run([character(len=300) :: linear, short, '&beam n_elem = ' &
            // str(merge(4, 15, ne == 1)) // ' / &stops node = ' // str(merge(5, 16, ne == 1)) &
            // ' /'], model, res)
         do k = 1, 4
            cfg = solver_settings_t()
            select case (k)
            case (1);  cfg%method = 'central_difference'
            case (2);  cfg%method = 'newmark';  cfg%newmark_alpha = 1.0_dp / 6.0_dp
            case (3);  cfg%method = 'newmark';  cfg%newmark_alpha = 1.0_dp / 12.0_dp
            case (4);  cfg%method = 'rk4'
            end select
            theory = limit(k) / model%omega_max
            call largest_stable_step(model, cfg, 0.5_dp * theory, 3000, 1.0e-4_dp, dt, err)
            if (allocated(err)) then
               call check(trim(names(k)) // ' stable step found', .false., err%message)
               cycle
            end if
            call note(str(merge(4, 15, ne == 1)) // ' elements, ' // trim(names(k)) &
               // ': largest stable step ' // str(dt) // ' s, theory ' // str(limit(k)) &
               // '/omega_max = ' // str(theory) // ' s (ratio ' // str(dt / theory) // ')')
            call check_close(str(merge(4, 15, ne == 1)) // ' elements, ' // trim(names(k)) &
               // ': measured stable step within 2 % of theory', dt, theory, rtol=0.02_dp)
         end do
      end do
   end subroutine stable_steps

   !> Beyond the limit a real run stops with a message naming the method, time and step.
   subroutine divergence_is_reported()
      type(model_t) :: model
      type(transient_result_t) :: res
      logical :: ok
      character(len=:), allocatable :: msg
      call run([character(len=300) :: linear, "&damping model = 'none' /", &
         "&solver method = 'central_difference', " &
         // "step_control = 'fixed', steps_per_period = 90, transient_periods = 0, " &
         // 'record_periods = 20 /'], model, res, ok, msg)
      call check('central difference beyond its limit: the run stops with an error', .not. ok)
      if (.not. ok) then
         call note('message: ' // msg)
         call check('the divergence message names the method, the time and the step', &
            index(msg, 'central_difference') > 0 .and. index(msg, 't =') > 0 .and. &
            index(msg, 'dt =') > 0)
      end if
   end subroutine divergence_is_reported
end program test_integrators
