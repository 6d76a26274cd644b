!> Writing the HDF5 files of gapbeam results, every dataset described by the output
!> catalogue, with an atomic rename on close. This module and gapbeam_hdf5_input (the reader)
!> are the only ones of gapbeam that use the `hdf5` Fortran module.
!>
!> Errors are a state of the writer (the habit of h5fortran and fortran-lang stdlib): the
!> first failure is kept, every later call does nothing, and `close` reports it (the file is
!> then deleted). A caller writes its datasets one after the other and looks at the error
!> once, at `close`.
!>
!> What a writer stores:
!>
!> - `put(path, value)`: the dataset `path` with the attributes the catalogue
!>   (gapbeam_output_catalogue) gives it for the file's analysis: `units` (UDUNITS-2; given at
!>   the call where they depend on the deck), `long_name` and, for two axes or more,
!>   `dimensions` (the axis names in C order, as h5py shows them). A path the catalogue does
!>   not describe, or a value of another rank, is refused (an error naming both).
!> - Paths are absolute; the groups on the way are created. Writing a dataset twice is an error.
!> - Attributes are variable-length UTF-8 strings (h5py reads them as str); string datasets
!>   are fixed-length, NUL-padded, flagged UTF-8: `put(path, text)` stores one scalar string
!>   of `len(text)` bytes (newlines kept), a string array `len(value)` bytes per element.
!> - Reals are 64-bit IEEE floats, integers the default Fortran integer (32 bit).
!> - Arrays keep the Fortran shape `(n1, n2)`; C-order readers (h5py) show `(n2, n1)`.
!>
!> A writer creates `path // '.part'` and renames it to `path` only in a successful `close`
!> (or writes `path` itself for a caller that owns the atomicity: an output set). Serial HDF5
!> is not thread-safe: use writers and readers from one thread at a time. The library is
!> initialised on first use, without HDF5's clean-up at exit (which crashes after a close
!> failed on a full disk); every file must be closed.
module gapbeam_hdf5_output
   use, intrinsic :: iso_c_binding, only: c_char, c_ptr, c_null_char, c_loc, c_null_ptr
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str, q => quoted
   use gapbeam_files, only: rename_file, remove_file
   use gapbeam_output_catalogue, only: dataset_t, describe, dims_attribute, dims_rank, &
      long_name_text
   use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5dont_atexit_f, h5eset_auto_f, &
      h5iis_valid_f, h5iget_type_f, H5I_GROUP_F, h5fcreate_f, h5fopen_f, h5fclose_f, &
      H5F_ACC_TRUNC_F, H5F_ACC_RDONLY_F, h5pcreate_f, h5pclose_f, h5pset_fclose_degree_f, &
      H5P_FILE_ACCESS_F, H5F_CLOSE_STRONG_F, h5gcreate_f, h5gclose_f, h5lexists_f, h5oopen_f, &
      h5oclose_f, h5ocopy_f, h5screate_f, h5screate_simple_f, h5sclose_f, H5S_SCALAR_F, &
      h5dcreate_f, h5dclose_f, h5dwrite_f, h5tcopy_f, h5tclose_f, h5tset_size_f, &
      h5tset_strpad_f, H5T_C_S1, H5T_STR_NULLPAD_F, H5T_STRING, h5tset_cset_f, &
      H5T_CSET_UTF8_F, H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, h5acreate_f, h5aclose_f, &
      h5awrite_f, h5aexists_f
   implicit none
   private
   public :: h5_writer_t
   ! shared with gapbeam_hdf5_input, the reader
   public :: file_open, path_exists, at

   character(len=*), parameter :: module_name = 'gapbeam_hdf5_output'
   integer(hid_t), parameter :: no_id = -1_hid_t   ! an identifier not (or no longer) open

   !> Writer of one HDF5 result file of an analysis.
   !>
   !> ```fortran
   !> call h5%create('results/x.h5', 'modes')
   !> call h5%put('/modes/frequency_hz', modes%frequency_hz)
   !> call h5%close(err)            ! the first failure of any call, or of the close
   !> ```
   type :: h5_writer_t
      private
      integer(hid_t) :: file_id = no_id                !! HDF5 identifier of the open file
      character(len=:), allocatable :: path            !! final file name
      character(len=:), allocatable :: part_path       !! the name written, `path.part`
      character(len=:), allocatable :: analysis        !! whose datasets (the catalogue's word)
      logical :: is_open = .false.                     !! whether `file_id` is an open file
      logical :: in_place = .false.                    !! `path` written directly, no rename
      type(error_t), allocatable :: err                !! the first failure
   contains
      procedure :: create => writer_create             !! create `path.part` for an analysis
      procedure, private :: put_real, put_integer, put_text, put_strings
      !> A dataset described by the catalogue: reals or integers of any rank, a text, a string
      !> array.
      generic :: put => put_real, put_integer, put_text, put_strings
      procedure :: attr => writer_attr                 !! string attribute of an object
      procedure :: copy_from => writer_copy_from       !! a group copied from another file
      procedure :: exists => writer_exists             !! whether a dataset or group exists
      procedure :: failed => writer_failed             !! whether a call failed
      procedure :: close => writer_close               !! close and rename; the first failure
      procedure :: abort => writer_abort               !! close and delete, quietly
   end type h5_writer_t

contains

   ! ---------------------------------------------------------------------------------------
   ! Writer
   ! ---------------------------------------------------------------------------------------

   !> Create (or truncate) `path // '.part'` for the datasets of `analysis`; `close` renames
   !> it. With `in_place`, `path` itself is written and nothing is renamed.
   subroutine writer_create(self, path, analysis, in_place)
      class(h5_writer_t), intent(inout) :: self          !! writer, not holding an open file
      character(len=*), intent(in) :: path               !! final file name
      character(len=*), intent(in) :: analysis           !! analysis word of the catalogue
      logical, intent(in), optional :: in_place          !! write `path` itself
      integer :: hdferr
      if (self%is_open) call note(self, .true., 'create: the writer has file ' &
         // q(self%part_path) // ' open already')
      if (len_trim(path) == 0) call note(self, .true., 'create: empty file path')
      if (allocated(self%err)) return
      self%analysis = trim(analysis)
      self%in_place = .false.
      if (present(in_place)) self%in_place = in_place
      self%path = trim(path)
      self%part_path = self%path
      if (.not. self%in_place) self%part_path = self%path // '.part'
      call file_open(self%part_path, .true., self%file_id, hdferr)
      self%is_open = hdferr == 0
      call note(self, hdferr /= 0, 'create: cannot create file ' // q(self%part_path) &
         // ' (temporary name of ' // q(self%path) // '; does the directory exist and is it ' &
         // 'writable?)')
   end subroutine writer_create

   !> Reals of rank 0 to 3 (an array may have size 0), stored with the Fortran shape; the
   !> catalogue's entry says which rank the dataset has.
   subroutine put_real(self, path, value, units, fill)
      class(h5_writer_t), intent(inout) :: self          !! writer
      character(len=*), intent(in) :: path               !! dataset of the catalogue
      real(dp), intent(in) :: value(..)                  !! value(s)
      character(len=*), intent(in), optional :: units    !! units where the deck decides them
      character(len=*), intent(in), optional :: fill     !! the `{...}` part of the long name
      real(dp), allocatable, target :: flat(:)
      integer(hsize_t), allocatable :: dims(:)
      type(c_ptr) :: buf
      call flat_shape(self, path, shape(value, hsize_t), rank(value), dims)
      allocate(flat(product(dims)))
      if (size(flat) > 0) then
         select rank (value)
         rank (0);  flat = [value]
         rank (1);  flat = value
         rank (2);  flat = reshape(value, [size(flat)])
         rank (3);  flat = reshape(value, [size(flat)])
         end select
      end if
      buf = c_null_ptr
      if (size(flat) > 0) buf = c_loc(flat)
      call put_data(self, path, H5T_NATIVE_DOUBLE, dims, buf, units, fill)
   end subroutine put_real

   !> Integers of rank 0 to 3, as put_real.
   subroutine put_integer(self, path, value, units, fill)
      class(h5_writer_t), intent(inout) :: self          !! writer
      character(len=*), intent(in) :: path               !! dataset of the catalogue
      integer, intent(in) :: value(..)                   !! value(s)
      character(len=*), intent(in), optional :: units    !! units where the deck decides them
      character(len=*), intent(in), optional :: fill     !! the `{...}` part of the long name
      integer, allocatable, target :: flat(:)
      integer(hsize_t), allocatable :: dims(:)
      type(c_ptr) :: buf
      call flat_shape(self, path, shape(value, hsize_t), rank(value), dims)
      allocate(flat(product(dims)))
      if (size(flat) > 0) then
         select rank (value)
         rank (0);  flat = [value]
         rank (1);  flat = value
         rank (2);  flat = reshape(value, [size(flat)])
         rank (3);  flat = reshape(value, [size(flat)])
         end select
      end if
      buf = c_null_ptr
      if (size(flat) > 0) buf = c_loc(flat)
      call put_data(self, path, H5T_NATIVE_INTEGER, dims, buf, units, fill)
   end subroutine put_integer

   !> The dimensions of a value of rank 0 to 3 (a higher rank is refused): gfortran (12) gives
   !> an empty array expression passed as assumed rank (`real(z)` of an empty z) the extent -1,
   !> taken as 0 here.
   subroutine flat_shape(self, path, extents, r, dims)
      class(h5_writer_t), intent(inout) :: self          !! writer
      character(len=*), intent(in) :: path               !! dataset
      integer(hsize_t), intent(in) :: extents(:)         !! shape() of the value
      integer, intent(in) :: r                           !! its rank
      integer(hsize_t), allocatable, intent(out) :: dims(:)   !! dimensions to store
      dims = max(0_hsize_t, extents)
      call note(self, r > 3, q(path) // ': a value of rank ' // str(r) // ' (at most 3)')
      if (r > 3) dims = [integer(hsize_t) :: 0]
   end subroutine flat_shape

   !> A text, whole (newlines kept), as one scalar string.
   subroutine put_text(self, path, text, fill)
      class(h5_writer_t), intent(inout) :: self          !! writer
      character(len=*), intent(in) :: path               !! dataset of the catalogue
      character(len=*), intent(in) :: text               !! text
      character(len=*), intent(in), optional :: fill     !! the `{...}` part of the long name
      call put_chars(self, path, [text], .true., fill)
   end subroutine put_text

   !> A rank-1 string array; trailing blanks become NUL padding.
   subroutine put_strings(self, path, value, fill)
      class(h5_writer_t), intent(inout) :: self          !! writer
      character(len=*), intent(in) :: path               !! dataset of the catalogue
      character(len=*), intent(in) :: value(:)           !! strings
      character(len=*), intent(in), optional :: fill     !! the `{...}` part of the long name
      call put_chars(self, path, value, .false., fill)
   end subroutine put_strings

   !> Strings as fixed-length, NUL-padded UTF-8: one scalar holding `value(1)` whole
   !> (`scalar`), or a rank-1 array of `len(value)` bytes each.
   subroutine put_chars(self, path, value, scalar, fill)
      class(h5_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path, value(:)
      logical, intent(in) :: scalar
      character(len=*), intent(in), optional :: fill
      character(kind=c_char, len=1), allocatable, target :: buf(:)
      integer(hid_t) :: type_id
      integer :: width, i, j, last, hdferr
      if (allocated(self%err)) return
      width = max(1, len(value))
      allocate(buf(max(1, width * size(value))), source=c_null_char)   ! c_loc needs one
      do i = 1, size(value)
         last = len(value)
         if (.not. scalar) last = len_trim(value(i))
         do j = 1, last
            buf((i - 1) * width + j) = value(i)(j:j)
         end do
      end do
      call string_type(width, type_id, hdferr)
      call note(self, hdferr /= 0, 'cannot make a string type for ' // at(path, self%part_path))
      if (allocated(self%err)) return
      if (scalar) then
         call put_data(self, path, type_id, [integer(hsize_t) ::], c_loc(buf), fill=fill)
      else
         call put_data(self, path, type_id, [int(size(value), hsize_t)], c_loc(buf), fill=fill)
      end if
      call h5tclose_f(type_id, hdferr)
   end subroutine put_chars

   !> Look the dataset up in the catalogue, create it (and the groups on the way), write
   !> `buf` unless it is empty, and attach its attributes.
   subroutine put_data(self, path, type_id, dims, buf, units, fill)
      class(h5_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      integer(hid_t), intent(in) :: type_id
      integer(hsize_t), intent(in) :: dims(:)
      type(c_ptr), intent(in) :: buf
      character(len=*), intent(in), optional :: units, fill
      type(dataset_t) :: entry
      character(len=:), allocatable :: u, name
      integer(hid_t) :: space_id, dset_id
      logical :: found
      integer :: hdferr, status
      if (.not. open_for(self, path)) return
      call describe(self%analysis, path, entry, found)
      call note(self, .not. found, q(path) // ' is not in the output catalogue for analysis ' &
         // q(self%analysis) // ' (gapbeam_output_catalogue): a programming error')
      if (found) call note(self, dims_rank(entry) /= size(dims), q(path) // ': a value of rank ' &
         // str(size(dims)) // ', the catalogue says ' // str(dims_rank(entry)))
      u = trim(entry%units)
      if (found .and. index(u, '=') == 1) then
         call note(self, .not. present(units), q(path) // ': its units depend on the deck and ' &
            // 'were not given')
         if (present(units)) u = units
      else if (present(units)) then
         call note(self, trim(units) /= u, q(path) // ': units ' // q(units) // ' given, the ' &
            // 'catalogue says ' // q(u))
      end if
      if (allocated(self%err)) return
      name = long_name_text(entry, '')
      if (present(fill)) name = long_name_text(entry, fill)
      call make_groups(self, path(1:index(path, '/', back=.true.) - 1))
      if (allocated(self%err)) return
      call note(self, path_exists(self%file_id, path), at(path, self%part_path) // ' already exists')
      if (allocated(self%err)) return
      if (size(dims) == 0) then
         call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
      else
         call h5screate_simple_f(size(dims), dims, space_id, hdferr)
      end if
      if (hdferr == 0) then
         call h5dcreate_f(self%file_id, path, type_id, space_id, dset_id, hdferr)
         call h5sclose_f(space_id, status)
      end if
      call note(self, hdferr /= 0, 'cannot create ' // at(path, self%part_path))
      if (allocated(self%err)) return
      if (product(dims) > 0) call h5dwrite_f(dset_id, type_id, buf, hdferr)
      call note(self, hdferr /= 0, 'cannot write ' // at(path, self%part_path) // ' (a full ' &
         // 'disk?)')
      call attach(self, dset_id, 'units', u, path)
      call attach(self, dset_id, 'long_name', name, path)
      if (len(dims_attribute(entry)) > 0) call attach(self, dset_id, 'dimensions', &
                                                      dims_attribute(entry), path)
      call h5dclose_f(dset_id, hdferr)
      call note(self, hdferr /= 0, 'cannot close ' // at(path, self%part_path) // ' (a full ' &
         // 'disk?)')
   end subroutine put_data

   !> A string attribute on an open object, unless a call failed already.
   subroutine attach(self, obj_id, name, text, path)
      class(h5_writer_t), intent(inout) :: self
      integer(hid_t), intent(in) :: obj_id
      character(len=*), intent(in) :: name, text, path
      integer :: hdferr
      if (allocated(self%err)) return
      call put_string_attr(obj_id, name, text, hdferr)
      call note(self, hdferr /= 0, 'cannot write attribute ' // q(name) // ' of ' &
         // at(path, self%part_path))
   end subroutine attach

   !> Attach the string attribute `name = text` to an existing group or dataset ('/': root).
   subroutine writer_attr(self, obj_path, name, text)
      class(h5_writer_t), intent(inout) :: self          !! writer
      character(len=*), intent(in) :: obj_path           !! group or dataset
      character(len=*), intent(in) :: name               !! attribute name
      character(len=*), intent(in) :: text               !! attribute value
      integer(hid_t) :: obj_id
      integer :: hdferr
      logical :: found
      if (.not. open_for(self, obj_path)) return
      call note(self, .not. path_exists(self%file_id, obj_path), 'no group or dataset ' &
         // at(obj_path, self%part_path) // ' to carry attribute ' // q(name))
      if (allocated(self%err)) return
      call h5oopen_f(self%file_id, obj_path, obj_id, hdferr)
      call note(self, hdferr /= 0, 'cannot open ' // at(obj_path, self%part_path))
      if (allocated(self%err)) return
      call h5aexists_f(obj_id, name, found, hdferr)
      call note(self, hdferr /= 0 .or. found, 'attribute ' // q(name) // ' exists already on ' &
         // at(obj_path, self%part_path))
      call attach(self, obj_id, name, text, obj_path)
      call h5oclose_f(obj_id, hdferr)
   end subroutine writer_attr

   !> Copy the group or dataset `obj_path` (with its contents and attributes) from the file
   !> `source` to the same path; its parent group is created.
   subroutine writer_copy_from(self, source, obj_path)
      class(h5_writer_t), intent(inout) :: self          !! writer
      character(len=*), intent(in) :: source             !! HDF5 file to copy from
      character(len=*), intent(in) :: obj_path           !! e.g. '/parameters'
      integer(hid_t) :: src_id
      integer :: hdferr
      if (.not. open_for(self, obj_path)) return
      call file_open(trim(source), .false., src_id, hdferr)
      call note(self, hdferr /= 0, 'copy_from: cannot open file ' // q(source))
      if (allocated(self%err)) return
      call make_groups(self, obj_path(1:index(obj_path, '/', back=.true.) - 1))
      call note(self, .not. path_exists(src_id, obj_path), 'copy_from: no ' // q(obj_path) &
         // ' in file ' // q(source))
      if (.not. allocated(self%err)) then
         call h5ocopy_f(src_id, obj_path, self%file_id, obj_path, hdferr)
         call note(self, hdferr /= 0, 'cannot copy ' // q(obj_path) // ' of file ' // q(source) &
            // ' into file ' // q(self%part_path))
      end if
      call h5fclose_f(src_id, hdferr)
   end subroutine writer_copy_from

   !> Whether a dataset or group exists in the file being written (false when not open).
   logical function writer_exists(self, obj_path) result(found)
      class(h5_writer_t), intent(in) :: self             !! writer
      character(len=*), intent(in) :: obj_path           !! dataset or group
      found = .false.
      if (self%is_open) found = path_exists(self%file_id, obj_path)
   end function writer_exists

   !> Whether a call of the writer failed (its error is reported by `close`).
   pure logical function writer_failed(self)
      class(h5_writer_t), intent(in) :: self             !! writer
      writer_failed = allocated(self%err)
   end function writer_failed

   !> Close the file and rename `path.part` to `path`; report the first failure of any call.
   !> After a failure the incomplete file is deleted; a failed rename leaves `path.part`
   !> (`abort` deletes it); `path` is untouched either way.
   subroutine writer_close(self, err)
      class(h5_writer_t), intent(inout) :: self          !! writer
      type(error_t), allocatable, intent(out) :: err     !! the first failure
      character(len=*), parameter :: rename_prefix = 'gapbeam_files:rename_file: '
      type(error_t), allocatable :: rename_err
      integer :: hdferr
      call note(self, .not. self%is_open, 'close: no open file (never created, or already ' &
         // 'closed or aborted)')
      if (allocated(self%err)) then
         call move_alloc(self%err, err)
         call self%abort()
         return
      end if
      call h5fclose_f(self%file_id, hdferr)
      self%file_id = no_id
      self%is_open = .false.
      if (hdferr /= 0) then
         call remove_file(self%part_path)
         call fatal_error(err, module_name // ':close: cannot close file ' &
            // q(self%part_path) // ' (a full disk?); it is incomplete and was deleted')
         return
      end if
      if (.not. self%in_place) call rename_file(self%part_path, self%path, rename_err)
      if (allocated(rename_err)) then   ! "cannot rename file 'a' to 'b': <reason> (errno N)"
         call fatal_error(err, module_name // ':close: ' &
            // without_prefix(rename_err%message, rename_prefix) // '; the results are left ' &
            // 'in ' // q(self%part_path))
         return
      end if
      deallocate(self%part_path, self%path)
   end subroutine writer_close

   !> Close the file, if open, and delete it; never fails (for error paths).
   subroutine writer_abort(self)
      class(h5_writer_t), intent(inout) :: self          !! writer, open or not
      integer :: hdferr
      if (self%is_open) call h5fclose_f(self%file_id, hdferr)   ! deleted below anyway
      self%file_id = no_id
      self%is_open = .false.
      if (allocated(self%part_path)) then
         call remove_file(self%part_path)   ! a missing file is fine
         deallocate(self%part_path)
      end if
      if (allocated(self%path)) deallocate(self%path)
   end subroutine writer_abort

   !> True when the writer may write `path`: open, no earlier failure, an absolute path.
   logical function open_for(self, path)
      class(h5_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      call note(self, .not. self%is_open, 'no open file (call create first) to write ' // q(path))
      call note(self, path(1:min(1, len(path))) /= '/' .or. index(path, '//') > 0, 'path ' &
         // q(path) // ' is not an absolute path without empty components')
      open_for = .not. allocated(self%err)
   end function open_for

   !> The groups of `group_path` and above it, where missing.
   subroutine make_groups(self, group_path)
      class(h5_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: group_path        !! '' for the root
      integer(hid_t) :: group_id
      integer :: k, hdferr
      logical :: found
      do k = 2, len(group_path) + 1
         if (k <= len(group_path)) then
            if (group_path(k:k) /= '/') cycle
         end if
         if (allocated(self%err)) return
         call h5lexists_f(self%file_id, group_path(1:k - 1), found, hdferr)
         if (found .and. hdferr == 0) then
            call note(self, object_type(self%file_id, group_path(1:k - 1)) /= H5I_GROUP_F, &
               q(group_path(1:k - 1)) // ' is not a group, in file ' // q(self%part_path))
         else
            call h5gcreate_f(self%file_id, group_path(1:k - 1), group_id, hdferr)
            if (hdferr == 0) call h5gclose_f(group_id, hdferr)
            call note(self, hdferr /= 0, 'cannot create group ' // at(group_path(1:k - 1), self%part_path))
         end if
      end do
   end subroutine make_groups

   !> Keep the first failure: set the error when `failed` and none is set.
   subroutine note(self, failed, message)
      class(h5_writer_t), intent(inout) :: self
      logical, intent(in) :: failed
      character(len=*), intent(in) :: message
      if (failed .and. .not. allocated(self%err)) call fatal_error(self%err, module_name &
         // ': ' // message)
   end subroutine note

   !> "dataset '<path>' in file '<file>'", for messages.
   pure function at(path, file) result(s)
      character(len=*), intent(in) :: path, file
      character(len=:), allocatable :: s
      s = 'dataset ' // q(path) // ' in file ' // q(file)
   end function at

   ! ---------------------------------------------------------------------------------------
   ! Library, paths, text
   ! ---------------------------------------------------------------------------------------

   !> Initialise the HDF5 library unless done, and switch off HDF5's own printing of errors.
   subroutine library_open(hdferr)
      integer, intent(out) :: hdferr                     !! 0 on success
      logical :: ready
      integer :: status
      ready = .false.
      if (H5T_NATIVE_DOUBLE > 0) then   ! set by an earlier h5open_f, still valid unless closed
         call h5iis_valid_f(H5T_NATIVE_DOUBLE, ready, status)
         if (status /= 0) ready = .false.
      end if
      hdferr = 0
      if (.not. ready) then
         ! no clean-up at exit: after a failed close (a full disk) HDF5's exit handler tries
         ! the file again and crashes; every file is closed by its writer or reader
         call h5dont_atexit_f(status)        ! fails harmlessly once the library is running
         call h5open_f(hdferr)
      end if
      if (hdferr == 0) call h5eset_auto_f(0, hdferr)
   end subroutine library_open

   !> Create (truncating) or open read-only an HDF5 file, the library initialised, with a
   !> file access list that closes every object of the file with the file.
   subroutine file_open(path, create, file_id, hdferr)
      character(len=*), intent(in) :: path               !! file name
      logical, intent(in) :: create                      !! create, else open read-only
      integer(hid_t), intent(out) :: file_id             !! the open file
      integer, intent(out) :: hdferr                     !! 0 on success
      integer(hid_t) :: fapl
      integer :: status
      call library_open(hdferr)
      if (hdferr == 0) call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, hdferr)
      if (hdferr /= 0) return
      call h5pset_fclose_degree_f(fapl, H5F_CLOSE_STRONG_F, hdferr)
      if (hdferr == 0 .and. create) then
         call h5fcreate_f(path, H5F_ACC_TRUNC_F, file_id, hdferr, access_prp=fapl)
      else if (hdferr == 0) then
         call h5fopen_f(path, H5F_ACC_RDONLY_F, file_id, hdferr, access_prp=fapl)
      end if
      call h5pclose_f(fapl, status)
   end subroutine file_open

   !> Whether every link of the absolute path `p` exists ('/' always does).
   logical function path_exists(file_id, p) result(found)
      integer(hid_t), intent(in) :: file_id
      character(len=*), intent(in) :: p
      integer :: k, hdferr
      logical :: link_found
      found = .false.
      do k = 2, len(p)
         if (k < len(p)) then
            if (p(k + 1:k + 1) /= '/') cycle
         end if
         call h5lexists_f(file_id, p(1:k), link_found, hdferr)
         if (hdferr /= 0 .or. .not. link_found) return
      end do
      found = .true.
   end function path_exists

   !> HDF5 identifier type (H5I_GROUP_F, H5I_DATASET_F, ...) of the object at `p`; -1 when
   !> it cannot be opened.
   integer function object_type(file_id, p)
      integer(hid_t), intent(in) :: file_id
      character(len=*), intent(in) :: p
      integer(hid_t) :: obj_id
      integer :: hdferr
      object_type = -1
      call h5oopen_f(file_id, p, obj_id, hdferr)
      if (hdferr /= 0) return
      call h5iget_type_f(obj_id, object_type, hdferr)
      call h5oclose_f(obj_id, hdferr)
   end function object_type

   !> Create and write a scalar variable-length UTF-8 string attribute on an open object.
   subroutine put_string_attr(obj_id, name, text, hdferr)
      integer(hid_t), intent(in) :: obj_id               !! open group or dataset
      character(len=*), intent(in) :: name, text         !! attribute name and value
      integer, intent(out) :: hdferr                     !! 0 on success
      character(kind=c_char, len=1), allocatable, target :: buf(:)
      type(c_ptr), target :: ptr(1)
      integer(hid_t) :: type_id, space_id, attr_id
      integer :: j, status
      allocate(buf(len(text) + 1))
      do j = 1, len(text)
         buf(j) = text(j:j)
      end do
      buf(len(text) + 1) = c_null_char
      ptr(1) = c_loc(buf(1))
      call h5tcopy_f(H5T_STRING, type_id, hdferr)
      if (hdferr /= 0) return
      call h5tset_cset_f(type_id, H5T_CSET_UTF8_F, hdferr)
      if (hdferr == 0) call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
      if (hdferr == 0) then
         call h5acreate_f(obj_id, name, type_id, space_id, attr_id, hdferr)
         if (hdferr == 0) then
            call h5awrite_f(attr_id, type_id, c_loc(ptr(1)), hdferr)
            call h5aclose_f(attr_id, status)
            if (hdferr == 0) hdferr = status
         end if
         call h5sclose_f(space_id, status)
      end if
      call h5tclose_f(type_id, status)
   end subroutine put_string_attr

   !> A copy of the C string type of `width` bytes, NUL-padded, UTF-8.
   subroutine string_type(width, type_id, hdferr)
      integer, intent(in) :: width                       !! bytes per string, >= 1
      integer(hid_t), intent(out) :: type_id             !! new datatype (close with h5tclose_f)
      integer, intent(out) :: hdferr                     !! 0 on success
      integer :: status
      call h5tcopy_f(H5T_C_S1, type_id, hdferr)
      if (hdferr /= 0) return
      call h5tset_size_f(type_id, int(width, size_t), hdferr)
      if (hdferr == 0) call h5tset_strpad_f(type_id, H5T_STR_NULLPAD_F, hdferr)
      if (hdferr == 0) call h5tset_cset_f(type_id, H5T_CSET_UTF8_F, hdferr)
      if (hdferr /= 0) call h5tclose_f(type_id, status)
   end subroutine string_type

   !> `message` without its leading `prefix`.
   pure function without_prefix(message, prefix) result(s)
      character(len=*), intent(in) :: message, prefix
      character(len=:), allocatable :: s
      s = message
      if (len(message) >= len(prefix)) then
         if (message(1:len(prefix)) == prefix) s = message(len(prefix) + 1:)
      end if
   end function without_prefix
end module gapbeam_hdf5_output
