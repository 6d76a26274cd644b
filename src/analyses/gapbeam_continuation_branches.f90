!> The branches of a continuation (issue 14): the implementation of run_continuation (see
!> gapbeam_continuation for the method): the start orbit, pseudo-arclength branches, the
!> bifurcations on them detected and located, the switching at period doublings, and the
!> two-parameter curves (gapbeam_bifurcation_curves). A submodule, so that the job depends on
!> the interface only.
submodule (gapbeam_continuation) gapbeam_continuation_branches
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_model, only: model_t, has_tube_physics
   use gapbeam_integrator, only: tube_physics_text
   use gapbeam_deck_variable, only: parse_deck_variable, check_deck_variable, get_deck_value, &
      deck_variable_label
   use gapbeam_model_builder, only: build_model
   use gapbeam_continuation_types, only: branch_t, curve_t
   use gapbeam_transition, only: setup_linear_parts, reduce_state
   use gapbeam_periodic, only: newton_orbit, transient_orbit, energy_size
   use gapbeam_continuation_problem, only: problem_t, point_t, map_at, correct_point, &
      tangent_of, measure_point, test_value, wdot, null_vector, below_range
   use gapbeam_bifurcation_curves, only: follow_curves, bif_t
   implicit none

   character(len=*), parameter :: kind_names(5) = [character(len=16) :: 'saddle_node', &
      'branch_point', 'period_doubling', 'neimark_sacker', 'grazing']

   !> The points, branches and bifurcations found so far.
   type :: store_t
      integer :: n = 0                                  !! points
      type(point_t), allocatable :: pts(:)              !! the points
      integer, allocatable :: branch_of(:)              !! branch of each point
      integer :: nb = 0                                 !! branches
      type(branch_t), allocatable :: branches(:)        !! the branches
      type(bif_t), allocatable :: bifs(:)               !! bifurcations
      integer :: n_bif = 0
      logical, allocatable :: switched(:)               !! a PD already switched from
   end type store_t

contains

   !> Run the continuation a deck asks for.
   module subroutine run_continuation(deck, res, err)
      type(deck_t), intent(in) :: deck                  !! validated deck
      type(continuation_result_t), intent(out) :: res   !! branches, bifurcations, curves
      type(error_t), allocatable, intent(out) :: err    !! set-up or start failure
      type(problem_t) :: pb
      type(point_t) :: p0
      type(store_t) :: st
      integer(int64) :: c0, c1, rate
      integer :: i
      call system_clock(c0, rate)
      call start_problem(deck, pb, err);  if (allocated(err)) return
      call start_orbit(pb, p0, err);  if (allocated(err)) return
      allocate(st%pts(64), st%branch_of(64), st%branches(8), st%bifs(16), st%switched(16))
      call follow_both(pb, p0, 0, st)
      ! the cascade: every period doubling found (also on doubled branches) is switched
      i = 0
      do while (i < st%n_bif)
         i = i + 1
         if (st%bifs(i)%kind /= 'period_doubling' .or. .not. pb%cfg%switch_period_doubling) &
            cycle
         if (st%switched(i)) cycle
         if (2 * st%bifs(i)%period > pb%cfg%max_period) cycle
         if (.not. st%bifs(i)%primary) cycle
         if (on_a_branch(pb, st, i)) cycle
         call switch_period_doubling(pb, st, i)
      end do
      call assemble(pb, st, res)
      if (pb%nvar == 2) call follow_curves(pb, st%bifs(1:st%n_bif), res%curves)
      res%map_evaluations = pb%evaluations
      res%periods_integrated = pb%periods
      call system_clock(c1)
      res%seconds = real(c1 - c0, dp) / real(rate, dp)
   end subroutine run_continuation

   !> Parse the variables, build the deck's model and the metric.
   subroutine start_problem(deck, pb, err)
      type(deck_t), intent(in) :: deck                  !! deck
      type(problem_t), intent(out) :: pb                !! problem
      type(error_t), allocatable, intent(out) :: err    !! unknown variable, build failure
      real(dp), allocatable :: u0(:), v0(:)
      pb%deck = deck
      pb%cfg = deck%continuation
      pb%solver = deck%solver
      pb%phase = deck%output%poincare_phase_deg / 360.0_dp
      call parse_deck_variable(pb%cfg%parameter, pb%var(1), err)
      if (.not. allocated(err)) call check_deck_variable(deck, pb%var(1), err)
      if (allocated(err)) return
      pb%nvar = 1
      if (len_trim(pb%cfg%parameter2) > 0) then
         call parse_deck_variable(pb%cfg%parameter2, pb%var(2), err)
         if (.not. allocated(err)) call check_deck_variable(deck, pb%var(2), err)
         if (allocated(err)) return
         pb%nvar = 2
         pb%lam2 = get_deck_value(deck, pb%var(2))
         pb%scale(2) = pb%cfg%parameter2_max - pb%cfg%parameter2_min
         if (.not. (pb%scale(2) > 0.0_dp)) pb%scale(2) = max(abs(pb%lam2), 1.0e-12_dp)
      end if
      pb%scale(1) = pb%cfg%parameter_max - pb%cfg%parameter_min
      if (.not. (pb%scale(1) > 0.0_dp)) pb%scale(1) = max(abs(get_deck_value(deck, pb%var(1))), &
                                                         1.0e-12_dp)
      pb%loc_tol = pb%cfg%locate_tolerance
      if (.not. (pb%loc_tol > 0.0_dp)) pb%loc_tol = 1.0e-7_dp * pb%scale(1)
      call build_model(deck, pb%base, u0, v0, err);  if (allocated(err)) return
      ! the periodic orbit is a fixed point of the map of (u, v): a stick anchor, a second
      ! plane or point forces are beyond the exact transition and saltation matrices
      if (any(pb%var(1:pb%nvar)%name == 'friction') .or. &
          any(pb%var(1:pb%nvar)%group == 'point_forces')) then
         call fatal_error(err, 'continuation cannot vary friction or point forces (a ' &
            // 'stick state and loads out of the base motion are beyond its exact map): map ' &
            // 'them with a &sweep variable instead')
         return
      end if
      if (has_tube_physics(pb%base)) then
         call fatal_error(err, 'continuation cannot follow this model: ' &
            // tube_physics_text(pb%base) // '; continuation handles planar models with ' &
            // 'frictionless flat stops and base motion along w only (its periodic orbits are ' &
            // 'fixed points of the map of (u, v), which friction''s stick state and the ' &
            // 'second plane are not part of): map such models with a &sweep instead')
         return
      end if
      call setup_linear_parts(pb%base, pb%lp0, err);  if (allocated(err)) return
      pb%n = 2 * pb%lp0%nr
   end subroutine start_problem

   !> An orbit found with p periods that repeats after a divisor q < p of them (a period-1
   !> orbit asked as period 2) is a period-q orbit: continued as such, with a note (on p
   !> periods its multipliers would be the q-period ones to the power p/q, and a period
   !> doubling, mu = -1, could not be seen).
   subroutine own_period(pb, lam0, x, p, p0, err)
      type(problem_t), intent(inout) :: pb              !! problem
      real(dp), intent(in) :: lam0                      !! value of the variable
      real(dp), intent(inout) :: x(:)                   !! the orbit's section state
      integer, intent(inout) :: p                       !! its periods (reduced)
      type(point_t), intent(inout) :: p0                !! start point (monodromy redone)
      type(error_t), allocatable, intent(out) :: err    !! failure of the reduced orbit
      real(dp), allocatable :: px(:), it(:, :)
      real(dp) :: size0, tol
      integer :: q, asked
      if (p < 2) return
      allocate(px(pb%n), it(pb%n, p))
      call pb%center%m%evaluate(x, px, err, iterates=it)
      pb%evaluations = pb%evaluations + 1;  pb%periods = pb%periods + p
      if (allocated(err)) return
      size0 = max(energy_size(pb%lp0, x), tiny(1.0_dp))
      tol = max(1.0e-6_dp, 100.0_dp * pb%cfg%tolerance)
      do q = 1, p / 2
         if (mod(p, q) /= 0) cycle
         if (energy_size(pb%lp0, it(:, q) - x) > tol * size0) cycle
         asked = p
         p = q
         call map_at(pb, pb%center, [lam0], p, err);  if (allocated(err)) return
         call newton_orbit(pb%center%m, x, pb%cfg%tolerance, 3 * pb%cfg%max_iterations, &
                           p0%jac, err, p0%iterations)
         pb%evaluations = pb%evaluations + pb%center%m%evaluations
         pb%periods = pb%periods + p * pb%center%m%evaluations
         if (allocated(err)) return
         pb%note = 'the start orbit found with ' // str(asked) // ' periods repeats after ' &
            // str(q) // ' (distance ' // str(energy_size(pb%lp0, it(:, q) - x) / size0) &
            // ' of its size): continued as a period-' // str(q) // ' orbit (on ' &
            // str(asked) // ' periods its multipliers would be squared and a period ' &
            // 'doubling could not be detected)'
         return
      end do
   end subroutine own_period

   !> The start orbit: transient or given state, period, Newton; tangent towards increasing
   !> values of the variable; the metric's energy scale.
   subroutine start_orbit(pb, p0, err)
      type(problem_t), intent(inout) :: pb              !! problem
      type(point_t), intent(out) :: p0                  !! the start point, measured
      type(error_t), allocatable, intent(out) :: err    !! no orbit found
      type(model_t) :: model
      real(dp), allocatable :: u0(:), v0(:), x(:), t(:)
      real(dp) :: lam0
      integer :: p, nt
      lam0 = get_deck_value(pb%deck, pb%var(1))
      call build_model(pb%deck, model, u0, v0, err);  if (allocated(err)) return
      call map_at(pb, pb%center, [lam0], 1, err);  if (allocated(err)) return
      if (pb%cfg%start == 'given') then
         x = reduce_state(pb%center%m%lp, u0, v0)
         p = pb%cfg%period
      else
         nt = pb%cfg%transient_periods
         if (nt < 0) nt = pb%solver%transient_periods
         call transient_orbit(pb%center%m, u0, v0, nt, max(pb%cfg%max_period, 1), 1.0e-6_dp, &
                              x, p, err)
         if (allocated(err)) return
         pb%periods = pb%periods + nt + 2 * max(pb%cfg%max_period, 1) + 2
         if (pb%cfg%period > 0) p = pb%cfg%period
         if (p == 0) then
            call fatal_error(err, 'continuation: no periodic orbit of period up to ' &
               // str(pb%cfg%max_period) // ' after ' // str(nt) // ' transient periods at ' &
               // deck_variable_label(pb%var(1)) // ' = ' // str(lam0) // ' (chaotic or a ' &
               // 'long transient): give &continuation period, more transient_periods or ' &
               // 'another start value')
            return
         end if
      end if
      call map_at(pb, pb%center, [lam0], p, err);  if (allocated(err)) return
      allocate(p0%jac(pb%n, pb%n))
      call newton_orbit(pb%center%m, x, pb%cfg%tolerance, 3 * pb%cfg%max_iterations, p0%jac, &
                        err, p0%iterations)
      pb%evaluations = pb%evaluations + pb%center%m%evaluations
      pb%periods = pb%periods + p * pb%center%m%evaluations
      if (allocated(err)) then
         err%message = 'continuation: the start orbit (period ' // str(p) // ') at ' &
            // deck_variable_label(pb%var(1)) // ' = ' // str(lam0) // ': ' // err%message
         return
      end if
      call own_period(pb, lam0, x, p, p0, err);  if (allocated(err)) return
      pb%e_ref = max(energy_size(pb%lp0, x), tiny(1.0_dp))
      p0%y = [x, lam0]
      p0%p = p
      ! the derivative in the variable (a corrector step of length 0 at fixed value) and the
      ! tangent towards increasing values
      t = [spread(0.0_dp, 1, pb%n), pb%scale(1)]
      call correct_point(pb, p, p0%y, t / sqrt(wdot(pb, t, t)), 0.0_dp, p0, err)
      if (allocated(err)) return
      call tangent_of(pb, p0, t, err);  if (allocated(err)) return
      call measure_point(pb, p0, err)
   end subroutine start_orbit

   !> Follow the branch through p0 down and/or up (as the settings ask), as one branch.
   subroutine follow_both(pb, p0, parent, st)
      type(problem_t), intent(inout) :: pb     !! problem
      type(point_t), intent(in) :: p0          !! start point with its tangent (increasing)
      integer, intent(in) :: parent            !! branch switched from (0: none)
      type(store_t), intent(inout) :: st       !! results
      type(point_t), allocatable :: down(:), up(:)
      character(len=:), allocatable :: end_down, end_up
      type(point_t) :: q
      integer :: k, nd, nu, b
      nd = 0;  nu = 0
      end_down = 'not followed';  end_up = 'not followed'
      if (pb%cfg%direction /= 'up') then
         q = p0;  q%t = -p0%t
         call follow_branch(pb, q, 0, down, nd, end_down)
      end if
      if (pb%cfg%direction /= 'down') call follow_branch(pb, p0, 0, up, nu, end_up)
      b = new_branch(st, p0%p, parent)
      do k = nd, 2, -1
         down(k)%sigma = -down(k)%sigma
         call add_point(st, down(k), b)
      end do
      call add_point(st, p0, b)
      do k = 2, nu
         call add_point(st, up(k), b)
      end do
      st%branches(b)%ended = 'down: ' // end_down // '; up: ' // end_up
      call record_bifurcations(st, b)
   end subroutine follow_both

   !> Follow a branch from p0 along p0%t: the points (p0 first), located bifurcation points
   !> included, and why it ended. half > 0: a doubled branch, ended when it merges into the
   !> branch of period half.
   subroutine follow_branch(pb, p0, half, pts, np, ended, others, other_branch)
      type(problem_t), intent(inout) :: pb                 !! problem
      type(point_t), intent(in) :: p0                      !! start, measured, with tangent
      integer, intent(in) :: half                          !! period of the parent (0: none)
      type(point_t), allocatable, intent(out) :: pts(:)    !! the points
      integer, intent(out) :: np                           !! how many
      character(len=:), allocatable, intent(out) :: ended  !! why it stopped
      real(dp), intent(in), optional :: others(:, :)       !! points of other branches (y)
      integer, intent(in), optional :: other_branch(:)     !! their branches
      type(point_t) :: pa, pn
      type(point_t), allocatable :: found(:)
      type(error_t), allocatable :: err
      real(dp), allocatable :: dprev(:), dcur(:)
      real(dp) :: ds, ds_min, ds_max, lam, dmerge, e_start
      integer :: nf, k, n, n_unstable
      n = pb%n
      ds_max = step_scaled(pb, pb%cfg%step_max, 1.0_dp / 50.0_dp)
      ds_min = step_scaled(pb, pb%cfg%step_min, 1.0e-7_dp)
      ds = min(step_scaled(pb, pb%cfg%step, 1.0_dp / 200.0_dp), ds_max)
      allocate(pts(64))
      np = 1;  pts(1) = p0
      pa = p0
      if (half > 0) dprev = p0%iterates(:, p0%p / 2) - p0%y(1:n)
      n_unstable = 0
      e_start = pb%e_ref
      pb%e_ref = max(energy_size(pb%lp0, p0%y(1:n)), 1.0e-2_dp * e_start)
      pa%t = pa%t / sqrt(wdot(pb, pa%t, pa%t))
      ended = 'max_points reached'
      do while (np < pb%cfg%max_points)
         call correct_point(pb, pa%p, pa%y, pa%t, ds, pn, err)
         if (.not. allocated(err)) call tangent_of(pb, pn, pa%t, err)
         if (.not. allocated(err)) then
            if (wdot(pb, pa%t, pn%t) < 0.8_dp) call fatal_error(err, 'the tangent turned ' &
               // 'by more than 37 degrees')
         end if
         if (.not. allocated(err)) call measure_point(pb, pn, err)
         if (allocated(err)) then
            ds = 0.5_dp * ds
            if (ds < ds_min) then
               if (pa%t(n + 1) < 0.0_dp .and. below_range(pb%var(1), pa%y(n + 1) &
                   - 1.0e-6_dp * pb%scale(1))) then
                  ! started at (or came to) the variable's bound and heads below it
                  ended = 'reached the lower bound of ' // deck_variable_label(pb%var(1)) &
                     // ' (' // str(pb%var(1)%lower) // ') at ' // str(pa%y(n + 1))
               else
                  ended = 'step below step_min at ' // str(pa%y(n + 1)) // ': ' // err%message
               end if
               exit
            end if
            deallocate(err)
            cycle
         end if
         pn%sigma = pa%sigma + ds
         if (half > 0) then
            ! a doubled branch that passes through its parent (the pitchfork of P^p) comes
            ! back as the same orbits started half a period later: P^(p/2)(x) - x reverses
            dcur = pn%iterates(:, pn%p / 2) - pn%y(1:n)
            dmerge = energy_size(pb%lp0, dcur) / max(energy_size(pb%lp0, pn%y(1:n)), &
                                                     tiny(1.0_dp))
            if (wdot(pb, [dcur, 0.0_dp], [dprev, 0.0_dp]) < 0.0_dp .or. &
                dmerge < 1.0e-3_dp) then
               ended = 'merged into the period-' // str(half) // ' branch between ' &
                  // str(pa%y(n + 1)) // ' and ' // str(pn%y(n + 1))
               exit
            end if
            dprev = dcur
         end if
         ! a closed branch (an isola, or a doubled branch around its parent) comes back
         do k = 1, np - 5
            if (sqrt(max(0.0_dp, wdot(pb, pts(k)%y - pn%y, pts(k)%y - pn%y))) < 0.5_dp * ds) &
               then
               ended = 'closed: back at its point ' // str(k) // ' (' // str(pn%y(n + 1)) // ')'
               exit
            end if
         end do
         if (index(ended, 'closed') == 1) exit
         if (present(others)) then
            ! the branch runs into one followed before (from its other end): stop there
            do k = 1, size(others, 2)
               if (sqrt(max(0.0_dp, wdot(pb, others(:, k) - pn%y, others(:, k) - pn%y))) &
                   < 0.5_dp * ds) then
                  ended = 'joined branch ' // str(other_branch(k)) // ' at ' // str(pn%y(n + 1))
                  exit
               end if
            end do
            if (index(ended, 'joined') == 1) exit
         end if
         call locate_all(pb, pa, pn, ds, found, nf)
         do k = 1, nf
            call push_point(pts, np, found(k))
         end do
         call push_point(pts, np, pn)
         lam = pn%y(n + 1)
         if (lam < pb%cfg%parameter_min .or. lam > pb%cfg%parameter_max) then
            ended = 'left the parameter range at ' // str(lam)
            exit
         end if
         if (half > 0 .and. pb%cfg%unstable_points > 0) then
            if (maxval(abs(pn%mu)) > 1.0_dp) then
               n_unstable = n_unstable + 1
            else
               n_unstable = 0
            end if
            if (n_unstable >= pb%cfg%unstable_points) then
               ended = str(n_unstable) // ' unstable points in a row (unstable_points) at ' &
                  // str(lam)
               exit
            end if
         end if
         ! the metric follows the size of the orbit (an orbit that grows tenfold towards a
         ! resonance would otherwise shrink the steps in the variable tenfold); the tangent is
         ! normalised again in the new metric
         pb%e_ref = max(energy_size(pb%lp0, pn%y(1:n)), 1.0e-2_dp * e_start)
         pn%t = pn%t / sqrt(wdot(pb, pn%t, pn%t))
         if (pn%iterations <= 2) then
            ds = min(1.5_dp * ds, ds_max)
         else if (pn%iterations >= 4) then
            ds = max(0.7_dp * ds, ds_min)
         end if
         pa = pn
      end do
   end subroutine follow_branch

   !> A step given in the unit of the variable as a scaled arclength (default: fraction of the
   !> scale).
   pure real(dp) function step_scaled(pb, step, fraction) result(ds)
      type(problem_t), intent(in) :: pb
      real(dp), intent(in) :: step, fraction
      if (step > 0.0_dp) then
         ds = step / pb%scale(1)
      else
         ds = fraction
      end if
   end function step_scaled

   !> Detect and locate every bifurcation between consecutive points a and b (ds apart).
   subroutine locate_all(pb, a, b, ds, found, nf)
      type(problem_t), intent(inout) :: pb               !! problem
      type(point_t), intent(in) :: a, b                  !! consecutive points
      real(dp), intent(in) :: ds                         !! their arclength distance
      type(point_t), allocatable, intent(out) :: found(:)   !! located points, by arclength
      integer, intent(out) :: nf                         !! how many
      type(point_t) :: q, tmp
      logical :: fold
      integer :: k, i, j
      allocate(found(5))
      nf = 0
      fold = a%t(pb%n + 1) * b%t(pb%n + 1) < 0.0_dp
      do k = 1, 5
         select case (k)
         case (1);  if (.not. fold) cycle
         case (2);  if (fold .or. mod(a%n_plus - b%n_plus, 2) == 0) cycle
         case (3);  if (mod(a%n_minus - b%n_minus, 2) == 0) cycle
         case (4);  if (a%n_complex == b%n_complex) cycle
         case (5);  if (a%impacts == b%impacts) cycle
         end select
         call locate(pb, a, b, ds, k, q)
         if (.not. allocated(q%y)) cycle
         ! a complex pair born from two real multipliers off the unit circle changes the
         ! count without crossing it: a Neimark-Sacker point has a pair on the circle
         if (k == 4) then
            if (.not. any(abs(abs(q%mu) - 1.0_dp) < 1.0e-3_dp .and. &
                          aimag(q%mu) /= 0.0_dp)) cycle
         end if
         nf = nf + 1
         q%located = .true.
         q%kind = k
         found(nf) = q
      end do
      do i = 2, nf                  ! order by arclength
         tmp = found(i);  j = i - 1
         do while (j >= 1)
            if (found(j)%sigma <= tmp%sigma) exit
            found(j + 1) = found(j);  j = j - 1
         end do
         found(j + 1) = tmp
      end do
   end subroutine locate_all

   !> Locate the zero of test function k between a (sigma 0) and b (sigma ds) on the
   !> arclength (Illinois; bisection on the crossing count when the test function does not
   !> change sign). q%y unallocated when it fails.
   subroutine locate(pb, a, b, ds, k, q)
      type(problem_t), intent(inout) :: pb       !! problem
      type(point_t), intent(in) :: a, b          !! bracket
      real(dp), intent(in) :: ds                 !! arclength from a to b
      integer, intent(in) :: k                   !! test function
      type(point_t), intent(out) :: q            !! the located point
      type(point_t) :: m, lo, hi
      type(error_t), allocatable :: err
      real(dp) :: slo, shi, glo, ghi, sm, gm
      logical :: by_count
      integer :: it, side, n
      n = pb%n
      lo = a;  hi = b;  slo = 0.0_dp;  shi = ds
      glo = test_value(a, k, 1);  ghi = test_value(b, k, 1)
      by_count = glo * ghi > 0.0_dp
      if (by_count) then
         glo = -1.0_dp;  ghi = 1.0_dp
      end if
      side = 0
      do it = 1, 80
         if (abs(hi%y(n + 1) - lo%y(n + 1)) <= pb%loc_tol .and. it > 1) exit
         if (by_count .or. mod(it, 6) == 0) then
            sm = 0.5_dp * (slo + shi)
         else
            sm = slo + (shi - slo) * glo / (glo - ghi)
            sm = max(slo + 0.02_dp * (shi - slo), min(shi - 0.02_dp * (shi - slo), sm))
         end if
         call correct_point(pb, a%p, a%y, a%t, sm, m, err)
         if (.not. allocated(err)) call tangent_of(pb, m, a%t, err)
         if (.not. allocated(err)) call measure_point(pb, m, err)
         if (allocated(err)) return
         m%sigma = a%sigma + sm
         if (by_count) then
            gm = merge(-1.0_dp, 1.0_dp, same_side(a, m, k))
         else
            gm = test_value(m, k, 1)
         end if
         if ((gm < 0.0_dp) .eqv. (glo < 0.0_dp)) then
            lo = m;  slo = sm;  glo = gm
            if (side == -1) ghi = 0.5_dp * ghi
            side = -1
         else
            hi = m;  shi = sm;  ghi = gm
            if (side == 1) glo = 0.5_dp * glo
            side = 1
         end if
      end do
      if (by_count .or. abs(glo) <= abs(ghi)) then
         q = lo
      else
         q = hi
      end if
      if (by_count .and. k == 5) q = hi      ! the first orbit with the new contact count
   end subroutine locate

   !> m is on a's side of the crossing of kind k (by the counts).
   pure logical function same_side(a, m, k)
      type(point_t), intent(in) :: a, m
      integer, intent(in) :: k
      select case (k)
      case (2);  same_side = mod(a%n_plus - m%n_plus, 2) == 0
      case (3);  same_side = mod(a%n_minus - m%n_minus, 2) == 0
      case (4);  same_side = a%n_complex == m%n_complex
      case (5);  same_side = a%impacts == m%impacts
      case default;  same_side = .true.
      end select
   end function same_side

   !> The points (y) of the branches of period p so far, and their branches.
   subroutine same_period_points(st, p, ys, bs)
      type(store_t), intent(in) :: st
      integer, intent(in) :: p
      real(dp), allocatable, intent(out) :: ys(:, :)
      integer, allocatable, intent(out) :: bs(:)
      integer :: j, m
      m = count(st%pts(1:st%n)%p == p)
      allocate(ys(size(st%pts(1)%y), m), bs(m))
      m = 0
      do j = 1, st%n
         if (st%pts(j)%p /= p) cycle
         m = m + 1
         ys(:, m) = st%pts(j)%y
         bs(m) = st%branch_of(j)
      end do
   end subroutine same_period_points

   !> A branch of twice the period of bifurcation i passes through its point already.
   logical function on_a_branch(pb, st, i)
      type(problem_t), intent(in) :: pb
      type(store_t), intent(in) :: st
      integer, intent(in) :: i
      integer :: j, n
      real(dp) :: d
      n = pb%n
      on_a_branch = .false.
      associate (y => st%pts(st%bifs(i)%point)%y)
         do j = 1, st%n
            if (st%pts(j)%p /= 2 * st%bifs(i)%period) cycle
            d = wdot(pb, st%pts(j)%y - y, st%pts(j)%y - y)
            if (sqrt(d) < 1.0e-4_dp) then
               on_a_branch = .true.
               return
            end if
         end do
      end associate
   end function on_a_branch

   !> Switch at period doubling i to the doubled branch and follow it.
   subroutine switch_period_doubling(pb, st, i)
      type(problem_t), intent(inout) :: pb     !! problem
      type(store_t), intent(inout) :: st       !! results
      integer, intent(in) :: i                 !! the bifurcation
      type(point_t) :: pd, q
      type(point_t), allocatable :: pts(:)
      type(error_t), allocatable :: err
      real(dp), allocatable :: v(:), t0(:), others(:, :)
      integer, allocatable :: other_branch(:)
      real(dp), parameter :: switch_steps(6) = [0.02_dp, 0.04_dp, 0.01_dp, 0.08_dp, &
                                                0.005_dp, 0.16_dp]
      character(len=:), allocatable :: ended
      real(dp) :: ds, dist
      integer :: np, b, k, n, tries, j
      n = pb%n
      st%switched(i) = .true.
      pd = st%pts(st%bifs(i)%point)
      call null_vector(pd%jac, -1.0_dp, v)
      ! along v, orthogonal (in W) to the parent branch: the hyperplane of the corrector then
      ! misses the parent's orbits (to first order) and cuts the doubled branch
      t0 = [v, 0.0_dp]
      t0 = t0 / sqrt(wdot(pb, t0, t0))
      t0 = t0 - wdot(pb, t0, pd%t) * pd%t
      t0 = t0 / sqrt(wdot(pb, t0, t0))
      do tries = 1, 6
         ds = switch_steps(tries)
         call correct_point(pb, 2 * pd%p, pd%y, t0, ds, q, err)
         if (.not. allocated(err)) call tangent_of(pb, q, t0, err)
         if (.not. allocated(err)) call measure_point(pb, q, err)
         if (.not. allocated(err)) then
            dist = energy_size(pb%lp0, q%iterates(:, pd%p) - q%y(1:n)) &
                   / max(energy_size(pb%lp0, q%y(1:n)), tiny(1.0_dp))
            if (dist > 1.0e-4_dp) exit
            call fatal_error(err, 'landed on the period-' // str(pd%p) // ' orbit')
         end if
         if (tries == 6) then
            st%bifs(i)%note = 'no switch to period ' // str(2 * pd%p) // ': ' // err%message
            return
         end if
         deallocate(err)
      end do
      ! orient away from the bifurcation point
      if (wdot(pb, q%t, q%y - pd%y) < 0.0_dp) q%t = -q%t
      q%sigma = ds
      call same_period_points(st, 2 * pd%p, others, other_branch)
      call follow_branch(pb, q, pd%p, pts, np, ended, others, other_branch)
      b = new_branch(st, 2 * pd%p, st%bifs(i)%branch)
      call doubled(pd)
      pd%sigma = 0.0_dp
      call add_point(st, pd, b)              ! the branch starts at the bifurcation
      do k = 1, np
         call add_point(st, pts(k), b)
      end do
      ! a doubled branch that merges ends at another period doubling of its parent (the
      ! nearest to its last point): that point closes it, and gives the same branch
      if (index(ended, 'merged') == 1) then
         j = 0
         do k = 1, st%n_bif
            if (st%bifs(k)%kind /= 'period_doubling' .or. st%bifs(k)%period /= pd%p / 2 &
                .or. k == i) cycle
            if (j == 0) then
               j = k
            else if (abs(st%bifs(k)%parameter - pts(np)%y(n + 1)) < &
                     abs(st%bifs(j)%parameter - pts(np)%y(n + 1))) then
               j = k
            end if
         end do
         if (j > 0) then
            if (abs(st%bifs(j)%parameter - pts(np)%y(n + 1)) <= 0.05_dp * pb%scale(1)) then
               st%switched(j) = .true.
               q = st%pts(st%bifs(j)%point)
               call doubled(q)
               q%sigma = pts(np)%sigma
               call add_point(st, q, b)
            end if
         end if
      end if
      st%branches(b)%ended = ended
      call record_bifurcations(st, b)
   end subroutine switch_period_doubling

   !> A period-doubling point as the first (or last) point of the doubled branch: the same
   !> orbit run over twice the periods.
   pure subroutine doubled(pt)
      type(point_t), intent(inout) :: pt
      pt%iterates = reshape([pt%iterates, pt%iterates], [size(pt%iterates, 1), 2 * pt%p])
      pt%p_strain = [pt%p_strain, pt%p_strain];  pt%p_rate = [pt%p_rate, pt%p_rate]
      pt%p_tip = [pt%p_tip, pt%p_tip]
      pt%p = 2 * pt%p
      pt%kind = 0;  pt%located = .true.
   end subroutine doubled

   !> Bifurcations of branch b from its located points.
   subroutine record_bifurcations(st, b)
      type(store_t), intent(inout) :: st       !! results
      integer, intent(in) :: b                 !! branch
      integer :: j, k
      type(bif_t), allocatable :: tmp(:)
      logical, allocatable :: sw(:)
      do j = st%branches(b)%first, st%branches(b)%last
         if (.not. st%pts(j)%located .or. st%pts(j)%kind == 0) cycle
         k = st%pts(j)%kind
         if (st%n_bif == size(st%bifs)) then
            allocate(tmp(2 * st%n_bif), sw(2 * st%n_bif))
            tmp(1:st%n_bif) = st%bifs(1:st%n_bif);  sw(1:st%n_bif) = st%switched(1:st%n_bif)
            call move_alloc(tmp, st%bifs);  call move_alloc(sw, st%switched)
         end if
         st%n_bif = st%n_bif + 1
         st%switched(st%n_bif) = .false.
         associate (bf => st%bifs(st%n_bif), pt => st%pts(j))
            bf%kind = kind_names(k)
            bf%point = j
            bf%branch = b
            bf%period = pt%p
            bf%parameter = pt%y(size(pt%y))
            bf%multiplier = critical_multiplier(pt%mu, k)
            bf%graze = pt%graze
            bf%t_graze = pt%t_graze;  bf%c_graze = pt%c_graze
            bf%y = pt%y
            bf%jac = pt%jac
            ! the orbit is stable on one side: every other multiplier inside the unit circle
            ! (grazing: the orbit is stable there)
            bf%primary = count(abs(pt%mu) > 1.0_dp + 1.0e-6_dp) == 0 .or. &
                         (count(abs(pt%mu) > 1.0_dp + 1.0e-6_dp) == 1 .and. k /= 5 .and. &
                          abs(bf%multiplier) > 1.0_dp + 1.0e-6_dp)
         end associate
      end do
   end subroutine record_bifurcations

   !> The multiplier that crosses at a bifurcation of kind k.
   pure complex(dp) function critical_multiplier(mu, k) result(c)
      complex(dp), intent(in) :: mu(:)
      integer, intent(in) :: k
      integer :: i
      real(dp) :: best, d
      c = mu(1)
      best = huge(1.0_dp)
      do i = 1, size(mu)
         select case (k)
         case (1, 2);  d = abs(mu(i) - (1.0_dp, 0.0_dp))
         case (3);  d = abs(mu(i) + (1.0_dp, 0.0_dp))
         case (4)
            if (aimag(mu(i)) <= 0.0_dp) cycle
            d = abs(abs(mu(i)) - 1.0_dp)
         case default         ! grazing: the largest multiplier
            return
         end select
         if (d < best) then
            best = d;  c = mu(i)
         end if
      end do
   end function critical_multiplier

   !> A new branch of period p (its points follow).
   integer function new_branch(st, p, parent) result(b)
      type(store_t), intent(inout) :: st
      integer, intent(in) :: p, parent
      type(branch_t), allocatable :: tmp(:)
      if (st%nb == size(st%branches)) then
         allocate(tmp(2 * st%nb))
         tmp(1:st%nb) = st%branches(1:st%nb)
         call move_alloc(tmp, st%branches)
      end if
      st%nb = st%nb + 1
      b = st%nb
      st%branches(b)%period = p
      st%branches(b)%parent = parent
      st%branches(b)%first = st%n + 1
      st%branches(b)%last = st%n
      st%branches(b)%ended = ''
   end function new_branch

   !> Append a point to branch b (the last branch).
   subroutine add_point(st, pt, b)
      type(store_t), intent(inout) :: st
      type(point_t), intent(in) :: pt
      integer, intent(in) :: b
      integer, allocatable :: bo(:)
      call push_point(st%pts, st%n, pt)
      if (st%n > size(st%branch_of)) then
         allocate(bo(size(st%pts)))
         bo(1:size(st%branch_of)) = st%branch_of
         call move_alloc(bo, st%branch_of)
      end if
      st%branch_of(st%n) = b
      st%branches(b)%last = st%n
   end subroutine add_point

   !> Append to a growing list of points.
   subroutine push_point(pts, n, pt)
      type(point_t), allocatable, intent(inout) :: pts(:)
      integer, intent(inout) :: n
      type(point_t), intent(in) :: pt
      type(point_t), allocatable :: tmp(:)
      if (n == size(pts)) then
         allocate(tmp(2 * n))
         tmp(1:n) = pts(1:n)
         call move_alloc(tmp, pts)
      end if
      n = n + 1
      pts(n) = pt
   end subroutine push_point

   !> Results from the store.
   subroutine assemble(pb, st, res)
      type(problem_t), intent(in) :: pb                 !! problem
      type(store_t), intent(in) :: st                   !! points, branches, bifurcations
      type(continuation_result_t), intent(inout) :: res !! result
      integer :: j, n, pm, k
      real(dp) :: nan
      nan = transfer(-2251799813685248_int64, 1.0_dp)
      n = pb%n
      res%note = ''
      if (allocated(pb%note)) res%note = pb%note
      res%parameter_name = deck_variable_label(pb%var(1))
      res%parameter_units = trim(pb%var(1)%units)
      res%parameter2_name = ''
      res%parameter2_units = ''
      if (pb%nvar == 2) then
         res%parameter2_name = deck_variable_label(pb%var(2))
         res%parameter2_units = trim(pb%var(2)%units)
         res%parameter2_value = pb%lam2
      end if
      res%n = st%n;  res%n_state = n
      res%dofs = pb%lp0%ir
      pm = 1
      do j = 1, st%n
         pm = max(pm, st%pts(j)%p)
      end do
      allocate(res%parameter(st%n), res%state(n, st%n), res%period(st%n), res%branch(st%n), &
         res%multipliers(n, st%n), res%stable(st%n), res%arclength(st%n), &
         res%iterations(st%n), res%located(st%n), res%grazing(st%n), res%impacts(st%n))
      allocate(res%p_strain(pm, st%n), res%p_rate(pm, st%n), res%p_tip(pm, st%n), source=nan)
      do j = 1, st%n
         associate (pt => st%pts(j))
            res%parameter(j) = pt%y(n + 1)
            res%state(:, j) = pt%y(1:n)
            res%period(j) = pt%p
            res%branch(j) = st%branch_of(j)
            res%multipliers(:, j) = pt%mu
            res%stable(j) = maxval(abs(pt%mu)) < 1.0_dp
            res%arclength(j) = pt%sigma
            res%iterations(j) = pt%iterations
            res%located(j) = pt%located
            res%grazing(j) = pt%graze
            res%impacts(j) = pt%impacts
            do k = 1, pt%p
               res%p_strain(k, j) = pt%p_strain(k)
               res%p_rate(k, j) = pt%p_rate(k)
               res%p_tip(k, j) = pt%p_tip(k)
            end do
         end associate
      end do
      res%branches = st%branches(1:st%nb)
      res%n_bif = st%n_bif
      allocate(res%bif_kind(st%n_bif), res%bif_parameter(st%n_bif), res%bif_period(st%n_bif), &
         res%bif_branch(st%n_bif), res%bif_point(st%n_bif), res%bif_multiplier(st%n_bif), &
         res%bif_grazing(st%n_bif), res%bif_note(st%n_bif))
      do j = 1, st%n_bif
         res%bif_kind(j) = st%bifs(j)%kind
         res%bif_parameter(j) = st%bifs(j)%parameter
         res%bif_period(j) = st%bifs(j)%period
         res%bif_branch(j) = st%bifs(j)%branch
         res%bif_point(j) = st%bifs(j)%point
         res%bif_multiplier(j) = st%bifs(j)%multiplier
         res%bif_grazing(j) = st%bifs(j)%graze
         res%bif_note(j) = st%bifs(j)%note
      end do
      allocate(res%curves(0))
   end subroutine assemble
end submodule gapbeam_continuation_branches
