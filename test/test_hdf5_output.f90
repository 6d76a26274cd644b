!> Tests of gapbeam_hdf5_output: round trips with units, nested groups, zero-length arrays,
!> the `.part` -> final rename on close, abort, and error messages naming file and dataset.
program test_hdf5_output
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t, h5_reader_t
   use gapbeam_testing, only: check, check_close, finish, note
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

   call test_round_trip()
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

   !> Write one value of each kind, close, read everything back.
   subroutine test_round_trip()
      type(h5_writer_t) :: w
      type(h5_reader_t) :: r
      type(error_t), allocatable :: err
      real(dp), parameter :: freq(3) = [12.5_dp, 78.31_dp, 219.07_dp]
      real(dp), parameter :: strain(4) = [1.0e-6_dp, -2.5e-5_dp, 3.0e-4_dp, 0.0_dp]
      real(dp) :: shape_in(3, 4), damping
      real(dp), allocatable :: r1(:), r2(:, :)
      integer, allocatable :: i1(:)
      integer :: i0, i
      character(len=:), allocatable :: deck, text, units
      character(len=:), allocatable :: labels(:)
      character(len=10) :: labels_in(3)
      character(len=4) :: no_labels(0)
      real(dp) :: no_reals(0)
      integer :: no_ints(0)
      logical :: ok

      allocate(character(len=1) :: labels(0))   ! defined length before the first read
      shape_in = reshape([(0.1_dp * i - 0.35_dp, i = 1, 12)], [3, 4])
      labels_in = [character(len=10) :: 'gap_1mm', 'gap 2 mm', 'no_stop']
      deck = ''
      do i = 1, 2200   ! about 100 kB of deck text with newlines
         deck = deck // '&beam  length = 0.5, n_elem = 20, line ' // repeat('x', 4) &
            // ' /' // new_line('a')
      end do

      call w%create(file_name, err)
      call check('create succeeds', .not. allocated(err), message(err))
      call check('before close: only the .part file exists', file_exists(part_name) &
         .and. .not. file_exists(file_name))

      call w%write('/modes/damping', 0.02_dp, '-', err)
      call check('write r0', .not. allocated(err), message(err))
      call w%write('/modes/frequency', freq, 'Hz', err)
      call check('write r1', .not. allocated(err), message(err))
      call w%write('/modes/shape', shape_in, 'm', err, 'mode shape, w at the nodes', &
                   'mode node')
      call check('write r2 with long_name and dimensions', .not. allocated(err), message(err))
      call w%write('/run/n_steps', 100000, '-', err)
      call check('write i0', .not. allocated(err), message(err))
      call w%write('/impacts/step', [3, 17, -42], '-', err)
      call check('write i1', .not. allocated(err), message(err))
      call w%write_text('/input/deck', deck, err)
      call check('write_text of ' // str(len(deck)) // ' characters', .not. allocated(err), &
         message(err))
      call w%write_text('/input/empty', '', err)
      call check('write_text of an empty text', .not. allocated(err), message(err))
      call w%write('/sweep/label', labels_in, '-', err)
      call check('write s1', .not. allocated(err), message(err))
      call w%write('/sweep/point_0001/poincare/strain', strain, '-', err)
      call check('write into four new nested groups', .not. allocated(err), message(err))
      call w%write('/history/time', no_reals, 's', err)
      call check('write zero-length r1', .not. allocated(err), message(err))
      call w%write('/history/impacts', no_ints, '-', err)
      call check('write zero-length i1', .not. allocated(err), message(err))
      call w%write('/history/labels', no_labels, '-', err)
      call check('write zero-length s1', .not. allocated(err), message(err))
      call w%write_attr('/sweep', 'description', 'cases of the gap sweep', err)
      call check('write_attr on a group', .not. allocated(err), message(err))
      call w%write_attr('/modes/frequency', 'label', 'natural frequencies', err)
      call check('write_attr on a dataset', .not. allocated(err), message(err))
      call check('writer exists: nested group', w%exists('/sweep/point_0001/poincare'))

      ! errors while writing
      call w%write('/modes/frequency', freq, 'Hz', err)
      call check('existing dataset: error', allocated(err))
      call check('existing dataset: message names dataset and file', &
         contains_text(err, '/modes/frequency') .and. contains_text(err, part_name) &
         .and. contains_text(err, 'gapbeam_hdf5_output:write_r1: '), message(err))
      call w%write('/run/n_steps/extra', 1.0_dp, 'm', err)
      call check('dataset used as group: error naming it', contains_text(err, '/run/n_steps'), &
         message(err))
      call w%write_attr('/sweep', 'description', 'again', err)
      call check('existing attribute: error naming it', contains_text(err, 'description') &
         .and. contains_text(err, '/sweep'), message(err))
      call w%write_attr('/nowhere', 'description', 'text', err)
      call check('attribute on a missing object: error naming it', &
         contains_text(err, '/nowhere'), message(err))

      call check('still before close: only the .part file exists', file_exists(part_name) &
         .and. .not. file_exists(file_name))
      call w%close(err)
      call check('close succeeds', .not. allocated(err), message(err))
      call check('after close: only the final file exists', file_exists(file_name) &
         .and. .not. file_exists(part_name))

      call r%open(file_name, err)
      call check('open for reading', .not. allocated(err), message(err))

      call r%read('/modes/damping', damping, err)
      call check_close('read r0', damping, 0.02_dp, rtol=0.0_dp)
      call r%read('/modes/frequency', r1, err)
      ok = .not. allocated(err) .and. size(r1) == size(freq)
      if (ok) ok = maxval(abs(r1 - freq)) == 0.0_dp
      call check('read r1: bit-exact', ok, message(err))
      call r%read('/modes/shape', r2, err)
      ok = .not. allocated(err) .and. all(shape(r2) == [3, 4])
      if (ok) ok = maxval(abs(r2 - shape_in)) == 0.0_dp
      call check('read r2: shape (3, 4) kept, bit-exact', ok, message(err))
      call r%read('/run/n_steps', i0, err)
      call check('read i0', .not. allocated(err) .and. i0 == 100000, message(err))
      call r%read('/impacts/step', i1, err)
      ok = .not. allocated(err) .and. size(i1) == 3
      if (ok) ok = all(i1 == [3, 17, -42])
      call check('read i1', ok, message(err))
      call r%read_text('/input/deck', text, err)
      call check('read_text: long text with newlines identical', .not. allocated(err) &
         .and. len(text) == len(deck) .and. text == deck, message(err))
      call r%read_text('/input/empty', text, err)
      call check('read_text: empty text', .not. allocated(err) .and. len(text) == 0, &
         message(err))
      call r%read('/sweep/label', labels, err)
      ok = .not. allocated(err) .and. size(labels) == 3
      if (ok) ok = len(labels) == 10 .and. all(labels == labels_in)
      call check('read s1: length and values', ok, message(err))
      call r%read('/sweep/point_0001/poincare/strain', r1, err)
      ok = .not. allocated(err) .and. size(r1) == size(strain)
      if (ok) ok = maxval(abs(r1 - strain)) == 0.0_dp
      call check('read from nested groups', ok, message(err))
      call r%read('/history/time', r1, err)
      call check('read zero-length r1', .not. allocated(err) .and. size(r1) == 0, message(err))
      call r%read('/history/impacts', i1, err)
      call check('read zero-length i1', .not. allocated(err) .and. size(i1) == 0, message(err))
      call r%read('/history/labels', labels, err)
      call check('read zero-length s1', .not. allocated(err) .and. size(labels) == 0, &
         message(err))

      call check_units(r, '/modes/damping', '-')
      call check_units(r, '/modes/frequency', 'Hz')
      call check_units(r, '/modes/shape', 'm')
      call check_units(r, '/run/n_steps', '-')
      call check_units(r, '/impacts/step', '-')
      call check_units(r, '/sweep/label', '-')
      call check_units(r, '/history/time', 's')
      call check_units(r, '/input/deck', '1')
      call r%read_attr('/modes/shape', 'long_name', text, err)
      call check('long_name written and read back', .not. allocated(err) &
         .and. text == 'mode shape, w at the nodes', message(err) // ' got ' // text)
      call r%read_attr('/modes/shape', 'dimensions', text, err)
      call check('dimensions written and read back', .not. allocated(err) &
         .and. text == 'mode node', message(err) // ' got ' // text)
      call r%read_attr('/modes/frequency', 'long_name', text, err)
      call check('no long_name unless given', allocated(err))
      call r%read_attr('/sweep', 'description', text, err)
      call check('read_attr of a group', .not. allocated(err) &
         .and. text == 'cases of the gap sweep', message(err))
      call r%read_attr('/modes/frequency', 'label', text, err)
      call check('read_attr of a dataset', .not. allocated(err) &
         .and. text == 'natural frequencies', message(err))

      call check('exists: root', r%exists('/'))
      call check('exists: intermediate group', r%exists('/sweep/point_0001'))
      call check('exists: nested dataset', r%exists('/sweep/point_0001/poincare/strain'))
      call check('exists: missing dataset is false', .not. r%exists('/modes/nope'))
      call check('exists: missing intermediate groups is false', &
         .not. r%exists('/nope/deeper/x'))
      call check('exists: below a dataset is false', .not. r%exists('/run/n_steps/x'))

      ! errors while reading
      call r%read('/modes/shape', r1, err)
      call check('read r1 of a rank-2 dataset: error naming it', &
         contains_text(err, '/modes/shape') .and. contains_text(err, 'rank'), message(err))
      call r%read('/modes/frequency', i1, err)
      call check('read i1 of a real dataset: error naming it', &
         contains_text(err, '/modes/frequency'), message(err))
      call r%read('/modes/missing', r1, err)
      call check('read a missing dataset: error naming dataset and file', &
         contains_text(err, '/modes/missing') .and. contains_text(err, file_name), &
         message(err))
      call r%read_text('/modes/frequency', text, err)
      call check('read_text of a real dataset: error', contains_text(err, '/modes/frequency'), &
         message(err))
      call r%read_units('/sweep', units, err)
      call check('read_units of a group without units: error naming it', &
         contains_text(err, '/sweep') .and. contains_text(err, 'units'), message(err))
      call r%close()
   end subroutine test_round_trip

   !> A file already at the final name stays intact until the new one is closed.
   subroutine test_replace_on_close()
      type(h5_writer_t) :: w
      type(h5_reader_t) :: r
      type(error_t), allocatable :: err
      real(dp) :: marker

      call check('earlier file present', file_exists(file_name))
      call w%create(file_name, err)
      call check('create over an earlier file', .not. allocated(err), message(err))
      call w%write('/marker', 2.0_dp, 'm', err)
      call check('write marker', .not. allocated(err), message(err))

      call r%open(file_name, err)   ! the earlier file, still complete, while the new one grows
      call check('earlier file still readable before close', .not. allocated(err) &
         .and. r%exists('/modes/frequency') .and. .not. r%exists('/marker'), message(err))
      call r%close()

      call w%close(err)
      call check('close replaces the earlier file', .not. allocated(err) &
         .and. .not. file_exists(part_name), message(err))
      call r%open(file_name, err)
      call check('new file readable', .not. allocated(err), message(err))
      call r%read('/marker', marker, err)
      call check_close('new file holds the marker', marker, 2.0_dp, rtol=0.0_dp)
      call check('new file lacks the earlier datasets', .not. r%exists('/modes'))
      call r%close()
   end subroutine test_replace_on_close

   !> Abort deletes the temporary file and never creates the final one.
   subroutine test_abort()
      type(h5_writer_t) :: w
      type(error_t), allocatable :: err

      call remove_file(file_name)
      call w%create(file_name, err)
      call check('create before abort', .not. allocated(err), message(err))
      call w%write('/history/time', [0.0_dp, 1.0e-4_dp], 's', err)
      call check('write before abort', .not. allocated(err), message(err))
      call w%abort()
      call check('abort leaves neither file', .not. file_exists(part_name) &
         .and. .not. file_exists(file_name))
      call w%abort()
      call check('second abort is harmless', .not. file_exists(part_name))
      call w%close(err)
      call check('close after abort: error', allocated(err), message(err))
      call w%write('/x', 1.0_dp, 'm', err)
      call check('write after abort: error naming the dataset', contains_text(err, '/x'), &
         message(err))
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
         contains_text(err, missing_name) .and. contains_text(err, 'gapbeam_hdf5_output:open: '), &
         message(err))
      call check('reader of a missing file: exists is false', .not. r%exists('/'))

      open(newunit=unit, file=text_name, status='replace', action='write')
      write(unit, '(a)') 'not an HDF5 file'
      close(unit)
      call r%open(text_name, err)
      call check('open a text file: error naming the file', contains_text(err, text_name), &
         message(err))
      call remove_file(text_name)

      call w%create('test_hdf5_output_no_such_dir/out.h5', err)
      call check('create in a missing directory: error naming the file', &
         contains_text(err, 'test_hdf5_output_no_such_dir/out.h5'), message(err))
      call w%write('/a', [1, 2], '-', err)
      call check('write without an open file: error naming the dataset', &
         contains_text(err, '/a'), message(err))
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
      call w%create(dir_name, err)
      call check('create next to a directory of the final name', .not. allocated(err), &
         message(err))
      call w%write('/x', 1.0_dp, 'm', err)
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

   !> Check the `units` attribute of a dataset.
   subroutine check_units(r, dset_path, want)
      type(h5_reader_t), intent(in) :: r          !! open reader
      character(len=*), intent(in) :: dset_path   !! dataset
      character(len=*), intent(in) :: want        !! expected units
      character(len=:), allocatable :: units
      type(error_t), allocatable :: err
      call r%read_units(dset_path, units, err)
      if (allocated(err)) then
         call check('units of ' // dset_path, .false., message(err))
      else
         call check('units of ' // dset_path // ' = ' // want, units == want .and. &
            len(units) == len(want), "got '" // units // "'")
      end if
   end subroutine check_units

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
