!> The registry of time integrators: each method of core/gapbeam_capabilities' method_table
!> bound to the type that implements its family. A submodule of gapbeam_integrator, so that
!> analyses depend on the interface only.
!>
!> Adding a method of an existing family (a Newmark variant with preset parameters) is one
!> line in method_table; adding one with a new implementation is one module (extending
!> stepper_t, or integrator_t for a method that is not one step at a time) and one case in
!> `family_stepper` (a family of one-step methods) or `make_integrator`. A caller may also add
!> a method of its own to a registry value (`method_registry_t%add`, a test's) and pass that
!> registry to make_integrator: nothing here changes.
submodule (gapbeam_integrator) gapbeam_integrator_registry
   use gapbeam_error, only: fatal_error
   use gapbeam_capabilities, only: method_word_list
   use gapbeam_newmark, only: newmark_stepper_t
   use gapbeam_alpha, only: alpha_stepper_t
   use gapbeam_explicit, only: central_difference_t, runge_kutta_t
   use gapbeam_stepping, only: stepping_integrator_t
   use gapbeam_exact, only: exact_integrator_t
   use gapbeam_exponential, only: exponential_t
   implicit none

contains

   !> The built-in methods: every line of method_table() with its implementation.
   module function method_registry() result(reg)
      type(method_registry_t) :: reg                          !! registry
      type(method_caps_t), allocatable :: t(:)
      class(stepper_t), allocatable :: proto
      integer :: j
      t = method_table()
      allocate(reg%entries(0))
      do j = 1, size(t)
         call family_stepper(t(j), proto)
         if (allocated(proto)) then
            call reg%add(t(j), proto)
            deallocate(proto)
         else
            call reg%add(t(j))
         end if
      end do
   end function method_registry

   !> The stepper of a one-step method's family (not allocated: not a one-step method).
   subroutine family_stepper(caps, proto)
      type(method_caps_t), intent(in) :: caps                 !! the method
      class(stepper_t), allocatable, intent(out) :: proto     !! its stepper
      select case (caps%family)
      case ('newmark')
         allocate(proto, source=newmark_stepper_t())
      case ('alpha')
         allocate(proto, source=alpha_stepper_t(hht=caps%name == 'hht'))
      case ('central_difference')
         allocate(proto, source=central_difference_t())
      case ('runge_kutta')
         allocate(proto, source=runge_kutta_t(embedded=caps%estimator == 'embedded'))
      case ('exponential')
         allocate(proto, source=exponential_t())
      case ('exact')
      case default
         error stop 'gapbeam_integrator_registry: method_table has a family without an ' &
            // 'implementation'
      end select
   end subroutine family_stepper

   !> An integrator of the settings' method, initialised for the model.
   module subroutine make_integrator(model, cfg, integ, err, registry)
      type(model_t), intent(in) :: model                      !! model
      type(solver_settings_t), intent(in) :: cfg              !! method and settings
      class(integrator_t), allocatable, intent(out) :: integ  !! ready to advance
      type(error_t), allocatable, intent(out) :: err          !! unknown method, set-up
      type(method_registry_t), intent(in), optional :: registry   !! methods
      type(method_registry_t) :: reg
      type(solver_settings_t) :: eff
      character(len=:), allocatable :: reason, why
      integer :: j
      if (present(registry)) then
         reg = registry
      else
         reg = method_registry()
      end if
      call resolve_method(model, cfg, eff, reason, reg%table())
      j = reg%find(eff%method)
      if (j == 0) then
         call fatal_error(err, "gapbeam_integrator: unknown method '" // trim(eff%method) &
            // "' (allowed: " // method_word_list(reg%table()) // ')')
         return
      end if
      ! what the method cannot integrate is refused here, where the method is resolved, with
      ! the method to use
      why = refusal(model, eff, reg%table())
      if (len(why) > 0) then
         call fatal_error(err, 'gapbeam_integrator: ' // why)
         return
      end if
      associate (e => reg%entries(j))
         if (allocated(e%proto)) then
            allocate(stepping_integrator_t :: integ)
            select type (integ)
            type is (stepping_integrator_t)
               allocate(integ%proto, source=e%proto)
            end select
         else if (e%caps%exact) then
            allocate(exact_integrator_t :: integ)
         else
            call fatal_error(err, "gapbeam_integrator: method '" // trim(eff%method) // "' " &
               // 'has no implementation in the registry')
            return
         end if
         integ%caps = e%caps
      end associate
      call integ%init(model, eff, err)
      integ%reason = reason
   end subroutine make_integrator

   !> An unprepared stepper of a one-step method word.
   module subroutine make_stepper(method, proto, err, registry)
      character(len=*), intent(in) :: method                  !! method word
      class(stepper_t), allocatable, intent(out) :: proto     !! the method's stepper
      type(error_t), allocatable, intent(out) :: err          !! not a one-step method
      type(method_registry_t), intent(in), optional :: registry   !! methods
      type(method_registry_t) :: reg
      integer :: j
      if (present(registry)) then
         reg = registry
      else
         reg = method_registry()
      end if
      j = reg%find(method)
      if (j > 0) then
         if (allocated(reg%entries(j)%proto)) then
            allocate(proto, source=reg%entries(j)%proto)
            return
         end if
      end if
      call fatal_error(err, "gapbeam_integrator:make_stepper: method '" // trim(method) &
         // "' is not a one-step method")
   end subroutine make_stepper
end submodule gapbeam_integrator_registry
