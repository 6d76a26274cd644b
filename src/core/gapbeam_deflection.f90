!> The deflected shape of the beam between the nodes, from the nodal values with the cubic
!> Hermite shape functions of the element (the shape the finite element model assumes), for
!> output: mode shapes drawn as the model sees them, the beam in motion.
!>
!> On element e (nodes e and e+1, length le, xi = (x - x_e)/le in [0, 1]):
!>    w(xi) = N1 w_e + N2 theta_e + N3 w_e+1 + N4 theta_e+1
!>    N1 = 1 - 3 xi^2 + 2 xi^3,  N2 = le (xi - 2 xi^2 + xi^3),
!>    N3 = 3 xi^2 - 2 xi^3,      N4 = le (xi^3 - xi^2).
!> For a Timoshenko beam (sys%shear_phi = phi > 0, theta the section rotation) the element's own
!> interdependent shape functions (gapbeam_beam_element:timoshenko_shapes):
!>    N1 = (1 - 3 xi^2 + 2 xi^3 + phi (1 - xi))/(1 + phi),
!>    N2 = le (xi - 2 xi^2 + xi^3 + phi (xi - xi^2)/2)/(1 + phi),
!>    N3 = (3 xi^2 - 2 xi^3 + phi xi)/(1 + phi),
!>    N4 = le (xi^3 - xi^2 - phi (xi - xi^2)/2)/(1 + phi).
!> A fixed dof (dof_of = 0) is zero. Points: x = 0, then `per_element` points on each element
!> ending at its right node, so the nodes are among them: n = n_elem * per_element + 1. The
!> second plane of a two-plane model (v, theta_v = dv/dx) the same way (`plane = 2`). The
!> modes as tables, x and w of each mode, at the nodes and on the curve between them.
module gapbeam_deflection
   use gapbeam_kinds, only: dp
   use gapbeam_model, only: system_t
   use gapbeam_results, only: modes_t
   use gapbeam_description, only: dof_w, dof_theta, dof_v, dof_theta_v
   implicit none
   private
   public :: shape_points, deflection, nodal_values, mode_shape_table, shape_curve_table

contains

   !> The x of the shape points [m].
   pure function shape_points(sys, per_element) result(x)
      type(system_t), intent(in) :: sys              !! assembled structure (n_node nodes)
      integer, intent(in) :: per_element            !! points per element (>= 1)
      real(dp), allocatable :: x(:)
      integer :: e, k, n_elem
      n_elem = sys%n_node - 1
      allocate(x(n_elem * per_element + 1))
      x(1) = 0.0_dp
      do e = 1, n_elem
         do k = 1, per_element
            x(1 + (e - 1) * per_element + k) = sys%element_length &
               * (real(e - 1, dp) + real(k, dp) / real(per_element, dp))
         end do
      end do
   end function shape_points

   !> w (or, with plane = 2, v) at the shape points for the dof vector u [m].
   pure function deflection(sys, u, per_element, plane) result(w)
      type(system_t), intent(in) :: sys              !! assembled structure
      real(dp), intent(in) :: u(:)                   !! dof values (w in m, theta in rad)
      integer, intent(in) :: per_element            !! points per element (>= 1)
      integer, intent(in), optional :: plane         !! 1 (w, default) or 2 (v)
      real(dp), allocatable :: w(:)
      real(dp) :: we(2), te(2), xi, le, phi, s
      integer :: e, k, n_elem, dw, dt
      dw = dof_w;  dt = dof_theta
      if (present(plane)) then
         if (plane == 2) then
            dw = dof_v;  dt = dof_theta_v
         end if
      end if
      n_elem = sys%n_node - 1
      le = sys%element_length
      allocate(w(n_elem * per_element + 1))
      w(1) = value_of(sys, u, dw, 1)
      do e = 1, n_elem
         we = [value_of(sys, u, dw, e), value_of(sys, u, dw, e + 1)]
         te = [value_of(sys, u, dt, e), value_of(sys, u, dt, e + 1)]
         do k = 1, per_element
            xi = real(k, dp) / real(per_element, dp)
            w(1 + (e - 1) * per_element + k) = (1.0_dp - 3.0_dp * xi**2 + 2.0_dp * xi**3) * we(1) &
               + le * (xi - 2.0_dp * xi**2 + xi**3) * te(1) &
               + (3.0_dp * xi**2 - 2.0_dp * xi**3) * we(2) + le * (xi**3 - xi**2) * te(2)
            if (sys%shear_phi > 0.0_dp) then
               phi = sys%shear_phi;  s = 1.0_dp / (1.0_dp + phi)
               w(1 + (e - 1) * per_element + k) = s * ((1 - 3 * xi**2 + 2 * xi**3 &
                  + phi * (1 - xi)) * we(1) + le * (xi - 2 * xi**2 + xi**3 + 0.5_dp * phi &
                  * (xi - xi**2)) * te(1) + (3 * xi**2 - 2 * xi**3 + phi * xi) * we(2) &
                  + le * (xi**3 - xi**2 - 0.5_dp * phi * (xi - xi**2)) * te(2))
            end if
         end do
      end do
   end function deflection

   !> w and theta at every node (0 where the dof is fixed).
   pure subroutine nodal_values(sys, u, w, theta)
      type(system_t), intent(in) :: sys              !! assembled structure
      real(dp), intent(in) :: u(:)                   !! dof values
      real(dp), intent(out) :: w(:), theta(:)        !! (n_node) [m], [rad]
      integer :: i
      do i = 1, sys%n_node
         w(i) = value_of(sys, u, dof_w, i)
         theta(i) = value_of(sys, u, dof_theta, i)
      end do
   end subroutine nodal_values

   !> Node x and w of each mode at the nodes (root w = 0): (n_node, 1 + n_modes).
   pure function mode_shape_table(sys, modes) result(tab)
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

   !> x and w of each mode between the nodes, from the element's Hermite shape functions:
   !> (n_points, 1 + n_modes).
   pure function shape_curve_table(sys, modes, per_element) result(tab)
      type(system_t), intent(in) :: sys      !! assembled structure
      type(modes_t), intent(in) :: modes     !! modes
      integer, intent(in) :: per_element     !! points per element
      real(dp), allocatable :: tab(:, :)
      real(dp), allocatable :: x(:)
      integer :: j
      x = shape_points(sys, per_element)
      allocate(tab(size(x), 1 + modes%n_modes))
      tab(:, 1) = x
      do j = 1, modes%n_modes
         tab(:, 1 + j) = deflection(sys, modes%shapes(:, j), per_element)
      end do
   end function shape_curve_table

   pure real(dp) function value_of(sys, u, dof, node)
      type(system_t), intent(in) :: sys
      real(dp), intent(in) :: u(:)
      integer, intent(in) :: dof, node
      integer :: g
      value_of = 0.0_dp
      if (dof > size(sys%dof_of, 1)) return        ! v of a one-plane model
      g = sys%dof_of(dof, node)
      if (g > 0) value_of = u(g)
   end function value_of
end module gapbeam_deflection
