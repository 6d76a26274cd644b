!> The continuation job: run the continuation a deck asks for, print the branches, the
!> bifurcations and the curves, and write PREFIX.h5 and the text tables (one output set: all
!> in place, or none changed), with the deck's parameters and model.
module gapbeam_continuation_job
   use, intrinsic :: iso_fortran_env, only: output_unit
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_parameters, only: run_parameters, stiffness_units
   use gapbeam_continuation_types, only: continuation_result_t
   use gapbeam_continuation, only: run_continuation
   use gapbeam_continuation_output, only: write_continuation
   implicit none
   private
   public :: run_continuation_job

contains

   !> Continue, report, write.
   subroutine run_continuation_job(deck, err)
      type(deck_t), intent(in) :: deck                 !! validated deck
      type(error_t), allocatable, intent(out) :: err   !! failure
      type(continuation_result_t) :: res
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:)
      character(len=200) :: line
      integer :: k, n_stable
      associate (c => deck%continuation)
         write(output_unit, '(a)') 'continuation: ' // trim(c%parameter) // ' from ' &
            // str(c%parameter_min) // ' to ' // str(c%parameter_max) // ', direction ' &
            // trim(c%direction) // ', start ' // trim(c%start) // ', Jacobian ' &
            // trim(c%jacobian) // ', integrator ' // trim(deck%solver%method)
         if (len_trim(c%parameter2) > 0) write(output_unit, '(a)') 'curves: ' &
            // join(c%curves) // ' in (' // trim(c%parameter) // ', ' // trim(c%parameter2) &
            // '), ' // trim(c%parameter2) // ' from ' // str(c%parameter2_min) // ' to ' &
            // str(c%parameter2_max)
      end associate
      call build_model(deck, model, u0, v0, err)     ! the deck's model, for /model
      if (allocated(err)) return
      call run_continuation(deck, res, err)
      if (allocated(err)) return
      if (allocated(res%note)) then
         if (len(res%note) > 0) write(output_unit, '(a)') 'note: ' // res%note
      end if
      do k = 1, size(res%branches)
         associate (b => res%branches(k))
            n_stable = count(res%stable(b%first:b%last))
            write(output_unit, '(a)') 'branch ' // str(k) // ': period ' // str(b%period) &
               // ', ' // str(b%last - b%first + 1) // ' points (' // str(n_stable) &
               // ' stable), ' // res%parameter_name // ' from ' &
               // str(minval(res%parameter(b%first:b%last))) // ' to ' &
               // str(maxval(res%parameter(b%first:b%last))) // trim(parent_text(b%parent)) &
               // '; ' // trim(b%ended)
         end associate
      end do
      do k = 1, res%n_bif
         write(line, '(a, f16.9, 1x, a, a, i0, a, i0, a, f9.5, sp, f9.5, a)') '  ', &
            res%bif_parameter(k), res%parameter_units, '  period ', res%bif_period(k), &
            ', branch ', res%bif_branch(k), ', multiplier ', real(res%bif_multiplier(k)), &
            aimag(res%bif_multiplier(k)), 'i'
         write(output_unit, '(a)') 'bifurcation: ' // res%bif_kind(k) // trim(line)
         if (len_trim(res%bif_note(k)) > 0) write(output_unit, '(a)') '  note: ' &
            // trim(res%bif_note(k))
      end do
      do k = 1, size(res%curves)
         associate (cv => res%curves(k))
            write(output_unit, '(a)') 'curve ' // str(k) // ': ' // trim(cv%kind) // ', period ' &
               // str(cv%period) // ', ' // str(size(cv%parameter)) // ' points, ' &
               // res%parameter_name // ' ' // str(minval(cv%parameter)) // '..' &
               // str(maxval(cv%parameter)) // ', ' // res%parameter2_name // ' ' &
               // str(minval(cv%parameter2)) // '..' // str(maxval(cv%parameter2)) // '; ' &
               // trim(cv%ended)
         end associate
      end do
      write(output_unit, '(a)') 'elapsed: ' // str(res%seconds) // ' s, ' &
         // str(res%map_evaluations) // ' map evaluations, ' // str(res%periods_integrated) &
         // ' forcing periods integrated'
      call write_continuation(trim(deck%job%output), trim(deck%job%title), deck%text, &
         trim(deck%continuation%overlay), res, deck%output%write_text, err, &
         run_parameters(deck, model%stop_stiffness, model%f1_open_hz, &
         model%omega_max / (2.0_dp * pi), model%n), model, stiffness_units(deck), &
         deck%warnings)
      if (allocated(err)) return
      if (deck%output%write_text) then
         write(output_unit, '(a)') 'files: ' // trim(deck%job%output) // '.h5, .branches.dat, ' &
            // '.bifurcations.dat, .multipliers.dat, .curves.dat'
      else
         write(output_unit, '(a)') 'files: ' // trim(deck%job%output) // '.h5'
      end if
   end subroutine run_continuation_job

   pure function parent_text(parent) result(t)
      integer, intent(in) :: parent
      character(len=:), allocatable :: t
      t = ''
      if (parent > 0) t = ', doubled from branch ' // str(parent)
   end function parent_text

   pure function join(words) result(t)
      character(len=*), intent(in) :: words(:)
      character(len=:), allocatable :: t
      integer :: k
      t = ''
      do k = 1, size(words)
         if (len_trim(words(k)) == 0) cycle
         if (len(t) > 0) t = t // ', '
         t = t // trim(words(k))
      end do
   end function join
end module gapbeam_continuation_job
