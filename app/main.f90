!> gapbeam: finite element simulation of vibro-impact and chaotic vibration of beams with gap
!> supports. Usage: gapbeam DECK [OVERRIDE ...], each OVERRIDE a namelist fragment applied
!> after the deck file, e.g. gapbeam inputs/x.nml "&forcing frequency_hz=10.2 /".
!>
!> Exit status: 0 done; 1 error (one line `error: ...` on standard error); 2 usage; 3 a sweep
!> stopped by --time-limit (its checkpoint kept); 4 the output prefix is locked by another run;
!> 5 a sweep (or merge) wrote all its files but some of its points failed (each listed on
!> standard error, marked in the files).
!> No backtrace is printed unless GAPBEAM_BACKTRACE=1 is set in the environment.
program main
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str, printable
   use gapbeam_deck, only: deck_t, add_warning
   use gapbeam_warnings, only: deck_warnings
   use gapbeam_warning_text, only: warning_length, warning_prefix
   use gapbeam_settings, only: batch_options_t
   use gapbeam_input, only: read_deck
   use gapbeam_files, only: make_parent_directory, output_name_problem
   use gapbeam_deck_rules, only: output_prefix_problem
   use gapbeam_output_catalogue, only: catalogue_text, section_names, section_analyses
   use gapbeam_lock, only: lock_t, acquire_lock, release_lock
   use gapbeam_jobs, only: run_modes, run_calibrate, run_transient_analysis, run_work_precision, &
      run_stability, run_model_size
   use gapbeam_sweep_job, only: run_sweep_job, sweep_prefix, status_interrupted, &
      status_failed_points
   use gapbeam_sweep_output, only: merge_sweep
   use gapbeam_blas_threads, only: serial_blas
   use gapbeam_usage, only: usage_lines, help_text, version_text
   use gapbeam_deck_help, only: deck_help
   use gapbeam_continuation_job, only: run_continuation_job   ! issue 14
   use gapbeam_stop_signal, only: catch_stop_signal, ignore_file_size_signal
   implicit none
   integer, parameter :: status_error = 1, status_usage = 2, status_locked = 4
   type(deck_t) :: deck
   type(error_t), allocatable :: err
   type(lock_t) :: lock
   character(len=:), allocatable :: path, arg, prefix
   character(len=:), allocatable :: overrides(:)
   type(batch_options_t) :: batch
   integer :: i, n_args, n_over, n_failed
   logical :: complete, options_done
   character(len=:), allocatable :: value, name

   if (serial_blas()) continue     ! results must not depend on BLAS threads
   call ignore_file_size_signal()  ! past `ulimit -f` a write fails (and is reported), no kill
   n_args = command_argument_count()
   if (n_args < 1) then
      write(error_unit, '(a)') usage_lines()
      write(error_unit, '(a)') '  OVERRIDE: a namelist fragment, e.g. ' &
         // '"&forcing frequency_hz=10.2 /"; gapbeam --help tells more'
      call finish(status_usage)
   end if
   path = argument(1)
   select case (path)
   case ('--help', '-h', '-help')
      write(output_unit, '(a)') help_text()
      call finish(0)
   case ('--version', '-V')
      write(output_unit, '(a)') version_text()
      call finish(0)
   case ('--help-deck')
      call help_deck(n_args)
   case ('--help-outputs')
      call help_outputs()
   end select
   if (path(1:min(1, len(path))) == '-') call usage_error("unknown option '" // path &
      // "' (a deck file name comes first)")
   ! overrides (or merge files) of any length: one array as long as the longest
   i = longest_argument()
   allocate(character(len=i) :: overrides(n_args))
   n_over = 0
   i = 1
   options_done = .false.
   do while (i < n_args)
      i = i + 1
      arg = argument(i)
      if (options_done .or. arg(1:min(1, len(arg))) /= '-' .or. arg == '-') then
         n_over = n_over + 1;  overrides(n_over) = arg
         cycle
      end if
      name = arg
      if (index(arg, '=') > 0) name = arg(1:index(arg, '=') - 1)
      select case (name)
      case ('--')
         options_done = .true.                 ! the rest are overrides (or merge files)
      case ('--quiet', '-q')
         if (name /= arg) call usage_error("'" // arg // "': " // name // ' takes no value')
         batch%quiet = .true.
      case ('--progress', '--shard', '--time-limit', '--shard-costs')
         if (name == arg) then                 ! 'NAME VALUE'
            if (i >= n_args) call usage_error(name // ' needs ' // value_wanted(name))
            i = i + 1
            value = argument(i)
         else                                  ! 'NAME=VALUE'
            value = arg(len(name) + 2:)
         end if
         if (path == 'merge' .and. name /= '--progress') call usage_error("'" // name &
            // "' applies to a sweep run, not to merge")
         call set_option(path, name, value, batch, lock)
      case default
         if (path == 'merge') call usage_error("unknown option '" // arg // "' (a file " &
            // "name starting with '-': put '--' before it)")
         if (index(arg, '--') == 1) call usage_error("unknown option '" // arg // "'")
         n_over = n_over + 1;  overrides(n_over) = arg
      end select
   end do
   if (path == 'merge') then
      call run_merge(overrides(1:n_over), lock)
      call finish(0)
   end if

   call read_deck(path, overrides(1:n_over), deck, err)
   if (allocated(err)) call fail(path, err%message, lock)
   if (len(output_prefix_problem(deck%job%output)) > 0) call fail(path, 'group &job: output ' &
      // "= '" // trim(deck%job%output) // "': " // output_prefix_problem(deck%job%output), lock)
   if ((batch%shard_count > 1 .or. batch%time_limit_s > 0.0_dp .or. &
        allocated(batch%shard_costs)) .and. deck%job%analysis /= 'sweep') &
      call fail(path, path // ": --shard, --time-limit and --shard-costs apply to " &
      // "analysis='sweep' only (this deck runs '" // trim(deck%job%analysis) // "')", lock)

   ! one writer per output prefix: the lock is taken before anything is computed
   if (deck%job%analysis == 'sweep') then
      prefix = sweep_prefix(deck, batch)
   else
      prefix = trim(deck%job%output)
   end if
   if (len(output_name_problem(prefix)) > 0) call fail(path, "group &job: output = '" &
      // trim(deck%job%output) // "': " // output_name_problem(prefix), lock)
   call take_lock(path, prefix, lock)
   ! SIGTERM (a batch job's time limit, preemption, scancel) stops a sweep that keeps a
   ! checkpoint as its time limit does; any other run it ends at once, as by default
   if (deck%job%analysis == 'sweep' .and. deck%sweep%checkpoint) call catch_stop_signal()

   write(output_unit, '(a)') 'gapbeam: ' // printable(trim(deck%job%title))
   write(output_unit, '(a)') 'analysis: ' // trim(deck%job%analysis)
   call warn_about_deck(deck)
   select case (deck%job%analysis)
   case ('modes')
      call run_modes(deck, err)
   case ('calibrate')
      call run_calibrate(deck, err)
   case ('transient')
      call run_transient_analysis(deck, err, batch)
   case ('work_precision')
      call run_work_precision(deck, err)
   case ('stability')
      call run_stability(deck, err)
   case ('model_size')
      call run_model_size(deck, err)
   case ('continuation')                                     ! issue 14
      call run_continuation_job(deck, err)
   case ('sweep')
      call run_sweep_job(deck, batch, complete, n_failed, err)
      if (allocated(err)) call fail(path, err%message, lock)
      write(output_unit, '(a)') 'output: ' // prefix
      call release_lock(lock)
      if (.not. complete) call finish(status_interrupted)
      if (n_failed > 0) call finish(status_failed_points)
      call finish(0)
   end select
   if (allocated(err)) call fail(path, err%message, lock)
   write(output_unit, '(a)') 'output: ' // prefix
   call release_lock(lock)
   call finish(0)

contains

   !> The deck's warnings (gapbeam_warnings): kept in the deck for the files' /run/warnings and
   !> printed on standard error, one line each.
   subroutine warn_about_deck(dk)
      type(deck_t), intent(inout) :: dk            !! validated deck
      character(len=warning_length), allocatable :: lines(:)
      integer :: k
      lines = deck_warnings(dk)
      do k = 1, size(lines)
         call add_warning(dk, trim(lines(k)))
         write(error_unit, '(a)') warning_prefix // printable(trim(lines(k)))
      end do
      flush(error_unit)
   end subroutine warn_about_deck

   !> gapbeam --help-outputs [ANALYSIS | SECTION | tsv]: the output catalogue on standard output.
   subroutine help_outputs()
      character(len=:), allocatable :: which
      which = ''
      if (n_args > 1) which = argument(2)
      if (which == 'tsv') then
         write(output_unit, '(a)', advance='no') catalogue_text('tsv')
      else if (which /= '' .and. .not. any(section_names == which) .and. &
               index(' ' // section_analyses(1) // ' ', ' ' // which // ' ') == 0) then
         call usage_error("--help-outputs '" // which // "': expected an analysis, a section " &
            // '(' // trim(join_words(section_names)) // ') or tsv')
      else
         write(output_unit, '(a)', advance='no') catalogue_text('markdown', which)
      end if
      call finish(0)
   end subroutine help_outputs

   !> Words joined by ', '.
   function join_words(words) result(t)
      character(len=*), intent(in) :: words(:)     !! words
      character(len=:), allocatable :: t
      integer :: k
      t = trim(words(1))
      do k = 2, size(words)
         t = t // ', ' // trim(words(k))
      end do
   end function join_words

   !> Command-line argument k, whole.
   function argument(k) result(a)
      integer, intent(in) :: k                     !! argument number
      character(len=:), allocatable :: a
      integer :: l
      call get_command_argument(k, length=l)
      allocate(character(len=l) :: a)
      if (l > 0) call get_command_argument(k, a)
   end function argument

   !> Length of the longest command-line argument (at least 1).
   integer function longest_argument()
      integer :: k, l
      longest_argument = 1
      do k = 1, command_argument_count()
         call get_command_argument(k, length=l)
         longest_argument = max(longest_argument, l)
      end do
   end function longest_argument

   !> A bad command line: the message and the usage on standard error, exit status 2.
   subroutine usage_error(message)
      character(len=*), intent(in) :: message      !! what is wrong
      write(error_unit, '(a)') 'error: ' // printable(message)
      write(error_unit, '(a)') usage_lines()
      call finish(status_usage)
   end subroutine usage_error

   !> Read '--shard I/N': two whole numbers, 1 <= I <= N, and nothing else.
   subroutine parse_shard(deck_path, text, si, sc, held)
      character(len=*), intent(in) :: deck_path    !! deck path, for messages
      character(len=*), intent(in) :: text         !! 'I/N'
      integer, intent(out) :: si, sc               !! shard index and count
      type(lock_t), intent(inout) :: held          !! lock (none held yet)
      integer :: slash
      logical :: ok
      slash = index(text, '/')
      ok = slash > 1
      if (ok) ok = whole_number(text(1:slash - 1), si) .and. whole_number(text(slash + 1:), sc)
      if (.not. ok) call fail(deck_path, "--shard '" // text // "': expected " &
         // 'I/N with whole numbers, e.g. --shard 3/16', held)
      if (sc < 1 .or. si < 1 .or. si > sc) call fail(deck_path, "--shard '" // text // "': " &
         // 'need 1 <= I <= N', held)
   end subroutine parse_shard

   !> Set the option `name` (one that takes a value) from `value`, checked strictly: the whole
   !> value must be what the option expects.
   subroutine set_option(deck_path, name, value, opts, held)
      character(len=*), intent(in) :: deck_path    !! deck path, for messages
      character(len=*), intent(in) :: name         !! the option, e.g. '--shard'
      character(len=*), intent(in) :: value        !! its value
      type(batch_options_t), intent(inout) :: opts !! the options
      type(lock_t), intent(inout) :: held          !! lock (none held yet)
      select case (name)
      case ('--progress')
         if (.not. seconds_value(value, opts%progress_interval_s)) call fail(deck_path, &
            "--progress '" // value // "': expected a number of seconds between progress " &
            // 'lines, > 0', held)
      case ('--shard')
         call parse_shard(deck_path, value, opts%shard_index, opts%shard_count, held)
      case ('--time-limit')
         if (.not. seconds_value(value, opts%time_limit_s)) call fail(deck_path, &
            "--time-limit '" // value // "': expected a positive number of seconds", held)
      case ('--shard-costs')
         if (len(value) == 0) call fail(deck_path, '--shard-costs needs a result file of an ' &
            // 'earlier sweep of the same grid, e.g. --shard-costs results/pilot.h5', held)
         opts%shard_costs = value
      end select
   end subroutine set_option

   !> What option `name` takes, for messages.
   function value_wanted(name) result(t)
      character(len=*), intent(in) :: name         !! the option
      character(len=:), allocatable :: t
      select case (name)
      case ('--shard')
         t = 'I/N, e.g. --shard 3/16'
      case ('--shard-costs')
         t = 'a result file of an earlier sweep of the same grid'
      case default
         t = 'a number of seconds'
      end select
   end function value_wanted

   !> Whether `text` is a whole number written with digits only (at most 9 of them); its value.
   logical function whole_number(text, n)
      character(len=*), intent(in) :: text         !! e.g. '16'
      integer, intent(out) :: n                    !! its value
      integer :: k
      n = 0
      whole_number = len(text) >= 1 .and. len(text) <= 9 .and. verify(text, '0123456789') == 0
      if (.not. whole_number) return
      do k = 1, len(text)
         n = 10 * n + (iachar(text(k:k)) - iachar('0'))
      end do
   end function whole_number

   !> Whether `text` is a number of seconds, > 0 and < 1e9, written as digits with an optional
   !> fraction and exponent ('30', '2.5', '1e3') and nothing else; its value.
   logical function seconds_value(text, x)
      character(len=*), intent(in) :: text         !! e.g. '6900'
      real(dp), intent(inout) :: x                 !! its value (unchanged when not a number)
      integer :: k, n_mantissa, ios
      real(dp) :: v
      seconds_value = .false.
      k = 1
      n_mantissa = digits_at(text, k)
      if (k <= len(text)) then
         if (text(k:k) == '.') then
            k = k + 1
            n_mantissa = n_mantissa + digits_at(text, k)
         end if
      end if
      if (n_mantissa == 0) return
      if (k <= len(text)) then
         if (scan(text(k:k), 'eEdD') == 1) then
            k = k + 1
            if (k <= len(text)) then
               if (scan(text(k:k), '+-') == 1) k = k + 1
            end if
            if (digits_at(text, k) == 0) return
         end if
      end if
      if (k <= len(text)) return                   ! something after the number
      read(text, *, iostat=ios) v
      if (ios /= 0 .or. .not. (v > 0.0_dp .and. v < 1.0e9_dp)) return
      x = v
      seconds_value = .true.
   end function seconds_value

   !> The number of decimal digits in `text` from position k on; k moves past them.
   integer function digits_at(text, k)
      character(len=*), intent(in) :: text         !! text
      integer, intent(inout) :: k                  !! position
      digits_at = 0
      do while (k <= len(text))
         if (verify(text(k:k), '0123456789') /= 0) exit
         k = k + 1
         digits_at = digits_at + 1
      end do
   end function digits_at

   !> Take the lock of the output prefix (creating its directory); exit with status 4 when
   !> another run holds it, with status 1 when the lock cannot be taken for another reason.
   subroutine take_lock(deck_path, out_prefix, held)
      character(len=*), intent(in) :: deck_path    !! deck path, for messages
      character(len=*), intent(in) :: out_prefix   !! output prefix
      type(lock_t), intent(inout) :: held          !! the lock, held on return
      type(error_t), allocatable :: e
      call make_parent_directory(out_prefix, e)
      if (allocated(e)) call fail(deck_path, e%message, held)
      call acquire_lock(held, out_prefix, e)
      if (allocated(e)) then
         if (held%busy) call fail(deck_path, e%message, held, status_locked)
         call fail(deck_path, e%message, held)
      end if
      if (allocated(held%note)) then
         write(error_unit, '(a)') 'gapbeam: note: ' // printable(held%note)
         flush(error_unit)
      end if
   end subroutine take_lock

   !> gapbeam merge OUT.h5 SHARD.h5 ...
   subroutine run_merge(args, held)
      character(len=*), intent(in) :: args(:)      !! OUT.h5, then the shard files
      type(lock_t), intent(inout) :: held          !! lock of OUT, taken here
      character(len=:), allocatable :: out
      type(error_t), allocatable :: e
      integer :: k, n_failed
      if (size(args) < 2) then
         write(error_unit, '(a)') 'usage: gapbeam merge OUT.h5 SHARD.h5 ...'
         call finish(status_usage)
      end if
      out = trim(args(1))
      k = len(out)
      if (k > 3) then
         if (out(k - 2:) == '.h5') out = out(1:k - 3)
      end if
      if (len(output_prefix_problem(out)) > 0) call fail('merge', 'gapbeam merge: ' &
         // output_prefix_problem(out), held)
      call take_lock('merge', out, held)
      call merge_sweep(out, args(2:), .true., e, n_failed)
      if (allocated(e)) then
         if (index(e%message, 'gapbeam merge: ') /= 1) e%message = 'gapbeam merge: ' // e%message
         call fail('merge', e%message, held)
      end if
      call release_lock(held)
      write(output_unit, '(a)') 'merged ' // str(size(args) - 1) // ' shard files into ' &
         // out // '.h5'
      if (n_failed > 0) then
         write(output_unit, '(a)') 'merge: ' // str(n_failed) // ' failed run(s) in the shards ' &
            // "(status 1, label 'failed' in the files)"
         flush(output_unit)
         write(error_unit, '(a)') 'gapbeam merge: ' // str(n_failed) // ' failed run(s) in ' &
            // 'the shards: marked in ' // out // ".h5 (/sweep/status 1, label 'failed'); " &
            // 'the sweeps that ran them listed why on their standard error'
         call finish(status_failed_points)
      end if
   end subroutine run_merge

   !> Write one error line, give the lock back, and end with `status` (default 1). The deck
   !> path starts the line unless the message starts with it already.
   subroutine fail(deck_path, message, held, status)
      character(len=*), intent(in) :: deck_path    !! deck path as given ('merge' for merge)
      character(len=*), intent(in) :: message      !! what went wrong
      type(lock_t), intent(inout) :: held          !! lock, released here
      integer, intent(in), optional :: status      !! exit status (1 when absent)
      character(len=:), allocatable :: line
      line = message
      if (deck_path /= 'merge' .and. len(deck_path) > 0) then
         if (index(message, deck_path // ': ') /= 1) line = deck_path // ': ' // message
      end if
      flush(output_unit)
      write(error_unit, '(a)') 'error: ' // printable(one_line(line))
      call release_lock(held)
      if (present(status)) call finish(status)
      call finish(status_error)
   end subroutine fail

   !> `gapbeam --help-deck [GROUP] [--markdown]`: the deck variables (docs/decks.md's tables).
   subroutine help_deck(n)
      integer, intent(in) :: n                     !! number of arguments
      character(len=:), allocatable :: text, group
      type(error_t), allocatable :: e
      logical :: markdown
      integer :: k
      group = '';  markdown = .false.
      do k = 2, n
         if (argument(k) == '--markdown') then
            markdown = .true.
         else if (len(group) == 0) then
            group = argument(k)
         else
            call usage_error("--help-deck takes one group, got '" // argument(k) // "' too")
         end if
      end do
      call deck_help(group, markdown, text, e)
      if (allocated(e)) call usage_error(e%message)
      write(output_unit, '(a)') text
      call finish(0)
   end subroutine help_deck

   !> `text` on one line: line feeds and carriage returns become blanks (other control
   !> characters are escaped by `printable`).
   function one_line(text) result(s)
      character(len=*), intent(in) :: text         !! message
      character(len=len(text)) :: s
      integer :: k
      s = text
      do k = 1, len(s)
         if (s(k:k) == achar(10) .or. s(k:k) == achar(13)) s(k:k) = ' '
      end do
   end function one_line

   !> End the program with `status`, printing nothing more: STOP with QUIET (ERROR STOP would
   !> print a backtrace and gfortran's summary of floating-point exceptions). With
   !> GAPBEAM_BACKTRACE=1 a non-zero status ends with ERROR STOP instead, for debugging.
   subroutine finish(status)
      integer, intent(in) :: status                !! exit status
      character(len=8) :: value
      integer :: l, st
      flush(output_unit)
      flush(error_unit)
      if (status /= 0) then
         call get_environment_variable('GAPBEAM_BACKTRACE', value, l, st)
         if (st == 0 .and. trim(value) == '1') error stop status
      end if
      stop status, quiet=.true.
   end subroutine finish

end program main
