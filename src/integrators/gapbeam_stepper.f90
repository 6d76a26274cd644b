!> The interface every time integrator implements: prepare for a step size, then advance one
!> step. The transient driver (gapbeam_transient) owns everything else: the power-of-two
!> step-size levels and their cached steppers, contact-event location, sampling, impact
!> statistics, divergence checks. Adding a method is one module that extends `stepper_t`,
!> plus its word in gapbeam_integrators.
module gapbeam_stepper
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_problem, only: problem_t
   use gapbeam_settings, only: solver_settings_t
   implicit none
   private
   public :: stepper_t

   !> One integrator at one step size.
   type, abstract :: stepper_t
      real(dp) :: dt = 0.0_dp                 !! step size it is prepared for [s]
      logical :: ready = .false.              !! prepared
      integer(int64) :: iterations = 0        !! inner iterations spent (e.g. fixed point)
      integer(int64) :: evaluations = 0       !! right-hand-side evaluations (explicit methods)
   contains
      procedure(prepare_interface), deferred :: prepare   !! factorize / precompute for dt
      procedure(step_interface), deferred :: step         !! advance one step of size dt
   end type stepper_t

   abstract interface
      !> Prepare the stepper for steps of size dt.
      subroutine prepare_interface(self, prob, cfg, dt, err)
         import :: stepper_t, problem_t, solver_settings_t, dp, error_t
         class(stepper_t), intent(inout) :: self          !! stepper
         type(problem_t), intent(in) :: prob              !! model
         type(solver_settings_t), intent(in) :: cfg       !! settings
         real(dp), intent(in) :: dt                       !! step size [s]
         type(error_t), allocatable, intent(out) :: err   !! factorization failure
      end subroutine prepare_interface

      !> Advance from (t0, u, v, a, f) to t0 + dt.
      !> `ok` false asks the driver to halve the step (an iteration did not converge);
      !> `ratio` is an embedded local-error estimate relative to its tolerance (> 1: reject),
      !> or a negative number when the method has none. `open_contact` > 0 holds that contact
      !> open (the step ends at its located onset: the left limit).
      subroutine step_interface(self, prob, t0, u, v, a, f, f_prev, dt_prev, u1, v1, a1, f1, &
                                ok, ratio, open_contact)
         import :: stepper_t, problem_t, dp
         class(stepper_t), intent(inout) :: self          !! stepper
         type(problem_t), intent(in) :: prob              !! model
         real(dp), intent(in) :: t0                       !! start time [s]
         real(dp), intent(in), contiguous :: u(:), v(:), a(:)   !! state at t0
         real(dp), intent(in), contiguous :: f(:)         !! contact forces at t0 [N]
         real(dp), intent(in), contiguous :: f_prev(:)    !! contact forces one step earlier [N]
         real(dp), intent(in) :: dt_prev                  !! length of that step [s]
         real(dp), intent(out), contiguous :: u1(:), v1(:), a1(:)   !! state at t0 + dt
         real(dp), intent(out), contiguous :: f1(:)       !! contact forces at t0 + dt [N]
         logical, intent(out) :: ok                       !! step succeeded
         real(dp), intent(out) :: ratio                   !! embedded error / tolerance, or < 0
         integer, intent(in) :: open_contact              !! contact held open (0: none)
      end subroutine step_interface
   end interface
end module gapbeam_stepper
