#!/usr/bin/env python3
"""Wear-output error against CPU (scripts/bench_wear.sh runs it; docs/tubes.md).

For every deck, every method and every tolerance: one serial run of gapbeam (release build),
its wear outputs per support (normal work rate, friction work rate, sliding distance) and its
record's CPU (/run/cpu_seconds) per simulated second; the errors against one converged run of the
same deck (--reference METHOD:TOLERANCE). A method that refuses the deck is listed as refused.
Writes PREFIX.txt (tables) and PREFIX.dat (one line per run and support, for the chart).

The comparison is meaningful only where the runs follow the same trajectory over the record:
each line states the impacts of the run and of the reference, and the table marks a run whose
impact count differs (a chaotic record: compare means over long records instead).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

OUTPUTS = [('normal_work_rate', 'W_N'), ('friction_work_rate', 'W_f'),
           ('sliding_distance', 's')]


def run(gapbeam, deck, method, tol, extra, workdir, lock):
    """One run; returns a dict of its figures, or a dict with 'refused'."""
    tag = f"{os.path.splitext(os.path.basename(deck))[0]}_{method}_{tol}"
    out = os.path.join(workdir, tag)
    cmd = lock + [gapbeam, deck, f"&solver method = '{method}', tolerance = {tol} /",
                  "&diagnostics certify = .false. /", f"&job output = '{out}' /"] + extra
    proc = subprocess.run(cmd, capture_output=True, text=True, env=dict(
        os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1'))
    if proc.returncode != 0:
        msg = (proc.stderr.strip() or proc.stdout.strip()).splitlines()
        return {'refused': msg[-1] if msg else f'exit {proc.returncode}'}
    with h5py.File(out + '.h5', 'r') as f:
        period = float(f['parameters/forcing/period'][()])
        t_rec = float(f['final/time'][()]) - int(f['diagnostics/transient_periods'][()]) * period
        res = {'cpu': float(f['run/cpu_seconds'][()]), 'sim': t_rec,
               'steps': int(f['run/steps_accepted'][()]),
               'method': f['run/method'][()].decode(),
               'transient': int(f['diagnostics/transient_periods'][()]),
               'impacts': np.array(f['impacts/count'][()])}
        for name, _ in OUTPUTS:
            res[name] = np.array(f['wear/' + name][()], dtype=float)
    for ext in ('.h5', '.history.dat', '.poincare.dat', '.orbit.dat', '.supports.dat'):
        if os.path.exists(out + ext):
            os.remove(out + ext)
    return res


def rel(a, b):
    return abs(a - b) / abs(b) if b != 0.0 else (0.0 if a == 0.0 else float('inf'))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('gapbeam')
    ap.add_argument('--decks', default='test/decks/tube_cantilever.nml')
    ap.add_argument('--methods', default='newmark rk45')
    ap.add_argument('--tolerances', default='1e-3 1e-4 1e-5 1e-6 1e-7')
    ap.add_argument('--reference', default='newmark:1e-8')
    ap.add_argument('--override', action='append', default=[],
                    help='a namelist fragment given to every run')
    ap.add_argument('--lock', default='', help='run every case under flock FILE')
    ap.add_argument('--out', default='bench_results/wear_error')
    a = ap.parse_args()
    lock = ['flock', a.lock] if a.lock else []
    ref_method, ref_tol = a.reference.split(':')
    txt, dat = [], ['# deck method tolerance stop cpu_s cpu_per_sim_s steps impacts '
                    'ref_impacts err_WN err_Wf err_s WN Wf s']
    txt.append('Wear-output error against CPU (scripts/bench_wear.sh; release build, serial, '
               'OMP_NUM_THREADS=1)')
    txt.append(f"reference: method {ref_method} at tolerance {ref_tol}; overrides: "
               f"{' '.join(a.override) or 'none'}")
    with tempfile.TemporaryDirectory() as work:
        for deck in a.decks.split():
            dtag = os.path.splitext(os.path.basename(deck))[0]
            ref = run(a.gapbeam, deck, ref_method, ref_tol, a.override, work, lock)
            if 'refused' in ref:
                sys.exit(f"bench_wear: the reference run of {deck} failed: {ref['refused']}")
            txt.append('')
            txt.append(f"{deck}: record {ref['sim']:.4g} s after {ref['transient']} transient "
                       f"periods; reference ({ref['method']}, {ref_tol}) "
                       f"{ref['cpu']:.3f} s CPU, {ref['steps']} steps")
            for k in range(len(ref['impacts'])):
                txt.append(f"  support {k + 1}: {ref['impacts'][k]} impacts, W_N "
                           f"{ref['normal_work_rate'][k]:.7e} W, W_f "
                           f"{ref['friction_work_rate'][k]:.7e} W, sliding "
                           f"{ref['sliding_distance'][k]:.7e} m")
            txt.append('  method     tol    CPU/sim s    steps  support impacts  err W_N   '
                       'err W_f   err s     max/tol')
            for method in a.methods.split():
                for tol in a.tolerances.split():
                    r = run(a.gapbeam, deck, method, tol, a.override, work, lock)
                    if 'refused' in r:
                        txt.append(f"  {method:9s} {tol:6s} refused: {r['refused']}")
                        continue
                    for k in range(len(ref['impacts'])):
                        e = [rel(r[n][k], ref[n][k]) for n, _ in OUTPUTS]
                        same = r['impacts'][k] == ref['impacts'][k] and \
                            r['transient'] == ref['transient']
                        txt.append(f"  {method:9s} {tol:6s} {r['cpu'] / r['sim']:10.4g} "
                                   f"{r['steps']:9d}  {k + 1:4d}  {r['impacts'][k]:4d}"
                                   f"{'' if same else '*':1s}  "
                                   + '  '.join(f'{x:8.2e}' for x in e)
                                   + f"  {max(e) / float(tol):7.1f}")
                        dat.append(f"{dtag} {method} {tol} {k + 1} {r['cpu']:.6g} "
                                   f"{r['cpu'] / r['sim']:.6g} {r['steps']} {r['impacts'][k]} "
                                   f"{ref['impacts'][k]} "
                                   + ' '.join(f'{x:.6e}' for x in e) + ' '
                                   + ' '.join(f'{r[n][k]:.10e}' for n, _ in OUTPUTS))
    txt.append('')
    txt.append('* impacts or transient differ from the reference: not the same trajectory')
    with open(a.out + '.txt', 'w') as f:
        f.write('\n'.join(txt) + '\n')
    with open(a.out + '.dat', 'w') as f:
        f.write('\n'.join(dat) + '\n')
    print('\n'.join(txt))


if __name__ == '__main__':
    main()
