!> The registry of time integrators: the word a deck gives in &solver method and the type that
!> implements it. A submodule of gapbeam_integrator, so that analyses depend on the interface
!> only. Adding a one-step method: one module extending stepper_t and one case in
!> make_stepper; adding an integrator of another kind: one module extending integrator_t and
!> one case in make_integrator.
submodule (gapbeam_integrator) gapbeam_integrator_registry
   use gapbeam_error, only: fatal_error
   use gapbeam_newmark, only: newmark_stepper_t
   use gapbeam_alpha, only: alpha_stepper_t
   use gapbeam_explicit, only: central_difference_t, runge_kutta_t
   use gapbeam_stepping, only: stepping_integrator_t
   use gapbeam_exact, only: exact_integrator_t
   implicit none

contains

   !> An integrator of the settings' method, initialised for the model.
   module subroutine make_integrator(model, cfg, integ, err)
      type(model_t), intent(in) :: model                      !! model
      type(solver_settings_t), intent(in) :: cfg              !! method and settings
      class(integrator_t), allocatable, intent(out) :: integ  !! ready to advance
      type(error_t), allocatable, intent(out) :: err          !! unknown method, set-up
      type(solver_settings_t) :: eff
      character(len=:), allocatable :: reason
      call resolve_method(model, cfg, eff, reason)
      ! what the exact integrator (and continuation through it) and the stepping methods do
      ! not handle is refused here, where the method is resolved, with the method to use
      reason_refused: block
         character(len=:), allocatable :: why
         why = tube_refusal(model, eff%method, eff%step_control, eff%stop_solution)
         if (len(why) > 0) then
            call fatal_error(err, 'gapbeam_integrator: ' // why)
            return
         end if
      end block reason_refused
      select case (eff%method)
      case ('exact')
         allocate(exact_integrator_t :: integ)
      case default
         allocate(stepping_integrator_t :: integ)
      end select
      call integ%init(model, eff, err)
      integ%reason = reason
   end subroutine make_integrator

   !> An unprepared stepper of a one-step method word.
   module subroutine make_stepper(method, proto, err)
      character(len=*), intent(in) :: method                  !! method word
      class(stepper_t), allocatable, intent(out) :: proto     !! the method's stepper
      type(error_t), allocatable, intent(out) :: err          !! not a one-step method
      select case (method)
      case ('newmark')
         allocate(newmark_stepper_t :: proto)
      case ('hht', 'generalized_alpha')
         allocate(alpha_stepper_t :: proto)
      case ('central_difference')
         allocate(central_difference_t :: proto)
      case ('rk4', 'rk45')
         allocate(runge_kutta_t :: proto)
      case default
         call fatal_error(err, "gapbeam_integrator:make_stepper: method '" // trim(method) &
            // "' is not a one-step method")
      end select
   end subroutine make_stepper
end submodule gapbeam_integrator_registry
