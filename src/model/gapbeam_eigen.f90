!> Modal analysis of the linear structure through LAPACK's generalized symmetric solvers.
!>
!> K phi = omega^2 M phi is solved as the pencil M phi = mu K phi with mu = 1/omega^2 (K is
!> positive definite for any supported root). In this form the lowest modes are the largest
!> mu, which LAPACK resolves to round-off of mu_max whatever the stiffness contrast (a root
!> spring of 1e11 N m/rad beside elements of 1e3 N/m breaks the K-M form: f1 came out 0 Hz).
!> Massless directions (lumped mass without rotary inertia) have mu = 0 and are dropped: their
!> number is the number of zero diagonal entries of a diagonal M, and mu below round-off of
!> mu_max otherwise.
!>
!> * solve_modes: all finite modes with shapes (dense dsygv), for the modes analysis and the
!>   reduced models. Shapes are mass-normalised, phi' M phi = 1, with the sign chosen so that
!>   the tip displacement (or, if zero, the largest component) is positive.
!> * band_frequencies: all finite omega^2 without shapes from the band storage (dsbgv,
!>   O(n^2) instead of O(n^3)), for the set-up of large models.
!> * lowest_frequency: f1 from the band solver, certified by two Sturm counts (the inertia of
!>   K - sigma M just below and just above omega_1^2); calibrations certify their answer.
module gapbeam_eigen
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dsygv, dsbgv, dpbtrf, dpotrf
   use gapbeam_linalg, only: band_matvec, band_solve
   use gapbeam_model, only: system_t
   use gapbeam_results, only: modes_t
   implicit none
   private
   public :: solve_modes, band_frequencies, lowest_frequency, count_below

   !> smallest relative margin of the Sturm counts around omega_1^2
   real(dp), parameter :: sturm_margin = 1.0e-6_dp
   !> omega^2 below this fraction of the shift of a mechanism (mechanism_shift) is a rigid mode
   real(dp), parameter :: rigid_tolerance = 1.0e-8_dp

contains

   !> Solve K phi = omega^2 M phi for all finite modes of `sys`.
   !>
   !> With a positive definite M the K-M form (B = M) resolves every mode to round-off of
   !> omega_max^2, the high modes best. It is kept when its f1 agrees with the certified one
   !> (lowest_frequency, from the M-K form) to 1e-9. Otherwise (stiff springs beside soft
   !> elements, hundreds of elements) and when M is singular, the M-K form (B = K) is solved
   !> instead, which resolves the low modes to round-off of 1/omega_1^2.
   subroutine solve_modes(sys, modes, err)
      type(system_t), intent(in) :: sys               !! assembled structure
      type(modes_t), intent(out) :: modes             !! frequencies, shapes, participation
      type(error_t), allocatable, intent(out) :: err  !! set on LAPACK failure
      real(dp), allocatable :: a(:, :), b(:, :), w(:), work(:)
      real(dp) :: query(1), s, f1
      integer :: n, info, i, j, nm, imax
      logical :: k_m

      n = sys%n_dof
      allocate(b, source=sys%m)
      call dpotrf('U', n, b, n, info)
      k_m = info == 0
      if (k_m) then
         a = sys%k;  b = sys%m
         call generalized(a, b, w, err);  if (allocated(err)) return
         call lowest_frequency(sys, f1, err, certify=.false.)
         if (allocated(err)) return
         k_m = abs(sqrt(max(w(1), 0.0_dp)) / (2.0_dp * pi) - f1) <= 1.0e-9_dp * f1
      end if
      if (k_m) then
         nm = n
         allocate(modes%omega2(nm), modes%shapes(n, nm))
         modes%omega2 = w
         modes%shapes = a
      else
         a = sys%m;  b = sys%k
         call generalized(a, b, w, err);  if (allocated(err)) return
         nm = finite_modes(sys, w)
         if (nm == 0) then
            call fatal_error(err, 'gapbeam_eigen:solve_modes: the structure has no mass')
            return
         end if
         ! w holds mu = 1/omega^2 ascending; the largest mu is the lowest frequency
         allocate(modes%omega2(nm), modes%shapes(n, nm))
         do j = 1, nm
            i = n + 1 - j
            modes%omega2(j) = 1.0_dp / w(i)
            modes%shapes(:, j) = a(:, i) / sqrt(w(i))   ! phi' K phi = 1 -> phi' M phi = 1
         end do
      end if
      modes%n_modes = nm
      do j = 1, nm
         if (sys%tip_dof > 0) then
            s = modes%shapes(sys%tip_dof, j)
         else
            s = 0.0_dp
         end if
         if (abs(s) <= 1.0e-12_dp * maxval(abs(modes%shapes(:, j)))) then
            imax = maxloc(abs(modes%shapes(:, j)), dim=1)
            s = modes%shapes(imax, j)
         end if
         if (s < 0.0_dp) modes%shapes(:, j) = -modes%shapes(:, j)
      end do
      modes%frequency_hz = sqrt(max(modes%omega2, 0.0_dp)) / (2.0_dp * pi)
      modes%participation = matmul(transpose(modes%shapes), matmul(sys%m, sys%r))
      modes%effective_mass = modes%participation**2
      modes%total_mass = dot_product(sys%r, matmul(sys%m, sys%r))
   end subroutine solve_modes

   !> dsygv on A x = lambda B x (B positive definite): eigenvalues ascending in w, vectors in a.
   subroutine generalized(a, b, w, err)
      real(dp), intent(inout) :: a(:, :)              !! A in, eigenvectors out
      real(dp), intent(inout) :: b(:, :)              !! B in, its Cholesky factor out
      real(dp), allocatable, intent(out) :: w(:)      !! eigenvalues
      type(error_t), allocatable, intent(out) :: err  !! B not definite, no convergence
      real(dp), allocatable :: work(:)
      real(dp) :: query(1)
      integer :: n, info
      n = size(a, 1)
      allocate(w(n))
      call dsygv(1, 'V', 'U', n, a, n, b, n, w, query, -1, info)
      allocate(work(max(1, int(query(1)))))
      call dsygv(1, 'V', 'U', n, a, n, b, n, w, work, size(work), info)
      if (info > n) then
         call fatal_error(err, 'gapbeam_eigen:solve_modes: the stiffness matrix is not ' &
            // 'positive definite (dsygv info=' // str(info) // '); check the root support ' &
            // 'and the springs')
      else if (info /= 0) then
         call fatal_error(err, 'gapbeam_eigen:solve_modes: dsygv failed, info=' // str(info))
      end if
   end subroutine generalized

   !> All finite omega^2 of `sys`, ascending, from the band storage (no shapes).
   subroutine band_frequencies(sys, omega2, err, mechanism)
      type(system_t), intent(in) :: sys                 !! assembled structure (band storage)
      real(dp), allocatable, intent(out) :: omega2(:)   !! [rad^2/s^2], ascending
      type(error_t), allocatable, intent(out) :: err    !! K not positive definite
      !> the structure has rigid modes (K singular; round-off may hide it from a Cholesky):
      !> solve the shifted problem (their omega^2 exactly 0)
      logical, intent(in), optional :: mechanism
      real(dp), allocatable :: ab(:, :), bb(:, :), w(:), work(:)
      real(dp) :: z(1, 1), sigma
      integer :: n, kd, info, nm, j
      n = sys%n_dof;  kd = sys%kd
      allocate(ab, source=sys%m_band)
      allocate(bb, source=sys%k_band)
      allocate(w(n), work(3 * n))
      sigma = 0.0_dp
      info = n + 1
      if (present(mechanism)) then
         if (.not. mechanism) call dsbgv('N', 'U', n, kd, kd, ab, kd + 1, bb, kd + 1, w, z, 1, &
                                         work, info)
      else
         call dsbgv('N', 'U', n, kd, kd, ab, kd + 1, bb, kd + 1, w, z, 1, work, info)
      end if
      if (info > n) then
         ! K singular: a mechanism (rigid modes, omega = 0). Shifted: M phi = mu (K + sigma M)
         ! phi, omega^2 = 1/mu - sigma, sigma a small fraction of the largest K_ii / M_ii
         sigma = mechanism_shift(sys)
         ab = sys%m_band
         bb = sys%k_band + sigma * sys%m_band
         call dsbgv('N', 'U', n, kd, kd, ab, kd + 1, bb, kd + 1, w, z, 1, work, info)
      end if
      if (info > n) then
         call fatal_error(err, 'gapbeam_eigen:band_frequencies: the stiffness matrix is not ' &
            // 'positive definite (dsbgv info=' // str(info) // '); check the root support ' &
            // 'and the springs')
         return
      else if (info /= 0) then
         call fatal_error(err, 'gapbeam_eigen:band_frequencies: dsbgv failed, info=' &
            // str(info))
         return
      end if
      nm = finite_modes(sys, w)
      if (nm == 0) then
         call fatal_error(err, 'gapbeam_eigen:band_frequencies: the structure has no mass')
         return
      end if
      allocate(omega2(nm))
      do j = 1, nm
         omega2(j) = 1.0_dp / w(n + 1 - j) - sigma
         ! a rigid mode: zero to the shift's round-off
         if (sigma > 0.0_dp .and. omega2(j) <= rigid_tolerance * sigma) omega2(j) = 0.0_dp
      end do
   end subroutine band_frequencies

   !> The shift of a mechanism's eigenproblem: 1e-4 x the largest K_ii / M_ii of the dofs with
   !> mass (about the lowest elastic omega^2 of a beam, so that the shifted problem keeps
   !> the accuracy of its lowest modes) [rad^2/s^2].
   pure real(dp) function mechanism_shift(sys) result(sigma)
      type(system_t), intent(in) :: sys                 !! assembled structure (band storage)
      real(dp) :: m_ii
      integer :: i
      sigma = 0.0_dp
      do i = 1, sys%n_dof
         m_ii = sys%m_band(sys%kd + 1, i)
         if (m_ii > 0.0_dp) sigma = max(sigma, sys%k_band(sys%kd + 1, i) / m_ii)
      end do
      sigma = 1.0e-4_dp * sigma
   end function mechanism_shift

   !> First natural frequency [Hz], certified.
   !>
   !> Inverse iteration on M phi = mu K phi from the static shape K^-1 M r (band Cholesky of
   !> K, O(n) per iteration; the Rayleigh quotient converges as (omega_1/omega_2)^4 per
   !> iteration), with all eigenvalues from band_frequencies as the fallback when it stalls
   !> (close first and second modes). The certificate: K - sigma M has no negative pivot at
   !> sigma = omega_1^2 (1 - r) and at least one at omega_1^2 (1 + r) (Sylvester's law of
   !> inertia), so this is the lowest eigenvalue and accurate to r, where r is 1e-6 or the
   !> round-off the discrete problem itself allows when that is larger,
   !> 10 eps ||K||_1 |phi_1|^2 / omega_1^2 with phi_1' M phi_1 = 1.
   subroutine lowest_frequency(sys, f1, err, certify, accuracy, mechanism)
      type(system_t), intent(in) :: sys               !! assembled structure
      real(dp), intent(out) :: f1                     !! first natural frequency [Hz]
      type(error_t), allocatable, intent(out) :: err  !! eigen failure or failed certificate
      logical, intent(in), optional :: certify        !! Sturm check (default: yes)
      real(dp), intent(out), optional :: accuracy     !! round-off bound of omega_1^2 (relative)
      logical, intent(in), optional :: mechanism      !! rigid modes: f1 = 0 exactly
      real(dp), allocatable :: omega2(:), fac(:, :), x(:), y(:), z(:)
      real(dp) :: r, mu, mu_old, w1, phi2, knorm
      integer :: below, upto, it, info, n, kd, i, j, calm
      f1 = 0.0_dp
      if (present(mechanism)) then
         if (mechanism) then
            if (present(accuracy)) accuracy = 0.0_dp
            return
         end if
      end if
      n = sys%n_dof;  kd = sys%kd
      fac = sys%k_band
      call dpbtrf('U', n, kd, fac, kd + 1, info)
      if (info /= 0) then
         ! a mechanism: its rigid modes are at omega = 0 (band_frequencies with a shift)
         call band_frequencies(sys, omega2, err)
         if (.not. allocated(err)) then
            if (omega2(1) == 0.0_dp) then
               if (present(accuracy)) accuracy = 0.0_dp
               return
            end if
         end if
         if (allocated(err)) deallocate(err)
         call fatal_error(err, 'gapbeam_eigen:lowest_frequency: the stiffness matrix is not ' &
            // 'positive definite (dpbtrf info=' // str(info) // '); check the root support ' &
            // 'and the springs')
         return
      end if
      allocate(y(n), z(n))
      x = sys%r
      if (sys%planes > 1) x = x + sys%r_v          ! two planes: start in both
      if (all(x == 0.0_dp)) x = 1.0_dp
      mu_old = 0.0_dp;  mu = 0.0_dp;  calm = 0
      do it = 1, 400
         call band_matvec(n, kd, sys%m_band, x, y)        ! y = M x
         z = y
         call band_solve(n, kd, fac, z)                   ! K z = M x
         mu = dot_product(z, y)                           ! z' K z = z' M x
         call band_matvec(n, kd, sys%m_band, z, y)        ! y = M z
         if (mu <= 0.0_dp) exit
         mu = dot_product(z, y) / mu                      ! Rayleigh quotient of (M, K)
         x = z / sqrt(dot_product(z, y))                  ! x' M x = 1
         if (abs(mu - mu_old) <= 1.0e-13_dp * mu) then
            calm = calm + 1
            if (calm >= 2) exit
         else
            calm = 0
         end if
         mu_old = mu
      end do
      if (calm >= 2) then
         w1 = 1.0_dp / mu
      else
         call band_frequencies(sys, omega2, err)
         if (allocated(err)) return
         w1 = omega2(1)
         x = 0.0_dp
      end if
      f1 = sqrt(max(w1, 0.0_dp)) / (2.0_dp * pi)
      ! the round-off of the discrete problem: ||dK|| |phi|^2 / omega_1^2
      knorm = 0.0_dp
      do j = 1, n        ! column sums of |K| from the upper band
         knorm = max(knorm, sum(abs(sys%k_band(:, j))) &
            + sum([(abs(sys%k_band(kd + 1 + j - i, i)), i = j + 1, min(n, j + kd))]))
      end do
      phi2 = dot_product(x, x)
      r = 0.1_dp
      if (w1 > 0.0_dp) r = min(0.1_dp, 10.0_dp * epsilon(1.0_dp) * knorm * phi2 / w1)
      if (present(accuracy)) accuracy = r
      r = max(r, sturm_margin)
      if (present(certify)) then
         if (.not. certify) return
      end if
      below = count_below(sys, w1 * (1.0_dp - r))
      upto = count_below(sys, w1 * (1.0_dp + r))
      if (below /= 0 .or. upto < 1) then
         call fatal_error(err, 'gapbeam_eigen:lowest_frequency: the eigen-solution f1 = ' &
            // str(f1) // ' Hz fails its Sturm check (' // str(below) // ' eigenvalues ' &
            // 'below f1 (1 - ' // str(r) // '), ' // str(upto) // ' below f1 (1 + ' // str(r) &
            // ')); the stiffness or mass matrix is too ill-conditioned (springs many orders ' &
            // 'stiffer than the beam?)')
         f1 = 0.0_dp
         return
      end if
   end subroutine lowest_frequency

   !> Number of eigenvalues omega^2 < sigma of K phi = omega^2 M phi: the negative pivots of
   !> the band LDL' factorisation of K - sigma M (no pivoting, as in the Sturm checks of
   !> structural eigen-solvers; an exact zero pivot is moved to +round-off).
   integer function count_below(sys, sigma) result(neg)
      type(system_t), intent(in) :: sys    !! assembled structure (band storage)
      real(dp), intent(in) :: sigma        !! shift [rad^2/s^2]
      real(dp), allocatable :: a(:, :), d(:)
      real(dp) :: s, scale
      integer :: n, kd, i, j, k
      n = sys%n_dof;  kd = sys%kd
      a = sys%k_band - sigma * sys%m_band      ! a(kd+1+i-j, j) = A(i, j), i <= j
      allocate(d(n))
      scale = maxval(abs(a))
      neg = 0
      ! A = U' D U with U unit upper triangular: overwrite a(kd+1+i-j, j), i < j, by U(i, j)
      do j = 1, n
         ! U(i, j) for i < j: (A(i, j) - sum_k U(k, i) d(k) U(k, j)) / d(i)
         do i = max(1, j - kd), j - 1
            s = a(kd + 1 + i - j, j)
            do k = max(1, j - kd), i - 1
               s = s - a(kd + 1 + k - i, i) * d(k) * a(kd + 1 + k - j, j)
            end do
            a(kd + 1 + i - j, j) = s / d(i)
         end do
         s = a(kd + 1, j)
         do k = max(1, j - kd), j - 1
            s = s - a(kd + 1 + k - j, j)**2 * d(k)
         end do
         if (s == 0.0_dp) s = epsilon(1.0_dp) * scale
         d(j) = s
         if (s < 0.0_dp) neg = neg + 1
      end do
   end function count_below

   !> Number of finite modes: the rank of M (its nonzero diagonal for a diagonal M, else the
   !> mu = 1/omega^2 above round-off of the largest).
   integer function finite_modes(sys, mu) result(nm)
      type(system_t), intent(in) :: sys     !! structure
      real(dp), intent(in) :: mu(:)         !! eigenvalues of M phi = mu K phi, ascending
      integer :: i
      if (sys%m_diagonal .and. allocated(sys%m_band)) then
         nm = count(sys%m_band(sys%kd + 1, :) > 0.0_dp)
      else if (sys%m_diagonal) then
         nm = count([(sys%m(i, i) > 0.0_dp, i = 1, sys%n_dof)])
      else
         nm = count(mu > 1.0e-12_dp * maxval(mu))
      end if
      nm = min(nm, count(mu > 0.0_dp))
   end function finite_modes
end module gapbeam_eigen
