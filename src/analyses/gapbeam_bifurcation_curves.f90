!> Two-parameter continuation of bifurcation points (issue 14): the period-doubling, fold and
!> grazing points located on the branches (gapbeam_continuation), followed as curves in the
!> plane of two deck variables, e.g. (forcing frequency, forcing amplitude) or (frequency,
!> gap).
!>
!> **Extended system.** Unknowns z = (x, lambda_1, lambda_2); equations
!>    P^p(x; lambda) - x = 0   (the orbit)   and   phi(x, lambda) = 0   (the bifurcation),
!> plus the pseudo-arclength condition, by Newton's method; the curve's tangent is the null
!> vector of the (n+1) x (n+2) Jacobian, oriented along the previous one. The test functions:
!> * period doubling and fold: the bordered function phi = g of
!>      [P_x + s I, b; c', 0] (w, g) = (0, 1),   s = +1 (doubling) or -1 (fold),
!>   with b, c approximate left and right null vectors of P_x + s I, updated at every
!>   converged point (regular where P_x + s I has a one-dimensional null space);
!> * grazing: phi = the extremum of the grazing contact's penetration d nearest (in time) the
!>   grazing instant of the previous point (d' = 0 there, and d = 0 on the curve).
!> Derivatives of phi in x and lambda and of P in lambda are forward differences (steps 1e-6
!> of each component's scale); P_x is the monodromy.
!>
!> A curve starts at every located bifurcation of a kind listed in &continuation curves where
!> the orbit is stable on one side (a period doubling or fold where it loses stability, a
!> grazing of a stable orbit: the boundaries of what a sweep observes), not at one already on
!> a curve of its kind and period; it is followed both ways from it, and
!> ends outside [parameter_min, parameter_max] x [parameter2_min, parameter2_max], after
!> curve_max_points, or when a step below 1e-6 fails.
module gapbeam_bifurcation_curves
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_continuation_types, only: curve_t
   use gapbeam_periodic, only: orbit_extrema_t, orbit_extrema, energy_size
   use gapbeam_continuation_problem, only: problem_t, map_at, orbit_eval, wdot, wvec, &
      solve_linear, null_vector
   implicit none
   private
   public :: bif_t, follow_curves

   !> A located bifurcation, as the curves need it.
   type :: bif_t
      character(len=16) :: kind = ''             !! 'period_doubling', ...
      integer :: point = 0                       !! its point in the branch store
      integer :: branch = 0                      !! its branch
      integer :: period = 1                      !! period of the orbit
      real(dp) :: parameter = 0.0_dp             !! value of the variable
      complex(dp) :: multiplier = (0.0_dp, 0.0_dp)   !! critical multiplier
      real(dp) :: graze = 0.0_dp                 !! grazing function there [m]
      real(dp) :: t_graze = 0.0_dp               !! its instant [s]
      integer :: c_graze = 0                     !! its contact
      real(dp), allocatable :: y(:)              !! (x, lambda)
      real(dp), allocatable :: jac(:, :)         !! monodromy
      logical :: primary = .false.               !! every other multiplier inside the circle
      character(len=160) :: note = ''            !! e.g. why no doubled branch starts here
   end type bif_t

   !> What a curve carries from point to point.
   type :: curve_state_t
      integer :: kind = 0                        !! 1 fold, 3 doubling, 5 grazing
      integer :: p = 1                           !! periods
      real(dp), allocatable :: b(:), c(:)        !! bordering vectors
      real(dp) :: t_graze = 0.0_dp               !! grazing instant [s]
      integer :: c_graze = 0                     !! grazing contact
   end type curve_state_t

contains

   !> Curves through the located bifurcations of the kinds asked for.
   subroutine follow_curves(pb, bifs, curves)
      type(problem_t), intent(inout) :: pb              !! problem (two variables)
      type(bif_t), intent(in) :: bifs(:)                !! located bifurcations
      type(curve_t), allocatable, intent(inout) :: curves(:)   !! the curves
      type(curve_t) :: cv
      type(curve_t), allocatable :: tmp(:)
      integer :: i, k
      if (.not. allocated(curves)) allocate(curves(0))
      do i = 1, size(bifs)
         if (.not. any(pb%cfg%curves == bifs(i)%kind)) cycle
         if (.not. bifs(i)%primary) cycle
         if (on_a_curve(pb, curves, bifs(i))) cycle
         call follow_curve(pb, bifs(i), cv)
         allocate(tmp(size(curves) + 1))
         do k = 1, size(curves)
            tmp(k) = curves(k)
         end do
         tmp(size(curves) + 1) = cv
         call move_alloc(tmp, curves)
      end do
   end subroutine follow_curves

   !> The bifurcation lies on a curve already followed (same kind and period, within 1e-3 of
   !> the scales).
   logical function on_a_curve(pb, curves, bf)
      type(problem_t), intent(in) :: pb
      type(curve_t), intent(in) :: curves(:)
      type(bif_t), intent(in) :: bf
      integer :: k, j
      real(dp) :: d
      on_a_curve = .false.
      do k = 1, size(curves)
         if (curves(k)%kind /= bf%kind .or. curves(k)%period /= bf%period) cycle
         do j = 1, size(curves(k)%parameter)
            d = max(abs(curves(k)%parameter(j) - bf%parameter) / pb%scale(1), &
                    abs(curves(k)%parameter2(j) - pb%lam2) / pb%scale(2))
            if (d < 1.0e-3_dp) then
               on_a_curve = .true.
               return
            end if
         end do
      end do
   end function on_a_curve

   !> Follow the curve through one bifurcation both ways.
   subroutine follow_curve(pb, bf, cv)
      type(problem_t), intent(inout) :: pb      !! problem
      type(bif_t), intent(in) :: bf             !! start
      type(curve_t), intent(out) :: cv          !! the curve
      type(curve_state_t) :: cs
      real(dp), allocatable :: z0(:), t0(:), za(:, :), zb(:, :), bt(:)
      real(dp) :: s
      character(len=:), allocatable :: ea, eb
      type(error_t), allocatable :: err
      integer :: na, nb, n, j
      n = pb%n
      cv%kind = bf%kind;  cv%period = bf%period
      cs%p = bf%period
      select case (bf%kind)
      case ('period_doubling');  cs%kind = 3
      case ('saddle_node');  cs%kind = 1
      case default;  cs%kind = 5
      end select
      s = merge(1.0_dp, -1.0_dp, cs%kind == 3)
      call null_vector(bf%jac, -s, cs%c)
      call null_vector(transpose(bf%jac), -s, cs%b)
      cs%c = cs%c / norm2(cs%c);  cs%b = cs%b / norm2(cs%b)
      cs%t_graze = bf%t_graze;  cs%c_graze = bf%c_graze
      z0 = [bf%y(1:n), bf%parameter, pb%lam2]
      pb%e_ref = max(energy_size(pb%lp0, z0(1:n)), tiny(1.0_dp))
      ! the tangent at the start, towards increasing lambda_2
      bt = [spread(0.0_dp, 1, n + 1), pb%scale(2)]
      call curve_tangent(pb, cs, z0, bt / sqrt(wdot(pb, bt, bt)), t0, err)
      if (allocated(err)) then
         allocate(cv%parameter(1), cv%parameter2(1))
         cv%parameter = bf%parameter;  cv%parameter2 = pb%lam2
         cv%ended = 'no tangent at the start: ' // err%message
         return
      end if
      call follow_one(pb, cs, z0, -t0, za, na, ea)
      call follow_one(pb, cs, z0, t0, zb, nb, eb)
      allocate(cv%parameter(na + nb - 1), cv%parameter2(na + nb - 1))
      do j = 1, na
         cv%parameter(j) = za(n + 1, na - j + 1);  cv%parameter2(j) = za(n + 2, na - j + 1)
      end do
      do j = 2, nb
         cv%parameter(na + j - 1) = zb(n + 1, j);  cv%parameter2(na + j - 1) = zb(n + 2, j)
      end do
      cv%ended = 'one end: ' // ea // '; other end: ' // eb
   end subroutine follow_curve

   !> Follow one way from z0 along t0: the points (z0 first) and why it ended.
   subroutine follow_one(pb, cs0, z0, t0, zs, nz, ended)
      type(problem_t), intent(inout) :: pb                 !! problem
      type(curve_state_t), intent(in) :: cs0               !! state at the start
      real(dp), intent(in) :: z0(:), t0(:)                 !! start and tangent
      real(dp), allocatable, intent(out) :: zs(:, :)       !! (n+2, nz) points
      integer, intent(out) :: nz                           !! how many
      character(len=:), allocatable, intent(out) :: ended  !! why it stopped
      type(curve_state_t) :: cs
      real(dp), allocatable :: za(:), ta(:), z(:), t(:), tmp(:, :), jx(:, :)
      type(error_t), allocatable :: err
      real(dp) :: ds, ds_max, e_start
      integer :: its, n, k, n_fail
      n = pb%n
      cs = cs0
      ds_max = pb%cfg%curve_step
      if (.not. (ds_max > 0.0_dp)) ds_max = 0.02_dp
      ds = 0.25_dp * ds_max
      allocate(zs(n + 2, 32))
      nz = 1;  zs(:, 1) = z0
      za = z0
      e_start = max(energy_size(pb%lp0, z0(1:n)), tiny(1.0_dp))
      pb%e_ref = e_start
      ta = t0 / sqrt(wdot(pb, t0, t0))
      ended = 'curve_max_points reached'
      n_fail = 0
      do while (nz < pb%cfg%curve_max_points)
         call curve_correct(pb, cs, za, ta, ds, z, jx, its, err)
         if (.not. allocated(err)) call tangent_from(pb, jx, ta, t, err)
         if (.not. allocated(err)) then
            if (wdot(pb, ta, t) < 0.8_dp) call fatal_error(err, 'the tangent turned by ' &
               // 'more than 37 degrees')
         end if
         if (allocated(err)) then
            ds = 0.5_dp * ds
            n_fail = n_fail + 1
            if (n_fail > 5) then
               ended = 'crawling at (' // str(za(n + 1)) // ', ' // str(za(n + 2)) // '): more ' &
                  // 'than 5 failed steps in 20 points (the test function is not smooth here: ' &
                  // 'a grazing nearby?); last: ' // err%message
               exit
            end if
            if (ds < 1.0e-6_dp) then
               ended = 'step below 1e-6 at (' // str(za(n + 1)) // ', ' // str(za(n + 2)) &
                  // '): ' // err%message
               exit
            end if
            deallocate(err)
            cycle
         end if
         if (nz == size(zs, 2)) then
            allocate(tmp(n + 2, 2 * nz))
            tmp(:, 1:nz) = zs
            call move_alloc(tmp, zs)
         end if
         nz = nz + 1
         zs(:, nz) = z
         if (mod(nz, 20) == 0) n_fail = 0
         if (nz > 6) then
            if (minval([(sqrt(max(0.0_dp, wdot(pb, zs(:, k) - z, zs(:, k) - z))), &
                         k = 1, nz - 5)]) < 0.5_dp * ds) then
               ended = 'closed: the curve is back at an earlier point'
               exit
            end if
         end if
         ! stalled: 40 points that move less than 1e-3 of the plane (a non-smooth point of
         ! the test function, e.g. where the orbit grazes)
         if (nz > 40) then
            if (maxval(abs((zs(n + 1:n + 2, nz) - zs(n + 1:n + 2, nz - 40)) / pb%scale)) &
                < 1.0e-3_dp) then
               ended = 'stalled at (' // str(z(n + 1)) // ', ' // str(z(n + 2)) // '): 40 ' &
                  // 'points within 1e-3 of the ranges (a non-smooth point, e.g. grazing?)'
               exit
            end if
         end if
         if (z(n + 1) < pb%cfg%parameter_min .or. z(n + 1) > pb%cfg%parameter_max .or. &
             z(n + 2) < pb%cfg%parameter2_min .or. z(n + 2) > pb%cfg%parameter2_max) then
            ended = 'left the range at (' // str(z(n + 1)) // ', ' // str(z(n + 2)) // ')'
            exit
         end if
         if (its <= 4) then              ! quasi-Newton iterations
            ds = min(1.5_dp * ds, ds_max)
         else if (its <= 7) then
            ds = min(1.2_dp * ds, ds_max)
         else if (its >= 10) then
            ds = 0.7_dp * ds
         end if
         call update_state(pb, cs, z)
         ! the metric follows the size of the orbit (see gapbeam_continuation_problem)
         pb%e_ref = max(energy_size(pb%lp0, z(1:n)), 1.0e-2_dp * e_start)
         za = z;  ta = t / sqrt(wdot(pb, t, t))
      end do
   end subroutine follow_one

   !> Test function phi at z (and the monodromy's bordered solution), see the module header.
   subroutine curve_phi(pb, cs, z, phi, err, px, jac_out)
      type(problem_t), intent(inout) :: pb              !! problem
      type(curve_state_t), intent(in) :: cs             !! curve state
      real(dp), intent(in) :: z(:)                      !! (x, lambda1, lambda2)
      real(dp), intent(out) :: phi                      !! the test function
      type(error_t), allocatable, intent(out) :: err    !! failure
      real(dp), intent(out), optional :: px(:)          !! P(x)
      real(dp), intent(out), optional :: jac_out(:, :)  !! the monodromy
      real(dp), allocatable :: jac(:, :), p1(:)
      type(orbit_extrema_t) :: ex
      integer :: n
      n = pb%n
      allocate(p1(n), jac(n, n))
      if (cs%kind == 5) then
         if (present(jac_out)) then
            call orbit_eval(pb, z, cs%p, p1, err, jac=jac)
         else
            call orbit_eval(pb, z, cs%p, p1, err)
         end if
         if (allocated(err)) return
         call orbit_extrema(pb%center%m, z(1:n), pb%cfg%grazing_samples, ex, err)
         if (allocated(err)) return
         phi = grazing_value(ex, cs, pb%center%m%period * cs%p)
      else
         call orbit_eval(pb, z, cs%p, p1, err, jac=jac);  if (allocated(err)) return
         phi = bordered(jac, merge(1.0_dp, -1.0_dp, cs%kind == 3), cs%b, cs%c)
      end if
      if (present(px)) px = p1
      if (present(jac_out)) jac_out = jac
   end subroutine curve_phi

   !> The extremum of the grazing contact nearest (cyclically) the tracked instant.
   pure real(dp) function grazing_value(ex, cs, orbit_time) result(g)
      type(orbit_extrema_t), intent(in) :: ex
      type(curve_state_t), intent(in) :: cs
      real(dp), intent(in) :: orbit_time
      real(dp) :: best, d
      integer :: i
      g = ex%nearest
      best = huge(1.0_dp)
      do i = 1, ex%n
         if (ex%contact(i) /= cs%c_graze) cycle
         d = abs(ex%t(i) - cs%t_graze)
         d = min(d, orbit_time - d)
         if (d < best) then
            best = d;  g = ex%d(i)
         end if
      end do
   end function grazing_value

   !> g of [A + s I, b; c', 0] (w, g) = (0, 1).
   pure real(dp) function bordered(a, s, b, c) result(g)
      real(dp), intent(in) :: a(:, :), s, b(:), c(:)
      real(dp) :: m(size(b) + 1, size(b) + 1), r(size(b) + 1)
      integer :: n, j, info
      n = size(b)
      m(1:n, 1:n) = a
      do j = 1, n
         m(j, j) = m(j, j) + s
      end do
      m(1:n, n + 1) = b
      m(n + 1, 1:n) = c
      m(n + 1, n + 1) = 0.0_dp
      r = 0.0_dp;  r(n + 1) = 1.0_dp
      call solve_pure(m, r, info)
      g = r(n + 1)
      if (info /= 0) g = 0.0_dp
   end function bordered

   !> Gaussian elimination with partial pivoting (pure: the bordered test function).
   pure subroutine solve_pure(a, b, info)
      real(dp), intent(inout) :: a(:, :), b(:)
      integer, intent(out) :: info
      integer :: n, i, k, piv
      real(dp) :: f, row(size(b)), tb
      n = size(b)
      info = 0
      do k = 1, n
         piv = k - 1 + maxloc(abs(a(k:, k)), dim=1)
         if (a(piv, k) == 0.0_dp) then
            info = k;  return
         end if
         if (piv /= k) then
            row = a(k, :);  a(k, :) = a(piv, :);  a(piv, :) = row
            tb = b(k);  b(k) = b(piv);  b(piv) = tb
         end if
         do i = k + 1, n
            f = a(i, k) / a(k, k)
            a(i, k:) = a(i, k:) - f * a(k, k:)
            b(i) = b(i) - f * b(k)
         end do
      end do
      do k = n, 1, -1
         b(k) = (b(k) - dot_product(a(k, k + 1:), b(k + 1:))) / a(k, k)
      end do
   end subroutine solve_pure

   !> Jacobian rows of the extended system at z: (n+1) x (n+2), and the residual (n+1).
   subroutine extended_jacobian(pb, cs, z, jx, r, err, residual_only)
      type(problem_t), intent(inout) :: pb                !! problem
      type(curve_state_t), intent(in) :: cs               !! curve state
      real(dp), intent(in) :: z(:)                        !! point
      real(dp), allocatable, intent(inout) :: jx(:, :)    !! Jacobian (residual_only: only
                                                          !! its orbit block P_x - I anew)
      real(dp), allocatable, intent(out) :: r(:)          !! residual (P(x) - x, phi)
      type(error_t), allocatable, intent(out) :: err      !! failure
      logical, intent(in), optional :: residual_only      !! only r
      real(dp), allocatable :: px(:), jac(:, :), zp(:), pp(:)
      real(dp) :: phi, phip, h, e
      integer :: n, j, k
      n = pb%n
      allocate(px(n), pp(n), jac(n, n))
      call curve_phi(pb, cs, z, phi, err, px, jac);  if (allocated(err)) return
      r = [px - z(1:n), phi]
      if (present(residual_only)) then
         if (residual_only) then
            if (allocated(jx)) then
               jx(1:n, 1:n) = jac
               do j = 1, n
                  jx(j, j) = jx(j, j) - 1.0_dp
               end do
            end if
            return
         end if
      end if
      if (allocated(jx)) deallocate(jx)
      allocate(jx(n + 1, n + 2))
      jx(1:n, 1:n) = jac
      do j = 1, n
         jx(j, j) = jx(j, j) - 1.0_dp
      end do
      e = max(energy_size(pb%lp0, z(1:n)), 1.0e-3_dp * pb%e_ref)
      ! phi_x by forward differences
      do j = 1, n
         if (j <= pb%lp0%nr) then
            h = 1.0e-6_dp * e / sqrt(pb%lp0%kr(j, j))
         else
            h = 1.0e-6_dp * e / sqrt(pb%lp0%mr(j - pb%lp0%nr, j - pb%lp0%nr))
         end if
         zp = z;  zp(j) = z(j) + h
         call curve_phi(pb, cs, zp, phip, err);  if (allocated(err)) return
         jx(n + 1, j) = (phip - phi) / h
      end do
      ! P_lambda and phi_lambda by forward differences
      do k = 1, 2
         h = 1.0e-6_dp * pb%scale(k)
         zp = z;  zp(n + k) = z(n + k) + h
         call curve_phi(pb, cs, zp, phip, err, pp);  if (allocated(err)) return
         jx(1:n, n + k) = (pp - px) / h
         jx(n + 1, n + k) = (phip - phi) / h
      end do
   end subroutine extended_jacobian

   !> Corrector on the extended system: the curve point at arclength sigma from za along t,
   !> and the Jacobian of its last iteration (for the tangent).
   subroutine curve_correct(pb, cs, za, t, sigma, z, jx, its, err)
      type(problem_t), intent(inout) :: pb              !! problem
      type(curve_state_t), intent(in) :: cs             !! curve state
      real(dp), intent(in) :: za(:), t(:), sigma        !! start, tangent, arclength
      real(dp), allocatable, intent(out) :: z(:)        !! the point
      real(dp), allocatable, intent(out) :: jx(:, :)    !! Jacobian of the last iteration
      integer, intent(out) :: its                       !! iterations
      type(error_t), allocatable, intent(out) :: err    !! no convergence
      real(dp), allocatable :: r(:), a(:, :), b(:), wt(:), r_prev(:), jstep(:, :), u(:)
      real(dp) :: sz, con
      integer :: n, info
      n = pb%n
      z = za + sigma * t
      wt = wvec(pb, t)
      allocate(a(n + 2, n + 2), b(n + 2))
      do its = 0, 2 * pb%cfg%max_iterations
         ! the whole extended Jacobian at the predictor; then its orbit block (the monodromy)
         ! anew at every iterate and the rest (the test function's row, the columns of the
         ! variables) by Broyden's rank-one update
         call extended_jacobian(pb, cs, z, jx, r, err, residual_only=its > 0)
         if (allocated(err)) return
         if (its > 0) then
            u = (r - r_prev - matmul(jstep, b)) / dot_product(b, b)
            jx(n + 1, :) = jstep(n + 1, :) + u(n + 1) * b
            jx(1:n, n + 1:n + 2) = jstep(1:n, n + 1:n + 2) + &
               matmul(reshape(u(1:n), [n, 1]), reshape(b(n + 1:n + 2), [1, 2]))
         end if
         r_prev = r
         sz = max(energy_size(pb%lp0, z(1:n)), 1.0e-3_dp * pb%e_ref)
         con = dot_product(wt, z - za) - sigma
         if (energy_size(pb%lp0, r(1:n)) <= pb%cfg%tolerance * sz .and. &
             abs(r(n + 1)) <= tiny_phi(cs, pb) .and. its > 0) return
         if (its == 2 * pb%cfg%max_iterations) exit
         a(1:n + 1, :) = jx
         a(n + 2, :) = wt
         jstep = jx
         b = [-r, -con]
         call solve_linear(a, b, info)
         if (info /= 0) then
            call fatal_error(err, 'curve corrector: singular Jacobian')
            return
         end if
         if (sqrt(max(0.0_dp, wdot(pb, b, b))) > 0.5_dp + 2.0_dp * abs(sigma)) then
            call fatal_error(err, 'curve corrector: diverging')
            return
         end if
         z = z + b
      end do
      call fatal_error(err, 'curve corrector: no convergence in ' &
         // str(2 * pb%cfg%max_iterations) // ' chord iterations')
   end subroutine curve_correct

   !> Size below which phi counts as zero: 1e-9 (bordered g, dimensionless) or 1e-9 of the
   !> orbit's size in displacement (grazing).
   pure real(dp) function tiny_phi(cs, pb)
      type(curve_state_t), intent(in) :: cs
      type(problem_t), intent(in) :: pb
      if (cs%kind == 5) then
         tiny_phi = 1.0e-9_dp * pb%e_ref / sqrt(pb%lp0%kr(pb%lp0%cpos(max(cs%c_graze, 1)), &
                    pb%lp0%cpos(max(cs%c_graze, 1))))
      else
         tiny_phi = 1.0e-9_dp
      end if
   end function tiny_phi

   !> Unit tangent of the curve at z, oriented along t_prev.
   subroutine curve_tangent(pb, cs, z, t_prev, t, err)
      type(problem_t), intent(inout) :: pb              !! problem
      type(curve_state_t), intent(in) :: cs             !! curve state
      real(dp), intent(in) :: z(:), t_prev(:)           !! point, previous tangent
      real(dp), allocatable, intent(out) :: t(:)        !! tangent
      type(error_t), allocatable, intent(out) :: err    !! singular
      real(dp), allocatable :: jx(:, :), r(:)
      call extended_jacobian(pb, cs, z, jx, r, err);  if (allocated(err)) return
      call tangent_from(pb, jx, t_prev, t, err)
   end subroutine curve_tangent

   !> Unit null vector of the (n+1) x (n+2) Jacobian jx, oriented along t_prev.
   subroutine tangent_from(pb, jx, t_prev, t, err)
      type(problem_t), intent(in) :: pb                 !! problem
      real(dp), intent(in) :: jx(:, :)                  !! extended Jacobian
      real(dp), intent(in) :: t_prev(:)                 !! previous tangent
      real(dp), allocatable, intent(out) :: t(:)        !! tangent
      type(error_t), allocatable, intent(out) :: err    !! singular
      real(dp), allocatable :: a(:, :)
      integer :: n, info
      n = size(jx, 2) - 2
      allocate(a(n + 2, n + 2))
      a(1:n + 1, :) = jx
      a(n + 2, :) = wvec(pb, t_prev)
      t = [spread(0.0_dp, 1, n + 1), 1.0_dp]
      call solve_linear(a, t, info)
      if (info /= 0) then
         call fatal_error(err, 'curve tangent: singular system')
         return
      end if
      t = t / sqrt(wdot(pb, t, t))
   end subroutine tangent_from

   !> After a converged point: new bordering vectors (the null vectors' approximations) or the
   !> new grazing instant.
   subroutine update_state(pb, cs, z)
      type(problem_t), intent(inout) :: pb
      type(curve_state_t), intent(inout) :: cs
      real(dp), intent(in) :: z(:)
      real(dp), allocatable :: jac(:, :), px(:), m(:, :), r(:)
      type(orbit_extrema_t) :: ex
      type(error_t), allocatable :: err
      real(dp) :: s, best, d, tt
      integer :: n, j, info, i
      n = pb%n
      allocate(px(n))
      if (cs%kind == 5) then
         call orbit_eval(pb, z, cs%p, px, err);  if (allocated(err)) return
         call orbit_extrema(pb%center%m, z(1:n), pb%cfg%grazing_samples, ex, err)
         if (allocated(err)) return
         tt = pb%center%m%period * cs%p
         best = huge(1.0_dp)
         do i = 1, ex%n
            if (ex%contact(i) /= cs%c_graze) cycle
            d = abs(ex%t(i) - cs%t_graze);  d = min(d, tt - d)
            if (d < best) then
               best = d;  cs%t_graze = ex%t(i)
            end if
         end do
         return
      end if
      allocate(jac(n, n))
      call orbit_eval(pb, z, cs%p, px, err, jac=jac);  if (allocated(err)) return
      s = merge(1.0_dp, -1.0_dp, cs%kind == 3)
      allocate(m(n + 1, n + 1), r(n + 1))
      m(1:n, 1:n) = jac
      do j = 1, n
         m(j, j) = m(j, j) + s
      end do
      m(1:n, n + 1) = cs%b;  m(n + 1, 1:n) = cs%c;  m(n + 1, n + 1) = 0.0_dp
      r = 0.0_dp;  r(n + 1) = 1.0_dp
      call solve_linear(m, r, info)
      if (info == 0 .and. norm2(r(1:n)) > 0.0_dp) cs%c = r(1:n) / norm2(r(1:n))
      m(1:n, 1:n) = transpose(jac)
      do j = 1, n
         m(j, j) = m(j, j) + s
      end do
      m(1:n, n + 1) = cs%c;  m(n + 1, 1:n) = cs%b;  m(n + 1, n + 1) = 0.0_dp
      r = 0.0_dp;  r(n + 1) = 1.0_dp
      call solve_linear(m, r, info)
      if (info == 0 .and. norm2(r(1:n)) > 0.0_dp) cs%b = r(1:n) / norm2(r(1:n))
   end subroutine update_state
end module gapbeam_bifurcation_curves
