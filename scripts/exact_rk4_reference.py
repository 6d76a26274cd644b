#!/usr/bin/env python3
"""Converged RK4 references for the exact integrator's tests at 30 and 60 elements.

RK4 with fixed steps needs T/2^17 (30 elements) and T/2^21 (60 elements) for stability alone:
the Rayleigh damping of the reference deck makes the high modes overdamped, with real
eigenvalues down to -gamma omega_max^2. Such runs take minutes in a release build and hours in
the debug build the test suite uses, so they are run here once and their final states stored
in test/data/; test_exact compares the exact integrator with them.

For each model the deck (inputs/moon_shaw_10p5hz.nml, 2 forcing periods from rest, the stop at
the tip) is run with method 'rk4', step_control 'fixed' at T/2^k for the given k (at least
two, each half the step of the one before); the header of the file records the energy-norm
differences between consecutive step sizes (the convergence check by halving), and the body
the final time, u and v of the finest run.

Usage:
  exact_rk4_reference.py GAPBEAM [--elements 30 --levels 17 18 19]
                         [--periods 2] [--out test/data/exact_rk4_30.txt]
"""

import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('gapbeam')
    ap.add_argument('--deck', default='inputs/moon_shaw_10p5hz.nml')
    ap.add_argument('--elements', type=int, default=30)
    ap.add_argument('--levels', type=int, nargs='+', default=[17, 18, 19])
    ap.add_argument('--periods', type=int, default=2)
    ap.add_argument('--out', default=None)
    a = ap.parse_args()
    out = a.out or 'test/data/exact_rk4_%d.txt' % a.elements
    n = a.elements
    common = ['&beam n_elem = %d / &stops node = %d /' % (n, n + 1),
              '&solver transient_periods = 0, record_periods = %d /' % a.periods,
              '&diagnostics lyapunov_periods = 0 /']
    finals = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in a.levels:
            prefix = os.path.join(tmp, 'rk4_%d' % k)
            ov = common + ["&solver method = 'rk4', step_control = 'fixed', "
                           "steps_per_period = %d /" % 2**k, "&job output = '%s' /" % prefix]
            p = subprocess.run([a.gapbeam, a.deck] + ov, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit('rk4 at T/2^%d failed: %s' % (k, p.stderr.strip() or p.stdout.strip()))
            with h5py.File(prefix + '.h5', 'r') as f:
                finals.append(dict(k=k, t=float(f['/final/time'][()]), u=f['/final/u'][()],
                                   v=f['/final/v'][()], K=f['/model/stiffness'][()],
                                   M=f['/model/mass'][()],
                                   impacts=int(np.sum(f['/statistics/n_impacts'][()]))
                                   if '/statistics/n_impacts' in f else -1))
            print('T/2^%d done' % k, flush=True)
    K, M = finals[-1]['K'], finals[-1]['M']

    def enorm(u, v):
        return np.sqrt(max(0.0, u @ K @ u + v @ M @ v))

    ref = finals[-1]
    scale = enorm(ref['u'], ref['v'])
    lines = ['# RK4 reference for test_exact (scripts/exact_rk4_reference.py): %s' % a.deck,
             '# overrides: ' + ' '.join(common),
             '# method rk4, step_control fixed, steps_per_period 2^k for k = '
             + ' '.join(str(f['k']) for f in finals)]
    for f0, f1 in zip(finals[:-1], finals[1:]):
        d = enorm(f0['u'] - f1['u'], f0['v'] - f1['v']) / scale
        lines.append('# energy-norm difference T/2^%d - T/2^%d: %.3e' % (f0['k'], f1['k'], d))
    lines.append('# below: final time, then u and v of the finest run, one dof per line')
    lines.append('%d %.17e' % (ref['u'].size, ref['t']))
    for ui, vi in zip(ref['u'], ref['v']):
        lines.append('%.17e %.17e' % (ui, vi))
    os.makedirs(os.path.dirname(out) or '.', exist_ok=True)
    with open(out, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines[:3 + len(finals)]))
    return 0


if __name__ == '__main__':
    sys.exit(main())
