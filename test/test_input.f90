!> The namelist deck reader: values land in their fields, defaults stay, overrides apply in
!> order, quotes and comments do not confuse the group detection, and bad decks are rejected
!> with a message naming the deck, the group, the variable and the value.
!>
!> Valid decks are test/decks/input_*.nml; each bad deck is written to test_input_tmp.nml,
!> read and deleted.
program test_input
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_settings, only: job_t, calibrate_t, analysis_words
   use gapbeam_input, only: read_deck
   use gapbeam_description, only: beam_t, root_t, dof_w, dof_theta
   use gapbeam_description, only: stop_side_words, stop_law_words
   use gapbeam_description, only: damping_t, rayleigh_from_ratios, damping_words
   use gapbeam_description, only: forcing_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t, stop_solution_words, &
      initial_state_words
   use gapbeam_description, only: rotary_inertia_words
   use gapbeam_settings, only: calibration_words
   implicit none
   character(len=*), parameter :: full = 'test/decks/input_full.nml'
   character(len=*), parameter :: minimal = 'test/decks/input_minimal.nml'
   character(len=*), parameter :: quotes = 'test/decks/input_quotes.nml'
   character(len=*), parameter :: tmp = 'test_input_tmp.nml'
   character(len=*), parameter :: nl = new_line('a')
   ! a valid deck: bad decks below add to it or replace a line of it
   character(len=*), parameter :: job = "&job analysis = 'modes' /" // nl
   character(len=*), parameter :: beam = "&beam length = 0.2, n_elem = 4, " &
      // "youngs_modulus = 200.0e9, density = 7850.0, width = 0.01, thickness = 5.0e-4 /" // nl
   character(len=*), parameter :: base = job // beam
   character(len=80), parameter :: no_overrides(0) = [character(len=80) ::]

   call full_deck()
   call minimal_deck()
   call overrides()
   call quotes_and_comments()
   call bad_decks()
   call bad_overrides()
   call docs_tables()
   call strict_text()
   call extreme_values()
   call long_initial_list()
   call design_variables()
   call remove(tmp)
   call check('temporary deck removed', .not. exists(tmp))
   call finish('test_input')

contains

   !> Every group of input_full.nml lands in its fields; unset variables keep the defaults.
   subroutine full_deck()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      type(solver_settings_t) :: sd
      type(output_settings_t) :: od
      type(beam_t) :: bd
      real(dp) :: beta, gamma
      call read_deck(full, no_overrides, deck, err)
      call check('input_full.nml is read', .not. allocated(err), message(err))
      if (allocated(err)) return
      call check('deck%path is the path given', deck%path == full)
      ! &job
      call check("&job analysis = 'transient'", deck%job%analysis == 'transient')
      call check("&job title", deck%job%title == 'input test: full deck')
      call check("&job output defaults to 'results/<deck stem>'", &
         deck%job%output == 'results/input_full', trim(deck%job%output))
      ! &beam
      call check_close('&beam length', deck%structure%beam%length, 0.25_dp, rtol=1.0e-15_dp)
      call check('&beam n_elem = 5', deck%structure%beam%n_elem == 5)
      call check_close('&beam youngs_modulus', deck%structure%beam%youngs_modulus, 190.0e9_dp, &
         rtol=1.0e-15_dp)
      call check_close('&beam density', deck%structure%beam%density, 7800.0_dp, rtol=1.0e-15_dp)
      call check_close('&beam width', deck%structure%beam%width, 0.012_dp, rtol=1.0e-15_dp)
      call check_close('&beam thickness', deck%structure%beam%thickness, 6.0e-4_dp, &
         rtol=1.0e-15_dp)
      call check("&beam mass_matrix = 'consistent'", &
         deck%structure%beam%mass_matrix == 'consistent')
      call check("&beam rotary_inertia = 'hrz'", deck%structure%beam%rotary_inertia == 'hrz')
      call check('&beam unset area, second_moment, fibre_distance keep the defaults (0)', &
         deck%structure%beam%area == 0.0_dp .and. deck%structure%beam%second_moment == 0.0_dp &
         .and. deck%structure%beam%fibre_distance == 0.0_dp .and. bd%area == 0.0_dp &
         .and. bd%second_moment == 0.0_dp .and. bd%fibre_distance == 0.0_dp)
      ! &root
      call check("&root condition = 'spring'", deck%structure%root%condition == 'spring')
      call check_close('&root k_theta', deck%structure%root%k_theta, 0.5_dp, rtol=1.0e-15_dp)
      ! &springs: two entries
      call check('&springs has 2 entries', size(deck%structure%springs) == 2)
      if (size(deck%structure%springs) == 2) then
         call check('&springs(1): node 3, w', deck%structure%springs(1)%node == 3 &
            .and. deck%structure%springs(1)%dof == dof_w)
         call check('&springs(2): node 6, theta', deck%structure%springs(2)%node == 6 &
            .and. deck%structure%springs(2)%dof == dof_theta)
         call check_close('&springs stiffness(1)', deck%structure%springs(1)%stiffness, &
            120.0_dp, rtol=1.0e-15_dp)
         call check_close('&springs stiffness(2)', deck%structure%springs(2)%stiffness, &
            0.75_dp, rtol=1.0e-15_dp)
      end if
      ! &masses
      call check('&masses has 2 entries', size(deck%structure%masses) == 2)
      if (size(deck%structure%masses) == 2) then
         call check('&masses nodes 6, 4', deck%structure%masses(1)%node == 6 &
            .and. deck%structure%masses(2)%node == 4)
         call check_close('&masses mass(2)', deck%structure%masses(2)%mass, 0.02_dp, &
            rtol=1.0e-15_dp)
         call check_close('&masses inertia(1)', deck%structure%masses(1)%inertia, 2.0e-7_dp, &
            rtol=1.0e-15_dp)
         call check('&masses unset inertia(2) = 0', deck%structure%masses(2)%inertia == 0.0_dp)
      end if
      ! &modes, &calibrate
      call check('&modes n_print = 3', deck%n_print_modes == 3)
      call check("&calibrate parameter = 'spring', index = 2", &
         deck%calibrate%parameter == 'spring' .and. deck%calibrate%index == 2)
      call check_close('&calibrate target_f1_hz', deck%calibrate%target_f1_hz, 6.5_dp, &
         rtol=1.0e-15_dp)
      ! &stops
      call check('&stops has 2 entries', size(deck%stops) == 2)
      if (size(deck%stops) == 2) then
         call check("&stops(1): node 6, w, side 'both', bilinear", deck%stops(1)%node == 6 &
            .and. deck%stops(1)%dof == dof_w .and. deck%stops(1)%side == 'both' &
            .and. deck%stops(1)%law == 'bilinear')
         call check_close('&stops gap(1)', deck%stops(1)%gap, 1.0e-3_dp, rtol=1.0e-15_dp)
         call check_close('&stops stiffness(1)', deck%stops(1)%stiffness, 500.0_dp, &
            rtol=1.0e-15_dp)
         call check_close('&stops damping(1)', deck%stops(1)%damping, 0.2_dp, rtol=1.0e-15_dp)
         call check("&stops(2): node 4, side 'negative', hertz, exponent 2", &
            deck%stops(2)%node == 4 .and. deck%stops(2)%side == 'negative' &
            .and. deck%stops(2)%law == 'hertz' .and. near(deck%stops(2)%exponent, 2.0_dp))
         call check_close('&stops stiffness(2)', deck%stops(2)%stiffness, 1.0e8_dp, &
            rtol=1.0e-15_dp)
         call check('&stops unset damping(2) = 0, rule_factor = 0', &
            deck%stops(2)%damping == 0.0_dp .and. deck%stops(1)%rule_factor == 0.0_dp)
         call check_close('&stops unset exponent(1) keeps the default 1.5', &
            deck%stops(1)%exponent, 1.5_dp, rtol=1.0e-15_dp)
      end if
      ! &damping 'ratios': coefficients from rayleigh_from_ratios
      call rayleigh_from_ratios(4.0_dp, 0.01_dp, 40.0_dp, 0.02_dp, beta, gamma)
      call check("&damping model = 'ratios'", deck%damping%model == 'ratios')
      call check_close('&damping ratios: mass coefficient = rayleigh_from_ratios', &
         deck%damping%mass_coefficient, beta, rtol=1.0e-14_dp)
      call check_close('&damping ratios: stiffness coefficient = rayleigh_from_ratios', &
         deck%damping%stiffness_coefficient, gamma, rtol=1.0e-14_dp)
      call check('&damping ratios: both coefficients > 0', beta > 0.0_dp .and. gamma > 0.0_dp)
      call check_close('&damping frequency2_hz kept', deck%damping%frequency2_hz, 40.0_dp, &
         rtol=1.0e-15_dp)
      ! &forcing
      call check_close('&forcing frequency_hz', deck%forcing%frequency_hz, 10.2_dp, &
         rtol=1.0e-15_dp)
      call check_close('&forcing amplitude_pp', deck%forcing%amplitude_pp, 3.5e-3_dp, &
         rtol=1.0e-15_dp)
      ! &solver: given values, and the defaults of the others
      call check("&solver stop_solution = 'fixed_point', step_control = 'fixed', " &
         // "linear_solver = 'banded'", deck%solver%stop_solution == 'fixed_point' &
         .and. deck%solver%step_control == 'fixed' .and. deck%solver%linear_solver == 'banded')
      call check_close('&solver fp_tolerance', deck%solver%fp_tolerance, 1.0e-8_dp, &
         rtol=1.0e-15_dp)
      call check('&solver steps_per_period = 512, max_halvings = 12', &
         deck%solver%steps_per_period == 512 .and. deck%solver%max_halvings == 12)
      call check('&solver locate_events = .false.', .not. deck%solver%locate_events)
      call check('&solver transient_periods = 10, record_periods = 20', &
         deck%solver%transient_periods == 10 .and. deck%solver%record_periods == 20)
      call check('&solver unset variables keep the solver_settings_t defaults', &
         deck%solver%method == sd%method .and. near(deck%solver%newmark_delta, sd%newmark_delta) &
         .and. near(deck%solver%newmark_alpha, sd%newmark_alpha) &
         .and. deck%solver%fp_max_iterations == sd%fp_max_iterations &
         .and. near(deck%solver%half_step_tolerance, sd%half_step_tolerance) &
         .and. near(deck%solver%residual_floor, sd%residual_floor) &
         .and. deck%solver%grow_after == sd%grow_after &
         .and. near(deck%solver%grow_ratio, sd%grow_ratio))
      ! &initial
      call check("&initial kind = 'given' with 2 entries", deck%initial%kind == 'given' &
         .and. size(deck%initial%node) == 2)
      if (size(deck%initial%node) == 2) then
         call check('&initial nodes 6 (w), 5 (theta)', all(deck%initial%node == [6, 5]) &
            .and. all(deck%initial%dof == [dof_w, dof_theta]))
         call check_close('&initial displacement(2)', deck%initial%displacement(2), 0.01_dp, &
            rtol=1.0e-15_dp)
         call check_close('&initial velocity(1)', deck%initial%velocity(1), -0.05_dp, &
            rtol=1.0e-15_dp)
         call check('&initial unset velocity(2) = 0', deck%initial%velocity(2) == 0.0_dp)
      end if
      ! &output
      call check_close('&output poincare_phase_deg', deck%output%poincare_phase_deg, 90.0_dp, &
         rtol=1.0e-15_dp)
      call check('&output samples_per_period = 32, write_text = .false.', &
         deck%output%samples_per_period == 32 .and. .not. deck%output%write_text)
      call check('&output unset history_periods keeps the default', &
         deck%output%history_periods == od%history_periods)
      ! effective text
      call check('deck%text is the file text (no overrides)', deck%text == file_text(full))
   end subroutine full_deck

   !> &job and &beam only: every other group takes the type defaults.
   subroutine minimal_deck()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      type(solver_settings_t) :: sd
      type(output_settings_t) :: od
      type(damping_t) :: dd
      type(forcing_t) :: fd
      type(root_t) :: rd
      type(beam_t) :: bd
      type(calibrate_t) :: cd
      type(job_t) :: jd
      call read_deck(minimal, no_overrides, deck, err)
      call check('input_minimal.nml is read', .not. allocated(err), message(err))
      if (allocated(err)) return
      call check("minimal: output prefix 'results/input_minimal'", &
         deck%job%output == 'results/input_minimal', trim(deck%job%output))
      call check('minimal: &job title keeps its default', deck%job%title == jd%title)
      call check('minimal: unset &beam variables keep the beam_t defaults', &
         deck%structure%beam%mass_matrix == bd%mass_matrix &
         .and. deck%structure%beam%rotary_inertia == bd%rotary_inertia &
         .and. deck%structure%beam%area == 0.0_dp .and. bd%area == 0.0_dp)
      call check('minimal: &root is the root_t default', &
         deck%structure%root%condition == rd%condition &
         .and. deck%structure%root%k_theta == 0.0_dp .and. rd%k_theta == 0.0_dp)
      call check('minimal: no springs, masses or stops', size(deck%structure%springs) == 0 &
         .and. size(deck%structure%masses) == 0 .and. size(deck%stops) == 0)
      call check('minimal: &modes n_print = 0', deck%n_print_modes == 0)
      call check('minimal: &calibrate is the calibrate_t default', &
         deck%calibrate%parameter == cd%parameter .and. deck%calibrate%index == cd%index &
         .and. deck%calibrate%target_f1_hz == 0.0_dp)
      call check('minimal: &damping is the damping_t default', same_damping(deck%damping, dd))
      call check('minimal: &forcing is the forcing_t default', &
         near(deck%forcing%frequency_hz, fd%frequency_hz) &
         .and. deck%forcing%amplitude_pp == 0.0_dp)
      call check('minimal: &solver is the solver_settings_t default', &
         same_solver(deck%solver, sd))
      call check('minimal: &output is the output_settings_t default', &
         near(deck%output%poincare_phase_deg, od%poincare_phase_deg) &
         .and. deck%output%samples_per_period == od%samples_per_period &
         .and. deck%output%history_periods == od%history_periods &
         .and. (deck%output%write_text .eqv. od%write_text))
      call check("minimal: &initial kind = 'rest', no entries", deck%initial%kind == 'rest' &
         .and. size(deck%initial%node) == 0)
   end subroutine minimal_deck

   !> Overrides apply after the file, in order; they can add groups; the text records them.
   subroutine overrides()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      character(len=80) :: ov(4)
      character(len=:), allocatable :: text
      integer :: i
      ov(1) = '&forcing frequency_hz = 7.5 /'
      ov(2) = '&beam n_elem = 6 /'
      ov(3) = '&solver steps_per_period = 128 /'
      ov(4) = '&FORCING Frequency_Hz = 9.25, amplitude_pp = 1.0e-3 /'
      call read_deck(minimal, ov, deck, err)
      call check('minimal deck with 4 overrides is read', .not. allocated(err), message(err))
      if (allocated(err)) return
      call check('override replaces a file value (n_elem 4 -> 6)', &
         deck%structure%beam%n_elem == 6)
      call check_close('override leaves the other file values (length)', &
         deck%structure%beam%length, 0.2_dp, rtol=1.0e-15_dp)
      call check_close('two overrides of frequency_hz: the last wins', &
         deck%forcing%frequency_hz, 9.25_dp, rtol=1.0e-15_dp)
      call check_close('override adds &forcing, absent from the file', &
         deck%forcing%amplitude_pp, 1.0e-3_dp, rtol=1.0e-15_dp)
      call check('override adds &solver: steps_per_period = 128', &
         deck%solver%steps_per_period == 128)
      text = file_text(minimal)
      call check('deck%text starts with the file text', index(deck%text, text) == 1)
      do i = 1, size(ov)
         call check('deck%text holds override ' // str(i), &
            index(deck%text, trim(ov(i))) > len(text))
      end do
      call check('deck%text holds the overrides in order', &
         index(deck%text, trim(ov(1))) < index(deck%text, trim(ov(2))) &
         .and. index(deck%text, trim(ov(2))) < index(deck%text, trim(ov(3))) &
         .and. index(deck%text, trim(ov(3))) < index(deck%text, trim(ov(4))))
      ! an override on a group the file has, not touching the given variables
      ov(1) = "&job title = 'override title' /"
      call read_deck(minimal, ov(1:1), deck, err)
      call check("override of &job title keeps the file's analysis", .not. allocated(err) &
         .and. deck%job%title == 'override title' .and. deck%job%analysis == 'modes', &
         message(err))
      ! a later override on a variable the file sets to a bad value repairs it
      call write_deck(tmp, job // replace(beam, 'n_elem = 4', 'n_elem = 0'))
      ov(1) = '&beam n_elem = 2 /'
      call read_deck(tmp, ov(1:1), deck, err)
      call check('validation runs after the overrides (file n_elem = 0, override 2)', &
         .not. allocated(err) .and. deck%structure%beam%n_elem == 2, message(err))
      ! a list given whole in an override replaces the file's list whole; an element
      ! assignment (stiffness(2) = ...) changes that element only
      call write_deck(tmp, base // '&stops node = 3, 5, stiffness = 1.0, 2.0 /')
      ov(1) = '&stops node = 4 /'
      call read_deck(tmp, ov(1:1), deck, err)
      call check('override node = 4 replaces the list node = 3, 5', .not. allocated(err), &
         message(err))
      if (.not. allocated(err)) call check('... one stop, at node 4, stiffness 1', &
         size(deck%stops) == 1 .and. deck%stops(1)%node == 4 &
         .and. near(deck%stops(1)%stiffness, 1.0_dp))
      ov(1) = '&stops stiffness(2) = 7.0 /'
      call read_deck(tmp, ov(1:1), deck, err)
      call check('override stiffness(2) = 7 keeps the list node = 3, 5', .not. allocated(err) &
         .and. size(deck%stops) == 2, message(err))
      if (.not. allocated(err)) call check('... stiffness (1, 7)', size(deck%stops) == 2 &
         .and. near(deck%stops(1)%stiffness, 1.0_dp) .and. near(deck%stops(2)%stiffness, 7.0_dp))
      call remove(tmp)
   end subroutine overrides

   !> Quoted '/' and '&' and comments do not open or close groups.
   subroutine quotes_and_comments()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      type(forcing_t) :: fd
      call read_deck(quotes, no_overrides, deck, err)
      call check('input_quotes.nml is read', .not. allocated(err), message(err))
      if (allocated(err)) return
      call check("quoted title 'x / y' read whole", deck%job%title == 'x / y', &
         trim(deck%job%title))
      call check("quoted output 'out/a&b' read whole (and not replaced by the default)", &
         deck%job%output == 'out/a&b', trim(deck%job%output))
      call check('&beam after the quotes is found: n_elem = 3, consistent', &
         deck%structure%beam%n_elem == 3 .and. deck%structure%beam%mass_matrix == 'consistent')
      call check_close('&beam length after a comment', deck%structure%beam%length, 0.3_dp, &
         rtol=1.0e-15_dp)
      call check_close('&root after the quotes is found: k_theta = 1.5', &
         deck%structure%root%k_theta, 1.5_dp, rtol=1.0e-15_dp)
      call check('groups named only in comments are not read (no &forcing, &springs)', &
         size(deck%structure%springs) == 0 .and. near(deck%forcing%frequency_hz, &
         fd%frequency_hz))
      ! a quoted string holding '&<group name>' followed by a blank
      call write_deck(tmp, "&job analysis = 'modes', title = 'clamped &beam / no stop' /" // nl &
         // replace(beam, 'n_elem = 4', 'n_elem = 7'))
      call read_deck(tmp, no_overrides, deck, err)
      call check("title 'clamped &beam / no stop' does not hide the &beam group", &
         .not. allocated(err), message(err))
      if (.not. allocated(err)) call check('... and &beam is read from its own line', &
         deck%structure%beam%n_elem == 7 .and. deck%job%title == 'clamped &beam / no stop')
      ! ... and a quoted '&<group name> /' must not stand in for that group
      call write_deck(tmp, "&job analysis = 'transient', title = 'run &forcing / test' /" // nl &
         // beam // '&forcing frequency_hz = 7.0 /')
      call read_deck(tmp, no_overrides, deck, err)
      call check("title 'run &forcing / test' does not replace &forcing (7 Hz read)", &
         .not. allocated(err) .and. near(deck%forcing%frequency_hz, 7.0_dp), &
         'frequency_hz = ' // str(deck%forcing%frequency_hz) // '; ' // message(err))
      ! DOS line ends
      call write_deck(tmp, "&job analysis = 'modes' /" // achar(13) // nl &
         // beam(1:len(beam) - 1) // achar(13) // nl &
         // "&root condition = 'spring', k_theta = 2.0 /" // achar(13) // nl)
      call read_deck(tmp, no_overrides, deck, err)
      call check('a deck with DOS line ends is read', .not. allocated(err) &
         .and. deck%structure%root%condition == 'spring', message(err))
      ! two groups in one override
      call read_deck(minimal, [character(len=80) :: "&output history_periods = 5 / " &
         // "&forcing amplitude_pp = 2.0e-3 /"], deck, err)
      call check('one override may hold two groups', .not. allocated(err) &
         .and. deck%output%history_periods == 5, message(err))
      if (.not. allocated(err)) call check_close('... both are applied', &
         deck%forcing%amplitude_pp, 2.0e-3_dp, rtol=1.0e-15_dp)
   end subroutine quotes_and_comments

   !> Bad decks: each must fail with a message naming the deck and holding the fragments.
   subroutine bad_decks()
      character(len=*), parameter :: bad_ratios = "&damping model = 'ratios', " &
         // "frequency1_hz = 1.0, ratio1 = 0.1, frequency2_hz = 10.0, ratio2 = 0.001 /"
      character(len=*), parameter :: bad_ratios2 = "&damping model = 'ratios', " &
         // "frequency1_hz = 1.0, ratio1 = 0.001, frequency2_hz = 10.0, ratio2 = 0.5 /"
      real(dp) :: beta, gamma
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      ! misspelled variables
      call expect_error('misspelled variable in &beam', job // replace(beam, 'length', &
         'lenght'), [character(len=60) :: '&beam', 'unknown variable lenght', 'lenght = 0.2'])
      call expect_error('misspelled variable in &solver', base &
         // '&solver step_per_period = 100 /', &
         [character(len=60) :: '&solver', 'step_per_period', 'steps_per_period'])
      ! unknown group, missing &beam, group twice
      call expect_error('unknown group', base // '&stop node = 5, stiffness = 100.0 /', &
         [character(len=60) :: 'unknown group &stop', 'allowed groups', '&stops'])
      call expect_error('missing &beam', job // "&root condition = 'clamped' /", &
         [character(len=60) :: 'required group &beam is missing'])
      call expect_error('missing &job', beam, &
         [character(len=60) :: 'required group &job is missing'])
      call expect_error('a group given twice in the file', base // '&beam n_elem = 6 /', &
         [character(len=60) :: 'group &beam appears more than once'])
      ! values of the wrong type
      call expect_error("wrong type: n_elem = 'four'", job // replace(beam, 'n_elem = 4', &
         "n_elem = 'four'"), [character(len=60) :: '&beam', "n_elem = 'four'", &
         'cannot read the value of n_elem'])
      call expect_error('wrong type: length = abc', job // replace(beam, 'length = 0.2', &
         'length = abc'), [character(len=60) :: '&beam', 'length = abc', &
         'cannot read the value of length'])
      call expect_error('wrong type: steps_per_period = 2.5', base &
         // '&solver steps_per_period = 2.5 /', [character(len=60) :: '&solver', &
         'steps_per_period = 2.5', 'cannot read the value of steps_per_period'])
      ! a logical given as a number: gfortran's namelist read fails with 'Bad repeat count',
      ! and the read after that one returns iostat 0 without reading anything
      call expect_error('wrong type: write_text = 12', base // '&output write_text = 12 /', &
         [character(len=60) :: '&output', 'write_text = 12', &
         'cannot read the value of write_text'])
      call expect_error('wrong type: locate_events = 1 (after a first item)', base &
         // '&solver steps_per_period = 64, locate_events = 1 /', [character(len=60) :: &
         '&solver', 'locate_events = 1', 'cannot read the value of locate_events'])
      call read_deck(full, no_overrides, deck, err)
      call check('a valid deck read after a bad logical is read whole', &
         .not. allocated(err) .and. deck%job%analysis == 'transient' &
         .and. deck%structure%beam%n_elem == 5, 'analysis = ' // trim(deck%job%analysis) &
         // '; ' // message(err))
      ! negative and zero values
      call expect_error('negative length', job // replace(beam, 'length = 0.2', &
         'length = -0.2'), [character(len=60) :: '&beam', 'length = -0.2', 'must be > 0'])
      call expect_error('zero n_elem', job // replace(beam, 'n_elem = 4', 'n_elem = 0'), &
         [character(len=60) :: '&beam', 'n_elem = 0', 'must be in 1..10000'])
      call expect_error('length = NaN', job // replace(beam, 'length = 0.2', 'length = NaN'), &
         [character(len=60) :: '&beam', 'length = NaN', 'must be > 0 and finite'])
      call expect_error('youngs_modulus = Infinity', job // replace(beam, '200.0e9', &
         'Infinity'), [character(len=60) :: '&beam', 'youngs_modulus = Infinity', &
         'must be > 0 and finite'])
      call expect_error('zero thickness', job // replace(beam, 'thickness = 5.0e-4', &
         'thickness = 0.0'), [character(len=60) :: '&beam', 'thickness = 0', 'must be > 0'])
      call expect_error('zero forcing frequency', base // '&forcing frequency_hz = 0.0 /', &
         [character(len=60) :: '&forcing', 'frequency_hz = 0', 'must be > 0'])
      call expect_error('negative stop gap', base &
         // '&stops node = 5, gap = -0.5, stiffness = 100.0 /', &
         [character(len=60) :: '&stops', 'gap(1) = -0.5', 'must be >= 0 and <= 1.3407808E+154'])
      call expect_error('zero stop stiffness without the rule', base // '&stops node = 5 /', &
         [character(len=60) :: '&stops', 'stiffness(1) = 0', 'must be > 0'])
      call expect_error('stop stiffness rule without a target', base &
         // '&stops node = 5, rule_factor = 2.0 /', &
         [character(len=60) :: '&stops', 'rule_factor(1) = 2', 'rule_f1_ratio(1) > 1', &
         'rule_f1_hz(1) > 0'])
      call expect_error('stop stiffness rule with rule_f1_ratio = NaN', base &
         // '&stops node = 5, rule_factor = 2.0, rule_f1_ratio = NaN /', &
         [character(len=60) :: '&stops', 'rule_f1_ratio(1) = NaN'])
      call expect_error("initial kind = 'given' without entries", base &
         // "&initial kind = 'given' /", [character(len=60) :: '&initial', "kind = 'given'"])
      call expect_error('negative spring stiffness(2)', base &
         // '&springs node = 3, 5, stiffness = 10.0, -3.0 /', &
         [character(len=60) :: '&springs', 'stiffness(2) = -3', 'must be > 0'])
      call expect_error('negative point mass', base // '&masses node = 5, mass = -1.0 /', &
         [character(len=60) :: '&masses', 'mass(1) = -1', 'must be >= 0'])
      call expect_error('zero samples_per_period', base &
         // '&output samples_per_period = 0 /', &
         [character(len=60) :: '&output', 'samples_per_period = 0'])
      call expect_error('newmark_delta below 1/2', base // '&solver newmark_delta = 0.4 /', &
         [character(len=60) :: '&solver', 'newmark_delta = 0.4', 'must be in [0.5, 1]'])
      call expect_error("root spring with k_theta = 0", base // "&root condition = 'spring' /", &
         [character(len=60) :: '&root', 'k_theta = 0', 'must be > 0'])
      ! nodes outside the mesh (4 elements: nodes 1..5)
      call expect_error('spring node outside the mesh', base &
         // '&springs node = 9, stiffness = 10.0 /', &
         [character(len=60) :: '&springs', 'node(1) = 9', 'must be in 1..5'])
      call expect_error('mass node 0', base // '&masses node = 0, mass = 1.0 /', &
         [character(len=60) :: '&masses', 'node(1) = 0', '1..5'])
      call expect_error('stop node outside the mesh', base &
         // '&stops node = 6, stiffness = 100.0 /', &
         [character(len=60) :: '&stops', 'node(1) = 6', '1..5'])
      call expect_error('initial node outside the mesh', base &
         // "&initial kind = 'given', node = 7, displacement = 1.0e-3 /", &
         [character(len=60) :: '&initial', 'node(1) = 7', '1..5'])
      call expect_error('list entry without a node (node(2) given only)', base &
         // '&springs node(2) = 3, stiffness = 10.0, 10.0 /', &
         [character(len=60) :: '&springs', 'node(1) is not given', 'node(2) is'])
      ! -1 is a value like any other, not "not given"
      call expect_error('stop at node -1', base // '&stops node = -1 /', &
         [character(len=60) :: '&stops', 'node(1) = -1', '1..5'])
      call expect_error('stop list ending in -1', base &
         // '&stops node = 5, -1, stiffness = 1.0 /', &
         [character(len=60) :: '&stops', 'node(2) = -1', '1..5'])
      call expect_error('mass at node -1', base // '&masses node = -1, mass = 1.0 /', &
         [character(len=60) :: '&masses', 'node(1) = -1'])
      call expect_error('spring at node -1', base // '&springs node = -1, stiffness = 1.0 /', &
         [character(len=60) :: '&springs', 'node(1) = -1'])
      ! entries beyond the node list would be ignored silently
      call expect_error('mass list longer than node', base &
         // '&masses node = 3, mass = 1.0, 2.0 /', &
         [character(len=60) :: '&masses', 'mass has an entry beyond the 1', 'node'])
      call expect_error('spring list ending in -1 beyond node', base &
         // '&springs node = 3, stiffness = 10.0, -1 /', &
         [character(len=60) :: '&springs', 'stiffness has an entry beyond the 1'])
      call expect_error('spring dof beyond node', base &
         // "&springs node = 3, dof = 'w', 'theta', stiffness = 10.0 /", &
         [character(len=60) :: '&springs', 'dof has an entry beyond the 1'])
      call expect_error('point-force amplitude beyond node', base &
         // '&point_forces node = 3, amplitude = 0.5, 0.5 /', &
         [character(len=60) :: '&point_forces', 'amplitude has an entry beyond the 1'])
      call expect_ok('mass list as long as node', base &
         // '&masses node = 3, 4, mass = 1.0, 2.0, inertia = 0.0 /')
      ! empty (null) values would keep the defaults silently
      call expect_error('empty value n_elem = ,', job // replace(beam, 'n_elem = 4', &
         'n_elem = '), [character(len=60) :: '&beam', 'no value for n_elem'])
      call expect_error('empty list entry node = 5, , 3', base // '&stops node = 5, , 3 /', &
         [character(len=60) :: '&stops', 'no value for node'])
      ! over-long character values are refused, naming the variable and its length
      call expect_error('title of 300 characters', "&job analysis = 'modes', title = '" &
         // repeat('t', 300) // "' /" // nl // beam, &
         [character(len=60) :: '&job', 'title is 300 characters long', 'at most 256'])
      call expect_error("mass_matrix = 'consistent      junk'", job // replace(beam, '/', &
         ", mass_matrix = 'consistent      junk' /"), [character(len=60) :: '&beam', &
         'mass_matrix is 20 characters long', 'at most 16'])
      ! a group without its closing '/'
      call expect_error('group not closed', base // '&forcing frequency_hz = 5.0', &
         [character(len=60) :: '&forcing', 'not closed'])
      ! old-Mac line ends (CR only) read like LF
      call expect_ok('CR-only line ends', "! comment" // achar(13) // "&job analysis = " &
         // "'modes' /" // achar(13) // replace(beam, nl, achar(13)))
      ! sizes, counted in 64 bits before anything is allocated
      call expect_error('sweep 65536 x 65536 points', "&job analysis = 'sweep' /" // nl // beam &
         // '&forcing frequency_hz = 5.0 /' // nl // '&sweep n_frequency = 65536, ' &
         // 'frequency_start_hz = 1.0, frequency_end_hz = 2.0, n_amplitude = 65536, ' &
         // 'amplitude_start_pp = 1.0e-3, amplitude_end_pp = 2.0e-3 /', &
         [character(len=60) :: '&sweep', 'n_frequency', '4294967296 points'])
      call expect_error('sweep n_frequency = 100000000', "&job analysis = 'sweep' /" // nl // beam &
         // '&forcing frequency_hz = 5.0 /' // nl // '&sweep n_frequency = 100000000, ' &
         // 'frequency_start_hz = 1.0, frequency_end_hz = 2.0 /', &
         [character(len=60) :: '&sweep', 'n_frequency = 100000000', 'must be in 0..1000000'])
      call expect_error('transient_periods = 2^31 - 1 (no wrap of the period counts)', base &
         // '&solver transient_periods = 2147483647, record_periods = 2147483647 /', &
         [character(len=60) :: '&solver', 'transient_periods = 2147483647', &
         'must be in 0..100000000'])
      call expect_error('the periods a run may integrate, counted in 64 bits', base &
         // '&solver transient_periods = 100000000, record_periods = 100000000 /', &
         [character(len=60) :: '&solver', 'a run may integrate up to', 'at most 2000000000'])
      call expect_error('thickness = 1e308 (EI overflows)', job // replace(beam, &
         'thickness = 5.0e-4', 'thickness = 1.0e308'), [character(len=60) :: '&beam', &
         'thickness', 'EI = Infinity'])
      ! the root: translation fixed, rotation fixed when clamped
      call expect_error("spring at node 1, dof 'w'", base &
         // "&springs node = 1, dof = 'w', stiffness = 10.0 /", &
         [character(len=60) :: '&springs', 'node(1) = 1', "dof 'w'", &
         'root translation is fixed'])
      call expect_error("stop at node 1, dof 'theta', clamped root", base &
         // "&stops node = 1, dof = 'theta', stiffness = 1.0 /", &
         [character(len=60) :: '&stops', 'node(1) = 1', "dof 'theta'", 'clamped'])
      call expect_error("initial value at node 1, dof 'w'", base &
         // "&initial kind = 'given', node = 1, dof = 'w', displacement = 1.0e-3 /", &
         [character(len=60) :: '&initial', 'node(1) = 1', 'root translation is fixed'])
      call expect_ok("stop at node 1, dof 'theta' with a root spring is accepted", base &
         // "&root condition = 'spring', k_theta = 1.0 /" // nl &
         // "&stops node = 1, dof = 'theta', stiffness = 1.0 /")
      ! unknown choice words: the message lists the allowed words
      call expect_error("mass_matrix = 'lumpy'", job // replace(beam, '/', &
         ", mass_matrix = 'lumpy' /"), [character(len=60) :: '&beam', &
         "mass_matrix = 'lumpy'", "allowed: 'lumped', 'consistent'"])
      call expect_error("rotary_inertia = 'full'", job // replace(beam, '/', &
         ", rotary_inertia = 'full' /"), [character(len=60) :: '&beam', &
         "rotary_inertia = 'full'", rotary_inertia_words])
      call expect_error("analysis = 'static'", "&job analysis = 'static' /" // nl // beam, &
         [character(len=60) :: '&job', "analysis = 'static'", analysis_words])
      call expect_error("root condition = 'hinged'", base // "&root condition = 'hinged' /", &
         [character(len=60) :: '&root', "condition = 'hinged'", "'clamped', 'spring', 'pinned'"])
      call expect_error("springs dof = 'x'", base &
         // "&springs node = 3, dof = 'x', stiffness = 1.0 /", &
         [character(len=60) :: '&springs', "dof(1) = 'x'", "'w', 'theta'"])
      call expect_error("stops side = 'up'", base &
         // "&stops node = 5, side = 'up', stiffness = 1.0 /", &
         [character(len=60) :: '&stops', "side(1) = 'up'", stop_side_words])
      call expect_error("stops law = 'linear'", base &
         // "&stops node = 5, law = 'linear', stiffness = 1.0 /", &
         [character(len=60) :: '&stops', "law(1) = 'linear'", stop_law_words])
      call expect_error("damping model = 'viscous'", base // "&damping model = 'viscous' /", &
         [character(len=60) :: '&damping', "model = 'viscous'", damping_words])
      call expect_error("stop_solution = 'newton'", base &
         // "&solver stop_solution = 'newton' /", &
         [character(len=60) :: '&solver', "stop_solution = 'newton'", stop_solution_words])
      call expect_error("initial kind = 'random'", base // "&initial kind = 'random' /", &
         [character(len=60) :: '&initial', "kind = 'random'", initial_state_words])
      call expect_error("calibrate parameter = 'length'", base &
         // "&calibrate parameter = 'length', target_f1_hz = 5.0 /", &
         [character(len=60) :: '&calibrate', "parameter = 'length'", calibration_words])
      ! &damping ratios giving a negative coefficient
      call rayleigh_from_ratios(1.0_dp, 0.1_dp, 10.0_dp, 0.001_dp, beta, gamma)
      call check('the first bad ratio pair gives gamma < 0', gamma < 0.0_dp)
      call expect_error('&damping ratios with a negative stiffness coefficient', &
         base // bad_ratios, [character(len=60) :: '&damping', 'ratios (0.1 at 1 Hz', &
         'negative Rayleigh coefficient'])
      call rayleigh_from_ratios(1.0_dp, 0.001_dp, 10.0_dp, 0.5_dp, beta, gamma)
      call check('the second bad ratio pair gives beta < 0', beta < 0.0_dp)
      call expect_error('&damping ratios with a negative mass coefficient', &
         base // bad_ratios2, [character(len=60) :: '&damping', 'ratio', &
         'negative Rayleigh coefficient'])
      call expect_error('&damping ratios with frequency2 <= frequency1', base &
         // "&damping model = 'ratios', frequency1_hz = 10.0, ratio1 = 0.01, " &
         // "frequency2_hz = 5.0, ratio2 = 0.01 /", &
         [character(len=60) :: '&damping', 'frequency2_hz = 5', 'frequency1_hz = 10'])
      ! Hertz with a damper
      call expect_error('Hertz stop with a damper', base &
         // "&stops node = 5, law = 'hertz', stiffness = 1.0e9, damping = 5.0 /", &
         [character(len=60) :: '&stops', 'damping(1) = 5', "law='bilinear'"])
      call expect_error('Hertz exponent outside [1, 10]', base &
         // "&stops node = 5, law = 'hertz', stiffness = 1.0e9, exponent = 0.5 /", &
         [character(len=60) :: '&stops', 'exponent(1) = 0.5', 'must be in [1, 10]'])
      ! &calibrate target missing for analysis='calibrate'
      call expect_error("analysis='calibrate' without target_f1_hz", &
         "&job analysis = 'calibrate' /" // nl // beam // "&calibrate parameter = 'width' /", &
         [character(len=60) :: '&calibrate', 'target_f1_hz = 0', "analysis='calibrate'"])
      call expect_error("analysis='calibrate' without &calibrate", &
         "&job analysis = 'calibrate' /" // nl // beam, &
         [character(len=60) :: '&calibrate', 'target_f1_hz'])
      call expect_error("calibrate 'root_k_theta' with a clamped root", base &
         // "&calibrate parameter = 'root_k_theta', target_f1_hz = 5.0 /", &
         [character(len=60) :: '&calibrate', "'root_k_theta'", "condition='spring'"])
      call expect_error("calibrate 'spring' index beyond &springs", base &
         // "&springs node = 5, stiffness = 10.0 /" // nl &
         // "&calibrate parameter = 'spring', index = 2, target_f1_hz = 5.0 /", &
         [character(len=60) :: '&calibrate', 'index = 2', 'must be in 1..1'])
      ! analysis='transient' without &forcing
      call expect_error("analysis='transient' without &forcing", &
         "&job analysis = 'transient' /" // nl // beam, &
         [character(len=60) :: '&forcing', 'missing', "analysis='transient'"])
      call expect_ok("analysis='transient' with &forcing is accepted", &
         "&job analysis = 'transient' /" // nl // beam // '&forcing frequency_hz = 5.0 /')
      ! the deck file itself
      call remove(tmp)
      call expect_missing()
   end subroutine bad_decks

   !> Bad overrides: the message names the deck and the override.
   subroutine bad_overrides()
      call expect_error('override with no group', base, &
         [character(len=60) :: "override 1 'frequency_hz = 10.2'", 'no namelist group'], &
         [character(len=80) :: 'frequency_hz = 10.2'])
      call expect_error('second override with no group', base, &
         [character(len=60) :: 'override 2', 'no namelist group'], &
         [character(len=80) :: '&forcing frequency_hz = 10.2 /', 'amplitude_pp = 1.0e-3'])
      call expect_error('override with a misspelled variable', base, &
         [character(len=60) :: "override 1 '&forcing frequncy_hz = 3.0 /'", '&forcing', &
         'unknown variable frequncy_hz', 'frequncy_hz = 3.0'], &
         [character(len=80) :: '&forcing frequncy_hz = 3.0 /'])
      call expect_error('override with an unknown group', base, &
         [character(len=60) :: 'override 1', 'unknown group &forcin'], &
         [character(len=80) :: '&forcin frequency_hz = 3.0 /'])
      call expect_error('override with a bad value', base, &
         [character(len=60) :: '&beam', 'n_elem = -3', 'must be in 1..10000'], &
         [character(len=80) :: '&beam n_elem = -3 /'])
      call expect_error('override with a value of the wrong type', base, &
         [character(len=60) :: 'override 1', '&beam', 'length = x', &
         'cannot read the value of length'], [character(len=80) :: '&beam length = x /'])
      call expect_error('a group twice in one override', base, &
         [character(len=60) :: 'override 1', 'group &forcing appears more than once'], &
         [character(len=80) :: '&forcing frequency_hz = 3.0 / &forcing amplitude_pp = 0.1 /'])
   end subroutine bad_overrides

   !> The reader refuses text it does not consume (each case ran silently before: a group with
   !> a stray character after its name was dropped whole, a lone sign kept the old value, a
   !> second assignment or the text after a '/' was ignored).
   subroutine strict_text()
      character(len=*), parameter :: forcing = '&forcing frequency_hz=9.8 /'
      character(len=10) :: bad(9)
      integer :: k
      ! characters around group names (override and deck file)
      call expect_error("override '&forcing. frequency_hz=9.8 /'", base, [character(len=60) :: &
         "override 1", "'&forcing.", 'must be followed by a blank'], &
         [character(len=80) :: '&forcing. frequency_hz=9.8 /'])
      bad = [character(len=10) :: '&forcing.', '&forcing-', '&forcing:', '&forcing=', &
         '&-forcing', '&.forcing', '&=forcing', '&!forcing', '& forcing']
      do k = 1, size(bad)
         call expect_error("deck with '" // trim(bad(k)) // " frequency_hz=9.8 /'", base &
            // trim(bad(k)) // ' frequency_hz=9.8 /', [character(len=60) :: 'line 3', &
            '&forcing', trim(bad(k))])
      end do
      call expect_error("'&damping.' in a deck", base // "&damping. model = 'rayleigh', " &
         // 'mass_coefficient = 1.0 /', [character(len=60) :: 'line 3', "'&damping."])
      call expect_error("'&job.' in a deck", "&job. analysis = 'transient' /" // nl // beam, &
         [character(len=60) :: 'line 1', "'&job."])
      call expect_error("override '&sweep: n_frequency=2 /'", base, [character(len=60) :: &
         "'&sweep:"], [character(len=80) :: '&sweep: n_frequency=2 /'])
      call expect_error("'&-tops' in a deck", base // '&-tops node = 5, stiffness = 1.0 /', &
         [character(len=60) :: "'&-tops", '(&tops?)'])
      ! text outside groups, a second '/', a repeated assignment
      call expect_error("text after a closing '/'", base // forcing // ' junk', &
         [character(len=60) :: 'line 3', "text after the '/' that closes group &forcing", &
         "'junk'"])
      call expect_error("a deck cut after '&'", job // '&', [character(len=60) :: &
         'line 2', "must be followed directly by a group name (after group &job)"])
      call expect_error('stray text between groups', job // 'stray text' // nl // beam, &
         [character(len=60) :: 'line 2', 'text outside a group (after group &job)'])
      call expect_error("a second '/' in a group", base // '&forcing frequency_hz=9.8 / ' &
         // 'amplitude_pp=1.0e-3 /', [character(len=60) :: &
         "text after the '/' that closes group &forcing", 'amplitude_pp=1.0e-3'])
      call expect_error('the same variable twice in a group', base // '&forcing ' &
         // 'frequency_hz=9.8, frequency_hz=10.2 /', [character(len=60) :: &
         'frequency_hz is assigned twice', 'frequency_hz=9.8', 'frequency_hz=10.2'])
      call expect_error('the same list entry twice in a group', base // '&stops node = 5, 3, ' &
         // 'node(2) = 4, stiffness = 1.0, 1.0 /', [character(len=60) :: &
         'node is assigned twice'])
      call expect_ok('entries of one list in two assignments of a group', base // '&stops ' &
         // 'node = 5, node(2) = 3, stiffness = 1.0, 1.0 /')
      ! a missing '/' is reported as such, naming both groups and the line
      call expect_error("a missing '/' in the middle of a deck", job // replace(beam, ' /', &
         '') // '&forcing frequency_hz = 5.0 /', [character(len=60) :: &
         "group &beam (line 2) is not closed: no '/' before &forcing at line 3"])
      ! lone signs
      call expect_error("'frequency_hz=+'", base, [character(len=60) :: '&forcing', &
         'frequency_hz = +', 'not a number'], [character(len=80) :: '&forcing frequency_hz=+ /'])
      call expect_error("'record_periods=-'", base, [character(len=60) :: '&solver', &
         'record_periods = -', 'not a number'], &
         [character(len=80) :: '&solver record_periods=- /'])
      call expect_error("'max_points=-'", base, [character(len=60) :: '&continuation', &
         'max_points = -'], [character(len=80) :: '&continuation max_points=- /'])
   end subroutine strict_text

   !> Numbers that overflow, counts beyond 32 bits, derived quantities out of range.
   subroutine extreme_values()
      call expect_error('frequency_hz = 1e309 (overflows)', base // '&forcing frequency_hz ' &
         // '= 1e309 /', [character(len=60) :: '&forcing', 'frequency_hz = 1e309', &
         'the number overflows'])
      call expect_error('frequency_hz = 1e308', base // '&forcing frequency_hz = 1e308 /', &
         [character(len=60) :: '&forcing', 'frequency_hz = 1E+308', 'must be > 0 and <= 1E+009'])
      call expect_error('transient_periods = 2^31 (beyond 32 bits)', base // '&solver ' &
         // 'transient_periods = 2147483648 /', [character(len=60) :: '&solver', &
         'transient_periods = 2147483648', 'the integer overflows'])
      call expect_error('amplitude_pp = 1e-300 (its response would underflow)', base &
         // '&forcing amplitude_pp = 1e-300 /', [character(len=60) :: '&forcing', &
         'amplitude_pp = 1E-300', 'must be 0 or in [1E-030'])
      call expect_ok('amplitude_pp = 1e-30 (the smallest non-zero amplitude)', base &
         // '&forcing amplitude_pp = 1e-30 /')
      call expect_error('amplitude_pp = 1e200 at 10 Hz (the base acceleration overflows)', base &
         // '&forcing frequency_hz = 10.0, amplitude_pp = 1e200 /', [character(len=60) :: &
         '&forcing', 'amplitude_pp = 1E+200', 'the base acceleration'])
      call expect_error('&initial displacement = 1e300', base // "&initial kind = 'given', " &
         // "node = 5, dof = 'w', displacement = 1e300 /", [character(len=60) :: '&initial', &
         'displacement(1) = 1E+300'])
      call expect_error('&initial: a (node, dof) given twice', base // "&initial kind = " &
         // "'given', node = 5, 5, dof = 'w', 'w', displacement = 1e-3, 2e-3 /", &
         [character(len=60) :: '&initial', 'node(2) = 5', 'also entry 1'])
      call expect_error('a repeat count beyond the list', base // '&sweep frequency_hz = ' &
         // '5000*10.0 /', [character(len=60) :: '&sweep', 'frequency_hz has 5000 entries', &
         'at most 4096'])
   end subroutine extreme_values

   !> &initial takes as many entries as the model has dofs: a rigid rotation about the root
   !> of a 40-element beam, every node's w and theta velocity (80 entries).
   subroutine long_initial_list()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      character(len=:), allocatable :: text, nodes, dofs, vel
      integer :: i
      nodes = '';  dofs = '';  vel = ''
      do i = 2, 41
         nodes = nodes // str(i) // ', ' // str(i) // ', '
         dofs = dofs // "'w', 'theta', "
         vel = vel // str(0.005_dp * (i - 1)) // ', 1.0, '
      end do
      text = job // replace(beam, 'n_elem = 4', 'n_elem = 40') // "&root condition = " &
         // "'spring', k_theta = 1.0 /" // nl // "&initial kind = 'given'," // nl // 'node = ' &
         // nodes // nl // 'dof = ' // dofs // nl // 'velocity = ' // vel // ' /' // nl
      call write_deck(tmp, text)
      call read_deck(tmp, no_overrides, deck, err)
      call remove(tmp)
      call check('&initial with 80 entries (every dof of a 40-element beam) is read', &
         .not. allocated(err), message(err))
      if (allocated(err)) return
      call check('... 80 entries, the last the tip rotation at 1 rad/s', &
         size(deck%initial%node) == 80 .and. deck%initial%node(80) == 41 .and. &
         deck%initial%dof(80) == dof_theta .and. near(deck%initial%velocity(80), 1.0_dp))
      call check_close('... the tip velocity omega L = 0.2 m/s', deck%initial%velocity(79), &
         0.2_dp, rtol=1.0e-12_dp)
   end subroutine long_initial_list

   !> Design variables by name, through the deck table: unit, range, the refusals of
   !> check_deck_variable, the Rayleigh coefficients that ratios give.
   subroutine design_variables()
      use gapbeam_deck_variable, only: deck_variable_t, parse_deck_variable, &
         check_deck_variable, get_deck_value, set_deck_value, deck_variable_words
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      type(deck_variable_t) :: var
      real(dp) :: beta, gamma
      call read_deck(full, no_overrides, deck, err)
      if (allocated(err)) return
      call parse_deck_variable('&stops gap(2)', var, err)
      call check("'&stops gap(2)': group, name, entry 2, unit m", .not. allocated(err) .and. &
         var%group == 'stops' .and. var%name == 'gap' .and. var%index == 2 .and. &
         var%units == 'm', message(err))
      call check_close('... its value in input_full.nml', get_deck_value(deck, var), &
         deck%stops(2)%gap, rtol=0.0_dp)
      call set_deck_value(deck, var, 3.0e-3_dp, err)
      call check('... set to 3 mm', .not. allocated(err) .and. deck%stops(2)%gap == 3.0e-3_dp)
      call set_deck_value(deck, var, -1.0_dp, err)
      call check('... set to -1: refused, the deck unchanged', allocated(err) .and. &
         deck%stops(2)%gap == 3.0e-3_dp)
      if (allocated(err)) call check('... the message: the label, the value, the range', &
         index(err%message, '&stops gap(2) = -1: must be >= 0') > 0, err%message)
      call parse_deck_variable('&forcing frequency_hz', var, err)
      call set_deck_value(deck, var, 2.0e9_dp, err)
      call check('&forcing frequency_hz = 2e9: refused (at most 1e9)', allocated(err))
      call parse_deck_variable('&stops side(1)', var, err)
      call check('&stops side: not a numeric variable', allocated(err))
      call parse_deck_variable('&forcing frequency_hz(2)', var, err)
      call check('&forcing frequency_hz(2): no entry index on a scalar group', allocated(err))
      call check('deck_variable_words names &beam length ... &forcing ... amplitude_pp', &
         index(deck_variable_words(), '&beam length, youngs_modulus') == 1 .and. &
         index(deck_variable_words(), '&forcing frequency_hz, amplitude_pp') > 0, &
         deck_variable_words())
      ! a ratio of model 'ratios': the coefficients follow
      call write_deck(tmp, base // "&damping model = 'ratios', frequency1_hz = 1.0, " &
         // 'ratio1 = 0.01, frequency2_hz = 10.0, ratio2 = 0.02 /')
      call read_deck(tmp, no_overrides, deck, err)
      call remove(tmp)
      if (allocated(err)) return
      call parse_deck_variable('&damping ratio2', var, err)
      call check_deck_variable(deck, var, err)
      call set_deck_value(deck, var, 0.05_dp, err)
      call rayleigh_from_ratios(1.0_dp, 0.01_dp, 10.0_dp, 0.05_dp, beta, gamma)
      call check('&damping ratio2 = 0.05: the Rayleigh coefficients recomputed', &
         .not. allocated(err) .and. deck%damping%ratio2 == 0.05_dp .and. &
         deck%damping%mass_coefficient == beta .and. deck%damping%stiffness_coefficient == gamma)
      call parse_deck_variable('&damping mass_coefficient', var, err)
      call check_deck_variable(deck, var, err)
      call check("&damping mass_coefficient with model 'ratios': refused", allocated(err))
      call parse_deck_variable('&beam area', var, err)
      call check_deck_variable(deck, var, err)
      call check('&beam area of a rectangular section: refused', allocated(err))
   end subroutine design_variables

   !> docs/decks.md holds, for every group of the deck table, exactly the table that
   !> `gapbeam --help-deck --markdown` prints (renew them with scripts/test_docs.py
   !> --write-decks GAPBEAM).
   subroutine docs_tables()
      use gapbeam_deck_help, only: deck_help, deck_table_begin, deck_table_end
      use gapbeam_deck_check, only: deck_names_t, deck_names
      character(len=:), allocatable :: doc, tables, block, group
      type(deck_names_t) :: names
      type(error_t), allocatable :: err
      integer :: g, a, b
      call deck_help('&stops', .false., tables, err)
      call check("--help-deck '&stops': gap's default, unit, range", .not. allocated(err) &
         .and. index(tables, 'gap = 0 [m];  >= 0') > 0 .and. index(tables, '&damping:') == 0)
      call deck_help('stop', .false., tables, err)
      call check("--help-deck stop: an unknown group", allocated(err))
      doc = file_text('docs/decks.md')
      call deck_help('', .true., tables, err)
      call check('--help-deck --markdown works', .not. allocated(err))
      if (allocated(err)) return
      names = deck_names()
      do g = 1, size(names%names)
         group = trim(names%names(g))
         a = index(tables, deck_table_begin(group))
         b = index(tables, deck_table_end(group)) + len(deck_table_end(group)) - 1
         block = tables(a:b)
         call check('docs/decks.md holds the generated table of &' // group, a > 0 .and. &
            index(doc, block) > 0, 'run: python3 scripts/test_docs.py --write-decks GAPBEAM')
      end do
   end subroutine docs_tables

   ! ---------------------------------------------------------------- helpers

   !> Write `text` to the temporary deck, read it (with overrides), expect an error whose
   !> message starts with the deck name and holds every fragment; delete the deck.
   subroutine expect_error(name, text, fragments, ov)
      character(len=*), intent(in) :: name              !! what is checked
      character(len=*), intent(in) :: text              !! deck text
      character(len=*), intent(in) :: fragments(:)      !! texts the message must hold
      character(len=*), intent(in), optional :: ov(:)   !! overrides
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      character(len=:), allocatable :: missing
      integer :: i
      call write_deck(tmp, text)
      if (present(ov)) then
         call read_deck(tmp, ov, deck, err)
      else
         call read_deck(tmp, no_overrides, deck, err)
      end if
      call remove(tmp)
      call check(name // ': rejected', allocated(err))
      if (.not. allocated(err)) return
      call note('message: ' // err%message)
      missing = ''
      if (index(err%message, tmp // ': ') /= 1) missing = missing // ' [' // tmp // ': ]'
      do i = 1, size(fragments)
         if (index(err%message, trim(fragments(i))) == 0) &
            missing = missing // ' [' // trim(fragments(i)) // ']'
      end do
      call check(name // ': the message names the deck and holds ' &
         // str(size(fragments)) // ' fragments', len(missing) == 0, 'missing:' // missing)
   end subroutine expect_error

   !> Write `text` to the temporary deck and expect it to be read without error.
   subroutine expect_ok(name, text)
      character(len=*), intent(in) :: name   !! what is checked
      character(len=*), intent(in) :: text   !! deck text
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      call write_deck(tmp, text)
      call read_deck(tmp, no_overrides, deck, err)
      call remove(tmp)
      call check(name, .not. allocated(err), message(err))
   end subroutine expect_ok

   !> A deck file that does not exist.
   subroutine expect_missing()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      call read_deck(tmp, no_overrides, deck, err)
      call check('a missing deck file is an error naming it', allocated(err))
      if (allocated(err)) call check('... the message says no such file', &
         index(err%message, tmp) == 1 .and. index(err%message, 'no such file') > 0, &
         err%message)
   end subroutine expect_missing

   !> Message of an error, or '' (for check details).
   function message(err) result(s)
      type(error_t), allocatable, intent(in) :: err   !! error or unallocated
      character(len=:), allocatable :: s
      s = ''
      if (allocated(err)) s = err%message
   end function message

   !> `s` with the first occurrence of `a` replaced by `b`.
   pure function replace(s, a, b) result(t)
      character(len=*), intent(in) :: s, a, b   !! text, old and new
      character(len=:), allocatable :: t
      integer :: i
      i = index(s, a)
      if (i == 0) then
         t = s
      else
         t = s(1:i - 1) // b // s(i + len(a):)
      end if
   end function replace

   !> Two reals equal to 1e-15 (copies of a type default).
   pure logical function near(a, b)
      real(dp), intent(in) :: a, b   !! values
      near = abs(a - b) <= 1.0e-15_dp * abs(b)
   end function near

   !> All fields of two solver settings agree.
   pure logical function same_solver(a, b)
      type(solver_settings_t), intent(in) :: a, b   !! settings
      same_solver = a%method == b%method .and. near(a%newmark_delta, b%newmark_delta) &
         .and. near(a%newmark_alpha, b%newmark_alpha) .and. a%stop_solution == b%stop_solution &
         .and. near(a%fp_tolerance, b%fp_tolerance) &
         .and. a%fp_max_iterations == b%fp_max_iterations .and. a%step_control == b%step_control &
         .and. a%steps_per_period == b%steps_per_period &
         .and. near(a%half_step_tolerance, b%half_step_tolerance) &
         .and. near(a%residual_floor, b%residual_floor) .and. a%max_halvings == b%max_halvings &
         .and. a%grow_after == b%grow_after .and. near(a%grow_ratio, b%grow_ratio) &
         .and. (a%locate_events .eqv. b%locate_events) .and. a%linear_solver == b%linear_solver &
         .and. a%transient_periods == b%transient_periods &
         .and. a%record_periods == b%record_periods
   end function same_solver

   !> All fields of two damping descriptions agree (the defaults are zeros).
   pure logical function same_damping(a, b)
      type(damping_t), intent(in) :: a, b   !! damping
      same_damping = a%model == b%model .and. abs(a%mass_coefficient - b%mass_coefficient) &
         + abs(a%stiffness_coefficient - b%stiffness_coefficient) &
         + abs(a%frequency1_hz - b%frequency1_hz) + abs(a%ratio1 - b%ratio1) &
         + abs(a%frequency2_hz - b%frequency2_hz) + abs(a%ratio2 - b%ratio2) == 0.0_dp
   end function same_damping

   !> Whole text of a file, as load_file keeps it.
   function file_text(path) result(text)
      character(len=*), intent(in) :: path   !! file
      character(len=:), allocatable :: text
      integer :: unit, n
      open(newunit=unit, file=path, access='stream', form='unformatted', status='old', &
           action='read')
      inquire(unit=unit, size=n)
      allocate(character(len=n) :: text)
      read(unit) text
      close(unit)
   end function file_text

   !> Write a deck file.
   subroutine write_deck(path, text)
      character(len=*), intent(in) :: path, text   !! file and contents
      integer :: unit
      open(newunit=unit, file=path, access='stream', form='unformatted', status='replace', &
           action='write')
      write(unit) text
      close(unit)
   end subroutine write_deck

   !> True if the file exists.
   logical function exists(path)
      character(len=*), intent(in) :: path   !! file
      inquire(file=path, exist=exists)
   end function exists

   !> Delete a file if it exists.
   subroutine remove(path)
      character(len=*), intent(in) :: path   !! file
      integer :: unit
      if (.not. exists(path)) return
      open(newunit=unit, file=path, status='old')
      close(unit, status='delete')
   end subroutine remove
end program test_input
