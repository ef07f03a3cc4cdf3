"""The dynamic comparison: the continuum's runs against each calibrated bed's on the same
motions."""

from __future__ import annotations

import copy
import importlib.util
import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ....scenes import Scene
from ...framework.measures import edge_uplift_history, reduced_edge_gap_history
from ...beds.continuum_points import history_grid, motion_scene, sampled_histories
from ...beds.pushover import bed_scene
from ...beds.stiffness import Calibration
from .options import DYNAMIC_MISSING, Options


# ---------------------------------------------------------------------------------------------
# Dynamics (needs upliftlab.continuum.dynamics.run)
# ---------------------------------------------------------------------------------------------


DYNAMIC_MEASURES = ("u", "theta", "uplift", "residual_settlement")
# both models measured alike (..measures): uplift = edge_uplift_history's peak,
# residual_settlement = settlement_when_flattest
DYNAMIC_LABELS = {"u": "peak u", "theta": "peak θ", "uplift": "peak edge gap",
                  "residual_settlement": "settlement when flattest"}
HISTORIES = ("theta", "u", "uplift", "settlement", "contact")


@dataclass(frozen=True, eq=False)
class DynamicRun:
    """One motion: ``continuum`` and each bed's (``beds``) histories on a common ``time`` grid
    (θ, u, edge uplift, settlement of the centre from rest, contact length) and ``peaks``
    (:data:`DYNAMIC_MEASURES`, from the full-resolution histories)."""

    key: str
    label: str
    time: np.ndarray
    continuum: dict = field(repr=False)
    beds: dict = field(repr=False)


@dataclass(frozen=True, eq=False)
class DynamicComparison:
    """The dynamic comparison (``runs``, one per motion), or why it did not run
    (``available`` False, ``reason``)."""

    available: bool
    reason: str
    runs: tuple[DynamicRun, ...] = ()


def dynamics_available() -> tuple[bool, str]:
    """(True, "") when :mod:`upliftlab.continuum.dynamics.run` imports and offers ``run_dynamic``
    and ``DynamicOptions``; else (False, the reason)."""
    if importlib.util.find_spec("upliftlab.continuum.dynamics.run") is None:
        return False, "upliftlab.continuum.dynamics does not exist"
    try:
        from ....continuum.dynamics import run as dynamics
    except Exception as exc:  # a module being written may not import yet
        return False, (f"upliftlab.continuum.dynamics does not import "
                       f"({type(exc).__name__}: {exc})")
    missing = [n for n in ("run_dynamic", "DynamicOptions") if not hasattr(dynamics, n)]
    if missing:
        return False, f"upliftlab.continuum.dynamics lacks {', '.join(missing)}"
    return True, ""


def _bed_dynamic(scene: Scene, cal: Calibration, point: Mapping, grid: np.ndarray) -> dict:
    """The calibrated bed's run of the same motion (reduced model, not stored: milliseconds)."""
    from ....reduced import IntegrationError, run as run_reduced

    data = copy.deepcopy(bed_scene(scene, cal).data)
    try:
        response = run_reduced(motion_scene({"scene": data, "motion": point["motion"]}))
    except IntegrationError as exc:  # refused: no values (NaN errors), the reason kept
        nan = [math.nan] * grid.size
        return {"peaks": dict.fromkeys(DYNAMIC_MEASURES, math.nan), "refused": str(exc),
                **dict.fromkeys(HISTORIES, nan)}
    gap = reduced_edge_gap_history(response)
    out = sampled_histories(response.time, response.theta, response.u,
                            edge_uplift_history(gap),
                            response.settlement, response.contact_length, grid)
    out["peaks"]["u"] = max(out["peaks"]["u"], response.peaks["u"])
    out["peaks"]["theta"] = max(out["peaks"]["theta"], response.peaks["theta"])
    return out


def _dynamic_motions(scene: Scene, options: Options, fast: bool) -> list[tuple[str, str, dict]]:
    """(key, label, motion point) of the dynamic comparison: the scene's pulse (shortened to
    ``pulse_duration`` if given) and, in full mode, each record of ``records``."""
    from ....motions import find_motion
    from ...framework.study import file_sha256

    motions = []
    spec = dict(scene.data.get("motion", {}))
    if spec.get("type") in ("sine", "cosine", "ricker"):
        if options.pulse_duration is not None:
            spec["duration"] = options.pulse_duration
        motions.append(("pulse", f"{spec['type']} pulse, {spec['amplitude']:g} g, T = "
                                 f"{spec['period']:g} s, {spec.get('duration', '')} s", spec))
    for name in () if fast else options.records:
        path = find_motion(name)
        table = {"type": "record", "name": name, "sha256": file_sha256(path),
                 "_path": str(path.resolve())}
        if options.record_duration is not None:
            table["duration"] = options.record_duration
        motions.append((name, name, table))
    return motions


def dynamic_points(scene: Scene, options: Options, fast: bool) -> tuple[list, list, str]:
    """(motions, points, reason): the continuum dynamic runs to make, or why there are none.
    The dynamic runs take ``dynamic_overrides``, and in fast mode ``fast_dynamic_overrides``
    on top (coarser meshes)."""
    if not options.dynamic:
        return [], [], "dynamic comparison not run: options.dynamic = false"
    ok, why = dynamics_available()
    if not ok:
        return [], [], f"{DYNAMIC_MISSING} ({why})"
    motions = _dynamic_motions(scene, options, fast)
    if not motions:
        return [], [], ("dynamic comparison not run: the scene's motion is no pulse and no "
                        "record was asked for")
    overrides = run_overrides(options, fast)
    if overrides:
        scene = scene.with_overrides(*overrides)
    table = {k: v for k, v in copy.deepcopy(scene.data).items() if k != "motion"}
    points = [{"scene": table, "motion": m, "analysis": "dynamic",
               "history_dt": options.history_dt} for _, _, m in motions]
    return motions, points, ""


def run_overrides(options: Options, fast: bool) -> tuple[str, ...]:
    """The scene overrides of the continuum's dynamic runs in this mode."""
    return options.dynamic_overrides + (options.fast_dynamic_overrides if fast else ())


def compare_dynamics(scene: Scene, calibrations, motions, points, records,
                     reason: str) -> DynamicComparison:
    """The beds' runs of the motions the continuum ran (``records``), side by side."""
    if not points:
        return DynamicComparison(False, reason)
    runs = []
    for (key, label, _), point, rec in zip(motions, points, records):
        grid = history_grid(rec["time"][-1], point["history_dt"])
        continuum = sampled_histories(rec["time"], *(rec[k] for k in HISTORIES), grid)
        continuum.update(steps=rec["steps"], dofs=rec["dofs"])
        beds = {c.name: _bed_dynamic(scene, c, point, grid) for c in calibrations}
        runs.append(DynamicRun(key, label, grid, continuum, beds))
    return DynamicComparison(True, "", tuple(runs))
