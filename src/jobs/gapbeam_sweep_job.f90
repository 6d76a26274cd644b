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
   use gapbeam_deck, only: deck_t
   use gapbeam_settings, only: sweep_settings_t, batch_options_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: point_result_t, label_chaotic, label_undecided
   use gapbeam_model_builder, only: build_model
   use gapbeam_sweep, only: n_points, n_items, item_points, run_items
   use gapbeam_checkpoint, only: checkpoint_t, checkpoint_open, checkpoint_append, &
      checkpoint_close
   use gapbeam_sweep_output, only: sweep_file_t, write_sweep
   use gapbeam_files, only: make_parent_directory
   use gapbeam_progress_meter, only: meter_t
   use gapbeam_parameters, only: run_parameters
   use gapbeam_kinds, only: pi
   use gapbeam_deck_variable, only: deck_variable_t, parse_deck_variable, check_deck_variable, &
      deck_variable_label
   implicit none
   private
   public :: run_sweep_job, sweep_prefix

   !> Exit status of a sweep stopped by its time limit (checkpoint kept, run again to finish).
   integer, parameter, public :: status_interrupted = 3

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
   subroutine run_sweep_job(deck, batch, complete, err)
      type(deck_t), intent(in) :: deck                 !! validated deck
      type(batch_options_t), intent(in) :: batch       !! shard and time limit
      logical, intent(out) :: complete                 !! all points of the shard done
      type(error_t), allocatable, intent(out) :: err   !! setup, I/O or checkpoint failure
      type(model_t) :: base
      type(point_result_t), allocatable :: results(:)
      type(checkpoint_t) :: ck
      type(sweep_file_t) :: sf
      logical, allocatable :: done(:)
      integer, allocatable :: mine(:), todo(:), pts(:)
      real(dp), allocatable :: u0(:), v0(:)
      integer :: k, np, ni, n_loaded, chunk, first, last, threads, j, n_done, n_total, n_failed, &
         n_pos, block, j1
      type(meter_t) :: meter
      integer(int64) :: c0, c1, rate
      real(dp) :: elapsed
      character(len=:), allocatable :: prefix, report
      type(deck_variable_t), allocatable :: vars(:)

      complete = .false.
      call system_clock(c0, rate)
      call build_model(deck, base, u0, v0, err)
      if (allocated(err)) return
      call axis_variables(deck, vars, err)
      if (allocated(err)) return
      np = n_points(deck%sweep);  ni = n_items(deck%sweep)
      mine = pack([(k, k = 1, ni)], [(mod(k - 1, batch%shard_count) + 1 &
                  == batch%shard_index, k = 1, ni)])
      allocate(results(np), done(np))
      done = .false.
      prefix = sweep_prefix(deck, batch)
      n_loaded = 0
      ! the output directory first: the checkpoint goes there
      call make_parent_directory(prefix, err)
      if (allocated(err)) return
      if (deck%sweep%checkpoint) then
         call checkpoint_open(ck, prefix // '.checkpoint', deck%text // new_line('a') &
            // '! shard ' // str(batch%shard_index) // ' of ' &
            // str(batch%shard_count), results, done, n_loaded, report, err)
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
         pts = item_points(deck%sweep, mine(k))
         n_total = n_total + size(pts)
         if (.not. all(done(pts))) todo = [todo, mine(k)]
      end do
      n_done = n_total - sum([(size(item_points(deck%sweep, todo(k))), k = 1, size(todo))])
      threads = 1
      !$ threads = omp_get_max_threads()
      ! work items between checkpoint writes and progress lines: each chunk ends in a barrier,
      ! so chunks are long; without checkpoint and progress the whole shard is one chunk
      chunk = deck%sweep%chunk
      if (chunk == 0) chunk = merge(4, 64, deck%sweep%mode == 'continuation') * threads
      if (.not. deck%sweep%checkpoint .and. .not. deck%sweep%progress .and. &
          deck%sweep%chunk == 0) chunk = max(1, size(todo))
      write(output_unit, '(a)') 'sweep: ' // str(np) // ' points (' &
         // str(size(deck%sweep%frequency_hz)) // ' frequencies x ' &
         // str(size(deck%sweep%amplitude_pp)) // ' ' // axis_words(vars) // '), mode ' &
         // trim(deck%sweep%mode) // ', shard ' // str(batch%shard_index) // ' of ' &
         // str(batch%shard_count) // ': ' // str(n_total) // ' points, ' &
         // str(n_done) // ' already in the checkpoint; ' // str(threads) // ' threads'

      first = 1
      call meter%start('sweep', 'points', real(n_total, dp), real(n_done, dp), &
         deck%sweep%progress .and. .not. batch%quiet, batch%progress_interval_s)
      do while (first <= size(todo))
         last = min(size(todo), first + chunk - 1)
         if (deck%sweep%mode == 'continuation') then
            ! rounds of `block` positions along every line of the chunk: about 8 points per
            ! thread per round, so that the barrier at the end of a round costs little
            n_pos = size(item_points(deck%sweep, todo(first)))
            block = max(1, (8 * threads + (last - first)) / (last - first + 1))
            do j1 = 1, n_pos, block
               if (size(vars) > 0) then
                  call run_items(base, deck%sweep, deck%solver, deck%output, &
                     deck%diagnostics, todo(first:last), u0, v0, results, j1, &
                     j1 + block - 1, deck, vars)
               else
                  call run_items(base, deck%sweep, deck%solver, deck%output, &
                     deck%diagnostics, todo(first:last), u0, v0, results, j1, j1 + block - 1)
               end if
               call finish_points(deck%sweep, todo(first:last), j1, j1 + block - 1, results, &
                                  deck%sweep%checkpoint, ck, done, n_done, err)
               if (allocated(err)) return
               call meter%update(real(n_done, dp))
            end do
         else
            if (size(vars) > 0) then
               call run_items(base, deck%sweep, deck%solver, deck%output, deck%diagnostics, &
                              todo(first:last), u0, v0, results, deck=deck, vars=vars)
            else
               call run_items(base, deck%sweep, deck%solver, deck%output, deck%diagnostics, &
                              todo(first:last), u0, v0, results)
            end if
            call finish_points(deck%sweep, todo(first:last), 1, 1, results, &
                               deck%sweep%checkpoint, ck, done, n_done, err)
            if (allocated(err)) return
            call meter%update(real(n_done, dp))
         end if
         first = last + 1
         call system_clock(c1)
         elapsed = real(c1 - c0, dp) / real(rate, dp)
         if (batch%time_limit_s > 0.0_dp .and. elapsed >= batch%time_limit_s .and. &
             first <= size(todo)) then
            call meter%finish(real(n_done, dp))
            call checkpoint_close(ck, delete=.false.)
            write(output_unit, '(a)') 'sweep: time limit reached after ' // str(n_done) // '/' &
               // str(n_total) // ' points; the checkpoint ' // prefix // '.checkpoint keeps ' &
               // 'them: run the same command again to finish'
            return
         end if
      end do
      call meter%finish()

      n_failed = 0
      do k = 1, size(mine)
         pts = item_points(deck%sweep, mine(k))
         do j = 1, size(pts)
            if (results(pts(j))%status /= 0) then
               n_failed = n_failed + 1
               write(error_unit, '(a)') 'sweep: point ' // str(pts(j)) // ' failed: ' &
                  // results(pts(j))%message
            end if
         end do
      end do
      sf%deck_text = deck%text
      sf%title = trim(deck%job%title)
      sf%grid_frequency_hz = deck%sweep%frequency_hz
      sf%grid_amplitude_pp = deck%sweep%amplitude_pp
      sf%axis_variable = axis_words(vars)
      sf%axis_units = 'm'
      if (size(vars) > 0) sf%axis_units = trim(vars(1)%units)
      if (sf%axis_units == '-') sf%axis_units = '1'
      sf%shard_index = batch%shard_index
      sf%shard_count = batch%shard_count
      sf%points = sorted_points(deck%sweep, mine)
      sf%parameters = run_parameters(deck, base%stop_stiffness, base%f1_open_hz, &
                                     base%omega_max / (2.0_dp * pi), base%n)
      call write_sweep(prefix, sf, results, deck%output%write_text, err)
      if (allocated(err)) return
      if (deck%sweep%checkpoint) call checkpoint_close(ck, delete=.true.)
      call summary(results(sf%points), n_failed)
      call system_clock(c1)
      write(output_unit, '(a)') 'sweep: ' // str(size(sf%points)) // ' points in ' &
         // str(real(c1 - c0, dp) / real(rate, dp)) // ' s; files: ' // prefix // '.h5' &
         // trim(merge(', .sweep.dat, .bifurcation.dat', '                              ', &
         deck%output%write_text))
      complete = .true.

   end subroutine run_sweep_job

   !> The deck variables that the amplitude axis sets (&sweep variable), parsed and checked on
   !> the deck; none when the axis is the base motion's amplitude_pp. The continuation mode
   !> needs the same model at every point of a line along the frequency axis only.
   subroutine axis_variables(deck, vars, err)
      type(deck_t), intent(in) :: deck                       !! validated deck
      type(deck_variable_t), allocatable, intent(out) :: vars(:)   !! the variables
      type(error_t), allocatable, intent(out) :: err         !! unknown or absent variable
      integer :: k
      allocate(vars(0))
      do k = 1, size(deck%sweep%variable)
         if (len_trim(deck%sweep%variable(k)) == 0) cycle
         vars = [vars, deck_variable_t()]
         call parse_deck_variable(deck%sweep%variable(k), vars(size(vars)), err)
         if (.not. allocated(err)) call check_deck_variable(deck, vars(size(vars)), err)
         if (allocated(err)) then
            err%message = 'group &sweep: variable(' // str(k) // '): ' // err%message
            return
         end if
      end do
      if (size(vars) == 1) then
         ! the base motion's own amplitude: the fast path, no rebuild
         if (vars(1)%group == 'forcing' .and. vars(1)%name == 'amplitude_pp') deallocate(vars)
         if (.not. allocated(vars)) allocate(vars(0))
      end if
      if (size(vars) > 0 .and. any(vars%group == 'forcing')) call fatal_error(err, &
         "group &sweep: variable: the &forcing variables are the sweep's own axes " &
         // "(frequency_hz, amplitude_pp); name other deck variables")
   end subroutine axis_variables

   !> 'amplitudes', or the variables the amplitude axis sets.
   function axis_words(vars) result(t)
      type(deck_variable_t), intent(in) :: vars(:)
      character(len=:), allocatable :: t
      integer :: k
      if (size(vars) == 0) then
         t = 'amplitudes'
         return
      end if
      t = 'values of'
      do k = 1, size(vars)
         if (k > 1) t = t // ','
         t = t // ' ' // deck_variable_label(vars(k))
      end do
   end function axis_words

   !> Positions j_first..j_last of the lines (points) of `items` are done: mark them, count
   !> them and append each successful one to the checkpoint (when there is one).
   subroutine finish_points(sw, items, j_first, j_last, results, with_checkpoint, ck, done, &
                            n_done, err)
      type(sweep_settings_t), intent(in) :: sw           !! sweep
      integer, intent(in) :: items(:)                    !! work items just run
      integer, intent(in) :: j_first, j_last             !! positions along each item
      type(point_result_t), intent(in) :: results(:)     !! results, by point
      logical, intent(in) :: with_checkpoint             !! append to `ck`
      type(checkpoint_t), intent(inout) :: ck            !! the checkpoint
      logical, intent(inout) :: done(:)                  !! points done, by point
      integer, intent(inout) :: n_done                   !! count of points done
      type(error_t), allocatable, intent(out) :: err     !! checkpoint write failure
      integer :: k, j
      integer, allocatable :: line(:)
      do k = 1, size(items)
         line = item_points(sw, items(k))
         do j = j_first, min(j_last, size(line))
            done(line(j)) = .true.
            n_done = n_done + 1
            if (with_checkpoint .and. results(line(j))%status == 0) then
               call checkpoint_append(ck, line(j), results(line(j)), err)
               if (allocated(err)) return
            end if
         end do
      end do
   end subroutine finish_points

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
   function sorted_points(sw, items) result(pts)
      type(sweep_settings_t), intent(in) :: sw
      integer, intent(in) :: items(:)
      integer, allocatable :: pts(:)
      logical, allocatable :: mask(:)
      integer :: k
      allocate(mask(n_points(sw)), source=.false.)
      do k = 1, size(items)
         mask(item_points(sw, items(k))) = .true.
      end do
      pts = pack([(k, k = 1, size(mask))], mask)
   end function sorted_points

   subroutine summary(res, n_failed)
      type(point_result_t), intent(in) :: res(:)
      integer, intent(in) :: n_failed
      integer :: p, c
      character(len=:), allocatable :: line
      line = 'labels:'
      do p = 1, maxval([0, res%label])
         c = count(res%label == p)
         if (c > 0) line = line // ' period ' // str(p) // ': ' // str(c) // ';'
      end do
      line = line // ' chaotic: ' // str(count(res%label == label_chaotic)) // '; undecided: ' &
         // str(count(res%label == label_undecided .and. res%status == 0)) // '; failed: ' &
         // str(n_failed)
      write(output_unit, '(a)') line
   end subroutine summary
end module gapbeam_sweep_job
