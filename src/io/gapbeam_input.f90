!> Decks: read the text strictly, apply command-line overrides, validate, keep the effective text.
!>
!> What each variable is (its group, type, unit, range or words, default) is declared once in
!> the deck table (core/gapbeam_deck_table). Reading a deck:
!>  1. every source (the deck file, then each override) is scanned by gapbeam_deck_text, which
!>     refuses any text it does not consume;
!>  2. the groups and variables named must be the table's, each group at most once per source;
!>  3. the values are applied through the table (gapbeam_deck_apply), converted to their types;
!>  4. every value is checked against its description (core/gapbeam_deck_check);
!>  5. the rules that tie variables together are checked (core/gapbeam_deck_rules and its
!>     _axes, _flow and _initial companions, given which groups and variables the sources
!>     name), in the order of the groups, and the derived values made (Rayleigh coefficients
!>     from ratios, the sweep's axes, the default output prefix); a start from a file
!>     (&initial kind = 'file') reads that file's final state (gapbeam_input_initial).
!> Messages read `DECK: group &beam: length = -0.2: must be > 0 and finite`; a problem of the
!> text also names the line (`DECK: line 7: ...`) or the override.
module gapbeam_input
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck_text, only: source_t, load_file, make_source, parse_source, basename_stem, &
      given_list
   use gapbeam_deck_rules, only: check_structure, check_stops, check_loads, check_settings, &
      check_capabilities, check_analysis, given_defaults, is_given
   use gapbeam_deck_rules_axes, only: make_sweep_axes, check_continuation, check_sizes
   use gapbeam_deck_rules_flow, only: check_flow
   use gapbeam_deck_rules_initial, only: check_initial, check_mechanism
   use gapbeam_input_initial, only: read_initial_file
   use gapbeam_deck_apply, only: apply_visitor_t, source_where
   use gapbeam_deck_check, only: check_deck_values, deck_names_t, deck_names, group_variables
   use gapbeam_deck_table, only: walk_deck
   use gapbeam_deck, only: deck_t
   implicit none
   private
   public :: read_deck

contains

   !> Read, override and validate a deck.
   subroutine read_deck(path, overrides, deck, err)
      character(len=*), intent(in) :: path            !! deck file
      character(len=*), intent(in) :: overrides(:)    !! namelist fragments applied in order
      type(deck_t), intent(out) :: deck               !! validated deck
      type(error_t), allocatable, intent(out) :: err  !! first problem found
      type(source_t), allocatable :: srcs(:)
      character(len=:), allocatable :: text
      type(apply_visitor_t) :: v
      character(len=:), allocatable :: named
      integer :: s

      deck%path = path
      call load_file(path, text, err)
      if (allocated(err)) return
      allocate(srcs(1 + size(overrides)))
      call make_source(path, text, .true., srcs(1))
      deck%text = text
      do s = 1, size(overrides)
         call make_source('override ' // str(s) // " '" // short_text(trim(overrides(s)), 80) &
                          // "'", trim(overrides(s)), .false., srcs(1 + s))
         deck%text = deck%text // new_line('a') // '! command-line override ' // str(s) &
            // new_line('a') // trim(overrides(s)) // new_line('a')
      end do
      do s = 1, size(srcs)
         if (s > 1 .and. index(srcs(s)%text, '&') == 0) then
            call fatal_error(err, path // ': ' // srcs(s)%label // ': no namelist group ' &
               // '(an override looks like "&forcing frequency_hz=10.2 /")')
            return
         end if
         call parse_source(srcs(s), err)
         if (allocated(err)) then
            if (s > 1) err%message = srcs(s)%label // ': ' // err%message
            err%message = path // ': ' // err%message
            return
         end if
         if (s > 1 .and. size(srcs(s)%groups) == 0) then
            call fatal_error(err, path // ': ' // srcs(s)%label // ': no namelist group ' &
               // '(an override looks like "&forcing frequency_hz=10.2 /")')
            return
         end if
      end do
      call check_names(srcs, err);  if (failed(err, path)) return
      named = given_list(srcs)

      v%srcs = srcs
      call walk_deck(v, deck)
      if (allocated(v%err)) call move_alloc(v%err, err)
      if (failed(err, path)) return
      call given_defaults(named, deck)
      call check_deck_values(deck, err);  if (failed(err, path)) return
      call check_structure(named, deck, err);  if (failed(err, path)) return
      call check_stops(deck%structure, deck%stops, err);  if (failed(err, path)) return
      call check_mechanism(deck, err);  if (failed(err, path)) return
      call check_loads(deck, err);  if (failed(err, path)) return
      call check_initial(deck, err);  if (failed(err, path)) return
      if (deck%initial%kind == 'file') call read_initial_file(deck, err)
      if (failed(err, path)) return
      call check_flow(deck, err);  if (failed(err, path)) return
      call check_settings(deck, err);  if (failed(err, path)) return
      call make_sweep_axes(named, deck, err);  if (failed(err, path)) return
      call check_continuation(named, deck, err);  if (failed(err, path)) return
      call check_sizes(deck, err);  if (failed(err, path)) return
      call check_capabilities(deck, err);  if (failed(err, path)) return
      call check_analysis(named, deck, err);  if (failed(err, path)) return
      if (len_trim(deck%job%output) == 0) deck%job%output = 'results/' // basename_stem(path)
   end subroutine read_deck

   !> True when `err` is set; its message then starts with the deck path.
   logical function failed(err, path)
      type(error_t), allocatable, intent(inout) :: err   !! status of a check
      character(len=*), intent(in) :: path               !! deck path as given
      failed = allocated(err)
      if (failed) then
         if (index(err%message, path // ': ') /= 1) err%message = path // ': ' // err%message
      end if
   end function failed

   !> Every group known and at most once per source, every variable one of its group's, and
   !> an entry index only on a list; &job and &beam present.
   subroutine check_names(srcs, err)
      type(source_t), intent(in) :: srcs(:)            !! parsed sources
      type(error_t), allocatable, intent(out) :: err   !! first name refused
      type(deck_names_t) :: names
      character(len=:), allocatable :: vars
      integer :: s, i, j, k
      names = deck_names()
      do s = 1, size(srcs)
         do i = 1, size(srcs(s)%groups)
            associate (g => srcs(s)%groups(i))
               vars = group_variables(names, g%name)
               if (len(vars) == 0) then
                  call fatal_error(err, source_where(srcs, s, g%line) // 'unknown group &' &
                     // g%name // '; allowed groups: &' // replace_spaces(trim(adjustl( &
                     names%groups))))
                  return
               end if
               do j = 1, i - 1
                  if (srcs(s)%groups(j)%name == g%name) then
                     call fatal_error(err, source_where(srcs, s, g%line) // 'group &' // g%name &
                        // ' appears more than once')
                     return
                  end if
               end do
               do k = 1, size(g%items)
                  if (index(vars, ' ' // g%items(k)%name // ' ') == 0) then
                     call fatal_error(err, source_where(srcs, s, g%items(k)%line) // 'group &' &
                        // g%name // ': unknown variable ' // g%items(k)%name // ' (in "' &
                        // g%items(k)%written // '"); the variables of &' // g%name &
                        // ' are:' // vars)
                     return
                  end if
                  if (g%items(k)%first > 0 .and. index(group_variables(names, g%name, &
                      indexed=.true.), ' ' // g%items(k)%name // ' ') == 0) then
                     call fatal_error(err, source_where(srcs, s, g%items(k)%line) // 'group &' &
                        // g%name // ': "' // g%items(k)%written // '": ' // g%items(k)%name &
                        // ' is not a list (no entry index)')
                     return
                  end if
               end do
            end associate
         end do
      end do
      if (.not. is_given(given_list(srcs), 'job')) call fatal_error(err, 'required group &job ' &
         // 'is missing')
      if (.not. is_given(given_list(srcs), 'beam')) call fatal_error(err, 'required group &beam ' &
         // 'is missing')
   end subroutine check_names

   ! ---------------------------------------------------------------- text helpers

   !> 'a b c' -> 'a, &b, &c'.
   pure function replace_spaces(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      integer :: i
      t = ''
      do i = 1, len(s)
         if (s(i:i) == ' ') then
            t = t // ', &'
         else
            t = t // s(i:i)
         end if
      end do
   end function replace_spaces

   !> `text`, cut to `n` characters with '...' when longer.
   pure function short_text(text, n) result(t)
      character(len=*), intent(in) :: text            !! any text
      integer, intent(in) :: n                        !! most characters kept
      character(len=:), allocatable :: t
      if (len(text) > n) then
         t = text(1:n) // '...'
      else
         t = text
      end if
   end function short_text
end module gapbeam_input
