!> The statistics over random draws of the points of a sweep file (docs/flow.md), written
!> and read back (merges keep them): /sweep/statistics/draws (draws per point, 0 for a point
!> without), /sweep/statistics/NAME (point, stop) with NAME_ci, for every output of
!> gapbeam_flow_results' list, the tip's RMS displacement one value per point. Written only
!> when some point of the file has draws.
module gapbeam_sweep_statistics
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use gapbeam_kinds, only: dp
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_results, only: point_result_t
   use gapbeam_flow_results, only: n_draw_outputs, draw_output_names
   implicit none
   private
   public :: write_sweep_statistics, read_sweep_statistics

contains

   !> /sweep/statistics of the file's points (NaN where a point has none), when any has.
   subroutine write_sweep_statistics(h5, results, points, ns)
      type(h5_writer_t), intent(inout) :: h5             !! writer
      type(point_result_t), intent(in) :: results(:)     !! all points
      integer, intent(in) :: points(:)                   !! the points of the file
      integer, intent(in) :: ns                          !! stops
      real(dp), allocatable :: m(:, :), c(:, :)
      integer, allocatable :: nd(:)
      integer :: j, k, n_items
      nd = [(results(points(j))%n_draws, j = 1, size(points))]
      if (all(nd == 0)) return
      call h5%put('/sweep/statistics/draws', nd)
      do k = 1, n_draw_outputs
         n_items = ns
         if (k == n_draw_outputs) n_items = 1
         allocate(m(n_items, size(points)), c(n_items, size(points)))
         m = ieee_value(1.0_dp, ieee_quiet_nan);  c = m
         do j = 1, size(points)
            associate (r => results(points(j)))
               if (r%n_draws == 0 .or. .not. allocated(r%draw_mean)) cycle
               if (size(r%draw_mean, 1) < n_items) cycle
               m(:, j) = r%draw_mean(1:n_items, k)
               c(:, j) = r%draw_ci(1:n_items, k)
            end associate
         end do
         if (k == n_draw_outputs) then
            call h5%put('/sweep/statistics/' // trim(draw_output_names(k)), m(1, :))
            call h5%put('/sweep/statistics/' // trim(draw_output_names(k)) // '_ci', c(1, :))
         else
            call h5%put('/sweep/statistics/' // trim(draw_output_names(k)), m)
            call h5%put('/sweep/statistics/' // trim(draw_output_names(k)) // '_ci', c)
         end if
         deallocate(m, c)
      end do
   end subroutine write_sweep_statistics

   !> The statistics of the file's points back into `results` (nothing when the file has
   !> none); `ok` is false when a dataset does not have one entry per point.
   subroutine read_sweep_statistics(h5, results, points, ok)
      type(h5_reader_t), intent(inout) :: h5             !! open file
      type(point_result_t), intent(inout) :: results(:)  !! all points
      integer, intent(in) :: points(:)                   !! the points of the file
      logical, intent(out) :: ok                         !! well formed
      integer, allocatable :: nd(:)
      real(dp), allocatable :: m(:, :), c(:, :), m1(:), c1(:)
      integer :: j, k, ni
      ok = .true.
      if (.not. h5%exists('/sweep/statistics/draws')) return
      call h5%read('/sweep/statistics/draws', nd)
      ok = size(nd) == size(points)
      if (.not. ok) return
      call h5%read('/sweep/statistics/' // trim(draw_output_names(1)), m)
      ni = size(m, 1)
      ok = size(m, 2) == size(points)
      if (.not. ok) return
      do j = 1, size(points)
         associate (r => results(points(j)))
            r%n_draws = nd(j)
            if (nd(j) == 0) cycle
            allocate(r%draw_mean(max(ni, 1), n_draw_outputs), source=0.0_dp)
            allocate(r%draw_ci(max(ni, 1), n_draw_outputs), source=0.0_dp)
         end associate
      end do
      do k = 1, n_draw_outputs
         if (k == n_draw_outputs) then
            call h5%read('/sweep/statistics/' // trim(draw_output_names(k)), m1)
            call h5%read('/sweep/statistics/' // trim(draw_output_names(k)) // '_ci', c1)
            ok = size(m1) == size(points) .and. size(c1) == size(points)
         else
            call h5%read('/sweep/statistics/' // trim(draw_output_names(k)), m)
            call h5%read('/sweep/statistics/' // trim(draw_output_names(k)) // '_ci', c)
            ok = all(shape(m) == [ni, size(points)]) .and. all(shape(c) == shape(m))
         end if
         if (.not. ok) return
         do j = 1, size(points)
            associate (r => results(points(j)))
               if (r%n_draws == 0) cycle
               if (k == n_draw_outputs) then
                  r%draw_mean(1, k) = m1(j);  r%draw_ci(1, k) = c1(j)
               else if (ni > 0) then
                  r%draw_mean(1:ni, k) = m(:, j);  r%draw_ci(1:ni, k) = c(:, j)
               end if
            end associate
         end do
      end do
   end subroutine read_sweep_statistics
end module gapbeam_sweep_statistics
