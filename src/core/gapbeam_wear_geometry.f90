!> From a wear volume to a wear depth in the tube wall: the geometry of the scar (docs/flow.md).
!>
!> Archard's law gives the volume the tube loses, V(t) = V' t (V' = wear_coefficient x normal
!> work rate, stationary). The scar is taken where the support removes it, all of it in one
!> place (the usual, conservative design assumption), the support itself unworn:
!> * tube (outer radius R) against a flat bar of land width b: the bar's plane cuts a flat into
!>   the tube to the depth h, over the land width along the tube:
!>      V(h) = b A_s(R, R - h),
!>   A_s(r, s) = r^2 acos(s/r) - s (r^2 - s^2)^(1/2) the area of the segment of a disc of
!>   radius r beyond a chord at distance s from its centre; for h << R,
!>   V ~ (4/3) b (2R)^(1/2) h^(3/2);
!> * tube in a drilled hole (radius R_h = hole_diameter/2 > R) through a plate of thickness t:
!>   the hole's cylinder cuts a crescent into the tube when the tube centre lies R_h - R + h
!>   from the hole centre, over the plate thickness:
!>      V(h) = t [A_s(R, x_c - d) - A_s(R_h, x_c)],  d = R_h - R + h,
!>      x_c = (d^2 + R_h^2 - R^2) / (2 d)  (the common chord, from the hole centre),
!>   the tube's segment beyond the common chord less the hole's; it is flatter than the flat
!>   bar's for the same depth when R_h is close to R (a conforming scar).
!> The depth is V's inverse (V increases with h: bisection safeguarding Newton, to 1e-13 of the
!> radius). A depth beyond the wall thickness means the wall is worn through: the depth is then
!> reported as the wall thickness (the relations above hold for the solid section only).
module gapbeam_wear_geometry
   use gapbeam_kinds, only: dp, pi
   use gapbeam_flow_results, only: wear_depth_t
   implicit none
   private
   public :: segment_area, flat_bar_volume, drilled_hole_volume, scar_volume, scar_depth, &
      seconds_per_year, wear_depth_history

   real(dp), parameter :: seconds_per_year = 365.25_dp * 86400.0_dp   !! Julian year [s]

contains

   !> Area of the part of a disc of radius r beyond a chord at signed distance s from its
   !> centre (s = r: none; s = -r: the whole disc) [m^2].
   elemental real(dp) function segment_area(r, s) result(a)
      real(dp), intent(in) :: r     !! radius [m]
      real(dp), intent(in) :: s     !! distance of the chord from the centre [m]
      real(dp) :: c, half
      c = min(max(s, -r), r)
      half = sqrt(max((r - c) * (r + c), 0.0_dp))     ! half the chord
      a = r * r * atan2(half, c) - c * half
   end function segment_area

   !> Scar volume of a tube of radius r against a flat bar of land width b at depth h [m^3].
   elemental real(dp) function flat_bar_volume(h, r, b) result(v)
      real(dp), intent(in) :: h     !! depth [m], 0 <= h <= 2r
      real(dp), intent(in) :: r     !! tube outer radius [m]
      real(dp), intent(in) :: b     !! land width [m]
      v = b * segment_area(r, r - h)
   end function flat_bar_volume

   !> Scar volume of a tube of radius r in a drilled hole of radius rh > r through a plate of
   !> thickness t at depth h [m^3].
   elemental real(dp) function drilled_hole_volume(h, r, rh, t) result(v)
      real(dp), intent(in) :: h     !! depth [m], >= 0
      real(dp), intent(in) :: r     !! tube outer radius [m]
      real(dp), intent(in) :: rh    !! hole radius [m]
      real(dp), intent(in) :: t     !! plate thickness [m]
      real(dp) :: d, xc
      v = 0.0_dp
      if (h <= 0.0_dp) return
      d = rh - r + h
      xc = (d * d + (rh - r) * (rh + r)) / (2.0_dp * d)
      v = t * max(segment_area(r, xc - d) - segment_area(rh, xc), 0.0_dp)
   end function drilled_hole_volume

   !> Scar volume at depth h for a support geometry word ('flat_bar', 'drilled_hole') [m^3].
   elemental real(dp) function scar_volume(geometry, h, r, land_width, hole_radius, &
                                           plate_thickness) result(v)
      character(len=*), intent(in) :: geometry   !! 'flat_bar' or 'drilled_hole'
      real(dp), intent(in) :: h                  !! depth [m]
      real(dp), intent(in) :: r                  !! tube outer radius [m]
      real(dp), intent(in) :: land_width         !! flat bar: land width [m]
      real(dp), intent(in) :: hole_radius        !! drilled hole: its radius [m]
      real(dp), intent(in) :: plate_thickness    !! drilled hole: plate thickness [m]
      select case (geometry)
      case ('flat_bar')
         v = flat_bar_volume(h, r, land_width)
      case ('drilled_hole')
         v = drilled_hole_volume(h, r, hole_radius, plate_thickness)
      case default
         v = 0.0_dp
      end select
   end function scar_volume

   !> The depth whose scar holds the volume v, at most h_max (the wall thickness) [m].
   elemental real(dp) function scar_depth(geometry, v, r, land_width, hole_radius, &
                                          plate_thickness, h_max) result(h)
      character(len=*), intent(in) :: geometry   !! 'flat_bar' or 'drilled_hole'
      real(dp), intent(in) :: v                  !! volume [m^3]
      real(dp), intent(in) :: r                  !! tube outer radius [m]
      real(dp), intent(in) :: land_width, hole_radius, plate_thickness   !! geometry [m]
      real(dp), intent(in) :: h_max              !! largest depth reported [m]
      real(dp) :: lo, hi, f, fl, dv, step
      integer :: it
      h = 0.0_dp
      if (v <= 0.0_dp) return
      hi = h_max
      if (scar_volume(geometry, hi, r, land_width, hole_radius, plate_thickness) <= v) then
         h = hi
         return
      end if
      lo = 0.0_dp
      h = 0.5_dp * hi
      do it = 1, 200
         f = scar_volume(geometry, h, r, land_width, hole_radius, plate_thickness) - v
         if (f > 0.0_dp) then
            hi = h
         else
            lo = h
         end if
         if (hi - lo <= 1.0e-13_dp * r) exit
         ! Newton from h with a difference slope, kept inside (lo, hi)
         step = 1.0e-7_dp * max(h, 1.0e-9_dp * r)
         fl = scar_volume(geometry, h + step, r, land_width, hole_radius, plate_thickness) - v
         dv = (fl - f) / step
         if (dv > 0.0_dp) then
            h = h - f / dv
         else
            h = -1.0_dp
         end if
         if (h <= lo .or. h >= hi) h = 0.5_dp * (lo + hi)
      end do
   end function scar_depth

   !> The depth of each support's scar at n times from 0 to `years` under its stationary
   !> Archard volume rate (V(t) = V' t, the depth V's inverse), and the time at which the depth
   !> reaches `fraction` of the wall: V(fraction wall) / V' (+huge without wear or geometry).
   pure function wear_depth_history(support, volume_rate, r, land_width, hole_radius, &
                                    plate_thickness, wall, years, fraction, n) result(wd)
      character(len=*), intent(in) :: support(:)       !! per stop: geometry word
      real(dp), intent(in) :: volume_rate(:)           !! per stop: V' [m^3/s]
      real(dp), intent(in) :: r                        !! tube outer radius [m]
      real(dp), intent(in) :: land_width(:), hole_radius(:), plate_thickness(:)  !! [m]
      real(dp), intent(in) :: wall                     !! wall thickness [m]
      real(dp), intent(in) :: years                    !! operating time [a]
      real(dp), intent(in) :: fraction                 !! of the wall, for the time [-]
      integer, intent(in) :: n                         !! times, >= 2
      type(wear_depth_t) :: wd
      integer :: i, j, ns
      real(dp) :: v_frac
      ns = size(support)
      allocate(wd%time_years(n), wd%depth(n, ns), wd%years_to_fraction(ns))
      wd%time_years = [(years * real(i - 1, dp) / real(n - 1, dp), i = 1, n)]
      do j = 1, ns
         do i = 1, n
            wd%depth(i, j) = scar_depth(support(j), volume_rate(j) * wd%time_years(i) &
               * seconds_per_year, r, land_width(j), hole_radius(j), plate_thickness(j), wall)
         end do
         wd%years_to_fraction(j) = huge(1.0_dp)
         v_frac = scar_volume(support(j), fraction * wall, r, land_width(j), hole_radius(j), &
                              plate_thickness(j))
         if (volume_rate(j) > 0.0_dp .and. v_frac > 0.0_dp) &
            wd%years_to_fraction(j) = v_frac / volume_rate(j) / seconds_per_year
      end do
   end function wear_depth_history
end module gapbeam_wear_geometry
