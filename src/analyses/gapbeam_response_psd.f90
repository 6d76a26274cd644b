!> The response spectral density at chosen nodes (&turbulence psd_nodes, docs/flow.md): the
!> displacement of each node (w, and v in a two-plane model) at the history samples of a
!> draw, mapped from the model's coordinates (the reduced basis's row of the node's dof on a
!> reduced model), its one-sided PSD (Welch: Hann segments of a power of two samples, 50 %
!> overlap; or the periodogram of the whole history, gapbeam_draw_statistics), and the mean
!> over the draws with the 95 % half-width at every frequency (Student t).
module gapbeam_response_psd
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t, global_dof
   use gapbeam_description, only: dof_w, dof_v, n_psd_nodes
   use gapbeam_results, only: transient_result_t
   use gapbeam_flow_results, only: response_psd_t
   use gapbeam_model_builder, only: build_model, build_full_model
   use gapbeam_draw_statistics, only: welch_psd, periodogram_psd, mean_half_width
   implicit none
   private
   public :: psd_rows, add_draw_psd, finish_psd, segment_length

contains

   !> The rows of the PSD series: series s is rows(:, s)' u, the displacement of node
   !> nodes(s) in plane planes(s) (zero where that dof is fixed).
   subroutine psd_rows(deck, rows, psd, err)
      type(deck_t), intent(in) :: deck                   !! deck with psd_nodes
      real(dp), allocatable, intent(out) :: rows(:, :)   !! (n_model, n_series)
      type(response_psd_t), intent(out) :: psd           !! nodes, planes, method set
      type(error_t), allocatable, intent(out) :: err     !! build failure
      type(model_t) :: full, model
      real(dp), allocatable :: basis(:, :), u0(:), v0(:)
      integer :: k, p, s, dof, n_planes
      call build_full_model(deck%structure, deck%stops, deck%damping, deck%forcing, full, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err, basis_out=basis)
      if (allocated(err)) return
      n_planes = full%sys%planes
      allocate(rows(model%n, n_psd_nodes(deck%turbulence) * n_planes), source=0.0_dp)
      allocate(psd%nodes(size(rows, 2)), psd%planes(size(rows, 2)))
      psd%method = deck%turbulence%psd_method
      s = 0
      do k = 1, n_psd_nodes(deck%turbulence)
         do p = 1, n_planes
            s = s + 1
            psd%nodes(s) = deck%turbulence%psd_nodes(k)
            psd%planes(s) = p
            dof = global_dof(full%sys, psd%nodes(s), merge(dof_w, dof_v, p == 1))
            if (dof == 0) cycle
            if (allocated(basis)) then
               rows(:, s) = basis(dof, :)
            else
               rows(dof, s) = 1.0_dp
            end if
         end do
      end do
   end subroutine psd_rows

   !> The Welch segment of n history samples at dt: the power of two nearest 1/(resolution
   !> dt), at most n; without a resolution the largest power of two <= n / 4 (at least 8, at
   !> most n).
   pure integer function segment_length(deck, n, dt) result(m)
      type(deck_t), intent(in) :: deck   !! deck
      integer, intent(in) :: n           !! history samples
      real(dp), intent(in) :: dt         !! sample interval [s]
      real(dp) :: want
      if (deck%turbulence%psd_resolution_hz > 0.0_dp) then
         want = 1.0_dp / (deck%turbulence%psd_resolution_hz * dt)
      else
         want = 0.25_dp * real(n, dp)
      end if
      m = 8
      do while (2 * m <= n .and. real(2 * m, dp) <= want * sqrt(2.0_dp))
         m = 2 * m
      end do
      if (deck%turbulence%psd_resolution_hz <= 0.0_dp) then
         do while (m > 8 .and. 4 * m > n)
            m = m / 2
         end do
      end if
      m = min(m, n)
   end function segment_length

   !> The PSD of every series of draw `res` (state history on) appended to psd%draws.
   subroutine add_draw_psd(deck, res, rows, psd, err)
      type(deck_t), intent(in) :: deck                   !! deck
      type(transient_result_t), intent(in) :: res        !! the draw's record
      real(dp), intent(in) :: rows(:, :)                 !! (n_model, n_series)
      type(response_psd_t), intent(inout) :: psd         !! the PSD so far
      type(error_t), allocatable, intent(out) :: err     !! too short a history
      real(dp), allocatable :: x(:, :), f(:), p(:), grown(:, :, :)
      real(dp) :: dt
      integer :: s, n
      n = 0
      if (allocated(res%history_u) .and. allocated(res%time)) n = size(res%time)
      if (n < 16) then
         call fatal_error(err, 'group &turbulence: psd_nodes: the history holds ' &
            // str(n) // ' samples, too few for a spectrum: raise &output ' &
            // 'history_periods or samples_per_period')
         return
      end if
      dt = res%time(2) - res%time(1)
      x = matmul(transpose(rows), res%history_u(:, 1:n))
      do s = 1, size(rows, 2)
         if (psd%method == 'periodogram') then
            call periodogram_psd(x(s, :), dt, f, p)
         else
            call welch_psd(x(s, :), dt, segment_length(deck, n, dt), f, p)
         end if
         if (s == 1) then
            if (.not. allocated(psd%draws)) then
               allocate(psd%draws(size(p), size(rows, 2), 0))
               psd%frequency_hz = f
            end if
            if (size(p) /= size(psd%draws, 1)) then
               call fatal_error(err, 'group &turbulence: psd_nodes: the draws'' histories ' &
                  // 'differ in length')
               return
            end if
            allocate(grown(size(p), size(rows, 2), size(psd%draws, 3) + 1))
            grown(:, :, 1:size(psd%draws, 3)) = psd%draws
         end if
         grown(:, s, size(grown, 3)) = p
      end do
      call move_alloc(grown, psd%draws)
      psd%n_draws = size(psd%draws, 3)
   end subroutine add_draw_psd

   !> The mean over the draws and its 95 % half-width at every frequency of every series.
   subroutine finish_psd(psd)
      type(response_psd_t), intent(inout) :: psd        !! with its draws
      integer :: k, s
      allocate(psd%psd(size(psd%draws, 1), size(psd%draws, 2)))
      allocate(psd%half_width, mold=psd%psd)
      do s = 1, size(psd%draws, 2)
         do k = 1, size(psd%draws, 1)
            call mean_half_width(psd%draws(k, s, :), psd%psd(k, s), psd%half_width(k, s))
         end do
      end do
   end subroutine finish_psd
end module gapbeam_response_psd
