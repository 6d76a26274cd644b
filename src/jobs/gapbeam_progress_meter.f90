!> Progress lines on standard error that people can read:
!>
!>    transient: 37.5 % (487/1300 periods), 12.3 periods/s, 0:00:39 left; t = 45.6 s, dt = 1.2E-05 s
!>    sweep: 50.0 % (256/512 points), 13.9 points/s, 0:00:18 left
!>
!> A meter is a monitor (gapbeam_progress): the computation calls `update` as often as it
!> likes and the meter prints only when `interval` seconds of wall time have passed since its
!> last line (and not before `interval` seconds from the start, so a short run prints nothing).
!> When standard error is a terminal the line is rewritten in place (carriage return) every
!> `interval` (default 1 s); otherwise, in a batch log, one whole line per interval (default
!> 10 s). `finish` closes the meter with a last line at 100 % when it printed anything.
!> A disabled meter (--quiet) prints nothing and costs one test per update.
!>
!> Rate and time left count the work done since `start` (a resumed sweep's earlier points
!> are not in the rate); the time left is the work left over that rate, as h:mm:ss.
!>
!> **A long run is announced**, --quiet or not: once `estimate_after_s` (2 s) of wall time
!> have passed, the meter estimates the time left from the rate so far; when it exceeds
!> `long_run_s` (1 h) it prints one warning line on standard error (kept in `warning`, which
!> the job stores in /run/warnings), e.g.
!>    gapbeam: warning: this transient run will take about 5:12:40 more (h:mm:ss, from 14.2
!>    periods/s over its first 2 s; 1 of 265000 periods done): ...
!> A run shorter than `estimate_after_s` is never estimated.
module gapbeam_progress_meter
   use, intrinsic :: iso_fortran_env, only: error_unit
   use, intrinsic :: iso_c_binding, only: c_int
   use gapbeam_kinds, only: dp
   use gapbeam_progress, only: monitor_t
   use gapbeam_clock, only: wall_seconds
   implicit none
   private
   public :: meter_t, progress_line, hms

   !> A progress meter on standard error.
   type, extends(monitor_t) :: meter_t
      character(len=:), allocatable :: what           !! what progresses ('sweep', 'transient')
      character(len=:), allocatable :: unit_name      !! units of the work ('points', 'periods')
      real(dp) :: total = 0.0_dp                      !! work of the whole computation
      real(dp) :: offset = 0.0_dp                     !! added to every `done` (later phases)
      real(dp) :: done_at_start = 0.0_dp              !! work already done at `start`
      real(dp) :: done = 0.0_dp                       !! work done so far
      real(dp) :: interval = 10.0_dp                  !! seconds between lines
      real(dp) :: wall0 = 0.0_dp                      !! wall clock at `start` [s]
      real(dp) :: last = 0.0_dp                       !! wall clock of the last line [s]
      real(dp) :: t = -1.0_dp, dt = -1.0_dp           !! last simulated time and step [s]
      logical :: enabled = .false.                    !! print at all
      logical :: tty = .false.                        !! standard error is a terminal
      logical :: shown = .false.                      !! a line was printed
      integer :: width = 0                            !! length of the line on a terminal
      logical :: estimate_pending = .false.           !! the long-run estimate still to make
      real(dp) :: estimate_after_s = 2.0_dp           !! wall time measured before it [s]
      real(dp) :: long_run_s = 3600.0_dp              !! time left that warns [s]
      character(len=:), allocatable :: warning        !! the long-run warning, once printed
   contains
      procedure :: start => meter_start
      procedure :: update => meter_update
      procedure :: finish => meter_finish
      procedure :: break_line => meter_break_line
   end type meter_t

   interface
      function c_isatty(fd) bind(c, name='isatty') result(r)
         import :: c_int
         integer(c_int), value, intent(in) :: fd
         integer(c_int) :: r
      end function c_isatty
   end interface

contains

   !> Whether standard error (file descriptor 2) is a terminal.
   logical function stderr_is_terminal()
      stderr_is_terminal = c_isatty(2_c_int) == 1_c_int
   end function stderr_is_terminal

   !> Start the meter: `total` units of work named `unit_name`, `done` of them done already.
   !> `interval` > 0 sets the seconds between lines; 0 takes 1 s on a terminal, 10 s otherwise.
   subroutine meter_start(self, what, unit_name, total, done, enabled, interval)
      class(meter_t), intent(inout) :: self          !! meter
      character(len=*), intent(in) :: what           !! 'sweep', 'transient', ...
      character(len=*), intent(in) :: unit_name      !! 'points', 'periods', ...
      real(dp), intent(in) :: total                  !! work of the whole computation
      real(dp), intent(in) :: done                   !! work done before this run
      logical, intent(in) :: enabled                 !! print at all (false: --quiet)
      real(dp), intent(in) :: interval               !! seconds between lines; 0: default
      self%what = what
      self%unit_name = unit_name
      self%total = total
      self%offset = 0.0_dp
      self%done_at_start = done
      self%done = done
      self%enabled = enabled
      self%tty = .false.
      if (enabled) self%tty = stderr_is_terminal()
      if (interval > 0.0_dp) then
         self%interval = interval
      else
         self%interval = merge(1.0_dp, 10.0_dp, self%tty)
      end if
      self%wall0 = wall_seconds()
      self%last = self%wall0
      self%t = -1.0_dp;  self%dt = -1.0_dp
      self%shown = .false.
      self%width = 0
      self%estimate_pending = total > done
      if (allocated(self%warning)) deallocate(self%warning)
   end subroutine meter_start

   !> `done` units done (plus the meter's offset); print a line when the interval has passed.
   subroutine meter_update(self, done, t, dt)
      class(meter_t), intent(inout) :: self            !! meter
      real(dp), intent(in) :: done                     !! work done [units]
      real(dp), intent(in), optional :: t              !! simulated time [s]
      real(dp), intent(in), optional :: dt             !! step size [s]
      real(dp) :: now
      if (.not. (self%enabled .or. self%estimate_pending)) return
      self%done = self%offset + done
      if (present(t)) self%t = t
      if (present(dt)) self%dt = dt
      now = wall_seconds()
      if (self%estimate_pending .and. now - self%wall0 >= self%estimate_after_s) &
         call estimate(self, now)
      if (.not. self%enabled) return
      if (now - self%last < self%interval) return
      self%last = now
      call show(self, now)
   end subroutine meter_update

   !> The computation is over: a last line when the meter printed anything, so a log ends at
   !> 100 % (or where a stopped run stopped).
   subroutine meter_finish(self, done)
      class(meter_t), intent(inout) :: self            !! meter
      real(dp), intent(in), optional :: done           !! work done at the end (default total)
      if (.not. (self%enabled .and. self%shown)) return
      self%done = self%total
      if (present(done)) self%done = done
      self%t = -1.0_dp;  self%dt = -1.0_dp
      call show(self, wall_seconds(), final=.true.)
      if (self%tty) write(error_unit, '(a)') ''
      flush(error_unit)
      self%shown = .false.
      self%width = 0
   end subroutine meter_finish

   !> Leave the in-place line on a terminal, so that other output can follow on lines of its
   !> own; the next progress line starts a new one. Nothing otherwise.
   subroutine meter_break_line(self)
      class(meter_t), intent(inout) :: self            !! meter
      if (.not. (self%enabled .and. self%shown .and. self%tty)) return
      if (self%width > 0) write(error_unit, '(a)') ''
      flush(error_unit)
      self%width = 0
   end subroutine meter_break_line

   !> The long-run estimate: the time left at the rate so far; a warning when it is more than
   !> `long_run_s`.
   subroutine estimate(self, now)
      type(meter_t), intent(inout) :: self           !! meter
      real(dp), intent(in) :: now                    !! wall clock [s]
      real(dp) :: rate, elapsed, left, shown
      self%estimate_pending = .false.
      shown = merge(anint(self%done), self%done, self%done >= 10.0_dp)   ! '26632', '0.2'
      elapsed = now - self%wall0
      if (.not. (elapsed > 0.0_dp .and. self%done > self%done_at_start)) return
      rate = (self%done - self%done_at_start) / elapsed
      left = max(0.0_dp, self%total - self%done) / rate
      if (.not. (left > self%long_run_s)) return
      self%warning = 'this ' // self%what // ' run will take about ' // hms(left) &
         // ' more (h:mm:ss, from ' // rate_text(rate) // ' ' // self%unit_name // '/s over ' &
         // 'its first ' // count_text(anint(elapsed)) // ' s; ' // count_text(shown) &
         // ' of ' // count_text(self%total) // ' ' // self%unit_name // ' done): check its ' &
         // 'settings (periods, steps, tolerance, model size) or run it as a batch job ' &
         // '(docs/running.md); --progress shows how it goes'
      call self%break_line()
      write(error_unit, '(a)') 'gapbeam: warning: ' // self%warning
      flush(error_unit)
   end subroutine estimate

   !> Print the meter's line: rewritten in place on a terminal, a new line otherwise.
   subroutine show(self, now, final)
      type(meter_t), intent(inout) :: self           !! meter (class not needed here)
      real(dp), intent(in) :: now                    !! wall clock [s]
      logical, intent(in), optional :: final         !! the last line: elapsed, not time left
      character(len=:), allocatable :: line
      real(dp) :: rate, elapsed
      elapsed = now - self%wall0
      rate = -1.0_dp
      if (elapsed > 0.0_dp .and. self%done > self%done_at_start) &
         rate = (self%done - self%done_at_start) / elapsed
      if (present(final)) then
         line = progress_line(self%what, self%done, self%total, self%unit_name, rate, elapsed)
      else
         line = progress_line(self%what, self%done, self%total, self%unit_name, rate)
      end if
      if (self%t >= 0.0_dp) line = line // '; t = ' // fixed3(self%t) // ' s'
      if (self%dt > 0.0_dp) line = line // ', dt = ' // sci3(self%dt) // ' s'
      if (self%tty) then
         write(error_unit, '(a)', advance='no') achar(13) // line &
            // repeat(' ', max(0, self%width - len(line)))
         self%width = len(line)
      else
         write(error_unit, '(a)') line
      end if
      flush(error_unit)
      self%shown = .true.
   end subroutine show

   !> 'what: 37.5 % (487/1300 periods), 12.3 periods/s, 0:00:39 left'; without a rate
   !> (rate <= 0) the rate and time left are omitted. With `elapsed` (the last line):
   !> 'what: 100.0 % (1300/1300 periods) in 0:01:45, 12.3 periods/s'.
   function progress_line(what, done, total, unit_name, rate, elapsed) result(line)
      character(len=*), intent(in) :: what             !! what progresses
      real(dp), intent(in) :: done, total              !! work done, whole work [units]
      character(len=*), intent(in) :: unit_name        !! 'points', 'periods'
      real(dp), intent(in) :: rate                     !! units per second (<= 0: unknown)
      real(dp), intent(in), optional :: elapsed        !! wall time of the whole run [s]
      character(len=:), allocatable :: line
      character(len=32) :: buf
      real(dp) :: pct
      pct = 100.0_dp
      if (total > 0.0_dp) pct = 100.0_dp * min(1.0_dp, max(0.0_dp, done / total))
      write(buf, '(f0.1)') pct
      line = what // ': ' // trim(adjustl(leading_zero(buf))) // ' % (' // count_text(done) &
         // '/' // count_text(total) // ' ' // unit_name // ')'
      if (present(elapsed)) then
         line = line // ' in ' // hms(elapsed)
         if (rate > 0.0_dp) line = line // ', ' // rate_text(rate) // ' ' // unit_name // '/s'
      else if (rate > 0.0_dp) then
         line = line // ', ' // rate_text(rate) // ' ' // unit_name // '/s, ' &
            // hms(max(0.0_dp, total - done) / rate) // ' left'
      end if
   end function progress_line

   !> Seconds as h:mm:ss (rounded to the second; hours unbounded; 'more than 1e6 h' beyond).
   function hms(seconds) result(t)
      real(dp), intent(in) :: seconds                  !! [s], >= 0
      character(len=:), allocatable :: t
      integer(8) :: s, h, m
      character(len=32) :: buf
      if (.not. (seconds < 3.6e9_dp)) then
         t = 'more than 1e6 h'
         return
      end if
      s = nint(max(0.0_dp, seconds), 8)
      h = s / 3600;  m = mod(s, 3600_8) / 60;  s = mod(s, 60_8)
      write(buf, '(i0, ":", i2.2, ":", i2.2)') h, m, s
      t = trim(buf)
   end function hms

   !> A count of work: whole numbers without decimals, else one decimal.
   function count_text(x) result(t)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: t
      character(len=32) :: buf
      if (abs(x - anint(x)) < 1.0e-9_dp * max(1.0_dp, abs(x)) .and. abs(x) < 1.0e15_dp) then
         write(buf, '(i0)') nint(x, 8)
      else
         write(buf, '(f0.1)') x
         buf = leading_zero(buf)
      end if
      t = trim(adjustl(buf))
   end function count_text

   !> A rate with three significant digits, e.g. '12.3', '0.0456', '1234'.
   function rate_text(r) result(t)
      real(dp), intent(in) :: r
      character(len=:), allocatable :: t
      character(len=32) :: buf
      integer :: decimals
      if (r >= 100.0_dp) then
         write(buf, '(i0)') nint(r, 8)
      else if (r >= 1.0e-4_dp) then
         decimals = 2 - floor(log10(r))
         write(buf, '(f0.' // achar(iachar('0') + decimals) // ')') r
      else
         write(buf, '(es9.2)') r
      end if
      t = trim(adjustl(leading_zero(buf)))
   end function rate_text

   !> A time with three decimals, e.g. '45.600'.
   function fixed3(x) result(t)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: t
      character(len=40) :: buf
      if (abs(x) < 1.0e12_dp) then
         write(buf, '(f0.3)') x
      else
         write(buf, '(es10.3)') x
      end if
      t = trim(adjustl(leading_zero(buf)))
   end function fixed3

   !> A number with four significant digits in exponent form, e.g. '1.200E-05'.
   function sci3(x) result(t)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: t
      character(len=40) :: buf
      write(buf, '(es10.3)') x
      t = trim(adjustl(buf))
   end function sci3

   !> f0.d output without its leading zero ('.5') gets it back ('0.5').
   function leading_zero(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s) + 1) :: t
      t = adjustl(s)
      if (t(1:1) == '.') t = '0' // t
   end function leading_zero
end module gapbeam_progress_meter
