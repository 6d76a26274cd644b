!> Keep BLAS and LAPACK serial inside gapbeam.
!>
!> gapbeam parallelises over sweep points with OpenMP and calls LAPACK only on small
!> matrices. A multithreaded BLAS (OpenBLAS) would split those calls differently with the
!> number of threads and change the round-off, so that results would depend on
!> OMP_NUM_THREADS. At start-up the program therefore asks the BLAS in use, if it is OpenBLAS
!> (found at run time with dlsym, so any BLAS still links), for one thread.
module gapbeam_blas_threads
   use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_funptr, c_int, c_char, &
      c_null_char, c_associated, c_f_procpointer
   implicit none
   private
   public :: serial_blas

   interface
      function c_dlsym(handle, name) bind(c, name='dlsym') result(f)
         import :: c_ptr, c_funptr, c_char
         type(c_ptr), value, intent(in) :: handle
         character(kind=c_char), intent(in) :: name(*)
         type(c_funptr) :: f
      end function c_dlsym
   end interface

   abstract interface
      subroutine set_threads(n) bind(c)
         import :: c_int
         integer(c_int), value, intent(in) :: n
      end subroutine set_threads
   end interface

contains

   !> Set OpenBLAS (if it is the BLAS in use) to one thread; returns whether it was found.
   logical function serial_blas()
      type(c_funptr) :: fp
      procedure(set_threads), pointer :: setter
      fp = c_dlsym(c_null_ptr, 'openblas_set_num_threads' // c_null_char)  ! RTLD_DEFAULT
      serial_blas = c_associated(fp)
      if (.not. serial_blas) return
      call c_f_procpointer(fp, setter)
      call setter(1_c_int)
   end function serial_blas
end module gapbeam_blas_threads
