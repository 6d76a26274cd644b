!> State-transition matrices of the piecewise-linear gap model: the Jacobian of the flow over
!> a sequence of linear segments, for shooting methods and Floquet multipliers.
!>
!> **Coordinates.** The state is x = (u_r, v_r), the displacements and velocities of the dofs
!> that carry mass (all dofs for a consistent mass or a lumped mass with rotary inertia; the
!> translations only for a lumped mass without it). The massless dofs follow by static
!> condensation, u_s = T u_r, v_s = T v_r, T = -K_ss^-1 K_sr (see gapbeam_exact_segment and
!> gapbeam_integrator:massless_equilibrium: the same relation), so they carry no state of their
!> own. `mass_dofs` lists the global indices of x's dofs, in global order.
!>
!> **Flow.** With the set m of active contacts fixed, x' = A_m x + b_s sin(Omega t) + b_m,
!>    A_m = [0, I; -M_r^-1 K_m, -M_r^-1 C_m],  K_m = K_r + sum_{c in m} k_c e_c e_c',
!>    C_m = C_r + sum_{c in m} c_c e_c e_c',
!> so a variation obeys dx' = A_m dx and the segment's transition matrix is e^{A_m tau}
!> (computed here by scaling and squaring with the degree-13 Pade approximant, Higham 2005;
!> exact to round-off, defective configurations included).
!>
!> **Switches.** At an instant where contact c closes or opens the state is continuous and the
!> vector field f jumps from f- to f+ (both evaluated at the switch). A variation of the start
!> state moves the switch instant; the saltation matrix
!>    S = I + (f+ - f-) n' / (n' f-)
!> carries the variation across, with n the gradient of the event function that switched: the
!> penetration d = s_c u_i - g_c (an onset, and a release of an undamped contact) or, for a
!> damped contact's release, lambda = k d + c d' (the damper never pulls: the force reaches 0
!> first). Without a damper the force k d is continuous at d = 0, f+ = f- and S = I; with one,
!> the onset makes the force jump by c d' and S carries the transversality factor n' f- = d'.
!> The Jacobian of the flow from t_a to t_b is then
!>    Phi = E_N S_{N-1} E_{N-1} ... S_1 E_1,   E_k = e^{A_{m_k} tau_k}.
!> A grazing switch (n' f- = 0) with a jump of f is singular: S is left out there (its factor
!> is unbounded; the map is not differentiable).
module gapbeam_transition
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t, load_factor
   use gapbeam_lapack, only: dgesv, dpotrf, dpotrs
   implicit none
   private
   public :: linear_parts_t, switch_log_t, setup_linear_parts, mass_dofs, saltation, &
      flow_jacobian, log_segment, reduce_state, expand_state

   !> The structure condensed onto its dofs with mass, as the flow of x = (u_r, v_r) needs it.
   type :: linear_parts_t
      integer :: n = 0                           !! all dofs
      integer :: nr = 0                          !! dofs with mass
      integer :: ns = 0                          !! massless dofs
      integer :: nc = 0                          !! one-sided contacts
      integer, allocatable :: ir(:), is(:)       !! global indices of the two groups
      integer, allocatable :: cpos(:)            !! reduced index of each contact's dof
      real(dp), allocatable :: t(:, :)           !! (ns, nr) u_s = T u_r
      real(dp), allocatable :: mk(:, :)          !! M_r^-1 K_r [1/s^2]
      real(dp), allocatable :: mc(:, :)          !! M_r^-1 C_r [1/s]
      real(dp), allocatable :: mq(:)             !! M_r^-1 q_r [-]
      real(dp), allocatable :: me(:, :)          !! (nr, nc) M_r^-1 e_c [1/kg ...]
      real(dp), allocatable :: kr(:, :)          !! condensed stiffness K_r
      real(dp), allocatable :: mr(:, :)          !! M_rr
   end type linear_parts_t

   !> The linear segments of one advance: their instants, configurations and end states.
   type :: switch_log_t
      integer :: n = 0                                 !! segments
      real(dp), allocatable :: t(:)                    !! (n+1) segment k is [t(k), t(k+1)] [s]
      integer(int64), allocatable :: mask(:)           !! (n) active contacts (bit c-1)
      real(dp), allocatable :: x(:, :)                 !! (2 nr, n) reduced state at t(k+1)
   end type switch_log_t

contains

   !> Global indices of the dofs with mass (the coordinates u_r of x = (u_r, v_r)).
   pure function mass_dofs(model) result(ir)
      type(model_t), intent(in) :: model   !! model
      integer, allocatable :: ir(:)
      integer :: i
      ir = pack([(i, i = 1, model%n)], [(model%sys%m(i, i) /= 0.0_dp, i = 1, model%n)])
   end function mass_dofs

   !> Reduced state (u_r, v_r) of a full (u, v).
   pure function reduce_state(lp, u, v) result(x)
      type(linear_parts_t), intent(in) :: lp   !! condensed structure
      real(dp), intent(in) :: u(:), v(:)       !! full displacement, velocity
      real(dp) :: x(2 * lp%nr)
      x(1:lp%nr) = u(lp%ir);  x(lp%nr + 1:) = v(lp%ir)
   end function reduce_state

   !> Full (u, v) of a reduced state (massless dofs by condensation).
   pure subroutine expand_state(lp, x, u, v)
      type(linear_parts_t), intent(in) :: lp   !! condensed structure
      real(dp), intent(in) :: x(:)             !! reduced state
      real(dp), intent(out) :: u(:), v(:)      !! full displacement, velocity
      u(lp%ir) = x(1:lp%nr);  v(lp%ir) = x(lp%nr + 1:)
      if (lp%ns > 0) then
         u(lp%is) = matmul(lp%t, x(1:lp%nr));  v(lp%is) = matmul(lp%t, x(lp%nr + 1:))
      end if
   end subroutine expand_state

   !> Condense the massless dofs and form M_r^-1 K_r, M_r^-1 C_r, M_r^-1 q_r, M_r^-1 e_c.
   subroutine setup_linear_parts(model, lp, err)
      type(model_t), intent(in) :: model               !! model
      type(linear_parts_t), intent(out) :: lp          !! condensed structure
      type(error_t), allocatable, intent(out) :: err   !! singular mass or stiffness block
      real(dp), allocatable :: kss(:, :), rhs(:, :), cr(:, :), mfac(:, :), b(:, :)
      integer :: i, j, n, nr, ns, info, c
      n = model%n
      lp%n = n
      lp%ir = mass_dofs(model)
      lp%is = pack([(i, i = 1, n)], [(model%sys%m(i, i) == 0.0_dp, i = 1, n)])
      nr = size(lp%ir);  ns = size(lp%is)
      lp%nr = nr;  lp%ns = ns;  lp%nc = model%n_contacts
      if (nr == 0) then
         call fatal_error(err, 'gapbeam_transition: the model has no mass')
         return
      end if
      allocate(lp%t(ns, nr))
      if (ns > 0) then
         kss = model%sys%k(lp%is, lp%is)
         rhs = -model%sys%k(lp%is, lp%ir)
         call dpotrf('U', ns, kss, ns, info)
         if (info == 0) call dpotrs('U', ns, nr, kss, ns, rhs, ns, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_transition: the stiffness of the massless dofs is ' &
               // 'singular (dpotrf/dpotrs info=' // str(info) // ')')
            return
         end if
         lp%t = rhs
      end if
      lp%mr = model%sys%m(lp%ir, lp%ir)
      lp%kr = model%sys%k(lp%ir, lp%ir)
      cr = model%c(lp%ir, lp%ir)
      if (ns > 0) then
         lp%kr = lp%kr + matmul(model%sys%k(lp%ir, lp%is), lp%t)
         cr = cr + matmul(model%c(lp%ir, lp%is), lp%t)
      end if
      lp%kr = 0.5_dp * (lp%kr + transpose(lp%kr))
      cr = 0.5_dp * (cr + transpose(cr))
      mfac = lp%mr
      call dpotrf('U', nr, mfac, nr, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_transition: the mass of the dofs with mass is not ' &
            // 'positive definite (dpotrf info=' // str(info) // ')')
         return
      end if
      allocate(lp%cpos(lp%nc))
      allocate(b(nr, 2 * nr + 1 + lp%nc), source=0.0_dp)
      b(:, 1:nr) = lp%kr
      b(:, nr + 1:2 * nr) = cr
      b(:, 2 * nr + 1) = model%q(lp%ir)
      do c = 1, lp%nc
         lp%cpos(c) = 0
         do j = 1, nr
            if (lp%ir(j) == model%c_dof(c)) lp%cpos(c) = j
         end do
         if (lp%cpos(c) == 0) then
            call fatal_error(err, 'gapbeam_transition: contact ' // str(c) // ' acts on a ' &
               // 'massless dof (global dof ' // str(model%c_dof(c)) // ')')
            return
         end if
         b(lp%cpos(c), 2 * nr + 1 + c) = 1.0_dp
      end do
      call dpotrs('U', nr, size(b, 2), mfac, nr, b, nr, info)
      lp%mk = b(:, 1:nr)
      lp%mc = b(:, nr + 1:2 * nr)
      lp%mq = b(:, 2 * nr + 1)
      lp%me = b(:, 2 * nr + 2:)
   end subroutine setup_linear_parts

   !> A_m of the configuration `mask` (see the module header).
   pure function state_matrix(lp, model, mask) result(a)
      type(linear_parts_t), intent(in) :: lp     !! condensed structure
      type(model_t), intent(in) :: model         !! model (contact laws)
      integer(int64), intent(in) :: mask         !! active contacts (bit c-1)
      real(dp) :: a(2 * lp%nr, 2 * lp%nr)
      integer :: nr, i, c, j
      nr = lp%nr
      a = 0.0_dp
      do i = 1, nr
         a(i, nr + i) = 1.0_dp
      end do
      a(nr + 1:, 1:nr) = -lp%mk
      a(nr + 1:, nr + 1:) = -lp%mc
      do c = 1, lp%nc
         if (.not. btest(mask, c - 1)) cycle
         j = lp%cpos(c)
         a(nr + 1:, j) = a(nr + 1:, j) - model%c_k(c) * lp%me(:, c)
         a(nr + 1:, nr + j) = a(nr + 1:, nr + j) - model%c_c(c) * lp%me(:, c)
      end do
   end function state_matrix

   !> The vector field x' of configuration `mask` at (x, t), forcing and gap loads included.
   pure function vector_field(lp, model, mask, x, t) result(f)
      type(linear_parts_t), intent(in) :: lp     !! condensed structure
      type(model_t), intent(in) :: model         !! model
      integer(int64), intent(in) :: mask         !! active contacts (bit c-1)
      real(dp), intent(in) :: x(:)               !! reduced state (u_r, v_r)
      real(dp), intent(in) :: t                  !! time [s]
      real(dp) :: f(2 * lp%nr)
      integer :: nr, c
      nr = lp%nr
      f = matmul(state_matrix(lp, model, mask), x)
      f(nr + 1:) = f(nr + 1:) + load_factor(model, t) * lp%mq
      do c = 1, lp%nc
         if (btest(mask, c - 1)) f(nr + 1:) = f(nr + 1:) + model%c_sign(c) * model%c_k(c) &
            * model%c_gap(c) * lp%me(:, c)
      end do
   end function vector_field

   !> Saltation matrix of the switch from m_old to m_new at (x, t) (one contact at a time,
   !> through the intermediate configurations when several switch together).
   pure function saltation(lp, model, m_old, m_new, x, t) result(s)
      type(linear_parts_t), intent(in) :: lp       !! condensed structure
      type(model_t), intent(in) :: model           !! model
      integer(int64), intent(in) :: m_old, m_new   !! activity before, after
      real(dp), intent(in) :: x(:)                 !! reduced state at the switch
      real(dp), intent(in) :: t                    !! instant [s]
      real(dp) :: s(2 * lp%nr, 2 * lp%nr)
      real(dp) :: fm(2 * lp%nr), fp(2 * lp%nr), nv(2 * lp%nr), den, jump
      integer(int64) :: m0, m1
      integer :: c, i, nr
      nr = lp%nr
      s = 0.0_dp
      do i = 1, 2 * nr
         s(i, i) = 1.0_dp
      end do
      m0 = m_old
      do c = 1, lp%nc
         if (btest(m0, c - 1) .eqv. btest(m_new, c - 1)) cycle
         if (btest(m_new, c - 1)) then
            m1 = ibset(m0, c - 1)
         else
            m1 = ibclr(m0, c - 1)
         end if
         fm = vector_field(lp, model, m0, x, t)
         fp = vector_field(lp, model, m1, x, t)
         jump = maxval(abs(fp - fm))
         if (jump > 1.0e-14_dp * maxval(abs(fm))) then
            nv = 0.0_dp
            i = lp%cpos(c)
            if (.not. btest(m_new, c - 1) .and. model%c_c(c) > 0.0_dp) then
               nv(i) = model%c_sign(c) * model%c_k(c)        ! release of a damped contact
               nv(nr + i) = model%c_sign(c) * model%c_c(c)
            else
               nv(i) = model%c_sign(c)                       ! d = s u - g
            end if
            den = dot_product(nv, fm)
            if (abs(den) > 0.0_dp) then
               s = s + matmul(reshape(fp - fm, [2 * nr, 1]), &
                              reshape(matmul(nv, s) / den, [1, 2 * nr]))
            end if
         end if
         m0 = m1
      end do
   end function saltation

   !> Matrix exponential e^{A tau}: scaling and squaring with the [13/13] Pade approximant
   !> (Higham, SIAM J. Matrix Anal. Appl. 26, 2005).
   subroutine expm(a, tau, e, err)
      real(dp), intent(in) :: a(:, :)                   !! square matrix
      real(dp), intent(in) :: tau                       !! multiplier of a
      real(dp), intent(out) :: e(:, :)                  !! e^{a tau}
      type(error_t), allocatable, intent(inout) :: err  !! singular Pade denominator
      real(dp), parameter :: b(0:13) = [64764752532480000.0_dp, 32382376266240000.0_dp, &
         7771770303897600.0_dp, 1187353796428800.0_dp, 129060195264000.0_dp, &
         10559470521600.0_dp, 670442572800.0_dp, 33522128640.0_dp, 1323241920.0_dp, &
         40840800.0_dp, 960960.0_dp, 16380.0_dp, 182.0_dp, 1.0_dp]
      real(dp), parameter :: theta13 = 5.371920351148152_dp
      real(dp), allocatable :: x(:, :), x2(:, :), x4(:, :), x6(:, :), u(:, :), v(:, :), &
         eye(:, :), p(:, :), q(:, :), d(:)
      integer, allocatable :: ipiv(:)
      real(dp) :: nrm
      integer :: n, i, s, info
      n = size(a, 1)
      x = a * tau
      call balance(x, d)
      nrm = maxval(sum(abs(x), dim=1))
      s = 0
      if (nrm > theta13) s = max(0, ceiling(log(nrm / theta13) / log(2.0_dp)))
      x = x / 2.0_dp**s
      allocate(eye(n, n), source=0.0_dp)
      do i = 1, n
         eye(i, i) = 1.0_dp
      end do
      x2 = matmul(x, x);  x4 = matmul(x2, x2);  x6 = matmul(x4, x2)
      u = matmul(x6, b(13) * x6 + b(11) * x4 + b(9) * x2) + b(7) * x6 + b(5) * x4 &
          + b(3) * x2 + b(1) * eye
      u = matmul(x, u)
      v = matmul(x6, b(12) * x6 + b(10) * x4 + b(8) * x2) + b(6) * x6 + b(4) * x4 &
          + b(2) * x2 + b(0) * eye
      p = v + u;  q = v - u
      allocate(ipiv(n))
      call dgesv(n, n, q, n, ipiv, p, n, info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_transition:expm: singular Pade denominator (dgesv ' &
            // 'info=' // str(info) // ')')
         e = eye
         return
      end if
      do i = 1, s
         p = matmul(p, p)
      end do
      do i = 1, n
         e(i, :) = p(i, :) * d(i) / d
      end do
   end subroutine expm

   !> Diagonal balancing (Parlett and Reinsch, powers of 2, no permutation): x <- D^-1 x D with
   !> row and column norms of each index about equal. The state matrices mix displacements and
   !> velocities (entries of M^-1 K up to omega_max^2 against 1), and the norm of the balanced
   !> one, about omega_max, sets the number of squarings and the error of e^{x}.
   pure subroutine balance(x, d)
      real(dp), intent(inout) :: x(:, :)             !! matrix, balanced on return
      real(dp), allocatable, intent(out) :: d(:)     !! the scaling D
      real(dp) :: c, r, f, g, sm
      integer :: i, n, sweep
      logical :: done
      n = size(x, 1)
      allocate(d(n), source=1.0_dp)
      do sweep = 1, 100
         done = .true.
         do i = 1, n
            c = sum(abs(x(:, i))) - abs(x(i, i))
            r = sum(abs(x(i, :))) - abs(x(i, i))
            if (c == 0.0_dp .or. r == 0.0_dp) cycle
            g = r / 2.0_dp;  f = 1.0_dp;  sm = c + r
            do while (c < g)
               f = f * 2.0_dp;  c = c * 4.0_dp
            end do
            g = r * 2.0_dp
            do while (c >= g)
               f = f / 2.0_dp;  c = c / 4.0_dp
            end do
            if ((c + r) / f < 0.95_dp * sm) then
               done = .false.
               d(i) = d(i) * f
               x(i, :) = x(i, :) / f
               x(:, i) = x(:, i) * f
            end if
         end do
         if (done) exit
      end do
   end subroutine balance

   !> Append the piece [ta, tb] of configuration `mask` with end state xb to a log (a piece
   !> of the same configuration as the last segment lengthens it).
   pure subroutine log_segment(log, ta, tb, mask, xb)
      type(switch_log_t), intent(inout) :: log    !! log
      real(dp), intent(in) :: ta, tb              !! piece [s]
      integer(int64), intent(in) :: mask          !! its configuration
      real(dp), intent(in) :: xb(:)               !! reduced state at tb
      real(dp), allocatable :: t2(:), x2(:, :)
      integer(int64), allocatable :: m2(:)
      integer :: n
      if (log%n == 0) then
         if (allocated(log%t)) deallocate(log%t, log%mask, log%x)
         allocate(log%t(9), log%mask(8), log%x(size(xb), 8))
         log%t(1) = ta
      else if (log%mask(log%n) == mask) then
         log%t(log%n + 1) = tb
         log%x(:, log%n) = xb
         return
      end if
      n = log%n + 1
      if (n > size(log%mask)) then
         allocate(t2(2 * n + 1), m2(2 * n), x2(size(xb), 2 * n))
         t2(1:n) = log%t(1:n);  m2(1:n - 1) = log%mask(1:n - 1);  x2(:, 1:n - 1) = log%x(:, 1:n - 1)
         call move_alloc(t2, log%t);  call move_alloc(m2, log%mask);  call move_alloc(x2, log%x)
      end if
      log%n = n
      log%mask(n) = mask
      log%t(n + 1) = tb
      log%x(:, n) = xb
   end subroutine log_segment

   !> Jacobian of the flow over the logged segments: Phi = E_N S_{N-1} ... S_1 E_1 (identity
   !> for an empty log).
   subroutine flow_jacobian(lp, model, log, jac, err)
      type(linear_parts_t), intent(in) :: lp            !! condensed structure
      type(model_t), intent(in) :: model                !! model
      type(switch_log_t), intent(in) :: log             !! segments of the advance
      real(dp), allocatable, intent(out) :: jac(:, :)   !! d x(t_b) / d x(t_a)
      type(error_t), allocatable, intent(out) :: err    !! expm failure
      real(dp), allocatable :: e(:, :)
      integer :: k, nn
      nn = 2 * lp%nr
      allocate(jac(nn, nn), e(nn, nn), source=0.0_dp)
      do k = 1, nn
         jac(k, k) = 1.0_dp
      end do
      do k = 1, log%n
         if (log%t(k + 1) > log%t(k)) then
            call expm(state_matrix(lp, model, log%mask(k)), log%t(k + 1) - log%t(k), e, err)
            if (allocated(err)) return
            jac = matmul(e, jac)
         end if
         if (k < log%n) then
            if (log%mask(k + 1) /= log%mask(k)) jac = matmul(saltation(lp, model, &
               log%mask(k), log%mask(k + 1), log%x(:, k), log%t(k + 1)), jac)
         end if
      end do
   end subroutine flow_jacobian
end module gapbeam_transition
