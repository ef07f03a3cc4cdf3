"""What the points say: errors against each scene's converged reference, Pareto fronts and
the cheapest point within a tolerance."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from ....checks import InputError
from ....scenes import Scene
from ...framework.study import StudyResult
from .grid import FLOOR_FRACTION, Grid, Options, QUANTITIES, SceneSpec
from .points import continuum_status, scales


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


def relative_to_reference(value: float, reference: float, floor: float) -> float:
    return (value - reference) / max(abs(reference), floor)


def _reference(records: Sequence[Mapping], springs: int, dt: float, floors: dict,
               tolerance: float) -> Reference:
    ref, half, coarse = records
    for r, what in ((ref, "reference"), (half, "half-springs check"), (coarse, "2·dt check")):
        if "error" in r:
            raise InputError(f"the {what} run (event stepper, dt ≤ {2 * dt:g} s) failed: "
                             f"{r['error']}")
    values = {q: ref[q] for q in QUANTITIES}
    cs = {q: abs(relative_to_reference(half[q], ref[q], floors[q])) for q in QUANTITIES}
    cd = {q: abs(relative_to_reference(coarse[q], ref[q], floors[q])) for q in QUANTITIES}
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
        errors = {q: relative_to_reference(r[q], ref.values[q], ref.floors[q]) for q in QUANTITIES}
        out.append(Point(p["model"], p["springs"], p["integrator"], r["dt"], r["runtime"],
                         len(r["runtimes"]), values, errors, None, r["measured_utc"]))
    return tuple(out)


def scene_result(spec: SceneSpec, scene: Scene, points, records, refs, ref_records,
                 grid: Grid, options: Options) -> SceneResult:
    floors = {q: FLOOR_FRACTION * v for q, v in scales(scene).items()}
    ref = _reference(ref_records, grid.springs[-1], grid.reference_dt, floors,
                     options.convergence_tolerance)
    pts = _points(points, records, ref)
    times = [p.runtime for p in pts]
    fronts = {q: tuple(pareto_front(times, [p.errors[q] for p in pts])) for q in QUANTITIES}
    return SceneResult(spec.label, scene.name, ref, pts, fronts)


def continuum_note(grid: Grid, results: Sequence[SceneResult]) -> str:
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
