!> What makes a result file describe itself, written by every result writer:
!>
!> * root attributes: `program` ('gapbeam'), `version`, `git_commit` (GAPBEAM_GIT_COMMIT, set
!>   by the repository's scripts, else 'unknown'), `compiler`, `creation_time` (ISO 8601 with
!>   the UTC offset), `analysis`, `deck_crc32` (zlib's CRC-32 of the /deck text, 8 hex digits),
!>   `units_convention` and `axis_order`;
!> * `/parameters`: every resolved model value (gapbeam_parameters);
!> * `/model`: the discrete model, so that other tools can integrate the same equations: K and
!>   M with the dof map (`/model/dof_node`, `dof_type`, `dof_name`: which node and which of w,
!>   theta, v, theta_v each degree of freedom is; a modal model has none), and for an analysis
!>   that integrates, C, the load shape, the forcing, the strain row and the contacts.
!>
!> Axis order, one rule for every file: in C order (as h5py, numpy, h5dump and ParaView show
!> a dataset) the first axis is the record -- history sample, sweep point, mode, method, study
!> level -- and the second is what each record holds -- stop, node, dof, period. Each
!> two-dimensional dataset names its axes in its `dimensions` attribute.
module gapbeam_file_info
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_parameters, only: parameter_set_t
   use gapbeam_model, only: system_t, model_t, has_modal_damping
   use gapbeam_description, only: dof_name
   use gapbeam_error, only: str
   use gapbeam_checksum, only: crc32_hex
   use gapbeam_version, only: program_version, compiler_text, git_commit
   implicit none
   private
   public :: write_file_info, write_parameter_set, write_structure, write_model, creation_time, &
      udunits

   !> The axis-order rule, as stored in the root attribute `axis_order`.
   character(len=*), parameter :: axis_order_text = 'C order (h5py, numpy, h5dump, ParaView):' &
      // ' the first axis is the record (history sample, sweep point, mode, method, study ' &
      // 'level), the second what each record holds (stop, node, dof, period); every 2-D ' &
      // 'dataset names its axes in its dimensions attribute'

contains

   !> The root attributes of a result file written by `analysis` from `deck_text`.
   subroutine write_file_info(h5, analysis, deck_text)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      character(len=*), intent(in) :: analysis           !! analysis word
      character(len=*), intent(in) :: deck_text          !! the effective deck text (/deck)
      call h5%attr('/', 'program', 'gapbeam')
      call h5%attr('/', 'version', program_version)
      call h5%attr('/', 'git_commit', git_commit())
      call h5%attr('/', 'compiler', compiler_text())
      call h5%attr('/', 'creation_time', creation_time())
      call h5%attr('/', 'analysis', analysis)
      call h5%attr('/', 'deck_crc32', crc32_hex(deck_text))
      call h5%attr('/', 'units_convention', 'UDUNITS-2 (units attribute of every dataset; 1 ' &
         // 'for a pure number); long_name says what the values are')
      call h5%attr('/', 'axis_order', axis_order_text)
   end subroutine write_file_info

   !> The run's parameters under /parameters.
   subroutine write_parameter_set(h5, set)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      type(parameter_set_t), intent(in) :: set           !! the parameters
      character(len=:), allocatable :: fill
      integer :: k
      if (.not. allocated(set%items)) return
      do k = 1, size(set%items)
         associate (p => set%items(k))
            fill = ''
            if (allocated(p%fill)) fill = p%fill
            if (allocated(p%text)) then
               call h5%put('/parameters/' // p%path, p%text)
            else if (p%is_array .and. allocated(p%units)) then
               call h5%put('/parameters/' // p%path, p%values, units=p%units)
            else if (p%is_array) then
               call h5%put('/parameters/' // p%path, p%values)
            else
               call h5%put('/parameters/' // p%path, p%values(1), fill=fill)
            end if
         end associate
      end do
   end subroutine write_parameter_set

   !> /model/stiffness, /model/mass and the dof map of an assembled structure (a modal
   !> model's matrices without a dof map).
   subroutine write_structure(h5, sys)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      type(system_t), intent(in) :: sys                  !! assembled structure (or modal)
      integer, allocatable :: node(:), kind(:)
      character(len=16), allocatable :: names(:)
      integer :: i, j, g
      call h5%put('/model/stiffness', sys%k)
      call h5%put('/model/mass', sys%m)
      if (sys%n_node < 1 .or. .not. allocated(sys%dof_of)) return   ! a modal model
      allocate(node(sys%n_dof), kind(sys%n_dof), names(sys%n_dof))
      node = 0;  kind = 0;  names = ''
      do i = 1, sys%n_node
         do j = 1, size(sys%dof_of, 1)
            g = sys%dof_of(j, i)
            if (g < 1) cycle
            node(g) = i;  kind(g) = j
            names(g) = dof_name(j) // '_' // str(i)
         end do
      end do
      call h5%put('/model/dof_node', node)
      call h5%put('/model/dof_type', kind)
      call h5%put('/model/dof_name', names)
   end subroutine write_structure

   !> /model of an analysis that integrates: the structure, the stop stiffnesses, C, the load
   !> shape, the forcing, the strain row, the one-sided and the ring contacts.
   subroutine write_model(h5, model, stiffness_units)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      type(model_t), intent(in) :: model                 !! the model
      character(len=*), intent(in) :: stiffness_units    !! of the stop stiffnesses
      call h5%put('/model/stop_stiffness', model%stop_stiffness, units=stiffness_units)
      call h5%put('/model/f1_open_hz', model%f1_open_hz)
      call write_structure(h5, model%sys)
      if (has_modal_damping(model)) then
         call h5%put('/model/damping', model%c, fill=' + M Phi diag(2 zeta omega) Phi^T M')
      else
         call h5%put('/model/damping', model%c, fill='')
      end if
      call h5%put('/model/load_shape', model%q)
      call h5%put('/model/forcing_omega', model%omega)
      call h5%put('/model/forcing_half_amplitude', model%half_amplitude)
      call h5%put('/model/strain_row', model%sys%strain_row)
      call h5%put('/model/contact_dof', model%c_dof)
      call h5%put('/model/contact_sign', model%c_sign)
      call h5%put('/model/contact_gap', model%c_gap)
      call h5%put('/model/contact_stiffness', model%c_k)
      call h5%put('/model/contact_damping', model%c_c)
      call h5%put('/model/contact_law', model%c_law)
      if (model%n_rings == 0) return
      call h5%put('/model/ring_dof_w', model%r_dof(1, :))
      call h5%put('/model/ring_dof_v', model%r_dof(2, :))
      call h5%put('/model/ring_gap', model%r_gap)
      call h5%put('/model/ring_stiffness', model%r_k)
      call h5%put('/model/ring_friction', model%r_mu)
      call h5%put('/model/ring_tangential_stiffness', model%r_kt)
   end subroutine write_model

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

   !> A deck variable's unit as UDUNITS-2 ('-' or none is '1', a pure number).
   pure function udunits(u) result(t)
      character(len=*), intent(in) :: u                  !! unit ('-', 'm', 'N m/rad', ...)
      character(len=:), allocatable :: t
      t = trim(u)
      if (t == '-' .or. len(t) == 0) t = '1'
   end function udunits
end module gapbeam_file_info
