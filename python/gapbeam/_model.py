"""The model a result came from (:func:`parameters`) and the beam in motion (:func:`motion`)."""

import numpy as np

from ._reader import Group, Quantity

__all__ = ["parameters", "Motion", "motion"]


def parameters(res):
    """The resolved model parameters of a result (its ``/parameters`` group) as a flat dict.

    Keys are the paths under ``/parameters`` (``'beam/thickness'``, ``'root/kappa'``,
    ``'stops/stiffness'``, ``'model/f1_open_hz'``, ...); values are :class:`Quantity` objects
    (``.values``, ``.units``, ``.long_name``), so ``float(p['beam/length'])`` is the length in
    metres. Files written before the group existed give an empty dict.

    >>> p = gapbeam.parameters(res)
    >>> p['beam/thickness'].values, p['beam/thickness'].units
    (array(0.00026196), 'm')
    """
    group = res.get("/parameters") if isinstance(res, Group) else None
    out = {}
    if not isinstance(group, Group):
        return out
    prefix = "/parameters/"
    for path, q in group.datasets().items():
        out[path[len(prefix):] if path.startswith(prefix) else path] = q
    return out


class Motion:
    """The beam in motion: the deflected shape at every history sample of a transient run
    (``&output state_history = .true.``).

    Attributes
    ----------
    time : numpy.ndarray
        Sample times [s], shape (n_samples,).
    x : numpy.ndarray
        Positions of the shape points [m], shape (n_points,): ``shape_points`` per element, the
        nodes among them.
    w : numpy.ndarray
        Deflection relative to the base [m] from the elements' Hermite shape functions, shape
        (n_samples, n_points): row i is the beam at ``time[i]``.
    node_x, node_w, node_theta : numpy.ndarray
        The nodes: positions [m] (n_nodes,), displacements [m] and rotations [rad]
        (n_samples, n_nodes).
    """

    def __init__(self, time, x, w, node_x, node_w, node_theta):
        self.time = time
        self.x = x
        self.w = w
        self.node_x = node_x
        self.node_w = node_w
        self.node_theta = node_theta

    def __repr__(self):
        return "<Motion {} samples x {} points>".format(len(self.time), len(self.x))


def motion(res):
    """The beam in motion of a transient run with ``&output state_history``: a :class:`Motion`.

    Raises ``ValueError`` for a result without it (another analysis, or a run without the state
    history).
    """
    need = ("/history/time", "/history/shape_x", "/history/shape_w", "/history/node_x",
            "/history/node_w", "/history/node_theta")
    if not isinstance(res, Group) or not all(isinstance(res.get(p), Quantity) for p in need):
        raise ValueError("no state history in this result: run a transient with "
                         "'&output state_history = .true. /'")
    v = [np.asarray(res[p].values) for p in need]
    return Motion(*v)
