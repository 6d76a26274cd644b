!> The modal exponential integrator (method 'exponential'): a linear free and forced response
!> exact to round-off with steps far beyond every mode's period (against the matrix exponential
!> in extended precision); the order of convergence of its nonlinear part on a contact case;
!> agreement with the exact integrator on a piecewise-linear reduced model (flat stop) and
!> with rk45 at a tight tolerance on a reduced tube with rings and friction; the energy balance;
!> an error estimate that falls to the round-off of the state's change (not of the state over
!> the step) as the step shrinks, late in a forced run; an estimate that bounds the true local
!> error of a step in sliding contact, of the method's order (and the sweeps at the contact
!> dofs give that step as the sweeps over every mode do); method 'auto' runs it on a
!> reduced model that the exact integrator cannot take, at no looser than its tolerance 1e-4.
program test_modal_exponential
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t, diagnostics_settings_t
   use gapbeam_integrator, only: integrator_t, stepper_t, make_integrator, make_stepper, &
      start_state
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_test_runs, only: load_or_stop, run_deck, load_deck
   use gapbeam_attractor, only: auto_period_tolerance
   use gapbeam_certify, only: accuracy_settings, check_diagnostics
   use gapbeam_expm_reference, only: expm_run
   use gapbeam_ring_contact, only: ring_slip
   use gapbeam_exponential, only: exponential_t
   implicit none
   character(len=*), parameter :: prog = 'test_modal_exponential'
   character(len=*), parameter :: beam = 'test/decks/moon_shaw_10p5hz_half_element.nml'
   character(len=*), parameter :: tube = 'test/decks/tube_cantilever.nml'

   call linear_response_exact()
   call convergence_order()
   call flat_stop_against_exact()
   call tube_against_rk45()
   call tiny_steps_estimate()
   call tight_tolerance_after_onsets()
   call estimate_bounds_error()
   call auto_on_reduced_models()
   call finish(prog)

contains

   !> A beam without its stop (free, then forced by the base, Rayleigh damping): steps of T/4
   !> (omega_max h about 2e3) against the matrix exponential of the first-order system in
   !> extended precision.
   subroutine linear_response_exact()
      type(deck_t) :: deck
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:), ur(:), vr(:), u(:), v(:)
      class(stepper_t), allocatable :: st
      type(state_t) :: s0, s1
      type(error_t), allocatable :: err
      real(dp) :: period, h, ratio, eu, ev
      integer :: j, k, switches, n, steps
      character(len=16) :: amp(2)
      character(len=200) :: ov(2)
      logical :: ok
      amp = [character(len=16) :: '0.0', '3.7e-3']
      do k = 1, 2
         ov(1) = '&stops gap = 1.0 / &forcing amplitude_pp = ' // trim(amp(k)) // ' /'
         ov(2) = '&initial kind = ''given'', node = 5, dof = ''w'', displacement = 1.0e-3, ' &
                 // 'velocity = 0.2 /'
         call load_or_stop(prog, beam, ov, deck, model, u0, v0)
         period = 2.0_dp * pi / model%omega
         n = model%n
         if (allocated(ur)) deallocate(ur, vr)
         allocate(ur(n), vr(n))
         call expm_run(model, u0, v0, 3, 64, ur, vr, switches)
         call make_stepper('exponential', st, err)
         if (allocated(err)) then
            call check('exponential stepper', .false., err%message);  return
         end if
         steps = 4
         h = period / steps
         call st%prepare(model, deck%solver, h, err)
         if (allocated(err)) then
            call check('exponential prepares', .false., err%message);  return
         end if
         call start_state(model, 0.0_dp, u0, v0, s0)
         s1 = s0
         do j = 1, 3 * steps
            call st%step(model, s0, s1, ok, ratio, 0)
            s0 = s1
         end do
         u = s0%u;  v = s0%v
         eu = maxval(abs(u - ur)) / maxval(abs(ur))
         ev = maxval(abs(v - vr)) / maxval(abs(vr))
         call note('linear ' // merge('forced', 'free  ', k == 2) // ' response, h = T/4 ' &
            // '(omega_max h = ' // str(model%omega_max * h) // '), 3 periods: error ' &
            // str(eu) // ' (u), ' // str(ev) // ' (v) of the largest value')
         call check_le('linear ' // trim(merge('forced', 'free  ', k == 2)) // ' response ' &
            // 'with steps of T/4 exact to round-off (u)', eu, 1.0e-11_dp)
         call check_le('linear ' // trim(merge('forced', 'free  ', k == 2)) // ' response ' &
            // 'with steps of T/4 exact to round-off (v)', ev, 1.0e-11_dp)
         call check('no contact switch in the reference', switches == 0)
      end do
   end subroutine linear_response_exact

   !> The end state of one forcing period on the flat-stop beam (reduced to 4 modes with its
   !> static mode) under fixed steps T/n with located events, against the exact integrator:
   !> the error's order as n doubles.
   subroutine convergence_order()
      type(deck_t) :: deck
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:)
      type(state_t) :: s_ref, s
      class(integrator_t), allocatable :: integ
      type(solver_settings_t) :: cfg
      type(error_t), allocatable :: err
      real(dp) :: period, e(4), p
      integer :: k
      integer, parameter :: steps(4) = [64, 128, 256, 512]
      call load_or_stop(prog, beam, [character(len=80) :: &
         "&reduction kind = 'modal', n_modes = 4 /"], deck, model, u0, v0)
      period = 2.0_dp * pi / model%omega
      cfg = deck%solver
      cfg%method = 'exact'
      call make_integrator(model, cfg, integ, err)
      if (allocated(err)) then
         call check('exact integrator', .false., err%message);  return
      end if
      call start_state(model, 0.0_dp, u0, v0, s_ref)
      call integ%advance(s_ref, 2.0_dp * period, err=err)
      do k = 1, size(steps)
         cfg = deck%solver
         cfg%method = 'exponential';  cfg%step_control = 'fixed'
         cfg%steps_per_period = steps(k)
         call make_integrator(model, cfg, integ, err)
         if (allocated(err)) then
            call check('exponential integrator', .false., err%message);  return
         end if
         call start_state(model, 0.0_dp, u0, v0, s)
         call integ%advance(s, 2.0_dp * period, err=err)
         if (allocated(err)) then
            call check('exponential, fixed steps T/' // str(steps(k)), .false., err%message)
            return
         end if
         e(k) = maxval(abs(s%u - s_ref%u)) / maxval(abs(s_ref%u))
      end do
      ! the mean order over the three halvings (the located events make each one's noisy)
      p = log(e(1) / e(4)) / log(8.0_dp)
      call note('flat stop, 2 periods, fixed steps T/64 .. T/512: errors ' // str(e(1)) // ', ' &
         // str(e(2)) // ', ' // str(e(3)) // ', ' // str(e(4)) // '; observed orders ' &
         // str(log(e(1) / e(2)) / log(2.0_dp)) // ', ' // str(log(e(2) / e(3)) / log(2.0_dp)) &
         // ', ' // str(log(e(3) / e(4)) / log(2.0_dp)) // '; mean ' // str(p))
      call check('fixed steps converge to the exact integrator (errors fall as steps halve)', &
         e(2) < e(1) .and. e(3) < e(2) .and. e(4) < e(3))
      call check_le('mean order of convergence on the contact case at least 3.5 (observed ' &
         // str(p) // ')', -p, -3.5_dp)
   end subroutine convergence_order

   !> The flat-stop beam reduced (4 modes and the static mode): impacts and peak force under
   !> error control against the exact integrator (the contact fraction is noted only: the
   !> stepping recorder interpolates the onsets and releases linearly, whatever the method).
   subroutine flat_stop_against_exact()
      type(model_t) :: model
      type(transient_result_t) :: rx, re
      type(error_t), allocatable :: err
      character(len=200) :: base(1)
      base(1) = "&reduction kind = 'modal', n_modes = 4 / &solver transient_periods = 0, " &
         // 'record_periods = 4 /'
      call run_deck(beam, [character(len=200) :: base(1), "&solver method = 'exact' /"], &
                    model, rx, err)
      if (allocated(err)) then
         call check('exact run', .false., err%message);  return
      end if
      call run_deck(beam, [character(len=200) :: base(1), "&solver method = 'exponential', " &
                    // 'tolerance = 1.0e-7 /'], model, re, err)
      if (allocated(err)) then
         call check('exponential run', .false., err%message);  return
      end if
      call note('flat stop, reduced: impacts ' // str(re%n_impacts(1)) // ' (exact ' &
         // str(rx%n_impacts(1)) // '), peak force ' // str(re%peak_force(1)) // ' N (exact ' &
         // str(rx%peak_force(1)) // '), contact fraction ' // str(re%contact_fraction(1)) &
         // ' (exact ' // str(rx%contact_fraction(1)) // ')')
      call check('flat stop, reduced: the same impacts as the exact integrator', &
                 re%n_impacts(1) == rx%n_impacts(1))
      call check_close('flat stop, reduced: peak force as the exact integrator', &
                       re%peak_force(1), rx%peak_force(1), 1.0e-4_dp)
   end subroutine flat_stop_against_exact

   !> The rattling cantilever tube (rings, friction, point forces, two planes) reduced: work
   !> rates, sliding, impacts and peak forces against rk45 at the same tight tolerance; the
   !> energy balance.
   subroutine tube_against_rk45()
      type(model_t) :: model
      type(transient_result_t) :: rk, re
      type(error_t), allocatable :: err
      character(len=200) :: base(1)
      real(dp) :: ek, ee
      integer :: k
      base(1) = "&reduction kind = 'auto' / &solver tolerance = 1.0e-6, transient_periods = 2, " &
         // 'record_periods = 3 / &output energy_balance = .true. /'
      call run_deck(tube, [character(len=200) :: base(1), "&solver method = 'rk45' /"], &
                    model, rk, err)
      if (allocated(err)) then
         call check('rk45 run', .false., err%message);  return
      end if
      call run_deck(tube, [character(len=200) :: base(1), "&solver method = 'exponential' /"], &
                    model, re, err)
      if (allocated(err)) then
         call check('exponential run', .false., err%message);  return
      end if
      do k = 1, size(rk%n_impacts)
         call note('tube, support ' // str(k) // ': impacts ' // str(re%n_impacts(k)) &
            // ' (rk45 ' // str(rk%n_impacts(k)) // '), W_N ' // str(re%normal_work_rate(k)) &
            // ' (' // str(rk%normal_work_rate(k)) // '), W_f ' // str(re%friction_work_rate(k)) &
            // ' (' // str(rk%friction_work_rate(k)) // '), sliding ' &
            // str(re%sliding_distance(k)) // ' (' // str(rk%sliding_distance(k)) // ')')
         call check('tube, support ' // str(k) // ': the same impacts as rk45', &
                    re%n_impacts(k) == rk%n_impacts(k))
         ! (20 x the tolerance: 1e-7 measured; 1.4e-4 while the controller checked the cubic
         ! interpolant only, which the wear statistics do not read)
         call check_close('tube, support ' // str(k) // ': normal work rate as rk45', &
                          re%normal_work_rate(k), rk%normal_work_rate(k), 2.0e-5_dp, 1.0e-12_dp)
         call check_close('tube, support ' // str(k) // ': friction work rate as rk45', &
                          re%friction_work_rate(k), rk%friction_work_rate(k), 2.0e-5_dp, &
                          1.0e-12_dp)
         call check_close('tube, support ' // str(k) // ': sliding distance as rk45', &
                          re%sliding_distance(k), rk%sliding_distance(k), 2.0e-5_dp, 1.0e-12_dp)
         call check_close('tube, support ' // str(k) // ': peak force as rk45', &
                          re%peak_force(k), rk%peak_force(k), 1.0e-3_dp, 1.0e-9_dp)
      end do
      ek = imbalance(rk);  ee = imbalance(re)
      call note('tube energy imbalance (of the input work): exponential ' // str(ee) &
                // ', rk45 ' // str(ek))
      ! (the balance is integrated on the quintic Hermite pieces. It was 1.45e-4 when the
      ! cubic interpolant's check was the only measure of the collocation's error, 3.8e-5 with
      ! the collocation's own estimate, 2.7e-6 with the quintic checked too and the step's own
      ! end acceleration)
      call check_le('tube: energy balance closes to 2e-5 of the input work', abs(ee), 2.0e-5_dp)
   end subroutine tube_against_rk45

   !> The reduced rattling tube at tolerance 1e-9, from rest over its first impacts: each
   !> located onset restarts with the ring touching (the right limit's acceleration, with the
   !> damper's c d'), and the step's forces take it as touching too. They did not (a hair
   !> outside by round-off, no force at the start, the damper's force jumping in between the
   !> nodes): the start acceleration that the quintic piece reads was up to 9 % off the step's
   !> own, and the run stopped at the smallest step at t = 5.2e-3 s.
   subroutine tight_tolerance_after_onsets()
      type(model_t) :: model
      type(transient_result_t) :: re, rr
      type(error_t), allocatable :: err
      character(len=200) :: base(2)
      base(1) = "&reduction kind = 'auto' / &solver tolerance = 1.0e-9, transient_periods = 0, " &
         // 'record_periods = 1 /'
      base(2) = "&solver method = 'exponential' /"
      call run_deck(tube, base, model, re, err)
      if (allocated(err)) then
         call check('tube at tolerance 1e-9: the exponential integrator runs', .false., &
                    err%message)
         return
      end if
      call check('tube at tolerance 1e-9: the exponential integrator runs', .true.)
      base(2) = "&solver method = 'rk45' /"
      call run_deck(tube, base, model, rr, err)
      if (allocated(err)) then
         call check('tube at tolerance 1e-9: rk45 runs', .false., err%message);  return
      end if
      call note('tube at 1e-9, 1 period: impacts ' // str(re%n_impacts(1)) // ' (rk45 ' &
         // str(rr%n_impacts(1)) // '), W_N ' // str(re%normal_work_rate(1)) // ' (' &
         // str(rr%normal_work_rate(1)) // ')')
      call check('tube at tolerance 1e-9: the same impacts as rk45', &
                 re%n_impacts(1) == rr%n_impacts(1))
      call check_close('tube at tolerance 1e-9: normal work rate as rk45', &
                       re%normal_work_rate(1), rr%normal_work_rate(1), 1.0e-6_dp, 1.0e-15_dp)
   end subroutine tight_tolerance_after_onsets

   !> The reduced forced tube at t = 2.66 s (the forcing's phase large: sin(Omega t) carries
   !> round-off 1e-13 of its amplitude) from a state with displacements and velocities in every
   !> coordinate: one step of T 1e-4, 1e-7 and 1e-10, and the method's error estimates (the
   !> local error's and the interpolant's, dense_error). They must fall with the step to the
   !> round-off of v, not grow as eps |u| / h: that floor drove the steps of the multispan tube
   !> at tolerance 1e-5 to the smallest one near a grazing onset ('step below the minimum').
   subroutine tiny_steps_estimate()
      type(deck_t) :: deck
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:), fda(:), ev(:), iu(:), iv(:)
      class(stepper_t), allocatable :: st
      type(state_t) :: s0, s1
      type(error_t), allocatable :: err
      real(dp) :: period, h, ratio, coef(3), e_u(3), e_v(3), us, vs
      integer :: j, k
      logical :: ok, has, has_d
      call load_or_stop(prog, tube, [character(len=80) :: "&reduction kind = 'auto' /"], &
                        deck, model, u0, v0)
      period = 2.0_dp * pi / model%omega
      ! inside the clearance, every coordinate moving (the state's acceleration in equilibrium
      ! with it: the interpolant checked is the quintic, from u, v, a at both ends)
      u0 = [(2.0e-6_dp * sin(1.3_dp * j), j = 1, model%n)]
      v0 = [(3.0e-3_dp * cos(0.7_dp * j), j = 1, model%n)]
      call start_state(model, 2.66_dp, u0, v0, s0)
      us = maxval(abs(s0%u));  vs = maxval(abs(s0%v))
      allocate(fda(model%n), ev(model%n), iu(model%n), iv(model%n))
      do k = 1, 3
         call make_stepper('exponential', st, err)
         if (.not. allocated(err)) then
            h = period * 10.0_dp**(-1 - 3 * k)
            call st%prepare(model, deck%solver, h, err)
         end if
         if (allocated(err)) then
            call check('exponential prepares', .false., err%message);  return
         end if
         s1 = s0
         call st%step(model, s0, s1, ok, ratio, 0)
         call st%local_error(model, s0, s1, fda, ev, coef, has)
         call st%dense_error(iu, iv, has_d)
         e_u(k) = max(maxval(abs(fda)) * h**2, maxval(abs(iu))) / us
         e_v(k) = max(maxval(abs(ev)), maxval(abs(iv))) / vs
         deallocate(st)
      end do
      call note('tube at t = 2.66 s, steps T 1e-4, 1e-7, 1e-10: estimate e_u / |u| ' &
         // str(e_u(1)) // ', ' // str(e_u(2)) // ', ' // str(e_u(3)) // '; e_v / |v| ' &
         // str(e_v(1)) // ', ' // str(e_v(2)) // ', ' // str(e_v(3)))
      call check_le('tiny steps: the displacement estimate at h = 1e-10 T is round-off', &
                    e_u(3), 1.0e-13_dp)
      call check_le('tiny steps: the velocity estimate at h = 1e-10 T is round-off of v ' &
                    // '(not eps |u| / h)', e_v(3), 1.0e-13_dp)
      call check_le('tiny steps: the velocity estimate falls from h = 1e-4 T to 1e-7 T', &
                    e_v(2), max(1.0e-3_dp * e_v(1), 1.0e-13_dp))
   end subroutine tiny_steps_estimate

   !> The error estimate against the true local error of a step in sliding contact: the reduced
   !> cantilever tube run under the exponential integrator until a ring slides, then from that
   !> state one step of h = T/100, T/200, T/400 and its estimate (local_error: the sweeps'
   !> difference and the collocation's own error), against 256 steps of h/256 of the same
   !> held regime (the reference's error is 256^-5 of the step's). The estimate must not fall
   !> below the true error by more than a factor 2, nor exceed it by more than 30 (a tight
   !> estimate gives long steps), and the true error must fall at least as h^5.5 (order 5: a
   !> local error h^6; measured h^7.0). The sweeps at the ring dofs (act_sweeps, the default
   !> here) give each step's end state and estimate as the sweeps over every mode
   !> (modal_sweeps) to the round-off of the step's change.
   subroutine estimate_bounds_error()
      type(deck_t) :: deck
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:), fda(:), ev(:)
      class(integrator_t), allocatable :: integ
      class(stepper_t), allocatable :: st, sf
      type(solver_settings_t) :: cfg
      type(state_t) :: s0, s1, sa, sb
      type(error_t), allocatable :: err
      real(dp) :: period, h, ratio, coef(3), e_true(3), e_est(3), t, scale
      integer :: k, j, rg
      logical :: ok, has, found
      call load_or_stop(prog, tube, [character(len=80) :: "&reduction kind = 'auto' /"], &
                        deck, model, u0, v0)
      period = 2.0_dp * pi / model%omega
      cfg = deck%solver
      cfg%method = 'exponential';  cfg%tolerance = 1.0e-6_dp
      call make_integrator(model, cfg, integ, err)
      if (allocated(err)) then
         call check('exponential integrator', .false., err%message);  return
      end if
      call start_state(model, 0.0_dp, u0, v0, s0)
      found = .false.;  t = 0.0_dp;  rg = 0
      do while (t < 6.0_dp * period .and. .not. found)
         t = t + period / 128.0_dp
         call integ%advance(s0, t, err=err)
         if (allocated(err)) then
            call check('exponential run to a sliding contact', .false., err%message);  return
         end if
         if (t > period) then
            do j = 1, model%n_rings
               if (s0%mode(j) == ring_slip .and. s0%fn(j) > 0.0_dp) then
                  found = .true.;  rg = j
               end if
            end do
         end if
      end do
      call check('the tube slides on a ring within 6 periods', found)
      if (.not. found) return
      scale = maxval(abs(s0%u(model%r_dof(:, rg))))
      allocate(fda(model%n), ev(model%n))
      do k = 1, 3
         h = period / (100.0_dp * 2.0_dp**(k - 1))
         call make_stepper('exponential', st, err)
         if (.not. allocated(err)) call st%prepare(model, cfg, h, err)
         if (.not. allocated(err)) call make_stepper('exponential', sf, err)
         if (.not. allocated(err)) call sf%prepare(model, cfg, h / 256.0_dp, err)
         if (allocated(err)) then
            call check('exponential prepares', .false., err%message);  return
         end if
         s1 = s0
         call st%step(model, s0, s1, ok, ratio, 0)
         call st%local_error(model, s0, s1, fda, ev, coef, has)
         sa = s0;  sb = s0
         do j = 1, 256
            call sf%step(model, sa, sb, ok, ratio, 0)
            sa = sb
         end do
         e_true(k) = maxval(abs(s1%u - sa%u)) / scale
         e_est(k) = maxval(abs(fda)) * h**2 / scale
         call modal_sweeps_agree(st, model, s0, s1, fda, h, k)
         deallocate(st, sf)
      end do
      call note('tube sliding on ring ' // str(rg) // ' at t = ' // str(s0%t) // ' s, one ' &
         // 'step of T/100, T/200, T/400: true local error ' // str(e_true(1)) // ', ' &
         // str(e_true(2)) // ', ' // str(e_true(3)) // '; estimate ' // str(e_est(1)) // ', ' &
         // str(e_est(2)) // ', ' // str(e_est(3)) // ' (of the ring''s displacement); ' &
         // 'observed local orders ' // str(log(e_true(1) / e_true(2)) / log(2.0_dp)) // ', ' &
         // str(log(e_true(2) / e_true(3)) / log(2.0_dp)))
      do k = 1, 3
         call check_le('sliding step T/' // str(100 * 2**(k - 1)) // ': the estimate is at ' &
            // 'least half the true local error', 0.5_dp * e_true(k), e_est(k))
         call check_le('sliding step T/' // str(100 * 2**(k - 1)) // ': the estimate is at ' &
            // 'most 30 x the true local error', e_est(k), 30.0_dp * e_true(k))
      end do
      call check_le('sliding: the true local error falls at least as h^5.5 over the two ' &
         // 'halvings', -log(e_true(1) / e_true(3)) / log(4.0_dp), -5.5_dp)
   end subroutine estimate_bounds_error

   !> One step of estimate_bounds_error (s0 to s1 with the sweeps at the ring dofs, its estimate
   !> fda) taken again by the same stepper with the sweeps over every mode: the change of the
   !> state and the estimate to 1e-9 of the step's change (their round-off: 1e-16 .. 1e-11).
   subroutine modal_sweeps_agree(st, model, s0, s1, fda, h, k)
      class(stepper_t), intent(inout) :: st
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: s0, s1
      real(dp), intent(in) :: fda(:), h
      integer, intent(in) :: k
      real(dp), allocatable :: fdm(:), evm(:)
      type(state_t) :: sm
      real(dp) :: du, de, ratio, coef(3)
      logical :: ok, has
      select type (st)
      type is (exponential_t)
         st%sweep_at_act = .false.
      class default
         call check('the exponential stepper', .false.);  return
      end select
      allocate(fdm(model%n), evm(model%n))
      sm = s0
      call st%step(model, s0, sm, ok, ratio, 0)
      call st%local_error(model, s0, sm, fdm, evm, coef, has)
      du = max(maxval(abs(sm%u - s1%u)) / maxval(abs(s1%u - s0%u)), &
               maxval(abs(sm%v - s1%v)) / maxval(abs(s1%v - s0%v)))
      ! (the estimate's difference against the step's change of the state: the estimate
      ! itself falls to about 1e-11 of it at T/400, where its sweeps' difference is of the
      ! round-off of the modes' sums and the two paths may end their sweeps one apart: 1e-16
      ! in the release build, 1e-11 in the checked one)
      de = maxval(abs(fdm - fda)) * h**2 / maxval(abs(s1%u - s0%u))
      call check_le('sliding step T/' // str(100 * 2**(k - 1)) // ': the sweeps at the ring ' &
         // 'dofs give the modal sweeps'' change of the state', du, 1.0e-9_dp)
      call check_le('sliding step T/' // str(100 * 2**(k - 1)) // ': and their estimate, to ' &
         // '1e-9 of the step''s change', de, 1.0e-9_dp)
      call note('act against modal sweeps, step h = ' // str(h) // ': state change ' &
         // str(du) // ', estimate ' // str(de) // ' (of the step''s change)')
   end subroutine modal_sweeps_agree

   !> Energy imbalance of a run relative to its input work.
   !> Method 'auto' (gapbeam_integrator: choose_auto): on the reduced tube (rings, friction) the
   !> modal exponential integrator, at the deck's tolerance when it is 1e-4 or tighter, else at
   !> 1e-4 (its registry's loosest_tolerance), bit for bit the run that asks for it; on the
   !> full tube Newmark; on the reduced flat-stop beam (piecewise linear) the exact integrator;
   !> on the reduced beam with a Hertz stop Newmark (the exponential integrator's orbits repeat
   !> worse there: gapbeam_integrator, choose_auto).
   subroutine auto_on_reduced_models()
      type(model_t) :: model
      type(transient_result_t) :: ra, rx, rf
      type(error_t), allocatable :: err
      type(deck_t) :: deck
      real(dp), allocatable :: u0(:), v0(:)
      type(solver_settings_t) :: tight
      type(diagnostics_settings_t) :: dg
      character(len=:), allocatable :: what
      logical :: needed
      character(len=200) :: base
      base = '&solver transient_periods = 1, record_periods = 1 /'
      call run_deck(tube, [character(len=200) :: base, "&reduction kind = 'auto' /", &
                    "&solver method = 'auto', tolerance = 1.0e-3 /"], model, ra, err)
      if (allocated(err)) then
         call check("auto, reduced tube", .false., err%message);  return
      end if
      call run_deck(tube, [character(len=200) :: base, "&reduction kind = 'auto' /", &
                    "&solver method = 'exponential', tolerance = 1.0e-4 /"], model, rx, err)
      if (allocated(err)) then
         call check("exponential at 1e-4, reduced tube", .false., err%message);  return
      end if
      call note("reduced tube at 1e-3: " // ra%method_reason)
      call check("method 'auto' on the reduced tube runs the exponential integrator", &
                 ra%method == 'exponential', ra%method)
      call check("method 'auto' says why: the model is reduced, and at what tolerance", &
                 index(ra%method_reason, 'reduced') > 0 .and. &
                 index(ra%method_reason, 'loosest') > 0, ra%method_reason)
      call check("method 'auto' at 1e-3 runs it at 1e-4: the same steps and work rates", &
                 ra%steps_accepted == rx%steps_accepted .and. &
                 all(ra%normal_work_rate == rx%normal_work_rate), &
                 str(int(ra%steps_accepted)) // ' / ' // str(int(rx%steps_accepted)))
      ! the labels' repeat tolerance is that of the deck's tolerance (10 x 1e-3), not of the
      ! tightened one: a run more accurate than asked must not find fewer periods
      call load_deck(tube, [character(len=200) :: base, "&reduction kind = 'auto' /", &
                     "&solver method = 'auto', tolerance = 1.0e-3 /"], deck, model, u0, v0, err)
      if (allocated(err)) then
         call check("auto, reduced tube, deck", .false., err%message);  return
      end if
      call check_close("method 'auto' at 1e-3 on the reduced tube: period tolerance 10 x the " &
                       // "deck's tolerance", auto_period_tolerance(model, deck%solver, &
                       deck%diagnostics), 1.0e-2_dp, 1.0e-12_dp)
      ! the accuracy check of a certificate (the exponential integrator at 1e-5) judges its
      ! orbit at 10 x the deck's tolerance / 10, as a Newmark run's check was: 1e-3, not 1e-4
      call accuracy_settings(model, deck%solver, deck%diagnostics%certify_ratio, tight, what, &
                             needed)
      dg = check_diagnostics(model, deck%solver, deck%diagnostics, tight)
      call check("certificate of 'auto' at 1e-3: the check runs the exponential integrator at " &
                 // '1e-5', needed .and. tight%method == 'exponential' .and. &
                 abs(tight%tolerance - 1.0e-5_dp) < 1.0e-18_dp, what)
      call check_close("certificate of 'auto' at 1e-3: the check's period tolerance 1e-3", &
                       auto_period_tolerance(model, tight, dg), 1.0e-3_dp, 1.0e-12_dp)
      deck%solver%method = 'exponential';  deck%solver%tolerance = 1.0e-4_dp
      call check_close("method 'exponential' at 1e-4: period tolerance 1e-3", &
                       auto_period_tolerance(model, deck%solver, deck%diagnostics), 1.0e-3_dp, &
                       1.0e-12_dp)
      call run_deck(tube, [character(len=200) :: base, "&reduction kind = 'auto' /", &
                    "&solver method = 'auto', tolerance = 1.0e-6 /"], model, ra, err)
      if (allocated(err)) then
         call check("auto at 1e-6, reduced tube", .false., err%message);  return
      end if
      call check("method 'auto' at 1e-6 on the reduced tube: the exponential integrator at " &
                 // "the deck's tolerance", ra%method == 'exponential' .and. &
                 index(ra%method_reason, 'loosest') == 0, ra%method_reason)
      call run_deck(tube, [character(len=200) :: base, "&reduction kind = 'none' /", &
                    "&solver method = 'auto', tolerance = 1.0e-3 /"], model, rf, err)
      if (allocated(err)) then
         call check("auto, full tube", .false., err%message);  return
      end if
      call check("method 'auto' on the full tube runs Newmark", rf%method == 'newmark', &
                 rf%method)
      call run_deck(beam, [character(len=200) :: base, &
                    "&reduction kind = 'modal', n_modes = 4 / &solver method = 'auto' /"], &
                    model, rf, err)
      if (allocated(err)) then
         call check("auto, reduced flat-stop beam", .false., err%message);  return
      end if
      call check("method 'auto' on the reduced flat-stop beam runs the exact integrator", &
                 rf%method == 'exact', rf%method)
      call run_deck(beam, [character(len=200) :: base, &
                    "&reduction kind = 'modal', n_modes = 4 / &solver method = 'auto' /", &
                    "&stops law = 'hertz', exponent = 1.5, stiffness = 1.0e8 /"], model, rf, err)
      if (allocated(err)) then
         call check("auto, reduced Hertz-stop beam", .false., err%message);  return
      end if
      call check("method 'auto' on the reduced beam with a Hertz stop runs Newmark", &
                 rf%method == 'newmark', rf%method)
   end subroutine auto_on_reduced_models

   real(dp) function imbalance(r)
      type(transient_result_t), intent(in) :: r
      imbalance = (r%input_work - r%rayleigh_dissipation - r%contact_damping_dissipation &
                   - r%friction_dissipation - r%stored_energy_change) / abs(r%input_work)
   end function imbalance
end program test_modal_exponential
