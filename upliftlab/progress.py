"""Progress bars of long runs (tqdm), in a terminal and in a notebook.

A long analysis (a continuum dynamic run, a pushover, a sweep of a study) takes a
``progress`` argument:

- a callable: called as the analysis documents (``progress(k, n, state)`` for the continuum's
  runs); the command line passes one that writes its log lines, unchanged;
- ``True``: a tqdm bar (elapsed time, rate, ETA) whatever the output is;
- ``False``: nothing;
- ``None`` (the default): a bar when someone watches (:func:`watched`): in a Jupyter kernel
  (a widget when ipywidgets is installed, else text in the cell's output), or on a terminal
  in the main process of a program that has not configured upliftlab's log lines (the command
  line has: its lines say the same, and a bar would cut through them). Never in worker
  processes, pipes or files.

The bar goes to stderr (text) or to the cell (widget); the library still never prints a result.
"""

from __future__ import annotations

import contextlib
import importlib.util
import multiprocessing
import sys
from typing import Callable, Iterator

__all__ = ["in_kernel", "watched", "bar_class", "bar", "steps_progress"]


def in_kernel() -> bool:
    """Whether this process is a Jupyter (IPython) kernel."""
    shell = sys.modules.get("IPython")
    if shell is None:
        return False
    ipython = shell.get_ipython()
    return ipython is not None and hasattr(ipython, "kernel")


def _log_lines_configured() -> bool:
    from .log import _Handler, logger

    return any(isinstance(h, _Handler) for h in logger().handlers)


def watched() -> bool:
    """Whether a default (``None``) progress shows a bar (module docstring)."""
    if in_kernel():
        return True
    stream = sys.stderr
    try:
        tty = stream is not None and stream.isatty()
    except (AttributeError, ValueError):  # closed or replaced by something without isatty
        return False
    return tty and multiprocessing.parent_process() is None and not _log_lines_configured()


def bar_class():
    """tqdm's notebook widget in a kernel with ipywidgets, else its text bar (what
    ``tqdm.auto`` picks, without its warning when ipywidgets is missing)."""
    if in_kernel() and importlib.util.find_spec("ipywidgets") is not None:
        from tqdm.notebook import tqdm
    else:
        from tqdm.std import tqdm
    return tqdm


def bar(total: int, description: str, unit: str = "step"):
    """A new progress bar over ``total`` ``unit``\\ s, named ``description``: elapsed time,
    rate and ETA; updated at most ten times a second."""
    return bar_class()(total=total, desc=description, unit=unit, dynamic_ncols=True,
                       mininterval=0.1, file=None if in_kernel() else sys.stderr)


@contextlib.contextmanager
def steps_progress(progress, description: str, *, offset: int = 0,
                   postfix: Callable | None = None) -> Iterator[Callable | None]:
    """The ``progress(k, n, state)`` callback to hand to a run, from the user's ``progress``
    (module docstring): theirs if callable, None if no bar is wanted, else one that moves a
    bar to step ``k + offset`` of ``n`` (``offset`` 1 for a run that counts its steps from
    0) with ``postfix(state)`` (text) beside it. The bar is closed when the block ends,
    however it ends."""
    if callable(progress):
        yield progress
        return
    if progress is False or (progress is None and not watched()):
        yield None
        return
    if progress not in (None, True):
        from .checks import InputError

        raise InputError(f"progress = {progress!r}: valid are None, True, False or a callable")
    shown = []

    def report(k, n, state=None):
        if not shown:
            shown.append(bar(int(n), description))
        current = shown[0]
        done = min(int(k) + offset, int(n))
        if postfix is not None and state is not None:
            current.set_postfix_str(postfix(state), refresh=False)
        current.update(done - current.n)

    try:
        yield report
    finally:
        if shown:
            shown[0].close()
