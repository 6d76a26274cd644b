!> Runs a sweep job: its shard of the work items in chunks of parallel work, a checkpoint
!> record for every finished point and progress (both outside the parallel region), then the
!> result files.
!>
!> In continuation mode the lines of a chunk are run in rounds of a few points along every
!> line (each point still starting from the final state of the one before, so the results are
!> the same), so that a sweep of one long line reports its progress and checkpoints its points
!> as it goes. The time limit is checked between chunks (whole lines) only.
module gapbeam_sweep_job
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit, int64
   !$ use omp_lib, only: omp_get_max_threads
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t, add_warning
   use gapbeam_settings, only: sweep_settings_t, batch_options_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: point_result_t, label_chaotic, label_undecided, label_unsettled, &
      label_failed, certificate_none, certificate_certified, certificate_disputed
   use gapbeam_model_builder, only: build_model
   use gapbeam_reduction_rule, only: reduction_info_t, reduction_text
   use gapbeam_sweep, only: sweep_plan_t, make_plan, n_points, n_items, item_slots, run_items, &
      group_of_item, group_points, slot_index, combine_point
   use gapbeam_checkpoint, only: checkpoint_t, checkpoint_open, checkpoint_append, &
      checkpoint_close
   use gapbeam_sweep_output, only: sweep_file_t, write_sweep, sweep_warnings
   use gapbeam_warning_text, only: warning_length, warning_prefix
   use gapbeam_files, only: make_parent_directory
   use gapbeam_progress_meter, only: meter_t
   use gapbeam_parameters, only: run_parameters, stiffness_units
   use gapbeam_kinds, only: pi
   use gapbeam_clock, only: process_cpu_seconds
   use gapbeam_shards, only: shard_deal_t, deal_shards, shard_items, deal_signature, deal_summary
   use gapbeam_stop_signal, only: stop_requested
   implicit none
   private
   public :: run_sweep_job, sweep_prefix

   !> Exit status of a sweep stopped by its time limit (checkpoint kept, run again to finish).
   integer, parameter, public :: status_interrupted = 3
   !> Exit status of a sweep (or merge) that wrote everything but in which some runs failed.
   integer, parameter, public :: status_failed_points = 5

contains

   !> Output prefix of a shard: PREFIX, or PREFIX.shard_I_of_N.
   function sweep_prefix(deck, batch) result(prefix)
      type(deck_t), intent(in) :: deck              !! the deck
      type(batch_options_t), intent(in) :: batch    !! the shard
      character(len=:), allocatable :: prefix
      prefix = trim(deck%job%output)
      if (batch%shard_count > 1) prefix = prefix // '.shard_' &
         // str(batch%shard_index) // '_of_' // str(batch%shard_count)
   end function sweep_prefix

   !> Run the deck's sweep (its shard); `complete` is false when the time limit stopped it.
   !> `n_failed` counts the failed runs (points or other starts) of the shard, each listed on
   !> standard error; the files are written whatever it is.
   subroutine run_sweep_job(deck, batch, complete, n_failed, err)
      type(deck_t), intent(in) :: deck                 !! validated deck
      type(batch_options_t), intent(in) :: batch       !! shard and time limit
      logical, intent(out) :: complete                 !! all points of the shard done
      integer, intent(out) :: n_failed                 !! failed runs of the shard
      type(error_t), allocatable, intent(out) :: err   !! setup, I/O or checkpoint failure
      type(model_t) :: base
      type(reduction_info_t) :: reduced
      type(sweep_plan_t) :: plan
      type(point_result_t), allocatable :: slots(:)
      type(checkpoint_t) :: ck
      logical, allocatable :: done(:)
      integer, allocatable :: mine(:), todo(:), ss(:)
      real(dp), allocatable :: u0(:), v0(:)
      integer :: k, np, ni, n_loaded, chunk, first, last, threads, n_done, n_total, n_pos, &
         n_round, j1
      type(meter_t) :: meter
      integer(int64) :: c0, c1, rate
      real(dp) :: elapsed, cpu0
      character(len=:), allocatable :: prefix, report
      type(shard_deal_t) :: deal

      complete = .false.
      n_failed = 0
      call system_clock(c0, rate)
      cpu0 = process_cpu_seconds()
      call build_model(deck, base, u0, v0, err, reduced)
      if (allocated(err)) return
      if (deck%reduction%kind /= 'none') write(output_unit, '(a)') &
         reduction_text(reduced, deck%solver%tolerance) // ' (every point keeps these modes)'
      call make_plan(deck, plan, err)
      if (allocated(err)) return
      np = n_points(plan);  ni = n_items(plan)
      call deal_shards(plan, batch, deal, err)
      if (allocated(err)) return
      mine = shard_items(plan, deal, batch%shard_index)
      allocate(slots(np * plan%ns), done(np * plan%ns))
      done = .false.
      prefix = sweep_prefix(deck, batch)
      n_loaded = 0
      ! the output directory first: the checkpoint goes there
      call make_parent_directory(prefix, err)
      if (allocated(err)) return
      if (deck%sweep%checkpoint) then
         call checkpoint_open(ck, prefix // '.checkpoint', deck%text // new_line('a') &
            // '! shard ' // str(batch%shard_index) // ' of ' &
            // str(batch%shard_count) // deal_signature(deal), slots, done, n_loaded, report, err)
         if (allocated(err)) return
         if (len(report) > 0) then
            write(error_unit, '(a)') 'sweep: checkpoint: ' // replace_new_lines(report, &
               new_line('a') // 'sweep: checkpoint: ')
            flush(error_unit)
         end if
      end if
      allocate(todo(0))
      n_total = 0
      do k = 1, size(mine)
         ss = item_slots(plan, mine(k))
         n_total = n_total + size(ss)
         if (.not. all(done(ss))) todo = [todo, mine(k)]
      end do
      n_done = n_total - sum([(size(item_slots(plan, todo(k))), k = 1, size(todo))])
      threads = 1
      !$ threads = omp_get_max_threads()
      ! work items between checkpoint writes and progress lines: each chunk ends in a barrier,
      ! so chunks are long; without checkpoint and progress the whole shard is one chunk
      chunk = deck%sweep%chunk
      if (chunk == 0) chunk = merge(4, 64, plan%lines) * threads
      if (.not. deck%sweep%checkpoint .and. .not. deck%sweep%progress .and. &
          deck%sweep%chunk == 0) chunk = max(1, size(todo))
      write(output_unit, '(a)') 'sweep: ' // str(np) // ' points (' // str(plan%nx) // ' x ' &
         // str(plan%ny) // ': ' // trim(plan%label(1)) // ' x ' &
         // trim(plan%label(2)) // '), ' // str(plan%ns) // ' start(s) per ' &
         // 'point (' // start_names(plan) // '), certification ' &
         // trim(merge('on ', 'off', deck%diagnostics%certify)) // ', shard ' &
         // str(batch%shard_index) // ' of ' // str(batch%shard_count) // ': ' &
         // str(n_total) // ' runs, ' // str(n_done) // ' already in the checkpoint; ' &
         // str(threads) // ' threads'
      if (len(deal_summary(deal, batch%shard_index)) > 0) write(output_unit, '(a)') &
         deal_summary(deal, batch%shard_index)

      first = 1
      call meter%start('sweep', trim(merge('points', 'runs  ', plan%ns == 1)), &
         real(n_total, dp), real(n_done, dp), deck%sweep%progress .and. .not. batch%quiet, batch%progress_interval_s)
      do while (first <= size(todo))
         last = min(size(todo), first + chunk - 1)
         if (plan%lines) then
            ! rounds of `n_round` positions along every line of the chunk: about 8 runs per
            ! thread per round, so that the barrier at the end of a round costs little
            n_pos = size(item_slots(plan, todo(first)))
            n_round = max(1, (8 * threads + (last - first)) / (last - first + 1))
            do j1 = 1, n_pos, n_round
               call run_items(deck, base, plan, todo(first:last), u0, v0, slots, j1, &
                              j1 + n_round - 1)
               call finish_slots(plan, todo(first:last), j1, j1 + n_round - 1, slots, &
                                 deck%sweep%checkpoint, ck, done, n_done, err)
               if (allocated(err)) return
               call meter%update(real(n_done, dp))
            end do
         else
            call run_items(deck, base, plan, todo(first:last), u0, v0, slots)
            call finish_slots(plan, todo(first:last), 1, huge(1), slots, &
                              deck%sweep%checkpoint, ck, done, n_done, err)
            if (allocated(err)) return
            call meter%update(real(n_done, dp))
         end if
         first = last + 1
         call system_clock(c1)
         elapsed = real(c1 - c0, dp) / real(rate, dp)
         if ((batch%time_limit_s > 0.0_dp .and. elapsed >= batch%time_limit_s .or. &
              stop_requested()) .and. first <= size(todo)) then
            call meter%finish(real(n_done, dp))
            call checkpoint_close(ck, delete=.false.)
            write(output_unit, '(a)') 'sweep: ' // trim(merge('stopped by SIGTERM', &
               'time limit reached', stop_requested())) // ' after ' // str(n_done) // '/' &
               // str(n_total) // ' runs; the checkpoint ' // prefix // '.checkpoint keeps ' &
               // 'them: run the same command again to finish'
            return
         end if
      end do
      call meter%finish()

      if (.not. allocated(meter%warning)) meter%warning = ''
      call write_shard(deck, batch, plan, base, slots, mine, prefix, cpu0, c0, rate, threads, &
                       meter%warning, n_failed, err)
      if (allocated(err)) return
      if (deck%sweep%checkpoint) call checkpoint_close(ck, delete=.true.)
      complete = .true.

   end subroutine run_sweep_job

   !> The shard's results: every point's first start with all starts' attractors, failures
   !> listed on standard error and counted in `n_failed`, the files under `prefix`, the
   !> summary lines.
   subroutine write_shard(deck, batch, plan, base, slots, mine, prefix, cpu0, c0, rate, &
                          threads, long_run, n_failed, err)
      type(deck_t), intent(in) :: deck                 !! validated deck
      type(batch_options_t), intent(in) :: batch       !! shard
      type(sweep_plan_t), intent(in) :: plan           !! the sweep's plan
      type(model_t), intent(in) :: base                !! the deck's model
      type(point_result_t), intent(in) :: slots(:)     !! every run of the sweep (the shard's done)
      integer, intent(in) :: mine(:)                   !! the shard's work items
      character(len=*), intent(in) :: prefix           !! output prefix
      real(dp), intent(in) :: cpu0                     !! process CPU time at the start [s]
      integer(int64), intent(in) :: c0, rate           !! wall clock at the start, its rate
      integer, intent(in) :: threads                   !! OpenMP threads
      character(len=*), intent(in) :: long_run         !! the meter's long-run warning, or ''
      integer, intent(inout) :: n_failed               !! failed runs of the shard
      type(error_t), allocatable, intent(out) :: err   !! I/O failure
      type(point_result_t), allocatable :: results(:)
      type(sweep_file_t) :: sf
      type(deck_t) :: notes                            !! the warnings the file stores
      integer, allocatable :: pts(:)
      integer :: k, j, np
      integer(int64) :: c1
      np = n_points(plan)
      ! every point of the shard: its first start with all starts' attractors; failures listed
      pts = shard_points(plan, mine)
      allocate(results(np))
      do k = 1, size(pts)
         results(pts(k)) = combine_point(deck, plan, slots, pts(k))
         do j = 1, plan%ns
            associate (sr => slots(slot_index(plan, pts(k), j)))
               if (sr%status /= 0) then
                  n_failed = n_failed + 1
                  write(error_unit, '(a)') 'sweep: failed: ' // sr%message
               end if
            end associate
         end do
      end do
      sf%deck_text = deck%text
      if (allocated(deck%warnings)) notes%warnings = deck%warnings
      if (len(long_run) > 0) call add_warning(notes, long_run)
      if (allocated(notes%warnings)) sf%warnings = notes%warnings
      sf%title = trim(deck%job%title)
      sf%grid_frequency_hz = deck%sweep%frequency_hz
      sf%grid_amplitude_pp = deck%sweep%amplitude_pp
      sf%x_variable = trim(plan%label(1))
      sf%y_variable = trim(plan%label(2))
      sf%x_units = trim(plan%var(1)%units)
      sf%y_units = trim(plan%var(2)%units)
      sf%grid_x = plan%x
      sf%grid_y = plan%y
      sf%start_kind = plan%kinds
      sf%shard_index = batch%shard_index
      sf%shard_count = batch%shard_count
      sf%points = pts
      sf%parameters = run_parameters(deck, base%stop_stiffness, base%f1_open_hz, &
                                     base%omega_max / (2.0_dp * pi), base%n)
      sf%model = base;  sf%stiffness_units = stiffness_units(deck)
      sf%cpu_seconds = process_cpu_seconds() - cpu0   ! inside the wall-time window
      call system_clock(c1)
      sf%wall_seconds = real(c1 - c0, dp) / real(rate, dp)
      sf%threads = threads
      call write_sweep(prefix, sf, results, deck%output%write_text, err)
      if (allocated(err)) return
      call print_new_warnings(sf, results)
      call summary(results(pts), n_failed, plan%ns)
      write(output_unit, '(a)') 'cpu: ' // str(sf%cpu_seconds) // ' s (all threads), wall ' &
         // str(sf%wall_seconds) // ' s, ' // str(threads) // ' thread(s)'
      call system_clock(c1)
      write(output_unit, '(a)') 'sweep: ' // str(size(pts)) // ' points in ' &
         // str(real(c1 - c0, dp) / real(rate, dp)) // ' s; files: ' // prefix // '.h5' &
         // trim(merge(', .sweep.dat, .bifurcation.dat', '                              ', &
         deck%output%write_text))
      if (n_failed > 0) write(output_unit, '(a)') 'sweep: ' // str(n_failed) // ' failed ' &
         // 'run(s), listed above on standard error and marked in the files (status 1, label ' &
         // "'failed')"
   end subroutine write_shard

   !> The warnings the sweep's points add to the deck's (stops never touched), on standard
   !> error.
   subroutine print_new_warnings(sf, results)
      type(sweep_file_t), intent(in) :: sf               !! file description
      type(point_result_t), intent(in) :: results(:)     !! all points
      character(len=warning_length), allocatable :: lines(:)
      integer :: k, k0
      lines = sweep_warnings(sf, results)
      k0 = 0
      if (allocated(sf%warnings)) k0 = size(sf%warnings)
      do k = k0 + 1, size(lines)
         write(error_unit, '(a)') warning_prefix // trim(lines(k))
      end do
   end subroutine print_new_warnings

   !> The starts of a plan, comma separated ('random' counted once with its number).
   function start_names(plan) result(t)
      type(sweep_plan_t), intent(in) :: plan    !! plan
      character(len=:), allocatable :: t
      integer :: k
      t = ''
      do k = 1, plan%ns
         if (plan%random_index(k) > 1) cycle
         if (len(t) > 0) t = t // ', '
         if (plan%kinds(k) == 'random') then
            t = t // 'random x ' // str(count(plan%random_index > 0))
         else
            t = t // trim(plan%kinds(k))
         end if
      end do
   end function start_names

   !> Positions j_first..j_last of the slots of `items` are done: mark them, count them and
   !> append each successful one to the checkpoint (when there is one).
   subroutine finish_slots(plan, items, j_first, j_last, slots, with_checkpoint, ck, done, &
                           n_done, err)
      type(sweep_plan_t), intent(in) :: plan             !! plan
      integer, intent(in) :: items(:)                    !! work items just run
      integer, intent(in) :: j_first, j_last             !! positions along each item
      type(point_result_t), intent(in) :: slots(:)       !! results, by slot
      logical, intent(in) :: with_checkpoint             !! append to `ck`
      type(checkpoint_t), intent(inout) :: ck            !! the checkpoint
      logical, intent(inout) :: done(:)                  !! slots done, by slot
      integer, intent(inout) :: n_done                   !! count of slots done
      type(error_t), allocatable, intent(out) :: err     !! checkpoint write failure
      integer :: k, j
      integer, allocatable :: ss(:)
      do k = 1, size(items)
         ss = item_slots(plan, items(k))
         do j = j_first, min(j_last, size(ss))
            done(ss(j)) = .true.
            n_done = n_done + 1
            if (with_checkpoint .and. slots(ss(j))%status == 0) then
               call checkpoint_append(ck, ss(j), slots(ss(j)), err)
               if (allocated(err)) return
            end if
         end do
      end do
   end subroutine finish_slots

   !> `text` with every new line replaced by `by`.
   pure function replace_new_lines(text, by) result(t)
      character(len=*), intent(in) :: text             !! lines
      character(len=*), intent(in) :: by               !! replacement of each new line
      character(len=:), allocatable :: t
      integer :: i
      t = ''
      do i = 1, len(text)
         if (text(i:i) == new_line('a')) then
            t = t // by
         else
            t = t // text(i:i)
         end if
      end do
   end function replace_new_lines

   !> All points of the given items, ascending.
   function shard_points(plan, items) result(pts)
      type(sweep_plan_t), intent(in) :: plan
      integer, intent(in) :: items(:)
      integer, allocatable :: pts(:)
      logical, allocatable :: mask(:)
      integer :: k
      allocate(mask(n_points(plan)), source=.false.)
      do k = 1, size(items)
         mask(group_points(plan, group_of_item(plan, items(k)))) = .true.
      end do
      pts = pack([(k, k = 1, size(mask))], mask)
   end function shard_points

   !> Counts of the labels, the certificates and the points with coexisting attractors.
   subroutine summary(res, n_failed, n_starts)
      type(point_result_t), intent(in) :: res(:)
      integer, intent(in) :: n_failed, n_starts
      integer :: p, c
      character(len=:), allocatable :: line
      line = 'labels:'
      do p = 1, maxval([0, res%label])
         c = count(res%label == p)
         if (c > 0) line = line // ' period ' // str(p) // ': ' // str(c) // ';'
      end do
      line = line // ' chaotic: ' // str(count(res%label == label_chaotic)) // '; undecided: ' &
         // str(count(res%label == label_undecided)) // '; unsettled: ' &
         // str(count(res%label == label_unsettled)) // '; failed: ' &
         // str(count(res%label == label_failed))
      write(output_unit, '(a)') line
      write(output_unit, '(a)') 'certificates: certified ' &
         // str(count(res%certificate == certificate_certified)) // ', disputed ' &
         // str(count(res%certificate == certificate_disputed)) // ', none ' &
         // str(count(res%certificate == certificate_none))
      if (n_starts > 1) write(output_unit, '(a)') 'attractors: ' &
         // str(count(res%n_attractors > 1)) // ' point(s) with coexisting attractors (' &
         // str(n_starts) // ' starts per point)'
      if (n_failed > 0) write(output_unit, '(a)') 'failed runs: ' // str(n_failed)
   end subroutine summary
end module gapbeam_sweep_job
