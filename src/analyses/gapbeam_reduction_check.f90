!> The convergence check of a reduced model (`&reduction kind = 'auto'`): the deck run again
!> with a richer basis (richer_factor x the cut-off, at least one more mode per plane) over
!> the same periods as the run being checked, and the wear outputs of both per support with
!> their relative differences.
!>
!> What the difference means: it is the change that the richer basis makes, which bounds the
!> truncation error of the basis when the response is periodic. In a chaotic or undecided
!> response two runs that differ by anything (a basis, a tolerance) part after some periods,
!> and record averages then differ by their statistical spread as well (on the multispan tube
!> over 40 periods: 0.2 % in the normal work rate of the most loaded baffle but 7 % in its
!> impacts between tolerances 1e-4 and 1e-5 of the full model; docs/tubes.md); a longer
!> record narrows it.
module gapbeam_reduction_check
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_settings, only: output_settings_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_reduction_rule, only: reduction_info_t
   use gapbeam_transient, only: integrate
   implicit none
   private
   public :: reduction_check_t, check_reduction, check_lines

   real(dp), parameter :: richer_factor = 1.5_dp   !! richer cut-off / the checked one [-]

   !> The checked run and the richer one, per support.
   type :: reduction_check_t
      real(dp) :: cutoff_hz = 0.0_dp             !! checked cut-off [Hz]
      real(dp) :: richer_cutoff_hz = 0.0_dp      !! the richer one [Hz]
      integer :: n = 0, n_richer = 0             !! coordinates of each [-]
      integer :: modes = 0, modes_richer = 0     !! modes per plane of each [-]
      real(dp) :: cpu_richer = 0.0_dp            !! CPU of the richer run [s]
      integer :: periods = 0                     !! recorded periods compared [-]
      !> the checked basis keeps every mode: it spans the full model, nothing richer was run
      logical :: complete = .false.
      real(dp), allocatable :: wn(:), wn_richer(:)       !! normal work rates [W]
      real(dp), allocatable :: wf(:), wf_richer(:)       !! friction work rates [W]
      real(dp), allocatable :: peak(:), peak_richer(:)   !! peak normal forces [N]
      integer, allocatable :: impacts(:), impacts_richer(:)   !! impacts in the record [-]
   end type reduction_check_t

contains

   !> Run `deck` with the richer basis over the periods of `res` (the periods discarded before
   !> its record, the settling test's extension included, then its record) and compare.
   subroutine check_reduction(deck, info, model, res, discarded, check, err)
      type(deck_t), intent(in) :: deck                 !! the deck (a reduced model)
      type(reduction_info_t), intent(in) :: info       !! what its reduction kept
      type(model_t), intent(in) :: model               !! its model
      type(transient_result_t), intent(in) :: res      !! its final record
      integer, intent(in) :: discarded                 !! periods run before that record
      type(reduction_check_t), intent(out) :: check    !! both and the differences
      type(error_t), allocatable, intent(out) :: err   !! build or solver failure
      type(deck_t) :: d
      type(model_t) :: m
      type(transient_result_t) :: rr
      type(reduction_info_t) :: ri
      type(output_settings_t) :: o
      real(dp), allocatable :: u0(:), v0(:)
      check%cutoff_hz = info%cutoff_hz
      check%n = model%n
      check%modes = info%modes_per_plane
      check%periods = deck%solver%record_periods
      if (info%modes_per_plane >= info%modes_available) then
         check%complete = .true.
         return
      end if
      d = deck
      d%reduction%kind = 'modal'
      d%reduction%cutoff_hz = richer_factor * info%cutoff_hz
      call build_model(d, m, u0, v0, err, ri)
      if (allocated(err)) return
      if (ri%modes_per_plane <= info%modes_per_plane) then
         ! no mode up to the richer cut-off: one more mode per plane
         d%reduction%cutoff_hz = 0.0_dp
         d%reduction%n_modes = info%modes_per_plane + 1
         call build_model(d, m, u0, v0, err, ri)
         if (allocated(err)) return
      end if
      d%solver%record_periods = deck%solver%record_periods
      d%solver%transient_periods = discarded
      o = deck%output
      o%history_periods = 0
      call integrate(m, d%solver, o, u0, v0, rr, err)
      if (allocated(err)) return
      check%richer_cutoff_hz = ri%highest_mode_hz
      if (d%reduction%cutoff_hz > 0.0_dp) check%richer_cutoff_hz = d%reduction%cutoff_hz
      check%n_richer = m%n
      check%modes_richer = ri%modes_per_plane
      check%cpu_richer = rr%cpu_seconds
      check%wn = res%normal_work_rate;  check%wn_richer = rr%normal_work_rate
      check%wf = res%friction_work_rate;  check%wf_richer = rr%friction_work_rate
      check%peak = res%peak_force;  check%peak_richer = rr%peak_force
      check%impacts = res%n_impacts;  check%impacts_richer = rr%n_impacts
   end subroutine check_reduction

   !> The check as lines for the terminal (newline separated); `periodic` false adds the
   !> remark on the statistical spread of a record.
   function check_lines(check, periodic) result(t)
      type(reduction_check_t), intent(in) :: check    !! the check
      logical, intent(in) :: periodic                 !! the response was found periodic
      character(len=:), allocatable :: t
      integer :: k
      if (check%complete) then
         t = 'reduction check: the basis keeps every mode of the model (' // str(check%modes) &
            // ' per plane): it spans the finite element model, nothing richer to compare'
         return
      end if
      t = 'reduction check: cut-off ' // str(check%cutoff_hz) // ' Hz (' // str(check%modes) &
         // ' modes per plane, ' // str(check%n) // ' coordinates) against ' &
         // str(check%richer_cutoff_hz) // ' Hz (' // str(check%modes_richer) // ' modes, ' &
         // str(check%n_richer) // ' coordinates; ' // str(check%cpu_richer) // ' s cpu), ' &
         // 'the same ' // str(check%periods) // ' recorded periods'
      do k = 1, size(check%wn)
         t = t // new_line('a') // 'reduction check: stop ' // str(k) // ': normal work rate ' &
            // str(check%wn(k)) // ' / ' // str(check%wn_richer(k)) // ' W (' &
            // pct(check%wn(k), check%wn_richer(k)) // '), friction work rate ' &
            // str(check%wf(k)) // ' / ' // str(check%wf_richer(k)) // ' W (' &
            // pct(check%wf(k), check%wf_richer(k)) // '), impacts ' // str(check%impacts(k)) &
            // ' / ' // str(check%impacts_richer(k)) // ', peak force ' // str(check%peak(k)) &
            // ' / ' // str(check%peak_richer(k)) // ' N (' &
            // pct(check%peak(k), check%peak_richer(k)) // ')'
      end do
      if (.not. periodic) t = t // new_line('a') // 'reduction check: the response is not ' &
         // 'periodic: the differences include the statistical spread of a record of ' &
         // str(check%periods) // ' periods (a longer record narrows it)'
   end function check_lines

   !> Relative difference of a against the richer b, in per cent ('-' when both are 0).
   function pct(a, b) result(t)
      real(dp), intent(in) :: a, b
      character(len=:), allocatable :: t
      if (a == 0.0_dp .and. b == 0.0_dp) then
         t = 'both 0'
      else
         t = str(100.0_dp * (a - b) / max(abs(b), abs(a))) // ' %'
      end if
   end function pct
end module gapbeam_reduction_check
