!> The Newmark gap solver against exact solutions, convergence orders and invariants.
program test_newmark
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_full_model, initial_vectors
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_diagnostics, only: detect_period
   use gapbeam_lapack, only: dgesv
   use gapbeam_test_runs, only: run_deck
   implicit none
   character(len=*), parameter :: ref = 'test/decks/moon_shaw_10p5hz_half_element.nml'
   character(len=*), parameter :: sdof = 'test/decks/sdof_bilinear.nml'
   character(len=*), parameter :: nostop = "&stops rule_factor = 0.0, stiffness = 1.0, " &
      // "gap = 10.0 /"

   call linear_frequency_response()
   call energy_and_period()
   call stop_never_reached()
   call zero_gap_scaling()
   call sdof_against_exact()
   call condensed_and_fixed_point()
   call half_step_efficiency()
   call attractor_against_finer_step()
   call symmetric_two_sided_stop()
   call fine_grid_over_a_long_horizon()
   call finish('test_newmark')

contains

   !> Run a deck with overrides; stops the test on a deck or solver error.
   subroutine run(path, overrides, model, res, ok)
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: overrides(:)
      type(model_t), intent(out) :: model
      type(transient_result_t), intent(out) :: res
      logical, intent(out), optional :: ok
      type(error_t), allocatable :: err
      call run_deck(path, overrides, model, res, err)
      if (present(ok)) then
         ok = .not. allocated(err)
         if (allocated(err)) call note('run failed: ' // err%message)
      else if (allocated(err)) then
         call check('run ' // path // ' succeeds', .false., err%message)
         call finish('test_newmark')
      end if
   end subroutine run

   !> Steady state of the linear structure against (K - W^2 M + i W C) Y = F.
   subroutine linear_frequency_response()
      type(model_t) :: model
      type(transient_result_t) :: res
      real(dp) :: err256, err512, amp, order
      character(len=*), parameter :: lin = "&damping model = 'ratios', frequency1_hz = 4.3, " &
         // "ratio1 = 0.02, frequency2_hz = 26.0, ratio2 = 0.02 /"
      character(len=*), parameter :: horizon = "&solver step_control = 'fixed', " &
         // "transient_periods = 400, record_periods = 2 /"
      call run(ref, [character(len=200) :: nostop, lin, horizon, &
               '&solver steps_per_period = 256 /'], model, res)
      call compare_frf(model, res, err256, amp)
      call check_le('linear: tip and root strain against the exact frequency response ' &
         // '(T/256, relative to the amplitude)', err256, 1.0e-3_dp)
      call run(ref, [character(len=200) :: nostop, lin, horizon, &
               '&solver steps_per_period = 512 /'], model, res)
      call compare_frf(model, res, err512, amp)
      order = log(err256 / err512) / log(2.0_dp)
      call note('linear steady state: error ' // str(err256) // ' (T/256), ' // str(err512) &
         // ' (T/512): observed order ' // str(order))
      call check_close('linear: fixed-step error falls at second order', order, 2.0_dp, &
         atol=0.15_dp)
   end subroutine linear_frequency_response

   subroutine compare_frf(model, res, rel_err, amp)
      type(model_t), intent(in) :: model
      type(transient_result_t), intent(in) :: res
      real(dp), intent(out) :: rel_err, amp
      real(dp), allocatable :: a(:, :), b(:), yr(:), yi(:)
      integer, allocatable :: ipiv(:)
      integer :: n, info, i, it
      real(dp) :: w, t, tip, eps, amp_eps, e_tip, e_eps
      n = model%n;  w = model%omega
      allocate(a(2 * n, 2 * n), b(2 * n), ipiv(2 * n))
      ! P = s(t) q with s = (A/2) W^2 sin(W t): u = Yr sin + Yi cos, (K - W^2 M) Y + i W C Y = F
      a(1:n, 1:n) = model%sys%k - w**2 * model%sys%m
      a(n + 1:, n + 1:) = a(1:n, 1:n)
      a(1:n, n + 1:) = -w * model%c
      a(n + 1:, 1:n) = w * model%c
      b = 0.0_dp
      b(1:n) = model%half_amplitude * w**2 * model%q
      call dgesv(2 * n, 1, a, 2 * n, ipiv, b, 2 * n, info)
      ! with u = Re(Y e^{iWt})-style split: F sin(Wt) = Im(F e^{iWt}); Y = Yr + i Yi solves
      ! (K - W^2 M + i W C) Y = F, u = Im(Y e^{iWt}) = Yr sin(Wt) + Yi cos(Wt)
      yr = b(1:n);  yi = b(n + 1:)
      amp = sqrt(yr(model%sys%tip_dof)**2 + yi(model%sys%tip_dof)**2)
      amp_eps = sqrt(dot_product(model%sys%strain_row, yr)**2 &
                     + dot_product(model%sys%strain_row, yi)**2)
      e_tip = 0.0_dp;  e_eps = 0.0_dp
      do it = 1, size(res%time)
         t = res%time(it)
         tip = yr(model%sys%tip_dof) * sin(w * t) + yi(model%sys%tip_dof) * cos(w * t)
         eps = dot_product(model%sys%strain_row, yr) * sin(w * t) &
               + dot_product(model%sys%strain_row, yi) * cos(w * t)
         e_tip = max(e_tip, abs(res%tip_displacement(it) - tip))
         e_eps = max(e_eps, abs(res%strain(it) - eps))
      end do
      rel_err = max(e_tip / amp, e_eps / amp_eps)
   end subroutine compare_frf

   !> Undamped free vibration: energy to round-off, and the period elongation of the
   !> trapezoidal rule, omega_h dt = 2 atan(omega dt / 2).
   subroutine energy_and_period()
      type(model_t) :: model
      type(transient_result_t) :: res
      real(dp) :: e0, e1, w, theta, u_exact, k, m, fn
      real(dp), allocatable :: u0(:), a0(:)
      integer :: n_steps
      character(len=200) :: ov
      call run(ref, [character(len=200) :: nostop, "&damping model = 'none' /", &
         '&forcing amplitude_pp = 0.0, frequency_hz = 4.3 /', &
         "&initial kind = 'given', node = 5, dof = 'w', displacement = 1.0e-3 /", &
         "&solver step_control = 'fixed', steps_per_period = 64, transient_periods = 0, " &
         // "record_periods = 50 /"], model, res)
      allocate(u0(model%n), source=0.0_dp)
      u0(model%sys%tip_dof) = 1.0e-3_dp
      e0 = 0.5_dp * dot_product(u0, matmul(model%sys%k, u0))
      e1 = 0.5_dp * dot_product(res%v, matmul(model%sys%m, res%v)) &
           + 0.5_dp * dot_product(res%u, matmul(model%sys%k, res%u))
      call check_close('undamped free vibration: energy conserved by the trapezoidal rule ' &
         // '(3200 steps)', e1, e0, rtol=1.0e-12_dp)
      ! single dof: u_n = u0 cos(n omega_h dt)
      k = 3 * 200.0e9_dp * 0.01_dp * 5.0e-4_dp**3 / 12 / 0.2_dp**3
      m = 7850.0_dp * 0.01_dp * 5.0e-4_dp * 0.2_dp / 2
      fn = sqrt(k / m) / (2 * pi)
      write(ov, '(a, es24.16, a)') '&forcing frequency_hz = ', fn, ' /'
      call run(sdof, [character(len=200) :: ov, '&stops gap = 1.0 /', &
         "&solver steps_per_period = 16, record_periods = 10 /"], model, res)
      w = 2 * pi * fn
      theta = 2 * atan(w * (1.0_dp / fn / 16) / 2)
      n_steps = 160
      u_exact = -1.0e-3_dp * cos(n_steps * theta)
      call note('trapezoidal period elongation at omega dt = 2 pi/16: T_h/T = ' &
         // str(w / fn / 16 / theta) // ' (formula omega dt / (2 atan(omega dt / 2)))')
      call check_close('free vibration after 160 steps equals u0 cos(n omega_h dt)', &
         res%u(model%sys%tip_dof), u_exact, rtol=1.0e-9_dp)
      allocate(a0(1))
   end subroutine energy_and_period

   !> A stop that is never reached gives exactly the linear result.
   subroutine stop_never_reached()
      type(model_t) :: model
      type(transient_result_t) :: res_lin, res_gap
      character(len=*), parameter :: short = '&solver transient_periods = 5, record_periods = 5 /'
      call run(ref, [character(len=200) :: short, "&stops rule_factor = 0.0, stiffness = 1.0e3, " &
         // "gap = 10.0 /"], model, res_gap)
      call run(ref, [character(len=200) :: short, "&stops rule_factor = 0.0, stiffness = 1.0e-3, " &
         // "gap = 20.0 /"], model, res_lin)
      call check('stop never reached: history identical to the linear run', &
         all(res_gap%strain == res_lin%strain) .and. &
         all(res_gap%tip_displacement == res_lin%tip_displacement) .and. &
         res_gap%steps_accepted == res_lin%steps_accepted .and. res_gap%n_impacts(1) == 0)
   end subroutine stop_never_reached

   !> Zero gap, bilinear stop: doubling the amplitude doubles the whole response.
   subroutine zero_gap_scaling()
      type(model_t) :: model
      type(transient_result_t) :: r1, r2
      real(dp) :: d
      character(len=*), parameter :: short = '&solver transient_periods = 10, record_periods = 10 /'
      call run(ref, [character(len=200) :: short, '&forcing amplitude_pp = 3.7e-3 /'], model, r1)
      call run(ref, [character(len=200) :: short, '&forcing amplitude_pp = 7.4e-3 /'], model, r2)
      d = max(maxval(abs(r2%strain - 2 * r1%strain)) / maxval(abs(r1%strain)), &
              maxval(abs(r2%p_strain_rate - 2 * r1%p_strain_rate)) &
              / maxval(abs(r1%p_strain_rate)), &
              maxval(abs(r2%stop_force - 2 * r1%stop_force)) / maxval(abs(r1%stop_force)))
      call check_le('zero gap: 2x amplitude gives 2x response (half-step control, events)', &
         d, 1.0e-13_dp)
      call check('zero gap: the scaled runs took the same steps', &
         r1%steps_accepted == r2%steps_accepted .and. r1%steps_rejected == r2%steps_rejected)
   end subroutine zero_gap_scaling

   !> Single-dof bilinear oscillator against its exact piecewise solution.
   subroutine sdof_against_exact()
      type(model_t) :: model
      type(transient_result_t) :: res, res_ref
      real(dp) :: k, m, ks, g, u0, fn, w1, tc, e(3, 2), order_ev, order_no
      integer :: i, j
      character(len=200) :: ov, ovs(2), ovs3(3)
      character(len=*), parameter :: ev(2) = [character(len=40) :: &
         '&solver locate_events = .true. /', '&solver locate_events = .false. /']
      k = 3 * 200.0e9_dp * 0.01_dp * 5.0e-4_dp**3 / 12 / 0.2_dp**3
      m = 7850.0_dp * 0.01_dp * 5.0e-4_dp * 0.2_dp / 2
      ks = 30.0_dp;  g = 2.0e-4_dp;  u0 = -1.0e-3_dp
      fn = sqrt(k / m) / (2 * pi);  w1 = 2 * pi * fn
      write(ov, '(a, es24.16, a)') '&forcing frequency_hz = ', fn, ' /'
      do j = 1, 2
         do i = 1, 3
            ovs3(1) = ov;  ovs3(2) = ev(j)
            ovs3(3) = '&solver steps_per_period = ' // str(128 * 2**(i - 1)) // ' /'
            call run(sdof, ovs3, model, res)
            e(i, j) = sdof_error(res, k, m, ks, g, u0)
         end do
      end do
      order_ev = log(e(2, 1) / e(3, 1)) / log(2.0_dp)
      order_no = log(e(2, 2) / e(3, 2)) / log(2.0_dp)
      call note('SDOF bilinear (undamped contact), max error / amplitude against the exact ' &
         // 'solution at T/128, T/256, T/512 with events: ' // str(e(1, 1)) // ', ' &
         // str(e(2, 1)) // ', ' // str(e(3, 1)) // ' (order ' // str(order_ev) // ')')
      call note('SDOF bilinear (undamped contact), without event location: ' // str(e(1, 2)) &
         // ', ' // str(e(2, 2)) // ', ' // str(e(3, 2)) // ' (order ' // str(order_no) &
         // '): the contact force is continuous, so the kink costs no order')
      call check('SDOF bilinear: the error falls as dt falls', &
         e(3, 1) < e(2, 1) .and. e(2, 1) < e(1, 1) .and. e(3, 2) < e(2, 2))
      call check_close('SDOF bilinear: second order against the exact solution', &
         order_ev, 2.0_dp, atol=0.2_dp)
      ! a contact damper makes the force jump at impact: measure the order with and without
      ! event location against a fine reference (T/32768 with events)
      call run(sdof, [character(len=200) :: ov, '&stops damping = 0.07 /', &
         '&solver steps_per_period = 32768 /'], model, res_ref)
      do j = 1, 2
         do i = 1, 3
            ovs3(1) = ov;  ovs3(2) = ev(j)
            ovs3(3) = '&stops damping = 0.07 / &solver steps_per_period = ' &
               // str(128 * 2**(i - 1)) // ' /'
            call run(sdof, ovs3, model, res)
            e(i, j) = maxval(abs(res%tip_displacement - res_ref%tip_displacement)) / abs(u0)
         end do
      end do
      order_ev = log(e(2, 1) / e(3, 1)) / log(2.0_dp)
      order_no = log(e(2, 2) / e(3, 2)) / log(2.0_dp)
      call note('SDOF with a contact damper (force jumps at impact): error at T/128, T/256, ' &
         // 'T/512 with events ' // str(e(1, 1)) // ', ' // str(e(2, 1)) // ', ' // str(e(3, 1)) &
         // ' (order ' // str(order_ev) // '); without ' // str(e(1, 2)) // ', ' &
         // str(e(2, 2)) // ', ' // str(e(3, 2)) // ' (order ' // str(order_no) // ')')
      call check_close('contact damper: event location keeps second order across impacts', &
         order_ev, 2.0_dp, atol=0.25_dp)
      call check('contact damper: event location beats plain stepping at T/512', &
         e(3, 1) < 0.5_dp * e(3, 2))
      ! the 4-element beam: the stop force is continuous too, but impacts excite the high modes
      call run(ref, [character(len=200) :: "&solver step_control = 'fixed', " &
         // 'steps_per_period = 65536, transient_periods = 0, record_periods = 2 /'], model, res_ref)
      do j = 1, 2
         do i = 1, 3
            ovs(1) = ev(j)
            ovs(2) = "&solver step_control = 'fixed', transient_periods = 0, " &
               // 'record_periods = 2, steps_per_period = ' // str(256 * 2**(i - 1)) // ' /'
            call run(ref, ovs, model, res)
            e(i, j) = maxval(abs(res%u - res_ref%u)) / maxval(abs(res_ref%u))
         end do
      end do
      order_ev = log(e(2, 1) / e(3, 1)) / log(2.0_dp)
      order_no = log(e(2, 2) / e(3, 2)) / log(2.0_dp)
      call note('10.5 Hz beam, 2 periods from rest, final-state error at T/256, T/512, ' &
         // 'T/1024 with events: ' // str(e(1, 1)) // ', ' // str(e(2, 1)) // ', ' &
         // str(e(3, 1)) // ' (order ' // str(order_ev) // '); without: ' // str(e(1, 2)) &
         // ', ' // str(e(2, 2)) // ', ' // str(e(3, 2)) // ' (order ' // str(order_no) // ')')
      call check_close('beam with impacts: event location gives second order', order_ev, &
         2.0_dp, atol=0.3_dp)
      ! contact onset of the free vibration released against the stop
      call run(sdof, [character(len=200) :: ov, '&solver steps_per_period = 4096 /'], model, res)
      tc = acos(-g / abs(u0)) / w1
      call check_close('SDOF: first contact time against acos(-g/U)/omega', &
         res%first_contact_time(1), tc, rtol=1.0e-6_dp)
   end subroutine sdof_against_exact

   real(dp) function sdof_error(r, k, m, ks, g, u0) result(err_max)
      type(transient_result_t), intent(in) :: r
      real(dp), intent(in) :: k, m, ks, g, u0
      integer :: q
      err_max = 0.0_dp
      do q = 1, size(r%time)
         err_max = max(err_max, abs(r%tip_displacement(q) - exact_u(r%time(q), k, m, ks, g, u0)))
      end do
      err_max = err_max / abs(u0)
   end function sdof_error

   !> Exact piecewise-linear response from (u0, 0) at t = 0.
   real(dp) function exact_u(t, k, m, ks, g, u0) result(u)
      real(dp), intent(in) :: t, k, m, ks, g, u0
      real(dp) :: w1, ts, us, vs, w2, ue, tau, r, ph, dtau
      logical :: closed
      integer :: seg
      w1 = sqrt(k / m);  w2 = sqrt((k + ks) / m);  ue = ks * g / (k + ks)
      ts = 0.0_dp;  us = u0;  vs = 0.0_dp;  closed = .false.
      do seg = 1, 1000
         if (.not. closed) then
            r = sqrt(us**2 + (vs / w1)**2);  ph = atan2(vs / w1, us)
            if (r <= g) then
               dtau = huge(1.0_dp)
            else
               dtau = modulo(ph - acos(g / r), 2 * pi) / w1
               if (dtau < 1.0e-12_dp / w1) dtau = dtau + 2 * pi / w1
            end if
            if (t <= ts + dtau) then
               tau = t - ts
               u = us * cos(w1 * tau) + vs / w1 * sin(w1 * tau)
               return
            end if
            tau = dtau
            u = us * cos(w1 * tau) + vs / w1 * sin(w1 * tau)
            vs = -us * w1 * sin(w1 * tau) + vs * cos(w1 * tau)
         else
            r = sqrt((us - ue)**2 + (vs / w2)**2);  ph = atan2(vs / w2, us - ue)
            dtau = modulo(ph + acos((g - ue) / r), 2 * pi) / w2
            if (dtau < 1.0e-12_dp / w2) dtau = dtau + 2 * pi / w2
            if (t <= ts + dtau) then
               tau = t - ts
               u = ue + (us - ue) * cos(w2 * tau) + vs / w2 * sin(w2 * tau)
               return
            end if
            tau = dtau
            u = ue + (us - ue) * cos(w2 * tau) + vs / w2 * sin(w2 * tau)
            vs = -(us - ue) * w2 * sin(w2 * tau) + vs * cos(w2 * tau)
         end if
         ts = ts + tau;  us = g;  closed = .not. closed
      end do
      u = huge(1.0_dp)
   end function exact_u

   !> The condensed solution and the paper's fixed point agree; a very stiff stop needs step
   !> cuts with the fixed point and none with the condensed solution.
   subroutine condensed_and_fixed_point()
      type(model_t) :: model
      type(transient_result_t) :: rc, rf
      real(dp) :: d, k_beam
      character(len=200) :: stiff
      character(len=*), parameter :: fixed = "&solver step_control = 'fixed', " &
         // "transient_periods = 0, record_periods = 5 /"
      ! the same steps for both (no event location: a split decided on the last digits of
      ! the state could differ between the two and move the trajectory by the step's error)
      call run(ref, [character(len=200) :: fixed, '&solver locate_events = .false. /'], model, rc)
      call run(ref, [character(len=200) :: fixed, '&solver locate_events = .false. /', &
         "&solver stop_solution = 'fixed_point', fp_tolerance = 1.0e-13 /"], model, rf)
      d = maxval(abs(rc%strain - rf%strain)) / maxval(abs(rc%strain))
      call note('condensed vs fixed point (tolerance 1e-13): max strain difference ' // str(d) &
         // ' of the amplitude; fixed-point iterations ' // str(int(rf%fp_iterations)) &
         // ' for ' // str(int(rf%steps_accepted)) // ' steps')
      call check_le('condensed and fixed point agree where both converge', d, 1.0e-8_dp)
      k_beam = 3 * 1.9918014e-3_dp / 0.2_dp**3
      write(stiff, '(a, es12.4, a)') '&stops rule_factor = 0.0, stiffness = ', &
         1.0e6_dp * k_beam, ' /'
      call run(ref, [character(len=200) :: fixed, stiff], model, rc)
      call run(ref, [character(len=200) :: fixed, stiff, &
         "&solver stop_solution = 'fixed_point' /"], model, rf)
      call note('stop 1e6 x the beam tip stiffness, fixed T/256: condensed ' &
         // str(int(rc%steps_rejected)) // ' rejected steps; fixed point ' &
         // str(int(rf%steps_rejected)) // ' step cuts, ' // str(int(rf%steps_accepted)) &
         // ' steps, dt down to ' // str(rf%dt_smallest) // ' s')
      call check('very stiff stop: the condensed solution needs no step cut', &
         rc%steps_rejected == 0 .and. all(abs(rc%u) <= huge(1.0_dp)))
      call check('very stiff stop: the fixed point needs step cuts', rf%steps_rejected > 0)
   end subroutine condensed_and_fixed_point

   !> Half-step control reaches the error of a fixed-step run with fewer steps.
   subroutine half_step_efficiency()
      type(model_t) :: model
      type(transient_result_t) :: r_ref, r_h, r_f
      real(dp) :: e_h, e_f
      integer :: n, steps_f
      character(len=*), parameter :: short = '&solver transient_periods = 0, record_periods = 4 /'
      call run(ref, [character(len=200) :: short, "&solver step_control = 'fixed', " &
         // 'steps_per_period = 65536 /'], model, r_ref)
      call run(ref, [character(len=200) :: short, '&solver locate_events = .false. /'], model, r_h)
      e_h = state_error(r_h, r_ref)
      steps_f = -1
      n = 256
      do while (n <= 65536)
         call run(ref, [character(len=200) :: short, "&solver step_control = 'fixed', " &
            // 'locate_events = .false., steps_per_period = ' // str(n) // ' /'], model, r_f)
         e_f = state_error(r_f, r_ref)
         if (e_f <= e_h) then
            steps_f = int(r_f%steps_accepted);  exit
         end if
         n = 2 * n
      end do
      call note('10.5 Hz, 4 periods, no event location: half-step control error ' // str(e_h) &
         // ' with ' // str(int(r_h%steps_accepted)) // ' steps (+' &
         // str(int(r_h%steps_rejected)) // ' rejected); fixed steps need T/' // str(n) &
         // ' = ' // str(steps_f) // ' steps for ' // str(e_f))
      call check('half-step control reaches the fixed-step error with fewer steps', &
         steps_f > int(r_h%steps_accepted + r_h%steps_rejected))
   end subroutine half_step_efficiency

   real(dp) function state_error(r, rr)
      type(transient_result_t), intent(in) :: r, rr
      state_error = maxval(abs(r%u - rr%u)) / maxval(abs(rr%u))
   end function state_error

   !> The 10.5 Hz deck's default settings settle on the same attractor as a 16x finer fixed
   !> step (a fixed T/200 without event location settles on a spurious period 3).
   subroutine attractor_against_finer_step()
      type(model_t) :: model
      type(transient_result_t) :: r_def, r_fine, r_coarse
      integer :: p_def, p_fine, p_coarse
      character(len=*), parameter :: horizon = '&solver transient_periods = 300, ' &
         // 'record_periods = 200 /'
      call run(ref, [character(len=200) :: horizon], model, r_def)
      call run(ref, [character(len=200) :: horizon, "&solver step_control = 'fixed', " &
         // 'steps_per_period = 4096 /'], model, r_fine)
      call run(ref, [character(len=200) :: horizon, "&solver step_control = 'fixed', " &
         // 'steps_per_period = 200, locate_events = .false. /'], model, r_coarse)
      p_def = period_of(r_def);  p_fine = period_of(r_fine);  p_coarse = period_of(r_coarse)
      call note('10.5 Hz attractor period: default settings ' // str(p_def) &
         // ', fixed T/4096 ' // str(p_fine) // ', fixed T/200 without events ' // str(p_coarse))
      call check('10.5 Hz deck: default settings give the attractor of a 16x finer fixed step', &
         p_def == p_fine .and. p_def > 0)
   end subroutine attractor_against_finer_step

   !> A two-sided symmetric stop under symmetric forcing: u(t + T/2) = -u(t) on the orbit.
   subroutine symmetric_two_sided_stop()
      type(model_t) :: model
      type(transient_result_t) :: r
      integer :: half
      real(dp) :: asym
      call run(ref, [character(len=200) :: "&stops side = 'both', gap = 5.0e-4 /", &
         '&forcing frequency_hz = 3.0, amplitude_pp = 2.0e-3 /', &
         '&solver transient_periods = 300, record_periods = 20 /', &
         '&output samples_per_period = 64, history_periods = 4 /'], model, r)
      half = 32
      asym = maxval(abs(r%strain(half + 1:) + r%strain(:size(r%strain) - half))) &
             / maxval(abs(r%strain))
      call note('two-sided stop, 3 Hz, 2 mm: impacts per period ' &
         // str(real(r%n_impacts(1), dp) / 20) // ', max |eps(t + T/2) + eps(t)| / max|eps| = ' &
         // str(asym))
      call check('two-sided stop: impacts on both sides', r%n_impacts(1) >= 40)
      call check_le('two-sided symmetric stop: the orbit is symmetric, eps(t + T/2) = -eps(t)', &
         asym, 1.0e-6_dp)
   end subroutine symmetric_two_sided_stop

   integer function period_of(r)
      type(transient_result_t), intent(in) :: r
      real(dp) :: sx, sy
      sx = maxval(r%strain) - minval(r%strain)
      sy = maxval(r%strain_rate) - minval(r%strain_rate)
      period_of = detect_period(r%p_strain, r%p_strain_rate, 12, 1.0e-3_dp, 100, sx, sy)
   end function period_of

   !> A tick grid finer than the time resolves (T/100 with 40 halvings over 260 periods:
   !> 2.9e16 ticks > 2^53) used to stop with 'times must lie on the step grid' or take steps
   !> of zero length ('not finite at t = ..., dt = 0'): the halvings are now lowered to fit the
   !> horizon and the run gives the same attractor as with the default 20 halvings.
   subroutine fine_grid_over_a_long_horizon()
      type(model_t) :: model
      type(transient_result_t) :: r40, r20
      logical :: ok
      character(len=*), parameter :: base = "&solver method = 'newmark', step_control = " &
         // "'half_step', steps_per_period = 100, transient_periods = 250, record_periods = 10, "
      call run(ref, [character(len=200) :: base // 'max_halvings = 40 /'], model, r40, ok)
      call check('T/100 with 40 halvings over 260 periods runs (no grid error, no zero step)', &
         ok)
      if (.not. ok) return
      call run(ref, [character(len=200) :: base // 'max_halvings = 20 /'], model, r20)
      call check_le('... and ends on the orbit of the 20-halving run: largest Poincare ' &
         // 'difference / strain range', maxval(abs(r40%p_strain - r20%p_strain)) &
         / (r20%strain_max - r20%strain_min), 1.0e-6_dp)
   end subroutine fine_grid_over_a_long_horizon
end program test_newmark
