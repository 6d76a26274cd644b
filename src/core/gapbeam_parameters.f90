!> The resolved parameters of a run, as a list of named values with units, for the
!> `/parameters` group of every result file: what the deck gave and what the program derived
!> from it (EI, rho A, kappa = k_theta L / EI, the stop stiffness from the paper's rule, the
!> Rayleigh coefficients from two ratios, f1 with the stops open, the highest frequency, the
!> forcing period), so that a file says which model produced it without its deck being parsed.
!>
!> Units are UDUNITS-2 strings ('m', 'N m-1', 'N m rad-1', '1' for a pure number).
module gapbeam_parameters
   use gapbeam_kinds, only: dp, pi
   use gapbeam_deck, only: deck_t
   use gapbeam_laws, only: law_caps_of
   use gapbeam_law, only: law_caps_t
   use gapbeam_description, only: beam_ei, beam_rho_a, beam_fibre_distance, beam_mass, &
      dof_w, dof_theta
   implicit none
   private
   public :: parameter_t, parameter_set_t, run_parameters, stiffness_units

   !> One named value (a number, a list of numbers, or a text).
   type :: parameter_t
      character(len=:), allocatable :: path        !! under /parameters, e.g. 'beam/length'
      real(dp), allocatable :: values(:)           !! the number(s); unallocated for a text
      logical :: is_array = .false.                !! a list (one value per stop, ...)
      character(len=:), allocatable :: text        !! a text value, else unallocated
      character(len=:), allocatable :: units       !! UDUNITS-2 units ('1' for a pure number)
      character(len=:), allocatable :: long_name   !! what the value is, in words
   end type parameter_t

   !> The parameters of a run.
   type :: parameter_set_t
      type(parameter_t), allocatable :: items(:)   !! in the order they are written
   contains
      procedure :: add_real, add_list, add_text
   end type parameter_set_t

contains

   !> Add a scalar.
   subroutine add_real(self, path, value, units, long_name)
      class(parameter_set_t), intent(inout) :: self    !! set
      character(len=*), intent(in) :: path             !! under /parameters
      real(dp), intent(in) :: value                    !! value [units]
      character(len=*), intent(in) :: units            !! UDUNITS-2 units
      character(len=*), intent(in) :: long_name        !! what it is
      type(parameter_t) :: p
      p%path = path;  p%values = [value];  p%units = units;  p%long_name = long_name
      call append(self, p)
   end subroutine add_real

   !> Add a list of numbers (one per stop, per mode, ...).
   subroutine add_list(self, path, values, units, long_name)
      class(parameter_set_t), intent(inout) :: self    !! set
      character(len=*), intent(in) :: path             !! under /parameters
      real(dp), intent(in) :: values(:)                !! values [units]
      character(len=*), intent(in) :: units            !! UDUNITS-2 units
      character(len=*), intent(in) :: long_name        !! what they are
      type(parameter_t) :: p
      p%path = path;  p%values = values;  p%is_array = .true.;  p%units = units
      p%long_name = long_name
      call append(self, p)
   end subroutine add_list

   !> Add a text.
   subroutine add_text(self, path, text, long_name)
      class(parameter_set_t), intent(inout) :: self    !! set
      character(len=*), intent(in) :: path             !! under /parameters
      character(len=*), intent(in) :: text             !! value
      character(len=*), intent(in) :: long_name        !! what it is
      type(parameter_t) :: p
      p%path = path;  p%text = text;  p%units = '1';  p%long_name = long_name
      call append(self, p)
   end subroutine add_text

   subroutine append(set, p)
      type(parameter_set_t), intent(inout) :: set
      type(parameter_t), intent(in) :: p
      type(parameter_t), allocatable :: grown(:)
      integer :: n
      if (.not. allocated(set%items)) allocate(set%items(0))
      n = size(set%items)
      allocate(grown(n + 1))
      grown(1:n) = set%items
      grown(n + 1) = p
      call move_alloc(grown, set%items)
   end subroutine append

   !> The parameters of a run of `deck`: the deck's values and what was resolved from them.
   !> The resolved values the caller knows are optional: the stop stiffnesses (the paper's rule
   !> applied), f1 with the stops open, the highest natural frequency and the number of dofs.
   function run_parameters(deck, stop_stiffness, f1_open_hz, f_max_hz, n_dof) result(set)
      type(deck_t), intent(in) :: deck                       !! validated deck
      real(dp), intent(in), optional :: stop_stiffness(:)    !! resolved, per deck stop
      real(dp), intent(in), optional :: f1_open_hz           !! first frequency, stops open [Hz]
      real(dp), intent(in), optional :: f_max_hz             !! highest frequency [Hz]
      integer, intent(in), optional :: n_dof                 !! dofs of the integrated model
      type(parameter_set_t) :: set
      real(dp) :: ei, le
      integer :: ns, j
      logical :: rectangle
      allocate(set%items(0))
      associate (b => deck%structure%beam, root => deck%structure%root)
         ei = beam_ei(b)
         le = b%length / real(b%n_elem, dp)
         rectangle = b%width > 0.0_dp .and. b%thickness > 0.0_dp
         call set%add_real('beam/length', b%length, 'm', 'beam length L')
         call set%add_real('beam/n_elem', real(b%n_elem, dp), '1', 'number of elements')
         call set%add_real('beam/element_length', le, 'm', 'element length')
         call set%add_real('beam/youngs_modulus', b%youngs_modulus, 'Pa', "Young's modulus E")
         call set%add_real('beam/density', b%density, 'kg m-3', 'density rho')
         if (rectangle) then
            call set%add_real('beam/width', b%width, 'm', 'section width b (rectangle)')
            call set%add_real('beam/thickness', b%thickness, 'm', &
                              'section thickness h, in the bending direction (rectangle)')
            call set%add_real('beam/area', b%width * b%thickness, 'm2', 'section area A = b h')
            call set%add_real('beam/second_moment', b%width * b%thickness**3 / 12.0_dp, 'm4', &
                              'second moment of area I = b h^3 / 12')
         else
            call set%add_real('beam/area', b%area, 'm2', 'section area A')
            call set%add_real('beam/second_moment', b%second_moment, 'm4', &
                              'second moment of area I')
         end if
         call set%add_real('beam/fibre_distance', beam_fibre_distance(b), 'm', &
                           'distance c of the strain fibre from the neutral axis')
         call set%add_real('beam/bending_stiffness', ei, 'N m2', 'bending stiffness EI')
         call set%add_real('beam/mass_per_length', beam_rho_a(b), 'kg m-1', &
                           'mass per unit length rho A')
         call set%add_real('beam/mass', beam_mass(b), 'kg', 'beam mass rho A L')
         call set%add_text('beam/mass_matrix', trim(b%mass_matrix), 'element mass matrix')
         call set%add_text('beam/rotary_inertia', trim(b%rotary_inertia), &
                           'rotary inertia rule of the lumped mass matrix')
         call set%add_text('root/condition', trim(root%condition), &
                           'root rotation: clamped, or restrained by a spring')
         if (root%condition == 'spring') then
            call set%add_real('root/k_theta', root%k_theta, 'N m rad-1', &
                              'root rotational spring k_theta')
            call set%add_real('root/kappa', root%k_theta * b%length / ei, '1', &
                              'root spring ratio kappa = k_theta L / EI')
         end if
      end associate
      ns = 0
      if (allocated(deck%stops)) ns = size(deck%stops)
      call set%add_real('stops/count', real(ns, dp), '1', 'number of stops')
      if (ns > 0) then
         call set%add_list('stops/node', [(real(deck%stops(j)%node, dp), j = 1, ns)], '1', &
                           'node of each stop (1 = root)')
         call set%add_list('stops/gap', [(deck%stops(j)%gap, j = 1, ns)], &
                           stop_units(deck, 'm', 'rad'), &
                           'clearance of each stop (m for a w stop, rad for a theta stop)')
         if (present(stop_stiffness)) call set%add_list('stops/stiffness', stop_stiffness, &
            stiffness_units(deck), 'contact stiffness of each stop, the paper''s rule ' &
            // 'applied (N m-1 for a bilinear w stop, N m rad-1 for a theta stop, N m-p for ' &
            // 'a Hertz stop)')
         call set%add_list('stops/damping', [(deck%stops(j)%damping, j = 1, ns)], &
                           stop_units(deck, 'N s m-1', 'N m s rad-1'), &
                           'contact damper of each stop, active in contact only')
         call set%add_list('stops/exponent', [(deck%stops(j)%exponent, j = 1, ns)], '1', &
                           'Hertz exponent p of each stop (bilinear stops: not used)')
         call set%add_list('stops/side', [(side_code(deck%stops(j)%side), j = 1, ns)], '1', &
                           'side of each stop: 1 positive (met moving +w), -1 negative, ' &
                           // '2 both')
         call set%add_list('stops/dof', [(real(deck%stops(j)%dof, dp), j = 1, ns)], '1', &
                           'dof of each stop: 1 w (transverse displacement), 2 theta (rotation)')
      end if
      call set%add_text('damping/model', trim(deck%damping%model), 'damping model')
      call set%add_real('damping/mass_coefficient', deck%damping%mass_coefficient, 's-1', &
                        'Rayleigh mass coefficient beta in C = beta M + gamma K')
      call set%add_real('damping/stiffness_coefficient', deck%damping%stiffness_coefficient, &
                        's', 'Rayleigh stiffness coefficient gamma in C = beta M + gamma K')
      call set%add_real('forcing/frequency_hz', deck%forcing%frequency_hz, 'Hz', &
                        'forcing frequency f of the deck (a sweep varies it: /sweep)')
      call set%add_real('forcing/amplitude_pp', deck%forcing%amplitude_pp, 'm', &
                        'base displacement amplitude, peak to peak (a sweep varies it)')
      call set%add_real('forcing/period', 1.0_dp / deck%forcing%frequency_hz, 's', &
                        'forcing period T = 1/f')
      call set%add_real('forcing/omega', 2.0_dp * pi * deck%forcing%frequency_hz, 'rad s-1', &
                        'forcing angular frequency 2 pi f')
      if (present(f1_open_hz)) call set%add_real('model/f1_open_hz', f1_open_hz, 'Hz', &
         'first natural frequency with the stops open')
      if (present(f_max_hz)) call set%add_real('model/f_max_hz', f_max_hz, 'Hz', &
         'highest natural frequency of the integrated model')
      if (present(n_dof)) call set%add_real('model/n_dof', real(n_dof, dp), '1', &
         'degrees of freedom of the integrated model')
      call set%add_text('model/reduction', trim(deck%reduction%kind), &
                        'none: the finite element model; modal: a modal model of it')
   end function run_parameters

   !> Units of a per-stop quantity: `w_units` when every stop acts on w, `theta_units` when
   !> every one acts on theta, '1' (see long_name) when they are mixed.
   function stop_units(deck, w_units, theta_units) result(u)
      type(deck_t), intent(in) :: deck
      character(len=*), intent(in) :: w_units, theta_units
      character(len=:), allocatable :: u
      if (all(deck%stops%dof == dof_w)) then
         u = w_units
      else if (all(deck%stops%dof == dof_theta)) then
         u = theta_units
      else
         u = '1'
      end if
   end function stop_units

   !> Units of the stop stiffnesses: N m-1 or N m rad-1 for laws with a linear stiffness
   !> (bilinear) at stops of one kind of dof; '1' (see long_name) otherwise (Hertz stops:
   !> N m-p, with p per stop).
   function stiffness_units(deck) result(u)
      type(deck_t), intent(in) :: deck
      character(len=:), allocatable :: u
      type(law_caps_t) :: lc
      integer :: j
      u = '1'
      do j = 1, size(deck%stops)
         lc = law_caps_of(deck%stops(j)%law)
         if (.not. lc%linear_stiffness) return
      end do
      u = stop_units(deck, 'N m-1', 'N m rad-1')
   end function stiffness_units

   pure real(dp) function side_code(word)
      character(len=*), intent(in) :: word
      select case (trim(word))
      case ('negative')
         side_code = -1.0_dp
      case ('both')
         side_code = 2.0_dp
      case default
         side_code = 1.0_dp
      end select
   end function side_code
end module gapbeam_parameters
