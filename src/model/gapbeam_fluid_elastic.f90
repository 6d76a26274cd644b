!> Fluid-elastic forces of cross flow as a damping per mode of the open structure (Connors).
!>
!> Connors' relation gives the critical velocity of a mode of frequency f_j and logarithmic
!> decrement delta_j = 2 pi zeta_s,j (zeta_s,j its structural damping ratio, Rayleigh and modal):
!>    U_c = K f_j D (m delta_j / (rho D^2))^(1/2),
!> m the mass per unit length with the added mass, rho the fluid density, D the tube diameter,
!> K Connors' constant. In a time simulation the fluid feeds energy into the mode as a negative
!> damping ratio that grows with U^2 and cancels the structural damping at U_c:
!>    zeta_fe,j = -rho U_e,j^2 / (2 pi K^2 f_j^2 m),   zeta_net,j = zeta_s,j (1 - U^2 / U_c,j^2).
!> Partial or non-uniform flow: the mode's effective velocity is the mode-shape-squared
!> weighted mean of U(x)^2 (Pettigrew & Taylor's effective velocity, uniform m and rho),
!>    U_e,j^2 = int_flow U(x)^2 phi_j(x)^2 dx / int_0^L phi_j(x)^2 dx,
!> U(x) = U f(x) over [region_start, region_end] (f piecewise linear through the profile
!> points, 1 without a profile), zero elsewhere; so U_c,j above is the reference velocity U at
!> which mode j's net damping vanishes, U_c / (U_e,j / U). The integrals use the cubic Hermite
!> interpolation of the mode's translations between the nodes, 5-point Gauss-Legendre on each
!> element piece (exact: the integrand is a polynomial of degree 8 at most).
!>
!> As damping, C_fe = M Phi diag(2 zeta_fe,j omega_j) Phi' M over every mode of the open
!> structure (Phi' M Phi = I): each mode gets exactly zeta_fe,j, and the planes are solved apart
!> (the dofs of w and v are not coupled in K and M), so a mode lies in one plane. A reduced
!> model takes B' C_fe B (its kept modes then get their own zeta_fe exactly).
module gapbeam_fluid_elastic
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_description, only: flow_t, dof_w, dof_theta, dof_v, dof_theta_v
   use gapbeam_model, only: system_t
   use gapbeam_results, only: modes_t
   use gapbeam_flow_results, only: flow_modes_t
   use gapbeam_eigen, only: solve_modes
   use gapbeam_linalg, only: dense_to_band
   use gapbeam_turbulence, only: gauss_legendre, hermite_at
   implicit none
   private
   public :: connors_velocity, fluid_elastic_ratio, velocity_ratio, flow_modes, &
      fluid_elastic_damping, plane_modes, profile_factor

contains

   !> Connors' critical velocity K f D (m delta / (rho D^2))^(1/2) [m/s].
   elemental real(dp) function connors_velocity(k, f, d, m, delta, rho) result(u)
      real(dp), intent(in) :: k       !! Connors' constant [-]
      real(dp), intent(in) :: f       !! natural frequency [Hz]
      real(dp), intent(in) :: d       !! tube diameter [m]
      real(dp), intent(in) :: m       !! mass per length with added mass [kg/m]
      real(dp), intent(in) :: delta   !! logarithmic decrement [-]
      real(dp), intent(in) :: rho     !! fluid density [kg/m^3]
      u = k * f * d * sqrt(m * max(delta, 0.0_dp) / (rho * d * d))
   end function connors_velocity

   !> The fluid-elastic damping ratio -rho U_e^2 / (2 pi K^2 f^2 m) [-].
   elemental real(dp) function fluid_elastic_ratio(rho, u_e, k, f, m) result(z)
      real(dp), intent(in) :: rho     !! fluid density [kg/m^3]
      real(dp), intent(in) :: u_e     !! the mode's effective velocity [m/s]
      real(dp), intent(in) :: k       !! Connors' constant [-]
      real(dp), intent(in) :: f       !! natural frequency [Hz]
      real(dp), intent(in) :: m       !! mass per length with added mass [kg/m]
      z = -rho * u_e**2 / (2.0_dp * pi * k**2 * f**2 * m)
   end function fluid_elastic_ratio

   !> The flow profile f(x) = U(x) / U: 0 outside the flow region, piecewise linear through the
   !> profile points inside (held constant beyond the first and the last), 1 without points.
   pure real(dp) function profile_factor(fl, length, x) result(f)
      type(flow_t), intent(in) :: fl          !! flow
      real(dp), intent(in) :: length          !! tube length [m]
      real(dp), intent(in) :: x               !! position [m]
      real(dp) :: a, b, r
      integer :: i, n
      call flow_region(fl, length, a, b)
      f = 0.0_dp
      if (x < a .or. x > b) return
      f = 1.0_dp
      if (.not. allocated(fl%profile_position)) return
      n = size(fl%profile_position)
      if (n == 0) return
      if (x <= fl%profile_position(1)) then
         f = fl%profile_factor(1)
      else if (x >= fl%profile_position(n)) then
         f = fl%profile_factor(n)
      else
         i = 1
         do while (x > fl%profile_position(i + 1))
            i = i + 1
         end do
         r = (x - fl%profile_position(i)) / (fl%profile_position(i + 1) - fl%profile_position(i))
         f = (1.0_dp - r) * fl%profile_factor(i) + r * fl%profile_factor(i + 1)
      end if
   end function profile_factor

   !> The flow region [a, b] (the whole tube when the deck gives none).
   pure subroutine flow_region(fl, length, a, b)
      type(flow_t), intent(in) :: fl          !! flow
      real(dp), intent(in) :: length          !! tube length [m]
      real(dp), intent(out) :: a, b           !! region [m]
      a = fl%region_start;  b = fl%region_end
      if (a == 0.0_dp .and. b == 0.0_dp) b = length
   end subroutine flow_region

   !> U_e^2 / U^2 of a mode shape in one plane (see the module header) [-].
   pure real(dp) function velocity_ratio(sys, fl, plane, phi) result(ratio)
      type(system_t), intent(in) :: sys       !! assembled structure
      type(flow_t), intent(in) :: fl          !! flow
      integer, intent(in) :: plane            !! 1 (w) or 2 (v)
      real(dp), intent(in) :: phi(:)          !! mode shape (n_dof)
      real(dp) :: xg(5), wg(5), length, a, b, x, w, y, top, bottom, fx
      real(dp), allocatable :: cuts(:)
      integer :: e, i, q, idx(4)
      real(dp) :: nv(4)
      call gauss_legendre(5, xg, wg)
      length = sys%element_length * real(sys%n_node - 1, dp)
      call flow_region(fl, length, a, b)
      ! breakpoints: the nodes, the region's ends and the profile points
      cuts = [(sys%element_length * real(e, dp), e = 0, sys%n_node - 1), a, b]
      if (allocated(fl%profile_position)) cuts = [cuts, fl%profile_position]
      cuts = sorted_unique(pack(cuts, cuts >= 0.0_dp .and. cuts <= length))
      top = 0.0_dp;  bottom = 0.0_dp
      do i = 1, size(cuts) - 1
         do q = 1, 5
            x = cuts(i) + xg(q) * (cuts(i + 1) - cuts(i))
            w = wg(q) * (cuts(i + 1) - cuts(i))
            call hermite_at(sys, plane, x, idx, nv)
            y = 0.0_dp
            do e = 1, 4
               if (idx(e) > 0) y = y + nv(e) * phi(idx(e))
            end do
            fx = profile_factor(fl, length, x)
            top = top + w * fx**2 * y**2
            bottom = bottom + w * y**2
         end do
      end do
      ratio = 0.0_dp
      if (bottom > 0.0_dp) ratio = top / bottom
   end function velocity_ratio

   !> Ascending, without repeats.
   pure function sorted_unique(x) result(y)
      real(dp), intent(in) :: x(:)            !! values
      real(dp), allocatable :: y(:)
      real(dp) :: t(size(x)), s
      integer :: i, j, n
      t = x
      do i = 2, size(t)
         s = t(i);  j = i - 1
         do while (j >= 1)
            if (t(j) <= s) exit
            t(j + 1) = t(j);  j = j - 1
         end do
         t(j + 1) = s
      end do
      n = 0
      allocate(y(size(t)))
      do i = 1, size(t)
         if (n > 0) then
            if (t(i) <= y(n)) cycle
         end if
         n = n + 1;  y(n) = t(i)
      end do
      y = y(1:n)
   end function sorted_unique

   !> The modes of one plane of a structure (the plane's dofs alone: K and M do not couple the
   !> planes), as full-length shapes (zero in the other plane).
   subroutine plane_modes(sys, plane, modes, err)
      type(system_t), intent(in) :: sys               !! assembled structure
      integer, intent(in) :: plane                    !! 1 (w) or 2 (v)
      type(modes_t), intent(out) :: modes             !! the plane's modes, full-length shapes
      type(error_t), allocatable, intent(out) :: err  !! eigen failure
      type(system_t) :: ps
      type(modes_t) :: pm
      integer, allocatable :: dofs(:)
      integer :: dw, dt
      if (sys%planes == 1) then
         call solve_modes(sys, modes, err)
         return
      end if
      dw = merge(dof_w, dof_v, plane == 1);  dt = merge(dof_theta, dof_theta_v, plane == 1)
      dofs = pack([sys%dof_of(dw, :), sys%dof_of(dt, :)], &
                  [sys%dof_of(dw, :), sys%dof_of(dt, :)] > 0)
      dofs = sorted_int(dofs)
      ps%n_dof = size(dofs);  ps%n_node = sys%n_node;  ps%kd = sys%kd;  ps%planes = 1
      ps%k = sys%k(dofs, dofs);  ps%m = sys%m(dofs, dofs)
      call dense_to_band(ps%k, ps%kd, ps%k_band)
      call dense_to_band(ps%m, ps%kd, ps%m_band)
      ps%m_diagonal = sys%m_diagonal
      if (plane == 1) then
         ps%r = sys%r(dofs)
      else
         ps%r = sys%r_v(dofs)
      end if
      ps%tip_dof = 0
      if (plane == 1 .and. sys%tip_dof > 0) ps%tip_dof = findloc(dofs, sys%tip_dof, 1)
      if (plane == 2 .and. sys%tip_dof_v > 0) ps%tip_dof = findloc(dofs, sys%tip_dof_v, 1)
      call solve_modes(ps, pm, err)
      if (allocated(err)) return
      modes = pm
      deallocate(modes%shapes)
      allocate(modes%shapes(sys%n_dof, pm%n_modes), source=0.0_dp)
      modes%shapes(dofs, :) = pm%shapes
   end subroutine plane_modes

   pure function sorted_int(x) result(y)
      integer, intent(in) :: x(:)
      integer :: y(size(x)), i, j, s
      y = x
      do i = 2, size(y)
         s = y(i);  j = i - 1
         do while (j >= 1)
            if (y(j) <= s) exit
            y(j + 1) = y(j);  j = j - 1
         end do
         y(j + 1) = s
      end do
   end function sorted_int

   !> The modes of the open structure with their fluid-elastic data at the flow's velocity:
   !> `zeta_s(f)` gives the structural damping ratio at a frequency (Rayleigh), `modal` adds a
   !> ratio per mode number of its plane (modal damping; absent: none).
   subroutine flow_modes(sys, fl, m_per_length, beta, gamma, fm, err, modal)
      type(system_t), intent(in) :: sys               !! assembled structure (open)
      type(flow_t), intent(in) :: fl                  !! flow
      real(dp), intent(in) :: m_per_length            !! m with added mass [kg/m]
      real(dp), intent(in) :: beta, gamma             !! Rayleigh coefficients [1/s], [s]
      type(flow_modes_t), intent(out) :: fm           !! modes with their fluid-elastic data
      type(error_t), allocatable, intent(out) :: err  !! eigen failure
      real(dp), intent(in), optional :: modal(:)      !! modal ratio of mode j of each plane
      type(modes_t) :: pm(2)
      integer :: p, np, j, n, i1, i2, k, jj
      logical :: acts(2)
      real(dp) :: w
      np = sys%planes
      do p = 1, np
         call plane_modes(sys, p, pm(p), err)
         if (allocated(err)) return
      end do
      n = sum([(pm(p)%n_modes, p = 1, np)])
      fm%n_modes = n
      allocate(fm%frequency_hz(n), fm%plane(n), fm%structural_ratio(n), &
               fm%velocity_ratio(n), fm%critical_velocity(n), fm%fluid_ratio(n), &
               fm%omega(n), fm%shapes(sys%n_dof, n))
      acts = [fl%planes /= 'v', fl%planes /= 'w'] .and. fl%fluid_elastic == 'connors'
      ! merge the planes' ascending lists (w first at equal frequency)
      i1 = 1;  i2 = 1
      do k = 1, n
         p = 1
         if (np > 1) then
            if (i1 > pm(1)%n_modes) then
               p = 2
            else if (i2 <= pm(2)%n_modes) then
               if (pm(2)%omega2(i2) < pm(1)%omega2(i1)) p = 2
            end if
         end if
         j = merge(i1, i2, p == 1)
         if (p == 1) then
            i1 = i1 + 1
         else
            i2 = i2 + 1
         end if
         fm%plane(k) = p
         fm%omega(k) = sqrt(max(pm(p)%omega2(j), 0.0_dp))
         fm%frequency_hz(k) = fm%omega(k) / (2.0_dp * pi)
         fm%shapes(:, k) = pm(p)%shapes(:, j)
         fm%structural_ratio(k) = beta / (2.0_dp * fm%omega(k)) + gamma * fm%omega(k) / 2.0_dp
         if (present(modal)) then
            jj = min(j, size(modal))
            if (size(modal) > 0) fm%structural_ratio(k) = fm%structural_ratio(k) + modal(jj)
         end if
         fm%velocity_ratio(k) = 0.0_dp
         if (acts(p)) fm%velocity_ratio(k) = velocity_ratio(sys, fl, p, fm%shapes(:, k))
         w = fm%velocity_ratio(k)
         fm%critical_velocity(k) = huge(1.0_dp)
         fm%fluid_ratio(k) = 0.0_dp
         if (w > 0.0_dp .and. fl%fluid_density > 0.0_dp .and. fl%tube_diameter > 0.0_dp) then
            fm%critical_velocity(k) = connors_velocity(fl%connors_constant, fm%frequency_hz(k), &
               fl%tube_diameter, m_per_length, 2.0_dp * pi * fm%structural_ratio(k), &
               fl%fluid_density) / sqrt(w)
            fm%fluid_ratio(k) = fluid_elastic_ratio(fl%fluid_density, fl%velocity * sqrt(w), &
               fl%connors_constant, fm%frequency_hz(k), m_per_length)
         end if
      end do
   end subroutine flow_modes

   !> C_fe = M Phi diag(2 zeta_fe,j omega_j) Phi' M of the flow's modes (n_dof x n_dof).
   pure function fluid_elastic_damping(sys, fm) result(c)
      type(system_t), intent(in) :: sys          !! assembled structure
      type(flow_modes_t), intent(in) :: fm       !! modes with zeta_fe
      real(dp), allocatable :: c(:, :)
      real(dp), allocatable :: mphi(:)
      integer :: j, i
      allocate(c(sys%n_dof, sys%n_dof), source=0.0_dp)
      do j = 1, fm%n_modes
         if (fm%fluid_ratio(j) == 0.0_dp) cycle
         mphi = matmul(sys%m, fm%shapes(:, j))
         do i = 1, sys%n_dof
            c(:, i) = c(:, i) + 2.0_dp * fm%fluid_ratio(j) * fm%omega(j) * mphi * mphi(i)
         end do
      end do
   end function fluid_elastic_damping
end module gapbeam_fluid_elastic
