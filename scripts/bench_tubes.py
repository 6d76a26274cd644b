#!/usr/bin/env python3
"""Full against reduced tube models, side by side (run by scripts/bench_tubes.sh).

Usage:
    python3 scripts/bench_tubes.py BENCH_EXE GAPBEAM_EXE [--out PREFIX] [--parts deck,periodic,map]

BENCH_EXE is the release build of the gapbeam_bench_tubes example (one variant of a deck per
call, one line of key=value fields); GAPBEAM_EXE the release gapbeam (the map runs through it,
as a user runs it). Every run is serial (OMP_NUM_THREADS=1 for the transient variants; the map
runs with the deck's own threads, both maps alike) and, when BENCH_LOCK names a lock file,
holds it while it runs (flock), so that nothing else shares the CPU.

Parts:
  deck      inputs/tube_multispan.nml as shipped (8 Hz, 0.2 mm; the default &reduction kind =
            'auto') over its own 30 transient + 40 recorded periods (BENCH_TUBES_TRANSIENT,
            BENCH_TUBES_RECORD): the full model and the default (reduced) run at the deck's
            tolerance 1e-4, side by side; the full model at 1e-3, 1e-5 and 1e-6 (its own spread:
            the response is not periodic, so record averages of two runs that differ in
            anything part); reduced models at several cut-offs and the 'auto' basis at
            tolerances 1e-3 .. 1e-6; where the steps go (steps with every support open and
            with a support in contact, for the full and the default reduced model, 2 + 4
            periods). (The 'auto' basis at 1e-6 is the full model: its cut-off is above every
            mode.)
  periodic  the same tube at 7 Hz with 0.05 mm clearances (a period-1 sliding orbit with six
            impacts per period at each baffle), 15 + 20 periods: the truncation error of the
            basis without the statistical spread of a chaotic record (cut-offs at tolerance
            1e-5 against the full model at 1e-6), and the same tolerance ladder; the
            exponential integrator on the 'auto' basis at 1e-3 .. 1e-6 and on the full model
            at 1e-4 (BENCH_TUBES_PERIODIC_QUICK=1: these, the reference and the full and
            default models at 1e-4 only).
  map       inputs/tube_map.nml (45 points) with the full model and as shipped (reduced), the
            reduced model under rk45 and under the exponential integrator: CPU
            (/run/cpu_seconds) and the contact class of every point: per baffle no contact,
            impacting (in contact less than half the time) or sustained contact, and sticking
            or sliding (the share of the normal work done while slipping, W_f / (mu W_N), below
            or above one half). BENCH_TUBES_MAP, a namelist fragment read after the map deck
            (for example '&sweep n_frequency = 5, n_y = 3 /'), runs a subset of its points.

Results go to PREFIX.txt (the tables), PREFIX.dat (one line per run, for the chart) and
PREFIX.png (scripts/tubes_reduction.gp: work-rate error against CPU per simulated second).
Runs are cached in PREFIX.cache/ by a key of the deck text, the variant and the executables'
contents: a second call re-runs only what changed (BENCH_TUBES_FRESH=1 runs everything again).
"""
import hashlib
import json
import os
import subprocess
import sys
import time

DECK = 'inputs/tube_multispan.nml'
RK45 = "&solver method = 'rk45' /"
EXP = "&solver method = 'exponential' /"
# Newmark on a reduced model (method 'auto' runs the exponential integrator there)
NEWMARK = "&solver method = 'newmark' /"
MAP = 'inputs/tube_map.nml'
PERIODIC = '&forcing frequency_hz = 7.0 / &stops gap = 0.05e-3, 0.05e-3 /'


def file_hash(path):
    h = hashlib.sha256()
    with open(path, 'rb') as f:
        h.update(f.read())
    return h.hexdigest()


class Runner:
    def __init__(self, bench, gapbeam, prefix):
        self.bench = bench
        self.gapbeam = gapbeam
        self.prefix = prefix
        self.cache = prefix + '.cache'
        os.makedirs(self.cache, exist_ok=True)
        self.exe_key = file_hash(bench) + file_hash(gapbeam)
        self.lock = os.environ.get('BENCH_LOCK', '')
        self.fresh = os.environ.get('BENCH_TUBES_FRESH', '0') == '1'

    def locked(self, cmd):
        return (['flock', self.lock] if self.lock else []) + cmd

    def variant(self, kind, cutoff, tol, transient, record, override='', profile=False):
        """One variant of the tube deck: the bench line as a dict (cached)."""
        args = [DECK, kind, repr(float(cutoff)), repr(float(tol)), str(transient), str(record)]
        if profile:
            args.append('profile')
        key = hashlib.sha256(json.dumps([self.exe_key, file_hash(DECK), args, override])
                             .encode()).hexdigest()[:24]
        path = os.path.join(self.cache, key + '.json')
        if os.path.exists(path) and not self.fresh:
            with open(path) as f:
                return json.load(f)
        env = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
        if override:
            env['GAPBEAM_BENCH_OVERRIDE'] = override
        else:
            env.pop('GAPBEAM_BENCH_OVERRIDE', None)
        t0 = time.time()
        out = subprocess.run(self.locked([self.bench] + args), env=env, check=True,
                             capture_output=True, text=True).stdout
        line = [x for x in out.splitlines() if x.startswith('kind=')][-1]
        fields = {}
        for item in line.split():
            k, v = item.split('=', 1)
            try:
                fields[k] = float(v)
            except ValueError:
                fields[k] = v
        fields['args'] = ' '.join(args[1:])
        fields['override'] = override
        sys.stderr.write('bench_tubes: %-44s %8.1f s cpu (%.0f s wall)\n'
                         % (' '.join(args[1:]) + (' [%s]' % override if override else ''),
                            fields['cpu_s'], time.time() - t0))
        with open(path, 'w') as f:
            json.dump(fields, f)
        return fields

    def map_run(self, kind, extra=''):
        """The map deck through gapbeam with &reduction kind = KIND: per point (x, y) the
        sweep's wear datasets, and the run's CPU."""
        import h5py
        import numpy as np
        out = os.path.join(self.cache, 'map_' + kind + ('_x' if extra else ''))
        subset = os.environ.get('BENCH_TUBES_MAP', '')
        key = hashlib.sha256(json.dumps([self.exe_key, file_hash(MAP), kind] + (
            [subset] if subset else []) + ([extra] if extra else [])).encode()) \
            .hexdigest()[:24]
        path = os.path.join(self.cache, 'map_%s_%s.json' % (kind, key))
        if os.path.exists(path) and not self.fresh:
            with open(path) as f:
                return json.load(f)
        cmd = self.locked([self.gapbeam, MAP, "&job output = '%s' /" % out,
                           "&reduction kind = '%s' /" % kind] + ([subset] if subset else [])
                          + ([extra] if extra else [])
                          + ['--quiet'])
        t0 = time.time()
        subprocess.run(cmd, check=True, capture_output=True, text=True)
        with h5py.File(out + '.h5', 'r') as h:
            r = {'cpu_s': float(np.asarray(h['/run/cpu_seconds'])),
                 'wall_s': float(np.asarray(h['/run/wall_seconds'])),
                 'x': np.asarray(h['/sweep/x']).tolist(),
                 'y': np.asarray(h['/sweep/y']).tolist()}
            for name in ('normal_work_rate', 'friction_work_rate', 'sliding_distance'):
                r[name] = np.asarray(h['/sweep/wear/' + name]).tolist()
            for name in ('contact_fraction', 'count', 'peak_force'):
                r[name] = np.asarray(h['/sweep/impacts/' + name]).tolist()
        sys.stderr.write('bench_tubes: map %-8s %8.1f s cpu (%.0f s wall)\n'
                         % (kind, r['cpu_s'], time.time() - t0))
        with open(path, 'w') as f:
            json.dump(r, f)
        return r


def rel(a, b):
    if a == b:
        return 0.0
    return (a - b) / max(abs(b), 1e-300)


def wear_errors(run, ref):
    """Largest relative differences over the supports: normal and friction work rate, impact
    rate, peak force (supports the reference never touches are skipped)."""
    e = {'wn': 0.0, 'wf': 0.0, 'impacts': 0.0, 'peak': 0.0}
    k = 1
    while ('wn_%d' % k) in ref:
        if ref['wn_%d' % k] > 0.0:
            e['wn'] = max(e['wn'], abs(rel(run['wn_%d' % k], ref['wn_%d' % k])))
            e['wf'] = max(e['wf'], abs(rel(run['wf_%d' % k], ref['wf_%d' % k])))
            e['impacts'] = max(e['impacts'], abs(rel(run['impact_rate_%d' % k],
                                                     ref['impact_rate_%d' % k])))
            e['peak'] = max(e['peak'], abs(rel(run['peak_%d' % k], ref['peak_%d' % k])))
        k += 1
    return e


def support_table(rows, names):
    """Per support: impacts, peak force, normal and friction work rates of each run."""
    lines = []
    k = 1
    while ('wn_%d' % k) in rows[0]:
        lines.append('  support %d' % k)
        lines.append('    %-34s %9s %12s %12s %12s %12s' % ('run', 'impacts', 'impact rate',
                     'peak [N]', 'W_N [W]', 'W_f [W]'))
        for r, n in zip(rows, names):
            lines.append('    %-34s %9d %12.4g %12.5g %12.5g %12.5g' % (
                n, r['impacts_%d' % k], r['impact_rate_%d' % k], r['peak_%d' % k],
                r['wn_%d' % k], r['wf_%d' % k]))
        k += 1
    return lines


def diff_line(name, run, ref):
    lines = []
    k = 1
    while ('wn_%d' % k) in ref:
        if ref['wn_%d' % k] > 0.0:
            lines.append('    %-34s support %d: W_N %+7.2f %%, W_f %+7.2f %%, impact rate '
                         '%+7.2f %%, peak force %+7.2f %%' % (
                             name, k, 100 * rel(run['wn_%d' % k], ref['wn_%d' % k]),
                             100 * rel(run['wf_%d' % k], ref['wf_%d' % k]),
                             100 * rel(run['impact_rate_%d' % k], ref['impact_rate_%d' % k]),
                             100 * rel(run['peak_%d' % k], ref['peak_%d' % k])))
        k += 1
    return lines


def describe(r):
    if r['kind'] == 'none':
        return 'full%s, tol %.0e' % ({'rk45': ' rk45', 'exponential': ' exp'}.get(
            r.get('method'), ''), r['tolerance'])
    label = 'auto' if r['kind'] == 'auto' else 'cut %g Hz' % r['cutoff_hz']
    if r.get('method') == 'rk45':
        label += ' rk45'
    elif r.get('method') == 'exponential':
        label += ' exp'
    elif r.get('method') == 'newmark':
        label += ' newmark'
    return '%s (%d coord.), tol %.0e' % (label, r['n'], r['tolerance'])


def part_deck(run, out, dat):
    tr = int(os.environ.get('BENCH_TUBES_TRANSIENT', '30'))
    rec = int(os.environ.get('BENCH_TUBES_RECORD', '40'))
    full = run.variant('none', 0, 1e-4, tr, rec)
    # the default: method 'auto', on this reduced model the exponential integrator
    auto = run.variant('auto', 0, 1e-4, tr, rec)
    nm = run.variant('auto', 0, 1e-4, tr, rec, NEWMARK)
    rk = run.variant('auto', 0, 1e-4, tr, rec, RK45)
    ex = auto if auto.get('method') == 'exponential' else run.variant('auto', 0, 1e-4, tr,
                                                                      rec, EXP)
    ratio = full['cpu_per_simulated_s'] / auto['cpu_per_simulated_s']
    out.append('== the tube deck (%s: 8 Hz, 0.2 mm), %d + %d periods, release build, serial'
               % (DECK, tr, rec))
    out.append('side by side at the deck tolerance 1e-4:')
    out.append('  full model:     %d dofs, highest mode %.0f Hz: %.2f s cpu, %.3f s cpu per '
               'simulated second, %d steps' % (full['n'], full['f_max_hz'], full['cpu_s'],
                                               full['cpu_per_simulated_s'], full['steps']))
    out.append("  default 'auto': %d coordinates (%d modes + %d static modes per plane, "
               'cut-off %.1f Hz, contact frequency %.1f Hz), highest frequency %.0f Hz, method '
               "'auto' = %s: %.2f s cpu, %.3f s cpu per simulated second, %d steps" % (
                   auto['n'], auto['modes_per_plane'], auto['static_per_plane'],
                   auto['cutoff_hz'], auto['contact_hz'], auto['f_max_hz'], auto['method'],
                   auto['cpu_s'], auto['cpu_per_simulated_s'], auto['steps']))
    out.append("  'auto' basis under Newmark (&solver method = 'newmark'): %.2f s cpu, %.3f s cpu "
               'per simulated second, %d steps' % (nm['cpu_s'], nm['cpu_per_simulated_s'],
                                                    nm['steps']))
    out.append("  'auto' basis under rk45 (&solver method = 'rk45'): %.2f s cpu, %.3f s cpu per "
               'simulated second, %d steps' % (rk['cpu_s'], rk['cpu_per_simulated_s'],
                                                rk['steps']))
    out.append("  'auto' basis under the modal exponential integrator (&solver method = "
               "'exponential'): %.2f s cpu, %.3f s cpu per simulated second, %d steps"
               % (ex['cpu_s'], ex['cpu_per_simulated_s'], ex['steps']))
    out.append('  CPU per simulated second: full / reduced (default) = %.2f; full / reduced under '
               'Newmark = %.2f; full / reduced under rk45 = %.2f; full / reduced under '
               'exponential = %.2f' % (
                   ratio, full['cpu_per_simulated_s'] / nm['cpu_per_simulated_s'],
                   full['cpu_per_simulated_s'] / rk['cpu_per_simulated_s'],
                   full['cpu_per_simulated_s'] / ex['cpu_per_simulated_s']))
    quick = os.environ.get('BENCH_TUBES_QUICK', '0') == '1'
    spread = [run.variant('none', 0, t, tr, rec) for t in ((1e-6,) if quick else
                                                           (1e-3, 1e-5, 1e-6))]
    reduced = [auto, nm, rk] + ([] if ex is auto else [ex])
    rows = [full] + reduced + spread
    out += support_table(rows, [describe(r) for r in rows])
    out.append('  differences against the full model at 1e-4 (the reduced run, then the full '
               "model's own spread between tolerances):")
    for r in reduced + spread:
        out += diff_line(describe(r), r, full)
    ref = spread[-1]
    # the full model under the exponential integrator: its linear part exact too, so the
    # high modes of the finite elements cost steps only through the interpolant's check
    fullex = [run.variant('none', 0, 1e-4, tr, rec, EXP)]
    if quick:
        cuts, autos, rks, excuts = [], [], [], []
        exs = [run.variant('auto', 0, t, tr, rec, EXP) for t in (1e-3, 1e-5, 1e-6)]
    else:
        cuts = [run.variant('modal', c, 1e-4, tr, rec, NEWMARK) for c in (150, 300, 700)]
        autos = [run.variant('auto', 0, t, tr, rec, NEWMARK) for t in (1e-3, 1e-5)]
        rks = [run.variant('auto', 0, t, tr, rec, RK45) for t in (1e-3, 1e-5)]
        exs = [run.variant('auto', 0, t, tr, rec, EXP) for t in (1e-3, 1e-5, 1e-6)]
        excuts = [run.variant('modal', c, 1e-4, tr, rec, EXP) for c in (300, 700)]
    out.append('  against the full model at 1e-6 (every run, for the chart):')
    # (each curve's points in the order of their tolerance: the chart draws them as lines)
    by_tol = lambda rows: sorted(rows, key=lambda r: -r['tolerance'])
    for r in by_tol([full] + spread[:-1]) + by_tol([nm] + autos) + cuts + by_tol([rk] + rks) \
            + by_tol([ex] + exs) + excuts + fullex:
        e = wear_errors(r, ref)
        out.append('    %-34s %8.3f s cpu/s  W_N %7.2f %%  W_f %7.2f %%  impact rate %7.2f %%  '
                   'peak %7.2f %%' % (describe(r), r['cpu_per_simulated_s'], 100 * e['wn'],
                                      100 * e['wf'], 100 * e['impacts'], 100 * e['peak']))
        dat.append('deck %s %s %g %g %d %.6g %.6g %.6g %.6g %.6g %.6g' % (
            ('full' if r['kind'] == 'none' else r['kind']) + {
                'rk45': '_rk45', 'exponential': '_exp'}.get(r.get('method'), ''),
            r['kind'],
            r['cutoff_hz'],
            r['tolerance'], r['n'], r['cpu_per_simulated_s'], e['wn'], e['wf'],
            e['impacts'], e['peak'], r['steps']))
    if quick:
        return ratio
    pf = run.variant('none', 0, 1e-4, 2, 4, profile=True)
    pa = run.variant('auto', 0, 1e-4, 2, 4, NEWMARK, profile=True)
    pr = run.variant('auto', 0, 1e-4, 2, 4, RK45, profile=True)
    pe = run.variant('auto', 0, 1e-4, 2, 4, EXP, profile=True)
    out.append('  where the steps go (2 + 4 periods at 1e-4):')
    for name, p in (('full', pf), ('auto', pa), ('auto rk45', pr), ('auto exp', pe)):
        out.append('    %-9s %8d steps with every support open (mean %.3g s), %8d with a '
                   'support in contact (mean %.3g s)' % (name, p['open_steps'],
                                                        p['open_mean_dt'], p['contact_steps'],
                                                        p['contact_mean_dt']))
    return ratio


def part_periodic(run, out, dat):
    tr, rec = 15, 20
    ref = run.variant('none', 0, 1e-6, tr, rec, PERIODIC)
    out.append('== the periodic case (%s with %s), %d + %d periods' % (DECK, PERIODIC, tr, rec))
    out.append('  reference: the full model at 1e-6: %.2f s cpu' % ref['cpu_s'])
    rows = [ref]
    # BENCH_TUBES_PERIODIC_QUICK=1: the full and default models at 1e-4 and the exponential
    # integrator (the 'auto' basis at 1e-3 .. 1e-6, the full model at 1e-4) only
    quick = os.environ.get('BENCH_TUBES_PERIODIC_QUICK', '0') == '1'
    if not quick:
        for c in (60, 100, 150, 200, 300, 450, 700, 1000, 1500):
            rows.append(run.variant('modal', c, 1e-5, tr, rec, PERIODIC))
    for t in ((1e-4,) if quick else (1e-3, 1e-4, 1e-5)):
        rows.append(run.variant('none', 0, t, tr, rec, PERIODIC))
    for t in ((1e-4,) if quick else (1e-3, 1e-4, 1e-5)):
        rows.append(run.variant('auto', 0, t, tr, rec, PERIODIC + ' ' + NEWMARK))
    for t in (1e-3, 1e-4, 1e-5, 1e-6):
        rows.append(run.variant('auto', 0, t, tr, rec, PERIODIC + ' ' + EXP))
    rows.append(run.variant('none', 0, 1e-4, tr, rec, PERIODIC + ' ' + EXP))
    for r in rows[1:]:
        e = wear_errors(r, ref)
        out.append('    %-34s %8.3f s cpu/s  W_N %9.2e  W_f %9.2e  impact rate %9.2e  peak '
                   '%9.2e' % (describe(r), r['cpu_per_simulated_s'], e['wn'], e['wf'],
                              e['impacts'], e['peak']))
        dat.append('periodic %s %s %g %g %d %.6g %.6g %.6g %.6g %.6g %.6g' % (
            ('full' if r['kind'] == 'none' else r['kind']) + {
                'rk45': '_rk45', 'exponential': '_exp'}.get(r.get('method'), ''),
            r['kind'], r['cutoff_hz'],
            r['tolerance'], r['n'], r['cpu_per_simulated_s'], e['wn'], e['wf'],
            e['impacts'], e['peak'], r['steps']))
    out += support_table(rows[:1], ['full, tol 1e-06'])


MU = 0.3   # the map deck's friction coefficient (both baffles)


def contact_class(cf, wn, wf):
    """'-' no contact; I impacting (in contact less than half the time), S sustained contact;
    then s sliding or k sticking: the share of the normal work done while slipping,
    W_f / (mu W_N), above or below one half (W_N also counts the elastic stick's motion, the
    friction work only the slip; the sweep files hold no stick fraction)."""
    if cf <= 0.0:
        return '-'
    slip = wf / (MU * wn) if wn > 0.0 else 0.0
    return ('I' if cf < 0.5 else 'S') + ('s' if slip >= 0.5 else 'k')


def part_map(run, out):
    full = run.map_run('none')
    red = run.map_run('auto')
    rk = run.map_run('auto', RK45)
    ex = run.map_run('auto', EXP)
    same_rk = 0
    same_ex = 0
    n = len(full['x'])
    same = 0
    lines = []
    for p in range(n):
        cf = [contact_class(full['contact_fraction'][p][k], full['normal_work_rate'][p][k],
                            full['friction_work_rate'][p][k])
              for k in range(len(full['contact_fraction'][p]))]
        cr = [contact_class(red['contact_fraction'][p][k], red['normal_work_rate'][p][k],
                            red['friction_work_rate'][p][k])
              for k in range(len(red['contact_fraction'][p]))]
        ck = [contact_class(rk['contact_fraction'][p][k], rk['normal_work_rate'][p][k],
                            rk['friction_work_rate'][p][k])
              for k in range(len(rk['contact_fraction'][p]))]
        if cf == cr:
            same += 1
        ce = [contact_class(ex['contact_fraction'][p][k], ex['normal_work_rate'][p][k],
                            ex['friction_work_rate'][p][k])
              for k in range(len(ex['contact_fraction'][p]))]
        if cf == ck:
            same_rk += 1
        if cf == ce:
            same_ex += 1
        wf = sum(full['normal_work_rate'][p])
        wr = sum(red['normal_work_rate'][p])
        lines.append('    %5.2f Hz %6.3f mm  full %-8s reduced %-8s  W_N %9.3e / %9.3e W%s' % (
            full['x'][p], 1e3 * full['y'][p], ' '.join(cf), ' '.join(cr), wf, wr,
            '' if cf == cr else '   <- differs'))
    subset = os.environ.get('BENCH_TUBES_MAP', '')
    out.append('== the tube map (%s, %d points%s)' % (MAP, n, ', a subset: ' + subset
                                                       if subset else ''))
    out.append('  full: %.1f s cpu (%.1f s wall); reduced (as shipped): %.1f s cpu (%.1f s '
               'wall); cpu ratio %.2f' % (full['cpu_s'], full['wall_s'], red['cpu_s'],
                                          red['wall_s'], full['cpu_s'] / red['cpu_s']))
    out.append('  the same contact class at both baffles (no contact / impacting / sustained, '
               'sticking / sliding): %d of %d points (%.1f %%)' % (same, n, 100.0 * same / n))
    out.append("  reduced under rk45 (&solver method = 'rk45'): %.1f s cpu (%.1f s wall); cpu "
               'ratio %.2f; the same contact class as the full map at %d of %d points (%.1f %%)'
               % (rk['cpu_s'], rk['wall_s'], full['cpu_s'] / rk['cpu_s'], same_rk, n,
                  100.0 * same_rk / n))
    out.append("  reduced under the modal exponential integrator (&solver method = "
               "'exponential'): %.1f s cpu (%.1f s wall); cpu ratio %.2f; the same contact "
               'class as the full map at %d of %d points (%.1f %%)'
               % (ex['cpu_s'], ex['wall_s'], full['cpu_s'] / ex['cpu_s'], same_ex, n,
                  100.0 * same_ex / n))
    out.append('  per point (class of baffle 1, baffle 2; summed normal work rate):')
    out += lines


def main():
    bench, gapbeam = sys.argv[1], sys.argv[2]
    prefix = 'bench_results/tubes_reduction'
    parts = ['deck', 'periodic', 'map']
    args = sys.argv[3:]
    while args:
        a = args.pop(0)
        if a == '--out':
            prefix = args.pop(0)
        elif a == '--parts':
            parts = args.pop(0).split(',')
    run = Runner(bench, gapbeam, prefix)
    out, dat = [], ['# case curve kind cutoff_hz tolerance n cpu_per_simulated_s err_wn err_wf '
                    'err_impact_rate err_peak steps']
    if 'deck' in parts:
        part_deck(run, out, dat)
    if 'periodic' in parts:
        part_periodic(run, out, dat)
    if 'map' in parts:
        part_map(run, out)
    with open(prefix + '.txt', 'w') as f:
        f.write('\n'.join(out) + '\n')
    with open(prefix + '.dat', 'w') as f:
        f.write('\n'.join(dat) + '\n')
    print('\n'.join(out))


if __name__ == '__main__':
    main()
