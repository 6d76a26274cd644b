!> One writer per output prefix: the lock file PREFIX.lock.
!>
!> A run takes the lock before it computes anything and gives it back when it ends (the file
!> is then deleted). The lock is an exclusive `flock` on PREFIX.lock, which the kernel releases
!> when the process ends in any way, killed or not; the file holds the holder's process id and
!> host, `gapbeam lock: pid 1234 host node17`, for messages. So:
!>
!> - a second run on the same prefix fails at once, naming the holder;
!> - a lock file whose lock is free was left by a run that ended without deleting it (killed):
!>   when it names this host, it is taken over and `note` says so; when it names another host,
!>   the run is refused (this host cannot tell whether that run still goes on, on a file system
!>   that does not share locks between hosts): delete the file once that run has ended;
!> - on a file system without `flock`, the holder named in the file decides: a process that
!>   no longer exists on this host is taken over, anything else is refused.
!>
!> `busy` tells a caller why `acquire_lock` failed: another run holds (or, for a lock file of
!> another host, may hold) the lock; any other failure (permission, a full disk, a name too
!> long) is an error of this run, reported with the system's reason in words.
!>
!> A run creates the file, takes the `flock`, then writes its line: a newcomer refused in
!> between reads the holder once the line is there (`holder_record`), so that the message
!> names it.
!>
!> After the `flock` the file is checked to still be the one under PREFIX.lock (a run that
!> ends deletes it, and a newcomer may hold the deleted file): if not, the lock is taken again.
!> Linux values of the C constants (`O_*`, `LOCK_*`, `errno`) are used.
module gapbeam_lock
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_long, c_size_t, c_null_char, c_ptr, &
      c_f_pointer
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_files, only: remove_file, process_id, errno_text
   implicit none
   private
   public :: lock_t, acquire_lock, release_lock

   !> A lock held on an output prefix.
   type :: lock_t
      integer(c_int) :: fd = -1                    !! file descriptor of PREFIX.lock (-1: none)
      character(len=:), allocatable :: path        !! PREFIX.lock
      character(len=:), allocatable :: note        !! set when a stale lock was taken over
      logical :: busy = .false.                    !! set when another run holds the lock (or
                                                   !! may hold it: a lock file of another host)
   end type lock_t

   integer(c_int), parameter :: o_rdwr = 2, o_creat = 64, o_cloexec = 524288
   integer(c_int), parameter :: lock_ex = 2, lock_nb = 4
   integer(c_int), parameter :: e_srch = 3, e_again = 11, e_nospc = 28
   integer(c_int), parameter :: file_mode = int(o'644', c_int)
   integer, parameter :: max_content = 1024    ! bytes of the lock file read back
   character(len=*), parameter :: here = 'gapbeam_lock: '

   interface
      !> POSIX `open` (declared with its optional mode argument, as Linux ABIs allow).
      function c_open(path, flags, mode) bind(c, name='open') result(fd)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value, intent(in) :: flags, mode
         integer(c_int) :: fd
      end function c_open

      !> POSIX `close`.
      function c_close(fd) bind(c, name='close') result(status)
         import :: c_int
         integer(c_int), value, intent(in) :: fd
         integer(c_int) :: status
      end function c_close

      !> BSD `flock`: 0 on success.
      function c_flock(fd, operation) bind(c, name='flock') result(status)
         import :: c_int
         integer(c_int), value, intent(in) :: fd, operation
         integer(c_int) :: status
      end function c_flock

      !> POSIX `ftruncate` (`off_t` is a long on 64-bit Linux).
      function c_ftruncate(fd, length) bind(c, name='ftruncate') result(status)
         import :: c_int, c_long
         integer(c_int), value, intent(in) :: fd
         integer(c_long), value, intent(in) :: length
         integer(c_int) :: status
      end function c_ftruncate

      !> POSIX `pwrite`: bytes written, or -1.
      function c_pwrite(fd, buf, count, offset) bind(c, name='pwrite') result(n)
         import :: c_int, c_char, c_size_t, c_long
         integer(c_int), value, intent(in) :: fd
         character(kind=c_char), intent(in) :: buf(*)
         integer(c_size_t), value, intent(in) :: count
         integer(c_long), value, intent(in) :: offset
         integer(c_long) :: n
      end function c_pwrite

      !> POSIX `pread`: bytes read, or -1.
      function c_pread(fd, buf, count, offset) bind(c, name='pread') result(n)
         import :: c_int, c_char, c_size_t, c_long
         integer(c_int), value, intent(in) :: fd
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_size_t), value, intent(in) :: count
         integer(c_long), value, intent(in) :: offset
         integer(c_long) :: n
      end function c_pread

      !> POSIX `fsync`: 0 on success.
      function c_fsync(fd) bind(c, name='fsync') result(status)
         import :: c_int
         integer(c_int), value, intent(in) :: fd
         integer(c_int) :: status
      end function c_fsync

      !> POSIX `usleep`: pause for `microseconds` (less than a second); 0 on success.
      function c_usleep(microseconds) bind(c, name='usleep') result(status)
         import :: c_int
         integer(c_int), value, intent(in) :: microseconds
         integer(c_int) :: status
      end function c_usleep

      !> POSIX `kill`; signal 0 only tests whether the process exists.
      function c_kill(pid, sig) bind(c, name='kill') result(status)
         import :: c_int
         integer(c_int), value, intent(in) :: pid, sig
         integer(c_int) :: status
      end function c_kill

      !> Address of the calling thread's `errno` (glibc and musl).
      function c_errno_location() bind(c, name='__errno_location') result(location)
         import :: c_ptr
         type(c_ptr) :: location
      end function c_errno_location

      !> POSIX `gethostname` from <unistd.h>: 0 on success.
      function c_gethostname(name, length) bind(c, name='gethostname') result(status)
         import :: c_char, c_int, c_size_t
         character(kind=c_char), intent(out) :: name(*)       !! buffer
         integer(c_size_t), value, intent(in) :: length       !! its size
         integer(c_int) :: status
      end function c_gethostname
   end interface

contains

   !> Take the lock of output prefix `prefix` (the file PREFIX.lock; its directory must exist).
   !> Fails at once, naming the holder, when another run holds it.
   subroutine acquire_lock(lock, prefix, err)
      type(lock_t), intent(out) :: lock                !! the lock, held on success
      character(len=*), intent(in) :: prefix           !! output prefix
      type(error_t), allocatable, intent(out) :: err   !! held by another run, or an I/O error
      character(len=:), allocatable :: mine, before, holder_host
      integer :: attempt, holder_pid
      integer(c_int) :: fd, code, status
      logical :: have_flock, same

      lock%path = trim(prefix) // '.lock'
      mine = 'gapbeam lock: pid ' // str(process_id()) // ' host ' // host_name() &
         // new_line('a')
      do attempt = 1, 20
         fd = c_open(lock%path // c_null_char, ior(ior(o_rdwr, o_creat), o_cloexec), file_mode)
         if (fd < 0) then
            code = errno()
            call fatal_error(err, here // 'cannot create the lock file ' // q(lock%path) &
               // ': ' // reason(code))
            return
         end if
         before = read_fd(fd)
         call parse_holder(before, holder_pid, holder_host)
         have_flock = c_flock(fd, ior(lock_ex, lock_nb)) == 0
         if (.not. have_flock) then
            code = errno()
            if (code == e_again) then
               before = holder_record(fd)     ! as the holder writes it after its flock
               call parse_holder(before, holder_pid, holder_host)
               code = c_close(fd)
               lock%busy = .true.
               call fatal_error(err, 'output ' // q(trim(prefix)) // ' is in use by another ' &
                  // 'gapbeam run (' // holder_text(holder_pid, holder_host) // ', lock file ' &
                  // q(lock%path) // '): wait until it ends, or give this run another ' &
                  // '&job output')
               return
            end if
            ! no flock on this file system: the holder named in the file decides
            if (len(before) > 0 .and. .not. is_stale(holder_pid, holder_host)) then
               code = c_close(fd)
               lock%busy = .true.
               call fatal_error(err, 'output ' // q(trim(prefix)) // ' is in use by another ' &
                  // 'gapbeam run (' // holder_text(holder_pid, holder_host) // ', lock file ' &
                  // q(lock%path) // '; this file system has no flock, so a lock file left by ' &
                  // 'a run on another host, or by a process id now reused, must be deleted ' &
                  // 'by hand)')
               return
            end if
         else if (len(before) > 0 .and. before /= mine) then
            ! a lock file whose lock is free: its run ended without deleting it
            if (holder_host /= host_name()) then
               code = c_close(fd)
               lock%busy = .true.
               call fatal_error(err, 'output ' // q(trim(prefix)) // ': the lock file ' &
                  // q(lock%path) // ' names ' // holder_text(holder_pid, holder_host) &
                  // '; from this host (' // host_name() // ') gapbeam cannot tell whether ' &
                  // 'that run still goes on: delete ' // q(lock%path) // ' once it has ended')
               return
            end if
         end if
         ! ours now: say so in the file, then check that it is still the file under the name
         if (.not. write_fd(fd, mine, code)) then
            status = c_close(fd)      ! an empty lock file may stay: the next run takes it
            call fatal_error(err, here // 'cannot write the lock file ' // q(lock%path) &
               // ': ' // reason(code))
            return
         end if
         same = read_path(lock%path) == mine
         if (same) then
            lock%fd = fd
            if (len(before) > 0 .and. before /= mine) lock%note = 'took over the stale lock ' &
               // q(lock%path) // ' of ' // holder_text(holder_pid, holder_host) &
               // ', which ended without releasing it (killed?); files it left under ' &
               // q(trim(prefix)) // ' with its process id in their names can be deleted'
            return
         end if
         code = c_close(fd)         ! the file was deleted by the run that held it: again
      end do
      lock%busy = .true.
      call fatal_error(err, here // 'cannot take the lock ' // q(lock%path) // ': it keeps ' &
         // 'changing under other gapbeam runs')
   end subroutine acquire_lock

   !> Give the lock back: delete PREFIX.lock, then close it. Nothing happens when no lock is
   !> held; never fails.
   subroutine release_lock(lock)
      type(lock_t), intent(inout) :: lock              !! the lock
      integer(c_int) :: status
      if (lock%fd < 0) return
      call remove_file(lock%path)      ! while still held: a newcomer then sees a new file
      status = c_close(lock%fd)
      lock%fd = -1
   end subroutine release_lock

   !> Content of the lock file `fd` whose lock another run holds, read once the holder has
   !> named itself in it: a run that has just created the file holds its `flock` a moment
   !> before it writes its line (up to wait_ms, then what the file holds: a file written by
   !> something else, or a holder that stopped between the two, gives 'holder unknown').
   function holder_record(fd) result(text)
      integer(c_int), intent(in) :: fd                 !! open lock file, held by another run
      character(len=:), allocatable :: text
      integer, parameter :: wait_ms = 2000, pause_ms = 2
      integer :: k, pid
      integer(c_int) :: status
      character(len=:), allocatable :: host
      do k = 0, wait_ms / pause_ms
         text = read_fd(fd)
         call parse_holder(text, pid, host)
         if (pid > 0 .and. len(host) > 0) then       ! (pid > 0: the text is not empty)
            if (text(len(text):) == new_line('a')) return
         end if
         status = c_usleep(int(1000 * pause_ms, c_int))
      end do
   end function holder_record

   !> Whether a lock file's holder is gone: a process id that no longer exists on this host.
   logical function is_stale(pid, host)
      integer, intent(in) :: pid                       !! holder's process id (0: unknown)
      character(len=*), intent(in) :: host             !! holder's host
      is_stale = .false.
      if (pid <= 0 .or. host /= host_name()) return
      if (c_kill(int(pid, c_int), 0_c_int) == 0) return
      is_stale = errno() == e_srch                     ! EPERM: it exists, owned by another user
   end function is_stale

   !> 'pid N on host H' (or 'holder unknown' for an empty or foreign file).
   function holder_text(pid, host) result(t)
      integer, intent(in) :: pid                       !! process id (0: unknown)
      character(len=*), intent(in) :: host             !! host ('' unknown)
      character(len=:), allocatable :: t
      if (pid > 0) then
         t = 'pid ' // str(pid) // ' on host ' // host
      else
         t = 'holder unknown'
      end if
   end function holder_text

   !> Process id and host from the text 'gapbeam lock: pid N host H'.
   subroutine parse_holder(text, pid, host)
      character(len=*), intent(in) :: text             !! content of a lock file
      integer, intent(out) :: pid                      !! 0 when not found
      character(len=:), allocatable, intent(out) :: host  !! '' when not found
      integer :: i, j, ios
      pid = 0;  host = ''
      i = index(text, ' pid ')
      j = index(text, ' host ')
      if (i == 0 .or. j <= i) return
      read(text(i + 5:j - 1), *, iostat=ios) pid
      if (ios /= 0) pid = 0
      host = text(j + 6:)
      i = scan(host, achar(10) // achar(13))
      if (i > 0) host = host(1:i - 1)
      host = trim(host)
   end subroutine parse_holder

   !> Replace the content of the open file `fd` by `text`, synced (written over the old
   !> content, then cut to its length: the file never reads empty in between); false on
   !> failure, with the C `errno` in `code` (ENOSPC for a short write).
   logical function write_fd(fd, text, code)
      integer(c_int), intent(in) :: fd                 !! open file
      character(len=*), intent(in) :: text             !! new content
      integer(c_int), intent(out) :: code              !! errno of the failure (0: none)
      character(kind=c_char) :: buf(max(1, len(text)))
      integer(c_long) :: n
      integer :: i
      write_fd = .false.
      code = 0
      do i = 1, len(text)
         buf(i) = text(i:i)
      end do
      n = c_pwrite(fd, buf, int(len(text), c_size_t), 0_c_long)
      if (n < 0) then
         code = errno();  return
      else if (n /= len(text)) then
         code = e_nospc;  return
      end if
      if (c_ftruncate(fd, int(len(text), c_long)) /= 0) then   ! cut what a longer line left
         code = errno();  return
      end if
      if (c_fsync(fd) /= 0) then
         code = errno();  return
      end if
      write_fd = .true.
   end function write_fd

   !> The system's reason for an `errno` value, in words: 'Permission denied (errno 13)'.
   function reason(code) result(t)
      integer(c_int), intent(in) :: code               !! errno value
      character(len=:), allocatable :: t
      t = errno_text(code) // ' (errno ' // str(int(code)) // ')'
   end function reason

   !> Content of the open file `fd` (at most max_content bytes).
   function read_fd(fd) result(text)
      integer(c_int), intent(in) :: fd                 !! open file
      character(len=:), allocatable :: text
      character(kind=c_char) :: buf(max_content)
      integer(c_long) :: n
      integer :: i
      n = c_pread(fd, buf, int(max_content, c_size_t), 0_c_long)
      if (n < 0) n = 0
      allocate(character(len=n) :: text)
      do i = 1, int(n)
         text(i:i) = buf(i)
      end do
   end function read_fd

   !> Content of the file at `path` (at most max_content bytes), '' when it cannot be read.
   function read_path(path) result(text)
      character(len=*), intent(in) :: path             !! file
      character(len=:), allocatable :: text
      integer(c_int) :: fd, status
      text = ''
      fd = c_open(path // c_null_char, o_cloexec, 0_c_int)     ! O_RDONLY = 0
      if (fd < 0) return
      text = read_fd(fd)
      status = c_close(fd)
   end function read_path

   !> The calling thread's C `errno`.
   function errno() result(code)
      integer(c_int) :: code
      integer(c_int), pointer :: location
      call c_f_pointer(c_errno_location(), location)
      code = location
   end function errno

   !> Text in single quotes.
   pure function q(s) result(quoted)
      character(len=*), intent(in) :: s                !! text
      character(len=:), allocatable :: quoted
      quoted = "'" // s // "'"
   end function q

   !> The name of this host (C `gethostname`), 'unknown-host' if it cannot be had.
   function host_name() result(name)
      character(len=:), allocatable :: name
      character(kind=c_char) :: buf(256)
      integer :: n
      buf = c_null_char
      if (c_gethostname(buf, int(size(buf) - 1, c_size_t)) /= 0) then
         name = 'unknown-host'
         return
      end if
      n = 0
      do while (n < size(buf))
         if (buf(n + 1) == c_null_char) exit
         n = n + 1
      end do
      allocate(character(len=n) :: name)
      name = transfer(buf(1:n), name)
      if (n == 0) name = 'unknown-host'
   end function host_name
end module gapbeam_lock
