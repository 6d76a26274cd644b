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
!> damping's off-diagonal part), is approximated over a step by the cubic through its values
!> at Lobatto's four nodes 0, (5 - sqrt 5) / 10, (5 + sqrt 5) / 10 and 1 (times h), and the
!> oscillators are solved exactly under that polynomial forcing (its particular polynomial, or,
!> when omega h < 1, the Taylor series of the forced solution, free of cancellation). The nodes'
!> values come from Picard sweeps: N at the start held constant, then five sweeps through the
!> cubic (stage errors h^2 ... h^6: order 5; a sweep whose node forces repeat the previous
!> sweep's bit for bit ends them). Where N is the contact and ring forces alone, the sweeps run
!> at the dofs where those act (act_sweeps: the nodes' displacements and velocities there from
!> the forces through the step size's na x na sensitivities), and the modes are propagated once,
!> from the last sweep's forces (4-7 % less CPU on the tube map's points; the same steps and
!> outputs to the round-off). The error estimate has two parts: the last two sweeps'
!> difference, and the collocation's own error, N at the check node h/2 against the cubic there
!> (the leading, h^4 N'''' term of the cubic's error, C4 s (s - a) (s - b) (s - 1)), carried to
!> the end by the oscillators' exact response to that quartic (the controller's order 5). The
!> quadratic through 0, h/2, h with four sweeps (order 4) took 1.9 and 2.6 times the steps on
!> the tube deck and its periodic case. The errors of the step's Hermite interpolants at its
!> midpoint against the method's own midpoint are returned apart (dense_error): the cubic from
!> u, v at both ends and the quintic from u, v, a, which samples, states and the wear
!> statistics read, and on which the events of a ring in contact at the step's start are
!> located, and the onset of a ring that a trial step entered, on that step redone with the
!> ring held open (the entering step itself ends with the contact's acceleration, which bends
!> its quintic before the onset). The integrator controls them per step, since the next step
!> starts from the method's end state, not from an interpolant: the cubic on what its events
!> read, the quintic on every watched output. (The cubic checked on every output, the root strain
!> among them, bounded 28 % of the tube deck's steps: its error, ~ (omega h)^4 / 384 of a
!> ringing static mode against the quintic's ~ (omega h)^6 / 46080.)
!>
!> The step is taken in increment form: the oscillators give the change of each modal
!> coordinate over the step (c - 1 by expm1, the harmonic terms' change by the product formulas
!> of sin a - sin b), the end state is u0 + Phi dx, and the interpolant's check is made on the
!> increments. So the round-off of a step is that of its change, not of the state: with
!> u1 = Phi x1 (and x0 = Phi' M u0) the interpolant's velocity (u1 - u0) / h carried
!> eps |u| / h, which the controller read as an error growing as the step shrank; it drove the
!> steps of a tube near a grazing onset down to the smallest one ('step below the minimum').
!>
!> So the step is set by how fast the contact, friction and turbulence forces change, and by
!> the interpolant, not by the retained modes' frequencies: a free linear response is exact to
!> round-off at any step. It needs a mass at every dof (M positive definite) and K positive
!> definite. Events (contact onset and release, stick-slip switches) are the stepping
!> integrator's, as for rk45: each step holds its start's ring regimes.
module gapbeam_exponential
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dsygv, dgemm, dgesv
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_integrator, only: stepper_t
   use gapbeam_contact_law, only: contact_force
   use gapbeam_ring_contact, only: ring_force, ring_open
   use gapbeam_random_load, only: add_random_load
   implicit none
   private
   public :: exponential_t, oscillator_propagator, oscillator_cm1, expm1

   integer, parameter :: n_sweeps = 5          ! Picard sweeps after the constant predictor
   real(dp), parameter :: taylor_below = 1.0_dp   ! omega h (and 2 zeta omega h) below: Taylor
   real(dp), parameter :: sq5 = 2.23606797749978969640917_dp
   !> the nodes' fractions of the step: Lobatto's (5 -+ sqrt 5) / 10 and 1, and the check node 1/2
   real(dp), parameter :: node_s(4) = [(5.0_dp - sq5) / 10.0_dp, (5.0_dp + sq5) / 10.0_dp, &
                                       1.0_dp, 0.5_dp]
   integer, parameter :: k_end = 3, k_mid = 4
   !> the error shape s (s - a) (s - b) (s - 1) = s^4 - 2 s^3 + 1.2 s^2 - 0.2 s, its value at 1/2
   real(dp), parameter :: w4_mid = 0.0125_dp

   !> The modal exponential stepper (see the module's description).
   type, extends(stepper_t) :: exponential_t
      logical :: built = .false.               !! modal decomposition done
      integer :: n = 0                         !! coordinates
      real(dp) :: rtol = 1.0e-6_dp             !! step_control 'embedded': relative tolerance
      real(dp) :: atol = 1.0e-12_dp            !! and absolute [m, m/s]
      !> step_control 'embedded': the step's ratio is computed (else the controller reads
      !> the estimates through local_error and dense_error, and the ratio is not used)
      logical :: embedded = .false.
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
      real(dp), allocatable :: vh(:)           !! |Phi| (|hs| + |hc|) Omega_f: its velocity's bound
      integer, allocatable :: act(:)           !! dofs where contact and ring forces act
      integer, allocatable :: ia(:)            !! position of a dof in act (0: none)
      real(dp), allocatable :: phia(:, :)      !! Phi(act, :)
      real(dp), allocatable :: phiat(:, :)     !! its transpose Phi(act, :)' (contiguous rows)
      !> the step's workspace (allocated once: gfortran puts automatic arrays on the heap):
      !> vectors (n, 9), the products with Phi (n, 11) and with Phi' M, |Phi| (n, 3)
      real(dp), allocatable :: wv(:, :), w7(:, :), p7(:, :), w2c(:, :), p2c(:, :)
      logical :: dense_n = .false.             !! N needs a whole load vector
      real(dp) :: vinv(3, 3) = 0.0_dp               !! the cubic's coefficients from the nodes
      real(dp), allocatable :: cn(:, :), sn(:, :)   !! propagator at the nodes: c, s(tau)
      real(dp), allocatable :: cm1(:, :)            !! c(tau) - 1 there (no cancellation)
      !> responses from rest to the forcing s^j (s = tau / h), j = 0..3, at the nodes (node_s:
      !> Lobatto's two inner nodes, the end, and the check node h/2): displacement and velocity
      !> (n, 0:3, 4)
      real(dp), allocatable :: rx(:, :, :), ry(:, :, :)
      real(dp), allocatable :: x(:, :), y(:, :)     !! node states (n, 0:4)
      real(dp), allocatable :: dx(:, :), dy(:, :)   !! their changes from the start (n, 0:4)
      real(dp), allocatable :: fx(:, :), fy(:, :)   !! the changes without N (n, 4)
      real(dp), allocatable :: g(:, :)         !! N at the nodes (n, 0:3)
      real(dp), allocatable :: z0(:), zd0(:), ua(:), va(:), ra(:), r(:)
      real(dp), allocatable :: ua0(:), va0(:)  !! the start's displacement, velocity at act
      real(dp), allocatable :: eu(:), ev(:)    !! embedded errors of the last step
      real(dp), allocatable :: iu(:), iv(:)    !! its cubic interpolant's errors at the midpoint
      real(dp), allocatable :: iq(:), ivq(:)   !! its quintic interpolant's errors there
      !> the response from rest at h to the forcing s (s - a) (s - b) (s - 1) (the cubic's error
      !> shape through the nodes): displacement and velocity
      real(dp), allocatable :: ex(:), ey(:)
      real(dp), allocatable :: fn(:), ft(:)    !! ring forces of the last evaluation [N]
      real(dp), allocatable :: a0(:)           !! the start's acceleration in the modes
      !> the sweeps at the act dofs (act_sweeps): their displacements (gu) and velocities (gv)
      !> at the node k = 1..3 against N's value there from the start's (m = 0) and the nodes'
      !> (m = 1..3) forces at the act dofs through the cubic, (na, na, 3, 0:3) per step size
      real(dp), allocatable :: gu(:, :, :, :), gv(:, :, :, :)
      real(dp), allocatable :: pk(:, :), pp(:, :)   !! the nodes' act forces: this, last sweep
      real(dp), allocatable :: dq(:, :)             !! the last sweep's changes from the start
      real(dp), allocatable :: bu(:, :), bv(:, :)   !! the nodes' act states without N's change
      !> the sweeps at the act dofs where they apply (else always the modal sweeps: the tests
      !> compare the two)
      logical :: sweep_at_act = .true.
   contains
      procedure :: prepare => ex_prepare
      procedure :: step => ex_step
      procedure :: local_error => ex_local_error
      procedure :: dense_error => ex_dense_error
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

   !> c(tau) - 1 of oscillator_propagator without cancellation (a step's change of a mode
   !> from its displacement: x(tau) - x0 = x0 (c - 1 + a s) + v0 s).
   elemental real(dp) function oscillator_cm1(w2, a, tau) result(cm1)
      real(dp), intent(in) :: w2, a, tau   !! omega^2 [1/s^2], zeta omega [1/s], time [s]
      real(dp) :: mu2, mu, em1
      mu2 = w2 - a * a
      em1 = expm1(-a * tau)
      if (mu2 > 0.0_dp) then
         mu = sqrt(mu2)
         cm1 = em1 * cos(mu * tau) - 2.0_dp * sin(0.5_dp * mu * tau)**2
      else if (mu2 < 0.0_dp) then
         mu = sqrt(-mu2)
         if (mu * tau < 1.0_dp) then
            cm1 = em1 * cosh(mu * tau) + 2.0_dp * sinh(0.5_dp * mu * tau)**2
         else
            cm1 = 0.5_dp * (expm1((mu - a) * tau) + expm1(-(mu + a) * tau))
         end if
      else
         cm1 = em1
      end if
   end function oscillator_cm1

   !> e^x - 1 without cancellation for small |x| (2 t / (1 - t), t = tanh(x / 2)).
   elemental real(dp) function expm1(x) result(r)
      real(dp), intent(in) :: x   !! argument
      real(dp) :: t
      if (abs(x) < 0.5_dp) then
         t = tanh(0.5_dp * x)
         r = 2.0_dp * t / (1.0_dp - t)
      else
         r = exp(x) - 1.0_dp
      end if
   end function expm1

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
      self%vh = matmul(abs(a), abs(self%hs) + abs(self%hc)) * self%wf
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
      self%phiat = transpose(self%phia)
      self%dense_n = model%turbulence%active .or. allocated(self%doff) .or. &
                     (.not. self%harmonic .and. (any(self%ls /= 0.0_dp) .or. &
                     any(self%lc /= 0.0_dp)))
      k = size(self%act)
      allocate(self%cn(n, 4), self%sn(n, 4), self%cm1(n, 4), self%rx(n, 0:3, 4), &
               self%ry(n, 0:3, 4), self%x(n, 0:4), self%y(n, 0:4), self%dx(n, 0:4), &
               self%dy(n, 0:4), self%fx(n, 4), self%fy(n, 4), self%ua0(k), self%va0(k), &
               self%g(n, 0:3), self%z0(n), self%zd0(n), self%ua(k), self%va(k), self%ra(k), &
               self%r(n), self%eu(n), self%ev(n), self%iu(n), self%iv(n), self%ex(n), &
               self%ey(n), self%a0(n), &
               self%fn(model%n_rings), &
               self%ft(model%n_rings), self%wv(n, 11), self%w7(n, 11), self%p7(n, 11), &
               self%iq(n), self%ivq(n), &
               self%w2c(n, 3), self%p2c(n, 3))
      allocate(self%gu(k, k, 3, 0:3), self%gv(k, k, 3, 0:3), self%pk(k, 0:3), self%pp(k, 3), &
               self%bu(k, 3), self%bv(k, 3), self%dq(k, 3))
      block
         real(dp) :: vm(3, 3)
         integer :: ip(3), inf, i2
         do i2 = 1, 3
            vm(i2, :) = [node_s(i2), node_s(i2)**2, node_s(i2)**3]
         end do
         self%vinv = 0.0_dp
         do i2 = 1, 3
            self%vinv(i2, i2) = 1.0_dp
         end do
         call dgesv(3, 3, vm, 3, ip, self%vinv, 3, inf)
      end block
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
      real(dp) :: tx(4), ty(4), gu(0:4)
      integer :: i
      self%rtol = cfg%rk_rtol;  self%atol = cfg%rk_atol
      self%embedded = cfg%step_control == 'embedded'
      if (.not. self%built) then
         call build(self, model, cfg, err)
         if (allocated(err)) return
      end if
      do k = 1, 4
         call oscillator_propagator(self%w2, self%ad, node_s(k) * dt, self%cn(:, k), &
                                    self%sn(:, k))
         self%cm1(:, k) = oscillator_cm1(self%w2, self%ad, node_s(k) * dt)
      end do
      do j = 1, self%n
         if (sqrt(self%w2(j)) * dt < taylor_below .and. 2.0_dp * self%ad(j) * dt &
             < taylor_below) then
            ! one Taylor series per forcing s^i, summed at the four nodes at once
            do i = 0, 3
               gu = 0.0_dp;  gu(i) = 1.0_dp
               call taylor_series(self%w2(j), self%ad(j), dt, gu, node_s, tx, ty)
               self%rx(j, i, :) = tx;  self%ry(j, i, :) = ty
            end do
            cycle
         end if
         do k = 1, 4
            call forced_response(self%w2(j), self%ad(j), dt, node_s(k), 1.0_dp, 0.0_dp, &
                                 0.0_dp, self%rx(j, 0, k), self%ry(j, 0, k))
            call forced_response(self%w2(j), self%ad(j), dt, node_s(k), 0.0_dp, 1.0_dp, &
                                 0.0_dp, self%rx(j, 1, k), self%ry(j, 1, k))
            call forced_response(self%w2(j), self%ad(j), dt, node_s(k), 0.0_dp, 0.0_dp, &
                                 1.0_dp, self%rx(j, 2, k), self%ry(j, 2, k))
            call forced_response(self%w2(j), self%ad(j), dt, node_s(k), 0.0_dp, 0.0_dp, &
                                 0.0_dp, self%rx(j, 3, k), self%ry(j, 3, k), g3=1.0_dp)
         end do
      end do
      do j = 1, self%n
         call forced_response(self%w2(j), self%ad(j), dt, 1.0_dp, 0.0_dp, -0.2_dp, 1.2_dp, &
                              self%ex(j), self%ey(j), g3=-2.0_dp, g4=1.0_dp)
      end do
      call node_sensitivities(self)
      self%dt = dt
      self%ready = .true.
   end subroutine ex_prepare

   !> The act dofs' displacements (gu) and velocities (gv) at the nodes k = 1..3 from N's forces
   !> at the act dofs: at the start (m = 0, the cubic's constant, Phi_a diag(r(:, 0, k)) Phi_a')
   !> and at the node m = 1..3 (its coefficients vinv(:, m) (p_m - p_0):
   !> sum_j vinv(j, m) Phi_a diag(r(:, j, k)) Phi_a').
   subroutine node_sensitivities(self)
      class(exponential_t), intent(inout) :: self
      integer :: k, m, i, l
      real(dp) :: wu(self%n), wv(self%n)
      do k = 1, 3
         do m = 0, 3
            if (m == 0) then
               wu = self%rx(:, 0, k);  wv = self%ry(:, 0, k)
            else
               wu = self%vinv(1, m) * self%rx(:, 1, k) + self%vinv(2, m) * self%rx(:, 2, k) &
                    + self%vinv(3, m) * self%rx(:, 3, k)
               wv = self%vinv(1, m) * self%ry(:, 1, k) + self%vinv(2, m) * self%ry(:, 2, k) &
                    + self%vinv(3, m) * self%ry(:, 3, k)
            end if
            do l = 1, size(self%act)
               do i = 1, size(self%act)
                  self%gu(i, l, k, m) = sum(self%phiat(:, i) * wu * self%phiat(:, l))
                  self%gv(i, l, k, m) = sum(self%phiat(:, i) * wv * self%phiat(:, l))
               end do
            end do
         end do
      end do
   end subroutine node_sensitivities

   !> N(t, x, x') in modal coordinates at the node k (0..4, node_s) of the step: the contact and
   !> ring forces (rings in the regimes of s0; `hold` > 0 held open) at the start's
   !> displacements plus the node's changes, turbulence, harmonic loads when not exact,
   !> -D_off x'. Contact forces into f, ring forces into self%fn, self%ft.
   subroutine nonlinear(self, model, s0, t, k, hold, gm, f)
      class(exponential_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: s0
      real(dp), intent(in) :: t
      integer, intent(in) :: k, hold
      real(dp), intent(out) :: gm(:), f(:)
      integer :: i, j
      real(dp) :: su, sv
      ! (loops: a library matmul's call costs more than these few products; one contiguous
      ! row of Phi per contact dof, summed in the order of the modes)
      do i = 1, size(self%act)
         su = self%ua0(i);  sv = self%va0(i)
         do j = 1, self%n
            su = su + self%phiat(j, i) * self%dx(j, k)
            sv = sv + self%phiat(j, i) * self%dy(j, k)
         end do
         self%ua(i) = su;  self%va(i) = sv
      end do
      call act_forces(self, model, s0, hold, f)
      gm = 0.0_dp
      do j = 1, size(self%act)
         if (self%ra(j) /= 0.0_dp) gm = gm + self%ra(j) * self%phiat(:, j)
      end do
      self%evaluations = self%evaluations + 1
      if (.not. self%dense_n) return
      self%r = 0.0_dp
      if (.not. self%harmonic) self%r = sin(self%wf * t) * self%ls + cos(self%wf * t) * self%lc
      call add_random_load(model%turbulence, t, self%r)
      gm = gm + matmul(self%r, self%phi)
      if (allocated(self%doff)) gm = gm - matmul(self%doff, self%y(:, k))
   end subroutine nonlinear

   !> The contact and ring forces at the act dofs (self%ra) from their displacements and
   !> velocities self%ua, self%va, in the regimes of s0 (`hold` > 0 held open); contact
   !> forces into f, ring forces into self%fn, self%ft.
   subroutine act_forces(self, model, s0, hold, f)
      class(exponential_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: s0
      integer, intent(in) :: hold
      real(dp), intent(out) :: f(:)
      integer :: c, i, rg
      integer :: ja(2)
      real(dp) :: pr(2), xa(2), xda(2)
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
         ja(1) = self%ia(model%r_dof(1, rg));  ja(2) = self%ia(model%r_dof(2, rg))
         ! (fixed-size copies: the sections self%ua(ja) passed on were heap temporaries, a
         ! malloc and free at each of the step's 18 force evaluations per ring)
         xa(1) = self%ua(ja(1));  xa(2) = self%ua(ja(2))
         xda(1) = self%va(ja(1));  xda(2) = self%va(ja(2))
         ! a ring closed at the step's start (a located onset among them) touches whatever the
         ! round-off of its penetration, as in the restart's acceleration (restart_rings) that
         ! the step's quintic piece reads: a hair outside, the damper's c d' jumped in between
         ! the nodes (start accelerations 9 % apart on the rattling tube; at tolerance 1e-9 the
         ! quintic's check then failed at the smallest step)
         call ring_force(model, rg, s0%mode(rg), s0%sigma(rg), s0%anchor(rg), xa, xda, pr, &
                         self%fn(rg), self%ft(rg), &
                         touching=(s0%mode(rg) /= ring_open .and. s0%fn(rg) > 0.0_dp))
         self%ra(ja(1)) = self%ra(ja(1)) + pr(1);  self%ra(ja(2)) = self%ra(ja(2)) + pr(2)
      end do
   end subroutine act_forces

   !> The oscillators from the start's deviation (z0, zd0) from the harmonic solution, forced by
   !> the cubic G0 + G1 s + G2 s^2 + G3 s^3 (s = tau / h), at the nodes k_from..k_to (node_s):
   !> their changes from the start into dx, dy (the part without N from free_changes:
   !> the harmonic solution's change by sin a - sin b = 2 cos((a + b) / 2) sin((a - b) / 2),
   !> c - 1 from cm1: no cancellation, so a change is exact to the round-off of its own size),
   !> and the nodes' states x, y.
   subroutine propagate(self, g0, g1, g2, g3, k_from, k_to)
      class(exponential_t), intent(inout) :: self
      real(dp), intent(in) :: g0(:), g1(:), g2(:), g3(:)
      integer, intent(in) :: k_from, k_to          !! the nodes (node_s)
      integer :: k
      do k = k_from, k_to
         ! (an associate name of a section has lower bounds 1: the responses' j = 0..3 are 1..4)
         associate (rx => self%rx(:, :, k), ry => self%ry(:, :, k))
            self%dx(:, k) = self%fx(:, k) + g0 * rx(:, 1) + g1 * rx(:, 2) + g2 * rx(:, 3) &
                            + g3 * rx(:, 4)
            self%dy(:, k) = self%fy(:, k) + g0 * ry(:, 1) + g1 * ry(:, 2) + g2 * ry(:, 3) &
                            + g3 * ry(:, 4)
         end associate
         self%x(:, k) = self%x(:, 0) + self%dx(:, k)
         self%y(:, k) = self%y(:, 0) + self%dy(:, k)
      end do
   end subroutine propagate

   !> The changes at the nodes without N: the oscillators from the start's deviation (z0, zd0)
   !> from the harmonic solution, and that solution's own change (once per step; propagate
   !> adds the response to N's cubic).
   subroutine free_changes(self, t0)
      class(exponential_t), intent(inout) :: self
      real(dp), intent(in) :: t0
      real(dp) :: tau, sh, ds, dc
      integer :: k
      do k = 1, 4
         tau = node_s(k) * self%dt
         sh = 2.0_dp * sin(0.5_dp * self%wf * tau)
         ds = sh * cos(self%wf * (t0 + 0.5_dp * tau))      ! sin(wf (t0 + tau)) - sin(wf t0)
         dc = -sh * sin(self%wf * (t0 + 0.5_dp * tau))     ! cos(wf (t0 + tau)) - cos(wf t0)
         associate (cm1 => self%cm1(:, k), s => self%sn(:, k), a => self%ad)
            self%fx(:, k) = self%z0 * (cm1 + a * s) + self%zd0 * s + self%hs * ds &
                            + self%hc * dc
            self%fy(:, k) = self%zd0 * (cm1 - a * s) - self%w2 * self%z0 * s &
                            + self%wf * (self%hs * dc - self%hc * ds)
         end associate
      end do
   end subroutine free_changes

   !> The response from rest of x'' + 2 a x' + w2 x = g0 + g1 s + g2 s^2 (s = tau / h) at s:
   !> by the Taylor series in s when omega h and 2 a h are below 1 (no cancellation between the
   !> homogeneous and the particular parts), else by the particular polynomial.
   pure subroutine forced_response(w2, a, h, s, g0, g1, g2, x, v, g3, g4)
      real(dp), intent(in) :: w2, a, h, s, g0, g1, g2
      real(dp), intent(out) :: x, v
      real(dp), intent(in), optional :: g3, g4     !! cubic and quartic terms
      real(dp) :: c0, c1, c2, c3, c4, c, sn, tau, q3, q4, xs(1), vs(1)
      q3 = 0.0_dp;  q4 = 0.0_dp
      if (present(g3)) q3 = g3
      if (present(g4)) q4 = g4
      if (sqrt(w2) * h < taylor_below .and. 2.0_dp * a * h < taylor_below) then
         call taylor_series(w2, a, h, [g0, g1, g2, q3, q4], [s], xs, vs)
         x = xs(1);  v = vs(1)
         return
      end if
      tau = s * h
      c4 = q4 / h**4 / w2
      c3 = (q3 / h**3 - 8.0_dp * a * c4) / w2
      c2 = (g2 / h**2 - 6.0_dp * a * c3 - 12.0_dp * c4) / w2
      c1 = (g1 / h - 4.0_dp * a * c2 - 6.0_dp * c3) / w2
      c0 = (g0 - 2.0_dp * a * c1 - 2.0_dp * c2) / w2
      call oscillator_propagator(w2, a, tau, c, sn)
      x = -c0 * (c + a * sn) - c1 * sn + c0 + tau * (c1 + tau * (c2 + tau * (c3 + tau * c4)))
      v = -c1 * (c - a * sn) + w2 * c0 * sn + c1 + tau * (2.0_dp * c2 + tau * (3.0_dp * c3 &
          + 4.0_dp * tau * c4))
   end subroutine forced_response

   !> The forced oscillator x'' + 2 a x' + w2 x = g(0) + g(1) s + g(2) s^2 + g(3) s^3
   !> (s = tau / h) from rest, at the fractions s(:) of the step, by its Taylor series in s
   !> (omega h < 1: no cancellation between the homogeneous and the particular parts); one
   !> series for every fraction.
   pure subroutine taylor_series(w2, a, h, g, s, x, v)
      real(dp), intent(in) :: w2, a, h, g(0:), s(:)
      real(dp), intent(out) :: x(:), v(:)
      real(dp) :: xk(0:80), gk, scale, sp(size(s))
      integer :: k
      xk(0) = 0.0_dp;  xk(1) = 0.0_dp
      x = 0.0_dp;  v = 0.0_dp
      scale = maxval(abs(g * h * h))
      sp = s
      do k = 0, 78
         gk = 0.0_dp
         if (k <= ubound(g, 1)) gk = g(k)
         xk(k + 2) = (gk * h * h - 2.0_dp * a * h * (k + 1) * xk(k + 1) - w2 * h * h * xk(k)) &
                     / real((k + 1) * (k + 2), dp)
         v = v + (k + 2) * xk(k + 2) * sp
         sp = sp * s
         x = x + xk(k + 2) * sp
         scale = max(scale, abs(xk(k + 2)))
         if (k >= ubound(g, 1) .and. abs(xk(k + 2)) + abs(xk(k + 1)) <= 1.0e-18_dp * scale) exit
      end do
      v = v / h
   end subroutine taylor_series

   !> The sweeps of a step through N's values at the nodes (N at the start in self%wv(:, 3)):
   !> the constant predictor, then up to n_sweeps sweeps, each N at the three nodes from the
   !> last sweep's cubic (a sweep whose node values repeat the last sweep's bit for bit ends
   !> them). On return: the cubic's coefficients (self%wv(:, 7), (:, 8), (:, 11)), the nodes'
   !> states from it, and the end's change of the sweep before (self%wv(:, 1), (:, 2)).
   subroutine modal_sweeps(self, model, s0, t0, hold, f)
      class(exponential_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: s0
      real(dp), intent(in) :: t0
      integer, intent(in) :: hold
      real(dp), intent(inout) :: f(:)
      integer :: sweep
      logical :: converged
      real(dp) :: h
      h = self%dt
      associate (dxe => self%wv(:, 1), dye => self%wv(:, 2), ge => self%wv(:, 3), &
                 g1 => self%wv(:, 4), g2 => self%wv(:, 5), zero => self%wv(:, 6), &
                 c1 => self%wv(:, 7), c2 => self%wv(:, 8), g3 => self%wv(:, 10), &
                 c3 => self%wv(:, 11))
      call propagate(self, ge, zero, zero, zero, 1, k_end)
      do sweep = 1, n_sweeps
         dxe = self%dx(:, k_end);  dye = self%dy(:, k_end)
         call nonlinear(self, model, s0, t0 + node_s(1) * h, 1, hold, g1, f)
         call nonlinear(self, model, s0, t0 + node_s(2) * h, 2, hold, g2, f)
         call nonlinear(self, model, s0, t0 + h, k_end, hold, g3, f)
         if (sweep == 1) then
            converged = all(ge == 0.0_dp) .and. all(g1 == 0.0_dp) .and. all(g2 == 0.0_dp) &
                        .and. all(g3 == 0.0_dp)
         else
            converged = all(g1 == self%g(:, 1)) .and. all(g2 == self%g(:, 2)) .and. &
                        all(g3 == self%g(:, 3))
         end if
         self%g(:, 1) = g1;  self%g(:, 2) = g2;  self%g(:, 3) = g3
         g1 = g1 - ge;  g2 = g2 - ge;  g3 = g3 - ge
         c1 = self%vinv(1, 1) * g1 + self%vinv(1, 2) * g2 + self%vinv(1, 3) * g3
         c2 = self%vinv(2, 1) * g1 + self%vinv(2, 2) * g2 + self%vinv(2, 3) * g3
         c3 = self%vinv(3, 1) * g1 + self%vinv(3, 2) * g2 + self%vinv(3, 3) * g3
         call propagate(self, ge, c1, c2, c3, 1, k_end)
         if (converged) exit
      end do
      end associate
   end subroutine modal_sweeps

   !> The sweeps of modal_sweeps where N is the contact and ring forces alone (no turbulence,
   !> off-diagonal damping or harmonic loads in N), carried at the act dofs: a node's
   !> displacements and velocities there are the start's, the free change's and the cubic's
   !> through the step size's sensitivities gu, gv (na x na: the modes' 3 na products per
   !> node instead of the 30-mode propagation and projection), and the modes are propagated
   !> once, from the last sweep's forces. The same cubic and nodes as modal_sweeps to the
   !> round-off of the act dofs' sums (the start's act forces in self%pk(:, 0)).
   subroutine act_sweeps(self, model, s0, hold, f)
      class(exponential_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: s0
      integer, intent(in) :: hold
      real(dp), intent(inout) :: f(:)
      integer :: sweep, k, m, j, l, na
      logical :: converged
      real(dp) :: su, sv
      ! (loops: the intrinsic matmul of these 4 x 4 products, with its temporaries, cost more
      ! than the 30-mode sweeps it replaces)
      na = size(self%act)
      associate (dxe => self%wv(:, 1), dye => self%wv(:, 2), ge => self%wv(:, 3), &
                 c1 => self%wv(:, 7), c2 => self%wv(:, 8), c3 => self%wv(:, 11), &
                 p0 => self%pk(:, 0), dq => self%dq)
      do k = 1, 3
         do j = 1, na
            su = self%ua0(j);  sv = self%va0(j)
            do l = 1, na
               su = su + self%gu(j, l, k, 0) * p0(l)
               sv = sv + self%gv(j, l, k, 0) * p0(l)
            end do
            do l = 1, self%n
               su = su + self%phiat(l, j) * self%fx(l, k)
               sv = sv + self%phiat(l, j) * self%fy(l, k)
            end do
            self%bu(j, k) = su;  self%bv(j, k) = sv
         end do
         self%pk(:, k) = p0
      end do
      do sweep = 1, n_sweeps
         ! the forces that this sweep's nodes are computed from, and their changes from the start
         do m = 1, 3
            self%pp(:, m) = self%pk(:, m)
            dq(:, m) = self%pk(:, m) - p0
         end do
         do k = 1, 3
            do j = 1, na
               su = self%bu(j, k);  sv = self%bv(j, k)
               do m = 1, 3
                  do l = 1, na
                     su = su + self%gu(j, l, k, m) * dq(l, m)
                     sv = sv + self%gv(j, l, k, m) * dq(l, m)
                  end do
               end do
               self%ua(j) = su;  self%va(j) = sv
            end do
            call act_forces(self, model, s0, hold, f)
            self%pk(:, k) = self%ra
         end do
         self%evaluations = self%evaluations + 3
         converged = .true.
         do m = 1, 3
            do l = 1, na
               if (sweep == 1) then
                  converged = converged .and. self%pk(l, m) == 0.0_dp .and. p0(l) == 0.0_dp
               else
                  converged = converged .and. self%pk(l, m) == self%pp(l, m)
               end if
            end do
         end do
         if (converged) exit
      end do
      ! the end of the sweep before's cubic (the estimate's), then the last forces' cubic (the
      ! inner nodes' states are not read after the sweeps)
      call act_cubic(self, self%pp, c1, c2, c3)
      call propagate(self, ge, c1, c2, c3, k_end, k_end)
      dxe = self%dx(:, k_end);  dye = self%dy(:, k_end)
      call act_cubic(self, self%pk(:, 1:3), c1, c2, c3)
      call propagate(self, ge, c1, c2, c3, k_end, k_end)
      end associate
   end subroutine act_sweeps

   !> The cubic's coefficients (c1, c2, c3) of N through the start's value (self%wv(:, 3)) and
   !> the modal loads of the act forces p(:, m) at the nodes m = 1..3 (summed as nonlinear
   !> sums them; their changes from the start in self%g(:, 1:3)).
   subroutine act_cubic(self, p, c1, c2, c3)
      class(exponential_t), intent(inout) :: self
      real(dp), intent(in) :: p(:, :)
      real(dp), intent(out) :: c1(:), c2(:), c3(:)
      integer :: m, j
      associate (d => self%g)
      do m = 1, 3
         d(:, m) = 0.0_dp
         do j = 1, size(self%act)
            if (p(j, m) /= 0.0_dp) d(:, m) = d(:, m) + p(j, m) * self%phiat(:, j)
         end do
         d(:, m) = d(:, m) - self%wv(:, 3)
      end do
      c1 = self%vinv(1, 1) * d(:, 1) + self%vinv(1, 2) * d(:, 2) + self%vinv(1, 3) * d(:, 3)
      c2 = self%vinv(2, 1) * d(:, 1) + self%vinv(2, 2) * d(:, 2) + self%vinv(2, 3) * d(:, 3)
      c3 = self%vinv(3, 1) * d(:, 1) + self%vinv(3, 2) * d(:, 2) + self%vinv(3, 3) * d(:, 3)
      end associate
   end subroutine act_cubic

   !> One step (see stepper_t%step).
   subroutine ex_step(self, model, s0, s1, ok, ratio, open_contact)
      class(exponential_t), intent(inout) :: self        !! stepper
      type(model_t), intent(in) :: model                 !! model
      type(state_t), intent(in) :: s0                    !! start
      type(state_t), intent(inout) :: s1                 !! end
      logical, intent(out) :: ok                         !! always true
      real(dp), intent(out) :: ratio                     !! embedded error / tolerance
      integer, intent(in) :: open_contact                !! contact held open (0: none)
      real(dp) :: h, t0, t1, sk, tk, sc, dph
      integer :: i, n
      ! (the node arrays are named through self: an associate name of a component that a
      ! called procedure redefines may be a copy; the workspace's columns below are redefined
      ! by no called procedure but through the argument they are passed as)
      n = self%n
      associate (dxe => self%wv(:, 1), dye => self%wv(:, 2), ge => self%wv(:, 3), &
                 g1 => self%wv(:, 4), g2 => self%wv(:, 5), zero => self%wv(:, 6), &
                 c1 => self%wv(:, 7), c2 => self%wv(:, 8), gq => self%wv(:, 9), &
                 g3 => self%wv(:, 10), c3 => self%wv(:, 11), &
                 w7 => self%w7, p7 => self%p7, w2c => self%w2c, p2c => self%p2c)
      h = self%dt;  t0 = s0%t;  t1 = t0 + h;  ok = .true.
      s1%t = t1
      w2c(:, 1) = s0%u;  w2c(:, 2) = s0%v;  w2c(:, 3) = s0%a
      call dgemm('N', 'N', n, 3, n, 1.0_dp, self%phit_m, n, w2c, n, 0.0_dp, p2c, n)
      self%x(:, 0) = p2c(:, 1);  self%y(:, 0) = p2c(:, 2);  self%a0 = p2c(:, 3)
      self%dx(:, 0) = 0.0_dp;  self%dy(:, 0) = 0.0_dp
      if (size(self%act) > 0) then
         self%ua0 = s0%u(self%act);  self%va0 = s0%v(self%act)
      end if
      sk = sin(self%wf * t0);  tk = cos(self%wf * t0)
      self%z0 = self%x(:, 0) - (self%hs * sk + self%hc * tk)
      self%zd0 = self%y(:, 0) - self%wf * (self%hs * tk - self%hc * sk)
      call nonlinear(self, model, s0, t0, 0, open_contact, ge, s1%f)
      self%g(:, 0) = ge
      zero = 0.0_dp
      call free_changes(self, t0)
      if (self%dense_n .or. size(self%act) == 0 .or. .not. self%sweep_at_act) then
         call modal_sweeps(self, model, s0, t0, open_contact, s1%f)
      else
         self%pk(:, 0) = self%ra
         call act_sweeps(self, model, s0, open_contact, s1%f)
      end if
      ! the collocation's own error: N at the check node h/2 of the converged step against the
      ! cubic there, d = N - Q = C4 s (s - a) (s - b) (s - 1) at s = 1/2 (C4 = d / 0.0125: the
      ! leading, h^4 N'''', term of the cubic's error), and its effect on the end: the
      ! oscillators' response to that quartic (ex, ey). The sweeps' difference alone measures
      ! only how far the sweeps have converged, not how well a cubic follows the forces.
      call propagate(self, ge, c1, c2, c3, k_mid, k_mid)
      call nonlinear(self, model, s0, t0 + 0.5_dp * h, k_mid, open_contact, gq, s1%f)
      gq = gq - (ge + 0.5_dp * c1 + 0.25_dp * c2 + 0.125_dp * c3)
      ! dxe, dye: the end of the previous sweep; the end state from the start plus its change
      w7(:, 1) = self%dx(:, k_end);  w7(:, 2) = self%dy(:, k_end)
      w7(:, 3) = self%dx(:, k_end) - dxe;  w7(:, 4) = self%dy(:, k_end) - dye
      w7(:, 8) = (gq / w4_mid) * self%ex
      w7(:, 9) = (gq / w4_mid) * self%ey
      ! the acceleration at the end in the step's regime (as rk45's last stage: a contact held
      ! open to a located onset stays open; its force, a damper's c d' jumping in there, is the
      ! next step's, from the restart at the event, and in the interpolant's check below it
      ! would be an error that no smaller step removes); the forces at the end are reported
      ! with every contact as it is
      call nonlinear(self, model, s0, t1, k_end, open_contact, ge, s1%f)
      if (self%harmonic) ge = ge + sin(self%wf * t1) * self%fs + cos(self%wf * t1) * self%fc
      w7(:, 5) = ge - 2.0_dp * self%ad * self%y(:, k_end) - self%w2 * self%x(:, k_end)
      if (open_contact > 0) call nonlinear(self, model, s0, t1, k_end, 0, ge, s1%f)
      ! the interpolants at the midpoint against the method's own midpoint (the check node
      ! h/2), on the changes (all in the modes: with 3 v0 / 2 taken physical it would carry
      ! v0 - Phi Phi' M v0, the projection's round-off, as an error). The cubic from u, v at
      ! both ends: u(h/2) - (u0 + u1) / 2 - h (v0 - v1) / 8 and
      ! v(h/2) - 3 (u1 - u0) / (2 h) + (v0 + v1) / 4. The quintic from u, v, a (the piece's,
      ! which samples, states and the wear statistics read; a0 the start's acceleration, a1
      ! this step's, w7(:, 5)): u(h/2) - (u0 + u1) / 2 - 5 h (v0 - v1) / 32 - h^2 (a0 + a1) / 64
      ! and v(h/2) - 15 (u1 - u0) / (8 h) + 7 (v0 + v1) / 16 - h (a1 - a0) / 32.
      w7(:, 6) = self%dx(:, k_mid) - 0.5_dp * self%dx(:, k_end) + 0.125_dp * h &
                 * self%dy(:, k_end)
      w7(:, 7) = 1.5_dp * self%y(:, 0) + self%dy(:, k_mid) + 0.25_dp * self%dy(:, k_end) &
                 - 1.5_dp * self%dx(:, k_end) / h
      w7(:, 10) = self%dx(:, k_mid) - 0.5_dp * self%dx(:, k_end) + (5.0_dp / 32.0_dp) * h &
                  * self%dy(:, k_end) - (h * h / 64.0_dp) * (self%a0 + w7(:, 5))
      w7(:, 11) = 1.875_dp * self%y(:, 0) + self%dy(:, k_mid) + 0.4375_dp * self%dy(:, k_end) &
                  - 1.875_dp * self%dx(:, k_end) / h - (h / 32.0_dp) * (w7(:, 5) - self%a0)
      ! (OpenBLAS's dgemm, dispatched to this CPU's vector unit: the compiler's inline matmul
      ! of this 30 x 30 by 9 product took a fifth of the tube deck's run)
      call dgemm('N', 'N', n, 11, n, 1.0_dp, self%phi, n, w7, n, 0.0_dp, p7, n)
      s1%u = s0%u + p7(:, 1);  s1%v = s0%v + p7(:, 2)
      self%eu = sign(abs(p7(:, 3)) + abs(p7(:, 8)), p7(:, 3))
      self%ev = sign(abs(p7(:, 4)) + abs(p7(:, 9)), p7(:, 4))
      s1%a = p7(:, 5)
      w2c(:, 1) = abs(self%x(:, 0)) + abs(self%x(:, k_end))
      w2c(:, 2) = abs(self%y(:, 0)) + abs(self%y(:, k_end))
      call dgemm('N', 'N', n, 2, n, 1.0_dp, self%phi_abs, n, w2c, n, 0.0_dp, p2c, n)
      associate (um => p7(:, 6), vm => p7(:, 7), uq => p7(:, 10), vq => p7(:, 11), &
                 ru => p2c(:, 1), rv => p2c(:, 2))
      ! the harmonic solution's phase Omega_f t carries the round-off of t (Omega_f ulp(t)):
      ! its change over the step, over h, has that relative error (2.66 s into a 40 Hz
      ! forcing, 1e-13 of its velocity, whatever the step)
      dph = 4.0_dp * (self%wf * spacing(abs(t1)) + epsilon(1.0_dp))
      ratio = 0.0_dp
      do i = 1, self%n
         ! below the round-off of u and v (eps sum_j |Phi_ij x_j|): nothing to control; the
         ! velocity check's round-off is that of v (its terms 3 v0 / 2 and Phi dx / h cancel),
         ! not u / h: the changes carry no round-off of the state
         if (abs(self%eu(i)) <= 16.0_dp * epsilon(1.0_dp) * ru(i)) &
            self%eu(i) = 0.0_dp
         if (abs(self%ev(i)) <= 16.0_dp * epsilon(1.0_dp) * rv(i)) self%ev(i) = 0.0_dp
         if (abs(um(i)) <= 16.0_dp * epsilon(1.0_dp) * ru(i)) um(i) = 0.0_dp
         if (abs(vm(i)) <= 16.0_dp * epsilon(1.0_dp) * rv(i) + dph * self%vh(i)) vm(i) = 0.0_dp
         if (abs(uq(i)) <= 16.0_dp * epsilon(1.0_dp) * ru(i)) uq(i) = 0.0_dp
         if (abs(vq(i)) <= 16.0_dp * epsilon(1.0_dp) * rv(i) + dph * self%vh(i)) vq(i) = 0.0_dp
         self%iu(i) = um(i);  self%iv(i) = vm(i);  self%iq(i) = uq(i);  self%ivq(i) = vq(i)
         if (.not. self%embedded) cycle
         sc = self%atol + self%rtol * max(abs(s0%u(i)), abs(s1%u(i)))
         ratio = max(ratio, abs(self%eu(i)) / sc)
         sc = self%atol + self%rtol * max(abs(s0%v(i)), abs(s1%v(i)))
         ratio = max(ratio, abs(self%ev(i)) / sc)
         ratio = max(ratio, abs(self%iv(i)) / sc)
         sc = self%atol + self%rtol * max(abs(s0%u(i)), abs(s1%u(i)))
         ratio = max(ratio, abs(self%iu(i)) / sc)
      end do
      end associate
      if (model%n_rings > 0) then
         s1%fn = self%fn;  s1%ft = self%ft
         s1%mode = s0%mode;  s1%sigma = s0%sigma;  s1%anchor = s0%anchor
      end if
      end associate
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

   !> The errors of the step's cubic and quintic Hermite interpolants at its midpoint (see
   !> stepper_t%dense_error).
   subroutine ex_dense_error(self, eu, ev, has, eq, evq)
      class(exponential_t), intent(inout) :: self      !! stepper
      real(dp), intent(out) :: eu(:)                   !! displacement error at the midpoint
      real(dp), intent(out) :: ev(:)                   !! velocity error at the midpoint
      logical, intent(out) :: has                      !! always
      real(dp), intent(out), optional :: eq(:), evq(:) !! the quintic's
      has = .true.
      eu = self%iu;  ev = self%iv
      if (present(eq)) eq = self%iq
      if (present(evq)) evq = self%ivq
   end subroutine ex_dense_error
end module gapbeam_exponential
