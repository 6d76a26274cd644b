"""scripts/paraview_check.py - ParaView reads a gapbeam XDMF file as written (pvpython).

Usage (scripts/test_paraview.sh runs it):
  pvpython scripts/paraview_check.py FILE.xdmf EXPECTED.json xdmf3|legacy

Opens FILE.xdmf with one of ParaView's XDMF readers ("xdmf3": Xdmf3ReaderS, ParaView's
default; "legacy": XDMFReader) and compares what it reads with EXPECTED.json, which
scripts/test_paraview.sh writes from the .h5 file with h5py: the number of time steps and their
values (/history/time, seconds), the beam block (its points on the x axis at /history/shape_x,
its segments, the point fields "w [m]", "displacement [m]" = (0, w, v) and, for two planes,
"v [m]", equal to /history/shape_w, /history/shape_v at the samples listed), the stop blocks
(their number, the cell fields "stop force [N]" and "contact [1 closed, 0 open]" equal to
/history/stop_force and 1 where it is > 0). Prints one `PASS  paraview: <reader>: ...` or
`FAIL  paraview: <reader>: ... (why)` line per check. Whether the reader logged a warning or an
error is checked by the caller on this script's standard error. Exit status 0, or 1 when a
check failed.
"""

import json
import sys

from paraview import servermanager as sm
from paraview import simple as pv


def leaves(data):
    """(name, dataset) of the leaves of a composite dataset (name None where it has none)."""
    out = []
    if not data.IsA("vtkCompositeDataSet"):
        return [(None, data)]
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        meta = it.GetCurrentMetaData()
        name = meta.Get(data.NAME()) if meta is not None and meta.Has(data.NAME()) else None
        out.append((name, it.GetCurrentDataObject()))
        it.GoToNextItem()
    return out


def values(array):
    """A VTK data array as a list of tuples (or of numbers with one component)."""
    n, k = array.GetNumberOfTuples(), array.GetNumberOfComponents()
    if k == 1:
        return [array.GetTuple1(i) for i in range(n)]
    return [array.GetTuple(i) for i in range(n)]


def main(argv):
    if len(argv) != 4 or argv[3] not in ("xdmf3", "legacy"):
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        return 2
    path, expected_path, which = argv[1], argv[2], argv[3]
    with open(expected_path, encoding="utf-8") as f:
        ex = json.load(f)
    failed = 0

    def check(what, ok, why=""):
        nonlocal failed
        if ok:
            print("PASS  paraview: {}: {}".format(which, what))
        else:
            failed += 1
            print("FAIL  paraview: {}: {} ({})".format(which, what, why))

    if which == "xdmf3":
        reader = pv.Xdmf3ReaderS(FileName=[path])
    else:
        reader = pv.XDMFReader(FileNames=[path])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues or [])
    check("{} time steps".format(len(ex["time"])), len(times) == len(ex["time"]),
          "{} steps".format(len(times)))
    if times and len(times) == len(ex["time"]):
        err = max(abs(a - b) for a, b in zip(times, ex["time"]))
        check("time values equal /history/time [s] (from {:.6g} to {:.6g} s)".format(
            ex["time"][0], ex["time"][-1]), err <= 1e-12 * max(1.0, abs(ex["time"][-1])),
            "largest difference {:.3g} s".format(err))
    if not times:
        return 1
    # each check over the listed samples (the first, the first in contact, an open one, the
    # last): one line each, naming the samples where it fails
    bad = {}

    def note(what, i, ok, why=""):
        bad.setdefault(what, [])
        if not ok:
            bad[what].append("sample {}: {}".format(i + 1, why))

    npt = len(ex["shape_x"])
    want_fields = sorted(["w [m]", "displacement [m]"] + (["v [m]"] if ex["two_planes"] else []))
    geometry = "one beam block of {} points on the x axis at /history/shape_x, {} segments".format(
        npt, npt - 1)
    fields = "beam fields " + ", ".join(want_fields)
    w_text = "w [m] equals /history/shape_w"
    d_text = "displacement [m] = (0, w, v)"
    v_text = "v [m] equals /history/shape_v"
    s_text = "{} stop block(s), stop force [N] and contact [1 closed, 0 open] equal " \
             "/history/stop_force, /history/stop_contact".format(ex["stop_grids"])
    seen = []
    for i in ex["samples"]:
        reader.UpdatePipeline(times[i])
        blocks = leaves(sm.Fetch(reader))
        beams = [b for _, b in blocks if b.GetPointData().GetArray("w [m]") is not None]
        stops = [b for _, b in blocks if b.GetCellData().GetArray("stop force [N]") is not None]
        b = beams[0] if len(beams) == 1 else None
        pts = [b.GetPoint(k) for k in range(b.GetNumberOfPoints())] if b else []
        note(geometry, i, b is not None and len(pts) == npt and b.GetNumberOfCells() == npt - 1
             and all(abs(p[0] - x) <= 1e-15 and p[1] == 0.0 and p[2] == 0.0
                     for p, x in zip(pts, ex["shape_x"])),
             "{} beam blocks, {} points".format(len(beams), len(pts)))
        if b is None:
            continue
        pd = b.GetPointData()
        names = sorted(pd.GetArrayName(k) for k in range(pd.GetNumberOfArrays()))
        note(fields, i, names == want_fields, str(names))
        w = values(pd.GetArray("w [m]"))
        d = values(pd.GetArray("displacement [m]")) if pd.GetArray("displacement [m]") else []
        ew = ex["w"][str(i)]
        ev = ex["v"][str(i)] if ex["two_planes"] else [0.0] * len(ew)
        note(w_text, i, w == ew, "largest difference {:.3g}".format(
            max(abs(a - c) for a, c in zip(w, ew)) if len(w) == len(ew) else -1))
        note(d_text, i, len(d) == len(ew) and all(
            t[0] == 0.0 and t[1] == a and t[2] == c for t, a, c in zip(d, ew, ev)))
        if ex["two_planes"]:
            v = values(pd.GetArray("v [m]")) if pd.GetArray("v [m]") else []
            note(v_text, i, v == ev)
        ef, ec = ex["stop_force"][str(i)], ex["stop_contact"][str(i)]
        got = []
        for st in stops:
            f = st.GetCellData().GetArray("stop force [N]")
            c = st.GetCellData().GetArray("contact [1 closed, 0 open]")
            got.append((f.GetTuple1(0) if f else None, c.GetTuple1(0) if c else None))
        want_fc = list(zip(ef, ec))
        note(s_text, i, len(got) == ex["stop_grids"] and all(g in want_fc for g in got),
             "got {}, want {}".format(got, want_fc))
        seen.append("{} (t = {:.4f} s, tip w {:.3g} m, stops {})".format(
            i + 1, times[i], ew[-1], ", ".join(
                "{:.3g} N {}".format(f, "closed" if c else "open") for f, c in want_fc)))
    for what, problems in bad.items():
        check(what, not problems, "; ".join(problems[:3]))
    print("NOTE  paraview: {}: samples checked: {}".format(which, "; ".join(seen)))
    return 1 if failed else 0


if __name__ == "__main__":
    status = main(sys.argv)
    sys.stdout.flush()
    sys.stderr.flush()
    import os
    os._exit(status)
