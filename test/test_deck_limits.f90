!> The bounds that keep reading a deck cheap whatever its text (gapbeam_deck_text): a deck
!> file above 8 MiB, more than 250,000 values in one source (repeats counted), more than
!> 10,000 assignments in a group or 1,000 groups are refused with a one-line error naming the
!> bound; decks just inside each bound are read past it (a 40 MB deck took 1.3 GB and minutes
!> before: values were appended one copy at a time).
program test_deck_limits
   use gapbeam_error, only: error_t
   use gapbeam_testing, only: check, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   implicit none
   character(len=*), parameter :: tmp = 'test_deck_limits_tmp.nml'
   character(len=1), parameter :: nl = achar(10)
   character(len=*), parameter :: base = "&job analysis = 'modes' /" // nl &
      // '&beam length = 0.2, n_elem = 4, youngs_modulus = 2e11, density = 7850, ' &
      // 'width = 7e-3, thickness = 2.6e-4 /' // nl
   character(len=:), allocatable :: text
   integer :: k

   ! a file above 8 MiB: refused before it is read
   text = base // repeat('! a comment line of a deck far too long to be one' // nl, 172000)
   call expect('a deck file of ' // itoa(len(text)) // ' bytes', text, &
      'more than a deck may have (8388608 bytes')
   text = base // repeat('! a comment line of a deck far too long to be one' // nl, 167000)
   call expect('a deck file of ' // itoa(len(text)) // ' bytes (under 8 MiB)', text, '')
   ! values: 250,000 in one source at most (a list of 250,001 refused; repeats counted)
   text = base // '&sweep frequency_hz = ' // repeat('1.0, ', 250000) // '1.0 /' // nl
   call expect('250,001 values in a list', text, 'more than 250000 values in one deck file')
   text = base // '&sweep frequency_hz = 100000*1.0, 100000*1.0, 50001*1.0 /' // nl
   call expect('250,001 values by repeats', text, 'more than 250000 values')
   text = base // '&sweep frequency_hz = 100000*1.0, 100000*1.0, 49990*1.0 /' // nl
   call expect('249,990 values by repeats: past the bound', text, '')
   ! assignments in one group and groups in one source
   text = base // '&sweep'
   do k = 1, 10001
      text = text // ' frequency_hz(' // itoa(k) // ') = 1.0'
   end do
   call expect('10,001 assignments in a group', text // ' /' // nl, &
      'group &sweep: more than 10000 assignments')
   text = base // repeat('&output /' // nl, 1001)
   call expect('1,001 groups', text, 'more than 1000 groups')
   call finish('test_deck_limits')

contains

   !> Read `text` as a deck file: an error that holds `fragment`, or (fragment '') any
   !> outcome but an error about a bound.
   subroutine expect(name, text, fragment)
      character(len=*), intent(in) :: name, text, fragment
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      character(len=1) :: none(0)
      integer :: unit
      logical :: bounded
      open(newunit=unit, file=tmp, access='stream', form='unformatted', status='replace', &
           action='write')
      write(unit) text
      close(unit)
      call read_deck(tmp, none, deck, err)
      open(newunit=unit, file=tmp, status='old')
      close(unit, status='delete')
      if (len(fragment) == 0) then
         ! a deck at its bounds reads; any error it has is not a bound's (Fortran's .or. does
         ! not short-circuit: err%message is read only when err is allocated)
         bounded = .false.
         if (allocated(err)) then
            call note(name // ': ' // err%message)
            bounded = index(err%message, 'more than') > 0
         end if
         call check(name // ': read at the bounds (no bound refuses it)', .not. bounded)
         return
      end if
      call check(name // ': refused', allocated(err))
      if (.not. allocated(err)) return
      call note(name // ': ' // err%message)
      call check(name // ': the message names the bound', index(err%message, fragment) > 0 &
         .and. index(err%message, tmp // ': ') == 1)
   end subroutine expect

   function itoa(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=16) :: b
      write(b, '(i0)') i
      s = trim(b)
   end function itoa
end program test_deck_limits
