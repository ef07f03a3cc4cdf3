"""The backbones of the hysteretic q–z springs (the compiled law: :mod:`.compiled`): the soil
types' shapes, z_ref from the bed's z50 (the settlement at which a centred load reaches half
the capacity) and back, and the bed's static forces on the nonlinear backbones.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ....checks import InputError
from ....scenes.laws.qz import SUCTION_MAX  # noqa: F401  (the drag capacity QzSimple allows)

__all__ = ["QzShape", "QZ_SOILS", "SUCTION_MAX", "qz_shape", "zref_from_z50", "backbone_force",
           "z50_lower_bound", "common_zref", "static_forces", "bed_z50", "check_z50"]


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


def qz_shape(soil: str, exponent: float | None = None,
             elastic_range: float | None = None) -> QzShape:
    """The backbone shape of ``soil`` (:data:`QZ_SOILS`) with its exponent n and its initial
    elastic half-range ``elast`` replaced where given (e.g. fitted to a continuum pushover,
    :mod:`upliftlab.comparisons.beds.qz_fit`). The largest range width is the soil's
    ``emax``, widened to 2·elast when the pristine range is wider, so that the law's cap
    min(·, emax·q_ult) on a reversal never cuts the range below its pristine width."""
    base = QZ_SOILS[soil]
    n = base.n if exponent is None else float(exponent)
    elast = base.elast if elastic_range is None else float(elastic_range)
    return QzShape(n=n, elast=elast, emax=max(base.emax, 2.0 * elast))


def zref_from_z50(qult, k, z50, shape: QzShape):
    """z_ref (length) that puts the virgin backbone through (z50, q_ult/2), elastic part
    included: z50 = q_ult/(2k) + z_ref·((2(1 − elast))^(1/n) − 1). Takes arrays; z50 must
    exceed the elastic q_ult/(2k) (callers check it and name the field)."""
    qult, k, z50 = (np.asarray(a, dtype=float) for a in (qult, k, z50))
    return (z50 - 0.5 * qult / k) / ((2.0 * (1.0 - shape.elast)) ** (1.0 / shape.n) - 1.0)


def backbone_force(z, k, qult, zref, shape: QzShape, iterations: int = 200) -> np.ndarray:
    """Forces (force) on the virgin backbones at compression z (length), by bisection on the
    closed-form z(Q) (arrays broadcast; an inverse independent of the compiled law's solver)."""
    z, k, qult, zref = np.broadcast_arrays(*(np.asarray(a, dtype=float)
                                             for a in (z, k, qult, zref)))
    qr = shape.elast * qult
    lo, hi = np.zeros(z.shape), qult.copy()
    for _ in range(iterations):
        q = 0.5 * (lo + hi)
        with np.errstate(divide="ignore", invalid="ignore"):
            plastic = np.where(q > qr, zref * (((qult - qr) / (qult - q)) ** (1.0 / shape.n)
                                               - 1.0), 0.0)
        low = q / k + plastic < z
        lo, hi = np.where(low, q, lo), np.where(low, hi, q)
    return 0.5 * (lo + hi)


def z50_lower_bound(k, qult, capacity: float) -> float:
    """The least settlement (length) at which a bed of stiffnesses ``k`` and capacities
    ``qult`` can carry half of ``capacity`` = Σ q_ult: where Σ min(k_i z, q_ult,i) reaches it
    (each spring elastic–perfectly plastic, the limit z_ref → 0 of its backbone)."""
    k, qult = np.asarray(k, dtype=float), np.asarray(qult, dtype=float)
    corners = np.sort(qult / k)
    carried = np.array([np.minimum(k * z, qult).sum() for z in corners])
    i = int(np.argmax(carried >= 0.5 * capacity))
    z_hi = corners[i]
    z_lo = corners[i - 1] if i > 0 else 0.0
    f_lo = np.minimum(k * z_lo, qult).sum()
    return float(z_lo + (0.5 * capacity - f_lo) / (carried[i] - f_lo) * (z_hi - z_lo))


def common_zref(k, qult, z50: float, shape: QzShape) -> float:
    """The near-field reference z_ref (length), one for every spring (a property of the soil),
    that puts the bed's virgin backbone under a centred load through (z50, Σ q_ult/2): every
    spring of a base that does not rotate settles z50, and their forces sum to half the
    capacity. For a bed whose k_i are proportional to q_ult,i it is :func:`zref_from_z50`.
    z50 must exceed :func:`z50_lower_bound` (callers check it and name the field)."""
    k, qult = np.asarray(k, dtype=float), np.asarray(qult, dtype=float)
    half = 0.5 * qult.sum()

    def excess(log_zref):
        return backbone_force(z50, k, qult, np.exp(log_zref), shape).sum() - half

    lo, hi = np.log(z50) - 60.0, np.log(z50) + 60.0
    return float(np.exp(brentq(excess, lo, hi, xtol=1e-14, rtol=1e-15, maxiter=500)))


def static_forces(stiffnesses, positions, qult, zref: float, weight: float,
                  shape: QzShape) -> np.ndarray:
    """The springs' forces F0 (force) at rest under ``weight`` on their virgin backbones
    (capacities ``qult``, reference ``zref``): the compression z at which their forces sum to
    the weight, the same for every spring of a base that does not rotate. A layout whose
    forces would then make a moment about the centre (an asymmetric one) is an
    :class:`InputError`."""
    k = np.asarray(stiffnesses, dtype=float)

    def excess(z):
        return backbone_force(z, k, qult, zref, shape).sum() - weight

    hi = weight / k.sum()
    while excess(hi) < 0.0:
        hi *= 2.0
    z = brentq(excess, 0.0, hi, xtol=1e-15 * hi, rtol=1e-15, maxiter=500)
    forces = backbone_force(z, k, qult, zref, shape)
    x = np.asarray(positions, dtype=float)
    moment = float(np.sum(forces * x))
    if abs(moment) > 1e-9 * weight * np.max(np.abs(x)):
        raise InputError(f"foundation.law = 'qz': the layout's springs carry a moment "
                         f"{moment:.4g} about the centre at rest; the q–z bed needs a layout "
                         "symmetric about the centre")
    return forces


def bed_z50(stiffnesses, qult, zref: float, shape: QzShape) -> float:
    """The settlement (length) at which a bed's springs, all settling alike on their virgin
    backbones (one near-field reference ``zref``), carry half their capacity together: the
    bed's z50 when z_ref is given instead (a shape whose elastic ranges alone carry half the
    capacity has no z_ref that z50 fixes)."""
    k, q = np.asarray(stiffnesses, dtype=float), np.asarray(qult, dtype=float)
    half = 0.5 * q.sum()

    def excess(z):
        return backbone_force(z, k, q, zref, shape).sum() - half

    hi = half / k.sum()
    while excess(hi) < 0.0:
        hi *= 2.0
    return float(brentq(excess, 0.0, hi, xtol=1e-15 * hi, rtol=1e-15, maxiter=500))


def check_z50(stiffnesses, qult, z50: float, elast: float = 0.0) -> None:
    """z50 must exceed the least settlement at which the bed can carry half its capacity
    (:func:`z50_lower_bound`), and, when the springs' elastic ranges (``elast``·q_ult) alone
    can carry half of it, stay below the settlement at which they do: beyond it every z_ref
    puts more than half the capacity on the bed at z50."""
    least = z50_lower_bound(stiffnesses, qult, float(np.sum(qult)))
    if z50 <= least:
        raise InputError(f"foundation.z50 = {z50:g}: the bed cannot carry half its capacity at "
                         f"that settlement even with rigid–plastic near fields (its springs, "
                         f"elastic up to q_ult, reach it at {least:.4g}); valid range is "
                         f"> {least:.4g}")
    q = np.asarray(qult, dtype=float)
    if elast * q.sum() > 0.5 * q.sum():
        most = z50_lower_bound(stiffnesses, elast * q, float(q.sum()))
        if z50 >= most:
            raise InputError(f"foundation.z50 = {z50:g}: the springs' far fields alone carry "
                             f"half the capacity at {most:.4g} (elastic range {elast:g} of "
                             f"q_ult), so no z_ref puts the bed through z50; valid range is "
                             f"({least:.4g}, {most:.4g}), or give foundation.qz_zref")
