!> Checkpoint of a sweep: every finished point is appended to `PREFIX.checkpoint` as it comes,
!> so a sweep killed at any moment and started again with the same deck runs only the points
!> not yet recorded, and ends with the same results as an uninterrupted run.
!>
!> File layout (stream access, native byte order): the text 'GAPBEAM-CHECKPOINT-1', the
!> signature length (int64) and the signature (the effective deck text and the shard), then
!> records: begin mark (int32), point index (int32), payload length m (int32), m reals
!> (pack_point), end mark (int32). A record cut short by a kill fails the marks and ends the
!> reading; the next record is written over it. A checkpoint whose signature differs from the
!> run's is refused, never mixed.
module gapbeam_checkpoint
   use, intrinsic :: iso_fortran_env, only: int32, int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_results, only: point_result_t
   use gapbeam_files, only: remove_file, file_exists
   implicit none
   private
   public :: checkpoint_t, checkpoint_open, checkpoint_append, checkpoint_close, pack_point, &
      unpack_point

   character(len=*), parameter :: magic = 'GAPBEAM-CHECKPOINT-1'
   integer(int32), parameter :: mark_begin = 1296253778_int32   ! 'RECM' in ASCII
   integer(int32), parameter :: mark_end = 1145980242_int32     ! 'REND'

   !> An open checkpoint file.
   type :: checkpoint_t
      integer :: unit = -1                       !! Fortran unit
      character(len=:), allocatable :: path      !! file path
      integer(int64) :: next_pos = 1             !! where the next record goes
   end type checkpoint_t

contains

   !> Open (or create) the checkpoint; load the points it already holds.
   subroutine checkpoint_open(ck, path, signature, results, done, n_loaded, err)
      type(checkpoint_t), intent(out) :: ck              !! checkpoint
      character(len=*), intent(in) :: path               !! file path
      character(len=*), intent(in) :: signature          !! deck text and shard
      type(point_result_t), intent(inout) :: results(:)  !! loaded points land here
      logical, intent(inout) :: done(:)                  !! set for loaded points
      integer, intent(out) :: n_loaded                   !! points loaded
      type(error_t), allocatable, intent(out) :: err     !! I/O error or foreign checkpoint
      character(len=len(magic)) :: head
      character(len=:), allocatable :: sig
      integer(int64) :: sig_len, pos, fsize
      integer(int32) :: m1, p, m, m2
      real(dp), allocatable :: x(:)
      type(point_result_t) :: pr
      integer :: ios
      logical :: ok
      character(len=256) :: msg
      ck%path = path
      n_loaded = 0
      if (file_exists(path)) then
         open(newunit=ck%unit, file=path, access='stream', form='unformatted', status='old', &
              action='readwrite', iostat=ios, iomsg=msg)
         if (ios /= 0) then
            call fatal_error(err, 'gapbeam_checkpoint: cannot open ' // path // ': ' // trim(msg))
            return
         end if
         inquire(unit=ck%unit, size=fsize)
         read(ck%unit, pos=1, iostat=ios) head, sig_len
         if (ios /= 0 .or. head /= magic .or. sig_len < 0 .or. sig_len > fsize) then
            close(ck%unit)
            call fatal_error(err, 'gapbeam_checkpoint: ' // path // ' is not a gapbeam sweep ' &
               // 'checkpoint; remove it or choose another output')
            return
         end if
         allocate(character(len=sig_len) :: sig)
         read(ck%unit, iostat=ios) sig
         if (ios /= 0 .or. sig /= signature) then
            close(ck%unit)
            call fatal_error(err, 'gapbeam_checkpoint: ' // path // ' belongs to a different ' &
               // 'deck or shard; it is not mixed with this run: remove it to start afresh, ' &
               // 'or run the deck that wrote it')
            return
         end if
         inquire(unit=ck%unit, pos=pos)
         do
            read(ck%unit, pos=pos, iostat=ios) m1, p, m
            if (ios /= 0 .or. m1 /= mark_begin .or. p < 1 .or. p > size(results) .or. m < 0 &
                .or. pos + 16_int64 + 8_int64 * m > fsize + 1) exit
            if (allocated(x)) deallocate(x)
            allocate(x(m))
            read(ck%unit, iostat=ios) x, m2
            if (ios /= 0 .or. m2 /= mark_end) exit
            call unpack_point(x, pr, ok)
            if (.not. ok) exit
            results(p) = pr
            if (.not. done(p)) n_loaded = n_loaded + 1
            done(p) = .true.
            inquire(unit=ck%unit, pos=pos)
         end do
         ck%next_pos = pos
      else
         open(newunit=ck%unit, file=path, access='stream', form='unformatted', status='new', &
              action='readwrite', iostat=ios, iomsg=msg)
         if (ios /= 0) then
            call fatal_error(err, 'gapbeam_checkpoint: cannot create ' // path // ': ' &
               // trim(msg))
            return
         end if
         write(ck%unit, pos=1) magic, int(len(signature), int64), signature
         flush(ck%unit)
         inquire(unit=ck%unit, pos=ck%next_pos)
      end if
   end subroutine checkpoint_open

   !> Append a finished point and flush it to disk.
   subroutine checkpoint_append(ck, p, pr, err)
      type(checkpoint_t), intent(inout) :: ck          !! checkpoint
      integer, intent(in) :: p                         !! point index
      type(point_result_t), intent(in) :: pr           !! its results
      type(error_t), allocatable, intent(out) :: err   !! write failure
      real(dp), allocatable :: x(:)
      integer :: ios
      x = pack_point(pr)
      write(ck%unit, pos=ck%next_pos, iostat=ios) mark_begin, int(p, int32), &
         int(size(x), int32), x, mark_end
      if (ios /= 0) then
         call fatal_error(err, 'gapbeam_checkpoint: cannot write to ' // ck%path // ' (point ' &
            // str(p) // ')')
         return
      end if
      flush(ck%unit)
      inquire(unit=ck%unit, pos=ck%next_pos)
   end subroutine checkpoint_append

   !> Close the checkpoint, and delete it when the sweep is complete.
   subroutine checkpoint_close(ck, delete)
      type(checkpoint_t), intent(inout) :: ck   !! checkpoint
      logical, intent(in) :: delete             !! remove the file
      if (ck%unit /= -1) close(ck%unit)
      ck%unit = -1
      if (delete .and. allocated(ck%path)) call remove_file(ck%path)
   end subroutine checkpoint_close

   !> A point's results as one real array (for checkpoints); integers are stored exactly.
   pure function pack_point(pr) result(x)
      type(point_result_t), intent(in) :: pr   !! a finished point
      real(dp), allocatable :: x(:)
      x = [real(pr%status, dp), real(pr%period, dp), real(pr%label, dp), pr%lyapunov, &
           pr%lyapunov_error, real(pr%steps, dp), pr%seconds, &
           real(size(pr%lyapunov_running), dp), pr%lyapunov_running, &
           real(size(pr%n_impacts), dp), real(pr%n_impacts, dp), pr%peak_force, pr%rms_force, &
           pr%contact_fraction, pr%impulse_per_period, pr%work_rate, &
           real(size(pr%p_strain), dp), pr%p_strain, pr%p_strain_rate, &
           real(size(pr%u_end), dp), pr%u_end, pr%v_end]
   end function pack_point

   !> Inverse of pack_point; ok is false when x is not a well-formed record.
   pure subroutine unpack_point(x, pr, ok)
      real(dp), intent(in) :: x(:)                !! packed record
      type(point_result_t), intent(out) :: pr     !! the point
      logical, intent(out) :: ok                  !! record well formed
      integer :: k, m, ns, nr, n
      ok = .false.
      if (size(x) < 9) return
      pr%status = nint(x(1));  pr%period = nint(x(2));  pr%label = nint(x(3))
      pr%lyapunov = x(4);  pr%lyapunov_error = x(5);  pr%steps = nint(x(6), int64)
      pr%seconds = x(7)
      k = 8
      m = nint(x(k));  if (m < 0 .or. k + m > size(x)) return
      pr%lyapunov_running = x(k + 1:k + m);  k = k + m + 1
      if (k > size(x)) return
      ns = nint(x(k));  if (ns < 0 .or. k + 6 * ns > size(x)) return
      pr%n_impacts = nint(x(k + 1:k + ns));  k = k + ns
      pr%peak_force = x(k + 1:k + ns);  k = k + ns
      pr%rms_force = x(k + 1:k + ns);  k = k + ns
      pr%contact_fraction = x(k + 1:k + ns);  k = k + ns
      pr%impulse_per_period = x(k + 1:k + ns);  k = k + ns
      pr%work_rate = x(k + 1:k + ns);  k = k + ns + 1
      if (k > size(x)) return
      nr = nint(x(k));  if (nr < 0 .or. k + 2 * nr > size(x)) return
      pr%p_strain = x(k + 1:k + nr);  k = k + nr
      pr%p_strain_rate = x(k + 1:k + nr);  k = k + nr + 1
      if (k > size(x)) return
      n = nint(x(k));  if (n < 0 .or. k + 2 * n /= size(x)) return
      pr%u_end = x(k + 1:k + n);  k = k + n
      pr%v_end = x(k + 1:k + n)
      ok = .true.
   end subroutine unpack_point
end module gapbeam_checkpoint
