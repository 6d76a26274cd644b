!> Warnings about a deck (analyses/gapbeam_warnings) and about a run's stops
!> (core/gapbeam_warning_text): no deck of inputs/ or test/decks/ warns; each value far outside
!> the model's scale does (a gap of 2 m, an amplitude of 4 m, a width of 6.6 m on a 0.2 m
!> beam), values just inside do not; the reach bound of a stop holds for a run from rest and
!> from a given velocity, and is tight (the largest tip displacement of the run is within
!> 15 % of it); a stop never touched gives its warning and the label's evidence.
program test_warnings
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_testing, only: check, check_le, finish, note
   use gapbeam_deck, only: deck_t, add_warning
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_warnings, only: deck_warnings, reach_bounds
   use gapbeam_warning_text, only: warning_length, untouched_stop_warnings, &
      untouched_sweep_warnings, untouched_evidence, is_untouched_warning
   use gapbeam_test_runs, only: load_deck
   implicit none
   character(len=*), parameter :: ref = 'inputs/moon_shaw_10p5hz.nml'
   character(len=*), parameter :: list = 'test_warnings_decks.tmp'

   call shipped_decks()
   call scale_cases()
   call reach_bound('from rest', [character(len=80) :: ''])
   call reach_bound('from a tip velocity of 0.3 m/s', [character(len=80) :: &
      "&initial kind = 'given', node = 5, dof = 'w', velocity = 0.3 /"])
   call reach_bound('undamped, from rest', [character(len=80) :: &
      '&damping stiffness_coefficient = 0 /'])
   call untouched()
   call finish('test_warnings')

contains

   !> The warnings of `path` with overrides, or a failed check.
   subroutine warnings_of(path, overrides, lines, ok)
      character(len=*), intent(in) :: path, overrides(:)
      character(len=warning_length), allocatable, intent(out) :: lines(:)
      logical, intent(out) :: ok
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      character(len=len(overrides)) :: ov(size(overrides))
      ov = overrides
      call read_deck(path, ov, deck, err)
      ok = .not. allocated(err)
      if (.not. ok) then
         call check('read ' // path, .false., err%message)
         allocate(lines(0))
         return
      end if
      lines = deck_warnings(deck)
   end subroutine warnings_of

   !> Whether some line holds every one of the texts.
   logical function has(lines, a, b)
      character(len=*), intent(in) :: lines(:), a
      character(len=*), intent(in), optional :: b
      integer :: k
      has = .false.
      do k = 1, size(lines)
         if (index(lines(k), a) == 0) cycle
         if (present(b)) then
            if (index(lines(k), b) == 0) cycle
         end if
         has = .true.
      end do
   end function has

   !> No deck that gapbeam ships (inputs/, test/decks/) warns: the thresholds are chosen so.
   subroutine shipped_decks()
      character(len=warning_length), allocatable :: lines(:)
      character(len=256) :: path
      integer :: unit, ios, n
      logical :: ok
      call execute_command_line('ls inputs/*.nml test/decks/*.nml > ' // list)
      open(newunit=unit, file=list, status='old', action='read')
      n = 0
      do
         read(unit, '(a)', iostat=ios) path
         if (ios /= 0) exit
         call warnings_of(trim(path), [character(len=1) ::], lines, ok)
         if (.not. ok) cycle
         n = n + 1
         if (size(lines) > 0) then
            call check('no warning: ' // trim(path), .false., trim(lines(1)))
         end if
      end do
      close(unit, status='delete')
      call check('every shipped deck read and quiet (' // trim(str_i(n)) // ' decks)', n >= 30)
   end subroutine shipped_decks

   !> Values far outside the model's scale warn, naming the value and the span; values a
   !> little inside the thresholds do not.
   subroutine scale_cases()
      character(len=warning_length), allocatable :: lines(:)
      logical :: ok
      call warnings_of(ref, [character(len=40) :: '&stops gap = 2 /'], lines, ok)
      call check('gap 2 m on a 0.2 m beam: the scale warning', &
         has(lines, 'stop 1 (&stops gap(1) = 2 m) is 10 times the span L = 0.2 m'))
      call check('gap 2 m: out of reach too', has(lines, 'gap 2 m is out of reach'))
      call warnings_of(ref, [character(len=40) :: '&forcing amplitude_pp = 4 /'], lines, ok)
      call check('amplitude 4 m warns', has(lines, '&forcing amplitude_pp = 4 m is 20 times'))
      call warnings_of(ref, [character(len=40) :: '&beam width = 6.6 /'], lines, ok)
      call check('width 6.6 m warns', has(lines, '&beam width = 6.6 m is 33 times', 'plate'))
      call warnings_of(ref, [character(len=40) :: '&beam thickness = 0.05 /'], lines, ok)
      call check('thickness 0.05 m (L/4) warns', has(lines, '&beam thickness = 5E-002 m'))
      ! a gap of 10 mm can be met (the bound is 11.7 mm); 19 mm (0.095 L) cannot: reach only
      call warnings_of(ref, [character(len=40) :: '&stops gap = 1.0e-2 /'], lines, ok)
      call check('gap 10 mm: no warning (the bound is 11.7 mm)', size(lines) == 0)
      call warnings_of(ref, [character(len=40) :: '&stops gap = 1.9e-2 /'], lines, ok)
      call check('gap 19 mm: out of reach, no scale warning', size(lines) == 1 .and. &
         has(lines, 'out of reach'))
      call warnings_of(ref, [character(len=40) :: '&forcing amplitude_pp = 0.039 /'], lines, ok)
      call check('amplitude 39 mm (0.195 L): no scale warning', .not. has(lines, 'amplitude'))
      ! two stops: the bound holds until the beam meets one, so it proves nothing about the
      ! far stop when the near one is within reach; both far: a warning for each
      call warnings_of(ref, [character(len=200) :: "&stops node = 5, 3, dof = 'w', 'w', side " &
         // "= 'positive', 'negative', gap = 2.0e-2, 1.0e-3, rule_factor = 2, 0, " &
         // "stiffness = 0, 500, rule_f1_ratio = 4.375 /"], lines, ok)
      call check('two stops, one within reach: no reach warning', ok .and. size(lines) == 0)
      call warnings_of(ref, [character(len=200) :: "&stops node = 5, 3, dof = 'w', 'w', side " &
         // "= 'positive', 'negative', gap = 2.0e-2, 1.5e-2, rule_factor = 2, 0, " &
         // "stiffness = 0, 500, rule_f1_ratio = 4.375 /"], lines, ok)
      call check('two stops, both out of reach: a warning for each', size(lines) == 2 .and. &
         has(lines, 'stop 1 (node 5, w)', 'out of reach') .and. &
         has(lines, 'stop 2 (node 3, w)', 'out of reach'))
      ! a modes analysis does not use the forcing: no amplitude warning
      call warnings_of('inputs/moon_shaw_modes.nml', [character(len=40) :: &
         '&forcing amplitude_pp = 4 /'], lines, ok)
      call check('modes analysis: the amplitude is not used, no warning', size(lines) == 0)
      ! a sweep: its largest amplitude
      call warnings_of('test/decks/sweep_small.nml', [character(len=60) :: &
         '&sweep amplitude_pp = 2.0e-3, 4.0 /'], lines, ok)
      call check('sweep with an amplitude of 4 m on its axis warns', &
         has(lines, 'amplitude_pp = 4 m'))
   end subroutine scale_cases

   !> The reach bound of the tip stop (gap 20 mm, out of reach) against a run of 400 periods
   !> that records every sample from the start: the largest |w_tip| is at most the bound and
   !> at least 0.85 of it.
   subroutine reach_bound(what, extra)
      character(len=*), intent(in) :: what, extra(:)
      type(deck_t) :: deck
      type(model_t) :: model
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), bc(:), br(:), sc(:), sr(:)
      real(dp) :: w_max
      logical :: ok
      character(len=80) :: ov(5 + count(extra /= ''))
      ov(1) = '&stops gap = 2.0e-2 /'
      ov(2) = '&solver transient_periods = 0, record_periods = 400 /'
      ov(3) = '&output history_periods = 400, samples_per_period = 256 /'
      ov(4) = '&diagnostics lyapunov_periods = 0 /'
      ov(5) = "&solver method = 'exact' /"
      ov(6:) = pack(extra, extra /= '')
      call load_deck(ref, ov, deck, model, u0, v0, err)
      if (allocated(err)) then
         call check('reach ' // what // ': load', .false., err%message)
         return
      end if
      call reach_bounds(model, u0, v0, bc, br, sc, sr, ok)
      call check('reach ' // what // ': a bound exists', ok .and. size(bc) == 1)
      if (.not. ok) return
      call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      if (allocated(err)) then
         call check('reach ' // what // ': run', .false., err%message)
         return
      end if
      w_max = maxval(abs(res%tip_displacement))
      call note('reach ' // what // ': bound ' // trim(str_r(bc(1))) // ' m, steady ' &
         // trim(str_r(sc(1))) // ' m, largest |w_tip| of the run ' // trim(str_r(w_max)) // ' m')
      call check_le('reach ' // what // ': the run stays within the bound', w_max, bc(1))
      ! the bound adds the steady amplitude and the free vibration's peak, whose phases need
      ! not meet within the run: from rest 0.96-0.998 of it is reached, from a velocity 0.89
      call check('reach ' // what // ': the bound is tight (run >= 0.85 bound)', &
         w_max >= 0.85_dp * bc(1))
      call check('reach ' // what // ': the stop was never met', res%n_impacts(1) == 0)
   end subroutine reach_bound

   !> The texts about stops never touched: a transient's warning and evidence, a sweep's
   !> (only a stop no finished point touched), and the mark a merge recognises.
   subroutine untouched()
      character(len=warning_length), allocatable :: lines(:)
      type(deck_t) :: deck
      lines = untouched_stop_warnings([0, 3], [0.0_dp, 0.1_dp], 100)
      call check('transient: one warning for the untouched stop', size(lines) == 1)
      call check('transient: it names stop 1 and the record', has(lines, &
         'stop 1 was never touched in the 100 recorded periods (0 impacts)'))
      call check('transient: evidence names stop 1', index(untouched_evidence([0, 3], &
         [0.0_dp, 0.1_dp]), 'stop 1 never met in the record') > 0)
      call check('transient: no evidence when every stop is met', &
         len(untouched_evidence([2, 3], [0.1_dp, 0.1_dp])) == 0)
      call check('a stop in contact without an impact onset counts as met', &
         size(untouched_stop_warnings([0], [1.0_dp], 10)) == 0)
      lines = untouched_sweep_warnings(reshape([0, 0, 0, 5], [2, 2]), &
         reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.1_dp], [2, 2]), [0, 0])
      call check('sweep: stop 1 untouched at both points, stop 2 met at one', &
         size(lines) == 1 .and. has(lines, 'stop 1 was never touched at any of the 2'))
      lines = untouched_sweep_warnings(reshape([0, 4], [1, 2]), reshape([0.0_dp, 0.1_dp], &
         [1, 2]), [0, 1])
      call check('sweep: a failed point does not count', size(lines) == 1)
      call check('a merge recognises the untouched warnings', is_untouched_warning(lines(1)) &
         .and. .not. is_untouched_warning('stop 1 (node 5, w): gap 2 m is out of reach'))
      call add_warning(deck, 'one')
      call add_warning(deck, 'two, longer')
      call add_warning(deck, 'one')
      call check('add_warning keeps each line once, in order', size(deck%warnings) == 2)
      if (size(deck%warnings) == 2) call check('add_warning: the lines whole', &
         deck%warnings(1) == 'one' .and. deck%warnings(2) == 'two, longer')
   end subroutine untouched

   function str_i(i) result(s)
      integer, intent(in) :: i
      character(len=16) :: s
      write(s, '(i0)') i
   end function str_i

   function str_r(x) result(s)
      real(dp), intent(in) :: x
      character(len=24) :: s
      write(s, '(es12.5)') x
   end function str_r
end program test_warnings
