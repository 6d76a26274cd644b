!> Recoverable errors and the text helpers used to build their messages.
!>
!> A procedure that can fail for a reason the user can fix (bad deck, LAPACK `info`,
!> no convergence, file I/O) returns an allocated `error_t` in its last argument;
!> the caller checks `allocated(err)` at once. Only `app/main.f90` ends the run.
module gapbeam_error
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: error_t, fatal_error, str, printable, quoted

   !> A recoverable failure: 'where: what (values)'.
   type :: error_t
      character(len=:), allocatable :: message   !! human-readable description
   end type error_t

   !> Number or logical to text, without surrounding blanks.
   interface str
      module procedure str_int, str_int64, str_real, str_logical
   end interface str

contains

   !> Text safe to print: every control character (ASCII 0-31 and 127, which a terminal would
   !> act on: escape sequences, bells, backspaces) written as an escape, `\t`, `\n`, `\r` or
   !> `\xHH` (two lower-case hex digits), as Python's repr writes them. Bytes above 127 (UTF-8)
   !> are kept.
   pure function printable(text) result(s)
      character(len=*), intent(in) :: text     !! text from a deck, a file or the command line
      character(len=:), allocatable :: s
      character(len=*), parameter :: hex = '0123456789abcdef'
      integer :: i, c, n
      n = 0
      do i = 1, len(text)
         c = iachar(text(i:i))
         n = n + 1
         if (c == 9 .or. c == 10 .or. c == 13) then
            n = n + 1
         else if (c < 32 .or. c == 127) then
            n = n + 3
         end if
      end do
      allocate(character(len=n) :: s)
      n = 0
      do i = 1, len(text)
         c = iachar(text(i:i))
         select case (c)
         case (9)
            s(n + 1:n + 2) = '\t';  n = n + 2
         case (10)
            s(n + 1:n + 2) = '\n';  n = n + 2
         case (13)
            s(n + 1:n + 2) = '\r';  n = n + 2
         case (0:8, 11, 12, 14:31, 127)
            s(n + 1:n + 4) = '\x' // hex(c / 16 + 1:c / 16 + 1) &
                             // hex(mod(c, 16) + 1:mod(c, 16) + 1)
            n = n + 4
         case default
            s(n + 1:n + 1) = text(i:i);  n = n + 1
         end select
      end do
   end function printable

   !> Allocate `err` with `message` (keeps the first error if one is already set).
   subroutine fatal_error(err, message)
      type(error_t), allocatable, intent(inout) :: err   !! error to set
      character(len=*), intent(in) :: message           !! what went wrong, and where
      if (allocated(err)) return
      allocate(err)
      err%message = message
   end subroutine fatal_error

   !> Integer to text.
   pure function str_int(i) result(s)
      integer, intent(in) :: i                 !! value
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end function str_int

   !> 64-bit integer to text.
   pure function str_int64(i) result(s)
      integer(int64), intent(in) :: i          !! value
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') i
      s = trim(buf)
   end function str_int64

   !> Text in single quotes, for messages: 'results/x.h5'.
   pure function quoted(text) result(s)
      character(len=*), intent(in) :: text     !! text
      character(len=:), allocatable :: s
      s = "'" // text // "'"
   end function quoted

   !> Real to text with enough digits to tell values apart (`g0` style, 8 significant digits).
   pure function str_real(x) result(s)
      real(dp), intent(in) :: x                !! value
      character(len=:), allocatable :: s
      character(len=32) :: buf
      if (x /= x) then
         s = 'NaN'
      else if (abs(x) > huge(x)) then
         if (x > 0) then
            s = 'Infinity'
         else
            s = '-Infinity'
         end if
      else if (x == 0.0_dp) then
         s = '0'
      else if (abs(x) >= 0.1_dp .and. abs(x) < 1.0e6_dp) then
         write(buf, '(g0.8)') x
         s = trim(adjustl(buf))
         call strip_zeros(s)
      else
         write(buf, '(es15.7e3)') x
         s = trim(adjustl(buf))
         call strip_mantissa_zeros(s)
      end if
   end function str_real

   !> Logical to text.
   pure function str_logical(b) result(s)
      logical, intent(in) :: b                 !! value
      character(len=:), allocatable :: s
      if (b) then
         s = '.true.'
      else
         s = '.false.'
      end if
   end function str_logical

   !> Remove trailing zeros of the mantissa ("1.9125000E-003" -> "1.9125E-003").
   pure subroutine strip_mantissa_zeros(s)
      character(len=:), allocatable, intent(inout) :: s
      integer :: e, k
      e = scan(s, 'eE')
      if (e == 0) return
      k = e - 1
      do while (k > 1 .and. s(k:k) == '0')
         k = k - 1
      end do
      if (s(k:k) == '.') k = k - 1
      s = s(1:k) // s(e:)
   end subroutine strip_mantissa_zeros

   !> Remove trailing zeros of a fixed-point number ("4.3000000" -> "4.3").
   pure subroutine strip_zeros(s)
      character(len=:), allocatable, intent(inout) :: s
      integer :: k
      if (index(s, '.') == 0 .or. scan(s, 'eE') > 0) return
      k = len(s)
      do while (k > 1 .and. s(k:k) == '0')
         k = k - 1
      end do
      if (s(k:k) == '.') k = k - 1
      s = s(1:k)
   end subroutine strip_zeros
end module gapbeam_error
