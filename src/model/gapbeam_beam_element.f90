!> Euler-Bernoulli two-node Hermite beam element.
!>
!> Local dofs are (w1, theta1, w2, theta2): w is the transverse displacement [m], theta = dw/dx
!> the rotation [rad], x runs from node 1 to node 2. All procedures are pure: everything comes
!> through the arguments.
module gapbeam_beam_element
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: beam_stiffness, beam_consistent_mass, beam_lumped_mass, beam_curvature_row
   public :: rotary_inertia_coefficient

contains

   !> Element stiffness matrix [N/m, N, N m].
   pure function beam_stiffness(ei, le) result(ke)
      real(dp), intent(in) :: ei   !! bending stiffness [N m^2]
      real(dp), intent(in) :: le   !! element length [m]
      real(dp) :: ke(4, 4)
      ! symmetric, so reshape's column-major fill order does not matter
      ke = ei / le**3 * reshape([ 12.0_dp,  6*le,     -12.0_dp,  6*le,     &
                                   6*le,     4*le**2,  -6*le,     2*le**2, &
                                 -12.0_dp, -6*le,      12.0_dp, -6*le,     &
                                   6*le,     2*le**2,  -6*le,     4*le**2], [4, 4])
   end function beam_stiffness

   !> Consistent mass matrix of the Hermite cubic element [kg, kg m, kg m^2].
   pure function beam_consistent_mass(rho_a, le) result(me)
      real(dp), intent(in) :: rho_a   !! mass per unit length [kg/m]
      real(dp), intent(in) :: le      !! element length [m]
      real(dp) :: me(4, 4)
      me = rho_a * le / 420.0_dp * reshape( &
         [ 156.0_dp,  22*le,      54.0_dp,  -13*le,     &
            22*le,     4*le**2,   13*le,     -3*le**2,  &
            54.0_dp,   13*le,    156.0_dp,  -22*le,     &
           -13*le,    -3*le**2,  -22*le,      4*le**2], [4, 4])
   end function beam_consistent_mass

   !> Rotary inertia lumped at each end, as a multiple of (rho_a*le)*le**2.
   !>
   !> 'half_element': the half element as a rigid bar rotating about its node,
   !>                 (m/2)(le/2)^2/3 = m le^2/24;
   !> 'hrz': diagonal of the consistent matrix scaled to the element mass (Hinton-Rock-Zienkiewicz),
   !>        m le^2/78; 'none': zero (rotations are then massless).
   !> Returns a negative value for an unknown word.
   pure function rotary_inertia_coefficient(rule) result(c)
      character(len=*), intent(in) :: rule   !! rotary-inertia rule
      real(dp) :: c
      select case (rule)
      case ('half_element')
         c = 1.0_dp / 24.0_dp
      case ('hrz')
         c = 1.0_dp / 78.0_dp
      case ('none')
         c = 0.0_dp
      case default
         c = -1.0_dp
      end select
   end function rotary_inertia_coefficient

   !> Lumped (diagonal) mass: rho_a*le/2 per end node, rotary inertia per `rule` [kg, kg m^2].
   pure function beam_lumped_mass(rho_a, le, rule) result(md)
      real(dp), intent(in) :: rho_a           !! mass per unit length [kg/m]
      real(dp), intent(in) :: le              !! element length [m]
      character(len=*), intent(in) :: rule    !! rotary-inertia rule, see rotary_inertia_coefficient
      real(dp) :: md(4)                       !! diagonal (w1, theta1, w2, theta2)
      real(dp) :: m, j
      m = rho_a * le
      j = max(0.0_dp, rotary_inertia_coefficient(rule)) * m * le**2
      md = [0.5_dp * m, j, 0.5_dp * m, j]
   end function beam_lumped_mass

   !> Row b such that the curvature w''(x) = dot_product(b, u_e) at x = xi*le [1/m per dof unit].
   pure function beam_curvature_row(le, xi) result(b)
      real(dp), intent(in) :: le   !! element length [m]
      real(dp), intent(in) :: xi   !! position along the element, 0 at node 1, 1 at node 2 [-]
      real(dp) :: b(4)
      b = [(-6.0_dp + 12.0_dp * xi) / le**2, (-4.0_dp + 6.0_dp * xi) / le, &
           ( 6.0_dp - 12.0_dp * xi) / le**2, (-2.0_dp + 6.0_dp * xi) / le]
   end function beam_curvature_row
end module gapbeam_beam_element
