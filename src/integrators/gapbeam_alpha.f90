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
module gapbeam_alpha
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dpotrf, dpotrs
   use gapbeam_model, only: model_t, load_factor
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_integrator, only: stepper_t
   use gapbeam_contact_law, only: solve_contacts
   use gapbeam_linalg, only: dense_matvec
   implicit none
   private
   public :: alpha_stepper_t, alpha_parameters

   !> HHT-alpha or generalized-alpha at one step size.
   type, extends(stepper_t) :: alpha_stepper_t
      real(dp) :: am = 0.0_dp, af = 0.0_dp, beta = 0.25_dp, gamma = 0.5_dp  !! parameters
      real(dp), allocatable :: fac(:, :)       !! Cholesky factor of Kbar
      real(dp), allocatable :: g(:, :)         !! Kbar^-1 E (n, n_slots)
      real(dp), allocatable :: h(:, :)         !! E' Kbar^-1 E
      real(dp), allocatable :: rhs(:), t1(:), t2(:)  !! workspaces
   contains
      procedure :: prepare => alpha_prepare
      procedure :: step => alpha_step
   end type alpha_stepper_t

contains

   !> (alpha_m, alpha_f, beta, gamma) of 'hht' (given alpha) or 'generalized_alpha' (given rho).
   pure subroutine alpha_parameters(method, hht_alpha, rho_inf, am, af, beta, gamma)
      character(len=*), intent(in) :: method      !! 'hht' or 'generalized_alpha'
      real(dp), intent(in) :: hht_alpha           !! HHT alpha in [-1/3, 0]
      real(dp), intent(in) :: rho_inf             !! generalized-alpha rho_inf in [0, 1]
      real(dp), intent(out) :: am, af, beta, gamma
      if (method == 'hht') then
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

   subroutine alpha_prepare(self, model, cfg, dt, err)
      class(alpha_stepper_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      real(dp), intent(in) :: dt
      type(error_t), allocatable, intent(out) :: err
      integer :: n, ns, info, j
      real(dp), allocatable :: kbar(:, :)
      call alpha_parameters(cfg%method, cfg%hht_alpha, cfg%rho_infinity, self%am, self%af, &
                            self%beta, self%gamma)
      n = model%n;  ns = model%n_slots
      kbar = (1.0_dp - self%am) / (self%beta * dt**2) * model%sys%m &
             + (1.0_dp - self%af) * self%gamma / (self%beta * dt) * model%c &
             + (1.0_dp - self%af) * model%sys%k
      call dpotrf('U', n, kbar, n, info)
      if (info /= 0) then
         call fatal_error(err, "method '" // trim(cfg%method) // "': effective stiffness not " &
            // 'positive definite (dpotrf info=' // str(info) // ', dt = ' // str(dt) // ' s)')
         return
      end if
      self%fac = kbar
      if (allocated(self%g)) deallocate(self%g)
      allocate(self%g(n, ns), source=0.0_dp)
      do j = 1, ns
         self%g(model%slot_dof(j), j) = 1.0_dp
      end do
      if (ns > 0) call dpotrs('U', n, ns, self%fac, n, self%g, n, info)
      if (allocated(self%h)) deallocate(self%h)
      allocate(self%h(ns, ns))
      do j = 1, ns
         self%h(j, :) = self%g(model%slot_dof(j), :)
      end do
      if (.not. allocated(self%rhs)) allocate(self%rhs(n), self%t1(n), self%t2(n))
      self%dt = dt
      self%ready = .true.
   end subroutine alpha_prepare

   !> One step (see stepper_t%step).
   subroutine alpha_step(self, model, s0, s1, ok, ratio, open_contact)
      class(alpha_stepper_t), intent(inout) :: self   !! stepper
      type(model_t), intent(in) :: model              !! model
      type(state_t), intent(in) :: s0                 !! start
      type(state_t), intent(inout) :: s1              !! end
      logical, intent(out) :: ok                      !! always true
      real(dp), intent(out) :: ratio                  !! no embedded estimate: -1
      integer, intent(in) :: open_contact             !! contact held open (0: none)
      real(dp) :: h, am, af, be, ga, p0, p1, ka
      real(dp) :: dstar(model%n_contacts), vstar(model%n_contacts)
      integer :: n, info, c, i
      n = model%n;  h = self%dt
      am = self%am;  af = self%af;  be = self%beta;  ga = self%gamma
      ok = .true.;  ratio = -1.0_dp
      p0 = load_factor(model, s0%t)
      p1 = load_factor(model, s0%t + h)
      s1%t = s0%t + h
      ! rhs = (1-af) P1 + af P0 - am M s0%a - af C s0%v - af K s0%u
      !       + (1-am) M [s0%u/(be h^2) + s0%v/(be h) + (1/(2be) - 1) s0%a]
      !       + (1-af) C [ga/(be h) s0%u - (1 - ga/be) s0%v - h (1 - ga/(2 be)) s0%a]
      self%t1 = -am * s0%a + (1.0_dp - am) * (s0%u / (be * h**2) + s0%v / (be * h) &
                + (0.5_dp / be - 1.0_dp) * s0%a)
      call dense_matvec(n, model%sys%m, self%t1, self%rhs)
      self%t1 = -af * s0%v + (1.0_dp - af) * (ga / (be * h) * s0%u - (1.0_dp - ga / be) * s0%v &
                - h * (1.0_dp - 0.5_dp * ga / be) * s0%a)
      call dense_matvec(n, model%c, self%t1, self%t2)
      self%rhs = self%rhs + self%t2
      call dense_matvec(n, model%sys%k, s0%u, self%t2)
      self%rhs = self%rhs - af * self%t2 + ((1.0_dp - af) * p1 + af * p0) * model%q
      s1%u = self%rhs
      call dpotrs('U', n, 1, self%fac, n, s1%u, n, info)
      ! contact forces at n+1-af from the condensed system (u1 = u1* - G s f): penetration
      ! and rate at n+1-af with zero contact forces, then the exact solve
      ka = ga / (be * h)
      do c = 1, model%n_contacts
         i = model%c_dof(c)
         dstar(c) = model%c_sign(c) * ((1.0_dp - af) * s1%u(i) + af * s0%u(i)) - model%c_gap(c)
         vstar(c) = model%c_sign(c) * ((1.0_dp - af) * (ka * (s1%u(i) - s0%u(i)) &
              + (1.0_dp - ga / be) * s0%v(i) + h * (1.0_dp - 0.5_dp * ga / be) * s0%a(i)) &
              + af * s0%v(i))
      end do
      s1%f = 0.0_dp
      call solve_contacts(model, self%h, 1.0_dp - af, ka, dstar, vstar, s1%f, open_contact)
      do c = 1, model%n_contacts
         if (s1%f(c) /= 0.0_dp) s1%u = s1%u - self%g(:, model%c_slot(c)) &
                                       * (model%c_sign(c) * s1%f(c))
      end do
      s1%a = (s1%u - s0%u - h * s0%v) / (be * h**2) - (0.5_dp / be - 1.0_dp) * s0%a
      s1%v = s0%v + h * ((1.0_dp - ga) * s0%a + ga * s1%a)
   end subroutine alpha_step
end module gapbeam_alpha
