!> Dof numbering and assembly of the linear structure: stiffness K, mass M, influence vector r.
!>
!> Global dofs are numbered node by node from the root, (w, theta) per node, skipping the
!> constrained ones (root w always; root theta when the root is clamped). K and M are kept
!> both dense and in LAPACK upper band storage, ab(kd+1+i-j, j) = A(i, j), with kd = 3.
module gapbeam_assembly
   use gapbeam_kinds, only: dp
   use gapbeam_description, only: structure_t, beam_ei, beam_rho_a, beam_fibre_distance, &
      n_nodes, dof_w, dof_theta
   use gapbeam_model, only: system_t
   use gapbeam_linalg, only: band_to_dense
   use gapbeam_beam_element, only: beam_stiffness, beam_consistent_mass, beam_lumped_mass, &
      beam_curvature_row
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
      integer :: nn, i, e, n, idx(4), a, b, kd
      real(dp) :: le, ei, rho_a, ke(4, 4), me(4, 4), md(4)
      logical :: lumped

      nn = n_nodes(st%beam)
      sys%n_node = nn
      allocate(sys%dof_of(2, nn))
      n = 0
      do i = 1, nn
         if (i == 1) then
            sys%dof_of(dof_w, i) = 0
            if (st%root%condition == 'spring') then
               n = n + 1;  sys%dof_of(dof_theta, i) = n
            else
               sys%dof_of(dof_theta, i) = 0
            end if
         else
            n = n + 1;  sys%dof_of(dof_w, i) = n
            n = n + 1;  sys%dof_of(dof_theta, i) = n
         end if
      end do
      sys%n_dof = n
      kd = sys%kd
      allocate(sys%k_band(kd + 1, n), sys%m_band(kd + 1, n), source=0.0_dp)

      le = st%beam%length / real(st%beam%n_elem, dp)
      ei = beam_ei(st%beam)
      rho_a = beam_rho_a(st%beam)
      lumped = st%beam%mass_matrix == 'lumped'
      sys%m_diagonal = lumped
      ke = beam_stiffness(ei, le)
      if (lumped) then
         md = beam_lumped_mass(rho_a, le, st%beam%rotary_inertia)
         me = 0.0_dp
         do a = 1, 4
            me(a, a) = md(a)
         end do
      else
         me = beam_consistent_mass(rho_a, le)
      end if
      do e = 1, st%beam%n_elem
         idx = [sys%dof_of(:, e), sys%dof_of(:, e + 1)]
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
         i = sys%dof_of(dof_theta, 1)
         sys%k_band(kd + 1, i) = sys%k_band(kd + 1, i) + st%root%k_theta
      end if
      if (allocated(st%springs)) then
         do e = 1, size(st%springs)
            i = sys%dof_of(st%springs(e)%dof, st%springs(e)%node)
            if (i > 0) sys%k_band(kd + 1, i) = sys%k_band(kd + 1, i) + st%springs(e)%stiffness
         end do
      end if
      if (allocated(st%masses)) then
         do e = 1, size(st%masses)
            i = sys%dof_of(dof_w, st%masses(e)%node)
            if (i > 0) sys%m_band(kd + 1, i) = sys%m_band(kd + 1, i) + st%masses(e)%mass
            i = sys%dof_of(dof_theta, st%masses(e)%node)
            if (i > 0) sys%m_band(kd + 1, i) = sys%m_band(kd + 1, i) + st%masses(e)%inertia
         end do
      end if
      if (present(dense)) then
         if (.not. dense) kd = -1
      end if
      if (kd >= 0) then
         call band_to_dense(sys%k_band, sys%k)
         call band_to_dense(sys%m_band, sys%m)
      end if

      allocate(sys%r(n), source=0.0_dp)
      do i = 2, nn
         sys%r(sys%dof_of(dof_w, i)) = 1.0_dp
      end do

      ! root strain eps = c * w''(0) from element 1's shape functions
      sys%fibre_distance = beam_fibre_distance(st%beam)
      sys%element_length = le
      allocate(sys%strain_row(n), source=0.0_dp)
      idx = [sys%dof_of(:, 1), sys%dof_of(:, 2)]
      md = sys%fibre_distance * beam_curvature_row(le, 0.0_dp)
      do a = 1, 4
         if (idx(a) > 0) sys%strain_row(idx(a)) = md(a)
      end do
      sys%tip_dof = sys%dof_of(dof_w, nn)
   end subroutine assemble

end module gapbeam_assembly
