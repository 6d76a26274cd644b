!> Stop laws against hand values, and the exact implicit contact force of one contact.
!>
!> `contact_force` is checked against f = max(0, k d + c d') (bilinear) and f = k d^p (Hertz)
!> computed by hand, the Hertz tangent k p d^(p-1) against a central difference. The force of
!> `solve_scalar_contact` must satisfy f = law(d* - h f, v* - kappa h f): against the closed
!> form for the bilinear law, and as a residual for every law over stiffnesses from k h = 1e-6
!> to 1e8. The residual of a stiff contact is ill-conditioned (d = d* - h f cancels), so it is
!> measured against f (1 + h law'(d)), the force times the condition number of the relation;
!> the Hertz force is also checked in the well-conditioned form (f/k)^(1/p) + h f = d*.
program test_contact
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_description, only: law_bilinear, law_hertz, law_code, stop_law_words
   use gapbeam_law, only: law_slot_t, law_caps_t
   use gapbeam_laws, only: builtin_laws, law_words_of => law_words, law_index, add_law
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_error, only: error_t
   use gapbeam_transient, only: integrate
   use gapbeam_integrator, only: integrator_t, make_integrator
   use gapbeam_test_runs, only: load_deck
   use gapbeam_test_law, only: hunt_crossley_law_t
   implicit none
   real(dp), parameter :: tol = 1.0e-12_dp          ! implicit relation, relative
   real(dp), parameter :: kh_range(6) = [1.0e-6_dp, 1.0e-3_dp, 1.0_dp, 1.0e3_dp, 1.0e6_dp, &
                                         1.0e8_dp]

   call law_words()
   call bilinear_force()
   call hertz_force()
   call hertz_tangent()
   call solve_bilinear_spring()
   call solve_bilinear_damper()
   call solve_damper_held()
   call solve_hertz()
   call solve_open()
   call solve_monotone()
   call a_law_from_the_tests()
   call finish('test_contact')

contains

   !> The law of a code from the registry: its force (the test's shorthand).
   elemental real(dp) function contact_force(law, k, c, p, d, dd) result(f)
      integer, intent(in) :: law                  !! law code
      real(dp), intent(in) :: k, c, p, d, dd      !! parameters, penetration, rate
      type(law_slot_t), allocatable :: laws(:)
      laws = builtin_laws()
      f = laws(law)%law%force(k, c, p, d, dd)
   end function contact_force

   !> The law of a code from the registry: its exact condensed solve.
   real(dp) function solve_scalar_contact(law, k, c, p, d_star, v_star, h, kappa) result(f)
      integer, intent(in) :: law                  !! law code
      real(dp), intent(in) :: k, c, p             !! parameters
      real(dp), intent(in) :: d_star, v_star, h, kappa   !! see contact_law_t%solve
      type(law_slot_t), allocatable :: laws(:)
      laws = builtin_laws()
      f = laws(law)%law%solve(k, c, p, d_star, v_star, h, kappa)
   end function solve_scalar_contact

   !> law_code maps the deck words to the law codes: the positions in the registry.
   subroutine law_words()
      type(law_slot_t), allocatable :: laws(:)
      type(law_caps_t) :: cb, ch
      laws = builtin_laws()
      cb = laws(law_bilinear)%law%caps();  ch = laws(law_hertz)%law%caps()
      call check("the registry's law law_bilinear is 'bilinear', law_hertz 'hertz'", &
         cb%name == 'bilinear' .and. ch%name == 'hertz')
      call check('stop_law_words (the deck reader''s list) = the registry''s names: ' &
         // law_words_of(), stop_law_words == law_words_of())
      call check('bilinear caps: piecewise linear, damper, rings; Hertz: exponent in [1, 10], ' &
         // 'no damper, not piecewise linear', cb%piecewise_linear .and. cb%uses_damping .and. &
         cb%rings .and. .not. ch%piecewise_linear .and. .not. ch%uses_damping .and. &
         ch%uses_exponent .and. ch%exponent_min == 1.0_dp .and. ch%exponent_max == 10.0_dp)
      call check("law_index('nonesuch') = 0", law_index('nonesuch') == 0)
      call check("law_code('bilinear') = law_bilinear", law_code('bilinear') == law_bilinear)
      call check("law_code('hertz') = law_hertz", law_code('hertz') == law_hertz)
      call check("law_code('Hertz') = 0 (words are lower case)", law_code('Hertz') == 0)
      call check('law codes differ and are non-zero', law_bilinear /= law_hertz &
         .and. law_bilinear /= 0 .and. law_hertz /= 0)
   end subroutine law_words

   !> Bilinear: k d + c d' in contact, zero when open, never negative.
   subroutine bilinear_force()
      real(dp), parameter :: k = 100.0_dp, c = 2.0_dp
      real(dp) :: f(3)
      call check_close('bilinear, spring only: k d = 100 x 0.01 = 1', &
         contact_force(law_bilinear, k, 0.0_dp, 1.5_dp, 0.01_dp, 0.3_dp), 1.0_dp, rtol=1.0e-14_dp)
      call check_close('bilinear, closing: k d + c d'' = 1 + 2 x 0.3 = 1.6', &
         contact_force(law_bilinear, k, c, 1.5_dp, 0.01_dp, 0.3_dp), 1.6_dp, rtol=1.0e-14_dp)
      call check_close('bilinear, opening slowly: 1 - 2 x 0.2 = 0.6', &
         contact_force(law_bilinear, k, c, 1.5_dp, 0.01_dp, -0.2_dp), 0.6_dp, rtol=1.0e-14_dp)
      call check('bilinear, opening fast: k d + c d'' = -0.6 gives 0 (the damper does not pull)', &
         contact_force(law_bilinear, k, c, 1.5_dp, 0.01_dp, -0.8_dp) == 0.0_dp)
      call check('bilinear at d = 0 closing: 0 (no contact without penetration)', &
         contact_force(law_bilinear, k, c, 1.5_dp, 0.0_dp, 5.0_dp) == 0.0_dp)
      call check('bilinear at d < 0: 0', &
         contact_force(law_bilinear, k, c, 1.5_dp, -0.01_dp, 5.0_dp) == 0.0_dp)
      call check('bilinear exponent is ignored', &
         contact_force(law_bilinear, k, c, 3.0_dp, 0.01_dp, 0.3_dp) &
         == contact_force(law_bilinear, k, c, 1.5_dp, 0.01_dp, 0.3_dp))
      ! elemental over penetrations
      f = contact_force(law_bilinear, k, 0.0_dp, 1.5_dp, [-1.0_dp, 0.0_dp, 0.5_dp], 0.0_dp)
      call check('contact_force is elemental: [0, 0, 50]', f(1) == 0.0_dp .and. f(2) == 0.0_dp &
         .and. abs(f(3) - 50.0_dp) <= 1.0e-14_dp * 50.0_dp)
   end subroutine bilinear_force

   !> Hertz: k d^p, p = 1.5 and 2, zero when open, no damper.
   subroutine hertz_force()
      call check_close('Hertz p = 1.5: 1e6 x (1e-4)^1.5 = 1', &
         contact_force(law_hertz, 1.0e6_dp, 0.0_dp, 1.5_dp, 1.0e-4_dp, 0.0_dp), 1.0_dp, &
         rtol=1.0e-14_dp)
      call check_close('Hertz p = 1.5: 1e6 x (4e-4)^1.5 = 8', &
         contact_force(law_hertz, 1.0e6_dp, 0.0_dp, 1.5_dp, 4.0e-4_dp, 0.0_dp), 8.0_dp, &
         rtol=1.0e-14_dp)
      call check_close('Hertz p = 2: 1e6 x (1e-3)^2 = 1', &
         contact_force(law_hertz, 1.0e6_dp, 0.0_dp, 2.0_dp, 1.0e-3_dp, 0.0_dp), 1.0_dp, &
         rtol=1.0e-14_dp)
      call check_close('Hertz p = 2: 2.5e5 x (2e-3)^2 = 1', &
         contact_force(law_hertz, 2.5e5_dp, 0.0_dp, 2.0_dp, 2.0e-3_dp, 0.0_dp), 1.0_dp, &
         rtol=1.0e-14_dp)
      call check('Hertz ignores the damper and the rate', &
         contact_force(law_hertz, 1.0e6_dp, 50.0_dp, 1.5_dp, 1.0e-4_dp, -3.0_dp) &
         == contact_force(law_hertz, 1.0e6_dp, 0.0_dp, 1.5_dp, 1.0e-4_dp, 0.0_dp))
      call check('Hertz at d = 0: 0', &
         contact_force(law_hertz, 1.0e6_dp, 0.0_dp, 1.5_dp, 0.0_dp, 1.0_dp) == 0.0_dp)
      call check('Hertz at d < 0: 0', &
         contact_force(law_hertz, 1.0e6_dp, 0.0_dp, 2.0_dp, -1.0e-3_dp, 1.0_dp) == 0.0_dp)
   end subroutine hertz_force

   !> The Hertz tangent k p d^(p-1) against a central difference of contact_force.
   subroutine hertz_tangent()
      real(dp), parameter :: k = 3.0e7_dp, ds(3) = [1.0e-6_dp, 2.5e-4_dp, 1.0e-2_dp]
      real(dp), parameter :: ps(2) = [1.5_dp, 2.0_dp]
      real(dp) :: d, p, delta, fd
      integer :: i, j
      do j = 1, size(ps)
         p = ps(j)
         do i = 1, size(ds)
            d = ds(i);  delta = 1.0e-5_dp * d
            fd = (contact_force(law_hertz, k, 0.0_dp, p, d + delta, 0.0_dp) &
                  - contact_force(law_hertz, k, 0.0_dp, p, d - delta, 0.0_dp)) / (2 * delta)
            call check_close('Hertz tangent k p d^(p-1), p = ' // str(p) // ', d = ' // str(d) &
               // ', against a central difference', fd, k * p * d**(p - 1), rtol=1.0e-6_dp)
         end do
      end do
   end subroutine hertz_tangent

   !> Residual f - law(d* - h f, v* - kappa h f) within tol times f and the conditioning.
   subroutine check_relation(name, law, k, c, p, d_star, v_star, h, kappa, f)
      character(len=*), intent(in) :: name       !! what is checked
      integer, intent(in) :: law                 !! law code
      real(dp), intent(in) :: k, c, p            !! law parameters
      real(dp), intent(in) :: d_star, v_star     !! penetration and rate at zero force
      real(dp), intent(in) :: h, kappa           !! compliance and rate factor of the step
      real(dp), intent(in) :: f                  !! force to check
      real(dp) :: d, r, cond
      d = d_star - h * f
      r = f - contact_force(law, k, c, p, d, v_star - kappa * h * f)
      if (law == law_bilinear) then
         cond = 1.0_dp + (k + c * kappa) * h
      else
         cond = 1.0_dp + p * h * f / max(d, tiny(d))
      end if
      call check_le(name // ': |f - law(d* - h f, v* - kappa h f)| / (f cond), cond = ' &
         // str(cond), abs(r) / max(f * cond, tiny(f)), tol)
   end subroutine check_relation

   !> Bilinear spring without damper: f = k d*/(1 + k h), from soft to very stiff.
   subroutine solve_bilinear_spring()
      real(dp), parameter :: h = 1.0e-4_dp, d_star = 2.0e-3_dp, v_star = 0.7_dp
      real(dp), parameter :: kappa = 2000.0_dp
      real(dp) :: k, f
      integer :: i
      do i = 1, size(kh_range)
         k = kh_range(i) / h
         f = solve_scalar_contact(law_bilinear, k, 0.0_dp, 1.5_dp, d_star, v_star, h, kappa)
         call check_close('bilinear k h = ' // str(kh_range(i)) // ': f = k d*/(1 + k h)', f, &
            k * d_star / (1.0_dp + k * h), rtol=tol)
         call check_relation('bilinear k h = ' // str(kh_range(i)), law_bilinear, k, 0.0_dp, &
            1.5_dp, d_star, v_star, h, kappa, f)
      end do
   end subroutine solve_bilinear_spring

   !> Bilinear with damper: f = (k d* + c v*)/(1 + (k + c kappa) h) while d stays > 0.
   subroutine solve_bilinear_damper()
      real(dp), parameter :: h = 1.0e-4_dp, d_star = 1.0e-3_dp, kappa = 2000.0_dp
      real(dp), parameter :: k = 1.0e4_dp, c = 5.0_dp
      real(dp), parameter :: vs(4) = [0.05_dp, 0.0_dp, -0.5_dp, 2.0_dp]
      real(dp) :: f, v_star
      integer :: i
      do i = 1, size(vs)
         v_star = vs(i)
         f = solve_scalar_contact(law_bilinear, k, c, 1.5_dp, d_star, v_star, h, kappa)
         call check_close('bilinear + damper, v* = ' // str(v_star) // ': closed form', f, &
            (k * d_star + c * v_star) / (1.0_dp + (k + c * kappa) * h), rtol=tol)
         call check_relation('bilinear + damper, v* = ' // str(v_star), law_bilinear, k, c, &
            1.5_dp, d_star, v_star, h, kappa, f)
         call check('bilinear + damper, v* = ' // str(v_star) // ': stays in contact (d > 0)', &
            d_star - h * f > 0.0_dp .and. f > 0.0_dp)
      end do
      ! stiff contact with damper
      f = solve_scalar_contact(law_bilinear, 1.0e12_dp, 1.0e3_dp, 1.5_dp, d_star, 0.1_dp, h, &
                               kappa)
      call check_relation('bilinear + damper, k h = 1e8', law_bilinear, 1.0e12_dp, 1.0e3_dp, &
         1.5_dp, d_star, 0.1_dp, h, kappa, f)
      ! separating fast: k d* + c v* < 0, the damper does not pull
      f = solve_scalar_contact(law_bilinear, k, c, 1.5_dp, d_star, -5.0_dp, h, kappa)
      call check('bilinear + damper, k d* + c v* < 0: f = 0', f == 0.0_dp)
      call check('bilinear + damper, k d* + c v* < 0: f = 0 satisfies the law', &
         contact_force(law_bilinear, k, c, 1.5_dp, d_star, -5.0_dp) == 0.0_dp)
   end subroutine solve_bilinear_damper

   !> A large damper closing fast on a small penetration: the closed branch would give d < 0,
   !> the contact sits at d = 0 with f = d*/h.
   subroutine solve_damper_held()
      real(dp), parameter :: k = 1.0e4_dp, c = 1.0e3_dp, kappa = 2000.0_dp
      real(dp), parameter :: d_star = 1.0e-6_dp, v_star = 1.0_dp
      real(dp) :: h, f, f_branch
      ! h = 2^-13: d*/h and h (d*/h) are exact, so d = 0 exactly
      h = 2.0_dp**(-13)
      f_branch = (k * d_star + c * v_star) / (1.0_dp + (k + c * kappa) * h)
      call check('damper-held case: the closed branch would give d < 0', &
         d_star - h * f_branch < 0.0_dp)
      f = solve_scalar_contact(law_bilinear, k, c, 1.5_dp, d_star, v_star, h, kappa)
      call check_close('damper-held: f = d*/h', f, d_star / h, rtol=1.0e-15_dp)
      call check('damper-held: d = d* - h f = 0 exactly (h a power of 2)', &
         d_star - h * f == 0.0_dp, 'd = ' // str(d_star - h * f))
      h = 1.0e-4_dp
      f = solve_scalar_contact(law_bilinear, k, c, 1.5_dp, d_star, v_star, h, kappa)
      call check_close('damper-held, h = 1e-4: f = d*/h', f, d_star / h, rtol=1.0e-15_dp)
      call check_le('damper-held, h = 1e-4: |d* - h f| <= 2 eps d*', abs(d_star - h * f), &
         2 * epsilon(1.0_dp) * d_star)
   end subroutine solve_damper_held

   !> Hertz p = 1.5 (and 2, and the linear limit p = 1) from soft to very stiff.
   subroutine solve_hertz()
      real(dp), parameter :: h = 1.0e-4_dp, d_star = 1.0e-3_dp, kappa = 2000.0_dp
      real(dp), parameter :: ps(2) = [1.5_dp, 2.0_dp]
      real(dp) :: k, f, p, d_of_f
      integer :: i, j
      do j = 1, size(ps)
         p = ps(j)
         do i = 1, size(kh_range)
            k = kh_range(i) / h
            f = solve_scalar_contact(law_hertz, k, 0.0_dp, p, d_star, 0.3_dp, h, kappa)
            call check('Hertz p = ' // str(p) // ', k h = ' // str(kh_range(i)) &
               // ': 0 < f < d*/h', f > 0.0_dp .and. f < d_star / h)
            call check_relation('Hertz p = ' // str(p) // ', k h = ' // str(kh_range(i)), &
               law_hertz, k, 0.0_dp, p, d_star, 0.3_dp, h, kappa, f)
            ! the same relation in a well-conditioned form: d(f) + h f = d*
            d_of_f = (f / k)**(1.0_dp / p)
            call check_close('Hertz p = ' // str(p) // ', k h = ' // str(kh_range(i)) &
               // ': (f/k)^(1/p) + h f = d*', d_of_f + h * f, d_star, rtol=tol)
         end do
      end do
      ! p = 1 is the linear spring: the closed form of the bilinear law
      k = 1.0e3_dp / h
      f = solve_scalar_contact(law_hertz, k, 0.0_dp, 1.0_dp, d_star, 0.0_dp, h, kappa)
      call check_close('Hertz p = 1 equals the linear spring k d*/(1 + k h)', f, &
         k * d_star / (1.0_dp + k * h), rtol=tol)
   end subroutine solve_hertz

   !> No force without penetration at zero contact force.
   subroutine solve_open()
      real(dp), parameter :: ds(2) = [0.0_dp, -1.0e-3_dp]
      integer :: i
      do i = 1, size(ds)
         call check('bilinear + damper, d* = ' // str(ds(i)) // ', v* > 0: f = 0', &
            solve_scalar_contact(law_bilinear, 1.0e4_dp, 1.0e3_dp, 1.5_dp, ds(i), 10.0_dp, &
            1.0e-4_dp, 2000.0_dp) == 0.0_dp)
         call check('Hertz, d* = ' // str(ds(i)) // ': f = 0', &
            solve_scalar_contact(law_hertz, 1.0e9_dp, 0.0_dp, 1.5_dp, ds(i), 10.0_dp, &
            1.0e-4_dp, 2000.0_dp) == 0.0_dp)
      end do
   end subroutine solve_open

   !> f grows strictly with d*, across the damper-held/closed transition too.
   subroutine solve_monotone()
      integer, parameter :: n = 41
      real(dp), parameter :: h = 1.0e-4_dp, kappa = 2000.0_dp
      real(dp) :: d_star(n), f_bil(n), f_held(n), f_hz(n), f_stiff(n)
      integer :: i
      do i = 1, n
         d_star(i) = 1.0e-8_dp * 10.0_dp**(0.15_dp * (i - 1))   ! 1e-8 .. 1e-2
      end do
      do i = 1, n
         f_bil(i) = solve_scalar_contact(law_bilinear, 1.0e4_dp, 5.0_dp, 1.5_dp, d_star(i), &
                                         0.05_dp, h, kappa)
         f_held(i) = solve_scalar_contact(law_bilinear, 1.0e4_dp, 1.0e3_dp, 1.5_dp, d_star(i), &
                                          1.0_dp, h, kappa)
         f_hz(i) = solve_scalar_contact(law_hertz, 1.0e7_dp, 0.0_dp, 1.5_dp, d_star(i), 0.0_dp, &
                                        h, kappa)
         f_stiff(i) = solve_scalar_contact(law_hertz, 1.0e12_dp, 0.0_dp, 2.0_dp, d_star(i), &
                                           0.0_dp, h, kappa)
      end do
      call check('bilinear + damper: f increases with d*', all(f_bil(2:) > f_bil(:n - 1)))
      call check('large damper (held, then closed branch): f increases with d*', &
         all(f_held(2:) > f_held(:n - 1)))
      call check('large damper sweep crosses from held to the closed branch', &
         abs(f_held(1) - d_star(1) / h) <= 1.0e-15_dp * f_held(1) &
         .and. d_star(n) - h * f_held(n) > 0.0_dp)
      call check('Hertz p = 1.5: f increases with d*', all(f_hz(2:) > f_hz(:n - 1)))
      call check('Hertz p = 2, k h = 1e8: f increases with d*', &
         all(f_stiff(2:) > f_stiff(:n - 1)))
      call note('Hertz p = 2, k = 1e12, h = 1e-4: f(d* = 1e-2) = ' // str(f_stiff(n)) &
         // ' N, d = ' // str(d_star(n) - h * f_stiff(n)) // ' m')
   end subroutine solve_monotone

   !> A law that is not built in (test/gapbeam_test_law: Hunt-Crossley, f = d^p (k + c d')):
   !> one `add_law` to a model and every integrator dispatches to its formulas. Newmark (its
   !> condensed `solve`) and rk45 (its `force`) converge to the same trajectory, which is not
   !> the Hertz one (no silent fallback to another law's formulas); the energy meter closes
   !> the balance with its `elastic` and `energy`; the exact integrator, 'auto' and a ring
   !> support read its capabilities; nothing in src/ or app/ names it.
   subroutine a_law_from_the_tests()
      type(deck_t) :: deck
      type(model_t) :: model, hz
      type(transient_result_t) :: rn, rr, rh
      type(solver_settings_t) :: cfg
      type(error_t), allocatable :: err
      class(integrator_t), allocatable :: integ
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: dnr, dnh, f, imbalance
      integer :: code, status
      character(len=*), parameter :: sdof = 'test/decks/sdof_impact.nml'
      call load_deck(sdof, [character(len=160) :: "&beam rotary_inertia = 'half_element' /", &
         "&stops law = 'hertz', stiffness = 3.0e4, exponent = 1.5 /", &
         "&solver method = 'newmark', tolerance = 1.0e-6, transient_periods = 0, " &
         // "record_periods = 3 /", "&output history_periods = 3, energy_balance = .true. /"], &
         deck, model, u0, v0, err)
      if (allocated(err)) then
         call check('load ' // sdof, .false., err%message);  return
      end if
      hz = model
      code = add_law(model%laws, hunt_crossley_law_t())     ! the one registry line
      model%c_law(1) = code;  model%c_c(1) = 2.5e5_dp
      call check('add_law gives the new law the next code (3)', code == 3)
      ! the condensed solve satisfies its own relation
      f = model%laws(code)%law%solve(3.0e4_dp, 2.5e5_dp, 1.5_dp, 1.0e-4_dp, 0.05_dp, 1.0e-2_dp, &
                                     2.0e3_dp)
      call check_le('Hunt-Crossley solve: |f - law(d* - h f, v* - kappa h f)| / f', &
         abs(f - model%laws(code)%law%force(3.0e4_dp, 2.5e5_dp, 1.5_dp, 1.0e-4_dp &
         - 1.0e-2_dp * f, 0.05_dp - 2.0e3_dp * 1.0e-2_dp * f)) / f, tol)
      cfg = deck%solver
      call integrate(model, cfg, deck%output, u0, v0, rn, err)
      if (allocated(err)) then
         call check('Newmark runs the test law', .false., err%message);  return
      end if
      call check('Newmark runs the test law', .true.)
      cfg%method = 'rk45';  cfg%tolerance = 1.0e-10_dp
      call integrate(model, cfg, deck%output, u0, v0, rr, err)
      if (allocated(err)) then
         call check('rk45 runs the test law', .false., err%message);  return
      end if
      call check('rk45 runs the test law', .true.)
      call integrate(hz, deck%solver, deck%output, u0, v0, rh, err)
      if (allocated(err)) return
      dnr = maxval(abs(rn%u - rr%u)) / maxval(abs(rr%u))
      dnh = maxval(abs(rn%u - rh%u)) / maxval(abs(rr%u))
      call check_le('Newmark (the law''s solve) and rk45 (its force) agree: relative ' &
         // 'difference of the final displacement', dnr, 1.0e-4_dp)
      call check('... and differ from the Hertz law''s run (' // str(dnh) // '): its damper ' &
         // 'acts', dnh > 100.0_dp * dnr .and. dnh > 1.0e-3_dp)
      imbalance = rn%input_work - rn%rayleigh_dissipation - rn%contact_damping_dissipation &
         - rn%friction_dissipation - rn%stored_energy_change
      call check('the energy meter uses its damper and energy: contact damper work ' &
         // str(rn%contact_damping_dissipation) // ' J > 0', rn%contact_damping_dissipation &
         > 0.0_dp)
      call check_le('... and the balance closes: |imbalance| / input work', &
         abs(imbalance) / max(abs(rn%input_work), tiny(1.0_dp)), 1.0e-3_dp)
      ! capabilities: the exact integrator refuses it, 'auto' does not choose it
      cfg = deck%solver;  cfg%method = 'exact'
      call make_integrator(model, cfg, integ, err)
      call check('the exact integrator refuses the test law', allocated(err))
      if (allocated(err)) call check("... naming it and why: " // err%message, &
         index(err%message, 'hunt_crossley') > 0 .and. index(err%message, 'piecewise') > 0)
      cfg%method = 'auto'
      call make_integrator(model, cfg, integ, err)
      call check("'auto' chooses Newmark for it: " // integ%reason, .not. allocated(err) &
         .and. integ%method == 'newmark' .and. index(integ%reason, 'Hunt-Crossley') > 0)
      ! a ring support's normal law must be one whose entry allows it
      call load_deck('test/decks/tube_cantilever.nml', [character(len=40) :: &
         '&output write_text = .false. /'], deck, model, &
                     u0, v0, err)
      if (allocated(err)) then
         call check('load tube_cantilever', .false., err%message);  return
      end if
      code = add_law(model%laws, hunt_crossley_law_t())
      model%r_law(1) = code
      call make_integrator(model, deck%solver, integ, err)
      call check('a ring support with the test law is refused: its entry says rings = .false.', &
         allocated(err))
      if (allocated(err)) call check('... ' // err%message, index(err%message, &
         'hunt_crossley') > 0)
      call execute_command_line("grep -rqi 'hunt_crossley\|hunt-crossley' src app", &
                                exitstat=status)
      call check('no source file in src/ or app/ names the test law (grep exit ' &
         // str(status) // ')', status == 1)
   end subroutine a_law_from_the_tests
end program test_contact
