!> Element matrices: symmetry, rigid-body modes, mass totals, curvature recovery.
program test_beam_element
   use gapbeam_kinds, only: dp
   use gapbeam_testing, only: check, check_close, check_le, finish
   use gapbeam_beam_element, only: beam_stiffness, beam_consistent_mass, beam_lumped_mass, &
      beam_curvature_row
   implicit none
   real(dp), parameter :: ei = 2.5_dp, le = 0.3_dp, rho_a = 1.7_dp
   real(dp) :: ke(4, 4), me(4, 4), md(4), trans(4), rot(4), u(4), b(4), xi
   integer :: i

   ke = beam_stiffness(ei, le)
   me = beam_consistent_mass(rho_a, le)
   call check_le('stiffness symmetric', maxval(abs(ke - transpose(ke))), 0.0_dp)
   call check_le('consistent mass symmetric', maxval(abs(me - transpose(me))), 0.0_dp)
   trans = [1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp]
   rot = [0.0_dp, 1.0_dp, le, 1.0_dp]          ! w = x: rigid rotation about node 1
   call check_le('rigid translation stores no energy', maxval(abs(matmul(ke, trans))), &
      1.0e-12_dp * maxval(abs(ke)))
   call check_le('rigid rotation stores no energy', maxval(abs(matmul(ke, rot))), &
      1.0e-12_dp * maxval(abs(ke)))
   call check_close('consistent mass adds up to rho A le', dot_product(trans, matmul(me, trans)), &
      rho_a * le, rtol=1.0e-14_dp)
   md = beam_lumped_mass(rho_a, le, 'half_element')
   call check_close('lumped mass adds up to rho A le', md(1) + md(3), rho_a * le, rtol=1.0e-14_dp)
   call check_close('half-element rotary inertia m le^2/24', md(2), rho_a * le**3 / 24.0_dp, &
      rtol=1.0e-14_dp)
   md = beam_lumped_mass(rho_a, le, 'none')
   call check('no rotary inertia with rule none', md(2) == 0.0_dp .and. md(4) == 0.0_dp)
   ! consistent mass: kinetic energy of a rigid rotation about node 1 equals rho A le^3/3
   call check_close('consistent mass rotary inertia of the element', &
      dot_product(rot, matmul(me, rot)), rho_a * le**3 / 3.0_dp, rtol=1.0e-13_dp)
   ! curvature of w = x^2/2 + x^3 (w'' = 1 + 6x) recovered exactly anywhere
   u = [0.0_dp, 0.0_dp, le**2 / 2 + le**3, le + 3 * le**2]
   do i = 0, 4
      xi = real(i, dp) / 4.0_dp
      b = beam_curvature_row(le, xi)
      call check_close('curvature of a cubic at xi', dot_product(b, u), 1.0_dp + 6.0_dp * xi * le, &
         rtol=1.0e-12_dp)
   end do
   ! strain energy of the cubic: u'Ku = EI * int (w'')^2 dx
   call check_close('strain energy of a cubic', dot_product(u, matmul(ke, u)), &
      ei * (le + 6 * le**2 + 12 * le**3), rtol=1.0e-12_dp)
   call finish('test_beam_element')
end program test_beam_element
