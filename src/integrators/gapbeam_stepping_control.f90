!> Error control of the stepping integrator (step_control = 'error'): the step-size ladder
!> h_max 2^(-L/2), the watched outputs and their floors, the local error of a step from the
!> method's estimate (or Richardson's two half steps) relative to the outputs' ranges within
!> a budget per block of an eighth of a forcing period, with the order of the method's
!> registry entry; steps end at contact switches.
submodule (gapbeam_stepping) gapbeam_stepping_control
   use gapbeam_random_load, only: rms_load
   implicit none

contains

   !> Error control: the step-size ladder h_max 2^(-L/2) (a factorisation per size, cached),
   !> the watched outputs (root strain, tip and contact displacements) and their floors: the
   !> quasi-static response to the forcing amplitude, K u = (A_pp/2) Omega^2 q.
   module subroutine init_control(self, model, cfg, err)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model
      type(solver_settings_t), intent(in) :: cfg            !! settings
      type(error_t), allocatable, intent(out) :: err        !! singular stiffness
      real(dp), allocatable :: kf(:, :), uqs(:)
      real(dp) :: v_turb
      integer :: info, c, n_out
      self%tolerance = cfg%tolerance
      ! the order the controller assumes for the method's error estimate (its registry entry)
      self%order = max(1, self%caps%control_order)
      ! with ring contacts the watched outputs are the supports' (w, v) and their velocities,
      ! the tip and the root strain: the root strain rate carries the high modes every
      ! impact excites, and resolving them to the tolerance of its range cost twice the steps
      ! of the supports' orbits (docs/tubes.md)
      self%watch_rate = model%n_rings == 0
      self%h_max = self%period / 16.0_dp
      self%n_levels = 2 * cfg%max_halvings + 9
      if (allocated(self%h_lev)) deallocate(self%h_lev)
      allocate(self%h_lev(0:self%n_levels - 1))
      do c = 0, self%n_levels - 1
         self%h_lev(c) = self%h_max * 2.0_dp**(-0.5_dp * c)
      end do
      allocate(self%fda(model%n), self%ev(model%n), self%eu(model%n), self%fda_prev(model%n), &
               self%eu_d(model%n), self%ev_d(model%n), self%eu_q(model%n), self%ev_q(model%n), &
               source=0.0_dp)
      self%out_dof = [integer ::]
      if (model%sys%tip_dof > 0) self%out_dof = [model%sys%tip_dof]
      if (model%sys%tip_dof_v > 0) self%out_dof = [self%out_dof, model%sys%tip_dof_v]
      do c = 1, model%n_slots
         if (.not. any(self%out_dof == model%slot_dof(c))) &
            self%out_dof = [self%out_dof, model%slot_dof(c)]
      end do
      n_out = 1 + size(self%out_dof)       ! the root strain first
      allocate(self%out_lo(2 * n_out), self%out_hi(2 * n_out), self%out_floor(2 * n_out))
      kf = model%sys%k
      ! a mechanism (rigid modes): no quasi-static response; the floors from the response of
      ! K + Omega^2 M instead (quasi-static in the stiff dofs, the inertia's in the rigid modes)
      if (model%mechanism) kf = model%sys%k + model%omega**2 * model%sys%m
      uqs = model%half_amplitude * model%omega**2 * model%q
      call dpotrf('U', model%n, kf, model%n, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_stepping: the stiffness matrix is not positive ' &
            // 'definite (dpotrf info=' // str(info) // ')')
         return
      end if
      call dpotrs('U', model%n, 1, kf, model%n, uqs, model%n, info)
      self%out_floor(1) = abs(dot_product(self%sw, uqs(self%si)))
      self%out_floor(2:n_out) = abs(uqs(self%out_dof))
      self%out_floor(n_out + 1:) = model%omega * self%out_floor(1:n_out)
      v_turb = huge(1.0_dp)
      if (has_tube_physics(model)) call tube_floors(self, model, kf, n_out, v_turb)
      ! after tube_floors, which sets the displacement floors anew
      if (model%mechanism) call mechanism_floors(self, model, n_out)
      if (model%n_rings > 0) call wear_floors(self, model, n_out, v_turb)
      if (self%caps%estimator == 'embedded') then
         ! rk_atol [m, m/s]: an absolute floor of the displacement and velocity outputs
         self%out_floor(2:n_out) = max(self%out_floor(2:n_out), cfg%rk_atol / cfg%tolerance)
         self%out_floor(n_out + 2:) = max(self%out_floor(n_out + 2:), cfg%rk_atol / cfg%tolerance)
      end if
   end subroutine init_control

   !> The floors of a mechanism, whose free flight has no strain at all and, without forcing,
   !> no response scale (the ranges start at 0 while the dofs move): a displacement of 1e-3 x
   !> the widest gap (at least 1e-9 x the span) and the strain such displacements of the
   !> strain row's nodes give are no errors to control (the strain of a rigid motion is round-off,
   !> eps ||K|| ||u|| ringing in the stiff modes, not a motion to resolve).
   subroutine mechanism_floors(self, model, n_out)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model (a mechanism)
      integer, intent(in) :: n_out                          !! displacement outputs
      real(dp) :: fu
      fu = 1.0e-9_dp * model%sys%element_length * real(model%sys%n_node - 1, dp)
      if (model%n_contacts > 0) fu = max(fu, 1.0e-3_dp * maxval(abs(model%c_gap)))
      self%out_floor(1) = max(self%out_floor(1), sum(abs(self%sw)) * fu)
      self%out_floor(2:n_out) = max(self%out_floor(2:n_out), fu)
      self%out_floor(n_out + 1:) = max(self%out_floor(n_out + 1:), &
                                       model%omega * self%out_floor(1:n_out))
   end subroutine mechanism_floors

   !> Carry `state` to t_target with error control: steps from the ladder, each accepted when
   !> the estimate of its local error in every watched output is within tolerance * (the
   !> output's range) * (step / forcing period); a step in which a contact opens or closes ends
   !> at that instant (its own step size, one factorisation), so no estimate straddles a
   !> switch; the last step before t_target and the observer's watch instant is cut to land on
   !> it.
   module subroutine advance_controlled(self, state, t_target, obs, err)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      type(state_t), intent(inout) :: state                 !! state, at t_target on return
      real(dp), intent(in) :: t_target                      !! target time [s]
      class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
      type(error_t), allocatable, intent(out) :: err        !! numerical failure
      real(dp) :: t, t_stop, tiny_t
      integer :: level
      call copy_state(state, self%sub(self%ix(0)))
      if (state%dt_prev == 0.0_dp) then
         call start_floors(self, state)
         ! begin at T / steps_per_period
         level = min(self%n_levels - 1, max(0, nint(2.0_dp * log(real(self%cfg%steps_per_period, &
            dp) / 16.0_dp) / log(2.0_dp))))
         self%sub(self%ix(0))%dt_prev = self%h_max / 16.0_dp
      else
         level = min(max(state%level, 0), self%n_levels - 1)
      end if
      self%t_begin = state%t;  self%n_since = 0;  self%t_checked = state%t
      self%energy_ref = 0.5_dp * dot_product(state%u, matmul(self%model%sys%k, state%u)) &
                        + 0.5_dp * dot_product(state%v, matmul(self%model%sys%m, state%v))
      self%block_start = state%t;  self%block_sum = 0.0_dp
      self%h_prev = 0.0_dp;  self%t_comp = 0.0_dp
      self%piece%model => self%model
      self%piece%sub => self%sub
      call self%track_outputs(self%sub(self%ix(0)), .true.)
      t = state%t
      tiny_t = 1.0e-12_dp * self%period
      do while (t < t_target - tiny_t)
         t_stop = t_target
         if (present(obs)) then
            if (obs%t_watch > t + tiny_t .and. obs%t_watch < t_target) t_stop = obs%t_watch
         end if
         call self%controlled_step(level, t_stop, obs, err)
         if (allocated(err)) return
         t = self%sub(self%ix(0))%t
      end do
      call copy_state(self%sub(self%ix(0)), state)
      state%t = t_target
      state%level = level
      self%fp_iterations = self%scratch%iterations + sum([(self%ops(level)%iterations, &
                                                          level = 0, self%n_levels - 1)])
   end subroutine advance_controlled

   !> One accepted step from sub-state ix(0) (rejections and smaller sizes inside), ending at
   !> or before t_stop or at a contact event; the level for the next step on return.
   module subroutine controlled_step(self, level, t_stop, obs, err)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      integer, intent(inout) :: level                       !! ladder level
      real(dp), intent(in) :: t_stop                        !! do not step beyond [s]
      class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
      type(error_t), allocatable, intent(out) :: err        !! failure at the smallest step
      real(dp) :: t0, t1, h, theta, ratio, r, q, coef(3), comp, qd, ql, cap
      logical :: ok, event, clipped, on_scratch, dense_held
      integer :: worst, switches, r_worst, d_worst
      real(dp) :: qd_held
      t0 = self%sub(self%ix(0))%t
      switches = 0
      cap = block_fraction * budget_scale * self%tolerance   ! one step's share of the budget
      do
         r = 0.0_dp;  self%held_ring = 0
         h = self%h_lev(level)
         if (t0 + h > t_stop - 1.0e-9_dp * h) then
            h = t_stop - t0
            call self%scratch%prepare(self%model, self%cfg, h, err)
            if (allocated(err)) return
            self%factorizations = self%factorizations + 1
            call self%one_step(self%scratch, 0, 0, ok, r)
            on_scratch = .true.
         else
            on_scratch = .false.
            if (.not. self%ops(level)%ready) then
               call self%ops(level)%prepare(self%model, self%cfg, h, err)
               if (allocated(err)) return
               self%factorizations = self%factorizations + 1
            end if
            call self%one_step(self%ops(level), 0, 0, ok, r)
         end if
         clipped = h == t_stop - t0
         call next_time(t0, h, self%t_comp, clipped, t1, comp)
         self%sub(self%ix(1))%t = t1
         event = .false.;  dense_held = .false.
         if (ok .and. self%cfg%locate_events .and. self%model%n_contacts &
             + self%model%n_rings > 0) then
            ! a trial step that enters a ring is redone with that ring held open: its onset
            ! is located on the free flight's quintic, which its check holds (the cubic of the
            ! step that entered cannot follow the contact begun inside it)
            if (level < self%n_levels - 2) self%held_ring = entered_ring(self)
            if (self%held_ring > 0) then
               if (on_scratch) then
                  call self%one_step(self%scratch, 0, self%model%n_contacts + self%held_ring, &
                                     ok, r)
               else
                  call self%one_step(self%ops(level), 0, self%model%n_contacts &
                                     + self%held_ring, ok, r)
               end if
            end if
            ! events are located on this trial step's interpolant: one that fails its own
            ! check (dense_error) places none; a smaller step first (the cubic's error ~ h^4)
            qd = dense_of(self, on_scratch, level, r_worst)
            ! held for the acceptance below while this trial step stands (ended at no event)
            qd_held = qd;  d_worst = r_worst;  dense_held = .true.
            if (qd > 1.0_dp .and. level < self%n_levels - 1) then
               self%steps_rejected = self%steps_rejected + 1
               level = min(self%n_levels - 1, level + levels_down(qd, 4))
               cycle
            end if
            theta = self%first_event(0, h)
            if (theta <= min_split .and. self%ev_friction .and. switches < 4) then
               ! a stick-slip switch at the very start: the regime changes there
               switches = switches + 1
               associate (s0 => self%sub(self%ix(0)))
                  call update_ring_modes(self%model, s0%u, s0%v, s0%a, s0%mode, s0%sigma, &
                                         s0%anchor, self%ev_contact - self%model%n_contacts)
               end associate
               cycle
            end if
            if (theta * h > min_split * h .and. (1.0_dp - theta) * h > min_split * h) then
               ! end the step at the event: one factorisation for its size
               call self%scratch%prepare(self%model, self%cfg, theta * h, err)
               if (allocated(err)) return
               self%factorizations = self%factorizations + 1
               call self%one_step(self%scratch, 0, merge(self%ev_contact, 0, self%ev_onset), &
                                  ok, r)
               h = theta * h
               call next_time(t0, h, self%t_comp, .false., t1, comp)
               self%sub(self%ix(1))%t = t1
               event = .true.;  on_scratch = .true.;  dense_held = .false.
            end if
            if (self%held_ring > 0 .and. .not. event) then
               ! the held ring's onset not placed inside the step: a smaller one
               self%steps_rejected = self%steps_rejected + 1
               level = min(self%n_levels - 1, level + 1)
               cycle
            end if
         end if
         if (ok) then
            ! (the stepper that took the step: a step clipped to t_stop within 1e-9 of the
            ! level's size was taken by the scratch stepper, and the level's holds another
            ! step's estimate, or none)
            if (on_scratch) then
               call self%scratch%local_error(self%model, self%sub(self%ix(0)), &
                  self%sub(self%ix(1)), self%fda, self%ev, coef, ok)
            else
               call self%ops(level)%local_error(self%model, self%sub(self%ix(0)), &
                  self%sub(self%ix(1)), self%fda, self%ev, coef, ok)
            end if
            if (.not. ok) then
               call fatal_error(err, "gapbeam_stepping: method '" // self%method // "' has " &
                  // "no local error estimate: use step_control = 'fixed'")
               return
            end if
            q = self%error_ratio(h, coef, worst)
            ! the wear watch's part held per step (wear_ratio), against a step's cap
            ql = self%wear_local / cap
            if (ql > q / cap) worst = 2 * (1 + size(self%out_dof)) + self%wear_local_ring
            if (self%h_prev == 0.0_dp .and. coef(2) >= 0.0_dp .and. coef(3) /= 0.0_dp) then
               ! the first step from a start or a contact event has no previous step to
               ! estimate a'' from: its velocity error is measured by two half steps
               call self%richardson(level, h, event, r, worst, err)
               if (allocated(err)) return
               dense_held = .false.   ! (its half steps may reuse the stepper)
               q = max(q, r)
               ql = max(ql, self%wear_local / cap)
            end if
            ! (after error_ratio: it overwrites the error arrays that error_ratio reads; the
            ! value found before event location when the step is the same: no input of it
            ! has changed since, and after it nothing reads the arrays it leaves)
            if (dense_held) then
               qd = qd_held;  r_worst = d_worst
            else
               qd = dense_of(self, on_scratch, level, r_worst)
            end if
            if (qd > max(ql, q / cap)) worst = r_worst
         else
            q = huge(1.0_dp);  worst = 0;  qd = 0.0_dp;  ql = 0.0_dp
         end if
         ! one step may not spend more than the budget of a whole block
         ratio = max(q / cap, qd, ql)
         if (ratio <= 1.0_dp) exit
         ! reject: smaller steps (the local error scales as h^3)
         self%steps_rejected = self%steps_rejected + 1
         if (level >= self%n_levels - 1) then
            call controlled_failure(self, t0, h, ratio, worst, ok, err)
            return
         end if
         level = min(self%n_levels - 1, level + levels_down(ratio, self%order + 1))
      end do
      ! accept
      self%t_comp = comp
      call swap_check_emit(self, t0, h, event, obs, err)
      if (allocated(err)) return
      call next_level(self, level, h, t1, q, qd, ql, event)
   end subroutine controlled_step

   !> After an accepted step [t1 - h, t1] (its local error q, interpolants' check qd and wear
   !> watch ql against their shares; `event`: it ends at a located event): the error history
   !> for the next step and the next step's level.
   subroutine next_level(self, level, h, t1, q, qd, ql, event)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(inout) :: level                       !! the step's level, then the next's
      real(dp), intent(in) :: h, t1, q, qd, ql              !! the step and its ratios
      logical, intent(in) :: event                          !! it ends at an event
      real(dp) :: rho
      integer :: dl, level_d, level_l
      ! a'' of the next step from this one's fda, unless the acceleration jumps here
      self%fda_prev = self%fda
      self%h_prev = merge(0.0_dp, h, event)
      self%block_sum = self%block_sum + q
      ! the largest steps whose interpolants, and the wear watch's local part, keep within
      ! their share (aiming at half of it; the cubic's error scales as h^4, a local error as
      ! h^(order + 1))
      level_d = share_level(self, level, qd, 4)
      level_l = share_level(self, level, ql, self%order + 1)
      if (self%caps%linear_exact .and. .not. event) then
         ! the linear part exact (free flight without error): the next step from this one's
         ! error per unit time against the budget's (aiming at half of it; the rate scales as
         ! h^order), at once, not only at a block's end
         rho = q / h * self%period / (budget_scale * self%tolerance)
         dl = max(-2, nint(log(max(rho, 1.0e-30_dp) / 0.5_dp) / log(2.0_dp**(0.5_dp &
                                                                      * self%order))))
         level = min(self%n_levels - 1, max(0, level + dl))
      end if
      if (t1 - self%block_start >= block_fraction * self%period * (1.0_dp - 1.0e-9_dp)) then
         ! the step size of the next block: the local errors of a block add up as h^2
         rho = self%block_sum / (budget_scale * self%tolerance * (t1 - self%block_start) &
                                 / self%period)
         if (rho > 1.0_dp) then
            level = min(self%n_levels - 1, level + ceiling(log(rho) / log(2.0_dp**(0.5_dp &
                                                           * self%order))))
         else if (rho < 0.3_dp) then
            level = max(0, level - min(2, floor(log(0.6_dp / rho) / log(2.0_dp**(0.5_dp &
                                                                   * self%order)))))
         end if
         self%block_start = t1;  self%block_sum = 0.0_dp
      end if
      if (.not. event) level = max(level, level_d, level_l)
   end subroutine next_level

   !> Levels (steps h_max 2^(-L/2)) to go down after a rejected step whose estimate, scaling
   !> as h^power, is `ratio` of its share: at least one (one when there is no estimate).
   pure integer function levels_down(ratio, power) result(dl)
      real(dp), intent(in) :: ratio                      !! estimate over its share (> 1)
      integer, intent(in) :: power                       !! the estimate's power of h
      dl = 1
      if (ratio < huge(1.0_dp)) dl = max(1, ceiling(log(ratio) / log(2.0_dp**(0.5_dp * power))))
   end function levels_down

   !> The level (step h_max 2^(-L/2)) whose estimate, `ratio` of its share at `level` and
   !> scaling as h^power, is half its share (0 when there is no estimate).
   pure integer function share_level(self, level, ratio, power) result(lv)
      class(stepping_integrator_t), intent(in) :: self   !! integrator (its ladder)
      integer, intent(in) :: level, power                !! the step's level, the power
      real(dp), intent(in) :: ratio                      !! its estimate over its share
      lv = 0
      if (ratio <= 0.0_dp) return
      lv = min(self%n_levels - 1, max(0, level + nint(log(ratio / 0.5_dp) &
                                                      / log(2.0_dp**(0.5_dp * power)))))
   end function share_level

   !> The local error of a step relative to the watched outputs' ranges: the largest of
   !> |l' e_u| / max(range, floor) over the root strain and the tip and contact displacements,
   !> and |l' e_v| / max(range, floor) over the root strain rate and those velocities, with
   !> e_u = coef(1) h^2 fda, e_v = coef(2) h fda + coef(3) h^3 a'' (a'' from this and the
   !> previous step's fda; or the method's own e_v). Returns the output (1-based over the
   !> displacement outputs, then the rates) of the largest.
   real(dp) module function error_ratio(self, h, coef, worst) result(ratio)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      real(dp), intent(in) :: h                          !! step [s]
      real(dp), intent(in) :: coef(3)                    !! the method's error coefficients
      integer, intent(out) :: worst                      !! output of the largest ratio
      self%eu = coef(1) * h**2 * self%fda
      if (coef(2) >= 0.0_dp) then
         self%ev = coef(2) * h * self%fda
         if (self%h_prev > 0.0_dp) self%ev = self%ev + coef(3) * h**3 * 2.0_dp &
            * (self%fda / h - self%fda_prev / self%h_prev) / (h + self%h_prev)
      end if
      ratio = self%output_ratio(worst)
   end function error_ratio

   !> max over the watched outputs of |l' e| / max(range, floor) for the errors held in
   !> self%eu (displacement outputs) and self%ev (rates); `worst` as in error_ratio.
   !> `events_only`: the outputs that event location reads only (the contact dofs and the wear
   !> watch; not the root strain, nor a tip that is not a contact dof).
   real(dp) module function output_ratio(self, worst, events_only) result(ratio)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(out) :: worst                      !! output of the largest ratio
      logical, intent(in), optional :: events_only       !! the contact dofs' outputs only
      real(dp) :: es, r, wl
      integer :: i, q, no, wr
      logical :: ev_only
      ev_only = .false.
      if (present(events_only)) ev_only = events_only
      no = 1 + size(self%out_dof)
      ratio = 0.0_dp;  worst = 1
      do i = 1, 2 * no
         if (i == no + 1 .and. .not. self%watch_rate) cycle
         if (ev_only) then
            if (i == 1 .or. i == no + 1) cycle
            if (.not. any(self%model%slot_dof == self%out_dof(mod(i - 2, no) + 1))) cycle
         end if
         if (i == 1 .or. i == no + 1) then
            es = 0.0_dp
            do q = 1, size(self%si)
               if (i == 1) es = es + self%sw(q) * self%eu(self%si(q))
               if (i > 1) es = es + self%sw(q) * self%ev(self%si(q))
            end do
         else if (i <= no) then
            es = self%eu(self%out_dof(i - 1))
         else
            es = self%ev(self%out_dof(i - no - 1))
         end if
         r = abs(es) / max(self%out_hi(i) - self%out_lo(i), self%out_floor(i), tiny(1.0_dp))
         if (r > ratio) then
            ratio = r;  worst = i
         end if
      end do
      self%wear_local = 0.0_dp;  self%wear_local_ring = 0
      if (self%model%n_rings > 0) then
         r = wear_ratio(self, q, wl, wr)
         self%wear_local = wl;  self%wear_local_ring = wr
         if (r > ratio) then
            ratio = r;  worst = 2 * no + q
         end if
      end if
   end function output_ratio

   !> The wear work watched (docs/methods.md, Wear): for each ring in contact at the end of the
   !> step and sliding over it (in slip; any contact without friction), the local error of the
   !> tangential velocity v_t = t.x' relative to its range (the sliding distance integrates
   !> |v_t|) and that of the work integrand f_n v_t relative to (the largest f_n) x (the range
   !> of v_t) (the normal work rate and friction work integrate it). Nothing in stick: it wears
   !> nothing. The integrand's error has two parts. f_n dv_t is summed with the other outputs'
   !> errors: an error of the sliding motion stays in the trajectory. v_t df_n, with df_n the
   !> law's change over the error of the penetration, is returned apart (`local`) and held per
   !> step, as the interpolant's error is: the penetration under a stiff contact is the
   !> contact mode's (2e6 N/m on the tube: 1.6 kHz, its damper's 5 %), whose error rings
   !> down in milliseconds and integrates to nothing over its cycles; an error of the force that
   !> lasts comes from the structure's motion, which the displacement outputs watch. (Summed,
   !> it bounded half of the tube deck's steps under the exponential integrator.) Returns the
   !> largest summed ratio and its ring (0: none).
   real(dp) function wear_ratio(self, worst, local, local_ring) result(ratio)
      class(stepping_integrator_t), intent(in) :: self   !! integrator (step in ix(0), ix(1))
      integer, intent(out) :: worst                      !! ring of the largest ratio
      real(dp), intent(out) :: local                     !! largest v_t df_n / (F_max V_t)
      integer, intent(out) :: local_ring                 !! its ring (0: none)
      real(dp) :: x(2), xd(2), d, n(2), t(2), gt, vt, dn, dvt, dd, dfn, fn, vs, fs, r, h
      integer :: rg
      ratio = 0.0_dp;  worst = 0;  local = 0.0_dp;  local_ring = 0
      associate (m => self%model, s0 => self%sub(self%ix(0)), s1 => self%sub(self%ix(1)))
         do rg = 1, m%n_rings
            fn = s1%fn(rg)
            if (fn <= 0.0_dp) cycle
            if (m%r_mu(rg) > 0.0_dp .and. s0%mode(rg) /= ring_slip) cycle
            x = ring_xy(m, rg, s1%u);  xd = ring_xy(m, rg, s1%v)
            call ring_geometry(m, rg, x, d, n, t, gt=gt)
            vt = dot_product(t, xd);  dn = dot_product(n, xd)
            dvt = dot_product(t, ring_xy(m, rg, self%ev))
            dd = dot_product(n, ring_xy(m, rg, self%eu))
            ! below the round-off of the position (and of the velocity, which an implicit
            ! step gets from the position as 2 x / h): no error to control
            h = max(s1%t - s0%t, tiny(1.0_dp))
            if (abs(dd) <= 16.0_dp * epsilon(1.0_dp) * maxval(abs(x))) dd = 0.0_dp
            if (abs(dvt) <= 16.0_dp * epsilon(1.0_dp) * (maxval(abs(xd)) + 2.0_dp &
                * maxval(abs(x)) / h)) dvt = 0.0_dp
            associate (law => m%laws(m%r_law(rg))%law)
               ! both at this d: the round-off of d (rho - g) cancels
               dfn = law%force(m%r_k(rg), m%r_c(rg), m%r_p(rg), d + dd, dn) &
                     - law%force(m%r_k(rg), m%r_c(rg), m%r_p(rg), d, dn)
            end associate
            vs = max(self%vt_hi(rg) - self%vt_lo(rg), self%vt_floor(rg), tiny(1.0_dp))
            fs = max(self%fn_max(rg), fn)
            r = max(abs(dvt) / vs, abs(fn * dvt) / (fs * vs))
            if (r > ratio) then
               ratio = r;  worst = rg
            end if
            r = abs(vt * dfn) / (fs * vs)
            if (r > local) then
               local = r;  local_ring = rg
            end if
         end do
      end associate
   end function wear_ratio

   !> The interpolant's own error of the step just taken by `st` (its dense_error; 0 when it
   !> has none), relative to the watched outputs' ranges and the stops' forces, over
   !> the cap of one step's propagated error (a block's budget). It is held per step, since it
   !> is not carried into the next step (which starts from the method's end state). Held only
   !> to a period's budget (5 x more) it let the full tube at 1e-4 locate 5 releases too early
   !> (5 extra impacts of 120 at a sliding baffle), the reduced one 2 at 1e-3. The state's
   !> error arrays eu, ev are overwritten. `worst`: the output of the largest (output_ratio).
   real(dp) function dense_ratio(self, st, worst) result(qd)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      class(stepper_t), intent(inout) :: st                 !! the stepper that took the step
      integer, intent(out) :: worst                         !! output of the largest ratio
      logical :: has
      integer :: w5
      real(dp) :: q5
      qd = 0.0_dp;  worst = 0
      call st%dense_error(self%eu_d, self%ev_d, has, self%eu_q, self%ev_q)
      if (.not. has) return
      ! the cubic, on what event location reads; nothing to read where no contact can be
      ! reached within the step (rings_clear)
      self%quintic_events = self%model%n_contacts == 0
      if (.not. rings_clear(self)) then
         self%eu = self%eu_d;  self%ev = self%ev_d
         ! (a ring in contact at the start has its events on the quintic: not on the cubic)
         if (self%quintic_events) call forget_closed_rings(self)
         qd = max(self%output_ratio(worst, events_only=.true.), self%wear_local, &
                  normal_force_ratio(self))
      end if
      ! the quintic, on every watched output (and the normal forces, whose peaks are located
      ! on it)
      self%eu = self%eu_q;  self%ev = self%ev_q
      q5 = max(self%output_ratio(w5), self%wear_local, normal_force_ratio(self))
      if (q5 > qd) worst = w5
      qd = max(qd, q5) / (block_fraction * budget_scale * self%tolerance)
   end function dense_ratio

   !> dense_ratio of the stepper that took the step (`on_scratch`: the scratch stepper, else
   !> the level's).
   real(dp) function dense_of(self, on_scratch, level, worst) result(qd)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      logical, intent(in) :: on_scratch                     !! the scratch stepper took it
      integer, intent(in) :: level                          !! else the level's
      integer, intent(out) :: worst                         !! output of the largest ratio
      if (on_scratch) then
         qd = dense_ratio(self, self%scratch, worst)
      else
         qd = dense_ratio(self, self%ops(level), worst)
      end if
   end function dense_of

   !> The interpolant's error of the normal force of each flat stop and ring in contact at
   !> either end of the step: the law's change over the errors held in eu, ev at its dofs
   !> (along the contact normal of a ring), relative to the ring's largest normal force so
   !> far (a flat stop: see below). The peak force is located on the interpolant, and the
   !> penetration is far below the range of the dofs that output_ratio measures it against
   !> (0.5 um under 1 N on a 2e6 N/m baffle against 100 um): with outputs alone the multispan
   !> tube's peak force at 7 Hz / 0.05 mm came 1.8 % low at tolerance 1e-4 and 1.4 % at 1e-6.
   real(dp) function normal_force_ratio(self) result(ratio)
      class(stepping_integrator_t), intent(in) :: self   !! integrator (step in ix(0), ix(1))
      real(dp) :: x(2), xd(2), d, n(2), t(2), gt, dn, dd, ddn, dfn, fs
      integer :: rg, c, i, q
      ratio = 0.0_dp
      associate (m => self%model, s0 => self%sub(self%ix(0)), s1 => self%sub(self%ix(1)))
         ! flat stops in contact at either end, against the larger end force (a trial step
         ! that enters a stop has its penetration's force at its end), and no less than the
         ! force at 1e-3 of the stop dof's quasi-static floor (a stop touched at rest carries
         ! no force to measure against): the onset located on the interpolant is within the
         ! tolerance of the force
         do c = 1, m%n_contacts
            if (max(abs(s0%f(c)), abs(s1%f(c))) <= 0.0_dp) cycle
            i = m%c_dof(c)
            q = findloc(self%out_dof, i, dim=1)
            fs = max(abs(s0%f(c)), abs(s1%f(c)), tiny(1.0_dp))
            if (q > 0) fs = max(fs, abs(contact_force(m, c, 1.0e-3_dp * self%out_floor(1 + q), &
                                                      0.0_dp)))
            d = max(m%c_sign(c) * s1%u(i) - m%c_gap(c), 0.0_dp)
            dn = m%c_sign(c) * s1%v(i)
            dfn = contact_force(m, c, d + abs(self%eu(i)), dn + m%c_sign(c) * self%ev(i)) &
                  - contact_force(m, c, d, dn)
            ratio = max(ratio, abs(dfn) / fs)
         end do
         do rg = 1, m%n_rings
            if (max(s0%fn(rg), s1%fn(rg)) <= 0.0_dp) cycle
            x = ring_xy(m, rg, s1%u);  xd = ring_xy(m, rg, s1%v)
            call ring_geometry(m, rg, x, d, n, t, gt=gt)
            dn = dot_product(n, xd)
            dd = dot_product(n, ring_xy(m, rg, self%eu))
            ddn = dot_product(n, ring_xy(m, rg, self%ev))
            associate (law => m%laws(m%r_law(rg))%law)
               dfn = law%force(m%r_k(rg), m%r_c(rg), m%r_p(rg), max(d, 0.0_dp) + abs(dd), &
                               dn + ddn) &
                     - law%force(m%r_k(rg), m%r_c(rg), m%r_p(rg), max(d, 0.0_dp), dn)
            end associate
            fs = max(self%fn_max(rg), s0%fn(rg), s1%fn(rg), tiny(1.0_dp))
            ratio = max(ratio, abs(dfn) / fs)
         end do
      end associate
   end function normal_force_ratio

   !> Floors of the wear watch: the velocity floor of each ring's two dofs, no larger than the
   !> base's velocity amplitude when the base moves (a support that holds a flexible structure
   !> moves it with the base, far less than its open quasi-static response), or with random
   !> forcing alone than the velocity of the harmonic response at Omega to the load's RMS (a
   !> nearly free mass has a static response of no scale); zero floors (no forcing) are set
   !> from the initial state (start_floors); the ranges start empty and are kept over the run.
   subroutine wear_floors(self, model, n_out, v_turb)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model
      integer, intent(in) :: n_out                          !! 1 + size(out_dof)
      real(dp), intent(in) :: v_turb                        !! turbulence's velocity [m/s]
      integer :: rg, j, q
      if (allocated(self%vt_lo)) deallocate(self%vt_lo, self%vt_hi, self%vt_floor, self%fn_max)
      allocate(self%vt_lo(model%n_rings), source=huge(1.0_dp))
      allocate(self%vt_hi(model%n_rings), source=-huge(1.0_dp))
      allocate(self%vt_floor(model%n_rings), self%fn_max(model%n_rings), source=0.0_dp)
      do rg = 1, model%n_rings
         do j = 1, 2
            q = findloc(self%out_dof, model%r_dof(j, rg), dim=1)
            if (q > 0) self%vt_floor(rg) = max(self%vt_floor(rg), self%out_floor(n_out + 1 + q))
         end do
         if (model%half_amplitude > 0.0_dp) then
            self%vt_floor(rg) = min(self%vt_floor(rg), model%half_amplitude * model%omega)
         else if (v_turb < huge(1.0_dp)) then
            self%vt_floor(rg) = min(self%vt_floor(rg), v_turb)
         end if
      end do
   end subroutine wear_floors

   !> Error ratio of the step held in sub(ix(1)) by Richardson extrapolation: the same
   !> interval in two half steps (local error 1/4 of the whole step's for a method whose local
   !> error is O(h^3)), e = (4/3) (y_h - y_h/2) for u and v, measured on the watched outputs
   !> as error_ratio does. For the steps that begin a run or follow a contact event, where the
   !> method's own estimate lacks a''; they are a few per forcing period.
   module subroutine richardson(self, level, h, event, ratio, worst, err)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      integer, intent(in) :: level                    !! the step's ladder level
      real(dp), intent(in) :: h                       !! the step [s]
      logical, intent(in) :: event                    !! it ends at a located event
      real(dp), intent(out) :: ratio                  !! error / tolerance share of the step
      integer, intent(out) :: worst                   !! output of the largest ratio
      type(error_t), allocatable, intent(out) :: err  !! factorisation failure
      logical :: ok
      real(dp) :: r
      integer :: hold
      ratio = huge(1.0_dp);  worst = 1
      hold = 0
      if (event .and. self%ev_onset) hold = self%ev_contact
      associate (s0 => self%sub(self%ix(0)), s1 => self%sub(self%ix(1)))
         if (.not. event .and. level + 2 < self%n_levels) then
            if (.not. self%ops(level + 2)%ready) then
               call self%ops(level + 2)%prepare(self%model, self%cfg, self%h_lev(level + 2), &
                                                err)
               if (allocated(err)) return
               self%factorizations = self%factorizations + 1
            end if
            call self%ops(level + 2)%step(self%model, s0, self%rich(1), ok, r, 0)
            if (ok) call self%ops(level + 2)%step(self%model, self%rich(1), self%rich(2), ok, &
                                                  r, 0)
         else
            call self%scratch_half%prepare(self%model, self%cfg, 0.5_dp * h, err)
            if (allocated(err)) return
            self%factorizations = self%factorizations + 1
            call self%scratch_half%step(self%model, s0, self%rich(1), ok, r, hold)
            if (ok) call self%scratch_half%step(self%model, self%rich(1), self%rich(2), ok, &
                                                r, hold)
         end if
         if (.not. ok) return
         self%eu = (4.0_dp / 3.0_dp) * (s1%u - self%rich(2)%u)
         self%ev = (4.0_dp / 3.0_dp) * (s1%v - self%rich(2)%v)
      end associate
      ratio = self%output_ratio(worst)
   end subroutine richardson

   !> Running ranges of the watched outputs (start: from this state).
   module subroutine track_outputs(self, s, first)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(state_t), intent(in) :: s                        !! an accepted state
      logical, intent(in) :: first                          !! reset the ranges
      real(dp) :: y(2 * (1 + size(self%out_dof)))
      integer :: q, no
      no = 1 + size(self%out_dof)
      y(1) = 0.0_dp;  y(no + 1) = 0.0_dp
      do q = 1, size(self%si)
         y(1) = y(1) + self%sw(q) * s%u(self%si(q))
         y(no + 1) = y(no + 1) + self%sw(q) * s%v(self%si(q))
      end do
      y(2:no) = s%u(self%out_dof);  y(no + 2:) = s%v(self%out_dof)
      if (first) then
         self%out_lo = y;  self%out_hi = y
      else
         self%out_lo = min(self%out_lo, y);  self%out_hi = max(self%out_hi, y)
      end if
      if (allocated(self%vt_lo)) call track_wear(self, s)
   end subroutine track_outputs

   !> The wear watch's ranges at an accepted state: the tangential velocity of each ring in
   !> contact and the largest normal force.
   subroutine track_wear(self, s)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(state_t), intent(in) :: s                        !! an accepted state
      real(dp) :: d, n(2), t(2), gt, vt
      integer :: rg
      associate (m => self%model)
         do rg = 1, m%n_rings
            if (s%fn(rg) <= 0.0_dp) cycle
            call ring_geometry(m, rg, ring_xy(m, rg, s%u), d, n, t, gt=gt)
            vt = dot_product(t, ring_xy(m, rg, s%v))
            self%vt_lo(rg) = min(self%vt_lo(rg), vt);  self%vt_hi(rg) = max(self%vt_hi(rg), vt)
            self%fn_max(rg) = max(self%fn_max(rg), s%fn(rg))
         end do
      end associate
   end subroutine track_wear

   !> Floors of the watched outputs of a model with two planes or extra loads: the largest
   !> response to any one load vector of the open structure: the quasi-static K^-1 L for the w
   !> and v base motions (as for a planar model, whose floors a planar deck run with two planes
   !> keeps), and for the sin and cos parts of the point forces the smaller of that and the
   !> harmonic (K - Omega^2 M + i Omega C)^-1 L (a force above a resonance moves the structure
   !> far less than its static response); with two planes the same floor for an
   !> output and its mirror in the other plane (an orbit can turn from one plane into the other;
   !> a plane at rest must not get a zero floor).
   subroutine tube_floors(self, model, kf, n_out, v_turb)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model
      real(dp), intent(in) :: kf(:, :)                      !! Cholesky factor of K
      integer, intent(in) :: n_out                          !! 1 + size(out_dof)
      real(dp), intent(inout) :: v_turb                     !! turbulence's ring velocity [m/s]
      real(dp), allocatable :: loads(:, :), zs(:, :), zd(:, :), a(:, :)
      integer, allocatable :: ipiv(:)
      real(dp) :: fl(n_out), ys, yd
      integer :: j, info, nh, q, i, nl, n, im
      logical :: point_force(4), harmonic
      n = model%n
      nl = 1
      point_force = [.false., .false., .true., .true.]
      allocate(loads(n, 4), source=0.0_dp)
      loads(:, 1) = model%half_amplitude * model%omega**2 * model%q
      if (allocated(model%q_v)) then
         nl = nl + 1;  loads(:, nl) = model%half_amplitude * model%omega**2 * model%q_v
      end if
      if (allocated(model%p_sin)) then
         loads(:, nl + 1) = model%p_sin;  loads(:, nl + 2) = model%p_cos
         point_force(nl + 1:nl + 2) = .true.
         nl = nl + 2
      end if
      point_force(1:nl - merge(2, 0, allocated(model%p_sin))) = .false.
      zs = loads(:, 1:nl)
      call dpotrs('U', n, nl, kf, n, zs, n, info)
      ! harmonic response: [K - W^2 M, -W C; W C, K - W^2 M] [x; y] = [L; 0], |z| = hypot
      info = 0
      if (n <= 1000 .and. any(point_force(1:nl))) then
         allocate(a(2 * n, 2 * n), ipiv(2 * n))
         a(1:n, 1:n) = model%sys%k - model%omega**2 * model%sys%m
         a(n + 1:, n + 1:) = a(1:n, 1:n)
         a(1:n, n + 1:) = -model%omega * model%c
         a(n + 1:, 1:n) = model%omega * model%c
         allocate(zd(2 * n, nl), source=0.0_dp)
         zd(1:n, :) = loads(:, 1:nl)
         call dgesv(2 * n, nl, a, 2 * n, ipiv, zd, 2 * n, info)
         if (info /= 0) zd = 0.0_dp
      end if
      nh = n / 2
      fl = 0.0_dp
      do j = 1, nl
         do q = 0, size(self%out_dof)
            do im = 0, min(1, model%sys%planes - 1)      ! the output, then its mirror
               harmonic = allocated(a) .and. info == 0 .and. point_force(j)
               yd = huge(1.0_dp)
               if (q == 0) then
                  ys = abs(dot_product(self%sw, zs(self%si + im * nh, j)))
                  if (harmonic) yd = hypot(dot_product(self%sw, zd(self%si + im * nh, j)), &
                                           dot_product(self%sw, zd(n + self%si + im * nh, j)))
               else
                  i = self%out_dof(q)
                  ! the same dof in the other plane (the planes are numbered alike)
                  if (im == 1) i = merge(i + nh, i - nh, i <= nh)
                  ys = abs(zs(i, j))
                  if (harmonic) yd = hypot(zd(i, j), zd(n + i, j))
               end if
               fl(1 + q) = max(fl(1 + q), min(ys, yd))
            end do
         end do
      end do
      self%out_floor(1:n_out) = fl
      self%out_floor(n_out + 1:) = model%omega * fl
      if (.not. model%turbulence%active) return
      ! turbulence: the static response to the load's RMS, its rate at the record's cut-off
      zs = reshape(rms_load(model%turbulence, n), [n, 1])
      call dpotrs('U', n, 1, kf, n, zs, n, info)
      fl(1) = abs(dot_product(self%sw, zs(self%si, 1)))
      fl(2:n_out) = abs(zs(self%out_dof, 1))
      self%out_floor(1:n_out) = max(self%out_floor(1:n_out), fl)
      self%out_floor(n_out + 1:) = max(self%out_floor(n_out + 1:), &
                                       2.0_dp * pi * model%turbulence%cutoff_hz * fl)
      call mirror_zero_floors(self, model, n_out)
      if (model%n_rings > 0) call turbulence_ring_velocity(model, &
         rms_load(model%turbulence, n), v_turb)
   end subroutine tube_floors

   !> An output that the load leaves at rest (a plane the random load does not drive) takes
   !> the floor of its mirror in the other plane: contacts couple the planes.
   subroutine mirror_zero_floors(self, model, n_out)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model
      integer, intent(in) :: n_out                          !! 1 + size(out_dof)
      integer :: q, i, nh, qm
      if (model%sys%planes < 2) return
      nh = model%n / 2
      do q = 1, size(self%out_dof)
         i = self%out_dof(q)
         qm = findloc(self%out_dof, merge(i + nh, i - nh, i <= nh), dim=1)
         if (qm == 0) cycle
         if (self%out_floor(1 + q) == 0.0_dp) self%out_floor(1 + q) = self%out_floor(1 + qm)
         if (self%out_floor(n_out + 1 + q) == 0.0_dp) &
            self%out_floor(n_out + 1 + q) = self%out_floor(n_out + 1 + qm)
      end do
   end subroutine mirror_zero_floors

   !> The velocity scale of the rings under the random load alone: the largest velocity
   !> amplitude of a ring dof in the harmonic response at Omega to the load's RMS, |(K -
   !> Omega^2 M + i Omega C)^-1 L| Omega (huge: not computed, above 1000 dofs).
   subroutine turbulence_ring_velocity(model, load, v_turb)
      type(model_t), intent(in) :: model      !! model
      real(dp), intent(in) :: load(:)         !! the load's RMS per dof
      real(dp), intent(inout) :: v_turb       !! velocity scale [m/s]
      real(dp), allocatable :: a(:, :), z(:, :)
      integer, allocatable :: ipiv(:)
      integer :: n, info, rg, j, i
      n = model%n
      if (n > 1000) return
      allocate(a(2 * n, 2 * n), ipiv(2 * n), z(2 * n, 1))
      a(1:n, 1:n) = model%sys%k - model%omega**2 * model%sys%m
      a(n + 1:, n + 1:) = a(1:n, 1:n)
      a(1:n, n + 1:) = -model%omega * model%c
      a(n + 1:, 1:n) = model%omega * model%c
      z = 0.0_dp;  z(1:n, 1) = load
      call dgesv(2 * n, 1, a, 2 * n, ipiv, z, 2 * n, info)
      if (info /= 0) return
      v_turb = 0.0_dp
      do rg = 1, model%n_rings
         do j = 1, 2
            i = model%r_dof(j, rg)
            v_turb = max(v_turb, model%omega * hypot(z(i, 1), z(n + i, 1)))
         end do
      end do
      if (v_turb == 0.0_dp) v_turb = huge(1.0_dp)
   end subroutine turbulence_ring_velocity

   !> Floors that no forcing gave (free vibration, self-excitation from an initial state) from
   !> the state the run starts from: a displacement output's the largest displacement of the
   !> watched dofs (or their largest velocity over Omega), a velocity's the largest velocity
   !> (or Omega times the displacement floor), the root strain's and its rate's alike, and a
   !> ring's sliding-velocity floor its dofs' velocity floor. Floors once set are kept.
   subroutine start_floors(self, s)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(state_t), intent(in) :: s                        !! the start
      real(dp) :: du, dv, su, sv, w
      integer :: no, rg, j, q
      no = 1 + size(self%out_dof)
      w = self%model%omega
      du = 0.0_dp;  dv = 0.0_dp
      if (no > 1) then
         du = maxval(abs(s%u(self%out_dof)));  dv = maxval(abs(s%v(self%out_dof)))
      end if
      su = abs(dot_product(self%sw, s%u(self%si)));  sv = abs(dot_product(self%sw, s%v(self%si)))
      if (du == 0.0_dp) du = dv / w
      if (dv == 0.0_dp) dv = w * du
      if (su == 0.0_dp) su = sv / w
      if (sv == 0.0_dp) sv = w * su
      if (self%out_floor(1) == 0.0_dp) self%out_floor(1) = su
      if (self%out_floor(no + 1) == 0.0_dp) self%out_floor(no + 1) = sv
      where (self%out_floor(2:no) == 0.0_dp) self%out_floor(2:no) = du
      where (self%out_floor(no + 2:) == 0.0_dp) self%out_floor(no + 2:) = dv
      if (.not. allocated(self%vt_floor)) return
      do rg = 1, self%model%n_rings
         if (self%vt_floor(rg) > 0.0_dp) cycle
         do j = 1, 2
            q = findloc(self%out_dof, self%model%r_dof(j, rg), dim=1)
            if (q > 0) self%vt_floor(rg) = max(self%vt_floor(rg), self%out_floor(no + 1 + q))
         end do
      end do
   end subroutine start_floors

   !> The end of a step, t0 + h, summed with Kahan's compensation so that millions of steps
   !> do not accumulate the rounding of the time (eps t per step: a phase error that bounded
   !> the accuracy near 1e-7); a step clipped to a target lands on it exactly.
   pure subroutine next_time(t0, h, comp0, clipped, t1, comp)
      real(dp), intent(in) :: t0, h       !! start [s], step [s]
      real(dp), intent(in) :: comp0       !! compensation carried so far [s]
      logical, intent(in) :: clipped      !! h = t_stop - t0: land on t_stop
      real(dp), intent(out) :: t1         !! end of the step [s]
      real(dp), intent(out) :: comp       !! compensation after it [s]
      real(dp) :: y
      if (clipped) then
         t1 = t0 + h;  comp = 0.0_dp
         return
      end if
      y = h - comp0
      t1 = t0 + y
      comp = (t1 - t0) - y
   end subroutine next_time

   !> Accept the step [t0, t0 + h] held in sub-state ix(1): divergence check, restart after an
   !> event where a damper makes the force jump, hand it to the observer, make it the start.
   subroutine swap_check_emit(self, t0, h, event, obs, err)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      real(dp), intent(in) :: t0, h                         !! the step [s]
      logical, intent(in) :: event                          !! it ends at a contact event
      class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
      type(error_t), allocatable, intent(out) :: err        !! divergence
      call self%check_divergence(t0, t0 + h, 1, err)
      if (allocated(err)) return
      if (self%model%n_rings > 0) then
         call self%ring_switches(1, event)
      else if (event) then
         self%events = self%events + 1
         if (self%jumps(self%ev_contact)) call self%restart_after_event(1)
      end if
      if (present(obs)) call self%emit_pieces(1, obs)
      call self%track_outputs(self%sub(self%ix(1)), .false.)
      self%steps_accepted = self%steps_accepted + 1
      self%dt_smallest = min(self%dt_smallest, h)
      self%dt_largest = max(self%dt_largest, h)
      associate (sl => self%sub(self%ix(1)), sp => self%sub(self%ix(0)))
         sl%f_prev = sp%f;  sl%dt_prev = h
      end associate
      self%ix([0, 1]) = self%ix([1, 0])
   end subroutine swap_check_emit

   !> The error of a step that fails at the smallest step size under error control.
   subroutine controlled_failure(self, t0, h, ratio, worst, ok, err)
      class(stepping_integrator_t), intent(in) :: self   !! integrator
      real(dp), intent(in) :: t0, h, ratio               !! the step and its error ratio
      integer, intent(in) :: worst                       !! output of the largest error
      logical, intent(in) :: ok                          !! false: the stepper failed
      type(error_t), allocatable, intent(out) :: err     !! the message
      character(len=:), allocatable :: what
      if (.not. ok) then
         what = 'the fixed point on the stop force does not converge'
      else if (worst > 2 * (1 + size(self%out_dof))) then
         what = 'the local error of the sliding or its work at stop ' // str(self%model%r_stop( &
                worst - 2 * (1 + size(self%out_dof)))) // ' is ' // str(ratio) // ' times the ' &
                // 'tolerance'
      else if (worst == 1) then
         what = 'the local error of the root strain is ' // str(ratio) // ' times the tolerance'
      else if (worst == 2 + size(self%out_dof)) then
         what = 'the local error of the root strain rate is ' // str(ratio) // ' times the ' &
                // 'tolerance'
      else
         ! outputs: the root strain, the dofs, then their rates in the same order
         what = 'the local error at ' // dof_label(self%model, self%out_dof(mod(worst - 2, &
                1 + size(self%out_dof)) + 1)) // ' is ' // str(ratio) // ' times the tolerance'
      end if
      call fatal_error(err, "gapbeam_stepping: method '" // self%method // "': at t = " &
         // str(t0) // ' s ' // what // ' with the smallest step dt = ' // str(h) // ' s; ' &
         // 'raise &solver tolerance (now ' // str(self%tolerance) // ') or max_halvings ' &
         // '(now ' // str(self%kmax) // ')')
   end subroutine controlled_failure
   !> Copy the state (arrays reused when sized).
   module pure subroutine copy_state(a, b)
      type(state_t), intent(in) :: a      !! source
      type(state_t), intent(inout) :: b   !! destination
      b%t = a%t
      b%u = a%u;  b%v = a%v;  b%a = a%a;  b%f = a%f
      if (allocated(a%f_prev)) then
         b%f_prev = a%f_prev
      else
         b%f_prev = a%f
      end if
      if (allocated(a%cu)) then
         b%cu = a%cu;  b%cv = a%cv
      else if (allocated(b%cu)) then
         deallocate(b%cu, b%cv)
      end if
      b%dt_prev = a%dt_prev;  b%level = a%level;  b%comfortable = a%comfortable
      if (allocated(a%mode)) then
         b%fn = a%fn;  b%ft = a%ft;  b%mode = a%mode;  b%sigma = a%sigma;  b%anchor = a%anchor
      end if
   end subroutine copy_state
end submodule gapbeam_stepping_control
