!> The dense output of a one-step method's sub-step: its end states and the Hermite
!> interpolants in between (quintic from (u, v, a) at both ends for the samples and states the
!> observer asks for; the cubic from (u, v) is what event location bisects).
module gapbeam_hermite_piece
   use gapbeam_kinds, only: dp
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_observer, only: piece_t
   use gapbeam_contact_law, only: contact_force
   implicit none
   private
   public :: hermite_piece_t, hermite_weights, quintic_weights

   !> One accepted sub-step: end values and the cubic Hermite interpolant in between.
   type, extends(piece_t) :: hermite_piece_t
      type(model_t), pointer :: model => null()            !! the integrator's model
      type(state_t), pointer :: sub(:) => null()           !! the integrator's sub-states
      integer :: ja = 0, jb = 0                            !! the states at ta and tb
   contains
      procedure :: sample => hermite_sample
      procedure :: state_at => hermite_state
   end type hermite_piece_t

contains

   !> Root strain, its rate, tip displacement and velocity, contact forces at t: quintic
   !> Hermite interpolation of the sub-step from (u, v, a) at both ends (error O(h^6) in u,
   !> O(h^5) in v, below the method's own in both).
   subroutine hermite_sample(self, t, strain, rate, tip, tip_velocity, force)
      class(hermite_piece_t), intent(in) :: self        !! piece
      real(dp), intent(in) :: t                         !! instant [s]
      real(dp), intent(out) :: strain, rate, tip, tip_velocity   !! outputs
      real(dp), intent(out) :: force(:)                 !! contact force magnitudes [N]
      real(dp) :: h, w(6), g(6), ui, vi
      integer :: i, c
      h = self%tb - self%ta
      call quintic_weights(min(1.0_dp, max(0.0_dp, (t - self%ta) / h)), h, w, g)
      strain = 0.0_dp;  rate = 0.0_dp;  tip = 0.0_dp;  tip_velocity = 0.0_dp
      associate (m => self%model, sa => self%sub(self%ja), sb => self%sub(self%jb))
         do i = 1, m%n
            ui = w(1) * sa%u(i) + w(2) * sa%v(i) + w(3) * sa%a(i) + w(4) * sb%u(i) &
                 + w(5) * sb%v(i) + w(6) * sb%a(i)
            vi = g(1) * sa%u(i) + g(2) * sa%v(i) + g(3) * sa%a(i) + g(4) * sb%u(i) &
                 + g(5) * sb%v(i) + g(6) * sb%a(i)
            strain = strain + m%sys%strain_row(i) * ui
            rate = rate + m%sys%strain_row(i) * vi
            if (i == m%sys%tip_dof) then
               tip = ui;  tip_velocity = vi
            end if
         end do
         do c = 1, m%n_contacts
            i = m%c_dof(c)
            ui = w(1) * sa%u(i) + w(2) * sa%v(i) + w(3) * sa%a(i) + w(4) * sb%u(i) &
                 + w(5) * sb%v(i) + w(6) * sb%a(i)
            vi = g(1) * sa%u(i) + g(2) * sa%v(i) + g(3) * sa%a(i) + g(4) * sb%u(i) &
                 + g(5) * sb%v(i) + g(6) * sb%a(i)
            force(c) = contact_force(m, c, m%c_sign(c) * ui - m%c_gap(c), m%c_sign(c) * vi)
         end do
      end associate
   end subroutine hermite_sample

   !> Displacement and velocity of every dof at t (quintic Hermite interpolation).
   subroutine hermite_state(self, t, u, v)
      class(hermite_piece_t), intent(in) :: self        !! piece
      real(dp), intent(in) :: t                         !! instant [s]
      real(dp), intent(out) :: u(:), v(:)               !! state
      real(dp) :: h, w(6), g(6)
      h = self%tb - self%ta
      call quintic_weights(min(1.0_dp, max(0.0_dp, (t - self%ta) / h)), h, w, g)
      associate (sa => self%sub(self%ja), sb => self%sub(self%jb))
         u = w(1) * sa%u + w(2) * sa%v + w(3) * sa%a + w(4) * sb%u + w(5) * sb%v + w(6) * sb%a
         v = g(1) * sa%u + g(2) * sa%v + g(3) * sa%a + g(4) * sb%u + g(5) * sb%v + g(6) * sb%a
      end associate
   end subroutine hermite_state

   !> Weights of the quintic Hermite interpolant at fraction x of a step of h: the value is
   !> w . (u0, v0, a0, u1, v1, a1), its time derivative g . (the same).
   pure subroutine quintic_weights(x, h, w, g)
      real(dp), intent(in) :: x, h             !! fraction [-], step [s]
      real(dp), intent(out) :: w(6), g(6)      !! weights of value and derivative
      real(dp) :: x2, x3, x4, x5
      x2 = x * x;  x3 = x2 * x;  x4 = x3 * x;  x5 = x4 * x
      w(1) = 1.0_dp - 10.0_dp * x3 + 15.0_dp * x4 - 6.0_dp * x5
      w(2) = h * (x - 6.0_dp * x3 + 8.0_dp * x4 - 3.0_dp * x5)
      w(3) = h**2 * 0.5_dp * (x2 - 3.0_dp * x3 + 3.0_dp * x4 - x5)
      w(4) = 10.0_dp * x3 - 15.0_dp * x4 + 6.0_dp * x5
      w(5) = h * (-4.0_dp * x3 + 7.0_dp * x4 - 3.0_dp * x5)
      w(6) = h**2 * 0.5_dp * (x3 - 2.0_dp * x4 + x5)
      g(1) = (-30.0_dp * x2 + 60.0_dp * x3 - 30.0_dp * x4) / h
      g(2) = 1.0_dp - 18.0_dp * x2 + 32.0_dp * x3 - 15.0_dp * x4
      g(3) = h * 0.5_dp * (2.0_dp * x - 9.0_dp * x2 + 12.0_dp * x3 - 5.0_dp * x4)
      g(4) = (30.0_dp * x2 - 60.0_dp * x3 + 30.0_dp * x4) / h
      g(5) = -12.0_dp * x2 + 28.0_dp * x3 - 15.0_dp * x4
      g(6) = h * 0.5_dp * (3.0_dp * x2 - 8.0_dp * x3 + 5.0_dp * x4)
   end subroutine quintic_weights

   !> Weights of the cubic Hermite interpolant (h..) and of its derivative times h (g..).
   pure subroutine hermite_weights(x, h00, h10, h01, h11, g00, g10, g01, g11)
      real(dp), intent(in) :: x                                   !! fraction of the step
      real(dp), intent(out) :: h00, h10, h01, h11, g00, g10, g01, g11   !! weights
      h00 = (1 + 2 * x) * (1 - x)**2;  h10 = x * (1 - x)**2
      h01 = x**2 * (3 - 2 * x);  h11 = x**2 * (x - 1)
      g00 = 6 * x**2 - 6 * x;  g10 = 3 * x**2 - 4 * x + 1
      g01 = -6 * x**2 + 6 * x;  g11 = 3 * x**2 - 2 * x
   end subroutine hermite_weights
end module gapbeam_hermite_piece
