!> The closed form of one linear segment of the exact event-driven integrator (gapbeam_exact):
!> the motion between two switches of the contact configuration, from a modal state, as sums
!> of exponentials; their values, derivative bounds, end state and window statistics.
!>
!> From the modal state (eta, v) at the segment start (forcing phase Omega r0) the particular
!> parts are subtracted, eta_h = eta - eta_s - Re(Y e^{i Omega r0}) (and the same for v), and
!> the transient is projected with the residue formula of the symmetric quadratic eigenproblem
!> (no eigenvector matrix is inverted, so its condition plays no part):
!>
!>    eta_h(tau) = sum_a c_a x_a e^{lambda_a tau},   c_a = s_a / nu_a,
!>    s_a = x_a'[(lambda_a I + D + Psi C_c Psi') eta_h + v_h]
!>
!> (x_a = e_j for the open configuration). A block of two nearly coalescing roots (see
!> gapbeam_exact_config) contributes e^{m tau}[cosh(delta tau) M0 + sinh(delta tau)/delta M1]
!> with the moments M0, M1 of the Laplace transform Q_c^-1[(lambda + D_c) eta_h + v_h] on the
!> block's circle (open configuration: M0 = eta_h,j e_j, M1 = (v_h,j - m eta_h,j) e_j).
!>
!> Every watched functional l_b (contact dofs, root strain, tip) is then
!>
!>    phi_b(tau) = l_b'eta_s + Re(h_b e^{i Omega tau}) + Re sum_a a_ab e^{lambda_a tau}
!>                 + sum_blocks Re(e^{m tau}[A_b C(tau) + B_b S(tau)])
!>
!> (`segment_t`, `eval_seg`): its derivatives multiply a_ab by lambda_a^k (blocks:
!> (A, B) -> (m A + B, delta^2 A + m B)), and sup_{s >= tau} |phi_b^(k)(s)| is bounded by
!> sum |a_ab| |lambda_a|^k e^{Re lambda_a tau} plus |h_b| Omega^k plus, per block,
!> |A| L^k e^{sigma tau} + |B| (k L^{k-1} + s* L^k) e^{sigma s*} (L = max|m +- delta|,
!> sigma = max Re(m +- delta), s* where that bound peaks beyond tau): e^{m s} S(s) is the divided
!> difference of e^{z s} over [m - delta, m + delta]. A decayed term below prune_tol of every
!> functional leaves the evaluations (`prune_seg`). Integrals of
!> a contact force, its square and f |d'| over a window follow in closed form
!> (`modal_window`; a block there is split into its two exponentials, or expanded about the
!> window start as e^{m s} times a polynomial when delta is too small for the split).
module gapbeam_exact_segment
   use gapbeam_kinds, only: dp
   use gapbeam_lapack, only: zgemm
   use gapbeam_exact_modes, only: open_modes_t
   use gapbeam_exact_config, only: config_t, config_solve, n_contour
   implicit none
   private
   public :: segment_t, start_segment, eval_seg, prune_seg, segment_values, segment_state, &
      modal_window, sign_after, band, add_fn, mono_quad, cubic_root


   real(dp), parameter :: zero_tol = 1.0e-12_dp    !! |phi^(k)| <= zero_tol * scale: zero
   real(dp), parameter :: prune_tol = 1.0e-17_dp   !! a decayed term below this is dropped
   integer, parameter :: deg_poly = 5               ! polynomial of a block in a window
   real(dp), parameter :: inv_k(10) = 1.0_dp / [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp, &
      6.0_dp, 7.0_dp, 8.0_dp, 9.0_dp, 10.0_dp]

   !> The current linear segment: coefficients of the state and of every watched functional.
   type :: segment_t
      integer :: nt = 0                             !! terms: simple roots, then the harmonic
      integer, allocatable :: root(:)               !! (nt) root of each term (0: harmonic)
      complex(dp), allocatable :: mu(:)             !! (nt) exponents [1/s]
      complex(dp), allocatable :: mp(:, :)          !! (3, nt) mu, mu^2, mu^3
      real(dp), allocatable :: am(:, :)             !! (0:4, nt) |mu|^k
      complex(dp), allocatable :: a(:, :)           !! (nt, nb) functional coefficients
      real(dp), allocatable :: absa(:, :)           !! |a|
      real(dp), allocatable :: a0(:)                !! (nb) constants (static part)
      complex(dp), allocatable :: e(:)              !! (nt) e^{mu tau} at the last evaluation
      real(dp), allocatable :: me(:)                !! |e^{mu tau}| there
      logical, allocatable :: live(:)               !! not pruned
      logical, allocatable :: real_term(:)          !! real exponent
      real(dp), allocatable :: tail(:, :)           !! (0:4, nb) bounds of the pruned terms
      integer :: n_eval = 0                         !! evaluations
      integer :: n_recur = 0                        !! evaluations by recurrence in a row
      real(dp) :: tau_last = 0.0_dp                 !! instant of the last evaluation [s]
      real(dp) :: mu_max = 0.0_dp                   !! largest |mu| [1/s]
      real(dp) :: horizon = 0.0_dp                  !! longest the segment can last [s]
      complex(dp), allocatable :: coef(:)           !! (2n) state coefficient of each root
      complex(dp), allocatable :: yt(:)             !! (n) Y e^{i Omega r0}
      real(dp) :: omega = 0.0_dp                    !! forcing [rad/s]
      ! blocks
      integer :: nblk = 0                           !! blocks
      complex(dp), allocatable :: bm(:), bd2(:)     !! (nblk) m, delta^2
      real(dp), allocatable :: blam(:), bsig(:)     !! (nblk) max |m +- delta|, max Re
      complex(dp), allocatable :: bm0(:, :), bm1(:, :)  !! (n, nblk) moments M0, M1
      complex(dp), allocatable :: ba(:, :), bb(:, :)    !! (nblk, nb) A_b, B_b
   end type segment_t

contains

   ! ------------------------------------------------------------------ projection

   !> The segment of configuration cf starting from the modal state (eta, vel) at forcing
   !> offset r0 [s].
   subroutine start_segment(om, cf, omega, period, eta, vel, r0, sg)
      type(open_modes_t), intent(in) :: om          !! open structure
      type(config_t), intent(in) :: cf              !! configuration
      real(dp), intent(in) :: omega, period         !! forcing [rad/s], [s]
      real(dp), intent(in) :: eta(:), vel(:)        !! (n) modal state
      real(dp), intent(in) :: r0                    !! forcing offset [s]
      type(segment_t), intent(inout) :: sg          !! the segment
      complex(dp) :: ph
      real(dp), allocatable :: eh(:), vh(:), cpsi(:)
      complex(dp), allocatable :: u(:, :), s(:, :)
      integer :: n, nr, nb, j, k, rho
      n = cf%n;  nr = cf%nroot;  nb = om%nb
      ph = cmplx(cos(omega * r0), sin(omega * r0), dp)
      sg%omega = omega
      sg%horizon = 2.0_dp * period
      sg%yt = cf%y * ph
      eh = eta - cf%eta_s - real(sg%yt)
      vh = vel - real(cmplx(0.0_dp, omega, dp) * sg%yt)
      allocate(cpsi(n), source=0.0_dp)
      if (cf%r > 0) cpsi = matmul(cf%psi, cf%cc * matmul(eh, cf%psi))
      if (allocated(sg%coef)) deallocate(sg%coef)
      allocate(sg%coef(nr), source=(0.0_dp, 0.0_dp))
      if (cf%r == 0) then
         do rho = 1, nr
            if (.not. cf%simple(rho)) cycle
            j = rho;  if (j > n) j = j - n
            sg%coef(rho) = ((cf%lam(rho) + om%d(j)) * eh(j) + vh(j)) / cf%nu(rho)
         end do
      else
         allocate(u(n, 2), s(nr, 2))
         u(:, 1) = cmplx(vh + cpsi + om%d * eh, 0.0_dp, dp)
         u(:, 2) = cmplx(eh, 0.0_dp, dp)
         call zgemm('T', 'N', nr, 2, n, (1.0_dp, 0.0_dp), cf%x, n, u, n, (0.0_dp, 0.0_dp), s, nr)
         do rho = 1, nr
            if (cf%simple(rho)) sg%coef(rho) = (s(rho, 1) + cf%lam(rho) * s(rho, 2)) / cf%nu(rho)
         end do
      end if
      ! terms: the simple roots (one of each complex-conjugate pair, its coefficient doubled:
      ! Re(a e^{lambda t}) + Re(conj(a) e^{conj(lambda) t}) = Re(2 a e^{lambda t})), then the
      ! harmonic
      call size_terms(sg, count(cf%simple .and. .not. (cf%partner > 0 .and. &
                      cf%partner < [(rho, rho = 1, nr)])) + 1, nb)
      k = 0
      do rho = 1, nr
         if (.not. cf%simple(rho)) cycle
         if (cf%partner(rho) > 0 .and. cf%partner(rho) < rho) cycle
         k = k + 1
         sg%root(k) = rho
         sg%mu(k) = cf%lam(rho)
         sg%a(k, :) = sg%coef(rho) * cf%lrow(rho, :)
         if (cf%partner(rho) > 0) sg%a(k, :) = 2.0_dp * sg%a(k, :)
      end do
      k = k + 1
      sg%root(k) = 0
      sg%mu(k) = cmplx(0.0_dp, omega, dp)
      sg%a(k, :) = cf%ly * ph
      sg%a0 = cf%ls
      do k = 1, sg%nt
         sg%mp(1, k) = sg%mu(k)
         sg%mp(2, k) = sg%mu(k)**2
         sg%mp(3, k) = sg%mu(k)**3
         sg%am(0, k) = 1.0_dp
         sg%am(1, k) = abs(sg%mu(k))
         sg%am(2, k) = sg%am(1, k)**2
         sg%am(3, k) = sg%am(1, k)**3
         sg%am(4, k) = sg%am(2, k)**2
         sg%real_term(k) = aimag(sg%mu(k)) == 0.0_dp
      end do
      sg%absa = abs(sg%a)
      sg%mu_max = maxval(sg%am(1, :))
      sg%live = .true.
      sg%tail = 0.0_dp
      sg%n_eval = 0;  sg%n_recur = 0;  sg%tau_last = 0.0_dp
      call start_blocks(om, cf, eh, vh, cpsi, sg)
   end subroutine start_segment

   !> Allocate the term arrays for nt terms and nb functionals (reused when the sizes match).
   subroutine size_terms(sg, nt, nb)
      type(segment_t), intent(inout) :: sg
      integer, intent(in) :: nt, nb
      if (allocated(sg%mu)) then
         if (size(sg%mu) /= nt .or. size(sg%a, 2) /= nb) deallocate(sg%root, sg%mu, sg%mp, &
            sg%am, sg%a, sg%absa, sg%a0, sg%e, sg%me, sg%live, sg%real_term, sg%tail)
      end if
      if (.not. allocated(sg%mu)) allocate(sg%root(nt), sg%mu(nt), sg%mp(3, nt), &
         sg%am(0:4, nt), sg%a(nt, nb), sg%absa(nt, nb), sg%a0(nb), sg%e(nt), sg%me(nt), &
         sg%live(nt), sg%real_term(nt), sg%tail(0:4, nb))
      sg%nt = nt
   end subroutine size_terms

   !> Moments of the blocks: M0 = sum_k w_k e_k, M1 = sum_k w_k (lambda_k - m) e_k with
   !> e_k = Q_c(lambda_k)^-1 [(lambda_k + D) eta_h + v_h + Psi C_c Psi' eta_h].
   subroutine start_blocks(om, cf, eh, vh, cpsi, sg)
      type(open_modes_t), intent(in) :: om
      type(config_t), intent(in) :: cf
      real(dp), intent(in) :: eh(:), vh(:), cpsi(:)
      type(segment_t), intent(inout) :: sg
      complex(dp), allocatable :: rhs(:), e(:)
      integer :: ib, k, j, n
      logical :: ok
      n = cf%n
      sg%nblk = cf%nblk
      if (allocated(sg%bm)) deallocate(sg%bm, sg%bd2, sg%blam, sg%bsig, sg%bm0, sg%bm1, sg%ba, &
                                       sg%bb)
      allocate(sg%bm(cf%nblk), sg%bd2(cf%nblk), sg%blam(cf%nblk), sg%bsig(cf%nblk), &
               sg%bm0(n, cf%nblk), sg%bm1(n, cf%nblk), sg%ba(cf%nblk, om%nb), &
               sg%bb(cf%nblk, om%nb))
      if (cf%nblk == 0) return
      allocate(rhs(n), e(n))
      do ib = 1, cf%nblk
         associate (bk => cf%blk(ib))
            sg%bm(ib) = bk%m;  sg%bd2(ib) = bk%d2
            sg%blam(ib) = bk%lam_abs;  sg%bsig(ib) = bk%sig
            sg%bm0(:, ib) = (0.0_dp, 0.0_dp);  sg%bm1(:, ib) = (0.0_dp, 0.0_dp)
            if (bk%mode > 0) then
               j = bk%mode
               sg%bm0(j, ib) = eh(j)
               sg%bm1(j, ib) = vh(j) - bk%m * eh(j)
            else
               do k = 1, n_contour
                  rhs = (bk%pts(k) + om%d) * eh + vh + cpsi
                  call config_solve(om, cf, bk%pts(k), rhs, e, ok)
                  sg%bm0(:, ib) = sg%bm0(:, ib) + bk%wts(k) * e
                  sg%bm1(:, ib) = sg%bm1(:, ib) + bk%wts(k) * (bk%pts(k) - bk%m) * e
               end do
            end if
         end associate
         sg%ba(ib, :) = matmul(sg%bm0(:, ib), om%ell)
         sg%bb(ib, :) = matmul(sg%bm1(:, ib), om%ell)
      end do
   end subroutine start_blocks

   ! ------------------------------------------------------------------ evaluation

   !> e^{m tau} cosh(delta tau) and e^{m tau} sinh(delta tau)/delta for delta^2 = d2: entire in
   !> d2, so exact and smooth through delta = 0 (series for |d2 tau^2| < 1).
   pure subroutine block_fn(m, d2, tau, ec, es)
      complex(dp), intent(in) :: m, d2
      real(dp), intent(in) :: tau
      complex(dp), intent(out) :: ec, es
      complex(dp) :: z2, t, c, s, dl, ep, em
      integer :: k
      z2 = d2 * tau * tau
      if (abs(z2) < 1.0_dp) then
         c = (0.0_dp, 0.0_dp);  s = (0.0_dp, 0.0_dp);  t = (1.0_dp, 0.0_dp)
         do k = 0, 13
            c = c + t / fact(2 * k)
            s = s + t / fact(2 * k + 1)
            t = t * z2
         end do
         ec = exp(m * tau) * c
         es = exp(m * tau) * tau * s
      else
         dl = sqrt(d2)
         ep = exp((m + dl) * tau);  em = exp((m - dl) * tau)
         ec = 0.5_dp * (ep + em)
         es = (ep - em) / (2.0_dp * dl)
      end if
   end subroutine block_fn

   !> k! as a real.
   pure real(dp) function fact(k)
      integer, intent(in) :: k
      integer :: i
      fact = 1.0_dp
      do i = 2, k
         fact = fact * real(i, dp)
      end do
   end function fact

   !> Values (derivatives 0..3) and bounds (0..4, over the rest of the segment) of the needed
   !> functionals at tau.
   subroutine eval_seg(sg, tau, need, val, bnd)
      type(segment_t), intent(inout) :: sg          !! segment
      real(dp), intent(in) :: tau                   !! instant [s]
      logical, intent(in) :: need(:)                !! functionals wanted
      real(dp), intent(out) :: val(0:, :)           !! (0:3, nb) values and derivatives
      real(dp), intent(out) :: bnd(0:, :)           !! (0:4, nb) bounds
      integer :: j, b, k
      real(dp) :: me, er, ei, zr, zi, mag, dt, v0, v1, v2, v3, u0, u1, u2, u3, u4
      complex(dp) :: zd, ez
      logical :: recur
      val = 0.0_dp;  bnd = 0.0_dp
      sg%n_eval = sg%n_eval + 1
      ! close to the last instant every e^{mu tau} follows from the last one times the Taylor
      ! series of e^{mu dt} (|mu dt| <= 1/16: degree 10 is exact to 1e-18), at most 4 times in
      ! a row (the products accumulate a few ulps); otherwise exp, cos and sin
      dt = tau - sg%tau_last
      recur = sg%n_recur < 4 .and. abs(dt) * sg%mu_max <= 0.0625_dp .and. sg%n_eval > 1
      if (recur) then
         sg%n_recur = sg%n_recur + 1
      else
         sg%n_recur = 0
      end if
      sg%tau_last = tau
      do j = 1, sg%nt
         if (.not. sg%live(j)) cycle
         if (recur) then
            zd = sg%mu(j) * dt
            ez = (1.0_dp, 0.0_dp) + zd * inv_k(10)
            do k = 9, 1, -1
               ez = (1.0_dp, 0.0_dp) + (zd * inv_k(k)) * ez
            end do
            sg%e(j) = sg%e(j) * ez
            er = real(sg%e(j));  ei = aimag(sg%e(j))
            me = sqrt(er**2 + ei**2)
         else
            me = exp(real(sg%mu(j)) * tau)
            if (sg%real_term(j)) then
               er = me;  ei = 0.0_dp
            else
               er = me * cos(aimag(sg%mu(j)) * tau)
               ei = me * sin(aimag(sg%mu(j)) * tau)
            end if
            sg%e(j) = cmplx(er, ei, dp)
         end if
         sg%me(j) = me
      end do
      do b = 1, size(need)
         if (.not. need(b)) cycle
         v0 = sg%a0(b);  v1 = 0.0_dp;  v2 = 0.0_dp;  v3 = 0.0_dp
         u0 = abs(sg%a0(b));  u1 = 0.0_dp;  u2 = 0.0_dp;  u3 = 0.0_dp;  u4 = 0.0_dp
         do j = 1, sg%nt
            if (.not. sg%live(j)) cycle
            er = real(sg%e(j));  ei = aimag(sg%e(j))
            zr = real(sg%a(j, b)) * er - aimag(sg%a(j, b)) * ei
            zi = real(sg%a(j, b)) * ei + aimag(sg%a(j, b)) * er
            v0 = v0 + zr
            v1 = v1 + zr * real(sg%mp(1, j)) - zi * aimag(sg%mp(1, j))
            v2 = v2 + zr * real(sg%mp(2, j)) - zi * aimag(sg%mp(2, j))
            v3 = v3 + zr * real(sg%mp(3, j)) - zi * aimag(sg%mp(3, j))
            mag = sg%absa(j, b) * sg%me(j)
            u0 = u0 + mag
            u1 = u1 + mag * sg%am(1, j)
            u2 = u2 + mag * sg%am(2, j)
            u3 = u3 + mag * sg%am(3, j)
            u4 = u4 + mag * sg%am(4, j)
         end do
         val(0, b) = v0;  val(1, b) = v1;  val(2, b) = v2;  val(3, b) = v3
         bnd(0, b) = u0 + sg%tail(0, b);  bnd(1, b) = u1 + sg%tail(1, b)
         bnd(2, b) = u2 + sg%tail(2, b);  bnd(3, b) = u3 + sg%tail(3, b)
         bnd(4, b) = u4 + sg%tail(4, b)
      end do
      if (sg%nblk > 0) call eval_blocks(sg, tau, need, val, bnd)
   end subroutine eval_seg

   !> Add the blocks' values and bounds.
   pure subroutine eval_blocks(sg, tau, need, val, bnd)
      type(segment_t), intent(in) :: sg
      real(dp), intent(in) :: tau
      logical, intent(in) :: need(:)
      real(dp), intent(inout) :: val(0:, :), bnd(0:, :)
      integer :: ib, b, k
      complex(dp) :: ec, es, ca, cb, t
      real(dp) :: lam, sig, sc, ss, s0, alpha, beta
      do ib = 1, sg%nblk
         call block_fn(sg%bm(ib), sg%bd2(ib), tau, ec, es)
         lam = sg%blam(ib);  sig = sg%bsig(ib)
         do b = 1, size(need)
            if (.not. need(b)) cycle
            ca = sg%ba(ib, b);  cb = sg%bb(ib, b)
            do k = 0, ubound(val, 1)
               val(k, b) = val(k, b) + real(ca * ec + cb * es)
               t = sg%bm(ib) * ca + cb
               cb = sg%bd2(ib) * ca + sg%bm(ib) * cb
               ca = t
            end do
            do k = 0, ubound(bnd, 1)
               ! the C part: |A| L^k e^{sigma s}; the S part: |B| (k L^{k-1} + s L^k) e^{sigma s},
               ! each at its largest over s >= tau
               alpha = real(k, dp) * lam**max(k - 1, 0)
               beta = lam**k
               if (sig < 0.0_dp) then
                  sc = tau
                  s0 = -1.0_dp / sig
                  if (beta > 0.0_dp) s0 = s0 - alpha / beta
                  ss = max(tau, s0)
               else
                  sc = max(tau, sg%horizon);  ss = sc
               end if
               bnd(k, b) = bnd(k, b) + abs(sg%ba(ib, b)) * beta * exp(sig * sc) &
                           + abs(sg%bb(ib, b)) * (alpha + ss * beta) * exp(sig * ss)
            end do
         end do
      end do
   end subroutine eval_blocks

   !> Drop the decayed terms that no longer matter to any functional (below prune_tol of its
   !> scale, value and first derivative) at the last evaluation, which must be at the current
   !> instant (later evaluations are not earlier). Their value and slope bounds go to the tail
   !> (the scales of the zero tests); their higher derivatives are dropped from the bounds: such
   !> a term moves a functional by less than prune_tol of its scale from here on, far below
   !> the zero tolerance, while |lambda|^k of a fast term (up to 1e11 1/s at 500 elements)
   !> would keep the curvature bounds, and with them the steps, absurdly small.
   subroutine prune_seg(sg)
      type(segment_t), intent(inout) :: sg          !! segment
      integer :: j, b, nb, k
      real(dp) :: s0(size(sg%a, 2)), s1(size(sg%a, 2)), mag
      logical :: keep
      nb = size(sg%a, 2)
      do b = 1, nb
         s0(b) = abs(sg%a0(b));  s1(b) = 0.0_dp
         do j = 1, sg%nt
            if (.not. sg%live(j)) cycle
            s0(b) = s0(b) + sg%absa(j, b) * sg%me(j)
            s1(b) = s1(b) + sg%absa(j, b) * sg%me(j) * sg%am(1, j)
         end do
      end do
      do j = 1, sg%nt - 1
         if (.not. sg%live(j) .or. .not. (real(sg%mu(j)) < 0.0_dp)) cycle
         keep = .false.
         do b = 1, nb
            if (sg%absa(j, b) * sg%me(j) > prune_tol * s0(b) .or. &
                sg%absa(j, b) * sg%me(j) * sg%am(1, j) > prune_tol * s1(b)) then
               keep = .true.;  exit
            end if
         end do
         if (keep) cycle
         sg%live(j) = .false.
         do b = 1, nb
            mag = sg%absa(j, b) * sg%me(j)
            do k = 0, 1
               sg%tail(k, b) = sg%tail(k, b) + mag * sg%am(k, j)
            end do
         end do
      end do
   end subroutine prune_seg

   !> Values and first derivatives of every functional at tau, from every term (pruned ones
   !> included: valid anywhere in the segment); does not touch the evaluation state.
   pure subroutine segment_values(sg, tau, val)
      type(segment_t), intent(in) :: sg             !! segment
      real(dp), intent(in) :: tau                   !! instant in the segment [s]
      real(dp), intent(out) :: val(0:, :)           !! (0:1, nb) values and derivatives
      integer :: j, b
      real(dp) :: er, ei, zr, zi, me, bd(0:0, size(val, 2))
      complex(dp) :: e(sg%nt)
      logical :: need(size(val, 2))
      val = 0.0_dp
      do j = 1, sg%nt
         me = exp(real(sg%mu(j)) * tau)
         if (sg%real_term(j)) then
            e(j) = cmplx(me, 0.0_dp, dp)
         else
            e(j) = cmplx(me * cos(aimag(sg%mu(j)) * tau), me * sin(aimag(sg%mu(j)) * tau), dp)
         end if
      end do
      do b = 1, size(val, 2)
         val(0, b) = sg%a0(b)
         do j = 1, sg%nt
            er = real(e(j));  ei = aimag(e(j))
            zr = real(sg%a(j, b)) * er - aimag(sg%a(j, b)) * ei
            zi = real(sg%a(j, b)) * ei + aimag(sg%a(j, b)) * er
            val(0, b) = val(0, b) + zr
            val(1, b) = val(1, b) + zr * real(sg%mp(1, j)) - zi * aimag(sg%mp(1, j))
         end do
      end do
      if (sg%nblk > 0) then
         need = .true.
         call eval_blocks(sg, tau, need, val, bd)
      end if
   end subroutine segment_values

   !> Modal state (eta, v) at tau in the segment (every term).
   subroutine segment_state(cf, sg, tau, eta, vel)
      type(config_t), intent(in) :: cf              !! configuration
      type(segment_t), intent(in) :: sg             !! segment
      real(dp), intent(in) :: tau                   !! instant [s]
      real(dp), intent(out) :: eta(:), vel(:)       !! (n) modal state
      complex(dp), allocatable :: e(:, :), out(:, :)
      complex(dp) :: ph, ec, es, iw
      integer :: rho, j, n, nr, ib
      n = cf%n;  nr = cf%nroot
      iw = cmplx(0.0_dp, sg%omega, dp)
      ph = cmplx(cos(sg%omega * tau), sin(sg%omega * tau), dp)
      eta = cf%eta_s + real(sg%yt * ph)
      vel = real(iw * sg%yt * ph)
      allocate(e(nr, 2))
      do rho = 1, nr
         e(rho, 1) = (0.0_dp, 0.0_dp)
         if (sg%coef(rho) /= (0.0_dp, 0.0_dp)) e(rho, 1) = sg%coef(rho) * exp(cf%lam(rho) * tau)
         e(rho, 2) = e(rho, 1) * cf%lam(rho)
      end do
      if (cf%r == 0) then
         do rho = 1, nr
            j = rho;  if (j > n) j = j - n
            eta(j) = eta(j) + real(e(rho, 1))
            vel(j) = vel(j) + real(e(rho, 2))
         end do
      else
         allocate(out(n, 2))
         call zgemm('N', 'N', n, 2, nr, (1.0_dp, 0.0_dp), cf%x, n, e, nr, (0.0_dp, 0.0_dp), &
                    out, n)
         eta = eta + real(out(:, 1))
         vel = vel + real(out(:, 2))
      end if
      do ib = 1, sg%nblk
         call block_fn(sg%bm(ib), sg%bd2(ib), tau, ec, es)
         eta = eta + real(sg%bm0(:, ib) * ec + sg%bm1(:, ib) * es)
         vel = vel + real((sg%bm(ib) * sg%bm0(:, ib) + sg%bm1(:, ib)) * ec &
                          + (sg%bd2(ib) * sg%bm0(:, ib) + sg%bm(ib) * sg%bm1(:, ib)) * es)
      end do
   end subroutine segment_state

   ! ------------------------------------------------------------------ statistics

   !> Closed-form integrals over [ta, tb] of f, f^2 and f |d'| for one active contact on
   !> functional b (f = k d + c d', d = s phi_b - g), the phase split at the zeros of d' in
   !> `roots`. A block enters as its two exponentials, or (delta (tb - ta) < 1e-2, where the
   !> split would cancel) as e^{m s} times its Taylor polynomial about ta (degree 5: exact to
   !> (delta (tb - ta))^6 / 6!).
   subroutine modal_window(sg, b, s, kc, cc, gap, ta, tb, roots, sf, sf2, sw)
      type(segment_t), intent(in) :: sg             !! segment
      integer, intent(in) :: b                      !! functional of the contact dof
      real(dp), intent(in) :: s, kc, cc, gap        !! sign, stiffness, damper, gap
      real(dp), intent(in) :: ta, tb                !! window in the segment [s]
      real(dp), intent(in) :: roots(:)              !! zeros of d' in the window [s]
      real(dp), intent(out) :: sf, sf2, sw          !! int f, int f^2, int f |d'|
      complex(dp), allocatable :: mu(:), pf(:), pd(:), pm(:), cf(:, :), cd(:, :)
      real(dp) :: f0, pa, pb, da, db, sgn, mid
      integer :: k
      call window_terms(sg, b, s, kc, cc, ta, tb, mu, pf, pd, pm, cf, cd)
      f0 = kc * (s * sg%a0(b) - gap)
      sf = lin_integral(mu, pf, pm, cf, f0, tb - ta)
      sf2 = prod_integral(mu, pf, pm, cf, f0, pf, cf, f0, tb - ta)
      sw = 0.0_dp
      pa = ta
      do k = 1, size(roots) + 1
         if (k <= size(roots)) then
            pb = min(max(roots(k), pa), tb)
         else
            pb = tb
         end if
         if (pb > pa) then
            mid = 0.5_dp * (pa + pb)
            sgn = sign(1.0_dp, window_value(mu, pd, pm, cd, 0.0_dp, mid - ta))
            if (cc == 0.0_dp) then
               ! f = k d: int f |d'| = +-(f_b^2 - f_a^2) / (2 k)
               da = window_value(mu, pf, pm, cf, f0, pa - ta)
               db = window_value(mu, pf, pm, cf, f0, pb - ta)
               if (kc > 0.0_dp) sw = sw + sgn * 0.5_dp * (db**2 - da**2) / kc
            else
               sw = sw + sgn * prod_window(mu, pf, pm, cf, f0, pd, cd, 0.0_dp, pa - ta, pb - ta)
            end if
         end if
         pa = pb
      end do
   end subroutine modal_window

   !> The force f = k d + c d' (minus its constant) and d' of one contact on the window, as
   !> exponential terms with coefficients at the window start (pf, pd) and polynomial-times-
   !> exponential terms e^{pm s} sum_k c_k s^k (cf, cd).
   subroutine window_terms(sg, b, s, kc, cc, ta, tb, mu, pf, pd, pm, cf, cd)
      type(segment_t), intent(in) :: sg
      integer, intent(in) :: b
      real(dp), intent(in) :: s, kc, cc, ta, tb
      complex(dp), allocatable, intent(out) :: mu(:), pf(:), pd(:), pm(:), cf(:, :), cd(:, :)
      complex(dp) :: ec, es, ca, cb, dl, u(0:deg_poly + 1), w(0:deg_poly + 1), t, x
      integer :: j, ib, nsplit, npoly, k, q
      logical, allocatable :: split(:)
      allocate(split(sg%nblk))
      do ib = 1, sg%nblk
         split(ib) = abs(sqrt(sg%bd2(ib))) * (tb - ta) >= 1.0e-2_dp
      end do
      nsplit = count(split);  npoly = sg%nblk - nsplit
      allocate(mu(sg%nt + 2 * nsplit), pf(sg%nt + 2 * nsplit), pd(sg%nt + 2 * nsplit), &
               pm(npoly), cf(0:deg_poly, npoly), cd(0:deg_poly, npoly))
      do j = 1, sg%nt
         mu(j) = sg%mu(j)
         x = sg%a(j, b) * exp(sg%mu(j) * ta)
         pf(j) = s * (kc + cc * sg%mu(j)) * x
         pd(j) = s * sg%mu(j) * x
      end do
      j = sg%nt;  q = 0
      do ib = 1, sg%nblk
         ! the block about ta: e^{m ta}[A' C(s) + B' S(s)], A' = A C(ta) + B S(ta),
         ! B' = delta^2 A S(ta) + B C(ta) (e^{m ta} in ec, es)
         call block_fn(sg%bm(ib), sg%bd2(ib), ta, ec, es)
         ca = sg%ba(ib, b) * ec + sg%bb(ib, b) * es
         cb = sg%bd2(ib) * sg%ba(ib, b) * es + sg%bb(ib, b) * ec
         if (split(ib)) then
            dl = sqrt(sg%bd2(ib))
            ! e^{m s}[A' C + B' S] = (A' + B'/delta)/2 e^{(m+delta)s} + (A' - B'/delta)/2 e^{(m-delta)s}
            do k = 1, 2
               j = j + 1
               t = merge(1.0_dp, -1.0_dp, k == 1) * dl
               mu(j) = sg%bm(ib) + t
               x = 0.5_dp * (ca + cb / t)
               pf(j) = s * (kc + cc * mu(j)) * x
               pd(j) = s * mu(j) * x
            end do
         else
            q = q + 1
            pm(q) = sg%bm(ib)
            ! u: the value polynomial A' C(s) + B' S(s); w: its derivative (mA' + B')C +
            ! (delta^2 A' + m B')S, both as Taylor polynomials in s; f = k d + c d'
            call block_poly(ca, cb, sg%bd2(ib), u)
            call block_poly(sg%bm(ib) * ca + cb, sg%bd2(ib) * ca + sg%bm(ib) * cb, &
                            sg%bd2(ib), w)
            cf(:, q) = s * (kc * u(0:deg_poly) + cc * w(0:deg_poly))
            cd(:, q) = s * w(0:deg_poly)
         end if
      end do
   end subroutine window_terms

   !> Taylor coefficients in s of A C(s) + B S(s) (C = cosh(delta s), S = sinh(delta s)/delta).
   pure subroutine block_poly(ca, cb, d2, c)
      complex(dp), intent(in) :: ca, cb, d2
      complex(dp), intent(out) :: c(0:)
      integer :: k
      c = (0.0_dp, 0.0_dp)
      do k = 0, ubound(c, 1)
         if (mod(k, 2) == 0) then
            c(k) = ca * d2**(k / 2) / fact(k)
         else
            c(k) = cb * d2**(k / 2) / fact(k)
         end if
      end do
   end subroutine block_poly

   !> Re(sum_j p_j e^{mu_j s}) + Re(sum_q e^{pm_q s} sum_k c_kq s^k) + p0 at s.
   pure real(dp) function window_value(mu, p, pm, c, p0, s) result(v)
      complex(dp), intent(in) :: mu(:), p(:), pm(:), c(0:, :)
      real(dp), intent(in) :: p0, s
      integer :: j, k
      complex(dp) :: poly
      v = p0
      do j = 1, size(mu)
         if (p(j) /= (0.0_dp, 0.0_dp)) v = v + real(p(j) * exp(mu(j) * s))
      end do
      do j = 1, size(pm)
         poly = (0.0_dp, 0.0_dp)
         do k = ubound(c, 1), 0, -1
            poly = poly * s + c(k, j)
         end do
         v = v + real(exp(pm(j) * s) * poly)
      end do
   end function window_value

   !> (e^z - 1) / z, given ez = e^z (series near 0).
   pure complex(dp) function phi1(z, ez)
      complex(dp), intent(in) :: z, ez
      complex(dp) :: term
      integer :: m
      if (real(z)**2 + aimag(z)**2 < 0.0625_dp) then
         phi1 = (1.0_dp, 0.0_dp);  term = (1.0_dp, 0.0_dp)
         do m = 2, 14
            term = term * z / real(m, dp)
            phi1 = phi1 + term
         end do
      else
         phi1 = (ez - 1.0_dp) / z
      end if
   end function phi1

   !> Integrals I_k = int_0^l s^k e^{z s} ds, k = 0..kmax: l^{k+1} J_k(z l) with
   !> J_k(x) = int_0^1 t^k e^{x t} dt, by 20-point Gauss-Legendre for |x| <= 12 (exact to
   !> round-off there: the integrand is entire and varies by at most e^12), else by the upward
   !> recurrence J_k = (e^x - k J_{k-1}) / x, stable for |x| > k.
   pure subroutine power_integrals(z, l, kmax, ik)
      complex(dp), intent(in) :: z
      real(dp), intent(in) :: l
      integer, intent(in) :: kmax
      complex(dp), intent(out) :: ik(0:kmax)
      complex(dp) :: x, ex, e
      real(dp) :: t(20), w(20)
      integer :: j, q
      x = z * l
      if (abs(x) <= 12.0_dp) then
         call gauss_legendre(t, w)
         ik = (0.0_dp, 0.0_dp)
         do q = 1, size(t)
            e = w(q) * exp(x * t(q))
            do j = 0, kmax
               ik(j) = ik(j) + e * t(q)**j
            end do
         end do
      else
         ex = exp(x)
         ik(0) = (ex - 1.0_dp) / x
         do j = 1, kmax
            ik(j) = (ex - real(j, dp) * ik(j - 1)) / x
         end do
      end if
      do j = 0, kmax
         ik(j) = ik(j) * l**(j + 1)
      end do
   end subroutine power_integrals

   !> Nodes and weights of n-point Gauss-Legendre on [0, 1].
   pure subroutine gauss_legendre(t, w)
      real(dp), intent(out) :: t(:), w(:)
      integer :: n, i, k, it
      real(dp) :: z, p0, p1, p2, dp1
      n = size(t)
      do i = 1, n
         z = cos(acos(-1.0_dp) * (real(i, dp) - 0.25_dp) / (real(n, dp) + 0.5_dp))
         do it = 1, 100
            p0 = 1.0_dp;  p1 = z
            do k = 2, n
               p2 = (real(2 * k - 1, dp) * z * p1 - real(k - 1, dp) * p0) / real(k, dp)
               p0 = p1;  p1 = p2
            end do
            dp1 = real(n, dp) * (z * p1 - p0) / (z**2 - 1.0_dp)
            z = z - p1 / dp1
            if (abs(p1 / dp1) < 1.0e-16_dp) exit
         end do
         t(i) = 0.5_dp * (1.0_dp - z)
         w(i) = 1.0_dp / ((1.0_dp - z**2) * dp1**2)
      end do
   end subroutine gauss_legendre

   !> Integral over [0, l] of Re(sum_j p_j e^{mu_j s}) + Re(sum_q e^{pm_q s} sum_k c_kq s^k) + p0.
   pure real(dp) function lin_integral(mu, p, pm, c, p0, l) result(s)
      complex(dp), intent(in) :: mu(:), p(:), pm(:), c(0:, :)
      real(dp), intent(in) :: p0, l
      complex(dp) :: ik(0:ubound(c, 1))
      integer :: j
      s = p0 * l
      do j = 1, size(mu)
         if (p(j) == (0.0_dp, 0.0_dp)) cycle
         s = s + real(p(j) * l * phi1(mu(j) * l, exp(mu(j) * l)))
      end do
      do j = 1, size(pm)
         call power_integrals(pm(j), l, ubound(c, 1), ik)
         s = s + real(sum(c(:, j) * ik))
      end do
   end function lin_integral

   !> Integral over [0, l] of the product of two window functions sharing their exponents
   !> (p, c with constant p0 and q, d with constant q0).
   pure real(dp) function prod_integral(mu, p, pm, c, p0, q, d, q0, l) result(s)
      complex(dp), intent(in) :: mu(:), p(:), pm(:), c(0:, :), q(:), d(0:, :)
      real(dp), intent(in) :: p0, q0, l
      s = prod_window(mu, p, pm, c, p0, q, d, q0, 0.0_dp, l)
   end function prod_integral

   !> Integral over [sa, sb] (offsets from the window start) of the product of two window
   !> functions: Re(a) Re(b) = (Re(a b) + Re(a conj(b))) / 2, every pair in closed form.
   pure real(dp) function prod_window(mu, p, pm, c, p0, q, d, q0, sa, sb) result(s)
      complex(dp), intent(in) :: mu(:), p(:), pm(:), c(0:, :), q(:), d(0:, :)
      real(dp), intent(in) :: p0, q0, sa, sb
      complex(dp) :: ea(size(mu)), el(size(mu)), pa(size(mu)), qa(size(mu)), ph(size(mu))
      complex(dp) :: cs(0:ubound(c, 1), size(pm)), ds(0:ubound(c, 1), size(pm))
      complex(dp) :: ik(0:2 * ubound(c, 1) + 1), acc
      real(dp) :: l, sp, sq, cut, mp(size(mu)), mq(size(mu)), w
      integer :: j, k, n, i, m, kd
      logical :: same
      same = all(p == q) .and. p0 == q0 .and. all(c == d)
      n = size(mu);  kd = ubound(c, 1)
      l = sb - sa
      do j = 1, n
         ea(j) = exp(mu(j) * sa)
         el(j) = exp(mu(j) * l)
         pa(j) = p(j) * ea(j)
         qa(j) = q(j) * ea(j)
         ph(j) = l * phi1(mu(j) * l, el(j))
      end do
      ! polynomial terms re-expanded about sa
      do j = 1, size(pm)
         call shift_poly(c(:, j), pm(j), sa, cs(:, j))
         call shift_poly(d(:, j), pm(j), sa, ds(:, j))
      end do
      do j = 1, n
         mp(j) = abs(real(pa(j))) + abs(aimag(pa(j)))
         mq(j) = abs(real(qa(j))) + abs(aimag(qa(j)))
      end do
      sp = sum(mp) + abs(p0) + sum(abs(cs));  sq = sum(mq) + abs(q0) + sum(abs(ds))
      cut = 1.0e-18_dp * sp * sq
      s = p0 * q0 * l
      do j = 1, n
         s = s + p0 * real(qa(j) * ph(j)) + q0 * real(pa(j) * ph(j))
      end do
      do j = 1, size(pm)
         call power_integrals(pm(j), l, kd, ik(0:kd))
         s = s + p0 * real(sum(ds(:, j) * ik(0:kd))) + q0 * real(sum(cs(:, j) * ik(0:kd)))
      end do
      do j = 1, n
         if (mp(j) * sq <= cut .and. mq(j) * sp <= cut) cycle
         ! a square (p = q) is symmetric in j, k: the pair counted once, twice
         do k = merge(j, 1, same), n
            if (mp(j) * mq(k) <= cut) cycle
            w = 0.5_dp
            if (same .and. k > j) w = 1.0_dp
            s = s + w * real(pa(j) * qa(k) * l * phi1((mu(j) + mu(k)) * l, el(j) * el(k)) &
                + pa(j) * conjg(qa(k)) * l * phi1((mu(j) + conjg(mu(k))) * l, &
                el(j) * conjg(el(k))))
         end do
      end do
      ! pairs with a polynomial term: exponential x polynomial, polynomial x polynomial
      do i = 1, size(pm)
         do j = 1, n
            call power_integrals(mu(j) + pm(i), l, kd, ik(0:kd))
            acc = pa(j) * sum(ds(:, i) * ik(0:kd)) + qa(j) * sum(cs(:, i) * ik(0:kd))
            s = s + 0.5_dp * real(acc)
            call power_integrals(conjg(mu(j)) + pm(i), l, kd, ik(0:kd))
            acc = conjg(pa(j)) * sum(ds(:, i) * ik(0:kd)) + conjg(qa(j)) * sum(cs(:, i) * ik(0:kd))
            s = s + 0.5_dp * real(acc)
         end do
         do m = 1, size(pm)
            call power_integrals(pm(i) + pm(m), l, 2 * kd, ik)
            acc = (0.0_dp, 0.0_dp)
            do j = 0, kd
               acc = acc + cs(j, i) * sum(ds(:, m) * ik(j:j + kd))
            end do
            s = s + 0.5_dp * real(acc)
            call power_integrals(pm(i) + conjg(pm(m)), l, 2 * kd, ik)
            acc = (0.0_dp, 0.0_dp)
            do j = 0, kd
               acc = acc + cs(j, i) * sum(conjg(ds(:, m)) * ik(j:j + kd))
            end do
            s = s + 0.5_dp * real(acc)
         end do
      end do
   end function prod_window

   !> Coefficients of e^{z (s0 + s)} sum_k c_k (s0 + s)^k as e^{z s} sum_k cs_k s^k.
   pure subroutine shift_poly(c, z, s0, cs)
      complex(dp), intent(in) :: c(0:), z
      real(dp), intent(in) :: s0
      complex(dp), intent(out) :: cs(0:)
      integer :: k, i
      real(dp) :: binom
      cs = (0.0_dp, 0.0_dp)
      do k = 0, ubound(c, 1)
         binom = 1.0_dp
         do i = 0, k
            ! (s0 + s)^k = sum_i binom(k, i) s0^(k-i) s^i
            cs(i) = cs(i) + c(k) * binom * s0**(k - i)
            binom = binom * real(k - i, dp) / real(i + 1, dp)
         end do
      end do
      cs = cs * exp(z * s0)
   end subroutine shift_poly

   ! ------------------------------------------------------------------ safe steps

   !> Sign of a function just after an instant from its value and derivatives (0 if all are
   !> zero to round-off of their scales).
   pure integer function sign_after(v, scl)
      real(dp), intent(in) :: v(0:), scl(0:)        !! derivatives 0.., their scales
      integer :: k
      sign_after = 0
      do k = 0, ubound(v, 1)
         if (abs(v(k)) > zero_tol * scl(k)) then
            sign_after = int(sign(1.0_dp, v(k)))
            return
         end if
      end do
   end function sign_after

   !> Dead band of a function starting within round-off of zero on the wrong side.
   pure real(dp) function band(y, scl)
      real(dp), intent(in) :: y, scl                !! value, scale
      band = 0.0_dp
      if (y <= 0.0_dp) band = 2.0_dp * abs(y) + zero_tol * scl
   end function band

   !> Record a function to keep >= 0 for the step choice: value y0, derivatives y1, y2,
   !> |y''| <= b2, |y'''| <= b3, and a step hm known safe otherwise (monotone step of a
   !> running extremum); q gets its quadratic step.
   pure subroutine add_fn(nf, q, fy, fy1, fy2, fb2, fb3, y0, y1, y2, b2, b3, hm)
      integer, intent(inout) :: nf                  !! functions so far
      real(dp), intent(inout) :: q(:), fy(:), fy1(:), fy2(:), fb2(:), fb3(:)   !! the list
      real(dp), intent(in) :: y0, y1, y2, b2, b3, hm   !! value, derivatives, bounds, step
      nf = nf + 1
      fy(nf) = y0;  fy1(nf) = y1;  fy2(nf) = y2;  fb2(nf) = b2;  fb3(nf) = b3
      q(nf) = hm
      if (y0 > 0.0_dp) then
         q(nf) = max(hm, quad_root(y0, y1, b2))
      else if (y0 == 0.0_dp .and. y1 == 0.0_dp .and. y2 == 0.0_dp .and. b2 == 0.0_dp .and. &
               b3 == 0.0_dp) then
         q(nf) = huge(1.0_dp)     ! identically zero on the segment: it cannot change sign
      end if
   end subroutine add_fn

   !> Step on which phi' (value p1, derivative p2, |phi'''| <= b3) keeps its sign.
   pure real(dp) function mono_quad(p1, p2, b3)
      real(dp), intent(in) :: p1, p2, b3            !! phi', phi'', bound of phi'''
      mono_quad = 0.0_dp
      if (p1 /= 0.0_dp) mono_quad = quad_root(abs(p1), sign(1.0_dp, p1) * p2, b3)
   end function mono_quad

   !> First positive zero of y + y1 s - b s^2 / 2 (y > 0).
   pure real(dp) function quad_root(y, y1, b) result(h)
      real(dp), intent(in) :: y, y1, b
      real(dp) :: disc
      if (b <= 0.0_dp) then
         if (y1 >= 0.0_dp) then
            h = huge(1.0_dp)
         else
            h = y / (-y1)
         end if
         return
      end if
      disc = sqrt(y1**2 + 2.0_dp * b * y)
      if (y1 >= 0.0_dp) then
         h = (y1 + disc) / b
      else
         h = 2.0_dp * y / (disc - y1)
      end if
   end function quad_root

   !> A point at or below the first positive zero of P(s) = y + a s + b s^2 - c s^3 (y, c > 0),
   !> within 1e-3 relative.
   pure real(dp) function cubic_root(y, a, b, c, cap) result(h)
      real(dp), intent(in) :: y, a, b, c            !! coefficients
      real(dp), intent(in) :: cap                   !! stop once the answer exceeds this
      real(dp) :: lo, hi, disc, s1, s2, mid, plo, phi, pm
      integer :: it, side
      ! P decreases on [lo, hi] from P(lo) > 0 to P(hi) <= 0
      lo = 0.0_dp;  hi = -1.0_dp
      disc = b**2 + 3.0_dp * a * c
      if (disc > 0.0_dp) then
         s1 = (b - sqrt(disc)) / (3.0_dp * c)      ! local minimum
         s2 = (b + sqrt(disc)) / (3.0_dp * c)      ! local maximum
         if (s1 > 0.0_dp .and. cubic_value(y, a, b, c, s1) <= 0.0_dp) then
            hi = s1
         else if (s2 > 0.0_dp) then
            lo = s2
         end if
      end if
      if (hi < 0.0_dp) then
         ! P decreases beyond lo: a zero past the cap does not matter
         if (lo >= cap) then
            h = lo;  return
         end if
         if (cubic_value(y, a, b, c, cap) > 0.0_dp) then
            h = cap;  return
         end if
         hi = cap
      end if
      ! P > 0 at lo, P <= 0 at hi, a single zero in between: Illinois, keeping lo safe
      plo = cubic_value(y, a, b, c, lo);  phi = cubic_value(y, a, b, c, hi);  side = 0
      do it = 1, 60
         if (hi - lo <= 1.0e-3_dp * lo .or. lo >= cap) exit
         mid = lo + (hi - lo) * plo / (plo - phi)
         if (.not. (mid > lo .and. mid < hi)) mid = 0.5_dp * (lo + hi)
         pm = cubic_value(y, a, b, c, mid)
         if (pm > 0.0_dp) then
            lo = mid;  plo = pm
            if (side == -1) phi = 0.5_dp * phi
            side = -1
         else
            hi = mid;  phi = pm
            if (side == 1) plo = 0.5_dp * plo
            side = 1
         end if
      end do
      h = lo
   end function cubic_root

   !> P(s) = y + a s + b s^2 - c s^3.
   pure real(dp) function cubic_value(y, a, b, c, s) result(p)
      real(dp), intent(in) :: y, a, b, c, s
      p = y + s * (a + s * (b - c * s))
   end function cubic_value
end module gapbeam_exact_segment
