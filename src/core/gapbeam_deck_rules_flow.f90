!> The deck rules of the flow excitation (&flow, &turbulence, &wear and the support
!> geometry of &stops) that tie variables together; the ranges of single values are the deck
!> table's (gapbeam_deck_table). Called by read_deck (io/gapbeam_input) after the stops and the
!> loads. And the wear depth of a deck's supports over &wear years (deck_wear_depth), which
!> the transient writer and job take from the same geometry.
module gapbeam_deck_rules_flow
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_flow_results, only: wear_depth_t
   use gapbeam_wear_geometry, only: wear_depth_history
   use gapbeam_description, only: n_psd_nodes
   implicit none
   private
   public :: check_flow, deck_wear_depth

contains

   !> Does the deck ask for random excitation (a turbulence spectrum)?
   pure logical function flow_is_random(deck)
      type(deck_t), intent(in) :: deck   !! deck
      flow_is_random = deck%turbulence%spectrum /= 'none'
   end function flow_is_random

   !> The tube diameter of the wear depth: &wear's, else &flow's [m].
   pure real(dp) function wear_tube_diameter(deck) result(d)
      type(deck_t), intent(in) :: deck   !! deck
      d = deck%wear%tube_diameter
      if (d <= 0.0_dp) d = deck%flow%tube_diameter
   end function wear_tube_diameter

   !> The wear depth of each support over &wear years from its Archard volume rate [m^3/s],
   !> through the support geometry of &stops (needs &wear years > 0).
   pure function deck_wear_depth(deck, volume_rate) result(wd)
      type(deck_t), intent(in) :: deck          !! deck
      real(dp), intent(in) :: volume_rate(:)    !! per stop [m^3/s]
      type(wear_depth_t) :: wd
      character(len=16), allocatable :: support(:)
      real(dp), allocatable :: land(:), hole_radius(:), plate(:)
      support = deck%stops%support
      land = deck%stops%land_width
      hole_radius = 0.5_dp * deck%stops%hole_diameter
      plate = deck%stops%plate_thickness
      associate (w => deck%wear)
         wd = wear_depth_history(support, volume_rate, 0.5_dp * wear_tube_diameter(deck), &
            land, hole_radius, plate, w%wall_thickness, w%years, w%wall_fraction, &
            w%depth_points)
      end associate
   end function deck_wear_depth

   !> Every rule between the flow's variables (the first broken one in err).
   subroutine check_flow(deck, err)
      type(deck_t), intent(in) :: deck                 !! deck, single values checked
      type(error_t), allocatable, intent(inout) :: err !! first problem found
      if (allocated(err)) return
      call check_flow_group(deck, err);  if (allocated(err)) return
      call check_turbulence(deck, err);  if (allocated(err)) return
      call check_wear(deck, err);  if (allocated(err)) return
      call check_flow_analysis(deck, err)
   end subroutine check_flow

   !> A range [a, b] along the tube: both 0 (the whole tube), or 0 <= a < b <= length.
   subroutine check_range(group, va, vb, a, b, length, err)
      character(len=*), intent(in) :: group, va, vb    !! names for the message
      real(dp), intent(in) :: a, b, length             !! the range, the tube length [m]
      type(error_t), allocatable, intent(inout) :: err
      if (a == 0.0_dp .and. b == 0.0_dp) return
      if (.not. (a < b .and. b <= length)) call fatal_error(err, 'group &' // group // ': ' &
         // va // ' = ' // str(a) // ', ' // vb // ' = ' // str(b) // ': must satisfy ' // va &
         // ' < ' // vb // ' <= the beam length ' // str(length) // ' m (both 0: the whole tube)')
   end subroutine check_range

   !> A table (x, y): as many values of each, at least two, x strictly increasing.
   subroutine check_table(group, vx, vy, x, y, err)
      character(len=*), intent(in) :: group, vx, vy    !! names for the message
      real(dp), allocatable, intent(in) :: x(:), y(:)  !! the lists (unallocated: not given)
      type(error_t), allocatable, intent(inout) :: err
      integer :: nx, ny, i
      nx = 0;  ny = 0
      if (allocated(x)) nx = size(x)
      if (allocated(y)) ny = size(y)
      if (nx < 2 .or. nx /= ny) then
         call fatal_error(err, 'group &' // group // ': ' // vx // ' (' // str(nx) // ' values) ' &
            // 'and ' // vy // ' (' // str(ny) // ' values): give the same number of each, at ' &
            // 'least two')
         return
      end if
      do i = 2, nx
         if (.not. (x(i) > x(i - 1))) then
            call fatal_error(err, 'group &' // group // ': ' // vx // '(' // str(i) // ') = ' &
               // str(x(i)) // ': the values must increase (' // vx // '(' // str(i - 1) &
               // ') = ' // str(x(i - 1)) // ')')
            return
         end if
      end do
   end subroutine check_table

   subroutine check_flow_group(deck, err)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      associate (f => deck%flow, length => deck%structure%beam%length)
         call check_range('flow', 'region_start', 'region_end', f%region_start, f%region_end, &
                          length, err)
         if (allocated(err)) return
         if (allocated(f%profile_position) .or. allocated(f%profile_factor)) then
            call check_table('flow', 'profile_position', 'profile_factor', f%profile_position, &
                             f%profile_factor, err)
            if (allocated(err)) return
            if (f%profile_position(size(f%profile_position)) > length) call fatal_error(err, &
               'group &flow: profile_position(' // str(size(f%profile_position)) // ') = ' &
               // str(f%profile_position(size(f%profile_position))) // ': beyond the beam ' &
               // 'length ' // str(length) // ' m')
         end if
         if (f%planes == 'v' .and. deck%structure%beam%planes < 2) call fatal_error(err, &
            "group &flow: planes = 'v' needs &beam planes = 2")
      end associate
   end subroutine check_flow_group

   subroutine check_turbulence(deck, err)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      real(dp) :: first
      associate (t => deck%turbulence, f => deck%flow)
         select case (t%spectrum)
         case ('none')
            if (t%draws > 1) call fatal_error(err, 'group &turbulence: draws = ' &
               // str(t%draws) // " with spectrum = 'none': draws are random records of a " &
               // "turbulence spectrum ('table' or 'reduced')")
            if (t%draws_target_ci > 0.0_dp .or. n_psd_nodes(t) > 0) call fatal_error(err, &
               "group &turbulence: draws_target_ci and psd_nodes with spectrum = 'none': " &
               // "they are statistics of a turbulence spectrum ('table' or 'reduced')")
            return
         case ('table')
            call check_table('turbulence', 'psd_frequency_hz', 'psd', t%psd_frequency_hz, &
                             t%psd, err)
            if (allocated(err)) return
            first = t%psd_frequency_hz(1)
         case ('reduced')
            call check_table('turbulence', 'reduced_frequency', 'reduced_psd', &
                             t%reduced_frequency, t%reduced_psd, err)
            if (allocated(err)) return
            if (.not. (f%velocity > 0.0_dp .and. f%fluid_density > 0.0_dp .and. &
                       f%tube_diameter > 0.0_dp)) then
               call fatal_error(err, "group &turbulence: spectrum = 'reduced' needs &flow " &
                  // 'velocity, fluid_density and tube_diameter > 0 (got ' // str(f%velocity) &
                  // ' m/s, ' // str(f%fluid_density) // ' kg/m^3, ' // str(f%tube_diameter) &
                  // ' m)')
               return
            end if
            first = t%reduced_frequency(1) * f%velocity / f%tube_diameter
         end select
         if (t%cutoff_hz > 0.0_dp .and. t%cutoff_hz <= first) then
            call fatal_error(err, 'group &turbulence: cutoff_hz = ' // str(t%cutoff_hz) &
               // ': must be above the first frequency of the spectrum, ' // str(first) // ' Hz')
            return
         end if
         call check_range('turbulence', 'load_start', 'load_end', t%load_start, t%load_end, &
                          deck%structure%beam%length, err)
         if (allocated(err)) return
         if (t%planes == 'v' .and. deck%structure%beam%planes < 2) call fatal_error(err, &
            "group &turbulence: planes = 'v' needs &beam planes = 2")
         if (.not. allocated(err)) call check_draw_options(deck, err)
      end associate
   end subroutine check_turbulence

   !> The target half-width and the response PSD.
   subroutine check_draw_options(deck, err)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      integer :: i
      associate (t => deck%turbulence)
         if (t%draws_target_ci > 0.0_dp .and. t%draws < 2) then
            call fatal_error(err, 'group &turbulence: draws_target_ci = ' &
               // str(t%draws_target_ci) // ' with draws = ' // str(t%draws) // ': a ' &
               // 'half-width needs draws >= 2 to start from')
         else if (t%draws_target_ci > 0.0_dp .and. t%draws_max < t%draws) then
            call fatal_error(err, 'group &turbulence: draws_max = ' // str(t%draws_max) &
               // ': must be at least draws = ' // str(t%draws))
         else if (n_psd_nodes(t) > 0 .and. deck%job%analysis /= 'transient') then
            call fatal_error(err, 'group &turbulence: psd_nodes with analysis = ''' &
               // trim(deck%job%analysis) // "': the response PSD is written by analysis " &
               // "= 'transient'")
         end if
         if (allocated(err)) return
         do i = 1, n_psd_nodes(t)
            if (t%psd_nodes(i) > deck%structure%beam%n_elem + 1) then
               call fatal_error(err, 'group &turbulence: psd_nodes(' // str(i) // ') = ' &
                  // str(t%psd_nodes(i)) // ': the beam has nodes 1..' &
                  // str(deck%structure%beam%n_elem + 1))
               return
            end if
         end do
      end associate
   end subroutine check_draw_options

   subroutine check_wear(deck, err)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      real(dp) :: d
      integer :: i
      d = wear_tube_diameter(deck)
      associate (w => deck%wear)
         if (.not. (w%years > 0.0_dp)) return
         if (.not. (d > 0.0_dp)) then
            call fatal_error(err, 'group &wear: years = ' // str(w%years) // ' needs the ' &
               // 'tube diameter: &wear tube_diameter or &flow tube_diameter > 0')
            return
         end if
         if (.not. (w%wall_thickness < 0.5_dp * d)) then
            call fatal_error(err, 'group &wear: wall_thickness = ' // str(w%wall_thickness) &
               // ': must be below the tube radius ' // str(0.5_dp * d) // ' m')
            return
         end if
         if (all(deck%stops%support == 'none')) then
            call fatal_error(err, 'group &wear: years = ' // str(w%years) // ': no stop has ' &
               // "a support geometry; give &stops support = 'flat_bar' (with land_width) " &
               // "or 'drilled_hole' (with plate_thickness, hole_diameter)")
            return
         end if
         do i = 1, size(deck%stops)
            if (deck%stops(i)%support /= 'drilled_hole') cycle
            if (.not. (deck%stops(i)%hole_diameter > d)) then
               call fatal_error(err, 'group &stops: hole_diameter(' // str(i) // ') = ' &
                  // str(deck%stops(i)%hole_diameter) // ': must be above the tube diameter ' &
                  // str(d) // ' m')
               return
            end if
         end do
      end associate
   end subroutine check_wear

   !> The analyses that take flow excitation.
   subroutine check_flow_analysis(deck, err)
      type(deck_t), intent(in) :: deck
      type(error_t), allocatable, intent(inout) :: err
      logical :: flow
      flow = deck%turbulence%spectrum /= 'none' .or. (deck%flow%velocity > 0.0_dp .and. &
             deck%flow%fluid_elastic /= 'none')
      if (.not. flow) return
      select case (deck%job%analysis)
      case ('modes', 'calibrate', 'transient')
      case ('sweep')
      case default
         call fatal_error(err, "group &job: analysis = '" // trim(deck%job%analysis) &
            // "' does not take flow excitation (&flow velocity > 0 with fluid_elastic, or a " &
            // "&turbulence spectrum): use 'transient' or 'sweep' ('modes' prints the " &
            // 'critical velocities)')
      end select
   end subroutine check_flow_analysis
end module gapbeam_deck_rules_flow
