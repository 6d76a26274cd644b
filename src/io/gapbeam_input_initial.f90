!> The start from a file (&initial kind = 'file'): the final state of an earlier transient
!> run (/final/u, /final/v, /final/time) read into the deck, after checking that the file's
!> structure (/parameters: beam, ends, springs, masses; the full model) is the deck's. Called
!> by read_deck after the rules of &initial (core/gapbeam_deck_rules_initial).
module gapbeam_input_initial
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_parameters, only: parameter_set_t, run_parameters
   use gapbeam_hdf5_input, only: h5_reader_t
   implicit none
   private
   public :: read_initial_file

   !> Relative difference above which a structure value of the file differs from the deck's.
   real(dp), parameter :: same_tolerance = 1.0e-12_dp

contains

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
