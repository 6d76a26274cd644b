!> Label and certify a point: the one procedure of the transient job and of the sweep (the
!> continuation's brute-force companion is a sweep).
!>
!> A point is a model (the deck's, or the deck's with a sweep's axis values) and its starts
!> (&diagnostics starts, gapbeam_starts' start_list). For each start:
!>    start state (start_vector) -> transient, settling, record, period, exponent, label
!>    (gapbeam_attractor: diagnose) -> certificate (gapbeam_certify, first start only)
!> and over the starts the distinct attractors (gapbeam_starts: group_attractors). One
!> integrator cache serves every run of one model: the records and their extensions, the
!> exponent's pair, the certificate's checks and the further starts use the integrator built
!> for their settings once (gapbeam_transient: integrator_cache_t).
!>
!> Numbering: the random start k of point p draws stream stream_random + n_s (p - 1) + k
!> (n_s starts per point) and the certificate's perturbed start stream seed p; the transient
!> job is point 1, so a one-point sweep of the deck gives the transient job's label and
!> certificate.
module gapbeam_point
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: solver_settings_t, output_settings_t, diagnostics_settings_t
   use gapbeam_results, only: transient_result_t, point_result_t
   use gapbeam_attractor, only: diagnose
   use gapbeam_certify, only: certify_point
   use gapbeam_starts, only: start_list, random_state, group_attractors
   use gapbeam_transient, only: integrator_cache_t
   use gapbeam_progress, only: monitor_t
   implicit none
   private
   public :: start_vector, label_start, label_point, integrator_cache_t

   integer, parameter :: stream_random = 1000000   !! generator streams of the random starts

contains

   !> The initial state of start k (of n_starts) of point `point`: the previous point's final
   !> state for 'up' / 'down' (u_prev, v_prev: the deck's at a line's first point), zero for
   !> 'rest', a seeded random state for 'random' (amplitude random_amplitude, or the point's
   !> peak-to-peak base amplitude), else the deck's (u_deck, v_deck).
   subroutine start_vector(model, diag, kind, point, n_starts, k, u_deck, v_deck, u_prev, &
                           v_prev, u, v, err)
      type(model_t), intent(in) :: model                 !! model of the point
      type(diagnostics_settings_t), intent(in) :: diag   !! seed, amplitude
      character(len=*), intent(in) :: kind               !! start kind
      integer, intent(in) :: point                       !! point number (1..)
      integer, intent(in) :: n_starts                    !! starts per point
      integer, intent(in) :: k                           !! this start (1..n_starts)
      real(dp), intent(in) :: u_deck(:), v_deck(:)       !! the deck's initial state
      real(dp), intent(in) :: u_prev(:), v_prev(:)       !! handed along a line
      real(dp), allocatable, intent(out) :: u(:), v(:)   !! the start
      type(error_t), allocatable, intent(out) :: err     !! modes for a random state failed
      real(dp) :: amplitude
      select case (kind)
      case ('up', 'down')
         u = u_prev;  v = v_prev
      case ('rest')
         allocate(u(size(u_deck)), v(size(v_deck)), source=0.0_dp)
      case ('random')
         amplitude = diag%random_amplitude
         if (.not. (amplitude > 0.0_dp)) amplitude = 2.0_dp * model%half_amplitude
         call random_state(model, diag%random_seed, stream_random + n_starts * (point - 1) + k, &
                           amplitude, u, v, err)
      case default
         u = u_deck;  v = v_deck
      end select
   end subroutine start_vector

   !> One start of a point: diagnosed from (u, v) (settled, period, exponent, label), then
   !> certified when asked (with the point's number as its seed), every run with the
   !> integrators of `cache`. `out` records the run; the certificate's checks keep no history.
   subroutine label_start(model, solver, out, diag, u, v, point, certify, res, pr, err, &
                          cache, monitor)
      type(model_t), intent(in) :: model                 !! model of the point
      type(solver_settings_t), intent(in) :: solver      !! the run's settings
      type(output_settings_t), intent(in) :: out         !! what the run records
      type(diagnostics_settings_t), intent(in) :: diag   !! classification settings
      real(dp), intent(in) :: u(:), v(:)                 !! the start
      integer, intent(in) :: point                       !! point number (certificate seed)
      logical, intent(in) :: certify                     !! certify the label
      type(transient_result_t), intent(out) :: res       !! the final record
      type(point_result_t), intent(inout) :: pr          !! label, evidence, certificate
      type(error_t), allocatable, intent(out) :: err     !! solver failure
      type(integrator_cache_t), intent(inout) :: cache   !! this model's integrators
      class(monitor_t), intent(inout), optional :: monitor   !! told the run's progress
      type(output_settings_t) :: quiet
      call diagnose(model, solver, out, diag, u, v, res, pr, err, monitor, cache)
      if (allocated(err) .or. .not. certify) return
      quiet = out
      quiet%history_periods = 0
      call certify_point(model, solver, quiet, diag, u, v, point, pr, cache)
   end subroutine label_start

   !> Every start of one point (the deck's model: the transient job), the first recorded with
   !> `out` and the monitor and certified when the deck asks, the others without history;
   !> their attractors grouped into `pr` (the first start's result). A failed further start
   !> is marked (status 1, label 'failed') and its message returned in `failures`; a failure
   !> of the first start is the error.
   subroutine label_point(model, solver, out, diag, u_deck, v_deck, point, res, pr, err, &
                          failures, monitor)
      type(model_t), intent(in) :: model                 !! the point's model
      type(solver_settings_t), intent(in) :: solver      !! the run's settings
      type(output_settings_t), intent(in) :: out         !! what the first start records
      type(diagnostics_settings_t), intent(in) :: diag   !! starts, classification
      real(dp), intent(in) :: u_deck(:), v_deck(:)       !! the deck's initial state
      integer, intent(in) :: point                       !! point number
      type(transient_result_t), intent(out) :: res       !! the first start's final record
      type(point_result_t), intent(out) :: pr            !! the point
      type(error_t), allocatable, intent(out) :: err     !! the first start failed
      !> one line per failed further start ("start k ('kind') failed: ...")
      character(len=:), allocatable, intent(out) :: failures(:)
      class(monitor_t), intent(inout), optional :: monitor   !! told the first run's progress
      type(integrator_cache_t) :: cache
      type(point_result_t), allocatable :: runs(:)
      type(transient_result_t) :: other
      type(output_settings_t) :: quiet
      type(error_t), allocatable :: run_err
      character(len=8), allocatable :: kinds(:)
      character(len=512), allocatable :: lines(:)
      integer, allocatable :: ridx(:)
      real(dp), allocatable :: u(:), v(:)
      integer :: k, nf
      call start_list(diag, 'deck', kinds, ridx)
      allocate(runs(size(kinds)), lines(size(kinds)))
      call start_vector(model, diag, kinds(1), point, size(kinds), 1, u_deck, v_deck, u_deck, &
                        v_deck, u, v, err)
      if (allocated(err)) return
      call label_start(model, solver, out, diag, u, v, point, diag%certify, res, pr, err, &
                       cache, monitor)
      if (allocated(err)) return
      runs(1) = pr
      quiet = out
      quiet%history_periods = 0
      nf = 0
      do k = 2, size(kinds)
         call start_vector(model, diag, kinds(k), point, size(kinds), k, u_deck, v_deck, &
                           u_deck, v_deck, u, v, err)
         if (allocated(err)) return
         call label_start(model, solver, quiet, diag, u, v, point, .false., other, runs(k), &
                          run_err, cache)
         if (allocated(run_err)) then
            runs(k)%status = 1
            nf = nf + 1
            lines(nf) = 'start ' // str(k) // " ('" // trim(kinds(k)) // "') failed: " &
               // run_err%message
            deallocate(run_err)
         end if
      end do
      call group_attractors(runs, diag, pr)
      allocate(character(len=512) :: failures(nf))
      failures = lines(1:nf)
   end subroutine label_point
end module gapbeam_point
