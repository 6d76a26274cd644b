!> A transient run of the Newmark gap solver: step-size control, contact-event location,
!> sampling of the history and the Poincare section, and the impact statistics.
!>
!> Time is counted in integer ticks of dt_max / 2^max_halvings, with dt_max = T /
!> steps_per_period (T the forcing period), so every step size the control uses is a power-of-
!> two fraction of dt_max, each has its factorization cached, and steps land exactly on the
!> forcing periods. A step is rejected and halved when the half-step residual exceeds the
!> tolerance (or the fixed point does not converge); the step doubles after `grow_after`
!> comfortable steps when the time is a multiple of the doubled step. With `locate_events`,
!> a step in which a contact opens or closes (penetration of the cubic Hermite interpolant of
!> the contact dof changes sign, grazing included) is split at that instant.
module gapbeam_transient
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_problem, only: problem_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t
   use gapbeam_newmark, only: half_step_ratio, state_load
   use gapbeam_stepper, only: stepper_t
   use gapbeam_integrators, only: make_stepper
   use gapbeam_contact, only: contact_force, law_bilinear
   use gapbeam_model, only: dof_name
   use gapbeam_lapack, only: dpotrf, dpotrs
   use gapbeam_filter, only: lowpass_t, design_lowpass
   implicit none
   private
   public :: transient_result_t, run_transient, initial_acceleration, dof_label, allocate_result

   integer, parameter :: max_sub = 8   ! sub-steps of one step at most (event splits)
   real(dp), parameter :: min_split = 1.0e-3_dp   ! no sub-step shorter than this fraction of a step

   !> Everything a transient run produces.
   type :: transient_result_t
      real(dp), allocatable :: time(:)              !! history sample times [s]
      real(dp), allocatable :: strain(:)            !! root strain [-]
      real(dp), allocatable :: strain_filtered(:)   !! low-pass filtered root strain (if asked) [-]
      real(dp), allocatable :: strain_rate(:)       !! root strain rate [1/s]
      real(dp), allocatable :: tip_displacement(:)  !! tip w relative to the base [m]
      real(dp), allocatable :: stop_force(:, :)     !! (samples, stops) contact force [N]
      real(dp), allocatable :: p_time(:)            !! Poincare sample times [s]
      real(dp), allocatable :: p_strain(:)          !! Poincare root strain [-]
      real(dp), allocatable :: p_strain_rate(:)     !! Poincare root strain rate [1/s]
      real(dp), allocatable :: p_tip(:)             !! Poincare tip displacement [m]
      real(dp), allocatable :: p_tip_velocity(:)    !! Poincare tip velocity [m/s]
      integer(int64) :: steps_accepted = 0          !! Newmark solves accepted (sub-steps too)
      integer(int64) :: steps_rejected = 0          !! steps rejected by the control
      integer(int64) :: events = 0                  !! steps split at a contact event
      integer(int64) :: factorizations = 0          !! Kbar factorizations
      integer(int64) :: fp_iterations = 0           !! fixed-point iterations
      real(dp) :: cpu_seconds = 0.0_dp              !! elapsed time of the run [s]
      real(dp) :: dt_smallest = 0.0_dp              !! smallest step used [s]
      real(dp) :: dt_largest = 0.0_dp               !! largest step used [s]
      integer, allocatable :: n_impacts(:)          !! per stop: contact onsets in the record
      real(dp), allocatable :: peak_force(:)        !! per stop [N]
      real(dp), allocatable :: rms_force(:)         !! per stop [N]
      real(dp), allocatable :: contact_fraction(:)  !! per stop: time in contact / record [-]
      real(dp), allocatable :: impulse_per_period(:)!! per stop [N s]
      real(dp), allocatable :: work_rate(:)         !! per stop: (1/T) int f |d'| dt [W]
      real(dp), allocatable :: first_contact_time(:) !! per stop: first onset, -1 if none [s]
      real(dp) :: strain_min = huge(1.0_dp)         !! root strain range over the record [-]
      real(dp) :: strain_max = -huge(1.0_dp)        !! (step ends) [-]
      real(dp) :: strain_rate_min = huge(1.0_dp)    !! root strain rate range [1/s]
      real(dp) :: strain_rate_max = -huge(1.0_dp)   !! [1/s]
      real(dp), allocatable :: u(:), v(:), a(:)     !! final state
      real(dp) :: t_end = 0.0_dp                    !! final time [s]
   end type transient_result_t

contains

   !> Allocate the result arrays: history (n_hist samples), Poincare (n_poinc points) and the
   !> per-stop statistics (ns stops), zeroed; first contact times -1 (none yet).
   subroutine allocate_result(res, n_hist, n_poinc, ns)
      type(transient_result_t), intent(inout) :: res   !! results
      integer, intent(in) :: n_hist, n_poinc, ns        !! sizes
      allocate(res%time(n_hist), res%strain(n_hist), res%strain_rate(n_hist), &
               res%tip_displacement(n_hist), res%stop_force(n_hist, ns))
      allocate(res%p_time(n_poinc), res%p_strain(n_poinc), res%p_strain_rate(n_poinc), &
               res%p_tip(n_poinc), res%p_tip_velocity(n_poinc))
      allocate(res%n_impacts(ns), source=0)
      allocate(res%first_contact_time(ns), source=-1.0_dp)
      allocate(res%peak_force(ns), source=0.0_dp)
   end subroutine allocate_result

   !> 'node 5 w' style label of a global dof.
   function dof_label(prob, i) result(s)
      type(problem_t), intent(in) :: prob   !! model
      integer, intent(in) :: i              !! global dof
      character(len=:), allocatable :: s
      integer :: node, d
      s = 'dof ' // str(i)
      do node = 1, prob%sys%n_node
         do d = 1, 2
            if (prob%sys%dof_of(d, node) == i) s = 'dof ' // str(i) // ' (node ' // str(node) &
               // ' ' // dof_name(d) // ')'
         end do
      end do
   end function dof_label

   !> Put massless dofs (lumped mass without rotary inertia) in static equilibrium with the
   !> others: K_ss u_s = -K_sr u_r, and the same for the velocity. The initial state of such
   !> dofs is not free; without this the first step would jump.
   subroutine massless_equilibrium(prob, u, v)
      type(problem_t), intent(in) :: prob      !! model
      real(dp), intent(inout) :: u(:), v(:)    !! state, massless entries replaced
      integer, allocatable :: s(:), r(:)
      real(dp), allocatable :: kss(:, :), b(:, :)
      integer :: i, ns, info
      s = pack([(i, i = 1, prob%n)], [(prob%sys%m(i, i) == 0.0_dp, i = 1, prob%n)])
      r = pack([(i, i = 1, prob%n)], [(prob%sys%m(i, i) /= 0.0_dp, i = 1, prob%n)])
      ns = size(s)
      if (ns == 0) return
      kss = prob%sys%k(s, s)
      allocate(b(ns, 2))
      b(:, 1) = -matmul(prob%sys%k(s, r), u(r))
      b(:, 2) = -matmul(prob%sys%k(s, r), v(r))
      call dpotrf('U', ns, kss, ns, info)
      if (info == 0) call dpotrs('U', ns, 2, kss, ns, b, ns, info)
      u(s) = b(:, 1);  v(s) = b(:, 2)
   end subroutine massless_equilibrium

   !> Acceleration in equilibrium with (t, u, v): M a = s(t) q - C v - K u - F_NL.
   !> Massless dofs (lumped mass without rotary inertia) get a = 0.
   subroutine initial_acceleration(prob, t, u, v, a)
      type(problem_t), intent(in) :: prob       !! model
      real(dp), intent(in) :: t                 !! time [s]
      real(dp), intent(in) :: u(:), v(:)        !! state
      real(dp), intent(out) :: a(:)             !! acceleration
      real(dp) :: f(prob%n_contacts)
      integer :: c, i
      do c = 1, prob%n_contacts
         i = prob%c_dof(c)
         f(c) = contact_force(prob%c_law(c), prob%c_k(c), prob%c_c(c), prob%c_p(c), &
            prob%c_sign(c) * u(i) - prob%c_gap(c), prob%c_sign(c) * v(i))
      end do
      call equilibrium_acceleration(prob, t, u, v, f, a)
   end subroutine initial_acceleration

   !> Acceleration in equilibrium with (t, u, v) and given contact forces f.
   subroutine equilibrium_acceleration(prob, t, u, v, f, a)
      type(problem_t), intent(in) :: prob       !! model
      real(dp), intent(in) :: t                 !! time [s]
      real(dp), intent(in) :: u(:), v(:)        !! state
      real(dp), intent(in) :: f(:)              !! contact force magnitudes [N]
      real(dp), intent(out) :: a(:)             !! acceleration
      real(dp), allocatable :: rhs(:), msub(:, :), b(:)
      integer, allocatable :: idx(:)
      integer :: c, i, info, nm
      rhs = state_load(prob, t) * prob%q - matmul(prob%c, v) - matmul(prob%sys%k, u)
      do c = 1, prob%n_contacts
         i = prob%c_dof(c)
         rhs(i) = rhs(i) - prob%c_sign(c) * f(c)
      end do
      a = 0.0_dp
      idx = pack([(i, i = 1, prob%n)], [(prob%sys%m(i, i) > 0.0_dp, i = 1, prob%n)])
      nm = size(idx)
      if (nm == 0) return
      msub = prob%sys%m(idx, idx)
      b = rhs(idx)
      call dpotrf('U', nm, msub, nm, info)
      if (info == 0) call dpotrs('U', nm, 1, msub, nm, b, nm, info)
      a(idx) = b
   end subroutine equilibrium_acceleration

   !> Integrate from (u0, v0) at t = 0 over transient + recorded periods.
   subroutine run_transient(prob, cfg, out, u0, v0, res, err)
      type(problem_t), intent(in) :: prob              !! model
      type(solver_settings_t), intent(in) :: cfg       !! solver settings
      type(output_settings_t), intent(in) :: out       !! what to record
      real(dp), intent(in) :: u0(:), v0(:)             !! initial state relative to the base
      type(transient_result_t), intent(out) :: res     !! results
      type(error_t), allocatable, intent(out) :: err   !! numerical failure
      class(stepper_t), allocatable :: ops(:), scratch, proto
      integer :: n, nc, ns, kmax, level, nsub, comfortable, worst, j, c, n_hist, n_poinc, &
         ih, ip, s_stop
      integer(int64) :: tick, end_tick, rec_tick, nt, count0, count1, rate
      integer(int64), allocatable :: nt_of(:)
      real(dp) :: period, dt_max, tick_dt, t0, t1, ratio, r, t_rec, theta, dt_r, t_cur, &
         dt_prev, t_h, t_p, t_rec_len, fsum
      logical :: ok, half_step, recording, all_found, embedded, filtering
      type(lowpass_t) :: fil_s, fil_r
      integer(int64) :: jf, jp_next, jh_next
      integer :: nf, ipf, ihf
      real(dp) :: dt_f
      integer :: n_since
      real(dp) :: energy, energy_ref
      real(dp) :: eratio
      real(dp) :: next_sample
      real(dp), allocatable :: u(:), v(:), a(:), f(:), fprev(:), &
         work(:), work6(:, :), sub_u(:, :), sub_v(:, :), sub_a(:, :), sub_f(:, :), sub_t(:), &
         yy(:)
      real(dp), allocatable :: acc_f2(:), acc_f(:), acc_contact(:), acc_work(:)
      logical, allocatable :: was_active(:)
      integer, allocatable :: si(:)
      real(dp), allocatable :: sw(:)
      integer :: i_ev, cc_ev, k_ev     ! contact, dof and sub-step examined by first_event
      real(dp) :: h_ev
      integer :: ev_contact            ! contact of the located event
      logical :: ev_onset              ! the event closes it (else opens it)

      call system_clock(count0, rate)
      n = prob%n;  nc = prob%n_contacts;  ns = prob%n_stops
      period = 2.0_dp * pi / prob%omega
      dt_max = period / real(cfg%steps_per_period, dp)
      kmax = cfg%max_halvings
      tick_dt = dt_max / 2.0_dp**kmax
      rec_tick = int(cfg%transient_periods, int64) * cfg%steps_per_period * 2_int64**kmax
      end_tick = rec_tick + int(cfg%record_periods, int64) * cfg%steps_per_period &
                 * 2_int64**kmax
      t_rec = real(rec_tick, dp) * tick_dt
      t_rec_len = real(cfg%record_periods, dp) * period
      half_step = cfg%step_control == 'half_step'
      call make_stepper(cfg, proto, err)
      if (allocated(err)) return
      allocate(ops(0:kmax), mold=proto)
      allocate(scratch, mold=proto)
      embedded = cfg%step_control == 'embedded'

      allocate(u(n), v(n), a(n), work(n), work6(n, 6), yy(n))
      allocate(f(nc), fprev(nc), source=0.0_dp)
      allocate(sub_u(n, 0:max_sub), sub_v(n, 0:max_sub), sub_a(n, 0:max_sub), &
               sub_f(nc, 0:max_sub), sub_t(0:max_sub))
      u = u0;  v = v0
      call massless_equilibrium(prob, u, v)
      call initial_acceleration(prob, 0.0_dp, u, v, a)
      do c = 1, nc
         f(c) = contact_force(prob%c_law(c), prob%c_k(c), prob%c_c(c), prob%c_p(c), &
            prob%c_sign(c) * u(prob%c_dof(c)) - prob%c_gap(c), prob%c_sign(c) * v(prob%c_dof(c)))
      end do
      fprev = f
      allocate(was_active(nc))
      was_active = f > 0.0_dp
      sub_u(:, 0) = u;  sub_v(:, 0) = v;  sub_a(:, 0) = a;  sub_f(:, 0) = f
      si = pack([(j, j = 1, n)], prob%sys%strain_row /= 0.0_dp)
      sw = prob%sys%strain_row(si)
      allocate(nt_of(0:kmax))
      do j = 0, kmax
         nt_of(j) = 2_int64**(kmax - j)
      end do

      n_hist = min(out%history_periods, cfg%record_periods) * out%samples_per_period
      n_poinc = cfg%record_periods
      call allocate_result(res, n_hist, n_poinc, ns)
      allocate(acc_f2(ns), acc_f(ns), acc_contact(ns), acc_work(ns), source=0.0_dp)
      ih = 1;  ip = 1;  next_sample = -huge(1.0_dp);  all_found = ns == 0
      filtering = out%filter_cutoff_hz > 0.0_dp
      allocate(res%strain_filtered(merge(n_hist, 0, filtering)))
      if (filtering) then
         nf = out%filter_samples_per_period
         dt_f = period / real(nf, dp)
         call design_lowpass(out%filter_order, out%filter_cutoff_hz, 1.0_dp / dt_f, fil_s, err)
         if (allocated(err)) then
            err%message = 'group &output: ' // err%message // ' (the filter samples ' &
               // str(nf) // ' times per forcing period: raise filter_samples_per_period)'
            return
         end if
         call design_lowpass(out%filter_order, out%filter_cutoff_hz, 1.0_dp / dt_f, fil_r, err)
         jf = 0;  ipf = 1;  ihf = 1
         jp_next = poincare_filter_index(1);  jh_next = history_filter_index(1)
      end if
      res%dt_smallest = huge(1.0_dp);  res%dt_largest = 0.0_dp

      tick = 0;  level = 0;  comfortable = 0;  dt_prev = dt_max;  n_since = 0
      energy_ref = 0.5_dp * dot_product(u, matmul(prob%sys%k, u)) &
                   + 0.5_dp * dot_product(v, matmul(prob%sys%m, v))
      do while (tick < end_tick)
         nt = nt_of(level)
         t0 = real(tick, dp) * tick_dt
         t1 = real(tick + nt, dp) * tick_dt
         if (.not. ops(level)%ready) then
            call ops(level)%prepare(prob, cfg, t1 - t0, err)
            if (allocated(err)) return
            res%factorizations = res%factorizations + 1
         end if

         ! ---- attempt the step, split at contact events
         sub_t(0) = t0
         nsub = 0;  ok = .true.;  t_cur = t0;  eratio = 0.0_dp
         do
            dt_r = t1 - t_cur
            if (nsub == 0) then
               call one_step(ops(level), nsub, 0)
            else
               call scratch%prepare(prob, cfg, dt_r, err)
               if (allocated(err)) return
               res%factorizations = res%factorizations + 1
               call one_step(scratch, nsub, 0)
            end if
            if (.not. ok) exit
            if (cfg%locate_events .and. nc > 0 .and. nsub < max_sub - 1) then
               theta = first_event(nsub, dt_r)
               if (theta * dt_r > min_split * (t1 - t0) .and. &
                   (1.0_dp - theta) * dt_r > min_split * (t1 - t0)) then
                  call scratch%prepare(prob, cfg, theta * dt_r, err)
                  if (allocated(err)) return
                  res%factorizations = res%factorizations + 1
                  if (ev_onset) then
                     call one_step(scratch, nsub, ev_contact)
                  else
                     call one_step(scratch, nsub, 0)
                  end if
                  if (.not. ok) exit
                  nsub = nsub + 1
                  sub_t(nsub) = t_cur + theta * dt_r
                  t_cur = sub_t(nsub)
                  res%events = res%events + 1
                  ! only a damper makes the force jump at a switch
                  if (prob%c_c(ev_contact) > 0.0_dp) call restart_after_event(nsub)
                  cycle
               end if
            end if
            nsub = nsub + 1
            sub_t(nsub) = t1
            exit
         end do

         ratio = 0.0_dp;  worst = 1
         if (embedded) ratio = eratio
         if (ok .and. half_step) then
            do j = 1, nsub
               call half_step_ratio(prob, cfg%newmark_delta, cfg%newmark_alpha, &
                  cfg%half_step_tolerance, cfg%residual_floor, sub_t(j - 1), &
                  sub_t(j) - sub_t(j - 1), sub_u(:, j - 1), sub_v(:, j - 1), sub_a(:, j - 1), &
                  sub_a(:, j), r, c, work6)
               if (r > ratio) then
                  ratio = r;  worst = c
               end if
            end do
         end if
         if (.not. ok .or. ratio > 1.0_dp) then
            res%steps_rejected = res%steps_rejected + 1
            comfortable = 0
            if (level >= kmax) then
               if (.not. ok) then
                  call fatal_error(err, 'gapbeam_transient:run_transient: the fixed point on ' &
                     // 'the stop force does not converge in ' // str(cfg%fp_max_iterations) &
                     // ' iterations even at the smallest step dt = ' // str(t1 - t0) &
                     // ' s (t = ' // str(t0) // ' s, stop ' // dof_label(prob, prob%c_dof(1)) &
                     // '); use stop_solution=''condensed'' or allow more max_halvings')
               else
                  call fatal_error(err, 'gapbeam_transient:run_transient: step below the ' &
                     // 'minimum: at t = ' // str(t0) // ' s the half-step residual at ' &
                     // dof_label(prob, worst) // ' is ' // str(ratio) // ' times the ' &
                     // 'tolerance with the smallest step dt = ' // str(t1 - t0) // ' s (' &
                     // 'steps_per_period = ' // str(cfg%steps_per_period) // ', max_halvings = ' &
                     // str(kmax) // ')')
               end if
               return
            end if
            level = level + 1
            cycle
         end if

         ! ---- accept
         ! a non-finite value reaches every dof within a step (dense or banded coupling); the
         ! energy check below catches growth that stays finite
         fsum = sub_u(1, nsub) + sub_v(1, nsub) + sub_u(n, nsub) + sub_v(n, nsub)
         if (.not. (abs(fsum) <= huge(1.0_dp))) then
            do j = 1, n
               if (.not. (abs(sub_u(j, nsub)) <= huge(1.0_dp)) .or. &
                   .not. (abs(sub_v(j, nsub)) <= huge(1.0_dp))) exit
            end do
            call fatal_error(err, 'gapbeam_transient:run_transient: method ''' &
               // trim(cfg%method) // ''' diverged: the solution is not finite at t = ' &
               // str(t1) // ' s, dt = ' // str(t1 - t0) // ' s, ' // dof_label(prob, min(j, n)))
            return
         end if
         ! energy bound: every 64 steps, against the largest energy of the first period
         n_since = n_since + 1
         if (n_since >= 64) then
            n_since = 0
            energy = 0.5_dp * dot_product(sub_u(:, nsub), matmul(prob%sys%k, sub_u(:, nsub))) &
                     + 0.5_dp * dot_product(sub_v(:, nsub), matmul(prob%sys%m, sub_v(:, nsub)))
            if (t1 <= period) then
               energy_ref = max(energy_ref, energy)
            else if (energy > cfg%energy_bound * energy_ref) then
               call fatal_error(err, 'gapbeam_transient:run_transient: method ''' &
                  // trim(cfg%method) // ''' diverged: the energy at t = ' // str(t1) &
                  // ' s is ' // str(energy / energy_ref) // ' times its largest value in ' &
                  // 'the first forcing period (bound energy_bound = ' &
                  // str(cfg%energy_bound) // '), dt = ' // str(t1 - t0) // ' s; omega_max dt = ' &
                  // str(prob%omega_max * (t1 - t0)))
               return
            end if
         end if
         recording = tick >= rec_tick
         do j = 1, nsub
            call record_substep(j)
         end do
         res%steps_accepted = res%steps_accepted + nsub
         res%dt_smallest = min(res%dt_smallest, t1 - t0)
         res%dt_largest = max(res%dt_largest, t1 - t0)
         fprev = sub_f(:, nsub - 1)
         dt_prev = sub_t(nsub) - sub_t(nsub - 1)
         sub_u(:, 0) = sub_u(:, nsub);  sub_v(:, 0) = sub_v(:, nsub)
         sub_a(:, 0) = sub_a(:, nsub);  sub_f(:, 0) = sub_f(:, nsub)
         tick = tick + nt

         ! ---- grow
         if (.not. (half_step .or. embedded) .or. ratio < cfg%grow_ratio) then
            comfortable = comfortable + 1
         else
            comfortable = 0
         end if
         if (level > 0 .and. comfortable >= cfg%grow_after) then
            if (mod(tick, 2 * nt) == 0) then
               level = level - 1;  comfortable = 0
            end if
         end if
      end do

      res%fp_iterations = scratch%iterations
      do j = 0, kmax
         res%fp_iterations = res%fp_iterations + ops(j)%iterations
      end do
      ! ---- statistics over the record
      res%rms_force = sqrt(acc_f2 / t_rec_len)
      res%contact_fraction = acc_contact / t_rec_len
      res%impulse_per_period = acc_f / real(cfg%record_periods, dp)
      res%work_rate = acc_work / t_rec_len
      res%u = sub_u(:, 0);  res%v = sub_v(:, 0);  res%a = sub_a(:, 0)
      res%t_end = real(end_tick, dp) * tick_dt
      if (ih <= n_hist) then
         res%time = res%time(1:ih - 1);  res%strain = res%strain(1:ih - 1)
         res%strain_rate = res%strain_rate(1:ih - 1)
         res%tip_displacement = res%tip_displacement(1:ih - 1)
         res%stop_force = res%stop_force(1:ih - 1, :)
      end if
      call system_clock(count1)
      res%cpu_seconds = real(count1 - count0, dp) / real(rate, dp)

   contains

      !> One step of the method from sub-state k to time sub_t(k) + stepper dt, into slot k+1.
      subroutine one_step(st, k, open_contact)
         class(stepper_t), intent(inout) :: st
         integer, intent(in) :: k
         integer, intent(in) :: open_contact   ! held open: a located onset ends the step
         real(dp) :: r
         if (k == 0) then
            call st%step(prob, sub_t(k), sub_u(:, k), sub_v(:, k), sub_a(:, k), sub_f(:, k), &
               fprev, dt_prev, sub_u(:, k + 1), sub_v(:, k + 1), sub_a(:, k + 1), &
               sub_f(:, k + 1), ok, r, open_contact)
         else
            call st%step(prob, sub_t(k), sub_u(:, k), sub_v(:, k), sub_a(:, k), sub_f(:, k), &
               sub_f(:, k - 1), sub_t(k) - sub_t(k - 1), sub_u(:, k + 1), sub_v(:, k + 1), &
               sub_a(:, k + 1), sub_f(:, k + 1), ok, r, open_contact)
         end if
         if (r > eratio) eratio = r
      end subroutine one_step

      !> First instant (fraction of the sub-step) where a contact opens or closes.
      real(dp) function first_event(k, h) result(th)
         integer, intent(in) :: k
         real(dp), intent(in) :: h
         integer :: cc, m, it
         real(dp) :: lo, hi, mid, p0, b1, b2, b3
         logical :: closed0, damped
         integer, parameter :: n_sample = 8
         th = 2.0_dp
         do cc = 1, nc
            i_ev = prob%c_dof(cc);  cc_ev = cc;  k_ev = k;  h_ev = h
            damped = prob%c_law(cc) == law_bilinear .and. prob%c_c(cc) > 0.0_dp
            closed0 = active(0.0_dp, damped)
            if (.not. damped) then
               ! Bernstein coefficients of the cubic bound it: no sign change, no event
               p0 = prob%c_sign(cc) * sub_u(i_ev, k) - prob%c_gap(cc)
               b1 = p0 + prob%c_sign(cc) * h * sub_v(i_ev, k) / 3.0_dp
               b3 = prob%c_sign(cc) * sub_u(i_ev, k + 1) - prob%c_gap(cc)
               b2 = b3 - prob%c_sign(cc) * h * sub_v(i_ev, k + 1) / 3.0_dp
               if (closed0) then
                  if (min(b1, b2, b3) > 0.0_dp) cycle
               else
                  if (max(b1, b2, b3) <= 0.0_dp) cycle
               end if
            end if
            do m = 1, n_sample
               hi = real(m, dp) / n_sample
               if (hi >= th) exit
               if (active(hi, damped) .neqv. closed0) then
                  lo = real(m - 1, dp) / n_sample
                  do it = 1, 60
                     mid = 0.5_dp * (lo + hi)
                     if (active(mid, damped) .neqv. closed0) then
                        hi = mid
                     else
                        lo = mid
                     end if
                  end do
                  if (hi < th) then
                     th = hi;  ev_contact = cc;  ev_onset = .not. closed0
                  end if
                  exit
               end if
            end do
         end do
      end function first_event

      !> At a located event the contact force may jump (a damper's force c d' at impact): the
      !> next sub-step starts from the right limit, forces of the new contact state and the
      !> acceleration in equilibrium with them, so that the trapezoidal rule does not average
      !> across the jump (which would cost an O(dt) velocity error per impact).
      subroutine restart_after_event(k)
         integer, intent(in) :: k
         integer :: c2, i2
         real(dp) :: d, dd
         do c2 = 1, nc
            i2 = prob%c_dof(c2)
            d = prob%c_sign(c2) * sub_u(i2, k) - prob%c_gap(c2)
            dd = prob%c_sign(c2) * sub_v(i2, k)
            if (c2 == ev_contact) then
               if (ev_onset) then
                  sub_f(c2, k) = contact_force(prob%c_law(c2), prob%c_k(c2), prob%c_c(c2), &
                     prob%c_p(c2), max(d, tiny(1.0_dp)), dd)
               else
                  sub_f(c2, k) = 0.0_dp
               end if
            else
               sub_f(c2, k) = contact_force(prob%c_law(c2), prob%c_k(c2), prob%c_c(c2), &
                  prob%c_p(c2), d, dd)
            end if
         end do
         call equilibrium_acceleration(prob, sub_t(k), sub_u(:, k), sub_v(:, k), &
                                       sub_f(:, k), sub_a(:, k))
      end subroutine restart_after_event

      !> Is contact cc_ev active at fraction x of the sub-step (cubic Hermite interpolant)?
      !> Penetration > 0, and for a bilinear law with a damper also k d + c d' > 0 (release).
      logical function active(x, damped)
         real(dp), intent(in) :: x
         logical, intent(in) :: damped
         real(dp) :: d, dd, h00, h10, h01, h11, g00, g10, g01, g11
         call hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
         d = prob%c_sign(cc_ev) * (h00 * sub_u(i_ev, k_ev) + h10 * h_ev * sub_v(i_ev, k_ev) &
             + h01 * sub_u(i_ev, k_ev + 1) + h11 * h_ev * sub_v(i_ev, k_ev + 1)) - prob%c_gap(cc_ev)
         active = d > 0.0_dp
         if (active .and. damped) then
            dd = prob%c_sign(cc_ev) * (g00 * sub_u(i_ev, k_ev) + g10 * h_ev * sub_v(i_ev, k_ev) &
                 + g01 * sub_u(i_ev, k_ev + 1) + g11 * h_ev * sub_v(i_ev, k_ev + 1)) / h_ev
            active = prob%c_k(cc_ev) * d + prob%c_c(cc_ev) * dd > 0.0_dp
         end if
      end function active

      !> Samples and statistics of accepted sub-step j (from j-1 to j).
      subroutine record_substep(jj)
         integer, intent(in) :: jj
         real(dp) :: ta, tb, h, x, h00, h10, h01, h11, g00, g10, g01, g11, ui, vi, fa, fb, &
            wa, wb, st, sv
         integer :: cc, i, ks
         ta = sub_t(jj - 1);  tb = sub_t(jj);  h = tb - ta
         if (recording) then
            st = 0.0_dp;  sv = 0.0_dp
            do i = 1, size(si)
               st = st + sw(i) * sub_u(si(i), jj)
               sv = sv + sw(i) * sub_v(si(i), jj)
            end do
            res%strain_min = min(res%strain_min, st);  res%strain_max = max(res%strain_max, st)
            res%strain_rate_min = min(res%strain_rate_min, sv)
            res%strain_rate_max = max(res%strain_rate_max, sv)
         end if
         if (tb + 1.0e-12_dp * period < next_sample .and. all_found) then
            if (recording) then
               call accumulate(jj, h)
            else
               do cc = 1, nc
                  was_active(cc) = sub_f(cc, jj) > 0.0_dp
               end do
            end if
            return
         end if
         ! history samples in (ta, tb]
         do while (ih <= n_hist)
            t_h = t_rec + real(ih - 1, dp) * period / real(out%samples_per_period, dp)
            if (t_h > tb + 1.0e-12_dp * period) exit
            x = min(1.0_dp, max(0.0_dp, (t_h - ta) / h))
            call hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
            res%time(ih) = t_h
            st = 0.0_dp;  sv = 0.0_dp
            do i = 1, n
               ui = h00 * sub_u(i, jj - 1) + h10 * h * sub_v(i, jj - 1) + h01 * sub_u(i, jj) &
                    + h11 * h * sub_v(i, jj)
               vi = (g00 * sub_u(i, jj - 1) + g10 * h * sub_v(i, jj - 1) + g01 * sub_u(i, jj) &
                    + g11 * h * sub_v(i, jj)) / h
               st = st + prob%sys%strain_row(i) * ui
               sv = sv + prob%sys%strain_row(i) * vi
               if (i == prob%sys%tip_dof) res%tip_displacement(ih) = ui
               work(i) = ui;  yy(i) = vi
            end do
            res%strain(ih) = st;  res%strain_rate(ih) = sv
            res%stop_force(ih, :) = 0.0_dp
            do cc = 1, nc
               i = prob%c_dof(cc);  ks = prob%c_stop(cc)
               res%stop_force(ih, ks) = res%stop_force(ih, ks) + contact_force(prob%c_law(cc), &
                  prob%c_k(cc), prob%c_c(cc), prob%c_p(cc), &
                  prob%c_sign(cc) * work(i) - prob%c_gap(cc), prob%c_sign(cc) * yy(i))
            end do
            ih = ih + 1
         end do
         ! Poincare samples in (ta, tb]
         do while (ip <= n_poinc)
            t_p = t_rec + (real(ip - 1, dp) + out%poincare_phase_deg / 360.0_dp) * period
            if (t_p > tb + 1.0e-12_dp * period) exit
            x = min(1.0_dp, max(0.0_dp, (t_p - ta) / h))
            call hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
            st = 0.0_dp;  sv = 0.0_dp
            do i = 1, n
               ui = h00 * sub_u(i, jj - 1) + h10 * h * sub_v(i, jj - 1) + h01 * sub_u(i, jj) &
                    + h11 * h * sub_v(i, jj)
               vi = (g00 * sub_u(i, jj - 1) + g10 * h * sub_v(i, jj - 1) + g01 * sub_u(i, jj) &
                    + g11 * h * sub_v(i, jj)) / h
               st = st + prob%sys%strain_row(i) * ui
               sv = sv + prob%sys%strain_row(i) * vi
               if (i == prob%sys%tip_dof) then
                  res%p_tip(ip) = ui;  res%p_tip_velocity(ip) = vi
               end if
            end do
            res%p_time(ip) = t_p;  res%p_strain(ip) = st;  res%p_strain_rate(ip) = sv
            ip = ip + 1
         end do
         if (filtering) call filter_samples(jj)
         next_sample = huge(1.0_dp)
         if (filtering) next_sample = real(jf, dp) * dt_f
         if (ih <= n_hist) next_sample = min(next_sample, t_rec + real(ih - 1, dp) * period &
            / real(out%samples_per_period, dp))
         if (ip <= n_poinc) next_sample = min(next_sample, t_rec + (real(ip - 1, dp) &
            + out%poincare_phase_deg / 360.0_dp) * period)
         ! first contact onset of each stop, interpolated linearly in the penetration
         do cc = 1, nc
            ks = prob%c_stop(cc)
            if (res%first_contact_time(ks) >= 0.0_dp) cycle
            if (sub_f(cc, jj) > 0.0_dp .and. .not. was_active(cc)) then
               i = prob%c_dof(cc)
               fa = prob%c_sign(cc) * sub_u(i, jj - 1) - prob%c_gap(cc)
               fb = prob%c_sign(cc) * sub_u(i, jj) - prob%c_gap(cc)
               if (fa <= 0.0_dp .and. fb > fa) then
                  res%first_contact_time(ks) = ta + h * (-fa) / (fb - fa)
               else
                  res%first_contact_time(ks) = ta
               end if
            end if
         end do
         all_found = all(res%first_contact_time >= 0.0_dp)
         if (.not. recording) then
            do cc = 1, nc
               was_active(cc) = sub_f(cc, jj) > 0.0_dp
            end do
            return
         end if
         call accumulate(jj, h)
      end subroutine record_substep

      !> Feed the low-pass filters with the root strain and its rate at their uniform sample
      !> times inside sub-step jj (cubic Hermite interpolation); store the filtered values at
      !> the Poincare instants (the nearest filter sample) and at the history samples.
      subroutine filter_samples(jj)
         integer, intent(in) :: jj
         real(dp) :: ta, tb, h, x, w(8), st, sv, ys, yr, tf
         integer :: q
         ta = sub_t(jj - 1);  tb = sub_t(jj);  h = tb - ta
         do
            tf = real(jf, dp) * dt_f
            if (tf > tb + 1.0e-12_dp * period) exit
            x = min(1.0_dp, max(0.0_dp, (tf - ta) / h))
            call hermite_weights(x, w(1), w(2), w(3), w(4), w(5), w(6), w(7), w(8))
            st = 0.0_dp;  sv = 0.0_dp
            do q = 1, size(si)
               st = st + sw(q) * (w(1) * sub_u(si(q), jj - 1) + w(2) * h * sub_v(si(q), jj - 1) &
                    + w(3) * sub_u(si(q), jj) + w(4) * h * sub_v(si(q), jj))
               sv = sv + sw(q) * (w(5) * sub_u(si(q), jj - 1) + w(6) * h * sub_v(si(q), jj - 1) &
                    + w(7) * sub_u(si(q), jj) + w(8) * h * sub_v(si(q), jj)) / h
            end do
            ys = fil_s%apply(st);  yr = fil_r%apply(sv)
            if (ipf <= n_poinc .and. jf == jp_next) then
               res%p_strain(ipf) = ys;  res%p_strain_rate(ipf) = yr
               ipf = ipf + 1;  jp_next = poincare_filter_index(ipf)
            end if
            if (ihf <= n_hist .and. jf == jh_next) then
               res%strain_filtered(ihf) = ys
               ihf = ihf + 1;  jh_next = history_filter_index(ihf)
            end if
            jf = jf + 1
         end do
      end subroutine filter_samples

      !> Filter sample index of Poincare point k (the nearest to its instant).
      integer(int64) function poincare_filter_index(k)
         integer, intent(in) :: k
         poincare_filter_index = int(cfg%transient_periods + k - 1, int64) * nf &
            + nint(out%poincare_phase_deg / 360.0_dp * nf, int64)
      end function poincare_filter_index

      !> Filter sample index of history sample i.
      integer(int64) function history_filter_index(i)
         integer, intent(in) :: i
         history_filter_index = int(cfg%transient_periods, int64) * nf &
            + int(i - 1, int64) * (nf / out%samples_per_period)
      end function history_filter_index

      !> Impact statistics of the record (trapezoid over sub-step jj of length h).
      subroutine accumulate(jj, h)
            integer, intent(in) :: jj
            real(dp), intent(in) :: h
            real(dp) :: fa2, fb2
            integer :: c2, i2, k2
            do c2 = 1, nc
               i2 = prob%c_dof(c2);  k2 = prob%c_stop(c2)
               fa2 = sub_f(c2, jj - 1);  fb2 = sub_f(c2, jj)
               if (fa2 == 0.0_dp .and. fb2 == 0.0_dp) then
                  was_active(c2) = .false.
                  cycle
               end if
               acc_f2(k2) = acc_f2(k2) + 0.5_dp * h * (fa2**2 + fb2**2)
               acc_f(k2) = acc_f(k2) + 0.5_dp * h * (fa2 + fb2)
               acc_work(k2) = acc_work(k2) + 0.5_dp * h * (fa2 * abs(sub_v(i2, jj - 1)) &
                              + fb2 * abs(sub_v(i2, jj)))
               if (fa2 > 0.0_dp .and. fb2 > 0.0_dp) then
                  acc_contact(k2) = acc_contact(k2) + h
               else
                  acc_contact(k2) = acc_contact(k2) + 0.5_dp * h
               end if
               if (fb2 > 0.0_dp .and. .not. was_active(c2)) &
                  res%n_impacts(k2) = res%n_impacts(k2) + 1
               was_active(c2) = fb2 > 0.0_dp
               res%peak_force(k2) = max(res%peak_force(k2), fb2)
            end do
      end subroutine accumulate
   end subroutine run_transient

   !> Cubic Hermite interpolant at fraction x of a step of size h from (u0, v0) to (u1, v1).
   pure real(dp) function hermite_value(x, h, u0, v0, u1, v1)
      real(dp), intent(in) :: x, h, u0, v0, u1, v1
      hermite_value = (1 + 2 * x) * (1 - x)**2 * u0 + x * (1 - x)**2 * h * v0 &
                      + x**2 * (3 - 2 * x) * u1 + x**2 * (x - 1) * h * v1
   end function hermite_value

   !> Weights of the cubic Hermite interpolant (h..) and of its derivative times h (g..).
   pure subroutine hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
      real(dp), intent(in) :: x
      real(dp), intent(out) :: h00, h10, h01, h11, g00, g10, g01, g11
      h00 = (1 + 2 * x) * (1 - x)**2;  h10 = x * (1 - x)**2
      h01 = x**2 * (3 - 2 * x);  h11 = x**2 * (x - 1)
      g00 = 6 * x**2 - 6 * x;  g10 = 3 * x**2 - 4 * x + 1
      g01 = -6 * x**2 + 6 * x;  g11 = 3 * x**2 - 2 * x
   end subroutine hermite_weights
end module gapbeam_transient
