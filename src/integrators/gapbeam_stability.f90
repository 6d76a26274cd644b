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
   use gapbeam_problem, only: problem_t
   use gapbeam_assembly, only: dense_to_band
   use gapbeam_settings, only: solver_settings_t, output_settings_t
   use gapbeam_stepper, only: stepper_t
   use gapbeam_integrators, only: make_stepper
   implicit none
   private
   public :: spectral_radius, test_problem, largest_stable_step, step_is_stable

contains

   !> A one-dof problem: unit mass, stiffness omega^2, no damping, no forcing, no contact.
   function test_problem(omega) result(prob)
      real(dp), intent(in) :: omega       !! natural frequency [rad/s]
      type(problem_t) :: prob
      prob%n = 1
      prob%sys%n_dof = 1;  prob%sys%n_node = 1;  prob%sys%kd = 0
      prob%sys%k = reshape([omega**2], [1, 1])
      prob%sys%m = reshape([1.0_dp], [1, 1])
      call dense_to_band(prob%sys%k, 0, prob%sys%k_band)
      call dense_to_band(prob%sys%m, 0, prob%sys%m_band)
      prob%sys%m_diagonal = .true.
      prob%sys%r = [1.0_dp];  prob%sys%strain_row = [0.0_dp];  prob%sys%tip_dof = 1
      prob%c = reshape([0.0_dp], [1, 1]);  prob%q = [0.0_dp]
      prob%omega = 1.0_dp;  prob%half_amplitude = 0.0_dp
      allocate(prob%c_dof(0), prob%c_sign(0), prob%c_gap(0), prob%c_law(0), prob%c_k(0), &
               prob%c_c(0), prob%c_p(0), prob%c_stop(0), prob%c_slot(0), prob%slot_dof(0))
      allocate(prob%stop_stiffness(0))
      prob%omega_max = omega
   end function test_problem

   !> Spectral radius of one step of the method at omega dt = x (omega = 1).
   subroutine spectral_radius(cfg, x, rho, err)
      type(solver_settings_t), intent(in) :: cfg      !! method and its parameters
      real(dp), intent(in) :: x                       !! omega dt [-]
      real(dp), intent(out) :: rho                    !! spectral radius [-]
      type(error_t), allocatable, intent(out) :: err  !! method cannot run
      class(stepper_t), allocatable :: st
      type(problem_t) :: prob
      type(solver_settings_t) :: c
      real(dp) :: amp(3, 3), u(1), v(1), a(1), u1(1), v1(1), a1(1), f(0), f1(0), ratio, &
         wr(3), wi(3), vl(1, 3), vr(1, 3), work(64), h
      logical :: ok
      integer :: j, m, info
      c = cfg
      if (c%method == 'rk45') c%method = 'rk4'     ! the embedded pair's 5th-order step differs;
                                                   ! the stability study uses fixed-step RK4
      prob = test_problem(1.0_dp)
      call make_stepper(c, st, err);  if (allocated(err)) return
      h = x
      call st%prepare(prob, c, h, err);  if (allocated(err)) return
      ! acceleration-carrying methods use (u, v, h^2 a) as the state
      select case (c%method)
      case ('newmark', 'hht', 'generalized_alpha')
         m = 3
      case default
         m = 2
      end select
      amp = 0.0_dp
      do j = 1, m
         u = 0.0_dp;  v = 0.0_dp;  a = 0.0_dp
         select case (j)
         case (1);  u = 1.0_dp
         case (2);  v = 1.0_dp / h
         case (3);  a = 1.0_dp / h**2
         end select
         if (m == 2) a = -u            ! equilibrium: a = -omega^2 u
         call st%step(prob, 0.0_dp, u, v, a, f, f, h, u1, v1, a1, f1, ok, ratio, 0)
         amp(1, j) = u1(1);  amp(2, j) = h * v1(1)
         if (m == 3) amp(3, j) = h**2 * a1(1)
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
   subroutine step_is_stable(prob, cfg, dt, n_steps, stable, err)
      type(problem_t), intent(in) :: prob             !! model (its damping and forcing are ignored)
      type(solver_settings_t), intent(in) :: cfg      !! method
      real(dp), intent(in) :: dt                      !! step [s]
      integer, intent(in) :: n_steps                  !! steps run
      logical, intent(out) :: stable                  !! bounded
      type(error_t), allocatable, intent(out) :: err  !! method cannot run
      class(stepper_t), allocatable :: st
      type(problem_t) :: p
      real(dp), allocatable :: u(:), v(:), a(:), u1(:), v1(:), a1(:), f(:), f1(:)
      real(dp) :: e0, e, ratio
      integer :: k, i
      integer(8) :: seed
      logical :: ok
      p = prob
      p%c = 0.0_dp;  p%beta = 0.0_dp;  p%gamma = 0.0_dp;  p%half_amplitude = 0.0_dp
      call make_stepper(cfg, st, err);  if (allocated(err)) return
      call st%prepare(p, cfg, dt, err);  if (allocated(err)) return
      allocate(u(p%n), v(p%n), a(p%n), u1(p%n), v1(p%n), a1(p%n), f(p%n_contacts), &
               f1(p%n_contacts), source=0.0_dp)
      seed = 20261121_8
      do i = 1, p%n
         seed = mod(seed * 6364136223846793005_8 + 1442695040888963407_8, huge(seed))
         u(i) = real(mod(abs(seed), 2000001_8) - 1000000_8, dp) * 1.0e-9_dp
      end do
      a = -solve_m(p, matmul(p%sys%k, u))
      e0 = energy(p, u, v)
      stable = .true.
      do k = 1, n_steps
         call st%step(p, (k - 1) * dt, u, v, a, f, f, dt, u1, v1, a1, f1, ok, ratio, 0)
         u = u1;  v = v1;  a = a1
         if (mod(k, 16) == 0 .or. k == n_steps) then
            e = energy(p, u, v)
            if (.not. (e <= 1.0e4_dp * e0)) then
               stable = .false.;  return
            end if
         end if
      end do
   end subroutine step_is_stable

   !> Largest stable fixed step, by bisection between dt_stable (stable) and dt_unstable
   !> (unstable), to relative precision rtol; the bracket is widened first if needed.
   subroutine largest_stable_step(prob, cfg, dt_guess, n_steps, rtol, dt, err)
      type(problem_t), intent(in) :: prob             !! model
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
         call step_is_stable(prob, cfg, lo, n_steps, stable, err);  if (allocated(err)) return
         if (stable) exit
         hi = lo;  lo = 0.5_dp * lo
      end do
      do it = 1, 60
         call step_is_stable(prob, cfg, hi, n_steps, stable, err);  if (allocated(err)) return
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
         call step_is_stable(prob, cfg, mid, n_steps, stable, err);  if (allocated(err)) return
         if (stable) then
            lo = mid
         else
            hi = mid
         end if
      end do
      dt = lo
   end subroutine largest_stable_step

   real(dp) function energy(p, u, v)
      type(problem_t), intent(in) :: p
      real(dp), intent(in) :: u(:), v(:)
      energy = 0.5_dp * dot_product(u, matmul(p%sys%k, u)) &
               + 0.5_dp * dot_product(v, matmul(p%sys%m, v))
   end function energy

   !> M^-1 b (massless dofs get 0).
   function solve_m(p, b) result(x)
      type(problem_t), intent(in) :: p
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
