!> Diagnostics of a forced run: period detection from the Poincare points.
module gapbeam_diagnostics
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: detect_period

contains

   !> Smallest period p <= p_max (in forcing periods) of a Poincare sequence, 0 if none.
   !>
   !> The last `n_test` points (all but the first p_max when fewer) are compared with the
   !> points p earlier; the sequence has period p when every such distance is below tol times
   !> the coordinate's scale (callers pass the size of the orbit, e.g. the range of the strain
   !> over a forcing period, so that a fixed point with round-off jitter has period 1).
   pure integer function detect_period(x, y, p_max, tol, n_test, scale_x, scale_y) result(p)
      real(dp), intent(in) :: x(:)      !! first coordinate of the points (e.g. strain)
      real(dp), intent(in) :: y(:)      !! second coordinate (e.g. strain rate)
      integer, intent(in) :: p_max      !! largest period tested
      real(dp), intent(in) :: tol       !! relative tolerance
      integer, intent(in) :: n_test     !! points tested
      real(dp), intent(in) :: scale_x   !! size of the orbit in x
      real(dp), intent(in) :: scale_y   !! size of the orbit in y
      integer :: n, first, q, i
      real(dp) :: sx, sy
      logical :: ok
      p = 0
      n = size(x)
      if (n < 2 * p_max + 1) return
      first = max(p_max + 1, n - n_test + 1)
      sx = max(scale_x, tiny(1.0_dp));  sy = max(scale_y, tiny(1.0_dp))
      do q = 1, p_max
         ok = .true.
         do i = first, n
            if (abs(x(i) - x(i - q)) > tol * sx .or. abs(y(i) - y(i - q)) > tol * sy) then
               ok = .false.;  exit
            end if
         end do
         if (ok) then
            p = q;  return
         end if
      end do
   end function detect_period
end module gapbeam_diagnostics
