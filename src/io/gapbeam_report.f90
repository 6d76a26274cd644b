!> Result files: HDF5 (through gapbeam_hdf5_output) and gnuplot-ready text tables. The files of
!> one run form an output set (gapbeam_output_set): written under temporary names, then put in
!> place together, or not at all; the HDF5 file lists them at /run/files. Every dataset carries
!> `units`; every file carries the effective deck text at /deck.
module gapbeam_report
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t, write_failed
   use gapbeam_files, only: write_table
   use gapbeam_output_set, only: output_set_t
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: system_t, model_t
   use gapbeam_description, only: dof_w
   use gapbeam_results, only: modes_t, transient_result_t, point_result_t, label_text
   implicit none
   private
   public :: write_modes, write_transient, write_calibration, mode_shape_table

contains

   !> Node x and w of each mode at the nodes (root w = 0), for plotting: (n_node, 1+n_modes).
   function mode_shape_table(sys, modes) result(tab)
      type(system_t), intent(in) :: sys      !! assembled structure
      type(modes_t), intent(in) :: modes     !! modes
      real(dp), allocatable :: tab(:, :)
      integer :: i, j, g
      allocate(tab(sys%n_node, 1 + modes%n_modes), source=0.0_dp)
      do i = 1, sys%n_node
         tab(i, 1) = real(i - 1, dp) * sys%element_length
         g = sys%dof_of(dof_w, i)
         if (g > 0) then
            do j = 1, modes%n_modes
               tab(i, 1 + j) = modes%shapes(g, j)
            end do
         end if
      end do
   end function mode_shape_table

   !> Modal analysis results: prefix.h5 and prefix.modes.dat, prefix.shapes.dat.
   subroutine write_modes(deck, sys, modes, stop_stiffness, err)
      type(deck_t), intent(in) :: deck                 !! the deck (output prefix, text)
      type(system_t), intent(in) :: sys                !! assembled structure
      type(modes_t), intent(in) :: modes               !! modes
      real(dp), intent(in) :: stop_stiffness(:)        !! resolved stop stiffness (may be empty)
      type(error_t), allocatable, intent(out) :: err   !! I/O failure; no file changed then
      type(output_set_t) :: set
      call set%begin(deck%job%output, [character(len=12) :: '.h5', '.modes.dat', &
                     '.shapes.dat'], err)
      if (allocated(err)) return
      call write_modes_files(set, deck, sys, modes, stop_stiffness, err)
      call set%finish(err)
   end subroutine write_modes

   !> The files of write_modes, under the set's temporary names.
   subroutine write_modes_files(set, deck, sys, modes, stop_stiffness, err)
      type(output_set_t), intent(in) :: set            !! .h5, .modes.dat, .shapes.dat
      type(deck_t), intent(in) :: deck                 !! the deck (title, text)
      type(system_t), intent(in) :: sys                !! assembled structure
      type(modes_t), intent(in) :: modes               !! modes
      real(dp), intent(in) :: stop_stiffness(:)        !! resolved stop stiffness (may be empty)
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
      type(h5_writer_t) :: h5
      real(dp), allocatable :: cols(:, :), tab(:, :)
      character(len=16), allocatable :: names(:), units(:)
      integer :: j
      call h5%create(set%temp(1), err, in_place=.true.);  if (allocated(err)) return
      call h5%write_text('/deck', deck%text, err);  if (write_failed(h5, err)) return
      call set%record(h5, err);  if (write_failed(h5, err)) return
      call h5%write('/modes/frequency_hz', modes%frequency_hz, 'Hz', err)
      if (write_failed(h5, err)) return
      call h5%write('/modes/shapes', modes%shapes, 'm/sqrt(kg)', err)
      if (write_failed(h5, err)) return
      call h5%write('/modes/participation', modes%participation, 'sqrt(kg)', err)
      if (write_failed(h5, err)) return
      call h5%write('/modes/effective_mass', modes%effective_mass, 'kg', err)
      if (write_failed(h5, err)) return
      call h5%write('/modes/moving_mass', modes%total_mass, 'kg', err)
      if (write_failed(h5, err)) return
      tab = mode_shape_table(sys, modes)
      call h5%write('/modes/node_x', tab(:, 1), 'm', err);  if (write_failed(h5, err)) return
      call h5%write('/modes/node_w', tab(:, 2:), 'm/sqrt(kg)', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/stiffness', sys%k, 'N/m, N, N m/rad', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/mass', sys%m, 'kg, kg m, kg m^2', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/stop_stiffness', stop_stiffness, 'N/m', err)
      if (write_failed(h5, err)) return
      call h5%close(err);  if (allocated(err)) return

      allocate(cols(modes%n_modes, 5))
      cols(:, 1) = [(real(j, dp), j = 1, modes%n_modes)]
      cols(:, 2) = modes%frequency_hz
      cols(:, 3) = modes%frequency_hz / modes%frequency_hz(1)
      cols(:, 4) = modes%participation
      cols(:, 5) = modes%effective_mass / modes%total_mass
      call write_table(set%temp(2), trim(deck%job%title) // ': natural frequencies', &
         [character(len=16) :: 'mode', 'frequency', 'ratio_to_f1', 'participation', &
         'eff_mass_fraction'], [character(len=16) :: '-', 'Hz', '-', 'sqrt(kg)', '-'], cols, err, &
         in_place=.true.)
      if (allocated(err)) return
      allocate(names(1 + modes%n_modes), units(1 + modes%n_modes))
      names(1) = 'x';  units(1) = 'm'
      do j = 1, modes%n_modes
         names(1 + j) = 'w_mode' // str(j);  units(1 + j) = 'm/sqrt(kg)'
      end do
      call write_table(set%temp(3), trim(deck%job%title) // ': mode shapes (w)', &
                       names, units, tab, err, in_place=.true.)
   end subroutine write_modes_files

   !> Calibration result: prefix.h5 with /calibrate/value and the first frequency.
   subroutine write_calibration(deck, value, units, f1_hz, err)
      type(deck_t), intent(in) :: deck                 !! the deck
      real(dp), intent(in) :: value                    !! calibrated value
      character(len=*), intent(in) :: units            !! its units
      real(dp), intent(in) :: f1_hz                    !! resulting first frequency [Hz]
      type(error_t), allocatable, intent(out) :: err   !! I/O failure; no file changed then
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      call set%begin(deck%job%output, ['.h5'], err);  if (allocated(err)) return
      call h5%create(set%temp(1), err, in_place=.true.)
      if (.not. allocated(err)) call write_calibration_h5(h5, set, deck, value, units, f1_hz, err)
      call set%finish(err)
   end subroutine write_calibration

   !> The datasets of write_calibration.
   subroutine write_calibration_h5(h5, set, deck, value, units, f1_hz, err)
      type(h5_writer_t), intent(inout) :: h5           !! writer, file created; closed here
      type(output_set_t), intent(in) :: set            !! the set (for /run/files)
      type(deck_t), intent(in) :: deck                 !! the deck
      real(dp), intent(in) :: value                    !! calibrated value
      character(len=*), intent(in) :: units            !! its units
      real(dp), intent(in) :: f1_hz                    !! resulting first frequency [Hz]
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
      call h5%write_text('/deck', deck%text, err);  if (write_failed(h5, err)) return
      call set%record(h5, err);  if (write_failed(h5, err)) return
      call h5%write_text('/calibrate/parameter', trim(deck%calibrate%parameter), err)
      if (write_failed(h5, err)) return
      call h5%write('/calibrate/value', value, units, err);  if (write_failed(h5, err)) return
      call h5%write('/calibrate/target_f1_hz', deck%calibrate%target_f1_hz, 'Hz', err)
      if (write_failed(h5, err)) return
      call h5%write('/calibrate/f1_hz', f1_hz, 'Hz', err);  if (write_failed(h5, err)) return
      call h5%close(err)
   end subroutine write_calibration_h5

   !> Transient results: prefix.h5, prefix.history.dat, prefix.poincare.dat (the last two when
   !> &output write_text).
   subroutine write_transient(deck, model, res, diag, err)
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(point_result_t), intent(in) :: diag         !! period, exponent, label
      type(error_t), allocatable, intent(out) :: err   !! I/O failure; no file changed then
      type(output_set_t) :: set
      if (deck%output%write_text .and. model%sys%planes > 1) then
         call set%begin(deck%job%output, [character(len=14) :: '.h5', '.history.dat', &
                        '.poincare.dat', '.orbit.dat', '.supports.dat'], err)
      else if (deck%output%write_text) then
         call set%begin(deck%job%output, [character(len=14) :: '.h5', '.history.dat', &
                        '.poincare.dat'], err)
      else
         call set%begin(deck%job%output, ['.h5'], err)
      end if
      if (allocated(err)) return
      call write_transient_h5(set, deck, model, res, diag, err)
      if (.not. allocated(err) .and. deck%output%write_text) &
         call write_transient_tables(set, deck, model, res, err)
      if (.not. allocated(err) .and. deck%output%write_text .and. model%sys%planes > 1) &
         call write_orbit_tables(set, deck, model, res, err)
      call set%finish(err)
   end subroutine write_transient

   !> PREFIX.h5 of a transient run, under the set's temporary name.
   subroutine write_transient_h5(set, deck, model, res, diag, err)
      type(output_set_t), intent(in) :: set            !! the set; file 1 is the .h5
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(point_result_t), intent(in) :: diag         !! period, exponent, label
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
      type(h5_writer_t) :: h5
      call h5%create(set%temp(1), err, in_place=.true.);  if (allocated(err)) return
      call h5%write_text('/deck', deck%text, err);  if (write_failed(h5, err)) return
      call set%record(h5, err);  if (write_failed(h5, err)) return
      call h5%write('/history/time', res%time, 's', err);  if (write_failed(h5, err)) return
      call h5%write('/history/strain', res%strain, '-', err);  if (write_failed(h5, err)) return
      call h5%write('/history/strain_rate', res%strain_rate, '1/s', err)
      if (write_failed(h5, err)) return
      if (deck%output%filter_cutoff_hz > 0.0_dp) then
         call h5%write('/history/strain_filtered', res%strain_filtered, '-', err)
         if (write_failed(h5, err)) return
         call h5%write('/poincare/filter_cutoff_hz', deck%output%filter_cutoff_hz, 'Hz', err)
         if (write_failed(h5, err)) return
      end if
      call h5%write('/history/tip_displacement', res%tip_displacement, 'm', err)
      if (write_failed(h5, err)) return
      call h5%write('/history/stop_force', res%stop_force, 'N', err)
      if (write_failed(h5, err)) return
      call h5%write('/poincare/time', res%p_time, 's', err);  if (write_failed(h5, err)) return
      call h5%write('/poincare/strain', res%p_strain, '-', err);  if (write_failed(h5, err)) return
      call h5%write('/poincare/strain_rate', res%p_strain_rate, '1/s', err)
      if (write_failed(h5, err)) return
      call h5%write('/poincare/tip_displacement', res%p_tip, 'm', err)
      if (write_failed(h5, err)) return
      call h5%write('/poincare/tip_velocity', res%p_tip_velocity, 'm/s', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/steps_accepted', int(res%steps_accepted), '-', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/steps_rejected', int(res%steps_rejected), '-', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/events', int(res%events), '-', err);  if (write_failed(h5, err)) return
      call h5%write('/run/factorizations', int(res%factorizations), '-', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/fixed_point_iterations', int(res%fp_iterations), '-', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/cpu_seconds', res%cpu_seconds, 's', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/wall_seconds', res%wall_seconds, 's', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/setup_seconds', res%setup_seconds, 's', err)
      if (write_failed(h5, err)) return
      call h5%write_text('/run/method', res%method, err)
      if (write_failed(h5, err)) return
      call h5%write_text('/run/method_reason', res%method_reason, err)
      if (write_failed(h5, err)) return
      call h5%write('/run/dt_smallest', res%dt_smallest, 's', err)
      if (write_failed(h5, err)) return
      call h5%write('/run/dt_largest', res%dt_largest, 's', err);  if (write_failed(h5, err)) return
      call h5%write('/model/stop_stiffness', model%stop_stiffness, 'N/m', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/f1_open_hz', model%f1_open_hz, 'Hz', err)
      if (write_failed(h5, err)) return
      ! the discrete model, so that other tools can integrate exactly the same equations
      call h5%write('/model/stiffness', model%sys%k, 'N/m, N, N m/rad', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/mass', model%sys%m, 'kg, kg m, kg m^2', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/damping', model%c, 'N s/m, ...', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/load_shape', model%q, 'kg (P = s(t) q)', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/forcing_omega', model%omega, 'rad/s', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/forcing_half_amplitude', model%half_amplitude, &
                    'm (s(t) = a omega^2 sin(omega t))', err);  if (write_failed(h5, err)) return
      call h5%write('/model/strain_row', model%sys%strain_row, '1/m', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/contact_dof', model%c_dof, '1-based dof index', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/contact_sign', model%c_sign, '-', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/contact_gap', model%c_gap, 'm', err);  if (write_failed(h5, err)) return
      call h5%write('/model/contact_stiffness', model%c_k, 'N/m', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/contact_damping', model%c_c, 'N s/m', err)
      if (write_failed(h5, err)) return
      call h5%write('/model/contact_law', model%c_law, '1: bilinear, 2: hertz', err)
      if (write_failed(h5, err)) return
      call h5%write('/impacts/count', res%n_impacts, '-', err);  if (write_failed(h5, err)) return
      call h5%write('/impacts/peak_force', res%peak_force, 'N', err)
      if (write_failed(h5, err)) return
      call h5%write('/impacts/rms_force', res%rms_force, 'N', err)
      if (write_failed(h5, err)) return
      call h5%write('/impacts/contact_fraction', res%contact_fraction, '-', err)
      if (write_failed(h5, err)) return
      call h5%write('/impacts/impulse_per_period', res%impulse_per_period, 'N s', err)
      if (write_failed(h5, err)) return
      call h5%write('/impacts/work_rate', res%work_rate, 'W', err)
      if (write_failed(h5, err)) return
      call h5%write('/impacts/first_contact_time', res%first_contact_time, 's', err)
      if (write_failed(h5, err)) return
      call write_wear_h5(h5, deck, model, res, err)
      if (allocated(err)) return
      call h5%write('/diagnostics/period', diag%period, 'forcing periods', err)
      if (write_failed(h5, err)) return
      call h5%write('/diagnostics/label', diag%label, 'p >= 1: period p; 0: undecided; ' &
         // '-1: chaotic', err);  if (write_failed(h5, err)) return
      call h5%write_text('/diagnostics/label_text', label_text(diag%label), err)
      if (write_failed(h5, err)) return
      call h5%write('/diagnostics/lyapunov', diag%lyapunov, '1/s', err)
      if (write_failed(h5, err)) return
      call h5%write('/diagnostics/lyapunov_error', diag%lyapunov_error, '1/s', err)
      if (write_failed(h5, err)) return
      call h5%write('/diagnostics/lyapunov_running', diag%lyapunov_running, '1/s', err)
      if (write_failed(h5, err)) return
      call h5%write('/final/u', res%u, 'm, rad', err);  if (write_failed(h5, err)) return
      call h5%write('/final/v', res%v, 'm/s, rad/s', err);  if (write_failed(h5, err)) return
      call h5%write('/final/time', res%t_end, 's', err);  if (write_failed(h5, err)) return
      call h5%close(err)
   end subroutine write_transient_h5

   !> /wear (per stop, beside /impacts), /orbit and /model/ring_* (two-plane models), /energy
   !> (when the balance was asked).
   subroutine write_wear_h5(h5, deck, model, res, err)
      type(h5_writer_t), intent(inout) :: h5           !! open writer
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
      real(dp), allocatable :: coef(:)
      integer, allocatable :: idof(:)
      integer :: k
      coef = [(deck%stops(k)%wear_coefficient, k = 1, size(deck%stops))]
      call h5%write('/wear/normal_work_rate', res%normal_work_rate, 'W', err)
      if (write_failed(h5, err)) return
      call h5%write('/wear/sliding_distance', res%sliding_distance, 'm', err)
      if (write_failed(h5, err)) return
      call h5%write('/wear/friction_work', res%friction_work, 'J', err)
      if (write_failed(h5, err)) return
      call h5%write('/wear/friction_work_rate', res%friction_work_rate, 'W', err)
      if (write_failed(h5, err)) return
      call h5%write('/wear/wear_volume_rate', res%wear_volume_rate, 'm^3/s', err)
      if (write_failed(h5, err)) return
      call h5%write('/wear/wear_coefficient', coef, '1/Pa', err)
      if (write_failed(h5, err)) return
      call h5%write('/wear/stick_fraction', res%stick_fraction, '-', err)
      if (write_failed(h5, err)) return
      if (model%sys%planes > 1) then
         call h5%write('/orbit/w', res%orbit_w, 'm', err);  if (write_failed(h5, err)) return
         call h5%write('/orbit/v', res%orbit_v, 'm', err);  if (write_failed(h5, err)) return
         call h5%write('/orbit/normal_force', res%stop_force, 'N', err)
         if (write_failed(h5, err)) return
         call h5%write('/orbit/tangential_force', res%tangential_force, 'N', err)
         if (write_failed(h5, err)) return
         call h5%write('/orbit/gap', [(deck%stops(k)%gap, k = 1, size(deck%stops))], 'm', err)
         if (write_failed(h5, err)) return
         call h5%write('/orbit/offset_w', [(deck%stops(k)%offset_w, k = 1, size(deck%stops))], &
                       'm', err);  if (write_failed(h5, err)) return
         call h5%write('/orbit/offset_v', [(deck%stops(k)%offset_v, k = 1, size(deck%stops))], &
                       'm', err);  if (write_failed(h5, err)) return
      end if
      if (model%n_rings > 0) then
         idof = model%r_dof(1, :)
         call h5%write('/model/ring_dof_w', idof, '1-based dof index', err)
         if (write_failed(h5, err)) return
         idof = model%r_dof(2, :)
         call h5%write('/model/ring_dof_v', idof, '1-based dof index', err)
         if (write_failed(h5, err)) return
         call h5%write('/model/ring_gap', model%r_gap, 'm', err)
         if (write_failed(h5, err)) return
         call h5%write('/model/ring_stiffness', model%r_k, 'N/m', err)
         if (write_failed(h5, err)) return
         call h5%write('/model/ring_friction', model%r_mu, '-', err)
         if (write_failed(h5, err)) return
         call h5%write('/model/ring_tangential_stiffness', model%r_kt, 'N/m', err)
         if (write_failed(h5, err)) return
      end if
      if (res%has_energy) then
         call h5%write('/energy/input_work', res%input_work, 'J', err)
         if (write_failed(h5, err)) return
         call h5%write('/energy/rayleigh_dissipation', res%rayleigh_dissipation, 'J', err)
         if (write_failed(h5, err)) return
         call h5%write('/energy/contact_damping_dissipation', res%contact_damping_dissipation, &
                       'J', err);  if (write_failed(h5, err)) return
         call h5%write('/energy/friction_dissipation', res%friction_dissipation, 'J', err)
         if (write_failed(h5, err)) return
         call h5%write('/energy/stored_energy_change', res%stored_energy_change, 'J', err)
         if (write_failed(h5, err)) return
         call h5%write('/energy/imbalance', res%input_work - res%rayleigh_dissipation &
            - res%contact_damping_dissipation - res%friction_dissipation &
            - res%stored_energy_change, 'J', err);  if (write_failed(h5, err)) return
      end if
   end subroutine write_wear_h5

   !> PREFIX.orbit.dat (time, then per stop w, v, normal and tangential force) and
   !> PREFIX.supports.dat (per stop: node, x, gap, hole offset, circular), two-plane models.
   subroutine write_orbit_tables(set, deck, model, res, err)
      type(output_set_t), intent(in) :: set            !! the set; files 4 and 5
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
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
      call write_table(set%temp(4), trim(deck%job%title) // ': orbits at the supports', names, &
                       units, cols, err, in_place=.true.)
      if (allocated(err)) return
      deallocate(cols)
      allocate(cols(ns, 7))
      do j = 1, ns
         cols(j, :) = [real(j, dp), real(deck%stops(j)%node, dp), &
            real(deck%stops(j)%node - 1, dp) * model%sys%element_length, deck%stops(j)%gap, &
            deck%stops(j)%offset_w, deck%stops(j)%offset_v, &
            merge(1.0_dp, 0.0_dp, deck%stops(j)%shape == 'circular')]
      end do
      call write_table(set%temp(5), trim(deck%job%title) // ': supports', &
         [character(len=16) :: 'stop', 'node', 'x', 'gap', 'offset_w', 'offset_v', 'circular'], &
         [character(len=16) :: '-', '-', 'm', 'm', 'm', 'm', '-'], cols, err, in_place=.true.)
   end subroutine write_orbit_tables

   !> PREFIX.history.dat and PREFIX.poincare.dat, under the set's temporary names.
   subroutine write_transient_tables(set, deck, model, res, err)
      type(output_set_t), intent(in) :: set            !! the set; files 2 and 3
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
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
      call write_table(set%temp(2), trim(deck%job%title), names, units, cols, err, &
                       in_place=.true.)
      if (allocated(err)) return
      deallocate(cols)
      allocate(cols(size(res%p_time), 5))
      cols(:, 1) = res%p_strain;  cols(:, 2) = res%p_strain_rate;  cols(:, 3) = res%p_tip
      cols(:, 4) = res%p_tip_velocity;  cols(:, 5) = res%p_time
      call write_table(set%temp(3), trim(deck%job%title), &
         [character(len=20) :: 'strain', 'strain_rate', 'tip_displacement', 'tip_velocity', &
         'time'], [character(len=20) :: '-', '1/s', 'm', 'm/s', 's'], cols, err, in_place=.true.)
   end subroutine write_transient_tables
end module gapbeam_report
