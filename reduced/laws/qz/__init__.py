"""The q–z foundation law: hysteretic springs of the QzSimple class (Boulanger et al. 1999) —
an elastic far field, a Masing near field with a hyperbolic backbone to its capacity, and a gap
with optional drag, in series. Its state is its history (the series' committed state), its
parameters its own columns of the spring record.

:mod:`.backbone` the backbone shapes, z_ref and the bed at rest; :mod:`.compiled` the compiled
law; here the builder (the bed's springs from the scene's :class:`~upliftlab.scenes.laws.QzLaw`)
and the law's entry in the registry.
"""

from __future__ import annotations

import numpy as np

from ....scenes.laws import QzLaw
from ..base import Bed, Law
from ..elastoplastic import elastic_static_forces, support_kind
from ..spring import STORY
from .backbone import (QZ_SOILS, SUCTION_MAX, QzShape, backbone_force, bed_z50,  # noqa: F401
                       check_z50, common_zref, qz_shape, static_forces, z50_lower_bound,
                       zref_from_z50)
from .compiled import (QZ, qz_backbone, qz_commit, qz_force, qz_mode,  # noqa: F401
                       qz_spring_state, qz_start, qz_trial)

__all__ = ["LAW", "QZ", "COLUMNS", "HISTORY", "springs", "qz_springs", "start"]

#: The q–z spring's own fields of the spring record (zero for the other kinds).
COLUMNS = (
    ("qult", np.float64),  # bearing capacity of the spring q_ult (force)
    ("zref", np.float64),  # near-field reference displacement of the hyperbola (length)
    ("npow", np.float64),  # exponent n of the near-field hyperbola (> 1)
    ("elast", np.float64),  # initial half-width of the near-field elastic range / q_ult
    ("emax", np.float64),  # largest width of the near-field elastic range / q_ult
    ("qd", np.float64),    # drag (suction) capacity of the gap, suction · q_ult (force)
    ("zd", np.float64),    # drag reference displacement z50/2 (length)
    ("zs", np.float64),    # total compression of the spring at static equilibrium (length)
)

#: The q–z spring's own fields of the history: the committed state of the series chain.
HISTORY = (
    ("zc", np.float64),   # total compression z (length)
    ("qc", np.float64),   # force Q (force)
    ("zp", np.float64),   # near-field plastic displacement (length)
    ("qr", np.float64),   # near-field elastic range: upper end (force)
    ("ql", np.float64),   # near-field elastic range: lower end (force)
    ("zin", np.float64),  # near-field plastic displacement at the range's ends (length)
    ("wel", np.float64),  # near-field elastic range width (force)
    ("zg", np.float64),   # gap displacement, 0 closed, < 0 open (length)
    ("qg", np.float64),   # drag force (force)
    ("qa", np.float64),   # drag branch anchor: force (force)
    ("za", np.float64),   # drag branch anchor: gap displacement (length)
)


def qz_springs(table: np.ndarray, qult, zref, suction: float, zd: float,
               shape: QzShape) -> np.ndarray:
    """The foundation rows of a spring ``table`` (``k`` and ``f0`` set) as q–z springs of
    capacity ``qult`` (force) and near-field reference ``zref`` (length; arrays or scalars),
    with a drag of ``suction``·q_ult and reference ``zd`` (length, z50/2); ``zs`` is each
    spring's virgin compression at its F0. Returns a new table (derived columns not filled:
    :func:`upliftlab.reduced.springs.derive_columns` does that)."""
    rows = table["kind"] != STORY
    table = np.array(table, dtype=table.dtype)
    count = int(rows.sum())
    qult = np.broadcast_to(np.asarray(qult, dtype=float), count)
    table["kind"][rows] = QZ
    table["fy"][rows] = np.inf
    table["qult"][rows] = qult
    table["zref"][rows] = np.broadcast_to(np.asarray(zref, dtype=float), count)
    table["npow"][rows] = shape.n
    table["elast"][rows] = shape.elast
    table["emax"][rows] = shape.emax
    table["qd"][rows] = suction * qult
    table["zd"][rows] = zd
    for j in np.flatnonzero(rows):
        table["zs"][j] = qz_backbone(table[j], table["f0"][j])
    return table


def springs(law: QzLaw, bed: Bed, table: np.ndarray) -> tuple[np.ndarray, float]:
    """The q–z bed: capacity ``capacity_multiple``·W shared over the tributary widths, one
    near-field z_ref that puts the bed's backbone through (z50, capacity/2) (or ``qz_zref``
    given, and the bed's z50 from it for the drag), static forces on the nonlinear backbones
    (:func:`.backbone.static_forces`) and the drag. The static rotation is the bonded bed's
    (the layout is symmetric: none)."""
    F0, theta = elastic_static_forces(bed)
    table["kind"] = support_kind(bed.support)
    table["f0"] = F0
    table["fy"] = np.inf
    shape = qz_shape(law.qz_soil, law.qz_exponent, law.qz_elastic_range)
    k, w = bed.layout.stiffnesses, bed.layout.widths
    qult = law.capacity_multiple * bed.weight * w / w.sum()
    if law.qz_zref is not None:
        zref, z50 = law.qz_zref, bed_z50(k, qult, law.qz_zref, shape)
    else:
        check_z50(k, qult, law.z50, shape.elast)
        zref, z50 = common_zref(k, qult, law.z50, shape), law.z50
    table["f0"] = static_forces(k, bed.layout.positions, qult, zref, bed.weight, shape)
    return qz_springs(table, qult, zref, law.suction, 0.5 * z50, shape), theta


def start(p, h) -> None:
    """A q–z spring at rest: on its virgin backbone at its static force F0."""
    qz_start(p, h, p["f0"])


LAW = Law(record=QzLaw, springs=springs, kinds=(QZ,), columns=COLUMNS, history=HISTORY,
          start=start)
