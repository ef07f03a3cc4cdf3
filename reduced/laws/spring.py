"""The spring record every law fills and the compiled kernels read, its history, and the codes
every law shares: the story spring's kind, the modes, and the compile options of helpers.

Spring parameters are a structured array, one record per spring, and the spring history
another. Their dtypes (:data:`upliftlab.reduced.laws.SPRING_DTYPE` and ``HISTORY_DTYPE``) are
the base fields here followed by the fields of each registered law that has its own (the q–z
law's capacity, backbone and series state). Records keep the laws readable (``p.k``, ``h.ep``)
and fast: unlike array rows they carry no reference count. Each spring carries its column of A
in its record (``nnz`` entries ``a0…a2`` at DOFs ``i0…i2``): every spring touches two or three
DOFs, so e = Aᵀq and the nodal forces A s are gathered and scattered per spring.

Every foundation law fills the base fields that the bookkeeping reads whatever the law (``k``,
``f0``, ``fy``, ``x``; ``ep`` in its history, its settlement since rest, so that
F0/k + e − ep is its compression) and reports one of the foundation modes for output.
"""

from __future__ import annotations

import numpy as np

__all__ = ["SPRING_FIELDS", "HISTORY_FIELDS", "STORY", "SEPARATED", "CONTACT", "YIELDING",
           "CLIPPED", "ELASTIC", "YIELD_POS", "YIELD_NEG", "HOT"]

try:  # numba's own switch for helpers that never allocate (numba.core.options.DefaultOptions)
    from numba.core.options import DefaultOptions as _DefaultOptions
    HOT = {"_nrt": False} if hasattr(_DefaultOptions, "_nrt") else {}
except ImportError:  # pragma: no cover
    HOT = {}

SPRING_FIELDS = (
    ("kind", np.int64),   # STORY, or a foundation law's kind (its compiled forms dispatch on it)
    ("nnz", np.int64),    # how many DOFs the spring connects (its column of A): 2 or 3
    ("i0", np.int64), ("i1", np.int64), ("i2", np.int64),          # their indices in q
    ("a0", np.float64), ("a1", np.float64), ("a2", np.float64),    # and the entries of A
    ("k", np.float64),    # stiffness (story: its elastic-plastic part) (force/length)
    ("c", np.float64),    # parallel dashpot (force·s/length)
    ("cimp", np.float64),  # impact dashpot c* (force·s/length)
    ("f0", np.float64),   # static compression F0 (force)
    ("fy", np.float64),   # yield force (force; inf = elastic)
    ("kh", np.float64),   # parallel hardening stiffness of a story (force/length)
    ("dzf", np.float64),  # impact stroke per unit closing velocity, m_eff (1 − ε)/c* (s)
    ("x", np.float64),    # position under the base (length)
    ("imph", np.float64),  # largest stable RK4 step while the impact dashpot acts (s)
    ("d0", np.float64),   # derived: δ0 = F0/k (length)
    ("dy", np.float64),   # derived: Fy/k (length)
    ("gs", np.float64),   # derived: 1/F0 (story: 1/Fy; 0 if elastic) (1/force)
    ("gd", np.float64),   # derived: 1/δ0 (1/length)
    ("share", np.float64),  # derived: c*/(c + c*), the impact dashpot's share
    ("arm", np.float64),  # story: its height above the story below, the lever of its shear
)

HISTORY_FIELDS = (
    ("ep", np.float64),   # plastic deformation: settlement, or plastic story drift (length)
    ("imp", np.float64),  # 1 while the impact dashpot acts, else 0
    ("e0", np.float64),   # deformation at the last recontact (length)
    ("dz", np.float64),   # impact stroke Δz of the last recontact (length)
)

STORY = 0  # the story spring (and the sway spring), whose forms are the kernels' own
SEPARATED, CONTACT, YIELDING, CLIPPED = 0, 1, 2, 3  # foundation modes
ELASTIC, YIELD_POS, YIELD_NEG = 0, 1, 2  # story modes
