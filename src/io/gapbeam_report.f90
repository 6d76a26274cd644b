!> Result files of the modes, calibrate and transient analyses: HDF5 (every dataset described
!> by the output catalogue) and gnuplot-ready text tables. The files of one run form an output
!> set (gapbeam_output_set): written under temporary names, then put in place together, or
!> not at all; the HDF5 file lists them at /run/files and carries the effective deck at /deck.
!>
!> Times are those of the whole trajectory: a transient run whose record was extended (the
!> settling test, a converging orbit) integrated `/diagnostics/transient_periods` forcing
!> periods before its final record, and `/history/time`, `/poincare/time`, `/final/time` and
!> the first contact times count from the start of the run, t = 0.
module gapbeam_report
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_xdmf, only: make_xdmf, write_xdmf_datasets
   use gapbeam_output_set, only: output_set_t
   use gapbeam_files, only: append_text
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: system_t, model_t
   use gapbeam_description, only: dof_w
   use gapbeam_results, only: modes_t, transient_result_t, point_result_t, label_text, &
      certificate_text, on_trajectory_clock
   use gapbeam_parameters, only: run_parameters, stiffness_units
   use gapbeam_deflection, only: shape_points, deflection, nodal_values, mode_shape_table, &
      shape_curve_table
   use gapbeam_file_info, only: write_parameter_set, write_structure, write_model
   use gapbeam_flow_results, only: wear_depth_t, draw_statistics_t, flow_modes_t, response_psd_t
   use gapbeam_psd_output, only: write_response_psd
   use gapbeam_deck_rules_flow, only: deck_wear_depth
   use gapbeam_point_fields, only: int_names, real_names, text_names, int_fields, real_fields, &
      text_field, array_names, array_extent, array_type, array_field
   implicit none
   private
   public :: write_modes, write_transient, write_calibration

   !> Points per element of the mode shape curves (Hermite shape functions).
   integer, parameter :: curve_points = 16

contains

   !> Modal analysis results: PREFIX.h5, PREFIX.modes.dat, .shapes.dat, .shape_curves.dat.
   subroutine write_modes(deck, sys, modes, stop_stiffness, err, fm)
      type(deck_t), intent(in) :: deck                 !! the deck (output prefix, text)
      type(system_t), intent(in) :: sys                !! assembled structure
      type(modes_t), intent(in) :: modes               !! modes
      real(dp), intent(in) :: stop_stiffness(:)        !! resolved stop stiffness (may be empty)
      type(error_t), allocatable, intent(out) :: err   !! I/O failure; no file changed then
      type(flow_modes_t), intent(in), optional :: fm   !! fluid-elastic data (&flow)
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      real(dp), allocatable :: cols(:, :), tab(:, :), curves(:, :)
      character(len=17), allocatable :: names(:), units(:)
      integer :: j
      tab = mode_shape_table(sys, modes)
      curves = shape_curve_table(sys, modes, curve_points)
      call set%begin(deck%job%output, [character(len=18) :: '.h5', '.modes.dat', &
                     '.shapes.dat', '.shape_curves.dat'])
      call set%open_h5(h5, 'modes', deck%text, deck%warnings)
      call write_parameter_set(h5, run_parameters(deck, stop_stiffness, &
         modes%frequency_hz(1), modes%frequency_hz(modes%n_modes), sys%n_dof))
      call h5%put('/modes/frequency_hz', modes%frequency_hz)
      call h5%put('/modes/shapes', modes%shapes)
      call h5%put('/modes/participation', modes%participation)
      call h5%put('/modes/effective_mass', modes%effective_mass)
      call h5%put('/modes/moving_mass', modes%total_mass)
      call h5%put('/modes/node_x', tab(:, 1))
      call h5%put('/modes/node_w', tab(:, 2:))
      call h5%put('/modes/shape_x', curves(:, 1))
      call h5%put('/modes/shape_w', curves(:, 2:))
      call write_structure(h5, sys)
      call h5%put('/model/stop_stiffness', stop_stiffness, units=stiffness_units(deck))
      if (present(fm)) then
         call h5%put('/flow/frequency_hz', fm%frequency_hz)
         call h5%put('/flow/plane', fm%plane)
         call h5%put('/flow/structural_ratio', fm%structural_ratio)
         call h5%put('/flow/velocity_ratio', fm%velocity_ratio)
         call h5%put('/flow/critical_velocity', fm%critical_velocity)
         call h5%put('/flow/fluid_ratio', fm%fluid_ratio)
         call h5%put('/flow/velocity', deck%flow%velocity)
      end if
      call set%close_h5(h5)

      allocate(cols(modes%n_modes, 5))
      cols(:, 1) = [(real(j, dp), j = 1, modes%n_modes)]
      cols(:, 2) = modes%frequency_hz
      cols(:, 3) = modes%frequency_hz / modes%frequency_hz(1)
      cols(:, 4) = modes%participation
      cols(:, 5) = modes%effective_mass / modes%total_mass
      call set%table('.modes.dat', trim(deck%job%title) // ': natural frequencies', &
         [character(len=17) :: 'mode', 'frequency', 'ratio_to_f1', 'participation', &
         'eff_mass_fraction'], [character(len=17) :: '-', 'Hz', '-', 'sqrt(kg)', '-'], cols)
      allocate(names(1 + modes%n_modes), units(1 + modes%n_modes))
      names(1) = 'x';  units(1) = 'm'
      do j = 1, modes%n_modes
         names(1 + j) = 'w_mode' // str(j);  units(1 + j) = 'm/sqrt(kg)'
      end do
      call set%table('.shapes.dat', trim(deck%job%title) // ': mode shapes (w)', names, &
                     units, tab)
      call set%table('.shape_curves.dat', trim(deck%job%title) // ': mode shapes (w), ' &
         // 'Hermite shape functions, ' // str(curve_points) // ' points per element', names, &
         units, curves)
      call set%finish(err)
   end subroutine write_modes

   !> Calibration result: PREFIX.h5 with /calibrate/value and the first frequency, and the
   !> calibrated structure's K and M.
   subroutine write_calibration(deck, sys, value, units, f1_hz, err)
      type(deck_t), intent(in) :: deck                 !! the deck
      type(system_t), intent(in) :: sys                !! the calibrated structure, assembled
      real(dp), intent(in) :: value                    !! calibrated value
      character(len=*), intent(in) :: units            !! its units
      real(dp), intent(in) :: f1_hz                    !! resulting first frequency [Hz]
      type(error_t), allocatable, intent(out) :: err   !! I/O failure; no file changed then
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      call set%begin(deck%job%output, ['.h5'])
      call set%open_h5(h5, 'calibrate', deck%text, deck%warnings)
      call write_parameter_set(h5, run_parameters(deck))
      call write_structure(h5, sys)
      call h5%put('/calibrate/parameter', trim(deck%calibrate%parameter))
      call h5%put('/calibrate/value', value, units=units)
      call h5%put('/calibrate/target_f1_hz', deck%calibrate%target_f1_hz)
      call h5%put('/calibrate/f1_hz', f1_hz)
      call set%close_h5(h5)
      call set%finish(err)
   end subroutine write_calibration

   !> Transient results: PREFIX.h5; with &output write_text PREFIX.history.dat and
   !> .poincare.dat (two planes: .orbit.dat, .supports.dat); with the state history PREFIX.xdmf
   !> (and .shape.dat).
   subroutine write_transient(deck, model, res, diag, err, stats, psd)
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results (the final record)
      type(point_result_t), intent(in) :: diag         !! period, exponent, label
      type(error_t), allocatable, intent(out) :: err   !! I/O failure; no file changed then
      type(draw_statistics_t), intent(in), optional :: stats(:)   !! over random draws
      type(response_psd_t), intent(in), optional :: psd           !! response PSD over them
      type(output_set_t) :: set
      type(transient_result_t) :: r
      character(len=14), allocatable :: suffixes(:)
      logical :: with_state, text, planes
      with_state = allocated(res%history_u)
      text = deck%output%write_text
      planes = model%sys%planes > 1
      suffixes = [character(len=14) :: '.h5']
      if (text) suffixes = [character(len=14) :: suffixes, '.history.dat', '.poincare.dat']
      if (text .and. planes) suffixes = [character(len=14) :: suffixes, '.orbit.dat', &
                                         '.supports.dat']
      if (with_state) suffixes = [character(len=14) :: suffixes, '.xdmf']
      if (with_state .and. text) suffixes = [character(len=14) :: suffixes, '.shape.dat']
      r = on_trajectory_clock(res, diag%transient_periods, deck%solver%record_periods, &
                              2.0_dp * pi / model%omega)
      call set%begin(deck%job%output, suffixes)
      call write_transient_h5(set, deck, model, r, diag, stats, psd)
      if (text) call write_transient_tables(set, deck, model, r)
      if (text .and. planes) call write_orbit_tables(set, deck, model, r)
      if (with_state) call write_xdmf(set, deck, model, r)
      if (with_state .and. text) call write_shape_table(set, deck, model, r)
      call set%finish(err)
   end subroutine write_transient

   !> PREFIX.h5 of a transient run, under the set's temporary name.
   subroutine write_transient_h5(set, deck, model, res, diag, stats, psd)
      type(output_set_t), intent(inout) :: set         !! the set
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(point_result_t), intent(in) :: diag         !! period, exponent, label
      type(draw_statistics_t), intent(in), optional :: stats(:)   !! over random draws
      type(response_psd_t), intent(in), optional :: psd           !! response PSD over them
      integer :: k
      type(h5_writer_t) :: h5
      character(len=:), allocatable :: filtered
      filtered = trim(merge(' (low-pass filtered)', '                    ', &
                            deck%output%filter_cutoff_hz > 0.0_dp))
      call set%open_h5(h5, 'transient', deck%text, deck%warnings)
      call write_parameter_set(h5, run_parameters(deck, model%stop_stiffness, &
         model%f1_open_hz, model%omega_max / (2.0_dp * pi), model%n))
      call write_history(h5, deck, model, res)
      call h5%put('/poincare/time', res%p_time)
      call h5%put('/poincare/strain', res%p_strain, fill=filtered)
      call h5%put('/poincare/strain_rate', res%p_strain_rate, fill=filtered)
      call h5%put('/poincare/tip_displacement', res%p_tip)
      call h5%put('/poincare/tip_velocity', res%p_tip_velocity)
      call write_run(h5, res)
      call write_model(h5, model, stiffness_units(deck))
      call write_impacts(h5, res)
      call write_wear_h5(h5, deck, model, res)
      call write_diagnostics(h5, diag)
      if (present(stats)) then
         call h5%put('/statistics/draws', stats(1)%n_draws)
         do k = 1, size(stats)
            if (stats(k)%name == 'tip_rms_displacement') then
               call h5%put('/statistics/' // stats(k)%name, stats(k)%mean(1))
               call h5%put('/statistics/' // stats(k)%name // '_ci', stats(k)%half_width(1))
            else
               call h5%put('/statistics/' // stats(k)%name, stats(k)%mean)
               call h5%put('/statistics/' // stats(k)%name // '_ci', stats(k)%half_width)
            end if
         end do
      end if
      if (present(psd)) call write_response_psd(h5, psd)
      call h5%put('/final/u', res%u)
      call h5%put('/final/v', res%v)
      call h5%put('/final/time', res%t_end)
      call set%close_h5(h5)
   end subroutine write_transient_h5

   !> /history: the samples of the record (and the full state and deflected shape with
   !> &output state_history).
   subroutine write_history(h5, deck, model, res)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      real(dp), allocatable :: nw(:, :), nt(:, :), sw(:, :), x(:), xyz(:, :, :)
      integer, allocatable :: seg(:, :)
      integer :: i, k, ns
      call h5%put('/history/time', res%time)
      call h5%put('/history/strain', res%strain)
      call h5%put('/history/strain_rate', res%strain_rate)
      if (deck%output%filter_cutoff_hz > 0.0_dp) then
         call h5%put('/history/strain_filtered', res%strain_filtered)
         call h5%put('/poincare/filter_cutoff_hz', deck%output%filter_cutoff_hz)
      end if
      call h5%put('/history/tip_displacement', res%tip_displacement)
      call h5%put('/history/stop_force', transpose(res%stop_force))   ! a row per sample (C)
      if (.not. allocated(res%history_u)) return
      ns = deck%output%shape_points
      x = shape_points(model%sys, ns)
      allocate(nw(model%sys%n_node, size(res%time)), nt(model%sys%n_node, size(res%time)))
      allocate(sw(size(x), size(res%time)), xyz(3, size(x), size(res%time)))
      do i = 1, size(res%time)
         call nodal_values(model%sys, res%history_u(:, i), nw(:, i), nt(:, i))
         sw(:, i) = deflection(model%sys, res%history_u(:, i), ns)
         xyz(1, :, i) = x;  xyz(2, :, i) = sw(:, i);  xyz(3, :, i) = 0.0_dp
      end do
      seg = reshape([([k - 1, k], k = 1, size(x) - 1)], [2, size(x) - 1])
      call h5%put('/history/node_x', shape_points(model%sys, 1))
      call h5%put('/history/node_w', nw)
      call h5%put('/history/node_theta', nt)
      call h5%put('/history/shape_x', x, fill=str(ns))
      call h5%put('/history/shape_w', sw)
      call h5%put('/history/shape_xyz', xyz)            ! the mesh of the .xdmf file
      call h5%put('/history/shape_segments', seg)
      call write_xdmf_datasets(h5, deck, model, res)   ! the .xdmf file's own datasets
   end subroutine write_history

   !> PREFIX.xdmf: read back the byte offsets of the datasets it addresses in the .h5 file (file
   !> 1 of the set, written and closed), then its text.
   subroutine write_xdmf(set, deck, model, res)
      type(output_set_t), intent(inout) :: set         !! the set
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results (with history_u)
      character(len=:), allocatable :: text
      type(error_t), allocatable :: e
      if (set%failed()) return
      call make_xdmf(set%temp(1), base_name(deck%job%output) // '.h5', deck, model, res, text, e)
      if (allocated(e)) then
         call set%keep(e)
      else
         call set%text('.xdmf', text)
      end if
   end subroutine write_xdmf

   !> /run: counters and timings of the integration.
   subroutine write_run(h5, res)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(transient_result_t), intent(in) :: res      !! results
      call h5%put('/run/steps_accepted', int(res%steps_accepted))
      call h5%put('/run/steps_rejected', int(res%steps_rejected))
      call h5%put('/run/events', int(res%events))
      call h5%put('/run/factorizations', int(res%factorizations))
      call h5%put('/run/fixed_point_iterations', int(res%fp_iterations))
      call h5%put('/run/cpu_seconds', res%cpu_seconds)
      call h5%put('/run/wall_seconds', res%wall_seconds)
      call h5%put('/run/setup_seconds', res%setup_seconds)
      call h5%put('/run/method', res%method)
      call h5%put('/run/method_reason', res%method_reason)
      call h5%put('/run/dt_smallest', res%dt_smallest)
      call h5%put('/run/dt_largest', res%dt_largest)
   end subroutine write_run

   !> /impacts: statistics of each stop over the record.
   subroutine write_impacts(h5, res)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(transient_result_t), intent(in) :: res      !! results
      call h5%put('/impacts/count', res%n_impacts)
      call h5%put('/impacts/peak_force', res%peak_force)
      call h5%put('/impacts/rms_force', res%rms_force)
      call h5%put('/impacts/contact_fraction', res%contact_fraction)
      call h5%put('/impacts/impulse_per_period', res%impulse_per_period)
      call h5%put('/impacts/work_rate', res%work_rate)
      call h5%put('/impacts/first_contact_time', res%first_contact_time)
   end subroutine write_impacts

   !> /wear (per stop, beside /impacts), /orbit (two-plane models), /energy (when asked).
   subroutine write_wear_h5(h5, deck, model, res)
      type(h5_writer_t), intent(inout) :: h5           !! open writer
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      call h5%put('/wear/normal_work_rate', res%normal_work_rate)
      call h5%put('/wear/sliding_distance', res%sliding_distance)
      call h5%put('/wear/friction_work', res%friction_work)
      call h5%put('/wear/friction_work_rate', res%friction_work_rate)
      call h5%put('/wear/wear_volume_rate', res%wear_volume_rate)
      call h5%put('/wear/wear_coefficient', [deck%stops%wear_coefficient])
      call h5%put('/wear/stick_fraction', res%stick_fraction)
      if (deck%wear%years > 0.0_dp) call write_wear_depth(h5, deck, res%wear_volume_rate)
      if (model%sys%planes > 1) then
         call h5%put('/orbit/w', transpose(res%orbit_w))
         call h5%put('/orbit/v', transpose(res%orbit_v))
         call h5%put('/orbit/normal_force', transpose(res%stop_force))
         call h5%put('/orbit/tangential_force', transpose(res%tangential_force))
         call h5%put('/orbit/gap', [deck%stops%gap])
         call h5%put('/orbit/offset_w', [deck%stops%offset_w])
         call h5%put('/orbit/offset_v', [deck%stops%offset_v])
      end if
      if (.not. res%has_energy) return
      call h5%put('/energy/input_work', res%input_work)
      call h5%put('/energy/rayleigh_dissipation', res%rayleigh_dissipation)
      call h5%put('/energy/contact_damping_dissipation', res%contact_damping_dissipation)
      call h5%put('/energy/friction_dissipation', res%friction_dissipation)
      call h5%put('/energy/stored_energy_change', res%stored_energy_change)
      call h5%put('/energy/imbalance', res%input_work - res%rayleigh_dissipation &
         - res%contact_damping_dissipation - res%friction_dissipation - res%stored_energy_change)
   end subroutine write_wear_h5

   !> /wear/depth: each support's scar depth over &wear years, and the time to a wall fraction.
   subroutine write_wear_depth(h5, deck, volume_rate)
      type(h5_writer_t), intent(inout) :: h5           !! open writer
      type(deck_t), intent(in) :: deck                 !! the deck (&wear years > 0)
      real(dp), intent(in) :: volume_rate(:)           !! per stop [m^3/s]
      type(wear_depth_t) :: wd
      wd = deck_wear_depth(deck, volume_rate)
      call h5%put('/wear/depth_time', wd%time_years)
      call h5%put('/wear/depth', transpose(wd%depth))   ! a row per time (C)
      call h5%put('/wear/years_to_wall_fraction', wd%years_to_fraction)
      call h5%put('/wear/wall_fraction', deck%wear%wall_fraction)
      call h5%put('/wear/wall_thickness', deck%wear%wall_thickness)
   end subroutine write_wear_depth

   !> /diagnostics: the label of a transient run, its evidence, its certificate and its starts
   !> (docs/labels.md).
   subroutine write_diagnostics(h5, diag)
      type(h5_writer_t), intent(inout) :: h5            !! writer with an open file
      type(point_result_t), intent(in) :: diag          !! diagnosed run
      character(len=*), parameter :: g = '/diagnostics/'
      integer :: iv(size(int_names)), k
      real(dp) :: rv(size(real_names))
      iv = int_fields(diag);  rv = real_fields(diag)
      do k = 1, size(int_names)   ! n_attractors with the starts, below
         if (all(int_names(k) /= [character(len=12) :: 'status', 'n_attractors'])) &
            call h5%put(g // trim(int_names(k)), iv(k))
      end do
      do k = 1, size(real_names)   ! a sweep point's cost and model are its file's own
         if (all(real_names(k) /= [character(len=10) :: 'seconds', 'steps', 'f1_open_hz'])) &
            call h5%put(g // trim(real_names(k)), rv(k))
      end do
      do k = 1, size(text_names) - 1   ! all but the failure message
         if (text_names(k) == 'certificate_reason' .and. &
             .not. allocated(diag%certificate_reason)) then
            call h5%put(g // trim(text_names(k)), 'certification is off (&diagnostics ' &
               // 'certify = .false.)')
         else
            call h5%put(g // trim(text_names(k)), text_field(diag, k))
         end if
      end do
      call h5%put(g // 'label_text', label_text(diag%label))
      call h5%put(g // 'lyapunov_running', diag%lyapunov_running)
      call h5%put(g // 'certificate_text', certificate_text(diag%certificate))
      if (.not. allocated(diag%start_label)) return
      if (size(diag%start_label) == 0) return
      do k = 1, size(array_names)   ! the per-start arrays, whole
         if (array_extent(k) /= 4) cycle
         if (array_names(k) == 'attractors/label') call h5%put(g // 'n_attractors', &
                                                               diag%n_attractors)
         if (array_type(k:k) == 'i') then
            call h5%put(g // trim(array_names(k)), nint(array_field(diag, k)))
         else
            call h5%put(g // trim(array_names(k)), array_field(diag, k))
         end if
      end do
   end subroutine write_diagnostics

   !> PREFIX.history.dat and PREFIX.poincare.dat.
   subroutine write_transient_tables(set, deck, model, res)
      type(output_set_t), intent(inout) :: set         !! the set
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      real(dp), allocatable :: cols(:, :)
      character(len=20), allocatable :: names(:), units(:)
      integer :: j, ns, nf
      ns = model%n_stops
      nf = merge(1, 0, deck%output%filter_cutoff_hz > 0.0_dp)
      allocate(cols(size(res%time), 4 + ns + nf), names(4 + ns + nf), units(4 + ns + nf))
      cols(:, 1) = res%time;  cols(:, 2) = res%strain;  cols(:, 3) = res%strain_rate
      cols(:, 4) = res%tip_displacement
      names(1:4) = [character(len=20) :: 'time', 'strain', 'strain_rate', 'tip_displacement']
      units(1:4) = [character(len=20) :: 's', '-', '1/s', 'm']
      do j = 1, ns
         cols(:, 4 + j) = res%stop_force(:, j)
         names(4 + j) = 'stop_force_' // str(j);  units(4 + j) = 'N'
      end do
      if (nf == 1) then
         cols(:, 5 + ns) = res%strain_filtered
         names(5 + ns) = 'strain_filtered';  units(5 + ns) = '-'
      end if
      call set%table('.history.dat', trim(deck%job%title), names, units, cols)
      call set%table('.poincare.dat', trim(deck%job%title), [character(len=20) :: 'strain', &
         'strain_rate', 'tip_displacement', 'tip_velocity', 'time'], [character(len=20) :: &
         '-', '1/s', 'm', 'm/s', 's'], reshape([res%p_strain, res%p_strain_rate, res%p_tip, &
         res%p_tip_velocity, res%p_time], [size(res%p_time), 5]))
   end subroutine write_transient_tables

   !> PREFIX.orbit.dat (time, then per stop w, v, normal and tangential force) and
   !> PREFIX.supports.dat (per stop: node, x, gap, hole offset, circular), two-plane models.
   subroutine write_orbit_tables(set, deck, model, res)
      type(output_set_t), intent(inout) :: set         !! the set
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      real(dp), allocatable :: cols(:, :)
      character(len=24), allocatable :: names(:), units(:)
      integer :: j, ns
      ns = model%n_stops
      allocate(cols(size(res%time), 1 + 4 * ns), names(1 + 4 * ns), units(1 + 4 * ns))
      cols(:, 1) = res%time;  names(1) = 'time';  units(1) = 's'
      do j = 1, ns
         cols(:, 4 * j - 2) = res%orbit_w(:, j);  names(4 * j - 2) = 'w_' // str(j)
         cols(:, 4 * j - 1) = res%orbit_v(:, j);  names(4 * j - 1) = 'v_' // str(j)
         cols(:, 4 * j) = res%stop_force(:, j);  names(4 * j) = 'normal_force_' // str(j)
         cols(:, 4 * j + 1) = res%tangential_force(:, j)
         names(4 * j + 1) = 'tangential_force_' // str(j)
         units(4 * j - 2:4 * j + 1) = [character(len=24) :: 'm', 'm', 'N', 'N']
      end do
      call set%table('.orbit.dat', trim(deck%job%title) // ': orbits at the supports', names, &
                     units, cols)
      deallocate(cols)
      allocate(cols(ns, 7))
      do j = 1, ns
         cols(j, :) = [real(j, dp), real(deck%stops(j)%node, dp), &
            real(deck%stops(j)%node - 1, dp) * model%sys%element_length, deck%stops(j)%gap, &
            deck%stops(j)%offset_w, deck%stops(j)%offset_v, &
            merge(1.0_dp, 0.0_dp, deck%stops(j)%shape == 'circular')]
      end do
      call set%table('.supports.dat', trim(deck%job%title) // ': supports', &
         [character(len=16) :: 'stop', 'node', 'x', 'gap', 'offset_w', 'offset_v', 'circular'], &
         [character(len=16) :: '-', '-', 'm', 'm', 'm', 'm', '-'], cols)
   end subroutine write_orbit_tables

   !> PREFIX.shape.dat: the deflected shape at every history sample, one gnuplot block (index)
   !> per sample, for the animation (scripts/animation.gp).
   subroutine write_shape_table(set, deck, model, res)
      type(output_set_t), intent(inout) :: set         !! the set
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results (with history_u)
      real(dp), allocatable :: x(:), w(:)
      character(len=:), allocatable :: text, buf
      character(len=64) :: line
      integer :: i, k, j, pos
      x = shape_points(model%sys, deck%output%shape_points)
      text = '# ' // trim(deck%job%title) // ': deflected shape relative to the base' &
         // new_line('a') // '# columns: x [m], w [m]; one block (gnuplot index) per history ' &
         // 'sample, preceded by its time' // new_line('a') // '# points per element: ' &
         // str(deck%output%shape_points) // ' (the nodes are every ' &
         // str(deck%output%shape_points) // 'th point from the first)' // new_line('a')
      do j = 1, size(deck%stops)
         text = text // '# stop ' // str(j) // ': x = ' // str(real(deck%stops(j)%node - 1, dp) &
            * model%sys%element_length) // ' m, dof ' // trim(merge('w    ', 'theta', &
            deck%stops(j)%dof == 1)) // ', side ' // trim(deck%stops(j)%side) // ', gap ' &
            // str(deck%stops(j)%gap) // new_line('a')
      end do
      text = text // '# x w' // new_line('a')
      pos = 0
      call append_text(buf, pos, text)
      do i = 1, size(res%time)
         w = deflection(model%sys, res%history_u(:, i), deck%output%shape_points)
         write(line, '(a, es24.16e3)') '# t = ', res%time(i)
         call append_text(buf, pos, trim(line) // new_line('a'))
         do k = 1, size(x)
            write(line, '(es24.16e3, 1x, es24.16e3)') x(k), w(k)
            call append_text(buf, pos, trim(adjustl(line)) // new_line('a'))
         end do
         call append_text(buf, pos, new_line('a') // new_line('a'))
      end do
      call set%text('.shape.dat', buf(1:pos))
   end subroutine write_shape_table

   !> The last component of a path ('results/x' -> 'x').
   pure function base_name(path) result(b)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: b
      b = trim(path)
      b = b(index(b, '/', back=.true.) + 1:)
   end function base_name
end module gapbeam_report
