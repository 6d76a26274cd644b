!> The model of a deck with numeric variables set to new values (gapbeam_deck_variable): the
!> deck is copied, the values set and the model rebuilt, so that every rule of the deck (the
!> stop-stiffness rule, damping ratios) applies again. The forcing variables only change the
!> forcing of the model, so with the deck's model at hand they skip the rebuild (not with a
!> turbulence record: its default resolution follows the forcing frequency; `draw` chooses
!> the record). A modal
!> reduction by a cut-off (or kind 'auto') keeps the deck's own number of modes at every value.
module gapbeam_deck_parameter
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t
   use gapbeam_deck, only: deck_t
   use gapbeam_deck_variable, only: deck_variable_t, set_deck_value
   use gapbeam_deck_table, only: max_frequency_hz, min_amplitude_pp
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_model
   use gapbeam_reduction_rule, only: reduction_info_t
   implicit none
   private
   public :: model_with_values

contains

   !> The model of `deck` with vars(k) = values(k); `base` (the model of `deck` itself) is
   !> copied instead of a rebuild when every variable is a forcing variable. There the
   !> frequency and the amplitude are checked against their ranges (gapbeam_deck_table) but
   !> for the amplitude's upper bound: a base motion too large for the scale rule diverges, a
   !> failed point of a sweep.
   subroutine model_with_values(deck, vars, values, model, err, base, draw)
      type(deck_t), intent(in) :: deck                   !! deck
      type(deck_variable_t), intent(in) :: vars(:)       !! variables (checked on this deck)
      real(dp), intent(in) :: values(:)                  !! their values
      type(model_t), intent(out) :: model                !! the model
      type(error_t), allocatable, intent(out) :: err     !! value out of range, build failure
      type(model_t), intent(in), optional :: base        !! model of `deck`
      integer, intent(in), optional :: draw              !! turbulence draw (default 1)
      type(deck_t) :: d
      type(reduction_info_t) :: info
      real(dp), allocatable :: u0(:), v0(:)
      integer :: k, dr
      dr = 1
      if (present(draw)) dr = draw
      ! a turbulence record depends on the forcing frequency (its default resolution) and on
      ! the draw: rebuilt
      if (present(base) .and. all(vars%group == 'forcing') .and. &
          deck%turbulence%spectrum == 'none') then
         model = base
         do k = 1, size(vars)
            if (vars(k)%name == 'frequency_hz') then
               if (.not. (values(k) > 0.0_dp .and. values(k) <= max_frequency_hz)) then
                  call set_deck_value(d, vars(k), values(k), err)   ! the range message
                  return
               end if
               model%omega = 2.0_dp * pi * values(k)
            else
               if (.not. (values(k) == 0.0_dp .or. values(k) >= min_amplitude_pp)) then
                  call set_deck_value(d, vars(k), values(k), err)
                  return
               end if
               model%half_amplitude = 0.5_dp * values(k)
            end if
         end do
         return
      end if
      d = deck
      do k = 1, size(vars)
         call set_deck_value(d, vars(k), values(k), err)
         if (allocated(err)) return
      end do
      if (deck%reduction%kind == 'auto' .or. (deck%reduction%kind == 'modal' .and. &
          deck%reduction%cutoff_hz > 0.0_dp)) then
         ! every point keeps the deck's own modes (the cut-off chosen at the deck's values), so
         ! that the points' coordinates are alike and states carry from one to the next
         call build_model(deck, model, u0, v0, err, info)
         if (allocated(err)) return
         d%reduction%kind = 'modal'
         d%reduction%cutoff_hz = 0.0_dp
         d%reduction%n_modes = info%modes_per_plane
      end if
      call build_model(d, model, u0, v0, err, draw=dr)
   end subroutine model_with_values
end module gapbeam_deck_parameter
