!> Two visitors of the deck table (gapbeam_deck_table): the check of every value against its
!> description (range, finiteness, words; the conditional "> 0 here" rules the table states),
!> and the names of the groups and their variables.
!>
!> `check_deck_values(deck, err)` gives the first value refused, as
!> "group &beam: length = -0.2: must be > 0 and finite" or
!> "group &stops: side(2) = 'up': allowed: 'positive', 'negative', 'both'". The rules that tie
!> variables together (a section given as a rectangle or in general, ring supports need two
!> planes, ...) are core/gapbeam_deck_rules' (and its companions'), checked after these.
module gapbeam_deck_check
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_deck_visitor, only: deck_visitor_t, deck_spec_t, spec_violation, &
      int_violation, word_position, kind_word
   use gapbeam_deck_table, only: walk_deck
   implicit none
   private
   public :: check_deck_values, deck_names_t, deck_names, group_variables

   !> The per-variable check.
   type, extends(deck_visitor_t) :: check_visitor_t
      type(error_t), allocatable :: err                !! the first value refused
   contains
      procedure :: on_real => check_real, on_int => check_int, on_text => check_text, &
         on_real_list => check_real_list, on_int_list => check_int_list, &
         on_text_list => check_text_list
   end type check_visitor_t

   !> The groups of the table and the variables of each, in order.
   type, extends(deck_visitor_t) :: deck_names_t
      character(len=:), allocatable :: groups          !! ' job beam ... ' (blanks around)
      character(len=16), allocatable :: names(:)       !! the groups, in order
      character(len=1024), allocatable :: variables(:) !! ' a b ' per group, as groups
      character(len=1024), allocatable :: indexed(:)   !! the list variables of each group
   contains
      procedure :: on_group => names_group, on_real => names_real, on_int => names_int, &
         on_logical => names_logical, on_text => names_text, on_code => names_code, &
         on_real_list => names_real_list, on_int_list => names_int_list, &
         on_text_list => names_text_list
   end type deck_names_t

contains

   !> The first value of `deck` its description refuses.
   subroutine check_deck_values(deck, err)
      type(deck_t), intent(inout) :: deck                !! deck, every value applied
      type(error_t), allocatable, intent(out) :: err     !! the first value refused
      type(check_visitor_t) :: v
      call walk_deck(v, deck)
      if (allocated(v%err)) call move_alloc(v%err, err)
   end subroutine check_deck_values

   !> 'name' or 'name(i)' in a list group.
   pure function label(v, s) result(t)
      class(deck_visitor_t), intent(in) :: v
      type(deck_spec_t), intent(in) :: s
      character(len=:), allocatable :: t
      t = trim(s%name)
      if (v%entry > 0) t = t // '(' // str(v%entry) // ')'
   end function label

   subroutine refuse(v, name, value, why)
      class(check_visitor_t), intent(inout) :: v
      character(len=*), intent(in) :: name, value, why
      call fatal_error(v%err, 'group &' // trim(v%group) // ': ' // name // ' = ' // value &
         // ': ' // why)
   end subroutine refuse

   subroutine check_real(self, s, x)
      class(check_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), intent(inout) :: x
      character(len=:), allocatable :: why
      if (allocated(self%err)) return
      why = spec_violation(s, x)
      if (len(why) > 0) call refuse(self, label(self, s), str(x), why)
   end subroutine check_real

   subroutine check_int(self, s, i)
      class(check_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: i
      character(len=:), allocatable :: why
      if (allocated(self%err)) return
      why = int_violation(s, i)
      if (len(why) > 0) call refuse(self, label(self, s), str(i), why)
   end subroutine check_int

   subroutine check_text(self, s, t)
      class(check_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), intent(inout) :: t
      if (allocated(self%err) .or. s%kind /= kind_word) return
      if (word_position(s%words, t) == 0) call refuse(self, label(self, s), "'" // trim(t) &
         // "'", 'allowed: ' // s%words)
   end subroutine check_text

   subroutine check_real_list(self, s, x)
      class(check_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), allocatable, intent(inout) :: x(:)
      character(len=:), allocatable :: why
      integer :: k
      if (allocated(self%err) .or. .not. allocated(x)) return
      do k = 1, size(x)
         why = spec_violation(s, x(k))
         if (len(why) > 0) then
            call refuse(self, trim(s%name) // '(' // str(k) // ')', str(x(k)), why)
            return
         end if
      end do
   end subroutine check_real_list

   subroutine check_int_list(self, s, i, default)
      class(check_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, allocatable, intent(inout) :: i(:)
      integer, intent(in) :: default(:)
      character(len=:), allocatable :: why
      integer :: k
      if (allocated(self%err) .or. .not. allocated(i)) return
      do k = 1, size(i)
         why = int_violation(s, i(k))
         if (len(why) > 0) then
            call refuse(self, trim(s%name) // '(' // str(k) // ')', str(i(k)), why)
            return
         end if
      end do
   end subroutine check_int_list

   subroutine check_text_list(self, s, w, default)
      class(check_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), allocatable, intent(inout) :: w(:)
      character(len=*), intent(in) :: default(:)
      integer :: k
      if (allocated(self%err) .or. .not. allocated(w)) return
      do k = 1, size(w)
         if (word_position(s%words, w(k)) == 0) then
            call refuse(self, trim(s%name) // '(' // str(k) // ')', "'" // trim(w(k)) // "'", &
               'allowed: ' // s%words)
            return
         end if
      end do
   end subroutine check_text_list

   ! ---------------------------------------------------------------- names

   !> The groups and variables of the table.
   function deck_names() result(v)
      type(deck_names_t) :: v
      type(deck_t) :: d
      v%describing = .true.
      v%groups = ' '
      allocate(v%names(0))
      allocate(v%variables(0), v%indexed(0))
      call walk_deck(v, d)
   end function deck_names

   !> The variables of `group` (' a b ', blanks around), '' if there is no such group.
   pure function group_variables(v, group, indexed) result(t)
      type(deck_names_t), intent(in) :: v
      character(len=*), intent(in) :: group
      logical, intent(in), optional :: indexed    !! only those that take an index
      character(len=:), allocatable :: t
      integer :: g
      t = ''
      g = findloc(v%names, group, dim=1)
      if (g == 0) return
      t = trim(v%variables(g)) // ' '
      if (present(indexed)) then
         if (indexed) t = trim(v%indexed(g)) // ' '
      end if
   end function group_variables

   subroutine names_group(self, name, meaning, list)
      class(deck_names_t), intent(inout) :: self
      character(len=*), intent(in) :: name, meaning
      logical, intent(in) :: list
      character(len=1024) :: blank
      blank = ' '
      self%groups = self%groups // name // ' '
      self%names = [character(len=16) :: self%names, name]
      self%variables = [character(len=1024) :: self%variables, blank]
      self%indexed = [character(len=1024) :: self%indexed, blank]
   end subroutine names_group

   subroutine add(self, s)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer :: g
      g = size(self%variables)
      if (index(self%variables(g) // ' ', ' ' // trim(s%name) // ' ') > 0) return
      self%variables(g) = trim(self%variables(g)) // ' ' // trim(s%name)
      if (s%list .or. self%entry > 0) self%indexed(g) = trim(self%indexed(g)) // ' ' // trim(s%name)
   end subroutine add

   subroutine names_real(self, s, x)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), intent(inout) :: x
      call add(self, s)
   end subroutine names_real

   subroutine names_int(self, s, i)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: i
      call add(self, s)
   end subroutine names_int

   subroutine names_logical(self, s, b)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      logical, intent(inout) :: b
      call add(self, s)
   end subroutine names_logical

   subroutine names_text(self, s, t)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), intent(inout) :: t
      call add(self, s)
   end subroutine names_text

   subroutine names_code(self, s, c)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: c
      call add(self, s)
   end subroutine names_code

   subroutine names_real_list(self, s, x)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), allocatable, intent(inout) :: x(:)
      call add(self, s)
   end subroutine names_real_list

   subroutine names_int_list(self, s, i, default)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, allocatable, intent(inout) :: i(:)
      integer, intent(in) :: default(:)
      call add(self, s)
   end subroutine names_int_list

   subroutine names_text_list(self, s, w, default)
      class(deck_names_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), allocatable, intent(inout) :: w(:)
      character(len=*), intent(in) :: default(:)
      call add(self, s)
   end subroutine names_text_list
end module gapbeam_deck_check
