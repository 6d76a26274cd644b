!> The recorder: the one observer that turns the pieces of a trajectory into the results of a
!> transient run. History samples, Poincare sampling, the low-pass filter of the root strain
!> and the impact statistics live here and nowhere else.
!>
!> Every integrator feeds it the same way (gapbeam_integrator:piece_t), so a stepping method
!> and the exact integrator produce the same result fields:
!> * history: `samples_per_period` samples per forcing period over the first
!>   `history_periods` recorded periods (root strain and rate, tip displacement, stop forces);
!> * state history (`state_history`): every dof at the history samples, from the piece's
!>   dense output (`state_at`);
!> * Poincare section: one point per recorded period at `poincare_phase_deg`;
!> * filter (when `filter_cutoff_hz` > 0): the root strain and its rate sampled uniformly from
!>   t = 0 at `filter_samples_per_period` per period through a causal Butterworth low-pass;
!>   its outputs replace the Poincare strain and rate and fill the filtered history column;
!> * statistics over the record, per stop: impacts (contact onsets), peak and rms force,
!>   contact fraction, impulse per period, work rate (1/T) int f |v| dt at the contact dof,
!>   the first contact time (from t = 0), and the root strain and rate ranges. A piece with
!>   exact statistics (the exact integrator: integrals in closed form, certified extrema) is
!>   taken as it is; otherwise the wear meter integrates the piece's interpolant by 3-point
!>   Gauss-Legendre quadrature (f, f^2, f |v| and the contact indicator: pieces end at located
!>   onsets and releases) and locates the peak force inside it by golden-section search.
module gapbeam_recorder
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: output_settings_t
   use gapbeam_results, only: transient_result_t, allocate_result
   use gapbeam_filter, only: lowpass_t, design_lowpass
   use gapbeam_observer, only: observer_t, piece_t
   use gapbeam_wear, only: wear_meter_t
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   private
   public :: recorder_t

   !> Records a transient run: transient_periods discarded, record_periods recorded.
   type, extends(observer_t) :: recorder_t
      type(transient_result_t) :: res                !! results being filled
      integer, allocatable :: c_stop(:)               !! deck stop of each contact
      integer, allocatable :: r_stop(:)               !! deck stop of each ring contact
      type(wear_meter_t) :: wear                      !! wear outputs, orbits, energy balance
      real(dp) :: period = 0.0_dp                     !! forcing period [s]
      real(dp) :: t_rec = 0.0_dp                      !! start of the record [s]
      real(dp) :: t_rec_len = 0.0_dp                  !! length of the record [s]
      integer :: transient_periods = 0                !! periods before the record
      integer :: record_periods = 0                   !! periods recorded
      integer :: spp = 1                              !! history samples per period
      real(dp) :: phase = 0.0_dp                      !! Poincare phase [periods]
      integer :: n_hist = 0, n_poinc = 0              !! samples kept
      integer :: ih = 1, ip = 1                       !! next history, Poincare sample
      real(dp) :: next_sample = -huge(1.0_dp)         !! earliest sample still due [s]
      logical :: all_found = .true.                   !! every stop has its first contact
      real(dp), allocatable :: acc_f(:), acc_f2(:), acc_work(:), acc_contact(:)  !! per stop
      real(dp), allocatable :: force(:)               !! contact forces of a sample
      real(dp), allocatable :: v_work(:)              !! velocities of a state sample
      ! low-pass filter
      logical :: filtering = .false.                  !! filter asked
      type(lowpass_t) :: fil_s, fil_r                 !! filters of the strain and its rate
      integer :: nf = 0                               !! filter samples per period
      real(dp) :: dt_f = 0.0_dp                       !! filter sample interval [s]
      integer(int64) :: jf = 0                        !! next filter sample
      integer :: ipf = 1, ihf = 1                     !! next filtered Poincare, history output
      integer(int64) :: jp_next = 0, jh_next = 0      !! their filter sample indices
   contains
      procedure :: init => recorder_init
      procedure :: observe => recorder_observe
      procedure :: finish => recorder_finish
      procedure, private :: take_samples, filter_samples, accumulate
   end type recorder_t

contains

   !> Prepare to record a run of `transient_periods` + `record_periods` forcing periods from
   !> t = 0 on this model.
   subroutine recorder_init(self, model, out, transient_periods, record_periods, err)
      class(recorder_t), intent(inout) :: self          !! recorder
      type(model_t), intent(in) :: model                !! model (forcing, contacts)
      type(output_settings_t), intent(in) :: out        !! what to record
      integer, intent(in) :: transient_periods          !! periods discarded
      integer, intent(in) :: record_periods             !! periods recorded
      type(error_t), allocatable, intent(out) :: err    !! filter design failure
      integer :: ns
      ns = model%n_stops
      self%c_stop = model%c_stop
      allocate(self%r_stop(model%n_rings))
      if (model%n_rings > 0) self%r_stop = model%r_stop
      call self%wear%init(model, ns, out%energy_balance)
      self%period = 2.0_dp * pi / model%omega
      self%transient_periods = transient_periods
      self%record_periods = record_periods
      self%t_rec = real(transient_periods, dp) * self%period
      self%t_rec_len = real(record_periods, dp) * self%period
      self%t_watch = self%t_rec
      self%spp = out%samples_per_period
      self%phase = out%poincare_phase_deg / 360.0_dp
      self%n_hist = min(out%history_periods, record_periods) * out%samples_per_period
      self%n_poinc = record_periods
      call allocate_result(self%res, self%n_hist, self%n_poinc, ns)
      allocate(self%acc_f(ns), self%acc_f2(ns), self%acc_work(ns), self%acc_contact(ns), &
               source=0.0_dp)
      allocate(self%force(model%n_contacts))
      if (out%state_history) then
         allocate(self%res%history_u(model%n, self%n_hist), self%v_work(model%n))
      end if
      self%ih = 1;  self%ip = 1;  self%next_sample = -huge(1.0_dp);  self%all_found = ns == 0
      self%filtering = out%filter_cutoff_hz > 0.0_dp
      allocate(self%res%strain_filtered(merge(self%n_hist, 0, self%filtering)))
      if (.not. self%filtering) return
      self%nf = out%filter_samples_per_period
      self%dt_f = self%period / real(self%nf, dp)
      call design_lowpass(out%filter_order, out%filter_cutoff_hz, 1.0_dp / self%dt_f, &
                          self%fil_s, err)
      if (allocated(err)) then
         err%message = 'group &output: ' // err%message // ' (the filter samples ' &
            // str(self%nf) // ' times per forcing period: raise filter_samples_per_period)'
         return
      end if
      call design_lowpass(out%filter_order, out%filter_cutoff_hz, 1.0_dp / self%dt_f, &
                          self%fil_r, err)
      self%jf = 0;  self%ipf = 1;  self%ihf = 1
      self%jp_next = poincare_filter_index(self, 1)
      self%jh_next = history_filter_index(self, 1)
   end subroutine recorder_init

   !> Take one more piece: extrema and statistics in the record, samples due in (ta, tb],
   !> first contact times.
   subroutine recorder_observe(self, piece)
      class(recorder_t), intent(inout) :: self          !! recorder
      class(piece_t), intent(in) :: piece               !! the piece
      logical :: recording
      integer :: c, ks
      recording = piece%ta >= self%t_rec
      if (recording) then
         associate (r => self%res)
            if (piece%exact_statistics) then
               r%strain_min = min(r%strain_min, piece%strain_min)
               r%strain_max = max(r%strain_max, piece%strain_max)
               r%strain_rate_min = min(r%strain_rate_min, piece%rate_min)
               r%strain_rate_max = max(r%strain_rate_max, piece%rate_max)
            else
               r%strain_min = min(r%strain_min, piece%strain_b)
               r%strain_max = max(r%strain_max, piece%strain_b)
               r%strain_rate_min = min(r%strain_rate_min, piece%rate_b)
               r%strain_rate_max = max(r%strain_rate_max, piece%rate_b)
            end if
         end associate
      end if
      if (piece%tb + 1.0e-12_dp * self%period < self%next_sample .and. self%all_found) then
         if (recording) call self%accumulate(piece)
         return
      end if
      call self%take_samples(piece)
      ! first contact onset of each stop (from t = 0)
      do c = 1, size(self%c_stop)
         ks = self%c_stop(c)
         if (self%res%first_contact_time(ks) >= 0.0_dp) cycle
         if (piece%onset(c)) self%res%first_contact_time(ks) = piece%onset_time(c)
      end do
      do c = 1, size(self%r_stop)
         ks = self%r_stop(c)
         if (self%res%first_contact_time(ks) >= 0.0_dp) cycle
         if (piece%r_onset(c)) self%res%first_contact_time(ks) = piece%r_onset_time(c)
      end do
      self%all_found = all(self%res%first_contact_time >= 0.0_dp)
      if (recording) call self%accumulate(piece)
   end subroutine recorder_observe

   !> History, Poincare and filter samples due in (ta, tb]; the next instant a sample is due.
   subroutine take_samples(self, piece)
      class(recorder_t), intent(inout) :: self          !! recorder
      class(piece_t), intent(in) :: piece               !! the piece
      real(dp) :: t, st, sv, tip, tipv, tol
      integer :: c, ks
      tol = 1.0e-12_dp * self%period
      associate (r => self%res)
         do while (self%ih <= self%n_hist)
            t = self%t_rec + real(self%ih - 1, dp) * self%period / real(self%spp, dp)
            if (t > piece%tb + tol) exit
            call piece%sample(t, st, sv, tip, tipv, self%force)
            r%time(self%ih) = t
            r%strain(self%ih) = st;  r%strain_rate(self%ih) = sv
            r%tip_displacement(self%ih) = tip
            if (allocated(r%history_u)) &
               call piece%state_at(t, r%history_u(:, self%ih), self%v_work)
            r%stop_force(self%ih, :) = 0.0_dp
            do c = 1, size(self%c_stop)
               ks = self%c_stop(c)
               r%stop_force(self%ih, ks) = r%stop_force(self%ih, ks) + self%force(c)
            end do
            call self%wear%sample(piece, t, self%ih, r)
            self%ih = self%ih + 1
         end do
         do while (self%ip <= self%n_poinc)
            t = self%t_rec + (real(self%ip - 1, dp) + self%phase) * self%period
            if (t > piece%tb + tol) exit
            call piece%sample(t, st, sv, tip, tipv, self%force)
            r%p_time(self%ip) = t
            r%p_strain(self%ip) = st;  r%p_strain_rate(self%ip) = sv
            r%p_tip(self%ip) = tip;  r%p_tip_velocity(self%ip) = tipv
            self%ip = self%ip + 1
         end do
      end associate
      if (self%filtering) call self%filter_samples(piece)
      self%next_sample = huge(1.0_dp)
      if (self%filtering) self%next_sample = real(self%jf, dp) * self%dt_f
      if (self%ih <= self%n_hist) self%next_sample = min(self%next_sample, self%t_rec &
         + real(self%ih - 1, dp) * self%period / real(self%spp, dp))
      if (self%ip <= self%n_poinc) self%next_sample = min(self%next_sample, self%t_rec &
         + (real(self%ip - 1, dp) + self%phase) * self%period)
   end subroutine take_samples

   !> Feed the low-pass filters with the root strain and its rate at their uniform sample
   !> times in (ta, tb]; keep the filtered values at the Poincare instants (the nearest filter
   !> sample) and at the history samples.
   subroutine filter_samples(self, piece)
      class(recorder_t), intent(inout) :: self          !! recorder
      class(piece_t), intent(in) :: piece               !! the piece
      real(dp) :: tf, st, sv, tip, tipv, ys, yr
      do
         tf = real(self%jf, dp) * self%dt_f
         if (tf > piece%tb + 1.0e-12_dp * self%period) exit
         call piece%sample(tf, st, sv, tip, tipv, self%force)
         ys = self%fil_s%apply(st);  yr = self%fil_r%apply(sv)
         if (self%ipf <= self%n_poinc .and. self%jf == self%jp_next) then
            self%res%p_strain(self%ipf) = ys;  self%res%p_strain_rate(self%ipf) = yr
            self%ipf = self%ipf + 1
            self%jp_next = poincare_filter_index(self, self%ipf)
         end if
         if (self%ihf <= self%n_hist .and. self%jf == self%jh_next) then
            self%res%strain_filtered(self%ihf) = ys
            self%ihf = self%ihf + 1
            self%jh_next = history_filter_index(self, self%ihf)
         end if
         self%jf = self%jf + 1
      end do
   end subroutine filter_samples

   !> Filter sample index of Poincare point k (the nearest to its instant).
   pure integer(int64) function poincare_filter_index(self, k)
      type(recorder_t), intent(in) :: self   !! recorder
      integer, intent(in) :: k               !! Poincare point
      poincare_filter_index = int(self%transient_periods + k - 1, int64) * self%nf &
         + nint(self%phase * self%nf, int64)
   end function poincare_filter_index

   !> Filter sample index of history sample i.
   pure integer(int64) function history_filter_index(self, i)
      type(recorder_t), intent(in) :: self   !! recorder
      integer, intent(in) :: i               !! history sample
      history_filter_index = int(self%transient_periods, int64) * self%nf &
         + int(i - 1, int64) * (self%nf / self%spp)
   end function history_filter_index

   !> Impact statistics of a recorded piece, per stop: the integrator's exact ones, else the
   !> wear meter's quadratures on the piece's interpolant (and the peak located on it).
   subroutine accumulate(self, piece)
      class(recorder_t), intent(inout) :: self          !! recorder
      class(piece_t), intent(in) :: piece               !! the piece
      integer :: c, k
      call self%wear%piece(piece, self%acc_f, self%acc_f2, self%acc_work, self%acc_contact, &
                           self%res%n_impacts, self%res%peak_force)
      do c = 1, size(self%c_stop)
         k = self%c_stop(c)
         if (piece%onset(c)) self%res%n_impacts(k) = self%res%n_impacts(k) + 1
         if (.not. piece%exact_statistics) cycle
         self%acc_f(k) = self%acc_f(k) + piece%int_f(c)
         self%acc_f2(k) = self%acc_f2(k) + piece%int_f2(c)
         self%acc_work(k) = self%acc_work(k) + piece%int_work(c)
         self%acc_contact(k) = self%acc_contact(k) + piece%t_contact(c)
         self%res%peak_force(k) = max(self%res%peak_force(k), piece%peak(c))
      end do
   end subroutine accumulate

   !> The results: statistics over the record, history trimmed to the samples taken.
   subroutine recorder_finish(self, res)
      class(recorder_t), intent(inout) :: self          !! recorder
      type(transient_result_t), intent(out) :: res      !! results (run counters not set)
      integer :: ih
      associate (r => self%res)
         if (self%record_periods > 0) then
            r%rms_force = sqrt(self%acc_f2 / self%t_rec_len)
            r%contact_fraction = self%acc_contact / self%t_rec_len
            r%impulse_per_period = self%acc_f / real(self%record_periods, dp)
            r%work_rate = self%acc_work / self%t_rec_len
         else
            r%rms_force = self%acc_f2;  r%contact_fraction = self%acc_contact
            r%impulse_per_period = self%acc_f;  r%work_rate = self%acc_work
         end if
         call self%wear%finish(self%t_rec_len, r)
         ih = self%ih
         if (ih <= self%n_hist) then
            r%time = r%time(1:ih - 1);  r%strain = r%strain(1:ih - 1)
            r%strain_rate = r%strain_rate(1:ih - 1)
            r%tip_displacement = r%tip_displacement(1:ih - 1)
            r%stop_force = r%stop_force(1:ih - 1, :)
            r%orbit_w = r%orbit_w(1:ih - 1, :);  r%orbit_v = r%orbit_v(1:ih - 1, :)
            r%tangential_force = r%tangential_force(1:ih - 1, :)

            if (allocated(r%history_u)) r%history_u = r%history_u(:, 1:ih - 1)
         end if
      end associate
      res = self%res
   end subroutine recorder_finish
end module gapbeam_recorder
