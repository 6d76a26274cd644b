#!/usr/bin/env python3
"""scripts/paper_regimes.py - summary of the paper-regime study (scripts/paper_regimes.sh).

Usage:
    scripts/paper_regimes.py OUTDIR

Reads every OUTDIR/*.h5 sweep of the study (x = forcing frequency, y = one model choice) and
prints, as Markdown: one row per (run, y value) with f1 of that model, the certified label at
the paper's three frequencies (9.8, 10.2, 10.5 Hz; the response scales with the amplitude at a
zero gap, so 3.7 and 4.0 mm give the same label), whether all three are chaotic, and the
chaotic bands of the row; then the rows where all three cases are chaotic. Needs numpy and
h5py (or the gapbeam reader's dependencies).
"""

import glob
import os
import sys

import h5py
import numpy as np

CASES = (9.8, 10.2, 10.5)


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def short(label, cert):
    name = {-1: "chaotic", 0: "undecided", -2: "unsettled", -3: "failed"}.get(
        int(label), "P{}".format(int(label)))
    return name + (" (disputed)" if int(cert) == 2 else "")


def bands(x, labels):
    """Contiguous runs of chaotic labels as 'a-b' texts."""
    out, start = [], None
    for i, lab in enumerate(labels):
        if lab == -1 and start is None:
            start = i
        if (lab != -1 or i == len(labels) - 1) and start is not None:
            end = i if lab == -1 else i - 1
            out.append("{:.1f}".format(x[start]) if end == start
                       else "{:.1f}-{:.1f}".format(x[start], x[end]))
            start = None
    return ", ".join(out) if out else "none"


def main(argv):
    if len(argv) != 2:
        print("usage: {} OUTDIR".format(argv[0]), file=sys.stderr)
        return 2
    rows, n_points, n_disputed, cpu_label, cpu_cert = [], 0, 0, 0.0, 0.0
    for path in sorted(glob.glob(os.path.join(argv[1], "*.h5"))):
        with h5py.File(path, "r") as f:
            s = f["sweep"]
            x, y = s["grid_x"][:], s["grid_y"][:]
            nx = len(x)
            lab, cert = s["label"][:], s["certificate"][:]
            f1 = s["f1_open_hz"][:]
            yvar = text(s["y_variable"][()])
            n_points += len(lab)
            n_disputed += int(np.sum(cert == 2))
            cpu_label += float(np.sum(s["seconds_label"][:]))
            cpu_cert += float(np.sum(s["seconds_certify"][:]))
            for j, yv in enumerate(y):
                row = slice(j * nx, (j + 1) * nx)
                li, ci = lab[row], cert[row]
                at = [int(np.argmin(abs(x - c))) for c in CASES]
                rows.append(dict(run=os.path.basename(path)[:-3], yvar=yvar, y=yv,
                                 f1=f1[j * nx], cases=[short(li[k], ci[k]) for k in at],
                                 all_chaotic=all(li[k] == -1 for k in at),
                                 certified=all(ci[k] == 1 for k in at),
                                 bands=bands(x, li)))
    print("## Labels of the paper's three cases\n")
    print("| run | y variable | y | f1 [Hz] | 9.8 Hz | 10.2 Hz | 10.5 Hz | all three chaotic "
          "| chaotic bands [Hz] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| {run} | {yvar} | {y:.4g} | {f1:.2f} | {c[0]} | {c[1]} | {c[2]} | {a} | {bands} |"
              .format(c=r["cases"], a="yes" if r["all_chaotic"] else "no", **r))
    good = [r for r in rows if r["all_chaotic"]]
    print("\n## Rows where all three cases are chaotic\n")
    if not good:
        print("none")
    for r in good:
        print("- {run}: {yvar} = {y:.4g} (f1 = {f1:.2f} Hz){cert}".format(
            cert="" if r["certified"] else ", a certificate disputed", **r))
    print("\n{} points, {} disputed certificates; CPU: labels {:.0f} s, certificates {:.0f} s "
          "(ratio {:.2f})".format(n_points, n_disputed, cpu_label, cpu_cert,
                                  cpu_cert / cpu_label if cpu_label > 0 else float("nan")))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
