!> Kind parameters of gapbeam: every real is `real(dp)` (`xp` only for extended-precision
!> residuals).
module gapbeam_kinds
   use, intrinsic :: iso_fortran_env, only: dp => real64
   implicit none
   private
   public :: dp, xp

   !> Extended precision for residuals and refinements (the exact integrator's modal data): the
   !> 80-bit x87 type where the compiler has it (gfortran), else quad, else double.
   integer, parameter :: xp = merge(selected_real_kind(18), merge(selected_real_kind(33), dp, &
                                    selected_real_kind(33) > 0), selected_real_kind(18) > 0)

   !> pi to double precision
   real(dp), parameter, public :: pi = 3.14159265358979323846264338327950288_dp
end module gapbeam_kinds
