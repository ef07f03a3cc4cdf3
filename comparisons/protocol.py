"""The study protocol: what every study declares, and the one way a study is run.

A study is a :class:`Study` record: a stable ``name`` (it names the output folder, the study's
store keys and the report's section, so it must not change when code moves), its options
record type, ``compute(scene, context) -> result`` and ``write(result, context) ->
StudyResult``. :func:`run_study` resolves the output folder and the store, computes, writes and
returns the result with its :class:`~.study.StudyResult` filled in; :func:`main_for` gives a
study its command line (``python -m upliftlab.comparisons.<name>``). The report walks
:data:`.registry.STUDIES` through the same two functions.

A result is a frozen dataclass with a ``study`` field (None until written): ``compute`` leaves
it None, :func:`run_study` replaces it with what ``write`` returned.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from .. import checks
from ..checks import InputError
from ..log import configure, logger
from .store import Store

__all__ = ["Study", "Context", "run_study", "main_for", "default_out", "CHECKOUT", "EXIT_OK",
           "EXIT_FAILED", "EXIT_INPUT", "EXIT_NUMERICS"]

EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_NUMERICS = 0, 1, 2, 3
#: The checkout the package runs from (an editable install); a study's kept store is looked
#: for under it (:attr:`Study.kept_store`).
CHECKOUT = Path(__file__).resolve().parents[1]


def default_out(name: str, fast: bool) -> Path:
    """The default output folder of study ``name``: ``results/<name>[-fast]``."""
    return Path("results") / (name + ("-fast" if fast else ""))


@dataclass(frozen=True)
class Context:
    """Where and how a study runs.

    ``fast``: small grids and coarse meshes. ``out``: the output folder (default
    :func:`default_out`); ``store``: the results store, a :class:`~.store.Store` or its folder
    (default ``<out>/store``). ``options`` and ``grid``: the study's records (None: its fast or
    full default). ``executor``, ``scheduler``, ``workers`` and ``progress`` go to the study's
    sweeps (:func:`.sweep.run_sweep`). ``results``: results of studies already run in the same
    report, by name (a study may reuse one instead of computing it again). ``started``: the
    wall clock (``time.perf_counter``, s) the study's elapsed time counts from. ``budget``
    (s of one worker): a study that estimates its runs' cost before it starts them refuses
    above it, when its own options set no budget (None: no limit; the report passes its own).
    """

    fast: bool = False
    out: str | Path | None = None
    store: Store | str | Path | None = None
    options: object = None
    grid: object = None
    executor: object = None
    scheduler: object = None
    workers: int | None = None
    progress: object = None
    results: Mapping = field(default_factory=dict)
    started: float = field(default_factory=time.perf_counter)
    budget: float | None = None

    def elapsed(self) -> float:
        """Seconds since :attr:`started`."""
        return time.perf_counter() - self.started


@dataclass(frozen=True)
class Study:
    """One study.

    ``name``: stable (output folder, store keys, report section). ``title`` and ``intro``: the
    report's heading and first line. ``options``: the options record type (or None).
    ``compute(scene, context)``: the result (its ``study`` None); ``write(result, context)``:
    the :class:`~.study.StudyResult` (files, summary, numbers). ``scene``: the default scene
    (None: the study picks its own scenes). ``describe(result)``: the lines its command line
    prints. ``passed(result)``: False makes the command line exit 1 (default: always passes).
    ``arguments(parser)`` adds the study's own command-line options and
    ``context_from(args, context)`` folds them into the context. ``own_store``: the study keys
    its whole result itself (the verification): the report hands it the report's store and
    does not cache it again. ``kept_store``: the folder, relative to the checkout's root, where
    the points of the study's full build are kept with the repository; the report's full build
    resumes from it when it is there (a run whose points are all kept costs minutes, not the
    hours its continuum runs took).
    """

    name: str
    title: str
    intro: str
    options: type | None
    compute: Callable
    write: Callable
    scene: str | None = None
    describe: Callable = lambda result: ()
    passed: Callable = lambda result: True
    arguments: Callable | None = None
    context_from: Callable | None = None
    own_store: bool = False
    kept_store: str | None = None
    help_fast: str = "small grids and coarse meshes"


def _resolved(study: Study, context: Context) -> Context:
    checks.boolean("fast", context.fast)
    out = Path(context.out) if context.out is not None else default_out(study.name, context.fast)
    store = context.store
    store = store if isinstance(store, Store) else Store(store or out / "store")
    return dataclasses.replace(context, out=out, store=store)


def run_study(study: Study, scene=None, context: Context | None = None):
    """Run ``study`` on ``scene`` (default: the study's own) in ``context``: compute, then write.

    Returns the result with its ``study`` field set to the :class:`~.study.StudyResult`.
    """
    context = _resolved(study, context or Context())
    scene = study.scene if scene is None else scene
    result = study.compute(scene, context)
    return dataclasses.replace(result, study=study.write(result, context))


def main_for(study: Study) -> Callable[[Sequence[str] | None], int]:
    """The command line of ``study``: ``python -m upliftlab.comparisons.<name> [--fast]
    [--out DIR] [--store DIR] [--scheduler ADDR] [--workers N] [--no-figures]`` plus its own
    options (``--scene`` when it takes one). Exit 0 when written (and passed), 1 when written
    but not passed, 2 for bad input (one line, nothing run)."""

    def main(argv: Sequence[str] | None = None) -> int:
        prog = f"python -m upliftlab.comparisons.{study.name}"
        parser = argparse.ArgumentParser(prog=prog, description=study.title)
        if study.scene is not None:
            parser.add_argument("--scene", default=study.scene, help="scene name or path")
        parser.add_argument("--fast", action="store_true", help=study.help_fast)
        parser.add_argument("--out", help=f"output directory (default results/{study.name}"
                                          "[-fast])")
        parser.add_argument("--store", help="results store (default: OUT/store)")
        parser.add_argument("--scheduler",
                            help="Dask scheduler address (or DASK_SCHEDULER_ADDRESS)")
        parser.add_argument("--workers", type=int, help="worker processes (default: CPUs)")
        parser.add_argument("--no-figures", action="store_true", help="write no PNG")
        if study.arguments is not None:
            study.arguments(parser)
        args = parser.parse_args(argv)
        configure(0)

        def say(message):
            logger(study.name).info(f"{study.name}: {message}")

        try:
            if args.workers is not None:
                checks.integer_at_least("--workers", args.workers, 1)
            context = Context(fast=args.fast, out=args.out, store=args.store,
                              scheduler=args.scheduler, workers=args.workers)
            if study.context_from is not None:
                context = study.context_from(args, context, say)
            result = run_study(study, getattr(args, "scene", None), context)
        except InputError as exc:
            print(f"error: {exc}", file=sys.stderr)
            return EXIT_INPUT
        except RuntimeError as exc:  # a solver that gave up names its step (as the CLI does)
            message = " ".join(str(exc).split())
            print(f"error: {study.name} failed ({type(exc).__name__}): {message}",
                  file=sys.stderr)
            return EXIT_NUMERICS
        for line in study.describe(result):
            print(line)
        print(f"wrote {len(result.study.files)} files to {result.study.directory} in "
              f"{result.study.elapsed:.1f} s")
        return EXIT_OK if study.passed(result) else EXIT_FAILED

    return main
