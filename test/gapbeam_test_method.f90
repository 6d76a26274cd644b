!> A time integrator that exists only in the tests: classical RK4 on the first-order form
!>    u' = v,   v' = M^-1 (s(t) q - C v - K u - sum_c (-s_c f_c) e_c)
!> with an embedded third-order solution from the same stages and the FSAL stage
!> k5 = f(t + h, y1): b^ = (1/6, 1/3, 1/3, 0, 1/6). The estimate y1 - y^1 is O(h^4), so its
!> error controller must work with order 3 (neither Newmark's 2 nor rk45's 4).
!>
!> It shows that a method is one module and one registry line: test_integrators adds
!> `rk43_caps` and an `rk43_stepper_t` to a registry value (method_registry_t%add) and
!> make_integrator dispatches to it, steps it under error control with its own order and
!> refuses it where its capabilities say; nothing in src/ names it.
module gapbeam_test_method
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error
   use gapbeam_lapack, only: dpotrf, dpotrs
   use gapbeam_model, only: model_t, load_factor, add_extra_load
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_capabilities, only: method_caps_t
   use gapbeam_integrator, only: stepper_t, contact_forces_at
   implicit none
   private
   public :: rk43_stepper_t, rk43_caps

   !> RK4 with the embedded 3rd-order FSAL estimate.
   type, extends(stepper_t) :: rk43_stepper_t
      real(dp), allocatable :: minv(:, :)            !! M^-1
      real(dp), allocatable :: ku(:, :), kv(:, :)    !! stage slopes (n, 5)
      real(dp), allocatable :: eu(:), ev(:)          !! embedded errors of the last step
   contains
      procedure :: prepare => rk43_prepare
      procedure :: step => rk43_step
      procedure :: local_error => rk43_local_error
   end type rk43_stepper_t

contains

   !> Its registry entry: explicit, order 4, an embedded estimate controlled as order 3, a
   !> mass at every dof, planar models (no rings).
   pure function rk43_caps() result(c)
      type(method_caps_t) :: c
      c = method_caps_t(name='rk43_test', family='test_rk43', summary='RK4 with an ' &
         // 'embedded FSAL third-order estimate (test only)', implicit=.false., order=4, &
         estimator='embedded', control_order=3, controls="'auto', 'error', 'fixed'", &
         auto_control='error', two_planes=.true., point_forces=.true., rings=.false., &
         massless=.false., carries_acceleration=.false., stability_limit=2.8284271247461903_dp, &
         stages=4, lyapunov_with='newmark', title='RK4(3)')
   end function rk43_caps

   subroutine rk43_prepare(self, model, cfg, dt, err)
      class(rk43_stepper_t), intent(inout) :: self    !! stepper
      type(model_t), intent(in) :: model              !! model
      type(solver_settings_t), intent(in) :: cfg      !! settings
      real(dp), intent(in) :: dt                      !! step [s]
      type(error_t), allocatable, intent(out) :: err  !! singular mass
      real(dp), allocatable :: fac(:, :)
      integer :: n, info, j
      n = model%n
      fac = model%sys%m
      call dpotrf('U', n, fac, n, info)
      if (info /= 0) then
         call fatal_error(err, 'rk43_test: singular mass matrix')
         return
      end if
      allocate(self%minv(n, n), source=0.0_dp)
      do j = 1, n
         self%minv(j, j) = 1.0_dp
      end do
      call dpotrs('U', n, n, fac, n, self%minv, n, info)
      if (.not. allocated(self%ku)) allocate(self%ku(n, 5), self%kv(n, 5), self%eu(n), &
                                             self%ev(n))
      self%dt = dt
      self%ready = .true.
   end subroutine rk43_prepare

   !> Acceleration M^-1 (s(t) q - C v - K u - F(u, v)) and the contact forces, contact `hold`
   !> held open.
   subroutine slope(self, model, t, u, v, hold, acc, f)
      class(rk43_stepper_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      real(dp), intent(in) :: t, u(:), v(:)
      integer, intent(in) :: hold
      real(dp), intent(out) :: acc(:), f(:)
      real(dp) :: r(model%n)
      integer :: c, i
      r = load_factor(model, t) * model%q - matmul(model%c, v) - matmul(model%sys%k, u)
      call add_extra_load(model, t, r)
      call contact_forces_at(model, u, v, f)
      do c = 1, model%n_contacts
         if (c == hold) f(c) = 0.0_dp
         i = model%c_dof(c)
         r(i) = r(i) - model%c_sign(c) * f(c)
      end do
      acc = matmul(self%minv, r)
      self%evaluations = self%evaluations + 1
   end subroutine slope

   !> One RK4 step and its embedded estimate (see stepper_t%step).
   subroutine rk43_step(self, model, s0, s1, ok, ratio, open_contact)
      class(rk43_stepper_t), intent(inout) :: self  !! stepper
      type(model_t), intent(in) :: model            !! model
      type(state_t), intent(in) :: s0               !! start
      type(state_t), intent(inout) :: s1            !! end
      logical, intent(out) :: ok                    !! always true
      real(dp), intent(out) :: ratio                !! -1: the controller measures
      integer, intent(in) :: open_contact           !! contact held open
      real(dp) :: h, t0
      h = self%dt;  t0 = s0%t;  ok = .true.;  ratio = -1.0_dp
      s1%t = t0 + h
      associate (ku => self%ku, kv => self%kv, u => s0%u, v => s0%v)
         ku(:, 1) = v
         call slope(self, model, t0, u, v, open_contact, kv(:, 1), s1%f)
         ku(:, 2) = v + 0.5_dp * h * kv(:, 1)
         call slope(self, model, t0 + 0.5_dp * h, u + 0.5_dp * h * ku(:, 1), ku(:, 2), &
                    open_contact, kv(:, 2), s1%f)
         ku(:, 3) = v + 0.5_dp * h * kv(:, 2)
         call slope(self, model, t0 + 0.5_dp * h, u + 0.5_dp * h * ku(:, 2), ku(:, 3), &
                    open_contact, kv(:, 3), s1%f)
         ku(:, 4) = v + h * kv(:, 3)
         call slope(self, model, t0 + h, u + h * ku(:, 3), ku(:, 4), open_contact, kv(:, 4), &
                    s1%f)
         s1%u = u + h / 6.0_dp * (ku(:, 1) + 2.0_dp * ku(:, 2) + 2.0_dp * ku(:, 3) + ku(:, 4))
         s1%v = v + h / 6.0_dp * (kv(:, 1) + 2.0_dp * kv(:, 2) + 2.0_dp * kv(:, 3) + kv(:, 4))
         ku(:, 5) = s1%v
         call slope(self, model, t0 + h, s1%u, s1%v, 0, kv(:, 5), s1%f)
         s1%a = kv(:, 5)
         ! y1 - y^1 = h (b - b^) . k with b - b^ = (0, 0, 0, 1/6, -1/6)
         self%eu = h * (ku(:, 4) - ku(:, 5)) / 6.0_dp
         self%ev = h * (kv(:, 4) - kv(:, 5)) / 6.0_dp
      end associate
   end subroutine rk43_step

   !> The embedded estimate: e_u = h^2 fda with fda = eu / h^2, e_v given (coef(2) < 0).
   subroutine rk43_local_error(self, model, s0, s1, fda, ev, coef, has)
      class(rk43_stepper_t), intent(inout) :: self  !! stepper
      type(model_t), intent(in) :: model            !! model
      type(state_t), intent(in) :: s0, s1           !! the step
      real(dp), intent(out) :: fda(:), ev(:)        !! error data
      real(dp), intent(out) :: coef(3)              !! [1, -1, 0]
      logical, intent(out) :: has                   !! true
      has = .true.
      coef = [1.0_dp, -1.0_dp, 0.0_dp]
      fda = self%eu / self%dt**2
      ev = self%ev
   end subroutine rk43_local_error
end module gapbeam_test_method
