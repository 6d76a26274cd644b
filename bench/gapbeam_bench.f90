!> Speed benchmark of the Newmark gap solver on the reference case: Moon & Shaw, 10.5 Hz,
!> 3.7 mm peak to peak, 4 elements (inputs/moon_shaw_10p5hz.nml), 300 transient + 1000 recorded
!> forcing periods, run with `run_transient` exactly as the `gapbeam` program runs it.
!>
!> Cases (each the whole run_transient call: step operators, stepping, sampling, statistics):
!>   a  fixed step T/256, condensed stop force, no event location (pure Newmark rate, active stop)
!>   b  fixed step T/256, condensed, event location on
!>   c  fixed step T/256, the paper's fixed point on the stop force, no event location
!>   d  half-step control at 0.01 (condensed, events on; the default before method 'auto')
!>   e  half-step control, fixed point, no event location (the paper's own method)
!>   f  Newmark with error control at tolerance 1e-4 (what 'auto' runs for a Hertz stop)
!>   g  the deck's default, method 'auto': the exact event-driven integrator
!>   h  the ceiling: a minimal loop in this program doing the arithmetic of one condensed
!>      fixed-step Newmark step with one bilinear stop on the same model (dense Kbar^-1 M
!>      product, closed-form stop force, correction), no allocation and no call but sin;
!>      run for as many steps as (a) and checked against (a)'s final state.
!>
!> Wall time from system_clock, the best (least) of the runs of each case: at least 3, more
!> while the runs of the case took under 1 s in all (at most 25). steps/s counts
!> accepted steps (sub-steps of an event split included); "ratio" is a case's steps/s over the
!> ceiling's. Run from the repository root (scripts/bench.sh does). Exit status 1 when the
!> ceiling does not reproduce case (a), or a run fails.
program gapbeam_bench
   use, intrinsic :: iso_fortran_env, only: int64, output_unit, error_unit, compiler_version, &
      compiler_options
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_description, only: law_bilinear
   use gapbeam_results, only: transient_result_t
   use gapbeam_model_builder, only: build_full_model, initial_vectors
   use gapbeam_integrator, only: start_state
   use gapbeam_transient, only: integrate
   use gapbeam_lapack, only: dpotrf, dpotrs
   implicit none

   character(len=*), parameter :: deck_path = 'inputs/moon_shaw_10p5hz.nml'
   integer, parameter :: n_rep = 3           !! timings per case at least; the least is reported
   integer, parameter :: max_rep = 25        !! timings per case at most
   real(dp), parameter :: min_total = 1.0_dp !! more timings while less than this was spent [s]
   integer, parameter :: n_case = 7          !! library cases a..g
   integer, parameter :: ov_len = 200
   character(len=*), parameter :: horizon = &
      '&solver transient_periods = 300, record_periods = 1000 /'
   real(dp), parameter :: same_tol = 1.0e-10_dp   !! ceiling vs (a): relative final-state match

   character(len=56) :: label(n_case + 1)
   character(len=ov_len) :: setting(n_case)
   real(dp) :: wall(n_case + 1), rate(n_case + 1)
   integer(int64) :: steps(n_case + 1), rejected(n_case + 1)
   integer :: runs(n_case + 1)
   type(transient_result_t) :: res(n_case)
   type(model_t) :: prob_a
   real(dp), allocatable :: uc(:), vc(:), ac(:)
   real(dp) :: diff, t_period
   integer :: i
   logical :: same

   label(1) = 'a  fixed T/256, condensed, events off'
   label(2) = 'b  fixed T/256, condensed, events on'
   label(3) = 'c  fixed T/256, fixed_point, events off'
   label(4) = 'd  half_step 0.01 (condensed, events on)'
   label(5) = 'e  half_step 0.01, fixed_point, events off (paper)'
   label(6) = 'f  newmark, error control, tolerance 1e-4'
   label(7) = "g  the deck's default: auto (exact integrator)"
   label(8) = 'h  CEILING: hand loop = (a) arithmetic'
   setting(1) = "&solver step_control = 'fixed', steps_per_period = 256, " &
      // "stop_solution = 'condensed', locate_events = .false. /"
   setting(2) = "&solver step_control = 'fixed', steps_per_period = 256, " &
      // "stop_solution = 'condensed', locate_events = .true. /"
   setting(3) = "&solver step_control = 'fixed', steps_per_period = 256, " &
      // "stop_solution = 'fixed_point', locate_events = .false. /"
   setting(4) = "&solver step_control = 'half_step', half_step_tolerance = 0.01 /"
   setting(5) = "&solver step_control = 'half_step', half_step_tolerance = 0.01, " &
      // "stop_solution = 'fixed_point', locate_events = .false. /"
   setting(6) = "&solver method = 'newmark', step_control = 'error', tolerance = 1e-4 /"
   setting(7) = ''

   do i = 1, n_case
      write(error_unit, '(a)') 'bench: running ' // trim(label(i))
      flush(error_unit)
      if (i == 1) then
         call time_case(setting(i), wall(i), runs(i), res(i), prob_a)
      else
         call time_case(setting(i), wall(i), runs(i), res(i))
      end if
      steps(i) = res(i)%steps_accepted
      rejected(i) = res(i)%steps_rejected
   end do

   write(error_unit, '(a)') 'bench: running ' // trim(label(n_case + 1))
   flush(error_unit)
   call time_ceiling(prob_a, res(1)%steps_accepted, wall(n_case + 1), runs(n_case + 1), uc, vc, &
                     ac)
   steps(n_case + 1) = res(1)%steps_accepted
   rejected(n_case + 1) = 0
   diff = max(rel_diff(uc, res(1)%u), rel_diff(vc, res(1)%v), rel_diff(ac, res(1)%a))
   same = diff <= same_tol

   rate = real(steps, dp) / wall
   t_period = 2.0_dp * pi / prob_a%omega

   ! ---- report
   write(output_unit, '(a)') 'gapbeam benchmark: ' // deck_path // ' (10.5 Hz, 3.7 mm p-p, ' &
      // '4 elements, 9 dofs, one bilinear stop at the tip)'
   write(output_unit, '(a, i0, a, es10.3, a)') '300 transient + 1000 recorded periods; ' &
      // 'fixed step T/256 = ', 256, ' steps per period, T = ', t_period, ' s'
   write(output_unit, '(a, i0, a, f0.1, a, i0, a)') 'wall time: system_clock around ' &
      // 'run_transient, best (least) of the runs: at least ', n_rep, ', more while under ', &
      min_total, ' s in all, at most ', max_rep
   write(output_unit, '(a)') 'steps/s = accepted steps / wall; ratio = steps/s / ceiling steps/s'
   write(output_unit, '(a)') 'compiler: ' // compiler_version()
   write(output_unit, '(a)') 'options:  ' // compiler_options()
   write(output_unit, '(a)') ''
   write(output_unit, '(a56, a10, a11, a10, a13, a18, a6)') pad('case'), 'wall [s]', 'steps', &
      'rejected', 'steps/s', 'ratio to ceiling', 'runs'
   do i = 1, n_case + 1
      write(output_unit, '(a56, f10.4, i11, i10, es13.3, f18.3, i6)') label(i), wall(i), &
         steps(i), rejected(i), rate(i), rate(i) / rate(n_case + 1), runs(i)
   end do
   write(output_unit, '(a)') ''
   write(output_unit, '(a)') 'details (last run of each case): events split, factorizations, ' &
      // 'fixed-point iterations, impacts in the record, contact fraction, smallest step [s]'
   do i = 1, n_case
      write(output_unit, '(a56, i9, i9, i10, i7, f8.4, es11.3)') label(i), res(i)%events, &
         res(i)%factorizations, res(i)%fp_iterations, res(i)%n_impacts(1), &
         res(i)%contact_fraction(1), res(i)%dt_smallest
   end do
   write(output_unit, '(a)') ''
   write(output_unit, '(a, i0, a, es10.3, a, es8.1, a)') 'ceiling check: final (u, v, a) of ' &
      // 'the hand loop vs case a after ', steps(n_case + 1), ' steps: max relative difference ', diff, &
      ' (want <= ', same_tol, '): ' // trim(merge('same state, same arithmetic', &
      'MISMATCH                   ', same))
   write(output_unit, '(a)') ''
   write(output_unit, '(a)') "whole 1300-period run with the deck's default settings: " &
      // fixed(wall(7), 3) // ' s (goal < 0.5 s)'
   write(output_unit, '(a)') 'fixed-step Newmark with an active stop: ' &
      // fixed(rate(1) / 1.0e6_dp, 2) // ' Msteps/s (goal >= 10 M/s), ceiling ' &
      // fixed(rate(n_case + 1) / 1.0e6_dp, 2) // ' Msteps/s, ratio ' &
      // fixed(rate(1) / rate(n_case + 1), 3)
   flush(output_unit)
   if (.not. same) error stop 1

contains

   !> x with d decimals and a leading zero (f0.d drops it).
   function fixed(x, d) result(s)
      real(dp), intent(in) :: x
      integer, intent(in) :: d
      character(len=:), allocatable :: s
      character(len=40) :: buf, fmt
      write(fmt, '(a, i0, a)') '(f0.', d, ')'
      write(buf, fmt) x
      s = trim(adjustl(buf))
      if (s(1:1) == '.') s = '0' // s
      if (len(s) > 1) then
         if (s(1:2) == '-.') s = '-0' // s(2:)
      end if
   end function fixed

   !> text padded on the right to the width of a label.
   function pad(text) result(s)
      character(len=*), intent(in) :: text
      character(len=56) :: s
      s = text
   end function pad

   !> max |x - y| / max |y|.
   pure real(dp) function rel_diff(x, y)
      real(dp), intent(in) :: x(:), y(:)
      rel_diff = maxval(abs(x - y)) / max(maxval(abs(y)), tiny(1.0_dp))
   end function rel_diff

   !> Stop with a message when err is set.
   subroutine die_on(err, what)
      type(error_t), allocatable, intent(in) :: err
      character(len=*), intent(in) :: what
      if (allocated(err)) then
         write(error_unit, '(a)') 'bench: error: ' // what // ': ' // err%message
         error stop 1
      end if
   end subroutine die_on

   !> True while another timing is wanted after `rep` runs that took `total` seconds.
   logical function more_runs(rep, total)
      integer, intent(in) :: rep
      real(dp), intent(in) :: total
      more_runs = rep < n_rep .or. (total < min_total .and. rep < max_rep)
   end function more_runs

   !> Read the deck with the horizon and `ov` as overrides, build the problem, and time
   !> run_transient (see more_runs); best wall time, the number of runs and the last result.
   subroutine time_case(ov, best, rep, res, prob_out)
      character(len=*), intent(in) :: ov
      real(dp), intent(out) :: best
      integer, intent(out) :: rep
      type(transient_result_t), intent(out) :: res
      type(model_t), intent(out), optional :: prob_out
      type(deck_t) :: deck
      type(model_t) :: model
      type(error_t), allocatable :: err
      character(len=ov_len), allocatable :: ovs(:)
      real(dp), allocatable :: u0(:), v0(:)
      integer(int64) :: c0, c1, crate, steps_first
      real(dp) :: total, t
      if (len_trim(ov) > 0) then
         ovs = [character(len=ov_len) :: horizon, ov]
      else
         ovs = [character(len=ov_len) :: horizon]
      end if
      call read_deck(deck_path, ovs, deck, err)
      call die_on(err, 'reading ' // deck_path)
      call build_full_model(deck%structure, deck%stops, deck%damping, deck%forcing, model, err)
      call die_on(err, 'building the problem')
      call initial_vectors(model, deck%initial, u0, v0)
      best = huge(1.0_dp)
      steps_first = -1
      rep = 0;  total = 0.0_dp
      do while (more_runs(rep, total))
         rep = rep + 1
         call system_clock(c0, crate)
         call integrate(model, deck%solver, deck%output, u0, v0, res, err)
         call system_clock(c1)
         call die_on(err, 'integrate')
         t = real(c1 - c0, dp) / real(crate, dp)
         best = min(best, t);  total = total + t
         if (rep == 1) steps_first = res%steps_accepted
         if (res%steps_accepted /= steps_first) then
            write(error_unit, '(a)') 'bench: error: repeated runs took different step counts'
            error stop 1
         end if
      end do
      if (present(prob_out)) prob_out = model
   end subroutine time_case

   !> Precompute the step operator of the ceiling loop for dt = T/256, Newmark (0.5, 0.25),
   !> run it n_steps from the deck's initial state (at rest) (see more_runs); best wall time,
   !> the number of runs and the final state.
   subroutine time_ceiling(model, n_steps, best, rep, u, v, a)
      type(model_t), intent(in) :: model
      integer(int64), intent(in) :: n_steps
      real(dp), intent(out) :: best
      integer, intent(out) :: rep
      real(dp), allocatable, intent(out) :: u(:), v(:), a(:)
      integer, parameter :: steps_per_period = 256, max_halvings = 20
      real(dp), parameter :: delta = 0.5_dp, alpha = 0.25_dp
      real(dp), allocatable :: kbar(:, :), am(:, :), rhs(:, :), u0(:), v0(:), a0v(:)
      type(state_t) :: s0
      real(dp) :: period, dt, tick_dt, a0, a1, a2, a3, a4, a5, c0k, c1k, cw, ch, amp_w2, h, &
         total, t
      integer(int64) :: nt, cl0, cl1, crate
      integer :: n, itip, info
      n = model%n
      if (model%n_contacts /= 1) error stop 'bench: the ceiling needs exactly one contact'
      if (model%c_law(1) /= law_bilinear .or. model%c_c(1) /= 0.0_dp) &
         error stop 'bench: the ceiling needs a bilinear stop without damper'
      itip = model%c_dof(1)
      ! time as run_transient counts it: ticks of dt_max / 2^max_halvings
      period = 2.0_dp * pi / model%omega
      dt = period / real(steps_per_period, dp)
      tick_dt = dt / 2.0_dp**max_halvings
      nt = 2_int64**max_halvings
      dt = real(nt, dp) * tick_dt
      ! Newmark constants and Kbar = (1 + a1 gamma) K + (a0 + a1 beta) M
      a0 = 1.0_dp / (alpha * dt**2)
      a1 = delta / (alpha * dt)
      a2 = 1.0_dp / (alpha * dt)
      a3 = 0.5_dp / alpha - 1.0_dp
      a4 = delta / alpha - 1.0_dp
      a5 = dt * (0.5_dp * delta / alpha - 1.0_dp)
      c1k = 1.0_dp + a1 * model%gamma
      c0k = a0 + a1 * model%beta
      cw = model%beta - model%gamma * c0k / c1k
      ch = model%gamma / c1k
      kbar = c1k * model%sys%k + c0k * model%sys%m
      call dpotrf('U', n, kbar, n, info)
      if (info /= 0) error stop 'bench: Kbar is not positive definite'
      ! gp = Kbar^-1 q, g = Kbar^-1 e_tip, AM = Kbar^-1 M
      allocate(rhs(n, 2))
      rhs(:, 1) = model%q
      rhs(:, 2) = 0.0_dp
      rhs(itip, 2) = 1.0_dp
      call dpotrs('U', n, 2, kbar, n, rhs, n, info)
      am = model%sys%m
      call dpotrs('U', n, n, kbar, n, am, n, info)
      h = rhs(itip, 2)
      amp_w2 = model%half_amplitude * model%omega**2
      ! initial state as run_transient sets it (at rest: u = v = 0, a from equilibrium)
      allocate(u0(n), v0(n), source=0.0_dp)
      call start_state(model, 0.0_dp, u0, v0, s0)
      a0v = s0%a
      allocate(u(n), v(n), a(n))
      best = huge(1.0_dp)
      rep = 0;  total = 0.0_dp
      do while (more_runs(rep, total))
         rep = rep + 1
         u = u0;  v = v0;  a = a0v
         call system_clock(cl0, crate)
         call ceiling_loop(n, n_steps, am, rhs(:, 1), rhs(:, 2), itip, model%c_sign(1), &
            model%c_gap(1), model%c_k(1), h, a0, a1, a2, a3, a4, a5, cw, ch, amp_w2, model%omega, &
            tick_dt, nt, u, v, a)
         call system_clock(cl1)
         t = real(cl1 - cl0, dp) / real(crate, dp)
         best = min(best, t);  total = total + t
      end do
   end subroutine time_ceiling

   !> The ceiling: n_steps condensed Newmark steps of size nt * tick_dt with one bilinear stop
   !> at dof itip. Per step: hm = a0 u + a2 v + a3 a, hc = a1 u + a4 v + a5 a,
   !> y* = AM (hm + cw hc) + ch hc + s(t) gp, d* = s_c y*_tip - gap,
   !> f = max(0, k d* / (1 + k h)), y = y* - g s_c f, v = a1 y - hc, a = a0 y - hm.
   !> The operations are those of gapbeam_newmark:condensed_step (predictor, closed-form stop
   !> force, correction), in the same order, so the result matches integrate to round-off.
   subroutine ceiling_loop(n, n_steps, am, gp, g, itip, sgn, gap, k, h, a0, a1, a2, a3, a4, a5, &
                           cw, ch, amp_w2, omega, tick_dt, nt, u, v, a)
      integer, intent(in) :: n, itip
      integer(int64), intent(in) :: n_steps, nt
      real(dp), intent(in) :: am(n, n), gp(n), g(n)
      real(dp), intent(in) :: sgn, gap, k, h, a0, a1, a2, a3, a4, a5, cw, ch, amp_w2, omega, &
         tick_dt
      real(dp), intent(inout) :: u(n), v(n), a(n)
      real(dp) :: hm(n), hc(n), w(n), y(n)
      real(dp) :: t0, t1, s, d, f
      integer(int64) :: step, tick
      integer :: i, j
      tick = 0
      do step = 1, n_steps
         t0 = real(tick, dp) * tick_dt
         tick = tick + nt
         t1 = real(tick, dp) * tick_dt
         s = amp_w2 * sin(omega * (t0 + (t1 - t0)))
         do i = 1, n
            hm(i) = a0 * u(i) + a2 * v(i) + a3 * a(i)
            hc(i) = a1 * u(i) + a4 * v(i) + a5 * a(i)
            w(i) = hm(i) + cw * hc(i)
            y(i) = 0.0_dp
         end do
         do j = 1, n
            do i = 1, n
               y(i) = y(i) + am(i, j) * w(j)
            end do
         end do
         do i = 1, n
            y(i) = y(i) + ch * hc(i) + s * gp(i)
         end do
         d = sgn * y(itip) - gap
         f = 0.0_dp
         if (d > 0.0_dp) then
            f = k * d / (1.0_dp + k * h)
            if (d - h * f <= 0.0_dp) f = d / h
            do i = 1, n
               y(i) = y(i) - g(i) * (sgn * f)
            end do
         end if
         do i = 1, n
            u(i) = y(i)
            v(i) = a1 * y(i) - hc(i)
            a(i) = a0 * y(i) - hm(i)
         end do
      end do
   end subroutine ceiling_loop
end program gapbeam_bench
