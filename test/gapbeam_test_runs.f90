!> Test helper: run a deck (with overrides) through the same path as the executable's
!> transient analysis: read, build the model (reduction included), integrate.
module gapbeam_test_runs
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_results, only: transient_result_t, point_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_sweep, only: sweep_plan_t, make_plan
   use gapbeam_attractor, only: diagnose
   use gapbeam_certify, only: certify_point
   use gapbeam_testing, only: check, finish
   implicit none
   private
   public :: run_deck, load_deck, load_or_stop, make_plan_or_stop, expect_refused, &
             diagnose_or_stop

contains

   !> Read `path` with `overrides`, build its model and integrate it; err on any failure.
   subroutine run_deck(path, overrides, model, res, err)
      character(len=*), intent(in) :: path              !! deck
      character(len=*), intent(in) :: overrides(:)      !! namelist fragments
      type(model_t), intent(out) :: model              !! the model integrated
      type(transient_result_t), intent(out) :: res      !! results
      type(error_t), allocatable, intent(out) :: err    !! deck, model or solver failure
      type(deck_t) :: deck
      real(dp), allocatable :: u0(:), v0(:)
      call load_deck(path, overrides, deck, model, u0, v0, err)
      if (.not. allocated(err)) call integrate(model, deck%solver, deck%output, u0, v0, res, err)
   end subroutine run_deck

   !> Read `path` with `overrides` and build its model and initial state; err on any failure.
   subroutine load_deck(path, overrides, deck, model, u0, v0, err)
      character(len=*), intent(in) :: path              !! deck
      character(len=*), intent(in) :: overrides(:)      !! namelist fragments
      type(deck_t), intent(out) :: deck                 !! the deck read
      type(model_t), intent(out) :: model              !! its model
      real(dp), allocatable, intent(out) :: u0(:), v0(:) !! its initial state
      type(error_t), allocatable, intent(out) :: err    !! deck or model failure
      character(len=len(overrides)) :: ov(size(overrides))
      ov = overrides
      call read_deck(path, ov, deck, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err)
   end subroutine load_deck

   !> load_deck, or a failed check and the end of test program `program`.
   subroutine load_or_stop(program, path, overrides, deck, model, u0, v0)
      character(len=*), intent(in) :: program           !! test program name
      character(len=*), intent(in) :: path              !! deck
      character(len=*), intent(in) :: overrides(:)      !! namelist fragments
      type(deck_t), intent(out) :: deck                 !! the deck read
      type(model_t), intent(out) :: model              !! its model
      real(dp), allocatable, intent(out) :: u0(:), v0(:) !! its initial state
      type(error_t), allocatable :: err
      call load_deck(path, overrides, deck, model, u0, v0, err)
      if (allocated(err)) then
         call check('load ' // path, .false., err%message)
         call finish(program)
      end if
   end subroutine load_or_stop

   !> Diagnose the point of deck `path` with `overrides` (and certify it when asked), or a
   !> failed check and the end of test program `program`.
   subroutine diagnose_or_stop(program, path, overrides, certify, pr)
      character(len=*), intent(in) :: program           !! test program name
      character(len=*), intent(in) :: path              !! deck
      character(len=*), intent(in) :: overrides(:)      !! namelist fragments
      logical, intent(in) :: certify                    !! certify the label too
      type(point_result_t), intent(out) :: pr           !! the point's label and evidence
      type(deck_t) :: deck
      type(model_t) :: model
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      call load_or_stop(program, path, overrides, deck, model, u0, v0)
      call diagnose(model, deck%solver, deck%output, deck%diagnostics, u0, v0, res, pr, err)
      if (allocated(err)) then
         call check('run ' // path, .false., err%message)
         call finish(program)
      end if
      if (certify) call certify_point(model, deck%solver, deck%output, deck%diagnostics, u0, &
                                      v0, 1, pr)
   end subroutine diagnose_or_stop

   !> The sweep plan of `deck`, or a failed check and the end of test program `program`.
   subroutine make_plan_or_stop(program, deck, plan)
      character(len=*), intent(in) :: program           !! test program name
      type(deck_t), intent(in) :: deck                  !! a sweep deck
      type(sweep_plan_t), intent(out) :: plan           !! its plan
      type(error_t), allocatable :: err
      call make_plan(deck, plan, err)
      if (allocated(err)) then
         call check('sweep plan', .false., err%message)
         call finish(program)
      end if
   end subroutine make_plan_or_stop
   !> Read deck `path` with one override and expect the one-line error to start with the deck
   !> and hold every fragment (group, variable, value, what is allowed).
   subroutine expect_refused(path, name, override, fragments)
      character(len=*), intent(in) :: path, name, override, fragments(:)
      type(deck_t) :: d
      type(error_t), allocatable :: e
      character(len=200) :: ov(1)
      character(len=:), allocatable :: missing
      integer :: i
      ov(1) = override
      call read_deck(path, ov, d, e)
      if (.not. allocated(e)) then
         call check(name, .false., 'the deck was accepted');  return
      end if
      missing = ''
      if (index(e%message, path // ': ') /= 1) missing = ' [the deck name first]'
      do i = 1, size(fragments)
         if (index(e%message, trim(fragments(i))) == 0) missing = missing // ' [' &
            // trim(fragments(i)) // ']'
      end do
      call check(name // ': ' // e%message, len(missing) == 0 .and. &
         index(e%message, new_line('a')) == 0, 'missing:' // missing)
   end subroutine expect_refused
end module gapbeam_test_runs
