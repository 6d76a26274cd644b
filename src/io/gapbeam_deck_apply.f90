!> The visitor that puts the values of a deck's sources (gapbeam_deck_text) into a deck_t, as
!> the deck table (core/gapbeam_deck_table) binds each variable to its component.
!>
!> Sources apply in order (the deck file, then each override): a later value wins, entry by
!> entry; a list given whole (`node = 4`, not `node(2) = 4`) replaces the earlier sources'
!> list whole. In a list group the entries are those `node` gives (from 1 on, without gaps);
!> an entry of another list beyond them is refused per source: beyond the node entries that
!> source gives, or beyond the deck's when it gives none (an override that shortens `node`
!> leaves the file's longer lists as they were). Every value is converted to its variable's
!> type here, with one-line messages naming the source, the line, the group and the variable:
!> a number that does not fit (1e309, an integer beyond 32 bits), a text too long for its
!> variable, a word where a number belongs.
module gapbeam_deck_apply
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck_text, only: source_t, value_t, value_number, value_logical, value_string, &
      lower
   use gapbeam_deck_visitor, only: deck_visitor_t, deck_spec_t, word_position
   implicit none
   private
   public :: apply_visitor_t, source_where

   !> The values of one variable in the current group, all sources merged.
   type :: merged_t
      integer :: n = 0                               !! highest entry given (0: not given)
      type(value_t), allocatable :: values(:)        !! entry values
      logical, allocatable :: given(:)               !! entry given
      integer, allocatable :: src(:), line(:)        !! where each entry was given
      logical :: indexed = .false.                   !! an entry assignment name(i) = ...
   end type merged_t

   !> Applies the sources' values.
   type, extends(deck_visitor_t) :: apply_visitor_t
      type(source_t), allocatable :: srcs(:)         !! parsed sources, in order
      type(error_t), allocatable :: err              !! the first value refused
      integer, allocatable :: at_group(:)            !! per source: the current group (0: none)
      integer, allocatable :: limit(:)               !! per source: entries its nodes give
      character(len=:), allocatable :: scalars       !! ' a b ': variables visited as such
      logical :: list_group = .false.                !! the current group is a list group
      integer :: n_entries = 0                       !! entries of the current list group
   contains
      procedure :: on_group => apply_group, on_end_group => apply_end_group, &
         on_entries => apply_entries, on_real => apply_real, on_int => apply_int, &
         on_logical => apply_logical, on_text => apply_text, on_code => apply_code, &
         on_real_list => apply_real_list, on_int_list => apply_int_list, &
         on_text_list => apply_text_list
   end type apply_visitor_t

contains

   !> 'line N: ' for the deck file, "override K '...': " for an override.
   pure function source_where(srcs, s, line) result(w)
      type(source_t), intent(in) :: srcs(:)          !! sources
      integer, intent(in) :: s                       !! source
      integer, intent(in) :: line                    !! line in it
      character(len=:), allocatable :: w
      if (srcs(s)%is_file) then
         w = 'line ' // str(line) // ': '
      else
         w = srcs(s)%label // ': '
      end if
   end function source_where

   subroutine apply_group(self, name, meaning, list)
      class(apply_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name, meaning
      logical, intent(in) :: list
      integer :: s, k
      if (.not. allocated(self%at_group)) allocate(self%at_group(size(self%srcs)), &
         self%limit(size(self%srcs)))
      self%at_group = 0;  self%limit = 0;  self%n_entries = 0
      self%list_group = list;  self%scalars = ' '
      do s = 1, size(self%srcs)
         do k = 1, size(self%srcs(s)%groups)
            if (self%srcs(s)%groups(k)%name == name) self%at_group(s) = k
         end do
      end do
   end subroutine apply_group

   !> The values of variable `name` in the current group, the sources merged in order.
   function merged(self, name) result(m)
      class(apply_visitor_t), intent(in) :: self
      character(len=*), intent(in) :: name
      type(merged_t) :: m
      integer :: s, k, j, first, top
      allocate(m%values(0), m%given(0), m%src(0), m%line(0))
      do s = 1, size(self%srcs)
         if (self%at_group(s) == 0) cycle
         associate (items => self%srcs(s)%groups(self%at_group(s))%items)
            do k = 1, size(items)      ! a list given whole replaces the earlier sources' list
               if (items(k)%name == name .and. items(k)%first == 0) m%given = .false.
            end do
            do k = 1, size(items)
               if (items(k)%name /= name) cycle
               first = max(items(k)%first, 1)
               if (items(k)%first > 0) m%indexed = .true.
               top = first + size(items(k)%values) - 1
               if (top > size(m%values)) call grow(m, top)
               do j = 1, size(items(k)%values)
                  m%values(first + j - 1) = items(k)%values(j)
                  m%given(first + j - 1) = .true.
                  m%src(first + j - 1) = s;  m%line(first + j - 1) = items(k)%line
               end do
            end do
         end associate
      end do
      m%n = findloc(m%given, .true., dim=1, back=.true.)
   contains
      subroutine grow(m, n)
         type(merged_t), intent(inout) :: m
         integer, intent(in) :: n
         type(value_t), allocatable :: v(:)
         integer :: old
         old = size(m%values)
         allocate(v(n))
         v(1:old) = m%values
         call move_alloc(v, m%values)
         m%given = [m%given, spread(.false., 1, n - old)]
         m%src = [m%src, spread(0, 1, n - old)]
         m%line = [m%line, spread(0, 1, n - old)]
      end subroutine grow
   end function merged

   !> Refuse: 'WHERE group &G: TEXT'.
   subroutine refuse(self, s, line, text)
      class(apply_visitor_t), intent(inout) :: self
      integer, intent(in) :: s, line
      character(len=*), intent(in) :: text
      call fatal_error(self%err, source_where(self%srcs, s, line) // 'group &' &
         // trim(self%group) // ': ' // text)
   end subroutine refuse

   !> The entries given from 1 on, at most max_entries (else an error).
   logical function entries_ok(self, m, name, max_entries)
      class(apply_visitor_t), intent(inout) :: self
      type(merged_t), intent(in) :: m
      character(len=*), intent(in) :: name
      integer, intent(in) :: max_entries
      integer :: i
      entries_ok = .false.
      do i = 1, m%n
         if (.not. m%given(i)) then
            call refuse(self, m%src(m%n), m%line(m%n), name // '(' // str(i) // ') is not ' &
               // 'given, but ' // name // '(' // str(m%n) // ') is: give the entries from 1 ' &
               // 'on, without gaps')
            return
         end if
      end do
      if (m%n > max_entries) then
         call refuse(self, m%src(m%n), m%line(m%n), name // ' has ' // str(m%n) &
            // ' entries: at most ' // str(max_entries))
         return
      end if
      entries_ok = .true.
   end function entries_ok

   !> The value of a scalar variable (or entry) of the current group; .false. if not given.
   logical function scalar_value(self, s, v, src, line, name)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      type(value_t), intent(out) :: v
      integer, intent(out) :: src, line
      character(len=:), allocatable, intent(out) :: name
      type(merged_t) :: m
      scalar_value = .false.
      name = trim(s%name)
      if (allocated(self%err)) return
      m = merged(self, trim(s%name))
      if (self%entry > 0) then
         name = name // '(' // str(self%entry) // ')'
         if (m%n < self%entry) return
         if (.not. m%given(self%entry)) return
         v = m%values(self%entry);  src = m%src(self%entry);  line = m%line(self%entry)
         scalar_value = .true.
         return
      end if
      self%scalars = self%scalars // trim(s%name) // ' '
      if (m%n == 0) return
      if (m%indexed .or. m%n > 1) then
         call refuse(self, m%src(m%n), m%line(m%n), name // ' takes one value, not a list ' &
            // '(' // str(m%n) // ' values or an entry index given)')
         return
      end if
      v = m%values(1);  src = m%src(1);  line = m%line(1)
      scalar_value = .true.
   end function scalar_value

   integer function apply_entries(self, current, max_entries) result(n)
      class(apply_visitor_t), intent(inout) :: self
      integer, intent(in) :: current, max_entries
      type(merged_t) :: m
      integer :: s, k
      n = 0
      if (allocated(self%err)) return
      m = merged(self, 'node')
      if (.not. entries_ok(self, m, 'node', max_entries)) return
      n = m%n
      self%n_entries = n
      ! the entries each source's node list gives (all the deck's when it gives none)
      do s = 1, size(self%srcs)
         self%limit(s) = n
         if (self%at_group(s) == 0) cycle
         associate (items => self%srcs(s)%groups(self%at_group(s))%items)
            do k = 1, size(items)
               if (items(k)%name == 'node') self%limit(s) = 0
            end do
            do k = 1, size(items)
               if (items(k)%name == 'node') self%limit(s) = max(self%limit(s), &
                  max(items(k)%first, 1) + size(items(k)%values) - 1)
            end do
         end associate
      end do
   end function apply_entries

   !> An entry of a per-node list beyond the node entries is refused (see the header).
   subroutine apply_end_group(self)
      class(apply_visitor_t), intent(inout) :: self
      integer :: s, k, top
      if (allocated(self%err) .or. .not. self%list_group) return
      do s = 1, size(self%srcs)
         if (self%at_group(s) == 0) cycle
         associate (items => self%srcs(s)%groups(self%at_group(s))%items)
            do k = 1, size(items)
               if (items(k)%name == 'node') cycle
               if (index(self%scalars, ' ' // items(k)%name // ' ') > 0) cycle
               top = max(items(k)%first, 1) + size(items(k)%values) - 1
               if (top > self%limit(s)) then
                  call refuse(self, s, items(k)%line, items(k)%name // ' has an entry beyond ' &
                     // 'the ' // str(self%limit(s)) // ' that node lists (one value per ' &
                     // 'node entry)')
                  return
               end if
            end do
         end associate
      end do
   end subroutine apply_end_group

   ! ---------------------------------------------------------------- conversions

   !> A number value as a real.
   subroutine to_real(self, v, src, line, name, x)
      class(apply_visitor_t), intent(inout) :: self
      type(value_t), intent(in) :: v
      integer, intent(in) :: src, line
      character(len=*), intent(in) :: name
      real(dp), intent(inout) :: x
      real(dp) :: y
      integer :: ios
      character(len=:), allocatable :: t
      if (v%kind /= value_number) then
         call refuse(self, src, line, name // ' = ' // shown(v) // ': cannot read the value ' &
            // 'of ' // name // ' (a number)')
         return
      end if
      read(v%text, *, iostat=ios) y
      t = lower(v%text)
      if (ios /= 0) then
         call refuse(self, src, line, name // ' = ' // v%text // ': cannot read the value of ' &
            // name // ' (a number)')
      else if (.not. ieee_is_finite(y) .and. index(t, 'inf') == 0 .and. index(t, 'nan') == 0) &
         then
         call refuse(self, src, line, name // ' = ' // v%text // ': the number overflows ' &
            // '(at most ' // str(huge(1.0_dp)) // ' in magnitude)')
      else
         x = y
      end if
   end subroutine to_real

   !> A number value as a 32-bit integer.
   subroutine to_int(self, v, src, line, name, i)
      class(apply_visitor_t), intent(inout) :: self
      type(value_t), intent(in) :: v
      integer, intent(in) :: src, line
      character(len=*), intent(in) :: name
      integer, intent(inout) :: i
      integer(int64) :: k
      integer :: ios, start
      ios = 1
      if (v%kind == value_number .and. len(v%text) > 0) then
         start = 1
         if (scan(v%text(1:1), '+-') > 0) start = 2
         if (len(v%text) >= start .and. len(v%text) - start < 18 .and. &
             verify(v%text(start:), '0123456789') == 0) read(v%text, *, iostat=ios) k
      end if
      if (ios /= 0 .and. v%kind == value_number .and. len(v%text) > 0) then
         if (verify(v%text, '+-0123456789') == 0) then
            call refuse(self, src, line, name // ' = ' // v%text // ': the integer ' &
               // 'overflows (at most ' // str(huge(1)) // ' in magnitude)')
            return
         end if
      end if
      if (ios /= 0) then
         call refuse(self, src, line, name // ' = ' // shown(v) // ': cannot read the value ' &
            // 'of ' // name // ' (a whole number)')
      else if (abs(k) > huge(1)) then
         call refuse(self, src, line, name // ' = ' // v%text // ': the integer overflows ' &
            // '(at most ' // str(huge(1)) // ' in magnitude)')
      else
         i = int(k)
      end if
   end subroutine to_int

   !> The value as written, for messages.
   pure function shown(v) result(t)
      type(value_t), intent(in) :: v
      character(len=:), allocatable :: t
      if (v%kind == value_string) then
         t = "'" // v%text // "'"
      else
         t = v%text
      end if
      if (len(t) > 60) t = t(1:60) // '...'
   end function shown

   !> A string value into a character variable of length `length`.
   subroutine to_text(self, v, src, line, name, length, t)
      class(apply_visitor_t), intent(inout) :: self
      type(value_t), intent(in) :: v
      integer, intent(in) :: src, line, length
      character(len=*), intent(in) :: name
      character(len=*), intent(inout) :: t
      if (v%kind /= value_string) then
         call refuse(self, src, line, name // ' = ' // shown(v) // ': cannot read the value ' &
            // 'of ' // name // " (a quoted text, e.g. 'word')")
      else if (len_trim(v%text) > length) then
         call refuse(self, src, line, name // ' is ' // str(len_trim(v%text)) // ' characters ' &
            // 'long: at most ' // str(length) // ' characters (value "' // shown(v) // '")')
      else
         t = v%text
      end if
   end subroutine to_text

   ! ---------------------------------------------------------------- the variables

   subroutine apply_real(self, s, x)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), intent(inout) :: x
      type(value_t) :: v
      integer :: src, line
      character(len=:), allocatable :: name
      if (scalar_value(self, s, v, src, line, name)) call to_real(self, v, src, line, name, x)
   end subroutine apply_real

   subroutine apply_int(self, s, i)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: i
      type(value_t) :: v
      integer :: src, line
      character(len=:), allocatable :: name
      if (scalar_value(self, s, v, src, line, name)) call to_int(self, v, src, line, name, i)
   end subroutine apply_int

   subroutine apply_logical(self, s, b)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      logical, intent(inout) :: b
      type(value_t) :: v
      integer :: src, line
      character(len=:), allocatable :: name
      if (.not. scalar_value(self, s, v, src, line, name)) return
      if (v%kind /= value_logical) then
         call refuse(self, src, line, name // ' = ' // shown(v) // ': cannot read the value ' &
            // 'of ' // name // ' (.true. or .false.)')
      else
         b = v%flag
      end if
   end subroutine apply_logical

   subroutine apply_text(self, s, t)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), intent(inout) :: t
      type(value_t) :: v
      integer :: src, line
      character(len=:), allocatable :: name
      if (scalar_value(self, s, v, src, line, name)) &
         call to_text(self, v, src, line, name, s%length, t)
   end subroutine apply_text

   subroutine apply_code(self, s, c)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: c
      type(value_t) :: v
      integer :: src, line
      character(len=:), allocatable :: name
      character(len=32) :: word
      if (.not. scalar_value(self, s, v, src, line, name)) return
      word = ''
      call to_text(self, v, src, line, name, len(word), word)
      if (allocated(self%err)) return
      if (word_position(s%words, word) == 0) then
         call refuse(self, src, line, name // " = '" // trim(word) // "': allowed: " // s%words)
      else
         c = word_position(s%words, word)
      end if
   end subroutine apply_code

   subroutine apply_real_list(self, s, x)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), allocatable, intent(inout) :: x(:)
      type(merged_t) :: m
      real(dp), allocatable :: y(:)
      integer :: k
      if (allocated(self%err)) return
      self%scalars = self%scalars // trim(s%name) // ' '
      m = merged(self, trim(s%name))
      if (m%n == 0) return
      if (.not. entries_ok(self, m, trim(s%name), s%max_entries)) return
      allocate(y(m%n))
      do k = 1, m%n
         call to_real(self, m%values(k), m%src(k), m%line(k), trim(s%name) // '(' // str(k) &
            // ')', y(k))
         if (allocated(self%err)) return
      end do
      call move_alloc(y, x)
   end subroutine apply_real_list

   subroutine apply_int_list(self, s, i, default)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, allocatable, intent(inout) :: i(:)
      integer, intent(in) :: default(:)
      type(merged_t) :: m
      integer, allocatable :: y(:)
      integer :: k
      if (allocated(self%err)) return
      self%scalars = self%scalars // trim(s%name) // ' '
      m = merged(self, trim(s%name))
      if (m%n == 0) then
         if (.not. allocated(i)) i = default
         return
      end if
      if (.not. entries_ok(self, m, trim(s%name), s%max_entries)) return
      allocate(y(m%n))
      do k = 1, m%n
         call to_int(self, m%values(k), m%src(k), m%line(k), trim(s%name) // '(' // str(k) &
            // ')', y(k))
         if (allocated(self%err)) return
      end do
      call move_alloc(y, i)
   end subroutine apply_int_list

   subroutine apply_text_list(self, s, w, default)
      class(apply_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), allocatable, intent(inout) :: w(:)
      character(len=*), intent(in) :: default(:)
      type(merged_t) :: m
      integer :: k
      if (allocated(self%err)) return
      self%scalars = self%scalars // trim(s%name) // ' '
      m = merged(self, trim(s%name))
      if (m%n == 0) then
         if (.not. allocated(w)) then
            allocate(w(size(default)))
            w = default
         end if
         return
      end if
      if (.not. entries_ok(self, m, trim(s%name), s%max_entries)) return
      if (allocated(w)) deallocate(w)
      allocate(w(m%n))
      do k = 1, m%n
         w(k) = ''
         call to_text(self, m%values(k), m%src(k), m%line(k), trim(s%name) // '(' // str(k) &
            // ')', s%length, w(k))
         if (allocated(self%err)) return
      end do
   end subroutine apply_text_list
end module gapbeam_deck_apply
