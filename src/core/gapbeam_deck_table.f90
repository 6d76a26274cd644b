!> The deck table: every group and variable of a deck, declared once.
!>
!> `walk_deck(v, deck)` calls the visitor `v` (gapbeam_deck_visitor) for every variable of every
!> group, in the order of docs/decks.md, each call naming the variable, binding it to its
!> component of `deck` and describing it: unit, allowed range or words, a one-line meaning,
!> whether it is a design variable (settable by name by sweeps, maps and continuation), and a
!> note for the rules that depend on other variables. The defaults are those of the types
!> (core/gapbeam_description, gapbeam_settings, gapbeam_continuation_types): a visitor over a
!> default deck_t reads them. The reader (io/gapbeam_input) applies and checks a deck's values
!> through it, `gapbeam --help-deck` and the tables of docs/decks.md print it, and
!> gapbeam_deck_variable gets and sets design variables through it.
!>
!> A new deck variable: its component (with its default) in its type, one call here, and any
!> rule that ties it to other variables in the reader's cross-variable checks; then
!> `python3 scripts/test_docs.py --write-decks GAPBEAM` renews the docs table (test_input fails
!> until it does).
!>
!> The walk of the groups of the structure and the forcing is here, that of the settings
!> groups in the submodule gapbeam_deck_table_settings.
module gapbeam_deck_table
   use gapbeam_kinds, only: dp, pi
   use gapbeam_deck_visitor, only: deck_visitor_t
   use gapbeam_description, only: beam_t, root_t, spring_t, point_mass_t, stop_t, damping_t, &
      forcing_t, point_force_t, stop_side_words, stop_law_words, damping_words, &
      rotary_inertia_words, stop_shape_words, end_condition_words, tip_condition_words, &
      flow_t, turbulence_t, fluid_elastic_words, spectrum_words, flow_plane_words, &
      psd_method_words, &
      support_geometry_words, beam_theory_words
   use gapbeam_settings, only: job_t, calibrate_t, analysis_words, calibration_words
   use gapbeam_deck, only: deck_t
   implicit none
   private
   public :: walk_deck, node_lo, node_hi, mesh, dof_words, max_axis_values, max_periods, &
      max_frequency_hz, min_amplitude_pp, max_initial_entries

   !> Words of a dof; the position of a word is its code (dof_w = 1, ... dof_theta_v = 4).
   character(len=*), parameter :: dof_words = "'w', 'theta', 'v', 'theta_v'"
   integer, parameter :: max_list_entries = 64      !! most entries of &springs, &masses, ...
   integer, parameter :: max_initial_entries = 40004  !! most &initial entries (every dof of
                                                      !! the largest mesh, two planes)
   integer, parameter :: max_axis_values = 4096      !! most values of a sweep axis list
   integer, parameter :: max_periods = 100000000     !! most periods of one count
   !> Highest forcing frequency: far above any beam model's validity, and low enough that
   !> Omega = 2 pi f, the base velocity and acceleration and the steps' 1/dt^2 stay finite
   real(dp), parameter :: max_frequency_hz = 1.0e9_dp
   !> Smallest non-zero base amplitude: below it the response's squares (energies, norms,
   !> the Lyapunov separation) underflow and the label would no longer be the amplitude's
   real(dp), parameter :: min_amplitude_pp = 1.0e-30_dp
   real(dp), parameter :: big = sqrt(huge(1.0_dp))   !! scale rule: squares must not overflow
   integer, parameter :: max_modal_ratios = 40004     !! most modal ratios (every mode)
   integer, parameter :: no_nodes(0) = [integer ::]     !! an empty node list
   real(dp), parameter :: max_modal_ratio = 100.0_dp  !! largest modal damping ratio

   interface
      !> The settings groups (&solver ... &continuation), in gapbeam_deck_table_settings.
      module subroutine walk_settings(v, deck)
         class(deck_visitor_t), intent(inout) :: v
         type(deck_t), intent(inout) :: deck
      end subroutine walk_settings
   end interface

contains

   !> Visit every variable of every group of `deck`.
   subroutine walk_deck(v, deck)
      class(deck_visitor_t), intent(inout) :: v      !! the job done on each variable
      type(deck_t), intent(inout) :: deck            !! deck (a default one to describe)
      call walk_job(v, deck%job)
      call walk_beam(v, deck%structure%beam)
      call walk_end(v, 'root', 'support at node 1 (its translation is always fixed)', &
                    deck%structure%root, end_condition_words)
      call walk_end(v, 'tip', 'support at the last node (free unless this group says ' &
                    // 'otherwise)', deck%structure%tip, tip_condition_words)
      call walk_springs(v, deck%structure%springs, deck%structure%beam%n_elem)
      call walk_masses(v, deck%structure%masses, deck%structure%beam%n_elem)
      call v%begin_group('modes', 'modal analysis printout')
      call v%int('n_print', deck%n_print_modes, lo=0, meaning='modes printed on standard ' &
         // 'output; 0 prints all (the output files always hold all modes)', &
         why='0 prints all modes')
      call v%end_group()
      call walk_calibrate(v, deck%calibrate)
      call walk_stops(v, deck%stops, deck%structure%beam%n_elem)
      call walk_damping(v, deck%damping)
      call walk_forcing(v, deck%forcing)
      call walk_point_forces(v, deck%forcing%forces, deck%structure%beam%n_elem)
      call walk_flow(v, deck%flow)
      call walk_turbulence(v, deck%turbulence)
      call walk_settings(v, deck)
   end subroutine walk_deck

   subroutine walk_job(v, j)
      class(deck_visitor_t), intent(inout) :: v
      type(job_t), intent(inout) :: j
      call v%begin_group('job', 'what to run and where the results go (required)')
      call v%word('analysis', j%analysis, analysis_words, meaning='analysis to run')
      call v%text('title', j%title, meaning='title of the text tables, the files and the plots')
      call v%text('output', j%output, meaning="output path prefix; '' means results/<deck " &
         // 'file name without extension>; missing directories are created')
      call v%end_group()
   end subroutine walk_job

   subroutine walk_beam(v, b)
      class(deck_visitor_t), intent(inout) :: v
      type(beam_t), intent(inout) :: b
      logical :: rect, general, timo
      character(len=:), allocatable :: why_g, why_k
      rect = b%width /= 0.0_dp .or. b%thickness /= 0.0_dp
      general = .not. rect .and. (b%area /= 0.0_dp .or. b%second_moment /= 0.0_dp .or. &
                                  b%fibre_distance /= 0.0_dp)
      timo = b%theory == 'timoshenko'
      why_g = '';  why_k = ''
      if (timo) why_g = "with theory = 'timoshenko'"
      if (timo .and. .not. rect) why_k = "with theory = 'timoshenko' and a general section"
      call v%begin_group('beam', 'uniform beam, Euler-Bernoulli or Timoshenko (required)')
      call v%real('length', b%length, 'm', lo=0.0_dp, lo_open=.true., required=.true., &
         design=.true., meaning='beam length L; nodes 1 (root, x = 0) to n_elem+1 (tip)')
      call v%int('n_elem', b%n_elem, lo=1, hi=10000, meaning='number of equal elements')
      call v%real('youngs_modulus', b%youngs_modulus, 'Pa', lo=0.0_dp, lo_open=.true., &
         required=.true., design=.true., meaning="Young's modulus E")
      call v%real('density', b%density, 'kg/m^3', lo=0.0_dp, lo_open=.true., required=.true., &
         design=.true., meaning='density rho')
      call v%real('width', b%width, 'm', lo=0.0_dp, positive=rect, design=.true., &
         note='> 0 when the rectangle is used', meaning='rectangular section: width b ' &
         // '(EI = E b h^3/12, rho A = rho b h, strain fibre at h/2)')
      call v%real('thickness', b%thickness, 'm', lo=0.0_dp, positive=rect, design=.true., &
         note='> 0 when the rectangle is used', meaning='rectangular section: thickness h ' &
         // '(in the bending direction)')
      call v%real('area', b%area, 'm^2', lo=0.0_dp, positive=general, design=.true., &
         note='> 0 when the general section is used', meaning='general section (width = ' &
         // 'thickness = 0): area A')
      call v%real('second_moment', b%second_moment, 'm^4', lo=0.0_dp, positive=general, &
         design=.true., note='> 0 when the general section is used', &
         meaning='general section: second moment of area I')
      call v%real('fibre_distance', b%fibre_distance, 'm', lo=0.0_dp, positive=general, &
         design=.true., note='> 0 when the general section is used', &
         meaning='general section: distance c of the strain fibre from the neutral axis')
      call v%word('mass_matrix', b%mass_matrix, "'lumped', 'consistent'", &
         meaning='element mass matrix')
      call v%word('rotary_inertia', b%rotary_inertia, rotary_inertia_words, meaning='rotary ' &
         // "inertia of the lumped mass per element end: 'half_element' (rho A le) le^2/24, " &
         // "'hrz' (rho A le) le^2/78, 'none' 0 (ignored for consistent mass)")
      call v%int('planes', b%planes, lo=1, hi=2, why='1: (w, theta) per node; 2: also ' &
         // '(v, theta_v)', meaning='planes of motion: 1, (w, theta) per node; 2, also ' &
         // '(v, theta_v) in the second transverse plane (tubes, docs/tubes.md)')
      call v%real('added_mass', b%added_mass, 'kg/m', lo=0.0_dp, design=.true., &
         meaning='mass per length added to rho A in the mass matrix only (fluid, contents)')
      call v%word('theory', b%theory, beam_theory_words, meaning="'euler_bernoulli'; " &
         // "'timoshenko': shear deformation and the section's rotary inertia rho I, the " &
         // 'rotation dofs then being the rotations of the cross-section (docs/methods.md)')
      call v%real('shear_modulus', b%shear_modulus, 'Pa', lo=0.0_dp, hi=big, positive=timo, &
         why=why_g, &
         design=.true., note="> 0 with theory = 'timoshenko' (ignored otherwise)", &
         meaning='shear modulus G (Timoshenko)')
      call v%real('shear_coefficient', b%shear_coefficient, '1', lo=0.0_dp, hi=1.0_dp, &
         positive=timo .and. .not. rect, design=.true., why=why_k, note="0: 5/6 for a " &
         // "rectangular " &
         // "section; > 0 with theory = 'timoshenko' and a general section", &
         meaning='shear coefficient k of k G A (Timoshenko): about 0.5 for a thin-walled ' &
         // 'tube, 0.9 for a solid circle')
      call v%end_group()
   end subroutine walk_beam

   !> &root and &tip (the same type).
   subroutine walk_end(v, name, meaning, r, words)
      class(deck_visitor_t), intent(inout) :: v
      character(len=*), intent(in) :: name, meaning, words
      type(root_t), intent(inout) :: r
      character(len=:), allocatable :: free
      free = ''
      if (name == 'tip') free = "; 'free': nothing fixed"
      call v%begin_group(name, meaning)
      call v%word('condition', r%condition, words, meaning="'clamped': translation and " &
         // "rotation fixed; 'spring': translation fixed, rotation on k_theta; 'pinned': " &
         // 'translation fixed' // free)
      call v%real('k_theta', r%k_theta, 'N m/rad', lo=0.0_dp, hi=big, &
         positive=r%condition == 'spring', design=name == 'root', &
         note="> 0 when condition = 'spring'", meaning='rotational spring of the ' // name)
      call v%end_group()
   end subroutine walk_end

   subroutine walk_springs(v, list, n_elem)
      class(deck_visitor_t), intent(inout) :: v
      type(spring_t), allocatable, intent(inout) :: list(:)
      integer, intent(in) :: n_elem          !! elements of the mesh (node range)
      type(spring_t), allocatable :: tmp(:)
      type(spring_t) :: proto
      integer :: n, i, m
      call v%begin_group('springs', 'linear springs from node dofs to the base (list)', .true.)
      m = 0
      if (allocated(list)) m = size(list)
      n = v%entries(m, max_list_entries)
      if (n < 0) then
         call v%at(1)
         call spring(v, proto, n_elem)
      else
         if (.not. allocated(list) .or. n /= m) then
            allocate(tmp(n))
            if (allocated(list)) tmp(1:min(n, m)) = list(1:min(n, m))
            call move_alloc(tmp, list)
         end if
         do i = 1, n
            call v%at(i)
            call spring(v, list(i), n_elem)
         end do
      end if
      call v%end_group()
   contains
      subroutine spring(v, s, n_elem)
         class(deck_visitor_t), intent(inout) :: v
         type(spring_t), intent(inout) :: s
         integer, intent(in) :: n_elem
         call v%int('node', s%node, lo=node_lo(v), hi=node_hi(v, n_elem), why=mesh(n_elem), &
            required=.true., note='1..n_elem+1, a free dof', &
            meaning='node of the spring')
         call v%code('dof', s%dof, dof_words, note="'v', 'theta_v' with planes = 2", &
            meaning='degree of freedom')
         call v%real('stiffness', s%stiffness, 'N/m', lo=0.0_dp, lo_open=.true., hi=big, &
            design=.true., meaning='spring stiffness (N m/rad on a rotation)')
      end subroutine spring
   end subroutine walk_springs

   subroutine walk_masses(v, list, n_elem)
      class(deck_visitor_t), intent(inout) :: v
      type(point_mass_t), allocatable, intent(inout) :: list(:)
      integer, intent(in) :: n_elem          !! elements of the mesh (node range)
      type(point_mass_t), allocatable :: tmp(:)
      type(point_mass_t) :: proto
      integer :: n, i, m
      call v%begin_group('masses', 'point masses and rotary inertias (list)', .true.)
      m = 0
      if (allocated(list)) m = size(list)
      n = v%entries(m, max_list_entries)
      if (n < 0) then
         call v%at(1)
         call mass(v, proto, n_elem)
      else
         if (.not. allocated(list) .or. n /= m) then
            allocate(tmp(n))
            if (allocated(list)) tmp(1:min(n, m)) = list(1:min(n, m))
            call move_alloc(tmp, list)
         end if
         do i = 1, n
            call v%at(i)
            call mass(v, list(i), n_elem)
         end do
      end if
      call v%end_group()
   contains
      subroutine mass(v, p, n_elem)
         class(deck_visitor_t), intent(inout) :: v
         type(point_mass_t), intent(inout) :: p
         integer, intent(in) :: n_elem
         call v%int('node', p%node, lo=node_lo(v), hi=node_hi(v, n_elem), why=mesh(n_elem), &
            required=.true., note='1..n_elem+1', &
            meaning='node of the mass')
         call v%real('mass', p%mass, 'kg', lo=0.0_dp, hi=big, design=.true., &
            meaning='translational ' &
            // 'mass (on w, and v with two planes)')
         call v%real('inertia', p%inertia, 'kg m^2', lo=0.0_dp, hi=big, design=.true., &
            meaning='rotary inertia (on theta)')
      end subroutine mass
   end subroutine walk_masses

   subroutine walk_calibrate(v, c)
      class(deck_visitor_t), intent(inout) :: v
      type(calibrate_t), intent(inout) :: c
      call v%begin_group('calibrate', 'fit a parameter to a target first frequency')
      call v%word('parameter', c%parameter, calibration_words, note="'root_k_theta' needs " &
         // "&root condition = 'spring'; 'thickness', 'width' a rectangle", &
         meaning='parameter fitted')
      call v%int('index', c%index, lo=1, note='1..number of &springs', &
         meaning="spring fitted when parameter = 'spring'")
      call v%real('target_f1_hz', c%target_f1_hz, 'Hz', lo=0.0_dp, &
         note="> 0 for analysis = 'calibrate'", meaning='target first natural frequency')
      call v%end_group()
   end subroutine walk_calibrate

   subroutine walk_stops(v, list, n_elem)
      class(deck_visitor_t), intent(inout) :: v
      type(stop_t), allocatable, intent(inout) :: list(:)
      integer, intent(in) :: n_elem          !! elements of the mesh (node range)
      type(stop_t), allocatable :: tmp(:)
      type(stop_t) :: proto
      integer :: n, i, m
      call v%begin_group('stops', 'gap supports (list)', .true.)
      m = 0
      if (allocated(list)) m = size(list)
      n = v%entries(m, max_list_entries)
      if (n < 0) then
         call v%at(1)
         call stop_entry(v, proto, n_elem)
      else
         if (.not. allocated(list) .or. n /= m) then
            allocate(tmp(n))
            if (allocated(list)) tmp(1:min(n, m)) = list(1:min(n, m))
            call move_alloc(tmp, list)
         end if
         do i = 1, n
            call v%at(i)
            call stop_entry(v, list(i), n_elem)
         end do
      end if
      call v%end_group()
   contains
      subroutine stop_entry(v, s, n_elem)
         class(deck_visitor_t), intent(inout) :: v
         type(stop_t), intent(inout) :: s
         integer, intent(in) :: n_elem
         call v%int('node', s%node, lo=node_lo(v), hi=node_hi(v, n_elem), why=mesh(n_elem), &
            required=.true., note='1..n_elem+1, a free dof', &
            meaning='node of the stop')
         call v%code('dof', s%dof, dof_words, note="'v', 'theta_v' with planes = 2", &
            meaning='degree of freedom the stop acts on')
         call v%word('side', s%side, stop_side_words, meaning='which way the stop is met ' &
            // "(u > gap, u < -gap, or both)")
         call v%word('law', s%law, stop_law_words, meaning='contact law: f = max(0, k d + ' &
            // "c d') or f = k d^p, d = s u - gap the penetration")
         call v%real('gap', s%gap, 'm', lo=0.0_dp, hi=big, design=.true., &
            meaning='clearance g (rad on a rotation dof)')
         call v%real('stiffness', s%stiffness, 'N/m', lo=0.0_dp, hi=big, design=.true., &
            positive=.not. (s%rule_factor > 0.0_dp), why='or rule_factor' // ix(v%entry) &
            // ' > 0: the stiffness from the rule', note='> 0 unless rule_factor > 0', &
            meaning='contact stiffness k (N m/rad on a rotation; N/m^p for hertz)')
         call v%real('damping', s%damping, 'N s/m', lo=0.0_dp, hi=big, design=.true., &
            note="0 with law = 'hertz'", meaning='contact damper c, active only in contact')
         call v%real('exponent', s%exponent, '1', lo=1.0_dp, hi=10.0_dp, design=.true., &
            meaning="Hertz exponent p (law = 'hertz')")
         call v%real('rule_factor', s%rule_factor, '1', lo=0.0_dp, hi=big, design=.true., &
            meaning='> 0: stiffness = rule_factor x the spring that raises f1 to the rule ' &
            // 'target; 0: stiffness as given')
         call v%real('rule_f1_ratio', s%rule_f1_ratio, '1', lo=1.0_dp + 1.0e-9_dp, &
            hi=1.0e6_dp, zero=.true., design=.true., meaning='rule target as a multiple of ' &
            // 'f1 with the stops open')
         call v%real('rule_f1_hz', s%rule_f1_hz, 'Hz', lo=0.0_dp, hi=max_frequency_hz, &
            design=.true., &
            note='> 0 with rule_factor > 0 and rule_f1_ratio = 0', &
            meaning='rule target as a frequency')
         call v%word('shape', s%shape, stop_shape_words, note="'circular' needs planes = 2, " &
            // 'gap > 0, no side, dof or rule', meaning="'flat': one dof; 'circular': a round " &
            // 'hole around the node, met at the radial gap')
         call v%real('offset_w', s%offset_w, 'm', lo=-1.0e3_dp, hi=1.0e3_dp, &
            note='circular only', meaning='w of the hole centre')
         call v%real('offset_v', s%offset_v, 'm', lo=-1.0e3_dp, hi=1.0e3_dp, &
            note='circular only', meaning='v of the hole centre')
         call v%real('friction', s%friction, '1', lo=0.0_dp, hi=10.0_dp, design=.true., &
            note='> 0 needs planes = 2 and a translation dof', &
            meaning='Coulomb coefficient mu of the support (stick and slip)')
         call v%real('tangential_stiffness', s%tangential_stiffness, 'N/m', lo=0.0_dp, hi=big, &
            meaning='stick stiffness k_t of the friction (0: the stiffness)')
         call v%real('wear_coefficient', s%wear_coefficient, '1/Pa', lo=0.0_dp, hi=big, &
            design=.true., meaning='Archard coefficient: wear volume rate / normal work rate')
         call v%word('support', s%support, support_geometry_words, meaning='geometry of the ' &
            // "support for the wear depth (&wear): 'flat_bar' (a flat land along the tube), " &
            // "'drilled_hole' (a round hole through a plate)")
         call v%real('land_width', s%land_width, 'm', lo=0.0_dp, hi=1.0e3_dp, design=.true., &
            positive=s%support == 'flat_bar', note="> 0 with support = 'flat_bar'", &
            meaning='flat bar: width of its land along the tube')
         call v%real('plate_thickness', s%plate_thickness, 'm', lo=0.0_dp, hi=1.0e3_dp, &
            design=.true., positive=s%support == 'drilled_hole', &
            note="> 0 with support = 'drilled_hole'", meaning='drilled hole: plate thickness')
         call v%real('hole_diameter', s%hole_diameter, 'm', lo=0.0_dp, hi=1.0e3_dp, &
            design=.true., positive=s%support == 'drilled_hole', &
            note="> the tube diameter with support = 'drilled_hole'", &
            meaning='drilled hole: hole diameter')
      end subroutine stop_entry
      function ix(i) result(t)
         integer, intent(in) :: i
         character(len=:), allocatable :: t
         character(len=12) :: buf
         write(buf, '(i0)') i
         t = '(' // trim(buf) // ')'
      end function ix
   end subroutine walk_stops

   subroutine walk_damping(v, d)
      class(deck_visitor_t), intent(inout) :: v
      type(damping_t), intent(inout) :: d
      logical :: ratios
      ratios = d%model == 'ratios'
      call v%begin_group('damping', 'damping of the linear structure (never the stops): ' &
         // 'Rayleigh C = beta M + gamma K, or modal with Rayleigh terms beside it')
      call v%word('model', d%model, damping_words, meaning="'none': C = 0; 'rayleigh': beta, " &
         // "gamma given; 'ratios': beta, gamma from two (frequency, ratio) pairs; 'modal': " &
         // 'M Phi diag(2 zeta_j omega_j) Phi^T M + beta M + gamma K (docs/methods.md)')
      call v%real('mass_coefficient', d%mass_coefficient, '1/s', lo=0.0_dp, hi=big, &
         design=.true., note="model = 'rayleigh' or 'modal'", meaning='beta')
      call v%real('stiffness_coefficient', d%stiffness_coefficient, 's', lo=0.0_dp, hi=big, &
         design=.true., note="model = 'rayleigh' or 'modal'", meaning='gamma')
      call v%real_list('modal_ratios', d%modal_ratios, max_modal_ratios, '1', lo=0.0_dp, &
         hi=max_modal_ratio, design=.true., note="required with model = 'modal', only there", &
         meaning='damping ratios zeta_j of modes 1, 2, ... of each plane, the last one for ' &
         // 'every further mode (one value: every mode alike)')
      call v%real('frequency1_hz', d%frequency1_hz, 'Hz', lo=0.0_dp, hi=max_frequency_hz, &
         positive=ratios, &
         design=.true., note="> 0 with model = 'ratios'", meaning='first frequency f_1')
      call v%real('ratio1', d%ratio1, '1', lo=0.0_dp, hi=big, design=.true., &
         note="model = 'ratios'", &
         meaning='damping ratio at f_1')
      call v%real('frequency2_hz', d%frequency2_hz, 'Hz', lo=0.0_dp, hi=max_frequency_hz, &
         positive=ratios, &
         design=.true., note="> frequency1_hz with model = 'ratios'", &
         meaning='second frequency f_2')
      call v%real('ratio2', d%ratio2, '1', lo=0.0_dp, hi=big, design=.true., &
         note="model = 'ratios'", &
         meaning='damping ratio at f_2')
      call v%end_group()
   end subroutine walk_damping

   subroutine walk_forcing(v, f)
      class(deck_visitor_t), intent(inout) :: v
      type(forcing_t), intent(inout) :: f
      real(dp) :: f_hi, a_hi, omega
      character(len=:), allocatable :: why_f, why_a
      ! the base acceleration (A_pp/2) Omega^2 must not overflow in squares either
      f_hi = max_frequency_hz;  a_hi = big;  why_f = '';  why_a = ''
      omega = 2.0_dp * pi * f%frequency_hz
      if (.not. v%describing .and. omega > 0.0_dp .and. omega <= 2.0_dp * pi * max_frequency_hz) &
         then
         a_hi = min(big, 2.0_dp * big / omega**2)
         if (f%amplitude_pp > a_hi) why_a = 'the base acceleration (A_pp/2) (2 pi f)^2 at most ' &
            // '1.34e154'
      end if
      if (.not. v%describing .and. f%amplitude_pp > 0.0_dp .and. f%amplitude_pp <= big) then
         f_hi = min(max_frequency_hz, sqrt(2.0_dp * big / f%amplitude_pp) / (2.0_dp * pi))
         if (f%frequency_hz > f_hi .and. f_hi < max_frequency_hz) why_f = 'the base ' &
            // 'acceleration (A_pp/2) (2 pi f)^2 at most 1.34e154'
      end if
      call v%begin_group('forcing', 'harmonic base excitation u_b = (A_pp/2) sin(2 pi f t)')
      call v%real('frequency_hz', f%frequency_hz, 'Hz', lo=0.0_dp, hi=f_hi, lo_open=.true., &
         design=.true., why=why_f, meaning='forcing frequency f; T = 1/f is the forcing period')
      call v%real('amplitude_pp', f%amplitude_pp, 'm', lo=min_amplitude_pp, hi=a_hi, &
         zero=.true., design=.true., why=why_a, note='(A_pp/2) (2 pi f)^2 at most 1.34e154', &
         meaning='base displacement amplitude, peak to peak (0: free vibration from &initial)')
      call v%real('direction_deg', f%direction_deg, 'deg', lo=-360.0_dp, hi=360.0_dp, &
         note='not 0 needs planes = 2', meaning='direction psi of the base motion from w ' &
         // 'towards v')
      call v%real('phase_v_deg', f%phase_v_deg, 'deg', lo=-360.0_dp, hi=360.0_dp, &
         note='not 0 needs planes = 2', meaning='phase phi of its v component')
      call v%end_group()
   end subroutine walk_forcing

   subroutine walk_point_forces(v, list, n_elem)
      class(deck_visitor_t), intent(inout) :: v
      type(point_force_t), allocatable, intent(inout) :: list(:)
      integer, intent(in) :: n_elem          !! elements of the mesh (node range)
      type(point_force_t), allocatable :: tmp(:)
      type(point_force_t) :: proto
      integer :: n, i, m
      call v%begin_group('point_forces', 'harmonic point forces F sin(Omega t + phase) at ' &
         // 'the forcing frequency (list)', .true.)
      m = 0
      if (allocated(list)) m = size(list)
      n = v%entries(m, max_list_entries)
      if (n < 0) then
         call v%at(1)
         call force(v, proto, n_elem)
      else
         if (.not. allocated(list) .or. n /= m) then
            allocate(tmp(n))
            if (allocated(list)) tmp(1:min(n, m)) = list(1:min(n, m))
            call move_alloc(tmp, list)
         end if
         do i = 1, n
            call v%at(i)
            call force(v, list(i), n_elem)
         end do
      end if
      call v%end_group()
   contains
      subroutine force(v, p, n_elem)
         class(deck_visitor_t), intent(inout) :: v
         type(point_force_t), intent(inout) :: p
         integer, intent(in) :: n_elem
         call v%int('node', p%node, lo=node_lo(v), hi=node_hi(v, n_elem), why=mesh(n_elem), &
            required=.true., note='1..n_elem+1, a free dof', &
            meaning='node of the force')
         call v%code('dof', p%dof, dof_words, note="'v', 'theta_v' with planes = 2", &
            meaning='dof it acts on (a moment on a rotation)')
         call v%real('amplitude', p%amplitude, 'N', lo=-1.0e12_dp, hi=1.0e12_dp, &
            design=.true., meaning='amplitude F (N m on a rotation)')
         call v%real('phase_deg', p%phase_deg, 'deg', lo=-360.0_dp, hi=360.0_dp, &
            meaning='phase; two forces in w and v 90 deg apart make a whirling force')
      end subroutine force
   end subroutine walk_point_forces

   subroutine walk_flow(v, f)
      class(deck_visitor_t), intent(inout) :: v
      type(flow_t), intent(inout) :: f
      logical :: used
      used = f%velocity > 0.0_dp
      call v%begin_group('flow', 'cross flow over the tube: fluid-elastic forces as a ' &
         // 'damping per mode (Connors), the scale of a reduced turbulence spectrum ' &
         // '(docs/flow.md)')
      call v%real('velocity', f%velocity, 'm/s', lo=0.0_dp, hi=1.0e4_dp, design=.true., &
         meaning='reference (gap) flow velocity U, the one of the Connors constant (0: no flow)')
      call v%real('fluid_density', f%fluid_density, 'kg/m^3', lo=0.0_dp, hi=1.0e5_dp, &
         design=.true., positive=used, note='> 0 with velocity > 0', &
         meaning='fluid density rho')
      call v%real('tube_diameter', f%tube_diameter, 'm', lo=0.0_dp, hi=1.0e3_dp, &
         design=.true., positive=used, note='> 0 with velocity > 0', &
         meaning='tube outer diameter D')
      call v%real('connors_constant', f%connors_constant, '1', lo=0.0_dp, lo_open=.true., &
         hi=100.0_dp, design=.true., meaning="Connors' constant K (about 3 on average, 2.4 " &
         // 'for design)')
      call v%word('fluid_elastic', f%fluid_elastic, fluid_elastic_words, meaning="'connors': " &
         // "a negative damping per mode, zeta = -rho U_e^2/(2 pi K^2 f^2 m); 'none': no " &
         // 'fluid-elastic force')
      call v%word('planes', f%planes, flow_plane_words, note="'v' needs &beam planes = 2", &
         meaning='planes of the fluid-elastic forces')
      call v%real('region_start', f%region_start, 'm', lo=0.0_dp, hi=1.0e4_dp, &
         design=.true., note='region_start < region_end <= length unless both are 0', &
         meaning='the flow region begins at this x')
      call v%real('region_end', f%region_end, 'm', lo=0.0_dp, hi=1.0e4_dp, design=.true., &
         meaning='the flow region ends at this x (both 0: the whole tube)')
      call v%real_list('profile_position', f%profile_position, 1000, 'm', lo=0.0_dp, &
         note='increasing, as many as profile_factor', meaning='non-uniform flow: the x of ' &
         // 'the profile points (none: uniform)')
      call v%real_list('profile_factor', f%profile_factor, 1000, '1', lo=0.0_dp, &
         meaning='U(x)/U at the profile points, linear between them')
      call v%end_group()
   end subroutine walk_flow

   subroutine walk_turbulence(v, t)
      class(deck_visitor_t), intent(inout) :: v
      type(turbulence_t), intent(inout) :: t
      call v%begin_group('turbulence', 'turbulence buffeting: a random force per unit ' &
         // 'length with a spectral density and a spatial coherence (docs/flow.md)')
      call v%word('spectrum', t%spectrum, spectrum_words, meaning="'table': S(f) from " &
         // "psd_frequency_hz, psd; 'reduced': (rho U^2 D/2)^2 (D/U) Phi(f D/U) from " &
         // "reduced_frequency, reduced_psd and &flow; 'none': no turbulence")
      call v%real_list('psd_frequency_hz', t%psd_frequency_hz, 4096, 'Hz', lo=0.0_dp, &
         lo_open=.true., note="increasing, as many as psd, with spectrum = 'table'", &
         meaning='frequencies of the spectrum table')
      call v%real_list('psd', t%psd, 4096, 'N^2/m^2/Hz', lo=0.0_dp, lo_open=.true., &
         meaning='one-sided spectral density of the force per unit length (log-log between ' &
         // 'points, 0 outside)')
      call v%real_list('reduced_frequency', t%reduced_frequency, 4096, '1', lo=0.0_dp, &
         lo_open=.true., note="increasing, as many as reduced_psd, with spectrum = 'reduced'", &
         meaning='reduced frequencies f D/U of the table of Phi')
      call v%real_list('reduced_psd', t%reduced_psd, 4096, '1', lo=0.0_dp, lo_open=.true., &
         meaning='the reduced spectrum Phi (log-log between points, 0 outside)')
      call v%real('correlation_length', t%correlation_length, 'm', lo=0.0_dp, hi=1.0e6_dp, &
         design=.true., meaning='lambda_c of the coherence exp(-|dx|/lambda_c) (0: fully ' &
         // 'correlated)')
      call v%word('planes', t%planes, flow_plane_words, note="'v' needs &beam planes = 2", &
         meaning="planes loaded, independently ('both' is w alone in a planar model)")
      call v%real('load_start', t%load_start, 'm', lo=0.0_dp, hi=1.0e4_dp, design=.true., &
         note='load_start < load_end <= length unless both are 0', &
         meaning='the loaded length begins at this x')
      call v%real('load_end', t%load_end, 'm', lo=0.0_dp, hi=1.0e4_dp, design=.true., &
         meaning='the loaded length ends at this x (both 0: the whole tube)')
      call v%real('cutoff_hz', t%cutoff_hz, 'Hz', lo=0.0_dp, hi=max_frequency_hz, &
         meaning="highest frequency of the record (0: the spectrum's last)")
      call v%real('frequency_resolution_hz', t%frequency_resolution_hz, 'Hz', lo=0.0_dp, &
         hi=max_frequency_hz, meaning="spacing df of the harmonics; the record repeats " &
         // "after 1/df (0: 1/the run's length, no repeat)")
      call v%int('points_per_cycle', t%points_per_cycle, lo=4, hi=64, meaning='record grid ' &
         // 'points per cycle at the cut-off (interpolation error (2 pi/n)^6/46080)')
      call v%int('seed', t%seed, meaning='seed of the random phases (a draw depends on the ' &
         // 'seed and its number only)')
      call v%int('draws', t%draws, lo=1, hi=100000, meaning='independent records per case ' &
         // '(with draws_target_ci: the first ones)')
      call v%real('draws_target_ci', t%draws_target_ci, '1', lo=0.0_dp, hi=10.0_dp, &
         note='needs draws >= 2', meaning='add draws until the 95 % half-width of the tip ' &
         // 'RMS and of every touched support''s work rates is below this fraction of the ' &
         // 'mean (0: a fixed number of draws)')
      call v%int('draws_max', t%draws_max, lo=2, hi=100000, meaning='most draws with ' &
         // 'draws_target_ci')
      call v%int_list('psd_nodes', t%psd_nodes, 64, no_nodes, lo=1, hi=100000, &
         note='transient runs; nodes 1..n_elem+1', meaning='nodes whose displacement ' &
         // 'spectral density (w, and v with two planes) is averaged over the draws')
      call v%word('psd_method', t%psd_method, psd_method_words, meaning="'welch': Hann " &
         // "segments, 50 % overlap; 'periodogram': the whole history, no window (exact " &
         // 'for a history of whole periods of the record)')
      call v%real('psd_resolution_hz', t%psd_resolution_hz, 'Hz', lo=0.0_dp, &
         hi=max_frequency_hz, meaning="Welch: bin width (segments of a power of two " &
         // "samples; 0: a quarter of the history)")
      call v%end_group()
   end subroutine walk_turbulence

   !> The node range of a list entry: 1..n_elem+1 (unbounded when describing: the note says).
   integer function node_lo(v)
      class(deck_visitor_t), intent(in) :: v
      node_lo = 1
      if (v%describing) node_lo = -huge(1)
   end function node_lo

   integer function node_hi(v, n_elem)
      class(deck_visitor_t), intent(in) :: v
      integer, intent(in) :: n_elem
      node_hi = n_elem + 1
      if (v%describing) node_hi = huge(1)
   end function node_hi

   !> Why a node is out of range.
   function mesh(n_elem) result(t)
      integer, intent(in) :: n_elem
      character(len=:), allocatable :: t
      character(len=12) :: a, b
      write(a, '(i0)') n_elem
      write(b, '(i0)') n_elem + 1
      t = 'the mesh has ' // trim(a) // ' elements, nodes 1..' // trim(b) // ' from the root'
   end function mesh
end module gapbeam_deck_table
