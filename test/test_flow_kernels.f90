!> The kernels of the flow excitation, each against a closed form or an independent
!> computation: the FFT against the direct sum; the counter-based random numbers (reproducible,
!> uniform, normal); the quintic Hermite record interpolation (exact on quintics, its error
!> bound on a harmonic); the turbulence spectrum (log-log table, reduced form); the nodal
!> coherence matrix against double integrals of a linear shape (any correlation length, fully
!> correlated, white limit); its factor; the record (variance, reproducibility, interpolation
!> against the harmonic sum, the two storage forms); Connors' velocities, effective velocities
!> and the fluid-elastic damping matrix; the wear scar volumes against a polar quadrature of
!> each geometry and their inverse; Student t quantiles and Welch's PSD.
program test_flow_kernels
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_fft, only: fft, next_power_of_two
   use gapbeam_random, only: stream_key, uniform_at, normal_at
   use gapbeam_random_load, only: random_load_t, add_random_load, random_signals_at, &
      quintic_weights
   use gapbeam_description, only: structure_t, turbulence_t, flow_t
   use gapbeam_model, only: system_t
   use gapbeam_assembly, only: assemble
   use gapbeam_turbulence, only: turbulence_psd, spectrum_band, nodal_coherence, load_shapes, &
      generate_record, gauss_legendre
   use gapbeam_fluid_elastic, only: connors_velocity, fluid_elastic_ratio, velocity_ratio, &
      flow_modes, fluid_elastic_damping
   use gapbeam_flow_results, only: flow_modes_t
   use gapbeam_wear_geometry, only: segment_area, flat_bar_volume, drilled_hole_volume, &
      scar_depth, scar_volume
   use gapbeam_draw_statistics, only: student_t_quantile, mean_half_width, welch_psd
   implicit none

   call fft_checks()
   call random_checks()
   call interpolation_checks()
   call spectrum_checks()
   call coherence_checks()
   call record_checks()
   call fluid_elastic_checks()
   call wear_geometry_checks()
   call statistics_checks()
   call finish('test_flow_kernels')

contains

   !> A uniform beam of n elements, 1 m, pinned at the root, the tip as given (pinned-free: a
   !> linear w = x is exact in its elements).
   function beam_system(n, planes, tip) result(sys)
      integer, intent(in) :: n, planes
      character(len=*), intent(in) :: tip

      type(system_t) :: sys
      type(structure_t) :: st
      st%beam%length = 1.0_dp;  st%beam%n_elem = n
      st%beam%youngs_modulus = 200.0e9_dp;  st%beam%density = 7850.0_dp
      st%beam%area = 1.0e-4_dp;  st%beam%second_moment = 1.0e-9_dp
      st%beam%fibre_distance = 0.01_dp;  st%beam%planes = planes
      st%beam%mass_matrix = 'consistent'
      st%root%condition = 'pinned';  st%tip%condition = tip
      allocate(st%springs(0), st%masses(0))
      call assemble(st, sys)
   end function beam_system

   subroutine fft_checks()
      complex(dp) :: x(16), y(16), d(16)
      integer :: j, k
      do j = 1, 16
         x(j) = cmplx(sin(1.3_dp * j) + 0.1_dp * j, cos(0.7_dp * j * j), dp)
      end do
      do k = 0, 15
         d(k + 1) = sum([(x(j + 1) * exp(cmplx(0.0_dp, -2.0_dp * pi * j * k / 16.0_dp, dp)), &
                          j = 0, 15)])
      end do
      y = x
      call fft(y, -1)
      call check_le('fft: forward transform equals the direct sum (16 points)', &
                    maxval(abs(y - d)) / maxval(abs(d)), 1.0e-13_dp)
      call fft(y, +1)
      call check_le('fft: backward after forward gives n x', maxval(abs(y / 16.0_dp - x)), &
                    1.0e-14_dp)
      call check('next_power_of_two(1000) = 1024, (1024) = 1024', &
                 next_power_of_two(1000) == 1024 .and. next_power_of_two(1024) == 1024)
   end subroutine fft_checks

   subroutine random_checks()
      integer(int64) :: key, i
      real(dp) :: u(200000), z(200000), m, v
      key = stream_key(7, 3, 11)
      u = [(uniform_at(key, i), i = 1, 200000)]
      call check('random: the same key gives the same numbers', &
                 all(u(1:100) == [(uniform_at(stream_key(7, 3, 11), i), i = 1, 100)]))
      call check('random: another draw gives other numbers', &
                 all(u(1:100) /= [(uniform_at(stream_key(7, 4, 11), i), i = 1, 100)]))
      call check('random: uniform numbers in [0, 1)', all(u >= 0.0_dp .and. u < 1.0_dp))
      ! mean 1/2 and variance 1/12 within 5 standard errors
      call check_close('random: uniform mean', sum(u) / size(u), 0.5_dp, &
                       atol=5.0_dp * sqrt(1.0_dp / 12.0_dp / size(u)))
      z = [(normal_at(key, i), i = 1, 200000)]
      m = sum(z) / size(z);  v = sum((z - m)**2) / (size(z) - 1)
      call check_close('random: normal mean 0', m, 0.0_dp, atol=5.0_dp / sqrt(real(size(z), dp)))
      call check_close('random: normal variance 1', v, 1.0_dp, &
                       atol=5.0_dp * sqrt(2.0_dp / size(z)))
      call check_close('random: normal fourth moment 3', sum(z**4) / size(z), 3.0_dp, &
                       atol=5.0_dp * sqrt(96.0_dp / size(z)))
   end subroutine random_checks

   subroutine interpolation_checks()
      real(dp) :: w(6), s, h, got, want, err, omega
      integer :: k
      ! a quintic p(t) on [0, h] from its values and derivatives at the ends
      h = 0.3_dp;  err = 0.0_dp
      do k = 0, 10
         s = k / 10.0_dp
         w = quintic_weights(s, h)
         got = w(1) * p(0.0_dp, 0) + w(2) * p(0.0_dp, 1) + w(3) * p(0.0_dp, 2) &
               + w(4) * p(h, 0) + w(5) * p(h, 1) + w(6) * p(h, 2)
         err = max(err, abs(got - p(s * h, 0)))
      end do
      call check_le('quintic Hermite: exact on a quintic', err, 1.0e-14_dp)
      ! a harmonic at 6 points per cycle: at most (omega h)^6 / 46080 at mid-interval
      omega = 2.0_dp * pi;  h = 1.0_dp / 6.0_dp
      w = quintic_weights(0.5_dp, h)
      got = w(1) * sin(0.1_dp) + w(2) * omega * cos(0.1_dp) - w(3) * omega**2 * sin(0.1_dp) &
            + w(4) * sin(0.1_dp + omega * h) + w(5) * omega * cos(0.1_dp + omega * h) &
            - w(6) * omega**2 * sin(0.1_dp + omega * h)
      want = sin(0.1_dp + 0.5_dp * omega * h)
      call check_le('quintic Hermite: harmonic error within (omega h)^6/46080 [' &
                    // str(abs(got - want)) // ']', abs(got - want), (omega * h)**6 / 46080.0_dp)
   end subroutine interpolation_checks

   pure real(dp) function p(t, d)
      real(dp), intent(in) :: t
      integer, intent(in) :: d
      select case (d)
      case (0)
         p = 1.0_dp - 2.0_dp * t + 0.5_dp * t**2 + 3.0_dp * t**3 - t**4 + 0.7_dp * t**5
      case (1)
         p = -2.0_dp + t + 9.0_dp * t**2 - 4.0_dp * t**3 + 3.5_dp * t**4
      case default
         p = 1.0_dp + 18.0_dp * t - 12.0_dp * t**2 + 14.0_dp * t**3
      end select
   end function p

   subroutine spectrum_checks()
      type(turbulence_t) :: tb
      type(flow_t) :: fl
      real(dp) :: lo, hi
      tb%spectrum = 'table'
      tb%psd_frequency_hz = [1.0_dp, 10.0_dp, 100.0_dp]
      tb%psd = [1.0e-2_dp, 1.0e-3_dp, 1.0e-6_dp]
      call check_close('psd table: at a point', turbulence_psd(tb, fl, 10.0_dp), 1.0e-3_dp, &
                       rtol=1.0e-14_dp)
      ! straight in log-log: f^-1 between 1 and 10 Hz, f^-3 between 10 and 100 Hz
      call check_close('psd table: log-log between points (f^-1)', &
                       turbulence_psd(tb, fl, 3.0_dp), 1.0e-2_dp / 3.0_dp, rtol=1.0e-13_dp)
      call check_close('psd table: log-log between points (f^-3)', &
                       turbulence_psd(tb, fl, 20.0_dp), 1.0e-3_dp / 8.0_dp, rtol=1.0e-13_dp)
      call check('psd table: zero outside the table', turbulence_psd(tb, fl, 0.5_dp) == 0.0_dp &
                 .and. turbulence_psd(tb, fl, 101.0_dp) == 0.0_dp)
      tb%cutoff_hz = 50.0_dp
      call spectrum_band(tb, fl, lo, hi)
      call check('psd table: band from the first point to the cut-off', lo == 1.0_dp .and. &
                 hi == 50.0_dp)
      ! reduced form: S = (rho U^2 D / 2)^2 (D / U) Phi(f D / U); Phi(0.1) = 1e-4 (slope -1)
      tb%spectrum = 'reduced';  tb%cutoff_hz = 0.0_dp
      tb%reduced_frequency = [0.01_dp, 1.0_dp];  tb%reduced_psd = [1.0e-3_dp, 1.0e-5_dp]
      fl%velocity = 2.0_dp;  fl%fluid_density = 1000.0_dp;  fl%tube_diameter = 0.02_dp
      call check_close('psd reduced: (rho U^2 D/2)^2 (D/U) Phi(fD/U)', &
                       turbulence_psd(tb, fl, 10.0_dp), (0.5_dp * 1000.0_dp * 4.0_dp * 0.02_dp)**2 &
                       * 0.01_dp * 1.0e-4_dp, rtol=1.0e-12_dp)
      call spectrum_band(tb, fl, lo, hi)
      call check_close('psd reduced: band top = last reduced frequency x U/D', hi, 100.0_dp, &
                       rtol=1.0e-14_dp)
   end subroutine spectrum_checks

   !> int_0^L int_0^L x y exp(-|x - y| / lambda) dx dy = 2 int_0^L exp(-s/lambda) C(s) ds,
   !> C(s) = (L - s)^3 / 3 + s (L - s)^2 / 2, by 200-point composite Gauss.
   real(dp) function linear_double_integral(len, lambda) result(r)
      real(dp), intent(in) :: len, lambda
      real(dp) :: xg(10), wg(10), s, a, b
      integer :: i, q
      call gauss_legendre(10, xg, wg)
      r = 0.0_dp
      do i = 1, 200
         a = len * (i - 1) / 200.0_dp;  b = len * i / 200.0_dp
         do q = 1, 10
            s = a + xg(q) * (b - a)
            r = r + wg(q) * (b - a) * 2.0_dp * exp(-s / lambda) &
                * ((len - s)**3 / 3.0_dp + s * (len - s)**2 / 2.0_dp)
         end do
      end do
   end function linear_double_integral

   subroutine coherence_checks()
      type(system_t) :: sys
      type(turbulence_t) :: tb
      real(dp), allocatable :: g(:, :), u(:), sh(:, :)
      integer, allocatable :: pl(:), rk(:)
      type(error_t), allocatable :: err
      integer :: i
      real(dp) :: lam
      real(dp), parameter :: lams(3) = [0.05_dp, 0.3_dp, 3.0_dp]
      sys = beam_system(8, 1, 'free')
      ! u: w = x, theta = 1 (exact in the Hermite elements)
      allocate(u(sys%n_dof), source=0.0_dp)
      do i = 1, sys%n_node
         if (sys%dof_of(1, i) > 0) u(sys%dof_of(1, i)) = sys%element_length * (i - 1)
         if (sys%dof_of(2, i) > 0) u(sys%dof_of(2, i)) = 1.0_dp
      end do
      do i = 1, 3
         lam = lams(i)
         call nodal_coherence(sys, 1, 0.0_dp, 1.0_dp, lam, g)
         call check_close('coherence: u''G u of w = x, lambda = ' // str(lam), &
                          dot_product(u, matmul(g, u)), linear_double_integral(1.0_dp, lam), &
                          rtol=1.0e-10_dp)
      end do
      call nodal_coherence(sys, 1, 0.0_dp, 1.0_dp, 0.0_dp, g)
      call check_close('coherence: fully correlated u''G u = (int x dx)^2', &
                       dot_product(u, matmul(g, u)), 0.25_dp, rtol=1.0e-13_dp)
      ! white limit: 2 lambda int x^2 dx
      call nodal_coherence(sys, 1, 0.0_dp, 1.0_dp, 1.0e-5_dp, g)
      call check_close('coherence: white limit 2 lambda int x^2 dx', &
                       dot_product(u, matmul(g, u)), 2.0e-5_dp / 3.0_dp, rtol=1.0e-13_dp)
      ! a part of the length: fully correlated int_0.2^0.7 x dx
      call nodal_coherence(sys, 1, 0.2_dp, 0.7_dp, 0.0_dp, g)
      call check_close('coherence: partial length [0.2, 0.7], fully correlated', &
                       dot_product(u, matmul(g, u)), (0.5_dp * (0.49_dp - 0.04_dp))**2, &
                       rtol=1.0e-13_dp)
      ! the factor: shapes shapes' = G, rank 1 when fully correlated
      tb%correlation_length = 0.1_dp;  tb%planes = 'w'
      call load_shapes(sys, tb, sh, pl, rk, err)
      call nodal_coherence(sys, 1, 0.0_dp, 1.0_dp, 0.1_dp, g)
      call check('load shapes: built', .not. allocated(err))
      call check_le('load shapes: L L'' = G', maxval(abs(matmul(sh, transpose(sh)) - g)) &
                    / maxval(abs(g)), 1.0e-9_dp)
      tb%correlation_length = 0.0_dp
      call load_shapes(sys, tb, sh, pl, rk, err)
      call check('load shapes: one component when fully correlated', size(sh, 2) == 1)
      sys = beam_system(8, 2, 'free')
      tb%planes = 'both'
      call load_shapes(sys, tb, sh, pl, rk, err)
      call check('load shapes: two planes, one component each, numbered per plane', &
                 size(sh, 2) == 2 .and. all(pl == [1, 2]) .and. all(rk == [1, 1]))
   end subroutine coherence_checks

   subroutine record_checks()
      type(random_load_t) :: rl, r2, rc
      real(dp), allocatable :: s(:), x(:), p1(:), p2(:), map(:, :)
      real(dp) :: df, var, err, t, amp, direct, bound
      integer :: k, nk, j, klo
      integer(int64) :: key
      type(error_t), allocatable :: e
      df = 0.5_dp;  klo = 2;  nk = 40          ! 1 .. 20.5 Hz
      allocate(s(nk))
      s = [(1.0_dp / (1.0_dp + (0.5_dp * (k + klo - 1))**2), k = 1, nk)]
      allocate(map(1, 1), source=1.0_dp)
      call generate_record(map, [5], s, klo, df, 6, 3, 1, rl, e)
      var = sum(rl%x(1, 1, :)**2) / rl%n_grid
      call check_close('record: variance over one period = sum S_k df', var, sum(s) * df, &
                       rtol=1.0e-12_dp)
      call check('record: the grid has >= 6 points per cycle at the top harmonic', &
                 rl%h <= 1.0_dp / (6.0_dp * rl%cutoff_hz) .and. rl%cutoff_hz == 20.5_dp)
      ! between the grid points against the harmonic sum itself
      key = stream_key(3, 1, 5)
      err = 0.0_dp;  amp = 0.0_dp;  bound = 0.0_dp
      allocate(x(1))
      do j = 1, 50
         t = 0.0137_dp * j * j
         call random_signals_at(rl, t, x)
         direct = 0.0_dp
         do k = 1, nk
            direct = direct + sqrt(2.0_dp * s(k) * df) * cos(2.0_dp * pi * (k + klo - 1) * df &
                     * t + 2.0_dp * pi * uniform_at(key, int(k + klo - 1, int64)))
         end do
         err = max(err, abs(x(1) - direct))
      end do
      do k = 1, nk
         bound = bound + sqrt(2.0_dp * s(k) * df) * (2.0_dp * pi * (k + klo - 1) * df &
                 * rl%h)**6 / 46080.0_dp
      end do
      call check_le('record: interpolation against the harmonic sum within its bound', err, &
                    bound)
      call generate_record(map, [5], s, klo, df, 6, 3, 1, r2, e)
      call check('record: the same key gives the same record', all(r2%x == rl%x))
      call generate_record(map, [5], s, klo, df, 6, 3, 2, r2, e)
      call check('record: another draw gives another record', any(r2%x /= rl%x))
      ! two storage forms: 3 components on 2 dofs (combined) against 3 components kept
      deallocate(map)
      map = reshape([1.0_dp, 0.5_dp, -2.0_dp, 0.3_dp, 0.7_dp, 1.5_dp], [2, 3])
      call generate_record(map, [1, 2, 3], s, klo, df, 6, 9, 4, rc, e)
      call check('record: more components than dofs are combined on the dofs', &
                 rc%n_signals == 2 .and. .not. allocated(rc%map))
      call generate_record(reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, &
                           0.0_dp, 1.0_dp], [3, 3]), [1, 2, 3], s, klo, df, 6, 9, 4, r2, &
                           e)
      allocate(p1(2), p2(3))
      err = 0.0_dp
      do j = 1, 20
         t = 0.173_dp * j
         p1 = 0.0_dp;  p2 = 0.0_dp
         call add_random_load(rc, t, p1)
         call add_random_load(r2, t, p2)
         err = max(err, maxval(abs(p1 - matmul(map, p2))))
      end do
      call check_le('record: combined form = map x components', err, &
                    1.0e-12_dp * sqrt(sum(s) * df))
   end subroutine record_checks

   subroutine fluid_elastic_checks()
      type(system_t) :: sys
      type(flow_t) :: fl
      type(flow_modes_t) :: fm
      type(error_t), allocatable :: err
      real(dp), allocatable :: c(:, :), d(:, :)
      real(dp) :: m, uc, zs, beta, gamma
      integer :: j
      sys = beam_system(20, 2, 'pinned')
      m = 7850.0_dp * 1.0e-4_dp
      fl%velocity = 1.0_dp;  fl%fluid_density = 1000.0_dp;  fl%tube_diameter = 0.02_dp
      fl%connors_constant = 3.0_dp
      beta = 0.5_dp;  gamma = 1.0e-5_dp
      call flow_modes(sys, fl, m, beta, gamma, fm, err)
      call check('flow modes: solved', .not. allocated(err))
      call check('flow modes: every mode of both planes, ascending', fm%n_modes == sys%n_dof &
                 .and. all(fm%frequency_hz(2:) >= fm%frequency_hz(:fm%n_modes - 1)))
      call check_close('flow modes: f1 of a pinned-pinned beam', fm%frequency_hz(1), &
                       pi / 2.0_dp * sqrt(200.0e9_dp * 1.0e-9_dp / m), rtol=1.0e-6_dp)
      call check('flow modes: planes paired', fm%plane(1) == 1 .and. fm%plane(2) == 2)
      zs = beta / (4.0_dp * pi * fm%frequency_hz(1)) + gamma * pi * fm%frequency_hz(1)
      uc = 3.0_dp * fm%frequency_hz(1) * 0.02_dp * sqrt(m * 2.0_dp * pi * zs &
           / (1000.0_dp * 0.02_dp**2))
      call check_close('flow modes: critical velocity of mode 1 = Connors', &
                       fm%critical_velocity(1), uc, rtol=1.0e-10_dp)
      call check_close('connors_velocity', connors_velocity(3.0_dp, 10.0_dp, 0.02_dp, 1.0_dp, &
                       0.1_dp, 1000.0_dp), 3.0_dp * 10.0_dp * 0.02_dp * sqrt(0.1_dp / 0.4_dp), &
                       rtol=1.0e-14_dp)
      call check_close('fluid-elastic ratio cancels the structural one at U_c', &
                       fluid_elastic_ratio(1000.0_dp, uc, 3.0_dp, fm%frequency_hz(1), m), -zs, &
                       rtol=1.0e-12_dp)
      ! a damping per mode: Phi' C Phi = diag(2 zeta_fe omega)
      c = fluid_elastic_damping(sys, fm)
      d = matmul(transpose(fm%shapes), matmul(c, fm%shapes))
      call check_le('fluid-elastic damping: diagonal in the modes', &
                    maxval(abs(d - diag(2.0_dp * fm%fluid_ratio * fm%omega))) &
                    / maxval(abs(d)), 1.0e-10_dp)
      ! half the span in flow: mode 1 (symmetric) weighs half, the whole span 1
      call check_close('effective velocity: whole span', fm%velocity_ratio(1), 1.0_dp, &
                       rtol=1.0e-12_dp)
      fl%region_start = 0.0_dp;  fl%region_end = 0.5_dp
      call check_close('effective velocity: half the span, mode 1 (sin^2 by symmetry)', &
                       velocity_ratio(sys, fl, 1, fm%shapes(:, 1)), 0.5_dp, rtol=1.0e-9_dp)
      ! a linear profile 0 -> 2 over the span: int (2x)^2 sin^2(pi x) dx / int sin^2 =
      ! 4 (1/3 - 1/(2 pi^2))
      fl%region_end = 0.0_dp
      fl%profile_position = [0.0_dp, 1.0_dp];  fl%profile_factor = [0.0_dp, 2.0_dp]
      call check_close('effective velocity: linear profile, mode 1', &
                       velocity_ratio(sys, fl, 1, fm%shapes(:, 1)), &
                       4.0_dp * (1.0_dp / 3.0_dp - 0.5_dp / pi**2), rtol=2.0e-6_dp)
      ! only w: the v modes get no fluid-elastic force
      deallocate(fl%profile_position, fl%profile_factor)
      fl%planes = 'w'
      call flow_modes(sys, fl, m, beta, gamma, fm, err)
      call check('fluid-elastic in w only: the v modes untouched', &
                 all(pack(fm%fluid_ratio, fm%plane == 2) == 0.0_dp) .and. &
                 all(pack(fm%fluid_ratio, fm%plane == 1) < 0.0_dp))
      j = 0
   end subroutine fluid_elastic_checks

   pure function diag(x) result(a)
      real(dp), intent(in) :: x(:)
      real(dp) :: a(size(x), size(x))
      integer :: i
      a = 0.0_dp
      do i = 1, size(x)
         a(i, i) = x(i)
      end do
   end function diag

   !> Area of the tube disc (radius r) beyond the removed boundary, in polar coordinates about
   !> the tube centre: (1/2) int max(0, r^2 - rho(theta)^2) dtheta over the angles where the
   !> boundary rho(theta) is inside the tube; rho the flat bar's plane at r - h, or the hole's
   !> circle (radius rh, its centre d = rh - r + h away). Composite Gauss, 400 x 10 points.
   real(dp) function polar_area(geometry, h, r, rh) result(a)
      character(len=*), intent(in) :: geometry
      real(dp), intent(in) :: h, r, rh
      real(dp) :: xg(10), wg(10), th, lo, hi, tc, rho, d
      integer :: i, q
      call gauss_legendre(10, xg, wg)
      ! the half angle where the boundary meets the tube's circle
      if (geometry == 'flat_bar') then
         tc = acos((r - h) / r)
      else
         d = rh - r + h
         ! rho(theta) = r: r^2 + 2 d r cos(theta) + d^2 = rh^2
         tc = acos(max(-1.0_dp, min(1.0_dp, (rh**2 - r**2 - d**2) / (2.0_dp * d * r))))
      end if
      a = 0.0_dp
      do i = 1, 400
         lo = -tc + 2.0_dp * tc * (i - 1) / 400.0_dp;  hi = -tc + 2.0_dp * tc * i / 400.0_dp
         do q = 1, 10
            th = lo + xg(q) * (hi - lo)
            if (geometry == 'flat_bar') then
               rho = (r - h) / cos(th)
            else
               rho = -d * cos(th) + sqrt(rh**2 - (d * sin(th))**2)
            end if
            a = a + 0.5_dp * wg(q) * (hi - lo) * max(0.0_dp, r**2 - rho**2)
         end do
      end do
   end function polar_area

   subroutine wear_geometry_checks()
      real(dp), parameter :: r = 9.525e-3_dp, rh = 9.9e-3_dp, b = 25.0e-3_dp, t = 30.0e-3_dp
      real(dp) :: h, e_flat, e_hole, e_small, v
      real(dp), parameter :: depths(6) = [1.0e-6_dp, 1.0e-5_dp, 1.0e-4_dp, 3.0e-4_dp, &
                                          6.0e-4_dp, 1.1e-3_dp]
      integer :: i
      e_flat = 0.0_dp;  e_hole = 0.0_dp
      do i = 1, 6
         h = depths(i)
         e_flat = max(e_flat, abs(flat_bar_volume(h, r, b) / (b * polar_area('flat_bar', h, r, &
                  rh)) - 1.0_dp))
         e_hole = max(e_hole, abs(drilled_hole_volume(h, r, rh, t) / (t * polar_area( &
                  'drilled_hole', h, r, rh)) - 1.0_dp))
      end do
      call check_le('wear: flat bar volume against the polar quadrature (1 um .. 1.1 mm)', &
                    e_flat, 1.0e-9_dp)
      call check_le('wear: drilled hole volume against the polar quadrature (1 um .. 1.1 mm)', &
                    e_hole, 1.0e-9_dp)
      h = 1.0e-7_dp
      e_small = abs(flat_bar_volume(h, r, b) / (4.0_dp / 3.0_dp * b * sqrt(2.0_dp * r) &
                * h**1.5_dp) - 1.0_dp)
      call check_le('wear: flat bar, small depth (4/3) b (2R)^(1/2) h^(3/2)', e_small, 1.0e-5_dp)
      call check_close('wear: segment of the whole disc', segment_area(r, -r), pi * r**2, &
                       rtol=1.0e-14_dp)
      call check('wear: drilled hole volume grows with depth', &
                 drilled_hole_volume(2.0e-4_dp, r, rh, t) > drilled_hole_volume(1.0e-4_dp, r, &
                 rh, t) .and. drilled_hole_volume(1.0e-4_dp, r, rh, t) > 0.0_dp)
      ! the depth is the inverse of the volume
      v = flat_bar_volume(3.3e-4_dp, r, b)
      call check_close('wear: flat bar depth from its volume', scar_depth('flat_bar', v, r, b, &
                       0.0_dp, 0.0_dp, 1.0e-3_dp), 3.3e-4_dp, rtol=1.0e-9_dp)
      v = drilled_hole_volume(4.4e-4_dp, r, rh, t)
      call check_close('wear: drilled hole depth from its volume', scar_depth('drilled_hole', &
                       v, r, 0.0_dp, rh, t, 1.0e-3_dp), 4.4e-4_dp, rtol=1.0e-9_dp)
      call check('wear: a volume beyond the wall gives the wall thickness', &
                 scar_depth('flat_bar', 1.0_dp, r, b, 0.0_dp, 0.0_dp, 1.0e-3_dp) == 1.0e-3_dp)
      call check('wear: no volume, no depth', scar_depth('flat_bar', 0.0_dp, r, b, 0.0_dp, &
                 0.0_dp, 1.0e-3_dp) == 0.0_dp .and. scar_volume('none', 1.0e-4_dp, r, b, rh, t) &
                 == 0.0_dp)
   end subroutine wear_geometry_checks

   subroutine statistics_checks()
      real(dp) :: m, hw, x(4096), dt, var, s
      real(dp), allocatable :: f(:), psd(:)
      integer(int64) :: key, i
      integer :: k
      call check_close('t quantile: 1 degree of freedom', student_t_quantile(0.975_dp, 1), &
                       12.7062047361747_dp, rtol=1.0e-10_dp)
      call check_close('t quantile: 9 degrees of freedom', student_t_quantile(0.975_dp, 9), &
                       2.26215716279820_dp, rtol=1.0e-10_dp)
      call check_close('t quantile: 3 degrees of freedom', student_t_quantile(0.975_dp, 3), &
                       3.18244630528371_dp, rtol=1.0e-10_dp)
      call check_close('t quantile: 10000 degrees of freedom (normal 1.95996)', &
                       student_t_quantile(0.975_dp, 10000), 1.96020119_dp, rtol=1.0e-7_dp)
      call mean_half_width([1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp], m, hw)
      call check_close('mean and half-width of 1, 2, 3, 4', hw, 3.18244630528371_dp &
                       * sqrt((5.0_dp / 3.0_dp) / 4.0_dp), rtol=1.0e-10_dp)
      call check('mean of 1..4 is 2.5; one draw has no half-width', m == 2.5_dp)
      ! Welch: white noise of variance 1 sampled at 1 kHz has a flat density 2 dt; a sine of
      ! amplitude a adds a^2/2 of variance around its frequency
      dt = 1.0e-3_dp
      key = stream_key(1, 1, 1)
      x = [(normal_at(key, i), i = 1, 4096)]
      call welch_psd(x, dt, 256, f, psd)
      s = sum(psd(1:127)) / 127.0_dp
      call check_close('Welch: white noise density 2 dt (32 averages: 5 %)', s, 2.0_dp * dt, &
                       rtol=0.05_dp)
      x = [(sin(2.0_dp * pi * 125.0_dp * dt * k), k = 1, 4096)]
      call welch_psd(x, dt, 256, f, psd)
      var = sum(psd) * (f(2) - f(1))
      call check_close('Welch: a sine''s density integrates to a^2/2', var, 0.5_dp, &
                       rtol=1.0e-3_dp)
      call check('Welch: the sine''s peak at its frequency', abs(f(maxloc(psd, 1)) - 125.0_dp) &
                 < 1.0e-9_dp)
   end subroutine statistics_checks
end program test_flow_kernels
