!> Persistence of chaos in the certificate: a chaotic label is certified only when the chaos
!> persists over certify_persistence x the periods before its record and the record. Systems:
!> the forced single-dof impact oscillator of test/decks/sdof_impact.nml (exact integrator).
!> - 18.7 Hz, just below its chaotic window (18.9-19.5 Hz): from rest with 50 transient and
!>   100 record periods the run is labelled chaotic (lambda ~ +4.6 1/s), but the trajectory
!>   falls onto a period-4 orbit after about 1,450 periods (a chaotic transient near the
!>   window's crisis; its first repeating record still reads period 12, the orbit losing a
!>   slowly decaying component). The check with a multiple of 10 catches it; the same deck
!>   run with 2,000 transient periods (no check involved) confirms period 4.
!> - 19.2 Hz, inside the window: the chaos persists and the label stays certified.
program test_persistence
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   use gapbeam_testing, only: check, finish, note
   use gapbeam_test_runs, only: diagnose_or_stop
   use gapbeam_results, only: point_result_t, label_text, label_chaotic, &
      certificate_certified, certificate_disputed, dispute_kind, dispute_transient, dispute_none
   implicit none
   character(len=*), parameter :: sdof = 'test/decks/sdof_impact.nml'
   character(len=*), parameter :: short = '&solver transient_periods = 50, record_periods = 100 /'

   call chaotic_transient_is_caught()
   call persistent_chaos_stays_certified()
   call finish('test_persistence')

contains

   !> Diagnose (and certify, when asked) the deck's own point with `overrides`.
   subroutine run(overrides, certify, pr)
      character(len=*), intent(in) :: overrides(:)
      logical, intent(in) :: certify
      type(point_result_t), intent(out) :: pr
      call diagnose_or_stop('test_persistence', sdof, overrides, certify, pr)
   end subroutine run

   !> 18.7 Hz: chaotic after 50 + 100 periods; the persistence check (10 x) finds period 4
   !> and disputes; without the check (0) the chaotic label is certified by the perturbed start
   !> alone; a long run settles on the period the check found.
   subroutine chaotic_transient_is_caught()
      type(point_result_t) :: caught, unchecked, long
      character(len=*), parameter :: at = '&forcing frequency_hz = 18.7 /'
      character(len=*), parameter :: expect = 'disputed: chaotic transient, then period 4 after '
      integer :: after, ios
      call run([character(len=200) :: at, short, '&diagnostics certify_persistence = 10 /'], &
               .true., caught)
      call note('18.7 Hz, multiple 10: ' // label_text(caught%label) // ' (lambda ' &
         // str(caught%lyapunov) // '); ' // caught%certificate_reason)
      call check('18.7 Hz: a short run labels the transient chaotic', &
         caught%label == label_chaotic .and. caught%lyapunov > 0.0_dp)
      call check('18.7 Hz: the persistence check disputes with "chaotic transient, then ' &
         // 'period 4 after N periods"', caught%certificate == certificate_disputed .and. &
         index(caught%certificate_reason, expect) == 1)
      call check('18.7 Hz: the charts mark it as a chaotic transient (dispute code 2)', &
         dispute_kind(caught%certificate, caught%certificate_reason) == dispute_transient)
      after = 0
      if (index(caught%certificate_reason, expect) == 1) then
         read(caught%certificate_reason(len(expect) + 1:), *, iostat=ios) after
         if (ios /= 0) after = 0
      end if
      ! the periods counted: after the run's own periods, within the 10 x continuation
      call check('18.7 Hz: N lies beyond the run''s own periods and within the continuation', &
         after > caught%transient_periods + 100 + caught%lyapunov_periods .and. &
         after <= caught%transient_periods + 100 + caught%lyapunov_periods &
         + 10 * (caught%transient_periods + 100) + 100)
      call run([character(len=200) :: at, short, '&diagnostics certify_persistence = 0 /'], &
               .true., unchecked)
      call note('18.7 Hz, no check: ' // unchecked%certificate_reason)
      call check('18.7 Hz: with certify_persistence = 0 no persistence check runs', &
         index(unchecked%certificate_reason, 'chaotic transient') == 0 .and. &
         index(unchecked%certificate_reason, 'chaotic for at least') == 0)
      call run([character(len=200) :: at, &
         '&solver transient_periods = 2000, record_periods = 100 /', &
         '&diagnostics certify = .false. /'], .false., long)
      call note('18.7 Hz after 2000 transient periods: ' // label_text(long%label) // ' (lambda ' &
         // str(long%lyapunov) // ' +- ' // str(long%lyapunov_error) // ')')
      call check('18.7 Hz: the long run settles on the period the check found (4, stable)', &
         long%label == 4 .and. long%lyapunov + 3.0_dp * long%lyapunov_error < 0.0_dp)
   end subroutine chaotic_transient_is_caught

   !> 19.2 Hz: the chaos persists over the default multiple (2) and the label is certified,
   !> the certificate saying for how long.
   subroutine persistent_chaos_stays_certified()
      type(point_result_t) :: pr
      call run([character(len=200) :: short], .true., pr)
      call note('19.2 Hz: ' // label_text(pr%label) // '; ' // pr%certificate_reason)
      call check('19.2 Hz: chaotic and certified, the chaos persisting', &
         pr%label == label_chaotic .and. pr%certificate == certificate_certified .and. &
         index(pr%certificate_reason, 'chaotic for at least ') > 0)
      call check('19.2 Hz: no dispute marker in the charts (dispute code 0)', &
         dispute_kind(pr%certificate, pr%certificate_reason) == dispute_none)
   end subroutine persistent_chaos_stays_certified
end program test_persistence
