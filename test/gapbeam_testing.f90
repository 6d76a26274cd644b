!> Tiny test helper: one line per check, a summary, and a non-zero exit on failure.
!>
!> Each check prints `PASS  name` or `FAIL  name (got ..., want ...)`; `scripts/test.sh`
!> counts these lines. `finish` prints `<program>: N checks, M failed` and stops with
!> `error stop 1` when anything failed, so `fpm test` sees the failure.
module gapbeam_testing
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private
   public :: check, check_close, check_le, finish, note

   integer, save :: n_checks = 0   ! test programs are serial: module state is fine here
   integer, save :: n_failed = 0

contains

   !> Record a logical check.
   subroutine check(name, ok, detail)
      character(len=*), intent(in) :: name             !! what is checked
      logical, intent(in) :: ok                        !! outcome
      character(len=*), intent(in), optional :: detail !! shown on failure
      n_checks = n_checks + 1
      if (ok) then
         write(output_unit, '(a)') 'PASS  ' // name
      else
         n_failed = n_failed + 1
         if (present(detail)) then
            write(output_unit, '(a)') 'FAIL  ' // name // ' (' // detail // ')'
         else
            write(output_unit, '(a)') 'FAIL  ' // name
         end if
      end if
      flush(output_unit)
   end subroutine check

   !> Check |got - want| <= rtol*|want| + atol.
   subroutine check_close(name, got, want, rtol, atol)
      character(len=*), intent(in) :: name       !! what is checked
      real(dp), intent(in) :: got                !! computed value
      real(dp), intent(in) :: want               !! reference value
      real(dp), intent(in), optional :: rtol     !! relative tolerance [-]
      real(dp), intent(in), optional :: atol     !! absolute tolerance
      real(dp) :: rt, at, err
      rt = 0.0_dp; at = 0.0_dp
      if (present(rtol)) rt = rtol
      if (present(atol)) at = atol
      err = abs(got - want)
      call check(name // ' [got ' // str(got) // ', want ' // str(want) // ', rel.err ' &
                 // str(err / max(abs(want), tiny(1.0_dp))) // ']', &
                 err <= rt * abs(want) + at .and. got == got, &
                 'got ' // str(got) // ', want ' // str(want) // ', rtol ' // str(rt) &
                 // ', atol ' // str(at))
   end subroutine check_close

   !> Check got <= bound.
   subroutine check_le(name, got, bound)
      character(len=*), intent(in) :: name       !! what is checked
      real(dp), intent(in) :: got                !! computed value
      real(dp), intent(in) :: bound              !! upper bound
      call check(name // ' [' // str(got) // ' <= ' // str(bound) // ']', got <= bound, &
                 'got ' // str(got) // ', bound ' // str(bound))
   end subroutine check_le

   !> Print an informational line (a measured order, a timing) that is not a check.
   subroutine note(text)
      character(len=*), intent(in) :: text     !! line to print
      write(output_unit, '(a)') 'NOTE  ' // text
   end subroutine note

   !> Print the summary and fail the program if any check failed.
   subroutine finish(program_name)
      character(len=*), intent(in) :: program_name   !! name of the test program
      write(output_unit, '(a)') program_name // ': ' // str(n_checks) // ' checks, ' &
         // str(n_failed) // ' failed'
      flush(output_unit)
      if (n_failed > 0) error stop 1
   end subroutine finish
end module gapbeam_testing
