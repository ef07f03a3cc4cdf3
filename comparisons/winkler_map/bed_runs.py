"""A bed's run of a map point: the reduced model on the point's scene and motion, measured as
the continuum's run of it is (:func:`.points.measured`). Live, never stored: a bed runs in
milliseconds, and its module is kept apart from the continuum's point function so that the
stored continuum runs do not depend on the reduced model's code (:mod:`..fingerprint`)."""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Mapping

import numpy as np

from ...scenes import scene_from_dict
from ..measures import edge_uplift_history, reduced_edge_gap_history
from .grid import MEASURES
from .points import measured, motion_table

__all__ = ["run_bed", "reduced_measures"]


def run_bed(point: Mapping, foundation: Mapping) -> dict:
    """A bed's run of a point's motion (reduced model, live, not stored): the measures of
    :func:`measured`, its ``peak_settlement`` (the base centre's largest settlement, down),
    its wall time ``wall_time_s`` (the run alone, s), or ``refused`` with the integrator's
    reason."""
    from ...reduced import IntegrationError, run as run_reduced

    data = copy.deepcopy(point["scene"])
    data["foundation"] = dict(foundation)
    B = 2.0 * data["foundation"]["half_width"]
    data["motion"] = motion_table(point["motion"], point["intensity"], B,
                                  data["structure"]["height"])
    for table in ("soil", "continuum"):
        data.pop(table, None)
    scene = scene_from_dict(data, merged=True)
    started = time.perf_counter()
    try:
        response = run_reduced(scene)
    except IntegrationError as exc:
        return {"refused": str(exc), "measures": dict.fromkeys(MEASURES, math.nan),
                "wall_time_s": time.perf_counter() - started}
    wall = time.perf_counter() - started
    return {"measures": reduced_measures(response), "wall_time_s": wall,
            "peak_settlement": float(np.max(response.settlement)),
            "energy_balance_error": float(response.peaks["energy_balance_error"])}


def reduced_measures(response) -> dict:
    """The measures of :func:`measured` of a reduced model's ``response`` (its peaks where the
    event stepper caught a peak between recorded steps)."""
    t = np.asarray(response.time, dtype=float)
    uplift = float(np.max(edge_uplift_history(reduced_edge_gap_history(response))))
    u_peak = max(float(np.max(np.abs(response.u))), float(response.peaks["u"]))
    theta = np.asarray(response.theta, dtype=float)
    out = measured(t - t[0], theta, uplift, np.asarray(response.settlement, dtype=float), u_peak,
                   np.max(np.abs(response.base_shear)))
    out["theta"] = max(out["theta"], float(response.peaks["theta"]))
    return out
