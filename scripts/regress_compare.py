#!/usr/bin/env python3
"""Compare two result folders of scripts/regress.sh run (before and after a change).

Usage:
    python3 scripts/regress_compare.py DIR_A DIR_B [--rtol R] [--atol A] [--no-logs]
                                       [--show N] [--quiet]
    (scripts/regress.sh compare DIR_A DIR_B ... calls this)

DIR_A is the reference (before), DIR_B the candidate (after). Every file of DIR_A is compared
with the file of the same name in DIR_B; files whose names start with '_' (the harness's
_cases.txt, _times.txt, _meta.txt) are skipped.

  *.h5         every dataset (recursively) and every attribute of every dataset: bitwise equal
               (same dtype, shape and bytes), else the largest absolute and relative difference
               for numbers, or "differs" for strings; shape and dtype changes are reported. A
               dataset or attribute of A missing in B is a failure; extra ones in B are allowed
               and listed.
  *.dat, *.txt the numeric tokens of every line compared as numbers (identical text, else the
               differences as above), every other token as text; the number of lines and of
               tokens per line must agree.
  *.log, *.err standard output and error of a case: the exit status (last line of the .log,
               `# regress: exit status N`) must agree; the text is compared like a table after
               the timings are masked (skip with --no-logs: then only the exit status counts).
  other files  byte for byte.

A file of A missing in B is a failure; extra files in B are listed. The folder's own path is
replaced by <OUTDIR> before text is compared (it is written into logs and tables).

Ignored, because they are wall-clock timings (found by inspecting the outputs of every analysis
of a545dd7):
  HDF5    /deck (the effective deck text, which holds the output path), and every dataset named
          cpu_seconds or seconds (/run/cpu_seconds, /sweep/seconds, /model_size/seconds,
          /work_precision/<series>/seconds), or whose name holds wall, elapsed or cpu; of
          /work_precision/<series>/seconds_to_1e-3 and _1e-6 only the sign is compared
          (negative: the error level was not reached).
  tables  columns named seconds (or holding wall, elapsed, cpu) of the .dat tables
          (PREFIX.wp_<series>.dat, PREFIX.model_size.dat); every number of
          PREFIX.work_precision.txt (times and ratios of times; its words, e.g. "not reached",
          are compared); the time column (last number before T/F) of PREFIX.model_size.txt.
  logs    the numbers of `cpu:` lines; `points in X s` of the sweep summary; the trailing
          `X s` of the model-size lines; every number of the work-precision table (between its
          `t(1e-3)` header and the next blank line); progress lines (`points/s`); gfortran
          backtraces.

Differences: abs = |a - b|, rel = |a - b| / max(|a|, |b|) (0 when both are 0; NaN equals NaN;
NaN against a number, or infinities of different sign, count as rel = inf). An element passes
when abs <= --atol or rel <= --rtol (both default 0: bitwise only). Integers and the exit
status are compared the same way; text and shapes must match exactly.

Output: one line per file (identical / within tolerance: max rel diff X / DIFFERS ... /
MISSING in B), detail lines for the first --show (default 6) differing datasets or lines of each
file, the extra files and datasets of B, and a summary line. Exit status 0 when every file is
bitwise identical or within the tolerance, 1 otherwise, 2 on a usage error.
"""

import argparse
import math
import os
import re
import sys

try:
    import numpy as np
except ImportError:  # pragma: no cover
    sys.exit('regress_compare: numpy is needed (python3 -m pip install numpy h5py)')
try:
    import h5py
except ImportError:  # pragma: no cover
    sys.exit('regress_compare: h5py is needed (python3 -m pip install h5py)')

EXIT_RE = re.compile(r'^# regress: exit status (-?\d+)\s*$')
TIMING_NAME = re.compile(r'(^|_)(seconds|cpu|wall|elapsed)($|_)|cpu|wall|elapsed', re.I)
SIGN_ONLY = re.compile(r'^seconds_to_', re.I)
NUM_RE = re.compile(r'^[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$|^[+-]?(nan|inf|infinity)$', re.I)


# ----------------------------------------------------------------------------------------------
# Differences
# ----------------------------------------------------------------------------------------------
class Diff:
    """Accumulates the largest differences of one file (or one item)."""

    def __init__(self):
        self.max_abs = 0.0
        self.max_rel = 0.0
        self.n_diff = 0          # numbers not bitwise (textually) equal
        self.n_fail = 0          # numbers beyond the tolerance
        self.hard = []           # structural / text differences (always failures)

    def add(self, other):
        self.max_abs = max(self.max_abs, other.max_abs)
        self.max_rel = max(self.max_rel, other.max_rel)
        self.n_diff += other.n_diff
        self.n_fail += other.n_fail
        self.hard += other.hard

    @property
    def identical(self):
        return self.n_diff == 0 and not self.hard

    @property
    def ok(self):
        return self.n_fail == 0 and not self.hard


def numeric_diff(a, b, rtol, atol):
    """Element-wise differences of two float arrays of the same shape -> Diff, index of worst."""
    d = Diff()
    a = np.asarray(a, dtype=np.float64).ravel()
    b = np.asarray(b, dtype=np.float64).ravel()
    with np.errstate(invalid='ignore', over='ignore'):
        same = (a == b) | (np.isnan(a) & np.isnan(b))
        diff = ~same
        if not diff.any():
            return d, None
        ad = np.where(diff, np.abs(a - b), 0.0)
        ad = np.where(np.isnan(ad), np.inf, ad)
        den = np.maximum(np.abs(a), np.abs(b))
        rel = np.where(diff, np.where(den > 0, ad / np.where(den > 0, den, 1.0), np.inf), 0.0)
        rel = np.where(np.isnan(rel), np.inf, rel)
    d.n_diff = int(diff.sum())
    fail = diff & ~((ad <= atol) | (rel <= rtol))
    d.n_fail = int(fail.sum())
    d.max_abs = float(ad.max())
    d.max_rel = float(rel.max())
    return d, int(np.argmax(rel))


def fmt(x):
    return 'inf' if math.isinf(x) else f'{x:.3e}'


# ----------------------------------------------------------------------------------------------
# HDF5
# ----------------------------------------------------------------------------------------------
def h5_items(path):
    """{dataset path: (value as numpy array, {attr: value})} of every dataset in the file."""
    out = {}
    with h5py.File(path, 'r') as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out['/' + name] = (np.asarray(obj[()]), {k: np.asarray(obj.attrs[k])
                                                         for k in obj.attrs})
        f.visititems(visit)
        out['/'] = (None, {k: np.asarray(f.attrs[k]) for k in f.attrs})
    return out


def timing_rule(dset):
    """'ignore', 'sign' or None for an HDF5 dataset path."""
    if dset == '/deck':
        return 'ignore'
    base = dset.rsplit('/', 1)[-1]
    if SIGN_ONLY.match(base):
        return 'sign'
    if TIMING_NAME.search(base):
        return 'ignore'
    return None


def same_bits(a, b):
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind == 'O':
        return [x for x in a.ravel()] == [x for x in b.ravel()]
    return a.tobytes() == b.tobytes()


def compare_values(label, a, b, rtol, atol, details):
    """Compare two numpy values; append detail lines; return Diff."""
    d = Diff()
    if same_bits(a, b):
        return d
    if a.shape != b.shape:
        d.hard.append(f'{label}: shape {a.shape} -> {b.shape}')
        details.append(d.hard[-1])
        return d
    num_a = a.dtype.kind in 'iufb'
    num_b = b.dtype.kind in 'iufb'
    if a.dtype != b.dtype:
        d.hard.append(f'{label}: dtype {a.dtype} -> {b.dtype}')
        details.append(d.hard[-1])
        if not (num_a and num_b):
            # strings of another length: compare the text as well
            ta = [x.decode() if isinstance(x, bytes) else str(x) for x in a.ravel()]
            tb = [x.decode() if isinstance(x, bytes) else str(x) for x in b.ravel()]
            if [t.rstrip() for t in ta] != [t.rstrip() for t in tb]:
                details.append(f'{label}: text differs')
            return d
    if not (num_a and num_b):
        d.hard.append(f'{label}: differs ({short(a)} -> {short(b)})')
        details.append(d.hard[-1])
        return d
    nd, worst = numeric_diff(a, b, rtol, atol)
    d.add(nd)
    if nd.n_diff:
        idx = np.unravel_index(worst, a.shape) if a.shape else ()
        details.append(f'{label}: {nd.n_diff} of {a.size} values differ, max abs {fmt(nd.max_abs)}'
                       f', max rel {fmt(nd.max_rel)} (worst at {tuple(int(i) for i in idx)}: '
                       f'{a.ravel()[worst].item()!r} -> {b.ravel()[worst].item()!r})')
    return d


def short(v):
    s = repr(v.tolist() if hasattr(v, 'tolist') else v)
    return s if len(s) < 60 else s[:57] + '...'


def compare_h5(pa, pb, opts, ignored, extras):
    d = Diff()
    details = []
    try:
        ia, ib = h5_items(pa), h5_items(pb)
    except OSError as e:
        d.hard.append(f'cannot read: {e}')
        return d, [d.hard[-1]]
    for name, (va, attrs_a) in ia.items():
        if name not in ib:
            d.hard.append(f'{name}: missing in B')
            details.append(d.hard[-1])
            continue
        vb, attrs_b = ib[name]
        rule = timing_rule(name) if va is not None else None
        if rule == 'ignore':
            ignored.add('h5 ' + re.sub(r'^/work_precision/[^/]+/', '/work_precision/*/', name))
        elif rule == 'sign':
            ignored.add('h5 ' + re.sub(r'^/work_precision/[^/]+/', '/work_precision/*/', name)
                        + ' (sign only)')
            if va.shape != vb.shape:
                d.hard.append(f'{name}: shape {va.shape} -> {vb.shape}')
                details.append(d.hard[-1])
            elif not np.array_equal(np.asarray(va) < 0, np.asarray(vb) < 0):
                d.hard.append(f'{name}: reached / not reached differs ({short(va)} -> {short(vb)})')
                details.append(d.hard[-1])
        elif va is not None:
            d.add(compare_values(name, va, vb, opts.rtol, opts.atol, details))
        for k, av in attrs_a.items():
            if k not in attrs_b:
                d.hard.append(f'{name} attribute {k}: missing in B')
                details.append(d.hard[-1])
            else:
                d.add(compare_values(f'{name} attribute {k}', av, attrs_b[k], opts.rtol,
                                     opts.atol, details))
        for k in attrs_b:
            if k not in attrs_a:
                extras.append(f'{os.path.basename(pb)}: {name} attribute {k}')
    for name in ib:
        if name not in ia:
            extras.append(f'{os.path.basename(pb)}: {name}')
    return d, details


# ----------------------------------------------------------------------------------------------
# Text tables and logs
# ----------------------------------------------------------------------------------------------
def is_num(tok):
    return bool(NUM_RE.match(tok))


def to_float(tok):
    return float(tok.replace('d', 'e').replace('D', 'E'))


def read_lines(path, outdirs):
    """The lines of a text file, every path in `outdirs` replaced by <OUTDIR>."""
    with open(path, 'r', errors='replace') as f:
        text = f.read()
    for d in outdirs:
        text = text.replace(d + '/', '<OUTDIR>/')
    return text.splitlines()


def outdirs_of(top):
    """The folder's path, and the path it was written to (`outdir:` in _meta.txt) if other."""
    dirs = [top]
    try:
        with open(os.path.join(top, '_meta.txt')) as f:
            for ln in f:
                if ln.startswith('outdir: '):
                    d = ln[len('outdir: '):].strip()
                    if d and d not in dirs:
                        dirs.insert(0, d)
    except OSError:
        pass
    return sorted(dirs, key=len, reverse=True)


def dat_masks(lines, ignored, fname):
    """Per-line sets of token indices to ignore in a .dat table (timing columns)."""
    header = None
    for ln in lines:
        if ln.startswith('#'):
            header = ln
        else:
            break
    if header is None:
        return {}
    names = header[1:].split()
    cols = {i for i, n in enumerate(names) if TIMING_NAME.search(n)}
    if not cols:
        return {}
    ignored.add('table *.' + re.sub(r'^wp_.*\.dat$', 'wp_*.dat', fname.split('.', 1)[-1])
                + ' column ' +
                ', '.join(names[i] for i in sorted(cols)))
    return {i: cols for i, ln in enumerate(lines) if not ln.startswith('#')}


def txt_masks(lines, fname, ignored):
    masks = {}
    if fname.endswith('.work_precision.txt'):
        ignored.add('table *.work_precision.txt: every number')
        for i, ln in enumerate(lines):
            masks[i] = 'all'
    elif fname.endswith('.model_size.txt'):
        ignored.add('table *.model_size.txt: time column')
        for i, ln in enumerate(lines):
            toks = ln.split()
            if len(toks) >= 2 and toks[-1] in ('T', 'F') and is_num(toks[-2]):
                masks[i] = {len(toks) - 2}
    return masks


def log_prepare(lines, ignored):
    """Drop backtraces and progress lines, mask timings; returns (lines, masks, exit status)."""
    status = None
    out, masks = [], {}
    in_wp = False
    for ln in lines:
        m = EXIT_RE.match(ln)
        if m:
            status = int(m.group(1))
            continue
        if ln.startswith('Error termination. Backtrace') or re.match(r'^#\d+\s+0x', ln) \
                or re.match(r'^\s+at \S+:\d+$', ln):
            continue
        if 'points/s' in ln:
            ignored.add('log: progress lines')
            continue
        i = len(out)
        if ln.startswith('cpu:'):
            masks[i] = 'all'
            ignored.add('log: cpu: line')
        if re.search(r' points in \S+ s', ln):
            ln = re.sub(r' points in \S+ s', ' points in <t> s', ln)
            ignored.add('log: sweep "points in X s"')
        if re.match(r'^\s+\d+ (elements|modes)\b', ln) and re.search(r', \S+ s( ok)?$', ln):
            ln = re.sub(r', \S+ s( ok)?$', r', <t> s\1', ln)
            ignored.add('log: model-size time')
        if 't(1e-3)' in ln:
            in_wp = True
        elif in_wp and not ln.strip():
            in_wp = False
        elif in_wp:
            masks[i] = 'all'
            ignored.add('log: work-precision table numbers')
        out.append(ln)
    return out, masks, status


def compare_lines(la, lb, masks, opts, details, label_fmt='line {}'):
    d = Diff()
    if len(la) != len(lb):
        d.hard.append(f'{len(la)} lines -> {len(lb)} lines')
        details.append(d.hard[-1])
    shown = 0
    for i, (x, y) in enumerate(zip(la, lb)):
        if x == y:
            continue
        ta, tb = x.split(), y.split()
        mask = masks.get(i, set())
        if len(ta) != len(tb):
            d.hard.append(f'line {i + 1}: {len(ta)} tokens -> {len(tb)} tokens')
            details.append(f'line {i + 1}: {x.strip()[:90]!r} -> {y.strip()[:90]!r}')
            continue
        ld = Diff()
        for j, (p, q) in enumerate(zip(ta, tb)):
            if p == q:
                continue
            if is_num(p) and is_num(q):
                if mask == 'all' or j in mask:
                    continue
                nd, _ = numeric_diff([to_float(p)], [to_float(q)], opts.rtol, opts.atol)
                if nd.n_diff == 0:      # same number written differently
                    nd.n_diff = 1
                ld.add(nd)
            else:
                ld.hard.append(f'line {i + 1}: token {j + 1} {p!r} -> {q!r}')
        if ld.n_diff or ld.hard:
            d.add(ld)
            if shown < opts.show:
                msg = f'line {i + 1}: '
                if ld.hard:
                    msg = ld.hard[0] + (f' (and {len(ld.hard) - 1} more tokens)'
                                        if len(ld.hard) > 1 else '')
                else:
                    msg += f'max rel {fmt(ld.max_rel)}, max abs {fmt(ld.max_abs)}'
                details.append(msg)
            shown += 1
    if shown > opts.show:
        details.append(f'... {shown - opts.show} more lines differ')
    return d


def compare_text(pa, pb, opts, ignored, outdirs_a, outdirs_b):
    details = []
    la, lb = read_lines(pa, outdirs_a), read_lines(pb, outdirs_b)
    fname = os.path.basename(pa)
    if fname.endswith('.dat'):
        masks = dat_masks(la, ignored, fname)
    else:
        masks = txt_masks(la, fname, ignored)
    return compare_lines(la, lb, masks, opts, details), details


def compare_log(pa, pb, opts, ignored, outdirs_a, outdirs_b):
    details = []
    la, ma, sa = log_prepare(read_lines(pa, outdirs_a), ignored)
    lb, mb, sb = log_prepare(read_lines(pb, outdirs_b), ignored)
    d = Diff()
    if sa != sb:
        d.hard.append(f'exit status {sa} -> {sb}')
        details.append(d.hard[-1])
    if not opts.no_logs:
        masks = {i: 'all' for i in set(ma) | set(mb)}   # only whole lines are masked
        d.add(compare_lines(la, lb, masks, opts, details))
    return d, details


def compare_bytes(pa, pb):
    with open(pa, 'rb') as f:
        a = f.read()
    with open(pb, 'rb') as f:
        b = f.read()
    d = Diff()
    if a != b:
        d.hard.append('bytes differ')
    return d, list(d.hard)


# ----------------------------------------------------------------------------------------------
def list_files(top):
    out = []
    for dp, dn, fn in os.walk(top):
        dn.sort()
        for f in sorted(fn):
            rel = os.path.relpath(os.path.join(dp, f), top)
            if os.path.basename(rel).startswith('_'):
                continue
            out.append(rel)
    return out


def main():
    ap = argparse.ArgumentParser(
        description='Compare two scripts/regress.sh result folders (see the module docstring).')
    ap.add_argument('dir_a', help='reference folder (before)')
    ap.add_argument('dir_b', help='candidate folder (after)')
    ap.add_argument('--rtol', type=float, default=0.0,
                    help='relative tolerance per number (default 0: bitwise)')
    ap.add_argument('--atol', type=float, default=0.0,
                    help='absolute tolerance per number (default 0)')
    ap.add_argument('--no-logs', action='store_true',
                    help='compare only the exit status of the .log files, not their text')
    ap.add_argument('--show', type=int, default=6,
                    help='detail lines per file (default 6)')
    ap.add_argument('--quiet', action='store_true', help='print only files that are not identical')
    if len(sys.argv) > 1 and sys.argv[1] in ('-h', '--help'):
        print(__doc__)
        return 0
    opts = ap.parse_args()
    dir_a, dir_b = (os.path.realpath(p) for p in (opts.dir_a, opts.dir_b))
    outdirs_a, outdirs_b = outdirs_of(dir_a), outdirs_of(dir_b)
    for p in (dir_a, dir_b):
        if not os.path.isdir(p):
            print(f'regress_compare: error: {p} is not a folder', file=sys.stderr)
            return 2
    fa, fb = list_files(dir_a), list_files(dir_b)
    if not fa:
        print(f'regress_compare: error: no result files in {dir_a}', file=sys.stderr)
        return 2
    set_b = set(fb)
    ignored = set()
    extras = []
    counts = {'identical': 0, 'within': 0, 'differs': 0, 'missing': 0}
    total = Diff()
    width = max(len(f) for f in fa)
    for rel in fa:
        pa, pb = os.path.join(dir_a, rel), os.path.join(dir_b, rel)
        if rel not in set_b:
            counts['missing'] += 1
            print(f'{rel:<{width}}  MISSING in B')
            continue
        if rel.endswith('.h5'):
            d, details = compare_h5(pa, pb, opts, ignored, extras)
        elif rel.endswith(('.dat', '.txt')):
            d, details = compare_text(pa, pb, opts, ignored, outdirs_a, outdirs_b)
        elif rel.endswith(('.log', '.err')):
            d, details = compare_log(pa, pb, opts, ignored, outdirs_a, outdirs_b)
        else:
            d, details = compare_bytes(pa, pb)
        total.add(d)
        if d.identical:
            counts['identical'] += 1
            if not opts.quiet:
                print(f'{rel:<{width}}  identical')
            continue
        if d.ok:
            counts['within'] += 1
            print(f'{rel:<{width}}  within tolerance: max rel diff {fmt(d.max_rel)} '
                  f'(max abs {fmt(d.max_abs)}, {d.n_diff} numbers not bitwise equal)')
        else:
            counts['differs'] += 1
            what = []
            if d.n_diff:
                what.append(f'max rel diff {fmt(d.max_rel)}, max abs {fmt(d.max_abs)}, '
                            f'{d.n_fail} of {d.n_diff} differing numbers beyond tolerance')
            if d.hard:
                what.append(f'{len(d.hard)} structural/text differences')
            print(f'{rel:<{width}}  DIFFERS: ' + '; '.join(what))
        for line in details[:opts.show + 1]:
            print(f'    {line}')
    for rel in fb:
        if rel not in set(fa):
            extras.append(f'{rel} (file)')
    if extras:
        print(f'extra in B (allowed): {len(extras)}')
        for e in extras:
            print(f'    {e}')
    if ignored:
        print('ignored (timings, deck text): ' + '; '.join(sorted(ignored)))
    n = len(fa)
    ok = counts['differs'] == 0 and counts['missing'] == 0
    print(f'summary: {n} files: {counts["identical"]} identical, {counts["within"]} within '
          f'tolerance (rtol {opts.rtol:g}, atol {opts.atol:g}), {counts["differs"]} differ, '
          f'{counts["missing"]} missing in B; {len(extras)} extra in B; '
          f'max rel diff {fmt(total.max_rel)}, max abs diff {fmt(total.max_abs)}: '
          + ('PASS' if ok else 'FAIL'))
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
