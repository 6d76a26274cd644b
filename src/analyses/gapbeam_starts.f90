!> Initial states of a point and the attractors they reach.
!>
!> Starts: 'deck' (the &initial state), 'rest' (zero), 'up' / 'down' (in a sweep, the final
!> state of the neighbour below / above along the line; the caller supplies it) and 'random':
!> seeded random states u = s sum_k xi_k phi_k omega_1/(omega_k phi_1,tip),
!> v = s sum_k eta_k omega_1 phi_k/phi_1,tip over the lowest three modes of the open
!> structure, xi and eta uniform in [-1, 1] (every mode gets at most the energy of mode 1
!> displaced by s at the tip; s = random_amplitude, or the point's peak-to-peak base
!> amplitude). The numbers come from a counter-based generator (SplitMix64) of the seed and a
!> stream number made of the point and the start, so a state never depends on the thread that
!> draws it.
!>
!> Attractors: the starts' labels are grouped in start order; a start joins the first group
!> whose first start has the same label and the same attractor: for periodic labels the two
!> orbits within orbit_tolerance (gapbeam_diagnostics orbit_distance), otherwise statistics
!> within settle_tolerance (statistics_distance), both relative to the larger orbit size.
module gapbeam_starts
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_random, only: splitmix64, add64
   use gapbeam_error, only: error_t, fatal_error
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: diagnostics_settings_t, starts_given
   use gapbeam_results, only: point_result_t, modes_t, label_failed
   use gapbeam_eigen, only: solve_modes
   use gapbeam_diagnostics, only: orbit_distance, statistics_distance
   implicit none
   private
   public :: uniform_numbers, random_state, group_attractors, attractor_distance, start_list

contains

   !> The starts of a point in order, 'random' expanded into random_starts entries:
   !> kinds(k) and, for a random start, its number among them (0 for the others). Without
   !> starts in the settings, the one start `default`.
   pure subroutine start_list(diag, default, kinds, random_index)
      type(diagnostics_settings_t), intent(in) :: diag        !! starts, random_starts
      character(len=*), intent(in) :: default                 !! start when none is given
      character(len=8), allocatable, intent(out) :: kinds(:)  !! one per start
      integer, allocatable, intent(out) :: random_index(:)    !! random number (0: not random)
      integer :: j, r, n
      n = starts_given(diag)
      if (n == 0) then
         kinds = [character(len=8) :: default]
         random_index = [0]
         return
      end if
      allocate(kinds(n), random_index(n))
      n = 0;  r = 0
      do j = 1, size(diag%starts)
         if (len_trim(diag%starts(j)) == 0) exit
         if (diag%starts(j) == 'random') then
            do while (r < diag%random_starts .and. n < size(kinds))
               r = r + 1;  n = n + 1
               kinds(n) = 'random';  random_index(n) = r
            end do
            r = 0
         else
            n = n + 1
            kinds(n) = diag%starts(j);  random_index(n) = 0
         end if
      end do
   end subroutine start_list

   !> n numbers uniform in [-1, 1) from (seed, stream): the i-th is SplitMix64 of key + i,
   !> key = SplitMix64(SplitMix64(seed) + stream), so any subset can be drawn independently.
   pure function uniform_numbers(seed, stream, n) result(x)
      integer, intent(in) :: seed        !! user seed
      integer, intent(in) :: stream      !! which sequence (point, start)
      integer, intent(in) :: n           !! how many
      real(dp) :: x(n)
      integer(int64) :: key, z
      integer :: i
      ! gapbeam_random's mixer: modulo 2^64 without signed overflow (the wrapping version
      ! gave one number for every i and stream at -O3)
      key = splitmix64(add64(splitmix64(int(seed, int64)), int(stream, int64)))
      do i = 1, n
         z = splitmix64(add64(key, int(i, int64)))
         ! the top 53 bits as a fraction in [0, 1)
         x(i) = 2.0_dp * (real(ishft(z, -11), dp) / 9007199254740992.0_dp) - 1.0_dp
      end do
   end function uniform_numbers

   !> A random initial state (see the module header), stream `stream` of `seed`.
   subroutine random_state(model, seed, stream, amplitude, u, v, err)
      type(model_t), intent(in) :: model                !! model of the point
      integer, intent(in) :: seed, stream               !! generator seed and stream
      real(dp), intent(in) :: amplitude                 !! tip scale s [m]
      real(dp), allocatable, intent(out) :: u(:), v(:)  !! state
      type(error_t), allocatable, intent(out) :: err    !! modes failed
      type(modes_t) :: modes
      real(dp) :: r(6), tip1, w1
      integer :: k, nk, tip
      call solve_modes(model%sys, modes, err)
      if (allocated(err)) return
      allocate(u(model%n), v(model%n), source=0.0_dp)
      nk = min(3, modes%n_modes)
      tip = model%sys%tip_dof
      if (nk < 1 .or. tip < 1 .or. tip > model%n) then
         call fatal_error(err, 'gapbeam_starts:random_state: the model has no mode or no tip ' &
            // 'translation to scale a random start')
         return
      end if
      tip1 = modes%shapes(tip, 1)
      if (tip1 == 0.0_dp) tip1 = maxval(abs(modes%shapes(:, 1)))
      w1 = sqrt(modes%omega2(1))
      r = uniform_numbers(seed, stream, 6)
      do k = 1, nk
         u = u + r(k) * amplitude * (w1 / sqrt(modes%omega2(k))) / abs(tip1) * modes%shapes(:, k)
         v = v + r(3 + k) * amplitude * w1 / abs(tip1) * modes%shapes(:, k)
      end do
   end subroutine random_state

   !> Distance between the attractors of two starts with the same label: orbit distance for a
   !> period, statistics distance otherwise, relative to the larger orbit size [-].
   pure real(dp) function attractor_distance(a, b) result(d)
      type(point_result_t), intent(in) :: a, b   !! two diagnosed starts
      real(dp) :: sx, sy
      sx = max(a%strain_range, b%strain_range)
      sy = max(a%strain_rate_range, b%strain_rate_range)
      if (a%label >= 1 .and. a%label == b%label) then
         d = orbit_distance(a%p_strain, a%p_strain_rate, b%p_strain, b%p_strain_rate, a%label, &
                            sx, sy)
      else
         d = statistics_distance(a%p_strain, a%p_strain_rate, b%p_strain, b%p_strain_rate, &
                                 sx, sy)
      end if
   end function attractor_distance

   !> Two diagnosed starts reached the same attractor.
   pure logical function same_attractor(a, b, diag) result(same)
      type(point_result_t), intent(in) :: a, b            !! two starts (status 0)
      type(diagnostics_settings_t), intent(in) :: diag    !! tolerances
      same = .false.
      if (a%label /= b%label) return
      if (.not. allocated(a%p_strain) .or. .not. allocated(b%p_strain)) return
      if (size(a%p_strain) == 0 .or. size(b%p_strain) == 0) return
      if (a%label >= 1) then
         same = attractor_distance(a, b) <= diag%orbit_tolerance
      else
         same = attractor_distance(a, b) <= diag%settle_tolerance
      end if
   end function same_attractor

   !> Group the starts of a point (all diagnosed) into distinct attractors; the summary goes
   !> into `pr` (start_label, start_attractor, start_lyapunov, start_transient, n_attractors,
   !> attractor_*: an attractor's transient is the mean over the starts that reached it).
   !> Failed starts (status /= 0) join no attractor (start_attractor 0) but count among the
   !> starts of the fractions.
   pure subroutine group_attractors(starts, diag, pr)
      type(point_result_t), intent(in) :: starts(:)       !! the starts, in order
      type(diagnostics_settings_t), intent(in) :: diag    !! tolerances
      type(point_result_t), intent(inout) :: pr           !! summary set
      integer :: ns, k, j, na
      integer, allocatable :: first(:)
      ns = size(starts)
      allocate(pr%start_label(ns), pr%start_attractor(ns), pr%start_lyapunov(ns), first(ns))
      allocate(pr%start_transient(ns))
      pr%start_attractor = 0
      na = 0
      do k = 1, ns
         pr%start_lyapunov(k) = starts(k)%lyapunov
         pr%start_transient(k) = starts(k)%transient_periods
         if (starts(k)%status /= 0) then
            pr%start_label(k) = label_failed
            cycle
         end if
         pr%start_label(k) = starts(k)%label
         do j = 1, na
            if (same_attractor(starts(first(j)), starts(k), diag)) then
               pr%start_attractor(k) = j
               exit
            end if
         end do
         if (pr%start_attractor(k) == 0) then
            na = na + 1
            first(na) = k
            pr%start_attractor(k) = na
         end if
      end do
      pr%n_attractors = na
      allocate(pr%attractor_label(na), pr%attractor_fraction(na), pr%attractor_lyapunov(na), &
               pr%attractor_transient(na))
      do j = 1, na
         pr%attractor_label(j) = starts(first(j))%label
         pr%attractor_lyapunov(j) = starts(first(j))%lyapunov
         pr%attractor_fraction(j) = real(count(pr%start_attractor == j), dp) / real(ns, dp)
         pr%attractor_transient(j) = real(sum(pr%start_transient, mask=pr%start_attractor &
            == j), dp) / real(count(pr%start_attractor == j), dp)
      end do
   end subroutine group_attractors
end module gapbeam_starts
