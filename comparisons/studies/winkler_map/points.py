"""One point of the map: its scene and the continuum's dynamic run (the sweep's point function,
stored), measured as a bed's run of the same motion is (:mod:`.bed_runs`).

The scene of a point is the beds' base scene, ``strip_footing_clay`` (B = 2 m,
:func:`...beds.base.base_table`), with the map's soil, mesh, box sides (:data:`SIDES`) and
structure: a story of weight N = V_ult/FS_v at height h = (h/B) B with
the fixed-base period T and 5 % damping, and the rotary inertia of a rigid B × h block about
its centroid, m (B² + h²)/12 with m = N/g (as in the scene). The motion's PGA is the
intensity times a_up = g B/(6h).
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Mapping

import numpy as np

from ....scenes import Scene, scene_from_dict
from ...framework.measures import (continuum_peak_edge_gap, peak_story_shear, residual_rotation,
                                   settlement_when_flattest)
from ...framework.sources import point_sources
from ...framework.store import point_function
from .motions import locate
from .reference import reference_continuum, reference_soil, reference_weights

__all__ = ["point_table", "motion_table", "evaluate_dynamic",
           "scales", "story_constants"]

STORY_DAMPING = 0.05
#: The box's sides in the map's dynamic runs (``continuum.boundary``): a free-field column
#: (u_x free, u_y held). With the sides' u_x held instead (``fixed``: a rigid container moving
#: with the base), the soil between the footing and the sides is squeezed against them by its
#: own inertia and yields where a site would not: measured on the clay (16 across, FS_v = 10,
#: the 0.25 s pulse at 3 a_up), 90–100 % of the elements beyond 3B from the footing yielded in
#: the top 10 m and the peak θ was 3.0 times the free-field column's; with these sides none
#: yielded.
SIDES = "shear"


def point_table(base: Mapping, soil: str, elements_across: int, N: float, h_over_B: float,
                period: float, g: float, reference: str = "box") -> dict:
    """The scene table of a point (no motion): the base scene with the map's soil, mesh and
    structure (module docstring) on the continuum ``reference`` (:mod:`.reference`; the
    default ``box`` adds nothing, so that its tables, and the keys of its stored runs, are
    those the kept store was made of)."""
    data = copy.deepcopy(dict(base))
    B = 2.0 * data["foundation"]["half_width"]
    h = h_over_B * B
    data["soil"] = reference_soil(soil, reference)
    data["continuum"] = {**data.get("continuum", {}), "elements_across": int(elements_across),
                         "boundary": SIDES,
                         **reference_continuum(data["soil"], B, reference)}
    data["structure"] = {**reference_weights(N, reference), "height": h, "period": float(period),
                         "damping_ratio": STORY_DAMPING,
                         "rotary_inertia": N / g * (B * B + h * h) / 12.0}
    return data


def motion_table(motion: Mapping, intensity: float, B: float, h: float) -> dict:
    """The scene's ``[motion]`` of a map motion at ``intensity`` × a_up, a_up = g B/(6h):
    a Ricker pulse of that amplitude (g) lasting 3T plus its tail, or a record scaled to that
    PGA (located by :func:`.motions.locate`)."""
    amplitude = intensity * B / (6.0 * h)
    if motion["type"] == "ricker":
        return {"type": "ricker", "amplitude": amplitude, "period": motion["period"],
                "duration": motion["duration"]}
    return {"type": "record", "name": locate(motion), "pga": amplitude}


def point_scene(point: Mapping) -> Scene:
    """The validated scene of a dynamic point (its table and its motion)."""
    data = copy.deepcopy(point["scene"])
    B = 2.0 * data["foundation"]["half_width"]
    data["motion"] = motion_table(point["motion"], point["intensity"], B,
                                  data["structure"]["height"])
    return scene_from_dict(data, merged=True)


def story_constants(scene: Scene) -> tuple[float, float]:
    """(k, c) of the story: its stiffness and the dashpot c = 2 ζ √(k m) (force/length,
    force·time/length), as both models build them."""
    story = scene.structure.stories[0]
    m = story.weight / scene.g
    return story.stiffness, 2.0 * scene.structure.damping_ratio * math.sqrt(story.stiffness * m)


def measured(time_, theta, uplift_peak, settlement, u_peak, shear_peak) -> dict:
    """The map's measures from a run's histories (:data:`.grid.MEASURES`), the same for both
    models: peak |θ|, peak edge uplift, the settlement when flattest, the residual rotation
    (mean θ over the last quarter), peak |u| and peak story shear."""
    return {"theta": float(np.max(np.abs(theta))), "uplift": float(uplift_peak),
            "residual_settlement": settlement_when_flattest(time_, theta, settlement),
            "residual_rotation": residual_rotation(time_, theta), "u": float(u_peak),
            "base_shear": float(shear_peak)}


_WARM: set[str] = set()


def _warm_kernels(point: Mapping) -> None:
    """Compile (or load from numba's cache) the continuum's kernels for this soil model once
    per process, on a 2-across mesh and a few steps, so that a run's wall time is its own and
    not the compiler's."""
    model_name = point["scene"]["soil"]["model"]
    if model_name in _WARM:
        return
    data = copy.deepcopy(point["scene"])
    data["continuum"] = {**data["continuum"], "elements_across": 2}
    data["motion"] = {"type": "ricker", "amplitude": 0.1, "period": 0.2, "duration": 0.02}
    _timed_run(scene_from_dict(data, merged=True))
    _WARM.add(model_name)


def _timed_run(scene):
    """(model, result, wall time s) of the continuum's dynamic run of ``scene`` (no
    snapshots)."""
    from ....continuum import build_model
    from ....continuum.dynamics.run import DynamicOptions, run_dynamic

    started = time.perf_counter()
    model = build_model(scene)
    result = run_dynamic(model, scene, scene.build_motion(),
                         DynamicOptions(snapshots=0, energy=False))
    return model, result, time.perf_counter() - started


def continuum_measures(scene, result):
    """(t from 0 (s), θ (rad), settlement of the centre from its static position (length,
    down), story deformation u (length), the gap history (nodes × steps, length), and the
    measures of :func:`measured`) of a continuum dynamic ``result`` of ``scene``."""
    t = np.asarray(result.time, dtype=float)
    t = t - t[0]
    footing = np.asarray(result.footing, dtype=float)
    theta = footing[:, 2]
    settlement = -(footing[:, 1] - footing[0, 1])
    s = np.asarray(result.structure_u, dtype=float).reshape(t.size, -1)[:, -1]
    s_dot = np.asarray(result.structure_velocity, dtype=float).reshape(t.size, -1)[:, -1]
    k, c = story_constants(scene)
    gap = np.asarray(result.gap, dtype=float)
    uplift = continuum_peak_edge_gap(gap, result.x)
    measures = measured(t, theta, uplift, settlement, np.max(np.abs(s)),
                        peak_story_shear(s, s_dot, k, c))
    return t, theta, settlement, s, gap, measures


@point_function("upliftlab.comparisons.winkler_map:evaluate_dynamic",
                models=("continuum",), tolerance=1e-4,
                sources=point_sources(__name__, __package__))
def evaluate_dynamic(point: Mapping) -> dict:
    """One continuum dynamic run of a point (explicit route, no soil snapshots): the measures
    of :func:`measured` from every recorded step, the run's steps, DOFs, step (s) and the
    factor ``dt_reduction`` by which the soil's Rayleigh damping shortened it (1 without),
    whether its return map was compiled and its soil model (for the cost estimate,
    :mod:`.cost`), its energy balance error, its largest plastic strain ε̄p at a quadrature
    point (``max_plastic_strain``) with the run's ``validity`` against the small-strain limit
    (:mod:`upliftlab.continuum.dynamics.validity`; records made before it have none), whether
    the far field (the box's side columns) yielded under the motion, ``far_field``: "elastic"
    or "from z1 to z2" (m, :mod:`upliftlab.continuum.dynamics.far_field`; records made before
    it have none) and its own wall time ``wall_time_s`` (model,
    gravity and time loop, s; the kernels are compiled before, :func:`_warm_kernels`). Units
    of the scene. A run the solver gives up on (it diverged, its contact failed or its energy
    does not balance) is a stored result too: ``{"error": kind and message, "soil_model",
    "wall_time_s"}``, which the map reports with the point and leaves out of every error. A
    run that ends in a bearing failure of the soil (:class:`~upliftlab.continuum.
    BearingFailure`) adds ``"failure": "bearing"``, its time ``failure_time_s`` and the
    footing's ``failure_settlement`` (m) and ``failure_rotation`` (rad): an outcome the map
    holds the beds to. No histories: the map reads none, and a record of a few hundred bytes
    lets a store of the whole grid be kept with the repository."""
    from ....continuum import BearingFailure, ContactError, ConvergenceError
    from ....continuum.dynamics.run_control import EnergyBalanceError

    _warm_kernels(point)
    scene = point_scene(point)
    started = time.perf_counter()
    try:
        model, result, wall = _timed_run(scene)
    except (ConvergenceError, ContactError, EnergyBalanceError) as exc:
        out = {"error": f"{type(exc).__name__}: {' '.join(str(exc).split())}",
               "soil_model": scene.soil.model, "wall_time_s": time.perf_counter() - started}
        if isinstance(exc, BearingFailure):
            out.update(failure="bearing", failure_time_s=exc.time,
                       failure_settlement=exc.settlement, failure_rotation=exc.rotation)
            if exc.result is not None:
                out["max_plastic_strain"] = float(exc.result.metadata["max_plastic_strain"])
        return out
    t, *_, measures = continuum_measures(scene, result)
    return {"measures": measures,
            "steps": int(result.metadata.get("steps", t.size - 1)), "dofs": int(model.dofs),
            "dt": float(result.metadata.get("dt", math.nan)),
            "dt_reduction": float(result.metadata.get("dt_reduction", 1.0)),
            "duration": float(t[-1]), "compiled": bool(result.metadata.get("compiled", True)),
            "soil_model": scene.soil.model,
            "energy_balance_error": float(result.metadata.get("energy_balance_error", math.nan)),
            "max_plastic_strain": float(result.metadata.get("max_plastic_strain", math.nan)),
            "validity": str(result.metadata.get("validity", "")),
            "far_field": str(result.metadata.get("far_field", "")),
            "wall_time_s": wall}


def scales(N: float, B: float, h: float, K_v: float, K_r: float, k_story: float) -> dict:
    """Each measure's value at the uplift threshold of a uniform Winkler bed with the
    continuum's K_r and K_v (the error floors' basis): θ_up = N B/(6 K_r), the static
    settlement N/K_v (edge uplift, residual settlement), the shear at a_up, N B/(6h), and the
    story deformation under it."""
    theta = N * B / (6.0 * K_r)
    shear = N * B / (6.0 * h)
    return {"theta": theta, "uplift": N / K_v, "residual_settlement": N / K_v,
            "residual_rotation": theta, "u": shear / k_story, "base_shear": shear}
