!> What a deck says about the structure: beam, root, boundary springs and point masses.
!>
!> SI units throughout. The beam lies along x from the root (node 1, x = 0) to the tip
!> (node n_elem+1, x = length); w is the transverse displacement relative to the base,
!> theta = dw/dx. Nodes are numbered 1..n_elem+1 from the root.
module gapbeam_model
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: beam_t, root_t, spring_t, point_mass_t, structure_t
   public :: beam_ei, beam_rho_a, beam_fibre_distance, beam_mass, n_nodes
   public :: dof_w, dof_theta, dof_code, dof_name

   integer, parameter :: dof_w = 1       !! local dof code of the transverse displacement
   integer, parameter :: dof_theta = 2   !! local dof code of the rotation

   !> Uniform Euler-Bernoulli beam.
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
   end type beam_t

   !> Root (node 1) support: the translation is always fixed.
   type :: root_t
      character(len=16) :: condition = 'clamped'  !! 'clamped' or 'spring'
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
      type(spring_t), allocatable :: springs(:)       !! boundary springs
      type(point_mass_t), allocatable :: masses(:)    !! point masses
   end type structure_t

contains

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

   !> Dof code of a word ('w' or 'theta'); 0 when unknown.
   pure integer function dof_code(word)
      character(len=*), intent(in) :: word   !! 'w' or 'theta'
      select case (trim(word))
      case ('w')
         dof_code = dof_w
      case ('theta')
         dof_code = dof_theta
      case default
         dof_code = 0
      end select
   end function dof_code

   !> Word of a dof code.
   pure function dof_name(code) result(word)
      integer, intent(in) :: code   !! dof_w or dof_theta
      character(len=:), allocatable :: word
      if (code == dof_theta) then
         word = 'theta'
      else
         word = 'w'
      end if
   end function dof_name
end module gapbeam_model
