"""The end-stiffened elasto-plastic bed whose capacity profile is fitted to the continuum's
rocking pushovers, with the impedance dashpots.

Where a bed's springs yield decides how it settles when it rocks. Two conventions bracket the
continuum: ``end_stiffened_plastic`` yields each spring at FS_v times its static force, so the
stiffened ends hold R_k times the middle's bearing pressure and hardly yield (it misses the
continuum's settlement by −50 to −100 % on the clay's pulse grid); ``end_stiffened_bearing``
yields every spring at one bearing pressure V_ult/B, so the ends, which carry R_k times the
middle's pressure at rest, yield at once and the bed settles up to 2.4 times as far. This bed
takes the one-parameter family between them,

    q_y,i ∝ (k_i/w_i)^β,    Σ q_y,i w_i = V_ult,

(β = 0 the uniform bearing pressure, β = 1 the stiffness-weighted yield), and fits β ∈ [0, 1]
to the continuum's own static rotation pushovers at the point's N: the monotonic path's moment
and settlement increment at each of the map's θ/θ_on ratios and the settlement one cycle at
each amplitude leaves (relative errors against the statics rows' floors, least squares over
β on a grid of :data:`BETAS`). The dynamic runs are not used: the fit sees only statics, and
the map then measures the bed on the dynamics like every other.

Needs in ``BedReference.extra``: ``rocking`` (the continuum's ``cyclic`` and ``monotonic``
pushover records at the point's N, with ``theta_on``), ``structure`` and ``impedance`` (for
the dashpots, :mod:`.dashpots`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...checks import InputError
from ...reduced.compatibility import end_stiffened_bed
from .base import required_extra, base_builder, base_table
from .dashpots import impedance_dashpots_of
from .pushover import FLOORS, bed_rocking

__all__ = ["FITTED", "BETAS", "CapacityFit", "capacity_profile", "fit_capacity_profile",
           "build_end_stiffened_fitted_impedance"]

#: This bed's name in :data:`.beds.BEDS`.
FITTED = "end_stiffened_fitted_impedance"
#: The exponents β tried, 0 to 1 by 0.05 (a tie goes to the lowest: where the statics do not
#: tell the profiles apart, nothing yields in them and β is not identifiable).
BETAS = tuple(round(0.05 * i, 2) for i in range(21))


@dataclass(frozen=True)
class CapacityFit:
    """The fitted profile: ``beta``, ``misfit`` its root-mean-square relative error over the
    fitted quantities, and ``misfits`` that of every β of :data:`BETAS`."""

    beta: float
    misfit: float
    misfits: tuple[float, ...]


def capacity_profile(stiffnesses, widths, capacity: float, beta: float) -> np.ndarray:
    """Yield forces (force) of springs with ``stiffnesses`` (force/length) and tributary
    ``widths`` (length) whose bearing pressures at yield grow as (k_i/w_i)^β and add up to
    ``capacity`` (force) over the bed."""
    k, w = np.asarray(stiffnesses, dtype=float), np.asarray(widths, dtype=float)
    pressure = (k / w) ** beta
    return capacity * w * pressure / np.sum(w * pressure)


def _rocking(reference) -> dict:
    rocking = required_extra(reference, "rocking", "the fitted bed needs the continuum's "
                             "cyclic and monotonic rotation pushovers at the point's N")
    if "error" in rocking:
        raise InputError(f"the fitted bed at N = {reference.N:g} ({reference.soil}): the "
                         f"continuum's rotation pushover stopped ({rocking['error']}), so there "
                         f"is nothing to fit its capacity profile to; leave the bed out "
                         f"(--beds, options.beds) or mend the pushover")
    return rocking


def _at(record, key: str, theta: float) -> float:
    thetas = np.asarray(record["theta"], dtype=float)
    return float(np.asarray(record[key], dtype=float)[int(np.argmin(np.abs(thetas - theta)))])


def _quantities(monotonic, cyclic, theta_on: float, ratios) -> np.ndarray:
    """M and the settlement increment at each ratio × θ_on on the monotonic path, then the
    settlement over the cyclic path."""
    s0 = _at(monotonic, "settlement", 0.0)
    moments = [_at(monotonic, "M", r * theta_on) for r in ratios]
    settlements = [_at(monotonic, "settlement", r * theta_on) - s0 for r in ratios]
    cycle = float(cyclic["settlement"][-1] - cyclic["settlement"][0])
    return np.array(moments + settlements + [cycle])


def _floors(reference, continuum_s0: float, ratios) -> np.ndarray:
    moment = FLOORS["moment"] * reference.N * reference.B
    settlement = FLOORS["settlement"] * abs(continuum_s0)
    return np.array([moment] * len(ratios) + [settlement] * (len(ratios) + 1))


def _bed_table(reference, options, beta: float) -> dict:

    table = dict(base_builder("end_stiffened_plastic")(reference, options))
    bed = end_stiffened_bed(0.5 * reference.B, table["stiffness"], table["springs"],
                            table["end_stiffness_ratio"], table["end_length"])
    table.pop("yield_multiple")
    table["yield_forces"] = [float(f) for f in capacity_profile(
        bed.stiffnesses, bed.widths, reference.V_ult, beta)]
    return table


_FITS: dict[tuple, CapacityFit] = {}


def fit_capacity_profile(reference, options) -> CapacityFit:
    """β of the bed at ``reference`` (module docstring), computed once per soil, N and bed
    (cached)."""
    rocking = _rocking(reference)
    monotonic, cyclic = rocking["monotonic"], rocking["cyclic"]
    theta_on = float(rocking["theta_on"])
    ratios = tuple(options.theta_ratios)
    key = (reference.soil, reference.N, reference.B, reference.K_v, reference.K_r,
           reference.V_ult, options.springs, options.end_length,
           options.max_end_stiffness_ratio, ratios, tuple(monotonic["settlement"]),
           tuple(cyclic["settlement"]), tuple(monotonic["M"]))
    if key in _FITS:
        return _FITS[key]
    target = _quantities(monotonic, cyclic, theta_on, ratios)
    floors = _floors(reference, _at(monotonic, "settlement", 0.0), ratios)
    scale = np.maximum(np.abs(target), floors)
    base = base_table()
    base["structure"] = dict(reference.extra.get("structure") or base["structure"])
    base["foundation"] = {**base["foundation"], "half_width": 0.5 * reference.B}
    misfits = []
    for beta in BETAS:
        table = {"support": "uplift", "half_width": 0.5 * reference.B,
                 **_bed_table(reference, options, beta)}
        pushed = bed_rocking(base, reference.N, table, cyclic["theta"], monotonic["theta"])
        got = _quantities(pushed["monotonic"], pushed["cyclic"], theta_on, ratios)
        misfits.append(float(np.sqrt(np.mean(((got - target) / scale) ** 2))))
    low = float(np.min(misfits))
    best = next(i for i, m in enumerate(misfits) if m <= low * (1.0 + 1e-9) + 1e-12)  # ties
    if not math.isfinite(misfits[best]):
        raise InputError(f"the fitted bed at N = {reference.N:g}: no capacity profile pushes "
                         "over to a finite moment and settlement")
    _FITS[key] = CapacityFit(BETAS[best], misfits[best], tuple(misfits))
    return _FITS[key]


def build_end_stiffened_fitted_impedance(reference, options) -> dict:
    """The end-stiffened elasto-plastic bed with the fitted capacity profile and the
    continuum impedance's dashpots (module docstring)."""
    table = _bed_table(reference, options, fit_capacity_profile(reference, options).beta)
    table["dashpots"] = list(impedance_dashpots_of(reference, options).dashpots)
    return table
