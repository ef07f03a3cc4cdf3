"""What the map's continuum runs will cost, estimated before any of them starts.

A dynamic run of the explicit route costs a fixed part (the mesh, the stable step's Lanczos
eigenvalue, the gravity state) and a part per step, both about proportional to the DOFs:
``seconds = F·dofs + R·dofs·steps`` (not counted: a worker's first run loads the compiled
kernels from numba's on-disk cache, or compiles them, once per process). ``steps`` =
duration/dt, with dt the stable step of the mesh: from the runs of the same soil and mesh
already stored, else from :data:`~upliftlab.continuum.dynamics.explicit.COURANT_ESTIMATE` (V_p
dt/h_min, below the measured value, so that the estimate errs on the cost's side). The soil's
Rayleigh damping (``continuum.damping_ratio``) shortens the step by the factor of its Maxwell
arm at the mesh's highest frequency
(:func:`~upliftlab.continuum.dynamics.rayleigh.damped_critical`, about 1/√(1 + β ω_c)), taken
here at ω_max = 2/dt of the undamped estimate (which errs high, so the factor errs low, on the
cost's side); a stored run's steps are counted as its undamped ones (× its ``dt_reduction``)
before they stand for another run's. F depends on the soil: the gravity state (Newton with the
vectorised return map on either route) of a frictional soil (Mohr–Coulomb, Drucker–Prager) is
slower than an undrained one's. Where the stored runs of the same kind of return map in the
time loop (compiled: elastic, Tresca, von Mises, Mohr–Coulomb; or the vectorised fallback:
Drucker–Prager) and the same kind of soil are of two lengths or more, F and R are both fitted
to them (:func:`fit_rates`: a pulse's few seconds of motion carry a fixed part that a record's
minute does not, and a fixed part taken from the defaults instead, larger than today's cached
start-up, left the pulses' per-step rate near zero and estimated the half-plane's records at 26
s against the 1–5 min they took), and a run is estimated at no less than its steps at the
stored runs' median of wall/(dofs·steps), every second counted as the steps' (a record far
longer than the pulses it is estimated from is then estimated high rather than low); otherwise
R is the stored runs' median of (wall − F·dofs)/(dofs·steps) with the default F, else the
default below. A static point (stiffness plus vertical pushover) costs S·dofs, S from the
stored statics when there are any. A soil's impedance (when a bed needs it,
:mod:`.impedance_points`) costs P·dofs·frequencies on the impedance's own mesh (one complex
factorisation per frequency), P from the stored impedances when there are any; it is one static
run.

The defaults were measured on the project's loaded 2-core machine with kernels compiled
(runs of 0.01 s and 0.3–1 s of a Ricker pulse on 4 and 16 across, the clay's compiled Tresca
and the frictional soil's Mohr–Coulomb, then through the fallback, and this study's 16-across
statics of the clay; reported in the issue note); the compiled Mohr–Coulomb costs per step
about what the compiled Tresca does (``benchmarks/EXPLICIT_MATERIALS.md``). The stored runs
replace the per-step rates as soon as there are any, so a second estimate is the machine's
own: the grid's own runs, else (a new slice of a kept store) the store's other dynamic runs of
the same code.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np

from ....checks import InputError
from ....scenes.soil import FRICTIONAL, SOIL_MODELS

__all__ = ["Estimate", "estimate_cost", "fit_rates", "mesh_size", "impedance_dofs",
           "refuse_over_budget", "timed_dynamic_runs", "damping_reduction",
           "FIXED_SECONDS_PER_DOF", "SECONDS_PER_DOF_STEP", "STATIC_SECONDS_PER_DOF",
           "compiled_soil_model", "IMPEDANCE_SECONDS_PER_DOF_FREQUENCY"]

#: Fixed cost of a dynamic run per DOF (s): mesh, stable step, gravity state; of an undrained
#: soil (False) and of a frictional one (True: the scene's ``soil.frictional``), whose gravity
#: state is slower.
FIXED_SECONDS_PER_DOF = {False: 4.0e-4, True: 1.1e-3}
#: Cost per step and DOF (s): compiled return maps, and the vectorised fallback.
SECONDS_PER_DOF_STEP = {True: 1.0e-7, False: 6.1e-6}
#: The least ratio of the longest stored run's steps to the shortest's for the fixed and
#: per-step costs to be fitted apart (:func:`fit_rates`).
FIT_STEP_SPAN = 1.2
#: Cost of a soil's statics (stiffness and vertical pushover) per DOF (s).
STATIC_SECONDS_PER_DOF = 3.0e-3


def compiled_soil_model(model: str) -> bool:
    """True when the soil model ``model`` has a compiled point return, which the explicit
    route's compiled element loop runs
    (:func:`~upliftlab.continuum.materials.registry.compiled_models`); the others run through
    their vectorised return map."""
    from ....continuum.materials.registry import compiled_models

    return model in compiled_models()


def _frictional(model: str) -> bool:
    """True for a soil model of frictional strength (the scene's list of models)."""
    return SOIL_MODELS.get(model) == FRICTIONAL

#: Cost of a soil's impedance per DOF of its mesh and per frequency (s): 19 frequencies on 4
#: and on 16 across, the clay's elastic constants, on the loaded 2-core machine.
IMPEDANCE_SECONDS_PER_DOF_FREQUENCY = 3.2e-5


@dataclass(frozen=True)
class Estimate:
    """``runs`` continuum runs to make (``static``: a soil's stiffness and vertical pushover
    count as one; ``dynamic``; ``stored`` more are already in the store) and their estimated
    ``seconds`` of one worker, ``by_soil`` the same per soil; ``per_run`` the median estimate
    of a dynamic run; ``source`` where the rates came from; ``checks`` stored runs made by
    earlier code that are made again to check them (:mod:`..freshness`), at their own
    recorded wall times, ``check_seconds`` (included in ``seconds``); ``fits`` the
    macro-element's fits to make (one per soil, not continuum runs) and their ``fit_seconds``
    at most (included in ``seconds``)."""

    runs: int
    static: int
    dynamic: int
    stored: int
    seconds: float
    by_soil: dict
    per_run: float
    source: str
    checks: int = 0
    check_seconds: float = 0.0
    fits: int = 0
    fit_seconds: float = 0.0

    def text(self, workers: int | None = 1) -> str:
        """The estimate in one line; ``workers`` None: a Dask cluster or a caller's executor,
        whose worker count is not known here, so no wall time is divided out."""
        check = (f"; {self.checks} stored runs made by earlier code are made again first, "
                 f"{_duration(self.check_seconds)} of one worker, to check them"
                 if self.checks else "")
        if self.fits:
            check = (f"; the macro-element's fit of {self.fits} soil"
                     f"{'s' if self.fits > 1 else ''}, at most {_duration(self.fit_seconds)} "
                     f"of one worker (included){check}")
        if self.runs == 0:
            return (f"0 continuum runs to make (0 static, 0 dynamic; {self.stored} already "
                    f"stored): every run is read from the store{check}")
        soils = ", ".join(f"{k} {_duration(v)}" for k, v in self.by_soil.items())
        if workers is None:
            split = "split over the executor's workers"
        else:
            split = (f"about {_duration(self.seconds / max(1, workers))} on {workers} worker"
                     f"{'s' if workers > 1 else ''}")
        return (f"{self.runs} continuum runs to make ({self.static} static, {self.dynamic} "
                f"dynamic; {self.stored} already stored), estimated {_duration(self.seconds)} "
                f"of one worker ({soils}; {split}; a "
                f"dynamic run about {_duration(self.per_run)}; rates {self.source}){check}")


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def mesh_size(scene) -> tuple[int, float]:
    """(DOFs, shortest element edge) of the continuum mesh of ``scene``, from its grid lines
    (without meshing)."""
    from ....meshes.soil import grid_lines

    options = scene.continuum
    x, y = grid_lines(scene.foundation.width, options, scene.soil.layer_depth)
    order = 2 if options.element in ("P2", "Q2") else 1
    dofs = 2 * (order * (x.size - 1) + 1) * (order * (y.size - 1) + 1)
    return dofs, float(min(np.diff(x).min(), np.diff(y).min()))


def impedance_dofs(point: Mapping) -> int:
    """The DOFs of an impedance point's mesh (its own box), from its grid lines, without
    meshing."""
    from .impedance_points import impedance_box_scene

    return mesh_size(impedance_box_scene(point))[0]


def damping_reduction(scene, omega_max: float) -> float:
    """The factor by which the soil's Rayleigh damping of ``scene`` shortens the explicit
    stable step of a mesh whose highest circular frequency is ``omega_max`` (rad/s): 1
    without damping (module docstring)."""
    from ....continuum.dynamics.rayleigh import damped_critical, scene_rayleigh

    damping = scene_rayleigh(scene)
    if damping is None:
        return 1.0
    return damped_critical(omega_max, damping) * omega_max / 2.0


def fit_rates(runs: Sequence[tuple[int, int, float]]) -> tuple[float, float] | None:
    """(F, R): the fixed cost per DOF (s) and the cost per DOF and step (s) fitted to
    ``runs`` (dofs, steps, wall time in s) as wall = F·dofs + R·dofs·steps, by non-negative
    least squares (on the wall times themselves: a fit on relative residuals pulls the
    estimate low); None when the runs' steps do not span a factor of
    :data:`FIT_STEP_SPAN` (F and R cannot be told apart), a wall time is not positive, or the
    fit gives no per-step cost."""
    from scipy.optimize import nnls

    a = np.asarray(runs, dtype=float).reshape(-1, 3)
    if a.shape[0] < 2 or not (a[:, 2] > 0).all() or not (a[:, 1] > 0).all() \
            or a[:, 1].max() < FIT_STEP_SPAN * a[:, 1].min():
        return None
    columns = np.column_stack([a[:, 0], a[:, 0] * a[:, 1]])
    scale = np.linalg.norm(columns, axis=0)
    (F, R), _ = nnls(columns / scale, a[:, 2])
    F, R = F / scale[0], R / scale[1]
    return (float(F), float(R)) if R > 0.0 else None


def _stored_rates(stored: Iterable[Mapping]) -> tuple[dict, dict, dict]:
    """From stored dynamic records: (F, R, R_all) per (compiled, frictional) where
    :func:`fit_rates` can fit F and R, R_all the median of wall/(dofs·steps) (every second
    counted as the steps'), the median per-step rates by compiled flag at the default fixed
    cost, and the undamped steps per second of simulated time by dofs (module docstring). A
    record's soil is frictional by its ``soil_model``; a record stored before it had one was
    frictional exactly when its return map was not compiled (then only Mohr–Coulomb and
    Drucker–Prager were not)."""
    rates, density, runs = {}, {}, {}
    for rec in stored:
        dofs, steps = rec["dofs"], max(1, rec["steps"])
        compiled = bool(rec["compiled"])
        frictional = (_frictional(rec["soil_model"]) if "soil_model" in rec
                      else not compiled)
        rest = max(0.0, rec["wall_time_s"] - FIXED_SECONDS_PER_DOF[frictional] * dofs)
        rates.setdefault(compiled, []).append(rest / (dofs * steps))
        runs.setdefault((compiled, frictional), []).append((dofs, steps, rec["wall_time_s"]))
        if rec["duration"] > 0:
            undamped = steps * rec.get("dt_reduction", 1.0)
            density.setdefault(dofs, []).append(undamped / rec["duration"])
    fits = {k: (*fit, float(np.median([w / (d * s) for d, s, w in v])))
            for k, v in runs.items() if (fit := fit_rates(v)) is not None}
    return (fits, {k: float(np.median(v)) for k, v in rates.items()},
            {k: float(np.median(v)) for k, v in density.items()})


def timed_dynamic_runs(store) -> list[dict]:
    """The timed dynamic runs of today's model revision anywhere in ``store``: the rates of a grid
    none of whose own runs are stored yet (a new slice of a kept store, or the advisor's
    ladder) are this machine's rates for the other slices, not the defaults measured once on
    short pulses."""
    from ...framework.store import function_name, revisions
    from .points import evaluate_dynamic

    name, models = function_name(evaluate_dynamic), revisions(evaluate_dynamic)
    entries = (store.entry(key) for key in store.keys())
    return [e["record"] for e in entries
            if e is not None and e.get("function") == name and e.get("models") == models
            and isinstance(e["record"], dict) and "error" not in e["record"]]


def estimate_cost(static: Sequence[tuple[str, object, bool]],
                  dynamic: Sequence[tuple[str, object, float, bool]],
                  stored_static: Sequence[Mapping], stored_dynamic: Sequence[Mapping],
                  impedance: Sequence[tuple[str, int, int, bool]] = (),
                  stored_impedance: Sequence[Mapping] = ()) -> Estimate:
    """The cost of the runs not yet stored.

    ``static``: (soil, scene, stored[, factor]) per static run, the scene of its soil and mesh
    (a soil's stiffness and vertical pushover count as one static run; ``factor`` scales that
    pair's cost for another static run, e.g. a rotation pushover's steps over the vertical
    pushover's); ``dynamic``: (soil, scene, duration in s, stored) per dynamic point;
    ``impedance``: (soil, DOFs of its mesh, frequencies, stored) per soil whose impedance a bed
    needs (one static run each); ``stored_static`` ({dofs, wall_time_s} of each soil's stored
    pair), ``stored_dynamic`` (stored dynamic records) and ``stored_impedance`` (stored
    impedance records): their timings replace the default rates.
    """
    from ....continuum.dynamics.run import wave_speeds
    from ....continuum.dynamics.explicit import COURANT_ESTIMATE

    fits, rates, density = _stored_rates(stored_dynamic)
    static_rate = (float(np.median([r["wall_time_s"] / r["dofs"] for r in stored_static]))
                   if stored_static else STATIC_SECONDS_PER_DOF)
    impedance_rate = (float(np.median([r["wall_time_s"] / (r["dofs"] * len(r["a0"]))
                                       for r in stored_impedance]))
                      if stored_impedance else IMPEDANCE_SECONDS_PER_DOF_FREQUENCY)
    by_soil, per_run, n_static, n_dynamic, stored = {}, [], 0, 0, 0
    for soil, scene, done, *factor in static:
        by_soil.setdefault(soil, 0.0)
        if done:
            stored += 1
            continue
        by_soil[soil] += static_rate * mesh_size(scene)[0] * (factor[0] if factor else 1.0)
        n_static += 1
    for soil, dofs, frequencies, done in impedance:
        by_soil.setdefault(soil, 0.0)
        if done:
            stored += 1
            continue
        by_soil[soil] += impedance_rate * dofs * frequencies
        n_static += 1
    for soil, scene, duration, done in dynamic:
        by_soil.setdefault(soil, 0.0)
        if done:
            stored += 1
            continue
        dofs, h_min = mesh_size(scene)
        compiled = compiled_soil_model(scene.soil.model)
        frictional = scene.soil.frictional
        undamped = density.get(dofs) or wave_speeds(scene.soil)[0] / (COURANT_ESTIMATE * h_min)
        per_second = undamped / damping_reduction(scene, 2.0 * undamped)
        steps = math.ceil(duration * per_second)
        if (compiled, frictional) in fits:  # never below every second counted as steps'
            fixed, rate, whole = fits[compiled, frictional]
            cost = max(fixed * dofs + rate * dofs * steps, whole * dofs * steps)
        else:
            rate = rates.get(compiled, SECONDS_PER_DOF_STEP[compiled])
            cost = FIXED_SECONDS_PER_DOF[frictional] * dofs + rate * dofs * steps
        per_run.append(cost)
        by_soil[soil] += cost
        n_dynamic += 1
    kinds = {True: "compiled", False: "fallback"}
    fitted = {k for k, _ in fits}
    source = ", ".join(f"{kinds[k]} return map: "
                       + ("the stored runs' (fixed part fitted)" if k in fitted
                          else "the stored runs'" if k in rates else "default") for k in kinds)
    return Estimate(n_static + n_dynamic, n_static, n_dynamic, stored, sum(by_soil.values()),
                    by_soil, float(np.median(per_run)) if per_run else 0.0, source)


def refuse_over_budget(estimate: Estimate, budget: float | None) -> None:
    """Refuse (one :class:`InputError` line) a run whose estimate exceeds ``budget`` (s)."""
    if budget is not None and estimate.seconds > budget:
        raise InputError(f"options.budget = {budget:g} s: the map's {estimate.runs} continuum "
                         f"runs not yet stored ({estimate.stored} are) are estimated at "
                         f"{estimate.seconds:.0f} s; valid range is "
                         f"[{estimate.seconds:.0f}, ...) s for this grid, or a smaller grid")


def with_checks(estimate: Estimate, store, keyed: Iterable[tuple[str, object]]) -> Estimate:
    """``estimate`` with the cost of checking the stale ones of the stored records ``keyed``
    ((key, point function) pairs): per function, :data:`..freshness.DEFAULT_SAMPLE` of them
    made again, each at the median wall time its stale records took to make."""
    from ...framework.freshness import DEFAULT_SAMPLE
    from ...framework.store import function_name

    walls: dict[str, list[float]] = {}
    for key, function in keyed:
        entry = store.entry(key)
        if entry is not None and not store.is_fresh(entry):
            record = entry["record"]
            wall = record.get("wall_time_s", 0.0) if isinstance(record, Mapping) else 0.0
            walls.setdefault(function_name(function), []).append(float(wall))
    checks = sum(min(DEFAULT_SAMPLE, len(w)) for w in walls.values())
    seconds = sum(min(DEFAULT_SAMPLE, len(w)) * float(np.median(w)) for w in walls.values())
    return replace(estimate, checks=checks, check_seconds=seconds,
                   seconds=estimate.seconds + seconds)
