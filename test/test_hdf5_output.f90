!> Tests of gapbeam_hdf5_output and gapbeam_hdf5_input: round trips with the catalogue's
!> units, long names and axes, nested groups, zero-length arrays, the `.part` -> final rename
!> on close, abort, the error state of writer and reader, the catalogue's own consistency.
program test_hdf5_output
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_output_catalogue, only: dataset_t, section_names, section_analyses, &
      section_datasets, catalogue_text
   use gapbeam_testing, only: check, finish, note
   implicit none

   interface
      !> POSIX mkdir (mode_t is an unsigned int on Linux).
      function c_mkdir(path, mode) bind(c, name='mkdir') result(status)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value, intent(in) :: mode
         integer(c_int) :: status
      end function c_mkdir

      !> POSIX rmdir.
      function c_rmdir(path) bind(c, name='rmdir') result(status)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: status
      end function c_rmdir
   end interface

   character(len=*), parameter :: file_name = 'test_hdf5_output_tmp.h5'
   character(len=*), parameter :: part_name = file_name // '.part'
   character(len=*), parameter :: text_name = 'test_hdf5_output_tmp.txt'
   character(len=*), parameter :: missing_name = 'test_hdf5_output_missing.h5'
   character(len=*), parameter :: dir_name = 'test_hdf5_output_tmpdir.h5'

   call remove_file(file_name)      ! leftovers of an interrupted earlier run
   call remove_file(part_name)
   call remove_file(text_name)

   call test_catalogue()
   call test_round_trip()
   call test_error_state()
   call test_replace_on_close()
   call test_abort()
   call test_errors()
   call test_rename_failure()

   call remove_file(file_name)
   call remove_file(part_name)
   call remove_file(text_name)
   call check('temporary files removed', .not. (file_exists(file_name) &
      .or. file_exists(part_name) .or. file_exists(text_name)))
   call finish('test_hdf5_output')

contains

   !> Write one value of each kind, close, read everything back with the attributes the
   !> catalogue gives.
   subroutine test_round_trip()
      type(h5_writer_t) :: w
      type(h5_reader_t) :: r
      type(error_t), allocatable :: err
      real(dp), parameter :: freq(3) = [12.5_dp, 78.31_dp, 219.07_dp]
      real(dp) :: k_in(3, 4), xyz_in(3, 5, 2)
      real(dp), allocatable :: r1(:), r2(:, :)
      integer, allocatable :: i1(:), i2(:, :)
      integer :: i0, i
      character(len=:), allocatable :: deck, text
      character(len=:), allocatable :: names(:)
      character(len=10) :: names_in(3)
      character(len=4) :: no_names(0)
      real(dp) :: no_reals(0)
      integer :: no_ints(0)
      logical :: ok

      allocate(character(len=1) :: names(0))   ! defined length before the first read
      k_in = reshape([(0.1_dp * i - 0.35_dp, i = 1, 12)], [3, 4])
      xyz_in = reshape([(1.0e-3_dp * i, i = 1, 30)], [3, 5, 2])
      names_in = [character(len=10) :: 'w_2', 'theta 2', 'w_3']
      deck = ''
      do i = 1, 2200   ! about 100 kB of deck text with newlines
         deck = deck // '&beam  length = 0.5, n_elem = 20, line ' // repeat('x', 4) &
            // ' /' // new_line('a')
      end do

      call w%create(file_name, 'transient')
      call check('create succeeds', .not. w%failed())
      call check('before close: only the .part file exists', file_exists(part_name) &
         .and. .not. file_exists(file_name))
      call w%put('/final/time', 0.02_dp)
      call w%put('/history/time', freq)
      call w%put('/model/stiffness', k_in(:, 1:3))            ! a section of an array
      call w%put('/model/mass', k_in)
      call w%put('/history/shape_xyz', xyz_in)
      call w%put('/run/steps_accepted', 100000)
      call w%put('/impacts/count', [3, 17, -42])
      call w%put('/history/shape_segments', reshape([0, 1, 1, 2], [2, 2]))
      call w%put('/deck', deck)
      call w%put('/run/method', '')
      call w%put('/model/dof_name', names_in)
      call w%put('/diagnostics/starts/label', [1, -1])          ! two new groups on the way
      call w%put('/impacts/peak_force', no_reals)
      call w%put('/impacts/first_contact_time', k_in(2, :))       ! a strided section
      call w%put('/diagnostics/starts/attractor', no_ints)
      call w%put('/run/files', no_names)
      call w%put('/model/stop_stiffness', [1.0e2_dp], units='N m-1')   ! units from the deck
      call w%put('/history/shape_x', [0.0_dp, 0.1_dp], fill='8')        ! long name completed
      call w%attr('/diagnostics', 'description', 'the label and its evidence')
      call w%attr('/history/time', 'note', 'absolute')
      call check('every dataset and attribute written without a failure', .not. w%failed())
      call check('writer exists: nested group', w%exists('/diagnostics/starts'))
      call check('still before close: only the .part file exists', file_exists(part_name) &
         .and. .not. file_exists(file_name))
      call w%close(err)
      call check('close succeeds', .not. allocated(err), message(err))
      call check('after close: only the final file exists', file_exists(file_name) &
         .and. .not. file_exists(part_name))

      call r%open(file_name)
      call r%read('/history/time', r1)
      ok = size(r1) == size(freq)
      if (ok) ok = all(r1 == freq)
      call check('read r1: bit-exact', ok)
      call r%read('/model/stiffness', r2)
      ok = all(shape(r2) == [3, 3])
      if (ok) ok = all(r2 == k_in(:, 1:3))
      call check('read r2 of a section: shape (3, 3) kept, bit-exact', ok)
      call r%read('/model/mass', r2)
      ok = all(shape(r2) == [3, 4])
      if (ok) ok = all(r2 == k_in)
      call check('read r2: shape (3, 4) kept, bit-exact', ok)
      call r%read('/impacts/first_contact_time', r1)
      ok = size(r1) == 4
      if (ok) ok = all(r1 == k_in(2, :))
      call check('read r1 written from a strided section', ok)
      call r%read('/run/steps_accepted', i0)
      call check('read i0', i0 == 100000)
      call r%read('/impacts/count', i1)
      ok = size(i1) == 3
      if (ok) ok = all(i1 == [3, 17, -42])
      call check('read i1', ok)
      call r%read('/history/shape_segments', i2)
      ok = all(shape(i2) == [2, 2])
      if (ok) ok = all(i2 == reshape([0, 1, 1, 2], [2, 2]))
      call check('read i2', ok)
      call r%read_text('/deck', text)
      call check('read_text: long text with newlines identical', len(text) == len(deck) &
         .and. text == deck)
      call r%read_text('/run/method', text)
      call check('read_text: empty text', len(text) == 0)
      call r%read('/model/dof_name', names)
      ok = size(names) == 3
      if (ok) ok = len(names) == 10 .and. all(names == names_in)
      call check('read s1: length and values', ok)
      call r%read('/diagnostics/starts/label', i1)
      call check('read from nested groups', all(i1 == [1, -1]))
      call r%read('/impacts/peak_force', r1)
      call check('read zero-length r1', size(r1) == 0)
      call r%read('/diagnostics/starts/attractor', i1)
      call check('read zero-length i1', size(i1) == 0)
      call r%read('/run/files', names)
      call check('read zero-length s1', size(names) == 0)
      call check('no read failed', .not. r%failed())

      call check_attr(r, '/final/time', 'units', 's')
      call check_attr(r, '/model/stiffness', 'units', 'N m-1')
      call check_attr(r, '/run/steps_accepted', 'units', '1')
      call check_attr(r, '/deck', 'units', '1')
      call check_attr(r, '/model/stop_stiffness', 'units', 'N m-1')
      call check_attr(r, '/model/stiffness', 'dimensions', 'dof dof')
      call check_attr(r, '/history/shape_xyz', 'dimensions', 'sample point coordinate')
      call check_attr(r, '/impacts/count', 'long_name', 'contact onsets of each stop in the ' &
                      // 'record')
      call check_attr(r, '/history/shape_x', 'long_name', 'x of the points of the deflected ' &
                      // 'shape (8 per element, the nodes among them)')
      call check_attr(r, '/diagnostics', 'description', 'the label and its evidence')
      call check_attr(r, '/history/time', 'note', 'absolute')
      call r%read_attr('/history/time', 'dimensions', text, err)
      call check('no dimensions below rank 2', allocated(err))

      call check('exists: root', r%exists('/'))
      call check('exists: intermediate group', r%exists('/diagnostics/starts'))
      call check('exists: missing dataset is false', .not. r%exists('/modes/nope'))
      call check('exists: missing intermediate groups is false', &
         .not. r%exists('/nope/deeper/x'))
      call check('exists: below a dataset is false', .not. r%exists('/final/time/x'))

      ! errors while reading, each its own (err given)
      call r%read('/model/stiffness', r1, err)
      call check('read r1 of a rank-2 dataset: error naming it', &
         contains_text(err, '/model/stiffness') .and. contains_text(err, 'rank'), message(err))
      call r%read('/history/time', i1, err)
      call check('read i1 of a real dataset: error naming it', &
         contains_text(err, '/history/time'), message(err))
      call r%read('/modes/missing', r1, err)
      call check('read a missing dataset: error naming dataset and file', &
         contains_text(err, '/modes/missing') .and. contains_text(err, file_name), message(err))
      call r%read_text('/history/time', text, err)
      call check('read_text of a real dataset: error', contains_text(err, '/history/time'), &
         message(err))
      call r%read_units('/diagnostics', text, err)
      call check('read_units of a group without units: error naming it', &
         contains_text(err, '/diagnostics') .and. contains_text(err, 'units'), message(err))
      call check('reads given err leave the state of the reader alone', .not. r%failed())
      ! the error state: the first failure kept, later reads skipped, close reports it
      call r%read('/modes/missing', r1)
      call check('a read without err that fails sets the state', r%failed())
      call r%read('/history/time', r1)
      call check('a later read does nothing', size(r1) == 0)
      call r%close(err)
      call check('close reports the first failure', contains_text(err, '/modes/missing'), &
         message(err))
   end subroutine test_round_trip

   !> The error state of the writer: the first failure kept, later calls do nothing, close
   !> reports it and deletes the file; each misuse the catalogue catches is named.
   subroutine test_error_state()
      call expect_failure(1, 'a path not in the catalogue', '/modes/damping', &
                          'not in the output catalogue')
      call expect_failure(1, 'a dataset of another analysis', '/sweep/label', &
                          'not in the output catalogue')
      call expect_failure(2, 'a value of another rank', '/history/time', 'rank 0')
      call expect_failure(1, 'the units of the deck not given', '/model/stop_stiffness', &
                          'units depend on the deck')
      call expect_failure(3, 'units that differ from the catalogue', '/final/time', &
                          "units 'm'")
      call expect_failure(4, 'a dataset written twice', '/run/events', 'already exists')
      call expect_failure(5, 'an attribute written twice', '/deck', 'exists already')
      call expect_failure(1, 'a path with an empty component', '/run//x', 'absolute path')
   end subroutine test_error_state

   !> One misuse (`how`): write a good dataset, the misuse, then another good one; close must
   !> report the misuse (naming `path` and `words`), delete the file and leave no final file.
   subroutine expect_failure(how, what, path, words)
      integer, intent(in) :: how
      character(len=*), intent(in) :: what, path, words
      type(h5_writer_t) :: w
      type(error_t), allocatable :: err
      call remove_file(file_name)
      call w%create(file_name, 'transient')
      call w%put('/deck', 'deck text')
      select case (how)
      case (1);  call w%put(path, [1.0_dp, 2.0_dp])
      case (2);  call w%put(path, 1.0_dp)
      case (3);  call w%put(path, 1.0_dp, units='m')
      case (4)
         call w%put(path, 1)
         call w%put(path, 2)
      case default
         call w%attr(path, 'note', 'one')
         call w%attr(path, 'note', 'two')
      end select
      call check('error state, ' // what // ': failed() is true', w%failed())
      call w%put('/run/steps_rejected', 3)                 ! does nothing now
      call w%close(err)
      call check('error state, ' // what // ': close reports it, naming ' // path, &
         contains_text(err, path) .and. contains_text(err, words) .and. &
         contains_text(err, 'gapbeam_hdf5_output'), message(err))
      call check('error state, ' // what // ': no file left', .not. file_exists(part_name) &
         .and. .not. file_exists(file_name))
   end subroutine expect_failure

   !> A file already at the final name stays intact until the new one is closed.
   subroutine test_replace_on_close()
      type(h5_writer_t) :: w
      type(h5_reader_t) :: r
      type(error_t), allocatable :: err
      real(dp), allocatable :: marker(:)

      call w%create(file_name, 'modes')
      call w%put('/modes/frequency_hz', [1.0_dp])
      call w%close(err)
      call check('earlier file present', file_exists(file_name), message(err))
      call w%create(file_name, 'transient')
      call w%put('/history/time', [2.0_dp])
      call r%open(file_name, err)   ! the earlier file, still complete, while the new one grows
      call check('earlier file still readable before close', .not. allocated(err) &
         .and. r%exists('/modes/frequency_hz') .and. .not. r%exists('/history'), message(err))
      call r%close()
      call w%close(err)
      call check('close replaces the earlier file', .not. allocated(err) &
         .and. .not. file_exists(part_name), message(err))
      call r%open(file_name)
      call r%read('/history/time', marker)
      call check('new file holds the marker', size(marker) == 1 .and. .not. r%failed())
      call check('new file lacks the earlier datasets', .not. r%exists('/modes'))
      call r%close()
   end subroutine test_replace_on_close

   !> Abort deletes the temporary file and never creates the final one.
   subroutine test_abort()
      type(h5_writer_t) :: w
      type(error_t), allocatable :: err

      call remove_file(file_name)
      call w%create(file_name, 'transient')
      call w%put('/history/time', [0.0_dp, 1.0e-4_dp])
      call check('create and write before abort', .not. w%failed())
      call w%abort()
      call check('abort leaves neither file', .not. file_exists(part_name) &
         .and. .not. file_exists(file_name))
      call w%abort()
      call check('second abort is harmless', .not. file_exists(part_name))
      call w%put('/final/time', 1.0_dp)
      call w%close(err)
      call check('write and close after abort: error naming the dataset', &
         contains_text(err, '/final/time') .and. contains_text(err, 'no open file'), message(err))
      call check('abort still left no file', .not. file_exists(part_name) &
         .and. .not. file_exists(file_name))
   end subroutine test_abort

   !> Open and create failures name the file.
   subroutine test_errors()
      type(h5_writer_t) :: w
      type(h5_reader_t) :: r
      type(error_t), allocatable :: err
      integer :: unit

      call r%open(missing_name, err)
      call check('open a missing file: error naming the file', &
         contains_text(err, missing_name) .and. contains_text(err, 'gapbeam_hdf5_input:open: '), &
         message(err))
      call check('reader of a missing file: exists is false', .not. r%exists('/'))

      open(newunit=unit, file=text_name, status='replace', action='write')
      write(unit, '(a)') 'not an HDF5 file'
      close(unit)
      call r%open(text_name, err)
      call check('open a text file: error naming the file', contains_text(err, text_name), &
         message(err))
      call remove_file(text_name)

      call w%create('test_hdf5_output_no_such_dir/out.h5', 'modes')
      call w%put('/modes/frequency_hz', [1.0_dp, 2.0_dp])
      call w%close(err)
      call check('create in a missing directory: close reports it, naming the file', &
         contains_text(err, 'test_hdf5_output_no_such_dir/out.h5'), message(err))
   end subroutine test_errors

   !> A rename that fails (final name is a directory) reports errno and keeps the .part file.
   subroutine test_rename_failure()
      type(h5_writer_t) :: w
      type(error_t), allocatable :: err
      integer(c_int) :: status

      status = c_mkdir(dir_name // c_null_char, int(o'755', c_int))
      if (status /= 0) then
         call note('mkdir ' // dir_name // ' failed: rename failure not tested')
         return
      end if
      call w%create(dir_name, 'transient')
      call w%put('/final/time', 1.0_dp)
      call w%close(err)
      call check('close onto a directory: error naming both paths and the reason', &
         contains_text(err, 'cannot rename') .and. contains_text(err, dir_name // '.part') &
         .and. contains_text(err, 'errno'), message(err))
      call check('failed rename keeps the .part file', file_exists(dir_name // '.part'))
      call w%abort()
      call check('abort after a failed rename deletes the .part file', &
         .not. file_exists(dir_name // '.part'))
      status = c_rmdir(dir_name // c_null_char)
      call check('test directory removed', status == 0)
   end subroutine test_rename_failure

   !> Every entry of the catalogue fits its fields (nothing cut), has units and a long name,
   !> and no path is described twice for one analysis.
   subroutine test_catalogue()
      type(dataset_t), allocatable :: list(:), other(:)
      character(len=:), allocatable :: bad
      integer :: s, k, t, j
      bad = ''
      do s = 1, size(section_names)
         list = section_datasets(trim(section_names(s)))
         do k = 1, size(list)
            associate (e => list(k))
               if (e%path(len(e%path):) /= ' ' .or. e%units(len(e%units):) /= ' ' .or. &
                   e%dims(len(e%dims):) /= ' ' .or. e%long_name(len(e%long_name):) /= ' ') &
                  bad = bad // ' ' // trim(e%path) // ' (a field filled to its end: cut?)'
               if (len_trim(e%units) == 0 .or. len_trim(e%long_name) == 0 .or. &
                   e%path(1:1) /= '/') bad = bad // ' ' // trim(e%path) // ' (incomplete)'
            end associate
            do t = s, size(section_names)
               if (.not. shares_word(section_analyses(s), section_analyses(t))) cycle
               other = section_datasets(trim(section_names(t)))
               do j = merge(k + 1, 1, t == s), size(other)
                  if (other(j)%path == list(k)%path) bad = bad // ' ' // trim(list(k)%path) &
                     // ' (twice)'
               end do
            end do
         end do
      end do
      call check('catalogue: every entry complete, nothing cut, no path twice', len(bad) == 0, &
                 bad)
      call check('catalogue: the markdown and tsv texts list every section', &
         index(catalogue_text('markdown'), '### continuation') > 0 .and. &
         index(catalogue_text('tsv'), '/continuation/state' // achar(9)) > 0)
   end subroutine test_catalogue

   !> Whether two blank-separated lists of words share a word.
   logical function shares_word(a, b)
      character(len=*), intent(in) :: a, b
      integer :: i, k
      shares_word = .false.
      i = 1
      do while (i <= len_trim(a))
         k = index(a(i:) // ' ', ' ')
         if (k > 1) then
            if (index(' ' // trim(b) // ' ', ' ' // a(i:i + k - 2) // ' ') > 0) shares_word = .true.
         end if
         i = i + k
      end do
   end function shares_word

   !> Check a string attribute of a dataset or group.
   subroutine check_attr(r, path, name, want)
      type(h5_reader_t), intent(inout) :: r       !! open reader
      character(len=*), intent(in) :: path, name  !! object, attribute
      character(len=*), intent(in) :: want        !! expected value
      character(len=:), allocatable :: text
      type(error_t), allocatable :: err
      call r%read_attr(path, name, text, err)
      call check(name // ' of ' // path // " = '" // want // "'", .not. allocated(err) &
         .and. text == want .and. len(text) == len(want), message(err) // "; got '" // text &
         // "'")
   end subroutine check_attr

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

   !> Whether a file exists.
   logical function file_exists(path)
      character(len=*), intent(in) :: path            !! file name
      inquire(file=path, exist=file_exists)
   end function file_exists

   !> Delete a file if it exists.
   subroutine remove_file(path)
      character(len=*), intent(in) :: path            !! file name
      integer :: unit, ios
      if (.not. file_exists(path)) return
      open(newunit=unit, file=path, status='old', iostat=ios)
      if (ios == 0) close(unit, status='delete')
   end subroutine remove_file

end program test_hdf5_output
