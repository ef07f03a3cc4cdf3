"""The exit codes of every upliftlab command, defined once, and the exceptions they stand for.

0 done; 1 a verification, report section or study check failed; 2 bad input (one line
naming the field, the value and the valid range, before any work); 3 a numerical failure (a
solver that gave up names its step; an energy balance beyond its tolerance; stale kept
results that moved; no space left on device); 130 interrupted. The library raises
exceptions; only the command line turns them into these codes (:func:`exit_code`) and lines
(:func:`disk_full_line`, :func:`interrupted_line`).
"""

from __future__ import annotations

import shlex

__all__ = ["EXIT_OK", "EXIT_FAILED", "EXIT_INPUT", "EXIT_NUMERICS", "EXIT_INTERRUPTED",
           "exit_code", "one_line", "disk_full_line", "interrupted_line"]

EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_NUMERICS, EXIT_INTERRUPTED = 0, 1, 2, 3, 130


def exit_code(exc: BaseException) -> int:
    """The exit code of a command that ended with ``exc``."""
    from ..checks import InputError
    from ..paths import disk_full

    if isinstance(exc, InputError):
        return EXIT_INPUT
    if isinstance(exc, KeyboardInterrupt):
        return EXIT_INTERRUPTED
    if disk_full(exc):
        return EXIT_NUMERICS
    if isinstance(exc, (RuntimeError, MemoryError, ArithmeticError)):
        return EXIT_NUMERICS
    return EXIT_FAILED


def one_line(exc: BaseException) -> str:
    """The message of ``exc`` on one line."""
    return " ".join(str(exc).split())


def disk_full_line(exc: OSError) -> str:
    """The one line of a write that found no space (:func:`upliftlab.paths.disk_full`)."""
    where = f" writing {exc.filename}" if getattr(exc, "filename", None) else ""
    why = " ".join(str(exc.strerror or exc).split())
    return (f"upliftlab: error: no space left on device{where} ({why}); the "
            "unfinished file was removed and the folder is not marked complete: free some "
            "space and run the command again")


def interrupted_line(exc: BaseException, argv: list[str]) -> str:
    """The one line of an interrupted command (Ctrl-C, SIGTERM): what was kept (the notes the
    library attached to the interruption, such as a sweep's stored points) and the command that
    resumes it (the same command: kept results are not computed again)."""
    kept = " ".join(" ".join(str(note).split()) for note in getattr(exc, "__notes__", ()))
    return (f"upliftlab: interrupted ({one_line(exc) or 'Ctrl-C'}); "
            + (kept.rstrip(".") + "; " if kept else "")
            + f"resume with: {shlex.join(['upliftlab', *argv])}")
