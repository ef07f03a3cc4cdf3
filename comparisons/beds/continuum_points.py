"""The continuum runs the beds are calibrated from and compared against, one point function
(:func:`evaluate_continuum`) that both Winkler studies sweep: the footing's stiffness, vertical
and rotation pushovers, and dynamic runs of a scene (:func:`evaluate_dynamic`), stored as plain
JSON values and histories. Its key name is the one its records were first stored under (the
Winkler-against-continuum study's), so the kept stores find them."""

from __future__ import annotations

import copy
from collections.abc import Mapping

import numpy as np

from ...checks import InputError
from ...scenes import Scene, scene_from_dict
from ..framework.measures import edge_uplift_history, settlement_when_flattest
from ..framework.sources import point_sources
from ..framework.store import point_function

__all__ = ["evaluate_continuum", "evaluate_dynamic", "motion_scene", "sampled_histories",
           "history_grid", "floats"]


# ---------------------------------------------------------------------------------------------
# Continuum points (evaluated by run_sweep, stored by content)
# ---------------------------------------------------------------------------------------------


def _point_scene(point: Mapping) -> Scene:
    scene = scene_from_dict(copy.deepcopy(point["scene"]), merged=True)
    if point.get("soil") == "elastic":
        scene = scene.with_overrides("soil.model='elastic'", "soil.undrained_strength=")
    return scene


def floats(values) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


@point_function("upliftlab.comparisons.winkler_vs_continuum:evaluate_continuum",
                models=("continuum",), tolerance=1e-4,
                sources=point_sources(__name__, __package__))
def evaluate_continuum(point: Mapping) -> dict:
    """One continuum analysis of a point: ``stiffness`` (K_v, K_r in full contact),
    ``rotation`` (a rotation pushover at ``N`` through ``rotations``), ``vertical`` (a vertical
    pushover through ``settlements``) or ``dynamic`` (:func:`evaluate_dynamic`). ``soil`` =
    ``elastic`` swaps the scene's soil for an elastic one of the same E and ν. Returns JSON
    values (units of the scene). A rotation pushover the soil cannot follow (Newton gives up
    after bisecting a step: a mechanism at this N) gives ``{"error": message, "dofs": ...}``."""
    from ...continuum import (ConvergenceError, build_model, footing_stiffness, rotation_pushover,
                               uplift_onset, vertical_pushover)
    from ...continuum.contact.footing import OPEN

    kind = point["analysis"]
    if kind == "dynamic":
        return evaluate_dynamic(point)
    model = build_model(_point_scene(point))
    if kind == "stiffness":
        k = footing_stiffness(model)
        return {"K_v": k.vertical, "K_r": k.rocking, "dofs": int(model.dofs)}
    if kind == "vertical":
        path = vertical_pushover(model, point["settlements"])
        return {"settlement": floats(path.settlement), "N": floats(path.N),
                "capacity": path.capacity, "dofs": int(model.dofs)}
    try:
        path = rotation_pushover(model, point["N"], point["rotations"])
    except ConvergenceError as exc:  # the soil cannot follow the path: a result, stored
        return {"error": f"the rotation pushover stopped: {exc}", "dofs": int(model.dofs)}
    try:
        onset = uplift_onset(path)
        onset = {"theta": onset.theta, "M": onset.M, "e": onset.e}
    except InputError as exc:
        onset = {"error": str(exc)}
    return {"theta": floats(path.theta), "M": floats(path.M), "N": floats(path.N),
            "settlement": floats(path.settlement), "contact": floats(path.contact_length),
            "lifted": [bool(v) for v in (path.status == OPEN).any(axis=1)], "onset": onset,
            "cuts": int(np.sum(path.cuts)), "dofs": int(model.dofs)}


def motion_scene(point: Mapping) -> Scene:
    """The point's scene with its motion table (a record is located by its ``_path``)."""
    data = copy.deepcopy(point["scene"])
    motion = dict(point["motion"])
    if motion["type"] == "record":
        motion = {"type": "record", "name": motion["_path"], "scale": motion.get("scale", 1.0)}
        if point["motion"].get("duration"):
            motion["duration"] = point["motion"]["duration"]
    data["motion"] = motion
    return scene_from_dict(data, merged=True)


def sampled_histories(time, theta, u, uplift, settlement, contact, grid) -> dict:
    """Peaks from the full histories and the histories on ``grid`` (linear interpolation).
    The residual settlement is the settlement of the centre at the moment of the last quarter
    of the run when the footing is flattest (smallest |θ|): rocking that goes on at the end
    (an undamped elastic bed rocks for ever) does not lift it."""
    time = np.asarray(time, dtype=float)
    series = {"theta": theta, "u": u, "uplift": uplift, "settlement": settlement,
              "contact": contact}
    series = {k: np.asarray(v, dtype=float) for k, v in series.items()}
    peaks = {"u": float(np.max(np.abs(series["u"]))),
             "theta": float(np.max(np.abs(series["theta"]))),
             "uplift": float(np.max(series["uplift"])),
             "residual_settlement": settlement_when_flattest(time, series["theta"],
                                                             series["settlement"])}
    return {"peaks": peaks, **{k: floats(np.interp(grid, time, v)) for k, v in series.items()}}


def history_grid(duration: float, step: float) -> np.ndarray:
    return np.linspace(0.0, duration, int(round(duration / step)) + 1)


def evaluate_dynamic(point: Mapping) -> dict:
    """One continuum dynamic run (:func:`upliftlab.continuum.dynamics.run.run_dynamic` with default
    :class:`DynamicOptions`, no soil snapshots or energy account) of the point's scene and
    motion: the histories of every step (JSON values, units of the scene): θ, the story
    deformation u, the edge uplift, the settlement of the centre from rest and the contact
    length. Peaks are taken from them by the study, so that the stored run does not depend on
    how they are measured."""
    from ...continuum import build_model
    from ...continuum.dynamics.run import DynamicOptions, run_dynamic

    scene = motion_scene(point)
    motion = scene.build_motion()
    model = build_model(scene)
    result = run_dynamic(model, scene, motion, DynamicOptions(snapshots=0, energy=False))
    time_ = np.asarray(result.time, dtype=float)
    footing = np.asarray(result.footing, dtype=float)
    u = np.asarray(result.structure_u, dtype=float).reshape(time_.size, -1)[:, -1]
    return {"time": floats(time_ - time_[0]), "theta": floats(footing[:, 2]), "u": floats(u),
            "uplift": floats(edge_uplift_history(result.gap)),
            "settlement": floats(-(footing[:, 1] - footing[0, 1])),
            "contact": floats(result.contact_length), "steps": int(time_.size),
            "dofs": int(model.dofs)}
