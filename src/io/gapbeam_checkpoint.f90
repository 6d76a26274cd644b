!> Checkpoint of a sweep: every finished point is appended to `PREFIX.checkpoint` as it comes,
!> so a sweep killed at any moment and started again with the same deck runs only the points
!> not yet recorded, and ends with the same results as an uninterrupted run.
!>
!> A record holds one slot of the sweep (a point's start, gapbeam_sweep), indexed by slot.
!>
!> File layout (stream access, native byte order): the text 'GAPBEAM-CHECKPOINT-4', the deck
!> hash (int64: CRC-32 of the signature), the signature length (int64) and the signature (the
!> effective deck text and the shard), then records: begin mark (int32), point index (int32),
!> payload length m (int32), m reals (pack_point), checksum (int64: CRC-32 of the bytes of
!> the point index, m and the reals), end mark (int32).
!>
!> Nothing read back is trusted without its checksum. A record that fails it (a flipped byte),
!> is not a well-formed point, or disagrees with another record of the same point is reported
!> and its point computed again; a record cut short (a kill while writing) ends the reading,
!> and the next record is written over it. A checkpoint whose hash or signature differs from
!> the run's is refused, never mixed.
module gapbeam_checkpoint
   use, intrinsic :: iso_fortran_env, only: int8, int32, int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_results, only: point_result_t
   use gapbeam_files, only: remove_file, file_exists, file_size
   implicit none
   private
   public :: checkpoint_t, checkpoint_open, checkpoint_append, checkpoint_close, pack_point, &
      unpack_point, crc32

   character(len=*), parameter :: magic = 'GAPBEAM-CHECKPOINT-4'
   character(len=*), parameter :: magic_1 = 'GAPBEAM-CHECKPOINT-1'   ! no checksums: refused
   character(len=*), parameter :: magic_2 = 'GAPBEAM-CHECKPOINT-2'   ! no evidence: refused
   character(len=*), parameter :: magic_3 = 'GAPBEAM-CHECKPOINT-3'   ! no wear: refused
   integer(int32), parameter :: mark_begin = 1296253778_int32   ! 'RECM' in ASCII
   integer(int32), parameter :: mark_end = 1145980242_int32     ! 'REND'

   !> An open checkpoint file.
   type :: checkpoint_t
      integer :: unit = -1                       !! Fortran unit
      character(len=:), allocatable :: path      !! file path
      integer(int64) :: next_pos = 1             !! where the next record goes
   end type checkpoint_t

contains

   !> Open (or create) the checkpoint; load the points it already holds. `report` lists what
   !> was not trusted, one line each ('' when all was well).
   subroutine checkpoint_open(ck, path, signature, results, done, n_loaded, report, err)
      type(checkpoint_t), intent(out) :: ck              !! checkpoint
      character(len=*), intent(in) :: path               !! file path
      character(len=*), intent(in) :: signature          !! deck text and shard
      type(point_result_t), intent(inout) :: results(:)  !! loaded points land here
      logical, intent(inout) :: done(:)                  !! set for loaded points
      integer, intent(out) :: n_loaded                   !! points loaded
      character(len=:), allocatable, intent(out) :: report  !! records not trusted
      type(error_t), allocatable, intent(out) :: err     !! I/O error or foreign checkpoint
      character(len=len(magic)) :: head
      character(len=:), allocatable :: sig
      integer(int64) :: sig_len, hash, fsize
      integer :: ios
      character(len=256) :: msg
      ck%path = path
      n_loaded = 0
      report = ''
      if (.not. file_exists(path)) then
         open(newunit=ck%unit, file=path, access='stream', form='unformatted', status='new', &
              action='readwrite', iostat=ios, iomsg=msg)
         if (ios /= 0) then
            call fatal_error(err, 'gapbeam_checkpoint: cannot create ' // path // ': ' &
               // trim(msg))
            return
         end if
         write(ck%unit, pos=1, iostat=ios, iomsg=msg) magic, crc32(text_bytes(signature)), &
            int(len(signature), int64), signature
         if (ios == 0) flush(ck%unit, iostat=ios, iomsg=msg)
         if (ios /= 0) then
            close(ck%unit, status='delete')
            ck%unit = -1
            call fatal_error(err, 'gapbeam_checkpoint: cannot write ' // path // ': ' // trim(msg))
            return
         end if
         inquire(unit=ck%unit, pos=ck%next_pos)
         if (file_size(path) /= ck%next_pos - 1) then
            close(ck%unit, status='delete')
            ck%unit = -1
            call fatal_error(err, 'gapbeam_checkpoint: cannot write ' // path // ' (is the ' &
               // 'disk full?)')
         end if
         return
      end if
      open(newunit=ck%unit, file=path, access='stream', form='unformatted', status='old', &
           action='readwrite', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(err, 'gapbeam_checkpoint: cannot open ' // path // ': ' // trim(msg))
         return
      end if
      inquire(unit=ck%unit, size=fsize)
      head = ''
      read(ck%unit, pos=1, iostat=ios) head, hash, sig_len
      if (head == magic_1) then
         call refuse(ck, 'was written by an older gapbeam, without checksums: remove it (its ' &
            // 'points are then computed again)', err)
         return
      end if
      if (head == magic_2) then
         call refuse(ck, 'was written by an older gapbeam, without the evidence and ' &
            // 'certificates of the labels: remove it (its points are then computed again)', err)
         return
      end if
      if (head == magic_3) then
         call refuse(ck, 'was written by an older gapbeam, without the wear outputs of the ' &
            // 'supports: remove it (its points are then computed again)', err)
         return
      end if
      if (ios /= 0 .or. head /= magic .or. sig_len < 0 .or. sig_len > fsize) then
         call refuse(ck, 'is not a gapbeam sweep checkpoint (or its header is damaged); ' &
            // 'remove it or choose another output', err)
         return
      end if
      allocate(character(len=sig_len) :: sig)
      read(ck%unit, iostat=ios) sig
      if (ios /= 0 .or. hash /= crc32(text_bytes(sig))) then
         call refuse(ck, 'has a damaged header (its deck hash does not match its deck text): ' &
            // 'remove it to start afresh', err)
         return
      end if
      if (hash /= crc32(text_bytes(signature)) .or. sig /= signature) then
         call refuse(ck, 'belongs to a different deck or shard; it is not mixed with this run: ' &
            // 'remove it to start afresh, or run the deck that wrote it', err)
         return
      end if
      call load_records(ck, fsize, results, done, n_loaded, report)
   end subroutine checkpoint_open

   !> Close a checkpoint that is not used, and say why.
   subroutine refuse(ck, why, err)
      type(checkpoint_t), intent(inout) :: ck          !! open checkpoint, closed here
      character(len=*), intent(in) :: why              !! reason, after the file name
      type(error_t), allocatable, intent(inout) :: err !! set
      close(ck%unit)
      ck%unit = -1
      call fatal_error(err, 'gapbeam_checkpoint: ' // ck%path // ' ' // why)
   end subroutine refuse

   !> Read the records after the header; set `ck%next_pos` after the last whole record.
   subroutine load_records(ck, fsize, results, done, n_loaded, report)
      type(checkpoint_t), intent(inout) :: ck            !! open checkpoint, header read
      integer(int64), intent(in) :: fsize                !! file size [bytes]
      type(point_result_t), intent(inout) :: results(:)  !! loaded points land here
      logical, intent(inout) :: done(:)                  !! set for loaded points
      integer, intent(out) :: n_loaded                   !! points loaded
      character(len=:), allocatable, intent(inout) :: report  !! records not trusted
      integer(int64) :: pos, sum_stored
      integer(int32) :: m1, p, m, m2
      real(dp), allocatable :: x(:)
      integer(int64), allocatable :: crc_of(:)           ! checksum of the record loaded per point
      logical, allocatable :: conflict(:)
      type(point_result_t) :: pr
      character(len=:), allocatable :: at
      integer :: ios, k
      logical :: ok
      allocate(crc_of(size(results)), source=-1_int64)
      allocate(conflict(size(results)), source=.false.)
      n_loaded = 0
      inquire(unit=ck%unit, pos=pos)
      k = 0
      do
         read(ck%unit, pos=pos, iostat=ios) m1, p, m
         if (ios /= 0 .or. m1 /= mark_begin .or. m < 0 .or. &
             pos + 24_int64 + 8_int64 * m > fsize + 1) exit
         if (allocated(x)) deallocate(x)
         allocate(x(m))
         read(ck%unit, iostat=ios) x, sum_stored, m2
         if (ios /= 0 .or. m2 /= mark_end) exit
         k = k + 1
         at = ck%path // ': record ' // str(k) // ' (byte ' // str_int64(pos) // ')'
         if (sum_stored /= record_crc(p, m, x)) then
            call add_line(report, at // ' fails its checksum: not trusted, its point is ' &
               // 'computed again')
         else if (p < 1 .or. p > size(results)) then
            call add_line(report, at // ' names point ' // str(int(p)) // ', outside 1..' &
               // str(size(results)) // ': ignored')
         else
            call unpack_point(x, pr, ok)
            if (.not. ok) then
               call add_line(report, at // ', point ' // str(int(p)) // ', is not a ' &
                  // 'well-formed point: not trusted, the point is computed again')
            else if (conflict(p)) then
               continue
            else if (crc_of(p) >= 0 .and. crc_of(p) /= sum_stored) then
               call add_line(report, at // ': point ' // str(int(p)) // ' has two different ' &
                  // 'records: neither is trusted, the point is computed again')
               conflict(p) = .true.
               if (done(p)) n_loaded = n_loaded - 1
               done(p) = .false.
            else if (crc_of(p) < 0) then
               crc_of(p) = sum_stored
               results(p) = pr
               if (.not. done(p)) n_loaded = n_loaded + 1
               done(p) = .true.
            end if                ! else: an identical copy of a record already loaded
         end if
         inquire(unit=ck%unit, pos=pos)
      end do
      if (pos <= fsize) call add_line(report, ck%path // ': the last ' &
         // str_int64(fsize - pos + 1) // ' bytes (from byte ' // str_int64(pos) // ') are not ' &
         // 'a whole record (a run stopped while writing?): dropped, and written over')
      ck%next_pos = pos
   end subroutine load_records

   !> Add a line to a report.
   subroutine add_line(report, line)
      character(len=:), allocatable, intent(inout) :: report   !! lines so far
      character(len=*), intent(in) :: line                     !! new line
      if (len(report) > 0) report = report // new_line('a')
      report = report // line
   end subroutine add_line

   !> Append a finished point and flush it to disk.
   subroutine checkpoint_append(ck, p, pr, err)
      type(checkpoint_t), intent(inout) :: ck          !! checkpoint
      integer, intent(in) :: p                         !! point index
      type(point_result_t), intent(in) :: pr           !! its results
      type(error_t), allocatable, intent(out) :: err   !! write failure
      real(dp), allocatable :: x(:)
      integer :: ios
      character(len=256) :: msg
      x = pack_point(pr)
      msg = ''
      write(ck%unit, pos=ck%next_pos, iostat=ios, iomsg=msg) mark_begin, int(p, int32), &
         int(size(x), int32), x, record_crc(int(p, int32), int(size(x), int32), x), mark_end
      if (ios == 0) flush(ck%unit, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(err, 'gapbeam_checkpoint: cannot write to ' // ck%path // ' (point ' &
            // str(p) // '): ' // trim(msg) // '; the points recorded before are kept')
         return
      end if
      inquire(unit=ck%unit, pos=ck%next_pos)
      ! gfortran reports no error when the disk is full: the size on disk tells
      if (file_size(ck%path) /= ck%next_pos - 1) then
         call fatal_error(err, 'gapbeam_checkpoint: cannot write to ' // ck%path // ' (point ' &
            // str(p) // '): only ' // str_int64(file_size(ck%path)) // ' of ' &
            // str_int64(ck%next_pos - 1) // ' bytes are stored (a full disk?); the ' &
            // 'points recorded before are kept')
      end if
   end subroutine checkpoint_append

   !> Close the checkpoint, and delete it when the sweep is complete.
   subroutine checkpoint_close(ck, delete)
      type(checkpoint_t), intent(inout) :: ck   !! checkpoint
      logical, intent(in) :: delete             !! remove the file
      integer :: ios
      if (ck%unit /= -1) close(ck%unit, iostat=ios)
      ck%unit = -1
      if (delete .and. allocated(ck%path)) call remove_file(ck%path)
   end subroutine checkpoint_close

   !> Checksum of a record: CRC-32 of the bytes of its point index, length and reals.
   pure function record_crc(p, m, x) result(crc)
      integer(int32), intent(in) :: p, m               !! point index, payload length
      real(dp), intent(in) :: x(:)                     !! payload
      integer(int64) :: crc
      crc = crc32(transfer(x, [0_int8]), crc32(transfer([p, m], [0_int8])))
   end function record_crc

   !> The bytes of a text.
   pure function text_bytes(text) result(b)
      character(len=*), intent(in) :: text             !! text
      integer(int8), allocatable :: b(:)
      integer :: i
      allocate(b(len(text)))
      do i = 1, len(text)
         b(i) = int(iachar(text(i:i)) - merge(256, 0, iachar(text(i:i)) > 127), int8)
      end do
   end function text_bytes

   !> CRC-32 (the zlib and PNG checksum: reflected polynomial 0xEDB88320) of `bytes`, continuing
   !> from `previous` (the CRC of the bytes before) when given; a value in 0..2**32-1.
   pure function crc32(bytes, previous) result(crc)
      integer(int8), intent(in) :: bytes(:)            !! data
      integer(int64), intent(in), optional :: previous !! CRC of the preceding data
      integer(int64) :: crc
      integer(int64), parameter :: poly = 3988292384_int64     ! 0xEDB88320
      integer(int64), parameter :: mask = 4294967295_int64     ! 0xFFFFFFFF
      integer :: i, k
      crc = 0
      if (present(previous)) crc = previous
      crc = ieor(crc, mask)
      do i = 1, size(bytes)
         crc = ieor(crc, iand(int(bytes(i), int64), 255_int64))
         do k = 1, 8
            if (iand(crc, 1_int64) /= 0) then
               crc = ieor(ishft(crc, -1), poly)
            else
               crc = ishft(crc, -1)
            end if
         end do
      end do
      crc = ieor(crc, mask)
   end function crc32

   !> A 64-bit integer as text.
   pure function str_int64(i) result(s)
      integer(int64), intent(in) :: i                  !! value
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end function str_int64

   !> A point's results as one real array (for checkpoints); integers and characters are
   !> stored exactly (a text as its length, then one character code per real).
   pure function pack_point(pr) result(x)
      type(point_result_t), intent(in) :: pr   !! a finished point
      real(dp), allocatable :: x(:)
      x = [real(pr%status, dp), real(pr%period, dp), real(pr%label, dp), pr%lyapunov, &
           pr%lyapunov_error, real(pr%steps, dp), pr%seconds, &
           real(size(pr%lyapunov_running), dp), pr%lyapunov_running, &
           real(size(pr%n_impacts), dp), real(pr%n_impacts, dp), pr%peak_force, pr%rms_force, &
           pr%contact_fraction, pr%impulse_per_period, pr%work_rate, &
           real(size(pr%p_strain), dp), pr%p_strain, pr%p_strain_rate, &
           real(size(pr%u_end), dp), pr%u_end, pr%v_end, &
           real(pr%lyapunov_periods, dp), real(pr%lyapunov_converged, dp), &
           real(pr%period_max_tested, dp), pr%period_tolerance, real(pr%closest_period, dp), &
           pr%repeat_distance, real(pr%transient_periods, dp), real(pr%settle_windows, dp), &
           pr%window_difference, real(pr%settled, dp), pr%strain_range, pr%strain_rate_range, &
           pr%seconds_label, real(pr%certificate, dp), real(pr%accuracy_label, dp), &
           pr%accuracy_lyapunov, pr%accuracy_lyapunov_error, pr%accuracy_distance, &
           real(pr%perturbed_label, dp), pr%perturbed_lyapunov, pr%perturbed_lyapunov_error, &
           pr%perturbed_distance, pr%seconds_certify, pr%x, pr%y, pr%f1_open_hz, &
           text_reals(pr%method), text_reals(pr%certificate_reason), &
           text_reals(pr%accuracy_method), &
           real(size(wear(pr%normal_work_rate)), dp), wear(pr%normal_work_rate), &
           wear(pr%sliding_distance), wear(pr%friction_work_rate), wear(pr%wear_volume_rate)]
   end function pack_point

   !> A wear array of a point, empty when the point has none.
   pure function wear(x) result(y)
      real(dp), allocatable, intent(in) :: x(:)   !! per stop
      real(dp), allocatable :: y(:)
      if (allocated(x)) then
         y = x
      else
         allocate(y(0))
      end if
   end function wear

   !> A text (possibly unallocated: '') as its length and character codes.
   pure function text_reals(t) result(x)
      character(len=:), allocatable, intent(in) :: t   !! text
      real(dp), allocatable :: x(:)
      integer :: i
      if (.not. allocated(t)) then
         x = [0.0_dp]
      else
         x = [real(len(t), dp), (real(iachar(t(i:i)), dp), i = 1, len(t))]
      end if
   end function text_reals

   !> Inverse of pack_point; ok is false when x is not a well-formed record.
   pure subroutine unpack_point(x, pr, ok)
      real(dp), intent(in) :: x(:)                !! packed record
      type(point_result_t), intent(out) :: pr     !! the point
      logical, intent(out) :: ok                  !! record well formed
      integer :: k, m, ns, nr, n
      integer, parameter :: n_scalars = 26
      real(dp) :: s(n_scalars)
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
      n = nint(x(k));  if (n < 0 .or. k + 2 * n + n_scalars > size(x)) return
      pr%u_end = x(k + 1:k + n);  k = k + n
      pr%v_end = x(k + 1:k + n);  k = k + n
      s = x(k + 1:k + n_scalars);  k = k + n_scalars
      pr%lyapunov_periods = nint(s(1));  pr%lyapunov_converged = nint(s(2))
      pr%period_max_tested = nint(s(3));  pr%period_tolerance = s(4)
      pr%closest_period = nint(s(5));  pr%repeat_distance = s(6)
      pr%transient_periods = nint(s(7));  pr%settle_windows = nint(s(8))
      pr%window_difference = s(9);  pr%settled = nint(s(10))
      pr%strain_range = s(11);  pr%strain_rate_range = s(12);  pr%seconds_label = s(13)
      pr%certificate = nint(s(14));  pr%accuracy_label = nint(s(15))
      pr%accuracy_lyapunov = s(16);  pr%accuracy_lyapunov_error = s(17)
      pr%accuracy_distance = s(18);  pr%perturbed_label = nint(s(19))
      pr%perturbed_lyapunov = s(20);  pr%perturbed_lyapunov_error = s(21)
      pr%perturbed_distance = s(22);  pr%seconds_certify = s(23)
      pr%x = s(24);  pr%y = s(25);  pr%f1_open_hz = s(26)
      call take_text(x, k, pr%method, ok);  if (.not. ok) return
      call take_text(x, k, pr%certificate_reason, ok);  if (.not. ok) return
      call take_text(x, k, pr%accuracy_method, ok);  if (.not. ok) return
      ! the wear block: its size, then four per-stop arrays
      ok = .false.
      if (k + 1 > size(x)) return
      k = k + 1
      ns = nint(x(k));  if (ns < 0 .or. k + 4 * ns /= size(x)) return
      pr%normal_work_rate = x(k + 1:k + ns);  k = k + ns
      pr%sliding_distance = x(k + 1:k + ns);  k = k + ns
      pr%friction_work_rate = x(k + 1:k + ns);  k = k + ns
      pr%wear_volume_rate = x(k + 1:k + ns)
      ok = .true.
   end subroutine unpack_point

   !> The text stored after x(k) (see text_reals); k moves past it.
   pure subroutine take_text(x, k, t, ok)
      real(dp), intent(in) :: x(:)                        !! packed record
      integer, intent(inout) :: k                         !! last position read
      character(len=:), allocatable, intent(out) :: t     !! the text
      logical, intent(out) :: ok                          !! well formed
      integer :: n, i, c
      ok = .false.
      if (k + 1 > size(x)) return
      n = nint(x(k + 1))
      if (n < 0 .or. k + 1 + n > size(x)) return
      allocate(character(len=n) :: t)
      do i = 1, n
         c = nint(x(k + 1 + i))
         if (c < 0 .or. c > 127) return
         t(i:i) = achar(c)
      end do
      k = k + 1 + n
      ok = .true.
   end subroutine take_text
end module gapbeam_checkpoint
