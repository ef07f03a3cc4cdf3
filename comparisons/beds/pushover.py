"""A bed pushed over on the continuum's rotation paths, and the values both are compared in.

The continuum's rotation pushovers at a vertical load N follow two paths scaled by θ_on =
2N(1 − ν)/(π G B), the elastic half-plane's uplift rotation: a monotonic path
(:func:`rotation_path`) and one full cycle per amplitude (:func:`cyclic_path`). A bed is pushed
over on the same rotations by the reduced model (:func:`bed_response`, :func:`bed_rocking`; the
record of one path :func:`pushover_record`). Both are read at the same points
(:func:`path_values`) and compared against the floors of :data:`FLOORS`, which both Winkler
studies and the fitted bed (:mod:`.fitted`) share.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from ...reduced import build_model as build_reduced, rocking_pushover, uplift_onset_force
from ...scenes import Scene, scene_from_dict
from .stiffness import Calibration

__all__ = ["FLOORS", "FREE_MOTION", "rotation_path", "cyclic_path", "repeated_cycles",
           "BedResponse", "bed_scene", "pushover_record", "bed_response", "bed_rocking",
           "path_values"]

#: Error floors, as fractions: a reference smaller than its floor is measured against the floor
#: instead (moments × N B, contact length × B, settlement × the continuum's settlement under N,
#: dissipated work × N B θ_on).
FLOORS = {"moment": 0.01, "contact": 0.05, "settlement": 0.1, "energy": 0.01}

#: A scene's motion that no pushover reads.
FREE_MOTION = {"type": "free", "velocity": 1.0, "duration": 1.0}


def rotation_path(theta_on: float, options) -> np.ndarray:
    """Monotonic rotations (rad): 0, fine steps through the half-plane onset θ_on (so that the
    onset has full-contact steps to extrapolate from, elastic or plastic), then
    ``monotonic_steps`` geometric steps to the largest of ``theta_ratios`` × θ_on, which are all
    on the path."""
    top = max(options.theta_ratios)
    ratios = [0.0, 0.3, 0.6, 0.8, 0.9, 1.0, 1.1, 1.25]
    ratios += list(np.geomspace(1.5, top, options.monotonic_steps)) + list(options.theta_ratios)
    ratios = np.unique(np.round(ratios, 10))
    return theta_on * ratios


def repeated_cycles(options, ratio: float, cycles: int):
    """``options`` (any record with ``cycle_ratios``) whose :func:`cyclic_path` is ``cycles``
    full cycles at one amplitude, ``ratio`` θ_on: the path that says whether a footing
    shakes down."""
    return replace(options, cycle_ratios=(float(ratio),) * int(cycles))


def cyclic_path(theta_on: float, options) -> np.ndarray:
    """One full cycle 0 → +a → −a → 0 per amplitude a ∈ ``cycle_ratios`` × θ_on, with
    ``cycle_steps`` steps per quarter cycle (rad); starts at 0."""
    n = options.cycle_steps
    path = [0.0]
    for a in options.cycle_ratios:
        quarter = np.arange(1, n + 1) / n
        path += list(a * quarter) + list(a * (1 - 2 * quarter)) + list(-a * (1 - quarter))
    return theta_on * np.array(path)


@dataclass(frozen=True, eq=False)
class BedResponse:
    """A calibrated bed's static response: the bed's ``K_v``, ``K_r``, uplift-onset moment
    ``onset_moment``, ``N_ult`` (inf for elastic springs), and the ``monotonic`` and ``cyclic``
    pushovers (θ, M, settlement = −V, contact) on the continuum's rotation paths."""

    calibration: Calibration
    K_v: float
    K_r: float
    onset_moment: float
    N_ult: float
    monotonic: dict = field(repr=False)
    cyclic: dict = field(repr=False)


def bed_scene(scene: Scene, cal: Calibration) -> Scene:
    """The scene with its foundation replaced by the calibrated bed."""
    data = copy.deepcopy(scene.data)
    old = data.get("foundation", {})
    table = cal.foundation_table()
    for key in ("damping_ratio", "restitution", "impact_multiple"):
        if key in old:
            table[key] = old[key]
    data["foundation"] = table
    return scene_from_dict(data, source=scene.source, merged=True)


def pushover_record(model, thetas) -> dict:
    """A rocking pushover of the bed. The reduced model measures V from static equilibrium, so
    the settlement of the base centre is its static settlement minus V: Σ k_i δ0_i / Σ k_i
    (= N/K_v for a symmetric bed); where springs reached their yield force under the weight
    (and settled plastically beyond their elastic compression δ0), the compression at rest of
    a spring below it less x_i θ_s (θ_s the static rotation), the same for each such spring."""
    p = rocking_pushover(model, thetas)
    found = model.foundation_slice
    P = model.params[found]
    capped = P["f0"] >= P["fy"] * (1.0 - 1e-12)
    if capped.any():
        static = float(np.mean((P["d0"] - P["x"] * model.static_rotation)[~capped]))
    else:
        static = float(np.sum(P["k"] * P["d0"]) / np.sum(P["k"]))
    return {"theta": np.asarray(thetas, dtype=float), "M": p.moment,
            "settlement": static - p.vertical, "contact": p.contact}


def bed_response(scene: Scene, cal: Calibration, ref) -> BedResponse:
    """The bed ``cal`` in ``scene``, pushed over on the rotations of the continuum reference
    ``ref`` (its ``monotonic`` and ``cyclic`` records' ``theta``, rad)."""
    model = build_reduced(bed_scene(scene, cal))
    layout = model.layout
    onset = uplift_onset_force(model) * float(model.heights[-1])
    N_ult = cal.yield_multiple * model.weight if cal.law == "elastoplastic" else math.inf
    return BedResponse(cal, layout.vertical_stiffness, layout.rocking_stiffness, onset, N_ult,
                       pushover_record(model, ref.monotonic["theta"]),
                       pushover_record(model, ref.cyclic["theta"]))


def bed_rocking(base: Mapping, N: float, foundation: Mapping, cyclic_theta, monotonic_theta
                ) -> dict:
    """A bed's pushovers on the continuum's rotations: ``cyclic`` and ``monotonic`` records
    (θ, M, settlement, contact) and its uplift-onset moment ``onset_moment`` (the quasi-static
    lateral force at the first spring's separation times the height), units of the scene.
    The macro-element's are its own (:func:`.macro_bed.macro_rocking`)."""
    if foundation.get("law") == "macro":
        from .macro_bed import macro_rocking

        return macro_rocking(N, foundation, cyclic_theta, monotonic_theta)
    data = {k: copy.deepcopy(v) for k, v in base.items() if k not in ("soil", "continuum")}
    data["structure"] = {**data["structure"], "weight": float(N)}
    data["foundation"] = dict(foundation)
    data["motion"] = dict(FREE_MOTION)
    model = build_reduced(scene_from_dict(data, merged=True))
    return {"cyclic": pushover_record(model, cyclic_theta),
            "monotonic": pushover_record(model, monotonic_theta),
            "onset_moment": float(uplift_onset_force(model) * model.heights[-1])}


def _at(record: Mapping, key: str, theta: float) -> float:
    thetas = np.asarray(record["theta"])
    k = int(np.argmin(np.abs(thetas - theta)))
    if abs(thetas[k] - theta) > 1e-9 * max(abs(theta), 1e-300):
        raise RuntimeError(f"θ = {theta:g} is not on the path")
    return float(np.asarray(record[key])[k])


def _energy(record: Mapping) -> float:
    """Dissipated work ∮ M dθ along a path (trapezoids)."""
    theta, M = np.asarray(record["theta"]), np.asarray(record["M"])
    return float(np.sum(0.5 * (M[1:] + M[:-1]) * np.diff(theta)))


def _peaks(record: Mapping) -> np.ndarray:
    """M at the turning points of a cyclic path (each ±amplitude)."""
    theta, M = np.asarray(record["theta"]), np.asarray(record["M"])
    d = np.diff(theta)
    turns = [k + 1 for k in range(d.size - 1) if d[k] * d[k + 1] < 0]
    return M[turns]


def path_values(mono: Mapping, cyc: Mapping, theta_ratios) -> dict:
    """M, contact length and settlement at each of ``theta_ratios`` × θ_on (``mono['_theta_on']``)
    on the monotonic path, the settlement under N, the largest M, and the cyclic path's
    dissipated work ∮ M dθ, settlement over the cycles and moments at its turning points."""
    out, scale = {}, mono["_theta_on"]
    for r in theta_ratios:
        out[f"M_{r:g}"] = _at(mono, "M", r * scale)
        out[f"contact_{r:g}"] = _at(mono, "contact", r * scale)
        out[f"settlement_{r:g}"] = _at(mono, "settlement", r * scale)
    out["settlement_0"] = _at(mono, "settlement", 0.0)
    out["M_max"] = float(np.max(mono["M"]))
    out["cyclic_energy"] = _energy(cyc)
    out["cyclic_settlement"] = float(cyc["settlement"][-1] - cyc["settlement"][0])
    out["_cyclic_peaks"] = _peaks(cyc)
    return out
