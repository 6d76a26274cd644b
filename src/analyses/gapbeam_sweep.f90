!> The sweep: a line or grid of points over one or two numeric deck variables (the forcing
!> frequency and amplitude by default), each point run from one or several starts to its
!> attractors, labelled, certified, in parallel with OpenMP.
!>
!> Points are numbered with x fastest: p = i_x + (i_y - 1) n_x. A point's model is the deck's
!> with the axis variables set to the point's values (an axis naming several variables sets
!> each of them to its value) (gapbeam_deck_parameter: the model is
!> rebuilt, so every rule of the deck applies again; a forcing variable only changes the
!> forcing). Each point has n_s starts (gapbeam_starts: 'deck', 'rest', 'random', or 'up' /
!> 'down' from the neighbour's final state along the lines of `axis`); the first start's
!> label is the point's label and is certified (gapbeam_certify) when asked.
!>
!> Work: every (point, start) pair is a slot, s = p + (k - 1) n_p. Slots are computed by work
!> items; an item is one start k over one group of points: with an 'up' or 'down' start the
!> groups are the lines along `axis` (one per value of the other axis), and an item of an 'up'
!> or 'down' start runs its line in that order, each point starting from the final state of
!> the one before (as in an experiment); without such a start every point is a group. Item
!> i = k + (g - 1) n_s. A work item runs serially on one thread, so results are bitwise
!> identical for any number of threads and any schedule. Groups are dealt to shards round
!> robin (group g belongs to shard mod(g - 1, N) + 1), so a shard holds whole points.
module gapbeam_sweep
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_settings, only: output_settings_t
   use gapbeam_results, only: transient_result_t, point_result_t, label_failed
   use gapbeam_deck_variable, only: deck_variable_t, parse_deck_variables, check_deck_variable, &
      deck_variables_label
   use gapbeam_deck_parameter, only: model_with_values
   use gapbeam_point, only: start_vector, label_start, integrator_cache_t
   use gapbeam_starts, only: start_list, group_attractors
   use gapbeam_flow_results, only: draw_statistics_t
   use gapbeam_draws, only: draws_wanted, collect_draws, draw_statistics, n_draw_outputs
   implicit none
   private
   public :: sweep_plan_t, make_plan, n_points, n_items, n_groups, group_of_item, item_slots, &
      group_points, slot_index, run_items, combine_point

   !> What a sweep runs: its axes, its starts, its groups.
   type :: sweep_plan_t
      type(deck_variable_t) :: var(2)                    !! the x and y variables (the first
                                                         !! of an axis of several)
      type(deck_variable_t), allocatable :: set(:)       !! every variable a point sets
      integer, allocatable :: set_axis(:)                !! its axis (1: x, 2: y)
      character(len=160) :: label(2) = ''                !! the axes' names, as in the file
      real(dp), allocatable :: x(:), y(:)                !! axis values
      integer :: nx = 0, ny = 0, np = 0                  !! axis sizes, points
      character(len=8), allocatable :: kinds(:)          !! start kinds, in order
      integer, allocatable :: random_index(:)            !! number of a random start (0: none)
      integer :: ns = 0                                  !! starts per point
      logical :: lines = .false.                         !! some start runs along lines
      integer :: line_axis = 1                           !! 1: lines along x, 2: along y
   end type sweep_plan_t

contains

   !> The plan of a deck's sweep (axes parsed and checked on the deck).
   subroutine make_plan(deck, plan, err)
      type(deck_t), intent(in) :: deck                  !! validated deck
      type(sweep_plan_t), intent(out) :: plan           !! plan
      type(error_t), allocatable, intent(out) :: err    !! unknown or absent variable
      character(len=8) :: default
      integer :: j
      type(deck_variable_t), allocatable :: xs(:), ys(:)
      call parse_deck_variables(deck%sweep%x_variable, xs, err)
      if (.not. allocated(err)) call parse_deck_variables(deck%sweep%y_variable, ys, err)
      if (.not. allocated(err)) then
         plan%set = [xs, ys]
         plan%set_axis = [spread(1, 1, size(xs)), spread(2, 1, size(ys))]
         do j = 1, size(plan%set)
            if (.not. allocated(err)) call check_deck_variable(deck, plan%set(j), err)
         end do
      end if
      if (allocated(err)) then
         err%message = 'group &sweep: ' // err%message
         return
      end if
      plan%var(1) = xs(1);  plan%var(2) = ys(1)
      plan%label(1) = deck_variables_label(xs);  plan%label(2) = deck_variables_label(ys)
      plan%x = deck%sweep%x;  plan%y = deck%sweep%y
      plan%nx = size(plan%x);  plan%ny = size(plan%y);  plan%np = plan%nx * plan%ny
      default = 'deck'
      if (deck%sweep%mode == 'continuation') default = deck%sweep%direction
      call start_list(deck%diagnostics, default, plan%kinds, plan%random_index)
      plan%ns = size(plan%kinds)
      plan%lines = any(plan%kinds == 'up' .or. plan%kinds == 'down')
      plan%line_axis = 1
      select case (deck%sweep%axis)
      case ('y')
         plan%line_axis = 2
      case ('frequency', 'amplitude')
         do j = 1, 2
            if (plan%var(j)%group == 'forcing' .and. ((deck%sweep%axis == 'frequency' .and. &
                plan%var(j)%name == 'frequency_hz') .or. (deck%sweep%axis == 'amplitude' &
                .and. plan%var(j)%name == 'amplitude_pp'))) plan%line_axis = j
         end do
      end select
   end subroutine make_plan

   !> Number of points.
   pure integer function n_points(plan)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      n_points = plan%np
   end function n_points

   !> Number of groups (lines, or points).
   pure integer function n_groups(plan)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      if (.not. plan%lines) then
         n_groups = plan%np
      else if (plan%line_axis == 1) then
         n_groups = plan%ny
      else
         n_groups = plan%nx
      end if
   end function n_groups

   !> Number of work items (groups x starts).
   pure integer function n_items(plan)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      n_items = n_groups(plan) * plan%ns
   end function n_items

   !> Group of work item i.
   pure integer function group_of_item(plan, i)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      integer, intent(in) :: i                 !! work item
      group_of_item = (i - 1) / plan%ns + 1
   end function group_of_item

   !> Points of group g, ascending along the line axis.
   pure function group_points(plan, g) result(pts)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      integer, intent(in) :: g                 !! group
      integer, allocatable :: pts(:)
      integer :: j
      if (.not. plan%lines) then
         pts = [g]
      else if (plan%line_axis == 1) then
         pts = [(j + (g - 1) * plan%nx, j = 1, plan%nx)]
      else
         pts = [(g + (j - 1) * plan%nx, j = 1, plan%ny)]
      end if
   end function group_points

   !> Slot of point p, start k.
   pure integer function slot_index(plan, p, k)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      integer, intent(in) :: p, k              !! point, start
      slot_index = p + (k - 1) * plan%np
   end function slot_index

   !> Slots of work item i, in the order they are run.
   pure function item_slots(plan, i) result(slots)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      integer, intent(in) :: i                 !! work item
      integer, allocatable :: slots(:), pts(:)
      integer :: k
      k = mod(i - 1, plan%ns) + 1
      pts = group_points(plan, group_of_item(plan, i))
      if (plan%kinds(k) == 'down') pts = pts(size(pts):1:-1)
      slots = pts + (k - 1) * plan%np
   end function item_slots

   !> Axis values of point p.
   pure subroutine point_values(plan, p, x, y)
      type(sweep_plan_t), intent(in) :: plan   !! plan
      integer, intent(in) :: p                 !! point
      real(dp), intent(out) :: x, y            !! values [their units]
      x = plan%x(mod(p - 1, plan%nx) + 1)
      y = plan%y((p - 1) / plan%nx + 1)
   end subroutine point_values

   !> Run slot s (point p, start k): the point's model (the deck's with the axis values set),
   !> the start its kind asks for (gapbeam_point: start_vector; (u_prev, v_prev) for 'up' /
   !> 'down': the previous point's final state, or the deck's start at a line's first point),
   !> then the point pipeline (label_start; the first start certified when the deck asks). A
   !> failure is recorded in the slot (status 1, its message, label 'failed'); nothing is
   !> printed.
   subroutine run_slot(deck, base, plan, s, u0, v0, u_prev, v_prev, sr)
      type(deck_t), intent(in) :: deck                   !! deck
      type(model_t), intent(in) :: base                  !! model of the deck itself
      type(sweep_plan_t), intent(in) :: plan             !! plan
      integer, intent(in) :: s                           !! slot
      real(dp), intent(in) :: u0(:), v0(:)               !! the deck's initial state
      real(dp), intent(in) :: u_prev(:), v_prev(:)       !! state handed along a line
      type(point_result_t), intent(out) :: sr            !! result of the slot
      type(model_t) :: model
      type(transient_result_t) :: res
      type(output_settings_t) :: o
      type(integrator_cache_t) :: cache
      type(error_t), allocatable :: err
      real(dp), allocatable :: u(:), v(:)
      integer :: p, k
      p = mod(s - 1, plan%np) + 1
      k = (s - 1) / plan%np + 1
      call point_values(plan, p, sr%x, sr%y)
      call model_with_values(deck, plan%set, merge(sr%x, sr%y, plan%set_axis == 1), model, err, &
                             base)
      if (.not. allocated(err)) then
         sr%f1_open_hz = model%f1_open_hz
         call start_vector(model, deck%diagnostics, plan%kinds(k), p, plan%ns, k, u0, v0, &
                           u_prev, v_prev, u, v, err)
      end if
      if (.not. allocated(err)) then
         o = deck%output
         o%history_periods = 0
         ! draws: the tip's history over the record, for its RMS
         if (k == 1 .and. draws_wanted(deck)) o%history_periods = deck%solver%record_periods
         call label_start(model, deck%solver, o, deck%diagnostics, u, v, p, &
                          k == 1 .and. deck%diagnostics%certify, res, sr, err, cache)
      end if
      if (.not. allocated(err) .and. k == 1 .and. draws_wanted(deck)) &
         call point_draws(deck, plan, model, u, v, o, res, sr, err)
      if (allocated(err)) then
         sr%status = 1
         sr%message = 'point ' // str(p) // ' (' // trim(plan%label(1)) // ' = ' &
            // str(sr%x) // ', ' // trim(plan%label(2)) // ' = ' // str(sr%y) &
            // '), start ' // str(k) // " ('" // trim(plan%kinds(k)) // "'): " // err%message
         call fill_failed(sr, base%n_stops, deck%solver%record_periods, u_prev, v_prev)
      end if
      sr%seconds = sr%seconds_label + sr%seconds_certify
   end subroutine run_slot

   !> The statistics over the random draws of a sweep point (gapbeam_draws) whose draw 1 is
   !> `res`, its start (u, v).
   subroutine point_draws(deck, plan, model, u, v, o, res, sr, err)
      type(deck_t), intent(in) :: deck                   !! deck
      type(sweep_plan_t), intent(in) :: plan             !! plan
      type(model_t), intent(in) :: model                 !! the point's model (draw 1)
      real(dp), intent(in) :: u(:), v(:)                 !! the point's start
      type(output_settings_t), intent(in) :: o           !! what a draw records
      type(transient_result_t), intent(in) :: res        !! draw 1's final record
      type(point_result_t), intent(inout) :: sr          !! the point
      type(error_t), allocatable, intent(out) :: err     !! a draw failed
      type(draw_statistics_t), allocatable :: stats(:)
      real(dp), allocatable :: vals(:, :, :)
      real(dp) :: t_rec
      integer :: j, ns
      t_rec = real(deck%solver%record_periods, dp) * 2.0_dp * pi / model%omega
      call collect_draws(deck, plan%set, merge(sr%x, sr%y, plan%set_axis == 1), u, v, o, res, &
                         t_rec, vals, err)
      if (allocated(err)) return
      ns = size(res%peak_force)
      stats = draw_statistics(vals, ns)
      sr%n_draws = size(vals, 1)
      allocate(sr%draw_mean(max(ns, 1), n_draw_outputs), source=0.0_dp)
      allocate(sr%draw_ci(max(ns, 1), n_draw_outputs), source=0.0_dp)
      do j = 1, n_draw_outputs
         sr%draw_mean(1:size(stats(j)%mean), j) = stats(j)%mean
         sr%draw_ci(1:size(stats(j)%mean), j) = stats(j)%half_width
      end do
   end subroutine point_draws

   !> A failed slot keeps NaN results of the right shapes, label 'failed'; a line goes on from
   !> the state it was given.
   subroutine fill_failed(pr, ns, nrec, u0, v0)
      type(point_result_t), intent(inout) :: pr
      integer, intent(in) :: ns, nrec
      real(dp), intent(in) :: u0(:), v0(:)
      real(dp) :: nan
      nan = transfer(-2251799813685248_8, 1.0_dp)
      pr%period = 0;  pr%label = label_failed;  pr%lyapunov = nan;  pr%lyapunov_error = nan
      if (allocated(pr%n_impacts)) deallocate(pr%n_impacts)
      allocate(pr%n_impacts(ns), source=0)
      pr%peak_force = spread(nan, 1, ns);  pr%rms_force = pr%peak_force
      pr%contact_fraction = pr%peak_force;  pr%impulse_per_period = pr%peak_force
      pr%work_rate = pr%peak_force
      pr%normal_work_rate = pr%peak_force;  pr%sliding_distance = pr%peak_force
      pr%friction_work_rate = pr%peak_force;  pr%wear_volume_rate = pr%peak_force
      pr%p_strain = spread(nan, 1, nrec);  pr%p_strain_rate = pr%p_strain
      if (allocated(pr%lyapunov_running)) deallocate(pr%lyapunov_running)
      allocate(pr%lyapunov_running(0))
      pr%u_end = u0;  pr%v_end = v0
      if (.not. allocated(pr%method)) pr%method = ''
   end subroutine fill_failed

   !> Run work items `items` in parallel (OpenMP, dynamic schedule, one item per thread at a
   !> time); slots(s) is written only by the thread that runs slot s. No I/O in here.
   !> Along a line every slot is handed the final state of the one before; with `first`,
   !> `last` only positions first..last of each item's slots are run, the slot before `first`
   !> having been run already (its final state is in `slots`), so a line run in several calls
   !> gives the same results as in one.
   subroutine run_items(deck, base, plan, items, u0, v0, slots, first, last)
      type(deck_t), intent(in) :: deck                   !! deck
      type(model_t), intent(in) :: base                  !! model of the deck itself
      type(sweep_plan_t), intent(in) :: plan             !! plan
      integer, intent(in) :: items(:)                    !! work items to run
      real(dp), intent(in) :: u0(:), v0(:)               !! the deck's initial state
      type(point_result_t), intent(inout) :: slots(:)    !! indexed by slot
      integer, intent(in), optional :: first, last       !! positions along each item to run
      integer :: i, j, j1, j2
      integer, allocatable :: ss(:)
      real(dp), allocatable :: u(:), v(:)
      j1 = 1;  j2 = huge(1)
      if (present(first)) j1 = max(1, first)
      if (present(last)) j2 = last
      !$omp parallel do default(none) schedule(dynamic, 1) &
      !$omp shared(deck, base, plan, items, u0, v0, slots, j1, j2) private(i, j, ss, u, v)
      do i = 1, size(items)
         ss = item_slots(plan, items(i))
         if (j1 > 1 .and. j1 <= size(ss)) then
            u = slots(ss(j1 - 1))%u_end;  v = slots(ss(j1 - 1))%v_end
         else
            u = u0;  v = v0
         end if
         do j = j1, min(j2, size(ss))
            call run_slot(deck, base, plan, ss(j), u0, v0, u, v, slots(ss(j)))
            u = slots(ss(j))%u_end;  v = slots(ss(j))%v_end
         end do
      end do
      !$omp end parallel do
   end subroutine run_items

   !> The result of point p: its first start's slot, with every start's label and the
   !> distinct attractors they reached (gapbeam_starts).
   function combine_point(deck, plan, slots, p) result(pr)
      type(deck_t), intent(in) :: deck                   !! deck (tolerances)
      type(sweep_plan_t), intent(in) :: plan             !! plan
      type(point_result_t), intent(in) :: slots(:)       !! all slots
      integer, intent(in) :: p                           !! point
      type(point_result_t) :: pr
      integer :: k
      pr = slots(p)
      call group_attractors([(slots(slot_index(plan, p, k)), k = 1, plan%ns)], &
                            deck%diagnostics, pr)
   end function combine_point
end module gapbeam_sweep
