"""Is one calibrated bed enough for the map? The map's goal, judged from its data.

A calibrated bed can stand in for the continuum over the map when one bed is within the θ
tolerance (10 %) of it in both peak θ and peak edge uplift at most of the map's points, more
than :data:`GOAL_SHARE` of them, while it runs at least :data:`GOAL_SPEEDUP` times faster
(median over the points, same machine). Where no bed is, the verdict says where the best one
misses (its share per soil and FS_v) and how (of its misses, how many lift the edge further
than the continuum and how many less): the mechanism it lacks, which the summary's signed
medians per FS_v then locate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .parts import bearing_failures, errors_of, options_of, point_values
from .grid import MEASURES, SOIL_LABELS

__all__ = ["GOAL_SHARE", "GOAL_SPEEDUP", "Goal", "hits", "goal", "goal_text"]

#: "Most of the map": the share of its points a bed must be within tolerance at.
GOAL_SHARE = 0.5
#: The least median speed-up over the continuum (wall time ratio) for a bed to count.
GOAL_SPEEDUP = 1000.0


def hits(ds) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(hit, counted, failed, called): ``hit`` (…, motion, calibration) the bed is within
    ``theta_tolerance`` in peak θ and edge uplift, or, where the continuum's soil failed in
    bearing (``failed``, …, motion), the bed's failed too (``called``, …, motion,
    calibration); ``counted`` (…, motion) the points that count: the continuum run finished
    or ended in a bearing failure (a point whose solver gave up has nothing to be within of)."""
    thr = options_of(ds)["theta_tolerance"]
    e = np.nan_to_num(np.abs(errors_of(ds)), nan=np.inf)
    q = MEASURES.index
    within = (e[..., q("theta")] <= thr) & (e[..., q("uplift")] <= thr)
    ran = np.isfinite(point_values(ds, "continuum_theta"))
    failed, called = bearing_failures(ds)
    return np.where(failed[..., None], called, within), ran | failed, failed, called


@dataclass(frozen=True)
class Goal:
    """The verdict: ``met`` when ``bed`` (the largest share among the beds at least
    ``speedup_needed`` times faster, else among all) is within ``threshold`` at more than
    ``share_needed`` of the points. ``share`` its share, ``speedup`` its median speed-up;
    ``by_soil_fs_v`` its share per (soil, FS_v); of its misses away from bearing failures
    and refused runs (``misses``), ``over`` the fraction where its edge uplift exceeds the
    continuum's by more than ``threshold`` and ``under`` where it falls short by more (the
    rest miss in θ alone)."""

    met: bool
    bed: str
    share: float
    speedup: float
    threshold: float
    share_needed: float
    speedup_needed: float
    by_soil_fs_v: dict
    misses: int
    over: float
    under: float


def goal(ds, by_bed: dict, speedup: dict) -> Goal:
    """The verdict for the map dataset ``ds`` from each calibration's share (``by_bed``, as
    :func:`.analysis.share` counts it) and median speed-up (``speedup``)."""
    names = [str(c) for c in ds["calibration"].values]
    fast = [n for n in names if math.isfinite(speedup[n]) and speedup[n] >= GOAL_SPEEDUP]
    bed = max(fast or names, key=lambda n: (_or_less(by_bed[n]), -names.index(n)))
    c = names.index(bed)
    hit, counted, failed, _ = hits(ds)
    by_cell = {}
    for s, soil in enumerate(str(v) for v in ds["soil"].values):
        for f, fs in enumerate(ds["fs_v"].values.tolist()):
            points = counted[s, f]
            by_cell[(soil, float(fs))] = (float(hit[s, f][points][:, c].mean()) if points.any()
                                          else math.nan)
    thr = options_of(ds)["theta_tolerance"]
    errors = errors_of(ds)[..., c, :]
    finite = np.isfinite(errors[..., MEASURES.index("theta")]) & np.isfinite(
        errors[..., MEASURES.index("uplift")])
    missed = counted & ~failed & finite & ~hit[..., c]
    uplift = errors[..., MEASURES.index("uplift")][missed]
    n = int(missed.sum())
    over = float((uplift > thr).sum() / n) if n else math.nan
    under = float((uplift < -thr).sum() / n) if n else math.nan
    met = bed in fast and by_bed[bed] > GOAL_SHARE
    return Goal(met, bed, by_bed[bed], speedup[bed], thr, GOAL_SHARE, GOAL_SPEEDUP, by_cell,
                n, over, under)


def _or_less(value: float) -> float:
    """A share to compare: NaN (no point counted) below every measured share."""
    return value if math.isfinite(value) else -math.inf


def _share(value: float) -> str:
    return f"{100 * value:.0f} %" if math.isfinite(value) else "no point"


def goal_text(goal: Goal) -> str:
    """The verdict in a paragraph, every number from :class:`Goal`."""
    thr = f"{100 * goal.threshold:g} %"
    head = (f"The goal, one calibrated bed within {thr} of the continuum in both peak θ and "
            f"peak edge uplift at most of the map's points (more than "
            f"{100 * goal.share_needed:g} %) at {goal.speedup_needed:,.0f} times less cost or "
            f"more, is **{'met' if goal.met else 'not met'}**: ")
    speed = (f"a median speed-up of {goal.speedup:,.0f}" if math.isfinite(goal.speedup)
             else "no measured speed-up")
    which = ("the best bed at that speed" if goal.speedup >= goal.speedup_needed
             else "no bed is that fast; the best bed" if math.isfinite(goal.speedup)
             else "no speed-up was measured; the best bed")
    share = f"{100 * goal.share:.1f} %" if math.isfinite(goal.share) else "none"
    head += f"{which}, {goal.bed} ({speed}), is within {thr} at {share} of the points."
    soils = {}
    for (soil, fs), value in goal.by_soil_fs_v.items():
        soils.setdefault(soil, []).append(f"{_share(value)} at FS_v = {fs:g}")
    where = "; ".join(f"on {SOIL_LABELS[s]} {', '.join(v)}" for s, v in soils.items())
    text = f"{head} Its share by soil and FS_v: {where}."
    if goal.misses:
        text += (f" Of the {goal.misses} points where it misses (bearing failures and refused "
                 f"runs aside), it lifts the edge further than the continuum by more than {thr} at "
                 f"{100 * goal.over:.0f} % and less by more than {thr} at "
                 f"{100 * goal.under:.0f} %; the rest miss in peak θ alone.")
    return text
