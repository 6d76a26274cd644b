!> How small can the model be for the question asked? A ladder of models of the same
!> structure (element counts, and modal models of the finest mesh with and without static
!> correction) run on the same forcing case and compared with the finest model.
!>
!> Per candidate: natural frequencies below a cut-off against the finest model's (largest
!> relative error), the period or label and the largest Lyapunov exponent of the response,
!> the distance of its Poincare set to the finest model's, the peak stop force, and the
!> elapsed time. The Poincare distance is the modified Hausdorff distance of Dubuisson and
!> Jain: the larger of the two mean nearest-neighbour distances (candidate to reference and
!> back) in the plane (strain, strain rate), each axis scaled by the range of the reference's
!> root strain (and strain rate) over the recorded motion, i.e. by the size of its orbit. The
!> recommended model is the one with the fewest coordinates (then the least time)
!> whose frequency error, label, Poincare distance and peak force all meet the tolerances.
module gapbeam_model_size
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: model_size_settings_t
   use gapbeam_results, only: modes_t, transient_result_t, point_result_t, candidate_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_eigen, only: solve_modes
   use gapbeam_transient, only: integrate
   use gapbeam_attractor, only: point_diagnostics
   implicit none
   private
   public :: model_size_study, poincare_distance

contains

   !> Run the ladder; `best` is the recommended candidate (0 if none meets the tolerances).
   subroutine model_size_study(deck, ms, cands, best, err)
      type(deck_t), intent(in) :: deck                 !! the case (its stops at nodes by x)
      type(model_size_settings_t), intent(in) :: ms    !! ladder and tolerances
      type(candidate_t), allocatable, intent(out) :: cands(:)  !! ladder, reference last
      integer, intent(out) :: best                     !! recommended candidate
      type(error_t), allocatable, intent(out) :: err   !! a model cannot be built
      type(deck_t) :: d
      type(modes_t) :: ref_modes
      type(point_result_t), allocatable :: pts(:)
      integer :: nc, k, finest, j
      real(dp), allocatable :: ref_ps(:), ref_pr(:)
      real(dp) :: sx, sy
      finest = maxval(ms%elements)
      nc = size(ms%elements) + 2 * size(ms%modes)
      allocate(cands(nc), pts(nc))
      k = 0
      do j = 1, size(ms%elements)
         k = k + 1
         cands(k)%n_elem = ms%elements(j);  cands(k)%name = str(ms%elements(j)) // ' elements'
      end do
      do j = 1, size(ms%modes)
         k = k + 1
         cands(k)%n_elem = finest;  cands(k)%n_modes = ms%modes(j)
         cands(k)%name = str(ms%modes(j)) // ' modes'
         k = k + 1
         cands(k)%n_elem = finest;  cands(k)%n_modes = ms%modes(j)
         cands(k)%static_correction = .true.
         cands(k)%name = str(ms%modes(j)) // ' modes + static'
      end do
      ! the reference: the finest mesh, full model
      call candidate_deck(deck, finest, 0, .false., d, err);  if (allocated(err)) return
      call run_candidate(d, pts(nc), ref_modes, cands(nc), err)   ! slot nc: scratch first
      if (allocated(err)) return
      ref_ps = pts(nc)%p_strain;  ref_pr = pts(nc)%p_strain_rate
      ! scales: the size of the reference orbit (its strain range over the record), so that a
      ! fixed point of the reference is compared against the motion's size, not zero
      sx = max(cands(nc)%strain_range, tiny(1.0_dp))
      sy = max(cands(nc)%strain_rate_range, tiny(1.0_dp))
      do k = 1, nc
         call candidate_deck(deck, cands(k)%n_elem, cands(k)%n_modes, &
                             cands(k)%static_correction, d, err)
         if (allocated(err)) return
         call run_candidate(d, pts(k), ref_modes, cands(k), err, ms%cutoff_hz)
         if (allocated(err)) then
            cands(k)%status = 1;  cands(k)%message = err%message
            deallocate(err)
            cycle
         end if
         cands(k)%poincare_distance = poincare_distance(pts(k)%p_strain, pts(k)%p_strain_rate, &
                                                        ref_ps, ref_pr, sx, sy)
      end do
      ! the reference candidate is the finest mesh in the element ladder
      best = 0
      do k = 1, nc
         if (cands(k)%status /= 0) cycle
         cands(k)%acceptable = cands(k)%frequency_error <= ms%frequency_tolerance .and. &
            cands(k)%label == reference_label(cands, finest) .and. &
            cands(k)%poincare_distance <= ms%poincare_tolerance .and. &
            abs(cands(k)%peak_force - reference_force(cands, finest)) <= ms%force_tolerance &
            * reference_force(cands, finest)
         if (cands(k)%acceptable) then
            if (best == 0) then
               best = k
            else if (cands(k)%n_coordinates < cands(best)%n_coordinates .or. &
                     (cands(k)%n_coordinates == cands(best)%n_coordinates .and. &
                      cands(k)%seconds < cands(best)%seconds)) then
               best = k
            end if
         end if
      end do
   end subroutine model_size_study


   integer function reference_label(cands, finest)
      type(candidate_t), intent(in) :: cands(:)
      integer, intent(in) :: finest
      integer :: k
      reference_label = 0
      do k = 1, size(cands)
         if (cands(k)%n_elem == finest .and. cands(k)%n_modes == 0) reference_label = cands(k)%label
      end do
   end function reference_label

   real(dp) function reference_force(cands, finest)
      type(candidate_t), intent(in) :: cands(:)
      integer, intent(in) :: finest
      integer :: k
      reference_force = 0.0_dp
      do k = 1, size(cands)
         if (cands(k)%n_elem == finest .and. cands(k)%n_modes == 0) &
            reference_force = cands(k)%peak_force
      end do
   end function reference_force

   !> The deck with another mesh (stops and initial values moved to the node at the same x)
   !> and reduction.
   subroutine candidate_deck(deck, n_elem, n_modes, static_correction, d, err)
      type(deck_t), intent(in) :: deck
      integer, intent(in) :: n_elem, n_modes
      logical, intent(in) :: static_correction
      type(deck_t), intent(out) :: d
      type(error_t), allocatable, intent(out) :: err
      integer :: i
      d = deck
      d%structure%beam%n_elem = n_elem
      do i = 1, size(d%stops)
         d%stops(i)%node = move_node(deck%structure%beam%n_elem, n_elem, deck%stops(i)%node, &
            'stop ' // str(i), err)
      end do
      if (allocated(d%structure%springs)) then
         do i = 1, size(d%structure%springs)
            d%structure%springs(i)%node = move_node(deck%structure%beam%n_elem, n_elem, &
               deck%structure%springs(i)%node, 'spring ' // str(i), err)
         end do
      end if
      if (allocated(d%structure%masses)) then
         do i = 1, size(d%structure%masses)
            d%structure%masses(i)%node = move_node(deck%structure%beam%n_elem, n_elem, &
               deck%structure%masses(i)%node, 'mass ' // str(i), err)
         end do
      end if
      if (allocated(d%initial%node)) then
         do i = 1, size(d%initial%node)
            d%initial%node(i) = move_node(deck%structure%beam%n_elem, n_elem, &
               deck%initial%node(i), 'initial value ' // str(i), err)
         end do
      end if
      if (n_modes > 0) then
         d%reduction%kind = 'modal';  d%reduction%n_modes = n_modes
         d%reduction%static_correction = static_correction
      else
         d%reduction%kind = 'none'
      end if
   end subroutine candidate_deck

   !> The node of an n_elem-element mesh at the position of `node` of an n_from-element mesh;
   !> an error (kept if one is already set) when that position is not a node of the new mesh.
   integer function move_node(n_from, n_elem, node, what, err)
      integer, intent(in) :: n_from, n_elem              !! element counts of the two meshes
      integer, intent(in) :: node                        !! node of the first mesh
      character(len=*), intent(in) :: what               !! what sits there, for the message
      type(error_t), allocatable, intent(inout) :: err   !! not a node
      real(dp) :: x
      x = real(node - 1, dp) / real(n_from, dp)
      move_node = nint(x * n_elem) + 1
      if (abs(real(move_node - 1, dp) - x * n_elem) > 1.0e-9_dp .and. .not. allocated(err)) &
         call fatal_error(err, 'model_size: ' // what // ' at x/L = ' // str(x) // ' is not ' &
         // 'a node of the ' // str(n_elem) // '-element mesh; choose element counts whose ' &
         // 'nodes include it')
   end function move_node

   !> Build, run and diagnose one candidate.
   subroutine run_candidate(d, pr, ref_modes, cand, err, cutoff_hz)
      type(deck_t), intent(in) :: d
      type(point_result_t), intent(out) :: pr
      type(modes_t), intent(inout) :: ref_modes
      type(candidate_t), intent(inout) :: cand
      type(error_t), allocatable, intent(out) :: err
      real(dp), intent(in), optional :: cutoff_hz
      type(model_t) :: model
      type(transient_result_t) :: res
      type(modes_t) :: modes
      real(dp), allocatable :: u0(:), v0(:)
      integer :: j, m
      call build_model(d, model, u0, v0, err);  if (allocated(err)) return
      cand%n_coordinates = model%n
      call solve_modes(model%sys, modes, err);  if (allocated(err)) return
      if (.not. present(cutoff_hz)) then
         ref_modes = modes
      else
         m = 0;  cand%frequency_error = 0.0_dp
         do j = 1, min(modes%n_modes, ref_modes%n_modes)
            if (ref_modes%frequency_hz(j) > cutoff_hz) exit
            m = j
            cand%frequency_error = max(cand%frequency_error, abs(modes%frequency_hz(j) &
               - ref_modes%frequency_hz(j)) / ref_modes%frequency_hz(j))
         end do
         if (m < count(ref_modes%frequency_hz <= cutoff_hz)) cand%frequency_error = huge(1.0_dp)
         cand%n_compared = m
      end if
      call integrate(model, d%solver, d%output, u0, v0, res, err)
      if (allocated(err)) return
      cand%seconds = res%cpu_seconds
      cand%strain_range = res%strain_max - res%strain_min
      cand%strain_rate_range = res%strain_rate_max - res%strain_rate_min
      pr%p_strain = res%p_strain;  pr%p_strain_rate = res%p_strain_rate
      call point_diagnostics(model, d%solver, d%diagnostics, res, pr, err)
      if (allocated(err)) return
      cand%period = pr%period;  cand%label = pr%label;  cand%lyapunov = pr%lyapunov
      cand%peak_force = 0.0_dp
      if (size(res%peak_force) > 0) cand%peak_force = res%peak_force(1)
   end subroutine run_candidate

   !> Modified Hausdorff distance of two point sets in the scaled (x, y) plane.
   pure real(dp) function poincare_distance(xa, ya, xb, yb, sx, sy) result(dist)
      real(dp), intent(in) :: xa(:), ya(:)    !! first set
      real(dp), intent(in) :: xb(:), yb(:)    !! second set
      real(dp), intent(in) :: sx, sy          !! scales of x and y
      dist = max(mean_nearest(xa, ya, xb, yb), mean_nearest(xb, yb, xa, ya))
   contains
      pure real(dp) function mean_nearest(x1, y1, x2, y2) result(m)
         real(dp), intent(in) :: x1(:), y1(:), x2(:), y2(:)
         integer :: i
         m = 0.0_dp
         do i = 1, size(x1)
            m = m + sqrt(minval(((x2 - x1(i)) / sx)**2 + ((y2 - y1(i)) / sy)**2))
         end do
         m = m / max(1, size(x1))
      end function mean_nearest
   end function poincare_distance
end module gapbeam_model_size
