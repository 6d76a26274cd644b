!> A numeric deck variable named by its group and name, `&stops gap(2)`, `&forcing frequency_hz`:
!> parse the name, read and set its value on a deck_t, with its unit and its allowed range.
!>
!> This is the "parameter setter" of the analyses that vary a design variable (continuation of
!> periodic orbits, two-parameter bifurcation curves, the axes of sweeps and maps): they set
!> the value on a copy of the deck and rebuild the model from it (gapbeam_deck_parameter), so a
!> variable means exactly what it means in a deck (the stop-stiffness rule, the damping ratios
!> are applied again). Pure data: nothing numerical here.
!>
!> The design variables, their units and ranges are those the deck table declares with
!> `design=.true.` (gapbeam_deck_table; `gapbeam --help-deck` marks them); list groups take an
!> entry index, default 1. A list of names separated by commas, '&stops gap(1), &stops gap(2)',
!> names several variables set together to one value (a sweep axis that moves both baffles'
!> clearance): they must have one unit, and a forcing variable stands alone
!> (parse_deck_variables). Setting a damping ratio or frequency with model = 'ratios'
!> recomputes the Rayleigh coefficients (as the deck reader does); setting a coefficient needs
!> model = 'rayleigh' or 'modal'. A list variable declared a design variable (`&damping
!> modal_ratios(i)`) takes the index of its element, default 1; the element must exist.
module gapbeam_deck_variable
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_description, only: rayleigh_from_ratios, damping_t
   use gapbeam_deck, only: deck_t
   use gapbeam_deck_visitor, only: deck_visitor_t, deck_spec_t, spec_violation
   use gapbeam_deck_table, only: walk_deck
   implicit none
   private
   public :: deck_variable_t, parse_deck_variable, check_deck_variable, get_deck_value, &
      set_deck_value, deck_variable_words, deck_variable_label, parse_deck_variables, &
      deck_variables_label

   !> A numeric deck variable.
   type :: deck_variable_t
      character(len=16) :: group = ''        !! namelist group, lower case, no '&'
      character(len=32) :: name = ''         !! variable
      integer :: index = 0                   !! entry of a list group (0: not a list group)
      character(len=16) :: units = ''        !! unit of its value
      real(dp) :: lower = 0.0_dp             !! allowed: value >= lower (or > lower)
      logical :: strict = .false.            !! value > lower (else >=)
   end type deck_variable_t

   !> What the walks below do with the variable they look for.
   integer, parameter :: op_describe = 1, op_get = 2, op_set = 3, op_words = 4

   !> The visitor that finds one design variable: describes, reads or sets it.
   type, extends(deck_visitor_t) :: design_visitor_t
      integer :: op = op_describe
      character(len=16) :: target_group = ''
      character(len=32) :: target_name = ''
      integer :: target_index = 0
      real(dp) :: x = 0.0_dp                  !! value read, or to set
      logical :: found = .false.              !! the variable was met
      logical :: group_found = .false.        !! its group has design variables
      logical :: in_list = .false.            !! it is an entry of a list group
      type(deck_spec_t) :: spec               !! its description
      character(len=:), allocatable :: words  !! op_words: the design variables
      character(len=:), allocatable :: refused  !! op_set: why the value is refused
   contains
      procedure :: on_real => design_real
      procedure :: on_real_list => design_real_list
   end type design_visitor_t

contains

   !> '&group name' or '&group name(i)' of a variable.
   pure function deck_variable_label(var) result(s)
      type(deck_variable_t), intent(in) :: var   !! variable
      character(len=:), allocatable :: s
      s = '&' // trim(var%group) // ' ' // trim(var%name)
      if (var%index > 0) s = s // '(' // str(var%index) // ')'
   end function deck_variable_label

   !> Parse '&group name', 'group name' or 'group%name', with '(i)' for a list entry.
   subroutine parse_deck_variable(text, var, err)
      character(len=*), intent(in) :: text              !! the name as written
      type(deck_variable_t), intent(out) :: var         !! the variable
      type(error_t), allocatable, intent(out) :: err    !! unknown variable
      character(len=:), allocatable :: t, g, n
      integer :: k, p, q, ios, idx
      t = trim(adjustl(to_lower(text)))
      if (len(t) > 0) then
         if (t(1:1) == '&') t = trim(adjustl(t(2:)))
      end if
      k = scan(t, ' %')
      if (k == 0) then
         call fatal_error(err, "variable '" // trim(text) // "': expected '&group name', e.g. " &
            // "'&forcing frequency_hz' or '&stops gap(1)'")
         return
      end if
      g = t(1:k - 1);  n = trim(adjustl(t(k + 1:)))
      idx = 0
      p = index(n, '(')
      if (p > 0) then
         q = index(n, ')')
         read(n(p + 1:max(p + 1, q - 1)), *, iostat=ios) idx
         if (q <= p + 1 .or. ios /= 0 .or. idx < 1) then
            call fatal_error(err, "variable '" // trim(text) // "': the entry index must be " &
               // "a whole number >= 1, e.g. '&stops gap(1)'")
            return
         end if
         n = n(1:p - 1)
      end if
      var%group = g;  var%name = n;  var%index = idx
      call describe(var, err)
      if (allocated(err)) then
         err%message = "variable '" // trim(text) // "': " // err%message
         return
      end if
      if (var%index < 0) then
         call fatal_error(err, "variable '" // trim(text) // "': &" // g // ' is not a ' &
            // 'list group (no entry index)')
         return
      end if
   end subroutine parse_deck_variable

   !> Parse a list of names separated by commas (one name: parse_deck_variable). The names
   !> must differ, share one unit, and a forcing variable must be the only one.
   subroutine parse_deck_variables(text, vars, err)
      character(len=*), intent(in) :: text                    !! the names as written
      type(deck_variable_t), allocatable, intent(out) :: vars(:)   !! the variables, in order
      type(error_t), allocatable, intent(out) :: err          !! unknown variable, bad list
      type(deck_variable_t) :: var
      integer :: a, b, j
      allocate(vars(0))
      a = 1
      do
         b = index(text(a:), ',')
         if (b == 0) then
            b = len(text) + 1
         else
            b = a + b - 1
         end if
         if (len_trim(text(a:b - 1)) == 0) then
            call fatal_error(err, "variables '" // trim(text) // "': an empty name in the " &
               // "list (names are separated by commas, e.g. '&stops gap(1), &stops gap(2)')")
            return
         end if
         call parse_deck_variable(text(a:b - 1), var, err)
         if (allocated(err)) return
         do j = 1, size(vars)
            if (deck_variable_label(vars(j)) == deck_variable_label(var)) then
               call fatal_error(err, "variables '" // trim(text) // "': '" &
                  // deck_variable_label(var) // "' is named twice")
               return
            end if
            if (vars(j)%units /= var%units) then
               call fatal_error(err, "variables '" // trim(text) // "': '" &
                  // deck_variable_label(var) // "' [" // trim(var%units) // '] and ' // "'" &
                  // deck_variable_label(vars(j)) // "' [" // trim(vars(j)%units) // '] ' &
                  // 'differ in unit: variables set together need one unit')
               return
            end if
         end do
         vars = [vars, var]
         if (b > len(text)) exit
         a = b + 1
      end do
      if (size(vars) > 1 .and. any(vars%group == 'forcing')) call fatal_error(err, &
         "variables '" // trim(text) // "': a &forcing variable cannot be set together with " &
         // 'others (it must be the only name)')
   end subroutine parse_deck_variables

   !> The labels of a list of variables, separated by ', '.
   pure function deck_variables_label(vars) result(s)
      type(deck_variable_t), intent(in) :: vars(:)   !! variables
      character(len=:), allocatable :: s
      integer :: j
      s = ''
      do j = 1, size(vars)
         if (j > 1) s = s // ', '
         s = s // deck_variable_label(vars(j))
      end do
   end function deck_variables_label

   !> Unit and range of a known variable (from the deck table).
   subroutine describe(var, err)
      type(deck_variable_t), intent(inout) :: var        !! group and name set
      type(error_t), allocatable, intent(out) :: err     !! unknown
      type(design_visitor_t) :: v
      type(deck_t) :: d
      v%op = op_describe;  v%describing = .true.
      v%target_group = var%group;  v%target_name = var%name
      call walk_deck(v, d)
      if (.not. v%group_found) then
         call fatal_error(err, 'unknown group &' // trim(var%group) // '; numeric variables: ' &
            // deck_variable_words())
      else if (.not. v%found) then
         call fatal_error(err, '&' // trim(var%group) // ' has no numeric variable ' &
            // trim(var%name) // '; numeric variables: ' // deck_variable_words())
      else
         var%units = v%spec%unit
         var%lower = v%spec%lo;  var%strict = v%spec%lo_open
         if (v%spec%zero .and. v%spec%lo > 0.0_dp) then
            var%lower = 0.0_dp;  var%strict = .false.
         end if
         if (v%in_list) then
            var%index = max(var%index, 1)
         else if (var%index > 0) then
            var%index = -1                   ! an index on a scalar: refused by the caller
         end if
      end if
   end subroutine describe

   !> The design variables, '&beam length, ...; &root k_theta; ...' (documentation, messages).
   function deck_variable_words() result(words)
      character(len=:), allocatable :: words
      type(design_visitor_t) :: v
      type(deck_t) :: d
      v%op = op_words;  v%describing = .true.;  v%words = ''
      call walk_deck(v, d)
      words = v%words
   end function deck_variable_words

   !> Describe, read or set the variable looked for; collect the names for op_words.
   subroutine design_real(self, s, x)
      class(design_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), intent(inout) :: x
      if (.not. s%design) return
      if (self%op == op_words) then
         if (index(self%words, '&' // trim(self%group) // ' ') == 0) then
            if (len(self%words) > 0) self%words = self%words // '; '
            self%words = self%words // '&' // trim(self%group) // ' ' // trim(s%name)
         else if (index(self%words, ' ' // trim(s%name) // ',') == 0 .and. &
                  .not. ends_with(self%words, ' ' // trim(s%name))) then
            self%words = self%words // ', ' // trim(s%name)
         end if
         return
      end if
      if (self%group /= self%target_group) return
      self%group_found = .true.
      if (s%name /= self%target_name) return
      if (self%op == op_describe) then
         self%found = .true.;  self%spec = s;  self%in_list = self%entry > 0
         return
      end if
      if (self%entry /= self%target_index) return
      self%found = .true.
      select case (self%op)
      case (op_get)
         self%x = x
      case (op_set)
         self%refused = spec_violation(s, self%x)
         if (len(self%refused) == 0) x = self%x
      end select
   contains
      pure logical function ends_with(t, tail)
         character(len=*), intent(in) :: t, tail
         ends_with = .false.
         if (len(t) >= len(tail)) ends_with = t(len(t) - len(tail) + 1:) == tail
      end function ends_with
   end subroutine design_real

   !> design_real for an element of a list variable (the target index is the element's).
   subroutine design_real_list(self, s, x)
      class(design_visitor_t), intent(inout) :: self
      type(deck_spec_t), intent(in) :: s
      real(dp), allocatable, intent(inout) :: x(:)
      real(dp) :: y
      if (.not. s%design) return
      if (self%op == op_words .or. self%op == op_describe) then
         y = 0.0_dp
         call design_real(self, s, y)
         if (self%op == op_describe .and. self%found .and. self%group == self%target_group &
             .and. s%name == self%target_name) self%in_list = .true.
         return
      end if
      if (self%group /= self%target_group .or. s%name /= self%target_name) return
      if (.not. allocated(x)) return
      if (self%target_index < 1 .or. self%target_index > size(x)) return
      self%found = .true.
      select case (self%op)
      case (op_get)
         self%x = x(self%target_index)
      case (op_set)
         self%refused = spec_violation(s, self%x)
         if (len(self%refused) == 0) x(self%target_index) = self%x
      end select
   end subroutine design_real_list

   !> The variable exists in this deck (list entry present, damping model matching).
   subroutine check_deck_variable(deck, var, err)
      type(deck_t), intent(in) :: deck                  !! deck
      type(deck_variable_t), intent(in) :: var          !! variable
      type(error_t), allocatable, intent(out) :: err    !! absent
      integer :: n
      character(len=:), allocatable :: lab
      lab = deck_variable_label(var)
      n = -1
      select case (trim(var%group))
      case ('springs')
         n = 0
         if (allocated(deck%structure%springs)) n = size(deck%structure%springs)
      case ('masses')
         n = 0
         if (allocated(deck%structure%masses)) n = size(deck%structure%masses)
      case ('stops')
         n = 0
         if (allocated(deck%stops)) n = size(deck%stops)
      case ('point_forces')
         n = 0
         if (allocated(deck%forcing%forces)) n = size(deck%forcing%forces)
      case ('root')
         if (deck%structure%root%condition /= 'spring') call fatal_error(err, lab &
            // ": the root is clamped (needs &root condition = 'spring')")
      case ('beam')
         select case (trim(var%name))
         case ('width', 'thickness')
            if (.not. (deck%structure%beam%width > 0.0_dp)) call fatal_error(err, &
               lab // ': the beam section is not a rectangle')
         case ('area', 'second_moment', 'fibre_distance')
            if (deck%structure%beam%width > 0.0_dp) call fatal_error(err, lab &
               // ': the beam section is a rectangle (vary width or thickness)')
         end select
      case ('damping')
         select case (trim(var%name))
         case ('mass_coefficient', 'stiffness_coefficient')
            if (deck%damping%model /= 'rayleigh' .and. deck%damping%model /= 'modal') &
               call fatal_error(err, lab // ": needs &damping model = 'rayleigh' or 'modal' " &
               // "(the deck has '" // trim(deck%damping%model) // "')")
         case ('modal_ratios')
            n = 0
            if (allocated(deck%damping%modal_ratios)) n = size(deck%damping%modal_ratios)
            if (deck%damping%model /= 'modal') then
               call fatal_error(err, lab // ": needs &damping model = 'modal' (the deck has '" &
                  // trim(deck%damping%model) // "')")
            else if (var%index > n) then
               call fatal_error(err, lab // ': the deck gives ' // str(n) // ' modal_ratios')
            end if
            n = -1
         case default
            if (deck%damping%model /= 'ratios') call fatal_error(err, lab &
               // ": needs &damping model = 'ratios' (the deck has '" &
               // trim(deck%damping%model) // "')")
         end select
      end select
      if (n >= 0 .and. var%index > n) call fatal_error(err, lab // ': the deck has ' &
         // str(n) // ' &' // trim(var%group) // ' entries')
      if (allocated(err)) return
      if (var%group == 'stops' .and. var%name == 'stiffness') then
         if (deck%stops(var%index)%rule_factor > 0.0_dp) call fatal_error(err, lab &
            // ': this stop takes its stiffness from the rule (rule_factor > 0): vary ' &
            // 'rule_factor instead')
      end if
   end subroutine check_deck_variable

   !> Current value of a variable in a deck (checked with check_deck_variable).
   function get_deck_value(deck, var) result(x)
      type(deck_t), intent(in) :: deck                  !! deck
      type(deck_variable_t), intent(in) :: var          !! variable
      real(dp) :: x
      type(design_visitor_t) :: v
      type(deck_t) :: d
      d = deck
      v%op = op_get
      v%target_group = var%group;  v%target_name = var%name;  v%target_index = var%index
      call walk_deck(v, d)
      if (.not. v%found) error stop 'gapbeam_deck_variable:get_deck_value: variable not parsed'
      x = v%x
   end function get_deck_value

   !> Set a variable on a deck, checking its range (and the Rayleigh coefficients that damping
   !> ratios give); the deck is unchanged on error.
   subroutine set_deck_value(deck, var, x, err)
      type(deck_t), intent(inout) :: deck               !! deck
      type(deck_variable_t), intent(in) :: var          !! variable (checked)
      real(dp), intent(in) :: x                         !! new value
      type(error_t), allocatable, intent(out) :: err    !! out of range
      type(design_visitor_t) :: v
      type(damping_t) :: dd
      real(dp) :: beta, gamma
      character(len=:), allocatable :: lab
      lab = deck_variable_label(var)
      if (var%group == 'damping' .and. index(var%name, '_coefficient') == 0 .and. &
          var%name /= 'modal_ratios') then
         ! a ratio or a frequency of model 'ratios': the coefficients follow
         dd = deck%damping
         call set_on(dd%frequency1_hz, 'frequency1_hz', var%name, x)
         call set_on(dd%ratio1, 'ratio1', var%name, x)
         call set_on(dd%frequency2_hz, 'frequency2_hz', var%name, x)
         call set_on(dd%ratio2, 'ratio2', var%name, x)
         call rayleigh_from_ratios(dd%frequency1_hz, dd%ratio1, dd%frequency2_hz, &
                                   dd%ratio2, beta, gamma)
         if (beta < 0.0_dp .or. gamma < 0.0_dp .or. &
             .not. (dd%frequency2_hz > dd%frequency1_hz)) then
            call fatal_error(err, lab // ' = ' // str(x) // ': the damping ' &
               // 'ratios give a negative Rayleigh coefficient or frequency2_hz <= ' &
               // 'frequency1_hz')
            return
         end if
      end if
      v%op = op_set;  v%x = x;  v%refused = ''
      v%target_group = var%group;  v%target_name = var%name;  v%target_index = var%index
      call walk_deck(v, deck)
      if (.not. v%found) error stop 'gapbeam_deck_variable:set_deck_value: variable not parsed'
      if (len(v%refused) > 0) then
         call fatal_error(err, lab // ' = ' // str(x) // ': ' // v%refused)
         return
      end if
      if (var%group == 'damping' .and. index(var%name, '_coefficient') == 0 .and. &
          var%name /= 'modal_ratios') then
         deck%damping%mass_coefficient = beta;  deck%damping%stiffness_coefficient = gamma
      end if
   contains
      !> y = x when the variable set is `name`.
      pure subroutine set_on(y, name, set_name, x)
         real(dp), intent(inout) :: y
         character(len=*), intent(in) :: name, set_name
         real(dp), intent(in) :: x
         if (set_name == name) y = x
      end subroutine set_on
   end subroutine set_deck_value

   !> Lower-case copy.
   pure function to_lower(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: i, c
      t = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) t(i:i) = achar(c + 32)
      end do
   end function to_lower
end module gapbeam_deck_variable
