!> Dof numbering and assembly of the linear structure: stiffness K, mass M, influence vector r.
!>
!> Euler-Bernoulli or Timoshenko elements (gapbeam_beam_element) as the beam's theory says;
!> for Timoshenko the rotation dofs are the section rotations psi and the root strain is
!> c psi'(0) (the bending strain; the shear strain does not strain the fibre).
!>
!> Global dofs are numbered node by node from the root, (w, theta) per node, skipping the
!> constrained ones (root w always; root theta when the root is clamped; the tip's by its
!> condition). With two planes the (v, theta_v) dofs follow, numbered the same way. K and M are kept
!> both dense and in LAPACK upper band storage, ab(kd+1+i-j, j) = A(i, j), with kd = 3.
module gapbeam_assembly
   use gapbeam_kinds, only: dp
   use gapbeam_description, only: structure_t, beam_ei, beam_rho_a, beam_fibre_distance, &
      n_nodes, dof_w, dof_theta, dof_v, beam_mass_per_length, beam_is_timoshenko, beam_rho_i, &
      beam_shear_stiffness
   use gapbeam_model, only: system_t
   use gapbeam_linalg, only: band_to_dense
   use gapbeam_beam_element, only: beam_stiffness, beam_consistent_mass, beam_lumped_mass, &
      beam_curvature_row, timoshenko_phi, timoshenko_stiffness, timoshenko_consistent_mass, &
      timoshenko_lumped_mass, timoshenko_shapes
   implicit none
   private
   public :: assemble

contains

   !> Number the dofs and assemble K, M, r and the root-strain row of a validated structure.
   !> K and M are assembled in band storage; the dense copies are filled from it unless
   !> `dense` is false (calibrations: O(n) memory per trial).
   pure subroutine assemble(st, sys, dense)
      type(structure_t), intent(in) :: st    !! validated structure
      type(system_t), intent(out) :: sys     !! assembled system
      logical, intent(in), optional :: dense !! fill sys%k and sys%m too (default: yes)
      integer :: nn, i, e, n, idx(4), a, b, kd, pl, np, d0
      real(dp) :: le, ei, rho_a, ke(4, 4), me(4, 4), md(4), phi, shape_n(4), shape_p(4)
      logical :: lumped, timoshenko

      nn = n_nodes(st%beam)
      np = max(1, st%beam%planes)
      sys%n_node = nn
      sys%planes = np
      allocate(sys%dof_of(2 * np, nn))
      ! plane by plane (all the (w, theta) dofs, then all the (v, theta_v) ones): the planes
      ! are uncoupled in K and M, so the band width stays kd = 3
      n = 0
      do pl = 1, np
         d0 = 2 * (pl - 1)
         do i = 1, nn
            call number_node(i, nn, st, n, sys%dof_of(d0 + dof_w, i), sys%dof_of(d0 + dof_theta, i))
         end do
      end do
      sys%n_dof = n
      kd = sys%kd
      allocate(sys%k_band(kd + 1, n), sys%m_band(kd + 1, n), source=0.0_dp)

      le = st%beam%length / real(st%beam%n_elem, dp)
      ei = beam_ei(st%beam)
      rho_a = beam_rho_a(st%beam)
      if (st%beam%added_mass > 0.0_dp) rho_a = beam_mass_per_length(st%beam)
      lumped = st%beam%mass_matrix == 'lumped'
      sys%m_diagonal = lumped
      timoshenko = beam_is_timoshenko(st%beam)
      phi = 0.0_dp
      if (timoshenko) phi = timoshenko_phi(ei, beam_shear_stiffness(st%beam), le)
      sys%shear_phi = phi
      if (timoshenko) then
         ke = timoshenko_stiffness(ei, phi, le)
      else
         ke = beam_stiffness(ei, le)
      end if
      if (lumped) then
         if (timoshenko) then
            md = timoshenko_lumped_mass(rho_a, beam_rho_i(st%beam), le, st%beam%rotary_inertia)
         else
            md = beam_lumped_mass(rho_a, le, st%beam%rotary_inertia)
         end if
         me = 0.0_dp
         do a = 1, 4
            me(a, a) = md(a)
         end do
      else if (timoshenko) then
         me = timoshenko_consistent_mass(rho_a, beam_rho_i(st%beam), phi, le)
      else
         me = beam_consistent_mass(rho_a, le)
      end if
      do pl = 1, np
         d0 = 2 * (pl - 1)
         do e = 1, st%beam%n_elem
            idx = [sys%dof_of(d0 + 1:d0 + 2, e), sys%dof_of(d0 + 1:d0 + 2, e + 1)]
            do b = 1, 4
               if (idx(b) == 0) cycle
               do a = 1, 4
                  if (idx(a) == 0 .or. idx(a) > idx(b)) cycle
                  i = kd + 1 + idx(a) - idx(b)
                  sys%k_band(i, idx(b)) = sys%k_band(i, idx(b)) + ke(a, b)
                  sys%m_band(i, idx(b)) = sys%m_band(i, idx(b)) + me(a, b)
               end do
            end do
         end do
         if (st%root%condition == 'spring') then
            i = sys%dof_of(d0 + dof_theta, 1)
            sys%k_band(kd + 1, i) = sys%k_band(kd + 1, i) + st%root%k_theta
         end if
         if (st%tip%condition == 'spring') then
            i = sys%dof_of(d0 + dof_theta, nn)
            sys%k_band(kd + 1, i) = sys%k_band(kd + 1, i) + st%tip%k_theta
         end if
      end do
      if (allocated(st%springs)) then
         do e = 1, size(st%springs)
            i = sys%dof_of(st%springs(e)%dof, st%springs(e)%node)
            if (i > 0) sys%k_band(kd + 1, i) = sys%k_band(kd + 1, i) + st%springs(e)%stiffness
         end do
      end if
      if (allocated(st%masses)) then
         do e = 1, size(st%masses)
            do pl = 1, np
               d0 = 2 * (pl - 1)
               i = sys%dof_of(d0 + dof_w, st%masses(e)%node)
               if (i > 0) sys%m_band(kd + 1, i) = sys%m_band(kd + 1, i) + st%masses(e)%mass
               i = sys%dof_of(d0 + dof_theta, st%masses(e)%node)
               if (i > 0) sys%m_band(kd + 1, i) = sys%m_band(kd + 1, i) + st%masses(e)%inertia
            end do
         end do
      end if
      if (present(dense)) then
         if (.not. dense) kd = -1
      end if
      if (kd >= 0) then
         call band_to_dense(sys%k_band, sys%k)
         call band_to_dense(sys%m_band, sys%m)
      end if

      allocate(sys%r(n), sys%r_v(n), source=0.0_dp)
      do i = 1, nn
         if (sys%dof_of(dof_w, i) > 0) sys%r(sys%dof_of(dof_w, i)) = 1.0_dp
         if (np > 1) then
            if (sys%dof_of(dof_v, i) > 0) sys%r_v(sys%dof_of(dof_v, i)) = 1.0_dp
         end if
      end do

      ! root strain eps = c * w''(0) (Timoshenko: c * psi'(0)) from element 1's shape functions
      sys%fibre_distance = beam_fibre_distance(st%beam)
      sys%element_length = le
      allocate(sys%strain_row(n), source=0.0_dp)
      idx = [sys%dof_of(1:2, 1), sys%dof_of(1:2, 2)]
      if (timoshenko) then
         call timoshenko_shapes(le, phi, 0.0_dp, shape_n, shape_p, md)
         md = sys%fibre_distance * md
      else
         md = sys%fibre_distance * beam_curvature_row(le, 0.0_dp)
      end if
      do a = 1, 4
         if (idx(a) > 0) sys%strain_row(idx(a)) = md(a)
      end do
      sys%tip_dof = sys%dof_of(dof_w, nn)
      if (np > 1) sys%tip_dof_v = sys%dof_of(dof_v, nn)
   end subroutine assemble

   !> Number the translation and rotation of node i (0: fixed by an end condition).
   pure subroutine number_node(i, nn, st, n, iw, it)
      integer, intent(in) :: i, nn               !! node, number of nodes
      type(structure_t), intent(in) :: st        !! structure (end conditions)
      integer, intent(inout) :: n                !! dofs numbered so far
      integer, intent(out) :: iw, it             !! index of the translation, the rotation
      logical :: fix_w, fix_t
      fix_w = .false.;  fix_t = .false.
      if (i == 1) then
         fix_w = .true.
         fix_t = st%root%condition == 'clamped'
      end if
      if (i == nn .and. st%tip%condition /= 'free') then
         fix_w = .true.
         fix_t = fix_t .or. st%tip%condition == 'clamped'
      end if
      iw = 0;  it = 0
      if (.not. fix_w) then
         n = n + 1;  iw = n
      end if
      if (.not. fix_t) then
         n = n + 1;  it = n
      end if
   end subroutine number_node

end module gapbeam_assembly
