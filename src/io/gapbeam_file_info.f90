!> What makes a result file describe itself, written by every result writer:
!>
!> * root attributes: `program` ('gapbeam'), `version`, `git_commit` (GAPBEAM_GIT_COMMIT, set
!>   by the repository's scripts, else 'unknown'), `compiler`, `creation_time` (ISO 8601 with
!>   the UTC offset), `analysis`, `deck_crc32` (zlib's CRC-32 of the /deck text, 8 hex digits),
!>   `units_convention` and `axis_order`;
!> * `/parameters`: every resolved model value (gapbeam_parameters), each with units and
!>   long_name;
!> * `/model/dof_node`, `/model/dof_type`, `/model/dof_name`: which node and which of (w,
!>   theta) each degree of freedom is (finite element models; a modal model has none).
!>
!> Axis order, one rule for every file: in C order (as h5py, numpy, h5dump and ParaView show
!> a dataset) the first axis is the record -- history sample, sweep point, mode, method,
!> study level -- and the second is what each record holds -- stop, node, dof, period. Each
!> two-dimensional dataset names its axes in its `dimensions` attribute.
module gapbeam_file_info
   use, intrinsic :: iso_fortran_env, only: int8, int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_parameters, only: parameter_set_t
   use gapbeam_model, only: system_t
   use gapbeam_description, only: dof_w, dof_theta
   use gapbeam_checkpoint, only: crc32
   use gapbeam_version, only: program_version, compiler_text, git_commit
   implicit none
   private
   public :: write_file_info, write_parameter_set, write_dof_map, axis_order_text, &
      creation_time, crc32_hex

   !> The axis-order rule, as stored in the root attribute `axis_order`.
   character(len=*), parameter :: axis_order_text = 'C order (h5py, numpy, h5dump, ParaView):' &
      // ' the first axis is the record (history sample, sweep point, mode, method, study ' &
      // 'level), the second what each record holds (stop, node, dof, period); every 2-D ' &
      // 'dataset names its axes in its dimensions attribute'

contains

   !> The root attributes of a result file written by `analysis` from `deck_text`.
   subroutine write_file_info(h5, analysis, deck_text, err)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      character(len=*), intent(in) :: analysis           !! analysis word
      character(len=*), intent(in) :: deck_text          !! the effective deck text (/deck)
      type(error_t), allocatable, intent(out) :: err     !! write failure
      call h5%write_attr('/', 'program', 'gapbeam', err);  if (allocated(err)) return
      call h5%write_attr('/', 'version', program_version, err);  if (allocated(err)) return
      call h5%write_attr('/', 'git_commit', git_commit(), err);  if (allocated(err)) return
      call h5%write_attr('/', 'compiler', compiler_text(), err);  if (allocated(err)) return
      call h5%write_attr('/', 'creation_time', creation_time(), err);  if (allocated(err)) return
      call h5%write_attr('/', 'analysis', analysis, err);  if (allocated(err)) return
      call h5%write_attr('/', 'deck_crc32', crc32_hex(deck_text), err)
      if (allocated(err)) return
      call h5%write_attr('/', 'units_convention', 'UDUNITS-2 (units attribute of every ' &
         // 'dataset; 1 for a pure number); long_name says what the values are', err)
      if (allocated(err)) return
      call h5%write_attr('/', 'axis_order', axis_order_text, err)
   end subroutine write_file_info

   !> The run's parameters under /parameters.
   subroutine write_parameter_set(h5, set, err)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      type(parameter_set_t), intent(in) :: set           !! the parameters
      type(error_t), allocatable, intent(out) :: err     !! write failure
      integer :: k
      if (.not. allocated(set%items)) return
      do k = 1, size(set%items)
         associate (p => set%items(k))
            if (allocated(p%text)) then
               call h5%write_text('/parameters/' // p%path, p%text, err, p%long_name)
            else if (p%is_array) then
               call h5%write('/parameters/' // p%path, p%values, p%units, err, p%long_name)
            else
               call h5%write('/parameters/' // p%path, p%values(1), p%units, err, p%long_name)
            end if
         end associate
         if (allocated(err)) return
      end do
   end subroutine write_parameter_set

   !> Which node and which dof each degree of freedom of a finite element model is.
   subroutine write_dof_map(h5, sys, err)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      type(system_t), intent(in) :: sys                  !! assembled structure
      type(error_t), allocatable, intent(out) :: err     !! write failure
      integer, allocatable :: node(:), kind(:)
      character(len=16), allocatable :: names(:)
      integer :: i, j, g
      if (sys%n_node < 1 .or. .not. allocated(sys%dof_of)) return   ! a modal model
      allocate(node(sys%n_dof), kind(sys%n_dof), names(sys%n_dof))
      node = 0;  kind = 0;  names = ''
      do i = 1, sys%n_node
         do j = dof_w, dof_theta
            g = sys%dof_of(j, i)
            if (g < 1) cycle
            node(g) = i;  kind(g) = j
            names(g) = merge('w_    ', 'theta_', j == dof_w)
            names(g) = trim(names(g)) // str(i)
         end do
      end do
      call h5%write('/model/dof_node', node, '1', err, 'node of each degree of freedom ' &
         // '(1 = root, node i at x = (i - 1) le)')
      if (allocated(err)) return
      call h5%write('/model/dof_type', kind, '1', err, 'kind of each degree of freedom: ' &
         // '1 w (transverse displacement, m), 2 theta (rotation dw/dx, rad)')
      if (allocated(err)) return
      call h5%write('/model/dof_name', names, '1', err, 'name of each degree of freedom: ' &
         // 'w_<node> or theta_<node>')
   end subroutine write_dof_map

   !> The current local time in ISO 8601 with the UTC offset, e.g. '2024-05-01T12:34:56+02:00'.
   function creation_time() result(t)
      character(len=:), allocatable :: t
      character(len=8) :: date
      character(len=10) :: time
      character(len=5) :: zone
      call date_and_time(date, time, zone)
      t = date(1:4) // '-' // date(5:6) // '-' // date(7:8) // 'T' // time(1:2) // ':' &
         // time(3:4) // ':' // time(5:6)
      if (len_trim(zone) == 5) t = t // zone(1:3) // ':' // zone(4:5)
   end function creation_time

   !> CRC-32 (zlib's) of a text as 8 lower-case hex digits.
   function crc32_hex(text) result(h)
      character(len=*), intent(in) :: text               !! the text
      character(len=:), allocatable :: h
      character(len=8) :: buf
      integer(int64) :: crc
      integer(int8), allocatable :: bytes(:)
      integer :: i
      allocate(bytes(len(text)))
      do i = 1, len(text)
         bytes(i) = int(iachar(text(i:i)) - merge(256, 0, iachar(text(i:i)) > 127), int8)
      end do
      crc = crc32(bytes)
      write(buf, '(z8.8)') crc
      h = buf
      do i = 1, len(h)
         if (h(i:i) >= 'A' .and. h(i:i) <= 'F') h(i:i) = achar(iachar(h(i:i)) + 32)
      end do
   end function crc32_hex
end module gapbeam_file_info
