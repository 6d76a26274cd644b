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
!>
!> Modal damping (C = beta M + gamma K + C_m, C_m dense) takes the dense path: Kbar = c1 K + c0 M
!> + a1 C_m, and the predictor gains (1/c1) Kbar^-1 C_m hC (the matrix `ac`); the other steps add
!> the products with C_m where they use C.
module gapbeam_newmark
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dpotrf, dpotrs, dpbtrf, dpbtrs
   use gapbeam_linalg, only: dense_matvec, band_matvec, band_solve, dense_to_band
   use gapbeam_model, only: model_t, load_factor, add_extra_load, has_tube_physics, &
      has_modal_damping
   use gapbeam_state, only: state_t
   use gapbeam_contact_law, only: contact_force, contact_solve, solve_contacts
   use gapbeam_ring_contact, only: solve_mixed_contacts
   use gapbeam_integrator, only: stepper_t
   use gapbeam_settings, only: solver_settings_t
   implicit none
   private
   public :: newmark_stepper_t, use_dense, half_step_ratio, condensed_step

   !> The constants of one Newmark step size.
   type :: newmark_constants_t
      real(dp) :: a0 = 0.0_dp, a1 = 0.0_dp, a2 = 0.0_dp   !! 1/(alpha dt^2), delta/(alpha dt),
      real(dp) :: a3 = 0.0_dp, a4 = 0.0_dp, a5 = 0.0_dp   !! 1/(alpha dt), ... (Bathe's notation)
      real(dp) :: cw = 0.0_dp, ch = 0.0_dp                !! y* = A_M (hM + cw hC) + ch hC + s gp
   end type newmark_constants_t

   !> Everything one step size needs, factorized once.
   type :: step_op_t
      logical :: ready = .false.                 !! built
      logical :: dense = .true.                  !! dense (small) or banded path
      real(dp) :: dt = 0.0_dp                    !! step size [s]
      type(newmark_constants_t) :: c             !! step constants
      real(dp), allocatable :: am(:, :)          !! dense: Kbar^-1 M
      real(dp), allocatable :: kinv(:, :)        !! dense: Kbar^-1 (LAPACK's call overhead
                                                 !! exceeds the work of a solve at this size)
      real(dp), allocatable :: fac(:, :)         !! dense Cholesky factor of Kbar (upper)
      real(dp), allocatable :: fab(:, :)         !! banded Cholesky factor of Kbar (upper)
      real(dp), allocatable :: gp(:)             !! Kbar^-1 q
      real(dp), allocatable :: g(:, :)           !! (n, n_slots) Kbar^-1 E
      real(dp), allocatable :: h(:, :)           !! (n_slots, n_slots) E' Kbar^-1 E
      real(dp), allocatable :: ac(:, :)          !! modal damping: Kbar^-1 C_m / c1
   end type step_op_t

   !> The Newmark (delta, alpha) method as a stepper: condensed or fixed-point stop forces.
   type, extends(stepper_t) :: newmark_stepper_t
      type(step_op_t) :: op                      !! factorized operator for dt
      logical :: fixed_point = .false.           !! the paper's fixed point (else condensed)
      !> solve for the acceleration (free of the cancellation that bounds the accuracy of the
      !> displacement form at small steps); used with error control
      logical :: acceleration_form = .false.
      real(dp) :: delta = 0.5_dp, alpha = 0.25_dp !! Newmark parameters
      real(dp) :: fp_tolerance = 1.0e-6_dp       !! fixed point: relative change
      integer :: fp_max_iterations = 50          !! fixed point: iteration limit
      real(dp), allocatable :: hm(:), hc(:), rhs(:), y(:)   !! workspaces
   contains
      procedure :: prepare => newmark_prepare
      procedure :: step => newmark_stepper_step
      procedure :: local_error => newmark_local_error
   end type newmark_stepper_t

contains

   !> Factorize Kbar for dt (dense below 61 dofs unless the deck says otherwise).
   subroutine newmark_prepare(self, model, cfg, dt, err)
      class(newmark_stepper_t), intent(inout) :: self  !! stepper
      type(model_t), intent(in) :: model               !! model
      type(solver_settings_t), intent(in) :: cfg       !! settings
      real(dp), intent(in) :: dt                       !! step [s]
      type(error_t), allocatable, intent(out) :: err   !! factorization failure
      integer :: i
      ! a conditionally stable member (linear acceleration, Fox-Goodwin, ...) has no stable step
      ! for a dof without mass (omega = infinity); the unconditionally stable ones run it
      if (cfg%newmark_alpha < 0.25_dp * (cfg%newmark_delta + 0.5_dp)**2 - 1.0e-12_dp) then
         do i = 1, model%n
            if (model%sys%m(i, i) > 0.0_dp) cycle
            call fatal_error(err, "method 'newmark' with newmark_alpha = " &
               // str(cfg%newmark_alpha) // ' is only conditionally stable and dof ' // str(i) &
               // " has no mass (no stable step): use newmark_alpha >= (newmark_delta + 1/2)^2/4" &
               // " or &beam rotary_inertia = 'half_element' or 'hrz'")
            return
         end do
      end if
      call build_step_op(model, cfg%newmark_delta, cfg%newmark_alpha, dt, &
                         use_dense(model, cfg%linear_solver), self%op, err)
      if (allocated(err)) return
      self%dt = dt
      self%fixed_point = cfg%stop_solution == 'fixed_point'
      self%fp_tolerance = cfg%fp_tolerance
      self%fp_max_iterations = cfg%fp_max_iterations
      ! models with extra loads or ring contacts always take the acceleration form (the same
      ! scheme; its step carries them)
      self%acceleration_form = cfg%step_control == 'error' .or. has_tube_physics(model)
      self%delta = cfg%newmark_delta;  self%alpha = cfg%newmark_alpha
      if (.not. allocated(self%hm)) allocate(self%hm(model%n), self%hc(model%n), &
                                             self%rhs(model%n), self%y(model%n))
      self%ready = .true.
   end subroutine newmark_prepare

   !> Dense storage for the linear solves? The deck's linear_solver, or 'auto': dense up to 60
   !> dofs (below that the dense product with Kbar^-1 M beats a banded solve). Always with
   !> modal damping: C is dense.
   pure logical function use_dense(model, linear_solver)
      type(model_t), intent(in) :: model               !! model
      character(len=*), intent(in) :: linear_solver    !! 'auto', 'dense' or 'banded'
      use_dense = .true.
      if (has_modal_damping(model)) return
      select case (linear_solver)
      case ('dense');  use_dense = .true.
      case ('banded'); use_dense = .false.
      case default;    use_dense = model%n <= 60
      end select
   end function use_dense

   !> One Newmark step (see stepper_t%step).
   subroutine newmark_stepper_step(self, model, s0, s1, ok, ratio, open_contact)
      class(newmark_stepper_t), intent(inout) :: self  !! stepper
      type(model_t), intent(in) :: model               !! model
      type(state_t), intent(in) :: s0                  !! start
      type(state_t), intent(inout) :: s1               !! end
      logical, intent(out) :: ok                       !! converged
      real(dp), intent(out) :: ratio                   !! no embedded estimate: -1
      integer, intent(in) :: open_contact              !! contact held open (0: none)
      real(dp) :: load
      integer :: it
      load = load_factor(model, s0%t + self%dt)
      s1%t = s0%t + self%dt
      ratio = -1.0_dp
      ok = .true.
      if (self%fixed_point .and. model%n_contacts > 0) then
         ! first guess: linear extrapolation of the last two steps (paper 4.1)
         s1%f = max(0.0_dp, s0%f + (s0%f - s0%f_prev) * self%dt / s0%dt_prev)
         call fixed_point_step(model, self%op, load, s0%u, s0%v, s0%a, self%fp_tolerance, &
            self%fp_max_iterations, s1%f, s1%u, s1%v, s1%a, it, ok, self%hm, self%hc, &
            self%rhs, self%y, open_contact)
         self%iterations = self%iterations + it
      else if (self%acceleration_form) then
         call acceleration_step(model, self%op, self%alpha, self%delta, load, s0, s1, &
                                self%hm, self%hc, self%rhs, self%y, open_contact)
      else
         call condensed_step(model, self%op, load, s0%u, s0%v, s0%a, s0%f, s1%u, s1%v, s1%a, &
                             s1%f, self%hm, self%hc, open_contact)
      end if
   end subroutine newmark_stepper_step

   !> One Newmark step solved for the acceleration, with the exact condensed stop forces:
   !>    u~ = u + h v + (1/2 - alpha) h^2 a,   v~ = v + (1 - delta) h a,
   !>    (M + delta h C + alpha h^2 K) a1 = P1 - C v~ - K u~ - E F,
   !>    u1 = u~ + alpha h^2 a1,   v1 = v~ + delta h a1.
   !> The residual on the right is formed from quantities of the size of the forces, so the
   !> acceleration keeps its relative accuracy at any step (the displacement form loses
   !> eps / (omega h)^2 of it to cancellation: the 1e-6 floor of the trapezoidal rule at T/1e5).
   !> M + delta h C + alpha h^2 K = alpha h^2 Kbar, so the factorisation of Kbar serves, and the
   !> contact compliance is the same H = E' Kbar^-1 E.
   subroutine acceleration_step(model, op, alpha, delta, load, s0, s1, ut, vt, r, w, hold)
      type(model_t), intent(in) :: model       !! model
      type(step_op_t), intent(in) :: op        !! step operator (Kbar factorised)
      real(dp), intent(in) :: alpha, delta     !! Newmark parameters
      real(dp), intent(in) :: load             !! load factor at the end of the step
      type(state_t), intent(in) :: s0          !! start
      type(state_t), intent(inout) :: s1       !! end
      real(dp), intent(inout) :: ut(:), vt(:), r(:), w(:)   !! workspaces (n)
      integer, intent(in) :: hold              !! contact held open (0: none)
      real(dp) :: h, bh2, dstar(model%n_contacts), vstar(model%n_contacts), dstep
      real(dp) :: ys(model%n_slots), vs(model%n_slots), pslot(model%n_slots)
      integer :: n, c, i, j
      n = model%n;  h = op%dt;  bh2 = alpha * h**2
      ut = s0%u + h * s0%v + (0.5_dp - alpha) * h**2 * s0%a
      vt = s0%v + (1.0_dp - delta) * h * s0%a
      ! r = P1 - K (u~ + gamma v~) - beta M v~  (C = beta M + gamma K)
      w = ut + model%gamma * vt
      call sym_matvec(op%dense, model%sys%kd, model%sys%k, model%sys%k_band, w, r)
      call sym_matvec(op%dense, model%sys%kd, model%sys%m, model%sys%m_band, vt, w)
      r = load * model%q - r - model%beta * w
      if (has_modal_damping(model)) then
         call dense_matvec(n, model%c_modal, vt, w)
         r = r - w
      end if
      call add_extra_load(model, s1%t, r)
      call kbar_solve(model, op, r)
      r = r / bh2                                   ! a1 with no contact force
      s1%u = ut + bh2 * r
      s1%v = vt + delta * h * r
      s1%f = 0.0_dp
      if (model%n_rings > 0) then
         ! ring contacts (and any scalar ones): the mixed exact solve in the slots, the regimes
         ! of the step's start held over the step
         ys = s1%u(model%slot_dof);  vs = s1%v(model%slot_dof)
         s1%f = s0%f
         call solve_mixed_contacts(model, op%h, op%c%a1, ys, vs, s0%mode, s0%sigma, s0%anchor, &
                                   hold, s1%f, s1%fn, s1%ft, pslot)
         s1%mode = s0%mode;  s1%sigma = s0%sigma;  s1%anchor = s0%anchor
         do j = 1, model%n_slots
            if (pslot(j) /= 0.0_dp) r = r + op%g(:, j) * (pslot(j) / bh2)
         end do
      else if (model%n_contacts > 0) then
         do c = 1, model%n_contacts
            i = model%c_dof(c)
            dstar(c) = model%c_sign(c) * s1%u(i) - model%c_gap(c)
            vstar(c) = model%c_sign(c) * s1%v(i)
         end do
         if (model%n_contacts == 1 .and. hold == 0) then
            s1%f(1) = contact_solve(model, 1, dstar(1), vstar(1), op%h(1, 1), op%c%a1)
         else
            s1%f = s0%f                                ! first guess of the Gauss-Seidel sweep
            call solve_contacts(model, op%h, 1.0_dp, op%c%a1, dstar, vstar, s1%f, hold)
         end if
         do c = 1, model%n_contacts
            if (s1%f(c) /= 0.0_dp) r = r - op%g(:, model%c_slot(c)) &
                                           * (model%c_sign(c) * s1%f(c) / bh2)
         end do
      end if
      s1%a = r
      ! u1 = u + du, v1 = v + dv summed with compensation: over millions of small steps the
      ! rounding of u + du (eps |u| each) would otherwise bound the accuracy near 1e-8
      if (.not. allocated(s1%cu)) allocate(s1%cu(n), s1%cv(n))
      do i = 1, n
         dstep = h * s0%v(i) + (0.5_dp - alpha) * h**2 * s0%a(i) + bh2 * r(i)
         if (allocated(s0%cu)) dstep = dstep - s0%cu(i)
         s1%u(i) = s0%u(i) + dstep
         s1%cu(i) = (s1%u(i) - s0%u(i)) - dstep
         dstep = (1.0_dp - delta) * h * s0%a(i) + delta * h * r(i)
         if (allocated(s0%cv)) dstep = dstep - s0%cv(i)
         s1%v(i) = s0%v(i) + dstep
         s1%cv(i) = (s1%v(i) - s0%v(i)) - dstep
      end do
   end subroutine acceleration_step

   !> x := Kbar^-1 x with the step operator's factor.
   subroutine kbar_solve(model, op, x)
      type(model_t), intent(in) :: model       !! model (band width)
      type(step_op_t), intent(in) :: op        !! step operator
      real(dp), intent(inout) :: x(:)          !! right-hand side, then solution
      integer :: n, info
      real(dp) :: y(size(x))
      n = model%n
      if (op%dense) then
         y = x
         call dense_matvec(n, op%kinv, y, x)
      else
         call band_solve(n, model%sys%kd, op%fab, x)
      end if
   end subroutine kbar_solve

   !> Local error estimate of the last step (see stepper_t%local_error): the displacement error
   !> (alpha - 1/6) h^2 (a1 - a0) of Zienkiewicz and Xie, the velocity error
   !> (delta - 1/2) h^2 a' + (delta/2 - 1/6) h^3 a'', with a1 - a0 filtered by the step's own
   !> operator, Kbar^-1 M / (alpha h^2) = (M + delta h C + alpha h^2 K)^-1 M: modes the step
   !> resolves (omega h << 1) pass unchanged, modes it does not resolve are damped by
   !> 1 / (alpha (omega h)^2), so that their ringing (bounded, and harmless to the outputs) does
   !> not pass for a large error.
   subroutine newmark_local_error(self, model, s0, s1, fda, ev, coef, has)
      class(newmark_stepper_t), intent(inout) :: self  !! stepper (its operator)
      type(model_t), intent(in) :: model               !! model
      type(state_t), intent(in) :: s0, s1              !! the step
      real(dp), intent(out) :: fda(:)                  !! filtered a1 - a0
      real(dp), intent(out) :: ev(:)                   !! unused
      real(dp), intent(out) :: coef(3)                 !! error coefficients
      logical, intent(out) :: has                      !! an estimate is given
      has = .true.
      self%y = s1%a - s0%a
      if (self%op%dense) then
         call dense_matvec(model%n, self%op%am, self%y, fda)     ! Kbar^-1 M (a1 - a0)
      else
         call sym_matvec(.false., model%sys%kd, model%sys%m, model%sys%m_band, self%y, fda)
         call kbar_solve(model, self%op, fda)
      end if
      fda = fda / (self%alpha * self%dt**2)
      ev = 0.0_dp
      coef = [self%alpha - 1.0_dp / 6.0_dp, self%delta - 0.5_dp, 0.5_dp * self%delta &
              - 1.0_dp / 6.0_dp]
   end subroutine newmark_local_error

   !> Factorize Kbar for a step size and precompute the predictor and contact influences.
   subroutine build_step_op(model, delta, alpha, dt, dense, op, err)
      type(model_t), intent(in) :: model             !! model
      real(dp), intent(in) :: delta                   !! Newmark delta [-]
      real(dp), intent(in) :: alpha                   !! Newmark alpha [-]
      real(dp), intent(in) :: dt                      !! step [s]
      logical, intent(in) :: dense                    !! dense path (else banded)
      type(step_op_t), intent(inout) :: op            !! result (arrays reused when sized)
      type(error_t), allocatable, intent(out) :: err  !! factorization failure
      integer :: n, ns, info, j, kd
      real(dp) :: c0, c1
      real(dp), allocatable :: kbar(:, :), rhs(:, :)

      n = model%n;  ns = model%n_slots;  kd = model%sys%kd
      op%dense = dense
      op%dt = dt
      op%c%a0 = 1.0_dp / (alpha * dt**2)
      op%c%a1 = delta / (alpha * dt)
      op%c%a2 = 1.0_dp / (alpha * dt)
      op%c%a3 = 0.5_dp / alpha - 1.0_dp
      op%c%a4 = delta / alpha - 1.0_dp
      op%c%a5 = dt * (0.5_dp * delta / alpha - 1.0_dp)
      c1 = 1.0_dp + op%c%a1 * model%gamma
      c0 = op%c%a0 + op%c%a1 * model%beta
      op%c%cw = model%beta - model%gamma * c0 / c1
      op%c%ch = model%gamma / c1
      kbar = c1 * model%sys%k + c0 * model%sys%m
      if (has_modal_damping(model)) kbar = kbar + op%c%a1 * model%c_modal
      allocate(rhs(n, 1 + ns))
      rhs(:, 1) = model%q
      rhs(:, 2:) = 0.0_dp
      do j = 1, ns
         rhs(model%slot_dof(j), 1 + j) = 1.0_dp
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
         op%am = model%sys%m
         call dpotrs('U', n, n, op%fac, n, op%am, n, info)
         if (allocated(op%kinv)) deallocate(op%kinv)
         allocate(op%kinv(n, n), source=0.0_dp)
         do j = 1, n
            op%kinv(j, j) = 1.0_dp
         end do
         call dpotrs('U', n, n, op%fac, n, op%kinv, n, info)
         if (allocated(op%fab)) deallocate(op%fab)
         if (allocated(op%ac)) deallocate(op%ac)
         if (has_modal_damping(model)) op%ac = matmul(op%kinv, model%c_modal) / c1
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
         op%h(j, :) = op%g(model%slot_dof(j), :)
      end do
      op%ready = .true.
   end subroutine build_step_op

   !> Contact-free predictor y* = Kbar^-1 Pbar at the end of the step; hm, hc are kept for
   !> the correction.
   pure subroutine newmark_predict(model, op, s1, u, v, a, hm, hc, ystar, work)
      type(model_t), intent(in) :: model     !! model
      type(step_op_t), intent(in) :: op       !! step operator
      real(dp), intent(in) :: s1              !! load factor at the end of the step
      real(dp), intent(in) :: u(:), v(:), a(:) !! state at the start
      real(dp), intent(out) :: hm(:), hc(:)   !! a0 u + a2 v + a3 a, a1 u + a4 v + a5 a
      real(dp), intent(out) :: ystar(:)       !! predictor [m]
      real(dp), intent(inout) :: work(:)      !! workspace (n)
      integer :: n
      n = model%n
      hm = op%c%a0 * u + op%c%a2 * v + op%c%a3 * a
      hc = op%c%a1 * u + op%c%a4 * v + op%c%a5 * a
      work = hm + op%c%cw * hc
      if (op%dense) then
         call dense_matvec(n, op%am, work, ystar)
         if (allocated(op%ac)) then
            call dense_matvec(n, op%ac, hc, work)
            ystar = ystar + work
         end if
      else
         if (model%sys%m_diagonal) then
            ystar = model%sys%m_band(model%sys%kd + 1, :) * work
         else
            call band_matvec(n, model%sys%kd, model%sys%m_band, work, ystar)
         end if
         call band_solve(n, model%sys%kd, op%fab, ystar)
      end if
      ystar = ystar + op%c%ch * hc + s1 * op%gp
   end subroutine newmark_predict



   !> One whole condensed step (predictor, exact contact forces, correction y = y* - G F) fused
   !> for speed: the hot path of every transient run. Same arithmetic as newmark_predict +
   !> condensed_contact + the correction, with explicit-shape arrays and no temporaries.
   pure subroutine condensed_step(model, op, s1, u, v, a, f, u1, v1, a1, f1, hm, hc, open_contact)
      type(model_t), intent(in) :: model              !! model
      type(step_op_t), intent(in) :: op                !! step operator (dense or banded)
      real(dp), intent(in) :: s1                       !! load factor at the end of the step
      real(dp), intent(in) :: u(model%n), v(model%n), a(model%n)    !! state at the start
      real(dp), intent(in) :: f(model%n_contacts)       !! contact forces at the start [N]
      real(dp), intent(out) :: u1(model%n), v1(model%n), a1(model%n) !! state at the end
      real(dp), intent(out) :: f1(model%n_contacts)     !! contact forces at the end [N]
      real(dp), intent(out) :: hm(model%n), hc(model%n)  !! workspaces
      integer, intent(in) :: open_contact              !! contact held open, 0: none (a located
                                                       !! onset ends this sub-step: left limit)
      integer :: n, i, j, c
      real(dp) :: xj, ds, vs, fc
      logical :: hold
      n = model%n
      hold = open_contact > 0
      if (op%dense .and. model%n_contacts == 1 .and. .not. hold .and. .not. allocated(op%ac)) then
         call dense_single_contact_step(n, op%am, op%gp, op%g(:, 1), op%h(1, 1), op%c, s1, &
            model, u, v, a, u1, v1, a1, f1(1), hm, hc)
         return
      end if
      if (op%dense) then
         do i = 1, n
            hm(i) = op%c%a0 * u(i) + op%c%a2 * v(i) + op%c%a3 * a(i)
            hc(i) = op%c%a1 * u(i) + op%c%a4 * v(i) + op%c%a5 * a(i)
            u1(i) = op%c%ch * hc(i) + s1 * op%gp(i)
         end do
         do j = 1, n
            xj = hm(j) + op%c%cw * hc(j)
            do i = 1, n
               u1(i) = u1(i) + op%am(i, j) * xj
            end do
         end do
         if (allocated(op%ac)) then
            do j = 1, n
               do i = 1, n
                  u1(i) = u1(i) + op%ac(i, j) * hc(j)
               end do
            end do
         end if
      else
         call newmark_predict(model, op, s1, u, v, a, hm, hc, u1, a1)
      end if
      if (model%n_contacts == 1) then
         i = model%c_dof(1)
         ds = model%c_sign(1) * u1(i) - model%c_gap(1)
         if (hold) ds = 0.0_dp
         if (ds > 0.0_dp) then
            vs = model%c_sign(1) * (op%c%a1 * u1(i) - hc(i))
            fc = contact_solve(model, 1, ds, vs, op%h(1, 1), op%c%a1)
         else
            fc = 0.0_dp
         end if
         f1(1) = fc
         if (fc /= 0.0_dp) then
            xj = model%c_sign(1) * fc
            do i = 1, n
               u1(i) = u1(i) - op%g(i, 1) * xj
            end do
         end if
      else if (model%n_contacts > 1) then
         f1 = f
         call condensed_contact(model, op, u, v, a, u1, f1, open_contact)
         do c = 1, model%n_contacts
            if (f1(c) /= 0.0_dp) u1 = u1 - op%g(:, model%c_slot(c)) * (model%c_sign(c) * f1(c))
         end do
      end if
      do i = 1, n
         v1(i) = op%c%a1 * u1(i) - hc(i)
         a1(i) = op%c%a0 * u1(i) - hm(i)
      end do
   end subroutine condensed_step

   !> Kernel of condensed_step for a dense operator and one contact: the arrays as
   !> explicit-shape arguments so that the compiler keeps them in registers and vectorises.
   pure subroutine dense_single_contact_step(n, am, gp, g, h, k, s1, model, u, v, a, u1, v1, &
                                             acc1, f1, hm, hc)
      integer, intent(in) :: n                        !! dofs
      real(dp), intent(in) :: am(n, n), gp(n), g(n)   !! Kbar^-1 M, Kbar^-1 q, Kbar^-1 e
      real(dp), intent(in) :: h                       !! e' Kbar^-1 e
      type(newmark_constants_t), intent(in) :: k      !! step constants
      real(dp), intent(in) :: s1                      !! load factor at the end
      type(model_t), intent(in) :: model              !! model (contact 1)
      real(dp), intent(in) :: u(n), v(n), a(n)        !! state at the start
      real(dp), intent(out) :: u1(n), v1(n), acc1(n)  !! state at the end
      real(dp), intent(out) :: f1                     !! contact force at the end [N]
      real(dp), intent(out) :: hm(n), hc(n)           !! workspaces
      integer :: i, j, dof
      real(dp) :: xj, ds, vs, a0, a1, a2, a3, a4, a5, cw, ch, sgn
      a0 = k%a0;  a1 = k%a1;  a2 = k%a2;  a3 = k%a3;  a4 = k%a4;  a5 = k%a5
      cw = k%cw;  ch = k%ch
      dof = model%c_dof(1);  sgn = model%c_sign(1)
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
      ds = sgn * u1(dof) - model%c_gap(1)
      f1 = 0.0_dp
      if (ds > 0.0_dp) then
         vs = sgn * (a1 * u1(dof) - hc(dof))
         f1 = contact_solve(model, 1, ds, vs, h, a1)
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

   !> Exact contact forces of the step from the predictor (the condensed method): closed form
   !> (bilinear) or safeguarded Newton (Hertz) for one contact, Gauss-Seidel over several
   !> (gapbeam_contact_law:solve_contacts). Contact `hold` is held open (0: none).
   pure subroutine condensed_contact(model, op, u, v, a, ystar, f, hold)
      type(model_t), intent(in) :: model      !! model
      type(step_op_t), intent(in) :: op        !! step operator
      real(dp), intent(in) :: u(:), v(:), a(:) !! state at the start
      real(dp), intent(in) :: ystar(:)         !! predictor
      real(dp), intent(inout) :: f(:)          !! contact force magnitudes (in: guess) [N]
      integer, intent(in) :: hold              !! contact held open (0: none)
      integer :: c, i
      real(dp) :: dstar(model%n_contacts), vstar(model%n_contacts)
      do c = 1, model%n_contacts
         i = model%c_dof(c)
         dstar(c) = model%c_sign(c) * ystar(i) - model%c_gap(c)
         vstar(c) = model%c_sign(c) * (op%c%a1 * (ystar(i) - u(i)) - op%c%a4 * v(i) &
                    - op%c%a5 * a(i))
      end do
      call solve_contacts(model, op%h, 1.0_dp, op%c%a1, dstar, vstar, f, hold)
   end subroutine condensed_contact

   !> The paper's fixed point on F_NL: y = Kbar^-1 (Pbar - E F) solved in full each iteration,
   !> F from the stop law at y, until max|dF| <= tol max|F|. Starts from `f` (extrapolated).
   subroutine fixed_point_step(model, op, s1, u, v, a, tol, max_iter, f, u1, v1, a1, &
                               iterations, converged, hm, hc, rhs, y, open_contact)
      type(model_t), intent(in) :: model     !! model
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
      n = model%n
      hm = op%c%a0 * u + op%c%a2 * v + op%c%a3 * a
      hc = op%c%a1 * u + op%c%a4 * v + op%c%a5 * a
      ! Pbar = M (hm + beta hc) + gamma K hc + s q
      tmp = hm + model%beta * hc
      call sym_matvec(op%dense, model%sys%kd, model%sys%m, model%sys%m_band, tmp, pbar)
      call sym_matvec(op%dense, model%sys%kd, model%sys%k, model%sys%k_band, hc, rhs)
      pbar = pbar + model%gamma * rhs + s1 * model%q
      if (has_modal_damping(model)) then
         call dense_matvec(n, model%c_modal, hc, rhs)
         pbar = pbar + rhs
      end if
      held = 0
      if (present(open_contact)) held = open_contact
      if (held > 0) f(held) = 0.0_dp
      converged = .false.
      do it = 1, max_iter
         rhs = pbar
         do c = 1, model%n_contacts
            i = model%c_dof(c)
            rhs(i) = rhs(i) - model%c_sign(c) * f(c)
         end do
         y = rhs
         if (op%dense) then
            call dpotrs('U', n, 1, op%fac, n, y, n, info)
         else
            call dpbtrs('U', n, model%sys%kd, 1, op%fab, model%sys%kd + 1, y, n, info)
         end if
         change = 0.0_dp;  fmax = 0.0_dp
         do c = 1, model%n_contacts
            i = model%c_dof(c)
            d = model%c_sign(c) * y(i) - model%c_gap(c)
            ddot = model%c_sign(c) * (op%c%a1 * y(i) - hc(i))
            fnew(c) = contact_force(model, c, d, ddot)
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
      do c = 1, model%n_contacts
         i = model%c_dof(c)
         rhs(i) = rhs(i) - model%c_sign(c) * f(c)
      end do
      u1 = rhs
      if (op%dense) then
         call dpotrs('U', n, 1, op%fac, n, u1, n, info)
      else
         call dpbtrs('U', n, model%sys%kd, 1, op%fab, model%sys%kd + 1, u1, n, info)
      end if
      v1 = op%c%a1 * u1 - hc
      a1 = op%c%a0 * u1 - hm
   end subroutine fixed_point_step

   !> y = A x with A dense or in upper band storage.
   pure subroutine sym_matvec(dense, kd, ad, ab, x, y)
      logical, intent(in) :: dense                  !! use the dense matrix
      integer, intent(in) :: kd                     !! semi-bandwidth
      real(dp), intent(in) :: ad(:, :), ab(:, :)    !! dense, band storage
      real(dp), intent(in) :: x(:)                  !! vector
      real(dp), intent(out) :: y(:)                 !! result
      if (dense) then
         call dense_matvec(size(x), ad, x, y)
      else
         call band_matvec(size(x), kd, ab, x, y)
      end if
   end subroutine sym_matvec

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
   subroutine half_step_ratio(model, dense, delta, alpha, tol, floor, t0, dt, u0, v0, a0, a1, &
                              ratio, worst, work)
      type(model_t), intent(in) :: model          !! model
      logical, intent(in) :: dense                 !! dense products (else banded)
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
      n = model%n
      h = 0.5_dp * dt
      associate (am => work(:, 1), um => work(:, 2), vm => work(:, 3), ku => work(:, 4), &
                 cv => work(:, 5), ma => work(:, 6))
         am = 0.5_dp * (a0 + a1)
         um = u0 + h * v0 + h**2 * ((0.5_dp - alpha) * a0 + alpha * am)
         vm = v0 + h * ((1.0_dp - delta) * a0 + delta * am)
         if (dense) then
            call dense_matvec(n, model%sys%k, um, ku)
            call dense_matvec(n, model%c, vm, cv)
            call dense_matvec(n, model%sys%m, am, ma)
         else
            call band_matvec(n, model%sys%kd, model%sys%k_band, um, ku)
            call band_matvec(n, model%sys%kd, model%sys%k_band, vm, cv)
            call band_matvec(n, model%sys%kd, model%sys%m_band, vm, ma)
            cv = model%gamma * cv + model%beta * ma
            if (has_modal_damping(model)) then
               call dense_matvec(n, model%c_modal, vm, ma)
               cv = cv + ma
            end if
            call band_matvec(n, model%sys%kd, model%sys%m_band, am, ma)
         end if
         s = load_factor(model, t0 + h)
         ! am now holds P - F_NL (force on the structure from the stops is -s f e)
         am = s * model%q
         call add_extra_load(model, t0 + h, am)
         do c = 1, model%n_contacts
            i = model%c_dof(c)
            d = model%c_sign(c) * um(i) - model%c_gap(c)
            ddot = model%c_sign(c) * vm(i)
            fc = contact_force(model, c, d, ddot)
            am(i) = am(i) - model%c_sign(c) * fc
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
