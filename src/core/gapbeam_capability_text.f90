!> The capability registries in words: the tables of docs/methods.md (Markdown; a test
!> compares the document with them) and the lines of `gapbeam --help`. Text only, no I/O.
module gapbeam_capability_text
   use gapbeam_kinds, only: dp
   use gapbeam_capabilities, only: method_caps_t, method_table
   use gapbeam_law, only: law_caps_t, law_slot_t
   use gapbeam_laws, only: builtin_laws
   implicit none
   private
   public :: capability_markdown, capability_help

   character(len=1), parameter :: nl = new_line('a')

contains

   !> The two Markdown tables (methods, stop laws), each row from one registry entry.
   function capability_markdown() result(t)
      character(len=:), allocatable :: t
      type(method_caps_t), allocatable :: m(:)
      type(law_slot_t), allocatable :: laws(:)
      type(law_caps_t) :: c
      integer :: j
      m = method_table()
      t = '| `method` | kind | order | error estimate (controller order) | step_control | ' &
         // 'stability (ω_max Δt) | two planes, point forces | rings, friction | contact ' &
         // 'dampers | laws not piecewise linear | massless dofs | exponent with | flow ' &
         // 'Jacobian |' // nl // '|---|---|---|---|---|---|---|---|---|---|---|---|---|' // nl
      do j = 1, size(m)
         t = t // '| `''' // trim(m(j)%name) // '''` | ' // kind_text(m(j)) // ' | ' &
            // order_text(m(j)) // ' | ' // estimate_text(m(j)) // ' | ' &
            // controls_text(m(j)) // ' | ' // limit_text(m(j)%stability_limit) // ' | ' &
            // yes(m(j)%two_planes .and. m(j)%point_forces) // ' | ' // rings_text(m(j)) &
            // ' | ' // yes(m(j)%dampers) // ' | ' // yes(m(j)%nonlinear_laws) // ' | ' &
            // yes(m(j)%massless) // ' | ' // with_text(m(j)%lyapunov_with) // ' | ' &
            // trim(merge('exact', 'no   ', m(j)%jacobian)) // ' |' // nl
      end do
      laws = builtin_laws()
      t = t // nl // '| `law` | force | piecewise linear (exact integrator, flow Jacobian) ' &
         // '| `damping` | `exponent` | ring supports | stick stiffness |' // nl &
         // '|---|---|---|---|---|---|---|' // nl
      do j = 1, size(laws)
         c = laws(j)%law%caps()
         t = t // '| `''' // trim(c%name) // '''` | ' // trim(c%force_text) // ' | ' &
            // yes(c%piecewise_linear) // ' | ' // yes(c%uses_damping) // ' | ' &
            // exponent_text(c) // ' | ' // yes(c%rings) // ' | ' &
            // trim(merge('defaults to `stiffness`', 'must be given          ', &
            c%linear_stiffness)) // ' |' // nl
      end do
   end function capability_markdown

   !> The lines of `--help`: one per method and per law.
   function capability_help() result(t)
      character(len=:), allocatable :: t
      type(method_caps_t), allocatable :: m(:)
      type(law_slot_t), allocatable :: laws(:)
      type(law_caps_t) :: c
      character(len=20) :: name
      integer :: j
      m = method_table()
      t = "Methods (&solver method; 'auto' chooses among them):" // nl
      do j = 1, size(m)
         name = m(j)%name
         t = t // '  ' // name // kind_text(m(j)) // ', order ' // order_text(m(j)) // '; ' &
            // trim(help_limits(m(j))) // nl
      end do
      laws = builtin_laws()
      t = t // 'Stop laws (&stops law):' // nl
      do j = 1, size(laws)
         c = laws(j)%law%caps()
         name = c%name
         t = t // '  ' // name // trim(c%force_text) // merge('; piecewise linear    ', &
            '; not piecewise linear', c%piecewise_linear) // nl
      end do
      t = t // 'What each can do: docs/methods.md (the capability tables).'
   end function capability_help

   !> What a method does not handle, for --help.
   function help_limits(c) result(t)
      type(method_caps_t), intent(in) :: c
      character(len=:), allocatable :: t
      t = ''
      if (.not. c%two_planes) t = t // 'planar only, '
      if (.not. c%rings) t = t // 'no rings/friction, '
      if (.not. c%nonlinear_laws) t = t // 'piecewise-linear laws only, '
      if (.not. c%massless) t = t // 'a mass at every dof, '
      if (c%stability_limit > 0.0_dp) t = t // 'stable for omega dt < ' &
         // trim(num(c%stability_limit)) // ', '
      if (len(t) == 0) then
         t = 'any model'
      else
         t = t(:len(t) - 2)
      end if
   end function help_limits

   function controls_text(c) result(t)
      type(method_caps_t), intent(in) :: c
      character(len=:), allocatable :: t
      if (c%exact) then
         t = 'any (none applies)'
      else
         t = trim(c%controls)
      end if
   end function controls_text

   function kind_text(c) result(t)
      type(method_caps_t), intent(in) :: c
      character(len=:), allocatable :: t
      if (c%exact) then
         t = 'event driven, closed form'
      else if (c%implicit) then
         t = 'implicit'
      else
         t = 'explicit'
      end if
   end function kind_text

   function order_text(c) result(t)
      type(method_caps_t), intent(in) :: c
      character(len=:), allocatable :: t
      if (c%exact) then
         t = 'exact (round-off)'
      else
         t = trim(num(real(c%order, dp)))
      end if
   end function order_text

   function estimate_text(c) result(t)
      type(method_caps_t), intent(in) :: c
      character(len=:), allocatable :: t
      select case (c%estimator)
      case ('newmark')
         t = 'a₁ − a₀ of the step (' // trim(num(real(c%control_order, dp))) // ')'
      case ('embedded')
         t = 'embedded pair (' // trim(num(real(c%control_order, dp))) // ')'
      case default
         t = '–'
      end select
   end function estimate_text

   function limit_text(x) result(t)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: t
      if (x > 0.0_dp) then
         t = trim(num(x))
      else
         t = 'unconditional'
      end if
   end function limit_text

   function rings_text(c) result(t)
      type(method_caps_t), intent(in) :: c
      character(len=:), allocatable :: t
      if (c%rings) then
         t = "yes (step_control = 'error')"
      else
         t = 'no'
      end if
   end function rings_text

   function with_text(name) result(t)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: t
      if (len_trim(name) == 0) then
         t = 'itself'
      else
         t = '`''' // trim(name) // '''`'
      end if
   end function with_text

   function exponent_text(c) result(t)
      type(law_caps_t), intent(in) :: c
      character(len=:), allocatable :: t
      if (c%uses_exponent) then
         t = '[' // trim(num(c%exponent_min)) // ', ' // trim(num(c%exponent_max)) // ']'
      else
         t = '–'
      end if
   end function exponent_text

   pure function yes(flag) result(t)
      logical, intent(in) :: flag
      character(len=:), allocatable :: t
      if (flag) then
         t = 'yes'
      else
         t = 'no'
      end if
   end function yes

   !> A number in at most 4 significant digits, without trailing zeros.
   function num(x) result(t)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: t
      character(len=24) :: buf
      write(buf, '(g0.4)') x
      t = trim(adjustl(buf))
      if (index(t, '.') > 0 .and. index(t, 'E') == 0) then
         do while (t(len(t):len(t)) == '0')
            t = t(:len(t) - 1)
         end do
         if (t(len(t):len(t)) == '.') t = t(:len(t) - 1)
      end if
   end function num
end module gapbeam_capability_text
