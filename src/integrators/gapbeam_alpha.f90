!> Implicit alpha methods with numerical damping of the high modes: Hilber-Hughes-Taylor
!> (HHT-alpha, alpha in [-1/3, 0]) and the generalized-alpha method of Chung and Hulbert
!> (spectral radius rho_inf in [0, 1] at infinite omega dt).
!>
!> Balance at the intermediate instants (alpha_m for inertia, alpha_f for the rest):
!>   M a_{n+1-am} + C v_{n+1-af} + K u_{n+1-af} - F_c(u_{n+1-af}, v_{n+1-af}) = P_{n+1-af}
!> with x_{n+1-a} = (1 - a) x_{n+1} + a x_n and the Newmark relations (beta, gamma) between
!> u, v, a. HHT: am = 0, af = -alpha, gamma = 1/2 - alpha, beta = (1 - alpha)^2/4;
!> generalized-alpha: am = (2 rho - 1)/(rho + 1), af = rho/(rho + 1), gamma = 1/2 - am + af,
!> beta = (1 - am + af)^2/4. The contact law is evaluated at n+1-af; as in the Newmark
!> solver the contact force is solved exactly from the system condensed on the contact dofs
!> (closed form for one bilinear contact, safeguarded Newton for Hertz, Gauss-Seidel over
!> several contacts).
!>
!> Two forms of the same step: for fixed steps the displacement u1 is solved for (as always);
!> with error control the acceleration a1 is (its residual has the size of the forces, so the
!> step keeps its accuracy at any step size). The effective matrix is kept dense or banded as
!> for Newmark, and a local error estimate is given (see alpha_local_error).
module gapbeam_alpha
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dpotrf, dpotrs, dpbtrf, dpbtrs
   use gapbeam_model, only: model_t, load_factor, add_extra_load, has_modal_damping
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_integrator, only: stepper_t
   use gapbeam_contact_law, only: solve_contacts
   use gapbeam_linalg, only: dense_matvec, band_matvec, band_solve, dense_to_band
   use gapbeam_newmark, only: use_dense
   implicit none
   private
   public :: alpha_stepper_t

   !> HHT-alpha or generalized-alpha at one step size.
   type, extends(stepper_t) :: alpha_stepper_t
      logical :: hht = .false.                 !! HHT (given alpha), else generalized-alpha
      real(dp) :: am = 0.0_dp, af = 0.0_dp, beta = 0.25_dp, gamma = 0.5_dp  !! parameters
      logical :: dense = .true.                !! dense factor (else banded)
      logical :: acceleration_form = .false.   !! solve for a1 (error control)
      real(dp), allocatable :: fac(:, :)       !! Cholesky factor of Kbar (dense)
      real(dp), allocatable :: kinv(:, :)      !! Kbar^-1 (dense)
      real(dp), allocatable :: fab(:, :)       !! Cholesky factor of Kbar (band storage)
      real(dp), allocatable :: g(:, :)         !! Kbar^-1 E (n, n_slots)
      real(dp), allocatable :: h(:, :)         !! E' Kbar^-1 E
      real(dp), allocatable :: rhs(:), t1(:), t2(:)  !! workspaces
   contains
      procedure :: prepare => alpha_prepare
      procedure :: step => alpha_step
      procedure :: local_error => alpha_local_error
   end type alpha_stepper_t

contains

   !> (alpha_m, alpha_f, beta, gamma) of HHT (given alpha) or generalized-alpha (given rho).
   pure subroutine alpha_parameters(hht, hht_alpha, rho_inf, am, af, beta, gamma)
      logical, intent(in) :: hht                  !! HHT, else generalized-alpha
      real(dp), intent(in) :: hht_alpha           !! HHT alpha in [-1/3, 0]
      real(dp), intent(in) :: rho_inf             !! generalized-alpha rho_inf in [0, 1]
      real(dp), intent(out) :: am, af, beta, gamma
      if (hht) then
         am = 0.0_dp
         af = -hht_alpha
         gamma = 0.5_dp - hht_alpha
         beta = 0.25_dp * (1.0_dp - hht_alpha)**2
      else
         am = (2.0_dp * rho_inf - 1.0_dp) / (rho_inf + 1.0_dp)
         af = rho_inf / (rho_inf + 1.0_dp)
         gamma = 0.5_dp - am + af
         beta = 0.25_dp * (1.0_dp - am + af)**2
      end if
   end subroutine alpha_parameters

   !> Factorise Kbar = (1-am)/(beta dt^2) M + (1-af) gamma/(beta dt) C + (1-af) K and the
   !> contact influences for steps of dt.
   subroutine alpha_prepare(self, model, cfg, dt, err)
      class(alpha_stepper_t), intent(inout) :: self   !! stepper
      type(model_t), intent(in) :: model              !! model
      type(solver_settings_t), intent(in) :: cfg      !! method, parameters
      real(dp), intent(in) :: dt                      !! step [s]
      type(error_t), allocatable, intent(out) :: err  !! not positive definite
      integer :: n, ns, info, j, kd
      real(dp), allocatable :: kbar(:, :)
      call alpha_parameters(self%hht, cfg%hht_alpha, cfg%rho_infinity, self%am, self%af, &
                            self%beta, self%gamma)
      n = model%n;  ns = model%n_slots;  kd = model%sys%kd
      self%dense = use_dense(model, cfg%linear_solver)
      self%acceleration_form = cfg%step_control == 'error'
      kbar = (1.0_dp - self%am) / (self%beta * dt**2) * model%sys%m &
             + (1.0_dp - self%af) * self%gamma / (self%beta * dt) * model%c &
             + (1.0_dp - self%af) * model%sys%k
      if (self%dense) then
         call dpotrf('U', n, kbar, n, info)
         self%fac = kbar
         if (info == 0) then            ! Kbar^-1 for the hot path (see kbar_solve)
            if (allocated(self%kinv)) deallocate(self%kinv)
            allocate(self%kinv(n, n), source=0.0_dp)
            do j = 1, n
               self%kinv(j, j) = 1.0_dp
            end do
            call dpotrs('U', n, n, self%fac, n, self%kinv, n, info)
         end if
      else
         call dense_to_band(kbar, kd, self%fab)
         call dpbtrf('U', n, kd, self%fab, kd + 1, info)
      end if
      if (info /= 0) then
         call fatal_error(err, "method '" // trim(cfg%method) // "': effective stiffness not " &
            // 'positive definite (factorisation info=' // str(info) // ', dt = ' // str(dt) &
            // ' s)')
         return
      end if
      if (allocated(self%g)) deallocate(self%g)
      allocate(self%g(n, ns), source=0.0_dp)
      do j = 1, ns
         self%g(model%slot_dof(j), j) = 1.0_dp
      end do
      if (ns > 0) then
         if (self%dense) then
            call dpotrs('U', n, ns, self%fac, n, self%g, n, info)
         else
            call dpbtrs('U', n, kd, ns, self%fab, kd + 1, self%g, n, info)
         end if
      end if
      if (allocated(self%h)) deallocate(self%h)
      allocate(self%h(ns, ns))
      do j = 1, ns
         self%h(j, :) = self%g(model%slot_dof(j), :)
      end do
      if (.not. allocated(self%rhs)) allocate(self%rhs(n), self%t1(n), self%t2(n))
      self%dt = dt
      self%ready = .true.
   end subroutine alpha_prepare

   !> x := Kbar^-1 x.
   subroutine kbar_solve(self, model, x)
      class(alpha_stepper_t), intent(in) :: self      !! stepper
      type(model_t), intent(in) :: model              !! model
      real(dp), intent(inout) :: x(:)                 !! right-hand side, then solution
      real(dp) :: y(size(x))
      if (self%dense) then        ! LAPACK's call overhead exceeds a product's work at this size
         y = x
         call dense_matvec(model%n, self%kinv, y, x)
      else
         call band_solve(model%n, model%sys%kd, self%fab, x)
      end if
   end subroutine kbar_solve

   !> y = A x for a dense matrix or its band form.
   subroutine matvec(self, model, ad, ab, x, y)
      class(alpha_stepper_t), intent(in) :: self      !! stepper (storage)
      type(model_t), intent(in) :: model              !! model
      real(dp), intent(in) :: ad(:, :), ab(:, :)      !! dense, band storage
      real(dp), intent(in) :: x(:)                    !! vector
      real(dp), intent(out) :: y(:)                   !! product
      if (self%dense) then
         call dense_matvec(model%n, ad, x, y)
      else
         call band_matvec(model%n, model%sys%kd, ab, x, y)
      end if
   end subroutine matvec

   !> One step (see stepper_t%step).
   subroutine alpha_step(self, model, s0, s1, ok, ratio, open_contact)
      class(alpha_stepper_t), intent(inout) :: self   !! stepper
      type(model_t), intent(in) :: model              !! model
      type(state_t), intent(in) :: s0                 !! start
      type(state_t), intent(inout) :: s1              !! end
      logical, intent(out) :: ok                      !! always true
      real(dp), intent(out) :: ratio                  !! no embedded estimate: -1
      integer, intent(in) :: open_contact             !! contact held open (0: none)
      real(dp) :: h, am, af, be, ga, p0, p1, ka, bh2
      real(dp) :: dstar(model%n_contacts), vstar(model%n_contacts)
      integer :: c, i
      h = self%dt;  bh2 = self%beta * h**2
      am = self%am;  af = self%af;  be = self%beta;  ga = self%gamma
      ok = .true.;  ratio = -1.0_dp
      p0 = load_factor(model, s0%t)
      p1 = load_factor(model, s0%t + h)
      s1%t = s0%t + h
      if (self%acceleration_form) then
         call accel_predictor(self, model, s0, p0, p1, s1)
      else
         call displacement_predictor(self, model, s0, p0, p1, s1)
      end if
      ! contact forces at n+1-af from the condensed system (u1 = u1* - G s f): penetration
      ! and rate at n+1-af with zero contact forces, then the exact solve
      ka = ga / (be * h)
      do c = 1, model%n_contacts
         i = model%c_dof(c)
         dstar(c) = model%c_sign(c) * ((1.0_dp - af) * s1%u(i) + af * s0%u(i)) - model%c_gap(c)
         vstar(c) = model%c_sign(c) * ((1.0_dp - af) * s1%v(i) + af * s0%v(i))
      end do
      s1%f = 0.0_dp
      call solve_contacts(model, self%h, 1.0_dp - af, ka, dstar, vstar, s1%f, open_contact)
      do c = 1, model%n_contacts
         if (s1%f(c) /= 0.0_dp) s1%u = s1%u - self%g(:, model%c_slot(c)) &
                                       * (model%c_sign(c) * s1%f(c))
      end do
      if (self%acceleration_form) then
         ! the contact correction of a1 directly (u1 - u~ would cancel): a1 = a1* - G s f / bh2
         s1%a = self%t2
         do c = 1, model%n_contacts
            if (s1%f(c) /= 0.0_dp) s1%a = s1%a - self%g(:, model%c_slot(c)) &
                                          * (model%c_sign(c) * s1%f(c) / bh2)
         end do
      else
         s1%a = (s1%u - s0%u - h * s0%v) / (be * h**2) - (0.5_dp / be - 1.0_dp) * s0%a
      end if
      s1%v = s0%v + h * ((1.0_dp - ga) * s0%a + ga * s1%a)
   end subroutine alpha_step

   !> u1 with no contact force, from the displacement form:
   !> rhs = (1-af) P1 + af P0 - am M a - af C v - af K u
   !>       + (1-am) M [u/(be h^2) + v/(be h) + (1/(2be) - 1) a]
   !>       + (1-af) C [ga/(be h) u - (1 - ga/be) v - h (1 - ga/(2 be)) a],   Kbar u1 = rhs.
   !> v1 follows the Newmark relation (used for the contact rate).
   subroutine displacement_predictor(self, model, s0, p0, p1, s1)
      class(alpha_stepper_t), intent(inout) :: self   !! stepper
      type(model_t), intent(in) :: model              !! model
      type(state_t), intent(in) :: s0                 !! start
      real(dp), intent(in) :: p0, p1                  !! load factors at the ends
      type(state_t), intent(inout) :: s1              !! u1, v1 with no contact force
      real(dp) :: h, am, af, be, ga
      h = self%dt
      am = self%am;  af = self%af;  be = self%beta;  ga = self%gamma
      self%t1 = -am * s0%a + (1.0_dp - am) * (s0%u / (be * h**2) + s0%v / (be * h) &
                + (0.5_dp / be - 1.0_dp) * s0%a)
      call matvec(self, model, model%sys%m, model%sys%m_band, self%t1, self%rhs)
      self%t1 = -af * s0%v + (1.0_dp - af) * (ga / (be * h) * s0%u - (1.0_dp - ga / be) * s0%v &
                - h * (1.0_dp - 0.5_dp * ga / be) * s0%a)
      call dense_matvec(model%n, model%c, self%t1, self%t2)
      self%rhs = self%rhs + self%t2
      call matvec(self, model, model%sys%k, model%sys%k_band, s0%u, self%t2)
      self%rhs = self%rhs - af * self%t2 + ((1.0_dp - af) * p1 + af * p0) * model%q
      call add_weighted_extra(model, s0%t, h, af, self%t1, self%rhs)
      s1%u = self%rhs
      call kbar_solve(self, model, s1%u)
      s1%v = ga / (be * h) * (s1%u - s0%u) + (1.0_dp - ga / be) * s0%v &
             + h * (1.0_dp - 0.5_dp * ga / be) * s0%a
   end subroutine displacement_predictor

   !> a1 with no contact force from the residual at n+1-af (acceleration form):
   !> beta h^2 Kbar a1 = P_{n+1-af} - am M a0 - C ((1-af) v~ + af v0) - K ((1-af) u~ + af u0),
   !> u~ = u0 + h v0 + (1/2 - beta) h^2 a0, v~ = v0 + (1 - gamma) h a0; then u1, v1 from the
   !> Newmark relations. Keeps a1 in t2.
   subroutine accel_predictor(self, model, s0, p0, p1, s1)
      class(alpha_stepper_t), intent(inout) :: self   !! stepper
      type(model_t), intent(in) :: model              !! model
      type(state_t), intent(in) :: s0                 !! start
      real(dp), intent(in) :: p0, p1                  !! load factors at the ends
      type(state_t), intent(inout) :: s1              !! u1, v1 with no contact force
      real(dp) :: h, am, af, be, ga, bh2
      h = self%dt;  bh2 = self%beta * h**2
      am = self%am;  af = self%af;  be = self%beta;  ga = self%gamma
      s1%u = s0%u + h * s0%v + (0.5_dp - be) * h**2 * s0%a        ! u~
      s1%v = s0%v + (1.0_dp - ga) * h * s0%a                        ! v~
      ! t1 = (1-af) u~ + af u0 + gamma_R ((1-af) v~ + af v0); C = beta_R M + gamma_R K
      self%t1 = (1.0_dp - af) * s1%u + af * s0%u &
                + model%gamma * ((1.0_dp - af) * s1%v + af * s0%v)
      call matvec(self, model, model%sys%k, model%sys%k_band, self%t1, self%rhs)
      self%t1 = am * s0%a + model%beta * ((1.0_dp - af) * s1%v + af * s0%v)
      call matvec(self, model, model%sys%m, model%sys%m_band, self%t1, self%t2)
      self%t2 = ((1.0_dp - af) * p1 + af * p0) * model%q - self%rhs - self%t2
      if (has_modal_damping(model)) then       ! C_m ((1-af) v~ + af v0): C's modal part
         self%t1 = (1.0_dp - af) * s1%v + af * s0%v
         call dense_matvec(model%n, model%c_modal, self%t1, self%rhs)
         self%t2 = self%t2 - self%rhs
      end if
      call add_weighted_extra(model, s0%t, h, af, self%t1, self%t2)
      call kbar_solve(self, model, self%t2)
      self%t2 = self%t2 / bh2
      s1%u = s1%u + bh2 * self%t2
      s1%v = s1%v + ga * h * self%t2
   end subroutine accel_predictor

   !> rhs = rhs + (1 - af) P_x(t0 + h) + af P_x(t0), P_x the loads beyond the w-plane base
   !> motion (two planes, point forces; nothing otherwise).
   pure subroutine add_weighted_extra(model, t0, h, af, work, rhs)
      type(model_t), intent(in) :: model              !! model
      real(dp), intent(in) :: t0, h, af               !! step start, size, alpha_f
      real(dp), intent(inout) :: work(:)              !! workspace (n)
      real(dp), intent(inout) :: rhs(:)               !! right-hand side
      if (.not. model%extra_load) return
      work = 0.0_dp
      call add_extra_load(model, t0 + h, work)
      rhs = rhs + (1.0_dp - af) * work
      work = 0.0_dp
      call add_extra_load(model, t0, work)
      rhs = rhs + af * work
   end subroutine add_weighted_extra

   !> Local error estimate of the last step (see stepper_t%local_error): displacement
   !> c h^2 (a1 - a0) with c = beta - 1/6 + (1/2 - gamma)/2 (the Newmark estimate of Zienkiewicz
   !> and Xie, with the shift of the alpha methods' acceleration by (alpha_m - alpha_f) h =
   !> (1/2 - gamma) h), velocity h^3 a''/12 (the first-order term cancels in the second-order
   !> methods), a1 - a0 filtered by the step's operator (1 - am) Kbar^-1 M / (beta h^2).
   subroutine alpha_local_error(self, model, s0, s1, fda, ev, coef, has)
      class(alpha_stepper_t), intent(inout) :: self    !! stepper
      type(model_t), intent(in) :: model               !! model
      type(state_t), intent(in) :: s0, s1              !! the step
      real(dp), intent(out) :: fda(:)                  !! filtered a1 - a0
      real(dp), intent(out) :: ev(:)                   !! unused
      real(dp), intent(out) :: coef(3)                 !! error coefficients
      logical, intent(out) :: has                      !! an estimate is given
      has = .true.
      self%t1 = s1%a - s0%a
      call matvec(self, model, model%sys%m, model%sys%m_band, self%t1, fda)
      call kbar_solve(self, model, fda)
      fda = (1.0_dp - self%am) / (self%beta * self%dt**2) * fda
      ev = 0.0_dp
      coef = [self%beta - 1.0_dp / 6.0_dp + 0.5_dp * (0.5_dp - self%gamma), 0.0_dp, &
              1.0_dp / 12.0_dp]
   end subroutine alpha_local_error
end module gapbeam_alpha
