!> XDMF description of the beam in motion and its stops, beside the HDF5 file of a transient run
!> with `&output state_history`, for ParaView: File > Open PREFIX.xdmf with either reader
!> ("Xdmf3 Reader S", ParaView's default, or the legacy "XDMF Reader"; both load it without a
!> warning: scripts/test_paraview.sh checks it).
!>
!> A temporal collection holds one spatial collection per history sample, at its time
!> (/history/time, absolute simulation time in seconds). In each:
!>  * grid `beam`: the undeformed shape mesh, `shape_points` points per element (the nodes among
!>    them) on the x axis joined by line segments (Polyline; /history/shape_mesh_xyz,
!>    /history/shape_segments), with point fields `w [m]` (and `v [m]` for two planes), the
!>    deflection relative to the base, and `displacement [m]` = (0, w, v), the vector to warp by;
!>  * one grid per stop, `stop J` (`stop J (+w)`, `stop J (-w)` for a two-sided stop): a flat
!>    stop as a block whose face lies at the gap (side positive: w = +gap and beyond), a circular
!>    one as the hole's circle in the (w, v) plane, both in the same displaced form (their
!>    geometry on the x axis at the stop's node, `displacement [m]` placing them, so that one
!>    "Warp By Vector" with one scale factor puts beam and stops in their places); cell fields
!>    `stop force [N]` (/history/stop_force) and `contact [1 closed, 0 open]`
!>    (/history/stop_contact: 1 while the stop pushes on the beam). A stop on a rotation is not
!>    drawn.
!> So the scene is the beam and its stops relative to the moving base, to scale with a warp
!> factor of 1 (a suggested factor, which keeps the swing within about a quarter of the span,
!> is written in the file's header comment).
!>
!> How the per-sample values are addressed: the one form that both readers accept for a slice
!> of a dataset is raw binary at a byte offset (Format="Binary" Seek="..."): the Xdmf3 reader
!> skips HDF5 hyperslabs ("Skipping unrecognized array type") and the legacy reader does not
!> parse the Xdmf3 "file.h5:/path|start:stride:count:dims" form. The writer stores every dataset
!> of the .h5 contiguously and uncompressed, so the XDMF file points at the values inside the
!> .h5 file itself: the offsets and byte order are read back from the file just written
!> (h5_reader_t%data_offset). Every number comes from the .h5 file, which must stay beside the
!> .xdmf file, unchanged (a repacked .h5, e.g. by h5repack, no longer matches: run again).
module gapbeam_xdmf
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: transient_result_t
   use gapbeam_description, only: dof_w
   use gapbeam_deflection, only: shape_points, deflection
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_files, only: append_text
   implicit none
   private
   public :: write_xdmf_datasets, make_xdmf, suggested_warp_scale

   !> The drawn stops: point ranges of /history/stop_mesh_* per grid.
   type :: stop_mesh_t
      integer :: n_grids = 0
      integer, allocatable :: stop(:)            !! deck stop of each grid
      character(len=16), allocatable :: label(:) !! '' or ' (+w)', ' (-w)'
      integer, allocatable :: first(:)           !! first point (from 0)
      integer, allocatable :: count(:)           !! points
      logical, allocatable :: ring(:)            !! circle (polyline) or block (quadrilateral)
      real(dp), allocatable :: xyz(:, :)         !! (3, points) undeformed: (x_stop, 0, 0)
      real(dp), allocatable :: disp(:, :)        !! (3, points) (0, w, v) placing them
   end type stop_mesh_t

   integer, parameter :: ring_segments = 24      !! segments of a circular stop's circle

contains

   !> The datasets the XDMF file reads, under /history (with `&output state_history`): the
   !> undeformed mesh, the displacement vectors, v for two planes, the contact state of every
   !> stop and the stops' meshes.
   subroutine write_xdmf_datasets(h5, deck, model, res)
      type(h5_writer_t), intent(inout) :: h5           !! writer of the .h5 file (its state
                                                       !! keeps a failure)
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results (with history_u)
      real(dp), allocatable :: x(:), mesh(:, :), disp(:, :, :), sv(:, :)
      integer, allocatable :: contact(:, :)
      type(stop_mesh_t) :: sm
      integer :: i, ns, two
      x = shape_points(model%sys, deck%output%shape_points)
      ns = size(res%time)
      two = model%sys%planes
      allocate(mesh(3, size(x)), source=0.0_dp)
      mesh(1, :) = x
      call h5%put('/history/shape_mesh_xyz', mesh)
      allocate(disp(3, size(x), ns), source=0.0_dp)
      if (two == 2) allocate(sv(size(x), ns))
      do i = 1, ns
         disp(2, :, i) = deflection(model%sys, res%history_u(:, i), deck%output%shape_points)
         if (two == 2) then
            sv(:, i) = deflection(model%sys, res%history_u(:, i), deck%output%shape_points, 2)
            disp(3, :, i) = sv(:, i)
         end if
      end do
      call h5%put('/history/shape_displacement', disp)
      if (two == 2) call h5%put('/history/shape_v', sv)
      allocate(contact(size(res%stop_force, 2), ns))
      contact = merge(1, 0, transpose(res%stop_force) > 0.0_dp)
      call h5%put('/history/stop_contact', contact)
      sm = stop_mesh(deck, model, maxval(abs(disp)))
      if (sm%n_grids == 0) return
      call h5%put('/history/stop_mesh_xyz', sm%xyz)
      call h5%put('/history/stop_mesh_displacement', sm%disp)
   end subroutine write_xdmf_datasets

   !> The drawn stops: a flat stop on w as a block (a quadrilateral of half-length 3 % of the
   !> beam along x, its face at the gap, `depth` deep beyond it), each side of a two-sided one
   !> as its own grid; a circular stop as its circle (ring_segments segments) around the hole
   !> centre; a stop on a rotation not at all.
   function stop_mesh(deck, model, swing) result(sm)
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      real(dp), intent(in) :: swing                    !! largest |w| or |v| of the record [m]
      type(stop_mesh_t) :: sm
      real(dp) :: xs, a, depth, s, g, phi
      integer :: j, k, side, n
      allocate(sm%stop(0), sm%label(0), sm%first(0), sm%count(0), sm%ring(0))
      allocate(sm%xyz(3, 0), sm%disp(3, 0))
      a = 0.03_dp * model%sys%element_length * real(model%sys%n_node - 1, dp)
      n = 0
      do j = 1, size(deck%stops)
         xs = model%sys%element_length * real(deck%stops(j)%node - 1, dp)
         g = deck%stops(j)%gap
         if (deck%stops(j)%shape == 'circular') then
            call add_grid(j, '', ring_segments + 1, .true.)
            do k = 0, ring_segments
               phi = 8.0_dp * atan(1.0_dp) * real(k, dp) / real(ring_segments, dp)
               call add_point(xs, [deck%stops(j)%offset_w + g * cos(phi), &
                                   deck%stops(j)%offset_v + g * sin(phi)])
            end do
            cycle
         end if
         if (deck%stops(j)%dof /= dof_w) cycle
         depth = max(0.25_dp * swing, g, 1.0e-3_dp * a)
         do side = 1, 2
            if (side == 1 .and. deck%stops(j)%side == 'negative') cycle
            if (side == 2 .and. deck%stops(j)%side == 'positive') cycle
            s = merge(1.0_dp, -1.0_dp, side == 1)
            call add_grid(j, trim(merge(' (+w)', ' (-w)', side == 1)), 4, .false.)
            if (deck%stops(j)%side /= 'both') sm%label(sm%n_grids) = ''
            call add_point(xs - a, [s * g, 0.0_dp])
            call add_point(xs + a, [s * g, 0.0_dp])
            call add_point(xs + a, [s * (g + depth), 0.0_dp])
            call add_point(xs - a, [s * (g + depth), 0.0_dp])
         end do
      end do
   contains
      subroutine add_grid(j, label, count, ring)
         integer, intent(in) :: j, count
         character(len=*), intent(in) :: label
         logical, intent(in) :: ring
         sm%n_grids = sm%n_grids + 1
         sm%stop = [sm%stop, j];  sm%first = [sm%first, n];  sm%count = [sm%count, count]
         sm%label = [character(len=16) :: sm%label, label];  sm%ring = [sm%ring, ring]
      end subroutine add_grid
      subroutine add_point(x, wv)
         real(dp), intent(in) :: x, wv(2)
         real(dp), allocatable :: t(:, :)
         allocate(t(3, n + 1))
         t(:, 1:n) = sm%xyz;  t(:, n + 1) = [x, 0.0_dp, 0.0_dp];  sm%xyz = t
         t(:, 1:n) = sm%disp;  t(:, n + 1) = [0.0_dp, wv(1), wv(2)];  sm%disp = t
         n = n + 1
      end subroutine add_point
   end function stop_mesh

   !> A warp scale factor that keeps the motion on screen: the largest |w| (or |v|) of the record
   !> shown as about a quarter of the span, rounded down to 1, 2 or 5 times a power of ten, and
   !> never above 1 when the true motion already reaches that (the true scale is then best).
   pure real(dp) function suggested_warp_scale(span, swing) result(f)
      real(dp), intent(in) :: span                     !! length of the beam [m]
      real(dp), intent(in) :: swing                    !! largest |w| or |v| [m]
      real(dp) :: raw, p
      f = 1.0_dp
      if (swing <= 0.0_dp) return
      raw = 0.25_dp * span / swing
      if (raw <= 1.0_dp) return
      p = 10.0_dp**floor(log10(raw))
      if (raw >= 5.0_dp * p) then
         f = 5.0_dp * p
      else if (raw >= 2.0_dp * p) then
         f = 2.0_dp * p
      else
         f = p
      end if
   end function suggested_warp_scale

   !> The XDMF text for the .h5 file `h5_path` (complete and closed; read for the byte offsets
   !> of its datasets), which the XDMF file names `h5_name` (relative to its own directory: the
   !> two stay side by side).
   subroutine make_xdmf(h5_path, h5_name, deck, model, res, text, err)
      character(len=*), intent(in) :: h5_path          !! the .h5 file as it is now named
      character(len=*), intent(in) :: h5_name          !! its final name, without a directory
      type(deck_t), intent(in) :: deck                 !! the deck
      type(model_t), intent(in) :: model               !! model
      type(transient_result_t), intent(in) :: res      !! results (with history_u)
      character(len=:), allocatable, intent(out) :: text  !! the XDMF file's text
      type(error_t), allocatable, intent(out) :: err   !! the .h5 file could not be read
      type(h5_reader_t) :: rd
      integer(int64) :: off(7)
      logical :: little(7), two
      type(stop_mesh_t) :: sm
      character(len=*), parameter :: dsets(7) = [character(len=36) :: '/history/shape_w', &
         '/history/shape_displacement', '/history/shape_v', '/history/stop_force', &
         '/history/stop_contact', '/history/stop_mesh_xyz', '/history/stop_mesh_displacement']
      real(dp) :: swing, span
      integer :: k, np, ns_stop
      two = model%sys%planes == 2
      ns_stop = size(res%stop_force, 2)
      np = size(shape_points(model%sys, deck%output%shape_points))
      swing = 0.0_dp
      do k = 1, size(res%time)
         swing = max(swing, maxval(abs(deflection(model%sys, res%history_u(:, k), &
                                                  deck%output%shape_points))))
         if (two) swing = max(swing, maxval(abs(deflection(model%sys, res%history_u(:, k), &
                                                           deck%output%shape_points, 2))))
      end do
      span = model%sys%element_length * real(model%sys%n_node - 1, dp)
      sm = stop_mesh(deck, model, swing)
      call rd%open(h5_path, err);  if (allocated(err)) return
      off = -1;  little = .true.
      do k = 1, size(dsets)
         if (k == 3 .and. .not. two) cycle
         if (k >= 6 .and. sm%n_grids == 0) cycle
         call rd%data_offset(trim(dsets(k)), off(k), little(k), err)
         if (allocated(err)) exit
      end do
      call rd%close()
      if (allocated(err)) return
      text = ''
      if (.not. all(little .eqv. little(1))) then
         call fatal_error(err, 'gapbeam_xdmf: ' // trim(h5_path) // ': datasets of mixed ' &
            // 'byte order')
         return
      end if
      text = xdmf_document()
   contains
      function xdmf_document() result(t)
         character(len=:), allocatable :: t, h5
         character(len=*), parameter :: nl = new_line('a')
         character(len=32) :: buf
         integer :: i, nt, j
         h5 = xml_escape(h5_name)
         nt = 0
         write(buf, '(g0.3)') suggested_warp_scale(span, swing)
         call append_text(t, nt, '<?xml version="1.0" encoding="utf-8"?>' // nl &
            // '<!-- gapbeam: the beam and its stops relative to the moving base at every ' &
            // 'history sample, time in seconds.' // nl &
            // '     ParaView: open with either XDMF reader, add Warp By Vector (vector ' &
            // '"displacement [m]", scale factor ' // trim(adjustl(buf)) // ' keeps the ' &
            // 'largest |w| = ' // str(swing) // ' m within a quarter of the span ' // str(span) &
            // ' m; 1 is true scale), colour by "w [m]" or the stops by "contact [1 closed, 0 ' &
            // 'open]" or "stop force [N]", play.' // nl &
            // '     Every value is read from ' // h5 // ' (the byte offsets of its ' &
            // 'datasets: keep it beside this file, unchanged). docs/outputs.md, ParaView. -->' &
            // nl // '<Xdmf Version="3.0">' // nl // ' <Domain>' // nl &
            // '  <Grid Name="' // xml_escape(trim(deck%job%title)) // '" GridType="Collection" ' &
            // 'CollectionType="Temporal">' // nl)
         do i = 1, size(res%time)
            write(buf, '(es24.16e3)') res%time(i)
            call append_text(t, nt, '   <Grid Name="sample ' // str(i) // '" GridType=' &
               // '"Collection" CollectionType="Spatial">' // nl // '    <Time Value="' &
               // trim(adjustl(buf)) // '"/>' // nl // beam_grid(i))
            do j = 1, sm%n_grids
               call append_text(t, nt, stop_grid(i, j))
            end do
            call append_text(t, nt, '   </Grid>' // nl)
         end do
         call append_text(t, nt, '  </Grid>' // nl // ' </Domain>' // nl // '</Xdmf>' // nl)
         t = t(1:nt)
      end function xdmf_document

      !> The beam's grid at sample i (from 1).
      function beam_grid(i) result(t)
         integer, intent(in) :: i
         character(len=:), allocatable :: t
         character(len=*), parameter :: nl = new_line('a')
         character(len=:), allocatable :: h5, np_s, ne_s
         integer(int64) :: i0
         h5 = xml_escape(h5_name);  np_s = str(np);  ne_s = str(np - 1)
         i0 = int(i - 1, int64)
         t = '    <Grid Name="beam" GridType="Uniform">' // nl &
            // '     <Topology TopologyType="Polyline" NodesPerElement="2" NumberOfElements="' &
            // ne_s // '">' // nl &
            // '      <DataItem Dimensions="' // ne_s // ' 2" NumberType="Int" Precision="4" ' &
            // 'Format="HDF">' // h5 // ':/history/shape_segments</DataItem>' // nl &
            // '     </Topology>' // nl // '     <Geometry GeometryType="XYZ">' // nl &
            // '      <DataItem Dimensions="' // np_s // ' 3" NumberType="Float" Precision="8" ' &
            // 'Format="HDF">' // h5 // ':/history/shape_mesh_xyz</DataItem>' // nl &
            // '     </Geometry>' // nl &
            // attribute('w [m]', 'Scalar', 'Node', np_s, 'Float', 8, off(1) + i0 * np * 8) &
            // attribute('displacement [m]', 'Vector', 'Node', np_s // ' 3', 'Float', 8, &
                         off(2) + i0 * np * 24)
         if (two) t = t // attribute('v [m]', 'Scalar', 'Node', np_s, 'Float', 8, &
                                     off(3) + i0 * np * 8)
         t = t // '    </Grid>' // nl
      end function beam_grid

      !> Grid j of the drawn stops at sample i (from 1).
      function stop_grid(i, j) result(t)
         integer, intent(in) :: i, j
         character(len=:), allocatable :: t
         character(len=*), parameter :: nl = new_line('a')
         character(len=:), allocatable :: h5, np_s, conn
         integer(int64) :: cell
         integer :: k
         h5 = xml_escape(h5_name);  np_s = str(sm%count(j))
         conn = ''
         do k = 0, sm%count(j) - 1
            conn = conn // ' ' // str(k)
         end do
         cell = int(i - 1, int64) * ns_stop + (sm%stop(j) - 1)
         t = '    <Grid Name="stop ' // str(sm%stop(j)) // trim(sm%label(j)) &
            // '" GridType="Uniform">' // nl &
            // '     <Topology TopologyType="' // trim(merge('Polyline     ', 'Quadrilateral', &
               sm%ring(j))) // '" NodesPerElement="' // np_s // '" NumberOfElements="1">' // nl &
            // '      <DataItem Dimensions="1 ' // np_s // '" NumberType="Int" Precision="4" ' &
            // 'Format="XML">' // conn(2:) // '</DataItem>' // nl // '     </Topology>' // nl &
            // '     <Geometry GeometryType="XYZ">' // nl &
            // data_item(np_s // ' 3', 'Float', 8, off(6) + int(sm%first(j), int64) * 24) &
            // '     </Geometry>' // nl &
            // attribute('displacement [m]', 'Vector', 'Node', np_s // ' 3', 'Float', 8, &
                         off(7) + int(sm%first(j), int64) * 24) &
            // attribute('stop force [N]', 'Scalar', 'Cell', '1', 'Float', 8, off(4) + cell * 8) &
            // attribute('contact [1 closed, 0 open]', 'Scalar', 'Cell', '1', 'Int', 4, &
                         off(5) + cell * 4) &
            // '    </Grid>' // nl
      end function stop_grid

      !> An attribute whose values lie at byte `seek` of the .h5 file.
      function attribute(name, kind, centre, dims, number, precision, seek) result(t)
         character(len=*), intent(in) :: name, kind, centre, dims, number
         integer, intent(in) :: precision
         integer(int64), intent(in) :: seek
         character(len=:), allocatable :: t
         t = '     <Attribute Name="' // xml_escape(name) // '" AttributeType="' // kind &
            // '" Center="' // centre // '">' // new_line('a') &
            // data_item(dims, number, precision, seek) // '     </Attribute>' // new_line('a')
      end function attribute

      !> A DataItem of raw values at byte `seek` of the .h5 file.
      function data_item(dims, number, precision, seek) result(t)
         character(len=*), intent(in) :: dims, number
         integer, intent(in) :: precision
         integer(int64), intent(in) :: seek
         character(len=:), allocatable :: t
         character(len=24) :: sk
         write(sk, '(i0)') seek
         t = '      <DataItem Dimensions="' // dims // '" NumberType="' // number &
            // '" Precision="' // str(precision) // '" Format="Binary" Endian="' &
            // trim(merge('Little', 'Big   ', little(1))) // '" Seek="' // trim(sk) // '">' &
            // xml_escape(h5_name) // '</DataItem>' // new_line('a')
      end function data_item
   end subroutine make_xdmf

   !> `s` with the XML special characters escaped.
   pure function xml_escape(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      integer :: i
      t = ''
      do i = 1, len(s)
         select case (s(i:i))
         case ('&');  t = t // '&amp;'
         case ('<');  t = t // '&lt;'
         case ('>');  t = t // '&gt;'
         case ('"');  t = t // '&quot;'
         case ("'");  t = t // '&apos;'
         case default;  t = t // s(i:i)
         end select
      end do
   end function xml_escape
end module gapbeam_xdmf
