!> Where the time of a tube run goes, full against reduced: one variant of a deck per call,
!> run as `gapbeam` runs a transient (the deck's integrator, recorder and wear meter), with
!> its model reduced as asked, printed as one line of `key=value` fields for
!> scripts/bench_tubes.sh (which runs the variants side by side and writes the table and the
!> chart).
!>
!> Usage: gapbeam_bench_tubes DECK KIND CUTOFF TOLERANCE TRANSIENT RECORD [profile]
!>   KIND       none (the finite element model), modal (CUTOFF [Hz] > 0, or n_modes of the
!>              deck when 0) or auto (the deck's &reduction rule)
!>   TOLERANCE  &solver tolerance;  TRANSIENT, RECORD: forcing periods
!> Environment: GAPBEAM_BENCH_OVERRIDE, one more namelist fragment read after the deck.
!>   GAPBEAM_BENCH_BATCHES = K (default 1): after the run, K - 1 more records of RECORD periods,
!>   each from the end state of the one before (no transient), one line `batch=j` each with the
!>   supports' fields (batch means of a chaotic record: scripts/bench_tubes_batches.py)
!>   profile    also integrate once more with an observer that sorts the accepted steps by the
!>              contact state of the supports (all open / a support in contact) and reports
!>              their number and mean length
!> Fields: the model (coordinates, modes and static modes per plane, cut-off, highest
!> frequency), the cost (CPU of the run, CPU per simulated second, steps), and per support the
!> impacts, impact rate, peak normal force, normal work rate, friction work rate, sliding
!> distance, contact and stick fractions.
program gapbeam_bench_tubes
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_reduction_rule, only: reduction_info_t
   use gapbeam_transient, only: integrate
   use gapbeam_integrator, only: integrator_t, make_integrator, start_state
   use gapbeam_bench_profile, only: profile_t
   implicit none
   character(len=256) :: deck_path, kind, arg
   character(len=400) :: ov(2)
   integer :: n_ov, env_len
   type(deck_t) :: deck
   type(model_t) :: model
   type(transient_result_t) :: res
   type(error_t), allocatable :: err
   type(reduction_info_t) :: info
   real(dp), allocatable :: u0(:), v0(:)
   real(dp) :: cutoff, tol, t_sim, t_rec
   integer :: n_transient, n_record, k, n_batch, b
   type(transient_result_t) :: rb
   real(dp), allocatable :: ub(:), vb(:)
   character(len=:), allocatable :: line

   if (command_argument_count() < 6) then
      write(error_unit, '(a)') 'usage: gapbeam_bench_tubes DECK KIND CUTOFF TOLERANCE ' &
         // 'TRANSIENT RECORD [profile]'
      error stop 2
   end if
   call get_command_argument(1, deck_path)
   call get_command_argument(2, kind)
   call get_command_argument(3, arg);  read(arg, *) cutoff
   call get_command_argument(4, arg);  read(arg, *) tol
   call get_command_argument(5, arg);  read(arg, *) n_transient
   call get_command_argument(6, arg);  read(arg, *) n_record
   write(ov(1), '(a, es12.5, a, i0, a, i0, a)') '&solver tolerance = ', tol, &
      ', transient_periods = ', n_transient, ', record_periods = ', n_record, ' /'
   ! GAPBEAM_BENCH_OVERRIDE: one more namelist fragment (another forcing, clearance, ...)
   n_ov = 1
   call get_environment_variable('GAPBEAM_BENCH_OVERRIDE', ov(2), env_len)
   if (env_len > 0) n_ov = 2
   call read_deck(trim(deck_path), ov(1:n_ov), deck, err)
   call stop_on(err)
   deck%reduction%kind = trim(kind)
   if (trim(kind) == 'modal' .and. cutoff > 0.0_dp) deck%reduction%cutoff_hz = cutoff
   call build_model(deck, model, u0, v0, err, info)
   call stop_on(err)
   call integrate(model, deck%solver, deck%output, u0, v0, res, err)
   call stop_on(err)
   t_sim = real(n_transient + n_record, dp) * 2.0_dp * pi / model%omega
   t_rec = real(n_record, dp) * 2.0_dp * pi / model%omega
   line = 'kind=' // trim(kind) // ' tolerance=' // num(tol) // ' n=' // int_text(model%n) &
      // ' modes_per_plane=' // int_text(info%modes_per_plane) // ' static_per_plane=' &
      // int_text(info%n_static) // ' cutoff_hz=' // num(info%cutoff_hz) // ' contact_hz=' &
      // num(info%contact_hz) // ' f_max_hz=' // num(model%omega_max / (2.0_dp * pi)) &
      // ' cpu_s=' // num(res%cpu_seconds) // ' cpu_per_simulated_s=' &
      // num(res%cpu_seconds / t_sim) // ' steps=' // int_text(int(res%steps_accepted)) &
      // ' rejected=' // int_text(int(res%steps_rejected)) // ' events=' &
      // int_text(int(res%events)) // ' method=' // res%method
   line = line // support_fields(res)
   if (command_argument_count() > 6) line = line // profile_fields()
   write(output_unit, '(a)') line
   n_batch = 1
   call get_environment_variable('GAPBEAM_BENCH_BATCHES', arg, env_len)
   if (env_len > 0) then
      read(arg, *, iostat=k) n_batch
      if (k /= 0 .or. n_batch < 1) then
         write(error_unit, '(a)') 'error: GAPBEAM_BENCH_BATCHES = ' // trim(arg) &
            // ': a whole number of records, at least 1'
         error stop 2
      end if
   end if
   if (n_batch > 1) write(output_unit, '(a)') 'batch=1 cpu_s=' // num(res%cpu_seconds) &
      // support_fields(res)
   deck%solver%transient_periods = 0
   ub = res%u;  vb = res%v
   do b = 2, n_batch
      ! the next record from this one's end: a whole number of periods, so the forcing's phase
      ! at t = 0 is the phase there (the rings' regimes start afresh from the state)
      call integrate(model, deck%solver, deck%output, ub, vb, rb, err)
      call stop_on(err)
      write(output_unit, '(a)') 'batch=' // int_text(b) // ' cpu_s=' // num(rb%cpu_seconds) &
         // support_fields(rb)
      ub = rb%u;  vb = rb%v
   end do

contains

   !> Per support: impacts, impact rate, peak normal force, normal and friction work rates,
   !> sliding distance, contact and stick fractions of a record of t_rec.
   function support_fields(r) result(t)
      type(transient_result_t), intent(in) :: r
      character(len=:), allocatable :: t
      integer :: j
      t = ''
      do j = 1, size(r%n_impacts)
         t = t // ' impacts_' // int_text(j) // '=' // int_text(r%n_impacts(j)) &
            // ' impact_rate_' // int_text(j) // '=' // num(r%n_impacts(j) / t_rec) &
            // ' peak_' // int_text(j) // '=' // num(r%peak_force(j)) // ' wn_' // int_text(j) &
            // '=' // num(r%normal_work_rate(j)) // ' wf_' // int_text(j) // '=' &
            // num(r%friction_work_rate(j)) // ' slide_' // int_text(j) // '=' &
            // num(r%sliding_distance(j)) // ' contact_' // int_text(j) // '=' &
            // num(r%contact_fraction(j)) // ' stick_' // int_text(j) // '=' &
            // num(r%stick_fraction(j))
      end do
   end function support_fields

   !> Integrate once more, sorting the accepted steps by the supports' contact state.
   function profile_fields() result(t)
      character(len=:), allocatable :: t
      class(integrator_t), allocatable :: integ
      type(state_t) :: s
      type(profile_t) :: pr
      call make_integrator(model, deck%solver, integ, err)
      call stop_on(err)
      call start_state(model, 0.0_dp, u0, v0, s)
      call integ%advance(s, t_sim, pr, err)
      call stop_on(err)
      t = ' open_steps=' // int_text(pr%n_open) // ' open_mean_dt=' &
         // num(pr%t_open / max(1, pr%n_open)) // ' contact_steps=' // int_text(pr%n_contact) &
         // ' contact_mean_dt=' // num(pr%t_contact / max(1, pr%n_contact))
   end function profile_fields

   subroutine stop_on(e)
      type(error_t), allocatable, intent(in) :: e
      if (allocated(e)) then
         write(error_unit, '(a)') 'error: ' // e%message
         error stop 1
      end if
   end subroutine stop_on

   function num(x) result(t)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: t
      character(len=32) :: b
      write(b, '(es16.9)') x
      t = trim(adjustl(b))
   end function num

   function int_text(i) result(t)
      integer, intent(in) :: i
      character(len=:), allocatable :: t
      character(len=16) :: b
      write(b, '(i0)') i
      t = trim(b)
   end function int_text
end program gapbeam_bench_tubes
