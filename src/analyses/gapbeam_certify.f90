!> The certificate of a label: independent re-checks of a diagnosed point, each a full
!> diagnosis (gapbeam_attractor: settling, period, adaptive exponent, label).
!>
!> 1. Accuracy: the same start at a second accuracy. Where the run was not exact and every
!>    stop is piecewise linear, the exact integrator (accurate to round-off); else the run's
!>    own method with every accuracy setting tightened `certify_ratio` times (tolerance,
!>    rk_rtol and half_step_tolerance divided, steps_per_period multiplied, which also refines
!>    the exponent's fixed steps). A run that was exact has no tighter accuracy: no check.
!> 2. Perturbed start: the run's own settings from the start plus a random state (seeded by
!>    the point) of `certify_perturbation` times the energy norm of the attractor's state.
!>
!> 3. Persistence (a chaotic label, certify_persistence > 0): the run continued from the end
!>    of its exponent's periods for certify_persistence x (transient_periods + record_periods);
!>    a period found there disputes the label ("chaotic transient, then period N after M
!>    periods"); else the certificate says "chaotic for at least M periods". The label stays
!>    chaotic: it is the diagnosis within the deck's budget; the longer run is the evidence.
!>
!> The point is certified when each check gives the same label and, for the accuracy check
!> of a periodic label, the same orbit (within orbit_tolerance of its size); otherwise it is
!> disputed, with the first disagreement as the reason (a check that fails numerically also
!> disputes). A perturbed start that lands on another orbit of the same period is not a
!> dispute of the label (it is recorded as a distance).
module gapbeam_certify
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_model, only: model_t, energy_norm
   use gapbeam_settings, only: solver_settings_t, output_settings_t, diagnostics_settings_t
   use gapbeam_results, only: point_result_t, transient_result_t, label_text, label_failed, &
      label_chaotic, certificate_certified, certificate_disputed
   use gapbeam_capabilities, only: method_caps_t, method_table, is_exact
   use gapbeam_integrator, only: resolve_method, refusal
   use gapbeam_attractor, only: diagnose, persistence, auto_period_tolerance
   use gapbeam_transient, only: integrator_cache_t
   use gapbeam_starts, only: uniform_numbers, attractor_distance
   use gapbeam_clock, only: thread_cpu_seconds
   implicit none
   private
   public :: certify_point, contradiction, accuracy_settings, check_diagnostics

   integer, parameter :: stream_perturbation = 1000   !! generator stream offset of the checks

contains

   !> Run both checks of a diagnosed point `pr` (started from (u0, v0)) and set its certificate.
   !> `cache`: the point's integrators (the perturbed start reuses the run's).
   subroutine certify_point(model, cfg, out, diag, u0, v0, seed, pr, cache)
      type(model_t), intent(in) :: model                 !! model of the point
      type(solver_settings_t), intent(in) :: cfg         !! the run's settings
      type(output_settings_t), intent(in) :: out         !! recording settings
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      real(dp), intent(in) :: u0(:), v0(:)               !! the run's start
      integer, intent(in) :: seed                        !! generator stream of this point
      type(point_result_t), intent(inout) :: pr          !! diagnosed point; certificate set
      type(integrator_cache_t), intent(inout), optional :: cache   !! this model's integrators
      type(solver_settings_t) :: tight
      type(point_result_t) :: chk
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      character(len=:), allocatable :: what, reason, why, persisted
      real(dp), allocatable :: du(:), dv(:)
      real(dp) :: cpu0, scale, dn
      logical :: needed

      cpu0 = thread_cpu_seconds()
      reason = ''
      ! 1. accuracy
      call accuracy_settings(model, cfg, diag%certify_ratio, tight, what, needed)
      pr%accuracy_method = ''
      if (needed) then
         call diagnose(model, tight, out, check_diagnostics(model, cfg, diag, tight), u0, v0, &
                       res, chk, err, cache=cache)
         if (allocated(err) .and. is_exact(tight%method)) then
            ! the exact integrator refused this model: tighten the run's own method instead
            call accuracy_settings(model, cfg, diag%certify_ratio, tight, what, needed, &
                                   no_exact=.true.)
            deallocate(err)
            chk = point_result_t()
            call diagnose(model, tight, out, check_diagnostics(model, cfg, diag, tight), u0, v0, &
                          res, chk, err, cache=cache)
         end if
         pr%accuracy_method = what
         call record_check(pr, chk, err, 'accuracy', what, diag, reason)
      end if
      ! 2. perturbed start
      du = uniform_numbers(diag%random_seed, stream_perturbation + 2 * seed, size(u0))
      dv = uniform_numbers(diag%random_seed, stream_perturbation + 2 * seed + 1, size(v0))
      scale = energy_norm(model, pr%u_end, pr%v_end)
      if (.not. (scale > 0.0_dp)) scale = energy_norm(model, u0, v0)
      dn = energy_norm(model, du, dv)
      if (scale > 0.0_dp .and. dn > 0.0_dp) then
         du = du * (diag%certify_perturbation * scale / dn)
         dv = dv * (diag%certify_perturbation * scale / dn)
      else
         du = du * diag%certify_perturbation;  dv = dv * diag%certify_perturbation
      end if
      chk = point_result_t()
      call diagnose(model, cfg, out, diag, u0 + du, v0 + dv, res, chk, err, cache=cache)
      call record_check(pr, chk, err, 'perturbed', 'a start perturbed by ' &
         // num(diag%certify_perturbation) // ' of the state norm', diag, reason)
      ! 3. persistence of a chaotic label: the run continued
      persisted = ''
      if (pr%label == label_chaotic .and. diag%certify_persistence > 0.0_dp) then
         call persistence_check(model, cfg, out, diag, pr, persisted, why, cache)
         if (len(why) > 0) reason = why
      end if
      ! the label's own evidence must agree with itself, whatever the checks say
      if (len(contradiction(pr, diag)) > 0) reason = contradiction(pr, diag)
      if (len(reason) == 0) then
         pr%certificate = certificate_certified
         if (needed) then
            pr%certificate_reason = 'certified: ' // what // ' and a perturbed start give ' &
               // label_text(pr%label) // ' too'
         else
            pr%certificate_reason = 'certified: a perturbed start gives ' &
               // label_text(pr%label) // ' too (the run was exact: no tighter accuracy)'
         end if
         pr%certificate_reason = pr%certificate_reason // persisted
      else
         pr%certificate = certificate_disputed
         pr%certificate_reason = 'disputed: ' // reason
      end if
      pr%seconds_certify = thread_cpu_seconds() - cpu0
   end subroutine certify_point

   !> The persistence check of a chaotic point: its run continued for certify_persistence x
   !> (its transient and record periods). `why`: the dispute ('' when the chaos persisted);
   !> `persisted`: the certificate's note when it did.
   subroutine persistence_check(model, cfg, out, diag, pr, persisted, why, cache)
      type(model_t), intent(in) :: model                 !! model of the point
      type(solver_settings_t), intent(in) :: cfg         !! the run's settings
      type(output_settings_t), intent(in) :: out         !! recording settings (no history)
      type(diagnostics_settings_t), intent(in) :: diag   !! the multiple
      type(point_result_t), intent(in) :: pr             !! the diagnosed point
      character(len=:), allocatable, intent(out) :: persisted   !! note of a persisting chaos
      character(len=:), allocatable, intent(out) :: why  !! the dispute ('' when none)
      type(integrator_cache_t), intent(inout), optional :: cache   !! this model's integrators
      type(error_t), allocatable :: err
      real(dp) :: n
      integer :: found, after
      n = diag%certify_persistence * real(pr%transient_periods + cfg%record_periods, dp)
      call persistence(model, cfg, out, diag, pr, nint(min(n, real(huge(1) / 4, dp))), found, &
                       after, err, cache)
      persisted = ''
      why = ''
      if (allocated(err)) then
         why = 'the persistence run (' // num(diag%certify_persistence) // ' x the transient ' &
            // 'and record periods further) failed: ' // err%message
      else if (found > 0) then
         why = 'chaotic transient, then period ' // str(found) // ' after ' // str(after) &
            // ' periods (the run continued for ' // num(diag%certify_persistence) &
            // ' x its transient and record periods)'
      else
         persisted = '; chaotic for at least ' // str(after) // ' periods (the run continued ' &
            // 'for ' // num(diag%certify_persistence) // ' x its transient and record periods)'
      end if
   end subroutine persistence_check

   !> A contradiction within a point's own evidence ('' when none): a period beside an
   !> exponent positive beyond chaos_sigmas standard errors (a stable orbit contracts: its
   !> exponent is negative), or a chaotic label beside a detected period. Either disputes the
   !> certificate, whatever the checks find.
   pure function contradiction(pr, diag) result(why)
      type(point_result_t), intent(in) :: pr             !! the diagnosed point
      type(diagnostics_settings_t), intent(in) :: diag   !! chaos_sigmas
      character(len=:), allocatable :: why
      why = ''
      if (pr%label >= 1 .and. pr%lyapunov_periods > 0 .and. pr%lyapunov > 0.0_dp .and. &
          pr%lyapunov > diag%chaos_sigmas * pr%lyapunov_error) then
         why = 'the label ' // label_text(pr%label) // ' contradicts its exponent (lambda ' &
            // num(pr%lyapunov) // ' +- ' // num(pr%lyapunov_error) // ' 1/s, positive beyond ' &
            // num(diag%chaos_sigmas) // ' sigma): a periodic orbit the run settled on ' &
            // 'contracts'
      else if (pr%label == label_chaotic .and. pr%period > 0) then
         why = 'the label chaotic contradicts the period ' // str(pr%period) // ' detected in ' &
            // 'its record'
      end if
   end function contradiction

   !> Compare one check with the point; the first disagreement becomes `reason`.
   subroutine record_check(pr, chk, err, kind, what, diag, reason)
      type(point_result_t), intent(inout) :: pr          !! the point
      type(point_result_t), intent(in) :: chk            !! the check's diagnosis
      type(error_t), allocatable, intent(in) :: err      !! the check's failure
      character(len=*), intent(in) :: kind               !! 'accuracy' or 'perturbed'
      character(len=*), intent(in) :: what              !! what the check ran, in words
      type(diagnostics_settings_t), intent(in) :: diag   !! orbit tolerance
      character(len=:), allocatable, intent(inout) :: reason  !! '' until a disagreement
      integer :: label
      real(dp) :: lam, sig, dist
      character(len=:), allocatable :: why
      why = ''
      if (allocated(err)) then
         label = label_failed;  lam = 0.0_dp;  sig = 0.0_dp;  dist = 0.0_dp
         why = 'the check with ' // what // ' failed: ' // err%message
      else
         label = chk%label;  lam = chk%lyapunov;  sig = chk%lyapunov_error
         dist = attractor_distance(pr, chk)
         if (label /= pr%label) then
            why = what // ' gives ' // label_text(label) // ' (lambda ' // num(lam) // ' +- ' &
               // num(sig) // ' 1/s) where the run gives ' // label_text(pr%label) &
               // ' (lambda ' // num(pr%lyapunov) // ' +- ' // num(pr%lyapunov_error) // ' 1/s)'
         else if (kind == 'accuracy' .and. label >= 1 .and. dist > diag%orbit_tolerance) then
            why = what // ' gives the same period but another orbit (distance ' // num(dist) &
               // ' of its size, tolerance ' // num(diag%orbit_tolerance) // ')'
         end if
      end if
      if (kind == 'accuracy') then
         pr%accuracy_label = label;  pr%accuracy_lyapunov = lam
         pr%accuracy_lyapunov_error = sig;  pr%accuracy_distance = dist
      else
         pr%perturbed_label = label;  pr%perturbed_lyapunov = lam
         pr%perturbed_lyapunov_error = sig;  pr%perturbed_distance = dist
      end if
      if (len(reason) == 0 .and. len(why) > 0) reason = why
   end subroutine record_check

   !> Settings of the accuracy check (see the module header); `needed` is false when the run
   !> itself was exact. `no_exact` asks for the tightened own method even where the exact
   !> integrator would apply.
   subroutine accuracy_settings(model, cfg, ratio, tight, what, needed, no_exact)
      type(model_t), intent(in) :: model                 !! model (its stop laws)
      type(solver_settings_t), intent(in) :: cfg         !! the run's settings
      real(dp), intent(in) :: ratio                      !! tightening factor (> 1)
      type(solver_settings_t), intent(out) :: tight      !! the check's settings
      character(len=:), allocatable, intent(out) :: what !! the check in words
      logical, intent(out) :: needed                     !! a check is possible
      logical, intent(in), optional :: no_exact          !! never the exact integrator
      type(solver_settings_t) :: eff, ex
      type(method_caps_t), allocatable :: t(:)
      character(len=:), allocatable :: reason
      logical :: exact_ok
      integer :: j
      call resolve_method(model, cfg, eff, reason)
      tight = eff
      needed = .not. is_exact(eff%method)
      what = ''
      if (.not. needed) return
      ! an exact method of the registry that can integrate the model (its laws piecewise
      ! linear, nothing it does not handle)
      t = method_table()
      exact_ok = .false.
      do j = 1, size(t)
         if (.not. t(j)%exact) cycle
         ex = eff;  ex%method = t(j)%name
         exact_ok = len(refusal(model, ex)) == 0
         if (exact_ok) exit
      end do
      if (present(no_exact)) exact_ok = exact_ok .and. .not. no_exact
      if (exact_ok) then
         tight = ex
         what = 'the exact integrator'
         return
      end if
      tight%tolerance = eff%tolerance / ratio
      tight%rk_rtol = eff%rk_rtol / ratio
      tight%half_step_tolerance = eff%half_step_tolerance / ratio
      tight%steps_per_period = nint(min(real(huge(1) / 2, dp), eff%steps_per_period * ratio))
      what = trim(eff%method) // ' (' // trim(eff%step_control) // ' step control) ' &
         // num(ratio) // ' x tighter'
   end subroutine accuracy_settings

   !> The accuracy check's diagnostics settings: the run's, with the automatic period
   !> tolerance of the deck's tolerance tightened by the ratio, and no stricter than the check's
   !> own; not the check's own alone, which method 'auto' may have tightened further (the
   !> modal exponential integrator runs a deck at 1e-3 at 1e-4 and its check at 1e-5: the
   !> check's orbit is judged at 10 x 1e-4, as a Newmark run's check at 1e-4 was, not at
   !> 10 x 1e-5, where an orbit the run found periodic came out undecided). The exact
   !> integrator keeps its own (1e-6); a deck's period_tolerance stays.
   function check_diagnostics(model, cfg, diag, tight) result(d)
      type(model_t), intent(in) :: model                 !! model of the point
      type(solver_settings_t), intent(in) :: cfg         !! the run's settings (the deck's)
      type(diagnostics_settings_t), intent(in) :: diag   !! the run's diagnostics settings
      type(solver_settings_t), intent(in) :: tight       !! the check's settings
      type(diagnostics_settings_t) :: d
      type(solver_settings_t) :: ref
      d = diag
      if (d%period_tolerance > 0.0_dp .or. is_exact(tight%method)) return
      ref = cfg
      ref%tolerance = cfg%tolerance / diag%certify_ratio
      d%period_tolerance = max(auto_period_tolerance(model, ref, diag), &
                               auto_period_tolerance(model, tight, diag))
   end function check_diagnostics

   !> A number in 3 significant digits.
   pure function num(x) result(t)
      real(dp), intent(in) :: x          !! value
      character(len=:), allocatable :: t
      character(len=16) :: buf
      if (x == 0.0_dp) then
         t = '0'
      else if (abs(x) >= 1.0e-2_dp .and. abs(x) < 1.0e4_dp) then
         write(buf, '(g0.3)') x
         t = trim(adjustl(buf))
      else
         write(buf, '(es9.2)') x
         t = trim(adjustl(buf))
      end if
   end function num
end module gapbeam_certify
