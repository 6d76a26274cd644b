!> XDMF (version 3) description of the beam in motion, beside the HDF5 file of a transient run
!> with `&output state_history`, so that ParaView (File > Open, "Xdmf3 Reader S" or "XDMF
!> Reader") shows the beam as a line mesh with its time series.
!>
!> The mesh is the deflected shape: `shape_points` points per element (the nodes among them)
!> joined by line segments (Polyline, two nodes per segment, /history/shape_segments), at the
!> coordinates (x, w, 0) of each history sample (/history/shape_xyz, one hyperslab per sample:
!> the beam moves when the time steps are played; w is small beside the length, so scale the
!> y axis in ParaView with a Transform filter). Point data: `w`, the deflection relative to the
!> base [m] (/history/shape_w). A temporal collection holds one grid per history sample at its
!> time (/history/time). The XDMF file names the HDF5 file without a directory, so the two must
!> stay side by side; every number is read from the HDF5 file (the XML holds only sizes, times
!> and hyperslab offsets).
module gapbeam_xdmf
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   implicit none
   private
   public :: xdmf_text

   !> One piece of text.
   type :: chunk_t
      character(len=:), allocatable :: s
   end type chunk_t

contains

   !> The XDMF text for the shape of `n_points` points at the sample `times`, stored in the
   !> HDF5 file `h5_name` (a name relative to the XDMF file's directory).
   function xdmf_text(h5_name, title, times, n_points) result(t)
      character(len=*), intent(in) :: h5_name          !! e.g. 'moon_shaw_10p5hz.h5'
      character(len=*), intent(in) :: title            !! the deck's title
      real(dp), intent(in) :: times(:)                 !! sample times [s]
      integer, intent(in) :: n_points                  !! points of the shape
      character(len=:), allocatable :: t
      character(len=*), parameter :: nl = new_line('a')
      type(chunk_t), allocatable :: parts(:)
      character(len=:), allocatable :: h5, np_s, ns_s, ne_s
      character(len=32) :: tbuf
      integer :: i, n, total, pos, k
      n = size(times)
      h5 = xml_escape(h5_name)
      np_s = str(n_points);  ns_s = str(n);  ne_s = str(n_points - 1)
      allocate(parts(n + 2))
      parts(1)%s = '<?xml version="1.0" encoding="utf-8"?>' // nl &
         // '<!-- gapbeam: the deflected beam at every history sample -->' // nl &
         // '<Xdmf Version="3.0">' // nl // ' <Domain>' // nl &
         // '  <Grid Name="' // xml_escape(title) // '" GridType="Collection" ' &
         // 'CollectionType="Temporal">' // nl
      do i = 1, n
         write(tbuf, '(es24.16e3)') times(i)
         parts(i + 1)%s = '   <Grid Name="sample ' // str(i) // '" GridType="Uniform">' // nl &
            // '    <Time Value="' // trim(adjustl(tbuf)) // '"/>' // nl &
            // '    <Topology TopologyType="Polyline" NodesPerElement="2" NumberOfElements="' &
            // ne_s // '">' // nl &
            // '     <DataItem Dimensions="' // ne_s // ' 2" NumberType="Int" Precision="4" ' &
            // 'Format="HDF">' // h5 // ':/history/shape_segments</DataItem>' // nl &
            // '    </Topology>' // nl &
            // '    <Geometry GeometryType="XYZ">' // nl &
            // '     <DataItem ItemType="HyperSlab" Dimensions="' // np_s &
            // ' 3" Type="HyperSlab">' &
            // nl // '      <DataItem Dimensions="3 3" NumberType="Int" Format="XML">' &
            // str(i - 1) // ' 0 0 1 1 1 1 ' // np_s // ' 3</DataItem>' // nl &
            // '      <DataItem Dimensions="' // ns_s // ' ' // np_s // ' 3" NumberType="Float" ' &
            // 'Precision="8" Format="HDF">' // h5 // ':/history/shape_xyz</DataItem>' // nl &
            // '     </DataItem>' // nl // '    </Geometry>' // nl &
            // '    <Attribute Name="w" AttributeType="Scalar" Center="Node">' // nl &
            // '     <DataItem ItemType="HyperSlab" Dimensions="' // np_s // '" Type="HyperSlab">' &
            // nl // '      <DataItem Dimensions="3 2" NumberType="Int" Format="XML">' &
            // str(i - 1) // ' 0 1 1 1 ' // np_s // '</DataItem>' // nl &
            // '      <DataItem Dimensions="' // ns_s // ' ' // np_s // '" NumberType="Float" ' &
            // 'Precision="8" Format="HDF">' // h5 // ':/history/shape_w</DataItem>' // nl &
            // '     </DataItem>' // nl // '    </Attribute>' // nl // '   </Grid>' // nl
      end do
      parts(n + 2)%s = '  </Grid>' // nl // ' </Domain>' // nl // '</Xdmf>' // nl
      total = 0
      do k = 1, size(parts)
         total = total + len(parts(k)%s)
      end do
      allocate(character(len=total) :: t)
      pos = 0
      do k = 1, size(parts)
         t(pos + 1:pos + len(parts(k)%s)) = parts(k)%s
         pos = pos + len(parts(k)%s)
      end do
   end function xdmf_text

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
