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
   use gapbeam_model, only: model_t, has_tube_physics, ring_xy
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_capabilities, only: method_caps
   use gapbeam_contact_law, only: contact_force, contact_releases_early, contact_jumps
   use gapbeam_observer, only: piece_t, observer_t
   use gapbeam_hermite_piece, only: hermite_piece_t, hermite_weights, quintic_weights
   use gapbeam_integrator, only: integrator_t, stepper_t, equilibrium_acceleration, zero_counters, &
      make_stepper, dof_label, ring_load
   use gapbeam_ring_contact, only: ring_open, ring_stick, ring_slip, ring_indicators, &
      ring_geometry, update_ring_modes, ring_force, onset_regime
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
      real(dp) :: t_checked = 0.0_dp                  !! time of the last energy check [s]
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
      real(dp), allocatable :: eu_d(:), ev_d(:)       !! its cubic interpolant's error (dense_error)
      real(dp), allocatable :: eu_q(:), ev_q(:)       !! its quintic interpolant's error
      !> the events of a ring in contact at a step's start (its release, its stick-slip
      !> switches) are located on the step's quintic (u, v, a at both ends: the piece that is
      !> emitted and checked) instead of the cubic from u, v: set by dense_ratio when the
      !> stepper checks its quintic and the model has no flat contacts
      logical :: quintic_events = .false.
      !> the ring that the trial step entered and that it was redone with held open (0: none):
      !> its onset is located on that step's quintic, the free flight's (controlled_step)
      integer :: held_ring = 0
      real(dp), allocatable :: fda_prev(:)            !! fda of the previous accepted step
      real(dp) :: h_prev = 0.0_dp                     !! its length (0: none usable) [s]
      integer :: order = 2                            !! order of the method
      real(dp) :: block_start = 0.0_dp                !! current block of the controller [s]
      real(dp) :: block_sum = 0.0_dp                  !! local errors accepted in it [-]
      !> the root strain rate is watched (not with ring contacts, see init_control)
      logical :: watch_rate = .true.
      !> the wear work watched per ring (wear_ratio): range of the tangential velocity in
      !> contact [m/s], its floor [m/s] and the largest normal force seen [N]
      real(dp), allocatable :: vt_lo(:), vt_hi(:), vt_floor(:), fn_max(:)
      !> the part of the wear watch held per step, not summed (output_ratio's last call): the
      !> work integrand's error from the penetration's, v_t df_n / (F_max V_t), and its ring
      real(dp) :: wear_local = 0.0_dp
      integer :: wear_local_ring = 0
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

   interface
      ! contact events: located, switched, restarted (submodule gapbeam_stepping_events)
      real(dp) module function first_event(self, k, h) result(th)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         integer, intent(in) :: k                              !! sub-step start
         real(dp), intent(in) :: h                             !! its length [s]
      end function first_event

      module subroutine first_ring_event(self, k, h, th)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         integer, intent(in) :: k                              !! sub-step start
         real(dp), intent(in) :: h                             !! its length [s]
         real(dp), intent(inout) :: th                         !! earliest event so far [-]
      end subroutine first_ring_event

      module subroutine ring_switches(self, k, event)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         integer, intent(in) :: k                              !! sub-state at the end
         logical, intent(in) :: event                          !! the step ended at an event
      end subroutine ring_switches

      module subroutine restart_after_event(self, k)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         integer, intent(in) :: k                              !! sub-state at the event
      end subroutine restart_after_event

      ! error control (submodule gapbeam_stepping_control)
      module pure subroutine copy_state(a, b)
         type(state_t), intent(in) :: a      !! source
         type(state_t), intent(inout) :: b   !! destination
      end subroutine copy_state

      module subroutine init_control(self, model, cfg, err)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         type(model_t), intent(in) :: model                    !! model
         type(solver_settings_t), intent(in) :: cfg            !! settings
         type(error_t), allocatable, intent(out) :: err        !! singular stiffness
      end subroutine init_control

      module subroutine advance_controlled(self, state, t_target, obs, err)
         class(stepping_integrator_t), intent(inout), target :: self   !! integrator
         type(state_t), intent(inout) :: state                 !! state, at t_target on return
         real(dp), intent(in) :: t_target                      !! target time [s]
         class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
         type(error_t), allocatable, intent(out) :: err        !! numerical failure
      end subroutine advance_controlled

      module subroutine controlled_step(self, level, t_stop, obs, err)
         class(stepping_integrator_t), intent(inout), target :: self   !! integrator
         integer, intent(inout) :: level                       !! ladder level
         real(dp), intent(in) :: t_stop                        !! do not step beyond [s]
         class(observer_t), intent(inout), optional :: obs     !! observer of the pieces
         type(error_t), allocatable, intent(out) :: err        !! failure at the smallest step
      end subroutine controlled_step

      real(dp) module function error_ratio(self, h, coef, worst) result(ratio)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         real(dp), intent(in) :: h                          !! step [s]
         real(dp), intent(in) :: coef(3)                    !! the method's error coefficients
         integer, intent(out) :: worst                      !! output of the largest ratio
      end function error_ratio

      real(dp) module function output_ratio(self, worst, events_only) result(ratio)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         integer, intent(out) :: worst                      !! output of the largest ratio
         logical, intent(in), optional :: events_only       !! the contact dofs' outputs only
      end function output_ratio

      module subroutine richardson(self, level, h, event, ratio, worst, err)
         class(stepping_integrator_t), intent(inout), target :: self   !! integrator
         integer, intent(in) :: level                    !! the step's ladder level
         real(dp), intent(in) :: h                       !! the step [s]
         logical, intent(in) :: event                    !! it ends at a located event
         real(dp), intent(out) :: ratio                  !! error / tolerance share of the step
         integer, intent(out) :: worst                   !! output of the largest ratio
         type(error_t), allocatable, intent(out) :: err  !! factorisation failure
      end subroutine richardson

      module subroutine track_outputs(self, s, first)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
         type(state_t), intent(in) :: s                        !! an accepted state
         logical, intent(in) :: first                          !! reset the ranges
      end subroutine track_outputs

      !> No ring can switch within the step ix(0) -> ix(1), whatever the cubic's error
      !> (stepping_events).
      logical module function rings_clear(self) result(clear)
         class(stepping_integrator_t), intent(in) :: self   !! integrator
      end function rings_clear

      !> The first ring that the trial step ix(0) -> ix(1) enters; 0: none (stepping_events).
      integer module function entered_ring(self) result(re)
         class(stepping_integrator_t), intent(in) :: self   !! integrator
      end function entered_ring

      !> The cubic's errors at the dofs of the rings whose events are on the quintic set to
      !> zero (stepping_events).
      module subroutine forget_closed_rings(self)
         class(stepping_integrator_t), intent(inout) :: self   !! integrator
      end subroutine forget_closed_rings
   end interface

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
      self%t_begin = state%t;  self%n_since = 0;  self%t_checked = state%t
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
         ! is the reference), by steps and by time (a method whose linear part is exact takes
         ! a period in fewer than 64 steps: the reference stayed the start's, 0 from rest)
         if (t1 - self%t_begin <= self%period) then
            if (self%n_since < max(1, min(64, self%cfg%steps_per_period / 8)) .and. &
                t1 - self%t_checked < 0.125_dp * self%period) return
         else if (self%n_since < 64) then
            return
         end if
         self%n_since = 0;  self%t_checked = t1
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
      real(dp) :: da, db, n(2), t(2), gt
      p%r_mode = sa%mode;  p%r_sigma = sa%sigma;  p%r_anchor = sa%anchor
      p%fn_a = sa%fn;  p%fn_b = sb%fn
      do r = 1, model%n_rings
         p%r_onset(r) = sb%fn(r) > 0.0_dp .and. .not. sa%fn(r) > 0.0_dp
         if (.not. p%r_onset(r)) cycle
         call ring_geometry(model, r, ring_xy(model, r, sa%u), da, n, t, gt=gt)
         call ring_geometry(model, r, ring_xy(model, r, sb%u), db, n, t, gt=gt)
         if (da <= 0.0_dp .and. db > da) then
            p%r_onset_time(r) = p%ta + (p%tb - p%ta) * (-da) / (db - da)
         else
            p%r_onset_time(r) = p%ta
         end if
      end do
   end subroutine ring_piece

end module gapbeam_stepping
