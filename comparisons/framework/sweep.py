"""Parameter sweeps: evaluate a function at many points, in parallel, resumably.

:func:`run_sweep` evaluates ``function(point) -> record`` at every point that is not already in
the :class:`~.store.Store`, in chunks (one task evaluates several points, so that the cost of a
task is amortised over many millisecond runs of the reduced model), on

* local processes (default): a ``ProcessPoolExecutor`` with one worker per CPU, started with
  ``spawn`` and ``OMP_NUM_THREADS=1`` (and the MKL/OpenBLAS equivalents) in the workers, all
  ended with the sweep, also when it is interrupted (:func:`upliftlab.workers.process_pool`);
* a Dask cluster, when ``scheduler`` or ``DASK_SCHEDULER_ADDRESS`` gives its address
  (``distributed.Client(address).get_executor()``; Dask is the optional extra ``dask``);
* any ``concurrent.futures`` executor passed as ``executor``.

Workers write each finished point to the store as soon as it is done (``write_through``), so an
interrupted sweep (Ctrl-C, a failing point, a killed job) loses no finished point, and running it
again computes only what is missing. On a Dask cluster, whose workers may not share the file
system, records are stored by the caller when their chunk returns: an interruption then loses
at most the unfinished chunks.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import math
import os
import sys
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

from ...checks import InputError, integer_at_least, scheduler_address
from ...workers import PARENT_POLL, SINGLE_THREAD_ENVIRONMENT, process_pool, watch_parent
from .freshness import DEFAULT_SAMPLE, check_stale
from .sweep_bar import sweep_report
from .store import Store, function_name, plain_params, point_key, record_meta

__all__ = ["run_sweep", "sweep_executor", "SweepProgress", "StderrProgress",
           "SINGLE_THREAD_ENVIRONMENT", "DASK_ENV", "PARENT_POLL", "watch_parent"]

DASK_ENV = "DASK_SCHEDULER_ADDRESS"
MAX_CHUNK = 16
TASKS_PER_WORKER = 4


@dataclass(frozen=True)
class SweepProgress:
    """Where a sweep stands: ``done`` of ``total`` points stored (``computed`` of them in this
    call), ``elapsed`` wall time (s)."""

    study: str
    done: int
    total: int
    computed: int
    elapsed: float

    @property
    def remaining_seconds(self) -> float:
        """Linear estimate of the time left (s); inf before the first computed point."""
        if self.computed == 0:
            return math.inf
        return self.elapsed / self.computed * (self.total - self.done)


class StderrProgress:
    """Print a progress line on stderr every ``every`` seconds once a sweep has run ``after``
    seconds, and a last line when a long sweep ends. Short sweeps print nothing."""

    def __init__(self, every: float = 10.0, after: float = 5.0, stream=None):
        self.every, self.after, self.stream = every, after, stream
        self._last = -math.inf

    def __call__(self, p: SweepProgress) -> None:
        finished = p.done == p.total
        due = p.elapsed - self._last >= self.every
        if p.elapsed < self.after or not (due or finished):
            return
        self._last = p.elapsed
        left = p.remaining_seconds
        eta = "" if finished or not math.isfinite(left) else f", about {left:.0f} s left"
        print(f"{p.study}: {p.done}/{p.total} points ({100.0 * p.done / p.total:.0f} %), "
              f"{p.elapsed:.0f} s{eta}", file=self.stream or sys.stderr, flush=True)


def _evaluate_chunk(function, items, store_root, meta, batched):
    """One task: evaluate ``items`` [(key, point)], storing each record if ``store_root``."""
    store = Store(store_root) if store_root is not None else None
    if batched:
        records = list(function([point for _, point in items]))
        if len(records) != len(items):
            raise ValueError(f"{meta['function']}: returned {len(records)} records for "
                             f"{len(items)} points")
    out = []
    for i, (key, point) in enumerate(items):
        record = records[i] if batched else function(point)
        if store is not None:
            store.put(key, record, {**meta, "params": plain_params(point)})
        out.append((key, record))
    return out


def _address(scheduler):
    """The scheduler given (an address is checked as one, before any work), else the
    address of ``DASK_SCHEDULER_ADDRESS`` (checked likewise), else None."""
    if scheduler is None:
        env = os.environ.get(DASK_ENV) or None
        return None if env is None else scheduler_address(DASK_ENV, env)
    return scheduler_address("scheduler", scheduler) if isinstance(scheduler, str) else scheduler


def _dask_client(scheduler):
    """(client, owned): a ``distributed.Client`` for an address, cluster or client."""
    if hasattr(scheduler, "get_executor"):
        return scheduler, False
    address = getattr(scheduler, "scheduler_address", scheduler)
    try:
        import distributed
    except ImportError:
        raise InputError(f"scheduler = {address!r}: running a sweep on a Dask cluster needs "
                         "the optional dependency dask[distributed] (pip install "
                         "'upliftlab[dask]'), or unset the scheduler to run on local "
                         "processes") from None
    if not isinstance(address, str) or not address:
        raise InputError(f"scheduler = {scheduler!r}: expected a Dask scheduler address "
                         "such as 'tcp://host:8786', a cluster or a distributed.Client")
    return distributed.Client(address), True


def _check_function(function, kind: str) -> None:
    qualname = getattr(function, "__qualname__", "")
    if not callable(function):
        raise InputError(f"function = {function!r}: not callable")
    if kind != "executor" and ("<locals>" in qualname or "<lambda>" in qualname):
        raise InputError(f"function = {qualname!r}: {kind} workers need a top-level function "
                         "of a module they can import (not a lambda or a nested def)")


def _keys(study: str, function, points: list) -> list[str]:
    keys = []
    for i, point in enumerate(points):
        if not isinstance(point, Mapping):
            raise InputError(f"points[{i}] = {point!r}: a point is a table of parameters (dict)")
        keys.append(point_key(study, function, point, where=f"points[{i}]"))
    return keys


def _chunks(items: list, size: int) -> list[list]:
    return [items[i:i + size] for i in range(0, len(items), size)]


def _auto_chunk(todo: int, workers: int) -> int:
    return max(1, min(MAX_CHUNK, math.ceil(todo / (TASKS_PER_WORKER * max(workers, 1)))))


def run_sweep(function: Callable, points: Iterable[Mapping], store: Store | str | os.PathLike,
              *, study: str | None = None, executor: cf.Executor | None = None,
              scheduler=None, chunk: int | None = None, progress=None,
              batched: bool = False, write_through: bool | None = None,
              workers: int | None = None, verify: int = DEFAULT_SAMPLE) -> list:
    """Evaluate ``function`` at every point not yet in ``store``; return all records in order.

    ``function(point) -> record`` is a top-level (picklable) function of one point (a dict of
    JSON values) returning JSON values (numbers, text, lists, tables); with ``batched`` it takes
    a list of points and returns a list of records. ``study`` names the study in the keys
    (default: the last part of the module in the function's key name). ``executor``: any
    ``concurrent.futures`` executor (kept open); otherwise :func:`sweep_executor`
    (``scheduler`` or local processes, ``workers`` of them). ``chunk`` points go to each task
    (default: up to :data:`MAX_CHUNK`, about :data:`TASKS_PER_WORKER` tasks per worker).
    ``progress``: None prints on stderr for long sweeps (a bar in a notebook), True a bar
    (:mod:`.sweep_bar`), False is silent, or a callable taking a :class:`SweepProgress` (called at the start and after every chunk; an exception it
    raises, such as KeyboardInterrupt, stops the sweep with every finished point stored).
    ``write_through`` (default: True except on Dask): workers store each point as soon as it is
    done. Stored records made by earlier code are checked before they are used: ``verify`` of
    them (seeded) are made again and must reproduce their records within the function's
    declared tolerance (:func:`.freshness.check_stale`; a
    :class:`~.freshness.StaleStoreError` names the points that moved).

    Every point is checked (JSON, finite numbers) and keyed before anything runs. Local worker
    processes are spawned: a script that calls this needs the usual
    ``if __name__ == "__main__":`` guard.
    """
    store = store if isinstance(store, Store) else Store(store)
    name = function_name(function)
    study = study or name.split(":", 1)[0].rsplit(".", 1)[-1]
    points = list(points)
    keys = _keys(study, function, points)
    if chunk is not None:
        chunk = integer_at_least("chunk", chunk, 1)
    if workers is not None:
        workers = integer_at_least("workers", workers, 1)
    address = _address(scheduler)
    kind = _kind(executor) if executor is not None else ("Dask" if address else "process")
    _check_function(function, kind)
    entries = {k: store.entry(k) for k in dict.fromkeys(keys)}
    todo = {k: p for k, p in zip(keys, points) if entries[k] is None}
    stale = {k: p for k, p in zip(keys, points)
             if entries[k] is not None and not store.is_fresh(entries[k])}
    report = sweep_report(progress, StderrProgress)
    meta = {k: v for k, v in record_meta(study, function, {}).items() if k != "params"}
    if todo or stale:
        through = (kind != "Dask") if write_through is None else bool(write_through)
        with contextlib.ExitStack() as stack:
            if executor is None and kind == "process":  # no more processes than chunks
                n = workers or os.cpu_count() or 1
                chunk = chunk or _auto_chunk(max(len(todo), 1), n)
                workers = min(n, max(math.ceil(len(todo) / chunk), min(verify, len(stale)), 1))
            if executor is None:
                executor = stack.enter_context(sweep_executor(address, workers=workers))
            if stale:
                check_stale(store, function, stale, sample=verify,
                            evaluate=_on(executor, meta, batched))
            if todo:
                _compute(function, todo, store, meta, report, executor, chunk, batched,
                         through, total=len(set(keys)))
    return [store.get(k) for k in keys]


def _on(executor, meta, batched):
    """An ``evaluate(function, items)`` for :func:`.freshness.check_stale` that makes the
    items on ``executor``, one task each, storing nothing."""

    def evaluate(function, items):
        futures = [executor.submit(_evaluate_chunk, function, [item], None, meta, batched)
                   for item in items]
        return [pair for future in futures for pair in future.result()]

    return evaluate


def _kind(executor) -> str:
    return "Dask" if type(executor).__module__.startswith("distributed") else "executor"


def _workers(executor) -> int:
    """How many tasks ``executor`` runs at once (for the default chunk size)."""
    client = getattr(executor, "_client", None)
    if client is not None and hasattr(client, "nthreads"):
        return max(1, sum(client.nthreads().values()))
    return getattr(executor, "_max_workers", None) or os.cpu_count() or 1


def _compute(function, todo, store, meta, report, executor, chunk, batched, through, total):
    start = time.perf_counter()
    items = list(todo.items())
    already = total - len(items)
    counts = {"computed": 0}

    def tick():
        if report is not None:
            report(SweepProgress(meta["study"], already + counts["computed"], total,
                                 counts["computed"], time.perf_counter() - start))

    tick()
    size = chunk or _auto_chunk(len(items), _workers(executor))
    root = store.root if through else None
    futures = [executor.submit(_evaluate_chunk, function, part, root, meta, batched)
               for part in _chunks(items, size)]
    try:
        _collect(futures, todo, store, meta, counts, tick)
    except BaseException as exc:
        stopped = sum(1 for f in futures if f.cancel())
        exc.add_note(f"run_sweep({meta['study']}): {already + counts['computed']} of {total} "
                     f"points are stored in {store.root} (with any that a worker stored "
                     f"before it was stopped); {stopped} chunks were not started; running "
                     "the sweep again computes only the rest")
        raise


def _collect(futures, todo, store, meta, counts, tick) -> None:
    """Store each chunk's records as it finishes. A failing chunk stops the sweep after the
    chunks already running have finished and been stored."""
    failure = None
    for future in cf.as_completed(futures):
        try:
            results = future.result()
        except cf.CancelledError:
            continue
        except Exception as exc:  # a point failed: keep what the running chunks finish
            if failure is None:
                failure = exc
                for other in futures:
                    other.cancel()
            continue
        for key, record in results:
            if not store.has(key):
                store.put(key, record, {**meta, "params": plain_params(todo[key])})
        counts["computed"] += len(results)
        tick()
    if failure is not None:
        raise failure


@contextlib.contextmanager
def sweep_executor(scheduler=None, *, workers: int | None = None):
    """The executor sweeps run on, for as long as the block lasts (so that several sweeps share
    one pool): a Dask cluster's when ``scheduler`` (an address, a cluster or a
    ``distributed.Client``) or ``DASK_SCHEDULER_ADDRESS`` is given, otherwise ``workers`` local
    processes (default: the CPU count), spawned with one thread each
    (:data:`SINGLE_THREAD_ENVIRONMENT`, set in this process while the block runs so that the
    workers inherit it at birth), all ended when the block ends, also by an interruption
    (:func:`upliftlab.workers.process_pool`)."""
    address = _address(scheduler)
    if address:
        client, owned = _dask_client(address)
        try:
            yield client.get_executor(pure=False)
        finally:
            if owned:
                client.close()
        return
    with process_pool(workers or os.cpu_count() or 1) as pool:
        yield pool  # interrupted: unstarted work cancelled, workers ended (finished work is stored)
