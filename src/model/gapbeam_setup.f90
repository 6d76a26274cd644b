!> From a validated deck to the problem an analysis integrates: the full model, its initial
!> state, and (when the deck asks for it) its modal reduction.
module gapbeam_setup
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_input, only: deck_t
   use gapbeam_problem, only: problem_t, build_problem, initial_vectors
   use gapbeam_reduction, only: reduce_problem, project
   implicit none
   private
   public :: build_model

contains

   !> The problem and the initial state (u0, v0) in its coordinates.
   subroutine build_model(deck, prob, u0, v0, err)
      type(deck_t), intent(in) :: deck                 !! validated deck
      type(problem_t), intent(out) :: prob             !! model to integrate
      real(dp), allocatable, intent(out) :: u0(:), v0(:)  !! initial state
      type(error_t), allocatable, intent(out) :: err   !! calibration, eigen or reduction failure
      type(problem_t) :: full
      real(dp), allocatable :: basis(:, :), uf(:), vf(:)
      call build_problem(deck%structure, deck%stops, deck%damping, deck%forcing, full, err)
      if (allocated(err)) return
      call initial_vectors(full, deck%initial, uf, vf)
      if (deck%reduction%kind /= 'modal') then
         prob = full;  u0 = uf;  v0 = vf
         return
      end if
      call reduce_problem(full, deck%reduction%n_modes, deck%reduction%static_correction, prob, &
                          basis, err)
      if (allocated(err)) then
         err%message = 'group &reduction: ' // err%message
         return
      end if
      u0 = project(full, basis, uf)
      v0 = project(full, basis, vf)
   end subroutine build_model
end module gapbeam_setup
