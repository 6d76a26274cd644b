!> Two-node beam elements: Euler-Bernoulli (Hermite cubics) and Timoshenko (interdependent
!> interpolation).
!>
!> Local dofs are (w1, theta1, w2, theta2): w is the transverse displacement [m], theta the
!> rotation [rad], x runs from node 1 to node 2. For Euler-Bernoulli theta = dw/dx; for
!> Timoshenko theta is the rotation psi of the cross-section, and the shear strain is
!> dw/dx - psi. All procedures are pure: everything comes through the arguments.
!>
!> The Timoshenko element is the two-node element with interdependent interpolation (Reddy 1997;
!> the same matrices as Friedman and Kosmatka 1993, and Przemieniecki's stiffness): w cubic and
!> psi quadratic, tied by the element's homogeneous static equations, so that the shear strain is
!> constant and exact. It has no shear locking (its stiffness tends to the Euler-Bernoulli matrix
!> as phi = 12 EI/(k G A le^2) -> 0) and is exact for static loads at the nodes.
module gapbeam_beam_element
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: beam_stiffness, beam_consistent_mass, beam_lumped_mass, beam_curvature_row

   public :: timoshenko_phi, timoshenko_stiffness, timoshenko_shapes, timoshenko_consistent_mass, &
      timoshenko_lumped_mass

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
   !> Shear parameter phi = 12 EI / (k G A le^2) of a Timoshenko element [-].
   pure function timoshenko_phi(ei, kga, le) result(phi)
      real(dp), intent(in) :: ei    !! bending stiffness [N m^2]
      real(dp), intent(in) :: kga   !! shear stiffness k G A [N]
      real(dp), intent(in) :: le    !! element length [m]
      real(dp) :: phi
      phi = 12.0_dp * ei / (kga * le**2)
   end function timoshenko_phi

   !> Stiffness of the two-node Timoshenko element with interdependent interpolation
   !> [N/m, N, N m]; phi = 0 is the Euler-Bernoulli matrix.
   pure function timoshenko_stiffness(ei, phi, le) result(ke)
      real(dp), intent(in) :: ei    !! bending stiffness [N m^2]
      real(dp), intent(in) :: phi   !! shear parameter 12 EI / (k G A le^2) [-]
      real(dp), intent(in) :: le    !! element length [m]
      real(dp) :: ke(4, 4)
      ke = ei / ((1.0_dp + phi) * le**3) * reshape( &
         [ 12.0_dp,  6*le,                -12.0_dp,  6*le,                &
            6*le,     (4 + phi) * le**2,  -6*le,     (2 - phi) * le**2,   &
          -12.0_dp, -6*le,                 12.0_dp, -6*le,                &
            6*le,     (2 - phi) * le**2,  -6*le,     (4 + phi) * le**2], [4, 4])
   end function timoshenko_stiffness

   !> Shape functions of the interdependent-interpolation element at xi = x/le: w = dot(n, u_e),
   !> psi = dot(p, u_e) (psi the section rotation), psi' = dot(dp, u_e) [-, m, 1/m, ...].
   !> They solve the static equations of the element exactly (constant shear force), so the
   !> element is exact for loads at its nodes; phi = 0 gives the Hermite cubics and psi = w'.
   pure subroutine timoshenko_shapes(le, phi, xi, n, p, dpsi)
      real(dp), intent(in) :: le        !! element length [m]
      real(dp), intent(in) :: phi       !! shear parameter [-]
      real(dp), intent(in) :: xi        !! position, 0 at node 1, 1 at node 2 [-]
      real(dp), intent(out) :: n(4)     !! w shape functions [-, m, -, m]
      real(dp), intent(out) :: p(4)     !! psi shape functions [1/m, -, 1/m, -]
      real(dp), intent(out) :: dpsi(4)  !! d psi / dx [1/m^2, 1/m, 1/m^2, 1/m]
      real(dp) :: s
      s = 1.0_dp / (1.0_dp + phi)
      n = s * [1 - 3 * xi**2 + 2 * xi**3 + phi * (1 - xi), &
               le * (xi - 2 * xi**2 + xi**3 + 0.5_dp * phi * (xi - xi**2)), &
               3 * xi**2 - 2 * xi**3 + phi * xi, &
               le * (-xi**2 + xi**3 - 0.5_dp * phi * (xi - xi**2))]
      p = s * [6 * (xi**2 - xi) / le, &
               1 - 4 * xi + 3 * xi**2 + phi * (1 - xi), &
               6 * (xi - xi**2) / le, &
               -2 * xi + 3 * xi**2 + phi * xi]
      dpsi = s * [6 * (2 * xi - 1) / le**2, (-4 + 6 * xi - phi) / le, &
                  6 * (1 - 2 * xi) / le**2, (-2 + 6 * xi + phi) / le]
   end subroutine timoshenko_shapes

   !> Consistent mass of the Timoshenko element, rho A int n'n dx + rho I int p'p dx
   !> (translational and rotary inertia), by 4-point Gauss-Legendre quadrature, exact for the
   !> degree-6 integrands [kg, kg m, kg m^2].
   pure function timoshenko_consistent_mass(rho_a, rho_i, phi, le) result(me)
      real(dp), intent(in) :: rho_a   !! mass per unit length [kg/m]
      real(dp), intent(in) :: rho_i   !! rotary inertia per unit length rho I [kg m]
      real(dp), intent(in) :: phi     !! shear parameter [-]
      real(dp), intent(in) :: le      !! element length [m]
      real(dp) :: me(4, 4)
      real(dp), parameter :: a = 0.33998104358485626480_dp, b = 0.86113631159405257522_dp
      real(dp), parameter :: wa = 0.65214515486254614263_dp, wb = 0.34785484513745385737_dp
      real(dp), parameter :: x(4) = [-b, -a, a, b], w(4) = [wb, wa, wa, wb]
      real(dp) :: n(4), p(4), d(4)
      integer :: q, i, j
      me = 0.0_dp
      do q = 1, 4
         call timoshenko_shapes(le, phi, 0.5_dp * (1.0_dp + x(q)), n, p, d)
         do j = 1, 4
            do i = 1, 4
               me(i, j) = me(i, j) + 0.5_dp * le * w(q) * (rho_a * n(i) * n(j) &
                                                            + rho_i * p(i) * p(j))
            end do
         end do
      end do
      me = 0.5_dp * (me + transpose(me))
   end function timoshenko_consistent_mass

   !> Lumped mass of the Timoshenko element: rho A le/2 per end node; on each rotation the
   !> rotary inertia of the half element's sections, rho I le/2, plus the lumped rule's term of
   !> the Euler-Bernoulli element (rotary_inertia_coefficient), so that 'none' gives the
   !> textbook lumped Timoshenko element [kg, kg m^2].
   pure function timoshenko_lumped_mass(rho_a, rho_i, le, rule) result(md)
      real(dp), intent(in) :: rho_a           !! mass per unit length [kg/m]
      real(dp), intent(in) :: rho_i           !! rotary inertia per unit length rho I [kg m]
      real(dp), intent(in) :: le              !! element length [m]
      character(len=*), intent(in) :: rule    !! rotary-inertia rule, see rotary_inertia_coefficient
      real(dp) :: md(4)                       !! diagonal (w1, psi1, w2, psi2)
      real(dp) :: m, j
      m = rho_a * le
      j = 0.5_dp * rho_i * le + max(0.0_dp, rotary_inertia_coefficient(rule)) * m * le**2
      md = [0.5_dp * m, j, 0.5_dp * m, j]
   end function timoshenko_lumped_mass
end module gapbeam_beam_element
