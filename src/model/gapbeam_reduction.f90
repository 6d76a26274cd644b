!> Modal reduction: the model projected on the lowest modes of the open structure (stops
!> inactive) and, with the static correction, on the residual attachment modes of the
!> support dofs, so that the contact flexibility is exact with few modes.
!>
!> Basis of a plane B = [phi_1 .. phi_m, r_1 .. r_s], r_j = K^-1 e_j - Phi_m Lambda_m^-1
!> Phi_m' e_j the residual attachment mode of attachment dof j (dropped when the kept modes
!> already represent it). The attachment dofs are the dofs of every contact (both directions
!> of a ring), and with two planes also the w and v of every support node (the tangential
!> direction of a flat stop, along which friction and the wear outputs act), and the dofs of
!> the point forces (their static response is then exact too). Since K^-1 e_j lies in the
!> span, the static response of the reduced model to any force at those dofs is the full
!> model's, to round-off.
!>
!> The coordinates are then changed, z = T^-1 x, so that the first coordinates of a plane ARE
!> the physical displacements of its pinned dofs (the attachment dofs and the tip): the stop
!> laws, the ring contacts, the condensed contact solution, the integrators and the outputs
!> run on the reduced problem unchanged, with every dof index of the model (contacts, rings,
!> slots, supports, tip) renumbered to its coordinate.
!>
!> **Two planes.** The open structure's planes are uncoupled (K and M are block diagonal,
!> the w-plane dofs first), so each plane is reduced on its own modes, the same number in
!> each (the cut-off's count in the plane that has more), with the pinned dofs mirrored (a dof
!> pinned in one plane is pinned in the other): the reduced coordinates are the w-plane block
!> then the v-plane block, equal in size, coordinate i of one the mirror of coordinate
!> i + n/2 of the other, as in the full model.
!>
!> **Loads.** Rayleigh damping carries over exactly (C_r = beta M_r + gamma K_r); the base
!> excitation enters through the projected load shapes B' M r and B' M r_v (the modal
!> participation factors), the point forces through B' p; the root strain is recovered from
!> the retained shapes (strain row B'' s); the influence vectors r, r_v and initial states are
!> projected by mass-weighted least squares.
module gapbeam_reduction
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dgesv, dpotrf, dpotrs
   use gapbeam_model, only: model_t, system_t
   use gapbeam_results, only: modes_t
   use gapbeam_eigen, only: solve_modes
   use gapbeam_linalg, only: dense_to_band
   implicit none
   private
   public :: reduce_model, project, plane_modes

contains

   !> The reduced problem and its basis (physical u = basis z). The modes kept in each plane
   !> are those up to `cutoff_hz` when it is given and positive (at least one), else the
   !> n_modes lowest.
   subroutine reduce_model(full, n_modes, static_correction, red, basis, err, cutoff_hz, &
                           modes_kept, highest_hz, modes_available)
      type(model_t), intent(in) :: full              !! full model (contacts resolved)
      integer, intent(in) :: n_modes                   !! modes kept in each plane
      logical, intent(in) :: static_correction         !! add residual attachment modes
      type(model_t), intent(out) :: red              !! reduced model
      real(dp), allocatable, intent(out) :: basis(:, :)  !! (n_full, n_red)
      type(error_t), allocatable, intent(out) :: err   !! too few modes, singular selection
      real(dp), intent(in), optional :: cutoff_hz      !! keep the modes up to this [Hz]
      integer, intent(out), optional :: modes_kept     !! modes kept in each plane
      real(dp), intent(out), optional :: highest_hz    !! the highest mode kept [Hz]
      integer, intent(out), optional :: modes_available  !! modes with mass in each plane
      type(modes_t) :: modes(2)
      type(system_t) :: sub
      integer, allocatable :: pinned(:), attach(:), map(:)
      real(dp), allocatable :: bp(:, :)
      integer :: n, np, nh, pl, off, keep, k, r, r1
      n = full%n
      np = full%sys%planes
      nh = n / np
      call reduction_dofs(full, pinned, attach)
      keep = 0
      do pl = 1, np
         if (np == 1) then
            call solve_modes(full%sys, modes(pl), err)
         else
            call plane_system(full%sys, pl, sub)
            call solve_modes(sub, modes(pl), err)
         end if
         if (allocated(err)) return
         if (present(cutoff_hz)) then
            if (cutoff_hz > 0.0_dp) keep = max(keep, 1, &
               count(modes(pl)%frequency_hz <= cutoff_hz))
         end if
      end do
      if (keep == 0) keep = n_modes
      do pl = 1, np
         if (keep < 1 .or. keep > modes(pl)%n_modes) then
            call fatal_error(err, 'gapbeam_reduction: n_modes = ' // str(keep) // ': the ' &
               // trim(merge('model has  ', 'plane has  ', np == 1)) // ' ' &
               // str(modes(pl)%n_modes) // ' modes with mass')
            return
         end if
      end do
      if (present(modes_kept)) modes_kept = keep
      if (present(modes_available)) modes_available = minval(modes(1:np)%n_modes)
      if (present(highest_hz)) highest_hz = maxval([(modes(pl)%frequency_hz(keep), pl = 1, np)])
      allocate(map(n), source=0)
      allocate(basis(n, 0))
      r1 = 0
      do pl = 1, np
         off = (pl - 1) * nh
         if (np == 1) then
            call plane_basis(full%sys%k, modes(pl), keep, static_correction, attach, pinned, &
                             bp, err)
         else
            call plane_basis(full%sys%k(off + 1:off + nh, off + 1:off + nh), modes(pl), keep, &
                             static_correction, attach, pinned, bp, err)
         end if
         if (allocated(err)) return
         r = size(bp, 2)
         if (pl == 1) r1 = r
         if (r /= r1) then
            call fatal_error(err, 'gapbeam_reduction: the two planes keep ' // str(r1) // ' and ' &
               // str(r) // ' basis vectors (a static mode is represented by the modes of one ' &
               // 'plane only): keep fewer modes, or set static_correction = .false.')
            return
         end if
         ! the block of the plane: rows off+1..off+nh, columns after the other plane's
         basis = reshape([basis, [real(dp) :: (0.0_dp, k = 1, n * r)]], [n, size(basis, 2) + r])
         basis(off + 1:off + nh, size(basis, 2) - r + 1:) = bp
         do k = 1, size(pinned)
            map(off + pinned(k)) = (pl - 1) * r1 + k
         end do
      end do
      call reduced_model(full, basis, map, red, err)
   end subroutine reduce_model

   !> The modes of one plane of a two-plane structure (its block of K and M), or of the whole
   !> structure with one plane.
   subroutine plane_modes(sys, plane, modes, err)
      type(system_t), intent(in) :: sys               !! assembled structure
      integer, intent(in) :: plane                    !! 1 (w) or 2 (v)
      type(modes_t), intent(out) :: modes             !! its modes
      type(error_t), allocatable, intent(out) :: err  !! eigen failure
      type(system_t) :: sub
      if (sys%planes == 1) then
         call solve_modes(sys, modes, err)
      else
         call plane_system(sys, plane, sub)
         call solve_modes(sub, modes, err)
      end if
   end subroutine plane_modes

   !> The planar system of one plane of a two-plane structure: its diagonal blocks of K and M
   !> (the planes are uncoupled), its influence vector and its tip dof.
   subroutine plane_system(sys, plane, sub)
      type(system_t), intent(in) :: sys      !! two-plane structure
      integer, intent(in) :: plane           !! 1 (w) or 2 (v)
      type(system_t), intent(out) :: sub     !! one plane
      integer :: nh, off
      nh = sys%n_dof / 2
      off = (plane - 1) * nh
      sub%n_dof = nh
      sub%n_node = sys%n_node
      sub%kd = sys%kd
      sub%planes = 1
      sub%k = sys%k(off + 1:off + nh, off + 1:off + nh)
      sub%m = sys%m(off + 1:off + nh, off + 1:off + nh)
      call dense_to_band(sub%k, sub%kd, sub%k_band)
      call dense_to_band(sub%m, sub%kd, sub%m_band)
      sub%m_diagonal = sys%m_diagonal
      if (plane == 1) then
         sub%r = sys%r(1:nh)
         sub%tip_dof = sys%tip_dof
      else
         sub%r = sys%r_v(nh + 1:)
         sub%tip_dof = max(0, sys%tip_dof_v - nh)
      end if
      allocate(sub%r_v(nh), sub%strain_row(nh), source=0.0_dp)
      sub%fibre_distance = sys%fibre_distance
      sub%element_length = sys%element_length
   end subroutine plane_system

   !> The dofs that get a residual attachment mode: every contact dof (both directions of a
   !> ring), with two planes the w and v of every support node, and the dofs of the point
   !> forces; in the order the model lists them, without repeats.
   function attachment_dofs(full) result(dofs)
      type(model_t), intent(in) :: full     !! full model
      integer, allocatable :: dofs(:)
      integer :: k
      dofs = [integer ::]
      call append(dofs, full%slot_dof)
      if (full%sys%planes > 1 .and. allocated(full%stop_dofs)) then
         do k = 1, size(full%stop_dofs, 2)
            call append(dofs, full%stop_dofs(:, k))
         end do
      end if
      if (allocated(full%p_sin)) call append(dofs, pack([(k, k = 1, full%n)], &
         full%p_sin /= 0.0_dp .or. full%p_cos /= 0.0_dp))
   end function attachment_dofs

   !> Pinned dofs (coordinates kept physical) and attachment dofs of a plane: with one plane
   !> the model's own dofs (the contact dofs, then the tip, then the point forces), with two
   !> planes the w-plane representatives of both planes' dofs (the v dof of a node stands for
   !> its w dof), the same list serving both planes.
   subroutine reduction_dofs(full, pinned, attach)
      type(model_t), intent(in) :: full               !! full model
      integer, allocatable, intent(out) :: pinned(:)  !! plane-local dofs kept physical
      integer, allocatable, intent(out) :: attach(:)  !! plane-local attachment dofs
      integer, allocatable :: all(:)
      integer :: nh
      all = attachment_dofs(full)
      if (full%sys%planes == 1) then
         attach = [integer ::]
         call append(attach, all)
         pinned = [integer ::]
         call append(pinned, full%slot_dof)
         call append(pinned, [full%sys%tip_dof])
         call append(pinned, all)
         return
      end if
      nh = full%n / 2
      attach = [integer ::]
      call append(attach, plane_local(all, nh))
      pinned = [integer ::]
      call append(pinned, plane_local(full%slot_dof, nh))
      call append(pinned, plane_local([full%sys%tip_dof, full%sys%tip_dof_v], nh))
      call append(pinned, attach)
   end subroutine reduction_dofs

   !> Plane-local index (1..nh) of global dofs of a two-plane model; 0 (none) stays 0.
   pure function plane_local(g, nh) result(l)
      integer, intent(in) :: g(:)     !! global dofs
      integer, intent(in) :: nh       !! dofs per plane
      integer :: l(size(g))
      l = merge(g - nh, g, g > nh)
   end function plane_local

   !> Append the positive entries of `new` that `list` does not hold yet, in order.
   pure subroutine append(list, new)
      integer, allocatable, intent(inout) :: list(:)   !! list
      integer, intent(in) :: new(:)                    !! candidates
      integer :: k
      do k = 1, size(new)
         if (new(k) <= 0) cycle
         if (any(list == new(k))) cycle
         list = [list, new(k)]
      end do
   end subroutine append

   !> The basis of one plane: its `keep` lowest modes and the residual attachment modes of the
   !> attachment dofs, transformed so that column j is the displacement of dof pinned(j).
   subroutine plane_basis(k, modes, keep, static_correction, attach, pinned, basis, err)
      real(dp), intent(in) :: k(:, :)                  !! the plane's stiffness
      type(modes_t), intent(in) :: modes               !! its modes
      integer, intent(in) :: keep                      !! modes kept
      logical, intent(in) :: static_correction         !! add the attachment modes
      integer, intent(in) :: attach(:)                 !! attachment dofs
      integer, intent(in) :: pinned(:)                 !! dofs kept physical
      real(dp), allocatable, intent(out) :: basis(:, :)  !! (n, r)
      type(error_t), allocatable, intent(out) :: err   !! not definite, singular selection
      real(dp), allocatable :: b(:, :), att(:, :), kf(:, :)
      integer :: n, ns, j, i, info
      real(dp) :: nrm, nrm0
      n = size(k, 1);  ns = size(attach)
      b = modes%shapes(:, 1:keep)
      if (static_correction .and. ns > 0) then
         ! K^-1 e_j minus what the kept modes represent (mass-normalised: Phi Lambda^-1 Phi')
         kf = k
         allocate(att(n, ns), source=0.0_dp)
         do j = 1, ns
            att(attach(j), j) = 1.0_dp
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
            do i = 1, keep
               att(:, j) = att(:, j) - b(:, i) * (b(attach(j), i) / modes%omega2(i))
            end do
            ! keep it unless the kept modes already represent this flexibility
            nrm = maxval(abs(att(:, j)))
            if (nrm > 1.0e-8_dp * nrm0) b = reshape([b, att(:, j) / nrm], [n, size(b, 2) + 1])
         end do
      end if
      call pin_coordinates(b, pinned, basis, err)
   end subroutine plane_basis

   !> The basis b transformed, B T, so that coordinate j is the displacement of dof pinned(j):
   !> for each pinned dof, the basis vector of the largest pivot is exchanged for it.
   subroutine pin_coordinates(b, pinned, basis, err)
      real(dp), intent(in) :: b(:, :)                  !! basis (n, r)
      integer, intent(in) :: pinned(:)                 !! dofs kept physical
      real(dp), allocatable, intent(out) :: basis(:, :)  !! (n, r), pinned rows unit vectors
      type(error_t), allocatable, intent(out) :: err   !! too few vectors, singular selection
      real(dp), allocatable :: tinv(:, :), cb(:, :), t(:, :), kf(:, :)
      integer, allocatable :: ipiv(:)
      logical, allocatable :: used(:)
      integer :: n, j, i, r, info, k, best
      real(dp) :: big
      n = size(b, 1);  r = size(b, 2)
      if (size(pinned) > r) then
         call fatal_error(err, 'gapbeam_reduction: ' // str(r) // ' basis vectors cannot ' &
            // 'carry ' // str(size(pinned)) // ' support, force and tip displacements: keep ' &
            // 'more modes')
         return
      end if
      ! choose, for each pinned dof, a basis vector to exchange for it (largest pivot)
      cb = b(pinned, :)
      allocate(used(r), source=.false.)
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
               // str(pinned(k)) // ' independently of the other supports: keep more modes ' &
               // 'or add the static correction')
            return
         end if
         used(best) = .true.
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
   end subroutine pin_coordinates

   !> The reduced model_t: matrices and loads projected on the basis, every dof index of the
   !> full model renumbered by `map` (full dof -> coordinate; 0 where not kept physical).
   subroutine reduced_model(full, basis, map, red, err)
      type(model_t), intent(in) :: full                !! full model
      real(dp), intent(in) :: basis(:, :)              !! (n_full, n_red)
      integer, intent(in) :: map(:)                    !! pinned dof -> coordinate
      type(model_t), intent(out) :: red                !! reduced model
      type(error_t), allocatable, intent(out) :: err   !! the basis has no mass somewhere
      type(modes_t) :: modes
      real(dp), allocatable :: mf(:, :)
      integer :: r, info
      r = size(basis, 2)
      red = full
      red%reduced = .true.
      red%n = r
      red%sys%n_dof = r
      red%sys%n_node = 0
      red%sys%kd = max(r - 1, 0)
      red%sys%k = matmul(transpose(basis), matmul(full%sys%k, basis))
      red%sys%m = matmul(transpose(basis), matmul(full%sys%m, basis))
      red%sys%k = 0.5_dp * (red%sys%k + transpose(red%sys%k))
      red%sys%m = 0.5_dp * (red%sys%m + transpose(red%sys%m))
      mf = red%sys%m
      call dpotrf('U', r, mf, r, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_reduction: the reduced mass matrix is not positive ' &
            // 'definite (a static mode moves massless dofs only): keep fewer static modes')
         return
      end if
      call dense_to_band(red%sys%k, red%sys%kd, red%sys%k_band)
      call dense_to_band(red%sys%m, red%sys%kd, red%sys%m_band)
      red%sys%m_diagonal = .false.
      red%c = red%beta * red%sys%m + red%gamma * red%sys%k
      red%q = matmul(transpose(basis), full%q)
      call project(full, basis, full%sys%r, red%sys%r, err);  if (allocated(err)) return
      call project(full, basis, full%sys%r_v, red%sys%r_v, err);  if (allocated(err)) return
      red%sys%strain_row = matmul(full%sys%strain_row, basis)
      if (allocated(full%q_v)) red%q_v = matmul(transpose(basis), full%q_v)
      if (allocated(full%p_sin)) then
         red%p_sin = matmul(transpose(basis), full%p_sin)
         red%p_cos = matmul(transpose(basis), full%p_cos)
      end if
      red%sys%tip_dof = mapped(full%sys%tip_dof)
      red%sys%tip_dof_v = mapped(full%sys%tip_dof_v)
      red%c_dof = remap(full%c_dof)
      red%c_tdof = remap(full%c_tdof, .false.)
      red%slot_dof = remap(full%slot_dof)
      if (full%n_rings > 0) red%r_dof = reshape(remap(reshape(full%r_dof, [2 * full%n_rings])), &
                                                [2, full%n_rings])
      ! a planar stop on theta: its node's w is not a coordinate (no orbit is drawn in one plane)
      if (allocated(full%stop_dofs)) red%stop_dofs = reshape(remap(reshape(full%stop_dofs, &
         [size(full%stop_dofs)]), full%sys%planes > 1), shape(full%stop_dofs))
      call solve_modes(red%sys, modes, err);  if (allocated(err)) return
      red%omega_max = sqrt(maxval(modes%omega2))
   contains
      !> The coordinate of full dof g (0 stays 0); a dof the model uses must be pinned, unless
      !> `strict` is false (then 0).
      integer function mapped(g, strict)
         integer, intent(in) :: g
         logical, intent(in), optional :: strict
         mapped = 0
         if (g <= 0) return
         mapped = map(g)
         if (present(strict)) then
            if (.not. strict) return
         end if
         if (mapped == 0) error stop 'gapbeam_reduction:reduced_model: a dof of the model ' &
            // 'is not a coordinate of the reduced model'
      end function mapped
      !> mapped, elementwise.
      function remap(g, strict) result(z)
         integer, intent(in) :: g(:)
         logical, intent(in), optional :: strict
         integer :: z(size(g)), k
         do k = 1, size(g)
            z(k) = mapped(g(k), strict)
         end do
      end function remap
   end subroutine reduced_model

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
