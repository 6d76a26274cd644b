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
   use gapbeam_studies, only: stability_series
   use gapbeam_test_runs, only: run_deck, load_deck
   use gapbeam_state, only: state_t
   use gapbeam_integrator, only: integrator_t, method_registry_t, method_registry, &
      make_integrator, start_state
   use gapbeam_stepping, only: stepping_integrator_t
   use gapbeam_capabilities, only: method_table, method_caps_t, method_word_list, method_caps
   use gapbeam_settings, only: method_words
   use gapbeam_test_method, only: rk43_stepper_t, rk43_caps
   use gapbeam_capability_text, only: capability_markdown
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
   call registry_is_the_one_place()
   call capability_tables_documented()
   call a_method_from_the_tests()
   call explicit_methods_need_mass()
   call stability_needs_methods()
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

   !> The method registry: the reader's words are its words, every family has its
   !> implementation, each method's stepper runs, and the controller's order is the entry's.
   subroutine registry_is_the_one_place()
      type(method_registry_t) :: reg
      type(method_caps_t), allocatable :: t(:)
      integer :: j, n_one_step
      reg = method_registry()
      t = method_table()
      call check('method_words (the reader''s list) = the registry''s: ' // method_word_list(), &
         method_words == method_word_list())
      n_one_step = 0
      do j = 1, size(reg%entries)
         if (allocated(reg%entries(j)%proto)) n_one_step = n_one_step + 1
      end do
      call check('every method but the exact one has a stepper in the registry (' &
         // str(n_one_step) // ' of ' // str(size(t)) // ')', n_one_step == size(t) - 1 &
         .and. size(reg%entries) == size(t))
      call check("rk45's controller order is 4 and Newmark's 2 (from the table)", &
         controller_order('rk45') == 4 .and. controller_order('newmark') == 2 .and. &
         controller_order('hht') == 2)
   end subroutine registry_is_the_one_place

   !> docs/methods.md carries the capability tables generated from the registries, verbatim
   !> between its two markers; on a difference the current tables go to
   !> test_integrators.capabilities.md.
   subroutine capability_tables_documented()
      character(len=*), parameter :: doc = 'docs/methods.md', &
         first = '<!-- capability tables: generated from the registries, do not edit by hand -->', &
         last = '<!-- end of the capability tables -->', out = 'test_integrators.capabilities.md'
      character(len=:), allocatable :: text, want, got
      integer :: u, i1, i2, ios
      logical :: same
      want = capability_markdown()
      open(newunit=u, file=doc, access='stream', form='unformatted', status='old', iostat=ios)
      if (ios /= 0) then
         call check('read ' // doc, .false.);  return
      end if
      allocate(character(len=0) :: text)
      block
         integer(8) :: n
         inquire(unit=u, size=n)
         deallocate(text);  allocate(character(len=n) :: text)
         read(u, iostat=ios) text
      end block
      close(u)
      i1 = index(text, first);  i2 = index(text, last)
      same = .false.
      got = ''
      if (i1 > 0 .and. i2 > i1) then
         got = text(i1 + len(first) + 1:i2 - 1)
         same = got == want
      end if
      call check('docs/methods.md carries the capability tables of the registries', same, &
         'document ' // str(len(got)) // ' bytes, registry ' // str(len(want)) // ' bytes')
      if (same) then
         open(newunit=u, file=out, status='old', iostat=ios)
         if (ios == 0) close(u, status='delete')
      else
         open(newunit=u, file=out, status='replace', action='write', iostat=ios)
         if (ios == 0) then
            write(u, '(a)') want(:len(want) - 1)
            close(u)
            call note('the current tables are in ' // out)
         end if
      end if
   end subroutine capability_tables_documented

   !> The order the stepping integrator's controller uses for method `name` (-1: none).
   integer function controller_order(name, reg) result(q)
      character(len=*), intent(in) :: name
      type(method_registry_t), intent(in), optional :: reg
      type(model_t) :: model
      type(transient_result_t) :: res
      type(solver_settings_t) :: cfg
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      q = -1
      call run([character(len=300) :: linear, short], model, res)
      cfg%method = name;  cfg%step_control = 'error'
      call make_integrator(model, cfg, integ, err, reg)
      if (allocated(err)) return
      select type (integ)
      type is (stepping_integrator_t)
         q = integ%order
      end select
   end function controller_order

   !> A method that is not built in (test/gapbeam_test_method: RK4 with an embedded
   !> third-order estimate): one `add` to a registry value and make_integrator dispatches to
   !> it, its fixed steps converge with its order, its error controller works with its order
   !> (steps grow as tol^(-1/4) for a local error estimate of order 4 in h), and it is refused
   !> where its capabilities say; nothing in src/ or app/ names it.
   subroutine a_method_from_the_tests()
      type(method_registry_t) :: reg
      type(model_t) :: model
      type(transient_result_t) :: r_ref, r1, r2
      type(solver_settings_t) :: cfg
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(deck_t) :: deck
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: e1, e2, order, steps(2), growth
      integer :: k, status
      reg = method_registry()
      call reg%add(rk43_caps(), rk43_stepper_t())          ! the one registry line
      ! dispatched: the registry builds the stepping integrator around the test's stepper
      call run([character(len=300) :: linear, short], model, r_ref)
      cfg = solver_settings_t();  cfg%method = 'rk43_test';  cfg%step_control = 'fixed'
      call make_integrator(model, cfg, integ, err, reg)
      call check('make_integrator dispatches to the test''s method', .not. allocated(err))
      if (allocated(err)) return
      call check("its integrator is the stepping one with method 'rk43_test'", &
         integ%method == 'rk43_test' .and. same_type_as(integ, stepping_integrator_t()))
      ! its own formulas: fixed steps converge with order 4 on the smooth linear case
      call run([character(len=300) :: linear, short, "&solver method = 'rk4', step_control = " &
         // "'fixed', steps_per_period = 8192, locate_events = .false. /"], model, r_ref)
      cfg = solver_settings_t();  cfg%method = 'rk43_test';  cfg%step_control = 'fixed'
      cfg%locate_events = .false.;  cfg%transient_periods = 0;  cfg%record_periods = 2
      cfg%steps_per_period = 256
      call final_state(model, cfg, reg, r1)
      cfg%steps_per_period = 512
      call final_state(model, cfg, reg, r2)
      e1 = state_error(r1, r_ref);  e2 = state_error(r2, r_ref)
      order = log(e1 / e2) / log(2.0_dp)
      call check_close('the test method''s fixed steps converge with order 4 (observed ' &
         // str(order) // ')', order, 4.0_dp, atol=0.3_dp)
      ! its controller's order: 3 (the registry entry), neither Newmark's 2 nor rk45's 4
      call check('the stepping integrator controls it with its own order 3', &
         controller_order('rk43_test', reg) == 3)
      ! steps against the tolerance: the local error estimate is O(h^4), so the step count
      ! grows by 10^(1/3) = 2.15 per decade of tolerance (error per unit time ~ h^3)
      cfg%step_control = 'error';  cfg%locate_events = .true.
      do k = 1, 2
         cfg%tolerance = 10.0_dp**(-3 - 2 * k)
         call final_state(model, cfg, reg, r1)
         steps(k) = real(r1%steps_accepted, dp)
      end do
      growth = sqrt(steps(2) / steps(1))
      call note('test method under error control: ' // str(int(steps(1))) // ' steps at ' &
         // 'tolerance 1e-5, ' // str(int(steps(2))) // ' at 1e-7: ' // str(growth) &
         // ' per decade')
      call check('its steps grow by about 10^(1/3) per decade of tolerance (' &
         // str(growth) // ')', growth > 1.9_dp .and. growth < 2.5_dp)
      ! refused where its capabilities say: dofs without mass, a ring support
      call load_deck('test/decks/sdof_impact.nml', [character(len=80) :: "&solver method = " &
         // "'auto' /"], deck, model, u0, v0, err)
      if (allocated(err)) then
         call check('load sdof_impact', .false., err%message);  return
      end if
      cfg = deck%solver;  cfg%method = 'rk43_test';  cfg%step_control = 'auto'
      call make_integrator(model, cfg, integ, err, reg)
      call check('refused on dofs without mass, naming the method and why', allocated(err))
      if (allocated(err)) call check('... ' // err%message, index(err%message, 'rk43_test') &
         > 0 .and. index(err%message, 'explicit methods need a mass at every dof') > 0)
      call load_deck('test/decks/tube_cantilever.nml', [character(len=80) :: &
         '&output write_text = .false. /'], deck, model, &
                     u0, v0, err)
      if (allocated(err)) then
         call check('load tube_cantilever', .false., err%message);  return
      end if
      cfg = deck%solver;  cfg%method = 'rk43_test';  cfg%step_control = 'auto'
      call make_integrator(model, cfg, integ, err, reg)
      call check('refused on a ring support (its entry: rings = .false.)', allocated(err))
      if (allocated(err)) call check('... ' // err%message, index(err%message, 'rk43_test') &
         > 0 .and. index(err%message, 'circular clearance') > 0)
      ! nothing else was edited: src/ and app/ do not name it
      call execute_command_line("grep -rqi 'rk43' src app", exitstat=status)
      call check('no source file in src/ or app/ names the test method (grep exit ' &
         // str(status) // ')', status == 1)
   end subroutine a_method_from_the_tests

   !> Run cfg with a registry's method from the deck's rest state to the end of the horizon.
   subroutine final_state(model, cfg, reg, res)
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      type(method_registry_t), intent(in) :: reg
      type(transient_result_t), intent(out) :: res
      class(integrator_t), allocatable :: integ
      type(state_t) :: s
      type(error_t), allocatable :: err
      call make_integrator(model, cfg, integ, err, reg)
      if (.not. allocated(err)) then
         call start_state(model, 0.0_dp, spread(0.0_dp, 1, model%n), &
                          spread(0.0_dp, 1, model%n), s)
         call integ%advance(s, real(cfg%transient_periods + cfg%record_periods, dp) * 2.0_dp &
                            * pi / model%omega, err=err)
      end if
      if (allocated(err)) then
         call check('run ' // trim(cfg%method), .false., err%message)
         return
      end if
      res%u = s%u;  res%v = s%v
      res%steps_accepted = integ%steps_accepted
   end subroutine final_state

   !> Explicit methods refuse a model with massless dofs before they start (central
   !> differences used to run and report a divergence).
   subroutine explicit_methods_need_mass()
      type(model_t) :: model
      type(transient_result_t) :: res
      logical :: ok
      character(len=:), allocatable :: msg
      integer :: k
      character(len=*), parameter :: m(3) = [character(len=20) :: 'central_difference', &
         'rk4', 'rk45']
      do k = 1, 3
         call run([character(len=300) :: short, "&beam rotary_inertia = 'none' /", &
            "&solver method = '" // trim(m(k)) // "' /"], model, res, ok, msg)
         call check(trim(m(k)) // " with rotary_inertia = 'none' is refused", .not. ok)
         if (.not. ok) call check('... naming the method and the reason: ' // msg, &
            index(msg, trim(m(k))) > 0 .and. &
            index(msg, 'explicit methods need a mass at every dof') > 0 .and. &
            index(msg, 'diverged') == 0)
      end do
   end subroutine explicit_methods_need_mass

   !> analysis = 'stability' on the default series (which start with 'auto') is refused with
   !> one line naming &study series and the value (it stopped with an internal message); an
   !> exact method is left out as before.
   subroutine stability_needs_methods()
      character(len=32), allocatable :: methods(:)
      type(error_t), allocatable :: err
      call stability_series([character(len=32) :: 'auto', 'newmark_error', 'exact'], methods, &
                            err)
      call check("stability with series 'auto' is refused", allocated(err))
      if (allocated(err)) call check('... naming the group, variable and value: ' &
         // err%message, index(err%message, 'group &study') > 0 .and. index(err%message, &
         "series(1) = 'auto'") > 0)
      call stability_series([character(len=32) :: 'newmark_fixed', 'exact', 'hht_error'], &
                            methods, err)
      call check("the series of one-step methods are charted, 'exact' left out", &
         .not. allocated(err) .and. size(methods) == 2)
   end subroutine stability_needs_methods
end program test_integrators
