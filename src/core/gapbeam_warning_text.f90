!> The texts of the warnings about a run's stops that come from its results (a stop never
!> touched), shared by the jobs that make them and the sweep merge that remakes them for the
!> whole grid. The warnings about the deck itself (scales, a stop out of reach) are made by
!> analyses/gapbeam_warnings. Every warning is one line; the program prints it on standard
!> error after `warning_prefix` and the writers store it in /run/warnings.
module gapbeam_warning_text
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   implicit none
   private
   public :: warning_prefix, untouched_stop_warnings, untouched_sweep_warnings, &
      is_untouched_warning, untouched_evidence, warning_length

   !> The longest warning line (lists of warnings are arrays of this length, trimmed when
   !> printed or stored).
   integer, parameter :: warning_length = 640

   !> What starts a warning on standard error.
   character(len=*), parameter :: warning_prefix = 'gapbeam: warning: '
   !> What every warning about a stop never touched contains (is_untouched_warning).
   character(len=*), parameter :: untouched_mark = ' was never touched'

contains

   !> One warning per stop of a transient run with no contact in the record: zero impacts and
   !> no time in contact. The run's label is then that of the beam without the stop.
   pure function untouched_stop_warnings(n_impacts, contact_fraction, record_periods) &
         result(lines)
      integer, intent(in) :: n_impacts(:)              !! per stop: impacts in the record
      real(dp), intent(in) :: contact_fraction(:)   !! per stop: time in contact [-]
      integer, intent(in) :: record_periods            !! periods recorded
      character(len=warning_length), allocatable :: lines(:)
      character(len=*), parameter :: tail = ' (0 impacts): the response, its label and its ' &
         // 'certificate are those of the beam without this stop; check its gap (and ' &
         // 'the forcing) if it was meant to be met'
      integer :: j, n
      n = count(n_impacts == 0 .and. contact_fraction == 0.0_dp)
      allocate(lines(n))
      n = 0
      do j = 1, size(n_impacts)
         if (n_impacts(j) /= 0 .or. contact_fraction(j) /= 0.0_dp) cycle
         n = n + 1
         lines(n) = line_for(j, record_periods) // tail
      end do
   contains
      pure function line_for(j, periods) result(t)
         integer, intent(in) :: j, periods
         character(len=:), allocatable :: t
         t = 'stop ' // str(j) // untouched_mark // ' in the ' // str(periods) &
            // ' recorded periods'
      end function line_for
   end function untouched_stop_warnings

   !> The evidence a label gets when some stops were never touched in its record, e.g.
   !> '; stop 1 never met in the record (0 impacts): the label of the beam without it';
   !> '' when every stop was met.
   pure function untouched_evidence(n_impacts, contact_fraction) result(t)
      integer, intent(in) :: n_impacts(:)              !! per stop: impacts in the record
      real(dp), intent(in) :: contact_fraction(:)   !! per stop: time in contact [-]
      character(len=:), allocatable :: t
      integer :: j, n
      t = ''
      n = 0
      do j = 1, size(n_impacts)
         if (n_impacts(j) /= 0 .or. contact_fraction(j) /= 0.0_dp) cycle
         n = n + 1
         if (n == 1) then
            t = '; stop ' // str(j)
         else
            t = t // ', ' // str(j)
         end if
      end do
      if (n == 0) return
      if (n == size(n_impacts)) then
         t = t // ' never met in the record (0 impacts): the label of the beam without ' &
            // 'stops'
      else
         t = t // ' never met in the record (0 impacts): the label of the beam without it'
      end if
   end function untouched_evidence

   !> One warning per stop that no finished point of a sweep touched (`impacts(stop, point)`,
   !> points with `status` 0 only), e.g. 'stop 1 was never touched at any of the 64 points
   !> ...'. Nothing when no point finished.
   pure function untouched_sweep_warnings(impacts, contact, status) result(lines)
      integer, intent(in) :: impacts(:, :)             !! (stop, point) impacts in the record
      real(dp), intent(in) :: contact(:, :)   !! (stop, point) contact fraction [-]
      integer, intent(in) :: status(:)                 !! per point: 0 done
      character(len=warning_length), allocatable :: lines(:)
      logical, allocatable :: done(:)
      integer :: j, n, n_done, k
      character(len=*), parameter :: tail = ' (0 impacts at every point): the map is that ' &
         // 'of the beam without this stop; check its gap (and the forcing) if it was meant ' &
         // 'to be met'
      done = status == 0
      n_done = count(done)
      n = 0
      do j = 1, size(impacts, 1)
         if (n_done > 0 .and. all(.not. done .or. (impacts(j, :) == 0 .and. &
             contact(j, :) == 0.0_dp))) n = n + 1
      end do
      allocate(lines(n))
      k = 0
      do j = 1, size(impacts, 1)
         if (n_done == 0 .or. .not. all(.not. done .or. (impacts(j, :) == 0 .and. &
             contact(j, :) == 0.0_dp))) cycle
         k = k + 1
         lines(k) = 'stop ' // str(j) // untouched_mark // ' at any of the ' // str(n_done) &
            // ' finished points' // tail
      end do
   end function untouched_sweep_warnings

   !> Whether a warning line is one of the above (a merge remakes them for the whole grid).
   pure logical function is_untouched_warning(line)
      character(len=*), intent(in) :: line             !! a warning
      is_untouched_warning = index(line, 'stop ') == 1 .and. index(line, untouched_mark) > 0
   end function is_untouched_warning
end module gapbeam_warning_text
