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
   !> points p earlier; the sequence has period p when every such distance, in each coordinate,
   !> is below tol times the coordinate's range over the tested points (the attractor's size).
   !> A sequence whose range is zero (a fixed point) has period 1.
   pure integer function detect_period(x, y, p_max, tol, n_test) result(p)
      real(dp), intent(in) :: x(:)      !! first coordinate of the points (e.g. strain)
      real(dp), intent(in) :: y(:)      !! second coordinate (e.g. strain rate)
      integer, intent(in) :: p_max      !! largest period tested
      real(dp), intent(in) :: tol       !! relative tolerance
      integer, intent(in) :: n_test     !! points tested
      integer :: n, first, q, i
      real(dp) :: rx, ry, sx, sy
      logical :: ok
      p = 0
      n = size(x)
      if (n < 2 * p_max + 1) return
      first = max(p_max + 1, n - n_test + 1)
      rx = maxval(x(first - p_max:n)) - minval(x(first - p_max:n))
      ry = maxval(y(first - p_max:n)) - minval(y(first - p_max:n))
      sx = max(rx, tiny(1.0_dp));  sy = max(ry, tiny(1.0_dp))
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
