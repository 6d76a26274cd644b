!> Two-dimensional support contacts ("rings"): a circular clearance around a node, or a flat
!> stop with Coulomb friction, acting on the node's two transverse dofs x = (w, v).
!>
!> **Geometry.** Circular: y = x - c (c the hole centre), rho = |y|, penetration
!> d = rho - g (g the radial gap), normal n = y / rho (radial, outwards), tangent t = (-n_v, n_w),
!> tangential coordinate tau = g atan2(n_v, n_w) (arc length on the clearance circle, grad tau =
!> (g / rho) t). Flat: n fixed (the stop's dof and side), d = n.x - g, tau = t.x.
!>
!> **Normal force** f_n >= 0 by the stop laws of gapbeam_contact_law on (d, d' = n.x').
!>
!> **Friction: Coulomb with an elastic stick (a Jenkins element: a spring k_t in series with a
!> Coulomb slider).** In stick the slider is held at its anchor tau_a and the tangential force
!> is f_t = -k_t (tau - tau_a) |grad tau|, admissible while |f_t| <= mu f_n; in slip
!> f_t = -sigma mu f_n with sigma the sliding direction along t. The force on the structure is
!> P = -f_n n + f_t t. The regime switches are exact events of the integrator (located on the
!> step's interpolant, gapbeam_stepping): stick -> slip where |f_t| reaches mu f_n, slip ->
!> stick where the slider's velocity d tau_a / dt reverses (tau_a = tau - sigma mu f_n /
!> (k_t |grad tau|): the node's tangential rate less the stick spring's stretch rate; the
!> anchor is then the slider's position, so that f_t is continuous), open -> stick at contact with the anchor at the contact point (f_t = 0). The
!> tangential force is therefore continuous at every switch, friction dissipates exactly
!> mu f_n times the slider's travel and nothing in stick, and the only departure from rigid
!> Coulomb friction is the elastic stick displacement |f_t| / k_t <= mu f_n / k_t (physical
!> tangential contact compliance; large k_t approaches rigid stick).
!>
!> **The implicit step.** Inside a Newmark step the contact displacement and velocity are
!> affine in the slot forces P: x = x* + A P, x' = x'* + kappa A P (A the step compliance at the
!> node's two dofs, kappa = delta/(alpha h)). With the other contacts' forces fixed, the ring's
!> end position x solves R(x) = A^-1 (x - x*) - P(x, x'*+kappa (x - x*)) = 0 (two equations,
!> Newton with a difference Jacobian and a backtracking line search; frictionless, it minimises
!> a strictly convex function). Several contacts: Gauss-Seidel over contacts (scalar and ring).
module gapbeam_ring_contact
   use gapbeam_kinds, only: dp, pi
   use gapbeam_model, only: model_t, ring_xy
   use gapbeam_contact_law, only: contact_solve
   implicit none
   private
   public :: ring_open, ring_stick, ring_slip
   public :: ring_geometry, ring_force, solve_mixed_contacts, ring_forces_at, onset_regime, &
      update_ring_modes, ring_indicators, ring_stored_energy, ring_tangent_gap, ring_anchor_of

   integer, parameter :: ring_open = 0    !! no contact (the anchor follows the node)
   integer, parameter :: ring_stick = 1   !! in contact, slider held at its anchor
   integer, parameter :: ring_slip = 2    !! in contact, sliding in direction sigma

   !> The local problem of one ring inside an implicit step.
   type :: ring_problem_t
      integer :: r = 0                       !! ring
      integer :: mode = ring_open            !! regime
      real(dp) :: sigma = 1.0_dp             !! slip direction
      real(dp) :: anchor = 0.0_dp            !! stick anchor [m]
      real(dp) :: ainv(2, 2) = 0.0_dp        !! inverse compliance [N/m]
      real(dp) :: xs(2) = 0.0_dp             !! position with no contact force [m]
      real(dp) :: vs(2) = 0.0_dp             !! velocity with no contact force [m/s]
      real(dp) :: kappa = 0.0_dp             !! d(velocity)/d(position) [1/s]
      real(dp) :: scale = 0.0_dp             !! length scale [m]
   end type ring_problem_t

contains

   !> Penetration, normal, tangent, tangential coordinate and |grad tau| of ring r at x (the
   !> coordinate, an arc tangent on a circle, only when asked for: the event search and the
   !> contact solve evaluate the geometry many times per step and need it in stick only).
   pure subroutine ring_geometry(model, r, x, d, n, t, tau, gt)
      type(model_t), intent(in) :: model    !! model (ring data)
      integer, intent(in) :: r              !! ring
      real(dp), intent(in) :: x(2)          !! (w, v) of the node [m]
      real(dp), intent(out) :: d            !! penetration [m]
      real(dp), intent(out) :: n(2), t(2)   !! normal, tangent [-]
      real(dp), intent(out), optional :: tau  !! tangential coordinate [m]
      real(dp), intent(out) :: gt           !! |grad tau| [-]
      real(dp) :: y(2), rho
      if (model%r_circular(r)) then
         y = x - model%r_centre(:, r)
         rho = norm2(y)
         if (rho > 0.0_dp) then
            n = y / rho
         else
            n = [1.0_dp, 0.0_dp]
         end if
         d = rho - model%r_gap(r)
         gt = model%r_gap(r) / max(rho, tiny(1.0_dp))
      else
         n = model%r_normal(:, r)
         d = dot_product(n, x) - model%r_gap(r)
         gt = 1.0_dp
      end if
      if (present(tau)) tau = tangent_coordinate(model, r, x, n)
      t = [-n(2), n(1)]
   end subroutine ring_geometry

   !> The tangential coordinate tau of ring r at x with normal n: the arc length g atan2(n_v,
   !> n_w) on a circle, t.x on a flat stop [m].
   pure real(dp) function tangent_coordinate(model, r, x, n) result(tau)
      type(model_t), intent(in) :: model    !! model (ring data)
      integer, intent(in) :: r              !! ring
      real(dp), intent(in) :: x(2), n(2)    !! (w, v) of the node [m], its normal [-]
      if (model%r_circular(r)) then
         tau = model%r_gap(r) * atan2(n(2), n(1))
      else
         tau = -n(2) * x(1) + n(1) * x(2)
      end if
   end function tangent_coordinate

   !> tau - tau_a, wrapped to a half circumference for a circular clearance [m].
   pure real(dp) function ring_tangent_gap(model, r, tau, anchor) result(dt)
      type(model_t), intent(in) :: model    !! model
      integer, intent(in) :: r              !! ring
      real(dp), intent(in) :: tau, anchor   !! coordinate and anchor [m]
      real(dp) :: c
      dt = tau - anchor
      if (model%r_circular(r)) then
         c = 2.0_dp * pi * model%r_gap(r)
         dt = dt - c * anint(dt / c)
      end if
   end function ring_tangent_gap

   !> Normal force by the stop law, extended smoothly beyond the contact when `extend` (for
   !> the Newton iteration: the law's `extended`, k d + c d' or k sign(d) |d|^p); else the law
   !> itself.
   pure real(dp) function normal_law(model, r, d, dd, extend) result(f)
      type(model_t), intent(in) :: model    !! model
      integer, intent(in) :: r              !! ring
      real(dp), intent(in) :: d, dd         !! penetration [m], its rate [m/s]
      logical, intent(in) :: extend         !! smooth extension
      associate (law => model%laws(model%r_law(r))%law)
         if (.not. extend) then
            f = law%force(model%r_k(r), model%r_c(r), model%r_p(r), d, dd)
         else
            f = law%extended(model%r_k(r), model%r_c(r), model%r_p(r), d, dd)
         end if
      end associate
   end function normal_law

   !> Force on the structure P (in (w, v)), normal force f_n and tangential force f_t of ring r
   !> at (x, x') in the given regime. An open regime with penetration is taken as stick (the
   !> anchor of an open ring is the node's own coordinate). `extend`: the smooth extension of
   !> the normal law (Newton iterates).
   pure subroutine ring_force(model, r, mode, sigma, anchor, x, xd, p, fn, ft, extend, touching)
      type(model_t), intent(in) :: model    !! model
      integer, intent(in) :: r              !! ring
      integer, intent(in) :: mode           !! ring_open, ring_stick or ring_slip
      real(dp), intent(in) :: sigma         !! slip direction along t
      real(dp), intent(in) :: anchor        !! stick anchor [m]
      real(dp), intent(in) :: x(2), xd(2)   !! position [m], velocity [m/s]
      real(dp), intent(out) :: p(2)         !! force on the structure [N]
      real(dp), intent(out) :: fn           !! normal force [N]
      real(dp), intent(out) :: ft           !! tangential force along t [N]
      logical, intent(in), optional :: extend   !! smooth extension of the normal law
      !> taken as touching (d >= tiny) at a located onset, whatever the round-off of d
      logical, intent(in), optional :: touching
      real(dp) :: d, n(2), t(2), gt
      logical :: ext
      ext = .false.
      if (present(extend)) ext = extend
      call ring_geometry(model, r, x, d, n, t, gt=gt)
      if (present(touching)) then
         if (touching) d = max(d, tiny(1.0_dp))
      end if
      p = 0.0_dp;  fn = 0.0_dp;  ft = 0.0_dp
      if (.not. ext .and. d <= 0.0_dp) return
      fn = normal_law(model, r, d, dot_product(n, xd), ext)
      if (.not. ext .and. fn <= 0.0_dp) then
         fn = 0.0_dp
         return
      end if
      if (model%r_mu(r) > 0.0_dp) then
         if (mode == ring_slip) then
            ft = -sigma * model%r_mu(r) * fn
         else
            ft = -model%r_kt(r) * ring_tangent_gap(model, r, tangent_coordinate(model, r, x, &
                                                                               n), anchor) * gt
            ! a ring that touches inside a step begun open: the element's return mapping
            ! (stick from the contact point, limited to the slip force)
            if (mode == ring_open) ft = max(-model%r_mu(r) * abs(fn), &
                                            min(model%r_mu(r) * abs(fn), ft))
         end if
      end if
      p = -fn * n + ft * t
   end subroutine ring_force

   !> The regime of ring r at a located onset (x, x' at the contact instant, d = 0): the stick
   !> force grows as k_t |grad tau| |v_t| per unit time and the slip limit as mu df_n/dt (the
   !> law's onset rate: k d' for the bilinear law, nothing for Hertz with p > 1); a force that
   !> jumps at an onset (a damper's c d' > 0) makes it stick at once. It sticks (anchor at the contact point) when the limit grows faster or
   !> is already positive, else slips in the direction of v_t.
   pure subroutine onset_regime(model, r, x, xd, mode, sigma, anchor)
      type(model_t), intent(in) :: model            !! model
      integer, intent(in) :: r                      !! ring
      real(dp), intent(in) :: x(2), xd(2)           !! position, velocity at the onset
      integer, intent(out) :: mode                  !! ring_stick or ring_slip
      real(dp), intent(out) :: sigma                !! slip direction
      real(dp), intent(out) :: anchor               !! stick anchor: the contact point [m]
      real(dp) :: d, n(2), t(2), tau, gt, vt, dn, rate
      call ring_geometry(model, r, x, d, n, t, tau, gt)
      anchor = tau
      vt = dot_product(t, xd);  dn = dot_product(n, xd)
      mode = ring_stick;  sigma = 1.0_dp
      if (model%r_mu(r) == 0.0_dp) return
      associate (law => model%laws(model%r_law(r))%law)
         if (law%jumps(model%r_k(r), model%r_c(r), model%r_p(r))) return
         rate = law%onset_rate(model%r_k(r), model%r_c(r), model%r_p(r), dn)
      end associate
      if (model%r_kt(r) * gt * abs(vt) > model%r_mu(r) * rate) then
         mode = ring_slip;  sigma = sign(1.0_dp, vt)
      end if
   end subroutine onset_regime

   !> Exact forces of ring r inside an implicit step (see the module header): the end position
   !> x with A^-1 (x - x*) = P(x, x'* + kappa (x - x*)), the force P, f_n and f_t. `hold`:
   !> held open (the step ends at a located onset).
   pure subroutine solve_ring(model, r, mode, sigma, anchor, amat, xs, vs, kappa, hold, x, p, &
                              fn, ft)
      type(model_t), intent(in) :: model     !! model
      integer, intent(in) :: r               !! ring
      integer, intent(in) :: mode            !! regime over the step
      real(dp), intent(in) :: sigma, anchor  !! slip direction, stick anchor [m]
      real(dp), intent(in) :: amat(2, 2)     !! compliance at (w, v) [m/N]
      real(dp), intent(in) :: xs(2), vs(2)   !! position and velocity with P = 0
      real(dp), intent(in) :: kappa          !! d(velocity)/d(position) of the scheme [1/s]
      logical, intent(in) :: hold            !! held open
      real(dp), intent(out) :: x(2), p(2)    !! end position [m], force [N]
      real(dp), intent(out) :: fn, ft        !! normal, tangential force [N]
      type(ring_problem_t) :: pb
      real(dp) :: det, d, n(2), t(2), gt, res(2), jac(2, 2), dx(2)
      real(dp) :: xt(2), rt(2), step, nrm, nrm_t, dxn, dxn_old, fe, ft_e
      integer :: it, j, ls
      x = xs;  p = 0.0_dp;  fn = 0.0_dp;  ft = 0.0_dp
      if (hold) return
      call ring_geometry(model, r, xs, d, n, t, gt=gt)
      if (d <= 0.0_dp) return
      if (normal_law(model, r, d, dot_product(n, vs), .true.) <= 0.0_dp) return
      det = amat(1, 1) * amat(2, 2) - amat(1, 2) * amat(2, 1)
      pb%ainv = reshape([amat(2, 2), -amat(2, 1), -amat(1, 2), amat(1, 1)], [2, 2]) / det
      pb%r = r;  pb%mode = mode;  pb%sigma = sigma;  pb%anchor = anchor
      pb%xs = xs;  pb%vs = vs;  pb%kappa = kappa
      pb%scale = max(norm2(xs), model%r_gap(r), norm2(model%r_centre(:, r)), tiny(1.0_dp))
      res = ring_residual(model, pb, x)
      nrm = norm2(res)
      dxn_old = huge(1.0_dp)
      do it = 1, 100
         ! difference Jacobian of the residual (the root does not depend on its accuracy)
         do j = 1, 2
            step = 1.0e-8_dp * pb%scale
            xt = x;  xt(j) = xt(j) + step
            jac(:, j) = (ring_residual(model, pb, xt) - res) / step
         end do
         det = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
         if (det == 0.0_dp) exit
         dx = -[jac(2, 2) * res(1) - jac(1, 2) * res(2), -jac(2, 1) * res(1) + jac(1, 1) &
               * res(2)] / det
         do ls = 1, 40
            xt = x + dx
            rt = ring_residual(model, pb, xt)
            nrm_t = norm2(rt)
            if (nrm_t <= nrm .or. norm2(dx) <= 8.0_dp * epsilon(1.0_dp) * pb%scale) exit
            dx = 0.5_dp * dx
         end do
         x = xt;  res = rt;  nrm = nrm_t
         dxn = norm2(dx)
         if (dxn <= 8.0_dp * epsilon(1.0_dp) * pb%scale) exit
         if (dxn <= 1.0e-11_dp * pb%scale .and. dxn >= 0.5_dp * dxn_old) exit
         dxn_old = dxn
      end do
      call ring_force(model, r, mode, sigma, anchor, x, vs + kappa * (x - xs), p, fe, ft_e, &
                      extend=.true.)
      if (fe <= 0.0_dp) then
         x = xs;  p = 0.0_dp
         return
      end if
      call ring_geometry(model, r, x, d, n, t, gt=gt)
      ! the damper pushes the node back beyond the surface: it sits on the surface
      if (d < 0.0_dp) call on_surface(model, pb, x, fe, ft_e)
      call ring_geometry(model, r, x, d, n, t, gt=gt)
      fn = fe;  ft = ft_e
      p = -fn * n + ft * t
   end subroutine solve_ring

   !> A^-1 (x - x*) - P(x) of a ring problem, with the smooth extension of the normal law.
   pure function ring_residual(model, pb, x) result(rr)
      type(model_t), intent(in) :: model         !! model
      type(ring_problem_t), intent(in) :: pb     !! the problem
      real(dp), intent(in) :: x(2)               !! position [m]
      real(dp) :: rr(2), pp(2), a, b
      call ring_force(model, pb%r, pb%mode, pb%sigma, pb%anchor, x, &
                      pb%vs + pb%kappa * (x - pb%xs), pp, a, b, extend=.true.)
      rr = matmul(pb%ainv, x - pb%xs) - pp
   end function ring_residual

   !> The node held on the surface d = 0 by a normal force lambda (a Lagrange multiplier):
   !> A^-1 (x - x*) + lambda n - f_t t = 0, d(x) = 0; Newton on (x, lambda).
   pure subroutine on_surface(model, pb, x, lam, ft)
      type(model_t), intent(in) :: model         !! model
      type(ring_problem_t), intent(in) :: pb     !! the problem
      real(dp), intent(inout) :: x(2)            !! in: guess; out: position on the surface
      real(dp), intent(inout) :: lam             !! in: guess; out: normal force [N]
      real(dp), intent(out) :: ft                !! tangential force [N]
      real(dp) :: z(3), zt(3), g(3), gtry(3), jj(3, 3), dz(3), hs, d, n(2), t(2), tau, gt
      integer :: k, i, q
      z = [x(1), x(2), lam]
      g = surface_residual(model, pb, z)
      do k = 1, 60
         do i = 1, 3
            if (i < 3) then
               hs = 1.0e-8_dp * pb%scale
            else
               hs = 1.0e-8_dp * max(abs(z(3)), tiny(1.0_dp))
            end if
            zt = z;  zt(i) = zt(i) + hs
            jj(:, i) = (surface_residual(model, pb, zt) - g) / hs
         end do
         dz = -g
         call solve3(jj, dz)
         do q = 1, 40
            gtry = surface_residual(model, pb, z + dz)
            if (norm2(gtry) <= norm2(g)) exit
            dz = 0.5_dp * dz
         end do
         z = z + dz;  g = gtry
         if (norm2(dz(1:2)) <= 8.0_dp * epsilon(1.0_dp) * pb%scale) exit
      end do
      x = z(1:2);  lam = max(z(3), 0.0_dp)
      call ring_geometry(model, pb%r, x, d, n, t, tau, gt)
      ft = surface_friction(model, pb, lam, tau, gt)
   end subroutine on_surface

   !> Tangential force of a ring problem at normal force lam and coordinate tau [N].
   pure real(dp) function surface_friction(model, pb, lam, tau, gt) result(ft)
      type(model_t), intent(in) :: model         !! model
      type(ring_problem_t), intent(in) :: pb     !! the problem
      real(dp), intent(in) :: lam, tau, gt       !! normal force, coordinate, |grad tau|
      ft = 0.0_dp
      if (model%r_mu(pb%r) == 0.0_dp) return
      if (pb%mode == ring_slip) then
         ft = -pb%sigma * model%r_mu(pb%r) * lam
      else
         ft = -model%r_kt(pb%r) * ring_tangent_gap(model, pb%r, tau, pb%anchor) * gt
      end if
   end function surface_friction

   !> Residual of the surface problem (x, lambda): force balance and d (scaled to a force).
   pure function surface_residual(model, pb, z) result(g)
      type(model_t), intent(in) :: model         !! model
      type(ring_problem_t), intent(in) :: pb     !! the problem
      real(dp), intent(in) :: z(3)               !! (x, lambda)
      real(dp) :: g(3), d, n(2), t(2), tau, gt
      call ring_geometry(model, pb%r, z(1:2), d, n, t, tau, gt)
      g(1:2) = matmul(pb%ainv, z(1:2) - pb%xs) + z(3) * n &
               - surface_friction(model, pb, z(3), tau, gt) * t
      g(3) = d * maxval(abs(pb%ainv))
   end function surface_residual

   !> Solve a 3x3 system in place (Gaussian elimination with partial pivoting).
   pure subroutine solve3(a, b)
      real(dp), intent(inout) :: a(3, 3)   !! matrix (destroyed)
      real(dp), intent(inout) :: b(3)      !! right-hand side, then solution
      integer :: i, k, piv
      real(dp) :: f, tmp(3), tb
      do k = 1, 3
         piv = k - 1 + maxloc(abs(a(k:3, k)), dim=1)
         if (piv /= k) then
            tmp = a(k, :);  a(k, :) = a(piv, :);  a(piv, :) = tmp
            tb = b(k);  b(k) = b(piv);  b(piv) = tb
         end if
         if (a(k, k) == 0.0_dp) then
            b = 0.0_dp
            return
         end if
         do i = k + 1, 3
            f = a(i, k) / a(k, k)
            a(i, k:3) = a(i, k:3) - f * a(k, k:3)
            b(i) = b(i) - f * b(k)
         end do
      end do
      do k = 3, 1, -1
         b(k) = (b(k) - dot_product(a(k, k + 1:3), b(k + 1:3))) / a(k, k)
      end do
   end subroutine solve3

   !> Exact forces of every contact (one-sided scalar contacts and rings) of an implicit step:
   !> Gauss-Seidel over the contacts, each solved exactly with the others' forces fixed.
   !>
   !> The slot displacements are y = ystar + H P and their rates y' = vstar + kappa H P, with P
   !> the force on the structure at each slot (-s f for a scalar contact, P_r for a ring) and
   !> H = E' Kbar^-1 E. Contact `hold` (scalar) or ring `hold - n_contacts` is held open.
   !> Returns the scalar forces f, the ring forces (fn, ft) and the slot forces P.
   pure subroutine solve_mixed_contacts(model, hmat, kappa, ystar, vstar, mode, sigma, anchor, &
                                        hold, f, fn, ft, pslot)
      type(model_t), intent(in) :: model          !! model
      real(dp), intent(in) :: hmat(:, :)          !! (n_slots, n_slots) compliance
      real(dp), intent(in) :: kappa               !! d(rate)/d(displacement) [1/s]
      real(dp), intent(in) :: ystar(:), vstar(:)  !! slot displacements, rates with P = 0
      integer, intent(in) :: mode(:)              !! ring regimes
      real(dp), intent(in) :: sigma(:), anchor(:) !! ring slip directions, anchors
      integer, intent(in) :: hold                 !! held open (0: none)
      real(dp), intent(inout) :: f(:)             !! scalar contact forces (in: guess) [N]
      real(dp), intent(out) :: fn(:), ft(:)       !! ring forces [N]
      real(dp), intent(out) :: pslot(:)           !! force at each slot [N]
      integer :: sweep, c, r, si, s2(2), nc
      real(dp) :: own(2), ys, vsc, fold, change, fmax, xs(2), vs(2), x(2), pr(2), amat(2, 2)
      real(dp), allocatable :: pring(:, :), shift(:)
      nc = model%n_contacts
      allocate(pring(2, model%n_rings), source=0.0_dp)
      allocate(shift(size(pslot)))
      fn = 0.0_dp;  ft = 0.0_dp
      pslot = 0.0_dp
      do c = 1, nc
         pslot(model%c_slot(c)) = pslot(model%c_slot(c)) - model%c_sign(c) * f(c)
      end do
      do sweep = 1, 1000
         change = 0.0_dp;  fmax = 0.0_dp
         do c = 1, nc
            si = model%c_slot(c)
            fold = f(c)
            pslot(si) = pslot(si) + model%c_sign(c) * f(c)         ! without its own force
            shift = matmul(hmat, pslot)
            ys = model%c_sign(c) * (ystar(si) + shift(si)) - model%c_gap(c)
            vsc = model%c_sign(c) * (vstar(si) + kappa * shift(si))
            f(c) = contact_solve(model, c, ys, vsc, hmat(si, si), kappa)
            if (c == hold) f(c) = 0.0_dp
            pslot(si) = pslot(si) - model%c_sign(c) * f(c)
            change = max(change, abs(f(c) - fold));  fmax = max(fmax, f(c))
         end do
         do r = 1, model%n_rings
            s2 = model%r_slot(:, r)
            own = pring(:, r)
            pslot(s2) = pslot(s2) - own
            shift = matmul(hmat, pslot)
            xs = ystar(s2) + shift(s2)
            vs = vstar(s2) + kappa * shift(s2)
            amat = hmat(s2, s2)
            call solve_ring(model, r, mode(r), sigma(r), anchor(r), amat, xs, vs, kappa, &
                            hold == nc + r, x, pr, fn(r), ft(r))
            pring(:, r) = pr
            pslot(s2) = pslot(s2) + pr
            change = max(change, maxval(abs(pr - own)));  fmax = max(fmax, norm2(pr))
         end do
         if (change <= 1.0e-14_dp * fmax .or. fmax == 0.0_dp) exit
         if (nc + model%n_rings == 1) exit
      end do
   end subroutine solve_mixed_contacts

   !> Ring forces from the laws at a state (u, v) in the given regimes; the force on the
   !> structure is added to p (size n) when present.
   pure subroutine ring_forces_at(model, u, v, mode, sigma, anchor, fn, ft, p)
      type(model_t), intent(in) :: model            !! model
      real(dp), intent(in) :: u(:), v(:)            !! state
      integer, intent(in) :: mode(:)               !! regimes
      real(dp), intent(in) :: sigma(:), anchor(:)   !! slip directions, anchors
      real(dp), intent(out) :: fn(:), ft(:)         !! forces [N]
      real(dp), intent(inout), optional :: p(:)     !! load vector: p = p + sum_r E_r P_r
      integer :: r
      real(dp) :: pr(2)
      do r = 1, model%n_rings
         call ring_force(model, r, mode(r), sigma(r), anchor(r), ring_xy(model, r, u), &
                         ring_xy(model, r, v), pr, fn(r), ft(r))
         if (present(p)) p(model%r_dof(:, r)) = p(model%r_dof(:, r)) + pr
      end do
   end subroutine ring_forces_at

   !> The regime indicators of ring r at (x, x', x''): `active` (in contact with a positive
   !> normal force) and `valid` (the regime holds: stick |f_t| <= mu f_n; slip: the slider
   !> keeps moving in direction sigma, sigma dtau_a/dt >= 0).
   pure subroutine ring_indicators(model, r, mode, sigma, anchor, x, xd, xdd, active, valid)
      type(model_t), intent(in) :: model            !! model
      integer, intent(in) :: r                      !! ring
      integer, intent(in) :: mode                   !! regime
      real(dp), intent(in) :: sigma, anchor         !! slip direction, anchor [m]
      real(dp), intent(in) :: x(2), xd(2), xdd(2)   !! position, velocity, acceleration
      logical, intent(out) :: active, valid         !! indicators
      real(dp) :: p(2), fn, ft
      call ring_force(model, r, mode, sigma, anchor, x, xd, p, fn, ft)
      active = fn > 0.0_dp
      valid = .true.
      if (.not. active .or. model%r_mu(r) == 0.0_dp) return
      if (mode == ring_slip) then
         valid = sigma * slider_rate(model, r, sigma, x, xd, xdd) >= 0.0_dp
      else if (mode == ring_stick) then
         valid = abs(ft) <= model%r_mu(r) * fn
      end if
   end subroutine ring_indicators

   !> Velocity of the slider in slip, dtau_a/dt with tau_a = tau - sigma mu f_n / (k_t |grad
   !> tau|): the node's tangential rate less the rate of the stick spring's stretch [m/s].
   pure real(dp) function slider_rate(model, r, sigma, x, xd, xdd) result(rate)
      type(model_t), intent(in) :: model            !! model
      integer, intent(in) :: r                      !! ring
      real(dp), intent(in) :: sigma                 !! slip direction
      real(dp), intent(in) :: x(2), xd(2), xdd(2)   !! position, velocity, acceleration
      real(dp) :: d, n(2), t(2), gt, vt, dn, ddd, fn, fdot, rho, curv
      call ring_geometry(model, r, x, d, n, t, gt=gt)
      vt = dot_product(t, xd);  dn = dot_product(n, xd)
      curv = 0.0_dp
      if (model%r_circular(r)) then
         rho = model%r_gap(r) + d
         curv = 1.0_dp / max(rho, tiny(1.0_dp))
      end if
      ddd = dot_product(n, xdd) + vt**2 * curv
      associate (law => model%laws(model%r_law(r))%law)
         fn = law%force(model%r_k(r), model%r_c(r), model%r_p(r), d, dn)
         fdot = law%rate(model%r_k(r), model%r_c(r), model%r_p(r), d, dn, ddd)
      end associate
      rate = gt * vt - sigma * model%r_mu(r) / model%r_kt(r) * (fdot / gt + fn * dn * curv / gt)
   end function slider_rate

   !> The slider's anchor in slip (tau_a = tau - sigma mu f_n / (k_t |grad tau|)), or the
   !> anchor itself in stick; the node's coordinate when open [m].
   pure real(dp) function ring_anchor_of(model, r, mode, sigma, anchor, x, xd) result(ta)
      type(model_t), intent(in) :: model            !! model
      integer, intent(in) :: r                      !! ring
      integer, intent(in) :: mode                   !! regime
      real(dp), intent(in) :: sigma, anchor         !! slip direction, anchor [m]
      real(dp), intent(in) :: x(2), xd(2)           !! position, velocity
      real(dp) :: p(2), fn, ft, d, n(2), t(2), tau, gt
      call ring_geometry(model, r, x, d, n, t, tau, gt)
      call ring_force(model, r, mode, sigma, anchor, x, xd, p, fn, ft)
      if (fn <= 0.0_dp .or. model%r_mu(r) == 0.0_dp) then
         ta = tau
      else if (mode == ring_slip) then
         ta = tau - sigma * model%r_mu(r) * fn / (model%r_kt(r) * gt)
      else
         ta = anchor
      end if
   end function ring_anchor_of

   !> The regimes at an accepted state: an open ring that touches sticks at its contact point
   !> (anchor = tau, f_t = 0); stick turns to slip when |f_t| > mu f_n (sigma = -sign f_t);
   !> slip turns to stick when sigma t.x' < 0 (anchor placed so that f_t is continuous); a
   !> ring without normal force opens. `event_ring` (0: none) ended the step at a located
   !> friction switch: its regime is switched whatever the round-off of the indicators.
   pure subroutine update_ring_modes(model, u, v, a, mode, sigma, anchor, event_ring)
      type(model_t), intent(in) :: model            !! model
      real(dp), intent(in) :: u(:), v(:), a(:)      !! the state
      integer, intent(inout) :: mode(:)             !! regimes
      real(dp), intent(inout) :: sigma(:), anchor(:) !! slip directions, anchors
      integer, intent(in) :: event_ring             !! ring of a located friction switch
      integer :: r
      real(dp) :: x(2), xd(2), xdd(2), p(2), fn, ft, d, n(2), t(2), tau, gt
      do r = 1, model%n_rings
         x = u(model%r_dof(:, r));  xd = v(model%r_dof(:, r));  xdd = a(model%r_dof(:, r))
         call ring_geometry(model, r, x, d, n, t, tau, gt)
         call ring_force(model, r, mode(r), sigma(r), anchor(r), x, xd, p, fn, ft)
         if (fn <= 0.0_dp) then
            mode(r) = ring_open;  anchor(r) = tau
            cycle
         end if
         if (mode(r) == ring_open) then
            ! touched inside the step (not located): the return mapping decided the force
            mode(r) = ring_stick
            if (model%r_mu(r) > 0.0_dp .and. abs(ft) >= model%r_mu(r) * fn) then
               mode(r) = ring_slip;  sigma(r) = -sign(1.0_dp, ft)
            end if
            cycle
         end if
         if (model%r_mu(r) == 0.0_dp) cycle
         if (mode(r) == ring_stick) then
            if (abs(ft) > model%r_mu(r) * fn .or. (r == event_ring .and. ft /= 0.0_dp)) then
               mode(r) = ring_slip
               sigma(r) = -sign(1.0_dp, ft)
            else if (r == event_ring .and. dot_product(t, xd) /= 0.0_dp) then
               ! a switch located at the very start of a stick whose spring is not yet
               ! stretched: it slips along the node's motion
               mode(r) = ring_slip
               sigma(r) = sign(1.0_dp, dot_product(t, xd))
            end if
         else
            if (sigma(r) * slider_rate(model, r, sigma(r), x, xd, xdd) < 0.0_dp .or. &
                r == event_ring) then
               ! the slider stops where it is: f_t continuous
               mode(r) = ring_stick
               anchor(r) = tau - sigma(r) * model%r_mu(r) * fn / (model%r_kt(r) * gt)
            end if
         end if
      end do
   end subroutine update_ring_modes

   !> Energy stored in ring r at (x, x'): the normal law's potential (k d^2/2 bilinear,
   !> k d^(p+1)/(p+1) Hertz: the law's `energy`) and the stick spring's
   !> f_t^2 / (2 k_t |grad tau|^2) [J].
   pure real(dp) function ring_stored_energy(model, r, mode, sigma, anchor, x, xd) result(e)
      type(model_t), intent(in) :: model            !! model
      integer, intent(in) :: r                      !! ring
      integer, intent(in) :: mode                   !! regime
      real(dp), intent(in) :: sigma, anchor         !! slip direction, anchor [m]
      real(dp), intent(in) :: x(2), xd(2)           !! position, velocity
      real(dp) :: p(2), fn, ft, d, n(2), t(2), gt
      call ring_geometry(model, r, x, d, n, t, gt=gt)
      e = 0.0_dp
      if (d <= 0.0_dp) return
      e = model%laws(model%r_law(r))%law%energy(model%r_k(r), model%r_c(r), model%r_p(r), d)
      if (model%r_mu(r) > 0.0_dp) then
         call ring_force(model, r, mode, sigma, anchor, x, xd, p, fn, ft)
         e = e + 0.5_dp * ft**2 / (model%r_kt(r) * gt**2)
      end if
   end function ring_stored_energy
end module gapbeam_ring_contact
