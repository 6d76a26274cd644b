!> The rules between deck variables: what the deck table (gapbeam_deck_table) cannot say of
!> one value alone, checked on the values a deck holds (read_deck, io/gapbeam_input, calls
!> them in the order of the groups) and given which groups and variables its sources name
!> (`given`, ' group group:variable ... '; `is_given`). Some make derived values: the Rayleigh
!> coefficients from damping ratios. The rules of &sweep and &continuation and the sizes of a
!> run are in gapbeam_deck_rules_axes, those of the flow in gapbeam_deck_rules_flow, those of
!> &initial in gapbeam_deck_rules_initial.
!> Messages read `group &beam: ...` (the reader puts the deck path before them).
module gapbeam_deck_rules
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str, q => quoted
   use gapbeam_capabilities, only: solver_refusal, method_caps, method_caps_t
   use gapbeam_laws, only: stop_law_refusal
   use gapbeam_description, only: structure_t, stop_t, dof_w, dof_theta, dof_v, dof_theta_v, &
      rayleigh_from_ratios, beam_ei, beam_rho_a, dof_name, beam_is_timoshenko, stop_is_ring, &
      beam_shear_stiffness, beam_shear_coefficient
   use gapbeam_deck, only: deck_t
   implicit none
   private
   public :: check_structure, check_stops, check_loads, check_settings, check_capabilities, &
      check_analysis, is_given, given_defaults, output_prefix_problem

contains

   !> Whether the sources name group or 'group:variable' `name` (`given` from the reader).
   pure logical function is_given(given, name)
      character(len=*), intent(in) :: given              !! ' group group:variable ... '
      character(len=*), intent(in) :: name               !! 'calibrate', 'sweep:frequency_hz'
      is_given = index(given, ' ' // name // ' ') > 0
   end function is_given

   !> Defaults that depend on what the deck gives: rk_rtol stands in for an rk45 deck's
   !> tolerance; no Lyapunov exponent by default with ring supports.
   subroutine given_defaults(given, deck)
      character(len=*), intent(in) :: given            !! what the sources name (is_given)
      type(deck_t), intent(inout) :: deck
      if (.not. is_given(given, 'solver:tolerance') .and. is_given(given, 'solver:rk_rtol') &
          .and. deck%solver%method == 'rk45') deck%solver%tolerance = deck%solver%rk_rtol
      if (any_ring(deck%stops) .and. .not. is_given(given, 'diagnostics:lyapunov_periods')) &
         deck%diagnostics%lyapunov_periods = 0
   end subroutine given_defaults

   !> Whether any stop is a ring support (circular clearance or friction).
   pure logical function any_ring(stops)
      type(stop_t), intent(in) :: stops(:)
      integer :: k
      any_ring = .false.
      do k = 1, size(stops)
         if (stop_is_ring(stops(k))) any_ring = .true.
      end do
   end function any_ring

   ! ---------------------------------------------------------------- the structure

   !> &beam, &root, &tip, &springs, &masses, &calibrate: the rules between variables.
   subroutine check_structure(given, deck, err)
      character(len=*), intent(in) :: given            !! what the sources name (is_given)
      type(deck_t), intent(inout) :: deck
      type(error_t), allocatable, intent(inout) :: err
      integer :: i
      associate (st => deck%structure, b => deck%structure%beam)
         if (b%width == 0.0_dp .and. b%thickness == 0.0_dp .and. b%area == 0.0_dp .and. &
             b%second_moment == 0.0_dp .and. b%fibre_distance == 0.0_dp) then
            call fatal_error(err, 'group &beam: the section is missing: give width and ' &
               // 'thickness (rectangle) or area, second_moment and fibre_distance')
            return
         end if
         call check_beam_scales(b, err)
         if (allocated(err)) return
         if (st%tip%condition == 'clamped' .and. b%n_elem < 2 .and. st%root%condition == &
             'clamped') then
            call fatal_error(err, "group &tip: condition = 'clamped' with a clamped root and " &
               // 'n_elem = 1 leaves no free dof')
            return
         end if
         do i = 1, size(st%springs)
            call require_node('springs', i, st%springs(i)%node, st%springs(i)%dof, st, err)
         end do
         if (allocated(err)) return
         call check_root_spring(st, err)
         if (allocated(err) .or. .not. is_given(given, 'calibrate')) return
         select case (deck%calibrate%parameter)
         case ('spring')
            if (deck%calibrate%index > size(st%springs)) call fatal_error(err, 'group ' &
               // '&calibrate: index = ' // str(deck%calibrate%index) // ': must be in 1..' &
               // str(size(st%springs)) // ' (the deck has ' // str(size(st%springs)) &
               // ' springs in &springs)')
         case ('root_k_theta')
            if (st%root%condition /= 'spring') call fatal_error(err, "group &calibrate: " &
               // "parameter = 'root_k_theta' needs &root condition='spring'")
         case ('thickness', 'width')
            if (b%width <= 0.0_dp) call fatal_error(err, "group &calibrate: parameter = '" &
               // trim(deck%calibrate%parameter) // "' needs a rectangular section (&beam " &
               // 'width, thickness)')
         end select
      end associate
   end subroutine check_structure

   !> The quantities the model is built from must be usable even when each input is: EI,
   !> rho A, the mass, and per element EI/le^3 (stiffness) and EI/(rho A le^4) (the square of a
   !> frequency) must lie between sqrt(tiny) and sqrt(huge) (about 1e-154 and 1e154), so that
   !> their squares (energies, norms) do not underflow or overflow either. Outside, the run
   !> would fail later, in an eigen-solve or an integration, far from the deck variables that
   !> cause it.
   subroutine check_beam_scales(b, err)
      use gapbeam_description, only: beam_t
      type(beam_t), intent(in) :: b                    !! beam, its inputs validated
      type(error_t), allocatable, intent(inout) :: err !! set when a scale is out of range
      real(dp) :: ei, rho_a, le, k_el, w2_el
      character(len=:), allocatable :: inputs
      if (allocated(err)) return
      ei = beam_ei(b);  rho_a = beam_rho_a(b)
      le = b%length / real(b%n_elem, dp)
      k_el = ei / le / le / le
      w2_el = ei / rho_a / le / le / le / le
      ! the strain fibre (general section) and the added mass enter the strain row and the
      ! mass: their scales too
      if (b%width <= 0.0_dp .and. .not. usable(b%fibre_distance / le / le)) then
         call fatal_error(err, 'group &beam: fibre_distance = ' // str(b%fibre_distance) &
            // ' with element length ' // str(le) // ' m gives a strain per unit rotation ' &
            // 'gradient c/le^2 = ' // str(b%fibre_distance / le / le) // ' 1/m: must be ' &
            // 'between ' // str(sqrt(tiny(1.0_dp))) // ' and ' // str(sqrt(huge(1.0_dp))))
         return
      end if
      if (beam_is_timoshenko(b)) then
         if (.not. (usable(beam_shear_stiffness(b)) .and. usable(12.0_dp * (ei / le / le) &
             / beam_shear_stiffness(b)))) then
            call fatal_error(err, "group &beam: theory = 'timoshenko' with shear_modulus = " &
               // str(b%shear_modulus) // ' and shear coefficient ' &
               // str(beam_shear_coefficient(b)) // ' gives k G A = ' &
               // str(beam_shear_stiffness(b)) // ' N and phi = 12 EI/(k G A le^2) = ' &
               // str(12.0_dp * (ei / le / le) / beam_shear_stiffness(b)) // ': each must be ' &
               // 'between ' // str(sqrt(tiny(1.0_dp))) // ' and ' // str(sqrt(huge(1.0_dp))))
            return
         end if
      end if
      if (b%added_mass > 0.0_dp .and. .not. usable((rho_a + b%added_mass) * b%length)) then
         call fatal_error(err, 'group &beam: added_mass = ' // str(b%added_mass) &
            // ' kg/m gives a beam mass of ' // str((rho_a + b%added_mass) * b%length) &
            // ' kg: must be at most ' // str(sqrt(huge(1.0_dp))))
         return
      end if
      if (usable(ei) .and. usable(rho_a) .and. usable(rho_a * b%length) .and. usable(k_el) &
          .and. usable(w2_el)) return
      if (b%width > 0.0_dp) then
         inputs = 'youngs_modulus = ' // str(b%youngs_modulus) // ', width = ' // str(b%width) &
            // ', thickness = ' // str(b%thickness)
      else
         inputs = 'youngs_modulus = ' // str(b%youngs_modulus) // ', area = ' // str(b%area) &
            // ', second_moment = ' // str(b%second_moment)
      end if
      call fatal_error(err, 'group &beam: ' // inputs // ', density = ' // str(b%density) &
         // ', length = ' // str(b%length) // ' and n_elem = ' // str(b%n_elem) // ' give EI = ' &
         // str(ei) // ' N m^2, rho A = ' // str(rho_a) // ' kg/m, element stiffness EI/le^3 = ' &
         // str(k_el) // ' N/m and EI/(rho A le^4) = ' // str(w2_el) // ' 1/s^2: each must be ' &
         // 'between ' // str(sqrt(tiny(1.0_dp))) // ' and ' // str(sqrt(huge(1.0_dp))))
   end subroutine check_beam_scales

   !> x finite and between sqrt(tiny) and sqrt(huge).
   pure logical function usable(x)
      real(dp), intent(in) :: x
      usable = ieee_is_finite(x) .and. x >= sqrt(tiny(1.0_dp)) .and. x <= sqrt(huge(1.0_dp))
   end function usable

   !> A root spring negligible against the beam (kappa = k_theta L / EI below 1e-12) with no
   !> &springs: to double precision the root is a pin and the beam a mechanism, whose stiffness
   !> matrix is singular (the eigen-solve would fail far from the deck variables).
   subroutine check_root_spring(st, err)
      type(structure_t), intent(in) :: st                !! beam, root, springs
      type(error_t), allocatable, intent(inout) :: err   !! the spring is negligible
      real(dp) :: kappa, ei_l
      if (allocated(err) .or. st%root%condition /= 'spring' .or. size(st%springs) > 0) return
      kappa = st%root%k_theta * st%beam%length / beam_ei(st%beam)
      ei_l = beam_ei(st%beam) / st%beam%length
      if (kappa < 1.0e-12_dp) call fatal_error(err, 'group &root: k_theta = ' &
         // str(st%root%k_theta) // ' N m/rad against the beam (&beam youngs_modulus, width, ' &
         // 'thickness or second_moment, length: EI/L = ' // str(ei_l) // ' N m): kappa = ' &
         // 'k_theta L / EI = ' // str(kappa) // ' is below 1e-12; to double precision the ' &
         // 'root is a pin and the beam, with no &springs, a mechanism (its stiffness matrix ' &
         // 'is singular)')
   end subroutine check_root_spring

   !> The node of entry i of a list group exists and its dof is free: not fixed by the root or
   !> tip condition, and a second-plane dof ('v', 'theta_v') only with &beam planes = 2.
   subroutine require_node(group, i, node, dof, st, err)
      character(len=*), intent(in) :: group            !! list group
      integer, intent(in) :: i, node, dof              !! entry, its node and dof code
      type(structure_t), intent(in) :: st              !! the structure
      type(error_t), allocatable, intent(inout) :: err !! the node or dof is refused
      character(len=:), allocatable :: v, w
      integer :: n_elem
      logical :: rot
      if (allocated(err)) return
      n_elem = st%beam%n_elem
      v = 'group &' // group // ': node(' // str(i) // ')'
      w = " with dof '" // dof_name(dof) // "'"
      rot = dof == dof_theta .or. dof == dof_theta_v
      if (node < 1 .or. node > n_elem + 1) then
         call fatal_error(err, v // ' = ' // str(node) // ': must be in 1..' // str(n_elem + 1) &
            // ' (the mesh has ' // str(n_elem) // ' elements, nodes 1..' // str(n_elem + 1) &
            // ' from the root)')
      else if ((dof == dof_v .or. dof == dof_theta_v) .and. st%beam%planes < 2) then
         call fatal_error(err, v // w // ': the second plane needs &beam planes = 2')
      else if (node == 1 .and. .not. rot) then
         call fatal_error(err, v // ' = 1' // w // ': the root translation is fixed')
      else if (node == 1 .and. rot .and. st%root%condition == 'clamped') then
         call fatal_error(err, v // ' = 1' // w // ": the root is clamped (use &root " &
            // "condition='spring')")
      else if (node == n_elem + 1 .and. .not. rot .and. st%tip%condition /= 'free') then
         call fatal_error(err, v // ' = ' // str(node) // w // ': the tip translation is ' &
            // "fixed (&tip condition = '" // trim(st%tip%condition) // "')")
      else if (node == n_elem + 1 .and. rot .and. st%tip%condition == 'clamped') then
         call fatal_error(err, v // ' = ' // str(node) // w // ': the tip is clamped')
      end if
   end subroutine require_node

   !> &stops: nodes, the stiffness rule, the Hertz law, the ring supports.
   subroutine check_stops(st, stops, err)
      type(structure_t), intent(in) :: st
      type(stop_t), intent(in) :: stops(:)
      type(error_t), allocatable, intent(inout) :: err
      character(len=:), allocatable :: ix
      integer :: i
      do i = 1, size(stops)
         ix = '(' // str(i) // ')'
         associate (s => stops(i))
            call require_node('stops', i, s%node, s%dof, st, err)
            call check_support(st, i, s, err)
            if (allocated(err)) return
            if (s%rule_factor > 0.0_dp .and. s%rule_f1_ratio == 0.0_dp .and. &
                s%rule_f1_hz == 0.0_dp) then
               call fatal_error(err, 'group &stops: rule_factor' // ix // ' = ' &
                  // str(s%rule_factor) // ' needs rule_f1_ratio' // ix // ' > 1 or ' &
                  // 'rule_f1_hz' // ix // ' > 0 (the target of the stiffness rule)')
               return
            end if
         end associate
      end do
   end subroutine check_stops

   !> The support variables of stop i: a circular clearance needs two planes, a positive gap,
   !> a translational node (both planes free there), no side or dof choice and no stiffness
   !> rule; friction needs two planes (the sliding direction) and a translational dof; the
   !> hole offset belongs to a circular clearance only.
   subroutine check_support(st, i, s, err)
      type(structure_t), intent(in) :: st
      integer, intent(in) :: i
      type(stop_t), intent(in) :: s
      type(error_t), allocatable, intent(inout) :: err
      character(len=:), allocatable :: ix
      if (allocated(err)) return
      ix = '(' // str(i) // ')'
      if (s%shape == 'circular') then
         if (st%beam%planes < 2) then
            call fatal_error(err, 'group &stops: shape' // ix // " = 'circular' needs &beam " &
               // 'planes = 2 (a circular clearance acts in both transverse planes)')
         else if (.not. (s%gap > 0.0_dp)) then
            call fatal_error(err, 'group &stops: gap' // ix // ' = ' // str(s%gap) // ": a " &
               // "circular clearance (shape = 'circular') needs a radial gap > 0")
         else if (s%dof /= dof_w) then
            call fatal_error(err, 'group &stops: dof' // ix // " = '" // dof_name(s%dof) &
               // "': a circular clearance acts on the node's w and v; leave dof out")
         else if (s%side /= 'positive') then
            call fatal_error(err, 'group &stops: side' // ix // " = '" // trim(s%side) &
               // "': a circular clearance has no side; leave side out")
         else if (s%rule_factor > 0.0_dp) then
            call fatal_error(err, 'group &stops: rule_factor' // ix // ' = ' &
               // str(s%rule_factor) // ': the stiffness rule is for flat stops; give ' &
               // 'stiffness for a circular clearance')
         else
            call require_node('stops', i, s%node, dof_v, st, err)
            if (allocated(err)) err%message = err%message // ' (stop' // ix // ' is circular)'
         end if
      else if (s%offset_w /= 0.0_dp .or. s%offset_v /= 0.0_dp) then
         call fatal_error(err, 'group &stops: offset_w' // ix // ' = ' // str(s%offset_w) &
            // ', offset_v' // ix // ' = ' // str(s%offset_v) // ": the hole centre offset " &
            // "belongs to a circular clearance (shape = 'circular')")
      end if
      if (allocated(err) .or. .not. (s%friction > 0.0_dp)) return
      if (st%beam%planes < 2) then
         call fatal_error(err, 'group &stops: friction' // ix // ' = ' // str(s%friction) &
            // ': friction needs &beam planes = 2 (a planar model has no sliding direction)')
      else if (s%dof == dof_theta .or. s%dof == dof_theta_v) then
         call fatal_error(err, 'group &stops: friction' // ix // ' = ' // str(s%friction) &
            // " on a rotation dof: friction acts on the translations ('w' or 'v')")
      else if (s%rule_factor > 0.0_dp) then
         call fatal_error(err, 'group &stops: friction' // ix // ' = ' // str(s%friction) &
            // ' with rule_factor' // ix // ': give stiffness (and tangential_stiffness) ' &
            // 'for a stop with friction')
      else
         ! the sliding direction: the node's other translation
         if (s%dof == dof_w) call require_node('stops', i, s%node, dof_v, st, err)
         if (s%dof == dof_v) call require_node('stops', i, s%node, dof_w, st, err)
         if (allocated(err)) err%message = err%message // ' (stop' // ix &
            // ' has friction: it slides along the other plane)'
      end if
   end subroutine check_support

   ! ---------------------------------------------------------------- loads and settings

   !> &damping (the coefficients that ratios give), &forcing, &point_forces, &initial.
   subroutine check_loads(deck, err)
      type(deck_t), intent(inout) :: deck
      type(error_t), allocatable, intent(inout) :: err
      integer :: i, j
      associate (d => deck%damping, st => deck%structure)
         if (allocated(d%modal_ratios) .and. d%model /= 'modal') then
            call fatal_error(err, "group &damping: modal_ratios is given with model = '" &
               // trim(d%model) // "': modal_ratios needs model = 'modal'")
            return
         end if
         select case (d%model)
         case ('none')
            d%mass_coefficient = 0.0_dp;  d%stiffness_coefficient = 0.0_dp
         case ('modal')
            if (.not. allocated(d%modal_ratios)) then
               call fatal_error(err, "group &damping: model = 'modal' needs modal_ratios " &
                  // '(one value for every mode, or the values of modes 1, 2, ..., the last ' &
                  // 'one for every further mode)')
               return
            end if
         case ('ratios')
            if (d%frequency2_hz <= d%frequency1_hz) then
               call fatal_error(err, 'group &damping: frequency2_hz = ' // str(d%frequency2_hz) &
                  // ': must be > frequency1_hz = ' // str(d%frequency1_hz))
               return
            end if
            call rayleigh_from_ratios(d%frequency1_hz, d%ratio1, d%frequency2_hz, d%ratio2, &
               d%mass_coefficient, d%stiffness_coefficient)
            if (d%mass_coefficient > sqrt(huge(1.0_dp)) .or. &
                d%stiffness_coefficient > sqrt(huge(1.0_dp))) then
               call fatal_error(err, 'group &damping: the ratios (' // str(d%ratio1) // ' at ' &
                  // str(d%frequency1_hz) // ' Hz, ' // str(d%ratio2) // ' at ' &
                  // str(d%frequency2_hz) // ' Hz) give beta = ' // str(d%mass_coefficient) &
                  // ' 1/s, gamma = ' // str(d%stiffness_coefficient) // ' s: each must be ' &
                  // 'at most ' // str(sqrt(huge(1.0_dp))) // ' (the scale rule)')
               return
            end if
            if (d%mass_coefficient < 0.0_dp .or. d%stiffness_coefficient < 0.0_dp) then
               call fatal_error(err, 'group &damping: the ratios (' // str(d%ratio1) // ' at ' &
                  // str(d%frequency1_hz) // ' Hz, ' // str(d%ratio2) // ' at ' &
                  // str(d%frequency2_hz) // ' Hz) give a negative Rayleigh coefficient ' &
                  // '(beta = ' // str(d%mass_coefficient) // ' 1/s, gamma = ' &
                  // str(d%stiffness_coefficient) // ' s): not allowed')
               return
            end if
         end select
         associate (f => deck%forcing)
            if ((f%direction_deg /= 0.0_dp .or. f%phase_v_deg /= 0.0_dp) .and. &
                st%beam%planes < 2) then
               call fatal_error(err, 'group &forcing: direction_deg = ' // str(f%direction_deg) &
                  // ', phase_v_deg = ' // str(f%phase_v_deg) // ': a base motion out of the ' &
                  // 'w plane needs &beam planes = 2')
               return
            end if
            do i = 1, size(f%forces)
               call require_node('point_forces', i, f%forces(i)%node, f%forces(i)%dof, st, err)
            end do
         end associate
         associate (ini => deck%initial)
            do i = 1, size(ini%node)
               call require_node('initial', i, ini%node(i), ini%dof(i), st, err)
               do j = 1, i - 1
                  if (ini%node(j) == ini%node(i) .and. ini%dof(j) == ini%dof(i) .and. &
                      .not. allocated(err)) call fatal_error(err, 'group &initial: node(' &
                     // str(i) // ') = ' // str(ini%node(i)) // " with dof '" &
                     // dof_name(ini%dof(i)) // "' is also entry " // str(j) // ': give each ' &
                     // '(node, dof) once')
               end do
            end do
            if (allocated(err)) return
            if (ini%kind == 'given' .and. size(ini%node) == 0) call fatal_error(err, &
               "group &initial: kind = 'given' needs node, dof, displacement and velocity lists")
         end associate
      end associate
   end subroutine check_loads

   !> &solver, &output, &diagnostics, &study, &model_size: the rules between variables.
   subroutine check_settings(deck, err)
      type(deck_t), intent(inout) :: deck
      type(error_t), allocatable, intent(inout) :: err
      real(dp) :: ticks
      integer :: j, k
      if (allocated(err)) return
      associate (s => deck%solver)
         ! time is counted in integer ticks of T / (steps_per_period 2^max_halvings)
         ticks = (real(s%transient_periods, dp) + real(s%record_periods, dp)) &
                 * real(s%steps_per_period, dp) * 2.0_dp**s%max_halvings
         if (.not. (ticks < 2.0_dp**62)) then
            call fatal_error(err, 'group &solver: (transient_periods + record_periods) * ' &
               // 'steps_per_period * 2**max_halvings = ' // str(ticks) // ' ticks: must ' &
               // 'be below 2**62; lower transient_periods, record_periods, max_halvings or ' &
               // 'steps_per_period')
            return
         end if
      end associate
      associate (o => deck%output)
         if (o%filter_cutoff_hz > 0.0_dp .and. mod(o%filter_samples_per_period, &
             o%samples_per_period) /= 0) then
            call fatal_error(err, 'group &output: filter_samples_per_period = ' &
               // str(o%filter_samples_per_period) // ': must be a multiple of ' &
               // 'samples_per_period = ' // str(o%samples_per_period) // ' (the filtered ' &
               // 'history is taken at the filter samples)')
            return
         end if
      end associate
      associate (d => deck%diagnostics)
         if (d%lyapunov_max_periods > 0 .and. d%lyapunov_max_periods < d%lyapunov_periods) then
            call fatal_error(err, 'group &diagnostics: lyapunov_max_periods = ' &
               // str(d%lyapunov_max_periods) // ': must be 0 or at least lyapunov_periods = ' &
               // str(d%lyapunov_periods))
            return
         end if
         do j = 1, size(d%starts)
            do k = 1, j - 1
               if (d%starts(k) == d%starts(j) .and. len_trim(d%starts(j)) > 0) then
                  call fatal_error(err, 'group &diagnostics: starts(' // str(j) // ") = '" &
                     // trim(d%starts(j)) // "' is also starts(" // str(k) // '): each start ' &
                     // "at most once ('random' gives random_starts states)")
                  return
               end if
            end do
         end do
      end associate
      associate (st => deck%study)
         if (st%omega_dt_max < st%omega_dt_min) then
            call fatal_error(err, 'group &study: omega_dt_max = ' // str(st%omega_dt_max) &
               // ': must be in [' // str(st%omega_dt_min) // ', 1E+012] (at least ' &
               // 'omega_dt_min)')
            return
         end if
         ! the finest fixed-step level counts its time in ticks too
         ticks = real(st%periods, dp) * real(st%base_steps, dp) * 2.0_dp**(st%levels - 1) &
                 * 2.0_dp**deck%solver%max_halvings
         if (deck%job%analysis == 'work_precision' .and. .not. (ticks < 2.0_dp**62)) then
            call fatal_error(err, 'group &study: periods * base_steps * 2**(levels - 1) * ' &
               // '&solver 2**max_halvings = ' // str(ticks) // ' ticks at the finest level: ' &
               // 'must be below 2**62; lower periods, base_steps or levels')
            return
         end if
      end associate
      associate (m => deck%model_size)
         m%elements = pack(m%elements, m%elements > 0)
         m%modes = pack(m%modes, m%modes > 0)
         if (size(m%elements) == 0) call fatal_error(err, 'group &model_size: elements: give ' &
            // 'at least one element count')
      end associate
   end subroutine check_settings

   !> What the methods and the contact laws can do: the combinations the reader refuses, as
   !> their registry entries say (gapbeam_capabilities, gapbeam_laws).
   subroutine check_capabilities(deck, err)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      integer :: i
      character(len=:), allocatable :: why
      type(method_caps_t) :: mc
      if (allocated(err)) return
      ! combinations of method, step control and stop solution: what the method's registry
      ! entry takes (gapbeam_capabilities)
      why = solver_refusal(deck%solver%method, deck%solver%step_control, &
                           deck%solver%stop_solution)
      if (len(why) > 0) call fatal_error(err, 'group &solver: ' // why)
      ! what each stop's law takes (its registry entry, gapbeam_laws): exponent, damper, ring
      do i = 1, size(deck%stops)
         if (allocated(err)) exit
         associate (s => deck%stops(i))
            why = stop_law_refusal(s%law, '(' // str(i) // ')', s%damping, s%exponent, &
               s%shape == 'circular' .or. s%friction > 0.0_dp, s%friction, &
               s%tangential_stiffness)
         end associate
         if (len(why) > 0) call fatal_error(err, 'group &stops: ' // why)
      end do
      if (allocated(err)) return
      if (deck%damping%model == 'modal' .and. deck%solver%linear_solver == 'banded') then
         call fatal_error(err, "group &solver: linear_solver = 'banded': modal damping " &
            // "(&damping model = 'modal') makes the damping matrix dense; use 'auto' or " &
            // "'dense'")
         return
      end if
      ! the exact Jacobian needs a method whose registry entry gives one
      mc = method_caps(deck%solver%method)
      if (deck%continuation%jacobian == 'exact' .and. .not. mc%jacobian .and. &
          deck%solver%method /= 'auto' .and. deck%job%analysis == 'continuation') then
         call fatal_error(err, "group &continuation: jacobian = 'exact' needs &solver " &
            // "method = 'exact' (or 'auto' with piecewise-linear stops; the deck has '" &
            // trim(deck%solver%method) // "'); use jacobian = 'finite_difference' with " &
            // 'other methods')
      end if
   end subroutine check_capabilities

   !> What each analysis needs: its groups and values; 'up' and 'down' starts in a sweep.
   subroutine check_analysis(given, deck, err)
      character(len=*), intent(in) :: given            !! what the sources name (is_given)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      logical :: lines
      associate (a => deck%job%analysis)
         if (a == 'calibrate' .and. deck%calibrate%target_f1_hz <= 0.0_dp) then
            call fatal_error(err, "group &calibrate: target_f1_hz = " &
               // str(deck%calibrate%target_f1_hz) // ": must be > 0 for analysis='calibrate'")
         else if ((a == 'transient' .or. a == 'sweep' .or. a == 'work_precision' .or. &
                   a == 'model_size' .or. a == 'continuation') .and. &
                  .not. is_given(given, 'forcing')) then
            call fatal_error(err, "group &forcing is missing: analysis='" // trim(a) &
               // "' needs frequency_hz (use amplitude_pp=0 for free vibration)")
         else if (a == 'sweep' .and. .not. is_given(given, 'sweep')) then
            call fatal_error(err, "group &sweep is missing: analysis='sweep' needs the " &
               // 'frequencies and amplitudes to sweep')
         end if
         if (allocated(err)) return
         lines = any(deck%diagnostics%starts == 'up' .or. deck%diagnostics%starts == 'down')
         if (lines .and. a /= 'sweep') then
            call fatal_error(err, "group &diagnostics: starts 'up' and 'down' start from a " &
               // "sweep neighbour's final state: only with analysis = 'sweep' (this deck " &
               // "runs '" // trim(a) // "')")
            return
         end if
         if (a /= 'sweep') return
      end associate
      if (all(len_trim(deck%diagnostics%starts) == 0)) lines = deck%sweep%mode == 'continuation'
      if (.not. lines) return
      associate (sw => deck%sweep)
         if ((sw%axis == 'frequency' .and. sw%x_variable /= '&forcing frequency_hz' .and. &
              sw%y_variable /= '&forcing frequency_hz') .or. (sw%axis == 'amplitude' .and. &
              sw%x_variable /= '&forcing amplitude_pp' .and. sw%y_variable /= &
              '&forcing amplitude_pp')) call fatal_error(err, "group &sweep: axis = '" &
            // trim(sw%axis) // "': the lines of a continuation run along an axis of the " &
            // "sweep, and neither x_variable ('" // trim(sw%x_variable) // "') nor " &
            // "y_variable ('" // trim(sw%y_variable) // "') is the " // trim(sw%axis) &
            // "; use axis = 'x' or 'y'")
      end associate
   end subroutine check_analysis
   ! ---------------------------------------------------------------- &job output

   !> Why `prefix` cannot be an output prefix (the files are PREFIX.h5, PREFIX.history.dat,
   !> ...), '' when it can: a prefix that names a directory ('results/x/', '.', '..', '/')
   !> would give hidden files ('results/x/.h5'). It is refused rather than given a stem: the
   !> user meant a directory, and only the user can say what the files there should be called.
   pure function output_prefix_problem(prefix) result(why)
      character(len=*), intent(in) :: prefix             !! output prefix as given
      character(len=:), allocatable :: why, last
      why = ''
      last = trim(prefix)
      last = last(index(last, '/', back=.true.) + 1:)
      if (len_trim(prefix) == 0) then
         why = 'the output prefix is empty: give a file stem, e.g. ''results/run'''
      else if (has_control(prefix)) then
         why = 'the output prefix contains a control character (' // control_names(prefix) &
            // '): such file names cannot be typed or listed safely; use letters, digits, ' &
            // "'_', '-', '.' and '/'"
      else if (len(last) == 0 .or. last == '.' .or. last == '..') then
         why = 'the output prefix ' // q(trim(prefix)) // ' names a directory, not a file ' &
            // 'stem: the files would be hidden (' // q(trim(prefix) // '.h5') // '); give ' &
            // 'a stem in it, e.g. ' // q(trim(prefix) // trim(merge('/  ', '   ', &
            len(last) > 0)) // 'run')
      end if
   end function output_prefix_problem

   !> Whether `text` holds a control character (ASCII 0-31 or 127).
   pure logical function has_control(text)
      character(len=*), intent(in) :: text               !! text
      integer :: i
      has_control = .false.
      do i = 1, len(text)
         if (iachar(text(i:i)) < 32 .or. iachar(text(i:i)) == 127) has_control = .true.
      end do
   end function has_control

   !> The control characters of `text`, as 'code 27' items (the first three).
   pure function control_names(text) result(t)
      character(len=*), intent(in) :: text               !! text
      character(len=:), allocatable :: t
      integer :: i, n
      t = '';  n = 0
      do i = 1, len(text)
         if (.not. (iachar(text(i:i)) < 32 .or. iachar(text(i:i)) == 127)) cycle
         n = n + 1
         if (n > 3) exit
         if (n > 1) t = t // ', '
         t = t // 'code ' // str(iachar(text(i:i))) // ' at position ' // str(i)
      end do
   end function control_names
end module gapbeam_deck_rules
