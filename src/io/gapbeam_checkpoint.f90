!> Checkpoint of a sweep: every finished point is appended to `PREFIX.checkpoint` as it comes,
!> so a sweep killed at any moment and started again with the same deck runs only the points
!> not yet recorded, and ends with the same results as an uninterrupted run.
!>
!> A record holds one slot of the sweep (a point's start, gapbeam_sweep), indexed by slot.
!>
!> File layout (stream access, native byte order): the text 'GAPBEAM-CHECKPOINT-6', the deck
!> hash (int64: CRC-32 of the signature), the signature length (int64) and the signature (the
!> effective deck text and the shard), then records: begin mark (int32), point index (int32),
!> payload length m (int32), m reals (pack_point), checksum (int64), end mark (int32). The
!> checksum is the CRC-32 of the bytes of the point index, m and the reals, continued from the
!> deck hash (zlib.crc32(record_bytes, deck_hash) in Python): the CRC-32 of the signature
!> followed by the record, so that a record is valid in the checkpoint of its own deck and
!> shard only.
!>
!> Nothing read back is trusted without its checksum. A record that fails it (a flipped byte,
!> or a record copied from another deck's checkpoint), is not a well-formed point, records a
!> failed run (never written by gapbeam: failed runs are computed again), or disagrees with
!> another record of the same point is reported and its point computed again. Bytes that are
!> not a whole record (a damaged mark or length in the middle of the file, or a record cut
!> short by a kill at its end) are reported and skipped, and the records after them are read.
!> After any such finding the file is rewritten with the trusted records only (under a
!> temporary name, then renamed), so that appending continues on a clean file. A checkpoint
!> whose hash or signature differs from the run's is refused, never mixed.
module gapbeam_checkpoint
   use, intrinsic :: iso_fortran_env, only: int8, int32, int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_results, only: point_result_t
   use gapbeam_files, only: remove_file, file_exists, file_size, rename_file
   use gapbeam_checksum, only: crc32, text_bytes
   use gapbeam_point_fields, only: array_field, set_array_field
   implicit none
   private
   public :: checkpoint_t, checkpoint_open, checkpoint_append, checkpoint_close

   character(len=*), parameter :: magic = 'GAPBEAM-CHECKPOINT-6'
   character(len=*), parameter :: magic_1 = 'GAPBEAM-CHECKPOINT-1'   ! older formats: refused
   character(len=*), parameter :: magic_2 = 'GAPBEAM-CHECKPOINT-2'
   character(len=*), parameter :: magic_3 = 'GAPBEAM-CHECKPOINT-3'
   character(len=*), parameter :: magic_4 = 'GAPBEAM-CHECKPOINT-4'
   character(len=*), parameter :: magic_5 = 'GAPBEAM-CHECKPOINT-5'
   !> What each older format lacks, for the message that refuses it.
   character(len=*), parameter :: older(5) = [character(len=60) :: 'without checksums', &
      'without the evidence and certificates of the labels', &
      'without the wear outputs of the supports', &
      'whose record checksums do not cover the deck', &
      'without the starts and the rerun periods of the exponents']
   integer(int32), parameter :: mark_begin = 1296253778_int32   ! 'RECM' in ASCII
   integer(int32), parameter :: mark_end = 1145980242_int32     ! 'REND'
   integer(int64), parameter :: record_overhead = 24_int64      ! bytes of a record besides its reals

   !> An open checkpoint file.
   type :: checkpoint_t
      integer :: unit = -1                       !! Fortran unit
      character(len=:), allocatable :: path      !! file path
      integer(int64) :: next_pos = 1             !! where the next record goes
      integer(int64) :: hash = 0                 !! the deck hash, start of every record's CRC
   end type checkpoint_t

   !> Where the records of a checkpoint file lie (byte ranges), while it is read.
   type :: record_spans_t
      integer(int64), allocatable :: first(:)    !! first byte of the record kept per slot (0: none)
      integer(int64), allocatable :: last(:)     !! its last byte
   end type record_spans_t

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
      integer(int64) :: sig_len, hash, fsize, header_end
      integer :: ios, k
      character(len=256) :: msg
      ck%path = path
      ck%hash = crc32(text_bytes(signature))
      n_loaded = 0
      report = ''
      if (file_exists(path) .and. header_cut_short(path, signature, ck%hash)) then
         call remove_file(path)
         report = path // ': cut short in its header (a run stopped while creating it): ' &
            // 'started afresh'
      end if
      if (.not. file_exists(path)) then
         call create_file(ck, signature, err)
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
      k = findloc([magic_1, magic_2, magic_3, magic_4, magic_5], head, dim=1)
      if (k > 0) then
         call refuse(ck, 'was written by an older gapbeam, ' // trim(older(k)) // ': remove ' &
            // 'it (its points are then computed again)', err)
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
      if (hash /= ck%hash .or. sig /= signature) then
         call refuse(ck, 'belongs to a different deck or shard; it is not mixed with this run: ' &
            // 'remove it to start afresh, or run the deck that wrote it', err)
         return
      end if
      inquire(unit=ck%unit, pos=header_end)
      call load_records(ck, header_end, fsize, results, done, n_loaded, report, err)
   end subroutine checkpoint_open

   !> Whether the file at `path` is shorter than the header this run would write and equal to
   !> its beginning (empty, or a header cut short by a kill): it holds nothing.
   function header_cut_short(path, signature, hash) result(cut)
      character(len=*), intent(in) :: path               !! the checkpoint file
      character(len=*), intent(in) :: signature          !! deck text and shard
      integer(int64), intent(in) :: hash                 !! the deck hash
      logical :: cut
      integer(int8), allocatable :: head(:), b(:)
      integer(int64) :: n
      integer :: unit, ios
      cut = .false.
      head = [text_bytes(magic), transfer(hash, [0_int8]), &
              transfer(int(len(signature), int64), [0_int8]), text_bytes(signature)]
      n = file_size(path)
      if (n < 0 .or. n >= size(head, kind=int64)) return
      if (n == 0) then
         cut = .true.
         return
      end if
      allocate(b(n))
      open(newunit=unit, file=path, access='stream', form='unformatted', status='old', &
           action='read', iostat=ios)
      if (ios /= 0) return
      read(unit, pos=1, iostat=ios) b
      close(unit)
      cut = ios == 0 .and. all(b == head(1:n))
   end function header_cut_short

   !> Create a new checkpoint file holding the header only.
   subroutine create_file(ck, signature, err)
      type(checkpoint_t), intent(inout) :: ck            !! checkpoint, path and hash set
      character(len=*), intent(in) :: signature          !! deck text and shard
      type(error_t), allocatable, intent(inout) :: err   !! I/O error
      integer :: ios
      character(len=256) :: msg
      open(newunit=ck%unit, file=ck%path, access='stream', form='unformatted', status='new', &
           action='readwrite', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(err, 'gapbeam_checkpoint: cannot create ' // ck%path // ': ' &
            // trim(msg))
         return
      end if
      write(ck%unit, pos=1, iostat=ios, iomsg=msg) magic, ck%hash, int(len(signature), int64), &
         signature
      if (ios == 0) flush(ck%unit, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         close(ck%unit, status='delete')
         ck%unit = -1
         call fatal_error(err, 'gapbeam_checkpoint: cannot write ' // ck%path // ': ' // trim(msg))
         return
      end if
      inquire(unit=ck%unit, pos=ck%next_pos)
      if (file_size(ck%path) /= ck%next_pos - 1) then
         close(ck%unit, status='delete')
         ck%unit = -1
         call fatal_error(err, 'gapbeam_checkpoint: cannot write ' // ck%path // ' (is the ' &
            // 'disk full?)')
      end if
   end subroutine create_file

   !> Close a checkpoint that is not used, and say why.
   subroutine refuse(ck, why, err)
      type(checkpoint_t), intent(inout) :: ck          !! open checkpoint, closed here
      character(len=*), intent(in) :: why              !! reason, after the file name
      type(error_t), allocatable, intent(inout) :: err !! set
      close(ck%unit)
      ck%unit = -1
      call fatal_error(err, 'gapbeam_checkpoint: ' // ck%path // ' ' // why)
   end subroutine refuse

   !> Read the records after the header (bytes header_end..fsize); when anything was not
   !> trusted, rewrite the file with the trusted records only. Sets `ck%next_pos`.
   subroutine load_records(ck, header_end, fsize, results, done, n_loaded, report, err)
      type(checkpoint_t), intent(inout) :: ck            !! open checkpoint, header read
      integer(int64), intent(in) :: header_end           !! first byte after the header
      integer(int64), intent(in) :: fsize                !! file size [bytes]
      type(point_result_t), intent(inout) :: results(:)  !! loaded points land here
      logical, intent(inout) :: done(:)                  !! set for loaded points
      integer, intent(out) :: n_loaded                   !! points loaded
      character(len=:), allocatable, intent(inout) :: report  !! records not trusted
      type(error_t), allocatable, intent(inout) :: err   !! the rewrite failed
      integer(int8), allocatable :: b(:)
      integer(int64) :: pos, q, nxt, sum_stored
      integer(int32) :: p, m
      real(dp), allocatable :: x(:)
      integer(int64), allocatable :: crc_of(:)           ! checksum of the record loaded per point
      logical, allocatable :: conflict(:)
      type(record_spans_t) :: kept
      type(point_result_t) :: pr
      character(len=:), allocatable :: at
      integer :: ios, k
      logical :: ok, whole, clean
      allocate(crc_of(size(results)), source=-1_int64)
      allocate(conflict(size(results)), source=.false.)
      allocate(kept%first(size(results)), kept%last(size(results)), source=0_int64)
      allocate(b(fsize))
      n_loaded = 0
      clean = .true.
      ios = 0
      if (fsize > 0) read(ck%unit, pos=1, iostat=ios) b
      if (fsize > 0 .and. ios /= 0) then
         call refuse(ck, 'cannot be read back', err)
         return
      end if
      pos = header_end
      k = 0
      do while (pos <= fsize)
         call parse_record(b, pos, whole, p, m, x, sum_stored, nxt)
         if (.not. whole) then
            clean = .false.
            q = next_whole_record(b, pos + 1)
            if (q == 0) then
               call add_line(report, ck%path // ': the last ' // str(fsize - pos + 1) &
                  // ' bytes (from byte ' // str(pos) // ') are not a whole record (a ' &
                  // 'run stopped while writing?): dropped')
               exit
            end if
            call add_line(report, ck%path // ': bytes ' // str(pos) // ' to ' &
               // str(q - 1) // ' are not a whole record (a damaged mark or length): ' &
               // 'skipped, the records after them are read; a point recorded there is ' &
               // 'computed again')
            pos = q
            cycle
         end if
         k = k + 1
         at = ck%path // ': record ' // str(k) // ' (byte ' // str(pos) // ')'
         if (sum_stored /= crc32(b(pos + 4:nxt - 13), ck%hash)) then
            clean = .false.
            call add_line(report, at // ' fails its checksum (a damaged record, or one copied ' &
               // 'from the checkpoint of another deck or shard): not trusted, its point is ' &
               // 'computed again')
         else if (p < 1 .or. p > size(results)) then
            clean = .false.
            call add_line(report, at // ' names point ' // str(int(p)) // ', outside 1..' &
               // str(size(results)) // ': ignored')
         else
            call unpack_point(x, pr, ok)
            if (.not. ok) then
               clean = .false.
               call add_line(report, at // ', point ' // str(int(p)) // ', is not a ' &
                  // 'well-formed point: not trusted, the point is computed again')
            else if (pr%status /= 0) then
               clean = .false.
               call add_line(report, at // ', point ' // str(int(p)) // ', records a failed ' &
                  // 'run (gapbeam records none): not trusted, the point is computed again')
            else if (conflict(p)) then
               continue
            else if (crc_of(p) >= 0 .and. crc_of(p) /= sum_stored) then
               clean = .false.
               call add_line(report, at // ': point ' // str(int(p)) // ' has two different ' &
                  // 'records: neither is trusted, the point is computed again')
               conflict(p) = .true.
               if (done(p)) n_loaded = n_loaded - 1
               done(p) = .false.
               kept%first(p) = 0
            else if (crc_of(p) < 0) then
               crc_of(p) = sum_stored
               results(p) = pr
               if (.not. done(p)) n_loaded = n_loaded + 1
               done(p) = .true.
               kept%first(p) = pos
               kept%last(p) = nxt - 1
            end if                ! else: an identical copy of a record already loaded
         end if
         pos = nxt
      end do
      if (clean) then
         ck%next_pos = fsize + 1
      else
         call rewrite(ck, b(1:header_end - 1), b, kept, err)
      end if
   end subroutine load_records

   !> Whether bytes b(pos:) begin with a whole record: its marks where its length puts them.
   !> Then its point index, length, reals, stored checksum and the byte after it.
   subroutine parse_record(b, pos, whole, p, m, x, sum_stored, nxt)
      integer(int8), intent(in) :: b(:)                  !! the file's bytes
      integer(int64), intent(in) :: pos                  !! where the record would begin
      logical, intent(out) :: whole                      !! a whole record is there
      integer(int32), intent(out) :: p, m                !! point index, payload length
      real(dp), allocatable, intent(inout) :: x(:)       !! payload
      integer(int64), intent(out) :: sum_stored          !! stored checksum
      integer(int64), intent(out) :: nxt                 !! first byte after the record
      integer(int64) :: n, e
      whole = .false.
      p = 0;  m = 0;  sum_stored = -1;  nxt = pos
      n = size(b, kind=int64)
      if (pos < 1 .or. pos + 11 > n) return
      if (transfer(b(pos:pos + 3), 0_int32) /= mark_begin) return
      p = transfer(b(pos + 4:pos + 7), 0_int32)
      m = transfer(b(pos + 8:pos + 11), 0_int32)
      if (m < 0) return
      if (pos - 1 + record_overhead + 8_int64 * m > n) return
      e = pos + 12 + 8_int64 * m                         ! first byte of the checksum
      if (transfer(b(e + 8:e + 11), 0_int32) /= mark_end) return
      sum_stored = transfer(b(e:e + 7), 0_int64)
      if (allocated(x)) deallocate(x)
      allocate(x(m))
      if (m > 0) x = transfer(b(pos + 12:e - 1), x, int(m))
      nxt = e + 12
      whole = .true.
   end subroutine parse_record

   !> The first byte at or after `from` where a whole record begins, 0 when none does.
   function next_whole_record(b, from) result(q)
      integer(int8), intent(in) :: b(:)                  !! the file's bytes
      integer(int64), intent(in) :: from                 !! where to start looking
      integer(int64) :: q
      integer(int8), parameter :: mark(4) = transfer(mark_begin, [0_int8], 4)
      integer(int64) :: j, nxt, sum_stored
      integer(int32) :: p, m
      real(dp), allocatable :: x(:)
      logical :: whole
      q = 0
      do j = from, size(b, kind=int64) - record_overhead + 1
         if (any(b(j:j + 3) /= mark)) cycle
         call parse_record(b, j, whole, p, m, x, sum_stored, nxt)
         if (whole) then
            q = j
            return
         end if
      end do
   end function next_whole_record

   !> Replace the checkpoint by its header and the kept records (in file order), under a
   !> temporary name renamed over it; reopen it for appending.
   subroutine rewrite(ck, header, b, kept, err)
      type(checkpoint_t), intent(inout) :: ck            !! open checkpoint, reopened here
      integer(int8), intent(in) :: header(:)             !! the header's bytes
      integer(int8), intent(in) :: b(:)                  !! the file's bytes
      type(record_spans_t), intent(in) :: kept           !! the records to keep
      type(error_t), allocatable, intent(inout) :: err   !! I/O failure (file unchanged)
      type(error_t), allocatable :: moved
      character(len=:), allocatable :: part
      integer(int64), allocatable :: starts(:)
      integer(int64) :: total
      integer :: unit, ios, j
      integer, allocatable :: order(:)
      character(len=512) :: msg
      close(ck%unit, iostat=ios)
      ck%unit = -1
      part = ck%path // '.part'
      starts = pack(kept%first, kept%first > 0)
      order = sort_index(starts)
      open(newunit=unit, file=part, access='stream', form='unformatted', status='replace', &
           action='write', iostat=ios, iomsg=msg)
      if (ios == 0) write(unit, pos=1, iostat=ios, iomsg=msg) header
      total = size(header, kind=int64)
      do j = 1, size(order)
         if (ios /= 0) exit
         associate (k => findloc(kept%first, starts(order(j)), dim=1))
            write(unit, iostat=ios, iomsg=msg) b(kept%first(k):kept%last(k))
            total = total + kept%last(k) - kept%first(k) + 1
         end associate
      end do
      if (ios == 0) flush(unit, iostat=ios, iomsg=msg)
      if (ios == 0) close(unit, iostat=ios, iomsg=msg)
      if (ios == 0 .and. file_size(part) /= total) then
         ios = 1
         msg = 'only ' // str(file_size(part)) // ' of ' // str(total) // ' bytes ' &
            // 'stored (a full disk?)'
      end if
      if (ios == 0) then
         call rename_file(part, ck%path, moved)
         if (allocated(moved)) then
            ios = 1
            msg = moved%message
         end if
      end if
      if (ios /= 0) then
         close(unit, iostat=j)
         call remove_file(part)
         call fatal_error(err, 'gapbeam_checkpoint: cannot rewrite ' // ck%path // ' without ' &
            // 'its untrusted records: ' // trim(msg) // '; the file is unchanged')
         return
      end if
      open(newunit=ck%unit, file=ck%path, access='stream', form='unformatted', status='old', &
           action='readwrite', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ck%unit = -1
         call fatal_error(err, 'gapbeam_checkpoint: cannot open ' // ck%path // ': ' // trim(msg))
         return
      end if
      ck%next_pos = total + 1
   end subroutine rewrite

   !> Indices that sort `v` ascending (insertion sort: a checkpoint's records are nearly in
   !> order already).
   pure function sort_index(v) result(idx)
      integer(int64), intent(in) :: v(:)                 !! values
      integer, allocatable :: idx(:)
      integer :: i, j, t
      idx = [(i, i = 1, size(v))]
      do i = 2, size(v)
         t = idx(i)
         j = i - 1
         do while (j >= 1)
            if (v(idx(j)) <= v(t)) exit
            idx(j + 1) = idx(j)
            j = j - 1
         end do
         idx(j + 1) = t
      end do
   end function sort_index

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
         int(size(x), int32), x, record_crc(ck%hash, int(p, int32), int(size(x), int32), x), &
         mark_end
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
            // str(p) // '): only ' // str(file_size(ck%path)) // ' of ' &
            // str(ck%next_pos - 1) // ' bytes are stored (a full disk?); the ' &
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

   !> Checksum of a record: CRC-32 of the bytes of its point index, length and reals,
   !> continued from the deck hash.
   pure function record_crc(hash, p, m, x) result(crc)
      integer(int64), intent(in) :: hash               !! the deck hash
      integer(int32), intent(in) :: p, m               !! point index, payload length
      real(dp), intent(in) :: x(:)                     !! payload
      integer(int64) :: crc
      crc = crc32(transfer(x, [0_int8]), crc32(transfer([p, m], [0_int8]), hash))
   end function record_crc

   !> A point's results as one real array (for checkpoints); integers and characters are
   !> stored exactly (a text as its length, then one character code per real); the per-stop
   !> arrays in the order of gapbeam_point_fields (array_names 1-6, then the wear, 7-10).
   pure function pack_point(pr) result(x)
      type(point_result_t), intent(in) :: pr   !! a finished point
      real(dp), allocatable :: x(:)
      integer :: k
      x = [real(pr%status, dp), real(pr%period, dp), real(pr%label, dp), pr%lyapunov, &
           pr%lyapunov_error, real(pr%steps, dp), pr%seconds, &
           real(size(pr%lyapunov_running), dp), pr%lyapunov_running, &
           real(size(pr%n_impacts), dp), (array_field(pr, k), k = 1, 6), &
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
           real(pr%lyapunov_dropped, dp), real(pr%lyapunov_rerun, dp), &
           real(pr%lyapunov_starts, dp), pr%lyapunov_spread, text_reals(pr%method), &
           text_reals(pr%certificate_reason), text_reals(pr%accuracy_method), &
           real(size(array_field(pr, 7)), dp), (array_field(pr, k), k = 7, 10)]
      ! statistics over draws (when the point has them): draws, items, outputs, mean, ci
      if (pr%n_draws > 0) x = [x, real(pr%n_draws, dp), real(size(pr%draw_mean, 1), dp), &
         real(size(pr%draw_mean, 2), dp), reshape(pr%draw_mean, [size(pr%draw_mean)]), &
         reshape(pr%draw_ci, [size(pr%draw_ci)])]
   end function pack_point

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
      integer :: k, m, ns, nr, n, nd, ni, no, j
      integer, parameter :: n_scalars = 30
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
      do j = 1, 6
         call set_array_field(pr, j, x(k + 1:k + ns));  k = k + ns
      end do
      k = k + 1
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
      pr%lyapunov_dropped = nint(s(27));  pr%lyapunov_rerun = nint(s(28))
      pr%lyapunov_starts = nint(s(29));  pr%lyapunov_spread = s(30)
      call take_text(x, k, pr%method, ok);  if (.not. ok) return
      call take_text(x, k, pr%certificate_reason, ok);  if (.not. ok) return
      call take_text(x, k, pr%accuracy_method, ok);  if (.not. ok) return
      ! the wear block: its size, then four per-stop arrays
      ok = .false.
      if (k + 1 > size(x)) return
      k = k + 1
      ns = nint(x(k));  if (ns < 0 .or. k + 4 * ns > size(x)) return
      do j = 7, 10
         call set_array_field(pr, j, x(k + 1:k + ns));  k = k + ns
      end do
      ! the statistics over draws, when there are any
      if (k < size(x)) then
         if (k + 3 > size(x)) return
         nd = nint(x(k + 1));  ni = nint(x(k + 2));  no = nint(x(k + 3));  k = k + 3
         if (nd < 1 .or. ni < 0 .or. no < 0 .or. k + 2 * ni * no /= size(x)) return
         pr%n_draws = nd
         pr%draw_mean = reshape(x(k + 1:k + ni * no), [ni, no]);  k = k + ni * no
         pr%draw_ci = reshape(x(k + 1:k + ni * no), [ni, no])
      end if
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
