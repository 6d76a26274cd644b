!> One contact configuration of the exact event-driven integrator (gapbeam_exact): the open
!> structure (gapbeam_exact_modes) plus the springs and dampers of the active contacts, as a
!> rank-r update of the diagonal modal structure (docs/exact_integrator.md).
!>
!> In modal coordinates a configuration with the active contacts A (r of them; Psi = their
!> modal rows, G(lambda) = diag(k_c + c_c lambda)) has the characteristic matrix
!>
!>    Q_c(lambda) = diag(q_j(lambda)) + Psi G(lambda) Psi',   q_j = lambda^2 + d_j lambda + w_j^2,
!>
!> whose 2n eigenvalues are the zeros of det Q_c = prod_j q_j det S, S = I + G Psi' Q_0^-1 Psi.
!>
!> **Roots.** Root a is stored as its home pole (open pole a, a bijection) plus an offset,
!> lambda_a = p_a + delta_a, and every difference is formed from pole differences,
!> lambda_a - p = (p_a - p) + delta_a: delta keeps full relative accuracy even where it is 1e-10
!> of |p| (high modes) and inside the overdamped cluster at -1/gamma. Initial guesses: the
!> first-order shift -t_a(p_a)/(p_a - p'_a) for weakly coupled poles (t_a = psi_a'(I + G P_a)^-1
!> G psi_a, P_a = sum_{j /= a} psi_j psi_j'/q_j), the split -dq/2 +- sqrt(dq^2/4 - t_a) of a
!> (nearly) double pole, and for the strongly coupled low modes the eigenvalues of a small
!> dense problem (those modes, the contact springs in series with the residual flexibility of
!> the others; dgeev), matched to their poles. Then Aberth-Ehrlich sweeps on P = det Q_c in
!> the pole-paired form that never subtracts large terms:
!>
!>    L_a = h_a'/h_a - sum_{b /= a} delta_b / ((lambda_a - p_b)(lambda_a - lambda_b)),
!>    h_a = det(I + G P_a)(delta_a + t_a/(lambda_a - p'_a)),   delta_a <- delta_a - 1/L_a,
!>
!> whose mutual repulsion keeps the roots distinct. The product identity
!> det S(z) = prod_a (1 - delta_a/(z - p_a)) at six points off the axes certifies the set (a
!> missing or doubled root breaks it grossly). An undamped configuration has its roots on the
!> imaginary axis exactly.
!>
!> **Eigenvectors** are explicit, x_a = e_a + z_a with w = (I + P_a G)^-1 psi_a and
!> z_aj = -psi_j' G w / q_j(lambda_a); the residue formula of the symmetric quadratic problem
!> projects a state with nu_a = x_a' Q_c'(lambda_a) x_a, so no eigenvector matrix is inverted.
!>
!> **Blocks.** A root whose eigenvalue condition |lambda| |x|^2 / |nu| exceeds 1/tol_cluster is
!> paired with the nearest other such root (a nearly double root: critical damping of an open
!> mode, or a coalescing contact pair) and the pair becomes a block
!> e^{m tau}[cosh(delta tau) M0 + sinh(delta tau)/delta M1]: m and delta^2 from power sums of
!> the zeros inside a circle (contour integrals of (log det Q_c)', trapezoidal rule on
!> n_contour points), exact at, near and past coalescence; M0, M1 are moments of the Laplace
!> transform of the transient on the same circle (gapbeam_exact_segment). For the open
!> configuration the block of a near-critical mode is its own oscillator: m = -d/2,
!> delta^2 = (d/2)^2 - w^2.
!>
!> **Particular solutions** by Woodbury on the diagonal plus rank r: the harmonic amplitude
!> Y = Q_c(i Omega)^-1 (-i p) (eta_p = Re(Y e^{i Omega t})) and the static part
!> eta_s = Q_c(0)^-1 Psi w (w_c = s_c k_c g_c, the gaps).
module gapbeam_exact_config
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t
   use gapbeam_lapack, only: dgeev
   use gapbeam_exact_modes, only: open_modes_t
   implicit none
   private
   public :: config_t, build_config, config_solve, mask_text, n_contour

   real(dp), parameter :: tol_cluster = 1.0e-2_dp   ! eigenvalue condition above 1/tol: a block
   integer, parameter :: n_contour = 64             ! trapezoid points on a block's circle
   real(dp), parameter :: weak_rel = 1.0e-3_dp      ! first-order guess trusted below this
   real(dp), parameter :: near_double = 1.0e-3_dp   ! |p - p'| < this |p|: a (nearly) double pole
   integer, parameter :: max_sweeps = 100           ! Aberth sweeps at most
   integer, parameter :: max_dense = 64             ! modes of the dense strong-coupling problem
   real(dp), parameter :: identity_tol = 1.0e-8_dp  ! product identity of the roots
   real(dp), parameter :: eps = epsilon(1.0_dp)

   !> Two nearly coalescing roots merged: e^{m tau}[cosh(delta tau) M0 + sinh(delta tau)/delta M1].
   type :: block_t
      integer :: i1 = 0, i2 = 0                     !! its two roots
      integer :: mode = 0                           !! open configuration: the mode, else 0
      complex(dp) :: m = (0.0_dp, 0.0_dp)           !! centre [1/s]
      complex(dp) :: d2 = (0.0_dp, 0.0_dp)          !! delta^2 [1/s^2]
      complex(dp) :: pts(n_contour) = (0.0_dp, 0.0_dp)   !! contour points [1/s]
      complex(dp) :: wts(n_contour) = (0.0_dp, 0.0_dp)   !! their weights (d lambda / 2 pi i)
      real(dp) :: lam_abs = 0.0_dp                  !! max |m +- delta| [1/s]
      real(dp) :: sig = 0.0_dp                      !! max Re(m +- delta) [1/s]
   end type block_t

   !> One contact configuration in modal coordinates.
   type :: config_t
      integer(int64) :: mask = 0                    !! active contacts (bit c-1)
      integer :: n = 0                              !! modes
      integer :: r = 0                              !! active contacts
      integer :: nroot = 0                          !! roots (2 n)
      integer, allocatable :: act(:)                !! (r) the active contacts
      real(dp), allocatable :: psi(:, :)            !! (n, r) their modal rows
      real(dp), allocatable :: kc(:), cc(:), wgap(:)   !! (r) stiffness, damper, s k g
      complex(dp), allocatable :: lam(:)            !! (2n) roots [1/s]
      complex(dp), allocatable :: delta(:)          !! (2n) offsets from the home poles [1/s]
      logical, allocatable :: simple(:)             !! (2n) not in a block
      integer, allocatable :: partner(:)            !! (2n) complex-conjugate root (0: none)
      complex(dp), allocatable :: x(:, :)           !! (n, 2n) eigenvectors (r > 0)
      complex(dp), allocatable :: nu(:)             !! (2n) x' Q_c'(lambda) x
      integer :: nblk = 0                           !! blocks
      type(block_t), allocatable :: blk(:)          !! (nblk) the blocks
      complex(dp), allocatable :: y(:)              !! (n) harmonic amplitude
      real(dp), allocatable :: eta_s(:)             !! (n) static part
      complex(dp), allocatable :: lrow(:, :)        !! (2n, nb) functionals of the eigenvectors
      complex(dp), allocatable :: ly(:)             !! (nb) functionals of y
      real(dp), allocatable :: ls(:)                !! (nb) functionals of eta_s
      integer :: sweeps = 0                         !! Aberth sweeps taken
      real(dp) :: identity_error = 0.0_dp           !! product identity of the roots
   end type config_t

contains

   !> The configuration `mask`: roots, eigenvectors, blocks, particular solutions.
   subroutine build_config(om, model, mask, cf, err)
      type(open_modes_t), intent(in) :: om              !! open structure
      type(model_t), intent(in) :: model                !! model (contacts)
      integer(int64), intent(in) :: mask                !! active contacts (bit c-1)
      type(config_t), intent(out) :: cf                 !! the configuration
      type(error_t), allocatable, intent(inout) :: err  !! failed roots, resonance
      character(len=:), allocatable :: where
      integer :: c, i, nc
      complex(dp), allocatable :: b(:), ys(:)
      logical :: ok
      nc = model%n_contacts
      where = 'gapbeam_exact: configuration ' // mask_text(mask, nc)
      cf%mask = mask
      cf%n = om%nr;  cf%nroot = 2 * om%nr
      cf%act = pack([(c, c = 1, nc)], [(btest(mask, c - 1), c = 1, nc)])
      cf%r = size(cf%act)
      allocate(cf%psi(cf%n, cf%r))
      do i = 1, cf%r
         cf%psi(:, i) = om%ell(:, om%cslot(cf%act(i)))
      end do
      cf%kc = model%c_k(cf%act);  cf%cc = model%c_c(cf%act)
      cf%wgap = model%c_sign(cf%act) * model%c_k(cf%act) * model%c_gap(cf%act)
      if (cf%r == 0) then
         call open_roots(om, cf)
      else
         call secular_roots(om, cf, where, err);  if (allocated(err)) return
         call root_vectors(om, cf)
         call conjugate_pairs(om, cf)
         call find_blocks(om, cf, where, err);  if (allocated(err)) return
      end if
      do i = 1, cf%nroot             ! a pair is folded only when both of its roots are simple
         if (cf%partner(i) > 0) then
            if (.not. (cf%simple(i) .and. cf%simple(cf%partner(i)))) cf%partner(i) = 0
         end if
      end do
      ! particular solutions
      allocate(cf%y(cf%n), cf%eta_s(cf%n))
      cf%y = (0.0_dp, 0.0_dp);  ok = .true.
      if (any(om%pload /= 0.0_dp)) call config_solve(om, cf, cmplx(0.0_dp, model%omega, dp), &
                                                     cmplx(0.0_dp, -om%pload, dp), cf%y, ok)
      if (.not. ok) then
         call fatal_error(err, where // ': the forcing frequency is a natural frequency of ' &
            // 'this undamped configuration; no periodic particular solution')
         return
      end if
      cf%eta_s = 0.0_dp
      if (cf%r > 0) then
         b = cmplx(matmul(cf%psi, cf%wgap), 0.0_dp, dp)
         allocate(ys(cf%n))
         call config_solve(om, cf, (0.0_dp, 0.0_dp), b, ys, ok)
         if (.not. ok) then
            call fatal_error(err, where // ': the stiffness is singular (no static solution)')
            return
         end if
         cf%eta_s = real(ys)
      end if
      call functional_rows(om, cf)
   end subroutine build_config

   !> The open configuration: the poles, the near-critical modes as blocks.
   subroutine open_roots(om, cf)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      integer :: j, n, nb
      real(dp) :: kappa
      n = cf%n
      cf%lam = [om%p1, om%p2]
      allocate(cf%delta(2 * n), source=(0.0_dp, 0.0_dp))
      cf%nu = [om%p1 - om%p2, om%p2 - om%p1]      ! q_j'(p) = 2 p + d_j
      allocate(cf%simple(2 * n), source=.true.)
      allocate(cf%partner(2 * n), source=0)
      do j = 1, n
         if (aimag(om%p1(j)) > 0.0_dp) then        ! underdamped: p2 = conj(p1) exactly
            cf%partner(j) = n + j;  cf%partner(n + j) = j
         end if
      end do
      nb = 0
      do j = 1, n
         kappa = condition(abs(om%p1(j)), abs(cf%nu(j)))
         if (kappa > 1.0_dp / tol_cluster) nb = nb + 1
      end do
      allocate(cf%blk(nb))
      cf%nblk = 0
      do j = 1, n
         kappa = condition(abs(om%p1(j)), abs(cf%nu(j)))
         if (.not. (kappa > 1.0_dp / tol_cluster)) cycle
         cf%nblk = cf%nblk + 1
         associate (bk => cf%blk(cf%nblk))
            bk%i1 = j;  bk%i2 = n + j;  bk%mode = j
            bk%m = cmplx(-0.5_dp * om%d(j), 0.0_dp, dp)
            bk%d2 = cmplx((0.5_dp * om%d(j) - sqrt(om%w2(j))) &
                          * (0.5_dp * om%d(j) + sqrt(om%w2(j))), 0.0_dp, dp)
            call block_bounds(bk)
         end associate
         cf%simple(j) = .false.;  cf%simple(n + j) = .false.
      end do
   end subroutine open_roots

   !> The pole of home index h (1..n: p1, n+1..2n: p2), the other pole of its mode, the mode.
   pure subroutine home_pole(om, h, p, po, a)
      type(open_modes_t), intent(in) :: om
      integer, intent(in) :: h
      complex(dp), intent(out) :: p, po
      integer, intent(out) :: a
      if (h <= om%nr) then
         a = h;  p = om%p1(a);  po = om%p2(a)
      else
         a = h - om%nr;  p = om%p2(a);  po = om%p1(a)
      end if
   end subroutine home_pole

   !> Pieces of the pole-cleared secular function at lambda = p_h + delta (home-pole form):
   !> t = psi_a'(I + G P_a)^-1 G psi_a, its derivative, tr((I + G P_a)^-1 (G P_a)'), with
   !> P_a = sum_{j /= a} psi_j psi_j' / q_j(lambda).
   pure subroutine home_terms(om, cf, pp, h, delta, t, tp, trbb)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(in) :: cf
      real(dp), intent(in) :: pp(:, :)              !! (n, r(r+1)/2) products psi_jc psi_jd
      integer, intent(in) :: h
      complex(dp), intent(in) :: delta
      complex(dp), intent(out) :: t, tp, trbb
      complex(dp) :: ph, po, q1, q2, iq, diq, lam
      complex(dp) :: pa(size(pp, 2)), pap(size(pp, 2))
      complex(dp) :: b(cf%r, cf%r), bp(cf%r, cf%r), bi(cf%r, cf%r), g(cf%r), gp(cf%r), &
         u(cf%r), v(cf%r)
      integer :: a, j, k, c, e, r
      logical :: ok
      r = cf%r
      call home_pole(om, h, ph, po, a)
      pa = (0.0_dp, 0.0_dp);  pap = (0.0_dp, 0.0_dp)
      do j = 1, cf%n
         if (j == a) cycle
         q1 = (ph - om%p1(j)) + delta
         q2 = (ph - om%p2(j)) + delta
         iq = 1.0_dp / (q1 * q2)
         diq = -(q1 + q2) * iq * iq
         do k = 1, size(pp, 2)
            pa(k) = pa(k) + pp(j, k) * iq
            pap(k) = pap(k) + pp(j, k) * diq
         end do
      end do
      lam = ph + delta
      g = cf%kc + cf%cc * lam
      gp = cmplx(cf%cc, 0.0_dp, dp)
      ! B = I + G P, B' = G' P + G P'
      k = 0
      do e = 1, r
         do c = 1, e
            k = k + 1
            b(c, e) = g(c) * pa(k);  b(e, c) = g(e) * pa(k)
            bp(c, e) = gp(c) * pa(k) + g(c) * pap(k)
            bp(e, c) = gp(e) * pa(k) + g(e) * pap(k)
         end do
         b(e, e) = b(e, e) + 1.0_dp
      end do
      call small_inverse(b, bi, ok)
      u = g * cf%psi(a, :)                       ! G psi_a
      v = matmul(bi, u)                          ! B^-1 G psi_a
      t = sum(cf%psi(a, :) * v)
      tp = -sum(cf%psi(a, :) * matmul(bi, matmul(bp, v))) &
           + sum(cf%psi(a, :) * matmul(bi, gp * cf%psi(a, :)))
      trbb = (0.0_dp, 0.0_dp)
      do c = 1, r
         trbb = trbb + sum(bi(c, :) * bp(:, c))
      end do
      if (.not. ok) then
         t = cmplx(huge(1.0_dp), 0.0_dp, dp);  tp = t;  trbb = t
      end if
   end subroutine home_terms

   !> Products psi_jc psi_jd (c <= d) of the active rows.
   pure subroutine pair_products(cf, pp)
      type(config_t), intent(in) :: cf
      real(dp), allocatable, intent(out) :: pp(:, :)
      integer :: c, e, k
      allocate(pp(cf%n, cf%r * (cf%r + 1) / 2))
      k = 0
      do e = 1, cf%r
         do c = 1, e
            k = k + 1
            pp(:, k) = cf%psi(:, c) * cf%psi(:, e)
         end do
      end do
   end subroutine pair_products

   !> All 2n roots of det Q_c: initial guesses, Aberth sweeps, product check.
   subroutine secular_roots(om, cf, where, err)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      character(len=*), intent(in) :: where
      type(error_t), allocatable, intent(inout) :: err
      real(dp), allocatable :: pp(:, :), prev(:)
      complex(dp), allocatable :: poles(:), step(:)
      logical, allocatable :: conv(:)
      complex(dp) :: t, tp, trbb, ph, po, lo, hu, hup, dab, s, big
      integer :: nr, a, b, it, idum
      nr = cf%nroot
      call pair_products(cf, pp)
      allocate(poles(nr))
      do a = 1, nr
         call home_pole(om, a, poles(a), po, idum)
      end do
      call initial_guesses(om, cf, pp, poles)
      allocate(step(nr), conv(nr), prev(nr))
      conv = .false.;  prev = huge(1.0_dp)
      big = cmplx(huge(1.0_dp), 0.0_dp, dp)
      do it = 1, max_sweeps
         cf%sweeps = it
         do a = 1, nr
            step(a) = (0.0_dp, 0.0_dp)
            if (conv(a)) cycle
            call home_terms(om, cf, pp, a, cf%delta(a), t, tp, trbb)
            call home_pole(om, a, ph, po, idum)
            lo = (ph - po) + cf%delta(a)              ! lambda_a - p'_a
            if (t == (0.0_dp, 0.0_dp)) then
               hu = cf%delta(a);  hup = (1.0_dp, 0.0_dp)
            else
               hu = cf%delta(a) + t / lo
               hup = 1.0_dp + tp / lo - t / lo**2
            end if
            if (hu == (0.0_dp, 0.0_dp)) then          ! an exact root (a decoupled mode)
               conv(a) = .true.;  cycle
            end if
            s = (0.0_dp, 0.0_dp)
            do b = 1, nr
               if (b == a .or. cf%delta(b) == (0.0_dp, 0.0_dp)) cycle
               dab = poles(a) - poles(b)
               s = s + cf%delta(b) / (((dab + cf%delta(a)) * (dab + cf%delta(a) - cf%delta(b))))
            end do
            step(a) = 1.0_dp / (trbb + hup / hu - s)
         end do
         do a = 1, nr
            if (conv(a)) cycle
            cf%delta(a) = cf%delta(a) - step(a)
            if (abs(step(a)) <= 2.0_dp * eps * abs(cf%delta(a)) .or. &
                (abs(step(a)) >= 0.5_dp * prev(a) .and. &
                 abs(step(a)) <= 1.0e-13_dp * abs(cf%delta(a)))) conv(a) = .true.
            prev(a) = abs(step(a))
         end do
         if (all(conv)) exit
      end do
      if (all(om%d == 0.0_dp) .and. all(cf%cc == 0.0_dp)) then
         ! undamped: the roots are on the imaginary axis (so are the poles)
         cf%delta = cmplx(0.0_dp, aimag(cf%delta), dp)
      end if
      cf%lam = poles + cf%delta
      call check_roots(om, cf, poles, cf%identity_error)
      if (.not. (cf%identity_error <= identity_tol)) then
         call fatal_error(err, where // ': the roots of its secular equation fail the product ' &
            // 'check (relative error ' // str(cf%identity_error) // ' after ' &
            // str(cf%sweeps) // ' Aberth sweeps); the exact integrator cannot represent ' &
            // 'this configuration: use method = ''newmark''')
         return
      end if
   end subroutine secular_roots

   !> Initial offsets: first-order shifts of weakly coupled poles, the split of (nearly) double
   !> poles, and for the strongly coupled low modes the eigenvalues of a small dense problem.
   subroutine initial_guesses(om, cf, pp, poles)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      real(dp), intent(in) :: pp(:, :)
      complex(dp), intent(in) :: poles(:)
      complex(dp) :: t, tp, trbb, ph, po, dq, shift
      real(dp) :: scale
      logical :: near2
      logical, allocatable :: strong(:)
      integer :: a, h, mmax, nr
      nr = cf%nroot
      allocate(cf%delta(nr), strong(nr))
      mmax = 0
      do h = 1, nr
         call home_pole(om, h, ph, po, a)
         call home_terms(om, cf, pp, h, (0.0_dp, 0.0_dp), t, tp, trbb)
         dq = ph - po
         near2 = abs(dq) < near_double * abs(ph)
         if (near2) then
            shift = -0.5_dp * dq + merge(1.0_dp, -1.0_dp, h <= cf%n) * sqrt(0.25_dp * dq**2 - t)
            scale = abs(ph)
         else
            shift = -t / dq
            scale = min(abs(ph), abs(dq))
         end if
         if (.not. (abs(shift) < huge(1.0_dp))) shift = (0.0_dp, 0.0_dp)
         strong(h) = .not. (abs(shift) < weak_rel * scale)
         cf%delta(h) = shift
         if (strong(h)) then
            cf%delta(h) = (0.0_dp, 0.0_dp)
            if (a <= max_dense) mmax = max(mmax, a)
            if (a > max_dense) cf%delta(h) = shift
         end if
      end do
      if (mmax > 0) call dense_guesses(om, cf, poles, mmax)
   end subroutine initial_guesses

   !> Guesses for the poles of modes 1..m from the eigenvalues of the first-order matrix of
   !> those modes with the contact springs in series with the others' static flexibility,
   !> K_eff = (I + K_c R)^-1 K_c, R = sum_{j > m} psi_j psi_j' / w_j^2; matched greedily.
   subroutine dense_guesses(om, cf, poles, m)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      complex(dp), intent(in) :: poles(:)
      integer, intent(in) :: m
      real(dp), allocatable :: rf(:, :), keff(:, :), kd(:, :), cd(:, :), amat(:, :), wr(:), &
         wi(:), work(:), vl(:, :), vr(:, :), dist(:, :)
      complex(dp), allocatable :: ev(:), mat(:, :), rhs(:, :)
      integer, allocatable :: idx(:)
      logical, allocatable :: used_e(:), used_p(:)
      integer :: r, j, c, info, lwork, k, e, p, be, bp
      real(dp) :: q(1), dmin
      logical :: ok
      r = cf%r
      allocate(rf(r, r), source=0.0_dp)
      do j = m + 1, cf%n
         do c = 1, r
            rf(:, c) = rf(:, c) + cf%psi(j, :) * cf%psi(j, c) / om%w2(j)
         end do
      end do
      ! K_eff = (I + K_c R)^-1 K_c
      allocate(mat(r, r), rhs(r, r))
      do c = 1, r
         mat(c, :) = cmplx(cf%kc(c) * rf(c, :), 0.0_dp, dp)
         mat(c, c) = mat(c, c) + 1.0_dp
      end do
      rhs = (0.0_dp, 0.0_dp)
      do c = 1, r
         rhs(c, c) = cmplx(cf%kc(c), 0.0_dp, dp)
      end do
      call small_solve(mat, rhs, ok)
      keff = real(rhs)
      kd = matmul(cf%psi(1:m, :), matmul(keff, transpose(cf%psi(1:m, :))))
      allocate(cd(m, m), source=0.0_dp)
      do c = 1, r
         do j = 1, m
            cd(:, j) = cd(:, j) + cf%psi(1:m, c) * cf%cc(c) * cf%psi(j, c)
         end do
      end do
      do j = 1, m
         kd(j, j) = kd(j, j) + om%w2(j)
         cd(j, j) = cd(j, j) + om%d(j)
      end do
      allocate(amat(2 * m, 2 * m), source=0.0_dp)
      do j = 1, m
         amat(j, m + j) = 1.0_dp
      end do
      amat(m + 1:, 1:m) = -kd
      amat(m + 1:, m + 1:) = -cd
      allocate(wr(2 * m), wi(2 * m), vl(1, 1), vr(1, 1))
      call dgeev('N', 'N', 2 * m, amat, 2 * m, wr, wi, vl, 1, vr, 1, q, -1, info)
      lwork = max(1, int(q(1)))
      allocate(work(lwork))
      call dgeev('N', 'N', 2 * m, amat, 2 * m, wr, wi, vl, 1, vr, 1, work, lwork, info)
      if (info /= 0) return                 ! keep the first-order guesses; Aberth copes
      ev = cmplx(wr, wi, dp)
      idx = [(j, j = 1, m), (cf%n + j, j = 1, m)]
      allocate(dist(2 * m, 2 * m), used_e(2 * m), used_p(2 * m))
      do p = 1, 2 * m
         dist(:, p) = abs(ev - poles(idx(p)))
      end do
      used_e = .false.;  used_p = .false.
      do k = 1, 2 * m
         dmin = huge(1.0_dp);  be = 0;  bp = 0
         do p = 1, 2 * m
            if (used_p(p)) cycle
            do e = 1, 2 * m
               if (used_e(e)) cycle
               if (dist(e, p) < dmin) then
                  dmin = dist(e, p);  be = e;  bp = p
               end if
            end do
         end do
         if (be == 0) exit
         used_e(be) = .true.;  used_p(bp) = .true.
         cf%delta(idx(bp)) = ev(be) - poles(idx(bp))
      end do
   end subroutine dense_guesses

   !> Relative error of the product identity det S(z) = prod_a (1 - delta_a/(z - p_a)) at six
   !> points off the axes (undamped poles lie on the imaginary axis).
   subroutine check_roots(om, cf, poles, worst)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(in) :: cf
      complex(dp), intent(in) :: poles(:)
      real(dp), intent(out) :: worst
      complex(dp) :: zs(6), ratio, dets
      real(dp) :: smin, smax, smed, dv
      integer :: k, a
      smin = minval(abs(poles));  smax = maxval(abs(poles))
      smin = max(smin, tiny(1.0_dp));  smed = sqrt(smin * smax)
      zs = [smed * (0.1_dp, 1.0_dp), smin * (0.07_dp, 0.7_dp), smax * (0.1_dp, 1.0_dp), &
            0.3_dp * smin * (1.0_dp, 1.0_dp), -smed * (1.0_dp, 0.5_dp), smin * (0.3_dp, 3.0_dp)]
      worst = 0.0_dp
      do k = 1, size(zs)
         ratio = (1.0_dp, 0.0_dp)
         do a = 1, size(poles)
            ratio = ratio * (1.0_dp - cf%delta(a) / (zs(k) - poles(a)))
         end do
         dets = det_s(om, cf, zs(k))
         dv = abs(ratio / dets - 1.0_dp)
         if (.not. (dv <= huge(1.0_dp))) then
            worst = huge(1.0_dp);  return
         end if
         worst = max(worst, dv)
      end do
   end subroutine check_roots

   !> det S(z), S = I + G(z) Psi' Q_0(z)^-1 Psi.
   function det_s(om, cf, z) result(d)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(in) :: cf
      complex(dp), intent(in) :: z
      complex(dp) :: d
      complex(dp) :: s(cf%r, cf%r), iq
      integer :: j, c
      s = (0.0_dp, 0.0_dp)
      do j = 1, cf%n
         iq = 1.0_dp / ((z - om%p1(j)) * (z - om%p2(j)))
         do c = 1, cf%r
            s(:, c) = s(:, c) + cf%psi(j, :) * cf%psi(j, c) * iq
         end do
      end do
      do c = 1, cf%r
         s(c, :) = s(c, :) * (cf%kc(c) + cf%cc(c) * z)
         s(c, c) = s(c, c) + 1.0_dp
      end do
      d = small_det(s)
   end function det_s

   !> Eigenvectors x_a = e_a + z_a, nu_a = x_a' Q_c'(lambda_a) x_a, for every root.
   subroutine root_vectors(om, cf)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      complex(dp), allocatable :: iq(:), dq(:)
      complex(dp) :: ph, po, q1, q2, lam, p(cf%r, cf%r), g(cf%r), w(cf%r, 1), gw(cf%r)
      integer :: h, a, j, c, n
      logical :: ok
      n = cf%n
      allocate(cf%x(n, cf%nroot), cf%nu(cf%nroot), iq(n), dq(n))
      do h = 1, cf%nroot
         call home_pole(om, h, ph, po, a)
         lam = cf%lam(h)
         p = (0.0_dp, 0.0_dp)
         do j = 1, n
            q1 = (ph - om%p1(j)) + cf%delta(h)
            q2 = (ph - om%p2(j)) + cf%delta(h)
            dq(j) = q1 + q2
            if (j == a) then
               iq(j) = (0.0_dp, 0.0_dp)
               cycle
            end if
            iq(j) = 1.0_dp / (q1 * q2)
            do c = 1, cf%r
               p(:, c) = p(:, c) + cf%psi(j, :) * cf%psi(j, c) * iq(j)
            end do
         end do
         g = cf%kc + cf%cc * lam
         do c = 1, cf%r                       ! A = I + P G
            p(:, c) = p(:, c) * g(c)
            p(c, c) = p(c, c) + 1.0_dp
         end do
         w(:, 1) = cmplx(cf%psi(a, :), 0.0_dp, dp)
         call small_solve(p, w, ok)
         gw = g * w(:, 1)
         cf%x(:, h) = -iq * matmul(cf%psi, gw)
         cf%x(a, h) = (1.0_dp, 0.0_dp)
         cf%nu(h) = sum(cf%x(:, h)**2 * dq) + sum(cf%cc * w(:, 1)**2)
      end do
   end subroutine root_vectors

   !> Pair the roots of the two poles of each underdamped mode when they are complex
   !> conjugates (to 1e-10, as the set of a real problem is): the second is then set to the
   !> exact conjugate of the first (offset, eigenvector, nu), so that the segments can keep one
   !> term per pair with twice its coefficient.
   subroutine conjugate_pairs(om, cf)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      integer :: j, a, b
      allocate(cf%partner(cf%nroot), source=0)
      do j = 1, cf%n
         if (.not. (aimag(om%p1(j)) > 0.0_dp)) cycle
         a = j;  b = cf%n + j
         if (.not. (aimag(cf%lam(a)) > 0.0_dp)) cycle
         if (.not. (abs(cf%lam(b) - conjg(cf%lam(a))) <= 1.0e-10_dp * abs(cf%lam(a)))) cycle
         cf%partner(a) = b;  cf%partner(b) = a
         cf%delta(b) = conjg(cf%delta(a))
         cf%lam(b) = conjg(cf%lam(a))
         cf%x(:, b) = conjg(cf%x(:, a))
         cf%nu(b) = conjg(cf%nu(a))
      end do
   end subroutine conjugate_pairs

   !> Nearly coalescing roots (eigenvalue condition above 1/tol_cluster) paired into blocks.
   subroutine find_blocks(om, cf, where, err)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      character(len=*), intent(in) :: where
      type(error_t), allocatable, intent(inout) :: err
      real(dp), allocatable :: kappa(:)
      logical, allocatable :: bad(:)
      integer :: i, j, k, nb
      real(dp) :: dmin, kmax
      allocate(kappa(cf%nroot))
      do i = 1, cf%nroot
         kappa(i) = condition(abs(cf%lam(i)) * sum(abs(cf%x(:, i))**2), abs(cf%nu(i)))
      end do
      allocate(bad(cf%nroot))
      bad = kappa > 1.0_dp / tol_cluster
      allocate(cf%simple(cf%nroot), source=.true.)
      nb = count(bad)
      allocate(cf%blk(nb / 2 + 1))
      cf%nblk = 0
      do
         ! the worst remaining root, paired with the nearest other bad root
         kmax = -1.0_dp;  i = 0
         do k = 1, cf%nroot
            if (bad(k) .and. cf%simple(k) .and. kappa(k) > kmax) then
               kmax = kappa(k);  i = k
            end if
         end do
         if (i == 0) exit
         dmin = huge(1.0_dp);  j = 0
         do k = 1, cf%nroot
            if (k == i .or. .not. bad(k) .or. .not. cf%simple(k)) cycle
            if (abs(cf%lam(k) - cf%lam(i)) < dmin) then
               dmin = abs(cf%lam(k) - cf%lam(i));  j = k
            end if
         end do
         if (j == 0) then
            call fatal_error(err, where // ': the root ' // str(real(cf%lam(i))) // ' + ' &
               // str(aimag(cf%lam(i))) // 'i is ill-conditioned (condition ' // str(kappa(i)) &
               // ') without a partner to merge it with')
            return
         end if
         cf%simple(i) = .false.;  cf%simple(j) = .false.
         cf%nblk = cf%nblk + 1
         cf%blk(cf%nblk)%i1 = i;  cf%blk(cf%nblk)%i2 = j
         call block_quadratic(om, cf, cf%blk(cf%nblk), where, err)
         if (allocated(err)) return
      end do
   end subroutine find_blocks

   !> m and delta^2 of the two roots inside a circle around a block, from the power sums
   !> p_k = (1/2 pi i) oint (lambda - c)^k (log det Q_c)' d lambda (trapezoidal rule).
   subroutine block_quadratic(om, cf, bk, where, err)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(in) :: cf
      type(block_t), intent(inout) :: bk
      character(len=*), intent(in) :: where
      type(error_t), allocatable, intent(inout) :: err
      complex(dp) :: c, z1, z2, ld, ps(0:2), e
      real(dp) :: rad, dist, rho, th, zr
      integer :: k, i
      z1 = cf%lam(bk%i1);  z2 = cf%lam(bk%i2)
      c = 0.5_dp * (z1 + z2)
      zr = max(abs(z1 - c), abs(z2 - c))
      dist = huge(1.0_dp)
      do i = 1, cf%nroot
         if (i == bk%i1 .or. i == bk%i2) cycle
         dist = min(dist, abs(cf%lam(i) - c))
      end do
      do i = 1, cf%n
         if (abs(om%p1(i) - c) > 4.0_dp * zr) dist = min(dist, abs(om%p1(i) - c))
         if (abs(om%p2(i) - c) > 4.0_dp * zr) dist = min(dist, abs(om%p2(i) - c))
      end do
      ! the trapezoidal rule errs by (rad / rho)^N + (rho / dist)^N; Q_c near the block is
      ! evaluated with an absolute error ~ eps |lambda|^2, i.e. relative ~ eps |c|^2 / rho^2:
      ! so the circle is taken as wide as the neighbours allow
      rad = max(0.5_dp * abs(z1 - z2), 1.0e-8_dp * abs(c))
      if (dist > 9.0_dp * rad) then
         rho = dist / 3.0_dp
      else if (dist > 4.0_dp * rad) then
         rho = sqrt(rad * dist)
      else
         rho = 2.0_dp * rad
      end if
      ps = (0.0_dp, 0.0_dp)
      do k = 1, n_contour
         th = 2.0_dp * pi * (real(k, dp) - 0.5_dp) / real(n_contour, dp)
         e = cmplx(cos(th), sin(th), dp)
         bk%pts(k) = c + rho * e
         bk%wts(k) = rho * e / real(n_contour, dp)
         ld = log_derivative(om, cf, bk%pts(k))
         ps = ps + bk%wts(k) * [(1.0_dp, 0.0_dp), rho * e, (rho * e)**2] * ld
      end do
      if (.not. (abs(ps(0) - 2.0_dp) <= 1.0e-6_dp)) then
         call fatal_error(err, where // ': a nearly double root at ' // str(real(c)) // ' + ' &
            // str(aimag(c)) // 'i is not isolated (the circle around it holds ' &
            // str(real(ps(0))) // ' roots, not 2)')
         return
      end if
      bk%m = c + 0.5_dp * ps(1)
      bk%d2 = 0.25_dp * (2.0_dp * ps(2) - ps(1)**2)
      call block_bounds(bk)
   end subroutine block_quadratic

   !> (log det Q_c)'(lambda) = sum_j q_j'/q_j + tr(S^-1 S').
   function log_derivative(om, cf, lam) result(ld)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(in) :: cf
      complex(dp), intent(in) :: lam
      complex(dp) :: ld
      complex(dp) :: s(cf%r, cf%r), sp(cf%r, cf%r), iq, diq, q1, q2, g, si(cf%r, cf%r)
      integer :: j, c
      logical :: ok
      ld = (0.0_dp, 0.0_dp)
      s = (0.0_dp, 0.0_dp);  sp = (0.0_dp, 0.0_dp)
      do j = 1, cf%n
         q1 = lam - om%p1(j);  q2 = lam - om%p2(j)
         ld = ld + 1.0_dp / q1 + 1.0_dp / q2
         iq = 1.0_dp / (q1 * q2)
         diq = -(q1 + q2) * iq * iq
         do c = 1, cf%r
            s(:, c) = s(:, c) + cf%psi(j, :) * cf%psi(j, c) * iq
            sp(:, c) = sp(:, c) + cf%psi(j, :) * cf%psi(j, c) * diq
         end do
      end do
      do c = 1, cf%r
         g = cf%kc(c) + cf%cc(c) * lam
         sp(c, :) = cf%cc(c) * s(c, :) + g * sp(c, :)
         s(c, :) = g * s(c, :)
         s(c, c) = s(c, c) + 1.0_dp
      end do
      call small_inverse(s, si, ok)
      do c = 1, cf%r
         ld = ld + sum(si(c, :) * sp(:, c))
      end do
   end function log_derivative

   !> Eigenvalue condition num / den, capped at 1e300 (a double root has den = 0).
   pure real(dp) function condition(num, den)
      real(dp), intent(in) :: num, den
      condition = 1.0e300_dp
      if (den > 1.0e-300_dp * num) condition = num / den
   end function condition

   !> Bound data of a block: max |m +- delta| and max Re(m +- delta).
   pure subroutine block_bounds(bk)
      type(block_t), intent(inout) :: bk
      complex(dp) :: dl
      dl = sqrt(bk%d2)
      bk%lam_abs = max(abs(bk%m + dl), abs(bk%m - dl))
      bk%sig = max(real(bk%m + dl), real(bk%m - dl))
   end subroutine block_bounds

   !> Q_c(lambda)^-1 b by Woodbury on the diagonal plus rank r; ok false when singular.
   subroutine config_solve(om, cf, lam, b, y, ok)
      type(open_modes_t), intent(in) :: om          !! open structure
      type(config_t), intent(in) :: cf              !! configuration
      complex(dp), intent(in) :: lam                !! argument [1/s]
      complex(dp), intent(in) :: b(:)               !! (n) right-hand side
      complex(dp), intent(out) :: y(:)              !! (n) solution
      logical, intent(out) :: ok                    !! not singular
      complex(dp) :: q(cf%n), s(cf%r, cf%r), rhs(cf%r, 1), xm(cf%n, cf%r), g(cf%r)
      integer :: c
      q = (lam - om%p1) * (lam - om%p2)
      ok = all(q /= (0.0_dp, 0.0_dp))
      if (.not. ok) return
      if (cf%r == 0) then
         y = b / q
         return
      end if
      do c = 1, cf%r
         xm(:, c) = cf%psi(:, c) / q
      end do
      g = cf%kc + cf%cc * lam
      s = matmul(transpose(cmplx(cf%psi, 0.0_dp, dp)), xm)
      do c = 1, cf%r
         s(c, :) = g(c) * s(c, :)
         s(c, c) = s(c, c) + 1.0_dp
         rhs(c, 1) = g(c) * sum(xm(:, c) * b)
      end do
      call small_solve(s, rhs, ok)
      if (.not. ok) return
      y = b / q - matmul(xm, rhs(:, 1))
   end subroutine config_solve

   !> Functionals of the eigenvectors and of the particular solutions.
   subroutine functional_rows(om, cf)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(inout) :: cf
      integer :: h, a, b
      complex(dp) :: ph, po
      allocate(cf%lrow(cf%nroot, om%nb))
      if (cf%r == 0) then
         do h = 1, cf%nroot
            call home_pole(om, h, ph, po, a)
            cf%lrow(h, :) = cmplx(om%ell(a, :), 0.0_dp, dp)
         end do
      else
         do b = 1, om%nb
            cf%lrow(:, b) = matmul(cmplx(om%ell(:, b), 0.0_dp, dp), cf%x)
         end do
      end if
      cf%ly = matmul(cf%y, om%ell)
      cf%ls = matmul(cf%eta_s, om%ell)
   end subroutine functional_rows

   !> Solve A X = B in place (B <- X) for a small complex A (Gauss-Jordan, partial pivoting).
   pure subroutine small_solve(a, b, ok)
      complex(dp), intent(in) :: a(:, :)            !! (r, r) matrix
      complex(dp), intent(inout) :: b(:, :)         !! (r, m) right-hand sides, solution
      logical, intent(out) :: ok                    !! not singular
      complex(dp) :: w(size(a, 1), size(a, 2)), row(size(a, 2)), rb(size(b, 2)), f
      integer :: n, k, p, i
      n = size(a, 1)
      w = a
      ok = .true.
      do k = 1, n
         p = k - 1 + maxloc(abs(w(k:, k)), 1)
         if (w(p, k) == (0.0_dp, 0.0_dp)) then
            ok = .false.;  return
         end if
         if (p /= k) then
            row = w(k, :);  w(k, :) = w(p, :);  w(p, :) = row
            rb = b(k, :);  b(k, :) = b(p, :);  b(p, :) = rb
         end if
         f = 1.0_dp / w(k, k)
         w(k, :) = w(k, :) * f;  b(k, :) = b(k, :) * f
         do i = 1, n
            if (i == k) cycle
            f = w(i, k)
            if (f == (0.0_dp, 0.0_dp)) cycle
            w(i, :) = w(i, :) - f * w(k, :)
            b(i, :) = b(i, :) - f * b(k, :)
         end do
      end do
   end subroutine small_solve

   !> Inverse of a small complex matrix.
   pure subroutine small_inverse(a, ai, ok)
      complex(dp), intent(in) :: a(:, :)
      complex(dp), intent(out) :: ai(:, :)
      logical, intent(out) :: ok
      integer :: i
      ai = (0.0_dp, 0.0_dp)
      do i = 1, size(a, 1)
         ai(i, i) = (1.0_dp, 0.0_dp)
      end do
      call small_solve(a, ai, ok)
   end subroutine small_inverse

   !> Determinant of a small complex matrix (LU with partial pivoting).
   pure complex(dp) function small_det(a) result(d)
      complex(dp), intent(in) :: a(:, :)
      complex(dp) :: w(size(a, 1), size(a, 2)), row(size(a, 2)), f
      integer :: n, k, p, i
      n = size(a, 1)
      w = a
      d = (1.0_dp, 0.0_dp)
      do k = 1, n
         p = k - 1 + maxloc(abs(w(k:, k)), 1)
         if (p /= k) then
            row = w(k, :);  w(k, :) = w(p, :);  w(p, :) = row
            d = -d
         end if
         d = d * w(k, k)
         if (w(k, k) == (0.0_dp, 0.0_dp)) return
         do i = k + 1, n
            f = w(i, k) / w(k, k)
            w(i, k:) = w(i, k:) - f * w(k, k:)
         end do
      end do
   end function small_det

   !> '(active contacts: 1 3)' style text of a mask.
   function mask_text(mask, nc) result(s)
      integer(int64), intent(in) :: mask             !! active contacts
      integer, intent(in) :: nc                      !! contacts
      character(len=:), allocatable :: s
      integer :: c
      s = '(active contacts:'
      do c = 1, nc
         if (btest(mask, c - 1)) s = s // ' ' // str(c)
      end do
      if (mask == 0) s = s // ' none'
      s = s // ')'
   end function mask_text
end module gapbeam_exact_config
