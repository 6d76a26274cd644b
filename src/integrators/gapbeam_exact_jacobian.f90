!> The Jacobian of the exact integrator's flow (issue 14: shooting, Floquet multipliers).
!>
!> `advance_jacobian` advances the state exactly as `advance` does, with an observer that logs
!> the linear segments (their instants, contact configurations and end states; watching off,
!> so that no statistics are computed), and composes the transition matrices e^{A_m tau} of
!> the segments with the saltation matrices of the switches (gapbeam_transition). The
!> integrator's own event search and closed form are untouched: the Jacobian depends only on
!> the switching instants and configurations it finds.
submodule (gapbeam_exact) gapbeam_exact_jacobian
   use gapbeam_transition, only: linear_parts_t, switch_log_t, setup_linear_parts, &
      log_segment, flow_jacobian, reduce_state
   implicit none

   !> Logs the segments of an advance.
   type, extends(observer_t) :: segment_logger_t
      type(linear_parts_t) :: lp            !! condensed structure
      type(switch_log_t) :: log             !! the segments
      real(dp), allocatable :: u(:), v(:)   !! workspaces
   contains
      procedure :: observe => logger_observe
   end type segment_logger_t

contains

   module subroutine exact_advance_jacobian(self, state, t_target, jac, err)
      class(exact_integrator_t), intent(inout), target :: self   !! integrator
      type(state_t), intent(inout) :: state            !! state, at t_target on return
      real(dp), intent(in) :: t_target                 !! target time [s]
      real(dp), allocatable, intent(out) :: jac(:, :)  !! (2 nr, 2 nr) Jacobian
      type(error_t), allocatable, intent(out) :: err   !! configuration failure
      type(segment_logger_t) :: logger
      call setup_linear_parts(self%model, logger%lp, err)
      if (allocated(err)) return
      logger%t_watch = huge(1.0_dp)          ! no statistics: segments only
      allocate(logger%u(self%model%n), logger%v(self%model%n))
      call self%advance(state, t_target, logger, err)
      if (allocated(err)) return
      call flow_jacobian(logger%lp, self%model, logger%log, jac, err)
   end subroutine exact_advance_jacobian

   !> Log one piece: its interval, configuration and end state.
   subroutine logger_observe(self, piece)
      class(segment_logger_t), intent(inout) :: self   !! logger
      class(piece_t), intent(in) :: piece              !! the piece
      select type (piece)
      type is (exact_piece_t)
         call piece%state_at(piece%tb, self%u, self%v)
         call log_segment(self%log, piece%ta, piece%tb, piece%mask, &
                          reduce_state(self%lp, self%u, self%v))
      class default
         error stop 'gapbeam_exact_jacobian: a piece not of the exact integrator'
      end select
   end subroutine logger_observe
end submodule gapbeam_exact_jacobian
