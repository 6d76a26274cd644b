!> The seams of time integration, tested through their interfaces: an integrator that is not
!> in src/ feeding the recorder, an observer that is not the recorder watching every method of
!> the registry, and the contract of integrator_t (advance lands on the target, contact
!> events are located, a state continues a run).
program test_seams
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_integrator, only: integrator_t, make_integrator, start_state
   use gapbeam_capabilities, only: method_caps_t, method_table
   use gapbeam_test_runs, only: load_or_stop
   use gapbeam_test_seam, only: oscillator_model, closed_form_t, closed_form_integrator_t, &
      seam_observer_t
   implicit none
   character(len=*), parameter :: ref = 'test/decks/moon_shaw_10p5hz_half_element.nml'

   call a_foreign_integrator_feeds_the_recorder()
   call every_method_feeds_an_observer()
   call a_state_continues_a_run()
   call finish('test_seams')

contains

   !> The closed-form integrator of test/gapbeam_test_seam feeds the recorder through
   !> integrate(): the Poincare points and the history are the closed form at their instants;
   !> the exact and Newmark integrators of the registry on the same model agree with it.
   subroutine a_foreign_integrator_feeds_the_recorder()
      type(model_t) :: model
      type(closed_form_integrator_t) :: cf
      type(closed_form_t) :: sol
      type(solver_settings_t) :: cfg
      type(output_settings_t) :: out
      type(transient_result_t) :: r, re, rn
      type(error_t), allocatable :: err
      real(dp) :: omega, x, v, worst, tp, scale
      integer :: k
      omega = 2.0_dp * pi
      model = oscillator_model((1.3_dp * omega)**2, 0.1_dp * 1.3_dp * omega, omega, 1.0e-3_dp)
      sol = closed_form_t(k=model%sys%k(1, 1), c=model%c(1, 1), omega=omega, &
                          half_amplitude=1.0e-3_dp)
      cfg%transient_periods = 5;  cfg%record_periods = 20
      out%samples_per_period = 16;  out%history_periods = 2
      out%poincare_phase_deg = 45.0_dp
      call integrate(model, cfg, out, [2.0e-3_dp], [0.0_dp], r, err, integrator=cf)
      if (allocated(err)) then
         call check('the closed-form integrator runs through integrate()', .false., &
                    err%message);  return
      end if
      call check('the recorder took ' // str(size(r%p_strain)) // ' Poincare points and ' &
         // str(size(r%time)) // ' history samples from the foreign integrator', &
         size(r%p_strain) == 20 .and. size(r%time) == 32)
      worst = 0.0_dp;  scale = maxval(abs(r%p_strain))
      do k = 1, size(r%p_strain)
         tp = (5 + k - 1 + 0.125_dp) * 2.0_dp * pi / omega
         call sol%at(0.0_dp, 2.0e-3_dp, 0.0_dp, tp, x, v)
         worst = max(worst, abs(r%p_strain(k) - x) / scale)
      end do
      call check_le('its Poincare points (phase 45 deg) are the closed form at their instants', &
         worst, 1.0e-12_dp)
      worst = 0.0_dp
      do k = 1, size(r%time)
         call sol%at(0.0_dp, 2.0e-3_dp, 0.0_dp, r%time(k), x, v)
         worst = max(worst, abs(r%tip_displacement(k) - x) / scale)
      end do
      call check_le('its history samples are the closed form at their times', worst, 1.0e-12_dp)
      ! the registry's integrators on the same model and recorder
      cfg%method = 'exact'
      call integrate(model, cfg, out, [2.0e-3_dp], [0.0_dp], re, err)
      if (.not. allocated(err)) then
         call check_le('the exact integrator''s Poincare points against the closed form', &
            maxval(abs(re%p_strain - r%p_strain)) / scale, 1.0e-10_dp)
      else
         call check('exact integrator on the oscillator', .false., err%message)
      end if
      cfg%method = 'newmark';  cfg%step_control = 'error';  cfg%tolerance = 1.0e-6_dp
      call integrate(model, cfg, out, [2.0e-3_dp], [0.0_dp], rn, err)
      if (.not. allocated(err)) then
         call check_le('Newmark (tolerance 1e-6) against the closed form', &
            maxval(abs(rn%p_strain - r%p_strain)) / scale, 1.0e-5_dp)
      else
         call check('Newmark on the oscillator', .false., err%message)
      end if
   end subroutine a_foreign_integrator_feeds_the_recorder

   !> A test observer watches every method of the registry on the reference beam (a zero-gap
   !> stop): the pieces tile the run in time order without gaps, one ends at the watch
   !> instant, every impact starts its piece at the contact (events located), and advance
   !> lands on the target.
   subroutine every_method_feeds_an_observer()
      type(deck_t) :: deck
      type(model_t) :: model
      type(method_caps_t), allocatable :: t(:)
      type(solver_settings_t) :: cfg
      class(integrator_t), allocatable :: integ
      type(seam_observer_t) :: obs
      type(state_t) :: s
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: period, t_end, bound
      integer :: j
      call load_or_stop('test_seams', ref, [character(len=80) :: '&output write_text = ' &
         // '.false. /'], deck, model, u0, v0)
      period = 2.0_dp * pi / model%omega
      t_end = 6.0_dp * period
      t = method_table()
      do j = 1, size(t)
         cfg = deck%solver
         cfg%method = t(j)%name;  cfg%step_control = 'auto';  cfg%stop_solution = 'condensed'
         cfg%steps_per_period = 512
         if (t(j)%stability_limit > 0.0_dp .and. .not. t(j)%implicit) &
            cfg%steps_per_period = 4096
         call make_integrator(model, cfg, integ, err)
         if (allocated(err)) then
            call check(trim(t(j)%name) // ' builds', .false., err%message);  cycle
         end if
         obs = seam_observer_t(model=model)
         obs%t_watch = 2.0_dp * period
         call start_state(model, 0.0_dp, u0, v0, s)
         call integ%advance(s, t_end, obs, err)
         if (allocated(err)) then
            call check(trim(t(j)%name) // ' runs', .false., err%message);  cycle
         end if
         call check(trim(t(j)%name) // ': advance lands on the target and the last piece ends ' &
            // 'there', s%t == t_end .and. abs(obs%t_last - t_end) <= 1.0e-12_dp * t_end)
         call check(trim(t(j)%name) // ': ' // str(obs%pieces) // ' pieces in time order, ' &
            // 'contiguous, one ending at the watch instant', .not. obs%backwards .and. &
            obs%worst_gap <= 1.0e-12_dp * t_end .and. obs%watch_is_boundary)
         ! the implicit methods solve the contact at the event; an explicit step ends where the
         ! step's cubic Hermite interpolant meets the stop: within its accuracy
         bound = 1.0e-6_dp
         if (.not. t(j)%implicit .and. .not. t(j)%exact) bound = max(bound, 10.0_dp * cfg%tolerance)
         call check_le(trim(t(j)%name) // ': ' // str(obs%onsets) // ' impacts, each piece ' &
            // 'starting at its contact: |d(ta)| / largest |d|', obs%worst_onset &
            / max(obs%d_scale, tiny(1.0_dp)), bound)
      end do
   end subroutine every_method_feeds_an_observer

   !> advance(s, 3T) then advance(s, 6T) continues the run: fixed steps give the state of one
   !> advance to 6T bit for bit (the state carries the step memory), the exact integrator to
   !> round-off.
   subroutine a_state_continues_a_run()
      type(deck_t) :: deck
      type(model_t) :: model
      type(solver_settings_t) :: cfg
      class(integrator_t), allocatable :: integ
      type(state_t) :: s1, s2
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: period, d
      integer :: j
      character(len=*), parameter :: methods(3) = [character(len=24) :: 'newmark', 'rk4', &
         'exact']
      call load_or_stop('test_seams', ref, [character(len=80) :: '&output write_text = ' &
         // '.false. /'], deck, model, u0, v0)
      period = 2.0_dp * pi / model%omega
      do j = 1, size(methods)
         cfg = deck%solver
         cfg%method = methods(j);  cfg%step_control = 'fixed';  cfg%steps_per_period = 1024
         call make_integrator(model, cfg, integ, err)
         if (allocated(err)) then
            call check(trim(methods(j)) // ' builds', .false., err%message);  cycle
         end if
         call start_state(model, 0.0_dp, u0, v0, s1)
         s2 = s1
         call integ%advance(s1, 3.0_dp * period, err=err)
         if (.not. allocated(err)) call integ%advance(s1, 6.0_dp * period, err=err)
         if (.not. allocated(err)) call integ%advance(s2, 6.0_dp * period, err=err)
         if (allocated(err)) then
            call check(trim(methods(j)) // ' runs', .false., err%message);  cycle
         end if
         d = max(maxval(abs(s1%u - s2%u)) / maxval(abs(s2%u)), &
                 maxval(abs(s1%v - s2%v)) / maxval(abs(s2%v)))
         call note(trim(methods(j)) // ': advance in two calls against one: ' // str(d))
         if (methods(j) == 'exact') then
            call check_le('exact: a continued state follows the same trajectory (to round-off)', &
               d, 1.0e-11_dp)
         else
            call check(trim(methods(j)) // ': a continued state gives the one-advance state ' &
               // 'bit for bit', d == 0.0_dp)
         end if
      end do
   end subroutine a_state_continues_a_run
end program test_seams
