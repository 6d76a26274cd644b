!> The registry of time integrators: the word a deck gives in &solver method, and the stepper
!> that implements it. Adding a method: one module extending stepper_t, one case here.
module gapbeam_integrators
   use gapbeam_error, only: error_t, fatal_error
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_stepper, only: stepper_t
   use gapbeam_newmark, only: newmark_stepper_t
   use gapbeam_alpha, only: alpha_stepper_t
   use gapbeam_explicit, only: central_difference_t, runge_kutta_t
   implicit none
   private
   public :: make_stepper

contains

   !> An unprepared stepper of the deck's method (the driver prepares one per step size).
   subroutine make_stepper(cfg, proto, err)
      type(solver_settings_t), intent(in) :: cfg                 !! settings
      class(stepper_t), allocatable, intent(out) :: proto        !! the method's stepper
      type(error_t), allocatable, intent(out) :: err             !! unknown method
      select case (cfg%method)
      case ('newmark')
         allocate(newmark_stepper_t :: proto)
      case ('hht', 'generalized_alpha')
         allocate(alpha_stepper_t :: proto)
      case ('central_difference')
         allocate(central_difference_t :: proto)
      case ('rk4', 'rk45')
         allocate(runge_kutta_t :: proto)
      case default
         call fatal_error(err, "gapbeam_integrators:make_stepper: method '" // trim(cfg%method) &
            // "' has no stepper")
      end select
   end subroutine make_stepper
end module gapbeam_integrators
