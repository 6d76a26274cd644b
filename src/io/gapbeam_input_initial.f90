!> The deck rules of &initial that tie its variables to each other and to the structure, and
!> the start from a file: kind = 'file' reads the final state of an earlier transient run
!> (/final/u, /final/v, /final/time) into the deck, after checking that the file's structure
!> (/parameters: beam, ends, springs, masses; the full model) is the deck's. The ranges of
!> single values are the deck table's (core/gapbeam_deck_table). Called by read_deck after
!> the loads.
!>
!> Rigid-body fields (kind = 'rotation', 'translation') are velocity distributions: a field's
!> values at the dofs the supports fix are held by the supports (a hinge locked, a moving base
!> stopped at t = 0), which is sound for a velocity (the initial velocity of a beam needs no
!> boundary condition: it lies in L2). A rigid rotation angle is a displacement, which must
!> meet the supports: an angle that would turn a clamped root or move a supported tip is
!> refused.
module gapbeam_input_initial
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_settings, only: initial_state_t
   use gapbeam_parameters, only: parameter_set_t, run_parameters
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_description, only: rigid_planes
   implicit none
   private
   public :: check_initial, check_mechanism

   !> Relative difference above which a structure value of the file differs from the deck's.
   real(dp), parameter :: same_tolerance = 1.0e-12_dp

contains

   !> The rules of &initial; for kind = 'file' the file's final state read into the deck.
   subroutine check_initial(deck, err)
      type(deck_t), intent(inout) :: deck                  !! deck (file state added)
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
      if (deck%initial%kind == 'file' .and. .not. allocated(err)) call read_initial_file(deck, err)
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

   !> The final state of initial_file into the deck (file_u, file_v, file_time), after its
   !> structure is checked against the deck's.
   subroutine read_initial_file(deck, err)
      type(deck_t), intent(inout) :: deck                  !! deck
      type(error_t), allocatable, intent(inout) :: err     !! unreadable file, another model
      type(h5_reader_t) :: h5
      type(error_t), allocatable :: e
      character(len=:), allocatable :: file, what, reduction
      real(dp) :: t
      file = trim(deck%initial%initial_file)
      what = "group &initial: initial_file = '" // file // "'"
      call h5%open(file, e)
      if (allocated(e)) then
         call fatal_error(err, what // ': ' // e%message)
         return
      end if
      if (.not. h5%exists('/final/u') .or. .not. h5%exists('/final/v') .or. &
          .not. h5%exists('/final/time')) then
         call fatal_error(err, what // ' has no final state (/final/u, /final/v, /final/time): ' &
            // "a start from a file needs a file of analysis = 'transient'")
      else if (.not. h5%exists('/parameters/model/reduction')) then
         call fatal_error(err, what // ' has no /parameters: its model cannot be checked ' &
            // '(a file of an older gapbeam; run it again)')
      else
         call h5%read_text('/parameters/model/reduction', reduction, e)
         if (.not. allocated(e) .and. reduction /= 'none') call fatal_error(err, what &
            // " was run on a reduced model (&reduction kind = '" // reduction // "' in the " &
            // "file; its final state is in modal coordinates): a start from a file needs " &
            // "a file of the full model (kind = 'none'); this deck may then reduce")
         if (.not. allocated(err) .and. .not. allocated(e)) call same_structure(h5, deck, &
                                                                               what, err)
         if (.not. allocated(err) .and. .not. allocated(e)) then
            call h5%read('/final/u', deck%initial%file_u, e)
            if (.not. allocated(e)) call h5%read('/final/v', deck%initial%file_v, e)
            if (.not. allocated(e)) call h5%read('/final/time', t, e)
         end if
         if (allocated(e)) call fatal_error(err, what // ': ' // e%message)
      end if
      call h5%close()
      if (allocated(err)) return
      if (size(deck%initial%file_u) /= size(deck%initial%file_v)) then
         call fatal_error(err, what // ': /final/u and /final/v differ in length (' &
            // str(size(deck%initial%file_u)) // ', ' // str(size(deck%initial%file_v)) // ')')
         return
      end if
      if (size(deck%initial%file_u) /= full_dofs(deck)) then
         call fatal_error(err, what // ': /final/u has ' // str(size(deck%initial%file_u)) &
            // ' values in the file, and the model of this deck ' // str(full_dofs(deck)) &
            // ' dofs')
         return
      end if
      deck%initial%file_time = t
   end subroutine read_initial_file

   !> The dofs of the deck's full model: per plane 2 per node, less the root's translation
   !> (and rotation when clamped) and what the tip condition fixes.
   pure integer function full_dofs(deck) result(n)
      type(deck_t), intent(in) :: deck                     !! deck
      n = 2 * (deck%structure%beam%n_elem + 1) - 1
      if (deck%structure%root%condition == 'clamped') n = n - 1
      select case (deck%structure%tip%condition)
      case ('clamped')
         n = n - 2
      case ('pinned', 'spring')
         n = n - 1
      end select
      n = n * deck%structure%beam%planes
   end function full_dofs

   !> Every structure value of the deck's /parameters (beam, ends, springs, masses) equal in
   !> the file (to same_tolerance): the dofs mean the same and the state its energy. The
   !> stops, damping and forcing may differ (a start from a file continues a run with them
   !> changed).
   subroutine same_structure(h5, deck, what, err)
      type(h5_reader_t), intent(inout) :: h5               !! the open file
      type(deck_t), intent(in) :: deck                     !! deck
      character(len=*), intent(in) :: what                 !! the message's start
      type(error_t), allocatable, intent(inout) :: err     !! differs
      type(parameter_set_t) :: set
      type(error_t), allocatable :: e
      character(len=:), allocatable :: path, text, mine, theirs
      real(dp), allocatable :: x(:)
      integer :: k
      logical :: differ
      set = run_parameters(deck)
      do k = 1, size(set%items)
         associate (p => set%items(k))
            if (.not. structural(p%path)) cycle
            path = '/parameters/' // p%path
            differ = .false.
            if (.not. h5%exists(path)) then
               theirs = 'absent'
               differ = .true.
            else if (allocated(p%text)) then
               call h5%read_text(path, text, e)
               theirs = "'" // text // "'"
               mine = "'" // p%text // "'"
               differ = allocated(e)
               if (.not. differ) differ = text /= p%text
            else
               call read_values(h5, path, p%is_array, x, e)
               differ = allocated(e)
               if (.not. differ) differ = size(x) /= size(p%values)
               if (.not. differ) differ = any(abs(x - p%values) > same_tolerance &
                  * max(abs(x), abs(p%values)))
               theirs = values_text(x)
               mine = values_text(p%values)
            end if
            if (.not. allocated(mine)) mine = values_text(p%values)
            if (allocated(p%text)) mine = "'" // p%text // "'"
            if (differ) then
               call fatal_error(err, what // ' is of another structure: ' // path // ' = ' &
                  // theirs // ' in the file, ' // mine // ' in this deck (a start from a ' &
                  // 'file needs the same beam, ends, springs and masses; stops, damping and ' &
                  // 'forcing may differ)')
               return
            end if
            if (allocated(mine)) deallocate(mine)
         end associate
      end do
   end subroutine same_structure

   !> A /parameters path that describes the structure (what the dofs are and mean).
   pure logical function structural(path)
      character(len=*), intent(in) :: path                 !! under /parameters
      structural = index(path, 'beam/') == 1 .or. index(path, 'root/') == 1 .or. &
                   index(path, 'tip/') == 1 .or. index(path, 'springs/') == 1 .or. &
                   index(path, 'masses/') == 1
   end function structural

   !> A numeric dataset of the deck's /parameters, scalar or list (`list`), as a list.
   subroutine read_values(h5, path, list, x, e)
      type(h5_reader_t), intent(inout) :: h5               !! the open file
      character(len=*), intent(in) :: path                 !! dataset
      logical, intent(in) :: list                          !! a list, else a scalar
      real(dp), allocatable, intent(out) :: x(:)           !! its values
      type(error_t), allocatable, intent(out) :: e         !! unreadable
      real(dp) :: x0
      if (list) then
         call h5%read(path, x, e)
      else
         call h5%read(path, x0, e)
         x = [x0]
      end if
   end subroutine read_values

   !> Values as text: one value, or a comma-separated list.
   function values_text(x) result(t)
      real(dp), intent(in) :: x(:)
      character(len=:), allocatable :: t
      integer :: i
      t = ''
      do i = 1, size(x)
         if (i > 1) t = t // ', '
         t = t // str(x(i))
      end do
      if (size(x) == 0) t = '(none)'
   end function values_text
end module gapbeam_input_initial
