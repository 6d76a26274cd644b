!> Stability of the integrators: the amplification matrix of one step on the undamped test
!> equation u'' + omega^2 u = 0 (its spectral radius against omega dt), and the largest stable
!> fixed step on a finite element model found by bisection with real runs.
!>
!> The amplification matrix is built by running one real step of the method's stepper on a
!> one-dof problem from the unit states (u, v) = (1, 0) and (0, 1) (the acceleration in
!> equilibrium), so it measures the code, not a formula. For methods that carry the
!> acceleration (the Newmark family, HHT, generalized-alpha) the state is (u, v, dt^2 a) and the
!> matrix is 3 x 3.
module gapbeam_stability
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dgeev, dpotrf, dpotrs
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_linalg, only: dense_to_band
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_integrator, only: stepper_t, make_stepper
   use gapbeam_capabilities, only: method_caps_t, method_caps
   implicit none
   private
   public :: spectral_radius, largest_stable_step

contains

   !> A one-dof problem: unit mass, stiffness omega^2, no damping, no forcing, no contact.
   function test_problem(omega) result(model)
      real(dp), intent(in) :: omega       !! natural frequency [rad/s]
      type(model_t) :: model
      model%n = 1
      model%sys%n_dof = 1;  model%sys%n_node = 1;  model%sys%kd = 0
      model%sys%k = reshape([omega**2], [1, 1])
      model%sys%m = reshape([1.0_dp], [1, 1])
      call dense_to_band(model%sys%k, 0, model%sys%k_band)
      call dense_to_band(model%sys%m, 0, model%sys%m_band)
      model%sys%m_diagonal = .true.
      model%sys%r = [1.0_dp];  model%sys%strain_row = [0.0_dp];  model%sys%tip_dof = 1
      model%c = reshape([0.0_dp], [1, 1]);  model%q = [0.0_dp]
      model%omega = 1.0_dp;  model%half_amplitude = 0.0_dp
      allocate(model%c_dof(0), model%c_sign(0), model%c_gap(0), model%c_law(0), model%c_k(0), &
               model%c_c(0), model%c_p(0), model%c_stop(0), model%c_slot(0), model%slot_dof(0))
      allocate(model%stop_stiffness(0))
      model%omega_max = omega
   end function test_problem

   !> Spectral radius of one step of the method at omega dt = x (omega = 1).
   subroutine spectral_radius(cfg, x, rho, err)
      type(solver_settings_t), intent(in) :: cfg      !! method and its parameters
      real(dp), intent(in) :: x                       !! omega dt [-]
      real(dp), intent(out) :: rho                    !! spectral radius [-]
      type(error_t), allocatable, intent(out) :: err  !! method cannot run
      class(stepper_t), allocatable :: st
      type(model_t) :: model
      type(solver_settings_t) :: c
      type(method_caps_t) :: mc
      type(state_t) :: s0, s1
      real(dp) :: amp(3, 3), ratio, wr(3), wi(3), vl(1, 3), vr(1, 3), work(64), h
      logical :: ok
      integer :: j, m, info
      c = cfg
      ! a method charted through another's matrix (rk45: its 5th-order step differs from a
      ! fixed step; the study uses fixed-step RK4)
      mc = method_caps(c%method)
      if (len_trim(mc%stability_with) > 0) then
         c%method = mc%stability_with
         mc = method_caps(c%method)
      end if
      model = test_problem(1.0_dp)
      call make_stepper(c%method, st, err);  if (allocated(err)) return
      h = x
      allocate(s0%u(1), s0%v(1), s0%a(1), s0%f(0), s0%f_prev(0), s1%u(1), s1%v(1), s1%a(1), &
               s1%f(0), s1%f_prev(0))
      s0%t = 0.0_dp;  s0%dt_prev = h
      call st%prepare(model, c, h, err);  if (allocated(err)) return
      ! acceleration-carrying methods use (u, v, h^2 a) as the state
      m = merge(3, 2, mc%carries_acceleration)
      amp = 0.0_dp
      do j = 1, m
         s0%u = 0.0_dp;  s0%v = 0.0_dp;  s0%a = 0.0_dp
         select case (j)
         case (1);  s0%u = 1.0_dp
         case (2);  s0%v = 1.0_dp / h
         case (3);  s0%a = 1.0_dp / h**2
         end select
         if (m == 2) s0%a = -s0%u            ! equilibrium: a = -omega^2 u
         call st%step(model, s0, s1, ok, ratio, 0)
         amp(1, j) = s1%u(1);  amp(2, j) = h * s1%v(1)
         if (m == 3) amp(3, j) = h**2 * s1%a(1)
      end do
      call dgeev('N', 'N', m, amp, 3, wr, wi, vl, 1, vr, 1, work, size(work), info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_stability:spectral_radius: dgeev info=' // str(info))
         return
      end if
      rho = maxval(sqrt(wr(1:m)**2 + wi(1:m)**2))
   end subroutine spectral_radius

   !> Does a fixed step dt stay bounded over n_steps on the model's free, undamped vibration
   !> from a pseudo-random initial displacement (all modes excited)? Unstable when the energy
   !> u'Ku/2 + v'Mv/2 grows beyond 1e4 times its initial value or turns non-finite.
   subroutine step_is_stable(model, cfg, dt, n_steps, stable, err)
      type(model_t), intent(in) :: model             !! model (its damping and forcing are ignored)
      type(solver_settings_t), intent(in) :: cfg      !! method
      real(dp), intent(in) :: dt                      !! step [s]
      integer, intent(in) :: n_steps                  !! steps run
      logical, intent(out) :: stable                  !! bounded
      type(error_t), allocatable, intent(out) :: err  !! method cannot run
      class(stepper_t), allocatable :: st
      type(model_t) :: p
      type(state_t) :: s0, s1
      real(dp) :: e0, e, ratio
      integer :: k, i
      integer(8) :: seed
      logical :: ok
      p = model
      p%c = 0.0_dp;  p%beta = 0.0_dp;  p%gamma = 0.0_dp;  p%half_amplitude = 0.0_dp
      call make_stepper(cfg%method, st, err);  if (allocated(err)) return
      call st%prepare(p, cfg, dt, err);  if (allocated(err)) return
      allocate(s0%u(p%n), s0%v(p%n), s0%a(p%n), s1%u(p%n), s1%v(p%n), s1%a(p%n), &
               s0%f(p%n_contacts), s0%f_prev(p%n_contacts), s1%f(p%n_contacts), &
               s1%f_prev(p%n_contacts), source=0.0_dp)
      s0%dt_prev = dt
      seed = 20261121_8
      do i = 1, p%n
         seed = mod(seed * 6364136223846793005_8 + 1442695040888963407_8, huge(seed))
         s0%u(i) = real(mod(abs(seed), 2000001_8) - 1000000_8, dp) * 1.0e-9_dp
      end do
      s0%a = -solve_m(p, matmul(p%sys%k, s0%u))
      e0 = energy(p, s0%u, s0%v)
      stable = .true.
      do k = 1, n_steps
         s0%t = (k - 1) * dt
         call st%step(p, s0, s1, ok, ratio, 0)
         s0%u = s1%u;  s0%v = s1%v;  s0%a = s1%a
         if (mod(k, 16) == 0 .or. k == n_steps) then
            e = energy(p, s0%u, s0%v)
            if (.not. (e <= 1.0e4_dp * e0)) then
               stable = .false.;  return
            end if
         end if
      end do
   end subroutine step_is_stable

   !> Largest stable fixed step, by bisection between dt_stable (stable) and dt_unstable
   !> (unstable), to relative precision rtol; the bracket is widened first if needed.
   subroutine largest_stable_step(model, cfg, dt_guess, n_steps, rtol, dt, err)
      type(model_t), intent(in) :: model             !! model
      type(solver_settings_t), intent(in) :: cfg      !! method
      real(dp), intent(in) :: dt_guess                !! a first guess [s]
      integer, intent(in) :: n_steps                  !! steps per trial
      real(dp), intent(in) :: rtol                    !! relative precision of the bisection
      real(dp), intent(out) :: dt                     !! largest stable step [s]
      type(error_t), allocatable, intent(out) :: err  !! method cannot run, or no bracket
      real(dp) :: lo, hi, mid
      logical :: stable
      integer :: it
      lo = dt_guess;  hi = dt_guess
      do it = 1, 60
         call step_is_stable(model, cfg, lo, n_steps, stable, err);  if (allocated(err)) return
         if (stable) exit
         hi = lo;  lo = 0.5_dp * lo
      end do
      do it = 1, 60
         call step_is_stable(model, cfg, hi, n_steps, stable, err);  if (allocated(err)) return
         if (.not. stable) exit
         lo = hi;  hi = 2.0_dp * hi
         if (it == 60) then
            call fatal_error(err, 'gapbeam_stability:largest_stable_step: no unstable step ' &
               // 'found up to ' // str(hi) // " s (method '" // trim(cfg%method) &
               // "' looks unconditionally stable)")
            return
         end if
      end do
      do while (hi - lo > rtol * lo)
         mid = 0.5_dp * (lo + hi)
         call step_is_stable(model, cfg, mid, n_steps, stable, err);  if (allocated(err)) return
         if (stable) then
            lo = mid
         else
            hi = mid
         end if
      end do
      dt = lo
   end subroutine largest_stable_step

   real(dp) function energy(p, u, v)
      type(model_t), intent(in) :: p
      real(dp), intent(in) :: u(:), v(:)
      energy = 0.5_dp * dot_product(u, matmul(p%sys%k, u)) &
               + 0.5_dp * dot_product(v, matmul(p%sys%m, v))
   end function energy

   !> M^-1 b (massless dofs get 0).
   function solve_m(p, b) result(x)
      type(model_t), intent(in) :: p
      real(dp), intent(in) :: b(:)
      real(dp) :: x(size(b))
      real(dp), allocatable :: mm(:, :)
      integer :: info
      if (p%sys%m_diagonal) then
         where (diag(p%sys%m) > 0.0_dp)
            x = b / diag(p%sys%m)
         elsewhere
            x = 0.0_dp
         end where
      else
         mm = p%sys%m;  x = b
         call dpotrf('U', p%n, mm, p%n, info)
         if (info /= 0) error stop 'gapbeam_stability:solve_m: a consistent mass matrix is ' &
            // 'positive definite'
         call dpotrs('U', p%n, 1, mm, p%n, x, p%n, info)
      end if
   end function solve_m

   pure function diag(m) result(d)
      real(dp), intent(in) :: m(:, :)
      real(dp) :: d(size(m, 1))
      integer :: i
      do i = 1, size(m, 1)
         d(i) = m(i, i)
      end do
   end function diag
end module gapbeam_stability
