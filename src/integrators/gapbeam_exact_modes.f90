!> The open structure of the exact event-driven integrator (gapbeam_exact) in mass-normalised
!> modal coordinates: u_r = Phi eta, Phi' M_r Phi = I, Phi' K_r Phi = diag(omega_j^2),
!> Phi' C_r Phi = diag(d_j), d_j = beta + gamma omega_j^2. With Rayleigh damping every mode is
!> an exact single-dof oscillator for any damping ratio; the contact configurations
!> (gapbeam_exact_config) are rank-r updates of this diagonal structure.
!>
!> **Modal damping** (C = beta M + gamma K + C_m, C_m = M Phi_m diag(2 zeta omega) Phi_m' M from the
!> model builder's modes Phi_m) is diagonal in the modes too: d_j gains phi_j' C_m phi_j (a
!> Rayleigh quotient, exact to second order in the difference between the builder's shapes and
!> the refined ones here). The off-diagonal rest, of the order of that difference times the
!> spread of the d_j, is dropped; it is checked to be below 1e-3 of the largest d_j (measured:
!> 1.3e-6 at 512 consistent elements, from the highest modes, which the builder's eigen-solution
!> resolves to about eps omega_max^2/omega_1^2 there), a guard against a damping that is not
!> classical at all. C_m has zero rows on massless dofs, so the
!> condensation below holds as it stands.
!>
!> **Massless dofs** (lumped mass without rotary inertia: zero rows of M) are condensed
!> statically, u_s = T u_r with T = -K_ss^-1 K_sr. This is exact: with C = beta M + gamma K
!> their rows read gamma z' + z = 0 for z = K_ss u_s + K_sr u_r, and the initial state is put
!> in equilibrium (z = 0). T is never formed: every product with it is a banded solve with
!> K_ss (band Cholesky), and where the result feeds the modal data (K_r x = K_rr x + K_rs T x)
!> the solve gets one step of iterative refinement with an extended-precision residual and
!> the product is accumulated in extended precision.
!>
!> **Modes.** dsyevd on D^-1/2 K_r D^-1/2 for a lumped M_r = D (Phi = D^-1/2 V), or on
!> U^-T K_r U^-1 for a consistent one (M_r = U'U: dpotrf, dsygst, dtrtrs). The symmetric
!> eigensolver's backward error eps ||M^-1 K|| shifts the low frequencies and rotates the low
!> shapes (at 60 elements omega_1^2 by 6e-9, phi_1 by 5e-10: 2e-8 of run error), so the modal
!> data are refined to the accuracy of the float64 model with residuals in extended precision
!> (`xp`; docs/exact_integrator.md):
!>
!> 1. every frequency becomes the Rayleigh quotient phi'K phi / phi'M phi (float64 quotients
!>    cancel like n^4);
!> 2. the n_refine lowest modes get one step of inverse iteration with the shift
!>    omega^2 (1 - 1e-7) on the banded pencil K - sigma M of the full model (massless rows
!>    included: that is the condensation), refined three times;
!> 3. every pair (i, j) with i or j among those low modes gets one Jacobi-type correction,
!>    c_ij = -(phi_i'K phi_j - lambda_j phi_i'M phi_j) / (lambda_i - lambda_j),
!>    phi_j <- phi_j + sum_i c_ij phi_i (correcting only within the low set leaves the others
!>    with the low modes' old errors: 1e-8 of run error at 120 elements), then Rayleigh
!>    quotients again.
!>
!> **Poles** of q_j(lambda) = lambda^2 + d_j lambda + omega_j^2: with D = d_j/2 and
!> disc = (D - omega_j)(D + omega_j), underdamped p = -D +- i sqrt(-disc), otherwise
!> p_fast = -(D + sqrt(disc)) and p_slow = omega_j^2 / p_fast; neither form cancels. p1 is the
!> upper (or slow) pole, p2 the lower (or fast) one.
!>
!> **Functionals** watched by the event search (one per contact dof, the root strain, the tip
!> displacement) and the load are kept as modal rows.
module gapbeam_exact_modes
   use gapbeam_linalg, only: dense_to_band, bandwidth
   use gapbeam_kinds, only: dp, xp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t, has_modal_damping
   use gapbeam_lapack, only: dpotrf, dsygst, dsyevd, dtrtrs, dpbtrf, dpbtrs, dgbtrf, dgbtrs
   implicit none
   private
   public :: open_modes_t, build_open_modes, to_modal, to_physical, condense

   integer, parameter :: n_refine = 24            ! low modes refined by inverse iteration
   real(dp), parameter :: shift_rel = 1.0e-7_dp   ! inverse-iteration shift below omega^2

   !> The open structure in modal coordinates.
   type :: open_modes_t
      integer :: n = 0                          !! dofs of the model
      integer :: nr = 0                         !! dofs with mass = modes
      integer :: ns = 0                         !! massless dofs
      integer, allocatable :: ir(:), is(:)      !! global indices of the two groups
      integer :: kd = 0                         !! semi-bandwidth of K and M
      real(dp), allocatable :: k_band(:, :)     !! (kd+1, n) upper band of K
      real(dp), allocatable :: m_band(:, :)     !! (kd+1, n) upper band of M
      integer :: kds = 0                        !! semi-bandwidth of K_ss
      real(dp), allocatable :: kss_fac(:, :)    !! (kds+1, ns) band Cholesky factor of K_ss
      real(dp), allocatable :: phi(:, :)        !! (nr, nr) modes, M_r-orthonormal
      real(dp), allocatable :: w2(:)            !! omega_j^2 [1/s^2]
      real(dp), allocatable :: d(:)             !! d_j = beta + gamma omega_j^2 [1/s]
      complex(dp), allocatable :: p1(:), p2(:)  !! poles: upper or slow, lower or fast [1/s]
      real(dp) :: beta = 0.0_dp                 !! Rayleigh mass coefficient [1/s]
      real(dp) :: gamma = 0.0_dp                !! Rayleigh stiffness coefficient [s]
      real(dp), allocatable :: pload(:)         !! modal load amplitude (A_pp/2) W^2 Phi' q_r
      integer :: nb = 0                         !! watched functionals: slots, strain, tip
      integer :: n_slots = 0                    !! distinct contact dofs
      integer :: b_strain = 0, b_tip = 0        !! functional index of root strain, tip
      real(dp), allocatable :: ell(:, :)        !! (nr, nb) modal rows of the functionals
      integer, allocatable :: cslot(:)          !! functional of each contact (its slot)
   end type open_modes_t

contains

   !> Condensation, refined modes, poles, modal load and functionals of the open structure.
   subroutine build_open_modes(model, om, err)
      type(model_t), intent(in) :: model                 !! model (Rayleigh damping)
      type(open_modes_t), intent(out) :: om              !! open structure
      type(error_t), allocatable, intent(out) :: err     !! massless coupling, LAPACK failure
      integer :: i, c, b, n
      real(dp), allocatable :: l(:, :), lr(:, :)
      n = model%n
      om%n = n
      om%beta = model%beta;  om%gamma = model%gamma
      call split_dofs(model, om, err);  if (allocated(err)) return
      call eigen_modes(model, om, err);  if (allocated(err)) return
      call refine_modes(om, err);  if (allocated(err)) return
      if (any(.not. (om%w2 > 0.0_dp))) then
         call fatal_error(err, 'gapbeam_exact: the stiffness of the dofs with mass is not ' &
            // 'positive definite (omega^2 = ' // str(minval(om%w2)) // ' 1/s^2)')
         return
      end if
      om%d = om%beta + om%gamma * om%w2
      if (has_modal_damping(model)) then
         call add_modal_damping(model, om, err);  if (allocated(err)) return
      end if
      allocate(om%p1(om%nr), om%p2(om%nr))
      do i = 1, om%nr
         call sdof_poles(om%d(i), om%w2(i), om%p1(i), om%p2(i))
      end do
      ! functionals and load: full rows -> reduced (T' l_s) -> modal (Phi' l_r)
      om%n_slots = model%n_slots
      om%nb = model%n_slots + 2
      om%b_strain = model%n_slots + 1
      om%b_tip = model%n_slots + 2
      allocate(l(n, om%nb + 1), source=0.0_dp)
      do b = 1, model%n_slots
         l(model%slot_dof(b), b) = 1.0_dp
      end do
      l(:, om%b_strain) = model%sys%strain_row
      if (model%sys%tip_dof > 0) l(model%sys%tip_dof, om%b_tip) = 1.0_dp
      l(:, om%nb + 1) = model%half_amplitude * model%omega**2 * model%q
      call reduce_rows(om, l, lr)
      om%ell = matmul(transpose(om%phi), lr(:, 1:om%nb))
      om%pload = matmul(transpose(om%phi), lr(:, om%nb + 1))
      allocate(om%cslot(model%n_contacts))
      do c = 1, model%n_contacts
         if (model%sys%m(model%c_dof(c), model%c_dof(c)) == 0.0_dp) then
            call fatal_error(err, 'gapbeam_exact: stop ' // str(model%c_stop(c)) &
               // ' acts on a massless dof (global dof ' // str(model%c_dof(c)) // '); the ' &
               // 'exact integrator condenses massless dofs and needs contacts on dofs with mass')
            return
         end if
         om%cslot(c) = model%c_slot(c)
      end do
   end subroutine build_open_modes

   !> Dofs with and without mass, the band forms of K and M, the band factor of K_ss.
   subroutine split_dofs(model, om, err)
      type(model_t), intent(in) :: model
      type(open_modes_t), intent(inout) :: om
      type(error_t), allocatable, intent(inout) :: err
      integer :: i, j, n, info
      real(dp), allocatable :: kss(:, :)
      real(dp) :: cm
      n = model%n
      om%ir = pack([(i, i = 1, n)], [(model%sys%m(i, i) /= 0.0_dp, i = 1, n)])
      om%is = pack([(i, i = 1, n)], [(model%sys%m(i, i) == 0.0_dp, i = 1, n)])
      om%nr = size(om%ir);  om%ns = size(om%is)
      if (om%nr == 0) then
         call fatal_error(err, 'gapbeam_exact: the model has no mass');  return
      end if
      if (om%ns > 0) then
         if (maxval(abs(model%sys%m(om%is, :))) > 0.0_dp) then
            call fatal_error(err, 'gapbeam_exact: a dof with zero diagonal mass is coupled by ' &
               // 'the mass matrix; cannot condense it')
            return
         end if
      end if
      om%kd = max(bandwidth(model%sys%k), bandwidth(model%sys%m))
      call dense_to_band(model%sys%k, om%kd, om%k_band)
      call dense_to_band(model%sys%m, om%kd, om%m_band)
      if (om%ns > 0) then
         kss = model%sys%k(om%is, om%is)
         om%kds = bandwidth(kss)
         call dense_to_band(kss, om%kds, om%kss_fac)
         call dpbtrf('U', om%ns, om%kds, om%kss_fac, om%kds + 1, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_exact: the stiffness of the massless dofs is ' &
               // 'singular (dpbtrf info=' // str(info) // ')')
            return
         end if
      end if
      ! the damping must be Rayleigh (+ modal): the modal form and the condensation rest on it
      do j = 1, n
         do i = 1, n
            cm = 0.0_dp
            if (has_modal_damping(model)) cm = model%c_modal(i, j)
            if (abs(model%c(i, j) - model%beta * model%sys%m(i, j) - model%gamma &
                    * model%sys%k(i, j) - cm) > 1.0e-12_dp * (abs(model%beta &
                    * model%sys%m(i, j)) + abs(model%gamma * model%sys%k(i, j)) + abs(cm)) &
                    + tiny(1.0_dp)) then
               call fatal_error(err, 'gapbeam_exact: the damping matrix is not beta M + gamma ' &
                  // 'K + C_modal (entry ' // str(i) // ', ' // str(j) // ')')
               return
            end if
         end do
      end do
   end subroutine split_dofs

   !> The modal damping's part of d_j, phi_j' C_m phi_j (the module header).
   subroutine add_modal_damping(model, om, err)
      type(model_t), intent(in) :: model
      type(open_modes_t), intent(inout) :: om
      type(error_t), allocatable, intent(inout) :: err
      real(dp), allocatable :: cm(:, :)
      real(dp) :: off
      integer :: j
      cm = matmul(transpose(om%phi), matmul(model%c_modal(om%ir, om%ir), om%phi))
      off = 0.0_dp
      do j = 1, om%nr
         om%d(j) = om%d(j) + cm(j, j)
         off = max(off, maxval(abs(cm(:j - 1, j))))
      end do
      if (off > 1.0e-3_dp * maxval(abs(om%d))) then
         call fatal_error(err, 'gapbeam_exact: the modal damping is not diagonal in the ' &
            // 'modes (off-diagonal ' // str(off) // ' against ' // str(maxval(abs(om%d))) &
            // ' 1/s)')
      end if
   end subroutine add_modal_damping

   !> Modes of the condensed structure: K_r phi = omega^2 M_r phi (dsyevd).
   subroutine eigen_modes(model, om, err)
      type(model_t), intent(in) :: model
      type(open_modes_t), intent(inout) :: om
      type(error_t), allocatable, intent(inout) :: err
      real(dp), allocatable :: a(:, :), mr(:, :), s(:), work(:), z(:, :), e(:, :)
      integer, allocatable :: iwork(:)
      integer :: nr, i, info, lwork, liwork, iq(1)
      real(dp) :: q(1)
      logical :: diagonal
      nr = om%nr
      ! K_r = K_rr + K_rs T, column by column from unit vectors (banded, refined)
      if (om%ns == 0) then
         a = model%sys%k
      else
         allocate(e(nr, nr), source=0.0_dp)
         do i = 1, nr
            e(i, i) = 1.0_dp
         end do
         call apply_k_dp(om, e, a)
         a = 0.5_dp * (a + transpose(a))
      end if
      mr = model%sys%m(om%ir, om%ir)
      diagonal = .true.
      do i = 1, nr
         if (any(mr(:i - 1, i) /= 0.0_dp) .or. any(mr(i + 1:, i) /= 0.0_dp)) diagonal = .false.
      end do
      if (diagonal) then
         s = [(1.0_dp / sqrt(mr(i, i)), i = 1, nr)]
         do i = 1, nr
            a(:, i) = a(:, i) * s * s(i)
         end do
      else
         call dpotrf('U', nr, mr, nr, info)
         if (info == 0) call dsygst(1, 'U', nr, a, nr, mr, nr, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_exact: the mass matrix of the dofs with mass is not ' &
               // 'positive definite (info=' // str(info) // ')')
            return
         end if
      end if
      ! divide and conquer (dsyevr's MRRR relies on IEEE infinities: it trips -ffpe-trap)
      allocate(om%w2(nr))
      call dsyevd('V', 'U', nr, a, nr, om%w2, q, -1, iq, -1, info)
      lwork = max(1, int(q(1)));  liwork = max(1, iq(1))
      allocate(work(lwork), iwork(liwork))
      call dsyevd('V', 'U', nr, a, nr, om%w2, work, lwork, iwork, liwork, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_exact: the symmetric eigensolver failed (dsyevd ' &
            // 'info=' // str(info) // ')')
         return
      end if
      call move_alloc(a, z)
      if (diagonal) then
         do i = 1, nr
            z(:, i) = z(:, i) * s
         end do
      else
         call dtrtrs('U', 'N', 'N', nr, nr, mr, nr, z, nr, info)
      end if
      call move_alloc(z, om%phi)
   end subroutine eigen_modes

   !> Refine the modal data with extended-precision residuals (see the module header).
   subroutine refine_modes(om, err)
      type(open_modes_t), intent(inout) :: om
      type(error_t), allocatable, intent(inout) :: err
      real(xp), allocatable :: w(:, :), kw(:, :), mw(:, :), lam(:), kl(:, :), ml(:, :), &
         cl(:, :), ch(:, :), wn(:, :), mn(:), kn(:)
      real(dp), allocatable :: v(:, :), phi(:, :), w2r(:)
      integer :: nr, m, i, j
      nr = om%nr
      m = min(nr, n_refine)
      ! 1. Rayleigh quotients and M-normalisation of every mode
      phi = om%phi
      allocate(w2r(nr))
      call rayleigh(om, phi, w2r)
      om%w2 = w2r
      ! 2. inverse iteration for the m lowest
      call inverse_iteration(om, m, phi, v, err)
      if (allocated(err)) return
      ! 3. one Jacobi-type correction of every pair with a low mode: c_ij for j low (any i),
      !    in cl(:, j), and for i low, j not, in ch(i, :)
      allocate(w(nr, nr))
      w = real(phi, xp)
      w(:, 1:m) = real(v, xp)
      call apply_k_xp(om, real(w, dp), kw)
      call apply_m_xp(om, real(w, dp), mw)
      allocate(lam(nr))
      do j = 1, nr
         lam(j) = sum(w(:, j) * kw(:, j)) / sum(w(:, j) * mw(:, j))
      end do
      kl = matmul(transpose(w(:, 1:m)), kw)          ! (m, nr): rows are the low modes
      ml = matmul(transpose(w(:, 1:m)), mw)
      deallocate(kw, mw)
      allocate(cl(nr, m), ch(m, nr - m), source=0.0_xp)
      do j = 1, m
         do i = 1, nr
            if (i == j) cycle
            if (separated(lam(i), lam(j))) cl(i, j) = -(kl(j, i) - lam(j) * ml(j, i)) &
                                                      / (lam(i) - lam(j))
         end do
      end do
      do j = m + 1, nr
         do i = 1, m
            if (separated(lam(i), lam(j))) ch(i, j - m) = -(kl(i, j) - lam(j) * ml(i, j)) &
                                                          / (lam(i) - lam(j))
         end do
      end do
      wn = w
      wn(:, 1:m) = wn(:, 1:m) + matmul(w, cl)
      if (m < nr) wn(:, m + 1:) = wn(:, m + 1:) + matmul(w(:, 1:m), ch)
      deallocate(w, cl, ch)
      ! Rayleigh quotients again, in extended precision
      call apply_k_xp(om, real(wn, dp), kw)
      call apply_m_xp(om, real(wn, dp), mw)
      allocate(mn(nr), kn(nr))
      do j = 1, nr
         mn(j) = sum(wn(:, j) * mw(:, j))
         kn(j) = sum(wn(:, j) * kw(:, j))
         om%phi(:, j) = real(wn(:, j) / sqrt(mn(j)), dp)
      end do
      om%w2 = real(kn / mn, dp)
   end subroutine refine_modes

   !> Two eigenvalues distinct enough for the Jacobi correction.
   pure logical function separated(a, b)
      real(xp), intent(in) :: a, b
      separated = abs(a - b) > 1.0e-12_xp * max(abs(a), abs(b))
   end function separated

   !> Rayleigh quotients in extended precision; phi M-normalised.
   subroutine rayleigh(om, phi, w2)
      type(open_modes_t), intent(in) :: om
      real(dp), intent(inout) :: phi(:, :)
      real(dp), intent(out) :: w2(:)
      real(xp), allocatable :: kp(:, :), mp(:, :)
      real(xp) :: mn, kn
      integer :: j
      call apply_k_xp(om, phi, kp)
      call apply_m_xp(om, phi, mp)
      do j = 1, size(phi, 2)
         mn = sum(real(phi(:, j), xp) * mp(:, j))
         kn = sum(real(phi(:, j), xp) * kp(:, j))
         w2(j) = real(kn / mn, dp)
         phi(:, j) = real(real(phi(:, j), xp) / sqrt(mn), dp)
      end do
   end subroutine rayleigh

   !> One step of inverse iteration with the shift omega^2 (1 - shift_rel) for each of the m
   !> lowest modes, on the banded pencil K - sigma M of the full model, the solve refined
   !> three times with extended-precision residuals; v gets the M-normalised reduced parts.
   subroutine inverse_iteration(om, m, phi, v, err)
      type(open_modes_t), intent(in) :: om
      integer, intent(in) :: m
      real(dp), intent(in) :: phi(:, :)               !! current modes
      real(dp), allocatable, intent(out) :: v(:, :)
      type(error_t), allocatable, intent(inout) :: err
      real(dp), allocatable :: ab(:, :), y(:, :), r(:, :), f(:, :)
      real(xp), allocatable :: bx(:, :), ky(:, :), my(:, :), vx(:), mv(:, :)
      integer, allocatable :: ipiv(:)
      integer :: n, kd, j, i, k, it, info, ldab
      real(dp) :: sigma
      n = om%n;  kd = om%kd;  ldab = 3 * kd + 1
      allocate(v(om%nr, m), ab(ldab, n), ipiv(n), y(n, 1), r(n, 1), f(n, 1))
      do j = 1, m
         sigma = om%w2(j) * (1.0_dp - shift_rel)    ! w2 holds the Rayleigh quotients
         ! general band storage of K - sigma M: ab(2kd+1+i-k, k) = A(i, k)
         ab = 0.0_dp
         do k = 1, n
            do i = max(1, k - kd), k
               ab(2 * kd + 1 + i - k, k) = om%k_band(kd + 1 + i - k, k) &
                                           - sigma * om%m_band(kd + 1 + i - k, k)
               ab(2 * kd + 1 + k - i, i) = ab(2 * kd + 1 + i - k, k)
            end do
         end do
         call dgbtrf(n, n, kd, kd, ab, ldab, ipiv, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_exact: inverse iteration for mode ' // str(j) &
               // ': K - sigma M is singular (dgbtrf info=' // str(info) // ')')
            return
         end if
         f = 0.0_dp
         f(om%ir, 1) = phi(:, j)
         call band_mul_xp(kd, om%m_band, f, bx)          ! b = M phi
         y(:, 1) = real(bx(:, 1), dp)
         call dgbtrs('N', n, kd, kd, 1, ab, ldab, ipiv, y, n, info)
         do it = 1, 3
            call band_mul_xp(kd, om%k_band, y, ky)
            call band_mul_xp(kd, om%m_band, y, my)
            r(:, 1) = real(bx(:, 1) - (ky(:, 1) - real(sigma, xp) * my(:, 1)), dp)
            call dgbtrs('N', n, kd, kd, 1, ab, ldab, ipiv, r, n, info)
            y = y + r
         end do
         f = 0.0_dp
         f(om%ir, 1) = y(om%ir, 1)
         call band_mul_xp(kd, om%m_band, f, mv)
         vx = real(y(om%ir, 1), xp)
         v(:, j) = real(vx / sqrt(sum(vx * mv(om%ir, 1))), dp)
      end do
   end subroutine inverse_iteration

   !> y = K_r x in extended precision (x on the dofs with mass, several columns).
   subroutine apply_k_xp(om, x, y)
      type(open_modes_t), intent(in) :: om
      real(dp), intent(in) :: x(:, :)                 !! (nr, m)
      real(xp), allocatable, intent(out) :: y(:, :)   !! (nr, m)
      real(dp), allocatable :: f(:, :)
      real(xp), allocatable :: h(:, :)
      call full_vectors(om, x, f)
      call band_mul_xp(om%kd, om%k_band, f, h)
      y = h(om%ir, :)
   end subroutine apply_k_xp

   !> y = K_r x in double precision (rounded from the extended-precision product).
   subroutine apply_k_dp(om, x, y)
      type(open_modes_t), intent(in) :: om
      real(dp), intent(in) :: x(:, :)
      real(dp), allocatable, intent(out) :: y(:, :)
      real(xp), allocatable :: yx(:, :)
      call apply_k_xp(om, x, yx)
      y = real(yx, dp)
   end subroutine apply_k_dp

   !> y = M_r x in extended precision (M_rs = 0 where there are massless dofs).
   subroutine apply_m_xp(om, x, y)
      type(open_modes_t), intent(in) :: om
      real(dp), intent(in) :: x(:, :)
      real(xp), allocatable, intent(out) :: y(:, :)
      real(dp), allocatable :: f(:, :)
      real(xp), allocatable :: h(:, :)
      allocate(f(om%n, size(x, 2)), source=0.0_dp)
      f(om%ir, :) = x
      call band_mul_xp(om%kd, om%m_band, f, h)
      y = h(om%ir, :)
   end subroutine apply_m_xp

   !> Full vectors of reduced ones: f_r = x, f_s = T x, the solve refined once with an
   !> extended-precision residual.
   subroutine full_vectors(om, x, f)
      type(open_modes_t), intent(in) :: om
      real(dp), intent(in) :: x(:, :)
      real(dp), allocatable, intent(out) :: f(:, :)
      real(xp), allocatable :: h(:, :)
      real(dp), allocatable :: z(:, :)
      integer :: info, m
      m = size(x, 2)
      allocate(f(om%n, m), source=0.0_dp)
      f(om%ir, :) = x
      if (om%ns == 0) return
      call band_mul_xp(om%kd, om%k_band, f, h)      ! h_s = K_sr x
      z = -real(h(om%is, :), dp)
      call dpbtrs('U', om%ns, om%kds, m, om%kss_fac, om%kds + 1, z, om%ns, info)
      f(om%is, :) = z
      call band_mul_xp(om%kd, om%k_band, f, h)      ! residual -(K_ss z + K_sr x)
      z = -real(h(om%is, :), dp)
      call dpbtrs('U', om%ns, om%kds, m, om%kss_fac, om%kds + 1, z, om%ns, info)
      f(om%is, :) = f(om%is, :) + z
   end subroutine full_vectors

   !> Rows of functionals on the full dofs reduced to the dofs with mass: l_r + T' l_s
   !> (T' l_s = -K_rs K_ss^-1 l_s).
   subroutine reduce_rows(om, l, lr)
      type(open_modes_t), intent(in) :: om
      real(dp), intent(in) :: l(:, :)                  !! (n, m)
      real(dp), allocatable, intent(out) :: lr(:, :)   !! (nr, m)
      real(dp), allocatable :: f(:, :), z(:, :)
      real(xp), allocatable :: h(:, :)
      integer :: info, m
      lr = l(om%ir, :)
      if (om%ns == 0) return
      m = size(l, 2)
      z = l(om%is, :)
      call dpbtrs('U', om%ns, om%kds, m, om%kss_fac, om%kds + 1, z, om%ns, info)
      allocate(f(om%n, m), source=0.0_dp)
      f(om%is, :) = z
      call band_mul_xp(om%kd, om%k_band, f, h)
      lr = real(real(lr, xp) - h(om%ir, :), dp)
   end subroutine reduce_rows

   !> Massless part of a state: z = T x (x on the dofs with mass).
   subroutine condense(om, x, z)
      type(open_modes_t), intent(in) :: om         !! open structure
      real(dp), intent(in) :: x(:)                 !! (nr) dofs with mass
      real(dp), intent(out) :: z(:)                !! (ns) massless dofs
      real(dp), allocatable :: f(:, :)
      if (om%ns == 0) return
      call full_vectors(om, reshape(x, [size(x), 1]), f)
      z = f(om%is, 1)
   end subroutine condense

   !> Modal coordinates of a physical state: eta = Phi' M_r u_r (the same for the velocity).
   subroutine to_modal(om, u, v, eta, vel)
      type(open_modes_t), intent(in) :: om          !! open structure
      real(dp), intent(in) :: u(:), v(:)            !! (n) displacement, velocity
      real(dp), intent(out) :: eta(:), vel(:)       !! (nr) modal coordinates and velocities
      real(dp), allocatable :: f(:, :)
      real(xp), allocatable :: h(:, :)
      allocate(f(om%n, 2), source=0.0_dp)
      f(om%ir, 1) = u(om%ir);  f(om%ir, 2) = v(om%ir)
      call band_mul_xp(om%kd, om%m_band, f, h)
      eta = matmul(real(h(om%ir, 1), dp), om%phi)
      vel = matmul(real(h(om%ir, 2), dp), om%phi)
   end subroutine to_modal

   !> Physical state of modal coordinates (massless dofs by condensation).
   subroutine to_physical(om, eta, vel, u, v)
      type(open_modes_t), intent(in) :: om          !! open structure
      real(dp), intent(in) :: eta(:), vel(:)        !! (nr) modal coordinates and velocities
      real(dp), intent(out) :: u(:), v(:)           !! (n) displacement, velocity
      real(dp) :: z(om%ns)
      u(om%ir) = matmul(om%phi, eta)
      v(om%ir) = matmul(om%phi, vel)
      if (om%ns == 0) return
      call condense(om, u(om%ir), z);  u(om%is) = z
      call condense(om, v(om%ir), z);  v(om%is) = z
   end subroutine to_physical

   !> y = A x in extended precision for a symmetric A in upper band storage ab(kd+1+i-j, j).
   pure subroutine band_mul_xp(kd, ab, x, y)
      integer, intent(in) :: kd
      real(dp), intent(in) :: ab(:, :)
      real(dp), intent(in) :: x(:, :)
      real(xp), allocatable, intent(out) :: y(:, :)
      integer :: i, j, c, n
      real(xp) :: aij
      n = size(x, 1)
      allocate(y(n, size(x, 2)), source=0.0_xp)
      do c = 1, size(x, 2)
         do j = 1, n
            y(j, c) = y(j, c) + real(ab(kd + 1, j), xp) * x(j, c)
            do i = max(1, j - kd), j - 1
               aij = real(ab(kd + 1 + i - j, j), xp)
               y(i, c) = y(i, c) + aij * x(j, c)
               y(j, c) = y(j, c) + aij * x(i, c)
            end do
         end do
      end do
   end subroutine band_mul_xp

   !> Roots of lambda^2 + d lambda + w2, stable for any damping ratio: p1 upper (or slow),
   !> p2 lower (or fast).
   pure subroutine sdof_poles(d, w2, p1, p2)
      real(dp), intent(in) :: d, w2
      complex(dp), intent(out) :: p1, p2
      real(dp) :: h, w, disc, fast
      h = 0.5_dp * d
      w = sqrt(w2)
      disc = (h - w) * (h + w)
      if (disc < 0.0_dp) then
         p1 = cmplx(-h, sqrt(-disc), dp)
         p2 = cmplx(-h, -sqrt(-disc), dp)
      else
         fast = -(h + sqrt(disc))
         p2 = cmplx(fast, 0.0_dp, dp)
         p1 = cmplx(w2 / fast, 0.0_dp, dp)
      end if
   end subroutine sdof_poles
end module gapbeam_exact_modes
