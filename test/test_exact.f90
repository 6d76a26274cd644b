!> The exact event-driven integrator against closed forms and invariants; the Newmark
!> integrator's convergence towards it.
program test_exact
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t, energy_norm
   use gapbeam_model_builder, only: build_full_model, initial_vectors
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_results, only: modes_t
   use gapbeam_eigen, only: solve_modes
   use gapbeam_exact, only: exact_integrator_t
   use gapbeam_test_runs, only: run_deck
   use gapbeam_expm_reference, only: expm_run
   implicit none
   !> extended precision for reference sums (double where the compiler has none)
   integer, parameter :: qp = max(selected_real_kind(30), selected_real_kind(15))
   character(len=*), parameter :: ref = 'test/decks/moon_shaw_10p5hz_half_element.nml'
   character(len=*), parameter :: sdof = 'test/decks/sdof_bilinear.nml'
   character(len=*), parameter :: free_beam = 'test/decks/exact_free_beam.nml'
   character(len=*), parameter :: nostop = "&stops rule_factor = 0.0, stiffness = 1.0, " &
      // "gap = 10.0 /"
   character(len=*), parameter :: ratios = "&damping model = 'ratios', frequency1_hz = 4.3, " &
      // "ratio1 = 0.02, frequency2_hz = 26.0, ratio2 = 0.02 /"
   ! single dof of sdof_bilinear.nml: k = 3 EI / L^3, m = rho A L / 2, stop 30 N/m at 0.2 mm
   real(dp), parameter :: k1 = 3 * 200.0e9_dp * 0.01_dp * 5.0e-4_dp**3 / 12 / 0.2_dp**3
   real(dp), parameter :: m1 = 7850.0_dp * 0.01_dp * 5.0e-4_dp * 0.2_dp / 2
   real(dp), parameter :: ks = 30.0_dp, g1 = 2.0e-4_dp, u1 = -1.0e-3_dp

   call linear_against_modal_superposition()
   call sdof_against_piecewise_solution()
   call sdof_impact_statistics()
   call energy_over_many_impacts()
   call zero_gap_homogeneity()
   call against_expm_reference()
   call critically_damped()
   call near_critical_beam()
   call two_stops_with_damper()
   call coalescing_contact_pair()
   call symmetric_two_sided_stop()
   call newmark_converges_to_exact()
   call filtered_strain()
   call unsupported_models()
   call fifteen_elements_against_rk4()
   call fine_meshes_against_rk4()
   call search_limit()
   call finish('test_exact')

contains

   !> Read a deck with overrides, build it and run the exact integrator (or Newmark).
   subroutine run(path, overrides, model, res, newmark, message, u0, v0, limit)
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: overrides(:)
      type(model_t), intent(out) :: model
      type(transient_result_t), intent(out) :: res
      logical, intent(in), optional :: newmark
      character(len=:), allocatable, intent(out), optional :: message   !! expected failure
      real(dp), allocatable, intent(out), optional :: u0(:), v0(:)       !! initial state
      integer, intent(in), optional :: limit                             !! search steps
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      real(dp), allocatable :: x0(:), y0(:)
      character(len=300) :: ov(size(overrides))
      type(exact_integrator_t) :: exact
      logical :: nm
      nm = .false.
      if (present(newmark)) nm = newmark
      ov = overrides
      call read_deck(path, ov, deck, err)
      if (.not. allocated(err)) call build_full_model(deck%structure, deck%stops, deck%damping, &
                                                   deck%forcing, model, err)
      if (.not. allocated(err)) then
         call initial_vectors(model, deck%initial, x0, y0)
         if (present(u0)) u0 = x0
         if (present(v0)) v0 = y0
         if (nm) then
            call integrate(model, deck%solver, deck%output, x0, y0, res, err)
         else
            if (present(limit)) exact%search_limit = limit
            call integrate(model, deck%solver, deck%output, x0, y0, res, err, exact)
         end if
      end if
      if (present(message)) then
         message = ''
         if (allocated(err)) message = err%message
      else if (allocated(err)) then
         call check('run ' // path // ' succeeds', .false., err%message)
         call finish('test_exact')
      end if
   end subroutine run

   !> '&forcing frequency_hz = <f1> /' with the SDOF natural frequency (sets the time base).
   function sdof_time_base() result(ov)
      character(len=300) :: ov
      write(ov, '(a, es24.16, a)') '&forcing frequency_hz = ', sqrt(k1 / m1) / (2 * pi), ' /'
   end function sdof_time_base

   ! ---------------------------------------------------------------- closed forms

   !> No impact: the open structure is classically damped (Rayleigh), so modal superposition
   !> with the modes of solve_modes is an independent exact solution, transient from the
   !> initial state included. History samples compared to 1e-12 of their amplitude.
   subroutine linear_against_modal_superposition()
      type(model_t) :: model
      type(transient_result_t) :: res
      real(dp) :: e_tip, e_eps
      real(dp), allocatable :: u0(:), v0(:)
      call run(ref, [character(len=300) :: nostop, ratios, &
         '&solver transient_periods = 0, record_periods = 6 /', &
         '&output history_periods = 6 /'], model, res, u0=u0, v0=v0)
      call modal_error(model, res, u0, v0, e_tip, e_eps)
      call note('no impact, 4 elements, Rayleigh (ratios), from rest, 6 periods: max error / ' &
         // 'amplitude of tip ' // str(e_tip) // ', root strain ' // str(e_eps))
      call check_le('no impact (beam, Rayleigh, from rest): tip against modal superposition', &
         e_tip, 1.0e-12_dp)
      call check_le('no impact (beam, Rayleigh, from rest): strain against modal superposition',&
         e_eps, 1.0e-12_dp)
      ! the same from a given state, with the stop far (forced, mass-proportional damping)
      call run(ref, [character(len=300) :: nostop, &
         "&damping model = 'rayleigh', mass_coefficient = 3.0, stiffness_coefficient = 0.0 /", &
         "&initial kind = 'given', node = 5, dof = 'w', displacement = 1.0e-3, " &
         // "velocity = -0.05 /", '&solver transient_periods = 1, record_periods = 4 /', &
         '&output history_periods = 4 /'], model, res, u0=u0, v0=v0)
      call modal_error(model, res, u0, v0, e_tip, e_eps)
      call check_le('no impact (beam, mass-proportional, given state, forced): tip and strain ' &
         // 'against modal superposition', max(e_tip, e_eps), 1.0e-12_dp)
      ! massless rotations (condensed): the single dof of the SDOF deck, forced
      call run(sdof, [character(len=300) :: '&stops gap = 1.0 /', &
         "&damping model = 'rayleigh', mass_coefficient = 2.0, stiffness_coefficient = 1.0e-3 /", &
         '&forcing frequency_hz = 3.0, amplitude_pp = 2.0e-3 /', &
         '&solver transient_periods = 1, record_periods = 3 /'], model, res, u0=u0, v0=v0)
      call modal_error(model, res, u0, v0, e_tip, e_eps)
      call check_le('no impact (massless rotation condensed, Rayleigh, forced): against modal ' &
         // 'superposition', max(e_tip, e_eps), 1.0e-12_dp)
   end subroutine linear_against_modal_superposition

   !> Largest error of the history (tip, strain) against modal superposition, relative to
   !> the largest value of each.
   subroutine modal_error(model, res, u0, v0, e_tip, e_eps)
      type(model_t), intent(in) :: model
      type(transient_result_t), intent(in) :: res
      real(dp), intent(in) :: u0(:), v0(:)
      real(dp), intent(out) :: e_tip, e_eps
      type(modes_t) :: modes
      type(error_t), allocatable :: err
      real(dp), allocatable :: q0(:), p0(:), u(:)
      real(dp) :: w, z, wd, fk, h_re, h_im, a, b, t, qk, om, amp, r1, r2, c1, c2, qp0, vp0, det
      complex(dp) :: hc
      integer :: k, it
      call solve_modes(model%sys, modes, err)
      if (allocated(err)) then
         call check('solve_modes succeeds', .false., err%message);  return
      end if
      ! omega^2 of dsygv carries the rounding of the largest eigenvalue (2.9e-13 of the first
      ! one here, 15 rad of phase in 6 periods): the Rayleigh quotient of its shape, summed in
      ! extended precision, is exact to second order in the shape's error
      do k = 1, modes%n_modes
         modes%omega2(k) = rayleigh_quotient(model, modes%shapes(:, k))
      end do
      ! modal coordinates of the initial state (massless entries do not enter: M rows zero)
      q0 = matmul(transpose(modes%shapes), matmul(model%sys%m, u0))
      p0 = matmul(transpose(modes%shapes), matmul(model%sys%m, v0))
      om = model%omega;  amp = model%half_amplitude * om**2
      e_tip = 0.0_dp;  e_eps = 0.0_dp
      allocate(u(model%n))
      do it = 1, size(res%time)
         t = res%time(it)
         u = 0.0_dp
         do k = 1, modes%n_modes
            w = sqrt(modes%omega2(k))
            z = 0.5_dp * (model%beta / w + model%gamma * w)
            fk = amp * dot_product(modes%shapes(:, k), model%q)
            hc = 1.0_dp / cmplx(w**2 - om**2, 2 * z * w * om, dp)
            h_re = real(hc);  h_im = aimag(hc)
            ! particular: F Im(H e^{i om t})
            qp0 = fk * h_im;  vp0 = fk * om * h_re
            qk = fk * (h_re * sin(om * t) + h_im * cos(om * t))
            a = q0(k) - qp0;  b = p0(k) - vp0
            if (z < 1.0_dp) then
               wd = w * sqrt(1.0_dp - z**2)
               qk = qk + exp(-z * w * t) * (a * cos(wd * t) + (b + z * w * a) / wd * sin(wd * t))
            else
               det = w * sqrt(z**2 - 1.0_dp)
               r1 = -z * w + det;  r2 = -z * w - det
               c1 = (b - r2 * a) / (r1 - r2);  c2 = a - c1
               qk = qk + c1 * exp(r1 * t) + c2 * exp(r2 * t)
            end if
            u = u + qk * modes%shapes(:, k)
         end do
         e_tip = max(e_tip, abs(res%tip_displacement(it) - u(model%sys%tip_dof)))
         e_eps = max(e_eps, abs(res%strain(it) - dot_product(model%sys%strain_row, u)))
      end do
      e_tip = e_tip / maxval(abs(res%tip_displacement))
      e_eps = e_eps / maxval(abs(res%strain))
   end subroutine modal_error

   !> phi'K phi / phi'M phi summed in extended precision.
   real(dp) function rayleigh_quotient(model, phi) result(w2)
      type(model_t), intent(in) :: model
      real(dp), intent(in) :: phi(:)
      real(qp) :: num, den
      integer :: i, j
      num = 0.0_qp;  den = 0.0_qp
      do j = 1, model%n
         do i = 1, model%n
            num = num + real(phi(i), qp) * model%sys%k(i, j) * phi(j)
            den = den + real(phi(i), qp) * model%sys%m(i, j) * phi(j)
         end do
      end do
      w2 = real(num / den, dp)
   end function rayleigh_quotient

   !> Exact piecewise-linear response of the SDOF from (u0, 0) at t = 0: displacement,
   !> velocity, and the switch times up to t.
   subroutine sdof_state(t, u, v, n_sw, t_sw)
      real(dp), intent(in) :: t
      real(dp), intent(out) :: u, v
      integer, intent(out), optional :: n_sw
      real(dp), intent(out), optional :: t_sw(:)
      real(dp) :: w1, w2, ue, ts, us, vs, r, ph, dtau, tau
      logical :: closed
      integer :: seg
      w1 = sqrt(k1 / m1);  w2 = sqrt((k1 + ks) / m1);  ue = ks * g1 / (k1 + ks)
      ts = 0.0_dp;  us = u1;  vs = 0.0_dp;  closed = .false.
      if (present(n_sw)) n_sw = 0
      do seg = 1, 100000
         if (.not. closed) then
            r = sqrt(us**2 + (vs / w1)**2);  ph = atan2(vs / w1, us)
            dtau = modulo(ph - acos(g1 / r), 2 * pi) / w1
            if (dtau < 1.0e-12_dp / w1) dtau = dtau + 2 * pi / w1
            tau = min(dtau, t - ts)
            u = us * cos(w1 * tau) + vs / w1 * sin(w1 * tau)
            v = -us * w1 * sin(w1 * tau) + vs * cos(w1 * tau)
         else
            r = sqrt((us - ue)**2 + (vs / w2)**2);  ph = atan2(vs / w2, us - ue)
            dtau = modulo(ph + acos((g1 - ue) / r), 2 * pi) / w2
            if (dtau < 1.0e-12_dp / w2) dtau = dtau + 2 * pi / w2
            tau = min(dtau, t - ts)
            u = ue + (us - ue) * cos(w2 * tau) + vs / w2 * sin(w2 * tau)
            v = -(us - ue) * w2 * sin(w2 * tau) + vs * cos(w2 * tau)
         end if
         if (t <= ts + dtau) return
         ts = ts + dtau;  us = g1;  vs = v;  closed = .not. closed
         if (present(n_sw)) then
            n_sw = n_sw + 1
            if (n_sw <= size(t_sw)) t_sw(n_sw) = ts
         end if
      end do
   end subroutine sdof_state

   !> The SDOF bilinear oscillator released against its stop: first contact, trajectory.
   subroutine sdof_against_piecewise_solution()
      type(model_t) :: model
      type(transient_result_t) :: res
      real(dp) :: e, u, v, tc
      integer :: q
      call run(sdof, [character(len=300) :: sdof_time_base(), &
         '&solver record_periods = 6 /', '&output history_periods = 6 /'], model, res)
      tc = acos(-g1 / abs(u1)) / sqrt(k1 / m1)
      call check_close('SDOF: first contact time equals acos(-g/U)/omega', &
         res%first_contact_time(1), tc, rtol=1.0e-12_dp)
      e = 0.0_dp
      do q = 1, size(res%time)
         call sdof_state(res%time(q), u, v)
         e = max(e, abs(res%tip_displacement(q) - u))
      end do
      call check_le('SDOF bilinear: trajectory against the exact piecewise solution ' &
         // '(6 periods, ' // str(int(res%n_impacts(1))) // ' impacts, / amplitude)', &
         e / abs(u1), 1.0e-12_dp)
      call sdof_state(res%t_end, u, v)
      call check_le('SDOF bilinear: final velocity against the exact solution', &
         abs(res%v(model%sys%tip_dof) - v) / (abs(u1) * sqrt(k1 / m1)), 1.0e-12_dp)
   end subroutine sdof_against_piecewise_solution

   !> Impact statistics of the SDOF against the piecewise solution: contact time from the
   !> switch times, peak force ks d_max, and the integrals of f, f^2, f |d'| (32-point
   !> Gauss-Legendre on each contact phase of the exact solution).
   subroutine sdof_impact_statistics()
      type(model_t) :: model
      type(transient_result_t) :: res
      real(dp) :: t_sw(200), t_rec, t_end, len, a, b, xg(32), wg(32), s_f, s_f2, s_w, s_c, u, v, &
         f, t, w1, w2, ue, vc, dmax, ce, tm, pa, pb
      integer :: n_sw, k, q, n_imp, p
      logical :: closed
      call run(sdof, [character(len=300) :: sdof_time_base(), &
         '&solver transient_periods = 1, record_periods = 9 /', &
         '&output history_periods = 1 /'], model, res)
      w1 = sqrt(k1 / m1);  w2 = sqrt((k1 + ks) / m1);  ue = ks * g1 / (k1 + ks)
      t_rec = 2 * pi / w1;  t_end = 10 * t_rec;  len = t_end - t_rec
      call sdof_state(t_end, u, v, n_sw, t_sw)
      call gauss(xg, wg)
      s_f = 0;  s_f2 = 0;  s_w = 0;  s_c = 0;  n_imp = 0
      closed = .false.
      do k = 1, n_sw
         closed = .not. closed
         if (.not. closed) cycle
         a = max(t_sw(k), t_rec)
         b = t_end
         if (k < n_sw) b = min(t_sw(k + 1), t_end)
         if (t_sw(k) >= t_rec) n_imp = n_imp + 1
         if (b <= a) cycle
         s_c = s_c + (b - a)
         ! the contact arc is symmetric: |v| has its kink at the middle of the full phase
         tm = 0.5_dp * (t_sw(k) + t_sw(min(k + 1, n_sw)))
         if (k == n_sw) tm = b
         do p = 1, 2
            pa = a;  pb = b
            if (p == 1) pb = min(b, max(a, tm))
            if (p == 2) pa = max(a, min(b, tm))
            do q = 1, size(xg)
               t = 0.5_dp * (pa + pb) + 0.5_dp * (pb - pa) * xg(q)
               call sdof_state(t, u, v)
               f = ks * (u - g1)
               s_f = s_f + 0.5_dp * (pb - pa) * wg(q) * f
               s_f2 = s_f2 + 0.5_dp * (pb - pa) * wg(q) * f**2
               s_w = s_w + 0.5_dp * (pb - pa) * wg(q) * f * abs(v)
            end do
         end do
      end do
      vc = w1 * sqrt(u1**2 - g1**2)
      dmax = sqrt((g1 - ue)**2 + (vc / w2)**2) - (g1 - ue)
      call check('SDOF statistics: impacts in the record', res%n_impacts(1) == n_imp, &
         str(int(res%n_impacts(1))) // ' vs ' // str(n_imp))
      call check_close('SDOF statistics: peak force = ks d_max', res%peak_force(1), ks * dmax, &
         rtol=1.0e-12_dp)
      call check_close('SDOF statistics: contact fraction from the switch times', &
         res%contact_fraction(1), s_c / len, rtol=1.0e-12_dp)
      call check_close('SDOF statistics: impulse per period', res%impulse_per_period(1), &
         s_f / 9, rtol=1.0e-12_dp)
      call check_close('SDOF statistics: rms force', res%rms_force(1), sqrt(s_f2 / len), &
         rtol=1.0e-12_dp)
      call check_close('SDOF statistics: work rate (1/T) int f |d''|', res%work_rate(1), &
         s_w / len, rtol=1.0e-12_dp)
      ! strain = c u_tip (the rotation follows u_tip): extremes at the bottom of the open swing
      ! (-U), the deepest penetration (g + d_max) and the fastest passage (|v| = w U at u = 0)
      ce = res%strain(2) / res%tip_displacement(2)
      call check_close('SDOF statistics: strain extremes at -U and g + d_max', &
         max(res%strain_max - max(ce * u1, ce * (g1 + dmax)), &
             res%strain_min - min(ce * u1, ce * (g1 + dmax))) / abs(ce * u1), 0.0_dp, &
         atol=1.0e-12_dp)
      call check_close('SDOF statistics: strain rate extremes +-c w U', &
         max(abs(res%strain_rate_max - abs(ce) * w1 * abs(u1)), &
             abs(res%strain_rate_min + abs(ce) * w1 * abs(u1))) / (abs(ce) * w1 * abs(u1)), &
         0.0_dp, atol=1.0e-12_dp)
   end subroutine sdof_impact_statistics

   !> Nodes and weights of n-point Gauss-Legendre on [-1, 1] (for the reference integrals).
   subroutine gauss(x, w)
      real(dp), intent(out) :: x(:), w(:)
      integer :: n, i, k, it
      real(dp) :: z, p0, p1, p2, d1
      n = size(x)
      do i = 1, n
         z = cos(pi * (i - 0.25_dp) / (n + 0.5_dp))
         do it = 1, 100
            p0 = 1;  p1 = z
            do k = 2, n
               p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k
               p0 = p1;  p1 = p2
            end do
            d1 = n * (z * p1 - p0) / (z**2 - 1)
            z = z - p1 / d1
            if (abs(p1 / d1) < 1.0e-16_dp) exit
         end do
         x(i) = z;  w(i) = 2 / ((1 - z**2) * d1**2)
      end do
   end subroutine gauss

   ! ---------------------------------------------------------------- invariants

   !> Undamped, unforced, undamped stop: the energy 1/2 v'Mv + 1/2 u'Ku + 1/2 k d^2 is
   !> conserved across many impacts (beam with rotary inertia; and with massless rotations,
   !> condensed).
   subroutine energy_over_many_impacts()
      type(model_t) :: model
      type(transient_result_t) :: r1, r2
      real(dp) :: e0, e1, e2
      character(len=300) :: ri
      integer :: variant
      do variant = 1, 2
         ri = '&output history_periods = 1 /'
         if (variant == 2) ri = "&beam rotary_inertia = 'none' /"
         call run(free_beam, [character(len=300) :: ri, &
            '&solver transient_periods = 0, record_periods = 1 /'], model, r1)
         e1 = energy(model, r1)
         call run(free_beam, [character(len=300) :: ri, &
            '&solver transient_periods = 0, record_periods = 60 /'], model, r2)
         e2 = energy(model, r2)
         if (variant == 1) then
            e0 = 0.5_dp * model%sys%k(model%sys%tip_dof, model%sys%tip_dof) * 2.0e-3_dp**2
            call check_close('energy: initial energy 1/2 k_tip u0^2 after one period', e1, e0, &
               rtol=1.0e-12_dp)
            call check_close('energy conserved over ' // str(int(r2%n_impacts(1))) &
               // ' impacts (undamped, unforced, undamped stop)', e2, e0, rtol=1.0e-12_dp)
         else
            call check_close('energy conserved over ' // str(int(r2%n_impacts(1))) &
               // ' impacts, massless rotations condensed', e2, e1, rtol=1.0e-12_dp)
         end if
         call check('energy test: many impacts', r2%n_impacts(1) >= 40)
      end do
   end subroutine energy_over_many_impacts

   !> Energy, with the quadratic forms summed in extended precision (u'Ku of a smooth shape
   !> cancels: in double its rounding alone would be ~1e-13 of the energy).
   real(dp) function energy(model, r) result(e)
      type(model_t), intent(in) :: model
      type(transient_result_t), intent(in) :: r
      real(qp) :: s
      real(dp) :: d
      integer :: c, i, j
      s = 0.0_qp
      do j = 1, model%n
         do i = 1, model%n
            s = s + 0.5_qp * (real(r%v(i), qp) * model%sys%m(i, j) * r%v(j) &
                              + real(r%u(i), qp) * model%sys%k(i, j) * r%u(j))
         end do
      end do
      do c = 1, model%n_contacts
         d = model%c_sign(c) * r%u(model%c_dof(c)) - model%c_gap(c)
         if (d > 0.0_dp) s = s + 0.5_qp * model%c_k(c) * real(d, qp)**2
      end do
      e = real(s, dp)
   end function energy

   !> Zero gap, from rest: the model is positively homogeneous, so doubling the amplitude
   !> doubles the whole response (switch times unchanged).
   subroutine zero_gap_homogeneity()
      type(model_t) :: model
      type(transient_result_t) :: r1, r2
      real(dp) :: d
      character(len=*), parameter :: short = '&solver transient_periods = 10, record_periods = 10 /'
      call run(ref, [character(len=300) :: short, '&forcing amplitude_pp = 3.7e-3 /'], model, r1)
      call run(ref, [character(len=300) :: short, '&forcing amplitude_pp = 7.4e-3 /'], model, r2)
      d = max(maxval(abs(r2%strain - 2 * r1%strain)) / maxval(abs(r1%strain)), &
              maxval(abs(r2%p_strain_rate - 2 * r1%p_strain_rate)) &
              / maxval(abs(r1%p_strain_rate)), &
              maxval(abs(r2%stop_force - 2 * r1%stop_force)) / maxval(abs(r1%stop_force)), &
              abs(r2%peak_force(1) - 2 * r1%peak_force(1)) / r1%peak_force(1), &
              abs(r2%work_rate(1) - 4 * r1%work_rate(1)) / r1%work_rate(1))
      call check_le('zero gap: 2x amplitude gives 2x response (history, Poincare, peak force, ' &
         // '4x work rate)', d, 1.0e-12_dp)
      call check('zero gap: same switches and contact fraction', r1%events == r2%events .and. &
         abs(r1%contact_fraction(1) - r2%contact_fraction(1)) <= 1.0e-13_dp)
   end subroutine zero_gap_homogeneity

   real(dp) function rel(x, y)
      real(dp), intent(in) :: x(:), y(:)
      rel = 0.0_dp
      if (size(x) == 0) return
      rel = maxval(abs(x - y)) / max(maxval(abs(y)), tiny(1.0_dp))
   end function rel

   !> The closed form against an independent reference (gapbeam_expm_reference: matrix
   !> exponentials of the augmented physical system in extended precision, switches bisected):
   !> a forced SDOF with a contact damper (massless rotation condensed) and a two-element beam
   !> with impacts; final states in the energy norm.
   subroutine against_expm_reference()
      type(model_t) :: model
      type(transient_result_t) :: r
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: d
      character(len=*), parameter :: damped(4) = [character(len=120) :: &
         '&stops damping = 0.07 /', "&damping model = 'rayleigh', mass_coefficient = 1.0, " &
         // 'stiffness_coefficient = 1.0e-4 /', '&forcing amplitude_pp = 1.0e-3 /', &
         '&solver transient_periods = 1, record_periods = 5 /']
      call run(sdof, [character(len=300) :: sdof_time_base(), damped], model, r, u0=u0, v0=v0)
      d = expm_difference(model, r, u0, v0, 6)
      call note('SDOF with a contact damper, forced: exact vs extended-precision matrix ' &
         // 'exponential, energy-norm difference of the final state ' // str(d) // '; ' &
         // str(int(r%events)) // ' switches')
      call check_le('contact damper: closed form and matrix-exponential reference agree', d, &
                    1.0e-11_dp)
      call run(ref, [character(len=300) :: '&beam n_elem = 2 / &stops node = 3 /', &
         '&solver transient_periods = 0, record_periods = 2 /'], model, r, u0=u0, v0=v0)
      d = expm_difference(model, r, u0, v0, 2)
      call note('2-element beam, 10.5 Hz, 2 periods from rest: exact vs matrix exponential ' &
         // str(d) // ', ' // str(int(r%events)) // ' switches')
      call check_le('beam with impacts: closed form and matrix-exponential reference agree', &
                    d, 1.0e-11_dp)
   end subroutine against_expm_reference

   !> Relative energy-norm difference between the final state of an exact run over `periods`
   !> from (u0, v0) and the matrix-exponential reference (T/256 steps, switches bisected).
   real(dp) function expm_difference(model, r, u0, v0, periods) result(d)
      type(model_t), intent(in) :: model
      type(transient_result_t), intent(in) :: r
      real(dp), intent(in) :: u0(:), v0(:)
      integer, intent(in) :: periods
      real(dp) :: u(model%n), v(model%n)
      integer :: switches
      call expm_run(model, u0, v0, periods, 256, u, v, switches)
      d = energy_norm(model, r%u - u, r%v - v) / energy_norm(model, u, v)
      if (switches /= r%events) d = huge(1.0_dp)
   end function expm_difference

   !> A critically damped mode (the open configuration's double pole): the 2-block closed
   !> form matches (u0 + (v0 + w u0) t) e^{-w t}; with impacts (contact configurations are
   !> not critical) it matches the matrix-exponential reference.
   subroutine critically_damped()
      type(model_t) :: model
      type(transient_result_t) :: ra
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: w, e_blk, t, u, d
      integer :: q
      character(len=300) :: crit
      w = sqrt(k1 / m1)
      write(crit, '(a, es24.16, a)') "&damping model = 'rayleigh', mass_coefficient = ", 2 * w, &
         ', stiffness_coefficient = 0.0 /'
      call run(sdof, [character(len=300) :: sdof_time_base(), crit, '&stops gap = 1.0 /', &
         "&initial kind = 'given', node = 2, dof = 'w', displacement = -1.0e-3, " &
         // "velocity = 0.2 /", '&solver record_periods = 2 /'], model, ra)
      e_blk = 0.0_dp
      do q = 1, size(ra%time)
         t = ra%time(q)
         u = (-1.0e-3_dp + (0.2_dp - w * 1.0e-3_dp) * t) * exp(-w * t)
         e_blk = max(e_blk, abs(ra%tip_displacement(q) - u))
      end do
      e_blk = e_blk / maxval(abs(ra%tip_displacement))
      call note('critically damped SDOF: error of the 2-block closed form ' // str(e_blk))
      call check_le('critically damped: the closed form matches (u0 + (v0 + w u0) t) e^(-w t)', &
         e_blk, 1.0e-12_dp)
      call run(sdof, [character(len=300) :: sdof_time_base(), crit, &
         "&initial kind = 'given', node = 2, dof = 'w', displacement = -1.0e-3, " &
         // "velocity = 0.3 /", '&solver record_periods = 2 /'], model, ra, u0=u0, v0=v0)
      call check('critically damped with impacts: there are impacts', ra%events >= 2)
      d = expm_difference(model, ra, u0, v0, 2)
      call note('critically damped SDOF with impacts: exact vs matrix exponential ' // str(d))
      call check_le('critically damped with impacts: closed form and matrix-exponential ' &
         // 'reference agree', d, 1.0e-11_dp)
   end subroutine critically_damped

   !> A beam mode near, at and past critical damping (C = gamma K with gamma omega_2 = 2
   !> (1 + eps), eps = -1e-6, 0, 1e-6: the open configuration's pair of mode 2 coalesces; all
   !> higher modes are overdamped), with impacts, against the matrix-exponential reference.
   subroutine near_critical_beam()
      type(model_t) :: model
      type(transient_result_t) :: r
      type(modes_t) :: modes
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: w2, d, eps(3)
      character(len=300) :: damp
      integer :: k
      character(len=*), parameter :: short = '&solver transient_periods = 0, record_periods = 2 /'
      call run(ref, [character(len=300) :: short], model, r)
      call solve_modes(model%sys, modes, err)
      if (allocated(err)) then
         call check('solve_modes succeeds', .false., err%message);  return
      end if
      w2 = sqrt(rayleigh_quotient(model, modes%shapes(:, 2)))
      eps = [-1.0e-6_dp, 0.0_dp, 1.0e-6_dp]
      do k = 1, 3
         write(damp, '(a, es24.16, a)') "&damping model = 'rayleigh', mass_coefficient = 0.0, " &
            // 'stiffness_coefficient = ', 2.0_dp * (1.0_dp + eps(k)) / w2, ' /'
         call run(ref, [character(len=300) :: short, damp, '&forcing amplitude_pp = 2.0e-2 /'], &
            model, r, u0=u0, v0=v0)
         d = expm_difference(model, r, u0, v0, 2)
         call note('4-element beam, mode 2 at damping ratio 1 + ' // str(eps(k)) // ', ' &
            // str(int(r%events)) // ' switches: exact vs matrix exponential ' // str(d))
         call check_le('mode 2 at damping ratio 1 + ' // str(eps(k)) // ' with impacts: ' &
            // 'closed form and matrix-exponential reference agree', d, 1.0e-11_dp)
         call check('mode 2 at damping ratio 1 + ' // str(eps(k)) // ': there are impacts', &
            r%events >= 2)
      end do
   end subroutine near_critical_beam

   !> A contact configuration whose pair of roots coalesces (the SDOF's stop damper at, or
   !> 1e-5 above, critical damping of the closed oscillator: a block from contour integrals,
   !> its window statistics by the polynomial and by the split form): the final state against
   !> the matrix-exponential reference, and every impact statistic against the mean of the
   !> runs at c (1 -+ 1e-3) (simple roots), which it matches to second order.
   subroutine coalescing_contact_pair()
      type(model_t) :: model
      type(transient_result_t) :: r, rl, rh
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: c_crit, d, s, z(2)
      integer :: k
      character(len=*), parameter :: common(3) = [character(len=120) :: &
         "&damping model = 'rayleigh', mass_coefficient = 1.0, stiffness_coefficient = 1.0e-4 /",&
         '&forcing amplitude_pp = 1.0e-3 /', '&solver transient_periods = 1, record_periods = 5 /']
      ! closed: m x'' + (beta m + gamma k1 + c) x' + (k1 + ks) x = ...: critical c
      c_crit = m1 * (2.0_dp * sqrt((k1 + ks) / m1) - 1.0_dp - 1.0e-4_dp * k1 / m1)
      z = [1.0_dp, 1.0_dp + 1.0e-5_dp]
      do k = 1, 2
         call run(sdof, [character(len=300) :: sdof_time_base(), common, damper(c_crit * z(k))], &
            model, r, u0=u0, v0=v0)
         d = expm_difference(model, r, u0, v0, 6)
         call run(sdof, [character(len=300) :: sdof_time_base(), common, &
            damper(c_crit * z(k) * (1.0_dp - 1.0e-3_dp))], model, rl)
         call run(sdof, [character(len=300) :: sdof_time_base(), common, &
            damper(c_crit * z(k) * (1.0_dp + 1.0e-3_dp))], model, rh)
         s = max(mean_dev(r%peak_force(1), rl%peak_force(1), rh%peak_force(1)), &
                 mean_dev(r%rms_force(1), rl%rms_force(1), rh%rms_force(1)), &
                 mean_dev(r%impulse_per_period(1), rl%impulse_per_period(1), &
                          rh%impulse_per_period(1)), &
                 mean_dev(r%work_rate(1), rl%work_rate(1), rh%work_rate(1)), &
                 mean_dev(r%contact_fraction(1), rl%contact_fraction(1), rh%contact_fraction(1)))
         call note('SDOF, stop damper at ' // str(z(k)) // ' x critical in contact, ' &
            // str(int(r%events)) // ' switches: exact vs matrix exponential ' // str(d) &
            // '; statistics against the mean of c (1 -+ 1e-3): ' // str(s))
         call check_le('coalescing contact pair (' // str(z(k)) // ' x critical): closed form ' &
            // 'and matrix-exponential reference agree', d, 1.0e-11_dp)
         call check_le('coalescing contact pair (' // str(z(k)) // ' x critical): impact ' &
            // 'statistics continuous to second order', s, 1.0e-5_dp)
         call check('coalescing contact pair: impacts, the same switches nearby', &
            r%events >= 4 .and. rl%events == r%events .and. rh%events == r%events)
      end do
   end subroutine coalescing_contact_pair

   !> '&stops damping = c /'
   function damper(c) result(ov)
      real(dp), intent(in) :: c
      character(len=300) :: ov
      write(ov, '(a, es24.16, a)') '&stops damping = ', c, ' /'
   end function damper

   !> |x - (a + b) / 2| / |x|.
   pure real(dp) function mean_dev(x, a, b)
      real(dp), intent(in) :: x, a, b
      mean_dev = abs(x - 0.5_dp * (a + b)) / max(abs(x), tiny(1.0_dp))
   end function mean_dev

   !> Two stops on a four-element beam, one of them with a contact damper (rank-1 and rank-2
   !> configurations, releases by the damper law), and massless rotations (condensed), against
   !> the matrix-exponential reference.
   subroutine two_stops_with_damper()
      type(model_t) :: model
      type(transient_result_t) :: r
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: d
      integer :: variant
      character(len=300) :: ri
      do variant = 1, 2
         ri = '&output history_periods = 3 /'
         if (variant == 2) ri = "&beam rotary_inertia = 'none' /"
         call run(ref, [character(len=300) :: ri, &
            "&stops node = 5, 3, dof = 'w', 'w', side = 'positive', 'negative', " &
            // "gap = 0.0, 2.0e-4, law = 'bilinear', 'bilinear', rule_factor = 2.0, 0.0, " &
            // 'stiffness = 0.0, 400.0, damping = 0.05, 0.0 /', &
            '&forcing amplitude_pp = 8.0e-3 /', &
            '&solver transient_periods = 0, record_periods = 3 /'], model, r, u0=u0, v0=v0)
         d = expm_difference(model, r, u0, v0, 3)
         call note('two stops, one damped' // trim(merge(', massless rotations', &
            '                    ', variant == 2)) // ': ' // str(r%n_impacts(1)) // ' and ' &
            // str(r%n_impacts(2)) // ' impacts, ' // str(int(r%events)) &
            // ' switches; exact vs matrix exponential ' // str(d))
         call check_le('two stops, one damped' // trim(merge(', massless rotations', &
            '                    ', variant == 2)) // ': closed form and matrix-exponential ' &
            // 'reference agree', d, 1.0e-11_dp)
         call check('two stops: both stops are hit', r%n_impacts(1) > 0 .and. r%n_impacts(2) > 0)
      end do
   end subroutine two_stops_with_damper

   !> A two-sided symmetric stop under symmetric forcing: eps(t + T/2) = -eps(t) on the
   !> attractor, to the decay of the transient.
   subroutine symmetric_two_sided_stop()
      type(model_t) :: model
      type(transient_result_t) :: r
      real(dp) :: asym
      integer :: half
      call run(ref, [character(len=300) :: "&stops side = 'both', gap = 5.0e-4 /", &
         '&forcing frequency_hz = 3.0, amplitude_pp = 2.0e-3 /', &
         '&solver transient_periods = 300, record_periods = 20 /', &
         '&output samples_per_period = 64, history_periods = 4 /'], model, r)
      half = 32
      asym = maxval(abs(r%strain(half + 1:) + r%strain(:size(r%strain) - half))) &
             / maxval(abs(r%strain))
      call note('two-sided stop, 3 Hz: impacts per period ' // str(real(r%n_impacts(1), dp) &
         / 20) // ', max |eps(t + T/2) + eps(t)| / max|eps| = ' // str(asym))
      call check('two-sided stop: impacts on both sides', r%n_impacts(1) >= 40)
      call check_le('two-sided symmetric stop: eps(t + T/2) = -eps(t)', asym, 1.0e-9_dp)
   end subroutine symmetric_two_sided_stop

   ! ---------------------------------------------------------------- Newmark

   !> Newmark (trapezoidal, fixed steps, events located) against the exact integrator:
   !> second order without impacts (checked); the orders across impacts are reported.
   subroutine newmark_converges_to_exact()
      type(model_t) :: model
      type(transient_result_t) :: rx, rn
      real(dp) :: e(3), order
      integer :: i
      character(len=300) :: ov
      character(len=*), parameter :: fixed = "&solver step_control = 'fixed', " &
         // 'locate_events = .true., transient_periods = 0, record_periods = 2, ' &
         // 'steps_per_period = '
      ! no impact
      ov = fixed // '256 /'
      call run(ref, [character(len=300) :: nostop, ratios, ov], model, rx)
      do i = 1, 3
         ov = fixed // str(128 * 2**i) // ' /'
         call run(ref, [character(len=300) :: nostop, ratios, ov], model, rn, newmark=.true.)
         e(i) = maxval(abs(rn%u - rx%u)) / maxval(abs(rx%u))
      end do
      order = log(e(2) / e(3)) / log(2.0_dp)
      call note('Newmark vs exact, no impact, final state after 2 periods at T/256, T/512, ' &
         // 'T/1024: ' // str(e(1)) // ', ' // str(e(2)) // ', ' // str(e(3)) // ' (order ' &
         // str(order) // ')')
      call check_close('Newmark converges to the exact integrator at second order (no impact)', &
         order, 2.0_dp, atol=0.1_dp)
      ! the 10.5 Hz deck: one impact per period, from rest
      ov = fixed // '256 /'
      call run(ref, [ov], model, rx)
      do i = 1, 3
         ov = fixed // str(256 * 2**i) // ' /'
         call run(ref, [ov], model, rn, newmark=.true.)
         e(i) = maxval(abs(rn%u - rx%u)) / maxval(abs(rx%u))
      end do
      order = log(e(2) / e(3)) / log(2.0_dp)
      call note('Newmark vs exact, 10.5 Hz deck, 2 periods from rest (' &
         // str(int(rx%n_impacts(1))) // ' impacts), final state at T/512, T/1024, T/2048: ' &
         // str(e(1)) // ', ' // str(e(2)) // ', ' // str(e(3)) // ' (order ' // str(order) &
         // ')')
      call check('Newmark error falls across impacts (10.5 Hz deck)', e(3) < e(2) .and. &
         e(2) < e(1))
      ! SDOF with a contact damper (the force jumps at impact)
      call run(sdof, [character(len=300) :: sdof_time_base(), '&stops damping = 0.07 /'], &
         model, rx)
      do i = 1, 3
         ov = '&solver steps_per_period = ' // str(64 * 2**i) // ' /'
         call run(sdof, [character(len=300) :: sdof_time_base(), '&stops damping = 0.07 /', ov], &
            model, rn, newmark=.true.)
         e(i) = maxval(abs(rn%tip_displacement - rx%tip_displacement)) / abs(u1)
      end do
      order = log(e(2) / e(3)) / log(2.0_dp)
      call note('Newmark vs exact, SDOF with a contact damper, history at T/128, T/256, ' &
         // 'T/512: ' // str(e(1)) // ', ' // str(e(2)) // ', ' // str(e(3)) // ' (order ' &
         // str(order) // ')')
      call check('Newmark error falls across damped impacts (SDOF)', e(3) < e(2) .and. &
         e(2) < e(1))
   end subroutine newmark_converges_to_exact

   !> The low-pass filtered strain (&output filter_cutoff_hz) is sampled and stored as
   !> run_transient does: it agrees with a fine fixed-step Newmark run, and replaces the
   !> Poincare strain (the raw tip samples stay).
   subroutine filtered_strain()
      type(model_t) :: model
      type(transient_result_t) :: rx, rn, rr
      real(dp) :: d_hist, d_poinc
      character(len=*), parameter :: horizon = "&solver step_control = 'fixed', " &
         // 'steps_per_period = 4096, transient_periods = 5, record_periods = 5 /'
      character(len=*), parameter :: filt = '&output filter_cutoff_hz = 40.0, filter_order = 4, ' &
         // 'filter_samples_per_period = 256, history_periods = 5 /'
      call run(ref, [character(len=300) :: horizon, filt], model, rx)
      call run(ref, [character(len=300) :: horizon, filt], model, rn, newmark=.true.)
      call run(ref, [character(len=300) :: horizon, '&output history_periods = 5 /'], model, rr)
      d_hist = rel(rx%strain_filtered, rn%strain_filtered)
      d_poinc = max(rel(rx%p_strain, rn%p_strain), rel(rx%p_strain_rate, rn%p_strain_rate))
      call note('filtered strain, exact vs Newmark T/4096: history ' // str(d_hist) &
         // ', Poincare ' // str(d_poinc))
      call check('filtered strain: one value per history sample', &
         size(rx%strain_filtered) == size(rx%time) .and. size(rx%time) > 0)
      call check_le('filtered strain agrees with fine Newmark (history and Poincare)', &
         max(d_hist, d_poinc), 1.0e-4_dp)
      call check('filtered strain replaces the Poincare strain (' // str(rel(rx%p_strain, &
         rr%p_strain)) // ' from the raw one), the tip samples stay raw (' &
         // str(rel(rx%p_tip, rr%p_tip)) // ')', rel(rx%p_strain, rr%p_strain) > 1.0e-3_dp &
         .and. rel(rx%p_tip, rr%p_tip) <= 1.0e-12_dp)
   end subroutine filtered_strain

   ! ---------------------------------------------------------------- limits

   !> Models outside the method are rejected with a clear message.
   subroutine unsupported_models()
      type(model_t) :: model
      type(transient_result_t) :: r
      character(len=:), allocatable :: msg
      call run(sdof, [character(len=300) :: "&stops law = 'hertz', stiffness = 1.0e6 /"], &
         model, r, message=msg)
      call check('Hertz stop rejected, naming the method and the law: ' // msg, &
         index(msg, 'exact') > 0 .and. index(msg, "'hertz'") > 0 .and. &
         index(msg, 'piecewise') > 0)
      call run(sdof, [character(len=300) :: "&stops dof = 'theta', gap = 0.01 /"], model, r, &
         message=msg)
      call check('stop on a massless dof rejected: ' // msg, index(msg, 'massless') > 0)
   end subroutine unsupported_models
   !> 15 elements (highest modes ~27 000 rad/s, so dgeev's eigenpairs alone are accurate to
   !> eps ||A|| ~ 1e-5 only): the exact final state against RK4 at T/16384 over 2 periods with
   !> impacts (RK4 there converges to about 1e-13).
   subroutine fifteen_elements_against_rk4()
      type(model_t) :: pe, pr
      type(transient_result_t) :: re, rr
      type(error_t), allocatable :: err
      real(dp) :: d, nrm
      character(len=*), parameter :: o15 = '&beam n_elem = 15 / &stops node = 16 / ' &
         // '&solver transient_periods = 0, record_periods = 2 / ' &
         // '&diagnostics lyapunov_periods = 0 /'
      call run_deck(ref, [character(len=200) :: o15, &
         "&solver method = 'exact' /"], pe, re, err)
      if (.not. allocated(err)) call run_deck(ref, &
         [character(len=200) :: o15, "&solver method = 'rk4', step_control = 'fixed', " &
         // 'steps_per_period = 16384 /'], pr, rr, err)
      if (allocated(err)) then
         call check('15 elements: runs succeed', .false., err%message)
         return
      end if
      nrm = sqrt(dot_product(rr%u, matmul(pr%sys%k, rr%u)) &
                 + dot_product(rr%v, matmul(pr%sys%m, rr%v)))
      d = sqrt(dot_product(re%u - rr%u, matmul(pr%sys%k, re%u - rr%u)) &
               + dot_product(re%v - rr%v, matmul(pr%sys%m, re%v - rr%v))) / nrm
      call note('15 elements, 2 periods with ' // str(re%n_impacts(1)) // ' impacts: exact ' &
         // 'against RK4 T/16384, relative energy-norm difference ' // str(d))
      call check('15 elements: exact integrator within 1e-10 of converged RK4', &
         d <= 1.0e-10_dp .and. re%n_impacts(1) > 0)
   end subroutine fifteen_elements_against_rk4

   !> 30 and 60 elements, where the high modes are overdamped (real eigenvalues down to
   !> -gamma omega_max^2, 5.9e7 1/s at 60 elements) and the former closed form hung: the exact
   !> final state after 2 periods from rest with impacts against converged RK4 (T/2^19 at 30,
   !> T/2^22 at 60 elements: minutes in a release build, so stored in test/data by
   !> scripts/exact_rk4_reference.py, whose header records the convergence by halving).
   subroutine fine_meshes_against_rk4()
      type(model_t) :: model
      type(transient_result_t) :: re
      type(error_t), allocatable :: err
      real(dp), allocatable :: u(:), v(:)
      real(dp) :: d, t
      integer :: k, n
      character(len=200) :: ov
      do k = 1, 2
         n = 30 * k
         call read_reference('test/data/exact_rk4_' // str(n) // '.txt', t, u, v)
         if (.not. allocated(u)) cycle
         write(ov, '(a, i0, a, i0, a)') '&beam n_elem = ', n, ' / &stops node = ', n + 1, &
            ' / &solver transient_periods = 0, record_periods = 2 / &diagnostics ' &
            // 'lyapunov_periods = 0 /'
         call run_deck(ref, [character(len=200) :: ov, "&solver method = 'exact' /"], model, &
                       re, err)
         if (allocated(err)) then
            call check(str(n) // ' elements: exact run succeeds', .false., err%message)
            cycle
         end if
         d = energy_norm(model, re%u - u, re%v - v) / energy_norm(model, u, v)
         call note(str(n) // ' elements, 2 periods with ' // str(re%n_impacts(1)) // ' impacts, ' &
            // str(int(re%events)) // ' switches: exact against converged RK4, relative ' &
            // 'energy-norm difference of the final state ' // str(d))
         call check(str(n) // ' elements: exact integrator within 1e-9 of converged RK4', &
            d <= 1.0e-9_dp .and. re%n_impacts(1) > 0 .and. abs(re%t_end - t) <= 1.0e-14_dp * t, &
            str(d))
      end do
   end subroutine fine_meshes_against_rk4

   !> Final time, u and v of a stored reference (lines starting with '#' are comments).
   subroutine read_reference(path, t, u, v)
      character(len=*), intent(in) :: path
      real(dp), intent(out) :: t
      real(dp), allocatable, intent(out) :: u(:), v(:)
      character(len=512) :: line
      integer :: unit, ios, n, i
      open(newunit=unit, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) then
         call check('reference ' // path // ' is readable', .false.);  return
      end if
      do
         read(unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) /= '#') exit
      end do
      if (ios == 0) read(line, *, iostat=ios) n, t
      if (ios == 0) then
         allocate(u(n), v(n))
         do i = 1, n
            read(unit, *, iostat=ios) u(i), v(i)
            if (ios /= 0) exit
         end do
      end if
      close(unit)
      if (ios /= 0) then
         if (allocated(u)) deallocate(u, v)
         call check('reference ' // path // ' is complete', .false.)
      end if
   end subroutine read_reference

   !> An event search that would take absurdly many steps ends with an error that names the
   !> time and what to change, never a hang (the step limit lowered to provoke one).
   subroutine search_limit()
      type(model_t) :: model
      type(transient_result_t) :: r
      character(len=:), allocatable :: msg
      call run(ref, [character(len=300) :: '&solver transient_periods = 0, record_periods = 1 /'], &
         model, r, message=msg, limit=3)
      call check('search limit: a clear error naming the time and the remedy: ' // msg, &
         index(msg, 'event search at t =') > 0 .and. index(msg, 'newmark') > 0)
   end subroutine search_limit

end program test_exact
