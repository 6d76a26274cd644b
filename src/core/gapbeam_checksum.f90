!> CRC-32, the zlib and PNG checksum, of bytes or of a text: the deck hash of a checkpoint
!> and its records (io/gapbeam_checkpoint), the `deck_crc32` attribute of every result file
!> and the signature of a shard deal (jobs/gapbeam_shards). A pure kernel, so in core.
module gapbeam_checksum
   use, intrinsic :: iso_fortran_env, only: int8, int64
   implicit none
   private
   public :: crc32, text_bytes, crc32_hex

contains

   !> The bytes of a text.
   pure function text_bytes(text) result(b)
      character(len=*), intent(in) :: text             !! text
      integer(int8), allocatable :: b(:)
      integer :: i
      allocate(b(len(text)))
      do i = 1, len(text)
         b(i) = int(iachar(text(i:i)) - merge(256, 0, iachar(text(i:i)) > 127), int8)
      end do
   end function text_bytes

   !> CRC-32 (the zlib and PNG checksum: reflected polynomial 0xEDB88320) of `bytes`, continuing
   !> from `previous` (the CRC of the bytes before) when given; a value in 0..2**32-1.
   pure function crc32(bytes, previous) result(crc)
      integer(int8), intent(in) :: bytes(:)            !! data
      integer(int64), intent(in), optional :: previous !! CRC of the preceding data
      integer(int64) :: crc
      integer(int64), parameter :: poly = 3988292384_int64     ! 0xEDB88320
      integer(int64), parameter :: mask = 4294967295_int64     ! 0xFFFFFFFF
      integer :: i, k
      crc = 0
      if (present(previous)) crc = previous
      crc = ieor(crc, mask)
      do i = 1, size(bytes)
         crc = ieor(crc, iand(int(bytes(i), int64), 255_int64))
         do k = 1, 8
            if (iand(crc, 1_int64) /= 0) then
               crc = ieor(ishft(crc, -1), poly)
            else
               crc = ishft(crc, -1)
            end if
         end do
      end do
      crc = ieor(crc, mask)
   end function crc32

   !> CRC-32 (zlib's) of a text as 8 lower-case hex digits.
   pure function crc32_hex(text) result(h)
      character(len=*), intent(in) :: text               !! the text
      character(len=:), allocatable :: h
      character(len=8) :: buf
      integer :: i
      write(buf, '(z8.8)') crc32(text_bytes(text))
      h = buf
      do i = 1, len(h)
         if (h(i:i) >= 'A' .and. h(i:i) <= 'F') h(i:i) = achar(iachar(h(i:i)) + 32)
      end do
   end function crc32_hex
end module gapbeam_checksum
