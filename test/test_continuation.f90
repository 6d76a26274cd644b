!> Periodic orbits, monodromy matrices and continuation (issue 14).
program test_continuation
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_testing, only: check, check_close, check_le, finish, note
   use gapbeam_deck, only: deck_t
   use gapbeam_input, only: read_deck
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_periodic, only: orbit_map_t, newton_orbit, transient_orbit, floquet_multipliers, &
      energy_size
   implicit none
   character(len=*), parameter :: ref = 'inputs/sweep_line_4mm.nml'

   call monodromy_against_differences()
   call finish('test_continuation')

contains

   subroutine load(path, overrides, deck, model, u0, v0)
      character(len=*), intent(in) :: path, overrides(:)
      type(deck_t), intent(out) :: deck
      type(model_t), intent(out) :: model
      real(dp), allocatable, intent(out) :: u0(:), v0(:)
      type(error_t), allocatable :: err
      character(len=300) :: ov(size(overrides))
      ov = overrides
      call read_deck(path, ov, deck, err)
      if (.not. allocated(err)) call build_model(deck, model, u0, v0, err)
      if (allocated(err)) then
         call check('load ' // path, .false., err%message)
         call finish('test_continuation')
      end if
   end subroutine load

   !> The exact monodromy (transition and saltation matrices) against central differences of
   !> the exact map: no impact, impacts at a zero gap, impacts on a damped stop (the saltation
   !> matrices at the onsets; without them the error is 3e-2).
   subroutine monodromy_against_differences()
      character(len=300) :: cases(3)
      character(len=24) :: names(3)
      integer :: k
      cases = [character(len=300) :: '&stops gap = 1.0 /', '&stops gap = 0.0 /', &
               '&stops damping = 0.02 /']
      names = [character(len=24) :: 'no impact', 'zero gap', 'damped stop']
      do k = 1, 3
         call one(cases(k), trim(names(k)))
      end do
   end subroutine monodromy_against_differences

   subroutine one(case, name)
      character(len=*), intent(in) :: case, name
      type(deck_t) :: deck
      type(model_t) :: model
      type(orbit_map_t) :: ex, fd
      real(dp), allocatable :: u0(:), v0(:), x(:), px(:), px2(:), ja(:, :), jb(:, :)
      type(error_t), allocatable :: err
      integer :: p
      real(dp) :: e
      call load(ref, [character(len=300) :: "&solver method = 'exact' /", &
         '&forcing frequency_hz = 10.0 /', case], deck, model, u0, v0)
      call ex%setup(model, deck%solver, 1, 0.0_dp, .true., 1.0e-5_dp, err)
      if (.not. allocated(err)) call fd%setup(model, deck%solver, 1, 0.0_dp, .false., &
                                              1.0e-5_dp, err)
      if (.not. allocated(err)) call transient_orbit(ex, u0, v0, 20, 8, 1.0e-6_dp, x, p, err)
      if (allocated(err)) then
         call check('monodromy, ' // name // ': set-up', .false., err%message)
         return
      end if
      allocate(px(size(x)), px2(size(x)), ja(size(x), size(x)), jb(size(x), size(x)))
      call ex%evaluate(x, px, err, jac=ja)
      if (.not. allocated(err)) call fd%evaluate(x, px2, err, jac=jb)
      if (allocated(err)) then
         call check('monodromy, ' // name // ': maps', .false., err%message)
         return
      end if
      e = maxval(abs(ja - jb)) / maxval(abs(jb))
      call check_le('monodromy, ' // name // ': exact against central differences ' &
         // '(max |error| / max |entry|)', e, 1.0e-6_dp)
      call check('monodromy, ' // name // ': same map', maxval(abs(px - px2)) == 0.0_dp)
   end subroutine one
end program test_continuation
