!> The impact statistics of flat stops follow the tolerance: on a two-sided stop with a
!> contact damper (the regression case v_two_sided_damper_rk45), Newmark with error control and
!> rk45 give the peak force, rms force, impulse per period, work rate and contact fraction of
!> each stop within a small multiple of the tolerance of the exact integrator (exact for flat
!> stops: its statistics are integrals and certified extrema of the closed-form pieces). The
!> peak is located inside each step on its interpolant and the integrals are Gauss quadratures
!> of it; end-point rules (the largest end force, trapezoids) were O(h^2) and missed the peak
!> between step ends: rk45 at 1e-6 was 3e-4 off in the peak force.
program test_stop_statistics
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_le, finish, note
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_test_runs, only: run_deck
   implicit none
   character(len=*), parameter :: ref = 'test/decks/moon_shaw_10p5hz_half_element.nml'
   !> 10 periods of transient, 16 recorded (the horizon of the regression case)
   character(len=*), parameter :: horizon = '&solver transient_periods = 10, ' &
      // 'record_periods = 16 /'
   character(len=*), parameter :: stops = "&stops side = 'both', gap = 0.5e-3, damping = 0.02 /"
   !> the statistics' error allowed, in units of the tolerance
   real(dp), parameter :: factor = 10.0_dp
   type(transient_result_t) :: rr
   logical :: ok

   call run('exact reference', "&solver method = 'exact' /", rr, ok)
   if (ok) then
      call note('exact: peak ' // str(rr%peak_force(1)) // ' N, rms ' // str(rr%rms_force(1)) &
         // ' N, impulse ' // str(rr%impulse_per_period(1)) // ' N s, work rate ' &
         // str(rr%work_rate(1)) // ' W, contact fraction ' // str(rr%contact_fraction(1)))
      call compare('rk45', 1.0e-6_dp, "&solver method = 'rk45', rk_rtol = 1e-6 /")
      call compare('rk45', 1.0e-8_dp, "&solver method = 'rk45', rk_rtol = 1e-8 /")
      call compare('newmark', 1.0e-5_dp, "&solver method = 'newmark', step_control = " &
                   // "'error', tolerance = 1e-5 /")
      call compare('newmark', 1.0e-6_dp, "&solver method = 'newmark', step_control = " &
                   // "'error', tolerance = 1e-6 /")
   end if
   call finish('test_stop_statistics')

contains

   !> Run the reference deck with the stops, the horizon and a solver group.
   subroutine run(what, solver, res, ok)
      character(len=*), intent(in) :: what, solver
      type(transient_result_t), intent(out) :: res
      logical, intent(out) :: ok
      type(model_t) :: model
      type(error_t), allocatable :: err
      call run_deck(ref, [character(len=200) :: stops, horizon, solver], model, res, err)
      ok = .not. allocated(err)
      if (allocated(err)) call check(what // ' runs', .false., err%message)
   end subroutine run

   !> A method at a tolerance against the exact reference: every statistic of every stop
   !> within factor x tol (relative to the exact value; the contact fraction absolute).
   subroutine compare(method, tol, solver)
      character(len=*), intent(in) :: method, solver
      real(dp), intent(in) :: tol
      type(transient_result_t) :: r
      logical :: ok
      real(dp) :: e(5)
      integer :: k
      character(len=:), allocatable :: what
      what = method // ' at ' // str(tol)
      call run(what, solver, r, ok)
      if (.not. ok) return
      do k = 1, size(rr%peak_force)
         call check(what // ', stop ' // str(k) // ': the exact run has impacts', &
                    rr%n_impacts(k) > 0 .and. r%n_impacts(k) == rr%n_impacts(k), &
                    str(r%n_impacts(k)) // ' vs ' // str(rr%n_impacts(k)))
         e(1) = rel(r%peak_force(k), rr%peak_force(k))
         e(2) = rel(r%rms_force(k), rr%rms_force(k))
         e(3) = rel(r%impulse_per_period(k), rr%impulse_per_period(k))
         e(4) = rel(r%work_rate(k), rr%work_rate(k))
         e(5) = abs(r%contact_fraction(k) - rr%contact_fraction(k))
         call note(what // ', stop ' // str(k) // ': errors peak ' // str(e(1)) // ', rms ' &
            // str(e(2)) // ', impulse ' // str(e(3)) // ', work rate ' // str(e(4)) &
            // ', contact fraction ' // str(e(5)) // ' (' // str(int(r%steps_accepted)) &
            // ' steps)')
         call check_le(what // ', stop ' // str(k) // ': peak force', e(1), factor * tol)
         call check_le(what // ', stop ' // str(k) // ': rms force', e(2), factor * tol)
         call check_le(what // ', stop ' // str(k) // ': impulse per period', e(3), factor * tol)
         call check_le(what // ', stop ' // str(k) // ': work rate', e(4), factor * tol)
         call check_le(what // ', stop ' // str(k) // ': contact fraction', e(5), factor * tol)
      end do
   end subroutine compare

   pure real(dp) function rel(x, x_ref)
      real(dp), intent(in) :: x, x_ref
      rel = abs(x - x_ref) / max(abs(x_ref), tiny(1.0_dp))
   end function rel
end program test_stop_statistics
