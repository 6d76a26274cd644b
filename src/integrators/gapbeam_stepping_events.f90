!> Contact events of the stepping integrator: the first contact switch (onset, release, the
!> force of a damper reaching zero) or ring switch (contact, stick-slip) inside a sub-step,
!> found on the cubic Hermite interpolant of the sub-step by sampling and bisection; the
!> regimes after an accepted sub-step; the restart from the right limit where a force jumps.
submodule (gapbeam_stepping) gapbeam_stepping_events
   implicit none

contains

   !> First instant (fraction of the sub-step k -> k+1 of length h) where a contact opens or
   !> closes; 2 if none. Sets ev_contact and ev_onset.
   real(dp) module function first_event(self, k, h) result(th)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-step start
      real(dp), intent(in) :: h                             !! its length [s]
      integer :: cc, m, it, i
      real(dp) :: lo, hi, mid, p0, b1, b2, b3, s, g
      logical :: closed0, damped
      integer, parameter :: n_sample = 8
      th = 2.0_dp
      associate (md => self%model, u0 => self%sub(self%ix(k))%u, &
                 v0 => self%sub(self%ix(k))%v, u1 => self%sub(self%ix(k + 1))%u, &
                 v1 => self%sub(self%ix(k + 1))%v)
         do cc = 1, md%n_contacts
            i = md%c_dof(cc);  s = md%c_sign(cc);  g = md%c_gap(cc)
            damped = self%early(cc)
            closed0 = contact_active(md, cc, 0.0_dp, h, u0(i), v0(i), u1(i), v1(i), damped)
            if (.not. damped) then
               ! Bernstein coefficients of the cubic bound it: no sign change, no event
               p0 = s * u0(i) - g
               b1 = p0 + s * h * v0(i) / 3.0_dp
               b3 = s * u1(i) - g
               b2 = b3 - s * h * v1(i) / 3.0_dp
               if (closed0) then
                  if (min(b1, b2, b3) > 0.0_dp) cycle
               else
                  if (max(b1, b2, b3) <= 0.0_dp) cycle
               end if
            end if
            do m = 1, n_sample
               hi = real(m, dp) / n_sample
               if (hi >= th) exit
               if (contact_active(md, cc, hi, h, u0(i), v0(i), u1(i), v1(i), damped) &
                   .neqv. closed0) then
                  lo = real(m - 1, dp) / n_sample
                  do it = 1, 60
                     mid = 0.5_dp * (lo + hi)
                     if (contact_active(md, cc, mid, h, u0(i), v0(i), u1(i), v1(i), damped) &
                         .neqv. closed0) then
                        hi = mid
                     else
                        lo = mid
                     end if
                  end do
                  if (hi < th) then
                     th = hi;  self%ev_contact = cc;  self%ev_onset = .not. closed0
                     self%ev_friction = .false.
                  end if
                  exit
               end if
            end do
         end do
      end associate
      if (self%model%n_rings > 0) call self%first_ring_event(k, h, th)
   end function first_event

   !> The first switch of a ring in the sub-step k -> k+1 of length h before fraction th:
   !> contact onset or release, or (in contact) the end of its friction regime (stick: |f_t|
   !> reaches mu f_n; slip: the tangential velocity reverses), on the cubic Hermite
   !> interpolant of the node's (w, v) in the regime of the sub-step's start. The indicators
   !> are sampled at 8 points and the first change is bisected; th, ev_contact (n_contacts +
   !> ring), ev_onset and ev_friction are set when one is found earlier.
   module subroutine first_ring_event(self, k, h, th)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-step start
      real(dp), intent(in) :: h                             !! its length [s]
      real(dp), intent(inout) :: th                         !! earliest event so far [-]
      integer, parameter :: n_sample = 8
      integer :: r, m, it
      real(dp) :: lo, hi, mid
      logical :: act0, val0, act, q5
      associate (md => self%model, s0 => self%sub(self%ix(k)), s1 => self%sub(self%ix(k + 1)))
         do r = 1, md%n_rings
            ! a ring in contact at the start, or the ring held open over a trial step that
            ! entered it (its onset on the free flight's quintic): on the quintic when the
            ! stepper checks it
            q5 = self%quintic_events .and. ((s0%mode(r) /= ring_open .and. s0%fn(r) > 0.0_dp) &
                                            .or. r == self%held_ring)
            call ring_state_at(md, s0, s1, r, h, 0.0_dp, q5, act0, val0)
            ! opened at a located release, whatever force the law leaves there
            if (s0%mode(r) == ring_open .and. s0%fn(r) <= 0.0_dp) act0 = .false.
            ! closed at a located onset, whatever the round-off of the penetration there (a
            ! hair outside would read as an onset at the step's start, which hides every
            ! later switch of the step: the stick that a damper's force starts ends in it)
            if (s0%mode(r) /= ring_open .and. s0%fn(r) > 0.0_dp) act0 = .true.
            do m = 1, n_sample
               hi = real(m, dp) / n_sample
               if (hi >= th) exit
               if (ring_switched(md, s0, s1, r, h, hi, q5, act0)) then
                  lo = real(m - 1, dp) / n_sample
                  do it = 1, 60
                     mid = 0.5_dp * (lo + hi)
                     if (ring_switched(md, s0, s1, r, h, mid, q5, act0)) then
                        hi = mid
                     else
                        lo = mid
                     end if
                  end do
                  if (hi < th) then
                     th = hi;  self%ev_contact = md%n_contacts + r
                     call ring_state_at(md, s0, s1, r, h, hi, q5, act, val0)
                     self%ev_onset = act .and. .not. act0
                     self%ev_friction = act .eqv. act0
                  end if
                  exit
               end if
            end do
         end do
      end associate
   end subroutine first_ring_event

   !> After an accepted sub-step k: the regimes of the rings at its end (a located friction
   !> switch forced, a located onset anchored at the contact point), the force jump of a
   !> damper at a located onset or release (the next sub-step starts from the right limit),
   !> and the ring forces of the new regimes (continuous at friction switches).
   module subroutine ring_switches(self, k, event)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-state at the end
      logical, intent(in) :: event                          !! the step ended at an event
      integer :: forced, r, c, onset_mode
      real(dp) :: d, n(2), t(2), tau, gt, onset_sigma
      real(dp), allocatable :: pr(:)
      logical :: jump
      associate (md => self%model, s => self%sub(self%ix(k)))
         forced = 0;  jump = .false.;  r = 0;  c = 0
         if (event) then
            self%events = self%events + 1
            if (self%ev_contact > md%n_contacts) then
               r = self%ev_contact - md%n_contacts
               if (self%ev_friction) forced = r
               if (self%ev_onset) then
                  ! closes here: stick at the contact point or slip at once
                  call onset_regime(md, r, ring_xy(md, r, s%u), ring_xy(md, r, s%v), &
                                    s%mode(r), s%sigma(r), s%anchor(r))
                  onset_mode = s%mode(r);  onset_sigma = s%sigma(r)
               end if
               jump = .not. self%ev_friction .and. md%laws(md%r_law(r))%law%jumps(md%r_k(r), &
                                                                      md%r_c(r), md%r_p(r))
            else
               c = self%ev_contact
               jump = self%jumps(c)
            end if
         end if
         call update_ring_modes(md, s%u, s%v, s%a, s%mode, s%sigma, s%anchor, forced)
         if (r > 0 .and. self%ev_onset) then
            ! round-off may put the onset a hair outside: it touches
            s%mode(r) = onset_mode;  s%sigma(r) = onset_sigma
            call ring_geometry(md, r, ring_xy(md, r, s%u), d, n, t, tau, gt)
            s%anchor(r) = tau
         else if (r > 0 .and. .not. self%ev_friction) then
            ! a located release: the step redone to the event may end a hair before it, with
            ! a vanishing normal force; it opens here (held in its regime over the next step,
            ! the wear meter would count the free flight as sliding or stick)
            s%mode(r) = ring_open
            call ring_geometry(md, r, ring_xy(md, r, s%u), d, n, t, tau, gt)
            s%anchor(r) = tau
         end if
         if (jump) then
            call self%restart_after_event(k)
         else
            pr = ring_load(md, s)
            if (r > 0 .and. .not. (self%ev_onset .or. self%ev_friction)) then
               s%fn(r) = 0.0_dp;  s%ft(r) = 0.0_dp
            end if
         end if
      end associate
   end subroutine ring_switches

   !> At a located event the contact force may jump (a damper's force c d' at impact): the
   !> next sub-step starts from the right limit, forces of the new contact state and the
   !> acceleration in equilibrium with them, so that the trapezoidal rule does not average
   !> across the jump (which would cost an O(dt) velocity error per impact).
   module subroutine restart_after_event(self, k)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator
      integer, intent(in) :: k                              !! sub-state at the event
      integer :: c, i
      real(dp) :: d, dd
      associate (md => self%model, s => self%sub(self%ix(k)))
         do c = 1, md%n_contacts
            i = md%c_dof(c)
            d = md%c_sign(c) * s%u(i) - md%c_gap(c)
            dd = md%c_sign(c) * s%v(i)
            if (c == self%ev_contact) then
               if (self%ev_onset) then
                  s%f(c) = contact_force(md, c, max(d, tiny(1.0_dp)), dd)
               else
                  s%f(c) = 0.0_dp
               end if
            else
               s%f(c) = contact_force(md, c, d, dd)
            end if
         end do
         if (md%n_rings > 0) then
            call restart_rings(md, self%ev_contact - md%n_contacts, self%ev_onset, s)
         else
            call equilibrium_acceleration(md, s%t, s%u, s%v, s%f, s%a)
         end if
      end associate
   end subroutine restart_after_event

   !> Indicators of ring r at fraction x of the sub-step s0 -> s1 of length h: the cubic
   !> Hermite interpolant of its node's (w, v) in the regime of s0, or (`quintic`) the quintic
   !> from (w, v), their rates and accelerations at both ends.
   subroutine ring_state_at(model, s0, s1, r, h, x, quintic, active, valid)
      type(model_t), intent(in) :: model        !! model
      type(state_t), intent(in) :: s0, s1       !! the sub-step's ends
      integer, intent(in) :: r                  !! ring
      real(dp), intent(in) :: h, x              !! length [s], fraction [-]
      logical, intent(in) :: quintic            !! the quintic, else the cubic
      logical, intent(out) :: active, valid     !! in contact; regime holds
      real(dp) :: h00, h10, h01, h11, g00, g10, g01, g11, xx(2), xd(2), xdd(2)
      real(dp) :: w(6), g(6), c(6)
      integer :: j, i
      if (quintic) then
         call quintic_weights(x, h, w, g)
         ! the second derivative's weights (times h^2)
         c(1) = -60.0_dp * x + 180.0_dp * x**2 - 120.0_dp * x**3
         c(2) = h * (-36.0_dp * x + 96.0_dp * x**2 - 60.0_dp * x**3)
         c(3) = h**2 * (1.0_dp - 9.0_dp * x + 18.0_dp * x**2 - 10.0_dp * x**3)
         c(4) = -c(1)
         c(5) = h * (-24.0_dp * x + 84.0_dp * x**2 - 60.0_dp * x**3)
         c(6) = h**2 * (3.0_dp * x - 12.0_dp * x**2 + 10.0_dp * x**3)
         do j = 1, 2
            i = model%r_dof(j, r)
            xx(j) = w(1) * s0%u(i) + w(2) * s0%v(i) + w(3) * s0%a(i) + w(4) * s1%u(i) &
                    + w(5) * s1%v(i) + w(6) * s1%a(i)
            xd(j) = g(1) * s0%u(i) + g(2) * s0%v(i) + g(3) * s0%a(i) + g(4) * s1%u(i) &
                    + g(5) * s1%v(i) + g(6) * s1%a(i)
            xdd(j) = (c(1) * s0%u(i) + c(2) * s0%v(i) + c(3) * s0%a(i) + c(4) * s1%u(i) &
                      + c(5) * s1%v(i) + c(6) * s1%a(i)) / h**2
         end do
         call ring_indicators(model, r, s0%mode(r), s0%sigma(r), s0%anchor(r), xx, xd, xdd, &
                              active, valid)
         return
      end if
      call hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
      do j = 1, 2
         i = model%r_dof(j, r)
         xx(j) = h00 * s0%u(i) + h10 * h * s0%v(i) + h01 * s1%u(i) + h11 * h * s1%v(i)
         xd(j) = (g00 * s0%u(i) + g10 * h * s0%v(i) + g01 * s1%u(i) + g11 * h * s1%v(i)) / h
         ! second derivative of the cubic
         xdd(j) = ((12.0_dp * x - 6.0_dp) * (s0%u(i) - s1%u(i)) + h * ((6.0_dp * x - 4.0_dp) &
                  * s0%v(i) + (6.0_dp * x - 2.0_dp) * s1%v(i))) / h**2
      end do
      call ring_indicators(model, r, s0%mode(r), s0%sigma(r), s0%anchor(r), xx, xd, xdd, &
                           active, valid)
   end subroutine ring_state_at

   !> Has ring r switched by fraction x: its activity differs from `act0`, or its friction
   !> regime no longer holds?
   logical function ring_switched(model, s0, s1, r, h, x, quintic, act0) result(sw)
      type(model_t), intent(in) :: model        !! model
      type(state_t), intent(in) :: s0, s1       !! the sub-step's ends
      integer, intent(in) :: r                  !! ring
      real(dp), intent(in) :: h, x              !! length [s], fraction [-]
      logical, intent(in) :: quintic            !! on the quintic (ring_state_at)
      logical, intent(in) :: act0               !! activity at the start
      logical :: a, v
      call ring_state_at(model, s0, s1, r, h, x, quintic, a, v)
      sw = (a .neqv. act0) .or. (a .and. .not. v)
   end function ring_switched

   !> The ring forces at a located switch of ring `re` (0: a scalar contact's), right limit:
   !> a ring that closes there (onset) is taken as touching even if round-off puts it a hair
   !> outside, one that opens there (release) carries no force; then the acceleration in
   !> equilibrium with every force.
   subroutine restart_rings(model, re, onset, s)
      type(model_t), intent(in) :: model        !! model
      integer, intent(in) :: re                 !! ring of the event (<= 0: none)
      logical, intent(in) :: onset              !! the event closes it
      type(state_t), intent(inout) :: s         !! state at the event
      real(dp) :: pr(model%n), pp(2)
      integer :: r
      pr = 0.0_dp
      do r = 1, model%n_rings
         call ring_force(model, r, s%mode(r), s%sigma(r), s%anchor(r), ring_xy(model, r, s%u), &
                         ring_xy(model, r, s%v), pp, s%fn(r), s%ft(r), &
                         touching=(r == re .and. onset))
         if (r == re .and. .not. onset) then
            ! released here: no force on the right
            pp = 0.0_dp;  s%fn(r) = 0.0_dp;  s%ft(r) = 0.0_dp
         end if
         pr(model%r_dof(:, r)) = pr(model%r_dof(:, r)) + pp
      end do
      call equilibrium_acceleration(model, s%t, s%u, s%v, s%f, s%a, pr)
   end subroutine restart_rings

   !> Is contact c active at fraction x of a sub-step of length h (cubic Hermite interpolant
   !> of its dof from (u0, v0) to (u1, v1))? Penetration > 0, and for a law whose force can
   !> vanish earlier (a damper) also a positive force (the release: k d + c d' > 0).
   pure logical function contact_active(model, c, x, h, u0, v0, u1, v1, damped) result(active)
      type(model_t), intent(in) :: model     !! model
      integer, intent(in) :: c               !! contact
      real(dp), intent(in) :: x, h           !! fraction [-], sub-step [s]
      real(dp), intent(in) :: u0, v0, u1, v1 !! the contact dof at the ends
      logical, intent(in) :: damped          !! the force can vanish before the penetration
      real(dp) :: d, dd, h00, h10, h01, h11, g00, g10, g01, g11
      ! hermite_weights' position weights written out: this runs several times per step, and a
      ! procedure of another module is not inlined (a global symbol under -fPIC): the call cost
      ! 2 % of the time of Newmark under error control (scripts/bench.sh, case f)
      h00 = (1 + 2 * x) * (1 - x)**2;  h10 = x * (1 - x)**2
      h01 = x**2 * (3 - 2 * x);  h11 = x**2 * (x - 1)
      d = model%c_sign(c) * (h00 * u0 + h10 * h * v0 + h01 * u1 + h11 * h * v1) - model%c_gap(c)
      active = d > 0.0_dp
      if (active .and. damped) then
         call hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
         dd = model%c_sign(c) * (g00 * u0 + g10 * h * v0 + g01 * u1 + g11 * h * v1) / h
         active = contact_force(model, c, d, dd) > 0.0_dp
      end if
   end function contact_active

   !> No ring can switch within the step ix(0) -> ix(1), whatever the cubic's error: the model
   !> has rings only (no flat contacts), each open at both ends, and the cubic Hermite path of
   !> its node stays inside its clearance by twice the cubic's own error there (the error
   !> estimate at the midpoint, where a cubic's h^4 error peaks). The path lies in the convex
   !> hull of its Bezier points x0, x0 + h x0'/3, x1 - h x1'/3, x1, and the clearance (a disk,
   !> or the half plane of a flat ring) is convex: all four inside by the margin puts the path
   !> there. Event location then finds nothing on any interpolant, so the cubic's check
   !> (dense_ratio) has nothing to hold; the quintic's still holds every output. (In free
   !> flight the cubic's check sized 8 084 of the 8 126 steps of the tube deck's open phases.)
   logical module function rings_clear(self) result(clear)
      class(stepping_integrator_t), intent(in) :: self   !! integrator (step in ix(0), ix(1))
      real(dp) :: h, e(2), p(2, 4), d, n(2), t(2), gt, margin
      integer :: rg, j
      clear = .false.
      associate (m => self%model, s0 => self%sub(self%ix(0)), s1 => self%sub(self%ix(1)))
         if (m%n_rings == 0 .or. m%n_contacts > 0) return
         h = s1%t - s0%t
         do rg = 1, m%n_rings
            if (s0%mode(rg) /= ring_open .or. s0%fn(rg) > 0.0_dp .or. s1%fn(rg) > 0.0_dp) return
            e = ring_xy(m, rg, self%eu_d)
            margin = 2.0_dp * norm2(e)
            p(:, 1) = ring_xy(m, rg, s0%u)
            p(:, 2) = p(:, 1) + (h / 3.0_dp) * ring_xy(m, rg, s0%v)
            p(:, 4) = ring_xy(m, rg, s1%u)
            p(:, 3) = p(:, 4) - (h / 3.0_dp) * ring_xy(m, rg, s1%v)
            do j = 1, 4
               call ring_geometry(m, rg, p(:, j), d, n, t, gt=gt)
               if (d > -margin) return
            end do
         end do
      end associate
      clear = .true.
   end function rings_clear

   !> The first ring that the trial step ix(0) -> ix(1) enters (open at the start, with a
   !> contact force at the end), when the stepper checks its quintic (quintic_events, set by
   !> its last dense_ratio); 0: none.
   integer module function entered_ring(self) result(re)
      class(stepping_integrator_t), intent(in) :: self   !! integrator
      integer :: rg
      re = 0
      if (.not. self%quintic_events) return
      associate (s0 => self%sub(self%ix(0)), s1 => self%sub(self%ix(1)))
         do rg = 1, self%model%n_rings
            if (s0%mode(rg) == ring_open .and. s0%fn(rg) <= 0.0_dp .and. s1%fn(rg) > 0.0_dp) &
               then
               re = rg;  return
            end if
         end do
      end associate
   end function entered_ring

   !> The cubic's errors at the dofs of the rings in contact at the step's start, and of the
   !> ring held open over a trial step that entered it, set to zero: their events are located
   !> on the quintic, which dense_ratio checks apart.
   module subroutine forget_closed_rings(self)
      class(stepping_integrator_t), intent(inout) :: self   !! integrator (step in ix(0))
      integer :: rg
      associate (m => self%model, s0 => self%sub(self%ix(0)))
         do rg = 1, m%n_rings
            if ((s0%mode(rg) == ring_open .or. s0%fn(rg) <= 0.0_dp) .and. &
                rg /= self%held_ring) cycle
            self%eu(m%r_dof(:, rg)) = 0.0_dp;  self%ev(m%r_dof(:, rg)) = 0.0_dp
         end do
      end associate
   end subroutine forget_closed_rings
end submodule gapbeam_stepping_events
