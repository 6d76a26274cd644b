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
   use gapbeam_problem, only: problem_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_stepper, only: stepper_t
   use gapbeam_contact, only: solve_scalar_contact
   use gapbeam_linalg, only: dense_matvec
   use gapbeam_newmark, only: state_load
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

   subroutine alpha_prepare(self, prob, cfg, dt, err)
      class(alpha_stepper_t), intent(inout) :: self
      type(problem_t), intent(in) :: prob
      type(solver_settings_t), intent(in) :: cfg
      real(dp), intent(in) :: dt
      type(error_t), allocatable, intent(out) :: err
      integer :: n, ns, info, j
      real(dp), allocatable :: kbar(:, :)
      call alpha_parameters(cfg%method, cfg%hht_alpha, cfg%rho_infinity, self%am, self%af, &
                            self%beta, self%gamma)
      n = prob%n;  ns = prob%n_slots
      kbar = (1.0_dp - self%am) / (self%beta * dt**2) * prob%sys%m &
             + (1.0_dp - self%af) * self%gamma / (self%beta * dt) * prob%c &
             + (1.0_dp - self%af) * prob%sys%k
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
         self%g(prob%slot_dof(j), j) = 1.0_dp
      end do
      if (ns > 0) call dpotrs('U', n, ns, self%fac, n, self%g, n, info)
      if (allocated(self%h)) deallocate(self%h)
      allocate(self%h(ns, ns))
      do j = 1, ns
         self%h(j, :) = self%g(prob%slot_dof(j), :)
      end do
      if (.not. allocated(self%rhs)) allocate(self%rhs(n), self%t1(n), self%t2(n))
      self%dt = dt
      self%ready = .true.
   end subroutine alpha_prepare

   subroutine alpha_step(self, prob, t0, u, v, a, f, f_prev, dt_prev, u1, v1, a1, f1, ok, ratio, &
                         open_contact)
      class(alpha_stepper_t), intent(inout) :: self
      type(problem_t), intent(in) :: prob
      real(dp), intent(in) :: t0, dt_prev
      real(dp), intent(in), contiguous :: u(:), v(:), a(:), f(:), f_prev(:)
      real(dp), intent(out), contiguous :: u1(:), v1(:), a1(:), f1(:)
      logical, intent(out) :: ok
      real(dp), intent(out) :: ratio
      integer, intent(in) :: open_contact
      real(dp) :: h, am, af, be, ga, s0, s1, ka, ds, vs, shift, fold, change, fmax
      integer :: n, info, c, o, i, si, sweeps
      n = prob%n;  h = self%dt
      am = self%am;  af = self%af;  be = self%beta;  ga = self%gamma
      ok = .true.;  ratio = -1.0_dp
      s0 = state_load(prob, t0)
      s1 = state_load(prob, t0 + h)
      ! rhs = (1-af) P1 + af P0 - am M a - af C v - af K u
      !       + (1-am) M [u/(be h^2) + v/(be h) + (1/(2be) - 1) a]
      !       + (1-af) C [ga/(be h) u - (1 - ga/be) v - h (1 - ga/(2 be)) a]
      self%t1 = -am * a + (1.0_dp - am) * (u / (be * h**2) + v / (be * h) &
                + (0.5_dp / be - 1.0_dp) * a)
      call dense_matvec(n, prob%sys%m, self%t1, self%rhs)
      self%t1 = -af * v + (1.0_dp - af) * (ga / (be * h) * u - (1.0_dp - ga / be) * v &
                - h * (1.0_dp - 0.5_dp * ga / be) * a)
      call dense_matvec(n, prob%c, self%t1, self%t2)
      self%rhs = self%rhs + self%t2
      call dense_matvec(n, prob%sys%k, u, self%t2)
      self%rhs = self%rhs - af * self%t2 + ((1.0_dp - af) * s1 + af * s0) * prob%q
      u1 = self%rhs
      call dpotrs('U', n, 1, self%fac, n, u1, n, info)
      ! contact forces at n+1-af from the condensed system (u1 = u1* - G s f)
      ka = ga / (be * h)
      f1 = 0.0_dp
      do sweeps = 1, merge(1, 1000, prob%n_contacts == 1)
         change = 0.0_dp;  fmax = 0.0_dp
         do c = 1, prob%n_contacts
            i = prob%c_dof(c);  si = prob%c_slot(c)
            shift = 0.0_dp
            do o = 1, prob%n_contacts
               if (o /= c) shift = shift + self%h(si, prob%c_slot(o)) * prob%c_sign(o) * f1(o)
            end do
            ! penetration and rate at n+1-af with this contact's force removed
            ds = prob%c_sign(c) * ((1.0_dp - af) * (u1(i) - shift) + af * u(i)) - prob%c_gap(c)
            vs = prob%c_sign(c) * ((1.0_dp - af) * (ka * (u1(i) - shift - u(i)) &
                 + (1.0_dp - ga / be) * v(i) + h * (1.0_dp - 0.5_dp * ga / be) * a(i)) &
                 + af * v(i))
            fold = f1(c)
            f1(c) = solve_scalar_contact(prob%c_law(c), prob%c_k(c), prob%c_c(c), prob%c_p(c), &
                       ds, vs, (1.0_dp - af) * self%h(si, si), ka)
            if (c == open_contact) f1(c) = 0.0_dp
            change = max(change, abs(f1(c) - fold));  fmax = max(fmax, f1(c))
         end do
         if (change <= 1.0e-14_dp * fmax .or. fmax == 0.0_dp) exit
      end do
      do c = 1, prob%n_contacts
         if (f1(c) /= 0.0_dp) u1 = u1 - self%g(:, prob%c_slot(c)) * (prob%c_sign(c) * f1(c))
      end do
      a1 = (u1 - u - h * v) / (be * h**2) - (0.5_dp / be - 1.0_dp) * a
      v1 = v + h * ((1.0_dp - ga) * a + ga * a1)
   end subroutine alpha_step
end module gapbeam_alpha
