#!/usr/bin/env python3
"""scripts/exponent_starts_study.py - how honest the exponent's error bar is on the chaotic
9.8 Hz deck (inputs/moon_shaw_9p8hz.nml, exact integrator), with one start and with
independent starts (&diagnostics lyapunov_starts); docs/labels.md section 9.

Usage:
  python3 scripts/exponent_starts_study.py GAPBEAM_EXE [--sets N] [--starts K ...]
                                           [--skip PART ...] [--out FILE]

GAPBEAM_EXE: the release build (fpm build --profile release; `fpm run --profile release
--runner echo gapbeam` prints its path). Every run is taken under the shared CPU lock file
that BENCH_LOCK names (flock; none when unset), one at a time. Writes (default
bench_results/exponent_starts.txt):

1. the reference: two runs of 100000 exponent periods (after 300 and 5300 transient
   periods), and their means over blocks of 10000 periods;
2. calibration: for each of lyapunov_starts = 1, 4, 8 (--starts), N sets of 30 runs of the
   deck's own settings, run i of set s after 300 + 700 i + offset_s transient periods (each
   starts elsewhere on the attractor): mean lambda, scatter, mean sigma, RMS of (lambda - ref) / sigma,
   the share beyond 2 and 3 sigma (an honest sigma: RMS near 1, 4.6 % and 0.27 %);
3. the deck at 10 record lengths (200 ... 1200 periods; where the exponent starts moves along
   one trajectory) for each start count: the runs, their weighted mean, the RMS of their
   deviation from it in their sigmas and the worst pair;
4. cost: the label's CPU (/diagnostics/seconds_label) summed over those 10 runs, without an
   exponent (lyapunov_periods = 0) and with 1, 4, 8 starts, 3 repetitions.
--skip reference calibration lengths cost leaves parts out (the calibration then compares
with 2.950 1/s, part 1's figure). Part 2 is 720 runs of about 0.1-0.6 s: under a busy shared
lock, run it in pieces (--starts 1, --starts 4, ...).
"""

import argparse
import os
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DECK = str(ROOT / "inputs" / "moon_shaw_9p8hz.nml")
LOCK = os.environ.get("BENCH_LOCK", "")
OFFSETS = [0, 350, -175, 175, 260, -260, -90, 85, 300, 390]
LENGTHS = [200, 250, 300, 350, 400, 450, 500, 700, 1000, 1200]


def run(exe, work, name, *overrides):
    """One run of the deck under the lock; its /diagnostics as a dict."""
    out = Path(work) / name
    subprocess.run((["flock", LOCK] if LOCK else []) + [exe, DECK, "--quiet",
                                                         f"&job output='{out}' /", *overrides],
                   check=True, stdout=subprocess.DEVNULL)
    with h5py.File(f"{out}.h5") as f:
        d = {k: f["/diagnostics"][k][()] for k in f["/diagnostics"]
             if isinstance(f["/diagnostics"][k], h5py.Dataset)}
    for suffix in (".h5", ".history.dat", ".poincare.dat"):
        Path(f"{out}{suffix}").unlink(missing_ok=True)
    return d


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("--sets", type=int, default=10)
    ap.add_argument("--starts", type=int, nargs="+", default=[1, 4, 8],
                    help="the start counts calibrated")
    ap.add_argument("--skip", nargs="*", default=[], choices=["reference", "calibration",
                    "lengths", "cost"], help="parts not run")
    ap.add_argument("--out", default=str(ROOT / "bench_results" / "exponent_starts.txt"))
    a = ap.parse_args()
    lines = []

    def say(text):
        print(text, flush=True)
        lines.append(text)

    period = 1.0 / 9.8
    with tempfile.TemporaryDirectory() as work:
        refs = [(2.950, 0.026)]   # part 1's figure when it is skipped
        if "reference" not in a.skip:
            say("== 1. reference: 100000 exponent periods (release build)")
            refs = []
        for t in (300, 5300) if "reference" not in a.skip else ():
            d = run(a.exe, work, f"ref{t}", f"&solver transient_periods={t} /",
                    "&diagnostics lyapunov_periods=100000, lyapunov_max_periods=100000, "
                    "certify=.false., transient_max_periods=100000 /")
            r = d["lyapunov_running"]
            k = np.arange(1, len(r) + 1)
            s = np.diff(np.concatenate([[0.0], r * k * period]))
            blocks = [s[i:i + 10000].sum() / (10000 * period) for i in range(0, len(s), 10000)]
            refs.append((d["lyapunov"], d["lyapunov_error"]))
            say(f"transient {t}: lambda {d['lyapunov']:.3f} +- {d['lyapunov_error']:.3f} 1/s; "
                "blocks of 10000: " + " ".join(f"{b:.2f}" for b in blocks))
        w = np.array([1 / e**2 for _, e in refs])
        ref = float(sum(wi * l for wi, (l, _) in zip(w, refs)) / w.sum())
        say(f"reference (weighted): {ref:.3f} +- {1 / np.sqrt(w.sum()):.3f} 1/s")

        say(f"\n== 2. calibration: {a.sets} sets of 30 runs, each from elsewhere on the attractor")
        for k_starts in a.starts if "calibration" not in a.skip else ():
            lam, sig, per = [], [], []
            for s_i in range(a.sets):
                for i in range(30):
                    t = 300 + 700 * i + OFFSETS[s_i % len(OFFSETS)] + 20 * (s_i // len(OFFSETS))
                    d = run(a.exe, work, "cal", f"&solver transient_periods={t} /",
                            f"&diagnostics lyapunov_starts={k_starts}, certify=.false., "
                            "transient_max_periods=100000 /")
                    lam.append(d["lyapunov"])
                    sig.append(d["lyapunov_error"])
                    per.append(d["lyapunov_periods"])
            lam, sig = np.array(lam), np.array(sig)
            z = (lam - ref) / sig
            say(f"lyapunov_starts {k_starts}: {len(lam)} runs, mean lambda {lam.mean():.3f} +- "
                f"{lam.std(ddof=1) / np.sqrt(len(lam)):.3f}, scatter {lam.std(ddof=1):.3f}, "
                f"mean sigma {sig.mean():.3f}, RMS (lambda - ref) / sigma "
                f"{np.sqrt((z**2).mean()):.2f}, beyond 2 sigma {100 * (abs(z) > 2).mean():.1f} %, "
                f"beyond 3 sigma {100 * (abs(z) > 3).mean():.1f} %, mean periods "
                f"{np.mean(per):.0f}")

        say("\n== 3. the deck at 10 record lengths (200 ... 1200)")
        for k_starts in (1, 4, 8) if "lengths" not in a.skip else ():
            ds = [run(a.exe, work, "len", f"&solver record_periods={n} /",
                      f"&diagnostics lyapunov_starts={k_starts}, certify=.false. /")
                  for n in LENGTHS]
            lam = np.array([d["lyapunov"] for d in ds])
            sig = np.array([d["lyapunov_error"] for d in ds])
            wts = 1 / sig**2
            mean = (wts * lam).sum() / wts.sum()
            worst = max(abs(lam[i] - lam[j]) / np.hypot(sig[i], sig[j])
                        for i in range(len(lam)) for j in range(i))
            say(f"lyapunov_starts {k_starts}: " + ", ".join(f"{x:.2f} +- {e:.2f}"
                                                           for x, e in zip(lam, sig)))
            say(f"  weighted mean {mean:.3f}, scatter {lam.std(ddof=1):.3f}, mean sigma "
                f"{sig.mean():.3f}, RMS (lambda - mean) / sigma "
                f"{np.sqrt((((lam - mean) / sig)**2).mean()):.2f}, worst pair {worst:.1f} sigma, "
                f"RMS (lambda - ref) / sigma {np.sqrt((((lam - ref) / sig)**2).mean()):.2f}")

        say("\n== 4. cost: label CPU over the 10 record lengths [s]")
        for rep in range(3 if "cost" not in a.skip else 0):
            row = []
            for k_starts in (0, 1, 4, 8):
                extra = ("lyapunov_periods=0" if k_starts == 0
                         else f"lyapunov_starts={k_starts}")
                row.append(sum(run(a.exe, work, "cost", f"&solver record_periods={n} /",
                                   f"&diagnostics {extra}, certify=.false. /")["seconds_label"]
                               for n in LENGTHS))
            say(f"repetition {rep + 1}: no exponent {row[0]:.3f}, 1 start {row[1]:.3f}, "
                f"4 starts {row[2]:.3f}, 8 starts {row[3]:.3f}; the exponent alone: 4 starts "
                f"{(row[2] - row[0]) / (row[1] - row[0]):.2f} x, 8 starts "
                f"{(row[3] - row[0]) / (row[1] - row[0]):.2f} x one start")
    Path(a.out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
