!> Modal reduction: the model projected on the m lowest modes of the open structure (stops
!> inactive), optionally with a static correction at each stop dof (its residual flexibility),
!> so that the contact force stays accurate with few modes.
!>
!> Basis B = [phi_1 .. phi_m, r_1 .. r_s], r_j = K^-1 e_j - Phi_m Lambda_m^-1 Phi_m' e_j the
!> residual attachment mode of stop dof j (dropped when the kept modes already represent it).
!> The coordinates are then changed, z = T^-1 x, so that the first coordinates ARE the
!> physical displacements of the stop dofs (and of the tip): the stop laws, the condensed
!> contact solution, the integrators and the outputs run on the reduced problem unchanged.
!> Rayleigh damping carries over exactly (C_r = beta M_r + gamma K_r); the base excitation
!> enters through the projected load shape B' M r (the modal participation factors); the root
!> strain is recovered from the retained shapes (strain row B'' s).
module gapbeam_reduction
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dgesv, dpotrf, dpotrs
   use gapbeam_model, only: model_t
   use gapbeam_results, only: modes_t
   use gapbeam_eigen, only: solve_modes
   use gapbeam_linalg, only: dense_to_band
   implicit none
   private
   public :: reduce_model, reduction_basis, project

contains

   !> The reduced problem and its basis (physical u = basis z).
   subroutine reduce_model(full, n_modes, static_correction, red, basis, err)
      type(model_t), intent(in) :: full              !! full model (contacts resolved)
      integer, intent(in) :: n_modes                   !! modes kept
      logical, intent(in) :: static_correction         !! add residual attachment modes
      type(model_t), intent(out) :: red              !! reduced model
      real(dp), allocatable, intent(out) :: basis(:, :)  !! (n_full, n_red)
      type(error_t), allocatable, intent(out) :: err   !! too few modes, singular selection
      type(modes_t) :: modes
      integer, allocatable :: pinned(:)
      integer :: n, r, j, k
      n = full%n
      call solve_modes(full%sys, modes, err);  if (allocated(err)) return
      if (n_modes < 1 .or. n_modes > modes%n_modes) then
         call fatal_error(err, 'gapbeam_reduction: n_modes = ' // str(n_modes) // ': the ' &
            // 'model has ' // str(modes%n_modes) // ' modes with mass')
         return
      end if
      ! pinned physical dofs: every stop dof, and the tip
      pinned = full%slot_dof
      if (full%sys%tip_dof > 0 .and. .not. any(pinned == full%sys%tip_dof)) &
         pinned = [pinned, full%sys%tip_dof]
      call reduction_basis(full, modes, n_modes, static_correction, pinned, basis, err)
      if (allocated(err)) return
      r = size(basis, 2)
      red = full
      red%n = r
      red%sys%n_dof = r
      red%sys%n_node = 0
      red%sys%kd = max(r - 1, 0)
      red%sys%k = matmul(transpose(basis), matmul(full%sys%k, basis))
      red%sys%m = matmul(transpose(basis), matmul(full%sys%m, basis))
      red%sys%k = 0.5_dp * (red%sys%k + transpose(red%sys%k))
      red%sys%m = 0.5_dp * (red%sys%m + transpose(red%sys%m))
      call dense_to_band(red%sys%k, red%sys%kd, red%sys%k_band)
      call dense_to_band(red%sys%m, red%sys%kd, red%sys%m_band)
      red%sys%m_diagonal = .false.
      red%c = red%beta * red%sys%m + red%gamma * red%sys%k
      red%q = matmul(transpose(basis), full%q)
      call project(full, basis, full%sys%r, red%sys%r, err);  if (allocated(err)) return
      red%sys%strain_row = matmul(full%sys%strain_row, basis)
      red%sys%tip_dof = 0
      do j = 1, size(pinned)
         if (pinned(j) == full%sys%tip_dof) red%sys%tip_dof = j
      end do
      ! contacts act on the pinned coordinates
      do j = 1, full%n_contacts
         red%c_dof(j) = full%c_slot(j)
      end do
      red%slot_dof = [(j, j = 1, full%n_slots)]
      ! the stops' own dofs (wear meter, orbits): their pinned coordinate, 0 when not pinned
      if (allocated(full%stop_dofs)) red%stop_dofs = reshape([((first_index(pinned, &
         full%stop_dofs(j, k)), j = 1, 2), k = 1, size(full%stop_dofs, 2))], &
         shape(full%stop_dofs))
      call solve_modes(red%sys, modes, err);  if (allocated(err)) return
      red%omega_max = sqrt(maxval(modes%omega2))
   end subroutine reduce_model

   !> Basis [modes, residual attachment modes] transformed so that coordinate j is the
   !> displacement of physical dof pinned(j).
   subroutine reduction_basis(full, modes, n_modes, static_correction, pinned, basis, err)
      type(model_t), intent(in) :: full
      type(modes_t), intent(in) :: modes
      integer, intent(in) :: n_modes
      logical, intent(in) :: static_correction
      integer, intent(in) :: pinned(:)
      real(dp), allocatable, intent(out) :: basis(:, :)
      type(error_t), allocatable, intent(out) :: err
      real(dp), allocatable :: b(:, :), att(:, :), kf(:, :), tinv(:, :), cb(:, :), t(:, :)
      integer, allocatable :: ipiv(:), piv(:)
      logical, allocatable :: used(:)
      integer :: n, ns, j, i, r, info, k, best
      real(dp) :: nrm, nrm0, big
      n = full%n;  ns = full%n_slots
      b = modes%shapes(:, 1:n_modes)
      if (static_correction .and. ns > 0) then
         ! K^-1 e_j minus what the kept modes represent (mass-normalised: Phi Lambda^-1 Phi')
         kf = full%sys%k
         allocate(att(n, ns), source=0.0_dp)
         do j = 1, ns
            att(full%slot_dof(j), j) = 1.0_dp
         end do
         call dpotrf('U', n, kf, n, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_reduction: the stiffness is not positive definite ' &
               // '(dpotrf info=' // str(info) // ')')
            return
         end if
         call dpotrs('U', n, ns, kf, n, att, n, info)
         do j = 1, ns
            nrm0 = maxval(abs(att(:, j)))
            do i = 1, n_modes
               att(:, j) = att(:, j) - b(:, i) * (b(full%slot_dof(j), i) / modes%omega2(i))
            end do
            ! keep it unless the kept modes already represent this flexibility
            nrm = maxval(abs(att(:, j)))
            if (nrm > 1.0e-8_dp * nrm0) b = reshape([b, att(:, j) / nrm], [n, size(b, 2) + 1])
         end do
      end if
      r = size(b, 2)
      if (size(pinned) > r) then
         call fatal_error(err, 'gapbeam_reduction: ' // str(r) // ' basis vectors cannot ' &
            // 'carry ' // str(size(pinned)) // ' stop and tip displacements: keep more modes')
         return
      end if
      ! choose, for each pinned dof, a basis vector to exchange for it (largest pivot)
      cb = b(pinned, :)
      allocate(used(r), source=.false.)
      allocate(piv(size(pinned)))
      t = cb
      do k = 1, size(pinned)
         big = 0.0_dp;  best = 0
         do j = 1, r
            if (used(j)) cycle
            if (abs(t(k, j)) > big) then
               big = abs(t(k, j));  best = j
            end if
         end do
         if (best == 0 .or. big <= 1.0e-12_dp * maxval(abs(cb))) then
            call fatal_error(err, 'gapbeam_reduction: the kept modes do not move dof ' &
               // str(pinned(k)) // ' independently of the other stops: keep more modes or ' &
               // 'add the static correction')
            return
         end if
         used(best) = .true.;  piv(k) = best
         ! eliminate this column's influence on the later rows
         do i = k + 1, size(pinned)
            t(i, :) = t(i, :) - t(k, :) * (t(i, best) / t(k, best))
         end do
      end do
      ! new coordinates z = Tinv x: first the pinned displacements, then the unused x
      allocate(tinv(r, r), source=0.0_dp)
      tinv(1:size(pinned), :) = cb
      k = size(pinned)
      do j = 1, r
         if (.not. used(j)) then
            k = k + 1
            tinv(k, j) = 1.0_dp
         end if
      end do
      ! basis' = B T, T = Tinv^-1:  solve Tinv' Y = B'  (Y = T' B')
      t = transpose(b)
      allocate(ipiv(r))
      kf = transpose(tinv)
      call dgesv(r, n, kf, r, ipiv, t, r, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_reduction: singular change of coordinates (dgesv info=' &
            // str(info) // ')')
         return
      end if
      basis = transpose(t)
      ! exact pins (remove round-off): row pinned(k) of the basis is the unit vector k
      do k = 1, size(pinned)
         basis(pinned(k), :) = 0.0_dp
         basis(pinned(k), k) = 1.0_dp
      end do
   end subroutine reduction_basis

   !> The position of value v in list, 0 when absent (or v = 0).
   pure integer function first_index(list, v) result(k)
      integer, intent(in) :: list(:)   !! values
      integer, intent(in) :: v         !! value
      integer :: i
      k = 0
      if (v == 0) return
      do i = 1, size(list)
         if (list(i) == v) then
            k = i
            return
         end if
      end do
   end function first_index

   !> Coordinates z of a physical vector x in the basis, mass-weighted least squares.
   subroutine project(full, basis, x, z, err)
      type(model_t), intent(in) :: full                !! full model
      real(dp), intent(in) :: basis(:, :)              !! (n_full, n_red)
      real(dp), intent(in) :: x(:)                     !! physical vector
      real(dp), allocatable, intent(out) :: z(:)       !! its coordinates
      type(error_t), allocatable, intent(out) :: err   !! the basis has no mass in some direction
      real(dp), allocatable :: a(:, :), rhs(:, :)
      integer :: r, info
      r = size(basis, 2)
      a = matmul(transpose(basis), matmul(full%sys%m, basis))
      rhs = reshape(matmul(transpose(basis), matmul(full%sys%m, x)), [r, 1])
      call dpotrf('U', r, a, r, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_reduction:project: the reduced mass matrix is not ' &
            // 'positive definite (dpotrf info=' // str(info) // ')')
         return
      end if
      call dpotrs('U', r, 1, a, r, rhs, r, info)
      z = rhs(:, 1)
   end subroutine project
end module gapbeam_reduction
