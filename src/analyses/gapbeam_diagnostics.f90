!> Diagnostics of a forced run: period detection from the Poincare points.
module gapbeam_diagnostics
   use gapbeam_kinds, only: dp
   use gapbeam_results, only: label_chaotic, label_undecided
   implicit none
   private
   public :: detect_period, classify

contains

   !> Label code of a run: its period p >= 1 if periodic; label_chaotic when no period is
   !> found and the largest Lyapunov exponent is positive beyond `sigmas` times its
   !> uncertainty; label_undecided otherwise (e.g. quasi-periodic, or a long transient).
   pure integer function classify(period, exponent, uncertainty, sigmas) result(code)
      integer, intent(in) :: period          !! detected period (0: none)
      real(dp), intent(in) :: exponent       !! largest Lyapunov exponent [1/s]
      real(dp), intent(in) :: uncertainty    !! its standard error [1/s]
      real(dp), intent(in) :: sigmas         !! how many standard errors above zero
      if (period > 0) then
         code = period
      else if (exponent > 0.0_dp .and. exponent > sigmas * uncertainty) then
         code = label_chaotic
      else
         code = label_undecided
      end if
   end function classify


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
      integer :: n, first, q, i, pm
      real(dp) :: sx, sy
      logical :: ok
      p = 0
      n = size(x)
      pm = min(p_max, (n - 1) / 2)   ! a short record tests the periods it can show twice
      if (pm < 1) return
      first = max(pm + 1, n - n_test + 1)
      sx = max(scale_x, tiny(1.0_dp));  sy = max(scale_y, tiny(1.0_dp))
      do q = 1, pm
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
