!> Everything a deck says, validated: the physical description and the settings of every
!> analysis, with the deck's effective text (file plus command-line overrides).
!>
!> The deck reader (src/io/gapbeam_input) fills it; analyses, the model builder and the writers
!> read it. Pure data: nothing here reads files or does numerics.
module gapbeam_deck
   use gapbeam_description, only: structure_t, stop_t, damping_t, forcing_t, flow_t, turbulence_t
   use gapbeam_settings, only: job_t, calibrate_t, solver_settings_t, output_settings_t, &
      initial_state_t, diagnostics_settings_t, sweep_settings_t, reduction_settings_t, &
      study_settings_t, model_size_settings_t, wear_settings_t
   use gapbeam_continuation_types, only: continuation_settings_t
   use gapbeam_warning_text, only: warning_length
   implicit none
   private
   public :: deck_t, add_warning

   !> A validated deck.
   type :: deck_t
      character(len=:), allocatable :: path          !! deck path as given
      character(len=:), allocatable :: text          !! effective text: file plus overrides
      type(job_t) :: job                             !! &job
      type(structure_t) :: structure                 !! &beam, &root, &springs, &masses
      integer :: n_print_modes = 0                   !! &modes n_print (0: all)
      type(calibrate_t) :: calibrate                 !! &calibrate
      type(stop_t), allocatable :: stops(:)          !! &stops
      type(damping_t) :: damping                     !! &damping
      type(forcing_t) :: forcing                     !! &forcing
      type(flow_t) :: flow                           !! &flow
      type(turbulence_t) :: turbulence               !! &turbulence
      type(solver_settings_t) :: solver              !! &solver
      type(initial_state_t) :: initial               !! &initial
      type(output_settings_t) :: output              !! &output
      type(diagnostics_settings_t) :: diagnostics    !! &diagnostics
      type(sweep_settings_t) :: sweep                !! &sweep
      type(reduction_settings_t) :: reduction        !! &reduction
      type(study_settings_t) :: study                !! &study
      type(model_size_settings_t) :: model_size      !! &model_size
      type(continuation_settings_t) :: continuation  !! &continuation
      type(wear_settings_t) :: wear                  !! &wear
      !> warnings about the deck and its run, one line each (analyses/gapbeam_warnings): the
      !> program prints them on standard error, the writers store them in /run/warnings
      !> (a fixed length: gfortran copies deferred-length array components wrongly)
      character(len=warning_length), allocatable :: warnings(:)
   end type deck_t

contains

   !> Add one warning line to the deck's list (kept in the order given, each once; cut at
   !> warning_length characters).
   pure subroutine add_warning(deck, text)
      type(deck_t), intent(inout) :: deck            !! deck
      character(len=*), intent(in) :: text           !! the warning, one line
      character(len=warning_length), allocatable :: list(:)
      integer :: k, n
      n = 0
      if (allocated(deck%warnings)) then
         n = size(deck%warnings)
         do k = 1, n
            if (deck%warnings(k) == text) return
         end do
      end if
      allocate(list(n + 1))
      if (n > 0) list(1:n) = deck%warnings
      list(n + 1) = text
      call move_alloc(list, deck%warnings)
   end subroutine add_warning
end module gapbeam_deck
