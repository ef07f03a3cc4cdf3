"""Many scenes through the reduced model at once: their peaks only, in parallel.

:func:`run_batch` integrates each scene exactly as :func:`~.run.run` with ``histories=False``
would (same model, motion, step and kernel), but keeps only a row of peak values per scene and
skips what a single run spends around its integration: histories, provenance, a
:class:`~.response.Response`. Chunks of scenes go to a pool of processes.

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
from ..workers import process_pool
from . import kernels as kn
from .integrators import StepPlan, method
from .model import build_model
from .peak_slots import decode_peaks, static_energy, weighted_plastic_settlement
from .response import energy_balance_error
from .run import KernelInputs, ground_acceleration, initial_conditions, integrate, plan_run

__all__ = ["BatchResult", "run_batch", "STATUS_NAMES", "COLUMNS"]

#: A run that finished with its energy balance beyond ``analysis.energy_tolerance``.
ENERGY = 100
STATUS_NAMES = {kn.OK: "ok", kn.CHATTER: "chattering", kn.NONFINITE: "non-finite state",
                kn.NO_CONVERGENCE: "Newton did not converge", kn.OVERTURNED: "overturned",
                kn.STEP_UNDERFLOW: "step underflow", ENERGY: "energy balance beyond tolerance"}
COLUMNS = ("u", "theta", "uplift_left", "weighted_plastic_settlement",
           "final_vertical_position", "base_shear", "energy_balance_error", "dt")
#: The columns defined only with a foundation of springs.
_FOUNDATION_COLUMNS = ("uplift_left", "weighted_plastic_settlement", "final_vertical_position")


@dataclass(frozen=True, eq=False)
class BatchResult:
    """One row per scene, in the order given (units of each scene).

    ``u`` peak superstructure deformation, ``theta`` peak base rotation, ``uplift_left`` peak
    gap under the leftmost foundation spring, ``weighted_plastic_settlement`` Σkε_p/Σk at the
    end (down positive: :func:`~.peak_slots.weighted_plastic_settlement`),
    ``final_vertical_position`` V at the end (up positive) (these three NaN without a
    foundation; a batch keeps the ends of each run only, so it cannot tell whether a run ended
    at rest and has no residual settlement), ``base_shear`` peak base shear,
    ``energy_balance_error`` as
    :attr:`~.response.Response.energy_balance_error` over the first and last states, ``dt`` the
    step taken (s), ``status`` 0 when the run finished (:data:`STATUS_NAMES`): an overturned
    structure keeps its peaks up to the toppling; a failed run, or one whose energy balance is
    beyond its ``analysis.energy_tolerance`` (:data:`ENERGY`), has NaN values. ``info`` holds
    the integrator, the pool, the wall time and the package version.
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


def run_batch(scenes: Sequence[Scene], motion: Motion | None = None, *,
              integrator: str | None = "events", dt: float | None = None,
              workers: int | None = None, chunk: int | None = None) -> BatchResult:
    """Integrate every scene and return its peaks; the same numbers as
    ``run(scene, motion=motion, integrator=integrator, dt=dt, histories=False).peaks``.

    ``motion`` replaces every scene's own motion; ``integrator`` None takes each scene's;
    ``dt`` None takes each scene's step (``analysis.dt``, else the automatic one). ``workers``
    processes (default: the CPU count; 1 runs in this process), each given ``chunk`` scenes
    at a time (default: enough chunks for eight per worker, at most 200 scenes each).
    Raises :class:`~upliftlab.checks.InputError`, naming the scene, before any integration if
    any scene cannot be run.
    """
    start = time.perf_counter()
    scenes = list(scenes)
    workers = _count("workers", os.cpu_count() or 1 if workers is None else workers)
    jobs, motions, names = _prepare(scenes, motion, integrator, dt)
    if chunk is None:
        chunk = max(1, min(200, math.ceil(len(jobs) / (8 * workers))))
    chunk = _count("chunk", chunk)
    pieces = [jobs[i:i + chunk] for i in range(0, len(jobs), chunk)]
    rows = np.full((len(jobs), len(COLUMNS)), np.nan)
    status = np.zeros(len(jobs), np.int64)
    for k, (values, codes) in enumerate(_execute(pieces, motions, workers)):
        rows[k * chunk:k * chunk + len(codes)] = values
        status[k * chunk:k * chunk + len(codes)] = codes
    info = {"integrator": integrator or "per scene", "workers": workers, "chunk": chunk,
            "scenes": len(jobs), "wall_time_s": time.perf_counter() - start,
            "version": __version__, "created": time.strftime("%Y-%m-%dT%H:%M:%S%z")}
    return BatchResult(*rows.T, status=status, names=tuple(names), info=info)


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
                if model.layout is not None else -1)
    return _Job(name, KernelInputs.of(model, plan), plan, q0, qd0, index, factor, samples,
                motion.dt, model.g, leftmost, a.energy_tolerance, model.exact)


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


# ---------------------------------------------------------------------------------------------
# Execution
# ---------------------------------------------------------------------------------------------


def _execute(pieces, motions, workers):
    """Each chunk's (values, statuses), in order: in this process or on a pool."""
    if workers == 1 or len(pieces) <= 1:
        for piece in pieces:
            yield _run_chunk(piece, [motions[i] for i in _used(piece)], _used(piece))
        return
    with process_pool(min(workers, len(pieces))) as pool:  # ends every worker on the way out
        futures = [pool.submit(_run_chunk, piece, [motions[i] for i in _used(piece)],
                               _used(piece)) for piece in pieces]
        for future in futures:
            yield future.result()


def _used(piece) -> list[int]:
    return sorted({job.motion for job in piece})


def _run_chunk(piece, accelerations, indices):
    """Integrate a chunk of jobs; their values (rows × COLUMNS) and statuses."""
    base = dict(zip(indices, accelerations))
    values = np.full((len(piece), len(COLUMNS)), np.nan)
    codes = np.zeros(len(piece), np.int64)
    for r, job in enumerate(piece):
        codes[r], out, counters = integrate(job.inputs, job.name, job.plan, job.q0, job.qd0,
                                            _samples(job, base[job.motion]), job.dtg,
                                            impacts=False)
        if codes[r] in (kn.OK, kn.OVERTURNED):
            row = _row(job, out)
            defined = [v for v, name in zip(row, COLUMNS) if job.leftmost >= 0
                       or name not in _FOUNDATION_COLUMNS]
            if not row[COLUMNS.index("energy_balance_error")] <= job.energy_tolerance:
                codes[r] = ENERGY
            elif np.all(np.isfinite(defined)):
                values[r] = row
            else:
                codes[r] = kn.NONFINITE
    return values, codes


def _samples(job: _Job, acceleration: np.ndarray) -> np.ndarray:
    """The kernel's ground acceleration for a job: its base motion scaled (as
    :meth:`~upliftlab.motions.Motion.scaled`), padded (as ``extended``), in length/s²."""
    acc = acceleration * job.factor if job.factor is not None else acceleration
    if job.samples > acc.size:
        acc = np.concatenate([acc, np.zeros(job.samples - acc.size)])
    return ground_acceleration(acc, job.g)


def _row(job: _Job, out: dict) -> list[float]:
    """The values of :attr:`~.response.Response.peaks` that the batch keeps, from the same
    arrays (the first and last states, the tracked peaks)."""
    inputs = job.inputs
    static = static_energy(inputs.params)
    pk = decode_peaks(out["raw_peaks"], stories=inputs.stories, rocks=inputs.theta >= 0,
                      settles=inputs.v >= 0, exact=job.exact, static=static)
    u, theta, shear = pk.u, pk.theta, pk.base_shear
    uplift = settlement = final_v = math.nan
    if job.leftmost >= 0:
        uplift = max(float(pk.opening[job.leftmost]), 0.0)
        settlement = weighted_plastic_settlement(inputs.params, out["plastic"][-1])
        final_v = float(out["q"][-1, inputs.v])
    energy = max(energy_balance_error(out["energy"], static), pk.energy_residual)
    return [u, theta, uplift, settlement, final_v, shear, energy, job.plan.dt]
