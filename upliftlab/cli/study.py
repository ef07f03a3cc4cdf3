"""``upliftlab study NAME [--fast] [--out DIR] [--store DIR] [--scheduler ADDR] [--workers N]
[--no-figures] [--force] [the study's own options]``: one study of
:mod:`upliftlab.comparisons.studies`, on its own (the report runs them all).

The output folder is claimed as every command's is (:func:`upliftlab.outdir.claim`): locked
while the study runs, refused if it holds another run's results (other settings) unless
``--force``, and marked complete at the end. A study names its files only as it writes them,
so each is checked then: a file there that upliftlab did not make is refused, never replaced
(``guard``), with or without ``--force``. Its points are in its store by then, so the run that
follows the user's move costs no computation again.

Each study declares its options (:class:`~upliftlab.comparisons.framework.protocol.Study`):
``--scene`` where it takes one, and what its ``arguments`` add. Exit 0 when written and its
checks passed, 1 when written but a check failed, 2 for bad input (one line, nothing run), 3
when a solver gave up or kept results moved (:mod:`.exits`).
"""

from __future__ import annotations

import argparse

from .. import checks
from ..log import configure, logger
from ..outdir import claim, probe_folder
from .common import Parser
from .exits import EXIT_FAILED, EXIT_OK

__all__ = ["add_study", "study_command"]

#: Options that say where and how a study runs, not what it computes: a run into the same
#: folder with other values of these is the same run. A study's ``budget`` only refuses a run
#: before it starts, so it is one of them.
_NOT_SETTINGS = frozenset({"out", "store", "scheduler", "workers", "force", "budget"})


def add_study(sub) -> None:
    """The parser of ``upliftlab study``: the study's name, then its own options."""
    from ..comparisons.studies.registry import STUDIES

    s = sub.add_parser("study", help="run one study of the report on its own "
                                     "(`upliftlab study NAME --help` for its options)")
    s.add_argument("name", choices=STUDIES, metavar="NAME",
                   help=f"the study: {', '.join(STUDIES)}")
    s.add_argument("options", nargs=argparse.REMAINDER, help="the study's options")


def _parser(study) -> argparse.ArgumentParser:
    parser = Parser(prog=f"upliftlab study {study.name}", description=study.title)
    if study.scene is not None:
        parser.add_argument("--scene", default=study.scene, help="scene name or path")
    parser.add_argument("--fast", action="store_true", help=study.help_fast)
    parser.add_argument("--out", help=f"output directory (default results/{study.name}[-fast])")
    parser.add_argument("--store", help="results store (default: OUT/store)")
    parser.add_argument("--scheduler", help="Dask scheduler address (or DASK_SCHEDULER_ADDRESS)")
    parser.add_argument("--workers", help="worker processes (default: CPUs)")
    parser.add_argument("--no-figures", action="store_true", help="write no PNG")
    parser.add_argument("--force", action="store_true",
                        help="replace another run's results in --out (upliftlab's files only)")
    if study.arguments is not None:
        study.arguments(parser)
    return parser


def study_command(args) -> int:
    """Run the study ``args.name`` with its options; the exit code of the module docstring."""
    from ..comparisons.framework.protocol import Context, default_out, run_study
    from ..comparisons.studies.registry import definition

    study = definition(args.name)
    options = _parser(study).parse_args(args.options)
    configure(int(getattr(args, "verbose", False)) - int(getattr(args, "quiet", False)))

    def say(message):
        logger(study.name).info(f"{study.name}: {message}")

    workers = None
    if options.workers is not None:
        from .common import number

        workers = number("--workers", options.workers, integer=True, low=1, high=4096)
    checks.boolean("--fast", options.fast)
    if options.scheduler is not None:
        checks.scheduler_address("--scheduler", options.scheduler, in_process=False)
    checks.boolean("--force", options.force)
    if options.store is not None:  # a file, or a place nothing can be made: before work
        probe_folder(options.store, "--store")
    settings = {"command": "study", "study": study.name,
                **{key: value for key, value in sorted(vars(options).items())
                   if key not in _NOT_SETTINGS}}
    with claim(options.out, default_out(study.name, options.fast), settings=settings,
               force=options.force, guard=True) as folder:
        context = Context(fast=options.fast, out=folder.path, store=options.store,
                          scheduler=options.scheduler, workers=workers)
        if study.context_from is not None:
            context = study.context_from(options, context, say)
        try:
            result = run_study(study, getattr(options, "scene", None), context)
        except RuntimeError as exc:  # a solver that gave up: which study, what kind, its message
            raise RuntimeError(f"{study.name} failed ({type(exc).__name__}): {exc}") from exc
        folder.complete(result.study.files)
    for line in study.describe(result):
        print(line)
    print(f"wrote {len(result.study.files)} files to {result.study.directory} in "
          f"{result.study.elapsed:.1f} s")
    return EXIT_OK if study.passed(result) else EXIT_FAILED
