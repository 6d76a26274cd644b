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
      certificate_disputed
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_attractor, only: diagnose
   use gapbeam_certify, only: certify_point, contradiction
   use gapbeam_periodic, only: orbit_map_t, newton_orbit, floquet_multipliers
   use gapbeam_transition, only: reduce_state
   implicit none
   character(len=*), parameter :: tube = 'test/decks/tube_planar.nml'
   character(len=*), parameter :: chaos = 'inputs/moon_shaw_9p8hz.nml'
   !> the tube's exponent to 1 % or over 600 periods
   character(len=*), parameter :: tight = &
      '&diagnostics lyapunov_rel_error = 0.01, lyapunov_max_periods = 600 /'

   call auto_exponent_is_the_exact_one_and_the_floquet_one()
   call modal_model_gives_the_same_exponent()
   call chaotic_exponent_within_its_errors()
   call contradictions_are_disputed()
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
   end subroutine contradictions_are_disputed
end program test_exponents
