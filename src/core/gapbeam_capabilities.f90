!> What every time integrator can do, declared once: the registry of methods.
!>
!> Each method is one line of `method_table` (its name, the implementation family that runs
!> it, order and error estimator, the step controls and stop solutions it takes, what a model
!> may contain for it, its stability limit, what the exponent and the stability chart use,
!> whether it gives an exact flow Jacobian). The integrators' registry
!> (integrators/gapbeam_integrator_registry) binds a family to the type that implements it; a
!> method of an existing family (a Newmark variant) is one line here and nothing else.
!>
!> Everything that asks what a method can do reads this table: the deck reader (io/ uses
!> core/ only), `method = 'auto'`, the refusals of make_integrator, the step controller's
!> order, the exponent's and the stability study's choices, `--help` and the capability table
!> of docs/methods.md (a test compares them). What a model needs of a method (`needs_t`) comes
!> from the model itself or, in the reader, from the deck.
module gapbeam_capabilities
   use gapbeam_kinds, only: dp
   use gapbeam_law, only: law_caps_t
   use gapbeam_model, only: model_t
   implicit none
   private
   public :: method_caps_t, needs_t, method_table, method_caps, method_exists, method_word_list, &
      model_needs, method_refusal, solver_refusal, needs_text, exact_method, is_exact

   !> What one method can do.
   type :: method_caps_t
      character(len=24) :: name = ''           !! the deck's word (&solver method)
      !> implementation family: 'newmark', 'alpha', 'central_difference', 'runge_kutta',
      !> 'exponential', 'exact' (the registry binds it to a type; a test may add its own)
      character(len=24) :: family = ''
      character(len=96) :: summary = ''        !! one line
      character(len=48) :: title = ''          !! how a sentence names it ('Newmark')
      logical :: implicit = .true.             !! implicit (a linear solve per step)
      logical :: exact = .false.               !! closed form between events (round-off)
      !> its linear part exact (free flight without error): the step may grow after any step
      !> well inside the error budget, not only at a block's end
      logical :: linear_exact = .false.
      integer :: order = 2                     !! order of accuracy (0: exact)
      !> local error estimate: 'none', 'newmark' (a1 - a0 of the step, Zienkiewicz-Xie),
      !> 'embedded' (an embedded pair), 'none' for the exact method
      character(len=16) :: estimator = 'none'
      !> order the error controller assumes for the estimate (its local error ~ h^(q+1));
      !> 0: no error control
      integer :: control_order = 0
      character(len=64) :: controls = ''       !! step controls it takes, as a word list
      character(len=16) :: auto_control = 'fixed'   !! what step_control 'auto' means for it
      logical :: fixed_point = .false.         !! the paper's fixed point on the stop force
      logical :: two_planes = .false.          !! two planes of motion
      logical :: point_forces = .false.        !! loads out of the w plane, point forces
      logical :: rings = .false.               !! ring supports: circular clearance, friction
      logical :: dampers = .true.              !! contact dampers
      logical :: nonlinear_laws = .true.       !! laws that are not piecewise linear (Hertz)
      logical :: massless = .true.             !! dofs without mass (lumped, no rotary inertia)
      logical :: carries_acceleration = .true. !! the step carries a (3 x 3 amplification)
      real(dp) :: stability_limit = 0.0_dp     !! omega_max dt limit (0: unconditional)
      integer :: stages = 1                    !! right-hand sides per step (explicit methods)
      !> the method of the Lyapunov exponent's fixed-step pair ('' itself): the explicit
      !> methods are only conditionally stable at T / steps_per_period
      character(len=24) :: lyapunov_with = ''
      !> the method whose amplification matrix the stability chart shows ('' itself)
      character(len=24) :: stability_with = ''
      logical :: jacobian = .false.            !! exact Jacobian of the flow (continuation)
      !> what 'auto' may choose it for: 'exact' (first choice when it can integrate the
      !> model), 'modal' (a reduced model, &reduction, that the exact one cannot integrate),
      !> 'fine' (tolerances below Newmark's floor, when estimated cheaper), 'default'
      !> (otherwise), '' (never)
      character(len=8) :: auto_role = ''
      !> the loosest tolerance at which 'auto' runs it (0: the deck's): a looser deck
      !> tolerance is tightened to it (where its labels were measured to hold)
      real(dp) :: loosest_tolerance = 0.0_dp
      real(dp) :: newmark_delta = -1.0_dp      !! preset delta of a variant (< 0: the deck's)
      real(dp) :: newmark_alpha = -1.0_dp      !! preset alpha of a variant (< 0: the deck's)
      !> the smallest tolerance its error control reaches in double precision (0: none
      !> known); below it 'auto' looks for a 'fine' method
      real(dp) :: accuracy_floor = 0.0_dp
      !> the &solver variables it reads, as 'label=variable' pairs (the solver line of a run)
      character(len=64) :: parameters = ''
   end type method_caps_t

   !> What a model asks of a method.
   type :: needs_t
      logical :: two_planes = .false.          !! planes = 2
      logical :: point_forces = .false.        !! loads out of the w plane or point forces
      logical :: rings = .false.               !! a circular clearance or friction
      logical :: circular = .false.            !! a circular clearance
      logical :: friction = .false.            !! friction
      logical :: dampers = .false.             !! a contact damper
      character(len=16) :: nonlinear_law = ''  !! a law that is not piecewise linear ('')
      !> a law on a ring support that cannot be a ring's normal law ('')
      character(len=16) :: unfit_ring_law = ''
      logical :: massless = .false.            !! dofs without mass
   end type needs_t

   character(len=*), parameter :: implicit_controls = "'auto', 'error', 'fixed'"
   character(len=*), parameter :: all_controls = "'auto', 'error', 'fixed', 'half_step', " &
      // "'embedded'"
   character(len=*), parameter :: newmark_controls = "'auto', 'error', 'fixed', 'half_step'"

contains

   !> Every method a deck may name, in the order `--help` and the docs list them.
   pure function method_table() result(t)
      type(method_caps_t), allocatable :: t(:)
      t = [ &
      method_caps_t(name='newmark', family='newmark', summary='implicit Newmark (trapezoidal ' &
         // 'by default), the stop force solved exactly in the contact dofs', order=2, &
         estimator='newmark', control_order=2, controls=newmark_controls, &
         auto_control='error', fixed_point=.true., two_planes=.true., point_forces=.true., &
         rings=.true., auto_role='default', title='Newmark', accuracy_floor=1.0e-7_dp, &
         parameters='delta=newmark_delta alpha=newmark_alpha'), &
      method_caps_t(name='hht', family='alpha', summary='Hilber-Hughes-Taylor alpha: implicit, ' &
         // 'numerical damping of the high modes', order=2, estimator='newmark', &
         control_order=2, controls=implicit_controls, auto_control='error', &
         two_planes=.true., point_forces=.true., title='HHT', parameters='alpha=hht_alpha'), &
      method_caps_t(name='generalized_alpha', family='alpha', summary='generalized-alpha ' &
         // '(Chung-Hulbert): implicit, numerical damping set by rho_infinity', order=2, &
         estimator='newmark', control_order=2, controls=implicit_controls, &
         auto_control='error', two_planes=.true., point_forces=.true., &
         title='generalized-alpha', parameters='rho_inf=rho_infinity'), &
      method_caps_t(name='central_difference', family='central_difference', &
         summary='explicit central differences (Newmark delta = 1/2, alpha = 0)', &
         implicit=.false., order=2, controls="'auto', 'fixed'", two_planes=.true., &
         point_forces=.true., massless=.false., carries_acceleration=.false., &
         stability_limit=2.0_dp, lyapunov_with='newmark', title='central differences'), &
      method_caps_t(name='linear_acceleration', family='newmark', summary='Newmark with ' &
         // 'delta = 1/2, alpha = 1/6 (linear acceleration over the step)', order=2, &
         estimator='newmark', control_order=2, controls=newmark_controls, &
         auto_control='fixed', fixed_point=.true., two_planes=.true., point_forces=.true., &
         rings=.true., stability_limit=3.4641016151377544_dp, newmark_delta=0.5_dp, &
         newmark_alpha=1.0_dp / 6.0_dp, title='linear acceleration', &
         accuracy_floor=1.0e-7_dp), &
      method_caps_t(name='fox_goodwin', family='newmark', summary='Newmark with delta = 1/2, ' &
         // 'alpha = 1/12 (Fox-Goodwin: the smallest period error of the family)', order=2, &
         estimator='newmark', control_order=2, controls=newmark_controls, &
         auto_control='fixed', fixed_point=.true., two_planes=.true., point_forces=.true., &
         rings=.true., stability_limit=2.449489742783178_dp, newmark_delta=0.5_dp, &
         newmark_alpha=1.0_dp / 12.0_dp, title='Fox-Goodwin', accuracy_floor=1.0e-7_dp), &
      method_caps_t(name='rk4', family='runge_kutta', summary='classical explicit ' &
         // 'Runge-Kutta of order 4, fixed steps', implicit=.false., order=4, &
         controls="'auto', 'fixed'", two_planes=.true., point_forces=.true., &
         massless=.false., carries_acceleration=.false., &
         stability_limit=2.8284271247461903_dp, stages=4, lyapunov_with='newmark', &
         title='RK4'), &
      method_caps_t(name='rk45', family='runge_kutta', summary='explicit Dormand-Prince 5(4) ' &
         // 'with its embedded error estimate', implicit=.false., order=5, &
         estimator='embedded', control_order=4, controls="'auto', 'error', 'embedded'", &
         auto_control='error', two_planes=.true., point_forces=.true., rings=.true., &
         massless=.false., carries_acceleration=.false., stability_limit=3.3_dp, stages=7, &
         lyapunov_with='newmark', stability_with='rk4', auto_role='fine', &
         title='the embedded Runge-Kutta method rk45', parameters='rtol=rk_rtol atol=rk_atol'), &
      method_caps_t(name='exponential', family='exponential', summary='modal exponential: ' &
         // 'the linear modes and harmonic loads exact, the contact forces collocated', &
         implicit=.false., order=5, estimator='embedded', control_order=5, linear_exact=.true., &
         controls="'auto', 'error', 'embedded'", auto_control='error', two_planes=.true., &
         point_forces=.true., rings=.true., massless=.false., carries_acceleration=.false., &
         stages=18, lyapunov_with='newmark', auto_role='modal', loosest_tolerance=1.0e-4_dp, &
         title='the modal exponential integrator', parameters='rtol=rk_rtol atol=rk_atol'), &
      method_caps_t(name='exact', family='exact', summary='event-driven closed form of the ' &
         // 'piecewise-linear model: the accuracy reference', exact=.true., order=0, &
         controls=all_controls, nonlinear_laws=.false., jacobian=.true., &
         auto_role='exact', title='the exact event-driven integrator')]
   end function method_table

   !> The capabilities of method `name` from `table` (default: method_table()); name '' when
   !> there is none.
   pure function method_caps(name, table) result(c)
      character(len=*), intent(in) :: name                       !! method word
      type(method_caps_t), intent(in), optional :: table(:)      !! registry
      type(method_caps_t) :: c
      type(method_caps_t), allocatable :: t(:)
      integer :: j
      if (present(table)) then
         t = table
      else
         t = method_table()
      end if
      do j = 1, size(t)
         if (trim(t(j)%name) == trim(name)) then
            c = t(j)
            return
         end if
      end do
   end function method_caps

   !> The name of the registry's exact method (the accuracy reference); '' when none.
   pure function exact_method() result(name)
      character(len=:), allocatable :: name
      type(method_caps_t), allocatable :: t(:)
      integer :: j
      t = method_table()
      name = ''
      do j = 1, size(t)
         if (t(j)%exact) then
            name = trim(t(j)%name)
            return
         end if
      end do
   end function exact_method

   !> Is method `name` of the built-in table an exact one?
   pure logical function is_exact(name) result(yes)
      character(len=*), intent(in) :: name   !! method word
      type(method_caps_t) :: c
      c = method_caps(name)
      yes = c%exact
   end function is_exact

   !> Is `name` a method of the table (default: method_table())?
   pure logical function method_exists(name, table) result(yes)
      character(len=*), intent(in) :: name                       !! method word
      type(method_caps_t), intent(in), optional :: table(:)      !! registry
      type(method_caps_t) :: c
      c = method_caps(name, table)
      yes = len_trim(c%name) > 0
   end function method_exists

   !> "'auto', 'newmark', ..." as the reader lists the method words.
   pure function method_word_list(table) result(w)
      type(method_caps_t), intent(in), optional :: table(:)      !! registry
      character(len=:), allocatable :: w
      type(method_caps_t), allocatable :: t(:)
      integer :: j
      if (present(table)) then
         t = table
      else
         t = method_table()
      end if
      w = "'auto'"
      do j = 1, size(t)
         w = w // ", '" // trim(t(j)%name) // "'"
      end do
   end function method_word_list

   !> Does the method take step control `word`?
   pure logical function allows_control(c, word) result(yes)
      type(method_caps_t), intent(in) :: c        !! method
      character(len=*), intent(in) :: word        !! step_control
      yes = index(c%controls, "'" // trim(word) // "'") > 0
   end function allows_control

   !> What a model asks of a method (its laws' capabilities from model%laws).
   function model_needs(model) result(nd)
      type(model_t), intent(in) :: model          !! model
      type(needs_t) :: nd
      type(law_caps_t), allocatable :: laws(:)
      integer :: c, i
      allocate(laws(0))
      if (allocated(model%laws)) laws = [(model%laws(c)%law%caps(), c = 1, size(model%laws))]
      nd%two_planes = model%sys%planes > 1
      nd%point_forces = model%extra_load
      nd%rings = model%n_rings > 0
      if (nd%rings) then
         nd%circular = any(model%r_circular)
         nd%friction = any(model%r_mu > 0.0_dp)
         nd%dampers = any(model%r_c > 0.0_dp)
      end if
      do c = 1, model%n_contacts
         if (model%c_c(c) > 0.0_dp .and. laws(model%c_law(c))%uses_damping) nd%dampers = .true.
         if (.not. laws(model%c_law(c))%piecewise_linear .and. len_trim(nd%nonlinear_law) &
             == 0) nd%nonlinear_law = laws(model%c_law(c))%name
      end do
      do c = 1, model%n_rings
         if (.not. laws(model%r_law(c))%piecewise_linear .and. len_trim(nd%nonlinear_law) &
             == 0) nd%nonlinear_law = laws(model%r_law(c))%name
         if (.not. laws(model%r_law(c))%rings) nd%unfit_ring_law = laws(model%r_law(c))%name
      end do
      if (allocated(model%sys%m)) then
         nd%massless = any([(model%sys%m(i, i) == 0.0_dp, i = 1, model%n)])
      end if
   end function model_needs

   !> Why method `c` with the resolved step control and stop solution cannot integrate a
   !> model with needs `nd`, or '' when it can. One sentence that names the method, what
   !> the model has and what to use instead.
   function method_refusal(c, nd, step_control, stop_solution, table) result(why)
      type(method_caps_t), intent(in) :: c             !! method
      type(needs_t), intent(in) :: nd                  !! what the model asks
      character(len=*), intent(in) :: step_control     !! resolved step control
      character(len=*), intent(in) :: stop_solution    !! 'condensed' or 'fixed_point'
      type(method_caps_t), intent(in), optional :: table(:)   !! registry
      character(len=:), allocatable :: why
      character(len=:), allocatable :: lacks
      why = ''
      lacks = ''
      if (len_trim(nd%unfit_ring_law) > 0) then
         why = "law '" // trim(nd%unfit_ring_law) // "' cannot be the normal law of a support " &
            // 'with a circular clearance or friction (its registry entry says so): no method ' &
            // 'integrates this model'
         return
      end if
      if (nd%massless .and. .not. c%massless) then
         why = "method '" // trim(c%name) // "' cannot integrate this model: it has dofs " &
            // 'without mass (lumped mass without rotary inertia); explicit methods need a ' &
            // "mass at every dof: use &beam rotary_inertia = 'half_element' or 'hrz', or an " &
            // 'implicit method (' // alternatives(nd, table) // ')'
         return
      end if
      if (nd%two_planes .and. .not. c%two_planes) lacks = join(lacks, 'two planes of motion')
      if (nd%point_forces .and. .not. c%point_forces) lacks = join(lacks, &
         'loads out of the w plane, point forces or turbulence')
      if (nd%circular .and. .not. c%rings) lacks = join(lacks, 'a circular clearance')
      if (nd%friction .and. .not. c%rings) lacks = join(lacks, 'friction')
      if (nd%dampers .and. .not. c%dampers) lacks = join(lacks, 'a contact damper')
      if (len_trim(nd%nonlinear_law) > 0 .and. .not. c%nonlinear_laws) lacks = join(lacks, &
         "a stop law that is not piecewise linear (law = '" // trim(nd%nonlinear_law) &
         // "')")
      if (len(lacks) > 0) then
         why = "method '" // trim(c%name) // "' cannot integrate this model: it has " // lacks &
            // '; ' // trim(c%name) // ' handles ' // features_text(c) // ': use ' &
            // alternatives(nd, table) // " (or 'auto', which chooses one)"
         return
      end if
      if (stop_solution == 'fixed_point' .and. (nd%two_planes .or. nd%point_forces .or. &
          nd%rings)) then
         why = "stop_solution = 'fixed_point' cannot integrate this model: it has " &
            // needs_text(nd) // ": use stop_solution = 'condensed'"
      else if (nd%rings .and. .not. c%exact .and. step_control /= 'error' .and. &
               step_control /= 'auto') then
         why = "method '" // trim(c%name) // "' with step_control = '" // trim(step_control) &
            // "' cannot integrate this model: it has " // needs_text(nd) // ": use " &
            // "step_control = 'error' (or 'auto'), whose steps end at every contact and " &
            // 'stick-slip switch'
      end if
   end function method_refusal

   !> What a model asks beyond a planar beam with flat frictionless stops, in words.
   function needs_text(nd) result(t)
      type(needs_t), intent(in) :: nd     !! needs
      character(len=:), allocatable :: t
      t = ''
      if (nd%circular) t = join(t, 'a circular clearance')
      if (nd%friction) t = join(t, 'friction')
      if (nd%two_planes) t = join(t, 'two planes of motion')
      if (nd%point_forces) t = join(t, 'loads out of the w plane, point forces or turbulence')
   end function needs_text

   !> What a method handles beyond a planar beam with flat frictionless bilinear stops.
   function features_text(c) result(t)
      type(method_caps_t), intent(in) :: c   !! method
      character(len=:), allocatable :: t
      t = 'planar models with flat frictionless stops'
      if (c%two_planes) t = t // ', two planes of motion'
      if (c%point_forces) t = t // ', point forces'
      if (c%rings) t = t // ', circular clearances and friction'
      if (c%dampers) t = t // ', contact dampers'
      if (c%nonlinear_laws) then
         t = t // ', any stop law'
      else
         t = t // ', piecewise-linear stop laws only'
      end if
      if (.not. c%massless) t = t // ' (every dof needs a mass)'
   end function features_text

   !> The methods that can integrate a model with needs `nd`, as a word list.
   function alternatives(nd, table) result(t)
      type(needs_t), intent(in) :: nd                         !! needs
      type(method_caps_t), intent(in), optional :: table(:)   !! registry
      character(len=:), allocatable :: t
      type(method_caps_t), allocatable :: all(:)
      integer :: j
      if (present(table)) then
         all = table
      else
         all = method_table()
      end if
      t = ''
      do j = 1, size(all)
         associate (c => all(j))
            if ((nd%massless .and. .not. c%massless) .or. (nd%two_planes .and. .not. &
                c%two_planes) .or. (nd%point_forces .and. .not. c%point_forces) .or. &
                (nd%rings .and. .not. c%rings) .or. (nd%dampers .and. .not. c%dampers) .or. &
                (len_trim(nd%nonlinear_law) > 0 .and. .not. c%nonlinear_laws)) cycle
            if (c%newmark_delta >= 0.0_dp .and. c%stability_limit > 0.0_dp) cycle
            if (len(t) > 0) t = t // ', '
            t = t // "method = '" // trim(c%name) // "'"
         end associate
      end do
      if (len(t) == 0) t = 'another model (no method handles all of it)'
   end function alternatives

   !> Why the deck's &solver combination of method, step control and stop solution is
   !> refused, or '' (the deck reader's check; 'auto' takes every step control the methods it
   !> may choose take, 'embedded' excepted).
   function solver_refusal(method, step_control, stop_solution) result(why)
      character(len=*), intent(in) :: method          !! &solver method
      character(len=*), intent(in) :: step_control    !! &solver step_control
      character(len=*), intent(in) :: stop_solution   !! &solver stop_solution
      character(len=:), allocatable :: why
      type(method_caps_t) :: c
      why = ''
      if (method == 'auto') then
         if (step_control == 'embedded') why = "step_control = 'embedded' needs a method " &
            // "with an embedded error estimate (" // with_control('embedded') // ')'
         return
      end if
      c = method_caps(method)
      if (len_trim(c%name) == 0) return        ! the word check reports it
      if (.not. allows_control(c, step_control)) then
         why = "step_control = '" // trim(step_control) // "' is not available with method " &
            // "= '" // trim(c%name) // "' (it takes " // trim(c%controls) // '); ' &
            // "step_control = '" // trim(step_control) // "' runs with " &
            // with_control(step_control)
      else if (stop_solution == 'fixed_point' .and. .not. c%fixed_point) then
         why = "stop_solution = 'fixed_point' (the paper's iteration on the stop force) is " &
            // "not available with method = '" // trim(c%name) // "', which uses the " &
            // "condensed solution; the fixed point runs with " // with_fixed_point()
      end if
   end function solver_refusal

   !> The methods that take step control `word` (the exact method, which ignores it, aside).
   function with_control(word) result(t)
      character(len=*), intent(in) :: word   !! step control
      character(len=:), allocatable :: t
      type(method_caps_t), allocatable :: all(:)
      integer :: j
      all = method_table()
      t = ''
      do j = 1, size(all)
         if (all(j)%exact .or. .not. allows_control(all(j), word)) cycle
         if (len(t) > 0) t = t // ', '
         t = t // "method = '" // trim(all(j)%name) // "'"
      end do
   end function with_control

   !> The methods with the paper's fixed point.
   function with_fixed_point() result(t)
      character(len=:), allocatable :: t
      type(method_caps_t), allocatable :: all(:)
      integer :: j
      all = method_table()
      t = ''
      do j = 1, size(all)
         if (.not. all(j)%fixed_point) cycle
         if (len(t) > 0) t = t // ', '
         t = t // "method = '" // trim(all(j)%name) // "'"
      end do
   end function with_fixed_point

   !> a, b joined by ', ' (b alone when a is empty).
   pure function join(a, b) result(t)
      character(len=*), intent(in) :: a, b   !! texts
      character(len=:), allocatable :: t
      if (len(a) == 0) then
         t = b
      else
         t = a // ', ' // b
      end if
   end function join
end module gapbeam_capabilities
