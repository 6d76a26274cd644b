#!/usr/bin/env python3
"""scripts/main_summary.py - the main job's comparison of this model with the paper's claims.

Usage:
  python3 scripts/main_summary.py DIR [CLAIMS]       (scripts/run.sh runs it after the main job)

Reads the claims (default inputs/paper_claims.txt: prefix | case | figure | the paper's
response) and, with the gapbeam Python reader (python/), each result file DIR/<prefix>.h5: for a
transient run its label (/diagnostics/label_text), period, largest Lyapunov exponent and impacts
per period; for a frequency line (a sweep) the labels along it: the periods it shows, its chaotic
bands, and whether a period-4 point borders a chaotic one (the paper: "period four motion becomes
chaotic"). A claim agrees when this model's label is of the same kind as the paper's (chaotic /
period p); labels are read from the files, so richer labels written by later versions appear as
they are.

Writes DIR/summary.txt (the table, also printed) and DIR/summary_vars.gp (gnuplot assignments
for scripts/summary.gp: the table's lines, the cases' labels, the chaotic bands of the line).
Exit status 0; 1 when a result file is missing or unreadable (named on stderr).
"""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))


def kind(label):
    """The kind of a label text: 'chaotic', 'period_<p>' or 'undecided' (a richer label from a
    later version is reduced to its kind by its first word)."""
    word = str(label).split()[0] if str(label).split() else ""
    if word.startswith("chao"):
        return "chaotic"
    if word.startswith("period_"):
        return word.rstrip(",;")
    return "undecided"


def merge_bands(runs, step, gap_steps=3):
    """Bands of chaos: runs closer than `gap_steps` grid steps joined (the periodic windows
    inside a band are counted): [(first, last, windows)]."""
    out = []
    for a, b in runs:
        if out and a - out[-1][1] <= gap_steps * step * 1.0001:
            out[-1] = (out[-1][0], b, out[-1][2] + 1)
        else:
            out.append((a, b, 0))
    return out


def bands(freq, labels):
    """Runs of consecutive chaotic points as (first, last) frequencies."""
    out, start, prev = [], None, None
    for f, lab in zip(freq, labels):
        if kind(lab) == "chaotic":
            if start is None:
                start = f
            prev = f
        elif start is not None:
            out.append((start, prev))
            start = None
    if start is not None:
        out.append((start, prev))
    return out


def cascade(freq, labels):
    """The first period-4 point followed along the line (through longer periods only) by a
    chaotic one: (f4, f_chaos), or None."""
    seq = [(f, kind(l)) for f, l in zip(freq, labels)]
    for i, (f, k) in enumerate(seq):
        if k != "period_4":
            continue
        for g, k2 in seq[i + 1:]:
            if k2 == "chaotic":
                return f, g
            if not (k2.startswith("period_") and int(k2.split("_")[1]) >= 4):
                break
    return None


def gp_string(s):
    return '"' + str(s).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def main(argv):
    if len(argv) not in (2, 3) or argv[1] in ("-h", "--help"):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    out_dir = Path(argv[1])
    claims_path = Path(argv[2]) if len(argv) == 3 else ROOT / "inputs" / "paper_claims.txt"
    import gapbeam
    import numpy as np

    claims = []
    for line in claims_path.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.lstrip().startswith("#"):
            claims.append([x.strip() for x in line.split("|")])
    rows, gp = [], []
    status = 0
    for k, (prefix, case, where, paper) in enumerate(claims, start=1):
        path = out_dir / (prefix + ".h5")
        try:
            res = gapbeam.load(str(path))
        except (OSError, ValueError) as exc:
            print("main_summary: cannot read {}: {}".format(path, exc), file=sys.stderr)
            status = 1
            continue
        if res.analysis == "transient":
            label = str(res.diagnostics.label_text.values)
            lam = float(res.diagnostics.lyapunov)
            sig = float(res.diagnostics.lyapunov_error)
            n_rec = len(res.poincare.strain.values)
            hits = float(res.impacts.count.values[0]) / n_rec if res.impacts.count.values.size \
                else 0.0
            model = "{} (λ = {:+.2f} ± {:.2f} 1/s, {:.2f} impacts/period)".format(
                label, lam, sig, hits)
            agree = kind(label) == kind(paper)
            gp.append("label{} = {}".format(k, gp_string(label)))
            gp.append("lambda{} = {}".format(k, gp_string("λ = {:+.2f} ± {:.2f} 1/s".format(
                lam, sig))))
        else:
            t = gapbeam.sweep_table(res)
            order = np.argsort(t["frequency_hz"])
            f = t["frequency_hz"][order]
            labs = [t["label_text"][i] for i in order]
            seen = sorted({kind(x) for x in labs if kind(x).startswith("period_")},
                          key=lambda s: int(s.split("_")[1]))
            cas = cascade(f, labs)
            b = bands(f, labs)
            step = float(np.min(np.diff(f))) if len(f) > 1 else 0.01
            merged = merge_bands(b, step)
            model = "periods {} seen;\n{};\nchaos in {}".format(
                ", ".join(s.split("_")[1] for s in seen) or "none",
                "period 4 at {:.2f} Hz, chaotic from {:.2f} Hz".format(*cas) if cas
                else "no period-4 point next to chaos",
                ",\n   ".join("{:.2f}-{:.2f} Hz{}".format(
                    a, c, " ({} periodic window{})".format(w, "s" if w > 1 else "") if w else "")
                    for a, c, w in merged) or "none")
            agree = cas is not None
            gp.append("bands = {}".format(gp_string(" ".join(
                "{:.6g} {:.6g}".format(a, c) for a, c in b))))
            gp.append("band_step = {:.6g}".format(step))
        verdict = "agrees" if agree else "differs"
        rows.append((case, where, paper, model, verdict))
        gp.append("case{} = {}".format(k, gp_string(case)))
        gp.append("paper{} = {}".format(k, gp_string("paper: {} ({})".format(paper, where))))
        gp.append("verdict{} = {}".format(k, gp_string(verdict)))
    gp.append("nclaims = {}".format(len(rows)))
    lines = ["This model against the paper (labels read from the result files):"]
    for case, where, paper, model, verdict in rows:
        lines.append("  {}: paper ({}) {}; gapbeam {} -> {}".format(
            case, where, paper, " ".join(model.split()), verdict))
    for i, (case, where, paper, model, verdict) in enumerate(rows, start=1):
        gp.append("row{} = {}".format(i, gp_string("{}\n  paper: {} ({})\n  gapbeam: {}\n  {}"
                                                    .format(case, paper, where,
                                                            model.replace("\n", "\n    "),
                                                            verdict.upper()))))
    text = "\n".join(lines) + "\n"
    (out_dir / "summary.txt").write_text(text, encoding="utf-8")
    (out_dir / "summary_vars.gp").write_text("\n".join(gp) + "\n", encoding="utf-8")
    sys.stdout.write(text)
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
