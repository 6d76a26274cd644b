#!/usr/bin/env python3
"""Summaries of the labelled tube map (scripts/tube_map_labels.sh): label counts, CPU, per-point
table, and the side-by-side comparison of two labelled runs of one row.

Usage:
  tube_map_labels.py counts RESULT.h5 [RESULT.h5 ...]   label counts and CPU of sweep files
  tube_map_labels.py points RESULT.h5                    one line per point
  tube_map_labels.py compare A.h5 B.h5                   the same points of two sweeps: labels
                                                         and exponents, difference / combined sigma
  tube_map_labels.py chaotic RESULT.h5                   'frequency gap' of every chaotic point
  tube_map_labels.py persist TRANSIENT.h5 [...]          label of transient runs (persistence)
"""
import sys
from collections import Counter

import h5py
import numpy as np


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def sweep(fn):
    f = h5py.File(fn, 'r')
    s = f['sweep']
    d = {k: s[k][()] for k in ('frequency_hz', 'y', 'label', 'period', 'lyapunov',
                                'lyapunov_error', 'lyapunov_periods', 'transient_periods',
                                'closest_period', 'repeat_distance', 'certificate',
                                'seconds', 'seconds_label')}
    d['label_text'] = [text(x) for x in s['label_text'][()]]
    d['contact'] = s['impacts/contact_fraction'][()].max(axis=1)
    d['cpu'] = float(f['run/cpu_seconds'][()])
    d['wall'] = float(f['run/wall_seconds'][()])
    d['n'] = len(d['label'])
    return d


def count_line(d):
    c = Counter()
    for lab, per in zip(d['label'], d['period']):
        lab = int(lab)
        if lab >= 1:
            c['period %d' % lab] += 1
        else:
            c[{0: 'undecided', -1: 'chaotic', -2: 'unsettled', -3: 'failed'}.get(lab, 'other')] += 1
    keys = sorted([k for k in c if k.startswith('period')], key=lambda k: int(k.split()[1]))
    keys += [k for k in ('chaotic', 'undecided', 'unsettled', 'failed', 'other') if k in c]
    periodic = sum(c[k] for k in c if k.startswith('period'))
    disputed = int(np.sum(d['certificate'] == 2))
    return ('%d points: ' % d['n'] + ', '.join('%s: %d' % (k, c[k]) for k in keys)
            + ' (periodic %d); disputed %d; cpu %.1f s (all threads), wall %.1f s'
            % (periodic, disputed, d['cpu'], d['wall']))


def point_line(d, i):
    return ('%6.2f Hz %6.3f mm  %-10s lambda %+7.3f +- %6.3f 1/s over %3d periods, %4d before '
            'the record, closest period %d at %.2e, contact %.3f, %.1f s cpu'
            % (d['frequency_hz'][i], 1e3 * d['y'][i], d['label_text'][i], d['lyapunov'][i],
               d['lyapunov_error'][i], d['lyapunov_periods'][i], d['transient_periods'][i],
               d['closest_period'][i], d['repeat_distance'][i], d['contact'][i],
               d['seconds'][i]))


def compare(a, b):
    same = 0
    out = []
    z = []
    for i in range(a['n']):
        j = [k for k in range(b['n']) if abs(b['frequency_hz'][k] - a['frequency_hz'][i]) < 1e-9
             and abs(b['y'][k] - a['y'][i]) < 1e-12]
        if not j:
            continue
        j = j[0]
        s = np.hypot(a['lyapunov_error'][i], b['lyapunov_error'][j])
        dz = abs(a['lyapunov'][i] - b['lyapunov'][j]) / s if s > 0 else np.inf
        z.append(dz)
        agree = a['label_text'][i] == b['label_text'][j]
        same += agree
        out.append('%6.2f Hz %6.3f mm  %-10s %+7.3f +- %5.3f | %-10s %+7.3f +- %5.3f | %4.1f sigma%s'
                   % (a['frequency_hz'][i], 1e3 * a['y'][i], a['label_text'][i], a['lyapunov'][i],
                      a['lyapunov_error'][i], b['label_text'][j], b['lyapunov'][j],
                      b['lyapunov_error'][j], dz, '' if agree else '  (labels differ)'))
    z = np.array(z)
    out.append('labels equal at %d of %d points; exponents within 1 / 2 / 3 combined sigma at '
               '%d / %d / %d; cpu %.1f s against %.1f s (ratio %.2f)'
               % (same, len(z), np.sum(z <= 1), np.sum(z <= 2), np.sum(z <= 3), a['cpu'],
                  b['cpu'], b['cpu'] / a['cpu']))
    return out


def persist(fn):
    f = h5py.File(fn, 'r')
    g = f['diagnostics']
    return ('%s: %s, lambda %+.3f +- %.3f 1/s over %d periods after %d periods, closest period '
            '%d at %.2e; %.1f s cpu for the label'
            % (fn, text(g['label_text'][()]), g['lyapunov'][()], g['lyapunov_error'][()],
               g['lyapunov_periods'][()], g['transient_periods'][()], g['closest_period'][()],
               g['repeat_distance'][()], float(g['seconds_label'][()])))


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    what, files = argv[1], argv[2:]
    if what == 'counts':
        for fn in files:
            print('%s: %s' % (fn, count_line(sweep(fn))))
    elif what == 'points':
        d = sweep(files[0])
        for i in range(d['n']):
            print(point_line(d, i))
    elif what == 'compare':
        print('\n'.join(compare(sweep(files[0]), sweep(files[1]))))
    elif what == 'chaotic':
        d = sweep(files[0])
        for i in range(d['n']):
            if d['label'][i] == -1:
                print('%.10g %.10g' % (d['frequency_hz'][i], d['y'][i]))
    elif what == 'persist':
        for fn in files:
            print(persist(fn))
    else:
        print(__doc__)
        return 2
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
