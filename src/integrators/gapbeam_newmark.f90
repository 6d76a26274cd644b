!> The implicit Newmark gap solver: one step of the (delta, alpha) scheme with the stop forces
!> as a pseudo-load (paper eqs. 4 and 7), their exact condensed solution or the paper's fixed
!> point, and the half-step residual of the paper's section 4.2.
!>
!> Per step size dt the effective stiffness Kbar = K + a0 M + a1 C (a0 = 1/(alpha dt^2),
!> a1 = delta/(alpha dt)) is factorized once and kept in a `step_op_t` together with everything
!> the step needs: the contact-free predictor y* = Kbar^-1 Pbar and the influence of the
!> contact forces G = Kbar^-1 E on the displacements, so that y = y* - G F. With C = beta M +
!> gamma K, Kbar^-1 Pbar reduces to one product with Kbar^-1 M (dense path) or one banded
!> solve (banded path) per step.
module gapbeam_newmark
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dpotrf, dpotrs, dpbtrf, dpbtrs
   use gapbeam_linalg, only: dense_matvec, band_matvec
   use gapbeam_assembly, only: dense_to_band
   use gapbeam_problem, only: problem_t
   use gapbeam_contact, only: contact_force, solve_scalar_contact
   use gapbeam_stepper, only: stepper_t
   use gapbeam_settings, only: solver_settings_t
   implicit none
   private
   public :: newmark_stepper_t, step_op_t, build_step_op, newmark_predict, condensed_contact, &
      fixed_point_step, &
      newmark_correct, half_step_ratio, state_load, condensed_step

   !> Everything one step size needs, factorized once.
   type :: step_op_t
      logical :: ready = .false.                 !! built
      logical :: dense = .true.                  !! dense (small) or banded path
      real(dp) :: dt = 0.0_dp                    !! step size [s]
      real(dp) :: a0, a1, a2, a3, a4, a5         !! Newmark constants
      real(dp) :: cw, ch                         !! y* = A_M (hM + cw hC) + ch hC + s gp
      real(dp), allocatable :: am(:, :)          !! dense: Kbar^-1 M
      real(dp), allocatable :: fac(:, :)         !! dense Cholesky factor of Kbar (upper)
      real(dp), allocatable :: fab(:, :)         !! banded Cholesky factor of Kbar (upper)
      real(dp), allocatable :: gp(:)             !! Kbar^-1 q
      real(dp), allocatable :: g(:, :)           !! (n, n_slots) Kbar^-1 E
      real(dp), allocatable :: h(:, :)           !! (n_slots, n_slots) E' Kbar^-1 E
   end type step_op_t

   !> The Newmark (delta, alpha) method as a stepper: condensed or fixed-point stop forces.
   type, extends(stepper_t) :: newmark_stepper_t
      type(step_op_t) :: op                      !! factorized operator for dt
      logical :: fixed_point = .false.           !! the paper's fixed point (else condensed)
      real(dp) :: fp_tolerance = 1.0e-6_dp       !! fixed point: relative change
      integer :: fp_max_iterations = 50          !! fixed point: iteration limit
      real(dp), allocatable :: hm(:), hc(:), rhs(:), y(:)   !! workspaces
   contains
      procedure :: prepare => newmark_prepare
      procedure :: step => newmark_stepper_step
   end type newmark_stepper_t

contains

   !> Factorize Kbar for dt (dense below 61 dofs unless the deck says otherwise).
   subroutine newmark_prepare(self, prob, cfg, dt, err)
      class(newmark_stepper_t), intent(inout) :: self  !! stepper
      type(problem_t), intent(in) :: prob              !! model
      type(solver_settings_t), intent(in) :: cfg       !! settings
      real(dp), intent(in) :: dt                       !! step [s]
      type(error_t), allocatable, intent(out) :: err   !! factorization failure
      logical :: dense
      select case (cfg%linear_solver)
      case ('dense');  dense = .true.
      case ('banded'); dense = .false.
      case default;    dense = prob%n <= 60
      end select
      call build_step_op(prob, cfg%newmark_delta, cfg%newmark_alpha, dt, dense, self%op, err)
      if (allocated(err)) return
      self%dt = dt
      self%fixed_point = cfg%stop_solution == 'fixed_point'
      self%fp_tolerance = cfg%fp_tolerance
      self%fp_max_iterations = cfg%fp_max_iterations
      if (.not. allocated(self%hm)) allocate(self%hm(prob%n), self%hc(prob%n), &
                                             self%rhs(prob%n), self%y(prob%n))
      self%ready = .true.
   end subroutine newmark_prepare

   !> One Newmark step (see stepper_t%step).
   subroutine newmark_stepper_step(self, prob, t0, u, v, a, f, f_prev, dt_prev, u1, v1, a1, &
                                   f1, ok, ratio, open_contact)
      class(newmark_stepper_t), intent(inout) :: self
      type(problem_t), intent(in) :: prob
      real(dp), intent(in) :: t0, dt_prev
      real(dp), intent(in), contiguous :: u(:), v(:), a(:), f(:), f_prev(:)
      real(dp), intent(out), contiguous :: u1(:), v1(:), a1(:), f1(:)
      logical, intent(out) :: ok
      real(dp), intent(out) :: ratio
      integer, intent(in) :: open_contact
      real(dp) :: s1
      integer :: it
      s1 = state_load(prob, t0 + self%dt)
      ratio = -1.0_dp
      ok = .true.
      if (self%fixed_point .and. prob%n_contacts > 0) then
         ! first guess: linear extrapolation of the last two steps (paper 4.1)
         f1 = max(0.0_dp, f + (f - f_prev) * self%dt / dt_prev)
         call fixed_point_step(prob, self%op, s1, u, v, a, self%fp_tolerance, &
            self%fp_max_iterations, f1, u1, v1, a1, it, ok, self%hm, self%hc, self%rhs, self%y, &
            open_contact)
         self%iterations = self%iterations + it
      else
         call condensed_step(prob, self%op, s1, u, v, a, f, u1, v1, a1, f1, self%hm, self%hc, &
                             open_contact)
      end if
   end subroutine newmark_stepper_step

   !> Factorize Kbar for a step size and precompute the predictor and contact influences.
   subroutine build_step_op(prob, delta, alpha, dt, dense, op, err)
      type(problem_t), intent(in) :: prob             !! model
      real(dp), intent(in) :: delta                   !! Newmark delta [-]
      real(dp), intent(in) :: alpha                   !! Newmark alpha [-]
      real(dp), intent(in) :: dt                      !! step [s]
      logical, intent(in) :: dense                    !! dense path (else banded)
      type(step_op_t), intent(inout) :: op            !! result (arrays reused when sized)
      type(error_t), allocatable, intent(out) :: err  !! factorization failure
      integer :: n, ns, info, j, kd
      real(dp) :: c0, c1
      real(dp), allocatable :: kbar(:, :), rhs(:, :)

      n = prob%n;  ns = prob%n_slots;  kd = prob%sys%kd
      op%dense = dense
      op%dt = dt
      op%a0 = 1.0_dp / (alpha * dt**2)
      op%a1 = delta / (alpha * dt)
      op%a2 = 1.0_dp / (alpha * dt)
      op%a3 = 0.5_dp / alpha - 1.0_dp
      op%a4 = delta / alpha - 1.0_dp
      op%a5 = dt * (0.5_dp * delta / alpha - 1.0_dp)
      c1 = 1.0_dp + op%a1 * prob%gamma
      c0 = op%a0 + op%a1 * prob%beta
      op%cw = prob%beta - prob%gamma * c0 / c1
      op%ch = prob%gamma / c1
      kbar = c1 * prob%sys%k + c0 * prob%sys%m
      allocate(rhs(n, 1 + ns))
      rhs(:, 1) = prob%q
      rhs(:, 2:) = 0.0_dp
      do j = 1, ns
         rhs(prob%slot_dof(j), 1 + j) = 1.0_dp
      end do
      if (dense) then
         call dpotrf('U', n, kbar, n, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_newmark:build_step_op: effective stiffness not ' &
               // 'positive definite (dpotrf info=' // str(info) // ', dt = ' // str(dt) // ' s)')
            return
         end if
         op%fac = kbar
         call dpotrs('U', n, 1 + ns, op%fac, n, rhs, n, info)
         op%am = prob%sys%m
         call dpotrs('U', n, n, op%fac, n, op%am, n, info)
         if (allocated(op%fab)) deallocate(op%fab)
      else
         call dense_to_band(kbar, kd, op%fab)
         call dpbtrf('U', n, kd, op%fab, kd + 1, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_newmark:build_step_op: effective stiffness not ' &
               // 'positive definite (dpbtrf info=' // str(info) // ', dt = ' // str(dt) // ' s)')
            return
         end if
         call dpbtrs('U', n, kd, 1 + ns, op%fab, kd + 1, rhs, n, info)
         if (allocated(op%am)) deallocate(op%am)
         if (allocated(op%fac)) deallocate(op%fac)
      end if
      op%gp = rhs(:, 1)
      op%g = rhs(:, 2:)
      if (allocated(op%h)) deallocate(op%h)
      allocate(op%h(ns, ns))
      do j = 1, ns
         op%h(j, :) = op%g(prob%slot_dof(j), :)
      end do
      op%ready = .true.
   end subroutine build_step_op

   !> Load factor s(t) with P(t) = s(t) q: s = (A_pp/2) Omega^2 sin(Omega t) [m/s^2].
   pure real(dp) function state_load(prob, t)
      type(problem_t), intent(in) :: prob   !! model
      real(dp), intent(in) :: t             !! time [s]
      state_load = prob%half_amplitude * prob%omega**2 * sin(prob%omega * t)
   end function state_load

   !> Contact-free predictor y* = Kbar^-1 Pbar at the end of the step; hm, hc are kept for
   !> the correction.
   pure subroutine newmark_predict(prob, op, s1, u, v, a, hm, hc, ystar, work)
      type(problem_t), intent(in) :: prob     !! model
      type(step_op_t), intent(in) :: op       !! step operator
      real(dp), intent(in) :: s1              !! load factor at the end of the step
      real(dp), intent(in) :: u(:), v(:), a(:) !! state at the start
      real(dp), intent(out) :: hm(:), hc(:)   !! a0 u + a2 v + a3 a, a1 u + a4 v + a5 a
      real(dp), intent(out) :: ystar(:)       !! predictor [m]
      real(dp), intent(inout) :: work(:)      !! workspace (n)
      integer :: n
      n = prob%n
      hm = op%a0 * u + op%a2 * v + op%a3 * a
      hc = op%a1 * u + op%a4 * v + op%a5 * a
      work = hm + op%cw * hc
      if (op%dense) then
         call dense_matvec(n, op%am, work, ystar)
      else
         if (prob%sys%m_diagonal) then
            ystar = prob%sys%m_band(prob%sys%kd + 1, :) * work
         else
            call band_matvec(n, prob%sys%kd, prob%sys%m_band, work, ystar)
         end if
         call band_solve(n, prob%sys%kd, op%fab, ystar)
      end if
      ystar = ystar + op%ch * hc + s1 * op%gp
   end subroutine newmark_predict

   !> Banded Cholesky solve written out (LAPACK's dpbtrs is not pure).
   pure subroutine band_solve(n, kd, fab, b)
      integer, intent(in) :: n, kd
      real(dp), intent(in) :: fab(kd + 1, n)   ! upper factor U, A = U'U
      real(dp), intent(inout) :: b(n)
      integer :: i, j
      real(dp) :: s
      ! U' z = b
      do j = 1, n
         s = b(j)
         do i = max(1, j - kd), j - 1
            s = s - fab(kd + 1 + i - j, j) * b(i)
         end do
         b(j) = s / fab(kd + 1, j)
      end do
      ! U x = z
      do j = n, 1, -1
         b(j) = b(j) / fab(kd + 1, j)
         do i = max(1, j - kd), j - 1
            b(i) = b(i) - fab(kd + 1 + i - j, j) * b(j)
         end do
      end do
   end subroutine band_solve

   !> One whole condensed step (predictor, exact contact forces, correction) fused for speed:
   !> the hot path of every transient run. Same arithmetic as newmark_predict +
   !> condensed_contact + newmark_correct, with explicit-shape arrays and no temporaries.
   pure subroutine condensed_step(prob, op, s1, u, v, a, f, u1, v1, a1, f1, hm, hc, open_contact)
      type(problem_t), intent(in) :: prob              !! model
      type(step_op_t), intent(in) :: op                !! step operator (dense or banded)
      real(dp), intent(in) :: s1                       !! load factor at the end of the step
      real(dp), intent(in) :: u(prob%n), v(prob%n), a(prob%n)    !! state at the start
      real(dp), intent(in) :: f(prob%n_contacts)       !! contact forces at the start [N]
      real(dp), intent(out) :: u1(prob%n), v1(prob%n), a1(prob%n) !! state at the end
      real(dp), intent(out) :: f1(prob%n_contacts)     !! contact forces at the end [N]
      real(dp), intent(out) :: hm(prob%n), hc(prob%n)  !! workspaces
      integer, intent(in), optional :: open_contact    !! contact held open (a located onset
                                                       !! ends this sub-step: left limit)
      integer :: n, i, j, c, sweeps
      real(dp) :: xj, ds, vs, fc
      logical :: hold
      n = prob%n
      hold = .false.
      if (present(open_contact)) hold = open_contact > 0
      if (op%dense .and. prob%n_contacts == 1 .and. .not. hold) then
         call dense_single_contact_step(n, op%am, op%gp, op%g(:, 1), op%h(1, 1), op%a0, op%a1, &
            op%a2, op%a3, op%a4, op%a5, op%cw, op%ch, s1, prob%c_dof(1), prob%c_sign(1), &
            prob%c_gap(1), prob%c_law(1), prob%c_k(1), prob%c_c(1), prob%c_p(1), u, v, a, &
            u1, v1, a1, f1(1), hm, hc)
         return
      end if
      if (op%dense) then
         do i = 1, n
            hm(i) = op%a0 * u(i) + op%a2 * v(i) + op%a3 * a(i)
            hc(i) = op%a1 * u(i) + op%a4 * v(i) + op%a5 * a(i)
            u1(i) = op%ch * hc(i) + s1 * op%gp(i)
         end do
         do j = 1, n
            xj = hm(j) + op%cw * hc(j)
            do i = 1, n
               u1(i) = u1(i) + op%am(i, j) * xj
            end do
         end do
      else
         call newmark_predict(prob, op, s1, u, v, a, hm, hc, u1, a1)
      end if
      if (prob%n_contacts == 1) then
         i = prob%c_dof(1)
         ds = prob%c_sign(1) * u1(i) - prob%c_gap(1)
         if (hold) ds = 0.0_dp
         if (ds > 0.0_dp) then
            vs = prob%c_sign(1) * (op%a1 * u1(i) - hc(i))
            fc = solve_scalar_contact(prob%c_law(1), prob%c_k(1), prob%c_c(1), prob%c_p(1), &
                                      ds, vs, op%h(1, 1), op%a1)
         else
            fc = 0.0_dp
         end if
         f1(1) = fc
         if (fc /= 0.0_dp) then
            xj = prob%c_sign(1) * fc
            do i = 1, n
               u1(i) = u1(i) - op%g(i, 1) * xj
            end do
         end if
      else if (prob%n_contacts > 1) then
         f1 = f
         call condensed_contact(prob, op, u, v, a, u1, f1, sweeps)
         if (hold) f1(open_contact) = 0.0_dp   ! approximate when contacts are coupled
         do c = 1, prob%n_contacts
            if (f1(c) /= 0.0_dp) u1 = u1 - op%g(:, prob%c_slot(c)) * (prob%c_sign(c) * f1(c))
         end do
      end if
      do i = 1, n
         v1(i) = op%a1 * u1(i) - hc(i)
         a1(i) = op%a0 * u1(i) - hm(i)
      end do
   end subroutine condensed_step

   !> Kernel of condensed_step for a dense operator and one contact: all data as
   !> explicit-shape arguments so that the compiler keeps it in registers and vectorises.
   pure subroutine dense_single_contact_step(n, am, gp, g, h, a0, a1, a2, a3, a4, a5, cw, ch, &
         s1, dof, sgn, gap, law, k, c, p, u, v, a, u1, v1, acc1, f1, hm, hc)
      integer, intent(in) :: n                        !! dofs
      real(dp), intent(in) :: am(n, n), gp(n), g(n)   !! Kbar^-1 M, Kbar^-1 q, Kbar^-1 e
      real(dp), intent(in) :: h                       !! e' Kbar^-1 e
      real(dp), intent(in) :: a0, a1, a2, a3, a4, a5, cw, ch   !! step constants
      real(dp), intent(in) :: s1                      !! load factor at the end
      integer, intent(in) :: dof                      !! contact dof
      real(dp), intent(in) :: sgn, gap                !! contact direction and gap
      integer, intent(in) :: law                      !! contact law
      real(dp), intent(in) :: k, c, p                 !! law parameters
      real(dp), intent(in) :: u(n), v(n), a(n)        !! state at the start
      real(dp), intent(out) :: u1(n), v1(n), acc1(n)  !! state at the end
      real(dp), intent(out) :: f1                     !! contact force at the end [N]
      real(dp), intent(out) :: hm(n), hc(n)           !! workspaces
      integer :: i, j
      real(dp) :: xj, ds, vs
      do i = 1, n
         hm(i) = a0 * u(i) + a2 * v(i) + a3 * a(i)
         hc(i) = a1 * u(i) + a4 * v(i) + a5 * a(i)
         u1(i) = ch * hc(i) + s1 * gp(i)
      end do
      do j = 1, n
         xj = hm(j) + cw * hc(j)
         do i = 1, n
            u1(i) = u1(i) + am(i, j) * xj
         end do
      end do
      ds = sgn * u1(dof) - gap
      f1 = 0.0_dp
      if (ds > 0.0_dp) then
         vs = sgn * (a1 * u1(dof) - hc(dof))
         f1 = solve_scalar_contact(law, k, c, p, ds, vs, h, a1)
         xj = sgn * f1
         do i = 1, n
            u1(i) = u1(i) - g(i) * xj
         end do
      end if
      do i = 1, n
         v1(i) = a1 * u1(i) - hc(i)
         acc1(i) = a0 * u1(i) - hm(i)
      end do
   end subroutine dense_single_contact_step

   !> Exact contact forces of the step from the predictor (the condensed method).
   !>
   !> One contact: closed form (bilinear) or safeguarded Newton (Hertz) in
   !> `solve_scalar_contact`. Several: projected (non-linear) Gauss-Seidel over the contacts
   !> with that exact scalar solve, which converges because the problem is the minimisation
   !> of a strictly convex function of the forces (H is positive definite).
   pure subroutine condensed_contact(prob, op, u, v, a, ystar, f, sweeps)
      type(problem_t), intent(in) :: prob      !! model
      type(step_op_t), intent(in) :: op        !! step operator
      real(dp), intent(in) :: u(:), v(:), a(:) !! state at the start
      real(dp), intent(in) :: ystar(:)         !! predictor
      real(dp), intent(inout) :: f(:)          !! contact force magnitudes (in: guess) [N]
      integer, intent(out) :: sweeps           !! Gauss-Seidel sweeps used
      integer :: c, o, i, si, so, nc
      real(dp) :: ds, vs, hcc, fold, change, fmax, shift
      nc = prob%n_contacts
      if (nc == 1) then
         i = prob%c_dof(1)
         ds = prob%c_sign(1) * ystar(i) - prob%c_gap(1)
         vs = prob%c_sign(1) * (op%a1 * (ystar(i) - u(i)) - op%a4 * v(i) - op%a5 * a(i))
         f(1) = solve_scalar_contact(prob%c_law(1), prob%c_k(1), prob%c_c(1), prob%c_p(1), &
                                     ds, vs, op%h(1, 1), op%a1)
         sweeps = 1
         return
      end if
      do sweeps = 1, 1000
         change = 0.0_dp;  fmax = 0.0_dp
         do c = 1, nc
            i = prob%c_dof(c);  si = prob%c_slot(c)
            ! displacement shift of dof i from the other contacts' forces
            shift = 0.0_dp
            do o = 1, nc
               if (o == c) cycle
               so = prob%c_slot(o)
               shift = shift + op%h(si, so) * prob%c_sign(o) * f(o)
            end do
            ds = prob%c_sign(c) * (ystar(i) - shift) - prob%c_gap(c)
            vs = prob%c_sign(c) * (op%a1 * (ystar(i) - shift - u(i)) - op%a4 * v(i) &
                 - op%a5 * a(i))
            hcc = op%h(si, si)
            fold = f(c)
            f(c) = solve_scalar_contact(prob%c_law(c), prob%c_k(c), prob%c_c(c), prob%c_p(c), &
                                        ds, vs, hcc, op%a1)
            change = max(change, abs(f(c) - fold))
            fmax = max(fmax, f(c))
         end do
         if (change <= 1.0e-14_dp * fmax .or. fmax == 0.0_dp) exit
      end do
   end subroutine condensed_contact

   !> Correct the predictor with the contact forces: y = y* - G F, then v, a at the end.
   pure subroutine newmark_correct(prob, op, ystar, hm, hc, f, u1, v1, a1)
      type(problem_t), intent(in) :: prob     !! model
      type(step_op_t), intent(in) :: op       !! step operator
      real(dp), intent(in) :: ystar(:)        !! predictor
      real(dp), intent(in) :: hm(:), hc(:)    !! from newmark_predict
      real(dp), intent(in) :: f(:)            !! contact force magnitudes [N]
      real(dp), intent(out) :: u1(:), v1(:), a1(:) !! state at the end
      integer :: c
      u1 = ystar
      do c = 1, prob%n_contacts
         if (f(c) /= 0.0_dp) u1 = u1 - op%g(:, prob%c_slot(c)) * (prob%c_sign(c) * f(c))
      end do
      v1 = op%a1 * u1 - hc
      a1 = op%a0 * u1 - hm
   end subroutine newmark_correct

   !> The paper's fixed point on F_NL: y = Kbar^-1 (Pbar - E F) solved in full each iteration,
   !> F from the stop law at y, until max|dF| <= tol max|F|. Starts from `f` (extrapolated).
   subroutine fixed_point_step(prob, op, s1, u, v, a, tol, max_iter, f, u1, v1, a1, &
                               iterations, converged, hm, hc, rhs, y, open_contact)
      type(problem_t), intent(in) :: prob     !! model
      type(step_op_t), intent(in) :: op       !! step operator
      real(dp), intent(in) :: s1              !! load factor at the end of the step
      real(dp), intent(in) :: u(:), v(:), a(:) !! state at the start
      real(dp), intent(in) :: tol             !! relative change tolerance
      integer, intent(in) :: max_iter         !! iteration limit
      real(dp), intent(inout) :: f(:)         !! in: first guess; out: converged forces [N]
      real(dp), intent(out) :: u1(:), v1(:), a1(:) !! state at the end
      integer, intent(out) :: iterations      !! iterations used
      logical, intent(out) :: converged       !! converged within max_iter
      real(dp), intent(inout) :: hm(:), hc(:), rhs(:), y(:)  !! workspaces (n)
      integer, intent(in), optional :: open_contact   !! contact held open (see condensed_step)
      integer :: n, c, i, info, it, held
      real(dp) :: pbar(size(u)), tmp(size(u)), fnew(size(f)), d, ddot, change, fmax
      n = prob%n
      hm = op%a0 * u + op%a2 * v + op%a3 * a
      hc = op%a1 * u + op%a4 * v + op%a5 * a
      ! Pbar = M (hm + beta hc) + gamma K hc + s q
      tmp = hm + prob%beta * hc
      call dense_or_band(prob%sys%m, prob%sys%m_band, tmp, pbar)
      call dense_or_band(prob%sys%k, prob%sys%k_band, hc, rhs)
      pbar = pbar + prob%gamma * rhs + s1 * prob%q
      held = 0
      if (present(open_contact)) held = open_contact
      if (held > 0) f(held) = 0.0_dp
      converged = .false.
      do it = 1, max_iter
         rhs = pbar
         do c = 1, prob%n_contacts
            i = prob%c_dof(c)
            rhs(i) = rhs(i) - prob%c_sign(c) * f(c)
         end do
         y = rhs
         if (op%dense) then
            call dpotrs('U', n, 1, op%fac, n, y, n, info)
         else
            call dpbtrs('U', n, prob%sys%kd, 1, op%fab, prob%sys%kd + 1, y, n, info)
         end if
         change = 0.0_dp;  fmax = 0.0_dp
         do c = 1, prob%n_contacts
            i = prob%c_dof(c)
            d = prob%c_sign(c) * y(i) - prob%c_gap(c)
            ddot = prob%c_sign(c) * (op%a1 * y(i) - hc(i))
            fnew(c) = contact_force(prob%c_law(c), prob%c_k(c), prob%c_c(c), prob%c_p(c), d, ddot)
            if (c == held) fnew(c) = 0.0_dp
            change = max(change, abs(fnew(c) - f(c)))
            fmax = max(fmax, fnew(c))
         end do
         f = fnew
         iterations = it
         if (change <= tol * fmax .or. (fmax == 0.0_dp .and. change == 0.0_dp)) then
            converged = .true.
            exit
         end if
      end do
      ! the displacements belong to the last solve; recompute them for the final forces
      rhs = pbar
      do c = 1, prob%n_contacts
         i = prob%c_dof(c)
         rhs(i) = rhs(i) - prob%c_sign(c) * f(c)
      end do
      u1 = rhs
      if (op%dense) then
         call dpotrs('U', n, 1, op%fac, n, u1, n, info)
      else
         call dpbtrs('U', n, prob%sys%kd, 1, op%fab, prob%sys%kd + 1, u1, n, info)
      end if
      v1 = op%a1 * u1 - hc
      a1 = op%a0 * u1 - hm
   contains
      subroutine dense_or_band(ad, ab, x, yy)
         real(dp), intent(in) :: ad(:, :), ab(:, :), x(:)
         real(dp), intent(out) :: yy(:)
         if (op%dense) then
            call dense_matvec(n, ad, x, yy)
         else
            call band_matvec(n, prob%sys%kd, ab, x, yy)
         end if
      end subroutine dense_or_band
   end subroutine fixed_point_step

   !> Half-step residual ratio of a step (paper section 4.2).
   !>
   !> At t + dt/2 the state follows from the Newmark formulas over dt/2 with the acceleration
   !> varying linearly in the step, a_m = (a0 + a1)/2:
   !>    u_m = u0 + h v0 + h^2 ((1/2 - alpha) a0 + alpha a_m),
   !>    v_m = v0 + h ((1-delta) a0 + delta a_m)
   !> (h = dt/2). The residual R = M a_m + C v_m + K u_m - P(t+h) - F_NL(u_m, v_m) is compared
   !> dof by dof with tol * max(|P - F_NL|, |K u_m|, |C v_m|, |M a_m|), that scale being
   !> floored at floor * (its largest value over the dofs). Returns max |R_j| / threshold_j
   !> (> 1: reject the step) and the dof where it occurs.
   subroutine half_step_ratio(prob, delta, alpha, tol, floor, t0, dt, u0, v0, a0, a1, &
                              ratio, worst, work)
      type(problem_t), intent(in) :: prob          !! model
      real(dp), intent(in) :: delta, alpha         !! Newmark parameters
      real(dp), intent(in) :: tol                  !! relative tolerance (paper: 0.01)
      real(dp), intent(in) :: floor                !! scale floor relative to the largest
      real(dp), intent(in) :: t0, dt               !! start and size of the step [s]
      real(dp), intent(in) :: u0(:), v0(:), a0(:)  !! state at the start
      real(dp), intent(in) :: a1(:)                !! acceleration at the end
      real(dp), intent(out) :: ratio               !! largest residual / threshold
      integer, intent(out) :: worst                !! dof of the largest ratio
      real(dp), intent(inout) :: work(:, :)        !! (n, 6) workspace
      integer :: n, c, i, j
      real(dp) :: h, s, d, ddot, fc, smax, thr, r
      n = prob%n
      h = 0.5_dp * dt
      associate (am => work(:, 1), um => work(:, 2), vm => work(:, 3), ku => work(:, 4), &
                 cv => work(:, 5), ma => work(:, 6))
         am = 0.5_dp * (a0 + a1)
         um = u0 + h * v0 + h**2 * ((0.5_dp - alpha) * a0 + alpha * am)
         vm = v0 + h * ((1.0_dp - delta) * a0 + delta * am)
         if (n <= 60) then
            call dense_matvec(n, prob%sys%k, um, ku)
            call dense_matvec(n, prob%c, vm, cv)
            call dense_matvec(n, prob%sys%m, am, ma)
         else
            call band_matvec(n, prob%sys%kd, prob%sys%k_band, um, ku)
            call band_matvec(n, prob%sys%kd, prob%sys%k_band, vm, cv)
            call band_matvec(n, prob%sys%kd, prob%sys%m_band, vm, ma)
            cv = prob%gamma * cv + prob%beta * ma
            call band_matvec(n, prob%sys%kd, prob%sys%m_band, am, ma)
         end if
         s = state_load(prob, t0 + h)
         ! am now holds P - F_NL (force on the structure from the stops is -s f e)
         am = s * prob%q
         do c = 1, prob%n_contacts
            i = prob%c_dof(c)
            d = prob%c_sign(c) * um(i) - prob%c_gap(c)
            ddot = prob%c_sign(c) * vm(i)
            fc = contact_force(prob%c_law(c), prob%c_k(c), prob%c_c(c), prob%c_p(c), d, ddot)
            am(i) = am(i) - prob%c_sign(c) * fc
         end do
         smax = 0.0_dp
         do j = 1, n
            um(j) = max(abs(am(j)), abs(ku(j)), abs(cv(j)), abs(ma(j)))
            smax = max(smax, um(j))
         end do
         ratio = 0.0_dp;  worst = 1
         if (smax == 0.0_dp) return
         do j = 1, n
            thr = tol * max(um(j), floor * smax)
            r = abs(ma(j) + cv(j) + ku(j) - am(j)) / thr
            if (r > ratio) then
               ratio = r;  worst = j
            end if
         end do
      end associate
   end subroutine half_step_ratio
end module gapbeam_newmark
