"""The exit codes of every upliftlab command, defined once, and the exceptions they stand for.

0 done; 1 a verification, report section or study check failed; 2 bad input (one line
naming the field, the value and the valid range, before any work); 3 a numerical failure (a
solver that gave up names its step; an energy balance beyond its tolerance; stale kept
results that moved; no space left on device); 130 interrupted. The library raises
exceptions; only the command line turns them into these codes (:func:`exit_code`) and lines
(:func:`disk_full_line`, :func:`interrupted_line`).
"""

from __future__ import annotations

import ctypes
import os
import shlex
import sys

__all__ = ["EXIT_OK", "EXIT_FAILED", "EXIT_INPUT", "EXIT_NUMERICS", "EXIT_INTERRUPTED",
           "exit_code", "one_line", "disk_full_line", "interrupted_line",
           "forget_handled_interrupt"]

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


def forget_handled_interrupt(code: int) -> None:
    """Let an interrupted ``python -m upliftlab`` end with ``code`` (130), as the command chose.

    CPython 3.11 marks a KeyboardInterrupt as unhandled whenever one leaves code that ``exec``
    or ``eval`` ran from a string (a dataclass's generated methods while a module is imported,
    for one), even when the command then catches it; at the end of a ``-m`` run that mark makes
    the interpreter kill itself with SIGINT (exit status -2 to a parent) in place of the exit
    code. The mark is cleared here; where the interpreter keeps it elsewhere (3.12 and later),
    the process ends here with ``code`` after the exit handlers have run and the streams are
    flushed (the command has already closed every file it wrote).
    """
    try:
        flag = ctypes.c_int.in_dll(ctypes.pythonapi, "_Py_UnhandledKeyboardInterrupt")
    except (ValueError, AttributeError):
        import atexit

        atexit._run_exitfuncs()
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(code)
    flag.value = 0
