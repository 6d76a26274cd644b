!> Kind parameters of gapbeam: every real is `real(dp)`.
module gapbeam_kinds
   use, intrinsic :: iso_fortran_env, only: dp => real64
   implicit none
   private
   public :: dp

   !> pi to double precision
   real(dp), parameter, public :: pi = 3.14159265358979323846264338327950288_dp
end module gapbeam_kinds
