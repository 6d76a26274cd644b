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
   implicit none
   private
   public :: deck_t

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
   end type deck_t
end module gapbeam_deck
