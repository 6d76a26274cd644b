"""gapbeam: read the HDF5 result files of the gapbeam vibro-impact code.

>>> import gapbeam
>>> res = gapbeam.load('results/sweep_line_4mm.h5')   # any analysis
>>> res.analysis, res['/sweep/frequency_hz'].units
('sweep', 'Hz')
>>> cols = gapbeam.sweep_table(res)                    # dict of columns, one row per point
>>> strain, strain_rate = gapbeam.poincare(res, point=3)

:func:`load` reads a whole file into a :class:`Result`: every dataset as a :class:`Quantity`
(``.values``, ``.units``, ``.long_name``, ``.path``), reached by path (``res['/sweep/label']``)
or by attribute (``res.sweep.label``), the stored deck text (``res.deck``) and the root
attributes (``res.attrs``). :func:`sweep_table` and :func:`table` give columns that
``pandas.DataFrame`` accepts; :func:`poincare` gives the Poincaré set of a transient run or of
sweep points; :func:`attractors` every start of every point and the attractor it reached;
:func:`parameters` the resolved model values of ``/parameters``; :func:`motion` the deflected
beam at every history sample (``&output state_history``); :data:`CATALOGUE` every dataset
gapbeam writes (path, units, axes, meaning, the analyses that write it), as the program's
``gapbeam --help-outputs tsv`` gives it. Needs numpy and h5py only.
"""

from ._catalogue import DATASETS as CATALOGUE
from ._reader import ANALYSES, Group, Quantity, Result, deck_value, load
from ._tables import PoincareSet, Table, attractors, poincare, sweep_table, table
from ._model import Motion, motion, parameters

__version__ = "0.1.0"

__all__ = [
    "ANALYSES",
    "CATALOGUE",
    "Group",
    "Motion",
    "PoincareSet",
    "Quantity",
    "Result",
    "Table",
    "attractors",
    "deck_value",
    "load",
    "motion",
    "parameters",
    "poincare",
    "sweep_table",
    "table",
]
