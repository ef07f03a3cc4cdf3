"""An interruption (Ctrl-C, SIGTERM) as a flag that a long computation checks, so that what it
computed is kept whatever the moment the signal comes.

Until a computation has something to keep, an interruption ends it at once (KeyboardInterrupt,
as Python's Ctrl-C does). Once it calls :meth:`StopFlag.defer` (a time loop at its first step),
an interruption only sets the flag: the loop checks it (:meth:`StopFlag.check`) and ends there
with what it has, and a signal that comes after the loop, while the results are written, lets
the writing finish (``stopped`` then says so). A second signal is no different from the first:
nothing is thrown away half-written; SIGKILL is the way to end a run without its results.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

__all__ = ["StopFlag", "stop_flag"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class StopFlag:
    """Whether, and by which signal, the user asked the command to stop (module docstring)."""

    def __init__(self) -> None:
        self.signal: int | None = None
        self.deferred = False

    @property
    def stopped(self) -> bool:
        """Whether a signal came."""
        return self.signal is not None

    @property
    def name(self) -> str:
        """The signal's name (SIGINT, SIGTERM), or '' before one came."""
        return signal.Signals(self.signal).name if self.signal is not None else ""

    def handler(self, signum, frame) -> None:
        """The signal handler: remember the first signal; raise at once unless deferred."""
        if self.signal is None:
            self.signal = signum
        if not self.deferred:
            raise KeyboardInterrupt(signal.Signals(signum).name)

    def defer(self) -> None:
        """From now on a signal only sets the flag; one that came already is raised here."""
        self.deferred = True
        self.check()

    def check(self) -> None:
        """Raise KeyboardInterrupt (naming the signal) if a signal came."""
        if self.signal is not None:
            raise KeyboardInterrupt(self.name)


@contextlib.contextmanager
def stop_flag() -> Iterator[StopFlag]:
    """A :class:`StopFlag` handling SIGINT and SIGTERM while the block runs (in the main thread;
    elsewhere the flag is never set and signals keep their handlers)."""
    flag = StopFlag()
    if threading.current_thread() is not threading.main_thread():
        yield flag
        return
    previous = {s: signal.signal(s, flag.handler) for s in _SIGNALS}
    try:
        yield flag
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
