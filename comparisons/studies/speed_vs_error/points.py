"""One point of the study: a scene discretised one way (model, springs, integrator, step),
run and timed in a sweep's worker (the sweep's point function), and the measures taken from it."""

from __future__ import annotations

import contextlib
import copy
import math
import os
import platform
import statistics
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from ....checks import InputError
from ....motions import find_motion
from ....reduced import IntegrationError, build_model, run as run_reduced, stability_limit
from ....scenes import Scene, load_scene, scene_from_dict
from ...framework.availability import continuum_status
from ...framework.measures import (continuum_peak_edge_gap, continuum_settlement_change,
                                   reduced_edge_uplift_from_peaks, reduced_plastic_settlement)
from ...framework.store import point_function
from ...framework.study import file_sha256
from .grid import Grid, MAX_HALVINGS, STABILITY_MARGIN, SceneSpec


# ---------------------------------------------------------------------------------------------
# Scenes and points
# ---------------------------------------------------------------------------------------------


def pulse_overrides(scene: Scene, kind: str, period: float, intensity: float) -> list[str]:
    """Overrides that replace a scene's motion by a pulse of ``intensity`` × a_up (a_up =
    g·b/(3h), the quasi-static uplift acceleration of a uniform bed under a rigid structure),
    period ``period`` (s), followed by 2 s of free vibration."""
    b, h = scene.foundation.half_width, scene.structure.height
    amplitude = intensity * b / (3.0 * h)
    out = ["motion.name=", "motion.pga=", "motion.scale=", f"motion.type='{kind}'",
           f"motion.amplitude={amplitude!r}", f"motion.period={period!r}",
           f"motion.duration={3.0 * period + 2.0!r}"]
    if kind == "sine":
        out.append("motion.cycles=1.0")
    return out


def load_spec(spec: SceneSpec) -> Scene:
    """The validated scene of a panel entry."""
    scene = load_scene(spec.scene, case=spec.case, overrides=list(spec.overrides))
    if spec.pulse is not None:
        scene = scene.with_overrides(*pulse_overrides(scene, *spec.pulse))
    if scene.foundation.support != "uplift":
        raise InputError(f"scene {spec.label!r}: foundation.support = "
                         f"{scene.foundation.support!r}; the study compares uplifting "
                         "foundations (support = 'uplift')")
    return scene


def measurement_context(workers: int) -> dict:
    """Where and how runtimes are measured: host, CPU, versions, threads, concurrent workers."""
    cpu = platform.processor() or platform.machine()
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    try:
        import numba
        numba_version = numba.__version__
    except ImportError:
        numba_version = "none"
    return {"host": platform.node(), "cpu": cpu, "cpus": os.cpu_count() or 1,
            "python": platform.python_version(), "numpy": np.__version__,
            "numba": numba_version, "threads": 1, "workers": int(workers)}


def motion_entry(scene: Scene) -> dict:
    """The point's motion identity: a record's SHA-256 (and its path, a locator)."""
    if scene.motion.type != "record":
        return {}
    path = find_motion(scene.motion.name)
    return {"motion_sha256": file_sha256(path), "_motion_path": str(path.resolve())}


def _point(data: dict, motion: dict, model: str, springs: int, integrator: str, step: dict,
           grid: Grid, context: dict) -> dict:
    """A point. ``_session`` (left out of the key) tags the records this call measures."""
    return {"scene": data, **motion, "model": model, "springs": int(springs),
            "integrator": integrator, "step": dict(step), "repeats": grid.repeats,
            "repeat_budget": grid.repeat_budget, "context": context, "_session": _SESSION}


def scene_points(scene: Scene, grid: Grid, context: dict,
                 continuum_levels: Sequence[int] = ()) -> tuple[list[dict], list[dict]]:
    """(ladder points, reference points [reference, half the springs, twice the step]); the
    continuum meshes of ``continuum_levels`` (elements across) when the continuum dynamics
    module is available."""
    data, motion = copy.deepcopy(scene.data), motion_entry(scene)
    pts = []
    models = [(m, 2) for m in grid.two_springs] + [("winkler", n) for n in grid.springs]
    for model, n in models:
        for name in grid.integrators:
            levels = grid.event_levels if name == "events" else grid.other_levels
            for rank in range(levels):
                pts.append(_point(data, motion, model, n, name, {"rank": rank}, grid, context))
    if continuum_status()[0]:
        for n in continuum_levels:
            pts.append(_point(data, motion, "continuum", n, "hht", {"auto": True}, grid,
                              context))
    nref, dt = grid.springs[-1], grid.reference_dt
    refs = [_point(data, motion, "winkler", n, "events", {"dt": d}, grid, context)
            for n, d in ((nref, dt), (nref // 2, dt), (nref, 2.0 * dt))]
    return pts, refs


def point_scene(point: Mapping) -> Scene:
    """The validated scene of a point: its model's foundation layout, its motion file."""
    data = copy.deepcopy(point["scene"])
    f = data["foundation"]
    for key in ("end_stiffness_ratio", "end_length", "positions", "stiffnesses"):
        f.pop(key, None)
    if point["model"] == "continuum":
        data.setdefault("continuum", {})["elements_across"] = int(point["springs"])
    else:
        f["layout"] = point["model"]
        f["springs"] = 2 if point["model"] in ("edges", "equivalent") else int(point["springs"])
    if "_motion_path" in point:
        data["motion"]["name"] = point["_motion_path"]
    return scene_from_dict(data, merged=True)


def _ladder_dt(scene: Scene, name: str, rank: int) -> tuple[float, float]:
    """(Δt of ladder level ``rank`` for integrator ``name``, its stability limit) (s)."""
    record_dt = scene.build_motion().dt
    limit = stability_limit(build_model(scene), name)
    k0 = 0
    while record_dt / 2 ** k0 > STABILITY_MARGIN * limit:
        k0 += 1
        if k0 > MAX_HALVINGS:
            raise InputError(f"integrator {name!r}: stability limit {limit:.3g} s is below "
                             f"record dt / 2^{MAX_HALVINGS}; not on the ladder")
    return record_dt / 2 ** (k0 + rank), limit


_WARM: set = set()
_SESSION = f"{os.getpid()}-{time.time():.0f}"


def _warm_up(scene: Scene, name: str) -> None:
    """Run ``name`` once on a 20 ms two-spring version of the scene in this process, so that
    loading the compiled kernel is not timed. The warm-up's response is discarded, and so is
    its refusal: in 20 ms a pulse that peaks later has put almost no energy in, and the energy
    check, relative to that input, can refuse a run whose kernels loaded all the same (the
    clay scene's Ricker pulse did, which made whichever of its points came first in a process
    an error)."""
    if name in _WARM:
        return
    tiny = scene.with_overrides("foundation.layout='edges'", "foundation.springs=2",
                                "analysis.duration=0.02", "analysis.dt=")
    try:
        run_reduced(tiny, integrator=name, histories=False)
    except IntegrationError:
        pass
    _WARM.add(name)


def _timed(scene: Scene, name: str, dt: float, repeats: int, budget: float):
    times, response = [], None
    while len(times) < repeats and sum(times) < budget:
        start = time.perf_counter()
        response = run_reduced(scene, integrator=name, dt=dt, histories=False)
        times.append(time.perf_counter() - start)
    return response, times


@point_function("upliftlab.comparisons.speed_vs_error:evaluate_point",
                models=("reduced", "continuum"), tolerance=1e-6)
def evaluate_point(point: Mapping) -> dict:
    """Run one point (timed); its four quantities, step, runtimes (s) and diagnostics.

    A run the integrator refuses gives ``{"error": message}``.
    """
    scene = point_scene(point)
    if point["model"] == "continuum":
        return evaluate_continuum(scene, point["repeats"], point["repeat_budget"],
                                  point.get("_session", ""))
    name, step = point["integrator"], point["step"]
    try:
        if "dt" in step:
            dt, limit = float(step["dt"]), math.nan
        else:
            dt, limit = _ladder_dt(scene, name, int(step["rank"]))
        _warm_up(scene, name)
        response, times = _timed(scene, name, dt, point["repeats"], point["repeat_budget"])
    except (IntegrationError, InputError) as exc:
        return {"error": str(exc)}
    pk = response.peaks
    return {"u": pk["u"], "theta": pk["theta"], "uplift": reduced_edge_uplift_from_peaks(response),
            "residual_settlement": reduced_plastic_settlement(response),
            "spring_uplift": pk["uplift_max"], "dt": dt,
            "stability_limit": response.info["stability_limit"] if math.isnan(limit) else limit,
            "steps": response.info["steps"], "runtime": statistics.median(times),
            "runtimes": times, "session": point.get("_session", ""),
            "measured_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
            "energy_balance_error": pk["energy_balance_error"]}


def evaluate_continuum(scene: Scene, repeats: int, budget: float, session: str = "") -> dict:
    """One continuum run (mesh, gravity, time history by the scene's ``continuum.dynamics``,
    explicit by default; timed like the reduced runs): peak
    story deformation u, peak footing rotation θ, peak gap at the footing edges and the
    settlement of the footing centre at the end from its static position (length, down)."""
    from ....continuum import build_model as build_continuum
    from ....continuum.dynamics.run import DynamicOptions, run_dynamic

    options = DynamicOptions(snapshots=0, energy=False)
    motion = scene.build_motion()
    times = []
    try:
        while len(times) < repeats and sum(times) < budget:
            start = time.perf_counter()
            model = build_continuum(scene)
            result = run_dynamic(model, scene, motion, options)
            times.append(time.perf_counter() - start)
    except (InputError, RuntimeError) as exc:
        return {"error": f"continuum: {exc}"}
    footing, gap = np.asarray(result.footing), np.asarray(result.gap)
    return {"u": float(np.max(np.abs(result.structure_u))),
            "theta": float(np.max(np.abs(footing[:, 2]))),
            "uplift": continuum_peak_edge_gap(gap, result.x),
            "residual_settlement": continuum_settlement_change(footing),
            "spring_uplift": float(max(0.0, np.max(gap))),
            "dt": float(result.metadata["dt"]),
            "stability_limit": float(result.metadata["dt_limit"])  # explicit: a real limit
            if result.metadata.get("method") == "explicit" else math.inf,
            "steps": int(result.metadata["steps"]),
            "runtime": statistics.median(times), "runtimes": times, "session": session,
            "dofs": int(model.dofs),
            "measured_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
            "energy_balance_error": float(result.energy_balance_error)}


def scales(scene: Scene) -> dict:
    """Each quantity's scale at the uniform bed's quasi-static uplift threshold (the floors'
    basis): u_up = (W b/3h)/k, θ_up = W/(K_v b), the static settlement W/K_v (uplift and
    residual settlement)."""
    w, kv = scene.structure.vertical_weight, scene.foundation.stiffness
    b, h = scene.foundation.half_width, scene.structure.height
    k = scene.structure.stories[0].stiffness
    settlement = w / kv
    return {"u": w * b / (3.0 * h) / k, "theta": w / (kv * b), "uplift": settlement,
            "residual_settlement": settlement}
