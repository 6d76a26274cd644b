!> How a sweep's work is dealt to shards (gapbeam_shards): round robin, and longest processing
!> time first from measured costs. Every group lands in exactly one shard; equal costs give
!> round robin; the LPT deal of a known case is the one worked out by hand; on the tube map's
!> measured point costs (bench_results/shard_makespans.txt) the largest shard is never worse than
!> round robin's and within the greedy bound; a shard's work items run costly first.
program test_shards
   use gapbeam_kinds, only: dp
   use gapbeam_testing, only: check, check_le, finish
   use gapbeam_deck, only: deck_t
   use gapbeam_model, only: model_t
   use gapbeam_sweep, only: sweep_plan_t, n_groups, n_items, group_of_item
   use gapbeam_shards, only: shard_deal_t, deal_round_robin, deal_by_cost, shard_loads, &
      shard_items, deal_signature
   use gapbeam_test_runs, only: load_or_stop, make_plan_or_stop
   implicit none

   !> CPU seconds of the 45 points of inputs/tube_map.nml, release build, one thread
   !> (bench_results/shard_makespans.txt), in point order.
   real(dp), parameter :: tube(45) = [7.46_dp, 8.11_dp, 7.98_dp, 6.52_dp, 6.86_dp, 5.77_dp, &
      6.63_dp, 6.03_dp, 5.61_dp, 6.73_dp, 5.73_dp, 4.90_dp, 2.99_dp, 2.82_dp, 3.53_dp, 3.13_dp, &
      4.44_dp, 4.60_dp, 5.33_dp, 5.49_dp, 4.50_dp, 4.43_dp, 3.03_dp, 3.01_dp, 2.91_dp, 2.73_dp, &
      3.71_dp, 0.55_dp, 2.85_dp, 3.41_dp, 4.25_dp, 3.52_dp, 2.45_dp, 2.72_dp, 2.70_dp, 3.23_dp, &
      0.22_dp, 0.31_dp, 1.93_dp, 2.82_dp, 2.97_dp, 3.58_dp, 3.28_dp, 2.46_dp, 2.98_dp]

   call round_robin()
   call lpt_by_hand()
   call equal_costs_give_round_robin()
   call tube_map_costs()
   call items_of_a_plan()
   call finish('test_shards')

contains

   !> Round robin: group g in shard mod(g - 1, N) + 1.
   subroutine round_robin()
      integer, allocatable :: s(:)
      s = deal_round_robin(7, 3)
      call check('round robin of 7 groups over 3 shards: 1 2 3 1 2 3 1', &
         all(s == [1, 2, 3, 1, 2, 3, 1]))
      s = deal_round_robin(2, 5)
      call check('round robin of 2 groups over 5 shards: 1 2 (shards 3-5 empty)', all(s == [1, 2]))
   end subroutine round_robin

   !> Costs 5, 4, 3, 3, 3 over 2 shards: 5 -> 1, 4 -> 2, 3 -> 2 (4 < 5), 3 -> 1 (5 < 7),
   !> 3 -> 2 (7 < 8): loads 8 and 10 (the best is 9: LPT's 4/3 bound allows 12).
   subroutine lpt_by_hand()
      integer, allocatable :: s(:)
      real(dp) :: load(2)
      s = deal_by_cost([5.0_dp, 4.0_dp, 3.0_dp, 3.0_dp, 3.0_dp], 2)
      call check('LPT of 5 4 3 3 3 over 2 shards: 1 2 2 1 2', all(s == [1, 2, 2, 1, 2]))
      load = shard_loads([5.0_dp, 4.0_dp, 3.0_dp, 3.0_dp, 3.0_dp], s, 2)
      call check('LPT loads 8 and 10', all(load == [8.0_dp, 10.0_dp]))
      s = deal_by_cost([1.0_dp, 9.0_dp, 2.0_dp, 8.0_dp], 2)
      call check('LPT of 1 9 2 8: 9 and 1 in one shard, 8 and 2 in the other', &
         s(2) == 1 .and. s(4) == 2 .and. s(3) == 2 .and. s(1) == 1)
   end subroutine lpt_by_hand

   !> Equal costs: the stable order and the first of equal loads make LPT round robin.
   subroutine equal_costs_give_round_robin()
      real(dp) :: c(11)
      c = 2.5_dp
      call check('equal costs: the deal by cost is round robin (11 groups, 4 shards)', &
         all(deal_by_cost(c, 4) == deal_round_robin(11, 4)))
   end subroutine equal_costs_give_round_robin

   !> The tube map's costs: every point once, the largest shard no worse than round robin's and
   !> within the greedy bound total / N + largest point.
   subroutine tube_map_costs()
      integer, parameter :: counts(4) = [2, 16, 64, 256]
      integer, allocatable :: s(:)
      real(dp), allocatable :: lpt(:), rr(:)
      integer :: j, n
      character(len=8) :: tag
      do j = 1, size(counts)
         n = counts(j)
         write(tag, '(i0)') n
         s = deal_by_cost(tube, n)
         call check('tube map, N = ' // trim(tag) // ': every point in a shard 1..N', &
            size(s) == size(tube) .and. all(s >= 1 .and. s <= n))
         lpt = shard_loads(tube, s, n)
         rr = shard_loads(tube, deal_round_robin(size(tube), n), n)
         call check('tube map, N = ' // trim(tag) // ': the shards hold all the cost', &
            abs(sum(lpt) - sum(tube)) <= 1.0e-12_dp * sum(tube))
         call check_le('tube map, N = ' // trim(tag) // ': largest shard by cost <= round robin''s', &
            maxval(lpt), maxval(rr))
         call check_le('tube map, N = ' // trim(tag) // ': largest shard <= total / N + largest point', &
            maxval(lpt), sum(tube) / n + maxval(tube))
      end do
      lpt = shard_loads(tube, deal_by_cost(tube, 16), 16)
      rr = shard_loads(tube, deal_round_robin(45, 16), 16)
      call check_le('tube map, N = 16: by cost at least 25 % shorter than round robin', &
         maxval(lpt), 0.75_dp * maxval(rr))
   end subroutine tube_map_costs

   !> A plan's items under a deal: disjoint, complete, costly first; the deal's signature.
   subroutine items_of_a_plan()
      type(deck_t) :: deck
      type(model_t) :: model
      type(sweep_plan_t) :: plan
      type(shard_deal_t) :: deal
      real(dp), allocatable :: u0(:), v0(:)
      integer, allocatable :: items(:), seen(:)
      integer :: i, k
      logical :: ordered
      call load_or_stop('test_shards', 'test/decks/sweep_small.nml', [character(len=1) :: ], &
         deck, model, u0, v0)
      call make_plan_or_stop('test_shards', deck, plan)
      deal%n_shards = 3
      deal%source = 'test'
      deal%cost = [(real(mod(7 * k, 5) + 1, dp), k = 1, n_groups(plan))]
      deal%shard_of = deal_by_cost(deal%cost, 3)
      allocate(seen(n_items(plan)), source=0)
      ordered = .true.
      do i = 1, 3
         items = shard_items(plan, deal, i)
         seen(items) = seen(items) + 1
         do k = 2, size(items)
            ordered = ordered .and. deal%cost(group_of_item(plan, items(k - 1))) >= &
               deal%cost(group_of_item(plan, items(k)))
         end do
      end do
      call check('sweep_small under a deal by cost: every work item in exactly one shard', &
         all(seen == 1))
      call check('each shard runs its costly items first', ordered)
      call check('a deal by cost is named in the checkpoint signature', &
         index(deal_signature(deal), '! shards dealt by cost (deal CRC-32 ') > 0)
      deallocate(deal%cost)
      call check('round robin adds nothing to the signature', len(deal_signature(deal)) == 0)
   end subroutine items_of_a_plan
end program test_shards
