!> Which work items of a sweep each shard runs (`--shard I/N`).
!>
!> The unit dealt is a group of points (a point, or a whole line when some start runs along
!> lines, gapbeam_sweep), so a shard holds whole points and whole lines. Two ways:
!>
!> - round robin (the default): group g goes to shard mod(g - 1, N) + 1, so every shard gets
!>   points spread over the whole grid; right when the points cost about the same;
!> - by cost (`--shard-costs FILE.h5`, a result file of an earlier sweep of the same grid, whole
!>   or merged): a group's cost is the sum of its points' `/sweep/seconds` there, and the
!>   groups are dealt longest first, each to the shard with the least cost so far (ties: the
!>   lower group, the lower shard), the LPT rule, whose largest shard is within 4/3 of the
!>   best possible. Within a shard the groups then run costly first, which also balances its
!>   threads.
!>
!> Either way the deal is a pure function of the plan, N and the file, so every task of an
!> array computes the same one; the results do not depend on it (every work item runs the
!> same way wherever it runs, and the merge writes the points in point order), only the time
!> to solution does. A deal by cost is part of the checkpoint's signature (its CRC-32), so that
!> a shard is never resumed under another deal.
module gapbeam_shards
   use, intrinsic :: iso_fortran_env, only: int8, int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_settings, only: batch_options_t
   use gapbeam_sweep, only: sweep_plan_t, n_points, n_groups, n_items, group_of_item, &
      group_points
   use gapbeam_hdf5_input, only: h5_reader_t
   use gapbeam_checksum, only: crc32
   implicit none
   private
   public :: shard_deal_t, deal_shards, shard_items, deal_signature, deal_summary, &
      deal_round_robin, deal_by_cost, shard_loads

   !> The shard of every group of a sweep.
   type :: shard_deal_t
      integer :: n_shards = 1                          !! N
      integer, allocatable :: shard_of(:)              !! shard of each group
      real(dp), allocatable :: cost(:)                 !! estimated cost of each group [s]
                                                       !! (unallocated: round robin)
      character(len=:), allocatable :: source          !! the cost file ('' for round robin)
   end type shard_deal_t

contains

   !> The deal of `plan`'s groups to `batch`'s shards.
   subroutine deal_shards(plan, batch, deal, err)
      type(sweep_plan_t), intent(in) :: plan             !! the sweep
      type(batch_options_t), intent(in) :: batch         !! shard count, cost file
      type(shard_deal_t), intent(out) :: deal            !! the deal
      type(error_t), allocatable, intent(out) :: err     !! the cost file is unusable
      real(dp), allocatable :: point_cost(:)
      integer :: g
      deal%n_shards = batch%shard_count
      deal%source = ''
      if (.not. allocated(batch%shard_costs)) then
         deal%shard_of = deal_round_robin(n_groups(plan), deal%n_shards)
         return
      end if
      call read_point_costs(batch%shard_costs, plan, point_cost, err)
      if (allocated(err)) return
      deal%source = batch%shard_costs
      allocate(deal%cost(n_groups(plan)))
      do g = 1, n_groups(plan)
         deal%cost(g) = sum(point_cost(group_points(plan, g)))
      end do
      deal%shard_of = deal_by_cost(deal%cost, deal%n_shards)
   end subroutine deal_shards

   !> Round robin: group g to shard mod(g - 1, n_shards) + 1.
   pure function deal_round_robin(n_groups, n_shards) result(shard_of)
      integer, intent(in) :: n_groups, n_shards          !! groups, shards
      integer, allocatable :: shard_of(:)
      integer :: g
      shard_of = [(mod(g - 1, n_shards) + 1, g = 1, n_groups)]
   end function deal_round_robin

   !> Longest processing time first: the groups by decreasing cost (ties: lower group first),
   !> each to the shard with the least cost so far (ties: lower shard).
   pure function deal_by_cost(cost, n_shards) result(shard_of)
      real(dp), intent(in) :: cost(:)                    !! cost of each group
      integer, intent(in) :: n_shards                    !! shards
      integer, allocatable :: shard_of(:)
      real(dp) :: load(n_shards)
      integer, allocatable :: order(:)
      integer :: j, k
      order = decreasing(cost)
      load = 0.0_dp
      allocate(shard_of(size(cost)))
      do j = 1, size(order)
         k = minloc(load, dim=1)                         ! the first of equal loads
         shard_of(order(j)) = k
         load(k) = load(k) + cost(order(j))
      end do
   end function deal_by_cost

   !> The cost of every shard under a deal.
   pure function shard_loads(cost, shard_of, n_shards) result(load)
      real(dp), intent(in) :: cost(:)                    !! cost of each group
      integer, intent(in) :: shard_of(:)                 !! shard of each group
      integer, intent(in) :: n_shards                    !! shards
      real(dp) :: load(n_shards)
      integer :: g
      load = 0.0_dp
      do g = 1, size(cost)
         load(shard_of(g)) = load(shard_of(g)) + cost(g)
      end do
   end function shard_loads

   !> The work items of shard `index`: ascending for round robin, costly groups first for a
   !> deal by cost.
   function shard_items(plan, deal, index) result(items)
      type(sweep_plan_t), intent(in) :: plan             !! the sweep
      type(shard_deal_t), intent(in) :: deal             !! the deal
      integer, intent(in) :: index                       !! the shard I
      integer, allocatable :: items(:)
      integer, allocatable :: order(:)
      integer :: k
      items = pack([(k, k = 1, n_items(plan))], &
                   [(deal%shard_of(group_of_item(plan, k)) == index, k = 1, n_items(plan))])
      if (.not. allocated(deal%cost)) return
      order = decreasing([(deal%cost(group_of_item(plan, items(k))), k = 1, size(items))])
      items = items(order)
   end function shard_items

   !> The line the deal adds to the checkpoint's signature: '' for round robin.
   function deal_signature(deal) result(t)
      type(shard_deal_t), intent(in) :: deal             !! the deal
      character(len=:), allocatable :: t
      character(len=8) :: hex
      if (.not. allocated(deal%cost)) then
         t = ''
         return
      end if
      write(hex, '(z8.8)') crc32(transfer(deal%shard_of, [0_int8]))
      t = new_line('a') // '! shards dealt by cost (deal CRC-32 ' // hex // ')'
   end function deal_signature

   !> One line on the deal for the run's summary: the shard's estimated cost against the
   !> largest shard's, and round robin's largest on the same costs; '' for round robin.
   function deal_summary(deal, index) result(t)
      type(shard_deal_t), intent(in) :: deal             !! the deal
      integer, intent(in) :: index                       !! the shard I
      character(len=:), allocatable :: t
      real(dp), allocatable :: mine(:), rr(:)
      if (.not. allocated(deal%cost)) then
         t = ''
         return
      end if
      mine = shard_loads(deal%cost, deal%shard_of, deal%n_shards)
      rr = shard_loads(deal%cost, deal_round_robin(size(deal%cost), deal%n_shards), &
                       deal%n_shards)
      t = 'shards: dealt by the costs in ' // deal%source // ' (' // str(sum(deal%cost)) &
         // ' s in all): this shard ' // str(mine(index)) // ' s, the largest ' &
         // str(maxval(mine)) // ' s (round robin: ' // str(maxval(rr)) // ' s)'
   end function deal_summary

   !> Cost of every point of `plan` from a sweep result file of the same grid: its
   !> `/sweep/seconds`, which must cover every point.
   subroutine read_point_costs(path, plan, cost, err)
      character(len=*), intent(in) :: path               !! the result file
      type(sweep_plan_t), intent(in) :: plan             !! the sweep
      real(dp), allocatable, intent(out) :: cost(:)      !! cost of each point [s]
      type(error_t), allocatable, intent(out) :: err     !! unreadable, or another grid
      character(len=*), parameter :: here = '--shard-costs '
      type(h5_reader_t) :: h5
      integer, allocatable :: pts(:)
      real(dp), allocatable :: seconds(:), gx(:), gy(:)
      logical, allocatable :: seen(:)
      integer :: total, k
      call h5%open(path, err)
      if (.not. allocated(err)) call h5%read('/sweep/n_points_total', total, err)
      if (.not. allocated(err)) call h5%read('/sweep/point_index', pts, err)
      if (.not. allocated(err)) call h5%read('/sweep/seconds', seconds, err)
      if (.not. allocated(err)) call h5%read('/sweep/grid_x', gx, err)
      if (.not. allocated(err)) call h5%read('/sweep/grid_y', gy, err)
      call h5%close()
      if (allocated(err)) then
         err%message = here // "'" // path // "': not a sweep result file: " // err%message
         return
      end if
      if (size(gx) /= plan%nx .or. size(gy) /= plan%ny .or. total /= n_points(plan)) then
         call fatal_error(err, here // "'" // path // "' holds a sweep of " // str(size(gx)) &
            // ' x ' // str(size(gy)) // ' points, this deck one of ' // str(plan%nx) // ' x ' &
            // str(plan%ny) // ': give a result file of the same grid')
         return
      end if
      allocate(seen(total), source=.false.)
      allocate(cost(total), source=0.0_dp)
      do k = 1, min(size(pts), size(seconds))
         if (pts(k) < 1 .or. pts(k) > total) cycle
         seen(pts(k)) = .true.
         cost(pts(k)) = max(0.0_dp, seconds(k))
      end do
      if (.not. all(seen) .or. size(seconds) /= size(pts)) then
         call fatal_error(err, here // "'" // path // "' holds " // str(count(seen)) // ' of ' &
            // 'the ' // str(total) // ' points (a shard file?): give the whole or merged file')
         return
      end if
      if (.not. all(cost < huge(1.0_dp))) then
         call fatal_error(err, here // "'" // path // "': its /sweep/seconds are not finite")
      end if
   end subroutine read_point_costs

   !> Indices that order `v` by decreasing value, equal values in index order (a stable
   !> merge sort: the same order on every machine).
   pure function decreasing(v) result(idx)
      real(dp), intent(in) :: v(:)                       !! values
      integer, allocatable :: idx(:)
      integer, allocatable :: tmp(:)
      integer :: i, width, lo, mid, hi, a, b, k, n
      logical :: left
      n = size(v)
      idx = [(i, i = 1, n)]
      allocate(tmp(n))
      width = 1
      do while (width < n)
         do lo = 1, n, 2 * width
            mid = min(lo + width, n + 1)
            hi = min(lo + 2 * width, n + 1)
            a = lo;  b = mid;  k = lo
            do while (k < hi)
               left = a < mid
               if (left .and. b < hi) left = v(idx(a)) >= v(idx(b))
               if (left) then
                  tmp(k) = idx(a);  a = a + 1
               else
                  tmp(k) = idx(b);  b = b + 1
               end if
               k = k + 1
            end do
         end do
         idx = tmp
         width = 2 * width
      end do
   end function decreasing
end module gapbeam_shards
