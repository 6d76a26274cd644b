!> From a validated deck to the model an analysis integrates: the stop stiffness (the paper's
!> rule where asked), the assembled structure, damping, contacts and forcing, the initial
!> state, and (when the deck asks for it) the modal reduction.
module gapbeam_model_builder
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str, fatal_error
   use gapbeam_laws, only: builtin_laws, law_index
   use gapbeam_description, only: structure_t, stop_t, damping_t, forcing_t, &
      forcing_omega, stop_is_ring, dof_w, dof_v, dof_theta, dof_theta_v, spring_t, &
      rigid_planes
   use gapbeam_settings, only: initial_state_t
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t, system_t, global_dof
   use gapbeam_assembly, only: assemble
   use gapbeam_eigen, only: band_frequencies
   use gapbeam_calibration, only: calibrate_spring, first_frequency
   use gapbeam_reduction, only: reduce_model, project
   use gapbeam_reduction_rule, only: reduction_info_t, auto_cutoff
   use gapbeam_flow_load, only: turbulence_record, add_fluid_elastic
   use gapbeam_modal_damping, only: apply_modal_damping, first_plane_mass
   implicit none
   private
   public :: build_model, build_full_model, resolve_stop_stiffness, initial_vectors

contains

   !> The model of a deck and the initial state (u0, v0) in its coordinates (modal ones when
   !> the deck asks for a reduction: kind 'modal' with n_modes or cutoff_hz, kind 'auto' with
   !> the cut-off of gapbeam_reduction_rule); `info` says what the reduction kept. The flow's
   !> forces (fluid-elastic damping, the turbulence record of draw `draw`) are added in the
   !> model's own coordinates.
   subroutine build_model(deck, model, u0, v0, err, info, draw, basis_out)
      type(deck_t), intent(in) :: deck                 !! validated deck
      type(model_t), intent(out) :: model              !! model to integrate
      real(dp), allocatable, intent(out) :: u0(:), v0(:)  !! initial state
      type(error_t), allocatable, intent(out) :: err   !! calibration, eigen or reduction failure
      type(reduction_info_t), intent(out), optional :: info  !! the reduction's choices
      integer, intent(in), optional :: draw            !! turbulence draw (default 1)
      !> the reduced basis (u = basis z); unallocated for the full model
      real(dp), allocatable, intent(out), optional :: basis_out(:, :)
      type(model_t) :: full
      type(reduction_info_t) :: ri
      real(dp), allocatable :: basis(:, :), uf(:), vf(:)
      integer :: d
      d = 1
      if (present(draw)) d = draw
      call build_full_model(deck%structure, deck%stops, deck%damping, deck%forcing, full, err)
      if (allocated(err)) return
      call initial_vectors(full, deck%initial, uf, vf)
      ri%kind = deck%reduction%kind
      ri%n_full = full%n
      if (deck%reduction%kind /= 'modal' .and. deck%reduction%kind /= 'auto') then
         model = full;  u0 = uf;  v0 = vf
         ri%n_reduced = full%n
         if (present(info)) info = ri
         call add_fluid_elastic(deck, full, model, err)
         if (allocated(err)) return
         if (deck%turbulence%spectrum /= 'none') then
            call turbulence_record(deck, full%sys, d, model%turbulence, err)
            model%extra_load = .true.
         end if
         return
      end if
      ri%cutoff_hz = deck%reduction%cutoff_hz
      if (deck%reduction%kind == 'auto') then
         call auto_cutoff(full, deck%solver%tolerance, ri, err)
         if (allocated(err)) then
            err%message = 'group &reduction: ' // err%message
            return
         end if
      end if
      call reduce_model(full, deck%reduction%n_modes, deck%reduction%static_correction, model, &
                        basis, err, cutoff_hz=ri%cutoff_hz, modes_kept=ri%modes_per_plane, &
                        highest_hz=ri%highest_mode_hz, modes_available=ri%modes_available)
      if (allocated(err)) then
         err%message = 'group &reduction: ' // err%message
         return
      end if
      call reduced_modal_damping(full, basis, deck%damping, model, err)
      if (allocated(err)) return
      ri%n_reduced = model%n
      ri%planes = full%sys%planes
      ri%n_static = model%n / full%sys%planes - ri%modes_per_plane
      ri%f_max_hz = model%omega_max / (2.0_dp * pi)
      if (present(info)) info = ri
      call project(full, basis, uf, u0, err)
      if (.not. allocated(err)) call project(full, basis, vf, v0, err)
      if (allocated(err)) then
         err%message = 'group &reduction: ' // err%message
         return
      end if
      call add_fluid_elastic(deck, full, model, err, basis)
      if (allocated(err)) return
      if (deck%turbulence%spectrum /= 'none') then
         call turbulence_record(deck, full%sys, d, model%turbulence, err, basis)
         model%extra_load = .true.
      end if
      if (present(basis_out)) call move_alloc(basis, basis_out)
   end subroutine build_model

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
            ! the rule acts in the stop's plane: a two-plane structure is calibrated as the
            ! planar structure of that plane (its f1 is the plane's)
            if (st%beam%planes > 1) then
               call calibrate_spring(plane_structure(st, stops(i)%dof), stops(i)%node, &
                  merge(dof_w, dof_theta, stops(i)%dof == dof_w .or. stops(i)%dof == dof_v), &
                  target, ks, err)
            else
               call calibrate_spring(st, stops(i)%node, stops(i)%dof, target, ks, err)
            end if
            if (allocated(err)) then
               err%message = 'stop ' // str(i) // ' stiffness rule: ' // err%message
               return
            end if
            k(i) = stops(i)%rule_factor * ks
         end if
      end do
   end subroutine resolve_stop_stiffness

   !> The planar structure of the plane of a dof of a two-plane structure: one plane, with the
   !> springs of that plane (those of the second plane moved to its first-plane dofs).
   function plane_structure(st, dof) result(ps)
      type(structure_t), intent(in) :: st      !! two-plane structure
      integer, intent(in) :: dof               !! a dof code of the plane
      type(structure_t) :: ps
      logical :: second
      integer :: k
      type(spring_t), allocatable :: keep(:)
      ps = st
      ps%beam%planes = 1
      second = dof == dof_v .or. dof == dof_theta_v
      allocate(keep(0))
      do k = 1, size(st%springs)
         if (second .neqv. (st%springs(k)%dof == dof_v .or. st%springs(k)%dof == dof_theta_v)) &
            cycle
         keep = [keep, st%springs(k)]
         if (second) keep(size(keep))%dof = keep(size(keep))%dof - 2
      end do
      ps%springs = keep
   end function plane_structure

   !> Assemble the structure and set up damping, forcing and contacts (full finite element
   !> model, no reduction).
   subroutine build_full_model(st, stops, damping, forcing, model, err)
      type(structure_t), intent(in) :: st             !! linear structure
      type(stop_t), intent(in) :: stops(:)            !! deck stops
      type(damping_t), intent(in) :: damping          !! Rayleigh coefficients
      type(forcing_t), intent(in) :: forcing          !! base excitation
      type(model_t), intent(out) :: model             !! result
      type(error_t), allocatable, intent(out) :: err  !! calibration or eigen failure
      real(dp), allocatable :: omega2(:)
      real(dp) :: f1_open
      logical :: rigid(2), held(2)

      call resolve_stop_stiffness(st, stops, model%stop_stiffness, f1_open, err)
      if (allocated(err)) return
      model%f1_open_hz = f1_open
      call assemble(st, model%sys)
      model%n = model%sys%n_dof
      call rigid_planes(st, stops, rigid, held)       ! held: the deck reader checked it
      model%mechanism = any(rigid)
      call band_frequencies(model%sys, omega2, err, mechanism=model%mechanism)
      if (allocated(err)) return
      model%omega_max = sqrt(maxval(omega2))
      model%beta = damping%mass_coefficient
      model%gamma = damping%stiffness_coefficient
      model%c = model%beta * model%sys%m + model%gamma * model%sys%k
      if (damping%model == 'modal') then
         if (model%sys%planes > 1) then
            call apply_modal_damping(model, damping, err, first_plane_mass(model%sys))
         else
            call apply_modal_damping(model, damping, err)
         end if
         if (allocated(err)) return
      end if
      model%q = matmul(model%sys%m, model%sys%r)
      model%omega = forcing_omega(forcing)
      model%half_amplitude = 0.5_dp * forcing%amplitude_pp
      call set_loads(forcing, model)
      call set_contacts(stops, model)
   end subroutine build_full_model

   !> Modal damping of a reduced model (damping%model = 'modal'; nothing otherwise): on the
   !> reduced model's own modes, the planes of a two-plane model told apart by the mass of the
   !> first plane projected on the basis, B' M_w B.
   subroutine reduced_modal_damping(full, basis, damping, red, err)
      type(model_t), intent(in) :: full               !! the finite element model
      real(dp), intent(in) :: basis(:, :)             !! physical u = basis z
      type(damping_t), intent(in) :: damping          !! the deck's damping
      type(model_t), intent(inout) :: red             !! reduced model (beta, gamma set)
      type(error_t), allocatable, intent(out) :: err  !! eigen failure
      if (damping%model /= 'modal') return
      if (full%sys%planes > 1) then
         call apply_modal_damping(red, damping, err, matmul(transpose(basis), &
                                  matmul(first_plane_mass(full%sys), basis)))
      else
         call apply_modal_damping(red, damping, err)
      end if
   end subroutine reduced_modal_damping

   !> The loads beyond the w-plane base motion: the direction and phase of a two-plane base
   !> motion and the harmonic point forces (add_extra_load).
   subroutine set_loads(forcing, model)
      type(forcing_t), intent(in) :: forcing          !! deck forcing
      type(model_t), intent(inout) :: model           !! model, q set for the w plane
      real(dp) :: psi, ph
      integer :: k, g
      if (forcing%direction_deg /= 0.0_dp) then
         psi = forcing%direction_deg * pi / 180.0_dp
         model%q = cos(psi) * model%q
         model%q_v = sin(psi) * matmul(model%sys%m, model%sys%r_v)
         model%phase_v = forcing%phase_v_deg * pi / 180.0_dp
         model%extra_load = .true.
      end if
      if (allocated(forcing%forces)) then
         if (size(forcing%forces) > 0) then
            allocate(model%p_sin(model%n), model%p_cos(model%n), source=0.0_dp)
            do k = 1, size(forcing%forces)
               g = global_dof(model%sys, forcing%forces(k)%node, forcing%forces(k)%dof)
               ph = forcing%forces(k)%phase_deg * pi / 180.0_dp
               if (g == 0) cycle
               model%p_sin(g) = model%p_sin(g) + forcing%forces(k)%amplitude * cos(ph)
               model%p_cos(g) = model%p_cos(g) + forcing%forces(k)%amplitude * sin(ph)
            end do
            model%extra_load = .true.
         end if
      end if
   end subroutine set_loads

   !> Contacts of the deck stops: one-sided contacts along a dof (two for a stop on both sides)
   !> and ring contacts (a circular clearance; a flat stop with friction, one per side); the
   !> distinct dofs that carry them (slots); per stop its node's (w, v) dofs and wear
   !> coefficient.
   subroutine set_contacts(stops, model)
      type(stop_t), intent(in) :: stops(:)            !! deck stops
      type(model_t), intent(inout) :: model           !! assembled model, stiffness resolved
      integer :: i, j, nc, nr, s, ns, k, tw
      integer, allocatable :: dofs(:)
      logical :: ring
      model%n_stops = size(stops)
      model%laws = builtin_laws()
      nc = 0;  nr = 0
      do i = 1, size(stops)
         ns = merge(2, 1, stops(i)%side == 'both' .and. stops(i)%shape /= 'circular')
         if (stop_is_ring(stops(i))) then
            nr = nr + ns
         else
            nc = nc + ns
         end if
      end do
      model%n_contacts = nc
      model%n_rings = nr
      allocate(model%c_dof(nc), model%c_sign(nc), model%c_gap(nc), model%c_law(nc), &
               model%c_k(nc), model%c_c(nc), model%c_p(nc), model%c_stop(nc), model%c_slot(nc), &
               model%c_tdof(nc))
      allocate(model%r_dof(2, nr), model%r_slot(2, nr), model%r_circular(nr), &
               model%r_normal(2, nr), model%r_centre(2, nr), model%r_gap(nr), model%r_law(nr), &
               model%r_k(nr), model%r_c(nr), model%r_p(nr), model%r_mu(nr), model%r_kt(nr), &
               model%r_stop(nr))
      allocate(model%stop_wear(size(stops)), model%stop_dofs(2, size(stops)))
      j = 0;  k = 0
      do i = 1, size(stops)
         model%stop_wear(i) = stops(i)%wear_coefficient
         model%stop_dofs(1, i) = global_dof(model%sys, stops(i)%node, dof_w)
         model%stop_dofs(2, i) = 0
         if (model%sys%planes > 1) model%stop_dofs(2, i) = global_dof(model%sys, stops(i)%node, &
                                                                      dof_v)
         ring = stop_is_ring(stops(i))
         ns = merge(2, 1, stops(i)%side == 'both' .and. stops(i)%shape /= 'circular')
         do s = 1, ns
            if (ring) then
               k = k + 1
               call set_ring(stops(i), i, s, model%stop_stiffness(i), model, k)
               cycle
            end if
            j = j + 1
            model%c_dof(j) = global_dof(model%sys, stops(i)%node, stops(i)%dof)
            if (stops(i)%side == 'negative' .or. s == 2) then
               model%c_sign(j) = -1.0_dp
            else
               model%c_sign(j) = 1.0_dp
            end if
            model%c_gap(j) = stops(i)%gap
            model%c_law(j) = law_index(stops(i)%law, model%laws)
            model%c_k(j) = model%stop_stiffness(i)
            model%c_c(j) = stops(i)%damping
            model%c_p(j) = stops(i)%exponent
            model%c_stop(j) = i
            ! the other plane's translation slides along the stop
            model%c_tdof(j) = 0
            if (stops(i)%dof == dof_w) model%c_tdof(j) = model%stop_dofs(2, i)
            if (stops(i)%dof == dof_v) model%c_tdof(j) = model%stop_dofs(1, i)
         end do
      end do
      ! slots: the distinct dofs of the scalar contacts, then the rings' (w, v)
      dofs = [model%c_dof, [(model%r_dof(:, k), k = 1, nr)]]
      allocate(model%slot_dof(size(dofs)))
      model%n_slots = 0
      do j = 1, size(dofs)
         tw = 0
         do s = 1, model%n_slots
            if (model%slot_dof(s) == dofs(j)) tw = s
         end do
         if (tw == 0) then
            model%n_slots = model%n_slots + 1
            model%slot_dof(model%n_slots) = dofs(j)
            tw = model%n_slots
         end if
         if (j <= nc) then
            model%c_slot(j) = tw
         else
            model%r_slot(2 - mod(j - nc, 2), (j - nc + 1) / 2) = tw
         end if
      end do
      model%slot_dof = model%slot_dof(1:model%n_slots)
   end subroutine set_contacts

   !> Ring contact k of deck stop i (side s of a flat stop with friction).
   subroutine set_ring(st, i, s, k_stop, model, k)
      type(stop_t), intent(in) :: st                  !! the deck stop
      integer, intent(in) :: i, s                     !! stop index, side (1 or 2)
      real(dp), intent(in) :: k_stop                  !! resolved normal stiffness
      type(model_t), intent(inout) :: model           !! model
      integer, intent(in) :: k                        !! ring index
      real(dp) :: sgn
      model%r_dof(:, k) = [global_dof(model%sys, st%node, dof_w), &
                           global_dof(model%sys, st%node, dof_v)]
      model%r_circular(k) = st%shape == 'circular'
      model%r_centre(:, k) = 0.0_dp
      model%r_normal(:, k) = 0.0_dp
      if (model%r_circular(k)) then
         model%r_centre(:, k) = [st%offset_w, st%offset_v]
      else
         sgn = merge(-1.0_dp, 1.0_dp, st%side == 'negative' .or. s == 2)
         if (st%dof == dof_v) then
            model%r_normal(:, k) = [0.0_dp, sgn]
         else
            model%r_normal(:, k) = [sgn, 0.0_dp]
         end if
      end if
      model%r_gap(k) = st%gap
      model%r_law(k) = law_index(st%law, model%laws)
      model%r_k(k) = k_stop
      model%r_c(k) = st%damping
      model%r_p(k) = st%exponent
      model%r_mu(k) = st%friction
      model%r_kt(k) = st%tangential_stiffness
      ! a law whose k is a stiffness in N/m gives the stick stiffness by default (the reader
      ! refuses the others without one)
      if (model%r_kt(k) <= 0.0_dp) model%r_kt(k) = k_stop
      model%r_stop(k) = i
   end subroutine set_ring

   !> Initial displacement and velocity relative to the base, in the full model's dofs: zero
   !> ('rest'), the given values at the listed node dofs ('given'), a rigid field at every
   !> free dof ('rotation': w = angle x, theta = angle, w' = Omega x, theta' = Omega, and the
   !> same in v; 'translation': w' = V, v' = V_v), or the file's final state ('file', read and
   !> checked against the structure by the deck reader). A rigid field's values at the dofs
   !> the supports fix are not dofs of the model: the supports hold them.
   pure subroutine initial_vectors(model, init, u0, v0)
      type(model_t), intent(in) :: model             !! the full model
      type(initial_state_t), intent(in) :: init      !! deck's &initial
      real(dp), allocatable, intent(out) :: u0(:)    !! displacement [m, rad]
      real(dp), allocatable, intent(out) :: v0(:)    !! velocity [m/s, rad/s]
      integer :: i, g
      allocate(u0(model%n), v0(model%n), source=0.0_dp)
      select case (init%kind)
      case ('given')
         do i = 1, size(init%node)
            g = global_dof(model%sys, init%node(i), init%dof(i))
            u0(g) = init%displacement(i)
            v0(g) = init%velocity(i)
         end do
      case ('rotation')
         call rigid_field(model%sys, 1, init%angle, 0.0_dp, u0)
         call rigid_field(model%sys, 1, init%angular_velocity, 0.0_dp, v0)
         if (model%sys%planes > 1) then
            call rigid_field(model%sys, 3, init%angle_v, 0.0_dp, u0)
            call rigid_field(model%sys, 3, init%angular_velocity_v, 0.0_dp, v0)
         end if
      case ('translation')
         call rigid_field(model%sys, 1, 0.0_dp, init%translation_velocity, v0)
         if (model%sys%planes > 1) &
            call rigid_field(model%sys, 3, 0.0_dp, init%translation_velocity_v, v0)
      case ('file')
         if (size(init%file_u) == model%n) then
            u0 = init%file_u;  v0 = init%file_v
         end if
      end select
   end subroutine initial_vectors

   !> The rigid field a + b x in one plane (first local dof `j0`: 1 for w, 3 for v) at every
   !> free dof: the translation dof of node i (x = (i - 1) le) gets translation + slope x,
   !> its rotation dof the slope. Fixed dofs are skipped.
   pure subroutine rigid_field(sys, j0, slope, translation, x)
      type(system_t), intent(in) :: sys              !! dof map, element length
      integer, intent(in) :: j0                      !! 1 (w, theta) or 3 (v, theta_v)
      real(dp), intent(in) :: slope                  !! the rotation [rad or rad/s]
      real(dp), intent(in) :: translation            !! the translation [m or m/s]
      real(dp), intent(inout) :: x(:)                !! field, the plane's dofs added
      integer :: i, g
      real(dp) :: xi
      do i = 1, sys%n_node
         xi = real(i - 1, dp) * sys%element_length
         g = sys%dof_of(j0, i)
         if (g > 0) x(g) = x(g) + translation + slope * xi
         g = sys%dof_of(j0 + 1, i)
         if (g > 0) x(g) = x(g) + slope
      end do
   end subroutine rigid_field
end module gapbeam_model_builder
