#!/usr/bin/env python3
"""python/tests/test_reader.py - the gapbeam Python reader against h5py, on every analysis.

Usage:
  python3 python/tests/test_reader.py GAPBEAM_EXE        (scripts/test.sh runs it this way,
                                                          with PYTHONPATH=python)
  GAPBEAM_EXE=/path/to/gapbeam python3 -m pytest python/tests
                                                         (without GAPBEAM_EXE only the checks
                                                          on a synthetic file run)

Runs GAPBEAM_EXE on small decks (the decks of inputs/ with short command-line overrides: a few
forcing periods, a few sweep points, a second stop) in a temporary directory: modes, calibrate,
transient (also one whose record the settling test extended: its times on the clock of the
whole trajectory), sweep (independent, continuation, two shards and their merge),
work_precision, stability, model_size, continuation (its parameters, its per-point table, its
output set) and the tube deck (two planes, ring supports: /wear, /orbit, /energy). Each output
file is read with `gapbeam.load` and independently with raw h5py, and compared: the same
datasets, equal values (dtype and shape too), the `units` and every other attribute, the deck
text, path and attribute access. The sweep files also check
`gapbeam.sweep_table` (equal-length columns, the values of the datasets they come from, per-stop
columns) and `gapbeam.poincare` (shapes and values per point); the transient file `poincare`.
A synthetic file with the layout additions to come (root attributes version/commit/date, a
/parameters group, `long_name` attributes, UDUNITS units, variable-length and space-padded
strings, arrays stored the other way round, a new per-point dataset) checks that the reader takes
them.

Every file is also checked for what makes it self-describing (check_conventions): every `units`
attribute parses with the small UDUNITS-2 grammar of python/tests/udunits.py (but the mass-
normalised modal units listed in NOT_UDUNITS, which UDUNITS-2 cannot write), every dataset has
a `long_name`, every 2-D dataset names its axes, the root attributes (version as in fpm.toml,
deck_crc32 = zlib.crc32 of /deck, an ISO 8601 creation time), attributes read as str, the
groups /parameters, /model and /run, and every dataset described by the output catalogue
(python/gapbeam/_catalogue.py, generated from `gapbeam --help-outputs tsv`) with its units, long
name and axes. scripts/output_catalogue.py --check: docs/outputs.md's tables and that module
equal the program's catalogue. A transient with `&output state_history` checks `gapbeam.motion` (the shape
through the nodes) and the .xdmf file: well-formed, every HDF5 item an existing dataset of that
shape, hyperslabs in range, the times those of /history/time.

Output: one line per check, `PASS  python: ...` or `FAIL  python: ... (why)`, then a summary line
`test_reader.py: N checks, M failed`; exit status 1 if a check failed, 2 on bad usage. The runs
use OMP_NUM_THREADS=1 and OPENBLAS_NUM_THREADS=1; each is allowed GAPBEAM_PY_TIMEOUT seconds
(default 300).
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import traceback
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT / "python") not in sys.path:
    sys.path.insert(0, str(ROOT / "python"))

try:
    import h5py
    import numpy as np
except ImportError as exc:  # reported as a failed check by main()
    h5py = np = None
    IMPORT_ERROR = exc
else:
    IMPORT_ERROR = None

# A second stop at node 3 (both sides, 1 mm gap), so that per-stop arrays have two stops.
STOP2 = "&stops node(2) = 3, side(2) = 'both', gap(2) = 1.0e-3, stiffness(2) = 100.0 /"
SHORT = ("&solver transient_periods = 5, record_periods = 10 /",
         "&diagnostics lyapunov_periods = 5 /")
SWEEP_GRID = ("&sweep n_frequency = 0, frequency_hz = 9.5, 10.5, n_amplitude = 0, "
              "amplitude_pp = 2.0e-3, 3.0e-3, 4.0e-3, checkpoint = .false., progress = .false. /")
# The lists have defaults of 7 and 6 entries; given values replace the first ones and 0 ends
# a list, so the trailing zeros shorten them to 2 meshes and 2 x 2 modal models.
MODEL_SIZE = "&model_size elements = 2, 4, 5*0, modes = 1, 2, 4*0 /"
# The tube deck (two planes, two baffles with circular clearances and friction) made small: 6
# elements (baffles at nodes 3 and 5, the force at node 4), a loose tolerance, 2 periods.
TUBE = ("&beam n_elem = 6 / &stops node = 3, 5 / &point_forces node = 4, 4 /",
        "&solver tolerance = 1.0e-3, transient_periods = 0, record_periods = 2 /",
        "&output history_periods = 2 /")
RECORD_PERIODS = 10

# name: (deck, [overrides], analysis, stops, extra command-line arguments)
CASES = {
    "modes": ("inputs/moon_shaw_modes.nml", [], "modes", 1, []),
    "calibrate": ("inputs/derive_width.nml", [], "calibrate", 0, []),
    "transient": ("inputs/moon_shaw_10p5hz.nml",
                  [STOP2, *SHORT, "&output history_periods = 2, filter_cutoff_hz = 40.0 /",
                   "&diagnostics starts = 'deck', 'random', random_starts = 2 /"],
                  "transient", 2, []),
    "sweep_independent": ("inputs/sweep_grid_gap.nml", [SWEEP_GRID, STOP2, *SHORT], "sweep", 2,
                          []),
    "sweep_shard_1": ("inputs/sweep_grid_gap.nml", [SWEEP_GRID, STOP2, *SHORT], "sweep", 2,
                      ["--shard", "1/2"]),
    "sweep_shard_2": ("inputs/sweep_grid_gap.nml", [SWEEP_GRID, STOP2, *SHORT], "sweep", 2,
                      ["--shard", "2/2"]),
    "sweep_continuation": ("inputs/sweep_line_4mm.nml",
                           ["&sweep n_frequency = 3, frequency_end_hz = 9.5, checkpoint = .false.,"
                            " progress = .false. /", *SHORT], "sweep", 1, []),
    # axes over a design variable (the stop gap, x) and the frequency (y), lines along y
    # started up and down, certificates on (issue 11)
    "sweep_starts": ("test/decks/sdof_impact.nml",
                     ["&job analysis = 'sweep' /",
                      "&sweep x_variable = '&stops gap', x_values = 0.0, 1.0, y_variable = "
                      "'&forcing frequency_hz', frequency_hz = 20.75, 21.0, axis = 'y', "
                      "checkpoint = .false., progress = .false. /",
                      "&solver transient_periods = 20, record_periods = 40 /",
                      "&diagnostics lyapunov_periods = 20, lyapunov_max_periods = 20, "
                      "starts = 'up', 'down' /"], "sweep", 1, []),
    "work_precision": ("inputs/work_precision_4el.nml",
                       ["&study levels = 2, periods = 2, repeats = 1 /"], "work_precision", 1, []),
    "stability": ("inputs/stability_4el.nml", ["&study n_omega_dt = 11 /"], "stability", 1, []),
    "model_size": ("inputs/model_size_10p5hz.nml", [MODEL_SIZE, *SHORT], "model_size", 1, []),
    "tube": ("inputs/tube_multispan.nml", list(TUBE), "tube", 2, []),
    "transient_state": ("inputs/moon_shaw_9p8hz.nml",
                        [*SHORT, "&output history_periods = 2, samples_per_period = 16, "
                         "state_history = .true., shape_points = 4 /"], "transient", 1, []),
    # a record extended by the settling test: 2 periods asked, 22 before the record
    "transient_extended": ("inputs/moon_shaw_10p5hz.nml",
                           ["&solver transient_periods = 2, record_periods = 20 /",
                            "&diagnostics settle_tolerance = 1.0e-6, lyapunov_periods = 10 /",
                            "&output history_periods = 2 /"], "transient", 1, []),
    "continuation": ("test/decks/sdof_continuation.nml",
                     ["&continuation parameter_max = 5.0 /", "&output write_text = .true. /"],
                     "continuation", 1, []),
}

# Units that UDUNITS-2 cannot write (it has integer powers only): the mass-normalised modal
# quantities, documented in docs/outputs.md. Any other units attribute must parse.
NOT_UDUNITS = {
    "/modes/shapes": "kg-1/2", "/modes/node_w": "kg-1/2", "/modes/shape_w": "kg-1/2",
    "/modes/participation": "kg1/2",
}
ROOT_ATTRIBUTES = ("program", "version", "git_commit", "compiler", "creation_time", "analysis",
                   "deck_crc32", "units_convention", "axis_order")


class Checks:
    """Prints one PASS/FAIL line per check and counts them."""

    def __init__(self):
        self.n = 0
        self.failed = []

    def check(self, name, ok, why=""):
        self.n += 1
        if ok:
            print("PASS  python: " + name, flush=True)
        else:
            self.failed.append(name)
            print("FAIL  python: {}{}".format(name, " ({})".format(why) if why else ""),
                  flush=True)
        return ok

    def run(self, name, fn):
        """Check that fn() returns True or (False, why) - an exception fails the check."""
        try:
            out = fn()
        except Exception as exc:  # noqa: BLE001 - every error is a failed check
            tb = traceback.extract_tb(exc.__traceback__)[-1]
            return self.check(name, False, "{}: {} at {}:{}".format(
                type(exc).__name__, exc, Path(tb.filename).name, tb.lineno))
        if isinstance(out, tuple):
            return self.check(name, bool(out[0]), out[1] if not out[0] else "")
        return self.check(name, bool(out))


# -- independent reading with raw h5py ---------------------------------------------------------
def raw_text(v):
    """h5py string data decoded by hand (the reference the package is compared against)."""
    if isinstance(v, (bytes, np.bytes_)):
        return bytes(v).decode("utf-8", "replace").rstrip("\x00")
    if isinstance(v, str):
        return v
    if isinstance(v, np.ndarray):
        return [raw_text(x) for x in v.tolist()]
    if isinstance(v, list):
        return [raw_text(x) for x in v]
    return v


def raw_datasets(path):
    """{path: (value, attrs)} of every dataset, {path: attrs} of every group, root attrs."""
    data, groups = {}, {}
    with h5py.File(path, "r") as f:
        root_attrs = {k: f.attrs[k] for k in f.attrs}

        def visit(name, obj):
            attrs = {k: obj.attrs[k] for k in obj.attrs}
            if isinstance(obj, h5py.Dataset):
                data["/" + name] = (obj[()], obj.dtype, attrs)
            else:
                groups["/" + name] = attrs

        f.visititems(visit)
    return data, groups, root_attrs


def same_value(q, raw, dtype):
    """True (or (False, why)) when a Quantity equals a raw h5py value."""
    if dtype.kind in "SO":
        got = q.values
        want = raw_text(raw)
        if np.ndim(raw) == 0:
            return (isinstance(got, str) and got == want, "{!r} != {!r}".format(got, want))
        ok = (isinstance(got, np.ndarray) and got.dtype.kind == "U" and got.shape == raw.shape
              and got.ravel().tolist() == np.asarray(want, dtype=object).ravel().tolist())
        return (ok, "{!r} != {!r}".format(got, want))
    got = q.values
    ok = (isinstance(got, np.ndarray) and got.dtype == dtype and got.shape == np.shape(raw)
          and np.array_equal(got, raw, equal_nan=dtype.kind == "f"))
    if isinstance(got, np.ndarray) and got.dtype == dtype and got.shape == np.shape(raw):
        return (ok, "values differ")
    return (ok, "{} {} != {} {}".format(getattr(got, "dtype", type(got)), np.shape(got), dtype,
                                        np.shape(raw)))


def same_attrs(decoded, raw):
    if set(decoded) != set(raw):
        return False
    for k, v in raw.items():
        d = decoded[k]
        if isinstance(v, (bytes, np.bytes_, str)):
            if d != raw_text(v):
                return False
        elif isinstance(v, np.ndarray) and v.dtype.kind in "SO":
            if np.asarray(d).ravel().tolist() != raw_text(v):
                return False
        elif not np.array_equal(np.asarray(d), np.asarray(v)):
            return False
    return True


def attr_walk(res, path):
    """The member at an absolute path reached by attribute access, or None where a name is not
    an identifier or is shadowed by an attribute of the class (res.deck is the deck text)."""
    node = res
    for part in path.strip("/").split("/"):
        if not part.isidentifier() or hasattr(type(node), part) or part in vars(node):
            return None
        node = getattr(node, part)
    return node


# -- checks ------------------------------------------------------------------------------------
def check_file(c, gapbeam, name, path, analysis):
    """The checks every result file gets; returns the Result (or None)."""
    res = None
    try:
        res = gapbeam.load(path)
    except Exception as exc:  # noqa: BLE001
        c.check("{}: gapbeam.load".format(name), False, repr(exc))
        return None
    data, groups, root_attrs = raw_datasets(path)
    ds = res.datasets()

    c.check("{}: analysis is '{}'".format(name, analysis), res.analysis == analysis,
            "got {!r}".format(res.analysis))
    c.check("{}: the same {} datasets as h5py".format(name, len(data)),
            set(ds) == set(data) and len(data) > 0,
            "only in reader: {}; only in h5py: {}".format(sorted(set(ds) - set(data)),
                                                          sorted(set(data) - set(ds))))

    def values_equal():
        bad = []
        for p, (raw, dtype, _) in data.items():
            out = same_value(ds[p], raw, dtype) if p in ds else (False, "missing")
            if not out[0]:
                bad.append("{}: {}".format(p, out[1]))
        return (not bad, "; ".join(bad[:3]))

    c.run("{}: every dataset's values, dtype and shape equal h5py's".format(name), values_equal)

    def units_equal():
        bad = []
        for p, (_, _, attrs) in data.items():
            q = ds.get(p)
            want = raw_text(attrs.get("units"))
            if q is None or not isinstance(q.units, str) or not q.units or q.units != want:
                bad.append("{}: {!r} vs {!r}".format(p, getattr(q, "units", None), want))
            elif q.long_name != (raw_text(attrs["long_name"]) if "long_name" in attrs else None):
                bad.append("{}: long_name {!r}".format(p, q.long_name))
        return (not bad, "; ".join(bad[:3]))

    c.run("{}: every dataset has units, equal to its h5py 'units' attribute".format(name),
          units_equal)

    def attrs_equal():
        bad = [p for p, (_, _, a) in data.items() if not same_attrs(ds[p].attrs, a)]
        bad += [p for p, a in groups.items() if not same_attrs(res[p].attrs, a)]
        if not same_attrs(res.attrs, root_attrs):
            bad.append("/")
        return (not bad, "differ: {}".format(bad[:5]))

    c.run("{}: attributes of datasets, groups and root equal h5py's".format(name), attrs_equal)

    def deck_equal():
        want = raw_text(data["/deck"][0]) if "/deck" in data else None
        ok = (want is not None and res.deck == want and "&job" in res.deck.lower()
              and gapbeam.deck_value(res.deck, "job", "analysis") == analysis)
        return (ok, "deck_value(analysis) = {!r}".format(
            gapbeam.deck_value(res.deck, "job", "analysis")))

    c.run("{}: res.deck equals /deck and names analysis '{}'".format(name, analysis), deck_equal)

    def access_equal():
        bad = []
        for p, q in ds.items():
            if res[p] is not q or res[p.lstrip("/")] is not q:
                bad.append(p + " (item)")
            walked = attr_walk(res, p)
            if walked is not None and walked is not q:
                bad.append(p + " (attribute)")
            parent, _, leaf = p.rpartition("/")
            g = res[parent] if parent else res
            if g[leaf] is not q or leaf not in g:
                bad.append(p + " (relative)")
        return (not bad, "; ".join(bad[:3]))

    c.run("{}: attribute, absolute and relative path access agree".format(name), access_equal)
    return res


def check_sweep(c, gapbeam, name, res, n_stops, points=None):
    path = res.filename
    data, _, _ = raw_datasets(path)
    m = len(data["/sweep/frequency_hz"][0])
    if points is not None:
        c.check("{}: points {} in the file".format(name, points),
                data["/sweep/point_index"][0].tolist() == points,
                "got {}".format(data["/sweep/point_index"][0].tolist()))
    t = gapbeam.sweep_table(res)

    def lengths():
        bad = [k for k, v in t.items() if not (isinstance(v, np.ndarray) and v.shape == (m,))]
        return (not bad and len(t) >= 10, "not 1-D of length {}: {}".format(m, bad))

    c.run("{}: sweep_table has {} columns, all 1-D of length {}".format(name, len(t), m), lengths)

    def values():
        bad = []
        for k in ("point_index", "frequency_hz", "amplitude_pp", "period", "label",
                  "lyapunov", "lyapunov_error", "status", "steps", "seconds"):
            if not np.array_equal(t[k], data["/sweep/" + k][0], equal_nan=True):
                bad.append(k)
        if t["label_text"].tolist() != raw_text(data["/sweep/label_text"][0]):
            bad.append("label_text")
        for stat in ("count", "peak_force", "rms_force", "contact_fraction",
                     "impulse_per_period", "work_rate"):
            raw = data["/sweep/impacts/" + stat][0]          # h5py: (m, n_stops), point first
            for s in range(n_stops):
                if not np.array_equal(t["{}_{}".format(stat, s + 1)], raw[:, s], equal_nan=True):
                    bad.append("{}_{}".format(stat, s + 1))
        for stat in ("normal_work_rate", "sliding_distance", "friction_work_rate",
                     "wear_volume_rate"):
            raw = data["/sweep/wear/" + stat][0]             # h5py: (m, n_stops), point first
            for s in range(n_stops):
                if not np.array_equal(t["{}_{}".format(stat, s + 1)], raw[:, s], equal_nan=True):
                    bad.append("{}_{}".format(stat, s + 1))
        return (not bad, "differ: {}".format(bad))

    c.run("{}: sweep_table columns equal the h5py datasets (per stop: columns of "
          "/sweep/impacts/* and /sweep/wear/*)".format(name), values)

    def stops():
        cols = sorted(k for k in t if k.startswith("peak_force_"))
        return (cols == ["peak_force_{}".format(s + 1) for s in range(n_stops)], str(cols))

    c.run("{}: sweep_table has the statistics of {} stop(s)".format(name, n_stops), stops)

    def units():
        bad = [k for k in t if not isinstance(t.units.get(k), str)]
        ok = t.units["frequency_hz"] == raw_text(data["/sweep/frequency_hz"][2]["units"])
        return (not bad and ok and t.units["peak_force_1"] == "N", "no units: {}".format(bad))

    c.run("{}: sweep_table units for every column".format(name), units)

    def grid_index():
        gf = data["/sweep/grid_frequency_hz"][0]
        ga = data["/sweep/grid_amplitude_pp"][0]
        return (np.array_equal(gf[t["frequency_index"] - 1], t["frequency_hz"])
                and np.array_equal(ga[t["amplitude_index"] - 1], t["amplitude_pp"]))

    c.run("{}: frequency_index and amplitude_index pick the point's grid values".format(name),
          grid_index)

    def per_point():
        strain = data["/sweep/poincare/strain"][0]            # h5py: (m, record_periods)
        rate = data["/sweep/poincare/strain_rate"][0]
        bad = []
        for r, p in enumerate(data["/sweep/point_index"][0]):
            s = gapbeam.poincare(res, point=int(p))
            x, y = s
            if not (x.shape == (RECORD_PERIODS,) and y.shape == (RECORD_PERIODS,)
                    and np.array_equal(x, strain[r]) and np.array_equal(y, rate[r])
                    and s.frequency_hz == data["/sweep/frequency_hz"][0][r]
                    and s.amplitude_pp == data["/sweep/amplitude_pp"][0][r] and s.point == p):
                bad.append(int(p))
        return (not bad, "points {}".format(bad))

    c.run("{}: poincare(point=p) of every point: ({},) strain and strain rate equal "
          "h5py".format(name, RECORD_PERIODS), per_point)

    def whole():
        s = gapbeam.poincare(res)
        return (s.strain.shape == (m, RECORD_PERIODS) and s.strain_rate.shape == (m, RECORD_PERIODS)
                and np.array_equal(s.strain, data["/sweep/poincare/strain"][0])
                and s.frequency_hz.shape == (m,) and s.units["strain_rate"] == "s-1",
                "shape {}".format(s.strain.shape))

    c.run("{}: poincare() of the whole sweep has shape ({}, {})".format(name, m, RECORD_PERIODS),
          whole)

    def missing():
        p = int(max(data["/sweep/point_index"][0])) + 100
        try:
            gapbeam.poincare(res, point=p)
        except ValueError:
            return True
        return (False, "no ValueError")

    c.run("{}: poincare() of a point not in the file is a ValueError".format(name), missing)

    def cpu_within_wall():
        # issue 10 item 6: CPU time of the process <= wall time x threads (merges have no /run)
        if "/run/cpu_seconds" not in data:
            return (name == "sweep_merged", "no /run/cpu_seconds")
        cpu = float(data["/run/cpu_seconds"][0])
        wall = float(data["/run/wall_seconds"][0])
        threads = int(data["/run/threads"][0])
        return (0.0 <= cpu <= wall * threads + 1e-3 and threads >= 1,
                "cpu {} s, wall {} s, {} threads".format(cpu, wall, threads))

    c.run("{}: /run/cpu_seconds <= /run/wall_seconds x /run/threads".format(name), cpu_within_wall)

    def exponent_counts():
        # the exponent's starts and its pair's rerun / dropped periods, per point (one start
        # where an exponent ran, none where not; 0 <= dropped <= rerun <= periods)
        n = data["/sweep/lyapunov_periods"][0]
        starts = data["/sweep/lyapunov_starts"][0]
        rerun = data["/sweep/lyapunov_rerun"][0]
        dropped = data["/sweep/lyapunov_dropped"][0]
        ok = (np.array_equal(starts, np.where(n > 0, 1, 0))
              and np.all((0 <= dropped) & (dropped <= rerun) & (rerun <= n))
              and np.all(data["/sweep/lyapunov_spread"][0] == 0.0))
        return (ok, "starts {}, rerun {}, dropped {}".format(starts, rerun, dropped))

    c.run("{}: lyapunov_starts, _rerun, _dropped, _spread of every point".format(name),
          exponent_counts)

    try:
        import pandas as pd
    except ImportError:
        pd = None
    if pd is not None:
        c.run("{}: pandas.DataFrame(sweep_table) has {} rows".format(name, m),
              lambda: pd.DataFrame(t).shape == (m, len(t)))
    return t


def check_transient(c, gapbeam, res, n_stops):
    data, _, _ = raw_datasets(res.filename)

    def pset():
        s = gapbeam.poincare(res)
        x, y = s
        return (x.shape == (RECORD_PERIODS,) and y.shape == (RECORD_PERIODS,)
                and np.array_equal(x, data["/poincare/strain"][0])
                and np.array_equal(y, data["/poincare/strain_rate"][0])
                and np.array_equal(s.time, data["/poincare/time"][0])
                and abs(s.frequency_hz - 10.5) < 1e-9 and abs(s.amplitude_pp - 3.7e-3) < 1e-12
                and s.units == {"strain": "1", "strain_rate": "s-1", "time": "s"},
                "shape {}, f {}, A {}".format(x.shape, s.frequency_hz, s.amplitude_pp))

    c.run("transient: poincare() gives ({},) strain and strain rate equal to /poincare/* and "
          "the forcing".format(RECORD_PERIODS), pset)

    def point_refused():
        try:
            gapbeam.poincare(res, point=1)
        except ValueError:
            return True
        return (False, "no ValueError")

    c.run("transient: poincare(point=1) is a ValueError", point_refused)
    c.check("transient: /history/stop_force holds {} stops (h5py shape (n_hist, n_stops), "
            "dimensions 'sample stop')".format(n_stops),
            res.history.stop_force.shape[1] == n_stops
            and res.history.stop_force.attrs.get("dimensions") == "sample stop",
            str(res.history.stop_force.shape))


def check_tube(c, res, n_stops):
    """The wear, orbit and energy datasets of a two-plane run with ring supports."""
    data, _, _ = raw_datasets(res.filename)

    def wear():
        bad = []
        for stat in ("normal_work_rate", "sliding_distance", "friction_work",
                     "friction_work_rate", "wear_volume_rate", "wear_coefficient",
                     "stick_fraction"):
            q = res["/wear/" + stat]
            if not (q.shape == (n_stops,) and np.array_equal(np.asarray(q.values),
                                                             data["/wear/" + stat][0])):
                bad.append(stat)
        return (not bad, "differ or not one per stop: {}".format(bad))

    c.run("tube: /wear/* has one value per support, equal to h5py", wear)

    def orbit():
        n_hist = data["/history/time"][0].shape[0]
        bad = [k for k in ("w", "v", "normal_force", "tangential_force")
               if data["/orbit/" + k][0].shape != (n_hist, n_stops)]
        return (not bad and res["/orbit/gap"].shape == (n_stops,), "shapes: {}".format(bad))

    c.run("tube: /orbit/* holds (samples, supports) and the gaps", orbit)
    c.check("tube: the wear outputs carry units", res["/wear/wear_volume_rate"].units == "m3 s-1"
            and res["/wear/normal_work_rate"].units == "W")
    c.check("tube: /energy is there with its imbalance", "/energy/imbalance" in data)


def check_starts(c, gapbeam, name, res):
    """A sweep over a design variable with two starts per point and certificates (issue 11)."""
    data, _, _ = raw_datasets(res.filename)
    m = len(data["/sweep/point_index"][0])
    t = gapbeam.sweep_table(res)

    def axes():
        gx, gy = data["/sweep/grid_x"][0], data["/sweep/grid_y"][0]
        return (m == 4 and np.array_equal(gx[t["x_index"] - 1], t["x"])
                and np.array_equal(gy[t["y_index"] - 1], t["y"])
                and np.array_equal(t["frequency_index"], t["y_index"])
                and np.array_equal(t["frequency_hz"], t["y"])
                and raw_text(data["/sweep/x_variable"][0]) == "&stops gap(1)"
                and t.units["x"] == "m", repr(t))

    c.run("{}: x_index/y_index pick the axis values, the frequency is the y axis".format(name),
          axes)

    def certificates():
        cert = t["certificate"]
        texts = t["certificate_text"].tolist()
        reasons = t["certificate_reason"].tolist()
        ok = all(x in (1, 2) for x in cert) and all(
            r.startswith(x + ":") for x, r in zip(texts, reasons))
        return (ok and "lyapunov_periods" in t and "window_difference" in t
                and "transient_periods" in t, "certificates {} {}".format(cert, reasons))

    c.run("{}: every point certified or disputed, with its reason and its evidence".format(name),
          certificates)

    def starts():
        a = gapbeam.attractors(res)
        raw = data["/sweep/starts/label"][0]                   # h5py: (m, n_starts)
        rows_ok = a.n_rows == 2 * m and a["kind"].tolist()[:2] == ["up", "down"]
        labels_ok = all(a["label"][2 * j + k] == raw[j][k] for j in range(m) for k in range(2))
        n_attr = data["/sweep/n_attractors"][0]
        attr_ok = all(max(a["attractor"][2 * j:2 * j + 2]) == n_attr[j] for j in range(m))
        frac_ok = np.allclose([a["attractor_fraction"][2 * j:2 * j + 2].sum() for j in range(m)
                               if n_attr[j] == 1], 2.0)
        return (rows_ok and labels_ok and attr_ok and frac_ok, repr(dict(a)))

    c.run("{}: attractors() has a row per point and start, matching /sweep/starts".format(name),
          starts)


def check_transient_starts(c, gapbeam, res):
    """A transient run from the deck's start and two random ones (issue 11)."""
    def starts():
        a = gapbeam.attractors(res)
        return (a.n_rows == 3 and a["start"].tolist() == [1, 2, 3]
                and np.isclose(sum(a["attractor_fraction"][a["attractor"] == a["attractor"][0]])
                               / sum(a["attractor"] == a["attractor"][0]),
                               res["/diagnostics/attractors/fraction"].values[
                                   a["attractor"][0] - 1]), repr(dict(a)))

    c.run("transient: attractors() has a row per start", starts)
    c.check("transient: the certificate and its reason are written",
            res["/diagnostics/certificate"].values in (1, 2)
            and isinstance(res["/diagnostics/certificate_reason"].values, str))


def check_no_poincare(c, gapbeam, name, res):
    def refused():
        try:
            gapbeam.poincare(res)
        except ValueError:
            pass
        else:
            return (False, "no ValueError")
        try:
            gapbeam.sweep_table(res)
        except ValueError:
            return True
        return (False, "sweep_table: no ValueError")

    c.run("{}: poincare() and sweep_table() are ValueErrors".format(name), refused)


def check_synthetic(c, gapbeam, workdir):
    """A file with the layout additions to come, written with h5py."""
    path = Path(workdir) / "future.h5"
    m, n_rec, n_stops = 3, 4, 2
    rng = np.random.default_rng(1)
    strain = rng.normal(size=(n_rec, m))   # stored the other way round: (periods, points)
    peak = rng.random((m, n_stops))        # (points, stops)
    with h5py.File(path, "w") as f:
        f.attrs["version"] = "0.2.0"
        f.attrs["commit"] = np.bytes_(b"0123abc")
        f.attrs["date"] = "2025-01-01T00:00:00Z"
        f.attrs["format"] = np.int32(2)
        f.create_dataset("deck", data="&job analysis = 'sweep' /\n&sweep frequency_hz = 9.5 /",
                         dtype=h5py.string_dtype())
        p = f.create_group("parameters")
        p.attrs["beam_length"] = 0.2
        p.create_dataset("beam/length", data=0.2).attrs["units"] = "m"
        s = f.create_group("sweep")

        def put(name, value, units, long_name=None, **kw):
            d = s.create_dataset(name, data=value, **kw)
            d.attrs["units"] = units
            if long_name:
                d.attrs["long_name"] = long_name
            return d

        put("point_index", np.array([1, 2, 3], np.int32), "1", "point number")
        put("frequency_hz", np.array([9.5, 10.0, 10.5]), "Hz", "forcing frequency")
        put("amplitude_pp", np.full(3, 2e-3), "m", "base amplitude, peak to peak")
        put("grid_frequency_hz", np.array([9.5, 10.0, 10.5]), "Hz")
        put("grid_amplitude_pp", np.array([2e-3]), "m")
        put("label", np.array([1, -1, 0], np.int32), "1")
        tid = h5py.h5t.C_S1.copy()
        tid.set_size(12)
        tid.set_strpad(h5py.h5t.STR_SPACEPAD)
        sp = h5py.h5d.create(s.id, b"label_text", tid, h5py.h5s.create_simple((3,)))
        sp.write(h5py.h5s.ALL, h5py.h5s.ALL,
                 np.array([b"period_1    ", b"chaotic     ", b"undecided   "], dtype="S12"))
        s["label_text"].attrs["units"] = "1"
        put("new_metric", np.array([0.5, 0.25, 0.125]), "m s-1", "a dataset added later")
        put("cube", np.zeros((2, 3, 4)), "1")
        put("impacts/peak_force", peak, "N", "largest stop force")
        put("poincare/strain", strain, "1", "root strain at the section")
        put("poincare/strain_rate", 2 * strain, "s-1", "root strain rate at the section")

    res = gapbeam.load(path)

    def top():
        ok = (res.analysis == "sweep" and res.attrs["version"] == "0.2.0"
              and res.attrs["commit"] == "0123abc" and res.attrs["format"] == 2
              and res.deck.startswith("&job analysis = 'sweep'")
              and float(res.parameters.beam.length) == 0.2
              and res["/parameters"].attrs["beam_length"] == 0.2)
        return (ok, "analysis {!r}, attrs {}".format(res.analysis, res.attrs))

    c.run("synthetic: root attributes, variable-length deck and /parameters are read", top)

    def names():
        q = res.sweep.new_metric
        return (q.units == "m s-1" and q.long_name == "a dataset added later"
                and res.sweep.label.units == "1" and res.sweep.cube.shape == (2, 3, 4)
                and res.sweep.label_text.values.tolist() == ["period_1", "chaotic", "undecided"],
                repr(res.sweep.label_text.values))

    c.run("synthetic: long_name, UDUNITS units, space-padded strings, a 3-D dataset", names)

    def table():
        t = gapbeam.sweep_table(res)
        ok = (t.n_rows == m and np.array_equal(t["new_metric"], [0.5, 0.25, 0.125])
              and "grid_frequency_hz" not in t and "cube" not in t
              and np.array_equal(t["peak_force_2"], peak[:, 1])
              and t.long_names["peak_force_1"] == "largest stop force"
              and t.units["new_metric"] == "m s-1")
        return (ok, repr(t))

    c.run("synthetic: sweep_table takes a new per-point dataset and (points, stops) arrays", table)

    def pset():
        s = gapbeam.poincare(res, point=2)
        w = gapbeam.poincare(res)
        return (np.array_equal(s.strain, strain[:, 1]) and np.array_equal(s.strain_rate,
                                                                          2 * strain[:, 1])
                and w.strain.shape == (m, n_rec) and s.units["strain"] == "1")

    c.run("synthetic: poincare() takes (periods, points) arrays", pset)


# -- running gapbeam ---------------------------------------------------------------------------
def run_gapbeam(exe, args, workdir, timeout):
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    p = subprocess.run([exe, *args], cwd=workdir, env=env, timeout=timeout,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout


def run_cases(c, exe, workdir, timeout):
    """Run every case; returns {name: h5 path} of those that produced a file."""
    files = {}
    for name, (deck, overrides, _, _, extra) in CASES.items():
        prefix = str(Path(workdir) / name)
        deck_path = str(ROOT / deck)
        if name.startswith("sweep_shard"):
            prefix = str(Path(workdir) / "sweep_sharded")
        args = [deck_path, *extra, *overrides, "&job output = '{}' /".format(prefix)]
        try:
            status, out = run_gapbeam(exe, args, workdir, timeout)
        except subprocess.TimeoutExpired:
            status, out = -1, "timed out after {} s".format(timeout)
        h5 = prefix + (".shard_{}_of_2".format(name[-1]) if name.startswith("sweep_shard")
                       else "") + ".h5"
        if c.check("{}: gapbeam {} runs".format(name, Path(deck).name),
                   status == 0 and os.path.isfile(h5),
                   "status {}: {}".format(status, out.strip().splitlines()[-3:])):
            files[name] = h5
    if "sweep_shard_1" in files and "sweep_shard_2" in files:
        merged = str(Path(workdir) / "sweep_merged.h5")
        status, out = run_gapbeam(exe, ["merge", merged, files["sweep_shard_1"],
                                        files["sweep_shard_2"]], workdir, timeout)
        if c.check("sweep_merged: gapbeam merge of the two shards", status == 0
                   and os.path.isfile(merged), "status {}: {}".format(status, out[-300:])):
            files["sweep_merged"] = merged
    return files


def check_conventions(c, name, path, analysis):
    """Self-describing files: units that UDUNITS-2 parses, long_name on every dataset, axis
    names on every 2-D dataset, root attributes (version as in fpm.toml, the deck's CRC-32, an
    ISO 8601 time), attributes that h5py reads as str, and the /parameters group."""
    import zlib

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import udunits

    bad_units, no_long, no_dims, not_str = [], [], [], []
    with h5py.File(path, "r") as f:
        root = dict(f.attrs)

        def visit(n, obj):
            p = "/" + n
            for k, v in obj.attrs.items():
                if not isinstance(v, str):
                    not_str.append("{}@{}".format(p, k))
            if not isinstance(obj, h5py.Dataset):
                return
            u = obj.attrs.get("units")
            try:
                udunits.parse(u)
            except ValueError as exc:
                if NOT_UDUNITS.get(p) != u:
                    bad_units.append("{} {!r}: {}".format(p, u, exc))
            if not obj.attrs.get("long_name"):
                no_long.append(p)
            if obj.ndim >= 2 and len(str(obj.attrs.get("dimensions", "")).split()) != obj.ndim:
                no_dims.append(p)

        f.visititems(visit)
        deck = f["/deck"][()]
        deck = deck.decode("utf-8") if isinstance(deck, bytes) else deck
        has_parameters = "parameters" in f and len(f["parameters"]) > 0
        groups = [g for g in ("parameters", "model", "run") if g not in f or len(f[g]) == 0]
        not_described = catalogue_differences(f, analysis)
    c.check("{}: every units attribute parses as UDUNITS-2 (but the documented "
            "mass-normalised ones)".format(name), not bad_units, "; ".join(bad_units[:5]))
    c.check("{}: every dataset has a long_name".format(name), not no_long, str(no_long[:8]))
    c.check("{}: every 2-D dataset names its axes (dimensions)".format(name), not no_dims,
            str(no_dims))
    c.check("{}: every attribute reads as str in h5py (UTF-8, variable length)".format(name),
            not not_str, str(not_str[:5]))
    missing = [k for k in ROOT_ATTRIBUTES if k not in root]
    version = re.search(r'^version\s*=\s*"([^"]+)"', (ROOT / "fpm.toml").read_text(), re.M)
    c.check("{}: root attributes {} present, analysis '{}', version as in fpm.toml".format(
        name, "/".join(ROOT_ATTRIBUTES), analysis),
        not missing and root.get("analysis") == analysis and version is not None
        and root.get("version") == version.group(1),
        "missing {}, analysis {!r}, version {!r}".format(missing, root.get("analysis"),
                                                         root.get("version")))
    c.check("{}: deck_crc32 is zlib's CRC-32 of /deck".format(name),
            root.get("deck_crc32") == "{:08x}".format(zlib.crc32(deck.encode("utf-8"))),
            "{} vs {:08x}".format(root.get("deck_crc32"), zlib.crc32(deck.encode("utf-8"))))
    c.check("{}: creation_time is ISO 8601 with its UTC offset".format(name),
            re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d[+-]\d\d:\d\d",
                         str(root.get("creation_time"))) is not None,
            str(root.get("creation_time")))
    c.check("{}: /parameters holds the resolved model".format(name), has_parameters)
    c.check("{}: /deck, /parameters, /model and /run are there".format(name), not groups,
            "missing or empty: {}".format(groups))
    c.check("{}: every dataset has the units, long_name and axes of the output catalogue "
            "(python/gapbeam/_catalogue.py)".format(name), not not_described,
            "; ".join(not_described[:5]))


def catalogue_pattern(text):
    """A regular expression for a catalogue path or long name: `<...>` any path component,
    `{...}` any text."""
    out = ""
    for part in re.split(r"(<[^>]*>|\{[^}]*\})", text):
        if part.startswith("<"):
            out += "[^/]+"
        elif part.startswith("{"):
            out += ".*"
        else:
            out += re.escape(part)
    return re.compile(out + r"\Z", re.S)


def catalogue_differences(f, analysis):
    """The datasets of an open file whose path, units, long_name or dimensions are not those
    of the catalogue entry for their analysis (python/gapbeam/_catalogue.py)."""
    from gapbeam._catalogue import DATASETS

    entries = [(catalogue_pattern(p), u, d, catalogue_pattern(l))
               for _, a, p, u, d, l in DATASETS if analysis in a]
    bad = []

    def visit(n, obj):
        if not isinstance(obj, h5py.Dataset):
            return
        path = "/" + n
        entry = next((e for e in entries if e[0].match(path)), None)
        if entry is None:
            bad.append(path + ": not in the catalogue")
            return
        _, units, dims, long_name = entry
        attrs = obj.attrs
        names = " ".join(w.split("=")[0] for w in dims.split()) if obj.ndim >= 2 else None
        if not units.startswith("=") and attrs.get("units") != units:
            bad.append("{}: units {!r}, catalogue {!r}".format(path, attrs.get("units"), units))
        if not long_name.match(str(attrs.get("long_name"))):
            bad.append("{}: long_name {!r}".format(path, attrs.get("long_name")))
        if len(dims.split()) != obj.ndim or attrs.get("dimensions") != names:
            bad.append("{}: rank {} dimensions {!r}, catalogue {!r}".format(
                path, obj.ndim, attrs.get("dimensions"), dims))

    f.visititems(visit)
    return bad


def check_time_origin(c, res):
    """A record extended by the settling test: its times are those of the whole trajectory."""
    period = 1.0 / 10.5
    n = int(res["/diagnostics/transient_periods"].values)
    t0 = float(res["/history/time"].values[0])
    p0 = float(res["/poincare/time"].values[0])
    t_end = float(res["/final/time"].values)
    c.check("transient_extended: the record was extended ({} > 2 transient periods)".format(n),
            n > 2)
    c.check("transient_extended: /history/time, /poincare/time and /final/time start at "
            "transient_periods T ({} periods) and end 20 periods later".format(n),
            abs(t0 - n * period) < 1e-9 and abs(p0 - n * period) < 1e-9
            and abs(t_end - (n + 20) * period) < 1e-9,
            "history {:.6f} T, poincare {:.6f} T, end {:.6f} T".format(
                t0 / period, p0 / period, t_end / period))


def check_continuation(c, gapbeam, res, path):
    """A continuation file: its parameters, its per-point table, its sibling tables."""
    p = gapbeam.parameters(res)
    c.check("continuation: parameters() gives the model (stop gap in m, the forcing)",
            p.get("stops/gap") is not None and p["stops/gap"].units == "m"
            and "forcing/frequency_hz" in p and "beam/length" in p, str(sorted(p)[:5]))
    t = gapbeam.table(res.continuation)
    n = len(res["/continuation/parameter"].values)
    c.check("continuation: table(res.continuation) has one row per point ({}) with the "
            "parameter, period, branch and stability".format(n),
            t.n_rows == n and {"parameter", "period", "branch", "stable"} <= set(t)
            and t.units["parameter"] == "Hz", repr(t))
    files = [str(x) for x in np.atleast_1d(res["/run/files"].values)]
    stem = Path(path).name[:-3]
    c.check("continuation: /run/files lists the .h5 and its four tables, all there",
            files == [stem + s for s in (".h5", ".branches.dat", ".bifurcations.dat",
                                         ".multipliers.dat", ".curves.dat")]
            and all((Path(path).parent / x).exists() for x in files), str(files))


def check_catalogue_docs(c, exe):
    """docs/outputs.md's tables and python/gapbeam/_catalogue.py equal the program's catalogue."""
    p = subprocess.run([sys.executable, str(ROOT / "scripts" / "output_catalogue.py"), exe,
                        "--check"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    c.check("docs/outputs.md and python/gapbeam/_catalogue.py come from `gapbeam "
            "--help-outputs` (scripts/output_catalogue.py --check)", p.returncode == 0,
            p.stdout.strip().replace("\n", "; "))


def check_state(c, gapbeam, path):
    """The state history: the Hermite shape through the nodes, the XDMF file beside the HDF5
    file well-formed and pointing at datasets that exist, with matching sizes and times."""
    import xml.etree.ElementTree as ET

    res = gapbeam.load(path)
    m = gapbeam.motion(res)
    per = (len(m.x) - 1) // (len(m.node_x) - 1)
    c.check("transient_state: motion() shape passes through the nodes and ends at the tip",
            np.allclose(m.w[:, ::per], m.node_w, rtol=0, atol=1e-15)
            and np.allclose(m.w[:, -1], res.history.tip_displacement.values, rtol=0, atol=1e-15)
            and m.w.shape == (len(m.time), len(m.x)),
            "shapes {} {}".format(m.w.shape, m.node_w.shape))
    p = gapbeam.parameters(res)
    c.check("transient_state: parameters() gives the beam with units",
            p["beam/length"].units == "m" and abs(float(p["beam/length"]) - 0.2) < 1e-12
            and p["root/kappa"].units == "1", str(sorted(p)[:5]))
    xdmf = path[:-3] + ".xdmf"
    try:
        tree = ET.parse(xdmf)
    except (OSError, ET.ParseError) as exc:
        c.check("transient_state: the .xdmf file is well-formed XML", False, str(exc))
        return
    c.check("transient_state: the .xdmf file is well-formed XML", True)
    problems = []
    grids = tree.getroot().findall("./Domain/Grid/Grid")
    times = [float(g.find("Time").get("Value")) for g in grids]
    if not np.allclose(times, res.history.time.values, rtol=1e-15, atol=0):
        problems.append("times differ from /history/time")
    with h5py.File(path, "r") as f:
        for g in grids:
            for item in g.iter("DataItem"):
                if item.get("Format") != "HDF":
                    continue
                fname, _, dset = item.text.strip().partition(":")
                dims = tuple(int(d) for d in item.get("Dimensions").split())
                if Path(fname).name != Path(path).name or "/" in fname:
                    problems.append("names file {}".format(fname))
                elif dset not in f:
                    problems.append("no dataset {}".format(dset))
                elif f[dset].shape != dims:
                    problems.append("{} has shape {}, the XDMF says {}".format(
                        dset, f[dset].shape, dims))
            for slab in g.iter("DataItem"):
                if slab.get("ItemType") != "HyperSlab":
                    continue
                sel, src = list(slab)
                n = int(src.get("Dimensions").split()[0])
                start = int(sel.text.split()[0])
                if not 0 <= start < n:
                    problems.append("hyperslab start {} outside 0..{}".format(start, n - 1))
    c.check("transient_state: every HDF5 item of the .xdmf exists with its shape, every "
            "hyperslab in range, times equal /history/time ({} grids)".format(len(grids)),
            not problems and len(grids) == len(res.history.time.values), str(problems[:5]))
    # the per-sample values the .xdmf addresses as raw bytes inside the .h5 file (Format="Binary"
    # Seek="...", the slice form both of ParaView's readers accept): read them there
    raw_problems, n_raw = [], 0
    want_of = {"w [m]": "/history/shape_w", "v [m]": "/history/shape_v",
               "displacement [m]": "/history/shape_displacement"}
    with h5py.File(path, "r") as f:
        for i in sorted({0, len(grids) - 1}):
            for grid in grids[i].iter("Grid"):
                for att in grid.findall("Attribute"):
                    item = att.find("DataItem")
                    if item is None or item.get("Format") != "Binary":
                        continue
                    dims = [int(d) for d in item.get("Dimensions").split()]
                    dtype = ("<" if item.get("Endian") == "Little" else ">") + (
                        "f8" if item.get("NumberType") == "Float" else "i4")
                    raw = np.fromfile(Path(path).parent / item.text.strip(), dtype=dtype,
                                      count=int(np.prod(dims)), offset=int(item.get("Seek")))
                    name = att.get("Name")
                    if grid.get("Name") == "beam" and name in want_of:
                        want = f[want_of[name]][i].ravel()
                    elif name == "stop force [N]":
                        j = int(grid.get("Name").split()[1]) - 1
                        want = f["/history/stop_force"][i, j:j + 1]
                    elif name.startswith("contact"):
                        j = int(grid.get("Name").split()[1]) - 1
                        want = f["/history/stop_contact"][i, j:j + 1]
                    else:
                        continue
                    n_raw += 1
                    if not np.array_equal(raw, want):
                        raw_problems.append("sample {} {} {}".format(i + 1, grid.get("Name"), name))
    c.check("transient_state: the .xdmf's raw values (Seek into the .h5) equal w, displacement, "
            "stop force and contact of the first and last samples ({} items)".format(n_raw),
            n_raw >= 8 and not raw_problems, str(raw_problems[:5]))


def check_documented(c, files):
    """Every dataset the program wrote is documented in docs/outputs.md, as `/path` (the
    work-precision series as `/work_precision/<series>/...`)."""
    docs = ROOT / "docs" / "outputs.md"
    text = docs.read_text(encoding="utf-8") if docs.exists() else ""
    paths = set()
    for path in files.values():
        with h5py.File(path, "r") as f:
            def visit(n, obj):
                if isinstance(obj, h5py.Dataset):
                    parts = ("/" + n).split("/")
                    if len(parts) > 3 and parts[1] == "work_precision":
                        parts[2] = "<series>"
                    if len(parts) > 4 and parts[2] == "curves" and parts[3].startswith("curve_"):
                        parts[3] = "curve_<NNN>"
                    paths.add("/".join(parts))
            f.visititems(visit)
    missing = sorted(p for p in paths if "`{}`".format(p) not in text)
    c.check("every dataset written ({} paths over every analysis) is documented in "
            "docs/outputs.md".format(len(paths)), bool(text) and not missing,
            "missing: {}".format(", ".join(missing[:12])))


def run_all(c, exe):
    import gapbeam

    print("test_reader.py: gapbeam package {}".format(gapbeam.__file__), flush=True)
    timeout = float(os.environ.get("GAPBEAM_PY_TIMEOUT", "300"))
    workdir = tempfile.mkdtemp(prefix="gapbeam-py-")
    try:
        check_synthetic(c, gapbeam, workdir)
        if exe is None:
            return
        files = run_cases(c, exe, workdir, timeout)
        tables = {}
        for name, path in files.items():
            case = CASES.get(name, CASES["sweep_independent"])
            analysis, n_stops = case[2], case[3]
            res = check_file(c, gapbeam, name, path,
                             "transient" if analysis == "tube" else analysis)
            if res is None:
                continue
            check_conventions(c, name, path, "transient" if analysis == "tube" else analysis)
            if analysis == "tube":
                check_tube(c, res, n_stops)
                continue
            if name == "transient_extended":
                check_time_origin(c, res)
                continue
            if analysis == "continuation":
                check_continuation(c, gapbeam, res, path)
                continue
            if name == "transient_state":
                check_state(c, gapbeam, path)
            if analysis == "sweep":
                points = {"sweep_shard_1": [1, 3, 5], "sweep_shard_2": [2, 4, 6]}.get(name)
                if name == "sweep_starts":
                    check_starts(c, gapbeam, name, res)
                    continue
                tables[name] = check_sweep(c, gapbeam, name, res, n_stops, points)
            elif name == "transient":
                check_transient(c, gapbeam, res, n_stops)
                check_transient_starts(c, gapbeam, res)
            elif analysis != "transient":
                check_no_poincare(c, gapbeam, name, res)
            if analysis == "model_size":
                t = gapbeam.table(res.model_size)
                c.check("model_size: table(res.model_size) has one row per model (6)",
                        t.n_rows == 6 and t["name"].tolist() == res.model_size.name.values.tolist()
                        and "recommended" not in t, repr(t))
            if analysis == "work_precision":
                t = gapbeam.table(res.work_precision.rk45)
                c.check("work_precision: table(rk45) has one row per level (2)",
                        t.n_rows == 2 and t.units["seconds"] == "s", repr(t))
        check_documented(c, files)
        check_catalogue_docs(c, exe)
        if "sweep_merged" in tables and "sweep_independent" in tables:
            a, b = tables["sweep_merged"], tables["sweep_independent"]
            differ = [k for k in b if not k.startswith("seconds")
                      and not np.array_equal(a.get(k), b[k], equal_nan=b[k].dtype.kind == "f")]
            c.check("sweep_merged: sweep_table equals the single-process run's (but the timings)",
                    set(a) == set(b) and not differ, "differ: {}".format(differ))
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print("usage: {} GAPBEAM_EXE".format(argv[0]), file=sys.stderr)
        return 2
    exe = argv[1]
    c = Checks()
    if IMPORT_ERROR is not None:
        c.check("import numpy and h5py", False, str(IMPORT_ERROR))
    elif not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        c.check("GAPBEAM_EXE '{}' is an executable file".format(exe), False)
    else:
        exe = os.path.abspath(exe)
        try:
            run_all(c, exe)
        except Exception as exc:  # noqa: BLE001 - report, do not crash without a FAIL line
            traceback.print_exc()
            c.check("test_reader.py ran to the end", False, repr(exc))
    print("test_reader.py: {} checks, {} failed".format(c.n, len(c.failed)), flush=True)
    return 1 if c.failed else 0


# -- pytest ------------------------------------------------------------------------------------
def test_synthetic_layout():
    """pytest: the checks on a synthetic file with later layout additions (no gapbeam needed)."""
    c = Checks()
    run_all(c, None)
    assert not c.failed, c.failed


def test_every_analysis():
    """pytest: every check against real gapbeam output (needs GAPBEAM_EXE)."""
    import pytest

    exe = os.environ.get("GAPBEAM_EXE")
    if not exe:
        pytest.skip("set GAPBEAM_EXE to the gapbeam executable")
    c = Checks()
    run_all(c, os.path.abspath(exe))
    assert not c.failed, c.failed


if __name__ == "__main__":
    sys.exit(main(sys.argv))
