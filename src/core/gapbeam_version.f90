!> What gapbeam is: its version, the compiler that built it, and the source commit when the
!> scripts that built it said which.
!>
!> The version must equal `version` in fpm.toml (scripts/test_cli.sh checks `gapbeam --version`
!> against it). The program cannot know the git commit of its own sources: fpm has no build
!> hook to bake it in, and a value baked in by hand would go stale. The scripts that build and
!> then run it (run.sh, test.sh, slurm_sweep.sh) export GAPBEAM_GIT_COMMIT from `git describe`;
!> without it the commit is 'unknown'.
module gapbeam_version
   use, intrinsic :: iso_fortran_env, only: compiler_version
   implicit none
   private
   public :: program_version, compiler_text, git_commit

   !> Version of the program (fpm.toml `version`).
   character(len=*), parameter :: program_version = '0.1.0'

contains

   !> The compiler that built the program, e.g. 'GCC version 12.2.0'.
   function compiler_text() result(t)
      character(len=:), allocatable :: t
      t = compiler_version()
   end function compiler_text

   !> The source commit as GAPBEAM_GIT_COMMIT gives it (set by the repository's scripts), else
   !> 'unknown'.
   function git_commit() result(t)
      character(len=:), allocatable :: t
      integer :: l, st
      call get_environment_variable('GAPBEAM_GIT_COMMIT', length=l, status=st)
      if (st /= 0 .or. l == 0) then
         t = 'unknown'
         return
      end if
      allocate(character(len=l) :: t)
      call get_environment_variable('GAPBEAM_GIT_COMMIT', t)
      t = trim(t)
      if (len(t) == 0 .or. len(t) > 200) t = 'unknown'
   end function git_commit
end module gapbeam_version
