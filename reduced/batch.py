"""Many scenes through the reduced model at once: their peaks only, in parallel.

:func:`run_batch` integrates each scene exactly as :func:`~.run.run` with ``histories=False``
would (same model, motion, step and kernel), but keeps only a row of peak values per scene and
skips what a single run spends around its integration: histories, provenance, a
:class:`~.response.Response`. Chunks of scenes go to a pool of processes, or to a Dask cluster
(``scheduler``: an address, a cluster or a ``distributed.Client``), :mod:`.batch_chunks`;
warnings a run raises on a worker are raised again in the caller, naming the run. The result
is also a :class:`pandas.DataFrame` (:meth:`BatchResult.to_dataframe`: one row per run, the
columns' units in its ``attrs``). Ctrl-C ends the batch with :class:`BatchInterrupted`, one
line with the call that resumes it (``resume=``), holding the finished runs.

Every scene is checked first — its model, its motion, its step against the stability limit — so
that bad input in any scene raises before any scene is integrated. A scene that the integrator
gives up on (chattering, divergence, Newton failure) gets a nonzero ``status`` and NaN values;
the other scenes are unaffected.
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from .. import __version__
from ..checks import InputError
from ..motions import Motion
from ..scenes import MotionSpec, Scene, build_motion
from . import kernels as kn
from .batch_chunks import COLUMNS, ENERGY, NOT_RUN, STATUS_NAMES, execute, rewarn
from .batch_table import BatchInterrupted, BatchTable
from .integrators import StepPlan, method
from .model import build_model
from .run import KernelInputs, initial_base_state, initial_conditions, plan_run

__all__ = ["BatchResult", "BatchInterrupted", "run_batch", "STATUS_NAMES", "COLUMNS", "NOT_RUN",
           "ENERGY"]



@dataclass(frozen=True, eq=False)
class BatchResult(BatchTable):
    """One row per scene, in the order given (units of each scene).

    ``u`` peak superstructure deformation, ``theta`` peak base rotation, ``uplift_left`` peak
    gap under the leftmost foundation spring, ``weighted_plastic_settlement`` Σkε_p/Σk at the
    end (down positive: :func:`~.peak_slots.weighted_plastic_settlement`; on a macro-element,
    ``uplift_left`` is the peak gap under the footing's left edge and
    ``weighted_plastic_settlement`` its plastic settlement v_p at the end),
    ``final_vertical_position`` V at the end (up positive) (these three NaN without a
    foundation; a batch keeps the ends of each run only, so it cannot tell whether a run ended
    at rest and has no residual settlement), ``base_shear`` peak base shear,
    ``energy_balance_error`` as
    :attr:`~.response.Response.energy_balance_error` over the first and last states, ``dt`` the
    step taken (s), ``status`` 0 when the run finished (:data:`STATUS_NAMES`): an overturned
    structure keeps its peaks up to the toppling; a failed run, or one whose energy balance is
    beyond its ``analysis.energy_tolerance`` (:data:`ENERGY`), has NaN values, and one that an
    interruption left undone has :data:`NOT_RUN`. ``names``, ``cases``, ``overrides`` and
    ``units`` (name, length, force) describe each scene; ``info`` holds the integrator, the
    pool or scheduler, the wall time and the package version. :meth:`to_dataframe` gives the
    table as a :class:`pandas.DataFrame`.
    """

    u: np.ndarray
    theta: np.ndarray
    uplift_left: np.ndarray
    weighted_plastic_settlement: np.ndarray
    final_vertical_position: np.ndarray
    base_shear: np.ndarray
    energy_balance_error: np.ndarray
    dt: np.ndarray
    status: np.ndarray
    names: tuple[str, ...] = ()
    info: dict = field(default_factory=dict)
    cases: tuple = ()
    overrides: tuple[tuple[str, ...], ...] = ()
    units: tuple[tuple[str, str, str], ...] = ()

    def __len__(self) -> int:
        return self.status.size

    @property
    def ok(self) -> np.ndarray:
        """True where the run finished."""
        return self.status == kn.OK

    def row(self, i: int) -> dict:
        """Scene i's values by column name (and its status name)."""
        out = {name: float(getattr(self, name)[i]) for name in COLUMNS}
        out["status"] = STATUS_NAMES.get(int(self.status[i]), str(int(self.status[i])))
        return out

    def columns(self) -> dict[str, np.ndarray]:
        """Every column, by name."""
        return {name: getattr(self, name) for name in COLUMNS + ("status",)}


@dataclass(frozen=True, eq=False)
class _Job:
    """One scene, ready for the kernel: everything but its ground motion's samples."""

    name: str            # integrator
    inputs: KernelInputs
    plan: StepPlan
    q0: np.ndarray
    qd0: np.ndarray
    motion: int          # index of its base motion in the batch
    factor: float | None  # scale on the base motion (None: taken as it is)
    samples: int         # samples after padding to the analysis duration
    dtg: float
    g: float
    leftmost: int        # spring index of the leftmost foundation spring (−1: none)
    energy_tolerance: float
    exact: bool
    element: bool = False  # the base is one element (the macro-element), not springs


def run_batch(scenes: Sequence[Scene], motion: Motion | None = None, *,
              integrator: str | None = "events", dt: float | None = None,
              workers: int | None = None, chunk: int | None = None, scheduler=None,
              resume: BatchResult | None = None) -> BatchResult:
    """Integrate every scene and return its peaks; the same numbers as
    ``run(scene, motion=motion, integrator=integrator, dt=dt, histories=False).peaks``.

    ``motion`` replaces every scene's own motion; ``integrator`` None takes each scene's;
    ``dt`` None takes each scene's step (``analysis.dt``, else the automatic one). ``workers``
    processes (default: the CPU count; 1 runs in this process), each given ``chunk`` scenes
    at a time (default: enough chunks for eight per worker, at most 200 scenes each); or the
    Dask cluster ``scheduler`` (an address, a cluster or a ``distributed.Client``; the extra
    ``dask``). Warnings raised by a run on a worker are raised again here, naming the run.
    ``resume``: the partial result of an interrupted batch of the same scenes
    (:class:`BatchInterrupted`'s ``partial``): only the runs it lacks are integrated.
    Raises :class:`~upliftlab.checks.InputError`, naming the scene, before any integration if
    any scene cannot be run; an interruption (Ctrl-C) raises :class:`BatchInterrupted`, one
    line with the command that resumes the batch, holding the finished runs.
    """
    start = time.perf_counter()
    scenes = list(scenes)
    workers = _count("workers", os.cpu_count() or 1 if workers is None else workers)
    jobs, motions, names = _prepare(scenes, motion, integrator, dt)
    rows, status = _resumed(resume, names)
    todo = [i for i in range(len(jobs)) if status[i] == NOT_RUN]
    if chunk is None:
        chunk = max(1, min(200, math.ceil(len(todo) / (8 * workers))))
    chunk = _count("chunk", chunk)
    pieces = [[jobs[i] for i in todo[k:k + chunk]] for k in range(0, len(todo), chunk)]
    where = {k: todo[k * chunk:(k + 1) * chunk] for k in range(len(pieces))}
    meta = {"names": tuple(names), "cases": tuple(s.case for s in scenes),
            "overrides": tuple(tuple(s.overrides) for s in scenes),
            "units": tuple((s.units.name, s.units.length, s.units.force) for s in scenes)}
    info = {"integrator": integrator or "per scene", "workers": workers, "chunk": chunk,
            "scenes": len(jobs), "scheduler": None if scheduler is None else str(
                getattr(scheduler, "scheduler_address", scheduler)),
            "version": __version__, "created": time.strftime("%Y-%m-%dT%H:%M:%S%z")}
    runs = execute(pieces, motions, workers, scheduler)
    try:
        for k, (values, codes, caught) in runs:
            rows[where[k]], status[where[k]] = values, codes
            rewarn(caught, names, where[k])
    except KeyboardInterrupt as exc:
        runs.close()  # every worker ended before the line is printed
        partial = BatchResult(*rows.T, status=status, info=info, **meta)
        raise BatchInterrupted(partial, str(exc) or "Ctrl-C") from None
    finally:
        runs.close()
    info["wall_time_s"] = time.perf_counter() - start
    return BatchResult(*rows.T, status=status, info=info, **meta)


def _resumed(resume, names) -> tuple[np.ndarray, np.ndarray]:
    """(rows, statuses) to start from: all NOT_RUN, or the finished runs of ``resume``."""
    rows = np.full((len(names), len(COLUMNS)), np.nan)
    status = np.full(len(names), NOT_RUN, np.int64)
    if resume is None:
        return rows, status
    if not isinstance(resume, BatchResult) or tuple(resume.names) != tuple(names):
        raise InputError(f"resume = {type(resume).__name__}: expected the partial result of "
                         f"an interrupted batch of the same {len(names)} scenes "
                         "(BatchInterrupted.partial)")
    return np.array([resume.columns()[c] for c in COLUMNS], float).T.copy(), \
        resume.status.copy()


def _count(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise InputError(f"{name} = {value!r}: expected a whole number >= 1")
    return int(value)


# ---------------------------------------------------------------------------------------------
# Preparation: every check a single run makes, for every scene, before any integration
# ---------------------------------------------------------------------------------------------


def _prepare(scenes, motion, integrator, dt):
    if integrator is not None:
        method(integrator)
    if dt is not None and not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
        raise InputError(f"dt = {dt!r}: expected a step > 0 (s), or None for each scene's own")
    bases: dict = {}      # base motion key -> index
    motions: list = []    # index -> (Motion, its samples)
    jobs, names, errors = [], [], []
    for i, scene in enumerate(scenes):
        if not isinstance(scene, Scene):
            raise InputError(f"scene {i}: expected a Scene (upliftlab.load_scene), "
                             f"got {type(scene).__name__}")
        try:
            jobs.append(_job(scene, motion, integrator, dt, bases, motions))
        except InputError as exc:
            errors.append(f"scene {i} ({scene.name}): {exc}")
        names.append(scene.name)
    if errors:
        more = f" (and {len(errors) - 3} more)" if len(errors) > 3 else ""
        raise InputError(f"{len(errors)} of {len(scenes)} scenes cannot be run; nothing was "
                         f"integrated: " + "; ".join(errors[:3]) + more)
    return jobs, [m.acceleration for m in motions], names


def _job(scene: Scene, motion, integrator, dt, bases, motions) -> _Job:
    """The run of one scene, as :func:`~.run.run_model` sets it up (histories off)."""
    model = build_model(scene)
    index, factor, motion = _base_motion(scene, motion, bases, motions)
    a = scene.analysis
    name = integrator or a.integrator
    duration = a.duration or motion.duration
    plan, _ = plan_run(model, motion, name, dt=dt, histories=False)
    q0, qd0 = initial_conditions(model, motion)
    samples = max(motion.acceleration.size, math.ceil(duration / motion.dt - 1e-9))
    found = model.foundation_slice
    leftmost = (model.foundation_start + int(np.argmin(model.params["x"][found]))
                if model.layout is not None and model.base is None else -1)
    inputs = KernelInputs.of(model, plan, base_state=initial_base_state(model, motion, q0))
    return _Job(name, inputs, plan, q0, qd0, index, factor, samples, motion.dt, model.g,
                leftmost, a.energy_tolerance, model.exact, model.base is not None)


def _base_motion(scene: Scene, motion: Motion | None, bases: dict, motions: list):
    """(index of the scene's base motion, the factor on it, the base motion).

    A record is read once per file, step and duration; each scene's ``scale`` or ``pga`` is a
    factor on it, applied as :func:`~upliftlab.scenes.build_motion` applies it. Other motions
    (given, free vibration, pulses) are taken as they are.
    """
    spec = scene.motion
    if motion is not None:
        key = ("given",)
    elif spec.type == "record":
        key = ("record", spec.name, spec.dt, spec.duration)
    else:
        key = ("spec", spec)
    if key not in bases:
        if motion is not None:
            base = motion
        elif spec.type == "record":
            base = build_motion(MotionSpec(type="record", name=spec.name, dt=spec.dt,
                                           duration=spec.duration))
        else:
            base = build_motion(spec)
        bases[key] = len(motions)
        motions.append(base)
    index = bases[key]
    base = motions[index]
    factor = None
    if motion is None and spec.type == "record":
        if spec.pga is not None:
            if base.pga == 0.0:
                base.scaled_to_pga(spec.pga)  # raises, naming the motion
            factor = spec.pga / base.pga
        else:
            factor = spec.scale
    return index, factor, base
