#!/usr/bin/env python3
"""Impact mesh study: peak impact force and impact work rate against the mesh, Euler-Bernoulli
against Timoshenko beams, for a point impact on a stiff bilinear stop (docs/methods.md).

The beam: a steel cantilever, L = 0.2 m, square section 10 x 10 mm (L/h = 20), E = 200 GPa,
G = E/2.6, k = 5/6, rho = 7850 kg/m3, consistent mass, modal damping 1 % in every mode; a
one-sided bilinear stop at the tip with no gap and stiffness K. Two cases (--case):

  forced  harmonic base motion at 100 Hz (about half the first natural frequency), 1 mm peak
          to peak, from rest; the record is the first two forcing periods (transient_periods =
          0): the first impacts from rest, a deterministic quantity that a mesh can converge
          (no attractor to settle on).
  single  free vibration (amplitude_pp = 0) from the Euler-Bernoulli first mode's velocity
          field (&initial at every node: w' and its slope, the tip moving away from the stop at
          --velocity m/s): the tip comes back and strikes the stop after about half a period;
          the record is 10 ms (one period of &forcing frequency_hz = 100).

The exact integrator runs every case, so the only error is the mesh's. For each theory,
stiffness and mesh the table gives the peak stop force (/impacts/peak_force), the work rate
(1/T) int f |u'| dt over the record (/impacts/work_rate), the contact onsets (/impacts/count)
and the CPU seconds of the run.

Usage:
  impact_mesh_study.py GAPBEAM [--case forced] [--velocity 0.1]
                       [--stiffness 1e8 1e10] [--elements 4 8 16 32 64 128 256]
                       [--timoshenko-elements 4 8 16 32 64 128 256 512]
                       [--mass consistent] [--out bench_results/impact_mesh_study]

Writes OUT.txt (markdown tables, also on stdout); the runs go to OUT_runs/. Exit status 1 when
a run fails (the table marks it and the rest still run).
"""

import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

E = 200.0e9
G = E / 2.6


BETA_L = 1.8751040687119611


def initial_group(n, velocity):
    """&initial: the first cantilever mode's velocity field, the tip at -velocity."""
    x = np.linspace(0.0, 0.2, n + 1)[1:]
    b = BETA_L / 0.2
    sig = (np.cosh(BETA_L) + np.cos(BETA_L)) / (np.sinh(BETA_L) + np.sin(BETA_L))
    phi = np.cosh(b * x) - np.cos(b * x) - sig * (np.sinh(b * x) - np.sin(b * x))
    dphi = b * (np.sinh(b * x) + np.sin(b * x) - sig * (np.cosh(b * x) - np.cos(b * x)))
    scale = -velocity / phi[-1]
    nodes, dofs, vel = [], [], []
    for i in range(n):
        nodes += [i + 2, i + 2]
        dofs += ["'w'", "'theta'"]
        vel += ['%.17g' % (scale * phi[i]), '%.17g' % (scale * dphi[i])]
    return ["&initial kind = 'given',",
            "   node = " + ', '.join(str(j) for j in nodes) + ',',
            "   dof = " + ', '.join(dofs) + ',',
            "   velocity = " + ', '.join(vel) + ' /']


def deck_text(theory, n, k, mass, prefix, case, velocity):
    forcing = "&forcing frequency_hz = 100.0, amplitude_pp = 1.0e-3 /"
    record = 2
    if case == 'single':
        forcing = "&forcing frequency_hz = 100.0, amplitude_pp = 0.0 /"
        record = 1
    lines = [
        "&job analysis = 'transient', output = '%s' /" % prefix,
        "&beam length = 0.2, n_elem = %d, youngs_modulus = %.6e, density = 7850.0," % (n, E),
        "      width = 0.01, thickness = 0.01, mass_matrix = '%s'," % mass,
        "      theory = '%s', shear_modulus = %.8e /" % (theory, G),
        "&root condition = 'clamped' /",
        "&stops node = %d, dof = 'w', side = 'positive', gap = 0.0, law = 'bilinear'," % (n + 1),
        "       stiffness = %.6e /" % k,
        "&damping model = 'modal', modal_ratios = 0.01 /",
        forcing,
        "&solver method = 'exact', transient_periods = 0, record_periods = %d /" % record,
        "&output write_text = .false. /",
    ]
    if case == 'single':
        lines += initial_group(n, velocity)
    return "\n".join(lines) + "\n"


def run(exe, theory, n, k, mass, rundir, case, velocity):
    name = '%s_%s_%s_k%.0e_n%d' % (case, theory, mass, k, n)
    prefix = os.path.join(rundir, name)
    path = prefix + '.nml'
    with open(path, 'w') as f:
        f.write(deck_text(theory, n, k, mass, prefix, case, velocity))
    p = subprocess.run([exe, path, '--quiet'], capture_output=True, text=True)
    if p.returncode != 0:
        lines = (p.stderr.strip() or p.stdout.strip()).splitlines()
        return None, (lines[-1] if lines else 'exit %d' % p.returncode)
    with h5py.File(prefix + '.h5', 'r') as f:
        return {'peak': float(f['/impacts/peak_force'][0]),
                'work': float(f['/impacts/work_rate'][0]),
                'count': int(f['/impacts/count'][0]),
                'cpu': float(f['/run/cpu_seconds'][()])}, ''


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('gapbeam')
    ap.add_argument('--case', choices=['forced', 'single'], default='forced')
    ap.add_argument('--velocity', type=float, default=0.1)
    ap.add_argument('--stiffness', type=float, nargs='+', default=[1e8, 1e10])
    ap.add_argument('--elements', type=int, nargs='+', default=[4, 8, 16, 32, 64, 128, 256])
    ap.add_argument('--timoshenko-elements', type=int, nargs='+',
                    default=[4, 8, 16, 32, 64, 128, 256, 512])
    ap.add_argument('--mass', default='consistent')
    ap.add_argument('--out', default='bench_results/impact_mesh_study')
    a = ap.parse_args()
    rundir = a.out + '_runs'
    os.makedirs(rundir, exist_ok=True)
    failed = False
    out = []
    for k in a.stiffness:
        res = {}
        for theory, meshes in (('euler_bernoulli', a.elements),
                               ('timoshenko', a.timoshenko_elements)):
            for n in meshes:
                r, msg = run(a.gapbeam, theory, n, k, a.mass, rundir, a.case, a.velocity)
                if r is None:
                    failed = True
                    print('failed: %s n=%d k=%g: %s' % (theory, n, k, msg), file=sys.stderr)
                res[(theory, n)] = r
        out.append('%s case, stop stiffness %.0e N/m, %s mass (peak force [N], work rate [W], '
                   'onsets; le/h = 20/n)' % (a.case, k, a.mass))
        out.append('')
        out.append('| elements | le/h | E-B peak | E-B work rate | E-B onsets | T peak | '
                   'T work rate | T onsets | E-B CPU [s] | T CPU [s] |')
        out.append('|---|---|---|---|---|---|---|---|---|---|')
        for n in sorted(set(a.elements) | set(a.timoshenko_elements)):
            cells = ['%d' % n, '%.4g' % (20.0 / n)]
            for theory in ('euler_bernoulli', 'timoshenko'):
                r = res.get((theory, n))
                if r is None:
                    cells += ['–', '–', '–']
                else:
                    cells += ['%.5g' % r['peak'], '%.5g' % r['work'], '%d' % r['count']]
            for theory in ('euler_bernoulli', 'timoshenko'):
                r = res.get((theory, n))
                cells.append('–' if r is None else '%.3g' % r['cpu'])
            out.append('| ' + ' | '.join(cells) + ' |')
        out.append('')
    text = '\n'.join(out)
    print(text)
    with open(a.out + '.txt', 'w') as f:
        f.write(text + '\n')
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
