!> The deck rules of &initial that tie its variables to each other and to the structure. The
!> ranges of single values are the deck table's (gapbeam_deck_table). Called by read_deck
!> (io/gapbeam_input) after the loads; for kind = 'file' the reader then reads the final state
!> of an earlier run (io/gapbeam_input_initial).
!>
!> Rigid-body fields (kind = 'rotation', 'translation') are velocity distributions: a field's
!> values at the dofs the supports fix are held by the supports (a hinge locked, a moving base
!> stopped at t = 0), which is sound for a velocity (the initial velocity of a beam needs no
!> boundary condition: it lies in L2). A rigid rotation angle is a displacement, which must
!> meet the supports: an angle that would turn a clamped root or move a supported tip is
!> refused.
module gapbeam_deck_rules_initial
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_description, only: rigid_planes
   implicit none
   private
   public :: check_initial, check_mechanism

contains

   !> The rules of &initial (for kind = 'file', io/gapbeam_input_initial then reads the file).
   subroutine check_initial(deck, err)
      type(deck_t), intent(in) :: deck                     !! deck
      type(error_t), allocatable, intent(inout) :: err     !! the first rule broken
      character(len=:), allocatable :: k
      if (allocated(err)) return
      associate (ini => deck%initial, planes => deck%structure%beam%planes)
         k = "group &initial: kind = '" // trim(ini%kind) // "'"
         call only_with(ini%angular_velocity, 'angular_velocity', 'rotation', ini%kind, err)
         call only_with(ini%angular_velocity_v, 'angular_velocity_v', 'rotation', ini%kind, err)
         call only_with(ini%angle, 'angle', 'rotation', ini%kind, err)
         call only_with(ini%angle_v, 'angle_v', 'rotation', ini%kind, err)
         call only_with(ini%translation_velocity, 'translation_velocity', 'translation', &
                        ini%kind, err)
         call only_with(ini%translation_velocity_v, 'translation_velocity_v', 'translation', &
                        ini%kind, err)
         if (allocated(err)) return
         if (len_trim(ini%initial_file) > 0 .and. ini%kind /= 'file') then
            call fatal_error(err, "group &initial: initial_file = '" // trim(ini%initial_file) &
               // "' is given with kind = '" // trim(ini%kind) // "': it needs kind = 'file'")
            return
         end if
         if (planes < 2) then
            call second_plane(ini%angular_velocity_v, 'angular_velocity_v', err)
            call second_plane(ini%angle_v, 'angle_v', err)
            call second_plane(ini%translation_velocity_v, 'translation_velocity_v', err)
            if (allocated(err)) return
         end if
         select case (ini%kind)
         case ('rotation', 'translation', 'file')
            if (size(ini%node) > 0) then
               call fatal_error(err, k // ' with ' // str(size(ini%node)) // ' node entries: ' &
                  // "the lists (node, dof, displacement, velocity) need kind = 'given'")
               return
            end if
         end select
         select case (ini%kind)
         case ('rotation')
            if (ini%angular_velocity == 0.0_dp .and. ini%angular_velocity_v == 0.0_dp .and. &
                ini%angle == 0.0_dp .and. ini%angle_v == 0.0_dp) then
               call fatal_error(err, k // ' with angular_velocity = angle = 0' &
                  // trim(merge(' (and their _v)', '               ', planes > 1)) &
                  // ': give a rate or an angle (kind = ''rest'' starts at rest)')
               return
            end if
            call check_angle(deck, ini%angle, 'angle', err)
            call check_angle(deck, ini%angle_v, 'angle_v', err)
         case ('translation')
            if (ini%translation_velocity == 0.0_dp .and. ini%translation_velocity_v == 0.0_dp) &
               call fatal_error(err, k // ' with translation_velocity = 0' &
               // trim(merge(' (and translation_velocity_v)', '                             ', &
               planes > 1)) // ': give a velocity (kind = ''rest'' starts at rest)')
         case ('file')
            if (len_trim(ini%initial_file) == 0) then
               call fatal_error(err, k // " needs initial_file (a transient run's .h5 file)")
               return
            end if
            if (deck%job%analysis == 'model_size') then
               call fatal_error(err, k // " with &job analysis = 'model_size': the meshes " &
                  // "compared cannot all start from one file's state (kind = 'rotation', " &
                  // "'translation' or 'given' can)")
               return
            end if
         end select
      end associate
   end subroutine check_initial

   !> A beam that is a mechanism (a pinned root, a free tip and no spring in a plane: the
   !> rigid rotation about the root in that plane, at zero frequency) is accepted when a stop
   !> holds every rigid mode: a stop whose dof moves in the mode (a translation at a node past
   !> the root, or a rotation; a circular clearance holds both planes). Otherwise refused.
   subroutine check_mechanism(deck, err)
      type(deck_t), intent(in) :: deck                     !! deck
      type(error_t), allocatable, intent(inout) :: err     !! a rigid mode no stop holds
      logical :: rigid(2), held(2)
      character(len=1), parameter :: plane_name(2) = ['w', 'v']
      integer :: p
      if (allocated(err)) return
      call rigid_planes(deck%structure, deck%stops, rigid, held)
      if (any(rigid) .and. deck%reduction%kind /= 'none') then
         call fatal_error(err, "group &reduction: kind = '" // trim(deck%reduction%kind) &
            // "' with a beam that is a mechanism (&root condition = 'pinned', a free tip, " &
            // 'no &springs): a modal model needs a structure without rigid modes (its ' &
            // "static modes solve K); use kind = 'none'")
         return
      end if
      if (any(rigid) .and. any(deck%stops%rule_factor > 0.0_dp .and. &
                               deck%stops%rule_f1_ratio > 0.0_dp)) then
         call fatal_error(err, 'group &stops: rule_f1_ratio with a beam that is a mechanism ' &
            // "(&root condition = 'pinned', a free tip, no &springs): its f1 with the stops " &
            // 'open is 0, so the ratio sets no target; give rule_f1_hz or stiffness')
         return
      end if
      do p = 1, 2
         if (.not. rigid(p) .or. held(p)) cycle
         call fatal_error(err, "group &root: condition = 'pinned' with a free tip and no " &
            // '&springs in the ' // plane_name(p) // ' plane is a mechanism (rigid rotation ' &
            // 'about the root) that no stop holds: add a stop in that plane (a flat stop at ' &
            // 'a node past the root, or a circular clearance), support the tip (&tip ' &
            // "condition = 'pinned', ...) or add springs")
         return
      end do
   end subroutine check_mechanism

   !> A variable of one kind given (non-zero) with another kind: refused.
   subroutine only_with(x, name, kind, given_kind, err)
      real(dp), intent(in) :: x                            !! its value
      character(len=*), intent(in) :: name, kind           !! variable, the kind it needs
      character(len=*), intent(in) :: given_kind           !! the deck's kind
      type(error_t), allocatable, intent(inout) :: err     !! refused
      if (allocated(err) .or. x == 0.0_dp .or. given_kind == kind) return
      call fatal_error(err, 'group &initial: ' // name // ' = ' // str(x) // " is given with " &
         // "kind = '" // trim(given_kind) // "': it needs kind = '" // kind // "'")
   end subroutine only_with

   !> A second-plane value with one plane: refused.
   subroutine second_plane(x, name, err)
      real(dp), intent(in) :: x                            !! its value
      character(len=*), intent(in) :: name                 !! variable
      type(error_t), allocatable, intent(inout) :: err     !! refused
      if (allocated(err) .or. x == 0.0_dp) return
      call fatal_error(err, 'group &initial: ' // name // ' = ' // str(x) // ' needs &beam ' &
         // 'planes = 2 (this deck has one plane)')
   end subroutine second_plane

   !> A rigid rotation angle (a displacement) must meet the supports: the root section turns
   !> (a clamped root fixes it) and the tip moves by angle L (a tip other than 'free' fixes
   !> its translation).
   subroutine check_angle(deck, angle, name, err)
      type(deck_t), intent(in) :: deck                     !! deck
      real(dp), intent(in) :: angle                        !! the angle [rad]
      character(len=*), intent(in) :: name                 !! 'angle' or 'angle_v'
      type(error_t), allocatable, intent(inout) :: err     !! refused
      character(len=:), allocatable :: what
      if (allocated(err) .or. angle == 0.0_dp) return
      what = 'group &initial: ' // name // ' = ' // str(angle) // " rad (kind = 'rotation') "
      if (deck%structure%root%condition == 'clamped') then
         call fatal_error(err, what // "turns the root section, which &root condition = " &
            // "'clamped' fixes; allowed: " // name // " = 0 with a clamped root (a rate, " &
            // 'angular_velocity, is allowed: a velocity field needs no support to move)')
      else if (deck%structure%tip%condition /= 'free') then
         call fatal_error(err, what // 'moves the tip by ' // str(angle &
            * deck%structure%beam%length) // " m, which &tip condition = '" &
            // trim(deck%structure%tip%condition) // "' fixes; allowed: " // name // ' = 0 ' &
            // "unless the tip is 'free'")
      end if
   end subroutine check_angle
end module gapbeam_deck_rules_initial
