!> What the outputs add for their readers: the deflected shape from the Hermite shape
!> functions, the XDMF text, the progress lines, the run's parameters (described by the
!> output catalogue), the forcing in words, the one time origin, the version.
program test_output_extras
   use, intrinsic :: iso_fortran_env, only: int32, int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_testing, only: check, check_close, finish
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: system_t, model_t
   use gapbeam_assembly, only: assemble
   use gapbeam_description, only: dof_w, dof_theta
   use gapbeam_deflection, only: shape_points, deflection, nodal_values
   use gapbeam_xdmf, only: make_xdmf, write_xdmf_datasets, suggested_warp_scale
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_test_runs, only: load_deck
   use gapbeam_files, only: remove_file
   use gapbeam_progress_meter, only: progress_line, hms, meter_t
   use gapbeam_parameters, only: parameter_set_t, run_parameters, forcing_text
   use gapbeam_output_catalogue, only: dataset_t, describe
   use gapbeam_results, only: transient_result_t
   use gapbeam_results, only: on_trajectory_clock
   use gapbeam_file_info, only: creation_time
   use gapbeam_checksum, only: crc32_hex
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

   !> The XDMF file of a short run with its state history (the 9.8 Hz deck, 3 recorded periods):
   !> one spatial collection per sample at its time, the beam and its stop, the title escaped
   !> for XML, the HDF5 file named without a directory; and every per-sample value it addresses
   !> (Format="Binary" Seek="..." into the .h5 file) read back raw from those bytes, as
   !> ParaView's readers read them, equal to the run's own values: w of the shape from the
   !> Hermite functions, the displacement (0, w, 0), the stop force and its contact state.
   subroutine xdmf_grids()
      character(len=*), parameter :: h5name = 'test_output_extras_x.h5'
      type(deck_t) :: deck
      type(model_t) :: model
      type(transient_result_t) :: res
      type(h5_writer_t) :: h5
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), sw(:, :), got(:), want(:), forces(:, :)
      integer, allocatable :: seg(:, :)
      character(len=:), allocatable :: t
      integer :: n, k, pos, i, np, ns, closed
      logical :: ok_w, ok_d, ok_f, ok_c
      call load_deck('inputs/moon_shaw_9p8hz.nml', [character(len=120) :: &
         '&solver transient_periods = 20, record_periods = 3 /', &
         '&output state_history = .true., history_periods = 3 /', &
         '&diagnostics lyapunov_periods = 0 /', "&job title = 'a <title> & more' /"], &
         deck, model, u0, v0, err)
      if (.not. allocated(err)) call integrate(model, deck%solver, deck%output, u0, v0, res, err)
      if (allocated(err)) then
         call check('xdmf: the run', .false., err%message)
         return
      end if
      np = size(shape_points(model%sys, deck%output%shape_points))
      ns = size(res%time)
      ! the two datasets the transient file holds anyway (as gapbeam_report writes them), then
      ! the XDMF file's own, then the XDMF file
      allocate(sw(np, ns))
      do i = 1, ns
         sw(:, i) = deflection(model%sys, res%history_u(:, i), deck%output%shape_points)
      end do
      forces = transpose(res%stop_force)
      seg = reshape([(k / 2, k = 1, 2 * (np - 1))], [2, np - 1])
      call h5%create(h5name, 'transient', in_place=.true.)
      call h5%put('/history/shape_w', sw)
      call h5%put('/history/stop_force', forces)
      call h5%put('/history/shape_segments', seg)
      call write_xdmf_datasets(h5, deck, model, res)
      call h5%close(err)
      if (.not. allocated(err)) call make_xdmf(h5name, h5name, deck, model, res, t, err)
      if (allocated(err)) then
         call check('xdmf: the files are written', .false., err%message)
         return
      end if
      n = 0;  pos = 1
      do
         k = index(t(pos:), '<Time Value=')
         if (k == 0) exit
         n = n + 1;  pos = pos + k
      end do
      call check('xdmf: one time step per sample (' // trim(str_i(ns)) // ')', n == ns)
      call check('xdmf: a beam and a stop grid per sample, the mesh and segments of ' &
         // h5name // ', no hyperslab', count_of(t, '<Grid Name="beam"') == ns .and. &
         count_of(t, '<Grid Name="stop 1"') == ns .and. &
         index(t, h5name // ':/history/shape_mesh_xyz') > 0 .and. &
         index(t, 'NumberOfElements="' // trim(str_i(np - 1)) // '"') > 0 .and. &
         index(t, 'HyperSlab') == 0)
      call check('xdmf: the title is escaped for XML', index(t, 'a &lt;title&gt; &amp; more') > 0 &
         .and. index(t, '<title>') == 0)
      ! the values at every sample, read where the XDMF file says they are
      ok_w = .true.;  ok_d = .true.;  ok_f = .true.;  ok_c = .true.;  closed = 0
      do i = 1, ns
         pos = index_of_nth(t, '<Grid Name="sample ', i)
         got = raw_doubles(h5name, seek_after(t, pos, 'Name="w [m]"'), np)
         ok_w = ok_w .and. all(got == sw(:, i))
         got = raw_doubles(h5name, seek_after(t, pos, 'Name="displacement [m]"'), 3 * np)
         want = reshape(transpose(reshape([0.0_dp * sw(:, i), sw(:, i), 0.0_dp * sw(:, i)], &
                                          [np, 3])), [3 * np])
         ok_d = ok_d .and. all(got == want)
         got = raw_doubles(h5name, seek_after(t, pos, 'Name="stop force [N]"'), 1)
         ok_f = ok_f .and. got(1) == res%stop_force(i, 1)
         k = raw_int(h5name, seek_after(t, pos, 'Name="contact [1 closed, 0 open]"'))
         ok_c = ok_c .and. k == merge(1, 0, res%stop_force(i, 1) > 0.0_dp)
         closed = closed + k
      end do
      call check('xdmf: w [m] at every sample read from its bytes in the .h5 = the Hermite shape', &
         ok_w)
      call check('xdmf: displacement [m] at every sample = (0, w, 0)', ok_d)
      call check('xdmf: stop force [N] at every sample = the run''s', ok_f)
      call check('xdmf: contact state at every sample = (force > 0); closed at ' &
         // trim(str_i(closed)) // ' of ' // trim(str_i(ns)) // ' samples', ok_c .and. &
         closed > 0 .and. closed < ns)
      call check('xdmf: the suggested warp scale shows the swing as about a quarter of the ' &
         // 'span (1, 2 or 5 x 10^k, never above 1 when the swing is that large already)', &
         suggested_warp_scale(0.2_dp, 0.0205_dp) == 2.0_dp .and. &
         suggested_warp_scale(0.2_dp, 0.001_dp) == 50.0_dp .and. &
         suggested_warp_scale(0.2_dp, 0.1_dp) == 1.0_dp .and. &
         suggested_warp_scale(0.2_dp, 0.0_dp) == 1.0_dp)
      call remove_file(h5name)
   end subroutine xdmf_grids

   !> Occurrences of `s` in `t`.
   integer function count_of(t, s) result(n)
      character(len=*), intent(in) :: t, s
      integer :: k, pos
      n = 0;  pos = 1
      do
         k = index(t(pos:), s)
         if (k == 0) exit
         n = n + 1;  pos = pos + k
      end do
   end function count_of

   !> Position of the i-th occurrence of `s` in `t` (0 if none).
   integer function index_of_nth(t, s, i) result(pos)
      character(len=*), intent(in) :: t, s
      integer, intent(in) :: i
      integer :: j, k
      pos = 0
      do j = 1, i
         k = index(t(pos + 1:), s)
         if (k == 0) then
            pos = 0
            return
         end if
         pos = pos + k
      end do
   end function index_of_nth

   !> The Seek="..." of the first DataItem after the first `name` from position `from`.
   integer(int64) function seek_after(t, from, name) result(seek)
      character(len=*), intent(in) :: t, name
      integer, intent(in) :: from
      integer :: a, b, c
      seek = -1
      a = index(t(from:), name)
      if (a == 0) return
      a = from + a - 1
      b = index(t(a:), 'Seek="')
      if (b == 0) return
      b = a + b - 1 + len('Seek="')
      c = index(t(b:), '"')
      read(t(b:b + c - 2), *) seek
   end function seek_after

   !> n doubles (little-endian, as the XDMF file says) at byte `seek` of `path`.
   function raw_doubles(path, seek, n) result(v)
      character(len=*), intent(in) :: path
      integer(int64), intent(in) :: seek
      integer, intent(in) :: n
      real(dp), allocatable :: v(:)
      integer :: u
      allocate(v(n), source=huge(1.0_dp))
      if (seek < 0) return
      open(newunit=u, file=path, access='stream', form='unformatted', action='read')
      read(u, pos=seek + 1) v
      close(u)
   end function raw_doubles

   !> A 4-byte integer at byte `seek` of `path`.
   integer function raw_int(path, seek) result(k)
      character(len=*), intent(in) :: path
      integer(int64), intent(in) :: seek
      integer(int32) :: v
      integer :: u
      k = -1
      if (seek < 0) return
      open(newunit=u, file=path, access='stream', form='unformatted', action='read')
      read(u, pos=seek + 1) v
      close(u)
      k = int(v)
   end function raw_int

   pure function str_i(i) result(t)
      integer, intent(in) :: i
      character(len=12) :: t
      write(t, '(i0)') i
   end function str_i

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
      p = run_parameters(deck, [90.13_dp], 4.3_dp, 300.0_dp, 9)
      ei = value_of(p, 'beam/bending_stiffness')
      kappa = value_of(p, 'root/kappa')
      call check_close('parameters: EI = E b h^3 / 12', ei, &
         200.0e9_dp * 7.0857084e-3_dp * 2.6196352e-4_dp**3 / 12.0_dp, rtol=1.0e-12_dp)
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
