!> Modal damping: C = beta M + gamma K + M Phi diag(2 zeta omega) Phi' M is diagonal in the
!> modes with the ratios asked (the last one repeated, the Rayleigh terms added, the two planes
!> numbered alike), and the free decay of each mode, started in its shape, has the logarithmic
!> decrement of its ratio: exact integrator (to round-off), Newmark, HHT, central difference
!> (fixed steps of T_d/2000), in the finite element model and in a reduced one.
program test_modal_damping
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_description, only: structure_t, damping_t, spring_t, dof_v, modal_ratio
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_full_model, build_model
   use gapbeam_results, only: modes_t
   use gapbeam_eigen, only: solve_modes
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_state, only: state_t
   use gapbeam_integrator, only: integrator_t, make_integrator, start_state
   use gapbeam_lapack, only: dsygv
   use gapbeam_deck_variable, only: deck_variable_t, parse_deck_variable, check_deck_variable, &
      set_deck_value, get_deck_value
   use gapbeam_test_runs, only: expect_refused
   implicit none
   real(dp), parameter :: ratios(3) = [0.01_dp, 0.03_dp, 0.002_dp]
   real(dp), parameter :: beta = 0.5_dp, gamma = 2.0e-6_dp
   type(deck_t) :: deck
   type(error_t), allocatable :: err
   character(len=200) :: ov(0)
   character(len=*), parameter :: ref_deck = 'test/decks/moon_shaw_10p5hz_half_element.nml'

   call read_deck(ref_deck, ov, deck, err)
   if (allocated(err)) then
      call check('read the reference deck', .false., err%message)
      call finish('test_modal_damping')
   end if
   deck%stops = deck%stops(1:0)
   deck%forcing%amplitude_pp = 0.0_dp
   deck%structure%beam%n_elem = 8
   call modal_matrix_checks(deck)
   call two_planes(deck)
   call free_decay(deck, 'exact', 1.0e-9_dp, 'full model')
   call free_decay(deck, 'newmark', 1.0e-5_dp, 'full model')
   call free_decay(deck, 'hht', 1.0e-5_dp, 'full model')
   call free_decay(deck, 'central_difference', 1.0e-5_dp, 'full model')
   deck%reduction%kind = 'modal'
   deck%reduction%n_modes = 4
   deck%reduction%static_correction = .true.
   call free_decay(deck, 'exact', 1.0e-9_dp, 'reduced model (4 modes + static correction)')
   call free_decay(deck, 'newmark', 1.0e-5_dp, 'reduced model (4 modes + static correction)')
   call bad_input()
   call design_variable()
   call finish('test_modal_damping')

contains

   function modal_damping(r) result(d)
      real(dp), intent(in) :: r(:)
      type(damping_t) :: d
      d%model = 'modal'
      d%modal_ratios = r
      d%mass_coefficient = beta
      d%stiffness_coefficient = gamma
   end function modal_damping

   !> Phi' C Phi = diag(2 zeta_j omega_j) with zeta_j = the ratio + the Rayleigh terms.
   subroutine modal_matrix_checks(d0)
      type(deck_t), intent(in) :: d0
      type(model_t) :: model
      type(modes_t) :: modes
      type(damping_t) :: dmp
      real(dp), allocatable :: cm(:, :)
      real(dp) :: zeta, worst, off, w
      integer :: j, n
      dmp = modal_damping(ratios)
      call build_full_model(d0%structure, d0%stops, dmp, d0%forcing, model, err)
      if (allocated(err)) then
         call check('build a model with modal damping', .false., err%message);  return
      end if
      call solve_modes(model%sys, modes, err)
      cm = matmul(transpose(modes%shapes), matmul(model%c, modes%shapes))
      n = modes%n_modes
      worst = 0.0_dp;  off = 0.0_dp
      do j = 1, n
         w = sqrt(modes%omega2(j))
         zeta = modal_ratio(dmp%modal_ratios, j) + beta / (2 * w) + gamma * w / 2
         worst = max(worst, abs(cm(j, j) / (2 * w) - zeta) / zeta)
         off = max(off, maxval(abs(cm(:j - 1, j))) / maxval(abs(cm)))
      end do
      call check_le('modal damping: Phi''C Phi diagonal entries give zeta_j + beta/(2 omega) + ' &
         // 'gamma omega/2 for every mode (last ratio repeated)', worst, 1.0e-10_dp)
      call check_le('modal damping: Phi''C Phi is diagonal', off, 1.0e-12_dp)
      call check('modal damping: C has a modal part and is symmetric', allocated(model%c_modal) &
         .and. maxval(abs(model%c - transpose(model%c))) <= 1.0e-14_dp * maxval(abs(model%c)))
      ! a single value damps every mode alike
      call build_full_model(d0%structure, d0%stops, modal_damping([0.02_dp]), d0%forcing, &
                            model, err)
      cm = matmul(transpose(modes%shapes), matmul(model%c_modal, modes%shapes))
      worst = 0.0_dp
      do j = 1, n
         worst = max(worst, abs(cm(j, j) / (2 * sqrt(modes%omega2(j))) - 0.02_dp) / 0.02_dp)
      end do
      call check_le('modal damping: one ratio damps every mode with it', worst, 1.0e-10_dp)
   end subroutine modal_matrix_checks

   !> Two planes: mode j of each plane gets ratio j, whether the planes' frequencies coincide
   !> (a symmetric beam: LAPACK may mix the pairs) or not (a spring in v only). Checked plane by
   !> plane: C has no block between the planes, and in each plane's own modes (dsygv on that
   !> plane's K and M) its block is diag(2 zeta_j omega_j), j numbered in the plane.
   subroutine two_planes(d0)
      type(deck_t), intent(in) :: d0
      type(structure_t) :: st
      type(model_t) :: model
      real(dp), allocatable :: r(:)
      integer, allocatable :: pw(:), pv(:)
      real(dp) :: worst, cross
      integer :: case
      r = ratios
      do case = 1, 2
         st = d0%structure
         st%beam%planes = 2
         if (case == 2) st%springs = [spring_t(node=3, dof=dof_v, stiffness=2.0_dp)]
         call build_full_model(st, d0%stops, modal_damping(ratios), d0%forcing, model, err)
         if (allocated(err)) then
            call check('two planes: build', .false., err%message);  return
         end if
         pw = pack(model%sys%dof_of(1:2, :), model%sys%dof_of(1:2, :) > 0)
         pv = pack(model%sys%dof_of(3:4, :), model%sys%dof_of(3:4, :) > 0)
         cross = maxval(abs(model%c_modal(pw, pv))) / maxval(abs(model%c_modal))
         worst = max(plane_error(model, pw, r), plane_error(model, pv, r))
         call note('two planes, case ' // str(case) // ': largest |zeta - ratio| ' &
            // str(worst) // ', coupling between the planes ' // str(cross))
         ! (a numbering error would be of the size of the ratios; 1e-6 is the eigenvectors'
         ! accuracy here, the per-plane solution against the two-plane one)
         if (case == 1) then
            call check_le('two planes, symmetric beam: mode j of each plane has ratio j, no ' &
               // 'coupling', max(worst / maxval(ratios), cross), 1.0e-6_dp)
         else
            call check_le('two planes, a spring in v: the modes of each plane numbered in that ' &
               // 'plane, no coupling', max(worst / maxval(ratios), cross), 1.0e-6_dp)
         end if
      end do
   end subroutine two_planes

   !> Largest |zeta_j - ratio(j)| + Rayleigh in the modes of the plane with dofs p.
   real(dp) function plane_error(model, p, r) result(worst)
      type(model_t), intent(in) :: model
      integer, intent(in) :: p(:)
      real(dp), allocatable, intent(in) :: r(:)
      real(dp), allocatable :: a(:, :), b(:, :), w(:), work(:), cm(:, :)
      real(dp) :: q(1), om
      integer :: n, info, j
      n = size(p)
      a = model%sys%k(p, p);  b = model%sys%m(p, p)
      allocate(w(n))
      call dsygv(1, 'V', 'U', n, a, n, b, n, w, q, -1, info)
      allocate(work(int(q(1))))
      call dsygv(1, 'V', 'U', n, a, n, b, n, w, work, size(work), info)
      cm = matmul(transpose(a), matmul(model%c(p, p), a))
      worst = 0.0_dp
      do j = 1, n
         om = sqrt(w(j))
         worst = max(worst, abs(cm(j, j) / (2 * om) - modal_ratio(r, j) - beta / (2 * om) &
                                - gamma * om / 2))
      end do
   end function plane_error

   !> Free decay from each of the first modes' shapes: u(T_d) = u(0) exp(-zeta omega T_d), so
   !> the logarithmic decrement ln(u_tip(0)/u_tip(T_d)) = 2 pi zeta / sqrt(1 - zeta^2) gives
   !> zeta (Rayleigh terms added to the modal ratio). Relative error of zeta within `tol`.
   subroutine free_decay(d0, method, tol, what)
      type(deck_t), intent(in) :: d0
      character(len=*), intent(in) :: method, what
      real(dp), intent(in) :: tol
      type(deck_t) :: d
      type(model_t) :: model
      type(modes_t) :: modes
      type(solver_settings_t) :: cfg
      type(state_t) :: s
      class(integrator_t), allocatable :: integ
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: w, zeta, td, delta, zeta_got, worst
      integer :: j, tip
      character(len=:), allocatable :: line
      d = d0
      d%damping = modal_damping(ratios)
      call build_model(d, model, u0, v0, err)
      if (allocated(err)) then
         call check('free decay: build (' // what // ')', .false., err%message);  return
      end if
      call solve_modes(model%sys, modes, err)
      tip = model%sys%tip_dof
      worst = 0.0_dp
      line = method // ', ' // what // ': zeta from the decrement (given):'
      do j = 1, 4
         w = sqrt(modes%omega2(j))
         zeta = modal_ratio(d%damping%modal_ratios, j) + beta / (2 * w) + gamma * w / 2
         td = 2 * pi / (w * sqrt(1 - zeta**2))
         cfg = d%solver
         cfg%method = method
         if (method /= 'exact') cfg%step_control = 'fixed'
         ! steps of T_d / 2000 of this mode: T_d is the 'forcing period' (there is no forcing)
         model%omega = 2 * pi / td
         cfg%steps_per_period = 2000
         call make_integrator(model, cfg, integ, err)
         if (allocated(err)) then
            call check('free decay: ' // method // ' (' // what // ')', .false., err%message)
            return
         end if
         call start_state(model, 0.0_dp, 1.0e-3_dp * modes%shapes(:, j) &
                          / modes%shapes(tip, j), 0.0_dp * u0, s)
         call integ%advance(s, td, err=err)
         if (allocated(err)) then
            call check('free decay: ' // method // ' (' // what // ')', .false., err%message)
            return
         end if
         delta = log(1.0e-3_dp / s%u(tip))
         zeta_got = delta / sqrt(4 * pi**2 + delta**2)
         worst = max(worst, abs(zeta_got - zeta) / zeta)
         line = line // ' ' // str(zeta_got) // ' (' // str(zeta) // ')'
         deallocate(integ)
      end do
      call note(line)
      call check_le('free decay of modes 1-4, ' // method // ', ' // what // ': zeta from the ' &
         // 'logarithmic decrement (relative error)', worst, tol)
   end subroutine free_decay

   !> Bad &damping modal input: one line naming deck, group, variable, value, rule.
   subroutine bad_input()
      call expect_refused(ref_deck, 'unknown damping model refused', "&damping model = 'modl' /", &
         [character(len=60) :: 'group &damping: model', "'modl'", "'modal'"])
      call expect_refused(ref_deck, 'modal damping without ratios refused', &
         "&damping model = 'modal' /", [character(len=60) :: 'group &damping:', &
         "model = 'modal' needs modal_ratios"])
      call expect_refused(ref_deck, 'a negative modal ratio refused', &
         "&damping model = 'modal', modal_ratios = 0.01, -0.1 /", [character(len=60) :: &
         'group &damping: modal_ratios(2)', '= -0.1', '[0, 100]'])
      call expect_refused(ref_deck, 'modal ratios with another model refused', &
         "&damping model = 'rayleigh', modal_ratios = 0.01 /", [character(len=60) :: &
         'group &damping: modal_ratios', "model = 'rayleigh'", "needs model = 'modal'"])
      call expect_refused(ref_deck, 'modal damping with the banded solver refused', &
         "&damping model = 'modal', modal_ratios = 0.01 / &solver linear_solver = 'banded' /", &
         [character(len=60) :: 'group &solver: linear_solver', "'banded'", 'modal damping', &
          "'auto' or 'dense'"])
   end subroutine bad_input

   !> &damping modal_ratios(i) as a design variable: parse, check, set, get; and the damping
   !> of the model built from the deck follows it.
   subroutine design_variable()
      type(deck_t) :: d
      type(deck_variable_t) :: var
      type(model_t) :: model
      type(modes_t) :: modes
      real(dp), allocatable :: u0(:), v0(:)
      real(dp) :: w
      d = deck
      d%damping = modal_damping([0.01_dp, 0.02_dp])
      call parse_deck_variable('&damping modal_ratios(2)', var, err)
      if (.not. allocated(err)) call check_deck_variable(d, var, err)
      if (.not. allocated(err)) call set_deck_value(d, var, 0.05_dp, err)
      if (allocated(err)) then
         call check('design variable &damping modal_ratios(2)', .false., err%message);  return
      end if
      call check_close('design variable &damping modal_ratios(2): set and read back', &
         get_deck_value(d, var), 0.05_dp, rtol=0.0_dp)
      call build_model(d, model, u0, v0, err)
      call solve_modes(model%sys, modes, err)
      w = sqrt(modes%omega2(3))
      call check_close('design variable modal_ratios(2) = 0.05 damps mode 3 (the last ratio ' &
         // 'repeated)', dot_product(modes%shapes(:, 3), matmul(model%c, modes%shapes(:, 3))) &
         / (2 * w), 0.05_dp + beta / (2 * w) + gamma * w / 2, rtol=1.0e-10_dp)
      call set_deck_value(d, var, -0.5_dp, err)
      call check('design variable modal_ratios(2) = -0.5 refused', allocated(err))
      call parse_deck_variable('&damping modal_ratios(3)', var, err)
      if (.not. allocated(err)) call check_deck_variable(d, var, err)
      call check('design variable modal_ratios(3) refused when the deck gives 2', &
         allocated(err))
      d%damping%model = 'rayleigh'
      call parse_deck_variable('&damping modal_ratios(1)', var, err)
      if (.not. allocated(err)) call check_deck_variable(d, var, err)
      call check('design variable modal_ratios(1) refused without modal damping', &
         allocated(err))
   end subroutine design_variable

end program test_modal_damping
