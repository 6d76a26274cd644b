!> What an observer of a trajectory sees: pieces of it, one accepted interval at a time.
!>
!> * `piece_t`: one accepted interval [ta, tb] of a trajectory: the contact forces, velocities
!>   and onsets at its ends, the root strain at its end, and dense output in between
!>   (`sample`, `state_at`). An integrator that knows more (the exact one: integrals of the
!>   contact force and certified extrema over the piece) says so in `exact_statistics`.
!> * `observer_t`: receives the pieces in time order; `t_watch` is the instant from which it
!>   keeps statistics (integrators end a piece there and track extrema from then on).
!>
!> Integrators (gapbeam_integrator) produce pieces; the recorder (gapbeam_recorder) is the
!> observer of a transient run. Neither knows the other.
module gapbeam_observer
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: piece_t, observer_t

   !> One accepted interval [ta, tb] of a trajectory, as an observer sees it.
   type, abstract :: piece_t
      real(dp) :: ta = 0.0_dp                      !! start [s]
      real(dp) :: tb = 0.0_dp                      !! end [s]
      real(dp), allocatable :: f_a(:), f_b(:)      !! contact forces at ta (right limit), tb [N]
      real(dp), allocatable :: vabs_a(:), vabs_b(:) !! |velocity| of each contact dof there
      logical, allocatable :: onset(:)             !! the contact closes in (ta, tb] (an impact)
      real(dp), allocatable :: onset_time(:)       !! when [s]
      real(dp) :: strain_b = 0.0_dp                !! root strain at tb [-]
      real(dp) :: rate_b = 0.0_dp                  !! root strain rate at tb [1/s]
      !> The integrator gives exact statistics below (else the observer uses the end values)
      logical :: exact_statistics = .false.
      real(dp), allocatable :: int_f(:)            !! integral of f over the piece [N s]
      real(dp), allocatable :: int_f2(:)           !! integral of f^2 [N^2 s]
      real(dp), allocatable :: int_work(:)         !! integral of f |d'| [J]
      real(dp), allocatable :: t_contact(:)        !! time in contact [s]
      real(dp), allocatable :: peak(:)             !! largest force of the contact's stop [N]
      ! ring contacts (circular clearances, friction): the regime over the piece
      integer, allocatable :: r_mode(:)            !! ring_open, ring_stick or ring_slip
      real(dp), allocatable :: r_sigma(:)          !! slip direction
      real(dp), allocatable :: r_anchor(:)         !! stick anchor [m]
      real(dp), allocatable :: fn_a(:), fn_b(:)    !! normal forces at ta (right limit), tb [N]
      logical, allocatable :: r_onset(:)           !! the ring closes in (ta, tb]
      real(dp), allocatable :: r_onset_time(:)     !! when [s]
      real(dp) :: strain_min = 0.0_dp, strain_max = 0.0_dp   !! root strain range so far [-]
      real(dp) :: rate_min = 0.0_dp, rate_max = 0.0_dp       !! root strain rate range [1/s]
   contains
      procedure(sample_interface), deferred :: sample     !! outputs at an instant
      procedure(state_interface), deferred :: state_at    !! full state at an instant
   end type piece_t

   !> Watches a trajectory piece by piece.
   type, abstract :: observer_t
      real(dp) :: t_watch = 0.0_dp                 !! statistics are kept from here on [s]
   contains
      procedure(observe_interface), deferred :: observe   !! one more piece
   end type observer_t

   abstract interface
      !> Root strain, its rate, tip displacement and velocity, and each contact's force at t.
      subroutine sample_interface(self, t, strain, rate, tip, tip_velocity, force)
         import :: piece_t, dp
         class(piece_t), intent(in) :: self              !! piece
         real(dp), intent(in) :: t                       !! instant in [ta, tb] [s]
         real(dp), intent(out) :: strain, rate           !! [-], [1/s]
         real(dp), intent(out) :: tip, tip_velocity      !! [m], [m/s]
         real(dp), intent(out) :: force(:)               !! contact force magnitudes [N]
      end subroutine sample_interface

      !> Displacement and velocity of every dof at t.
      subroutine state_interface(self, t, u, v)
         import :: piece_t, dp
         class(piece_t), intent(in) :: self              !! piece
         real(dp), intent(in) :: t                       !! instant in [ta, tb] [s]
         real(dp), intent(out) :: u(:), v(:)             !! [m, rad], [m/s, rad/s]
      end subroutine state_interface

      !> Take one more piece of the trajectory.
      subroutine observe_interface(self, piece)
         import :: observer_t, piece_t
         class(observer_t), intent(inout) :: self        !! observer
         class(piece_t), intent(in) :: piece             !! the piece
      end subroutine observe_interface
   end interface
end module gapbeam_observer
