!> Sweep result files: HDF5 (one per shard, or the whole sweep), gnuplot-ready text, and the
!> merge of shard files into the file a single process would have written.
!>
!> HDF5 layout: /deck; /sweep/grid_frequency_hz, /sweep/grid_amplitude_pp (the forcing axes, or
!> the &forcing value), /sweep/grid_x, /sweep/grid_y, /sweep/x_variable, /sweep/y_variable
!> (the axes); /sweep/shard_index, /sweep/shard_count, /sweep/n_points_total; per point of the
!> file, in point order: /sweep/point_index, x, y, frequency_hz, amplitude_pp, the integer and
!> real fields of `int_names` and `real_names`, the texts of `text_names`, label_text and
!> certificate_text; /sweep/impacts/<stat> (points, stops); /sweep/poincare/strain and
!> strain_rate (recorded periods, points); /sweep/lyapunov_running (periods, points);
!> /sweep/starts/kind (starts), /sweep/starts/label, attractor, lyapunov (starts, points);
!> /sweep/attractors/label, fraction, lyapunov (starts, points; padded past n_attractors);
!> /parameters and /model (gapbeam_file_info: the deck's model; a merge copies the first
!> shard's). Shapes above are Fortran's: in C order (h5py) every per-point array has the
!> point first: (point, stop), (point, period), (point, start). Units and long names are
!> those of the output catalogue.
module gapbeam_sweep_output
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_files, only: real_path, file_exists
   use gapbeam_output_set, only: output_set_t
   use gapbeam_results, only: point_result_t, label_text, certificate_text, label_failed, &
      dispute_kind
   use gapbeam_model, only: model_t
   use gapbeam_parameters, only: parameter_set_t
   use gapbeam_file_info, only: write_parameter_set, write_model, udunits
   use gapbeam_point_fields, only: int_names, real_names, text_names, int_fields, &
      set_int_fields, real_fields, set_real_fields, text_field, set_text_field, array_names, &
      array_extent, array_type, array_late, array_field, set_array_field
   use gapbeam_sweep_statistics, only: write_sweep_statistics, read_sweep_statistics
   use gapbeam_warning_text, only: untouched_sweep_warnings, is_untouched_warning, &
      warning_length
   implicit none
   private
   public :: sweep_file_t, write_sweep, read_sweep, merge_sweep, sweep_warnings

   !> What a sweep file holds besides the points.
   type :: sweep_file_t
      character(len=:), allocatable :: deck_text     !! effective deck text
      !> the deck's warnings; write_sweep adds those about stops never touched, from the points
      !> of the file (read_sweep leaves them out, so that a merge remakes them for the grid)
      character(len=warning_length), allocatable :: warnings(:)
      character(len=:), allocatable :: title         !! job title
      real(dp), allocatable :: grid_frequency_hz(:)  !! frequency axis [Hz] (or the one value)
      real(dp), allocatable :: grid_amplitude_pp(:)  !! amplitude axis [m] (or the one value)
      character(len=:), allocatable :: x_variable    !! x axis variable ('&forcing frequency_hz')
      character(len=:), allocatable :: y_variable    !! y axis variable
      character(len=:), allocatable :: x_units       !! its unit
      character(len=:), allocatable :: y_units       !! its unit
      real(dp), allocatable :: grid_x(:)             !! x axis values
      real(dp), allocatable :: grid_y(:)             !! y axis values
      character(len=8), allocatable :: start_kind(:) !! kind of each start
      integer :: shard_index = 1                     !! this file's shard
      integer :: shard_count = 1                     !! shards of the sweep
      integer, allocatable :: points(:)              !! point indices in the file (ascending)
      type(parameter_set_t) :: parameters            !! the run's parameters (/parameters)
      type(model_t), allocatable :: model            !! the deck's model (/model)
      character(len=:), allocatable :: stiffness_units   !! of its stop stiffnesses
      !> a file whose /parameters and /model are copied instead (a merge: the first shard's)
      character(len=:), allocatable :: parameters_source
      logical :: has_model = .false.                 !! the file read holds /model
      real(dp) :: cpu_seconds = -1.0_dp              !! CPU time of the process, all threads [s]
      real(dp) :: wall_seconds = -1.0_dp             !! elapsed time of the job [s]
      integer :: threads = 0                         !! OpenMP threads of the run
   end type sweep_file_t

   !> A list of texts (one text dataset of a file).
   type :: text_list_t
      character(len=:), allocatable :: v(:)        !! the texts, blank padded
   end type text_list_t

   !> One array of every point of a file, (n, points).
   type :: stat_t
      real(dp), allocatable :: v(:, :)             !! values
   end type stat_t

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
      if (write_text) then
         call set%begin(prefix, [character(len=16) :: '.h5', '.sweep.dat', '.bifurcation.dat'])
      else
         call set%begin(prefix, ['.h5'])
      end if
      call sweep_h5(set, sf, results)
      if (write_text) call sweep_tables(set, sf, results)
      call set%finish(err)
   end subroutine write_sweep

   !> The warnings of a sweep file: the deck's, then one per stop that no finished point of
   !> the file touched.
   function sweep_warnings(sf, results) result(lines)
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points
      character(len=warning_length), allocatable :: lines(:), more(:)
      integer, allocatable :: impacts(:, :), status(:)
      real(dp), allocatable :: contact(:, :)
      integer :: ns, nr, nl, j, p
      call point_sizes(results, sf%points, ns, nr, nl)
      allocate(impacts(ns, size(sf%points)), source=0)
      allocate(contact(ns, size(sf%points)), source=0.0_dp)
      allocate(status(size(sf%points)), source=1)
      do j = 1, size(sf%points)
         p = sf%points(j)
         if (results(p)%status /= 0 .or. .not. allocated(results(p)%n_impacts) .or. &
             .not. allocated(results(p)%contact_fraction)) cycle
         if (size(results(p)%n_impacts) /= ns .or. size(results(p)%contact_fraction) /= ns) &
            cycle
         impacts(:, j) = results(p)%n_impacts
         contact(:, j) = results(p)%contact_fraction
         status(j) = 0
      end do
      more = untouched_sweep_warnings(impacts, contact, status)
      lines = more
      if (allocated(sf%warnings)) lines = [character(len=warning_length) :: sf%warnings, more]
   end function sweep_warnings

   !> /run/warnings of a sweep file into sf%warnings, less those about stops never touched
   !> (remade for the points a merge writes); none in a file of an older gapbeam.
   subroutine read_warnings(h5, sf)
      type(h5_reader_t), intent(inout) :: h5             !! open file
      type(sweep_file_t), intent(inout) :: sf            !! description
      character(len=:), allocatable :: all(:)
      integer :: k
      allocate(sf%warnings(0))
      if (.not. h5%exists('/run/warnings')) return
      call h5%read('/run/warnings', all)
      if (h5%failed()) return
      sf%warnings = pack(all, [(.not. is_untouched_warning(all(k)), k = 1, size(all))])
   end subroutine read_warnings

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

   !> Array k (array_names) of every point of the file, Fortran (n, points): in C order
   !> (h5py) one row per point; past a point's own values 0 (array_type 'z', 'i') or NaN.
   function array_table(results, points, k, n) result(v)
      type(point_result_t), intent(in) :: results(:)     !! all points
      integer, intent(in) :: points(:)                   !! the points of the file
      integer, intent(in) :: k                           !! the array
      integer, intent(in) :: n                           !! its length
      real(dp) :: v(n, size(points))
      real(dp), allocatable :: x(:)
      integer :: j, m
      v = ieee_value(0.0_dp, ieee_quiet_nan)
      if (array_type(k:k) /= 'r') v = 0.0_dp
      do j = 1, size(points)
         x = array_field(results(points(j)), k)
         m = min(n, size(x))
         v(1:m, j) = x(1:m)
      end do
   end function array_table

   !> Forcing frequency and amplitude of point p of a file's sweep, and its axis values.
   pure subroutine point_axes(sf, p, x, y, f, a)
      type(sweep_file_t), intent(in) :: sf           !! file description
      integer, intent(in) :: p                       !! point
      real(dp), intent(out) :: x, y, f, a            !! axis values, [Hz], [m]
      integer :: nx
      nx = size(sf%grid_x)
      x = sf%grid_x(mod(p - 1, nx) + 1)
      y = sf%grid_y((p - 1) / nx + 1)
      f = sf%grid_frequency_hz(1);  a = sf%grid_amplitude_pp(1)
      if (sf%x_variable == '&forcing frequency_hz') f = x
      if (sf%y_variable == '&forcing frequency_hz') f = y
      if (sf%x_variable == '&forcing amplitude_pp') a = x
      if (sf%y_variable == '&forcing amplitude_pp') a = y
   end subroutine point_axes

   !> Strings of one text field for the points of a file, as a fixed-length array.
   function texts(results, points, j) result(t)
      type(point_result_t), intent(in) :: results(:)     !! all points
      integer, intent(in) :: points(:)                   !! the points of the file
      integer, intent(in) :: j                           !! text field
      character(len=:), allocatable :: t(:)
      integer :: k
      allocate(character(len=max(1, maxval([(len(text_field(results(points(k)), j)), &
                                             k = 1, size(points))]))) :: t(size(points)))
      do k = 1, size(points)
         t(k) = text_field(results(points(k)), j)
      end do
   end function texts

   !> PREFIX.h5 of a sweep: the datasets listed in the module header.
   subroutine sweep_h5(set, sf, results)
      type(output_set_t), intent(inout) :: set           !! the set; its .h5 is written here
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points (indexed by point)
      type(h5_writer_t) :: h5
      real(dp), allocatable :: f(:), a(:), x(:), y(:), rv(:, :)
      integer, allocatable :: iv(:, :)
      character(len=16), allocatable :: labels(:), certs(:)
      integer :: m, ns, nr, nl, j, k, sizes(4)
      m = size(sf%points)
      call point_sizes(results, sf%points, ns, nr, nl)
      allocate(f(m), a(m), x(m), y(m), labels(m), certs(m))
      do j = 1, m
         call point_axes(sf, sf%points(j), x(j), y(j), f(j), a(j))
         labels(j) = label_text(results(sf%points(j))%label)
         certs(j) = certificate_text(results(sf%points(j))%certificate)
      end do
      call set%open_h5(h5, 'sweep', sf%deck_text, sweep_warnings(sf, results))
      if (allocated(sf%parameters_source)) then
         call h5%copy_from(sf%parameters_source, '/parameters')
         if (sf%has_model) call h5%copy_from(sf%parameters_source, '/model')
      else
         call write_parameter_set(h5, sf%parameters)
         if (allocated(sf%model)) call write_model(h5, sf%model, sf%stiffness_units)
      end if
      call h5%put('/sweep/title', sf%title)
      if (sf%threads > 0) then   ! a run, not a merge (a merge's shards hold their own)
         call h5%put('/run/cpu_seconds', sf%cpu_seconds)
         call h5%put('/run/wall_seconds', sf%wall_seconds)
         call h5%put('/run/threads', sf%threads)
      end if
      call h5%put('/sweep/grid_frequency_hz', sf%grid_frequency_hz)
      call h5%put('/sweep/grid_amplitude_pp', sf%grid_amplitude_pp)
      call h5%put('/sweep/x_variable', sf%x_variable)
      call h5%put('/sweep/y_variable', sf%y_variable)
      call h5%put('/sweep/grid_x', sf%grid_x, units=udunits(sf%x_units), fill=sf%x_variable)
      call h5%put('/sweep/grid_y', sf%grid_y, units=udunits(sf%y_units), fill=sf%y_variable)
      call h5%put('/sweep/shard_index', sf%shard_index)
      call h5%put('/sweep/shard_count', sf%shard_count)
      call h5%put('/sweep/n_points_total', size(sf%grid_x) * size(sf%grid_y))
      call h5%put('/sweep/point_index', sf%points)
      call h5%put('/sweep/x', x, units=udunits(sf%x_units))
      call h5%put('/sweep/y', y, units=udunits(sf%y_units))
      call h5%put('/sweep/frequency_hz', f)
      call h5%put('/sweep/amplitude_pp', a)
      allocate(iv(size(int_names), m), rv(size(real_names), m))
      do j = 1, m
         iv(:, j) = int_fields(results(sf%points(j)))
         rv(:, j) = real_fields(results(sf%points(j)))
      end do
      do k = 1, size(int_names)
         call h5%put('/sweep/' // trim(int_names(k)), iv(k, :))
      end do
      do k = 1, size(real_names)
         call h5%put('/sweep/' // trim(real_names(k)), rv(k, :))
      end do
      call h5%put('/sweep/label_text', labels)
      call h5%put('/sweep/certificate_text', certs)
      do k = 1, size(text_names)
         call h5%put('/sweep/' // trim(text_names(k)), texts(results, sf%points, k))
      end do
      sizes = [ns, nr, nl, size(sf%start_kind)]
      do k = 1, size(array_names)
         if (k == 11) call write_sweep_statistics(h5, results, sf%points, ns)
         if (k == 14) call h5%put('/sweep/starts/kind', sf%start_kind)
         rv = array_table(results, sf%points, k, sizes(array_extent(k)))
         if (array_type(k:k) == 'i') then
            call h5%put('/sweep/' // trim(array_names(k)), nint(rv))
         else
            call h5%put('/sweep/' // trim(array_names(k)), rv)
         end if
      end do
      call set%close_h5(h5)
   end subroutine sweep_h5

   !> PREFIX.sweep.dat (one row per point) and PREFIX.bifurcation.dat (every Poincare point
   !> with its axis values and the point's label and certificate), under the set's temporary
   !> names. Columns 1 and 2 are the x and y axis values (frequency and amplitude_pp by
   !> default).
   subroutine sweep_tables(set, sf, results)
      type(output_set_t), intent(inout) :: set           !! the set
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points (indexed by point)
      integer, parameter :: nc = 22
      integer :: m, ns, nr, nl, j, p, k
      real(dp), allocatable :: f(:), a(:), x(:), y(:), cols(:, :), st(:, :)
      character(len=24) :: names(nc), units(nc), xn, yn, xu, yu

      ! (locals: gfortran mishandles deferred-length results inside array constructors)
      xn = axis_name(sf%x_variable);  yn = axis_name(sf%y_variable)
      xu = sf%x_units;  yu = sf%y_units
      m = size(sf%points)
      call point_sizes(results, sf%points, ns, nr, nl)
      allocate(f(m), a(m), x(m), y(m))
      do j = 1, m
         call point_axes(sf, sf%points(j), x(j), y(j), f(j), a(j))
      end do
      allocate(cols(m, nc))
      cols = 0.0_dp
      cols(:, 1) = x;  cols(:, 2) = y
      do j = 1, m
         p = sf%points(j)
         cols(j, 3) = results(p)%period;  cols(j, 4) = results(p)%label
         cols(j, 5) = results(p)%lyapunov;  cols(j, 6) = results(p)%lyapunov_error
         if (ns > 0) then
            allocate(st(ns, 10))
            do k = 1, 10
               st(:, k:k) = array_table(results, [p], k, ns)
            end do
            cols(j, 7:10) = [st(1, 1), st(1, 2), st(1, 3), st(1, 6)]
            cols(j, 18) = sum(st(:, 7));  cols(j, 19) = sum(st(:, 10))
            cols(j, 20) = maxval(st(:, 4));  cols(j, 21) = sum(st(:, 1))
            deallocate(st)
         end if
         cols(j, 11) = results(p)%status;  cols(j, 12) = results(p)%certificate
         cols(j, 13) = results(p)%n_attractors;  cols(j, 14) = results(p)%lyapunov_periods
         cols(j, 15) = results(p)%transient_periods
         cols(j, 22) = 0
         if (allocated(results(p)%certificate_reason)) cols(j, 22) = dispute_kind( &
            results(p)%certificate, results(p)%certificate_reason)
      end do
      cols(:, 16) = f;  cols(:, 17) = a
      names = [character(len=24) :: xn, yn, &
         'period', 'label', 'lyapunov', 'lyapunov_error', 'impacts_stop1', 'peak_force_stop1', &
         'rms_force_stop1', 'work_rate_stop1', 'status', 'certificate', 'n_attractors', &
         'lyapunov_periods', 'transient_periods', 'frequency_hz', 'amplitude_pp', &
         'normal_work_rate_total', 'wear_volume_rate_total', 'contact_fraction_max', &
         'impacts_total', 'dispute']
      units = [character(len=24) :: xu, yu, 'periods', 'p|0|-1|-2|-3', '1/s', &
         '1/s', '-', 'N', 'N', 'W', '0|1', '0|1|2', '-', 'periods', 'periods', 'Hz', 'm', 'W', &
         'm3/s', '-', '-', '0|1|2|3']
      ! the grid's extent in the title line, so that a shard's chart places its tiles on the
      ! whole grid (scripts/chaos_map.gp, lyapunov.gp)
      call set%table('.sweep.dat', sf%title // ': sweep points (label: p = period,' &
         // ' 0 undecided, -1 chaotic, -2 unsettled, -3 failed; certificate: 1 certified,' &
         // ' 2 disputed, 0 none; dispute: 1 contradiction, 2 chaotic transient, 3 a check' &
         // ' disagrees, 0 none); grid: ' // str(size(sf%grid_x)) // ' ' // trim(xn) &
         // ' from ' // num(minval(sf%grid_x)) // ' to ' // num(maxval(sf%grid_x)) // ' ' &
         // one_word(xu) // ', ' // str(size(sf%grid_y)) // ' ' // trim(yn) // ' from ' &
         // num(minval(sf%grid_y)) // ' to ' // num(maxval(sf%grid_y)) // ' ' // one_word(yu), &
         names, units, cols)
      deallocate(cols);  allocate(cols(m * nr, 6))
      do j = 1, m
         p = sf%points(j)
         cols((j - 1) * nr + 1:j * nr, 1) = x(j)
         cols((j - 1) * nr + 1:j * nr, 2) = y(j)
         cols((j - 1) * nr + 1:j * nr, 3:3) = array_table(results, [p], 11, nr)
         cols((j - 1) * nr + 1:j * nr, 4:4) = array_table(results, [p], 12, nr)
         cols((j - 1) * nr + 1:j * nr, 5) = results(p)%label
         cols((j - 1) * nr + 1:j * nr, 6) = results(p)%certificate
      end do
      call set%table('.bifurcation.dat', sf%title // ': Poincare points of every sweep point', &
         [character(len=24) :: xn, yn, 'strain', 'strain_rate', 'label', 'certificate'], &
         [character(len=24) :: xu, yu, '-', '1/s', 'p|0|-1|-2|-3', '0|1|2'], cols)
   end subroutine sweep_tables

   !> Column name of an axis: 'frequency' and 'amplitude_pp' for the forcing (as before),
   !> else the variable's name ('gap', 'k_theta', with its entry: 'gap_2'); an axis of several
   !> variables joins them: 'gap_1_2' (one name, its entries), else 'gap_1__friction_1'.
   pure function axis_name(variable) result(t)
      character(len=*), intent(in) :: variable           !! '&group name(i)', comma separated
      character(len=:), allocatable :: t, part, base, first_base, joined, entries
      logical :: same
      integer :: a, b, k, n
      if (variable == '&forcing frequency_hz') then
         t = 'frequency'
         return
      else if (variable == '&forcing amplitude_pp') then
         t = 'amplitude_pp'
         return
      end if
      joined = '';  entries = '';  first_base = '';  same = .true.;  n = 0
      a = 1
      do
         b = index(variable(a:), ',')
         if (b == 0) then
            b = len(variable) + 1
         else
            b = a + b - 1
         end if
         part = trim(adjustl(variable(a:b - 1)))
         k = index(part, ' ')
         part = trim(part(k + 1:))
         base = part
         k = index(part, '(')
         if (k > 0) then
            base = part(1:k - 1)
            entries = entries // '_' // part(k + 1:len(part) - 1)
            part = base // '_' // part(k + 1:len(part) - 1)
         else
            same = .false.
         end if
         n = n + 1
         if (n == 1) then
            joined = part;  first_base = base
         else
            same = same .and. base == first_base
            joined = joined // '__' // part
         end if
         if (b > len(variable)) exit
         a = b + 1
      end do
      t = joined
      if (n > 1 .and. same) t = first_base // entries
   end function axis_name

   !> Read a sweep file back: its description and its points into `results` (sized to all
   !> points of the sweep on return).
   subroutine read_sweep(path, sf, results, err)
      character(len=*), intent(in) :: path                         !! file
      type(sweep_file_t), intent(out) :: sf                        !! description
      type(point_result_t), allocatable, intent(inout) :: results(:) !! points land here
      type(error_t), allocatable, intent(out) :: err               !! I/O failure
      character(len=*), parameter :: here = 'gapbeam_sweep_output:read_sweep: '
      type(h5_reader_t) :: h5
      type(stat_t) :: st(size(array_names))
      type(text_list_t) :: tv(size(text_names))
      integer :: total, j, n, k, m
      integer, allocatable :: iv(:, :), ione(:)
      real(dp), allocatable :: rv(:, :), xv(:), yv(:), one(:)
      character(len=:), allocatable :: kinds(:), axis_order
      type(point_result_t), allocatable :: drawn(:)
      logical :: aligned, ok
      call h5%open(path, err);  if (allocated(err)) return
      call h5%read_attr('/', 'axis_order', axis_order, err)
      if (allocated(err)) then
         call fatal_error(err, here // path // ' was written by an older gapbeam (no ' &
            // 'axis_order attribute; its impact arrays are transposed): merge it with the ' &
            // 'version that wrote it')
         call h5%close()
         return
      end if
      call h5%read_text('/deck', sf%deck_text)
      call read_warnings(h5, sf)
      call h5%read_text('/sweep/title', sf%title)
      call h5%read('/sweep/grid_frequency_hz', sf%grid_frequency_hz)
      call h5%read('/sweep/grid_amplitude_pp', sf%grid_amplitude_pp)
      call h5%read_text('/sweep/x_variable', sf%x_variable)
      call h5%read_text('/sweep/y_variable', sf%y_variable)
      call h5%read('/sweep/grid_x', sf%grid_x)
      call h5%read('/sweep/grid_y', sf%grid_y)
      call h5%read_units('/sweep/grid_x', sf%x_units)
      call h5%read_units('/sweep/grid_y', sf%y_units)
      call h5%read('/sweep/shard_index', sf%shard_index)
      call h5%read('/sweep/shard_count', sf%shard_count)
      call h5%read('/sweep/n_points_total', total)
      call h5%read('/sweep/point_index', sf%points)
      call h5%read('/sweep/x', xv)
      call h5%read('/sweep/y', yv)
      n = size(sf%points)
      aligned = size(xv) == n .and. size(yv) == n
      allocate(iv(n, size(int_names)), rv(n, size(real_names)))
      iv = 0;  rv = 0.0_dp   ! fields added later are zero in files written before them
      do k = 1, size(int_names)
         if (.not. h5%exists('/sweep/' // trim(int_names(k)))) cycle
         call h5%read('/sweep/' // trim(int_names(k)), ione)
         aligned = aligned .and. size(ione) == n
         if (aligned) iv(:, k) = ione
      end do
      do k = 1, size(real_names)
         if (.not. h5%exists('/sweep/' // trim(real_names(k)))) cycle
         call h5%read('/sweep/' // trim(real_names(k)), one)
         aligned = aligned .and. size(one) == n
         if (aligned) rv(:, k) = one
      end do
      do k = 1, size(text_names)
         call h5%read('/sweep/' // trim(text_names(k)), tv(k)%v)
         aligned = aligned .and. size(tv(k)%v) == n
      end do
      do k = 1, size(array_names)
         call read_array(h5, k, st)
         aligned = aligned .and. size(st(k)%v, 2) == n
      end do
      call h5%read('/sweep/starts/kind', kinds)
      sf%has_model = h5%exists('/model')
      allocate(drawn(n))
      call read_sweep_statistics(h5, drawn, [(j, j = 1, n)], ok)
      aligned = aligned .and. ok
      call h5%close(err)
      if (allocated(err)) return
      sf%start_kind = kinds
      if (.not. allocated(results)) allocate(results(total))
      if (.not. aligned) then
         call fatal_error(err, here // path // ': a per-point dataset of /sweep does not have ' &
            // 'one entry per point')
      else if (size(results) /= total) then
         call fatal_error(err, here // path // ' has ' // str(total) // ' points in all, the ' &
            // 'other files ' // str(size(results)))
      else if (any(sf%points < 1 .or. sf%points > total)) then
         call fatal_error(err, here // path // ': a point index outside 1..' // str(total))
      end if
      if (allocated(err)) return
      do j = 1, n
         associate (r => results(sf%points(j)))
            call set_int_fields(r, iv(j, :))
            call set_real_fields(r, rv(j, :))
            do k = 1, size(text_names)
               call set_text_field(r, k, trim(tv(k)%v(j)))
            end do
            r%x = xv(j);  r%y = yv(j)
            do k = 1, size(array_names)   ! without the padding past the point's own values
               m = size(st(k)%v, 1)
               if (k == 13) m = min(m, max(0, r%lyapunov_periods))
               if (index(array_names(k), 'attractors/') == 1) m = r%n_attractors
               call set_array_field(r, k, st(k)%v(1:m, j))
            end do
            r%n_draws = drawn(j)%n_draws
            if (allocated(drawn(j)%draw_mean)) then
               call move_alloc(drawn(j)%draw_mean, r%draw_mean)
               call move_alloc(drawn(j)%draw_ci, r%draw_ci)
            end if
         end associate
      end do
   end subroutine read_sweep

   !> Array k (array_names) of a sweep file, as reals; an array that files of an older gapbeam
   !> lack (array_late) as 0, the attractors' mean transients as NaN.
   subroutine read_array(h5, k, st)
      type(h5_reader_t), intent(inout) :: h5             !! open file
      integer, intent(in) :: k                           !! the array
      type(stat_t), intent(inout) :: st(:)               !! the arrays read (those before k)
      character(len=:), allocatable :: path
      integer, allocatable :: iv(:, :)
      path = '/sweep/' // trim(array_names(k))
      if (array_late(k) .and. .not. h5%exists(path)) then
         allocate(st(k)%v, mold=st(merge(1, 14, array_extent(k) == 1))%v)
         st(k)%v = 0.0_dp
         if (array_extent(k) == 4 .and. array_type(k:k) == 'r') st(k)%v = ieee_value(0.0_dp, &
                                                                              ieee_quiet_nan)
      else if (array_type(k:k) == 'i') then
         call h5%read(path, iv)
         st(k)%v = real(iv, dp)
      else
         call h5%read(path, st(k)%v)
      end if
   end subroutine read_array

   !> Merge shard files into OUT (prefix without '.h5'): all from one deck, shards 1..N each
   !> exactly once, every point present once. The result is written by write_sweep, like a
   !> single-process run.
   subroutine merge_sweep(out_prefix, paths, write_text, err, n_failed)
      character(len=*), intent(in) :: out_prefix         !! output prefix
      character(len=*), intent(in) :: paths(:)           !! shard files
      logical, intent(in) :: write_text                  !! also the text tables
      type(error_t), allocatable, intent(out) :: err     !! mismatch or I/O failure
      integer, intent(out), optional :: n_failed         !! failed runs (points or starts)
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
      merged%shard_index = 1;  merged%shard_count = 1
      merged%points = [(p, p = 1, size(results))]
      merged%parameters_source = trim(paths(1))
      call write_sweep(out_prefix, merged, results, write_text, err)
      if (present(n_failed)) then
         n_failed = 0
         do p = 1, size(results)
            if (allocated(results(p)%start_label)) then
               n_failed = n_failed + count(results(p)%start_label == label_failed)
            else if (results(p)%status /= 0) then
               n_failed = n_failed + 1
            end if
         end do
      end if
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

   !> A unit as one word (blanks as '.', the UDUNITS-2 product): the grid line is read by words.
   pure function one_word(u) result(t)
      character(len=*), intent(in) :: u                  !! unit
      character(len=:), allocatable :: t
      integer :: k
      t = trim(adjustl(u))
      if (len(t) == 0) t = '1'
      do k = 1, len(t)
         if (t(k:k) == ' ') t(k:k) = '.'
      end do
   end function one_word

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
