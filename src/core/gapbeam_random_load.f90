!> A random load record, generated once per draw and evaluated cheaply at any time.
!>
!> The load vector is P(t) = A x(t) (A the map, n_model x n_signals; without a map the
!> signals are the model's dofs). Each signal x_m is a band-limited periodic function of period
!> n_grid h (the record's period 1/df), tabulated on the grid t_j = j h with its value, first
!> and second derivatives (exact, from the spectral sum: gapbeam_turbulence). Between grid points
!> it is the quintic Hermite interpolant of those six numbers, so the load is C2 in time (the
!> integrators' error estimators see a smooth acceleration), and for a harmonic of angular
!> frequency w the interpolation error is at most (w h)^6 / 46080 of its amplitude
!> ((t - t_j)^3 (t - t_j+1)^3 / 6! at mid-interval): 2.9e-5 at 6 grid points per cycle.
!> One evaluation costs two grid columns, 6 n_signals multiply-adds and the map.
module gapbeam_random_load
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: random_load_t, add_random_load, random_signals_at, quintic_weights, rms_load

   !> A tabulated random load (empty and inactive by default).
   type :: random_load_t
      logical :: active = .false.                !! a record is present
      real(dp) :: h = 0.0_dp                     !! grid step [s]
      integer :: n_grid = 0                      !! grid points per period of the record
      integer :: n_signals = 0                   !! tabulated signals
      real(dp) :: cutoff_hz = 0.0_dp             !! highest frequency in the record [Hz]
      !> (n_signals, 3, 0:n_grid-1): value, first and second time derivative at t_j [N, N/s,
      !> N/s^2 per unit signal]
      real(dp), allocatable :: x(:, :, :)
      !> (n_model, n_signals) load = map x(t); unallocated: signal i is the load on dof i
      real(dp), allocatable :: map(:, :)
   end type random_load_t

contains

   !> The six quintic Hermite weights at s in [0, 1] on an interval of length h: value, h x
   !> derivative, h^2 x second derivative at the left end, then the same at the right end.
   pure function quintic_weights(s, h) result(w)
      real(dp), intent(in) :: s   !! position in the interval [-]
      real(dp), intent(in) :: h   !! interval length [s]
      real(dp) :: w(6)
      real(dp) :: s2, s3, s4, s5
      s2 = s * s;  s3 = s2 * s;  s4 = s3 * s;  s5 = s4 * s
      w(1) = 1.0_dp - 10.0_dp * s3 + 15.0_dp * s4 - 6.0_dp * s5
      w(2) = h * (s - 6.0_dp * s3 + 8.0_dp * s4 - 3.0_dp * s5)
      w(3) = h * h * 0.5_dp * (s2 - 3.0_dp * s3 + 3.0_dp * s4 - s5)
      w(4) = 10.0_dp * s3 - 15.0_dp * s4 + 6.0_dp * s5
      w(5) = h * (-4.0_dp * s3 + 7.0_dp * s4 - 3.0_dp * s5)
      w(6) = h * h * 0.5_dp * (s3 - 2.0_dp * s4 + s5)
   end function quintic_weights

   !> The signals at time t (any t: the record is periodic).
   pure subroutine random_signals_at(rl, t, x)
      type(random_load_t), intent(in) :: rl   !! record
      real(dp), intent(in) :: t               !! time [s]
      real(dp), intent(out) :: x(:)           !! (n_signals)
      real(dp) :: tau, w(6)
      integer :: j, j1
      tau = t / rl%h
      j = floor(tau)
      w = quintic_weights(tau - real(j, dp), rl%h)
      j = modulo(j, rl%n_grid)
      j1 = j + 1
      if (j1 == rl%n_grid) j1 = 0
      x = w(1) * rl%x(:, 1, j) + w(2) * rl%x(:, 2, j) + w(3) * rl%x(:, 3, j) &
          + w(4) * rl%x(:, 1, j1) + w(5) * rl%x(:, 2, j1) + w(6) * rl%x(:, 3, j1)
   end subroutine random_signals_at

   !> p = p + P(t).
   pure subroutine add_random_load(rl, t, p)
      type(random_load_t), intent(in) :: rl   !! record
      real(dp), intent(in) :: t               !! time [s]
      real(dp), intent(inout) :: p(:)         !! load vector [N, N m]
      real(dp) :: x(rl%n_signals)
      integer :: m
      if (.not. rl%active) return
      call random_signals_at(rl, t, x)
      if (allocated(rl%map)) then
         do m = 1, rl%n_signals
            p = p + x(m) * rl%map(:, m)
         end do
      else
         p(1:rl%n_signals) = p(1:rl%n_signals) + x
      end if
   end subroutine add_random_load

   !> The RMS of the load on each of the n coordinates over the record's period (the signals
   !> independent: sqrt(sum_m (map(i, m) rms_m)^2)), from the grid values.
   pure function rms_load(rl, n) result(p)
      type(random_load_t), intent(in) :: rl   !! record (active)
      integer, intent(in) :: n                !! coordinates
      real(dp) :: p(n)
      real(dp) :: ms(rl%n_signals)
      integer :: m
      p = 0.0_dp
      if (.not. rl%active) return
      do m = 1, rl%n_signals
         ms(m) = sum(rl%x(m, 1, :)**2) / real(rl%n_grid, dp)
      end do
      if (allocated(rl%map)) then
         do m = 1, rl%n_signals
            p = p + rl%map(:, m)**2 * ms(m)
         end do
      else
         p(1:rl%n_signals) = ms
      end if
      p = sqrt(p)
   end function rms_load
end module gapbeam_random_load
