!> HDF5 files of gapbeam results: writing, with an atomic rename on close, and reading back.
!>
!> This is the only module of gapbeam that uses the `hdf5` Fortran module.
!>
!> What a writer stores:
!>
!> - Paths are absolute, '/history/time' or '/sweep/point_0001/poincare/strain'; the groups on
!>   the way are created when missing. Writing a dataset that already exists is an error.
!> - Every dataset written by `write` has a string attribute `units` in UDUNITS-2 form ('Hz',
!>   'm', 'm s-1', 'N m rad-1', '1' for a pure number, 's-1'); optional attributes `long_name`
!>   (what the values are, in words) and `dimensions` (the names of the axes in C order, as
!>   h5py shows them, e.g. 'point stop'). Text datasets written by `write_text` get
!>   `units = '1'`.
!> - Attributes are variable-length UTF-8 strings (h5py reads them as str); string datasets
!>   are fixed-length, flagged UTF-8.
!> - Reals are 64-bit IEEE floats, integers the default Fortran integer (32 bit).
!> - Rank-2 arrays keep the Fortran shape `(n1, n2)` as the HDF5 Fortran API does; C-order
!>   readers (h5py, h5dump) show the dimensions reversed, `(n2, n1)`.
!> - Strings are fixed-length, NUL-padded: `write_text` stores one scalar string of
!>   `len(text)` bytes (at least 1, newlines kept); a string array keeps `len(value)` bytes per
!>   element, its trailing blanks become NUL padding and read back as blanks.
!>
!> A writer creates `path // '.part'` and renames it to `path` only in a successful `close`:
!> a run that fails or is killed leaves no half-written file under the final name, and a file
!> already at `path` from an earlier run is replaced only by a complete one (the rename and the
!> deletion of `.part` files go through `gapbeam_files`).
!>
!> Serial HDF5 is not thread-safe: use writers and readers from one thread at a time (outside
!> OpenMP parallel regions, or inside one named critical section). The library is initialised
!> on first use, without HDF5's clean-up at program exit (which crashes after a close failed
!> on a full disk), and never shut down by this module, so several files can be written and
!> read in one program, one after another or at the same time; every file must be closed.
module gapbeam_hdf5_output
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: iso_c_binding, only: c_char, c_ptr, c_null_char, c_loc, c_null_ptr, &
      c_associated, c_f_pointer, c_size_t, c_int
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_files, only: rename_file, remove_file
   use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5dont_atexit_f, h5eset_auto_f, &
      h5iis_valid_f, h5iget_type_f, H5I_GROUP_F, H5I_DATASET_F, &
      h5fcreate_f, h5fopen_f, h5fclose_f, H5F_ACC_TRUNC_F, H5F_ACC_RDONLY_F, &
      h5pcreate_f, h5pclose_f, h5pset_fclose_degree_f, H5P_FILE_ACCESS_F, H5F_CLOSE_STRONG_F, &
      h5gcreate_f, h5gclose_f, h5lexists_f, h5oopen_f, h5oclose_f, h5ocopy_f, &
      h5screate_f, h5screate_simple_f, h5sclose_f, H5S_SCALAR_F, &
      h5sget_simple_extent_ndims_f, h5sget_simple_extent_dims_f, &
      h5dcreate_f, h5dopen_f, h5dclose_f, h5dwrite_f, h5dread_f, h5dget_type_f, h5dget_space_f, &
      h5tcopy_f, h5tclose_f, h5tset_size_f, h5tset_strpad_f, h5tget_size_f, h5tget_class_f, &
      h5tis_variable_str_f, H5T_C_S1, H5T_STR_NULLPAD_F, H5T_STRING_F, H5T_FLOAT_F, &
      H5T_STRING, h5tset_cset_f, H5T_CSET_UTF8_F, &
      H5T_INTEGER_F, H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, &
      h5acreate_f, h5aopen_f, h5aclose_f, h5awrite_f, h5aread_f, h5aexists_f, h5aget_type_f, &
      h5aget_space_f, haddr_t, h5dget_offset_f, h5tget_order_f, H5T_ORDER_LE_F
   implicit none
   private
   public :: h5_writer_t, h5_reader_t, write_failed

   character(len=*), parameter :: module_name = 'gapbeam_hdf5_output'

   interface
      !> strlen(3) of a C string.
      function c_strlen(p) bind(c, name='strlen') result(n)
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: p
         integer(c_size_t) :: n
      end function c_strlen
      !> H5free_memory: frees memory the HDF5 library allocated (a variable-length string).
      function c_free_memory(p) bind(c, name='H5free_memory') result(status)
         import :: c_ptr, c_int
         type(c_ptr), value, intent(in) :: p
         integer(c_int) :: status
      end function c_free_memory
   end interface
   integer(hid_t), parameter :: no_id = -1_hid_t   ! an HDF5 identifier not (or no longer) open

   !> Writer of one HDF5 result file, created as `path.part` and renamed to `path` on close.
   !>
   !> ```fortran
   !> call out%create('results/baseline.h5', err);  if (allocated(err)) return
   !> call out%write_text('/input/deck', deck_text, err)
   !> call out%write('/modes/frequency', freq_hz, units='Hz', err=err)
   !> call out%close(err)
   !> ```
   type :: h5_writer_t
      private
      integer(hid_t) :: file_id = no_id                !! HDF5 identifier of the open file
      character(len=:), allocatable :: path            !! final file name, written on close
      character(len=:), allocatable :: part_path       !! temporary file name, `path // '.part'`
      logical :: is_open = .false.                     !! whether `file_id` is an open file
      logical :: in_place = .false.                    !! `path` written directly, no rename
   contains
      procedure :: create => writer_create             !! create `path.part`, remember `path`
      procedure :: write_text => writer_write_text     !! scalar string dataset (whole text)
      procedure, private :: write_r0 => writer_write_r0
      procedure, private :: write_r1 => writer_write_r1
      procedure, private :: write_r2 => writer_write_r2
      procedure, private :: write_i0 => writer_write_i0
      procedure, private :: write_i1 => writer_write_i1
      procedure, private :: write_r3 => writer_write_r3
      procedure, private :: write_i2 => writer_write_i2
      procedure, private :: write_s1 => writer_write_s1
      !> Dataset of a real(dp) scalar / rank-1 / rank-2 array, an integer scalar / rank-1 array
      !> or a rank-1 string array, with a `units` attribute.
      generic :: write => write_r0, write_r1, write_r2, write_r3, write_i0, write_i1, write_i2, &
         write_s1
      procedure :: write_attr => writer_write_attr     !! string attribute on a group or dataset
      procedure :: create_group => writer_create_group !! group and its parents, when missing
      procedure :: exists => writer_exists             !! whether a dataset or group exists
      procedure :: copy_from => writer_copy_from       !! copy a group from another file
      procedure :: close => writer_close               !! close, then rename `path.part` to `path`
      procedure :: abort => writer_abort               !! close and delete `path.part`, quietly
   end type h5_writer_t

   !> Read-only access to an HDF5 file written by `h5_writer_t`.
   type :: h5_reader_t
      private
      integer(hid_t) :: file_id = no_id                !! HDF5 identifier of the open file
      character(len=:), allocatable :: path            !! name of the open file
      logical :: is_open = .false.                     !! whether `file_id` is an open file
   contains
      procedure :: open => reader_open                 !! open a file read-only
      procedure :: exists => reader_exists             !! whether a dataset or group exists
      procedure, private :: read_r0 => reader_read_r0
      procedure, private :: read_r1 => reader_read_r1
      procedure, private :: read_r2 => reader_read_r2
      procedure, private :: read_i0 => reader_read_i0
      procedure, private :: read_i1 => reader_read_i1
      procedure, private :: read_i2 => reader_read_i2
      procedure, private :: read_s1 => reader_read_s1
      !> Read a real(dp) scalar / rank-1 / rank-2, an integer scalar / rank-1 or a string array
      !> dataset; arrays are allocated to the stored shape.
      generic :: read => read_r0, read_r1, read_r2, read_i0, read_i1, read_i2, read_s1
      procedure :: read_text => reader_read_text       !! scalar string dataset
      procedure :: read_units => reader_read_units     !! the `units` attribute of a dataset
      procedure :: read_attr => reader_read_attr       !! a string attribute of a group or dataset
      procedure :: data_offset => reader_data_offset   !! byte offset and order of stored values
      procedure :: close => reader_close               !! close the file, quietly
   end type h5_reader_t

contains

   ! ---------------------------------------------------------------------------------------
   ! Writer
   ! ---------------------------------------------------------------------------------------

   !> Create (or truncate) `path // '.part'` for writing; `close` renames it to `path`.
   !> With `in_place = .true.` `path` itself is written and `close` renames nothing (for a
   !> caller that owns the atomicity, such as an output set writing under temporary names).
   subroutine writer_create(self, path, err, in_place)
      class(h5_writer_t), intent(inout) :: self          !! writer, not holding an open file
      character(len=*), intent(in) :: path               !! final file name, e.g. 'results/a.h5'
      type(error_t), allocatable, intent(out) :: err     !! set when the file cannot be created
      logical, intent(in), optional :: in_place          !! write `path` itself
      character(len=*), parameter :: proc = 'create'
      character(len=:), allocatable :: part
      integer(hid_t) :: fapl
      integer :: hdferr, status

      if (self%is_open) then
         call fatal_error(err, here(proc) // 'writer already has file ' // q(self%part_path) &
            // ' open; close or abort it before creating ' // q(trim(path)))
         return
      end if
      if (len_trim(path) == 0) then
         call fatal_error(err, here(proc) // 'empty file path')
         return
      end if
      self%in_place = .false.
      if (present(in_place)) self%in_place = in_place
      if (self%in_place) then
         part = trim(path)
      else
         part = trim(path) // '.part'
      end if
      call library_open(status)
      if (status /= 0) then
         call fatal_error(err, here(proc) // 'cannot initialise the HDF5 library to create file ' &
            // q(part))
         return
      end if
      call file_access_list(fapl, status)
      if (status /= 0) then
         call fatal_error(err, here(proc) // 'cannot set up file access for file ' // q(part))
         return
      end if
      call h5fcreate_f(part, H5F_ACC_TRUNC_F, self%file_id, hdferr, access_prp=fapl)
      call h5pclose_f(fapl, status)
      if (hdferr /= 0) then
         self%file_id = no_id
         call fatal_error(err, here(proc) // 'cannot create file ' // q(part) &
            // ' (temporary name of ' // q(trim(path)) &
            // '; does the directory exist and is it writable?)')
         return
      end if
      self%path = trim(path)
      self%part_path = part
      self%is_open = .true.
      if (status /= 0) then
         call fatal_error(err, here(proc) // 'cannot release the file access list of file ' &
            // q(part))
      end if
   end subroutine writer_create

   !> Write `text` (newlines kept, any length) as one fixed-length string, with `units = '1'`.
   subroutine writer_write_text(self, dset_path, text, err, long_name)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/input/deck'
      character(len=*), intent(in) :: text               !! text to store
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the text is, in words
      call write_strings(self, 'write_text', dset_path, [text], .true., '1', err, long_name)
   end subroutine writer_write_text

   !> Write a real scalar.
   subroutine writer_write_r0(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/modes/damping'
      real(dp), intent(in) :: value                      !! value [units]
      character(len=*), intent(in) :: units              !! units of `value`, e.g. 'Hz', '-'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      character(len=*), parameter :: proc = 'write_r0'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(0)
      integer :: hdferr

      call begin_dataset(self, proc, dset_path, H5T_NATIVE_DOUBLE, dims, dset_id, err)
      if (allocated(err)) return
      call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, value, [1_hsize_t], hdferr)
      if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
         // at('dataset', dset_path, self%part_path))
      call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
   end subroutine writer_write_r0

   !> Write a real rank-1 array (size 0 allowed).
   subroutine writer_write_r1(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/history/time'
      real(dp), intent(in) :: value(:)                   !! values [units]
      character(len=*), intent(in) :: units              !! units of `value`, e.g. 's', 'm'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      character(len=*), parameter :: proc = 'write_r1'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(1)
      integer :: hdferr

      dims = shape(value, kind=hsize_t)
      call begin_dataset(self, proc, dset_path, H5T_NATIVE_DOUBLE, dims, dset_id, err)
      if (allocated(err)) return
      if (size(value) > 0) then
         call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
            // at('dataset', dset_path, self%part_path))
      end if
      call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
   end subroutine writer_write_r1

   !> Write a real rank-2 array; HDF5 dims are the Fortran shape `(n1, n2)`.
   subroutine writer_write_r2(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/modes/shape'
      real(dp), intent(in) :: value(:, :)                !! values [units]
      character(len=*), intent(in) :: units              !! units of `value`, e.g. 'm'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      character(len=*), parameter :: proc = 'write_r2'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(2)
      integer :: hdferr

      dims = shape(value, kind=hsize_t)
      call begin_dataset(self, proc, dset_path, H5T_NATIVE_DOUBLE, dims, dset_id, err)
      if (allocated(err)) return
      if (size(value) > 0) then
         call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
            // at('dataset', dset_path, self%part_path))
      end if
      call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
   end subroutine writer_write_r2

   !> Write a real rank-3 array; HDF5 dims are the Fortran shape `(n1, n2, n3)`.
   subroutine writer_write_r3(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/history/shape_xyz'
      real(dp), intent(in) :: value(:, :, :)                !! values [units]
      character(len=*), intent(in) :: units              !! units of `value`, e.g. 'm'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      character(len=*), parameter :: proc = 'write_r3'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(3)
      integer :: hdferr

      dims = shape(value, kind=hsize_t)
      call begin_dataset(self, proc, dset_path, H5T_NATIVE_DOUBLE, dims, dset_id, err)
      if (allocated(err)) return
      if (size(value) > 0) then
         call h5dwrite_f(dset_id, H5T_NATIVE_DOUBLE, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
            // at('dataset', dset_path, self%part_path))
      end if
      call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
   end subroutine writer_write_r3

   !> Write an integer rank-2 array; HDF5 dims are the Fortran shape `(n1, n2)`.
   subroutine writer_write_i2(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/history/segments'
      integer, intent(in) :: value(:, :)                !! values [units]
      character(len=*), intent(in) :: units              !! units of `value`, e.g. 'm'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      character(len=*), parameter :: proc = 'write_i2'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(2)
      integer :: hdferr

      dims = shape(value, kind=hsize_t)
      call begin_dataset(self, proc, dset_path, H5T_NATIVE_INTEGER, dims, dset_id, err)
      if (allocated(err)) return
      if (size(value) > 0) then
         call h5dwrite_f(dset_id, H5T_NATIVE_INTEGER, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
            // at('dataset', dset_path, self%part_path))
      end if
      call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
   end subroutine writer_write_i2

   !> Write an integer scalar.
   subroutine writer_write_i0(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/run/n_steps'
      integer, intent(in) :: value                       !! value [units]
      character(len=*), intent(in) :: units              !! units of `value`, usually '-'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      character(len=*), parameter :: proc = 'write_i0'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(0)
      integer :: hdferr

      call begin_dataset(self, proc, dset_path, H5T_NATIVE_INTEGER, dims, dset_id, err)
      if (allocated(err)) return
      call h5dwrite_f(dset_id, H5T_NATIVE_INTEGER, value, [1_hsize_t], hdferr)
      if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
         // at('dataset', dset_path, self%part_path))
      call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
   end subroutine writer_write_i0

   !> Write an integer rank-1 array (size 0 allowed).
   subroutine writer_write_i1(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/impacts/step'
      integer, intent(in) :: value(:)                    !! values [units]
      character(len=*), intent(in) :: units              !! units of `value`, usually '-'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      character(len=*), parameter :: proc = 'write_i1'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(1)
      integer :: hdferr

      dims = shape(value, kind=hsize_t)
      call begin_dataset(self, proc, dset_path, H5T_NATIVE_INTEGER, dims, dset_id, err)
      if (allocated(err)) return
      if (size(value) > 0) then
         call h5dwrite_f(dset_id, H5T_NATIVE_INTEGER, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
            // at('dataset', dset_path, self%part_path))
      end if
      call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
   end subroutine writer_write_i1

   !> Write a rank-1 string array (size 0 allowed) as fixed-length strings of `len(value)`.
   subroutine writer_write_s1(self, dset_path, value, units, err, long_name, dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: dset_path          !! new dataset, e.g. '/sweep/label'
      character(len=*), intent(in) :: value(:)           !! strings; trailing blanks are padding
      character(len=*), intent(in) :: units              !! units, usually '1'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), intent(in), optional :: long_name   !! what the values are, in words
      character(len=*), intent(in), optional :: dimensions  !! axis names, C order
      call write_strings(self, 'write_s1', dset_path, value, .false., units, err, long_name, &
                         dimensions)
   end subroutine writer_write_s1

   !> Attach the string attribute `name = text` to an existing group or dataset.
   subroutine writer_write_attr(self, obj_path, name, text, err)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: obj_path           !! group or dataset, '/' for the root
      character(len=*), intent(in) :: name               !! attribute name, e.g. 'description'
      character(len=*), intent(in) :: text               !! attribute value
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and object
      character(len=*), parameter :: proc = 'write_attr'
      character(len=:), allocatable :: p
      integer(hid_t) :: obj_id
      integer :: hdferr, status
      logical :: found

      p = clean_path(obj_path)
      if (.not. self%is_open) then
         call fatal_error(err, here(proc) // 'writer has no open file (call create first) to ' &
            // 'write attribute ' // q(name) // ' on ' // q(p))
         return
      end if
      if (len_trim(name) == 0) then
         call fatal_error(err, here(proc) // 'empty attribute name for ' &
            // at('object', p, self%part_path))
         return
      end if
      if (.not. path_exists(self%file_id, p)) then
         call fatal_error(err, here(proc) // 'no group or dataset ' // q(p) // ' in file ' &
            // q(self%part_path) // ' to carry attribute ' // q(name))
         return
      end if
      call h5oopen_f(self%file_id, p, obj_id, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot open ' // at('object', p, self%part_path))
         return
      end if
      call h5aexists_f(obj_id, trim(name), found, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot look up attribute ' // q(trim(name)) &
            // ' of ' // at('object', p, self%part_path))
      else if (found) then
         call fatal_error(err, here(proc) // 'attribute ' // q(trim(name)) &
            // ' already exists on ' // at('object', p, self%part_path))
      else
         call put_string_attr(obj_id, trim(name), text, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write attribute ' &
            // q(trim(name)) // ' on ' // at('object', p, self%part_path))
      end if
      call h5oclose_f(obj_id, status)
      if (status /= 0) call fatal_error(err, here(proc) // 'cannot close ' &
         // at('object', p, self%part_path))
   end subroutine writer_write_attr

   !> Create a group and the groups above it, where missing (an existing group is fine).
   subroutine writer_create_group(self, group_path, err)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: group_path         !! group, e.g. '/sweep/point_0001'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and group
      character(len=*), parameter :: proc = 'create_group'
      character(len=:), allocatable :: p

      p = clean_path(group_path)
      if (.not. self%is_open) then
         call fatal_error(err, here(proc) // 'writer has no open file (call create first) ' &
            // 'to create group ' // q(p))
         return
      end if
      call ensure_groups(self%file_id, proc, p, len(p), self%part_path, err)
   end subroutine writer_create_group

   !> Whether a dataset or group exists in the file being written (false when not open).
   logical function writer_exists(self, obj_path) result(found)
      class(h5_writer_t), intent(in) :: self             !! writer
      character(len=*), intent(in) :: obj_path           !! dataset or group, e.g. '/history'
      found = .false.
      if (self%is_open) found = path_exists(self%file_id, clean_path(obj_path))
   end function writer_exists

   !> Copy the group or dataset `obj_path` (with everything in it and its attributes) from the
   !> file `source` to the same path in the file being written; its parent must exist.
   subroutine writer_copy_from(self, source, obj_path, err)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: source             !! HDF5 file to copy from
      character(len=*), intent(in) :: obj_path           !! e.g. '/parameters'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names both files
      character(len=*), parameter :: proc = 'copy_from'
      character(len=:), allocatable :: p
      integer(hid_t) :: src_id, fapl
      integer :: hdferr, status

      p = clean_path(obj_path)
      if (.not. self%is_open) then
         call fatal_error(err, here(proc) // 'writer has no open file (call create first) to ' &
            // 'copy ' // q(p) // ' into')
         return
      end if
      call file_access_list(fapl, status)
      if (status /= 0) then
         call fatal_error(err, here(proc) // 'cannot set up file access for file ' // q(source))
         return
      end if
      call h5fopen_f(trim(source), H5F_ACC_RDONLY_F, src_id, hdferr, access_prp=fapl)
      call h5pclose_f(fapl, status)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot open file ' // q(source))
         return
      end if
      if (.not. path_exists(src_id, p)) then
         call fatal_error(err, here(proc) // 'no ' // at('object', p, source) // ' to copy')
      else
         call h5ocopy_f(src_id, p, self%file_id, p, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot copy ' &
            // at('object', p, source) // ' into file ' // q(self%part_path))
      end if
      call h5fclose_f(src_id, status)
      if (status /= 0 .and. .not. allocated(err)) call fatal_error(err, here(proc) &
         // 'cannot close file ' // q(source))
   end subroutine writer_copy_from

   !> Close the file, then rename `path.part` to `path` (atomically replacing an older `path`).
   !>
   !> A failed close (HDF5 writes its buffers there: a full disk shows here) deletes the
   !> incomplete file; a failed rename leaves `path.part` in place (call `abort` to delete it);
   !> `path` is untouched either way. In place, nothing is renamed.
   subroutine writer_close(self, err)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      type(error_t), allocatable, intent(out) :: err     !! set when closing or renaming fails
      character(len=*), parameter :: proc = 'close'
      character(len=*), parameter :: rename_prefix = 'gapbeam_files:rename_file: '
      type(error_t), allocatable :: rename_err
      integer :: hdferr

      if (.not. self%is_open) then
         call fatal_error(err, here(proc) // 'writer has no open file (never created, or ' &
            // 'already closed or aborted)')
         return
      end if
      call h5fclose_f(self%file_id, hdferr)
      self%file_id = no_id
      self%is_open = .false.
      if (hdferr /= 0) then
         call remove_file(self%part_path)
         call fatal_error(err, here(proc) // 'cannot close file ' // q(self%part_path) &
            // ' (a full disk?); it is incomplete and was deleted')
         return
      end if
      if (self%in_place) then
         deallocate(self%part_path, self%path)
         return
      end if
      call rename_file(self%part_path, self%path, rename_err)
      if (allocated(rename_err)) then   ! "cannot rename file 'a' to 'b': <reason> (errno N)"
         call fatal_error(err, here(proc) // without_prefix(rename_err%message, rename_prefix) &
            // '; the results are left in ' // q(self%part_path))
         return
      end if
      deallocate(self%part_path, self%path)
   end subroutine writer_close

   !> True when `err` is set; the writer is then aborted (its file closed and deleted). For
   !> a writer's error path: `if (write_failed(h5, err)) return`.
   logical function write_failed(h5, err)
      type(h5_writer_t), intent(inout) :: h5             !! writer
      type(error_t), allocatable, intent(in) :: err      !! status of the last write
      write_failed = allocated(err)
      if (write_failed) call h5%abort()
   end function write_failed

   !> Close the file, if open, and delete `path.part`; never fails (for error paths).
   subroutine writer_abort(self)
      class(h5_writer_t), intent(inout) :: self          !! writer, open or not
      integer :: hdferr

      if (self%is_open) then
         call h5fclose_f(self%file_id, hdferr)   ! failure ignored: the file is deleted below
      end if
      self%file_id = no_id
      self%is_open = .false.
      if (allocated(self%part_path)) then
         call remove_file(self%part_path)   ! a missing file is fine
         deallocate(self%part_path)
      end if
      if (allocated(self%path)) deallocate(self%path)
   end subroutine writer_abort

   ! ---------------------------------------------------------------------------------------
   ! Reader
   ! ---------------------------------------------------------------------------------------

   !> Open an existing HDF5 file read-only.
   subroutine reader_open(self, path, err)
      class(h5_reader_t), intent(inout) :: self          !! reader, not holding an open file
      character(len=*), intent(in) :: path               !! file name, e.g. 'results/a.h5'
      type(error_t), allocatable, intent(out) :: err     !! set when the file cannot be opened
      character(len=*), parameter :: proc = 'open'
      integer(hid_t) :: fapl
      integer :: hdferr, status
      logical :: found

      if (self%is_open) then
         call fatal_error(err, here(proc) // 'reader already has file ' // q(self%path) &
            // ' open; close it before opening ' // q(trim(path)))
         return
      end if
      if (len_trim(path) == 0) then
         call fatal_error(err, here(proc) // 'empty file path')
         return
      end if
      inquire(file=trim(path), exist=found)
      if (.not. found) then
         call fatal_error(err, here(proc) // 'file ' // q(trim(path)) // ' does not exist')
         return
      end if
      call library_open(status)
      if (status /= 0) then
         call fatal_error(err, here(proc) // 'cannot initialise the HDF5 library to open file ' &
            // q(trim(path)))
         return
      end if
      call file_access_list(fapl, status)
      if (status /= 0) then
         call fatal_error(err, here(proc) // 'cannot set up file access for file ' &
            // q(trim(path)))
         return
      end if
      call h5fopen_f(trim(path), H5F_ACC_RDONLY_F, self%file_id, hdferr, access_prp=fapl)
      call h5pclose_f(fapl, status)
      if (hdferr /= 0) then
         self%file_id = no_id
         call fatal_error(err, here(proc) // 'cannot open file ' // q(trim(path)) &
            // ' for reading (not an HDF5 file, or not readable)')
         return
      end if
      self%path = trim(path)
      self%is_open = .true.
      if (status /= 0) then
         call fatal_error(err, here(proc) // 'cannot release the file access list of file ' &
            // q(self%path))
      end if
   end subroutine reader_open

   !> Where the values of a dataset start in the file (bytes from its start) and whether they
   !> are little-endian, for readers that address them directly (the XDMF files' Format="Binary"
   !> Seek="..."). The writer stores every dataset contiguously, uncompressed; an error when
   !> this one is not (an edited or repacked file).
   subroutine reader_data_offset(self, dset_path, offset, little_endian, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/history/shape_w'
      integer(int64), intent(out) :: offset              !! first byte of the values
      logical, intent(out) :: little_endian              !! byte order of the values
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), parameter :: proc = 'data_offset'
      integer(hid_t) :: dset_id, type_id
      integer(haddr_t) :: addr
      integer :: hdferr, status, order

      offset = -1;  little_endian = .true.
      call open_dataset(self, proc, dset_path, dset_id, err)
      if (allocated(err)) return
      call h5dget_offset_f(dset_id, addr, hdferr)
      offset = int(addr, int64)
      if (hdferr /= 0 .or. offset < 0) then
         call fatal_error(err, here(proc) // at('dataset', clean_path(dset_path), self%path) &
            // ' is not stored contiguously (no byte offset)')
      else
         call h5dget_type_f(dset_id, type_id, hdferr)
         if (hdferr == 0) then
            call h5tget_order_f(type_id, order, hdferr)
            call h5tclose_f(type_id, status)
            call keep_first(hdferr, status)
         end if
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot get the byte order of ' &
            // at('dataset', clean_path(dset_path), self%path))
         little_endian = order == H5T_ORDER_LE_F
      end if
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine reader_data_offset

   !> Whether a dataset or group exists; false (not an error) when a group on the way is missing
   !> or no file is open.
   logical function reader_exists(self, dset_path) result(found)
      class(h5_reader_t), intent(in) :: self             !! reader
      character(len=*), intent(in) :: dset_path          !! dataset or group, e.g. '/history'
      found = .false.
      if (self%is_open) found = path_exists(self%file_id, clean_path(dset_path))
   end function reader_exists

   !> Read a real scalar dataset.
   subroutine reader_read_r0(self, dset_path, value, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/modes/damping'
      real(dp), intent(out) :: value                     !! stored value [units attribute]
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), parameter :: proc = 'read_r0'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(0)
      integer :: hdferr

      value = 0.0_dp
      call open_numeric(self, proc, dset_path, H5T_FLOAT_F, dims, dset_id, err)
      if (allocated(err)) return
      call h5dread_f(dset_id, H5T_NATIVE_DOUBLE, value, [1_hsize_t], hdferr)
      if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' &
         // at('dataset', dset_path, self%path))
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine reader_read_r0

   !> Read a real rank-1 dataset.
   subroutine reader_read_r1(self, dset_path, value, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/history/time'
      real(dp), allocatable, intent(out) :: value(:)     !! stored values [units attribute]
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), parameter :: proc = 'read_r1'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(1)
      integer :: hdferr

      call open_numeric(self, proc, dset_path, H5T_FLOAT_F, dims, dset_id, err)
      if (allocated(err)) then
         allocate(value(0))
         return
      end if
      allocate(value(dims(1)))
      if (size(value) > 0) then
         call h5dread_f(dset_id, H5T_NATIVE_DOUBLE, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' &
            // at('dataset', dset_path, self%path))
      end if
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine reader_read_r1

   !> Read a real rank-2 dataset into an array of the stored shape `(n1, n2)`.
   subroutine reader_read_r2(self, dset_path, value, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/modes/shape'
      real(dp), allocatable, intent(out) :: value(:, :)  !! stored values [units attribute]
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), parameter :: proc = 'read_r2'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(2)
      integer :: hdferr

      call open_numeric(self, proc, dset_path, H5T_FLOAT_F, dims, dset_id, err)
      if (allocated(err)) then
         allocate(value(0, 0))
         return
      end if
      allocate(value(dims(1), dims(2)))
      if (size(value) > 0) then
         call h5dread_f(dset_id, H5T_NATIVE_DOUBLE, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' &
            // at('dataset', dset_path, self%path))
      end if
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine reader_read_r2

   !> Read an integer scalar dataset.
   subroutine reader_read_i0(self, dset_path, value, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/run/n_steps'
      integer, intent(out) :: value                      !! stored value [units attribute]
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), parameter :: proc = 'read_i0'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(0)
      integer :: hdferr

      value = 0
      call open_numeric(self, proc, dset_path, H5T_INTEGER_F, dims, dset_id, err)
      if (allocated(err)) return
      call h5dread_f(dset_id, H5T_NATIVE_INTEGER, value, [1_hsize_t], hdferr)
      if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' &
         // at('dataset', dset_path, self%path))
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine reader_read_i0

   !> Read an integer rank-1 dataset.
   subroutine reader_read_i1(self, dset_path, value, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/impacts/step'
      integer, allocatable, intent(out) :: value(:)      !! stored values [units attribute]
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), parameter :: proc = 'read_i1'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(1)
      integer :: hdferr

      call open_numeric(self, proc, dset_path, H5T_INTEGER_F, dims, dset_id, err)
      if (allocated(err)) then
         allocate(value(0))
         return
      end if
      allocate(value(dims(1)))
      if (size(value) > 0) then
         call h5dread_f(dset_id, H5T_NATIVE_INTEGER, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' &
            // at('dataset', dset_path, self%path))
      end if
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine reader_read_i1

   !> Read an integer rank-2 dataset.
   subroutine reader_read_i2(self, dset_path, value, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/sweep/starts/label'
      integer, allocatable, intent(out) :: value(:, :)   !! stored values [units attribute]
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(len=*), parameter :: proc = 'read_i2'
      integer(hid_t) :: dset_id
      integer(hsize_t) :: dims(2)
      integer :: hdferr

      call open_numeric(self, proc, dset_path, H5T_INTEGER_F, dims, dset_id, err)
      if (allocated(err)) then
         allocate(value(0, 0))
         return
      end if
      allocate(value(dims(1), dims(2)))
      if (size(value) > 0) then
         call h5dread_f(dset_id, H5T_NATIVE_INTEGER, value, dims, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' &
            // at('dataset', dset_path, self%path))
      end if
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine reader_read_i2

   !> Read a rank-1 fixed-length string dataset; NUL padding comes back as blanks.
   subroutine reader_read_s1(self, dset_path, value, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/sweep/label'
      !> strings of the stored length, blank-padded
      character(len=:), allocatable, intent(out) :: value(:)
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(kind=c_char, len=1), allocatable :: buf(:)
      integer :: width, n, i, j

      call read_strings(self, 'read_s1', dset_path, 1, buf, width, n, err)
      if (allocated(err)) then
         allocate(character(len=0) :: value(0))
         return
      end if
      allocate(character(len=width) :: value(n))
      do i = 1, n
         do j = 1, width
            if (buf((i - 1) * width + j) == c_null_char) then
               value(i)(j:j) = ' '
            else
               value(i)(j:j) = buf((i - 1) * width + j)
            end if
         end do
      end do
   end subroutine reader_read_s1

   !> Read a scalar fixed-length string dataset (written by `write_text`); trailing NUL
   !> padding is removed.
   subroutine reader_read_text(self, dset_path, text, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/input/deck'
      character(len=:), allocatable, intent(out) :: text !! stored text
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      character(kind=c_char, len=1), allocatable :: buf(:)
      integer :: width, n

      call read_strings(self, 'read_text', dset_path, 0, buf, width, n, err)
      if (allocated(err)) then
         text = ''
         return
      end if
      text = chars_to_text(buf, trim_nul=.true.)
   end subroutine reader_read_text

   !> Read the `units` attribute of a dataset.
   subroutine reader_read_units(self, dset_path, units, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: dset_path          !! dataset, e.g. '/modes/frequency'
      character(len=:), allocatable, intent(out) :: units  !! stored units, e.g. 'Hz'
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and dataset
      call read_string_attr(self, 'read_units', dset_path, 'units', units, err)
   end subroutine reader_read_units

   !> Read a string attribute of a group or dataset.
   subroutine reader_read_attr(self, obj_path, name, text, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: obj_path           !! group or dataset, '/' for the root
      character(len=*), intent(in) :: name               !! attribute name, e.g. 'description'
      character(len=:), allocatable, intent(out) :: text !! stored attribute value
      type(error_t), allocatable, intent(out) :: err     !! set on failure; names file and object
      call read_string_attr(self, 'read_attr', obj_path, name, text, err)
   end subroutine reader_read_attr

   !> Close the file, if open; never fails.
   subroutine reader_close(self)
      class(h5_reader_t), intent(inout) :: self          !! reader, open or not
      integer :: hdferr
      if (self%is_open) then
         call h5fclose_f(self%file_id, hdferr)   ! read-only: nothing is lost if this fails
      end if
      self%file_id = no_id
      self%is_open = .false.
      if (allocated(self%path)) deallocate(self%path)
   end subroutine reader_close

   ! ---------------------------------------------------------------------------------------
   ! Writing helpers
   ! ---------------------------------------------------------------------------------------

   !> Check the writer and the path, create missing parent groups, and create a new dataset
   !> of `type_id` with shape `dims` (scalar when `size(dims) == 0`).
   subroutine begin_dataset(self, proc, dset_path, type_id, dims, dset_id, err)
      class(h5_writer_t), intent(in) :: self             !! writer
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: dset_path          !! dataset path as given
      integer(hid_t), intent(in) :: type_id              !! HDF5 file datatype
      integer(hsize_t), intent(in) :: dims(:)            !! shape; empty for a scalar
      integer(hid_t), intent(out) :: dset_id             !! open dataset, on success
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      character(len=:), allocatable :: p
      integer(hid_t) :: space_id
      integer :: hdferr, status

      dset_id = no_id
      p = clean_path(dset_path)
      if (.not. self%is_open) then
         call fatal_error(err, here(proc) // 'writer has no open file (call create first) ' &
            // 'to write dataset ' // q(p))
         return
      end if
      if (p == '/') then
         call fatal_error(err, here(proc) // 'dataset path ' // q(dset_path) &
            // ' names the root group, not a dataset, in file ' // q(self%part_path))
         return
      end if
      call ensure_groups(self%file_id, proc, p, index(p, '/', back=.true.) - 1, &
         self%part_path, err)
      if (allocated(err)) return
      if (path_exists(self%file_id, p)) then
         call fatal_error(err, here(proc) // at('dataset', p, self%part_path) &
            // ' already exists')
         return
      end if
      if (size(dims) == 0) then
         call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
      else
         call h5screate_simple_f(size(dims), dims, space_id, hdferr)
      end if
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot create the dataspace of ' &
            // at('dataset', p, self%part_path))
         return
      end if
      call h5dcreate_f(self%file_id, p, type_id, space_id, dset_id, hdferr)
      if (hdferr /= 0) then
         dset_id = no_id
         call fatal_error(err, here(proc) // 'cannot create ' // at('dataset', p, self%part_path))
      end if
      call h5sclose_f(space_id, status)
      if (status /= 0) call fatal_error(err, here(proc) // 'cannot close the dataspace of ' &
         // at('dataset', p, self%part_path))
   end subroutine begin_dataset

   !> Attach the `units` attribute, and `long_name` and `dimensions` when given (unless an
   !> error is already set), and close the dataset.
   subroutine end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
      class(h5_writer_t), intent(in) :: self             !! writer
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: dset_path          !! dataset path as given
      integer(hid_t), intent(inout) :: dset_id           !! open dataset; closed on return
      character(len=*), intent(in) :: units              !! value of the `units` attribute
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      character(len=*), intent(in), optional :: long_name   !! `long_name` attribute
      character(len=*), intent(in), optional :: dimensions  !! `dimensions` attribute
      integer :: hdferr

      if (.not. allocated(err)) then
         call put_string_attr(dset_id, 'units', units, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write attribute ''units'' &
            &of ' // at('dataset', clean_path(dset_path), self%part_path))
      end if
      if (.not. allocated(err) .and. present(long_name)) then
         call put_string_attr(dset_id, 'long_name', long_name, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write attribute &
            &''long_name'' of ' // at('dataset', clean_path(dset_path), self%part_path))
      end if
      if (.not. allocated(err) .and. present(dimensions)) then
         call put_string_attr(dset_id, 'dimensions', dimensions, hdferr)
         if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write attribute &
            &''dimensions'' of ' // at('dataset', clean_path(dset_path), self%part_path))
      end if
      call close_dataset(proc, dset_id, dset_path, self%part_path, err)
   end subroutine end_dataset

   !> Write strings as a fixed-length string dataset: a scalar holding `value(1)` whole
   !> (`scalar`), or a rank-1 array with trailing blanks turned into NUL padding.
   subroutine write_strings(self, proc, dset_path, value, scalar, units, err, long_name, &
                            dimensions)
      class(h5_writer_t), intent(inout) :: self          !! writer with an open file
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: dset_path          !! new dataset
      character(len=*), intent(in) :: value(:)           !! strings (one when `scalar`)
      logical, intent(in) :: scalar                      !! scalar text dataset
      character(len=*), intent(in) :: units              !! value of the `units` attribute
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      character(len=*), intent(in), optional :: long_name   !! `long_name` attribute
      character(len=*), intent(in), optional :: dimensions  !! `dimensions` attribute
      character(kind=c_char, len=1), allocatable, target :: buf(:)
      integer(hid_t) :: type_id, dset_id
      integer(hsize_t), allocatable :: dims(:)
      integer :: width, n, i, j, last, hdferr, status

      width = max(1, len(value))
      n = size(value)
      if (scalar) then
         allocate(dims(0))
      else
         allocate(dims(1))
         dims(1) = int(n, hsize_t)
      end if
      call string_type(width, type_id, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot make a string type of length ' &
            // str(width) // ' for ' // at('dataset', clean_path(dset_path), self%part_path))
         return
      end if
      call begin_dataset(self, proc, dset_path, type_id, dims, dset_id, err)
      if (.not. allocated(err)) then
         allocate(buf(width * n))
         buf = c_null_char
         do i = 1, n
            last = len(value)
            if (.not. scalar) last = len_trim(value(i))
            do j = 1, last
               buf((i - 1) * width + j) = value(i)(j:j)
            end do
         end do
         if (n > 0) then
            call h5dwrite_f(dset_id, type_id, c_loc(buf(1)), hdferr)
            if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot write ' &
               // at('dataset', clean_path(dset_path), self%part_path))
         end if
         call end_dataset(self, proc, dset_path, dset_id, units, err, long_name, dimensions)
      end if
      call h5tclose_f(type_id, status)
      if (status /= 0) call fatal_error(err, here(proc) // 'cannot close the string type of ' &
         // at('dataset', clean_path(dset_path), self%part_path))
   end subroutine write_strings

   !> Create and write a scalar variable-length UTF-8 string attribute on an open object
   !> (h5py reads it as str).
   subroutine put_string_attr(obj_id, name, text, hdferr)
      integer(hid_t), intent(in) :: obj_id               !! open group or dataset
      character(len=*), intent(in) :: name               !! attribute name
      character(len=*), intent(in) :: text               !! attribute value
      integer, intent(out) :: hdferr                     !! 0 on success, first failure otherwise
      character(kind=c_char, len=1), allocatable, target :: buf(:)
      type(c_ptr), target :: ptr(1)
      type(c_ptr) :: buf_ptr
      integer(hid_t) :: type_id, space_id, attr_id
      integer :: j, status

      allocate(buf(len(text) + 1))
      do j = 1, len(text)
         buf(j) = text(j:j)
      end do
      buf(len(text) + 1) = c_null_char
      ptr(1) = c_loc(buf(1))
      type_id = no_id
      space_id = no_id
      attr_id = no_id
      call h5tcopy_f(H5T_STRING, type_id, hdferr)
      if (hdferr /= 0) return
      call h5tset_cset_f(type_id, H5T_CSET_UTF8_F, hdferr)
      if (hdferr == 0) call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
      if (hdferr == 0) call h5acreate_f(obj_id, name, type_id, space_id, attr_id, hdferr)
      buf_ptr = c_loc(ptr(1))
      if (hdferr == 0) call h5awrite_f(attr_id, type_id, buf_ptr, hdferr)
      if (attr_id /= no_id) then
         call h5aclose_f(attr_id, status)
         call keep_first(hdferr, status)
      end if
      if (space_id /= no_id) then
         call h5sclose_f(space_id, status)
         call keep_first(hdferr, status)
      end if
      call h5tclose_f(type_id, status)
      call keep_first(hdferr, status)
   end subroutine put_string_attr

   !> Create the groups `p(1:k)` for every `k <= upto` ending a path component, where missing.
   subroutine ensure_groups(file_id, proc, p, upto, file_name, err)
      integer(hid_t), intent(in) :: file_id              !! open file
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: p                  !! clean absolute path
      integer, intent(in) :: upto                        !! last character of the deepest group
      character(len=*), intent(in) :: file_name          !! file name, for messages
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      integer(hid_t) :: group_id
      integer :: k, hdferr, status, obj_type
      logical :: found

      do k = 2, upto
         if (k < upto) then
            if (p(k + 1:k + 1) /= '/') cycle
         end if
         call h5lexists_f(file_id, p(1:k), found, hdferr)
         if (hdferr /= 0) then
            call fatal_error(err, here(proc) // 'cannot look up group ' // q(p(1:k)) &
               // ' on the way to ' // at('object', p, file_name))
            return
         end if
         if (found) then
            call object_type(file_id, p(1:k), obj_type, hdferr)
            if (hdferr /= 0 .or. obj_type /= H5I_GROUP_F) then
               call fatal_error(err, here(proc) // q(p(1:k)) // ' is not a group, so ' &
                  // at('object', p, file_name) // ' cannot be created')
               return
            end if
         else
            call h5gcreate_f(file_id, p(1:k), group_id, hdferr)
            if (hdferr /= 0) then
               call fatal_error(err, here(proc) // 'cannot create group ' // q(p(1:k)) &
                  // ' on the way to ' // at('object', p, file_name))
               return
            end if
            call h5gclose_f(group_id, status)
            if (status /= 0) then
               call fatal_error(err, here(proc) // 'cannot close group ' // q(p(1:k)) &
                  // ' on the way to ' // at('object', p, file_name))
               return
            end if
         end if
      end do
   end subroutine ensure_groups

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

   ! ---------------------------------------------------------------------------------------
   ! Reading helpers
   ! ---------------------------------------------------------------------------------------

   !> Open a dataset and check it: numeric class `type_class` and rank `size(dims)`.
   subroutine open_numeric(self, proc, dset_path, type_class, dims, dset_id, err)
      class(h5_reader_t), intent(in) :: self             !! reader
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: dset_path          !! dataset path as given
      integer, intent(in) :: type_class                  !! H5T_FLOAT_F or H5T_INTEGER_F
      integer(hsize_t), intent(out) :: dims(:)           !! stored shape (rank must match)
      integer(hid_t), intent(out) :: dset_id             !! open dataset, on success
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      integer(hid_t) :: type_id
      integer :: hdferr, status, stored_class

      call open_dataset(self, proc, dset_path, dset_id, err)
      if (allocated(err)) return
      call h5dget_type_f(dset_id, type_id, hdferr)
      if (hdferr == 0) then
         call h5tget_class_f(type_id, stored_class, hdferr)
         call h5tclose_f(type_id, status)
         call keep_first(hdferr, status)
      end if
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot get the datatype of ' &
            // at('dataset', clean_path(dset_path), self%path))
      else if (stored_class /= type_class) then
         call fatal_error(err, here(proc) // at('dataset', clean_path(dset_path), self%path) &
            // ' holds ' // class_name(stored_class) // ', not ' // class_name(type_class))
      else
         call check_shape(proc, dset_id, dset_path, self%path, dims, err)
      end if
      if (allocated(err)) call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine open_numeric

   !> Read a fixed-length string dataset of rank `rank` (0 or 1) as raw bytes.
   subroutine read_strings(self, proc, dset_path, rank, buf, width, n, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: dset_path          !! dataset path as given
      integer, intent(in) :: rank                        !! 0: scalar text, 1: string array
      !> bytes of all strings, `width` each
      character(kind=c_char, len=1), allocatable, target, intent(out) :: buf(:)
      integer, intent(out) :: width                      !! bytes per string
      integer, intent(out) :: n                          !! number of strings
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      integer(hid_t) :: dset_id, type_id
      integer(hsize_t) :: dims(rank)
      type(c_ptr) :: buf_ptr
      integer :: hdferr, status

      width = 0
      n = 0
      call open_dataset(self, proc, dset_path, dset_id, err)
      if (allocated(err)) return
      call h5dget_type_f(dset_id, type_id, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot get the datatype of ' &
            // at('dataset', clean_path(dset_path), self%path))
      else
         call check_string_type(proc, type_id, 'dataset', dset_path, self%path, width, err)
         if (.not. allocated(err)) then
            call check_shape(proc, dset_id, dset_path, self%path, dims, err)
         end if
         if (.not. allocated(err)) then
            n = int(product(dims))
            allocate(buf(width * n))
            if (n > 0) then
               buf_ptr = c_loc(buf(1))
               call h5dread_f(dset_id, type_id, buf_ptr, hdferr)
               if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' &
                  // at('dataset', clean_path(dset_path), self%path))
            end if
         end if
         call h5tclose_f(type_id, status)
         if (status /= 0) call fatal_error(err, here(proc) // 'cannot close the datatype of ' &
            // at('dataset', clean_path(dset_path), self%path))
      end if
      call close_dataset(proc, dset_id, dset_path, self%path, err)
   end subroutine read_strings

   !> Read a scalar fixed-length string attribute `name` of a group or dataset.
   subroutine read_string_attr(self, proc, obj_path, name, text, err)
      class(h5_reader_t), intent(in) :: self             !! reader with an open file
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: obj_path           !! group or dataset path as given
      character(len=*), intent(in) :: name               !! attribute name
      character(len=:), allocatable, intent(out) :: text !! attribute value
      type(error_t), allocatable, intent(out) :: err     !! set on failure
      character(kind=c_char, len=1), allocatable, target :: buf(:)
      character(len=:), allocatable :: p, what
      integer(hid_t) :: obj_id, attr_id, type_id, space_id
      type(c_ptr) :: buf_ptr
      integer :: hdferr, status, width, rank
      logical :: found, variable

      text = ''
      p = clean_path(obj_path)
      if (.not. self%is_open) then
         call fatal_error(err, here(proc) // 'reader has no open file (call open first) to ' &
            // 'read attribute ' // q(name) // ' of ' // q(p))
         return
      end if
      what = 'attribute ' // q(trim(name)) // ' of ' // at('object', p, self%path)
      if (.not. path_exists(self%file_id, p)) then
         call fatal_error(err, here(proc) // 'no ' // at('object', p, self%path) &
            // ' to read attribute ' // q(trim(name)) // ' from')
         return
      end if
      call h5oopen_f(self%file_id, p, obj_id, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot open ' // at('object', p, self%path))
         return
      end if
      call h5aexists_f(obj_id, trim(name), found, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot look up ' // what)
      else if (.not. found) then
         call fatal_error(err, here(proc) // 'no ' // what)
      else
         call h5aopen_f(obj_id, trim(name), attr_id, hdferr)
         if (hdferr /= 0) then
            call fatal_error(err, here(proc) // 'cannot open ' // what)
         else
            call h5aget_type_f(attr_id, type_id, hdferr)
            if (hdferr /= 0) then
               call fatal_error(err, here(proc) // 'cannot get the datatype of ' // what)
            else
               call check_string_type(proc, type_id, 'attribute ' // q(trim(name)) // ' of', &
                  p, self%path, width, err, variable)
               if (.not. allocated(err)) then
                  call h5aget_space_f(attr_id, space_id, hdferr)
                  if (hdferr == 0) then
                     call h5sget_simple_extent_ndims_f(space_id, rank, hdferr)
                     call h5sclose_f(space_id, status)
                     call keep_first(hdferr, status)
                  end if
                  if (hdferr /= 0) then
                     call fatal_error(err, here(proc) // 'cannot get the dataspace of ' // what)
                  else if (rank /= 0) then
                     call fatal_error(err, here(proc) // what // ' is not a scalar (rank ' &
                        // str(rank) // ')')
                  else if (variable) then
                     call read_variable_string(attr_id, type_id, text, hdferr)
                     if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot read ' // what)
                  else
                     allocate(buf(width))
                     buf_ptr = c_loc(buf(1))
                     call h5aread_f(attr_id, type_id, buf_ptr, hdferr)
                     if (hdferr /= 0) then
                        call fatal_error(err, here(proc) // 'cannot read ' // what)
                     else
                        text = chars_to_text(buf, trim_nul=.true.)
                     end if
                  end if
               end if
               call h5tclose_f(type_id, status)
               if (status /= 0) call fatal_error(err, here(proc) &
                  // 'cannot close the datatype of ' // what)
            end if
            call h5aclose_f(attr_id, status)
            if (status /= 0) call fatal_error(err, here(proc) // 'cannot close ' // what)
         end if
      end if
      call h5oclose_f(obj_id, status)
      if (status /= 0) call fatal_error(err, here(proc) // 'cannot close ' &
         // at('object', p, self%path))
   end subroutine read_string_attr

   !> Read a scalar variable-length string attribute and free the library's copy.
   subroutine read_variable_string(attr_id, type_id, text, hdferr)
      integer(hid_t), intent(in) :: attr_id              !! open attribute
      integer(hid_t), intent(in) :: type_id              !! its (variable-length string) type
      character(len=:), allocatable, intent(out) :: text !! the value
      integer, intent(out) :: hdferr                     !! 0 on success
      type(c_ptr), target :: ptr(1)
      type(c_ptr) :: buf_ptr
      character(kind=c_char, len=1), pointer :: chars(:)
      integer :: n
      text = ''
      ptr(1) = c_null_ptr
      buf_ptr = c_loc(ptr(1))
      call h5aread_f(attr_id, type_id, buf_ptr, hdferr)
      if (hdferr /= 0 .or. .not. c_associated(ptr(1))) return
      n = int(c_strlen(ptr(1)))
      call c_f_pointer(ptr(1), chars, [max(n, 1)])
      text = chars_to_text(chars(1:n), trim_nul=.true.)
      if (c_free_memory(ptr(1)) < 0) hdferr = -1
   end subroutine read_variable_string

   !> Open an existing dataset of the reader's file.
   subroutine open_dataset(self, proc, dset_path, dset_id, err)
      class(h5_reader_t), intent(in) :: self             !! reader
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      character(len=*), intent(in) :: dset_path          !! dataset path as given
      integer(hid_t), intent(out) :: dset_id             !! open dataset, on success
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      character(len=:), allocatable :: p
      integer :: hdferr, obj_type

      dset_id = no_id
      p = clean_path(dset_path)
      if (.not. self%is_open) then
         call fatal_error(err, here(proc) // 'reader has no open file (call open first) to ' &
            // 'read dataset ' // q(p))
         return
      end if
      if (.not. path_exists(self%file_id, p)) then
         call fatal_error(err, here(proc) // 'no ' // at('dataset', p, self%path))
         return
      end if
      call object_type(self%file_id, p, obj_type, hdferr)
      if (hdferr == 0 .and. obj_type /= H5I_DATASET_F) then
         call fatal_error(err, here(proc) // q(p) // ' is a group, not a dataset, in file ' &
            // q(self%path))
         return
      end if
      call h5dopen_f(self%file_id, p, dset_id, hdferr)
      if (hdferr /= 0) then
         dset_id = no_id
         call fatal_error(err, here(proc) // 'cannot open ' // at('dataset', p, self%path))
      end if
   end subroutine open_dataset

   !> Check that a dataset has rank `size(dims)` and return its shape in `dims`.
   subroutine check_shape(proc, dset_id, dset_path, file_name, dims, err)
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      integer(hid_t), intent(in) :: dset_id              !! open dataset
      character(len=*), intent(in) :: dset_path          !! dataset path, for messages
      character(len=*), intent(in) :: file_name          !! file name, for messages
      integer(hsize_t), intent(out) :: dims(:)           !! stored shape
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      integer(hid_t) :: space_id
      integer(hsize_t) :: stored(7), max_dims(7)
      integer :: hdferr, status, rank

      dims = 0
      call h5dget_space_f(dset_id, space_id, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot get the dataspace of ' &
            // at('dataset', clean_path(dset_path), file_name))
         return
      end if
      call h5sget_simple_extent_ndims_f(space_id, rank, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot get the rank of ' &
            // at('dataset', clean_path(dset_path), file_name))
      else if (rank /= size(dims)) then
         call fatal_error(err, here(proc) // at('dataset', clean_path(dset_path), file_name) &
            // ' has rank ' // str(rank) // ', not ' // str(size(dims)))
      else if (rank > 0) then
         call h5sget_simple_extent_dims_f(space_id, stored(1:rank), max_dims(1:rank), hdferr)
         if (hdferr < 0) then   ! returns the rank on success
            call fatal_error(err, here(proc) // 'cannot get the shape of ' &
               // at('dataset', clean_path(dset_path), file_name))
         else
            dims = stored(1:rank)
         end if
      end if
      call h5sclose_f(space_id, status)
      if (status /= 0) call fatal_error(err, here(proc) // 'cannot close the dataspace of ' &
         // at('dataset', clean_path(dset_path), file_name))
   end subroutine check_shape

   !> Check that `type_id` is a fixed-length string type and return its length in bytes; with
   !> `variable` present, a variable-length string type is accepted too (and said so).
   subroutine check_string_type(proc, type_id, kind_name, obj_path, file_name, width, err, &
                                variable)
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      integer(hid_t), intent(in) :: type_id              !! datatype of a dataset or attribute
      character(len=*), intent(in) :: kind_name          !! 'dataset', or "attribute 'x' of"
      character(len=*), intent(in) :: obj_path           !! object path, for messages
      character(len=*), intent(in) :: file_name          !! file name, for messages
      integer, intent(out) :: width                      !! bytes per string
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      logical, intent(out), optional :: variable         !! a variable-length string type
      integer(size_t) :: type_size
      integer :: hdferr, stored_class
      logical :: is_variable

      width = 0
      if (present(variable)) variable = .false.
      call h5tget_class_f(type_id, stored_class, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot get the type class of ' &
            // at(kind_name, clean_path(obj_path), file_name))
         return
      end if
      if (stored_class /= H5T_STRING_F) then
         call fatal_error(err, here(proc) // at(kind_name, clean_path(obj_path), file_name) &
            // ' holds ' // class_name(stored_class) // ', not strings')
         return
      end if
      call h5tis_variable_str_f(type_id, is_variable, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot inspect the string type of ' &
            // at(kind_name, clean_path(obj_path), file_name))
         return
      end if
      if (is_variable .and. present(variable)) then
         variable = .true.
         return
      end if
      if (is_variable) then
         call fatal_error(err, here(proc) // at(kind_name, clean_path(obj_path), file_name) &
            // ' holds variable-length strings; only fixed-length strings are supported')
         return
      end if
      call h5tget_size_f(type_id, type_size, hdferr)
      if (hdferr /= 0) then
         call fatal_error(err, here(proc) // 'cannot get the string length of ' &
            // at(kind_name, clean_path(obj_path), file_name))
         return
      end if
      width = int(type_size)
   end subroutine check_string_type

   !> Close a dataset, recording a failure in `err` (first error kept).
   subroutine close_dataset(proc, dset_id, dset_path, file_name, err)
      character(len=*), intent(in) :: proc               !! calling procedure, for messages
      integer(hid_t), intent(inout) :: dset_id           !! open dataset; `no_id` on return
      character(len=*), intent(in) :: dset_path          !! dataset path, for messages
      character(len=*), intent(in) :: file_name          !! file name, for messages
      type(error_t), allocatable, intent(inout) :: err   !! set on failure
      integer :: hdferr
      if (dset_id == no_id) return
      call h5dclose_f(dset_id, hdferr)
      dset_id = no_id
      if (hdferr /= 0) call fatal_error(err, here(proc) // 'cannot close ' &
         // at('dataset', clean_path(dset_path), file_name))
   end subroutine close_dataset

   ! ---------------------------------------------------------------------------------------
   ! Library, paths, text
   ! ---------------------------------------------------------------------------------------

   !> Initialise the HDF5 library and its Fortran type identifiers unless already done, and
   !> switch off HDF5's own printing of errors (they come back as `error_t`).
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
         ! no clean-up at exit: after a failed close (a full disk) HDF5's exit handler tries the
         ! file again and crashes (SIGSEGV after the error message was written). Every file
         ! is closed (or aborted) by its writer or reader, so there is nothing left to clean.
         call h5dont_atexit_f(status)        ! fails harmlessly once the library is running
         call h5open_f(hdferr)
      end if
      if (hdferr /= 0) return
      call h5eset_auto_f(0, hdferr)
   end subroutine library_open

   !> File access property list closing every object of a file with the file.
   subroutine file_access_list(fapl, hdferr)
      integer(hid_t), intent(out) :: fapl               !! new list (close with h5pclose_f)
      integer, intent(out) :: hdferr                     !! 0 on success
      integer :: status
      call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, hdferr)
      if (hdferr /= 0) return
      call h5pset_fclose_degree_f(fapl, H5F_CLOSE_STRONG_F, hdferr)
      if (hdferr /= 0) call h5pclose_f(fapl, status)
   end subroutine file_access_list

   !> Whether every link of the clean absolute path `p` exists ('/' always does).
   logical function path_exists(file_id, p) result(found)
      integer(hid_t), intent(in) :: file_id              !! open file
      character(len=*), intent(in) :: p                  !! clean absolute path
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

   !> HDF5 identifier type (H5I_GROUP_F, H5I_DATASET_F, ...) of the object at `p`.
   subroutine object_type(file_id, p, obj_type, hdferr)
      integer(hid_t), intent(in) :: file_id              !! open file
      character(len=*), intent(in) :: p                  !! existing object
      integer, intent(out) :: obj_type                   !! identifier type
      integer, intent(out) :: hdferr                     !! 0 on success
      integer(hid_t) :: obj_id
      integer :: status
      obj_type = -1
      call h5oopen_f(file_id, p, obj_id, hdferr)
      if (hdferr /= 0) return
      call h5iget_type_f(obj_id, obj_type, hdferr)
      call h5oclose_f(obj_id, status)
      call keep_first(hdferr, status)
   end subroutine object_type

   !> Absolute path with single separators and no trailing '/': 'a//b/' -> '/a/b', '' -> '/'.
   pure function clean_path(path) result(p)
      character(len=*), intent(in) :: path               !! path as given
      character(len=:), allocatable :: p
      integer :: i
      p = '/'
      do i = 1, len_trim(path)
         if (path(i:i) == '/' .and. p(len(p):len(p)) == '/') cycle
         p = p // path(i:i)
      end do
      if (len(p) > 1 .and. p(len(p):len(p)) == '/') p = p(1:len(p) - 1)
   end function clean_path

   !> Text of the bytes in `buf`, without trailing NUL padding when `trim_nul`.
   pure function chars_to_text(buf, trim_nul) result(text)
      character(kind=c_char, len=1), intent(in) :: buf(:)  !! bytes
      logical, intent(in) :: trim_nul                      !! drop trailing NULs
      character(len=:), allocatable :: text
      integer :: n, j
      n = size(buf)
      if (trim_nul) then
         do while (n > 0)
            if (buf(n) /= c_null_char) exit
            n = n - 1
         end do
      end if
      allocate(character(len=n) :: text)
      do j = 1, n
         text(j:j) = buf(j)
      end do
   end function chars_to_text

   !> Keep the first non-zero status: `status` becomes `new` only when it is still 0.
   pure subroutine keep_first(status, new)
      integer, intent(inout) :: status                   !! accumulated status
      integer, intent(in) :: new                         !! status of the latest call
      if (status == 0) status = new
   end subroutine keep_first

   !> Message prefix 'gapbeam_hdf5_output:<proc>: '.
   pure function here(proc) result(s)
      character(len=*), intent(in) :: proc               !! procedure name
      character(len=:), allocatable :: s
      s = module_name // ':' // proc // ': '
   end function here

   !> "<kind_name> '<obj>' in file '<file_name>'".
   pure function at(kind_name, obj, file_name) result(s)
      character(len=*), intent(in) :: kind_name          !! 'dataset', 'object', ...
      character(len=*), intent(in) :: obj                !! object path
      character(len=*), intent(in) :: file_name          !! file name
      character(len=:), allocatable :: s
      s = kind_name // ' ' // q(obj) // ' in file ' // q(file_name)
   end function at

   !> Text in single quotes.
   pure function q(s) result(quoted)
      character(len=*), intent(in) :: s                  !! text
      character(len=:), allocatable :: quoted
      quoted = "'" // s // "'"
   end function q

   !> Name of an HDF5 type class, for messages.
   pure function class_name(type_class) result(s)
      integer, intent(in) :: type_class                  !! H5T_*_F class
      character(len=:), allocatable :: s
      if (type_class == H5T_FLOAT_F) then
         s = 'floating-point numbers'
      else if (type_class == H5T_INTEGER_F) then
         s = 'integers'
      else if (type_class == H5T_STRING_F) then
         s = 'strings'
      else
         s = 'data of HDF5 type class ' // str(type_class)
      end if
   end function class_name

   !> `message` without its leading `prefix`; `message` itself when it does not start with it.
   pure function without_prefix(message, prefix) result(s)
      character(len=*), intent(in) :: message            !! text
      character(len=*), intent(in) :: prefix             !! leading part to drop
      character(len=:), allocatable :: s
      s = message
      if (len(message) >= len(prefix)) then
         if (message(1:len(prefix)) == prefix) s = message(len(prefix) + 1:)
      end if
   end function without_prefix

end module gapbeam_hdf5_output
