!> Modal analysis of the linear structure through LAPACK's generalized symmetric solver.
!>
!> K phi = omega^2 M phi. When M is positive definite, dsygv solves it directly. When M is
!> singular (lumped mass with massless rotations), the pencil is turned round, M phi = mu K phi
!> with mu = 1/omega^2 (K is positive definite for any supported root), and the massless
!> directions (mu = 0, infinite frequency) are dropped. Shapes are mass-normalised,
!> phi' M phi = 1, with the sign chosen so that the tip displacement (or, if zero, the largest
!> component) is positive.
module gapbeam_eigen
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_lapack, only: dsygv, dpotrf
   use gapbeam_model, only: system_t
   use gapbeam_results, only: modes_t
   implicit none
   private
   public :: solve_modes

contains

   !> Solve K phi = omega^2 M phi for all finite modes of `sys`.
   subroutine solve_modes(sys, modes, err)
      type(system_t), intent(in) :: sys               !! assembled structure
      type(modes_t), intent(out) :: modes             !! frequencies, shapes, participation
      type(error_t), allocatable, intent(out) :: err  !! set on LAPACK failure
      real(dp), allocatable :: a(:, :), b(:, :), w(:), work(:)
      real(dp) :: query(1), mu_max, s
      integer :: n, info, i, j, nm, imax
      logical :: m_definite

      n = sys%n_dof
      allocate(b, source=sys%m)
      call dpotrf('U', n, b, n, info)
      m_definite = info == 0
      allocate(w(n))
      if (m_definite) then
         allocate(a, source=sys%k)
         b = sys%m
      else
         allocate(a, source=sys%m)
         b = sys%k
      end if
      call dsygv(1, 'V', 'U', n, a, n, b, n, w, query, -1, info)
      allocate(work(max(1, int(query(1)))))
      call dsygv(1, 'V', 'U', n, a, n, b, n, w, work, size(work), info)
      if (info > n) then
         call fatal_error(err, 'gapbeam_eigen:solve_modes: the ' // merge('mass     ', &
            'stiffness', m_definite) // ' matrix is not positive definite (dsygv info=' &
            // str(info) // '); check the root support and the springs')
         return
      else if (info /= 0) then
         call fatal_error(err, 'gapbeam_eigen:solve_modes: dsygv failed, info=' // str(info))
         return
      end if

      if (m_definite) then
         nm = n
         allocate(modes%omega2(nm), modes%shapes(n, nm))
         modes%omega2 = w
         modes%shapes = a
      else
         ! w holds mu = 1/omega^2 ascending; the largest mu is the lowest frequency
         mu_max = maxval(w)
         nm = count(w > 1.0e-12_dp * mu_max)
         allocate(modes%omega2(nm), modes%shapes(n, nm))
         do j = 1, nm
            i = n + 1 - j
            modes%omega2(j) = 1.0_dp / w(i)
            modes%shapes(:, j) = a(:, i) / sqrt(w(i))   ! phi' K phi = 1 -> phi' M phi = 1
         end do
      end if
      modes%n_modes = nm
      do j = 1, nm
         if (sys%tip_dof > 0) then
            s = modes%shapes(sys%tip_dof, j)
         else
            s = 0.0_dp
         end if
         if (abs(s) <= 1.0e-12_dp * maxval(abs(modes%shapes(:, j)))) then
            imax = maxloc(abs(modes%shapes(:, j)), dim=1)
            s = modes%shapes(imax, j)
         end if
         if (s < 0.0_dp) modes%shapes(:, j) = -modes%shapes(:, j)
      end do
      modes%frequency_hz = sqrt(max(modes%omega2, 0.0_dp)) / (2.0_dp * pi)
      modes%participation = matmul(transpose(modes%shapes), matmul(sys%m, sys%r))
      modes%effective_mass = modes%participation**2
      modes%total_mass = dot_product(sys%r, matmul(sys%m, sys%r))
   end subroutine solve_modes
end module gapbeam_eigen
