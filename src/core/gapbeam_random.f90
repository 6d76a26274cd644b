!> Counter-based random numbers: every number is a pure function of (seed, stream, index), so a
!> random record depends on nothing but its key. No generator state is carried between calls:
!> the result does not depend on the thread count, on the order in which points or draws run,
!> or on what else was drawn before.
!>
!> The i-th number of stream (seed, stream) is SplitMix64(key + i) with
!> key = SplitMix64(SplitMix64(SplitMix64(seed) + stream) + substream) (Steele, Lea & Flood,
!> 2014: SplitMix64 passes BigCrush as a counter-based generator; the same mixer as the random
!> starts of src/analyses/gapbeam_starts). The top 53 bits make a double in [0, 1).
!> The arithmetic is modulo 2^64 (two's complement), as the mixer intends, emulated on 32-bit
!> halves so that no signed integer overflows (an optimiser may assume none does).
module gapbeam_random
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp, pi
   implicit none
   private
   public :: stream_key, uniform_at, normal_at, phase_at, splitmix64, add64

   integer(int64), parameter :: mask32 = 4294967295_int64   !! the low 32 bits

contains

   !> SplitMix64 output function of a 64-bit counter. The arithmetic is modulo 2^64 on the
   !> bit patterns, done without signed overflow (add64, mul64): an optimising compiler may
   !> assume that integer arithmetic does not overflow, and at -O3 gfortran folded the
   !> wrapping version of stream_key into one key for every (seed, stream, substream).
   pure integer(int64) function splitmix64(x) result(z)
      integer(int64), intent(in) :: x   !! counter
      integer(int64), parameter :: golden = -7046029254386353131_int64   ! 0x9E3779B97F4A7C15
      integer(int64), parameter :: m1 = -4658895280553007687_int64       ! 0xBF58476D1CE4E5B9
      integer(int64), parameter :: m2 = -7723592293110705685_int64       ! 0x94D049BB133111EB
      z = add64(x, golden)
      z = mul64(ieor(z, ishft(z, -30)), m1)
      z = mul64(ieor(z, ishft(z, -27)), m2)
      z = ieor(z, ishft(z, -31))
   end function splitmix64

   !> a + b modulo 2^64 (two's complement bit patterns), on 32-bit halves: no overflow.
   pure integer(int64) function add64(a, b) result(c)
      integer(int64), intent(in) :: a, b   !! addends
      integer(int64) :: lo, hi
      lo = iand(a, mask32) + iand(b, mask32)
      hi = iand(ishft(a, -32), mask32) + iand(ishft(b, -32), mask32) + ishft(lo, -32)
      c = ior(ishft(iand(hi, mask32), 32), iand(lo, mask32))
   end function add64

   !> a b modulo 2^64 (two's complement bit patterns), from 16-bit limbs: no overflow.
   pure integer(int64) function mul64(a, b) result(c)
      integer(int64), intent(in) :: a, b   !! factors
      integer(int64) :: al, ah, bl, bh, hi, lo, h1, l1, h2, l2, cross
      al = iand(a, mask32);  ah = iand(ishft(a, -32), mask32)
      bl = iand(b, mask32);  bh = iand(ishft(b, -32), mask32)
      call mul32(al, bl, hi, lo)
      call mul32(ah, bl, h1, l1)
      call mul32(al, bh, h2, l2)
      cross = iand(l1 + l2, mask32)
      c = ior(ishft(iand(hi + cross, mask32), 32), lo)
   end function mul64

   !> The 64-bit product of a, b < 2^32 as its 32-bit halves (every partial product < 2^33).
   pure subroutine mul32(a, b, hi, lo)
      integer(int64), intent(in) :: a, b     !! factors in [0, 2^32)
      integer(int64), intent(out) :: hi, lo  !! product = hi 2^32 + lo, both in [0, 2^32)
      integer(int64), parameter :: mask16 = 65535_int64
      integer(int64) :: a0, a1, b0, b1, mid
      a0 = iand(a, mask16);  a1 = ishft(a, -16)
      b0 = iand(b, mask16);  b1 = ishft(b, -16)
      mid = a0 * b1 + a1 * b0
      lo = a0 * b0 + ishft(iand(mid, mask16), 16)
      hi = a1 * b1 + ishft(mid, -16) + ishft(lo, -32)
      lo = iand(lo, mask32);  hi = iand(hi, mask32)
   end subroutine mul32

   !> The key of a stream: (seed, stream, substream) mixed into one 64-bit word.
   pure integer(int64) function stream_key(seed, stream, substream) result(key)
      integer, intent(in) :: seed        !! user seed
      integer, intent(in) :: stream      !! e.g. the draw
      integer, intent(in) :: substream   !! e.g. the plane and the component
      key = splitmix64(add64(splitmix64(add64(splitmix64(int(seed, int64)), &
                                              int(stream, int64))), int(substream, int64)))
   end function stream_key

   !> The i-th number of a stream, uniform in [0, 1).
   elemental real(dp) function uniform_at(key, i) result(u)
      integer(int64), intent(in) :: key   !! stream key (stream_key)
      integer(int64), intent(in) :: i     !! index in the stream
      integer(int64) :: z
      z = splitmix64(add64(key, i))
      u = real(ishft(z, -11), dp) / 9007199254740992.0_dp
   end function uniform_at

   !> The i-th phase of a stream, uniform in [0, 2 pi).
   elemental real(dp) function phase_at(key, i) result(phi)
      integer(int64), intent(in) :: key   !! stream key
      integer(int64), intent(in) :: i     !! index in the stream
      phi = 2.0_dp * pi * uniform_at(key, i)
   end function phase_at

   !> The i-th standard normal number of a stream (Box-Muller on the numbers 2i and 2i+1).
   elemental real(dp) function normal_at(key, i) result(x)
      integer(int64), intent(in) :: key   !! stream key
      integer(int64), intent(in) :: i     !! index in the stream
      real(dp) :: u1, u2
      u1 = 1.0_dp - uniform_at(key, 2_int64 * i)          ! in (0, 1]
      u2 = uniform_at(key, 2_int64 * i + 1_int64)
      x = sqrt(-2.0_dp * log(u1)) * cos(2.0_dp * pi * u2)
   end function normal_at
end module gapbeam_random
