!> Test doubles for the seams of time integration (test_seams): an integrator that is not in
!> src/ (the closed-form solution of a forced, damped single-dof oscillator, handing pieces of
!> an eighth of a period to its observer) and an observer that checks what every integrator
!> must hand to an observer (contiguous pieces in time order, a piece boundary at the watch
!> instant, contact onsets located at a piece's start).
module gapbeam_test_seam
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error
   use gapbeam_model, only: model_t
   use gapbeam_state, only: state_t
   use gapbeam_settings, only: solver_settings_t
   use gapbeam_observer, only: piece_t, observer_t
   use gapbeam_integrator, only: integrator_t
   use gapbeam_laws, only: builtin_laws
   use gapbeam_linalg, only: dense_to_band
   implicit none
   private
   public :: oscillator_model, closed_form_t, closed_form_integrator_t, seam_observer_t

   !> The oscillator x'' + c x' + k x = (A/2) Omega^2 sin(Omega t) (unit mass) in closed form.
   type :: closed_form_t
      real(dp) :: k = 1.0_dp, c = 0.0_dp, omega = 1.0_dp, half_amplitude = 0.0_dp
   contains
      procedure :: at => closed_form_at        !! (x, v) at t from (x0, v0) at t0
   end type closed_form_t

   !> A piece of the closed form: anchored at (t0, x0, v0).
   type, extends(piece_t) :: closed_form_piece_t
      type(closed_form_t) :: sol                !! the oscillator
      real(dp) :: t0 = 0.0_dp, x0 = 0.0_dp, v0 = 0.0_dp   !! anchor
   contains
      procedure :: sample => piece_sample
      procedure :: state_at => piece_state
   end type closed_form_piece_t

   !> The closed-form integrator of that oscillator: pieces of T/8 (cut at the target and at
   !> the observer's watch instant).
   type, extends(integrator_t) :: closed_form_integrator_t
      type(closed_form_t) :: sol                !! the oscillator
      real(dp) :: period = 0.0_dp               !! forcing period [s]
   contains
      procedure :: init => cf_init
      procedure :: advance => cf_advance
   end type closed_form_integrator_t

   !> Checks what an integrator hands to an observer.
   type, extends(observer_t) :: seam_observer_t
      type(model_t) :: model                    !! the model (contacts)
      integer :: pieces = 0                     !! pieces seen
      real(dp) :: t_last = -huge(1.0_dp)        !! end of the last piece [s]
      real(dp) :: worst_gap = 0.0_dp            !! largest |ta - previous tb| [s]
      logical :: backwards = .false.            !! a piece with tb < ta
      logical :: watch_is_boundary = .false.    !! a piece ends exactly at t_watch
      integer :: onsets = 0                     !! contact onsets seen
      real(dp) :: worst_onset = 0.0_dp          !! largest |d(ta)| of an onset piece [m]
      real(dp) :: d_scale = 0.0_dp              !! largest |d| at piece ends [m]
   contains
      procedure :: observe => seam_observe
   end type seam_observer_t

contains

   !> The oscillator as a model: one dof, unit mass, stiffness k, damping c (mass
   !> proportional), load shape 1, no contact.
   function oscillator_model(k, c, omega, half_amplitude) result(model)
      real(dp), intent(in) :: k, c, omega, half_amplitude   !! [N/m], [N s/m], [rad/s], [m]
      type(model_t) :: model
      model%n = 1
      model%sys%n_dof = 1;  model%sys%n_node = 1;  model%sys%kd = 0
      model%sys%k = reshape([k], [1, 1]);  model%sys%m = reshape([1.0_dp], [1, 1])
      call dense_to_band(model%sys%k, 0, model%sys%k_band)
      call dense_to_band(model%sys%m, 0, model%sys%m_band)
      model%sys%m_diagonal = .true.
      model%sys%r = [1.0_dp];  model%sys%strain_row = [1.0_dp];  model%sys%tip_dof = 1
      model%beta = c;  model%gamma = 0.0_dp
      model%c = reshape([c], [1, 1]);  model%q = [1.0_dp]
      model%omega = omega;  model%half_amplitude = half_amplitude
      allocate(model%c_dof(0), model%c_sign(0), model%c_gap(0), model%c_law(0), model%c_k(0), &
               model%c_c(0), model%c_p(0), model%c_stop(0), model%c_slot(0), model%slot_dof(0), &
               model%c_tdof(0), model%stop_stiffness(0), model%stop_wear(0), &
               model%stop_dofs(2, 0))
      allocate(model%r_dof(2, 0), model%r_slot(2, 0), model%r_circular(0), &
               model%r_normal(2, 0), model%r_centre(2, 0), model%r_gap(0), model%r_law(0), &
               model%r_k(0), model%r_c(0), model%r_p(0), model%r_mu(0), model%r_kt(0), &
               model%r_stop(0))
      model%laws = builtin_laws()
      model%omega_max = sqrt(k)
   end function oscillator_model

   !> (x, v) at t of the solution through (x0, v0) at t0 (underdamped: c^2 < 4 k).
   subroutine closed_form_at(self, t0, x0, v0, t, x, v)
      class(closed_form_t), intent(in) :: self    !! the oscillator
      real(dp), intent(in) :: t0, x0, v0          !! anchor
      real(dp), intent(in) :: t                   !! instant [s]
      real(dp), intent(out) :: x, v               !! displacement, velocity
      complex(dp) :: h
      real(dp) :: xp0, vp0, z, w0, wd, c1, c2, tau, e
      h = self%half_amplitude * self%omega**2 / cmplx(self%k - self%omega**2, &
                                                       self%c * self%omega, dp)
      xp0 = real(h) * sin(self%omega * t0) + aimag(h) * cos(self%omega * t0)
      vp0 = self%omega * (real(h) * cos(self%omega * t0) - aimag(h) * sin(self%omega * t0))
      w0 = sqrt(self%k);  z = self%c / (2.0_dp * w0);  wd = w0 * sqrt(1.0_dp - z**2)
      c1 = x0 - xp0;  c2 = (v0 - vp0 + z * w0 * c1) / wd
      tau = t - t0;  e = exp(-z * w0 * tau)
      x = real(h) * sin(self%omega * t) + aimag(h) * cos(self%omega * t) &
          + e * (c1 * cos(wd * tau) + c2 * sin(wd * tau))
      v = self%omega * (real(h) * cos(self%omega * t) - aimag(h) * sin(self%omega * t)) &
          + e * ((-z * w0 * c1 + wd * c2) * cos(wd * tau) + (-z * w0 * c2 - wd * c1) &
          * sin(wd * tau))
   end subroutine closed_form_at

   subroutine piece_sample(self, t, strain, rate, tip, tip_velocity, force)
      class(closed_form_piece_t), intent(in) :: self
      real(dp), intent(in) :: t
      real(dp), intent(out) :: strain, rate, tip, tip_velocity, force(:)
      call self%sol%at(self%t0, self%x0, self%v0, t, tip, tip_velocity)
      strain = tip;  rate = tip_velocity
   end subroutine piece_sample

   subroutine piece_state(self, t, u, v)
      class(closed_form_piece_t), intent(in) :: self
      real(dp), intent(in) :: t
      real(dp), intent(out) :: u(:), v(:)
      call self%sol%at(self%t0, self%x0, self%v0, t, u(1), v(1))
   end subroutine piece_state

   subroutine cf_init(self, model, cfg, err)
      class(closed_form_integrator_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(solver_settings_t), intent(in) :: cfg
      type(error_t), allocatable, intent(out) :: err
      if (model%n /= 1 .or. model%n_contacts /= 0) then
         call fatal_error(err, 'closed_form: a single dof without contact only')
         return
      end if
      self%method = 'closed_form'
      self%sol = closed_form_t(k=model%sys%k(1, 1), c=model%c(1, 1), omega=model%omega, &
                               half_amplitude=model%half_amplitude)
      self%period = 2.0_dp * pi / model%omega
   end subroutine cf_init

   !> Pieces of T/8 (the last cut at t_target, one boundary at the watch instant).
   subroutine cf_advance(self, state, t_target, obs, err)
      class(closed_form_integrator_t), intent(inout), target :: self
      type(state_t), intent(inout) :: state
      real(dp), intent(in) :: t_target
      class(observer_t), intent(inout), optional :: obs
      type(error_t), allocatable, intent(out) :: err
      type(closed_form_piece_t) :: p
      real(dp) :: t, tn, x, v
      allocate(p%f_a(0), p%f_b(0), p%vabs_a(0), p%vabs_b(0), p%onset(0), p%onset_time(0), &
               p%r_mode(0), p%r_sigma(0), p%r_anchor(0), p%fn_a(0), p%fn_b(0), p%r_onset(0), &
               p%r_onset_time(0))
      p%sol = self%sol
      t = state%t
      do while (t < t_target)
         tn = min(t_target, t + 0.125_dp * self%period)
         if (present(obs)) then
            if (obs%t_watch > t .and. obs%t_watch < tn) tn = obs%t_watch
         end if
         p%t0 = state%t;  p%x0 = state%u(1);  p%v0 = state%v(1)
         p%ta = t;  p%tb = tn
         call self%sol%at(p%t0, p%x0, p%v0, tn, x, v)
         p%strain_b = x;  p%rate_b = v
         if (present(obs)) call obs%observe(p)
         state%t = tn;  state%u(1) = x;  state%v(1) = v
         self%steps_accepted = self%steps_accepted + 1
         t = tn
      end do
      state%t = t_target
      state%a(1) = self%sol%half_amplitude * self%sol%omega**2 * sin(self%sol%omega * t_target) &
                   - self%sol%c * state%v(1) - self%sol%k * state%u(1)
   end subroutine cf_advance

   !> Check one piece: contiguity, order, the watch instant, located onsets.
   subroutine seam_observe(self, piece)
      class(seam_observer_t), intent(inout) :: self
      class(piece_t), intent(in) :: piece
      real(dp) :: u(self%model%n), v(self%model%n), d
      integer :: c, i
      if (self%pieces > 0) self%worst_gap = max(self%worst_gap, abs(piece%ta - self%t_last))
      if (piece%tb < piece%ta) self%backwards = .true.
      if (piece%tb == self%t_watch) self%watch_is_boundary = .true.
      self%pieces = self%pieces + 1
      self%t_last = piece%tb
      if (self%model%n_contacts == 0) return
      call piece%state_at(piece%tb, u, v)
      do c = 1, self%model%n_contacts
         i = self%model%c_dof(c)
         self%d_scale = max(self%d_scale, abs(self%model%c_sign(c) * u(i) - self%model%c_gap(c)))
      end do
      do c = 1, self%model%n_contacts
         if (.not. piece%onset(c)) cycle
         self%onsets = self%onsets + 1
         call piece%state_at(piece%ta, u, v)
         i = self%model%c_dof(c)
         d = self%model%c_sign(c) * u(i) - self%model%c_gap(c)
         self%worst_onset = max(self%worst_onset, abs(d))
      end do
   end subroutine seam_observe
end module gapbeam_test_seam
