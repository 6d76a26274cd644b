!> The flow excitation in runs (docs/flow.md), checked against closed forms and independent
!> numerical integrations:
!> * wear depth over years: a whirling tube against a flat bar and in a drilled hole; every
!>   depth of /wear/depth holds the Archard volume V' t by an independent quadrature of the
!>   scar's cross-section, the depth grows with time, and the time to a wall fraction is the
!>   quadrature's volume at that depth over V'.
!> * fluid-elastic instability of the linear cantilever tube (Connors' damping per mode): the
!>   critical velocity of mode 1 is Connors' value; started in mode 1, the free vibration
!>   decays below it and grows above it at the rate the net modal damping predicts (the ratio
!>   of the tip at successive Poincare samples one damped period apart, e^(-zeta_net omega
!>   T_d)), within 1 %; the reduced model has the same rate.
!> * the flow velocity as a design variable: a sweep point's model at U (&sweep x_variable =
!>   '&flow velocity') is the deck's model with that velocity.
!> * turbulence on a linear cantilever tube (test/decks/tube_turbulence.nml): over one period
!>   of the record, the tip's mean square and its amplitude at every harmonic against the
!>   analytic modal frequency response (fully correlated: exact for every draw, within the
!>   integrator's error; short correlation: the mean over draws within its confidence
!>   interval); the reduced model; a draw reproduced exactly, another draw different.
program test_flow
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_test_runs, only: run_deck
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_flow_results, only: wear_depth_t
   use gapbeam_deck_rules_flow, only: deck_wear_depth
   use gapbeam_wear_geometry, only: seconds_per_year
   use gapbeam_test_runs, only: load_deck
   use gapbeam_model_builder, only: build_model
   use gapbeam_reduction, only: reduce_model, project
   use gapbeam_sweep, only: sweep_plan_t, make_plan
   use gapbeam_deck_parameter, only: model_with_values
   use gapbeam_transient, only: integrate
   use gapbeam_eigen, only: solve_modes
   use gapbeam_results, only: modes_t
   use gapbeam_model, only: global_dof
   use gapbeam_description, only: dof_w, beam_mass_per_length
   use gapbeam_turbulence, only: load_shapes, turbulence_psd
   use gapbeam_fft, only: fft
   use gapbeam_flow_results, only: flow_modes_t
   use gapbeam_flow_load, only: deck_flow_modes
   use gapbeam_fluid_elastic, only: connors_velocity
   use gapbeam_draw_statistics, only: mean_half_width, student_t_quantile
   implicit none
   character(len=*), parameter :: buffet = 'test/decks/tube_turbulence.nml'
   character(len=*), parameter :: whirl = 'test/decks/tube_whirl.nml'

   call wear_depth_over_years()
   call turbulence_linear_tube()
   call connors_instability()
   call velocity_design_variable()
   call finish('test_flow')

contains

   !> Area of the scar's cross-section by an independent quadrature: the tube's disc (radius r,
   !> centre at c on the x axis) outside the support, the half-plane x <= rh (flat bar: rh = r -
   !> h, c = 0) or the disc of radius rh about the origin (drilled hole); midpoint rule in y on
   !> the chord lengths, with n points.
   real(dp) function scar_area_quadrature(hole, r, rh, c, n) result(a)
      logical, intent(in) :: hole          !! drilled hole (else flat bar)
      real(dp), intent(in) :: r, rh, c     !! tube radius, hole radius or bar plane, tube centre
      integer, intent(in) :: n             !! quadrature points
      integer :: i
      real(dp) :: y, dy, xt, xs
      a = 0.0_dp
      dy = 2.0_dp * r / n
      do i = 1, n
         y = -r + (i - 0.5_dp) * dy
         xt = sqrt(max(r * r - y * y, 0.0_dp))
         if (hole) then
            if (abs(y) >= rh) then
               xs = -huge(1.0_dp)      ! outside the hole's band: all of the tube's chord
            else
               xs = sqrt(rh * rh - y * y)
            end if
         else
            xs = rh
         end if
         a = a + max(0.0_dp, c + xt - max(xs, c - xt)) * dy
      end do
   end function scar_area_quadrature

   !> The whirl of test/decks/tube_whirl.nml with friction and wear, its support as a flat bar
   !> and as a drilled hole, over 40 years.
   subroutine wear_depth_over_years()
      type(model_t) :: model
      type(transient_result_t) :: res
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      type(wear_depth_t) :: wd
      real(dp), parameter :: d = 0.019_dp, wall = 1.1e-3_dp, r = 0.5_dp * d
      real(dp), parameter :: b = 0.02_dp, t = 0.03_dp, rh = 0.5_dp * 0.0195_dp
      real(dp) :: v, err_max, vq
      integer :: i, g
      logical :: hole
      character(len=12) :: geometry
      character(len=200) :: support
      do g = 1, 2
         hole = g == 2
         if (hole) then
            geometry = 'drilled_hole'
            support = "&stops friction = 0.2, wear_coefficient = 2.0e-15, support = " &
               // "'drilled_hole', plate_thickness = 0.03, hole_diameter = 0.0195 /"
         else
            geometry = 'flat_bar'
            support = "&stops friction = 0.2, wear_coefficient = 2.0e-15, support = " &
               // "'flat_bar', land_width = 0.02 /"
         end if
         call read_deck(whirl, [character(len=200) :: support, '&wear years = 40, ' &
            // 'wall_thickness = 1.1e-3, tube_diameter = 0.019, wall_fraction = 0.4, ' &
            // 'depth_points = 21 /', '&solver transient_periods = 10, record_periods = 4 /'], &
            deck, err)
         call check('wear depth (' // trim(geometry) // '): the deck reads', .not. allocated(err))
         if (allocated(err)) return
         call run_deck(whirl, [character(len=200) :: support, '&solver transient_periods = ' &
            // '10, record_periods = 4 /'], model, res, err)
         call check('wear depth (' // trim(geometry) // '): the whirl runs', .not. allocated(err))
         if (allocated(err)) return
         call check('wear depth (' // trim(geometry) // '): the whirl wears', &
                    res%wear_volume_rate(1) > 0.0_dp)
         wd = deck_wear_depth(deck, res%wear_volume_rate)
         call check('wear depth (' // trim(geometry) // '): 21 times, 0 to 40 years', &
                    size(wd%time_years) == 21 .and. wd%time_years(1) == 0.0_dp .and. &
                    abs(wd%time_years(21) - 40.0_dp) < 1.0e-12_dp .and. wd%depth(1, 1) == 0.0_dp)
         call check('wear depth (' // trim(geometry) // '): grows with time', &
                    all(wd%depth(2:, 1) > wd%depth(:20, 1)) .and. wd%depth(21, 1) < wall)
         err_max = 0.0_dp
         do i = 2, 21
            v = res%wear_volume_rate(1) * wd%time_years(i) * seconds_per_year
            vq = scar_volume_quadrature(hole, wd%depth(i, 1), r, b, rh, t)
            err_max = max(err_max, abs(vq - v) / v)
         end do
         call check_le('wear depth (' // trim(geometry) // '): the quadrature''s scar volume ' &
                       // 'at each depth is V'' t', err_max, 1.0e-8_dp)
         call note('wear depth (' // trim(geometry) // '): ' // str(wd%depth(21, 1)) &
                   // ' m after 40 years at ' // str(res%wear_volume_rate(1)) // ' m^3/s')
         vq = scar_volume_quadrature(hole, 0.4_dp * wall, r, b, rh, t)
         call check_close('wear depth (' // trim(geometry) // '): years to 40 % of the wall = ' &
            // 'quadrature volume / V''', wd%years_to_fraction(1), &
            vq / res%wear_volume_rate(1) / seconds_per_year, 1.0e-6_dp)
      end do
   end subroutine wear_depth_over_years

   !> The scar volume at depth h of the whirl's tube (r) on the flat bar (land b) or in the
   !> drilled hole (radius rh, plate t), by the quadrature.
   real(dp) function scar_volume_quadrature(hole, h, r, b, rh, t) result(vq)
      logical, intent(in) :: hole
      real(dp), intent(in) :: h, r, b, rh, t
      if (hole) then
         vq = t * scar_area_quadrature(.true., r, rh, rh - r + h, 2000000)
      else
         vq = b * scar_area_quadrature(.false., r, r - h, 0.0_dp, 2000000)
      end if
   end function scar_volume_quadrature

   !> The tip's response to one draw: its mean square over the recorded period, and the
   !> amplitude of each harmonic k df, k = 1 .. n/2 - 1, from the FFT of the n samples.
   subroutine tip_response(path, overrides, draw, ms, amp, res_model, ok)
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: overrides(:)
      integer, intent(in) :: draw
      real(dp), intent(out) :: ms
      real(dp), allocatable, intent(out) :: amp(:)
      type(model_t), intent(out) :: res_model
      logical, intent(out) :: ok
      type(deck_t) :: deck
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      complex(dp), allocatable :: z(:)
      integer :: n
      character(len=160) :: ov(size(overrides) + 1)
      ov(1:size(overrides)) = overrides
      ov(size(ov)) = '&turbulence seed = ' // str(7 + 1000 * (draw - 1)) // ' /'
      call load_deck(path, ov, deck, res_model, u0, v0, err)
      if (.not. allocated(err)) call integrate(res_model, deck%solver, deck%output, u0, v0, &
                                               res, err)
      ok = .not. allocated(err)
      if (.not. ok) then
         call check('turbulence: the deck runs', .false., err%message)
         return
      end if
      n = deck%output%samples_per_period
      ms = sum(res%tip_displacement(1:n)**2) / n
      z = cmplx(res%tip_displacement(1:n), 0.0_dp, dp)
      call fft(z, -1)
      amp = 2.0_dp * abs(z(2:n / 2)) / n
   end subroutine tip_response

   !> The analytic tip response of the full model of `path`: the mean square sum_k S_k df
   !> sum_m |H_tip(f_k) L_m|^2 and, for one component, the amplitude sqrt(2 S_k df) |H L| of
   !> each harmonic; H from the mass-normalised modes and the Rayleigh damping.
   subroutine analytic_tip(path, overrides, ms, amp, ok)
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: overrides(:)
      real(dp), intent(out) :: ms
      real(dp), allocatable, intent(out) :: amp(:)
      logical, intent(out) :: ok
      type(deck_t) :: deck
      type(model_t) :: model
      type(modes_t) :: modes
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), shapes(:, :), gm(:, :)
      integer, allocatable :: plane_of(:), rank_in_plane(:)
      complex(dp) :: h
      real(dp) :: df, w, sk, r2
      integer :: k, m, j, tip, nk
      call load_deck(path, overrides, deck, model, u0, v0, err)
      if (.not. allocated(err)) call solve_modes(model%sys, modes, err)
      if (.not. allocated(err)) call load_shapes(model%sys, deck%turbulence, shapes, &
                                                 plane_of, rank_in_plane, err)
      ok = .not. allocated(err)
      if (.not. ok) return
      tip = global_dof(model%sys, model%sys%n_node, dof_w)
      gm = matmul(transpose(modes%shapes), shapes)      ! modal loads (mode, component)
      df = deck%turbulence%frequency_resolution_hz
      nk = deck%output%samples_per_period / 2 - 1
      allocate(amp(nk), source=0.0_dp)
      ms = 0.0_dp
      do k = 1, nk
         w = 2.0_dp * pi * k * df
         sk = turbulence_psd(deck%turbulence, deck%flow, k * df)
         if (sk <= 0.0_dp) cycle
         r2 = 0.0_dp
         do m = 1, size(shapes, 2)
            h = (0.0_dp, 0.0_dp)
            do j = 1, modes%n_modes
               h = h + modes%shapes(tip, j) * gm(j, m) / cmplx(modes%omega2(j) - w * w, &
                   w * (model%beta + model%gamma * modes%omega2(j)), dp)
            end do
            r2 = r2 + abs(h)**2
         end do
         ms = ms + sk * df * r2
         amp(k) = sqrt(2.0_dp * sk * df * r2)
      end do
   end subroutine analytic_tip

   !> Turbulence on the linear cantilever tube against the analytic modal response.
   subroutine turbulence_linear_tube()
      character(len=160), parameter :: short(1) = [character(len=160) :: &
         '&turbulence correlation_length = 0.05 /']
      character(len=160), parameter :: none(1) = [character(len=160) :: '&job /']
      character(len=160), parameter :: reduced(1) = [character(len=160) :: &
         "&reduction kind = 'modal', n_modes = 3 /"]
      integer, parameter :: n_draws = 4
      type(model_t) :: model
      real(dp) :: ms, ms_ref, ms2, mean, hw, x(n_draws)
      real(dp), allocatable :: amp(:), amp_ref(:), amp2(:)
      logical :: ok, ok_ref
      integer :: d
      ! fully correlated: every draw has the analytic mean square and spectrum
      call analytic_tip(buffet, none, ms_ref, amp_ref, ok_ref)
      call check('turbulence: the analytic response is computed', ok_ref)
      call tip_response(buffet, none, 1, ms, amp, model, ok)
      if (.not. (ok .and. ok_ref)) return
      call check('turbulence: the record is on the model, one component (fully correlated)', &
                 model%turbulence%active .and. model%turbulence%n_signals == 1)
      call check_close('turbulence, fully correlated: tip mean square = analytic modal sum', &
                       ms, ms_ref, 2.0e-3_dp)
      call check_le('turbulence, fully correlated: tip amplitude at every harmonic, relative ' &
                    // 'to the largest', maxval(abs(amp - amp_ref)) / maxval(amp_ref), 2.0e-3_dp)
      call note('turbulence, fully correlated: tip rms ' // str(sqrt(ms)) // ' m, analytic ' &
                // str(sqrt(ms_ref)) // ' m')
      call check('turbulence: a draw is reproduced exactly', same_record(buffet, 1, 1))
      call check('turbulence: another draw is another record', .not. same_record(buffet, 1, 2))
      call tip_response(buffet, reduced, 1, ms2, amp2, model, ok)
      if (ok) then
         call check('turbulence: the reduced model carries the projected record', &
                    model%turbulence%active .and. model%n < 17)
         call check_close('turbulence, reduced model (3 modes + static correction): tip mean ' &
                          // 'square = analytic', ms2, ms_ref, 5.0e-3_dp)
      end if
      ! short correlation: the mean over draws within its 99 % confidence interval
      call analytic_tip(buffet, short, ms_ref, amp_ref, ok_ref)
      call check('turbulence, short correlation: the analytic response is computed', ok_ref)
      if (.not. ok_ref) return
      do d = 1, n_draws
         call tip_response(buffet, short, d, x(d), amp, model, ok)
         if (.not. ok) return
      end do
      call check('turbulence, short correlation: several components', &
                 model%turbulence%n_signals > 1)
      call mean_half_width(x, mean, hw)
      hw = hw * student_t_quantile(0.995_dp, n_draws - 1) / student_t_quantile(0.975_dp, &
                                                                              n_draws - 1)
      call check_le('turbulence, short correlation: |mean tip mean square - analytic| within ' &
                    // 'the 99 % half-width of ' // str(n_draws) // ' draws', &
                    abs(mean - ms_ref), hw)
      call note('turbulence, short correlation (lambda_c = 0.05 m): mean square ' // str(mean) &
                // ' +- ' // str(hw) // ' (99 %), analytic ' // str(ms_ref) // ' m^2')
   end subroutine turbulence_linear_tube

   !> Do draws d1 and d2 of the deck's turbulence give the same record on its model?
   logical function same_record(path, d1, d2) result(same)
      character(len=*), intent(in) :: path
      integer, intent(in) :: d1, d2
      type(deck_t) :: deck
      type(model_t) :: m1, m2
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      same = .false.
      call read_deck(path, [character(len=8) ::], deck, err)
      if (.not. allocated(err)) call build_model(deck, m1, u0, v0, err, draw=d1)
      if (.not. allocated(err)) call build_model(deck, m2, u0, v0, err, draw=d2)
      if (allocated(err)) return
      same = all(m1%turbulence%x == m2%turbulence%x)
   end function same_record

   !> The linear cantilever tube in cross flow, mode 1 at 0.5, 1 and 1.5 U_c.
   subroutine connors_instability()
      character(len=160), parameter :: flow = "&flow fluid_density = 1000.0, tube_diameter " &
         // "= 0.019, connors_constant = 3.0, velocity = 1.0 /"
      character(len=160), parameter :: plain = "&turbulence spectrum = 'none' /"
      type(deck_t) :: deck
      type(model_t) :: model
      type(flow_modes_t) :: fm
      type(error_t), allocatable :: err
      real(dp) :: uc, want, zeta_s, zeta_net, f1, w1, growth, factor(3), m
      real(dp), allocatable :: u0(:), v0(:)
      integer :: k
      character(len=12) :: tag
      call read_deck(buffet, [character(len=160) :: flow, plain], deck, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err)
      call check('connors: the tube in cross flow builds', .not. allocated(err))
      if (allocated(err)) return
      call deck_flow_modes(deck, model%sys, model%beta, model%gamma, fm, err)
      call check('connors: the flow modes are solved', .not. allocated(err))
      if (allocated(err)) return
      f1 = fm%frequency_hz(1);  zeta_s = fm%structural_ratio(1)
      m = beam_mass_per_length(deck%structure%beam)
      want = 3.0_dp * f1 * 0.019_dp * sqrt(m * 2.0_dp * pi * zeta_s / (1000.0_dp * 0.019_dp**2))
      uc = fm%critical_velocity(1)
      call check_close('connors: critical velocity of mode 1 = K f D (m delta / (rho D^2))^(1/2)', &
                       uc, want, 1.0e-12_dp)
      call check_close('connors: the library''s connors_velocity agrees', uc, &
                       connors_velocity(3.0_dp, f1, 0.019_dp, m, 2.0_dp * pi * zeta_s, &
                                        1000.0_dp), 1.0e-12_dp)
      call note('connors: mode 1 at ' // str(f1) // ' Hz, zeta_s = ' // str(zeta_s) &
                // ', U_c = ' // str(uc) // ' m/s')
      factor = [0.5_dp, 1.0_dp, 1.5_dp]
      do k = 1, 3
         write(tag, '(f4.2)') factor(k)
         zeta_net = zeta_s * (1.0_dp - factor(k)**2)
         w1 = 2.0_dp * pi * f1
         growth = free_decay_rate(deck, factor(k) * uc, w1, zeta_net, .false.)
         if (k == 2) then
            call check_le('connors: at U_c the free vibration neither grows nor decays ' &
                          // '(|rate| / (zeta_s omega))', abs(growth) / (zeta_s * w1), 1.0e-3_dp)
         else
            call check_close('connors: U = ' // trim(tag) // ' U_c: decay rate = zeta_net ' &
                             // 'omega_1', growth, zeta_net * w1, 1.0e-2_dp)
         end if
      end do
      growth = free_decay_rate(deck, 1.5_dp * uc, w1, zeta_s * (1.0_dp - 2.25_dp), .true.)
      call check_close('connors: reduced model (3 modes), U = 1.5 U_c: growth rate = zeta_net ' &
                       // 'omega_1', growth, zeta_s * (1.0_dp - 2.25_dp) * w1, 1.0e-2_dp)
   end subroutine connors_instability

   !> The decay rate sigma of the tube started in mode 1 at flow velocity u: the tip at the
   !> Poincare samples one damped period T_d apart is a geometric sequence of ratio
   !> e^(-sigma T_d); sigma from its first and last samples.
   real(dp) function free_decay_rate(deck0, u, w1, zeta_net, reduced) result(sigma)
      type(deck_t), intent(in) :: deck0
      real(dp), intent(in) :: u, w1, zeta_net
      logical, intent(in) :: reduced
      type(deck_t) :: deck
      type(model_t) :: model, full
      type(flow_modes_t) :: fm
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), phi(:), p(:)
      real(dp) :: wd
      integer :: n
      sigma = huge(1.0_dp)
      deck = deck0
      deck%flow%velocity = u
      wd = w1 * sqrt(1.0_dp - zeta_net**2)
      deck%forcing%frequency_hz = wd / (2.0_dp * pi)
      deck%forcing%amplitude_pp = 0.0_dp
      deck%solver%method = 'newmark'
      deck%solver%step_control = 'fixed'            ! no forcing: no scale for error control
      deck%solver%steps_per_period = 1000           ! omega h = 6.3e-3
      deck%solver%transient_periods = 0
      deck%solver%record_periods = 20
      call build_model(deck, full, u0, v0, err)
      if (allocated(err)) return
      call deck_flow_modes(deck, full%sys, full%beta, full%gamma, fm, err)
      if (allocated(err)) return
      phi = 1.0e-3_dp * fm%shapes(:, 1) / fm%shapes(full%sys%tip_dof, 1)   ! tip 1 mm
      if (reduced) then
         deck%reduction%kind = 'modal';  deck%reduction%n_modes = 3
         call build_model(deck, model, u0, v0, err)
         if (allocated(err)) return
         ! the reduced coordinates of mode 1: the tip (a pinned coordinate) and the modes
         u0 = reduced_coordinates(deck, full, phi, err)
         if (allocated(err)) return
      else
         model = full
         u0 = phi
      end if
      v0 = 0.0_dp * u0
      call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      if (allocated(err)) then
         call check('connors: the free vibration runs', .false., err%message)
         return
      end if
      p = res%p_tip
      n = size(p)
      sigma = -log(p(n) / p(1)) / (real(n - 1, dp) * 2.0_dp * pi / wd)
   end function free_decay_rate

   !> The coordinates of the physical vector x in the reduced basis of the deck.
   function reduced_coordinates(deck, full, x, err) result(z)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: full
      real(dp), intent(in) :: x(:)
      type(error_t), allocatable, intent(out) :: err
      real(dp), allocatable :: z(:), basis(:, :)
      type(model_t) :: red
      call reduce_model(full, deck%reduction%n_modes, deck%reduction%static_correction, red, &
                        basis, err)
      if (.not. allocated(err)) call project(full, basis, x, z, err)
   end function reduced_coordinates

   !> A sweep over &flow velocity: each point's model is the deck's at that velocity.
   subroutine velocity_design_variable()
      type(deck_t) :: deck, d2
      type(model_t) :: m, ref
      type(sweep_plan_t) :: plan
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      call read_deck(buffet, [character(len=160) :: "&job analysis = 'sweep' /", &
         "&turbulence spectrum = 'none' /", "&flow fluid_density = 1000.0, tube_diameter = " &
         // "0.019, velocity = 1.0 /", "&sweep x_variable = '&flow velocity', x_values = " &
         // "0.5, 2.5, amplitude_pp = 0.0 /"], deck, err)
      call check('velocity sweep: the deck reads', .not. allocated(err))
      if (allocated(err)) return
      call make_plan(deck, plan, err)
      if (.not. allocated(err)) call model_with_values(deck, plan%set, [2.5_dp, 0.0_dp], m, err)
      call check('velocity sweep: the point''s model builds', .not. allocated(err))
      if (allocated(err)) return
      d2 = deck
      d2%flow%velocity = 2.5_dp
      call build_model(d2, ref, u0, v0, err)
      if (allocated(err)) return
      call check_le('velocity sweep: the point''s damping = the deck''s at U = 2.5 m/s', &
                    maxval(abs(m%c - ref%c)), 1.0e-12_dp * maxval(abs(ref%c)))
      call build_model(deck, ref, u0, v0, err)
      if (allocated(err)) return
      call check_close('velocity sweep: its fluid-elastic damping is (2.5)^2 the one at 1 m/s', &
                       maxval(abs(m%c_modal)), 6.25_dp * maxval(abs(ref%c_modal)), 1.0e-12_dp)
   end subroutine velocity_design_variable
end program test_flow
