!> CPU and wall clocks.
!>
!> A run reports the CPU time of the thread that ran it (CLOCK_THREAD_CPUTIME_ID): in an
!> OpenMP sweep every point runs on one thread, and BLAS is kept serial
!> (gapbeam_blas_threads), so this is the work the point cost, whatever the other threads do.
!> A whole job reports the process's CPU time (all threads) beside its wall time.
module gapbeam_clock
   use, intrinsic :: iso_c_binding, only: c_int, c_long, c_int64_t
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: thread_cpu_seconds, process_cpu_seconds, wall_seconds

   !> struct timespec of Linux (64-bit time_t and long)
   type, bind(c) :: timespec_t
      integer(c_int64_t) :: tv_sec
      integer(c_long) :: tv_nsec
   end type timespec_t

   integer(c_int), parameter :: clock_process_cputime_id = 2
   integer(c_int), parameter :: clock_thread_cputime_id = 3

   interface
      function c_clock_gettime(clock_id, tp) bind(c, name='clock_gettime') result(rc)
         import :: c_int, timespec_t
         integer(c_int), value, intent(in) :: clock_id
         type(timespec_t), intent(out) :: tp
         integer(c_int) :: rc
      end function c_clock_gettime
   end interface

contains

   !> CPU time of the calling thread [s] (the process's where the thread clock is missing).
   real(dp) function thread_cpu_seconds() result(s)
      s = clock_seconds(clock_thread_cputime_id)
   end function thread_cpu_seconds

   !> CPU time of the process, all threads together [s].
   real(dp) function process_cpu_seconds() result(s)
      s = clock_seconds(clock_process_cputime_id)
   end function process_cpu_seconds

   !> Wall time from an arbitrary origin [s].
   real(dp) function wall_seconds() result(s)
      integer(kind=8) :: count, rate
      call system_clock(count, rate)
      s = real(count, dp) / real(rate, dp)
   end function wall_seconds

   real(dp) function clock_seconds(id) result(s)
      integer(c_int), intent(in) :: id
      type(timespec_t) :: tp
      real :: t
      if (c_clock_gettime(id, tp) == 0) then
         s = real(tp%tv_sec, dp) + 1.0e-9_dp * real(tp%tv_nsec, dp)
      else
         call cpu_time(t)
         s = real(t, dp)
      end if
   end function clock_seconds

end module gapbeam_clock
