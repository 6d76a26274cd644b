!> The turbulence record of one draw on a model (docs/flow.md): the load shapes of the deck's
!> turbulence on the full structure (gapbeam_turbulence: the nodal cross-spectral matrix
!> factored once), projected on the reduced model's basis when there is one (the generalised
!> load B' L xi), and the harmonics of the band [first frequency of the spectrum, cut-off] at
!> the deck's resolution (default: 1 / the run's length, so that the record does not repeat).
!> A draw is a pure function of (seed, draw, plane, component, harmonic): the same on any
!> thread, in any order, on the full and on the reduced model.
module gapbeam_flow_load
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: system_t, model_t
   use gapbeam_description, only: forcing_omega, beam_mass_per_length
   use gapbeam_flow_results, only: flow_modes_t
   use gapbeam_fluid_elastic, only: flow_modes, fluid_elastic_damping
   use gapbeam_random_load, only: random_load_t
   use gapbeam_turbulence, only: load_shapes, spectrum_band, turbulence_psd, generate_record
   implicit none
   private
   public :: turbulence_record, deck_flow_modes, add_fluid_elastic

   !> substreams: plane p, component m of that plane -> p * plane_stride + m
   integer, parameter :: plane_stride = 1048576

contains

   !> The frequency step df of the record: the deck's, or 1 / (transient + record periods of
   !> the forcing) [Hz].
   pure real(dp) function record_resolution(deck) result(df)
      type(deck_t), intent(in) :: deck   !! deck
      df = deck%turbulence%frequency_resolution_hz
      if (df > 0.0_dp) return
      df = forcing_omega(deck%forcing) / (2.0_dp * pi) &
           / real(deck%solver%transient_periods + deck%solver%record_periods, dp)
   end function record_resolution

   !> The record of draw `draw` of the deck's turbulence on the structure `sys` (the full
   !> model's), in the coordinates of `basis` when given (u = basis z).
   subroutine turbulence_record(deck, sys, draw, rl, err, basis)
      type(deck_t), intent(in) :: deck                   !! deck with a turbulence spectrum
      type(system_t), intent(in) :: sys                  !! the full structure
      integer, intent(in) :: draw                        !! draw number, 1, 2, ...
      type(random_load_t), intent(out) :: rl             !! the record
      type(error_t), allocatable, intent(out) :: err     !! eigen failure, record too large
      real(dp), intent(in), optional :: basis(:, :)      !! (n_full, n_red) reduced basis
      real(dp), allocatable :: shapes(:, :), psd_k(:)
      integer, allocatable :: plane_of(:), rank_in_plane(:)
      real(dp) :: df, f_lo, f_hi
      integer :: k_lo, k_hi, k
      call load_shapes(sys, deck%turbulence, shapes, plane_of, rank_in_plane, err)
      if (allocated(err)) return
      df = record_resolution(deck)
      call spectrum_band(deck%turbulence, deck%flow, f_lo, f_hi)
      k_lo = max(1, ceiling(f_lo / df * (1.0_dp - 1.0e-12_dp)))
      k_hi = floor(f_hi / df * (1.0_dp + 1.0e-12_dp))
      if (k_hi < k_lo .or. size(shapes, 2) == 0) then
         call fatal_error(err, 'group &turbulence: no harmonic of the record in the band ' &
            // str(f_lo) // ' .. ' // str(f_hi) // ' Hz at the resolution ' // str(df) &
            // ' Hz, or no loaded dof: lower frequency_resolution_hz or widen the band')
         return
      end if
      psd_k = [(turbulence_psd(deck%turbulence, deck%flow, real(k, dp) * df), k = k_lo, k_hi)]
      if (present(basis)) shapes = matmul(transpose(basis), shapes)
      call generate_record(shapes, plane_of * plane_stride + rank_in_plane, psd_k, k_lo, df, &
         deck%turbulence%points_per_cycle, deck%turbulence%seed, draw, rl, err)
      if (allocated(err)) err%message = 'group &turbulence: ' // err%message
   end subroutine turbulence_record

   !> The modes of the deck's open structure `sys` (the full model's) with their fluid-elastic
   !> data at &flow velocity: structural damping from the Rayleigh coefficients (beta, gamma)
   !> and, with &damping model = 'modal', the modal ratios.
   subroutine deck_flow_modes(deck, sys, beta, gamma, fm, err)
      type(deck_t), intent(in) :: deck                 !! deck
      type(system_t), intent(in) :: sys                !! the full structure
      real(dp), intent(in) :: beta, gamma              !! resolved Rayleigh coefficients
      type(flow_modes_t), intent(out) :: fm            !! modes with U_c, zeta_fe
      type(error_t), allocatable, intent(out) :: err   !! eigen failure
      if (deck%damping%model == 'modal' .and. allocated(deck%damping%modal_ratios)) then
         call flow_modes(sys, deck%flow, beam_mass_per_length(deck%structure%beam), beta, &
                         gamma, fm, err, deck%damping%modal_ratios)
      else
         call flow_modes(sys, deck%flow, beam_mass_per_length(deck%structure%beam), beta, &
                         gamma, fm, err)
      end if
      if (allocated(err)) err%message = 'group &flow: ' // err%message
   end subroutine deck_flow_modes

   !> Add the fluid-elastic damping of &flow (Connors: a negative damping ratio per mode of
   !> the open structure) to the model's dense damping: C = beta M + gamma K + c_modal with
   !> c_modal += C_fe (B' C_fe B on a reduced model). Nothing without flow or with
   !> fluid_elastic = 'none'.
   subroutine add_fluid_elastic(deck, full, model, err, basis)
      type(deck_t), intent(in) :: deck                 !! deck
      type(model_t), intent(in) :: full                !! the finite element model
      type(model_t), intent(inout) :: model            !! the model integrated (may be full)
      type(error_t), allocatable, intent(out) :: err   !! eigen failure
      real(dp), intent(in), optional :: basis(:, :)    !! reduced basis (u = basis z)
      type(flow_modes_t) :: fm
      real(dp), allocatable :: cfe(:, :)
      if (.not. (deck%flow%velocity > 0.0_dp .and. deck%flow%fluid_elastic == 'connors')) return
      call deck_flow_modes(deck, full%sys, full%beta, full%gamma, fm, err)
      if (allocated(err)) return
      cfe = fluid_elastic_damping(full%sys, fm)
      if (present(basis)) cfe = matmul(transpose(basis), matmul(cfe, basis))
      if (.not. allocated(model%c_modal)) allocate(model%c_modal(model%n, model%n), source=0.0_dp)
      model%c_modal = model%c_modal + cfe
      model%c = model%beta * model%sys%m + model%gamma * model%sys%k + model%c_modal
   end subroutine add_fluid_elastic
end module gapbeam_flow_load
