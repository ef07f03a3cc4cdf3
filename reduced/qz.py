"""Parameters of the hysteretic q–z foundation springs (the law: :mod:`.kernels.qz_law`): the
soil types' backbone shapes, z_ref from z50, and the spring records of a bed with their
histories at static equilibrium.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import springs as sp
from .kernels import QZ, qz_backbone, qz_start


@dataclass(frozen=True)
class QzShape:
    """Shape of a soil's near-field backbone (dimensionless): exponent ``n`` of the hyperbola,
    initial elastic half-range ``elast``·q_ult and its largest width ``emax``·q_ult. The values
    are those Boulanger et al. (1999) fitted to Reese and O'Neill's (clay) and Vijayvergiya's
    (sand) q–z curves, as QzSimple1 types 1 and 2 take them."""

    n: float
    elast: float
    emax: float


QZ_SOILS = {"clay": QzShape(n=1.2, elast=0.2, emax=0.7),
            "sand": QzShape(n=5.5, elast=0.3, emax=0.7)}
SUCTION_MAX = 0.1  # the drag capacity QzSimple allows, as a fraction of q_ult


def zref_from_z50(qult, k, z50, shape: QzShape):
    """z_ref (length) that puts the virgin backbone through (z50, q_ult/2), elastic part
    included: z50 = q_ult/(2k) + z_ref·((2(1 − elast))^(1/n) − 1). Takes arrays; z50 must
    exceed the elastic q_ult/(2k) (callers check it and name the field)."""
    qult, k, z50 = (np.asarray(a, dtype=float) for a in (qult, k, z50))
    return (z50 - 0.5 * qult / k) / ((2.0 * (1.0 - shape.elast)) ** (1.0 / shape.n) - 1.0)


def qz_springs(table: np.ndarray, qult, z50, suction: float, shape: QzShape):
    """Turn the foundation rows of a spring ``table`` (``kind``, ``k``, ``f0`` set) into q–z
    springs of capacity ``qult`` and z50 (arrays, force and length) with drag ``suction``·q_ult;
    returns (records with derived columns, their histories at the static force F0)."""
    rows = table["kind"] != sp.STORY
    table = np.array(table, dtype=sp.SPRING_DTYPE)
    qult = np.broadcast_to(np.asarray(qult, dtype=float), rows.sum())
    z50 = np.broadcast_to(np.asarray(z50, dtype=float), rows.sum())
    table["kind"][rows] = QZ
    table["fy"][rows] = np.inf
    table["qult"][rows] = qult
    table["zref"][rows] = zref_from_z50(qult, table["k"][rows], z50, shape)
    table["npow"][rows] = shape.n
    table["elast"][rows] = shape.elast
    table["emax"][rows] = shape.emax
    table["qd"][rows] = suction * qult
    table["zd"][rows] = 0.5 * z50
    P = sp.derive_columns(table)
    H = np.zeros(P.size, dtype=sp.HISTORY_DTYPE)
    for j in np.flatnonzero(rows):
        P["zs"][j] = qz_backbone(P[j], P["f0"][j])
        qz_start(P[j], H[j], P["f0"][j])
    return P, H
