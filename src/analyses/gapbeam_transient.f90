!> A transient run with any method: the deck's integrator advances the model from the initial
!> state over the transient and recorded forcing periods while the recorder watches.
!>
!> Progress: with a monitor (gapbeam_progress), the recorder is wrapped in a watcher that tells
!> the monitor every `watch_every` pieces how many forcing periods are done, the time and the
!> step; without one the plain recorder runs, exactly as before.
module gapbeam_transient
   use, intrinsic :: iso_fortran_env, only: int64, int8
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_integrator, only: integrator_t, make_integrator, start_state, resolve_method, &
      refusal
   use gapbeam_recorder, only: recorder_t
   use gapbeam_observer, only: piece_t
   use gapbeam_progress, only: monitor_t
   use gapbeam_clock, only: thread_cpu_seconds, wall_seconds
   implicit none
   private
   public :: integrate, integrator_cache_t

   !> Capacity of an integrator cache (distinct settings of one point: the run, the exponent,
   !> the accuracy check's two).
   integer, parameter :: cache_capacity = 8

   !> One cached integrator and the settings it was built for.
   type :: cached_integrator_t
      integer(int8), allocatable :: key(:)             !! the settings, the horizon aside
      class(integrator_t), allocatable :: integ        !! built for them
   end type cached_integrator_t

   !> Integrators built for ONE model and reused by all its runs (the records of a run and
   !> its extensions, the exponent's pair, the certificate's checks, further starts): one per
   !> distinct solver settings, the horizon (transient and record periods) aside. Nothing is
   !> rebuilt for an extension: factorisations, modal decompositions and contact
   !> configurations stay. A pointer from `get` is valid until the cache goes.
   type :: integrator_cache_t
      type(cached_integrator_t), allocatable :: entries(:)   !! capacity cache_capacity
      integer :: n = 0                                       !! entries in use
      integer :: next = 1                                    !! the one replaced when full
   contains
      procedure :: get => cache_get                          !! the integrator of settings
   end type integrator_cache_t

   !> Accepted pieces between two progress updates (a clock read each: negligible).
   integer, parameter :: watch_every = 64

   !> The recorder, telling a monitor how far the run has got.
   type, extends(recorder_t) :: watched_recorder_t
      class(monitor_t), pointer :: monitor => null()   !! told the periods done
      integer :: pieces = 0                            !! pieces seen
   contains
      procedure :: observe => watched_observe
   end type watched_recorder_t

contains

   !> The integrator of `cfg` for `model`: the cached one built for the same settings (the
   !> horizon aside), else one built now (make_integrator) and kept.
   subroutine cache_get(self, model, cfg, integ, err)
      class(integrator_cache_t), intent(inout), target :: self   !! cache (one model)
      type(model_t), intent(in) :: model                         !! the model
      type(solver_settings_t), intent(in) :: cfg                 !! settings
      class(integrator_t), pointer, intent(out) :: integ         !! its integrator
      type(error_t), allocatable, intent(out) :: err             !! set-up failure
      type(solver_settings_t) :: key_cfg
      integer(int8), allocatable :: key(:)
      integer :: j
      integ => null()
      key_cfg = cfg
      key_cfg%transient_periods = 0;  key_cfg%record_periods = 0
      key = transfer(key_cfg, [0_int8])
      if (.not. allocated(self%entries)) allocate(self%entries(cache_capacity))
      do j = 1, self%n
         if (size(self%entries(j)%key) /= size(key)) cycle
         if (all(self%entries(j)%key == key)) then
            integ => self%entries(j)%integ
            return
         end if
      end do
      if (self%n < cache_capacity) then
         self%n = self%n + 1;  j = self%n
      else
         j = self%next;  self%next = mod(self%next, cache_capacity) + 1
         deallocate(self%entries(j)%integ)
      end if
      call make_integrator(model, cfg, self%entries(j)%integ, err)
      if (allocated(err)) then
         if (allocated(self%entries(j)%integ)) deallocate(self%entries(j)%integ)
         self%entries(j)%key = [integer(int8) ::]
         return
      end if
      self%entries(j)%key = key
      integ => self%entries(j)%integ
   end subroutine cache_get

   !> Record the piece, and every `watch_every` pieces tell the monitor where the run is.
   subroutine watched_observe(self, piece)
      class(watched_recorder_t), intent(inout) :: self   !! recorder with a monitor
      class(piece_t), intent(in) :: piece                 !! the piece
      call self%recorder_t%observe(piece)
      self%pieces = self%pieces + 1
      if (mod(self%pieces, watch_every) == 0) &
         call self%monitor%update(piece%tb / self%period, piece%tb, piece%tb - piece%ta)
   end subroutine watched_observe

   !> Integrate from (u0, v0) at t = 0 over the settings' transient and recorded periods, with
   !> the settings' method (the integrator of `cache` for those settings when a cache of this
   !> model is given), or with `integrator` when given (an integrator of a chosen type with
   !> options set, initialised here). A `monitor` is told the forcing periods done as the run
   !> goes (see the module header).
   subroutine integrate(model, cfg, out, u0, v0, res, err, integrator, monitor, cache)
      type(model_t), intent(in) :: model               !! model
      type(solver_settings_t), intent(in) :: cfg       !! method and settings
      type(output_settings_t), intent(in) :: out       !! what to record
      real(dp), intent(in) :: u0(:), v0(:)             !! initial state relative to the base
      type(transient_result_t), intent(out) :: res     !! results
      type(error_t), allocatable, intent(out) :: err   !! numerical failure
      class(integrator_t), intent(inout), optional :: integrator   !! the integrator to use
      class(monitor_t), intent(inout), optional, target :: monitor !! told the progress
      type(integrator_cache_t), intent(inout), optional :: cache   !! this model's integrators
      class(integrator_t), allocatable :: integ
      class(integrator_t), pointer :: cached
      type(solver_settings_t) :: eff
      character(len=:), allocatable :: reason, why
      real(dp) :: cpu0, wall0
      cpu0 = thread_cpu_seconds();  wall0 = wall_seconds()
      if (present(cache) .and. .not. present(integrator)) then
         call cache%get(model, cfg, cached, err)
         if (allocated(err)) return
         call cached%reset_counters()
         call record(model, cfg, out, u0, v0, cached, res, err, monitor)
      else if (present(integrator)) then
         call resolve_method(model, cfg, eff, reason)
         why = refusal(model, eff)
         if (len(why) > 0) then
            call fatal_error(err, 'gapbeam_integrator: ' // why)
            return
         end if
         call integrator%init(model, eff, err)
         if (allocated(err)) return
         integrator%reason = reason
         call record(model, cfg, out, u0, v0, integrator, res, err, monitor)
      else
         call make_integrator(model, cfg, integ, err)
         if (allocated(err)) return
         call record(model, cfg, out, u0, v0, integ, res, err, monitor)
      end if
      if (allocated(err)) return
      res%cpu_seconds = thread_cpu_seconds() - cpu0
      res%wall_seconds = wall_seconds() - wall0
   end subroutine integrate

   !> Advance from (u0, v0) at t = 0 with an initialised integrator while a recorder watches
   !> (a watched recorder when a monitor is given).
   subroutine record(model, cfg, out, u0, v0, integ, res, err, monitor)
      type(model_t), intent(in) :: model               !! model
      type(solver_settings_t), intent(in) :: cfg       !! horizon
      type(output_settings_t), intent(in) :: out       !! what to record
      real(dp), intent(in) :: u0(:), v0(:)             !! initial state relative to the base
      class(integrator_t), intent(inout) :: integ      !! integrator
      type(transient_result_t), intent(out) :: res     !! results
      type(error_t), allocatable, intent(out) :: err   !! numerical failure
      class(monitor_t), intent(inout), optional, target :: monitor !! told the progress
      class(recorder_t), allocatable :: rec
      type(state_t) :: state
      real(dp) :: period
      if (present(monitor)) then
         allocate(watched_recorder_t :: rec)
         select type (rec)
         type is (watched_recorder_t)
            rec%monitor => monitor
         end select
      else
         allocate(recorder_t :: rec)
      end if
      call rec%init(model, out, cfg%transient_periods, cfg%record_periods, err)
      if (allocated(err)) return
      call start_state(model, 0.0_dp, u0, v0, state)
      period = 2.0_dp * pi / model%omega
      call integ%advance(state, real(cfg%transient_periods + cfg%record_periods, dp) * period, &
                         rec, err)
      if (allocated(err)) return
      call rec%finish(res)
      res%steps_accepted = integ%steps_accepted
      res%steps_rejected = integ%steps_rejected
      res%events = integ%events
      res%factorizations = integ%factorizations
      res%fp_iterations = integ%fp_iterations
      res%dt_smallest = integ%dt_smallest
      res%dt_largest = integ%dt_largest
      if (res%dt_smallest > res%dt_largest) res%dt_smallest = 0.0_dp
      res%u = state%u;  res%v = state%v;  res%a = state%a
      res%t_end = state%t
      res%method = integ%method
      res%method_reason = "method '" // integ%method // "' as asked"
      if (allocated(integ%reason)) res%method_reason = integ%reason
   end subroutine record
end module gapbeam_transient
