!> The exponent from independent starts (&diagnostics lyapunov_starts) and the exponent pair's
!> rerun and dropped periods in the result file:
!> - the combination of starts against a hand computation;
!> - the chaotic 9.8 Hz deck at two record lengths, each from 1 and from 4 starts, agreeing
!>   within their stated errors with each other and with one long run of 8 starts, which
!>   agrees with the exponent of two runs of 100000 periods (2.95 +- 0.03 1/s, release build:
!>   2.936 +- 0.061 and 2.953 +- 0.029 after 300 and 5300 transient periods);
!> - a stable orbit runs one start whatever the starts asked: the same one, bit for bit;
!> - the rerun and dropped periods of a ring support's pair: counted, plausible (dropped <=
!>   rerun <= periods run), zero without rings, and written to /diagnostics.
program test_exponent_starts
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_results, only: lyapunov_t, point_result_t, transient_result_t, label_chaotic, &
      label_text
   use gapbeam_attractor, only: combine_starts, diagnose
   use gapbeam_report, only: write_transient
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_test_runs, only: diagnose_or_stop, load_or_stop, expect_refused
   use gapbeam_testing, only: check, check_le, finish, note
   implicit none
   character(len=*), parameter :: chaos = 'inputs/moon_shaw_9p8hz.nml'
   character(len=*), parameter :: stable = 'test/decks/tube_planar.nml'
   character(len=*), parameter :: ring = 'test/decks/stick_ring.nml'
   character(len=*), parameter :: quiet = '&diagnostics certify = .false. /'

   call starts_combine_as_computed_by_hand()
   call record_lengths_and_starts_agree()
   call stable_orbit_runs_one_start()
   call rerun_periods_are_written()
   call bad_starts_are_refused()
   call finish('test_exponent_starts')

contains

   !> One start of n periods with a constant running estimate lambda and error sigma.
   function part(n, lambda, sigma) result(p)
      integer, intent(in) :: n
      real(dp), intent(in) :: lambda, sigma
      type(lyapunov_t) :: p
      p%periods = n;  p%exponent = lambda;  p%uncertainty = sigma
      allocate(p%running(n), source=lambda)
      allocate(p%section(2, n), source=real(n, dp))
      p%discordant = 1;  p%retried = 2
   end function part

   !> Three starts of 100, 100 and 200 periods at 1, 2 and 3 1/s, each +- 0.1: lambda 2.25
   !> (weighted by periods), sigma from the spread sqrt(275 / 800) (sum n_j (lambda_j -
   !> lambda)^2 / ((K - 1) sum n_j)), larger than the starts' own sqrt(600) / 400; the running
   !> estimate joined (2 at the end of the second start, 2.25 at the end).
   subroutine starts_combine_as_computed_by_hand()
      type(lyapunov_t) :: c
      real(dp), parameter :: period = 0.5_dp
      call combine_starts([part(100, 1.0_dp, 0.1_dp), part(100, 2.0_dp, 0.1_dp), &
                           part(200, 3.0_dp, 0.1_dp)], period, c)
      call check_le('combined lambda = 2.25', abs(c%exponent - 2.25_dp), 1.0e-12_dp)
      call check_le('spread sigma = sqrt(275 / 800)', abs(c%spread - sqrt(275.0_dp / 800.0_dp)), &
                    1.0e-12_dp)
      call check_le('sigma = the larger (the spread)', abs(c%uncertainty - c%spread), 1.0e-12_dp)
      call check('3 starts of 400 periods, 3 dropped and 6 rerun in all', c%starts == 3 .and. &
                 c%periods == 400 .and. c%discordant == 3 .and. c%retried == 6)
      call check('running estimate and sections joined', size(c%running) == 400 .and. &
                 size(c%section, 2) == 400 .and. abs(c%running(200) - 1.5_dp) < 1.0e-12_dp &
                 .and. abs(c%running(400) - 2.25_dp) < 1.0e-12_dp .and. &
                 c%section(1, 250) == 200.0_dp)
      ! agreeing starts: the starts' own errors, sqrt(sum (n_j sigma_j)^2) / sum n_j
      call combine_starts([part(100, 2.0_dp, 0.3_dp), part(300, 2.0_dp, 0.1_dp)], period, c)
      call check_le('agreeing starts: sigma from their own errors', &
                    abs(c%uncertainty - sqrt(30.0_dp**2 + 30.0_dp**2) / 400.0_dp), 1.0e-12_dp)
   end subroutine starts_combine_as_computed_by_hand

   !> The 9.8 Hz deck's exponent at record lengths 200 and 600 (where the exponent starts
   !> moves), from 1 and from 4 starts, and from 8 starts of up to 2000 periods each: every
   !> pair within 3 combined sigma, the long run within 3 combined sigma of 2.95 +- 0.03.
   subroutine record_lengths_and_starts_agree()
      character(len=70), parameter :: lengths(2) = [character(len=70) :: &
         '&solver record_periods = 200 /', '&solver record_periods = 600 /']
      type(point_result_t) :: p(5)
      real(dp) :: worst, z
      integer :: i, j, k
      k = 0
      do i = 1, 2
         do j = 1, 2
            k = k + 1
            call diagnose_or_stop('test_exponent_starts', chaos, [character(len=70) :: quiet, &
               lengths(i), '&diagnostics lyapunov_starts = ' // str(merge(1, 4, j == 1)) &
               // ' /'], .false., p(k))
         end do
      end do
      call diagnose_or_stop('test_exponent_starts', chaos, [character(len=100) :: quiet, &
         '&diagnostics lyapunov_starts = 8, lyapunov_max_periods = 16000, ' // &
         'lyapunov_rel_error = 0.01 /'], .false., p(5))
      do k = 1, 5
         call note('9.8 Hz run ' // str(k) // ': ' // label_text(p(k)%label) // ', lambda ' &
            // str(p(k)%lyapunov) // ' +- ' // str(p(k)%lyapunov_error) // ' 1/s over ' &
            // str(p(k)%lyapunov_periods) // ' periods, ' // str(p(k)%lyapunov_starts) &
            // ' starts (spread sigma ' // str(p(k)%lyapunov_spread) // ')')
      end do
      call check('9.8 Hz: every run chaotic', all(p%label == label_chaotic))
      call check('one start: 1 start, no spread', p(1)%lyapunov_starts == 1 .and. &
                 p(3)%lyapunov_starts == 1 .and. p(1)%lyapunov_spread == 0.0_dp)
      call check('4 starts on chaos: 4 starts and a spread', p(2)%lyapunov_starts == 4 .and. &
                 p(4)%lyapunov_starts == 4 .and. p(2)%lyapunov_spread > 0.0_dp .and. &
                 p(4)%lyapunov_spread > 0.0_dp)
      call check('4 starts: sigma at least the spread', &
                 p(2)%lyapunov_error >= p(2)%lyapunov_spread)
      call check('8 starts of 2000 periods (a target they cannot meet): 16000 periods', &
                 p(5)%lyapunov_starts == 8 .and. p(5)%lyapunov_periods == 16000)
      worst = 0.0_dp
      do i = 1, 5
         do j = 1, i - 1
            z = abs(p(i)%lyapunov - p(j)%lyapunov) &
                / sqrt(p(i)%lyapunov_error**2 + p(j)%lyapunov_error**2)
            worst = max(worst, z)
         end do
      end do
      call check_le('9.8 Hz: every pair of runs within 3 combined sigma', worst, 3.0_dp)
      call check_le('the long run: sigma <= 0.15 1/s', p(5)%lyapunov_error, 0.15_dp)
      call check_le('the long run within 3 combined sigma of 100000 periods (2.95 +- 0.03)', &
                    abs(p(5)%lyapunov - 2.95_dp), 3.0_dp * sqrt(p(5)%lyapunov_error**2 &
                    + 0.03_dp**2))
   end subroutine record_lengths_and_starts_agree

   !> The planar tube at 9 Hz settles on a period-1 orbit: with 4 starts asked only one
   !> runs (the orbit is confidently stable after the first start's first periods), and it
   !> is the single start's run, bit for bit.
   subroutine stable_orbit_runs_one_start()
      type(point_result_t) :: one, four
      call diagnose_or_stop('test_exponent_starts', stable, [character(len=60) :: quiet], &
                            .false., one)
      call diagnose_or_stop('test_exponent_starts', stable, [character(len=60) :: quiet, &
                            '&diagnostics lyapunov_starts = 4 /'], .false., four)
      call note('planar tube: ' // label_text(one%label) // ', lambda ' // str(one%lyapunov) &
         // ' +- ' // str(one%lyapunov_error) // ' (1 start), ' // str(four%lyapunov) // ' +- ' &
         // str(four%lyapunov_error) // ' 1/s (4 asked, ' // str(four%lyapunov_starts) // ' run)')
      call check('stable orbit: negative beyond 3 sigma', one%period > 0 .and. &
                 one%lyapunov + 3.0_dp * one%lyapunov_error < 0.0_dp)
      call check('stable orbit: one start run of 4 asked, no spread', &
                 four%lyapunov_starts == 1 .and. four%lyapunov_spread == 0.0_dp)
      call check('stable orbit: 4 asked is 1 start, bit for bit (lambda, sigma, periods)', &
                 four%lyapunov == one%lyapunov .and. &
                 four%lyapunov_error == one%lyapunov_error .and. &
                 four%lyapunov_periods == one%lyapunov_periods)
   end subroutine stable_orbit_runs_one_start

   !> The stuck ring's pair (error control, whole states): rerun and dropped periods counted
   !> with dropped <= rerun <= the pair's periods, and written to /diagnostics as counted;
   !> zero for a model without rings (fixed steps: one step sequence).
   subroutine rerun_periods_are_written()
      type(deck_t) :: deck
      type(model_t) :: model
      type(transient_result_t) :: res
      type(point_result_t) :: pr, plain
      type(error_t), allocatable :: err
      type(h5_reader_t) :: r
      real(dp), allocatable :: u0(:), v0(:)
      character(len=:), allocatable :: prefix
      integer :: rerun, dropped, starts
      prefix = 'test_exponent_starts_ring'
      call load_or_stop('test_exponent_starts', ring, [character(len=80) :: quiet, &
         "&job output = '" // prefix // "' /"], deck, model, u0, v0)
      call diagnose(model, deck%solver, deck%output, deck%diagnostics, u0, v0, res, pr, err)
      if (.not. allocated(err)) call write_transient(deck, model, res, pr, err)
      if (allocated(err)) then
         call check('stuck ring: run and write', .false., err%message)
         return
      end if
      call note('stuck ring: ' // str(pr%lyapunov_rerun) // ' of ' // str(pr%lyapunov_periods) &
         // ' periods rerun, ' // str(pr%lyapunov_dropped) // ' dropped')
      call check('stuck ring: 0 <= dropped <= rerun <= periods', pr%lyapunov_dropped >= 0 &
         .and. pr%lyapunov_dropped <= pr%lyapunov_rerun .and. &
         pr%lyapunov_rerun <= pr%lyapunov_periods)
      call r%open(prefix // '.h5')
      call r%read('/diagnostics/lyapunov_rerun', rerun)
      call r%read('/diagnostics/lyapunov_dropped', dropped)
      call r%read('/diagnostics/lyapunov_starts', starts)
      call check('/diagnostics/lyapunov_rerun, _dropped, _starts written as counted', &
         .not. r%failed() .and. rerun == pr%lyapunov_rerun .and. &
         dropped == pr%lyapunov_dropped .and. starts == 1)
      call r%close()
      call execute_command_line('rm -f ' // prefix // '.h5 ' // prefix // '.*.dat')
      call diagnose_or_stop('test_exponent_starts', stable, [character(len=60) :: quiet], &
                            .false., plain)
      call check('no rings: nothing rerun or dropped', plain%lyapunov_rerun == 0 .and. &
                 plain%lyapunov_dropped == 0)
   end subroutine rerun_periods_are_written

   !> lyapunov_starts outside 1..64, and starts whose periods (each at least
   !> lyapunov_periods, with a lead-in of up to 4 x) pass the most a run may integrate.
   subroutine bad_starts_are_refused()
      call expect_refused(chaos, 'lyapunov_starts = 0 refused', &
         '&diagnostics lyapunov_starts = 0 /', [character(len=30) :: '&diagnostics', &
         'lyapunov_starts = 0', '1..64'])
      call expect_refused(chaos, 'lyapunov_starts = 65 refused', &
         '&diagnostics lyapunov_starts = 65 /', [character(len=30) :: '&diagnostics', &
         'lyapunov_starts = 65', '1..64'])
      call expect_refused(chaos, '64 starts of at least 1e7 periods each refused', &
         '&diagnostics lyapunov_starts = 64, lyapunov_periods = 10000000 /', &
         [character(len=30) :: 'lyapunov_periods = 10000000', 'at most'])
   end subroutine bad_starts_are_refused
end program test_exponent_starts
