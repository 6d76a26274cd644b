!> `gapbeam --help-deck [GROUP]` and the tables of docs/decks.md, from the deck table
!> (gapbeam_deck_table): every variable with its unit, default (a default deck_t's value),
!> what is allowed and its meaning. Text only: the program prints it.
module gapbeam_deck_help
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_deck_visitor, only: deck_visitor_t, deck_spec_t, spec_allowed, number_text, &
      word_item
   use gapbeam_deck_table, only: walk_deck
   use gapbeam_deck_check, only: deck_names_t, deck_names
   implicit none
   private
   public :: deck_help, deck_table_begin, deck_table_end

   character(len=1), parameter :: nl = new_line('a')

   !> Writes the description of every variable of one group (or all) as text or markdown.
   type, extends(deck_visitor_t) :: help_visitor_t
      character(len=:), allocatable :: only       !! group wanted ('': all)
      logical :: markdown = .false.               !! the tables of docs/decks.md
      logical :: active = .false.                 !! in a group wanted
      character(len=:), allocatable :: out        !! the output
   contains
      procedure :: on_group => help_group, on_end_group => help_end_group, &
         on_real => help_real, on_int => help_int, on_logical => help_logical, &
         on_text => help_text, on_code => help_code, on_real_list => help_real_list, &
         on_int_list => help_int_list, on_text_list => help_text_list
   end type help_visitor_t

contains

   !> The help of group `group` ('' or 'all': every group), as text or markdown tables.
   subroutine deck_help(group, markdown, text, err)
      character(len=*), intent(in) :: group           !! group name, with or without '&'
      logical, intent(in) :: markdown                 !! docs/decks.md tables
      character(len=:), allocatable, intent(out) :: text   !! the help
      type(error_t), allocatable, intent(out) :: err  !! unknown group
      type(help_visitor_t) :: v
      type(deck_names_t) :: names
      type(deck_t) :: d
      v%only = trim(adjustl(group))
      if (len(v%only) > 0) then
         if (v%only(1:1) == '&') v%only = v%only(2:)
      end if
      if (v%only == 'all') v%only = ''
      if (len(v%only) > 0) then
         names = deck_names()
         if (index(names%groups, ' ' // v%only // ' ') == 0) then
            call fatal_error(err, "--help-deck: unknown group '" // group // "'; the groups: " &
               // trim(adjustl(names%groups)))
            return
         end if
      end if
      v%markdown = markdown;  v%describing = .true.;  v%out = ''
      if (.not. markdown) v%out = 'Deck variables: name = default [unit]; what is allowed; ' &
         // 'its meaning. Design variables can be' // nl // 'swept, mapped and continued by ' &
         // "name ('&stops gap(1)'). Lists: name = v1, v2, ... or name(i) = v (entry i)." // nl
      call walk_deck(v, d)
      text = v%out
   end subroutine deck_help

   !> The line that opens the generated table of a group in docs/decks.md.
   pure function deck_table_begin(group) result(t)
      character(len=*), intent(in) :: group
      character(len=:), allocatable :: t
      t = '<!-- deck table &' // group // ': made by `gapbeam --help-deck --markdown` from ' &
         // 'src/core/gapbeam_deck_table.f90; do not edit -->'
   end function deck_table_begin

   !> The line that closes it.
   pure function deck_table_end(group) result(t)
      character(len=*), intent(in) :: group
      character(len=:), allocatable :: t
      t = '<!-- end of deck table &' // group // ' -->'
   end function deck_table_end

   subroutine help_group(self, name, meaning, list)
      class(help_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name, meaning
      logical, intent(in) :: list
      self%active = len(self%only) == 0 .or. self%only == name
      if (.not. self%active) return
      if (self%markdown) then
         self%out = self%out // deck_table_begin(name) // nl &
            // '| variable | unit | default | allowed | meaning |' // nl &
            // '|---|---|---|---|---|' &
            // nl
      else
         self%out = self%out // nl // '&' // name // ': ' // meaning // nl
         if (list) self%out = self%out // '  (a list: one entry per node given; ' &
            // 'name(i) = v sets entry i)' // nl
      end if
   end subroutine help_group

   subroutine help_end_group(self)
      class(help_visitor_t), intent(inout) :: self
      if (self%active .and. self%markdown) self%out = self%out // deck_table_end(trim(self%group)) &
         // nl
      self%active = .false.
   end subroutine help_end_group

   !> One variable: its line(s) of help or its table row.
   subroutine add(self, s, default)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), intent(in) :: default
      character(len=:), allocatable :: def, meaning, unit
      if (.not. self%active) return
      def = default
      if (s%required) def = 'required'
      meaning = s%meaning
      if (s%design) meaning = meaning // ' (design variable)'
      unit = s%unit
      if (self%markdown) then
         if (unit == '' .or. unit == '1') unit = '–'
         self%out = self%out // '| `' // trim(s%name) // '` | ' // unit // ' | ' &
            // escaped(def) // ' | ' // escaped(spec_allowed(s)) // ' | ' // escaped(meaning) &
            // ' |' // nl
      else
         if (unit == '1') unit = ''
         if (len(unit) > 0) unit = ' [' // unit // ']'
         self%out = self%out // '  ' // trim(s%name) // ' = ' // def // unit // ';  ' &
            // spec_allowed(s) // nl // '      ' // meaning // nl
      end if
   contains
      !> '|' escaped for a markdown table cell.
      pure function escaped(t) result(u)
         character(len=*), intent(in) :: t
         character(len=:), allocatable :: u
         integer :: i
         u = ''
         do i = 1, len(t)
            if (t(i:i) == '|') then
               u = u // '\|'
            else
               u = u // t(i:i)
            end if
         end do
      end function escaped
   end subroutine add

   subroutine help_real(self, s, x)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), intent(inout) :: x
      call add(self, s, number_text(x))
   end subroutine help_real

   subroutine help_int(self, s, i)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: i
      call add(self, s, str(i))
   end subroutine help_int

   subroutine help_logical(self, s, b)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      logical, intent(inout) :: b
      call add(self, s, str(b))
   end subroutine help_logical

   subroutine help_text(self, s, t)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), intent(inout) :: t
      call add(self, s, "'" // trim(t) // "'")
   end subroutine help_text

   subroutine help_code(self, s, c)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: c
      call add(self, s, "'" // word_item(s%words, c) // "'")
   end subroutine help_code

   subroutine help_real_list(self, s, x)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), allocatable, intent(inout) :: x(:)
      call add(self, s, 'none')
   end subroutine help_real_list

   subroutine help_int_list(self, s, i, default)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, allocatable, intent(inout) :: i(:)
      integer, intent(in) :: default(:)
      character(len=:), allocatable :: t
      integer :: k
      t = ''
      do k = 1, size(default)
         if (k > 1) t = t // ', '
         t = t // str(default(k))
      end do
      if (size(default) == 0) t = 'none'
      call add(self, s, t)
   end subroutine help_int_list

   subroutine help_text_list(self, s, w, default)
      class(help_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), allocatable, intent(inout) :: w(:)
      character(len=*), intent(in) :: default(:)
      character(len=:), allocatable :: t
      integer :: k
      t = ''
      do k = 1, size(default)
         if (k > 1) t = t // ', '
         t = t // "'" // trim(default(k)) // "'"
      end do
      if (size(default) == 0) t = 'none'
      call add(self, s, t)
   end subroutine help_text_list
end module gapbeam_deck_help
