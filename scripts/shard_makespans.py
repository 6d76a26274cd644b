#!/usr/bin/env python3
"""scripts/shard_makespans.py - time to solution of a sweep split into N shards, from the
measured cost of every point (/sweep/seconds of a whole or merged result file).

Usage:
  scripts/shard_makespans.py RESULT.h5 [N ...]        (default N: 2 16 64 256)

For each N it prints the makespan (the largest shard's summed cost: all N shards run at once,
one core each) of
  round robin     gapbeam's default deal, point p in shard mod(p - 1, N) + 1;
  by cost         --shard-costs: longest processing time first, each point to the shard with
                  the least cost so far (ties: lower point, lower shard), as gapbeam_shards does;
  throttled       min(4 N, points) shards dealt round robin and run N at a time in index order
                  (sbatch --array=1-M%N): each freed slot takes the next shard;
and the lower bound max(total / N, largest point), with each deal's efficiency
(total / (N x makespan)). Groups are points (mode 'independent'); the costs are CPU seconds, so
the makespans assume one core per shard and nothing else on it; per-shard overheads (start,
model set-up, file writing, scheduling) are not included.
"""
import sys

import h5py


def round_robin(costs, n):
    loads = [0.0] * n
    for p, c in enumerate(costs):
        loads[p % n] += c
    return max(loads)


def by_cost(costs, n):
    loads = [0.0] * n
    for p in sorted(range(len(costs)), key=lambda q: (-costs[q], q)):
        k = min(range(n), key=lambda j: (loads[j], j))
        loads[k] += costs[p]
    return max(loads)


def throttled(costs, n):
    m = min(4 * n, len(costs))
    shards = [0.0] * m
    for p, c in enumerate(costs):
        shards[p % m] += c
    free = [0.0] * n                 # the time each slot becomes free
    end = 0.0
    for s in shards:                 # in index order, each to the slot free first
        k = min(range(n), key=lambda j: (free[j], j))
        free[k] += s
        end = max(end, free[k])
    return end, m


def main(argv):
    if len(argv) < 2 or argv[1] in ('-h', '--help'):
        print(__doc__)
        return 0 if len(argv) >= 2 else 2
    counts = [int(a) for a in argv[2:]] or [2, 16, 64, 256]
    with h5py.File(argv[1], 'r') as f:
        idx = f['/sweep/point_index'][:]
        sec = f['/sweep/seconds'][:]
        total_points = int(f['/sweep/n_points_total'][()])
    if len(idx) != total_points:
        sys.exit('{}: {} of {} points: give a whole or merged file'.format(argv[1], len(idx),
                                                                          total_points))
    costs = [0.0] * total_points
    for p, c in zip(idx, sec):
        costs[p - 1] = max(0.0, float(c))
    total = sum(costs)
    print('# {}: {} points, {:.1f} s CPU in all, points {:.2f} .. {:.2f} s'.format(
        argv[1], len(costs), total, min(costs), max(costs)))
    print('# makespan [s] (efficiency total / (N x makespan))')
    print('{:>5} {:>16} {:>16} {:>22} {:>12}'.format('N', 'round robin', 'by cost',
                                                       'throttled (M shards)', 'lower bound'))
    for n in counts:
        rr, lpt = round_robin(costs, n), by_cost(costs, n)
        th, m = throttled(costs, n)
        lb = max(total / n, max(costs))

        def cell(x):
            return '{:7.2f} ({:3.0f} %)'.format(x, 100.0 * total / (n * x))
        print('{:>5} {:>16} {:>16} {:>14} ({:>4}) {:>12.2f}'.format(
            n, cell(rr), cell(lpt), cell(th), m, lb))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
