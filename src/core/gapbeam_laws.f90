!> The registry of contact (stop) laws: the laws a deck may name in &stops law, in the order
!> of their codes. Adding a law is one module extending contact_law_t (gapbeam_law) and one
!> line in `builtin_laws`; everything else (the reader's checks, the integrators' refusals,
!> `method = 'auto'`, the help text and the capability table of docs/methods.md) reads the
!> law's `caps`.
!>
!> A model carries its laws (model_t%laws, filled from this registry by the model builder), so
!> a law that is not built in (a test's) is added to one model with `add_law`.
module gapbeam_laws
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   use gapbeam_law, only: contact_law_t, law_caps_t, law_slot_t
   use gapbeam_law_bilinear, only: bilinear_law_t
   use gapbeam_law_hertz, only: hertz_law_t
   implicit none
   private
   public :: builtin_laws, law_index, law_words, law_caps_of, add_law, stop_law_refusal

contains

   !> Every law a deck may name; a law's code is its position here.
   pure function builtin_laws() result(laws)
      type(law_slot_t), allocatable :: laws(:)
      allocate(laws(0))
      call push_law(laws, bilinear_law_t())
      call push_law(laws, hertz_law_t())
   end function builtin_laws

   !> Code (position) of the law named `word` among `laws` (default: the built-in ones); 0 if
   !> none has that name.
   pure function law_index(word, laws) result(code)
      character(len=*), intent(in) :: word                 !! law name
      type(law_slot_t), intent(in), optional :: laws(:)    !! registry (default: built in)
      integer :: code
      type(law_slot_t), allocatable :: all(:)
      if (present(laws)) then
         all = laws
      else
         all = builtin_laws()
      end if
      do code = 1, size(all)
         if (all(code)%law%name() == trim(word)) return
      end do
      code = 0
   end function law_index

   !> The capabilities of the law named `word` (name '' when there is none).
   pure function law_caps_of(word) result(c)
      character(len=*), intent(in) :: word   !! law name
      type(law_caps_t) :: c
      type(law_slot_t), allocatable :: all(:)
      integer :: code
      all = builtin_laws()
      code = law_index(word, all)
      if (code > 0) c = all(code)%law%caps()
   end function law_caps_of

   !> The law names as a reader lists them: "'bilinear', 'hertz'".
   pure function law_words(laws) result(t)
      type(law_slot_t), intent(in), optional :: laws(:)    !! registry (default: built in)
      character(len=:), allocatable :: t
      type(law_slot_t), allocatable :: all(:)
      integer :: j
      if (present(laws)) then
         all = laws
      else
         all = builtin_laws()
      end if
      t = ''
      do j = 1, size(all)
         if (j > 1) t = t // ', '
         t = t // "'" // all(j)%law%name() // "'"
      end do
   end function law_words

   !> Add `law` to `laws` (a model's, or a registry copy) unless one of that name is there;
   !> its code.
   function add_law(laws, law) result(code)
      type(law_slot_t), allocatable, intent(inout) :: laws(:)   !! laws
      class(contact_law_t), intent(in) :: law                   !! the new law
      integer :: code
      if (.not. allocated(laws)) allocate(laws(0))
      code = law_index(law%name(), laws)
      if (code > 0) return
      call push_law(laws, law)
      code = size(laws)
   end function add_law

   !> Append `law` to `laws`.
   pure subroutine push_law(laws, law)
      type(law_slot_t), allocatable, intent(inout) :: laws(:)   !! laws
      class(contact_law_t), intent(in) :: law                   !! the new law
      type(law_slot_t), allocatable :: more(:)
      integer :: j, n
      n = size(laws)
      allocate(more(n + 1))
      do j = 1, n
         call move_alloc(laws(j)%law, more(j)%law)
      end do
      allocate(more(n + 1)%law, source=law)
      call move_alloc(more, laws)
   end subroutine push_law

   !> Why a stop with this law and these parameters is refused, or '' (for the &stops reader;
   !> `ix` is the stop's index as the deck writes it, '(2)'): a damper with a law that has
   !> none, an exponent outside the law's range, friction with a law whose stiffness is not a
   !> stick stiffness and no tangential_stiffness, a ring support with a law that cannot be
   !> its normal law.
   function stop_law_refusal(word, ix, damping, exponent, ring, friction, k_t) result(why)
      character(len=*), intent(in) :: word        !! &stops law
      character(len=*), intent(in) :: ix          !! '(i)' of the stop
      real(dp), intent(in) :: damping             !! &stops damping [N s/m]
      real(dp), intent(in) :: exponent            !! &stops exponent [-]
      logical, intent(in) :: ring                 !! circular clearance or friction
      real(dp), intent(in) :: friction            !! &stops friction [-]
      real(dp), intent(in) :: k_t                 !! &stops tangential_stiffness [N/m]
      character(len=:), allocatable :: why
      type(law_caps_t) :: c
      why = ''
      c = law_caps_of(word)
      if (len_trim(c%name) == 0) return           ! the word check reports it
      if (c%uses_exponent .and. .not. (exponent >= c%exponent_min .and. &
          exponent <= c%exponent_max)) then
         why = 'exponent' // ix // ' = ' // str(exponent) // ': must be in [' &
            // str(c%exponent_min) // ', ' // str(c%exponent_max) // "] for law = '" &
            // trim(c%name) // "'"
      else if (damping > 0.0_dp .and. .not. c%uses_damping) then
         why = 'damping' // ix // ' = ' // str(damping) // ": law = '" // trim(c%name) &
            // "' has no contact damper (" // trim(c%force_text) // '); a damper needs ' &
            // damper_laws()
      else if (ring .and. .not. c%rings) then
         why = "law" // ix // " = '" // trim(c%name) // "' cannot be the normal law of a " &
            // 'support with a circular clearance or friction'
      else if (friction > 0.0_dp .and. .not. c%linear_stiffness .and. &
               .not. (k_t > 0.0_dp)) then
         why = 'friction' // ix // ' = ' // str(friction) // " with law = '" // trim(c%name) &
            // "' needs tangential_stiffness" // ix // ' > 0 [N/m] (the stick stiffness; ' &
            // 'with the bilinear law it defaults to the normal stiffness)'
      end if
   end function stop_law_refusal

   !> The laws with a contact damper: "law='bilinear'" (joined by ' or ').
   function damper_laws() result(t)
      character(len=:), allocatable :: t
      type(law_slot_t), allocatable :: all(:)
      type(law_caps_t) :: c
      integer :: j
      all = builtin_laws()
      t = ''
      do j = 1, size(all)
         c = all(j)%law%caps()
         if (.not. c%uses_damping) cycle
         if (len(t) > 0) t = t // ' or '
         t = t // "law='" // trim(c%name) // "'"
      end do
   end function damper_laws
end module gapbeam_laws
