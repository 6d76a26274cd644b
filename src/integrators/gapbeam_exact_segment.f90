!> The closed form of the piecewise-linear gap model between contact switches: the linear
!> algebra of the exact event-driven integrator (gapbeam_exact), kept apart from its event
!> search and bookkeeping.
!>
!> Between two switches of the contact configuration (the set of active contacts) the motion
!> obeys a linear system with constant coefficients. In the state x = (u, v) of the dofs that
!> carry mass,
!>
!>    x' = A x + b_s sin(Omega t) + b_0,   A = [0, I; -M^-1 K_e, -M^-1 C_e],
!>
!> with K_e = K + sum_active k_c e_c e_c', C_e = C + sum_active c_c e_c e_c' (contact spring and
!> damper at the contact dof), b_0 = M^-1 sum_active s_c k_c g_c e_c (the gap) and
!> b_s = M^-1 q (A_pp/2) Omega^2. Its solution is known in closed form,
!>
!>    x(t0 + tau) = x_c + Re(X e^{i Omega (t0 + tau)}) + sum_j f_j Re(c_j w_j e^{lambda_j tau}),
!>
!> with x_c = -A^-1 b_0 (static part), X the harmonic particular solution,
!> (K_e - Omega^2 M + i Omega C_e) X_u = -i F, and (lambda_j, w_j) the eigenpairs of A (LAPACK
!> dgeev; one of each complex-conjugate pair is kept, f_j = 2, real eigenvalues f_j = 1). The
!> eigen decomposition, W^-1, x_c and X are computed once per configuration (`config_t`); a
!> switch only projects the state on the new basis, c = W^-1 (x - x_c - Re(X e^{i Omega t0})),
!> with one step of iterative refinement (`start_segment`). The real part of each complex
!> eigenvalue is replaced by the exact identity of the symmetric quadratic problem,
!> Re(lambda) = -phi^H C_e phi / (2 phi^H M phi) with phi the computed shape: dgeev's own real
!> part is off by ~eps ||A|| (an energy drift of ~1e-13 per second without damping); this one is
!> exactly 0 for an undamped configuration and exact to second order otherwise. The imaginary
!> part (the frequency) comes from the same shape, sqrt(phi^H K_e phi / phi^H M phi -
!> Re(lambda)^2), since dgeev's is off by ~eps ||A|| too, and each complex shape gets one step
!> of inverse iteration, (K_e + mu C_e + mu^2 M) phi' = M phi, before W^-1 is formed.
!>
!> Every watched quantity (contact penetrations, root strain, tip displacement) is a linear
!> functional of x, hence a sum of exponentials Re(sum_j a_j e^{mu_j tau}) + a_0 (`segment_t`),
!> whose derivatives multiply a_j by mu_j^k and whose magnitudes sum_j |a_j e^{mu_j tau}|
!> |mu_j|^k bound |phi^(k)| on the rest of the segment (`eval_seg`). Integrals of a contact force,
!> its square and f |d'| over a window follow in closed form (`modal_window`).
!>
!> **Massless dofs** (lumped mass without rotary inertia: zero rows of M). With C = beta M +
!> gamma K, their rows read gamma (K_ss v_s + K_sr v_r) + K_ss u_s + K_sr u_r = 0, i.e.
!> gamma z' + z = 0 for z = K_ss u_s + K_sr u_r. The initial state is put in equilibrium
!> (z(0) = z'(0) = 0), so z = 0 for all time: u_s = T u_r, T = -K_ss^-1 K_sr, exactly (static
!> condensation, `setup_reduction`), and the remaining rows carry K_r = K_rr + K_rs T,
!> C_r = C_rr + C_rs T = beta M_rr + gamma K_r. Contacts on massless dofs are rejected.
!>
!> **Defective configurations.** When the eigenvector matrix is ill-conditioned (row-equilibrated
!> condition number above the limit, e.g. a critically damped mode), the configuration is
!> integrated instead by a Taylor expansion of the matrix exponential of the augmented, balanced
!> system z = (u, v/w_s, a sin, a cos, a), z' = Ahat z, on sub-steps with ||Ahat||_F h <= 1/2
!> (degree 18, truncation below 1e-22), with the bounds |phi^(k)| <= |l| ||Ahat||^k e^{1/2} |z_k|;
!> statistics by 16-point Gauss-Legendre on each sub-step. Exact to round-off but slow (about
!> 6 ||Ahat||_F sub-steps per second): a safety net for a non-generic case.
module gapbeam_exact_segment
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t
   use gapbeam_lapack, only: dgeev, dgesv, dpotrf, dpotrs, zgesv
   implicit none
   private
   public :: reduced_t, config_t, segment_t, setup_reduction, expand, build_config, mask_text, &
      start_segment, eval_seg, segment_values, segment_state, taylor_next, modal_window, &
      taylor_window, gauss_legendre, sign_after, band, add_fn, mono_quad, cubic_root
   public :: zero_tol, cond_limit, n_taylor

   real(dp), parameter :: zero_tol = 1.0e-12_dp    !! |phi^(k)| <= zero_tol * scale: zero
   real(dp), parameter :: prune_tol = 1.0e-17_dp   !! a decayed term below this is dropped
   real(dp), parameter :: cond_limit = 1.0e6_dp    !! eigenvector condition: above, Taylor
   integer, parameter :: n_taylor = 18             !! Taylor degree of the fallback
   real(dp), parameter :: inv_k(10) = 1.0_dp / [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp, &
      6.0_dp, 7.0_dp, 8.0_dp, 9.0_dp, 10.0_dp]

   !> The structure condensed to its dofs with mass.
   type :: reduced_t
      integer :: n = 0                         ! all dofs
      integer :: nr = 0                        ! dofs with mass
      integer :: ns = 0                        ! massless dofs
      integer :: nb = 0                        ! watched functionals: slots, strain, tip
      integer :: n_slots = 0                   ! distinct contact dofs
      integer :: b_strain = 0                  ! functional index of the root strain
      integer :: b_tip = 0                     ! functional index of the tip displacement
      integer, allocatable :: ir(:), is(:)     ! global indices of the two groups
      integer, allocatable :: cpos(:)          ! reduced index of each contact's dof
      integer, allocatable :: cslot(:)         ! functional of each contact (its slot)
      real(dp), allocatable :: t(:, :)         ! (ns, nr) u_s = T u_r
      real(dp), allocatable :: mr(:, :)        ! M_rr
      real(dp), allocatable :: mfac(:, :)      ! Cholesky factor of M_rr
      real(dp), allocatable :: kr(:, :)        ! condensed stiffness
      real(dp), allocatable :: cr(:, :)        ! condensed damping
      real(dp), allocatable :: qr(:)           ! load shape
      real(dp), allocatable :: ell(:, :)       ! (nr, nb) functional rows on u_r
   end type reduced_t

   !> One contact configuration, closed form (modal) or Taylor fallback.
   type :: config_t
      integer(int64) :: mask = 0                    ! active contacts (bit c-1)
      logical :: modal = .true.                     ! eigen decomposition usable
      real(dp) :: cond = 0.0_dp                     ! condition of the eigenvector matrix
      integer :: p = 0                              ! kept eigenvalues (one per pair)
      complex(dp), allocatable :: mu(:)             ! (p) eigenvalues
      real(dp), allocatable :: fac(:)               ! (p) 1 (real) or 2 (pair)
      complex(dp), allocatable :: wh(:, :)          ! (2 nr, p) eigenvectors
      complex(dp), allocatable :: winv(:, :)        ! (p, 2 nr) rows of W^-1
      complex(dp), allocatable :: lrow(:, :)        ! (p, nb) functionals of the eigenvectors
      complex(dp), allocatable :: xh(:)             ! (2 nr) harmonic amplitude
      complex(dp), allocatable :: lh(:)             ! (nb) functionals of xh
      real(dp), allocatable :: xc(:)                ! (2 nr) static part
      real(dp), allocatable :: lc(:)                ! (nb) functionals of xc
      real(dp), allocatable :: amat(:, :)           ! (2 nr, 2 nr) A
      real(dp), allocatable :: absamat(:, :)        ! |A|
      real(dp), allocatable :: bsv(:), b0v(:)       ! (2 nr) forcing and gap vectors
      ! Taylor fallback
      real(dp), allocatable :: ahat(:, :)           ! augmented balanced matrix
      real(dp) :: omega_s = 1.0_dp                  ! velocity scale [1/s]
      real(dp) :: alpha = 1.0_dp                    ! scale of the forcing entries [m]
      real(dp) :: nrm = 0.0_dp                      ! ||Ahat||_F
      real(dp) :: hsub = 0.0_dp                     ! sub-step
   end type config_t

   !> The current linear segment: coefficients of every watched functional.
   type :: segment_t
      integer :: ic = 0                             ! configuration
      logical :: modal = .true.
      integer :: nt = 0                             ! terms (eigenvalues + harmonic)
      complex(dp), allocatable :: mu(:)             ! (nt) exponents
      complex(dp), allocatable :: mp(:, :)          ! (3, nt) mu, mu^2, mu^3
      real(dp), allocatable :: am(:, :)             ! (0:4, nt) |mu|^k
      complex(dp), allocatable :: c(:)              ! (nt) state coefficients (f_j c_j)
      complex(dp), allocatable :: e(:)              ! (nt) e^{mu tau} at the last evaluation
      complex(dp), allocatable :: a(:, :)           ! (nt, nb) functional coefficients
      real(dp), allocatable :: absa(:, :)           ! |a|
      real(dp), allocatable :: a0(:)                ! (nb) constants
      logical, allocatable :: live(:)               ! not pruned
      logical, allocatable :: real_term(:)          ! real exponent
      real(dp), allocatable :: me(:)                ! |e^{mu tau}| at the last evaluation
      integer :: n_eval = 0
      integer :: n_recur = 0                        ! evaluations by recurrence in a row
      real(dp) :: tau_last = 0.0_dp                 ! instant of the last evaluation
      real(dp) :: mu_max = 0.0_dp                   ! largest |mu|
      ! Taylor fallback: current sub-step [tk, tk + hsub]
      real(dp) :: tk = 0.0_dp
      real(dp), allocatable :: pw(:, :)             ! (na, 0:n_taylor) Ahat^m z_k / m!
      real(dp), allocatable :: pc(:, :)             ! (0:n_taylor, nb) functional coefficients
      real(dp), allocatable :: elln(:)              ! (nb) |l|_2
      real(dp) :: zbound = 0.0_dp                   ! bound of |z| on the sub-step
   end type segment_t

contains

   ! ------------------------------------------------------------------ set-up

   !> Condense the massless dofs and set up the watched functionals.
   subroutine setup_reduction(model, red, err)
      type(model_t), intent(in) :: model
      type(reduced_t), intent(out) :: red
      type(error_t), allocatable, intent(out) :: err
      integer :: i, j, n, nr, ns, info, c, b
      real(dp), allocatable :: kss(:, :), rhs(:, :), l(:)
      real(dp) :: scl
      n = model%n
      red%n = n
      red%ir = pack([(i, i = 1, n)], [(model%sys%m(i, i) /= 0.0_dp, i = 1, n)])
      red%is = pack([(i, i = 1, n)], [(model%sys%m(i, i) == 0.0_dp, i = 1, n)])
      nr = size(red%ir);  ns = size(red%is)
      red%nr = nr;  red%ns = ns
      if (nr == 0) then
         call fatal_error(err, 'gapbeam_exact: the model has no mass')
         return
      end if
      allocate(red%t(ns, nr))
      if (ns > 0) then
         if (maxval(abs(model%sys%m(red%is, :))) > 0.0_dp) then
            call fatal_error(err, 'gapbeam_exact: a dof with zero diagonal mass ' &
               // 'is coupled by the mass matrix; cannot condense it')
            return
         end if
         scl = max(maxval(abs(model%c)), tiny(1.0_dp))
         if (maxval(abs(model%c(red%is, :) - model%gamma * model%sys%k(red%is, :))) &
             > 1.0e-12_dp * scl) then
            call fatal_error(err, 'gapbeam_exact: the damping rows of the massless ' &
               // 'dofs are not gamma K (Rayleigh): the static condensation does not apply')
            return
         end if
         kss = model%sys%k(red%is, red%is)
         rhs = -model%sys%k(red%is, red%ir)
         call dpotrf('U', ns, kss, ns, info)
         if (info == 0) call dpotrs('U', ns, nr, kss, ns, rhs, ns, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_exact: the stiffness of the massless ' &
               // 'dofs is singular (dpotrf/dpotrs info=' // str(info) // ')')
            return
         end if
         red%t = rhs
      end if
      red%mr = model%sys%m(red%ir, red%ir)
      red%kr = model%sys%k(red%ir, red%ir)
      red%cr = model%c(red%ir, red%ir)
      if (ns > 0) then
         red%kr = red%kr + matmul(model%sys%k(red%ir, red%is), red%t)
         red%cr = red%cr + matmul(model%c(red%ir, red%is), red%t)
      end if
      red%kr = 0.5_dp * (red%kr + transpose(red%kr))
      red%cr = 0.5_dp * (red%cr + transpose(red%cr))
      red%qr = model%q(red%ir)
      red%mfac = red%mr
      call dpotrf('U', nr, red%mfac, nr, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_exact: the mass matrix of the dofs with mass ' &
            // 'is not positive definite (dpotrf info=' // str(info) // ')')
         return
      end if
      ! contacts and functionals
      red%n_slots = model%n_slots
      red%nb = model%n_slots + 2
      red%b_strain = model%n_slots + 1
      red%b_tip = model%n_slots + 2
      allocate(red%cpos(model%n_contacts), red%cslot(model%n_contacts))
      do c = 1, model%n_contacts
         red%cpos(c) = 0
         do j = 1, nr
            if (red%ir(j) == model%c_dof(c)) red%cpos(c) = j
         end do
         if (red%cpos(c) == 0) then
            call fatal_error(err, 'gapbeam_exact: stop ' // str(model%c_stop(c)) &
               // ' acts on a massless dof (global dof ' // str(model%c_dof(c)) // '); the ' &
               // 'exact integrator condenses massless dofs and needs contacts on dofs with mass')
            return
         end if
         red%cslot(c) = model%c_slot(c)
      end do
      allocate(red%ell(nr, red%nb), l(n))
      do b = 1, red%nb
         l = 0.0_dp
         if (b <= model%n_slots) then
            l(model%slot_dof(b)) = 1.0_dp
         else if (b == red%b_strain) then
            l = model%sys%strain_row
         else
            if (model%sys%tip_dof > 0) l(model%sys%tip_dof) = 1.0_dp
         end if
         red%ell(:, b) = l(red%ir)
         if (ns > 0) red%ell(:, b) = red%ell(:, b) + matmul(transpose(red%t), l(red%is))
      end do
   end subroutine setup_reduction

   !> Full vector from the reduced one: x_s = T x_r.
   pure subroutine expand(red, xr, x)
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: xr(:)
      real(dp), intent(out) :: x(:)
      x(red%ir) = xr
      if (red%ns > 0) x(red%is) = matmul(red%t, xr)
   end subroutine expand

   !> Closed form (or Taylor fallback) of the configuration `mask`.
   subroutine build_config(model, red, mask, climit, cf, err)
      type(model_t), intent(in) :: model                !! model
      type(reduced_t), intent(in) :: red                !! condensed structure
      integer(int64), intent(in) :: mask                !! active contacts (bit c-1)
      real(dp), intent(in) :: climit                    !! eigenvector condition limit
      type(config_t), intent(out) :: cf                 !! the configuration
      type(error_t), allocatable, intent(inout) :: err  !! singular or resonant configuration
      real(dp), allocatable :: ke(:, :), ce(:, :), b0(:), g(:, :), h(:, :)
      real(dp) :: amp
      character(len=:), allocatable :: where
      where = 'gapbeam_exact: configuration ' // mask_text(mask, model%n_contacts)
      cf%mask = mask
      call config_matrices(model, red, mask, ke, ce, b0)
      amp = model%half_amplitude * model%omega**2
      call particular_parts(red, ke, ce, b0, model%omega, amp, where, cf, err)
      if (allocated(err)) return
      call state_matrix(red, ke, ce, b0, amp, cf, g, h)
      call eigen_basis(red, climit, where, cf, err)
      if (allocated(err)) return
      if (.not. (cf%cond <= climit) .and. climit < huge(1.0_dp)) then
         call build_taylor(red, model%omega, amp, g, h, b0, cf)
         return
      end if
      call refine_eigenpairs(red, ke, ce, cf)
      call functional_rows(red, cf)
   end subroutine build_config

   !> Stiffness, damping and gap load of a configuration: the condensed structure plus the
   !> spring, damper and gap of every active contact.
   pure subroutine config_matrices(model, red, mask, ke, ce, b0)
      type(model_t), intent(in) :: model                !! model
      type(reduced_t), intent(in) :: red                !! condensed structure
      integer(int64), intent(in) :: mask                !! active contacts
      real(dp), allocatable, intent(out) :: ke(:, :), ce(:, :), b0(:)   !! K_e, C_e, gap load
      integer :: c, i
      ke = red%kr;  ce = red%cr
      allocate(b0(red%nr), source=0.0_dp)
      do c = 1, model%n_contacts
         if (.not. btest(mask, c - 1)) cycle
         i = red%cpos(c)
         ke(i, i) = ke(i, i) + model%c_k(c)
         ce(i, i) = ce(i, i) + model%c_c(c)
         b0(i) = b0(i) + model%c_sign(c) * model%c_k(c) * model%c_gap(c)
      end do
   end subroutine config_matrices

   !> Static part x_c = (K_e^-1 b0, 0) and harmonic particular solution:
   !> (K_e - W^2 M + i W C_e) Y = F, u = Re(-i Y e^{iWt}).
   subroutine particular_parts(red, ke, ce, b0, om, amp, where, cf, err)
      type(reduced_t), intent(in) :: red                !! condensed structure
      real(dp), intent(in) :: ke(:, :), ce(:, :), b0(:) !! K_e, C_e, gap load
      real(dp), intent(in) :: om, amp                   !! forcing [rad/s], (A_pp/2) W^2
      character(len=*), intent(in) :: where             !! for messages
      type(config_t), intent(inout) :: cf               !! xc, xh set
      type(error_t), allocatable, intent(inout) :: err  !! singular or resonant
      real(dp), allocatable :: kf(:, :), a2(:, :), y2(:, :)
      integer, allocatable :: ipiv(:)
      integer :: nr, nn, info
      nr = red%nr;  nn = 2 * nr
      kf = ke
      call dpotrf('U', nr, kf, nr, info)
      allocate(cf%xc(nn), source=0.0_dp)
      if (info == 0) then
         cf%xc(1:nr) = b0
         call dpotrs('U', nr, 1, kf, nr, cf%xc, nr, info)
      end if
      if (info /= 0) then
         call fatal_error(err, where // ': the stiffness is not positive definite (info=' &
            // str(info) // ')')
         return
      end if
      allocate(cf%xh(nn), source=(0.0_dp, 0.0_dp))
      if (amp == 0.0_dp) return
      allocate(a2(nn, nn), y2(nn, 1), ipiv(nn))
      a2(1:nr, 1:nr) = ke - om**2 * red%mr
      a2(nr + 1:, nr + 1:) = a2(1:nr, 1:nr)
      a2(1:nr, nr + 1:) = -om * ce
      a2(nr + 1:, 1:nr) = om * ce
      y2 = 0.0_dp
      y2(1:nr, 1) = amp * red%qr
      call dgesv(nn, 1, a2, nn, ipiv, y2, nn, info)
      if (info /= 0) then
         call fatal_error(err, where // ': the forcing frequency is a natural frequency ' &
            // 'of an undamped configuration (dgesv info=' // str(info) // '); no ' &
            // 'periodic particular solution')
         return
      end if
      cf%xh(1:nr) = cmplx(y2(nr + 1:, 1), -y2(1:nr, 1), dp)     ! -i Y
      cf%xh(nr + 1:) = om * cmplx(y2(1:nr, 1), y2(nr + 1:, 1), dp)   ! i W (-i Y)
   end subroutine particular_parts

   !> A = [0 I; -M^-1 K_e, -M^-1 C_e] (and |A|), the forcing and gap vectors; g = M^-1 K_e,
   !> h = M^-1 C_e for the Taylor fallback.
   subroutine state_matrix(red, ke, ce, b0, amp, cf, g, h)
      type(reduced_t), intent(in) :: red                !! condensed structure
      real(dp), intent(in) :: ke(:, :), ce(:, :), b0(:) !! K_e, C_e, gap load
      real(dp), intent(in) :: amp                       !! (A_pp/2) W^2
      type(config_t), intent(inout) :: cf               !! amat, absamat, bsv, b0v set
      real(dp), allocatable, intent(out) :: g(:, :), h(:, :)   !! M^-1 K_e, M^-1 C_e
      integer :: nr, nn, i, info
      nr = red%nr;  nn = 2 * nr
      g = ke;  h = ce
      call dpotrs('U', nr, nr, red%mfac, nr, g, nr, info)
      call dpotrs('U', nr, nr, red%mfac, nr, h, nr, info)
      allocate(cf%amat(nn, nn), source=0.0_dp)
      do i = 1, nr
         cf%amat(i, nr + i) = 1.0_dp
      end do
      cf%amat(nr + 1:, 1:nr) = -g
      cf%amat(nr + 1:, nr + 1:) = -h
      cf%absamat = abs(cf%amat)
      allocate(cf%bsv(nn), cf%b0v(nn), source=0.0_dp)
      cf%bsv(nr + 1:) = amp * red%qr
      cf%b0v(nr + 1:) = b0
      call dpotrs('U', nr, 1, red%mfac, nr, cf%bsv(nr + 1:), nr, info)
      call dpotrs('U', nr, 1, red%mfac, nr, cf%b0v(nr + 1:), nr, info)
   end subroutine state_matrix

   !> Eigenpairs of A (dgeev), W^-1, the row-equilibrated condition number of W, and one
   !> eigenvalue of each complex-conjugate pair kept (mu, fac, wh, winv).
   subroutine eigen_basis(red, climit, where, cf, err)
      type(reduced_t), intent(in) :: red                !! condensed structure
      real(dp), intent(in) :: climit                    !! condition limit (< 0: skip)
      character(len=*), intent(in) :: where             !! for messages
      type(config_t), intent(inout) :: cf               !! the configuration
      type(error_t), allocatable, intent(inout) :: err  !! dgeev failure
      real(dp), allocatable :: amat(:, :), wr(:), wi(:), vr(:, :), vl(:, :), work(:), rs(:)
      complex(dp), allocatable :: w(:, :), winv(:, :), wcopy(:, :)
      integer, allocatable :: ipiv(:)
      integer :: nn, lwork, info, i, j, p
      real(dp) :: query(1), n1, n2
      nn = 2 * red%nr
      amat = cf%amat
      allocate(wr(nn), wi(nn), vr(nn, nn), vl(1, 1))
      call dgeev('N', 'V', nn, amat, nn, wr, wi, vl, 1, vr, nn, query, -1, info)
      lwork = max(1, int(query(1)))
      allocate(work(lwork))
      call dgeev('N', 'V', nn, amat, nn, wr, wi, vl, 1, vr, nn, work, lwork, info)
      if (info /= 0) then
         call fatal_error(err, where // ': dgeev failed, info=' // str(info))
         return
      end if
      allocate(w(nn, nn))
      j = 1
      do while (j <= nn)
         if (wi(j) == 0.0_dp .or. j == nn) then
            w(:, j) = cmplx(vr(:, j), 0.0_dp, dp)
            j = j + 1
         else
            w(:, j) = cmplx(vr(:, j), vr(:, j + 1), dp)
            w(:, j + 1) = conjg(w(:, j))
            j = j + 2
         end if
      end do
      wcopy = w
      allocate(winv(nn, nn), source=(0.0_dp, 0.0_dp))
      do i = 1, nn
         winv(i, i) = (1.0_dp, 0.0_dp)
      end do
      allocate(ipiv(nn))
      call zgesv(nn, nn, wcopy, nn, ipiv, winv, nn, info)
      ! row-equilibrated 1-norm condition number
      allocate(rs(nn))
      do i = 1, nn
         rs(i) = max(maxval(abs(w(i, :))), tiny(1.0_dp))
      end do
      n1 = 0.0_dp;  n2 = 0.0_dp
      do j = 1, nn
         n1 = max(n1, sum(abs(w(:, j)) / rs))
         n2 = max(n2, rs(j) * sum(abs(winv(:, j))))
      end do
      cf%cond = n1 * n2
      if (info /= 0) cf%cond = huge(1.0_dp)
      if (.not. (cf%cond <= climit) .and. climit < huge(1.0_dp)) return
      ! keep one eigenvalue of each pair
      p = count(wi >= 0.0_dp)
      allocate(cf%mu(p), cf%fac(p), cf%wh(nn, p), cf%winv(p, nn))
      p = 0
      j = 1
      do while (j <= nn)
         p = p + 1
         cf%mu(p) = cmplx(wr(j), wi(j), dp)
         cf%wh(:, p) = w(:, j)
         cf%winv(p, :) = winv(j, :)
         if (wi(j) == 0.0_dp .or. j == nn) then
            cf%fac(p) = 1.0_dp
            j = j + 1
         else
            cf%fac(p) = 2.0_dp
            j = j + 2
         end if
      end do
      cf%p = p
      cf%mu = cf%mu(1:p);  cf%fac = cf%fac(1:p)
      cf%wh = cf%wh(:, 1:p);  cf%winv = cf%winv(1:p, :)
   end subroutine eigen_basis

   !> Refine the complex eigenpairs. The real part of a complex eigenvalue of the symmetric
   !> quadratic problem (lambda^2 M + lambda C + K) phi = 0 is exactly -phi^H C phi /
   !> (2 phi^H M phi): taken from the computed shape it is accurate to the shape's error
   !> squared (dgeev's own is off by ~eps ||A||, an energy drift of ~1e-13 per second without
   !> damping), and it is exactly 0 for an undamped configuration. The imaginary part likewise:
   !> dgeev's is off by ~eps ||A|| in absolute terms, i.e. by eps omega_max^2 / omega relative
   !> for a low mode of a stiff model, while the root of phi^H (lambda^2 M + lambda C + K) phi
   !> = 0 is again accurate to the shape's error squared; it is taken unless the discriminant
   !> cancels (a nearly critically damped pair). Then one step of inverse iteration on each
   !> complex shape with the refined eigenvalue, (K + mu C + mu^2 M) phi' = M phi, W^-1 again,
   !> and the eigenvalues once more from the new shapes.
   subroutine refine_eigenpairs(red, ke, ce, cf)
      type(reduced_t), intent(in) :: red                !! condensed structure
      real(dp), intent(in) :: ke(:, :), ce(:, :)        !! K_e, C_e
      type(config_t), intent(inout) :: cf               !! mu, wh, winv refined
      complex(dp), allocatable :: qm(:, :), phq(:, :), w(:, :), winv(:, :)
      integer, allocatable :: ip2(:), jidx(:), ipiv(:)
      integer :: nr, nn, p, j, i, q, info
      nr = red%nr;  nn = 2 * nr;  p = cf%p
      call rayleigh_eigenvalues(red, ke, ce, cf)
      allocate(qm(nr, nr), phq(nr, 1), ip2(nr))
      do j = 1, p
         if (aimag(cf%mu(j)) == 0.0_dp) cycle
         qm = ke + cf%mu(j) * ce + cf%mu(j)**2 * red%mr
         phq(:, 1) = matmul(red%mr, cf%wh(1:nr, j))
         call zgesv(nr, 1, qm, nr, ip2, phq, nr, info)
         if (info /= 0) cycle
         if (.not. (maxval(abs(phq)) > 0.0_dp)) cycle
         phq = phq * (maxval(abs(cf%wh(1:nr, j))) / maxval(abs(phq)))
         cf%wh(1:nr, j) = phq(:, 1)
         cf%wh(nr + 1:, j) = cf%mu(j) * phq(:, 1)
      end do
      allocate(w(nn, nn), jidx(p), ipiv(nn))
      q = 0
      do j = 1, p
         q = q + 1
         w(:, q) = cf%wh(:, j)
         jidx(j) = q
         if (cf%fac(j) == 2.0_dp) then
            q = q + 1
            w(:, q) = conjg(cf%wh(:, j))
         end if
      end do
      allocate(winv(nn, nn), source=(0.0_dp, 0.0_dp))
      do i = 1, nn
         winv(i, i) = (1.0_dp, 0.0_dp)
      end do
      call zgesv(nn, nn, w, nn, ipiv, winv, nn, info)
      do j = 1, p
         cf%winv(j, :) = winv(jidx(j), :)
      end do
      call rayleigh_eigenvalues(red, ke, ce, cf)
   end subroutine refine_eigenpairs

   !> Real and imaginary parts of each complex eigenvalue from its shape (see
   !> refine_eigenpairs).
   subroutine rayleigh_eigenvalues(red, ke, ce, cf)
      type(reduced_t), intent(in) :: red                !! condensed structure
      real(dp), intent(in) :: ke(:, :), ce(:, :)        !! K_e, C_e
      type(config_t), intent(inout) :: cf               !! mu refined
      integer :: j, nr
      real(dp) :: n1, n2, n3, re_mu, im_mu, im2
      nr = red%nr
      do j = 1, cf%p
         if (aimag(cf%mu(j)) == 0.0_dp) cycle
         n1 = real(dot_product(cf%wh(1:nr, j), matmul(ce, cf%wh(1:nr, j))))
         n2 = real(dot_product(cf%wh(1:nr, j), matmul(red%mr, cf%wh(1:nr, j))))
         n3 = real(dot_product(cf%wh(1:nr, j), matmul(ke, cf%wh(1:nr, j))))
         if (n2 > 0.0_dp) then
            re_mu = -0.5_dp * n1 / n2
            im2 = n3 / n2 - re_mu**2
            im_mu = aimag(cf%mu(j))
            if (im2 > 0.25_dp * (n3 / n2)) im_mu = sqrt(im2)
            cf%mu(j) = cmplx(re_mu, im_mu, dp)
         end if
      end do
   end subroutine rayleigh_eigenvalues

   !> The watched functionals on the eigenvectors, the harmonic and the static parts.
   pure subroutine functional_rows(red, cf)
      type(reduced_t), intent(in) :: red                !! condensed structure
      type(config_t), intent(inout) :: cf               !! lrow, lh, lc set
      integer :: b, j, nr
      nr = red%nr
      allocate(cf%lrow(cf%p, red%nb), cf%lh(red%nb), cf%lc(red%nb))
      do b = 1, red%nb
         do j = 1, cf%p
            cf%lrow(j, b) = sum(red%ell(:, b) * cf%wh(1:nr, j))
         end do
         cf%lh(b) = sum(red%ell(:, b) * cf%xh(1:nr))
         cf%lc(b) = sum(red%ell(:, b) * cf%xc(1:nr))
      end do
   end subroutine functional_rows

   !> Augmented balanced matrix of the Taylor fallback.
   subroutine build_taylor(red, om, amp, g, h, b0, cf)
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: om, amp
      real(dp), intent(in) :: g(:, :), h(:, :), b0(:)   ! M^-1 Ke, M^-1 Ce, gap load
      type(config_t), intent(inout) :: cf
      integer :: nr, na, i, info
      real(dp), allocatable :: f(:, :)
      nr = red%nr;  na = 2 * nr + 3
      cf%modal = .false.
      cf%omega_s = sqrt(maxval(sum(abs(g), dim=2)))
      if (.not. (cf%omega_s > 0.0_dp)) cf%omega_s = 1.0_dp
      cf%alpha = max(maxval(abs(cf%xh(1:nr))), maxval(abs(cf%xc(1:nr))))
      if (.not. (cf%alpha > 0.0_dp)) cf%alpha = 1.0_dp
      allocate(f(nr, 2))
      f(:, 1) = amp * red%qr;  f(:, 2) = b0
      call dpotrs('U', nr, 2, red%mfac, nr, f, nr, info)
      allocate(cf%ahat(na, na), source=0.0_dp)
      do i = 1, nr
         cf%ahat(i, nr + i) = cf%omega_s
      end do
      cf%ahat(nr + 1:2 * nr, 1:nr) = -g / cf%omega_s
      cf%ahat(nr + 1:2 * nr, nr + 1:2 * nr) = -h
      cf%ahat(nr + 1:2 * nr, 2 * nr + 1) = f(:, 1) / (cf%omega_s * cf%alpha)
      cf%ahat(nr + 1:2 * nr, 2 * nr + 3) = f(:, 2) / (cf%omega_s * cf%alpha)
      cf%ahat(2 * nr + 1, 2 * nr + 2) = om
      cf%ahat(2 * nr + 2, 2 * nr + 1) = -om
      cf%nrm = sqrt(sum(cf%ahat**2))
      cf%hsub = 0.5_dp / cf%nrm
   end subroutine build_taylor

   !> 'contacts {1, 3} active' style text of a mask.
   function mask_text(mask, nc) result(s)
      integer(int64), intent(in) :: mask
      integer, intent(in) :: nc
      character(len=:), allocatable :: s
      integer :: c
      s = '(active contacts:'
      do c = 1, nc
         if (btest(mask, c - 1)) s = s // ' ' // str(c)
      end do
      if (mask == 0) s = s // ' none'
      s = s // ')'
   end function mask_text

   ! ------------------------------------------------------------------ segments

   !> Coefficients of the segment starting from x0 at forcing offset r0.
   subroutine start_segment(cf, red, om, x0, r0, sg)
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: om, x0(:), r0
      type(segment_t), intent(inout) :: sg
      integer :: p, nt, j, b, nr, na
      complex(dp) :: ph
      real(dp), allocatable :: rhs(:), z(:), res(:)
      nr = red%nr
      sg%modal = cf%modal
      sg%n_eval = 0
      if (.not. cf%modal) then
         na = 2 * nr + 3
         if (.not. allocated(sg%pw)) then
            allocate(sg%pw(na, 0:n_taylor), sg%pc(0:n_taylor, red%nb), sg%elln(red%nb))
         else if (size(sg%pw, 1) /= na) then
            deallocate(sg%pw, sg%pc, sg%elln)
            allocate(sg%pw(na, 0:n_taylor), sg%pc(0:n_taylor, red%nb), sg%elln(red%nb))
         end if
         do b = 1, red%nb
            sg%elln(b) = norm2(red%ell(:, b))
         end do
         allocate(z(na))
         z(1:nr) = x0(1:nr)
         z(nr + 1:2 * nr) = x0(nr + 1:) / cf%omega_s
         z(2 * nr + 1) = cf%alpha * sin(om * r0)
         z(2 * nr + 2) = cf%alpha * cos(om * r0)
         z(2 * nr + 3) = cf%alpha
         sg%tk = 0.0_dp
         call taylor_load(sg, cf, red, z)
         return
      end if
      p = cf%p
      nt = p + 1
      if (allocated(sg%mu)) then
         if (size(sg%mu) /= nt .or. size(sg%a, 2) /= red%nb) deallocate(sg%mu, sg%mp, sg%am, &
            sg%c, sg%a, sg%absa, sg%a0, sg%live, sg%real_term, sg%me, sg%e)
      end if
      if (.not. allocated(sg%mu)) allocate(sg%mu(nt), sg%mp(3, nt), sg%am(0:4, nt), sg%c(nt), &
         sg%a(nt, red%nb), sg%absa(nt, red%nb), sg%a0(red%nb), sg%live(nt), sg%real_term(nt), &
         sg%me(nt), sg%e(nt))
      sg%nt = nt
      sg%n_recur = 0;  sg%tau_last = 0.0_dp
      ph = cmplx(cos(om * r0), sin(om * r0), dp)
      rhs = x0 - cf%xc - real(cf%xh * ph)
      sg%mu(1:p) = cf%mu
      sg%mu(nt) = cmplx(0.0_dp, om, dp)
      do j = 1, p
         sg%c(j) = cf%fac(j) * sum(cf%winv(j, :) * rhs)
      end do
      ! one step of iterative refinement: the residual of the reconstruction, projected again
      ! (the explicit inverse alone leaves ~cond(W) eps; this brings it to ~eps)
      res = rhs
      do j = 1, p
         res = res - real(sg%c(j) * cf%wh(:, j))
      end do
      do j = 1, p
         sg%c(j) = sg%c(j) + cf%fac(j) * sum(cf%winv(j, :) * res)
      end do
      sg%c(nt) = ph
      do j = 1, nt
         sg%mp(1, j) = sg%mu(j)
         sg%mp(2, j) = sg%mu(j)**2
         sg%mp(3, j) = sg%mu(j)**3
         sg%am(0, j) = 1.0_dp
         sg%am(1, j) = abs(sg%mu(j))
         sg%am(2, j) = sg%am(1, j)**2
         sg%am(3, j) = sg%am(1, j)**3
         sg%am(4, j) = sg%am(2, j)**2
         sg%real_term(j) = aimag(sg%mu(j)) == 0.0_dp
      end do
      do b = 1, red%nb
         sg%a(1:p, b) = sg%c(1:p) * cf%lrow(:, b)
         sg%a(nt, b) = cf%lh(b) * ph
         sg%a0(b) = cf%lc(b)
      end do
      sg%absa = abs(sg%a)
      sg%mu_max = maxval(sg%am(1, :))
      sg%live = sg%absa(:, 1) >= 0.0_dp
      sg%live(nt) = cf%lh(1) /= (0.0_dp, 0.0_dp) .or. any(cf%xh /= (0.0_dp, 0.0_dp))
   end subroutine start_segment

   !> Values (derivatives 0..3) and bounds (0..4) of the needed functionals at tau.
   subroutine eval_seg(sg, cf, red, tau, need, val, bnd)
      type(segment_t), intent(inout) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: tau
      logical, intent(in) :: need(:)
      real(dp), intent(out) :: val(0:, :), bnd(0:, :)
      integer :: j, b, m, k
      real(dp) :: me, er, ei, zr, zi, mag, s, acc(0:3), fall, dt, v0, v1, v2, v3, u0, u1, u2, &
         u3, u4
      complex(dp) :: zd, ez
      logical :: recur
      val = 0.0_dp;  bnd = 0.0_dp
      if (.not. sg%modal) then
         s = tau - sg%tk
         do b = 1, red%nb
            if (.not. need(b)) cycle
            acc = 0.0_dp
            do m = n_taylor, 0, -1
               do k = 0, 3
                  if (m < k) cycle
                  fall = 1.0_dp
                  if (k >= 1) fall = real(m, dp)
                  if (k >= 2) fall = fall * real(m - 1, dp)
                  if (k >= 3) fall = fall * real(m - 2, dp)
                  acc(k) = acc(k) * s + fall * sg%pc(m, b)
               end do
            end do
            val(:, b) = acc
            do k = 0, 4
               bnd(k, b) = sg%elln(b) * cf%nrm**k * sg%zbound
            end do
         end do
         return
      end if
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
      ! sums per functional, in scalars
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
         bnd(0, b) = u0;  bnd(1, b) = u1;  bnd(2, b) = u2;  bnd(3, b) = u3;  bnd(4, b) = u4
      end do
      if (mod(sg%n_eval, 8) == 0) call prune(sg)
   end subroutine eval_seg

   !> Values and first derivatives of every functional at tau, from every term (pruned ones
   !> included: valid anywhere in the segment, or in the current Taylor sub-step); does not
   !> touch the segment's evaluation state.
   pure subroutine segment_values(sg, red, tau, val)
      type(segment_t), intent(in) :: sg                 !! segment
      type(reduced_t), intent(in) :: red                !! condensed structure
      real(dp), intent(in) :: tau                       !! instant in the segment [s]
      real(dp), intent(out) :: val(0:, :)               !! (0:1, nb) values and derivatives
      integer :: j, b, m
      real(dp) :: x, er, ei, zr, zi, me
      complex(dp) :: e(sg%nt)
      val = 0.0_dp
      if (.not. sg%modal) then
         x = tau - sg%tk
         do b = 1, red%nb
            do m = n_taylor, 0, -1
               val(0, b) = val(0, b) * x + sg%pc(m, b)
               if (m >= 1) val(1, b) = val(1, b) * x + real(m, dp) * sg%pc(m, b)
            end do
         end do
         return
      end if
      do j = 1, sg%nt
         me = exp(real(sg%mu(j)) * tau)
         if (sg%real_term(j)) then
            e(j) = cmplx(me, 0.0_dp, dp)
         else
            e(j) = cmplx(me * cos(aimag(sg%mu(j)) * tau), me * sin(aimag(sg%mu(j)) * tau), dp)
         end if
      end do
      do b = 1, red%nb
         val(0, b) = sg%a0(b)
         do j = 1, sg%nt
            er = real(e(j));  ei = aimag(e(j))
            zr = real(sg%a(j, b)) * er - aimag(sg%a(j, b)) * ei
            zi = real(sg%a(j, b)) * ei + aimag(sg%a(j, b)) * er
            val(0, b) = val(0, b) + zr
            val(1, b) = val(1, b) + zr * real(sg%mp(1, j)) - zi * aimag(sg%mp(1, j))
         end do
      end do
   end subroutine segment_values

   !> Drop the decaying terms that no longer matter to any functional (below prune_tol of
   !> its current size, value and first derivative).
   subroutine prune(sg)
      type(segment_t), intent(inout) :: sg
      integer :: j, b, nb
      real(dp) :: s0, s1
      logical :: keep(sg%nt)
      nb = size(sg%a, 2)
      keep = .false.
      keep(sg%nt) = sg%live(sg%nt)
      do b = 1, nb
         s0 = abs(sg%a0(b));  s1 = 0.0_dp
         do j = 1, sg%nt
            if (.not. sg%live(j)) cycle
            s0 = s0 + sg%absa(j, b) * sg%me(j)
            s1 = s1 + sg%absa(j, b) * sg%me(j) * sg%am(1, j)
         end do
         do j = 1, sg%nt - 1
            if (.not. sg%live(j) .or. keep(j)) cycle
            if (sg%absa(j, b) * sg%me(j) > prune_tol * s0 .or. &
                sg%absa(j, b) * sg%me(j) * sg%am(1, j) > prune_tol * s1) keep(j) = .true.
         end do
      end do
      do j = 1, sg%nt - 1
         if (sg%live(j) .and. real(sg%mu(j)) < 0.0_dp .and. .not. keep(j)) sg%live(j) = .false.
      end do
   end subroutine prune

   !> Full reduced state x = (u, v) and acceleration at tau (every term).
   subroutine segment_state(sg, cf, red, om, tau, x, acc)
      type(segment_t), intent(in) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: om, tau
      real(dp), intent(out) :: x(:), acc(:)      ! (2 nr), (nr)
      integer :: j, nr, m
      complex(dp) :: e
      real(dp), allocatable :: zv(:), zd(:)
      nr = red%nr
      if (.not. sg%modal) then
         zv = sg%pw(:, n_taylor);  zd = real(n_taylor, dp) * sg%pw(:, n_taylor)
         do m = n_taylor - 1, 0, -1
            zv = zv * (tau - sg%tk) + sg%pw(:, m)
            if (m >= 1) zd = zd * (tau - sg%tk) + real(m, dp) * sg%pw(:, m)
         end do
         x(1:nr) = zv(1:nr)
         x(nr + 1:) = cf%omega_s * zv(nr + 1:2 * nr)
         acc = cf%omega_s * zd(nr + 1:2 * nr)
         return
      end if
      x = cf%xc
      acc = 0.0_dp
      do j = 1, cf%p
         e = sg%c(j) * exp(sg%mu(j) * tau)
         x = x + real(e * cf%wh(:, j))
         acc = acc + real(e * sg%mu(j) * cf%wh(nr + 1:, j))
      end do
      e = sg%c(sg%nt) * exp(sg%mu(sg%nt) * tau)
      x = x + real(e * cf%xh)
      acc = acc + real(e * cmplx(0.0_dp, om, dp) * cf%xh(nr + 1:))
   end subroutine segment_state

   !> Load the Taylor sub-step starting from z.
   subroutine taylor_load(sg, cf, red, z)
      type(segment_t), intent(inout) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), intent(in) :: z(:)
      integer :: m, b, nr
      nr = red%nr
      sg%pw(:, 0) = z
      do m = 1, n_taylor
         sg%pw(:, m) = matmul(cf%ahat, sg%pw(:, m - 1)) / real(m, dp)
      end do
      do b = 1, red%nb
         do m = 0, n_taylor
            sg%pc(m, b) = sum(red%ell(:, b) * sg%pw(1:nr, m))
         end do
      end do
      sg%zbound = norm2(z) * exp(cf%nrm * cf%hsub)
   end subroutine taylor_load

   !> Move the Taylor expansion to the next sub-step.
   subroutine taylor_next(sg, cf, red)
      type(segment_t), intent(inout) :: sg
      type(config_t), intent(in) :: cf
      type(reduced_t), intent(in) :: red
      real(dp), allocatable :: z(:)
      integer :: m
      z = sg%pw(:, n_taylor)
      do m = n_taylor - 1, 0, -1
         z = z * cf%hsub + sg%pw(:, m)
      end do
      sg%tk = sg%tk + cf%hsub
      call taylor_load(sg, cf, red, z)
   end subroutine taylor_next

   ! ------------------------------------------------------------------ statistics

   !> Closed-form integrals over [ta, tb] of f, f^2 and f |d'| for one active contact
   !> (f = k d + c d', d = s u - g), the phase split at the zeros of d' in `roots`.
   subroutine modal_window(sg, b, s, kc, cc, gap, ta, tb, roots, sf, sf2, sw)
      type(segment_t), intent(in) :: sg
      integer, intent(in) :: b
      real(dp), intent(in) :: s, kc, cc, gap, ta, tb, roots(:)
      real(dp), intent(out) :: sf, sf2, sw
      complex(dp) :: pf(sg%nt), pd(sg%nt)
      real(dp) :: f0, pa, pb, da, db, sgn, mid
      integer :: j, k, nt
      nt = sg%nt
      do j = 1, nt
         pf(j) = s * (kc + cc * sg%mu(j)) * sg%a(j, b)
         pd(j) = s * sg%mu(j) * sg%a(j, b)
      end do
      if (.not. sg%live(nt)) then
         pf(nt) = 0.0_dp;  pd(nt) = 0.0_dp
      end if
      f0 = kc * (s * sg%a0(b) - gap)
      sf = lin_integral(sg%mu, pf, f0, ta, tb)
      sf2 = prod_integral(sg%mu, pf, f0, pf, f0, ta, tb)
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
            sgn = sign(1.0_dp, modal_value(sg%mu, pd, 0.0_dp, mid))
            if (cc == 0.0_dp) then
               da = s * modal_value(sg%mu, sg%a(:, b), sg%a0(b), pa) - gap
               db = s * modal_value(sg%mu, sg%a(:, b), sg%a0(b), pb) - gap
               sw = sw + sgn * 0.5_dp * kc * (db**2 - da**2)
            else
               sw = sw + sgn * prod_integral(sg%mu, pf, f0, pd, 0.0_dp, pa, pb)
            end if
         end if
         pa = pb
      end do
   end subroutine modal_window

   !> Re(sum_j a_j e^{mu_j tau}) + a0.
   pure real(dp) function modal_value(mu, a, a0, tau) result(v)
      complex(dp), intent(in) :: mu(:), a(:)
      real(dp), intent(in) :: a0, tau
      integer :: j
      v = a0
      do j = 1, size(mu)
         if (a(j) /= (0.0_dp, 0.0_dp)) v = v + real(a(j) * exp(mu(j) * tau))
      end do
   end function modal_value

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

   !> Integral over [ta, tb] of Re(sum_j p_j e^{mu_j tau}) + p0.
   pure real(dp) function lin_integral(mu, p, p0, ta, tb) result(s)
      complex(dp), intent(in) :: mu(:), p(:)
      real(dp), intent(in) :: p0, ta, tb
      integer :: j
      real(dp) :: l
      l = tb - ta
      s = p0 * l
      do j = 1, size(mu)
         if (p(j) == (0.0_dp, 0.0_dp)) cycle
         s = s + real(p(j) * exp(mu(j) * ta) * l * phi1(mu(j) * l, exp(mu(j) * l)))
      end do
   end function lin_integral

   !> Integral over [ta, tb] of (Re(sum p e^{mu tau}) + p0)(Re(sum q e^{mu tau}) + q0), in
   !> closed form: Re(a) Re(b) = (Re(a b) + Re(a conj(b))) / 2.
   pure real(dp) function prod_integral(mu, p, p0, q, q0, ta, tb) result(s)
      complex(dp), intent(in) :: mu(:), p(:), q(:)
      real(dp), intent(in) :: p0, q0, ta, tb
      complex(dp) :: ea(size(mu)), el(size(mu)), pa(size(mu)), qa(size(mu)), ph(size(mu))
      real(dp) :: l, sp, sq, cut, mp(size(mu)), mq(size(mu)), w
      integer :: j, k, n
      logical :: same
      same = all(p == q) .and. p0 == q0
      n = size(mu)
      l = tb - ta
      do j = 1, n
         ea(j) = exp(mu(j) * ta)
         el(j) = exp(mu(j) * l)
         pa(j) = p(j) * ea(j)
         qa(j) = q(j) * ea(j)
         ph(j) = l * phi1(mu(j) * l, el(j))
      end do
      do j = 1, n
         mp(j) = abs(real(pa(j))) + abs(aimag(pa(j)))
         mq(j) = abs(real(qa(j))) + abs(aimag(qa(j)))
      end do
      sp = sum(mp) + abs(p0);  sq = sum(mq) + abs(q0)
      cut = 1.0e-18_dp * sp * sq
      s = p0 * q0 * l
      do j = 1, n
         s = s + p0 * real(qa(j) * ph(j)) + q0 * real(pa(j) * ph(j))
      end do
      do j = 1, n
         if (mp(j) * sq <= cut) cycle
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
   end function prod_integral

   !> Gauss-Legendre integrals over [ta, tb] (inside the current Taylor sub-step) of f, f^2
   !> and f |d'| for one active contact, split at the zeros of d'.
   subroutine taylor_window(sg, b, s, kc, cc, gap, ta, tb, roots, xg, wg, sf, sf2, sw)
      type(segment_t), intent(in) :: sg
      integer, intent(in) :: b
      real(dp), intent(in) :: s, kc, cc, gap, ta, tb, roots(:), xg(:), wg(:)
      real(dp), intent(out) :: sf, sf2, sw
      real(dp) :: pa, pb, tau, u, du, d, dd, f, half, mid, x
      integer :: k, q, m
      sf = 0.0_dp;  sf2 = 0.0_dp;  sw = 0.0_dp
      pa = ta
      do k = 1, size(roots) + 1
         if (k <= size(roots)) then
            pb = min(max(roots(k), pa), tb)
         else
            pb = tb
         end if
         if (pb > pa) then
            half = 0.5_dp * (pb - pa);  mid = 0.5_dp * (pa + pb)
            do q = 1, size(xg)
               tau = mid + half * xg(q)
               x = tau - sg%tk
               u = 0.0_dp;  du = 0.0_dp
               do m = n_taylor, 0, -1
                  u = u * x + sg%pc(m, b)
                  if (m >= 1) du = du * x + real(m, dp) * sg%pc(m, b)
               end do
               d = s * u - gap;  dd = s * du
               f = kc * d + cc * dd
               sf = sf + half * wg(q) * f
               sf2 = sf2 + half * wg(q) * f**2
               sw = sw + half * wg(q) * f * abs(dd)
            end do
         end if
         pa = pb
      end do
   end subroutine taylor_window

   !> Nodes and weights of n-point Gauss-Legendre on [-1, 1].
   pure subroutine gauss_legendre(x, w)
      real(dp), intent(out) :: x(:), w(:)
      integer :: n, i, k, it
      real(dp) :: z, p0, p1, p2, dp1
      n = size(x)
      do i = 1, n
         z = cos(pi * (real(i, dp) - 0.25_dp) / (real(n, dp) + 0.5_dp))
         do it = 1, 100
            p0 = 1.0_dp;  p1 = z
            do k = 2, n
               p2 = (real(2 * k - 1, dp) * z * p1 - real(k - 1, dp) * p0) / real(k, dp)
               p0 = p1;  p1 = p2
            end do
            dp1 = real(n, dp) * (z * p1 - p0) / (z**2 - 1.0_dp)
            if (abs(p1 / dp1) < 1.0e-16_dp) then
               z = z - p1 / dp1;  exit
            end if
            z = z - p1 / dp1
         end do
         x(i) = z
         w(i) = 2.0_dp / ((1.0_dp - z**2) * dp1**2)
      end do
   end subroutine gauss_legendre

   ! ------------------------------------------------------------------ safe steps

   !> Sign of a function just after an instant from its value and derivatives (0 if all are
   !> zero to round-off of their scales).
   pure integer function sign_after(v, scl)
      real(dp), intent(in) :: v(0:), scl(0:)
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
      real(dp), intent(in) :: y, scl
      band = 0.0_dp
      if (y <= 0.0_dp) band = 2.0_dp * abs(y) + zero_tol * scl
   end function band

   !> Largest h with y + y1 s + y2 s^2/2 + ... >= 0 on [0, h] guaranteed by the bounds
   !> |phi''| <= b2 (quadratic) or |phi'''| <= b3 (cubic).
   pure real(dp) function root_step(y, y1, y2, b2, b3, cap) result(h)
      real(dp), intent(in) :: y, y1, y2, b2, b3
      real(dp), intent(in) :: cap           ! a step this long is enough
      h = 0.0_dp
      if (.not. (y > 0.0_dp)) return
      h = quad_root(y, y1, b2)
      if (h >= cap) return
      if (y2 > -0.5_dp * b2 .and. b3 > 0.0_dp) h = max(h, cubic_root(y, y1, 0.5_dp * y2, &
                                                                      b3 / 6.0_dp, cap))
   end function root_step

   !> Record a function to keep >= 0 for the step choice: value y0, derivatives y1, y2,
   !> |y''| <= b2, |y'''| <= b3, and a step hm known safe otherwise (monotone step of a
   !> running extremum); q gets its quadratic step.
   pure subroutine add_fn(nf, q, fy, fy1, fy2, fb2, fb3, y0, y1, y2, b2, b3, hm)
      integer, intent(inout) :: nf
      real(dp), intent(inout) :: q(:), fy(:), fy1(:), fy2(:), fb2(:), fb3(:)
      real(dp), intent(in) :: y0, y1, y2, b2, b3, hm
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
      real(dp), intent(in) :: p1, p2, b3
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
      real(dp), intent(in) :: y, a, b, c
      real(dp), intent(in) :: cap           ! stop once the answer is known to exceed this
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
      real(dp), intent(in) :: y, a, b, c, s   !! coefficients, argument
      p = y + s * (a + s * (b - c * s))
   end function cubic_value
end module gapbeam_exact_segment
