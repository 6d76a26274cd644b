!> Exponents that mean what they say: the exponent of a deck whose method 'auto' is the exact
!> integrator is the exact integrator's (not the default method's at fixed steps); it equals
!> the one the periodic orbit's Floquet multipliers give (the exact monodromy, saltations
!> included); a modal model reaching the same orbit gives the same exponent; a chaotic set
!> gives one exponent within the stated errors in physical and modal coordinates; and a label
!> that contradicts its own exponent is disputed.
program test_exponents
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_test_runs, only: load_or_stop
   use gapbeam_results, only: transient_result_t, point_result_t, label_text, label_chaotic, &
      certificate_disputed, dispute_kind, dispute_contradiction
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_attractor, only: diagnose
   use gapbeam_certify, only: certify_point, contradiction
   use gapbeam_periodic, only: orbit_map_t, newton_orbit, floquet_multipliers
   use gapbeam_transition, only: reduce_state
   implicit none
   character(len=*), parameter :: tube = 'test/decks/tube_planar.nml'
   character(len=*), parameter :: chaos = 'inputs/moon_shaw_9p8hz.nml'
   !> a mass held by friction on a ring support (stuck, or stick-slip with a larger forcing)
   character(len=*), parameter :: ring = 'test/decks/stick_ring.nml'
   character(len=*), parameter :: slip = '&forcing amplitude_pp = 0.1013211836 /'
   !> the tube's exponent to 1 % or over 600 periods
   character(len=*), parameter :: tight = &
      '&diagnostics lyapunov_rel_error = 0.01, lyapunov_max_periods = 600 /'

   call auto_exponent_is_the_exact_one_and_the_floquet_one()
   call modal_model_gives_the_same_exponent()
   call chaotic_exponent_within_its_errors()
   call contradictions_are_disputed()
   call stuck_ring_gives_the_least_damped_rate()
   call stick_slip_exponent_converges()
   call finish('test_exponents')

contains

   !> Diagnose a deck's own point (no certificate); stop if the run fails.
   subroutine run(path, overrides, pr, model)
      character(len=*), intent(in) :: path, overrides(:)
      type(point_result_t), intent(out) :: pr
      type(model_t), intent(out), optional :: model
      type(deck_t) :: deck
      type(model_t) :: m
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      call load_or_stop('test_exponents', path, overrides, deck, m, u0, v0)
      call diagnose(m, deck%solver, deck%output, deck%diagnostics, u0, v0, res, pr, err)
      if (allocated(err)) then
         call check('run ' // path, .false., err%message)
         call finish('test_exponents')
      end if
      if (present(model)) model = m
   end subroutine run

   !> The exponent of a period-p orbit from its largest Floquet multiplier, ln|mu| / (p T),
   !> the orbit converged by Newton shooting from (u, v) with the exact monodromy.
   real(dp) function floquet_exponent(model, p, u, v) result(lambda)
      type(model_t), intent(in) :: model
      integer, intent(in) :: p
      real(dp), intent(in) :: u(:), v(:)
      type(orbit_map_t) :: map
      type(solver_settings_t) :: cfg
      type(error_t), allocatable :: err
      real(dp), allocatable :: x(:), jac(:, :)
      complex(dp), allocatable :: mu(:)
      cfg%method = 'exact'
      lambda = huge(1.0_dp)
      call map%setup(model, cfg, p, 0.0_dp, .true., 1.0e-6_dp, err)
      if (.not. allocated(err)) then
         x = reduce_state(map%lp, u, v)
         allocate(jac(size(x), size(x)))
         call newton_orbit(map, x, 1.0e-12_dp, 8, jac, err)
      end if
      if (.not. allocated(err)) call floquet_multipliers(jac, mu, err)
      if (allocated(err)) then
         call check('Floquet multipliers', .false., err%message)
         return
      end if
      lambda = log(maxval(abs(mu))) / (p * 2.0_dp * pi / model%omega)
   end function floquet_exponent

   !> On the planar tube (method 'auto', which is the exact integrator) the exponent is the
   !> one method 'exact' gives, bit for bit, and the one of the orbit's largest multiplier
   !> within 3 sigma (its sigma stated, not zero).
   subroutine auto_exponent_is_the_exact_one_and_the_floquet_one()
      type(point_result_t) :: auto, exact
      type(model_t) :: model
      real(dp) :: lam_f
      call run(tube, [character(len=80) :: tight], auto, model)
      call run(tube, [character(len=80) :: tight, "&solver method = 'exact' /"], exact)
      call check('planar tube: period 1 (auto: ' // label_text(auto%label) // ')', auto%label == 1)
      call check("planar tube: the exponent of method 'auto' is the exact integrator's, bit for " &
         // 'bit (' // str(auto%lyapunov) // ' and ' // str(exact%lyapunov) // ' 1/s)', &
         auto%lyapunov == exact%lyapunov .and. auto%lyapunov_error == exact%lyapunov_error)
      lam_f = floquet_exponent(model, max(1, auto%period), auto%u_end, auto%v_end)
      call note('planar tube 9 Hz: lambda ' // str(auto%lyapunov) // ' +- ' &
         // str(auto%lyapunov_error) // ' 1/s over ' // str(auto%lyapunov_periods) &
         // ' periods; Floquet ' // str(lam_f) // ' 1/s')
      call check('planar tube: the stated error is positive', auto%lyapunov_error > 0.0_dp)
      call check_le('planar tube: |lambda - Floquet exponent| <= 3 sigma', &
         abs(auto%lyapunov - lam_f), 3.0_dp * auto%lyapunov_error)
   end subroutine auto_exponent_is_the_exact_one_and_the_floquet_one

   !> A modal model (16 of 24 modes and the static correction of the stop dofs) reaches the same
   !> period-1 orbit and gives the full model's exponent within their combined errors and the
   !> exponent of its own Floquet multipliers within 3 sigma.
   subroutine modal_model_gives_the_same_exponent()
      type(point_result_t) :: full, red
      type(model_t) :: model
      real(dp) :: bound, lam_f
      call run(tube, [character(len=80) :: tight], full)
      call run(tube, [character(len=80) :: tight, "&reduction kind = 'modal', n_modes = 16 /"], &
               red, model)
      call note('planar tube 9 Hz, 16 modes: lambda ' // str(red%lyapunov) // ' +- ' &
         // str(red%lyapunov_error) // ' 1/s; full ' // str(full%lyapunov) // ' +- ' &
         // str(full%lyapunov_error))
      call check('modal model: the same period (' // label_text(red%label) // ')', &
         red%label == full%label)
      bound = 3.0_dp * sqrt(full%lyapunov_error**2 + red%lyapunov_error**2)
      call check_le('modal model: |lambda_modal - lambda_full| <= 3 combined sigma', &
         abs(red%lyapunov - full%lyapunov), bound)
      lam_f = floquet_exponent(model, max(1, red%period), red%u_end, red%v_end)
      call check_le('modal model: |lambda - its Floquet exponent| <= 3 sigma', &
         abs(red%lyapunov - lam_f), 3.0_dp * red%lyapunov_error)
   end subroutine modal_model_gives_the_same_exponent

   !> The chaotic 9.8 Hz deck and the same model in modal coordinates (all 4 modes with mass, the
   !> coordinates changed so that the stop dof is one of them): both chaotic, with exponents
   !> within 3 combined sigma (the trajectories part after a few periods, so this compares
   !> two samples of one chaotic set, the norm and weights of the modal coordinates included).
   subroutine chaotic_exponent_within_its_errors()
      type(point_result_t) :: full, red
      real(dp) :: bound
      call run(chaos, [character(len=60) :: '&solver record_periods = 500 /'], full)
      call run(chaos, [character(len=60) :: '&solver record_periods = 500 /', &
                      "&reduction kind = 'modal', n_modes = 4 /"], red)
      call note('9.8 Hz: full ' // label_text(full%label) // ', lambda ' // str(full%lyapunov) &
         // ' +- ' // str(full%lyapunov_error) // ' 1/s over ' // str(full%lyapunov_periods) &
         // ' periods; modal (all 4 modes) ' // label_text(red%label) // ', ' // str(red%lyapunov) &
         // ' +- ' // str(red%lyapunov_error) // ' over ' // str(red%lyapunov_periods))
      call check('9.8 Hz: chaotic in physical and in modal coordinates', &
         full%label == label_chaotic .and. red%label == label_chaotic)
      bound = 3.0_dp * sqrt(full%lyapunov_error**2 + red%lyapunov_error**2)
      call check_le('9.8 Hz: |lambda_modal - lambda_full| <= 3 combined sigma', &
         abs(red%lyapunov - full%lyapunov), bound)
   end subroutine chaotic_exponent_within_its_errors

   !> A period beside a clearly positive exponent, or chaos beside a detected period, is a
   !> contradiction; the certificate of such a point is disputed with that reason even when
   !> both checks agree with its label.
   subroutine contradictions_are_disputed()
      type(point_result_t) :: pr
      type(deck_t) :: deck
      type(model_t) :: model
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      pr%label = 3;  pr%period = 3;  pr%lyapunov = 2.4_dp;  pr%lyapunov_error = 0.2_dp
      pr%lyapunov_periods = 100
      call load_or_stop('test_exponents', tube, &
         [character(len=60) :: '&solver method = ''exact'' /'], &
                        deck, model, u0, v0)
      call check('period 3 beside lambda = 2.4 +- 0.2 is a contradiction', &
         len(contradiction(pr, deck%diagnostics)) > 0, contradiction(pr, deck%diagnostics))
      pr%lyapunov = 0.5_dp
      call check('period 3 beside lambda = 0.5 +- 0.2 (2.5 sigma) is none', &
         len(contradiction(pr, deck%diagnostics)) == 0)
      pr%label = label_chaotic
      call check('chaotic beside a detected period 3 is a contradiction', &
         len(contradiction(pr, deck%diagnostics)) > 0)
      pr%period = 0
      call check('chaotic without a period is none', len(contradiction(pr, deck%diagnostics)) == 0)
      ! a real point whose evidence is made contradictory: certified checks, disputed point
      pr = point_result_t()
      call diagnose(model, deck%solver, deck%output, deck%diagnostics, u0, v0, res, pr, err)
      if (allocated(err)) then
         call check('diagnose the tube', .false., err%message)
         return
      end if
      pr%lyapunov = abs(pr%lyapunov) + 10.0_dp * pr%lyapunov_error + 1.0_dp
      call certify_point(model, deck%solver, deck%output, deck%diagnostics, u0, v0, 1, pr)
      call check('a period beside a positive exponent: disputed even though the perturbed ' &
         // 'start agrees (' // pr%certificate_reason // ')', &
         pr%certificate == certificate_disputed .and. pr%perturbed_label == pr%label .and. &
         index(pr%certificate_reason, 'contradicts') > 0)
      call check('... and the charts mark it as a contradiction (dispute code 1)', &
         dispute_kind(pr%certificate, pr%certificate_reason) == dispute_contradiction)
   end subroutine contradictions_are_disputed
   !> A support that sticks for ever (test/decks/stick_ring.nml: mu N = 1 N against a base
   !> force of 0.4 N) leaves a linear structure, the mass held by the stick spring and the
   !> contact spring. Its damping is C = 2 M (mass-proportional), so every underdamped mode
   !> decays at exactly -C/(2M) = -1 1/s whatever the stiffnesses (its eigenvalues are
   !> -1 +- i omega_d; the w mode adds the contact damper: -1 - 20/(2 x 1.00005) = -11 1/s):
   !> the largest exponent is -1 1/s. The perturbed trajectory must keep the stick anchor of
   !> the period before (rebuilt from (u, v) the stick spring would lose its stretch every
   !> period). Newmark's trapezoidal steps under error control change the decay rate by
   !> O((omega h)^2): the exponent converges to -1 as the tolerance falls (measured, release:
   !> -0.8675 at 1e-4, -0.9904 at 1e-5, -0.99885 at 1e-6, each +- 1.3e-3 .. 1.7e-4).
   subroutine stuck_ring_gives_the_least_damped_rate()
      type(point_result_t) :: p4, p5
      real(dp) :: e4, e5
      call run(ring, [character(len=80) :: '&solver tolerance = 1.0e-4 /'], p4)
      call run(ring, [character(len=80) :: '&solver tolerance = 1.0e-5 /'], p5)
      e4 = abs(p4%lyapunov + 1.0_dp);  e5 = abs(p5%lyapunov + 1.0_dp)
      call note('stuck ring: lambda ' // str(p4%lyapunov) // ' +- ' // str(p4%lyapunov_error) &
         // ' (tolerance 1e-4), ' // str(p5%lyapunov) // ' +- ' // str(p5%lyapunov_error) &
         // ' 1/s (1e-5); closed form -1 1/s')
      call check('stuck ring: the support sticks all the time (no sliding)', &
                 p5%sliding_distance(1) == 0.0_dp)
      call check('stuck ring: an exponent with a stated error over ' &
         // str(p5%lyapunov_periods) // ' periods', p5%lyapunov_periods > 0 .and. &
         p5%lyapunov_error > 0.0_dp)
      call check_le('stuck ring: |lambda + 1| at tolerance 1e-5 (the trapezoidal steps'' ' &
         // 'error, 0.0096 measured)', e5, 0.015_dp)
      call check_le('stuck ring: the error falls at least 5 x from tolerance 1e-4 to 1e-5', &
         5.0_dp * e5, e4)
   end subroutine stuck_ring_gives_the_least_damped_rate

   !> The same mass forced at 2 m/s^2 (twice mu N / m) sticks and slips twice a period: the
   !> trajectories' regimes, slip directions and anchors switch at their own located events
   !> (the stick anchor is set where each slider stops). Its exponent (a stable orbit) is
   !> negative beyond 3 sigma, and the same within 3 combined sigma at a 10 x tighter
   !> tolerance (measured, release: -2.7647 +- 0.0009 at 1e-3, -2.7635 +- 0.0009 at 1e-4,
   !> -2.7633 +- 0.0009 1/s at 1e-5).
   subroutine stick_slip_exponent_converges()
      type(point_result_t) :: p3, p4
      real(dp) :: bound
      call run(ring, [character(len=80) :: slip, '&solver tolerance = 1.0e-3 /'], p3)
      call run(ring, [character(len=80) :: slip, '&solver tolerance = 1.0e-4 /'], p4)
      call note('stick-slip: lambda ' // str(p3%lyapunov) // ' +- ' // str(p3%lyapunov_error) &
         // ' (tolerance 1e-3), ' // str(p4%lyapunov) // ' +- ' // str(p4%lyapunov_error) &
         // ' 1/s (1e-4); sliding ' // str(p4%sliding_distance(1)) // ' m in the record')
      call check('stick-slip: the support slides', p4%sliding_distance(1) > 0.0_dp)
      call check('stick-slip: negative beyond 3 sigma', &
                 p4%lyapunov + 3.0_dp * p4%lyapunov_error < 0.0_dp)
      bound = 3.0_dp * sqrt(p3%lyapunov_error**2 + p4%lyapunov_error**2)
      call check_le('stick-slip: |lambda(1e-3) - lambda(1e-4)| <= 3 combined sigma', &
                    abs(p3%lyapunov - p4%lyapunov), bound)
   end subroutine stick_slip_exponent_converges
end program test_exponents
