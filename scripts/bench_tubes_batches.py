#!/usr/bin/env python3
"""The tube deck's 2 % judged on a chaotic record: batch means, full against reduced.

Usage:
    python3 scripts/bench_tubes_batches.py BENCH_EXE [--out PREFIX] [--batches K] [--starts S]
        [--record N] [--transient N] [--deck DECK] [--cutoffs HZ,...] [--first-start J]
        [--save DIR] [--from FILES ...]

The tube deck (inputs/tube_multispan.nml) is chaotic: two runs that differ in anything (the
model, the integrator, the tolerance) part, so one record's averages of two runs differ by the
record's own spread (the full model's 20-period records at 1e-3 ... 1e-6 differ by up to
18 %). What a wear estimate wants from a run is the attractor's averages: each support's normal
and friction work rates, impact rate, sliding distance, and the expected peak force of a record.
These are compared here as batch means with their standard errors. Each variant runs
`TRANSIENT` periods and then K records of `RECORD` periods, each from the end state of the one
before (BENCH_EXE, the release gapbeam_bench_tubes, with GAPBEAM_BENCH_BATCHES = K), from S
starts: the deck's own (rest) and S - 1 others with the mid-span node's initial velocity
(j - 1) mm/s in w (PERTURB; independent trajectories of the same attractor). The S x K batch
values of a quantity give its mean and standard error (the batches are taken as independent:
at the deck's largest Lyapunov exponent, about +3 1/s, a record of 20 periods, 2.5 s, is many
e-folding times long). The difference of the reduced model's mean from the full
model's is stated with two standard errors of the difference:
  met        |difference| + 2 SE <= 2 %
  missed     |difference| - 2 SE > 2 %
  undecided  otherwise (more batches would tell)
Variants: the full model (&reduction kind = 'none') and the default (reduced, 'auto') at the
deck's tolerance, the default at 10 x tighter (its own convergence), and reduced models with
the cut-offs of --cutoffs (&reduction kind = 'modal', cutoff_hz; default 1500,3000) at the
deck's tolerance. Serial (OMP_NUM_THREADS=1), under flock BENCH_LOCK when it names a lock
file. --first-start J runs the starts J..S only (to add starts to an earlier run); --save DIR
keeps each run's output as DIR/VARIANT_sJ.txt (VARIANT: full, auto, auto_tight, cutHZ).
--from reads the bench output files of earlier runs instead of running: one argument
per variant in that order, each a comma-separated list of files (one per start); it refuses
two files with the same batches (a start that was not perturbed repeats the first).
Writes PREFIX.txt.
"""
import argparse
import math
import os
import subprocess
import sys
import time

PERTURB = "&initial kind = 'given', node = 13, dof = 'w', velocity = %.6e /"
QUANTITIES = [('wn', 'normal work rate [W]'), ('wf', 'friction work rate [W]'),
              ('impact_rate', 'impact rate [1/s]'), ('slide', 'sliding distance [m]'),
              ('peak', 'peak force of a record [N]')]


def read_batches(text):
    """The `batch=j` lines of a bench output as a list of dicts (numbers as floats)."""
    rows = []
    for line in text.splitlines():
        if not line.startswith('batch='):
            continue
        row = {}
        for item in line.split():
            k, v = item.split('=', 1)
            row[k] = float(v)
        rows.append(row)
    return rows


def mean_se(x):
    n = len(x)
    m = sum(x) / n
    if n < 2:
        return m, float('nan')
    var = sum((xi - m) ** 2 for xi in x) / (n - 1)
    return m, math.sqrt(var / n)


def run_variant(args, kind, cutoff, tol, start, tag):
    env = dict(os.environ, OMP_NUM_THREADS='1', GAPBEAM_BENCH_BATCHES=str(args.batches))
    env.pop('GAPBEAM_BENCH_OVERRIDE', None)
    if start > 1:
        env['GAPBEAM_BENCH_OVERRIDE'] = PERTURB % (1.0e-3 * (start - 1))
    cmd = [args.bench, args.deck, kind, repr(cutoff), repr(tol), str(args.transient),
           str(args.record)]
    lock = os.environ.get('BENCH_LOCK')
    if lock:
        cmd = ['flock', lock] + cmd
    t0 = time.time()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    sys.stderr.write('bench_tubes_batches: %s %g Hz %g, start %d: %.0f s wall\n'
                     % (kind, cutoff, tol, start, time.time() - t0))
    if args.save:
        os.makedirs(args.save, exist_ok=True)
        with open(os.path.join(args.save, '%s_s%d.txt' % (tag, start)), 'w') as f:
            f.write(out)
    return out


def distinct_starts(name, groups):
    """Exit when two starts of a variant gave the same batches (a repeated trajectory would
    count as independent and shrink the standard errors)."""
    seen = {}
    for f, rows in groups:
        key = tuple(sorted((k, v) for k, v in rows[0].items() if k != 'cpu_s')) if rows \
            else ()
        if key in seen:
            sys.exit('bench_tubes_batches: %s: %s repeats the batches of %s' % (name, f,
                                                                                 seen[key]))
        seen[key] = f


def supports(rows):
    k = 1
    while ('wn_%d' % k) in rows[0]:
        k += 1
    return k - 1


def verdict(d, se):
    if abs(d) + 2.0 * se <= 0.02:
        return 'met'
    if abs(d) - 2.0 * se > 0.02:
        return 'missed'
    return 'undecided'


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('bench')
    p.add_argument('--out', default='bench_results/tubes_batches')
    p.add_argument('--batches', type=int, default=40)
    p.add_argument('--starts', type=int, default=2)
    p.add_argument('--record', type=int, default=20)
    p.add_argument('--transient', type=int, default=10)
    p.add_argument('--deck', default='inputs/tube_multispan.nml')
    p.add_argument('--tolerance', type=float, default=1.0e-4)
    p.add_argument('--cutoffs', default='1500,3000')
    p.add_argument('--first-start', type=int, default=1)
    p.add_argument('--save', default='')
    p.add_argument('--from', dest='from_files', nargs='+', default=None)
    args = p.parse_args()
    if not 1 <= args.first_start <= args.starts:
        sys.exit('bench_tubes_batches: --first-start %d: must be 1 .. --starts (%d)'
                 % (args.first_start, args.starts))
    cutoffs = [float(c) for c in args.cutoffs.split(',') if c]
    variants = [('none', 0.0, args.tolerance), ('auto', 0.0, args.tolerance),
                ('auto', 0.0, args.tolerance / 10.0)] + [('modal', c, args.tolerance)
                                                         for c in cutoffs]
    names = ['full model (kind none), %g' % args.tolerance,
             'reduced (kind auto, as shipped), %g' % args.tolerance,
             'reduced (kind auto), %g' % (args.tolerance / 10.0)] + [
                 'reduced (cut-off %g Hz), %g' % (c, args.tolerance) for c in cutoffs]
    tags = ['as shipped', '10x tighter'] + ['%g Hz' % c for c in cutoffs]
    files = ['full', 'auto', 'auto_tight'] + ['cut%g' % c for c in cutoffs]
    if args.from_files:
        if len(args.from_files) != len(variants):
            sys.exit('bench_tubes_batches: --from takes %d lists of files' % len(variants))
        groups = [[(f, read_batches(open(f).read())) for f in group.split(',')]
                  for group in args.from_files]
    else:
        groups = [[('start %d' % j, read_batches(run_variant(args, kind, cut, tol, j, tag)))
                   for j in range(args.first_start, args.starts + 1)]
                  for (kind, cut, tol), tag in zip(variants, files)]
    for name, g in zip(names, groups):
        distinct_starts(name, g)
    runs = [sum((rows for _, rows in g), []) for g in groups]
    for name, rows in zip(names, runs):
        if len(rows) < 2:
            sys.exit('bench_tubes_batches: %s: fewer than two batches' % name)
    ns = supports(runs[0])
    out = ['# The tube deck (%s) as batch means: %d records of %d periods after %d, each from '
           'the end state of the one before, over the starts' % (args.deck, len(runs[0]),
                                                                 args.record, args.transient),
           '# (scripts/bench_tubes_batches.py; mean +- one standard error over the batches; '
           'difference from the full model with two standard errors; verdict against 2 %)', '']
    for name, rows in zip(names, runs):
        cpu = sum(r['cpu_s'] for r in rows)
        out.append('%-40s %3d batches, %8.2f s cpu, full over it %6.1f' % (
            name, len(rows), cpu, sum(r['cpu_s'] for r in runs[0]) / cpu))
    out.append('')
    for s in range(1, ns + 1):
        out.append('== support %d' % s)
        for q, label in QUANTITIES:
            key = '%s_%d' % (q, s)
            vals = [mean_se([r[key] for r in rows]) for rows in runs]
            mf, sf = vals[0]
            if mf == 0.0:
                out.append('  %-28s never touched by the full model' % label)
                continue
            out.append('  %-28s full %.5e +- %.1f %%' % (label, mf, 100.0 * sf / abs(mf)))
            for (m, se), tag in zip(vals[1:], tags):
                d = (m - mf) / mf
                sd = math.hypot(se, sf * m / mf) / abs(mf)
                out.append('    %-14s %+6.2f %% +- %.2f %% (2 SE)  %s' % (
                    tag, 100.0 * d, 200.0 * sd, verdict(d, sd)))
    text = '\n'.join(out) + '\n'
    os.makedirs(os.path.dirname(args.out) or '.', exist_ok=True)
    with open(args.out + '.txt', 'w') as f:
        f.write(text)
    sys.stdout.write(text)


if __name__ == '__main__':
    main()
