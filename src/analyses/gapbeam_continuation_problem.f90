!> The problem a continuation solves, shared by the branches (gapbeam_continuation) and the
!> two-parameter curves (gapbeam_bifurcation_curves): the deck and its varied variables, the
!> stroboscopic maps at given values (cached), the scaled norm, the pseudo-arclength corrector,
!> tangents, and what is measured at each converged orbit.
!>
!> **Unknowns.** y = (x, lambda): the reduced section state x = (u_r, v_r) of the orbit
!> (gapbeam_periodic) and the continued variable lambda. The orbit equation is
!> G(y) = P^p(x; lambda) - x = 0, with P the one-period map.
!>
!> **Norm.** <a, b>_W = (a_u' K_r b_u + a_v' M_r b_v) / (2 E_ref)^2 + a_lambda b_lambda / S^2,
!> with K_r, M_r of the starting model, E_ref the energy norm of the last orbit of the branch
!> (updated at every point, at least 1/100 of the start orbit's) and S the parameter scale
!> (the width of the continuation range): a step of 1 moves the orbit by twice its own size
!> or the parameter across its range. Steps, tangents and the arclength are measured in this
!> norm.
!>
!> **Corrector.** From a point y_a with unit tangent t, the point at arclength sigma solves
!> G(y) = 0 and <t, y - y_a>_W = sigma by Newton's method from y_a + sigma t, with the
!> Jacobian [P_x - I, P_lambda; (W t)'], P_x the monodromy (exact or by differences) and
!> P_lambda by central differences of the map in lambda (step 1e-6 S; one-sided, of second
!> order, where lambda - h would leave the variable's range: a start at its bound). The next
!> tangent
!> !> solves [P_x - I, P_lambda; (W t_prev)'] t = (0, 1), normalised: it keeps its
!> orientation through folds.
module gapbeam_continuation_problem
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_deck_variable, only: deck_variable_t
   use gapbeam_deck_parameter, only: model_with_values
   use gapbeam_continuation_types, only: continuation_settings_t
   use gapbeam_transition, only: linear_parts_t, setup_linear_parts, expand_state
   use gapbeam_periodic, only: orbit_map_t, orbit_extrema_t, orbit_extrema, energy_dot, &
      energy_size, floquet_multipliers, count_unstable
   use gapbeam_lapack, only: dgesv
   implicit none
   private
   public :: problem_t, point_t, map_at, orbit_eval, wdot, wvec, correct_point, tangent_of, &
      measure_point, solve_linear, test_value, null_vector, below_range

   integer, parameter :: test_kinds = 5   !! fold, branch point, period doubling, NS, grazing

   !> A map at given values of the variables, kept for reuse.
   type :: cached_map_t
      type(orbit_map_t) :: m                   !! the map
      real(dp) :: lam(2) = huge(1.0_dp)        !! variable values it was built for
      integer :: p = 0                         !! its periods
   end type cached_map_t

   !> What a continuation works on.
   type :: problem_t
      type(deck_t) :: deck                          !! the deck
      type(model_t) :: base                         !! its model
      type(solver_settings_t) :: solver             !! integrator settings
      type(continuation_settings_t) :: cfg          !! &continuation
      type(deck_variable_t) :: var(2)               !! continued variable(s)
      integer :: nvar = 1                           !! 1: branches, 2: curves
      real(dp) :: lam2 = 0.0_dp                     !! value of var(2) on the branches
      real(dp) :: phase = 0.0_dp                    !! section phase [periods]
      type(linear_parts_t) :: lp0                   !! metric (starting model)
      real(dp) :: e_ref = 1.0_dp                    !! energy norm of the start orbit
      real(dp) :: scale(2) = 1.0_dp                 !! parameter scales
      real(dp) :: loc_tol = 0.0_dp                  !! location tolerance [unit of var(1)]
      integer :: n = 0                              !! size of a state
      type(cached_map_t) :: center, aux             !! maps at y and at perturbed values
      integer :: evaluations = 0                    !! maps evaluated (p periods each)
      integer :: periods = 0                        !! forcing periods integrated
      character(len=:), allocatable :: note         !! about the start ('' none)
   end type problem_t

   !> A converged orbit with what is measured on it.
   type :: point_t
      real(dp), allocatable :: y(:)                 !! (x, lambda [, lambda2])
      real(dp), allocatable :: t(:)                 !! unit tangent
      integer :: p = 1                              !! periods
      real(dp), allocatable :: jac(:, :)            !! monodromy
      real(dp), allocatable :: dpdl(:)              !! dP/dlambda
      complex(dp), allocatable :: mu(:)             !! multipliers
      integer :: n_plus = 0, n_minus = 0, n_complex = 0   !! unstable multipliers
      integer :: impacts = 0                        !! contact intervals per orbit
      real(dp) :: graze = 0.0_dp                    !! extremum of d nearest 0 [m]
      real(dp) :: t_graze = 0.0_dp                  !! its instant from the section [s]
      integer :: c_graze = 0                        !! its contact
      real(dp), allocatable :: iterates(:, :)       !! (n, p) after each period
      real(dp), allocatable :: p_strain(:)          !! (p) root strain after each period [-]
      real(dp), allocatable :: p_rate(:)            !! (p) its rate [1/s]
      real(dp), allocatable :: p_tip(:)             !! (p) tip displacement [m]
      real(dp) :: sigma = 0.0_dp                    !! arclength along the branch
      integer :: iterations = 0                     !! corrector iterations
      logical :: located = .false.                  !! a located bifurcation point
      integer :: kind = 0                           !! its test function (test_value)
   end type point_t

contains

   !> Make `cm` the map at the variables' values lam (var(2) at pb%lam2 when one variable).
   subroutine map_at(pb, cm, lam, p, err)
      type(problem_t), intent(inout) :: pb              !! problem
      type(cached_map_t), intent(inout) :: cm           !! cache
      real(dp), intent(in) :: lam(:)                    !! values of var(1:size(lam))
      integer, intent(in) :: p                          !! periods
      type(error_t), allocatable, intent(out) :: err    !! value out of range, set-up failure
      type(model_t) :: model
      real(dp) :: l(2)
      l = [lam(1), pb%lam2]
      if (size(lam) > 1) l(2) = lam(2)
      if (cm%p == p .and. all(cm%lam(1:pb%nvar) == l(1:pb%nvar))) return
      cm%p = 0
      if (pb%nvar == 1 .and. size(lam) == 1) then
         call model_with_values(pb%deck, pb%var(1:1), l(1:1), model, err, pb%base)
      else
         call model_with_values(pb%deck, pb%var, l, model, err, pb%base)
      end if
      if (allocated(err)) return
      call cm%m%setup(model, pb%solver, p, pb%phase, pb%cfg%jacobian == 'exact', &
                      pb%cfg%fd_step, err)
      if (allocated(err)) return
      cm%lam = l;  cm%p = p
   end subroutine map_at

   !> P(x) at y = (x, lam...), with the monodromy and the derivatives in the variables
   !> (central differences; at a variable's lower bound one-sided, (-3 P(l) + 4 P(l + h)
   !> - P(l + 2h)) / 2h, as exact to second order) when asked.
   subroutine orbit_eval(pb, y, p, px, err, jac, dpdl, iterates)
      type(problem_t), intent(inout) :: pb                 !! problem
      real(dp), intent(in) :: y(:)                         !! (x, lambda(1:nl))
      integer, intent(in) :: p                             !! periods
      real(dp), intent(out) :: px(:)                       !! P(x)
      type(error_t), allocatable, intent(out) :: err       !! failure
      real(dp), intent(out), optional :: jac(:, :)         !! P_x
      real(dp), intent(out), optional :: dpdl(:, :)        !! (n, nl) P_lambda
      real(dp), intent(out), optional :: iterates(:, :)    !! (n, p)
      real(dp), allocatable :: lam(:), pp(:), pm(:)
      real(dp) :: h
      integer :: n, k
      n = pb%n
      lam = y(n + 1:)
      call map_at(pb, pb%center, lam, p, err);  if (allocated(err)) return
      call pb%center%m%evaluate(y(1:n), px, err, jac=jac, iterates=iterates)
      call count_map(pb, p, 1)
      if (allocated(err) .or. .not. present(dpdl)) return
      allocate(pp(n), pm(n))
      do k = 1, size(lam)
         h = 1.0e-6_dp * pb%scale(k)
         lam = y(n + 1:);  lam(k) = lam(k) + h
         call map_at(pb, pb%aux, lam, p, err);  if (allocated(err)) return
         call pb%aux%m%evaluate(y(1:n), pp, err);  if (allocated(err)) return
         if (below_range(pb%var(k), y(n + k) - h)) then
            ! at the bound: one-sided, second order, from P(l), P(l + h), P(l + 2h)
            lam(k) = lam(k) + h
            call map_at(pb, pb%aux, lam, p, err);  if (allocated(err)) return
            call pb%aux%m%evaluate(y(1:n), pm, err);  if (allocated(err)) return
            dpdl(:, k) = (-3.0_dp * px + 4.0_dp * pp - pm) / (2.0_dp * h)
         else
            lam(k) = lam(k) - 2.0_dp * h
            call map_at(pb, pb%aux, lam, p, err);  if (allocated(err)) return
            call pb%aux%m%evaluate(y(1:n), pm, err);  if (allocated(err)) return
            dpdl(:, k) = (pp - pm) / (2.0_dp * h)
         end if
         call count_map(pb, p, 2)
      end do
   end subroutine orbit_eval

   !> Is x outside the allowed range of variable `var` (below its lower bound)?
   pure logical function below_range(var, x)
      type(deck_variable_t), intent(in) :: var   !! variable
      real(dp), intent(in) :: x                  !! value
      if (var%strict) then
         below_range = .not. (x > var%lower)
      else
         below_range = .not. (x >= var%lower)
      end if
   end function below_range

   !> Count map evaluations (of p periods each).
   subroutine count_map(pb, p, k)
      type(problem_t), intent(inout) :: pb
      integer, intent(in) :: p, k
      pb%evaluations = pb%evaluations + k
      pb%periods = pb%periods + k * p
   end subroutine count_map

   !> W b: <a, b>_W = dot(a, wvec(b)).
   pure function wvec(pb, b) result(w)
      type(problem_t), intent(in) :: pb       !! problem
      real(dp), intent(in) :: b(:)            !! vector (x, lambda...)
      real(dp) :: w(size(b))
      integer :: nr, k
      nr = pb%lp0%nr
      w(1:nr) = matmul(pb%lp0%kr, b(1:nr)) / (2.0_dp * pb%e_ref)**2
      w(nr + 1:2 * nr) = matmul(pb%lp0%mr, b(nr + 1:2 * nr)) / (2.0_dp * pb%e_ref)**2
      do k = 1, size(b) - 2 * nr
         w(2 * nr + k) = b(2 * nr + k) / pb%scale(k)**2
      end do
   end function wvec

   !> <a, b>_W.
   pure real(dp) function wdot(pb, a, b)
      type(problem_t), intent(in) :: pb       !! problem
      real(dp), intent(in) :: a(:), b(:)      !! vectors
      wdot = dot_product(a, wvec(pb, b))
   end function wdot

   !> Solve a x = b (a overwritten); info /= 0: singular.
   subroutine solve_linear(a, b, info)
      real(dp), intent(inout) :: a(:, :)      !! matrix
      real(dp), intent(inout) :: b(:)         !! right-hand side, solution
      integer, intent(out) :: info            !! dgesv info
      integer :: ipiv(size(b))
      real(dp) :: r(size(b), 1)
      r(:, 1) = b
      call dgesv(size(b), 1, a, size(b), ipiv, r, size(b), info)
      b = r(:, 1)
   end subroutine solve_linear

   !> Pseudo-arclength corrector (one variable): the orbit at arclength sigma from ya along t.
   subroutine correct_point(pb, p, ya, t, sigma, pt, err)
      type(problem_t), intent(inout) :: pb            !! problem (one variable)
      integer, intent(in) :: p                        !! periods
      real(dp), intent(in) :: ya(:), t(:)             !! start point, unit tangent
      real(dp), intent(in) :: sigma                   !! arclength
      type(point_t), intent(inout) :: pt              !! y, jac, dpdl, iterations set
      type(error_t), allocatable, intent(out) :: err  !! no convergence, failure
      real(dp), allocatable :: px(:), a(:, :), b(:), d(:, :), wt(:)
      integer :: it, n, j, info
      real(dp) :: res, con, sz, res_prev
      n = pb%n
      pt%y = ya + sigma * t
      pt%p = p
      allocate(px(n), a(n + 1, n + 1), b(n + 1), d(n, 1))
      res_prev = huge(1.0_dp)
      if (allocated(pt%jac)) deallocate(pt%jac)
      allocate(pt%jac(n, n))
      wt = wvec(pb, t)
      do it = 0, pb%cfg%max_iterations
         call orbit_eval(pb, pt%y, p, px, err, jac=pt%jac, dpdl=d)
         if (allocated(err)) return
         pt%dpdl = d(:, 1)
         sz = max(energy_size(pb%lp0, pt%y(1:n)), 1.0e-3_dp * pb%e_ref)
         res = energy_size(pb%lp0, px - pt%y(1:n))
         con = dot_product(wt, pt%y - ya) - sigma
         pt%iterations = it
         if (res <= pb%cfg%tolerance * sz .and. abs(con) <= 1.0e-3_dp * abs(sigma) + &
             pb%cfg%tolerance) return
         ! stagnation at the map's round-off (long or strongly unstable orbits): accepted
         ! within 100 times the tolerance
         if (it >= 2 .and. res <= 1.0e2_dp * pb%cfg%tolerance * sz) then
            if (res > 0.5_dp * res_prev) return
         end if
         res_prev = res
         if (it == pb%cfg%max_iterations) exit
         a(1:n, 1:n) = pt%jac
         do j = 1, n
            a(j, j) = a(j, j) - 1.0_dp
         end do
         a(1:n, n + 1) = pt%dpdl
         a(n + 1, :) = wt
         b(1:n) = pt%y(1:n) - px
         b(n + 1) = -con
         call solve_linear(a, b, info)
         if (info /= 0) then
            call fatal_error(err, 'corrector: singular Jacobian (dgesv info=' // str(info) // ')')
            return
         end if
         if (sqrt(max(0.0_dp, wdot(pb, b, b))) > 0.5_dp + 2.0_dp * abs(sigma)) then
            call fatal_error(err, 'corrector: diverging (correction ' &
               // str(sqrt(wdot(pb, b, b))) // ')')
            return
         end if
         pt%y = pt%y + b
      end do
      call fatal_error(err, 'corrector: no convergence in ' // str(pb%cfg%max_iterations) &
         // ' iterations (residual ' // str(res / sz) // ')')
   end subroutine correct_point

   !> Unit tangent at a converged point, oriented along t_prev (one variable).
   subroutine tangent_of(pb, pt, t_prev, err)
      type(problem_t), intent(in) :: pb                !! problem
      type(point_t), intent(inout) :: pt               !! point (jac, dpdl set); t set
      real(dp), intent(in) :: t_prev(:)                !! previous tangent
      type(error_t), allocatable, intent(out) :: err   !! singular system
      real(dp), allocatable :: a(:, :), b(:)
      integer :: n, j, info
      n = pb%n
      allocate(a(n + 1, n + 1), b(n + 1))
      a(1:n, 1:n) = pt%jac
      do j = 1, n
         a(j, j) = a(j, j) - 1.0_dp
      end do
      a(1:n, n + 1) = pt%dpdl
      a(n + 1, :) = wvec(pb, t_prev)
      b = 0.0_dp;  b(n + 1) = 1.0_dp
      call solve_linear(a, b, info)
      if (info /= 0) then
         call fatal_error(err, 'tangent: singular system (dgesv info=' // str(info) // ')')
         return
      end if
      pt%t = b / sqrt(wdot(pb, b, b))
   end subroutine tangent_of

   !> Multipliers, their counts, the Poincare iterates and the grazing function of a point.
   subroutine measure_point(pb, pt, err)
      type(problem_t), intent(inout) :: pb             !! problem
      type(point_t), intent(inout) :: pt               !! converged point (jac set)
      type(error_t), allocatable, intent(out) :: err   !! failure
      type(orbit_extrema_t) :: ex
      real(dp), allocatable :: px(:)
      integer :: n
      n = pb%n
      call floquet_multipliers(pt%jac, pt%mu, err);  if (allocated(err)) return
      call count_unstable(pt%mu, pt%n_plus, pt%n_minus, pt%n_complex)
      allocate(px(n))
      if (allocated(pt%iterates)) deallocate(pt%iterates)
      allocate(pt%iterates(n, pt%p))
      call orbit_eval(pb, pt%y, pt%p, px, err, iterates=pt%iterates)
      if (allocated(err)) return
      call poincare_outputs(pb%center%m, pt)
      call orbit_extrema(pb%center%m, pt%y(1:n), pb%cfg%grazing_samples, ex, err)
      if (allocated(err)) return
      call count_map(pb, pt%p, 1)
      pt%impacts = sum(ex%intervals)
      pt%graze = ex%nearest;  pt%t_graze = ex%t_nearest;  pt%c_graze = ex%c_nearest
   end subroutine measure_point

   !> Root strain, its rate and the tip displacement at the p section points of an orbit.
   subroutine poincare_outputs(m, pt)
      type(orbit_map_t), intent(in) :: m               !! map of the point
      type(point_t), intent(inout) :: pt               !! point (iterates set)
      real(dp), allocatable :: u(:), v(:)
      integer :: k, nr
      nr = m%lp%nr
      allocate(u(m%model%n), v(m%model%n))
      pt%p_strain = [(0.0_dp, k = 1, pt%p)]
      pt%p_rate = pt%p_strain;  pt%p_tip = pt%p_strain
      do k = 1, pt%p
         call expand_state(m%lp, pt%iterates(:, k), u, v)
         pt%p_strain(k) = dot_product(m%model%sys%strain_row, u)
         pt%p_rate(k) = dot_product(m%model%sys%strain_row, v)
         if (m%model%sys%tip_dof > 0) pt%p_tip(k) = u(m%model%sys%tip_dof)
      end do
   end subroutine poincare_outputs

   !> Test function of kind k at a measured point: 1 fold (lambda component of the tangent),
   !> 2 branch point (prod (mu_i - 1)), 3 period doubling (prod (mu_i + 1)), 4 Neimark-Sacker
   !> (|mu| - 1 of the complex multiplier nearest the unit circle), 5 grazing (the extremum of
   !> d nearest 0).
   pure real(dp) function test_value(pt, k, nl) result(g)
      type(point_t), intent(in) :: pt          !! point
      integer, intent(in) :: k                 !! kind
      integer, intent(in) :: nl                !! number of variables (tangent length - n)
      integer :: i, n
      n = size(pt%y) - nl
      select case (k)
      case (1)
         g = pt%t(n + 1)
      case (2)
         g = real(product(pt%mu - (1.0_dp, 0.0_dp)))
      case (3)
         g = real(product(pt%mu + (1.0_dp, 0.0_dp)))
      case (4)
         ! the complex pair nearest the unit circle (a product over all pairs would also change
         ! sign where two real multipliers inside the circle meet)
         g = huge(1.0_dp)
         do i = 1, size(pt%mu)
            if (aimag(pt%mu(i)) == 0.0_dp) cycle
            if (abs(abs(pt%mu(i)) - 1.0_dp) < abs(g)) g = abs(pt%mu(i)) - 1.0_dp
         end do
      case default
         g = pt%graze
      end select
   end function test_value

   !> A null vector of a - s I (s = -1: period doubling, +1: fold) by two steps of inverse
   !> iteration, normalised to max |v_i| = 1.
   subroutine null_vector(a, s, v)
      real(dp), intent(in) :: a(:, :)          !! monodromy
      real(dp), intent(in) :: s                !! the multiplier
      real(dp), allocatable, intent(out) :: v(:)   !! null vector
      real(dp), allocatable :: m(:, :)
      integer :: n, j, k, info
      n = size(a, 1)
      allocate(v(n))
      v = [(1.0_dp + 0.1_dp * real(mod(j * 7, 13), dp), j = 1, n)]
      do k = 1, 3
         m = a
         do j = 1, n
            m(j, j) = m(j, j) - s + 1.0e-12_dp
         end do
         call solve_linear(m, v, info)
         if (info /= 0) exit
         v = v / maxval(abs(v))
      end do
   end subroutine null_vector
end module gapbeam_continuation_problem
