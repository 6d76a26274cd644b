!> From a validated deck to the model an analysis integrates: the stop stiffness (the paper's
!> rule where asked), the assembled structure, damping, contacts and forcing, the initial
!> state, and (when the deck asks for it) the modal reduction.
module gapbeam_model_builder
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_description, only: structure_t, stop_t, damping_t, forcing_t, law_code, &
      forcing_omega
   use gapbeam_settings, only: initial_state_t
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t, global_dof
   use gapbeam_assembly, only: assemble
   use gapbeam_eigen, only: band_frequencies
   use gapbeam_calibration, only: calibrate_spring, first_frequency
   use gapbeam_reduction, only: reduce_model, project
   implicit none
   private
   public :: build_model, build_full_model, resolve_stop_stiffness, initial_vectors

contains

   !> The model of a deck and the initial state (u0, v0) in its coordinates (modal ones when
   !> the deck asks for a reduction).
   subroutine build_model(deck, model, u0, v0, err)
      type(deck_t), intent(in) :: deck                 !! validated deck
      type(model_t), intent(out) :: model              !! model to integrate
      real(dp), allocatable, intent(out) :: u0(:), v0(:)  !! initial state
      type(error_t), allocatable, intent(out) :: err   !! calibration, eigen or reduction failure
      type(model_t) :: full
      real(dp), allocatable :: basis(:, :), uf(:), vf(:)
      call build_full_model(deck%structure, deck%stops, deck%damping, deck%forcing, full, err)
      if (allocated(err)) return
      call initial_vectors(full, deck%initial, uf, vf)
      if (deck%reduction%kind /= 'modal') then
         model = full;  u0 = uf;  v0 = vf
         return
      end if
      call reduce_model(full, deck%reduction%n_modes, deck%reduction%static_correction, model, &
                        basis, err)
      if (allocated(err)) then
         err%message = 'group &reduction: ' // err%message
         return
      end if
      call project(full, basis, uf, u0, err)
      if (.not. allocated(err)) call project(full, basis, vf, v0, err)
      if (allocated(err)) err%message = 'group &reduction: ' // err%message
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
            call calibrate_spring(st, stops(i)%node, stops(i)%dof, target, ks, err)
            if (allocated(err)) then
               err%message = 'stop ' // str(i) // ' stiffness rule: ' // err%message
               return
            end if
            k(i) = stops(i)%rule_factor * ks
         end if
      end do
   end subroutine resolve_stop_stiffness

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

      call resolve_stop_stiffness(st, stops, model%stop_stiffness, f1_open, err)
      if (allocated(err)) return
      model%f1_open_hz = f1_open
      call assemble(st, model%sys)
      model%n = model%sys%n_dof
      call band_frequencies(model%sys, omega2, err)
      if (allocated(err)) return
      model%omega_max = sqrt(maxval(omega2))
      model%beta = damping%mass_coefficient
      model%gamma = damping%stiffness_coefficient
      model%c = model%beta * model%sys%m + model%gamma * model%sys%k
      model%q = matmul(model%sys%m, model%sys%r)
      model%omega = forcing_omega(forcing)
      model%half_amplitude = 0.5_dp * forcing%amplitude_pp
      call set_contacts(stops, model)
   end subroutine build_full_model

   !> One-sided contacts of the deck stops (two for a stop on both sides) and the distinct
   !> dofs that carry them (slots).
   subroutine set_contacts(stops, model)
      type(stop_t), intent(in) :: stops(:)            !! deck stops
      type(model_t), intent(inout) :: model           !! assembled model, stiffness resolved
      integer :: i, j, nc, s
      model%n_stops = size(stops)
      nc = 0
      do i = 1, size(stops)
         nc = nc + merge(2, 1, stops(i)%side == 'both')
      end do
      model%n_contacts = nc
      allocate(model%c_dof(nc), model%c_sign(nc), model%c_gap(nc), model%c_law(nc), &
               model%c_k(nc), model%c_c(nc), model%c_p(nc), model%c_stop(nc), model%c_slot(nc))
      j = 0
      do i = 1, size(stops)
         do s = 1, merge(2, 1, stops(i)%side == 'both')
            j = j + 1
            model%c_dof(j) = global_dof(model%sys, stops(i)%node, stops(i)%dof)
            if (stops(i)%side == 'negative' .or. s == 2) then
               model%c_sign(j) = -1.0_dp
            else
               model%c_sign(j) = 1.0_dp
            end if
            model%c_gap(j) = stops(i)%gap
            model%c_law(j) = law_code(stops(i)%law)
            model%c_k(j) = model%stop_stiffness(i)
            model%c_c(j) = stops(i)%damping
            model%c_p(j) = stops(i)%exponent
            model%c_stop(j) = i
         end do
      end do
      allocate(model%slot_dof(nc))
      model%n_slots = 0
      do j = 1, nc
         model%c_slot(j) = 0
         do s = 1, model%n_slots
            if (model%slot_dof(s) == model%c_dof(j)) model%c_slot(j) = s
         end do
         if (model%c_slot(j) == 0) then
            model%n_slots = model%n_slots + 1
            model%slot_dof(model%n_slots) = model%c_dof(j)
            model%c_slot(j) = model%n_slots
         end if
      end do
      model%slot_dof = model%slot_dof(1:model%n_slots)
   end subroutine set_contacts

   !> Initial displacement and velocity relative to the base: zero ('rest') or the given
   !> values at the listed node dofs.
   pure subroutine initial_vectors(model, init, u0, v0)
      type(model_t), intent(in) :: model             !! model
      type(initial_state_t), intent(in) :: init      !! deck's &initial
      real(dp), allocatable, intent(out) :: u0(:)    !! displacement [m, rad]
      real(dp), allocatable, intent(out) :: v0(:)    !! velocity [m/s, rad/s]
      integer :: i, g
      allocate(u0(model%n), v0(model%n), source=0.0_dp)
      if (init%kind /= 'given') return
      do i = 1, size(init%node)
         g = global_dof(model%sys, init%node(i), init%dof(i))
         u0(g) = init%displacement(i)
         v0(g) = init%velocity(i)
      end do
   end subroutine initial_vectors
end module gapbeam_model_builder
