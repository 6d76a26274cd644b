!> Progress of a long computation as the computation sees it: a monitor it tells how far it
!> has got. Analyses take an optional `class(monitor_t)` and call `update` now and then (every
!> so many accepted steps, after each forcing period); what a monitor does with that (print a
!> line on standard error, gapbeam_progress_meter) is not their business. An analysis with no
!> monitor runs exactly as before.
!>
!> Monitors are for serial runs: nothing inside an OpenMP parallel region gets one (sweeps
!> report between their parallel chunks).
module gapbeam_progress
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: monitor_t

   !> Told how far a computation has got.
   type, abstract :: monitor_t
   contains
      procedure(update_interface), deferred :: update   !! work done so far
   end type monitor_t

   abstract interface
      !> The computation has done `done` units of its work (forcing periods, points), and is
      !> at simulated time `t` with step `dt` when it integrates.
      subroutine update_interface(self, done, t, dt)
         import :: monitor_t, dp
         class(monitor_t), intent(inout) :: self         !! monitor
         real(dp), intent(in) :: done                    !! work done [its units]
         real(dp), intent(in), optional :: t             !! simulated time [s]
         real(dp), intent(in), optional :: dt            !! current step size [s]
      end subroutine update_interface
   end interface
end module gapbeam_progress
