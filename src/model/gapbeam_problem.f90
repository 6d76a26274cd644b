!> The model a transient analysis integrates: the assembled structure, its damping, the
!> contacts (one-sided, stiffness resolved) and the forcing.
!>
!> Equations in coordinates relative to the base:
!>    M a + C v + K u + sum_c (-s_c f_c) e_c = s(t) q,    q = M r,  s(t) = -u_b''(t)
!> with C = beta M + gamma K and f_c >= 0 the magnitude of contact c (see gapbeam_contact).
module gapbeam_problem
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_model, only: structure_t
   use gapbeam_assembly, only: system_t, assemble, global_dof
   use gapbeam_eigen, only: modes_t, solve_modes
   use gapbeam_calibration, only: calibrate_spring, first_frequency
   use gapbeam_contact, only: stop_t, law_code
   use gapbeam_damping, only: damping_t
   use gapbeam_excitation, only: forcing_t, forcing_omega
   use gapbeam_settings, only: initial_state_t
   implicit none
   private
   public :: problem_t, build_problem, resolve_stop_stiffness, initial_vectors

   !> Everything the integrators need, in global dofs.
   type :: problem_t
      type(system_t) :: sys                      !! K, M, r, strain row, dof map
      integer :: n = 0                           !! number of dofs
      real(dp) :: beta = 0.0_dp                  !! Rayleigh mass coefficient [1/s]
      real(dp) :: gamma = 0.0_dp                 !! Rayleigh stiffness coefficient [s]
      real(dp), allocatable :: c(:, :)           !! dense damping matrix
      real(dp), allocatable :: q(:)              !! load shape M r [kg]
      real(dp) :: omega = 0.0_dp                 !! forcing angular frequency [rad/s]
      real(dp) :: half_amplitude = 0.0_dp        !! A_pp / 2 [m]
      ! contacts (one-sided)
      integer :: n_contacts = 0                  !! number of one-sided contacts
      integer :: n_stops = 0                     !! number of deck stops
      integer, allocatable :: c_dof(:)           !! global dof of each contact
      real(dp), allocatable :: c_sign(:)         !! direction s = +1 or -1
      real(dp), allocatable :: c_gap(:)          !! gap [m]
      integer, allocatable :: c_law(:)           !! law code
      real(dp), allocatable :: c_k(:)            !! stiffness
      real(dp), allocatable :: c_c(:)            !! damper [N s/m]
      real(dp), allocatable :: c_p(:)            !! Hertz exponent
      integer, allocatable :: c_stop(:)          !! deck stop of each contact
      integer, allocatable :: c_slot(:)          !! index of the contact's dof in slot_dof
      integer :: n_slots = 0                     !! distinct contact dofs
      integer, allocatable :: slot_dof(:)        !! global dof of each slot
      real(dp), allocatable :: stop_stiffness(:) !! resolved stiffness of each deck stop
      real(dp) :: omega_max = 0.0_dp             !! highest natural frequency [rad/s]
      real(dp) :: f1_open_hz = 0.0_dp            !! first frequency, stops open [Hz]
   end type problem_t

contains

   !> Stiffness of each deck stop, applying the paper's rule where asked:
   !> k = rule_factor * (lowest spring at the stop dof that raises f1 to the target).
   subroutine resolve_stop_stiffness(st, stops, k, f1_open, err)
      type(structure_t), intent(in) :: st             !! linear structure
      type(stop_t), intent(in) :: stops(:)            !! deck stops
      real(dp), allocatable, intent(out) :: k(:)      !! resolved stiffness
      real(dp), intent(out) :: f1_open                !! f1 with the stops open [Hz]
      type(error_t), allocatable, intent(out) :: err  !! calibration failure
      real(dp) :: target, ks
      integer :: i
      allocate(k(size(stops)))
      call first_frequency(st, f1_open, err)
      if (allocated(err)) return
      do i = 1, size(stops)
         k(i) = stops(i)%stiffness
         if (stops(i)%rule_factor > 0.0_dp) then
            if (stops(i)%rule_f1_ratio > 0.0_dp) then
               target = stops(i)%rule_f1_ratio * f1_open
            else
               target = stops(i)%rule_f1_hz
            end if
            call calibrate_spring(st, stops(i)%node, stops(i)%dof, target, ks, err)
            if (allocated(err)) then
               err%message = 'stop ' // str(i) // ' stiffness rule: ' // err%message
               return
            end if
            k(i) = stops(i)%rule_factor * ks
         end if
      end do
   end subroutine resolve_stop_stiffness

   !> Assemble the structure and set up damping, forcing and contacts.
   subroutine build_problem(st, stops, damping, forcing, prob, err)
      type(structure_t), intent(in) :: st             !! linear structure
      type(stop_t), intent(in) :: stops(:)            !! deck stops
      type(damping_t), intent(in) :: damping          !! Rayleigh coefficients
      type(forcing_t), intent(in) :: forcing          !! base excitation
      type(problem_t), intent(out) :: prob            !! result
      type(error_t), allocatable, intent(out) :: err  !! calibration or eigen failure
      type(modes_t) :: modes
      integer :: i, j, nc, s
      real(dp) :: f1_open

      call resolve_stop_stiffness(st, stops, prob%stop_stiffness, f1_open, err)
      if (allocated(err)) return
      prob%f1_open_hz = f1_open
      call assemble(st, prob%sys)
      prob%n = prob%sys%n_dof
      call solve_modes(prob%sys, modes, err)
      if (allocated(err)) return
      prob%omega_max = sqrt(maxval(modes%omega2))
      prob%beta = damping%mass_coefficient
      prob%gamma = damping%stiffness_coefficient
      prob%c = prob%beta * prob%sys%m + prob%gamma * prob%sys%k
      prob%q = matmul(prob%sys%m, prob%sys%r)
      prob%omega = forcing_omega(forcing)
      prob%half_amplitude = 0.5_dp * forcing%amplitude_pp

      prob%n_stops = size(stops)
      nc = 0
      do i = 1, size(stops)
         nc = nc + merge(2, 1, stops(i)%side == 'both')
      end do
      prob%n_contacts = nc
      allocate(prob%c_dof(nc), prob%c_sign(nc), prob%c_gap(nc), prob%c_law(nc), prob%c_k(nc), &
               prob%c_c(nc), prob%c_p(nc), prob%c_stop(nc), prob%c_slot(nc))
      j = 0
      do i = 1, size(stops)
         do s = 1, merge(2, 1, stops(i)%side == 'both')
            j = j + 1
            prob%c_dof(j) = global_dof(prob%sys, stops(i)%node, stops(i)%dof)
            if (stops(i)%side == 'negative' .or. s == 2) then
               prob%c_sign(j) = -1.0_dp
            else
               prob%c_sign(j) = 1.0_dp
            end if
            prob%c_gap(j) = stops(i)%gap
            prob%c_law(j) = law_code(stops(i)%law)
            prob%c_k(j) = prob%stop_stiffness(i)
            prob%c_c(j) = stops(i)%damping
            prob%c_p(j) = stops(i)%exponent
            prob%c_stop(j) = i
         end do
      end do
      ! distinct dofs carrying contacts
      allocate(prob%slot_dof(nc))
      prob%n_slots = 0
      do j = 1, nc
         prob%c_slot(j) = 0
         do s = 1, prob%n_slots
            if (prob%slot_dof(s) == prob%c_dof(j)) prob%c_slot(j) = s
         end do
         if (prob%c_slot(j) == 0) then
            prob%n_slots = prob%n_slots + 1
            prob%slot_dof(prob%n_slots) = prob%c_dof(j)
            prob%c_slot(j) = prob%n_slots
         end if
      end do
      prob%slot_dof = prob%slot_dof(1:prob%n_slots)
   end subroutine build_problem

   !> Initial displacement and velocity relative to the base: zero ('rest') or the given
   !> values at the listed node dofs.
   pure subroutine initial_vectors(prob, init, u0, v0)
      type(problem_t), intent(in) :: prob            !! model
      type(initial_state_t), intent(in) :: init      !! deck's &initial
      real(dp), allocatable, intent(out) :: u0(:)    !! displacement [m, rad]
      real(dp), allocatable, intent(out) :: v0(:)    !! velocity [m/s, rad/s]
      integer :: i, g
      allocate(u0(prob%n), v0(prob%n), source=0.0_dp)
      if (init%kind /= 'given') return
      do i = 1, size(init%node)
         g = global_dof(prob%sys, init%node(i), init%dof(i))
         u0(g) = init%displacement(i)
         v0(g) = init%velocity(i)
      end do
   end subroutine initial_vectors
end module gapbeam_problem
