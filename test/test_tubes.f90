!> Tubes in baffle holes (issue 15): two planes of motion, circular clearances, friction, wear,
!> multi-span tubes, checked against closed forms and against the planar model.
!>
!> * planar equivalence: a planar deck run with &beam planes = 2 gives the planar results;
!> * frictionless whirl: a single mass under a rotating force in a circular clearance has a
!>   steady whirl whose radius, phase lag and normal work rate follow in closed form;
!> * friction whirl: the same with Coulomb friction: radius, friction work rate mu N R Omega,
!>   sliding distance R Omega T;
!> * friction dissipation: a preloaded contact under a slow tangential force dissipates
!>   mu N times the sliding distance, the stick-slip loop of the elastic-stick Coulomb law
!>   (quasi-static closed form); a stuck contact dissipates nothing;
!> * energy balance over a rattling run with impacts, a contact damper and friction;
!> * rotational symmetry: rotating the forcing direction rotates the orbit and leaves the work
!>   rates unchanged;
!> * accuracy: the error of a ring-contact run against a converged one stays within a small
!>   factor of &solver tolerance;
!> * end conditions and added mass against exact frequencies; two-plane modes;
!> * what the exact integrator and the other methods refuse.
program test_tubes
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t, modes_t
   use gapbeam_test_runs, only: run_deck
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model_builder, only: build_model
   use gapbeam_assembly, only: assemble
   use gapbeam_eigen, only: solve_modes
   use gapbeam_calibration, only: first_frequency
   use gapbeam_description, only: beam_ei, beam_rho_a
   use gapbeam_continuation, only: run_continuation
   use gapbeam_continuation_types, only: continuation_result_t
   use gapbeam_results, only: point_result_t
   use gapbeam_sweep, only: sweep_plan_t, make_plan, run_items, n_items, n_points
   use gapbeam_deck_parameter, only: model_with_values
   implicit none
   character(len=*), parameter :: whirl = 'test/decks/tube_whirl.nml'
   character(len=*), parameter :: slide = 'test/decks/tube_slide.nml'
   character(len=*), parameter :: cantilever = 'test/decks/tube_cantilever.nml'
   character(len=*), parameter :: moon_shaw = 'inputs/moon_shaw_10p5hz.nml'
   ! the numbers of tube_whirl.nml: k_b = 3 EI / L^3, m = rho A L / 2 + 0.05, c = beta m
   real(dp), parameter :: wkb = 3.0_dp * 200.0e9_dp * 0.01_dp * (5.0e-4_dp)**3 / 12.0_dp &
                                / 0.2_dp**3
   real(dp), parameter :: wm = 7850.0_dp * 0.01_dp * 5.0e-4_dp * 0.2_dp / 2.0_dp + 0.05_dp
   real(dp), parameter :: wc = 20.0_dp * wm
   real(dp), parameter :: womega = 2.0_dp * pi * 8.0_dp
   real(dp), parameter :: wks = 2000.0_dp, wg = 1.0e-3_dp, wf0 = 0.5_dp
   character(len=120), parameter :: rk45_reduced(2) = [character(len=120) :: &
      "&solver method = 'rk45' /", "&reduction kind = 'modal', cutoff_hz = 1.0e9 /"]

   call planar_equivalence()
   call frictionless_whirl()
   call friction_whirl('', [character(len=120) ::])
   call friction_dissipation('', [character(len=120) ::])
   call energy_balance('', [character(len=120) ::], 1.0e-5_dp)
   ! rk45 on the reduced models (every mode kept: the same model; the explicit method needs a
   ! mass at every coordinate, which the reduction gives by condensing the massless rotations)
   call friction_whirl('rk45, reduced: ', rk45_reduced)
   call friction_dissipation('rk45, reduced: ', rk45_reduced)
   ! (rk45's balance holds to its accuracy, about 4 x the tolerance, falling with it: 4.6e-5
   ! at 1e-5, 1.3e-7 at 1e-6; the trapezoidal rule's to round-off)
   call energy_balance('rk45, reduced: ', rk45_reduced, 10.0_dp * 1.0e-4_dp)
   call rotational_symmetry()
   call accuracy_against_converged()
   call end_conditions()
   call refusals()
   call sweep_over_clearance()
   call finish('test_tubes')

contains

   !> Run a deck; a failure is a failed check and returns ok false.
   subroutine run(what, path, overrides, model, res, ok)
      character(len=*), intent(in) :: what, path
      character(len=*), intent(in) :: overrides(:)
      type(model_t), intent(out) :: model
      type(transient_result_t), intent(out) :: res
      logical, intent(out) :: ok
      type(error_t), allocatable :: err
      call run_deck(path, overrides, model, res, err)
      ok = .not. allocated(err)
      if (allocated(err)) call check(what // ' runs', .false., err%message)
   end subroutine run

   pure real(dp) function span(x)
      real(dp), intent(in) :: x(:)
      span = maxval(x) - minval(x)
   end function span

   !> The Moon & Shaw deck (planar, one flat stop) with planes = 1 and 2, Newmark under error
   !> control, 3 periods from rest: the w plane is the same to round-off, the v plane at rest.
   subroutine planar_equivalence()
      type(model_t) :: m1, m2
      type(transient_result_t) :: r1, r2
      logical :: ok1, ok2
      character(len=*), parameter :: common = "&solver method = 'newmark', tolerance = 1.0e-5, " &
         // 'transient_periods = 0, record_periods = 3 / &output history_periods = 3 /'
      call run('planar deck', moon_shaw, [character(len=200) :: common], m1, r1, ok1)
      call run('planar deck with planes = 2', moon_shaw, [character(len=200) :: common, &
               '&beam planes = 2 /'], m2, r2, ok2)
      if (.not. (ok1 .and. ok2)) return
      call check('planes = 2 doubles the dofs', m2%n == 2 * m1%n)
      call check_le('planes = 2: root strain as planar (relative to its range)', &
         maxval(abs(r2%strain - r1%strain)) / span(r1%strain), 1.0e-12_dp)
      call check_le('planes = 2: tip as planar', &
         maxval(abs(r2%tip_displacement - r1%tip_displacement)) / span(r1%tip_displacement), &
         1.0e-12_dp)
      call check_le('planes = 2: stop force as planar', &
         maxval(abs(r2%stop_force - r1%stop_force)) / maxval(r1%stop_force), 1.0e-12_dp)
      call check('planes = 2: same impacts', all(r2%n_impacts == r1%n_impacts))
      call check_le('planes = 2: the v plane stays at rest', maxval(abs(r2%u(m1%n + 1:))), 0.0_dp)
      call check('planes = 2: the same steps', r2%steps_accepted == r1%steps_accepted)
      call check("planes = 2 with 'auto' runs Newmark (the exact integrator is planar)", &
                 r2%method == 'newmark')
   end subroutine planar_equivalence

   !> The whirl of tube_whirl.nml in closed form: with x = R exp(i (Omega t - phi)) in the
   !> (w, v) plane, F = F0 exp(i Omega t), N = k_s (R - g) and sliding direction +t,
   !>    [k_b - m Omega^2 + i c Omega + (N / R)(1 + i mu)] R exp(-i phi) = F0.
   subroutine whirl_closed_form(mu, r, phi, n_force)
      real(dp), intent(in) :: mu                  !! friction coefficient
      real(dp), intent(out) :: r, phi, n_force    !! radius [m], lag [rad], normal force [N]
      real(dp) :: lo, hi, mid
      integer :: it
      lo = wg * (1.0_dp + 1.0e-12_dp);  hi = 1.0_dp
      do it = 1, 200
         mid = 0.5_dp * (lo + hi)
         if (mid * abs(whirl_z(mid, mu)) > wf0) then
            hi = mid
         else
            lo = mid
         end if
      end do
      r = 0.5_dp * (lo + hi)
      phi = atan2(aimag(whirl_z(r, mu)), real(whirl_z(r, mu), dp))
      n_force = wks * (r - wg)
   end subroutine whirl_closed_form

   complex(dp) function whirl_z(r, mu)
      real(dp), intent(in) :: r, mu
      whirl_z = cmplx(wkb - wm * womega**2, wc * womega, dp) &
                + wks * (r - wg) / r * cmplx(1.0_dp, mu, dp)
   end function whirl_z

   !> '&initial' on the closed-form whirl at t = 0 (in contact, sliding forward).
   function on_whirl(r, phi) result(line)
      real(dp), intent(in) :: r, phi
      character(len=:), allocatable :: line
      line = "&initial kind = 'given', node = 2, 2, dof = 'w', 'v', displacement = " &
         // str(r * cos(phi)) // ', ' // str(-r * sin(phi)) // ', velocity = ' &
         // str(r * womega * sin(phi)) // ', ' // str(r * womega * cos(phi)) // ' /'
   end function on_whirl

   !> Largest relative deviation of the recorded orbit radius from R and of its phase lag.
   subroutine whirl_errors(res, r, phi, er, ep)
      type(transient_result_t), intent(in) :: res
      real(dp), intent(in) :: r, phi
      real(dp), intent(out) :: er, ep
      real(dp) :: rad(size(res%time)), lag(size(res%time))
      rad = hypot(res%orbit_w(:, 1), res%orbit_v(:, 1))
      lag = womega * res%time - atan2(res%orbit_v(:, 1), res%orbit_w(:, 1))
      lag = atan2(sin(lag), cos(lag))
      er = maxval(abs(rad / r - 1.0_dp))
      ep = maxval(abs(lag - phi))
   end subroutine whirl_errors

   !> Frictionless: radius, phase lag, normal force, normal work rate N R Omega, sliding R Omega.
   subroutine frictionless_whirl()
      type(model_t) :: m
      type(transient_result_t) :: res
      logical :: ok
      real(dp) :: r, phi, nf, er, ep, tol, t_rec
      character(len=300) :: ov(1)
      tol = 1.0e-5_dp
      call whirl_closed_form(0.0_dp, r, phi, nf)
      ov(1) = on_whirl(r, phi)
      call run('frictionless whirl', whirl, ov, m, res, ok)
      if (.not. ok) return
      call whirl_errors(res, r, phi, er, ep)
      call note('frictionless whirl: R = ' // str(r) // ' m, lag ' // str(phi) // ' rad; ' &
                // 'radius error ' // str(er) // ', lag error ' // str(ep) // ' rad at ' &
                // 'tolerance ' // str(tol))
      call check_le('frictionless whirl: radius within 3 tolerances', er, 3.0_dp * tol)
      call check_le('frictionless whirl: phase lag within 3 tolerances [rad]', ep, 3.0_dp * tol)
      call check_close('frictionless whirl: normal force', res%peak_force(1), nf, &
                       rtol=3.0_dp * tol * wks * r / nf)
      call check_close('frictionless whirl: normal work rate N R Omega', &
                       res%normal_work_rate(1), nf * r * womega, rtol=1.0e-3_dp)
      t_rec = 10.0_dp / 8.0_dp
      call check_close('frictionless whirl: sliding R Omega T', res%sliding_distance(1), &
                       r * womega * t_rec, rtol=1.0e-3_dp)
      call check('frictionless whirl: in contact all the time, no impacts', &
                 res%contact_fraction(1) == 1.0_dp .and. res%n_impacts(1) == 0)
      call check_le('frictionless whirl: no friction work', abs(res%friction_work(1)), 0.0_dp)
   end subroutine frictionless_whirl

   !> With friction mu = 0.1: the steady sliding whirl, friction work rate mu N R Omega.
   subroutine friction_whirl(tag, extra)
      character(len=*), intent(in) :: tag        !! prefix of the check names
      character(len=*), intent(in) :: extra(:)   !! more overrides (the method, a reduction)
      type(model_t) :: m
      type(transient_result_t) :: res
      logical :: ok
      real(dp) :: r, phi, nf, er, ep, tol, t_rec, mu, r0, phi0, nf0
      character(len=300) :: ov(2 + size(extra))
      tol = 1.0e-5_dp;  mu = 0.1_dp
      call whirl_closed_form(mu, r, phi, nf)
      call whirl_closed_form(0.0_dp, r0, phi0, nf0)
      ov(1) = on_whirl(r, phi);  ov(2) = '&stops friction = 0.1 /';  ov(3:) = extra
      call run(tag // 'friction whirl', whirl, ov, m, res, ok)
      if (.not. ok) return
      call whirl_errors(res, r, phi, er, ep)
      call note(tag // 'friction whirl (mu = 0.1): R = ' // str(r) // ' m, lag ' // str(phi) &
                // ' rad; radius error ' // str(er) // ', lag error ' // str(ep) // ' rad')
      call check(tag // 'friction whirl: friction changes the whirl (lag ' // str(phi) &
                 // ' against ' &
                 // str(phi0) // ')', abs(phi - phi0) > 100.0_dp * tol)
      call check_le(tag // 'friction whirl: radius within 3 tolerances', er, 3.0_dp * tol)
      call check_le(tag // 'friction whirl: phase lag within 3 tolerances [rad]', ep, 3.0_dp * tol)
      t_rec = 10.0_dp / 8.0_dp
      call check_close(tag // 'friction whirl: friction work rate mu N R Omega', &
                       res%friction_work_rate(1), mu * nf * r * womega, rtol=1.0e-3_dp)
      call check_close(tag // 'friction whirl: sliding distance R Omega T', &
                       res%sliding_distance(1), &
                       r * womega * t_rec, rtol=1.0e-3_dp)
      call check_close(tag // 'friction whirl: friction work = mu N x sliding distance', &
                       res%friction_work(1), mu * nf * res%sliding_distance(1), rtol=1.0e-6_dp)
      call check(tag // 'friction whirl: it slides all the time', res%stick_fraction(1) == 0.0_dp)
   end subroutine friction_whirl

   !> tube_slide.nml: N = k_b w0 pressing the tip on the wall, F0 sin(Omega t) along it.
   !> Quasi-static loop of the elastic-stick Coulomb law (spring k_t in series with the
   !> slider, k_b in parallel): dissipation per cycle 4 mu N ((F0 - mu N)/k_b - mu N / k_t).
   subroutine friction_dissipation(tag, extra)
      character(len=*), intent(in) :: tag        !! prefix of the check names
      character(len=*), intent(in) :: extra(:)   !! more overrides (the method, a reduction)
      character(len=120) :: ov(1 + size(extra))
      type(model_t) :: m
      type(transient_result_t) :: res
      logical :: ok
      real(dp) :: kb, n, mu, f0, kt, per_cycle, want, amp, mass, c, omega
      kb = 3.0_dp * 200.0e9_dp * 0.01_dp * (2.0e-3_dp)**3 / 12.0_dp / 0.2_dp**3
      mu = 0.3_dp;  f0 = 0.05_dp;  kt = 1.0e5_dp
      call run(tag // 'stick-slip', slide, extra, m, res, ok)
      if (.not. ok) return
      n = res%rms_force(1)
      per_cycle = res%friction_work(1) / 2.0_dp
      want = 4.0_dp * mu * n * ((f0 - mu * n) / kb - mu * n / kt)
      call note(tag // 'stick-slip: N = ' // str(n) // ' N, friction work per cycle ' &
                // str(per_cycle) // ' J, quasi-static elastic-stick Coulomb ' // str(want) &
                // ' J, rigid Coulomb ' // str(4.0_dp * mu * n * (f0 - mu * n) / kb) // ' J')
      call check_le(tag // 'stick-slip: the normal force is the preload (peak / rms - 1)', &
                    res%peak_force(1) / n - 1.0_dp, 1.0e-3_dp)
      call check_close(tag // 'stick-slip: friction work = mu N x sliding distance (N to 1e-3)', &
                       res%friction_work(1), mu * n * res%sliding_distance(1), rtol=1.0e-3_dp)
      ! the slow forcing (1 Hz against 14 Hz) leaves inertia and damping at about 1 %
      call check_close(tag // 'stick-slip: dissipation per cycle = the quasi-static loop', &
                       per_cycle, &
                       want, rtol=0.02_dp)
      call check(tag // 'stick-slip: it sticks part of the time and slips the rest', &
                 res%stick_fraction(1) > 0.1_dp .and. res%stick_fraction(1) < 0.9_dp)
      call check_le(tag // 'stick-slip: energy balance (relative to the input work)', &
                    abs(imbalance(res)) / res%input_work, 1.0e-6_dp)
      ! below mu N the contact stays stuck: no sliding, no dissipation, and the tip follows
      ! the spring-mass k_b + k_t
      ov(1) = '&point_forces amplitude = 0.01 /';  ov(2:) = extra
      call run(tag // 'stuck contact', slide, ov, m, res, ok)
      if (.not. ok) return
      call check(tag // 'stuck contact: no sliding', res%sliding_distance(1) == 0.0_dp)
      call check(tag // 'stuck contact: no friction work', res%friction_work(1) == 0.0_dp)
      call check(tag // 'stuck contact: stuck all the time', res%stick_fraction(1) == 1.0_dp)
      mass = 7850.0_dp * 0.01_dp * 2.0e-3_dp * 0.2_dp / 2.0_dp + 0.05_dp
      c = 20.0_dp * mass;  omega = 2.0_dp * pi
      amp = 0.01_dp / abs(cmplx(kb + kt - mass * omega**2, c * omega, dp))
      call check_close(tag // 'stuck contact: tangential amplitude of the stuck spring-mass', &
                       0.5_dp * span(res%orbit_v(:, 1)), amp, rtol=1.0e-3_dp)
      call note(tag // 'stuck contact: input ' // str(res%input_work) // ' J, Rayleigh ' &
         // str(res%rayleigh_dissipation) // ' J, stored ' // str(res%stored_energy_change) &
         // ' J, imbalance ' // str(imbalance(res)) // ' J')
      ! the input work is tiny here (an elastic stick of 1e-7 m): the balance holds to the
      ! deck's tolerance of 1e-3
      call check_le(tag // 'stuck contact: energy balance (relative to the input work, tolerance ' &
                    // '1e-3)', abs(imbalance(res)) / res%input_work, 1.0e-3_dp)
   end subroutine friction_dissipation

   pure real(dp) function imbalance(res)
      type(transient_result_t), intent(in) :: res
      imbalance = res%input_work - res%rayleigh_dissipation - res%contact_damping_dissipation &
                  - res%friction_dissipation - res%stored_energy_change
   end function imbalance

   !> A rattling tube (impacts, a contact damper, friction): input = dissipation + stored.
   subroutine energy_balance(tag, extra, bound)
      character(len=*), intent(in) :: tag        !! prefix of the check names
      character(len=*), intent(in) :: extra(:)   !! more overrides (the method, a reduction)
      real(dp), intent(in) :: bound              !! of the imbalance / input work
      character(len=120) :: ov(1 + size(extra))
      type(model_t) :: m
      type(transient_result_t) :: res
      logical :: ok
      ov(1) = '&solver tolerance = 1.0e-4, record_periods = 4 /';  ov(2:) = extra
      call run(tag // 'rattling tube', cantilever, ov, m, res, ok)
      if (.not. ok) return
      call note(tag // 'energy over 4 periods: input ' // str(res%input_work) // ' J, Rayleigh ' &
         // str(res%rayleigh_dissipation) // ' J, contact damper ' &
         // str(res%contact_damping_dissipation) // ' J, friction ' &
         // str(res%friction_dissipation) // ' J, stored ' // str(res%stored_energy_change) &
         // ' J, imbalance ' // str(imbalance(res)) // ' J')
      call check(tag // 'rattling tube: it impacts, slides and sticks', res%n_impacts(1) > 0 .and. &
                 res%stick_fraction(1) > 0.0_dp .and. res%friction_dissipation > 0.0_dp)
      call check(tag // 'rattling tube: every term is there', &
                 res%rayleigh_dissipation > 0.0_dp .and. &
                 res%contact_damping_dissipation > 0.0_dp)
      call check_le(tag // 'rattling tube: energy balance within ' // str(bound) // ' of the ' &
                    // 'input work', abs(imbalance(res)) / res%input_work, bound)
   end subroutine energy_balance

   !> The whirl deck with friction (impacts, stick-slip) under an elliptical force
   !> (a sin(Omega t), b cos(Omega t)) and under the same force turned by 30 degrees (point
   !> forces of the turned components' amplitudes and phases): the orbit turns by 30 degrees,
   !> the work rates stay.
   subroutine rotational_symmetry()
      type(model_t) :: m
      type(transient_result_t) :: r0, r30
      logical :: ok0, ok30
      real(dp) :: c, s, e_orbit, tol
      character(len=200) :: ov(3)
      tol = 1.0e-6_dp
      ov(1) = '&solver tolerance = 1.0e-6, transient_periods = 0, record_periods = 2 / ' &
              // '&output history_periods = 2 /'
      ov(2) = '&stops friction = 0.3 /'
      ov(3) = elliptical(0.0_dp)
      call run('elliptical force', whirl, ov, m, r0, ok0)
      ov(3) = elliptical(pi / 6.0_dp)
      call run('elliptical force turned by 30 degrees', whirl, ov, m, r30, ok30)
      if (.not. (ok0 .and. ok30)) return
      c = cos(pi / 6.0_dp);  s = sin(pi / 6.0_dp)
      e_orbit = max(maxval(abs(r30%orbit_w(:, 1) - (c * r0%orbit_w(:, 1) - s * r0%orbit_v(:, 1)))), &
                    maxval(abs(r30%orbit_v(:, 1) - (s * r0%orbit_w(:, 1) + c * r0%orbit_v(:, 1))))) &
                / max(span(r0%orbit_w(:, 1)), span(r0%orbit_v(:, 1)))
      call note('rotational symmetry: orbit difference ' // str(e_orbit) // ' of its range, ' &
         // 'normal work rate ' // str(r0%normal_work_rate(1)) // ' / ' &
         // str(r30%normal_work_rate(1)) // ' W, friction work rate ' &
         // str(r0%friction_work_rate(1)) // ' / ' // str(r30%friction_work_rate(1)) &
         // ' W, impacts ' // str(r0%n_impacts(1)) // ' / ' // str(r30%n_impacts(1)))
      call check('rotational symmetry: it impacts and slides', r0%n_impacts(1) > 0 .and. &
                 r0%friction_work(1) > 0.0_dp)
      call check_le('rotational symmetry: the orbit turns with the forcing (10 x tolerance)', &
                    e_orbit, 10.0_dp * tol)
      call check_close('rotational symmetry: normal work rate unchanged', &
                       r30%normal_work_rate(1), r0%normal_work_rate(1), rtol=10.0_dp * tol)
      call check_close('rotational symmetry: friction work rate unchanged', &
                       r30%friction_work_rate(1), r0%friction_work_rate(1), rtol=10.0_dp * tol)
      call check_close('rotational symmetry: impact work rate unchanged', r30%work_rate(1), &
                       r0%work_rate(1), rtol=10.0_dp * tol)
      call check('rotational symmetry: same impacts', r30%n_impacts(1) == r0%n_impacts(1))
   end subroutine rotational_symmetry

   !> &point_forces of (0.5 sin(Omega t), 0.25 cos(Omega t)) turned by angle a: each component
   !> as an amplitude and a phase.
   function elliptical(a) result(line)
      real(dp), intent(in) :: a
      character(len=:), allocatable :: line
      complex(dp) :: fw, fv
      ! F = Re(fhat exp(i Omega t)) per component written as A sin(Omega t + phase):
      ! a sin = (a, 0) as (sin, cos) parts; b cos = (0, b)
      fw = cmplx(0.5_dp * cos(a), -0.25_dp * sin(a), dp)       ! (sin part, cos part)
      fv = cmplx(0.5_dp * sin(a), 0.25_dp * cos(a), dp)
      line = "&point_forces node = 2, 2, dof = 'w', 'v', amplitude = " // str(abs(fw)) // ', ' &
         // str(abs(fv)) // ', phase_deg = ' // str(atan2(aimag(fw), real(fw, dp)) * 180.0_dp &
         / pi) // ', ' // str(atan2(aimag(fv), real(fv, dp)) * 180.0_dp / pi) // ' /'
   end function elliptical

   !> The whirl deck with mu = 0.3 from rest (impacts, stick-slip; 11 impacts in 3 periods) at
   !> tolerances 1e-3 and 1e-4 against a run at 1e-6: the largest error of the orbit at the
   !> support (relative to its range) stays within the band of issue 10, [0.03, 3] x the
   !> tolerance, and the friction work converges with the tolerance.
   subroutine accuracy_against_converged()
      type(model_t) :: m
      type(transient_result_t) :: ref, res
      logical :: ok
      real(dp) :: tols(2), e(2), ew(2)
      character(len=200) :: ov(1)
      integer :: k
      character(len=*), parameter :: hz = 'transient_periods = 0, record_periods = 3 / ' &
         // '&output samples_per_period = 64, history_periods = 3 / &stops friction = 0.3 /'
      tols = [1.0e-3_dp, 1.0e-4_dp]
      ov(1) = '&solver tolerance = 1.0e-6, ' // hz
      call run('converged whirl with impacts', whirl, ov, m, ref, ok)
      if (.not. ok) return
      do k = 1, 2
         ov(1) = '&solver tolerance = ' // str(tols(k)) // ', ' // hz
         call run('whirl with impacts', whirl, ov, m, res, ok)
         if (.not. ok) return
         e(k) = max(maxval(abs(res%orbit_w(:, 1) - ref%orbit_w(:, 1))) / span(ref%orbit_w(:, 1)), &
                    maxval(abs(res%orbit_v(:, 1) - ref%orbit_v(:, 1))) / span(ref%orbit_v(:, 1)))
         ew(k) = abs(res%friction_work(1) / ref%friction_work(1) - 1.0_dp)
      end do
      call note('ring contacts (impacts, stick-slip): orbit error / range at tolerance 1e-3, ' &
                // '1e-4: ' // str(e(1)) // ', ' // str(e(2)) // '; friction work error ' &
                // str(ew(1)) // ', ' // str(ew(2)) // ' (' // str(ref%n_impacts(1)) &
                // ' impacts)')
      do k = 1, 2
         call check_le('ring contacts: orbit error within 3 x tolerance ' // str(tols(k)), &
                       e(k), 3.0_dp * tols(k))
         call check('ring contacts: orbit error above 0.03 x tolerance ' // str(tols(k)) &
                    // ' (the control is not wasteful)', e(k) >= 0.03_dp * tols(k))
         call check_le('ring contacts: friction work within the tolerance ' // str(tols(k)), &
                       ew(k), tols(k))
      end do
      call check('ring contacts: the errors fall with the tolerance', e(2) < e(1) .and. &
                 ew(2) < ew(1))
   end subroutine accuracy_against_converged

   !> Clamped-pinned and pinned-pinned beams against the exact first frequencies, the added
   !> mass, and the two planes' modes in pairs.
   subroutine end_conditions()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      type(modes_t) :: modes
      type(model_t) :: model
      real(dp) :: f1, f_exact, ei, rho_a
      real(dp), allocatable :: uu(:), vv(:)
      character(len=*), parameter :: beam = "&beam n_elem = 30, added_mass = 0.0, " &
         // "mass_matrix = 'consistent' /"
      call read_deck(cantilever, [character(len=90) :: beam, "&tip condition = 'pinned' /"], &
                     deck, err)
      if (allocated(err)) then
         call check('clamped-pinned deck reads', .false., err%message);  return
      end if
      ei = beam_ei(deck%structure%beam);  rho_a = beam_rho_a(deck%structure%beam)
      call first_frequency(deck%structure, f1, err)
      f_exact = 3.92660231_dp**2 / (2.0_dp * pi) * sqrt(ei / (rho_a * 0.5_dp**4))
      call check_close('clamped-pinned: f1 (beta L = 3.92660231)', f1, f_exact, rtol=1.0e-4_dp)
      call read_deck(cantilever, [character(len=90) :: beam, "&tip condition = 'pinned' /", &
                     "&root condition = 'pinned' /"], deck, err)
      if (allocated(err)) return
      call first_frequency(deck%structure, f1, err)
      call check_close('pinned-pinned: f1 = (pi/L)^2 sqrt(EI / rho A) / (2 pi)', f1, &
                       pi / (2.0_dp * 0.5_dp**2) * sqrt(ei / rho_a), rtol=1.0e-4_dp)
      call read_deck(cantilever, [character(len=90) :: &
                     "&beam n_elem = 30, added_mass = 0.5, mass_matrix = 'consistent' /", &
                     "&tip condition = 'pinned' /", &
                     "&root condition = 'pinned' /"], deck, err)
      if (allocated(err)) return
      call first_frequency(deck%structure, f1, err)
      call check_close('added mass: f1 scales by sqrt(rho A / (rho A + m_a))', f1, &
                       pi / (2.0_dp * 0.5_dp**2) * sqrt(ei / (rho_a + 0.5_dp)), rtol=1.0e-4_dp)
      call read_deck(cantilever, [character(len=80) :: '&beam n_elem = 6 /'], deck, err)
      if (allocated(err)) return
      call solve_modes_of(deck, modes, err)
      if (allocated(err)) then
         call check('two-plane modes', .false., err%message);  return
      end if
      call check('two planes: the modes come in equal pairs', all(abs(modes%frequency_hz(2:: &
         2) - modes%frequency_hz(1::2)) <= 1.0e-9_dp * modes%frequency_hz(2::2)))
      call build_model(deck, model, uu, vv, err)
      call check('two-plane model builds', .not. allocated(err))
   end subroutine end_conditions

   subroutine solve_modes_of(deck, modes, err)
      type(deck_t), intent(in) :: deck
      type(modes_t), intent(out) :: modes
      type(error_t), allocatable, intent(out) :: err
      type(model_t) :: model
      call assemble(deck%structure, model%sys)
      call solve_modes(model%sys, modes, err)
   end subroutine solve_modes_of

   !> The exact integrator (and continuation through it) and the other methods refuse what they
   !> cannot integrate, naming the method to use; the modal reduction takes these models.
   subroutine refusals()
      type(model_t) :: m
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      call run_deck(cantilever, [character(len=80) :: "&solver method = 'exact' /"], m, res, err)
      call check("method 'exact' refuses a circular clearance and names 'newmark'", &
                 has(err, "method 'exact' cannot integrate") .and. has(err, "'newmark'") .and. &
                 has(err, 'circular clearance'))
      call run_deck(moon_shaw, [character(len=80) :: "&solver method = 'exact' /", &
                    '&beam planes = 2 /'], m, res, err)
      call check("method 'exact' refuses a two-plane model", has(err, 'two planes'))
      call run_deck(cantilever, [character(len=80) :: "&solver method = 'hht' /"], m, res, err)
      call check("method 'hht' refuses friction and names 'newmark'", &
                 has(err, "method 'hht' cannot") .and. has(err, "'newmark'"))
      call run_deck(cantilever, [character(len=80) :: "&solver step_control = 'fixed' /"], m, &
                    res, err)
      call check("step_control 'fixed' refuses ring contacts and names 'error'", &
                 has(err, "step_control = 'error'"))
      call run_deck(cantilever, [character(len=80) :: "&reduction kind = 'modal' /"], m, res, err)
      call check("a modal reduction takes a two-plane model with a ring (test_reduction)", &
                 .not. allocated(err) .and. m%n < 16)
      call run_deck(whirl, [character(len=80) :: '&diagnostics lyapunov_periods = 10 /'], m, &
                    res, err)
      call check('a Lyapunov exponent with ring supports is accepted (computed: test_exponents)', &
                 .not. allocated(err))
      ! continuation: the deck is valid, the model is refused when the branches start
      block
         type(deck_t) :: deck
         type(continuation_result_t) :: cres
         call read_deck(whirl, [character(len=120) :: "&job analysis = 'continuation' /", &
            "&continuation parameter = '&forcing frequency_hz', parameter_min = 6.0, " &
            // "parameter_max = 10.0 /"], deck, err)
         call check('a continuation deck of the whirl model is valid', .not. allocated(err))
         if (.not. allocated(err)) call run_continuation(deck, cres, err)
         call check('continuation refuses a circular clearance, names it and the &sweep', &
                    has(err, 'continuation cannot follow this model') .and. &
                    has(err, 'circular clearance') .and. has(err, '&sweep'))
      end block
   end subroutine refusals

   !> A sweep whose y axis is a deck variable (&sweep y_variable = '&stops gap(1)'): each point
   !> equals a transient run of the deck with that clearance (the model rebuilt), and the
   !> clearance changes the work rate. An axis of several variables ('&stops gap(1), &stops
   !> gap(2)') sets all of them; a list mixing units or with a forcing variable is refused.
   subroutine sweep_over_clearance()
      type(deck_t) :: deck
      type(model_t) :: base, m
      type(transient_result_t) :: res
      type(point_result_t), allocatable :: pts(:)
      type(sweep_plan_t) :: plan
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      integer :: k
      character(len=100), parameter :: short = &
         '&solver transient_periods = 4, record_periods = 4, tolerance = 1.0e-4 /'
      ! no settling extension and no certificate: the sweep point runs what the deck runs
      character(len=100), parameter :: plain = &
         '&diagnostics settle_windows = 0, certify = .false. /'
      call read_deck(whirl, [character(len=160) :: "&job analysis = 'sweep' /", short, plain, &
         "&sweep frequency_hz = 8.0, y_variable = '&stops gap(1)', y_values = 0.8e-3, 1.0e-3, " &
         // "progress = .false. /"], deck, err)
      call check('a sweep over the clearance (&sweep y_variable) reads', .not. allocated(err))
      if (allocated(err)) return
      call check('its y axis holds the clearances', size(deck%sweep%y) == 2 .and. &
                 deck%sweep%y_variable == '&stops gap(1)')
      call check('ring supports: no Lyapunov exponent by default', &
                 deck%diagnostics%lyapunov_periods == 0)
      call make_plan(deck, plan, err)
      if (.not. allocated(err)) call build_model(deck, base, u0, v0, err)
      call check('its plan and its model build', .not. allocated(err))
      if (allocated(err)) return
      allocate(pts(n_points(plan) * plan%ns))
      call run_items(deck, base, plan, [(k, k = 1, n_items(plan))], u0, v0, pts)
      call check('both sweep points ran', all(pts%status == 0), pts(1)%message)
      call run_deck(whirl, [character(len=100) :: short, '&stops gap = 0.8e-3 /'], m, res, err)
      call check('the deck with gap 0.8 mm runs', .not. allocated(err))
      if (allocated(err)) return
      call check_close('sweep point at gap 0.8 mm: normal work rate as the deck with that gap', &
                       pts(1)%normal_work_rate(1), res%normal_work_rate(1), 1.0e-12_dp)
      call check_close('sweep point at gap 0.8 mm: peak force as the deck with that gap', &
                       pts(1)%peak_force(1), res%peak_force(1), 1.0e-12_dp)
      call check('the clearance changes the peak force (0.8 mm against 1.0 mm)', &
                 abs(pts(1)%peak_force(1) - pts(2)%peak_force(1)) > 1.0e-3_dp &
                 * pts(2)%peak_force(1))
      ! both baffles of the multispan tube on one axis
      call read_deck('inputs/tube_multispan.nml', [character(len=160) :: &
         "&job analysis = 'sweep' /", "&sweep frequency_hz = 8.0, y_variable = '&stops " &
         // "gap(1), &stops gap(2)', y_values = 0.1e-3, 0.3e-3 /"], deck, err)
      call check('an axis of two variables reads, labelled by both', .not. allocated(err) &
                 .and. deck%sweep%y_variable == '&stops gap(1), &stops gap(2)')
      if (allocated(err)) return
      call make_plan(deck, plan, err)
      call check('its plan sets three variables (x, and y twice)', .not. allocated(err) .and. &
                 size(plan%set) == 3 .and. all(plan%set_axis == [1, 2, 2]))
      if (allocated(err)) return
      call model_with_values(deck, plan%set, [8.0_dp, 0.3e-3_dp, 0.3e-3_dp], m, err)
      call check('the y value reaches both baffles', .not. allocated(err) .and. &
                 all(abs(m%c_gap - 0.3e-3_dp) < 1.0e-15_dp))
      call read_deck('inputs/tube_multispan.nml', [character(len=160) :: &
         "&job analysis = 'sweep' /", "&sweep frequency_hz = 8.0, y_variable = '&stops " &
         // "gap(1), &stops friction(2)', y_values = 0.1e-3 /"], deck, err)
      call check('an axis of variables of two units is refused', allocated(err) .and. &
                 has(err, 'one unit'))
      call read_deck('inputs/tube_multispan.nml', [character(len=160) :: &
         "&job analysis = 'sweep' /", "&sweep y_variable = '&stops gap(1), &stops gap(1)', " &
         // "y_values = 0.1e-3 /"], deck, err)
      call check('a variable named twice on an axis is refused', allocated(err) .and. &
                 has(err, 'named twice'))
      call read_deck('inputs/tube_multispan.nml', [character(len=160) :: &
         "&job analysis = 'sweep' /", "&sweep x_variable = '&stops gap(1)', x_values = 1e-4, " &
         // "y_variable = '&stops gap(2), &stops gap(1)', y_values = 0.1e-3 /"], deck, err)
      call check('a variable on both axes is refused', allocated(err) .and. &
                 has(err, 'both name'))
      call read_deck('inputs/tube_multispan.nml', [character(len=160) :: &
         "&job analysis = 'sweep' /", '&sweep frequency_hz = 8.0 /', &
         '&diagnostics lyapunov_periods = 10 /'], deck, err)
      call check('an exponent asked for with ring supports is taken', .not. allocated(err) &
                 .and. deck%diagnostics%lyapunov_periods == 10)
   end subroutine sweep_over_clearance

   logical function has(err, text)
      type(error_t), allocatable, intent(in) :: err
      character(len=*), intent(in) :: text
      has = .false.
      if (allocated(err)) has = index(err%message, text) > 0
   end function has
end program test_tubes
