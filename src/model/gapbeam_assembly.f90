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
   use gapbeam_linalg, only: dense_to_band
   use gapbeam_beam_element, only: beam_stiffness, beam_consistent_mass, beam_lumped_mass, &
      beam_curvature_row
   implicit none
   private
   public :: assemble

contains

   !> Number the dofs and assemble K, M, r and the root-strain row of a validated structure.
   pure subroutine assemble(st, sys)
      type(structure_t), intent(in) :: st    !! validated structure
      type(system_t), intent(out) :: sys     !! assembled system
      integer :: nn, i, e, n, idx(4), a, b
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
      allocate(sys%k(n, n), sys%m(n, n), source=0.0_dp)

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
               if (idx(a) == 0) cycle
               sys%k(idx(a), idx(b)) = sys%k(idx(a), idx(b)) + ke(a, b)
               sys%m(idx(a), idx(b)) = sys%m(idx(a), idx(b)) + me(a, b)
            end do
         end do
      end do
      if (st%root%condition == 'spring') then
         i = sys%dof_of(dof_theta, 1)
         sys%k(i, i) = sys%k(i, i) + st%root%k_theta
      end if
      if (allocated(st%springs)) then
         do e = 1, size(st%springs)
            i = sys%dof_of(st%springs(e)%dof, st%springs(e)%node)
            if (i > 0) sys%k(i, i) = sys%k(i, i) + st%springs(e)%stiffness
         end do
      end if
      if (allocated(st%masses)) then
         do e = 1, size(st%masses)
            i = sys%dof_of(dof_w, st%masses(e)%node)
            if (i > 0) sys%m(i, i) = sys%m(i, i) + st%masses(e)%mass
            i = sys%dof_of(dof_theta, st%masses(e)%node)
            if (i > 0) sys%m(i, i) = sys%m(i, i) + st%masses(e)%inertia
         end do
      end if
      call dense_to_band(sys%k, sys%kd, sys%k_band)
      call dense_to_band(sys%m, sys%kd, sys%m_band)

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
