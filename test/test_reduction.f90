!> Modal reduction. Planar: all modes reproduce the full model; the static correction makes
!> the contact flexibility exact and the peak stop force closer with few modes. Tubes (two
!> planes, rings, friction, point forces, whirling base motion, several spans): the contact
!> flexibility and the static response to the point forces exact with any cut-off, the loads
!> projected right (harmonic response against the full model), reduced against full runs of
!> the small two-plane decks and a 12-element multispan tube with everything at once (every
!> mode kept: the same trajectory, stick-slip and energy balance; a cut-off: work rates
!> close), the closed-form whirl and stick-slip on reduced models, and a sweep of a reduced
!> tube (points, shards merged, a stopped and resumed run).
program test_reduction
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_model, build_full_model
   use gapbeam_reduction, only: reduce_model
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_lapack, only: dpotrf, dpotrs, zgesv
   use gapbeam_test_runs, only: run_deck
   use gapbeam_results, only: point_result_t
   use gapbeam_settings, only: batch_options_t
   use gapbeam_sweep_job, only: run_sweep_job
   use gapbeam_sweep_output, only: sweep_file_t, read_sweep, merge_sweep
   use gapbeam_files, only: remove_file, file_exists
   use gapbeam_reduction_rule, only: reduction_info_t
   use gapbeam_reduction_check, only: reduction_check_t, check_reduction, check_lines
   implicit none
   character(len=*), parameter :: ref = 'test/decks/moon_shaw_10p5hz_half_element.nml'
   character(len=*), parameter :: tube = 'inputs/tube_multispan.nml'
   character(len=*), parameter :: cantilever = 'test/decks/tube_cantilever.nml'
   character(len=*), parameter :: whirl = 'test/decks/tube_whirl.nml'
   character(len=*), parameter :: slide = 'test/decks/tube_slide.nml'
   character(len=*), parameter :: short = "&solver step_control = 'fixed', " &
      // 'transient_periods = 0, record_periods = 5 /'

   call planar_reduction()
   call static_flexibility_two_planes()
   call loads_projected()
   call reduced_small_tubes()
   call reduced_multispan_tube()
   call sweep_of_reduced_tube()
   call auto_rule()
   call finish('test_reduction')

contains

   !> The planar Moon & Shaw deck: all modes reproduce the full trajectory; the static
   !> correction makes the static deflection under a stop load exact.
   subroutine planar_reduction()
      type(model_t) :: pf, pr
      type(transient_result_t) :: rf, rr, r2, r2s
      real(dp) :: d, u_full, u_red, e_with, e_without
      integer :: n_all

      ! fixed steps without event location: the two runs take exactly the same steps (a located
      ! event's sub-step can flip between split and not split on round-off, which moves the
      ! trajectory by the local truncation error, about 1e-9 here)
      call run([character(len=200) :: short, '&solver locate_events = .false. /'], pf, rf)
      n_all = pf%n
      call run([character(len=200) :: short, '&solver locate_events = .false. /', &
         "&reduction kind = 'modal', n_modes = " // str(n_all) &
         // ', static_correction = .false. /'], pr, rr)
      d = max(maxval(abs(rr%strain - rf%strain)) / maxval(abs(rf%strain)), &
              maxval(abs(rr%tip_displacement - rf%tip_displacement)) &
              / maxval(abs(rf%tip_displacement)), &
              maxval(abs(rr%stop_force - rf%stop_force)) / maxval(abs(rf%stop_force)))
      call note('all ' // str(n_all) // ' modes: largest relative difference to the full ' &
         // 'model ' // str(d))
      call check('the modal model with all modes has as many coordinates as the full one', &
         pr%n == n_all)
      call check_le('a modal model keeping all modes reproduces the full trajectory', d, &
         1.0e-9_dp)
      call run([character(len=200) :: short], pf, rf)

      ! static tip deflection under a unit stop load: exact with the static correction
      call run([character(len=200) :: short, "&reduction kind = 'modal', n_modes = 2, " &
         // 'static_correction = .true. /'], pr, r2s)
      u_full = static_response(pf, pf%c_dof(1))
      u_red = static_response(pr, pr%c_dof(1))
      call check_close('2 modes + static correction: static deflection under a stop load ' &
         // 'exact', u_red, u_full, rtol=1.0e-10_dp)
      call run([character(len=200) :: short, "&reduction kind = 'modal', n_modes = 2, " &
         // 'static_correction = .false. /'], pr, r2)
      u_red = static_response(pr, pr%c_dof(1))
      call note('2 modes without static correction: static deflection ' // str(u_red) &
         // ' against ' // str(u_full) // ' (full model)')
      e_with = abs(r2s%peak_force(1) - rf%peak_force(1)) / rf%peak_force(1)
      e_without = abs(r2%peak_force(1) - rf%peak_force(1)) / rf%peak_force(1)
      call note('peak stop force over 5 periods: full ' // str(rf%peak_force(1)) // ' N; 2 ' &
         // 'modes with static correction ' // str(r2s%peak_force(1)) // ' N (error ' &
         // str(e_with) // '), without ' // str(r2%peak_force(1)) // ' N (error ' &
         // str(e_without) // ')')
      call check('static correction brings the peak stop force closer to the full model', &
         e_with < e_without)
   end subroutine planar_reduction


   !> The full model of a deck (read with overrides) and its reduction with `cutoff_hz` (0:
   !> n_modes per plane), static correction as given.
   subroutine full_and_reduced(path, overrides, cutoff_hz, n_modes, static, full, red, basis, &
                               ok)
      character(len=*), intent(in) :: path, overrides(:)
      real(dp), intent(in) :: cutoff_hz
      integer, intent(in) :: n_modes
      logical, intent(in) :: static
      type(model_t), intent(out) :: full, red
      real(dp), allocatable, intent(out) :: basis(:, :)
      logical, intent(out) :: ok
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      character(len=len(overrides)) :: ov(size(overrides))
      ov = overrides
      call read_deck(path, ov, deck, err)
      if (.not. allocated(err)) call build_full_model(deck%structure, deck%stops, &
         deck%damping, deck%forcing, full, err)
      if (.not. allocated(err)) call reduce_model(full, n_modes, static, red, basis, err, &
                                                  cutoff_hz=cutoff_hz)
      ok = .not. allocated(err)
      if (.not. ok) call check('reduce ' // path, .false., err%message)
   end subroutine full_and_reduced

   !> The compliance of a stiffness matrix between the given dofs: (K^-1)(dofs, dofs).
   function compliance(k, dofs) result(c)
      real(dp), intent(in) :: k(:, :)
      integer, intent(in) :: dofs(:)
      real(dp), allocatable :: c(:, :), kf(:, :), b(:, :)
      integer :: n, j, info
      n = size(k, 1)
      kf = k
      allocate(b(n, size(dofs)), source=0.0_dp)
      do j = 1, size(dofs)
         b(dofs(j), j) = 1.0_dp
      end do
      call dpotrf('U', n, kf, n, info)
      call dpotrs('U', n, size(dofs), kf, n, b, n, info)
      c = b(dofs, :)
   end function compliance

   !> The static response K^-1 f.
   function static_solution(k, f) result(u)
      real(dp), intent(in) :: k(:, :), f(:)
      real(dp), allocatable :: u(:), kf(:, :), b(:, :)
      integer :: n, info
      n = size(k, 1)
      kf = k
      b = reshape(f, [n, 1])
      call dpotrf('U', n, kf, n, info)
      call dpotrs('U', n, 1, kf, n, b, n, info)
      u = b(:, 1)
   end function static_solution

   !> Every dof the supports use: the contact dofs and both directions of each support node.
   function support_dofs(m) result(d)
      type(model_t), intent(in) :: m
      integer, allocatable :: d(:)
      d = [m%slot_dof, m%stop_dofs(1, :), m%stop_dofs(2, :)]
   end function support_dofs

   !> The multispan tube reduced on its modes up to 100 Hz (3 per plane) with the static
   !> modes: the flexibility between every pair of support dofs (w and v at both baffles) is
   !> the full model's to round-off, and so is the static response to the point forces
   !> everywhere; without the static modes it is not.
   subroutine static_flexibility_two_planes()
      type(model_t) :: full, red, red0
      real(dp), allocatable :: basis(:, :), basis0(:, :), cf(:, :), cr(:, :), uf(:), ur(:)
      real(dp) :: e, e0, ep
      logical :: ok
      call full_and_reduced(tube, [character(len=1) ::], 100.0_dp, 0, .true., full, red, basis, &
                            ok)
      if (.not. ok) return
      call note('tube reduced to 100 Hz: ' // str(red%n) // ' coordinates of ' // str(full%n) &
         // ', highest frequency ' // str(red%omega_max / (2.0_dp * pi)) // ' Hz (full ' &
         // str(full%omega_max / (2.0_dp * pi)) // ' Hz)')
      call check('two planes: the reduced coordinates split into two equal planes', &
                 red%sys%planes == 2 .and. mod(red%n, 2) == 0)
      call check('the ring dofs are coordinates of the reduced model (w, v mirrored)', &
                 all(red%r_dof(2, :) == red%r_dof(1, :) + red%n / 2))
      cf = compliance(full%sys%k, support_dofs(full))
      cr = compliance(red%sys%k, support_dofs(red))
      e = maxval(abs(cr - cf)) / maxval(abs(cf))
      call note('flexibility at the supports (w, v at both baffles): largest difference ' &
         // str(e) // ' of the largest entry')
      call check_le('static modes: the flexibility between the support dofs is exact', e, &
                    1.0e-10_dp)
      call full_and_reduced(tube, [character(len=1) ::], 100.0_dp, 0, .false., full, red0, &
                            basis0, ok)
      if (.not. ok) return
      e0 = maxval(abs(compliance(red0%sys%k, support_dofs(red0)) - cf)) / maxval(abs(cf))
      call note('without the static modes: difference ' // str(e0))
      call check('without the static modes the flexibility at the supports is off (> 0.1 %)', &
                 e0 > 1.0e-3_dp)
      ! the point forces: the static response everywhere (K^-1 p lies in the basis)
      uf = static_solution(full%sys%k, full%p_sin + full%p_cos)
      ur = matmul(basis, static_solution(red%sys%k, red%p_sin + red%p_cos))
      ep = maxval(abs(ur - uf)) / maxval(abs(uf))
      call note('static response to the point forces: largest difference ' // str(ep) &
         // ' of its largest value')
      call check_le('static modes at the force: its static response is exact everywhere', ep, &
                    1.0e-10_dp)
   end subroutine static_flexibility_two_planes

   !> (K - W^2 M + i W C)^-1 l, the harmonic response of the open structure.
   function harmonic(m, w, l) result(x)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: w, l(:)
      complex(dp), allocatable :: x(:), a(:, :), b(:, :)
      integer, allocatable :: ipiv(:)
      integer :: n, info
      n = m%n
      a = cmplx(m%sys%k - w**2 * m%sys%m, w * m%c, dp)
      b = reshape(cmplx(l, 0.0_dp, dp), [n, 1])
      allocate(ipiv(n))
      call zgesv(n, 1, a, n, ipiv, b, n, info)
      x = b(:, 1)
   end function harmonic

   !> The loads of a whirling base motion (w and v, 90 degrees apart) and of the point forces,
   !> projected on the basis: the harmonic response at the support dofs against the full
   !> model's at the forcing frequency and at 4 x it; with every mode kept it is exact.
   subroutine loads_projected()
      type(model_t) :: full, red
      real(dp), allocatable :: basis(:, :)
      real(dp) :: e(4), w
      logical :: ok
      integer :: k, j
      character(len=*), parameter :: whirling = '&forcing amplitude_pp = 1.0e-3, ' &
         // 'direction_deg = 30.0, phase_v_deg = 90.0 /'
      character(len=12), parameter :: names(4) = [character(len=12) :: 'base w', 'base v', &
         'force (sin)', 'force (cos)']
      do j = 1, 2
         if (j == 1) then
            call full_and_reduced(tube, [whirling], 150.0_dp, 0, .true., full, red, basis, ok)
         else
            call full_and_reduced(tube, [whirling], 0.0_dp, full%n / 2, .true., full, red, &
                                  basis, ok)
         end if
         if (.not. ok) return
         call check('the whirling base motion has loads in both planes', allocated(red%q_v) &
                    .and. maxval(abs(red%q_v)) > 0.0_dp .and. maxval(abs(red%q)) > 0.0_dp)
         do k = 1, 2
            w = real(4 * (k - 1) + 1, dp) * full%omega
            e(1) = load_error(full, red, w, full%q, red%q)
            e(2) = load_error(full, red, w, full%q_v, red%q_v)
            e(3) = load_error(full, red, w, full%p_sin, red%p_sin)
            e(4) = load_error(full, red, w, full%p_cos, red%p_cos)
            if (j == 1) then
               call note('cut-off 150 Hz, ' // str(w / (2.0_dp * pi)) // ' Hz: harmonic ' &
                  // 'response at the supports, relative error ' // str(e(1)) // ' (' &
                  // trim(names(1)) // '), ' // str(e(2)) // ' (' // trim(names(2)) // '), ' &
                  // str(e(3)) // ' (' // trim(names(3)) // '), ' // str(e(4)) // ' (' &
                  // trim(names(4)) // ')')
               call check_le('cut-off 150 Hz: harmonic response to each load at ' &
                  // str(w / (2.0_dp * pi)) // ' Hz within 1e-3', maxval(e), 1.0e-3_dp)
            else
               call check_le('every mode kept: harmonic response to each load exact at ' &
                  // str(w / (2.0_dp * pi)) // ' Hz', maxval(e), 1.0e-9_dp)
            end if
         end do
      end do
   end subroutine loads_projected

   !> Largest relative error of the reduced model's harmonic response at frequency w to load
   !> lr, at the support dofs, against the full model's response to lf.
   real(dp) function load_error(full, red, w, lf, lr)
      type(model_t), intent(in) :: full, red
      real(dp), intent(in) :: w, lf(:), lr(:)
      complex(dp), allocatable :: xf(:), xr(:)
      integer, allocatable :: df(:), dr(:)
      df = support_dofs(full);  dr = support_dofs(red)
      xf = harmonic(full, w, lf)
      xr = harmonic(red, w, lr)
      load_error = maxval(abs(xr(dr) - xf(df))) / maxval(abs(xf(df)))
   end function load_error

   !> Read a deck with overrides, set its reduction (kind, cut-off, modes per plane), build and
   !> integrate it.
   subroutine run_reduced(path, overrides, kind, cutoff_hz, n_modes, model, res, ok)
      character(len=*), intent(in) :: path, overrides(:), kind
      real(dp), intent(in) :: cutoff_hz
      integer, intent(in) :: n_modes
      type(model_t), intent(out) :: model
      type(transient_result_t), intent(out) :: res
      logical, intent(out) :: ok
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      character(len=len(overrides)) :: ov(size(overrides))
      ov = overrides
      call read_deck(path, ov, deck, err)
      if (.not. allocated(err)) then
         deck%reduction%kind = kind
         deck%reduction%cutoff_hz = cutoff_hz
         deck%reduction%n_modes = n_modes
         call build_model(deck, model, u0, v0, err)
      end if
      if (.not. allocated(err)) call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      ok = .not. allocated(err)
      if (.not. ok) call check(path // ' (' // kind // ') runs', .false., err%message)
   end subroutine run_reduced

   pure real(dp) function span(x)
      real(dp), intent(in) :: x(:)
      span = maxval(x) - minval(x)
   end function span

   !> Largest relative difference of two runs' orbits, normal forces and wear outputs.
   real(dp) function run_difference(a, b) result(d)
      type(transient_result_t), intent(in) :: a, b
      integer :: k
      d = 0.0_dp
      do k = 1, size(a%n_impacts)
         d = max(d, maxval(abs(a%orbit_w(:, k) - b%orbit_w(:, k))) / span(a%orbit_w(:, k)), &
                 maxval(abs(a%orbit_v(:, k) - b%orbit_v(:, k))) / span(a%orbit_v(:, k)))
         if (a%peak_force(k) > 0.0_dp) d = max(d, maxval(abs(a%stop_force(:, k) &
            - b%stop_force(:, k))) / a%peak_force(k), abs(b%normal_work_rate(k) &
            / a%normal_work_rate(k) - 1.0_dp))
         if (a%friction_work_rate(k) > 0.0_dp) d = max(d, abs(b%friction_work_rate(k) &
            / a%friction_work_rate(k) - 1.0_dp))
      end do
   end function run_difference

   !> Reduced against full runs of the small two-plane decks: every mode kept (the reduction
   !> is a change of coordinates) gives the same run; a cut-off gives close work rates.
   subroutine reduced_small_tubes()
      type(model_t) :: mf, mr
      type(transient_result_t) :: rf, rr
      logical :: okf, okr
      real(dp) :: d
      integer :: j, k, nov
      character(len=48), parameter :: decks(3) = [character(len=48) :: cantilever, whirl, slide]
      character(len=160) :: ov(3, 2)
      ov = ''
      ! (one method for both: 'auto' runs the exponential integrator on the reduced model)
      ov(1, 1) = '&solver tolerance = 1.0e-6, transient_periods = 0, record_periods = 2, ' &
                 // "method = 'newmark' /"
      ov(1, 2) = '&output history_periods = 2 /'
      ov(2, 1) = ov(1, 1)
      ov(2, 2) = '&output history_periods = 2 / &stops friction = 0.3 /'
      ov(3, 1) = "&solver tolerance = 1.0e-4, method = 'newmark' /"
      do j = 1, 3
         nov = merge(1, 2, j == 3)
         call run_reduced(trim(decks(j)), ov(j, :nov), 'none', 0.0_dp, 0, mf, rf, okf)
         call run_reduced(trim(decks(j)), ov(j, :nov), 'modal', 1.0e12_dp, 0, mr, rr, okr)
         if (.not. (okf .and. okr)) cycle
         d = run_difference(rf, rr)
         call note(trim(decks(j)) // ', every mode kept (' // str(mr%n) // ' coordinates, ' &
            // str(mf%n) // ' dofs): largest relative difference ' // str(d) // '; impacts ' &
            // str(sum(rf%n_impacts)) // ' / ' // str(sum(rr%n_impacts)))
         call check_le(trim(decks(j)) // ': the reduced model with every mode runs as the ' &
                       // 'full one', d, 1.0e-6_dp)
         call check(trim(decks(j)) // ': the same impacts', all(rf%n_impacts == rr%n_impacts))
      end do
      ! a cut-off: the rattling tube on 2 modes per plane and the static modes
      ov(1, 1) = '&solver tolerance = 1.0e-5, transient_periods = 4, record_periods = 8 /'
      call run_reduced(cantilever, ov(1, :), 'none', 0.0_dp, 0, mf, rf, okf)
      if (.not. okf) return
      do k = 1, 2
         call run_reduced(cantilever, ov(1, :), 'modal', 0.0_dp, k + 1, mr, rr, okr)
         if (.not. okr) return
         call note('rattling tube, ' // str(k + 1) // ' modes per plane (' // str(mr%n) &
            // ' coordinates, highest mode ' // str(mr%omega_max / (2.0_dp * pi)) // ' Hz): ' &
            // 'normal work rate ' // str(rr%normal_work_rate(1)) // ' W (full ' &
            // str(rf%normal_work_rate(1)) // '), friction ' // str(rr%friction_work_rate(1)) &
            // ' W (' // str(rf%friction_work_rate(1)) // '), impacts ' &
            // str(rr%n_impacts(1)) // ' (' // str(rf%n_impacts(1)) // '), peak force ' &
            // str(rr%peak_force(1)) // ' N (' // str(rf%peak_force(1)) // ')')
      end do
      call check_le('rattling tube, 3 modes per plane: normal work rate within 1 %', &
                    abs(rr%normal_work_rate(1) / rf%normal_work_rate(1) - 1.0_dp), 0.01_dp)
      call check_le('rattling tube, 3 modes per plane: friction work rate within 1 %', &
                    abs(rr%friction_work_rate(1) / rf%friction_work_rate(1) - 1.0_dp), 0.01_dp)
      call check_le('rattling tube, 3 modes per plane: peak force within 1 %', &
                    abs(rr%peak_force(1) / rf%peak_force(1) - 1.0_dp), 0.01_dp)
      call check('rattling tube, 3 modes per plane: the same impacts', &
                 rr%n_impacts(1) == rf%n_impacts(1))
   end subroutine reduced_small_tubes

   !> The multispan tube deck on 12 elements with everything at once: two intermediate ring
   !> supports with friction (one hole offset), the pinned top, added mass, point forces and a
   !> whirling base motion. Every mode kept: the full run (orbits, forces, work rates, impacts,
   !> stick-slip, energy balance); the auto basis: work rates, impacts and peak forces close to
   !> the full model's, the energy balance closed as tightly.
   subroutine reduced_multispan_tube()
      type(model_t) :: mf, mr, ma
      type(transient_result_t) :: rf, rr, ra, rf4
      logical :: ok
      real(dp) :: d, ea
      integer :: k
      character(len=160) :: ov(4)
      ov(1) = '&beam n_elem = 12 / &stops node = 5, 9, gap = 0.1e-3, 0.1e-3, offset_w = ' &
              // '0.03e-3, 0.0 /'
      ov(2) = '&point_forces node = 7, 7 / &forcing amplitude_pp = 2.0e-4, direction_deg = ' &
              // '30.0, phase_v_deg = 90.0 /'
      ! (one method for both: 'auto' runs the exponential integrator on the reduced model)
      ov(3) = '&solver tolerance = 1.0e-6, transient_periods = 1, record_periods = 2, ' &
              // "method = 'newmark' /"
      ov(4) = '&output history_periods = 2 /'
      call run_reduced(tube, ov, 'none', 0.0_dp, 0, mf, rf, ok)
      if (.not. ok) return
      call run_reduced(tube, ov, 'modal', 1.0e12_dp, 0, mr, rr, ok)
      if (.not. ok) return
      d = run_difference(rf, rr)
      call note('multispan tube, 12 elements, every mode kept (' // str(mr%n) // ' coordinates): ' &
         // 'largest relative difference ' // str(d) // '; impacts ' // str(rf%n_impacts(1)) &
         // ', ' // str(rf%n_impacts(2)) // '; stick fractions ' // str(rf%stick_fraction(1)) &
         // ', ' // str(rf%stick_fraction(2)) // '; events ' // str(int(rf%events)))
      call check('multispan tube: both supports impact, slide and stick', &
                 all(rf%n_impacts > 0) .and. all(rf%friction_work_rate > 0.0_dp) &
                 .and. any(rf%stick_fraction > 0.0_dp))
      call check_le('multispan tube, every mode kept: the reduced run is the full one', d, &
                    1.0e-5_dp)
      call check('multispan tube, every mode kept: the same impacts', &
                 all(rf%n_impacts == rr%n_impacts))
      call check_le('multispan tube, every mode kept: the same stick fractions', &
                    maxval(abs(rf%stick_fraction - rr%stick_fraction)), 1.0e-4_dp)
      call check_le('multispan tube, every mode kept: energy balance closes as in the full ' &
                    // 'model', abs(imbalance(rr)), max(1.0e-6_dp, 2.0_dp * abs(imbalance(rf))))
      ! the basis rule at the default tolerance against the full model at that tolerance
      ov(3) = '&solver tolerance = 1.0e-4, transient_periods = 1, record_periods = 2 /'
      call run_reduced(tube, ov, 'none', 0.0_dp, 0, mf, rf4, ok)
      if (.not. ok) return
      call run_reduced(tube, ov, 'auto', 0.0_dp, 0, ma, ra, ok)
      if (.not. ok) return
      ea = imbalance(ra)
      call check('multispan tube, auto basis: fewer coordinates than dofs', ma%n < mf%n)
      do k = 1, 2
         call note('multispan tube, support ' // str(k) // ', auto basis (' // str(ma%n) &
            // ' coordinates) / full at 1e-4 / full at 1e-6: normal work rate ' &
            // str(ra%normal_work_rate(k)) // ' / ' // str(rf4%normal_work_rate(k)) // ' / ' &
            // str(rf%normal_work_rate(k)) // ' W, friction ' // str(ra%friction_work_rate(k)) &
            // ' / ' // str(rf4%friction_work_rate(k)) // ' / ' // str(rf%friction_work_rate(k)) &
            // ' W, peak ' // str(ra%peak_force(k)) // ' / ' // str(rf4%peak_force(k)) // ' / ' &
            // str(rf%peak_force(k)) // ' N, impacts ' // str(ra%n_impacts(k)) // ' / ' &
            // str(rf4%n_impacts(k)) // ' / ' // str(rf%n_impacts(k)))
         call check_le('multispan tube, auto basis: normal work rate within 2 % of the ' &
            // 'converged full run, support ' // str(k), &
            abs(ra%normal_work_rate(k) / rf%normal_work_rate(k) - 1.0_dp), 0.02_dp)
         call check_le('multispan tube, auto basis: friction work rate within 2 %, support ' &
            // str(k), abs(ra%friction_work_rate(k) / rf%friction_work_rate(k) - 1.0_dp), 0.02_dp)
         call check_le('multispan tube, auto basis: peak force within 2 %, support ' // str(k), &
            abs(ra%peak_force(k) / rf%peak_force(k) - 1.0_dp), 0.02_dp)
         call check('multispan tube, auto basis: the same impacts as the full model at its ' &
                    // 'tolerance, support ' // str(k), ra%n_impacts(k) == rf4%n_impacts(k))
      end do
      call check("multispan tube, auto basis: method 'auto' runs the exponential integrator", &
                 ra%method == 'exponential', ra%method)
      ! The balance is integrated on the steps' quintic Hermite pieces (u, v, a at both ends).
      ! Under the exponential integrator at 1e-4 it closed to 9.9e-4 of the input while the
      ! controller checked the cubic only (friction with a contact damper: the damper's force
      ! follows the interpolant's velocity, and an end acceleration with the damper's jump at
      ! an onset bent the quintic); with the quintic checked on every output and the step's
      ! own end acceleration, 1.9e-5 (docs/methods.md).
      call check_le('multispan tube, auto basis (exponential, 1e-4): energy imbalance below ' &
                    // '1e-4 of the input', abs(ea), 1.0e-4_dp)
      ov(3) = '&solver tolerance = 1.0e-5, transient_periods = 1, record_periods = 2 /'
      call run_reduced(tube, ov, 'auto', 0.0_dp, 0, ma, ra, ok)
      if (.not. ok) return
      call check_le('multispan tube, auto basis (exponential, 1e-5): energy imbalance below ' &
                    // '1e-5 of the input', abs(imbalance(ra)), 1.0e-5_dp)
      ov(3) = "&solver tolerance = 1.0e-4, transient_periods = 1, record_periods = 2, method " &
              // "= 'newmark' /"
      call run_reduced(tube, ov, 'auto', 0.0_dp, 0, ma, ra, ok)
      if (.not. ok) return
      call check_le('multispan tube, auto basis (Newmark, 1e-4): energy imbalance below 1e-4 ' &
                    // 'of the input', abs(imbalance(ra)), 1.0e-4_dp)
   end subroutine reduced_multispan_tube

   !> Energy imbalance of a run relative to its input work.
   real(dp) function imbalance(r)
      type(transient_result_t), intent(in) :: r
      imbalance = (r%input_work - r%rayleigh_dissipation - r%contact_damping_dissipation &
                   - r%friction_dissipation - r%stored_energy_change) / abs(r%input_work)
   end function imbalance

   !> A sweep (clearance of the ring, two points) of the rattling tube reduced to 3 modes per
   !> plane, through the job driver as the executable runs it: each point equals the reduced
   !> transient run with that clearance; two shards merged equal the single-process file; a run
   !> stopped by its time limit and resumed from its checkpoint equals it too.
   subroutine sweep_of_reduced_tube()
      type(model_t) :: m
      type(transient_result_t) :: res
      type(sweep_file_t) :: sf
      type(point_result_t), allocatable :: pts(:)
      type(error_t), allocatable :: err
      logical :: complete, ok
      character(len=*), parameter :: base = 'test_reduction_sweep'
      character(len=*), parameter :: solver = '&solver tolerance = 1.0e-4, ' &
         // 'transient_periods = 2, record_periods = 3 /'
      call sweep_job(base, 1, 1, 0.0_dp, complete)
      call check('reduced tube: the sweep completes', complete .and. file_exists(base // '.h5'))
      if (.not. complete) return
      call read_sweep(base // '.h5', sf, pts, err)
      call check('reduced tube: its file reads', .not. allocated(err))
      if (allocated(err)) return
      call run_reduced(cantilever, [character(len=100) :: solver, '&stops gap = 0.15e-3 /'], &
                       'modal', 0.0_dp, 3, m, res, ok)
      if (.not. ok) return
      call check('reduced tube: both points ran and impact', all(pts%status == 0) .and. &
                 pts(1)%n_impacts(1) > 0 .and. pts(2)%n_impacts(1) > 0)
      call check_close('reduced tube: sweep point = the transient run with that clearance ' &
         // '(normal work rate)', pts(1)%normal_work_rate(1), res%normal_work_rate(1), &
         rtol=1.0e-12_dp)
      call check_close('reduced tube: sweep point = the transient run (friction work rate)', &
         pts(1)%friction_work_rate(1), res%friction_work_rate(1), rtol=1.0e-12_dp)
      call check('reduced tube: the clearance changes the work rate', &
         abs(pts(1)%normal_work_rate(1) - pts(2)%normal_work_rate(1)) > 1.0e-3_dp &
         * pts(2)%normal_work_rate(1))
      call sweep_job(base // '_part', 1, 2, 0.0_dp, complete)
      call sweep_job(base // '_part', 2, 2, 0.0_dp, complete)
      call merge_sweep(base // '_merged', [character(len=64) :: base // '_part.shard_2_of_2.h5', &
         base // '_part.shard_1_of_2.h5'], .false., err)
      call check('reduced tube: two shards merge', .not. allocated(err))
      call check('reduced tube: the merged shards equal the single-process sweep', &
                 same_points(base // '_merged.h5', pts))
      call sweep_job(base // '_resume', 1, 1, 1.0e-9_dp, complete)
      call check('reduced tube: a time limit stops the sweep, its checkpoint kept', &
                 .not. complete .and. file_exists(base // '_resume.checkpoint'))
      call sweep_job(base // '_resume', 1, 1, 0.0_dp, complete)
      call check('reduced tube: the resumed sweep equals the uninterrupted one', complete .and. &
                 same_points(base // '_resume.h5', pts))
      call remove_file(base // '.h5')
      call remove_file(base // '_merged.h5')
      call remove_file(base // '_part.shard_1_of_2.h5')
      call remove_file(base // '_part.shard_2_of_2.h5')
      call remove_file(base // '_resume.h5')
   end subroutine sweep_of_reduced_tube

   !> Run the reduced-tube sweep through the job driver (shard i of n, time limit).
   subroutine sweep_job(prefix, shard, n_shards, limit, complete)
      character(len=*), intent(in) :: prefix
      integer, intent(in) :: shard, n_shards
      real(dp), intent(in) :: limit
      logical, intent(out) :: complete
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      integer :: n_failed
      character(len=160) :: ov(5)
      ! element by element: gfortran 12 overruns a typed constructor of concatenations here
      ov(1) = "&job analysis = 'sweep', output = '" // prefix // "' /"
      ov(2) = '&solver tolerance = 1.0e-4, transient_periods = 2, record_periods = 3 /'
      ov(3) = '&diagnostics settle_windows = 0, certify = .false. /'
      ov(4) = "&sweep frequency_hz = 40.0, y_variable = '&stops gap(1)', y_values = 0.15e-3, " &
         // '0.25e-3, progress = .false., chunk = 1 /'
      ov(5) = '&output write_text = .false. /'
      call read_deck(cantilever, ov, deck, err)
      complete = .false.
      if (.not. allocated(err)) then
         deck%reduction%kind = 'modal'
         deck%reduction%n_modes = 3
         call run_sweep_job(deck, batch_options_t(shard_index=shard, shard_count=n_shards, &
                            time_limit_s=limit, quiet=.true.), complete, n_failed, err)
      end if
      if (allocated(err)) call check('reduced tube sweep ' // prefix // ' runs', .false., &
                                     err%message)
   end subroutine sweep_job

   !> The points of a sweep file equal `want` (label, impacts, work rates).
   logical function same_points(path, want)
      character(len=*), intent(in) :: path
      type(point_result_t), intent(in) :: want(:)
      type(sweep_file_t) :: sf
      type(point_result_t), allocatable :: got(:)
      type(error_t), allocatable :: err
      integer :: k
      same_points = .false.
      call read_sweep(path, sf, got, err)
      if (allocated(err)) return
      if (size(got) /= size(want)) return
      same_points = all([(all(got(k)%n_impacts == want(k)%n_impacts) .and. &
         all(got(k)%normal_work_rate == want(k)%normal_work_rate) .and. &
         all(got(k)%friction_work_rate == want(k)%friction_work_rate) .and. &
         got(k)%label == want(k)%label, k = 1, size(want))])
   end function same_points

   !> kind = 'auto' on the shipped tube deck: the cut-off is the rule's (4 x the contact
   !> frequency at tolerance 1e-4, 4 x 10^0.6 x it at 1e-5), the contact frequency is the
   !> Rayleigh quotient of the static shape under a force at a baffle; every point of a sweep
   !> keeps the deck's modes. The convergence check on the rattling tube: its richer run is the
   !> deck run with the richer cut-off over the same periods.
   subroutine auto_rule()
      type(deck_t) :: deck
      type(model_t) :: model, full, mr
      type(reduction_info_t) :: info, info5
      type(transient_result_t) :: res, rr
      type(reduction_check_t) :: chk
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), psi(:), kf(:, :), b(:, :)
      real(dp) :: ks, ms, fc
      integer :: j, info_l, r, d
      logical :: ok
      call read_deck(tube, [character(len=1) ::], deck, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err, info)
      call check('the shipped tube deck asks for the reduction by the rule and builds', &
                 .not. allocated(err) .and. deck%reduction%kind == 'auto')
      if (allocated(err)) return
      call note("tube deck, kind = 'auto': cut-off " // str(info%cutoff_hz) // ' Hz, contact ' &
         // 'frequency ' // str(info%contact_hz) // ' Hz, ' // str(info%modes_per_plane) &
         // ' modes + ' // str(info%n_static) // ' static modes per plane, ' &
         // str(info%n_reduced) // ' coordinates of ' // str(info%n_full))
      ! the contact frequency of every ring dof from the full model, independently
      call build_full_model(deck%structure, deck%stops, deck%damping, deck%forcing, full, err)
      if (allocated(err)) return
      fc = 0.0_dp
      do r = 1, full%n_rings
         do d = 1, 2
            j = full%r_dof(d, r)
            kf = full%sys%k
            allocate(b(full%n, 1), source=0.0_dp)
            b(j, 1) = 1.0_dp
            call dpotrf('U', full%n, kf, full%n, info_l)
            call dpotrs('U', full%n, 1, kf, full%n, b, full%n, info_l)
            psi = b(:, 1)
            deallocate(b)
            ks = 1.0_dp / psi(j)
            ms = dot_product(psi, matmul(full%sys%m, psi)) / psi(j)**2
            fc = max(fc, sqrt((ks + max(full%r_k(r), full%r_kt(r))) / ms) / (2.0_dp * pi))
         end do
      end do
      call check_close('the contact frequency is the stiffest support''s Rayleigh quotient', &
                       info%contact_hz, fc, rtol=1.0e-10_dp)
      call check_close('cut-off = 4 x the contact frequency at tolerance 1e-4', info%cutoff_hz, &
                       4.0_dp * fc, rtol=1.0e-12_dp)
      call check('the basis keeps every mode up to the cut-off and none above', &
                 info%highest_mode_hz <= info%cutoff_hz .and. info%modes_per_plane > 0)
      deck%solver%tolerance = 1.0e-5_dp
      call build_model(deck, mr, u0, v0, err, info5)
      if (allocated(err)) return
      call check_close('at tolerance 1e-5 the cut-off is 10^0.6 x larger', info5%cutoff_hz, &
                       10.0_dp**0.6_dp * info%cutoff_hz, rtol=1.0e-12_dp)
      ! the convergence check of the rattling tube
      call read_deck(cantilever, [character(len=90) :: &
         '&solver tolerance = 1.0e-5, transient_periods = 2, record_periods = 4 /'], deck, err)
      if (allocated(err)) return
      deck%reduction%kind = 'auto'
      call build_model(deck, model, u0, v0, err, info)
      if (.not. allocated(err)) call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      if (.not. allocated(err)) call check_reduction(deck, info, model, res, 2, chk, err)
      call check('the convergence check runs', .not. allocated(err))
      if (allocated(err)) then
         call note(err%message);  return
      end if
      call check('below 1e-4 the rule keeps more modes (rattling tube at 1e-5: every mode), ' &
                 // 'and the check says there is nothing richer', chk%complete .and. &
                 info%modes_per_plane == info%modes_available)
      ! at 1e-4 the rule keeps 3 of the 8 modes per plane: a richer run is compared
      deck%solver%tolerance = 1.0e-4_dp
      call build_model(deck, model, u0, v0, err, info)
      if (.not. allocated(err)) call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      if (.not. allocated(err)) call check_reduction(deck, info, model, res, 2, chk, err)
      call check('the convergence check runs at 1e-4', .not. allocated(err))
      if (allocated(err)) return
      call run_reduced(cantilever, [character(len=90) :: &
         '&solver tolerance = 1.0e-4, transient_periods = 2, record_periods = 4 /'], 'modal', &
         0.0_dp, chk%modes_richer, mr, rr, ok)
      if (.not. ok) return
      call note(check_lines(chk, .false.))
      call check('the check runs a richer basis (more modes per plane)', &
                 chk%modes_richer > chk%modes .and. chk%n_richer == mr%n)
      call check_close('the check''s richer run is the deck run with that basis over the same ' &
         // 'periods', chk%wn_richer(1), rr%normal_work_rate(1), rtol=1.0e-12_dp)
      call check_close('the check''s own run is the run checked', chk%wn(1), &
                       res%normal_work_rate(1), rtol=0.0_dp)
   end subroutine auto_rule

   subroutine run(overrides, model, res)
      character(len=*), intent(in) :: overrides(:)
      type(model_t), intent(out) :: model
      type(transient_result_t), intent(out) :: res
      type(error_t), allocatable :: err
      call run_deck(ref, overrides, model, res, err)
      if (allocated(err)) then
         call check('run succeeds', .false., err%message)
         call finish('test_reduction')
      end if
   end subroutine run

   !> Displacement of dof i under a unit force at dof i: (K^-1)_ii.
   real(dp) function static_response(p, i)
      type(model_t), intent(in) :: p
      integer, intent(in) :: i
      real(dp), allocatable :: k(:, :), b(:)
      integer :: info
      k = p%sys%k
      allocate(b(p%n), source=0.0_dp)
      b(i) = 1.0_dp
      call dpotrf('U', p%n, k, p%n, info)
      call dpotrs('U', p%n, 1, k, p%n, b, p%n, info)
      static_response = b(i)
   end function static_response
end program test_reduction
