!> Tests of gapbeam_files: table and text round trips, header lines, atomic writes (no `.part`
!> left), zero-row tables, nested directory creation and the error messages of failed calls.
program test_files
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_files, only: rename_file, remove_file, make_parent_directory, file_exists, &
      directory_exists, write_table, write_text_file
   use gapbeam_deck_rules, only: output_prefix_problem
   use gapbeam_testing, only: check, check_close, finish
   implicit none

   character(len=*), parameter :: tmp_dir = 'test_files_tmp'
   character(len=*), parameter :: table_name = tmp_dir // '/table.dat'
   character(len=*), parameter :: empty_name = tmp_dir // '/empty.dat'
   character(len=*), parameter :: text_name = tmp_dir // '/report.txt'
   character(len=*), parameter :: plain_name = tmp_dir // '/plain'
   character(len=*), parameter :: nested_dir = tmp_dir // '/a/b'
   character(len=*), parameter :: nested_name = nested_dir // '/table.dat'

   call clean_up()            ! leftovers of an interrupted earlier run
   call test_directories()
   call test_table_round_trip()
   call test_zero_rows()
   call test_text_round_trip()
   call test_errors()
   call test_output_prefixes()
   call clean_up()
   call check('temporary files and directories removed', .not. file_exists(tmp_dir))
   call finish('test_files')

contains

   !> An output prefix names the files' stem: one that names a directory is refused, with
   !> the hidden file it would give and a stem to use instead.
   subroutine test_output_prefixes()
      character(len=:), allocatable :: why
      call check('output prefix: a stem in a directory is fine', &
         output_prefix_problem('results/sweep/run') == '' .and. &
         output_prefix_problem('run') == '' .and. output_prefix_problem('./run') == '' .and. &
         output_prefix_problem('../a.b') == '')
      why = output_prefix_problem('results/x/')
      call check('output prefix results/x/: refused, naming the hidden file and a stem', &
         index(why, "'results/x/' names a directory") > 0 .and. &
         index(why, "'results/x/.h5'") > 0 .and. index(why, "'results/x/run'") > 0, why)
      call check('output prefix . and .. and / and an empty one: refused', &
         output_prefix_problem('.') /= '' .and. output_prefix_problem('..') /= '' .and. &
         output_prefix_problem('a/..') /= '' .and. output_prefix_problem('/') /= '' .and. &
         output_prefix_problem('   ') /= '')
   end subroutine test_output_prefixes

   !> make_parent_directory creates nested directories; a second call is fine.
   subroutine test_directories()
      type(error_t), allocatable :: err

      call make_parent_directory(nested_name, err)
      call check('make_parent_directory creates nested directories', .not. allocated(err) &
         .and. file_exists(tmp_dir) .and. file_exists(tmp_dir // '/a') &
         .and. file_exists(nested_dir), message(err))
      call check('make_parent_directory creates no file of the final name', &
         .not. file_exists(nested_name))
      call make_parent_directory(nested_name, err)
      call check('make_parent_directory on existing directories is fine', &
         .not. allocated(err), message(err))
      call make_parent_directory(nested_dir // '/', err)
      call check('make_parent_directory of a path ending in / is fine', &
         .not. allocated(err), message(err))
      call make_parent_directory('test_files_no_directory_part.dat', err)
      call check('make_parent_directory without a directory part does nothing', &
         .not. allocated(err) .and. .not. file_exists('test_files_no_directory_part.dat'), &
         message(err))
      call write_table(nested_name, 'in a nested directory', ['x'], ['m'], &
         reshape([1.0_dp], [1, 1]), err)
      call check('write_table into the new directory', .not. allocated(err) &
         .and. file_exists(nested_name), message(err))
   end subroutine test_directories

   !> Write a table with awkward values, read it back with formatted reads.
   subroutine test_table_round_trip()
      integer, parameter :: n_rows = 5, n_cols = 3
      real(dp) :: columns(n_rows, n_cols), row(n_cols)
      type(error_t), allocatable :: err
      character(len=1024) :: line
      character(len=:), allocatable :: header(:)
      integer :: unit, ios, j, n_data, n_header

      columns(:, 1) = [0.0_dp, 1.0e-4_dp, 2.0e-4_dp, 3.0e-4_dp, 4.0e-4_dp]
      columns(:, 2) = [-1.25e-3_dp, 4.0_dp * atan(1.0_dp), -1.0e-300_dp, 1.0e300_dp, &
         1.0_dp / 3.0_dp]
      columns(:, 3) = [tiny(1.0_dp), huge(1.0_dp), -epsilon(1.0_dp), 123456789.0123456_dp, &
         -0.0_dp]
      call write_table(table_name, 'tip displacement, test deck', &
         [character(len=6) :: 't', 'w_tip', 'f_stop'], [character(len=1) :: 's', 'm', 'N'], &
         columns, err)
      call check('write_table succeeds', .not. allocated(err), message(err))
      call check('write_table writes its file, no other', file_exists(table_name) &
         .and. .not. file_exists(table_name // '.part'))

      allocate(character(len=1024) :: header(0))
      n_data = 0
      n_header = 0
      open(newunit=unit, file=table_name, status='old', action='read', iostat=ios)
      call check('table file opens', ios == 0)
      if (ios /= 0) return
      do
         read(unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == '#') then
            n_header = n_header + 1
            header = [character(len=1024) :: header, line]
            cycle
         end if
         n_data = n_data + 1
         if (n_data > n_rows) cycle
         read(line, *, iostat=ios) row
         call check('row ' // str(n_data) // ' reads back', ios == 0)
         do j = 1, n_cols
            call check_close('row ' // str(n_data) // ', column ' // str(j), row(j), &
               columns(n_data, j), rtol=1.0e-15_dp)
         end do
      end do
      close(unit)
      call check('table has ' // str(n_rows) // ' data lines', n_data == n_rows, &
         'got ' // str(n_data))
      call check('table has 3 header lines', n_header == 3, 'got ' // str(n_header))
      if (n_header == 3) then
         call check('title line', header(1) == '# tip displacement, test deck', trim(header(1)))
         call check('columns line', header(2) == '# columns: t [s], w_tip [m], f_stop [N]', &
            trim(header(2)))
         call check('header line', header(3) == '# t w_tip f_stop', trim(header(3)))
      end if
      call check('values read back exactly', all(read_values(table_name, n_rows, n_cols) &
         == columns))

      columns = -columns   ! rewriting replaces the earlier file
      call write_table(table_name, 'second version', ['t     ', 'w_tip ', 'f_stop'], &
         ['s', 'm', 'N'], columns, err)
      call check('write_table replaces an existing file', .not. allocated(err) &
         .and. all(read_values(table_name, n_rows, n_cols) == columns), message(err))
   end subroutine test_table_round_trip

   !> A table without rows holds the three header lines only.
   subroutine test_zero_rows()
      real(dp) :: columns(0, 2)
      type(error_t), allocatable :: err
      character(len=256) :: line
      integer :: unit, ios, n_lines

      call write_table(empty_name, 'no rows', ['t', 'w'], ['s', 'm'], columns, err)
      call check('write_table with zero rows succeeds', .not. allocated(err) &
         .and. file_exists(empty_name) .and. .not. file_exists(empty_name // '.part'), &
         message(err))
      n_lines = 0
      open(newunit=unit, file=empty_name, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read(unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         n_lines = n_lines + 1
         call check('zero-row table: line ' // str(n_lines) // ' is a comment', &
            line(1:1) == '#', trim(line))
      end do
      close(unit)
      call check('zero-row table has exactly 3 lines', n_lines == 3, 'got ' // str(n_lines))
   end subroutine test_zero_rows

   !> write_text_file stores the text byte for byte, new lines included.
   subroutine test_text_round_trip()
      type(error_t), allocatable :: err
      character(len=:), allocatable :: text

      text = 'gapbeam report' // new_line('a') // '  first mode 12.5 Hz' // new_line('a') &
         // 'last line without new line  '
      call write_text_file(text_name, 'earlier content' // new_line('a'), err)
      call write_text_file(text_name, text, err)
      call check('write_text_file succeeds', .not. allocated(err) &
         .and. .not. file_exists(text_name // '.part'), message(err))
      call check('write_text_file round trip', read_text(text_name) == text &
         .and. len(read_text(text_name)) == len(text), read_text(text_name))
      call write_text_file(tmp_dir // '/empty.txt', '', err)
      call check('write_text_file with empty text', .not. allocated(err) &
         .and. len(read_text(tmp_dir // '/empty.txt')) == 0, message(err))
   end subroutine test_text_round_trip

   !> Failures come back as errors naming the paths, with no .part file left.
   subroutine test_errors()
      type(error_t), allocatable :: err
      character(len=*), parameter :: missing = tmp_dir // '/missing.txt'
      character(len=*), parameter :: other = tmp_dir // '/other.txt'
      character(len=*), parameter :: no_dir = tmp_dir // '/no_such_dir/t.dat'

      call write_text_file(plain_name, 'a regular file' // new_line('a'), err)
      call make_parent_directory(plain_name // '/x/y.dat', err)
      call check('make_parent_directory below a regular file: error naming it', &
         contains_text(err, 'gapbeam_files:make_parent_directory: ') &
         .and. contains_text(err, "'" // plain_name // "'") &
         .and. contains_text(err, 'not a directory'), message(err))
      call check('make_parent_directory below a regular file creates nothing', &
         .not. file_exists(plain_name // '/x'))

      call rename_file(missing, other, err)
      call check('rename_file of a missing file: error naming both paths and errno', &
         contains_text(err, 'gapbeam_files:rename_file: ') &
         .and. contains_text(err, "'" // missing // "'") &
         .and. contains_text(err, "'" // other // "'") .and. contains_text(err, 'errno'), &
         message(err))
      call rename_file(plain_name, other, err)
      call check('rename_file moves a file', .not. allocated(err) .and. file_exists(other) &
         .and. .not. file_exists(plain_name), message(err))
      call remove_file(other)
      call remove_file(other)   ! a missing file is silently ignored
      call check('remove_file deletes a file', .not. file_exists(other))

      call write_table(no_dir, 'nowhere', ['x'], ['m'], reshape([1.0_dp], [1, 1]), err)
      call check('write_table into a missing directory: error naming the file', &
         contains_text(err, 'gapbeam_files:write_table: ') &
         .and. contains_text(err, no_dir), message(err))
      call write_text_file(no_dir, 'x', err)
      call check('write_text_file into a missing directory: error naming the file', &
         contains_text(err, 'gapbeam_files:write_text_file: ') &
         .and. contains_text(err, no_dir), message(err))

      call write_table(nested_dir, 'onto a directory', ['x'], ['m'], &   ! open: EISDIR
         reshape([1.0_dp], [1, 1]), err)
      call check('write_table onto a directory: error naming it, the directory kept', &
         contains_text(err, 'gapbeam_files:write_table: cannot create') &
         .and. contains_text(err, nested_dir) .and. directory_exists(nested_dir), message(err))
   end subroutine test_errors

   !> Delete everything the test creates (directories last, deepest first).
   subroutine clean_up()
      call remove_file(table_name)
      call remove_file(table_name // '.part')
      call remove_file(empty_name)
      call remove_file(text_name)
      call remove_file(tmp_dir // '/empty.txt')
      call remove_file(plain_name)
      call remove_file(tmp_dir // '/other.txt')
      call remove_file(nested_name)
      call remove_file(nested_dir // '.part')
      call remove_file(nested_dir)            ! remove_file removes empty directories too
      call remove_file(tmp_dir // '/a')
      call remove_file(tmp_dir)
   end subroutine clean_up

   !> The data lines of a table, read with list-directed (formatted) reads.
   function read_values(path, n_rows, n_cols) result(values)
      character(len=*), intent(in) :: path      !! table file
      integer, intent(in) :: n_rows, n_cols     !! expected shape
      real(dp) :: values(n_rows, n_cols)
      character(len=1024) :: line
      integer :: unit, ios, i
      values = huge(1.0_dp)
      open(newunit=unit, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      i = 0
      do
         read(unit, '(a)', iostat=ios) line
         if (ios /= 0 .or. i == n_rows) exit
         if (line(1:1) == '#') cycle
         i = i + 1
         read(line, *, iostat=ios) values(i, :)
      end do
      close(unit)
   end function read_values

   !> The whole content of a file, byte for byte.
   function read_text(path) result(text)
      character(len=*), intent(in) :: path      !! file
      character(len=:), allocatable :: text
      integer :: unit, ios, n
      text = '<unreadable>'
      open(newunit=unit, file=path, status='old', action='read', access='stream', &
         form='unformatted', iostat=ios)
      if (ios /= 0) return
      inquire(unit=unit, size=n)
      deallocate(text)
      allocate(character(len=n) :: text)
      if (n > 0) read(unit, iostat=ios) text
      close(unit)
   end function read_text

   !> Whether an error is set and its message contains `text`.
   logical function contains_text(err, text)
      type(error_t), allocatable, intent(in) :: err   !! error, possibly unset
      character(len=*), intent(in) :: text            !! expected part of the message
      contains_text = .false.
      if (allocated(err)) contains_text = index(err%message, text) > 0
   end function contains_text

   !> The message of an error, or 'no error'.
   function message(err) result(s)
      type(error_t), allocatable, intent(in) :: err   !! error, possibly unset
      character(len=:), allocatable :: s
      s = 'no error'
      if (allocated(err)) s = err%message
   end function message

end program test_files
