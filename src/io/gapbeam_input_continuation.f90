!> The &continuation group of a deck (issue 14): read, override and validate, with the
!> helpers of gapbeam_input (a submodule, so that the group reader lives apart from the
!> others). Every message names the deck, the group, the variable, the value and what is
!> allowed, on one line.
submodule (gapbeam_input) gapbeam_input_continuation
   use gapbeam_capabilities, only: method_caps, method_caps_t
   use gapbeam_continuation_types, only: continuation_settings_t, max_curve_kinds, &
      continuation_direction_words, continuation_start_words, jacobian_words, curve_kind_words
   use gapbeam_deck_variable, only: deck_variable_t, parse_deck_variable, check_deck_variable, &
      get_deck_value, deck_variable_label
   implicit none

contains

   module subroutine read_continuation(srcs, deck, present_group, err)
      type(source_t), intent(in) :: srcs(:)           !! deck file, then overrides
      type(deck_t), intent(inout) :: deck             !! deck read so far
      logical, intent(in) :: present_group            !! the deck has &continuation
      type(error_t), allocatable, intent(out) :: err  !! first problem found
      type(continuation_settings_t) :: c
      type(method_caps_t) :: mc
      character(len=64) :: parameter, parameter2
      character(len=8) :: direction
      character(len=16) :: start
      character(len=24) :: jacobian, curves(max_curve_kinds)
      character(len=256) :: overlay
      real(dp) :: parameter_min, parameter_max, step, step_min, step_max, tolerance, fd_step, &
         locate_tolerance, parameter2_min, parameter2_max, curve_step
      integer :: period, transient_periods, max_points, max_iterations, max_period, &
         grazing_samples, curve_max_points, k, unstable_points
      logical :: switch_period_doubling
      namelist /continuation/ parameter, parameter_min, parameter_max, direction, start, &
         period, transient_periods, step, step_min, step_max, max_points, tolerance, &
         max_iterations, jacobian, fd_step, locate_tolerance, switch_period_doubling, &
         max_period, grazing_samples, parameter2, parameter2_min, parameter2_max, curves, &
         curve_max_points, curve_step, overlay, unstable_points
      if (.not. present_group) then
         if (deck%job%analysis == 'continuation') call fatal_error(err, 'group &continuation ' &
            // "is missing: analysis='continuation' needs at least parameter, parameter_min " &
            // 'and parameter_max')
         return
      end if
      c = deck%continuation
      parameter = c%parameter;  parameter_min = c%parameter_min;  parameter_max = c%parameter_max
      direction = c%direction;  start = c%start;  period = c%period
      transient_periods = c%transient_periods;  step = c%step;  step_min = c%step_min
      step_max = c%step_max;  max_points = c%max_points;  tolerance = c%tolerance
      max_iterations = c%max_iterations;  jacobian = c%jacobian;  fd_step = c%fd_step
      locate_tolerance = c%locate_tolerance;  switch_period_doubling = c%switch_period_doubling
      max_period = c%max_period;  grazing_samples = c%grazing_samples
      unstable_points = c%unstable_points
      parameter2 = c%parameter2;  parameter2_min = c%parameter2_min
      parameter2_max = c%parameter2_max;  curves = c%curves
      curve_max_points = c%curve_max_points;  curve_step = c%curve_step;  overlay = c%overlay
      call apply_group(srcs, 'continuation', 'parameter parameter_min parameter_max ' &
         // 'direction start period transient_periods step step_min step_max max_points ' &
         // 'tolerance max_iterations jacobian fd_step locate_tolerance ' &
         // 'switch_period_doubling max_period grazing_samples parameter2 parameter2_min ' &
         // 'parameter2_max curves curve_max_points curve_step overlay unstable_points', &
         reader, err)
      if (allocated(err)) return
      call check_variable(deck, 'parameter', parameter, parameter_min, parameter_max, &
                          'parameter_min', 'parameter_max', err)
      if (allocated(err)) return
      call require_word('continuation', 'direction', direction, continuation_direction_words, &
                        err)
      call require_word('continuation', 'start', start, continuation_start_words, err)
      call require_word('continuation', 'jacobian', jacobian, jacobian_words, err)
      call require_int('continuation', 'max_period', max_period, 1, 1024, err)
      call require_int('continuation', 'period', period, 0, max_period, err, &
                       '0: detected from the transient')
      call require_int('continuation', 'transient_periods', transient_periods, -1, huge(1), err, &
                       "-1: &solver's transient_periods")
      call require_nonnegative('continuation', 'step', step, err)
      call require_nonnegative('continuation', 'step_min', step_min, err)
      call require_nonnegative('continuation', 'step_max', step_max, err)
      call require_int('continuation', 'max_points', max_points, 2, 1000000, err)
      call require_range('continuation', 'tolerance', tolerance, 1.0e-15_dp, 1.0e-2_dp, err)
      call require_int('continuation', 'max_iterations', max_iterations, 1, 100, err)
      call require_range('continuation', 'fd_step', fd_step, 1.0e-12_dp, 1.0e-2_dp, err)
      call require_nonnegative('continuation', 'locate_tolerance', locate_tolerance, err)
      call require_int('continuation', 'grazing_samples', grazing_samples, 8, 1000000, err)
      call require_int('continuation', 'unstable_points', unstable_points, 0, 1000000, err, &
                       '0: doubled branches are followed however unstable')
      call require_int('continuation', 'curve_max_points', curve_max_points, 2, 1000000, err)
      call require_range('continuation', 'curve_step', curve_step, 0.0_dp, 1.0_dp, err)
      if (allocated(err)) return
      if (step_max > 0.0_dp .and. step_min > 0.0_dp .and. .not. (step_min < step_max)) then
         call fatal_error(err, 'group &continuation: step_min = ' // str(step_min) &
            // ': must be < step_max = ' // str(step_max))
         return
      end if
      ! the exact Jacobian needs a method whose registry entry gives one
      mc = method_caps(deck%solver%method)
      if (jacobian == 'exact' .and. .not. mc%jacobian .and. deck%solver%method /= 'auto') then
         call fatal_error(err, "group &continuation: jacobian = 'exact' needs &solver " &
            // "method = 'exact' (or 'auto' with piecewise-linear stops; the deck has '" &
            // trim(deck%solver%method) // "'); use jacobian = 'finite_difference' with " &
            // 'other methods')
         return
      end if
      if (start == 'given') then
         if (period < 1) call fatal_error(err, "group &continuation: period = " // str(period) &
            // ": must be >= 1 with start = 'given' (the period of the given orbit)")
         if (deck%initial%kind /= 'given') call fatal_error(err, "group &continuation: start " &
            // "= 'given' takes the section state from &initial, which needs kind = 'given'")
         if (allocated(err)) return
      end if
      do k = 1, max_curve_kinds
         if (len_trim(curves(k)) == 0) cycle
         call require_word('continuation', 'curves(' // str(k) // ')', curves(k), &
                           curve_kind_words, err)
      end do
      if (allocated(err)) return
      if (len_trim(parameter2) > 0) then
         call check_variable(deck, 'parameter2', parameter2, parameter2_min, parameter2_max, &
                             'parameter2_min', 'parameter2_max', err)
         if (allocated(err)) return
         if (trim(adjustl(parameter2)) == trim(adjustl(parameter))) call fatal_error(err, &
            "group &continuation: parameter2 = '" // trim(parameter2) // "': must differ " &
            // 'from parameter')
         if (all(len_trim(curves) == 0)) call fatal_error(err, 'group &continuation: ' &
            // "parameter2 = '" // trim(parameter2) // "' needs curves, e.g. curves = " &
            // "'period_doubling', 'grazing' (allowed: " // curve_kind_words // ')')
      else if (any(len_trim(curves) > 0)) then
         k = findloc(len_trim(curves) > 0, .true., dim=1)
         call fatal_error(err, "group &continuation: curves(" // str(k) // ") = '" &
            // trim(curves(k)) &
            // "': two-parameter curves need parameter2 (the second variable, e.g. " &
            // "'&forcing amplitude_pp') with parameter2_min and parameter2_max")
      end if
      if (allocated(err)) return
      deck%continuation = continuation_settings_t(parameter=parameter, &
         parameter_min=parameter_min, parameter_max=parameter_max, direction=direction, &
         start=start, period=period, transient_periods=transient_periods, step=step, &
         step_min=step_min, step_max=step_max, max_points=max_points, tolerance=tolerance, &
         max_iterations=max_iterations, jacobian=jacobian, fd_step=fd_step, &
         locate_tolerance=locate_tolerance, switch_period_doubling=switch_period_doubling, &
         max_period=max_period, grazing_samples=grazing_samples, parameter2=parameter2, &
         parameter2_min=parameter2_min, parameter2_max=parameter2_max, curves=curves, &
         curve_max_points=curve_max_points, curve_step=curve_step, overlay=overlay, &
         unstable_points=unstable_points)
   contains
      subroutine reader(lines, ios, msg)
         character(len=*), intent(in) :: lines(:)
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         read(lines, nml=continuation, iostat=ios, iomsg=msg)
      end subroutine reader

   end subroutine read_continuation

   !> A variable name that parses and exists in the deck, a range that holds its value.
   subroutine check_variable(deck, vname, text, lo, hi, vlo, vhi, err)
      type(deck_t), intent(in) :: deck
      character(len=*), intent(in) :: vname, text, vlo, vhi
      real(dp), intent(in) :: lo, hi
      type(error_t), allocatable, intent(out) :: err
      type(deck_variable_t) :: var
      real(dp) :: x
      call parse_deck_variable(text, var, err)
      if (.not. allocated(err)) call check_deck_variable(deck, var, err)
      if (allocated(err)) then
         err%message = 'group &continuation: ' // vname // ' = ''' // trim(text) // ''': ' &
            // err%message
         return
      end if
      if (.not. (lo < hi) .or. abs(lo) > huge(lo) .or. abs(hi) > huge(hi)) then
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
end submodule gapbeam_input_continuation
