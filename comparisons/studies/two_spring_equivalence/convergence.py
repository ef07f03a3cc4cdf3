"""The converged Winkler bed: the smallest N whose static and dynamic measures change by
less than the tolerance on doubling N."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from ....reduced import rocking_pushover, uplift_onset_force
from ...framework.study import relative_error
from ...framework.sweep import run_sweep
from .dataset import convergence_dataset
from .grid import CASES, FLOOR_FRACTION, Grid, METRICS, Options, STUDY
from .maps import refusal
from .motions import motion_label
from .points import Base, evaluate_point, make_point
from .statics import static_model


# ---------------------------------------------------------------------------------------------
# Convergence of the Winkler bed in N
# ---------------------------------------------------------------------------------------------


def _static_measures(base: Base, springs: int, options: Options) -> dict:
    elastic = static_model(base, "uniform", "winkler", springs, options, "elastic")
    plastic = static_model(base, "uniform", "winkler", springs, options, "elastoplastic")
    w, b = elastic.weight, elastic.layout.half_width
    theta_up = w / (elastic.layout.vertical_stiffness * b)
    nb = 2.0 * w * b
    path = rocking_pushover(plastic, theta_up * np.geomspace(0.5, 1000.0, 15))
    return {"onset": uplift_onset_force(elastic) * float(elastic.heights[-1]) / nb,
            "moment_3_theta_up": float(rocking_pushover(elastic, [3.0 * theta_up]).moment[0]
                                       / nb),
            "ultimate": float(path.moment[-1] / nb)}


def _largest_change(finer: Mapping, coarser: Mapping, floors: Mapping | None = None) -> float:
    change = 0.0
    for key, value in finer.items():
        floor = floors[key] if floors else 0.0
        change = max(change, abs(relative_error(coarser[key], value, max(floor, 1e-300))))
    return change


def _first_converged(changes: Sequence[float], tolerance: float) -> int | None:
    """Index k of the first N from which every later change is within ``tolerance``."""
    k = len(changes)
    while k > 0 and changes[k - 1] <= tolerance:
        k -= 1
    return k if k < len(changes) else None


def check_convergence(base: Base, grid: Grid, options: Options, motion: Mapping, store,
                      sweep_options: Mapping):
    """The convergence check of the uniform Winkler bed in the number of springs N, as a
    labelled dataset over ``springs`` (:func:`.dataset.convergence_dataset`).

    The static measures per N (onset, M(3θ_up), M_ult, normalised by N B) and the dynamic ones
    per case at the middle intensity; ``changes`` "static"/case: the largest relative change
    from each N to the next (a dynamic change is the largest over every intensity of the grid).
    The chosen N (attribute ``chosen_springs``) is the smallest from which every later
    doubling changes the static measures by at most ``options.static_tolerance`` and the
    dynamic ones of Cases A and B by at most ``options.convergence_tolerance`` (Case C is
    reported); ``converged`` is False when even the largest pair differs by more (N is then
    the largest candidate)."""
    counts = tuple(int(n) for n in grid.spring_counts)
    static = [_static_measures(base, n, options) for n in counts]
    cases, levels = tuple(CASES), tuple(grid.intensities)
    points = [make_point(base, bed="uniform", layout="winkler", springs=n, options=options,
                         case=c, motion={**motion, "intensity": level})
              for c in cases for level in levels for n in counts]
    records = iter(run_sweep(evaluate_point, points, store, study=STUDY, **sweep_options))
    runs = {c: [[next(records) for _ in counts] for _ in levels] for c in cases}
    changes = {"static": [_largest_change(static[j + 1], static[j])
                          for j in range(len(counts) - 1)]}
    for c in cases:
        changes[c] = [max(_dynamic_change(column[j + 1], column[j]) for column in runs[c])
                      for j in range(len(counts) - 1)]
    dynamic = {c: runs[c][levels.index(_middle(levels))] for c in cases}
    picks = [_first_converged(changes["static"], options.static_tolerance)]
    picks += [_first_converged(changes[c], options.convergence_tolerance) for c in ("A", "B")]
    converged = all(p is not None for p in picks)
    index = max(picks) if converged else len(counts) - 1
    check = {"candidates": counts, "springs": counts[index], "converged": converged,
             "tolerance": options.convergence_tolerance,
             "static_tolerance": options.static_tolerance,
             "static": {k: [s[k] for s in static] for k in static[0]},
             "dynamic": {c: {m: [r.get(m, math.nan) for r in recs] for m in METRICS}
                         for c, recs in dynamic.items()},
             "changes": changes,
             "motion": f"{motion_label(motion)} at intensities "
                       f"{', '.join(f'{v:g}' for v in levels)} (figure: "
                       f"{_middle(levels):g} × a_up)"}
    return convergence_dataset(check, base.table["units"])


def _middle(levels: Sequence[float]) -> float:
    return levels[len(levels) // 2]


def _dynamic_change(finer: Mapping, coarser: Mapping) -> float:
    if refusal(finer) or refusal(coarser):
        return math.inf
    floors = {m: FLOOR_FRACTION * finer["scales"][m] for m in METRICS}
    return _largest_change({m: finer[m] for m in METRICS}, coarser, floors)
