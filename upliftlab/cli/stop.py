"""An interruption (Ctrl-C, SIGTERM) as a flag that a long computation checks, so that what it
computed is kept whatever the moment the signal comes.

Until a computation has something to keep, an interruption ends it at once (KeyboardInterrupt,
as Python's Ctrl-C does). Once it calls :meth:`StopFlag.defer` (a time loop at its first step),
an interruption only sets the flag: the loop checks it (:meth:`StopFlag.check`) and ends there
with what it has, and a signal that comes after the loop, while the results are written, lets
the writing finish (``stopped`` then says so). A second signal is no different from the first:
nothing is thrown away half-written; SIGKILL is the way to end a run without its results.

Every signal is remembered, also one whose KeyboardInterrupt Python swallows (raised while a
weakref callback or a ``__del__`` runs, it is printed as "Exception ignored" and the code goes
on): a command checks the flag at its safe points and so still ends there. A flag made inside
another's block starts with the signal the outer one holds. A signal the process inherited as
ignored (SIGINT in a job a non-interactive shell started in the background) stays ignored.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

__all__ = ["StopFlag", "stop_flag"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM)
#: The flags whose blocks are running, innermost last (:func:`stop_flag`).
_ACTIVE: list[StopFlag] = []


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

    def adopt(self, signals) -> None:
        """Take the first of ``signals`` (numbers that came before this flag was set, e.g.
        while the command loaded: :data:`upliftlab.COMMAND_SIGNALS`) as this flag's, unless it
        holds one already."""
        if self.signal is None and signals:
            self.signal = signals[0]

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
    previous = {s: signal.signal(s, flag.handler) for s in _SIGNALS
                if signal.getsignal(s) is not signal.SIG_IGN}
    if _ACTIVE and flag.signal is None:  # one the outer block's code may not have checked yet
        flag.signal = _ACTIVE[-1].signal
    _ACTIVE.append(flag)
    try:
        yield flag
    finally:
        _ACTIVE.remove(flag)
        for s, handler in previous.items():
            signal.signal(s, handler)
