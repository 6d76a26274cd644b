#!/usr/bin/env python3
"""Model-size ladder: cost and accuracy of gapbeam's methods against the number of elements.

For each element count the deck (default inputs/moon_shaw_10p5hz.nml: 10.5 Hz, 3.7 mm p-p,
the stop at the tip) is run as a transient from rest over a few forcing periods with every
sample kept, once per method:

  exact    the exact event-driven integrator (what method = 'auto', the default, runs for a
           piecewise-linear stop), the reference;
  newmark  Newmark with error control at the ladder's tolerance (what 'auto' runs for a
           Hertz stop).

and the table gives, per run: steps per forcing period (linear segments for exact), CPU seconds
per simulated second (gapbeam's /run/cpu_seconds, the CPU time of the time loop), the set-up
CPU seconds (/run/setup_seconds: calibration, assembly, eigen-solutions), and the output error
against the exact run of the same model: the largest error over the history of the root
strain, its rate and the tip displacement, relative to their ranges (the work-precision
study's output error).  The exact run is checked in turn against a tight Newmark run
(tolerance --check-tolerance) where that is affordable (--check-up-to elements: 15 by default;
at 30 and 60 elements the Newmark check alone takes minutes, and test_exact compares the exact
integrator there with converged RK4 references instead).

Usage:
  model_size_ladder.py GAPBEAM [--deck DECK] [--elements 4 15 30 60 120 240 480]
                       [--periods 5] [--tolerance 1e-4] [--check-tolerance 1e-8]
                       [--check-up-to 15] [--out bench_results/model_size_ladder]

Writes OUT.txt (the table, also on stdout) and OUT.dat (gnuplot-ready columns); runs go to
OUT_runs/.  Exit status 1 when a run fails (the table marks it and the rest still run).
"""

import argparse
import os
import subprocess
import sys

import h5py
import numpy as np


def run(exe, deck, prefix, overrides):
    """Run gapbeam on DECK with OVERRIDES; return the h5 path or None (and the message)."""
    args = [exe, deck] + list(overrides) + ["&job output = '%s' /" % prefix]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        lines = (p.stderr.strip() or p.stdout.strip()).splitlines()
        return None, (lines[-1] if lines else 'exit %d' % p.returncode)
    return prefix + '.h5', ''


def load(path):
    with h5py.File(path, 'r') as f:
        out = {k: f['/history/' + k][()] for k in ('strain', 'strain_rate', 'tip_displacement')}
        for k in ('steps_accepted', 'cpu_seconds', 'setup_seconds', 'wall_seconds'):
            out[k] = float(f['/run/' + k][()]) if '/run/' + k in f else float('nan')
        out['omega'] = float(f['/model/forcing_omega'][()])
    return out


def output_error(r, ref):
    e = 0.0
    for k in ('strain', 'strain_rate', 'tip_displacement'):
        span = np.ptp(ref[k])
        e = max(e, float(np.max(np.abs(r[k] - ref[k])) / span))
    return e


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('gapbeam')
    ap.add_argument('--deck', default='inputs/moon_shaw_10p5hz.nml')
    ap.add_argument('--elements', type=int, nargs='+', default=[4, 15, 30, 60, 120, 240, 480])
    ap.add_argument('--periods', type=int, default=5)
    ap.add_argument('--tolerance', type=float, default=1e-4)
    ap.add_argument('--check-tolerance', type=float, default=1e-8)
    ap.add_argument('--check-up-to', type=int, default=15)
    ap.add_argument('--out', default='bench_results/model_size_ladder')
    a = ap.parse_args()

    rundir = a.out + '_runs'
    os.makedirs(rundir, exist_ok=True)
    common = ['&solver transient_periods = 0, record_periods = %d /' % a.periods,
              '&output history_periods = %d, samples_per_period = 64 /' % a.periods,
              '&diagnostics lyapunov_periods = 0 /']
    header = ('%5s  %-8s %12s %14s %12s %12s  %s' % ('elem', 'method', 'steps/period',
              'cpu/sim-s [s]', 'setup [s]', 'out. error', 'note'))
    lines = ['model-size ladder: %s, %d forcing periods from rest; newmark at tolerance %g; '
             'error: output error against the exact run of the same model' %
             (a.deck, a.periods, a.tolerance), header]
    rows = []
    failed = False
    print('\n'.join(lines), flush=True)
    for n in a.elements:
        model = ['&beam n_elem = %d / &stops node = %d /' % (n, n + 1)]
        res = {}
        for name, ov in (('exact', "&solver method = 'exact' /"),
                         ('newmark', "&solver method = 'newmark', step_control = 'error', "
                                     "tolerance = %g /" % a.tolerance)):
            h5, msg = run(a.gapbeam, a.deck, '%s/%s_%d' % (rundir, name, n), common + model + [ov])
            res[name] = (load(h5) if h5 else None, msg)
        if n <= a.check_up_to:
            h5, msg = run(a.gapbeam, a.deck, '%s/check_%d' % (rundir, n), common + model +
                          ["&solver method = 'newmark', step_control = 'error', tolerance = %g /"
                           % a.check_tolerance])
            res['check'] = (load(h5) if h5 else None, msg)
        ref = res['exact'][0]
        for name in ('exact', 'newmark'):
            r, msg = res[name]
            if r is None:
                failed = True
                line = '%5d  %-8s %12s %14s %12s %12s  failed: %s' % (n, name, '-', '-', '-', '-',
                                                                      msg)
                rows.append((n, name, np.nan, np.nan, np.nan, np.nan))
            else:
                sim = a.periods * 2 * np.pi / r['omega']
                if name == 'exact':
                    chk = res.get('check', (None, ''))[0]
                    err = output_error(r, chk) if chk is not None else float('nan')
                    note = ('error against newmark at tolerance %g' % a.check_tolerance
                            if chk is not None else 'reference')
                else:
                    err = output_error(r, ref) if ref is not None else float('nan')
                    note = ''
                steps = r['steps_accepted'] / a.periods
                line = '%5d  %-8s %12.0f %14.4g %12.3g %12.3g  %s' % (
                    n, name, steps, r['cpu_seconds'] / sim, r['setup_seconds'], err, note)
                rows.append((n, name, steps, r['cpu_seconds'] / sim, r['setup_seconds'], err))
            lines.append(line)
            print(line, flush=True)
    with open(a.out + '.txt', 'w') as f:
        f.write('\n'.join(lines) + '\n')
    with open(a.out + '.dat', 'w') as f:
        f.write('# elements method(0 exact, 1 newmark) steps_per_period cpu_per_simulated_s '
                'setup_s output_error\n')
        for n, name, s, c, su, e in rows:
            f.write('%d %d %.6g %.6g %.6g %.6g\n' % (n, 0 if name == 'exact' else 1, s, c, su, e))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
