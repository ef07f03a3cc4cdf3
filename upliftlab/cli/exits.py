"""The exit codes of every upliftlab command, defined once, and the exceptions they stand for.

0 done; 1 a verification, report section or study check failed; 2 bad input (one line
naming the field, the value and the valid range, before any work); 3 a numerical failure (a
solver that gave up names its step; an energy balance beyond its tolerance; stale kept
results that moved); 130 interrupted. The library raises exceptions; only the command line
turns them into these codes (:func:`exit_code`).
"""

from __future__ import annotations

__all__ = ["EXIT_OK", "EXIT_FAILED", "EXIT_INPUT", "EXIT_NUMERICS", "EXIT_INTERRUPTED",
           "exit_code", "one_line"]

EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_NUMERICS, EXIT_INTERRUPTED = 0, 1, 2, 3, 130


def exit_code(exc: BaseException) -> int:
    """The exit code of a command that ended with ``exc``."""
    from ..checks import InputError

    if isinstance(exc, InputError):
        return EXIT_INPUT
    if isinstance(exc, KeyboardInterrupt):
        return EXIT_INTERRUPTED
    if isinstance(exc, (RuntimeError, MemoryError, ArithmeticError)):
        return EXIT_NUMERICS
    return EXIT_FAILED


def one_line(exc: BaseException) -> str:
    """The message of ``exc`` on one line."""
    return " ".join(str(exc).split())
