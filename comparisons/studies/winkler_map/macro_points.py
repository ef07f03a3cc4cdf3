"""The macro-element's fit, once per soil, as a stored point of the map (issue 36 §2 and §3).

A soil's point holds what :func:`~upliftlab.comparisons.beds.macro.calibrate_macro` is fitted
to, as numbers: the footing's width, the soil's statics (K_v, K_r, V_ult), its strength (the
capacity's form: c, φ, γ, :func:`~upliftlab.comparisons.beds.macro.soil_strength`), the
continuum's rotation pushovers at ``options.macro_fs_v`` (monotonic and cyclic) and at
``options.macro_repeat_fs_v`` (repeated cycles at one amplitude), each with the store key of
its run, and the fit's ``evaluations``. Its record is the fitted law's fields and
the fit's checks (the capacity line's residuals, the moment and settlement misfits and the
largest miss of N per pushover, the cost), or ``error`` where the fit was refused. The fit is
deterministic, so a record made again reproduces it; it takes minutes (a few hundred
evaluations of every pushover), which is why it is kept.

The pushovers are those of the map's own statics rows (:mod:`.rocking`), at the FS_v of
``options.macro_fs_v`` whatever the grid's FS_v, so that a slice of the map and the whole map
compare the same element. No dynamic run enters: the map is the test.

The records depend on the element's law and the fit alone (the declared sources: this
module's imports within the reduced model's laws, the scenes' law records and the
comparisons), not on the continuum's code: the pushovers enter as numbers.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping, Sequence

import numpy as np

from ...beds.pushover import repeated_cycles
from ...beds.macro import (FIT_SECONDS_PER_STEP, RotationPushover, calibrate_macro,
                           evaluation_bound)
from ...framework.sources import import_closure, source_name
from ...framework.store import point_function
from .rocking import rocking_points

__all__ = ["macro_fit_point", "evaluate_macro_fit", "fit_seconds", "fit_rotation_points",
           "fit_rotation_fs",
           "soil_fit_points"]


def macro_fit_point(soil: str, *, width: float, K_v: float, K_r: float, V_ult: float,
                    strength: Mapping, pushovers: Sequence[tuple[Mapping, Mapping, str]],
                    evaluations: int) -> dict:
    """The fit point of ``soil``: ``pushovers`` as (rotation point, its record, its store key)
    of the continuum's rotation pushovers that ran to their end, in the map's order."""
    rows = []
    for point, record, key in pushovers:
        rows.append({"N": float(point["N"]),
                     "theta": [float(v) for v in record["theta"]],
                     "M": [float(v) for v in record["M"]],
                     "settlement": [float(v) for v in record["settlement"]],
                     "source": str(key)})
    return {"soil": soil, "width": float(width), "K_v": float(K_v), "K_r": float(K_r),
            "V_ult": float(V_ult), "strength": {k: float(v) for k, v in strength.items()},
            "pushovers": rows, "evaluations": int(evaluations)}


def _pushovers(point: Mapping) -> list[RotationPushover]:
    out = [RotationPushover(float(p["N"]), np.asarray(p["theta"], dtype=float),
                            np.asarray(p["M"], dtype=float),
                            np.asarray(p["settlement"], dtype=float), str(p["source"]))
           for p in point["pushovers"]]
    return sorted(out, key=lambda p: (p.N, len(p.theta)))


def fit_seconds(rotations: Sequence[Mapping], evaluations: int) -> float:
    """A soil's fit's cost before it starts (s of one worker), from its rotation points: at
    most :func:`~...beds.macro.evaluation_bound` evaluations, each a pass over every path's
    steps at :data:`~...beds.macro.FIT_SECONDS_PER_STEP`."""
    steps = sum(len(p["rotations"]) for p in rotations)
    return evaluation_bound(evaluations) * steps * FIT_SECONDS_PER_STEP


def fit_rotation_fs(options) -> list[tuple[float, bool]]:
    """(FS_v, whether the map's statics rows push over the same path) of each of a soil's
    :func:`fit_rotation_points`, in their order."""
    return [(fs, True) for fs in options.macro_fs_v for _ in range(2)] + \
        [(fs, False) for fs in options.macro_repeat_fs_v]


def fit_rotation_points(soils: Sequence[str], options, base: Mapping,
                        loads: Mapping) -> list[dict]:
    """The continuum's rotation pushovers the fits are made from, per soil: per FS_v of
    ``options.macro_fs_v`` the cyclic and the monotonic one (:func:`.rocking.rocking_points`,
    the map's own), then per FS_v of ``options.macro_repeat_fs_v`` ``options.repeat_cycles``
    full cycles at ``options.repeat_ratio`` θ_on (whether the footing shakes down);
    ``loads[soil]`` its V_ult."""
    repeated = repeated_cycles(options, options.repeat_ratio, options.repeat_cycles)
    points = []
    for soil in soils:
        for fs in options.macro_fs_v:
            points += rocking_points(base, soil, loads[soil] / fs, options)
        points += [rocking_points(base, soil, loads[soil] / fs, repeated)[0]
                   for fs in options.macro_repeat_fs_v]
    return points


def soil_fit_points(soils: Sequence[str], options, base: Mapping, statics: Mapping,
                    rotations: Sequence[Mapping], records: Sequence[Mapping],
                    keys: Sequence[str], g: float) -> list[dict]:
    """The fit point of each soil (:func:`macro_fit_point`) from :func:`fit_rotation_points`'
    ``rotations``, their ``records`` and store ``keys``, and ``statics[soil]`` (its
    :class:`.statics.SoilStatics`): the pushovers that ran to their end (one that stopped is
    left out; a soil without a monotonic one is refused by its fit)."""
    from ....scenes import scene_from_dict
    from ...beds.macro import macro_strength

    per_soil = len(fit_rotation_fs(options))
    width = 2.0 * base["foundation"]["half_width"]
    points = []
    for i, soil in enumerate(soils):
        rows = slice(i * per_soil, (i + 1) * per_soil)
        kept = [(p, r, k) for p, r, k in zip(rotations[rows], records[rows], keys[rows])
                if "error" not in r]
        table = {**rotations[i * per_soil]["scene"], "motion": dict(_FREE)}
        strength = macro_strength(scene_from_dict(table, merged=True))
        st = statics[soil]
        points.append(macro_fit_point(soil, width=width, K_v=st.K_v, K_r=st.K_r,
                                      V_ult=st.V_ult, strength=strength, pushovers=kept,
                                      evaluations=options.macro_evaluations))
    return points


_FREE = {"type": "free", "velocity": 1.0, "duration": 1.0}  # a scene's motion, unused


#: What a fit's record depends on: the fit and the element's law, and what they import.
_SOURCES = tuple(sorted({source_name(__name__), *(source_name(m) for m in import_closure(
    "upliftlab.comparisons.beds.macro", "upliftlab"))}))


@point_function("upliftlab.comparisons.winkler_map:evaluate_macro_fit", models=("reduced",),
                tolerance=1e-6, sources=_SOURCES)
def evaluate_macro_fit(point: Mapping) -> dict:
    """The macro-element fitted to a soil's fit point (module docstring): ``law`` (the
    :class:`~upliftlab.reduced.laws.macro.MacroElement`'s fields), ``capacity_residuals``,
    ``moment_rms``, ``settlement_rms``, ``load_misses`` (per pushover, in the order of
    ``sources``), ``cost``, ``evaluations`` and the fit's ``wall_time_s``; or ``error`` with
    the reason the fit was refused (no monotonic pushover, a capacity line that falls, a law
    that cannot hold N)."""
    from ....checks import InputError
    from ....reduced.laws.macro import MacroStepError

    started = time.perf_counter()
    pushovers = _pushovers(point)
    try:
        fit = calibrate_macro(pushovers, width=point["width"], V_ult=point["V_ult"],
                              K_v=point["K_v"], K_r=point["K_r"],
                              max_evaluations=int(point["evaluations"]), **point["strength"])
    except (InputError, MacroStepError) as exc:
        return {"error": " ".join(str(exc).split()),
                "wall_time_s": time.perf_counter() - started}
    return {"law": {k: float(v) for k, v in dataclasses.asdict(fit.law).items()},
            "capacity_residuals": [float(v) for v in fit.capacity_residuals],
            "moment_rms": [float(v) for v in fit.moment_rms],
            "settlement_rms": [float(v) for v in fit.settlement_rms],
            "load_misses": [float(v) for v in fit.load_misses],
            "sources": list(fit.sources), "cost": float(fit.cost),
            "evaluations": int(fit.evaluations),
            "wall_time_s": time.perf_counter() - started}
