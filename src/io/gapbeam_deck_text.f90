!> The text of namelist decks, read strictly: every character of a deck file or an override is
!> consumed by a group, an assignment, a value, a comment or a blank, or refused with a
!> message naming the line (deck file) and what was found.
!>
!> The syntax is Fortran namelist input as gapbeam's decks use it: a group opens with `&name`
!> (the name right after '&', then a blank or the end of the line) and closes with `/`; inside,
!> assignments `name = value, value ...` or `name(i) = value ...` (entries from i on), values
!> separated by commas or blanks and running over lines, `r*value` repeats, quoted strings
!> ('...' or "...", a doubled quote for one, on one line), logicals (.true., .false., t, f,
!> true, false, .t., .f.), numbers (Fortran forms, d or e exponents, NaN, Inf); `!` starts a
!> comment to the end of the line. Refused: text outside a group (between groups or after a
!> closing '/'), characters around a group name (`&forcing.`, `& forcing`, `&-tops`), a group
!> that runs into the next one, an unknown character where a name or a value belongs, a lone
!> sign, an empty value (`x = ,`, `x = 1, , 2`, `3*`: namelist input would keep the old value
!> silently), array sections, and a variable or list entry assigned twice in one group.
!> What the values mean (types, ranges) is for the reader (gapbeam_input) to decide.
module gapbeam_deck_text
   use gapbeam_error, only: error_t, fatal_error, str
   implicit none
   private
   public :: source_t, value_t, load_file, make_source, parse_source, lower, basename_stem, &
      given_list
   public :: value_number, value_logical, value_string

   integer, parameter :: value_number = 1    !! a number (integer or real syntax, NaN, Inf)
   integer, parameter :: value_logical = 2   !! .true. or .false.
   integer, parameter :: value_string = 3    !! a quoted string (quotes removed)
   integer, parameter :: max_repeat = 100000 !! largest repeat count r of r*value
   !> Bounds that keep reading a deck cheap whatever its text (a deck of inputs/ has a few kB
   !> and at most 20 groups, 12 assignments in a group and 50 values; the longest list gapbeam
   !> reads, &initial of its largest model, has 4 x 40004 values):
   integer, parameter :: max_deck_bytes = 8 * 1024 * 1024   !! largest deck file [bytes]
   integer, parameter :: max_values = 250000       !! most values in one source (repeats counted)
   integer, parameter :: max_items = 10000         !! most assignments in one group
   integer, parameter :: max_groups = 1000         !! most groups in one source

   !> One value of an assignment.
   type :: value_t
      integer :: kind = 0                             !! value_number, ...
      character(len=:), allocatable :: text           !! as written (strings: the contents)
      logical :: flag = .false.                       !! a logical's value
   end type value_t

   !> One assignment: name [ (first) ] = values.
   type :: assignment_t
      character(len=:), allocatable :: name           !! variable, lower case
      integer :: first = 0                            !! entry given (0: the whole variable)
      integer :: line = 0                             !! line of the name
      character(len=:), allocatable :: written        !! as written, on one line (messages)
      type(value_t), allocatable :: values(:)         !! the values, repeats expanded
   end type assignment_t

   !> One group of a source.
   type :: group_text_t
      character(len=:), allocatable :: name           !! lower case
      integer :: line = 0                             !! line of '&name'
      type(assignment_t), allocatable :: items(:)     !! in order
   end type group_text_t

   !> One source of namelist text: the deck file or an override.
   type :: source_t
      character(len=:), allocatable :: label          !! 'deck.nml' or "override 2 '...'"
      character(len=:), allocatable :: text           !! LF line ends
      logical :: is_file = .true.                     !! messages name lines of files only
      type(group_text_t), allocatable :: groups(:)    !! after parse_source
   end type source_t

   !> Where the scanner is.
   type :: cursor_t
      character(len=:), allocatable :: t              !! the text
      integer :: p = 1                                !! next character
      integer :: line = 1                             !! its line
      logical :: is_file = .true.                     !! name lines in messages
      integer :: n_values = 0                         !! values read so far (max_values)
   end type cursor_t

   character(len=1), parameter :: lf = achar(10), tab = achar(9)

contains

   !> Lower-case copy of a string.
   pure function lower(s) result(t)
      character(len=*), intent(in) :: s   !! text
      character(len=len(s)) :: t
      integer :: i, c
      t = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) t(i:i) = achar(c + 32)
      end do
   end function lower

   !> File name without directory and extension ('inputs/a.nml' -> 'a').
   pure function basename_stem(path) result(stem)
      character(len=*), intent(in) :: path   !! path
      character(len=:), allocatable :: stem
      integer :: i, j
      i = index(path, '/', back=.true.)
      stem = path(i + 1:)
      j = index(stem, '.', back=.true.)
      if (j > 1) stem = stem(1:j - 1)
   end function basename_stem

   !> A source from a text (any line ends; a UTF-8 byte-order mark first is dropped).
   pure subroutine make_source(label, text, is_file, src)
      character(len=*), intent(in) :: label     !! for messages
      character(len=*), intent(in) :: text      !! the text
      logical, intent(in) :: is_file            !! the deck file (messages name its lines)
      type(source_t), intent(out) :: src        !! result
      src%label = label
      src%is_file = is_file
      src%text = unix_line_ends(text)
      if (len(src%text) >= 3) then
         if (src%text(1:3) == char(239) // char(187) // char(191)) src%text = src%text(4:)
      end if
   end subroutine make_source

   !> Read a whole text file.
   subroutine load_file(path, text, err)
      character(len=*), intent(in) :: path                !! file path
      character(len=:), allocatable, intent(out) :: text  !! its contents
      type(error_t), allocatable, intent(out) :: err      !! set if it cannot be read
      integer :: unit, ios, fsize
      character(len=256) :: msg
      logical :: exists
      inquire(file=path, exist=exists)
      if (.not. exists) then
         call fatal_error(err, path // ': cannot open the deck file: no such file')
         return
      end if
      open(newunit=unit, file=path, access='stream', form='unformatted', status='old', &
           action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(err, path // ': cannot open the deck file: ' // trim(msg))
         return
      end if
      inquire(unit=unit, size=fsize)
      if (fsize > max_deck_bytes) then
         close(unit)
         call fatal_error(err, path // ': the deck file has ' // str(fsize) // ' bytes, more ' &
            // 'than a deck may have (' // str(max_deck_bytes) // ' bytes, 8 MiB; a deck of ' &
            // 'inputs/ has a few kB): is it a deck?')
         return
      end if
      allocate(character(len=max(fsize, 0)) :: text)
      if (fsize > 0) read(unit, iostat=ios, iomsg=msg) text
      close(unit)
      if (ios /= 0) call fatal_error(err, path // ': cannot read the deck file: ' // trim(msg))
   end subroutine load_file

   !> Text with every line end as LF: CRLF (DOS) becomes LF, then a lone CR (old Mac) too.
   pure function unix_line_ends(s) result(t)
      character(len=*), intent(in) :: s   !! text with any line ends
      character(len=:), allocatable :: t
      character(len=1), parameter :: cr = achar(13)
      integer :: i, k
      allocate(character(len=len(s)) :: t)
      k = 0
      do i = 1, len(s)
         if (s(i:i) == cr) then
            if (i < len(s)) then
               if (s(i + 1:i + 1) == lf) cycle     ! CR of CRLF: the LF follows
            end if
            k = k + 1;  t(k:k) = lf
         else
            k = k + 1;  t(k:k) = s(i:i)
         end if
      end do
      t = t(1:k)
   end function unix_line_ends

   !> The groups and variables the sources name, ' group group:variable ... ' (the deck rules'
   !> `given`, core/gapbeam_deck_rules: is_given).
   pure function given_list(srcs) result(t)
      type(source_t), intent(in) :: srcs(:)            !! parsed sources
      character(len=:), allocatable :: t
      integer :: s, i, k
      t = ' '
      do s = 1, size(srcs)
         do i = 1, size(srcs(s)%groups)
            associate (g => srcs(s)%groups(i))
               t = t // g%name // ' '
               do k = 1, size(g%items)
                  t = t // g%name // ':' // g%items(k)%name // ' '
               end do
            end associate
         end do
      end do
   end function given_list

   ! ---------------------------------------------------------------- the scanner

   !> Split a source into its groups and assignments, refusing what is not namelist text.
   subroutine parse_source(src, err)
      type(source_t), intent(inout) :: src              !! its groups are set
      type(error_t), allocatable, intent(out) :: err    !! the first text refused
      type(cursor_t) :: c
      type(group_text_t) :: g
      character(len=:), allocatable :: closed
      integer :: closed_line
      c%t = src%text;  c%is_file = src%is_file
      allocate(src%groups(0))
      if (len(c%t) > max_deck_bytes) then
         call fatal_error(err, 'the text has ' // str(len(c%t)) // ' bytes, more than a deck ' &
            // 'may have (' // str(max_deck_bytes) // ')')
         return
      end if
      closed = '';  closed_line = 0
      do
         call skip_space(c)
         if (c%p > len(c%t)) exit
         if (c%t(c%p:c%p) == '&') then
            if (size(src%groups) >= max_groups) then
               call fatal_error(err, at(c) // 'more than ' // str(max_groups) // ' groups: ' &
                  // 'a deck has one of each group')
               return
            end if
            call parse_group(c, closed, g, err)
            if (allocated(err)) return
            src%groups = [src%groups, g]
            closed = g%name;  closed_line = c%line
         else if (len(closed) > 0 .and. closed_line == c%line) then
            call fatal_error(err, at(c) // "text after the '/' that closes group &" // closed &
               // ": '" // rest_of_line(c) // "' (a group ends at its '/'; a comment " &
               // "starts with '!')")
            return
         else
            call fatal_error(err, at(c) // "text outside a group" // after(closed) // ": '" &
               // rest_of_line(c) // "' (a group starts with &name, a comment with '!')")
            return
         end if
      end do
   end subroutine parse_source

   !> ' (after group &name)', or '' before the first group.
   pure function after(closed) result(t)
      character(len=*), intent(in) :: closed
      character(len=:), allocatable :: t
      t = ''
      if (len(closed) > 0) t = ' (after group &' // closed // ')'
   end function after

   !> '&name ... /' at the cursor; `closed` names the group before it ('' for none).
   subroutine parse_group(c, closed, g, err)
      type(cursor_t), intent(inout) :: c
      character(len=*), intent(in) :: closed
      type(group_text_t), intent(out) :: g
      type(error_t), allocatable, intent(inout) :: err
      type(assignment_t) :: item
      character(len=1) :: ch
      integer :: k, n_items
      g%line = c%line
      c%p = c%p + 1
      if (.not. is_letter(peek(c))) then
         call fatal_error(err, at(c) // "'" // group_token(c) // "': '&' must be followed " &
            // 'directly by a group name' // after(closed) // meant(c))
         return
      end if
      g%name = lower(read_name(c))
      ch = peek(c)
      if (.not. (ch == ' ' .or. ch == tab .or. ch == lf .or. ch == '/' .or. &
                 c%p > len(c%t))) then
         c%p = c%p - len(g%name)
         call fatal_error(err, at(c) // "'" // group_token(c) // "': a group name must be " &
            // 'followed by a blank or the end of the line')
         return
      end if
      allocate(g%items(8))
      n_items = 0
      do
         call skip_space(c)
         if (c%p > len(c%t)) then
            call fatal_error(err, 'group &' // g%name // opened(c, g%line) // " is not " &
               // "closed: no '/' before the end of the " &
               // trim(merge('deck file', 'override ', c%is_file)))
            return
         end if
         ch = peek(c)
         if (ch == '/') then
            c%p = c%p + 1
            g%items = g%items(1:n_items)
            exit
         else if (ch == '&') then
            c%p = c%p + 1
            if (c%is_file) then
               call fatal_error(err, 'group &' // g%name // opened(c, g%line) // " is not " &
                  // "closed: no '/' before &" // lower(read_name(c)) // ' at line ' &
                  // str(c%line))
            else
               call fatal_error(err, 'group &' // g%name // " is not closed: no '/' before &" &
                  // lower(read_name(c)))
            end if
            return
         else if (is_letter(ch)) then
            if (n_items >= max_items) then
               call fatal_error(err, at(c) // 'group &' // g%name // ': more than ' &
                  // str(max_items) // ' assignments (give a list: name = v1, v2, ...)')
               return
            end if
            call parse_assignment(c, g%name, item, err)
            if (allocated(err)) return
            do k = 1, n_items
               if (overlap(g%items(k), item)) then
                  call fatal_error(err, at(c, item%line) // 'group &' // g%name // ': ' &
                     // trim(item%name) // ' is assigned twice (' // trim(g%items(k)%written) &
                     // '; ' // trim(item%written) // '): give each variable or list entry ' &
                     // 'once per group')
                  return
               end if
            end do
            if (n_items == size(g%items)) call grow_items(g%items)
            n_items = n_items + 1
            g%items(n_items) = item
         else
            call fatal_error(err, at(c) // 'group &' // g%name // ": '" // rest_of_line(c) &
               // "': a variable name expected (an assignment reads name = value)")
            return
         end if
      end do
   end subroutine parse_group

   !> ' (line 7)': the line where a group opened, in a deck file's messages.
   pure function opened(c, line) result(t)
      type(cursor_t), intent(in) :: c                 !! cursor (is_file)
      integer, intent(in) :: line                     !! line of '&name'
      character(len=:), allocatable :: t
      t = ''
      if (c%is_file) t = ' (line ' // str(line) // ')'
   end function opened

   !> Twice the room for assignments, the first kept.
   pure subroutine grow_items(items)
      type(assignment_t), allocatable, intent(inout) :: items(:)   !! list
      type(assignment_t), allocatable :: more(:)
      allocate(more(2 * size(items)))
      more(1:size(items)) = items
      call move_alloc(more, items)
   end subroutine grow_items

   !> Twice the room for values, the first kept.
   pure subroutine grow_values(values)
      type(value_t), allocatable, intent(inout) :: values(:)       !! list
      type(value_t), allocatable :: more(:)
      allocate(more(2 * size(values)))
      more(1:size(values)) = values
      call move_alloc(more, values)
   end subroutine grow_values

   !> 'name [ (i) ] = values' at the cursor.
   subroutine parse_assignment(c, group, a, err)
      type(cursor_t), intent(inout) :: c
      character(len=*), intent(in) :: group
      type(assignment_t), intent(out) :: a
      type(error_t), allocatable, intent(inout) :: err
      integer :: start, last, ios, n
      character(len=:), allocatable :: digits_text
      logical :: after_comma
      start = c%p;  a%line = c%line
      a%name = lower(read_name(c))
      call skip_blanks(c)
      if (peek(c) == '(') then
         c%p = c%p + 1
         call skip_blanks(c)
         digits_text = ''
         do while (is_digit(peek(c)) .and. len(digits_text) < 9)
            digits_text = digits_text // peek(c);  c%p = c%p + 1
         end do
         call skip_blanks(c)
         ios = 1
         if (len(digits_text) > 0) read(digits_text, *, iostat=ios) a%first
         if (peek(c) == ':') then
            call fatal_error(err, at(c) // 'group &' // group // ': ' // a%name // "(...:...): " &
               // 'array sections are not read; give ' // a%name // '(i) = v1, v2, ... (from ' &
               // 'entry i on)')
            return
         else if (ios /= 0 .or. a%first < 1 .or. peek(c) /= ')') then
            call fatal_error(err, at(c) // 'group &' // group // ": '" // a%name // '(' &
               // rest_of_line(c) // "': an entry index is a whole number >= 1, e.g. " &
               // a%name // '(2)')
            return
         end if
         c%p = c%p + 1
         call skip_blanks(c)
      end if
      if (peek(c) /= '=') then
         call fatal_error(err, at(c) // 'group &' // group // ": '" // a%name // ' ' &
            // rest_of_line(c) // "': '=' expected after the variable name")
         return
      end if
      c%p = c%p + 1
      allocate(a%values(8))
      n = 0
      after_comma = .true.;  last = c%p - 1
      do
         call skip_space(c)
         if (c%p > len(c%t)) exit
         if (scan(peek(c), '/&') > 0) exit
         if (peek(c) == ',') then
            if (after_comma) exit                     ! an empty value: refused below
            after_comma = .true.;  c%p = c%p + 1
            cycle
         end if
         if (is_letter(peek(c)) .and. assignment_follows(c)) exit
         call parse_value(c, group, a, n, err)
         if (allocated(err)) return
         after_comma = .false.;  last = c%p - 1
      end do
      a%values = a%values(1:n)
      a%written = one_line(c%t(start:max(last, start)))
      if (size(a%values) == 0 .or. (after_comma .and. peek(c) == ',')) then
         call fatal_error(err, at(c, a%line) // 'group &' // group // ': "' // a%written &
            // '": no value for ' // a%name // ' (an empty value would keep the default ' &
            // 'silently: give a value or leave ' // a%name // ' out)')
      end if
   end subroutine parse_assignment

   !> One value (or r*value) at the cursor, appended to a%values(1:n) (n counts them).
   subroutine parse_value(c, group, a, n, err)
      type(cursor_t), intent(inout) :: c
      character(len=*), intent(in) :: group
      type(assignment_t), intent(inout) :: a
      integer, intent(inout) :: n
      type(error_t), allocatable, intent(inout) :: err
      type(value_t) :: v
      character(len=:), allocatable :: tok
      integer :: r, star, ios, k
      r = 1
      if (scan(peek(c), '''"') > 0) then
         call parse_string(c, group, a%name, v, err)
      else
         tok = read_token(c)
         star = index(tok, '*')
         if (star > 1) then
            if (verify(tok(1:star - 1), '0123456789') == 0 .and. star <= 10) then
               read(tok(1:star - 1), *, iostat=ios) r
               if (r < 1 .or. r > max_repeat) then
                  call fatal_error(err, at(c) // 'group &' // group // ': ' // a%name // ' = ' &
                     // tok // ': a repeat count r*value needs 1 <= r <= ' // str(max_repeat))
                  return
               end if
               tok = tok(star + 1:)
               if (len(tok) == 0) then
                  if (scan(peek(c), '''"') == 0) then
                     call fatal_error(err, at(c) // 'group &' // group // ': ' // a%name &
                        // ' = ' // str(r) // '*: no value for ' // a%name // ' after the ' &
                        // "repeat count (namelist input would keep the old value silently)")
                     return
                  end if
                  call parse_string(c, group, a%name, v, err)
               end if
            end if
         end if
         if (.not. allocated(err) .and. len(tok) > 0) call classify(tok, v)
         if (v%kind == 0) then
            call fatal_error(err, at(c) // 'group &' // group // ': ' // a%name // ' = ' // tok &
               // ': not a number, a logical (.true., .false.) or a quoted text; cannot read ' &
               // 'the value of ' // a%name)
            return
         end if
      end if
      if (allocated(err)) return
      if (.not. (c%p > len(c%t) .or. scan(peek(c), ' ,/!&' // tab // lf) > 0)) then
         call fatal_error(err, at(c) // 'group &' // group // ': ' // a%name // ": '" &
            // rest_of_line(c) // "' right after a value (values are separated by commas or " &
            // 'blanks)')
         return
      end if
      if (c%n_values > max_values - r) then
         call fatal_error(err, at(c) // 'group &' // group // ': ' // a%name // ': more than ' &
            // str(max_values) // ' values in one ' &
            // trim(merge('deck file', 'override ', c%is_file)) // ' (repeats r*value ' &
            // 'counted): no list gapbeam reads is that long')
         return
      end if
      c%n_values = c%n_values + r
      do k = 1, r
         if (n == size(a%values)) call grow_values(a%values)
         n = n + 1
         a%values(n) = v
      end do
   end subroutine parse_value

   !> A quoted string at the cursor ('' or "" inside for one quote), on one line.
   subroutine parse_string(c, group, name, v, err)
      type(cursor_t), intent(inout) :: c
      character(len=*), intent(in) :: group, name
      type(value_t), intent(out) :: v
      type(error_t), allocatable, intent(inout) :: err
      character(len=1) :: q
      integer :: p0
      q = peek(c);  p0 = c%p;  c%p = c%p + 1
      v%kind = value_string;  v%text = ''
      do
         if (c%p > len(c%t) .or. peek(c) == lf) then
            call fatal_error(err, at(c) // 'group &' // group // ': a quote opened in the ' &
               // 'value of ' // name // ' is never closed on its line (' &
               // one_line(c%t(p0:min(len(c%t), p0 + 60))) // ')')
            return
         end if
         if (peek(c) == q) then
            if (c%p < len(c%t)) then
               if (c%t(c%p + 1:c%p + 1) == q) then
                  v%text = v%text // q;  c%p = c%p + 2
                  cycle
               end if
            end if
            c%p = c%p + 1
            return
         end if
         v%text = v%text // peek(c);  c%p = c%p + 1
      end do
   end subroutine parse_string

   !> The kind of an unquoted token (0: none, i.e. not a value).
   pure subroutine classify(tok, v)
      character(len=*), intent(in) :: tok
      type(value_t), intent(inout) :: v
      character(len=len(tok)) :: t
      t = lower(tok)
      v%text = tok
      select case (t)
      case ('.true.', '.t.', '.t', 't', 'true')
         v%kind = value_logical;  v%flag = .true.
      case ('.false.', '.f.', '.f', 'f', 'false')
         v%kind = value_logical;  v%flag = .false.
      case default
         if (is_number(t)) v%kind = value_number
      end select
   end subroutine classify

   !> Fortran number syntax: [sign] digits [. digits] [(e|d) [sign] digits], '.5', NaN, Inf.
   pure logical function is_number(t)
      character(len=*), intent(in) :: t      !! lower case
      integer :: i, n, mant
      is_number = .false.
      n = len(t);  i = 1
      if (n == 0) return
      if (scan(t(1:1), '+-') > 0) i = 2
      if (t(i:) == 'nan' .or. t(i:) == 'inf' .or. t(i:) == 'infinity') then
         is_number = .true.
         return
      end if
      mant = 0
      do while (i <= n)
         if (.not. is_digit(t(i:i))) exit
         i = i + 1;  mant = mant + 1
      end do
      if (i <= n) then
         if (t(i:i) == '.') then
            i = i + 1
            do while (i <= n)
               if (.not. is_digit(t(i:i))) exit
               i = i + 1;  mant = mant + 1
            end do
         end if
      end if
      if (mant == 0) return
      if (i <= n) then
         if (scan(t(i:i), 'ed') == 0) return
         i = i + 1
         if (i <= n) then
            if (scan(t(i:i), '+-') > 0) i = i + 1
         end if
         if (i > n) return
         if (verify(t(i:), '0123456789') /= 0) return
      end if
      is_number = .true.
   end function is_number

   !> Whether 'name =' or 'name(' follows at the cursor (the next assignment).
   pure logical function assignment_follows(c)
      type(cursor_t), intent(in) :: c
      integer :: p
      p = c%p
      do while (p <= len(c%t))
         if (.not. is_name_char(c%t(p:p))) exit
         p = p + 1
      end do
      do while (p <= len(c%t))
         if (c%t(p:p) /= ' ' .and. c%t(p:p) /= tab) exit
         p = p + 1
      end do
      assignment_follows = .false.
      if (p <= len(c%t)) assignment_follows = c%t(p:p) == '=' .or. c%t(p:p) == '('
   end function assignment_follows

   !> Two assignments that set the same variable or list entry.
   pure logical function overlap(a, b)
      type(assignment_t), intent(in) :: a, b
      integer :: a1, a2, b1, b2
      overlap = .false.
      if (a%name /= b%name) return
      a1 = max(a%first, 1);  a2 = a1 + size(a%values) - 1
      b1 = max(b%first, 1);  b2 = b1 + size(b%values) - 1
      overlap = (a%first == 0 .and. b%first == 0) .or. (a1 <= b2 .and. b1 <= a2)
   end function overlap

   !> Skip blanks, line ends and comments.
   pure subroutine skip_space(c)
      type(cursor_t), intent(inout) :: c
      character(len=1) :: ch
      do while (c%p <= len(c%t))
         ch = c%t(c%p:c%p)
         if (ch == lf) then
            c%line = c%line + 1
         else if (ch == '!') then
            do while (c%p < len(c%t))
               if (c%t(c%p + 1:c%p + 1) == lf) exit
               c%p = c%p + 1
            end do
         else if (ch /= ' ' .and. ch /= tab) then
            return
         end if
         c%p = c%p + 1
      end do
   end subroutine skip_space

   !> Skip blanks and tabs on the line.
   pure subroutine skip_blanks(c)
      type(cursor_t), intent(inout) :: c
      do while (c%p <= len(c%t))
         if (c%t(c%p:c%p) /= ' ' .and. c%t(c%p:c%p) /= tab) return
         c%p = c%p + 1
      end do
   end subroutine skip_blanks

   !> The name at the cursor (letters, digits, '_').
   function read_name(c) result(name)
      type(cursor_t), intent(inout) :: c
      character(len=:), allocatable :: name
      integer :: p0
      p0 = c%p
      do while (c%p <= len(c%t))
         if (.not. is_name_char(c%t(c%p:c%p))) exit
         c%p = c%p + 1
      end do
      name = c%t(p0:c%p - 1)
   end function read_name

   !> An unquoted token at the cursor: up to a blank, a comma, '/', '!' or the line end.
   function read_token(c) result(tok)
      type(cursor_t), intent(inout) :: c
      character(len=:), allocatable :: tok
      integer :: p0
      p0 = c%p
      do while (c%p <= len(c%t))
         if (scan(c%t(c%p:c%p), ' ,/!' // tab // lf) > 0) exit
         if (c%p > p0 .and. scan(c%t(c%p:c%p), '''"') > 0 .and. c%t(c%p - 1:c%p - 1) == '*') &
            exit
         c%p = c%p + 1
      end do
      tok = c%t(p0:c%p - 1)
   end function read_token

   !> The character at the cursor (a blank past the end).
   pure character(len=1) function peek(c)
      type(cursor_t), intent(in) :: c
      peek = ' '
      if (c%p <= len(c%t)) peek = c%t(c%p:c%p)
   end function peek

   !> The group opening as written, from its '&' (just before the cursor) to the first blank
   !> after a name: '&forcing.', '& forcing', '&-tops' (at most 30 characters).
   pure function group_token(c) result(t)
      type(cursor_t), intent(in) :: c
      character(len=:), allocatable :: t
      integer :: q
      logical :: named
      named = .false.
      q = c%p
      do while (q <= len(c%t) .and. q - c%p < 29)
         if (c%t(q:q) == lf) exit
         if ((c%t(q:q) == ' ' .or. c%t(q:q) == tab) .and. named) exit
         if (is_letter(c%t(q:q))) named = .true.
         q = q + 1
      end do
      t = '&' // c%t(c%p:q - 1)
   end function group_token

   !> ' (&name?)': the first name on the rest of the line, the group perhaps meant.
   pure function meant(c) result(t)
      type(cursor_t), intent(in) :: c
      character(len=:), allocatable :: t
      integer :: p, q
      t = ''
      p = c%p
      do while (p <= len(c%t))
         if (c%t(p:p) == lf) return
         if (is_letter(c%t(p:p))) exit
         p = p + 1
      end do
      if (p > len(c%t)) return
      q = p
      do while (q <= len(c%t))
         if (.not. is_name_char(c%t(q:q))) exit
         q = q + 1
      end do
      t = ' (&' // lower(c%t(p:q - 1)) // '?)'
   end function meant

   !> The rest of the cursor's line, at most 40 characters.
   pure function rest_of_line(c) result(t)
      type(cursor_t), intent(in) :: c
      character(len=:), allocatable :: t
      integer :: e
      e = index(c%t(min(c%p, len(c%t) + 1):), lf)
      if (e == 0) then
         t = c%t(min(c%p, len(c%t) + 1):)
      else
         t = c%t(c%p:c%p + e - 2)
      end if
      t = trim(t)
      if (len(t) > 40) t = t(1:40) // '...'
   end function rest_of_line

   !> 'line N: ' in a deck file ('' in an override).
   pure function at(c, line) result(t)
      type(cursor_t), intent(in) :: c
      integer, intent(in), optional :: line
      character(len=:), allocatable :: t
      t = ''
      if (.not. c%is_file) return
      if (present(line)) then
         t = 'line ' // str(line) // ': '
      else
         t = 'line ' // str(c%line) // ': '
      end if
   end function at

   !> Text on one line: line ends and runs of blanks as one blank.
   pure function one_line(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      integer :: i, k
      allocate(character(len=min(len(s), 204)) :: t)
      k = 0
      do i = 1, len(s)
         if (k == len(t)) exit                  ! enough for the 200 characters shown
         if (s(i:i) == lf .or. s(i:i) == tab .or. s(i:i) == ' ') then
            if (k > 0) then
               if (t(k:k) /= ' ') then
                  k = k + 1;  t(k:k) = ' '
               end if
            end if
         else
            k = k + 1;  t(k:k) = s(i:i)
         end if
      end do
      t = trim(t(1:k))
      if (len(t) > 200) t = t(1:200) // '...'
   end function one_line

   pure logical function is_letter(ch)
      character(len=1), intent(in) :: ch
      is_letter = (ch >= 'a' .and. ch <= 'z') .or. (ch >= 'A' .and. ch <= 'Z')
   end function is_letter

   pure logical function is_digit(ch)
      character(len=1), intent(in) :: ch
      is_digit = ch >= '0' .and. ch <= '9'
   end function is_digit

   pure logical function is_name_char(ch)
      character(len=1), intent(in) :: ch
      is_name_char = is_letter(ch) .or. is_digit(ch) .or. ch == '_'
   end function is_name_char
end module gapbeam_deck_text
