!> What a run changes: the state of the model at one instant.
!>
!> Displacement, velocity and acceleration are relative to the base, in the model's global
!> dofs; f holds the force magnitude of each one-sided contact (f > 0: the contact is closed).
!> The last components are the memory a stepping integrator carries from step to step (the
!> step-size level and the previous step, for the paper's extrapolated fixed point), so that
!> a stored state continues a run exactly; the exact integrator ignores them. Ring contacts
!> (two-dimensional supports) add their forces and their friction regime.
module gapbeam_state
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: state_t

   !> The state of the model at time t.
   type :: state_t
      real(dp) :: t = 0.0_dp                     !! time [s]
      real(dp), allocatable :: u(:)              !! displacement [m, rad]
      real(dp), allocatable :: v(:)              !! velocity [m/s, rad/s]
      real(dp), allocatable :: a(:)              !! acceleration [m/s^2, rad/s^2]
      real(dp), allocatable :: f(:)              !! contact force magnitudes [N]
      real(dp), allocatable :: f_prev(:)         !! contact forces one step earlier [N]
      !> the rounding u and v carry under compensated (Kahan) summation of the increments,
      !> where a method uses it (Newmark's acceleration form); unallocated: none
      real(dp), allocatable :: cu(:), cv(:)
      real(dp) :: dt_prev = 0.0_dp               !! length of the last step [s] (0: none yet)
      integer :: level = 0                       !! step-size level of the step control [-]
      integer :: comfortable = 0                 !! comfortable steps at this level [-]
      ! ring contacts (circular clearances, friction; none in a planar frictionless model)
      real(dp), allocatable :: fn(:)             !! normal force of each ring [N]
      real(dp), allocatable :: ft(:)             !! tangential force along t (signed) [N]
      !> friction regime over the next step: ring_open, ring_stick or ring_slip
      !> (gapbeam_ring_contact)
      integer, allocatable :: mode(:)
      real(dp), allocatable :: sigma(:)          !! slip: sliding direction along t (+1, -1)
      real(dp), allocatable :: anchor(:)         !! stick: tangential coordinate of the anchor [m]
   end type state_t
end module gapbeam_state
