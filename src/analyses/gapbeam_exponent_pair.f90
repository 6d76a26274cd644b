!> The two trajectories of the largest Lyapunov exponent as whole integrator states, for models
!> with ring supports (circular clearances, friction): the state of such a model is more than
!> (u, v): each ring's regime (open, stick, slip), its slip direction and its stick anchor.
!>
!> **Each trajectory carries its own state.** The reference and the perturbed trajectory are
!> advanced one forcing period at a time from where they stopped (the forcing phase restarts
!> at t = 0, the forcing being T-periodic), never rebuilt from (u, v): a ring that sticks over
!> a period boundary keeps its anchor, and the perturbed trajectory has its own regimes and
!> anchors, switched at its own located events.
!>
!> **Renormalisation of the whole state.** After each period the difference of every
!> continuous component (u, v and the stick anchors tau_a) is scaled by the same factor
!> d_0 / d, so that the perturbed state stays the reference plus a small multiple of one
!> tangent vector of the full state (Benettin's method on the full state). Keeping the
!> perturbed trajectory's own anchors while scaling (u, v) only would not be a tangent vector:
!> on a chaotic set, where (u, v) is shrunk every period, an anchor difference set at a stick
!> onset would stay at its unshrunk size and grow out of the small-separation regime. The
!> regime and slip direction, being discrete, are the perturbed trajectory's own, checked at
!> the rescaled state (gapbeam_ring_contact's update_ring_modes), and its acceleration and
!> forces are recomputed there. The step control's memory (step level) is the reference's.
!>
!> **Separation norm.** The energy norm of the full state:
!> d^2 = du'K du + dv'M dv + sum_r k_t (d(tau - tau_a))^2 over the rings that stick in both
!> (the stick spring's strain energy, twice, as du'K du is): the energy norm of the structure as
!> it is held in the period's stick regime. An anchor difference is a neutral direction of a
!> permanent stick (a shifted static equilibrium of the stuck structure): it is counted, and it
!> is zero when the perturbation starts in (u, v) only (as here) and both trajectories stick on
!> the same anchor, which the anchor keeps; then the exponent is the stuck structure's least
!> damped modal rate -zeta omega, as it must be.
!>
!> **Step sequences.** Ring switches are located only under error control, so both
!> trajectories run the run's own method with its error control. Their step sequences are
!> then functions of their states with discrete decisions (step levels, rejections): two
!> trajectories d_0 apart take the same steps, except where the reference lies within d_0 of
!> a decision threshold, and then their difference holds the difference of two local errors
!> (of the order of the tolerance, far above d_0), which is no stretching of the flow. Each
!> period's two step sequences are compared (the same number of accepted pieces, each of
!> nearly the same length: event times move with the state, step sizes do not); a period
!> whose sequences differ is run again from the other side (-delta: the tangent map is linear,
!> so -delta stretches as +delta does) and, if that differs too, at 1/100 of the size; a period
!> still discordant is not counted (`discordant`).
module gapbeam_exponent_pair
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_model, only: model_t, ring_xy
   use gapbeam_state, only: state_t
   use gapbeam_observer, only: observer_t, piece_t
   use gapbeam_integrator, only: integrator_t, start_state, equilibrium_acceleration, &
      contact_forces_at, ring_load, massless_equilibrium
   use gapbeam_ring_contact, only: ring_stick, ring_geometry, ring_tangent_gap, update_ring_modes
   implicit none
   private
   public :: pair_t, pair_start, pair_period

   !> The two trajectories and the separation they started the period with.
   type :: pair_t
      type(state_t) :: a                  !! reference
      type(state_t) :: b                  !! perturbed
      real(dp) :: d0 = 0.0_dp             !! separation at the start of every period
      integer :: discordant = 0           !! periods not counted (step sequences differ)
      integer :: retried = 0              !! periods run again from the other side
   end type pair_t

   !> The accepted pieces of one advance: their lengths [s].
   type, extends(observer_t) :: step_log_t
      integer :: n = 0
      real(dp), allocatable :: h(:)
   contains
      procedure :: observe => log_piece
   end type step_log_t

contains

   !> Keep the length of one more piece.
   subroutine log_piece(self, piece)
      class(step_log_t), intent(inout) :: self   !! log
      class(piece_t), intent(in) :: piece        !! piece
      real(dp), allocatable :: more(:)
      if (.not. allocated(self%h)) allocate(self%h(256))
      if (self%n == size(self%h)) then
         allocate(more(2 * self%n))
         more(1:self%n) = self%h
         call move_alloc(more, self%h)
      end if
      self%n = self%n + 1
      self%h(self%n) = piece%tb - piece%ta
   end subroutine log_piece

   !> Start the pair at (u, v): the reference from (u, v) (rings in the regime the state calls
   !> for), the perturbed one displaced by d0 along the reference's (u, v), its regimes and
   !> anchors the reference's.
   subroutine pair_start(model, u, v, d0, pair)
      type(model_t), intent(in) :: model        !! model
      real(dp), intent(in) :: u(:), v(:)        !! state on the attractor
      real(dp), intent(in) :: d0                !! separation [energy norm]
      type(pair_t), intent(out) :: pair         !! the two trajectories
      real(dp), allocatable :: du(:), dv(:), da(:)
      real(dp) :: d
      call start_state(model, 0.0_dp, u, v, pair%a)
      pair%d0 = d0
      du = u;  dv = v
      allocate(da(model%n_rings), source=0.0_dp)
      pair%b = pair%a
      d = state_separation(model, pair%a, with(pair%a, du, dv, da, 1.0_dp))
      if (d == 0.0_dp) then
         du = 1.0_dp;  dv = 0.0_dp
         d = state_separation(model, pair%a, with(pair%a, du, dv, da, 1.0_dp))
      end if
      call displace(model, pair%a, du, dv, da, d0 / d, pair%b)
   end subroutine pair_start

   !> A copy of s with (u, v, anchor) + c (du, dv, da) (nothing else recomputed).
   function with(s, du, dv, da, c) result(w)
      type(state_t), intent(in) :: s                   !! state
      real(dp), intent(in) :: du(:), dv(:), da(:)      !! difference
      real(dp), intent(in) :: c                        !! its multiple
      type(state_t) :: w
      w = s
      w%u = s%u + c * du;  w%v = s%v + c * dv;  w%anchor = s%anchor + c * da
   end function with

   !> b = a + s (du, dv, da) in its continuous components, b's own regimes and slip
   !> directions checked there, its forces and acceleration recomputed; the step control's
   !> memory the reference's.
   subroutine displace(model, a, du, dv, da, s, b)
      type(model_t), intent(in) :: model              !! model
      type(state_t), intent(in) :: a                  !! reference
      real(dp), intent(in) :: du(:), dv(:), da(:)     !! difference of the states
      real(dp), intent(in) :: s                       !! its scale
      type(state_t), intent(inout) :: b               !! perturbed state (regimes in, all out)
      real(dp), allocatable :: acc(:), pr(:)
      acc = a%a + s * (b%a - a%a)
      b%t = a%t
      b%u = a%u + s * du;  b%v = a%v + s * dv;  b%anchor = a%anchor + s * da
      ! dofs without mass are in equilibrium with the others (the separation norm does not see
      ! them: scaled by d0 / d > 1 every period of a contracting orbit, they would grow)
      call massless_equilibrium(model, b%u, b%v)
      call contact_forces_at(model, b%u, b%v, b%f)
      call update_ring_modes(model, b%u, b%v, acc, b%mode, b%sigma, b%anchor, 0)
      pr = ring_load(model, b)
      call equilibrium_acceleration(model, b%t, b%u, b%v, b%f, b%a, pr)
      b%f_prev = b%f
      b%dt_prev = a%dt_prev;  b%level = a%level;  b%comfortable = a%comfortable
      if (allocated(a%cu)) then
         b%cu = a%cu;  b%cv = a%cv
      end if
   end subroutine displace

   !> The separation of two states in the energy norm of the full state (module header).
   real(dp) function state_separation(model, a, b) result(d)
      type(model_t), intent(in) :: model     !! model
      type(state_t), intent(in) :: a, b      !! states
      real(dp), allocatable :: du(:), dv(:)
      real(dp) :: e, g, n(2), t(2), ta, tb, gt
      integer :: r
      du = b%u - a%u;  dv = b%v - a%v
      e = dot_product(du, matmul(model%sys%k, du)) + dot_product(dv, matmul(model%sys%m, dv))
      do r = 1, model%n_rings
         if (model%r_mu(r) <= 0.0_dp) cycle
         if (a%mode(r) /= ring_stick .or. b%mode(r) /= ring_stick) cycle
         call ring_geometry(model, r, ring_xy(model, r, a%u), g, n, t, ta, gt)
         call ring_geometry(model, r, ring_xy(model, r, b%u), g, n, t, tb, gt)
         e = e + model%r_kt(r) * (ring_tangent_gap(model, r, tb, b%anchor(r)) &
                                  - ring_tangent_gap(model, r, ta, a%anchor(r)))**2
      end do
      d = sqrt(max(e, 0.0_dp))
   end function state_separation

   !> One forcing period of both trajectories; `stretch` = ln(d / d0) of the separation d at
   !> its end (`counted` false: the period's step sequences differed from every side tried);
   !> then the perturbed state is put back at d0 from the reference along the new difference.
   subroutine pair_period(model, integ, period, pair, stretch, counted, err)
      type(model_t), intent(in) :: model               !! model
      class(integrator_t), intent(inout) :: integ      !! the pair's integrator
      real(dp), intent(in) :: period                   !! forcing period [s]
      type(pair_t), intent(inout) :: pair              !! the two trajectories
      real(dp), intent(out) :: stretch                 !! ln(d / d0)
      logical, intent(out) :: counted                  !! a sample of the flow's stretching
      type(error_t), allocatable, intent(out) :: err   !! solver failure
      type(step_log_t) :: log_a, log_b
      type(state_t) :: a0, b0
      real(dp), allocatable :: du(:), dv(:), da(:)
      real(dp) :: d, scale
      integer :: try
      pair%a%t = 0.0_dp;  pair%b%t = 0.0_dp
      a0 = pair%a;  b0 = pair%b
      call integ%advance(pair%a, period, log_a, err);  if (allocated(err)) return
      counted = .false.
      scale = 1.0_dp
      do try = 1, 3
         if (try > 1) then
            ! the other side (-delta), then 1/100 of the size
            if (try == 2) then
               scale = -1.0_dp
            else
               scale = 0.01_dp
            end if
            pair%retried = pair%retried + merge(1, 0, try == 2)
            pair%b = b0
            call displace(model, a0, b0%u - a0%u, b0%v - a0%v, &
                          anchor_difference(model, a0, b0), scale, pair%b)
         end if
         log_b%n = 0
         call integ%advance(pair%b, period, log_b, err);  if (allocated(err)) return
         counted = same_steps(log_a, log_b, period)
         if (counted) exit
      end do
      if (.not. counted) pair%discordant = pair%discordant + 1
      d = state_separation(model, pair%a, pair%b)
      if (d == 0.0_dp) then
         stretch = log(tiny(1.0_dp))
         du = pair%a%u;  dv = pair%a%v
         allocate(da(model%n_rings), source=0.0_dp)
         pair%b = pair%a
         d = max(state_separation(model, pair%a, with(pair%a, du, dv, da, 1.0_dp)), &
                 tiny(1.0_dp))
      else
         stretch = log(d / (abs(scale) * pair%d0))
         du = pair%b%u - pair%a%u;  dv = pair%b%v - pair%a%v
         da = anchor_difference(model, pair%a, pair%b)
      end if
      call displace(model, pair%a, du, dv, da, pair%d0 / d, pair%b)
   end subroutine pair_period

   !> The anchors of b less those of a, wrapped to a half circumference on a circle, for the
   !> rings that stick in both (elsewhere an anchor is no state of its own: it follows the node
   !> when open, and a slip places it where the slider stops) [m].
   function anchor_difference(model, a, b) result(da)
      type(model_t), intent(in) :: model     !! model
      type(state_t), intent(in) :: a, b      !! states
      real(dp), allocatable :: da(:)
      integer :: r
      allocate(da(model%n_rings), source=0.0_dp)
      do r = 1, model%n_rings
         if (a%mode(r) == ring_stick .and. b%mode(r) == ring_stick) &
            da(r) = ring_tangent_gap(model, r, b%anchor(r), a%anchor(r))
      end do
   end function anchor_difference

   !> The two logs took the same steps: as many pieces, each of the same length within 10 %
   !> or 1e-4 T (a located event moves a piece end with the state, by far less; a step decision
   !> of the error control changes a step by a factor 2^(1/2) at least; pieces shorter than
   !> 1e-4 T, such as the ends clipped to an event or a period, carry no local error that
   !> matters).
   logical function same_steps(la, lb, period) result(same)
      type(step_log_t), intent(in) :: la, lb   !! logs
      real(dp), intent(in) :: period           !! forcing period [s]
      integer :: i
      same = la%n == lb%n
      if (.not. same) return
      do i = 1, la%n
         if (abs(la%h(i) - lb%h(i)) > max(0.1_dp * max(la%h(i), lb%h(i)), &
                                          1.0e-4_dp * period)) then
            same = .false.
            return
         end if
      end do
   end function same_steps
end module gapbeam_exponent_pair
