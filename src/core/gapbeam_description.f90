!> What a deck describes physically: the beam, its root, boundary springs and point masses, the
!> gap supports (stops), the damping and the forcing. Pure data with a few pure helpers; the
!> model builder (src/model) turns it into the matrices the integrators use.
!>
!> SI units throughout. The beam lies along x from the root (node 1, x = 0) to the tip
!> (node n_elem+1, x = length); w is the transverse displacement relative to the base,
!> theta = dw/dx. Nodes are numbered 1..n_elem+1 from the root.
!>
!> Stops: a one-sided contact acts at one dof with a direction s = +1 (met when the dof moves
!> in +w, u >= gap) or s = -1 (u <= -gap); 'both' sides makes two one-sided contacts.
!>
!> Two planes of motion (`planes = 2`, see docs/tubes.md): every node also carries v (the
!> transverse displacement in the second plane) and theta_v = dv/dx; the same element acts in
!> each plane and the planes are coupled only by the supports. A support with a circular
!> clearance ('circular') is met when the radial distance of (w, v) at its node from the hole
!> centre (offset_w, offset_v) reaches the gap; its normal is radial. Any support may carry
!> Coulomb friction (coefficient mu) with an elastic stick (tangential_stiffness), see
!> src/model/gapbeam_ring_contact.f90.
module gapbeam_description
   use gapbeam_kinds, only: dp, pi
   use gapbeam_laws, only: law_index
   implicit none
   private
   public :: beam_t, root_t, spring_t, point_mass_t, structure_t, stop_t, damping_t, forcing_t
   public :: point_force_t, flow_t, turbulence_t
   public :: beam_ei, beam_rho_a, beam_fibre_distance, beam_mass, n_nodes, forcing_omega
   public :: beam_mass_per_length, stop_is_ring
   public :: beam_rho_i, beam_shear_stiffness, beam_shear_coefficient, beam_is_timoshenko
   public :: modal_ratio, rigid_planes
   public :: rayleigh_from_ratios, modal_damping_ratio
   public :: dof_w, dof_theta, dof_v, dof_theta_v, dof_name, law_code, law_bilinear, law_hertz
   public :: stop_side_words, stop_law_words, damping_words, rotary_inertia_words, &
      stop_shape_words, end_condition_words, tip_condition_words, beam_theory_words
   public :: fluid_elastic_words, spectrum_words, flow_plane_words, support_geometry_words, &
      psd_method_words, n_psd_nodes

   integer, parameter :: dof_w = 1       !! local dof code of the transverse displacement
   integer, parameter :: dof_theta = 2   !! local dof code of the rotation theta = dw/dx
   integer, parameter :: dof_v = 3       !! local dof code of v (second plane, planes = 2)
   integer, parameter :: dof_theta_v = 4 !! local dof code of theta_v = dv/dx (planes = 2)
   !> codes of the built-in laws (their positions in gapbeam_laws' registry; a test checks)
   integer, parameter :: law_bilinear = 1
   integer, parameter :: law_hertz = 2      !! code of the Hertz stop law

   character(len=*), parameter :: stop_side_words = "'positive', 'negative', 'both'"
   character(len=*), parameter :: stop_law_words = "'bilinear', 'hertz'"
   character(len=*), parameter :: damping_words = "'none', 'rayleigh', 'ratios', 'modal'"
   character(len=*), parameter :: stop_shape_words = "'flat', 'circular'"
   !> support conditions of the root (node 1)
   character(len=*), parameter :: end_condition_words = "'clamped', 'spring', 'pinned'"
   !> support conditions of the tip (the last node)
   character(len=*), parameter :: tip_condition_words = "'free', 'clamped', 'spring', 'pinned'"
   !> fluid-elastic force models of &flow
   character(len=*), parameter :: fluid_elastic_words = "'connors', 'none'"
   !> forms of the turbulence spectrum of &turbulence
   character(len=*), parameter :: spectrum_words = "'none', 'table', 'reduced'"
   character(len=*), parameter :: psd_method_words = "'welch', 'periodogram'"
   !> planes a flow force acts in
   character(len=*), parameter :: flow_plane_words = "'both', 'w', 'v'"
   !> the geometry of a support that the wear scar takes (gapbeam_wear_geometry)
   character(len=*), parameter :: support_geometry_words = "'none', 'flat_bar', 'drilled_hole'"
   !> Rotary-inertia rules of the lumped mass matrix (see gapbeam_beam_element).
   character(len=*), parameter :: rotary_inertia_words = "'half_element', 'hrz', 'none'"
   !> Beam theories (see gapbeam_beam_element).
   character(len=*), parameter :: beam_theory_words = "'euler_bernoulli', 'timoshenko'"
   !> Shear coefficient of a rectangular section when the deck gives none [-].
   real(dp), parameter :: rectangle_shear_coefficient = 5.0_dp / 6.0_dp

   !> Uniform beam, Euler-Bernoulli or Timoshenko.
   type :: beam_t
      real(dp) :: length = 0.0_dp          !! length [m]
      integer  :: n_elem = 4               !! number of elements [-]
      real(dp) :: youngs_modulus = 0.0_dp  !! Young's modulus E [Pa]
      real(dp) :: density = 0.0_dp         !! density rho [kg/m^3]
      real(dp) :: width = 0.0_dp           !! rectangular section width b [m] (0: use area etc.)
      real(dp) :: thickness = 0.0_dp       !! rectangular section thickness h [m]
      real(dp) :: area = 0.0_dp            !! general section: area A [m^2]
      real(dp) :: second_moment = 0.0_dp   !! general section: second moment I [m^4]
      real(dp) :: fibre_distance = 0.0_dp  !! general section: strain fibre distance c [m]
      character(len=16) :: mass_matrix = 'lumped'           !! 'lumped' or 'consistent'
      character(len=16) :: rotary_inertia = 'half_element'  !! lumped rotary-inertia rule
      integer  :: planes = 1               !! planes of motion: 1 (w, theta) or 2 (+ v, theta_v)
      !> mass per unit length added to rho A in the mass matrix only (fluid added mass,
      !> contents) [kg/m]
      real(dp) :: added_mass = 0.0_dp
      !> 'euler_bernoulli' or 'timoshenko' (shear deformation and rotary inertia rho I; the
      !> rotation dofs are then the rotations of the cross-section)
      character(len=16) :: theory = 'euler_bernoulli'
      real(dp) :: shear_modulus = 0.0_dp       !! Timoshenko: shear modulus G [Pa]
      !> Timoshenko: shear coefficient k of k G A [-]; 0: 5/6 for a rectangular section (a
      !> general section must give it)
      real(dp) :: shear_coefficient = 0.0_dp
   end type beam_t

   !> End support: the root (node 1; its translation is always fixed) or the tip (last node).
   !> 'clamped': translation and rotation fixed; 'pinned': translation fixed; 'spring':
   !> translation fixed and a rotational spring k_theta; 'free' (tip only): nothing fixed.
   !> With two planes the same condition holds in both.
   type :: root_t
      character(len=16) :: condition = 'clamped'  !! see end_condition_words
      real(dp) :: k_theta = 0.0_dp                !! rotational spring [N m/rad] when 'spring'
   end type root_t

   !> Linear spring from a node dof to ground (the base).
   type :: spring_t
      integer  :: node = 0                 !! node index [-]
      integer  :: dof = dof_w              !! dof_w or dof_theta
      real(dp) :: stiffness = 0.0_dp       !! [N/m] for w, [N m/rad] for theta
   end type spring_t

   !> Point mass and rotary inertia at a node.
   type :: point_mass_t
      integer  :: node = 0                 !! node index [-]
      real(dp) :: mass = 0.0_dp            !! translational mass [kg]
      real(dp) :: inertia = 0.0_dp         !! rotary inertia [kg m^2]
   end type point_mass_t

   !> The linear structure: beam, root, springs and masses.
   type :: structure_t
      type(beam_t) :: beam                            !! the beam
      type(root_t) :: root                            !! root support
      type(root_t) :: tip = root_t(condition='free')  !! tip support ('free' by default)
      type(spring_t), allocatable :: springs(:)       !! boundary springs
      type(point_mass_t), allocatable :: masses(:)    !! point masses
   end type structure_t

   !> A stop as the deck gives it ('both' sides means two one-sided contacts).
   !>
   !> Laws: bilinear f = max(0, k d + c d') while d > 0, else 0 (the damper never pulls);
   !> hertz f = k d^p while d > 0, else 0; d = s u - gap the penetration.
   type :: stop_t
      integer  :: node = -1                     !! node index [-]
      integer  :: dof = dof_w                   !! dof code (dof_w or dof_theta)
      character(len=16) :: side = 'positive'    !! 'positive', 'negative' or 'both'
      character(len=16) :: law = 'bilinear'     !! 'bilinear' or 'hertz'
      real(dp) :: gap = 0.0_dp                  !! clearance [m or rad]
      real(dp) :: stiffness = 0.0_dp            !! k [N/m] (bilinear) or [N/m^p] (hertz)
      real(dp) :: damping = 0.0_dp              !! contact damper c [N s/m] (bilinear only)
      real(dp) :: exponent = 1.5_dp             !! Hertz exponent p [-]
      real(dp) :: rule_factor = 0.0_dp          !! > 0: k = factor * calibrated spring [-]
      real(dp) :: rule_f1_ratio = 0.0_dp        !! rule target: f1 / f1(open structure) [-]
      real(dp) :: rule_f1_hz = 0.0_dp           !! rule target: f1 [Hz] (if ratio not given)
      character(len=16) :: shape = 'flat'       !! 'flat' (one dof) or 'circular' (radial gap)
      real(dp) :: offset_w = 0.0_dp             !! circular: hole centre offset in w [m]
      real(dp) :: offset_v = 0.0_dp             !! circular: hole centre offset in v [m]
      real(dp) :: friction = 0.0_dp             !! Coulomb coefficient mu [-]
      real(dp) :: tangential_stiffness = 0.0_dp !! stick stiffness k_t [N/m] (0: = stiffness)
      real(dp) :: wear_coefficient = 0.0_dp     !! Archard: wear volume / normal work [1/Pa]
      !> the support's geometry for the wear depth: 'none', 'flat_bar' (a flat land of width
      !> land_width along the tube) or 'drilled_hole' (a hole of hole_diameter through a plate
      !> of plate_thickness)
      character(len=16) :: support = 'none'
      real(dp) :: land_width = 0.0_dp           !! flat bar: width of the land along the tube [m]
      real(dp) :: plate_thickness = 0.0_dp      !! drilled hole: plate thickness [m]
      real(dp) :: hole_diameter = 0.0_dp        !! drilled hole: hole diameter [m]
   end type stop_t

   !> Harmonic point force F sin(Omega t + phase) at a node dof, at the forcing frequency.
   type :: point_force_t
      integer  :: node = 0                      !! node index [-]
      integer  :: dof = dof_w                   !! dof code
      real(dp) :: amplitude = 0.0_dp            !! F [N or N m]
      real(dp) :: phase_deg = 0.0_dp            !! phase [deg]
   end type point_force_t

   !> Damping of the linear structure (never the stop springs): Rayleigh C = beta M + gamma K
   !> (after the deck reader only the coefficients matter), and with model = 'modal' the modal
   !> part M Phi diag(2 zeta_j omega_j) Phi' M added to it (mode j of the integrated model,
   !> numbered per plane, ratio modal_ratio(modal_ratios, j)).
   type :: damping_t
      character(len=16) :: model = 'none'          !! 'none', 'rayleigh', 'ratios' or 'modal'
      real(dp) :: mass_coefficient = 0.0_dp        !! beta in C = beta M + gamma K [1/s]
      real(dp) :: stiffness_coefficient = 0.0_dp   !! gamma [s]
      real(dp) :: frequency1_hz = 0.0_dp           !! 'ratios': first frequency [Hz]
      real(dp) :: ratio1 = 0.0_dp                  !! 'ratios': damping ratio at frequency1 [-]
      real(dp) :: frequency2_hz = 0.0_dp           !! 'ratios': second frequency [Hz]
      real(dp) :: ratio2 = 0.0_dp                  !! 'ratios': damping ratio at frequency2 [-]
      !> 'modal': damping ratios of modes 1, 2, ... (the last one for every further mode) [-]
      real(dp), allocatable :: modal_ratios(:)
   end type damping_t

   !> Harmonic base excitation u_b(t) = (amplitude_pp / 2) sin(2 pi f t) along w; with two
   !> planes the motion is (A/2) (cos psi sin(Omega t) e_w + sin psi sin(Omega t + phi) e_v),
   !> psi = direction_deg, phi = phase_v_deg (psi = 45, phi = 90: a circular whirling input),
   !> plus any harmonic point forces at the same frequency.
   type :: forcing_t
      real(dp) :: frequency_hz = 10.0_dp    !! forcing frequency f [Hz]
      real(dp) :: amplitude_pp = 0.0_dp     !! base displacement, peak to peak [m]
      real(dp) :: direction_deg = 0.0_dp    !! direction psi of the base motion from w to v [deg]
      real(dp) :: phase_v_deg = 0.0_dp      !! phase phi of its v component [deg]
      type(point_force_t), allocatable :: forces(:)   !! harmonic point forces
   end type forcing_t

   !> Cross flow over the tube (docs/flow.md): its velocity and fluid, the tube's diameter, and
   !> the fluid-elastic forces as a damping per mode of the open structure (Connors):
   !>    zeta_fe,j = -rho U_e,j^2 / (2 pi K^2 f_j^2 m),
   !> U_e,j the mode's effective velocity, U_e,j^2 = int U(x)^2 phi_j(x)^2 dx / int phi_j^2 dx
   !> (the flow region only in the numerator), m the mass per length with added mass; the mode's
   !> net damping vanishes at Connors' critical velocity U_c = K f D (m delta / (rho D^2))^(1/2).
   type :: flow_t
      real(dp) :: velocity = 0.0_dp            !! U: the reference (gap) velocity [m/s]
      real(dp) :: fluid_density = 0.0_dp       !! rho [kg/m^3]
      real(dp) :: tube_diameter = 0.0_dp       !! D: the tube's outer diameter [m]
      real(dp) :: connors_constant = 3.0_dp    !! K of Connors' relation [-]
      character(len=16) :: fluid_elastic = 'connors'   !! 'connors' or 'none'
      character(len=8) :: planes = 'both'      !! planes of the fluid-elastic forces
      real(dp) :: region_start = 0.0_dp        !! flow region: from x [m]
      real(dp) :: region_end = 0.0_dp          !! ... to x [m] (both 0: the whole tube)
      !> non-uniform flow: U(x) = U f(x), f piecewise linear through these points (x [m], f [-]);
      !> unallocated: f = 1 in the region
      real(dp), allocatable :: profile_position(:)
      real(dp), allocatable :: profile_factor(:)
   end type flow_t

   !> Turbulence buffeting: a random force per unit length q(x, t) over [load_start, load_end]
   !> with a one-sided spectral density S(f) at every x and the coherence exp(-|dx| / lambda_c)
   !> between points, independent between the planes (docs/flow.md, gapbeam_turbulence).
   !> A planar model takes 'both' as w alone.
   type :: turbulence_t
      character(len=16) :: spectrum = 'none'     !! 'none', 'table' or 'reduced'
      real(dp), allocatable :: psd_frequency_hz(:)  !! 'table': frequencies [Hz]
      real(dp), allocatable :: psd(:)            !! 'table': S(f) [(N/m)^2/Hz], log-log between
      !> 'reduced': S(f) = (rho U^2 D / 2)^2 (D / U) Phi(f D / U) with these points of Phi
      real(dp), allocatable :: reduced_frequency(:)   !! f D / U [-]
      real(dp), allocatable :: reduced_psd(:)         !! Phi [-]
      real(dp) :: correlation_length = 0.0_dp    !! lambda_c [m] (0: fully correlated)
      character(len=8) :: planes = 'both'        !! planes loaded
      real(dp) :: load_start = 0.0_dp            !! loaded from x [m]
      real(dp) :: load_end = 0.0_dp              !! ... to x [m] (both 0: the whole tube)
      real(dp) :: cutoff_hz = 0.0_dp             !! highest frequency (0: the spectrum's last)
      real(dp) :: frequency_resolution_hz = 0.0_dp  !! df (0: 1 / the run's length)
      integer :: points_per_cycle = 6            !! record grid points per cycle at the cut-off
      integer :: seed = 1                        !! seed of the random phases
      integer :: draws = 1                       !! independent records per case
      !> add draws until the 95 % half-width of every watched output is below this fraction
      !> of its mean (0: off; docs/flow.md)
      real(dp) :: draws_target_ci = 0.0_dp
      integer :: draws_max = 100                 !! most draws with draws_target_ci
      integer, allocatable :: psd_nodes(:)       !! nodes of the response PSD (none: no PSD)
      character(len=16) :: psd_method = 'welch'  !! 'welch' or 'periodogram'
      real(dp) :: psd_resolution_hz = 0.0_dp     !! Welch bin width (0: 1/4 of the record)
   end type turbulence_t

contains

   !> Number of nodes of the response PSD (&turbulence psd_nodes).
   pure integer function n_psd_nodes(t)
      type(turbulence_t), intent(in) :: t   !! turbulence
      n_psd_nodes = 0
      if (allocated(t%psd_nodes)) n_psd_nodes = size(t%psd_nodes)
   end function n_psd_nodes

   !> Bending stiffness EI [N m^2].
   pure function beam_ei(b) result(ei)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: ei
      if (b%width > 0.0_dp .and. b%thickness > 0.0_dp) then
         ei = b%youngs_modulus * b%width * b%thickness**3 / 12.0_dp
      else
         ei = b%youngs_modulus * b%second_moment
      end if
   end function beam_ei

   !> Mass per unit length rho*A [kg/m].
   pure function beam_rho_a(b) result(rho_a)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: rho_a
      if (b%width > 0.0_dp .and. b%thickness > 0.0_dp) then
         rho_a = b%density * b%width * b%thickness
      else
         rho_a = b%density * b%area
      end if
   end function beam_rho_a

   !> Mass per unit length of the mass matrix: rho A plus the added mass [kg/m].
   pure function beam_mass_per_length(b) result(m)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: m
      m = beam_rho_a(b) + b%added_mass
   end function beam_mass_per_length

   !> Is the beam a Timoshenko beam?
   pure logical function beam_is_timoshenko(b)
      type(beam_t), intent(in) :: b   !! beam
      beam_is_timoshenko = b%theory == 'timoshenko'
   end function beam_is_timoshenko

   !> Rotary inertia per unit length rho I of the section [kg m].
   pure function beam_rho_i(b) result(rho_i)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: rho_i
      if (b%width > 0.0_dp .and. b%thickness > 0.0_dp) then
         rho_i = b%density * b%width * b%thickness**3 / 12.0_dp
      else
         rho_i = b%density * b%second_moment
      end if
   end function beam_rho_i

   !> Shear coefficient k of the Timoshenko beam: the deck's, or 5/6 for a rectangular section
   !> when it gives none (0 for a general section without one) [-].
   pure function beam_shear_coefficient(b) result(k)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: k
      k = b%shear_coefficient
      if (k <= 0.0_dp .and. b%width > 0.0_dp .and. b%thickness > 0.0_dp) &
         k = rectangle_shear_coefficient
   end function beam_shear_coefficient

   !> Shear stiffness k G A of the Timoshenko beam [N].
   pure function beam_shear_stiffness(b) result(kga)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: kga, a
      if (b%width > 0.0_dp .and. b%thickness > 0.0_dp) then
         a = b%width * b%thickness
      else
         a = b%area
      end if
      kga = beam_shear_coefficient(b) * b%shear_modulus * a
   end function beam_shear_stiffness

   !> Does a stop act through the two-dimensional support contact (a circular clearance, or
   !> any stop with friction) rather than as one-sided contacts along one dof?
   pure logical function stop_is_ring(s)
      type(stop_t), intent(in) :: s   !! stop
      stop_is_ring = s%shape == 'circular' .or. s%friction > 0.0_dp
   end function stop_is_ring

   !> Distance of the strain fibre from the neutral axis [m] (h/2 for a rectangle).
   pure function beam_fibre_distance(b) result(c)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: c
      if (b%width > 0.0_dp .and. b%thickness > 0.0_dp) then
         c = 0.5_dp * b%thickness
      else
         c = b%fibre_distance
      end if
   end function beam_fibre_distance

   !> Total beam mass [kg].
   pure function beam_mass(b) result(m)
      type(beam_t), intent(in) :: b   !! beam
      real(dp) :: m
      m = beam_rho_a(b) * b%length
   end function beam_mass

   !> Number of nodes of the mesh.
   pure integer function n_nodes(b)
      type(beam_t), intent(in) :: b   !! beam
      n_nodes = b%n_elem + 1
   end function n_nodes

   !> Forcing angular frequency [rad/s].
   pure real(dp) function forcing_omega(f)
      type(forcing_t), intent(in) :: f   !! forcing
      forcing_omega = 2.0_dp * pi * f%frequency_hz
   end function forcing_omega

   !> Dof code of a word ('w', 'theta', 'v', 'theta_v'); 0 when unknown.
   pure integer function dof_code(word)
      character(len=*), intent(in) :: word   !! 'w', 'theta', 'v' or 'theta_v'
      select case (trim(word))
      case ('w')
         dof_code = dof_w
      case ('theta')
         dof_code = dof_theta
      case ('v')
         dof_code = dof_v
      case ('theta_v')
         dof_code = dof_theta_v
      case default
         dof_code = 0
      end select
   end function dof_code

   !> Word of a dof code.
   pure function dof_name(code) result(word)
      integer, intent(in) :: code   !! dof code
      character(len=:), allocatable :: word
      select case (code)
      case (dof_theta)
         word = 'theta'
      case (dof_v)
         word = 'v'
      case (dof_theta_v)
         word = 'theta_v'
      case default
         word = 'w'
      end select
   end function dof_name

   !> Law code of a word (its position in the law registry, gapbeam_laws); 0 if unknown.
   integer function law_code(word)
      character(len=*), intent(in) :: word   !! a law's name
      law_code = law_index(word)
   end function law_code

   !> Coefficients (beta, gamma) with zeta(f) = beta/(2 omega) + gamma omega/2 through two pairs.
   pure subroutine rayleigh_from_ratios(f1, z1, f2, z2, beta, gamma)
      real(dp), intent(in) :: f1, z1, f2, z2   !! frequencies [Hz] and ratios [-]
      real(dp), intent(out) :: beta            !! mass coefficient [1/s]
      real(dp), intent(out) :: gamma           !! stiffness coefficient [s]
      real(dp) :: w1, w2
      w1 = 2.0_dp * pi * f1;  w2 = 2.0_dp * pi * f2
      beta = 2.0_dp * w1 * w2 * (z1 * w2 - z2 * w1) / (w2**2 - w1**2)
      gamma = 2.0_dp * (z2 * w2 - z1 * w1) / (w2**2 - w1**2)
   end subroutine rayleigh_from_ratios

   !> Damping ratio of mode j (1, 2, ...) from a list of modal ratios: the j-th, or the last one
   !> for every mode beyond the list; 0 for an empty or absent list [-].
   pure function modal_ratio(ratios, j) result(zeta)
      real(dp), allocatable, intent(in) :: ratios(:)  !! the deck's modal_ratios
      integer, intent(in) :: j                        !! mode number (>= 1)
      real(dp) :: zeta
      zeta = 0.0_dp
      if (.not. allocated(ratios)) return
      if (size(ratios) == 0) return
      zeta = ratios(min(j, size(ratios)))
   end function modal_ratio

   !> Modal damping ratio of Rayleigh damping at a frequency [-].
   elemental function modal_damping_ratio(beta, gamma, f_hz) result(zeta)
      real(dp), intent(in) :: beta    !! mass coefficient [1/s]
      real(dp), intent(in) :: gamma   !! stiffness coefficient [s]
      real(dp), intent(in) :: f_hz    !! frequency [Hz]
      real(dp) :: zeta, w
      w = 2.0_dp * pi * f_hz
      zeta = beta / (2.0_dp * w) + gamma * w / 2.0_dp
   end function modal_damping_ratio

   !> Per plane (w, v): whether the structure has a rigid mode (the rotation about a pinned
   !> root with a free tip and no spring in the plane) and whether a stop holds it.
   pure subroutine rigid_planes(st, stops, rigid, held)
      type(structure_t), intent(in) :: st                  !! structure
      type(stop_t), intent(in) :: stops(:)                 !! stops
      logical, intent(out) :: rigid(2)                     !! a rigid mode in w, in v
      logical, intent(out) :: held(2)                      !! a stop holds it
      integer :: i
      rigid = .false.;  held = .false.
      if (st%root%condition /= 'pinned' .or. st%tip%condition /= 'free') return
      rigid(1) = .true.
      rigid(2) = st%beam%planes > 1
      do i = 1, size(st%springs)
         if (any(st%springs(i)%dof == [dof_w, dof_theta])) rigid(1) = .false.
         if (any(st%springs(i)%dof == [dof_v, dof_theta_v])) rigid(2) = .false.
      end do
      do i = 1, size(stops)
         associate (s => stops(i))
            if (s%shape == 'circular') then
               if (s%node > 1) held = .true.
            else if (s%dof == dof_w .and. s%node > 1 .or. s%dof == dof_theta) then
               held(1) = .true.
            else if (s%dof == dof_v .and. s%node > 1 .or. s%dof == dof_theta_v) then
               held(2) = .true.
            end if
         end associate
      end do
   end subroutine rigid_planes
end module gapbeam_description
