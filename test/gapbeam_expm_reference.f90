!> Test helper: an independent reference for the exact integrator on small models. The same
!> piecewise-linear system in physical coordinates (massless dofs condensed), augmented with
!> the forcing, z = (u, v, sin W t, cos W t, 1), z' = A_mask z for each contact configuration,
!> propagated with matrix exponentials in extended precision (`xp`); no eigen-decomposition
!> anywhere, so it checks the modal closed form, the secular roots, the blocks and the event
!> logic of gapbeam_exact, not just their consistency.
!>
!> Time runs on a grid of units h0 / 2^n_levels (h0 = T / steps_per_period). Each
!> configuration gets a ladder of exponentials E_j = exp(A h0 / 2^j): Taylor series (degree
!> 24) of the balanced matrix where ||A h0 / 2^j|| <= 1/2, squaring for the coarser levels. A
!> step that changes the contact activity (d > 0 and, with a damper, k d + c d' > 0) is bisected
!> on the ladder to one unit (about 1e-16 of the period), and the run goes on from just after
!> the switch with the activity found there. Events shorter than a step (grazing) are missed:
!> use it on models and horizons without them.
module gapbeam_expm_reference
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, xp
   use gapbeam_model, only: model_t
   implicit none
   private
   public :: expm_run

   integer, parameter :: n_levels = 45          ! bisection levels below a step
   integer, parameter :: n_taylor = 24          ! Taylor degree at ||X|| <= 1/2

   !> Ladder of one configuration.
   type :: ladder_t
      logical :: built = .false.
      real(xp), allocatable :: e(:, :, :)       ! (nz, nz, 0:n_levels) balanced exponentials
      real(xp), allocatable :: d(:)             ! balancing: z = D z_b
   end type ladder_t

contains

   !> Run the model from (u0, v0) at t = 0 to t_end = periods T; final (u, v), switches.
   subroutine expm_run(model, u0, v0, periods, steps_per_period, u, v, switches)
      type(model_t), intent(in) :: model            !! model (bilinear stops)
      real(dp), intent(in) :: u0(:), v0(:)          !! initial state (full dofs)
      integer, intent(in) :: periods                !! forcing periods to run
      integer, intent(in) :: steps_per_period       !! coarse steps per period (power of 2)
      real(dp), intent(out) :: u(:), v(:)           !! final state (full dofs)
      integer, intent(out) :: switches              !! changes of the contact activity
      real(xp), allocatable :: kr(:, :), mr(:, :), t(:, :), z(:), zt(:), q(:)
      integer, allocatable :: ir(:), is(:), cpos(:)
      type(ladder_t), allocatable :: lad(:)
      integer :: n, nr, nz, i, c, mask, new, j, jj
      integer(int64) :: now, last, left, unit_step
      n = model%n
      ir = pack([(i, i = 1, n)], [(model%sys%m(i, i) /= 0.0_dp, i = 1, n)])
      is = pack([(i, i = 1, n)], [(model%sys%m(i, i) == 0.0_dp, i = 1, n)])
      nr = size(ir)
      call condense(model, ir, is, kr, mr, t, q)
      allocate(cpos(model%n_contacts))
      do c = 1, model%n_contacts
         cpos(c) = findloc(ir, model%c_dof(c), 1)
      end do
      nz = 2 * nr + 3
      allocate(lad(0:2**model%n_contacts - 1), z(nz))
      z(1:nr) = real(u0(ir), xp);  z(nr + 1:2 * nr) = real(v0(ir), xp)
      z(2 * nr + 1) = 0.0_xp;  z(2 * nr + 2) = 1.0_xp;  z(2 * nr + 3) = 1.0_xp
      mask = activity(model, cpos, nr, z)
      switches = 0
      unit_step = 2_int64**n_levels
      last = int(periods, int64) * int(steps_per_period, int64) * unit_step
      now = 0
      do while (now < last)
         ! the largest ladder step that fits
         left = last - now
         j = 0
         do while (unit_step / 2_int64**j > left)
            j = j + 1
         end do
         call build(model, cpos, kr, mr, q, mask, steps_per_period, lad(mask))
         zt = step(lad(mask), j, z)
         new = activity(model, cpos, nr, zt)
         if (new == mask) then
            z = zt;  now = now + unit_step / 2_int64**j
            cycle
         end if
         ! bisect: advance by halves that keep the activity, to one unit before the switch
         do jj = j + 1, n_levels
            zt = step(lad(mask), jj, z)
            if (activity(model, cpos, nr, zt) == mask) then
               z = zt;  now = now + unit_step / 2_int64**jj
            end if
         end do
         z = step(lad(mask), n_levels, z);  now = now + 1
         new = activity(model, cpos, nr, z)
         if (new /= mask) switches = switches + 1
         mask = new
      end do
      u = 0.0_dp;  v = 0.0_dp
      u(ir) = real(z(1:nr), dp);  v(ir) = real(z(nr + 1:2 * nr), dp)
      if (size(is) > 0) then
         u(is) = real(matmul(t, z(1:nr)), dp)
         v(is) = real(matmul(t, z(nr + 1:2 * nr)), dp)
      end if
   end subroutine expm_run

   !> Active contacts of a state: d > 0 and (with a damper) k d + c d' > 0.
   integer function activity(model, cpos, nr, z) result(mask)
      type(model_t), intent(in) :: model
      integer, intent(in) :: cpos(:), nr
      real(xp), intent(in) :: z(:)
      real(xp) :: d, dd
      integer :: c
      mask = 0
      do c = 1, model%n_contacts
         d = model%c_sign(c) * z(cpos(c)) - model%c_gap(c)
         dd = model%c_sign(c) * z(nr + cpos(c))
         if (d > 0.0_xp .and. model%c_k(c) * d + model%c_c(c) * dd > 0.0_xp) &
            mask = ibset(mask, c - 1)
      end do
   end function activity

   !> z advanced by h0 / 2^j in the configuration of the ladder.
   function step(lad, j, z) result(zn)
      type(ladder_t), intent(in) :: lad
      integer, intent(in) :: j
      real(xp), intent(in) :: z(:)
      real(xp) :: zn(size(z))
      zn = lad%d * matmul(lad%e(:, :, j), z / lad%d)
   end function step

   !> Static condensation in extended precision: K_r = K_rr + K_rs T, T = -K_ss^-1 K_sr;
   !> M_r; load shape q_r = q_r + T' q_s.
   subroutine condense(model, ir, is, kr, mr, t, q)
      type(model_t), intent(in) :: model
      integer, intent(in) :: ir(:), is(:)
      real(xp), allocatable, intent(out) :: kr(:, :), mr(:, :), t(:, :), q(:)
      real(xp), allocatable :: kss(:, :)
      kr = real(model%sys%k(ir, ir), xp)
      mr = real(model%sys%m(ir, ir), xp)
      q = real(model%q(ir), xp)
      allocate(t(size(is), size(ir)))
      if (size(is) == 0) return
      kss = real(model%sys%k(is, is), xp)
      t = -real(model%sys%k(is, ir), xp)
      call solve_xp(kss, t)
      kr = kr + matmul(real(model%sys%k(ir, is), xp), t)
      q = q + matmul(transpose(t), real(model%q(is), xp))
   end subroutine condense

   !> The ladder of configuration `mask` (once).
   subroutine build(model, cpos, kr, mr, q, mask, steps_per_period, lad)
      type(model_t), intent(in) :: model
      integer, intent(in) :: cpos(:)
      real(xp), intent(in) :: kr(:, :), mr(:, :), q(:)
      integer, intent(in) :: mask, steps_per_period
      type(ladder_t), intent(inout) :: lad
      real(xp), allocatable :: ke(:, :), ce(:, :), a(:, :), mi(:, :), f(:, :), x(:, :), &
         term(:, :), e(:, :)
      real(xp) :: h0, om, nrm
      integer :: nr, nz, c, i, j, j0, k
      if (lad%built) return
      nr = size(kr, 1);  nz = 2 * nr + 3
      ke = kr;  ce = real(model%beta, xp) * mr + real(model%gamma, xp) * kr
      allocate(f(nr, 2), source=0.0_xp)
      om = real(model%omega, xp)
      f(:, 1) = real(model%half_amplitude, xp) * om**2 * q
      do c = 1, model%n_contacts
         if (.not. btest(mask, c - 1)) cycle
         i = cpos(c)
         ke(i, i) = ke(i, i) + model%c_k(c)
         ce(i, i) = ce(i, i) + model%c_c(c)
         f(i, 2) = f(i, 2) + real(model%c_sign(c), xp) * model%c_k(c) * model%c_gap(c)
      end do
      ! M^-1 [K_e, C_e, f]
      allocate(mi(nr, 2 * nr + 2))
      mi(:, 1:nr) = ke;  mi(:, nr + 1:2 * nr) = ce;  mi(:, 2 * nr + 1:) = f
      call solve_xp(mr, mi)
      allocate(a(nz, nz), source=0.0_xp)
      do i = 1, nr
         a(i, nr + i) = 1.0_xp
      end do
      a(nr + 1:2 * nr, 1:nr) = -mi(:, 1:nr)
      a(nr + 1:2 * nr, nr + 1:2 * nr) = -mi(:, nr + 1:2 * nr)
      a(nr + 1:2 * nr, 2 * nr + 1) = mi(:, 2 * nr + 1)
      a(nr + 1:2 * nr, 2 * nr + 3) = mi(:, 2 * nr + 2)
      a(2 * nr + 1, 2 * nr + 2) = om
      a(2 * nr + 2, 2 * nr + 1) = -om
      call balance(a, lad%d)
      h0 = 2.0_xp * acos(-1.0_xp) / om / real(steps_per_period, xp)
      nrm = maxval(sum(abs(a), dim=1))
      j0 = 0
      do while (nrm * h0 / 2.0_xp**j0 > 0.5_xp)
         j0 = j0 + 1
      end do
      allocate(lad%e(nz, nz, 0:n_levels))
      do j = max(j0, 0), n_levels
         x = a * (h0 / 2.0_xp**j)
         allocate(e(nz, nz), term(nz, nz), source=0.0_xp)
         do i = 1, nz
            e(i, i) = 1.0_xp;  term(i, i) = 1.0_xp
         end do
         do k = 1, n_taylor
            term = matmul(term, x) / real(k, xp)
            e = e + term
         end do
         lad%e(:, :, j) = e
         deallocate(e, term)
      end do
      do j = j0 - 1, 0, -1
         lad%e(:, :, j) = matmul(lad%e(:, :, j + 1), lad%e(:, :, j + 1))
      end do
      lad%built = .true.
   end subroutine build

   !> Diagonal balancing by powers of two (Parlett-Reinsch): a <- D^-1 a D.
   subroutine balance(a, d)
      real(xp), intent(inout) :: a(:, :)
      real(xp), allocatable, intent(out) :: d(:)
      real(xp) :: c, r, f, g, s
      integer :: i, n, it
      logical :: done
      n = size(a, 1)
      allocate(d(n), source=1.0_xp)
      do it = 1, 100
         done = .true.
         do i = 1, n
            c = sum(abs(a(:, i))) - abs(a(i, i))
            r = sum(abs(a(i, :))) - abs(a(i, i))
            if (c == 0.0_xp .or. r == 0.0_xp) cycle
            g = r / 2.0_xp;  f = 1.0_xp;  s = c + r
            do while (c < g)
               f = f * 2.0_xp;  c = c * 4.0_xp
            end do
            g = r * 2.0_xp
            do while (c >= g)
               f = f / 2.0_xp;  c = c / 4.0_xp
            end do
            if ((c + r) / f < 0.95_xp * s) then
               done = .false.
               d(i) = d(i) * f
               a(i, :) = a(i, :) / f
               a(:, i) = a(:, i) * f
            end if
         end do
         if (done) exit
      end do
   end subroutine balance

   !> Solve A X = B in place (Gaussian elimination with partial pivoting, extended precision).
   subroutine solve_xp(a, b)
      real(xp), intent(in) :: a(:, :)
      real(xp), intent(inout) :: b(:, :)
      real(xp) :: w(size(a, 1), size(a, 2)), row(size(a, 2)), rb(size(b, 2)), f
      integer :: n, k, p, i
      n = size(a, 1)
      w = a
      do k = 1, n
         p = k - 1 + maxloc(abs(w(k:, k)), 1)
         if (p /= k) then
            row = w(k, :);  w(k, :) = w(p, :);  w(p, :) = row
            rb = b(k, :);  b(k, :) = b(p, :);  b(p, :) = rb
         end if
         do i = k + 1, n
            f = w(i, k) / w(k, k)
            w(i, k:) = w(i, k:) - f * w(k, k:)
            b(i, :) = b(i, :) - f * b(k, :)
         end do
      end do
      do k = n, 1, -1
         b(k, :) = (b(k, :) - matmul(w(k, k + 1:), b(k + 1:, :))) / w(k, k)
      end do
   end subroutine solve_xp
end module gapbeam_expm_reference
