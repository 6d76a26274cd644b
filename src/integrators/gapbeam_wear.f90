!> The wear and energy meter of a transient run: what a support sees beyond the impacts (normal
!> work rate, sliding, friction work, Archard wear), the ring contacts' share of the impact
!> statistics, the flat stops' impact statistics for the integrators that do not give them
!> exactly (force integrals, work, contact time, the peak located inside each piece), the orbits
!> at the supports, and the energy balance of the record.
!>
!> The recorder (gapbeam_recorder) owns one and hands it the recorded pieces. Each piece is
!> integrated with 3-point Gauss-Legendre quadrature on its dense output (pieces end at every
!> contact and stick-slip switch, so the integrands are smooth inside one); exact end-point
!> formulas where they exist:
!> * normal work rate W_N = (1/T) int f_n |v_slip| dt over the slip only: with friction the
!>   slider's velocity, W_N = (friction work of the slip pieces) / mu (nothing in stick: the
!>   stick spring's elastic motion wears nothing); without friction the tangential velocity of
!>   the node in contact (t.x' for a ring, the other plane's translation for a flat stop of a
!>   two-plane model);
!> * sliding distance: the friction slider's travel over the slip pieces, sigma (tau_a(tb) -
!>   tau_a(ta)) on a flat stop (exact; the stick spring's stretch, at most mu f_n / k_t, is not
!>   sliding); on a circle at the contact radius rho = g + d, sigma int (rho / g) dtau_a, by
!>   parts (rho_b / g) (tau_a(tb) - tau_a(ta)) less the quadrature of (tau_a - tau_a(ta)) d' / g
!>   (the radius changes with the penetration: the mean of its end values was a second-order
!>   error per piece, which the long steps of rk45 showed); or int |v_t| dt over the contact
!>   time for a support without friction;
!> * friction work over a slip piece: int -f_t v_t dt - (E_t(tb) - E_t(ta)) (the work into the
!>   Jenkins element less the change of its spring energy); nothing in stick;
!> * wear volume rate = wear_coefficient W_N (Archard with the work-rate form of tube-wear
!>   practice);
!> * energy balance (when asked): input work int P(t).v dt, Rayleigh int v'Cv dt, contact
!>   dampers int (f - k d) d' dt, friction, and the change of the stored energy (kinetic, strain,
!>   contact springs, stick springs) between the start and the end of the record.
module gapbeam_wear
   use gapbeam_kinds, only: dp
   use gapbeam_model, only: model_t, ring_xy, load_factor, add_extra_load, has_tube_physics, &
      has_modal_damping
   use gapbeam_contact_law, only: contact_force, contact_elastic, contact_energy
   use gapbeam_ring_contact, only: ring_force, ring_geometry, ring_stored_energy, ring_slip, &
      ring_anchor_of, ring_tangent_gap
   use gapbeam_linalg, only: band_matvec, dense_matvec
   use gapbeam_observer, only: piece_t
   use gapbeam_results, only: transient_result_t
   implicit none
   private
   public :: wear_meter_t

   real(dp), parameter :: gx(3) = [0.5_dp - 0.5_dp * sqrt(0.6_dp), 0.5_dp, &
                                   0.5_dp + 0.5_dp * sqrt(0.6_dp)]   ! Gauss points on [0, 1]
   real(dp), parameter :: gw(3) = [5.0_dp, 8.0_dp, 5.0_dp] / 18.0_dp  ! their weights

   !> Accumulates the wear outputs and the energy balance of the recorded pieces.
   type :: wear_meter_t
      logical :: active = .false.          !! the model has two planes or ring contacts
      logical :: energy = .false.          !! energy balance asked
      logical :: flat = .false.            !! the model has flat contacts (their statistics)
      type(model_t) :: model               !! the model (a copy, when active or energy)
      real(dp), allocatable :: wn(:), slide(:), fric(:), stick(:), contact(:)   !! per stop
      real(dp) :: e_in = 0.0_dp, e_ray = 0.0_dp, e_damp = 0.0_dp, e_fric = 0.0_dp
      real(dp) :: e_start = 0.0_dp, e_end = 0.0_dp   !! stored energy [J]
      logical :: started = .false.         !! the first recorded piece was seen
      !> the last piece's end state and ring regimes: its stored energy (e_end) is computed
      !> once, at the finish, not at every piece's end
      real(dp), allocatable :: u_end(:), v_end(:), end_sigma(:), end_anchor(:)
      integer, allocatable :: end_mode(:)
      real(dp), allocatable :: u(:), v(:), w(:), y(:)   !! workspaces (n)
      !> the Rayleigh (and modal) damping matrix beta M + gamma K (+ C_modal) in one, where the
      !> products are dense (a reduced model): one product per Gauss point instead of two
      real(dp), allocatable :: c_ray(:, :)
      !> flat contacts: force and penetration rate at the Gauss points of a piece, its time
      !> in contact and its work int f |d'| dt
      real(dp), allocatable :: fq(:, :), dq(:, :), tin(:), wk(:)
      logical, allocatable :: busy(:)              !! flat contacts loaded at an end of a piece
      !> rings: ring_piece_stats' workspace (allocated once: gfortran puts automatic arrays on
      !> the heap), (n_rings, 8) and the normal forces at the Gauss points (3, n_rings)
      real(dp), allocatable :: rw(:, :), rfq(:, :)
   contains
      procedure :: init => meter_init
      procedure :: piece => meter_piece
      procedure :: sample => meter_sample
      procedure :: finish => meter_finish
      procedure, private :: energy_at, ring_piece_stats, scalar_point, located_peak, &
         flat_point, flat_piece_end, flat_work, flat_at
   end type wear_meter_t

contains

   !> Prepare for a model with ns deck stops.
   subroutine meter_init(self, model, ns, energy)
      class(wear_meter_t), intent(inout) :: self   !! meter
      type(model_t), intent(in) :: model           !! model
      integer, intent(in) :: ns                    !! deck stops
      logical, intent(in) :: energy                !! energy balance asked
      self%active = has_tube_physics(model)
      self%energy = energy
      self%flat = model%n_contacts > 0
      allocate(self%wn(ns), self%slide(ns), self%fric(ns), self%stick(ns), self%contact(ns), &
               source=0.0_dp)
      allocate(self%fq(3, model%n_contacts), self%dq(3, model%n_contacts), &
               self%tin(model%n_contacts), self%wk(model%n_contacts), source=0.0_dp)
      allocate(self%busy(model%n_contacts), source=.false.)
      allocate(self%rw(model%n_rings, 8), self%rfq(3, model%n_rings), source=0.0_dp)
      if (.not. (self%active .or. self%energy .or. self%flat)) return
      self%model = model
      allocate(self%u(model%n), self%v(model%n), self%w(model%n), self%y(model%n), &
               self%u_end(model%n), self%v_end(model%n), self%end_sigma(model%n_rings), &
               self%end_anchor(model%n_rings), source=0.0_dp)
      allocate(self%end_mode(model%n_rings), source=0)
      if (energy .and. .not. band_products(model, model%sys%m_band, model%sys%m) .and. .not. &
          band_products(model, model%sys%k_band, model%sys%k)) then
         self%c_ray = model%beta * model%sys%m + model%gamma * model%sys%k
         if (has_modal_damping(model)) self%c_ray = self%c_ray + model%c_modal
      end if
   end subroutine meter_init

   !> A recorded piece: wear integrals, the impact statistics of the rings and (unless the
   !> integrator gives them exactly) of the flat contacts, added to the recorder's per-stop
   !> accumulators, the energy terms.
   subroutine meter_piece(self, p, acc_f, acc_f2, acc_work, acc_contact, n_impacts, peak)
      class(wear_meter_t), intent(inout) :: self       !! meter
      class(piece_t), intent(in) :: p                  !! the piece
      real(dp), intent(inout) :: acc_f(:), acc_f2(:), acc_work(:), acc_contact(:)  !! per stop
      integer, intent(inout) :: n_impacts(:)           !! per stop
      real(dp), intent(inout) :: peak(:)               !! per stop [N]
      real(dp) :: h, wq, t, pv, ray
      logical :: flat
      integer :: q
      flat = .false.
      if (self%flat .and. .not. p%exact_statistics) then
         self%busy = p%f_a /= 0.0_dp .or. p%f_b /= 0.0_dp
         flat = any(self%busy)
      end if
      if (.not. (self%active .or. self%energy .or. flat)) return
      associate (m => self%model)
         h = p%tb - p%ta
         if (self%energy .and. .not. self%started) then
            call p%state_at(p%ta, self%u, self%v)
            self%e_start = self%energy_at(p%r_mode, p%r_sigma, p%r_anchor, self%u, self%v)
         end if
         self%started = .true.
         do q = 1, 3
            t = p%ta + gx(q) * h
            wq = gw(q) * h
            call p%state_at(t, self%u, self%v)
            if (self%energy) then
               self%w = load_factor(m, t) * m%q
               call add_extra_load(m, t, self%w)
               pv = dot_product(self%w, self%v)
               if (allocated(self%c_ray)) then
                  call dense_matvec(m%n, self%c_ray, self%v, self%y)
                  ray = dot_product(self%v, self%y)
               else
                  ray = m%beta * quad(m, m%sys%m_band, m%sys%m, self%v, self%y) + m%gamma &
                        * quad(m, m%sys%k_band, m%sys%k, self%v, self%y)
                  if (has_modal_damping(m)) ray = ray + dot_product(self%v, &
                                                              matmul(m%c_modal, self%v))
               end if
               self%e_in = self%e_in + wq * pv
               self%e_ray = self%e_ray + wq * ray
            end if
            if (self%active .or. self%energy) call self%scalar_point(wq)
            if (flat) call self%flat_point(q, wq, acc_f, acc_f2)
         end do
         if (flat) call self%flat_piece_end(p, acc_work, acc_contact, peak)
         if (m%n_rings > 0 .and. (self%active .or. self%energy)) &
            call self%ring_piece_stats(p, acc_f, acc_f2, acc_work, acc_contact, n_impacts, peak)
         if (self%energy) then
            call p%state_at(p%tb, self%u_end, self%v_end)
            self%end_mode = p%r_mode;  self%end_sigma = p%r_sigma
            self%end_anchor = p%r_anchor
         end if
      end associate
   end subroutine meter_piece

   !> The flat contacts loaded at an end of the piece, at its Gauss point q (state in u, v):
   !> the quadratures of f, f^2, f |d'| and of the contact indicator (pieces end at located
   !> onsets and releases, where the force may jump: the integrands are smooth inside one).
   subroutine flat_point(self, q, wq, acc_f, acc_f2)
      class(wear_meter_t), intent(inout) :: self       !! meter
      integer, intent(in) :: q                         !! Gauss point
      real(dp), intent(in) :: wq                       !! its weight times the piece [s]
      real(dp), intent(inout) :: acc_f(:), acc_f2(:)   !! per stop
      integer :: c, k
      real(dp) :: f
      do c = 1, self%model%n_contacts
         self%fq(q, c) = 0.0_dp;  self%dq(q, c) = 0.0_dp
         if (q == 1) then
            self%tin(c) = 0.0_dp;  self%wk(c) = 0.0_dp
         end if
         if (.not. self%busy(c)) cycle
         k = self%model%c_stop(c)
         call self%flat_at(c, f, self%dq(q, c))
         self%fq(q, c) = f
         if (f <= 0.0_dp) cycle
         self%tin(c) = self%tin(c) + wq
         acc_f(k) = acc_f(k) + wq * f
         acc_f2(k) = acc_f2(k) + wq * f**2
         self%wk(c) = self%wk(c) + wq * f * abs(self%dq(q, c))
      end do
   end subroutine flat_point

   !> Force and penetration rate of flat contact c at the state in u, v.
   subroutine flat_at(self, c, f, dd)
      class(wear_meter_t), intent(in) :: self          !! meter
      integer, intent(in) :: c                         !! contact
      real(dp), intent(out) :: f, dd                   !! force [N], penetration rate [m/s]
      integer :: i
      associate (m => self%model)
         i = m%c_dof(c)
         dd = m%c_sign(c) * self%v(i)
         f = contact_force(m, c, m%c_sign(c) * self%u(i) - m%c_gap(c), dd)
      end associate
   end subroutine flat_at

   !> The flat contacts after the Gauss points of a piece: the work, the contact time, and the
   !> peak force (the ends', or located on the interpolant when a Gauss point's force exceeds
   !> them).
   subroutine flat_piece_end(self, p, acc_work, acc_contact, peak)
      class(wear_meter_t), intent(inout) :: self       !! meter
      class(piece_t), intent(in) :: p                  !! the piece
      real(dp), intent(inout) :: acc_work(:)           !! per stop [J]
      real(dp), intent(inout) :: acc_contact(:)        !! per stop [s]
      real(dp), intent(inout) :: peak(:)               !! per stop [N]
      integer :: c, k
      do c = 1, self%model%n_contacts
         if (.not. self%busy(c)) cycle
         k = self%model%c_stop(c)
         acc_contact(k) = acc_contact(k) + self%tin(c)
         acc_work(k) = acc_work(k) + self%flat_work(p, c)
         peak(k) = max(peak(k), p%f_a(c), p%f_b(c))
         if (maxval(self%fq(:, c)) > max(p%f_a(c), p%f_b(c))) &
            peak(k) = max(peak(k), self%located_peak(p, c, .false., self%fq(:, c)))
      end do
   end subroutine flat_piece_end

   !> The work int f |d'| dt of flat contact c over a piece. |d'| has a kink where the
   !> penetration turns (inside the piece of an impact's deepest point): where d' changes sign
   !> between the ends and the Gauss points, the piece is split at its zeros (located on the
   !> interpolant by the Illinois rule) and each part integrated by 3-point Gauss; else the
   !> piece's own quadrature stands.
   real(dp) function flat_work(self, p, c) result(w)
      class(wear_meter_t), intent(inout) :: self   !! meter
      class(piece_t), intent(in) :: p              !! the piece
      integer, intent(in) :: c                     !! flat contact
      real(dp) :: sn(5), dn(5), cut(6), f, dd, h, a, b, fa, fb, s, fs, t
      integer :: j, nc, it, q, side
      h = p%tb - p%ta
      sn = [0.0_dp, gx(1), gx(2), gx(3), 1.0_dp]
      dn(2:4) = self%dq(:, c)
      call p%state_at(p%ta, self%u, self%v)
      call self%flat_at(c, f, dn(1))
      call p%state_at(p%tb, self%u, self%v)
      call self%flat_at(c, f, dn(5))
      nc = 1;  cut(1) = 0.0_dp
      do j = 1, 4
         if (.not. (dn(j) * dn(j + 1) < 0.0_dp)) cycle
         a = sn(j);  b = sn(j + 1);  fa = dn(j);  fb = dn(j + 1);  side = 0
         s = a
         do it = 1, 60
            s = (a * fb - b * fa) / (fb - fa)
            fs = rate_at(s)
            if (fs * fb > 0.0_dp) then
               b = s;  fb = fs
               if (side == -1) fa = 0.5_dp * fa
               side = -1
            else
               a = s;  fa = fs
               if (side == 1) fb = 0.5_dp * fb
               side = 1
            end if
            if (b - a <= 1.0e-12_dp .or. fs == 0.0_dp) exit
         end do
         nc = nc + 1;  cut(nc) = s
      end do
      if (nc == 1) then
         w = self%wk(c)
         return
      end if
      nc = nc + 1;  cut(nc) = 1.0_dp
      w = 0.0_dp
      do j = 1, nc - 1
         do q = 1, 3
            t = p%ta + h * (cut(j) + gx(q) * (cut(j + 1) - cut(j)))
            call p%state_at(t, self%u, self%v)
            call self%flat_at(c, f, dd)
            if (f > 0.0_dp) w = w + gw(q) * h * (cut(j + 1) - cut(j)) * f * abs(dd)
         end do
      end do
   contains
      real(dp) function rate_at(x) result(r)
         real(dp), intent(in) :: x
         real(dp) :: fx
         call p%state_at(p%ta + x * h, self%u, self%v)
         call self%flat_at(c, fx, r)
      end function rate_at
   end function flat_work

   !> The scalar contacts at one quadrature point (state in u, v): normal work rate and
   !> sliding along the other plane, contact-damper dissipation.
   subroutine scalar_point(self, wq)
      class(wear_meter_t), intent(inout) :: self   !! meter
      real(dp), intent(in) :: wq                   !! quadrature weight times the piece [s]
      integer :: c, i, k, it
      real(dp) :: d, dd, f, fe
      associate (m => self%model)
         do c = 1, m%n_contacts
            i = m%c_dof(c);  k = m%c_stop(c)
            d = m%c_sign(c) * self%u(i) - m%c_gap(c)
            dd = m%c_sign(c) * self%v(i)
            f = contact_force(m, c, d, dd)
            ! the damper's share of the work (the force less its elastic part), wherever the
            ! spring is compressed (a released damped contact, f = 0 at d > 0, returns the
            ! spring's energy to nothing)
            if (self%energy .and. d > 0.0_dp) then
               fe = contact_elastic(m, c, d)
               if (f /= fe) self%e_damp = self%e_damp + wq * (f - fe) * dd
            end if
            if (f <= 0.0_dp) cycle
            it = m%c_tdof(c)
            if (it > 0) then
               self%wn(k) = self%wn(k) + wq * f * abs(self%v(it))
               self%slide(k) = self%slide(k) + wq * abs(self%v(it))
            end if
         end do
      end associate
   end subroutine scalar_point

   !> The ring contacts over a piece.
   subroutine ring_piece_stats(self, p, acc_f, acc_f2, acc_work, acc_contact, n_impacts, peak)
      class(wear_meter_t), intent(inout) :: self       !! meter
      class(piece_t), intent(in) :: p                  !! the piece
      real(dp), intent(inout) :: acc_f(:), acc_f2(:), acc_work(:), acc_contact(:)  !! per stop
      integer, intent(inout) :: n_impacts(:)           !! per stop
      real(dp), intent(inout) :: peak(:)               !! per stop [N]
      real(dp) :: h, wq, t, x(2), xd(2), pr(2), fn, ft, d, n(2), tg(2), gt, vt, dn, fe
      real(dp) :: tc
      integer :: q, r, k, e
      associate (m => self%model, pw => self%rw(:, 1), ea => self%rw(:, 2), &
                 eb => self%rw(:, 3), ta_a => self%rw(:, 4), tb_a => self%rw(:, 5), &
                 rho_b => self%rw(:, 6), sq => self%rw(:, 7), tin => self%rw(:, 8), &
                 fq => self%rfq)
         h = p%tb - p%ta
         pw = 0.0_dp;  sq = 0.0_dp;  tin = 0.0_dp
         ! the ends: stick-spring energy (its change is not dissipated)
         do e = 1, 2
            t = merge(p%ta, p%tb, e == 1)
            call p%state_at(t, self%u, self%v)
            do r = 1, m%n_rings
               x = ring_xy(m, r, self%u);  xd = ring_xy(m, r, self%v)
               call ring_force(m, r, p%r_mode(r), p%r_sigma(r), p%r_anchor(r), x, xd, pr, fn, ft)
               call ring_geometry(m, r, x, d, n, tg, gt=gt)
               if (e == 1) then
                  ea(r) = 0.0_dp
                  if (m%r_mu(r) > 0.0_dp) ea(r) = 0.5_dp * ft**2 / (m%r_kt(r) * gt**2)
                  ta_a(r) = ring_anchor_of(m, r, p%r_mode(r), p%r_sigma(r), p%r_anchor(r), x, xd)
               else
                  eb(r) = 0.0_dp
                  if (m%r_mu(r) > 0.0_dp) eb(r) = 0.5_dp * ft**2 / (m%r_kt(r) * gt**2)
                  tb_a(r) = ring_anchor_of(m, r, p%r_mode(r), p%r_sigma(r), p%r_anchor(r), x, xd)
                  rho_b(r) = m%r_gap(r) + d
               end if
               if (.not. m%r_circular(r)) rho_b(r) = 1.0_dp   ! flat: no radius, the factor is 1
            end do
         end do
         do q = 1, 3
            t = p%ta + gx(q) * h
            wq = gw(q) * h
            call p%state_at(t, self%u, self%v)
            do r = 1, m%n_rings
               k = m%r_stop(r)
               x = ring_xy(m, r, self%u);  xd = ring_xy(m, r, self%v)
               call ring_force(m, r, p%r_mode(r), p%r_sigma(r), p%r_anchor(r), x, xd, pr, fn, ft)
               fq(q, r) = fn
               call ring_geometry(m, r, x, d, n, tg, gt=gt)
               vt = dot_product(tg, xd);  dn = dot_product(n, xd)
               ! the slider's travel at the contact radius rho, int rho dtau_a, by parts:
               ! rho_b (tau_a(tb) - tau_a(ta)) - int (tau_a - tau_a(ta)) rho' dt (rho' = d')
               if (p%r_mode(r) == ring_slip .and. m%r_mu(r) > 0.0_dp .and. m%r_circular(r)) &
                  sq(r) = sq(r) + wq * ring_tangent_gap(m, r, ring_anchor_of(m, r, p%r_mode(r), &
                          p%r_sigma(r), p%r_anchor(r), x, xd), ta_a(r)) * dn
               if (self%energy .and. d > 0.0_dp) then
                  fe = m%laws(m%r_law(r))%law%elastic(m%r_k(r), m%r_c(r), m%r_p(r), d)
                  if (fn /= fe) self%e_damp = self%e_damp + wq * (fn - fe) * dn
               end if
               if (fn <= 0.0_dp) cycle
               tin(r) = tin(r) + wq
               acc_f(k) = acc_f(k) + wq * fn
               acc_f2(k) = acc_f2(k) + wq * fn**2
               acc_work(k) = acc_work(k) + wq * fn * abs(dn)
               if (m%r_mu(r) == 0.0_dp) then
                  ! no stick: every motion along the wall slides
                  self%wn(k) = self%wn(k) + wq * fn * abs(vt)
                  self%slide(k) = self%slide(k) + wq * abs(vt)
               end if
               if (p%r_mode(r) == ring_slip) pw(r) = pw(r) - wq * ft * vt
            end do
         end do
         do r = 1, m%n_rings
            k = m%r_stop(r)
            ! the contact time: the quadrature of the contact's indicator (pieces end at
            ! located onsets and releases, so a piece is in contact at all its points or none;
            ! the mean of the ends' counted half of a piece that ends at a release, whose
            ! normal force is zero on the right)
            tc = tin(r)
            acc_contact(k) = acc_contact(k) + tc
            self%contact(k) = self%contact(k) + tc
            if (p%r_mode(r) /= ring_slip .and. m%r_mu(r) > 0.0_dp) &
               self%stick(k) = self%stick(k) + tc
            if (p%r_onset(r)) n_impacts(k) = n_impacts(k) + 1
            peak(k) = max(peak(k), p%fn_b(r))
            if (maxval(fq(:, r)) > max(p%fn_a(r), p%fn_b(r))) &
               peak(k) = max(peak(k), self%located_peak(p, r, .true., fq(:, r)))
            if (p%r_mode(r) == ring_slip .and. m%r_mu(r) > 0.0_dp) then
               ! the slider's dissipation mu int f_n |d tau_a / dt| dt; the normal work rate is
               ! its share without mu: slip only, the stick spring's motion is not wear
               self%fric(k) = self%fric(k) + pw(r) - (eb(r) - ea(r))
               self%wn(k) = self%wn(k) + (pw(r) - (eb(r) - ea(r))) / m%r_mu(r)
               ! the slider's travel, at the contact radius (rho = 1: flat)
               self%slide(k) = self%slide(k) + p%r_sigma(r) * (rho_b(r) * ring_tangent_gap(m, &
                  r, tb_a(r), ta_a(r)) - sq(r)) / merge(m%r_gap(r), 1.0_dp, m%r_circular(r))
            end if
         end do
      end associate
   end subroutine ring_piece_stats

   !> The largest normal force of ring j (ring) or flat contact j inside a piece whose Gauss
   !> points' forces fq exceed both ends': golden-section search on the piece's interpolant between the neighbours of
   !> the largest sample (the peak of an impact located, not the largest value at a step's
   !> end).
   real(dp) function located_peak(self, p, j, ring, fq) result(fmax)
      class(wear_meter_t), intent(inout) :: self   !! meter
      class(piece_t), intent(in) :: p              !! the piece
      integer, intent(in) :: j                     !! ring or flat contact
      logical, intent(in) :: ring                  !! j is a ring (else a flat contact)
      real(dp), intent(in) :: fq(3)                !! normal force at the Gauss points [N]
      real(dp), parameter :: gr = 0.5_dp * (sqrt(5.0_dp) - 1.0_dp)
      real(dp) :: sn(5), a, b, c, d, fc, fd
      integer :: jq, it
      sn = [0.0_dp, gx(1), gx(2), gx(3), 1.0_dp]
      jq = 1 + maxloc(fq, 1)
      fmax = fq(jq - 1)
      a = sn(jq - 1);  b = sn(jq + 1)
      c = b - gr * (b - a);  d = a + gr * (b - a)
      fc = force_at(c);  fd = force_at(d)
      do it = 1, 40
         if (fc >= fd) then
            b = d;  d = c;  fd = fc
            c = b - gr * (b - a);  fc = force_at(c)
         else
            a = c;  c = d;  fc = fd
            d = a + gr * (b - a);  fd = force_at(d)
         end if
         if (b - a <= 1.0e-6_dp) exit
      end do
      fmax = max(fmax, fc, fd)
   contains
      real(dp) function force_at(s) result(fn)
         real(dp), intent(in) :: s
         real(dp) :: pr(2), ft
         integer :: i
         call p%state_at(p%ta + s * (p%tb - p%ta), self%u, self%v)
         associate (m => self%model)
            if (ring) then
               call ring_force(m, j, p%r_mode(j), p%r_sigma(j), p%r_anchor(j), &
                               ring_xy(m, j, self%u), ring_xy(m, j, self%v), pr, fn, ft)
            else
               i = m%c_dof(j)
               fn = contact_force(m, j, m%c_sign(j) * self%u(i) - m%c_gap(j), &
                                  m%c_sign(j) * self%v(i))
            end if
         end associate
      end function force_at
   end function located_peak

   !> Stored energy at a state of a piece: kinetic, strain, contact springs and stick springs
   !> (the rings in the piece's regime) [J].
   real(dp) function energy_at(self, mode, sigma, anchor, u, v) result(e)
      class(wear_meter_t), intent(inout) :: self   !! meter
      integer, intent(in) :: mode(:)               !! the rings' regimes
      real(dp), intent(in) :: sigma(:), anchor(:)  !! their slip directions and anchors
      real(dp), intent(in) :: u(:), v(:)           !! state
      integer :: c, r
      real(dp) :: d
      associate (m => self%model)
         e = 0.5_dp * quad(m, m%sys%m_band, m%sys%m, v, self%y) &
             + 0.5_dp * quad(m, m%sys%k_band, m%sys%k, u, self%y)
         do c = 1, m%n_contacts
            d = m%c_sign(c) * u(m%c_dof(c)) - m%c_gap(c)
            if (d <= 0.0_dp) cycle
            e = e + contact_energy(m, c, d)
         end do
         do r = 1, m%n_rings
            e = e + ring_stored_energy(m, r, mode(r), sigma(r), anchor(r), &
                                       ring_xy(m, r, u), ring_xy(m, r, v))
         end do
      end associate
   end function energy_at

   !> x' A x with A in band storage when there is one and it is narrow, else dense (a reduced
   !> model's band is the whole matrix: the dense product vectorises).
   real(dp) function quad(model, ab, ad, x, y) result(s)
      type(model_t), intent(in) :: model          !! model (size, band width)
      real(dp), intent(in) :: ab(:, :), ad(:, :)  !! band and dense storage
      real(dp), intent(in) :: x(:)                !! vector
      real(dp), intent(inout) :: y(:)             !! workspace
      if (band_products(model, ab, ad)) then
         call band_matvec(model%n, model%sys%kd, ab, x, y)
      else
         call dense_matvec(model%n, ad, x, y)
      end if
      s = dot_product(x, y)
   end function quad

   !> quad takes the band product: there is a band storage and it is narrow, or no dense one.
   pure logical function band_products(model, ab, ad) result(band)
      type(model_t), intent(in) :: model          !! model (size, band width)
      real(dp), intent(in) :: ab(:, :), ad(:, :)  !! band and dense storage
      band = size(ab, 2) == model%n .and. (4 * model%sys%kd < model%n .or. size(ad, 1) &
             /= model%n)
   end function band_products

   !> Orbits, tangential and ring normal forces at a history sample (two-plane models).
   subroutine meter_sample(self, p, t, ih, res)
      class(wear_meter_t), intent(inout) :: self       !! meter
      class(piece_t), intent(in) :: p                  !! the piece holding t
      real(dp), intent(in) :: t                        !! instant [s]
      integer, intent(in) :: ih                        !! history sample
      type(transient_result_t), intent(inout) :: res   !! results (orbits, stop forces)
      integer :: k, r
      real(dp) :: pr(2), fn, ft
      if (.not. self%active) return
      associate (m => self%model)
         call p%state_at(t, self%u, self%v)
         do k = 1, m%n_stops
            if (m%stop_dofs(1, k) > 0) res%orbit_w(ih, k) = self%u(m%stop_dofs(1, k))
            if (m%stop_dofs(2, k) > 0) res%orbit_v(ih, k) = self%u(m%stop_dofs(2, k))
         end do
         res%tangential_force(ih, :) = 0.0_dp
         do r = 1, m%n_rings
            call ring_force(m, r, p%r_mode(r), p%r_sigma(r), p%r_anchor(r), &
                            ring_xy(m, r, self%u), ring_xy(m, r, self%v), pr, fn, ft)
            k = m%r_stop(r)
            res%stop_force(ih, k) = res%stop_force(ih, k) + fn
            res%tangential_force(ih, k) = res%tangential_force(ih, k) + ft
         end do
      end associate
   end subroutine meter_sample

   !> The wear outputs and the energy balance over a record of length t_len.
   subroutine meter_finish(self, t_len, res)
      class(wear_meter_t), intent(inout) :: self       !! meter
      real(dp), intent(in) :: t_len                    !! record length [s]
      type(transient_result_t), intent(inout) :: res   !! results
      real(dp) :: tl
      tl = max(t_len, tiny(1.0_dp))
      res%normal_work_rate = self%wn / tl
      res%sliding_distance = self%slide
      res%friction_work = self%fric
      res%friction_work_rate = self%fric / tl
      if (allocated(self%model%stop_wear)) then
         res%wear_volume_rate = self%model%stop_wear * res%normal_work_rate
      else
         res%wear_volume_rate = 0.0_dp
      end if
      where (self%contact > 0.0_dp)
         res%stick_fraction = self%stick / self%contact
      elsewhere
         res%stick_fraction = 0.0_dp
      end where
      res%has_energy = self%energy
      if (self%energy) then
         res%input_work = self%e_in
         res%rayleigh_dissipation = self%e_ray
         res%contact_damping_dissipation = self%e_damp
         res%friction_dissipation = sum(self%fric)
         if (self%started) self%e_end = self%energy_at(self%end_mode, self%end_sigma, &
                                                       self%end_anchor, self%u_end, self%v_end)
         res%stored_energy_change = self%e_end - self%e_start
      end if
   end subroutine meter_finish
end module gapbeam_wear
