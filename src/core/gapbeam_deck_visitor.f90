!> The visitor of the deck table (gapbeam_deck_table): every deck variable is declared once, by
!> one call of a `deck_visitor_t` method that both describes the variable (group, name, type,
!> unit, allowed range or words, a one-line meaning, whether it is a design variable, a note
!> for conditional rules) and binds it to its component of `deck_t`. Each job on the deck is a
!> visitor that extends this type and overrides the `on_*` methods it needs: apply the parsed
!> values (the reader), check every value against its description, print `--help-deck` and
!> the tables of docs/decks.md, get and set a design variable by name.
!>
!> The walk calls, per group: `begin_group(name, meaning)`, the variable calls, `end_group()`.
!> A list group (&springs, &stops, ...) asks `n = entries(current size)` and walks each entry
!> after `at(i)`; a describing visitor gets n = -1 and the walk visits one prototype entry (the
!> type's defaults) at entry 1. Nothing here reads or writes files.
module gapbeam_deck_visitor
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   implicit none
   private
   public :: deck_visitor_t, deck_spec_t, spec_violation, spec_allowed, word_item, word_position, &
      number_text, int_violation
   public :: kind_word, kind_text, kind_code

   integer, parameter :: kind_real = 1      !! a real [its unit]
   integer, parameter :: kind_int = 2       !! an integer
   integer, parameter :: kind_logical = 3   !! .true. or .false.
   integer, parameter :: kind_word = 4      !! one of a list of words, stored as the word
   integer, parameter :: kind_text = 5      !! any text (a title, a path, a variable's name)
   integer, parameter :: kind_code = 6      !! one of a list of words, stored as its position

   !> What the table says of one variable.
   type :: deck_spec_t
      character(len=32) :: name = ''                 !! variable name, lower case
      integer :: kind = 0                            !! kind_real, kind_int, ...
      logical :: list = .false.                      !! an array: name = v1, v2, ...
      integer :: max_entries = 1                     !! most entries of a list
      character(len=:), allocatable :: unit          !! unit of the value ('': none)
      real(dp) :: lo = -huge(1.0_dp)                 !! allowed: lo <= value (lo < if lo_open)
      real(dp) :: hi = huge(1.0_dp)                  !! allowed: value <= hi (< if hi_open)
      logical :: lo_open = .false.                   !! lo itself is not allowed
      logical :: hi_open = .false.                   !! hi itself is not allowed
      logical :: zero = .false.                      !! 0 is allowed besides [lo, hi]
      logical :: positive = .false.                  !! a conditional rule of this deck holds:
                                                     !! the value must be > 0
      character(len=:), allocatable :: words         !! allowed words, "'a', 'b'"
      character(len=:), allocatable :: meaning       !! one line
      character(len=:), allocatable :: note          !! conditional rules, in words
      character(len=:), allocatable :: why           !! said after a range message
      logical :: design = .false.                    !! settable by sweeps, maps, continuation
      logical :: required = .false.                  !! the default is a placeholder
      integer :: length = 0                          !! a text's most characters
   end type deck_spec_t

   !> The visitor the table calls; the `on_*` methods do nothing unless overridden.
   type :: deck_visitor_t
      character(len=16) :: group = ''        !! group being walked, lower case, no '&'
      integer :: entry = 0                   !! entry of a list group being walked (0: none)
      logical :: describing = .false.        !! list groups: one prototype entry, at entry 1
   contains
      procedure, non_overridable :: begin_group, end_group, entries, at
      procedure, non_overridable :: real => visit_real, int => visit_int
      procedure, non_overridable :: logical => visit_logical, word => visit_word
      procedure, non_overridable :: text => visit_text, code => visit_code
      procedure, non_overridable :: real_list => visit_real_list, int_list => visit_int_list
      procedure, non_overridable :: word_list => visit_word_list
      procedure :: on_group, on_end_group, on_entries, on_real, on_int, on_logical, on_text, &
         on_code, on_real_list, on_int_list, on_text_list
   end type deck_visitor_t

contains

   ! ---------------------------------------------------------------- the walk's calls

   !> A group starts.
   subroutine begin_group(self, name, meaning, list)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! group name, lower case
      character(len=*), intent(in) :: meaning        !! one line
      logical, intent(in), optional :: list          !! a list group (entries per node)
      logical :: is_list
      is_list = .false.
      if (present(list)) is_list = list
      self%group = name;  self%entry = 0
      call self%on_group(name, meaning, is_list)
   end subroutine begin_group

   !> The group ends.
   subroutine end_group(self)
      class(deck_visitor_t), intent(inout) :: self
      call self%on_end_group()
      self%group = '';  self%entry = 0
   end subroutine end_group

   !> Entries of the current list group, given its current size: -1 when describing.
   integer function entries(self, current, max_entries) result(n)
      class(deck_visitor_t), intent(inout) :: self
      integer, intent(in) :: current                 !! entries the deck holds now
      integer, intent(in) :: max_entries             !! most entries allowed
      if (self%describing) then
         n = -1
      else
         n = self%on_entries(current, max_entries)
      end if
   end function entries

   !> The next variable calls are of entry i of the list group (0: the group's scalars).
   subroutine at(self, i)
      class(deck_visitor_t), intent(inout) :: self
      integer, intent(in) :: i                       !! entry
      self%entry = i
   end subroutine at

   !> A real variable.
   subroutine visit_real(self, name, x, unit, lo, hi, lo_open, hi_open, zero, positive, &
                         meaning, note, why, design, required)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      real(dp), intent(inout) :: x                   !! its component
      character(len=*), intent(in), optional :: unit, meaning, note, why
      real(dp), intent(in), optional :: lo, hi
      logical, intent(in), optional :: lo_open, hi_open, zero, positive, design, required
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_real, unit, lo, hi, lo_open, hi_open, zero, positive, &
                     meaning, note, why, design, required)
      call self%on_real(s, x)
   end subroutine visit_real

   !> An integer variable.
   subroutine visit_int(self, name, i, lo, hi, zero, unit, meaning, note, why, required)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      integer, intent(inout) :: i                    !! its component
      integer, intent(in), optional :: lo, hi
      logical, intent(in), optional :: zero, required
      character(len=*), intent(in), optional :: unit, meaning, note, why
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_int, unit, zero=zero, meaning=meaning, note=note, why=why, &
                     required=required)
      if (present(lo)) then
         if (lo > -huge(1)) s%lo = real(lo, dp)    ! -huge(1), huge(1): no bound
      end if
      if (present(hi)) then
         if (hi < huge(1)) s%hi = real(hi, dp)
      end if
      call self%on_int(s, i)
   end subroutine visit_int

   !> A logical variable.
   subroutine visit_logical(self, name, b, meaning, note)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      logical, intent(inout) :: b                    !! its component
      character(len=*), intent(in), optional :: meaning, note
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_logical, meaning=meaning, note=note)
      call self%on_logical(s, b)
   end subroutine visit_logical

   !> A word out of `words` ("'a', 'b'"), stored as the word.
   subroutine visit_word(self, name, w, words, meaning, note)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      character(len=*), intent(inout) :: w           !! its component
      character(len=*), intent(in) :: words          !! allowed words
      character(len=*), intent(in), optional :: meaning, note
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_word, meaning=meaning, note=note)
      s%words = words;  s%length = len(w)
      call self%on_text(s, w)
   end subroutine visit_word

   !> Any text, at most len(t) characters.
   subroutine visit_text(self, name, t, meaning, note)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      character(len=*), intent(inout) :: t           !! its component
      character(len=*), intent(in), optional :: meaning, note
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_text, meaning=meaning, note=note)
      s%length = len(t)
      call self%on_text(s, t)
   end subroutine visit_text

   !> A word out of `words`, stored as its position in the list (dof codes).
   subroutine visit_code(self, name, c, words, meaning, note)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      integer, intent(inout) :: c                    !! its component: position in words
      character(len=*), intent(in) :: words          !! allowed words
      character(len=*), intent(in), optional :: meaning, note
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_code, meaning=meaning, note=note)
      s%words = words;  s%length = 8
      call self%on_code(s, c)
   end subroutine visit_code

   !> A list of reals (unallocated: not given).
   subroutine visit_real_list(self, name, x, max_entries, unit, lo, hi, lo_open, zero, &
                              meaning, note, design)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      real(dp), allocatable, intent(inout) :: x(:)   !! its component
      integer, intent(in) :: max_entries             !! most entries
      character(len=*), intent(in), optional :: unit, meaning, note
      real(dp), intent(in), optional :: lo, hi
      logical, intent(in), optional :: lo_open, zero
      logical, intent(in), optional :: design        !! each entry a design variable, name(i)
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_real, unit, lo, hi, lo_open, zero=zero, meaning=meaning, &
                     note=note)
      s%list = .true.;  s%max_entries = max_entries
      if (present(design)) s%design = design
      call self%on_real_list(s, x)
   end subroutine visit_real_list

   !> A list of integers; `default` when none is given.
   subroutine visit_int_list(self, name, i, max_entries, default, lo, hi, meaning, note)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name           !! variable name
      integer, allocatable, intent(inout) :: i(:)    !! its component
      integer, intent(in) :: max_entries             !! most entries
      integer, intent(in) :: default(:)              !! the list when none is given
      integer, intent(in), optional :: lo, hi
      character(len=*), intent(in), optional :: meaning, note
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_int, meaning=meaning, note=note)
      if (present(lo)) s%lo = real(lo, dp)
      if (present(hi)) s%hi = real(hi, dp)
      s%list = .true.;  s%max_entries = max_entries
      call self%on_int_list(s, i, default)
   end subroutine visit_int_list

   !> A list of words out of `words`; `default` when none is given.
   subroutine visit_word_list(self, name, w, max_entries, words, default, meaning, note)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name                     !! variable name
      character(len=*), allocatable, intent(inout) :: w(:)     !! its component
      integer, intent(in) :: max_entries                       !! most entries
      character(len=*), intent(in) :: words                    !! allowed words
      character(len=*), intent(in) :: default(:)               !! the list when none is given
      character(len=*), intent(in), optional :: meaning, note
      type(deck_spec_t) :: s
      call make_spec(s, name, kind_word, meaning=meaning, note=note)
      s%words = words;  s%length = len(w);  s%list = .true.;  s%max_entries = max_entries
      call self%on_text_list(s, w, default)
   end subroutine visit_word_list

   !> The description from the optional arguments of the calls above.
   subroutine make_spec(s, name, kind, unit, lo, hi, lo_open, hi_open, zero, positive, &
                        meaning, note, why, design, required)
      type(deck_spec_t), intent(out) :: s
      character(len=*), intent(in) :: name
      integer, intent(in) :: kind
      character(len=*), intent(in), optional :: unit, meaning, note, why
      real(dp), intent(in), optional :: lo, hi
      logical, intent(in), optional :: lo_open, hi_open, zero, positive, design, required
      s%name = name;  s%kind = kind
      s%unit = '';  s%words = '';  s%meaning = '';  s%note = '';  s%why = ''
      if (present(unit)) s%unit = unit
      if (present(lo)) s%lo = lo
      if (present(hi)) s%hi = hi
      if (present(lo_open)) s%lo_open = lo_open
      if (present(hi_open)) s%hi_open = hi_open
      if (present(zero)) s%zero = zero
      if (present(positive)) s%positive = positive
      if (present(meaning)) s%meaning = meaning
      if (present(note)) s%note = note
      if (present(why)) s%why = why
      if (present(design)) s%design = design
      if (present(required)) s%required = required
   end subroutine make_spec

   ! ---------------------------------------------------------------- default (no-op) methods

   subroutine on_group(self, name, meaning, list)
      class(deck_visitor_t), intent(inout) :: self
      character(len=*), intent(in) :: name, meaning
      logical, intent(in) :: list
   end subroutine on_group

   subroutine on_end_group(self)
      class(deck_visitor_t), intent(inout) :: self
   end subroutine on_end_group

   integer function on_entries(self, current, max_entries) result(n)
      class(deck_visitor_t), intent(inout) :: self
      integer, intent(in) :: current, max_entries
      n = current
   end function on_entries

   subroutine on_real(self, s, x)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), intent(inout) :: x
   end subroutine on_real

   subroutine on_int(self, s, i)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: i
   end subroutine on_int

   subroutine on_logical(self, s, b)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      logical, intent(inout) :: b
   end subroutine on_logical

   subroutine on_text(self, s, t)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), intent(inout) :: t
   end subroutine on_text

   subroutine on_code(self, s, c)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, intent(inout) :: c
   end subroutine on_code

   subroutine on_real_list(self, s, x)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), allocatable, intent(inout) :: x(:)
   end subroutine on_real_list

   subroutine on_int_list(self, s, i, default)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      integer, allocatable, intent(inout) :: i(:)
      integer, intent(in) :: default(:)
   end subroutine on_int_list

   subroutine on_text_list(self, s, w, default)
      class(deck_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      character(len=*), allocatable, intent(inout) :: w(:)
      character(len=*), intent(in) :: default(:)
   end subroutine on_text_list

   ! ---------------------------------------------------------------- what a spec allows

   !> Why a real value is refused ('' when it is allowed): 'must be > 0 and finite', ...
   pure function spec_violation(s, x) result(msg)
      type(deck_spec_t), intent(in) :: s             !! description
      real(dp), intent(in) :: x                      !! value
      character(len=:), allocatable :: msg
      logical :: ok
      msg = ''
      if (s%zero .and. x == 0.0_dp) return
      ok = ieee_is_finite(x)
      if (ok) ok = x > s%lo .or. (x == s%lo .and. .not. s%lo_open)
      if (ok) ok = x < s%hi .or. (x == s%hi .and. .not. s%hi_open)
      if (ok .and. s%positive) then
         if (.not. (x > 0.0_dp)) then
            msg = 'must be > 0 and finite'
            if (len(s%why) > 0) msg = msg // ' (' // s%why // ')'
         end if
         return
      end if
      if (ok) return
      msg = 'must be ' // range_text(s, .false.)
      if (len(s%why) > 0) msg = msg // ' (' // s%why // ')'
   end function spec_violation

   !> Why an integer value is refused ('' when it is allowed): 'must be in 1..10000', ...
   pure function int_violation(s, i) result(msg)
      type(deck_spec_t), intent(in) :: s             !! description
      integer, intent(in) :: i                       !! value
      character(len=:), allocatable :: msg
      msg = ''
      if (s%zero .and. i == 0) return
      if (real(i, dp) >= s%lo .and. real(i, dp) <= s%hi) return
      msg = 'must be ' // range_text(s, .false.)
      if (len(s%why) > 0) msg = msg // ' (' // s%why // ')'
   end function int_violation

   !> The range of a numeric description in words: '> 0 and finite', 'in [0.5, 1]',
   !> 'in 1..10000', '>= 1', '0 or in [1e-12, 0.5]'. `short`: without 'in' and 'finite'.
   pure function range_text(s, short) result(t)
      type(deck_spec_t), intent(in) :: s             !! description
      logical, intent(in) :: short                   !! for the help and the docs
      character(len=:), allocatable :: t
      character(len=:), allocatable :: lo, hi
      logical :: has_lo, has_hi
      has_lo = s%lo > -huge(1.0_dp);  has_hi = s%hi < huge(1.0_dp)
      if (s%kind == kind_int) then
         lo = '';  hi = ''
         if (has_lo) lo = str(int(s%lo))
         if (has_hi) hi = str(int(s%hi))
      else if (short) then                            ! messages: as str() writes numbers
         lo = number_text(s%lo);  hi = number_text(s%hi)
      else
         lo = str(s%lo);  hi = str(s%hi)
      end if
      if (s%kind == kind_int) then
         if (has_lo .and. has_hi) then
            t = lo // '..' // hi
            if (.not. short) t = 'in ' // t
         else if (has_lo) then
            t = '>= ' // lo
         else if (has_hi) then
            t = '<= ' // hi
         else
            t = 'any integer'
         end if
      else if (has_lo .and. has_hi .and. .not. (s%lo_open .or. s%hi_open) .and. &
               .not. (s%lo == 0.0_dp .and. s%hi == sqrt(huge(1.0_dp)))) then
         t = '[' // lo // ', ' // hi // ']'
         if (.not. short) t = 'in ' // t
      else if (has_lo .and. has_hi) then
         t = trim(merge('> ', '>=', s%lo_open)) // ' ' // lo // ' and ' &
            // trim(merge('< ', '<=', s%hi_open)) // ' ' // hi
      else if (has_lo) then
         t = trim(merge('> ', '>=', s%lo_open)) // ' ' // lo
         if (.not. short) t = t // ' and finite'
      else if (has_hi) then
         t = trim(merge('< ', '<=', s%hi_open)) // ' ' // hi
         if (.not. short) t = t // ' and finite'
      else
         t = 'finite'
      end if
      if (s%zero) t = '0 or ' // t
   end function range_text

   !> What a variable allows, for the help and the docs: the range or the words, and the note.
   pure function spec_allowed(s) result(t)
      type(deck_spec_t), intent(in) :: s             !! description
      character(len=:), allocatable :: t
      select case (s%kind)
      case (kind_real, kind_int)
         t = range_text(s, .true.)
         if (t == 'any integer' .and. len(s%note) > 0) then
            t = s%note
            return
         end if
      case (kind_logical)
         t = '.true., .false.'
      case (kind_word, kind_code)
         t = s%words
      case default
         t = 'text, at most ' // str(s%length) // ' characters'
      end select
      if (s%list .and. (s%kind == kind_word .or. s%kind == kind_code)) then
         t = 'up to ' // str(s%max_entries) // ' of ' // t
      else if (s%list .and. t == 'finite') then
         t = 'up to ' // str(s%max_entries) // ' values'
      else if (s%list) then
         t = 'up to ' // str(s%max_entries) // ' values, each ' // t
      end if
      if (len(s%note) > 0) t = t // '; ' // s%note
   end function spec_allowed

   !> A number as short as it reads back exactly (at most 4 significant digits otherwise):
   !> 1e-12, 0.5, 256, 1.341e154.
   pure function number_text(x) result(t)
      real(dp), intent(in) :: x                      !! value
      character(len=:), allocatable :: t
      character(len=40) :: buf
      real(dp) :: y
      integer :: d, e, ios, k
      if (x == 0.0_dp) then
         t = '0'
         return
      end if
      if (.not. ieee_is_finite(x)) then
         t = str(x)
         return
      end if
      if (abs(x) < 1.0e6_dp .and. x == aint(x)) then
         write(buf, '(i0)') nint(x, kind=8)
         t = trim(buf)
         return
      end if
      do d = 1, 17
         write(buf, '(es40.' // ndig(d - 1) // 'e3)') x
         read(buf, *, iostat=ios) y
         if (ios == 0 .and. y == x) exit
      end do
      if (d > 17) then                  ! never: 17 digits always read back
         d = 4
      else if (d > 9) then
         d = 4
      end if
      write(buf, '(es40.' // ndig(d - 1) // 'e3)') x
      buf = adjustl(buf)
      k = index(buf, 'E')
      read(buf(k + 1:), *) e
      t = buf(1:k - 1)
      if (e >= -3 .and. e <= 5) then   ! plain decimal
         write(buf, '(f40.' // ndig(max(0, d - 1 - e)) // ')') x
         t = trim(adjustl(buf))
         if (index(t, '.') > 0) then
            do while (t(len(t):len(t)) == '0')
               t = t(1:len(t) - 1)
            end do
            if (t(len(t):len(t)) == '.') t = t(1:len(t) - 1)
         end if
         if (t(1:1) == '.') t = '0' // t
         if (len(t) > 1) then
            if (t(1:2) == '-.') t = '-0' // t(2:)
         end if
      else
         if (index(t, '.') > 0) then
            do while (t(len(t):len(t)) == '0')
               t = t(1:len(t) - 1)
            end do
            if (t(len(t):len(t)) == '.') t = t(1:len(t) - 1)
         end if
         t = t // 'e' // trim(str_int(e))
      end if
   contains
      pure function ndig(n) result(s)
         integer, intent(in) :: n
         character(len=:), allocatable :: s
         s = trim(str_int(n))
      end function ndig
      pure function str_int(n) result(s)
         integer, intent(in) :: n
         character(len=12) :: s
         write(s, '(i0)') n
      end function str_int
   end function number_text

   ! ---------------------------------------------------------------- word lists

   !> Number of words in "'a', 'b', 'c'".
   pure integer function word_count(words) result(n)
      character(len=*), intent(in) :: words          !! quoted words, comma separated
      integer :: k
      n = 0
      do k = 1, len(words)
         if (words(k:k) == "'") n = n + 1
      end do
      n = n / 2
   end function word_count

   !> Word k of "'a', 'b', 'c'" (without quotes), '' when there is none.
   pure function word_item(words, k) result(w)
      character(len=*), intent(in) :: words          !! quoted words
      integer, intent(in) :: k                       !! position
      character(len=:), allocatable :: w
      integer :: i, j, q
      w = ''
      q = 0;  i = 0
      do j = 1, len(words)
         if (words(j:j) /= "'") cycle
         q = q + 1
         if (q == 2 * k - 1) i = j + 1
         if (q == 2 * k) then
            w = words(i:j - 1)
            return
         end if
      end do
   end function word_item

   !> Position of `word` in "'a', 'b'" (0: not there).
   pure integer function word_position(words, word) result(k)
      character(len=*), intent(in) :: words          !! quoted words
      character(len=*), intent(in) :: word           !! a word
      do k = 1, word_count(words)
         if (word_item(words, k) == trim(word) .and. len_trim(word) > 0) return
      end do
      k = 0
   end function word_position
end module gapbeam_deck_visitor
