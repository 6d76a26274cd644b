"""Helpers on a loaded result: tables of columns (:func:`sweep_table`, :func:`table`) and
Poincaré sets (:func:`poincare`).

None of them needs pandas or matplotlib; a :class:`Table` is a dict of equal-length 1-D numpy
arrays, which ``pandas.DataFrame(table)`` takes as it is.
"""

import numpy as np

from ._catalogue import DATASETS
from ._reader import Group, Quantity, Result

__all__ = ["Table", "PoincareSet", "table", "sweep_table", "poincare", "attractors"]


def _names(prefix, dims):
    """Names of the catalogue's datasets directly under `prefix` with axes `dims`, in order."""
    return tuple(path[len(prefix):] for _, _, path, _, d, _ in DATASETS
                 if path.startswith(prefix) and "/" not in path[len(prefix):] and d == dims)


# The field lists, from the output catalogue (gapbeam --help-outputs): the per-point columns
# of a sweep table, in the catalogue's order (1-D datasets of /sweep added later follow them in
# the file's order), and the per-stop statistics of /sweep/impacts and /sweep/wear.
_SWEEP_COLUMNS = _names("/sweep/", "m")
_IMPACT_COLUMNS = _names("/sweep/impacts/", "point=m stop=n_stops")
_WEAR_COLUMNS = _names("/sweep/wear/", "point=m stop=n_stops")


class Table(dict):
    """Columns of a table: a dict name -> 1-D numpy array, every column of the same length.

    ``pandas.DataFrame(t)`` makes a data frame of it (one row per entry); ``numpy`` and plain
    Python use it as a dict. Besides the columns it carries

    Attributes
    ----------
    units : dict
        name -> units string of each column (``None`` where the file gives none).
    long_names : dict
        name -> ``long_name`` of each column (``None`` where the file gives none).
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.units = {}
        self.long_names = {}

    def add(self, name, values, units=None, long_name=None):
        """Add (or replace) a column."""
        self[name] = values
        self.units[name] = units
        self.long_names[name] = long_name

    @property
    def n_rows(self):
        """Number of rows (0 for a table without columns)."""
        for v in self.values():
            return len(v)
        return 0

    def __repr__(self):
        return "<Table {} rows: {}>".format(self.n_rows, ", ".join(self))


def _quantity(res, path):
    q = res.get(path)
    return q if isinstance(q, Quantity) else None


def table(group, length=None):
    """The 1-D datasets of a group as a :class:`Table`, one row per entry.

    Parameters
    ----------
    group : Group
        E.g. ``res.model_size`` (one row per model) or ``res.work_precision.rk45`` (one row per
        level).
    length : int, optional
        Number of rows: the 1-D datasets of this length become the columns. By default the length
        shared by the most 1-D datasets of the group (the larger length on a tie).

    Scalars, 2-D datasets and subgroups are left out. Column names are the dataset names.
    """
    if not isinstance(group, Group):
        raise TypeError("table() takes a Group (e.g. res.model_size), not {!r}".format(group))
    ones = [(n, q) for n, q in group.items() if isinstance(q, Quantity) and q.ndim == 1]
    if length is None:
        counts = {}
        for _, q in ones:
            counts[len(q)] = counts.get(len(q), 0) + 1
        if not counts:
            return Table()
        length = max(counts, key=lambda k: (counts[k], k))
    out = Table()
    for name, q in ones:
        if len(q) == length:
            out.add(name, np.asarray(q.values), q.units, q.long_name)
    return out


def _dims(q):
    """The axis names of a dataset (its ``dimensions`` attribute, C order), or None."""
    d = q.attrs.get("dimensions") if isinstance(q, Quantity) else None
    return tuple(d.split()) if isinstance(d, str) else None


def _as_stops_by_points(values, m, dims=None):
    """A per-stop 2-D array as (n_stops, m), one column per point.

    Files with ``dimensions`` attributes say their axis order ('point stop' since version 0.1.0:
    one row per point); older files wrote (n_stops, m) in the h5py view. Without the attribute
    the axis of length m is taken; when both axes have length m the older layout is assumed.
    """
    a = np.asarray(values)
    if a.ndim == 1 and a.shape[0] == m:
        return a.reshape(1, m)
    if a.ndim != 2:
        raise ValueError("expected a 2-D per-stop array, got shape {}".format(a.shape))
    if dims == ("point", "stop") and a.shape[0] == m:
        return a.T
    if dims == ("stop", "point") and a.shape[1] == m:
        return a
    if a.shape[1] == m:
        return a
    if a.shape[0] == m:
        return a.T
    raise ValueError("no axis of shape {} has the sweep's {} points".format(a.shape, m))


def _as_points_by_periods(values, m):
    """A per-point 2-D array (Poincaré points, running exponent) as (m, n), one row per point.

    gapbeam writes the Fortran shape (n, m), which h5py shows as (m, n); an array stored the other
    way round is transposed. When both axes have length m, today's layout is assumed.
    """
    a = np.asarray(values)
    if a.ndim == 1 and m == 1:
        return a.reshape(1, -1)
    if a.ndim != 2:
        raise ValueError("expected a 2-D per-point array, got shape {}".format(a.shape))
    if a.shape[0] == m:
        return a
    if a.shape[1] == m:
        return a.T
    raise ValueError("no axis of shape {} has the sweep's {} points".format(a.shape, m))


def _sweep_group(res):
    if not isinstance(res, Group) or not isinstance(res.get("/sweep"), Group):
        what = getattr(res, "analysis", type(res).__name__)
        raise ValueError("not a sweep result (analysis {!r}): it has no /sweep group".format(what))
    return res["/sweep"]


def _n_points(sweep):
    for name in ("point_index", "frequency_hz", "amplitude_pp"):
        q = sweep.get(name)
        if isinstance(q, Quantity) and q.ndim == 1:
            return len(q)
    raise ValueError("the /sweep group has neither point_index nor frequency_hz")


def _text(q):
    """The text of a scalar string dataset ('' when absent)."""
    if not isinstance(q, Quantity):
        return ""
    v = q.values
    if isinstance(v, np.ndarray):
        v = v.item() if v.shape == () else v
    if isinstance(v, bytes):
        v = v.decode()
    return str(v).strip()


def sweep_table(res):
    """The points of a sweep as a :class:`Table`: one row per point in the file.

    Columns, in this order (each present when the file has its dataset):

    - ``point_index`` (point number p, from 1; x fastest), ``frequency_index`` and
      ``amplitude_index`` (i_f and i_a of the point, from 1, derived from p and the grid; 1 when
      that forcing variable is no axis), ``x_index`` and ``y_index`` (files with the
      ``grid_x``/``grid_y`` axes of any deck variable), ``frequency_hz`` [Hz],
      ``amplitude_pp`` [m], ``period`` [forcing periods], ``label`` (p >= 1 period p,
      0 undecided, -1 chaotic, -2 unsettled, -3 failed), ``label_text`` (str), ``lyapunov``
      [1/s], ``lyapunov_error`` [1/s], ``status`` (0 done, 1 failed), ``steps``, ``seconds``
      [s];
    - every other 1-D dataset of ``/sweep`` with one entry per point (later additions: the
      axis values ``x`` and ``y``, the certificate and the evidence of each label, the number
      of attractors; docs/labels.md);
    - the impact statistics of every stop, flattened: ``count_1``, ``peak_force_1``,
      ``rms_force_1``, ``contact_fraction_1``, ``impulse_per_period_1``, ``work_rate_1``, then
      the same for stop 2, ... (``<dataset of /sweep/impacts>_<stop number>``);
    - the wear outputs of every stop when the file has ``/sweep/wear``, flattened the same way:
      ``normal_work_rate_1``, ``sliding_distance_1``, ``friction_work_rate_1``,
      ``wear_volume_rate_1``, ...

    The Poincaré points and the running exponents (several values per point) are not columns:
    see :func:`poincare` and ``res['/sweep/lyapunov_running']``. Units are in ``table.units``.

    >>> import pandas as pd
    >>> df = pd.DataFrame(gapbeam.sweep_table(res))
    """
    sweep = _sweep_group(res)
    m = _n_points(sweep)
    out = Table()

    point = sweep.get("point_index")
    points = (
        np.asarray(point.values)
        if isinstance(point, Quantity) and point.shape == (m,)
        else np.arange(1, m + 1, dtype=np.int32)
    )
    index_units = point.units if isinstance(point, Quantity) else None
    out.add("point_index", points, index_units, getattr(point, "long_name", None))
    grid_x = sweep.get("grid_x")
    grid_f = sweep.get("grid_frequency_hz")
    if isinstance(grid_x, Quantity) and grid_x.ndim == 1 and len(grid_x) > 0:
        # axes over any deck variables: x fastest; the forcing indices follow the axis that is
        # the forcing variable (1 when it is no axis)
        n_x = len(grid_x)
        ix = ((points - 1) % n_x + 1).astype(points.dtype)
        iy = ((points - 1) // n_x + 1).astype(points.dtype)
        names = [_text(sweep.get("x_variable")), _text(sweep.get("y_variable"))]
        ones_i = np.ones_like(points)
        for index_name, variable in (("frequency_index", "&forcing frequency_hz"),
                                     ("amplitude_index", "&forcing amplitude_pp")):
            index = ix if names[0] == variable else iy if names[1] == variable else ones_i
            out.add(index_name, index, index_units)
        out.add("x_index", ix, index_units)
        out.add("y_index", iy, index_units)
    elif isinstance(grid_f, Quantity) and grid_f.ndim == 1 and len(grid_f) > 0:
        n_f = len(grid_f)
        out.add("frequency_index", ((points - 1) % n_f + 1).astype(points.dtype), index_units)
        out.add("amplitude_index", ((points - 1) // n_f + 1).astype(points.dtype), index_units)

    ones = [
        (n, q)
        for n, q in sweep.items()
        if isinstance(q, Quantity) and q.shape == (m,) and not n.startswith("grid_")
    ]
    known = [n for n in _SWEEP_COLUMNS if any(n == k for k, _ in ones)]
    others = [n for n, _ in ones if n not in _SWEEP_COLUMNS]
    for name in known + others:
        if name == "point_index":
            continue
        q = sweep[name]
        out.add(name, np.asarray(q.values), q.units, q.long_name)

    for group, order in (("impacts", _IMPACT_COLUMNS), ("wear", _WEAR_COLUMNS)):
        _add_per_stop(out, sweep.get(group), order, m)
    return out


def _add_per_stop(out, grp, order, m):
    """Add the (stops, points) datasets of group ``grp`` as ``<name>_<stop>`` columns."""
    if not isinstance(grp, Group):
        return
    names = [n for n in order if isinstance(grp.get(n), Quantity)]
    names += [
        n
        for n, q in grp.items()
        if isinstance(q, Quantity) and n not in order and q.ndim in (1, 2)
    ]
    per_stop = {}
    for name in names:
        q = grp[name]
        try:
            per_stop[name] = (_as_stops_by_points(q.values, m, _dims(q)), q)
        except ValueError:
            continue  # not one value per stop and point: not a column
    n_stops = max((a.shape[0] for a, _ in per_stop.values()), default=0)
    for k in range(n_stops):
        for name, (a, q) in per_stop.items():
            if k < a.shape[0]:
                out.add("{}_{}".format(name, k + 1), a[k], q.units, q.long_name)


class PoincareSet:
    """A Poincaré set: the root strain and strain rate at the section, one point per period.

    Unpacks as ``strain, strain_rate = gapbeam.poincare(res)``.

    Attributes
    ----------
    strain : numpy.ndarray
        Root strain ε at the section [-]: shape (record_periods,) for a transient run or one
        sweep point; (n_points, record_periods) for a whole sweep, one row per point.
    strain_rate : numpy.ndarray
        Root strain rate dε/dt at the section [1/s], same shape.
    time : numpy.ndarray or None
        Section times [s] (transient runs only; ``None`` for a sweep).
    point : int, numpy.ndarray or None
        The sweep point number(s) p; ``None`` for a transient run.
    frequency_hz, amplitude_pp : float, numpy.ndarray or None
        The forcing of the run or point(s) [Hz], [m peak to peak]; ``None`` when the file does not
        give it.
    units : dict
        Units of ``strain``, ``strain_rate`` (and ``time``) as stored in the file.
    """

    def __init__(self, strain, strain_rate, time=None, point=None, frequency_hz=None,
                 amplitude_pp=None, units=None):
        self.strain = strain
        self.strain_rate = strain_rate
        self.time = time
        self.point = point
        self.frequency_hz = frequency_hz
        self.amplitude_pp = amplitude_pp
        self.units = {} if units is None else dict(units)

    def __iter__(self):
        yield self.strain
        yield self.strain_rate

    def __len__(self):
        return len(self.strain)

    def __repr__(self):
        where = "" if self.point is None or np.ndim(self.point) else " point {}".format(self.point)
        return "<PoincareSet{} shape {}>".format(where, np.shape(self.strain))


def _units(q):
    return q.units if isinstance(q, Quantity) else None


def poincare(res, point=None):
    """The Poincaré set of a transient run or of a sweep point.

    Parameters
    ----------
    res : Result
        A transient or a sweep result (:func:`gapbeam.load`).
    point : int, optional
        Sweep only: the point number p (``/sweep/point_index``, from 1, frequency fastest; a
        shard file holds only its own points). Without it a sweep gives every point of the file,
        one row each (the data of a bifurcation diagram).

    Returns
    -------
    PoincareSet
        ``strain`` and ``strain_rate`` (1-D for a transient run or one point, 2-D (n_points,
        record_periods) for a whole sweep), with the forcing and the units.

    Raises
    ------
    ValueError
        For a result without Poincaré points, a point on a transient run, or a point that is not
        in the file.
    """
    if isinstance(res, Group) and isinstance(res.get("/poincare/strain"), Quantity):
        if point is not None:
            raise ValueError("point= is for sweep results; this is a transient run")
        strain = res["/poincare/strain"]
        rate = res["/poincare/strain_rate"]
        time = _quantity(res, "/poincare/time")
        omega = _quantity(res, "/model/forcing_omega")
        half = _quantity(res, "/model/forcing_half_amplitude")
        units = {"strain": strain.units, "strain_rate": rate.units}
        if time is not None:
            units["time"] = time.units
        return PoincareSet(
            np.asarray(strain.values),
            np.asarray(rate.values),
            time=None if time is None else np.asarray(time.values),
            frequency_hz=None if omega is None else float(omega) / (2.0 * np.pi),
            amplitude_pp=None if half is None else 2.0 * float(half),
            units=units,
        )
    if isinstance(res, Group) and isinstance(res.get("/sweep"), Group):
        sweep = res["/sweep"]
        m = _n_points(sweep)
        strain_q = sweep.get("poincare/strain")
        rate_q = sweep.get("poincare/strain_rate")
        if not isinstance(strain_q, Quantity) or not isinstance(rate_q, Quantity):
            raise ValueError("this sweep file has no /sweep/poincare/strain and strain_rate")
        strain = _as_points_by_periods(strain_q.values, m)
        rate = _as_points_by_periods(rate_q.values, m)
        pq = sweep.get("point_index")
        points = np.asarray(pq.values) if isinstance(pq, Quantity) else np.arange(1, m + 1)
        fq = sweep.get("frequency_hz")
        aq = sweep.get("amplitude_pp")
        freq = None if fq is None else np.asarray(fq.values)
        amp = None if aq is None else np.asarray(aq.values)
        units = {"strain": strain_q.units, "strain_rate": rate_q.units}
        if point is None:
            return PoincareSet(strain, rate, point=points, frequency_hz=freq, amplitude_pp=amp,
                               units=units)
        if isinstance(point, (bool, np.bool_)) or not isinstance(point, (int, np.integer)):
            raise ValueError("point must be a point number (int), not {!r}".format(point))
        rows = np.flatnonzero(points == point)
        if rows.size == 0:
            shown = ", ".join(str(p) for p in points[:10]) + (" ..." if m > 10 else "")
            raise ValueError(
                "point {} is not in this file (its points: {})".format(point, shown or "none")
            )
        r = int(rows[0])
        return PoincareSet(
            strain[r].copy(),
            rate[r].copy(),
            point=int(point),
            frequency_hz=None if freq is None else float(freq[r]),
            amplitude_pp=None if amp is None else float(amp[r]),
            units=units,
        )
    what = res.analysis if isinstance(res, Result) else type(res).__name__
    raise ValueError("no Poincaré set in a {!r} result (transient and sweep results have one)"
                     .format(what))


def attractors(res):
    """Every start of every point and the attractor it reached, as a :class:`Table`.

    One row per (point, start) of a sweep, or per start of a transient run: ``point_index``
    (sweep only), ``start`` (1 = the start whose label is the point's), ``kind`` ('deck',
    'rest', 'up', 'down', 'random'; sweep only), ``label`` of the start (-3: it failed),
    ``lyapunov`` [1/s], ``attractor`` (number of the distinct attractor it reached, from 1;
    0 when it failed), and that attractor's ``attractor_label`` and ``attractor_fraction``
    (the fraction of the point's starts that reached it). See docs/labels.md.

    Raises ValueError when the result has no starts (files written before issue 11, or
    another analysis).
    """
    if isinstance(res, Group) and isinstance(res.get("/sweep"), Group):
        sweep = res["/sweep"]
        m = _n_points(sweep)
        needed = ["starts/label", "starts/attractor", "starts/lyapunov", "attractors/label",
                  "attractors/fraction"]
        if any(not isinstance(sweep.get(n), Quantity) for n in needed):
            raise ValueError("this sweep file has no /sweep/starts (written before issue 11?)")
        # Fortran (n_starts, m), h5py (m, n_starts): one row per start after the transpose
        label = _as_points_by_periods(sweep["starts/label"].values, m).T
        attr = _as_points_by_periods(sweep["starts/attractor"].values, m).T
        lyap = _as_points_by_periods(sweep["starts/lyapunov"].values, m).T
        a_label = _as_points_by_periods(sweep["attractors/label"].values, m).T
        a_frac = _as_points_by_periods(sweep["attractors/fraction"].values, m).T
        kinds = sweep.get("starts/kind")
        kinds = [] if not isinstance(kinds, Quantity) else [
            (k.decode() if isinstance(k, bytes) else str(k)).strip()
            for k in np.atleast_1d(kinds.values)]
        point = sweep.get("point_index")
        points = (np.asarray(point.values) if isinstance(point, Quantity) and point.shape == (m,)
                  else np.arange(1, m + 1, dtype=np.int32))
        n_s = label.shape[0]
        rows = [(j, k) for j in range(m) for k in range(n_s)]
        out = Table()
        out.add("point_index", np.array([points[j] for j, _ in rows], dtype=points.dtype))
        out.add("start", np.array([k + 1 for _, k in rows], dtype=np.int32))
        out.add("kind", np.array([kinds[k] if k < len(kinds) else "" for _, k in rows]))
        out.add("label", np.array([label[k, j] for j, k in rows]), sweep["starts/label"].units)
        out.add("lyapunov", np.array([lyap[k, j] for j, k in rows]), "1/s")
        out.add("attractor", np.array([attr[k, j] for j, k in rows]))
        out.add("attractor_label", np.array(
            [a_label[attr[k, j] - 1, j] if attr[k, j] > 0 else -3 for j, k in rows]))
        out.add("attractor_fraction", np.array(
            [a_frac[attr[k, j] - 1, j] if attr[k, j] > 0 else np.nan for j, k in rows]), "-")
        return out
    diag = res.get("/diagnostics") if isinstance(res, Group) else None
    if isinstance(diag, Group) and isinstance(diag.get("starts/label"), Quantity):
        label = np.atleast_1d(diag["starts/label"].values)
        attr = np.atleast_1d(diag["starts/attractor"].values)
        lyap = np.atleast_1d(diag["starts/lyapunov"].values)
        a_label = np.atleast_1d(diag["attractors/label"].values)
        a_frac = np.atleast_1d(diag["attractors/fraction"].values)
        out = Table()
        out.add("start", np.arange(1, len(label) + 1, dtype=np.int32))
        out.add("label", label, diag["starts/label"].units)
        out.add("lyapunov", lyap, "1/s")
        out.add("attractor", attr)
        out.add("attractor_label", np.array([a_label[a - 1] if a > 0 else -3 for a in attr]))
        out.add("attractor_fraction", np.array([a_frac[a - 1] if a > 0 else np.nan
                                                for a in attr]), "-")
        return out
    what = getattr(res, "analysis", type(res).__name__)
    raise ValueError("no starts in a {!r} result (sweeps and transient runs since issue 11 have "
                     "them)".format(what))
