!> Text handling of namelist decks: loading a file, finding groups, splitting assignments.
!>
!> A deck is a sequence of sources: the deck file, then each command-line override (a
!> namelist fragment such as "&forcing frequency_hz=10.2 /"). Quotes (' and ") and
!> comments (! to the end of a line, outside quotes) are honoured when groups are located.
module gapbeam_deck_text
   use gapbeam_error, only: error_t, fatal_error
   implicit none
   private
   public :: source_t, load_file, make_source, group_names, group_block, split_assignments
   public :: lower, basename_stem, null_value, longest_text_value, assigned_name, quote_left_open
   public :: swallowed_group

   !> One source of namelist text (file or override), as lines.
   type :: source_t
      character(len=:), allocatable :: label       !! 'deck.nml' or "override 2 '...'"
      character(len=:), allocatable :: lines(:)    !! the text, one element per line
   end type source_t

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

   !> Build a source from a text with newlines.
   pure subroutine make_source(label, text, src)
      character(len=*), intent(in) :: label     !! for messages
      character(len=*), intent(in) :: text      !! text, lines separated by newline
      type(source_t), intent(out) :: src        !! result
      integer :: n, i, start, width, k
      character(len=1), parameter :: nl = new_line('a')
      n = 1;  width = 1;  start = 1
      do i = 1, len(text)
         if (text(i:i) == nl) then
            n = n + 1
            width = max(width, i - start);  start = i + 1
         end if
      end do
      width = max(width, len(text) - start + 1, 1)
      allocate(character(len=width) :: src%lines(n))
      k = 0;  start = 1
      do i = 1, len(text) + 1
         if (i > len(text)) then
            k = k + 1;  src%lines(k) = text(start:)
         else if (text(i:i) == nl) then
            k = k + 1;  src%lines(k) = text(start:i - 1);  start = i + 1
         end if
      end do
      src%label = label
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
      allocate(character(len=max(fsize, 0)) :: text)
      if (fsize > 0) read(unit, iostat=ios, iomsg=msg) text
      close(unit)
      if (ios /= 0) then
         call fatal_error(err, path // ': cannot read the deck file: ' // trim(msg))
         return
      end if
      text = unix_line_ends(text)
   end subroutine load_file

   !> Text with every line end as LF: CRLF (DOS) becomes LF, then a lone CR (old Mac) too.
   pure function unix_line_ends(s) result(t)
      character(len=*), intent(in) :: s   !! text with any line ends
      character(len=:), allocatable :: t
      character(len=1), parameter :: cr = achar(13), lf = achar(10)
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

   !> Names (lower case) of all groups opened in a source, in order, with repeats.
   pure subroutine group_names(src, names)
      type(source_t), intent(in) :: src                       !! source
      character(len=32), allocatable, intent(out) :: names(:) !! group names
      integer :: l, i, j, n
      character(len=1) :: q
      character(len=:), allocatable :: line
      character(len=32), allocatable :: buf(:)
      allocate(buf(16))
      n = 0;  q = ' '
      do l = 1, size(src%lines)
         line = trim(src%lines(l))   ! the lines are padded to the longest one
         i = 1
         do while (i <= len(line))
            if (q /= ' ') then
               if (line(i:i) == q) q = ' '
            else if (line(i:i) == '"' .or. line(i:i) == "'") then
               q = line(i:i)
            else if (line(i:i) == '!') then
               exit
            else if (line(i:i) == '&' .or. line(i:i) == '$') then
               j = i + 1
               do while (j <= len(line))
                  if (.not. is_name_char(line(j:j))) exit
                  j = j + 1
               end do
               if (j > i + 1) then
                  if (n == size(buf)) buf = [buf, buf]     ! no limit on the number of groups
                  n = n + 1;  buf(n) = lower(line(i + 1:j - 1))
               end if
               i = j - 1
            end if
            i = i + 1
         end do
      end do
      names = buf(1:n)
   end subroutine group_names

   !> The lines of group `name` (from '&name' to its closing '/'), or an unallocated array.
   pure subroutine group_block(src, name, block, closed)
      type(source_t), intent(in) :: src                          !! source
      character(len=*), intent(in) :: name                       !! group name, lower case
      character(len=:), allocatable, intent(out) :: block(:)     !! the group's lines
      logical, intent(out), optional :: closed                   !! a '/' ends the group
      integer :: l, i, first, last, cstart, cend
      character(len=1) :: q
      character(len=:), allocatable :: line
      logical :: inside
      q = ' ';  inside = .false.;  first = 0;  last = 0;  cstart = 1;  cend = 0
      outer: do l = 1, size(src%lines)
         line = trim(src%lines(l))   ! the lines are padded to the longest one
         i = 1
         do while (i <= len(line))
            if (q /= ' ') then
               if (line(i:i) == q) q = ' '
            else if (line(i:i) == '"' .or. line(i:i) == "'") then
               q = line(i:i)
            else if (line(i:i) == '!') then
               exit
            else if (.not. inside .and. (line(i:i) == '&' .or. line(i:i) == '$')) then
               if (lower(line(i + 1:min(len(line), i + len(name)))) == name) then
                  if (i + len(name) + 1 > len(line)) then
                     inside = .true.
                  else if (.not. is_name_char(line(i + len(name) + 1:i + len(name) + 1))) then
                     inside = .true.
                  end if
                  if (inside) then
                     first = l;  cstart = i;  i = i + len(name)
                  end if
               end if
            else if (inside .and. line(i:i) == '/') then
               last = l;  cend = i
               exit outer
            end if
            i = i + 1
         end do
      end do outer
      if (present(closed)) closed = last > 0
      if (first == 0) return
      if (last == 0) last = size(src%lines)
      allocate(character(len=len(src%lines)) :: block(last - first + 1))
      block = src%lines(first:last)
      block(1) = repeat(' ', cstart - 1) // src%lines(first)(cstart:)
      if (cend > 0) block(size(block)) = block(size(block))(1:cend)
   end subroutine group_block

   pure logical function is_name_char(c)
      character(len=1), intent(in) :: c
      is_name_char = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. &
                     (c >= '0' .and. c <= '9') .or. c == '_'
   end function is_name_char

   !> Split a group block into its assignments ('name = value', 'node(2) = 3, 4').
   pure subroutine split_assignments(block, items)
      character(len=*), intent(in) :: block(:)                   !! lines of one group
      character(len=:), allocatable, intent(out) :: items(:)     !! one assignment each
      character(len=:), allocatable :: s
      integer :: i, j, k, n, l, ends
      integer, allocatable :: starts(:)
      character(len=1) :: q
      logical :: at_sep
      ! join the lines without comments
      s = ''
      do l = 1, size(block)
         q = ' '
         ends = len(block(l))
         do i = 1, len(block(l))
            if (q /= ' ') then
               if (block(l)(i:i) == q) q = ' '
            else if (block(l)(i:i) == '"' .or. block(l)(i:i) == "'") then
               q = block(l)(i:i)
            else if (block(l)(i:i) == '!') then
               ends = i - 1;  exit
            end if
         end do
         s = s // ' ' // block(l)(1:ends)
      end do
      ! drop '&name' and the closing '/'
      i = index(s, '&');  if (i == 0) i = index(s, '$')
      if (i > 0) then
         j = i + 1
         do while (j <= len(s))
            if (.not. is_name_char(s(j:j))) exit
            j = j + 1
         end do
         s = s(j:)
      end if
      ! find the starts of 'name [(...)] =' outside quotes
      allocate(starts(16))
      n = 0;  q = ' ';  at_sep = .true.
      i = 1
      do while (i <= len(s))
         if (q /= ' ') then
            if (s(i:i) == q) q = ' '
            at_sep = .false.
         else if (s(i:i) == '"' .or. s(i:i) == "'") then
            q = s(i:i);  at_sep = .false.
         else if (s(i:i) == ' ' .or. s(i:i) == ',') then
            at_sep = .true.
         else
            if (at_sep .and. is_name_char(s(i:i))) then
               j = i
               do while (j <= len(s))
                  if (.not. is_name_char(s(j:j))) exit
                  j = j + 1
               end do
               k = j
               do while (k <= len(s))
                  if (s(k:k) /= ' ') exit
                  k = k + 1
               end do
               if (k <= len(s)) then
                  if (s(k:k) == '(') then
                     k = index(s(k:), ')') + k
                     do while (k <= len(s))
                        if (s(k:k) /= ' ') exit
                        k = k + 1
                     end do
                  end if
               end if
               if (k <= len(s)) then
                  if (s(k:k) == '=') then
                     if (n == size(starts)) starts = [starts, starts]   ! no limit
                     n = n + 1;  starts(n) = i
                  end if
               end if
               i = j - 1
            end if
            at_sep = .false.
         end if
         i = i + 1
      end do
      ! cut: each assignment runs to the next start (trailing '/' and commas removed)
      allocate(character(len=max(1, len(s))) :: items(n))
      do k = 1, n
         if (k < n) then
            items(k) = s(starts(k):starts(k + 1) - 1)
         else
            items(k) = s(starts(k):)
         end if
         call trim_tail(items(k))
      end do
   end subroutine split_assignments

   !> Whether a quote opened in `item` is still open at its end (then the rest of the source,
   !> the closing '/' included, is read as part of the string).
   pure logical function quote_left_open(item)
      character(len=*), intent(in) :: item                 !! one assignment
      integer :: i
      character(len=1) :: q
      q = ' '
      do i = 1, len(item)
         if (q /= ' ') then
            if (item(i:i) == q) q = ' '
         else if (item(i:i) == "'" .or. item(i:i) == '"') then
            q = item(i:i)
         end if
      end do
      quote_left_open = q /= ' '
   end function quote_left_open

   !> A group of `groups` (space-separated names) that starts a line inside a quoted string: a
   !> quote opened in an earlier value and never closed swallows the groups after it (up to the
   !> next quote), so that they would silently vanish. The message names that group and its line,
   !> and the line where the open quote stands with its group and the variables assigned there
   !> (which of its quotes is the stray one the text cannot tell); '' when there is none.
   pure function swallowed_group(src, groups) result(t)
      type(source_t), intent(in) :: src                    !! source
      character(len=*), intent(in) :: groups               !! known group names
      character(len=:), allocatable :: t, line, grp, grp_q
      character(len=1) :: q
      integer :: l, i, j, k, ql, gl, gl_q, m
      t = '';  q = ' ';  ql = 0;  grp = '';  grp_q = '';  gl = 1;  gl_q = 1
      do l = 1, size(src%lines)
         line = trim(src%lines(l))
         k = verify(line, ' ')
         if (q /= ' ' .and. k > 0) then
            if (line(k:k) == '&' .or. line(k:k) == '$') then
               j = name_end(line, k + 1)
               if (j > k + 1) then
                  if (index(' ' // groups // ' ', ' ' // lower(line(k + 1:j - 1)) // ' ') > 0) then
                     t = ''
                     do m = gl_q, ql                  ! the group's assignments up to the quote
                        if (len(t) > 0 .and. len(assigned_names(trim(src%lines(m)))) > 0) &
                           t = t // ', '
                        t = t // assigned_names(trim(src%lines(m)))
                     end do
                     t = 'group &' // lower(line(k + 1:j - 1)) // ' (line ' // int_text(l) &
                        // ') lies inside a quoted string: a quote on line ' // int_text(ql) &
                        // ' (&' // grp_q // ': ' // t // ') is left open'
                     return
                  end if
               end if
            end if
         end if
         i = 1
         do while (i <= len(line))
            if (q /= ' ') then
               if (line(i:i) == q) q = ' '
            else if (line(i:i) == '"' .or. line(i:i) == "'") then
               q = line(i:i);  ql = l;  grp_q = grp;  gl_q = gl
            else if (line(i:i) == '!') then
               exit
            else if (line(i:i) == '&' .or. line(i:i) == '$') then
               j = name_end(line, i + 1)
               if (j > i + 1) then
                  grp = lower(line(i + 1:j - 1));  gl = l
               end if
               i = j - 1
            end if
            i = i + 1
         end do
      end do
   contains
      !> The position after the name that starts at `i`.
      pure integer function name_end(line, i) result(j)
         character(len=*), intent(in) :: line
         integer, intent(in) :: i
         j = i
         do while (j <= len(line))
            if (.not. is_name_char(line(j:j))) exit
            j = j + 1
         end do
      end function name_end
      !> The names before every '=' of a line, comma separated.
      pure function assigned_names(line) result(s)
         character(len=*), intent(in) :: line
         character(len=:), allocatable :: s
         integer :: e, b
         s = ''
         do e = 1, len(line)
            if (line(e:e) /= '=') cycle
            b = len_trim(line(1:e - 1))
            if (b == 0) cycle
            if (len(s) > 0) s = s // ', '
            s = s // assigned_name(line(scan(line(1:b), ' ,', back=.true.) + 1:e))
         end do
      end function assigned_names
      pure function int_text(n) result(s)
         integer, intent(in) :: n
         character(len=:), allocatable :: s
         character(len=12) :: b
         write(b, '(i0)') n
         s = trim(b)
      end function int_text
   end function swallowed_group

   !> The variable name of an assignment, lower case: 'Node(2) = 3' -> 'node'.
   pure function assigned_name(item) result(var)
      character(len=*), intent(in) :: item                 !! one assignment
      character(len=:), allocatable :: var
      integer :: p
      p = scan(item, '(=')
      var = trim(lower(adjustl(item(1:max(p - 1, 1)))))
   end function assigned_name

   !> True if an assignment gives a null value, which namelist input reads as "leave the
   !> variable as it is": nothing after '=' ('x =', 'x = ,'), an empty entry in a list
   !> ('x = 1, , 3', 'x = , 2') or a repeat without a value ('x = 3*').
   pure logical function null_value(item)
      character(len=*), intent(in) :: item                 !! one assignment, as split
      integer :: i, eq, n
      character(len=1) :: q, prev
      eq = index(item, '=')
      null_value = .false.
      if (eq == 0) return
      q = ' ';  prev = ','          ! as if a separator came right before the value
      n = len_trim(item)
      null_value = .true.
      do i = eq + 1, n
         if (q /= ' ') then
            if (item(i:i) == q) q = ' '
            cycle
         end if
         select case (item(i:i))
         case ("'", '"')
            q = item(i:i);  prev = 'x'
         case (' ')
            cycle
         case (',')
            if (prev == ',') return
            prev = ','
         case ('*')
            if (i == n) return
            if (scan(item(i + 1:i + 1), ', ') > 0) return
            prev = 'x'
         case default
            prev = 'x'
         end select
      end do
      null_value = prev == ','       ! nothing after '=', or after the last separator
   end function null_value

   !> Length of the longest character constant in the value of an assignment: each quoted
   !> string ('a doubled '''' quote counts once'), or each blank- or comma-separated token of
   !> an unquoted value. 0 for an empty value.
   pure integer function longest_text_value(item) result(longest)
      character(len=*), intent(in) :: item                 !! one assignment, as split
      integer :: i, eq, n, run
      character(len=1) :: q
      longest = 0
      eq = index(item, '=')
      if (eq == 0) return
      n = len_trim(item)
      q = ' ';  run = 0;  i = eq + 1
      do while (i <= n)
         if (q /= ' ') then
            if (item(i:i) == q) then
               if (i < n) then
                  if (item(i + 1:i + 1) == q) then   ! doubled quote: one character
                     run = run + 1;  i = i + 2
                     cycle
                  end if
               end if
               q = ' ';  longest = max(longest, run);  run = 0
            else
               run = run + 1
            end if
         else if (item(i:i) == "'" .or. item(i:i) == '"') then
            q = item(i:i);  run = 0
         else if (item(i:i) == ' ' .or. item(i:i) == ',') then
            longest = max(longest, run);  run = 0
         else
            run = run + 1
         end if
         i = i + 1
      end do
      longest = max(longest, run)
   end function longest_text_value

   pure subroutine trim_tail(t)
      character(len=*), intent(inout) :: t
      integer :: e
      e = len_trim(t)
      do while (e > 0)
         if (t(e:e) /= ',' .and. t(e:e) /= '/' .and. t(e:e) /= ' ') exit
         t(e:e) = ' ';  e = e - 1
      end do
   end subroutine trim_tail
end module gapbeam_deck_text
