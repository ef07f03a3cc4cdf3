"""Messages: the library logs through :mod:`logging` under the ``upliftlab`` logger.

Progress of long work and notes about a run go to ``logging`` (INFO and WARNING), details of
how a run was set up (its step, its plan, the compilation of kernels) to DEBUG; the library
never prints. A program that uses upliftlab sees nothing unless it configures logging; the
command line does, with :func:`configure`: INFO and above by default, WARNING and above with
``--quiet``, everything with ``--verbose``, each message on one line of stderr. Errors are not
messages: they are exceptions, which the command line turns into one line and an exit code.

The first run on a machine compiles the reduced model's kernels (numba) and caches them; it
says so (:func:`announce_compilation`) instead of going silent for the minute it takes.
"""

from __future__ import annotations

import logging
import os
import sys
from pathlib import Path

__all__ = ["logger", "configure", "LEVELS", "announce_compilation", "kernels_cached",
           "cache_index"]

#: ``--quiet``, default, ``--verbose``: the lowest level shown.
LEVELS = {-1: logging.WARNING, 0: logging.INFO, 1: logging.DEBUG}
_announced: set[str] = set()


def logger(name: str = "") -> logging.Logger:
    """The logger ``upliftlab.<name>`` (``upliftlab`` for the empty name)."""
    return logging.getLogger("upliftlab" + (f".{name}" if name else ""))


class _Handler(logging.StreamHandler):
    """stderr as it is when the message is written (tests and pipes replace it)."""

    def __init__(self):
        super().__init__(sys.stderr)

    def emit(self, record):
        self.stream = sys.stderr  # not setStream: it would flush the old one, maybe closed
        super().emit(record)


def configure(verbosity: int = 0) -> None:
    """Show upliftlab's messages on stderr from the level of ``verbosity`` (−1 quiet, 0 normal,
    1 verbose), one line each; replaces an earlier call's handler."""
    if verbosity not in LEVELS:
        raise ValueError(f"verbosity = {verbosity}: valid are {sorted(LEVELS)}")
    root = logger()
    for handler in [h for h in root.handlers if isinstance(h, _Handler)]:
        root.removeHandler(handler)
    handler = _Handler()
    handler.setFormatter(logging.Formatter("%(message)s"))
    root.addHandler(handler)
    root.setLevel(LEVELS[verbosity])
    root.propagate = False


def cache_index(function) -> tuple[Path, str]:
    """Where numba's cache keeps the index of a compiled ``function`` (cache=True) under
    ``NUMBA_CACHE_DIR``: the folder (for a source of upliftlab's packages, while upliftlab's
    locator is numba's first: its place in the package,
    :func:`upliftlab.kernel_cache.package_subpath`; else numba's own name,
    ``<source folder name>_<sha1 of its absolute path>``) and the file pattern
    ``<module>.<function>-*.nbi``."""
    import hashlib
    import inspect

    plain = getattr(function, "py_func", function)
    source = Path(inspect.getfile(plain)).resolve()
    pattern = f"{source.stem}.{plain.__name__}-*.nbi"
    if _package_locator_first():
        from .kernel_cache import package_subpath

        folder = package_subpath(source)
        if folder is not None:
            return Path(folder), pattern
    folder = f"{source.parent.name}_{hashlib.sha1(str(source.parent).encode()).hexdigest()}"
    return Path(folder), pattern


def _package_locator_first() -> bool:
    """Whether numba looks for upliftlab's kernels with upliftlab's locator first (its
    ``CACHE_LOCATOR_CLASSES``; a numba without it caches by path)."""
    from numba.core import config

    chosen = getattr(config, "CACHE_LOCATOR_CLASSES", "") or ""
    return chosen.split(",")[0].strip() == "upliftlab.kernel_cache.PackageLocator"


def kernels_cached(cache: str | os.PathLike | None, function) -> bool:
    """Whether numba's cache folder ``cache`` holds the index of the compiled ``function``
    (:func:`cache_index`): an earlier run of this source compiled and cached it."""
    if not cache:
        return False
    folder, pattern = cache_index(function)
    where = Path(cache) / folder
    return where.is_dir() and any(where.glob(pattern))


def announce_compilation(what: str, function, expected: str = "") -> None:
    """Say, once per process, that ``what`` is being compiled when numba's cache does not hold
    the compiled ``function`` yet (:func:`kernels_cached`), and how long it is ``expected`` to
    take (text, e.g. "about 1–2 minutes"); a function numba does not cache (``cache=False``) is
    compiled in every new process, and the notice says that instead."""
    if what in _announced:
        return
    _announced.add(what)
    cache = os.environ.get("NUMBA_CACHE_DIR")
    if os.environ.get("NUMBA_DISABLE_JIT") == "1":
        return
    if type(getattr(function, "_cache", None)).__name__ == "NullCache":
        logger("compile").info(f"upliftlab: compiling {what} (in every new process: they "
                               "take other kernels as arguments, which numba does not cache)")
        return
    if kernels_cached(cache, function):
        return
    took = f"{expected}, " if expected else ""
    logger("compile").info(f"upliftlab: compiling {what} ({took}once: the next runs read them "
                           f"from the cache in {cache or 'the package folder'})")
