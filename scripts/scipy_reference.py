#!/usr/bin/env python3
"""General-purpose baseline for gapbeam's work-precision study: SciPy's solve_ivp.

Reads the discrete model that a gapbeam transient run writes to PREFIX.h5 (/model/...),
integrates the same equations from rest with scipy.integrate.solve_ivp (RK45, DOP853, Radau,
LSODA) over a ladder of tolerances, and scores the final state against a reference run
(another gapbeam .h5, e.g. the exact integrator or a fine RK4 run) in the energy norm

    error = sqrt(du' K du + dv' M dv) / sqrt(u' K u + v' M v)

that gapbeam's work_precision study uses.

Equations (relative coordinates, u = v = 0 at t = 0):

    M u'' + C u' + K u + sum_c s_c f_c e_c = s(t) q,      s(t) = a omega^2 sin(omega t)
    f_c = max(0, k_c d_c + c_c d_c')  while  d_c = s_c u_dof(c) - g_c > 0,  else 0

(the stop force f_c >= 0 pushes the dof back out of the stop; with f_c entering with the
other sign the stop pulls the dof in and the solution blows up.)  First-order form
y = [u, v], y' = A y + s(t) b + (contact terms), A = [[0, I], [-M^-1 K, -M^-1 C]],
b = M^-1 q, with M^-1 precomputed (dense) and a vectorised numpy right-hand side.

Two variants per method:
  events  the standard way to script an impact problem: each contact configuration is a
          linear ODE; solve_ivp runs with terminal `events` (the penetration d_c, and for a
          damped contact also k d + c d') and is restarted from the event state with the
          other configuration, until the end time.  The implicit methods get the (constant)
          Jacobian of the configuration.
  plain   one solve_ivp call, the piecewise stop force evaluated inside the right-hand side
          (the step-size control has to cope with the kink).  The implicit methods get the
          piecewise Jacobian (callable).

Tolerances: rtol = 1e-2, 1e-3, ..., 1e-12 and atol = rtol * ATOL_SCALE (scalar,
ATOL_SCALE = 1e-6 by default, i.e. 1 um and 1 um/s per unit rtol: the displacements here are
~1e-2 m and the velocities ~1 m/s, so the rtol term dominates except for components near zero).

Timing: time.process_time() around the whole integration (all segments and restarts, not the
model set-up); best of up to --repeats (5) runs while the runs are short (a run is repeated only
while the total time spent on that point stays below 2 s).  Set OMP_NUM_THREADS=1
OPENBLAS_NUM_THREADS=1 for single-core figures.

Outputs (gnuplot-ready, same layout as gapbeam's PREFIX.wp_<series>.dat):
  OUT.wp_scipy_<method>[_events].dat    columns: seconds, error, poincare_error (NaN: no
                                        Poincare section here), steps (RHS evaluations,
                                        summed over segments), parameter (rtol)
and, with --gapbeam, the same ladder for gapbeam's own methods run as transient jobs
(OUT.wp_gapbeam_<series>.dat: auto (the default method), exact, rk45 and newmark_error (error
control at tolerance 1e-2 ...), rk4, newmark_half_step, newmark_fixed; seconds = gapbeam's
/run/cpu_seconds, the CPU time of its time loop, best of --repeats while < 0.2 s),
scored against the same reference.  A summary table (time to reach each error level, log-log
interpolation between the bracketing runs, as gapbeam's cpu_to_reach) goes to stdout.

Usage:
  scipy_reference.py MODEL.h5 REFERENCE.h5 --diff-only      (difference of the final states)
  scipy_reference.py MODEL.h5 REFERENCE.h5 --out PREFIX [--methods RK45 DOP853 Radau LSODA]
                     [--rtols 1e-2 ... ] [--variants events plain] [--repeats 3]
                     [--max-seconds 60] [--gapbeam BIN --deck DECK --override '&...' ...]
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np
from scipy.integrate import solve_ivp
import scipy

LEVELS = (1e-2, 1e-3, 1e-6, 1e-9)


# ----------------------------------------------------------------------------------------------
# model
# ----------------------------------------------------------------------------------------------
class Model:
    """The discrete model of a gapbeam run (from PREFIX.h5)."""

    def __init__(self, path):
        with h5py.File(path, "r") as f:
            m = f["model"]
            # stored in Fortran order: h5py sees the transpose
            self.K = np.ascontiguousarray(m["stiffness"][()].T)
            self.M = np.ascontiguousarray(m["mass"][()].T)
            self.C = np.ascontiguousarray(m["damping"][()].T)
            self.q = np.asarray(m["load_shape"][()], dtype=float)
            self.a = float(m["forcing_half_amplitude"][()])
            self.omega = float(m["forcing_omega"][()])
            self.dof = np.asarray(m["contact_dof"][()], dtype=int).reshape(-1) - 1
            self.sgn = np.asarray(m["contact_sign"][()], dtype=float).reshape(-1)
            self.gap = np.asarray(m["contact_gap"][()], dtype=float).reshape(-1)
            self.kc = np.asarray(m["contact_stiffness"][()], dtype=float).reshape(-1)
            self.cc = np.asarray(m["contact_damping"][()], dtype=float).reshape(-1)
            law = np.asarray(m["contact_law"][()], dtype=int).reshape(-1)
            self.t_end = float(f["final/time"][()])
            self.title = f["deck"][()].decode(errors="replace") if "deck" in f else ""
        if np.any(law != 1):
            sys.exit("scipy_reference: only bilinear stops (contact_law = 1) are supported")
        for name, mat in (("K", self.K), ("M", self.M), ("C", self.C)):
            scale = max(np.abs(mat).max(), np.finfo(float).tiny)
            if np.abs(mat - mat.T).max() > 1e-12 * scale:
                print(f"scipy_reference: warning: {name} is not symmetric", file=sys.stderr)
        self.n = self.K.shape[0]
        self.nc = self.dof.size
        n = self.n
        self.Minv = np.linalg.inv(self.M)
        A = np.zeros((2 * n, 2 * n))
        A[:n, n:] = np.eye(n)
        A[n:, :n] = -self.Minv @ self.K
        A[n:, n:] = -self.Minv @ self.C
        self.A = A
        self.b = self.Minv @ self.q
        self.amp = self.a * self.omega ** 2
        # columns of M^-1 at the contact dofs, times the sign: acceleration per unit stop force
        self.Me = -(self.Minv[:, self.dof] * self.sgn) if self.nc else np.zeros((n, 0))
        self._cfg = {}

    def energy_norm(self, u, v):
        with np.errstate(all="ignore"):
            val = float(u @ self.K @ u + v @ self.M @ v)
        # a diverged state must not score as error 0 (max(0, nan) is 0)
        return math.sqrt(max(0.0, val)) if math.isfinite(val) else math.nan

    # -- plain variant ------------------------------------------------------------------------
    def rhs_plain(self):
        n, A, b, amp, om = self.n, self.A, self.b, self.amp, self.omega
        dof, sgn, gap, kc, cc, Me = self.dof, self.sgn, self.gap, self.kc, self.cc, self.Me
        cnt = [0]
        if self.nc == 0:
            def f(t, y):
                cnt[0] += 1
                out = A @ y
                out[n:] += (amp * math.sin(om * t)) * b
                return out
            return f, cnt

        def f(t, y):
            cnt[0] += 1
            out = A @ y
            out[n:] += (amp * math.sin(om * t)) * b
            d = sgn * y[dof] - gap
            if np.any(d > 0.0):
                fc = kc * d + cc * (sgn * y[n + dof])
                fc = np.where((d > 0.0) & (fc > 0.0), fc, 0.0)
                out[n:] += Me @ fc
            return out
        return f, cnt

    def jac_plain(self):
        n, A, dof, sgn, gap, kc, cc = self.n, self.A, self.dof, self.sgn, self.gap, self.kc, self.cc

        def jac(t, y):
            if self.nc == 0:
                return A
            d = sgn * y[dof] - gap
            fc = kc * d + cc * (sgn * y[n + dof])
            act = (d > 0.0) & (fc > 0.0)
            if not np.any(act):
                return A
            return self.config(tuple(bool(x) for x in act))[0]
        return jac

    # -- events variant: one linear ODE per contact configuration ------------------------------
    def config(self, active):
        """(A_cfg, r_cfg) for the tuple of active contacts: y' = A_cfg y + s(t) b + r_cfg."""
        got = self._cfg.get(active)
        if got is not None:
            return got
        n = self.n
        A = self.A.copy()
        r = np.zeros(2 * n)
        for c, on in enumerate(active):
            if not on:
                continue
            d, s = self.dof[c], self.sgn[c]
            col = self.Me[:, c]                    # -s M^-1 e_d
            # f = k (s u_d - g) + c s v_d
            A[n:, d] += col * self.kc[c] * s
            A[n:, n + d] += col * self.cc[c] * s
            r[n:] += col * (-self.kc[c] * self.gap[c])
        got = (A, r)
        self._cfg[active] = got
        return got

    def rhs_config(self, active, cnt):
        n, b, amp, om = self.n, self.b, self.amp, self.omega
        A, r = self.config(active)
        if any(active):
            def f(t, y):
                cnt[0] += 1
                out = A @ y + r
                out[n:] += (amp * math.sin(om * t)) * b
                return out
        else:
            def f(t, y):
                cnt[0] += 1
                out = A @ y
                out[n:] += (amp * math.sin(om * t)) * b
                return out
        return f, A

    def events_config(self, active):
        """Terminal events of a configuration: list of (function, contact, kind)."""
        n, evs = self.n, []
        for c, on in enumerate(active):
            d, s, g, k, cd = self.dof[c], self.sgn[c], self.gap[c], self.kc[c], self.cc[c]

            def pen(t, y, d=d, s=s, g=g):
                return s * y[d] - g
            pen.terminal = True
            pen.direction = -1.0 if on else 1.0
            evs.append((pen, c, "d"))
            if cd > 0.0:
                def force(t, y, d=d, s=s, g=g, k=k, cd=cd):
                    return k * (s * y[d] - g) + cd * s * y[n + d]
                force.terminal = True
                force.direction = -1.0 if on else 1.0
                evs.append((force, c, "f"))
        return evs


# ----------------------------------------------------------------------------------------------
# integration
# ----------------------------------------------------------------------------------------------
def integrate_plain(model, method, rtol, atol):
    f, cnt = model.rhs_plain()
    kw = {}
    if method in ("Radau", "BDF", "LSODA"):
        kw["jac"] = model.jac_plain()
    y0 = np.zeros(2 * model.n)
    sol = solve_ivp(f, (0.0, model.t_end), y0, method=method, rtol=rtol, atol=atol, **kw)
    if sol.status != 0:
        return None, cnt[0], sol.message
    return sol.y[:, -1], cnt[0], ""


def integrate_events(model, method, rtol, atol, max_events=100000):
    cnt = [0]
    y = np.zeros(2 * model.n)
    t = 0.0
    # start open: at rest with zero gap the penetration event fires at t = 0+ and switches
    active = tuple([False] * model.nc)
    nev, stuck = 0, 0
    while t < model.t_end:
        f, A = model.rhs_config(active, cnt)
        evs = model.events_config(active)
        kw = {}
        if method in ("Radau", "BDF"):
            kw["jac"] = A                          # constant: factorised once per step size
        elif method == "LSODA":
            kw["jac"] = lambda t_, y_, A=A: A      # LSODA's wrapper wants a callable
        sol = solve_ivp(f, (t, model.t_end), y, method=method, rtol=rtol, atol=atol,
                        events=[e[0] for e in evs] or None, **kw)
        if sol.status == -1:
            return None, cnt[0], sol.message
        if sol.status == 0:
            y = sol.y[:, -1]
            t = model.t_end
            break
        # a terminal event: the earliest one ends the segment (solve_ivp stops at the first)
        hit = [j for j, te in enumerate(sol.t_events) if te.size]
        i = min(hit, key=lambda j: sol.t_events[j][0])
        t_new = float(sol.t_events[i][0])
        y = sol.y_events[i][0].copy()
        _, c, kind = evs[i]
        new = list(active)
        if active[c]:
            new[c] = False
        else:
            d = model.sgn[c] * y[model.dof[c]] - model.gap[c]
            if kind == "d":
                new[c] = True                      # f = c d' > 0 as d crosses upward
            else:
                new[c] = d > 0.0                   # the law switches on only in penetration
        stuck = stuck + 1 if t_new <= t else 0
        if stuck > 100:
            return None, cnt[0], "events: no progress (chattering at t = %g)" % t_new
        t = t_new
        active = tuple(new)
        nev += 1
        if nev > max_events:
            return None, cnt[0], "events: more than %d events" % max_events
    return y, cnt[0], ""


def timed(fn, repeats, budget=2.0):
    """Best process_time of up to `repeats` runs (repeats only while the total stays < budget)."""
    best, res, spent = math.inf, None, 0.0
    for _ in range(max(1, repeats)):
        t0 = time.process_time()
        res = fn()
        dt = time.process_time() - t0
        best = min(best, dt)
        spent += dt
        if res[0] is None or spent + dt > budget:
            break
    return best, res


# ----------------------------------------------------------------------------------------------
# tables
# ----------------------------------------------------------------------------------------------
def cpu_to_reach(rows, level):
    """As gapbeam's cpu_to_reach: first run of the ladder with error <= level, log-log
    interpolated with the run before it when that one is above the level; None: not reached."""
    prev = None
    for sec, err in rows:
        if err is None or not math.isfinite(err):
            prev = None
            continue
        if err <= level:
            if prev is not None and prev[1] > level and err > 0.0:
                w = math.log(level / prev[1]) / math.log(err / prev[1])
                return math.exp(math.log(prev[0]) + w * (math.log(sec) - math.log(prev[0])))
            return sec
        prev = (sec, err)
    return None


def write_table(path, title, series, rows, pname):
    with open(path, "w") as fh:
        fh.write(f"# {title}: {series}\n")
        fh.write(f"# columns: seconds [s], error [-], poincare_error [-], steps [{'RHS evaluations' if series.startswith('scipy') else 'accepted steps'}], parameter [{pname}]\n")
        fh.write("# seconds error poincare_error steps parameter\n")
        for r in rows:
            fh.write(" %.16E %.16E %.16E %.16E %.16E\n" % r)


def fmt(x):
    return "not reached" if x is None else "%.3E" % x


# ----------------------------------------------------------------------------------------------
# gapbeam's own methods as transient runs (optional)
# ----------------------------------------------------------------------------------------------
def gapbeam_ladders(ne_rk4_min):
    rk45 = [("rk45", f"&solver method='rk45', tolerance={r:.0e} /", r)
            for r in (10.0 ** -k for k in range(2, 11))]
    ne = [("newmark_error", f"&solver method='newmark', step_control='error', tolerance={r:.0e} /",
           r) for r in (10.0 ** -k for k in range(2, 9))]
    rk4 = [("rk4", f"&solver method='rk4', step_control='fixed', steps_per_period={s} /", s)
           for s in (2 ** k for k in range(7, 16)) if s >= ne_rk4_min]
    hs = [("newmark_half_step",
           f"&solver method='newmark', step_control='half_step', half_step_tolerance={0.1 * 10 ** (-k / 2):.6e} /",
           0.1 * 10 ** (-k / 2)) for k in range(0, 12)]
    nf = [("newmark_fixed", f"&solver method='newmark', step_control='fixed', steps_per_period={s} /",
           s) for s in (2 ** k for k in range(8, 17))]
    ex = [("exact", "&solver method='exact' /", 0.0)]
    auto = [("auto", "&solver method='auto', step_control='auto' /", 0.0)]
    return {"auto": auto, "exact": ex, "rk45": rk45, "newmark_error": ne, "rk4": rk4,
            "newmark_half_step": hs, "newmark_fixed": nf}


def run_gapbeam(binary, deck, overrides, extra, tmp, repeats):
    best, state = math.inf, None
    for _ in range(max(1, repeats)):
        prefix = os.path.join(tmp, "g")
        # No "&output history_periods = 0 /": with it the exact integrator of this gapbeam
        # version goes wrong on the 4-element case (the history costs next to nothing).
        # No Lyapunov periods after the record: they are not timed, and explicit methods can
        # fail there (rk45's largest step is unstable with 15 elements), failing the whole run.
        cmd = [binary, deck, *overrides, extra, f"&job output='{prefix}' /",
               "&diagnostics lyapunov_periods = 0 /"]
        p = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if p.returncode != 0 or "error:" in p.stdout + p.stderr:
            return None, None, None
        with h5py.File(prefix + ".h5", "r") as f:
            sec = float(f["run/cpu_seconds"][()])
            state = (f["final/u"][()], f["final/v"][()], int(f["run/steps_accepted"][()]))
        best = min(best, sec)
        if sec > 0.2:
            break
    return best, state[:2], state[2]


# ----------------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("model", help="gapbeam transient output PREFIX.h5 (the model)")
    ap.add_argument("reference", help="gapbeam .h5 whose /final state is the reference")
    ap.add_argument("--out", default=None, help="output prefix for the .wp_scipy_*.dat tables")
    ap.add_argument("--title", default=None)
    ap.add_argument("--methods", nargs="+", default=["RK45", "DOP853", "Radau", "LSODA"])
    ap.add_argument("--variants", nargs="*", default=["events", "plain"],
                    choices=["events", "plain"])
    ap.add_argument("--rtols", nargs="+", type=float,
                    default=[10.0 ** -k for k in range(2, 13)])
    ap.add_argument("--atol-scale", type=float, default=1e-6, help="atol = rtol * this")
    ap.add_argument("--repeats", type=int, default=5,
                    help="best of up to this many runs, while a point's runs total < 2 s")
    ap.add_argument("--max-seconds", type=float, default=60.0,
                    help="stop a ladder after a run longer than this")
    ap.add_argument("--gapbeam", default=None, help="gapbeam binary: also time its methods")
    ap.add_argument("--deck", default=None, help="deck for the gapbeam runs")
    ap.add_argument("--override", action="append", default=[],
                    help="namelist override for the gapbeam runs (repeatable)")
    ap.add_argument("--rk4-min-steps", type=int, default=128,
                    help="smallest stable steps_per_period for gapbeam's rk4 ladder")
    ap.add_argument("--diff-only", action="store_true",
                    help="print the relative energy-norm difference of MODEL's /final state "
                         "from REFERENCE's and exit")
    args = ap.parse_args()

    model = Model(args.model)
    with h5py.File(args.reference, "r") as f:
        u_ref, v_ref = f["final/u"][()], f["final/v"][()]
        t_ref = float(f["final/time"][()])
    if abs(t_ref - model.t_end) > 1e-12 * max(1.0, t_ref):
        sys.exit(f"scipy_reference: reference ends at {t_ref}, model run at {model.t_end}")
    norm_ref = model.energy_norm(u_ref, v_ref)
    n = model.n
    if args.diff_only:
        with h5py.File(args.model, "r") as f:
            u, v = f["final/u"][()], f["final/v"][()]
        print("%.6e" % (model.energy_norm(u - u_ref, v - v_ref) / norm_ref))
        return
    if not args.out:
        ap.error("--out is required")
    title = args.title or os.path.basename(args.out)

    def error_of(y):
        return model.energy_norm(y[:n] - u_ref, y[n:] - v_ref) / norm_ref

    print(f"scipy_reference: numpy {np.__version__}, scipy {scipy.__version__}, "
          f"python {sys.version.split()[0]}; OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', '-')}"
          f" OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', '-')}")
    print(f"model: {n} dofs, {model.nc} contacts, t = 0 .. {model.t_end:.10g} s; "
          f"reference {args.reference}; atol = rtol * {args.atol_scale:g}; "
          f"best of up to {args.repeats} (process_time)")

    results = {}
    for variant in args.variants:
        for method in args.methods:
            series = f"scipy_{method}" + ("_events" if variant == "events" else "")
            rows, ladder = [], []
            for rtol in args.rtols:
                atol = rtol * args.atol_scale
                if variant == "events":
                    fn = lambda: integrate_events(model, method, rtol, atol)  # noqa: E731
                else:
                    fn = lambda: integrate_plain(model, method, rtol, atol)   # noqa: E731
                sec, (y, nfev, msg) = timed(fn, args.repeats)
                if y is None:
                    print(f"  {series:24s} rtol {rtol:7.0e}: failed after {sec:.3g} s: {msg}")
                    ladder.append((sec, None))
                else:
                    err = error_of(y)
                    rows.append((sec, err, float("nan"), float(nfev), rtol))
                    ladder.append((sec, err))
                    print(f"  {series:24s} rtol {rtol:7.0e}: {sec:10.4g} s  error {err:9.3e}"
                          f"  {nfev:8d} RHS", flush=True)
                if sec > args.max_seconds:
                    print(f"  {series:24s} stopping the ladder (run > {args.max_seconds:g} s)")
                    break
            write_table(f"{args.out}.wp_{series}.dat", title, series, rows, "rtol")
            results[series] = ladder

    if args.gapbeam:
        deck = args.deck
        with tempfile.TemporaryDirectory() as tmp:
            for name, ladder in gapbeam_ladders(args.rk4_min_steps).items():
                rows, lad = [], []
                for _, extra, par in ladder:
                    sec, st, steps = run_gapbeam(args.gapbeam, deck, args.override, extra, tmp,
                                                 args.repeats)
                    if sec is None:
                        print(f"  gapbeam_{name:16s} {par:9.3g}: failed")
                        lad.append((math.inf, None))
                        continue
                    err = model.energy_norm(st[0] - u_ref, st[1] - v_ref) / norm_ref
                    rows.append((sec, err, float("nan"), float(steps), par))
                    lad.append((sec, err))
                    print(f"  gapbeam_{name:16s} {par:9.3g}: {sec:10.4g} s  error {err:9.3e}"
                          f"  {steps:8d} steps", flush=True)
                pname = {"rk45": "tolerance", "newmark_error": "tolerance", "rk4": "steps per period", "newmark_fixed": "steps per period",
                         "newmark_half_step": "half-step tolerance"}.get(name, "-")
                write_table(f"{args.out}.wp_gapbeam_{name}.dat", title, f"gapbeam_{name}",
                            rows, pname)
                results[f"gapbeam_{name}"] = lad

    print()
    print(f"{title}: time [s] to reach a relative final-state error (energy norm), "
          "log-log interpolation between runs")
    head = "  %-26s" % "series" + "".join("%14s" % ("t(%.0e)" % lv) for lv in LEVELS)
    print(head)
    for series, ladder in results.items():
        print("  %-26s" % series + "".join("%14s" % fmt(cpu_to_reach(ladder, lv))
                                           for lv in LEVELS))
    best_s = {lv: min((x for s, lad in results.items() if s.startswith("scipy")
                       for x in [cpu_to_reach(lad, lv)] if x is not None), default=None)
              for lv in LEVELS}
    best_g = {lv: min((x for s, lad in results.items() if s.startswith("gapbeam")
                       for x in [cpu_to_reach(lad, lv)] if x is not None), default=None)
              for lv in LEVELS}
    print("  %-26s" % "best scipy" + "".join("%14s" % fmt(best_s[lv]) for lv in LEVELS))
    if args.gapbeam:
        print("  %-26s" % "best gapbeam" + "".join("%14s" % fmt(best_g[lv]) for lv in LEVELS))
        print("  %-26s" % "ratio scipy/gapbeam" + "".join(
            "%14s" % ("-" if best_s[lv] is None or best_g[lv] is None
                      else "%.1f" % (best_s[lv] / best_g[lv])) for lv in LEVELS))
        dflt = results.get("gapbeam_auto")
        if dflt is not None:
            print("  %-26s" % "ratio scipy/gapbeam auto" + "".join(
                "%14s" % ("-" if best_s[lv] is None or cpu_to_reach(dflt, lv) is None
                          else "%.1f" % (best_s[lv] / cpu_to_reach(dflt, lv))) for lv in LEVELS))


if __name__ == "__main__":
    main()
