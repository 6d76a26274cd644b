!> Exact event-driven integrator of the piecewise-linear gap model: the accuracy reference.
!>
!> Between two switches of the contact configuration (the set of active contacts) the motion
!> obeys a linear system with constant coefficients. In the state x = (u, v) of the dofs that
!> carry mass,
!>
!>    x' = A x + b_s sin(Omega t) + b_0,   A = [0, I; -M^-1 K_e, -M^-1 C_e],
!>
!> with K_e = K + sum_active k_c e_c e_c', C_e = C + sum_active c_c e_c e_c' (contact spring and
!> damper at the contact dof), b_0 = M^-1 sum_active s_c k_c g_c e_c (the gap) and
!> b_s = M^-1 q (A_pp/2) Omega^2. Its solution is known in closed form,
!>
!>    x(t0 + tau) = x_c + Re(X e^{i Omega (t0 + tau)}) + sum_j f_j Re(c_j w_j e^{lambda_j tau}),
!>
!> with x_c = -A^-1 b_0 (static part), X the harmonic particular solution,
!> (K_e - Omega^2 M + i Omega C_e) X_u = -i F, and (lambda_j, w_j) the eigenpairs of A (LAPACK
!> dgeev; one of each complex-conjugate pair is kept, f_j = 2, real eigenvalues f_j = 1). The
!> eigen decomposition, W^-1, x_c and X are computed once per configuration met (built lazily,
!> cached by the bit mask of active contacts); a switch only projects the state on the new basis,
!> c = W^-1 (x - x_c - Re(X e^{i Omega t0})), with one step of iterative refinement. The real
!> part of each complex eigenvalue is replaced by the exact identity of the symmetric quadratic
!> problem, Re(lambda) = -phi^H C_e phi / (2 phi^H M phi) with phi the computed shape: dgeev's
!> own real part is off by ~eps ||A|| (an energy drift of ~1e-13 per second without damping);
!> this one is exactly 0 for an undamped configuration and exact to second order otherwise.
!> The imaginary part (the frequency) comes from the same shape, sqrt(phi^H K_e phi /
!> phi^H M phi - Re(lambda)^2), since dgeev's is off by ~eps ||A|| too (2.6e-10 rad/s on the
!> first mode of the 15-element model, where ||A|| ~ 7.5e10), and each complex shape gets one
!> step of inverse iteration, (K_e + mu C_e + mu^2 M) phi' = M phi, before W^-1 is formed:
!> on the 15-element model this takes the final-state error from 1.6e-9 to 1.3e-11 (against
!> RK4 at T/16384, which converges to 1e-13).
!>
!> **Events.** Every quantity the integrator watches is a linear functional of x, hence a sum of
!> exponentials phi(tau) = Re(sum_j a_j e^{mu_j tau}) + a_0 (the harmonic is the term
!> mu = i Omega). Its derivatives follow by multiplying a_j by mu_j^k, and since Re(mu_j) <= 0
!> the sums sum_j |a_j e^{mu_j tau}| |mu_j|^k bound |phi^(k)| on the whole rest of the segment.
!> The search for the first sign change steps safely: from tau it advances to the first zero of a
!> lower bound of sigma phi (quadratic: phi + phi' s - B2 s^2/2, or cubic: phi + phi' s +
!> phi'' s^2/2 - B3 s^3/6, whichever reaches further), so no root, grazing included, is missed
!> (short of an excursion shorter than the time tolerance); near a transversal root these steps
!> converge quadratically from the safe side, and the root is bracketed to time_tol * T (1e-14 of
!> the forcing period), then bisected if needed. A contact c with penetration d = s_c u_i - g_c
!> is active while d > 0 and, for a damped stop, k d + c d' > 0 (the damper never pulls): the
!> watched functions are d and, with a damper, k d + c d'. At a sign change the activity of all
!> contacts is decided from the sign just after the instant: the first of d, d', d'', d''' (and
!> of k d + c d' and its derivatives) that is not zero to round-off, the derivatives taken from
!> the state through the equations of motion (free of the cancellations of the modal sums, and
!> the same before and after the switch). A change of activity ends the segment, otherwise the
!> search goes on. A new segment re-decides at its first instant (at most 4 switches at one
!> instant, then the configuration is kept); a watched function that starts within round-off
!> of zero on the wrong side gets a dead band of that size until it is clear of zero. This is
!> how a contact that starts exactly at zero gap from rest (d = d' = d'' = 0, d''' > 0) closes.
!> Terms that have decayed below 1e-17 of every functional are dropped from the search.
!>
!> **Statistics.** Over each contact phase in the record the integrals of f, f^2 and f |d'| are
!> computed in closed form (products of exponentials; |d'| by splitting the phase at the zeros
!> of d', which are located like events); contact time comes from the event times. The largest
!> force, the root strain and strain-rate extremes are exact extrema over the record (to 1e-13
!> of the function's scale): a running maximum M is certified by the same bounds (the cubic
!> bound of phi under M + tol, or a step on which phi' keeps its sign), which converge onto each
!> local maximum that could exceed M.
!>
!> **Massless dofs** (lumped mass without rotary inertia: zero rows of M). With C = beta M +
!> gamma K, their rows read gamma (K_ss v_s + K_sr v_r) + K_ss u_s + K_sr u_r = 0, i.e.
!> gamma z' + z = 0 for z = K_ss u_s + K_sr u_r. The initial state is put in equilibrium
!> (z(0) = z'(0) = 0, as run_transient does), so z = 0 for all time: u_s = T u_r,
!> T = -K_ss^-1 K_sr, exactly (static condensation), and the remaining rows carry
!> K_r = K_rr + K_rs T, C_r = C_rr + C_rs T = beta M_rr + gamma K_r. Contacts on massless dofs
!> are rejected. The final acceleration of a massless dof is T a_r (the derivative of the
!> constraint).
!>
!> **Defective configurations.** When the eigenvector matrix is ill-conditioned (row-equilibrated
!> condition number above 1e6, e.g. a critically damped mode), the configuration is integrated
!> instead by a Taylor expansion of the matrix exponential of the augmented, balanced system
!> z = (u, v/w_s, a sin, a cos, a), z' = Ahat z, on sub-steps with ||Ahat||_F h <= 1/2 (degree
!> 18, truncation below 1e-22); the same safe-step event search runs on the sub-step polynomials
!> with the bounds |phi^(k)| <= |l| ||Ahat||^k e^{1/2} |z_k|, and the statistics are integrated
!> by 16-point Gauss-Legendre on each sub-step. It is exact to round-off but slow (about
!> 6 ||Ahat||_F sub-steps per second), a safety net for a non-generic case.
!>
!> Time is kept as (forcing periods k, offset r in [0, T)), so the forcing phase Omega r is
!> computed without the loss of precision of Omega t at large t; a segment longer than two
!> periods is re-anchored (projected again, not counted as a segment).
!>
!> Result counters: steps_accepted = linear segments, events = configuration switches,
!> factorizations = configurations built; dt_smallest / dt_largest = shortest / longest
!> segment; steps_rejected and fp_iterations stay 0. The strain and strain-rate ranges are the
!> exact extrema over the record (run_transient samples them at step ends).
!>
!> Accuracy (test/test_exact.f90): 1e-13 against modal superposition without impacts, 1e-14
!> against the SDOF piecewise solution and its statistics, energy to 1e-15 over 260 impacts;
!> the closed form and the Taylor fallback agree to ~1e-12 on the 10.5 Hz attractor.
!>
!> Limits: bilinear stops only (the Hertz law is not piecewise linear: rejected with an error);
!> forcing exactly at an undamped natural frequency of a configuration (no periodic particular
!> solution) is rejected; at most 62 one-sided contacts.
module gapbeam_exact
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_problem, only: problem_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t
   use gapbeam_transient, only: transient_result_t, allocate_result
   use gapbeam_contact, only: law_bilinear, contact_force
   use gapbeam_lapack, only: dgeev, dgesv, dpotrf, dpotrs, zgesv
   use gapbeam_filter, only: lowpass_t, design_lowpass
   implicit none
   private
   public :: run_exact

   real(dp), parameter :: zero_tol = 1.0e-12_dp    ! |phi^(k)| <= zero_tol * scale: zero
   real(dp), parameter :: peak_tol = 1.0e-13_dp    ! extrema: tolerance / scale of the function
   real(dp), parameter :: prune_tol = 1.0e-17_dp   ! a decayed term below this is dropped
   real(dp), parameter :: time_tol = 1.0e-14_dp    ! event bracket / forcing period
   real(dp), parameter :: cond_limit = 1.0e6_dp    ! eigenvector condition: above, Taylor
   integer, parameter :: n_taylor = 18             ! Taylor degree of the fallback
   real(dp), parameter :: inv_k(10) = 1.0_dp / [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp, &
      6.0_dp, 7.0_dp, 8.0_dp, 9.0_dp, 10.0_dp]
   integer, parameter :: n_gauss = 16              ! Gauss-Legendre points of the fallback
   integer, parameter :: max_flips = 4             ! switches allowed at one instant
   integer, parameter :: max_roots = 64            ! zeros of d' kept per contact phase window

   ! outcome of a sweep over a segment
   integer, parameter :: end_switch = 1, end_horizon = 2, end_anchor = 3

   !> The structure condensed to its dofs with mass.
   type :: reduced_t
      integer :: n = 0                         ! all dofs
      integer :: nr = 0                        ! dofs with mass
      integer :: ns = 0                        ! massless dofs
      integer :: nb = 0                        ! watched functionals: slots, strain, tip
      integer :: n_slots = 0                   ! distinct contact dofs
      integer :: b_strain = 0                  ! functional index of the root strain
      integer :: b_tip = 0                     ! functional index of the tip displacement
      integer, allocatable :: ir(:), is(:)     ! global indices of the two groups
      integer, allocatable :: cpos(:)          ! reduced index of each contact's dof
      integer, allocatable :: cslot(:)         ! functional of each contact (its slot)
      real(dp), allocatable :: t(:, :)         ! (ns, nr) u_s = T u_r
      real(dp), allocatable :: mr(:, :)        ! M_rr
      real(dp), allocatable :: mfac(:, :)      ! Cholesky factor of M_rr
      real(dp), allocatable :: kr(:, :)        ! condensed stiffness
      real(dp), allocatable :: cr(:, :)        ! condensed damping
      real(dp), allocatable :: qr(:)           ! load shape
      real(dp), allocatable :: ell(:, :)       ! (nr, nb) functional rows on u_r
   end type reduced_t

   !> One contact configuration, closed form (modal) or Taylor fallback.
   type :: config_t
      integer(int64) :: mask = 0                    ! active contacts (bit c-1)
      logical :: modal = .true.                     ! eigen decomposition usable
      real(dp) :: cond = 0.0_dp                     ! condition of the eigenvector matrix
      integer :: p = 0                              ! kept eigenvalues (one per pair)
      complex(dp), allocatable :: mu(:)             ! (p) eigenvalues
      real(dp), allocatable :: fac(:)               ! (p) 1 (real) or 2 (pair)
      complex(dp), allocatable :: wh(:, :)          ! (2 nr, p) eigenvectors
      complex(dp), allocatable :: winv(:, :)        ! (p, 2 nr) rows of W^-1
      complex(dp), allocatable :: lrow(:, :)        ! (p, nb) functionals of the eigenvectors
      complex(dp), allocatable :: xh(:)             ! (2 nr) harmonic amplitude
      complex(dp), allocatable :: lh(:)             ! (nb) functionals of xh
      real(dp), allocatable :: xc(:)                ! (2 nr) static part
      real(dp), allocatable :: lc(:)                ! (nb) functionals of xc
      real(dp), allocatable :: amat(:, :)           ! (2 nr, 2 nr) A
      real(dp), allocatable :: absamat(:, :)        ! |A|
      real(dp), allocatable :: bsv(:), b0v(:)       ! (2 nr) forcing and gap vectors
      ! Taylor fallback
      real(dp), allocatable :: ahat(:, :)           ! augmented balanced matrix
      real(dp) :: omega_s = 1.0_dp                  ! velocity scale [1/s]
      real(dp) :: alpha = 1.0_dp                    ! scale of the forcing entries [m]
      real(dp) :: nrm = 0.0_dp                      ! ||Ahat||_F
      real(dp) :: hsub = 0.0_dp                     ! sub-step
   end type config_t

   !> The current linear segment: coefficients of every watched functional.
   type :: segment_t
      integer :: ic = 0                             ! configuration
      logical :: modal = .true.
      integer :: nt = 0                             ! terms (eigenvalues + harmonic)
      complex(dp), allocatable :: mu(:)             ! (nt) exponents
      complex(dp), allocatable :: mp(:, :)          ! (3, nt) mu, mu^2, mu^3
      real(dp), allocatable :: am(:, :)             ! (0:4, nt) |mu|^k
      complex(dp), allocatable :: c(:)              ! (nt) state coefficients (f_j c_j)
      complex(dp), allocatable :: e(:)              ! (nt) e^{mu tau} at the last evaluation
      complex(dp), allocatable :: a(:, :)           ! (nt, nb) functional coefficients
      real(dp), allocatable :: absa(:, :)           ! |a|
      real(dp), allocatable :: a0(:)                ! (nb) constants
      logical, allocatable :: live(:)               ! not pruned
      logical, allocatable :: real_term(:)          ! real exponent
      real(dp), allocatable :: me(:)                ! |e^{mu tau}| at the last evaluation
      integer :: n_eval = 0
      integer :: n_recur = 0                        ! evaluations by recurrence in a row
      real(dp) :: tau_last = 0.0_dp                 ! instant of the last evaluation
      real(dp) :: mu_max = 0.0_dp                   ! largest |mu|
      ! Taylor fallback: current sub-step [tk, tk + hsub]
      real(dp) :: tk = 0.0_dp
      real(dp), allocatable :: pw(:, :)             ! (na, 0:n_taylor) Ahat^m z_k / m!
      real(dp), allocatable :: pc(:, :)             ! (0:n_taylor, nb) functional coefficients
      real(dp), allocatable :: elln(:)              ! (nb) |l|_2
      real(dp) :: zbound = 0.0_dp                   ! bound of |z| on the sub-step
   end type segment_t

contains

   !> Integrate from (u0, v0) at t = 0 over transient + recorded periods, exactly.
   !>
   !> Same horizon, samples and result fields as run_transient; steps_accepted counts the
   !> linear segments, events the switches of the contact configuration, factorizations the
   !> configurations built; dt_smallest/dt_largest are the shortest/longest segments.
   subroutine run_exact(prob, cfg, out, u0, v0, res, err, engine)
      type(problem_t), intent(in) :: prob              !! model (bilinear stops only)
      type(solver_settings_t), intent(in) :: cfg       !! uses transient_periods, record_periods
      type(output_settings_t), intent(in) :: out       !! what to record
      real(dp), intent(in) :: u0(:), v0(:)             !! initial state relative to the base
      type(transient_result_t), intent(out) :: res     !! results
      type(error_t), allocatable, intent(out) :: err   !! unsupported model or LAPACK failure
      !> 'auto' (default: closed form, Taylor where the eigenvectors are ill-conditioned),
      !> 'modal' (closed form everywhere) or 'taylor' (the fallback everywhere: a cross-check)
      character(len=*), intent(in), optional :: engine
      type(reduced_t) :: red
      real(dp) :: climit
      type(config_t), allocatable :: cfgs(:)
      type(segment_t) :: sg
      integer :: nc, ns, nb, ncfg, ic, c, i, n_hist, n_poinc, ih, ip, flips, outcome, spp
      integer(int64) :: k0, k_rec, k_end, mask, new_mask, count0, count1, rate
      real(dp) :: period, omega, tol_t, r0, t_rec, t_rec_len, tau_end, tau_w0, d, dd
      real(dp) :: xg(n_gauss), wg(n_gauss)
      real(dp), allocatable :: x0(:), val(:, :), bnd(:, :), acc_f(:), acc_f2(:), &
         acc_work(:), acc_contact(:), del_d(:), del_l(:), del_w(:), roots(:, :), xe(:), ae(:)
      real(dp), allocatable :: dsv(:, :), dss(:, :)
      ! work arrays (allocated once: gfortran puts automatic arrays on the heap)
      real(dp), allocatable :: q(:), fy(:), fy1(:), fy2(:), fb2(:), fb3(:), v2(:, :), b2(:, :), &
         x1(:), s1(:)
      logical, allocatable :: done(:), nd(:)
      integer :: nf                                      ! functions recorded by add
      integer, allocatable :: sig_d(:), sig_l(:), sig_w(:), n_roots(:)
      logical, allocatable :: need(:), damped(:)
      logical :: recording
      logical :: filtering                         ! low-pass filtered strain asked
      type(lowpass_t) :: fil_s, fil_r              ! filters of the strain and its rate
      integer :: nfs, ipf, ihf                     ! filter samples per period, next outputs
      integer(int64) :: jf, jp_next, jh_next       ! next filter sample, its output indices

      call system_clock(count0, rate)
      nc = prob%n_contacts;  ns = prob%n_stops
      if (.not. (prob%omega > 0.0_dp)) then
         call fatal_error(err, 'gapbeam_exact:run_exact: the forcing frequency must be > 0 '&
            // '(it sets the period and the horizon), got ' // str(prob%omega) // ' rad/s')
         return
      end if
      do c = 1, nc
         if (prob%c_law(c) /= law_bilinear) then
            call fatal_error(err, 'gapbeam_exact:run_exact: the exact event-driven integrator ' &
               // 'needs piecewise-linear stops; stop ' // str(prob%c_stop(c)) // ' uses the ' &
               // 'Hertz law (f = k d^p), which is not piecewise linear: use the Newmark ' &
               // 'integrator for it')
            return
         end if
      end do
      if (nc > 62) then
         call fatal_error(err, 'gapbeam_exact:run_exact: at most 62 one-sided contacts, got ' &
            // str(nc))
         return
      end if
      climit = cond_limit
      if (present(engine)) then
         select case (engine)
         case ('auto')
         case ('modal');  climit = huge(1.0_dp)
         case ('taylor'); climit = -1.0_dp
         case default
            call fatal_error(err, 'gapbeam_exact:run_exact: engine must be ''auto'', ''modal'' ' &
               // 'or ''taylor'', got ''' // engine // '''')
            return
         end select
      end if
      call setup_reduction(prob, red, err)
      if (allocated(err)) return
      nb = red%nb
      omega = prob%omega
      period = 2.0_dp * pi / omega
      ! event brackets: time_tol of the shorter of the forcing period and the first open period
      tol_t = time_tol * period
      if (prob%f1_open_hz > 0.0_dp) tol_t = time_tol * min(period, 1.0_dp / prob%f1_open_hz)
      spp = out%samples_per_period
      k_rec = int(cfg%transient_periods, int64)
      k_end = k_rec + int(cfg%record_periods, int64)
      t_rec = real(cfg%transient_periods, dp) * period
      t_rec_len = real(cfg%record_periods, dp) * period
      call gauss_legendre(xg, wg)

      n_hist = min(out%history_periods, cfg%record_periods) * spp
      n_poinc = cfg%record_periods
      call allocate_result(res, n_hist, n_poinc, ns)
      allocate(acc_f2(ns), acc_f(ns), acc_contact(ns), acc_work(ns), source=0.0_dp)
      ! low-pass filter of the root strain and its rate (as run_transient): uniform samples
      ! from t = 0; the filtered values replace the Poincare strain and fill strain_filtered
      filtering = out%filter_cutoff_hz > 0.0_dp
      allocate(res%strain_filtered(merge(n_hist, 0, filtering)))
      if (filtering) then
         nfs = out%filter_samples_per_period
         call design_lowpass(out%filter_order, out%filter_cutoff_hz, real(nfs, dp) / period, &
                             fil_s, err)
         if (allocated(err)) then
            err%message = 'group &output: ' // err%message // ' (the filter samples ' &
               // str(nfs) // ' times per forcing period: raise filter_samples_per_period)'
            return
         end if
         call design_lowpass(out%filter_order, out%filter_cutoff_hz, real(nfs, dp) / period, &
                             fil_r, err)
         jf = 0;  ipf = 1;  ihf = 1
         jp_next = poincare_filter_index(1);  jh_next = history_filter_index(1)
      end if
      res%dt_smallest = huge(1.0_dp);  res%dt_largest = 0.0_dp
      allocate(val(0:3, nb), bnd(0:4, nb), need(nb))
      allocate(sig_d(nc), sig_l(nc), sig_w(nc), del_d(nc), del_l(nc), del_w(nc), n_roots(nc), &
               roots(max_roots, nc), damped(nc), dsv(0:3, nc), dss(0:3, nc))
      damped = prob%c_c(1:nc) > 0.0_dp
      sig_w = 1;  del_w = 0.0_dp;  n_roots = 0
      allocate(cfgs(4))
      ncfg = 0
      allocate(xe(2 * red%nr), ae(red%nr), x1(2 * red%nr), s1(2 * red%nr))
      allocate(q(4 * nc + 4), fy(4 * nc + 4), fy1(4 * nc + 4), fy2(4 * nc + 4), &
               fb2(4 * nc + 4), fb3(4 * nc + 4), done(4 * nc + 4), v2(0:3, nb), b2(0:4, nb), &
               nd(nb))

      ! initial state: massless dofs in equilibrium, instantaneous contact activity
      x0 = [u0(red%ir), v0(red%ir)]
      mask = 0
      do c = 1, nc
         i = prob%c_dof(c)
         d = prob%c_sign(c) * u0(i) - prob%c_gap(c)
         dd = prob%c_sign(c) * v0(i)
         if (contact_force(prob%c_law(c), prob%c_k(c), prob%c_c(c), prob%c_p(c), d, dd) &
             > 0.0_dp) mask = ibset(mask, c - 1)
      end do
      k0 = 0;  r0 = 0.0_dp;  flips = 0;  ih = 1;  ip = 1
      recording = k_rec == 0;  tau_w0 = 0.0_dp

      do
         ic = config_index(mask)
         if (allocated(err)) return
         call start_segment(cfgs(ic), red, omega, x0, r0, sg)
         sg%ic = ic
         ! activity just after the start, in this representation
         call set_need(.false.)
         call eval_seg(sg, cfgs(ic), red, 0.0_dp, need, val, bnd)
         call state_derivs(x0, r0)
         new_mask = decide()
         if (new_mask /= mask .and. flips < max_flips) then
            call register_switch(mask, new_mask, 0.0_dp)
            mask = new_mask;  flips = flips + 1
            cycle
         end if
         res%steps_accepted = res%steps_accepted + 1
         call init_signs()
         tau_w0 = 0.0_dp
         n_roots = 0
         call sweep(tau_end, outcome, new_mask)
         if (allocated(err)) return
         if (recording) call accumulate_window(tau_w0, tau_end)
         res%dt_smallest = min(res%dt_smallest, tau_end)
         res%dt_largest = max(res%dt_largest, tau_end)
         call segment_state(sg, cfgs(ic), red, omega, tau_end, xe, ae)
         if (outcome == end_horizon) exit
         if (outcome == end_anchor) res%steps_accepted = res%steps_accepted - 1
         x0 = xe
         r0 = r0 + tau_end
         if (r0 >= period) then
            k0 = k0 + int(r0 / period, int64)
            r0 = r0 - real(int(r0 / period, int64), dp) * period
            if (r0 < 0.0_dp) then
               r0 = r0 + period;  k0 = k0 - 1
            end if
         end if
         if (tau_end > 0.0_dp) flips = 0
         if (outcome == end_switch) then
            call register_switch(mask, new_mask, 0.0_dp)
            mask = new_mask
         end if
      end do

      ! ---- final state and statistics
      allocate(res%u(red%n), res%v(red%n), res%a(red%n))
      call expand(red, xe(1:red%nr), res%u)
      call expand(red, xe(red%nr + 1:), res%v)
      call expand(red, ae, res%a)
      res%t_end = real(k_end, dp) * period
      if (cfg%record_periods > 0) then
         res%rms_force = sqrt(acc_f2 / t_rec_len)
         res%contact_fraction = acc_contact / t_rec_len
         res%impulse_per_period = acc_f / real(cfg%record_periods, dp)
         res%work_rate = acc_work / t_rec_len
      else
         res%rms_force = acc_f2;  res%contact_fraction = acc_contact
         res%impulse_per_period = acc_f;  res%work_rate = acc_work
      end if
      res%factorizations = ncfg
      if (res%dt_smallest > res%dt_largest) res%dt_smallest = 0.0_dp
      call system_clock(count1)
      res%cpu_seconds = real(count1 - count0, dp) / real(rate, dp)

   contains

      !> Index of the configuration of `msk`, built on first use.
      integer function config_index(msk) result(j)
         integer(int64), intent(in) :: msk
         type(config_t), allocatable :: tmp(:)
         do j = 1, ncfg
            if (cfgs(j)%mask == msk) return
         end do
         if (ncfg == size(cfgs)) then
            allocate(tmp(2 * ncfg))
            tmp(1:ncfg) = cfgs(1:ncfg)
            call move_alloc(tmp, cfgs)
         end if
         ncfg = ncfg + 1
         j = ncfg
         call build_config(prob, red, msk, climit, cfgs(j), err)
      end function config_index

      !> Absolute time of tau in the current segment [s].
      real(dp) function abs_time(tau)
         real(dp), intent(in) :: tau
         abs_time = real(k0, dp) * period + r0 + tau
      end function abs_time

      !> Offset of the instant (k periods + r) from the segment start.
      real(dp) function tau_of(k, r)
         integer(int64), intent(in) :: k
         real(dp), intent(in) :: r
         tau_of = real(k - k0, dp) * period + (r - r0)
      end function tau_of

      !> Contact functions of contact cc from the slot values: d and lambda = k d + c d'
      !> with derivatives 0..2 (lambda) or 0..3 (d), and their scales/bounds 0..4 (d), 0..3.
      subroutine contact_functions(cc, dv, db, lv, lb)
         integer, intent(in) :: cc
         real(dp), intent(out) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
         integer :: b
         real(dp) :: s
         b = red%cslot(cc);  s = prob%c_sign(cc)
         dv = s * val(:, b);  dv(0) = dv(0) - prob%c_gap(cc)
         db = bnd(:, b);  db(0) = db(0) + abs(prob%c_gap(cc))
         lv = prob%c_k(cc) * dv(0:2) + prob%c_c(cc) * dv(1:3)
         lb = prob%c_k(cc) * db(0:3) + prob%c_c(cc) * db(1:4)
      end subroutine contact_functions

      !> Activity of every contact just after tau, from the current values (val, bnd).
      integer(int64) function decide() result(msk)
         integer :: cc
         msk = 0
         do cc = 1, nc
            if (sign_d(cc) > 0 .and. sign_l(cc) > 0) msk = ibset(msk, cc - 1)
         end do
      end function decide

      !> Sign just after the instant of d (sign_d) and of k d + c d' (sign_l; 1 without a
      !> damper) of contact cc, from the state derivatives of state_derivs.
      integer function sign_d(cc)
         integer, intent(in) :: cc
         sign_d = sign_after(dsv(:, cc), dss(:, cc))
      end function sign_d

      integer function sign_l(cc)
         integer, intent(in) :: cc
         sign_l = 1
         if (damped(cc)) sign_l = sign_after(prob%c_k(cc) * dsv(0:2, cc) &
            + prob%c_c(cc) * dsv(1:3, cc), prob%c_k(cc) * dss(0:2, cc) &
            + prob%c_c(cc) * dss(1:3, cc))
      end function sign_l

      !> Derivatives 0..3 of every contact's penetration d at the state x (forcing offset r),
      !> through the equations of motion of the current configuration, and their scales (sum
      !> of the magnitudes of the terms): free of the cancellations of the modal sums, and the
      !> same in the representations before and after a switch. bnd must hold the bounds of
      !> the slots at the same instant.
      subroutine state_derivs(x, r)
         real(dp), intent(in) :: x(:), r
         real(dp) :: xk(0:3), sk(0:3), sn, cs
         integer :: cc, i, nr, j
         sn = sin(omega * r);  cs = cos(omega * r)
         nr = red%nr
         associate(am => cfgs(ic)%amat, aa => cfgs(ic)%absamat, bs => cfgs(ic)%bsv, &
                   b0 => cfgs(ic)%b0v)
            ! x' in full (u' = v needs no product), x'' and x''' only in the contact rows
            x1(1:nr) = x(nr + 1:);  s1(1:nr) = abs(x(nr + 1:))
            do j = nr + 1, 2 * nr
               x1(j) = dot_product(am(j, :), x) + bs(j) * sn + b0(j)
               s1(j) = dot_product(aa(j, :), abs(x)) + abs(bs(j)) + abs(b0(j))
            end do
            do cc = 1, nc
               i = red%cpos(cc)
               xk(0) = x(i);  sk(0) = abs(x(i))
               xk(1) = x1(i);  sk(1) = s1(i)
               xk(2) = x1(nr + i);  sk(2) = s1(nr + i)
               xk(3) = dot_product(am(nr + i, :), x1) + bs(nr + i) * omega * cs
               sk(3) = dot_product(aa(nr + i, :), s1) + abs(bs(nr + i)) * omega
               dsv(:, cc) = prob%c_sign(cc) * xk
               dss(:, cc) = sk
            end do
         end associate
         do cc = 1, nc
            dsv(0, cc) = dsv(0, cc) - prob%c_gap(cc)
            ! u_i and v_i scale only themselves here: their round-off is that of the modal
            ! sums they come from
            dss(0, cc) = max(dss(0, cc), bnd(0, red%cslot(cc))) + abs(prob%c_gap(cc))
            dss(1, cc) = max(dss(1, cc), bnd(1, red%cslot(cc)))
         end do
      end subroutine state_derivs

      !> Signs of the watched functions at the start of a segment, consistent with `mask`;
      !> a function within round-off of zero gets a dead band.
      subroutine init_signs()
         integer :: cc
         real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
         logical :: on
         do cc = 1, nc
            call contact_functions(cc, dv, db, lv, lb)
            on = btest(mask, cc - 1)
            sig_d(cc) = sign_d(cc)
            sig_l(cc) = sign_l(cc)
            if (on) then
               sig_d(cc) = 1;  sig_l(cc) = 1
            else
               if (sig_d(cc) == 0) sig_d(cc) = -1
               if (sig_l(cc) == 0) sig_l(cc) = -1
               if (sig_d(cc) > 0 .and. sig_l(cc) > 0) sig_l(cc) = -1
            end if
            del_d(cc) = band(sig_d(cc) * dv(0), db(0))
            del_l(cc) = 0.0_dp
            if (damped(cc)) del_l(cc) = band(sig_l(cc) * lv(0), lb(0))
         end do
      end subroutine init_signs

      !> Onsets and releases between masks m_old and m_new at tau of the current segment.
      subroutine register_switch(m_old, m_new, tau)
         integer(int64), intent(in) :: m_old, m_new
         real(dp), intent(in) :: tau
         integer :: cc, ks
         real(dp) :: t
         res%events = res%events + 1
         t = abs_time(tau)
         do cc = 1, nc
            if (btest(m_new, cc - 1) .and. .not. btest(m_old, cc - 1)) then
               ks = prob%c_stop(cc)
               if (res%first_contact_time(ks) < 0.0_dp) res%first_contact_time(ks) = t
               if (recording) res%n_impacts(ks) = res%n_impacts(ks) + 1
            end if
         end do
      end subroutine register_switch

      !> Sweep the segment from tau = 0: samples, extrema, zeros of d', until a switch, the
      !> horizon or a re-anchoring instant.
      subroutine sweep(tau_stop, how, m_new)
         real(dp), intent(out) :: tau_stop
         integer, intent(out) :: how
         integer(int64), intent(out) :: m_new
         real(dp) :: tau, tn, h, hf, target, tr, th, tp, tq, tl, tt, tf
         integer(int64) :: kh, kp
         real(dp) :: rh, rp
         integer :: kind_hit, c_hit
         logical :: hit
         m_new = mask
         tau = 0.0_dp      ! val, bnd hold the values at tau = 0
         if (recording) call start_trackers(tau)
         do
            ! next stop
            target = 2.0_dp * period
            tl = tau_of(k_end, 0.0_dp);  target = min(target, tl)
            tr = huge(1.0_dp)
            if (.not. recording) tr = tau_of(k_rec, 0.0_dp)
            target = min(target, tr)
            th = huge(1.0_dp)
            if (ih <= n_hist) then
               kh = k_rec + int((ih - 1) / spp, int64)
               rh = real(mod(ih - 1, spp), dp) * period / real(spp, dp)
               th = tau_of(kh, rh)
            end if
            target = min(target, th)
            tp = huge(1.0_dp)
            if (ip <= n_poinc) then
               tq = out%poincare_phase_deg / 360.0_dp
               kp = k_rec + int(ip - 1, int64) + int(floor(tq), int64)
               rp = (tq - floor(tq)) * period
               tp = tau_of(kp, rp)
            end if
            target = min(target, tp)
            tf = huge(1.0_dp)
            if (filtering .and. (ipf <= n_poinc .or. ihf <= n_hist)) then
               tf = tau_of(jf / nfs, real(mod(jf, int(nfs, int64)), dp) * period &
                                      / real(nfs, dp))
            end if
            target = min(target, tf)
            target = max(target, tau)
            ! ---- step to the target
            do while (tau < target)
               if (.not. sg%modal) then
                  if (tau >= sg%tk + cfgs(ic)%hsub) then
                     if (recording) call accumulate_window(tau_w0, tau)
                     tau_w0 = tau
                     call taylor_next(sg, cfgs(ic), red)
                  end if
               end if
               h = min(step_limit(), target - tau)
               if (.not. sg%modal) h = min(h, sg%tk + cfgs(ic)%hsub - tau)
               hf = max(tol_t, 4.0_dp * spacing(max(tau, period)))
               if (h < hf) h = min(hf, target - tau)
               if (.not. sg%modal) h = min(h, sg%tk + cfgs(ic)%hsub - tau)
               tn = tau + h
               if (tn >= target) then
                  tn = target
                  if (target >= min(th, tp)) call set_need(.true.)   ! a sample is due
               end if
               call eval_seg(sg, cfgs(ic), red, tn, need, val, bnd)
               call find_flip(tau, tn, hf, hit, tt, kind_hit, c_hit)
               if (allocated(err)) return
               if (hit) then
                  tn = tt
                  call eval_seg(sg, cfgs(ic), red, tn, need, val, bnd)
                  if (kind_hit == 3) then
                     ! zero of d' in a contact phase: splits the work integral (a full list
                     ! closes the statistics window here)
                     if (n_roots(c_hit) == max_roots) then
                        call accumulate_window(tau_w0, tn)
                        tau_w0 = tn
                     else
                        n_roots(c_hit) = n_roots(c_hit) + 1
                        roots(n_roots(c_hit), c_hit) = tn
                     end if
                     sig_w(c_hit) = -sig_w(c_hit);  del_w(c_hit) = 0.0_dp
                  else
                     call segment_state(sg, cfgs(ic), red, omega, tn, xe, ae)
                     call state_derivs(xe, r0 + tn)
                     m_new = decide()
                     if (m_new /= mask) then
                        if (recording) call update_trackers()
                        tau_stop = tn;  how = end_switch
                        return
                     end if
                     if (kind_hit == 1) then
                        sig_d(c_hit) = -sig_d(c_hit);  del_d(c_hit) = 0.0_dp
                     else
                        sig_l(c_hit) = -sig_l(c_hit);  del_l(c_hit) = 0.0_dp
                     end if
                  end if
               end if
               tau = tn
               call clear_bands()
               if (recording) call update_trackers()
            end do
            ! ---- at the target: the stops due now
            if (tau >= tr) then
               recording = .true.
               tau_w0 = tau
               n_roots = 0
               call set_need(.false.)
               call eval_seg(sg, cfgs(ic), red, tau, need, val, bnd)
               call start_trackers(tau)
            end if
            if (tau >= th .or. tau >= tp .or. tau >= tf) then
               if ((tau >= th .or. tau >= tp) .and. .not. all(need)) then
                  call set_need(.true.)
                  call eval_seg(sg, cfgs(ic), red, tau, need, val, bnd)
               end if
               if (tau >= th) call history_sample()
               if (tau >= tp) call poincare_sample()
               if (tau >= tf) call filter_sample()
               call set_need(.false.)
               cycle
            end if
            if (tau >= tl) then
               tau_stop = tau;  how = end_horizon
               return
            end if
            if (tau >= 2.0_dp * period) then
               tau_stop = tau;  how = end_anchor
               return
            end if
         end do
      end subroutine sweep

      !> Functionals evaluated in the sweep: slots, the strain while recording, all if `all`.
      subroutine set_need(all)
         logical, intent(in) :: all
         need = all
         need(1:red%n_slots) = .true.
         if (recording .or. filtering) need(red%b_strain) = .true.
      end subroutine set_need

      !> Largest safe step from the current values for every watched function.
      real(dp) function step_limit() result(h)
         integer :: cc, bs, ks, f, k
         real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3), y, tol, s, qmin
         ! pass 1: the quadratic (and monotone) steps of every watched function
         nf = 0
         do cc = 1, nc
            call contact_functions(cc, dv, db, lv, lb)
            s = sig_d(cc)
            call add(s * dv(0) + del_d(cc), s * dv(1), s * dv(2), db(2), db(3), 0.0_dp)
            if (damped(cc)) then
               s = sig_l(cc)
               call add(s * lv(0) + del_l(cc), s * lv(1), s * lv(2), lb(2), lb(3), 0.0_dp)
            end if
            if (recording .and. btest(mask, cc - 1)) then
               s = sig_w(cc)
               call add(s * dv(1) + del_w(cc), s * dv(2), s * dv(3), db(3), db(4), 0.0_dp)
               ks = prob%c_stop(cc)
               tol = peak_tol * lb(0)
               call add(res%peak_force(ks) + tol - lv(0), -lv(1), -lv(2), lb(2), lb(3), &
                        mono_quad(lv(1), lv(2), lb(3)))
            end if
         end do
         if (recording) then
            bs = red%b_strain
            tol = peak_tol * bnd(0, bs)
            call add(res%strain_max + tol - val(0, bs), -val(1, bs), -val(2, bs), bnd(2, bs), &
                     bnd(3, bs), mono_quad(val(1, bs), val(2, bs), bnd(3, bs)))
            call add(val(0, bs) - res%strain_min + tol, val(1, bs), val(2, bs), bnd(2, bs), &
                     bnd(3, bs), mono_quad(val(1, bs), val(2, bs), bnd(3, bs)))
            tol = peak_tol * bnd(1, bs)
            call add(res%strain_rate_max + tol - val(1, bs), -val(2, bs), -val(3, bs), &
                     bnd(3, bs), bnd(4, bs), mono_quad(val(2, bs), val(3, bs), bnd(4, bs)))
            call add(val(1, bs) - res%strain_rate_min + tol, val(2, bs), val(3, bs), &
                     bnd(3, bs), bnd(4, bs), mono_quad(val(2, bs), val(3, bs), bnd(4, bs)))
         end if
         ! pass 2: in ascending order of the quadratic steps, the cubic bound where it can
         ! still lengthen the step (the result is the least over the functions)
         h = period
         done = .false.
         do k = 1, nf
            qmin = huge(1.0_dp);  f = 0
            do cc = 1, nf
               if (.not. done(cc) .and. q(cc) < qmin) then
                  qmin = q(cc);  f = cc
               end if
            end do
            if (f == 0 .or. qmin >= h) exit
            done(f) = .true.
            s = qmin
            if (fy(f) > 0.0_dp .and. fy2(f) > -0.5_dp * fb2(f) .and. fb3(f) > 0.0_dp) &
               s = max(s, cubic_root(fy(f), fy1(f), 0.5_dp * fy2(f), fb3(f) / 6.0_dp, h))
            h = min(h, s)
         end do
      end function step_limit

      !> Record one watched function for step_limit (see add_fn).
      subroutine add(y0, y1, y2, b2, b3, hm)
         real(dp), intent(in) :: y0, y1, y2, b2, b3, hm
         call add_fn(nf, q, fy, fy1, fy2, fb2, fb3, y0, y1, y2, b2, b3, hm)
      end subroutine add

      !> Did a watched function change sign on (ta, tb]? If so, bracket the first such change
      !> to hf and return its upper end tt, the kind (1: d, 2: lambda, 3: d') and the contact.
      !> On return, val/bnd hold the values at tb (not tt).
      subroutine find_flip(ta, tb, hf, hit, tt, kind_hit, c_hit)
         real(dp), intent(in) :: ta, tb, hf
         logical, intent(out) :: hit
         real(dp), intent(out) :: tt
         integer, intent(out) :: kind_hit, c_hit
         integer :: cc, kk
         real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3), y, t1
         hit = .false.;  tt = tb;  kind_hit = 0;  c_hit = 0
         do cc = 1, nc
            call contact_functions(cc, dv, db, lv, lb)
            do kk = 1, 3
               select case (kk)
               case (1)
                  y = sig_d(cc) * dv(0) + del_d(cc)
               case (2)
                  if (.not. damped(cc)) cycle
                  y = sig_l(cc) * lv(0) + del_l(cc)
               case (3)
                  if (.not. (recording .and. btest(mask, cc - 1))) cycle
                  y = sig_w(cc) * dv(1) + del_w(cc)
               end select
               if (y >= 0.0_dp) cycle
               t1 = tb
               if (tb - ta > hf) t1 = refine(cc, kk, ta, tb, hf)
               if (.not. hit .or. t1 < tt) then
                  hit = .true.;  tt = t1;  kind_hit = kk;  c_hit = cc
               end if
            end do
         end do
      end subroutine find_flip

      !> Value of watched function (contact cc, kind kk) at tau, sign-adjusted (y < 0: flipped).
      real(dp) function watched(cc, kk, tau) result(y)
         integer, intent(in) :: cc, kk
         real(dp), intent(in) :: tau
         real(dp) :: dv(0:3), s
         integer :: b
         nd = .false.;  b = red%cslot(cc);  nd(b) = .true.
         call eval_seg(sg, cfgs(ic), red, tau, nd, v2, b2)
         s = prob%c_sign(cc)
         dv = s * v2(:, b);  dv(0) = dv(0) - prob%c_gap(cc)
         select case (kk)
         case (1)
            y = sig_d(cc) * dv(0) + del_d(cc)
         case (2)
            y = sig_l(cc) * (prob%c_k(cc) * dv(0) + prob%c_c(cc) * dv(1)) + del_l(cc)
         case default
            y = sig_w(cc) * dv(1) + del_w(cc)
         end select
      end function watched

      !> Bracket the first sign change of a watched function in (ta, tb] to width hf
      !> (bisection with a secant guess); returns the upper end.
      real(dp) function refine(cc, kk, ta, tb, hf) result(t1)
         integer, intent(in) :: cc, kk
         real(dp), intent(in) :: ta, tb, hf
         real(dp) :: lo, hi, ylo, yhi, mid, ym
         integer :: it, side
         lo = ta;  hi = tb
         ylo = watched(cc, kk, lo);  yhi = watched(cc, kk, hi)
         if (ylo < 0.0_dp) then
            t1 = lo;  return
         end if
         side = 0
         do it = 1, 200
            if (hi - lo <= hf) exit
            ! Illinois step, kept at least hf/2 inside the bracket; bisection every 8th
            mid = lo + (hi - lo) * ylo / (ylo - yhi)
            mid = max(lo + 0.5_dp * hf, min(hi - 0.5_dp * hf, mid))
            if (mod(it, 8) == 0) mid = 0.5_dp * (lo + hi)
            ym = watched(cc, kk, mid)
            if (ym < 0.0_dp) then
               hi = mid;  yhi = ym
               if (side == 1) ylo = 0.5_dp * ylo
               side = 1
            else
               lo = mid;  ylo = ym
               if (side == -1) yhi = 0.5_dp * yhi
               side = -1
            end if
         end do
         t1 = hi
      end function refine

      !> Drop the dead band of a function once it is clearly on its side.
      subroutine clear_bands()
         integer :: cc
         real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
         do cc = 1, nc
            if (del_d(cc) == 0.0_dp .and. del_l(cc) == 0.0_dp .and. del_w(cc) == 0.0_dp) cycle
            call contact_functions(cc, dv, db, lv, lb)
            if (sig_d(cc) * dv(0) > del_d(cc)) del_d(cc) = 0.0_dp
            if (sig_l(cc) * lv(0) > del_l(cc)) del_l(cc) = 0.0_dp
            if (sig_w(cc) * dv(1) > del_w(cc)) del_w(cc) = 0.0_dp
         end do
      end subroutine clear_bands

      !> Running extrema at the current values (record only).
      subroutine update_trackers()
         integer :: cc, bs, ks
         real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
         bs = red%b_strain
         res%strain_max = max(res%strain_max, val(0, bs))
         res%strain_min = min(res%strain_min, val(0, bs))
         res%strain_rate_max = max(res%strain_rate_max, val(1, bs))
         res%strain_rate_min = min(res%strain_rate_min, val(1, bs))
         do cc = 1, nc
            if (.not. btest(mask, cc - 1)) cycle
            call contact_functions(cc, dv, db, lv, lb)
            ks = prob%c_stop(cc)
            res%peak_force(ks) = max(res%peak_force(ks), lv(0))
         end do
      end subroutine update_trackers

      !> Begin the record-only watches at tau: extrema and the sign of d' of active contacts.
      subroutine start_trackers(tau)
         real(dp), intent(in) :: tau
         integer :: cc
         real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
         call update_trackers()
         call segment_state(sg, cfgs(ic), red, omega, tau, xe, ae)
         call state_derivs(xe, r0 + tau)
         do cc = 1, nc
            call contact_functions(cc, dv, db, lv, lb)
            sig_w(cc) = sign_after(dsv(1:3, cc), dss(1:3, cc))
            if (sig_w(cc) == 0) sig_w(cc) = 1
            del_w(cc) = band(sig_w(cc) * dv(1), db(1))
         end do
      end subroutine start_trackers

      !> Integrals over [ta, tb] of the current segment for the active contacts (record).
      subroutine accumulate_window(ta, tb)
         real(dp), intent(in) :: ta, tb
         integer :: cc, ks
         real(dp) :: sf, sf2, sw
         if (tb <= ta) then
            n_roots = 0;  return
         end if
         do cc = 1, nc
            if (.not. btest(mask, cc - 1)) cycle
            ks = prob%c_stop(cc)
            if (sg%modal) then
               call modal_window(sg, red%cslot(cc), prob%c_sign(cc), prob%c_k(cc), &
                  prob%c_c(cc), prob%c_gap(cc), ta, tb, roots(1:n_roots(cc), cc), sf, sf2, sw)
            else
               call taylor_window(sg, red%cslot(cc), prob%c_sign(cc), prob%c_k(cc), &
                  prob%c_c(cc), prob%c_gap(cc), ta, tb, roots(1:n_roots(cc), cc), xg, wg, &
                  sf, sf2, sw)
            end if
            acc_f(ks) = acc_f(ks) + sf
            acc_f2(ks) = acc_f2(ks) + sf2
            acc_work(ks) = acc_work(ks) + sw
            acc_contact(ks) = acc_contact(ks) + (tb - ta)
         end do
         n_roots = 0
      end subroutine accumulate_window

      !> History sample ih at the current instant (val holds every functional).
      subroutine history_sample()
         integer :: cc, ks
         real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
         res%time(ih) = t_rec + real(ih - 1, dp) * period / real(spp, dp)
         res%strain(ih) = val(0, red%b_strain)
         res%strain_rate(ih) = val(1, red%b_strain)
         res%tip_displacement(ih) = val(0, red%b_tip)
         res%stop_force(ih, :) = 0.0_dp
         do cc = 1, nc
            if (.not. btest(mask, cc - 1)) cycle
            call contact_functions(cc, dv, db, lv, lb)
            ks = prob%c_stop(cc)
            res%stop_force(ih, ks) = res%stop_force(ih, ks) + max(0.0_dp, lv(0))
         end do
         ih = ih + 1
      end subroutine history_sample

      !> Poincare sample ip at the current instant.
      subroutine poincare_sample()
         res%p_time(ip) = t_rec + (real(ip - 1, dp) + out%poincare_phase_deg / 360.0_dp) &
                          * period
         if (.not. filtering) then
            res%p_strain(ip) = val(0, red%b_strain)
            res%p_strain_rate(ip) = val(1, red%b_strain)
         end if
         res%p_tip(ip) = val(0, red%b_tip)
         res%p_tip_velocity(ip) = val(1, red%b_tip)
         ip = ip + 1
      end subroutine poincare_sample

      !> Filter sample jf at the current instant: feed both filters, store their outputs at the
      !> Poincare and history filter indices.
      subroutine filter_sample()
         real(dp) :: ys, yr
         ys = fil_s%apply(val(0, red%b_strain))
         yr = fil_r%apply(val(1, red%b_strain))
         if (ipf <= n_poinc .and. jf == jp_next) then
            res%p_strain(ipf) = ys;  res%p_strain_rate(ipf) = yr
            ipf = ipf + 1;  jp_next = poincare_filter_index(ipf)
         end if
         if (ihf <= n_hist .and. jf == jh_next) then
            res%strain_filtered(ihf) = ys
            ihf = ihf + 1;  jh_next = history_filter_index(ihf)
         end if
         jf = jf + 1
      end subroutine filter_sample

      !> Filter sample index of Poincare sample k (as run_transient).
      integer(int64) function poincare_filter_index(k)
         integer, intent(in) :: k
         poincare_filter_index = int(cfg%transient_periods + k - 1, int64) * nfs &
            + nint(out%poincare_phase_deg / 360.0_dp * nfs, int64)
      end function poincare_filter_index

      !> Filter sample index of history sample i (as run_transient).
      integer(int64) function history_filter_index(i)
         integer, intent(in) :: i
         history_filter_index = int(cfg%transient_periods, int64) * nfs &
            + int(i - 1, int64) * (nfs / out%samples_per_period)
      end function history_filter_index
   end subroutine run_exact

   ! ------------------------------------------------------------------ set-up

   !> Condense the massless dofs and set up the watched functionals.
   subroutine setup_reduction(prob, red, err)
      type(problem_t), intent(in) :: prob
      type(reduced_t), intent(out) :: red
      type(error_t), allocatable, intent(out) :: err
      integer :: i, j, n, nr, ns, info, c, b
      real(dp), allocatable :: kss(:, :), rhs(:, :), l(:)
      real(dp) :: scl
      n = prob%n
      red%n = n
      red%ir = pack([(i, i = 1, n)], [(prob%sys%m(i, i) /= 0.0_dp, i = 1, n)])
      red%is = pack([(i, i = 1, n)], [(prob%sys%m(i, i) == 0.0_dp, i = 1, n)])
      nr = size(red%ir);  ns = size(red%is)
      red%nr = nr;  red%ns = ns
      if (nr == 0) then
         call fatal_error(err, 'gapbeam_exact:run_exact: the model has no mass')
         return
      end if
      allocate(red%t(ns, nr))
      if (ns > 0) then
         if (maxval(abs(prob%sys%m(red%is, :))) > 0.0_dp) then
            call fatal_error(err, 'gapbeam_exact:run_exact: a dof with zero diagonal mass ' &
               // 'is coupled by the mass matrix; cannot condense it')
            return
         end if
         scl = max(maxval(abs(prob%c)), tiny(1.0_dp))
         if (maxval(abs(prob%c(red%is, :) - prob%gamma * prob%sys%k(red%is, :))) &
             > 1.0e-12_dp * scl) then
            call fatal_error(err, 'gapbeam_exact:run_exact: the damping rows of the massless ' &
               // 'dofs are not gamma K (Rayleigh): the static condensation does not apply')
            return
         end if
         kss = prob%sys%k(red%is, red%is)
         rhs = -prob%sys%k(red%is, red%ir)
         call dpotrf('U', ns, kss, ns, info)
         if (info == 0) call dpotrs('U', ns, nr, kss, ns, rhs, ns, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_exact:run_exact: the stiffness of the massless ' &
               // 'dofs is singular (dpotrf/dpotrs info=' // str(info) // ')')
            return
         end if
         red%t = rhs
      end if
      red%mr = prob%sys%m(red%ir, red%ir)
      red%kr = prob%sys%k(red%ir, red%ir)
      red%cr = prob%c(red%ir, red%ir)
      if (ns > 0) then
         red%kr = red%kr + matmul(prob%sys%k(red%ir, red%is), red%t)
         red%cr = red%cr + matmul(prob%c(red%ir, red%is), red%t)
      end if
      red%kr = 0.5_dp * (red%kr + transpose(red%kr))
      red%cr = 0.5_dp * (red%cr + transpose(red%cr))
      red%qr = prob%q(red%ir)
      red%mfac = red%mr
      call dpotrf('U', nr, red%mfac, nr, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_exact:run_exact: the mass matrix of the dofs with mass ' &
            // 'is not positive definite (dpotrf info=' // str(info) // ')')
         return
      end if
      ! contacts and functionals
      red%n_slots = prob%n_slots
      red%nb = prob%n_slots + 2
      red%b_strain = prob%n_slots + 1
      red%b_tip = prob%n_slots + 2
      allocate(red%cpos(prob%n_contacts), red%cslot(prob%n_contacts))
      do c = 1, prob%n_contacts
         red%cpos(c) = 0
         do j = 1, nr
            if (red%ir(j) == prob%c_dof(c)) red%cpos(c) = j
         end do
         if (red%cpos(c) == 0) then
            call fatal_error(err, 'gapbeam_exact:run_exact: stop ' // str(prob%c_stop(c)) &
               // ' acts on a massless dof (global dof ' // str(prob%c_dof(c)) // '); the ' &
               // 'exact integrator condenses massless dofs and needs contacts on dofs with mass')
            return
         end if
         red%cslot(c) = prob%c_slot(c)
      end do
      allocate(red%ell(nr, red%nb), l(n))
      do b = 1, red%nb
         l = 0.0_dp
         if (b <= prob%n_slots) then
            l(prob%slot_dof(b)) = 1.0_dp
         else if (b == red%b_strain) then
            l = prob%sys%strain_row
         else
            if (prob%sys%tip_dof > 0) l(prob%sys%tip_dof) = 1.0_dp
         end if
         red%ell(:, b) = l(red%ir)
         if (ns > 0) red%ell(:, b) = red%ell(:, b) + matmul(transpose(red%t), l(red%is))
      end do
   end subroutine setup_reduction

   !> Full vector from the reduced one: x_s = T x_r.
   pure subroutine expand(red, xr, x)
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: xr(:)
      real(dp), intent(out) :: x(:)
      x(red%ir) = xr
      if (red%ns > 0) x(red%is) = matmul(red%t, xr)
   end subroutine expand

   !> Closed form (or Taylor fallback) of the configuration `mask`.
   subroutine build_config(prob, red, mask, climit, cf, err)
      type(problem_t), intent(in) :: prob
      type(reduced_t), intent(in) :: red
      integer(int64), intent(in) :: mask
      real(dp), intent(in) :: climit                    ! eigenvector condition limit
      type(config_t), intent(out) :: cf
      type(error_t), allocatable, intent(inout) :: err
      integer :: nr, nn, c, i, j, info, lwork, p, b
      real(dp), allocatable :: ke(:, :), ce(:, :), b0(:), kf(:, :), a2(:, :), y2(:, :), &
         g(:, :), h(:, :), amat(:, :), wr(:), wi(:), vr(:, :), vl(:, :), work(:), rs(:)
      complex(dp), allocatable :: w(:, :), winv(:, :), wcopy(:, :)
      integer, allocatable :: ipiv(:)
      real(dp) :: amp, om, query(1), n1, n2, n3, re_mu, im_mu, im2
      complex(dp), allocatable :: qm(:, :), phq(:, :)
      integer, allocatable :: ip2(:), jidx(:)
      integer :: it, q
      character(len=:), allocatable :: where
      where = 'gapbeam_exact:run_exact: configuration ' // mask_text(mask, prob%n_contacts)
      nr = red%nr;  nn = 2 * nr
      om = prob%omega
      cf%mask = mask
      ke = red%kr;  ce = red%cr
      allocate(b0(nr), source=0.0_dp)
      do c = 1, prob%n_contacts
         if (.not. btest(mask, c - 1)) cycle
         i = red%cpos(c)
         ke(i, i) = ke(i, i) + prob%c_k(c)
         ce(i, i) = ce(i, i) + prob%c_c(c)
         b0(i) = b0(i) + prob%c_sign(c) * prob%c_k(c) * prob%c_gap(c)
      end do
      ! static part x_c = (Ke^-1 b0, 0)
      kf = ke
      call dpotrf('U', nr, kf, nr, info)
      allocate(cf%xc(nn), source=0.0_dp)
      if (info == 0) then
         cf%xc(1:nr) = b0
         call dpotrs('U', nr, 1, kf, nr, cf%xc, nr, info)
      end if
      if (info /= 0) then
         call fatal_error(err, where // ': the stiffness is not positive definite (info=' &
            // str(info) // ')')
         return
      end if
      ! harmonic particular solution: (Ke - W^2 M + i W Ce) Y = F, u = Re(-i Y e^{iWt})
      amp = prob%half_amplitude * om**2
      allocate(cf%xh(nn), source=(0.0_dp, 0.0_dp))
      if (amp /= 0.0_dp) then
         allocate(a2(nn, nn), y2(nn, 1), ipiv(nn))
         a2(1:nr, 1:nr) = ke - om**2 * red%mr
         a2(nr + 1:, nr + 1:) = a2(1:nr, 1:nr)
         a2(1:nr, nr + 1:) = -om * ce
         a2(nr + 1:, 1:nr) = om * ce
         y2 = 0.0_dp
         y2(1:nr, 1) = amp * red%qr
         call dgesv(nn, 1, a2, nn, ipiv, y2, nn, info)
         if (info /= 0) then
            call fatal_error(err, where // ': the forcing frequency is a natural frequency ' &
               // 'of an undamped configuration (dgesv info=' // str(info) // '); no ' &
               // 'periodic particular solution')
            return
         end if
         cf%xh(1:nr) = cmplx(y2(nr + 1:, 1), -y2(1:nr, 1), dp)     ! -i Y
         cf%xh(nr + 1:) = om * cmplx(y2(1:nr, 1), y2(nr + 1:, 1), dp)   ! i W (-i Y)
      end if
      ! A = [0 I; -M^-1 Ke, -M^-1 Ce]
      g = ke;  h = ce
      call dpotrs('U', nr, nr, red%mfac, nr, g, nr, info)
      call dpotrs('U', nr, nr, red%mfac, nr, h, nr, info)
      allocate(amat(nn, nn), source=0.0_dp)
      do i = 1, nr
         amat(i, nr + i) = 1.0_dp
      end do
      amat(nr + 1:, 1:nr) = -g
      amat(nr + 1:, nr + 1:) = -h
      cf%amat = amat
      cf%absamat = abs(amat)
      allocate(cf%bsv(nn), cf%b0v(nn), source=0.0_dp)
      cf%bsv(nr + 1:) = amp * red%qr
      cf%b0v(nr + 1:) = b0
      call dpotrs('U', nr, 1, red%mfac, nr, cf%bsv(nr + 1:), nr, info)
      call dpotrs('U', nr, 1, red%mfac, nr, cf%b0v(nr + 1:), nr, info)
      ! eigen decomposition
      allocate(wr(nn), wi(nn), vr(nn, nn), vl(1, 1))
      call dgeev('N', 'V', nn, amat, nn, wr, wi, vl, 1, vr, nn, query, -1, info)
      lwork = max(1, int(query(1)))
      allocate(work(lwork))
      call dgeev('N', 'V', nn, amat, nn, wr, wi, vl, 1, vr, nn, work, lwork, info)
      if (info /= 0) then
         call fatal_error(err, where // ': dgeev failed, info=' // str(info))
         return
      end if
      allocate(w(nn, nn))
      j = 1
      do while (j <= nn)
         if (wi(j) == 0.0_dp .or. j == nn) then
            w(:, j) = cmplx(vr(:, j), 0.0_dp, dp)
            j = j + 1
         else
            w(:, j) = cmplx(vr(:, j), vr(:, j + 1), dp)
            w(:, j + 1) = conjg(w(:, j))
            j = j + 2
         end if
      end do
      wcopy = w
      allocate(winv(nn, nn), source=(0.0_dp, 0.0_dp))
      do i = 1, nn
         winv(i, i) = (1.0_dp, 0.0_dp)
      end do
      if (.not. allocated(ipiv)) allocate(ipiv(nn))
      call zgesv(nn, nn, wcopy, nn, ipiv, winv, nn, info)
      ! row-equilibrated 1-norm condition number
      allocate(rs(nn))
      do i = 1, nn
         rs(i) = max(maxval(abs(w(i, :))), tiny(1.0_dp))
      end do
      n1 = 0.0_dp;  n2 = 0.0_dp
      do j = 1, nn
         n1 = max(n1, sum(abs(w(:, j)) / rs))
         n2 = max(n2, rs(j) * sum(abs(winv(:, j))))
      end do
      cf%cond = n1 * n2
      if (info /= 0) cf%cond = huge(1.0_dp)
      if (.not. (cf%cond <= climit) .and. climit < huge(1.0_dp)) then
         call build_taylor(red, om, amp, g, h, b0, cf)
         return
      end if
      ! keep one eigenvalue of each pair
      p = count(wi >= 0.0_dp)
      allocate(cf%mu(p), cf%fac(p), cf%wh(nn, p), cf%winv(p, nn))
      p = 0
      j = 1
      do while (j <= nn)
         p = p + 1
         cf%mu(p) = cmplx(wr(j), wi(j), dp)
         cf%wh(:, p) = w(:, j)
         cf%winv(p, :) = winv(j, :)
         if (wi(j) == 0.0_dp .or. j == nn) then
            cf%fac(p) = 1.0_dp
            j = j + 1
         else
            cf%fac(p) = 2.0_dp
            j = j + 2
         end if
      end do
      cf%p = p
      cf%mu = cf%mu(1:p);  cf%fac = cf%fac(1:p)
      allocate(jidx(p))
      ! the real part of a complex eigenvalue of the symmetric quadratic problem
      ! (lambda^2 M + lambda C + K) phi = 0 is exactly -phi^H C phi / (2 phi^H M phi): taken
      ! from the computed shape it is accurate to the shape's error squared (dgeev's own is
      ! off by ~eps ||A||, an energy drift of ~1e-13 per second without damping), and it is
      ! exactly 0 for an undamped configuration
      ! The imaginary part likewise: dgeev's is off by ~eps ||A|| in absolute terms, i.e. by
      ! eps omega_max^2 / omega relative for a low mode of a stiff model (4e-11 for the first
      ! mode of 15 elements: a phase error of 1e-9 over ten periods), while the root of
      ! phi^H (lambda^2 M + lambda C + K) phi = 0 is again accurate to the shape's error squared.
      ! It is taken unless the discriminant cancels (a nearly critically damped pair).
      do it = 1, 2
      if (it == 2) then
         ! one step of inverse iteration on each complex shape with the refined eigenvalue,
         ! (K + mu C + mu^2 M) phi' = M phi, then W^-1 again
         allocate(qm(nr, nr), phq(nr, 1), ip2(nr))
         do j = 1, p
            if (aimag(cf%mu(j)) == 0.0_dp) cycle
            qm = ke + cf%mu(j) * ce + cf%mu(j)**2 * red%mr
            phq(:, 1) = matmul(red%mr, cf%wh(1:nr, j))
            call zgesv(nr, 1, qm, nr, ip2, phq, nr, info)
            if (info /= 0) cycle
            if (.not. (maxval(abs(phq)) > 0.0_dp)) cycle
            phq = phq * (maxval(abs(cf%wh(1:nr, j))) / maxval(abs(phq)))
            cf%wh(1:nr, j) = phq(:, 1)
            cf%wh(nr + 1:, j) = cf%mu(j) * phq(:, 1)
         end do
         q = 0
         do j = 1, p
            q = q + 1
            w(:, q) = cf%wh(:, j)
            jidx(j) = q
            if (cf%fac(j) == 2.0_dp) then
               q = q + 1
               w(:, q) = conjg(cf%wh(:, j))
            end if
         end do
         wcopy = w
         winv = (0.0_dp, 0.0_dp)
         do i = 1, nn
            winv(i, i) = (1.0_dp, 0.0_dp)
         end do
         call zgesv(nn, nn, wcopy, nn, ipiv, winv, nn, info)
         do j = 1, p
            cf%winv(j, :) = winv(jidx(j), :)
         end do
      end if
      do j = 1, p
         if (aimag(cf%mu(j)) == 0.0_dp) cycle
         n1 = real(dot_product(cf%wh(1:nr, j), matmul(ce, cf%wh(1:nr, j))))
         n2 = real(dot_product(cf%wh(1:nr, j), matmul(red%mr, cf%wh(1:nr, j))))
         n3 = real(dot_product(cf%wh(1:nr, j), matmul(ke, cf%wh(1:nr, j))))
         if (n2 > 0.0_dp) then
            re_mu = -0.5_dp * n1 / n2
            im2 = n3 / n2 - re_mu**2
            im_mu = aimag(cf%mu(j))
            if (im2 > 0.25_dp * (n3 / n2)) im_mu = sqrt(im2)
            cf%mu(j) = cmplx(re_mu, im_mu, dp)
         end if
      end do
      end do
      cf%wh = cf%wh(:, 1:p);  cf%winv = cf%winv(1:p, :)
      allocate(cf%lrow(p, red%nb), cf%lh(red%nb), cf%lc(red%nb))
      do b = 1, red%nb
         do j = 1, p
            cf%lrow(j, b) = sum(red%ell(:, b) * cf%wh(1:nr, j))
         end do
         cf%lh(b) = sum(red%ell(:, b) * cf%xh(1:nr))
         cf%lc(b) = sum(red%ell(:, b) * cf%xc(1:nr))
      end do
   end subroutine build_config

   !> Augmented balanced matrix of the Taylor fallback.
   subroutine build_taylor(red, om, amp, g, h, b0, cf)
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: om, amp
      real(dp), intent(in) :: g(:, :), h(:, :), b0(:)   ! M^-1 Ke, M^-1 Ce, gap load
      type(config_t), intent(inout) :: cf
      integer :: nr, na, i, info
      real(dp), allocatable :: f(:, :)
      nr = red%nr;  na = 2 * nr + 3
      cf%modal = .false.
      cf%omega_s = sqrt(maxval(sum(abs(g), dim=2)))
      if (.not. (cf%omega_s > 0.0_dp)) cf%omega_s = 1.0_dp
      cf%alpha = max(maxval(abs(cf%xh(1:nr))), maxval(abs(cf%xc(1:nr))))
      if (.not. (cf%alpha > 0.0_dp)) cf%alpha = 1.0_dp
      allocate(f(nr, 2))
      f(:, 1) = amp * red%qr;  f(:, 2) = b0
      call dpotrs('U', nr, 2, red%mfac, nr, f, nr, info)
      allocate(cf%ahat(na, na), source=0.0_dp)
      do i = 1, nr
         cf%ahat(i, nr + i) = cf%omega_s
      end do
      cf%ahat(nr + 1:2 * nr, 1:nr) = -g / cf%omega_s
      cf%ahat(nr + 1:2 * nr, nr + 1:2 * nr) = -h
      cf%ahat(nr + 1:2 * nr, 2 * nr + 1) = f(:, 1) / (cf%omega_s * cf%alpha)
      cf%ahat(nr + 1:2 * nr, 2 * nr + 3) = f(:, 2) / (cf%omega_s * cf%alpha)
      cf%ahat(2 * nr + 1, 2 * nr + 2) = om
      cf%ahat(2 * nr + 2, 2 * nr + 1) = -om
      cf%nrm = sqrt(sum(cf%ahat**2))
      cf%hsub = 0.5_dp / cf%nrm
   end subroutine build_taylor

   !> 'contacts {1, 3} active' style text of a mask.
   function mask_text(mask, nc) result(s)
      integer(int64), intent(in) :: mask
      integer, intent(in) :: nc
      character(len=:), allocatable :: s
      integer :: c
      s = '(active contacts:'
      do c = 1, nc
         if (btest(mask, c - 1)) s = s // ' ' // str(c)
      end do
      if (mask == 0) s = s // ' none'
      s = s // ')'
   end function mask_text

   ! ------------------------------------------------------------------ segments

   !> Coefficients of the segment starting from x0 at forcing offset r0.
   subroutine start_segment(cf, red, om, x0, r0, sg)
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: om, x0(:), r0
      type(segment_t), intent(inout) :: sg
      integer :: p, nt, j, b, nr, na
      complex(dp) :: ph
      real(dp), allocatable :: rhs(:), z(:), res(:)
      nr = red%nr
      sg%modal = cf%modal
      sg%n_eval = 0
      if (.not. cf%modal) then
         na = 2 * nr + 3
         if (.not. allocated(sg%pw)) then
            allocate(sg%pw(na, 0:n_taylor), sg%pc(0:n_taylor, red%nb), sg%elln(red%nb))
         else if (size(sg%pw, 1) /= na) then
            deallocate(sg%pw, sg%pc, sg%elln)
            allocate(sg%pw(na, 0:n_taylor), sg%pc(0:n_taylor, red%nb), sg%elln(red%nb))
         end if
         do b = 1, red%nb
            sg%elln(b) = norm2(red%ell(:, b))
         end do
         allocate(z(na))
         z(1:nr) = x0(1:nr)
         z(nr + 1:2 * nr) = x0(nr + 1:) / cf%omega_s
         z(2 * nr + 1) = cf%alpha * sin(om * r0)
         z(2 * nr + 2) = cf%alpha * cos(om * r0)
         z(2 * nr + 3) = cf%alpha
         sg%tk = 0.0_dp
         call taylor_load(sg, cf, red, z)
         return
      end if
      p = cf%p
      nt = p + 1
      if (allocated(sg%mu)) then
         if (size(sg%mu) /= nt .or. size(sg%a, 2) /= red%nb) deallocate(sg%mu, sg%mp, sg%am, &
            sg%c, sg%a, sg%absa, sg%a0, sg%live, sg%real_term, sg%me, sg%e)
      end if
      if (.not. allocated(sg%mu)) allocate(sg%mu(nt), sg%mp(3, nt), sg%am(0:4, nt), sg%c(nt), &
         sg%a(nt, red%nb), sg%absa(nt, red%nb), sg%a0(red%nb), sg%live(nt), sg%real_term(nt), &
         sg%me(nt), sg%e(nt))
      sg%nt = nt
      sg%n_recur = 0;  sg%tau_last = 0.0_dp
      ph = cmplx(cos(om * r0), sin(om * r0), dp)
      rhs = x0 - cf%xc - real(cf%xh * ph)
      sg%mu(1:p) = cf%mu
      sg%mu(nt) = cmplx(0.0_dp, om, dp)
      do j = 1, p
         sg%c(j) = cf%fac(j) * sum(cf%winv(j, :) * rhs)
      end do
      ! one step of iterative refinement: the residual of the reconstruction, projected again
      ! (the explicit inverse alone leaves ~cond(W) eps; this brings it to ~eps)
      res = rhs
      do j = 1, p
         res = res - real(sg%c(j) * cf%wh(:, j))
      end do
      do j = 1, p
         sg%c(j) = sg%c(j) + cf%fac(j) * sum(cf%winv(j, :) * res)
      end do
      sg%c(nt) = ph
      do j = 1, nt
         sg%mp(1, j) = sg%mu(j)
         sg%mp(2, j) = sg%mu(j)**2
         sg%mp(3, j) = sg%mu(j)**3
         sg%am(0, j) = 1.0_dp
         sg%am(1, j) = abs(sg%mu(j))
         sg%am(2, j) = sg%am(1, j)**2
         sg%am(3, j) = sg%am(1, j)**3
         sg%am(4, j) = sg%am(2, j)**2
         sg%real_term(j) = aimag(sg%mu(j)) == 0.0_dp
      end do
      do b = 1, red%nb
         sg%a(1:p, b) = sg%c(1:p) * cf%lrow(:, b)
         sg%a(nt, b) = cf%lh(b) * ph
         sg%a0(b) = cf%lc(b)
      end do
      sg%absa = abs(sg%a)
      sg%mu_max = maxval(sg%am(1, :))
      sg%live = sg%absa(:, 1) >= 0.0_dp
      sg%live(nt) = cf%lh(1) /= (0.0_dp, 0.0_dp) .or. any(cf%xh /= (0.0_dp, 0.0_dp))
   end subroutine start_segment

   !> Values (derivatives 0..3) and bounds (0..4) of the needed functionals at tau.
   subroutine eval_seg(sg, cf, red, tau, need, val, bnd)
      type(segment_t), intent(inout) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: tau
      logical, intent(in) :: need(:)
      real(dp), intent(out) :: val(0:, :), bnd(0:, :)
      integer :: j, b, m, k
      real(dp) :: me, er, ei, zr, zi, mag, s, acc(0:3), fall, dt, v0, v1, v2, v3, u0, u1, u2, &
         u3, u4
      complex(dp) :: zd, ez
      logical :: recur
      val = 0.0_dp;  bnd = 0.0_dp
      if (.not. sg%modal) then
         s = tau - sg%tk
         do b = 1, red%nb
            if (.not. need(b)) cycle
            acc = 0.0_dp
            do m = n_taylor, 0, -1
               do k = 0, 3
                  if (m < k) cycle
                  fall = 1.0_dp
                  if (k >= 1) fall = real(m, dp)
                  if (k >= 2) fall = fall * real(m - 1, dp)
                  if (k >= 3) fall = fall * real(m - 2, dp)
                  acc(k) = acc(k) * s + fall * sg%pc(m, b)
               end do
            end do
            val(:, b) = acc
            do k = 0, 4
               bnd(k, b) = sg%elln(b) * cf%nrm**k * sg%zbound
            end do
         end do
         return
      end if
      sg%n_eval = sg%n_eval + 1
      ! close to the last instant every e^{mu tau} follows from the last one times the Taylor
      ! series of e^{mu dt} (|mu dt| <= 1/16: degree 10 is exact to 1e-18), at most 4 times in
      ! a row (the products accumulate a few ulps); otherwise exp, cos and sin
      dt = tau - sg%tau_last
      recur = sg%n_recur < 4 .and. abs(dt) * sg%mu_max <= 0.0625_dp .and. sg%n_eval > 1
      if (recur) then
         sg%n_recur = sg%n_recur + 1
      else
         sg%n_recur = 0
      end if
      sg%tau_last = tau
      do j = 1, sg%nt
         if (.not. sg%live(j)) cycle
         if (recur) then
            zd = sg%mu(j) * dt
            ez = (1.0_dp, 0.0_dp) + zd * inv_k(10)
            do k = 9, 1, -1
               ez = (1.0_dp, 0.0_dp) + (zd * inv_k(k)) * ez
            end do
            sg%e(j) = sg%e(j) * ez
            er = real(sg%e(j));  ei = aimag(sg%e(j))
            me = sqrt(er**2 + ei**2)
         else
            me = exp(real(sg%mu(j)) * tau)
            if (sg%real_term(j)) then
               er = me;  ei = 0.0_dp
            else
               er = me * cos(aimag(sg%mu(j)) * tau)
               ei = me * sin(aimag(sg%mu(j)) * tau)
            end if
            sg%e(j) = cmplx(er, ei, dp)
         end if
         sg%me(j) = me
      end do
      ! sums per functional, in scalars
      do b = 1, size(need)
         if (.not. need(b)) cycle
         v0 = sg%a0(b);  v1 = 0.0_dp;  v2 = 0.0_dp;  v3 = 0.0_dp
         u0 = abs(sg%a0(b));  u1 = 0.0_dp;  u2 = 0.0_dp;  u3 = 0.0_dp;  u4 = 0.0_dp
         do j = 1, sg%nt
            if (.not. sg%live(j)) cycle
            er = real(sg%e(j));  ei = aimag(sg%e(j))
            zr = real(sg%a(j, b)) * er - aimag(sg%a(j, b)) * ei
            zi = real(sg%a(j, b)) * ei + aimag(sg%a(j, b)) * er
            v0 = v0 + zr
            v1 = v1 + zr * real(sg%mp(1, j)) - zi * aimag(sg%mp(1, j))
            v2 = v2 + zr * real(sg%mp(2, j)) - zi * aimag(sg%mp(2, j))
            v3 = v3 + zr * real(sg%mp(3, j)) - zi * aimag(sg%mp(3, j))
            mag = sg%absa(j, b) * sg%me(j)
            u0 = u0 + mag
            u1 = u1 + mag * sg%am(1, j)
            u2 = u2 + mag * sg%am(2, j)
            u3 = u3 + mag * sg%am(3, j)
            u4 = u4 + mag * sg%am(4, j)
         end do
         val(0, b) = v0;  val(1, b) = v1;  val(2, b) = v2;  val(3, b) = v3
         bnd(0, b) = u0;  bnd(1, b) = u1;  bnd(2, b) = u2;  bnd(3, b) = u3;  bnd(4, b) = u4
      end do
      if (mod(sg%n_eval, 8) == 0) call prune(sg)
   end subroutine eval_seg

   !> Drop the decaying terms that no longer matter to any functional (below prune_tol of
   !> its current size, value and first derivative).
   subroutine prune(sg)
      type(segment_t), intent(inout) :: sg
      integer :: j, b, nb
      real(dp) :: s0, s1
      logical :: keep(sg%nt)
      nb = size(sg%a, 2)
      keep = .false.
      keep(sg%nt) = sg%live(sg%nt)
      do b = 1, nb
         s0 = abs(sg%a0(b));  s1 = 0.0_dp
         do j = 1, sg%nt
            if (.not. sg%live(j)) cycle
            s0 = s0 + sg%absa(j, b) * sg%me(j)
            s1 = s1 + sg%absa(j, b) * sg%me(j) * sg%am(1, j)
         end do
         do j = 1, sg%nt - 1
            if (.not. sg%live(j) .or. keep(j)) cycle
            if (sg%absa(j, b) * sg%me(j) > prune_tol * s0 .or. &
                sg%absa(j, b) * sg%me(j) * sg%am(1, j) > prune_tol * s1) keep(j) = .true.
         end do
      end do
      do j = 1, sg%nt - 1
         if (sg%live(j) .and. real(sg%mu(j)) < 0.0_dp .and. .not. keep(j)) sg%live(j) = .false.
      end do
   end subroutine prune

   !> Full reduced state x = (u, v) and acceleration at tau (every term).
   subroutine segment_state(sg, cf, red, om, tau, x, acc)
      type(segment_t), intent(in) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: om, tau
      real(dp), intent(out) :: x(:), acc(:)      ! (2 nr), (nr)
      integer :: j, nr, m
      complex(dp) :: e
      real(dp), allocatable :: zv(:), zd(:)
      nr = red%nr
      if (.not. sg%modal) then
         zv = sg%pw(:, n_taylor);  zd = real(n_taylor, dp) * sg%pw(:, n_taylor)
         do m = n_taylor - 1, 0, -1
            zv = zv * (tau - sg%tk) + sg%pw(:, m)
            if (m >= 1) zd = zd * (tau - sg%tk) + real(m, dp) * sg%pw(:, m)
         end do
         x(1:nr) = zv(1:nr)
         x(nr + 1:) = cf%omega_s * zv(nr + 1:2 * nr)
         acc = cf%omega_s * zd(nr + 1:2 * nr)
         return
      end if
      x = cf%xc
      acc = 0.0_dp
      do j = 1, cf%p
         e = sg%c(j) * exp(sg%mu(j) * tau)
         x = x + real(e * cf%wh(:, j))
         acc = acc + real(e * sg%mu(j) * cf%wh(nr + 1:, j))
      end do
      e = sg%c(sg%nt) * exp(sg%mu(sg%nt) * tau)
      x = x + real(e * cf%xh)
      acc = acc + real(e * cmplx(0.0_dp, om, dp) * cf%xh(nr + 1:))
   end subroutine segment_state

   !> Load the Taylor sub-step starting from z.
   subroutine taylor_load(sg, cf, red, z)
      type(segment_t), intent(inout) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: z(:)
      integer :: m, b, nr
      nr = red%nr
      sg%pw(:, 0) = z
      do m = 1, n_taylor
         sg%pw(:, m) = matmul(cf%ahat, sg%pw(:, m - 1)) / real(m, dp)
      end do
      do b = 1, red%nb
         do m = 0, n_taylor
            sg%pc(m, b) = sum(red%ell(:, b) * sg%pw(1:nr, m))
         end do
      end do
      sg%zbound = norm2(z) * exp(cf%nrm * cf%hsub)
   end subroutine taylor_load

   !> Move the Taylor expansion to the next sub-step.
   subroutine taylor_next(sg, cf, red)
      type(segment_t), intent(inout) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), allocatable :: z(:)
      integer :: m
      z = sg%pw(:, n_taylor)
      do m = n_taylor - 1, 0, -1
         z = z * cf%hsub + sg%pw(:, m)
      end do
      sg%tk = sg%tk + cf%hsub
      call taylor_load(sg, cf, red, z)
   end subroutine taylor_next

   ! ------------------------------------------------------------------ statistics

   !> Closed-form integrals over [ta, tb] of f, f^2 and f |d'| for one active contact
   !> (f = k d + c d', d = s u - g), the phase split at the zeros of d' in `roots`.
   subroutine modal_window(sg, b, s, kc, cc, gap, ta, tb, roots, sf, sf2, sw)
      type(segment_t), intent(in) :: sg
      integer, intent(in) :: b
      real(dp), intent(in) :: s, kc, cc, gap, ta, tb, roots(:)
      real(dp), intent(out) :: sf, sf2, sw
      complex(dp) :: pf(sg%nt), pd(sg%nt)
      real(dp) :: f0, pa, pb, da, db, sgn, mid
      integer :: j, k, nt
      nt = sg%nt
      do j = 1, nt
         pf(j) = s * (kc + cc * sg%mu(j)) * sg%a(j, b)
         pd(j) = s * sg%mu(j) * sg%a(j, b)
      end do
      if (.not. sg%live(nt)) then
         pf(nt) = 0.0_dp;  pd(nt) = 0.0_dp
      end if
      f0 = kc * (s * sg%a0(b) - gap)
      sf = lin_integral(sg%mu, pf, f0, ta, tb)
      sf2 = prod_integral(sg%mu, pf, f0, pf, f0, ta, tb)
      sw = 0.0_dp
      pa = ta
      do k = 1, size(roots) + 1
         if (k <= size(roots)) then
            pb = min(max(roots(k), pa), tb)
         else
            pb = tb
         end if
         if (pb > pa) then
            mid = 0.5_dp * (pa + pb)
            sgn = sign(1.0_dp, modal_value(sg%mu, pd, 0.0_dp, mid))
            if (cc == 0.0_dp) then
               da = s * modal_value(sg%mu, sg%a(:, b), sg%a0(b), pa) - gap
               db = s * modal_value(sg%mu, sg%a(:, b), sg%a0(b), pb) - gap
               sw = sw + sgn * 0.5_dp * kc * (db**2 - da**2)
            else
               sw = sw + sgn * prod_integral(sg%mu, pf, f0, pd, 0.0_dp, pa, pb)
            end if
         end if
         pa = pb
      end do
   end subroutine modal_window

   !> Re(sum_j a_j e^{mu_j tau}) + a0.
   pure real(dp) function modal_value(mu, a, a0, tau) result(v)
      complex(dp), intent(in) :: mu(:), a(:)
      real(dp), intent(in) :: a0, tau
      integer :: j
      v = a0
      do j = 1, size(mu)
         if (a(j) /= (0.0_dp, 0.0_dp)) v = v + real(a(j) * exp(mu(j) * tau))
      end do
   end function modal_value

   !> (e^z - 1) / z, given ez = e^z (series near 0).
   pure complex(dp) function phi1(z, ez)
      complex(dp), intent(in) :: z, ez
      complex(dp) :: term
      integer :: m
      if (real(z)**2 + aimag(z)**2 < 0.0625_dp) then
         phi1 = (1.0_dp, 0.0_dp);  term = (1.0_dp, 0.0_dp)
         do m = 2, 14
            term = term * z / real(m, dp)
            phi1 = phi1 + term
         end do
      else
         phi1 = (ez - 1.0_dp) / z
      end if
   end function phi1

   !> Integral over [ta, tb] of Re(sum_j p_j e^{mu_j tau}) + p0.
   pure real(dp) function lin_integral(mu, p, p0, ta, tb) result(s)
      complex(dp), intent(in) :: mu(:), p(:)
      real(dp), intent(in) :: p0, ta, tb
      integer :: j
      real(dp) :: l
      l = tb - ta
      s = p0 * l
      do j = 1, size(mu)
         if (p(j) == (0.0_dp, 0.0_dp)) cycle
         s = s + real(p(j) * exp(mu(j) * ta) * l * phi1(mu(j) * l, exp(mu(j) * l)))
      end do
   end function lin_integral

   !> Integral over [ta, tb] of (Re(sum p e^{mu tau}) + p0)(Re(sum q e^{mu tau}) + q0), in
   !> closed form: Re(a) Re(b) = (Re(a b) + Re(a conj(b))) / 2.
   pure real(dp) function prod_integral(mu, p, p0, q, q0, ta, tb) result(s)
      complex(dp), intent(in) :: mu(:), p(:), q(:)
      real(dp), intent(in) :: p0, q0, ta, tb
      complex(dp) :: ea(size(mu)), el(size(mu)), pa(size(mu)), qa(size(mu)), ph(size(mu))
      real(dp) :: l, sp, sq, cut, mp(size(mu)), mq(size(mu)), w
      integer :: j, k, n
      logical :: same
      same = all(p == q) .and. p0 == q0
      n = size(mu)
      l = tb - ta
      do j = 1, n
         ea(j) = exp(mu(j) * ta)
         el(j) = exp(mu(j) * l)
         pa(j) = p(j) * ea(j)
         qa(j) = q(j) * ea(j)
         ph(j) = l * phi1(mu(j) * l, el(j))
      end do
      do j = 1, n
         mp(j) = abs(real(pa(j))) + abs(aimag(pa(j)))
         mq(j) = abs(real(qa(j))) + abs(aimag(qa(j)))
      end do
      sp = sum(mp) + abs(p0);  sq = sum(mq) + abs(q0)
      cut = 1.0e-18_dp * sp * sq
      s = p0 * q0 * l
      do j = 1, n
         s = s + p0 * real(qa(j) * ph(j)) + q0 * real(pa(j) * ph(j))
      end do
      do j = 1, n
         if (mp(j) * sq <= cut) cycle
         ! a square (p = q) is symmetric in j, k: the pair counted once, twice
         do k = merge(j, 1, same), n
            if (mp(j) * mq(k) <= cut) cycle
            w = 0.5_dp
            if (same .and. k > j) w = 1.0_dp
            s = s + w * real(pa(j) * qa(k) * l * phi1((mu(j) + mu(k)) * l, el(j) * el(k)) &
                + pa(j) * conjg(qa(k)) * l * phi1((mu(j) + conjg(mu(k))) * l, &
                el(j) * conjg(el(k))))
         end do
      end do
   end function prod_integral

   !> Gauss-Legendre integrals over [ta, tb] (inside the current Taylor sub-step) of f, f^2
   !> and f |d'| for one active contact, split at the zeros of d'.
   subroutine taylor_window(sg, b, s, kc, cc, gap, ta, tb, roots, xg, wg, sf, sf2, sw)
      type(segment_t), intent(in) :: sg
      integer, intent(in) :: b
      real(dp), intent(in) :: s, kc, cc, gap, ta, tb, roots(:), xg(:), wg(:)
      real(dp), intent(out) :: sf, sf2, sw
      real(dp) :: pa, pb, tau, u, du, d, dd, f, half, mid, x
      integer :: k, q, m
      sf = 0.0_dp;  sf2 = 0.0_dp;  sw = 0.0_dp
      pa = ta
      do k = 1, size(roots) + 1
         if (k <= size(roots)) then
            pb = min(max(roots(k), pa), tb)
         else
            pb = tb
         end if
         if (pb > pa) then
            half = 0.5_dp * (pb - pa);  mid = 0.5_dp * (pa + pb)
            do q = 1, size(xg)
               tau = mid + half * xg(q)
               x = tau - sg%tk
               u = 0.0_dp;  du = 0.0_dp
               do m = n_taylor, 0, -1
                  u = u * x + sg%pc(m, b)
                  if (m >= 1) du = du * x + real(m, dp) * sg%pc(m, b)
               end do
               d = s * u - gap;  dd = s * du
               f = kc * d + cc * dd
               sf = sf + half * wg(q) * f
               sf2 = sf2 + half * wg(q) * f**2
               sw = sw + half * wg(q) * f * abs(dd)
            end do
         end if
         pa = pb
      end do
   end subroutine taylor_window

   !> Nodes and weights of n-point Gauss-Legendre on [-1, 1].
   pure subroutine gauss_legendre(x, w)
      real(dp), intent(out) :: x(:), w(:)
      integer :: n, i, k, it
      real(dp) :: z, p0, p1, p2, dp1
      n = size(x)
      do i = 1, n
         z = cos(pi * (real(i, dp) - 0.25_dp) / (real(n, dp) + 0.5_dp))
         do it = 1, 100
            p0 = 1.0_dp;  p1 = z
            do k = 2, n
               p2 = (real(2 * k - 1, dp) * z * p1 - real(k - 1, dp) * p0) / real(k, dp)
               p0 = p1;  p1 = p2
            end do
            dp1 = real(n, dp) * (z * p1 - p0) / (z**2 - 1.0_dp)
            if (abs(p1 / dp1) < 1.0e-16_dp) then
               z = z - p1 / dp1;  exit
            end if
            z = z - p1 / dp1
         end do
         x(i) = z
         w(i) = 2.0_dp / ((1.0_dp - z**2) * dp1**2)
      end do
   end subroutine gauss_legendre

   ! ------------------------------------------------------------------ safe steps

   !> Sign of a function just after an instant from its value and derivatives (0 if all are
   !> zero to round-off of their scales).
   pure integer function sign_after(v, scl)
      real(dp), intent(in) :: v(0:), scl(0:)
      integer :: k
      sign_after = 0
      do k = 0, ubound(v, 1)
         if (abs(v(k)) > zero_tol * scl(k)) then
            sign_after = int(sign(1.0_dp, v(k)))
            return
         end if
      end do
   end function sign_after

   !> Dead band of a function starting within round-off of zero on the wrong side.
   pure real(dp) function band(y, scl)
      real(dp), intent(in) :: y, scl
      band = 0.0_dp
      if (y <= 0.0_dp) band = 2.0_dp * abs(y) + zero_tol * scl
   end function band

   !> Largest h with y + y1 s + y2 s^2/2 + ... >= 0 on [0, h] guaranteed by the bounds
   !> |phi''| <= b2 (quadratic) or |phi'''| <= b3 (cubic).
   pure real(dp) function root_step(y, y1, y2, b2, b3, cap) result(h)
      real(dp), intent(in) :: y, y1, y2, b2, b3
      real(dp), intent(in) :: cap           ! a step this long is enough
      h = 0.0_dp
      if (.not. (y > 0.0_dp)) return
      h = quad_root(y, y1, b2)
      if (h >= cap) return
      if (y2 > -0.5_dp * b2 .and. b3 > 0.0_dp) h = max(h, cubic_root(y, y1, 0.5_dp * y2, &
                                                                      b3 / 6.0_dp, cap))
   end function root_step

   !> Safe step of a running maximum: y = M + tol - phi > 0, p1 = phi', p2 = phi''; either
   !> phi stays below M + tol (cubic/quadratic bound) or phi' keeps its sign (phi monotone,
   !> its maximum on the step at an end).
   pure real(dp) function max_step(y, p1, p2, b2, b3, cap) result(h)
      real(dp), intent(in) :: y, p1, p2, b2, b3
      real(dp), intent(in) :: cap           ! a step this long is enough
      h = 0.0_dp
      if (p1 /= 0.0_dp) h = quad_root(abs(p1), sign(1.0_dp, p1) * p2, b3)
      if (h >= cap) return
      h = max(h, root_step(y, -p1, -p2, b2, b3, cap))
   end function max_step

   !> Record a function to keep >= 0 for the step choice: value y0, derivatives y1, y2,
   !> |y''| <= b2, |y'''| <= b3, and a step hm known safe otherwise (monotone step of a
   !> running extremum); q gets its quadratic step.
   pure subroutine add_fn(nf, q, fy, fy1, fy2, fb2, fb3, y0, y1, y2, b2, b3, hm)
      integer, intent(inout) :: nf
      real(dp), intent(inout) :: q(:), fy(:), fy1(:), fy2(:), fb2(:), fb3(:)
      real(dp), intent(in) :: y0, y1, y2, b2, b3, hm
      nf = nf + 1
      fy(nf) = y0;  fy1(nf) = y1;  fy2(nf) = y2;  fb2(nf) = b2;  fb3(nf) = b3
      q(nf) = hm
      if (y0 > 0.0_dp) q(nf) = max(hm, quad_root(y0, y1, b2))
   end subroutine add_fn

   !> Step on which phi' (value p1, derivative p2, |phi'''| <= b3) keeps its sign.
   pure real(dp) function mono_quad(p1, p2, b3)
      real(dp), intent(in) :: p1, p2, b3
      mono_quad = 0.0_dp
      if (p1 /= 0.0_dp) mono_quad = quad_root(abs(p1), sign(1.0_dp, p1) * p2, b3)
   end function mono_quad

   !> First positive zero of y + y1 s - b s^2 / 2 (y > 0).
   pure real(dp) function quad_root(y, y1, b) result(h)
      real(dp), intent(in) :: y, y1, b
      real(dp) :: disc
      if (b <= 0.0_dp) then
         if (y1 >= 0.0_dp) then
            h = huge(1.0_dp)
         else
            h = y / (-y1)
         end if
         return
      end if
      disc = sqrt(y1**2 + 2.0_dp * b * y)
      if (y1 >= 0.0_dp) then
         h = (y1 + disc) / b
      else
         h = 2.0_dp * y / (disc - y1)
      end if
   end function quad_root

   !> A point at or below the first positive zero of P(s) = y + a s + b s^2 - c s^3 (y, c > 0),
   !> within 1e-3 relative.
   pure real(dp) function cubic_root(y, a, b, c, cap) result(h)
      real(dp), intent(in) :: y, a, b, c
      real(dp), intent(in) :: cap           ! stop once the answer is known to exceed this
      real(dp) :: lo, hi, disc, s1, s2, mid, plo, phi, pm
      integer :: it, side
      ! P decreases on [lo, hi] from P(lo) > 0 to P(hi) <= 0
      lo = 0.0_dp;  hi = -1.0_dp
      disc = b**2 + 3.0_dp * a * c
      if (disc > 0.0_dp) then
         s1 = (b - sqrt(disc)) / (3.0_dp * c)      ! local minimum
         s2 = (b + sqrt(disc)) / (3.0_dp * c)      ! local maximum
         if (s1 > 0.0_dp .and. poly(s1) <= 0.0_dp) then
            hi = s1
         else if (s2 > 0.0_dp) then
            lo = s2
         end if
      end if
      if (hi < 0.0_dp) then
         ! P decreases beyond lo: a zero past the cap does not matter
         if (lo >= cap) then
            h = lo;  return
         end if
         if (poly(cap) > 0.0_dp) then
            h = cap;  return
         end if
         hi = cap
      end if
      ! P > 0 at lo, P <= 0 at hi, a single zero in between: Illinois, keeping lo safe
      plo = poly(lo);  phi = poly(hi);  side = 0
      do it = 1, 60
         if (hi - lo <= 1.0e-3_dp * lo .or. lo >= cap) exit
         mid = lo + (hi - lo) * plo / (plo - phi)
         if (.not. (mid > lo .and. mid < hi)) mid = 0.5_dp * (lo + hi)
         pm = poly(mid)
         if (pm > 0.0_dp) then
            lo = mid;  plo = pm
            if (side == -1) phi = 0.5_dp * phi
            side = -1
         else
            hi = mid;  phi = pm
            if (side == 1) plo = 0.5_dp * plo
            side = 1
         end if
      end do
      h = lo
   contains
      pure real(dp) function poly(s)
         real(dp), intent(in) :: s
         poly = y + s * (a + s * (b - c * s))
      end function poly
   end function cubic_root
end module gapbeam_exact
