!> The deck rules of the groups that name other deck variables (the axes of &sweep, the
!> variables of &continuation) and the sizes of a run, counted in 64 bits (see
!> gapbeam_deck_rules).
module gapbeam_deck_rules_axes
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck_rules, only: is_given
   use gapbeam_deck, only: deck_t
   use gapbeam_settings, only: starts_given
   use gapbeam_deck_variable, only: deck_variable_t, parse_deck_variable, &
      parse_deck_variables, check_deck_variable, get_deck_value, set_deck_value, &
      deck_variable_label, deck_variables_label
   implicit none
   private
   public :: make_sweep_axes, check_continuation, check_sizes

   integer, parameter :: max_points = 1000000   !! most points of a sweep
   !> Most values kept in memory for one array of results (history samples, Poincare points,
   !> Lyapunov estimates) or for all the points of a sweep: 5e8 reals are 4 GB.
   integer(int64), parameter :: max_values = 500000000_int64
   !> Most forcing periods one run may integrate in all (the transient with its settling
   !> extensions, the records, the exponent's periods): every period count of the analyses
   !> then fits in 32 bits.
   integer(int64), parameter :: max_run_periods = 2000000000_int64

contains

   !> &sweep. The axes: x is '&forcing frequency_hz' (values from frequency_hz or its range)
   !> and y '&forcing amplitude_pp' (amplitude_pp or its range) unless x_variable / y_variable
   !> name other numeric deck variables, whose values come from x_values / y_values or their
   !> ranges (x_start, x_end, n_x; the deck's value when neither is given). The extreme values
   !> of every axis are checked by setting them on a copy of the deck (gapbeam_deck_variable).
   !> The axes of &sweep (see the header).
   subroutine make_sweep_axes(given, deck, err)
      character(len=*), intent(in) :: given            !! what the sources name (is_given)
      type(deck_t), intent(inout) :: deck
      type(error_t), allocatable, intent(inout) :: err
      type(deck_variable_t) :: var(2), forcing(2)
      type(deck_variable_t), allocatable :: xvars(:), yvars(:)
      real(dp), allocatable :: fa(:), aa(:), x(:), y(:)
      integer :: i, j
      if (allocated(err)) return
      associate (sw => deck%sweep)
         call sweep_variable('x_variable', sw%x_variable, deck, xvars, err)
         call sweep_variable('y_variable', sw%y_variable, deck, yvars, err)
         if (allocated(err)) return
         ! an axis of several variables is led by its first (forcing variables stand alone)
         var(1) = xvars(1);  var(2) = yvars(1)
         do i = 1, size(xvars)
            do j = 1, size(yvars)
               if (deck_variable_label(xvars(i)) == deck_variable_label(yvars(j))) then
                  call fatal_error(err, "group &sweep: x_variable and y_variable both name '" &
                     // deck_variable_label(xvars(i)) // "': the two axes need two variables")
                  return
               end if
            end do
         end do
         call make_axis('frequency_hz', 'frequency_start_hz', 'frequency_end_hz', &
            'n_frequency', sw%frequency_hz, sw%frequency_start_hz, sw%frequency_end_hz, &
            sw%n_frequency, deck%forcing%frequency_hz, fa, err)
         call make_axis('amplitude_pp', 'amplitude_start_pp', 'amplitude_end_pp', &
            'n_amplitude', sw%amplitude_pp, sw%amplitude_start_pp, sw%amplitude_end_pp, &
            sw%n_amplitude, deck%forcing%amplitude_pp, aa, err)
         if (allocated(err)) return
         ! a forcing list given while no axis is that variable would be ignored silently
         if ((is_given(given, 'sweep:frequency_hz') .or. sw%n_frequency > 0) .and. &
             .not. any(label_of(var) == '&forcing frequency_hz')) call fatal_error(err, &
            'group &sweep: frequency_hz (or n_frequency) is given but neither x_variable ' &
            // "nor y_variable is '&forcing frequency_hz'")
         if ((is_given(given, 'sweep:amplitude_pp') .or. sw%n_amplitude > 0) .and. &
             .not. any(label_of(var) == '&forcing amplitude_pp')) call fatal_error(err, &
            'group &sweep: amplitude_pp (or n_amplitude) is given but neither x_variable ' &
            // "nor y_variable is '&forcing amplitude_pp'")
         if (allocated(err)) return
         call variable_axis('x', xvars, sw%x_values, sw%x_start, sw%x_end, sw%n_x, fa, aa, &
            deck, x, err)
         call variable_axis('y', yvars, sw%y_values, sw%y_start, sw%y_end, sw%n_y, fa, aa, &
            deck, y, err)
         if (allocated(err)) return
         if (int(size(x), int64) * size(y) > max_points) then
            call fatal_error(err, 'group &sweep: ' // str(size(x)) // ' values of x (' &
               // axis_source(var(1), 'x') // ') x ' // str(size(y)) // ' values of y (' &
               // axis_source(var(2), 'y') // ') = ' // str(int(size(x), int64) &
               * size(y)) // ' points: at most ' // str(max_points) // ' points in one ' &
               // 'sweep (split the map into several decks)')
            return
         end if
         if (all(label_of(var) /= '&forcing frequency_hz')) fa = [deck%forcing%frequency_hz]
         if (all(label_of(var) /= '&forcing amplitude_pp')) aa = [deck%forcing%amplitude_pp]
         ! the forcing axes at their extremes: each value in range (a base motion beyond the
         ! scale rule, (A_pp/2)(2 pi f)^2 > sqrt(huge), makes a failed point, marked as such)
         call parse_deck_variable('&forcing amplitude_pp', forcing(2), err)
         call parse_deck_variable('&forcing frequency_hz', forcing(1), err)
         call check_extremes(deck, forcing(2:2), aa, 'amplitude axis', err, forcing(1), &
                             minval(fa), upper=.false.)
         call check_extremes(deck, forcing(1:1), fa, 'frequency axis', err, forcing(2), &
                             0.0_dp)
         if (allocated(err)) return
         sw%x = x;  sw%y = y;  sw%frequency_hz = fa;  sw%amplitude_pp = aa
         sw%x_variable = deck_variables_label(xvars);  sw%y_variable = deck_variables_label(yvars)
      end associate
   end subroutine make_sweep_axes

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

   !> Values of one axis: the forcing axes from their own lists, another variable from
   !> values / start-end-count or the deck's value.
   subroutine variable_axis(c, vars, list, x0, x1, n, fa, aa, deck, axis_out, err)
      character(len=1), intent(in) :: c                  !! 'x' or 'y'
      type(deck_variable_t), intent(in) :: vars(:)       !! the axis variables (one or more)
      real(dp), allocatable, intent(in) :: list(:)       !! x_values / y_values given
      real(dp), intent(in) :: x0, x1                     !! range ends
      integer, intent(in) :: n                           !! range count (0: none)
      real(dp), intent(in) :: fa(:), aa(:)               !! frequency and amplitude axes
      type(deck_t), intent(in) :: deck                   !! deck read so far
      real(dp), allocatable, intent(out) :: axis_out(:)  !! values
      type(error_t), allocatable, intent(inout) :: err   !! bad value
      integer :: n_list
      character(len=:), allocatable :: lab
      if (allocated(err)) return
      n_list = 0
      if (allocated(list)) n_list = size(list)
      lab = deck_variable_label(vars(1))
      if (lab == '&forcing frequency_hz' .or. lab == '&forcing amplitude_pp') then
         if (n_list > 0 .or. n > 0) then
            call fatal_error(err, 'group &sweep: ' // c // '_values (or n_' // c // ") is " &
               // "given for '" // lab // "': give its values as " &
               // trim(merge('frequency_hz', 'amplitude_pp', vars(1)%name == &
               'frequency_hz')) // ' (or its range) instead')
         else if (vars(1)%name == 'frequency_hz') then
            axis_out = fa
         else
            axis_out = aa
         end if
         return
      end if
      call make_axis(c // '_values', c // '_start', c // '_end', 'n_' // c, list, x0, x1, n, &
                     get_deck_value(deck, vars(1)), axis_out, err)
      if (.not. allocated(err)) call check_extremes(deck, vars, axis_out, c // ' axis', err)
   end subroutine variable_axis

   !> The extreme values of an axis (smallest, largest, smallest non-zero magnitude), set on
   !> a copy of the deck: every value of an axis then lies in its variables' range. With
   !> `other`, that variable is first set to `other_value` (the frequency's range depends on
   !> the amplitude).
   subroutine check_extremes(deck, vars, values, what, err, other, other_value, upper)
      type(deck_t), intent(in) :: deck                   !! deck
      type(deck_variable_t), intent(in) :: vars(:)       !! the axis variables
      real(dp), intent(in) :: values(:)                  !! the axis
      character(len=*), intent(in) :: what               !! 'x axis', ...
      type(error_t), allocatable, intent(inout) :: err   !! a value out of range
      type(deck_variable_t), intent(in), optional :: other
      real(dp), intent(in), optional :: other_value
      logical, intent(in), optional :: upper          !! check the largest value (default)
      type(deck_t) :: d
      real(dp) :: probe(3)
      integer :: k, i
      if (allocated(err) .or. size(values) == 0) return
      probe = [minval(values), maxval(values), minval(abs(values), mask=values /= 0.0_dp)]
      if (.not. any(values /= 0.0_dp)) probe(3) = probe(1)
      if (present(upper)) then
         if (.not. upper) probe(2) = probe(1)
      end if
      d = deck
      if (present(other)) then
         call set_deck_value(d, other, other_value, err)
         if (allocated(err)) then
            err%message = 'group &sweep: ' // what // ': ' // err%message
            return
         end if
      end if
      do k = 1, 3
         do i = 1, size(vars)
            call set_deck_value(d, vars(i), probe(k), err)
            if (allocated(err)) then
               err%message = 'group &sweep: ' // what // " ('" &
                  // deck_variable_label(vars(i)) // "'): " // err%message
               return
            end if
         end do
      end do
   end subroutine check_extremes

   !> A forcing axis from its list, or from start, end and count; `default` (the &forcing
   !> value) if neither is given.
   subroutine make_axis(vlist, vstart, vend, vn, list, x0, x1, n, default, axis_out, err)
      character(len=*), intent(in) :: vlist, vstart, vend, vn   !! variable names, for messages
      real(dp), allocatable, intent(in) :: list(:)    !! the list entries given
      real(dp), intent(in) :: x0, x1                  !! first and last value of a range
      integer, intent(in) :: n                        !! values of the range (0: no range)
      real(dp), intent(in) :: default                 !! value when neither is given
      real(dp), allocatable, intent(out) :: axis_out(:)  !! the axis
      type(error_t), allocatable, intent(inout) :: err   !! set on a bad axis
      integer :: j, n_list
      if (allocated(err)) return
      n_list = 0
      if (allocated(list)) n_list = size(list)
      if (n_list > 0 .and. n > 0) then
         call fatal_error(err, 'group &sweep: give either the list ' // vlist // ' or ' &
            // vstart // ', ' // vend // ' and ' // vn // ', not both')
      else if (n_list > 0) then
         axis_out = list
      else if (n == 1) then
         axis_out = [x0]
      else if (n > 1) then
         axis_out = [(x0 + (x1 - x0) * real(j - 1, dp) / real(n - 1, dp), j = 1, n)]
         if (.not. all(ieee_is_finite(axis_out))) call fatal_error(err, 'group &sweep: ' &
            // vstart // ' = ' // str(x0) // ', ' // vend // ' = ' // str(x1) // ': the ' &
            // 'range between them overflows (its values must be finite)')
      else
         axis_out = [default]
      end if
   end subroutine make_axis

   ! ---------------------------------------------------------------- &continuation

   !> &continuation: the variables and their ranges, the start, the curves.
   subroutine check_continuation(given, deck, err)
      character(len=*), intent(in) :: given            !! what the sources name (is_given)
      type(deck_t), intent(inout) :: deck
      type(error_t), allocatable, intent(inout) :: err
      integer :: k
      if (allocated(err)) return
      if (.not. is_given(given, 'continuation')) then
         if (deck%job%analysis == 'continuation') call fatal_error(err, 'group &continuation ' &
            // "is missing: analysis='continuation' needs at least parameter, parameter_min " &
            // 'and parameter_max')
         return
      end if
      associate (c => deck%continuation)
         call check_variable(deck, 'parameter', c%parameter, c%parameter_min, c%parameter_max, &
                             'parameter_min', 'parameter_max', err)
         if (allocated(err)) return
         if (c%period > c%max_period) then
            call fatal_error(err, 'group &continuation: period = ' // str(c%period) &
               // ': must be in 0..' // str(c%max_period) // ' (max_period; 0: detected from ' &
               // 'the transient)')
         else if (c%step_max > 0.0_dp .and. c%step_min > 0.0_dp .and. &
                  .not. (c%step_min < c%step_max)) then
            call fatal_error(err, 'group &continuation: step_min = ' // str(c%step_min) &
               // ': must be < step_max = ' // str(c%step_max))
         else if (c%start == 'given' .and. c%period < 1) then
            call fatal_error(err, "group &continuation: period = " // str(c%period) &
               // ": must be >= 1 with start = 'given' (the period of the given orbit)")
         else if (c%start == 'given' .and. deck%initial%kind /= 'given') then
            call fatal_error(err, "group &continuation: start = 'given' takes the section " &
               // "state from &initial, which needs kind = 'given'")
         end if
         if (allocated(err)) return
         if (len_trim(c%parameter2) > 0) then
            call check_variable(deck, 'parameter2', c%parameter2, c%parameter2_min, &
                                c%parameter2_max, 'parameter2_min', 'parameter2_max', err)
            if (allocated(err)) return
            if (trim(adjustl(c%parameter2)) == trim(adjustl(c%parameter))) call fatal_error( &
               err, "group &continuation: parameter2 = '" // trim(c%parameter2) // "': must " &
               // 'differ from parameter')
            if (all(len_trim(c%curves) == 0)) call fatal_error(err, 'group &continuation: ' &
               // "parameter2 = '" // trim(c%parameter2) // "' needs curves, e.g. curves = " &
               // "'period_doubling', 'grazing'")
         else if (any(len_trim(c%curves) > 0)) then
            k = findloc(len_trim(c%curves) > 0, .true., dim=1)
            call fatal_error(err, "group &continuation: curves(" // str(k) // ") = '" &
               // trim(c%curves(k)) // "': two-parameter curves need parameter2 (the " &
               // "second variable, e.g. '&forcing amplitude_pp') with parameter2_min and " &
               // 'parameter2_max')
         end if
      end associate
   end subroutine check_continuation

   !> A variable name that parses and exists in the deck, a range that holds its value.
   subroutine check_variable(deck, vname, text, lo, hi, vlo, vhi, err)
      type(deck_t), intent(in) :: deck
      character(len=*), intent(in) :: vname, text, vlo, vhi
      real(dp), intent(in) :: lo, hi
      type(error_t), allocatable, intent(inout) :: err
      type(deck_variable_t) :: var
      real(dp) :: x
      call parse_deck_variable(text, var, err)
      if (.not. allocated(err)) call check_deck_variable(deck, var, err)
      if (allocated(err)) then
         err%message = 'group &continuation: ' // vname // ' = ''' // trim(text) // ''': ' &
            // err%message
         return
      end if
      if (.not. (lo < hi)) then
         call fatal_error(err, 'group &continuation: ' // vlo // ' = ' // str(lo) // ', ' &
            // vhi // ' = ' // str(hi) // ': need finite ' // vlo // ' < ' // vhi &
            // ' (the range of ' // deck_variable_label(var) // ' [' // trim(var%units) &
            // '])')
         return
      end if
      x = get_deck_value(deck, var)
      if (x < lo .or. x > hi) call fatal_error(err, 'group &continuation: ' // vname &
         // ' = ''' // trim(text) // ''': the deck''s value ' // str(x) // ' [' &
         // trim(var%units) // '] (the start) must lie in [' // vlo // ', ' // vhi // '] = [' &
         // str(lo) // ', ' // str(hi) // ']')
   end subroutine check_variable

   ! ---------------------------------------------------------------- sizes

   !> Sizes of the result arrays, counted in 64-bit integers before anything is allocated:
   !> the history of a run, the results a sweep keeps for all its points, and the forcing
   !> periods one run may integrate in all (so that every period count fits in 32 bits).
   subroutine check_sizes(deck, err)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      integer(int64) :: samples, per_point, points, lyap, budget, total
      if (allocated(err)) return
      associate (s => deck%solver, d => deck%diagnostics, o => deck%output)
         ! the transient budget and the exponent's (as the label's analysis takes them); the
         ! settling extensions, up to 9 records and exponents, and the convergence runs
         if (d%transient_max_periods > 0) then
            budget = max(d%transient_max_periods, s%transient_periods)
         else
            budget = max(10_int64 * s%transient_periods, int(s%transient_periods, int64) &
                         + s%record_periods)
         end if
         lyap = d%lyapunov_max_periods
         if (lyap == 0) lyap = 20_int64 * d%lyapunov_periods
         ! independent starts: each at least lyapunov_periods, with a lead-in of up to 4 x
         if (d%lyapunov_starts > 1) lyap = max(lyap, int(d%lyapunov_starts, int64) &
            * d%lyapunov_periods) + 4_int64 * d%lyapunov_starts * d%lyapunov_periods
         total = 2_int64 * budget + 17_int64 * s%record_periods + 9_int64 * lyap
         if (total > max_run_periods) then
            call fatal_error(err, 'group &solver: transient_periods = ' &
               // str(s%transient_periods) // ', record_periods = ' // str(s%record_periods) &
               // ' with &diagnostics transient_max_periods = ' // str(d%transient_max_periods) &
               // ' and lyapunov_periods = ' // str(d%lyapunov_periods) // ' (max ' &
               // str(d%lyapunov_max_periods) // '): a run may integrate up to ' &
               // str(total) // ' forcing periods (2 x the transient budget ' &
               // str(budget) // ' + 17 records + 9 exponents of ' // str(lyap) &
               // '): at most ' // str(max_run_periods))
            return
         end if
         samples = int(min(o%history_periods, s%record_periods), int64) * o%samples_per_period
         if (samples > max_values) then
            call fatal_error(err, 'group &output: history_periods = ' &
               // str(o%history_periods) // ' (at most record_periods = ' &
               // str(s%record_periods) // ') x samples_per_period = ' &
               // str(o%samples_per_period) // ' = ' // str(samples) &
               // ' history samples: at most ' // str(max_values))
            return
         end if
         if (o%state_history .and. deck%job%analysis == 'transient') then
            if (deck%reduction%kind /= 'none') then
               call fatal_error(err, "group &output: state_history = .true.: needs the finite " &
                  // "element model, not a modal one (&reduction kind = '" &
                  // trim(deck%reduction%kind) // "'; allowed: 'none')")
               return
            end if
            ! every dof at every history sample, and the deflected shape at its points
            per_point = 2_int64 * (deck%structure%beam%n_elem + 1) &
                        + int(deck%structure%beam%n_elem, int64) * o%shape_points + 1
            if (samples * per_point > max_values) then
               call fatal_error(err, 'group &output: state_history = .true.: ' &
                  // str(samples) // ' history samples x ' // str(per_point) &
                  // ' values each (2 dofs per node and the shape at n_elem x shape_points ' &
                  // '+ 1 points) = ' // str(samples * per_point) // ': at most ' &
                  // str(max_values) // '; keep fewer history_periods, ' &
                  // 'samples_per_period or shape_points')
               return
            end if
         end if
         if (deck%job%analysis /= 'sweep') return
         ! per run (point and start): Poincare strain and rate, the running Lyapunov estimate
         ! (at most lyapunov_max_periods), the final state
         per_point = 2_int64 * s%record_periods + lyap &
                     + 4_int64 * deck%structure%beam%planes * (deck%structure%beam%n_elem + 1) &
                     + 16_int64 * size(deck%stops)
         points = int(size(deck%sweep%x), int64) * size(deck%sweep%y) &
                  * max(1, starts_given(d))
         if (points * per_point > max_values) then
            call fatal_error(err, 'group &sweep: ' // str(points) // ' runs (points x ' &
               // 'starts) x ' // str(per_point) // ' values kept per run (2 x &solver ' &
               // 'record_periods + &diagnostics lyapunov_max_periods + the final state) = ' &
               // str(points * per_point) // ': at most ' // str(max_values) &
               // ' values; sweep fewer points (n_frequency, n_amplitude, n_x, n_y), use ' &
               // 'fewer starts or record fewer periods')
         end if
      end associate
   end subroutine check_sizes
end module gapbeam_deck_rules_axes
