!> Modal damping: a damping ratio per mode of the integrated model,
!>
!>    C_modal = M Phi diag(2 zeta_j omega_j) Phi' M,    Phi' M Phi = I,
!>
!> added to the Rayleigh terms, C = beta M + gamma K + C_modal, so that mode j has the ratio
!> zeta_j + beta/(2 omega_j) + gamma omega_j/2 and C stays diagonal in the modes (classical
!> damping: the exact integrator keeps its modal form). Phi holds every mode with mass of the
!> model that is integrated: the finite element model, or a reduced model (its own modes: the
!> kept modes of the structure, then the modes of its static correction), so C_modal is dense.
!> Massless dofs (lumped mass without rotary inertia) have zero rows in M and so in C_modal.
!>
!> Mode numbers: with one plane, mode j is the j-th lowest. With two planes the modes are
!> numbered in each plane (the planes are uncoupled in K and M): mode j of w and mode j of v
!> both get zeta_j. A cluster of equal frequencies (the two planes of a symmetric beam) is
!> first turned into modes that each lie in one plane (the eigenvectors of Phi_c' M_w Phi_c,
!> M_w the mass of the first plane's dofs), so that a basis LAPACK mixed between the planes is
!> numbered as the planes are.
module gapbeam_modal_damping
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_description, only: damping_t, modal_ratio, dof_w, dof_theta
   use gapbeam_model, only: system_t, model_t
   use gapbeam_results, only: modes_t
   use gapbeam_eigen, only: solve_modes
   use gapbeam_lapack, only: dsyevd
   implicit none
   private
   public :: apply_modal_damping, first_plane_mass

   !> relative distance of two omega^2 below which they form one cluster
   real(dp), parameter :: cluster_tolerance = 1.0e-6_dp

contains

   !> C_modal of a structure for a list of modal ratios, and the ratio and angular frequency
   !> given to each of its modes (ascending).
   subroutine modal_damping_matrix(sys, ratios, c_modal, zeta, omega, err, m_plane)
      type(system_t), intent(in) :: sys                  !! the integrated structure (k, m)
      real(dp), allocatable, intent(in) :: ratios(:)     !! the deck's modal_ratios [-]
      real(dp), allocatable, intent(out) :: c_modal(:, :)  !! M Phi diag(2 zeta omega) Phi' M
      real(dp), allocatable, intent(out) :: zeta(:)      !! ratio of each mode [-]
      real(dp), allocatable, intent(out) :: omega(:)     !! its angular frequency [rad/s]
      type(error_t), allocatable, intent(out) :: err     !! eigen failure
      real(dp), intent(in), optional :: m_plane(:, :)    !! two planes: mass of the first plane
      type(modes_t) :: modes
      real(dp), allocatable :: w(:, :)
      integer, allocatable :: plane(:)
      integer :: j, nm, count(2)
      call solve_modes(sys, modes, err)
      if (allocated(err)) return
      nm = modes%n_modes
      allocate(plane(nm), source=1)
      if (present(m_plane)) call split_planes(modes, m_plane, plane)
      allocate(zeta(nm))
      omega = sqrt(max(modes%omega2, 0.0_dp))
      count = 0
      do j = 1, nm
         count(plane(j)) = count(plane(j)) + 1
         zeta(j) = modal_ratio(ratios, count(plane(j)))
      end do
      ! W = M Phi scaled by sqrt(2 zeta omega); C = W W'
      w = matmul(sys%m, modes%shapes)
      do j = 1, nm
         w(:, j) = w(:, j) * sqrt(2.0_dp * zeta(j) * omega(j))
      end do
      c_modal = matmul(w, transpose(w))
      c_modal = 0.5_dp * (c_modal + transpose(c_modal))
   end subroutine modal_damping_matrix

   !> Rotate each cluster of equal frequencies into modes that lie in one plane, and say the
   !> plane of every mode (1: the mass fraction in the first plane is at least one half).
   subroutine split_planes(modes, m_plane, plane)
      type(modes_t), intent(inout) :: modes            !! modes (clusters rotated)
      real(dp), intent(in) :: m_plane(:, :)            !! mass of the first plane's dofs
      integer, intent(out) :: plane(:)                 !! 1 or 2 per mode
      real(dp), allocatable :: p(:, :), x(:, :), ev(:), work(:)
      integer, allocatable :: iwork(:)
      integer :: i, j, nm, c, info, lw, liw
      real(dp) :: fr
      nm = modes%n_modes
      i = 1
      do while (i <= nm)
         j = i
         do while (j < nm)
            if (modes%omega2(j + 1) - modes%omega2(i) > cluster_tolerance &
                * abs(modes%omega2(j + 1))) exit
            j = j + 1
         end do
         c = j - i + 1
         if (c > 1) then
            x = modes%shapes(:, i:j)
            p = matmul(transpose(x), matmul(m_plane, x))
            allocate(ev(c))
            lw = 1 + 6 * c + 2 * c**2;  liw = 3 + 5 * c
            allocate(work(lw), iwork(liw))
            call dsyevd('V', 'U', c, p, c, ev, work, lw, iwork, liw, info)
            ! (a failure leaves LAPACK's basis: the numbering is then that of the fractions)
            if (info == 0) modes%shapes(:, i:j) = matmul(x, p)
            deallocate(ev, work, iwork)
         end if
         i = j + 1
      end do
      do j = 1, nm
         fr = dot_product(modes%shapes(:, j), matmul(m_plane, modes%shapes(:, j)))
         plane(j) = merge(1, 2, fr >= 0.5_dp)
      end do
   end subroutine split_planes

   !> The mass of the first plane's dofs, (w, theta) of every node, of a two-plane structure
   !> (zero elsewhere); the structure must carry its dof map.
   function first_plane_mass(sys) result(mw)
      type(system_t), intent(in) :: sys       !! assembled two-plane structure
      real(dp), allocatable :: mw(:, :)
      logical, allocatable :: first(:)
      integer :: i, j
      allocate(first(sys%n_dof), source=.false.)
      do i = 1, sys%n_node
         do j = dof_w, dof_theta
            if (sys%dof_of(j, i) > 0) first(sys%dof_of(j, i)) = .true.
         end do
      end do
      mw = sys%m
      do j = 1, sys%n_dof
         do i = 1, sys%n_dof
            if (.not. (first(i) .and. first(j))) mw(i, j) = 0.0_dp
         end do
      end do
   end function first_plane_mass

   !> Set the modal part of the damping of a model (damping%model = 'modal'): c_modal from
   !> the model's own modes and C = beta M + gamma K + c_modal. Nothing for the other models.
   !> `m_plane`: for a two-plane model, the mass of the first plane in the model's coordinates
   !> (first_plane_mass for the finite element model, B' M_w B for a reduced one).
   subroutine apply_modal_damping(model, damping, err, m_plane)
      type(model_t), intent(inout) :: model            !! model (sys, beta, gamma set)
      type(damping_t), intent(in) :: damping           !! the deck's damping
      type(error_t), allocatable, intent(out) :: err   !! eigen failure
      real(dp), intent(in), optional :: m_plane(:, :)  !! two planes: mass of the first plane
      real(dp), allocatable :: zeta(:), omega(:)
      if (allocated(model%c_modal)) deallocate(model%c_modal)
      if (damping%model /= 'modal') return
      call modal_damping_matrix(model%sys, damping%modal_ratios, model%c_modal, zeta, omega, &
                                err, m_plane)
      if (allocated(err)) then
         err%message = 'group &damping: modal damping: ' // err%message
         return
      end if
      model%c = model%beta * model%sys%m + model%gamma * model%sys%k + model%c_modal
   end subroutine apply_modal_damping
end module gapbeam_modal_damping
