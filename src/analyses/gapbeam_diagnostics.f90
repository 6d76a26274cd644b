!> Diagnostics of a forced run from its Poincare points: period detection, the settling test
!> (statistics of successive windows of the record), distances between two attractors, and
!> the label that combines them with the largest Lyapunov exponent. Pure procedures only.
!>
!> Every distance is relative to the size of the orbit, per coordinate: the range of the root
!> strain and of its rate over the record (S_x, S_y), and the larger of the two coordinates'
!> relative distances is taken (a Chebyshev distance in scaled coordinates).
module gapbeam_diagnostics
   use gapbeam_kinds, only: dp
   use gapbeam_results, only: label_chaotic, label_undecided, label_unsettled
   implicit none
   private
   public :: detect_period, period_search, classify, window_difference, orbit_distance, &
      statistics_distance, repeat_distance

   integer, parameter :: n_statistics = 10   !! mean, std, 10/50/90 % quantiles of x and y

contains

   !> Label code of a run: its period p >= 1 if periodic; label_chaotic when no period is
   !> found and the largest Lyapunov exponent is positive beyond `sigmas` times its
   !> uncertainty; label_unsettled when the transient did not settle; label_undecided
   !> otherwise (quasi-periodic, a period longer than those tried, an exponent not clearly
   !> positive, or no exponent).
   pure integer function classify(period, exponent, uncertainty, sigmas, settled, has_exponent) &
         result(code)
      integer, intent(in) :: period          !! detected period (0: none)
      real(dp), intent(in) :: exponent       !! largest Lyapunov exponent [1/s]
      real(dp), intent(in) :: uncertainty    !! its standard error [1/s]
      real(dp), intent(in) :: sigmas         !! how many standard errors above zero
      logical, intent(in) :: settled         !! the settling test passed (or was not asked)
      logical, intent(in) :: has_exponent    !! the exponent was computed
      if (.not. settled) then
         code = label_unsettled
      else if (period > 0) then
         code = period
      else if (has_exponent .and. exponent > 0.0_dp .and. exponent > sigmas * uncertainty) then
         code = label_chaotic
      else
         code = label_undecided
      end if
   end function classify

   !> Smallest period p <= p_max (in forcing periods) of a Poincare sequence, 0 if none.
   pure integer function detect_period(x, y, p_max, tol, n_test, scale_x, scale_y) result(p)
      real(dp), intent(in) :: x(:)      !! first coordinate of the points (e.g. strain)
      real(dp), intent(in) :: y(:)      !! second coordinate (e.g. strain rate)
      integer, intent(in) :: p_max      !! largest period tested
      real(dp), intent(in) :: tol       !! relative tolerance
      integer, intent(in) :: n_test     !! points tested (at least 2 periods' worth)
      real(dp), intent(in) :: scale_x   !! size of the orbit in x
      real(dp), intent(in) :: scale_y   !! size of the orbit in y
      integer :: closest, tested
      real(dp) :: distance
      call period_search(x, y, p_max, tol, n_test, scale_x, scale_y, p, closest, distance, &
                         tested)
   end function detect_period

   !> Period search with its evidence.
   !>
   !> Candidate q = 1 .. p_t, p_t = min(p_max, n/3) (a record shows every period tried at
   !> least three times): the last max(n_test, 2q) points (never the first q) are compared
   !> with the points q periods earlier, and the repeat distance of q is the largest of those
   !> distances, relative to the orbit size (callers pass the range of each coordinate over
   !> the record, so that a fixed point with round-off jitter has period 1). The period is the
   !> smallest q whose repeat distance is <= tol (0: none); `closest` is the q with the
   !> smallest repeat distance and `distance` that distance, which says how far from periodic
   !> a record without a period is.
   pure subroutine period_search(x, y, p_max, tol, n_test, scale_x, scale_y, p, closest, &
                                 distance, tested)
      real(dp), intent(in) :: x(:), y(:)     !! Poincare points
      integer, intent(in) :: p_max           !! largest period asked for
      real(dp), intent(in) :: tol            !! relative tolerance
      integer, intent(in) :: n_test          !! points tested per candidate (at least 2q)
      real(dp), intent(in) :: scale_x, scale_y  !! orbit size per coordinate
      integer, intent(out) :: p              !! period found (0: none)
      integer, intent(out) :: closest        !! candidate with the smallest repeat distance
      real(dp), intent(out) :: distance      !! that distance [-]
      integer, intent(out) :: tested         !! candidates tried: 1 .. tested
      integer :: n, first, q, i
      real(dp) :: sx, sy, dq
      p = 0;  closest = 0;  distance = huge(1.0_dp)
      n = size(x)
      tested = max(0, min(p_max, n / 3))
      sx = max(scale_x, tiny(1.0_dp));  sy = max(scale_y, tiny(1.0_dp))
      do q = 1, tested
         first = max(q + 1, n - max(n_test, 2 * q) + 1)
         dq = 0.0_dp
         do i = first, n
            dq = max(dq, abs(x(i) - x(i - q)) / sx, abs(y(i) - y(i - q)) / sy)
            if (dq > distance .and. dq > tol) exit   ! cannot be the closest, not periodic
         end do
         if (dq < distance) then
            distance = dq;  closest = q
         end if
         if (dq <= tol .and. p == 0) then
            p = q
            return
         end if
      end do
   end subroutine period_search

   !> Repeat distance of candidate period q: the largest distance between the last
   !> max(n_test, 2q) points (never the first q) and the points q periods earlier, relative
   !> to the orbit size (huge when the record is shorter than q + 1 points).
   pure real(dp) function repeat_distance(x, y, q, n_test, scale_x, scale_y) result(d)
      real(dp), intent(in) :: x(:), y(:)     !! Poincare points
      integer, intent(in) :: q               !! candidate period
      integer, intent(in) :: n_test          !! points tested (at least 2q)
      real(dp), intent(in) :: scale_x, scale_y  !! orbit size per coordinate
      integer :: n, i
      real(dp) :: sx, sy
      n = size(x)
      d = huge(1.0_dp)
      if (n < q + 1) return
      sx = max(scale_x, tiny(1.0_dp));  sy = max(scale_y, tiny(1.0_dp))
      d = 0.0_dp
      do i = max(q + 1, n - max(n_test, 2 * q) + 1), n
         d = max(d, abs(x(i) - x(i - q)) / sx, abs(y(i) - y(i - q)) / sy)
      end do
   end function repeat_distance

   !> Largest difference between the statistics of successive windows of a record and those
   !> of its last window, relative to the orbit size (the settling test).
   !>
   !> The record is cut into `n_windows` windows of equal length (the last points are the
   !> last window); with a period p each window is shortened to whole periods, so that the
   !> statistics of a periodic orbit are those of the same points in every window. The
   !> statistics of a window are the mean, standard deviation and 10, 50 and 90 % quantiles
   !> of each coordinate.
   pure real(dp) function window_difference(x, y, n_windows, period, scale_x, scale_y) &
         result(d)
      real(dp), intent(in) :: x(:), y(:)     !! Poincare points
      integer, intent(in) :: n_windows       !! windows (>= 2)
      integer, intent(in) :: period          !! period of the record (0: none)
      real(dp), intent(in) :: scale_x, scale_y  !! orbit size per coordinate
      real(dp) :: last(n_statistics), here(n_statistics)
      integer :: n, w, len_w, len_s, k, i1
      d = 0.0_dp
      n = size(x)
      len_w = n / max(1, n_windows)
      if (n_windows < 2 .or. len_w < 1) return
      len_s = len_w
      if (period > 0 .and. len_w >= period) len_s = (len_w / period) * period
      call statistics(x(n - len_s + 1:n), y(n - len_s + 1:n), last)
      do w = 1, n_windows - 1
         k = n - (n_windows - w + 1) * len_w     ! window w ends at k + len_w
         i1 = k + len_w - len_s + 1
         call statistics(x(i1:k + len_w), y(i1:k + len_w), here)
         d = max(d, scaled_difference(here, last, scale_x, scale_y))
      end do
   end function window_difference

   !> Distance between the statistics of two whole records (two attractors) [-].
   pure real(dp) function statistics_distance(xa, ya, xb, yb, scale_x, scale_y) result(d)
      real(dp), intent(in) :: xa(:), ya(:)   !! record a
      real(dp), intent(in) :: xb(:), yb(:)   !! record b
      real(dp), intent(in) :: scale_x, scale_y  !! orbit size per coordinate
      real(dp) :: sa(n_statistics), sb(n_statistics)
      call statistics(xa, ya, sa)
      call statistics(xb, yb, sb)
      d = scaled_difference(sa, sb, scale_x, scale_y)
   end function statistics_distance

   !> Distance between two periodic orbits of period p from their last p Poincare points: the
   !> largest distance from a point of either orbit to the nearest point of the other
   !> (Hausdorff), relative to the orbit size [-].
   pure real(dp) function orbit_distance(xa, ya, xb, yb, p, scale_x, scale_y) result(d)
      real(dp), intent(in) :: xa(:), ya(:)   !! orbit a
      real(dp), intent(in) :: xb(:), yb(:)   !! orbit b
      integer, intent(in) :: p               !! period (points compared from each)
      real(dp), intent(in) :: scale_x, scale_y  !! orbit size per coordinate
      integer :: na, nb, q
      na = size(xa);  nb = size(xb)
      q = min(p, na, nb)
      d = max(one_way(xa(na - q + 1:na), ya(na - q + 1:na), xb(nb - q + 1:nb), &
                      yb(nb - q + 1:nb), scale_x, scale_y), &
              one_way(xb(nb - q + 1:nb), yb(nb - q + 1:nb), xa(na - q + 1:na), &
                      ya(na - q + 1:na), scale_x, scale_y))
   end function orbit_distance

   !> Largest distance from a point of set 1 to the nearest point of set 2 [-].
   pure real(dp) function one_way(x1, y1, x2, y2, scale_x, scale_y) result(h)
      real(dp), intent(in) :: x1(:), y1(:)      !! set 1
      real(dp), intent(in) :: x2(:), y2(:)      !! set 2
      real(dp), intent(in) :: scale_x, scale_y  !! orbit size per coordinate
      integer :: i, j
      real(dp) :: m, sx, sy
      sx = max(scale_x, tiny(1.0_dp));  sy = max(scale_y, tiny(1.0_dp))
      h = 0.0_dp
      do i = 1, size(x1)
         m = huge(1.0_dp)
         do j = 1, size(x2)
            m = min(m, max(abs(x1(i) - x2(j)) / sx, abs(y1(i) - y2(j)) / sy))
         end do
         h = max(h, m)
      end do
   end function one_way

   !> Largest difference of two statistics vectors, each coordinate's relative to its scale.
   pure real(dp) function scaled_difference(a, b, scale_x, scale_y) result(d)
      real(dp), intent(in) :: a(n_statistics), b(n_statistics)   !! statistics
      real(dp), intent(in) :: scale_x, scale_y                   !! orbit size per coordinate
      integer, parameter :: half = n_statistics / 2
      d = max(maxval(abs(a(1:half) - b(1:half))) / max(scale_x, tiny(1.0_dp)), &
              maxval(abs(a(half + 1:) - b(half + 1:))) / max(scale_y, tiny(1.0_dp)))
   end function scaled_difference

   !> Mean, standard deviation and 10, 50, 90 % quantiles of x, then of y.
   pure subroutine statistics(x, y, s)
      real(dp), intent(in) :: x(:), y(:)           !! points
      real(dp), intent(out) :: s(n_statistics)     !! statistics
      call moments(x, s(1:5))
      call moments(y, s(6:10))
   end subroutine statistics

   !> Mean, standard deviation and 10, 50, 90 % quantiles of one coordinate.
   pure subroutine moments(z, t)
      real(dp), intent(in) :: z(:)     !! values
      real(dp), intent(out) :: t(5)    !! statistics
      real(dp), allocatable :: w(:)
      real(dp) :: mean
      integer :: n
      n = size(z)
      t = 0.0_dp
      if (n == 0) return
      mean = sum(z) / n
      t(1) = mean
      t(2) = sqrt(sum((z - mean)**2) / n)
      w = z
      call heap_sort(w)
      t(3) = quantile(w, 0.1_dp);  t(4) = quantile(w, 0.5_dp);  t(5) = quantile(w, 0.9_dp)
   end subroutine moments

   !> Quantile of sorted values, linear interpolation between order statistics.
   pure real(dp) function quantile(w, f)
      real(dp), intent(in) :: w(:)    !! sorted values
      real(dp), intent(in) :: f       !! fraction in [0, 1]
      real(dp) :: h
      integer :: i
      h = f * (size(w) - 1) + 1.0_dp
      i = min(size(w) - 1, max(1, int(h)))
      if (size(w) == 1) then
         quantile = w(1)
      else
         quantile = w(i) + (h - i) * (w(i + 1) - w(i))
      end if
   end function quantile

   !> Sort ascending in place (heap sort).
   pure subroutine heap_sort(a)
      real(dp), intent(inout) :: a(:)   !! values
      integer :: n, i
      real(dp) :: t
      n = size(a)
      do i = n / 2, 1, -1
         call sift(a, i, n)
      end do
      do i = n, 2, -1
         t = a(1);  a(1) = a(i);  a(i) = t
         call sift(a, 1, i - 1)
      end do
   end subroutine heap_sort

   !> Sift a(start) down the heap a(1:last).
   pure subroutine sift(a, start, last)
      real(dp), intent(inout) :: a(:)        !! heap
      integer, intent(in) :: start, last     !! root and end of the heap
      integer :: root, child
      real(dp) :: tmp
      root = start
      do while (2 * root <= last)
         child = 2 * root
         if (child < last) then
            if (a(child) < a(child + 1)) child = child + 1
         end if
         if (a(root) < a(child)) then
            tmp = a(root);  a(root) = a(child);  a(child) = tmp
            root = child
         else
            exit
         end if
      end do
   end subroutine sift
end module gapbeam_diagnostics
