"""The continuum statics the calibrations need, per soil: the footing's stiffness in full
contact (K_v, K_r) and its vertical capacity V_ult (a vertical pushover), each one stored point
of the sweep (:func:`evaluate_static`). Neither depends on the vertical load, so one pair per
soil serves every FS_v: N = V_ult/FS_v.
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ....scenes import scene_from_dict
from ...beds.base import base_table
from ...framework.sources import point_sources
from ...framework.store import point_function
from .reference import reference_soil

if TYPE_CHECKING:  # annotations only: the stored runs do not depend on the grid
    from .grid import Options

__all__ = ["SoilStatics", "static_points", "evaluate_static", "soil_statics", "static_scene"]

_NOMINAL_MOTION = {"type": "free", "velocity": 1.0, "duration": 1.0}  # unused by the statics


def static_points(soil: str, options: Options, half_width: float) -> list[dict]:
    """The two static analyses of ``soil`` (on the options' continuum reference,
    :func:`.reference.reference_soil`) on the options' mesh: ``stiffness`` and ``vertical``
    (to ``settlement_ratio`` × B in ``vertical_steps``)."""
    base = {"soil": reference_soil(soil, options.reference),
            "continuum": {"elements_across": int(options.elements_across)},
            "half_width": float(half_width)}
    B = 2.0 * half_width
    settlements = np.linspace(0.0, options.settlement_ratio * B, options.vertical_steps + 1)[1:]
    return [{**base, "analysis": "stiffness"},
            {**base, "analysis": "vertical", "settlements": [float(s) for s in settlements]}]


def static_scene(point: Mapping):
    """The validated scene of a static point: the map's base scene with the point's soil,
    continuum options and half-width (its motion unused)."""
    data = base_table()
    data["soil"] = copy.deepcopy(dict(point["soil"]))
    data["continuum"] = {**data.get("continuum", {}), **point["continuum"]}
    data["foundation"] = {**data["foundation"], "half_width": point["half_width"]}
    data["motion"] = dict(_NOMINAL_MOTION)
    return scene_from_dict(data, merged=True)


@point_function("upliftlab.comparisons.winkler_map:evaluate_static",
                models=("continuum",), tolerance=1e-4,
                sources=point_sources(__name__, __package__))
def evaluate_static(point: Mapping) -> dict:
    """One continuum static analysis of a soil: ``stiffness`` (K_v, K_r with every contact node
    tied to the footing) or ``vertical`` (the load–settlement path and its maximum,
    ``capacity``); with the DOFs and the run's own wall time ``wall_time_s`` (s). Units of the
    scene (kN/m, kN m/rad/m, m)."""
    from ....continuum import build_model, footing_stiffness, vertical_pushover

    started = time.perf_counter()
    model = build_model(static_scene(point))
    if point["analysis"] == "stiffness":
        k = footing_stiffness(model)
        out = {"K_v": float(k.vertical), "K_r": float(k.rocking)}
    else:
        path = vertical_pushover(model, point["settlements"])
        out = {"settlement": [float(v) for v in path.settlement],
               "N": [float(v) for v in path.N], "capacity": float(path.capacity)}
    return {**out, "dofs": int(model.dofs), "wall_time_s": time.perf_counter() - started}


@dataclass(frozen=True)
class SoilStatics:
    """A soil's continuum statics: ``K_v`` (kN/m/m), ``K_r`` (kN m/rad/m), ``V_ult`` (kN/m, the
    largest load of the vertical pushover), ``plateau`` the last step's load increase over
    V_ult (how flat the path ends), ``settlement``/``load`` the path, ``dofs`` and the two
    runs' wall times (s)."""

    soil: str
    K_v: float
    K_r: float
    V_ult: float
    plateau: float
    settlement: tuple[float, ...]
    load: tuple[float, ...]
    dofs: int
    wall_time_s: float


def soil_statics(soil: str, records: Sequence[Mapping]) -> SoilStatics:
    """The :class:`SoilStatics` from the two records of :func:`static_points` (in order)."""
    stiffness, vertical = records
    load = np.asarray(vertical["N"], dtype=float)
    plateau = float((load[-1] - load[-2]) / vertical["capacity"]) if load.size > 1 else math.nan
    return SoilStatics(soil, stiffness["K_v"], stiffness["K_r"], vertical["capacity"], plateau,
                       tuple(vertical["settlement"]), tuple(vertical["N"]), stiffness["dofs"],
                       stiffness["wall_time_s"] + vertical["wall_time_s"])
