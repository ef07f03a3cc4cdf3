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
import logging
import multiprocessing
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator, Mapping

from .paths import remove_live_temporaries

__all__ = ["SINGLE_THREAD_ENVIRONMENT", "PARENT_POLL", "TERMINATE_GRACE",
           "inherited_environment", "signals_deferred", "process_pool", "watch_parent",
           "single_threaded", "in_child", "dying_with_this_process"]

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


#: How often (s) :func:`in_child` looks at its ``check`` while the child computes.
CHILD_POLL = 0.05


def in_child(work: Callable, *args, check: Callable[[], None] = lambda: None, **kwargs):
    """``work(*args, **kwargs)`` computed in a forked child process, its answer (or the
    exception it raised) returned (raised) here; its log records are handled here as they come.

    Why: compiled code (a numba time loop) holds the interpreter until it returns, so a signal
    handler of this process could not run before the loop's end (18 s later, in one case).
    This process only waits, calling ``check`` every :data:`CHILD_POLL` s: what ``check``
    raises (a :class:`~upliftlab.cli.stop.StopFlag`'s KeyboardInterrupt) ends the child at
    once (SIGKILL: it writes no file) and is raised here. The child ignores SIGINT (a Ctrl-C
    to the process group is this process's to handle) and dies with this process (Linux's
    parent-death signal). Without ``os.fork`` (Windows) ``work`` runs here."""
    if not hasattr(os, "fork"):
        return work(*args, **kwargs)
    import sys

    read, write = os.pipe()
    for stream in (sys.stdout, sys.stderr):  # nothing buffered here is written twice
        stream.flush()
    parent = os.getpid()
    pid = os.fork()
    if pid == 0:  # the child: it never returns from here
        os.close(read)
        _child(parent, write, work, args, kwargs)
    os.close(write)
    status = None
    try:
        message = _read_answer(read, check)
        status = os.waitpid(pid, 0)[1]
    finally:
        os.close(read)
        if status is None:  # ended early here: the child goes too
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
    return _answer(message, status, check)


def _child(parent: int, write: int, work: Callable, args, kwargs) -> None:
    """The forked child of :func:`in_child`: compute, send the answer as framed pickles on
    ``write`` (the log records first, as they come), and end without running this process's
    exit handlers or ``finally`` blocks (they belong to the parent)."""
    import pickle
    import sys

    code = 0
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        _die_with(parent)
        root = logging.getLogger("upliftlab")
        root.handlers, root.propagate = [_PipeHandler(write)], False
        try:
            message = ("answer", work(*args, **kwargs))
        except BaseException as exc:  # noqa: BLE001  (raised in the parent)
            import traceback

            exc.add_note("in the computing process:\n" + "".join(
                traceback.format_exception(exc)).rstrip())
            message = ("raised", exc)
        try:
            data = pickle.dumps(message, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception as exc:  # noqa: BLE001  (an exception that does not pickle)
            data = pickle.dumps(("raised", RuntimeError(f"{type(message[1]).__name__}: "
                                                        f"{message[1]} ({exc})")))
        _send(write, data)
    except BaseException:  # noqa: BLE001  (the parent says the child ended without an answer)
        code = 1
    finally:
        with contextlib.suppress(Exception):
            sys.stdout.flush()
            sys.stderr.flush()
        os._exit(code)


#: A program that runs another in its own place (``exec``) after asking Linux to end it
#: (SIGKILL) when the process that started it dies: argv[1] that process's id, argv[2:] the
#: command. The parent-death signal survives the exec; a parent already gone ends it at once.
#: A program that cannot be run ends it with one line and exit 127, as a shell's does.
_DIES_WITH_PARENT = """import ctypes, os, signal, sys
try:
    ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)
except (OSError, AttributeError):
    pass
if os.getppid() != int(sys.argv[1]):
    os._exit(1)
try:
    os.execvp(sys.argv[2], sys.argv[2:])
except OSError as exc:
    print(f"cannot run {sys.argv[2]!r}: {exc.strerror}", file=sys.stderr)
    os._exit(127)
"""


def dying_with_this_process(command) -> list[str]:
    """``command`` (a program and its arguments) as a command that runs it, in its own place,
    so that it ends when this process dies, also by SIGKILL, which nothing here can catch (a
    program upliftlab starts, OpenSees or a browser, must not outlive it). Linux's parent-death
    signal, set by a few fixed lines of Python before they execute ``command`` (which reaches
    them only as arguments, never as code). It follows the thread that starts the program: start
    it from the thread that waits for it; Linux clears it when a set-user-id program is executed
    (a browser started through one is then not covered). Elsewhere than Linux: ``command`` as it
    is, and a killed upliftlab does not end it."""
    import sys

    command = [str(part) for part in command]
    if not sys.platform.startswith("linux"):
        return command
    # -I: the folder it starts in (the user's) is not on its path, nor PYTHON* variables
    # read: no module of theirs named ctypes or signal runs in its place
    return [sys.executable, "-I", "-c", _DIES_WITH_PARENT, str(os.getpid()), *command]


def _die_with(parent: int) -> None:
    """End this process (SIGKILL) when ``parent`` dies (Linux's PR_SET_PDEATHSIG; elsewhere
    nothing), also if it died already."""
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG = 1
    except (OSError, AttributeError):
        pass
    if os.getppid() != parent:
        os._exit(1)


def _send(fd: int, data: bytes) -> None:
    """Write one frame: the length of ``data`` (8 bytes) and ``data``."""
    for part in (len(data).to_bytes(8, "little"), data):
        view = memoryview(part)
        while view:
            view = view[os.write(fd, view):]


class _PipeHandler(logging.Handler):
    """The child's log handler: each record, its message formatted, sent to the parent."""

    def __init__(self, fd: int) -> None:
        super().__init__()
        self.fd = fd

    def emit(self, record: logging.LogRecord) -> None:
        import pickle

        record.msg, record.args, record.exc_info = record.getMessage(), None, None
        _send(self.fd, pickle.dumps(("log", record)))


def _read_answer(read: int, check: Callable[[], None]):
    """The message ("answer" or "raised", value) the child sends on ``read`` (:func:`_child`),
    None if it sent none; its log records handled as they come, and ``check`` called while no
    answer has come nor started to come (an answer being received is computed: it is kept)."""
    import pickle
    import select

    buffer, message = bytearray(), None
    while True:
        if message is None and not buffer:
            check()
        ready, _, _ = select.select([read], [], [], CHILD_POLL)
        if not ready:
            continue
        chunk = os.read(read, 1 << 20)
        if not chunk:
            break
        buffer += chunk
        while len(buffer) >= 8 and len(buffer) >= 8 + int.from_bytes(buffer[:8], "little"):
            size = int.from_bytes(buffer[:8], "little")
            kind, value = pickle.loads(buffer[8:8 + size])
            del buffer[:8 + size]
            if kind == "log":
                logging.getLogger(value.name).handle(value)
            else:
                message = (kind, value)
    return message


def _answer(message, status: int, check: Callable[[], None]):
    """What :func:`in_child` returns or raises: the child's ``message``; when it sent none, the
    interruption that ended it (``check``'s, or the signal it died of) or a RuntimeError
    naming how it ended (exit ``status``, as ``os.waitpid`` gives it)."""
    if message is None:
        check()  # a signal to the whole process group ended the child too
        ended = os.waitstatus_to_exitcode(status)
        if -ended in (signal.SIGINT, signal.SIGTERM):
            raise KeyboardInterrupt(signal.Signals(-ended).name)
        why = (f"by {signal.Signals(-ended).name}" if ended < 0 else f"with exit status {ended}")
        raise RuntimeError(f"the computing process ended {why} before its answer")
    kind, value = message
    if kind == "raised":
        raise value
    return value
