!> Sweep result files: HDF5 (one per shard, or the whole sweep), gnuplot-ready text, and the
!> merge of shard files into the file a single process would have written.
!>
!> HDF5 layout: /deck; /sweep/grid_frequency_hz, /sweep/grid_amplitude_pp (the axes);
!> /sweep/shard_index, /sweep/shard_count, /sweep/n_points_total; per point of the file, in
!> point order: /sweep/point_index, frequency_hz, amplitude_pp, period, label, label_text,
!> lyapunov, lyapunov_error, status, steps, seconds; /sweep/impacts/<stat> (points, stops);
!> /sweep/poincare/strain and strain_rate (recorded periods, points);
!> /sweep/lyapunov_running (periods, points).
module gapbeam_sweep_output
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_hdf5_output, only: h5_writer_t, h5_reader_t
   use gapbeam_files, only: write_table, make_parent_directory
   use gapbeam_results, only: point_result_t, label_text
   implicit none
   private
   public :: sweep_file_t, write_sweep, read_sweep, merge_sweep

   !> What a sweep file holds besides the points.
   type :: sweep_file_t
      character(len=:), allocatable :: deck_text     !! effective deck text
      character(len=:), allocatable :: title         !! job title
      real(dp), allocatable :: grid_frequency_hz(:)  !! frequency axis [Hz]
      real(dp), allocatable :: grid_amplitude_pp(:)  !! amplitude axis [m]
      integer :: shard_index = 1                     !! this file's shard
      integer :: shard_count = 1                     !! shards of the sweep
      integer, allocatable :: points(:)              !! point indices in the file (ascending)
   end type sweep_file_t

contains

   !> Write points `sf%points` of `results` to PREFIX.h5 (and the text tables when asked).
   subroutine write_sweep(prefix, sf, results, write_text, err)
      character(len=*), intent(in) :: prefix             !! output path prefix
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points (indexed by point)
      logical, intent(in) :: write_text                  !! also .sweep.dat, .bifurcation.dat
      type(error_t), allocatable, intent(out) :: err     !! I/O failure
      type(h5_writer_t) :: h5
      integer :: m, ns, nr, nl, j, p, nf
      real(dp), allocatable :: f(:), a(:), r2(:, :), cols(:, :)
      integer, allocatable :: i2(:, :)
      character(len=16), allocatable :: labels(:)
      character(len=24), allocatable :: names(:), units(:)

      m = size(sf%points);  nf = size(sf%grid_frequency_hz)
      ns = 0;  nr = 0;  nl = 0
      if (m > 0) then
         ns = size(results(sf%points(1))%peak_force)
         nr = size(results(sf%points(1))%p_strain)
         nl = size(results(sf%points(1))%lyapunov_running)
      end if
      allocate(f(m), a(m), labels(m))
      do j = 1, m
         p = sf%points(j)
         f(j) = sf%grid_frequency_hz(mod(p - 1, nf) + 1)
         a(j) = sf%grid_amplitude_pp((p - 1) / nf + 1)
         labels(j) = label_text(results(p)%label)
      end do
      call make_parent_directory(prefix // '.h5', err);  if (allocated(err)) return
      call h5%create(prefix // '.h5', err);  if (allocated(err)) return
      call h5%write_text('/deck', sf%deck_text, err);  if (failed()) return
      call h5%write_text('/sweep/title', sf%title, err);  if (failed()) return
      call h5%write('/sweep/grid_frequency_hz', sf%grid_frequency_hz, 'Hz', err)
      if (failed()) return
      call h5%write('/sweep/grid_amplitude_pp', sf%grid_amplitude_pp, 'm', err)
      if (failed()) return
      call h5%write('/sweep/shard_index', sf%shard_index, '-', err);  if (failed()) return
      call h5%write('/sweep/shard_count', sf%shard_count, '-', err);  if (failed()) return
      call h5%write('/sweep/n_points_total', nf * size(sf%grid_amplitude_pp), '-', err)
      if (failed()) return
      call h5%write('/sweep/point_index', sf%points, '-', err);  if (failed()) return
      call h5%write('/sweep/frequency_hz', f, 'Hz', err);  if (failed()) return
      call h5%write('/sweep/amplitude_pp', a, 'm', err);  if (failed()) return
      call h5%write('/sweep/period', [(results(sf%points(j))%period, j = 1, m)], &
                    'forcing periods', err);  if (failed()) return
      call h5%write('/sweep/label', [(results(sf%points(j))%label, j = 1, m)], &
                    'p >= 1: period p; 0: undecided; -1: chaotic', err);  if (failed()) return
      call h5%write('/sweep/label_text', labels, '-', err);  if (failed()) return
      call h5%write('/sweep/lyapunov', [(results(sf%points(j))%lyapunov, j = 1, m)], '1/s', err)
      if (failed()) return
      call h5%write('/sweep/lyapunov_error', [(results(sf%points(j))%lyapunov_error, &
                    j = 1, m)], '1/s', err);  if (failed()) return
      call h5%write('/sweep/status', [(results(sf%points(j))%status, j = 1, m)], &
                    '0: done, 1: failed', err);  if (failed()) return
      call h5%write('/sweep/steps', [(real(results(sf%points(j))%steps, dp), j = 1, m)], '-', err)
      if (failed()) return
      call h5%write('/sweep/seconds', [(results(sf%points(j))%seconds, j = 1, m)], 's', err)
      if (failed()) return
      allocate(i2(m, ns))
      do j = 1, m
         i2(j, :) = results(sf%points(j))%n_impacts
      end do
      call h5%write('/sweep/impacts/count', reshape(real(i2, dp), [m, ns]), '-', err)
      if (failed()) return
      call stat('/sweep/impacts/peak_force', 1, 'N');  if (allocated(err)) return
      call stat('/sweep/impacts/rms_force', 2, 'N');  if (allocated(err)) return
      call stat('/sweep/impacts/contact_fraction', 3, '-');  if (allocated(err)) return
      call stat('/sweep/impacts/impulse_per_period', 4, 'N s');  if (allocated(err)) return
      call stat('/sweep/impacts/work_rate', 5, 'W');  if (allocated(err)) return
      allocate(r2(nr, m))
      do j = 1, m
         r2(:, j) = results(sf%points(j))%p_strain
      end do
      call h5%write('/sweep/poincare/strain', r2, '-', err);  if (failed()) return
      do j = 1, m
         r2(:, j) = results(sf%points(j))%p_strain_rate
      end do
      call h5%write('/sweep/poincare/strain_rate', r2, '1/s', err);  if (failed()) return
      deallocate(r2);  allocate(r2(nl, m))
      do j = 1, m
         r2(:, j) = results(sf%points(j))%lyapunov_running
      end do
      call h5%write('/sweep/lyapunov_running', r2, '1/s', err);  if (failed()) return
      call h5%close(err);  if (allocated(err)) return
      if (.not. write_text) return

      ! one row per point
      allocate(cols(m, 6 + 4 * max(ns, 1)), names(6 + 4 * max(ns, 1)), units(6 + 4 * max(ns, 1)))
      cols = 0.0_dp
      cols(:, 1) = f;  cols(:, 2) = a
      do j = 1, m
         p = sf%points(j)
         cols(j, 3) = results(p)%period;  cols(j, 4) = results(p)%label
         cols(j, 5) = results(p)%lyapunov;  cols(j, 6) = results(p)%lyapunov_error
         if (ns > 0) then
            cols(j, 7) = results(p)%n_impacts(1);  cols(j, 8) = results(p)%peak_force(1)
            cols(j, 9) = results(p)%rms_force(1);  cols(j, 10) = results(p)%work_rate(1)
         end if
      end do
      names(1:10) = [character(len=24) :: 'frequency', 'amplitude_pp', 'period', 'label', &
         'lyapunov', 'lyapunov_error', 'impacts_stop1', 'peak_force_stop1', 'rms_force_stop1', &
         'work_rate_stop1']
      units(1:10) = [character(len=24) :: 'Hz', 'm', 'periods', 'p|0|-1', '1/s', '1/s', '-', &
         'N', 'N', 'W']
      call write_table(prefix // '.sweep.dat', sf%title // ': sweep points (label: p = period,' &
         // ' 0 undecided, -1 chaotic)', names(1:10), units(1:10), cols(:, 1:10), err)
      if (allocated(err)) return
      ! bifurcation data: every Poincare point with its forcing
      deallocate(cols);  allocate(cols(m * nr, 4))
      do j = 1, m
         p = sf%points(j)
         cols((j - 1) * nr + 1:j * nr, 1) = f(j)
         cols((j - 1) * nr + 1:j * nr, 2) = a(j)
         cols((j - 1) * nr + 1:j * nr, 3) = results(p)%p_strain
         cols((j - 1) * nr + 1:j * nr, 4) = results(p)%p_strain_rate
      end do
      call write_table(prefix // '.bifurcation.dat', sf%title // ': Poincare points of every ' &
         // 'sweep point', [character(len=24) :: 'frequency', 'amplitude_pp', 'strain', &
         'strain_rate'], [character(len=24) :: 'Hz', 'm', '-', '1/s'], cols, err)
   contains
      logical function failed()
         failed = allocated(err)
         if (failed) call h5%abort()
      end function failed

      subroutine stat(path, which, unit_text)
         character(len=*), intent(in) :: path, unit_text
         integer, intent(in) :: which
         real(dp) :: v(m, ns)
         integer :: q
         do q = 1, m
            select case (which)
            case (1);  v(q, :) = results(sf%points(q))%peak_force
            case (2);  v(q, :) = results(sf%points(q))%rms_force
            case (3);  v(q, :) = results(sf%points(q))%contact_fraction
            case (4);  v(q, :) = results(sf%points(q))%impulse_per_period
            case (5);  v(q, :) = results(sf%points(q))%work_rate
            end select
         end do
         call h5%write(path, v, unit_text, err)
         if (allocated(err)) call h5%abort()
      end subroutine stat
   end subroutine write_sweep

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
         rms(:, :), cf(:, :), imp(:, :), wr(:, :), ps(:, :), pr(:, :), lr(:, :)
      call h5%open(path, err);  if (allocated(err)) return
      call h5%read_text('/deck', sf%deck_text, err);  if (allocated(err)) goto 9
      call h5%read_text('/sweep/title', sf%title, err);  if (allocated(err)) goto 9
      call h5%read('/sweep/grid_frequency_hz', sf%grid_frequency_hz, err)
      if (allocated(err)) goto 9
      call h5%read('/sweep/grid_amplitude_pp', sf%grid_amplitude_pp, err)
      if (allocated(err)) goto 9
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
         results(p)%seconds = secs(j);  results(p)%n_impacts = nint(cnt(j, :))
         results(p)%peak_force = pk(j, :);  results(p)%rms_force = rms(j, :)
         results(p)%contact_fraction = cf(j, :);  results(p)%impulse_per_period = imp(j, :)
         results(p)%work_rate = wr(j, :);  results(p)%p_strain = ps(:, j)
         results(p)%p_strain_rate = pr(:, j);  results(p)%lyapunov_running = lr(:, j)
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
      call write_sweep(out_prefix, merged, results, write_text, err)
   end subroutine merge_sweep

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
