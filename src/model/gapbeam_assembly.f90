!> Dof numbering and assembly of the linear structure: stiffness K, mass M, influence vector r.
!>
!> Global dofs are numbered node by node from the root, (w, theta) per node, skipping the
!> constrained ones (root w always; root theta when the root is clamped). K and M are kept
!> both dense and in LAPACK upper band storage, ab(kd+1+i-j, j) = A(i, j), with kd = 3.
module gapbeam_assembly
   use gapbeam_kinds, only: dp
   use gapbeam_model, only: structure_t, beam_ei, beam_rho_a, beam_fibre_distance, n_nodes, &
      dof_w, dof_theta
   use gapbeam_beam_element, only: beam_stiffness, beam_consistent_mass, beam_lumped_mass, &
      beam_curvature_row
   implicit none
   private
   public :: system_t, assemble, dense_to_band, global_dof

   !> Semi-bandwidth of the assembled matrices.
   integer, parameter, public :: band_kd = 3

   !> The assembled linear structure (beam + root spring + boundary springs + point masses).
   type :: system_t
      integer :: n_dof = 0                         !! number of free dofs
      integer :: n_node = 0                        !! number of nodes
      integer :: kd = band_kd                      !! semi-bandwidth
      integer, allocatable :: dof_of(:, :)         !! (2, n_node) index of (w, theta), 0: fixed
      real(dp), allocatable :: k(:, :)             !! dense stiffness [N/m ...]
      real(dp), allocatable :: m(:, :)             !! dense mass [kg ...]
      real(dp), allocatable :: k_band(:, :)        !! upper band storage of k
      real(dp), allocatable :: m_band(:, :)        !! upper band storage of m
      logical :: m_diagonal = .false.              !! true for a lumped mass matrix
      real(dp), allocatable :: r(:)                !! rigid base-translation influence vector [-]
      real(dp), allocatable :: strain_row(:)       !! root strain = dot(strain_row, u) [-/m...]
      integer :: tip_dof = 0                       !! global index of the tip w
      real(dp) :: fibre_distance = 0.0_dp          !! strain fibre distance c [m]
      real(dp) :: element_length = 0.0_dp          !! element length [m]
   end type system_t

contains

   !> Global index of (node, dof code), 0 if constrained; error stop outside the mesh.
   pure integer function global_dof(sys, node, dof)
      type(system_t), intent(in) :: sys   !! assembled system
      integer, intent(in) :: node         !! node index 1..n_node
      integer, intent(in) :: dof          !! dof_w or dof_theta
      if (node < 1 .or. node > sys%n_node .or. dof < 1 .or. dof > 2) &
         error stop 'gapbeam_assembly:global_dof: node or dof outside the mesh'
      global_dof = sys%dof_of(dof, node)
   end function global_dof

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

   !> Copy the upper band of a dense symmetric matrix to LAPACK band storage.
   pure subroutine dense_to_band(a, kd, ab)
      real(dp), intent(in) :: a(:, :)                    !! dense symmetric matrix
      integer, intent(in) :: kd                          !! semi-bandwidth
      real(dp), allocatable, intent(out) :: ab(:, :)     !! (kd+1, n) upper band storage
      integer :: i, j, n
      n = size(a, 2)
      allocate(ab(kd + 1, n), source=0.0_dp)
      do j = 1, n
         do i = max(1, j - kd), j
            ab(kd + 1 + i - j, j) = a(i, j)
         end do
      end do
   end subroutine dense_to_band
end module gapbeam_assembly
