"""What does each model cost for the error it leaves? Runtime against error on a panel of scenes.

For every scene of a panel (the paper's short- and long-period buildings in Cases A, B and C,
the shear wall, pulses at several intensities) every model runs at every discretization:

* two springs: ``edges`` (±b) and ``equivalent`` (±b/√3);
* a uniform Winkler bed of N springs, N = 10 … 640;
* each integrator (``events``, ``rk4``, ``abm4``, ``newmark``, ``hht``) at a ladder of steps
  Δt = record Δt / 2^(k₀ + r), r = 0, 1, …, where k₀ is the first level inside the
  integrator's stability limit for that model (0 for the implicit ones);
* continuum mesh levels, when :mod:`upliftlab.continuum.dynamics` exists (the summary says
  when they were not run).

The error of a run is |value − reference| / max(|reference|, floor) in four quantities: peak
superstructure deformation u, peak base rotation θ, peak edge uplift and residual settlement.
The reference is the finest discretization: the event stepper on the largest bed at
``reference_dt``. Its convergence is checked by the change from the next-finer level down: the
bed of half as many springs at the same step, and the same bed at twice the step.

**Runtime** is the wall time of a whole reduced run (model, step choice, integration, peaks) in a
single-threaded worker process, the median of up to ``repeats`` repeats (fewer once a point's
runs have taken ``repeat_budget`` s), after a warm-up run of the same integrator in that process.
Runtimes are **stored with their measurement context** (host, CPU, thread settings, versions,
the number of concurrent workers and the time of measurement): the context is part of each
point's key, so re-running on the same machine recomputes nothing, and another machine measures
everything afresh. The summary states the context and how many measurement sessions contributed.

Run it with ``python -m upliftlab.comparisons.speed_vs_error [--fast] [--out DIR]``.
"""

from __future__ import annotations

import contextlib
import copy
import math
import os
import platform
import statistics
import sys
import time
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

from .. import checks
from ..checks import InputError
from ..motions import find_motion
from ..results import provenance, write_csv
from ..scenes import Scene, load_scene, scene_from_dict
from ..reduced import IntegrationError, build_model, run as run_reduced, stability_limit
from ..reduced import kernels as kn
from .protocol import Context, Study, main_for, run_study
from .store import Store
from .study import StudyResult, file_sha256, require_matplotlib, write_figure, write_summary
from .sweep import run_sweep, sweep_executor

__all__ = ["STUDY", "QUANTITIES", "INTEGRATORS", "MODELS", "SceneSpec", "Grid", "Options",
           "FULL_GRID", "FAST_GRID", "Point", "Reference", "SceneResult", "SpeedVsError",
           "DEFINITION", "compute", "write", "run", "main", "evaluate_point", "point_scene",
           "edge_uplift",
           "permanent_settlement", "pareto_front", "motion_entry", "scales", "load_spec",
           "scene_points", "check_grid",
           "check_options", "measurement_context", "continuum_status", "pulse_overrides"]

STUDY = "speed_vs_error"
QUANTITIES = ("u", "theta", "uplift", "residual_settlement")
LABELS = {"u": "peak u", "theta": "peak θ", "uplift": "peak edge uplift",
          "residual_settlement": "residual settlement"}
INTEGRATORS = ("events", "rk4", "abm4", "newmark", "hht")
IMPLICIT = ("newmark", "hht")
MODELS = ("edges", "equivalent", "winkler")
FLOOR_FRACTION = 0.1  # error floor: this fraction of the quantity's uplift-threshold scale
STABILITY_MARGIN = 0.95  # a ladder step is used only below this fraction of the limit
MAX_HALVINGS = 16


# ---------------------------------------------------------------------------------------------
# Parameters
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class SceneSpec:
    """One scene of the panel: a packaged scene ``scene`` with ``case`` and ``overrides``
    (dotted TOML keys), shown as ``label``. ``pulse`` = (kind, period in s, intensity in units
    of a_up = g·b/(3h)) replaces the scene's motion by a one-cycle ``sine`` or a ``ricker``
    pulse followed by 2 s of free vibration. ``continuum_levels``: elements across the footing
    of the continuum meshes to run (the scene needs a ``[soil]`` table)."""

    label: str
    scene: str
    case: str | None = None
    overrides: tuple[str, ...] = ()
    pulse: tuple[str, float, float] | None = None
    continuum_levels: tuple[int, ...] = ()


_PAPER = tuple(SceneSpec(f"{b}-{c}", f"{b}_period_elcentro", c)
               for b in ("short", "long") for c in ("A", "B", "C"))
# The paper's impact damper is sized per spring and its bed has no limit in N, so the paper's
# Case C and the wall have no converged reference; with the tributary impact mass they do.
_TRIBUTARY = ("foundation.impact_mass=tributary",)
_CONVERGING = (tuple(SceneSpec(f"{b}-C-tributary", f"{b}_period_elcentro", "C", _TRIBUTARY)
                     for b in ("short", "long"))
               + (SceneSpec("wall-e07-tributary", "wall_elcentro", "e07", _TRIBUTARY),))
_PULSES = tuple(SceneSpec(f"sine-{i:g}a_up-B", "short_period_elcentro", "B", (),
                          ("sine", 0.3, i)) for i in (1.0, 2.0, 4.0))


@dataclass(frozen=True)
class Grid:
    """The discretizations. ``springs`` the Winkler beds N (ascending; the largest is the
    reference bed); ``integrators``; ``event_levels`` and ``other_levels`` the number of Δt
    levels of the event stepper and of the others; ``reference_dt`` (s) the reference step
    (event stepper, largest bed); ``repeats`` and ``repeat_budget`` (s) of the timing."""

    scenes: tuple[SceneSpec, ...]
    springs: tuple[int, ...] = (10, 20, 40, 80, 160, 320, 640)
    integrators: tuple[str, ...] = INTEGRATORS
    two_springs: tuple[str, ...] = ("edges", "equivalent")
    event_levels: int = 4
    other_levels: int = 2
    reference_dt: float = 6.25e-4
    repeats: int = 5
    repeat_budget: float = 0.5


_CLAY = SceneSpec("strip-clay-ricker", "strip_footing_clay", None,
                  ("motion.duration=1.5", "continuum.domain_width=6.0",
                   "continuum.domain_depth=4.0"), None, (4, 8))
FULL_GRID = Grid(scenes=_PAPER + (SceneSpec("wall-e07", "wall_elcentro", "e07"),) + _CONVERGING
                 + _PULSES + (_CLAY,))
FAST_GRID = Grid(scenes=(SceneSpec("sine-2a_up-B", "short_period_elcentro", "B", (),
                                   ("sine", 0.3, 2.0)),
                         SceneSpec("ricker-3a_up-A", "short_period_elcentro", "A", (),
                                   ("ricker", 0.25, 3.0))),
                 springs=(10, 40, 160), event_levels=3, other_levels=2)


@dataclass(frozen=True)
class Options:
    """How the study judges and what it writes: ``convergence_tolerance`` the largest change
    of the reference from the next-finer level for it to count as converged; ``tolerances``
    the error levels of the table (fractions); ``figures`` writes PNGs."""

    convergence_tolerance: float = 0.01
    tolerances: tuple[float, ...] = (0.01, 0.05, 0.10)
    figures: bool = True


def check_grid(grid: Grid) -> Grid:
    """Validate the grid; an :class:`InputError` names the field, value and valid range."""
    if not isinstance(grid.scenes, Sequence) or not grid.scenes:
        raise InputError(f"grid.scenes = {grid.scenes!r}: expected a non-empty list of scenes")
    labels = [s.label for s in grid.scenes]
    if len(set(labels)) != len(labels):
        raise InputError(f"grid.scenes: labels {labels!r} repeat; each scene needs its own")
    counts = grid.springs
    if isinstance(counts, (str, bytes)) or not isinstance(counts, Sequence) or not counts:
        raise InputError(f"grid.springs = {counts!r}: expected a non-empty list of integers")
    for i, n in enumerate(counts):
        checks.integer_at_least(f"grid.springs[{i}]", n, 4)
        if n > 4096:
            raise InputError(f"grid.springs[{i}] = {n}: valid range is [4, 4096]")
    if any(b <= a for a, b in zip(counts, counts[1:])):
        raise InputError(f"grid.springs = {list(counts)!r}: values must strictly ascend")
    if counts[-1] % 2:
        raise InputError(f"grid.springs[-1] = {counts[-1]}: the reference bed must be even "
                         "(its convergence check halves it)")
    for i, name in enumerate(grid.integrators):
        checks.one_of(f"grid.integrators[{i}]", name, INTEGRATORS)
    for i, name in enumerate(grid.two_springs):
        checks.one_of(f"grid.two_springs[{i}]", name, MODELS[:2])
    checks.integer_at_least("grid.event_levels", grid.event_levels, 1)
    checks.integer_at_least("grid.other_levels", grid.other_levels, 1)
    checks.in_range("grid.reference_dt", grid.reference_dt, 0.0, 0.01, low_open=True)
    checks.integer_at_least("grid.repeats", grid.repeats, 1)
    checks.in_range("grid.repeat_budget", grid.repeat_budget, 0.0, 600.0, low_open=True)
    for s in grid.scenes:
        for i, n in enumerate(s.continuum_levels):
            checks.integer_at_least(f"scene {s.label}: continuum_levels[{i}]", n, 2)
        if s.pulse is not None:
            kind, period, intensity = s.pulse
            checks.one_of(f"scene {s.label}: pulse kind", kind, ("sine", "ricker"))
            checks.in_range(f"scene {s.label}: pulse period", period, 0.02, 10.0)
            checks.in_range(f"scene {s.label}: pulse intensity", intensity, 0.0, 50.0,
                            low_open=True)
    return grid


def check_options(options: Options) -> Options:
    """Validate the options; an :class:`InputError` names the field, value and valid range."""
    checks.in_range("options.convergence_tolerance", options.convergence_tolerance, 0.0, 0.5,
                    low_open=True)
    if not options.tolerances:
        raise InputError("options.tolerances = (): expected at least one tolerance")
    for i, t in enumerate(options.tolerances):
        checks.in_range(f"options.tolerances[{i}]", t, 0.0, 1.0, low_open=True, high_open=True)
    checks.boolean("options.figures", options.figures)
    return options


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


def edge_uplift(response) -> float:
    """Peak uplift of the footing edge x = ±b (length): for each spring its peak gap (tracked
    at every step) plus the lift from the spring to the edge on its side under the peak base
    rotation, (b − |x_i|)·θ_peak; the largest over the springs. Exact for springs at the edge
    (two ``edges`` springs; the error of the others vanishes as 1/N for a bed), a rigid-base
    estimate for springs inside it (``equivalent``)."""
    model = response.model
    found = model.foundation_slice
    gaps = response.raw_peaks[kn.N_PEAK_SCALARS::2][found]
    x = model.params["x"][found]
    b = model.layout.half_width
    theta = response.peaks["theta"]
    return float(max(0.0, np.max(gaps + (b - np.abs(x)) * theta)))


def permanent_settlement(response) -> float:
    """Residual settlement of the base centre once it rests on every spring again (length,
    down): Σ k_i ε_p,i / Σ k_i at the end (0 for elastic springs)."""
    model = response.model
    found = model.foundation_slice
    k = model.params["k"][found]
    return float(np.sum(k * response.plastic[-1, found]) / np.sum(k))


_WARM: set = set()
_SESSION = f"{os.getpid()}-{time.time():.0f}"


def _warm_up(scene: Scene, name: str) -> None:
    """Run ``name`` once on a 20 ms two-spring version of the scene in this process, so that
    loading the compiled kernel is not timed."""
    if name in _WARM:
        return
    tiny = scene.with_overrides("foundation.layout='edges'", "foundation.springs=2",
                                "analysis.duration=0.02", "analysis.dt=")
    run_reduced(tiny, integrator=name, histories=False)
    _WARM.add(name)


def _timed(scene: Scene, name: str, dt: float, repeats: int, budget: float):
    times, response = [], None
    while len(times) < repeats and sum(times) < budget:
        start = time.perf_counter()
        response = run_reduced(scene, integrator=name, dt=dt, histories=False)
        times.append(time.perf_counter() - start)
    return response, times


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
    return {"u": pk["u"], "theta": pk["theta"], "uplift": edge_uplift(response),
            "residual_settlement": permanent_settlement(response),
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
    from ..continuum import build_model as build_continuum
    from ..continuum.dynamics import DynamicOptions, run_dynamic

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
    footing, x = np.asarray(result.footing), np.asarray(result.x)
    gap = np.asarray(result.gap)
    edges = [int(np.argmin(x)), int(np.argmax(x))]
    t = np.asarray(result.time)
    return {"u": float(np.max(np.abs(result.structure_u))),
            "theta": float(np.max(np.abs(footing[:, 2]))),
            "uplift": float(max(0.0, np.max(gap[:, edges]))),
            "residual_settlement": float(footing[0, 1] - footing[-1, 1]),
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


# ---------------------------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Point:
    """One evaluated discretization of a scene: ``model`` and ``springs``, ``integrator`` and
    ``dt`` (s), ``runtime`` (s, median of ``repeats``), ``values`` and signed relative
    ``errors`` per quantity (NaN if the run was refused: ``failure``)."""

    model: str
    springs: int
    integrator: str
    dt: float
    runtime: float
    repeats: int
    values: dict
    errors: dict
    failure: str | None = None
    measured_utc: str = ""

    @property
    def label(self) -> str:
        model = self.model if self.model != "winkler" else f"N={self.springs}"
        return f"{model} {self.integrator} dt={self.dt:.3g}"

    def abs_error(self, quantity: str) -> float:
        return abs(self.errors.get(quantity, math.nan))


@dataclass(frozen=True)
class Reference:
    """The scene's reference (event stepper, ``springs``, ``dt``): its ``values``, its
    ``runtime`` and its convergence: ``change_springs`` and ``change_dt`` per quantity, the
    relative changes from the bed of half the springs and from twice the step; ``converged``
    per quantity when both are within ``tolerance``."""

    springs: int
    dt: float
    values: dict
    runtime: float
    change_springs: dict
    change_dt: dict
    converged: dict
    tolerance: float
    floors: dict


@dataclass(frozen=True)
class SceneResult:
    """The points of one scene, its reference and each quantity's Pareto front."""

    label: str
    name: str
    reference: Reference
    points: tuple[Point, ...]
    fronts: dict  # quantity -> tuple of indices into points, by ascending runtime

    def front(self, quantity: str) -> list[Point]:
        return [self.points[i] for i in self.fronts[quantity]]

    def cheapest(self, quantity: str, tolerance: float) -> Point | None:
        """The fastest point within ``tolerance`` (fraction) in ``quantity``, or None."""
        ok = [p for p in self.points if p.abs_error(quantity) <= tolerance]
        return min(ok, key=lambda p: p.runtime) if ok else None


@dataclass(frozen=True, eq=False)
class SpeedVsError:
    """The study's result: files and summary (``study``), the scenes, and what was not run."""

    study: StudyResult
    scenes: tuple[SceneResult, ...]
    grid: Grid
    options: Options
    context: dict
    continuum: str
    sessions: int

    def scene(self, label: str) -> SceneResult:
        return next(s for s in self.scenes if s.label == label)


def pareto_front(runtimes: Sequence[float], errors: Sequence[float]) -> list[int]:
    """Indices of the points no other point beats in both runtime and |error|, by ascending
    runtime (NaN errors never enter; ties in runtime go to the smaller error)."""
    order = sorted((i for i, e in enumerate(errors) if math.isfinite(e)),
                   key=lambda i: (runtimes[i], abs(errors[i])))
    front, best = [], math.inf
    for i in order:
        if abs(errors[i]) < best:
            front.append(i)
            best = abs(errors[i])
    return front


def _relative(value: float, reference: float, floor: float) -> float:
    return (value - reference) / max(abs(reference), floor)


def _reference(records: Sequence[Mapping], springs: int, dt: float, floors: dict,
               tolerance: float) -> Reference:
    ref, half, coarse = records
    for r, what in ((ref, "reference"), (half, "half-springs check"), (coarse, "2·dt check")):
        if "error" in r:
            raise InputError(f"the {what} run (event stepper, dt ≤ {2 * dt:g} s) failed: "
                             f"{r['error']}")
    values = {q: ref[q] for q in QUANTITIES}
    cs = {q: abs(_relative(half[q], ref[q], floors[q])) for q in QUANTITIES}
    cd = {q: abs(_relative(coarse[q], ref[q], floors[q])) for q in QUANTITIES}
    conv = {q: max(cs[q], cd[q]) <= tolerance for q in QUANTITIES}
    return Reference(springs, dt, values, ref["runtime"], cs, cd, conv, tolerance, floors)


def _points(points: Sequence[Mapping], records: Sequence[Mapping], ref: Reference):
    out = []
    for p, r in zip(points, records):
        if "error" in r:
            nan = {q: math.nan for q in QUANTITIES}
            out.append(Point(p["model"], p["springs"], p["integrator"], math.nan, math.nan, 0,
                             nan, nan, r["error"]))
            continue
        values = {q: r[q] for q in QUANTITIES}
        errors = {q: _relative(r[q], ref.values[q], ref.floors[q]) for q in QUANTITIES}
        out.append(Point(p["model"], p["springs"], p["integrator"], r["dt"], r["runtime"],
                         len(r["runtimes"]), values, errors, None, r["measured_utc"]))
    return tuple(out)


def _scene_result(spec: SceneSpec, scene: Scene, points, records, refs, ref_records,
                  grid: Grid, options: Options) -> SceneResult:
    floors = {q: FLOOR_FRACTION * v for q, v in scales(scene).items()}
    ref = _reference(ref_records, grid.springs[-1], grid.reference_dt, floors,
                     options.convergence_tolerance)
    pts = _points(points, records, ref)
    times = [p.runtime for p in pts]
    fronts = {q: tuple(pareto_front(times, [p.errors[q] for p in pts])) for q in QUANTITIES}
    return SceneResult(spec.label, scene.name, ref, pts, fronts)


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------


def continuum_status() -> tuple[bool, str]:
    """(available, why): whether the continuum dynamics module can be imported."""
    try:
        from ..continuum import dynamics  # noqa: F401
    except Exception as exc:  # noqa: BLE001 — any failure to import means "not available"
        return False, (f"continuum points were not run: upliftlab.continuum.dynamics is not "
                       f"available ({type(exc).__name__}: {exc})")
    return True, "upliftlab.continuum.dynamics is available"


def _continuum_note(grid: Grid, results: Sequence[SceneResult]) -> str:
    available, why = continuum_status()
    if not available:
        return why
    ran = [(s.label, [p for p in s.points if p.model == "continuum"]) for s in results]
    ran = [(label, pts) for label, pts in ran if pts]
    if not ran:
        return ("continuum points were not run: no scene of this panel has continuum mesh "
                "levels (they need a [soil] table; the full panel's strip-clay-ricker has them)")
    parts = []
    for label, pts in ran:
        levels = ", ".join(f"{p.springs} elements across ({p.runtime:.3g} s)"
                           if p.failure is None else f"{p.springs} across: refused"
                           for p in pts)
        parts.append(f"{label}: {levels}")
    return ("continuum meshes run (the scene's continuum.dynamics, explicit by default; "
            "automatic step): " + "; ".join(parts))


def _panel(scene, grid: Grid) -> Grid:
    if scene is None:
        return grid
    if isinstance(scene, SceneSpec):
        return replace(grid, scenes=(scene,))
    if isinstance(scene, str):
        return replace(grid, scenes=(SceneSpec(scene, scene),))
    if isinstance(scene, Sequence):
        return replace(grid, scenes=tuple(scene))
    raise InputError(f"scene = {scene!r}: expected None (the panel), a scene name or a "
                     "SceneSpec, or a list of SceneSpec")


def compute(scene, ctx: Context) -> SpeedVsError:
    """Every point of the panel (``scene``: None for ``ctx.grid``'s panel, a scene or scene
    specs) under ``ctx.options``; ``ctx.workers`` local processes (default: the CPU count)."""
    grid = check_grid(_panel(scene, ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID)))
    options = check_options(ctx.options or Options())
    if options.figures:
        require_matplotlib(STUDY)
    scenes = [load_spec(s) for s in grid.scenes]
    nworkers = ctx.workers or (os.cpu_count() or 1)
    context = measurement_context(nworkers)
    per_scene = [scene_points(s, grid, context, spec.continuum_levels)
                 for spec, s in zip(grid.scenes, scenes)]
    flat = [p for pts, refs in per_scene for p in pts + refs]
    executor = ctx.executor
    with contextlib.ExitStack() as stack:
        if executor is None:
            executor = stack.enter_context(sweep_executor(ctx.scheduler, workers=nworkers))
        records = run_sweep(evaluate_point, flat, ctx.store, study=STUDY, executor=executor,
                            progress=ctx.progress)
    results, k = [], 0
    for spec, s, (pts, refs) in zip(grid.scenes, scenes, per_scene):
        recs, k = records[k:k + len(pts)], k + len(pts)
        ref_recs, k = records[k:k + len(refs)], k + len(refs)
        results.append(_scene_result(spec, s, pts, recs, refs, ref_recs, grid, options))
    sessions = len({r.get("session", "") for r in records if "error" not in r})
    return SpeedVsError(None, tuple(results), grid, options, context,
                        _continuum_note(grid, results), sessions)


def run(scene: str | SceneSpec | Sequence[SceneSpec] | None = None, fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        grid: Grid | None = None, options: Options | None = None, executor=None,
        scheduler=None, progress=None, workers: int | None = None) -> SpeedVsError:
    """Run the study on ``scene`` (default: the panel of :data:`FULL_GRID`, or
    :data:`FAST_GRID` with ``fast``: two short pulse scenes, N = 10, 40, 160).

    ``out``: output directory (default ``results/speed_vs_error[-fast]``); ``store``: the
    results store (default ``<out>/store``); ``executor``/``scheduler``/``progress`` go to
    :func:`.sweep.run_sweep`; ``workers`` local processes (default: the CPU count). Every
    parameter and scene is checked before anything runs.
    """
    return run_study(DEFINITION, scene, Context(
        fast=fast, out=out, store=store, grid=grid, options=options, executor=executor,
        scheduler=scheduler, progress=progress, workers=workers))


# ---------------------------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------------------------


def write(result: SpeedVsError, ctx: Context) -> StudyResult:
    """Points, Pareto fronts, figures and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, fast=fast, grid=asdict(result.grid),
                      options=asdict(result.options), context=result.context,
                      store=str(store.root))
    files = [_write_points(result, out / "points.csv"), _write_pareto(result, out / "pareto.csv")]
    if result.options.figures:
        files += [_figure(s, out / "figures" / f"{s.label}.png") for s in result.scenes]
    elapsed = ctx.elapsed()
    numbers = _numbers(result, elapsed)
    text = _markdown(result, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


_MODEL_CODE = {"edges": -2, "equivalent": -1, "continuum": 1}


def _columns(rows: list[tuple[SceneResult, Point]]) -> dict:
    cols = {"scene": [i for i, _ in rows], "springs": [p.springs for _, p in rows],
            "layout_code": [_MODEL_CODE.get(p.model, 0) for _, p in rows],
            "integrator": [INTEGRATORS.index(p.integrator) for _, p in rows],
            "dt_s": [p.dt for _, p in rows], "runtime_s": [p.runtime for _, p in rows],
            "repeats": [p.repeats for _, p in rows]}
    for q in QUANTITIES:
        cols[q] = [p.values[q] for _, p in rows]
        cols[f"error_{q}"] = [p.errors[q] for _, p in rows]
    return {k: np.array(v, dtype=float) for k, v in cols.items()}


def _legend(result: SpeedVsError) -> str:
    scenes = ", ".join(f"{i} = {s.label}" for i, s in enumerate(result.scenes))
    return (f"scene index: {scenes}\nlayout_code: -2 edges (two springs at +/-b), -1 "
            f"equivalent (+/-b/sqrt3), 0 Winkler bed of `springs` springs, 1 continuum mesh "
            f"of `springs` elements across the footing\nintegrator: "
            + ", ".join(f"{i} = {n}" for i, n in enumerate(INTEGRATORS))
            + "\nerrors: (value - reference)/max(|reference|, floor); NaN: refused run")


def _write_points(result: SpeedVsError, path: Path) -> Path:
    rows = [(i, p) for i, s in enumerate(result.scenes) for p in s.points]
    return write_csv(path, _columns(rows), header=f"{STUDY}: every run\n{_legend(result)}")


def _write_pareto(result: SpeedVsError, path: Path) -> Path:
    cols: dict[str, list] = {"scene": [], "quantity": [], "rank": []}
    rows = []
    for i, s in enumerate(result.scenes):
        for qi, q in enumerate(QUANTITIES):
            for r, p in enumerate(s.front(q)):
                cols["scene"].append(i)
                cols["quantity"].append(qi)
                cols["rank"].append(r)
                rows.append((i, p))
    data = {k: np.array(v, dtype=float) for k, v in cols.items()}
    if rows:
        data.update(_columns(rows))
    legend = _legend(result) + "\nquantity: " + ", ".join(f"{i} = {q}" for i, q in
                                                           enumerate(QUANTITIES))
    return write_csv(path, data, header=f"{STUDY}: Pareto fronts (runtime vs |error|)\n{legend}")


_COLOURS = {"events": "C0", "rk4": "C1", "abm4": "C2", "newmark": "C3", "hht": "C4"}
_MARKERS = {"edges": "s", "equivalent": "D", "winkler": "o", "continuum": "^"}


def _figure(s: SceneResult, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, axes = plt.subplots(1, len(QUANTITIES), figsize=(4.2 * len(QUANTITIES), 3.8),
                             constrained_layout=True)
    for ax, q in zip(axes, QUANTITIES):
        floor = 1e-6
        for p in s.points:
            if p.failure is None:
                ax.loglog(p.runtime, max(p.abs_error(q), floor), _MARKERS[p.model],
                          color=_COLOURS[p.integrator], ms=3 + 0.6 * math.log2(p.springs),
                          alpha=0.6, mfc="none")
        front = s.front(q)
        ax.loglog([p.runtime for p in front], [max(p.abs_error(q), floor) for p in front],
                  "k-", lw=1.2, label="Pareto front")
        ax.axvline(s.reference.runtime, color="grey", ls=":", label="reference runtime")
        ax.set_xlabel("runtime (s)")
        ax.set_ylabel(f"|error| in {LABELS[q]}")
        ax.set_title(f"{s.label}: {LABELS[q]}", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # decades only
    handles = [plt.Line2D([], [], color=c, marker="o", ls="", label=n)
               for n, c in _COLOURS.items()]
    handles += [plt.Line2D([], [], color="k", marker=m, ls="", mfc="none", label=n)
                for n, m in _MARKERS.items()]
    axes[0].legend(handles=handles, fontsize=6, title="marker size ∝ log N", title_fontsize=6)
    return write_figure(path, fig)


def _point_dict(p: Point | None, ref: Reference) -> dict | None:
    if p is None:
        return None
    return {"model": p.model, "springs": p.springs, "integrator": p.integrator, "dt": p.dt,
            "runtime_s": p.runtime, "repeats": p.repeats,
            "errors": p.errors, "speedup_vs_reference": ref.runtime / p.runtime}


def _numbers(result: SpeedVsError, elapsed: float) -> dict:
    scenes = {}
    tally = {n: 0 for n in INTEGRATORS}
    for s in result.scenes:
        ref = s.reference
        scenes[s.label] = {
            "scene": s.name,
            "reference": {"springs": ref.springs, "dt": ref.dt, "values": ref.values,
                          "runtime_s": ref.runtime, "change_half_springs": ref.change_springs,
                          "change_double_dt": ref.change_dt, "converged": ref.converged,
                          "tolerance": ref.tolerance, "floors": ref.floors},
            "points": len(s.points),
            "refused": [f"{p.model} N={p.springs} {p.integrator}: {p.failure}"
                        for p in s.points if p.failure],
            "pareto": {q: [_point_dict(p, ref) for p in s.front(q)] for q in QUANTITIES},
            "cheapest": {q: {f"{t:g}": _point_dict(s.cheapest(q, t), ref)
                             for t in result.options.tolerances} for q in QUANTITIES},
            "cheapest_note": {q: _table_note(s, q) for q in QUANTITIES}}
        for q in QUANTITIES:
            for p in s.front(q):
                tally[p.integrator] += 1
    return {"scenes": scenes, "pareto_points_by_integrator": tally,
            "measurement_context": result.context, "measurement_sessions": result.sessions,
            "runtimes": "stored with their measurement context (part of each point's key)",
            "continuum": result.continuum, "elapsed_s": elapsed}


def _pct(v: float) -> str:
    if not math.isfinite(v):
        return "n/a"
    return f"{100 * v:.2g} %" if v < 0.01 else f"{100 * v:.1f} %"


def _short(p: Point) -> str:
    model = {"edges": "2 springs ±b", "equivalent": "2 springs ±b/√3",
             "continuum": f"continuum {p.springs} elements across"}.get(p.model,
                                                                          f"N = {p.springs}")
    return f"{model}, {p.integrator}, Δt = {p.dt:.3g} s"


def _continuum_lines(result: SpeedVsError) -> list[str]:
    """The continuum meshes: values, error against the scene's (Winkler) reference, and the
    change of each mesh from the next finer one."""
    lines = []
    for s in result.scenes:
        pts = sorted((p for p in s.points if p.model == "continuum" and p.failure is None),
                     key=lambda p: p.springs)
        if not pts:
            continue
        lines += [f"### {s.label} — continuum meshes against the Winkler reference", "",
                  "| elements across | runtime (s) | " + " | ".join(
                      f"{LABELS[q]} (error; change to next finer)" for q in QUANTITIES)
                  + " |", "|---|---|" + "---|" * len(QUANTITIES)]
        for k, p in enumerate(pts):
            finer = pts[k + 1] if k + 1 < len(pts) else None
            cells = []
            for q in QUANTITIES:
                change = ("—" if finer is None else _pct(abs(_relative(
                    p.values[q], finer.values[q], s.reference.floors[q]))))
                cells.append(f"{p.values[q]:.4g} ({_pct(p.abs_error(q))}; {change})")
            lines.append(f"| {p.springs} | {p.runtime:.3g} | " + " | ".join(cells) + " |")
        lines += ["", "The continuum is another model (soil continuum, plasticity, radiation), "
                  "so its error against the Winkler reference is model discrepancy plus mesh "
                  "error; the change to the next finer mesh is its own discretization error.",
                  ""]
    return lines


def _table_note(s: SceneResult, q: str) -> str:
    """Why the cheapest-within-tolerance cells of (scene, quantity) say nothing, or ''."""
    ref = s.reference
    if not ref.converged[q]:
        change = max(ref.change_springs[q], ref.change_dt[q])
        return f"n/a: reference not converged (changes {_pct(change)})"
    if ref.values[q] == 0.0 and all(p.values[q] == 0.0 for p in s.points if not p.failure):
        return "0 for every model (elastic springs)"
    return ""


def _markdown(result: SpeedVsError, fast: bool, elapsed: float) -> str:
    ctx, opt = result.context, result.options
    lines = [f"# Speed against error{' (fast)' if fast else ''}", "",
             f"{len(result.scenes)} scenes, {sum(len(s.points) for s in result.scenes)} runs "
             f"plus 3 reference runs each. Wall time {elapsed:.1f} s.", "",
             "Error = |value − reference| / max(|reference|, floor), floor = "
             f"{FLOOR_FRACTION:g} × the quantity's scale at the uplift threshold (u_up = "
             "(W b/3h)/k, θ_up = W/(K_v b), W/K_v for uplift and settlement). Peak edge uplift: "
             "the largest tracked spring gap plus (b − |x_i|)·θ_peak; residual settlement: "
             "Σ k_i ε_p,i / Σ k_i at the end (zero for elastic springs).", "",
             f"Runtimes: wall time of a whole reduced run in a single-threaded worker, median of "
             f"up to {result.grid.repeats} repeats (fewer once {result.grid.repeat_budget:g} s "
             f"were spent), after a warm-up. They are **stored with their measurement context** "
             f"(in each point's key): {ctx['cpu']} on host `{ctx['host']}`, {ctx['workers']} "
             f"concurrent single-threaded workers on {ctx['cpus']} CPUs, numba {ctx['numba']}; "
             f"{result.sessions} measurement session(s) (calls of the study that ran points) "
             "contributed. Compare runtimes as ratios within this table.", "",
             f"Continuum: {result.continuum}.", "",
             "## References and their convergence", "",
             "| scene | reference | " + " | ".join(f"{LABELS[q]} (ΔN, Δdt)" for q in QUANTITIES)
             + " | ref. runtime |", "|---|---|" + "---|" * len(QUANTITIES) + "---|"]
    for s in result.scenes:
        r = s.reference
        cells = [f"{r.values[q]:.4g} ({_pct(r.change_springs[q])}, {_pct(r.change_dt[q])})"
                 + ("" if r.converged[q] else " **not conv.**") for q in QUANTITIES]
        lines.append(f"| {s.label} | events, N = {r.springs}, Δt = {r.dt:g} s | "
                     + " | ".join(cells) + f" | {r.runtime:.3g} s |")
    notconv = [(s.label, q) for s in result.scenes for q in QUANTITIES
               if not s.reference.converged[q]]
    lines += ["", f"Converged to {_pct(opt.convergence_tolerance)} (change from half the "
              f"springs and from twice the step): "
              + (f"all but {len(notconv)}: " + ", ".join(f"{a} {LABELS[q]}" for a, q in notconv)
                 if notconv else "every scene and quantity") + ". Errors against an unconverged "
              "reference are at best as good as its change.", ""]
    lines += ["## Cheapest discretization within each tolerance", "",
              "| scene | quantity | " + " | ".join(f"within {_pct(t)}" for t in opt.tolerances)
              + " |", "|---|---|" + "---|" * len(opt.tolerances)]
    for s in result.scenes:
        for q in QUANTITIES:
            note = _table_note(s, q)
            if note:
                lines.append(f"| {s.label} | {LABELS[q]} | " + " | ".join(
                    [note] * len(opt.tolerances)) + " |")
                continue
            cells = []
            for t in opt.tolerances:
                p = s.cheapest(q, t)
                cells.append("none" if p is None else
                             f"{_short(p)}: {p.runtime * 1e3:.3g} ms, {_pct(p.abs_error(q))} "
                             f"(×{s.reference.runtime / p.runtime:.3g} faster than ref.)")
            lines.append(f"| {s.label} | {LABELS[q]} | " + " | ".join(cells) + " |")
    tally = _numbers(result, elapsed)["pareto_points_by_integrator"]
    lines += ["", "## Pareto fronts", "", "Points on the fronts (all scenes and quantities) by "
              "integrator: " + ", ".join(f"{n} {c}" for n, c in tally.items()) + ".", ""]
    for s in result.scenes:
        lines += [f"### {s.label} — peak u", "", "| runtime (ms) | |error| | discretization |",
                  "|---|---|---|"]
        lines += [f"| {p.runtime * 1e3:.3g} | {_pct(p.abs_error('u'))} | {_short(p)} |"
                  for p in s.front("u")]
        lines.append("")
    lines += _continuum_lines(result)
    refused = [(s.label, p) for s in result.scenes for p in s.points if p.failure]
    lines += [f"Refused runs: {len(refused)}."]
    lines += [f"- {a}: {_short(p)}: {p.failure}" for a, p in refused[:10]]
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _context_from(args, ctx: Context, say) -> Context:
    return replace(ctx, options=Options(figures=not args.no_figures))


def _describe(result: SpeedVsError) -> list[str]:
    lines = []
    for s in result.scenes:
        p = s.cheapest("u", 0.05)
        best = _table_note(s, "u") or ("none" if p is None else
                                       f"{_short(p)} ({p.runtime * 1e3:.3g} ms)")
        lines.append(f"{s.label}: reference {s.reference.runtime:.3g} s; cheapest within 5 % "
                     f"in peak u: {best}")
    return lines


DEFINITION = Study(STUDY, "Speed against error",
                   "What each model and discretisation costs for the error it leaves.", Options,
                   compute, write, describe=_describe, context_from=_context_from,
                   help_fast="two short pulses, few levels")
main = main_for(DEFINITION)


if __name__ == "__main__":
    sys.exit(main())
