!> Diagnostics and the sweep: Lyapunov exponent, period detection, thread-count independence,
!> shards and merge, checkpoint and resume, and the exact zero-gap amplitude scaling.
program test_sweep
   !$ use omp_lib, only: omp_set_num_threads
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_settings, only: batch_options_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_full_model, initial_vectors
   use gapbeam_results, only: transient_result_t
   use gapbeam_transient, only: integrate
   use gapbeam_results, only: point_result_t
   use gapbeam_test_runs, only: make_plan_or_stop
   use gapbeam_sweep, only: sweep_plan_t, run_items, n_items, n_points
   use gapbeam_attractor, only: diagnose
   use gapbeam_sweep_job, only: run_sweep_job
   use gapbeam_sweep_output, only: sweep_file_t, read_sweep, merge_sweep
   use gapbeam_diagnostics, only: detect_period
   use gapbeam_files, only: remove_file, file_exists
   use gapbeam_blas_threads, only: serial_blas
   implicit none
   character(len=*), parameter :: small = 'test/decks/sweep_small.nml'
   character(len=*), parameter :: sdof = 'test/decks/sdof_bilinear.nml'

   if (serial_blas()) call note('OpenBLAS set to one thread')
   call lyapunov_of_linear_oscillator()
   call periodic_point_has_negative_exponent()
   call period_detection()
   call thread_count_independence()
   call shards_and_merge()
   call kill_and_resume()
   call zero_gap_scaling()
   call finish('test_sweep')

contains

   subroutine load(path, overrides, deck, model)
      character(len=*), intent(in) :: path, overrides(:)
      type(deck_t), intent(out) :: deck
      type(model_t), intent(out) :: model
      type(error_t), allocatable :: err
      character(len=200) :: ov(size(overrides))
      ov = overrides
      call read_deck(path, ov, deck, err)
      if (.not. allocated(err)) call build_full_model(deck%structure, deck%stops, deck%damping, &
                                                   deck%forcing, model, err)
      if (allocated(err)) then
         call check('load ' // path, .false., err%message)
         call finish('test_sweep')
      end if
   end subroutine load

   !> Mass-proportional damping decays every mode at beta/2: lambda = -zeta omega = -beta/2.
   subroutine lyapunov_of_linear_oscillator()
      type(deck_t) :: deck
      type(model_t) :: model
      type(point_result_t) :: pr
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      real(dp), parameter :: beta = 0.8_dp
      call load(sdof, [character(len=200) :: '&stops gap = 1.0 /', &
         "&damping model = 'rayleigh', mass_coefficient = 0.8 /", &
         '&forcing frequency_hz = 7.1, amplitude_pp = 1.0e-3 /', &
         '&solver transient_periods = 200, record_periods = 100 /', &
         '&diagnostics lyapunov_periods = 200 /'], deck, model)
      call initial_vectors(model, deck%initial, u0, v0)
      call diagnose(model, deck%solver, deck%output, deck%diagnostics, u0, v0, res, pr, err)
      call check('linear oscillator run succeeds', .not. allocated(err))
      call check_close('Lyapunov exponent of a damped linear oscillator = -zeta omega', &
         pr%lyapunov, -0.5_dp * beta, rtol=0.01_dp)
      call check('damped linear oscillator is labelled period 1', pr%label == 1)
   end subroutine lyapunov_of_linear_oscillator

   subroutine periodic_point_has_negative_exponent()
      type(deck_t) :: deck
      type(model_t) :: model
      type(point_result_t) :: pr
      type(transient_result_t) :: res
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:)
      call load('test/decks/moon_shaw_10p5hz_half_element.nml', [character(len=200) :: &
         '&solver transient_periods = 300, record_periods = 100 /'], deck, model)
      call initial_vectors(model, deck%initial, u0, v0)
      call diagnose(model, deck%solver, deck%output, deck%diagnostics, u0, v0, res, pr, err)
      call check('10.5 Hz point runs', .not. allocated(err))
      call note('10.5 Hz / 3.7 mm: period ' // str(pr%period) // ', lambda = ' &
         // str(pr%lyapunov) // ' +- ' // str(pr%lyapunov_error) // ' 1/s')
      call check('10.5 Hz point is labelled periodic', pr%label >= 1)
      call check('a periodic point has a negative exponent', &
         pr%lyapunov < 0.0_dp .and. pr%lyapunov + 3 * pr%lyapunov_error < 0.0_dp)
   end subroutine periodic_point_has_negative_exponent

   subroutine period_detection()
      real(dp) :: x(400), y(400), r
      integer :: p, i, seed(64)
      do p = 1, 4
         do i = 1, 400
            x(i) = cos(2 * pi * mod(i, p) / p + 0.3_dp) + 1.0e-9_dp * sin(17.0_dp * i)
            y(i) = sin(2 * pi * mod(i, p) / p + 0.3_dp) + 1.0e-9_dp * cos(13.0_dp * i)
         end do
         call check('period ' // str(p) // ' sequence detected', &
            detect_period(x, y, 12, 1.0e-6_dp, 64, 2.0_dp, 2.0_dp) == p)
      end do
      seed = 12345
      call random_seed(put=seed(1:size_seed()))
      do i = 1, 400
         call random_number(r);  x(i) = r
         call random_number(r);  y(i) = r
      end do
      call check('noise has no period', detect_period(x, y, 12, 1.0e-3_dp, 64, 1.0_dp, 1.0_dp) == 0)
   end subroutine period_detection

   integer function size_seed()
      call random_seed(size=size_seed)
      size_seed = min(size_seed, 64)
   end function size_seed

   !> Bitwise identical results with 1 and 2 threads, in both modes.
   subroutine thread_count_independence()
      type(deck_t) :: deck
      type(model_t) :: model
      type(point_result_t), allocatable :: r1(:), r2(:), r3(:)
      type(sweep_plan_t) :: plan
      real(dp), allocatable :: u0(:), v0(:)
      integer :: k, mode
      character(len=200) :: ov
      do mode = 1, 2
         ov = "&sweep mode = 'independent' /"
         if (mode == 2) ov = "&sweep mode = 'continuation' /"
         call load(small, [ov], deck, model)
         call make_plan_or_stop('test_sweep', deck, plan)
         call initial_vectors(model, deck%initial, u0, v0)
         allocate(r1(n_points(plan) * plan%ns), r2(n_points(plan) * plan%ns))
         !$ call omp_set_num_threads(1)
         call run_items(deck, model, plan, [(k, k = 1, n_items(plan))], u0, v0, r1)
         !$ call omp_set_num_threads(2)
         call run_items(deck, model, plan, [(k, k = 1, n_items(plan))], u0, v0, r2)
         call check(trim(ov) // ': 1 and 2 threads give bitwise identical points', &
            all([(same(r1(k), r2(k)), k = 1, size(r1))]))
         if (mode == 2) then
            ! a line run in rounds of points (as the sweep job does for its progress lines)
            ! starts each round from the final state of the point before: the same results
            allocate(r3(size(r1)))
            call run_items(deck, model, plan, [(k, k = 1, n_items(plan))], u0, v0, r3, 1, 1)
            call run_items(deck, model, plan, [(k, k = 1, n_items(plan))], u0, v0, r3, 2, 2)
            call run_items(deck, model, plan, [(k, k = 1, n_items(plan))], u0, v0, r3, 3, &
                           huge(1))
            call check(trim(ov) // ': a line run in rounds of points gives bitwise identical ' &
               // 'points', all([(same(r1(k), r3(k)), k = 1, size(r1))]))
            deallocate(r3)
         end if
         deallocate(r1, r2)
      end do
   end subroutine thread_count_independence


   logical function same(a, b)
      type(point_result_t), intent(in) :: a, b
      same = a%status == b%status .and. a%period == b%period .and. a%label == b%label .and. &
         a%lyapunov == b%lyapunov .and. all(a%p_strain == b%p_strain) .and. &
         all(a%p_strain_rate == b%p_strain_rate) .and. all(a%peak_force == b%peak_force) .and. &
         all(a%n_impacts == b%n_impacts) .and. all(a%work_rate == b%work_rate) .and. &
         all(a%lyapunov_running == b%lyapunov_running) .and. a%certificate == b%certificate &
         .and. a%accuracy_lyapunov == b%accuracy_lyapunov .and. &
         a%perturbed_lyapunov == b%perturbed_lyapunov .and. &
         a%transient_periods == b%transient_periods
   end function same

   !> Run the deck's sweep through the job driver (as the executable does).
   subroutine job(overrides, shard, n_shards, limit, complete)
      character(len=*), intent(in) :: overrides(:)
      integer, intent(in) :: shard, n_shards
      real(dp), intent(in) :: limit
      logical, intent(out) :: complete
      type(deck_t) :: deck
      type(error_t), allocatable :: err
      character(len=200) :: ov(size(overrides))
      integer :: n_failed
      ov = overrides
      call read_deck(small, ov, deck, err)
      if (.not. allocated(err)) then
         call run_sweep_job(deck, batch_options_t(shard_index=shard, shard_count=n_shards, &
                                                  time_limit_s=limit), complete, n_failed, err)
      end if
      if (allocated(err)) then
         call check('sweep job runs', .false., err%message)
         call finish('test_sweep')
      end if
   end subroutine job

   subroutine load_file(path, sf, res)
      character(len=*), intent(in) :: path
      type(sweep_file_t), intent(out) :: sf
      type(point_result_t), allocatable, intent(out) :: res(:)
      type(error_t), allocatable :: err
      call read_sweep(path, sf, res, err)
      if (allocated(err)) then
         call check('read ' // path, .false., err%message)
         call finish('test_sweep')
      end if
   end subroutine load_file

   logical function same_files(a, b, same_deck)
      character(len=*), intent(in) :: a, b
      logical, intent(in) :: same_deck   !! also require the same deck text
      type(sweep_file_t) :: sa, sb
      type(point_result_t), allocatable :: ra(:), rb(:)
      integer :: k
      call load_file(a, sa, ra)
      call load_file(b, sb, rb)
      same_files = (sa%deck_text == sb%deck_text .or. .not. same_deck) .and. &
         all(sa%points == sb%points) .and. &
         size(ra) == size(rb) .and. sa%shard_count == sb%shard_count
      if (same_files) same_files = all([(same(ra(k), rb(k)), k = 1, size(ra))])
   end function same_files

   subroutine shards_and_merge()
      type(error_t), allocatable :: err
      logical :: complete
      character(len=*), parameter :: full = "&job output = 'test_sweep_full' /"
      character(len=*), parameter :: part = "&job output = 'test_sweep_full' /"
      call job([character(len=200) :: full], 1, 1, 0.0_dp, complete)
      call check('single-process sweep completes', complete .and. &
                 file_exists('test_sweep_full.h5') .and. &
                 .not. file_exists('test_sweep_full.checkpoint'))
      call job([character(len=200) :: part], 1, 3, 0.0_dp, complete)
      call job([character(len=200) :: part], 2, 3, 0.0_dp, complete)
      call job([character(len=200) :: part], 3, 3, 0.0_dp, complete)
      call merge_sweep('test_sweep_merged', [character(len=64) :: &
         'test_sweep_full.shard_3_of_3.h5', 'test_sweep_full.shard_1_of_3.h5', &
         'test_sweep_full.shard_2_of_3.h5'], .false., err)
      call check('merge of 3 shards succeeds', .not. allocated(err))
      call check('merged shards equal the single-process run', &
         same_files('test_sweep_merged.h5', 'test_sweep_full.h5', .true.))
      call merge_sweep('test_sweep_bad', [character(len=64) :: &
         'test_sweep_full.shard_1_of_3.h5', 'test_sweep_full.shard_2_of_3.h5'], .false., err)
      call check('merge refuses a missing shard', allocated(err))
      if (allocated(err)) call note('message: ' // err%message)
      call merge_sweep('test_sweep_bad', [character(len=64) :: &
         'test_sweep_full.shard_1_of_3.h5', 'test_sweep_full.shard_2_of_3.h5', &
         'test_sweep_full.shard_2_of_3.h5'], .false., err)
      call check('merge refuses a duplicated shard', allocated(err))
      if (allocated(err)) call note('message: ' // err%message)
      call job([character(len=200) :: "&job output = 'test_sweep_other' /", &
         '&forcing amplitude_pp = 3.0e-3 /'], 2, 3, 0.0_dp, complete)
      call merge_sweep('test_sweep_bad', [character(len=64) :: &
         'test_sweep_full.shard_1_of_3.h5', 'test_sweep_other.shard_2_of_3.h5', &
         'test_sweep_full.shard_3_of_3.h5'], .false., err)
      call check('merge refuses shards of a different deck', allocated(err))
      if (allocated(err)) call note('message: ' // err%message)
      call check('a refused merge writes no file', .not. file_exists('test_sweep_bad.h5'))
      call remove_file('test_sweep_merged.h5')
      call remove_file('test_sweep_full.shard_1_of_3.h5')
      call remove_file('test_sweep_full.shard_2_of_3.h5')
      call remove_file('test_sweep_full.shard_3_of_3.h5')
      call remove_file('test_sweep_other.shard_2_of_3.h5')
   end subroutine shards_and_merge

   !> Stop after the first chunk (time limit), cut the checkpoint's last record short as a
   !> kill during a write would, then run again: the result equals the uninterrupted run.
   subroutine kill_and_resume()
      logical :: complete
      integer :: u, fsize
      character(len=:), allocatable :: bytes
      type(error_t), allocatable :: err
      type(deck_t) :: deck
      character(len=*), parameter :: res = "&job output = 'test_sweep_resume' /"
      integer :: n_failed
      call job([character(len=200) :: res], 1, 1, 1.0e-9_dp, complete)
      call check('time limit stops the sweep with its checkpoint kept', .not. complete .and. &
         file_exists('test_sweep_resume.checkpoint') .and. &
         .not. file_exists('test_sweep_resume.h5'))
      ! cut the file inside its last record
      open(newunit=u, file='test_sweep_resume.checkpoint', access='stream', form='unformatted', &
           status='old')
      inquire(unit=u, size=fsize)
      allocate(character(len=fsize - 13) :: bytes)
      read(u) bytes
      close(u, status='delete')
      open(newunit=u, file='test_sweep_resume.checkpoint', access='stream', form='unformatted', &
           status='new')
      write(u) bytes
      close(u)
      ! a different deck is refused, not mixed
      call read_deck(small, [character(len=200) :: res, '&forcing amplitude_pp = 3.0e-3 /'], &
                     deck, err)
      call run_sweep_job(deck, batch_options_t(), complete, n_failed, err)
      call check('a different deck against the checkpoint is refused', allocated(err))
      if (allocated(err)) call note('message: ' // err%message)
      call job([character(len=200) :: res], 1, 1, 0.0_dp, complete)
      call check('resumed sweep completes and removes its checkpoint', complete .and. &
         .not. file_exists('test_sweep_resume.checkpoint'))
      call check('killed and resumed sweep equals the uninterrupted run', &
         same_files('test_sweep_resume.h5', 'test_sweep_full.h5', .false.))
      call remove_file('test_sweep_resume.h5')
      call remove_file('test_sweep_full.h5')
   end subroutine kill_and_resume

   !> Zero gap, bilinear stop: the point at 2A is exactly twice the point at A.
   subroutine zero_gap_scaling()
      type(deck_t) :: deck
      type(model_t) :: model
      type(point_result_t), allocatable :: r(:)
      type(sweep_plan_t) :: plan
      real(dp), allocatable :: u0(:), v0(:)
      integer :: k, nf
      logical :: ok
      call load(small, [character(len=200) :: "&sweep mode = 'independent' /"], deck, model)
      call make_plan_or_stop('test_sweep', deck, plan)
      call initial_vectors(model, deck%initial, u0, v0)
      allocate(r(n_points(plan) * plan%ns))
      call run_items(deck, model, plan, [(k, k = 1, n_items(plan))], u0, v0, r)
      nf = size(deck%sweep%frequency_hz)
      ok = .true.
      do k = 1, nf   ! amplitudes 2 mm and 4 mm
         ok = ok .and. all(r(k + nf)%p_strain == 2 * r(k)%p_strain) .and. &
              all(r(k + nf)%peak_force == 2 * r(k)%peak_force) .and. &
              r(k + nf)%label == r(k)%label .and. r(k + nf)%lyapunov == r(k)%lyapunov
      end do
      call check('zero gap sweep: the 4 mm points are exactly twice the 2 mm points, ' &
         // 'same labels and exponents', ok)
   end subroutine zero_gap_scaling
end program test_sweep
