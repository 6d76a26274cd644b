!> The modal exponential integrator: exact for the linear part, error-controlled on the rest.
!>
!> The model M u'' + C u' + K u = L(t) + F(t, u, u') is written in the undamped modes of
!> (K, M) (u = Phi x, Phi' M Phi = I, Phi' K Phi = Omega^2):
!>    x'' + D x' + Omega^2 x = Phi' L(t) + Phi' F(t, Phi x, Phi x'),
!> with D = Phi' C Phi. Its diagonal (Rayleigh and modal damping are diagonal in these modes)
!> and Omega^2 are the linear part: each mode a damped oscillator solved in closed form; the
!> harmonic loads L(t) (base motion in w and v, point forces: sin and cos of Omega_f t) are
!> solved exactly by their particular solution. What is left, N = Phi' F - D_off x' (contact and
!> ring forces with friction in the regimes of the step's start, turbulence, a non-proportional
!> damping's off-diagonal part), is approximated over a step by the quadratic through its values
!> at the nodes 0, h/2 and h (Lobatto collocation), and the oscillators are solved exactly under
!> that polynomial forcing (its particular polynomial, or, when omega h < 1, the Taylor series
!> of the forced solution, free of cancellation). The nodes' values come from Picard sweeps:
!> N at the start held constant, then three sweeps through the quadratic (stage error h^2, h^3,
!> h^4; the end h^5: order 4). The embedded estimate is the difference of the last two sweeps
!> (an h^4 estimate of the third sweep's error: the controller's order 3), plus the error of the
!> cubic Hermite interpolant of the step (the dense output that events and the recorder read)
!> at its midpoint against the method's own midpoint.
!>
!> So the step is set by how fast the contact, friction and turbulence forces change, and by
!> the interpolant, not by the retained modes' frequencies: a free linear response is exact to
!> round-off at any step. It needs a mass at every dof (M positive definite) and K positive
!> definite. Events (contact onset and release, stick-slip switches) are the stepping
!> integrator's, as for rk45: each step holds its start's ring regimes.
module gapbeam_exponential
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dsygv
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_integrator, only: stepper_t
   use gapbeam_contact_law, only: contact_force
   use gapbeam_ring_contact, only: ring_force
   use gapbeam_random_load, only: add_random_load
   implicit none
   private
   public :: exponential_t, oscillator_propagator

   integer, parameter :: n_sweeps = 3          ! Picard sweeps after the constant predictor
   real(dp), parameter :: taylor_below = 1.0_dp   ! omega h (and 2 zeta omega h) below: Taylor

   !> The modal exponential stepper (see the module's description).
   type, extends(stepper_t) :: exponential_t
      logical :: built = .false.               !! modal decomposition done
      integer :: n = 0                         !! coordinates
      real(dp) :: rtol = 1.0e-6_dp             !! step_control 'embedded': relative tolerance
      real(dp) :: atol = 1.0e-12_dp            !! and absolute [m, m/s]
      real(dp) :: wf = 0.0_dp                  !! forcing circular frequency [rad/s]
      real(dp), allocatable :: phi(:, :)       !! modes, M-orthonormal (u = Phi x)
      real(dp), allocatable :: phi_abs(:, :)   !! |Phi| (the round-off of u = Phi x)
      real(dp), allocatable :: phit_m(:, :)    !! Phi' M (x = Phi' M u)
      real(dp), allocatable :: w2(:)           !! omega^2 per mode [1/s^2]
      real(dp), allocatable :: ad(:)           !! half the modal damping, zeta omega [1/s]
      real(dp), allocatable :: doff(:, :)      !! off-diagonal modal damping (when present)
      logical :: harmonic = .false.            !! harmonic loads in the linear part
      real(dp), allocatable :: ls(:), lc(:)    !! harmonic loads: sin and cos parts [N]
      real(dp), allocatable :: fs(:), fc(:)    !! their modal loads
      real(dp), allocatable :: hs(:), hc(:)    !! particular solution hs sin + hc cos
      integer, allocatable :: act(:)           !! dofs where contact and ring forces act
      integer, allocatable :: ia(:)            !! position of a dof in act (0: none)
      real(dp), allocatable :: phia(:, :)      !! Phi(act, :)
      logical :: dense_n = .false.             !! N needs a whole load vector
      real(dp), allocatable :: cn(:, :), sn(:, :)   !! propagator at h/2, h: c(tau), s(tau)
      !> responses from rest to the forcing s^j (s = tau / h), j = 0..2, at the nodes h/2, h:
      !> displacement and velocity (n, 0:2, 2)
      real(dp), allocatable :: rx(:, :, :), ry(:, :, :)
      real(dp), allocatable :: x(:, :), y(:, :)     !! node states (n, 0:2)
      real(dp), allocatable :: g(:, :)         !! N at the nodes (n, 0:2)
      real(dp), allocatable :: z0(:), zd0(:), ua(:), va(:), ra(:), r(:)
      real(dp), allocatable :: eu(:), ev(:)    !! embedded errors of the last step
      real(dp), allocatable :: fn(:), ft(:)    !! ring forces of the last evaluation [N]
   contains
      procedure :: prepare => ex_prepare
      procedure :: step => ex_step
      procedure :: local_error => ex_local_error
   end type exponential_t

contains

   !> c(tau) = e^(-a tau) C(tau), s(tau) = e^(-a tau) S(tau) of the damped oscillator
   !> x'' + 2 a x' + w2 x = 0: x(tau) = x0 (c + a s) + v0 s, x'(tau) = v0 (c - a s) - w2 x0 s
   !> (under-, critically and over-damped alike).
   elemental subroutine oscillator_propagator(w2, a, tau, c, s)
      real(dp), intent(in) :: w2, a, tau   !! omega^2 [1/s^2], zeta omega [1/s], time [s]
      real(dp), intent(out) :: c, s        !! the two functions
      real(dp) :: mu2, mu, e
      mu2 = w2 - a * a
      e = exp(-a * tau)
      if (mu2 > 0.0_dp) then
         mu = sqrt(mu2)
         c = e * cos(mu * tau);  s = e * sin(mu * tau) / mu
      else if (mu2 < 0.0_dp) then
         mu = sqrt(-mu2)
         if (mu * tau < 1.0_dp) then
            c = e * cosh(mu * tau);  s = e * sinh(mu * tau) / mu
         else
            c = 0.5_dp * (exp((mu - a) * tau) + exp(-(mu + a) * tau))
            s = 0.5_dp * (exp((mu - a) * tau) - exp(-(mu + a) * tau)) / mu
         end if
      else
         c = e;  s = tau * e
      end if
   end subroutine oscillator_propagator

   !> The modal decomposition (once): modes, modal damping, harmonic particular solution, the
   !> dofs where forces act.
   subroutine build(self, model, cfg, err)
      class(exponential_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      type(error_t), allocatable, intent(out) :: err
      real(dp), allocatable :: a(:, :), b(:, :), work(:), d(:, :)
      real(dp) :: wq(1), det, e2, dmax
      integer :: n, info, j, c, k
      n = model%n;  self%n = n
      a = model%sys%k;  b = model%sys%m
      allocate(self%w2(n))
      call dsygv(1, 'V', 'U', n, a, n, b, n, self%w2, wq, -1, info)
      allocate(work(max(1, int(wq(1)))))
      call dsygv(1, 'V', 'U', n, a, n, b, n, self%w2, work, size(work), info)
      if (info > n) then
         call fatal_error(err, "method '" // trim(cfg%method) // "': the mass matrix is " &
            // 'singular (dof ' // str(info - n) // ' has no mass); the exponential method ' &
            // "needs a mass at every dof: use &beam rotary_inertia = 'half_element' or " &
            // "'hrz', or an implicit method")
         return
      else if (info /= 0) then
         call fatal_error(err, "method '" // trim(cfg%method) // "': dsygv failed (info=" &
            // str(info) // ')')
         return
      end if
      if (self%w2(1) <= 0.0_dp) then
         call fatal_error(err, "method '" // trim(cfg%method) // "': the stiffness matrix " &
            // 'is not positive definite (lowest omega^2 = ' // str(self%w2(1)) // ' 1/s^2)')
         return
      end if
      self%phi = a
      self%phi_abs = abs(a)
      self%phit_m = matmul(transpose(a), model%sys%m)
      d = matmul(transpose(a), matmul(model%c, a))
      allocate(self%ad(n))
      dmax = 0.0_dp
      do j = 1, n
         self%ad(j) = 0.5_dp * d(j, j)
         dmax = max(dmax, abs(d(j, j)))
         d(j, j) = 0.0_dp
      end do
      ! proportional damping leaves round-off off the diagonal: below it, none
      if (maxval(abs(d)) > 1.0e-10_dp * max(dmax, sqrt(self%w2(n)) * 1.0e-12_dp)) &
         self%doff = d
      ! the harmonic loads: base motion (w, and v at its phase) and point forces
      self%wf = model%omega
      allocate(self%ls(n), self%lc(n))
      self%ls = model%half_amplitude * model%omega**2 * model%q
      self%lc = 0.0_dp
      if (model%extra_load) then
         if (allocated(model%q_v)) then
            self%ls = self%ls + model%half_amplitude * model%omega**2 * cos(model%phase_v) &
                      * model%q_v
            self%lc = self%lc + model%half_amplitude * model%omega**2 * sin(model%phase_v) &
                      * model%q_v
         end if
         if (allocated(model%p_sin)) then
            self%ls = self%ls + model%p_sin;  self%lc = self%lc + model%p_cos
         end if
      end if
      self%fs = matmul(self%ls, a);  self%fc = matmul(self%lc, a)
      allocate(self%hs(n), self%hc(n))
      self%harmonic = .true.
      do j = 1, n
         e2 = self%w2(j) - self%wf**2
         det = e2**2 + (2.0_dp * self%ad(j) * self%wf)**2
         if (det <= 1.0e-20_dp * self%w2(j)**2) then
            ! undamped at resonance: no bounded particular solution; the loads go to N
            self%harmonic = .false.;  exit
         end if
         self%hs(j) = (e2 * self%fs(j) + 2.0_dp * self%ad(j) * self%wf * self%fc(j)) / det
         self%hc(j) = (e2 * self%fc(j) - 2.0_dp * self%ad(j) * self%wf * self%fs(j)) / det
      end do
      if (.not. self%harmonic) then
         self%hs = 0.0_dp;  self%hc = 0.0_dp
      end if
      ! where the contact and ring forces act
      allocate(self%ia(n), source=0)
      self%act = [integer ::]
      do c = 1, model%n_contacts
         call add_dof(model%c_dof(c))
      end do
      do c = 1, model%n_rings
         call add_dof(model%r_dof(1, c));  call add_dof(model%r_dof(2, c))
      end do
      self%phia = a(self%act, :)
      self%dense_n = model%turbulence%active .or. allocated(self%doff) .or. &
                     (.not. self%harmonic .and. (any(self%ls /= 0.0_dp) .or. &
                     any(self%lc /= 0.0_dp)))
      k = size(self%act)
      allocate(self%cn(n, 2), self%sn(n, 2), self%rx(n, 0:2, 2), self%ry(n, 0:2, 2), &
               self%x(n, 0:2), self%y(n, 0:2), &
               self%g(n, 0:2), self%z0(n), self%zd0(n), self%ua(k), self%va(k), self%ra(k), &
               self%r(n), self%eu(n), self%ev(n), self%fn(model%n_rings), &
               self%ft(model%n_rings))
      self%built = .true.
   contains
      subroutine add_dof(i)
         integer, intent(in) :: i
         if (self%ia(i) > 0) return
         self%act = [self%act, i]
         self%ia(i) = size(self%act)
      end subroutine add_dof
   end subroutine build

   subroutine ex_prepare(self, model, cfg, dt, err)
      class(exponential_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      real(dp), intent(in) :: dt
      type(error_t), allocatable, intent(out) :: err
      integer :: k, j
      self%rtol = cfg%rk_rtol;  self%atol = cfg%rk_atol
      if (.not. self%built) then
         call build(self, model, cfg, err)
         if (allocated(err)) return
      end if
      do k = 1, 2
         call oscillator_propagator(self%w2, self%ad, 0.5_dp * k * dt, self%cn(:, k), &
                                    self%sn(:, k))
      end do
      do k = 1, 2
         do j = 1, self%n
            call forced_response(self%w2(j), self%ad(j), dt, 0.5_dp * k, 1.0_dp, 0.0_dp, &
                                 0.0_dp, self%rx(j, 0, k), self%ry(j, 0, k))
            call forced_response(self%w2(j), self%ad(j), dt, 0.5_dp * k, 0.0_dp, 1.0_dp, &
                                 0.0_dp, self%rx(j, 1, k), self%ry(j, 1, k))
            call forced_response(self%w2(j), self%ad(j), dt, 0.5_dp * k, 0.0_dp, 0.0_dp, &
                                 1.0_dp, self%rx(j, 2, k), self%ry(j, 2, k))
         end do
      end do
      self%dt = dt
      self%ready = .true.
   end subroutine ex_prepare

   !> N(t, x, x') in modal coordinates: the contact and ring forces (rings in the regimes of
   !> s0; `hold` > 0 held open), turbulence, harmonic loads when not exact, -D_off x'. Contact
   !> forces into f, ring forces into self%fn, self%ft.
   subroutine nonlinear(self, model, s0, t, x, y, hold, gm, f)
      class(exponential_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: s0
      real(dp), intent(in) :: t, x(:), y(:)
      integer, intent(in) :: hold
      real(dp), intent(out) :: gm(:), f(:)
      integer :: c, i, rg, na
      integer :: ja(2)
      real(dp) :: pr(2)
      na = size(self%act)
      if (na > 0) then
         self%ua = matmul(self%phia, x);  self%va = matmul(self%phia, y)
      end if
      self%ra = 0.0_dp
      do c = 1, model%n_contacts
         i = self%ia(model%c_dof(c))
         f(c) = contact_force(model, c, model%c_sign(c) * self%ua(i) - model%c_gap(c), &
                              model%c_sign(c) * self%va(i))
         if (c == hold) f(c) = 0.0_dp
         self%ra(i) = self%ra(i) - model%c_sign(c) * f(c)
      end do
      do rg = 1, model%n_rings
         if (rg + model%n_contacts == hold) then
            self%fn(rg) = 0.0_dp;  self%ft(rg) = 0.0_dp
            cycle
         end if
         ja = self%ia(model%r_dof(:, rg))
         call ring_force(model, rg, s0%mode(rg), s0%sigma(rg), s0%anchor(rg), self%ua(ja), &
                         self%va(ja), pr, self%fn(rg), self%ft(rg))
         self%ra(ja) = self%ra(ja) + pr
      end do
      if (na > 0) then
         gm = matmul(self%ra, self%phia)
      else
         gm = 0.0_dp
      end if
      self%evaluations = self%evaluations + 1
      if (.not. self%dense_n) return
      self%r = 0.0_dp
      if (.not. self%harmonic) self%r = sin(self%wf * t) * self%ls + cos(self%wf * t) * self%lc
      call add_random_load(model%turbulence, t, self%r)
      gm = gm + matmul(self%r, self%phi)
      if (allocated(self%doff)) gm = gm - matmul(self%doff, y)
   end subroutine nonlinear

   !> The oscillators from the start's deviation (z0, zd0) from the harmonic solution, forced by
   !> the quadratic G0 + G1 s + G2 s^2 (s = tau / h), at the nodes s = 1/2 and 1: into x, y
   !> (harmonic solution added) at columns 1 and 2.
   subroutine propagate(self, t0, g0, g1, g2)
      class(exponential_t), intent(inout) :: self
      real(dp), intent(in) :: t0
      real(dp), intent(in) :: g0(:), g1(:), g2(:)
      real(dp) :: tau, sk, tk
      integer :: k
      do k = 1, 2
         tau = 0.5_dp * k * self%dt
         sk = sin(self%wf * (t0 + tau));  tk = cos(self%wf * (t0 + tau))
         ! (an associate name of a section has lower bounds 1: the responses' j = 0..2 are 1..3)
         associate (c => self%cn(:, k), s => self%sn(:, k), a => self%ad, &
                    rx => self%rx(:, :, k), ry => self%ry(:, :, k))
            self%x(:, k) = self%z0 * (c + a * s) + self%zd0 * s + g0 * rx(:, 1) &
                           + g1 * rx(:, 2) + g2 * rx(:, 3) + self%hs * sk + self%hc * tk
            self%y(:, k) = self%zd0 * (c - a * s) - self%w2 * self%z0 * s + g0 * ry(:, 1) &
                           + g1 * ry(:, 2) + g2 * ry(:, 3) + self%wf * (self%hs * tk - self%hc * sk)
         end associate
      end do
   end subroutine propagate

   !> The response from rest of x'' + 2 a x' + w2 x = g0 + g1 s + g2 s^2 (s = tau / h) at s:
   !> by the Taylor series in s when omega h and 2 a h are below 1 (no cancellation between the
   !> homogeneous and the particular parts), else by the particular polynomial.
   pure subroutine forced_response(w2, a, h, s, g0, g1, g2, x, v)
      real(dp), intent(in) :: w2, a, h, s, g0, g1, g2
      real(dp), intent(out) :: x, v
      real(dp) :: c0, c1, c2, c, sn, tau
      if (sqrt(w2) * h < taylor_below .and. 2.0_dp * a * h < taylor_below) then
         call taylor_node(w2, a, h, s, 0.0_dp, 0.0_dp, g0, g1, g2, x, v)
         return
      end if
      tau = s * h
      c2 = g2 / h**2 / w2
      c1 = (g1 / h - 4.0_dp * a * c2) / w2
      c0 = (g0 - 2.0_dp * a * c1 - 2.0_dp * c2) / w2
      call oscillator_propagator(w2, a, tau, c, sn)
      x = -c0 * (c + a * sn) - c1 * sn + c0 + tau * (c1 + tau * c2)
      v = -c1 * (c - a * sn) + w2 * c0 * sn + c1 + 2.0_dp * tau * c2
   end subroutine forced_response

   !> The forced oscillator x'' + 2 a x' + w2 x = g0 + g1 s + g2 s^2 (s = tau / h) at s by its
   !> Taylor series in s (omega h < 1: no cancellation between the homogeneous and the
   !> particular parts).
   pure subroutine taylor_node(w2, a, h, s, x0, v0, g0, g1, g2, x, v)
      real(dp), intent(in) :: w2, a, h, s, x0, v0, g0, g1, g2
      real(dp), intent(out) :: x, v
      real(dp) :: xk(0:80), gk, scale, sp
      integer :: k
      xk(0) = x0;  xk(1) = h * v0
      x = xk(0) + s * xk(1);  v = xk(1)
      scale = max(abs(xk(0)), abs(xk(1)), abs(g0 * h * h), abs(g1 * h * h), abs(g2 * h * h))
      sp = s
      do k = 0, 78
         gk = 0.0_dp
         if (k == 0) gk = g0
         if (k == 1) gk = g1
         if (k == 2) gk = g2
         xk(k + 2) = (gk * h * h - 2.0_dp * a * h * (k + 1) * xk(k + 1) - w2 * h * h * xk(k)) &
                     / real((k + 1) * (k + 2), dp)
         v = v + (k + 2) * xk(k + 2) * sp
         sp = sp * s
         x = x + xk(k + 2) * sp
         scale = max(scale, abs(xk(k + 2)))
         if (k >= 3 .and. abs(xk(k + 2)) + abs(xk(k + 1)) <= 1.0e-18_dp * scale) exit
      end do
      v = v / h
   end subroutine taylor_node

   !> One step (see stepper_t%step).
   subroutine ex_step(self, model, s0, s1, ok, ratio, open_contact)
      class(exponential_t), intent(inout) :: self        !! stepper
      type(model_t), intent(in) :: model                 !! model
      type(state_t), intent(in) :: s0                    !! start
      type(state_t), intent(inout) :: s1                 !! end
      logical, intent(out) :: ok                         !! always true
      real(dp), intent(out) :: ratio                     !! embedded error / tolerance
      integer, intent(in) :: open_contact                !! contact held open (0: none)
      real(dp) :: h, t0, t1, sk, tk, sc, um, vm
      real(dp) :: xe(self%n), ye(self%n), ge(self%n), g1(self%n), g2(self%n), zero(self%n)
      real(dp) :: ru0(self%n), ru1(self%n), rv(self%n)
      integer :: sweep, i
      ! (the node arrays are named through self: an associate name of a component that a
      ! called procedure redefines may be a copy)
      h = self%dt;  t0 = s0%t;  t1 = t0 + h;  ok = .true.
      s1%t = t1
      self%x(:, 0) = matmul(self%phit_m, s0%u);  self%y(:, 0) = matmul(self%phit_m, s0%v)
      sk = sin(self%wf * t0);  tk = cos(self%wf * t0)
      self%z0 = self%x(:, 0) - (self%hs * sk + self%hc * tk)
      self%zd0 = self%y(:, 0) - self%wf * (self%hs * tk - self%hc * sk)
      xe = self%x(:, 0);  ye = self%y(:, 0)
      call nonlinear(self, model, s0, t0, xe, ye, open_contact, ge, s1%f)
      self%g(:, 0) = ge
      zero = 0.0_dp
      call propagate(self, t0, ge, zero, zero)
      do sweep = 1, n_sweeps
         xe = self%x(:, 1);  ye = self%y(:, 1)
         call nonlinear(self, model, s0, t0 + 0.5_dp * h, xe, ye, open_contact, g1, s1%f)
         xe = self%x(:, 2);  ye = self%y(:, 2)
         call nonlinear(self, model, s0, t1, xe, ye, open_contact, g2, s1%f)
         self%g(:, 1) = g1;  self%g(:, 2) = g2
         call propagate(self, t0, ge, 4.0_dp * g1 - 3.0_dp * ge - g2, &
                        2.0_dp * (g2 - 2.0_dp * g1 + ge))
      end do
      ! xe, ye: the end of the previous sweep
      xe = self%x(:, 2) - xe;  ye = self%y(:, 2) - ye
      s1%u = matmul(self%phi, self%x(:, 2));  s1%v = matmul(self%phi, self%y(:, 2))
      self%eu = matmul(self%phi, xe);  self%ev = matmul(self%phi, ye)
      ! forces and acceleration at the end (no contact held: as rk45's last stage)
      xe = self%x(:, 2);  ye = self%y(:, 2)
      call nonlinear(self, model, s0, t1, xe, ye, 0, ge, s1%f)
      if (self%harmonic) ge = ge + sin(self%wf * t1) * self%fs + cos(self%wf * t1) * self%fc
      ge = ge - 2.0_dp * self%ad * ye - self%w2 * xe
      s1%a = matmul(self%phi, ge)
      ! the error: the last two sweeps, and the cubic Hermite interpolant at the midpoint
      xe = matmul(self%phi, self%x(:, 1));  ye = matmul(self%phi, self%y(:, 1))
      ru0 = matmul(self%phi_abs, abs(self%x(:, 0)))
      ru1 = matmul(self%phi_abs, abs(self%x(:, 2)))
      rv = matmul(self%phi_abs, abs(self%y(:, 0))) + matmul(self%phi_abs, abs(self%y(:, 2)))
      ratio = 0.0_dp
      do i = 1, self%n
         ! the sweeps' difference below the round-off of Phi x, Phi x': nothing to control
         if (abs(self%eu(i)) <= 16.0_dp * epsilon(1.0_dp) * (ru0(i) + ru1(i))) &
            self%eu(i) = 0.0_dp
         if (abs(self%ev(i)) <= 16.0_dp * epsilon(1.0_dp) * rv(i)) self%ev(i) = 0.0_dp
         um = xe(i) - (0.5_dp * (s0%u(i) + s1%u(i)) + 0.125_dp * h * (s0%v(i) - s1%v(i)))
         vm = ye(i) - (1.5_dp * (s1%u(i) - s0%u(i)) / h - 0.25_dp * (s0%v(i) + s1%v(i)))
         ! the interpolant carries the round-off of u = Phi x (eps sum_j |Phi_ij x_j| at each
         ! end), its velocity that over h: below it, no error to control (as the wear watch
         ! does for an implicit step's velocity)
         if (abs(um) <= 16.0_dp * epsilon(1.0_dp) * (ru0(i) + ru1(i))) um = 0.0_dp
         if (abs(vm) <= 16.0_dp * epsilon(1.0_dp) * (ru0(i) + ru1(i)) / h) vm = 0.0_dp
         self%eu(i) = sign(abs(self%eu(i)) + abs(um), self%eu(i))
         self%ev(i) = sign(abs(self%ev(i)) + abs(vm), self%ev(i))
         sc = self%atol + self%rtol * max(abs(s0%u(i)), abs(s1%u(i)))
         ratio = max(ratio, abs(self%eu(i)) / sc)
         sc = self%atol + self%rtol * max(abs(s0%v(i)), abs(s1%v(i)))
         ratio = max(ratio, abs(self%ev(i)) / sc)
      end do
      if (model%n_rings > 0) then
         s1%fn = self%fn;  s1%ft = self%ft
         s1%mode = s0%mode;  s1%sigma = s0%sigma;  s1%anchor = s0%anchor
      end if
   end subroutine ex_step

   !> The embedded estimate of the last step (see the module's description).
   subroutine ex_local_error(self, model, s0, s1, fda, ev, coef, has)
      class(exponential_t), intent(inout) :: self      !! stepper
      type(model_t), intent(in) :: model               !! model
      type(state_t), intent(in) :: s0, s1              !! the step
      real(dp), intent(out) :: fda(:)                  !! e_u / h^2
      real(dp), intent(out) :: ev(:)                   !! the velocity error
      real(dp), intent(out) :: coef(3)                 !! [1, -1, 0]: e_u = h^2 fda, ev given
      logical, intent(out) :: has                      !! always
      has = .true.
      coef = [1.0_dp, -1.0_dp, 0.0_dp]
      fda = self%eu / self%dt**2;  ev = self%ev
   end subroutine ex_local_error
end module gapbeam_exponential
