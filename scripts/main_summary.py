#!/usr/bin/env python3
"""scripts/main_summary.py - the main job's comparison of this model with the paper's claims.

Usage:
  python3 scripts/main_summary.py DIR [CLAIMS]       (scripts/run.sh runs it after the main job)

Reads the claims (default inputs/paper_claims.txt: prefix | case | figure | the paper's
response) and, with the gapbeam Python reader (python/), each result file DIR/<prefix>.h5: for a
transient run its label (/diagnostics/label_text), largest Lyapunov exponent with its standard
error, certificate and impacts per period, and the same for DIR/<prefix>_half_element.h5 where it
exists (the case with the rigid half element's rotary inertia in the lumped mass, which the main
job runs beside the reference decks' translational masses only); for a frequency line (a sweep) the labels along it: the periods it shows, its chaotic
bands, and whether a period-4 point borders a chaotic one (the paper: "period four motion becomes
chaotic"). A claim agrees when this model's label is of the same kind as the paper's (chaotic /
period p); labels are read from the files, so richer labels written by later versions appear as
they are.

Writes DIR/summary.txt (the table, also printed) and DIR/summary_vars.gp (gnuplot assignments
for scripts/summary.gp: the table's lines, the cases' labels, the chaotic bands of the line).
Exit status 0; 1 when a result file is missing or unreadable (named on stderr).
"""

import sys
import textwrap
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


def transient_summary(res):
    """A transient run's label text, exponent and its standard error [1/s], certificate text and
    impacts per recorded period (stop 1)."""
    d = res.diagnostics
    label = str(d.label_text.values)
    cert = str(d.certificate_text.values) if "certificate_text" in d else "not certified"
    n_rec = len(res.poincare.strain.values)
    hits = float(res.impacts.count.values[0]) / n_rec if res.impacts.count.values.size else 0.0
    return label, float(d.lyapunov), float(d.lyapunov_error), cert, hits


def route(freq, labels):
    """The labels along the line from the last period-1 point before the first chaotic one, as
    runs: 'period 1 to 9.00 Hz, period 4 at 9.01 Hz, ..., chaotic from 9.10 Hz', or ''."""
    ks = [kind(l) for l in labels]
    if "chaotic" not in ks:
        return ""
    c = ks.index("chaotic")
    a = max([i for i in range(c) if ks[i] == "period_1"], default=0)
    runs = []
    for i in range(a, c):
        if runs and runs[-1][0] == ks[i]:
            runs[-1][2] = freq[i]
        else:
            runs.append([ks[i], freq[i], freq[i]])
    words = []
    for j, (k, f0, f1) in enumerate(runs):
        name = k.replace("_", " ")
        if j == 0 and k == "period_1":
            words.append("{} to {:.2f} Hz".format(name, f1))
        elif f0 == f1:
            words.append("{} at {:.2f} Hz".format(name, f0))
        else:
            words.append("{} {:.2f}-{:.2f} Hz".format(name, f0, f1))
    words.append("chaotic from {:.2f} Hz".format(freq[c]))
    return ", ".join(words)


def gp_string(s):
    return '"' + str(s).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def line_summary(res, np):
    """A frequency line's text (periods seen, the period-4 test, the route into chaos, the
    chaotic bands), a one-line form of it, whether a period-4 point borders a chaotic one, the
    bands and the step."""
    import gapbeam
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
    way = route(f, labs)
    text = "periods {} seen;\n{};\n{}{}".format(
        ", ".join(s.split("_")[1] for s in seen) or "none",
        "period 4 at {:.2f} Hz, chaotic from {:.2f} Hz".format(*cas) if cas
        else "no period-4 point next to chaos",
        "\n   ".join(textwrap.wrap("into chaos: {};".format(way), 64)) + "\n" if way else "",
        "\n   ".join(textwrap.wrap("chaos in {}".format(", ".join(
            "{:.2f}-{:.2f} Hz{}".format(
                a, c, " ({} periodic window{})".format(w, "s" if w > 1 else "") if w else "")
            for a, c, w in merged) or "none"), 64)))
    short = "period 4 at {:.2f} Hz, chaotic from {:.2f} Hz".format(*cas) if cas else \
        "no period-4 point next to chaos; into chaos: {}".format(way or "none")
    return text, short, cas is not None, b, step


def summarise(res, paper, np):
    """One result file against the paper's claim: (text, agrees, gnuplot items for the figure:
    label and exponent of a transient run, bands and step of a line)."""
    if res.analysis == "transient":
        label, lam, sig, cert, hits = transient_summary(res)
        text = "{} (λ = {:+.2f} ± {:.2f} 1/s, {}, {:.2f} impacts/period)".format(
            label, lam, sig, cert, hits)
        return text, kind(label) == kind(paper), {
            "label": label, "lambda": "λ = {:+.2f} ± {:.2f} 1/s, {}".format(lam, sig, cert),
            "short": "{} (λ = {:+.2f} ± {:.2f} 1/s, {})".format(label, lam, sig, cert)}
    text, short, agree, b, step = line_summary(res, np)
    return text, agree, {"bands": " ".join("{:.6g} {:.6g}".format(a, c) for a, c in b),
                         "band_step": step, "short": short}


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
    rows, gp, alts = [], [], []
    status = 0
    for k, (prefix, case, where, paper) in enumerate(claims, start=1):
        path = out_dir / (prefix + ".h5")
        try:
            model, agree, items = summarise(gapbeam.load(str(path)), paper, np)
        except (OSError, ValueError) as exc:
            print("main_summary: cannot read {}: {}".format(path, exc), file=sys.stderr)
            status = 1
            continue
        if "label" in items:
            gp.append("label{} = {}".format(k, gp_string(items["label"])))
            gp.append("lambda{} = {}".format(k, gp_string(items["lambda"])))
        else:
            gp.append("bands = {}".format(gp_string(items["bands"])))
            gp.append("band_step = {:.6g}".format(items["band_step"]))
        # the same claim with the former mass rule, where the main job ran it
        alt_path = out_dir / (prefix + "_half_element.h5")
        alt_text = ""
        if alt_path.exists():
            try:
                _, a_agree, a_items = summarise(gapbeam.load(str(alt_path)), paper, np)
            except (OSError, ValueError) as exc:
                print("main_summary: cannot read {}: {}".format(alt_path, exc), file=sys.stderr)
                status = 1
            else:
                alt_text = "{} -> {}".format(a_items["short"],
                                             "agrees" if a_agree else "differs")
                alts.append((case, alt_text))
        if "label" in items:
            gp.append("alt{} = {}".format(k, gp_string(alt_text)))
        verdict = "agrees" if agree else "differs"
        rows.append((case, where, paper, model, verdict))
        gp.append("case{} = {}".format(k, gp_string(case)))
        gp.append("paper{} = {}".format(k, gp_string("paper: {} ({})".format(paper, where))))
        gp.append("verdict{} = {}".format(k, gp_string(verdict)))
    gp.append("nclaims = {}".format(len(rows)))
    lines = ["This model against the paper (labels read from the result files; the reference "
             "decks: lumped mass, translational masses only):"]
    for case, where, paper, model, verdict in rows:
        lines.append("  {}: paper ({}) {}; gapbeam {} -> {}".format(
            case, where, paper, " ".join(model.split()), verdict))
    if alts:
        lines.append("With the rotary inertia of the rigid half element in the lumped mass (the "
                     "former reference; docs/paper_regimes.md):")
        for case, text in alts:
            lines.append("  {}: gapbeam {}".format(case, " ".join(text.split())))
    alt_of = dict(alts)
    for i, (case, where, paper, model, verdict) in enumerate(rows, start=1):
        alt = ("\n  rigid half element: " + alt_of[case].replace("\n", "\n    ")) \
            if case in alt_of else ""
        row = "{}\n  paper: {} ({})\n  gapbeam: {}\n  {}{}".format(
            case, paper, where, model.replace("\n", "\n    "), verdict.upper(), alt)
        gp.append("row{} = {}".format(i, gp_string(row)))
        gp.append("rowlines{} = {}".format(i, row.count("\n") + 1))
    text = "\n".join(lines) + "\n"
    (out_dir / "summary.txt").write_text(text, encoding="utf-8")
    (out_dir / "summary_vars.gp").write_text("\n".join(gp) + "\n", encoding="utf-8")
    sys.stdout.write(text)
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
