"""Where the chunks of a reduced batch (:func:`~.batch.run_batch`) are integrated: in this
process, on a pool of local processes, or on a Dask cluster; and what a chunk brings back.

A chunk returns its rows of peak values, their statuses and the warnings its runs raised
(caught in the worker, each with the run that raised it, and raised again in the caller by
:func:`rewarn`, naming the run): a warning raised on a worker process or a Dask worker would
otherwise be printed there, or nowhere, and never reach the user. Chunks come back as they
finish (:func:`execute` yields each with its index), so that an interruption keeps every
finished one.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import math
import warnings

import numpy as np

from ..checks import InputError, scheduler_address
from ..workers import process_pool
from . import kernels as kn
from .peak_slots import decode_peaks, static_energy, weighted_plastic_settlement
from .response import ENERGY_NAMES, energy_balance_error
from .run import ground_acceleration, integrate

__all__ = ["COLUMNS", "ENERGY", "NOT_RUN", "STATUS_NAMES", "execute", "run_chunk", "rewarn",
           "dask_client"]

#: A run that finished with its energy balance beyond ``analysis.energy_tolerance``, or whose
#: macro-element did negative plastic work beyond it (a single run refuses both alike).
ENERGY = 100
#: A run that an interruption left undone (:class:`~.batch.BatchInterrupted`).
NOT_RUN = 101
STATUS_NAMES = {kn.OK: "ok", kn.CHATTER: "chattering", kn.NONFINITE: "non-finite state",
                kn.NO_CONVERGENCE: "Newton did not converge", kn.OVERTURNED: "overturned",
                kn.STEP_UNDERFLOW: "step underflow", ENERGY: "energy balance beyond tolerance",
                kn.BASE_FAILED: "macro-element step failed",
                NOT_RUN: "not run (interrupted)"}
COLUMNS = ("u", "theta", "uplift_left", "weighted_plastic_settlement",
           "final_vertical_position", "base_shear", "energy_balance_error", "dt")
#: The columns defined only with a foundation of springs.
FOUNDATION_COLUMNS = ("uplift_left", "weighted_plastic_settlement", "final_vertical_position")


def dask_client(scheduler):
    """(client, owned): a ``distributed.Client`` for ``scheduler``, an address (checked as
    one: :func:`upliftlab.checks.scheduler_address`), a cluster or a client (owned False:
    the caller's to close)."""
    if hasattr(scheduler, "submit") and hasattr(scheduler, "gather"):
        return scheduler, False
    address = getattr(scheduler, "scheduler_address", scheduler)
    address = scheduler_address("scheduler", address)
    try:
        import distributed
    except ImportError:
        raise InputError(f"scheduler = {address!r}: running a batch on a Dask cluster needs "
                         "the optional dependency dask[distributed] (pip install "
                         "'upliftlab[dask]'), or give no scheduler") from None
    return distributed.Client(address), True


def execute(pieces, motions, workers, scheduler=None):
    """Each chunk of ``pieces`` integrated, as ``(index, (values, statuses, warnings))`` in
    the order they finish: on the Dask cluster ``scheduler`` if given, else in this process
    (``workers`` 1 or one chunk) or on ``workers`` local processes, every one of which ends
    with the generator (:func:`upliftlab.workers.process_pool`), also when it is closed by an
    interruption."""
    args = [(piece, [motions[i] for i in _used(piece)], _used(piece)) for piece in pieces]
    if scheduler is not None:
        yield from _on_dask(args, scheduler)
    elif workers == 1 or len(pieces) <= 1:
        for k, a in enumerate(args):
            yield k, run_chunk(*a)
    else:
        with process_pool(min(workers, len(pieces))) as pool:
            futures = {pool.submit(run_chunk, *a): k for k, a in enumerate(args)}
            for future in cf.as_completed(futures):
                yield futures[future], future.result()


def _on_dask(args, scheduler):
    from distributed import as_completed

    client, owned = dask_client(scheduler)
    futures = {}
    try:
        futures = {client.submit(run_chunk, *a, pure=False): k for k, a in enumerate(args)}
        for future in as_completed(list(futures)):
            yield futures[future], future.result()
    finally:
        unfinished = [f for f in futures if not f.done()]
        if unfinished:
            with contextlib.suppress(Exception):
                client.cancel(unfinished)
        if owned:
            client.close()


def rewarn(caught, names, indices, stacklevel: int = 3) -> None:
    """Raise again in the caller the ``caught`` warnings of a chunk whose runs are runs
    ``indices`` of the batch, each naming its run: ``run 7 (scene name): message``."""
    for r, category, message in caught:
        i = indices[r]
        warnings.warn(f"run {i} ({names[i]}): {message}", category, stacklevel=stacklevel)


def _used(piece) -> list[int]:
    return sorted({job.motion for job in piece})


def run_chunk(piece, accelerations, indices):
    """Integrate a chunk of jobs: their values (rows × COLUMNS), statuses, and the warnings
    each run raised, as ``(row, category, message)``."""
    base = dict(zip(indices, accelerations))
    values = np.full((len(piece), len(COLUMNS)), np.nan)
    codes = np.zeros(len(piece), np.int64)
    caught = []
    for r, job in enumerate(piece):
        with warnings.catch_warnings(record=True) as records:
            warnings.simplefilter("always")
            codes[r], values[r] = _run_job(job, base[job.motion])
        caught.extend((r, w.category, str(w.message)) for w in records)
    return values, codes, caught


def _run_job(job, acceleration) -> tuple[int, np.ndarray]:
    """One job's status and row (NaN unless it finished)."""
    values = np.full(len(COLUMNS), np.nan)
    code, out, counters = integrate(job.inputs, job.name, job.plan, job.q0, job.qd0,
                                    _samples(job, acceleration), job.dtg, impacts=False)
    if code in (kn.OK, kn.OVERTURNED):
        row = _row(job, out)
        defined = [v for v, name in zip(row, COLUMNS) if job.leftmost >= 0 or job.element
                   or name not in FOUNDATION_COLUMNS]
        if not row[COLUMNS.index("energy_balance_error")] <= job.energy_tolerance:
            code = ENERGY
        elif job.element and not out["base_negative_work"] <= job.energy_tolerance * max(
                float(np.max(np.abs(out["energy"][:, ENERGY_NAMES.index("input")]),
                             initial=0.0)),
                _static(job), 1e-300):
            code = ENERGY
        elif np.all(np.isfinite(defined)):
            values[:] = row
        else:
            code = kn.NONFINITE
    return code, values


def _samples(job, acceleration: np.ndarray) -> np.ndarray:
    """The kernel's ground acceleration for a job: its base motion scaled (as
    :meth:`~upliftlab.motions.Motion.scaled`), padded (as ``extended``), in length/s²."""
    acc = acceleration * job.factor if job.factor is not None else acceleration
    if job.samples > acc.size:
        acc = np.concatenate([acc, np.zeros(job.samples - acc.size)])
    return ground_acceleration(acc, job.g)


def _static(job) -> float:
    """The scale floor of a job's energy balance: its bed's (and its base element's) strain
    energy at rest (:func:`~.peak_slots.static_energy`)."""
    base = job.inputs.base
    rest = float(base[6][kn.C_E0]) if base[0].size else 0.0
    return static_energy(job.inputs.params) + rest


def _row(job, out: dict) -> list[float]:
    """The values of :attr:`~.response.Response.peaks` that the batch keeps, from the same
    arrays (the first and last states, the tracked peaks)."""
    inputs = job.inputs
    static = _static(job)
    pk = decode_peaks(out["raw_peaks"], stories=inputs.stories, rocks=inputs.theta >= 0,
                      settles=inputs.v >= 0, exact=job.exact, static=static)
    u, theta, shear = pk.u, pk.theta, pk.base_shear
    uplift = settlement = final_v = math.nan
    if job.leftmost >= 0:
        uplift = max(float(pk.opening[job.leftmost]), 0.0)
        settlement = weighted_plastic_settlement(inputs.params, out["plastic"][-1])
        final_v = float(out["q"][-1, inputs.v])
    elif job.element:  # its left edge's gap, its plastic settlement v_p (:mod:`.kernels.base`)
        uplift = pk.base_gap_left
        settlement = float(out["base"][-1, 3])
        final_v = float(out["q"][-1, inputs.v])
    energy = max(energy_balance_error(out["energy"], static), pk.energy_residual)
    return [u, theta, uplift, settlement, final_v, shear, energy, job.plan.dt]
