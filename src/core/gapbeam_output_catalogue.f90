!> The output catalogue: every dataset gapbeam writes, described once.
!>
!> Each entry gives the path, the UDUNITS-2 units, the axes and the long name of a dataset;
!> the entries are grouped in sections (the tables of docs/outputs.md), each written by the
!> analyses it names. The HDF5 writer (gapbeam_hdf5_output) takes a value and looks its
!> description up here by analysis and path: a dataset missing from the catalogue cannot be
!> written. `gapbeam --help-outputs` prints the catalogue; docs/outputs.md and the Python
!> reader's field lists are generated from that print (scripts/output_catalogue.py), and the
!> test suite fails when they differ.
!>
!> Conventions of an entry:
!> - path: absolute; a component `<word>` stands for any name (`/work_precision/<series>/x`),
!>   and `curve_<NNN>` for any name starting `curve_`.
!> - units: UDUNITS-2 ('1' for a pure number or a code). Units that depend on the deck start
!>   with '=' followed by what they are in words: the writer is then given them at each call.
!> - dims: one word per axis in C order (as h5py shows the dataset), 'name=size' (the name is
!>   the axis in the `dimensions` attribute that datasets of rank 2 or more carry, the size
!>   what the docs call its length), or only the size for rank 1; '' for a scalar.
!> - long_name: what the values are; a part in braces, `{...}`, is replaced by a text the
!>   writer is given (the braces' text is what the docs show).
module gapbeam_output_catalogue
   use gapbeam_output_studies, only: dataset_t, work_precision_sets, stability_sets, &
      model_size_sets, continuation_sets
   use gapbeam_output_flow, only: sweep_draw_sets, psd_sets
   implicit none
   private
   public :: dataset_t, describe, section_names, section_analyses, catalogue_text, &
      section_datasets, dims_attribute, dims_rank, long_name_text


   !> The sections, in the order of docs/outputs.md, and the analyses that write each.
   character(len=*), parameter :: all_analyses = 'modes calibrate transient sweep ' &
      // 'work_precision stability model_size continuation'
   character(len=*), parameter :: model_analyses = 'transient sweep work_precision stability ' &
      // 'model_size continuation'
   character(len=*), parameter :: section_names(15) = [character(len=16) :: 'file', &
      'parameters', 'structure', 'model', 'modes', 'calibrate', 'history', 'state', &
      'transient', 'tubes', 'sweep', 'work_precision', 'stability', 'model_size', &
      'continuation']
   character(len=*), parameter :: section_analyses(15) = [character(len=96) :: all_analyses, &
      all_analyses, all_analyses, 'modes ' // model_analyses, 'modes', 'calibrate', &
      'transient', 'transient', 'transient', 'transient', 'sweep', 'work_precision', &
      'stability', 'model_size', 'continuation']

   character(len=*), parameter :: label_codes = 'p >= 1: period p; 0: undecided; -1: ' &
      // 'chaotic; -2: unsettled; -3: failed'
   character(len=*), parameter :: rel = ', relative to the orbit size'

   type(dataset_t), parameter :: file_sets(*) = [ &
      dataset_t('/deck', '1', '', 'the effective deck text: deck file and command-line ' &
                // 'overrides'), &
      dataset_t('/run/files', '1', 'n_files', 'the files written together with this one, in ' &
                // 'its directory, by one run (they appear together or not at all)'), &
      dataset_t('/run/warnings', '1', 'n_warnings', 'warnings about the deck and the run, one ' &
                // 'line each, as printed on standard error (none: length 0)')]

   type(dataset_t), parameter :: parameter_sets(*) = [ &
      dataset_t('/parameters/beam/length', 'm', '', 'beam length L'), &
      dataset_t('/parameters/beam/n_elem', '1', '', 'number of elements'), &
      dataset_t('/parameters/beam/element_length', 'm', '', 'element length'), &
      dataset_t('/parameters/beam/youngs_modulus', 'Pa', '', "Young's modulus E"), &
      dataset_t('/parameters/beam/density', 'kg m-3', '', 'density rho'), &
      dataset_t('/parameters/beam/width', 'm', '', 'section width b (rectangle)'), &
      dataset_t('/parameters/beam/thickness', 'm', '', 'section thickness h, in the bending ' &
                // 'direction (rectangle)'), &
      dataset_t('/parameters/beam/area', 'm2', '', 'section area A{ = b h}'), &
      dataset_t('/parameters/beam/second_moment', 'm4', '', 'second moment of area I' &
                // '{ = b h^3 / 12}'), &
      dataset_t('/parameters/beam/fibre_distance', 'm', '', 'distance c of the strain fibre ' &
                // 'from the neutral axis'), &
      dataset_t('/parameters/beam/bending_stiffness', 'N m2', '', 'bending stiffness EI'), &
      dataset_t('/parameters/beam/mass_per_length', 'kg m-1', '', 'mass per unit length rho A'), &
      dataset_t('/parameters/beam/mass', 'kg', '', 'beam mass rho A L'), &
      dataset_t('/parameters/beam/mass_matrix', '1', '', 'element mass matrix'), &
      dataset_t('/parameters/beam/rotary_inertia', '1', '', 'rotary inertia rule of the ' &
                // 'lumped mass matrix'), &
      dataset_t('/parameters/beam/theory', '1', '', 'beam theory: timoshenko (absent for ' &
                // 'Euler-Bernoulli beams)'), &
      dataset_t('/parameters/beam/shear_modulus', 'Pa', '', 'shear modulus G (Timoshenko)'), &
      dataset_t('/parameters/beam/shear_coefficient', '1', '', 'shear coefficient k, 5/6 for ' &
                // 'a rectangle unless the deck gives it (Timoshenko)'), &
      dataset_t('/parameters/beam/shear_stiffness', 'N', '', 'shear stiffness k G A ' &
                // '(Timoshenko)'), &
      dataset_t('/parameters/beam/shear_parameter', '1', '', 'phi = 12 EI / (k G A le^2) of ' &
                // 'the elements (Timoshenko)'), &
      dataset_t('/parameters/beam/planes', '1', '', 'planes of motion: 1 (w, theta) or 2 (w, ' &
                // 'theta, v, theta_v)'), &
      dataset_t('/parameters/beam/added_mass', 'kg m-1', '', 'added (fluid) mass per unit ' &
                // 'length, beside rho A'), &
      dataset_t('/parameters/root/condition', '1', '', 'root condition: clamped, spring ' &
                // '(rotation restrained by k_theta) or pinned'), &
      dataset_t('/parameters/root/k_theta', 'N m rad-1', '', 'root rotational spring k_theta'), &
      dataset_t('/parameters/root/kappa', '1', '', 'root spring ratio kappa = k_theta L / EI'), &
      dataset_t('/parameters/tip/condition', '1', '', 'tip condition: free, clamped, spring ' &
                // '(pinned, rotation restrained by k_theta) or pinned'), &
      dataset_t('/parameters/tip/k_theta', 'N m rad-1', '', 'tip rotational spring k_theta'), &
      dataset_t('/parameters/springs/count', '1', '', 'number of springs to ground'), &
      dataset_t('/parameters/springs/node', '1', 'n_springs', 'node of each spring (1 = root)'), &
      dataset_t('/parameters/springs/dof', '1', 'n_springs', 'dof of each spring: 1 w, 2 ' &
                // 'theta, 3 v, 4 theta_v'), &
      dataset_t('/parameters/springs/stiffness', '=N m-1 (w, v) or N m rad-1 (theta); 1 mixed', &
                'n_springs', 'stiffness of each spring (N m-1 on a displacement, N m rad-1 ' &
                // 'on a rotation)'), &
      dataset_t('/parameters/masses/count', '1', '', 'number of point masses'), &
      dataset_t('/parameters/masses/node', '1', 'n_masses', 'node of each point mass'), &
      dataset_t('/parameters/masses/mass', 'kg', 'n_masses', 'translational mass of each ' &
                // 'point mass'), &
      dataset_t('/parameters/masses/inertia', 'kg m2', 'n_masses', 'rotary inertia of each ' &
                // 'point mass'), &
      dataset_t('/parameters/stops/count', '1', '', 'number of stops'), &
      dataset_t('/parameters/stops/node', '1', 'n_stops', 'node of each stop (1 = root)'), &
      dataset_t('/parameters/stops/dof', '1', 'n_stops', 'dof of each stop: 1 w (transverse ' &
                // 'displacement), 2 theta (rotation)'), &
      dataset_t('/parameters/stops/side', '1', 'n_stops', 'side of each stop: 1 positive (met ' &
                // 'moving +w), -1 negative, 2 both'), &
      dataset_t('/parameters/stops/law', '1', 'n_stops', 'contact law of each stop: 1 ' &
                // 'bilinear, 2 hertz'), &
      dataset_t('/parameters/stops/gap', '=m (w stops) or rad (theta stops); 1 mixed', &
                'n_stops', 'clearance of each stop (m for a w stop, rad for a theta stop)'), &
      dataset_t('/parameters/stops/stiffness', '=N m-1 (w) or N m rad-1 (theta); 1 Hertz or ' &
                // 'mixed', 'n_stops', 'contact stiffness of each stop, the paper''s rule ' &
                // 'applied (N m-1 for a bilinear w stop, N m rad-1 for a theta stop, N m-p ' &
                // 'for a Hertz stop)'), &
      dataset_t('/parameters/stops/damping', '=N s m-1 (w) or N m s rad-1 (theta); 1 mixed', &
                'n_stops', 'contact damper of each stop, active in contact only'), &
      dataset_t('/parameters/stops/exponent', '1', 'n_stops', 'Hertz exponent p of each stop ' &
                // '(bilinear stops: not used)'), &
      dataset_t('/parameters/stops/rule_factor', '1', 'n_stops', 'stiffness rule of each ' &
                // 'stop: k = factor x the lowest spring raising f1 to the target (0: the ' &
                // 'stiffness given)'), &
      dataset_t('/parameters/stops/rule_f1_ratio', '1', 'n_stops', 'target of the rule: f1 / ' &
                // 'f1 of the open structure (0: rule_f1_hz)'), &
      dataset_t('/parameters/stops/rule_f1_hz', 'Hz', 'n_stops', 'target of the rule: f1'), &
      dataset_t('/parameters/stops/circular', '1', 'n_stops', 'shape of each support: 0 flat ' &
                // '(one dof), 1 circular (a hole: radial clearance in the w-v plane)'), &
      dataset_t('/parameters/stops/offset_w', 'm', 'n_stops', 'w of the centre of each hole'), &
      dataset_t('/parameters/stops/offset_v', 'm', 'n_stops', 'v of the centre of each hole'), &
      dataset_t('/parameters/stops/friction', '1', 'n_stops', 'Coulomb friction coefficient ' &
                // 'mu of each support'), &
      dataset_t('/parameters/stops/tangential_stiffness', 'N m-1', 'n_stops', 'stick ' &
                // '(tangential) stiffness of each support (0: the normal stiffness)'), &
      dataset_t('/parameters/stops/wear_coefficient', 'Pa-1', 'n_stops', 'Archard wear ' &
                // 'coefficient of each support (m3 per N m of normal work)'), &
      dataset_t('/parameters/damping/model', '1', '', 'damping model'), &
      dataset_t('/parameters/damping/mass_coefficient', 's-1', '', 'Rayleigh mass ' &
                // 'coefficient beta in C = beta M + gamma K'), &
      dataset_t('/parameters/damping/stiffness_coefficient', 's', '', 'Rayleigh stiffness ' &
                // 'coefficient gamma in C = beta M + gamma K'), &
      dataset_t('/parameters/damping/frequency1_hz', 'Hz', '', 'first frequency of the ' &
                // 'two damping ratios (model ratios)'), &
      dataset_t('/parameters/damping/ratio1', '1', '', 'damping ratio at frequency1_hz'), &
      dataset_t('/parameters/damping/frequency2_hz', 'Hz', '', 'second frequency of the two ' &
                // 'damping ratios'), &
      dataset_t('/parameters/damping/ratio2', '1', '', 'damping ratio at frequency2_hz'), &
      dataset_t('/parameters/damping/modal_ratios', '1', 'n_ratios', 'modal damping ratios of ' &
                // 'modes 1, 2, ... of each plane, the last one for every further mode, beside ' &
                // 'the Rayleigh terms (model modal)'), &
      dataset_t('/parameters/forcing/frequency_hz', 'Hz', '', 'forcing frequency f of the ' &
                // 'deck (a sweep varies it: /sweep)'), &
      dataset_t('/parameters/forcing/amplitude_pp', 'm', '', 'base displacement amplitude, ' &
                // 'peak to peak (a sweep varies it)'), &
      dataset_t('/parameters/forcing/period', 's', '', 'forcing period T = 1/f'), &
      dataset_t('/parameters/forcing/omega', 'rad s-1', '', 'forcing angular frequency 2 pi f'), &
      dataset_t('/parameters/forcing/direction_deg', 'degree', '', 'direction psi of the base ' &
                // 'motion from w towards v (two planes)'), &
      dataset_t('/parameters/forcing/phase_v_deg', 'degree', '', 'phase phi of the v ' &
                // 'component of the base motion (a whirl: psi = 45, phi = +-90)'), &
      dataset_t('/parameters/point_forces/count', '1', '', 'number of harmonic point forces'), &
      dataset_t('/parameters/point_forces/node', '1', 'n_forces', 'node of each point force'), &
      dataset_t('/parameters/point_forces/dof', '1', 'n_forces', 'dof of each point force: 1 ' &
                // 'w, 2 theta, 3 v, 4 theta_v'), &
      dataset_t('/parameters/point_forces/amplitude', '=N (w, v) or N m (theta); 1 mixed', &
                'n_forces', 'amplitude F of each point force, F sin(Omega t + phase)'), &
      dataset_t('/parameters/point_forces/phase_deg', 'degree', 'n_forces', 'phase of each ' &
                // 'point force'), &
      dataset_t('/parameters/model/f1_open_hz', 'Hz', '', 'first natural frequency with the ' &
                // 'stops open'), &
      dataset_t('/parameters/model/f_max_hz', 'Hz', '', 'highest natural frequency of the ' &
                // 'integrated model'), &
      dataset_t('/parameters/model/n_dof', '1', '', 'degrees of freedom of the integrated ' &
                // 'model'), &
      dataset_t('/parameters/model/reduction', '1', '', 'none: the finite element model; ' &
                // 'modal: a modal model of it'), &
      dataset_t('/parameters/model/n_modes', '1', '', 'modes of the open structure kept by ' &
                // 'the modal model'), &
      dataset_t('/parameters/model/static_correction', '1', '', '1: the modal model adds the ' &
                // 'residual flexibility at each stop dof, 0: not')]

   type(dataset_t), parameter :: structure_sets(*) = [ &
      dataset_t('/model/stiffness', 'N m-1', 'dof=n_dof dof=n_dof', 'stiffness matrix K ' &
                // '(beam, root spring, springs); entries (w, w) N m-1, (w, theta) N rad-1, ' &
                // '(theta, theta) N m rad-1: /model/dof_type says which dof is which'), &
      dataset_t('/model/mass', 'kg', 'dof=n_dof dof=n_dof', 'mass matrix M; entries (w, w) ' &
                // 'kg, (w, theta) kg m rad-1, (theta, theta) kg m2 rad-2'), &
      dataset_t('/model/dof_node', '1', 'n_dof', 'node of each degree of freedom (1 = root, ' &
                // 'node i at x = (i - 1) le)'), &
      dataset_t('/model/dof_type', '1', 'n_dof', 'kind of each degree of freedom: 1 w ' &
                // '(transverse displacement, m), 2 theta (rotation dw/dx, rad), 3 v, 4 ' &
                // 'theta_v (the second plane)'), &
      dataset_t('/model/dof_name', '1', 'n_dof', 'name of each degree of freedom: w_<node>, ' &
                // 'theta_<node>, v_<node> or theta_v_<node>')]

   type(dataset_t), parameter :: model_sets(*) = [ &
      dataset_t('/model/stop_stiffness', '=N m-1 (w) or N m rad-1 (theta); 1 Hertz or mixed', &
                'n_stops', 'resolved contact stiffness of each stop, the paper''s rule ' &
                // 'applied (N m-1 for a bilinear w stop, N m rad-1 for a theta stop, N m-p ' &
                // 'for a Hertz stop)'), &
      dataset_t('/model/f1_open_hz', 'Hz', '', 'first natural frequency with the stops open'), &
      dataset_t('/model/damping', 'N s m-1', 'dof=n_dof dof=n_dof', 'damping matrix C = beta ' &
                // 'M + gamma K{ + M Phi diag(2 zeta omega) Phi^T M with modal damping}; theta ' &
                // 'entries as for K, times s'), &
      dataset_t('/model/load_shape', 'kg', 'n_dof', 'load shape q = M r: the load is P(t) = ' &
                // 's(t) q (theta entries kg m)'), &
      dataset_t('/model/forcing_omega', 'rad s-1', '', 'forcing angular frequency Omega'), &
      dataset_t('/model/forcing_half_amplitude', 'm', '', 'A_pp / 2: s(t) = (A_pp/2) Omega^2 ' &
                // 'sin(Omega t)'), &
      dataset_t('/model/strain_row', 'm-1', 'n_dof', 'root strain = strain_row . u (theta ' &
                // 'entries rad-1)'), &
      dataset_t('/model/contact_dof', '1', 'n_contacts', 'dof (1-based index) of each ' &
                // 'one-sided contact'), &
      dataset_t('/model/contact_sign', '1', 'n_contacts', 'direction s of each contact: +1 ' &
                // 'met moving +w, -1 moving -w'), &
      dataset_t('/model/contact_gap', 'm', 'n_contacts', 'gap of each contact (rad for a ' &
                // 'theta dof)'), &
      dataset_t('/model/contact_stiffness', 'N m-1', 'n_contacts', 'stiffness of each contact ' &
                // '(N m rad-1 for a theta dof, N m-p for Hertz)'), &
      dataset_t('/model/contact_damping', 'N s m-1', 'n_contacts', 'damper of each contact, ' &
                // 'active in contact only'), &
      dataset_t('/model/contact_law', '1', 'n_contacts', 'law of each contact: 1 bilinear, ' &
                // '2 hertz'), &
      dataset_t('/model/ring_dof_w', '1', 'n_rings', 'w dof (1-based index) of each ring ' &
                // 'contact'), &
      dataset_t('/model/ring_dof_v', '1', 'n_rings', 'v dof (1-based index) of each ring ' &
                // 'contact'), &
      dataset_t('/model/ring_gap', 'm', 'n_rings', 'radial clearance of each ring contact'), &
      dataset_t('/model/ring_stiffness', 'N m-1', 'n_rings', 'normal stiffness of each ring ' &
                // 'contact'), &
      dataset_t('/model/ring_friction', '1', 'n_rings', 'Coulomb friction coefficient of ' &
                // 'each ring contact'), &
      dataset_t('/model/ring_tangential_stiffness', 'N m-1', 'n_rings', 'stick (tangential) ' &
                // 'stiffness of each ring contact')]

   type(dataset_t), parameter :: modes_sets(*) = [ &
      dataset_t('/flow/frequency_hz', 'Hz', 'n_flow_modes', 'natural frequency of every mode ' &
                // 'of the open structure, ascending (both planes; written with &flow ' &
                // 'fluid_density and tube_diameter > 0)'), &
      dataset_t('/flow/plane', '1', 'n_flow_modes', 'plane of each mode: 1 w, 2 v'), &
      dataset_t('/flow/structural_ratio', '1', 'n_flow_modes', 'structural damping ratio ' &
                // 'of each mode (Rayleigh and modal)'), &
      dataset_t('/flow/velocity_ratio', '1', 'n_flow_modes', '(U_e/U)^2 of each mode: the ' &
                // 'mode-shape-squared weighted square of the flow profile'), &
      dataset_t('/flow/critical_velocity', 'm s-1', 'n_flow_modes', 'Connors critical ' &
                // 'velocity of each mode, the reference velocity at which its net damping ' &
                // 'vanishes (1.8e308: no flow on the mode)'), &
      dataset_t('/flow/fluid_ratio', '1', 'n_flow_modes', 'fluid-elastic damping ratio of ' &
                // 'each mode at &flow velocity (negative)'), &
      dataset_t('/flow/velocity', 'm s-1', '', 'the reference flow velocity U (&flow ' &
                // 'velocity)'), &
      dataset_t('/modes/frequency_hz', 'Hz', 'n_modes', 'natural frequency of each mode ' &
                // '(stops open)'), &
      dataset_t('/modes/shapes', 'kg-1/2', 'mode=n_modes dof=n_dof', 'mass-normalised mode ' &
                // 'shapes (phi^T M phi = 1): w entries m kg-1/2 per m of modal coordinate, ' &
                // 'theta entries rad kg-1/2; /model/dof_type says which is which'), &
      dataset_t('/modes/participation', 'kg1/2', 'n_modes', 'base-excitation participation ' &
                // 'factor phi^T M r of each mode'), &
      dataset_t('/modes/effective_mass', 'kg', 'n_modes', 'effective modal mass (phi^T M r)^2 ' &
                // 'of each mode'), &
      dataset_t('/modes/moving_mass', 'kg', '', 'mass moved by the base, r^T M r'), &
      dataset_t('/modes/node_x', 'm', 'n_node', 'position x of each node'), &
      dataset_t('/modes/node_w', 'kg-1/2', 'mode=n_modes node=n_node', 'transverse ' &
                // 'displacement w of each mode at the nodes (0 at the root), mass-normalised'), &
      dataset_t('/modes/shape_x', 'm', 'n_shape', 'x of the points of the shape curves (16 ' &
                // 'per element, the nodes among them)'), &
      dataset_t('/modes/shape_w', 'kg-1/2', 'mode=n_modes point=n_shape', 'w of each mode ' &
                // 'between the nodes from the element''s cubic Hermite shape functions, ' &
                // 'mass-normalised')]

   type(dataset_t), parameter :: calibrate_sets(*) = [ &
      dataset_t('/calibrate/parameter', '1', '', 'the fitted parameter (&calibrate parameter)'), &
      dataset_t('/calibrate/value', '=the parameter''s: N m rad-1, N m-1 or m', '', 'fitted ' &
                // 'value of the parameter'), &
      dataset_t('/calibrate/target_f1_hz', 'Hz', '', 'target first natural frequency'), &
      dataset_t('/calibrate/f1_hz', 'Hz', '', 'first natural frequency recomputed with the ' &
                // 'fitted value')]

   type(dataset_t), parameter :: history_sets(*) = [ &
      dataset_t('/history/time', 's', 'n_hist', 'sample time t_rec + (i - 1) T / ' &
                // 'samples_per_period, t_rec = transient_periods T (the time of the whole ' &
                // 'trajectory)'), &
      dataset_t('/history/strain', '1', 'n_hist', 'root strain c w''''(0), tension positive ' &
                // 'on the -w face'), &
      dataset_t('/history/strain_rate', 's-1', 'n_hist', 'root strain rate'), &
      dataset_t('/history/strain_filtered', '1', 'n_hist', 'root strain through the causal ' &
                // 'Butterworth low-pass'), &
      dataset_t('/history/tip_displacement', 'm', 'n_hist', 'tip displacement w relative to ' &
                // 'the base'), &
      dataset_t('/history/stop_force', 'N', 'sample=n_hist stop=n_stops', 'force magnitude of ' &
                // 'each stop'), &
      dataset_t('/poincare/filter_cutoff_hz', 'Hz', '', 'cut-off frequency of the low-pass ' &
                // 'filter')]

   type(dataset_t), parameter :: state_sets(*) = [ &
      dataset_t('/history/node_x', 'm', 'n_node', 'position x of each node'), &
      dataset_t('/history/node_w', 'm', 'sample=n_hist node=n_node', 'transverse displacement ' &
                // 'w of each node relative to the base, at each sample'), &
      dataset_t('/history/node_theta', 'rad', 'sample=n_hist node=n_node', 'rotation theta = ' &
                // 'dw/dx of each node, at each sample'), &
      dataset_t('/history/shape_x', 'm', 'n_points', 'x of the points of the deflected shape ' &
                // '({shape_points} per element, the nodes among them)'), &
      dataset_t('/history/shape_w', 'm', 'sample=n_hist point=n_points', 'deflected shape ' &
                // 'w(x) relative to the base at each sample, from the element''s cubic ' &
                // 'Hermite shape functions'), &
      dataset_t('/history/shape_xyz', 'm', 'sample=n_hist point=n_points coordinate=3', &
                'points (x, w, 0) of the deflected shape at each sample (the .xdmf file reads ' &
                // 'shape_mesh_xyz and shape_displacement)'), &
      dataset_t('/history/shape_segments', '1', 'segment=n_points-1 end=2', 'line segments ' &
                // 'of the shape mesh: the two points (from 0) each joins'), &
      dataset_t('/history/shape_mesh_xyz', 'm', 'point=n_points coordinate=3', 'undeformed ' &
                // 'points (x, 0, 0) of the shape mesh: the geometry of the .xdmf file'), &
      dataset_t('/history/shape_displacement', 'm', 'sample=n_hist point=n_points ' &
                // 'component=3', 'displacement (0, w, v) of the points of the shape mesh ' &
                // 'relative to the base at each sample: the warp vector of the .xdmf file'), &
      dataset_t('/history/shape_v', 'm', 'sample=n_hist point=n_points', 'deflected shape ' &
                // 'v(x) in the second plane relative to the base at each sample (two-plane ' &
                // 'models)'), &
      dataset_t('/history/stop_contact', '1', 'sample=n_hist stop=n_stops', 'contact state ' &
                // 'of each stop at each sample: 1 while it pushes on the beam (force > 0), 0 ' &
                // 'open'), &
      dataset_t('/history/stop_mesh_xyz', 'm', 'point=n_stop_points coordinate=3', &
                'undeformed points of the drawn stops of the .xdmf file, on the x axis at ' &
                // 'their nodes'), &
      dataset_t('/history/stop_mesh_displacement', 'm', 'point=n_stop_points component=3', &
                'displacement (0, w, v) placing the drawn stops relative to the base: a flat ' &
                // 'stop''s face at its gap, a circular one''s circle')]

   type(dataset_t), parameter :: transient_sets(*) = [ &
      dataset_t('/poincare/time', 's', 'record_periods', 'time of each Poincare point, t_rec ' &
                // '+ (i - 1 + phase/360) T (the time of the whole trajectory)'), &
      dataset_t('/poincare/strain', '1', 'record_periods', 'root strain at the Poincare ' &
                // 'section{ (low-pass filtered, with the filter)}'), &
      dataset_t('/poincare/strain_rate', 's-1', 'record_periods', 'root strain rate at the ' &
                // 'Poincare section{ (low-pass filtered, with the filter)}'), &
      dataset_t('/poincare/tip_displacement', 'm', 'record_periods', 'tip displacement w ' &
                // 'relative to the base at the Poincare section'), &
      dataset_t('/poincare/tip_velocity', 'm s-1', 'record_periods', 'tip velocity relative ' &
                // 'to the base at the Poincare section'), &
      dataset_t('/run/steps_accepted', '1', '', 'accepted steps (event sub-steps included)'), &
      dataset_t('/run/steps_rejected', '1', '', 'steps rejected by the step control'), &
      dataset_t('/run/events', '1', '', 'steps split at a located contact event'), &
      dataset_t('/run/factorizations', '1', '', 'factorisations of the effective stiffness'), &
      dataset_t('/run/fixed_point_iterations', '1', '', 'fixed-point iterations (0 unless ' &
                // 'stop_solution = fixed_point)'), &
      dataset_t('/run/cpu_seconds', 's', '', 'CPU time of the integration (the thread that ' &
                // 'ran it)'), &
      dataset_t('/run/wall_seconds', 's', '', 'wall time of the integration'), &
      dataset_t('/run/setup_seconds', 's', '', 'CPU time of the model''s set-up (assembly, ' &
                // 'calibrations, eigenvalues)'), &
      dataset_t('/run/method', '1', '', 'the integrator that ran'), &
      dataset_t('/run/method_reason', '1', '', 'why that method (method auto chooses)'), &
      dataset_t('/run/dt_smallest', 's', '', 'smallest step used'), &
      dataset_t('/run/dt_largest', 's', '', 'largest step used'), &
      dataset_t('/impacts/count', '1', 'n_stops', 'contact onsets of each stop in the record'), &
      dataset_t('/impacts/peak_force', 'N', 'n_stops', 'largest force of each stop in the ' &
                // 'record'), &
      dataset_t('/impacts/rms_force', 'N', 'n_stops', 'root mean square force of each stop ' &
                // 'over the record'), &
      dataset_t('/impacts/contact_fraction', '1', 'n_stops', 'fraction of the record each ' &
                // 'stop is in contact'), &
      dataset_t('/impacts/impulse_per_period', 'N s', 'n_stops', 'impulse of each stop per ' &
                // 'forcing period'), &
      dataset_t('/impacts/work_rate', 'W', 'n_stops', 'mean rate of contact work of each ' &
                // 'stop'), &
      dataset_t('/impacts/first_contact_time', 's', 'n_stops', 'first contact onset of each ' &
                // 'stop from t = 0; -1: never'), &
      dataset_t('/diagnostics/period', '1', '', 'detected period in forcing periods; 0: none ' &
                // 'up to period_max'), &
      dataset_t('/diagnostics/label', '1', '', 'label code: ' // label_codes), &
      dataset_t('/diagnostics/label_text', '1', '', 'label: period_<p>, chaotic, undecided, ' &
                // 'unsettled or failed'), &
      dataset_t('/diagnostics/lyapunov', 's-1', '', 'largest Lyapunov exponent (0 when ' &
                // 'lyapunov_periods = 0)'), &
      dataset_t('/diagnostics/lyapunov_error', 's-1', '', 'standard error of the largest ' &
                // 'Lyapunov exponent'), &
      dataset_t('/diagnostics/lyapunov_running', 's-1', 'lyapunov_periods', 'running ' &
                // 'estimate of the largest Lyapunov exponent after each period'), &
      dataset_t('/diagnostics/lyapunov_periods', '1', '', 'forcing periods averaged for the ' &
                // 'Lyapunov exponent'), &
      dataset_t('/diagnostics/lyapunov_converged', '1', '', '1: sigma met its target, 0: ' &
                // 'stopped at the most periods'), &
      dataset_t('/diagnostics/lyapunov_dropped', '1', '', 'periods of the exponent''s pair ' &
                // 'not counted: their two step sequences differed from every side tried ' &
                // '(ring supports)'), &
      dataset_t('/diagnostics/lyapunov_rerun', '1', '', 'periods of the exponent''s pair ' &
                // 'run again from the other side: their step sequences differed (ring ' &
                // 'supports)'), &
      dataset_t('/diagnostics/lyapunov_starts', '1', '', 'independent starts combined in the ' &
                // 'exponent (0: no exponent)'), &
      dataset_t('/diagnostics/lyapunov_spread', 's-1', '', 'standard error of the exponent ' &
                // 'from the spread of its starts (0: one start)'), &
      dataset_t('/diagnostics/period_max_tested', '1', '', 'periods 1..this were tried for a ' &
                // 'period'), &
      dataset_t('/diagnostics/period_tolerance', '1', '', 'period tolerance used' // rel), &
      dataset_t('/diagnostics/closest_period', '1', '', 'best-repeating candidate period in ' &
                // 'forcing periods'), &
      dataset_t('/diagnostics/repeat_distance', '1', '', 'repeat distance of the closest ' &
                // 'period' // rel), &
      dataset_t('/diagnostics/transient_periods', '1', '', 'forcing periods before the final ' &
                // 'record, in all'), &
      dataset_t('/diagnostics/settle_windows', '1', '', 'windows of the record compared by ' &
                // 'the settling test'), &
      dataset_t('/diagnostics/window_difference', '1', '', 'largest difference of the ' &
                // 'settling windows' // rel), &
      dataset_t('/diagnostics/settled', '1', '', '1: the windows agree (or no test), 0: not ' &
                // 'settled'), &
      dataset_t('/diagnostics/strain_range', '1', '', 'range of the root strain over the ' &
                // 'final record'), &
      dataset_t('/diagnostics/strain_rate_range', 's-1', '', 'range of the root strain rate ' &
                // 'over the final record'), &
      dataset_t('/diagnostics/seconds_label', 's', '', 'CPU time of the labelled run'), &
      dataset_t('/diagnostics/seconds_certify', 's', '', 'CPU time of the certificate''s ' &
                // 'checks'), &
      dataset_t('/diagnostics/certificate', '1', '', 'certificate: 0 none, 1 certified, 2 ' &
                // 'disputed'), &
      dataset_t('/diagnostics/certificate_text', '1', '', 'certificate: certified, disputed ' &
                // 'or none'), &
      dataset_t('/diagnostics/certificate_reason', '1', '', 'the certificate and its reason'), &
      dataset_t('/diagnostics/method', '1', '', 'integration method of the labelled run'), &
      dataset_t('/diagnostics/accuracy_method', '1', '', 'what the accuracy check ran ('''' ' &
                // 'when none)'), &
      dataset_t('/diagnostics/accuracy_label', '1', '', 'label code of the accuracy check ' &
                // '(-3: the check failed)'), &
      dataset_t('/diagnostics/accuracy_lyapunov', 's-1', '', 'Lyapunov exponent of the ' &
                // 'accuracy check'), &
      dataset_t('/diagnostics/accuracy_lyapunov_error', 's-1', '', 'standard error of the ' &
                // 'Lyapunov exponent of the accuracy check'), &
      dataset_t('/diagnostics/accuracy_distance', '1', '', 'distance of the accuracy check''s ' &
                // 'orbit to the run''s' // rel), &
      dataset_t('/diagnostics/perturbed_label', '1', '', 'label code of the perturbed start ' &
                // '(-3: the check failed)'), &
      dataset_t('/diagnostics/perturbed_lyapunov', 's-1', '', 'Lyapunov exponent of the ' &
                // 'perturbed start'), &
      dataset_t('/diagnostics/perturbed_lyapunov_error', 's-1', '', 'standard error of the ' &
                // 'Lyapunov exponent of the perturbed start'), &
      dataset_t('/diagnostics/perturbed_distance', '1', '', 'distance of the perturbed ' &
                // 'start''s orbit to the run''s' // rel), &
      dataset_t('/diagnostics/starts/label', '1', 'n_starts', 'label code of every start (' &
                // label_codes // ')'), &
      dataset_t('/diagnostics/starts/attractor', '1', 'n_starts', 'attractor number each ' &
                // 'start reached (0: failed)'), &
      dataset_t('/diagnostics/starts/lyapunov', 's-1', 'n_starts', 'largest Lyapunov ' &
                // 'exponent of every start'), &
      dataset_t('/diagnostics/n_attractors', '1', '', 'distinct attractors reached by the ' &
                // 'starts'), &
      dataset_t('/diagnostics/attractors/label', '1', 'n_attractors', 'label code of each ' &
                // 'distinct attractor'), &
      dataset_t('/diagnostics/attractors/fraction', '1', 'n_attractors', 'fraction of the ' &
                // 'starts that reached each attractor'), &
      dataset_t('/diagnostics/attractors/lyapunov', 's-1', 'n_attractors', 'largest Lyapunov ' &
                // 'exponent of each attractor''s first start'), &
      dataset_t('/diagnostics/starts/transient_periods', '1', 'n_starts', 'periods each ' &
                // 'start ran before its final record (transient and settling extensions)'), &
      dataset_t('/diagnostics/attractors/mean_transient_periods', '1', 'n_attractors', &
                'mean over the starts reaching each attractor of their transient periods'), &
      dataset_t('/final/u', 'm', 'n_dof', 'displacement of each dof at the end of the run, ' &
                // 'before the Lyapunov periods (w in m, theta in rad: /model/dof_type)'), &
      dataset_t('/final/v', 'm s-1', 'n_dof', 'velocity of each dof at the end of the run (w ' &
                // 'in m s-1, theta in rad s-1)'), &
      dataset_t('/final/time', 's', '', 'end time (transient_periods + record_periods) T')]

   type(dataset_t), parameter :: tube_sets(*) = [ &
      dataset_t('/wear/normal_work_rate', 'W', 'n_stops', 'normal work rate of each support, ' &
                // '(1/T) integral of F_N |v_slip| dt over the record, slip only'), &
      dataset_t('/wear/sliding_distance', 'm', 'n_stops', 'distance each support slid (the ' &
                // 'slider''s travel) over the record'), &
      dataset_t('/wear/friction_work', 'J', 'n_stops', 'work of the friction force of each ' &
                // 'support over the record'), &
      dataset_t('/wear/friction_work_rate', 'W', 'n_stops', 'mean friction power of each ' &
                // 'support'), &
      dataset_t('/wear/wear_volume_rate', 'm3 s-1', 'n_stops', 'Archard wear volume rate of ' &
                // 'each support, wear_coefficient times normal_work_rate'), &
      dataset_t('/wear/wear_coefficient', 'Pa-1', 'n_stops', 'Archard wear coefficient of ' &
                // 'each support (m3 per N m of normal work)'), &
      dataset_t('/wear/stick_fraction', '1', 'n_stops', 'fraction of the contact time each ' &
                // 'support sticks'), &
      dataset_t('/wear/depth_time', '31557600 s', 'n_depth', 'operating time in Julian ' &
                // 'years, 0 to &wear years (written with &wear years > 0)'), &
      dataset_t('/wear/depth', 'm', 'time=n_depth stop=n_stops', 'wear depth of each ' &
                // 'support''s scar in the tube wall after that time at the wear volume rate ' &
                // '(flat bar or drilled hole geometry, docs/flow.md; at most the wall)'), &
      dataset_t('/wear/years_to_wall_fraction', '31557600 s', 'n_stops', 'operating time ' &
                // '(Julian years) until the scar of each support reaches wall_fraction of ' &
                // 'the wall (1.8e308: ' &
                // 'never)'), &
      dataset_t('/wear/wall_fraction', '1', '', 'fraction of the wall of ' &
                // 'years_to_wall_fraction (&wear wall_fraction)'), &
      dataset_t('/wear/wall_thickness', 'm', '', 'tube wall thickness (&wear wall_thickness)'), &
      dataset_t('/statistics/draws', '1', '', 'random draws (&turbulence draws) the ' &
                // 'statistics are taken over'), &
      dataset_t('/statistics/impact_rate', 's-1', 'n_stops', '' &
                // 'impacts per second of each stop: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/impact_rate_ci', 's-1', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/impact_rate (Student t)'), &
      dataset_t('/statistics/peak_force', 'N', 'n_stops', '' &
                // 'peak contact force of each stop: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/peak_force_ci', 'N', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/peak_force (Student t)'), &
      dataset_t('/statistics/rms_force', 'N', 'n_stops', '' &
                // 'RMS contact force of each stop: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/rms_force_ci', 'N', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/rms_force (Student t)'), &
      dataset_t('/statistics/contact_fraction', '1', 'n_stops', '' &
                // 'fraction of the record each stop is in contact: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/contact_fraction_ci', '1', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/contact_fraction (Student t)'), &
      dataset_t('/statistics/work_rate', 'W', 'n_stops', '' &
                // 'impact work rate of each stop: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/work_rate_ci', 'W', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/work_rate (Student t)'), &
      dataset_t('/statistics/normal_work_rate', 'W', 'n_stops', '' &
                // 'normal work rate of each support: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/normal_work_rate_ci', 'W', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/normal_work_rate (Student t)'), &
      dataset_t('/statistics/friction_work_rate', 'W', 'n_stops', '' &
                // 'friction work rate of each support: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/friction_work_rate_ci', 'W', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/friction_work_rate (Student t)'), &
      dataset_t('/statistics/wear_volume_rate', 'm3 s-1', 'n_stops', '' &
                // 'Archard wear volume rate of each support: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/wear_volume_rate_ci', 'm3 s-1', 'n_stops', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/wear_volume_rate (Student t)'), &
      dataset_t('/statistics/tip_rms_displacement', 'm', '', '' &
                // 'RMS tip displacement over the history samples: mean over ' &
                // 'the draws'), &
      dataset_t('/statistics/tip_rms_displacement_ci', 'm', '', 'half-width of the 95 % ' &
                // 'confidence interval of /statistics/tip_rms_displacement (Student t)'), &
      dataset_t('/orbit/w', 'm', 'sample=n_hist stop=n_stops', 'displacement w of each ' &
                // 'support''s node at the history samples'), &
      dataset_t('/orbit/v', 'm', 'sample=n_hist stop=n_stops', 'displacement v of each ' &
                // 'support''s node at the history samples'), &
      dataset_t('/orbit/normal_force', 'N', 'sample=n_hist stop=n_stops', 'normal (radial) ' &
                // 'contact force of each support at the history samples'), &
      dataset_t('/orbit/tangential_force', 'N', 'sample=n_hist stop=n_stops', 'tangential ' &
                // '(friction) force of each support at the history samples'), &
      dataset_t('/orbit/gap', 'm', 'n_stops', 'radial clearance (or gap) of each support'), &
      dataset_t('/orbit/offset_w', 'm', 'n_stops', 'w of the centre of each hole'), &
      dataset_t('/orbit/offset_v', 'm', 'n_stops', 'v of the centre of each hole'), &
      dataset_t('/energy/input_work', 'J', '', 'work of the base motion and point forces over ' &
                // 'the record'), &
      dataset_t('/energy/rayleigh_dissipation', 'J', '', 'energy dissipated by the Rayleigh ' &
                // 'damping'), &
      dataset_t('/energy/contact_damping_dissipation', 'J', '', 'energy dissipated by the ' &
                // 'contact dampers'), &
      dataset_t('/energy/friction_dissipation', 'J', '', 'energy dissipated by friction'), &
      dataset_t('/energy/stored_energy_change', 'J', '', 'change of kinetic, strain and ' &
                // 'contact-spring energy over the record'), &
      dataset_t('/energy/imbalance', 'J', '', 'input work less dissipation and stored energy ' &
                // 'change')]

   type(dataset_t), parameter :: sweep_sets(*) = [ &
      dataset_t('/sweep/point_index', '1', 'm', 'point number p = i_x + (i_y - 1) n_x of each ' &
                // 'point of the file (x fastest)'), &
      dataset_t('/sweep/frequency_hz', 'Hz', 'm', 'forcing frequency of the point'), &
      dataset_t('/sweep/amplitude_pp', 'm', 'm', 'base displacement amplitude of the point, ' &
                // 'peak to peak'), &
      dataset_t('/sweep/period', '1', 'm', 'detected period in forcing periods; 0: none up ' &
                // 'to period_max'), &
      dataset_t('/sweep/label', '1', 'm', 'label code of the point (' // label_codes // ')'), &
      dataset_t('/sweep/label_text', '1', 'm', 'label: period_<p>, chaotic, undecided, ' &
                // 'unsettled or failed'), &
      dataset_t('/sweep/lyapunov', 's-1', 'm', 'largest Lyapunov exponent'), &
      dataset_t('/sweep/lyapunov_error', 's-1', 'm', 'standard error of the largest Lyapunov ' &
                // 'exponent'), &
      dataset_t('/sweep/status', '1', 'm', 'status of the point: 0 done, 1 failed (results ' &
                // 'NaN)'), &
      dataset_t('/sweep/steps', '1', 'm', 'accepted integration steps of the labelled run ' &
                // '(Lyapunov periods not counted)'), &
      dataset_t('/sweep/seconds', 's', 'm', 'CPU time of the point (labelled run and ' &
                // 'certificate)'), &
      dataset_t('/sweep/x', '=the variable''s', 'm', 'x axis value of the point'), &
      dataset_t('/sweep/y', '=the variable''s', 'm', 'y axis value of the point'), &
      dataset_t('/sweep/certificate', '1', 'm', 'certificate: 0 none, 1 certified, 2 ' &
                // 'disputed'), &
      dataset_t('/sweep/certificate_text', '1', 'm', 'certificate: certified, disputed or ' &
                // 'none'), &
      dataset_t('/sweep/certificate_reason', '1', 'm', 'the certificate and its reason'), &
      dataset_t('/sweep/lyapunov_periods', '1', 'm', 'forcing periods averaged for the ' &
                // 'Lyapunov exponent'), &
      dataset_t('/sweep/lyapunov_converged', '1', 'm', 'exponent converged: 1 sigma met its ' &
                // 'target, 0 stopped at the most periods'), &
      dataset_t('/sweep/lyapunov_dropped', '1', 'm', 'periods of the exponent''s pair not ' &
                // 'counted: their step sequences differed from every side tried'), &
      dataset_t('/sweep/lyapunov_rerun', '1', 'm', 'periods of the exponent''s pair run ' &
                // 'again from the other side'), &
      dataset_t('/sweep/lyapunov_starts', '1', 'm', 'independent starts combined in the ' &
                // 'exponent (0: none)'), &
      dataset_t('/sweep/lyapunov_spread', 's-1', 'm', 'standard error of the exponent from ' &
                // 'the spread of its starts (0: one start)'), &
      dataset_t('/sweep/period_max_tested', '1', 'm', 'periods 1..this were tried for a ' &
                // 'period'), &
      dataset_t('/sweep/closest_period', '1', 'm', 'best-repeating candidate period in ' &
                // 'forcing periods'), &
      dataset_t('/sweep/transient_periods', '1', 'm', 'forcing periods before the final ' &
                // 'record, in all'), &
      dataset_t('/sweep/settle_windows', '1', 'm', 'windows of the record compared by the ' &
                // 'settling test'), &
      dataset_t('/sweep/settled', '1', 'm', 'settled: 1 the windows agree (or no test), 0 ' &
                // 'not settled'), &
      dataset_t('/sweep/accuracy_label', '1', 'm', 'label code of the accuracy check (-3: ' &
                // 'the check failed)'), &
      dataset_t('/sweep/perturbed_label', '1', 'm', 'label code of the perturbed start (-3: ' &
                // 'the check failed)'), &
      dataset_t('/sweep/n_attractors', '1', 'm', 'distinct attractors reached by the starts ' &
                // 'of the point'), &
      dataset_t('/sweep/f1_open_hz', 'Hz', 'm', 'first natural frequency of the point''s ' &
                // 'model, stops open'), &
      dataset_t('/sweep/period_tolerance', '1', 'm', 'period tolerance used' // rel), &
      dataset_t('/sweep/repeat_distance', '1', 'm', 'repeat distance of the closest period' &
                // rel), &
      dataset_t('/sweep/window_difference', '1', 'm', 'largest difference of the settling ' &
                // 'windows' // rel), &
      dataset_t('/sweep/strain_range', '1', 'm', 'range of the root strain over the final ' &
                // 'record'), &
      dataset_t('/sweep/strain_rate_range', 's-1', 'm', 'range of the root strain rate over ' &
                // 'the final record'), &
      dataset_t('/sweep/seconds_label', 's', 'm', 'CPU time of the labelled run'), &
      dataset_t('/sweep/seconds_certify', 's', 'm', 'CPU time of the certificate''s checks'), &
      dataset_t('/sweep/accuracy_lyapunov', 's-1', 'm', 'Lyapunov exponent of the accuracy ' &
                // 'check'), &
      dataset_t('/sweep/accuracy_lyapunov_error', 's-1', 'm', 'standard error of the ' &
                // 'Lyapunov exponent of the accuracy check'), &
      dataset_t('/sweep/accuracy_distance', '1', 'm', 'distance of the accuracy check''s ' &
                // 'orbit to the run''s' // rel), &
      dataset_t('/sweep/perturbed_lyapunov', 's-1', 'm', 'Lyapunov exponent of the perturbed ' &
                // 'start'), &
      dataset_t('/sweep/perturbed_lyapunov_error', 's-1', 'm', 'standard error of the ' &
                // 'Lyapunov exponent of the perturbed start'), &
      dataset_t('/sweep/perturbed_distance', '1', 'm', 'distance of the perturbed start''s ' &
                // 'orbit to the run''s' // rel), &
      dataset_t('/sweep/method', '1', 'm', 'integration method of the labelled run'), &
      dataset_t('/sweep/accuracy_method', '1', 'm', 'what the accuracy check ran ('''' when ' &
                // 'none)'), &
      dataset_t('/sweep/message', '1', 'm', 'failure message ('''' when done)'), &
      dataset_t('/sweep/impacts/count', '1', 'point=m stop=n_stops', 'contact onsets of each ' &
                // 'stop in the record'), &
      dataset_t('/sweep/impacts/peak_force', 'N', 'point=m stop=n_stops', 'largest force of ' &
                // 'each stop in the record'), &
      dataset_t('/sweep/impacts/rms_force', 'N', 'point=m stop=n_stops', 'root mean square ' &
                // 'force of each stop over the record'), &
      dataset_t('/sweep/impacts/contact_fraction', '1', 'point=m stop=n_stops', 'fraction of ' &
                // 'the record each stop is in contact'), &
      dataset_t('/sweep/impacts/impulse_per_period', 'N s', 'point=m stop=n_stops', 'impulse ' &
                // 'of each stop per forcing period'), &
      dataset_t('/sweep/impacts/work_rate', 'W', 'point=m stop=n_stops', 'mean rate of ' &
                // 'contact work of each stop'), &
      dataset_t('/sweep/wear/normal_work_rate', 'W', 'point=m stop=n_stops', 'normal work ' &
                // 'rate of each support, (1/T) integral of F_N |v_slip| dt, slip only'), &
      dataset_t('/sweep/wear/sliding_distance', 'm', 'point=m stop=n_stops', 'distance each ' &
                // 'support slid over the record'), &
      dataset_t('/sweep/wear/friction_work_rate', 'W', 'point=m stop=n_stops', 'mean ' &
                // 'friction power of each support'), &
      dataset_t('/sweep/wear/wear_volume_rate', 'm3 s-1', 'point=m stop=n_stops', 'Archard ' &
                // 'wear volume rate of each support'), &
      dataset_t('/sweep/poincare/strain', '1', 'point=m period=record_periods', 'root strain ' &
                // 'at the Poincare section, every recorded period of the final record'), &
      dataset_t('/sweep/poincare/strain_rate', 's-1', 'point=m period=record_periods', 'root ' &
                // 'strain rate at the Poincare section, every recorded period of the final ' &
                // 'record'), &
      dataset_t('/sweep/lyapunov_running', 's-1', 'point=m period=lyapunov_periods', 'running ' &
                // 'estimate of the largest Lyapunov exponent after each period (NaN past the ' &
                // 'point''s own)'), &
      dataset_t('/sweep/starts/kind', '1', 'n_starts', "kind of each start: 'deck', 'rest', " &
                // "'up', 'down' or 'random'"), &
      dataset_t('/sweep/starts/label', '1', 'point=m start=n_starts', 'label code of every ' &
                // 'start (' // label_codes // ')'), &
      dataset_t('/sweep/starts/attractor', '1', 'point=m start=n_starts', 'attractor number ' &
                // 'each start reached (0: failed)'), &
      dataset_t('/sweep/starts/lyapunov', 's-1', 'point=m start=n_starts', 'largest Lyapunov ' &
                // 'exponent of every start'), &
      dataset_t('/sweep/attractors/label', '1', 'point=m attractor=n_starts', 'label code of ' &
                // 'each distinct attractor (0 past n_attractors)'), &
      dataset_t('/sweep/attractors/fraction', '1', 'point=m attractor=n_starts', 'fraction of ' &
                // 'the starts that reached each attractor (NaN past n_attractors)'), &
      dataset_t('/sweep/attractors/lyapunov', 's-1', 'point=m attractor=n_starts', 'largest ' &
                // 'Lyapunov exponent of each attractor''s first start (NaN past ' &
                // 'n_attractors)'), &
      dataset_t('/sweep/starts/transient_periods', '1', 'point=m start=n_starts', 'periods ' &
                // 'each start ran before its final record (transient and settling ' &
                // 'extensions; 0 past the end)'), &
      dataset_t('/sweep/attractors/mean_transient_periods', '1', 'point=m attractor=n_starts', &
                'mean over the starts reaching each attractor of their transient periods (NaN ' &
                // 'past n_attractors)'), &
      dataset_t('/sweep/title', '1', '', '&job title'), &
      dataset_t('/sweep/grid_frequency_hz', 'Hz', 'n_f', 'forcing frequency axis of the sweep ' &
                // 'grid (or the one &forcing value)'), &
      dataset_t('/sweep/grid_amplitude_pp', 'm', 'n_a', 'base displacement amplitude axis, ' &
                // 'peak to peak (or the one &forcing value)'), &
      dataset_t('/sweep/x_variable', '1', '', 'deck variable of the x axis'), &
      dataset_t('/sweep/y_variable', '1', '', 'deck variable of the y axis'), &
      dataset_t('/sweep/grid_x', '=the variable''s', 'n_x', 'x axis values ({the deck ' &
                // 'variable})'), &
      dataset_t('/sweep/grid_y', '=the variable''s', 'n_y', 'y axis values ({the deck ' &
                // 'variable})'), &
      dataset_t('/sweep/shard_index', '1', '', 'shard I of this file (1 for a whole or merged ' &
                // 'sweep)'), &
      dataset_t('/sweep/shard_count', '1', '', 'number N of shards'), &
      dataset_t('/sweep/n_points_total', '1', '', 'points of the whole sweep, n_x x n_y'), &
      dataset_t('/run/cpu_seconds', 's', '', 'CPU time of the process up to the writing of ' &
                // 'the results, all threads'), &
      dataset_t('/run/wall_seconds', 's', '', 'wall time of the job up to the writing of the ' &
                // 'results'), &
      dataset_t('/run/threads', '1', '', 'OpenMP threads of the run')]


contains

   !> The entries of section `name` (none for an unknown name).
   function section_datasets(name) result(list)
      character(len=*), intent(in) :: name             !! a word of section_names
      type(dataset_t), allocatable :: list(:)
      select case (name)
      case ('file');  list = file_sets
      case ('parameters');  list = parameter_sets
      case ('structure');  list = structure_sets
      case ('model');  list = model_sets
      case ('modes');  list = modes_sets
      case ('calibrate');  list = calibrate_sets
      case ('history');  list = history_sets
      case ('state');  list = state_sets
      case ('transient');  list = transient_sets
      case ('tubes');  list = [tube_sets, psd_sets]
      case ('sweep');  list = [sweep_sets, sweep_draw_sets]
      case ('work_precision');  list = work_precision_sets
      case ('stability');  list = stability_sets
      case ('model_size');  list = model_size_sets
      case ('continuation');  list = continuation_sets
      case default;  allocate(list(0))
      end select
   end function section_datasets

   !> The description of dataset `path` written by `analysis`; `found` is false when the
   !> catalogue has none.
   subroutine describe(analysis, path, entry, found)
      character(len=*), intent(in) :: analysis         !! analysis word, e.g. 'transient'
      character(len=*), intent(in) :: path             !! absolute dataset path
      type(dataset_t), intent(out) :: entry            !! its description
      logical, intent(out) :: found                    !! whether the catalogue has it
      type(dataset_t), allocatable :: list(:)
      integer :: s, k
      found = .false.
      do s = 1, size(section_names)
         if (.not. has_word(section_analyses(s), analysis)) cycle
         list = section_datasets(trim(section_names(s)))
         do k = 1, size(list)
            if (matches(trim(list(k)%path), path)) then
               entry = list(k)
               found = .true.
               return
            end if
         end do
      end do
   end subroutine describe

   !> Whether `path` matches the pattern: the same components, `<...>` matching any name
   !> and `prefix<...>` any name starting with prefix.
   pure logical function matches(pattern, path)
      character(len=*), intent(in) :: pattern, path
      integer :: i, j, a, b
      matches = .false.
      i = 1;  j = 1
      do
         a = scan(pattern(i:), '/');  b = scan(path(j:), '/')
         if ((a == 0) .neqv. (b == 0)) return
         if (a == 0) then
            matches = component_matches(pattern(i:), path(j:))
            return
         end if
         if (.not. component_matches(pattern(i:i + a - 2), path(j:j + b - 2))) return
         i = i + a;  j = j + b
      end do
   end function matches

   pure logical function component_matches(pattern, name)
      character(len=*), intent(in) :: pattern, name
      integer :: k
      k = index(pattern, '<')
      if (k == 0) then
         component_matches = pattern == name
      else
         component_matches = len(name) >= k
         if (component_matches) component_matches = name(1:k - 1) == pattern(1:k - 1)
      end if
   end function component_matches

   !> Whether the blank-separated list `words` holds `word`.
   pure logical function has_word(words, word)
      character(len=*), intent(in) :: words, word
      has_word = index(' ' // trim(words) // ' ', ' ' // trim(word) // ' ') > 0
   end function has_word

   !> Number of axes of an entry.
   pure integer function dims_rank(entry)
      type(dataset_t), intent(in) :: entry
      integer :: k
      dims_rank = 0
      do k = 1, len_trim(entry%dims)
         if (entry%dims(k:k) == ' ') cycle
         if (k == 1) then
            dims_rank = 1
         else if (entry%dims(k - 1:k - 1) == ' ') then
            dims_rank = dims_rank + 1
         end if
      end do
   end function dims_rank

   !> The `dimensions` attribute of an entry (axis names, C order), '' below rank 2.
   pure function dims_attribute(entry) result(t)
      type(dataset_t), intent(in) :: entry
      character(len=:), allocatable :: t
      integer :: n
      t = ''
      if (dims_rank(entry) < 2) return
      do n = 1, dims_rank(entry)
         if (n > 1) t = t // ' '
         t = t // axis(entry%dims, n, name=.true.)
      end do
   end function dims_attribute

   !> The shape in words as the docs show it: 'scalar', '(n_modes)', '(n_hist, n_stops)'.
   pure function shape_words(entry) result(t)
      type(dataset_t), intent(in) :: entry
      character(len=:), allocatable :: t
      integer :: n
      t = 'scalar'
      if (dims_rank(entry) == 0) return
      t = '('
      do n = 1, dims_rank(entry)
         if (n > 1) t = t // ', '
         t = t // axis(entry%dims, n, name=.false.)
      end do
      t = t // ')'
   end function shape_words

   !> The name (`name`) or the size of axis n of dims ('name=size' words, or 'size').
   pure function axis(dims, n, name) result(t)
      character(len=*), intent(in) :: dims
      integer, intent(in) :: n
      logical, intent(in) :: name
      character(len=:), allocatable :: t
      integer :: k, e
      t = adjustl(dims)
      do k = 2, n
         t = adjustl(t(index(t, ' '):))
      end do
      t = t(1:index(t // ' ', ' ') - 1)
      e = index(t, '=')
      if (name) then
         t = t(1:e - 1)
      else
         t = t(e + 1:)
      end if
   end function axis

   !> The long name with its `{...}` part replaced by `fill` (the docs' text when absent).
   pure function long_name_text(entry, fill) result(t)
      type(dataset_t), intent(in) :: entry
      character(len=*), intent(in), optional :: fill
      character(len=:), allocatable :: t
      integer :: a, b
      t = trim(entry%long_name)
      a = index(t, '{');  b = index(t, '}')
      if (a == 0 .or. b < a) return
      if (present(fill)) then
         t = t(1:a - 1) // fill // t(b + 1:)
      else
         t = t(1:a - 1) // t(a + 1:b - 1) // t(b + 1:)
      end if
   end function long_name_text

   !> The catalogue as text: `format` 'markdown' (a heading and a table per section, as in
   !> docs/outputs.md) or 'tsv' (section, analyses, path, units, dims, long name, one line per
   !> dataset); only the sections written by `analysis` when given ('' or absent: all).
   function catalogue_text(format, analysis) result(text)
      character(len=*), intent(in) :: format           !! 'markdown' or 'tsv'
      character(len=*), intent(in), optional :: analysis   !! an analysis word, or a section
      character(len=:), allocatable :: text
      character(len=*), parameter :: tab = achar(9), nl = new_line('a')
      type(dataset_t), allocatable :: list(:)
      character(len=:), allocatable :: u
      integer :: s, k
      text = ''
      do s = 1, size(section_names)
         if (present(analysis)) then
            if (len_trim(analysis) > 0 .and. .not. has_word(section_analyses(s), analysis) &
                .and. analysis /= section_names(s)) cycle
         end if
         list = section_datasets(trim(section_names(s)))
         if (format == 'markdown') text = text // '### ' // trim(section_names(s)) &
            // ' (written by: ' // trim(section_analyses(s)) // ')' // nl // nl &
            // '| dataset | shape (C order, as h5py shows it) | units | content |' // nl &
            // '|---|---|---|---|' // nl
         do k = 1, size(list)
            associate (e => list(k))
               if (format == 'markdown') then
                  u = '`' // trim(e%units) // '`'
                  if (e%units(1:1) == '=') u = trim(e%units(2:))
                  text = text // '| `' // trim(e%path) // '` | ' // shape_words(e) // ' | ' &
                     // u // ' | ' // escaped(long_name_text(e)) // ' |' // nl
               else
                  text = text // trim(section_names(s)) // tab // trim(section_analyses(s)) &
                     // tab // trim(e%path) // tab // trim(e%units) // tab // trim(e%dims) &
                     // tab // trim(e%long_name) // nl
               end if
            end associate
         end do
         if (format == 'markdown') text = text // nl
      end do
   end function catalogue_text

   !> Text for a markdown table cell: '|' escaped.
   pure function escaped(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      integer :: k
      t = ''
      do k = 1, len(s)
         if (s(k:k) == '|') t = t // '\'
         t = t // s(k:k)
      end do
   end function escaped
end module gapbeam_output_catalogue
