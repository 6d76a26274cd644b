!> Files and directories: the one module of gapbeam that calls C file-system functions.
!>
!> - `rename_file`, `remove_file`, `make_parent_directory`, `file_exists`: thin wrappers of
!>   C `rename`, `remove`, `mkdir` and `access` that report failures as `error_t` with the C
!>   reason (`strerror` text and `errno`).
!> - `write_table` and `write_text_file` write a text file with every write, the flush and the
!>   close checked (and its size on disk, which is how a full disk shows with gfortran), and
!>   delete it on failure. They write the path they are given: the atomicity of a run's files
!>   is the output set's (gapbeam_output_set), which gives them temporary names and puts the
!>   complete files in place together.
!>
!> Paths are used without their trailing blanks (as Fortran `open` does), so fixed-length
!> character variables can be passed directly. Tables are meant for gnuplot: '#' lines are
!> comments, then one row per line with the columns separated by blanks.
!>
!> - `process_id`, `real_path`, `directory_exists`: C `getpid`, `realpath` and `access`, for
!>   lock files, temporary names unique to a process and the comparison of paths.
!>
!> The `errno` of the calling thread is read through glibc's (and musl's) `__errno_location`.
!> C `strerror` may share its buffer between threads: call the procedures that report a C
!> failure from one thread at a time (outside OpenMP parallel regions), like all file output.
module gapbeam_files
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_null_char, c_f_pointer, &
      c_associated, c_long
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str, q => quoted
   implicit none
   private
   public :: rename_file, remove_file, make_parent_directory, file_exists, directory_exists
   public :: write_table, write_text_file, append_text
   public :: process_id, real_path, file_size, errno_text
   public :: output_name_problem

   character(len=*), parameter :: module_name = 'gapbeam_files'
   character(len=*), parameter :: value_format = '(*(es24.16e3, :, 1x))'   ! one table row
   integer, parameter :: value_width = 25     ! characters per value in a row, separator included
   integer, parameter :: max_c_string = 4096                 ! longest C string read back
   integer(c_int), parameter :: f_ok = 0_c_int               ! access(): existence test (F_OK)
   integer(c_int), parameter :: dir_mode = int(o'777', c_int) ! mkdir(): rwx for all, less umask
   !> The most characters gapbeam adds to the last component of an output prefix: the longest
   !> suffix, '.work_precision_failed.dat' (26), and the temporary name's '.<pid>.part' (13 with
   !> a pid of 7 digits, Linux's largest).
   integer, parameter :: output_suffix_allowance = 39
   integer(c_int), parameter :: pc_name_max = 3_c_int        ! pathconf(): _PC_NAME_MAX (Linux)

   interface
      !> C `rename` from <stdio.h>: 0 on success, -1 with `errno` set on failure.
      function c_rename(old_name, new_name) bind(c, name='rename') result(status)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: old_name(*)   !! NUL-terminated path
         character(kind=c_char), intent(in) :: new_name(*)   !! NUL-terminated path
         integer(c_int) :: status
      end function c_rename

      !> C `remove` from <stdio.h>: 0 on success (a file, or an empty directory).
      function c_remove(file_name) bind(c, name='remove') result(status)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: file_name(*)  !! NUL-terminated path
         integer(c_int) :: status
      end function c_remove

      !> POSIX `mkdir` from <sys/stat.h> (`mode_t` is an unsigned int on Linux):
      !> 0 on success, -1 with `errno` set on failure.
      function c_mkdir(path, mode) bind(c, name='mkdir') result(status)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)       !! NUL-terminated path
         integer(c_int), value, intent(in) :: mode           !! permissions, before umask
         integer(c_int) :: status
      end function c_mkdir

      !> POSIX `access` from <unistd.h>: 0 when `path` passes the test `mode`.
      function c_access(path, mode) bind(c, name='access') result(status)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)       !! NUL-terminated path
         integer(c_int), value, intent(in) :: mode           !! F_OK, R_OK, W_OK or X_OK
         integer(c_int) :: status
      end function c_access

      !> C `strerror` from <string.h>: text of an `errno` value.
      function c_strerror(errnum) bind(c, name='strerror') result(text)
         import :: c_int, c_ptr
         integer(c_int), value, intent(in) :: errnum         !! errno value
         type(c_ptr) :: text
      end function c_strerror

      !> POSIX `getpid` from <unistd.h> (`pid_t` is an int on Linux).
      function c_getpid() bind(c, name='getpid') result(pid)
         import :: c_int
         integer(c_int) :: pid
      end function c_getpid

      !> POSIX `realpath` from <stdlib.h>: the canonical absolute path into `resolved`
      !> (PATH_MAX bytes), or a null pointer with `errno` set.
      function c_realpath(path, resolved) bind(c, name='realpath') result(p)
         import :: c_char, c_ptr
         character(kind=c_char), intent(in) :: path(*)       !! NUL-terminated path
         character(kind=c_char), intent(out) :: resolved(*)  !! buffer of PATH_MAX bytes
         type(c_ptr) :: p
      end function c_realpath

      !> POSIX `open` (read only here: flags O_RDONLY, no mode).
      function c_open_read(path, flags) bind(c, name='open') result(fd)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)       !! NUL-terminated path
         integer(c_int), value, intent(in) :: flags          !! O_RDONLY = 0
         integer(c_int) :: fd
      end function c_open_read

      !> POSIX `lseek` (`off_t` is a long on 64-bit Linux): the new offset, or -1.
      function c_lseek(fd, offset, whence) bind(c, name='lseek') result(pos)
         import :: c_int, c_long
         integer(c_int), value, intent(in) :: fd             !! open file
         integer(c_long), value, intent(in) :: offset        !! offset
         integer(c_int), value, intent(in) :: whence         !! SEEK_END = 2
         integer(c_long) :: pos
      end function c_lseek

      !> POSIX `close`.
      function c_close(fd) bind(c, name='close') result(status)
         import :: c_int
         integer(c_int), value, intent(in) :: fd             !! open file
         integer(c_int) :: status
      end function c_close

      !> POSIX `pathconf`: a limit of the file system of `path` (-1: none or unknown).
      function c_pathconf(path, name) bind(c, name='pathconf') result(value)
         import :: c_char, c_int, c_long
         character(kind=c_char), intent(in) :: path(*)       !! NUL-terminated path
         integer(c_int), value, intent(in) :: name           !! _PC_NAME_MAX = 3
         integer(c_long) :: value
      end function c_pathconf

      !> Address of the calling thread's `errno` (glibc and musl; macOS names it `__error`).
      function c_errno_location() bind(c, name='__errno_location') result(location)
         import :: c_ptr
         type(c_ptr) :: location
      end function c_errno_location
   end interface

contains

   ! ---------------------------------------------------------------------------------------
   ! Files and directories
   ! ---------------------------------------------------------------------------------------

   !> Rename `old_path` to `new_path` with C `rename`, replacing an existing file
   !> `new_path` atomically (both must lie on the same file system).
   !>
   !> The error reads `gapbeam_files:rename_file: cannot rename file 'old' to 'new':
   !> <strerror text> (errno N)`.
   subroutine rename_file(old_path, new_path, err)
      character(len=*), intent(in) :: old_path           !! existing file
      character(len=*), intent(in) :: new_path           !! new name
      type(error_t), allocatable, intent(out) :: err     !! set when the rename fails
      character(len=:), allocatable :: reason
      call rename_path(trim(old_path), trim(new_path), reason)
      if (len(reason) > 0) call fatal_error(err, here('rename_file') // reason)
   end subroutine rename_file

   !> Delete a file (or an empty directory) with C `remove`; a missing file, an empty path or
   !> any other failure is silently ignored (for clean-up on error paths).
   subroutine remove_file(path)
      character(len=*), intent(in) :: path               !! file to delete
      integer(c_int) :: status
      if (len_trim(path) == 0) return
      status = c_remove(trim(path) // c_null_char)
   end subroutine remove_file

   !> Create the directory part of the file path `path` and every missing ancestor, like
   !> `mkdir -p "$(dirname path)"`: 'results/sweep/a.h5' creates 'results' and
   !> 'results/sweep'. The directory part is everything before the last '/', so 'out/' creates
   !> 'out'. Directories that exist already are fine; a path without '/' does nothing.
   !> New directories get mode 0777 less the umask.
   subroutine make_parent_directory(path, err)
      character(len=*), intent(in) :: path               !! file path, e.g. 'results/a.dat'
      type(error_t), allocatable, intent(out) :: err     !! set when a directory cannot be made
      character(len=*), parameter :: proc = 'make_parent_directory'
      character(len=:), allocatable :: p, dir, message
      integer :: i, last
      integer(c_int) :: status, code

      p = trim(path)
      last = index(p, '/', back=.true.)
      do i = 2, last           ! i = 1 would be the root directory '/', which always exists
         if (p(i:i) /= '/') cycle
         if (p(i - 1:i - 1) == '/') cycle   ! 'a//b': 'a/' is the directory 'a', done already
         dir = p(1:i - 1)
         status = c_mkdir(dir // c_null_char, dir_mode)
         if (status == 0) cycle
         code = current_errno()
         if (is_directory(dir)) cycle       ! there already (EEXIST), or made by someone else
         message = here(proc) // 'cannot create directory ' // q(dir) // ' (for ' // q(p) &
            // '): ' // errno_text(code) // ' (errno ' // str(int(code)) // ')'
         if (exists(dir)) message = message // '; ' // q(dir) &
            // ' exists and is not a directory (or cannot be searched)'
         call fatal_error(err, message)
         return
      end do
   end subroutine make_parent_directory

   !> Why the files of output prefix `prefix` could not be created, found before anything is
   !> computed, or '' when they can: a component of the prefix longer than the file system's
   !> NAME_MAX (pathconf of the nearest directory that exists; 255 when unknown), the last one
   !> counted with the `output_suffix_allowance` characters gapbeam adds to it. (Without this
   !> check such a run failed only when its files were written, after the computation.)
   function output_name_problem(prefix) result(why)
      character(len=*), intent(in) :: prefix             !! output prefix (validated)
      character(len=:), allocatable :: why, p, dir, comp
      integer :: name_max, a, b
      integer(c_long) :: lim
      why = ''
      p = trim(prefix)
      ! NAME_MAX of the file system of the nearest existing directory above the prefix
      dir = p(1:max(0, index(p, '/', back=.true.) - 1))
      do while (len(dir) > 0)
         if (is_directory(dir)) exit
         dir = dir(1:max(0, index(dir, '/', back=.true.) - 1))
      end do
      if (len(dir) == 0) then
         dir = '.'
         if (p(1:1) == '/') dir = '/'
      end if
      lim = c_pathconf(dir // c_null_char, pc_name_max)
      name_max = 255
      if (lim > 0 .and. lim < 100000) name_max = int(lim)
      a = 1
      do while (a <= len(p))
         b = index(p(a:), '/')
         if (b == 0) then
            comp = p(a:)
            if (len(comp) + output_suffix_allowance > name_max) why = 'file name too long: ' &
               // 'its last component (' // str(len(comp)) // ' characters, ' &
               // q(comp(1:min(len(comp), 24)) // '...') // ') is too long: the files ' &
               // 'gapbeam writes add up to ' &
               // str(output_suffix_allowance) // " characters to it ('" &
               // ".work_precision_failed.dat.<pid>.part') and a file name may have at most " &
               // str(name_max) // ' (NAME_MAX of ' // q(dir) // '): give at most ' &
               // str(name_max - output_suffix_allowance) // ' characters'
            exit
         end if
         comp = p(a:a + b - 2)
         if (len(comp) > name_max) then
            why = 'file name too long: its directory component ' &
               // q(comp(1:min(len(comp), 24)) // '...') // ' (' &
               // str(len(comp)) // ' characters) is longer than a file name may be (' &
               // str(name_max) // ', NAME_MAX of ' // q(dir) // ')'
            exit
         end if
         a = a + b
      end do
   end function output_name_problem

   !> Whether a file or directory exists at `path` (C `access` with F_OK).
   logical function file_exists(path)
      character(len=*), intent(in) :: path               !! file or directory name
      file_exists = .false.
      if (len_trim(path) == 0) return
      file_exists = exists(trim(path))
   end function file_exists

   !> Whether `path` is a directory that can be entered.
   logical function directory_exists(path)
      character(len=*), intent(in) :: path               !! path
      directory_exists = .false.
      if (len_trim(path) == 0) return
      directory_exists = is_directory(trim(path))
   end function directory_exists

   !> Size in bytes of the file at `path` as the file system has it (C `lseek` to its end),
   !> -1 when it cannot be opened. Unlike INQUIRE on a file that is open in this program, it
   !> does not count data still buffered, nor data a write failed to store.
   function file_size(path) result(bytes)
      character(len=*), intent(in) :: path               !! file
      integer(int64) :: bytes
      integer(c_int) :: fd, status
      bytes = -1
      if (len_trim(path) == 0) return
      fd = c_open_read(trim(path) // c_null_char, 0_c_int)
      if (fd < 0) return
      bytes = int(c_lseek(fd, 0_c_long, 2_c_int), int64)
      status = c_close(fd)
   end function file_size

   !> The process id of this program.
   integer function process_id()
      process_id = int(c_getpid())
   end function process_id

   !> The canonical absolute path of an existing file or directory (C `realpath`: links,
   !> '.' and '..' resolved), or '' when it does not exist or cannot be resolved.
   function real_path(path) result(resolved)
      character(len=*), intent(in) :: path               !! file or directory
      character(len=:), allocatable :: resolved
      character(kind=c_char) :: buf(max_c_string + 1)
      type(c_ptr) :: p
      integer :: n
      resolved = ''
      if (len_trim(path) == 0) return
      buf = c_null_char
      p = c_realpath(trim(path) // c_null_char, buf)
      if (.not. c_associated(p)) return
      n = 0
      do while (n < max_c_string)
         if (buf(n + 1) == c_null_char) exit
         n = n + 1
      end do
      deallocate(resolved)
      allocate(character(len=n) :: resolved)
      resolved = transfer(buf(1:n), resolved)
   end function real_path

   ! ---------------------------------------------------------------------------------------
   ! Atomic text files
   ! ---------------------------------------------------------------------------------------

   !> Write a gnuplot-ready table to `path` (deleted on failure).
   !>
   !> The file holds three comment lines, then one line per row of `columns`, each value in
   !> `es24.16e3` (17 significant digits, so reals read back exactly) followed by a blank:
   !>
   !> ```text
   !> # tip displacement, baseline deck
   !> # columns: t [s], w_tip [m]
   !> # t w_tip
   !>   0.0000000000000000E+000   1.2500000000000000E-003
   !> ```
   !>
   !> Zero rows give the comment lines only. The directory of `path` must exist (see
   !> `make_parent_directory`). `names` and `units` must have one entry per column of
   !> `columns` (`error stop` otherwise: a programming error); names should contain no blanks.
   subroutine write_table(path, title, names, units, columns, err)
      character(len=*), intent(in) :: path               !! file to write, e.g. 'results/tip.dat'
      character(len=*), intent(in) :: title              !! first comment line (new lines -> ' ')
      character(len=*), intent(in) :: names(:)           !! column names, e.g. ['t    ', 'w_tip']
      character(len=*), intent(in) :: units(:)           !! column units, e.g. ['s', 'm']
      real(dp), intent(in) :: columns(:, :)              !! values, shape (n_rows, n_cols)
      type(error_t), allocatable, intent(out) :: err     !! set on failure; no file is left
      character(len=*), parameter :: proc = 'write_table'
      character(len=:), allocatable :: p, described, header, line, row
      character(len=512) :: msg
      integer :: unit, ios, i, j, width
      integer(int64) :: bytes

      if (size(names) /= size(columns, 2) .or. size(units) /= size(columns, 2)) then
         error stop 'gapbeam_files:write_table: size(names) = ' // str(size(names)) &
            // ' and size(units) = ' // str(size(units)) // ' must equal the number of columns ' &
            // str(size(columns, 2))
      end if
      p = trim(path)
      described = ''
      header = ''
      do j = 1, size(names)
         if (j > 1) described = described // ', '
         described = described // trim(names(j)) // ' [' // trim(units(j)) // ']'
         header = header // ' ' // trim(names(j))
      end do

      call open_file(proc, p, .false., unit, err)
      if (allocated(err)) return
      msg = ''
      ! every line through a buffer, so that the bytes the file must have are known
      allocate(character(len=max(1, value_width * size(columns, 2))) :: row)
      line = '# ' // trim(one_line(title))
      write(unit, '(a)', iostat=ios, iomsg=msg) line
      bytes = len(line) + 1
      line = '# columns: ' // described
      if (ios == 0) write(unit, '(a)', iostat=ios, iomsg=msg) line
      bytes = bytes + len(line) + 1
      line = '#' // header
      if (ios == 0) write(unit, '(a)', iostat=ios, iomsg=msg) line
      bytes = bytes + len(line) + 1
      width = max(0, value_width * size(columns, 2) - 1)
      do i = 1, size(columns, 1)
         if (ios /= 0) exit
         write(row, value_format, iostat=ios, iomsg=msg) columns(i, :)
         if (ios == 0) write(unit, '(a)', iostat=ios, iomsg=msg) row(1:width)
         bytes = bytes + width + 1
      end do
      call close_file(proc, p, unit, ios, msg, bytes, err)
   end subroutine write_table

   !> Write `text` to `path` byte for byte (deleted on failure).
   !>
   !> New lines inside `text` are kept; none is added, so end the text with
   !> `new_line('a')` for a conventional last line. The directory of `path` must exist.
   subroutine write_text_file(path, text, err)
      character(len=*), intent(in) :: path               !! file to write, e.g. 'results/report.txt'
      character(len=*), intent(in) :: text               !! whole file content
      type(error_t), allocatable, intent(out) :: err     !! set on failure; no file is left
      character(len=*), parameter :: proc = 'write_text_file'
      character(len=:), allocatable :: p
      character(len=512) :: msg
      integer :: unit, ios

      p = trim(path)
      call open_file(proc, p, .true., unit, err)
      if (allocated(err)) return
      msg = ''
      write(unit, iostat=ios, iomsg=msg) text
      call close_file(proc, p, unit, ios, msg, int(len(text), int64), err)
   end subroutine write_text_file

   !> Append text to a buffer t of used length nt (capacity doubles): a long text built
   !> piece by piece in linear time; t(1:nt) is the text.
   pure subroutine append_text(t, nt, x)
      character(len=:), allocatable, intent(inout) :: t   !! buffer (allocated on first use)
      integer, intent(inout) :: nt                         !! its used length (0 at first)
      character(len=*), intent(in) :: x                    !! text to append
      character(len=:), allocatable :: tmp
      if (.not. allocated(t)) allocate(character(len=max(4096, 2 * len(x))) :: t)
      if (nt + len(x) > len(t)) then
         allocate(character(len=max(2 * len(t), nt + len(x))) :: tmp)
         tmp(1:nt) = t(1:nt)
         call move_alloc(tmp, t)
      end if
      t(nt + 1:nt + len(x)) = x
      nt = nt + len(x)
   end subroutine append_text

   ! ---------------------------------------------------------------------------------------
   ! Helpers
   ! ---------------------------------------------------------------------------------------

   !> Create (or truncate) `p` for writing: formatted sequential, or unformatted stream for a
   !> byte-for-byte copy; an empty name refused.
   subroutine open_file(proc, p, stream, unit, err)
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: p                  !! file name, trimmed
      logical, intent(in) :: stream                      !! unformatted stream access
      integer, intent(out) :: unit                       !! unit of the open file
      type(error_t), allocatable, intent(inout) :: err   !! set when the file cannot be created
      character(len=512) :: msg
      integer :: ios
      if (len(p) == 0) then
         call fatal_error(err, here(proc) // 'empty file path')
         return
      end if
      msg = ''
      if (stream) then
         open(newunit=unit, file=p, status='replace', action='write', access='stream', &
              form='unformatted', iostat=ios, iomsg=msg)
      else
         open(newunit=unit, file=p, status='replace', action='write', form='formatted', &
              iostat=ios, iomsg=msg)
      end if
      if (ios /= 0) call fatal_error(err, here(proc) // 'cannot create file ' // q(p) &
         // ' (does the directory exist and is it writable?): ' // trim(msg))
   end subroutine open_file

   !> Close the file `p`; after a write error (`ios /= 0`), or when flushing or closing fails,
   !> or when it has not the bytes written, delete it and set `err`.
   !>
   !> The size of the closed file is compared with the bytes written: gfortran (12) reports
   !> no error when the disk is full (the data are dropped, the writes, FLUSH and CLOSE
   !> succeed), so this is the check that catches it.
   subroutine close_file(proc, p, unit, ios, msg, expected, err)
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: p                  !! file name, trimmed
      integer, intent(in) :: unit                        !! its unit
      integer, intent(in) :: ios                         !! status of the writes, 0 when all ok
      character(len=*), intent(in) :: msg                !! iomsg of the failed write
      integer(int64), intent(in) :: expected             !! bytes the file must have
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      character(len=512) :: close_msg
      integer :: close_ios, ios_ignored
      integer(int64) :: stored
      if (ios /= 0) then
         close(unit, status='delete', iostat=close_ios)
         call remove_file(p)
         call fatal_error(err, here(proc) // 'cannot write file ' // q(p) // ': ' // trim(msg))
         return
      end if
      close_msg = ''
      flush(unit, iostat=close_ios, iomsg=close_msg)      ! a full disk shows here, or in close
      if (close_ios == 0) close(unit, iostat=close_ios, iomsg=close_msg)
      if (close_ios /= 0) then
         close(unit, status='delete', iostat=ios_ignored)
         call remove_file(p)
         call fatal_error(err, here(proc) // 'cannot flush or close file ' // q(p) // ': ' &
            // trim(close_msg))
         return
      end if
      stored = file_size(p)
      if (stored /= expected) then
         call remove_file(p)
         call fatal_error(err, here(proc) // 'file ' // q(p) // ' is incomplete: ' &
            // str(stored) // ' of ' // str(expected) // ' bytes stored (a full ' &
            // 'disk, or the file size limit?); it was deleted')
      end if
   end subroutine close_file

   !> C `rename` of `old` to `new`; `reason` is '' on success, else
   !> "cannot rename file 'old' to 'new': <strerror text> (errno N)".
   subroutine rename_path(old, new, reason)
      character(len=*), intent(in) :: old                !! existing file, trimmed
      character(len=*), intent(in) :: new                !! new name, trimmed
      character(len=:), allocatable, intent(out) :: reason   !! why it failed, or ''
      integer(c_int) :: status, code
      reason = ''
      status = c_rename(old // c_null_char, new // c_null_char)
      if (status == 0) return
      code = current_errno()
      reason = 'cannot rename file ' // q(old) // ' to ' // q(new) // ': ' // errno_text(code) &
         // ' (errno ' // str(int(code)) // ')'
   end subroutine rename_path

   !> Whether `p` (trimmed, not empty) exists, as file or directory.
   logical function exists(p)
      character(len=*), intent(in) :: p                  !! path
      exists = c_access(p // c_null_char, f_ok) == 0
   end function exists

   !> Whether `p` (trimmed, not empty) is a directory that can be entered.
   logical function is_directory(p)
      character(len=*), intent(in) :: p                  !! path
      is_directory = c_access(p // '/.' // c_null_char, f_ok) == 0   ! ENOTDIR for a file
   end function is_directory

   !> The calling thread's C `errno`, read right after a failed C call.
   function current_errno() result(code)
      integer(c_int) :: code
      integer(c_int), pointer :: location
      call c_f_pointer(c_errno_location(), location)
      code = location
   end function current_errno

   !> C `strerror` text of an `errno` value.
   function errno_text(code) result(text)
      integer(c_int), intent(in) :: code                 !! errno value
      character(len=:), allocatable :: text
      character(kind=c_char, len=1), pointer :: chars(:)
      type(c_ptr) :: p
      integer :: n, j
      text = 'unknown error'
      p = c_strerror(code)
      if (.not. c_associated(p)) return
      call c_f_pointer(p, chars, [max_c_string])
      n = 0
      do while (n < max_c_string)
         if (chars(n + 1) == c_null_char) exit
         n = n + 1
      end do
      deallocate(text)
      allocate(character(len=n) :: text)
      do j = 1, n
         text(j:j) = chars(j)
      end do
   end function errno_text

   !> `text` on one line: carriage returns and line feeds become blanks.
   pure function one_line(text) result(s)
      character(len=*), intent(in) :: text               !! text, possibly with new lines
      character(len=len(text)) :: s
      integer :: i
      s = text
      do i = 1, len(s)
         if (s(i:i) == achar(10) .or. s(i:i) == achar(13)) s(i:i) = ' '
      end do
   end function one_line

   !> Message prefix 'gapbeam_files:<proc>: '.
   pure function here(proc) result(s)
      character(len=*), intent(in) :: proc               !! procedure name
      character(len=:), allocatable :: s
      s = module_name // ':' // proc // ': '
   end function here
end module gapbeam_files
