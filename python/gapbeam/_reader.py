"""Read a gapbeam HDF5 result file into memory: :func:`load`, :class:`Result`, :class:`Group`
and :class:`Quantity`.

The whole file is read when it is loaded and closed again, so a :class:`Result` stays valid after
the file is replaced or removed. Every dataset and attribute of the file is kept, whatever the
analysis, so datasets, groups and attributes added by later versions of gapbeam are read without
a change here.
"""

import os
import re

import h5py
import numpy as np

__all__ = ["load", "Result", "Group", "Quantity", "ANALYSES"]

#: The analyses gapbeam runs (``&job analysis``).
ANALYSES = (
    "modes",
    "calibrate",
    "transient",
    "sweep",
    "work_precision",
    "stability",
    "model_size",
    "continuation",
)

# Top-level groups that name the analysis that wrote a file, most specific first: a transient
# file also holds /model, as a modes file does, so /modes is looked at only after the groups
# that only a transient run writes.
_ANALYSIS_GROUPS = (
    ("sweep", "sweep"),
    ("work_precision", "work_precision"),
    ("stability", "stability"),
    ("model_size", "model_size"),
    ("continuation", "continuation"),
    ("calibrate", "calibrate"),
    ("poincare", "transient"),
    ("history", "transient"),
    ("diagnostics", "transient"),
    ("modes", "modes"),
)


def _decode_bytes(b):
    """bytes -> str (UTF-8; undecodable bytes replaced, never an exception)."""
    return b.decode("utf-8", errors="replace")


def _decode_attr(value):
    """An HDF5 attribute value as Python/numpy data with every string decoded to str."""
    if isinstance(value, (bytes, np.bytes_)):
        return _decode_bytes(bytes(value))
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "S":
            return np.char.decode(value, "utf-8", errors="replace")
        if value.dtype.kind == "O":
            return np.array(
                [_decode_bytes(v) if isinstance(v, bytes) else v for v in value.ravel()],
                dtype=object,
            ).reshape(value.shape)
    return value


def _decode_attrs(attrs):
    """All attributes of an HDF5 object as a dict of decoded values (unreadable ones skipped)."""
    out = {}
    for name in attrs:
        try:
            out[name] = _decode_attr(attrs[name])
        except (OSError, TypeError, ValueError):  # an attribute type h5py cannot read
            continue
    return out


def _string_pad_is_space(dset):
    """True when dset has a fixed-length string type padded with spaces (Fortran style)."""
    try:
        tid = dset.id.get_type()
        return (
            isinstance(tid, h5py.h5t.TypeStringID)
            and not tid.is_variable_str()
            and tid.get_strpad() == h5py.h5t.STR_SPACEPAD
        )
    except (AttributeError, TypeError, ValueError):
        return False


def read_dataset(dset):
    """The value of an h5py dataset with strings decoded.

    Numbers: a numpy array of the stored type (0-d for a scalar dataset). Strings (fixed or
    variable length): ``str`` for a scalar dataset, else a numpy array of ``str`` (dtype ``<U``)
    of the stored shape; bytes are decoded as UTF-8, trailing NULs (and, for a space-padded type,
    trailing blanks) removed.
    """
    raw = dset[()]
    kind = dset.dtype.kind
    is_string = kind == "S" or (kind == "O" and h5py.check_string_dtype(dset.dtype) is not None)
    if isinstance(raw, h5py.Empty):  # a dataset with a null dataspace: no value at all
        return "" if is_string else np.empty((0,), dtype=dset.dtype)
    if not is_string:
        return np.asarray(raw)
    strip = _string_pad_is_space(dset)

    def one(v):
        s = _decode_bytes(bytes(v)) if isinstance(v, (bytes, np.bytes_)) else str(v)
        s = s.rstrip("\x00")
        return s.rstrip(" ") if strip else s

    if np.ndim(raw) == 0:
        return one(raw.item() if isinstance(raw, np.ndarray) else raw)
    arr = np.asarray(raw)
    items = [one(v) for v in arr.ravel()]
    if not items:
        return np.zeros(arr.shape, dtype="<U1")
    return np.array(items, dtype=str).reshape(arr.shape)


class Quantity:
    """One dataset of a result file: its values and what they mean.

    Attributes
    ----------
    values : numpy.ndarray or str
        The data, in the file's (C, h5py) order: the reverse of the Fortran shapes listed in the
        gapbeam README, e.g. ``/sweep/impacts/peak_force`` is ``(n_stops, n_points)``. Numbers keep
        their stored type (float64, int32); a scalar dataset gives a 0-d array. Text is decoded:
        a ``str`` for a scalar dataset, else an array of ``str``.
    units : str or None
        The ``units`` attribute (``None`` if the dataset has none). Today's files use ``'-'`` for
        dimensionless values and descriptions such as ``'0: done, 1: failed'`` for codes.
    long_name : str or None
        The ``long_name`` attribute, if the file has one.
    path : str
        The dataset's absolute path in the file, e.g. ``'/sweep/frequency_hz'``.
    attrs : dict
        Every attribute of the dataset, strings decoded.

    A Quantity converts to a numpy array (``numpy.asarray(q)``, and so plotting and numpy
    functions accept it); indexing, ``len``, ``float``, ``int``, ``shape``, ``dtype`` and ``ndim``
    act on :attr:`values`. For arithmetic, use ``q.values``.
    """

    __slots__ = ("values", "units", "long_name", "path", "attrs")

    def __init__(self, values, units=None, long_name=None, path="", attrs=None):
        self.values = values
        self.units = units
        self.long_name = long_name
        self.path = path
        self.attrs = {} if attrs is None else dict(attrs)

    @classmethod
    def from_h5(cls, dset):
        """A Quantity with the values and decoded attributes of an h5py dataset."""
        attrs = _decode_attrs(dset.attrs)
        units = attrs.get("units")
        long_name = attrs.get("long_name")
        return cls(
            read_dataset(dset),
            units=units if isinstance(units, str) else None,
            long_name=long_name if isinstance(long_name, str) else None,
            path=dset.name,
            attrs=attrs,
        )

    @property
    def name(self):
        """The last component of :attr:`path`."""
        return self.path.rsplit("/", 1)[-1]

    @property
    def is_text(self):
        """True for a text dataset."""
        return isinstance(self.values, str) or (
            isinstance(self.values, np.ndarray) and self.values.dtype.kind == "U"
        )

    @property
    def shape(self):
        """Shape of :attr:`values` (``()`` for a scalar)."""
        return np.shape(self.values)

    @property
    def ndim(self):
        """Number of dimensions of :attr:`values`."""
        return np.ndim(self.values)

    @property
    def dtype(self):
        """numpy dtype of :attr:`values`."""
        return np.asarray(self.values).dtype

    def __array__(self, dtype=None, copy=None):
        arr = np.asarray(self.values, dtype=dtype)
        return arr.copy() if copy else arr

    def __len__(self):
        return len(self.values)

    def __getitem__(self, key):
        return self.values[key]

    def __iter__(self):
        return iter(self.values)

    def __float__(self):
        return float(np.asarray(self.values))

    def __int__(self):
        return int(np.asarray(self.values))

    def item(self):
        """The value of a one-element quantity as a Python number (or str)."""
        if isinstance(self.values, str):
            return self.values
        return np.asarray(self.values).item()

    def __str__(self):
        if isinstance(self.values, str):
            return self.values
        text = np.array2string(np.asarray(self.values), threshold=20, edgeitems=3)
        return text if self.units is None else "{} [{}]".format(text, self.units)

    def __repr__(self):
        if isinstance(self.values, str):
            what = "str, {} characters".format(len(self.values))
        else:
            what = "{} {}".format(self.shape, self.dtype)
        units = "" if self.units is None else " [{}]".format(self.units)
        return "<Quantity {} {}{}>".format(self.path, what, units)


class Group:
    """A group of a result file: its members by name, as items or as attributes.

    ``g['peak_force']``, ``g['impacts/peak_force']`` (relative path) and ``g.peak_force`` give
    the same :class:`Quantity` (or :class:`Group`); an absolute path (``'/sweep/frequency_hz'``)
    is looked up from the file's root. Attribute access covers members whose names are Python
    identifiers and not already attributes of the group (``path``, ``attrs``, ``keys`` ...); item
    access covers every name. ``keys()``, ``values()``, ``items()``, ``in`` and iteration list
    the direct members; :meth:`datasets` walks the whole subtree.

    Attributes
    ----------
    path : str
        Absolute path of the group (``'/'`` for the root).
    attrs : dict
        The group's HDF5 attributes, strings decoded.
    """

    def __init__(self, path, attrs=None, members=None, root=None):
        self.path = path
        self.attrs = {} if attrs is None else dict(attrs)
        self._members = {} if members is None else members
        self._root = self if root is None else root

    @classmethod
    def _from_h5(cls, h5group, root=None, group=None):
        g = cls(h5group.name, _decode_attrs(h5group.attrs), {}, root) if group is None else group
        for name in h5group:
            link = h5group.get(name, getlink=True)
            if isinstance(link, (h5py.ExternalLink,)):
                continue  # another file: not part of this result
            try:
                obj = h5group[name]
            except KeyError:  # a dangling soft link
                continue
            if isinstance(obj, h5py.Dataset):
                g._members[name] = Quantity.from_h5(obj)
            elif isinstance(obj, h5py.Group):
                g._members[name] = Group._from_h5(obj, root=g._root)
        return g

    # -- access -------------------------------------------------------------------------------
    def __getitem__(self, key):
        if not isinstance(key, str):
            raise TypeError("a group is indexed by a name or a path, not {!r}".format(key))
        node = self._root if key.startswith("/") else self
        for part in key.strip("/").split("/"):
            if part in ("", "."):
                continue
            if not isinstance(node, Group) or part not in node._members:
                raise KeyError("{}: no {!r} in the file (under {})".format(key, part, node.path))
            node = node._members[part]
        return node

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        members = self.__dict__.get("_members", {})
        if name in members:
            return members[name]
        raise AttributeError(
            "group {} has no member {!r} (its members: {})".format(
                self.path, name, ", ".join(members) or "none"
            )
        )

    def __dir__(self):
        names = set(super().__dir__())
        names.update(n for n in self._members if n.isidentifier())
        return sorted(names)

    def __contains__(self, key):
        try:
            self[key]
        except (KeyError, TypeError):
            return False
        return True

    def __iter__(self):
        return iter(self._members)

    def __len__(self):
        return len(self._members)

    def keys(self):
        """Names of the direct members (datasets and groups), in the file's order."""
        return self._members.keys()

    def values(self):
        """The direct members: :class:`Quantity` and :class:`Group` objects."""
        return self._members.values()

    def items(self):
        """(name, member) pairs of the direct members."""
        return self._members.items()

    def get(self, key, default=None):
        """``self[key]``, or ``default`` when there is no such member."""
        try:
            return self[key]
        except KeyError:
            return default

    def groups(self):
        """The direct subgroups, by name."""
        return {k: v for k, v in self._members.items() if isinstance(v, Group)}

    def datasets(self):
        """Every dataset below this group, as a dict absolute path -> :class:`Quantity`."""
        out = {}
        for member in self._members.values():
            if isinstance(member, Group):
                out.update(member.datasets())
            else:
                out[member.path] = member
        return out

    def tree(self):
        """A text listing of the subtree: one line per group and dataset, with shape and units."""
        lines = []

        def walk(g, indent):
            for name, m in g.items():
                if isinstance(m, Group):
                    lines.append("{}{}/".format(indent, name))
                    walk(m, indent + "  ")
                else:
                    shape = "str" if isinstance(m.values, str) else str(m.shape)
                    units = "" if m.units is None else "  [{}]".format(m.units)
                    lines.append("{}{}  {}{}".format(indent, name, shape, units))

        walk(self, "")
        return "\n".join(lines)

    def __repr__(self):
        return "<Group {} ({})>".format(self.path, ", ".join(self._members) or "empty")


class Result(Group):
    """The content of one gapbeam result file (the root group), from :func:`load`.

    Attributes
    ----------
    filename : str
        The file that was read.
    analysis : str
        The analysis that wrote the file: one of :data:`ANALYSES` (``'unknown'`` if it cannot be
        told). Taken from a root attribute ``analysis`` when the file has one, else from the
        groups present (``/sweep`` -> ``'sweep'``, ``/poincare`` -> ``'transient'`` ...), else from
        the deck text.
    deck : str
        The effective deck text stored at ``/deck`` (deck file plus command-line overrides);
        ``''`` if the file has none.
    attrs : dict
        The root attributes (later versions add e.g. ``version``, ``commit``, ``date``).

    Datasets are reached by path, ``res['/sweep/frequency_hz']``, or by attributes,
    ``res.sweep.frequency_hz``; both give a :class:`Quantity`.
    """

    def __init__(self, filename, attrs=None, members=None):
        super().__init__("/", attrs, members)
        self.filename = filename
        self.analysis = "unknown"

    @property
    def deck(self):
        """The effective deck text (``/deck``), ``''`` when the file has none."""
        q = self._members.get("deck")
        if isinstance(q, Quantity) and isinstance(q.values, str):
            return q.values
        return ""

    @property
    def title(self):
        """The run's title: ``/sweep/title``, else ``&job title`` of the deck, else ``''``."""
        q = self.get("/sweep/title")
        if isinstance(q, Quantity) and isinstance(q.values, str):
            return q.values
        value = deck_value(self.deck, "job", "title")
        return value if isinstance(value, str) else ""

    def __repr__(self):
        return "<Result {} analysis={!r} ({})>".format(
            self.filename, self.analysis, ", ".join(self._members) or "empty"
        )


def _strip_comment(line):
    """A deck line without its ``!`` comment (a ``!`` inside quotes is text)."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif c == "!":
            return line[:i]
    return line


def _deck_groups(deck):
    """(name, body) of every namelist group of a deck text, in order; comments removed."""
    text = "\n".join(_strip_comment(line) for line in deck.splitlines())
    groups = []
    i, n = 0, len(text)
    while i < n:
        if text[i] != "&":
            i += 1
            continue
        j = i + 1
        while j < n and (text[j].isalnum() or text[j] == "_"):
            j += 1
        name = text[i + 1 : j].lower()
        quote = None
        k = j
        while k < n:
            c = text[k]
            if quote:
                if c == quote:
                    quote = None
            elif c in "'\"":
                quote = c
            elif c == "/":
                break
            k += 1
        groups.append((name, text[j:k]))
        i = k + 1
    return groups


def deck_value(deck, group, variable):
    """The last value given to ``&group variable`` in a deck text, or ``None``.

    A small helper for the scalar settings of a deck (``deck_value(res.deck, 'job',
    'analysis')``): quoted strings are returned without quotes, anything else as the text
    written; array elements and repeated values are not interpreted. The last assignment wins,
    as in gapbeam (a command-line override follows the deck in the stored text).
    """
    var_re = re.compile(
        r"(?:^|[\s,])" + re.escape(variable) + r"\s*=\s*('[^']*'|\"[^\"]*\"|[^,\s/]+)", re.I
    )
    found = None
    for name, body in _deck_groups(deck):
        if name != group.lower():
            continue
        for m in var_re.finditer(body):
            found = m.group(1)
    if found is not None and found[:1] in "'\"":
        found = found[1:-1]
    return found


def _infer_analysis(res, root_attrs):
    value = root_attrs.get("analysis")
    if isinstance(value, str) and value.strip():
        return value.strip()
    for group, analysis in _ANALYSIS_GROUPS:
        if isinstance(res._members.get(group), Group):
            return analysis
    value = deck_value(res.deck, "job", "analysis")
    if value:
        return value.strip().lower()
    return "unknown"


def load(path):
    """Read a gapbeam result file (``PREFIX.h5``) of any analysis.

    Parameters
    ----------
    path : str, os.PathLike or h5py.File
        The file to read (an open ``h5py.File`` is read and left open).

    Returns
    -------
    Result
        Every group, dataset and attribute of the file, read into memory; the file is closed.

    Examples
    --------
    >>> res = gapbeam.load('results/moon_shaw_10p5hz.h5')
    >>> res.analysis
    'transient'
    >>> res['/poincare/strain'].units
    '-'
    >>> res.diagnostics.label_text.values
    'period_1'
    """
    if isinstance(path, h5py.File):
        return _load_open(path, path.filename)
    filename = os.fspath(path)
    with h5py.File(filename, "r") as f:
        return _load_open(f, filename)


def _load_open(f, filename):
    root_attrs = _decode_attrs(f.attrs)
    res = Result(filename, root_attrs, {})
    Group._from_h5(f, root=res, group=res)
    res.analysis = _infer_analysis(res, root_attrs)
    return res
