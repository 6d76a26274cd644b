!> What the outputs add for their readers: the deflected shape from the Hermite shape
!> functions, the XDMF text, the progress lines, the run's parameters (described by the
!> output catalogue), the forcing in words, the one time origin, the version.
program test_output_extras
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_testing, only: check, check_close, finish
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: system_t
   use gapbeam_assembly, only: assemble
   use gapbeam_description, only: dof_w, dof_theta
   use gapbeam_deflection, only: shape_points, deflection, nodal_values
   use gapbeam_xdmf, only: xdmf_text
   use gapbeam_progress_meter, only: progress_line, hms, meter_t
   use gapbeam_parameters, only: parameter_set_t, run_parameters, forcing_text
   use gapbeam_output_catalogue, only: dataset_t, describe
   use gapbeam_results, only: transient_result_t
   use gapbeam_report, only: on_trajectory_clock
   use gapbeam_file_info, only: crc32_hex, creation_time
   use gapbeam_version, only: program_version
   implicit none

   call hermite_shape_is_exact_for_cubics()
   call xdmf_grids()
   call progress_lines()
   call parameters_of_the_reference_deck()
   call one_time_origin()
   call checksums_and_times()
   call finish('test_output_extras')

contains

   !> A cubic w(x) = a x^3 + b x^2 + c x given at the nodes (w and theta = w') is reproduced
   !> exactly between them: the Hermite shape functions span the cubics.
   subroutine hermite_shape_is_exact_for_cubics()
      type(deck_t) :: deck
      type(system_t) :: sys
      type(error_t), allocatable :: err
      real(dp), allocatable :: u(:), x(:), w(:), nw(:), nt(:)
      real(dp), parameter :: a = 3.0_dp, b = -1.5_dp, c = 0.02_dp
      real(dp) :: xi
      integer :: i, g
      call read_deck('test/decks/input_minimal.nml', [character(len=80) :: &
         "&root condition = 'spring', k_theta = 1.0 /"], deck, err)
      if (allocated(err)) then
         call check('read the minimal deck', .false., err%message)
         return
      end if
      call assemble(deck%structure, sys)
      allocate(u(sys%n_dof), source=0.0_dp)
      do i = 1, sys%n_node
         xi = real(i - 1, dp) * sys%element_length
         g = sys%dof_of(dof_w, i)
         if (g > 0) u(g) = a * xi**3 + b * xi**2 + c * xi
         g = sys%dof_of(dof_theta, i)
         if (g > 0) u(g) = 3.0_dp * a * xi**2 + 2.0_dp * b * xi + c
      end do
      x = shape_points(sys, 7)
      w = deflection(sys, u, 7)
      call check('shape points: n_elem x 7 + 1, from 0 to the length', &
         size(x) == (sys%n_node - 1) * 7 + 1 .and. x(1) == 0.0_dp .and. &
         abs(x(size(x)) - deck%structure%beam%length) < 1.0e-14_dp)
      call check_close('Hermite deflection of a cubic: largest error between the nodes', &
         maxval(abs(w - (a * x**3 + b * x**2 + c * x))), 0.0_dp, atol=1.0e-15_dp)
      allocate(nw(sys%n_node), nt(sys%n_node))
      call nodal_values(sys, u, nw, nt)
      call check_close('nodal values: every 7th shape point is a node', &
         maxval(abs(w(1::7) - nw)), 0.0_dp, atol=0.0_dp)
   end subroutine hermite_shape_is_exact_for_cubics

   !> One grid per sample, the HDF5 file named without a directory, sizes of the shape.
   subroutine xdmf_grids()
      character(len=:), allocatable :: t
      integer :: n, k, pos
      t = xdmf_text('x.h5', 'a <title> & more', [0.0_dp, 0.5_dp, 1.0_dp], 33)
      n = 0;  pos = 1
      do
         k = index(t(pos:), '<Time Value=')
         if (k == 0) exit
         n = n + 1;  pos = pos + k
      end do
      call check('xdmf: one grid per sample (3)', n == 3)
      call check('xdmf: the datasets of x.h5, the shape of 33 points in 32 segments', &
         index(t, 'x.h5:/history/shape_xyz') > 0 .and. index(t, 'x.h5:/history/shape_w') > 0 &
         .and. index(t, 'NumberOfElements="32"') > 0 .and. index(t, '"3 33 3"') > 0)
      call check('xdmf: the title is escaped for XML', index(t, 'a &lt;title&gt; &amp; more') > 0 &
         .and. index(t, '<title>') == 0)
      call check('xdmf: the last sample''s hyperslab starts at 2', &
         index(t, '>2 0 0 1 1 1 1 33 3<') > 0)
   end subroutine xdmf_grids

   subroutine progress_lines()
      type(meter_t) :: m
      call check('hms(3725) = 1:02:05', hms(3725.0_dp) == '1:02:05')
      call check('hms(0.4) = 0:00:00', hms(0.4_dp) == '0:00:00')
      call check('hms(359999) = 99:59:59 (hours unbounded)', hms(359999.0_dp) == '99:59:59')
      call check('hms(1e12) says it is too long', hms(1.0e12_dp) == 'more than 1e6 h')
      call check('progress line: percent, counts, rate, time left', &
         progress_line('sweep', 256.0_dp, 512.0_dp, 'points', 13.9_dp) &
         == 'sweep: 50.0 % (256/512 points), 13.9 points/s, 0:00:18 left')
      call check('progress line: fractional work, a slow rate', &
         progress_line('transient', 1.7_dp, 204.0_dp, 'periods', 0.551_dp) &
         == 'transient: 0.8 % (1.7/204 periods), 0.551 periods/s, 0:06:07 left')
      call check('progress line without a rate', &
         progress_line('sweep', 0.0_dp, 10.0_dp, 'points', -1.0_dp) &
         == 'sweep: 0.0 % (0/10 points)')
      call check('the last line: the time taken', &
         progress_line('sweep', 10.0_dp, 10.0_dp, 'points', 2.0_dp, 5.0_dp) &
         == 'sweep: 100.0 % (10/10 points) in 0:00:05, 2.00 points/s')
      ! a disabled meter takes updates and prints nothing (nothing to see here but no crash)
      call m%start('sweep', 'points', 10.0_dp, 0.0_dp, .false., 0.0_dp)
      call m%update(5.0_dp)
      call m%finish()
      call check('a disabled meter ignores updates', .not. m%shown)
   end subroutine progress_lines

   !> The resolved parameters of the reference deck (EI, kappa) and of the tube deck (all it
   !> takes to rebuild the model: planes, added mass, the tip, the holes, friction, point
   !> forces), each described by the output catalogue with the units it says.
   subroutine parameters_of_the_reference_deck()
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      type(parameter_set_t) :: p
      real(dp) :: ei, kappa
      integer :: k
      call read_deck('inputs/moon_shaw_10p5hz.nml', [character(len=1) :: ], deck, err)
      if (allocated(err)) then
         call check('read the reference deck', .false., err%message)
         return
      end if
      p = run_parameters(deck, [105.64_dp], 4.3_dp, 300.0_dp, 9)
      ei = value_of(p, 'beam/bending_stiffness')
      kappa = value_of(p, 'root/kappa')
      call check_close('parameters: EI = E b h^3 / 12', ei, &
         200.0e9_dp * 6.6477523e-3_dp * 2.6196352e-4_dp**3 / 12.0_dp, rtol=1.0e-12_dp)
      call check_close('parameters: kappa = k_theta L / EI', kappa, 0.0912_dp * 0.2_dp / ei, &
         rtol=1.0e-12_dp)
      call check_described(p, 'reference deck')
      call check('forcing text of the reference deck: frequency and base motion', &
         forcing_text(deck) == '10.5 Hz, 3.7 mm peak to peak', forcing_text(deck))

      call read_deck('inputs/tube_multispan.nml', [character(len=1) :: ], deck, err)
      if (allocated(err)) then
         call check('read the tube deck', .false., err%message)
         return
      end if
      p = run_parameters(deck)
      call check('tube parameters: planes 2, tip pinned, added mass 0.47 kg/m', &
         value_of(p, 'beam/planes') == 2.0_dp .and. text_of(p, 'tip/condition') == 'pinned' &
         .and. value_of(p, 'beam/added_mass') == deck%structure%beam%added_mass &
         .and. deck%structure%beam%added_mass > 0.0_dp)
      call check('tube parameters: the point forces (nodes, dofs, amplitudes, phases)', &
         value_of(p, 'point_forces/count') == 2.0_dp .and. &
         all(list_of(p, 'point_forces/node') == [13.0_dp, 13.0_dp]) .and. &
         all(list_of(p, 'point_forces/dof') == [1.0_dp, 3.0_dp]) .and. &
         all(list_of(p, 'point_forces/amplitude') == deck%forcing%forces%amplitude) .and. &
         all(list_of(p, 'point_forces/phase_deg') == deck%forcing%forces%phase_deg))
      call check('tube parameters: circular holes, their offsets, friction, tangential ' &
         // 'stiffness and wear coefficients', &
         all(list_of(p, 'stops/circular') == 1.0_dp) .and. &
         all(list_of(p, 'stops/offset_w') == deck%stops%offset_w) .and. &
         all(list_of(p, 'stops/offset_v') == deck%stops%offset_v) .and. &
         all(list_of(p, 'stops/friction') == deck%stops%friction) .and. &
         all(list_of(p, 'stops/tangential_stiffness') == deck%stops%tangential_stiffness) .and. &
         all(list_of(p, 'stops/wear_coefficient') == deck%stops%wear_coefficient) .and. &
         any(deck%stops%friction > 0.0_dp))
      call check('tube parameters: the direction and phase of the base motion', &
         value_of(p, 'forcing/direction_deg') == deck%forcing%direction_deg .and. &
         value_of(p, 'forcing/phase_v_deg') == deck%forcing%phase_v_deg)
      call check_described(p, 'tube deck')
      call check('forcing text of the tube: the point forces, no base motion', &
         index(forcing_text(deck), '8 Hz; point forces 0.6 N at node 13 (w), 0.35 N at node ' &
         // '13 (v') == 1 .and. index(forcing_text(deck), '; no base motion') > 0, &
         forcing_text(deck))
   end subroutine parameters_of_the_reference_deck

   !> Every parameter has an entry in the output catalogue for every analysis, and carries
   !> units exactly where the catalogue says the deck decides them.
   subroutine check_described(p, what)
      type(parameter_set_t), intent(in) :: p
      character(len=*), intent(in) :: what
      type(dataset_t) :: entry
      character(len=:), allocatable :: bad
      logical :: found
      integer :: k
      bad = ''
      do k = 1, size(p%items)
         call describe('sweep', '/parameters/' // p%items(k)%path, entry, found)
         if (.not. found) then
            bad = bad // ' ' // p%items(k)%path // ' (not in the catalogue)'
         else if ((index(entry%units, '=') == 1) .neqv. allocated(p%items(k)%units)) then
            bad = bad // ' ' // p%items(k)%path // ' (units)'
         end if
      end do
      call check('parameters of the ' // what // ': every value in the catalogue, deck units ' &
         // 'where it says', len(bad) == 0, bad)
   end subroutine check_described

   !> The value of a scalar parameter (-huge when absent).
   real(dp) function value_of(p, path)
      type(parameter_set_t), intent(in) :: p
      character(len=*), intent(in) :: path
      integer :: k
      value_of = -huge(1.0_dp)
      do k = 1, size(p%items)
         if (p%items(k)%path == path .and. allocated(p%items(k)%values)) &
            value_of = p%items(k)%values(1)
      end do
   end function value_of

   !> The values of a list parameter (none when absent).
   function list_of(p, path) result(v)
      type(parameter_set_t), intent(in) :: p
      character(len=*), intent(in) :: path
      real(dp), allocatable :: v(:)
      integer :: k
      allocate(v(0))
      do k = 1, size(p%items)
         if (p%items(k)%path == path .and. allocated(p%items(k)%values)) v = p%items(k)%values
      end do
   end function list_of

   !> The text of a text parameter ('' when absent).
   function text_of(p, path) result(t)
      type(parameter_set_t), intent(in) :: p
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: t
      integer :: k
      t = ''
      do k = 1, size(p%items)
         if (p%items(k)%path == path .and. allocated(p%items(k)%text)) t = p%items(k)%text
      end do
   end function text_of

   !> The times of a record whose run began after an extension are put on the clock of the
   !> whole trajectory; a record without an extension keeps its times bit for bit.
   subroutine one_time_origin()
      type(transient_result_t) :: res, r
      real(dp), parameter :: period = 0.1_dp
      res%time = [0.2_dp, 0.25_dp];  res%p_time = [0.2_dp, 0.3_dp]
      res%first_contact_time = [-1.0_dp, 0.05_dp]
      res%t_end = 0.4_dp                        ! a run of 2 + 2 periods
      r = on_trajectory_clock(res, 22, 2, period)
      call check_close('time origin: the history starts at 22 periods', r%time(1), &
                       22 * period, rtol=1.0e-14_dp)
      call check_close('time origin: the Poincare points too', r%p_time(2), 23 * period, &
                       rtol=1.0e-14_dp)
      call check_close('time origin: the end at 24 periods', r%t_end, 24 * period, &
                       rtol=1.0e-14_dp)
      call check('time origin: a first contact is shifted, "never" (-1) kept', &
         r%first_contact_time(1) == -1.0_dp .and. &
         abs(r%first_contact_time(2) - (0.05_dp + 20 * period)) < 1.0e-14_dp)
      r = on_trajectory_clock(res, 2, 2, period)
      call check('time origin: a record without extension keeps its times bit for bit', &
         all(r%time == res%time) .and. all(r%p_time == res%p_time) .and. r%t_end == res%t_end)
   end subroutine one_time_origin

   subroutine checksums_and_times()
      character(len=:), allocatable :: t
      integer :: k
      call check('CRC-32 of "123456789" is cbf43926 (the standard check value)', &
         crc32_hex('123456789') == 'cbf43926')
      t = creation_time()
      call check('creation time is ISO 8601 (YYYY-MM-DDThh:mm:ss+hh:mm)', len(t) == 25 .and. &
         t(5:5) == '-' .and. t(11:11) == 'T' .and. t(23:23) == ':')
      call check('a version of the form major.minor.patch', &
         count([(program_version(k:k) == '.', k = 1, len(program_version))]) == 2)
   end subroutine checksums_and_times
end program test_output_extras
