!> The stepping integrator: any one-step method (a stepper_t) with step-size control and
!> contact-event location.
!>
!> Time is counted in integer ticks of dt_max / 2^max_halvings, with dt_max = T /
!> steps_per_period (T the forcing period), so every step size the control uses is a power-of-
!> two fraction of dt_max, each has its stepper (factorisation) cached, and steps land exactly
!> on the forcing periods. A step is rejected and halved when the half-step residual (or the
!> method's embedded estimate) exceeds the tolerance, or the fixed point does not converge; the
!> step doubles after `grow_after` comfortable steps when the time is a multiple of the doubled
!> step. With `locate_events`, a step in which a contact opens or closes (the penetration of
!> the cubic Hermite interpolant of the contact dof changes sign, grazing included; with a
!> damper, the force k d + c d' reaching zero) is split at that instant, and when the force
!> jumps there (a damper) the next sub-step restarts from the right limit.
!>
!> Each accepted sub-step is handed to the observer as a `hermite_piece_t`: the end values and
!> the cubic Hermite interpolant of (u, v) in between.
module gapbeam_stepping
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t, has_tube_physics
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_capabilities, only: method_caps
   use gapbeam_contact_law, only: contact_force, contact_releases_early, contact_jumps
   use gapbeam_observer, only: piece_t, observer_t
   use gapbeam_integrator, only: integrator_t, stepper_t, equilibrium_acceleration, zero_counters, &
      make_stepper, dof_label, ring_load
   use gapbeam_ring_contact, only: ring_open, ring_stick, ring_indicators, ring_geometry, &
      update_ring_modes, ring_force, onset_regime
   use gapbeam_newmark, only: half_step_ratio, use_dense
   use gapbeam_lapack, only: dpotrf, dpotrs, dgesv
   implicit none
   private
   public :: stepping_integrator_t, hermite_piece_t, hermite_weights

   integer, parameter :: max_sub = 8   ! sub-steps of one step at most (event splits)
   ! error control: blocks of this fraction of a forcing period keep one step size; the local
   ! errors accepted in a forcing period add up to at most budget_scale * tolerance
   real(dp), parameter :: block_fraction = 0.125_dp
   real(dp), parameter :: budget_scale = 0.2_dp
   real(dp), parameter :: min_split = 1.0e-3_dp   ! no sub-step shorter than this fraction of a step

   !> One accepted sub-step: end values and the cubic Hermite interpolant in between.
   type, extends(piece_t) :: hermite_piece_t
      type(model_t), pointer :: model => null()            !! the integrator's model
      type(state_t), pointer :: sub(:) => null()           !! the integrator's sub-states
      integer :: ja = 0, jb = 0                            !! the states at ta and tb
   contains
      procedure :: sample => hermite_sample
      procedure :: state_at => hermite_state
   end type hermite_piece_t

   !> A one-step method with step control and event location.
   type, extends(integrator_t) :: stepping_integrator_t
      !> the method's stepper, unprepared (set by the registry before init; else init asks
      !> the registry for the settings' method)
      class(stepper_t), allocatable :: proto
      type(model_t) :: model                          !! the model (own copy)
      type(solver_settings_t) :: cfg                  !! settings
      class(stepper_t), allocatable :: ops(:)         !! one stepper per step level 0..kmax
      class(stepper_t), allocatable :: scratch        !! for the sub-steps of an event split
      class(stepper_t), allocatable :: scratch_half   !! half steps of a Richardson check
      type(state_t) :: rich(2)                        !! the two half steps' states
      type(state_t), allocatable :: sub(:)            !! sub-states of a step (storage)
      integer :: ix(0:max_sub) = 0                    !! sub-state k is sub(ix(k))
      type(hermite_piece_t) :: piece                  !! handed to the observer
      real(dp) :: period = 0.0_dp                     !! forcing period [s]
      real(dp) :: dt_max = 0.0_dp                     !! largest step [s]
      real(dp) :: tick_dt = 0.0_dp                    !! time unit [s]
      integer :: kmax = 0                             !! smallest step = dt_max / 2^kmax
      logical :: half_step = .false.                  !! half-step residual control
      logical :: embedded = .false.                   !! the method's embedded estimate
      logical :: dense = .true.                       !! dense products in the residual
      integer, allocatable :: si(:)                   !! dofs in the root strain
      real(dp), allocatable :: sw(:)                  !! their weights
      real(dp), allocatable :: work6(:, :)            !! half-step residual workspace
      real(dp) :: energy_ref = 0.0_dp                 !! divergence check: reference energy
      real(dp) :: t_begin = 0.0_dp                    !! start of the current advance [s]
      integer :: n_since = 0                          !! steps since the last energy check
      !> contact of the located event (n_contacts + r: ring r)
      integer :: ev_contact = 0
      logical :: ev_onset = .false.                   !! the event closes it (else opens it)
      logical :: ev_friction = .false.                !! a stick-slip switch of a ring
      ! error control (step_control = 'error')
      logical :: controlled = .false.                 !! local error against the tolerance
      real(dp) :: tolerance = 0.0_dp                  !! relative accuracy asked [-]
      real(dp) :: h_max = 0.0_dp                      !! largest step [s]
      integer :: n_levels = 0                         !! step sizes h_max 2^(-L/2), L = 0..
      real(dp), allocatable :: h_lev(:)               !! (0:n_levels-1) those sizes [s]
      real(dp) :: t_comp = 0.0_dp                     !! Kahan compensation of the time [s]
      integer, allocatable :: out_dof(:)              !! outputs watched: tip and contact dofs
      !> ranges and floors of the watched outputs: root strain, the out_dof displacements,
      !> then root strain rate and the out_dof velocities
      real(dp), allocatable :: out_lo(:), out_hi(:), out_floor(:)
      real(dp), allocatable :: fda(:), ev(:), eu(:)   !! local error data of a step (n)
      real(dp), allocatable :: fda_prev(:)            !! fda of the previous accepted step
      real(dp) :: h_prev = 0.0_dp                     !! its length (0: none usable) [s]
      integer :: order = 2                            !! order of the method
      real(dp) :: block_start = 0.0_dp                !! current block of the controller [s]
      real(dp) :: block_sum = 0.0_dp                  !! local errors accepted in it [-]
      !> the root strain rate is watched (not with ring contacts, see init_control)
      logical :: watch_rate = .true.
      !> per contact: its force can vanish while it penetrates (located where the force does)
      logical, allocatable :: early(:)
      logical, allocatable :: jumps(:)                !! per contact: its force jumps at onset
   contains
      procedure :: init => stepping_init
      procedure :: advance => stepping_advance
      procedure :: reset_counters => stepping_reset_counters
      procedure, private :: attempt_step, control_ratio, check_divergence, emit_pieces, &
         first_event, restart_after_event, one_step, advance_controlled, controlled_step, &
         error_ratio, output_ratio, richardson, track_outputs, init_control, ring_switches, &
         first_ring_event
   end type stepping_integrator_t

contains

   !> Build the steppers (prepared lazily, one per step level) and the workspaces.
   subroutine stepping_init(self, model, cfg, err)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model
      type(solver_settings_t), intent(in) :: cfg            !! settings
      type(error_t), allocatable, intent(out) :: err        !! no such stepper
      integer :: k, j
      if (.not. allocated(self%proto)) then
         call make_stepper(cfg%method, self%proto, err)
         if (allocated(err)) return
      end if
      if (len_trim(self%caps%name) == 0) self%caps = method_caps(cfg%method)
      self%method = trim(cfg%method)
      self%model = model
      self%cfg = cfg
      self%period = 2.0_dp * pi / model%omega
      self%dt_max = self%period / real(cfg%steps_per_period, dp)
      self%kmax = cfg%max_halvings
      self%tick_dt = self%dt_max / 2.0_dp**self%kmax
      self%half_step = cfg%step_control == 'half_step'
      self%embedded = cfg%step_control == 'embedded'
      self%dense = use_dense(model, cfg%linear_solver)
      self%controlled = cfg%step_control == 'error'
      self%early = [(contact_releases_early(model, j), j = 1, model%n_contacts)]
      self%jumps = [(contact_jumps(model, j), j = 1, model%n_contacts)]
      self%si = pack([(j, j = 1, model%n)], model%sys%strain_row /= 0.0_dp)
      self%sw = model%sys%strain_row(self%si)
      if (self%controlled) then
         call self%init_control(model, cfg, err)
         if (allocated(err)) return
         allocate(self%ops(0:self%n_levels - 1), source=self%proto)
      else
         allocate(self%ops(0:self%kmax), source=self%proto)
      end if
      allocate(self%scratch, source=self%proto)
      allocate(self%scratch_half, source=self%proto)
      allocate(self%sub(0:max_sub))
      self%ix = [(k, k = 0, max_sub)]
      do k = 0, max_sub
         allocate(self%sub(k)%u(model%n), self%sub(k)%v(model%n), self%sub(k)%a(model%n), &
                  self%sub(k)%f(model%n_contacts), self%sub(k)%f_prev(model%n_contacts), &
                  source=0.0_dp)
         allocate(self%sub(k)%fn(model%n_rings), self%sub(k)%ft(model%n_rings), &
                  self%sub(k)%sigma(model%n_rings), self%sub(k)%anchor(model%n_rings), &
                  source=0.0_dp)
         allocate(self%sub(k)%mode(model%n_rings), source=ring_open)
      end do
      do k = 1, 2
         allocate(self%rich(k)%u(model%n), self%rich(k)%v(model%n), self%rich(k)%a(model%n), &
                  self%rich(k)%f(model%n_contacts), self%rich(k)%f_prev(model%n_contacts), &
                  source=0.0_dp)
         allocate(self%rich(k)%fn(model%n_rings), self%rich(k)%ft(model%n_rings), &
                  self%rich(k)%sigma(model%n_rings), self%rich(k)%anchor(model%n_rings), &
                  source=0.0_dp)
         allocate(self%rich(k)%mode(model%n_rings), source=ring_open)
      end do
      allocate(self%work6(model%n, 6))
      associate (p => self%piece, nc => model%n_contacts, nr => model%n_rings)
         allocate(p%f_a(nc), p%f_b(nc), p%vabs_a(nc), p%vabs_b(nc), p%onset_time(nc), &
                  source=0.0_dp)
         allocate(p%onset(nc), source=.false.)
         allocate(p%fn_a(nr), p%fn_b(nr), p%r_sigma(nr), p%r_anchor(nr), p%r_onset_time(nr), &
                  source=0.0_dp)
         allocate(p%r_mode(nr), source=ring_open)
         allocate(p%r_onset(nr), source=.false.)
      end associate
   end subroutine stepping_init

   !> The counters to zero, the steppers' iteration counts included.
   subroutine stepping_reset_counters(self)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer :: k
      call zero_counters(self)
      if (allocated(self%ops)) then
         do k = lbound(self%ops, 1), ubound(self%ops, 1)
            self%ops(k)%iterations = 0
         end do
      end if
      if (allocated(self%scratch)) self%scratch%iterations = 0
   end subroutine stepping_reset_counters

   !> Carry `state` to t_target (see integrator_t%advance). The times must lie on the tick
   !> grid of the step control (any multiple of dt_max / 2^max_halvings, e.g. any forcing
   !> period).
   subroutine stepping_advance(self, state, t_target, obs, err)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      type(state_t), intent(inout) :: state                 !! state, at t_target on return
      real(dp), intent(in) :: t_target                      !! target time [s]
      class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
      type(error_t), allocatable, intent(out) :: err        !! numerical failure
      integer(int64) :: tick, end_tick, watch_tick, nt
      integer :: level, nsub, worst, comfortable
      real(dp) :: t0, t1, ratio, eratio
      logical :: ok

      if (self%controlled) then
         call self%advance_controlled(state, t_target, obs, err)
         return
      end if
      call fit_grid(self, max(abs(t_target), abs(state%t)))
      tick = nint(state%t / self%tick_dt, int64)
      end_tick = nint(t_target / self%tick_dt, int64)
      if (abs(real(tick, dp) * self%tick_dt - state%t) > 0.01_dp * self%tick_dt .or. &
          abs(real(end_tick, dp) * self%tick_dt - t_target) > 0.01_dp * self%tick_dt) then
         call fatal_error(err, 'gapbeam_stepping:advance: the times ' // str(state%t) &
            // ' s and ' // str(t_target) // ' s are not on the step grid of T / (' &
            // str(self%cfg%steps_per_period) // ' x 2^' // str(self%kmax) // ')')
         return
      end if
      watch_tick = -1
      if (present(obs)) watch_tick = nint(obs%t_watch / self%tick_dt, int64)
      call copy_state(state, self%sub(self%ix(0)))
      if (self%sub(self%ix(0))%dt_prev == 0.0_dp) self%sub(self%ix(0))%dt_prev = self%dt_max
      level = min(state%level, self%kmax);  comfortable = state%comfortable
      self%piece%model => self%model
      self%piece%sub => self%sub
      self%t_begin = state%t;  self%n_since = 0
      self%energy_ref = 0.5_dp * dot_product(state%u, matmul(self%model%sys%k, state%u)) &
                        + 0.5_dp * dot_product(state%v, matmul(self%model%sys%m, state%v))
      do while (tick < end_tick)
         ! never step over the target or the observer's watch instant
         do while (level < self%kmax .and. (tick + 2_int64**(self%kmax - level) > end_tick .or. &
                   (watch_tick > tick .and. watch_tick < tick + 2_int64**(self%kmax - level))))
            level = level + 1
         end do
         nt = 2_int64**(self%kmax - level)
         t0 = real(tick, dp) * self%tick_dt
         t1 = real(tick + nt, dp) * self%tick_dt
         if (.not. self%ops(level)%ready) then
            call self%ops(level)%prepare(self%model, self%cfg, t1 - t0, err)
            if (allocated(err)) return
            self%factorizations = self%factorizations + 1
         end if
         call self%attempt_step(level, t0, t1, nsub, ok, eratio, err)
         if (allocated(err)) return
         call self%control_ratio(ok, nsub, eratio, ratio, worst)
         if (.not. ok .or. ratio > 1.0_dp) then
            self%steps_rejected = self%steps_rejected + 1
            comfortable = 0
            if (level >= self%kmax) then
               call step_failure(self, ok, t0, t1, ratio, worst, err)
               return
            end if
            level = level + 1
            cycle
         end if
         call self%check_divergence(t0, t1, nsub, err)
         if (allocated(err)) return
         if (present(obs)) call self%emit_pieces(nsub, obs)
         self%steps_accepted = self%steps_accepted + nsub
         self%dt_smallest = min(self%dt_smallest, t1 - t0)
         self%dt_largest = max(self%dt_largest, t1 - t0)
         ! the next step starts from the end of this one (its memory: the last sub-step); the
         ! storage of the two is swapped, not copied
         associate (sl => self%sub(self%ix(nsub)), sp => self%sub(self%ix(nsub - 1)))
            sl%f_prev = sp%f;  sl%dt_prev = sl%t - sp%t
         end associate
         self%ix([0, nsub]) = self%ix([nsub, 0])
         tick = tick + nt
         ! grow
         if (.not. (self%half_step .or. self%embedded) .or. ratio < self%cfg%grow_ratio) then
            comfortable = comfortable + 1
         else
            comfortable = 0
         end if
         if (level > 0 .and. comfortable >= self%cfg%grow_after) then
            if (mod(tick, 2 * nt) == 0) then
               level = level - 1;  comfortable = 0
            end if
         end if
      end do
      call copy_state(self%sub(self%ix(0)), state)
      state%t = t_target
      state%level = level;  state%comfortable = comfortable
      self%fp_iterations = self%scratch%iterations + sum([(self%ops(level)%iterations, &
                                      level = lbound(self%ops, 1), ubound(self%ops, 1))])
   end subroutine stepping_advance

   !> The time grid of an advance to t_end: ticks of dt_max / 2^kmax with kmax = max_halvings,
   !> lowered (never below 0) until t_end is below 2^45 ticks, so that every grid time is
   !> resolved to 1/128 of a tick in double precision: a tick finer than the resolution of the
   !> time itself cannot be stepped on (steps of zero length). Only extreme settings are
   !> affected: the default T/256 with 20 halvings keeps its grid for 1.3e5 forcing periods;
   !> T/1e8 over 1300 periods keeps 8 halvings (steps down to 4e-12 of a period).
   subroutine fit_grid(self, t_end)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      real(dp), intent(in) :: t_end                         !! latest time of the advance [s]
      integer :: k
      k = self%cfg%max_halvings
      do while (k > 0 .and. t_end / (self%dt_max / 2.0_dp**k) >= 2.0_dp**45)
         k = k - 1
      end do
      self%kmax = k
      self%tick_dt = self%dt_max / 2.0_dp**k
   end subroutine fit_grid

   !> ' (lowered to fit the time grid)' when fit_grid lowered max_halvings, else ''.
   function lowered_text(self) result(t)
      class(stepping_integrator_t), intent(in) :: self   !! integrator
      character(len=:), allocatable :: t
      t = ''
      if (self%kmax < self%cfg%max_halvings) t = ' (lowered from ' &
         // str(self%cfg%max_halvings) // ' to fit the time grid of the horizon)'
   end function lowered_text

   !> The error of a step that fails at the smallest step size.
   subroutine step_failure(self, ok, t0, t1, ratio, worst, err)
      class(stepping_integrator_t), intent(in) :: self   !! integrator
      logical, intent(in) :: ok                          !! false: the fixed point failed
      real(dp), intent(in) :: t0, t1, ratio              !! the step and its error ratio
      integer, intent(in) :: worst                       !! dof of the largest residual
      type(error_t), allocatable, intent(out) :: err     !! the message
      if (.not. ok) then
         call fatal_error(err, 'gapbeam_stepping:advance: the fixed point on the stop force ' &
            // 'does not converge in ' // str(self%cfg%fp_max_iterations) // ' iterations even ' &
            // 'at the smallest step dt = ' // str(t1 - t0) // ' s (t = ' // str(t0) // ' s, ' &
            // 'stop ' // dof_label(self%model, self%model%c_dof(1)) &
            // '); use stop_solution=''condensed'' or allow more max_halvings')
      else
         call fatal_error(err, 'gapbeam_stepping:advance: step below the minimum: at t = ' &
            // str(t0) // ' s the half-step residual at ' // dof_label(self%model, worst) &
            // ' is ' // str(ratio) // ' times the tolerance with the smallest step dt = ' &
            // str(t1 - t0) // ' s (steps_per_period = ' // str(self%cfg%steps_per_period) &
            // ', max_halvings = ' // str(self%kmax) // lowered_text(self) // ')')
      end if
   end subroutine step_failure

   !> Attempt the step [t0, t1] from sub(0), split at contact events: sub-states 1..nsub.
   subroutine attempt_step(self, level, t0, t1, nsub, ok, eratio, err)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: level                          !! step level (stepper ops(level))
      real(dp), intent(in) :: t0, t1                        !! the step [s]
      integer, intent(out) :: nsub                          !! sub-steps taken
      logical, intent(out) :: ok                            !! no stepper failed
      real(dp), intent(out) :: eratio                       !! largest embedded error ratio
      type(error_t), allocatable, intent(out) :: err        !! factorisation failure
      real(dp) :: t_cur, dt_r, theta
      self%sub(self%ix(0))%t = t0
      nsub = 0;  ok = .true.;  t_cur = t0;  eratio = 0.0_dp
      do
         dt_r = t1 - t_cur
         if (nsub == 0) then
            call self%one_step(self%ops(level), nsub, 0, ok, eratio)
         else
            call self%scratch%prepare(self%model, self%cfg, dt_r, err)
            if (allocated(err)) return
            self%factorizations = self%factorizations + 1
            call self%one_step(self%scratch, nsub, 0, ok, eratio)
         end if
         if (.not. ok) return
         if (self%cfg%locate_events .and. self%model%n_contacts > 0 .and. &
             nsub < max_sub - 1) then
            theta = self%first_event(nsub, dt_r)
            if (theta * dt_r > min_split * (t1 - t0) .and. &
                (1.0_dp - theta) * dt_r > min_split * (t1 - t0)) then
               call self%scratch%prepare(self%model, self%cfg, theta * dt_r, err)
               if (allocated(err)) return
               self%factorizations = self%factorizations + 1
               call self%one_step(self%scratch, nsub, merge(self%ev_contact, 0, self%ev_onset), &
                                  ok, eratio)
               if (.not. ok) return
               nsub = nsub + 1
               self%sub(self%ix(nsub))%t = t_cur + theta * dt_r
               t_cur = self%sub(self%ix(nsub))%t
               self%events = self%events + 1
               ! only a force that jumps (a damper) needs the right limit at a switch
               if (self%jumps(self%ev_contact)) call self%restart_after_event(nsub)
               cycle
            end if
         end if
         nsub = nsub + 1
         self%sub(self%ix(nsub))%t = t1
         return
      end do
   end subroutine attempt_step

   !> One step of a stepper from sub-state k into sub-state k+1.
   subroutine one_step(self, st, k, open_contact, ok, eratio)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      class(stepper_t), intent(inout) :: st                 !! prepared stepper
      integer, intent(in) :: k                              !! start sub-state
      integer, intent(in) :: open_contact                   !! contact held open (0: none)
      logical, intent(out) :: ok                            !! stepper succeeded
      real(dp), intent(inout) :: eratio                     !! largest embedded ratio so far
      real(dp) :: r
      if (k > 0) then
         associate (sk => self%sub(self%ix(k)), sp => self%sub(self%ix(k - 1)))
            sk%f_prev = sp%f;  sk%dt_prev = sk%t - sp%t
         end associate
      end if
      call st%step(self%model, self%sub(self%ix(k)), self%sub(self%ix(k + 1)), ok, r, &
                   open_contact)
      if (r > eratio) eratio = r
   end subroutine one_step

   !> The error ratio of the attempted step: the embedded estimate, or the largest half-step
   !> residual ratio over the sub-steps (with its dof), 0 for fixed steps.
   subroutine control_ratio(self, ok, nsub, eratio, ratio, worst)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      logical, intent(in) :: ok                             !! the steppers succeeded
      integer, intent(in) :: nsub                           !! sub-steps
      real(dp), intent(in) :: eratio                        !! embedded ratio
      real(dp), intent(out) :: ratio                        !! > 1: reject
      integer, intent(out) :: worst                         !! dof of the largest residual
      integer :: j, c
      real(dp) :: r
      ratio = 0.0_dp;  worst = 1
      if (self%embedded) ratio = eratio
      if (.not. (ok .and. self%half_step)) return
      do j = 1, nsub
         associate (s0 => self%sub(self%ix(j - 1)), s1 => self%sub(self%ix(j)))
            call half_step_ratio(self%model, self%dense, self%cfg%newmark_delta, &
               self%cfg%newmark_alpha, self%cfg%half_step_tolerance, self%cfg%residual_floor, &
               s0%t, s1%t - s0%t, s0%u, s0%v, s0%a, s1%a, r, c, self%work6)
         end associate
         if (r > ratio) then
            ratio = r;  worst = c
         end if
      end do
   end subroutine control_ratio

   !> Divergence of an accepted step: a non-finite state (a non-finite value reaches every dof
   !> within a step, dense or banded), or every 64 steps an energy beyond energy_bound times
   !> its largest value in the first forcing period of the advance.
   subroutine check_divergence(self, t0, t1, nsub, err)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      real(dp), intent(in) :: t0, t1                        !! the step [s]
      integer, intent(in) :: nsub                           !! its last sub-state
      type(error_t), allocatable, intent(out) :: err        !! divergence
      real(dp) :: fsum, energy
      integer :: j, n
      n = self%model%n
      associate (u => self%sub(self%ix(nsub))%u, v => self%sub(self%ix(nsub))%v)
         fsum = u(1) + v(1) + u(n) + v(n)
         if (.not. (abs(fsum) <= huge(1.0_dp))) then
            do j = 1, n
               if (.not. (abs(u(j)) <= huge(1.0_dp)) .or. .not. (abs(v(j)) <= huge(1.0_dp))) exit
            end do
            call fatal_error(err, 'gapbeam_stepping:advance: method ''' // self%method &
               // ''' diverged: the solution is not finite at t = ' // str(t1) // ' s, dt = ' &
               // str(t1 - t0) // ' s, ' // dof_label(self%model, min(j, n)))
            return
         end if
         self%n_since = self%n_since + 1
         ! every 64 steps; in the first forcing period at least 8 times (its largest energy
         ! is the reference)
         if (t1 - self%t_begin <= self%period) then
            if (self%n_since < max(1, min(64, self%cfg%steps_per_period / 8))) return
         else if (self%n_since < 64) then
            return
         end if
         self%n_since = 0
         energy = 0.5_dp * dot_product(u, matmul(self%model%sys%k, u)) &
                  + 0.5_dp * dot_product(v, matmul(self%model%sys%m, v))
      end associate
      if (t1 - self%t_begin <= self%period) then
         self%energy_ref = max(self%energy_ref, energy)
      else if (energy > self%cfg%energy_bound * self%energy_ref) then
         call fatal_error(err, 'gapbeam_stepping:advance: method ''' // self%method &
            // ''' diverged: the energy at t = ' // str(t1) // ' s is ' &
            // str(energy / self%energy_ref) // ' times its largest value in the first ' &
            // 'forcing period (bound energy_bound = ' // str(self%cfg%energy_bound) &
            // '), dt = ' // str(t1 - t0) // ' s; omega_max dt = ' &
            // str(self%model%omega_max * (t1 - t0)))
      end if
   end subroutine check_divergence

   !> Hand the accepted sub-steps 1..nsub to the observer.
   subroutine emit_pieces(self, nsub, obs)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      integer, intent(in) :: nsub                           !! sub-steps
      class(observer_t), intent(inout) :: obs               !! observer
      integer :: j, c, i, q, ja, jb
      real(dp) :: fa, fb, st, sv
      associate (p => self%piece, m => self%model)
         do j = 1, nsub
            ja = self%ix(j - 1);  jb = self%ix(j)
            p%ja = ja;  p%jb = jb
            associate (sa => self%sub(ja), sb => self%sub(jb))
               p%ta = sa%t;  p%tb = sb%t
               ! the watch instant exactly (ticks times tick_dt may differ in the last bit)
               if (abs(p%ta - obs%t_watch) <= 0.5_dp * self%tick_dt) p%ta = obs%t_watch
               if (abs(p%tb - obs%t_watch) <= 0.5_dp * self%tick_dt) p%tb = obs%t_watch
               do c = 1, m%n_contacts
                  i = m%c_dof(c)
                  p%f_a(c) = sa%f(c);  p%f_b(c) = sb%f(c)
                  p%vabs_a(c) = abs(sa%v(i));  p%vabs_b(c) = abs(sb%v(i))
                  p%onset(c) = p%f_b(c) > 0.0_dp .and. .not. p%f_a(c) > 0.0_dp
                  if (p%onset(c)) then
                     ! onset instant: linear interpolation of the penetration
                     fa = m%c_sign(c) * sa%u(i) - m%c_gap(c)
                     fb = m%c_sign(c) * sb%u(i) - m%c_gap(c)
                     if (fa <= 0.0_dp .and. fb > fa) then
                        p%onset_time(c) = p%ta + (p%tb - p%ta) * (-fa) / (fb - fa)
                     else
                        p%onset_time(c) = p%ta
                     end if
                  end if
               end do
               st = 0.0_dp;  sv = 0.0_dp
               do q = 1, size(self%si)
                  st = st + self%sw(q) * sb%u(self%si(q))
                  sv = sv + self%sw(q) * sb%v(self%si(q))
               end do
            end associate
            p%strain_b = st;  p%rate_b = sv
            if (m%n_rings > 0) call ring_piece(m, self%sub(ja), self%sub(jb), p)
            call obs%observe(p)
         end do
      end associate
   end subroutine emit_pieces

   !> The ring data of a piece from its end states: the regime (of the start), the normal
   !> forces at the ends, onsets (the normal force appears; the instant by linear interpolation
   !> of the penetration).
   subroutine ring_piece(model, sa, sb, p)
      type(model_t), intent(in) :: model          !! model
      type(state_t), intent(in) :: sa, sb         !! the piece's end states
      class(piece_t), intent(inout) :: p          !! the piece
      integer :: r
      real(dp) :: da, db, n(2), t(2), tau, gt
      p%r_mode = sa%mode;  p%r_sigma = sa%sigma;  p%r_anchor = sa%anchor
      p%fn_a = sa%fn;  p%fn_b = sb%fn
      do r = 1, model%n_rings
         p%r_onset(r) = sb%fn(r) > 0.0_dp .and. .not. sa%fn(r) > 0.0_dp
         if (.not. p%r_onset(r)) cycle
         call ring_geometry(model, r, sa%u(model%r_dof(:, r)), da, n, t, tau, gt)
         call ring_geometry(model, r, sb%u(model%r_dof(:, r)), db, n, t, tau, gt)
         if (da <= 0.0_dp .and. db > da) then
            p%r_onset_time(r) = p%ta + (p%tb - p%ta) * (-da) / (db - da)
         else
            p%r_onset_time(r) = p%ta
         end if
      end do
   end subroutine ring_piece

   !> First instant (fraction of the sub-step k -> k+1 of length h) where a contact opens or
   !> closes; 2 if none. Sets ev_contact and ev_onset.
   real(dp) function first_event(self, k, h) result(th)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-step start
      real(dp), intent(in) :: h                             !! its length [s]
      integer :: cc, m, it, i
      real(dp) :: lo, hi, mid, p0, b1, b2, b3, s, g
      logical :: closed0, damped
      integer, parameter :: n_sample = 8
      th = 2.0_dp
      associate (md => self%model, u0 => self%sub(self%ix(k))%u, &
                 v0 => self%sub(self%ix(k))%v, u1 => self%sub(self%ix(k + 1))%u, &
                 v1 => self%sub(self%ix(k + 1))%v)
         do cc = 1, md%n_contacts
            i = md%c_dof(cc);  s = md%c_sign(cc);  g = md%c_gap(cc)
            damped = self%early(cc)
            closed0 = contact_active(md, cc, 0.0_dp, h, u0(i), v0(i), u1(i), v1(i), damped)
            if (.not. damped) then
               ! Bernstein coefficients of the cubic bound it: no sign change, no event
               p0 = s * u0(i) - g
               b1 = p0 + s * h * v0(i) / 3.0_dp
               b3 = s * u1(i) - g
               b2 = b3 - s * h * v1(i) / 3.0_dp
               if (closed0) then
                  if (min(b1, b2, b3) > 0.0_dp) cycle
               else
                  if (max(b1, b2, b3) <= 0.0_dp) cycle
               end if
            end if
            do m = 1, n_sample
               hi = real(m, dp) / n_sample
               if (hi >= th) exit
               if (contact_active(md, cc, hi, h, u0(i), v0(i), u1(i), v1(i), damped) &
                   .neqv. closed0) then
                  lo = real(m - 1, dp) / n_sample
                  do it = 1, 60
                     mid = 0.5_dp * (lo + hi)
                     if (contact_active(md, cc, mid, h, u0(i), v0(i), u1(i), v1(i), damped) &
                         .neqv. closed0) then
                        hi = mid
                     else
                        lo = mid
                     end if
                  end do
                  if (hi < th) then
                     th = hi;  self%ev_contact = cc;  self%ev_onset = .not. closed0
                     self%ev_friction = .false.
                  end if
                  exit
               end if
            end do
         end do
      end associate
      if (self%model%n_rings > 0) call self%first_ring_event(k, h, th)
   end function first_event

   !> The first switch of a ring in the sub-step k -> k+1 of length h before fraction th:
   !> contact onset or release, or (in contact) the end of its friction regime (stick: |f_t|
   !> reaches mu f_n; slip: the tangential velocity reverses), on the cubic Hermite
   !> interpolant of the node's (w, v) in the regime of the sub-step's start. The indicators
   !> are sampled at 8 points and the first change is bisected; th, ev_contact (n_contacts +
   !> ring), ev_onset and ev_friction are set when one is found earlier.
   subroutine first_ring_event(self, k, h, th)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-step start
      real(dp), intent(in) :: h                             !! its length [s]
      real(dp), intent(inout) :: th                         !! earliest event so far [-]
      integer, parameter :: n_sample = 8
      integer :: r, m, it
      real(dp) :: lo, hi, mid
      logical :: act0, val0, act
      associate (md => self%model, s0 => self%sub(self%ix(k)), s1 => self%sub(self%ix(k + 1)))
         do r = 1, md%n_rings
            call ring_state_at(md, s0, s1, r, h, 0.0_dp, act0, val0)
            do m = 1, n_sample
               hi = real(m, dp) / n_sample
               if (hi >= th) exit
               if (ring_switched(md, s0, s1, r, h, hi, act0)) then
                  lo = real(m - 1, dp) / n_sample
                  do it = 1, 60
                     mid = 0.5_dp * (lo + hi)
                     if (ring_switched(md, s0, s1, r, h, mid, act0)) then
                        hi = mid
                     else
                        lo = mid
                     end if
                  end do
                  if (hi < th) then
                     th = hi;  self%ev_contact = md%n_contacts + r
                     call ring_state_at(md, s0, s1, r, h, hi, act, val0)
                     self%ev_onset = act .and. .not. act0
                     self%ev_friction = act .eqv. act0
                  end if
                  exit
               end if
            end do
         end do
      end associate
   end subroutine first_ring_event

   !> Indicators of ring r at fraction x of the sub-step s0 -> s1 of length h: the cubic
   !> Hermite interpolant of its node's (w, v) in the regime of s0.
   subroutine ring_state_at(model, s0, s1, r, h, x, active, valid)
      type(model_t), intent(in) :: model        !! model
      type(state_t), intent(in) :: s0, s1       !! the sub-step's ends
      integer, intent(in) :: r                  !! ring
      real(dp), intent(in) :: h, x              !! length [s], fraction [-]
      logical, intent(out) :: active, valid     !! in contact; regime holds
      real(dp) :: h00, h10, h01, h11, g00, g10, g01, g11, xx(2), xd(2), xdd(2)
      integer :: j, i
      call hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
      do j = 1, 2
         i = model%r_dof(j, r)
         xx(j) = h00 * s0%u(i) + h10 * h * s0%v(i) + h01 * s1%u(i) + h11 * h * s1%v(i)
         xd(j) = (g00 * s0%u(i) + g10 * h * s0%v(i) + g01 * s1%u(i) + g11 * h * s1%v(i)) / h
         ! second derivative of the cubic
         xdd(j) = ((12.0_dp * x - 6.0_dp) * (s0%u(i) - s1%u(i)) + h * ((6.0_dp * x - 4.0_dp) &
                  * s0%v(i) + (6.0_dp * x - 2.0_dp) * s1%v(i))) / h**2
      end do
      call ring_indicators(model, r, s0%mode(r), s0%sigma(r), s0%anchor(r), xx, xd, xdd, &
                           active, valid)
   end subroutine ring_state_at

   !> Has ring r switched by fraction x: its activity differs from `act0`, or its friction
   !> regime no longer holds?
   logical function ring_switched(model, s0, s1, r, h, x, act0) result(sw)
      type(model_t), intent(in) :: model        !! model
      type(state_t), intent(in) :: s0, s1       !! the sub-step's ends
      integer, intent(in) :: r                  !! ring
      real(dp), intent(in) :: h, x              !! length [s], fraction [-]
      logical, intent(in) :: act0               !! activity at the start
      logical :: a, v
      call ring_state_at(model, s0, s1, r, h, x, a, v)
      sw = (a .neqv. act0) .or. (a .and. .not. v)
   end function ring_switched

   !> After an accepted sub-step k: the regimes of the rings at its end (a located friction
   !> switch forced, a located onset anchored at the contact point), the force jump of a
   !> damper at a located onset or release (the next sub-step starts from the right limit),
   !> and the ring forces of the new regimes (continuous at friction switches).
   subroutine ring_switches(self, k, event)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-state at the end
      logical, intent(in) :: event                          !! the step ended at an event
      integer :: forced, r, c, onset_mode
      real(dp) :: d, n(2), t(2), tau, gt, onset_sigma
      real(dp), allocatable :: pr(:)
      logical :: jump
      associate (md => self%model, s => self%sub(self%ix(k)))
         forced = 0;  jump = .false.;  r = 0;  c = 0
         if (event) then
            self%events = self%events + 1
            if (self%ev_contact > md%n_contacts) then
               r = self%ev_contact - md%n_contacts
               if (self%ev_friction) forced = r
               if (self%ev_onset) then
                  ! closes here: stick at the contact point or slip at once
                  call onset_regime(md, r, s%u(md%r_dof(:, r)), s%v(md%r_dof(:, r)), &
                                    s%mode(r), s%sigma(r), s%anchor(r))
                  onset_mode = s%mode(r);  onset_sigma = s%sigma(r)
               end if
               jump = .not. self%ev_friction .and. md%laws(md%r_law(r))%law%jumps(md%r_k(r), &
                                                                      md%r_c(r), md%r_p(r))
            else
               c = self%ev_contact
               jump = self%jumps(c)
            end if
         end if
         call update_ring_modes(md, s%u, s%v, s%a, s%mode, s%sigma, s%anchor, forced)
         if (r > 0 .and. self%ev_onset) then
            ! round-off may put the onset a hair outside: it touches
            s%mode(r) = onset_mode;  s%sigma(r) = onset_sigma
            call ring_geometry(md, r, s%u(md%r_dof(:, r)), d, n, t, tau, gt)
            s%anchor(r) = tau
         end if
         if (jump) then
            call self%restart_after_event(k)
         else
            pr = ring_load(md, s)
         end if
      end associate
   end subroutine ring_switches

   !> At a located event the contact force may jump (a damper's force c d' at impact): the
   !> next sub-step starts from the right limit, forces of the new contact state and the
   !> acceleration in equilibrium with them, so that the trapezoidal rule does not average
   !> across the jump (which would cost an O(dt) velocity error per impact).
   subroutine restart_after_event(self, k)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-state at the event
      integer :: c, i
      real(dp) :: d, dd
      associate (md => self%model, s => self%sub(self%ix(k)))
         do c = 1, md%n_contacts
            i = md%c_dof(c)
            d = md%c_sign(c) * s%u(i) - md%c_gap(c)
            dd = md%c_sign(c) * s%v(i)
            if (c == self%ev_contact) then
               if (self%ev_onset) then
                  s%f(c) = contact_force(md, c, max(d, tiny(1.0_dp)), dd)
               else
                  s%f(c) = 0.0_dp
               end if
            else
               s%f(c) = contact_force(md, c, d, dd)
            end if
         end do
         if (md%n_rings > 0) then
            call restart_rings(md, self%ev_contact - md%n_contacts, self%ev_onset, s)
         else
            call equilibrium_acceleration(md, s%t, s%u, s%v, s%f, s%a)
         end if
      end associate
   end subroutine restart_after_event

   !> The ring forces at a located switch of ring `re` (0: a scalar contact's), right limit:
   !> a ring that closes there (onset) is taken as touching even if round-off puts it a hair
   !> outside; then the acceleration in equilibrium with every force.
   subroutine restart_rings(model, re, onset, s)
      type(model_t), intent(in) :: model        !! model
      integer, intent(in) :: re                 !! ring of the event (<= 0: none)
      logical, intent(in) :: onset              !! the event closes it
      type(state_t), intent(inout) :: s         !! state at the event
      real(dp) :: pr(model%n), pp(2)
      integer :: r
      pr = 0.0_dp
      do r = 1, model%n_rings
         call ring_force(model, r, s%mode(r), s%sigma(r), s%anchor(r), s%u(model%r_dof(:, r)), &
                         s%v(model%r_dof(:, r)), pp, s%fn(r), s%ft(r), &
                         touching=(r == re .and. onset))
         pr(model%r_dof(:, r)) = pr(model%r_dof(:, r)) + pp
      end do
      call equilibrium_acceleration(model, s%t, s%u, s%v, s%f, s%a, pr)
   end subroutine restart_rings

   !> Is contact c active at fraction x of a sub-step of length h (cubic Hermite interpolant
   !> of its dof from (u0, v0) to (u1, v1))? Penetration > 0, and for a law whose force can
   !> vanish earlier (a damper) also a positive force (the release: k d + c d' > 0).
   pure logical function contact_active(model, c, x, h, u0, v0, u1, v1, damped) result(active)
      type(model_t), intent(in) :: model     !! model
      integer, intent(in) :: c               !! contact
      real(dp), intent(in) :: x, h           !! fraction [-], sub-step [s]
      real(dp), intent(in) :: u0, v0, u1, v1 !! the contact dof at the ends
      logical, intent(in) :: damped          !! the force can vanish before the penetration
      real(dp) :: d, dd, h00, h10, h01, h11, g00, g10, g01, g11
      call hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
      d = model%c_sign(c) * (h00 * u0 + h10 * h * v0 + h01 * u1 + h11 * h * v1) - model%c_gap(c)
      active = d > 0.0_dp
      if (active .and. damped) then
         dd = model%c_sign(c) * (g00 * u0 + g10 * h * v0 + g01 * u1 + g11 * h * v1) / h
         active = contact_force(model, c, d, dd) > 0.0_dp
      end if
   end function contact_active

   !> Copy the state (arrays reused when sized).
   pure subroutine copy_state(a, b)
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

   !> Error control: the step-size ladder h_max 2^(-L/2) (a factorisation per size, cached),
   !> the watched outputs (root strain, tip and contact displacements) and their floors: the
   !> quasi-static response to the forcing amplitude, K u = (A_pp/2) Omega^2 q.
   subroutine init_control(self, model, cfg, err)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model
      type(solver_settings_t), intent(in) :: cfg            !! settings
      type(error_t), allocatable, intent(out) :: err        !! singular stiffness
      real(dp), allocatable :: kf(:, :), uqs(:)
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
      if (has_tube_physics(model)) call tube_floors(self, model, kf, n_out)
      if (self%caps%estimator == 'embedded') then
         ! rk_atol [m, m/s]: an absolute floor of the displacement and velocity outputs
         self%out_floor(2:n_out) = max(self%out_floor(2:n_out), cfg%rk_atol / cfg%tolerance)
         self%out_floor(n_out + 2:) = max(self%out_floor(n_out + 2:), cfg%rk_atol / cfg%tolerance)
      end if
   end subroutine init_control

   !> Floors of the watched outputs of a model with two planes or extra loads: the largest
   !> response to any one load vector of the open structure: the quasi-static K^-1 L for the w
   !> and v base motions (as for a planar model, whose floors a planar deck run with two planes
   !> keeps), and for the sin and cos parts of the point forces the smaller of that and the
   !> harmonic (K - Omega^2 M + i Omega C)^-1 L (a force above a resonance moves the structure
   !> far less than its static response); with two planes the same floor for an
   !> output and its mirror in the other plane (an orbit can turn from one plane into the other;
   !> a plane at rest must not get a zero floor).
   subroutine tube_floors(self, model, kf, n_out)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      type(model_t), intent(in) :: model                    !! model
      real(dp), intent(in) :: kf(:, :)                      !! Cholesky factor of K
      integer, intent(in) :: n_out                          !! 1 + size(out_dof)
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
   end subroutine tube_floors

   !> Carry `state` to t_target with error control: steps from the ladder, each accepted when
   !> the estimate of its local error in every watched output is within tolerance * (the
   !> output's range) * (step / forcing period); a step in which a contact opens or closes ends
   !> at that instant (its own step size, one factorisation), so no estimate straddles a
   !> switch; the last step before t_target and the observer's watch instant is cut to land on
   !> it.
   subroutine advance_controlled(self, state, t_target, obs, err)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      type(state_t), intent(inout) :: state                 !! state, at t_target on return
      real(dp), intent(in) :: t_target                      !! target time [s]
      class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
      type(error_t), allocatable, intent(out) :: err        !! numerical failure
      real(dp) :: t, t_stop, tiny_t
      integer :: level
      call copy_state(state, self%sub(self%ix(0)))
      if (state%dt_prev == 0.0_dp) then
         ! begin at T / steps_per_period
         level = min(self%n_levels - 1, max(0, nint(2.0_dp * log(real(self%cfg%steps_per_period, &
            dp) / 16.0_dp) / log(2.0_dp))))
         self%sub(self%ix(0))%dt_prev = self%h_max / 16.0_dp
      else
         level = min(max(state%level, 0), self%n_levels - 1)
      end if
      self%t_begin = state%t;  self%n_since = 0
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
   subroutine controlled_step(self, level, t_stop, obs, err)
      class(stepping_integrator_t), intent(inout), target :: self   !! integrator
      integer, intent(inout) :: level                       !! ladder level
      real(dp), intent(in) :: t_stop                        !! do not step beyond [s]
      class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
      type(error_t), allocatable, intent(out) :: err        !! failure at the smallest step
      real(dp) :: t0, t1, h, theta, ratio, r, q, rho, coef(3), comp
      logical :: ok, event, clipped
      integer :: worst, dl, switches
      t0 = self%sub(self%ix(0))%t
      switches = 0
      do
         r = 0.0_dp
         h = self%h_lev(level)
         if (t0 + h > t_stop - 1.0e-9_dp * h) then
            h = t_stop - t0
            call self%scratch%prepare(self%model, self%cfg, h, err)
            if (allocated(err)) return
            self%factorizations = self%factorizations + 1
            call self%one_step(self%scratch, 0, 0, ok, r)
         else
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
         event = .false.
         if (ok .and. self%cfg%locate_events .and. self%model%n_contacts &
             + self%model%n_rings > 0) then
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
               event = .true.
            end if
         end if
         if (ok) then
            if (event .or. h < self%h_lev(level) * (1.0_dp - 1.0e-9_dp)) then
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
            if (self%h_prev == 0.0_dp .and. coef(2) >= 0.0_dp .and. coef(3) /= 0.0_dp) then
               ! the first step from a start or a contact event has no previous step to
               ! estimate a'' from: its velocity error is measured by two half steps
               call self%richardson(level, h, event, r, worst, err)
               if (allocated(err)) return
               q = max(q, r)
            end if
         else
            q = huge(1.0_dp);  worst = 0
         end if
         ! one step may not spend more than the budget of a whole block
         ratio = q / (block_fraction * budget_scale * self%tolerance)
         if (ratio <= 1.0_dp) exit
         ! reject: smaller steps (the local error scales as h^3)
         self%steps_rejected = self%steps_rejected + 1
         if (level >= self%n_levels - 1) then
            call controlled_failure(self, t0, h, ratio, worst, ok, err)
            return
         end if
         dl = 1
         if (ratio < huge(1.0_dp)) dl = max(1, ceiling(log(ratio) / log(2.0_dp**(0.5_dp &
                                                 * (self%order + 1)))))
         level = min(self%n_levels - 1, level + dl)
      end do
      ! accept
      self%t_comp = comp
      call swap_check_emit(self, t0, h, event, obs, err)
      if (allocated(err)) return
      ! a'' of the next step from this one's fda, unless the acceleration jumps here
      self%fda_prev = self%fda
      self%h_prev = merge(0.0_dp, h, event)
      self%block_sum = self%block_sum + q
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
   end subroutine controlled_step

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
      else if (worst == 1) then
         what = 'the local error of the root strain is ' // str(ratio) // ' times the tolerance'
      else if (worst == 2 + size(self%out_dof)) then
         what = 'the local error of the root strain rate is ' // str(ratio) // ' times the ' &
                // 'tolerance'
      else
         what = 'the local error at ' // dof_label(self%model, self%out_dof(mod(worst - 2, &
                1 + size(self%out_dof)))) // ' is ' // str(ratio) // ' times the tolerance'
      end if
      call fatal_error(err, "gapbeam_stepping: method '" // self%method // "': at t = " &
         // str(t0) // ' s ' // what // ' with the smallest step dt = ' // str(h) // ' s; ' &
         // 'raise &solver tolerance (now ' // str(self%tolerance) // ') or max_halvings ' &
         // '(now ' // str(self%kmax) // ')')
   end subroutine controlled_failure

   !> The local error of a step relative to the watched outputs' ranges: the largest of
   !> |l' e_u| / max(range, floor) over the root strain and the tip and contact displacements,
   !> and |l' e_v| / max(range, floor) over the root strain rate and those velocities, with
   !> e_u = coef(1) h^2 fda, e_v = coef(2) h fda + coef(3) h^3 a'' (a'' from this and the
   !> previous step's fda; or the method's own e_v). Returns the output (1-based over the
   !> displacement outputs, then the rates) of the largest.
   real(dp) function error_ratio(self, h, coef, worst) result(ratio)
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
   real(dp) function output_ratio(self, worst) result(ratio)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(out) :: worst                      !! output of the largest ratio
      real(dp) :: es, r
      integer :: i, q, no
      no = 1 + size(self%out_dof)
      ratio = 0.0_dp;  worst = 1
      do i = 1, 2 * no
         if (i == no + 1 .and. .not. self%watch_rate) cycle
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
   end function output_ratio

   !> Error ratio of the step held in sub(ix(1)) by Richardson extrapolation: the same
   !> interval in two half steps (local error 1/4 of the whole step's for a method whose local
   !> error is O(h^3)), e = (4/3) (y_h - y_h/2) for u and v, measured on the watched outputs
   !> as error_ratio does. For the steps that begin a run or follow a contact event, where the
   !> method's own estimate lacks a''; they are a few per forcing period.
   subroutine richardson(self, level, h, event, ratio, worst, err)
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
   subroutine track_outputs(self, s, first)
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
   end subroutine track_outputs

   !> Root strain, its rate, tip displacement and velocity, contact forces at t: quintic
   !> Hermite interpolation of the sub-step from (u, v, a) at both ends (error O(h^6) in u,
   !> O(h^5) in v, below the method's own in both).
   subroutine hermite_sample(self, t, strain, rate, tip, tip_velocity, force)
      class(hermite_piece_t), intent(in) :: self        !! piece
      real(dp), intent(in) :: t                         !! instant [s]
      real(dp), intent(out) :: strain, rate, tip, tip_velocity   !! outputs
      real(dp), intent(out) :: force(:)                 !! contact force magnitudes [N]
      real(dp) :: h, w(6), g(6), ui, vi
      integer :: i, c
      h = self%tb - self%ta
      call quintic_weights(min(1.0_dp, max(0.0_dp, (t - self%ta) / h)), h, w, g)
      strain = 0.0_dp;  rate = 0.0_dp;  tip = 0.0_dp;  tip_velocity = 0.0_dp
      associate (m => self%model, sa => self%sub(self%ja), sb => self%sub(self%jb))
         do i = 1, m%n
            ui = w(1) * sa%u(i) + w(2) * sa%v(i) + w(3) * sa%a(i) + w(4) * sb%u(i) &
                 + w(5) * sb%v(i) + w(6) * sb%a(i)
            vi = g(1) * sa%u(i) + g(2) * sa%v(i) + g(3) * sa%a(i) + g(4) * sb%u(i) &
                 + g(5) * sb%v(i) + g(6) * sb%a(i)
            strain = strain + m%sys%strain_row(i) * ui
            rate = rate + m%sys%strain_row(i) * vi
            if (i == m%sys%tip_dof) then
               tip = ui;  tip_velocity = vi
            end if
         end do
         do c = 1, m%n_contacts
            i = m%c_dof(c)
            ui = w(1) * sa%u(i) + w(2) * sa%v(i) + w(3) * sa%a(i) + w(4) * sb%u(i) &
                 + w(5) * sb%v(i) + w(6) * sb%a(i)
            vi = g(1) * sa%u(i) + g(2) * sa%v(i) + g(3) * sa%a(i) + g(4) * sb%u(i) &
                 + g(5) * sb%v(i) + g(6) * sb%a(i)
            force(c) = contact_force(m, c, m%c_sign(c) * ui - m%c_gap(c), m%c_sign(c) * vi)
         end do
      end associate
   end subroutine hermite_sample

   !> Displacement and velocity of every dof at t (quintic Hermite interpolation).
   subroutine hermite_state(self, t, u, v)
      class(hermite_piece_t), intent(in) :: self        !! piece
      real(dp), intent(in) :: t                         !! instant [s]
      real(dp), intent(out) :: u(:), v(:)               !! state
      real(dp) :: h, w(6), g(6)
      h = self%tb - self%ta
      call quintic_weights(min(1.0_dp, max(0.0_dp, (t - self%ta) / h)), h, w, g)
      associate (sa => self%sub(self%ja), sb => self%sub(self%jb))
         u = w(1) * sa%u + w(2) * sa%v + w(3) * sa%a + w(4) * sb%u + w(5) * sb%v + w(6) * sb%a
         v = g(1) * sa%u + g(2) * sa%v + g(3) * sa%a + g(4) * sb%u + g(5) * sb%v + g(6) * sb%a
      end associate
   end subroutine hermite_state

   !> Weights of the quintic Hermite interpolant at fraction x of a step of h: the value is
   !> w . (u0, v0, a0, u1, v1, a1), its time derivative g . (the same).
   pure subroutine quintic_weights(x, h, w, g)
      real(dp), intent(in) :: x, h             !! fraction [-], step [s]
      real(dp), intent(out) :: w(6), g(6)      !! weights of value and derivative
      real(dp) :: x2, x3, x4, x5
      x2 = x * x;  x3 = x2 * x;  x4 = x3 * x;  x5 = x4 * x
      w(1) = 1.0_dp - 10.0_dp * x3 + 15.0_dp * x4 - 6.0_dp * x5
      w(2) = h * (x - 6.0_dp * x3 + 8.0_dp * x4 - 3.0_dp * x5)
      w(3) = h**2 * 0.5_dp * (x2 - 3.0_dp * x3 + 3.0_dp * x4 - x5)
      w(4) = 10.0_dp * x3 - 15.0_dp * x4 + 6.0_dp * x5
      w(5) = h * (-4.0_dp * x3 + 7.0_dp * x4 - 3.0_dp * x5)
      w(6) = h**2 * 0.5_dp * (x3 - 2.0_dp * x4 + x5)
      g(1) = (-30.0_dp * x2 + 60.0_dp * x3 - 30.0_dp * x4) / h
      g(2) = 1.0_dp - 18.0_dp * x2 + 32.0_dp * x3 - 15.0_dp * x4
      g(3) = h * 0.5_dp * (2.0_dp * x - 9.0_dp * x2 + 12.0_dp * x3 - 5.0_dp * x4)
      g(4) = (30.0_dp * x2 - 60.0_dp * x3 + 30.0_dp * x4) / h
      g(5) = -12.0_dp * x2 + 28.0_dp * x3 - 15.0_dp * x4
      g(6) = h * 0.5_dp * (3.0_dp * x2 - 8.0_dp * x3 + 5.0_dp * x4)
   end subroutine quintic_weights

   !> Weights of the cubic Hermite interpolant (h..) and of its derivative times h (g..).
   pure subroutine hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
      real(dp), intent(in) :: x                                   !! fraction of the step
      real(dp), intent(out) :: h00, h10, h01, h11, g00, g10, g01, g11   !! weights
      h00 = (1 + 2 * x) * (1 - x)**2;  h10 = x * (1 - x)**2
      h01 = x**2 * (3 - 2 * x);  h11 = x**2 * (x - 1)
      g00 = 6 * x**2 - 6 * x;  g10 = 3 * x**2 - 4 * x + 1
      g01 = -6 * x**2 + 6 * x;  g11 = 3 * x**2 - 2 * x
   end subroutine hermite_weights
end module gapbeam_stepping
