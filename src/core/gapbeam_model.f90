!> The discrete model an analysis integrates: the assembled structure (system_t) and, around
!> it, damping, contacts and forcing (model_t). Types and small pure helpers only; the model
!> builder (src/model) fills them from what the deck describes.
!>
!> Equations in coordinates relative to the base:
!>    M a + C v + K u + sum_c (-s_c f_c) e_c = s(t) q,    q = M r,  s(t) = -u_b''(t)
!> with C = beta M + gamma K (+ c_modal, modal damping) and f_c >= 0 the magnitude of contact c (see gapbeam_contact_law).
!> Two-plane models (planes = 2) and point forces add `extra` loads (add_extra_load), and the
!> supports with a circular clearance or friction act as two-dimensional contacts (rings, see
!> gapbeam_ring_contact): sum_r P_r on the (w, v) dofs of their node.
module gapbeam_model
   use gapbeam_kinds, only: dp
   use gapbeam_random_load, only: random_load_t, add_random_load
   use gapbeam_law, only: law_slot_t
   implicit none
   private
   public :: system_t, model_t, ring_xy, load_factor, global_dof, energy_norm, add_extra_load, &
      has_tube_physics, has_modal_damping

   integer, parameter :: band_kd = 3   !! semi-bandwidth of the beam matrices

   !> Global matrices and the dof map of the assembled structure.
   type :: system_t
      integer :: n_dof = 0                         !! number of free dofs
      integer :: n_node = 0                        !! number of nodes
      integer :: kd = band_kd                      !! semi-bandwidth
      integer :: planes = 1                        !! planes of motion (1 or 2)
      !> (2, n_node) index of (w, theta), or (4, n_node) of (w, theta, v, theta_v); 0: fixed.
      !> With two planes all the (w, theta) dofs come first, then all the (v, theta_v) ones, so
      !> that the band width stays kd = 3 (the planes are coupled only by the supports).
      integer, allocatable :: dof_of(:, :)
      real(dp), allocatable :: k(:, :)             !! dense stiffness [N/m ...]
      real(dp), allocatable :: m(:, :)             !! dense mass [kg ...]
      real(dp), allocatable :: k_band(:, :)        !! upper band storage of k
      real(dp), allocatable :: m_band(:, :)        !! upper band storage of m
      logical :: m_diagonal = .false.              !! true for a lumped mass matrix
      real(dp), allocatable :: r(:)                !! rigid base-translation influence vector [-]
      real(dp), allocatable :: r_v(:)              !! the same in v (zero with one plane) [-]
      real(dp), allocatable :: strain_row(:)       !! root strain = dot(strain_row, u) [-/m...]
      integer :: tip_dof = 0                       !! global index of the tip w
      integer :: tip_dof_v = 0                     !! global index of the tip v (0: none)
      real(dp) :: fibre_distance = 0.0_dp          !! strain fibre distance c [m]
      real(dp) :: element_length = 0.0_dp          !! element length [m]
      !> Timoshenko shear parameter phi = 12 EI / (k G A le^2) of the elements; 0 for
      !> Euler-Bernoulli (the rotation dofs are then dw/dx, else the section rotations) [-]
      real(dp) :: shear_phi = 0.0_dp
   end type system_t

   !> Everything the integrators need, in global dofs.
   type :: model_t
      type(system_t) :: sys                      !! K, M, r, strain row, dof map
      integer :: n = 0                           !! number of dofs
      real(dp) :: beta = 0.0_dp                  !! Rayleigh mass coefficient [1/s]
      real(dp) :: gamma = 0.0_dp                 !! Rayleigh stiffness coefficient [s]
      real(dp), allocatable :: c(:, :)           !! dense damping matrix
      !> modal damping (&damping model = 'modal'): the part M Phi diag(2 zeta omega) Phi' M of
      !> C beside the Rayleigh terms, C = beta M + gamma K + c_modal (dense); unallocated
      !> without modal damping
      real(dp), allocatable :: c_modal(:, :)
      real(dp), allocatable :: q(:)              !! load shape M r [kg]
      real(dp) :: omega = 0.0_dp                 !! forcing angular frequency [rad/s]
      real(dp) :: half_amplitude = 0.0_dp        !! A_pp / 2 [m]
      ! contacts (one-sided)
      integer :: n_contacts = 0                  !! number of one-sided contacts
      integer :: n_stops = 0                     !! number of deck stops
      integer, allocatable :: c_dof(:)           !! global dof of each contact
      real(dp), allocatable :: c_sign(:)         !! direction s = +1 or -1
      real(dp), allocatable :: c_gap(:)          !! gap [m]
      integer, allocatable :: c_law(:)           !! law code: index in `laws`
      real(dp), allocatable :: c_k(:)            !! stiffness
      real(dp), allocatable :: c_c(:)            !! damper [N s/m]
      real(dp), allocatable :: c_p(:)            !! Hertz exponent
      integer, allocatable :: c_stop(:)          !! deck stop of each contact
      integer, allocatable :: c_slot(:)          !! index of the contact's dof in slot_dof
      integer :: n_slots = 0                     !! distinct contact dofs
      integer, allocatable :: slot_dof(:)        !! global dof of each slot
      real(dp), allocatable :: stop_stiffness(:) !! resolved stiffness of each deck stop
      ! loads beyond the w-plane base motion (add_extra_load)
      logical :: extra_load = .false.            !! q_v, point forces or turbulence present
      real(dp), allocatable :: q_v(:)            !! v-plane base load shape sin(psi) M r_v [kg]
      real(dp) :: phase_v = 0.0_dp               !! phase of the v base motion [rad]
      real(dp), allocatable :: p_sin(:), p_cos(:) !! point forces: sin, cos parts [N, N m]
      type(random_load_t) :: turbulence          !! turbulence record of one draw (docs/flow.md)
      ! two-dimensional support contacts (circular clearance or friction): rings
      integer :: n_rings = 0                     !! number of ring contacts
      integer, allocatable :: r_dof(:, :)        !! (2, n_rings) global dofs of w and v
      integer, allocatable :: r_slot(:, :)       !! (2, n_rings) their slots
      logical, allocatable :: r_circular(:)      !! circular clearance (else flat)
      real(dp), allocatable :: r_normal(:, :)    !! (2, n_rings) flat: normal in (w, v)
      real(dp), allocatable :: r_centre(:, :)    !! (2, n_rings) circular: hole centre [m]
      real(dp), allocatable :: r_gap(:)          !! radial gap / gap [m]
      integer, allocatable :: r_law(:)           !! law code: index in `laws`
      real(dp), allocatable :: r_k(:), r_c(:), r_p(:)   !! normal law: stiffness, damper, exponent
      real(dp), allocatable :: r_mu(:)           !! Coulomb coefficient [-]
      real(dp), allocatable :: r_kt(:)           !! stick stiffness [N/m]
      integer, allocatable :: r_stop(:)          !! deck stop of each ring
      ! per deck stop, for the wear outputs and orbits
      real(dp), allocatable :: stop_wear(:)      !! Archard coefficient [1/Pa]
      integer, allocatable :: stop_dofs(:, :)    !! (2, n_stops) w and v dof of the stop's node
      integer, allocatable :: c_tdof(:)          !! tangent dof of each contact (0: none)
      real(dp) :: omega_max = 0.0_dp             !! highest natural frequency [rad/s]
      real(dp) :: f1_open_hz = 0.0_dp            !! first frequency, stops open [Hz]
      !> a mechanism: rigid modes (omega = 0) that only the stops hold (a pinned root, a free
      !> tip, no spring in a plane)
      logical :: mechanism = .false.
      !> a reduced model (&reduction): modal and static-mode coordinates, not nodal dofs
      logical :: reduced = .false.
      !> the contact laws, indexed by c_law and r_law (gapbeam_laws: the built-in ones, in the
      !> order of their codes)
      type(law_slot_t), allocatable :: laws(:)
   end type model_t

contains

   !> Load factor s(t) with P(t) = s(t) q: s = (A_pp/2) Omega^2 sin(Omega t) [m/s^2].
   pure real(dp) function load_factor(model, t)
      type(model_t), intent(in) :: model   !! model
      real(dp), intent(in) :: t            !! time [s]
      load_factor = model%half_amplitude * model%omega**2 * sin(model%omega * t)
   end function load_factor

   !> Add the loads beyond the w-plane base motion at time t to p: the v-plane base motion
   !> (A/2) Omega^2 sin(Omega t + phi) q_v and the point forces sin(Omega t) p_sin +
   !> cos(Omega t) p_cos, and the turbulence record. Nothing for a planar model without point
   !> forces or turbulence.
   pure subroutine add_extra_load(model, t, p)
      type(model_t), intent(in) :: model   !! model
      real(dp), intent(in) :: t            !! time [s]
      real(dp), intent(inout) :: p(:)      !! load vector [N, N m]
      if (.not. model%extra_load) return
      if (allocated(model%q_v)) p = p + model%half_amplitude * model%omega**2 &
         * sin(model%omega * t + model%phase_v) * model%q_v
      if (allocated(model%p_sin)) p = p + sin(model%omega * t) * model%p_sin &
         + cos(model%omega * t) * model%p_cos
      call add_random_load(model%turbulence, t, p)
   end subroutine add_extra_load

   !> The (w, v) values of ring r in the vector u (a state's u, v or a): a fixed-size result,
   !> so that passing them on makes no temporary array on the heap, as u(model%r_dof(:, r))
   !> does.
   pure function ring_xy(model, r, u) result(x)
      type(model_t), intent(in) :: model   !! model
      integer, intent(in) :: r             !! ring
      real(dp), intent(in) :: u(:)         !! vector over the dofs
      real(dp) :: x(2)
      x(1) = u(model%r_dof(1, r));  x(2) = u(model%r_dof(2, r))
   end function ring_xy

   !> Does the model need what only some integrators handle: two planes, extra loads, ring
   !> contacts (circular clearances, friction)?
   pure logical function has_tube_physics(model)
      type(model_t), intent(in) :: model   !! model
      has_tube_physics = model%sys%planes > 1 .or. model%extra_load .or. model%n_rings > 0
   end function has_tube_physics

   !> Does the damping have a modal part (C dense, not beta M + gamma K)?
   pure logical function has_modal_damping(model)
      type(model_t), intent(in) :: model   !! model
      has_modal_damping = allocated(model%c_modal)
   end function has_modal_damping

   !> Global index of a node dof (0 when fixed); a node outside the mesh is a programming error.
   pure integer function global_dof(sys, node, dof)
      type(system_t), intent(in) :: sys   !! assembled system
      integer, intent(in) :: node         !! node index 1..n_node
      integer, intent(in) :: dof          !! dof code (dof_w, dof_theta, dof_v, dof_theta_v)
      if (node < 1 .or. node > sys%n_node .or. dof < 1 .or. dof > size(sys%dof_of, 1)) &
         error stop 'gapbeam_model:global_dof: node or dof outside the mesh'
      global_dof = sys%dof_of(dof, node)
   end function global_dof

   !> Energy norm sqrt(u'Ku + v'Mv) of a state (or of a difference of states).
   pure real(dp) function energy_norm(model, u, v)
      type(model_t), intent(in) :: model   !! model
      real(dp), intent(in) :: u(:), v(:)   !! displacement, velocity
      energy_norm = sqrt(max(0.0_dp, dot_product(u, matmul(model%sys%k, u)) &
                             + dot_product(v, matmul(model%sys%m, v))))
   end function energy_norm
end module gapbeam_model
