!> Periodic orbits, monodromy matrices and continuation (issue 14).
program test_continuation
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_test_runs, only: load_or_stop
   use gapbeam_periodic, only: orbit_map_t, newton_orbit, transient_orbit, floquet_multipliers, &
      energy_size
   use gapbeam_continuation, only: run_continuation
   use gapbeam_continuation_types, only: continuation_result_t
   use gapbeam_settings, only: solver_settings_t, diagnostics_settings_t, output_settings_t
   use gapbeam_results, only: point_result_t, transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_attractor, only: point_diagnostics
   use gapbeam_state, only: state_t
   use gapbeam_transition, only: reduce_state
   use gapbeam_continuation_output, only: write_continuation
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_files, only: remove_file, file_exists
   implicit none
   character(len=*), parameter :: ref = 'test/decks/sweep_line_4mm_half_element.nml'
   character(len=*), parameter :: sdof = 'test/decks/sdof_continuation.nml'
   ! the single dof of sdof_continuation.nml: k = 3 EI / L^3, m = rho A L / 2, c = gamma k
   real(dp), parameter :: ei1 = 200.0e9_dp * 0.01_dp * 5.0e-4_dp**3 / 12
   real(dp), parameter :: k1 = 3 * ei1 / 0.2_dp**3, m1 = 7850.0_dp * 0.01_dp * 5.0e-4_dp &
      * 0.2_dp / 2, c1 = 9.0e-4_dp * k1, ks = 30.0_dp, gap = 2.0e-4_dp, a1 = 3.0e-4_dp

   call deck_errors()
   call monodromy_against_differences()
   call sdof_against_closed_form()
   call sdof_grazing_curve()
   call sdof_given_start_and_differences()
   call reference_line_against_sweep()
   call folds_against_up_down_sweeps()
   call period_reduced_to_the_orbits_own()
   call start_at_a_bound()
   call finish('test_continuation')

contains


   !> Bad &continuation groups are rejected with one line naming the deck, the group, the
   !> variable, the value and what is allowed.
   subroutine deck_errors()
      character(len=*), parameter :: job = "&job analysis = 'continuation' /"
      character(len=*), parameter :: ex = "&solver method = 'exact' /"
      call bad('unknown variable name', [character(len=200) :: job, ex, &
         "&continuation parameter = '&forcing freq', parameter_min = 8, parameter_max = 11 /"], &
         [character(len=40) :: 'sweep_line_4mm_half_element.nml', '&continuation', 'parameter', &
         'freq', 'frequency_hz'])
      call bad('empty range', [character(len=200) :: job, ex, &
         "&continuation parameter_min = 11.0, parameter_max = 8.0 /"], &
         [character(len=40) :: '&continuation', 'parameter_min', 'parameter_max', '11', '8'])
      call bad('start value outside the range', [character(len=200) :: job, ex, &
         "&continuation parameter_min = 10.5, parameter_max = 11.0 /"], &
         [character(len=40) :: '&continuation', 'parameter', '10', '10.5'])
      call bad('exact Jacobian with Newmark', [character(len=200) :: job, &
         "&solver method = 'newmark' /", &
         "&continuation parameter_min = 8.0, parameter_max = 11.0 /"], &
         [character(len=40) :: '&continuation', 'jacobian', 'exact', 'newmark'])
      call bad('curves without parameter2', [character(len=200) :: job, ex, &
         "&continuation parameter_min = 8, parameter_max = 11, curves = 'grazing' /"], &
         [character(len=40) :: '&continuation', 'curves', 'parameter2'])
      call bad('stop entry beyond the list', [character(len=200) :: job, ex, &
         "&continuation parameter = '&stops gap(3)', parameter_min = 0, parameter_max = 1e-3 /"],&
         [character(len=40) :: '&continuation', 'parameter', '&stops gap(3)', '1 &stops'])
      call bad('tolerance out of range', [character(len=200) :: job, ex, &
         "&continuation parameter_min = 8, parameter_max = 11, tolerance = 0.5 /"], &
         [character(len=40) :: '&continuation', 'tolerance', '0.5', '1E-015'])
      call bad('unknown word for direction', [character(len=200) :: job, ex, &
         "&continuation parameter_min = 8, parameter_max = 11, direction = 'sideways' /"], &
         [character(len=40) :: '&continuation', 'direction', 'sideways', "'both'"])
      call bad('group missing', [character(len=200) :: job, ex], &
         [character(len=40) :: '&continuation', 'missing', 'parameter_min'])
   end subroutine deck_errors

   subroutine bad(name, overrides, words)
      character(len=*), intent(in) :: name, overrides(:), words(:)
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      integer :: k
      logical :: ok
      call read_deck(ref, overrides, deck, err)
      if (.not. allocated(err)) then
         call check('deck error, ' // name // ': rejected', .false.)
         return
      end if
      ok = index(err%message, new_line('a')) == 0
      do k = 1, size(words)
         ok = ok .and. index(err%message, trim(words(k))) > 0
      end do
      call check('deck error, ' // name // ': one line naming ' // join_words(words), ok, &
                 err%message)
   end subroutine bad

   pure function join_words(w) result(t)
      character(len=*), intent(in) :: w(:)
      character(len=:), allocatable :: t
      integer :: j
      t = ''
      do j = 1, size(w)
         if (j > 1) t = t // ', '
         t = t // trim(w(j))
      end do
   end function join_words

   !> The exact monodromy (transition and saltation matrices) against central differences of
   !> the exact map: no impact, impacts at a zero gap, impacts on a damped stop (the saltation
   !> matrices at the onsets; without them the error is 3e-2).
   subroutine monodromy_against_differences()
      character(len=300) :: cases(3)
      character(len=24) :: names(3)
      integer :: k
      cases = [character(len=300) :: '&stops gap = 1.0 /', '&stops gap = 0.0 /', &
               '&stops damping = 0.02 /']
      names = [character(len=24) :: 'no impact', 'zero gap', 'damped stop']
      do k = 1, 3
         call one(cases(k), trim(names(k)))
      end do
   end subroutine monodromy_against_differences

   subroutine one(case, name)
      character(len=*), intent(in) :: case, name
      type(deck_t) :: deck
      type(model_t) :: model
      type(orbit_map_t) :: ex, fd
      real(dp), allocatable :: u0(:), v0(:), x(:), px(:), px2(:), ja(:, :), jb(:, :)
      type(error_t), allocatable :: err
      integer :: p
      real(dp) :: e
      call load_or_stop('test_continuation', ref, [character(len=300) :: "&solver method = 'exact' /", &
         '&forcing frequency_hz = 10.0 /', case], deck, model, u0, v0)
      call ex%setup(model, deck%solver, 1, 0.0_dp, .true., 1.0e-5_dp, err)
      if (.not. allocated(err)) call fd%setup(model, deck%solver, 1, 0.0_dp, .false., &
                                              1.0e-5_dp, err)
      if (.not. allocated(err)) call transient_orbit(ex, u0, v0, 20, 8, 1.0e-6_dp, x, p, err)
      if (allocated(err)) then
         call check('monodromy, ' // name // ': set-up', .false., err%message)
         return
      end if
      allocate(px(size(x)), px2(size(x)), ja(size(x), size(x)), jb(size(x), size(x)))
      call ex%evaluate(x, px, err, jac=ja)
      if (.not. allocated(err)) call fd%evaluate(x, px2, err, jac=jb)
      if (allocated(err)) then
         call check('monodromy, ' // name // ': maps', .false., err%message)
         return
      end if
      e = maxval(abs(ja - jb)) / maxval(abs(jb))
      call check_le('monodromy, ' // name // ': exact against central differences ' &
         // '(max |error| / max |entry|)', e, 1.0e-6_dp)
      call check('monodromy, ' // name // ': same map', maxval(abs(px - px2)) == 0.0_dp)
   end subroutine one
   ! ---------------------------------------------------------------- the 4 mm line

   !> Labels (period, impacts per recorded period) of an up or down sweep along frequencies fs
   !> of the deck's model, each point from the last point's final state (the first from rest
   !> with a longer transient), exact integrator.
   subroutine line_sweep(deck, model, fs, period, impacts, transient)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      real(dp), intent(in) :: fs(:)
      integer, intent(out) :: period(:), impacts(:)
      integer, intent(in) :: transient          !! periods before each point (300 for the first)
      type(solver_settings_t) :: cfg
      type(diagnostics_settings_t) :: dg
      type(point_result_t) :: pr
      type(model_t) :: m
      type(output_settings_t) :: o
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u(:), v(:)
      integer :: j
      cfg = deck%solver
      cfg%method = 'exact';  cfg%record_periods = 40
      dg = deck%diagnostics
      ! the record as it is (no settling extension), periods at the former fixed tolerance
      dg%lyapunov_periods = 0;  dg%period_max = 8;  dg%period_tolerance = 1.0e-3_dp
      o = deck%output;  o%history_periods = 0
      allocate(u(model%n), v(model%n), source=0.0_dp)
      do j = 1, size(fs)
         cfg%transient_periods = merge(max(300, transient), transient, j == 1)
         m = model
         m%omega = 2.0_dp * pi * fs(j);  m%half_amplitude = 0.5_dp * deck%forcing%amplitude_pp
         call integrate(m, cfg, o, u, v, res, err)
         if (.not. allocated(err)) call point_diagnostics(m, cfg, dg, res, pr, err)
         if (allocated(err)) then
            call check('line sweep at ' // str(fs(j)) // ' Hz', .false., err%message)
            return
         end if
         period(j) = pr%period
         impacts(j) = res%n_impacts(1)
         u = pr%u_end;  v = pr%v_end
      end do
   end subroutine line_sweep

   !> On the 4 mm line (zero gap) from 8.40 to 8.62 Hz: the period doublings (and the
   !> Neimark-Sacker point) of the continued branch lie in the 0.01 Hz step of an up sweep
   !> where its period changes; a direct simulation started on a continued stable orbit (of
   !> period 2) stays on it.
   subroutine reference_line_against_sweep()
      type(deck_t) :: deck
      type(model_t) :: model
      type(continuation_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), fs(:)
      integer, allocatable :: per(:), imp(:)
      integer :: k, j, i, nf
      real(dp) :: f
      character(len=:), allocatable :: name
      call load_or_stop('test_continuation', ref, [character(len=300) :: "&solver method = 'exact' /", &
         '&forcing frequency_hz = 8.40 /', "&job analysis = 'continuation' /", &
         "&continuation parameter = '&forcing frequency_hz', parameter_min = 8.40, " &
         // "parameter_max = 8.62, direction = 'up', step_max = 0.02, max_period = 2 /"], &
         deck, model, u0, v0)
      call run_continuation(deck, res, err)
      if (allocated(err)) then
         call check('4 mm line: continuation runs', .false., err%message)
         return
      end if
      nf = 23
      fs = [(8.40_dp + 0.01_dp * real(j - 1, dp), j = 1, nf)]
      allocate(per(nf), imp(nf))
      call line_sweep(deck, model, fs, per, imp, 100)
      call note('4 mm up sweep 8.40-8.62 Hz, periods: ' // join_int(per))
      call check('4 mm line: two period doublings and a Neimark-Sacker point', &
         count(res%bif_kind == 'period_doubling' .and. res%bif_period == 1) == 2 .and. &
         count(res%bif_kind == 'neimark_sacker') == 1)
      do k = 1, res%n_bif
         if (res%bif_kind(k) /= 'period_doubling' .and. res%bif_kind(k) /= 'neimark_sacker') &
            cycle
         if (res%bif_period(k) /= 1) cycle
         ! the nearest step of the sweep where the period changes: within one step (a sweep
         ! point a hair past a doubling keeps the old period over its transient, the
         ! multiplier being close to -1 there)
         f = res%bif_parameter(k)
         i = 0
         do j = 1, nf - 1
            if (per(j) == per(j + 1)) cycle
            if (i == 0) then
               i = j
            else if (abs(f - 0.5_dp * (fs(j) + fs(j + 1))) < &
                     abs(f - 0.5_dp * (fs(i) + fs(i + 1)))) then
               i = j
            end if
         end do
         name = trim(res%bif_kind(k)) // ' at ' // str(f) // ' Hz'
         if (i == 0) then
            call check('4 mm line: ' // name // ': the sweep changes period', .false.)
            cycle
         end if
         call check_le('4 mm line: ' // name // ' against the nearest period change of the ' &
            // 'sweep (' // str(fs(i)) // ': ' // str(per(i)) // ', ' // str(fs(i + 1)) // ': ' &
            // str(per(i + 1)) // '), distance to its midpoint [Hz]', &
            abs(f - 0.5_dp * (fs(i) + fs(i + 1))), 0.0105_dp)
      end do
      call stays_on_orbit(deck, model, res)
   end subroutine reference_line_against_sweep

   !> A direct simulation (exact integrator, 60 periods) from the section state of the stable
   !> period-2 orbit nearest 8.50 Hz returns to the orbit's two section points every period.
   subroutine stays_on_orbit(deck, model, res)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(continuation_result_t), intent(in) :: res
      type(orbit_map_t) :: m
      type(model_t) :: mdl
      type(state_t) :: st
      type(error_t), allocatable :: err
      real(dp), allocatable :: x(:), px(:), xs(:, :)
      real(dp) :: dev, sz
      integer :: j, best, k
      best = 0
      do j = 1, res%n
         if (res%period(j) /= 2 .or. .not. res%stable(j)) cycle
         if (best == 0) then
            best = j
         else if (abs(res%parameter(j) - 8.50_dp) < abs(res%parameter(best) - 8.50_dp)) then
            best = j
         end if
      end do
      if (best == 0) then
         call check('4 mm line: a stable period-2 orbit was continued', .false.)
         return
      end if
      mdl = model
      mdl%omega = 2 * pi * res%parameter(best)
      call m%setup(mdl, deck%solver, 1, 0.0_dp, .false., 1.0e-5_dp, err)
      x = res%state(:, best)
      allocate(px(size(x)), xs(size(x), 0:1))
      xs(:, 0) = x
      call m%evaluate(x, px, err);  xs(:, 1) = px
      sz = energy_size(m%lp, x)
      dev = 0.0_dp
      call m%section_state(x, st)          ! one run of 60 periods from the section state
      do k = 1, 60
         call m%integ%advance(st, real(k, dp) * m%period, err=err)
         if (allocated(err)) exit
         x = reduce_state(m%lp, st%u, st%v)
         dev = max(dev, energy_size(m%lp, x - xs(:, mod(k, 2))) / sz)
      end do
      call check_le('4 mm line: 60 periods of direct simulation from the continued period-2 ' &
         // 'orbit at ' // str(res%parameter(best)) // ' Hz stay on it (energy distance / size)', &
         dev, 1.0e-8_dp)
   end subroutine stays_on_orbit

   !> The folds of the period-1 branch near 8.78 Hz against the jumps of up and down sweeps:
   !> the up sweep reaches the one-impact orbit just above the upper fold, the down sweep
   !> leaves it just below the lower fold: the hysteresis interval.
   subroutine folds_against_up_down_sweeps()
      type(deck_t) :: deck
      type(model_t) :: model
      type(continuation_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), fs(:), folds(:)
      integer, allocatable :: per(:), imp(:)
      integer :: j, nf, i_up, i_down
      call load_or_stop('test_continuation', ref, [character(len=300) :: "&solver method = 'exact' /", &
         '&forcing frequency_hz = 8.82 /', "&job analysis = 'continuation' /", &
         "&continuation parameter = '&forcing frequency_hz', parameter_min = 8.74, " &
         // "parameter_max = 8.82, direction = 'down', step_max = 0.01, " &
         // 'switch_period_doubling = .false. /'], deck, model, u0, v0)
      call run_continuation(deck, res, err)
      if (allocated(err)) then
         call check('hysteresis: continuation runs', .false., err%message)
         return
      end if
      folds = pack(res%bif_parameter, res%bif_kind == 'saddle_node')
      call check('hysteresis: two folds', size(folds) == 2)
      if (size(folds) /= 2) return
      call note('folds at ' // str(minval(folds)) // ' and ' // str(maxval(folds)) // ' Hz')
      nf = 9
      allocate(per(nf), imp(nf))
      ! up: the first point on the one-impact period-1 orbit. 8.79 Hz lies 0.003 Hz above the
      ! upper fold, where the passage past the fold's ghost is slow (time ~ 1/sqrt(distance)):
      ! 400 periods a point were marginal (enough or not by round-off), 800 and 1600 agree
      fs = [(8.74_dp + 0.01_dp * real(j - 1, dp), j = 1, nf)]
      call line_sweep(deck, model, fs, per, imp, 800)
      call note('up sweep 8.74-8.82 Hz, periods: ' // join_int(per) // '; impacts: ' &
         // join_int(imp))
      i_up = findloc(per == 1 .and. imp == 40, .true., dim=1)
      call check('hysteresis: the up sweep jumps onto the branch in the step of the upper fold',&
         i_up > 1 .and. fs(max(i_up, 2) - 1) < maxval(folds) .and. fs(max(i_up, 1)) > maxval(folds))
      ! down: the last point on it
      fs = fs(nf:1:-1)
      call line_sweep(deck, model, fs, per, imp, 400)
      call note('down sweep 8.82-8.74 Hz, periods: ' // join_int(per) // '; impacts: ' &
         // join_int(imp))
      i_down = findloc(per == 1 .and. imp == 40, .false., dim=1) - 1
      call check('hysteresis: the down sweep leaves the branch in the step of the lower fold', &
         i_down >= 1 .and. i_down < nf .and. fs(max(i_down, 1)) > minval(folds) .and. &
         fs(min(i_down + 1, nf)) < minval(folds))
   end subroutine folds_against_up_down_sweeps

   pure function join_int(v) result(t)
      integer, intent(in) :: v(:)
      character(len=:), allocatable :: t
      integer :: j
      t = ''
      do j = 1, size(v)
         t = t // ' ' // str(v(j))
      end do
   end function join_int

   ! ---------------------------------------------------------------- SDOF in closed form

   !> The continued branch of the SDOF bilinear oscillator against its closed form: below the
   !> grazing the linear steady state, above it the orbit with one contact per period (onset
   !> time, onset velocity and release time solving three equations of closed-form phase maps
   !> by Newton's method); multipliers the eigenvalues of E_free(T - tau_c) E_contact(tau_c).
   subroutine sdof_against_closed_form()
      type(deck_t) :: deck
      type(continuation_result_t) :: res
      type(error_t), allocatable :: err
      character(len=300) :: ov(0)
      real(dp) :: xr(2), es, em, ex, om, fg, lo, hi, u_amp
      complex(dp) :: mr(2), mg(2)
      integer :: j, n_imp, n_lin, k
      call read_deck(sdof, ov, deck, err)
      if (.not. allocated(err)) call run_continuation(deck, res, err)
      if (allocated(err)) then
         call check('SDOF continuation runs', .false., err%message)
         return
      end if
      es = 0.0_dp;  em = 0.0_dp;  n_imp = 0;  n_lin = 0
      do j = 1, res%n
         om = 2 * pi * res%parameter(j)
         if (res%located(j)) cycle          ! a grazing point: contact of zero duration
         if (res%impacts(j) == 0) then
            call linear_orbit(om, xr, mr)
            n_lin = n_lin + 1
         else
            call impacting_orbit(om, res%state(:, j), xr, mr, err)
            if (allocated(err)) then
               call check('SDOF closed form at ' // str(res%parameter(j)) // ' Hz', .false., &
                          err%message)
               return
            end if
            n_imp = n_imp + 1
         end if
         u_amp = max(abs(xr(1)), abs(xr(2)) / om)
         es = max(es, abs(res%state(1, j) - xr(1)) / u_amp, &
                  abs(res%state(2, j) - xr(2)) / (om * u_amp))
         mg = res%multipliers(:, j)
         ex = min(maxval(abs(mg - mr)), maxval(abs(mg - mr([2, 1]))))
         em = max(em, ex)
      end do
      call note('SDOF: ' // str(n_lin) // ' orbits without impact, ' // str(n_imp) // ' with ' &
         // 'one impact per period, 3 to 12 Hz')
      call check('SDOF: both regimes continued', n_lin > 5 .and. n_imp > 20)
      call check_le('SDOF branch: section state against the closed form (max relative error)', &
                    es, 1.0e-8_dp)
      call check_le('SDOF branch: multipliers against the closed form (max error)', em, 1.0e-8_dp)
      ! grazing: the linear orbit's amplitude |U(Omega)| reaches the gap
      lo = 2 * pi * 3.0_dp;  hi = 2 * pi * 6.0_dp
      do k = 1, 200
         om = 0.5_dp * (lo + hi)
         if (abs(lin_amplitude(om)) < gap) then
            lo = om
         else
            hi = om
         end if
      end do
      fg = 0.5_dp * (lo + hi) / (2 * pi)
      do k = 1, res%n_bif
         if (res%bif_kind(k) == 'grazing') then
            call check_close('SDOF: grazing frequency against |U(Omega)| = gap [Hz]', &
                             res%bif_parameter(k), fg, rtol=1.0e-7_dp)
         end if
      end do
      call check('SDOF: one grazing found', count(res%bif_kind == 'grazing') == 1)
      call written_and_read_back(res)
   end subroutine sdof_against_closed_form

   !> &continuation period = 2 on a period-1 orbit: continued as period 1, with a note (it
   !> used to be reported as a period-2 branch whose multipliers were the squares of the
   !> period-1 ones).
   subroutine period_reduced_to_the_orbits_own()
      type(deck_t) :: deck
      type(continuation_result_t) :: res
      type(error_t), allocatable :: err
      call read_deck(sdof, [character(len=200) :: "&continuation period = 2, parameter_max " &
         // "= 4.0 /"], deck, err)
      if (.not. allocated(err)) call run_continuation(deck, res, err)
      if (allocated(err)) then
         call check('period = 2 on a period-1 orbit runs', .false., err%message);  return
      end if
      call check('period = 2 on a period-1 orbit: the branch is a period-1 branch', &
         res%branches(1)%period == 1 .and. all(res%period == 1))
      call check('... with a note saying so: ' // res%note, index(res%note, 'repeats after 1') &
         > 0 .and. index(res%note, 'period-1') > 0)
   end subroutine period_reduced_to_the_orbits_own

   !> A continuation from the lower bound of its variable (&stops gap(1) from 0): the
   !> derivative in the variable is one-sided there, and the branch ends at the bound going
   !> down (it used to stop with "gap(1) = -1E-009: must be >= 0", an internal value).
   subroutine start_at_a_bound()
      type(deck_t) :: deck
      type(continuation_result_t) :: res
      type(error_t), allocatable :: err
      call read_deck(sdof, [character(len=200) :: '&stops gap = 0.0 /', &
         "&continuation parameter = '&stops gap(1)', parameter_min = 0.0, parameter_max = " &
         // "1.5e-5, direction = 'both' /"], deck, err)
      if (.not. allocated(err)) call run_continuation(deck, res, err)
      if (allocated(err)) then
         call check('a continuation from gap(1) = 0, its bound, runs', .false., err%message)
         return
      end if
      call check('a continuation from gap(1) = 0, its bound, runs: ' &
         // str(res%branches(1)%last - res%branches(1)%first + 1) // ' points up to ' &
         // str(maxval(res%parameter)) // ' m', res%n > 5 .and. maxval(res%parameter) > 1.0e-5_dp &
         .and. minval(res%parameter) >= 0.0_dp)
      call check('... and its down side ends at the bound: ' // trim(res%branches(1)%ended), &
         index(res%branches(1)%ended, 'reached the lower bound') > 0)
   end subroutine start_at_a_bound

   !> The result files: PREFIX.h5 read back (parameter with its unit, multipliers, stable,
   !> bifurcation kinds) and the four tables written; then deleted.
   subroutine written_and_read_back(res)
      type(continuation_result_t), intent(in) :: res
      character(len=*), parameter :: prefix = 'test_continuation_output'
      character(len=*), parameter :: tables(4) = [character(len=17) :: '.branches.dat', &
         '.bifurcations.dat', '.multipliers.dat', '.curves.dat']
      type(h5_reader_t) :: h5
      type(error_t), allocatable :: err
      real(dp), allocatable :: par(:), mre(:, :)
      integer, allocatable :: stab(:)
      character(len=:), allocatable :: kinds(:), units
      integer :: k
      call write_continuation(prefix, 'test', 'deck text', '', res, .true., err)
      if (allocated(err)) then
         call check('output: written', .false., err%message)
         return
      end if
      call h5%open(prefix // '.h5', err)
      if (.not. allocated(err)) call h5%read('/continuation/parameter', par, err)
      if (.not. allocated(err)) call h5%read_units('/continuation/parameter', units, err)
      if (.not. allocated(err)) call h5%read('/continuation/multipliers/real', mre, err)
      if (.not. allocated(err)) call h5%read('/continuation/stable', stab, err)
      if (.not. allocated(err)) call h5%read('/continuation/bifurcations/kind', kinds, err)
      call h5%close()
      if (allocated(err)) then
         call check('output: read back', .false., err%message)
      else
         call check('output: /continuation/parameter in Hz, as computed', units == 'Hz' .and. &
            size(par) == res%n .and. all(par == res%parameter))
         call check('output: multipliers (real parts) and stable flags', &
            all(mre == real(res%multipliers, dp)) .and. all((stab == 1) .eqv. res%stable))
         call check('output: bifurcation kinds', size(kinds) == res%n_bif .and. &
            all(kinds == res%bif_kind))
      end if
      do k = 1, 4
         call check('output: ' // prefix // trim(tables(k)) // ' written', &
                    file_exists(prefix // trim(tables(k))))
         call remove_file(prefix // trim(tables(k)))
      end do
      call remove_file(prefix // '.h5')
   end subroutine written_and_read_back

   !> The grazing point continued in (frequency, amplitude): the SDOF's linear orbit touches the
   !> stop where |U(Omega)| = gap, i.e. on A_pp(Omega) = 2 gap |k/m - Omega^2 + i c Omega / m|
   !> / Omega^2; every point of the curve against it.
   subroutine sdof_grazing_curve()
      type(deck_t) :: deck
      type(continuation_result_t) :: res
      type(error_t), allocatable :: err
      real(dp) :: e, om, ac
      integer :: j, k, n
      call read_deck(sdof, [character(len=200) :: "&continuation parameter2 = '&forcing " &
         // "amplitude_pp', parameter2_min = 3.0e-4, parameter2_max = 1.2e-3, curves = " &
         // "'grazing', parameter_max = 6.0, curve_step = 0.05 /"], deck, err)
      if (.not. allocated(err)) call run_continuation(deck, res, err)
      if (allocated(err)) then
         call check('SDOF grazing curve: runs', .false., err%message)
         return
      end if
      call check('SDOF grazing curve: one curve', size(res%curves) == 1)
      if (size(res%curves) /= 1) return
      e = 0.0_dp;  n = 0
      do k = 1, size(res%curves)
         do j = 1, size(res%curves(k)%parameter)
            om = 2 * pi * res%curves(k)%parameter(j)
            ac = 2 * gap * abs(cmplx(k1 / m1 - om**2, c1 / m1 * om, dp)) / om**2
            e = max(e, abs(res%curves(k)%parameter2(j) - ac) / ac)
            n = n + 1
         end do
      end do
      call note('SDOF grazing curve: ' // str(n) // ' points, ' &
         // str(minval(res%curves(1)%parameter)) // ' to ' // str(maxval(res%curves(1)%parameter)) &
         // ' Hz; ' // trim(res%curves(1)%ended))
      call check('SDOF grazing curve: spans the amplitude range', &
         minval(res%curves(1)%parameter2) < 3.1e-4_dp .and. &
         maxval(res%curves(1)%parameter2) > 1.19e-3_dp)
      call check_le('SDOF grazing curve: amplitude against the closed form (max relative ' &
         // 'error)', e, 1.0e-8_dp)
   end subroutine sdof_grazing_curve

   !> The SDOF's orbit at 3 Hz (no impact) started from a given section state (&initial, the
   !> closed form's x 1.2) instead of a transient, and the branch to 5 Hz with the monodromy by
   !> finite differences instead of the exact one: the same orbits and multipliers.
   subroutine sdof_given_start_and_differences()
      type(deck_t) :: deck
      type(continuation_result_t) :: res
      type(error_t), allocatable :: err
      real(dp) :: xr(2), es, em, om
      complex(dp) :: mr(2), mg(2)
      character(len=200) :: ov(2)
      integer :: j
      om = 2 * pi * 3.0_dp
      call linear_orbit(om, xr, mr)
      write(ov(1), '(a, es24.16, a, es24.16, a)') "&initial kind = 'given', node = 2, dof = " &
         // "'w', displacement = ", 1.2_dp * xr(1), ', velocity = ', 1.2_dp * xr(2), ' /'
      ov(2) = "&continuation start = 'given', period = 1, jacobian = 'finite_difference', " &
         // 'parameter_max = 5.0, tolerance = 1.0e-11 /'
      call read_deck(sdof, ov, deck, err)
      if (.not. allocated(err)) call run_continuation(deck, res, err)
      if (allocated(err)) then
         call check('SDOF given start, differences: runs', .false., err%message)
         return
      end if
      es = 0.0_dp;  em = 0.0_dp
      do j = 1, res%n
         if (res%located(j) .or. res%impacts(j) > 0) cycle
         om = 2 * pi * res%parameter(j)
         call linear_orbit(om, xr, mr)
         es = max(es, maxval(abs(res%state(:, j) - xr) / [abs(xr(1)) + abs(xr(2)) / om, &
                                                          om * abs(xr(1)) + abs(xr(2))]))
         mg = res%multipliers(:, j)
         em = max(em, min(maxval(abs(mg - mr)), maxval(abs(mg - mr([2, 1])))))
      end do
      call check_close('SDOF given start: the branch starts at the deck''s 3 Hz', &
                       res%parameter(1), 3.0_dp, rtol=1.0e-14_dp)
      call check_le('SDOF, finite-difference monodromy: states against the closed form', es, &
                    1.0e-8_dp)
      call check_le('SDOF, finite-difference monodromy: multipliers against the closed form', &
                    em, 1.0e-7_dp)
      call check('SDOF, finite-difference monodromy: the grazing found', &
                 count(res%bif_kind == 'grazing') == 1)
   end subroutine sdof_given_start_and_differences

   !> Complex amplitude of the forced response of a phase with stiffness ke: u = Re(U e^{i W t}).
   pure complex(dp) function forced_amplitude(ke, om) result(u)
      real(dp), intent(in) :: ke, om
      u = (0.0_dp, -1.0_dp) * a1 * om**2 / cmplx(ke / m1 - om**2, c1 / m1 * om, dp)
   end function forced_amplitude

   pure real(dp) function lin_amplitude(om)
      real(dp), intent(in) :: om
      lin_amplitude = abs(forced_amplitude(k1, om))
   end function lin_amplitude

   !> Homogeneous propagator e^{A tau} of u'' + (c/m) u' + (ke/m) u = 0 (underdamped).
   pure function propagator(ke, tau) result(e)
      real(dp), intent(in) :: ke, tau
      real(dp) :: e(2, 2), w, z, wd, ex, cs, sn
      w = sqrt(ke / m1);  z = c1 / (2 * m1 * w);  wd = w * sqrt(1 - z**2)
      ex = exp(-z * w * tau);  cs = cos(wd * tau);  sn = sin(wd * tau)
      e(1, 1) = ex * (cs + z * w / wd * sn);  e(1, 2) = ex * sn / wd
      e(2, 1) = -ex * w**2 / wd * sn;  e(2, 2) = ex * (cs - z * w / wd * sn)
   end function propagator

   !> Particular solution (u, v) of a phase at t: static part plus the harmonic.
   pure function particular(contact, om, t) result(x)
      logical, intent(in) :: contact
      real(dp), intent(in) :: om, t
      real(dp) :: x(2), ke, us
      complex(dp) :: u, e
      ke = k1;  us = 0.0_dp
      if (contact) then
         ke = k1 + ks;  us = ks * gap / (k1 + ks)
      end if
      u = forced_amplitude(ke, om)
      e = exp(cmplx(0.0_dp, om * t, dp))
      x(1) = us + real(u * e);  x(2) = real((0.0_dp, 1.0_dp) * om * u * e)
   end function particular

   !> The state at tb of a phase started from x at ta.
   pure function phase(contact, om, ta, x, tb) result(y)
      logical, intent(in) :: contact
      real(dp), intent(in) :: om, ta, x(2), tb
      real(dp) :: y(2), ke
      ke = k1
      if (contact) ke = k1 + ks
      y = particular(contact, om, tb) + matmul(propagator(ke, tb - ta), &
                                               x - particular(contact, om, ta))
   end function phase

   !> Linear steady state at the section (t = 0) and its multipliers.
   subroutine linear_orbit(om, x, mu)
      real(dp), intent(in) :: om
      real(dp), intent(out) :: x(2)
      complex(dp), intent(out) :: mu(2)
      x = particular(.false., om, 0.0_dp)
      call eig2(propagator(k1, 2 * pi / om), mu)
   end subroutine linear_orbit

   !> Eigenvalues of a 2 x 2 matrix.
   subroutine eig2(a, mu)
      real(dp), intent(in) :: a(2, 2)
      complex(dp), intent(out) :: mu(2)
      complex(dp) :: tr, dt, sq
      tr = a(1, 1) + a(2, 2);  dt = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
      sq = sqrt(tr**2 / 4 - dt)
      mu = [tr / 2 + sq, tr / 2 - sq]
   end subroutine eig2

   !> The orbit with one contact per period near the given section state: onset time t_on,
   !> onset velocity v_on and release time t_off from closed-form phase maps (Newton), then
   !> the section state and the multipliers.
   subroutine impacting_orbit(om, x0, x, mu, err)
      real(dp), intent(in) :: om, x0(2)
      real(dp), intent(out) :: x(2)
      complex(dp), intent(out) :: mu(2)
      type(error_t), allocatable, intent(out) :: err
      real(dp) :: per, z(3), f(3), jz(3, 3), zp(3), fp(3), h, y(2), t, tn, tb
      integer :: it, j, info, ipiv(3)
      logical :: inc, inc_n
      per = 2 * pi / om
      ! a guess from the given state: sample one period with the phase maps, find u = gap
      t = 0.0_dp;  y = x0;  inc = y(1) > gap
      z = -1.0_dp
      do j = 1, 40000
         tn = t + per / 20000
         y = phase(inc, om, t, y, tn)
         inc_n = y(1) > gap
         if (inc_n .neqv. inc) then
            if (inc_n .and. z(1) < 0.0_dp) then
               z(1) = tn;  z(2) = y(2)
            else if (.not. inc_n .and. z(1) >= 0.0_dp) then
               z(3) = tn;  exit
            end if
            inc = inc_n
         end if
         t = tn
      end do
      if (z(3) < 0.0_dp) then
         allocate(err);  err%message = 'no onset and release found'
         return
      end if
      do it = 1, 30
         call residual(om, z, f)
         if (maxval(abs(f / [gap, gap, abs(z(2))])) < 1.0e-15_dp) exit
         do j = 1, 3
            h = 1.0e-7_dp * max(abs(z(j)), merge(per, abs(z(2)), j /= 2))
            zp = z;  zp(j) = z(j) + h
            call residual(om, zp, fp)
            jz(:, j) = (fp - f) / h
         end do
         f = -f
         call dgesv3(jz, f, ipiv, info)
         z = z + f
      end do
      call residual(om, z, f)
      if (maxval(abs(f / [gap, gap, abs(z(2))])) > 1.0e-12_dp) then
         allocate(err);  err%message = 'closed form: no convergence'
         return
      end if
      ! section state: from the release, free flight to the next multiple of the period (or
      ! through the next contact when the section falls inside one)
      tb = per * real(ceiling(z(3) / per), dp)
      if (tb < z(1) + per) then
         x = phase(.false., om, z(3), [gap, phase_v(om, z)], tb)
      else
         x = phase(.true., om, z(1) + per, [gap, z(2)], tb)
      end if
      call eig2(matmul(propagator(k1, z(1) + per - z(3)), propagator(k1 + ks, z(3) - z(1))), mu)
   end subroutine impacting_orbit

   !> Velocity at the release of the contact phase started at onset (z(1), gap, z(2)).
   real(dp) function phase_v(om, zz)
      real(dp), intent(in) :: om, zz(3)
      real(dp) :: w(2)
      w = phase(.true., om, zz(1), [gap, zz(2)], zz(3))
      phase_v = w(2)
   end function phase_v

   !> Residual of the one-contact orbit: release at gap, next onset at gap with v_on.
   subroutine residual(om, zz, ff)
      real(dp), intent(in) :: om, zz(3)
      real(dp), intent(out) :: ff(3)
      real(dp) :: w1(2), w2(2)
      w1 = phase(.true., om, zz(1), [gap, zz(2)], zz(3))
      w2 = phase(.false., om, zz(3), [gap, w1(2)], zz(1) + 2 * pi / om)
      ff = [w1(1) - gap, w2(1) - gap, w2(2) - zz(2)]
   end subroutine residual

   !> 3 x 3 Gaussian elimination with partial pivoting.
   subroutine dgesv3(a, b, ipiv, info)
      real(dp), intent(inout) :: a(3, 3), b(3)
      integer, intent(out) :: ipiv(3), info
      integer :: i, k, p
      real(dp) :: f, r(3), t
      info = 0
      do k = 1, 3
         p = k - 1 + maxloc(abs(a(k:, k)), dim=1)
         ipiv(k) = p
         r = a(k, :);  a(k, :) = a(p, :);  a(p, :) = r
         t = b(k);  b(k) = b(p);  b(p) = t
         do i = k + 1, 3
            f = a(i, k) / a(k, k)
            a(i, :) = a(i, :) - f * a(k, :);  b(i) = b(i) - f * b(k)
         end do
      end do
      do k = 3, 1, -1
         b(k) = (b(k) - dot_product(a(k, k + 1:), b(k + 1:))) / a(k, k)
      end do
   end subroutine dgesv3
end program test_continuation
