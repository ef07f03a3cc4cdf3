"""What the runs say, read from the study's dataset: each scene's runs, whether its reference
converged, the Pareto fronts of runtime against error and the cheapest run within a
tolerance."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .grid import QUANTITIES


@dataclass(frozen=True)
class Run:
    """One run of a scene, as the dataset holds it: ``model`` (``edges``, ``equivalent``,
    ``winkler``, ``continuum``) and ``springs``, ``integrator`` and ``dt`` (s), ``runtime`` (s,
    median of ``repeats``), ``values`` and signed relative ``errors`` per quantity (NaN if the
    run was refused: ``failure``)."""

    model: str
    springs: int
    integrator: str
    dt: float
    runtime: float
    repeats: int
    values: dict
    errors: dict
    failure: str | None = None

    def abs_error(self, quantity: str) -> float:
        return abs(self.errors.get(quantity, math.nan))


def runs(ds, scene: str) -> list[Run]:
    """The runs of ``scene`` in the order they were made: by model, integrator and level."""
    one = ds.sel(scene=scene)
    ran, failure = one.ran.values, one.failure.values
    dt, runtime, repeats = one.dt.values, one.runtime.values, one.repeats.values
    value, error = one.value.values, one.error.values
    layouts, springs = ds.layout.values.tolist(), ds.springs.values.tolist()
    integrators = ds.integrator.values.tolist()
    out = []
    for m, i, k in zip(*np.nonzero(ran)):  # C order: model, integrator, level
        why = str(failure[m, i, k]) or None
        out.append(Run(layouts[m], int(springs[m]), integrators[i], float(dt[m, i, k]),
                       float(runtime[m, i, k]), 0 if why else int(repeats[m, i, k]),
                       dict(zip(QUANTITIES, value[m, i, k].tolist())),
                       dict(zip(QUANTITIES, error[m, i, k].tolist())), why))
    return out


def converged(ds, scene: str) -> dict[str, bool]:
    """Per quantity: the reference of ``scene`` changes by at most the convergence tolerance
    from half the springs and from twice the step."""
    one = ds.sel(scene=scene)
    change = np.maximum(one.change_half_springs.values, one.change_double_dt.values)
    tolerance = float(ds.attrs["options_convergence_tolerance"])
    return {q: bool(c <= tolerance) for q, c in zip(QUANTITIES, change)}


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


def front(points: Sequence[Run], quantity: str) -> list[Run]:
    """The Pareto front of ``points`` in ``quantity``, by ascending runtime."""
    indices = pareto_front([p.runtime for p in points], [p.errors[quantity] for p in points])
    return [points[i] for i in indices]


def cheapest(points: Sequence[Run], quantity: str, tolerance: float) -> Run | None:
    """The fastest of ``points`` within ``tolerance`` (fraction) in ``quantity``, or None."""
    ok = [p for p in points if p.abs_error(quantity) <= tolerance]
    return min(ok, key=lambda p: p.runtime) if ok else None


def table_note(ds, scene: str, points: Sequence[Run], q: str) -> str:
    """Why the cheapest-within-tolerance cells of (scene, quantity) say nothing, or ''."""
    one = ds.sel(scene=scene, quantity=q)
    if not converged(ds, scene)[q]:
        change = max(float(one.change_half_springs), float(one.change_double_dt))
        return f"n/a: reference not converged (changes {percent(change)})"
    if float(one.reference) == 0.0 and all(p.values[q] == 0.0 for p in points if not p.failure):
        return "0 for every model (elastic springs)"
    return ""


def percent(v: float) -> str:
    if not math.isfinite(v):
        return "n/a"
    return f"{100 * v:.2g} %" if v < 0.01 else f"{100 * v:.1f} %"


def continuum_note(available: tuple[bool, str], labels: Sequence[str],
                   continuum: Sequence[Sequence]) -> str:
    """What the summary says of the continuum: why it was not run, or per scene its meshes
    (``continuum``: per scene, the (elements across, runtime in s, failure) of its meshes)."""
    ok, why = available
    if not ok:
        return why
    ran = [(label, pts) for label, pts in zip(labels, continuum) if pts]
    if not ran:
        return ("continuum points were not run: no scene of this panel has continuum mesh "
                "levels (they need a [soil] table; the full panel's strip-clay-ricker has them)")
    parts = []
    for label, pts in ran:
        levels = ", ".join(f"{n} elements across ({runtime:.3g} s)" if failure is None
                           else f"{n} across: refused" for n, runtime, failure in pts)
        parts.append(f"{label}: {levels}")
    return ("continuum meshes run (the scene's continuum.dynamics, explicit by default; "
            "automatic step): " + "; ".join(parts))
