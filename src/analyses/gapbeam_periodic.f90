!> Periodic orbits of the forced gap model: the stroboscopic (Poincare) map over p forcing
!> periods, its Jacobian (the monodromy matrix), Newton shooting, Floquet multipliers, and the
!> extrema of the contact penetrations along an orbit (grazing).
!>
!> **Section and coordinates.** The section is the forcing phase t0 = phase T (T = 2 pi /
!> Omega); the map carries the state at t0 to the state at t0 + p T. The state is the reduced
!> x = (u_r, v_r) of the dofs with mass (gapbeam_transition: mass_dofs); a point of the
!> section is started in equilibrium for the massless dofs (start_state), which the flow keeps,
!> so x determines the orbit.
!>
!> **Jacobian.** 'exact': the exact integrator's transition and saltation matrices
!> (advance_jacobian), composed over the p periods; 'finite_difference': central differences
!> of the map with any integrator, step h_j = fd_step s_j per component, s_j the size of
!> component j alone carrying the energy of the state (s_j = E / sqrt(K_jj) for a
!> displacement, E / sqrt(M_jj) for a velocity, E the energy norm of x).
!>
!> **Norm.** Sizes and distances of states are measured in the energy norm
!> ||x||_E^2 = u' K_r u + v' M_r v of the condensed structure (gapbeam_transition).
module gapbeam_periodic
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_observer, only: observer_t, piece_t
   use gapbeam_integrator, only: integrator_t, make_integrator, start_state
   use gapbeam_transition, only: linear_parts_t, setup_linear_parts, reduce_state
   use gapbeam_lapack, only: dgesv, dgeev
   implicit none
   private
   public :: orbit_map_t, orbit_extrema_t, newton_orbit, floquet_multipliers, energy_size, &
      energy_dot, transient_orbit, orbit_extrema, count_unstable

   !> The stroboscopic map of one model over p forcing periods.
   type :: orbit_map_t
      type(model_t) :: model                       !! the model
      class(integrator_t), allocatable :: integ    !! its integrator
      type(linear_parts_t) :: lp                   !! condensed structure (norm, dofs)
      integer :: p = 1                             !! forcing periods per map
      real(dp) :: phase = 0.0_dp                   !! section phase [periods, 0..1)
      real(dp) :: period = 0.0_dp                  !! forcing period T [s]
      logical :: exact_jacobian = .true.           !! integrator's Jacobian, else differences
      real(dp) :: fd_step = 1.0e-7_dp              !! relative difference step [-]
      integer :: evaluations = 0                   !! map evaluations (periods: times p)
   contains
      procedure :: setup => map_setup
      procedure :: evaluate => map_evaluate
      procedure :: section_state => map_section_state
   end type orbit_map_t

   !> Extrema of every contact's penetration d along an orbit (d' = 0), in time order.
   type :: orbit_extrema_t
      integer :: n = 0                               !! extrema found
      real(dp), allocatable :: t(:)                  !! their instants from the section [s]
      real(dp), allocatable :: d(:)                  !! d there [m, rad]
      integer, allocatable :: contact(:)             !! contact of each
      integer, allocatable :: intervals(:)           !! contact intervals per contact
      real(dp) :: nearest = -huge(1.0_dp)            !! the extremum of d nearest zero (signed)
      real(dp) :: t_nearest = 0.0_dp                 !! its instant [s]
      integer :: c_nearest = 0                       !! its contact
   end type orbit_extrema_t

   !> Samples d' of every contact along a trajectory and keeps its extrema.
   type, extends(observer_t) :: extrema_observer_t
      type(model_t), pointer :: model => null()
      real(dp) :: t_start = 0.0_dp, dt = 0.0_dp     !! sampling grid [s]
      type(orbit_extrema_t) :: ex
      real(dp), allocatable :: u(:), v(:)
   contains
      procedure :: observe => extrema_observe
   end type extrema_observer_t

contains

   ! ------------------------------------------------------------------ the map

   !> Build the map of `model` over p periods at section `phase` with the settings' method.
   subroutine map_setup(self, model, cfg, p, phase, exact_jacobian, fd_step, err)
      class(orbit_map_t), intent(inout) :: self          !! map
      type(model_t), intent(in) :: model                 !! model
      type(solver_settings_t), intent(in) :: cfg         !! integrator settings
      integer, intent(in) :: p                           !! forcing periods
      real(dp), intent(in) :: phase                      !! section phase [periods]
      logical, intent(in) :: exact_jacobian              !! integrator's own Jacobian
      real(dp), intent(in) :: fd_step                    !! relative difference step
      type(error_t), allocatable, intent(out) :: err     !! integrator set-up failure
      self%model = model
      self%p = p
      self%phase = phase - floor(phase)
      self%period = 2.0_dp * pi / model%omega
      self%exact_jacobian = exact_jacobian
      self%fd_step = fd_step
      if (allocated(self%integ)) deallocate(self%integ)
      call make_integrator(model, cfg, self%integ, err)
      if (allocated(err)) return
      call setup_linear_parts(model, self%lp, err)
   end subroutine map_setup

   !> The state at the section from a reduced x (massless dofs in equilibrium).
   subroutine map_section_state(self, x, st)
      class(orbit_map_t), intent(in) :: self       !! map
      real(dp), intent(in) :: x(:)                 !! reduced state
      type(state_t), intent(out) :: st             !! state at t0
      real(dp), allocatable :: u(:), v(:)
      allocate(u(self%model%n), v(self%model%n), source=0.0_dp)
      u(self%lp%ir) = x(1:self%lp%nr);  v(self%lp%ir) = x(self%lp%nr + 1:)
      call start_state(self%model, self%phase * self%period, u, v, st)
   end subroutine map_section_state

   !> px = P(x) over p periods; optionally its Jacobian and the state after each period.
   subroutine map_evaluate(self, x, px, err, jac, iterates)
      class(orbit_map_t), intent(inout) :: self              !! map
      real(dp), intent(in) :: x(:)                           !! reduced state at the section
      real(dp), intent(out) :: px(:)                         !! its image
      type(error_t), allocatable, intent(out) :: err         !! integrator failure
      real(dp), intent(out), optional :: jac(:, :)           !! dP/dx
      real(dp), intent(out), optional :: iterates(:, :)      !! (2 nr, p) after each period
      real(dp), allocatable :: xp(:), xm(:), s(:), y(:)
      integer :: j
      real(dp) :: h
      if (present(jac) .and. self%exact_jacobian) then
         call run_map(self, x, px, err, jac, iterates)
         return
      end if
      call run_map(self, x, px, err, its=iterates)
      if (allocated(err) .or. .not. present(jac)) return
      s = component_scales(self%lp, x)
      allocate(xp(size(x)), xm(size(x)), y(size(x)))
      do j = 1, size(x)
         h = self%fd_step * s(j)
         y = x;  y(j) = x(j) + h
         call run_map(self, y, xp, err);  if (allocated(err)) return
         y(j) = x(j) - h
         call run_map(self, y, xm, err);  if (allocated(err)) return
         jac(:, j) = (xp - xm) / (2.0_dp * h)
      end do
   end subroutine map_evaluate

   !> One map evaluation: x0 -> x1 over p periods, the integrator's Jacobian when jj is
   !> present, the state after each period when its is present.
   subroutine run_map(self, x0, x1, e, jj, its)
      class(orbit_map_t), intent(inout) :: self              !! map
      real(dp), intent(in) :: x0(:)                          !! start
      real(dp), intent(out) :: x1(:)                         !! end
      type(error_t), allocatable, intent(out) :: e           !! integrator failure
      real(dp), intent(out), optional :: jj(:, :)            !! Jacobian
      real(dp), intent(out), optional :: its(:, :)           !! states after each period
      type(state_t) :: st
      real(dp), allocatable :: jk(:, :)
      integer :: k
      real(dp) :: t0
      call self%section_state(x0, st)
      t0 = st%t
      if (present(jj)) then
         jj = 0.0_dp
         do k = 1, size(jj, 1)
            jj(k, k) = 1.0_dp
         end do
      end if
      do k = 1, self%p
         if (present(jj)) then
            call self%integ%advance_jacobian(st, t0 + real(k, dp) * self%period, jk, e)
            if (allocated(e)) return
            jj = matmul(jk, jj)
         else
            call self%integ%advance(st, t0 + real(k, dp) * self%period, err=e)
            if (allocated(e)) return
         end if
         if (present(its)) its(:, k) = reduce_state(self%lp, st%u, st%v)
      end do
      x1 = reduce_state(self%lp, st%u, st%v)
      self%evaluations = self%evaluations + 1
   end subroutine run_map

   !> Scale of each component of x: the size of that component alone carrying the energy of x.
   pure function component_scales(lp, x) result(s)
      type(linear_parts_t), intent(in) :: lp   !! condensed structure
      real(dp), intent(in) :: x(:)             !! reduced state
      real(dp) :: s(size(x)), e
      integer :: j, nr
      nr = lp%nr
      e = max(energy_size(lp, x), tiny(1.0_dp))
      do j = 1, nr
         s(j) = e / sqrt(lp%kr(j, j))
         s(nr + j) = e / sqrt(lp%mr(j, j))
      end do
      if (e <= tiny(1.0_dp)) s = 1.0e-6_dp
   end function component_scales

   !> Energy norm ||x||_E = sqrt(u' K_r u + v' M_r v) [sqrt(J)].
   pure real(dp) function energy_size(lp, x)
      type(linear_parts_t), intent(in) :: lp   !! condensed structure
      real(dp), intent(in) :: x(:)             !! reduced state (or a difference)
      energy_size = sqrt(max(0.0_dp, energy_dot(lp, x, x)))
   end function energy_size

   !> Energy inner product u_a' K_r u_b + v_a' M_r v_b [J].
   pure real(dp) function energy_dot(lp, a, b)
      type(linear_parts_t), intent(in) :: lp   !! condensed structure
      real(dp), intent(in) :: a(:), b(:)       !! reduced states
      integer :: nr
      nr = lp%nr
      energy_dot = dot_product(a(1:nr), matmul(lp%kr, b(1:nr))) &
                   + dot_product(a(nr + 1:), matmul(lp%mr, b(nr + 1:)))
   end function energy_dot

   ! ------------------------------------------------------------------ orbits

   !> Newton's method on P(x) - x = 0 at fixed parameters, from x (the converged orbit on
   !> return, with the monodromy there). Converged when ||P(x) - x||_E <= tol ||x||_E.
   subroutine newton_orbit(map, x, tol, max_iter, jac, err, iterations)
      type(orbit_map_t), intent(inout) :: map         !! map
      real(dp), intent(inout) :: x(:)                 !! start; the orbit on return
      real(dp), intent(in) :: tol                     !! relative tolerance
      integer, intent(in) :: max_iter                 !! iterations allowed
      real(dp), intent(out) :: jac(:, :)              !! monodromy at the orbit
      type(error_t), allocatable, intent(out) :: err  !! no convergence, solver failure
      integer, intent(out), optional :: iterations    !! corrections made
      real(dp), allocatable :: px(:), a(:, :), r(:, :)
      integer, allocatable :: ipiv(:)
      integer :: it, n, info, j
      real(dp) :: res, sz
      n = size(x)
      allocate(px(n), a(n, n), r(n, 1), ipiv(n))
      do it = 0, max_iter
         call map%evaluate(x, px, err, jac=jac)
         if (allocated(err)) return
         sz = max(energy_size(map%lp, x), tiny(1.0_dp))
         res = energy_size(map%lp, px - x)
         if (present(iterations)) iterations = it
         if (res <= tol * sz) return
         if (it == max_iter) exit
         a = jac
         do j = 1, n
            a(j, j) = a(j, j) - 1.0_dp
         end do
         r(:, 1) = x - px
         call dgesv(n, 1, a, n, ipiv, r, n, info)
         if (info /= 0) then
            call fatal_error(err, 'gapbeam_periodic:newton_orbit: P - I is singular (a ' &
               // 'multiplier is 1: a fold or a branch point), dgesv info=' // str(info))
            return
         end if
         x = x + r(:, 1)
      end do
      call fatal_error(err, 'gapbeam_periodic:newton_orbit: no convergence in ' &
         // str(max_iter) // ' iterations (residual ' // str(res / sz) // ' of the orbit size)')
   end subroutine newton_orbit

   !> Run the model from (u0, v0) at t = 0 over n_transient periods, then sample the section
   !> over up to 2 p_max + 2 periods and detect the period of the reduced state (the smallest
   !> p with ||x_{k+p} - x_k||_E <= tol ||x_k||_E over the last p_max + 1 points); x is the last
   !> section state, p = 0 when no period is found.
   subroutine transient_orbit(map, u0, v0, n_transient, p_max, tol, x, p, err)
      type(orbit_map_t), intent(inout) :: map         !! map (its p is not used)
      real(dp), intent(in) :: u0(:), v0(:)            !! initial state at t = 0
      integer, intent(in) :: n_transient              !! periods discarded
      integer, intent(in) :: p_max                    !! largest period looked for
      real(dp), intent(in) :: tol                     !! relative repeat distance
      real(dp), allocatable, intent(out) :: x(:)      !! section state at the end
      integer, intent(out) :: p                       !! period found (0: none)
      type(error_t), allocatable, intent(out) :: err  !! integrator failure
      type(state_t) :: st
      real(dp), allocatable :: xs(:, :)
      real(dp) :: t0
      integer :: k, m, q, i
      logical :: ok
      call start_state(map%model, 0.0_dp, u0, v0, st)
      t0 = (real(n_transient, dp) + map%phase) * map%period
      call map%integ%advance(st, t0, err=err)
      if (allocated(err)) return
      m = 2 * p_max + 2
      allocate(xs(2 * map%lp%nr, 0:m))
      xs(:, 0) = reduce_state(map%lp, st%u, st%v)
      p = 0
      do k = 1, m
         call map%integ%advance(st, t0 + real(k, dp) * map%period, err=err)
         if (allocated(err)) return
         xs(:, k) = reduce_state(map%lp, st%u, st%v)
         do q = 1, min(p_max, k / 2)
            if (k < 2 * q) cycle
            ok = .true.
            do i = k - q + 1, k
               if (energy_size(map%lp, xs(:, i) - xs(:, i - q)) > tol * max(energy_size( &
                   map%lp, xs(:, i)), tiny(1.0_dp))) then
                  ok = .false.;  exit
               end if
            end do
            if (ok) then
               p = q;  x = xs(:, k)
               return
            end if
         end do
      end do
      x = xs(:, m)
   end subroutine transient_orbit

   !> Eigenvalues of a monodromy matrix (dgeev), sorted by decreasing modulus.
   subroutine floquet_multipliers(jac, mu, err)
      real(dp), intent(in) :: jac(:, :)               !! monodromy
      complex(dp), allocatable, intent(out) :: mu(:)  !! multipliers
      type(error_t), allocatable, intent(out) :: err  !! dgeev failure
      real(dp), allocatable :: a(:, :), wr(:), wi(:), vl(:, :), vr(:, :), work(:)
      real(dp) :: query(1)
      integer :: n, info, i, j
      complex(dp) :: tmp
      n = size(jac, 1)
      a = jac
      allocate(wr(n), wi(n), vl(1, 1), vr(1, 1))
      call dgeev('N', 'N', n, a, n, wr, wi, vl, 1, vr, 1, query, -1, info)
      allocate(work(max(1, int(query(1)))))
      call dgeev('N', 'N', n, a, n, wr, wi, vl, 1, vr, 1, work, size(work), info)
      if (info /= 0) then
         call fatal_error(err, 'gapbeam_periodic:floquet_multipliers: dgeev failed, info=' &
            // str(info))
         return
      end if
      mu = cmplx(wr, wi, dp)
      do i = 2, n
         tmp = mu(i)
         j = i - 1
         do while (j >= 1)
            if (abs(mu(j)) >= abs(tmp)) exit
            mu(j + 1) = mu(j)
            j = j - 1
         end do
         mu(j + 1) = tmp
      end do
   end subroutine floquet_multipliers

   !> Multipliers outside the unit circle: real > 1, real < -1, complex (counted singly).
   pure subroutine count_unstable(mu, n_plus, n_minus, n_complex)
      complex(dp), intent(in) :: mu(:)            !! multipliers
      integer, intent(out) :: n_plus, n_minus, n_complex
      integer :: i
      n_plus = 0;  n_minus = 0;  n_complex = 0
      do i = 1, size(mu)
         if (.not. (abs(mu(i)) > 1.0_dp)) cycle
         if (aimag(mu(i)) == 0.0_dp) then
            if (real(mu(i)) > 0.0_dp) then
               n_plus = n_plus + 1
            else
               n_minus = n_minus + 1
            end if
         else
            n_complex = n_complex + 1
         end if
      end do
   end subroutine count_unstable

   ! ------------------------------------------------------------------ extrema

   !> Extrema of every contact's penetration over the orbit through x (p periods), found from
   !> d' sampled `samples` times per period (and at every piece end) and refined by
   !> bisection to round-off; the number of contact intervals of each contact per orbit and
   !> the extremum nearest zero (the grazing function).
   subroutine orbit_extrema(map, x, samples, ex, err)
      type(orbit_map_t), intent(inout), target :: map  !! map
      real(dp), intent(in) :: x(:)                     !! section state of the orbit
      integer, intent(in) :: samples                   !! samples of d' per forcing period
      type(orbit_extrema_t), intent(out) :: ex         !! the extrema
      type(error_t), allocatable, intent(out) :: err   !! integrator failure
      type(extrema_observer_t) :: obs
      type(state_t) :: st
      integer :: c, i, j, k, nc, m
      real(dp) :: a, b
      call map%section_state(x, st)
      obs%model => map%model
      obs%t_watch = huge(1.0_dp)
      obs%t_start = st%t
      obs%dt = map%period / real(max(samples, 4), dp)
      allocate(obs%u(map%model%n), obs%v(map%model%n))
      allocate(obs%ex%t(64), obs%ex%d(64), obs%ex%contact(64))
      call map%integ%advance(st, st%t + real(map%p, dp) * map%period, obs, err)
      if (allocated(err)) return
      ex%n = obs%ex%n
      ex%t = obs%ex%t(1:ex%n) - obs%t_start
      ex%d = obs%ex%d(1:ex%n)
      ex%contact = obs%ex%contact(1:ex%n)
      nc = map%model%n_contacts
      allocate(ex%intervals(nc), source=0)
      do c = 1, nc
         ! sign changes of the (cyclic) sequence of extrema: two per contact interval
         m = count(ex%contact == c)
         k = 0
         do i = 1, ex%n
            if (ex%contact(i) /= c) cycle
            j = i
            do
               j = mod(j, ex%n) + 1
               if (ex%contact(j) == c) exit
            end do
            a = ex%d(i);  b = ex%d(j)
            if ((a > 0.0_dp) .neqv. (b > 0.0_dp)) k = k + 1
         end do
         if (m > 0) ex%intervals(c) = k / 2
      end do
      do i = 1, ex%n
         if (ex%c_nearest == 0 .or. abs(ex%d(i)) < abs(ex%nearest)) then
            ex%nearest = ex%d(i);  ex%t_nearest = ex%t(i);  ex%c_nearest = ex%contact(i)
         end if
      end do
   end subroutine orbit_extrema

   !> d' of contact c at t inside a piece.
   real(dp) function contact_rate(self, piece, c, t)
      class(extrema_observer_t), intent(inout) :: self
      class(piece_t), intent(in) :: piece
      integer, intent(in) :: c
      real(dp), intent(in) :: t
      call piece%state_at(t, self%u, self%v)
      contact_rate = self%model%c_sign(c) * self%v(self%model%c_dof(c))
   end function contact_rate

   !> Sample d' over the piece on the grid (and at its ends); refine each sign change.
   subroutine extrema_observe(self, piece)
      class(extrema_observer_t), intent(inout) :: self   !! observer
      class(piece_t), intent(in) :: piece                !! piece
      integer :: c, j, j0, j1, it
      real(dp) :: ta, tb, ya, yb, t, tm, ym, lo, hi, ylo, d
      if (.not. (piece%tb > piece%ta)) return
      j0 = ceiling((piece%ta - self%t_start) / self%dt)
      j1 = floor((piece%tb - self%t_start) / self%dt)
      do c = 1, self%model%n_contacts
         ta = piece%ta
         ya = contact_rate(self, piece, c, ta)
         do j = j0, j1 + 1
            if (j <= j1) then
               t = self%t_start + real(j, dp) * self%dt
               if (.not. (t > ta)) cycle
               if (t >= piece%tb) t = piece%tb
            else
               t = piece%tb
            end if
            if (.not. (t > ta)) cycle
            tb = t
            yb = contact_rate(self, piece, c, tb)
            if ((ya > 0.0_dp .and. yb <= 0.0_dp) .or. (ya < 0.0_dp .and. yb >= 0.0_dp)) then
               if (yb == 0.0_dp .and. tb < piece%tb) then
                  tm = tb            ! exactly at a grid point (not the end: the next piece)
               else if (yb == 0.0_dp) then
                  ta = tb;  ya = yb
                  cycle              ! at the piece end: the next piece starts there
               else
                  lo = ta;  hi = tb;  ylo = ya
                  do it = 1, 200
                     tm = 0.5_dp * (lo + hi)
                     if (.not. (tm > lo .and. tm < hi)) exit
                     ym = contact_rate(self, piece, c, tm)
                     if ((ym > 0.0_dp) .eqv. (ylo > 0.0_dp)) then
                        lo = tm;  ylo = ym
                     else
                        hi = tm
                     end if
                  end do
                  tm = 0.5_dp * (lo + hi)
               end if
               call piece%state_at(tm, self%u, self%v)
               d = self%model%c_sign(c) * self%u(self%model%c_dof(c)) - self%model%c_gap(c)
               call push(self%ex, tm, d, c)
            end if
            ta = tb;  ya = yb
         end do
      end do
   end subroutine extrema_observe

   !> Append an extremum (arrays grow by doubling).
   pure subroutine push(ex, t, d, c)
      type(orbit_extrema_t), intent(inout) :: ex
      real(dp), intent(in) :: t, d
      integer, intent(in) :: c
      real(dp), allocatable :: t2(:), d2(:)
      integer, allocatable :: c2(:)
      if (ex%n == size(ex%t)) then
         allocate(t2(2 * ex%n), d2(2 * ex%n), c2(2 * ex%n))
         t2(1:ex%n) = ex%t;  d2(1:ex%n) = ex%d;  c2(1:ex%n) = ex%contact
         call move_alloc(t2, ex%t);  call move_alloc(d2, ex%d);  call move_alloc(c2, ex%contact)
      end if
      ex%n = ex%n + 1
      ex%t(ex%n) = t;  ex%d(ex%n) = d;  ex%contact(ex%n) = c
   end subroutine push
end module gapbeam_periodic
