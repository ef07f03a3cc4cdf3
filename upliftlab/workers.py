"""Pools of worker processes that end with the run that started them.

Worker pools (the reduced model's batch, the studies' sweeps) run one single-threaded task per
core: :data:`SINGLE_THREAD_ENVIRONMENT` keeps OpenMP, BLAS and numba from starting a thread per
core in every worker, which on a two-core machine would oversubscribe it many times over. A
spawned worker reads these variables when its libraries load, so they are set in the parent
while the pool starts (:func:`inherited_environment`), not in the worker.

**No orphans.** :func:`process_pool` is the one way such a pool is made. Interrupting the run
at any moment ends every process it started:

* a worker is spawned with SIGINT blocked, and ignores it once it runs: a Ctrl-C (sent to the
  terminal's whole process group) reaches only the parent, which ends the workers; no worker
  prints a traceback of its own;
* a worker is spawned inside :func:`signals_deferred`: an interruption that arrives while a
  process is being started is held until the pool has recorded it, so no worker is started
  that the pool does not know of;
* when the pool's block ends by an exception (an interruption, a failed point) the pool is
  shut down, its unstarted tasks cancelled, and every worker terminated (SIGTERM, on which a
  worker removes the temporary file it was writing and ends; SIGKILL after
  :data:`TERMINATE_GRACE` s); at a normal end the workers are asked to exit and are
  waited for;
* a worker whose parent has gone (killed with SIGKILL, which nothing can catch) ends itself
  within :data:`PARENT_POLL` s (:func:`watch_parent`), also when the parent died while the
  worker was still starting: the worker is told its parent's process id at birth instead of
  reading it when it is ready, by which time it may already belong to another process.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import multiprocessing
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator, Mapping

from .paths import remove_live_temporaries

__all__ = ["SINGLE_THREAD_ENVIRONMENT", "PARENT_POLL", "TERMINATE_GRACE",
           "inherited_environment", "signals_deferred", "process_pool", "watch_parent",
           "single_threaded"]

#: One thread for OpenMP, MKL, OpenBLAS and numba.
SINGLE_THREAD_ENVIRONMENT = {"OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
                             "OPENBLAS_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1"}
#: How often (s) a worker checks that the process that started it is still alive.
PARENT_POLL = 0.5
#: How long (s) a worker is given to end after SIGTERM before it is killed.
TERMINATE_GRACE = 2.0
#: How long (s) a normal end of a pool waits for its idle workers to exit.
EXIT_WAIT = 10.0

_INTERRUPTS = (signal.SIGINT, signal.SIGTERM)


def single_threaded():
    """A context that limits the loaded BLAS and OpenMP pools to one thread for its block
    (``threadpoolctl``; nothing if it is not installed), and restores them after. The
    continuum's dense algebra is small (a footing's 4 × 4 forms, a row's dot products over the
    soil's DOFs), and a multi-threaded BLAS wakes its threads for each call: on a loaded
    machine a thread that must wait for a core turns a microsecond's call into milliseconds.
    The command line starts with one BLAS thread for the same reason
    (:mod:`upliftlab.cli`); this is for the API, as in a notebook."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        return contextlib.nullcontext()
    import scipy.linalg  # noqa: F401  (load scipy's own BLAS first: limits apply to loaded
    import scipy.sparse.linalg  # noqa: F401  libraries only)
    return threadpool_limits(limits=1)


@contextlib.contextmanager
def inherited_environment(values: Mapping[str, str]) -> Iterator[None]:
    """Set environment variables for the block (processes spawned in it inherit them); the
    earlier values, or their absence, come back when it ends."""
    old = {k: os.environ.get(k) for k in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


@contextlib.contextmanager
def signals_deferred() -> Iterator[None]:
    """Hold SIGINT and SIGTERM while the block runs (a few milliseconds: starting a process)
    and deliver them after it, to the handlers in place before; processes started in the block
    begin with SIGINT blocked. Outside the main thread (where no handler can be set) the block
    just runs."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held: list[int] = []
    previous = {s: signal.signal(s, lambda signum, frame: held.append(signum))
                for s in _INTERRUPTS}
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        if held:
            signal.raise_signal(held[0])


def watch_parent(parent: int | None = None, poll: float = PARENT_POLL) -> threading.Thread:
    """Start a daemon thread that ends this process (exit status 1) as soon as its parent is
    no longer ``parent`` (default: the parent now): the parent has gone and this process was
    re-parented."""
    parent = os.getppid() if parent is None else parent

    def watch():
        while True:
            if os.getppid() != parent:
                os._exit(1)
            time.sleep(poll)

    thread = threading.Thread(target=watch, name="upliftlab-parent-watch", daemon=True)
    thread.start()
    return thread


def _stopped(signum, frame) -> None:
    """A worker's SIGTERM: remove what it was writing, and end at once."""
    remove_live_temporaries()
    os._exit(128 + signum)


def _worker_start(parent: int, initializer, initargs) -> None:
    """Every worker's first act: one thread, no SIGINT, SIGTERM ends it without leaving a part
    file, end with the parent ``parent``, then the pool's own ``initializer``."""
    os.environ.update(SINGLE_THREAD_ENVIRONMENT)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _stopped)
    watch_parent(parent)
    if initializer is not None:
        initializer(*initargs)


class _Pool(cf.ProcessPoolExecutor):
    """A process pool whose workers are started with interruptions held
    (:func:`signals_deferred`), so that each one is known to the pool before an interruption
    can end the run."""

    def submit(self, fn, /, *args, **kwargs):
        with signals_deferred():
            return super().submit(fn, *args, **kwargs)

    def workers(self) -> list:
        """The worker processes started so far."""
        return list((getattr(self, "_processes", None) or {}).values())


def _end(pool: _Pool, failed: bool) -> None:
    """Shut ``pool`` down: cancel what has not started; wait for idle workers to exit (a normal
    end) or terminate them (``failed``), then kill any still alive; then wait for the pool's
    manager thread to end. (Left running, it closes its wake-up pipe while the interpreter's
    exit writes to it: Python 3.11 printed "Exception ignored … Bad file descriptor" with a
    traceback after an interrupted study's one line, seen once in the tests' runs.)"""
    workers = pool.workers()
    # CPython's (3.9 and later), taken before shutdown() lets go of it
    manager = getattr(pool, "_executor_manager_thread", None)
    pool.shutdown(wait=False, cancel_futures=True)
    if not failed:
        deadline = time.monotonic() + EXIT_WAIT
        for worker in workers:
            worker.join(max(0.0, deadline - time.monotonic()))
    for worker in workers:
        if worker.is_alive():
            worker.terminate()
    deadline = time.monotonic() + TERMINATE_GRACE
    for worker in workers:
        worker.join(max(0.0, deadline - time.monotonic()))
        if worker.is_alive():
            worker.kill()
            worker.join(TERMINATE_GRACE)
    if manager is not None and manager is not threading.current_thread():
        manager.join(TERMINATE_GRACE)


@contextlib.contextmanager
def process_pool(workers: int, initializer: Callable | None = None,
                 initargs: tuple = ()) -> Iterator[cf.ProcessPoolExecutor]:
    """A ``concurrent.futures`` pool of ``workers`` spawned processes, one thread each, that
    ends with the block (module docstring); ``initializer(*initargs)`` runs in each worker
    after upliftlab's own start."""
    pool = _Pool(max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                 initializer=_worker_start, initargs=(os.getpid(), initializer, initargs))
    failed = True
    try:
        with inherited_environment(SINGLE_THREAD_ENVIRONMENT):
            yield pool
        failed = False
    finally:
        with signals_deferred():
            _end(pool, failed)
