#!/usr/bin/env python3
"""Modal damping cost: the same model with Rayleigh and with modal damping, side by side.

For each element count the deck (default inputs/moon_shaw_10p5hz.nml, the stop moved to the
tip) runs 5 forcing periods from rest, once per damping and method (best CPU of --repeats runs,
/run/cpu_seconds):

  rayleigh   the deck's Rayleigh damping (C = beta M + gamma K: banded above 60 dofs);
  modal=ray  &damping model = 'modal' with modal_ratios = the deck's Rayleigh ratio of every
             mode, beta/(2 omega_j) + gamma omega_j/2 (from a modes run): the same C, so the
             same steps and results, and the ratio of the CPU times is the price of the dense
             modal form alone;
  modal      one ratio for every mode (--ratio, default 0.0042: the deck's ratio at f1), what
             a user would write: the high modes lightly damped.

Methods: newmark (error control at --tolerance) and exact.

Usage:
  modal_damping_cost.py GAPBEAM [--deck DECK] [--elements 15 30 60 120 240]
                        [--tolerance 1e-4] [--ratio 0.0042] [--repeats 3]
                        [--skip-modal-newmark-above 60] [--out bench_results/modal_damping_cost]

Writes OUT.txt (a markdown table, also on stdout); runs go to OUT_runs/.
"""

import argparse
import math
import os
import subprocess
import sys

import h5py


def run(exe, deck, prefix, overrides):
    args = [exe, deck, '--quiet'] + list(overrides) + ["&job output = '%s' /" % prefix]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        lines = (p.stderr.strip() or p.stdout.strip()).splitlines()
        raise RuntimeError(lines[-1] if lines else 'exit %d' % p.returncode)
    return prefix + '.h5'


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('gapbeam')
    ap.add_argument('--deck', default='inputs/moon_shaw_10p5hz.nml')
    ap.add_argument('--elements', type=int, nargs='+', default=[15, 30, 60, 120, 240])
    ap.add_argument('--tolerance', type=float, default=1e-4)
    ap.add_argument('--ratio', type=float, default=0.0042)
    ap.add_argument('--repeats', type=int, default=3)
    ap.add_argument('--skip-modal-newmark-above', type=int, default=60)
    ap.add_argument('--out', default='bench_results/modal_damping_cost')
    a = ap.parse_args()
    rundir = a.out + '_runs'
    os.makedirs(rundir, exist_ok=True)
    rows = ['| elements | dofs | method | damping | steps | CPU per simulated second [s] | '
            '/ rayleigh | peak force [N] |', '|---|---|---|---|---|---|---|---|']
    for n in a.elements:
        mesh = ['&beam n_elem = %d /' % n, '&stops node = %d /' % (n + 1)]
        h5 = run(a.gapbeam, a.deck, os.path.join(rundir, 'modes_%d' % n),
                 mesh + ["&job analysis = 'modes' /"])
        with h5py.File(h5, 'r') as f:
            freq = f['/modes/frequency_hz'][()]
            beta = float(f['/parameters/damping/mass_coefficient'][()])
            gamma = float(f['/parameters/damping/stiffness_coefficient'][()])
        ray = [beta / (4 * math.pi * fj) + gamma * math.pi * fj for fj in freq]
        variants = {
            'rayleigh': [],
            'modal=ray': ["&damping model = 'modal', mass_coefficient = 0.0, "
                          "stiffness_coefficient = 0.0, modal_ratios = "
                          + ', '.join('%.17g' % z for z in ray) + ' /'],
            'modal': ["&damping model = 'modal', mass_coefficient = 0.0, "
                      "stiffness_coefficient = 0.0, modal_ratios = %g /" % a.ratio],
        }
        for method in ('newmark', 'exact'):
            base = None
            for name, ov in variants.items():
                if (method == 'newmark' and name == 'modal'
                        and n > a.skip_modal_newmark_above):
                    continue
                solver = ["&solver method = '%s', tolerance = %g, transient_periods = 0, "
                          "record_periods = 5 /" % (method, a.tolerance)]
                best = float('inf')
                for r in range(a.repeats):
                    h5 = run(a.gapbeam, a.deck, os.path.join(
                        rundir, '%s_%s_%d' % (method, name.replace('=', '_'), n)),
                        mesh + ov + solver)
                    with h5py.File(h5, 'r') as f:
                        best = min(best, float(f['/run/cpu_seconds'][()]))
                        steps = int(f['/run/steps_accepted'][()])
                        peak = float(f['/impacts/peak_force'][0])
                        ndof = int(f['/parameters/model/n_dof'][()])
                        tsim = 5.0 / float(f['/parameters/forcing/frequency_hz'][()])
                if name == 'rayleigh':
                    base = best
                rows.append('| %d | %d | %s | %s | %d | %.4g | %.2f | %.5g |' % (
                    n, ndof, method, name, steps, best / tsim, best / base, peak))
    text = '\n'.join(rows)
    print(text)
    with open(a.out + '.txt', 'w') as f:
        f.write(text + '\n')
    return 0


if __name__ == '__main__':
    sys.exit(main())
