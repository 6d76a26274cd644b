!> Result files: HDF5 (through gapbeam_hdf5_output) and gnuplot-ready text tables. The files of
!> one run form an output set (gapbeam_output_set): written under temporary names, then put in
!> place together, or not at all; the HDF5 file lists them at /run/files. Every dataset carries
!> `units`; every file carries the effective deck text at /deck.
module gapbeam_report
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t, write_failed
   use gapbeam_files, only: write_table, write_text_file
   use gapbeam_xdmf, only: write_xdmf, write_xdmf_datasets
   use gapbeam_output_set, only: output_set_t
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: system_t, model_t
   use gapbeam_description, only: dof_w
   use gapbeam_results, only: modes_t, transient_result_t, point_result_t, label_text, &
      certificate_text
   use gapbeam_kinds, only: pi
   use gapbeam_parameters, only: run_parameters, stiffness_units
   use gapbeam_deflection, only: shape_points, deflection, nodal_values
   use gapbeam_file_info, only: write_file_info, write_parameter_set, write_dof_map
   implicit none
   private

   !> The label codes, for long names.
   character(len=*), parameter :: label_codes = 'p >= 1: period p; 0: undecided; -1: ' &
      // 'chaotic; -2: unsettled; -3: failed'
   public :: write_modes, write_transient, write_calibration, mode_shape_table

   !> Points per element of the mode shape curves (Hermite shape functions).
   integer, parameter :: curve_points = 16

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
      call set%begin(deck%job%output, [character(len=18) :: '.h5', '.modes.dat', &
                     '.shapes.dat', '.shape_curves.dat'], err)
      if (allocated(err)) return
      call write_modes_files(set, deck, sys, modes, stop_stiffness, err)
      call set%finish(err)
   end subroutine write_modes

   !> The files of write_modes, under the set's temporary names.
   subroutine write_modes_files(set, deck, sys, modes, stop_stiffness, err)
      !> .h5, .modes.dat, .shapes.dat, .shape_curves.dat
      type(output_set_t), intent(in) :: set
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
      call write_file_info(h5, 'modes', deck%text, err);  if (write_failed(h5, err)) return
      call h5%write_text('/deck', deck%text, err, 'the effective deck text: deck file and ' &
         // 'command-line overrides');  if (write_failed(h5, err)) return
      call set%record(h5, err);  if (write_failed(h5, err)) return
      call write_parameter_set(h5, run_parameters(deck, stop_stiffness, &
         modes%frequency_hz(1), modes%frequency_hz(modes%n_modes), sys%n_dof), err)
      if (write_failed(h5, err)) return
      call h5%write('/modes/frequency_hz', modes%frequency_hz, 'Hz', err, &
                    'natural frequency of each mode (stops open)')
      if (write_failed(h5, err)) return
      ! mass-normalised shapes: kg^(-1/2) per dof, not expressible in UDUNITS-2 (integer
      ! powers only); the units string says it in the same product form
      call h5%write('/modes/shapes', modes%shapes, 'kg-1/2', err, 'mass-normalised mode ' &
         // 'shapes (phi^T M phi = 1): w entries m kg-1/2 per m of modal coordinate, theta ' &
         // 'entries rad kg-1/2; /model/dof_type says which is which', 'mode dof')
      if (write_failed(h5, err)) return
      call h5%write('/modes/participation', modes%participation, 'kg1/2', err, &
                    'base-excitation participation factor phi^T M r of each mode')
      if (write_failed(h5, err)) return
      call h5%write('/modes/effective_mass', modes%effective_mass, 'kg', err, &
                    'effective modal mass (phi^T M r)^2 of each mode')
      if (write_failed(h5, err)) return
      call h5%write('/modes/moving_mass', modes%total_mass, 'kg', err, &
                    'mass moved by the base, r^T M r')
      if (write_failed(h5, err)) return
      tab = mode_shape_table(sys, modes)
      call h5%write('/modes/node_x', tab(:, 1), 'm', err, 'position x of each node')
      if (write_failed(h5, err)) return
      call h5%write('/modes/node_w', tab(:, 2:), 'kg-1/2', err, 'transverse ' &
         // 'displacement w of each mode at the nodes (0 at the root), mass-normalised', &
         'mode node')
      if (write_failed(h5, err)) return
      call write_shape_curves(h5, sys, modes, err);  if (write_failed(h5, err)) return
      call write_model_matrices(h5, sys, err);  if (write_failed(h5, err)) return
      call h5%write('/model/stop_stiffness', stop_stiffness, stiffness_units(deck), err, &
                    'resolved contact stiffness of each stop (the paper''s rule applied)')
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
      if (allocated(err)) return
      call write_table(set%temp(4), trim(deck%job%title) // ': mode shapes (w), Hermite ' &
         // 'shape functions, ' // str(curve_points) // ' points per element', names, units, &
         shape_curve_table(sys, modes), err, in_place=.true.)
   end subroutine write_modes_files

   !> x and w of each mode between the nodes, from the element's Hermite shape functions:
   !> (n_points, 1 + n_modes).
   function shape_curve_table(sys, modes) result(tab)
      type(system_t), intent(in) :: sys      !! assembled structure
      type(modes_t), intent(in) :: modes     !! modes
      real(dp), allocatable :: tab(:, :)
      real(dp), allocatable :: x(:)
      integer :: j
      x = shape_points(sys, curve_points)
      allocate(tab(size(x), 1 + modes%n_modes))
      tab(:, 1) = x
      do j = 1, modes%n_modes
         tab(:, 1 + j) = deflection(sys, modes%shapes(:, j), curve_points)
      end do
   end function shape_curve_table

   !> /modes/shape_x and /modes/shape_w: the mode shapes between the nodes.
   subroutine write_shape_curves(h5, sys, modes, err)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(system_t), intent(in) :: sys                !! assembled structure
      type(modes_t), intent(in) :: modes               !! modes
      type(error_t), allocatable, intent(out) :: err   !! write failure
      real(dp), allocatable :: tab(:, :)
      tab = shape_curve_table(sys, modes)
      call h5%write('/modes/shape_x', tab(:, 1), 'm', err, 'x of the points of the shape ' &
         // 'curves (' // str(curve_points) // ' per element, the nodes among them)')
      if (allocated(err)) return
      call h5%write('/modes/shape_w', tab(:, 2:), 'kg-1/2', err, 'w of each mode between ' &
         // 'the nodes from the element''s cubic Hermite shape functions, mass-normalised', &
         'mode point')
   end subroutine write_shape_curves

   !> /model/stiffness, /model/mass and the dof map of a finite element model.
   subroutine write_model_matrices(h5, sys, err)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(system_t), intent(in) :: sys                !! assembled structure (or modal model)
      type(error_t), allocatable, intent(out) :: err   !! write failure
      call h5%write('/model/stiffness', sys%k, 'N m-1', err, 'stiffness matrix K (beam, root ' &
         // 'spring, springs); entries (w, w) N m-1, (w, theta) N rad-1, (theta, theta) N m ' &
         // 'rad-1: /model/dof_type says which dof is which', 'dof dof')
      if (allocated(err)) return
      call h5%write('/model/mass', sys%m, 'kg', err, 'mass matrix M; entries (w, w) kg, ' &
         // '(w, theta) kg m rad-1, (theta, theta) kg m2 rad-2', 'dof dof')
      if (allocated(err)) return
      call write_dof_map(h5, sys, err)
   end subroutine write_model_matrices

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
      call write_file_info(h5, 'calibrate', deck%text, err);  if (write_failed(h5, err)) return
      call h5%write_text('/deck', deck%text, err, 'the effective deck text: deck file and ' &
         // 'command-line overrides');  if (write_failed(h5, err)) return
      call set%record(h5, err);  if (write_failed(h5, err)) return
      call write_parameter_set(h5, run_parameters(deck), err);  if (write_failed(h5, err)) return
      call h5%write_text('/calibrate/parameter', trim(deck%calibrate%parameter), err, &
                         'the fitted parameter (&calibrate parameter)')
      if (write_failed(h5, err)) return
      call h5%write('/calibrate/value', value, units, err, 'fitted value of the parameter')
      if (write_failed(h5, err)) return
      call h5%write('/calibrate/target_f1_hz', deck%calibrate%target_f1_hz, 'Hz', err, &
                    'target first natural frequency')
      if (write_failed(h5, err)) return
      call h5%write('/calibrate/f1_hz', f1_hz, 'Hz', err, 'first natural frequency ' &
         // 'recomputed with the fitted value');  if (write_failed(h5, err)) return
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
      character(len=14), allocatable :: suffixes(:)
      logical :: with_state
      with_state = allocated(res%history_u)
      suffixes = [character(len=14) :: '.h5']
      if (deck%output%write_text) suffixes = [character(len=14) :: suffixes, '.history.dat', &
                                              '.poincare.dat']
      if (deck%output%write_text .and. model%sys%planes > 1) suffixes = &
         [character(len=14) :: suffixes, '.orbit.dat', '.supports.dat']
      if (with_state) suffixes = [character(len=14) :: suffixes, '.xdmf']
      if (with_state .and. deck%output%write_text) suffixes = [character(len=14) :: suffixes, &
                                                               '.shape.dat']
      call set%begin(deck%job%output, suffixes, err)
      if (allocated(err)) return
      call write_transient_h5(set, deck, model, res, diag, err)
      if (.not. allocated(err) .and. deck%output%write_text) &
         call write_transient_tables(set, deck, model, res, err)
      if (.not. allocated(err) .and. deck%output%write_text .and. model%sys%planes > 1) &
         call write_orbit_tables(set, deck, model, res, err)
      if (.not. allocated(err) .and. with_state) &
         call write_xdmf(set%temp(set%size() - merge(1, 0, deck%output%write_text)), &
            set%temp(1), base_name(deck%job%output) // '.h5', deck, model, res, err)
      if (.not. allocated(err) .and. with_state .and. deck%output%write_text) &
         call write_shape_table(set%temp(set%size()), deck, model, res, err)
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
      call write_file_info(h5, 'transient', deck%text, err);  if (write_failed(h5, err)) return
      call h5%write_text('/deck', deck%text, err, 'the effective deck text: deck file and ' &
         // 'command-line overrides');  if (write_failed(h5, err)) return
      call set%record(h5, err);  if (write_failed(h5, err)) return
      call write_parameter_set(h5, run_parameters(deck, model%stop_stiffness, &
         model%f1_open_hz, model%omega_max / (2.0_dp * pi), model%n), err)
      if (write_failed(h5, err)) return
      call write_history(h5, deck, model, res, err);  if (write_failed(h5, err)) return
      call h5%write('/poincare/time', res%p_time, 's', err, 'time of each Poincare point, ' &
         // 't_rec + (i - 1 + phase/360) T');  if (write_failed(h5, err)) return
      call h5%write('/poincare/strain', res%p_strain, '1', err, 'root strain at the Poincare ' &
         // 'section' // filtered_text(deck));  if (write_failed(h5, err)) return
      call h5%write('/poincare/strain_rate', res%p_strain_rate, 's-1', err, 'root strain ' &
         // 'rate at the Poincare section' // filtered_text(deck))
      if (write_failed(h5, err)) return
      call h5%write('/poincare/tip_displacement', res%p_tip, 'm', err, 'tip displacement w ' &
         // 'relative to the base at the Poincare section');  if (write_failed(h5, err)) return
      call h5%write('/poincare/tip_velocity', res%p_tip_velocity, 'm s-1', err, 'tip ' &
         // 'velocity relative to the base at the Poincare section')
      if (write_failed(h5, err)) return
      call write_run(h5, res, err);  if (write_failed(h5, err)) return
      call write_model(h5, model, err);  if (write_failed(h5, err)) return
      call write_impacts(h5, res, err);  if (write_failed(h5, err)) return
      call write_wear_h5(h5, deck, model, res, err);  if (write_failed(h5, err)) return
      call h5%write('/diagnostics/period', diag%period, '1', err, 'detected period in ' &
         // 'forcing periods; 0: none up to period_max');  if (write_failed(h5, err)) return
      call h5%write('/diagnostics/label', diag%label, '1', err, 'label code: ' // label_codes)
      if (write_failed(h5, err)) return
      call h5%write_text('/diagnostics/label_text', label_text(diag%label), err, &
                         'label: period_<p>, chaotic, undecided, unsettled or failed')
      if (write_failed(h5, err)) return
      call h5%write('/diagnostics/lyapunov', diag%lyapunov, 's-1', err, 'largest Lyapunov ' &
         // 'exponent (0 when lyapunov_periods = 0)');  if (write_failed(h5, err)) return
      call h5%write('/diagnostics/lyapunov_error', diag%lyapunov_error, 's-1', err, &
                    'standard error of the largest Lyapunov exponent')
      if (write_failed(h5, err)) return
      call h5%write('/diagnostics/lyapunov_running', diag%lyapunov_running, 's-1', err, &
                    'running estimate of the largest Lyapunov exponent after each period')
      if (write_failed(h5, err)) return
      call write_evidence(h5, diag, err);  if (write_failed(h5, err)) return
      call h5%write('/final/u', res%u, 'm', err, 'displacement of each dof at the end of the ' &
         // 'run, before the Lyapunov periods (w in m, theta in rad: /model/dof_type)')
      if (write_failed(h5, err)) return
      call h5%write('/final/v', res%v, 'm s-1', err, 'velocity of each dof at the end of the ' &
         // 'run (w in m s-1, theta in rad s-1)');  if (write_failed(h5, err)) return
      call h5%write('/final/time', res%t_end, 's', err, 'end time (transient_periods + ' &
         // 'record_periods) T');  if (write_failed(h5, err)) return
      call h5%close(err)
   end subroutine write_transient_h5

   !> ' (low-pass filtered)' when the deck filters the root strain.
   function filtered_text(deck) result(t)
      type(deck_t), intent(in) :: deck
      character(len=:), allocatable :: t
      t = ''
      if (deck%output%filter_cutoff_hz > 0.0_dp) t = ' (low-pass filtered)'
   end function filtered_text

   !> /history: the samples of the record (and the full state and deflected shape with
   !> &output state_history).
   subroutine write_history(h5, deck, model, res, err)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(error_t), allocatable, intent(out) :: err   !! write failure
      real(dp), allocatable :: nw(:, :), nt(:, :), sw(:, :), forces(:, :)
      integer :: i, np
      call h5%write('/history/time', res%time, 's', err, 'sample time t_rec + (i - 1) T / ' &
         // 'samples_per_period');  if (allocated(err)) return
      call h5%write('/history/strain', res%strain, '1', err, 'root strain c w''''(0), tension ' &
         // 'positive on the -w face');  if (allocated(err)) return
      call h5%write('/history/strain_rate', res%strain_rate, 's-1', err, 'root strain rate')
      if (allocated(err)) return
      if (deck%output%filter_cutoff_hz > 0.0_dp) then
         call h5%write('/history/strain_filtered', res%strain_filtered, '1', err, 'root ' &
            // 'strain through the causal Butterworth low-pass');  if (allocated(err)) return
         call h5%write('/poincare/filter_cutoff_hz', deck%output%filter_cutoff_hz, 'Hz', err, &
                       'cut-off frequency of the low-pass filter');  if (allocated(err)) return
      end if
      call h5%write('/history/tip_displacement', res%tip_displacement, 'm', err, 'tip ' &
         // 'displacement w relative to the base');  if (allocated(err)) return
      forces = transpose(res%stop_force)   ! (stops, samples): one row per sample in C order
      call h5%write('/history/stop_force', forces, 'N', err, 'force magnitude of each stop', &
                    'sample stop');  if (allocated(err)) return
      if (.not. allocated(res%history_u)) return
      np = model%sys%n_node
      allocate(nw(np, size(res%time)), nt(np, size(res%time)))
      do i = 1, size(res%time)
         call nodal_values(model%sys, res%history_u(:, i), nw(:, i), nt(:, i))
      end do
      call h5%write('/history/node_x', shape_points(model%sys, 1), 'm', err, 'position x of ' &
         // 'each node');  if (allocated(err)) return
      call h5%write('/history/node_w', nw, 'm', err, 'transverse displacement w of each node ' &
         // 'relative to the base, at each sample', 'sample node');  if (allocated(err)) return
      call h5%write('/history/node_theta', nt, 'rad', err, 'rotation theta = dw/dx of each ' &
         // 'node, at each sample', 'sample node');  if (allocated(err)) return
      allocate(sw(size(shape_points(model%sys, deck%output%shape_points)), size(res%time)))
      do i = 1, size(res%time)
         sw(:, i) = deflection(model%sys, res%history_u(:, i), deck%output%shape_points)
      end do
      call h5%write('/history/shape_x', shape_points(model%sys, deck%output%shape_points), 'm', &
         err, 'x of the points of the deflected shape (' // str(deck%output%shape_points) &
         // ' per element, the nodes among them)');  if (allocated(err)) return
      call h5%write('/history/shape_w', sw, 'm', err, 'deflected shape w(x) relative to the ' &
         // 'base at each sample, from the element''s cubic Hermite shape functions', &
         'sample point')
      if (allocated(err)) return
      ! for the XDMF file: the deflected shape as points (x, w, 0) and its line segments
      block
         real(dp), allocatable :: xyz(:, :, :), x(:)
         integer, allocatable :: seg(:, :)
         integer :: k
         x = shape_points(model%sys, deck%output%shape_points)
         allocate(xyz(3, size(x), size(res%time)), seg(2, size(x) - 1))
         do i = 1, size(res%time)
            xyz(1, :, i) = x;  xyz(2, :, i) = sw(:, i);  xyz(3, :, i) = 0.0_dp
         end do
         seg(1, :) = [(k - 1, k = 1, size(x) - 1)];  seg(2, :) = seg(1, :) + 1
         call h5%write('/history/shape_xyz', xyz, 'm', err, 'points (x, w, 0) of the ' &
            // 'deflected shape at each sample, the mesh of the .xdmf file', &
            'sample point coordinate')
         if (allocated(err)) return
         call h5%write('/history/shape_segments', seg, '1', err, 'line segments of the ' &
            // 'shape mesh: the two points (from 0) each joins', 'segment end')
         if (allocated(err)) return
      end block
      call write_xdmf_datasets(h5, deck, model, res, err)
   end subroutine write_history

   !> PREFIX.shape.dat: the deflected shape at every history sample, one gnuplot block (index)
   !> per sample, for the animation (scripts/animation.gp).
   subroutine write_shape_table(path, deck, model, res, err)
      character(len=*), intent(in) :: path             !! temporary file name
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results (with history_u)
      type(error_t), allocatable, intent(out) :: err   !! write failure
      real(dp), allocatable :: x(:), w(:)
      character(len=:), allocatable :: text
      character(len=64) :: line
      integer :: i, k, j, n, pos
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
      n = size(res%time)
      block
         character(len=:), allocatable :: buf
         allocate(character(len=len(text) + n * (40 + size(x) * 50)) :: buf)
         buf(1:len(text)) = text
         pos = len(text)
         do i = 1, n
            w = deflection(model%sys, res%history_u(:, i), deck%output%shape_points)
            write(line, '(a, es24.16e3)') '# t = ', res%time(i)
            buf(pos + 1:pos + len_trim(line) + 1) = trim(line) // new_line('a')
            pos = pos + len_trim(line) + 1
            do k = 1, size(x)
               write(line, '(es24.16e3, 1x, es24.16e3)') x(k), w(k)
               buf(pos + 1:pos + len_trim(line) + 1) = trim(adjustl(line)) // new_line('a')
               pos = pos + len_trim(adjustl(line)) + 1
            end do
            buf(pos + 1:pos + 2) = new_line('a') // new_line('a')
            pos = pos + 2
         end do
         call write_text_file(path, buf(1:pos), err, in_place=.true.)
      end block
   end subroutine write_shape_table

   !> The last component of a path ('results/x' -> 'x').
   pure function base_name(path) result(b)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: b
      b = trim(path)
      b = b(index(b, '/', back=.true.) + 1:)
   end function base_name

   !> /run: counters and timings of the integration.
   subroutine write_run(h5, res, err)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(transient_result_t), intent(in) :: res      !! results
      type(error_t), allocatable, intent(out) :: err   !! write failure
      call h5%write('/run/steps_accepted', int(res%steps_accepted), '1', err, 'accepted ' &
         // 'steps (event sub-steps included)');  if (allocated(err)) return
      call h5%write('/run/steps_rejected', int(res%steps_rejected), '1', err, 'steps ' &
         // 'rejected by the step control');  if (allocated(err)) return
      call h5%write('/run/events', int(res%events), '1', err, 'steps split at a located ' &
         // 'contact event');  if (allocated(err)) return
      call h5%write('/run/factorizations', int(res%factorizations), '1', err, &
                    'factorisations of the effective stiffness');  if (allocated(err)) return
      call h5%write('/run/fixed_point_iterations', int(res%fp_iterations), '1', err, &
                    'fixed-point iterations (0 unless stop_solution = fixed_point)')
      if (allocated(err)) return
      call h5%write('/run/cpu_seconds', res%cpu_seconds, 's', err, 'CPU time of the ' &
         // 'integration (the thread that ran it)');  if (allocated(err)) return
      call h5%write('/run/wall_seconds', res%wall_seconds, 's', err, 'wall time of the ' &
         // 'integration');  if (allocated(err)) return
      call h5%write('/run/setup_seconds', res%setup_seconds, 's', err, 'CPU time of the ' &
         // 'model''s set-up (assembly, calibrations, eigenvalues)');  if (allocated(err)) return
      call h5%write_text('/run/method', res%method, err, 'the integrator that ran')
      if (allocated(err)) return
      call h5%write_text('/run/method_reason', res%method_reason, err, 'why that method ' &
         // '(method auto chooses)');  if (allocated(err)) return
      call h5%write('/run/dt_smallest', res%dt_smallest, 's', err, 'smallest step used')
      if (allocated(err)) return
      call h5%write('/run/dt_largest', res%dt_largest, 's', err, 'largest step used')
   end subroutine write_run

   !> /model: the discrete model, so that other tools can integrate the same equations.
   subroutine write_model(h5, model, err)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(model_t), intent(in) :: model               !! model
      type(error_t), allocatable, intent(out) :: err   !! write failure
      call h5%write('/model/stop_stiffness', model%stop_stiffness, 'N m-1', err, 'resolved ' &
         // 'contact stiffness of each stop (N m rad-1 for a theta stop, N m-p for Hertz)')
      if (allocated(err)) return
      call h5%write('/model/f1_open_hz', model%f1_open_hz, 'Hz', err, 'first natural ' &
         // 'frequency with the stops open');  if (allocated(err)) return
      call write_model_matrices(h5, model%sys, err);  if (allocated(err)) return
      call h5%write('/model/damping', model%c, 'N s m-1', err, 'damping matrix C = beta M + ' &
         // 'gamma K; theta entries as for K, times s', 'dof dof');  if (allocated(err)) return
      call h5%write('/model/load_shape', model%q, 'kg', err, 'load shape q = M r: the load ' &
         // 'is P(t) = s(t) q (theta entries kg m)');  if (allocated(err)) return
      call h5%write('/model/forcing_omega', model%omega, 'rad s-1', err, 'forcing angular ' &
         // 'frequency Omega');  if (allocated(err)) return
      call h5%write('/model/forcing_half_amplitude', model%half_amplitude, 'm', err, 'A_pp / ' &
         // '2: s(t) = (A_pp/2) Omega^2 sin(Omega t)');  if (allocated(err)) return
      call h5%write('/model/strain_row', model%sys%strain_row, 'm-1', err, 'root strain = ' &
         // 'strain_row . u (theta entries rad-1)');  if (allocated(err)) return
      call h5%write('/model/contact_dof', model%c_dof, '1', err, 'dof (1-based index) of each ' &
         // 'one-sided contact');  if (allocated(err)) return
      call h5%write('/model/contact_sign', model%c_sign, '1', err, 'direction s of each ' &
         // 'contact: +1 met moving +w, -1 moving -w');  if (allocated(err)) return
      call h5%write('/model/contact_gap', model%c_gap, 'm', err, 'gap of each contact (rad ' &
         // 'for a theta dof)');  if (allocated(err)) return
      call h5%write('/model/contact_stiffness', model%c_k, 'N m-1', err, 'stiffness of each ' &
         // 'contact (N m rad-1 for a theta dof, N m-p for Hertz)');  if (allocated(err)) return
      call h5%write('/model/contact_damping', model%c_c, 'N s m-1', err, 'damper of each ' &
         // 'contact, active in contact only');  if (allocated(err)) return
      call h5%write('/model/contact_law', model%c_law, '1', err, 'law of each contact: ' &
         // '1 bilinear, 2 hertz')
   end subroutine write_model

   !> /impacts: statistics of each stop over the record.
   subroutine write_impacts(h5, res, err)
      type(h5_writer_t), intent(inout) :: h5           !! writer
      type(transient_result_t), intent(in) :: res      !! results
      type(error_t), allocatable, intent(out) :: err   !! write failure
      call h5%write('/impacts/count', res%n_impacts, '1', err, 'contact onsets of each stop ' &
         // 'in the record');  if (allocated(err)) return
      call h5%write('/impacts/peak_force', res%peak_force, 'N', err, 'largest force of each ' &
         // 'stop in the record');  if (allocated(err)) return
      call h5%write('/impacts/rms_force', res%rms_force, 'N', err, 'root mean square force ' &
         // 'of each stop over the record');  if (allocated(err)) return
      call h5%write('/impacts/contact_fraction', res%contact_fraction, '1', err, 'fraction ' &
         // 'of the record each stop is in contact');  if (allocated(err)) return
      call h5%write('/impacts/impulse_per_period', res%impulse_per_period, 'N s', err, &
                    'impulse of each stop per forcing period');  if (allocated(err)) return
      call h5%write('/impacts/work_rate', res%work_rate, 'W', err, 'mean rate of contact ' &
         // 'work of each stop');  if (allocated(err)) return
      call h5%write('/impacts/first_contact_time', res%first_contact_time, 's', err, 'first ' &
         // 'contact onset of each stop from t = 0; -1: never')
   end subroutine write_impacts

   !> /wear (per stop, beside /impacts), /orbit and /model/ring_* (two-plane models), /energy
   !> (when the balance was asked).
   subroutine write_wear_h5(h5, deck, model, res, err)
      type(h5_writer_t), intent(inout) :: h5           !! open writer
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
      real(dp), allocatable :: coef(:), orbit(:, :)
      integer, allocatable :: idof(:)
      integer :: k
      coef = [(deck%stops(k)%wear_coefficient, k = 1, size(deck%stops))]
      call h5%write('/wear/normal_work_rate', res%normal_work_rate, 'W', err, 'normal work ' &
         // 'rate of each support, (1/T) integral of F_N |v_t| dt over the record')
      if (allocated(err)) return
      call h5%write('/wear/sliding_distance', res%sliding_distance, 'm', err, 'distance each ' &
         // 'support slid (the slider''s travel) over the record');  if (allocated(err)) return
      call h5%write('/wear/friction_work', res%friction_work, 'J', err, 'work of the friction ' &
         // 'force of each support over the record');  if (allocated(err)) return
      call h5%write('/wear/friction_work_rate', res%friction_work_rate, 'W', err, 'mean ' &
         // 'friction power of each support');  if (allocated(err)) return
      call h5%write('/wear/wear_volume_rate', res%wear_volume_rate, 'm3 s-1', err, 'Archard ' &
         // 'wear volume rate of each support, wear_coefficient times normal_work_rate')
      if (allocated(err)) return
      call h5%write('/wear/wear_coefficient', coef, 'Pa-1', err, 'Archard wear coefficient ' &
         // 'of each support (m3 per N m of normal work)');  if (allocated(err)) return
      call h5%write('/wear/stick_fraction', res%stick_fraction, '1', err, 'fraction of the ' &
         // 'contact time each support sticks');  if (allocated(err)) return
      if (model%sys%planes > 1) then
         orbit = transpose(res%orbit_w)
         call h5%write('/orbit/w', orbit, 'm', err, 'displacement w of each support''s node ' &
            // 'at the history samples', 'sample stop');  if (allocated(err)) return
         orbit = transpose(res%orbit_v)
         call h5%write('/orbit/v', orbit, 'm', err, 'displacement v of each support''s node ' &
            // 'at the history samples', 'sample stop');  if (allocated(err)) return
         orbit = transpose(res%stop_force)
         call h5%write('/orbit/normal_force', orbit, 'N', err, 'normal (radial) contact force ' &
            // 'of each support at the history samples', 'sample stop')
         if (allocated(err)) return
         orbit = transpose(res%tangential_force)
         call h5%write('/orbit/tangential_force', orbit, 'N', err, 'tangential (friction) ' &
            // 'force of each support at the history samples', 'sample stop')
         if (allocated(err)) return
         call h5%write('/orbit/gap', [(deck%stops(k)%gap, k = 1, size(deck%stops))], 'm', err, &
                       'radial clearance (or gap) of each support');  if (allocated(err)) return
         call h5%write('/orbit/offset_w', [(deck%stops(k)%offset_w, k = 1, size(deck%stops))], &
                       'm', err, 'w of the centre of each hole');  if (allocated(err)) return
         call h5%write('/orbit/offset_v', [(deck%stops(k)%offset_v, k = 1, size(deck%stops))], &
                       'm', err, 'v of the centre of each hole');  if (allocated(err)) return
      end if
      if (model%n_rings > 0) then
         idof = model%r_dof(1, :)
         call h5%write('/model/ring_dof_w', idof, '1', err, 'w dof (1-based index) of each ' &
            // 'ring contact');  if (allocated(err)) return
         idof = model%r_dof(2, :)
         call h5%write('/model/ring_dof_v', idof, '1', err, 'v dof (1-based index) of each ' &
            // 'ring contact');  if (allocated(err)) return
         call h5%write('/model/ring_gap', model%r_gap, 'm', err, 'radial clearance of each ' &
            // 'ring contact');  if (allocated(err)) return
         call h5%write('/model/ring_stiffness', model%r_k, 'N m-1', err, 'normal stiffness of ' &
            // 'each ring contact');  if (allocated(err)) return
         call h5%write('/model/ring_friction', model%r_mu, '1', err, 'Coulomb friction ' &
            // 'coefficient of each ring contact');  if (allocated(err)) return
         call h5%write('/model/ring_tangential_stiffness', model%r_kt, 'N m-1', err, 'stick ' &
            // '(tangential) stiffness of each ring contact');  if (allocated(err)) return
      end if
      if (res%has_energy) then
         call h5%write('/energy/input_work', res%input_work, 'J', err, 'work of the base ' &
            // 'motion and point forces over the record');  if (allocated(err)) return
         call h5%write('/energy/rayleigh_dissipation', res%rayleigh_dissipation, 'J', err, &
                       'energy dissipated by the Rayleigh damping');  if (allocated(err)) return
         call h5%write('/energy/contact_damping_dissipation', res%contact_damping_dissipation, &
                       'J', err, 'energy dissipated by the contact dampers')
         if (allocated(err)) return
         call h5%write('/energy/friction_dissipation', res%friction_dissipation, 'J', err, &
                       'energy dissipated by friction');  if (allocated(err)) return
         call h5%write('/energy/stored_energy_change', res%stored_energy_change, 'J', err, &
                       'change of kinetic, strain and contact-spring energy over the record')
         if (allocated(err)) return
         call h5%write('/energy/imbalance', res%input_work - res%rayleigh_dissipation &
            - res%contact_damping_dissipation - res%friction_dissipation &
            - res%stored_energy_change, 'J', err, 'input work less dissipation and stored ' &
            // 'energy change')
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

   !> The evidence of a transient run's label, its certificate and its starts: the
   !> /diagnostics datasets besides period, label, lyapunov (docs/labels.md).
   subroutine write_evidence(h5, diag, err)
      type(h5_writer_t), intent(inout) :: h5            !! writer with an open file
      type(point_result_t), intent(in) :: diag          !! diagnosed run
      type(error_t), allocatable, intent(out) :: err    !! I/O failure
      character(len=*), parameter :: g = '/diagnostics/'
      integer :: ns
      character(len=*), parameter :: rel = ', relative to the orbit size'
      call h5%write(g // 'lyapunov_periods', diag%lyapunov_periods, '1', err, 'forcing ' &
         // 'periods averaged for the Lyapunov exponent');  if (allocated(err)) return
      call h5%write(g // 'lyapunov_converged', diag%lyapunov_converged, '1', err, '1: sigma ' &
         // 'met its target, 0: stopped at the most periods');  if (allocated(err)) return
      call h5%write(g // 'period_max_tested', diag%period_max_tested, '1', err, 'periods ' &
         // '1..this were tried for a period');  if (allocated(err)) return
      call h5%write(g // 'period_tolerance', diag%period_tolerance, '1', err, 'period ' &
         // 'tolerance used' // rel);  if (allocated(err)) return
      call h5%write(g // 'closest_period', diag%closest_period, '1', err, 'best-repeating ' &
         // 'candidate period in forcing periods');  if (allocated(err)) return
      call h5%write(g // 'repeat_distance', diag%repeat_distance, '1', err, 'repeat ' &
         // 'distance of the closest period' // rel);  if (allocated(err)) return
      call h5%write(g // 'transient_periods', diag%transient_periods, '1', err, 'forcing ' &
         // 'periods before the final record, in all');  if (allocated(err)) return
      call h5%write(g // 'settle_windows', diag%settle_windows, '1', err, 'windows of the ' &
         // 'record compared by the settling test');  if (allocated(err)) return
      call h5%write(g // 'window_difference', diag%window_difference, '1', err, 'largest ' &
         // 'difference of the settling windows' // rel);  if (allocated(err)) return
      call h5%write(g // 'settled', diag%settled, '1', err, '1: the windows agree (or no ' &
         // 'test), 0: not settled');  if (allocated(err)) return
      call h5%write(g // 'strain_range', diag%strain_range, '1', err, 'range of the root ' &
         // 'strain over the final record');  if (allocated(err)) return
      call h5%write(g // 'strain_rate_range', diag%strain_rate_range, 's-1', err, 'range of ' &
         // 'the root strain rate over the final record');  if (allocated(err)) return
      call h5%write(g // 'seconds_label', diag%seconds_label, 's', err, 'CPU time of the ' &
         // 'labelled run');  if (allocated(err)) return
      call h5%write(g // 'seconds_certify', diag%seconds_certify, 's', err, 'CPU time of the ' &
         // 'certificate''s checks');  if (allocated(err)) return
      call h5%write(g // 'certificate', diag%certificate, '1', err, 'certificate: 0 none, ' &
         // '1 certified, 2 disputed');  if (allocated(err)) return
      call h5%write_text(g // 'certificate_text', certificate_text(diag%certificate), err, &
                         'certificate: certified, disputed or none')
      if (allocated(err)) return
      call h5%write_text(g // 'certificate_reason', text_or(diag%certificate_reason, &
         'certification is off (&diagnostics certify = .false.)'), err, 'the certificate ' &
         // 'and its reason');  if (allocated(err)) return
      call h5%write_text(g // 'method', text_or(diag%method, ''), err, 'integration method ' &
         // 'of the labelled run');  if (allocated(err)) return
      call h5%write_text(g // 'accuracy_method', text_or(diag%accuracy_method, ''), err, &
                         'what the accuracy check ran ('''' when none)')
      if (allocated(err)) return
      call h5%write(g // 'accuracy_label', diag%accuracy_label, '1', err, 'label code of the ' &
         // 'accuracy check (-3: the check failed)');  if (allocated(err)) return
      call h5%write(g // 'accuracy_lyapunov', diag%accuracy_lyapunov, 's-1', err, 'Lyapunov ' &
         // 'exponent of the accuracy check');  if (allocated(err)) return
      call h5%write(g // 'accuracy_lyapunov_error', diag%accuracy_lyapunov_error, 's-1', err, &
         'standard error of the Lyapunov exponent of the accuracy check')
      if (allocated(err)) return
      call h5%write(g // 'accuracy_distance', diag%accuracy_distance, '1', err, 'distance ' &
         // 'of the accuracy check''s orbit to the run''s' // rel);  if (allocated(err)) return
      call h5%write(g // 'perturbed_label', diag%perturbed_label, '1', err, 'label code of ' &
         // 'the perturbed start (-3: the check failed)');  if (allocated(err)) return
      call h5%write(g // 'perturbed_lyapunov', diag%perturbed_lyapunov, 's-1', err, &
                    'Lyapunov exponent of the perturbed start');  if (allocated(err)) return
      call h5%write(g // 'perturbed_lyapunov_error', diag%perturbed_lyapunov_error, 's-1', &
         err, 'standard error of the Lyapunov exponent of the perturbed start')
      if (allocated(err)) return
      call h5%write(g // 'perturbed_distance', diag%perturbed_distance, '1', err, 'distance ' &
         // 'of the perturbed start''s orbit to the run''s' // rel);  if (allocated(err)) return
      ns = 0
      if (allocated(diag%start_label)) ns = size(diag%start_label)
      if (ns == 0) return
      call h5%write(g // 'starts/label', diag%start_label, '1', err, 'label code of every ' &
         // 'start (' // label_codes // ')');  if (allocated(err)) return
      call h5%write(g // 'starts/attractor', diag%start_attractor, '1', err, 'attractor ' &
         // 'number each start reached (0: failed)');  if (allocated(err)) return
      call h5%write(g // 'starts/lyapunov', diag%start_lyapunov, 's-1', err, 'largest ' &
         // 'Lyapunov exponent of every start');  if (allocated(err)) return
      call h5%write(g // 'n_attractors', diag%n_attractors, '1', err, 'distinct attractors ' &
         // 'reached by the starts');  if (allocated(err)) return
      call h5%write(g // 'attractors/label', diag%attractor_label, '1', err, 'label code of ' &
         // 'each distinct attractor');  if (allocated(err)) return
      call h5%write(g // 'attractors/fraction', diag%attractor_fraction, '1', err, 'fraction ' &
         // 'of the starts that reached each attractor');  if (allocated(err)) return
      call h5%write(g // 'attractors/lyapunov', diag%attractor_lyapunov, 's-1', err, &
                    'largest Lyapunov exponent of each attractor''s first start')
   end subroutine write_evidence

   !> `t`, or `default` when t is not allocated.
   pure function text_or(t, default) result(s)
      character(len=:), allocatable, intent(in) :: t    !! text
      character(len=*), intent(in) :: default           !! when absent
      character(len=:), allocatable :: s
      if (allocated(t)) then
         s = t
      else
         s = default
      end if
   end function text_or
end module gapbeam_report
