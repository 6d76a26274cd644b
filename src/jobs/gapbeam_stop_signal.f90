!> SIGTERM as a request to stop cleanly. A batch system sends it at a job's time limit, on
!> preemption and on `scancel`; a sweep that catches it stops after the chunk in progress as at
!> its time limit (checkpoint kept, exit status 3, lock released).
!>
!> The handler only counts the signal and puts the default action back, so a second SIGTERM
!> ends the process at once (as SIGKILL would: the checkpoint keeps the chunks before). Linux
!> signal number 15.
!>
!> And SIGXFSZ ignored (`ignore_file_size_signal`), so that a write beyond the file size limit
!> fails and is reported instead of killing the process.
module gapbeam_stop_signal
   use, intrinsic :: iso_c_binding, only: c_int, c_funptr, c_funloc, c_null_funptr, c_intptr_t
   implicit none
   private
   public :: catch_stop_signal, stop_requested, ignore_file_size_signal

   integer(c_int), parameter :: sigterm = 15
   integer(c_int), volatile, save :: n_received = 0     ! SIGTERMs received

   interface
      !> C `signal` from <signal.h>: the previous handler.
      function c_signal(signum, handler) bind(c, name='signal') result(previous)
         import :: c_int, c_funptr
         integer(c_int), value, intent(in) :: signum         !! signal number
         type(c_funptr), value, intent(in) :: handler        !! new handler (SIG_DFL: null, SIG_IGN: 1)
         type(c_funptr) :: previous
      end function c_signal
   end interface

contains

   !> From now on, a SIGTERM sets `stop_requested` instead of ending the process.
   subroutine catch_stop_signal()
      type(c_funptr) :: previous
      previous = c_signal(sigterm, c_funloc(on_stop_signal))
   end subroutine catch_stop_signal

   !> Whether a SIGTERM has come.
   logical function stop_requested()
      stop_requested = n_received > 0
   end function stop_requested

   !> The handler: count, and let the next SIGTERM end the process.
   subroutine on_stop_signal(signum) bind(c)
      integer(c_int), value, intent(in) :: signum          !! the signal (SIGTERM)
      type(c_funptr) :: previous
      n_received = n_received + 1
      previous = c_signal(signum, c_null_funptr)
   end subroutine on_stop_signal

   !> Ignore SIGXFSZ, so that a write beyond the file size limit (`ulimit -f`) fails with
   !> EFBIG, which the writers report like a full disk, instead of killing the program (the
   !> Fortran runtime would print a backtrace). Linux signal number 25.
   subroutine ignore_file_size_signal()
      integer(c_int), parameter :: sigxfsz = 25
      integer(c_intptr_t), parameter :: sig_ign = 1
      type(c_funptr) :: previous
      previous = c_signal(sigxfsz, transfer(sig_ign, previous))
   end subroutine ignore_file_size_signal
end module gapbeam_stop_signal
