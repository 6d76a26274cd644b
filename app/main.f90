!> gapbeam: finite element simulation of vibro-impact and chaotic vibration of beams with gap
!> supports. Usage: gapbeam DECK [OVERRIDE ...], each OVERRIDE a namelist fragment applied
!> after the deck file, e.g. gapbeam inputs/x.nml "&forcing frequency_hz=10.2 /".
program main
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_settings, only: batch_options_t
   use gapbeam_input, only: read_deck
   use gapbeam_jobs, only: run_modes, run_calibrate, run_transient_analysis, run_work_precision, &
      run_stability, run_model_size
   use gapbeam_sweep_job, only: run_sweep_job, sweep_prefix, status_interrupted
   use gapbeam_sweep_output, only: merge_sweep
   use gapbeam_blas_threads, only: serial_blas
   use gapbeam_continuation_job, only: run_continuation_job   ! issue 14
   implicit none
   type(deck_t) :: deck
   type(error_t), allocatable :: err
   character(len=:), allocatable :: path, arg
   character(len=:), allocatable :: overrides(:)
   type(batch_options_t) :: batch
   integer :: i, n_args, ios
   logical :: complete

   if (serial_blas()) continue     ! results must not depend on BLAS threads
   n_args = command_argument_count()
   if (n_args < 1) then
      write(error_unit, '(a)') 'usage: gapbeam DECK [--shard I/N] [--time-limit S] [OVERRIDE ...]'
      write(error_unit, '(a)') '       gapbeam merge OUT.h5 SHARD.h5 ...'
      write(error_unit, '(a)') '  OVERRIDE: a namelist fragment, e.g. ' &
         // '"&forcing frequency_hz=10.2 /"'
      error stop 2
   end if
   allocate(character(len=4096) :: overrides(0))
   i = 0
   do while (i < n_args)
      i = i + 1
      arg = argument(i)
      if (i == 1) then
         path = arg
      else if (path == 'merge') then
         overrides = [character(len=4096) :: overrides, arg]
      else if (arg == '--shard' .or. index(arg, '--shard=') == 1) then
         if (arg == '--shard') then
            i = i + 1
            if (i > n_args) call fail_text('--shard needs I/N, e.g. --shard 3/16')
            arg = argument(i)
         else
            arg = arg(9:)
         end if
         call parse_shard(arg, batch%shard_index, batch%shard_count)
      else if (arg == '--time-limit' .or. index(arg, '--time-limit=') == 1) then
         if (arg == '--time-limit') then
            i = i + 1
            if (i > n_args) call fail_text('--time-limit needs a number of seconds')
            arg = argument(i)
         else
            arg = arg(14:)
         end if
         read(arg, *, iostat=ios) batch%time_limit_s
         if (ios /= 0 .or. .not. (batch%time_limit_s > 0.0_dp)) call fail_text("--time-limit '" &
            // arg // "': expected a positive number of seconds")
      else
         overrides = [character(len=4096) :: overrides, arg]
      end if
   end do
   if (path == 'merge') then
      call run_merge(overrides)
      stop
   end if

   call read_deck(path, overrides, deck, err)
   if (allocated(err)) call fail(err)
   if ((batch%shard_count > 1 .or. batch%time_limit_s > 0.0_dp) .and. &
       deck%job%analysis /= 'sweep') &
      call fail_text(path // ": --shard and --time-limit apply to analysis='sweep' only " &
      // "(this deck runs '" // trim(deck%job%analysis) // "')")
   write(output_unit, '(a)') 'gapbeam: ' // trim(deck%job%title)
   write(output_unit, '(a)') 'analysis: ' // trim(deck%job%analysis)
   select case (deck%job%analysis)
   case ('modes')
      call run_modes(deck, err)
   case ('calibrate')
      call run_calibrate(deck, err)
   case ('transient')
      call run_transient_analysis(deck, err)
   case ('work_precision')
      call run_work_precision(deck, err)
   case ('stability')
      call run_stability(deck, err)
   case ('model_size')
      call run_model_size(deck, err)
   case ('continuation')                                     ! issue 14
      call run_continuation_job(deck, err)
   case ('sweep')
      call run_sweep_job(deck, batch, complete, err)
      if (allocated(err)) call fail(err)
      write(output_unit, '(a)') 'output: ' // sweep_prefix(deck, batch)
      if (.not. complete) error stop status_interrupted
      stop
   end select
   if (allocated(err)) call fail(err)
   write(output_unit, '(a)') 'output: ' // trim(deck%job%output)

contains

   function argument(k) result(a)
      integer, intent(in) :: k
      character(len=:), allocatable :: a
      integer :: l
      call get_command_argument(k, length=l)
      allocate(character(len=l) :: a)
      call get_command_argument(k, a)
   end function argument

   subroutine parse_shard(text, si, sc)
      character(len=*), intent(in) :: text
      integer, intent(out) :: si, sc
      integer :: slash, ios1, ios2
      slash = index(text, '/')
      ios1 = 1;  ios2 = 1
      if (slash > 1) then
         read(text(1:slash - 1), *, iostat=ios1) si
         read(text(slash + 1:), *, iostat=ios2) sc
      end if
      if (ios1 /= 0 .or. ios2 /= 0) call fail_text("--shard '" // text // "': expected I/N " &
         // 'with whole numbers, e.g. --shard 3/16')
      if (sc < 1 .or. si < 1 .or. si > sc) call fail_text("--shard '" // text // "': need " &
         // '1 <= I <= N')
   end subroutine parse_shard

   subroutine run_merge(args)
      character(len=*), intent(in) :: args(:)
      character(len=:), allocatable :: out
      integer :: k
      if (size(args) < 2) call fail_text('usage: gapbeam merge OUT.h5 SHARD.h5 ...')
      out = trim(args(1))
      k = len(out)
      if (k > 3) then
         if (out(k - 2:) == '.h5') out = out(1:k - 3)
      end if
      call merge_sweep(out, args(2:), .true., err)
      if (allocated(err)) call fail(err)
      write(output_unit, '(a)') 'merged ' // str(size(args) - 1) // ' shard files into ' &
         // out // '.h5'
   end subroutine run_merge

   subroutine fail_text(text)
      character(len=*), intent(in) :: text
      if (allocated(path)) then
         if (path /= 'merge' .and. index(text, path // ': ') /= 1) then
            write(error_unit, '(a)') 'error: ' // path // ': ' // text
            flush(error_unit)
            error stop 1
         end if
      end if
      write(error_unit, '(a)') 'error: ' // text
      flush(error_unit)
      error stop 1
   end subroutine fail_text

   subroutine fail(e)
      type(error_t), intent(in) :: e
      if (allocated(path)) then
         if (index(e%message, path // ': ') /= 1 .and. path /= 'merge') then
            write(error_unit, '(a)') 'error: ' // path // ': ' // e%message
            flush(error_unit)
            error stop 1
         end if
      end if
      write(error_unit, '(a)') 'error: ' // e%message
      flush(error_unit)
      error stop 1
   end subroutine fail

end program main
