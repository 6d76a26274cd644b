!> The shape of time integration: integrators advance a state, observers watch the pieces of
!> trajectory they produce.
!>
!> * `integrator_t`: built once from the model and the solver settings (`init`: factorisations,
!>   eigen decompositions), then `advance(state, t_target, observer)` carries a state_t to a
!>   target time, locating contact events inside. The same object advances any number of
!>   states (a Lyapunov pair, the periods of a shooting method) without rebuilding anything.
!> * observers (gapbeam_observer) receive the pieces of trajectory an advance produces: the
!>   recorder of a transient run, or nothing (a Lyapunov pair, a shooting period).
!> * `stepper_t`: one step of a one-step method at one step size; the stepping integrator
!>   (gapbeam_stepping) drives any stepper with step control and event location.
!>
!> The registry (submodule gapbeam_integrator_registry) maps the deck's method word to an
!> implementation: adding a method is one module and one line there. Analyses use this module
!> only, never an implementation.
module gapbeam_integrator
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_model, only: model_t, load_factor, add_extra_load, ring_xy
   use gapbeam_description, only: dof_name
   use gapbeam_law, only: law_caps_t
   use gapbeam_capabilities, only: method_caps_t, needs_t, method_table, method_caps, &
      model_needs, method_refusal, needs_text
   use gapbeam_observer, only: piece_t, observer_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_contact_law, only: contact_force
   use gapbeam_ring_contact, only: ring_open, ring_geometry, ring_forces_at, update_ring_modes, &
      onset_regime
   use gapbeam_lapack, only: dpotrf, dpotrs
   implicit none
   private
   public :: integrator_t, stepper_t, make_integrator, make_stepper
   public :: start_state, equilibrium_acceleration, contact_forces_at, massless_equilibrium, &
      dof_label, resolve_method, refusal, tube_physics_text, ring_load
   public :: method_registry_t, method_registry, zero_counters

   !> A time integrator: built once, advances states.
   type, abstract :: integrator_t
      character(len=:), allocatable :: method      !! the deck's method word
      integer(int64) :: steps_accepted = 0         !! steps (or linear segments) accepted
      integer(int64) :: steps_rejected = 0         !! steps rejected by the control
      integer(int64) :: events = 0                 !! contact events located
      integer(int64) :: factorizations = 0         !! operators built (factorisations, configs)
      integer(int64) :: fp_iterations = 0          !! fixed-point iterations on the stop force
      real(dp) :: dt_smallest = huge(1.0_dp)       !! smallest step (segment) [s]
      real(dp) :: dt_largest = 0.0_dp              !! largest step (segment) [s]
      character(len=:), allocatable :: reason      !! why this method ran ('auto')
      type(method_caps_t) :: caps                  !! what the method can do (the registry's)
   contains
      procedure(init_interface), deferred :: init        !! build for a model
      procedure(advance_interface), deferred :: advance  !! carry a state to a time
      ! --- continuation hook (issue 14): the Jacobian of the flow where an integrator has one
      !     (the exact integrator overrides it); the default says there is none
      procedure :: advance_jacobian => advance_jacobian_none
      ! --- end of the continuation hook
      procedure :: reset_counters => zero_counters       !! counters to zero (a new record)
   end type integrator_t

   !> One step of a one-step method at one step size.
   type, abstract :: stepper_t
      real(dp) :: dt = 0.0_dp                 !! step size it is prepared for [s]
      logical :: ready = .false.              !! prepared
      integer(int64) :: iterations = 0        !! inner iterations spent (e.g. fixed point)
      integer(int64) :: evaluations = 0       !! right-hand-side evaluations (explicit methods)
   contains
      procedure(prepare_interface), deferred :: prepare   !! factorise / precompute for dt
      procedure(step_interface), deferred :: step         !! advance one step of size dt
      procedure :: local_error => no_local_error          !! error estimate of the last step
      procedure :: dense_error => no_dense_error          !! its interpolant's own error
   end type stepper_t

   !> A method of the registry: what it can do (gapbeam_capabilities) and, for a one-step
   !> method, an unprepared stepper of it (its prototype; not allocated: the exact integrator).
   type :: method_entry_t
      type(method_caps_t) :: caps                      !! capabilities
      class(stepper_t), allocatable :: proto           !! stepper prototype
   end type method_entry_t

   !> The registry of time integrators: the built-in methods (method_registry()), to which a
   !> caller (a test) may add its own with `add`.
   type :: method_registry_t
      type(method_entry_t), allocatable :: entries(:)  !! the methods
   contains
      procedure :: add => registry_add                 !! one more method
      procedure :: table => registry_table             !! capabilities of every method
      procedure :: find => registry_find               !! index of a method word (0: none)
   end type method_registry_t

   abstract interface
      !> Build the integrator for a model (keeps its own copy of the model).
      subroutine init_interface(self, model, cfg, err)
         import :: integrator_t, model_t, solver_settings_t, error_t
         class(integrator_t), intent(inout) :: self      !! integrator
         type(model_t), intent(in) :: model              !! model
         type(solver_settings_t), intent(in) :: cfg      !! settings
         type(error_t), allocatable, intent(out) :: err  !! unsupported model, LAPACK failure
      end subroutine init_interface

      !> Carry `state` from state%t to t_target, feeding `obs` (if present) with the pieces.
      subroutine advance_interface(self, state, t_target, obs, err)
         import :: integrator_t, state_t, observer_t, dp, error_t
         class(integrator_t), intent(inout), target :: self   !! integrator
         type(state_t), intent(inout) :: state           !! state, at t_target on return
         real(dp), intent(in) :: t_target                !! target time [s]
         class(observer_t), intent(inout), optional :: obs    !! observer
         type(error_t), allocatable, intent(out) :: err  !! numerical failure
      end subroutine advance_interface

      !> Prepare the stepper for steps of size dt.
      subroutine prepare_interface(self, model, cfg, dt, err)
         import :: stepper_t, model_t, solver_settings_t, dp, error_t
         class(stepper_t), intent(inout) :: self          !! stepper
         type(model_t), intent(in) :: model               !! model
         type(solver_settings_t), intent(in) :: cfg       !! settings
         real(dp), intent(in) :: dt                       !! step size [s]
         type(error_t), allocatable, intent(out) :: err   !! factorisation failure
      end subroutine prepare_interface

      !> Advance s0 by dt into s1 (t, u, v, a, f; s0%f_prev and s0%dt_prev feed the paper's
      !> extrapolated fixed point). `ok` false asks for a smaller step (an iteration did not
      !> converge); `ratio` is an embedded local-error estimate relative to its tolerance
      !> (> 1: reject), or negative when the method has none. `open_contact` > 0 holds that
      !> contact open (the step ends at its located onset: the left limit).
      subroutine step_interface(self, model, s0, s1, ok, ratio, open_contact)
         import :: stepper_t, model_t, state_t, dp
         class(stepper_t), intent(inout) :: self          !! stepper
         type(model_t), intent(in) :: model               !! model
         type(state_t), intent(in) :: s0                  !! state at the start
         type(state_t), intent(inout) :: s1               !! state at the end (arrays sized)
         logical, intent(out) :: ok                       !! step succeeded
         real(dp), intent(out) :: ratio                   !! embedded error / tolerance, or < 0
         integer, intent(in) :: open_contact              !! contact held open (0: none)
      end subroutine step_interface
   end interface

   interface
      !> An integrator of the settings' method, initialised for the model: 'auto' resolved,
      !> refused with the registry's reason when the method cannot integrate the model.
      !> `registry`: the built-in methods when absent.
      module subroutine make_integrator(model, cfg, integ, err, registry)
         type(model_t), intent(in) :: model                      !! model
         type(solver_settings_t), intent(in) :: cfg              !! method and settings
         class(integrator_t), allocatable, intent(out) :: integ  !! ready to advance
         type(error_t), allocatable, intent(out) :: err          !! unknown method, set-up
         type(method_registry_t), intent(in), optional :: registry   !! methods
      end subroutine make_integrator

      !> An unprepared stepper of a one-step method word (the registry).
      module subroutine make_stepper(method, proto, err, registry)
         character(len=*), intent(in) :: method                  !! method word
         class(stepper_t), allocatable, intent(out) :: proto     !! the method's stepper
         type(error_t), allocatable, intent(out) :: err          !! not a one-step method
         type(method_registry_t), intent(in), optional :: registry   !! methods
      end subroutine make_stepper

      !> The built-in methods: every line of method_table() with its implementation.
      module function method_registry() result(reg)
         type(method_registry_t) :: reg                          !! registry
      end function method_registry
   end interface

contains

   !> The settings a run uses: method 'auto' resolved by the registry (`choose_auto`), a
   !> variant's preset parameters applied, and step_control 'auto' resolved to the method's
   !> own (`auto_control`: 'error' for the methods with an error estimate, 'fixed' for the
   !> others; 'embedded' is the embedded pairs' name for 'error'); `reason` says which method
   !> runs and why. `table`: the registry's capabilities (default: method_table()).
   subroutine resolve_method(model, cfg, eff, reason, table)
      type(model_t), intent(in) :: model                   !! model (its needs)
      type(solver_settings_t), intent(in) :: cfg           !! the deck's settings
      type(solver_settings_t), intent(out) :: eff          !! the settings that run
      character(len=:), allocatable, intent(out) :: reason !! one line
      type(method_caps_t), intent(in), optional :: table(:)   !! registry
      type(method_caps_t), allocatable :: t(:)
      type(method_caps_t) :: c
      if (present(table)) then
         t = table
      else
         t = method_table()
      end if
      eff = cfg
      reason = "method '" // trim(cfg%method) // "' as the deck asks"
      if (cfg%method == 'auto') call choose_auto(model, cfg, t, eff%method, reason)
      c = method_caps(eff%method, t)
      if (cfg%method == 'auto' .and. c%loosest_tolerance > 0.0_dp .and. &
          eff%tolerance > c%loosest_tolerance) then
         eff%tolerance = c%loosest_tolerance
         reason = reason // ' at tolerance ' // str(c%loosest_tolerance) // " (the loosest " &
            // "'auto' runs it at; the deck asks " // str(cfg%tolerance) // ')'
      end if
      if (c%newmark_delta >= 0.0_dp) eff%newmark_delta = c%newmark_delta
      if (c%newmark_alpha >= 0.0_dp) eff%newmark_alpha = c%newmark_alpha
      select case (eff%step_control)
      case ('auto')
         eff%step_control = c%auto_control
      case ('embedded')
         eff%step_control = 'error'
      end select
   end subroutine resolve_method

   !> What method 'auto' runs, from the registry's roles: the 'exact' method when it can
   !> integrate the model; else, on a reduced model (&reduction) with piecewise-linear stop
   !> laws and what the exact one cannot take (rings, friction, two planes, point forces,
   !> turbulence), the 'modal' one (the modal exponential integrator, exact on the retained
   !> modes) when it can integrate it; else the
   !> 'default' one (Newmark with error control at the tolerance), unless the tolerance is
   !> below the default's accuracy floor and a 'fine' method can integrate the model at an
   !> estimated lower cost. A deck that asks for the
   !> default's stepping options (step_control 'half_step' or 'fixed', stop_solution
   !> 'fixed_point': written before 'auto' existed, when Newmark was the default) keeps it.
   subroutine choose_auto(model, cfg, t, method, reason)
      type(model_t), intent(in) :: model                   !! model
      type(solver_settings_t), intent(in) :: cfg           !! the deck's settings
      type(method_caps_t), intent(in) :: t(:)              !! registry
      character(len=*), intent(inout) :: method            !! 'auto' in, the choice out
      character(len=:), allocatable, intent(inout) :: reason !! why
      type(needs_t) :: nd
      integer :: j, i_exact, i_modal, i_fine, i_default
      i_exact = 0;  i_modal = 0;  i_fine = 0;  i_default = 0
      do j = size(t), 1, -1
         select case (t(j)%auto_role)
         case ('exact');  i_exact = j
         case ('modal');  i_modal = j
         case ('fine');  i_fine = j
         case ('default');  i_default = j
         end select
      end do
      if (i_default == 0) error stop 'gapbeam_integrator:choose_auto: no default method in ' &
         // 'the registry'
      method = t(i_default)%name
      nd = model_needs(model)
      if (cfg%step_control == 'half_step' .or. cfg%step_control == 'fixed' .or. &
          cfg%stop_solution == 'fixed_point') then
         reason = "method 'auto': the deck asks for stepping options (step_control = '" &
            // trim(cfg%step_control) // "', stop_solution = '" // trim(cfg%stop_solution) &
            // "'), so " // trim(t(i_default)%title)
      else if (model%mechanism) then
         reason = "method 'auto': the beam is a mechanism (rigid modes that only its stops " &
            // 'hold), which the exact integrator cannot integrate yet, so ' &
            // trim(t(i_default)%title) // ' with error control at the tolerance'
      else if (model%reduced .and. len_trim(nd%nonlinear_law) == 0 .and. &
               len(needs_text(nd)) > 0 .and. .not. can_run(i_exact) .and. can_run(i_modal)) then
         ! (piecewise-linear laws only: on a reduced beam with a Hertz stop, whose force has
         ! an unbounded second derivative at the onset, the exponential integrator's orbit
         ! repeated to only 2.5e-6 at tolerance 1e-7, against Newmark's 2e-8)
         method = t(i_modal)%name
         reason = "method 'auto': the model is reduced (&reduction) and has " &
            // needs_text(nd) // ', so ' // trim(t(i_modal)%title)
      else if (len(needs_text(nd)) > 0 .and. .not. can_run(i_exact)) then
         reason = "method 'auto': it has " // needs_text(nd) // ', so ' &
            // trim(t(i_default)%title) // ' with error control at the tolerance'
      else if (can_run(i_exact)) then
         method = t(i_exact)%name
         reason = "method 'auto': every stop is piecewise linear, so " // trim(t(i_exact)%title)
      else if (cfg%tolerance < t(i_default)%accuracy_floor .and. can_run(i_fine)) then
         if (.not. cheaper(model, cfg%tolerance, t(i_fine), t(i_default))) then
            reason = nonlinear_reason()
            return
         end if
         method = t(i_fine)%name
         reason = "method 'auto': a stop is not piecewise linear (" // law_title() &
            // ') and the tolerance is below what ' // trim(t(i_default)%title) // ' reaches ' &
            // 'in double precision (about ' // str(t(i_default)%accuracy_floor) // '), so ' &
            // trim(t(i_fine)%title) // ' (estimated cheaper for this model)'
      else
         reason = nonlinear_reason()
      end if

   contains

      !> Can method j of the registry integrate the model (j = 0: there is none)?
      logical function can_run(j)
         integer, intent(in) :: j
         can_run = .false.
         if (j > 0) can_run = len(method_refusal(t(j), nd, t(j)%auto_control, 'condensed', &
                                                 t)) == 0
         ! a mechanism: not the exact integrator (refusal)
         if (j > 0 .and. model%mechanism) can_run = can_run .and. .not. t(j)%exact
      end function can_run

      !> The title of the first law that is not piecewise linear.
      function law_title() result(w)
         character(len=:), allocatable :: w
         type(law_caps_t) :: lc
         integer :: k
         w = trim(nd%nonlinear_law)
         do k = 1, size(model%laws)
            lc = model%laws(k)%law%caps()
            if (lc%name == nd%nonlinear_law) w = trim(lc%title)
         end do
      end function law_title

      function nonlinear_reason() result(w)
         character(len=:), allocatable :: w
         w = "method 'auto': a stop is not piecewise linear (" // law_title() // '), so ' &
            // trim(t(i_default)%title) // ' with error control at the tolerance'
      end function nonlinear_reason
   end subroutine choose_auto

   !> Why the registry's method (with the resolved step control and stop solution) cannot
   !> integrate the model, or '' when it can (gapbeam_capabilities: method_refusal).
   function refusal(model, eff, table) result(why)
      type(model_t), intent(in) :: model                  !! model
      type(solver_settings_t), intent(in) :: eff          !! resolved settings
      type(method_caps_t), intent(in), optional :: table(:)   !! registry
      character(len=:), allocatable :: why
      type(method_caps_t) :: c
      c = method_caps(eff%method, table)
      why = ''
      if (len_trim(c%name) == 0) return
      why = method_refusal(c, model_needs(model), eff%step_control, eff%stop_solution, table)
      if (len(why) == 0 .and. c%exact .and. model%mechanism) why = "method '" &
         // trim(c%name) // "' cannot integrate this model: it is a mechanism (a rigid mode " &
         // 'that only its stops hold, f1 = 0 with the stops open), whose closed ' &
         // "configurations the exact integrator cannot solve yet: use method = 'newmark'"
   end function refusal

   !> What a model has beyond a planar beam with flat frictionless stops, in words ('it
   !> has ...'; '' when nothing).
   function tube_physics_text(model) result(t)
      type(model_t), intent(in) :: model            !! model
      character(len=:), allocatable :: t
      t = needs_text(model_needs(model))
      if (len(t) > 0) t = 'it has ' // t
   end function tube_physics_text

   !> Whether the 'fine' (explicit, embedded) method `fine` is expected to cost less than the
   !> 'default' implicit one at `tol` on this model: flops per forcing period from the step
   !> counts measured on the reference beam (Newmark about 100 tol^(-1/order) steps, rk45
   !> 60 tol^(-1/order) or its stability limit T |lambda|_max / limit, whichever is more,
   !> |lambda|_max = max(omega_max, beta + gamma omega_max^2): Rayleigh damping makes the high
   !> modes overdamped and stiff) and the work of a step (an implicit step 4 n^2 dense or 40 n
   !> banded, an explicit one 3 n^2 per stage of dense products). Explicit methods need a mass
   !> at every dof.
   pure logical function cheaper(model, tol, fine, default) result(yes)
      type(model_t), intent(in) :: model              !! model
      real(dp), intent(in) :: tol                     !! tolerance
      type(method_caps_t), intent(in) :: fine         !! the candidate
      type(method_caps_t), intent(in) :: default      !! the default method
      real(dp) :: n, period, cost_nm, cost_rk
      yes = .false.
      if (.not. allocated(model%sys%m_band)) return
      if (any(model%sys%m_band(model%sys%kd + 1, :) <= 0.0_dp)) return
      if (fine%order < 1 .or. default%order < 1 .or. .not. (fine%stability_limit > 0.0_dp)) &
         return
      n = real(model%n, dp)
      period = 2.0_dp * pi / model%omega
      cost_nm = 100.0_dp * tol**(-1.0_dp / default%order) * merge(4.0_dp * n**2, 40.0_dp * n, &
                                                                 model%n <= 60)
      ! the stiffest eigenvalue: omega_max, or beta + gamma omega_max^2 when overdamped
      cost_rk = max(60.0_dp * tol**(-1.0_dp / fine%order), period * max(model%omega_max, &
                model%beta + model%gamma * model%omega_max**2) / fine%stability_limit) &
                * (3.0_dp * fine%stages) * n**2
      yes = cost_rk < cost_nm
   end function cheaper

   !> The default: a method without a local error estimate.
   !>
   !> A method with one returns the change of acceleration over the step, filtered so that
   !> only the modes the step resolves pass (fda), and coefficients such that the local errors
   !> of the step are e_u = coef(1) h^2 fda and e_v = coef(2) h fda + coef(3) h^3 a'' (the
   !> integrator estimates a'' from fda of this and the previous step); coef(2) < 0 means the
   !> method gives e_v itself (ev).
   subroutine no_local_error(self, model, s0, s1, fda, ev, coef, has)
      class(stepper_t), intent(inout) :: self         !! stepper
      type(model_t), intent(in) :: model              !! model
      type(state_t), intent(in) :: s0, s1             !! the step just taken
      real(dp), intent(out) :: fda(:)                 !! filtered a1 - a0 [m/s^2, rad/s^2]
      real(dp), intent(out) :: ev(:)                  !! velocity error, if coef(2) < 0
      real(dp), intent(out) :: coef(3)                !! error coefficients
      logical, intent(out) :: has                     !! false: none
      fda = 0.0_dp;  ev = 0.0_dp;  coef = 0.0_dp
      has = .false.
   end subroutine no_local_error

   !> The default: the step's interpolant has no error estimate of its own (what local_error
   !> estimates covers it, or nothing is known).
   !>
   !> A method that has one returns the errors of the step's Hermite interpolants at its
   !> midpoint, in displacement and velocity: of the cubic from u, v at both ends, on which
   !> events are located (eu, ev), and of the quintic from u, v, a, which samples, states and
   !> the wear statistics read (eq, evq, when asked for). The integrator controls them per
   !> step, not per unit time: they are not carried into the next step (which starts from the
   !> method's end state), so they do not add up along the trajectory.
   subroutine no_dense_error(self, eu, ev, has, eq, evq)
      class(stepper_t), intent(inout) :: self         !! stepper
      real(dp), intent(out) :: eu(:)                  !! cubic's displacement error at the midpoint
      real(dp), intent(out) :: ev(:)                  !! cubic's velocity error at the midpoint
      logical, intent(out) :: has                     !! false: none
      real(dp), intent(out), optional :: eq(:), evq(:) !! the quintic's
      eu = 0.0_dp;  ev = 0.0_dp
      if (present(eq)) eq = 0.0_dp
      if (present(evq)) evq = 0.0_dp
      has = .false.
   end subroutine no_dense_error

   !> The counters to zero: what a record reports is then the work of that record (an
   !> integrator reused for the next run of the same model keeps its factorisations).
   subroutine zero_counters(self)
      class(integrator_t), intent(inout) :: self   !! integrator
      self%steps_accepted = 0;  self%steps_rejected = 0;  self%events = 0
      self%factorizations = 0;  self%fp_iterations = 0
      self%dt_smallest = huge(1.0_dp);  self%dt_largest = 0.0_dp
   end subroutine zero_counters

   ! --- continuation hook (issue 14)
   !> Advance and return d x(t_target) / d x(t) in the reduced coordinates of the dofs with
   !> mass (see gapbeam_exact_jacobian); this integrator has no such Jacobian: an error, the
   !> state unchanged. Callers use finite differences of `advance` instead.
   subroutine advance_jacobian_none(self, state, t_target, jac, err)
      class(integrator_t), intent(inout), target :: self   !! integrator
      type(state_t), intent(inout) :: state            !! state (unchanged)
      real(dp), intent(in) :: t_target                 !! target time [s]
      real(dp), allocatable, intent(out) :: jac(:, :)  !! not allocated
      type(error_t), allocatable, intent(out) :: err   !! always set
      allocate(err)
      err%message = "gapbeam_integrator: method '" // self%method // "' gives no exact " &
         // "Jacobian of its flow (use &continuation jacobian = 'finite_difference')"
   end subroutine advance_jacobian_none
   ! --- end of the continuation hook

   !> The state at time t from a displacement and a velocity: massless dofs (lumped mass
   !> without rotary inertia) put in equilibrium with the others, contact forces from the
   !> laws, acceleration in equilibrium, no step history.
   subroutine start_state(model, t, u, v, state)
      type(model_t), intent(in) :: model        !! model
      real(dp), intent(in) :: t                 !! time [s]
      real(dp), intent(in) :: u(:), v(:)        !! displacement, velocity
      type(state_t), intent(out) :: state       !! the state
      real(dp), allocatable :: pr(:)
      real(dp) :: d, n(2), tg(2), tau, gt
      integer :: r
      state%t = t
      state%u = u;  state%v = v
      call massless_equilibrium(model, state%u, state%v)
      allocate(state%a(model%n), state%f(model%n_contacts))
      call contact_forces_at(model, state%u, state%v, state%f)
      ! rings: open with the anchor at the node, then the regime the state calls for (a ring
      ! in contact sticks at its contact point, or slips at once along its tangential
      ! velocity, as at a located onset: onset_regime)
      allocate(state%fn(model%n_rings), state%ft(model%n_rings), state%sigma(model%n_rings), &
               state%anchor(model%n_rings), source=0.0_dp)
      allocate(state%mode(model%n_rings), source=ring_open)
      state%sigma = 1.0_dp
      do r = 1, model%n_rings
         call ring_geometry(model, r, ring_xy(model, r, state%u), d, n, tg, tau, gt)
         state%anchor(r) = tau
      end do
      call update_ring_modes(model, state%u, state%v, spread(0.0_dp, 1, model%n), state%mode, &
                             state%sigma, state%anchor, 0)
      do r = 1, model%n_rings
         if (state%mode(r) /= ring_open) call onset_regime(model, r, ring_xy(model, r, state%u), &
            ring_xy(model, r, state%v), state%mode(r), state%sigma(r), state%anchor(r))
      end do
      pr = ring_load(model, state)
      call equilibrium_acceleration(model, t, state%u, state%v, state%f, state%a, pr)
      state%f_prev = state%f
      state%dt_prev = 0.0_dp
      state%level = 0;  state%comfortable = 0
   end subroutine start_state

   !> Contact force magnitudes from the laws at (u, v).
   pure subroutine contact_forces_at(model, u, v, f)
      type(model_t), intent(in) :: model        !! model
      real(dp), intent(in) :: u(:), v(:)        !! state
      real(dp), intent(out) :: f(:)             !! contact force magnitudes [N]
      integer :: c, i
      do c = 1, model%n_contacts
         i = model%c_dof(c)
         f(c) = contact_force(model, c, model%c_sign(c) * u(i) - model%c_gap(c), &
                              model%c_sign(c) * v(i))
      end do
   end subroutine contact_forces_at

   !> Put massless dofs (lumped mass without rotary inertia) in static equilibrium with the
   !> others: K_ss u_s = -K_sr u_r, and the same for the velocity. The initial state of such
   !> dofs is not free; without this the first step would jump. (K_ss is a diagonal block of
   !> the positive definite K, hence positive definite.)
   subroutine massless_equilibrium(model, u, v)
      type(model_t), intent(in) :: model       !! model
      real(dp), intent(inout) :: u(:), v(:)    !! state, massless entries replaced
      integer, allocatable :: s(:), r(:)
      real(dp), allocatable :: kss(:, :), b(:, :)
      integer :: i, ns, info
      s = pack([(i, i = 1, model%n)], [(model%sys%m(i, i) == 0.0_dp, i = 1, model%n)])
      r = pack([(i, i = 1, model%n)], [(model%sys%m(i, i) /= 0.0_dp, i = 1, model%n)])
      ns = size(s)
      if (ns == 0) return
      kss = model%sys%k(s, s)
      allocate(b(ns, 2))
      b(:, 1) = -matmul(model%sys%k(s, r), u(r))
      b(:, 2) = -matmul(model%sys%k(s, r), v(r))
      call dpotrf('U', ns, kss, ns, info)
      if (info /= 0) error stop 'gapbeam_integrator:massless_equilibrium: K_ss not positive ' &
         // 'definite (the stiffness of a validated model is)'
      call dpotrs('U', ns, 2, kss, ns, b, ns, info)
      u(s) = b(:, 1);  v(s) = b(:, 2)
   end subroutine massless_equilibrium

   !> The force of the rings on the structure at a state (their forces from the laws in the
   !> state's regimes; fn and ft of the state are set), as a load vector (size n).
   function ring_load(model, state) result(pr)
      type(model_t), intent(in) :: model        !! model
      type(state_t), intent(inout) :: state     !! state (fn, ft set)
      real(dp), allocatable :: pr(:)
      allocate(pr(model%n), source=0.0_dp)
      if (model%n_rings == 0) return
      call ring_forces_at(model, state%u, state%v, state%mode, state%sigma, state%anchor, &
                          state%fn, state%ft, pr)
   end function ring_load

   !> Acceleration in equilibrium with (t, u, v) and given contact forces f:
   !> M a = s(t) q + (extra loads) - C v - K u - F_c + P_rings. Massless dofs get a = 0.
   subroutine equilibrium_acceleration(model, t, u, v, f, a, pr)
      type(model_t), intent(in) :: model        !! model
      real(dp), intent(in) :: t                 !! time [s]
      real(dp), intent(in) :: u(:), v(:)        !! state
      real(dp), intent(in) :: f(:)              !! contact force magnitudes [N]
      real(dp), intent(out) :: a(:)             !! acceleration
      real(dp), intent(in), optional :: pr(:)   !! force of the rings on the structure [N]
      real(dp), allocatable :: rhs(:), msub(:, :), b(:)
      integer, allocatable :: idx(:)
      integer :: c, i, info, nm
      rhs = load_factor(model, t) * model%q - matmul(model%c, v) - matmul(model%sys%k, u)
      call add_extra_load(model, t, rhs)
      if (present(pr)) rhs = rhs + pr
      do c = 1, model%n_contacts
         i = model%c_dof(c)
         rhs(i) = rhs(i) - model%c_sign(c) * f(c)
      end do
      a = 0.0_dp
      idx = pack([(i, i = 1, model%n)], [(model%sys%m(i, i) > 0.0_dp, i = 1, model%n)])
      nm = size(idx)
      if (nm == 0) return
      msub = model%sys%m(idx, idx)
      b = rhs(idx)
      call dpotrf('U', nm, msub, nm, info)
      if (info /= 0) error stop 'gapbeam_integrator:equilibrium_acceleration: the mass of the ' &
         // 'dofs with mass is not positive definite'
      call dpotrs('U', nm, 1, msub, nm, b, nm, info)
      a(idx) = b
   end subroutine equilibrium_acceleration

   !> 'dof 5 (node 3 w)' style label of a global dof.
   function dof_label(model, i) result(s)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: i             !! global dof
      character(len=:), allocatable :: s
      integer :: node, d
      s = 'dof ' // str(i)
      if (.not. allocated(model%sys%dof_of)) return
      do node = 1, model%sys%n_node
         do d = 1, size(model%sys%dof_of, 1)
            if (model%sys%dof_of(d, node) == i) s = 'dof ' // str(i) // ' (node ' // str(node) &
               // ' ' // dof_name(d) // ')'
         end do
      end do
   end function dof_label

   !> Add a method (its capabilities and, for a one-step method, its stepper); a method of
   !> the same name is replaced.
   subroutine registry_add(self, caps, proto)
      class(method_registry_t), intent(inout) :: self      !! registry
      type(method_caps_t), intent(in) :: caps              !! what it can do
      class(stepper_t), intent(in), optional :: proto      !! its stepper (one-step method)
      type(method_entry_t), allocatable :: more(:)
      integer :: j, n
      if (.not. allocated(self%entries)) allocate(self%entries(0))
      j = self%find(caps%name)
      if (j == 0) then
         n = size(self%entries)
         allocate(more(n + 1))
         do j = 1, n
            more(j)%caps = self%entries(j)%caps
            if (allocated(self%entries(j)%proto)) call move_alloc(self%entries(j)%proto, &
                                                                  more(j)%proto)
         end do
         call move_alloc(more, self%entries)
         j = n + 1
      end if
      self%entries(j)%caps = caps
      if (allocated(self%entries(j)%proto)) deallocate(self%entries(j)%proto)
      if (present(proto)) allocate(self%entries(j)%proto, source=proto)
   end subroutine registry_add

   !> The capabilities of every method of the registry, in order.
   function registry_table(self) result(t)
      class(method_registry_t), intent(in) :: self         !! registry
      type(method_caps_t), allocatable :: t(:)
      integer :: j
      allocate(t(0))
      if (allocated(self%entries)) t = [(self%entries(j)%caps, j = 1, size(self%entries))]
   end function registry_table

   !> Index of method `name` in the registry (0: none).
   integer function registry_find(self, name) result(j)
      class(method_registry_t), intent(in) :: self         !! registry
      character(len=*), intent(in) :: name                 !! method word
      if (allocated(self%entries)) then
         do j = 1, size(self%entries)
            if (trim(self%entries(j)%caps%name) == trim(name)) return
         end do
      end if
      j = 0
   end function registry_find
end module gapbeam_integrator
