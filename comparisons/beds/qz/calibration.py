"""The hysteretic q–z bed calibrated from the continuum, one function per parameter.

- *Capacity*: each spring carries the bearing capacity N_ult over its tributary strip,
  q_ult,i = N_ult · w_i / B (:func:`spring_capacities`), so that the bed's capacity under a
  centred load is the continuum's.
- *Stiffness and its distribution*: the end-stiffened bed whose K_v and K_r are the continuum's
  (closed-form R_k of :func:`..stiffness.end_stiffening`), :func:`qz_stiffnesses`.
- *z50*: the settlement of the continuum's vertical pushover at half its capacity
  (:func:`z50_from_pushover`); under a centred load every spring of a rigid base settles as
  much, and the reduced model gives every spring one near-field z_ref that puts the bed's
  backbone through (z50, N_ult/2) (:func:`upliftlab.reduced.laws.qz.common_zref`). A bed too soft
  to carry N_ult/2 at z50 even with rigid–plastic near fields cannot be calibrated (an
  :class:`InputError` with the least z50 it can take).
- *Gap*: from a cyclic vertical pushover (down, back up past lift-off): the drag (suction)
  ratio is the largest tension the interface carried over N_ult (:func:`suction_from_cyclic`;
  zero for the continuum's unilateral contact), and the width of the near field's elastic
  range is the force span over which the first unloading stays on the initial stiffness
  (:func:`elastic_range_from_unloading`), as a fraction of N_ult.

:func:`calibrate_qz` puts them together from a continuum reference (its stiffnesses, capacity
and vertical pushover).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ....checks import InputError
from ....reduced.compatibility import end_stiffened_bed
from ....reduced.kernels import HISTORY_DTYPE, QZ, qz_commit, qz_start
from ....reduced.laws.qz import (QZ_SOILS, SUCTION_MAX, QzShape, common_zref, qz_springs,
                                z50_lower_bound)
from ....reduced.springs import derive_columns, spring_table
from ..stiffness import end_stiffening


def spring_capacities(capacity: float, widths) -> np.ndarray:
    """q_ult,i = N_ult · w_i / Σ w (force): the capacity ``capacity`` (force) shared over the
    tributary ``widths`` (length)."""
    w = np.asarray(widths, dtype=float)
    return capacity * w / w.sum()


def qz_stiffnesses(K_v: float, K_r: float, half_width: float, springs: int, end_length: float,
                   max_ratio: float) -> tuple[np.ndarray, float, bool]:
    """Initial stiffnesses k_i (force/length) of the end-stiffened bed with the continuum's
    K_v and K_r, its end-stiffness ratio R_k, and whether K_r/K_v was reachable. If it was not
    (no bed under the footing has K_r/K_v above b²), R_k is the nearest bound and K_r is kept,
    K_v missed, as the elastic end-stiffened bed does (:func:`..stiffness.calibrate`):
    rocking is the response the beds are compared in."""
    stiff = end_stiffening(K_r / K_v, half_width, springs, end_length, max_ratio)
    unit = end_stiffened_bed(half_width, 1.0, springs, stiff.ratio, end_length)
    total = K_v if stiff.feasible else K_r / unit.rocking_stiffness
    return np.array(unit.stiffnesses) * total, stiff.ratio, stiff.feasible


def z50_from_pushover(settlement, force, capacity: float) -> float:
    """The settlement (length) at which a monotonic pushover first carries half of
    ``capacity``, interpolated linearly between its points."""
    s, n = np.asarray(settlement, dtype=float), np.asarray(force, dtype=float)
    half = 0.5 * capacity
    above = np.flatnonzero(n >= half)
    if above.size == 0 or above[0] == 0:
        raise InputError(f"vertical pushover: its forces (up to {n.max():g}) never cross half "
                         f"the capacity {half:g} after its first point; push it further")
    i = above[0]
    return float(s[i - 1] + (half - n[i - 1]) / (n[i] - n[i - 1]) * (s[i] - s[i - 1]))


def suction_from_cyclic(force, capacity: float) -> float:
    """Drag ratio of the gap: the largest tension (−force, force positive in compression) a
    cyclic pushover carried, over ``capacity``; 0 if it never pulled. Above QzSimple's
    largest, :data:`~upliftlab.reduced.laws.qz.SUCTION_MAX`, it is an error."""
    tension = max(0.0, -float(np.min(force)))
    ratio = tension / capacity
    if ratio > SUCTION_MAX:
        raise InputError(f"cyclic pushover: tension {tension:g} is {ratio:.3g} of the capacity; "
                         f"the q–z gap's drag takes at most {SUCTION_MAX:g}")
    return ratio


def elastic_range_from_unloading(settlement, force, stiffness: float, capacity: float,
                                 rtol: float = 0.05) -> float:
    """Width of the near field's elastic range as a fraction of ``capacity``, from the first
    unloading of a cyclic pushover (settlement positive down, force positive in compression):
    the force drop from the reversal to the last point whose secant from the reversal is
    still within ``rtol`` of ``stiffness`` (the initial stiffness, force/length)."""
    s, n = np.asarray(settlement, dtype=float), np.asarray(force, dtype=float)
    back = np.flatnonzero(np.diff(s) < 0.0)
    if back.size == 0:
        raise InputError("cyclic pushover: it never unloads (its settlement never decreases)")
    turn = int(back[0])
    up = np.flatnonzero(np.diff(s[turn:]) > 0.0)  # the unloading ends where it reloads
    stop = turn + int(up[0]) + 1 if up.size else s.size
    ds = s[turn] - s[turn + 1:stop]
    dn = n[turn] - n[turn + 1:stop]
    secant = dn / ds
    elastic = np.abs(secant / stiffness - 1.0) <= rtol
    if not elastic[0]:
        return 0.0
    last = int(np.argmin(elastic)) - 1 if not elastic.all() else elastic.size - 1
    return float(dn[last] / capacity)


@dataclass(frozen=True)
class QzCalibration:
    """A q–z bed calibrated from the continuum: ``stiffnesses`` k_i and ``capacities``
    q_ult,i per spring (force/length, force), the end-stiffness ratio ``end_stiffness_ratio``
    and ``end_length`` (fraction of b), ``z50`` (length), ``suction`` (drag ratio), the soil
    shape ``soil``, the bed's ``capacity_multiple`` N_ult/N, and ``feasible`` (K_r/K_v reached)."""

    half_width: float
    springs: int
    vertical_stiffness: float
    stiffnesses: np.ndarray
    capacities: np.ndarray
    end_stiffness_ratio: float
    end_length: float
    z50: float
    suction: float
    soil: str
    capacity_multiple: float
    feasible: bool

    def foundation_table(self) -> dict:
        """The reduced model's ``[foundation]`` table of this bed (law ``qz``)."""
        return {"support": "uplift", "half_width": self.half_width, "layout": "end_stiffened",
                "springs": self.springs, "stiffness": self.vertical_stiffness,
                "end_stiffness_ratio": self.end_stiffness_ratio, "end_length": self.end_length,
                "law": "qz", "capacity_multiple": self.capacity_multiple, "z50": self.z50,
                "suction": self.suction, "qz_soil": self.soil}


def calibrate_qz(ref, springs: int, end_length: float, max_ratio: float, soil: str = "clay",
                 cyclic_force=None) -> QzCalibration:
    """The q–z bed of a continuum reference ``ref`` (its width ``B``, stiffnesses ``K_v`` and
    ``K_r``, capacity ``N_ult`` and ``vertical`` pushover): stiffnesses to its K_v and K_r,
    capacities from its N_ult, z50 from its vertical pushover, and the drag from
    ``cyclic_force`` (the interface force along a cyclic pushover; None: 0, the unilateral
    contact's)."""
    b = 0.5 * ref.B
    k, ratio, feasible = qz_stiffnesses(ref.K_v, ref.K_r, b, springs, end_length, max_ratio)
    widths = np.full(springs, ref.B / springs)
    capacities = spring_capacities(ref.N_ult, widths)
    z50 = z50_from_pushover(ref.vertical["settlement"], ref.vertical["N"], ref.N_ult)
    suction = 0.0 if cyclic_force is None else suction_from_cyclic(cyclic_force, ref.N_ult)
    least = z50_lower_bound(k, capacities, ref.N_ult)
    if z50 <= least:
        raise InputError(f"q–z calibration: the continuum's z50 = {z50:.4g} is below the least "
                         f"settlement {least:.4g} at which this bed (R_k = {ratio:.4g}) can carry "
                         "half the capacity: its softest springs are too soft for its capacities")
    return QzCalibration(b, springs, float(k.sum()), k, capacities, ratio, end_length, z50,
                         suction, soil, ref.N_ult / ref.N, feasible)


def bed_vertical_path(stiffnesses, capacities, z50: float, settlements, soil: str = "clay",
                      suction: float = 0.0, shape: QzShape | None = None) -> np.ndarray:
    """The force (force) a q–z bed carries along a centred settlement path (length, positive
    down, from the unloaded state; any sequence, cyclic too): every spring settles as much,
    each through the compiled law and its history, z_ref from
    :func:`~upliftlab.reduced.laws.qz.common_zref` — what the continuum's vertical pushover is
    compared with. ``shape`` (None: the ``soil``'s) is the backbone's shape."""
    k, q = np.asarray(stiffnesses, dtype=float), np.asarray(capacities, dtype=float)
    shape = QZ_SOILS[soil] if shape is None else shape
    return bed_path_at_zref(k, q, common_zref(k, q, z50, shape), settlements, shape, suction,
                            0.5 * z50)


def bed_path_at_zref(stiffnesses, capacities, zref: float, settlements, shape: QzShape,
                     suction: float = 0.0, zd: float = 0.0) -> np.ndarray:
    """:func:`bed_vertical_path` of a bed given its near-field reference ``zref`` (length)
    instead of z50, and the drag's reference ``zd`` (length; read only with ``suction`` > 0)."""
    k, q = np.asarray(stiffnesses, dtype=float), np.asarray(capacities, dtype=float)
    table = spring_table(k.size)
    table["kind"], table["k"] = QZ, k
    P = derive_columns(qz_springs(table, q, zref, suction, zd, shape))
    H = np.zeros(k.size, dtype=HISTORY_DTYPE)
    for j in range(k.size):
        qz_start(P[j], H[j], 0.0)
    forces = []
    for z in np.asarray(settlements, dtype=float):
        for j in range(k.size):
            qz_commit(P[j], H[j], z)
        forces.append(float(H["qc"].sum()))
    return np.array(forces)


__all__ = ["bed_path_at_zref", "bed_vertical_path", "QZ_SOILS", "QzCalibration", "calibrate_qz",
           "elastic_range_from_unloading", "qz_stiffnesses", "spring_capacities",
           "suction_from_cyclic", "z50_from_pushover"]
