!> Explicit comparison integrators: the central difference method (Newmark delta = 1/2,
!> alpha = 0, in its explicit form) and the Runge-Kutta methods RK4 (classical, fixed step)
!> and RK45 (Dormand-Prince 5(4) with its embedded error estimate) on the first-order form
!>    u' = v,   v' = M^-1 (s(t) q - C v - K u - sum_c (-s_c f_c) e_c).
!> All need a mass at every dof (M positive definite): lumped mass without rotary inertia
!> is refused with a clear error. Contact forces are evaluated from the stop laws at each
!> stage (explicitly). Known stability limits (undamped, omega_max dt): central difference 2,
!> RK4 2 sqrt(2) on the imaginary axis.
module gapbeam_explicit
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dpotrf, dpotrs
   use gapbeam_model, only: model_t, load_factor, add_extra_load
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_integrator, only: stepper_t
   use gapbeam_contact_law, only: contact_force
   use gapbeam_linalg, only: dense_matvec
   use gapbeam_ring_contact, only: ring_force
   implicit none
   private
   public :: central_difference_t, runge_kutta_t

   !> Central difference: u1 = u + dt v + dt^2/2 a; (M + dt/2 C) a1 = P1 - K u1 - C (v + dt/2 a)
   !> - F(u1, v + dt/2 a); v1 = v + dt/2 (a + a1).
   type, extends(stepper_t) :: central_difference_t
      real(dp), allocatable :: fac(:, :)      !! (M + dt/2 C)^-1
      real(dp), allocatable :: w(:), r(:)     !! workspaces
   contains
      procedure :: prepare => cd_prepare
      procedure :: step => cd_step
   end type central_difference_t

   !> Runge-Kutta on the first-order form: classical RK4, or Dormand-Prince 5(4) with its
   !> embedded estimate (the registry sets `embedded` for rk45).
   type, extends(stepper_t) :: runge_kutta_t
      logical :: embedded = .false.           !! Dormand-Prince with the embedded estimate
      real(dp) :: rtol = 1.0e-6_dp            !! rk45 relative tolerance
      real(dp) :: atol = 1.0e-12_dp           !! rk45 absolute tolerance (SI units of u, v)
      real(dp), allocatable :: mfac(:, :)     !! M^-1
      real(dp), allocatable :: ku(:, :), kv(:, :)  !! stage slopes (n, 7)
      real(dp), allocatable :: ut(:), vt(:), r(:)  !! workspaces
      real(dp), allocatable :: eu(:), ev(:)   !! rk45: embedded errors of the step
      real(dp), allocatable :: fn(:), ft(:)   !! ring forces of the last evaluation [N]
   contains
      procedure :: prepare => rk_prepare
      procedure :: step => rk_step
      procedure :: local_error => rk_local_error
   end type runge_kutta_t

   ! Dormand-Prince 5(4) tableau
   real(dp), parameter :: c2 = 1.0_dp / 5, c3 = 3.0_dp / 10, c4 = 4.0_dp / 5, c5 = 8.0_dp / 9
   real(dp), parameter :: a21 = 1.0_dp / 5
   real(dp), parameter :: a31 = 3.0_dp / 40, a32 = 9.0_dp / 40
   real(dp), parameter :: a41 = 44.0_dp / 45, a42 = -56.0_dp / 15, a43 = 32.0_dp / 9
   real(dp), parameter :: a51 = 19372.0_dp / 6561, a52 = -25360.0_dp / 2187, &
      a53 = 64448.0_dp / 6561, a54 = -212.0_dp / 729
   real(dp), parameter :: a61 = 9017.0_dp / 3168, a62 = -355.0_dp / 33, &
      a63 = 46732.0_dp / 5247, a64 = 49.0_dp / 176, a65 = -5103.0_dp / 18656
   real(dp), parameter :: b1 = 35.0_dp / 384, b3 = 500.0_dp / 1113, b4 = 125.0_dp / 192, &
      b5 = -2187.0_dp / 6784, b6 = 11.0_dp / 84
   real(dp), parameter :: e1 = 71.0_dp / 57600, e3 = -71.0_dp / 16695, e4 = 71.0_dp / 1920, &
      e5 = -17253.0_dp / 339200, e6 = 22.0_dp / 525, e7 = -1.0_dp / 40

contains

   !> The inverse of a mass-like SPD matrix (Cholesky, then solves on the identity: LAPACK's
   !> call overhead exceeds a product's work at these sizes); error naming the method when it
   !> is singular.
   subroutine factor_spd(name, a, inv, err)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: a(:, :)
      real(dp), allocatable, intent(out) :: inv(:, :)
      type(error_t), allocatable, intent(out) :: err
      real(dp), allocatable :: fac(:, :)
      integer :: info, n, j
      n = size(a, 1)
      fac = a
      call dpotrf('U', n, fac, n, info)
      if (info /= 0) then
         call fatal_error(err, "method '" // name // "': the mass matrix is " &
         // 'singular (dof ' // str(info) // ' has no mass); explicit methods need a mass at ' &
         // "every dof: use &beam rotary_inertia = 'half_element' or 'hrz', or an implicit method")
         return
      end if
      allocate(inv(n, n), source=0.0_dp)
      do j = 1, n
         inv(j, j) = 1.0_dp
      end do
      call dpotrs('U', n, n, fac, n, inv, n, info)
   end subroutine factor_spd

   !> Contact forces from the laws at (u, v); `hold` > 0 is held open.
   pure subroutine contact_forces(model, u, v, hold, f, r)
      type(model_t), intent(in) :: model
      real(dp), intent(in) :: u(:), v(:)
      integer, intent(in) :: hold
      real(dp), intent(out) :: f(:)
      real(dp), intent(inout) :: r(:)      !! force vector: r = r + sum (-s_c f_c) e_c
      integer :: c, i
      do c = 1, model%n_contacts
         i = model%c_dof(c)
         f(c) = contact_force(model, c, model%c_sign(c) * u(i) - model%c_gap(c), &
                              model%c_sign(c) * v(i))
         if (c == hold) f(c) = 0.0_dp
         r(i) = r(i) - model%c_sign(c) * f(c)
      end do
   end subroutine contact_forces

   subroutine cd_prepare(self, model, cfg, dt, err)
      class(central_difference_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      real(dp), intent(in) :: dt
      type(error_t), allocatable, intent(out) :: err
      integer :: i
      ! M + dt/2 C is regular even where M is not, but a dof without mass has omega = infinity:
      ! no step is stable
      do i = 1, model%n
         if (model%sys%m(i, i) > 0.0_dp) cycle
         call fatal_error(err, "method 'central_difference': the mass matrix is singular (dof " &
            // str(i) // ' has no mass); explicit methods need a mass at every dof: use &beam ' &
            // "rotary_inertia = 'half_element' or 'hrz', or an implicit method")
         return
      end do
      call factor_spd('central_difference', model%sys%m + 0.5_dp * dt * model%c, self%fac, err)
      if (allocated(err)) return
      if (.not. allocated(self%w)) allocate(self%w(model%n), self%r(model%n))
      self%dt = dt
      self%ready = .true.
   end subroutine cd_prepare

   !> One step (see stepper_t%step).
   subroutine cd_step(self, model, s0, s1, ok, ratio, open_contact)
      class(central_difference_t), intent(inout) :: self  !! stepper
      type(model_t), intent(in) :: model                  !! model
      type(state_t), intent(in) :: s0                     !! start
      type(state_t), intent(inout) :: s1                  !! end
      logical, intent(out) :: ok                          !! always true
      real(dp), intent(out) :: ratio                      !! no embedded estimate: -1
      integer, intent(in) :: open_contact                 !! contact held open (0: none)
      real(dp) :: h, p1
      integer :: n, info
      n = model%n;  h = self%dt
      ok = .true.;  ratio = -1.0_dp
      s1%t = s0%t + h
      s1%u = s0%u + h * s0%v + 0.5_dp * h**2 * s0%a
      self%w = s0%v + 0.5_dp * h * s0%a                 ! velocity predictor
      p1 = load_factor(model, s0%t + h)
      call dense_matvec(n, model%sys%k, s1%u, s1%a)
      call dense_matvec(n, model%c, self%w, self%r)
      self%r = p1 * model%q - s1%a - self%r
      call add_extra_load(model, s0%t + h, self%r)
      call contact_forces(model, s1%u, self%w, open_contact, s1%f, self%r)
      call dense_matvec(n, self%fac, self%r, s1%a)
      s1%v = self%w + 0.5_dp * h * s1%a
      self%evaluations = self%evaluations + 1
   end subroutine cd_step

   subroutine rk_prepare(self, model, cfg, dt, err)
      class(runge_kutta_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      real(dp), intent(in) :: dt
      type(error_t), allocatable, intent(out) :: err
      self%rtol = cfg%rk_rtol;  self%atol = cfg%rk_atol
      call factor_spd(trim(cfg%method), model%sys%m, self%mfac, err)
      if (allocated(err)) return
      if (.not. allocated(self%ku)) allocate(self%ku(model%n, 7), self%kv(model%n, 7), &
         self%ut(model%n), self%vt(model%n), self%r(model%n), self%eu(model%n), &
         self%ev(model%n), self%fn(model%n_rings), self%ft(model%n_rings))
      self%dt = dt
      self%ready = .true.
   end subroutine rk_prepare

   !> Acceleration M^-1 (s(t) q - C v - K u - F(u, v)), the ring supports in the regimes of
   !> the step's start s0 (held over the step: the integrator ends a step at every switch).
   subroutine rk_accel(self, model, s0, t, u, v, hold, acc, f)
      class(runge_kutta_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: s0
      real(dp), intent(in) :: t, u(:), v(:)
      integer, intent(in) :: hold
      real(dp), intent(out) :: acc(:), f(:)
      integer :: n, r
      real(dp) :: pr(2)
      n = model%n
      call dense_matvec(n, model%sys%k, u, acc)
      call dense_matvec(n, model%c, v, self%r)
      self%r = load_factor(model, t) * model%q - acc - self%r
      call add_extra_load(model, t, self%r)
      call contact_forces(model, u, v, hold, f, self%r)
      do r = 1, model%n_rings
         if (r + model%n_contacts == hold) then
            self%fn(r) = 0.0_dp;  self%ft(r) = 0.0_dp
            cycle
         end if
         associate (dofs => model%r_dof(:, r))
            call ring_force(model, r, s0%mode(r), s0%sigma(r), s0%anchor(r), u(dofs), v(dofs), &
                            pr, self%fn(r), self%ft(r))
            self%r(dofs) = self%r(dofs) + pr
         end associate
      end do
      call dense_matvec(n, self%mfac, self%r, acc)
      self%evaluations = self%evaluations + 1
   end subroutine rk_accel

   !> One step (see stepper_t%step): classical RK4, or Dormand-Prince 5(4) with the embedded
   !> error estimate (FSAL: the acceleration at the end is the next step's first stage).
   subroutine rk_step(self, model, s0, s1, ok, ratio, open_contact)
      class(runge_kutta_t), intent(inout) :: self        !! stepper
      type(model_t), intent(in) :: model                 !! model
      type(state_t), intent(in) :: s0                    !! start
      type(state_t), intent(inout) :: s1                 !! end
      logical, intent(out) :: ok                         !! always true
      real(dp), intent(out) :: ratio                     !! rk45: error / tolerance; rk4: -1
      integer, intent(in) :: open_contact                !! contact held open (0: none)
      real(dp) :: h, eu, ev, sc, t0
      integer :: i
      h = self%dt;  ok = .true.;  ratio = -1.0_dp;  t0 = s0%t
      s1%t = s0%t + h
      associate (ku => self%ku, kv => self%kv, ut => self%ut, vt => self%vt, u => s0%u, &
                 v => s0%v, a => s0%a, u1 => s1%u, v1 => s1%v, a1 => s1%a, f1 => s1%f)
         if (.not. self%embedded) then
            ku(:, 1) = v;  call rk_accel(self, model, s0, t0, u, v, open_contact, kv(:, 1), f1)
            ut = u + 0.5_dp * h * ku(:, 1);  vt = v + 0.5_dp * h * kv(:, 1)
            ku(:, 2) = vt
            call rk_accel(self, model, s0, t0 + 0.5_dp * h, ut, vt, open_contact, kv(:, 2), f1)
            ut = u + 0.5_dp * h * ku(:, 2);  vt = v + 0.5_dp * h * kv(:, 2)
            ku(:, 3) = vt
            call rk_accel(self, model, s0, t0 + 0.5_dp * h, ut, vt, open_contact, kv(:, 3), f1)
            ut = u + h * ku(:, 3);  vt = v + h * kv(:, 3)
            ku(:, 4) = vt
            call rk_accel(self, model, s0, t0 + h, ut, vt, open_contact, kv(:, 4), f1)
            u1 = u + h / 6 * (ku(:, 1) + 2 * ku(:, 2) + 2 * ku(:, 3) + ku(:, 4))
            v1 = v + h / 6 * (kv(:, 1) + 2 * kv(:, 2) + 2 * kv(:, 3) + kv(:, 4))
            ! acceleration and forces at the end (the next step's first stage)
            call rk_accel(self, model, s0, t0 + h, u1, v1, 0, a1, f1)
            self%evaluations = self%evaluations - 1   ! reused as the next first stage
         else
            ku(:, 1) = v;  kv(:, 1) = a
            if (open_contact > 0) call rk_accel(self, model, s0, t0, u, v, open_contact, &
                                                kv(:, 1), f1)
            call rk_stage(self, model, s0, h, open_contact, 2, c2, [a21], f1)
            call rk_stage(self, model, s0, h, open_contact, 3, c3, [a31, a32], f1)
            call rk_stage(self, model, s0, h, open_contact, 4, c4, [a41, a42, a43], f1)
            call rk_stage(self, model, s0, h, open_contact, 5, c5, [a51, a52, a53, a54], f1)
            call rk_stage(self, model, s0, h, open_contact, 6, 1.0_dp, [a61, a62, a63, a64, a65], f1)
            u1 = u + h * (b1 * ku(:, 1) + b3 * ku(:, 3) + b4 * ku(:, 4) + b5 * ku(:, 5) &
                 + b6 * ku(:, 6))
            v1 = v + h * (b1 * kv(:, 1) + b3 * kv(:, 3) + b4 * kv(:, 4) + b5 * kv(:, 5) &
                 + b6 * kv(:, 6))
            ku(:, 7) = v1
            ! FSAL: the last stage, and the next step's first, in the step's regime (a contact
            ! held open to a located onset stays open: its force, a damper's c d' jumping in
            ! there, is the next step's, from the restart at the event; in this stage it
            ! would enter the error estimate as an error that no smaller step reduces)
            call rk_accel(self, model, s0, t0 + h, u1, v1, open_contact, kv(:, 7), f1)
            a1 = kv(:, 7)
            ! the forces at the end are reported with every contact as it is
            if (open_contact > 0) call rk_accel(self, model, s0, t0 + h, u1, v1, 0, self%ut, f1)
            ratio = 0.0_dp
            do i = 1, model%n
               eu = h * (e1 * ku(i, 1) + e3 * ku(i, 3) + e4 * ku(i, 4) + e5 * ku(i, 5) &
                    + e6 * ku(i, 6) + e7 * ku(i, 7))
               self%eu(i) = eu
               ev = h * (e1 * kv(i, 1) + e3 * kv(i, 3) + e4 * kv(i, 4) + e5 * kv(i, 5) &
                    + e6 * kv(i, 6) + e7 * kv(i, 7))
               self%ev(i) = ev
               sc = self%atol + self%rtol * max(abs(u(i)), abs(u1(i)))
               ratio = max(ratio, abs(eu) / sc)
               sc = self%atol + self%rtol * max(abs(v(i)), abs(v1(i)))
               ratio = max(ratio, abs(ev) / sc)
            end do
         end if
      end associate
      if (model%n_rings > 0) then
         ! the forces of the end's evaluation; the regimes of the start (switches are the
         ! integrator's: it ends a step at each)
         s1%fn = self%fn;  s1%ft = self%ft
         s1%mode = s0%mode;  s1%sigma = s0%sigma;  s1%anchor = s0%anchor
      end if
   end subroutine rk_step

   !> rk45: the embedded (4th against 5th order) estimate of the last step's displacement error.
   subroutine rk_local_error(self, model, s0, s1, fda, ev, coef, has)
      class(runge_kutta_t), intent(inout) :: self      !! stepper
      type(model_t), intent(in) :: model               !! model
      type(state_t), intent(in) :: s0, s1              !! the step
      real(dp), intent(out) :: fda(:)                  !! e_u / h^2
      real(dp), intent(out) :: ev(:)                   !! the embedded velocity error
      real(dp), intent(out) :: coef(3)                 !! [1, -1, 0]: e_u = h^2 fda, ev given
      logical, intent(out) :: has                      !! rk45 only
      has = self%embedded
      coef = [1.0_dp, -1.0_dp, 0.0_dp]
      if (has) then
         fda = self%eu / self%dt**2;  ev = self%ev
      else
         fda = 0.0_dp;  ev = 0.0_dp
      end if
   end subroutine rk_local_error

   !> Stage j of an explicit Runge-Kutta step: state s0 + h sum_m aj(m) k_m at t0 + cj h,
   !> slopes into column j of ku, kv.
   subroutine rk_stage(self, model, s0, h, open_contact, j, cj, aj, f)
      class(runge_kutta_t), intent(inout) :: self   !! stepper (slopes and workspaces)
      type(model_t), intent(in) :: model            !! model
      type(state_t), intent(in) :: s0               !! state at the start of the step
      real(dp), intent(in) :: h                     !! step [s]
      integer, intent(in) :: open_contact           !! contact held open (0: none)
      integer, intent(in) :: j                      !! stage
      real(dp), intent(in) :: cj, aj(:)             !! its node and coefficients
      real(dp), intent(out) :: f(:)                 !! contact forces of the stage [N]
      integer :: m
      self%ut = s0%u;  self%vt = s0%v
      do m = 1, j - 1
         self%ut = self%ut + h * aj(m) * self%ku(:, m)
         self%vt = self%vt + h * aj(m) * self%kv(:, m)
      end do
      self%ku(:, j) = self%vt
      call rk_accel(self, model, s0, s0%t + cj * h, self%ut, self%vt, open_contact, self%kv(:, j), f)
   end subroutine rk_stage
end module gapbeam_explicit
