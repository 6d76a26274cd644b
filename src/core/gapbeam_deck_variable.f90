!> A numeric deck variable named by its group and name, `&stops gap(2)`, `&forcing frequency_hz`:
!> parse the name, read and set its value on a deck_t, with its unit and its allowed range.
!>
!> This is the "parameter setter" of the analyses that vary a design variable (continuation of
!> periodic orbits, two-parameter bifurcation curves; maps over any variable later): they set
!> the value on a copy of the deck and rebuild the model from it (gapbeam_deck_parameter), so a
!> variable means exactly what it means in a deck (the stop-stiffness rule, the damping ratios
!> are applied again). Pure data: nothing numerical here.
!>
!> Variables (real scalars; list groups take an entry index, default 1):
!>   &beam length youngs_modulus density width thickness area second_moment fibre_distance
!>         added_mass
!>   &root k_theta      &springs(i) stiffness      &masses(i) mass inertia
!>   &stops(i) gap stiffness damping exponent rule_factor rule_f1_ratio rule_f1_hz friction
!>         wear_coefficient
!>   &point_forces(i) amplitude
!>   &damping mass_coefficient stiffness_coefficient frequency1_hz ratio1 frequency2_hz ratio2
!>   &forcing frequency_hz amplitude_pp
!> A list of names separated by commas, '&stops gap(1), &stops gap(2)', names several variables
!> set together to one value (a sweep axis that moves both baffles' clearance): they must have
!> one unit, and a forcing variable stands alone (parse_deck_variables).
!> Setting a damping ratio or frequency with model = 'ratios' recomputes the Rayleigh
!> coefficients (as the deck reader does); setting a coefficient needs model = 'rayleigh'.
module gapbeam_deck_variable
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_description, only: rayleigh_from_ratios, damping_t
   use gapbeam_deck, only: deck_t
   implicit none
   private
   public :: deck_variable_t, parse_deck_variable, check_deck_variable, get_deck_value, &
      set_deck_value, deck_variable_words, deck_variable_label, parse_deck_variables, &
      deck_variables_label

   !> The variables, 'group:name' (documentation and messages).
   character(len=*), parameter :: deck_variable_words = '&beam length, youngs_modulus, ' &
      // 'density, width, thickness, area, second_moment, fibre_distance, added_mass; &root ' &
      // 'k_theta; &springs stiffness; &masses mass, inertia; &stops gap, stiffness, damping, ' &
      // 'exponent, rule_factor, rule_f1_ratio, rule_f1_hz, friction, wear_coefficient; ' &
      // '&point_forces amplitude; &damping mass_coefficient, ' &
      // 'stiffness_coefficient, frequency1_hz, ratio1, frequency2_hz, ratio2; &forcing ' &
      // 'frequency_hz, amplitude_pp'

   !> A numeric deck variable.
   type :: deck_variable_t
      character(len=16) :: group = ''        !! namelist group, lower case, no '&'
      character(len=32) :: name = ''         !! variable
      integer :: index = 0                   !! entry of a list group (0: not a list group)
      character(len=16) :: units = ''        !! unit of its value
      real(dp) :: lower = 0.0_dp             !! allowed: value >= lower (or > lower)
      logical :: strict = .false.            !! value > lower (else >=)
   end type deck_variable_t

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
      var%group = g;  var%name = n
      call describe(var, err)
      if (allocated(err)) then
         err%message = "variable '" // trim(text) // "': " // err%message
         return
      end if
      select case (g)
      case ('springs', 'masses', 'stops', 'point_forces')
         var%index = max(idx, 1)
      case default
         if (idx > 0) then
            call fatal_error(err, "variable '" // trim(text) // "': &" // g // ' is not a ' &
               // 'list group (no entry index)')
            return
         end if
      end select
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

   !> Unit and range of a known variable.
   subroutine describe(var, err)
      type(deck_variable_t), intent(inout) :: var        !! group and name set
      type(error_t), allocatable, intent(out) :: err     !! unknown
      logical :: ok
      ok = .true.
      var%lower = 0.0_dp;  var%strict = .true.
      select case (trim(var%group))
      case ('beam')
         select case (trim(var%name))
         case ('length', 'width', 'thickness', 'fibre_distance');  var%units = 'm'
         case ('youngs_modulus');  var%units = 'Pa'
         case ('density');  var%units = 'kg/m^3'
         case ('area');  var%units = 'm^2'
         case ('second_moment');  var%units = 'm^4'
         case ('added_mass');  var%units = 'kg/m';  var%strict = .false.
         case default;  ok = .false.
         end select
      case ('root')
         ok = var%name == 'k_theta';  var%units = 'N m/rad'
      case ('springs')
         ok = var%name == 'stiffness';  var%units = 'N/m'
      case ('masses')
         ok = var%name == 'mass' .or. var%name == 'inertia';  var%strict = .false.
         var%units = merge('kg     ', 'kg m^2 ', var%name == 'mass')
      case ('stops')
         select case (trim(var%name))
         case ('gap');  var%units = 'm';  var%strict = .false.
         case ('stiffness');  var%units = 'N/m'
         case ('damping');  var%units = 'N s/m';  var%strict = .false.
         case ('exponent');  var%units = '-';  var%lower = 1.0_dp;  var%strict = .false.
         case ('rule_factor', 'rule_f1_ratio');  var%units = '-'
         case ('rule_f1_hz');  var%units = 'Hz'
         case ('friction');  var%units = '-';  var%strict = .false.
         case ('wear_coefficient');  var%units = '1/Pa';  var%strict = .false.
         case default;  ok = .false.
         end select
      case ('point_forces')
         ok = var%name == 'amplitude';  var%units = 'N';  var%strict = .false.
         var%lower = -huge(1.0_dp)
      case ('damping')
         var%strict = .false.
         select case (trim(var%name))
         case ('mass_coefficient');  var%units = '1/s'
         case ('stiffness_coefficient');  var%units = 's'
         case ('frequency1_hz', 'frequency2_hz');  var%units = 'Hz';  var%strict = .true.
         case ('ratio1', 'ratio2');  var%units = '-'
         case default;  ok = .false.
         end select
      case ('forcing')
         select case (trim(var%name))
         case ('frequency_hz');  var%units = 'Hz'
         case ('amplitude_pp');  var%units = 'm';  var%strict = .false.
         case default;  ok = .false.
         end select
      case default
         call fatal_error(err, 'unknown group &' // trim(var%group) // '; numeric variables: ' &
            // deck_variable_words)
         return
      end select
      if (.not. ok) call fatal_error(err, '&' // trim(var%group) // ' has no numeric variable ' &
         // trim(var%name) // '; numeric variables: ' // deck_variable_words)
   end subroutine describe

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
            if (deck%damping%model /= 'rayleigh') call fatal_error(err, lab &
               // ": needs &damping model = 'rayleigh' (the deck has '" &
               // trim(deck%damping%model) // "')")
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
      integer :: i
      i = var%index
      associate (b => deck%structure%beam)
         select case (trim(var%group) // ':' // trim(var%name))
         case ('beam:length');  x = b%length
         case ('beam:youngs_modulus');  x = b%youngs_modulus
         case ('beam:density');  x = b%density
         case ('beam:width');  x = b%width
         case ('beam:thickness');  x = b%thickness
         case ('beam:area');  x = b%area
         case ('beam:second_moment');  x = b%second_moment
         case ('beam:fibre_distance');  x = b%fibre_distance
         case ('root:k_theta');  x = deck%structure%root%k_theta
         case ('springs:stiffness');  x = deck%structure%springs(i)%stiffness
         case ('masses:mass');  x = deck%structure%masses(i)%mass
         case ('masses:inertia');  x = deck%structure%masses(i)%inertia
         case ('stops:gap');  x = deck%stops(i)%gap
         case ('stops:stiffness');  x = deck%stops(i)%stiffness
         case ('stops:damping');  x = deck%stops(i)%damping
         case ('stops:exponent');  x = deck%stops(i)%exponent
         case ('stops:rule_factor');  x = deck%stops(i)%rule_factor
         case ('stops:rule_f1_ratio');  x = deck%stops(i)%rule_f1_ratio
         case ('stops:rule_f1_hz');  x = deck%stops(i)%rule_f1_hz
         case ('stops:friction');  x = deck%stops(i)%friction
         case ('stops:wear_coefficient');  x = deck%stops(i)%wear_coefficient
         case ('beam:added_mass');  x = b%added_mass
         case ('point_forces:amplitude');  x = deck%forcing%forces(i)%amplitude
         case ('damping:mass_coefficient');  x = deck%damping%mass_coefficient
         case ('damping:stiffness_coefficient');  x = deck%damping%stiffness_coefficient
         case ('damping:frequency1_hz');  x = deck%damping%frequency1_hz
         case ('damping:ratio1');  x = deck%damping%ratio1
         case ('damping:frequency2_hz');  x = deck%damping%frequency2_hz
         case ('damping:ratio2');  x = deck%damping%ratio2
         case ('forcing:frequency_hz');  x = deck%forcing%frequency_hz
         case ('forcing:amplitude_pp');  x = deck%forcing%amplitude_pp
         case default
            error stop 'gapbeam_deck_variable:get_deck_value: variable not parsed'
         end select
      end associate
   end function get_deck_value

   !> Set a variable on a deck, checking its range (and the Rayleigh coefficients that damping
   !> ratios give); the deck is unchanged on error.
   subroutine set_deck_value(deck, var, x, err)
      type(deck_t), intent(inout) :: deck               !! deck
      type(deck_variable_t), intent(in) :: var          !! variable (checked)
      real(dp), intent(in) :: x                         !! new value
      type(error_t), allocatable, intent(out) :: err    !! out of range
      integer :: i
      real(dp) :: beta, gamma
      type(damping_t) :: dd
      character(len=:), allocatable :: lab
      lab = deck_variable_label(var)
      if (.not. (x >= var%lower) .or. (var%strict .and. .not. (x > var%lower)) .or. &
          abs(x) > huge(x)) then
         call fatal_error(err, lab // ' = ' // str(x) // ': must be ' &
            // trim(merge('> ', '>=', var%strict)) // ' ' // str(var%lower) // ' and finite')
         return
      end if
      i = var%index
      associate (b => deck%structure%beam)
         select case (trim(var%group) // ':' // trim(var%name))
         case ('beam:length');  b%length = x
         case ('beam:youngs_modulus');  b%youngs_modulus = x
         case ('beam:density');  b%density = x
         case ('beam:width');  b%width = x
         case ('beam:thickness');  b%thickness = x
         case ('beam:area');  b%area = x
         case ('beam:second_moment');  b%second_moment = x
         case ('beam:fibre_distance');  b%fibre_distance = x
         case ('root:k_theta');  deck%structure%root%k_theta = x
         case ('springs:stiffness');  deck%structure%springs(i)%stiffness = x
         case ('masses:mass');  deck%structure%masses(i)%mass = x
         case ('masses:inertia');  deck%structure%masses(i)%inertia = x
         case ('stops:gap');  deck%stops(i)%gap = x
         case ('stops:stiffness');  deck%stops(i)%stiffness = x
         case ('stops:damping');  deck%stops(i)%damping = x
         case ('stops:exponent');  deck%stops(i)%exponent = x
         case ('stops:rule_factor');  deck%stops(i)%rule_factor = x
         case ('stops:rule_f1_ratio');  deck%stops(i)%rule_f1_ratio = x
         case ('stops:rule_f1_hz');  deck%stops(i)%rule_f1_hz = x
         case ('stops:friction');  deck%stops(i)%friction = x
         case ('stops:wear_coefficient');  deck%stops(i)%wear_coefficient = x
         case ('beam:added_mass');  b%added_mass = x
         case ('point_forces:amplitude');  deck%forcing%forces(i)%amplitude = x
         case ('damping:mass_coefficient');  deck%damping%mass_coefficient = x
         case ('damping:stiffness_coefficient');  deck%damping%stiffness_coefficient = x
         case ('damping:frequency1_hz', 'damping:ratio1', 'damping:frequency2_hz', &
               'damping:ratio2')
            dd = deck%damping
            select case (trim(var%name))
            case ('frequency1_hz');  dd%frequency1_hz = x
            case ('ratio1');  dd%ratio1 = x
            case ('frequency2_hz');  dd%frequency2_hz = x
            case ('ratio2');  dd%ratio2 = x
            end select
            call rayleigh_from_ratios(dd%frequency1_hz, dd%ratio1, dd%frequency2_hz, &
                                      dd%ratio2, beta, gamma)
            if (beta < 0.0_dp .or. gamma < 0.0_dp .or. &
                .not. (dd%frequency2_hz > dd%frequency1_hz)) then
               call fatal_error(err, lab // ' = ' // str(x) // ': the damping ' &
                  // 'ratios give a negative Rayleigh coefficient or frequency2_hz <= ' &
                  // 'frequency1_hz')
               return
            end if
            dd%mass_coefficient = beta;  dd%stiffness_coefficient = gamma
            deck%damping = dd
         case ('forcing:frequency_hz');  deck%forcing%frequency_hz = x
         case ('forcing:amplitude_pp');  deck%forcing%amplitude_pp = x
         case default
            error stop 'gapbeam_deck_variable:set_deck_value: variable not parsed'
         end select
      end associate
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
