"""The q–z backbone's shape fitted to the continuum's whole vertical pushover.

The one-point calibration (:func:`.calibration.calibrate_qz`) puts the bed's backbone
through (z50, N_ult/2) with a soil's textbook shape; the continuum's pushover on clay is nearly
linear to about half its capacity and then bends sharply, which that hyperbola is not (it
overshoots the continuum by up to 15 % of N_ult between z50 and 2·z50). Here the law's three
free shape parameters — the near field's reference z_ref (equivalently the bed's z50), the
initial elastic half-range ``elast`` (the part of q_ult carried by the far field alone) and
the hyperbola's exponent n — are chosen by :func:`scipy.optimize.least_squares` (bounded) to
minimise the misfit between the bed's centred path (:func:`.calibration.bed_path_at_zref`,
the compiled law) and the continuum's path at every point of the pushover, for a given bed
(stiffnesses k_i and capacities q_ult,i; the caller states which distribution: K_v kept or
K_r kept). The range's largest width ``emax`` does not show in a monotonic path: it is the
soil's, widened to 2·elast (:func:`upliftlab.reduced.laws.qz.qz_shape`).

Misfits are fractions of the bed's capacity Σ q_ult (= N_ult): the largest and the rms of
(bed − continuum)/N_ult over the pushover's points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ....checks import InputError
from ....reduced.laws.qz import QzShape, bed_z50, qz_shape, z50_lower_bound
from ....scenes.laws.qz import QZ_ELASTIC_RANGE_MAX, QZ_EXPONENT_MAX
from .calibration import bed_path_at_zref, bed_vertical_path, z50_from_pushover

__all__ = ["QzFit", "fit_backbone", "path_misfit", "one_point_misfit"]

#: Bounds of the fitted exponent n: above 1 (the law's work integral) and at most the scene's
#: largest; a pushover of ten points hardly tells a sharper bend apart.
FIT_EXPONENT = (1.05, QZ_EXPONENT_MAX)
#: Bounds of the fitted elastic range elast: inside the scene's, so that a fitted shape is
#: always one a scene accepts.
FIT_ELASTIC_RANGE = (0.0, min(0.9, QZ_ELASTIC_RANGE_MAX))
#: Starting points (elast, n) of the local fits; the best is kept (the misfit is not convex).
STARTS = ((0.1, 1.5), (0.3, 3.0), (0.5, 5.0), (0.7, 2.0))


@dataclass(frozen=True)
class QzFit:
    """A backbone fitted to a pushover: ``z50`` (length) the bed's settlement at half its
    capacity, ``zref`` (length) the springs' near-field reference, ``elastic_range`` elast and
    ``exponent`` n, ``emax`` the range's largest width (fractions of q_ult; not fitted),
    ``misfit_max`` and ``misfit_rms`` of (bed − continuum)/N_ult over the pushover's points,
    ``residuals`` those fractions point by point."""

    z50: float
    zref: float
    elastic_range: float
    exponent: float
    emax: float
    misfit_max: float
    misfit_rms: float
    residuals: tuple[float, ...]

    @property
    def shape(self) -> QzShape:
        """The fitted :class:`~upliftlab.reduced.laws.qz.QzShape`."""
        return QzShape(n=self.exponent, elast=self.elastic_range, emax=self.emax)


def _pushover(settlement, load) -> tuple[np.ndarray, np.ndarray]:
    s, n = np.asarray(settlement, dtype=float), np.asarray(load, dtype=float)
    if s.ndim != 1 or s.size < 4 or s.size != n.size:
        raise InputError(f"vertical pushover: {s.size} settlements and {n.size} loads; give "
                         "one load per settlement, at least 4 points")
    if not (np.all(np.isfinite(s)) and np.all(np.isfinite(n))):
        raise InputError("vertical pushover: a settlement or load is not finite")
    if s[0] <= 0.0 or np.any(np.diff(s) <= 0.0):
        raise InputError(f"vertical pushover: settlements {s.tolist()!r} must be positive and "
                         "increasing (a monotonic pushover from the unloaded state)")
    return s, n


def path_misfit(settlement, load, stiffnesses, capacities, z50: float,
                shape: QzShape) -> np.ndarray:
    """(bed − continuum)/Σ q_ult at each point of the pushover (settlement, length; load,
    force) for the bed through (z50, Σ q_ult/2) of backbone ``shape``."""
    s, n = _pushover(settlement, load)
    capacity = float(np.sum(capacities))
    return (bed_vertical_path(stiffnesses, capacities, z50, s, shape=shape) - n) / capacity


def one_point_misfit(settlement, load, stiffnesses, capacities, soil: str = "clay",
                     capacity: float | None = None) -> tuple[float, float, float]:
    """The one-point calibration's (z50 where the pushover reaches half of ``capacity``, None:
    Σ q_ult; the ``soil``'s shape) largest and rms misfit, as fractions of Σ q_ult, and its
    z50 (length)."""
    s, n = _pushover(settlement, load)
    total = float(np.sum(capacities))
    z50 = z50_from_pushover(np.concatenate([[0.0], s]), np.concatenate([[0.0], n]),
                            total if capacity is None else capacity)
    r = path_misfit(s, n, stiffnesses, capacities, z50, qz_shape(soil))
    return float(np.max(np.abs(r))), float(np.sqrt(np.mean(r * r))), z50


def fit_backbone(settlement, load, stiffnesses, capacities, soil: str = "clay") -> QzFit:
    """The shape (z_ref, elast, n) whose bed path fits the pushover (settlement, length;
    load, force: its points from the first step on, monotonic) best in least squares, for the
    bed of ``stiffnesses`` k_i (force/length) and ``capacities`` q_ult,i (force); emax from the
    ``soil`` (:func:`upliftlab.reduced.laws.qz.qz_shape`). Several starts (:data:`STARTS`), the
    best kept. z50 of the result is the fitted bed's (:func:`upliftlab.reduced.laws.qz.bed_z50`);
    with an elastic range above half the capacity it does not fix z_ref, which a scene then
    takes as ``foundation.qz_zref``."""
    s, n = _pushover(settlement, load)
    k, q = np.asarray(stiffnesses, dtype=float), np.asarray(capacities, dtype=float)
    if k.shape != q.shape or k.size == 0 or np.any(k <= 0.0) or np.any(q <= 0.0):
        raise InputError("fit_backbone: give one positive stiffness and capacity per spring")
    capacity = float(q.sum())
    (e_lo, e_hi), (n_lo, n_hi) = FIT_ELASTIC_RANGE, FIT_EXPONENT
    scale = float(s[-1])

    def residuals(x):
        zref, elast, expo = scale * np.exp(x[0]), x[1], x[2]
        shape = qz_shape(soil, expo, elast)
        return (bed_path_at_zref(k, q, zref, s, shape) - n) / capacity

    z_half = max(z50_lower_bound(k, q, capacity), 1e-12 * scale)
    best = None
    for elast0, n0 in STARTS:
        x0 = np.array([np.log(0.3 * z_half / scale), elast0, n0])
        fit = least_squares(residuals, x0, bounds=([np.log(1e-8), e_lo, n_lo],
                                                   [np.log(1e3), e_hi, n_hi]),
                            x_scale=[1.0, 0.1, 1.0], xtol=1e-12, ftol=1e-12, gtol=1e-12,
                            max_nfev=400)
        if best is None or fit.cost < best.cost:
            best = fit
    zref, elast, expo = scale * float(np.exp(best.x[0])), float(best.x[1]), float(best.x[2])
    shape = qz_shape(soil, expo, elast)
    r = residuals(best.x)
    return QzFit(bed_z50(k, q, zref, shape), zref, elast, expo, shape.emax,
                 float(np.max(np.abs(r))), float(np.sqrt(np.mean(r * r))),
                 tuple(float(v) for v in r))
