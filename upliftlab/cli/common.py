"""What every upliftlab command shares: its parser, the checks of its options, its folders.

A command checks everything before it starts: an option is a number in its range
(:func:`number`), an override the command would ignore is refused
(:func:`refuse_without_effect`), and a run's default output folder names what makes it
differ from the scene's defaults (:func:`default_out`).
"""

from __future__ import annotations

import argparse
import fnmatch
import math
import time
from pathlib import Path

from ..checks import InputError
from ..log import logger
from ..outdir import settings_digest
from .exits import EXIT_INPUT

__all__ = ["Parser", "add_verbosity", "refuse_without_effect", "number", "say_if_rounded",
           "say_if_step_changed", "default_out", "mesh_overrides", "say", "eta", "MESH_KEYS",
           "FORCE_HELP"]

#: The help of every ``--force``: what it replaces, and what it never does.
FORCE_HELP = ("replace a different run in --out (only files upliftlab made there: a file of "
              "yours at an output's name is refused, --force or not)")

#: ``--mesh`` keys: the [continuum] fields that shape the mesh and its quadrature.
MESH_KEYS = ("elements_across", "grading", "element", "domain_width", "domain_depth",
             "intorder")


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line (``upliftlab: error: ...``), exit 2."""

    def error(self, message):
        self.exit(EXIT_INPUT, f"upliftlab: error: {self.prog}: {message} (see {self.prog} "
                              "--help)\n")


def add_verbosity(parser: argparse.ArgumentParser) -> None:
    """``--quiet`` (warnings and errors only) and ``--verbose`` (details of each run's set-up)
    (:mod:`upliftlab.log`)."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument("-q", "--quiet", action="store_true",
                       help="only warnings and errors on stderr")
    group.add_argument("-v", "--verbose", action="store_true",
                       help="also the details of each run (steps, compilation)")


def _key(item: str) -> str:
    return item.split("=", 1)[0].strip()


def refuse_without_effect(overrides, command: str, used: tuple[str, ...]) -> None:
    """Refuse an override whose key the command does not read (``used``: glob patterns of
    dotted keys): it would be applied to the scene and then ignored."""
    for item in overrides:
        key = _key(item)
        if "=" in item and key and not key.startswith("cases.") and \
                not any(fnmatch.fnmatchcase(key, pattern) for pattern in used):
            raise InputError(f"--set {item!r}: has no effect: {command} does not use {key}")


def number(name: str, text: str | None, *, integer: bool = False, low: float = 0.0,
           high: float = math.inf):
    """A number in (``low``, ``high``] (an integer in [``low``, ``high``]) given on the
    command line, or None."""
    if text is None:
        return None
    try:
        value = int(text) if integer else float(text)
    except ValueError:
        kind = (f"an integer in [{low:g}, {high:g}]" if integer
                else f"a number in ({low:g}, {high:g}]")
        raise InputError(f"{name} = {text!r}: expected {kind}") from None
    if integer and not low <= value <= high:
        raise InputError(f"{name} = {value}: valid range is [{low:g}, {high:g}]")
    if not integer and not (low < value <= high and math.isfinite(value)):
        raise InputError(f"{name} = {text}: valid range is ({low:g}, {high:g}]")
    return value


def say_if_rounded(command: str, duration: float, steps: int, dt: float) -> None:
    """Say on stderr when a run's length differs from the duration asked for (it is a whole
    number of steps)."""
    if abs(steps * dt - duration) > 1e-9 * max(duration, 1.0):
        logger("cli").warning(f"{command}: note: the duration {duration:g} s runs as {steps} "
                              f"steps of {dt:.6g} s = {steps * dt:.6g} s")


def say_if_step_changed(command: str, field: str, asked: float | None, used: float,
                        duration: float) -> None:
    """Say on stderr when a step asked for (s; ``field`` names where it was given) runs as
    another: a run's steps and its output steps are whole numbers in its ``duration`` (s), so
    a step that does not divide it is made smaller (or, beyond the duration, the duration)."""
    if asked is not None and abs(used - asked) > 1e-9 * asked:
        logger("cli").warning(f"{command}: note: {field} = {asked:g} s runs as {used:.6g} s, "
                              f"a whole number of steps in the run's {duration:g} s")


def _short(settings: dict) -> str:
    return settings_digest(settings)[:8]


def default_out(stem: str, variant: dict) -> Path:
    """``results/<stem>``, with a digest of ``variant`` when it changes the scene's defaults
    (overrides, motion, step), so that different runs do not share a folder."""
    extra = {k: v for k, v in variant.items() if v}
    return Path("results") / (f"{stem}-{_short(extra)}" if extra else stem)


def mesh_overrides(items: list[str]) -> list[str]:
    """``--mesh a=1,b=2`` -> ``continuum.a=1``, ``continuum.b=2``; unknown keys refused."""
    overrides = []
    for item in items:
        for pair in filter(None, (p.strip() for p in item.split(","))):
            key, sep, value = pair.partition("=")
            if not sep or not value.strip():
                raise InputError(f"--mesh {pair!r}: expected KEY=VALUE with KEY one of "
                                 f"{', '.join(MESH_KEYS)}")
            if key.strip() not in MESH_KEYS:
                raise InputError(f"--mesh {key.strip()!r}: unknown mesh key (valid: "
                                 f"{', '.join(MESH_KEYS)})")
            overrides.append(f"continuum.{key.strip()}={value.strip()}")
    return overrides


def say(message: str, command: str = "continuum") -> None:
    """One progress line of ``upliftlab command`` on stderr."""
    logger(command).info(f"upliftlab {command}: {message}")


def eta(started: float, done: int, total: int) -> str:
    """"; elapsed, about … left" after ``done`` of ``total`` (s since ``started``)."""
    elapsed = time.perf_counter() - started
    left = elapsed / max(done, 1) * (total - done)
    return f"; {elapsed:.0f} s, about {left:.0f} s left" if done < total else \
        f"; {elapsed:.0f} s"
