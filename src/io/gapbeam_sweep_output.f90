!> Sweep result files: HDF5 (one per shard, or the whole sweep), gnuplot-ready text, and the
!> merge of shard files into the file a single process would have written.
!>
!> HDF5 layout: /deck; /sweep/grid_frequency_hz, /sweep/grid_amplitude_pp (the axes);
!> /sweep/shard_index, /sweep/shard_count, /sweep/n_points_total; per point of the file, in
!> point order: /sweep/point_index, frequency_hz, amplitude_pp, period, label, label_text,
!> lyapunov, lyapunov_error, status, steps, seconds; /sweep/impacts/<stat>; /sweep/poincare/
!> strain and strain_rate; /sweep/lyapunov_running; /parameters (gapbeam_file_info). In C order
!> (h5py) every per-point array has the point first: (point, stop), (point, period).
module gapbeam_sweep_output
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_hdf5_output, only: h5_writer_t, h5_reader_t, write_failed
   use gapbeam_files, only: write_table, real_path, file_exists
   use gapbeam_output_set, only: output_set_t
   use gapbeam_results, only: point_result_t, label_text
   use gapbeam_parameters, only: parameter_set_t
   use gapbeam_file_info, only: write_file_info, write_parameter_set
   implicit none
   private
   public :: sweep_file_t, write_sweep, read_sweep, merge_sweep

   !> What a sweep file holds besides the points.
   type :: sweep_file_t
      character(len=:), allocatable :: deck_text     !! effective deck text
      character(len=:), allocatable :: title         !! job title
      real(dp), allocatable :: grid_frequency_hz(:)  !! frequency axis [Hz]
      real(dp), allocatable :: grid_amplitude_pp(:)  !! amplitude axis [m]
      !> what the amplitude axis sets: 'amplitudes' (amplitude_pp of the base motion) or
      !> 'values of &stops gap(1), ...' (&sweep variable)
      character(len=:), allocatable :: axis_variable
      character(len=:), allocatable :: axis_units    !! units of the amplitude axis ('m')
      integer :: shard_index = 1                     !! this file's shard
      integer :: shard_count = 1                     !! shards of the sweep
      integer, allocatable :: points(:)              !! point indices in the file (ascending)
      type(parameter_set_t) :: parameters            !! the run's parameters (/parameters)
      !> a file whose /parameters are copied instead (a merge: the first shard's)
      character(len=:), allocatable :: parameters_source
   end type sweep_file_t

contains

   !> Write points `sf%points` of `results` to PREFIX.h5 (and the text tables when asked), as
   !> one output set (gapbeam_output_set): all files in place, or none changed.
   !>
   !> Per-point arrays (impact statistics, Poincare points, the running Lyapunov estimate) are
   !> sized from the points that succeeded (status 0); a failed point, whose arrays may be
   !> empty or shorter, gets NaN in the missing places.
   subroutine write_sweep(prefix, sf, results, write_text, err)
      character(len=*), intent(in) :: prefix             !! output path prefix
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points (indexed by point)
      logical, intent(in) :: write_text                  !! also .sweep.dat, .bifurcation.dat
      type(error_t), allocatable, intent(out) :: err     !! I/O failure; no file changed then
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      if (write_text) then
         call set%begin(prefix, [character(len=16) :: '.h5', '.sweep.dat', '.bifurcation.dat'], &
                        err)
      else
         call set%begin(prefix, ['.h5'], err)
      end if
      if (allocated(err)) return
      call h5%create(set%temp(1), err, in_place=.true.)
      if (.not. allocated(err)) call sweep_h5(h5, set, sf, results, err)
      if (.not. allocated(err) .and. write_text) call sweep_tables(set, sf, results, err)
      call set%finish(err)
   end subroutine write_sweep

   !> What the amplitude axis sets, 'amplitudes' unless the sweep names deck variables.
   pure function axis_text(sf) result(t)
      type(sweep_file_t), intent(in) :: sf
      character(len=:), allocatable :: t
      t = 'amplitudes'
      if (allocated(sf%axis_variable)) t = sf%axis_variable
   end function axis_text

   !> '' or '; amplitude axis: values of <variables> [units]' for the table's title line.
   function axis_note(sf) result(t)
      type(sweep_file_t), intent(in) :: sf
      character(len=:), allocatable :: t
      t = ''
      if (axis_text(sf) /= 'amplitudes') t = '; amplitude axis: ' // axis_text(sf) &
         // ' [' // sf%axis_units // ']'
   end function axis_note

   !> Sizes of the per-point arrays: stops, recorded periods, Lyapunov periods, from the
   !> points that succeeded (from all points when none did).
   subroutine point_sizes(results, points, ns, nr, nl)
      type(point_result_t), intent(in) :: results(:)     !! all points
      integer, intent(in) :: points(:)                   !! the points of the file
      integer, intent(out) :: ns, nr, nl                 !! stops, recorded and Lyapunov periods
      integer :: j, p, pass
      ns = 0;  nr = 0;  nl = 0
      do pass = 1, 2
         do j = 1, size(points)
            p = points(j)
            if (pass == 1 .and. results(p)%status /= 0) cycle
            if (allocated(results(p)%peak_force)) ns = max(ns, size(results(p)%peak_force))
            if (allocated(results(p)%p_strain)) nr = max(nr, size(results(p)%p_strain))
            if (allocated(results(p)%lyapunov_running)) &
               nl = max(nl, size(results(p)%lyapunov_running))
         end do
         if (any(results(points)%status == 0)) exit
      end do
   end subroutine point_sizes

   !> `x` (if allocated) in an array of length n, NaN where x has no value.
   pure function padded(x, n) result(y)
      real(dp), allocatable, intent(in) :: x(:)          !! values (possibly too short, or none)
      integer, intent(in) :: n                           !! length wanted
      real(dp) :: y(n)
      integer :: m
      y = ieee_value(0.0_dp, ieee_quiet_nan)
      if (.not. allocated(x)) return
      m = min(n, size(x))
      y(1:m) = x(1:m)
   end function padded

   !> One impact statistic of every point of the file, Fortran (stops, points): in C order
   !> (h5py) one row per point.
   function impact_stat(results, points, which, ns) result(v)
      type(point_result_t), intent(in) :: results(:)     !! all points
      integer, intent(in) :: points(:)                   !! the points of the file
      integer, intent(in) :: which                       !! 1 peak, 2 rms, 3 contact fraction,
                                                         !! 4 impulse per period, 5 work rate,
                                                         !! 6 normal work rate, 7 sliding
                                                         !! distance, 8 friction work rate,
                                                         !! 9 wear volume rate
      integer, intent(in) :: ns                          !! stops
      real(dp) :: v(ns, size(points))
      integer :: j, p
      do j = 1, size(points)
         p = points(j)
         select case (which)
         case (1);  v(:, j) = padded(results(p)%peak_force, ns)
         case (2);  v(:, j) = padded(results(p)%rms_force, ns)
         case (3);  v(:, j) = padded(results(p)%contact_fraction, ns)
         case (4);  v(:, j) = padded(results(p)%impulse_per_period, ns)
         case (6);  v(:, j) = padded(results(p)%normal_work_rate, ns)
         case (7);  v(:, j) = padded(results(p)%sliding_distance, ns)
         case (8);  v(:, j) = padded(results(p)%friction_work_rate, ns)
         case (9);  v(:, j) = padded(results(p)%wear_volume_rate, ns)
         case default;  v(:, j) = padded(results(p)%work_rate, ns)
         end select
      end do
   end function impact_stat

   !> Impact counts of every point of the file, Fortran (stops, points); 0 where a point has
   !> none.
   function impact_counts(results, points, ns) result(v)
      type(point_result_t), intent(in) :: results(:)     !! all points
      integer, intent(in) :: points(:)                   !! the points of the file
      integer, intent(in) :: ns                          !! stops
      real(dp) :: v(ns, size(points))
      integer :: j, p, m
      v = 0.0_dp
      do j = 1, size(points)
         p = points(j)
         if (.not. allocated(results(p)%n_impacts)) cycle
         m = min(ns, size(results(p)%n_impacts))
         v(1:m, j) = real(results(p)%n_impacts(1:m), dp)
      end do
   end function impact_counts

   !> PREFIX.h5 of a sweep: the datasets listed in the module header.
   subroutine sweep_h5(h5, set, sf, results, err)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created; closed here
      type(output_set_t), intent(in) :: set              !! the set (for /run/files)
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points (indexed by point)
      type(error_t), allocatable, intent(out) :: err     !! I/O failure
      integer :: m, ns, nr, nl, j, p, nf
      real(dp), allocatable :: f(:), a(:), r2(:, :)
      character(len=16), allocatable :: labels(:)
      character(len=*), parameter :: stat_names(5) = [character(len=18) :: 'peak_force', &
         'rms_force', 'contact_fraction', 'impulse_per_period', 'work_rate']
      character(len=*), parameter :: stat_units(5) = [character(len=3) :: 'N', 'N', '1', &
         'N s', 'W']
      character(len=*), parameter :: wear_names(4) = [character(len=18) :: 'normal_work_rate', &
         'sliding_distance', 'friction_work_rate', 'wear_volume_rate']
      character(len=*), parameter :: wear_units(4) = [character(len=6) :: 'W', 'm', 'W', &
         'm3 s-1']
      character(len=*), parameter :: wear_long(4) = [character(len=72) :: &
         'normal work rate of each support, (1/T) integral of F_N |v_t| dt', &
         'distance each support slid over the record', &
         'mean friction power of each support', &
         'Archard wear volume rate of each support']
      character(len=*), parameter :: stat_long(5) = [character(len=60) :: &
         'largest force of each stop in the record', &
         'root mean square force of each stop over the record', &
         'fraction of the record each stop is in contact', &
         'impulse of each stop per forcing period', &
         'mean rate of contact work of each stop']

      m = size(sf%points);  nf = size(sf%grid_frequency_hz)
      call point_sizes(results, sf%points, ns, nr, nl)
      allocate(f(m), a(m), labels(m))
      do j = 1, m
         p = sf%points(j)
         f(j) = sf%grid_frequency_hz(mod(p - 1, nf) + 1)
         a(j) = sf%grid_amplitude_pp((p - 1) / nf + 1)
         labels(j) = label_text(results(p)%label)
      end do
      call write_file_info(h5, 'sweep', sf%deck_text, err);  if (write_failed(h5, err)) return
      call h5%write_text('/deck', sf%deck_text, err, 'the effective deck text: deck file ' &
         // 'and command-line overrides');  if (write_failed(h5, err)) return
      call set%record(h5, err);  if (write_failed(h5, err)) return
      if (allocated(sf%parameters_source)) then
         call h5%copy_from(sf%parameters_source, '/parameters', err)
      else
         call write_parameter_set(h5, sf%parameters, err)
      end if
      if (write_failed(h5, err)) return
      call h5%write_text('/sweep/title', sf%title, err, '&job title')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/grid_frequency_hz', sf%grid_frequency_hz, 'Hz', err, &
                    'frequency axis of the sweep grid')
      if (write_failed(h5, err)) return
      if (axis_text(sf) == 'amplitudes') then
         call h5%write('/sweep/grid_amplitude_pp', sf%grid_amplitude_pp, 'm', err, &
                       'amplitude axis of the sweep grid, base displacement peak to peak')
      else
         call h5%write('/sweep/grid_amplitude_pp', sf%grid_amplitude_pp, sf%axis_units, err, &
                       'second axis of the sweep grid: ' // axis_text(sf) &
                       // ' (&sweep variable)')
      end if
      if (write_failed(h5, err)) return
      call h5%write_text('/sweep/amplitude_axis', axis_text(sf), err, 'what the second ' &
         // "axis sets: 'amplitudes' (base motion amplitude_pp) or the deck variables")
      if (write_failed(h5, err)) return
      call h5%write('/sweep/shard_index', sf%shard_index, '1', err, &
                    'shard I of this file (1 for a whole or merged sweep)')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/shard_count', sf%shard_count, '1', err, 'number N of shards')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/n_points_total', nf * size(sf%grid_amplitude_pp), '1', err, &
                    'points of the whole sweep, n_frequency x n_amplitude')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/point_index', sf%points, '1', err, 'point number p = i_f + ' &
         // '(i_a - 1) n_f of each point of the file (frequency fastest)')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/frequency_hz', f, 'Hz', err, 'forcing frequency of the point')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/amplitude_pp', a, 'm', err, 'base displacement amplitude of the ' &
         // 'point, peak to peak');  if (write_failed(h5, err)) return
      call h5%write('/sweep/period', [(results(sf%points(j))%period, j = 1, m)], '1', err, &
                    'detected period in forcing periods; 0: none up to period_max')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/label', [(results(sf%points(j))%label, j = 1, m)], '1', err, &
                    'label code: p >= 1 period p, 0 undecided, -1 chaotic')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/label_text', labels, '1', err, 'label: period_<p>, chaotic or ' &
         // 'undecided');  if (write_failed(h5, err)) return
      call h5%write('/sweep/lyapunov', [(results(sf%points(j))%lyapunov, j = 1, m)], 's-1', &
                    err, 'largest Lyapunov exponent')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/lyapunov_error', [(results(sf%points(j))%lyapunov_error, &
                    j = 1, m)], 's-1', err, 'standard error of the largest Lyapunov exponent')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/status', [(results(sf%points(j))%status, j = 1, m)], '1', err, &
                    'status of the point: 0 done, 1 failed (results NaN)')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/steps', [(real(results(sf%points(j))%steps, dp), j = 1, m)], '1', &
                    err, 'accepted integration steps of the point''s run (Lyapunov periods ' &
                    // 'not counted)')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/seconds', [(results(sf%points(j))%seconds, j = 1, m)], 's', err, &
                    'wall time of the point (run and exponent)')
      if (write_failed(h5, err)) return
      call h5%write('/sweep/impacts/count', impact_counts(results, sf%points, ns), '1', err, &
                    'contact onsets of each stop in the record', 'point stop')
      if (write_failed(h5, err)) return
      do j = 1, size(stat_names)
         call h5%write('/sweep/impacts/' // trim(stat_names(j)), &
                       impact_stat(results, sf%points, j, ns), trim(stat_units(j)), err, &
                       trim(stat_long(j)), 'point stop')
         if (write_failed(h5, err)) return
      end do
      do j = 1, size(wear_names)
         call h5%write('/sweep/wear/' // trim(wear_names(j)), &
                       impact_stat(results, sf%points, 5 + j, ns), trim(wear_units(j)), err, &
                       trim(wear_long(j)), 'point stop')
         if (write_failed(h5, err)) return
      end do
      allocate(r2(nr, m))
      do j = 1, m
         r2(:, j) = padded(results(sf%points(j))%p_strain, nr)
      end do
      call h5%write('/sweep/poincare/strain', r2, '1', err, 'root strain at the Poincare ' &
         // 'section, every recorded period', 'point period')
      if (write_failed(h5, err)) return
      do j = 1, m
         r2(:, j) = padded(results(sf%points(j))%p_strain_rate, nr)
      end do
      call h5%write('/sweep/poincare/strain_rate', r2, 's-1', err, 'root strain rate at the ' &
         // 'Poincare section, every recorded period', 'point period')
      if (write_failed(h5, err)) return
      deallocate(r2);  allocate(r2(nl, m))
      do j = 1, m
         r2(:, j) = padded(results(sf%points(j))%lyapunov_running, nl)
      end do
      call h5%write('/sweep/lyapunov_running', r2, 's-1', err, 'running estimate of the ' &
         // 'largest Lyapunov exponent after each period', 'point period')
      if (write_failed(h5, err)) return
      call h5%close(err)
   end subroutine sweep_h5

   !> PREFIX.sweep.dat (one row per point) and PREFIX.bifurcation.dat (every Poincare point
   !> with its forcing), under the set's temporary names.
   subroutine sweep_tables(set, sf, results, err)
      type(output_set_t), intent(in) :: set              !! files 2 and 3
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points (indexed by point)
      type(error_t), allocatable, intent(out) :: err     !! I/O failure
      integer :: m, ns, nr, nl, j, p, nf
      real(dp), allocatable :: f(:), a(:), cols(:, :), row(:), counts(:, :)
      character(len=24) :: names(14), units(14)

      m = size(sf%points);  nf = size(sf%grid_frequency_hz)
      call point_sizes(results, sf%points, ns, nr, nl)
      allocate(f(m), a(m))
      do j = 1, m
         p = sf%points(j)
         f(j) = sf%grid_frequency_hz(mod(p - 1, nf) + 1)
         a(j) = sf%grid_amplitude_pp((p - 1) / nf + 1)
      end do
      allocate(cols(m, 14))
      cols = 0.0_dp
      cols(:, 1) = f;  cols(:, 2) = a
      do j = 1, m
         p = sf%points(j)
         cols(j, 3) = results(p)%period;  cols(j, 4) = results(p)%label
         cols(j, 5) = results(p)%lyapunov;  cols(j, 6) = results(p)%lyapunov_error
         if (ns > 0) then
            counts = impact_counts(results, [p], ns)
            cols(j, 7) = counts(1, 1)
            row = padded(results(p)%peak_force, ns);  cols(j, 8) = row(1)
            row = padded(results(p)%rms_force, ns);  cols(j, 9) = row(1)
            row = padded(results(p)%work_rate, ns);  cols(j, 10) = row(1)
            cols(j, 11) = sum(padded(results(p)%normal_work_rate, ns))
            cols(j, 12) = sum(padded(results(p)%wear_volume_rate, ns))
            cols(j, 13) = maxval(padded(results(p)%contact_fraction, ns))
            cols(j, 14) = sum(counts(:, 1))
         end if
      end do
      names = [character(len=24) :: 'frequency', 'amplitude_pp', 'period', 'label', &
         'lyapunov', 'lyapunov_error', 'impacts_stop1', 'peak_force_stop1', 'rms_force_stop1', &
         'work_rate_stop1', 'normal_work_rate_total', 'wear_volume_rate_total', &
         'contact_fraction_max', 'impacts_total']
      units = [character(len=24) :: 'Hz', 'm', 'periods', 'p|0|-1', '1/s', '1/s', '-', &
         'N', 'N', 'W', 'W', 'm3/s', '-', '-']
      ! the grid's extent in the title line, so that a shard's chart places its tiles on the
      ! whole grid (scripts/chaos_map.gp, lyapunov.gp)
      call write_table(set%temp(2), sf%title // ': sweep points (label: p = period,' &
         // ' 0 undecided, -1 chaotic); grid: ' // str(nf) // ' frequencies from ' &
         // num(minval(sf%grid_frequency_hz)) // ' to ' // num(maxval(sf%grid_frequency_hz)) &
         // ' Hz, ' // str(size(sf%grid_amplitude_pp)) // ' amplitudes from ' &
         // num(minval(sf%grid_amplitude_pp)) // ' to ' // num(maxval(sf%grid_amplitude_pp)) &
         // ' m' // trim(axis_note(sf)), names, units, cols, err, in_place=.true.)
      if (allocated(err)) return
      deallocate(cols);  allocate(cols(m * nr, 4))
      do j = 1, m
         p = sf%points(j)
         cols((j - 1) * nr + 1:j * nr, 1) = f(j)
         cols((j - 1) * nr + 1:j * nr, 2) = a(j)
         cols((j - 1) * nr + 1:j * nr, 3) = padded(results(p)%p_strain, nr)
         cols((j - 1) * nr + 1:j * nr, 4) = padded(results(p)%p_strain_rate, nr)
      end do
      call write_table(set%temp(3), sf%title // ': Poincare points of every sweep point', &
         [character(len=24) :: 'frequency', 'amplitude_pp', 'strain', 'strain_rate'], &
         [character(len=24) :: 'Hz', 'm', '-', '1/s'], cols, err, in_place=.true.)
   end subroutine sweep_tables

   !> Read a sweep file back: its description and its points into `results` (sized to all
   !> points of the sweep on return).
   subroutine read_sweep(path, sf, results, err)
      character(len=*), intent(in) :: path                         !! file
      type(sweep_file_t), intent(out) :: sf                        !! description
      type(point_result_t), allocatable, intent(inout) :: results(:) !! points land here
      type(error_t), allocatable, intent(out) :: err               !! I/O failure
      type(h5_reader_t) :: h5
      integer :: total, j, p
      integer, allocatable :: period(:), label(:), status(:)
      real(dp), allocatable :: lyap(:), lerr(:), steps(:), secs(:), cnt(:, :), pk(:, :), &
         rms(:, :), cf(:, :), imp(:, :), wr(:, :), ps(:, :), pr(:, :), lr(:, :), &
         wn(:, :), sd(:, :), fw(:, :), wv(:, :)
      character(len=:), allocatable :: axis_order
      call h5%open(path, err);  if (allocated(err)) return
      call h5%read_attr('/', 'axis_order', axis_order, err)
      if (allocated(err)) then
         call fatal_error(err, 'gapbeam_sweep_output:read_sweep: ' // path // ' was written ' &
            // 'by an older gapbeam (no axis_order attribute; its impact arrays are ' &
            // 'transposed): merge it with the version that wrote it')
         goto 9
      end if
      call h5%read_text('/deck', sf%deck_text, err);  if (allocated(err)) goto 9
      call h5%read_text('/sweep/title', sf%title, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/grid_frequency_hz', sf%grid_frequency_hz, err)
      if (allocated(err)) goto 9
      call h5%read('/sweep/grid_amplitude_pp', sf%grid_amplitude_pp, err)
      if (allocated(err)) goto 9
      sf%axis_variable = 'amplitudes';  sf%axis_units = 'm'
      if (h5%exists('/sweep/amplitude_axis')) then
         call h5%read_text('/sweep/amplitude_axis', sf%axis_variable, err)
         if (allocated(err)) goto 9
         call h5%read_attr('/sweep/grid_amplitude_pp', 'units', sf%axis_units, err)
         if (allocated(err)) goto 9
      end if
      call h5%read('/sweep/shard_index', sf%shard_index, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/shard_count', sf%shard_count, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/n_points_total', total, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/point_index', sf%points, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/period', period, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/label', label, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/status', status, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/lyapunov', lyap, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/lyapunov_error', lerr, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/steps', steps, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/seconds', secs, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/impacts/count', cnt, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/impacts/peak_force', pk, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/impacts/rms_force', rms, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/impacts/contact_fraction', cf, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/impacts/impulse_per_period', imp, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/impacts/work_rate', wr, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/poincare/strain', ps, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/poincare/strain_rate', pr, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/lyapunov_running', lr, err);  if (allocated(err)) goto 9
      if (h5%exists('/sweep/wear/normal_work_rate')) then
         call h5%read('/sweep/wear/normal_work_rate', wn, err);  if (allocated(err)) goto 9
         call h5%read('/sweep/wear/sliding_distance', sd, err);  if (allocated(err)) goto 9
         call h5%read('/sweep/wear/friction_work_rate', fw, err);  if (allocated(err)) goto 9
         call h5%read('/sweep/wear/wear_volume_rate', wv, err);  if (allocated(err)) goto 9
      else
         allocate(wn, sd, fw, wv, mold=wr)
         wn = 0.0_dp;  sd = 0.0_dp;  fw = 0.0_dp;  wv = 0.0_dp
      end if
      if (.not. allocated(results)) allocate(results(total))
      if (size(results) /= total) then
         call fatal_error(err, 'gapbeam_sweep_output:read_sweep: ' // path // ' has ' &
            // str(total) // ' points in all, the other files ' // str(size(results)))
         goto 9
      end if
      do j = 1, size(sf%points)
         p = sf%points(j)
         if (p < 1 .or. p > total) then
            call fatal_error(err, 'gapbeam_sweep_output:read_sweep: ' // path // ': point ' &
               // 'index ' // str(p) // ' outside 1..' // str(total))
            goto 9
         end if
         results(p)%period = period(j);  results(p)%label = label(j)
         results(p)%status = status(j);  results(p)%lyapunov = lyap(j)
         results(p)%lyapunov_error = lerr(j);  results(p)%steps = nint(steps(j), int64)
         results(p)%seconds = secs(j);  results(p)%n_impacts = nint(cnt(:, j))
         results(p)%peak_force = pk(:, j);  results(p)%rms_force = rms(:, j)
         results(p)%contact_fraction = cf(:, j);  results(p)%impulse_per_period = imp(:, j)
         results(p)%work_rate = wr(:, j);  results(p)%p_strain = ps(:, j)
         results(p)%p_strain_rate = pr(:, j);  results(p)%lyapunov_running = lr(:, j)
         results(p)%normal_work_rate = wn(:, j);  results(p)%sliding_distance = sd(:, j)
         results(p)%friction_work_rate = fw(:, j);  results(p)%wear_volume_rate = wv(:, j)
      end do
9     call h5%close()
   end subroutine read_sweep

   !> Merge shard files into OUT (prefix without '.h5'): all from one deck, shards 1..N each
   !> exactly once, every point present once. The result is written by write_sweep, like a
   !> single-process run.
   subroutine merge_sweep(out_prefix, paths, write_text, err)
      character(len=*), intent(in) :: out_prefix         !! output prefix
      character(len=*), intent(in) :: paths(:)           !! shard files
      logical, intent(in) :: write_text                  !! also the text tables
      type(error_t), allocatable, intent(out) :: err     !! mismatch or I/O failure
      type(sweep_file_t) :: first, sf, merged
      type(point_result_t), allocatable :: results(:)
      logical, allocatable :: seen_shard(:), seen_point(:)
      integer :: k, j, p
      character(len=*), parameter :: here = 'gapbeam merge: '
      if (size(paths) == 0) then
         call fatal_error(err, here // 'no shard files given')
         return
      end if
      call check_merge_paths(out_prefix, paths, err)
      if (allocated(err)) return
      do k = 1, size(paths)
         call read_sweep(trim(paths(k)), sf, results, err)
         if (allocated(err)) then
            err%message = here // trim(paths(k)) // ': ' // err%message
            return
         end if
         if (k == 1) then
            first = sf
            allocate(seen_shard(sf%shard_count), source=.false.)
            allocate(seen_point(size(results)), source=.false.)
         else if (sf%deck_text /= first%deck_text) then
            call fatal_error(err, here // trim(paths(k)) // ' was run from a different deck ' &
               // 'than ' // trim(paths(1)) // ': refusing to mix them')
            return
         else if (sf%shard_count /= first%shard_count) then
            call fatal_error(err, here // trim(paths(k)) // ' is shard ' // str(sf%shard_index) &
               // ' of ' // str(sf%shard_count) // ', ' // trim(paths(1)) // ' one of ' &
               // str(first%shard_count))
            return
         end if
         if (sf%shard_index < 1 .or. sf%shard_index > first%shard_count) then
            call fatal_error(err, here // trim(paths(k)) // ': shard index ' &
               // str(sf%shard_index) // ' outside 1..' // str(first%shard_count))
            return
         end if
         if (seen_shard(sf%shard_index)) then
            call fatal_error(err, here // 'shard ' // str(sf%shard_index) // ' of ' &
               // str(first%shard_count) // ' is given twice (' // trim(paths(k)) // ')')
            return
         end if
         seen_shard(sf%shard_index) = .true.
         do j = 1, size(sf%points)
            p = sf%points(j)
            if (seen_point(p)) then
               call fatal_error(err, here // 'point ' // str(p) // ' appears in two files (' &
                  // trim(paths(k)) // ')')
               return
            end if
            seen_point(p) = .true.
         end do
      end do
      if (.not. all(seen_shard)) then
         call fatal_error(err, here // 'incomplete set: missing shard(s) ' &
            // list_missing(seen_shard) // ' of ' // str(first%shard_count))
         return
      end if
      if (.not. all(seen_point)) then
         call fatal_error(err, here // 'incomplete set: ' // str(count(.not. seen_point)) &
            // ' points missing (a shard file is incomplete)')
         return
      end if
      merged = first
      merged%parameters_source = trim(paths(1))
      merged%shard_index = 1;  merged%shard_count = 1
      merged%points = [(p, p = 1, size(results))]
      call write_sweep(out_prefix, merged, results, write_text, err)
   end subroutine merge_sweep

   !> Refuse a merge whose inputs name one file twice, or whose output is one of its inputs
   !> (compared as canonical paths, so 'a.h5' and './a.h5' are the same file).
   subroutine check_merge_paths(out_prefix, paths, err)
      character(len=*), intent(in) :: out_prefix         !! output prefix
      character(len=*), intent(in) :: paths(:)           !! shard files
      type(error_t), allocatable, intent(out) :: err     !! the clash found
      character(len=*), parameter :: here = 'gapbeam merge: '
      character(len=:), allocatable :: canon(:), out_real
      integer :: k, j, width
      width = 1
      do k = 1, size(paths)
         if (.not. file_exists(paths(k))) then
            call fatal_error(err, here // 'shard file ' // trim(paths(k)) // ' does not exist')
            return
         end if
         width = max(width, len(real_path(paths(k))))
      end do
      allocate(character(len=width) :: canon(size(paths)))
      do k = 1, size(paths)
         canon(k) = real_path(paths(k))
         do j = 1, k - 1
            if (canon(j) == canon(k)) then
               call fatal_error(err, here // trim(paths(k)) // ' is given twice (inputs ' &
                  // str(j) // ' and ' // str(k) // ' are the same file)')
               return
            end if
         end do
      end do
      out_real = real_path(trim(out_prefix) // '.h5')
      if (len(out_real) == 0) return
      do k = 1, size(paths)
         if (trim(canon(k)) == out_real) then
            call fatal_error(err, here // 'the output ' // trim(out_prefix) // '.h5 is also ' &
               // 'input ' // str(k) // ' (' // trim(paths(k)) // '): it would be overwritten; ' &
               // 'give another output name')
            return
         end if
      end do
   end subroutine check_merge_paths

   !> A number with 17 significant digits and a decimal point, as every reader takes it.
   function num(x) result(t)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: t
      character(len=32) :: buf
      write(buf, '(es24.16e3)') x
      t = trim(adjustl(buf))
   end function num

   pure function list_missing(seen) result(t)
      logical, intent(in) :: seen(:)
      character(len=:), allocatable :: t
      integer :: i
      t = ''
      do i = 1, size(seen)
         if (.not. seen(i)) then
            if (len(t) > 0) t = t // ', '
            t = t // str(i)
         end if
      end do
   end function list_missing
end module gapbeam_sweep_output
