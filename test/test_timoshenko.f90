!> Timoshenko beams: the element (energy, mass, limits), the static tip deflection, the natural
!> frequencies of a thick pinned-pinned beam (the classical frequency equation) and of a thick
!> cantilever (the exact solution of the Timoshenko equations) with their order under mesh
!> refinement, and the slender limit (Euler-Bernoulli, no shear locking).
program test_timoshenko
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_description, only: structure_t, beam_t, root_t, beam_shear_stiffness, beam_ei
   use gapbeam_model, only: system_t
   use gapbeam_assembly, only: assemble
   use gapbeam_results, only: modes_t
   use gapbeam_eigen, only: solve_modes
   use gapbeam_beam_element, only: beam_stiffness, beam_consistent_mass, timoshenko_phi, &
      timoshenko_stiffness, timoshenko_shapes, timoshenko_consistent_mass, timoshenko_lumped_mass
   use gapbeam_lapack, only: dpotrf, dpotrs
   use gapbeam_model, only: model_t
   use gapbeam_description, only: stop_t, damping_t, forcing_t
   use gapbeam_model_builder, only: build_full_model
   use gapbeam_reduction, only: reduce_model
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_test_runs, only: expect_refused
   implicit none
   ! a thick steel beam: L/h = 5
   real(dp), parameter :: e_mod = 200.0e9_dp, g_mod = e_mod / 2.6_dp, rho = 7850.0_dp
   real(dp), parameter :: len_ = 1.0_dp, b = 0.1_dp, h = 0.2_dp, k_shear = 5.0_dp / 6.0_dp
   type(structure_t) :: st
   character(len=*), parameter :: ref_deck = 'inputs/moon_shaw_10p5hz.nml'

   call element_checks()
   st = thick_beam(4, 'consistent')
   call static_tip_deflection(st)
   call pinned_pinned(st)
   call cantilever(st)
   call slender_limit(st)
   call reduced_model(st)
   call bad_input()
   call finish('test_timoshenko')

contains

   function thick_beam(n_elem, mass) result(s)
      integer, intent(in) :: n_elem
      character(len=*), intent(in) :: mass
      type(structure_t) :: s
      s%beam = beam_t(length=len_, n_elem=n_elem, youngs_modulus=e_mod, density=rho, width=b, &
                      thickness=h, mass_matrix=mass, theory='timoshenko', shear_modulus=g_mod)
      s%root = root_t(condition='clamped')
      allocate(s%springs(0), s%masses(0))
   end function thick_beam

   !> The element against its definition: K = int EI p'p' + kGA (n' - p)(n' - p) dx, the
   !> consistent mass against the closed form of Friedman and Kosmatka, phi = 0 against the
   !> Euler-Bernoulli matrices, rigid motions, the lumped masses.
   subroutine element_checks()
      real(dp), parameter :: ei = 2.5_dp, kga = 7.0_dp, le = 0.3_dp, ra = 1.7_dp, ri = 0.02_dp
      real(dp) :: phi, ke(4, 4), kq(4, 4), me(4, 4), mf(4, 4), md(4), n(4), p(4), d(4)
      real(dp) :: dn(4), x, wq, eps, rot(4)
      integer :: q, i, j
      phi = timoshenko_phi(ei, kga, le)
      ke = timoshenko_stiffness(ei, phi, le)
      ! the energy by Simpson's rule, exact here: the integrand is at most quadratic
      kq = 0.0_dp
      eps = 1.0e-6_dp
      do q = 0, 200
         x = real(q, dp) / 200.0_dp
         wq = merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(q, 2) == 1), q == 0 .or. q == 200) &
              * le / (3.0_dp * 200.0_dp)
         call timoshenko_shapes(le, phi, x, n, p, d)
         dn = shape_slope(le, phi, x)
         do j = 1, 4
            do i = 1, 4
               kq(i, j) = kq(i, j) + wq * (ei * d(i) * d(j) + kga * (dn(i) - p(i)) * (dn(j) - p(j)))
            end do
         end do
      end do
      call check_le('Timoshenko stiffness = int EI psi''^2 + kGA (w'' - psi)^2 of its shapes', &
         maxval(abs(ke - kq)), 1.0e-10_dp * maxval(abs(ke)))
      call check_le('Timoshenko stiffness symmetric', maxval(abs(ke - transpose(ke))), 0.0_dp)
      rot = [0.0_dp, 1.0_dp, le, 1.0_dp]
      call check_le('Timoshenko: rigid motions store no energy', maxval(abs(matmul(ke, &
         [1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp]))) + maxval(abs(matmul(ke, rot))), &
         1.0e-12_dp * maxval(abs(ke)))
      call check_le('Timoshenko stiffness at phi = 0 is the Euler-Bernoulli matrix', &
         maxval(abs(timoshenko_stiffness(ei, 0.0_dp, le) - beam_stiffness(ei, le))), &
         1.0e-14_dp * maxval(abs(beam_stiffness(ei, le))))
      me = timoshenko_consistent_mass(ra, ri, phi, le)
      mf = friedman_kosmatka_mass(ra, ri, phi, le)
      call check_le('Timoshenko consistent mass = the closed form of Friedman and Kosmatka', &
         maxval(abs(me - mf)), 1.0e-13_dp * maxval(abs(mf)))
      me = timoshenko_consistent_mass(ra, 0.0_dp, 0.0_dp, le)
      call check_le('Timoshenko consistent mass at phi = 0, rho I = 0 is the Hermite mass', &
         maxval(abs(me - beam_consistent_mass(ra, le))), 1.0e-14_dp * ra * le)
      me = timoshenko_consistent_mass(ra, ri, phi, le)
      call check_close('Timoshenko consistent mass adds up to rho A le', dot_product( &
         [1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp], matmul(me, [1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp])), &
         ra * le, rtol=1.0e-13_dp)
      ! a uniform section rotation psi = 1 with w = 0 is not rigid, but its rotary inertia is
      ! rho I le plus the translation's (the shapes of psi at w = 0 carry some w)
      md = timoshenko_lumped_mass(ra, ri, le, 'none')
      call check('lumped Timoshenko mass with rule none: rho A le/2, rho I le/2', &
         abs(md(1) - 0.5_dp * ra * le) <= 1.0e-15_dp .and. abs(md(2) - 0.5_dp * ri * le) &
         <= 1.0e-15_dp .and. md(3) == md(1) .and. md(4) == md(2))
      md = timoshenko_lumped_mass(ra, ri, le, 'half_element')
      call check_close('lumped Timoshenko mass, half_element: rho I le/2 + m le^2/24', md(2), &
         0.5_dp * ri * le + ra * le**3 / 24.0_dp, rtol=1.0e-14_dp)
   end subroutine element_checks

   !> dw/dx of the shapes at xi (finite difference of the exact cubic is avoided: the analytic
   !> derivative).
   function shape_slope(le, phi, xi) result(dn)
      real(dp), intent(in) :: le, phi, xi
      real(dp) :: dn(4), s
      s = 1.0_dp / (1.0_dp + phi)
      dn = s * [(-6 * xi + 6 * xi**2 - phi) / le, 1 - 4 * xi + 3 * xi**2 + 0.5_dp * phi &
                * (1 - 2 * xi), (6 * xi - 6 * xi**2 + phi) / le, -2 * xi + 3 * xi**2 &
                - 0.5_dp * phi * (1 - 2 * xi)]
   end function shape_slope

   !> The consistent mass of the interdependent element as published (Friedman and Kosmatka
   !> 1993, translational and rotary parts), typed from the paper, not from our shapes.
   function friedman_kosmatka_mass(ra, ri, phi, l) result(m)
      real(dp), intent(in) :: ra, ri, phi, l
      real(dp) :: m(4, 4), t(4, 4), r(4, 4), c
      c = ra * l / (1 + phi)**2
      t(1, :) = [13.0_dp / 35 + 7 * phi / 10 + phi**2 / 3, (11.0_dp / 210 + 11 * phi / 120 &
         + phi**2 / 24) * l, 9.0_dp / 70 + 3 * phi / 10 + phi**2 / 6, -(13.0_dp / 420 &
         + 3 * phi / 40 + phi**2 / 24) * l]
      t(2, :) = [t(1, 2), (1.0_dp / 105 + phi / 60 + phi**2 / 120) * l**2, (13.0_dp / 420 &
         + 3 * phi / 40 + phi**2 / 24) * l, -(1.0_dp / 140 + phi / 60 + phi**2 / 120) * l**2]
      t(3, :) = [t(1, 3), t(2, 3), t(1, 1), -t(1, 2)]
      t(4, :) = [t(1, 4), t(2, 4), t(3, 4), t(2, 2)]
      r(1, :) = [6.0_dp / 5, (1.0_dp / 10 - phi / 2) * l, -6.0_dp / 5, (1.0_dp / 10 - phi / 2) * l]
      r(2, :) = [r(1, 2), (2.0_dp / 15 + phi / 6 + phi**2 / 3) * l**2, (-1.0_dp / 10 + phi / 2) &
         * l, (-1.0_dp / 30 - phi / 6 + phi**2 / 6) * l**2]
      r(3, :) = [r(1, 3), r(2, 3), 6.0_dp / 5, (-1.0_dp / 10 + phi / 2) * l]
      r(4, :) = [r(1, 4), r(2, 4), r(3, 4), r(2, 2)]
      m = c * t + ri / ((1 + phi)**2 * l) * r
   end function friedman_kosmatka_mass

   !> A cantilever with a tip force: P L^3/(3 EI) + P L/(k G A) at any mesh (the element is
   !> exact for nodal loads).
   subroutine static_tip_deflection(s0)
      type(structure_t), intent(in) :: s0
      type(structure_t) :: s
      type(system_t) :: sys
      real(dp), allocatable :: a(:, :), f(:, :)
      real(dp) :: exact, ei, kga
      integer :: ne, info, n
      integer, parameter :: meshes(3) = [1, 3, 10]
      s = s0
      ei = beam_ei(s%beam);  kga = beam_shear_stiffness(s%beam)
      exact = len_**3 / (3 * ei) + len_ / kga
      do ne = 1, size(meshes)
         s%beam%n_elem = meshes(ne)
         call assemble(s, sys)
         n = sys%n_dof
         a = sys%k
         allocate(f(n, 1), source=0.0_dp)
         f(sys%tip_dof, 1) = 1.0_dp
         call dpotrf('U', n, a, n, info)
         call dpotrs('U', n, 1, a, n, f, n, info)
         call check_close('Timoshenko cantilever tip deflection P L^3/(3EI) + P L/(kGA), ' &
            // str(meshes(ne)) // ' element(s)', f(sys%tip_dof, 1), exact, rtol=1.0e-12_dp)
         ! the bending moment P L at the root: strain c psi'(0) = (h/2) P L / EI, exact
         call check_close('Timoshenko root strain (h/2) P L/EI from psi''(0), ' &
            // str(meshes(ne)) // ' element(s)', dot_product(sys%strain_row, f(:, 1)), &
            0.5_dp * h * len_ / ei, rtol=1.0e-12_dp)
         deallocate(f)
      end do
      call note('static tip deflection of the L/h = 5 cantilever: shear adds ' &
         // str(100 * (len_ / kga) / (len_**3 / (3 * ei))) // ' % to P L^3/(3EI)')
   end subroutine static_tip_deflection

   !> Exact frequencies of the simply supported Timoshenko beam, mode n, bending branch [Hz]:
   !> (kGA k^2 - rho A w^2)(EI k^2 + kGA - rho I w^2) = (kGA k)^2, k = n pi / L.
   real(dp) function pinned_exact(bm, n) result(f)
      type(beam_t), intent(in) :: bm
      integer, intent(in) :: n
      real(dp) :: kn, ei, kga, ra, ri, qa, qb, qc
      call section(bm, ei, kga, ra, ri)
      kn = n * pi / bm%length
      qa = ra * ri
      qb = -(ra * (ei * kn**2 + kga) + ri * kga * kn**2)
      qc = kga * kn**2 * ei * kn**2
      ! the smaller root of qa x^2 + qb x + qc, without cancellation
      f = sqrt(2 * qc / (-qb + sqrt(qb**2 - 4 * qa * qc))) / (2 * pi)
   end function pinned_exact

   subroutine section(bm, ei, kga, ra, ri)
      type(beam_t), intent(in) :: bm
      real(dp), intent(out) :: ei, kga, ra, ri
      ei = beam_ei(bm);  kga = beam_shear_stiffness(bm)
      ra = bm%density * bm%width * bm%thickness
      ri = bm%density * bm%width * bm%thickness**3 / 12
   end subroutine section

   !> Frequencies of a structure [Hz].
   function frequencies(s) result(f)
      type(structure_t), intent(in) :: s
      real(dp), allocatable :: f(:)
      type(system_t) :: sys
      type(modes_t) :: modes
      type(error_t), allocatable :: err
      call assemble(s, sys)
      call solve_modes(sys, modes, err)
      if (allocated(err)) error stop 'test_timoshenko: solve_modes failed'
      f = modes%frequency_hz
   end function frequencies

   !> The thick pinned-pinned beam against the frequency equation: errors at 4 ... 32
   !> elements, the order, consistent and lumped mass.
   subroutine pinned_pinned(s0)
      type(structure_t), intent(in) :: s0
      type(structure_t) :: s
      real(dp) :: fx(4), e(4, 4), order
      real(dp), allocatable :: f(:)
      integer :: i, m, im
      character(len=10), parameter :: masses(2) = [character(len=10) :: 'consistent', 'lumped']
      s = s0
      s%root = root_t(condition='pinned');  s%tip = root_t(condition='pinned')
      do i = 1, 4
         fx(i) = pinned_exact(s%beam, i)
      end do
      call note('pinned-pinned L/h = 5, exact Timoshenko f1..f4 [Hz]: ' // str(fx(1)) // ' ' &
         // str(fx(2)) // ' ' // str(fx(3)) // ' ' // str(fx(4)) // ' (Euler-Bernoulli f1 ' &
         // str(pi / 2 * sqrt(beam_ei(s%beam) / (rho * b * h)) / len_**2) // ')')
      do im = 1, 2
         s%beam%mass_matrix = masses(im)
         s%beam%rotary_inertia = 'none'
         do m = 1, 4
            s%beam%n_elem = 4 * 2**(m - 1)
            f = frequencies(s)
            e(:, m) = abs(f(1:4) - fx) / fx
            call note('pinned-pinned, ' // trim(masses(im)) // ', ' // str(s%beam%n_elem) &
               // ' elements: relative errors of f1..f4 ' // str(e(1, m)) // ' ' // str(e(2, m)) &
               // ' ' // str(e(3, m)) // ' ' // str(e(4, m)))
         end do
         do i = 1, 2
            order = log(e(i, 3) / e(i, 4)) / log(2.0_dp)
            call note('pinned-pinned, ' // trim(masses(im)) // ': order of f' // str(i) &
               // ' (16 -> 32 elements) ' // str(order))
            ! order 2 with either mass: the shear strain is constant on each element, so its
            ! energy converges at O(h^2) (the bending part at O(h^4), as Euler-Bernoulli's)
            call check_close('Timoshenko pinned-pinned f' // str(i) // ', ' // trim(masses(im)) &
               // ' mass: order 2', order, 2.0_dp, atol=0.2_dp)
         end do
         call check_le('Timoshenko pinned-pinned f1 at 32 elements (' // trim(masses(im)) &
            // ') within 1e-4 of the frequency equation', e(1, 4), 1.0e-4_dp)
      end do
   end subroutine pinned_pinned

   !> Determinant of the cantilever's boundary conditions (clamped at 0: w = psi = 0; free at L:
   !> EI psi' = 0, kGA (w' - psi) = 0) on the exact solution of the Timoshenko equations at
   !> angular frequency w below the cut-off sqrt(kGA/(rho I)).
   real(dp) function cantilever_determinant(bm, w) result(det)
      type(beam_t), intent(in) :: bm
      real(dp), intent(in) :: w
      real(dp) :: ei, kga, ra, ri, qa, qb, qc, disc, s1, s2, al, be, g, hh, l, m(4, 4)
      call section(bm, ei, kga, ra, ri)
      l = bm%length
      ! s^2 of w = exp(s x): (kGA s^2 + rho A w^2)(EI s^2 - kGA + rho I w^2) + kGA^2 s^2 = 0
      qa = kga * ei
      qb = kga * (ri * w**2) + ra * w**2 * ei
      qc = ra * w**2 * (-kga + ri * w**2)
      disc = sqrt(qb**2 - 4 * qa * qc)
      s1 = 2 * qc / (-qb - disc)          ! > 0
      s2 = (-qb - disc) / (2 * qa)        ! < 0
      al = sqrt(s1);  be = sqrt(-s2)
      g = (kga * al**2 + ra * w**2) / (kga * al)     ! psi / w for cosh, sinh
      hh = (ra * w**2 - kga * be**2) / (kga * be)    ! psi / w for cos, sin
      ! columns: w = cosh, sinh, cos, sin; psi = g sinh, g cosh, hh sin, -hh cos
      m(1, :) = [1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp]
      m(2, :) = [0.0_dp, g, 0.0_dp, -hh]
      m(3, :) = [g * al * cosh(al * l), g * al * sinh(al * l), hh * be * cos(be * l), &
                 hh * be * sin(be * l)]
      m(4, :) = [al * sinh(al * l) - g * sinh(al * l), al * cosh(al * l) - g * cosh(al * l), &
                 -be * sin(be * l) - hh * sin(be * l), be * cos(be * l) + hh * cos(be * l)]
      det = determinant4(m)
   end function cantilever_determinant

   real(dp) function determinant4(a) result(d)
      real(dp), intent(in) :: a(4, 4)
      real(dp) :: u(4, 4), t
      integer :: i, j, p
      u = a;  d = 1.0_dp
      do j = 1, 4
         p = j - 1 + maxloc(abs(u(j:, j)), dim=1)
         if (p /= j) then
            u([j, p], :) = u([p, j], :);  d = -d
         end if
         d = d * u(j, j)
         if (u(j, j) == 0.0_dp) return
         do i = j + 1, 4
            t = u(i, j) / u(j, j)
            u(i, :) = u(i, :) - t * u(j, :)
         end do
      end do
   end function determinant4

   !> The first n roots of the cantilever determinant [Hz] (scan, then bisection).
   function cantilever_exact(bm, n) result(f)
      type(beam_t), intent(in) :: bm
      integer, intent(in) :: n
      real(dp) :: f(n), wa, wb, da, db, wm, dm, ei, kga, ra, ri, wc
      integer :: k, it
      call section(bm, ei, kga, ra, ri)
      wc = sqrt(kga / ri)
      k = 0
      wa = 1.0e-3_dp * wc;  da = cantilever_determinant(bm, wa)
      do while (k < n)
         wb = wa + 1.0e-4_dp * wc
         if (wb >= wc) error stop 'test_timoshenko: fewer cantilever roots below the cut-off'
         db = cantilever_determinant(bm, wb)
         if (sign(1.0_dp, da) /= sign(1.0_dp, db)) then
            do it = 1, 200
               wm = 0.5_dp * (wa + wb);  dm = cantilever_determinant(bm, wm)
               if (sign(1.0_dp, dm) == sign(1.0_dp, da)) then
                  wa = wm;  da = dm
               else
                  wb = wm
               end if
               if (wb - wa <= 4 * epsilon(1.0_dp) * wb) exit
            end do
            k = k + 1
            f(k) = 0.5_dp * (wa + wb) / (2 * pi)
            wa = wb;  da = cantilever_determinant(bm, wa)
         else
            wa = wb;  da = db
         end if
      end do
   end function cantilever_exact

   !> The thick cantilever against the exact solution: errors and order, consistent mass.
   subroutine cantilever(s0)
      type(structure_t), intent(in) :: s0
      type(structure_t) :: s
      real(dp) :: fx(3), e(3, 4), order
      real(dp), allocatable :: f(:)
      integer :: m, i
      s = s0
      s%beam%mass_matrix = 'consistent'
      fx = cantilever_exact(s%beam, 3)
      call note('cantilever L/h = 5, exact Timoshenko f1..f3 [Hz]: ' // str(fx(1)) // ' ' &
         // str(fx(2)) // ' ' // str(fx(3)))
      do m = 1, 4
         s%beam%n_elem = 4 * 2**(m - 1)
         f = frequencies(s)
         e(:, m) = abs(f(1:3) - fx) / fx
         call note('cantilever, consistent, ' // str(s%beam%n_elem) // ' elements: relative ' &
            // 'errors of f1..f3 ' // str(e(1, m)) // ' ' // str(e(2, m)) // ' ' // str(e(3, m)))
      end do
      do i = 1, 2
         order = log(e(i, 3) / e(i, 4)) / log(2.0_dp)
         call note('cantilever, consistent: order of f' // str(i) // ' (16 -> 32 elements) ' &
            // str(order))
         call check_close('Timoshenko cantilever f' // str(i) // ', consistent mass: order 2', &
            order, 2.0_dp, atol=0.2_dp)
      end do
      call check_le('Timoshenko cantilever f1 at 32 elements within 1e-5 of the exact ' &
         // 'solution', e(1, 4), 1.0e-5_dp)
   end subroutine cantilever

   !> Slender beams: the Timoshenko model tends to the Euler-Bernoulli one, with the classical
   !> first-order shear and rotary-inertia correction
   !> f_T / f_EB = 1 - (1/2) (n pi r / L)^2 (1 + E/(k G)), r^2 = I/A, down to L/h = 1e4 with 16
   !> elements (a locking element would be far too stiff there).
   subroutine slender_limit(s0)
      type(structure_t), intent(in) :: s0
      type(structure_t) :: s, se
      real(dp) :: ft(1), fe(1), corr, r2, ratio
      real(dp), allocatable :: f(:)
      integer :: j
      real(dp), parameter :: slender(3) = [20.0_dp, 100.0_dp, 1.0e4_dp]
      do j = 1, 3
         s = s0
         s%root = root_t(condition='pinned');  s%tip = root_t(condition='pinned')
         s%beam%mass_matrix = 'consistent'
         s%beam%n_elem = 16
         s%beam%thickness = len_ / slender(j)
         se = s
         se%beam%theory = 'euler_bernoulli'
         f = frequencies(s);  ft = f(1)
         f = frequencies(se);  fe = f(1)
         r2 = s%beam%thickness**2 / 12
         corr = 0.5_dp * (pi**2 * r2 / len_**2) * (1 + e_mod / (k_shear * g_mod))
         ratio = (1 - ft(1) / fe(1)) / corr
         call note('slender limit L/h = ' // str(slender(j)) // ': 1 - f_T/f_EB = ' &
            // str(1 - ft(1) / fe(1)) // ', first-order correction ' // str(corr))
         if (j > 1) call check_close('L/h = ' // str(slender(j)) // ', 16 elements: 1 - f_T/f_EB ' &
            // '= (1/2)(pi r/L)^2 (1 + E/(kG)) to 1 % (slender limit, no shear locking)', ratio, &
            1.0_dp, rtol=1.0e-2_dp)
      end do
   end subroutine slender_limit

   !> The reduction projects the Timoshenko K and M: its lowest frequencies are the full
   !> model's (4 modes and the static correction at a stop at the tip, far open).
   subroutine reduced_model(s0)
      type(structure_t), intent(in) :: s0
      integer :: info
      real(dp), allocatable :: a(:, :), f(:, :)
      type(structure_t) :: s
      type(model_t) :: full, red
      type(stop_t) :: stops(1)
      type(modes_t) :: mf, mr
      type(error_t), allocatable :: err
      real(dp), allocatable :: basis(:, :)
      s = s0
      s%beam%n_elem = 16
      stops(1) = stop_t(node=17, gap=1.0_dp, stiffness=1.0e6_dp)
      call build_full_model(s, stops, damping_t(), forcing_t(), full, err)
      if (.not. allocated(err)) call reduce_model(full, 4, .true., red, basis, err)
      if (.not. allocated(err)) call solve_modes(full%sys, mf, err)
      if (.not. allocated(err)) call solve_modes(red%sys, mr, err)
      if (allocated(err)) then
         call check('Timoshenko reduced model', .false., err%message);  return
      end if
      call check_le('Timoshenko, 4 modes + static correction: f1..f4 of the full model', &
         maxval(abs(mr%frequency_hz(1:4) - mf%frequency_hz(1:4)) / mf%frequency_hz(1:4)), &
         1.0e-10_dp)
      ! a tip load: the static correction holds K^-1 e_tip, so the root strain is exact
      a = red%sys%k
      allocate(f(red%n, 1), source=0.0_dp)
      f(red%sys%tip_dof, 1) = 1.0_dp
      call dpotrf('U', red%n, a, red%n, info)
      call dpotrs('U', red%n, 1, a, red%n, f, red%n, info)
      call check_close('Timoshenko reduced model: root strain (h/2) P L/EI under a tip load', &
         dot_product(red%sys%strain_row, f(:, 1)), 0.5_dp * h * len_ / beam_ei(s%beam), &
         rtol=1.0e-10_dp)
   end subroutine reduced_model

   !> Bad &beam theory and shear values: one line naming deck, group, variable, value, rule.
   subroutine bad_input()
      call expect_refused(ref_deck, 'unknown theory refused', "&beam theory = 'timoshenk' /", &
         [character(len=60) :: 'group &beam: theory', "'timoshenk'", &
          "'euler_bernoulli', 'timoshenko'"])
      call expect_refused(ref_deck, 'Timoshenko without a shear modulus refused', &
         "&beam theory = 'timoshenko' /", [character(len=60) :: 'group &beam: shear_modulus', &
         '= 0', 'must be > 0', "theory = 'timoshenko'"])
      call expect_refused(ref_deck, 'negative shear modulus refused', &
         "&beam theory = 'timoshenko', shear_modulus = -1.0 /", [character(len=60) :: &
         'group &beam: shear_modulus', '= -1', '>= 0'])
      call expect_refused(ref_deck, 'shear coefficient above 1 refused', &
         "&beam theory = 'timoshenko', shear_modulus = 8e10, shear_coefficient = 1.5 /", &
         [character(len=60) :: 'group &beam: shear_coefficient', '= 1.5', '[0, 1]'])
      call expect_refused(ref_deck, 'general section without a shear coefficient refused', &
         "&beam theory = 'timoshenko', shear_modulus = 8e10, width = 0, thickness = 0, " &
         // 'area = 1e-6, second_moment = 1e-12, fibre_distance = 1e-3 /', &
         [character(len=60) :: 'group &beam: shear_coefficient', '= 0', 'must be > 0', &
          'general section'])
   end subroutine bad_input

end program test_timoshenko
