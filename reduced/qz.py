"""Parameters of the hysteretic q–z foundation springs (the law: :mod:`.kernels.qz_law`): the
soil types' backbone shapes, z_ref from z50, the spring records of a bed, its static forces on
the nonlinear backbones and the springs' histories at rest.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..checks import InputError
from . import springs as sp
from .kernels import QZ, qz_backbone, qz_start, qz_trial


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


def qz_springs(table: np.ndarray, qult, z50, suction: float, shape: QzShape) -> np.ndarray:
    """The foundation rows of a spring ``table`` (``k`` and ``f0`` set) as q–z springs of
    capacity ``qult`` and z50 (arrays or scalars, force and length) with drag
    ``suction``·q_ult; ``zs`` is each spring's virgin compression at its F0. Returns a new
    table (derived columns not filled: :func:`~.springs.derive_columns` does that)."""
    rows = table["kind"] != sp.STORY
    table = np.array(table, dtype=sp.SPRING_DTYPE)
    count = int(rows.sum())
    qult = np.broadcast_to(np.asarray(qult, dtype=float), count)
    z50 = np.broadcast_to(np.asarray(z50, dtype=float), count)
    table["kind"][rows] = QZ
    table["fy"][rows] = np.inf
    table["qult"][rows] = qult
    table["zref"][rows] = zref_from_z50(qult, table["k"][rows], z50, shape)
    table["npow"][rows] = shape.n
    table["elast"][rows] = shape.elast
    table["emax"][rows] = shape.emax
    table["qd"][rows] = suction * qult
    table["zd"][rows] = 0.5 * z50
    for j in np.flatnonzero(rows):
        table["zs"][j] = qz_backbone(table[j], table["f0"][j])
    return table


def initial_history(params: np.ndarray) -> np.ndarray:
    """The springs' history at the start of a run: zeros, and every q–z spring on its virgin
    backbone at its static force F0."""
    H = np.zeros(params.size, dtype=sp.HISTORY_DTYPE)
    for j in np.flatnonzero(params["kind"] == QZ):
        qz_start(params[j], H[j], params["f0"][j])
    return H


def static_forces(stiffnesses, positions, widths, weight: float, capacity: float, z50: float,
                  shape: QzShape) -> np.ndarray:
    """The springs' forces F0 (force) at rest under ``weight`` on virgin q–z backbones of
    capacities ``capacity``·w_i/Σw and the given z50: the compression z at which their forces
    sum to the weight, the same for every spring of a base that does not rotate. A layout whose
    forces would then make a moment about the centre (an asymmetric one) is an
    :class:`InputError`."""
    k = np.asarray(stiffnesses, dtype=float)
    w = np.asarray(widths, dtype=float)
    qult = capacity * w / w.sum()
    table = sp.spring_table(k.size)
    table["kind"], table["k"] = QZ, k
    table = qz_springs(table, qult, z50, 0.0, shape)
    H = np.zeros(k.size, dtype=sp.HISTORY_DTYPE)
    for j in range(k.size):
        qz_start(table[j], H[j], 0.0)

    def excess(z):
        return sum(qz_trial(table[j], H[j], z)[0] for j in range(k.size)) - weight

    hi = weight / k.sum()
    while excess(hi) < 0.0:
        hi *= 2.0
    z = brentq(excess, 0.0, hi, xtol=1e-15 * hi, rtol=1e-15, maxiter=500)
    forces = np.array([qz_trial(table[j], H[j], z)[0] for j in range(k.size)])
    x = np.asarray(positions, dtype=float)
    moment = float(np.sum(forces * x))
    if abs(moment) > 1e-9 * weight * np.max(np.abs(x)):
        raise InputError(f"foundation.law = 'qz': the layout's springs carry a moment "
                         f"{moment:.4g} about the centre at rest; the q–z bed needs a layout "
                         "symmetric about the centre")
    return forces


def check_z50(stiffnesses, widths, capacity: float, z50: float) -> None:
    """z50 must exceed every spring's elastic displacement at half capacity, q_ult/(2k)."""
    k = np.asarray(stiffnesses, dtype=float)
    w = np.asarray(widths, dtype=float)
    elastic = 0.5 * capacity * w / w.sum() / k
    if z50 <= elastic.max():
        raise InputError(f"foundation.z50 = {z50:g}: below the elastic displacement at half "
                         f"capacity of the softest spring, q_ult/(2k) = {elastic.max():.4g}; "
                         f"valid range is > {elastic.max():.4g}")
