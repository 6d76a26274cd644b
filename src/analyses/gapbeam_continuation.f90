!> Continuation of periodic orbits of the forced gap model (issue 14): branches of orbits in one
!> deck variable by pseudo-arclength continuation, their Floquet multipliers and stability,
!> the bifurcations on them located, the period-doubling cascade followed by branch switching,
!> and (gapbeam_bifurcation_curves) the bifurcation points continued in two variables.
!>
!> **Start.** 'transient': the deck's initial state is run over the transient periods with the
!> deck's integrator, the section state sampled and its period detected (or &continuation
!> period taken); 'given': the &initial state is the section state of an orbit of the given
!> period. Newton's method then converges the orbit at the deck's value of the variable.
!>
!> **Branches.** From the start, 'up' and/or 'down' in the variable; each step is predicted
!> along the tangent and corrected (gapbeam_continuation_problem); the step grows by 1.5 after
!> an easy correction (at most 2 iterations) up to step_max, shrinks by 0.7 after a hard one
!> (4 or more) and halves on a failure or a turn of the tangent by more than 37 degrees, down
!> to step_min. Folds are passed: the arclength, not the variable, parametrises the branch.
!> A branch ends outside [parameter_min, parameter_max], after max_points, at the smallest
!> step, or (a doubled branch) when it merges back into the branch of half its period.
!>
!> **Bifurcations** between two consecutive points: a fold ('saddle_node') where the tangent's
!> variable component changes sign; a 'branch_point' where a real multiplier crosses +1
!> without a fold; 'period_doubling' where one crosses -1; 'neimark_sacker' where a complex
!> pair crosses the unit circle; 'grazing' where the number of contact intervals per orbit
!> changes (an extremum of a penetration d crosses 0). Each is located on the arclength by the
!> Illinois method on its test function (gapbeam_continuation_problem: test_value) to
!> locate_tolerance in the variable, and inserted in the branch as a point.
!>
!> **Period doubling.** At each located period doubling of a branch of period p <= max_period/2
!> the doubled branch (period 2p) is started along the critical eigenvector v of the monodromy
!> (P v = -v): a corrector step of 0.02 from the bifurcation point, on the hyperplane normal to
!> v, lands on the period-2p orbits, which are then continued like any branch, and their own
!> doublings switched in turn: the cascade is followed as far as it resolves.
module gapbeam_continuation
   use gapbeam_error, only: error_t
   use gapbeam_deck, only: deck_t
   use gapbeam_continuation_types, only: continuation_result_t
   implicit none
   private
   public :: run_continuation

   interface
      !> Run the continuation a deck asks for: the start orbit, the branches with their
      !> bifurcations, the doubled branches, and the two-parameter curves (submodule
      !> gapbeam_continuation_branches).
      module subroutine run_continuation(deck, res, err)
         type(deck_t), intent(in) :: deck                  !! validated deck
         type(continuation_result_t), intent(out) :: res   !! branches, bifurcations, curves
         type(error_t), allocatable, intent(out) :: err    !! set-up or start failure
      end subroutine run_continuation
   end interface
end module gapbeam_continuation
