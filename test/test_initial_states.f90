!> Initial states (&initial, docs/decks.md): the rigid-body fields of kind = 'rotation' and
!> 'translation' against their closed forms (every free dof, both planes, the kinetic energy
!> 1/2 Omega^2 J of the lumped mass), the supports holding their own dofs; kind = 'file'
!> continuing a run (2N periods in one run against N periods and N more from the first run's
!> file, exact integrator, forced: the forcing's phase continued); the refusals (an angle on a
!> clamped root or with a supported tip, a file of another structure or of no transient run,
!> values of another kind, a mechanism that no stop holds).
program test_initial_states
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_jobs, only: run_transient_analysis
   use gapbeam_warnings, only: deck_warnings
   use gapbeam_warning_text, only: warning_length
   use gapbeam_test_runs, only: load_or_stop, expect_refused
   implicit none
   character(len=*), parameter :: deck_path = 'test/decks/initial_rotation.nml'
   character(len=*), parameter :: program_name = 'test_initial_states'

   call rotation_field()
   call rotation_two_planes()
   call translation_field()
   call file_continuation()
   call refusals()
   call free_flight()
   call finish(program_name)

contains

   !> x of node i (the deck's 8 elements on 0.2 m).
   pure real(dp) function x_of(i)
      integer, intent(in) :: i
      x_of = real(i - 1, dp) * 0.2_dp / 8.0_dp
   end function x_of

   !> The field largest difference from w = a + b x, theta = b over the free dofs of plane
   !> rows (j0, j0 + 1).
   real(dp) function field_error(model, x, j0, a, b) result(e)
      type(model_t), intent(in) :: model
      real(dp), intent(in) :: x(:), a, b
      integer, intent(in) :: j0
      integer :: i, g
      e = 0.0_dp
      do i = 1, model%sys%n_node
         g = model%sys%dof_of(j0, i)
         if (g > 0) e = max(e, abs(x(g) - (a + b * x_of(i))))
         g = model%sys%dof_of(j0 + 1, i)
         if (g > 0) e = max(e, abs(x(g) - b))
      end do
   end function field_error

   !> kind = 'rotation': w' = Omega x, theta' = Omega at every free dof (root rotation on its
   !> spring included), the angle likewise, and 1/2 v'Mv = 1/2 Omega^2 J with J the lumped
   !> mass's moment of inertia about the root, summed here from the deck's values.
   subroutine rotation_field()
      type(deck_t) :: deck
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: omega, rho_a, j, energy
      omega = 0.5_dp
      call load_or_stop(program_name, deck_path, [character(len=60) :: &
         '&initial angle = 1.0e-3 /'], deck, model, u0, v0)
      call check('rotation: the root rotation is a dof (spring root)', &
         model%sys%dof_of(2, 1) > 0)
      call check_le("rotation: w' = Omega x, theta' = Omega at every free dof", &
         field_error(model, v0, 1, 0.0_dp, omega), 0.0_dp)
      call check_le('rotation: w = angle x, theta = angle at every free dof', &
         field_error(model, u0, 1, 0.0_dp, 1.0e-3_dp), 0.0_dp)
      rho_a = 7850.0_dp * 7.0857084e-3_dp * 2.6196352e-4_dp
      j = lumped_j()
      energy = 0.5_dp * dot_product(v0, matmul(model%sys%m, v0))
      call check_close('rotation: kinetic energy 1/2 Omega^2 J', energy, &
                       0.5_dp * omega**2 * j, rtol=1.0e-14_dp)
      call note('rotation: J of the 8-element lumped mass / rho A L^3 / 3 of the uniform ' &
         // 'beam = ' // str(j / (rho_a * 0.2_dp**3 / 3.0_dp)))
   end subroutine rotation_field

   !> Two planes: the w and v rates each in their own plane.
   subroutine rotation_two_planes()
      type(deck_t) :: deck
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:)
      call load_or_stop(program_name, deck_path, [character(len=80) :: '&beam planes = 2 /', &
         '&initial angular_velocity = 0.5, angular_velocity_v = -0.25, angle_v = 2.0e-3 /'], &
         deck, model, u0, v0)
      call check_le("two planes: w' = 0.5 x, theta' = 0.5", &
         field_error(model, v0, 1, 0.0_dp, 0.5_dp), 0.0_dp)
      call check_le("two planes: v' = -0.25 x, theta_v' = -0.25", &
         field_error(model, v0, 3, 0.0_dp, -0.25_dp), 0.0_dp)
      call check_le('two planes: u = 0 in w, v = 2e-3 x, theta_v = 2e-3', &
         max(field_error(model, u0, 1, 0.0_dp, 0.0_dp), &
             field_error(model, u0, 3, 0.0_dp, 2.0e-3_dp)), 0.0_dp)
   end subroutine rotation_two_planes

   !> kind = 'translation': w' = V, theta' = 0 at every free dof; a clamped root and a pinned
   !> tip hold their own dofs (the tip's w is not a dof), the others take the field.
   subroutine translation_field()
      type(deck_t) :: deck
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:)
      call load_or_stop(program_name, deck_path, [character(len=90) :: &
         "&initial kind = 'translation', angular_velocity = 0, translation_velocity = 0.3 /", &
         "&root condition = 'clamped' /", "&tip condition = 'pinned' /", &
         "&stops node = 5 /"], deck, model, u0, v0)
      call check('translation: the tip w and the root are not dofs', &
         model%sys%dof_of(1, 9) == 0 .and. model%sys%dof_of(2, 1) == 0)
      call check_le("translation: w' = V, theta' = 0 at every free dof", &
         field_error(model, v0, 1, 0.3_dp, 0.0_dp), 0.0_dp)
      call check_le('translation: u = 0', maxval(abs(u0)), 0.0_dp)
      call check_close('translation: kinetic energy 1/2 V^2 (the masses of the free w dofs)', &
         0.5_dp * dot_product(v0, matmul(model%sys%m, v0)), 0.5_dp * 0.3_dp**2 &
         * 7.0_dp * 7850.0_dp * 7.0857084e-3_dp * 2.6196352e-4_dp * 0.2_dp / 8.0_dp, &
         rtol=1.0e-14_dp)
   end subroutine translation_field

   !> kind = 'file': the transient job over N periods writes its file (its label may extend
   !> the run: the file ends after M periods, /final/time = M T); N more periods started from
   !> that file equal run A over M + N periods (the exact integrator; the forcing continues in
   !> phase: the file ends at a whole number of periods).
   subroutine file_continuation()
      integer, parameter :: n = 5
      character(len=*), parameter :: first = 'test_initial_states_first'
      type(deck_t) :: deck, deck2
      type(model_t) :: model, model2
      type(transient_result_t) :: whole, rest
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), u2(:), v2(:)
      real(dp) :: du, dv
      integer :: m
      character(len=120) :: ov(3)
      ! (the overrides set one by one: gfortran 12 overruns a typed array constructor of
      ! concatenations with a deferred-length function result)
      ov(1) = '&solver record_periods = ' // str(n) // ' /'
      ov(2) = "&job output = '" // first // "' /"
      ov(3) = '&diagnostics certify = .false. /'
      call load_or_stop(program_name, deck_path, ov, deck, model, u0, v0)
      call run_transient_analysis(deck, err)
      if (allocated(err)) then
         call check('file: the first run and its file', .false., err%message);  return
      end if
      ov(2) = "&initial kind = 'file', angular_velocity = 0, initial_file = '" // first &
              // ".h5' /"
      call load_or_stop(program_name, deck_path, ov, deck2, model2, u2, v2)
      m = nint(deck2%initial%file_time * 10.5_dp)
      call check_close('file: the start time read is a whole number of periods (' // str(m) &
                       // ')', deck2%initial%file_time * 10.5_dp, real(m, dp), rtol=1.0e-13_dp)
      call integrate(model2, deck2%solver, deck2%output, u2, v2, rest, err)
      if (allocated(err)) then
         call check('file: the run from the file', .false., err%message);  return
      end if
      deck%solver%record_periods = m + n
      call integrate(model, deck%solver, deck%output, u0, v0, whole, err)
      if (allocated(err)) then
         call check('file: run A over M + N periods', .false., err%message);  return
      end if
      du = maxval(abs(rest%u - whole%u)) / maxval(abs(whole%u))
      dv = maxval(abs(rest%v - whole%v)) / maxval(abs(whole%v))
      call note('file: M + N = ' // str(m) // ' + ' // str(n) // ' periods; largest ' &
         // 'difference of the final state / its largest value: displacement ' // str(du) &
         // ', velocity ' // str(dv))
      call check_le('file: M + N periods in one run = N from the file, displacement', du, &
                    1.0e-9_dp)
      call check_le('file: M + N periods in one run = N from the file, velocity', dv, &
                    1.0e-9_dp)
      call check('file: impacts in the continued run', sum(rest%n_impacts) > 0)
      call expect_refused(deck_path, 'file of another mesh', "&initial kind = 'file', " &
         // "angular_velocity = 0, initial_file = '" // first // ".h5' / &beam n_elem = 16 /", &
         [character(len=40) :: '&initial', 'initial_file', '/parameters/beam/n_elem', &
         '= 8 in the file', '16 in this deck'])
      call expect_refused(deck_path, 'file of another width', "&initial kind = 'file', " &
         // "angular_velocity = 0, initial_file = '" // first // ".h5' / &beam width = 7e-3 /", &
         [character(len=40) :: '/parameters/beam/width', 'in the file', 'in this deck'])
      call expect_refused(deck_path, 'file missing', "&initial kind = 'file', " &
         // "angular_velocity = 0, initial_file = 'no_such_file.h5' /", &
         [character(len=40) :: '&initial', "initial_file = 'no_such_file.h5'", 'does not exist'])
      call expect_refused(deck_path, 'file without a name', "&initial kind = 'file', " &
         // 'angular_velocity = 0 /', [character(len=40) :: "kind = 'file'", 'initial_file'])
      call execute_command_line('rm -f ' // first // '.h5 ' // first // '.history.dat ' &
                                // first // '.poincare.dat')
   end subroutine file_continuation

   !> The moment of inertia about the root of the deck's lumped mass (8 elements, rotary
   !> inertia of the half element; the root rotation a dof), summed from the deck's values:
   !> translational masses rho A le (interior nodes), rho A le / 2 (tip); rotary inertia
   !> (rho A le) le^2 / 24 per element end, 2 n ends, the root's included.
   pure real(dp) function lumped_j() result(j)
      real(dp) :: rho_a, le
      integer :: i
      rho_a = 7850.0_dp * 7.0857084e-3_dp * 2.6196352e-4_dp
      le = 0.2_dp / 8.0_dp
      j = 0.0_dp
      do i = 2, 8
         j = j + rho_a * le * x_of(i)**2
      end do
      j = j + 0.5_dp * rho_a * le * 0.2_dp**2 + 16.0_dp * rho_a * le**3 / 24.0_dp
   end function lumped_j

   !> A mechanism held by a stop (pinned root, free tip, tip stop 5 mm away; undamped, no
   !> forcing), started with a rigid rotation of 0.01 rad/s: accepted with its warning; in
   !> free flight (10 periods of 10.5 Hz, 0.95 s, before the tip meets the stop at 2.5 s)
   !> Newmark keeps the rigid motion w = Omega x t, theta = Omega t exactly (the trapezoidal
   !> rule integrates a motion of zero acceleration exactly; round-off aside); after the tip
   !> meets the stop (40 periods, 3.8 s, fixed steps T/256 with the contact events located)
   !> the energy is still 1/2 Omega^2 J.
   subroutine free_flight()
      type(deck_t) :: deck
      type(model_t) :: model
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), uw(:), vw(:)
      character(len=warning_length), allocatable :: lines(:)
      character(len=100) :: ov(5)
      real(dp) :: omega, t, e0, e1, scale
      integer :: i, g
      omega = 0.01_dp
      ov(1) = "&root condition = 'pinned' /"
      ov(2) = "&damping model = 'none' /"
      ov(3) = '&forcing amplitude_pp = 0 /'
      ov(4) = "&solver method = 'auto', record_periods = 10 /"
      ov(5) = '&initial angular_velocity = 0.01 /'
      call load_or_stop(program_name, deck_path, ov, deck, model, u0, v0)
      call check('mechanism: accepted, the model knows it', model%mechanism)
      call check_close('mechanism: f1 with the stops open is 0', model%f1_open_hz, 0.0_dp, &
                       atol=0.0_dp)
      lines = deck_warnings(deck)
      call check('mechanism: the warning says so', size(lines) >= 1 .and. &
         index(lines(1), 'the beam is a mechanism') > 0 .and. index(lines(1), 'w plane') > 0)
      call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      if (allocated(err)) then
         call check('mechanism: free flight', .false., err%message);  return
      end if
      call check('mechanism: auto runs Newmark (not the exact integrator)', &
         res%method == 'newmark')
      t = res%t_end
      allocate(uw(model%n), vw(model%n))
      do i = 1, model%sys%n_node
         g = model%sys%dof_of(1, i)
         if (g > 0) then
            uw(g) = omega * x_of(i) * t;  vw(g) = omega * x_of(i)
         end if
         g = model%sys%dof_of(2, i)
         if (g > 0) then
            uw(g) = omega * t;  vw(g) = omega
         end if
      end do
      scale = omega * 0.2_dp * t
      call note('mechanism: free flight over ' // str(t) // ' s, largest |u - Omega x t| / ' &
         // '(Omega L t) = ' // str(maxval(abs(res%u - uw)) / scale) // ', |v - Omega x| / ' &
         // '(Omega L) = ' // str(maxval(abs(res%v - vw)) / (omega * 0.2_dp)))
      ! round-off only: K times the rigid field is eps ||K|| ||u|| in floating point, not 0,
      ! and excites the stiff modes at that level (measured 2.0e-11 and 1.1e-10)
      call check_le('mechanism: free flight is the rigid rotation (displacement)', &
                    maxval(abs(res%u - uw)) / scale, 1.0e-10_dp)
      call check_le('mechanism: free flight is the rigid rotation (velocity)', &
                    maxval(abs(res%v - vw)) / (omega * 0.2_dp), 1.0e-9_dp)
      call check('mechanism: no impact before the stop is reached', sum(res%n_impacts) == 0)
      e0 = 0.5_dp * omega**2 * lumped_j()
      call check_close('mechanism: kinetic energy 1/2 Omega^2 J', 0.5_dp * dot_product(res%v, &
                       matmul(model%sys%m, res%v)), e0, rtol=1.0e-10_dp)
      deck%solver%record_periods = 40
      deck%solver%step_control = 'fixed'
      call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      if (allocated(err)) then
         call check('mechanism: meeting the stop', .false., err%message);  return
      end if
      e1 = 0.5_dp * dot_product(res%v, matmul(model%sys%m, res%v)) &
           + 0.5_dp * dot_product(res%u, matmul(model%sys%k, res%u)) + 0.5_dp &
           * sum(model%c_k * max(0.0_dp, model%c_sign * res%u(model%c_dof) - model%c_gap)**2)
      call note('mechanism: after ' // str(sum(res%n_impacts)) // ' impacts in ' &
         // str(res%t_end) // ' s, energy / (1/2 Omega^2 J) - 1 = ' // str(e1 / e0 - 1.0_dp))
      call check('mechanism: the tip met the stop', sum(res%n_impacts) >= 1)
      call check_le('mechanism: energy kept through the impacts (undamped)', &
                    abs(e1 / e0 - 1.0_dp), 1.0e-3_dp)
      call expect_refused(deck_path, 'mechanism with a modal model', "&root condition = " &
         // "'pinned' / &reduction kind = 'auto' /", [character(len=40) :: '&reduction', &
         "kind = 'auto'", 'mechanism', "kind = 'none'"])
      call expect_refused(deck_path, 'mechanism with the stop rule''s ratio', "&root " &
         // "condition = 'pinned' / &stops stiffness = 0, rule_factor = 2, " &
         // 'rule_f1_ratio = 4.375 /', [character(len=40) :: '&stops', 'rule_f1_ratio', &
         'mechanism', 'rule_f1_hz'])
      deck%solver%method = 'exact'
      call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      call check('mechanism: the exact integrator refuses it clearly', allocated(err))
      if (allocated(err)) call check('mechanism: ... naming the mechanism: ' // err%message, &
         index(err%message, 'mechanism') > 0 .and. index(err%message, 'newmark') > 0)
   end subroutine free_flight

   !> The one-line errors (deck, group, variable, value, what is allowed).
   subroutine refusals()
      call expect_refused(deck_path, 'angle on a clamped root', "&root condition = " &
         // "'clamped' / &initial angle = 0.01 /", [character(len=40) :: '&initial', &
         'angle = 1E-002 rad', "condition = 'clamped'", 'allowed: angle = 0'])
      call expect_refused(deck_path, 'angle with a pinned tip', "&tip condition = 'pinned' " &
         // "/ &stops node = 5 / &initial angle = 0.01 /", [character(len=40) :: '&initial', &
         'angle = 1E-002 rad', 'moves the tip by 2E-003 m', "&tip condition = 'pinned'"])
      call expect_refused(deck_path, 'rate of another kind', "&initial kind = " &
         // "'translation', translation_velocity = 1 /", [character(len=40) :: '&initial', &
         'angular_velocity = 0.5', "kind = 'translation'", "needs kind = 'rotation'"])
      call expect_refused(deck_path, 'rotation of nothing', '&initial angular_velocity = 0 /', &
         [character(len=40) :: '&initial', "kind = 'rotation'", 'angular_velocity = angle = 0'])
      call expect_refused(deck_path, 'second plane with one plane', &
         '&initial angular_velocity_v = 1 /', [character(len=40) :: '&initial', &
         'angular_velocity_v = 1', 'planes = 2'])
      call expect_refused(deck_path, 'lists with a rigid field', "&initial node = 3, " &
         // 'velocity = 1 /', [character(len=40) :: '&initial', "kind = 'rotation'", &
         '1 node entries', "kind = 'given'"])
      call expect_refused('test/decks/input_minimal.nml', 'a mechanism no stop holds (no ' &
         // "stop)", "&root condition = 'pinned' /", [character(len=40) :: '&root', &
         "condition = 'pinned'", 'w plane', 'mechanism', 'no stop holds'])
      call expect_refused(deck_path, 'a mechanism no stop holds (v plane)', "&root " &
         // "condition = 'pinned' / &beam planes = 2 /", [character(len=40) :: '&root', &
         "condition = 'pinned'", 'v plane', 'mechanism', 'no stop holds'])
   end subroutine refusals
end program test_initial_states
