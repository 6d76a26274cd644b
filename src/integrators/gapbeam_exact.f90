!> Exact event-driven integrator of the piecewise-linear gap model: the accuracy reference.
!>
!> Between switches of the contact configuration the motion is known in closed form. In the
!> open structure's mass-normalised modal coordinates (gapbeam_exact_modes) every
!> configuration is a rank-r update of n single-dof oscillators, whose 2n roots, eigenvectors
!> and nearly coalescing pairs are found once per configuration (gapbeam_exact_config); a
!> segment is a sum of exponentials projected by the residue formula, no eigenvector matrix
!> inverted (gapbeam_exact_segment). This holds for any mesh and any Rayleigh damping (modes
!> near, at and past critical, massless rotations condensed, contact dampers, several stops).
!> This module finds the switches and hands the observer one piece per window of a segment.
!>
!> **Events.** Every quantity watched is a sum of exponentials phi(tau) = Re(sum_j a_j
!> e^{mu_j tau}) + a_0 (plus rare blocks) whose derivatives and their bounds on the rest of the
!> segment are known. The search for the first sign change steps safely: from tau it advances
!> to the first zero of a lower bound of sigma phi (quadratic: phi + phi' s - B2 s^2/2, or
!> cubic: phi + phi' s + phi'' s^2/2 - B3 s^3/6, whichever reaches further), so no root,
!> grazing included, is missed (short of an excursion shorter than the time tolerance); near a
!> transversal root these steps converge quadratically from the safe side, and the root is
!> bracketed to time_tol * T (1e-14 of the forcing period), then bisected if needed. A contact
!> c with penetration d = s_c u_i - g_c is active while d > 0 and, for a damped stop,
!> k d + c d' > 0 (the damper never pulls): the watched functions are d and, with a damper,
!> k d + c d'. At a sign change the activity of all contacts is decided from the sign just after
!> the instant: the first of d and its derivatives up to the third (and of k d + c d' and its
!> derivatives) that is not zero to round-off, the derivatives taken from the modal state
!> through the equations of motion (free of the cancellations of the modal sums, and the same
!> before and after the switch). A change of activity ends the segment, otherwise the search
!> goes on. A new segment re-decides at its first instant (at most 4 switches at one instant,
!> then the configuration is kept); a watched function that starts within round-off of zero on
!> the wrong side gets a dead band of that size until it is clear of zero. This is how a
!> contact that starts exactly at zero gap from rest (d = d' = d'' = 0, d''' > 0) closes. A
!> segment whose search would take more than search_limit steps (fast terms that do not
!> decay) ends the run with an error naming the time and what to change: never a silent hang.
!>
!> **Statistics.** From the observer's watch instant on, over each window of a segment the
!> integrals of f, f^2 and f |d'| of every active contact are computed in closed form (|d'| by
!> splitting the window at the zeros of d', located like events), and the largest force, the
!> root strain and strain-rate extremes are exact extrema (to 1e-13 of the function's scale): a
!> running maximum M is certified by the same bounds (the cubic bound of phi under M + tol, or a
!> step on which phi' keeps its sign), which converge onto each local maximum that could exceed
!> M. A window ends at a switch, a re-anchoring, the watch instant or a full list of zeros of
!> d'; each window is one piece for the observer, whose samples are evaluated from the closed
!> form at any instant inside.
!>
!> Time is kept as (forcing periods k, offset r in [0, T)), so the forcing phase Omega r is
!> computed without the loss of precision of Omega t at large t; a segment longer than two
!> periods is re-anchored (projected again, not counted as a segment).
!>
!> Counters: steps_accepted = linear segments, events = configuration switches,
!> factorizations = configurations built; dt_smallest / dt_largest = shortest / longest
!> segment.
!>
!> Limits: piecewise-linear stop laws only (the bilinear law; a law whose caps say otherwise,
!> such as Hertz, is rejected with an error);
!> Rayleigh damping C = beta M + gamma K (as every deck builds it); forcing exactly at an
!> undamped natural frequency of a configuration (no periodic particular solution) is
!> rejected; at most 62 one-sided contacts.
module gapbeam_exact
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_law, only: law_caps_t
   use gapbeam_contact_law, only: contact_force
   use gapbeam_observer, only: piece_t, observer_t
   use gapbeam_integrator, only: integrator_t, contact_forces_at
   use gapbeam_exact_modes, only: open_modes_t, build_open_modes, to_modal, to_physical
   use gapbeam_exact_config, only: config_t, build_config, mask_text
   use gapbeam_exact_piece, only: exact_piece_t
   use gapbeam_exact_segment, only: segment_t, start_segment, eval_seg, prune_seg, &
      segment_state, modal_window, sign_after, band, add_fn, mono_quad, &
      cubic_root
   implicit none
   private
   public :: exact_integrator_t, exact_piece_t

   real(dp), parameter :: peak_tol = 1.0e-13_dp    ! extrema: tolerance / scale of the function
   real(dp), parameter :: tiny_scale = 1.0e-10_dp  ! margin of the load scale below sqrt(huge)
   real(dp), parameter :: time_tol = 1.0e-14_dp    ! event bracket / forcing period
   integer, parameter :: max_flips = 4             ! switches allowed at one instant
   integer, parameter :: max_roots = 64            ! zeros of d' kept per contact phase window
   integer, parameter :: prune_every = 8           ! accepted steps between prunings

   ! outcome of a sweep over a segment
   integer, parameter :: end_switch = 1, end_horizon = 2, end_anchor = 3


   !> The exact event-driven integrator.
   type, extends(integrator_t) :: exact_integrator_t
      type(model_t) :: model                          !! the model (own copy)
      type(open_modes_t) :: om                        !! open structure in modal coordinates
      type(config_t), allocatable :: cfgs(:)          !! configurations built so far
      integer :: ncfg = 0                             !! how many
      type(segment_t) :: sg                           !! the current segment
      integer :: ic = 0                               !! its configuration
      real(dp) :: period = 0.0_dp, omega = 0.0_dp     !! forcing [s], [rad/s]
      real(dp) :: tol_t = 0.0_dp                      !! event bracket [s]
      integer :: nc = 0, nb = 0, n = 0                !! contacts, functionals, modes
      integer(int64) :: k0 = 0                        !! segment start: periods
      real(dp) :: r0 = 0.0_dp                         !!    and offset [s]
      integer(int64) :: mask = 0                      !! active contacts
      integer(int64) :: k_end = 0, k_watch = 0        !! horizon, watch instant: periods
      real(dp) :: r_end = 0.0_dp, r_watch = 0.0_dp    !!    and offsets [s]
      real(dp) :: t_end = 0.0_dp, t_watch = 0.0_dp    !! the same as times [s]
      logical :: watching = .false.                   !! statistics kept
      logical :: watch_due = .false.                  !! the watch instant is ahead
      real(dp), allocatable :: val(:, :), bnd(:, :)   !! (0:3 | 0:4, nb) values, bounds at tau
      logical, allocatable :: need(:)                 !! functionals evaluated in the sweep
      integer, allocatable :: sig_d(:), sig_l(:), sig_w(:)   !! signs of d, k d + c d', d'
      real(dp), allocatable :: del_d(:), del_l(:), del_w(:)  !! their dead bands
      logical, allocatable :: damped(:)               !! contact with a damper
      real(dp), allocatable :: dsv(:, :), dss(:, :)   !! (0:3, nc) derivatives of d, scales
      integer, allocatable :: n_roots(:)              !! zeros of d' in the window
      real(dp), allocatable :: roots(:, :)            !! (max_roots, nc) their instants
      real(dp) :: tau_w0 = 0.0_dp                     !! start of the window
      real(dp) :: smin = 0.0_dp, smax = 0.0_dp        !! running strain extrema (watching)
      real(dp) :: rmin = 0.0_dp, rmax = 0.0_dp        !! running strain-rate extrema
      real(dp), allocatable :: peak(:)                !! running peak force per stop [N]
      logical, allocatable :: onset(:)                !! contacts closed since the last piece
      real(dp), allocatable :: onset_t(:)             !! when [s]
      integer :: nf = 0                               !! functions in the step-limit list
      real(dp), allocatable :: q(:), fy(:), fy1(:), fy2(:), fb2(:), fb3(:)   !! that list
      logical, allocatable :: done(:)                 !! its processed flags
      real(dp), allocatable :: xe(:)                  !! (2n) modal state (eta, v) at the end
      real(dp), allocatable :: ae(:)                  !! (n) modal acceleration there
      integer :: search_steps = 0                     !! safe steps in the current segment
      integer :: search_limit = 200000                !! more in one segment: an error
      type(exact_piece_t) :: piece                    !! handed to the observer
   contains
      procedure :: init => exact_init
      procedure :: advance => exact_advance
      procedure, private :: begin_advance, config_index, run_segment, sweep, step_limit, &
         add, find_flip, watched, refine, decide, sign_d, sign_l, state_derivs, init_signs, &
         modal_acceleration, stalled, &
         register_switch, clear_bands, update_trackers, start_trackers, contact_functions, &
         emit_window, start_watching, abs_time, tau_of
      ! --- continuation hook (issue 14): the Jacobian of the flow, in submodule
      !     gapbeam_exact_jacobian (src/integrators/gapbeam_exact_jacobian.f90)
      procedure :: advance_jacobian => exact_advance_jacobian
      ! --- end of the continuation hook
   end type exact_integrator_t

   ! --- continuation hook (issue 14)
   interface
      !> Carry `state` to t_target as `advance` does, and return the Jacobian of the end state
      !> with respect to the start state, jac = d x(t_target) / d x(state%t), in the reduced
      !> coordinates x = (u_r, v_r) of the dofs with mass (gapbeam_transition: mass_dofs;
      !> massless dofs follow by static condensation): the state-transition matrices of the
      !> linear segments and the saltation matrices of the contact switches.
      module subroutine exact_advance_jacobian(self, state, t_target, jac, err)
         class(exact_integrator_t), intent(inout), target :: self   !! integrator
         type(state_t), intent(inout) :: state            !! state, at t_target on return
         real(dp), intent(in) :: t_target                 !! target time [s]
         real(dp), allocatable, intent(out) :: jac(:, :)  !! (2 nr, 2 nr) Jacobian
         type(error_t), allocatable, intent(out) :: err   !! configuration failure
      end subroutine exact_advance_jacobian
   end interface
   ! --- end of the continuation hook

contains

   !> Check the model, build the open structure's modes, set up the workspaces.
   subroutine exact_init(self, model, cfg, err)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                 !! model (bilinear stops only)
      type(solver_settings_t), intent(in) :: cfg         !! settings (unused)
      type(error_t), allocatable, intent(out) :: err     !! unsupported model, LAPACK failure
      integer :: c, nc, nb, nr
      type(law_caps_t) :: lc
      self%method = 'exact'
      nc = model%n_contacts
      if (.not. (model%omega > 0.0_dp)) then
         call fatal_error(err, 'gapbeam_exact: the forcing frequency must be > 0 (it sets the ' &
            // 'period and the horizon), got ' // str(model%omega) // ' rad/s')
         return
      end if
      do c = 1, nc
         lc = model%laws(model%c_law(c))%law%caps()
         if (.not. lc%piecewise_linear) then
            call fatal_error(err, 'gapbeam_exact: the exact event-driven integrator needs ' &
               // 'piecewise-linear stops; stop ' // str(model%c_stop(c)) // " uses the law '" &
               // trim(lc%name) // "' (" // trim(lc%force_text) // '), which is not piecewise ' &
               // 'linear: use the Newmark integrator for it')
            return
         end if
      end do
      if (nc > 62) then
         call fatal_error(err, 'gapbeam_exact: at most 62 one-sided contacts, got ' // str(nc))
         return
      end if
      ! the closed forms square the state: keep it within sqrt(huge)
      if (.not. (model%half_amplitude * model%omega**2 * maxval(abs(model%q), &
          mask=model%q == model%q) < sqrt(huge(1.0_dp)) * tiny_scale)) then
         call fatal_error(err, 'gapbeam_exact: the base acceleration amplitude ' &
            // str(model%half_amplitude * model%omega**2) // ' m/s^2 (&forcing amplitude_pp ' &
            // str(2.0_dp * model%half_amplitude) // ' m) is beyond the range the exact ' &
            // 'integrator can represent; use a physical amplitude')
         return
      end if
      self%model = model
      call build_open_modes(model, self%om, err)
      if (allocated(err)) return
      nb = self%om%nb;  nr = self%om%nr
      self%nc = nc;  self%nb = nb;  self%n = nr
      self%omega = model%omega
      self%period = 2.0_dp * pi / model%omega
      ! event brackets: time_tol of the shorter of the forcing period and the first open period
      self%tol_t = time_tol * self%period
      if (model%f1_open_hz > 0.0_dp) self%tol_t = time_tol * min(self%period, &
                                                                 1.0_dp / model%f1_open_hz)
      allocate(self%val(0:3, nb), self%bnd(0:4, nb), self%need(nb))
      allocate(self%sig_d(nc), self%sig_l(nc), self%sig_w(nc), self%del_d(nc), self%del_l(nc), &
               self%del_w(nc), self%n_roots(nc), self%roots(max_roots, nc), self%damped(nc), &
               self%dsv(0:3, nc), self%dss(0:3, nc), self%onset(nc), self%onset_t(nc), &
               self%peak(model%n_stops))
      self%damped = model%c_c(1:nc) > 0.0_dp
      self%sig_w = 1;  self%del_w = 0.0_dp;  self%n_roots = 0;  self%onset = .false.
      allocate(self%cfgs(4))
      self%ncfg = 0
      allocate(self%xe(2 * nr), self%ae(nr))
      allocate(self%q(4 * nc + 4), self%fy(4 * nc + 4), self%fy1(4 * nc + 4), &
               self%fy2(4 * nc + 4), self%fb2(4 * nc + 4), self%fb3(4 * nc + 4), &
               self%done(4 * nc + 4))
      associate (p => self%piece)
         allocate(p%f_a(nc), p%f_b(nc), p%vabs_a(nc), p%vabs_b(nc), p%onset_time(nc), &
                  p%int_f(nc), p%int_f2(nc), p%int_work(nc), p%t_contact(nc), p%peak(nc), &
                  source=0.0_dp)
         allocate(p%onset(nc), source=.false.)
      end associate
   end subroutine exact_init

   !> Carry `state` to t_target exactly (see integrator_t%advance).
   subroutine exact_advance(self, state, t_target, obs, err)
      class(exact_integrator_t), intent(inout), target :: self   !! integrator
      type(state_t), intent(inout) :: state               !! state, at t_target on return
      real(dp), intent(in) :: t_target                    !! target time [s]
      class(observer_t), intent(inout), optional :: obs   !! observer of the pieces
      type(error_t), allocatable, intent(out) :: err      !! configuration failure
      real(dp), allocatable :: x0(:), dummy(:)
      integer :: outcome, flips, n, ncfg0
      integer(int64) :: new_mask
      real(dp) :: tau_end, rem
      ncfg0 = self%ncfg
      call self%begin_advance(state, t_target, obs, x0)
      flips = 0
      do
         call self%run_segment(x0, flips, tau_end, outcome, new_mask, obs, err)
         if (allocated(err)) return
         if (outcome == 0) cycle          ! a switch at the first instant: new segment
         if (outcome == end_horizon) exit
         if (outcome == end_anchor) self%steps_accepted = self%steps_accepted - 1
         x0 = self%xe
         self%r0 = self%r0 + tau_end
         if (self%r0 >= self%period) then
            rem = real(int(self%r0 / self%period, int64), dp)
            self%k0 = self%k0 + int(self%r0 / self%period, int64)
            self%r0 = self%r0 - rem * self%period
            if (self%r0 < 0.0_dp) then
               self%r0 = self%r0 + self%period;  self%k0 = self%k0 - 1
            end if
         end if
         if (tau_end > 0.0_dp) flips = 0
         if (outcome == end_switch) then
            call self%register_switch(self%mask, new_mask, 0.0_dp)   ! at the new anchor
            self%mask = new_mask
         end if
      end do
      n = self%n
      call to_physical(self%om, self%xe(1:n), self%xe(n + 1:), state%u, state%v)
      allocate(dummy(size(state%a)))
      call to_physical(self%om, self%ae, self%ae, state%a, dummy)
      state%t = t_target
      call contact_forces_at(self%model, state%u, state%v, state%f)
      state%f_prev = state%f
      state%dt_prev = 0.0_dp
      self%factorizations = self%factorizations + (self%ncfg - ncfg0)
   end subroutine exact_advance

   !> Anchor the time, the horizon and the watch instant; the initial contact activity.
   subroutine begin_advance(self, state, t_target, obs, x0)
      class(exact_integrator_t), intent(inout) :: self    !! integrator
      type(state_t), intent(in) :: state                  !! start
      real(dp), intent(in) :: t_target                    !! target time [s]
      class(observer_t), intent(in), optional :: obs      !! observer
      real(dp), allocatable, intent(out) :: x0(:)         !! modal state (eta, v)
      integer :: c, i
      real(dp) :: d, dd
      call split_time(state%t, self%period, self%k0, self%r0)
      call split_time(t_target, self%period, self%k_end, self%r_end)
      self%t_end = t_target
      self%watching = .false.;  self%watch_due = .false.
      if (present(obs)) then
         self%t_watch = obs%t_watch
         call split_time(obs%t_watch, self%period, self%k_watch, self%r_watch)
         self%watching = state%t >= obs%t_watch
         self%watch_due = .not. self%watching .and. obs%t_watch < t_target
      end if
      self%smin = huge(1.0_dp);  self%smax = -huge(1.0_dp)
      self%rmin = huge(1.0_dp);  self%rmax = -huge(1.0_dp)
      self%peak = 0.0_dp
      self%onset = .false.
      allocate(x0(2 * self%n))
      call to_modal(self%om, state%u, state%v, x0(1:self%n), x0(self%n + 1:))
      self%mask = 0
      do c = 1, self%nc
         i = self%model%c_dof(c)
         d = self%model%c_sign(c) * state%u(i) - self%model%c_gap(c)
         dd = self%model%c_sign(c) * state%v(i)
         if (contact_force(self%model, c, d, dd) > 0.0_dp) self%mask = ibset(self%mask, c - 1)
      end do
   end subroutine begin_advance

   !> One linear segment from x0 at the current anchor: decide the activity at its start (a
   !> switch there returns outcome 0 and the new mask is taken), else sweep it to its end and
   !> leave the end state in xe, ae.
   subroutine run_segment(self, x0, flips, tau_end, outcome, new_mask, obs, err)
      class(exact_integrator_t), intent(inout), target :: self   !! integrator
      real(dp), intent(in) :: x0(:)                       !! modal state at the start
      integer, intent(inout) :: flips                     !! switches at this instant so far
      real(dp), intent(out) :: tau_end                    !! length of the segment [s]
      integer, intent(out) :: outcome                     !! 0, end_switch/horizon/anchor
      integer(int64), intent(out) :: new_mask             !! activity after a switch
      class(observer_t), intent(inout), optional :: obs   !! observer
      type(error_t), allocatable, intent(inout) :: err    !! configuration failure
      integer :: n
      n = self%n
      self%ic = self%config_index(self%mask, err)
      if (allocated(err)) return
      call start_segment(self%om, self%cfgs(self%ic), self%omega, self%period, x0(1:n), &
                         x0(n + 1:), self%r0, self%sg)
      ! activity just after the start, in this representation
      call set_need(self, .false.)
      call eval_seg(self%sg, 0.0_dp, self%need, self%val, self%bnd)
      call self%state_derivs(x0, self%r0)
      new_mask = self%decide()
      tau_end = 0.0_dp
      if (new_mask /= self%mask .and. flips < max_flips) then
         call self%register_switch(self%mask, new_mask, 0.0_dp)
         self%mask = new_mask;  flips = flips + 1
         outcome = 0
         return
      end if
      self%steps_accepted = self%steps_accepted + 1
      call self%init_signs()
      self%tau_w0 = 0.0_dp
      self%n_roots = 0
      self%search_steps = 0
      call self%sweep(tau_end, outcome, new_mask, obs, err)
      if (allocated(err)) return
      call self%emit_window(self%tau_w0, tau_end, obs)
      self%dt_smallest = min(self%dt_smallest, tau_end)
      self%dt_largest = max(self%dt_largest, tau_end)
      call segment_state(self%cfgs(self%ic), self%sg, tau_end, self%xe(1:n), self%xe(n + 1:))
      call self%modal_acceleration(self%xe, self%r0 + tau_end, self%ae)
   end subroutine run_segment

   !> Index of the configuration of `msk`, built on first use.
   integer function config_index(self, msk, err) result(j)
      class(exact_integrator_t), intent(inout) :: self    !! integrator
      integer(int64), intent(in) :: msk                   !! active contacts
      type(error_t), allocatable, intent(inout) :: err    !! build failure
      type(config_t), allocatable :: tmp(:)
      do j = 1, self%ncfg
         if (self%cfgs(j)%mask == msk) return
      end do
      if (self%ncfg == size(self%cfgs)) then
         allocate(tmp(2 * self%ncfg))
         tmp(1:self%ncfg) = self%cfgs(1:self%ncfg)
         call move_alloc(tmp, self%cfgs)
      end if
      self%ncfg = self%ncfg + 1
      j = self%ncfg
      call build_config(self%om, self%model, msk, self%cfgs(j), err)
   end function config_index

   !> Absolute time of tau in the current segment [s], the horizon and watch instants exact.
   real(dp) function abs_time(self, tau) result(t)
      class(exact_integrator_t), intent(in) :: self   !! integrator
      real(dp), intent(in) :: tau                     !! offset in the segment [s]
      t = real(self%k0, dp) * self%period + self%r0 + tau
      if (abs(t - self%t_end) <= self%tol_t) t = self%t_end
      if (self%watch_due .or. self%watching) then
         if (abs(t - self%t_watch) <= self%tol_t) t = self%t_watch
      end if
   end function abs_time

   !> Offset of the instant (k periods + r) from the segment start [s].
   real(dp) function tau_of(self, k, r)
      class(exact_integrator_t), intent(in) :: self   !! integrator
      integer(int64), intent(in) :: k                 !! periods
      real(dp), intent(in) :: r                       !! offset [s]
      tau_of = real(k - self%k0, dp) * self%period + (r - self%r0)
   end function tau_of

   !> Contact functions of contact cc from the slot values: d and lambda = k d + c d'
   !> with derivatives 0..2 (lambda) or 0..3 (d), and their scales/bounds 0..4 (d), 0..3.
   subroutine contact_functions(self, cc, dv, db, lv, lb)
      class(exact_integrator_t), intent(in) :: self   !! integrator
      integer, intent(in) :: cc                       !! contact
      real(dp), intent(out) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)   !! values, bounds
      integer :: b
      real(dp) :: s
      associate (m => self%model)
         b = self%om%cslot(cc);  s = m%c_sign(cc)
         dv = s * self%val(:, b);  dv(0) = dv(0) - m%c_gap(cc)
         db = self%bnd(:, b);  db(0) = db(0) + abs(m%c_gap(cc))
         lv = m%c_k(cc) * dv(0:2) + m%c_c(cc) * dv(1:3)
         lb = m%c_k(cc) * db(0:3) + m%c_c(cc) * db(1:4)
      end associate
   end subroutine contact_functions

   !> Activity of every contact just after the instant of the last state_derivs.
   integer(int64) function decide(self) result(msk)
      class(exact_integrator_t), intent(in) :: self   !! integrator
      integer :: cc
      msk = 0
      do cc = 1, self%nc
         if (self%sign_d(cc) > 0 .and. self%sign_l(cc) > 0) msk = ibset(msk, cc - 1)
      end do
   end function decide

   !> Sign just after the instant of d of contact cc.
   integer function sign_d(self, cc)
      class(exact_integrator_t), intent(in) :: self   !! integrator
      integer, intent(in) :: cc                       !! contact
      sign_d = sign_after(self%dsv(:, cc), self%dss(:, cc))
   end function sign_d

   !> Sign just after the instant of k d + c d' of contact cc (1 without a damper).
   integer function sign_l(self, cc)
      class(exact_integrator_t), intent(in) :: self   !! integrator
      integer, intent(in) :: cc                       !! contact
      sign_l = 1
      associate (m => self%model)
         if (self%damped(cc)) sign_l = sign_after(m%c_k(cc) * self%dsv(0:2, cc) &
            + m%c_c(cc) * self%dsv(1:3, cc), m%c_k(cc) * self%dss(0:2, cc) &
            + m%c_c(cc) * self%dss(1:3, cc))
      end associate
   end function sign_l

   !> Derivatives 0..3 of every contact's penetration d at the modal state x (forcing offset
   !> r), through the modal equations of motion of the current configuration,
   !>    a = p sin(W r) - D v - W^2 eta - sum_active psi_c (k_c psi_c'eta + c_c psi_c'v - w_c),
   !>    a' = p W cos(W r) - D a - W^2 v - sum_active psi_c (k_c psi_c'v + c_c psi_c'a),
   !> and their scales (sums of the magnitudes of the terms): free of the cancellations of the
   !> modal sums, and the same in the representations before and after a switch. bnd must hold
   !> the bounds of the slots at the same instant.
   subroutine state_derivs(self, x, r)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      real(dp), intent(in) :: x(:), r                    !! modal state (eta, v), offset [s]
      real(dp) :: acc(self%n), acs(self%n), jrk(self%n), jcs(self%n), xk(0:3), sk(0:3)
      integer :: cc, n, b
      n = self%n
      call self%modal_acceleration(x, r, acc, acs, jrk, jcs)
      associate (m => self%model, om => self%om)
         do cc = 1, self%nc
            b = om%cslot(cc)
            xk(0) = dot_product(om%ell(:, b), x(1:n))
            sk(0) = dot_product(abs(om%ell(:, b)), abs(x(1:n)))
            xk(1) = dot_product(om%ell(:, b), x(n + 1:))
            sk(1) = dot_product(abs(om%ell(:, b)), abs(x(n + 1:)))
            xk(2) = dot_product(om%ell(:, b), acc)
            sk(2) = dot_product(abs(om%ell(:, b)), acs)
            xk(3) = dot_product(om%ell(:, b), jrk)
            sk(3) = dot_product(abs(om%ell(:, b)), jcs)
            self%dsv(:, cc) = m%c_sign(cc) * xk
            self%dsv(0, cc) = self%dsv(0, cc) - m%c_gap(cc)
            ! d and d' scale only themselves here: their round-off is that of the modal sums
            ! they come from
            self%dss(0, cc) = max(sk(0), self%bnd(0, b)) + abs(m%c_gap(cc))
            self%dss(1, cc) = max(sk(1), self%bnd(1, b))
            self%dss(2:3, cc) = sk(2:3)
         end do
      end associate
   end subroutine state_derivs

   !> Modal acceleration at the modal state x (forcing offset r) in the current
   !> configuration; optionally the scales of its terms, the jerk and its scales.
   subroutine modal_acceleration(self, x, r, acc, acs, jrk, jcs)
      class(exact_integrator_t), intent(in) :: self      !! integrator
      real(dp), intent(in) :: x(:), r                    !! modal state (eta, v), offset [s]
      real(dp), intent(out) :: acc(:)                    !! (n) acceleration
      real(dp), intent(out), optional :: acs(:), jrk(:), jcs(:)   !! scales, jerk, scales
      real(dp) :: sn, cs, pe, pv, pa, fc
      integer :: i, n
      n = self%n
      sn = sin(self%omega * r);  cs = cos(self%omega * r)
      associate (om => self%om, cf => self%cfgs(self%ic), eta => x(1:n), v => x(n + 1:))
         acc = om%pload * sn - om%d * v - om%w2 * eta
         if (present(acs)) acs = abs(om%pload * sn) + abs(om%d * v) + abs(om%w2 * eta)
         do i = 1, cf%r
            pe = dot_product(cf%psi(:, i), eta);  pv = dot_product(cf%psi(:, i), v)
            fc = cf%kc(i) * pe + cf%cc(i) * pv - cf%wgap(i)
            acc = acc - cf%psi(:, i) * fc
            if (present(acs)) acs = acs + abs(cf%psi(:, i)) * (abs(cf%kc(i) * pe) &
                                          + abs(cf%cc(i) * pv) + abs(cf%wgap(i)))
         end do
         if (.not. present(jrk)) return
         jrk = om%pload * self%omega * cs - om%d * acc - om%w2 * v
         jcs = abs(om%pload * self%omega) + abs(om%d * acc) + abs(om%w2 * v)
         do i = 1, cf%r
            pv = dot_product(cf%psi(:, i), v);  pa = dot_product(cf%psi(:, i), acc)
            jrk = jrk - cf%psi(:, i) * (cf%kc(i) * pv + cf%cc(i) * pa)
            jcs = jcs + abs(cf%psi(:, i)) * (abs(cf%kc(i) * pv) + abs(cf%cc(i) * pa))
         end do
      end associate
   end subroutine modal_acceleration

   !> Signs of the watched functions at the start of a segment, consistent with `mask`;
   !> a function within round-off of zero gets a dead band.
   subroutine init_signs(self)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      integer :: cc
      real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
      logical :: on
      do cc = 1, self%nc
         call self%contact_functions(cc, dv, db, lv, lb)
         on = btest(self%mask, cc - 1)
         self%sig_d(cc) = self%sign_d(cc)
         self%sig_l(cc) = self%sign_l(cc)
         if (on) then
            self%sig_d(cc) = 1;  self%sig_l(cc) = 1
         else
            if (self%sig_d(cc) == 0) self%sig_d(cc) = -1
            if (self%sig_l(cc) == 0) self%sig_l(cc) = -1
            if (self%sig_d(cc) > 0 .and. self%sig_l(cc) > 0) self%sig_l(cc) = -1
         end if
         self%del_d(cc) = band(self%sig_d(cc) * dv(0), db(0))
         self%del_l(cc) = 0.0_dp
         if (self%damped(cc)) self%del_l(cc) = band(self%sig_l(cc) * lv(0), lb(0))
      end do
   end subroutine init_signs

   !> Onsets and releases between masks m_old and m_new at tau of the current segment: the
   !> onsets go to the next piece.
   subroutine register_switch(self, m_old, m_new, tau)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      integer(int64), intent(in) :: m_old, m_new         !! activity before, after
      real(dp), intent(in) :: tau                        !! instant in the segment [s]
      integer :: cc
      self%events = self%events + 1
      do cc = 1, self%nc
         if (btest(m_new, cc - 1) .and. .not. btest(m_old, cc - 1) .and. &
             .not. self%onset(cc)) then
            self%onset(cc) = .true.
            self%onset_t(cc) = self%abs_time(tau)
         end if
      end do
   end subroutine register_switch

   !> Functionals evaluated in the sweep: the contact slots, and the strain while watching
   !> (for its extrema); all of them if `all`.
   subroutine set_need(self, all)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      logical, intent(in) :: all                         !! every functional
      self%need = all
      self%need(1:self%om%n_slots) = .true.
      if (self%watching) self%need(self%om%b_strain) = .true.
   end subroutine set_need

   !> Sweep the segment from tau = 0: zeros of d', extrema while watching, until a switch, the
   !> horizon or a re-anchoring instant; windows end at the watch instant, at Taylor sub-steps
   !> and when the list of zeros of d' is full.
   subroutine sweep(self, tau_stop, how, m_new, obs, err)
      class(exact_integrator_t), intent(inout), target :: self   !! integrator
      real(dp), intent(out) :: tau_stop                   !! where the segment ends [s]
      integer, intent(out) :: how                         !! end_switch, horizon or anchor
      integer(int64), intent(out) :: m_new                !! activity after a switch
      class(observer_t), intent(inout), optional :: obs   !! observer
      type(error_t), allocatable, intent(inout) :: err    !! the search does not advance
      real(dp) :: tau, target, tl, tr
      logical :: switched
      m_new = self%mask
      tau_stop = 0.0_dp;  how = end_horizon
      tau = 0.0_dp      ! val, bnd hold the values at tau = 0
      if (self%watching) call self%start_trackers(tau)
      do
         ! next stop: re-anchoring, the horizon, the watch instant
         tl = self%tau_of(self%k_end, self%r_end)
         target = min(2.0_dp * self%period, tl)
         tr = huge(1.0_dp)
         if (self%watch_due) tr = self%tau_of(self%k_watch, self%r_watch)
         target = max(min(target, tr), tau)
         call advance_to(self, tau, target, switched, m_new, obs, err)
         if (allocated(err)) return
         if (switched) then
            tau_stop = tau;  how = end_switch
            return
         end if
         if (tau >= tr) then
            call self%start_watching(tau, obs)
            cycle
         end if
         if (tau >= tl) then
            tau_stop = tau;  how = end_horizon
            return
         end if
         if (tau >= 2.0_dp * self%period) then
            tau_stop = tau;  how = end_anchor
            return
         end if
      end do
   end subroutine sweep

   !> Step from tau towards target with safe steps; stops early at a switch. More than
   !> search_limit steps in one segment is an error naming the time and the cause.
   subroutine advance_to(self, tau, target, switched, m_new, obs, err)
      class(exact_integrator_t), intent(inout), target :: self   !! integrator
      real(dp), intent(inout) :: tau                      !! current instant [s]
      real(dp), intent(in) :: target                      !! where to go [s]
      logical, intent(out) :: switched                    !! a switch ended the segment
      integer(int64), intent(inout) :: m_new              !! the new activity
      class(observer_t), intent(inout), optional :: obs   !! observer
      type(error_t), allocatable, intent(inout) :: err    !! the search does not advance
      real(dp) :: tn, h, hf, tt
      integer :: kind_hit, c_hit, n
      logical :: hit
      switched = .false.
      n = self%n
      associate (cf => self%cfgs(self%ic), sg => self%sg)
         do while (tau < target)
            self%search_steps = self%search_steps + 1
            if (self%search_steps > self%search_limit) then
               call stalled(self, tau, err)
               return
            end if
            h = min(self%step_limit(), target - tau)
            hf = max(self%tol_t, 4.0_dp * spacing(max(tau, self%period)))
            if (h < hf) h = min(hf, target - tau)
            tn = min(tau + h, target)
            call eval_seg(sg, tn, self%need, self%val, self%bnd)
            call self%find_flip(tau, tn, hf, hit, tt, kind_hit, c_hit)
            if (hit) then
               tn = tt
               call eval_seg(sg, tn, self%need, self%val, self%bnd)
               if (kind_hit == 3) then
                  ! zero of d' in a contact phase: splits the work integral (a full list
                  ! closes the window here)
                  if (self%n_roots(c_hit) == max_roots) then
                     call self%emit_window(self%tau_w0, tn, obs)
                     self%tau_w0 = tn
                  else
                     self%n_roots(c_hit) = self%n_roots(c_hit) + 1
                     self%roots(self%n_roots(c_hit), c_hit) = tn
                  end if
                  self%sig_w(c_hit) = -self%sig_w(c_hit);  self%del_w(c_hit) = 0.0_dp
               else
                  call segment_state(cf, sg, tn, self%xe(1:n), self%xe(n + 1:))
                  call self%state_derivs(self%xe, self%r0 + tn)
                  m_new = self%decide()
                  if (m_new /= self%mask) then
                     if (self%watching) call self%update_trackers()
                     tau = tn;  switched = .true.
                     return
                  end if
                  if (kind_hit == 1) then
                     self%sig_d(c_hit) = -self%sig_d(c_hit);  self%del_d(c_hit) = 0.0_dp
                  else
                     self%sig_l(c_hit) = -self%sig_l(c_hit);  self%del_l(c_hit) = 0.0_dp
                  end if
               end if
            end if
            tau = tn
            ! the last evaluation was at tau: decayed terms leave from here on
            if (mod(self%search_steps, prune_every) == 0) call prune_seg(sg)
            call self%clear_bands()
            if (self%watching) call self%update_trackers()
         end do
      end associate
   end subroutine advance_to

   !> The error of an event search that does not advance: where, and what to change.
   subroutine stalled(self, tau, err)
      class(exact_integrator_t), intent(in) :: self     !! integrator
      real(dp), intent(in) :: tau                       !! instant in the segment [s]
      type(error_t), allocatable, intent(inout) :: err  !! the error
      real(dp) :: fast, slow
      integer :: j
      character(len=:), allocatable :: what
      ! the fastest live terms: those that do not decay, else any
      fast = 0.0_dp;  slow = 0.0_dp
      do j = 1, self%sg%nt
         if (.not. self%sg%live(j) .or. self%sg%root(j) == 0) cycle
         fast = max(fast, abs(self%sg%mu(j)))
         if (abs(real(self%sg%mu(j))) <= 1.0e-6_dp * abs(self%sg%mu(j))) &
            slow = max(slow, abs(self%sg%mu(j)))
      end do
      if (slow > 0.0_dp) then
         what = 'undamped terms up to ' // str(slow) // ' 1/s keep its watched functions ' &
            // 'oscillating'
      else
         what = 'its watched functions carry terms up to ' // str(fast) // ' 1/s'
      end if
      call fatal_error(err, 'gapbeam_exact: the event search at t = ' &
         // str(self%abs_time(tau)) // ' s needs more than ' // str(self%search_limit) &
         // ' steps in one linear segment (configuration ' // mask_text(self%mask, self%nc) &
         // '; ' // what // '): add damping (&damping stiffness_coefficient), use fewer ' &
         // 'elements, or use method = ''newmark''')
   end subroutine stalled

   !> The watch instant is reached at tau: close the window before it, start the statistics.
   subroutine start_watching(self, tau, obs)
      class(exact_integrator_t), intent(inout), target :: self   !! integrator
      real(dp), intent(in) :: tau                         !! the watch instant [s]
      class(observer_t), intent(inout), optional :: obs   !! observer
      call self%emit_window(self%tau_w0, tau, obs)
      self%watching = .true.;  self%watch_due = .false.
      self%tau_w0 = tau
      self%n_roots = 0
      call set_need(self, .false.)
      call eval_seg(self%sg, tau, self%need, self%val, self%bnd)
      call self%start_trackers(tau)
   end subroutine start_watching

   !> Largest safe step from the current values for every watched function.
   real(dp) function step_limit(self) result(h)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      integer :: cc, bs, ks, f, k
      real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3), tol, s, qmin
      ! pass 1: the quadratic (and monotone) steps of every watched function
      self%nf = 0
      do cc = 1, self%nc
         call self%contact_functions(cc, dv, db, lv, lb)
         s = self%sig_d(cc)
         call self%add(s * dv(0) + self%del_d(cc), s * dv(1), s * dv(2), db(2), db(3), 0.0_dp)
         if (self%damped(cc)) then
            s = self%sig_l(cc)
            call self%add(s * lv(0) + self%del_l(cc), s * lv(1), s * lv(2), lb(2), lb(3), 0.0_dp)
         end if
         if (self%watching .and. btest(self%mask, cc - 1)) then
            s = self%sig_w(cc)
            call self%add(s * dv(1) + self%del_w(cc), s * dv(2), s * dv(3), db(3), db(4), 0.0_dp)
            ks = self%model%c_stop(cc)
            tol = peak_tol * lb(0)
            call self%add(self%peak(ks) + tol - lv(0), -lv(1), -lv(2), lb(2), lb(3), &
                          mono_quad(lv(1), lv(2), lb(3)))
         end if
      end do
      if (self%watching) then
         bs = self%om%b_strain
         associate (val => self%val, bnd => self%bnd)
            tol = peak_tol * bnd(0, bs)
            call self%add(self%smax + tol - val(0, bs), -val(1, bs), -val(2, bs), bnd(2, bs), &
                          bnd(3, bs), mono_quad(val(1, bs), val(2, bs), bnd(3, bs)))
            call self%add(val(0, bs) - self%smin + tol, val(1, bs), val(2, bs), bnd(2, bs), &
                          bnd(3, bs), mono_quad(val(1, bs), val(2, bs), bnd(3, bs)))
            tol = peak_tol * bnd(1, bs)
            call self%add(self%rmax + tol - val(1, bs), -val(2, bs), -val(3, bs), bnd(3, bs), &
                          bnd(4, bs), mono_quad(val(2, bs), val(3, bs), bnd(4, bs)))
            call self%add(val(1, bs) - self%rmin + tol, val(2, bs), val(3, bs), bnd(3, bs), &
                          bnd(4, bs), mono_quad(val(2, bs), val(3, bs), bnd(4, bs)))
         end associate
      end if
      ! pass 2: in ascending order of the quadratic steps, the cubic bound where it can
      ! still lengthen the step (the result is the least over the functions)
      h = self%period
      self%done = .false.
      do k = 1, self%nf
         qmin = huge(1.0_dp);  f = 0
         do cc = 1, self%nf
            if (.not. self%done(cc) .and. self%q(cc) < qmin) then
               qmin = self%q(cc);  f = cc
            end if
         end do
         if (f == 0 .or. qmin >= h) exit
         self%done(f) = .true.
         s = qmin
         if (self%fy(f) > 0.0_dp .and. self%fy2(f) > -0.5_dp * self%fb2(f) .and. &
             self%fb3(f) > 0.0_dp) s = max(s, cubic_root(self%fy(f), self%fy1(f), &
             0.5_dp * self%fy2(f), self%fb3(f) / 6.0_dp, h))
         h = min(h, s)
      end do
   end function step_limit

   !> Record one watched function for step_limit (see add_fn).
   subroutine add(self, y0, y1, y2, b2, b3, hm)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      real(dp), intent(in) :: y0, y1, y2, b2, b3, hm     !! value, derivatives, bounds, step
      call add_fn(self%nf, self%q, self%fy, self%fy1, self%fy2, self%fb2, self%fb3, y0, y1, y2, &
                  b2, b3, hm)
   end subroutine add

   !> Did a watched function change sign on (ta, tb]? If so, bracket the first such change
   !> to hf and return its upper end tt, the kind (1: d, 2: lambda, 3: d') and the contact.
   !> On return, val/bnd hold the values at tb (not tt).
   subroutine find_flip(self, ta, tb, hf, hit, tt, kind_hit, c_hit)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      real(dp), intent(in) :: ta, tb, hf                 !! interval, bracket width [s]
      logical, intent(out) :: hit                        !! a change of sign
      real(dp), intent(out) :: tt                        !! its upper bracket [s]
      integer, intent(out) :: kind_hit, c_hit            !! which function
      integer :: cc, kk
      real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3), y, t1
      hit = .false.;  tt = tb;  kind_hit = 0;  c_hit = 0
      do cc = 1, self%nc
         call self%contact_functions(cc, dv, db, lv, lb)
         do kk = 1, 3
            select case (kk)
            case (1)
               y = self%sig_d(cc) * dv(0) + self%del_d(cc)
            case (2)
               if (.not. self%damped(cc)) cycle
               y = self%sig_l(cc) * lv(0) + self%del_l(cc)
            case (3)
               if (.not. (self%watching .and. btest(self%mask, cc - 1))) cycle
               y = self%sig_w(cc) * dv(1) + self%del_w(cc)
            end select
            if (y >= 0.0_dp) cycle
            t1 = tb
            if (tb - ta > hf) t1 = self%refine(cc, kk, ta, tb, hf)
            if (.not. hit .or. t1 < tt) then
               hit = .true.;  tt = t1;  kind_hit = kk;  c_hit = cc
            end if
         end do
      end do
   end subroutine find_flip

   !> Value of watched function (contact cc, kind kk) at tau, sign-adjusted (y < 0: flipped).
   real(dp) function watched(self, cc, kk, tau) result(y)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: cc, kk                      !! contact, kind
      real(dp), intent(in) :: tau                        !! instant [s]
      real(dp) :: dv(0:3), s, v2(0:3, self%nb), b2(0:4, self%nb)
      logical :: nd(self%nb)
      integer :: b
      associate (m => self%model)
         nd = .false.;  b = self%om%cslot(cc);  nd(b) = .true.
         call eval_seg(self%sg, tau, nd, v2, b2)
         s = m%c_sign(cc)
         dv = s * v2(:, b);  dv(0) = dv(0) - m%c_gap(cc)
         select case (kk)
         case (1)
            y = self%sig_d(cc) * dv(0) + self%del_d(cc)
         case (2)
            y = self%sig_l(cc) * (m%c_k(cc) * dv(0) + m%c_c(cc) * dv(1)) + self%del_l(cc)
         case default
            y = self%sig_w(cc) * dv(1) + self%del_w(cc)
         end select
      end associate
   end function watched

   !> Bracket the first sign change of a watched function in (ta, tb] to width hf
   !> (bisection with a secant guess); returns the upper end.
   real(dp) function refine(self, cc, kk, ta, tb, hf) result(t1)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: cc, kk                      !! contact, kind
      real(dp), intent(in) :: ta, tb, hf                 !! interval, bracket width [s]
      real(dp) :: lo, hi, ylo, yhi, mid, ym
      integer :: it, side
      lo = ta;  hi = tb
      ylo = self%watched(cc, kk, lo);  yhi = self%watched(cc, kk, hi)
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
         ym = self%watched(cc, kk, mid)
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
   subroutine clear_bands(self)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      integer :: cc
      real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
      do cc = 1, self%nc
         if (self%del_d(cc) == 0.0_dp .and. self%del_l(cc) == 0.0_dp .and. &
             self%del_w(cc) == 0.0_dp) cycle
         call self%contact_functions(cc, dv, db, lv, lb)
         if (self%sig_d(cc) * dv(0) > self%del_d(cc)) self%del_d(cc) = 0.0_dp
         if (self%sig_l(cc) * lv(0) > self%del_l(cc)) self%del_l(cc) = 0.0_dp
         if (self%sig_w(cc) * dv(1) > self%del_w(cc)) self%del_w(cc) = 0.0_dp
      end do
   end subroutine clear_bands

   !> Running extrema at the current values (while watching).
   subroutine update_trackers(self)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      integer :: cc, bs, ks
      real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
      bs = self%om%b_strain
      self%smax = max(self%smax, self%val(0, bs))
      self%smin = min(self%smin, self%val(0, bs))
      self%rmax = max(self%rmax, self%val(1, bs))
      self%rmin = min(self%rmin, self%val(1, bs))
      do cc = 1, self%nc
         if (.not. btest(self%mask, cc - 1)) cycle
         call self%contact_functions(cc, dv, db, lv, lb)
         ks = self%model%c_stop(cc)
         self%peak(ks) = max(self%peak(ks), lv(0))
      end do
   end subroutine update_trackers

   !> Begin the watch-only trackers at tau: extrema and the sign of d' of active contacts.
   subroutine start_trackers(self, tau)
      class(exact_integrator_t), intent(inout) :: self   !! integrator
      real(dp), intent(in) :: tau                        !! instant [s]
      integer :: cc
      real(dp) :: dv(0:3), db(0:4), lv(0:2), lb(0:3)
      call self%update_trackers()
      call segment_state(self%cfgs(self%ic), self%sg, tau, self%xe(1:self%n), &
                         self%xe(self%n + 1:))
      call self%state_derivs(self%xe, self%r0 + tau)
      do cc = 1, self%nc
         call self%contact_functions(cc, dv, db, lv, lb)
         self%sig_w(cc) = sign_after(self%dsv(1:3, cc), self%dss(1:3, cc))
         if (self%sig_w(cc) == 0) self%sig_w(cc) = 1
         self%del_w(cc) = band(self%sig_w(cc) * dv(1), db(1))
      end do
   end subroutine start_trackers

   !> Hand the window [ta, tb] of the current segment to the observer: while watching, the
   !> closed-form integrals of every active contact over it and the running extrema.
   subroutine emit_window(self, ta, tb, obs)
      class(exact_integrator_t), intent(inout), target :: self   !! integrator
      real(dp), intent(in) :: ta, tb                      !! window in the segment [s]
      class(observer_t), intent(inout), optional :: obs   !! observer
      integer :: cc
      real(dp) :: sf, sf2, sw
      if (.not. present(obs) .or. .not. (tb > ta)) then
         self%n_roots = 0
         return
      end if
      associate (p => self%piece, m => self%model)
         p%sg => self%sg;  p%cf => self%cfgs(self%ic);  p%om => self%om
         p%model => self%model
         p%omega = self%omega;  p%mask = self%mask
         p%t0 = real(self%k0, dp) * self%period + self%r0
         p%ta = self%abs_time(ta);  p%tb = self%abs_time(tb)
         p%onset = self%onset;  p%onset_time = self%onset_t
         self%onset = .false.
         p%exact_statistics = self%watching
         p%int_f = 0.0_dp;  p%int_f2 = 0.0_dp;  p%int_work = 0.0_dp;  p%t_contact = 0.0_dp
         if (self%watching) then
            do cc = 1, self%nc
               p%peak(cc) = self%peak(m%c_stop(cc))
               if (.not. btest(self%mask, cc - 1)) cycle
               call modal_window(self%sg, self%om%cslot(cc), m%c_sign(cc), m%c_k(cc), &
                  m%c_c(cc), m%c_gap(cc), ta, tb, self%roots(1:self%n_roots(cc), cc), sf, sf2, sw)
               p%int_f(cc) = sf;  p%int_f2(cc) = sf2;  p%int_work(cc) = sw
               p%t_contact(cc) = tb - ta
            end do
            p%strain_min = self%smin;  p%strain_max = self%smax
            p%rate_min = self%rmin;  p%rate_max = self%rmax
         end if
      end associate
      call obs%observe(self%piece)
      self%n_roots = 0
   end subroutine emit_window

   !> A time as whole forcing periods and an offset in [0, T) (a time within 1e-9 T of a
   !> period boundary is on it).
   pure subroutine split_time(t, period, k, r)
      real(dp), intent(in) :: t, period       !! time, period [s]
      integer(int64), intent(out) :: k        !! periods
      real(dp), intent(out) :: r              !! offset [s]
      real(dp) :: x
      x = t / period
      if (abs(x - anint(x)) <= 1.0e-9_dp * max(1.0_dp, abs(x))) then
         k = nint(x, int64);  r = 0.0_dp
      else
         k = floor(x, int64);  r = t - real(k, dp) * period
      end if
   end subroutine split_time
end module gapbeam_exact
