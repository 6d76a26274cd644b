!> Reading HDF5 files written by gapbeam (gapbeam_hdf5_output writes them).
!>
!> A failure is a state of the reader, as of the writer: the first failure of the reads
!> given no `err` is kept, later such reads do nothing, and `failed()` and `close(err)` report
!> it; a read given its own `err` reports there and leaves the state alone. Arrays come back
!> allocated to the stored (Fortran) shape; fixed-length strings without their NUL padding.
module gapbeam_hdf5_input
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: iso_c_binding, only: c_char, c_ptr, c_null_char, c_loc, c_null_ptr, &
      c_associated, c_f_pointer, c_size_t, c_int
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str, q => quoted
   use gapbeam_hdf5_output, only: file_open, path_exists, at
   use hdf5, only: hid_t, hsize_t, size_t, h5fclose_f, h5oopen_f, h5oclose_f, h5sclose_f, &
      h5sget_simple_extent_ndims_f, h5sget_simple_extent_dims_f, h5dopen_f, h5dclose_f, h5dread_f, h5dget_type_f, &
      h5dget_space_f, h5tclose_f, h5tget_size_f, h5tget_class_f, h5tis_variable_str_f, &
      H5T_STRING_F, H5T_FLOAT_F, H5T_INTEGER_F, H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, &
      h5aopen_f, h5aclose_f, h5aread_f, h5aexists_f, h5aget_type_f, h5aget_space_f, &
      haddr_t, h5dget_offset_f, h5tget_order_f, H5T_ORDER_LE_F
   implicit none
   private
   public :: h5_reader_t

   character(len=*), parameter :: module_name = 'gapbeam_hdf5_input'
   integer(hid_t), parameter :: no_id = -1_hid_t   ! an identifier not (or no longer) open

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


   !> Read-only access to an HDF5 file; a failure is kept like a writer's, unless the read
   !> is given its own `err`.
   type :: h5_reader_t
      private
      integer(hid_t) :: file_id = no_id                !! HDF5 identifier of the open file
      character(len=:), allocatable :: path            !! name of the open file
      logical :: is_open = .false.                     !! whether `file_id` is an open file
      type(error_t), allocatable :: err                !! the first failure
   contains
      procedure :: open => reader_open                 !! open a file read-only
      procedure :: exists => reader_exists             !! whether a dataset or group exists
      procedure, private :: read_r0, read_r1, read_r2, read_i0, read_i1, read_i2, read_s1
      !> A real scalar, rank 1 or 2, an integer scalar, rank 1 or 2, or a string array
      !> (allocated).
      generic :: read => read_r0, read_r1, read_r2, read_i0, read_i1, read_i2, read_s1
      procedure :: read_text => reader_read_text       !! scalar string dataset
      procedure :: read_units => reader_read_units     !! the `units` attribute of a dataset
      procedure :: read_attr => reader_read_attr       !! a string attribute of an object
      procedure :: data_offset => reader_data_offset   !! byte offset and order of stored values
      procedure :: failed => reader_failed             !! whether a read failed
      procedure :: close => reader_close               !! close; the first failure, if asked
   end type h5_reader_t

contains

   ! ---------------------------------------------------------------------------------------
   ! Reader
   ! ---------------------------------------------------------------------------------------

   !> Open an existing HDF5 file read-only.
   subroutine reader_open(self, path, err)
      class(h5_reader_t), intent(inout) :: self          !! reader, not holding an open file
      character(len=*), intent(in) :: path               !! file name
      type(error_t), allocatable, intent(out), optional :: err   !! this call's failure
      type(error_t), allocatable :: e
      integer :: hdferr
      logical :: found
      inquire(file=trim(path), exist=found)
      if (self%is_open) then
         call fatal_error(e, module_name // ':open: the reader has file ' // q(self%path) &
            // ' open already')
      else if (len_trim(path) == 0 .or. .not. found) then
         call fatal_error(e, module_name // ':open: file ' // q(trim(path)) // ' does not exist')
      else
         call file_open(trim(path), .false., self%file_id, hdferr)
         if (hdferr /= 0) call fatal_error(e, module_name // ':open: cannot open file ' &
            // q(trim(path)) // ' for reading (not an HDF5 file, or not readable)')
         self%is_open = hdferr == 0
         self%path = trim(path)
      end if
      call settle(self, e, err)
   end subroutine reader_open

   !> Where the values of a dataset start in the file (bytes from its start) and whether they
   !> are little-endian, for readers that address them directly (the XDMF files' Format="Binary"
   !> Seek="..."). The writer stores every dataset contiguously, uncompressed; a failure when
   !> this one is not (an edited or repacked file).
   subroutine reader_data_offset(self, path, offset, little_endian, err)
      class(h5_reader_t), intent(inout) :: self          !! reader with an open file
      character(len=*), intent(in) :: path               !! dataset, e.g. '/history/shape_w'
      integer(int64), intent(out) :: offset              !! first byte of the values
      logical, intent(out) :: little_endian              !! byte order of the values
      type(error_t), allocatable, intent(out), optional :: err   !! this call's failure
      type(error_t), allocatable :: e
      integer(hid_t) :: dset_id, type_id
      integer(haddr_t) :: addr
      integer :: hdferr, status, order
      offset = -1;  little_endian = .true.
      if (skipped(self, err)) return
      if (.not. self%is_open) then
         call fatal_error(e, module_name // ':data_offset: no file is open')
         call settle(self, e, err)
         return
      end if
      call h5dopen_f(self%file_id, path, dset_id, hdferr)
      if (hdferr /= 0) then
         call fatal_error(e, module_name // ':data_offset: cannot open ' // at(path, self%path))
      else
         call h5dget_offset_f(dset_id, addr, hdferr)
         offset = int(addr, int64)
         if (hdferr /= 0 .or. offset < 0) then
            call fatal_error(e, module_name // ':data_offset: ' // at(path, self%path) &
               // ' is not stored contiguously (no byte offset)')
         else
            call h5dget_type_f(dset_id, type_id, hdferr)
            if (hdferr == 0) then
               call h5tget_order_f(type_id, order, hdferr)
               call h5tclose_f(type_id, status)
            end if
            if (hdferr /= 0) call fatal_error(e, module_name // ':data_offset: cannot get the ' &
               // 'byte order of ' // at(path, self%path))
            little_endian = order == H5T_ORDER_LE_F
         end if
         call h5dclose_f(dset_id, status)
      end if
      call settle(self, e, err)
   end subroutine reader_data_offset

   !> Whether a dataset or group exists (false when a group on the way is missing).
   logical function reader_exists(self, obj_path) result(found)
      class(h5_reader_t), intent(in) :: self             !! reader
      character(len=*), intent(in) :: obj_path           !! dataset or group
      found = .false.
      if (self%is_open) found = path_exists(self%file_id, obj_path)
   end function reader_exists

   !> Real scalar.
   subroutine read_r0(self, path, value, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      real(dp), intent(out), target :: value             !! stored value
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      integer(hsize_t) :: dims(0)
      value = 0.0_dp
      call read_numeric(self, path, H5T_FLOAT_F, dims, err, c_loc(value))
   end subroutine read_r0

   !> Real rank-1 array.
   subroutine read_r1(self, path, value, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      real(dp), allocatable, target, intent(out) :: value(:)   !! stored values
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      integer(hsize_t) :: dims(1)
      call read_numeric(self, path, H5T_FLOAT_F, dims, err)
      allocate(value(dims(1)))
      if (size(value) > 0) call read_numeric(self, path, H5T_FLOAT_F, dims, err, c_loc(value))
   end subroutine read_r1

   !> Real rank-2 array, of the stored (Fortran) shape.
   subroutine read_r2(self, path, value, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      real(dp), allocatable, target, intent(out) :: value(:, :)   !! stored values
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      integer(hsize_t) :: dims(2)
      call read_numeric(self, path, H5T_FLOAT_F, dims, err)
      allocate(value(dims(1), dims(2)))
      if (size(value) > 0) call read_numeric(self, path, H5T_FLOAT_F, dims, err, c_loc(value))
   end subroutine read_r2

   !> Integer scalar.
   subroutine read_i0(self, path, value, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      integer, intent(out), target :: value              !! stored value
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      integer(hsize_t) :: dims(0)
      value = 0
      call read_numeric(self, path, H5T_INTEGER_F, dims, err, c_loc(value))
   end subroutine read_i0

   !> Integer rank-1 array.
   subroutine read_i1(self, path, value, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      integer, allocatable, target, intent(out) :: value(:)   !! stored values
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      integer(hsize_t) :: dims(1)
      call read_numeric(self, path, H5T_INTEGER_F, dims, err)
      allocate(value(dims(1)))
      if (size(value) > 0) call read_numeric(self, path, H5T_INTEGER_F, dims, err, c_loc(value))
   end subroutine read_i1

   !> Integer rank-2 array, of the stored (Fortran) shape.
   subroutine read_i2(self, path, value, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      integer, allocatable, target, intent(out) :: value(:, :)   !! stored values
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      integer(hsize_t) :: dims(2)
      call read_numeric(self, path, H5T_INTEGER_F, dims, err)
      allocate(value(dims(1), dims(2)))
      if (size(value) > 0) call read_numeric(self, path, H5T_INTEGER_F, dims, err, c_loc(value))
   end subroutine read_i2

   !> Rank-1 string array; NUL padding comes back as blanks.
   subroutine read_s1(self, path, value, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      character(len=:), allocatable, intent(out) :: value(:)   !! strings, blank padded
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      character(kind=c_char, len=1), allocatable :: buf(:)
      integer :: width, n, i, j
      call read_strings(self, path, 1, buf, width, n, err)
      allocate(character(len=width) :: value(n))
      do i = 1, n
         do j = 1, width
            value(i)(j:j) = buf((i - 1) * width + j)
            if (value(i)(j:j) == c_null_char) value(i)(j:j) = ' '
         end do
      end do
   end subroutine read_s1

   !> A scalar string dataset (written by `put(path, text)`), without its NUL padding.
   subroutine reader_read_text(self, path, text, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      character(len=:), allocatable, intent(out) :: text !! stored text
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      character(kind=c_char, len=1), allocatable :: buf(:)
      integer :: width, n
      call read_strings(self, path, 0, buf, width, n, err)
      text = chars_to_text(buf)
   end subroutine reader_read_text

   !> The `units` attribute of a dataset.
   subroutine reader_read_units(self, path, units, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: path               !! dataset
      character(len=:), allocatable, intent(out) :: units  !! stored units
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      call reader_read_attr(self, path, 'units', units, err)
   end subroutine reader_read_units

   !> A scalar string attribute (fixed or variable length) of a group or dataset.
   subroutine reader_read_attr(self, obj_path, name, text, err)
      class(h5_reader_t), intent(inout) :: self          !! reader
      character(len=*), intent(in) :: obj_path           !! group or dataset ('/': root)
      character(len=*), intent(in) :: name               !! attribute name
      character(len=:), allocatable, intent(out) :: text !! attribute value
      type(error_t), allocatable, intent(out), optional :: err   !! this read's failure
      character(kind=c_char, len=1), allocatable, target :: buf(:)
      type(error_t), allocatable :: e
      integer(hid_t) :: obj_id, attr_id, type_id, space_id
      character(len=:), allocatable :: what
      integer :: hdferr, status, width, rank
      logical :: found, variable
      type(c_ptr) :: address
      text = ''
      if (skipped(self, err)) return
      what = 'attribute ' // q(name) // ' of ' // q(obj_path) // ' in file ' // q(self%path)
      found = .false.
      if (self%is_open) found = path_exists(self%file_id, obj_path)
      hdferr = -1
      if (found) call h5oopen_f(self%file_id, obj_path, obj_id, hdferr)
      if (hdferr == 0) then
         call h5aexists_f(obj_id, name, found, hdferr)
         if (found .and. hdferr == 0) then
            call h5aopen_f(obj_id, name, attr_id, hdferr)
            if (hdferr == 0) call h5aget_type_f(attr_id, type_id, hdferr)
            if (hdferr == 0) then
               call check_string_type(type_id, what, width, e, variable)
               call h5aget_space_f(attr_id, space_id, status)
               call h5sget_simple_extent_ndims_f(space_id, rank, status)
               call h5sclose_f(space_id, status)
               if (.not. allocated(e) .and. rank /= 0) call fatal_error(e, module_name &
                  // ': ' // what // ' is not a scalar')
               if (.not. allocated(e) .and. variable) then
                  call read_variable_string(attr_id, type_id, text, hdferr)
               else if (.not. allocated(e)) then
                  allocate(buf(width))
                  address = c_loc(buf)
                  call h5aread_f(attr_id, type_id, address, hdferr)
                  if (hdferr == 0) text = chars_to_text(buf)
               end if
               call h5tclose_f(type_id, status)
               call h5aclose_f(attr_id, status)
            end if
         end if
         call h5oclose_f(obj_id, status)
      end if
      if (.not. allocated(e) .and. .not. found) call fatal_error(e, module_name // ': no ' // what)
      if (.not. allocated(e) .and. hdferr /= 0) call fatal_error(e, module_name &
         // ': cannot read ' // what)
      call settle(self, e, err)
   end subroutine reader_read_attr

   !> Whether a read failed (since open, for the reads given no `err`).
   pure logical function reader_failed(self)
      class(h5_reader_t), intent(in) :: self             !! reader
      reader_failed = allocated(self%err)
   end function reader_failed

   !> Close the file, if open; `err` gets the first failure of the reads given no `err`.
   subroutine reader_close(self, err)
      class(h5_reader_t), intent(inout) :: self          !! reader, open or not
      type(error_t), allocatable, intent(out), optional :: err   !! the first failure
      integer :: hdferr
      if (self%is_open) call h5fclose_f(self%file_id, hdferr)   ! read-only: nothing lost
      self%file_id = no_id
      self%is_open = .false.
      if (allocated(self%path)) deallocate(self%path)
      if (present(err) .and. allocated(self%err)) call move_alloc(self%err, err)
      if (allocated(self%err)) deallocate(self%err)
   end subroutine reader_close

   !> The failure `e` of a read: into `err` when given, else kept (the first one).
   subroutine settle(self, e, err)
      class(h5_reader_t), intent(inout) :: self
      type(error_t), allocatable, intent(inout) :: e
      type(error_t), allocatable, intent(out), optional :: err
      if (present(err)) then
         if (allocated(e)) call move_alloc(e, err)
      else if (allocated(e) .and. .not. allocated(self%err)) then
         call move_alloc(e, self%err)
      end if
   end subroutine settle

   !> True (the read is skipped) when an earlier read without `err` failed and this one has
   !> no `err` either.
   logical function skipped(self, err)
      class(h5_reader_t), intent(in) :: self
      type(error_t), allocatable, intent(in), optional :: err
      skipped = allocated(self%err) .and. .not. present(err)
   end function skipped

   !> Open dataset `path`, check its class and rank, return its shape in `dims`, and read it
   !> into `buf` when given.
   subroutine read_numeric(self, path, type_class, dims, err, buf)
      class(h5_reader_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      integer, intent(in) :: type_class
      integer(hsize_t), intent(out) :: dims(:)
      type(error_t), allocatable, intent(out), optional :: err
      type(c_ptr), intent(in), optional :: buf
      type(error_t), allocatable :: e
      integer(hid_t) :: dset_id, type_id, mem_type
      integer :: hdferr, status, stored_class
      type(c_ptr) :: address
      dims = 0
      if (skipped(self, err)) return
      call open_dataset(self, path, dset_id, e)
      if (.not. allocated(e)) then
         call h5dget_type_f(dset_id, type_id, hdferr)
         call h5tget_class_f(type_id, stored_class, status)
         call h5tclose_f(type_id, status)
         if (hdferr /= 0 .or. stored_class /= type_class) call fatal_error(e, module_name &
            // ': ' // at(path, self%path) // ' holds ' // class_name(stored_class) // ', not ' &
            // class_name(type_class))
         if (.not. allocated(e)) call dataset_shape(self, dset_id, path, dims, e)
         mem_type = H5T_NATIVE_DOUBLE
         if (type_class == H5T_INTEGER_F) mem_type = H5T_NATIVE_INTEGER
         if (.not. allocated(e) .and. present(buf)) then
            address = buf
            call h5dread_f(dset_id, mem_type, address, hdferr)
            if (hdferr /= 0) call fatal_error(e, module_name // ': cannot read ' &
               // at(path, self%path))
         end if
         call h5dclose_f(dset_id, status)
      end if
      call settle(self, e, err)
   end subroutine read_numeric

   !> Read a fixed-length string dataset of rank `rank` (0 or 1) as raw bytes.
   subroutine read_strings(self, path, rank, buf, width, n, err)
      class(h5_reader_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      integer, intent(in) :: rank
      character(kind=c_char, len=1), allocatable, target, intent(out) :: buf(:)
      integer, intent(out) :: width, n
      type(error_t), allocatable, intent(out), optional :: err
      type(error_t), allocatable :: e
      integer(hid_t) :: dset_id, type_id
      integer(hsize_t) :: dims(rank)
      integer :: hdferr, status
      type(c_ptr) :: address
      width = 1;  n = 0
      allocate(buf(0))
      if (skipped(self, err)) return
      call open_dataset(self, path, dset_id, e)
      if (.not. allocated(e)) then
         call h5dget_type_f(dset_id, type_id, hdferr)
         call check_string_type(type_id, at(path, self%path), width, e)
         if (.not. allocated(e)) call dataset_shape(self, dset_id, path, dims, e)
         if (.not. allocated(e)) then
            n = int(product(dims))
            deallocate(buf)
            allocate(buf(max(1, width * n)))
            address = c_loc(buf)
            call h5dread_f(dset_id, type_id, address, hdferr)
            if (hdferr /= 0) call fatal_error(e, module_name // ': cannot read ' &
               // at(path, self%path))
            buf = buf(1:width * n)   ! (one byte was allocated for c_loc when n = 0)
         end if
         call h5tclose_f(type_id, status)
         call h5dclose_f(dset_id, status)
      end if
      call settle(self, e, err)
   end subroutine read_strings

   !> Open an existing dataset of the reader's file.
   subroutine open_dataset(self, path, dset_id, e)
      class(h5_reader_t), intent(in) :: self
      character(len=*), intent(in) :: path
      integer(hid_t), intent(out) :: dset_id
      type(error_t), allocatable, intent(out) :: e
      integer :: hdferr
      dset_id = no_id
      if (.not. self%is_open) then
         call fatal_error(e, module_name // ': no open file (call open first) to read ' // q(path))
      else if (.not. path_exists(self%file_id, path)) then
         call fatal_error(e, module_name // ': no ' // at(path, self%path))
      else
         call h5dopen_f(self%file_id, path, dset_id, hdferr)
         if (hdferr /= 0) call fatal_error(e, module_name // ': ' // q(path) // ' in file ' &
            // q(self%path) // ' is a group or cannot be opened as a dataset')
      end if
   end subroutine open_dataset

   !> The shape of an open dataset, whose rank must be size(dims).
   subroutine dataset_shape(self, dset_id, path, dims, e)
      class(h5_reader_t), intent(in) :: self
      integer(hid_t), intent(in) :: dset_id
      character(len=*), intent(in) :: path
      integer(hsize_t), intent(out) :: dims(:)
      type(error_t), allocatable, intent(inout) :: e
      integer(hid_t) :: space_id
      integer(hsize_t) :: stored(7), max_dims(7)
      integer :: hdferr, status, rank
      dims = 0
      call h5dget_space_f(dset_id, space_id, hdferr)
      if (hdferr == 0) call h5sget_simple_extent_ndims_f(space_id, rank, hdferr)
      if (hdferr == 0 .and. rank /= size(dims)) then
         call fatal_error(e, module_name // ': ' // at(path, self%path) // ' has rank ' &
            // str(rank) // ', not ' // str(size(dims)))
      else if (hdferr == 0 .and. rank > 0) then
         call h5sget_simple_extent_dims_f(space_id, stored(1:rank), max_dims(1:rank), status)
         dims = stored(1:rank)
      end if
      if (hdferr /= 0) call fatal_error(e, module_name // ': cannot get the shape of ' &
         // at(path, self%path))
      call h5sclose_f(space_id, status)
   end subroutine dataset_shape

   !> A fixed-length string type and its length in bytes; with `variable` present, a
   !> variable-length string type is accepted too (and said so).
   subroutine check_string_type(type_id, what, width, e, variable)
      integer(hid_t), intent(in) :: type_id
      character(len=*), intent(in) :: what
      integer, intent(out) :: width
      type(error_t), allocatable, intent(inout) :: e
      logical, intent(out), optional :: variable
      integer(size_t) :: type_size
      integer :: hdferr, stored_class
      logical :: is_variable
      width = 1
      if (present(variable)) variable = .false.
      call h5tget_class_f(type_id, stored_class, hdferr)
      if (hdferr /= 0 .or. stored_class /= H5T_STRING_F) then
         call fatal_error(e, module_name // ': ' // what // ' holds ' // class_name(stored_class) &
            // ', not strings')
         return
      end if
      call h5tis_variable_str_f(type_id, is_variable, hdferr)
      if (is_variable .and. present(variable)) then
         variable = .true.
      else if (is_variable) then
         call fatal_error(e, module_name // ': ' // what // ' holds variable-length strings; ' &
            // 'only fixed-length strings are supported')
      else
         call h5tget_size_f(type_id, type_size, hdferr)
         width = int(type_size)
      end if
   end subroutine check_string_type

   !> A scalar variable-length string attribute; the library's copy is freed.
   subroutine read_variable_string(attr_id, type_id, text, hdferr)
      integer(hid_t), intent(in) :: attr_id, type_id
      character(len=:), allocatable, intent(out) :: text
      integer, intent(out) :: hdferr
      type(c_ptr), target :: ptr(1)
      type(c_ptr) :: address
      character(kind=c_char, len=1), pointer :: chars(:)
      integer :: n
      text = ''
      ptr(1) = c_null_ptr
      address = c_loc(ptr(1))
      call h5aread_f(attr_id, type_id, address, hdferr)
      if (hdferr /= 0 .or. .not. c_associated(ptr(1))) return
      n = int(c_strlen(ptr(1)))
      call c_f_pointer(ptr(1), chars, [max(n, 1)])
      text = chars_to_text(chars(1:n))
      if (c_free_memory(ptr(1)) < 0) hdferr = -1
   end subroutine read_variable_string


   !> Text of the bytes in `buf`, without trailing NUL padding.
   pure function chars_to_text(buf) result(text)
      character(kind=c_char, len=1), intent(in) :: buf(:)  !! bytes
      character(len=:), allocatable :: text
      integer :: n, j
      n = size(buf)
      do while (n > 0)
         if (buf(n) /= c_null_char) exit
         n = n - 1
      end do
      allocate(character(len=n) :: text)
      do j = 1, n
         text(j:j) = buf(j)
      end do
   end function chars_to_text

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
end module gapbeam_hdf5_input
