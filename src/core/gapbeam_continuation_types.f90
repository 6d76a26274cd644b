!> Continuation of periodic orbits (issue 14): the settings of a `&continuation` group and the
!> results the analysis returns (branches of orbits with their multipliers, the bifurcations
!> located on them, and the two-parameter curves of bifurcation points). Pure data.
module gapbeam_continuation_types
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: continuation_settings_t, continuation_result_t, curve_t, branch_t
   public :: continuation_direction_words, continuation_start_words, jacobian_words, &
      curve_kind_words

   character(len=*), parameter :: continuation_direction_words = "'up', 'down', 'both'"
   character(len=*), parameter :: continuation_start_words = "'transient', 'given'"
   character(len=*), parameter :: jacobian_words = "'exact', 'finite_difference'"
   character(len=*), parameter :: curve_kind_words = "'period_doubling', 'saddle_node', " &
      // "'grazing'"
   character(len=*), parameter :: bifurcation_kind_words = "'saddle_node', " &
      // "'period_doubling', 'neimark_sacker', 'grazing', 'branch_point'"
   integer, parameter :: max_curve_kinds = 3   !! kinds of two-parameter curves

   !> &continuation: what to continue, how, and which curves to draw.
   type :: continuation_settings_t
      character(len=64) :: parameter = '&forcing frequency_hz'   !! continued deck variable
      real(dp) :: parameter_min = 0.0_dp        !! branches stop below this [unit of parameter]
      real(dp) :: parameter_max = 0.0_dp        !! ... and above this
      character(len=8) :: direction = 'both'    !! 'up', 'down' or 'both' from the start
      character(len=16) :: start = 'transient'  !! start orbit: after the deck's transient, or
                                                !! the &initial state taken as a section point
      integer :: period = 0                     !! period of the start orbit (0: detected)
      integer :: transient_periods = -1         !! periods before the start (-1: &solver's)
      real(dp) :: step = 0.0_dp                 !! first step [parameter unit] (0: range/200)
      real(dp) :: step_min = 0.0_dp             !! smallest step (0: range * 1e-7)
      real(dp) :: step_max = 0.0_dp             !! largest step (0: range / 50)
      integer :: max_points = 400               !! points per branch
      real(dp) :: tolerance = 1.0e-10_dp        !! Newton: residual / orbit size
      integer :: max_iterations = 8             !! Newton iterations per point
      character(len=24) :: jacobian = 'exact'   !! monodromy: 'exact' or 'finite_difference'
      real(dp) :: fd_step = 1.0e-5_dp           !! relative step of the differences
      real(dp) :: locate_tolerance = 0.0_dp     !! bifurcations located to this (0: range*1e-7)
      logical :: switch_period_doubling = .true. !! follow the doubled branch at each PD
      integer :: max_period = 16                !! longest period followed (cascade)
      integer :: unstable_points = 0            !! a doubled branch stops after this many
                                                !! unstable points in a row (0: never)
      integer :: grazing_samples = 256          !! samples of d' per forcing period
      character(len=64) :: parameter2 = ''      !! second variable of the curves ('' : none)
      real(dp) :: parameter2_min = 0.0_dp       !! curves stop outside [min, max]
      real(dp) :: parameter2_max = 0.0_dp
      character(len=24) :: curves(max_curve_kinds) = ''   !! kinds continued in two parameters
      integer :: curve_max_points = 300         !! points per curve
      real(dp) :: curve_step = 0.0_dp           !! largest curve step, scaled (0: 0.02)
      character(len=256) :: overlay = ''        !! prefix of a sweep drawn under the charts
   end type continuation_settings_t

   !> One branch: a sequence of orbits of one period.
   type :: branch_t
      integer :: period = 1                          !! forcing periods of the orbit
      integer :: parent = 0                          !! branch it was switched from (0: start)
      integer :: first = 0, last = -1                !! its points in the result arrays
      character(len=256) :: ended = ''                !! why it stopped
   end type branch_t

   !> A two-parameter curve of bifurcation points.
   type :: curve_t
      character(len=16) :: kind = ''                 !! 'period_doubling', ...
      integer :: period = 1                          !! period of the orbits on it
      real(dp), allocatable :: parameter(:)          !! first variable [its unit]
      real(dp), allocatable :: parameter2(:)         !! second variable [its unit]
      character(len=256) :: ended = ''                !! why it stopped (each end)
   end type curve_t

   !> Everything a continuation produces.
   type :: continuation_result_t
      character(len=:), allocatable :: parameter_name    !! '&forcing frequency_hz'
      character(len=:), allocatable :: parameter_units   !! 'Hz'
      character(len=:), allocatable :: parameter2_name   !! '' without curves
      character(len=:), allocatable :: parameter2_units
      real(dp) :: parameter2_value = 0.0_dp          !! the second variable along the branches
      integer :: n = 0                               !! points (all branches)
      integer :: n_state = 0                         !! size of a state
      integer, allocatable :: dofs(:)                !! global dof of each u entry of a state
      real(dp), allocatable :: parameter(:)          !! (n)
      real(dp), allocatable :: state(:, :)           !! (n_state, n) section state (u_r, v_r)
      integer, allocatable :: period(:)              !! (n) forcing periods
      integer, allocatable :: branch(:)              !! (n) branch index
      complex(dp), allocatable :: multipliers(:, :)  !! (n_state, n) by decreasing modulus
      logical, allocatable :: stable(:)              !! (n) all |multiplier| < 1
      real(dp), allocatable :: arclength(:)          !! (n) along the branch, scaled
      integer, allocatable :: iterations(:)          !! (n) Newton iterations
      logical, allocatable :: located(:)             !! (n) a located bifurcation point
      real(dp), allocatable :: grazing(:)            !! (n) extremum of d nearest 0 [m]
      integer, allocatable :: impacts(:)             !! (n) contact intervals per orbit
      real(dp), allocatable :: p_strain(:, :)        !! (max_period, n) root strain at the p
                                                     !!   section points (NaN beyond p) [-]
      real(dp), allocatable :: p_rate(:, :)          !! the same, strain rate [1/s]
      real(dp), allocatable :: p_tip(:, :)           !! the same, tip displacement [m]
      type(branch_t), allocatable :: branches(:)     !! the branches
      ! bifurcations
      integer :: n_bif = 0
      character(len=16), allocatable :: bif_kind(:)  !! kind
      real(dp), allocatable :: bif_parameter(:)      !! where [unit]
      integer, allocatable :: bif_period(:)          !! period of the orbit there
      integer, allocatable :: bif_branch(:)          !! its branch
      integer, allocatable :: bif_point(:)           !! its point in the arrays above
      complex(dp), allocatable :: bif_multiplier(:)  !! the critical multiplier
      real(dp), allocatable :: bif_grazing(:)        !! grazing function there [m]
      character(len=160), allocatable :: bif_note(:) !! e.g. why no doubled branch starts
      ! two-parameter curves
      type(curve_t), allocatable :: curves(:)
      real(dp) :: seconds = 0.0_dp                   !! elapsed [s]
      integer :: map_evaluations = 0                 !! maps of p periods evaluated
      integer :: periods_integrated = 0              !! forcing periods integrated in all
      character(len=:), allocatable :: note          !! about the start orbit ('' none)
   end type continuation_result_t
end module gapbeam_continuation_types
