!> Namelist decks: read, apply command-line overrides, validate, and keep the effective text.
!>
!> One group per concept: &job, &beam, &root, &springs, &masses, &modes, &calibrate, &stops,
!> &damping, &forcing, &solver, &initial, &output. Each reader seeds its locals from the type
!> defaults, reads the group from the deck file and then from every override that names it,
!> validates, and only then copies into the deck: a half-read configuration never escapes.
!> Messages read `DECK: group &beam: length = -0.2: must be > 0`.
module gapbeam_input
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_capabilities, only: solver_refusal
   use gapbeam_laws, only: stop_law_refusal
   use gapbeam_deck_text, only: source_t, load_file, make_source, group_names, group_block, &
      split_assignments, lower, basename_stem, null_value, longest_text_value, assigned_name, &
      quote_left_open
   use gapbeam_description, only: beam_t, root_t, spring_t, point_mass_t, structure_t, &
      stop_t, damping_t, forcing_t, dof_code, dof_w, dof_theta, stop_side_words, &
      stop_law_words, damping_words, rotary_inertia_words, rayleigh_from_ratios, beam_ei, &
      beam_rho_a, dof_v, dof_theta_v, point_force_t, stop_shape_words, end_condition_words, &
      tip_condition_words, stop_is_ring
   use gapbeam_settings, only: job_t, calibrate_t, solver_settings_t, output_settings_t, &
      initial_state_t, diagnostics_settings_t, reduction_settings_t, model_size_settings_t, &
      sweep_settings_t, study_settings_t, stop_solution_words, step_control_words, &
      linear_solver_words, method_words, initial_state_words, sweep_mode_words, &
      sweep_direction_words, sweep_axis_words, series_words, calibration_words, analysis_words, &
      start_words, starts_given
   use gapbeam_deck, only: deck_t
   use gapbeam_deck_variable, only: deck_variable_t, parse_deck_variable, check_deck_variable, &
      get_deck_value, set_deck_value, deck_variable_label, parse_deck_variables, &
      deck_variables_label
   implicit none
   private
   public :: read_deck, known_groups
   ! --- continuation hook (issue 14): the submodule gapbeam_input_continuation calls these;
   !     gfortran gives private module procedures internal linkage, so they must be public
   public :: apply_group, require_int, require_nonnegative, require_range, require_word
   ! --- end of the continuation hook

   integer, parameter :: nmax = 64   !! most entries of a list group (&springs, &stops, ...)
   !> what a list entry holds before a read that looks for entries beyond the node list
   real(dp), parameter :: list_marker = -7.77e77_dp
   character(len=*), parameter :: list_word_marker = '#'

   character(len=*), parameter :: dof_words = "'w', 'theta', 'v', 'theta_v'"

   character(len=*), parameter :: known_groups = 'job beam root springs masses modes ' // &
      'calibrate stops damping forcing solver initial output diagnostics sweep reduction ' // &
      'study model_size continuation tip point_forces'
   integer, parameter :: naxis = 4096   !! most values of a sweep axis list
   integer, parameter :: max_axis = 1000000     !! most values of a sweep axis range (n_frequency)
   integer, parameter :: max_points = 1000000   !! most points of a sweep
   !> Most values kept in memory for one array of results (history samples, Poincare points,
   !> Lyapunov estimates) or for all the points of a sweep: 5e8 reals are 4 GB.
   integer(int64), parameter :: max_values = 500000000_int64
   integer, parameter :: max_periods = 100000000   !! most recorded or Lyapunov periods

   !> Entries given in a list variable read twice (see list_entries_int).
   interface list_entries
      module procedure list_entries_int, list_entries_real
   end interface list_entries

   abstract interface
      !> Reads one namelist group from an internal file.
      subroutine nml_reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
      end subroutine nml_reader
   end interface

   ! --- continuation hook (issue 14): &continuation, in submodule gapbeam_input_continuation
   interface
      !> Read and validate &continuation (after every other group: it names deck variables).
      module subroutine read_continuation(srcs, deck, present_group, err)
         type(source_t), intent(in) :: srcs(:)           !! deck file, then overrides
         type(deck_t), intent(inout) :: deck             !! deck read so far
         logical, intent(in) :: present_group            !! the deck has &continuation
         type(error_t), allocatable, intent(out) :: err  !! first problem found
      end subroutine read_continuation
   end interface
   ! --- end of the continuation hook

contains

   !> Read, override and validate a deck.
   subroutine read_deck(path, overrides, deck, err)
      character(len=*), intent(in) :: path            !! deck file
      character(len=*), intent(in) :: overrides(:)    !! namelist fragments applied in order
      type(deck_t), intent(out) :: deck               !! validated deck
      type(error_t), allocatable, intent(out) :: err  !! first problem found
      type(source_t), allocatable :: srcs(:)
      character(len=:), allocatable :: text
      character(len=32), allocatable :: names(:)
      character(len=:), allocatable :: block(:)
      type(sweep_settings_t) :: sweep
      integer :: s, i, j
      logical :: closed

      deck%path = path
      call load_file(path, text, err)
      if (allocated(err)) return
      allocate(srcs(1 + size(overrides)))
      call make_source(path, text, srcs(1))
      deck%text = text
      do s = 1, size(overrides)
         call make_source('override ' // str(s) // " '" // short_text(trim(overrides(s)), 80) &
                          // "'", trim(overrides(s)), srcs(1 + s))
         deck%text = deck%text // new_line('a') // '! command-line override ' // str(s) &
            // new_line('a') // trim(overrides(s)) // new_line('a')
      end do

      ! every group must be known, and appear at most once per source
      do s = 1, size(srcs)
         call group_names(srcs(s), names)
         if (s > 1 .and. size(names) == 0) then
            call fatal_error(err, path // ': ' // srcs(s)%label // ': no namelist group ' &
               // '(an override looks like "&forcing frequency_hz=10.2 /")')
            return
         end if
         do i = 1, size(names)
            if (index(' ' // known_groups // ' ', ' ' // trim(names(i)) // ' ') == 0) then
               call fatal_error(err, path // ': ' // where(srcs, s) // 'unknown group &' &
                  // trim(names(i)) // '; allowed groups: &' // replace_spaces(known_groups))
               return
            end if
            do j = 1, i - 1
               if (names(j) == names(i)) then
                  call fatal_error(err, path // ': ' // where(srcs, s) // 'group &' &
                     // trim(names(i)) // ' appears more than once')
                  return
               end if
            end do
            call group_block(srcs(s), trim(names(i)), block, closed)
            if (.not. closed) then
               call fatal_error(err, path // ': ' // where(srcs, s) // 'group &' &
                  // trim(names(i)) // " is not closed: no '/' before the end of the " &
                  // trim(merge('deck file', 'override ', s == 1)) // open_quote(block))
               return
            end if
         end do
      end do
      do i = 1, 2
         if (i == 1) text = 'job'
         if (i == 2) text = 'beam'
         if (.not. group_present(srcs, text)) then
            call fatal_error(err, path // ': required group &' // text // ' is missing')
            return
         end if
      end do

      call read_job(srcs, deck%job, err);              if (failed(err, path)) return
      call read_beam(srcs, deck%structure%beam, err);  if (failed(err, path)) return
      call read_root(srcs, deck%structure%root, err);  if (failed(err, path)) return
      call read_tip(srcs, deck%structure, err);  if (failed(err, path)) return
      call read_springs(srcs, deck%structure, deck%structure%springs, err)
      if (failed(err, path)) return
      if (deck%structure%root%condition == 'pinned' .and. deck%structure%tip%condition == &
          'free' .and. size(deck%structure%springs) == 0) then
         call fatal_error(err, path // ": group &root: condition = 'pinned' with a free tip " &
            // 'and no &springs is a mechanism (rigid rotation about the root): support the ' &
            // "tip (&tip condition = 'pinned', ...) or add springs")
         return
      end if
      call read_masses(srcs, deck%structure%beam%n_elem, deck%structure%masses, err)
      if (failed(err, path)) return
      call check_root_spring(deck%structure, err);  if (failed(err, path)) return
      call read_modes(srcs, deck%n_print_modes, err);  if (failed(err, path)) return
      call read_calibrate(srcs, deck%structure, deck%calibrate, err);  if (failed(err, path)) return
      call read_stops(srcs, deck%structure, deck%stops, err);  if (failed(err, path)) return
      call read_damping(srcs, deck%damping, err);  if (failed(err, path)) return
      call read_forcing(srcs, deck%structure, deck%forcing, err);  if (failed(err, path)) return
      call read_point_forces(srcs, deck%structure, deck%forcing%forces, err)
      if (failed(err, path)) return
      call read_solver(srcs, deck%solver, err);  if (failed(err, path)) return
      call read_initial(srcs, deck%structure, deck%initial, err);  if (failed(err, path)) return
      call read_output(srcs, deck%output, err);  if (failed(err, path)) return
      ! no Lyapunov exponent by default with ring supports (refused when asked for: below)
      if (any_ring(deck%stops)) deck%diagnostics%lyapunov_periods = 0
      call read_diagnostics(srcs, deck%diagnostics, err);  if (failed(err, path)) return
      sweep = deck%sweep
      call read_sweep(srcs, deck, sweep, err);  if (failed(err, path)) return
      deck%sweep = sweep
      call read_study(srcs, deck%study, err);  if (failed(err, path)) return
      call read_model_size(srcs, deck%model_size, err);  if (failed(err, path)) return
      call read_reduction(srcs, deck%reduction, err);  if (failed(err, path)) return
      call read_continuation(srcs, deck, group_present(srcs, 'continuation'), err)   ! issue 14
      if (failed(err, path)) return
      call check_sizes(deck, err);  if (failed(err, path)) return
      call check_starts(deck, err);  if (failed(err, path)) return
      if (deck%diagnostics%lyapunov_periods > 0 .and. any_ring(deck%stops) .and. &
          (deck%job%analysis == 'transient' .or. deck%job%analysis == 'sweep')) then
         ! the two trajectories restart from (u, v) every period: a stick anchor is not part
         ! of it, and the fixed steps they take cannot end at every stick-slip switch
         call fatal_error(err, path // ': group &diagnostics: lyapunov_periods = ' &
            // str(deck%diagnostics%lyapunov_periods) // ': the Lyapunov exponent is not ' &
            // 'available with ring supports (circular clearance or friction: their stick ' &
            // 'state is not part of the state (u, v) the exponent perturbs); set ' &
            // 'lyapunov_periods = 0, the default with ring supports (the label then comes from the ' &
            // 'period detection alone)')
         return
      end if
      if (len_trim(deck%job%output) == 0) deck%job%output = 'results/' // basename_stem(path)
      if (deck%job%analysis == 'calibrate' .and. deck%calibrate%target_f1_hz <= 0.0_dp) then
         call fatal_error(err, path // ": group &calibrate: target_f1_hz = " &
            // str(deck%calibrate%target_f1_hz) // ": must be > 0 for analysis='calibrate'")
         return
      end if
      if ((deck%job%analysis == 'transient' .or. deck%job%analysis == 'sweep' .or. &
           deck%job%analysis == 'work_precision' .or. deck%job%analysis == 'model_size' .or. &
           deck%job%analysis == 'continuation') .and. &
          .not. group_present(srcs, 'forcing')) then
         call fatal_error(err, path // ": group &forcing is missing: analysis='" &
            // trim(deck%job%analysis) // "' needs frequency_hz (use amplitude_pp=0 for free " &
            // 'vibration)')
         return
      end if
      if (deck%job%analysis == 'sweep' .and. .not. group_present(srcs, 'sweep')) then
         call fatal_error(err, path // ": group &sweep is missing: analysis='sweep' needs " &
            // 'the frequencies and amplitudes to sweep')
         return
      end if
   end subroutine read_deck

   !> Whether any stop is a ring support (circular clearance or friction).
   pure logical function any_ring(stops)
      type(stop_t), intent(in), allocatable :: stops(:)
      integer :: k
      any_ring = .false.
      if (.not. allocated(stops)) return
      do k = 1, size(stops)
         if (stop_is_ring(stops(k))) any_ring = .true.
      end do
   end function any_ring

   !> True when `err` is set; its message then starts with the deck path.
   logical function failed(err, path)
      type(error_t), allocatable, intent(inout) :: err   !! status of a group reader
      character(len=*), intent(in) :: path               !! deck path as given
      failed = allocated(err)
      if (failed) then
         if (index(err%message, path // ': ') /= 1) err%message = path // ': ' // err%message
      end if
   end function failed

   !> Sizes of the result arrays, counted in 64-bit integers before anything is allocated:
   !> the history of a run, and the results a sweep keeps for all its points.
   subroutine check_sizes(deck, err)
      type(deck_t), intent(in) :: deck                 !! deck, every group validated
      type(error_t), allocatable, intent(inout) :: err !! set when an array would be too large
      integer(int64) :: samples, per_point, points, lyap
      if (allocated(err)) return
      samples = int(min(deck%output%history_periods, deck%solver%record_periods), int64) &
                * deck%output%samples_per_period
      if (samples > max_values) then
         call fatal_error(err, 'group &output: history_periods = ' &
            // str(deck%output%history_periods) // ' (at most record_periods = ' &
            // str(deck%solver%record_periods) // ') x samples_per_period = ' &
            // str(deck%output%samples_per_period) // ' = ' // str_int64(samples) &
            // ' history samples: at most ' // str_int64(max_values))
         return
      end if
      if (deck%output%state_history .and. deck%job%analysis == 'transient') then
         if (deck%reduction%kind /= 'none') then
            call fatal_error(err, "group &output: state_history = .true.: needs the finite " &
               // "element model, not a modal one (&reduction kind = '" &
               // trim(deck%reduction%kind) // "'; allowed: 'none')")
            return
         end if
         ! every dof at every history sample, and the deflected shape at its points
         per_point = 2_int64 * (deck%structure%beam%n_elem + 1) &
                     + int(deck%structure%beam%n_elem, int64) * deck%output%shape_points + 1
         if (samples * per_point > max_values) then
            call fatal_error(err, 'group &output: state_history = .true.: ' &
               // str_int64(samples) // ' history samples x ' // str_int64(per_point) &
               // ' values each (2 dofs per node and the shape at n_elem x shape_points + 1 ' &
               // 'points) = ' // str_int64(samples * per_point) // ': at most ' &
               // str_int64(max_values) // '; keep fewer history_periods, samples_per_period ' &
               // 'or shape_points')
            return
         end if
      end if
      if (deck%job%analysis /= 'sweep') return
      ! per run (point and start): Poincare strain and rate, the running Lyapunov estimate (at
      ! most lyapunov_max_periods), the final state
      lyap = deck%diagnostics%lyapunov_max_periods
      if (lyap == 0) lyap = 20_int64 * deck%diagnostics%lyapunov_periods
      per_point = 2_int64 * deck%solver%record_periods + lyap &
                  + 4_int64 * deck%structure%beam%planes * (deck%structure%beam%n_elem + 1) &
                  + 16_int64 * size(deck%stops)
      points = int(size(deck%sweep%x), int64) * size(deck%sweep%y) * max(1, starts_given(deck%diagnostics))
      if (points * per_point > max_values) then
         call fatal_error(err, 'group &sweep: ' // str_int64(points) // ' runs (points x ' &
            // 'starts) x ' // str_int64(per_point) // ' values kept per run (2 x &solver ' &
            // 'record_periods + &diagnostics lyapunov_max_periods + the final state) = ' &
            // str_int64(points * per_point) // ': at most ' // str_int64(max_values) &
            // ' values; sweep fewer points (n_frequency, n_amplitude, n_x, n_y), use fewer ' &
            // 'starts or record fewer periods')
      end if
   end subroutine check_sizes

   !> 'up' and 'down' starts need the lines of a sweep, along an axis the sweep has.
   subroutine check_starts(deck, err)
      type(deck_t), intent(in) :: deck                 !! deck, every group validated
      type(error_t), allocatable, intent(inout) :: err !! set on a start that cannot be made
      logical :: lines
      if (allocated(err)) return
      lines = any(deck%diagnostics%starts == 'up' .or. deck%diagnostics%starts == 'down')
      if (lines .and. deck%job%analysis /= 'sweep') then
         call fatal_error(err, "group &diagnostics: starts 'up' and 'down' start from a " &
            // "sweep neighbour's final state: only with analysis = 'sweep' (this deck runs '" &
            // trim(deck%job%analysis) // "')")
         return
      end if
      if (deck%job%analysis /= 'sweep') return
      if (all(len_trim(deck%diagnostics%starts) == 0)) lines = deck%sweep%mode == 'continuation'
      if (.not. lines) return
      if ((deck%sweep%axis == 'frequency' .and. deck%sweep%x_variable /= '&forcing frequency_hz' &
           .and. deck%sweep%y_variable /= '&forcing frequency_hz') .or. &
          (deck%sweep%axis == 'amplitude' .and. deck%sweep%x_variable /= '&forcing amplitude_pp' &
           .and. deck%sweep%y_variable /= '&forcing amplitude_pp')) then
         call fatal_error(err, "group &sweep: axis = '" // trim(deck%sweep%axis) // "': the " &
            // 'lines of a continuation run along an axis of the sweep, and neither ' &
            // "x_variable ('" // trim(deck%sweep%x_variable) // "') nor y_variable ('" &
            // trim(deck%sweep%y_variable) // "') is the " // trim(deck%sweep%axis) &
            // "; use axis = 'x' or 'y'")
      end if
   end subroutine check_starts

   !> ' (a quote opened in the value of VAR is never closed)' when the last assignment of an
   !> unclosed group holds a quote left open (the '/' then belongs to the string), else ''.
   function open_quote(block) result(t)
      character(len=*), intent(in) :: block(:)         !! the group's lines, to the end
      character(len=:), allocatable :: t
      character(len=:), allocatable :: items(:)
      t = ''
      call split_assignments(block, items)
      if (size(items) == 0) return
      if (.not. quote_left_open(items(size(items)))) return
      t = ' (a quote opened in the value of ' // assigned_name(items(size(items))) &
         // ' is never closed)'
   end function open_quote

   !> A 64-bit integer as text.
   pure function str_int64(i) result(s)
      integer(int64), intent(in) :: i                  !! value
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end function str_int64

   pure function where(srcs, s) result(w)
      type(source_t), intent(in) :: srcs(:)
      integer, intent(in) :: s
      character(len=:), allocatable :: w
      if (s == 1) then
         w = ''
      else
         w = srcs(s)%label // ': '
      end if
   end function where

   pure function replace_spaces(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      integer :: i
      t = ''
      do i = 1, len(s)
         if (s(i:i) == ' ') then
            t = t // ', &'
         else
            t = t // s(i:i)
         end if
      end do
   end function replace_spaces

   !> True if any source opens the group.
   logical function group_present(srcs, name)
      type(source_t), intent(in) :: srcs(:)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: block(:)
      integer :: s
      group_present = .false.
      do s = 1, size(srcs)
         call group_block(srcs(s), name, block)
         if (allocated(block)) group_present = .true.
      end do
   end function group_present

   !> Read group `name` from every source that has it. Before a source is read, every
   !> assignment of the group is checked at the text level: the variable must be one of the
   !> group's, the value must not be null ('x = ,' would keep the default silently) and a
   !> character value must fit its variable. On a read error the assignment at fault is found
   !> and named.
   !>
   !> `variables` lists the group's variables, blank separated; a character variable carries
   !> its length, 'analysis:32 title:256 output:256'.
   subroutine apply_group(srcs, name, variables, reader, err)
      type(source_t), intent(in) :: srcs(:)           !! deck file, then overrides
      character(len=*), intent(in) :: name            !! group name
      character(len=*), intent(in) :: variables       !! the group's variables (see above)
      procedure(nml_reader) :: reader                 !! reads the group into the caller's locals
      type(error_t), allocatable, intent(out) :: err  !! set on a read error
      character(len=:), allocatable :: block(:), items(:)
      character(len=512) :: msg, msg2
      character(len=:), allocatable :: var, one(:), replaced
      integer :: s, ios, k
      do s = 1, size(srcs)
         call group_block(srcs(s), name, block)
         if (.not. allocated(block)) cycle
         call split_assignments(block, items)
         do k = 1, size(items)
            call check_assignment(name, variables, items(k), err)
            if (allocated(err)) then
               err%message = where(srcs, s) // err%message
               return
            end if
         end do
         ! a list given whole in a later source replaces this source's list whole
         replaced = later_lists(srcs, s, name, variables)
         if (len_trim(replaced) > 0) then
            if (any([(index(replaced, ' ' // assigned_name(items(k)) // ' ') > 0, &
                      k = 1, size(items))])) call without_lists(name, items, replaced, block)
         end if
         msg = ''
         call reader(block, ios, msg)
         if (ios == 0) cycle
         ! an empty read of the group clears the runtime's state after a failed namelist read
         ! (gfortran then returns iostat 0 without reading on the next internal file)
         allocate(character(len=len(name) + 3) :: one(1))
         one(1) = '&' // name // ' /'
         call reader(one, ios, msg2)
         deallocate(one)
         do k = 1, size(items)
            var = assigned_name(items(k))
            allocate(character(len=len_trim(items(k)) + len(name) + 4) :: one(1))
            one(1) = '&' // name // ' ' // trim(items(k)) // ' /'
            msg2 = ''
            call reader(one, ios, msg2)
            deallocate(one)
            if (ios /= 0) then
               call fatal_error(err, where(srcs, s) // 'group &' // name // ': ' &
                  // trim(items(k)) // ': cannot read the value of ' // var // ' (' &
                  // trim(msg2) // ')')
               return
            end if
         end do
         call fatal_error(err, where(srcs, s) // 'group &' // name // ': ' // trim(msg))
         return
      end do
   end subroutine apply_group

   !> A root spring negligible against the beam (kappa = k_theta L / EI below 1e-12) with no
   !> &springs: to double precision the root is a pin and the beam a mechanism, whose stiffness
   !> matrix is singular (the eigen-solve would fail far from the deck variables).
   subroutine check_root_spring(st, err)
      type(structure_t), intent(in) :: st                !! beam, root, springs
      type(error_t), allocatable, intent(out) :: err     !! the spring is negligible
      real(dp) :: kappa, ei_l
      if (st%root%condition /= 'spring') return
      if (allocated(st%springs)) then
         if (size(st%springs) > 0) return
      end if
      kappa = st%root%k_theta * st%beam%length / beam_ei(st%beam)
      ei_l = beam_ei(st%beam) / st%beam%length
      if (kappa < 1.0e-12_dp) call fatal_error(err, 'group &root: k_theta = ' &
         // str(st%root%k_theta) // ' N m/rad against the beam (&beam youngs_modulus, width, ' &
         // 'thickness or second_moment, length: EI/L = ' // str(ei_l) // ' N m): kappa = ' &
         // 'k_theta L / EI = ' // str(kappa) // ' is below ' &
         // '1e-12; to double precision the root is a pin and the beam, with no &springs, a ' &
         // 'mechanism (its stiffness matrix is singular)')
   end subroutine check_root_spring

   !> The list variables of group `name` assigned whole ('node = 2, 3', not 'node(2) = 3') in
   !> the sources after source `s`, as ' a b ' (blank separated, blanks around), or ''.
   function later_lists(srcs, s, name, variables) result(names)
      type(source_t), intent(in) :: srcs(:)           !! deck file, then overrides
      integer, intent(in) :: s                        !! the source being read
      character(len=*), intent(in) :: name            !! group name
      character(len=*), intent(in) :: variables       !! the group's variables
      character(len=:), allocatable :: names
      character(len=:), allocatable :: block(:), items(:), var
      integer :: t, k, max_len, eq, paren
      logical :: known, is_list
      names = ''
      do t = s + 1, size(srcs)
         call group_block(srcs(t), name, block)
         if (.not. allocated(block)) cycle
         call split_assignments(block, items)
         do k = 1, size(items)
            var = assigned_name(items(k))
            call variable_spec(variables, var, known, max_len, is_list)
            if (.not. (known .and. is_list)) cycle
            eq = index(items(k), '=');  paren = index(items(k), '(')
            if (paren > 0 .and. paren < eq) cycle          ! an element, not the whole list
            if (index(names // ' ', ' ' // var // ' ') == 0) names = names // ' ' // var
         end do
      end do
      if (len(names) > 0) names = names // ' '
   end function later_lists

   !> The block of group `name` rebuilt from its assignments without those to the variables
   !> in `replaced` (' a b ').
   pure subroutine without_lists(name, items, replaced, block)
      character(len=*), intent(in) :: name            !! group name
      character(len=*), intent(in) :: items(:)        !! the group's assignments
      character(len=*), intent(in) :: replaced        !! variables to leave out
      character(len=:), allocatable, intent(inout) :: block(:)  !! one line on return
      character(len=:), allocatable :: line
      integer :: k
      line = '&' // name
      do k = 1, size(items)
         if (index(replaced, ' ' // assigned_name(items(k)) // ' ') > 0) cycle
         line = line // ' ' // trim(items(k)) // ','
      end do
      line = line // ' /'
      deallocate(block)
      allocate(character(len=len(line)) :: block(1))
      block(1) = line
   end subroutine without_lists

   !> Check one assignment of group `group` at the text level (see apply_group).
   subroutine check_assignment(group, variables, item, err)
      character(len=*), intent(in) :: group           !! group name
      character(len=*), intent(in) :: variables       !! the group's variables, with lengths
      character(len=*), intent(in) :: item            !! one assignment
      type(error_t), allocatable, intent(inout) :: err  !! set when the assignment is refused
      character(len=:), allocatable :: var
      integer :: max_len, n
      logical :: known
      var = assigned_name(item)
      call variable_spec(variables, var, known, max_len)
      if (.not. known) then
         call fatal_error(err, 'group &' // group // ': unknown variable ' // var // ' (in "' &
            // short_text(trim(item), 200) // '"); the variables of &' // group // ' are: ' &
            // plain_names(variables))
      else if (null_value(item)) then
         call fatal_error(err, 'group &' // group // ': "' // short_text(trim(item), 200) &
            // '": no value for ' // var // ' (an empty value would keep the default ' &
            // 'silently: give a value or leave ' // var // ' out)')
      else if (max_len > 0) then
         n = longest_text_value(item)
         if (n > max_len) call fatal_error(err, 'group &' // group // ': ' // var &
            // ' is ' // str(n) // ' characters long: at most ' // str(max_len) &
            // ' characters (value "' // short_text(trim(adjustl(item(index(item, '=') + 1:))), &
            60) // '")')
      end if
   end subroutine check_assignment

   !> Whether `var` is in the variable list; for a character variable its length (0 for other
   !> variables); whether it is an array (a list).
   pure subroutine variable_spec(variables, var, known, max_len, is_list)
      character(len=*), intent(in) :: variables       !! 'a b():16 c', blank separated
      character(len=*), intent(in) :: var             !! variable name, lower case
      logical, intent(out) :: known                   !! var is in the list
      integer, intent(out) :: max_len                 !! its length, 0 if not character
      logical, intent(out), optional :: is_list       !! an array variable ('name()')
      character(len=:), allocatable :: token
      integer :: i, j, k, ios
      known = .false.;  max_len = 0
      if (present(is_list)) is_list = .false.
      i = 1
      do while (i <= len(variables))
         if (variables(i:i) == ' ') then
            i = i + 1
            cycle
         end if
         j = index(variables(i:), ' ')
         if (j == 0) then
            j = len(variables)
         else
            j = i + j - 2
         end if
         token = variables(i:j)
         i = j + 1
         k = scan(token, '(:')
         if (k == 0) k = len(token) + 1
         if (token(1:k - 1) /= var) cycle
         known = .true.
         if (present(is_list)) is_list = index(token, '()') > 0
         k = index(token, ':')
         if (k > 0) then
            read(token(k + 1:), *, iostat=ios) max_len
            if (ios /= 0) max_len = 0
         end if
         return
      end do
   end subroutine variable_spec

   !> The variable list without the markers: 'a b():16 c' -> 'a b c'.
   pure function plain_names(variables) result(t)
      character(len=*), intent(in) :: variables       !! variable list
      character(len=:), allocatable :: t
      integer :: i
      logical :: skip
      t = '';  skip = .false.
      do i = 1, len(variables)
         if (variables(i:i) == ':' .or. variables(i:i) == '(') skip = .true.
         if (variables(i:i) == ' ') skip = .false.
         if (.not. skip) t = t // variables(i:i)
      end do
   end function plain_names

   !> `text`, cut to `n` characters with '...' when longer.
   pure function short_text(text, n) result(t)
      character(len=*), intent(in) :: text            !! any text
      integer, intent(in) :: n                        !! most characters kept
      character(len=:), allocatable :: t
      if (len(text) > n) then
         t = text(1:n) // '...'
      else
         t = text
      end if
   end function short_text

   ! ---------------------------------------------------------------- validation helpers

   subroutine require_positive(group, var, x, err)
      character(len=*), intent(in) :: group, var
      real(dp), intent(in) :: x
      type(error_t), allocatable, intent(inout) :: err
      if (allocated(err)) return
      if (.not. (x > 0.0_dp) .or. x > huge(x)) call fatal_error(err, 'group &' // group // ': ' &
         // var // ' = ' // str(x) // ': must be > 0 and finite')
   end subroutine require_positive

   subroutine require_nonnegative(group, var, x, err)
      character(len=*), intent(in) :: group, var
      real(dp), intent(in) :: x
      type(error_t), allocatable, intent(inout) :: err
      if (allocated(err)) return
      if (.not. (x >= 0.0_dp) .or. x > huge(x)) call fatal_error(err, 'group &' // group &
         // ': ' // var // ' = ' // str(x) // ': must be >= 0 and finite')
   end subroutine require_nonnegative

   subroutine require_range(group, var, x, lo, hi, err)
      character(len=*), intent(in) :: group, var
      real(dp), intent(in) :: x, lo, hi
      type(error_t), allocatable, intent(inout) :: err
      if (allocated(err)) return
      if (.not. (x >= lo .and. x <= hi)) call fatal_error(err, 'group &' // group // ': ' &
         // var // ' = ' // str(x) // ': must be in [' // str(lo) // ', ' // str(hi) // ']')
   end subroutine require_range

   subroutine require_int(group, var, i, lo, hi, err, why)
      character(len=*), intent(in) :: group, var
      integer, intent(in) :: i, lo, hi
      type(error_t), allocatable, intent(inout) :: err
      character(len=*), intent(in), optional :: why
      character(len=:), allocatable :: extra
      if (allocated(err)) return
      extra = ''
      if (present(why)) extra = ' (' // why // ')'
      if (i < lo .or. i > hi) then
         if (hi == huge(hi)) then
            call fatal_error(err, 'group &' // group // ': ' // var // ' = ' // str(i) &
               // ': must be >= ' // str(lo) // extra)
         else
            call fatal_error(err, 'group &' // group // ': ' // var // ' = ' // str(i) &
               // ': must be in ' // str(lo) // '..' // str(hi) // extra)
         end if
      end if
   end subroutine require_int

   subroutine require_word(group, var, word, allowed, err)
      character(len=*), intent(in) :: group, var, word
      character(len=*), intent(in) :: allowed     !! "'a', 'b'"
      type(error_t), allocatable, intent(inout) :: err
      if (allocated(err)) return
      if (index(allowed, "'" // trim(word) // "'") == 0 .or. len_trim(word) == 0) &
         call fatal_error(err, 'group &' // group // ': ' // var // " = '" // trim(word) &
         // "': allowed: " // allowed)
   end subroutine require_word

   !> Number of entries given in a list variable that was read twice, each time from entries
   !> preset to a different marker (`first` from -1, `second` from -2): an entry is given where
   !> both reads agree, so an explicit -1 counts as given (and is refused later as a value).
   !> The entries must be given from 1 on, without gaps ('node(3) = 5' alone is an error).
   subroutine list_entries_int(group, var, first, second, n, err)
      character(len=*), intent(in) :: group, var      !! group and variable, for messages
      integer, intent(in) :: first(:), second(:)      !! the two reads
      integer, intent(out) :: n                       !! entries given
      type(error_t), allocatable, intent(inout) :: err  !! set on a gap
      call check_gaps(group, var, first == second, n, err)
   end subroutine list_entries_int

   !> list_entries_int for a list of reals.
   subroutine list_entries_real(group, var, first, second, n, err)
      character(len=*), intent(in) :: group, var      !! group and variable, for messages
      real(dp), intent(in) :: first(:), second(:)     !! the two reads
      integer, intent(out) :: n                       !! entries given
      type(error_t), allocatable, intent(inout) :: err  !! set on a gap
      ! equal bit patterns: a NaN given in the deck is given (and refused as a value later)
      call check_gaps(group, var, first == second .or. &
         transfer(first, 1_int64, size(first)) == transfer(second, 1_int64, size(second)), n, err)
   end subroutine list_entries_real

   !> An entry of a per-node list beyond the n entries of `node` is refused: it would be ignored
   !> silently ('mass = 1.0, 2.0' with one node). `marked` is the list read again over
   !> list_marker.
   subroutine no_entries_beyond(group, var, marked, n, err)
      character(len=*), intent(in) :: group, var      !! group and variable, for messages
      real(dp), intent(in) :: marked(:)               !! the list read over list_marker
      integer, intent(in) :: n                        !! entries node gives
      type(error_t), allocatable, intent(inout) :: err  !! set on an entry beyond n
      if (allocated(err)) return
      if (any(marked(n + 1:) /= list_marker)) call fatal_error(err, 'group &' // group // ': ' &
         // var // ' has an entry beyond the ' // str(n) // ' that node lists (one value per ' &
         // 'node entry)')
   end subroutine no_entries_beyond

   !> no_entries_beyond for a list of words (read again over list_word_marker).
   subroutine no_words_beyond(group, var, marked, n, err)
      character(len=*), intent(in) :: group, var      !! group and variable, for messages
      character(len=*), intent(in) :: marked(:)       !! the list read over list_word_marker
      integer, intent(in) :: n                        !! entries node gives
      type(error_t), allocatable, intent(inout) :: err  !! set on an entry beyond n
      if (allocated(err)) return
      if (any(marked(n + 1:) /= list_word_marker)) call fatal_error(err, 'group &' // group &
         // ': ' // var // ' has an entry beyond the ' // str(n) // ' that node lists (one ' &
         // 'value per node entry)')
   end subroutine no_words_beyond

   !> Number of the last given entry; an error if an entry before it was not given.
   subroutine check_gaps(group, var, given, n, err)
      character(len=*), intent(in) :: group, var      !! group and variable, for messages
      logical, intent(in) :: given(:)                 !! entry given
      integer, intent(out) :: n                       !! last given entry (0: none)
      type(error_t), allocatable, intent(inout) :: err  !! set on a gap
      integer :: i
      n = findloc(given, .true., dim=1, back=.true.)
      if (allocated(err)) return
      do i = 1, n
         if (.not. given(i)) then
            call fatal_error(err, 'group &' // group // ': ' // var // '(' // str(i) &
               // ') is not given, but ' // var // '(' // str(n) // ') is: give the entries ' &
               // 'from 1 on, without gaps')
            return
         end if
      end do
   end subroutine check_gaps

   !> The node exists and its dof is free: not fixed by the root or tip condition, and a
   !> second-plane dof ('v', 'theta_v') only with &beam planes = 2.
   subroutine require_node(group, var, i, node, dof, st, err)
      character(len=*), intent(in) :: group, var
      integer, intent(in) :: i, node, dof
      type(structure_t), intent(in) :: st
      type(error_t), allocatable, intent(inout) :: err
      character(len=:), allocatable :: v
      integer :: n_elem
      logical :: rot
      if (allocated(err)) return
      n_elem = st%beam%n_elem
      v = var // '(' // str(i) // ')'
      call require_int(group, v, node, 1, n_elem + 1, err, 'the mesh has ' // str(n_elem) &
         // ' elements, nodes 1..' // str(n_elem + 1) // ' from the root')
      if (allocated(err)) return
      rot = dof == dof_theta .or. dof == dof_theta_v
      if ((dof == dof_v .or. dof == dof_theta_v) .and. st%beam%planes < 2) then
         call fatal_error(err, 'group &' // group // ': ' // v // " with dof '" &
            // trim(dof_word(dof)) // "': the second plane needs &beam planes = 2")
      else if (node == 1 .and. .not. rot) then
         call fatal_error(err, 'group &' // group // ': ' // v // " = 1 with dof '" &
            // trim(dof_word(dof)) // "': the root translation is fixed")
      else if (node == 1 .and. rot .and. st%root%condition == 'clamped') then
         call fatal_error(err, 'group &' // group // ': ' // v // " = 1 with dof '" &
            // trim(dof_word(dof)) // "': the root is clamped (use &root condition='spring')")
      else if (node == n_elem + 1 .and. .not. rot .and. st%tip%condition /= 'free') then
         call fatal_error(err, 'group &' // group // ': ' // v // ' = ' // str(node) &
            // " with dof '" // trim(dof_word(dof)) // "': the tip translation is fixed " &
            // "(&tip condition = '" // trim(st%tip%condition) // "')")
      else if (node == n_elem + 1 .and. rot .and. st%tip%condition == 'clamped') then
         call fatal_error(err, 'group &' // group // ': ' // v // ' = ' // str(node) &
            // " with dof '" // trim(dof_word(dof)) // "': the tip is clamped")
      end if
   end subroutine require_node

   !> The deck word of a dof code.
   pure function dof_word(code) result(w)
      integer, intent(in) :: code
      character(len=8) :: w
      select case (code)
      case (dof_theta);    w = 'theta'
      case (dof_v);        w = 'v'
      case (dof_theta_v);  w = 'theta_v'
      case default;        w = 'w'
      end select
   end function dof_word

   ! ---------------------------------------------------------------- group readers

   subroutine read_job(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(job_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=32) :: analysis
      character(len=256) :: title, output
      namelist /job/ analysis, title, output
      analysis = cfg%analysis;  title = cfg%title;  output = cfg%output
      call apply_group(srcs, 'job', 'analysis:32 title:256 output:256', reader, err)
      if (allocated(err)) return
      call require_word('job', 'analysis', analysis, analysis_words, err)
      if (allocated(err)) return
      cfg = job_t(analysis=analysis, title=title, output=output)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=job, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_job

   subroutine read_beam(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(beam_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      real(dp) :: length, youngs_modulus, density, width, thickness, area, second_moment, &
         fibre_distance
      integer :: n_elem, planes
      real(dp) :: added_mass
      character(len=16) :: mass_matrix, rotary_inertia
      type(beam_t) :: trial
      namelist /beam/ length, n_elem, youngs_modulus, density, width, thickness, area, &
         second_moment, fibre_distance, mass_matrix, rotary_inertia, planes, added_mass
      planes = cfg%planes;  added_mass = cfg%added_mass
      length = cfg%length;  n_elem = cfg%n_elem;  youngs_modulus = cfg%youngs_modulus
      density = cfg%density;  width = cfg%width;  thickness = cfg%thickness
      area = cfg%area;  second_moment = cfg%second_moment;  fibre_distance = cfg%fibre_distance
      mass_matrix = cfg%mass_matrix;  rotary_inertia = cfg%rotary_inertia
      call apply_group(srcs, 'beam', 'length n_elem youngs_modulus density width thickness ' &
         // 'area second_moment fibre_distance mass_matrix:16 rotary_inertia:16 planes ' &
         // 'added_mass', reader, err)
      if (allocated(err)) return
      call require_positive('beam', 'length', length, err)
      call require_int('beam', 'n_elem', n_elem, 1, 10000, err)
      call require_positive('beam', 'youngs_modulus', youngs_modulus, err)
      call require_positive('beam', 'density', density, err)
      if (width /= 0.0_dp .or. thickness /= 0.0_dp) then
         call require_positive('beam', 'width', width, err)
         call require_positive('beam', 'thickness', thickness, err)
      else if (area /= 0.0_dp .or. second_moment /= 0.0_dp .or. fibre_distance /= 0.0_dp) then
         call require_positive('beam', 'area', area, err)
         call require_positive('beam', 'second_moment', second_moment, err)
         call require_positive('beam', 'fibre_distance', fibre_distance, err)
      else if (.not. allocated(err)) then
         call fatal_error(err, 'group &beam: the section is missing: give width and thickness ' &
            // '(rectangle) or area, second_moment and fibre_distance')
      end if
      call require_word('beam', 'mass_matrix', mass_matrix, "'lumped', 'consistent'", err)
      call require_word('beam', 'rotary_inertia', rotary_inertia, rotary_inertia_words, err)
      call require_int('beam', 'planes', planes, 1, 2, err, '1: (w, theta) per node; 2: also ' &
         // '(v, theta_v)')
      call require_nonnegative('beam', 'added_mass', added_mass, err)
      if (allocated(err)) return
      trial = beam_t(length=length, n_elem=n_elem, youngs_modulus=youngs_modulus, &
         density=density, width=width, thickness=thickness, area=area, &
         second_moment=second_moment, fibre_distance=fibre_distance, mass_matrix=mass_matrix, &
         rotary_inertia=rotary_inertia, planes=planes, added_mass=added_mass)
      call check_beam_scales(trial, err)
      if (allocated(err)) return
      cfg = trial
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=beam, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_beam

   !> The quantities the model is built from must be usable even when each input is: EI,
   !> rho A, the mass, and per element EI/le^3 (stiffness) and EI/(rho A le^4) (the square of a
   !> frequency) must lie between sqrt(tiny) and sqrt(huge) (about 1e-154 and 1e154), so that
   !> their squares (energies, norms) do not underflow or overflow either. Outside, the run
   !> would fail later, in an eigen-solve or an integration, far from the deck variables that
   !> cause it.
   subroutine check_beam_scales(b, err)
      type(beam_t), intent(in) :: b                    !! beam, its inputs validated
      type(error_t), allocatable, intent(inout) :: err !! set when a scale is out of range
      real(dp) :: ei, rho_a, le, k_el, w2_el
      character(len=:), allocatable :: inputs
      if (allocated(err)) return
      ei = beam_ei(b);  rho_a = beam_rho_a(b)
      le = b%length / real(b%n_elem, dp)
      k_el = ei / le / le / le
      w2_el = ei / rho_a / le / le / le / le
      ! the strain fibre (general section) and the added mass enter the strain row and the
      ! mass: their scales too (a huge fibre distance gave an infinite root strain at the first
      ! step, an error of the step control far from the deck variable)
      if (b%width <= 0.0_dp .and. .not. usable(b%fibre_distance / le / le)) then
         call fatal_error(err, 'group &beam: fibre_distance = ' // str(b%fibre_distance) &
            // ' with element length ' // str(le) // ' m gives a strain per unit rotation ' &
            // 'gradient c/le^2 = ' // str(b%fibre_distance / le / le) // ' 1/m: must be ' &
            // 'between ' // str(sqrt(tiny(1.0_dp))) // ' and ' // str(sqrt(huge(1.0_dp))))
         return
      end if
      if (b%added_mass > 0.0_dp .and. .not. usable((rho_a + b%added_mass) * b%length)) then
         call fatal_error(err, 'group &beam: added_mass = ' // str(b%added_mass) &
            // ' kg/m gives a beam mass of ' // str((rho_a + b%added_mass) * b%length) &
            // ' kg: must be at most ' // str(sqrt(huge(1.0_dp))))
         return
      end if
      if (usable(ei) .and. usable(rho_a) .and. usable(rho_a * b%length) .and. usable(k_el) &
          .and. usable(w2_el)) return
      if (b%width > 0.0_dp) then
         inputs = 'youngs_modulus = ' // str(b%youngs_modulus) // ', width = ' // str(b%width) &
            // ', thickness = ' // str(b%thickness)
      else
         inputs = 'youngs_modulus = ' // str(b%youngs_modulus) // ', area = ' // str(b%area) &
            // ', second_moment = ' // str(b%second_moment)
      end if
      call fatal_error(err, 'group &beam: ' // inputs // ', density = ' // str(b%density) &
         // ', length = ' // str(b%length) // ' and n_elem = ' // str(b%n_elem) // ' give EI = ' &
         // str(ei) // ' N m^2, rho A = ' // str(rho_a) // ' kg/m, element stiffness EI/le^3 = ' &
         // str(k_el) // ' N/m and EI/(rho A le^4) = ' // str(w2_el) // ' 1/s^2: each must be ' &
         // 'between ' // str(sqrt(tiny(1.0_dp))) // ' and ' // str(sqrt(huge(1.0_dp))))
   contains
      pure logical function usable(x)
         real(dp), intent(in) :: x
         usable = ieee_is_finite(x) .and. x >= sqrt(tiny(1.0_dp)) .and. x <= sqrt(huge(1.0_dp))
      end function usable
   end subroutine check_beam_scales

   subroutine read_root(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(root_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=16) :: condition
      real(dp) :: k_theta
      namelist / root / condition, k_theta
      condition = cfg%condition;  k_theta = cfg%k_theta
      call apply_group(srcs, 'root', 'condition:16 k_theta', reader, err)
      if (allocated(err)) return
      call require_word('root', 'condition', condition, end_condition_words, err)
      if (condition == 'spring') call require_positive('root', 'k_theta', k_theta, err)
      ! the beam's scale rule (check_beam_scales): a larger spring overflows the stiffness's
      ! norms and eigen-solves later, far from the deck variable
      if (condition == 'spring' .and. .not. allocated(err)) then
         if (k_theta > sqrt(huge(1.0_dp))) call fatal_error(err, 'group &root: k_theta = ' &
            // str(k_theta) // ': must be at most ' // str(sqrt(huge(1.0_dp))) &
            // ' (its square must not overflow)')
      end if
      if (allocated(err)) return
      cfg = root_t(condition=condition, k_theta=k_theta)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=root, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_root

   !> &tip: the support of the last node ('free' unless the deck says otherwise).
   subroutine read_tip(srcs, st, err)
      type(source_t), intent(in) :: srcs(:)
      type(structure_t), intent(inout) :: st
      type(error_t), allocatable, intent(out) :: err
      character(len=16) :: condition
      real(dp) :: k_theta
      namelist / tip / condition, k_theta
      condition = st%tip%condition;  k_theta = st%tip%k_theta
      call apply_group(srcs, 'tip', 'condition:16 k_theta', reader, err)
      if (allocated(err)) return
      call require_word('tip', 'condition', condition, tip_condition_words, err)
      if (condition == 'spring') call require_positive('tip', 'k_theta', k_theta, err)
      if (allocated(err)) return
      if (condition == 'clamped' .and. st%beam%n_elem < 2 .and. st%root%condition == &
          'clamped') then
         call fatal_error(err, "group &tip: condition = 'clamped' with a clamped root and " &
            // 'n_elem = 1 leaves no free dof')
         return
      end if
      st%tip = root_t(condition=condition, k_theta=k_theta)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=tip, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_tip

   subroutine read_springs(srcs, st, list, err)
      type(source_t), intent(in) :: srcs(:)
      type(structure_t), intent(in) :: st
      type(spring_t), allocatable, intent(out) :: list(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: node(nmax), given(nmax), n, i, code
      character(len=8) :: dof(nmax)
      real(dp) :: stiffness(nmax)
      namelist /springs/ node, dof, stiffness
      node = -1;  dof = 'w';  stiffness = 0.0_dp
      call apply_group(srcs, 'springs', 'node() dof():8 stiffness()', reader, err)
      if (allocated(err)) return
      given = node
      node = -2
      call apply_group(srcs, 'springs', 'node() dof():8 stiffness()', reader, err)
      call list_entries('springs', 'node', given, node, n, err)
      if (allocated(err)) return
      block
         real(dp) :: s_stiffness(nmax)
         character(len=8) :: s_dof(nmax)
         s_stiffness = stiffness;  s_dof = dof
         stiffness = list_marker;  dof = list_word_marker
         call apply_group(srcs, 'springs', 'node() dof():8 stiffness()', reader, err)
         call no_entries_beyond('springs', 'stiffness', stiffness, n, err)
         call no_words_beyond('springs', 'dof', dof, n, err)
         stiffness = s_stiffness;  dof = s_dof
         if (allocated(err)) return
      end block
      allocate(list(n))
      do i = 1, n
         call require_word('springs', 'dof(' // str(i) // ')', dof(i), dof_words, err)
         code = dof_code(dof(i))
         call require_node('springs', 'node', i, node(i), code, st, err)
         call require_positive('springs', 'stiffness(' // str(i) // ')', stiffness(i), err)
         if (allocated(err)) return
         list(i) = spring_t(node=node(i), dof=code, stiffness=stiffness(i))
      end do
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=springs, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_springs

   subroutine read_masses(srcs, n_elem, list, err)
      type(source_t), intent(in) :: srcs(:)
      integer, intent(in) :: n_elem
      type(point_mass_t), allocatable, intent(out) :: list(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: node(nmax), given(nmax), n, i
      real(dp) :: mass(nmax), inertia(nmax)
      namelist /masses/ node, mass, inertia
      node = -1;  mass = 0.0_dp;  inertia = 0.0_dp
      call apply_group(srcs, 'masses', 'node() mass() inertia()', reader, err)
      if (allocated(err)) return
      given = node
      node = -2
      call apply_group(srcs, 'masses', 'node() mass() inertia()', reader, err)
      call list_entries('masses', 'node', given, node, n, err)
      if (allocated(err)) return
      block
         real(dp) :: s_mass(nmax), s_inertia(nmax)
         s_mass = mass;  s_inertia = inertia
         mass = list_marker;  inertia = list_marker
         call apply_group(srcs, 'masses', 'node() mass() inertia()', reader, err)
         call no_entries_beyond('masses', 'mass', mass, n, err)
         call no_entries_beyond('masses', 'inertia', inertia, n, err)
         mass = s_mass;  inertia = s_inertia
         if (allocated(err)) return
      end block
      allocate(list(n))
      do i = 1, n
         call require_int('masses', 'node(' // str(i) // ')', node(i), 1, n_elem + 1, err, &
            'the mesh has nodes 1..' // str(n_elem + 1))
         call require_nonnegative('masses', 'mass(' // str(i) // ')', mass(i), err)
         call require_nonnegative('masses', 'inertia(' // str(i) // ')', inertia(i), err)
         if (allocated(err)) return
         list(i) = point_mass_t(node=node(i), mass=mass(i), inertia=inertia(i))
      end do
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=masses, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_masses

   subroutine read_modes(srcs, n_print_modes, err)
      type(source_t), intent(in) :: srcs(:)
      integer, intent(inout) :: n_print_modes
      type(error_t), allocatable, intent(out) :: err
      integer :: n_print
      namelist /modes/ n_print
      n_print = n_print_modes
      call apply_group(srcs, 'modes', 'n_print', reader, err)
      if (allocated(err)) return
      call require_int('modes', 'n_print', n_print, 0, huge(1), err, '0 prints all modes')
      if (allocated(err)) return
      n_print_modes = n_print
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=modes, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_modes

   subroutine read_calibrate(srcs, st, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(structure_t), intent(in) :: st
      type(calibrate_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=16) :: parameter
      integer :: index
      real(dp) :: target_f1_hz
      namelist /calibrate/ parameter, index, target_f1_hz
      if (.not. group_present(srcs, 'calibrate')) return
      parameter = cfg%parameter;  index = cfg%index;  target_f1_hz = cfg%target_f1_hz
      call apply_group(srcs, 'calibrate', 'parameter:16 index target_f1_hz', reader, err)
      if (allocated(err)) return
      call require_word('calibrate', 'parameter', parameter, calibration_words, err)
      call require_nonnegative('calibrate', 'target_f1_hz', target_f1_hz, err)
      if (allocated(err)) return
      select case (parameter)
      case ('spring')
         call require_int('calibrate', 'index', index, 1, size(st%springs), err, &
            'the deck has ' // str(size(st%springs)) // ' springs in &springs')
      case ('root_k_theta')
         if (st%root%condition /= 'spring') call fatal_error(err, "group &calibrate: " &
            // "parameter = 'root_k_theta' needs &root condition='spring'")
      case ('thickness', 'width')
         if (st%beam%width <= 0.0_dp) call fatal_error(err, 'group &calibrate: parameter = ''' &
            // trim(parameter) // "' needs a rectangular section (&beam width, thickness)")
      end select
      if (allocated(err)) return
      cfg = calibrate_t(parameter=parameter, index=index, target_f1_hz=target_f1_hz)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=calibrate, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_calibrate

   subroutine read_stops(srcs, st, list, err)
      type(source_t), intent(in) :: srcs(:)
      type(structure_t), intent(in) :: st
      type(stop_t), allocatable, intent(out) :: list(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: node(nmax), given(nmax), n, i, code
      character(len=8) :: dof(nmax)
      character(len=16) :: side(nmax), law(nmax)
      real(dp), dimension(nmax) :: gap, stiffness, damping, exponent, rule_factor, &
         rule_f1_ratio, rule_f1_hz, offset_w, offset_v, friction, tangential_stiffness, &
         wear_coefficient
      character(len=16) :: shape(nmax)
      character(len=:), allocatable :: ix, why
      type(stop_t) :: d
      character(len=*), parameter :: stop_vars = 'node() dof():8 side():16 law():16 gap() ' &
         // 'stiffness() damping() exponent() rule_factor() rule_f1_ratio() rule_f1_hz() ' &
         // 'shape():16 offset_w() offset_v() friction() tangential_stiffness() ' &
         // 'wear_coefficient()'
      namelist /stops/ node, dof, side, law, gap, stiffness, damping, exponent, rule_factor, &
         rule_f1_ratio, rule_f1_hz, shape, offset_w, offset_v, friction, tangential_stiffness, &
         wear_coefficient
      shape = d%shape;  offset_w = d%offset_w;  offset_v = d%offset_v;  friction = d%friction
      tangential_stiffness = d%tangential_stiffness;  wear_coefficient = d%wear_coefficient
      node = -1;  dof = 'w';  side = d%side;  law = d%law;  gap = d%gap
      stiffness = d%stiffness;  damping = d%damping;  exponent = d%exponent
      rule_factor = d%rule_factor;  rule_f1_ratio = d%rule_f1_ratio;  rule_f1_hz = d%rule_f1_hz
      call apply_group(srcs, 'stops', stop_vars, reader, err)
      if (allocated(err)) return
      given = node
      node = -2
      call apply_group(srcs, 'stops', stop_vars, reader, err)
      call list_entries('stops', 'node', given, node, n, err)
      if (allocated(err)) return
      call no_extra_entries(n, err)
      if (allocated(err)) return
      allocate(list(n))
      do i = 1, n
         ix = '(' // str(i) // ')'
         call require_word('stops', 'dof' // ix, dof(i), dof_words, err)
         code = dof_code(dof(i))
         call require_node('stops', 'node', i, node(i), code, st, err)
         call require_word('stops', 'shape' // ix, shape(i), stop_shape_words, err)
         call check_support(st, i, node(i), code, side(i), shape(i), gap(i), offset_w(i), &
            offset_v(i), friction(i), tangential_stiffness(i), wear_coefficient(i), &
            rule_factor(i), law(i), err)
         call require_word('stops', 'side' // ix, side(i), stop_side_words, err)
         call require_word('stops', 'law' // ix, law(i), stop_law_words, err)
         call require_nonnegative('stops', 'gap' // ix, gap(i), err)
         call require_nonnegative('stops', 'damping' // ix, damping(i), err)
         call require_nonnegative('stops', 'rule_factor' // ix, rule_factor(i), err)
         if (allocated(err)) return
         if (rule_factor(i) > 0.0_dp) then
            if (rule_f1_ratio(i) /= 0.0_dp) then      ! given (true for NaN too): check it
               call require_range('stops', 'rule_f1_ratio' // ix, rule_f1_ratio(i), &
                  1.0_dp + 1.0e-9_dp, 1.0e6_dp, err)
            else if (rule_f1_hz(i) == 0.0_dp) then
               call fatal_error(err, 'group &stops: rule_factor' // ix // ' = ' &
                  // str(rule_factor(i)) // ' needs rule_f1_ratio' // ix // ' > 1 or ' &
                  // 'rule_f1_hz' // ix // ' > 0 (the target of the stiffness rule)')
            else
               call require_positive('stops', 'rule_f1_hz' // ix, rule_f1_hz(i), err)
            end if
         else
            call require_positive('stops', 'stiffness' // ix, stiffness(i), err)
            if (allocated(err)) err%message = err%message // ' (or rule_factor' // ix &
               // ' > 0: the stiffness from the rule)'
         end if
         ! what the law takes (its registry entry, gapbeam_laws): exponent, damper, ring
         why = stop_law_refusal(law(i), ix, damping(i), exponent(i), shape(i) == 'circular' &
            .or. friction(i) > 0.0_dp, friction(i), tangential_stiffness(i))
         if (len(why) > 0) call fatal_error(err, 'group &stops: ' // why)
         if (allocated(err)) return
         list(i) = stop_t(node=node(i), dof=code, side=side(i), law=law(i), gap=gap(i), &
            stiffness=stiffness(i), damping=damping(i), exponent=exponent(i), &
            rule_factor=rule_factor(i), rule_f1_ratio=rule_f1_ratio(i), rule_f1_hz=rule_f1_hz(i), &
            shape=shape(i), offset_w=offset_w(i), offset_v=offset_v(i), friction=friction(i), &
            tangential_stiffness=tangential_stiffness(i), wear_coefficient=wear_coefficient(i))
      end do
   contains
      !> An entry of a per-stop list beyond the stops is refused: it would be ignored silently
      !> ('gap = 2e-4, 2e-4, -1' with two nodes). Checked per source (the deck file, each
      !> override): within one, against the node entries it gives, or the n stops of the whole
      !> deck when it gives none (an override that shortens node leaves the file's longer lists
      !> as they were: their extra entries are not an error). Read again over markers.
      subroutine no_extra_entries(n, err)
         integer, intent(in) :: n
         type(error_t), allocatable, intent(inout) :: err
         real(dp), parameter :: mark = -7.77e77_dp
         character(len=*), parameter :: cmark = '#'
         character(len=20) :: names(16)
         integer :: j, k, lim, n1(nmax)
         logical :: extra(16)
         real(dp), dimension(nmax) :: s_gap, s_stiffness, s_damping, s_exponent, s_rf, s_rr, &
            s_rh, s_ow, s_ov, s_fr, s_kt, s_wc
         character(len=16) :: s_side(nmax), s_law(nmax), s_shape(nmax)
         character(len=8) :: s_dof(nmax)
         integer :: s_node(nmax)
         s_gap = gap;  s_stiffness = stiffness;  s_damping = damping;  s_exponent = exponent
         s_rf = rule_factor;  s_rr = rule_f1_ratio;  s_rh = rule_f1_hz;  s_ow = offset_w
         s_ov = offset_v;  s_fr = friction;  s_kt = tangential_stiffness;  s_wc = wear_coefficient
         s_side = side;  s_law = law;  s_shape = shape;  s_dof = dof;  s_node = node
         names = [character(len=20) :: 'gap', 'stiffness', 'damping', 'exponent', &
            'rule_factor', 'rule_f1_ratio', 'rule_f1_hz', 'offset_w', 'offset_v', 'friction', &
            'tangential_stiffness', 'wear_coefficient', 'side', 'law', 'shape', 'dof']
         do k = 1, size(srcs)
            ! the node entries this source gives (two markers tell them)
            node = -1
            call apply_group(srcs(k:k), 'stops', stop_vars, reader, err)
            if (allocated(err)) exit
            n1 = node;  node = -2
            call apply_group(srcs(k:k), 'stops', stop_vars, reader, err)
            if (allocated(err)) exit
            lim = n
            do j = nmax, 1, -1
               if (n1(j) /= -1 .or. node(j) /= -2) then
                  lim = j
                  exit
               end if
            end do
            if (lim >= nmax) cycle
            gap = mark;  stiffness = mark;  damping = mark;  exponent = mark;  rule_factor = mark
            rule_f1_ratio = mark;  rule_f1_hz = mark;  offset_w = mark;  offset_v = mark
            friction = mark;  tangential_stiffness = mark;  wear_coefficient = mark
            side = cmark;  law = cmark;  shape = cmark;  dof = cmark
            call apply_group(srcs(k:k), 'stops', stop_vars, reader, err)
            if (allocated(err)) exit
            extra = [any(gap(lim + 1:) /= mark), any(stiffness(lim + 1:) /= mark), &
               any(damping(lim + 1:) /= mark), any(exponent(lim + 1:) /= mark), &
               any(rule_factor(lim + 1:) /= mark), any(rule_f1_ratio(lim + 1:) /= mark), &
               any(rule_f1_hz(lim + 1:) /= mark), any(offset_w(lim + 1:) /= mark), &
               any(offset_v(lim + 1:) /= mark), any(friction(lim + 1:) /= mark), &
               any(tangential_stiffness(lim + 1:) /= mark), &
               any(wear_coefficient(lim + 1:) /= mark), any(side(lim + 1:) /= cmark), &
               any(law(lim + 1:) /= cmark), any(shape(lim + 1:) /= cmark), &
               any(dof(lim + 1:) /= cmark)]
            do j = 1, size(names)
               if (extra(j)) then
                  call fatal_error(err, 'group &stops: ' // trim(names(j)) // ' has an entry ' &
                     // 'beyond the ' // str(lim) // ' stop(s) that node lists (one value per ' &
                     // 'node entry)')
                  exit
               end if
            end do
            if (allocated(err)) exit
         end do
         gap = s_gap;  stiffness = s_stiffness;  damping = s_damping;  exponent = s_exponent
         rule_factor = s_rf;  rule_f1_ratio = s_rr;  rule_f1_hz = s_rh;  offset_w = s_ow
         offset_v = s_ov;  friction = s_fr;  tangential_stiffness = s_kt;  wear_coefficient = s_wc
         side = s_side;  law = s_law;  shape = s_shape;  dof = s_dof;  node = s_node
      end subroutine no_extra_entries

      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=stops, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_stops

   !> The support variables of stop `ix` ('(i)'): a circular clearance needs two planes, a
   !> positive gap, a translational node (both planes free there), no side or dof choice and
   !> no stiffness rule; friction needs two planes (the sliding direction) and a translational
   !> dof; the hole offset belongs to a circular clearance only.
   subroutine check_support(st, i, node, code, side, shape, gap, offset_w, offset_v, &
                            friction, k_t, wear, rule_factor, law, err)
      type(structure_t), intent(in) :: st
      integer, intent(in) :: i
      character(len=*), intent(in) :: side, shape, law
      integer, intent(in) :: node, code
      real(dp), intent(in) :: gap, offset_w, offset_v, friction, k_t, wear, rule_factor
      type(error_t), allocatable, intent(inout) :: err
      character(len=:), allocatable :: ix
      if (allocated(err)) return
      ix = '(' // str(i) // ')'
      call require_range('stops', 'friction' // ix, friction, 0.0_dp, 10.0_dp, err)
      ! at most sqrt(huge): the stick spring's energy and the wear volume square or multiply them
      call require_range('stops', 'tangential_stiffness' // ix, k_t, 0.0_dp, &
                         sqrt(huge(1.0_dp)), err)
      call require_range('stops', 'wear_coefficient' // ix, wear, 0.0_dp, sqrt(huge(1.0_dp)), &
                         err)
      call require_range('stops', 'offset_w' // ix, offset_w, -1.0e3_dp, 1.0e3_dp, err)
      call require_range('stops', 'offset_v' // ix, offset_v, -1.0e3_dp, 1.0e3_dp, err)
      if (allocated(err)) return
      if (shape == 'circular') then
         if (st%beam%planes < 2) then
            call fatal_error(err, 'group &stops: shape' // ix // " = 'circular' needs &beam " &
               // 'planes = 2 (a circular clearance acts in both transverse planes)')
         else if (.not. (gap > 0.0_dp)) then
            call fatal_error(err, 'group &stops: gap' // ix // ' = ' // str(gap) // ": a " &
               // "circular clearance (shape = 'circular') needs a radial gap > 0")
         else if (code /= dof_w) then
            call fatal_error(err, 'group &stops: dof' // ix // " = '" // trim(dof_word(code)) &
               // "': a circular clearance acts on the node's w and v; leave dof out")
         else if (side /= 'positive') then
            call fatal_error(err, 'group &stops: side' // ix // " = '" // trim(side) // "': " &
               // 'a circular clearance has no side; leave side out')
         else if (rule_factor > 0.0_dp) then
            call fatal_error(err, 'group &stops: rule_factor' // ix // ' = ' // str(rule_factor) &
               // ': the stiffness rule is for flat stops; give stiffness for a circular ' &
               // 'clearance')
         else
            call require_node('stops', 'node', i, node, dof_v, st, err)
            if (allocated(err)) err%message = err%message // ' (stop' // ix // ' is circular)'
         end if
      else if (offset_w /= 0.0_dp .or. offset_v /= 0.0_dp) then
         call fatal_error(err, 'group &stops: offset_w' // ix // ' = ' // str(offset_w) &
            // ', offset_v' // ix // ' = ' // str(offset_v) // ": the hole centre offset " &
            // "belongs to a circular clearance (shape = 'circular')")
      end if
      if (allocated(err)) return
      if (friction > 0.0_dp) then
         if (st%beam%planes < 2) then
            call fatal_error(err, 'group &stops: friction' // ix // ' = ' // str(friction) &
               // ': friction needs &beam planes = 2 (a planar model has no sliding direction)')
         else if (code == dof_theta .or. code == dof_theta_v) then
            call fatal_error(err, 'group &stops: friction' // ix // ' = ' // str(friction) &
               // " on a rotation dof: friction acts on the translations ('w' or 'v')")
         else if (rule_factor > 0.0_dp) then
            call fatal_error(err, 'group &stops: friction' // ix // ' = ' // str(friction) &
               // ' with rule_factor' // ix // ': give stiffness (and tangential_stiffness) ' &
               // 'for a stop with friction')
         else
            ! the sliding direction: the node's other translation
            if (code == dof_w) call require_node('stops', 'node', i, node, dof_v, st, err)
            if (code == dof_v) call require_node('stops', 'node', i, node, dof_w, st, err)
            if (allocated(err)) err%message = err%message // ' (stop' // ix &
               // ' has friction: it slides along the other plane)'
         end if
      end if
   end subroutine check_support

   subroutine read_damping(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(damping_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=16) :: model
      real(dp) :: mass_coefficient, stiffness_coefficient, frequency1_hz, ratio1, &
         frequency2_hz, ratio2
      namelist /damping/ model, mass_coefficient, stiffness_coefficient, frequency1_hz, ratio1, &
         frequency2_hz, ratio2
      model = cfg%model;  mass_coefficient = cfg%mass_coefficient
      stiffness_coefficient = cfg%stiffness_coefficient;  frequency1_hz = cfg%frequency1_hz
      ratio1 = cfg%ratio1;  frequency2_hz = cfg%frequency2_hz;  ratio2 = cfg%ratio2
      call apply_group(srcs, 'damping', 'model:16 mass_coefficient stiffness_coefficient ' &
         // 'frequency1_hz ratio1 frequency2_hz ratio2', reader, err)
      if (allocated(err)) return
      call require_word('damping', 'model', model, damping_words, err)
      if (allocated(err)) return
      select case (model)
      case ('none')
         mass_coefficient = 0.0_dp;  stiffness_coefficient = 0.0_dp
      case ('rayleigh')
         call require_nonnegative('damping', 'mass_coefficient', mass_coefficient, err)
         call require_nonnegative('damping', 'stiffness_coefficient', stiffness_coefficient, err)
         ! the beam's scale rule (check_beam_scales): beta M and gamma K must not overflow
         ! (beta = 1e308 made every damping term infinite and the run never end)
         if (.not. allocated(err) .and. mass_coefficient > sqrt(huge(1.0_dp))) &
            call fatal_error(err, 'group &damping: mass_coefficient = ' // str(mass_coefficient) &
               // ': must be at most ' // str(sqrt(huge(1.0_dp))) // ' (1/s)')
         if (.not. allocated(err) .and. stiffness_coefficient > sqrt(huge(1.0_dp))) &
            call fatal_error(err, 'group &damping: stiffness_coefficient = ' &
               // str(stiffness_coefficient) // ': must be at most ' // str(sqrt(huge(1.0_dp))) &
               // ' (s)')
      case ('ratios')
         call require_positive('damping', 'frequency1_hz', frequency1_hz, err)
         call require_positive('damping', 'frequency2_hz', frequency2_hz, err)
         call require_nonnegative('damping', 'ratio1', ratio1, err)
         call require_nonnegative('damping', 'ratio2', ratio2, err)
         if (allocated(err)) return
         if (frequency2_hz <= frequency1_hz) then
            call fatal_error(err, 'group &damping: frequency2_hz = ' // str(frequency2_hz) &
               // ': must be > frequency1_hz = ' // str(frequency1_hz))
            return
         end if
         call rayleigh_from_ratios(frequency1_hz, ratio1, frequency2_hz, ratio2, &
            mass_coefficient, stiffness_coefficient)
         if (mass_coefficient < 0.0_dp .or. stiffness_coefficient < 0.0_dp) then
            call fatal_error(err, 'group &damping: the ratios (' // str(ratio1) // ' at ' &
               // str(frequency1_hz) // ' Hz, ' // str(ratio2) // ' at ' // str(frequency2_hz) &
               // ' Hz) give a negative Rayleigh coefficient (beta = ' // str(mass_coefficient) &
               // ' 1/s, gamma = ' // str(stiffness_coefficient) // ' s): not allowed')
         end if
      end select
      if (allocated(err)) return
      cfg = damping_t(model=model, mass_coefficient=mass_coefficient, &
         stiffness_coefficient=stiffness_coefficient, frequency1_hz=frequency1_hz, &
         ratio1=ratio1, frequency2_hz=frequency2_hz, ratio2=ratio2)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=damping, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_damping

   subroutine read_forcing(srcs, st, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(structure_t), intent(in) :: st
      type(forcing_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      real(dp) :: frequency_hz, amplitude_pp, direction_deg, phase_v_deg
      namelist /forcing/ frequency_hz, amplitude_pp, direction_deg, phase_v_deg
      frequency_hz = cfg%frequency_hz;  amplitude_pp = cfg%amplitude_pp
      direction_deg = cfg%direction_deg;  phase_v_deg = cfg%phase_v_deg
      call apply_group(srcs, 'forcing', 'frequency_hz amplitude_pp direction_deg phase_v_deg', &
         reader, err)
      if (allocated(err)) return
      call require_positive('forcing', 'frequency_hz', frequency_hz, err)
      call require_nonnegative('forcing', 'amplitude_pp', amplitude_pp, err)
      ! a base motion beyond sqrt(huge) m makes every point diverge (a sweep whose axes are
      ! other variables would fail each point instead of refusing the deck); a sweep's own
      ! amplitude axis values are checked per point (a failed point, marked)
      if (.not. allocated(err) .and. amplitude_pp > sqrt(huge(1.0_dp))) call fatal_error(err, &
         'group &forcing: amplitude_pp = ' // str(amplitude_pp) // ' m: must be at most ' &
         // str(sqrt(huge(1.0_dp))) // ' m')
      call require_range('forcing', 'direction_deg', direction_deg, -360.0_dp, 360.0_dp, err)
      call require_range('forcing', 'phase_v_deg', phase_v_deg, -360.0_dp, 360.0_dp, err)
      if (allocated(err)) return
      if ((direction_deg /= 0.0_dp .or. phase_v_deg /= 0.0_dp) .and. st%beam%planes < 2) then
         call fatal_error(err, 'group &forcing: direction_deg = ' // str(direction_deg) &
            // ', phase_v_deg = ' // str(phase_v_deg) // ': a base motion out of the w plane ' &
            // 'needs &beam planes = 2')
         return
      end if
      cfg = forcing_t(frequency_hz=frequency_hz, amplitude_pp=amplitude_pp, &
         direction_deg=direction_deg, phase_v_deg=phase_v_deg)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=forcing, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_forcing

   !> &point_forces: harmonic forces F sin(Omega t + phase) at node dofs, at the forcing
   !> frequency.
   subroutine read_point_forces(srcs, st, list, err)
      type(source_t), intent(in) :: srcs(:)
      type(structure_t), intent(in) :: st
      type(point_force_t), allocatable, intent(out) :: list(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: node(nmax), given(nmax), n, i, code
      character(len=8) :: dof(nmax)
      real(dp) :: amplitude(nmax), phase_deg(nmax)
      character(len=*), parameter :: vars = 'node() dof():8 amplitude() phase_deg()'
      namelist /point_forces/ node, dof, amplitude, phase_deg
      node = -1;  dof = 'w';  amplitude = 0.0_dp;  phase_deg = 0.0_dp
      call apply_group(srcs, 'point_forces', vars, reader, err)
      if (allocated(err)) return
      given = node
      node = -2
      call apply_group(srcs, 'point_forces', vars, reader, err)
      call list_entries('point_forces', 'node', given, node, n, err)
      if (allocated(err)) return
      block
         real(dp) :: s_amplitude(nmax), s_phase(nmax)
         character(len=8) :: s_dof(nmax)
         s_amplitude = amplitude;  s_phase = phase_deg;  s_dof = dof
         amplitude = list_marker;  phase_deg = list_marker;  dof = list_word_marker
         call apply_group(srcs, 'point_forces', vars, reader, err)
         call no_entries_beyond('point_forces', 'amplitude', amplitude, n, err)
         call no_entries_beyond('point_forces', 'phase_deg', phase_deg, n, err)
         call no_words_beyond('point_forces', 'dof', dof, n, err)
         amplitude = s_amplitude;  phase_deg = s_phase;  dof = s_dof
         if (allocated(err)) return
      end block
      allocate(list(n))
      do i = 1, n
         call require_word('point_forces', 'dof(' // str(i) // ')', dof(i), dof_words, err)
         code = dof_code(dof(i))
         call require_node('point_forces', 'node', i, node(i), code, st, err)
         call require_range('point_forces', 'amplitude(' // str(i) // ')', amplitude(i), &
            -1.0e12_dp, 1.0e12_dp, err)
         call require_range('point_forces', 'phase_deg(' // str(i) // ')', phase_deg(i), &
            -360.0_dp, 360.0_dp, err)
         if (allocated(err)) return
         list(i) = point_force_t(node=node(i), dof=code, amplitude=amplitude(i), &
                                 phase_deg=phase_deg(i))
      end do
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=point_forces, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_point_forces

   subroutine read_solver(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(solver_settings_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=24) :: method, stop_solution, step_control, linear_solver
      real(dp) :: newmark_delta, newmark_alpha, fp_tolerance, half_step_tolerance, &
         residual_floor, grow_ratio, hht_alpha, rho_infinity, rk_rtol, rk_atol, energy_bound, &
         tolerance, ticks
      real(dp), parameter :: unset = -huge(1.0_dp)
      integer :: fp_max_iterations, steps_per_period, max_halvings, grow_after, &
         transient_periods, record_periods
      logical :: locate_events
      character(len=:), allocatable :: why
      namelist /solver/ method, tolerance, newmark_delta, newmark_alpha, hht_alpha, &
         rho_infinity, rk_rtol, rk_atol, energy_bound, stop_solution, fp_tolerance, &
         fp_max_iterations, step_control, steps_per_period, half_step_tolerance, &
         residual_floor, max_halvings, grow_after, grow_ratio, locate_events, linear_solver, &
         transient_periods, record_periods
      method = cfg%method;  newmark_delta = cfg%newmark_delta;  newmark_alpha = cfg%newmark_alpha
      tolerance = unset;  rk_rtol = unset    ! not given (rk_rtol stands in for tolerance)
      hht_alpha = cfg%hht_alpha;  rho_infinity = cfg%rho_infinity
      rk_atol = cfg%rk_atol;  energy_bound = cfg%energy_bound
      stop_solution = cfg%stop_solution;  fp_tolerance = cfg%fp_tolerance
      fp_max_iterations = cfg%fp_max_iterations;  step_control = cfg%step_control
      steps_per_period = cfg%steps_per_period;  half_step_tolerance = cfg%half_step_tolerance
      residual_floor = cfg%residual_floor;  max_halvings = cfg%max_halvings
      grow_after = cfg%grow_after;  grow_ratio = cfg%grow_ratio
      locate_events = cfg%locate_events;  linear_solver = cfg%linear_solver
      transient_periods = cfg%transient_periods;  record_periods = cfg%record_periods
      call apply_group(srcs, 'solver', 'method:24 tolerance newmark_delta newmark_alpha ' &
         // 'hht_alpha rho_infinity rk_rtol rk_atol energy_bound stop_solution:24 ' &
         // 'fp_tolerance fp_max_iterations step_control:24 steps_per_period ' &
         // 'half_step_tolerance residual_floor max_halvings grow_after grow_ratio ' &
         // 'locate_events linear_solver:24 transient_periods record_periods', reader, err)
      if (allocated(err)) return
      ! rk_rtol (the rk45 tolerance before `tolerance` existed) sets tolerance for rk45 decks
      if (tolerance == unset .and. rk_rtol /= unset .and. method == 'rk45') tolerance = rk_rtol
      if (tolerance == unset) tolerance = cfg%tolerance
      if (rk_rtol == unset) rk_rtol = cfg%rk_rtol
      call require_word('solver', 'method', method, method_words, err)
      call require_range('solver', 'tolerance', tolerance, 1.0e-12_dp, 0.5_dp, err)
      call require_range('solver', 'newmark_delta', newmark_delta, 0.5_dp, 1.0_dp, err)
      call require_range('solver', 'newmark_alpha', newmark_alpha, 1.0e-3_dp, 1.0_dp, err)
      call require_range('solver', 'hht_alpha', hht_alpha, -1.0_dp / 3.0_dp, 0.0_dp, err)
      call require_range('solver', 'rho_infinity', rho_infinity, 0.0_dp, 1.0_dp, err)
      call require_range('solver', 'rk_rtol', rk_rtol, 1.0e-14_dp, 1.0_dp, err)
      call require_range('solver', 'rk_atol', rk_atol, 0.0_dp, 1.0_dp, err)
      call require_range('solver', 'energy_bound', energy_bound, 1.0_dp, 1.0e300_dp, err)
      call require_word('solver', 'stop_solution', stop_solution, stop_solution_words, err)
      call require_range('solver', 'fp_tolerance', fp_tolerance, 1.0e-15_dp, 0.1_dp, err)
      call require_int('solver', 'fp_max_iterations', fp_max_iterations, 1, 100000, err)
      call require_word('solver', 'step_control', step_control, step_control_words, err)
      call require_int('solver', 'steps_per_period', steps_per_period, 4, 100000000, err)
      call require_range('solver', 'half_step_tolerance', half_step_tolerance, 1.0e-8_dp, &
         10.0_dp, err)
      call require_range('solver', 'residual_floor', residual_floor, 0.0_dp, 1.0_dp, err)
      call require_int('solver', 'max_halvings', max_halvings, 0, 40, err)
      call require_int('solver', 'grow_after', grow_after, 1, 100000, err)
      call require_range('solver', 'grow_ratio', grow_ratio, 0.0_dp, 1.0_dp, err)
      call require_word('solver', 'linear_solver', linear_solver, linear_solver_words, err)
      call require_int('solver', 'transient_periods', transient_periods, 0, huge(1), err)
      call require_int('solver', 'record_periods', record_periods, 1, max_periods, err, &
         'every recorded period keeps its Poincare point')
      if (allocated(err)) return
      ! combinations of method, step control and stop solution: what the method's registry
      ! entry takes (gapbeam_capabilities)
      why = solver_refusal(method, step_control, stop_solution)
      if (len(why) > 0) call fatal_error(err, 'group &solver: ' // why)
      if (allocated(err)) return
      ! time is counted in integer ticks of T / (steps_per_period 2^max_halvings); the sum is
      ! taken in real arithmetic, as two periods near huge(1) overflow an integer
      ticks = (real(transient_periods, dp) + real(record_periods, dp)) &
              * real(steps_per_period, dp) * 2.0_dp**max_halvings
      if (.not. (ticks < 2.0_dp**62)) then
         call fatal_error(err, 'group &solver: (transient_periods + record_periods) * ' &
            // 'steps_per_period * 2**max_halvings = ' // str(ticks) // ' ticks: must ' &
            // 'be below 2**62; lower transient_periods, record_periods, max_halvings or ' &
            // 'steps_per_period')
         return
      end if
      cfg = solver_settings_t(method=method, tolerance=tolerance, newmark_delta=newmark_delta, &
         newmark_alpha=newmark_alpha, hht_alpha=hht_alpha, rho_infinity=rho_infinity, &
         rk_rtol=rk_rtol, rk_atol=rk_atol, energy_bound=energy_bound, &
         stop_solution=stop_solution, fp_tolerance=fp_tolerance, &
         fp_max_iterations=fp_max_iterations, step_control=step_control, &
         steps_per_period=steps_per_period, half_step_tolerance=half_step_tolerance, &
         residual_floor=residual_floor, max_halvings=max_halvings, grow_after=grow_after, &
         grow_ratio=grow_ratio, locate_events=locate_events, linear_solver=linear_solver, &
         transient_periods=transient_periods, record_periods=record_periods)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=solver, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_solver

   subroutine read_initial(srcs, st, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(structure_t), intent(in) :: st
      type(initial_state_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=16) :: kind
      integer :: node(nmax), given(nmax), n, i, code(nmax)
      character(len=8) :: dof(nmax)
      real(dp) :: displacement(nmax), velocity(nmax)
      namelist /initial/ kind, node, dof, displacement, velocity
      kind = cfg%kind;  node = -1;  dof = 'w';  displacement = 0.0_dp;  velocity = 0.0_dp
      call apply_group(srcs, 'initial', 'kind:16 node() dof():8 displacement() velocity()', &
         reader, err)
      if (allocated(err)) return
      given = node
      node = -2
      call apply_group(srcs, 'initial', 'kind:16 node() dof():8 displacement() velocity()', &
         reader, err)
      call list_entries('initial', 'node', given, node, n, err)
      if (allocated(err)) return
      call require_word('initial', 'kind', kind, initial_state_words, err)
      code = 0
      do i = 1, n
         call require_word('initial', 'dof(' // str(i) // ')', dof(i), dof_words, err)
         code(i) = dof_code(dof(i))
         call require_node('initial', 'node', i, node(i), code(i), st, err)
      end do
      if (kind == 'given' .and. n == 0 .and. .not. allocated(err)) call fatal_error(err, &
         "group &initial: kind = 'given' needs node, dof, displacement and velocity lists")
      if (allocated(err)) return
      cfg%kind = kind
      cfg%node = node(1:n);  cfg%dof = code(1:n)
      cfg%displacement = displacement(1:n);  cfg%velocity = velocity(1:n)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=initial, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_initial

   subroutine read_output(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(output_settings_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      real(dp) :: poincare_phase_deg, filter_cutoff_hz
      integer :: samples_per_period, history_periods, filter_order, filter_samples_per_period, &
         shape_points
      logical :: write_text, state_history, energy_balance
      namelist /output/ poincare_phase_deg, samples_per_period, history_periods, write_text, &
         filter_cutoff_hz, filter_order, filter_samples_per_period, state_history, shape_points, &
         energy_balance
      energy_balance = cfg%energy_balance
      poincare_phase_deg = cfg%poincare_phase_deg;  samples_per_period = cfg%samples_per_period
      history_periods = cfg%history_periods;  write_text = cfg%write_text
      filter_cutoff_hz = cfg%filter_cutoff_hz;  filter_order = cfg%filter_order
      filter_samples_per_period = cfg%filter_samples_per_period
      state_history = cfg%state_history;  shape_points = cfg%shape_points
      call apply_group(srcs, 'output', 'poincare_phase_deg samples_per_period history_periods ' &
         // 'write_text filter_cutoff_hz filter_order filter_samples_per_period state_history ' &
         // 'shape_points energy_balance', reader, err)
      if (allocated(err)) return
      call require_range('output', 'poincare_phase_deg', poincare_phase_deg, 0.0_dp, &
         360.0_dp, err)
      call require_int('output', 'samples_per_period', samples_per_period, 1, 100000, err)
      call require_int('output', 'history_periods', history_periods, 0, huge(1), err)
      if (allocated(err)) return
      ! history samples: min(history_periods, record_periods) x samples_per_period, checked in
      ! read_deck once &solver is known
      call require_nonnegative('output', 'filter_cutoff_hz', filter_cutoff_hz, err)
      call require_int('output', 'filter_order', filter_order, 1, 12, err)
      call require_int('output', 'filter_samples_per_period', filter_samples_per_period, 16, &
         1000000, err)
      call require_int('output', 'shape_points', shape_points, 1, 1000, err)
      if (allocated(err)) return
      if (filter_cutoff_hz > 0.0_dp .and. mod(filter_samples_per_period, samples_per_period) &
          /= 0) then
         call fatal_error(err, 'group &output: filter_samples_per_period = ' &
            // str(filter_samples_per_period) // ': must be a multiple of samples_per_period = ' &
            // str(samples_per_period) // ' (the filtered history is taken at the filter samples)')
         return
      end if
      cfg = output_settings_t(poincare_phase_deg=poincare_phase_deg, &
         samples_per_period=samples_per_period, history_periods=history_periods, &
         write_text=write_text, filter_cutoff_hz=filter_cutoff_hz, filter_order=filter_order, &
         filter_samples_per_period=filter_samples_per_period, state_history=state_history, &
         shape_points=shape_points, energy_balance=energy_balance)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=output, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_output

   subroutine read_diagnostics(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(diagnostics_settings_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      integer :: period_max, period_points, lyapunov_periods, lyapunov_max_periods, &
         settle_windows, transient_max_periods, random_starts, random_seed, j, k
      real(dp) :: period_tolerance, lyapunov_perturbation, chaos_sigmas, lyapunov_rel_error, &
         lyapunov_abs_error, settle_tolerance, certify_ratio, certify_perturbation, &
         orbit_tolerance, random_amplitude
      logical :: certify
      character(len=8) :: starts(8)
      namelist /diagnostics/ period_max, period_tolerance, period_points, lyapunov_periods, &
         lyapunov_perturbation, chaos_sigmas, lyapunov_max_periods, lyapunov_rel_error, &
         lyapunov_abs_error, settle_windows, settle_tolerance, transient_max_periods, &
         certify, certify_ratio, certify_perturbation, orbit_tolerance, starts, &
         random_starts, random_seed, random_amplitude
      period_max = cfg%period_max;  period_tolerance = cfg%period_tolerance
      period_points = cfg%period_points;  lyapunov_periods = cfg%lyapunov_periods
      lyapunov_perturbation = cfg%lyapunov_perturbation;  chaos_sigmas = cfg%chaos_sigmas
      lyapunov_max_periods = cfg%lyapunov_max_periods
      lyapunov_rel_error = cfg%lyapunov_rel_error;  lyapunov_abs_error = cfg%lyapunov_abs_error
      settle_windows = cfg%settle_windows;  settle_tolerance = cfg%settle_tolerance
      transient_max_periods = cfg%transient_max_periods;  certify = cfg%certify
      certify_ratio = cfg%certify_ratio;  certify_perturbation = cfg%certify_perturbation
      orbit_tolerance = cfg%orbit_tolerance;  starts = cfg%starts
      random_starts = cfg%random_starts;  random_seed = cfg%random_seed
      random_amplitude = cfg%random_amplitude
      call apply_group(srcs, 'diagnostics', 'period_max period_tolerance period_points ' &
         // 'lyapunov_periods lyapunov_perturbation chaos_sigmas lyapunov_max_periods ' &
         // 'lyapunov_rel_error lyapunov_abs_error settle_windows settle_tolerance ' &
         // 'transient_max_periods certify certify_ratio certify_perturbation ' &
         // 'orbit_tolerance starts():8 random_starts random_seed random_amplitude', reader, err)
      if (allocated(err)) return
      call require_int('diagnostics', 'period_max', period_max, 1, 1000, err)
      if (period_tolerance /= 0.0_dp) call require_range('diagnostics', 'period_tolerance', &
         period_tolerance, 1.0e-12_dp, 0.5_dp, err)
      call require_int('diagnostics', 'period_points', period_points, 1, huge(1), err)
      call require_int('diagnostics', 'lyapunov_periods', lyapunov_periods, 0, max_periods, err, &
         'every period keeps its running estimate')
      call require_int('diagnostics', 'lyapunov_max_periods', lyapunov_max_periods, 0, &
         max_periods, err, '0: 20 x lyapunov_periods')
      if (lyapunov_max_periods > 0) call require_int('diagnostics', 'lyapunov_max_periods', &
         lyapunov_max_periods, lyapunov_periods, max_periods, err, 'at least lyapunov_periods = ' &
         // str(lyapunov_periods) // '; 0: 20 x lyapunov_periods')
      call require_range('diagnostics', 'lyapunov_rel_error', lyapunov_rel_error, 0.0_dp, &
         10.0_dp, err)
      call require_range('diagnostics', 'lyapunov_abs_error', lyapunov_abs_error, 0.0_dp, &
         1.0e6_dp, err)
      call require_range('diagnostics', 'lyapunov_perturbation', lyapunov_perturbation, &
         1.0e-14_dp, 1.0e-2_dp, err)
      call require_range('diagnostics', 'chaos_sigmas', chaos_sigmas, 0.0_dp, 100.0_dp, err)
      call require_int('diagnostics', 'settle_windows', settle_windows, 0, 100, err, &
         '0: no settling test; 1 is not allowed')
      if (settle_windows == 1) call require_int('diagnostics', 'settle_windows', &
         settle_windows, 2, 100, err, '0: no settling test; 1 is not allowed')
      call require_range('diagnostics', 'settle_tolerance', settle_tolerance, 1.0e-6_dp, &
         10.0_dp, err)
      call require_int('diagnostics', 'transient_max_periods', transient_max_periods, 0, &
         max_periods, err, '0: 10 x &solver transient_periods')
      call require_range('diagnostics', 'certify_ratio', certify_ratio, 1.5_dp, 1.0e4_dp, err)
      call require_range('diagnostics', 'certify_perturbation', certify_perturbation, &
         1.0e-12_dp, 1.0_dp, err)
      call require_range('diagnostics', 'orbit_tolerance', orbit_tolerance, 1.0e-12_dp, &
         1.0_dp, err)
      call require_int('diagnostics', 'random_starts', random_starts, 1, 1000, err)
      call require_nonnegative('diagnostics', 'random_amplitude', random_amplitude, err)
      if (allocated(err)) return
      do j = 1, size(starts)
         if (len_trim(starts(j)) == 0) then
            if (any(len_trim(starts(j + 1:)) > 0)) call fatal_error(err, 'group &diagnostics: ' &
               // 'starts(' // str(j) // ") is empty but a later entry is given: list the " &
               // 'starts from starts(1) on, without gaps')
            exit
         end if
         call require_word('diagnostics', 'starts(' // str(j) // ')', starts(j), start_words, &
                           err)
         do k = 1, j - 1
            if (starts(k) == starts(j) .and. .not. allocated(err)) call fatal_error(err, &
               'group &diagnostics: starts(' // str(j) // ") = '" // trim(starts(j)) &
               // "' is also starts(" // str(k) // '): each start at most once (' &
               // "'random' gives random_starts states)")
         end do
      end do
      if (allocated(err)) return
      cfg = diagnostics_settings_t(period_max=period_max, period_tolerance=period_tolerance, &
         period_points=period_points, lyapunov_periods=lyapunov_periods, &
         lyapunov_max_periods=lyapunov_max_periods, lyapunov_rel_error=lyapunov_rel_error, &
         lyapunov_abs_error=lyapunov_abs_error, lyapunov_perturbation=lyapunov_perturbation, &
         chaos_sigmas=chaos_sigmas, settle_windows=settle_windows, &
         settle_tolerance=settle_tolerance, transient_max_periods=transient_max_periods, &
         certify=certify, certify_ratio=certify_ratio, &
         certify_perturbation=certify_perturbation, orbit_tolerance=orbit_tolerance, &
         starts=starts, random_starts=random_starts, random_seed=random_seed, &
         random_amplitude=random_amplitude)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=diagnostics, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_diagnostics

   !> &sweep. The axes: x is '&forcing frequency_hz' (values from frequency_hz or its range)
   !> and y '&forcing amplitude_pp' (amplitude_pp or its range) unless x_variable / y_variable
   !> name other numeric deck variables, whose values come from x_values / y_values or their
   !> ranges (x_start, x_end, n_x; the deck's value when neither is given). Every value is
   !> checked by setting it on a copy of the deck (gapbeam_deck_variable).
   subroutine read_sweep(srcs, deck, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(deck_t), intent(in) :: deck                   !! deck read so far
      type(sweep_settings_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: vars = 'mode:16 direction:16 axis:16 frequency_hz() ' &
         // 'amplitude_pp() frequency_start_hz frequency_end_hz n_frequency amplitude_start_pp ' &
         // 'amplitude_end_pp n_amplitude progress chunk checkpoint x_variable:160 ' &
         // 'y_variable:160 x_values() y_values() x_start x_end n_x y_start y_end n_y'
      character(len=16) :: mode, direction, axis
      character(len=160) :: x_variable, y_variable
      real(dp), allocatable :: frequency_hz(:), amplitude_pp(:), f_given(:), a_given(:), &
         x_values(:), y_values(:), x_given(:), y_given(:), fa(:), aa(:)
      real(dp) :: frequency_start_hz, frequency_end_hz, amplitude_start_pp, amplitude_end_pp, &
         x_start, x_end, y_start, y_end
      integer :: n_frequency, n_amplitude, chunk, nf, na, n_x, n_y, nx, ny
      logical :: progress, checkpoint
      type(deck_variable_t) :: var(2)
      type(deck_variable_t), allocatable :: xvars(:), yvars(:)
      namelist /sweep/ mode, direction, axis, frequency_hz, amplitude_pp, frequency_start_hz, &
         frequency_end_hz, n_frequency, amplitude_start_pp, amplitude_end_pp, n_amplitude, &
         progress, chunk, checkpoint, x_variable, y_variable, x_values, y_values, x_start, &
         x_end, n_x, y_start, y_end, n_y
      allocate(frequency_hz(naxis), amplitude_pp(naxis), x_values(naxis), y_values(naxis))
      mode = cfg%mode;  direction = cfg%direction;  axis = cfg%axis
      x_variable = cfg%x_variable;  y_variable = cfg%y_variable
      frequency_hz = -1.0_dp;  amplitude_pp = -1.0_dp;  x_values = -1.0_dp;  y_values = -1.0_dp
      frequency_start_hz = 0.0_dp;  frequency_end_hz = 0.0_dp;  n_frequency = 0
      amplitude_start_pp = 0.0_dp;  amplitude_end_pp = 0.0_dp;  n_amplitude = 0
      x_start = 0.0_dp;  x_end = 0.0_dp;  n_x = 0;  y_start = 0.0_dp;  y_end = 0.0_dp;  n_y = 0
      progress = cfg%progress;  chunk = cfg%chunk;  checkpoint = cfg%checkpoint
      call apply_group(srcs, 'sweep', vars, reader, err)
      if (allocated(err)) return
      ! the lists are read twice, from two markers, to tell the entries given (-1 included)
      f_given = frequency_hz;  a_given = amplitude_pp;  x_given = x_values;  y_given = y_values
      frequency_hz = -2.0_dp;  amplitude_pp = -2.0_dp;  x_values = -2.0_dp;  y_values = -2.0_dp
      call apply_group(srcs, 'sweep', vars, reader, err)
      call list_entries('sweep', 'frequency_hz', f_given, frequency_hz, nf, err)
      call list_entries('sweep', 'amplitude_pp', a_given, amplitude_pp, na, err)
      call list_entries('sweep', 'x_values', x_given, x_values, nx, err)
      call list_entries('sweep', 'y_values', y_given, y_values, ny, err)
      call require_word('sweep', 'mode', mode, sweep_mode_words, err)
      call require_word('sweep', 'direction', direction, sweep_direction_words, err)
      call require_word('sweep', 'axis', axis, sweep_axis_words, err)
      call require_int('sweep', 'chunk', chunk, 0, huge(1), err)
      call require_int('sweep', 'n_frequency', n_frequency, 0, max_axis, err)
      call require_int('sweep', 'n_amplitude', n_amplitude, 0, max_axis, err)
      call require_int('sweep', 'n_x', n_x, 0, max_axis, err)
      call require_int('sweep', 'n_y', n_y, 0, max_axis, err)
      if (allocated(err)) return
      call sweep_variable('x_variable', x_variable, deck, xvars, err)
      call sweep_variable('y_variable', y_variable, deck, yvars, err)
      if (allocated(err)) return
      ! an axis of several variables is led by its first (forcing variables stand alone)
      var(1) = xvars(1);  var(2) = yvars(1)
      block
         integer :: i, j
         do i = 1, size(xvars)
            do j = 1, size(yvars)
               if (deck_variable_label(xvars(i)) == deck_variable_label(yvars(j))) then
                  call fatal_error(err, "group &sweep: x_variable and y_variable both name '" &
                     // deck_variable_label(xvars(i)) // "': the two axes need two variables")
                  return
               end if
            end do
         end do
      end block
      call make_axis('frequency_hz', 'frequency_start_hz', 'frequency_end_hz', 'n_frequency', &
         frequency_hz(1:nf), frequency_start_hz, frequency_end_hz, n_frequency, &
         deck%forcing%frequency_hz, .true., fa, err)
      if (allocated(err)) return
      call make_axis('amplitude_pp', 'amplitude_start_pp', 'amplitude_end_pp', 'n_amplitude', &
         amplitude_pp(1:na), amplitude_start_pp, amplitude_end_pp, n_amplitude, &
         deck%forcing%amplitude_pp, .false., aa, err)
      if (allocated(err)) return
      ! a forcing list given while no axis is that variable would be ignored silently
      if ((nf > 0 .or. n_frequency > 0) .and. &
          .not. any(label_of(var) == '&forcing frequency_hz')) call fatal_error(err, &
         'group &sweep: frequency_hz (or n_frequency) is given but ' &
         // "neither x_variable nor y_variable is '&forcing frequency_hz'")
      if ((na > 0 .or. n_amplitude > 0) .and. &
          .not. any(label_of(var) == '&forcing amplitude_pp')) call fatal_error(err, &
         'group &sweep: amplitude_pp (or n_amplitude) is given but ' &
         // "neither x_variable nor y_variable is '&forcing amplitude_pp'")
      if (allocated(err)) return
      call variable_axis(1, xvars, x_values(1:nx), x_start, x_end, n_x, fa, aa, deck, cfg%x, err)
      if (allocated(err)) return
      call variable_axis(2, yvars, y_values(1:ny), y_start, y_end, n_y, fa, aa, deck, cfg%y, err)
      if (allocated(err)) return
      if (int(size(cfg%x), int64) * size(cfg%y) > max_points) then
         call fatal_error(err, 'group &sweep: ' // str(size(cfg%x)) // ' values of x (' &
            // axis_source(var(1), 'x') // ') x ' // str(size(cfg%y)) // ' values of y (' &
            // axis_source(var(2), 'y') // ') = ' // str_int64(int(size(cfg%x), int64) &
            * size(cfg%y)) // ' points: at most ' // str(max_points) &
            // ' points in one sweep (split the map into several decks)')
         return
      end if
      cfg%frequency_hz = fa;  cfg%amplitude_pp = aa
      if (deck_variable_label(var(1)) == '&forcing frequency_hz') cfg%frequency_hz = cfg%x
      if (deck_variable_label(var(2)) == '&forcing frequency_hz') cfg%frequency_hz = cfg%y
      if (deck_variable_label(var(1)) == '&forcing amplitude_pp') cfg%amplitude_pp = cfg%x
      if (deck_variable_label(var(2)) == '&forcing amplitude_pp') cfg%amplitude_pp = cfg%y
      if (all(label_of(var) /= '&forcing frequency_hz')) cfg%frequency_hz = &
         [deck%forcing%frequency_hz]
      if (all(label_of(var) /= '&forcing amplitude_pp')) cfg%amplitude_pp = &
         [deck%forcing%amplitude_pp]
      cfg%x_variable = deck_variables_label(xvars);  cfg%y_variable = deck_variables_label(yvars)
      cfg%mode = mode;  cfg%direction = direction;  cfg%axis = axis
      cfg%progress = progress;  cfg%chunk = chunk;  cfg%checkpoint = checkpoint
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=sweep, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_sweep

   !> Where the values of a sweep axis come from, for messages.
   pure function axis_source(var, c) result(t)
      type(deck_variable_t), intent(in) :: var           !! the axis variable
      character(len=1), intent(in) :: c                  !! 'x' or 'y'
      character(len=:), allocatable :: t
      if (deck_variable_label(var) == '&forcing frequency_hz') then
         t = "'&forcing frequency_hz': frequency_hz or n_frequency"
      else if (deck_variable_label(var) == '&forcing amplitude_pp') then
         t = "'&forcing amplitude_pp': amplitude_pp or n_amplitude"
      else
         t = "'" // deck_variable_label(var) // "': " // c // '_values or n_' // c
      end if
   end function axis_source

   !> Labels of sweep variables ('&forcing frequency_hz', '&stops gap(1)').
   pure function label_of(var) result(t)
      type(deck_variable_t), intent(in) :: var(:)       !! variables
      character(len=64) :: t(size(var))
      integer :: k
      do k = 1, size(var)
         t(k) = deck_variable_label(var(k))
      end do
   end function label_of

   !> Parse and check one axis variable of &sweep.
   subroutine sweep_variable(name, text, deck, vars, err)
      character(len=*), intent(in) :: name               !! 'x_variable' or 'y_variable'
      character(len=*), intent(in) :: text               !! its value: names, comma separated
      type(deck_t), intent(in) :: deck                   !! deck read so far
      type(deck_variable_t), allocatable, intent(out) :: vars(:)   !! parsed
      type(error_t), allocatable, intent(inout) :: err   !! unknown or absent variable
      integer :: j
      if (allocated(err)) return
      call parse_deck_variables(text, vars, err)
      do j = 1, size(vars)
         if (.not. allocated(err)) call check_deck_variable(deck, vars(j), err)
      end do
      if (allocated(err)) err%message = "group &sweep: " // name // " = '" // trim(text) &
         // "': " // err%message
   end subroutine sweep_variable

   !> Values of axis j: the forcing axes from their own lists, another variable from
   !> values / start-end-count or the deck's value; each value checked on a deck copy.
   subroutine variable_axis(j, vars, list, x0, x1, n, fa, aa, deck, axis_out, err)
      integer, intent(in) :: j                           !! 1: x, 2: y
      type(deck_variable_t), intent(in) :: vars(:)       !! the axis variables (one or more)
      real(dp), intent(in) :: list(:)                    !! x_values / y_values given
      real(dp), intent(in) :: x0, x1                     !! range ends
      integer, intent(in) :: n                           !! range count (0: none)
      real(dp), intent(in) :: fa(:), aa(:)               !! frequency and amplitude axes
      type(deck_t), intent(in) :: deck                   !! deck read so far
      real(dp), allocatable, intent(out) :: axis_out(:)  !! values
      type(error_t), allocatable, intent(inout) :: err   !! bad value
      character(len=1) :: c
      type(deck_t) :: d
      type(deck_variable_t) :: var
      integer :: k, i
      if (allocated(err)) return
      c = merge('x', 'y', j == 1)
      var = vars(1)
      if (deck_variable_label(var) == '&forcing frequency_hz' .or. &
          deck_variable_label(var) == '&forcing amplitude_pp') then
         if (size(list) > 0 .or. n > 0) then
            call fatal_error(err, 'group &sweep: ' // c // '_values (or n_' // c // ") is " &
               // "given for '" // deck_variable_label(var) // "': give its values as " &
               // trim(merge('frequency_hz', 'amplitude_pp', var%name == 'frequency_hz')) &
               // ' (or its range) instead')
            return
         end if
         if (var%name == 'frequency_hz') then
            axis_out = fa
         else
            axis_out = aa
         end if
         return
      end if
      if (size(list) > 0 .and. n > 0) then
         call fatal_error(err, 'group &sweep: give either the list ' // c // '_values or ' &
            // c // '_start, ' // c // '_end and n_' // c // ', not both')
         return
      end if
      if (size(list) > 0) then
         axis_out = list
      else if (n == 1) then
         axis_out = [x0]
      else if (n > 1) then
         axis_out = [(x0 + (x1 - x0) * real(k - 1, dp) / real(n - 1, dp), k = 1, n)]
         if (.not. all(ieee_is_finite(axis_out))) then
            call fatal_error(err, 'group &sweep: ' // c // '_start = ' // str(x0) // ', ' // c &
               // '_end = ' // str(x1) // ': the range between them overflows (its values ' &
               // 'must be finite)')
            return
         end if
      else
         axis_out = [get_deck_value(deck, var)]
      end if
      do k = 1, size(axis_out)
         d = deck
         do i = 1, size(vars)
            call set_deck_value(d, vars(i), axis_out(k), err)
            if (allocated(err)) then
               err%message = 'group &sweep: ' // c // " axis ('" // deck_variable_label(vars(i)) &
                  // "') value " // str(k) // ': ' // err%message
               return
            end if
         end do
      end do
   end subroutine variable_axis

   !> A sweep axis from the list `list` (the entries given), or from start, end and count
   !> (`x0`, `x1`, `n`); `default` (the &forcing value) if neither is given.
   subroutine make_axis(vlist, vstart, vend, vn, list, x0, x1, n, default, positive, axis_out, &
                        err)
      character(len=*), intent(in) :: vlist, vstart, vend, vn   !! variable names, for messages
      real(dp), intent(in) :: list(:)                 !! the list entries given
      real(dp), intent(in) :: x0, x1                  !! first and last value of a range
      integer, intent(in) :: n                        !! values of the range (0: no range)
      real(dp), intent(in) :: default                 !! value when neither is given
      logical, intent(in) :: positive                 !! values must be > 0 (else >= 0)
      real(dp), allocatable, intent(out) :: axis_out(:)  !! the axis
      type(error_t), allocatable, intent(inout) :: err   !! set on a bad axis
      integer :: j
      if (allocated(err)) return
      if (size(list) > 0 .and. n > 0) then
         call fatal_error(err, 'group &sweep: give either the list ' // vlist // ' or ' &
            // vstart // ', ' // vend // ' and ' // vn // ', not both')
         return
      end if
      if (size(list) > 0) then
         axis_out = list
      else if (n > 0) then
         if (positive) then
            call require_positive('sweep', vstart, x0, err)
            if (n > 1) call require_positive('sweep', vend, x1, err)
         else
            call require_nonnegative('sweep', vstart, x0, err)
            if (n > 1) call require_nonnegative('sweep', vend, x1, err)
         end if
         if (allocated(err)) return
         if (n == 1) then
            axis_out = [x0]
         else
            axis_out = [(x0 + (x1 - x0) * real(j - 1, dp) / real(n - 1, dp), j = 1, n)]
            if (.not. all(ieee_is_finite(axis_out))) then
               call fatal_error(err, 'group &sweep: ' // vstart // ' = ' // str(x0) // ', ' &
                  // vend // ' = ' // str(x1) // ': the range between them overflows (its ' &
                  // 'values must be finite)')
               return
            end if
         end if
      else
         axis_out = [default]
      end if
      do j = 1, size(axis_out)
         if (positive) then
            call require_positive('sweep', vlist // '(' // str(j) // ')', axis_out(j), err)
         else
            call require_nonnegative('sweep', vlist // '(' // str(j) // ')', axis_out(j), err)
         end if
      end do
   end subroutine make_axis

   subroutine read_reduction(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(reduction_settings_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=16) :: kind
      integer :: n_modes
      logical :: static_correction
      namelist /reduction/ kind, n_modes, static_correction
      kind = cfg%kind;  n_modes = cfg%n_modes;  static_correction = cfg%static_correction
      call apply_group(srcs, 'reduction', 'kind:16 n_modes static_correction', reader, err)
      if (allocated(err)) return
      call require_word('reduction', 'kind', kind, "'none', 'modal'", err)
      call require_int('reduction', 'n_modes', n_modes, 1, 100000, err)
      if (allocated(err)) return
      cfg = reduction_settings_t(kind=kind, n_modes=n_modes, static_correction=static_correction)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=reduction, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_reduction

   subroutine read_study(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(study_settings_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=32) :: series(16)
      integer :: levels, periods, base_steps, repeats, n_omega_dt, n, i
      real(dp) :: tolerance_start, rtol_start, omega_dt_min, omega_dt_max
      namelist /study/ series, levels, periods, base_steps, tolerance_start, rtol_start, &
         repeats, omega_dt_min, omega_dt_max, n_omega_dt
      series = ''   ! a shorter list in the deck must not inherit the default's tail
      levels = cfg%levels;  periods = cfg%periods;  base_steps = cfg%base_steps
      repeats = cfg%repeats;  n_omega_dt = cfg%n_omega_dt
      tolerance_start = cfg%tolerance_start;  rtol_start = cfg%rtol_start
      omega_dt_min = cfg%omega_dt_min;  omega_dt_max = cfg%omega_dt_max
      call apply_group(srcs, 'study', 'series():32 levels periods base_steps tolerance_start ' &
         // 'rtol_start repeats omega_dt_min omega_dt_max n_omega_dt', reader, err)
      if (allocated(err)) return
      if (all(len_trim(series) == 0)) series(1:10) = [character(len=32) :: 'auto', &
         'newmark_error', 'hht_error', 'generalized_alpha_error', 'rk45', 'newmark_half_step', &
         'newmark_fixed', 'paper', 'rk4', 'exact']
      n = 0
      do i = 1, size(series)
         if (len_trim(series(i)) == 0) exit
         call require_word('study', 'series(' // str(i) // ')', series(i), series_words, err)
         n = i
      end do
      call require_int('study', 'levels', levels, 1, 30, err)
      call require_int('study', 'periods', periods, 1, huge(1), err)
      call require_int('study', 'base_steps', base_steps, 4, 100000000, err)
      call require_int('study', 'repeats', repeats, 1, 100, err)
      call require_int('study', 'n_omega_dt', n_omega_dt, 2, 100000, err)
      call require_range('study', 'tolerance_start', tolerance_start, 1.0e-12_dp, 10.0_dp, err)
      call require_range('study', 'rtol_start', rtol_start, 1.0e-12_dp, 0.5_dp, err)
      call require_positive('study', 'omega_dt_min', omega_dt_min, err)
      call require_range('study', 'omega_dt_max', omega_dt_max, omega_dt_min, 1.0e12_dp, err)
      if (allocated(err)) return
      cfg%series = series(1:n)
      cfg%levels = levels;  cfg%periods = periods;  cfg%base_steps = base_steps
      cfg%repeats = repeats;  cfg%n_omega_dt = n_omega_dt
      cfg%tolerance_start = tolerance_start;  cfg%rtol_start = rtol_start
      cfg%omega_dt_min = omega_dt_min;  cfg%omega_dt_max = omega_dt_max
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=study, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_study

   subroutine read_model_size(srcs, cfg, err)
      type(source_t), intent(in) :: srcs(:)
      type(model_size_settings_t), intent(inout) :: cfg
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: vars = 'elements() modes() cutoff_hz frequency_tolerance ' &
         // 'poincare_tolerance force_tolerance'
      integer :: elements(16), modes(16), e_given(16), m_given(16), ne, nm, i
      real(dp) :: cutoff_hz, frequency_tolerance, poincare_tolerance, force_tolerance
      namelist /model_size/ elements, modes, cutoff_hz, frequency_tolerance, poincare_tolerance, &
         force_tolerance
      cutoff_hz = cfg%cutoff_hz;  frequency_tolerance = cfg%frequency_tolerance
      poincare_tolerance = cfg%poincare_tolerance;  force_tolerance = cfg%force_tolerance
      ! the lists are read twice, from two markers, to tell the entries given: a list in the
      ! deck replaces the default list whole (it does not inherit the default's tail)
      elements = -1;  modes = -1
      call apply_group(srcs, 'model_size', vars, reader, err)
      if (allocated(err)) return
      e_given = elements;  m_given = modes
      elements = -2;  modes = -2
      call apply_group(srcs, 'model_size', vars, reader, err)
      call list_entries('model_size', 'elements', e_given, elements, ne, err)
      call list_entries('model_size', 'modes', m_given, modes, nm, err)
      if (allocated(err)) return
      elements(ne + 1:) = 0;  modes(nm + 1:) = 0
      if (ne == 0) elements(1:7) = [2, 3, 4, 6, 8, 15, 30]
      if (nm == 0) modes(1:6) = [1, 2, 3, 4, 5, 6]
      do i = 1, size(elements)   ! zero entries are allowed and skipped
         call require_int('model_size', 'elements(' // str(i) // ')', elements(i), 0, 10000, err)
         call require_int('model_size', 'modes(' // str(i) // ')', modes(i), 0, 10000, err)
      end do
      ne = count(elements > 0)
      if (ne == 0 .and. .not. allocated(err)) call fatal_error(err, 'group &model_size: ' &
         // 'elements: give at least one element count')
      call require_positive('model_size', 'cutoff_hz', cutoff_hz, err)
      call require_positive('model_size', 'frequency_tolerance', frequency_tolerance, err)
      call require_positive('model_size', 'poincare_tolerance', poincare_tolerance, err)
      call require_positive('model_size', 'force_tolerance', force_tolerance, err)
      if (allocated(err)) return
      cfg%elements = pack(elements, elements > 0)
      cfg%modes = pack(modes, modes > 0)
      cfg%cutoff_hz = cutoff_hz;  cfg%frequency_tolerance = frequency_tolerance
      cfg%poincare_tolerance = poincare_tolerance;  cfg%force_tolerance = force_tolerance
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=model_size, iostat=ios, iomsg=msg)
      end subroutine reader
   end subroutine read_model_size
end module gapbeam_input
