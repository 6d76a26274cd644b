!> Modal reduction: all modes reproduce the full model; the static correction makes the
!> contact flexibility exact and the peak stop force closer with few modes.
program test_reduction
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_lapack, only: dpotrf, dpotrs
   use gapbeam_test_runs, only: run_deck
   implicit none
   character(len=*), parameter :: ref = 'test/decks/moon_shaw_10p5hz_half_element.nml'
   character(len=*), parameter :: short = "&solver step_control = 'fixed', " &
      // 'transient_periods = 0, record_periods = 5 /'
   type(model_t) :: pf, pr
   type(transient_result_t) :: rf, rr, r2, r2s
   real(dp) :: d, u_full, u_red, e_with, e_without
   integer :: n_all

   ! fixed steps without event location: the two runs take exactly the same steps (a located
   ! event's sub-step can flip between split and not split on round-off, which moves the
   ! trajectory by the local truncation error, about 1e-9 here)
   call run([character(len=200) :: short, '&solver locate_events = .false. /'], pf, rf)
   n_all = pf%n
   call run([character(len=200) :: short, '&solver locate_events = .false. /', &
      "&reduction kind = 'modal', n_modes = " // str(n_all) // ', static_correction = .false. /'], &
      pr, rr)
   d = max(maxval(abs(rr%strain - rf%strain)) / maxval(abs(rf%strain)), &
           maxval(abs(rr%tip_displacement - rf%tip_displacement)) &
           / maxval(abs(rf%tip_displacement)), &
           maxval(abs(rr%stop_force - rf%stop_force)) / maxval(abs(rf%stop_force)))
   call note('all ' // str(n_all) // ' modes: largest relative difference to the full model ' &
      // str(d))
   call check('the modal model with all modes has as many coordinates as the full one', &
      pr%n == n_all)
   call check_le('a modal model keeping all modes reproduces the full trajectory', d, 1.0e-9_dp)
   call run([character(len=200) :: short], pf, rf)

   ! static tip deflection under a unit stop load: exact with the static correction
   call run([character(len=200) :: short, "&reduction kind = 'modal', n_modes = 2, " &
      // 'static_correction = .true. /'], pr, r2s)
   u_full = static_response(pf, pf%c_dof(1))
   u_red = static_response(pr, pr%c_dof(1))
   call check_close('2 modes + static correction: static deflection under a stop load exact', &
      u_red, u_full, rtol=1.0e-10_dp)
   call run([character(len=200) :: short, "&reduction kind = 'modal', n_modes = 2, " &
      // 'static_correction = .false. /'], pr, r2)
   u_red = static_response(pr, pr%c_dof(1))
   call note('2 modes without static correction: static deflection ' // str(u_red) &
      // ' against ' // str(u_full) // ' (full model)')
   e_with = abs(r2s%peak_force(1) - rf%peak_force(1)) / rf%peak_force(1)
   e_without = abs(r2%peak_force(1) - rf%peak_force(1)) / rf%peak_force(1)
   call note('peak stop force over 5 periods: full ' // str(rf%peak_force(1)) // ' N; 2 modes ' &
      // 'with static correction ' // str(r2s%peak_force(1)) // ' N (error ' // str(e_with) &
      // '), without ' // str(r2%peak_force(1)) // ' N (error ' // str(e_without) // ')')
   call check('static correction brings the peak stop force closer to the full model', &
      e_with < e_without)
   call finish('test_reduction')

contains

   subroutine run(overrides, model, res)
      character(len=*), intent(in) :: overrides(:)
      type(model_t), intent(out) :: model
      type(transient_result_t), intent(out) :: res
      type(error_t), allocatable :: err
      call run_deck(ref, overrides, model, res, err)
      if (allocated(err)) then
         call check('run succeeds', .false., err%message)
         call finish('test_reduction')
      end if
   end subroutine run

   !> Displacement of dof i under a unit force at dof i: (K^-1)_ii.
   real(dp) function static_response(p, i)
      type(model_t), intent(in) :: p
      integer, intent(in) :: i
      real(dp), allocatable :: k(:, :), b(:)
      integer :: info
      k = p%sys%k
      allocate(b(p%n), source=0.0_dp)
      b(i) = 1.0_dp
      call dpotrf('U', p%n, k, p%n, info)
      call dpotrs('U', p%n, 1, k, p%n, b, p%n, info)
      static_response = b(i)
   end function static_response
end program test_reduction
