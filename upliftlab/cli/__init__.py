"""The ``upliftlab`` command (also ``python -m upliftlab``)::

    upliftlab run SCENE [--case C] [--motion NAME|PATH] [--set KEY=VALUE ...] [--out DIR] [--json]
                  [--force] [--budget SECONDS]
    upliftlab paper [--out DIR] [--motion PATH] [--force]
    upliftlab scenes
    upliftlab advise SCENE --quantity peak_u --tol 5% [--case C] [--set KEY=VALUE ...] [--fast]
                     [--budget SECONDS] [--map PATH] [--json]
    upliftlab report [--fast] [--out DIR] [--scheduler ADDR] [--force] [--budget SECONDS]
                     [--pdf A4|Letter ...]
    upliftlab study NAME [--fast] [--out DIR] [--store DIR] [the study's options]
    upliftlab continuum SCENE [--analysis pushover|dynamic|impedance] [--case C]
                        [--set KEY=VALUE ...] [--mesh KEY=VALUE[,KEY=VALUE ...] ...]
                        [--theta-max RAD] [--steps N] [--motion NAME|PATH] [--a0 LIST]
                        [--boundary pml|lysmer] [--scale S] [--threads N] [--out DIR]
                        [--no-render] [--json] [--force] [--budget SECONDS]
    upliftlab opensees SCENE [--case A|B] [--set KEY=VALUE ...] [--out DIR] [--run] [--json]
                       [--force]
    upliftlab calibrate SCENE [--case C] [--set KEY=VALUE ...] [--mesh KEY=VALUE ...]
                        [--fs-v LIST] [--evaluations N] [--workers N] [--out DIR] [--json]
                        [--force] [--budget SECONDS]
    upliftlab store verify|migrate|pack DIR [--sample N] [--name NAME]

Bad input ends with one line naming the field, the value and the valid range (exit code 2),
before any work and before any file is written: the scene, the options, the overrides (one
that the command would ignore is refused), the output folder (:mod:`upliftlab.outdir`) and the
run's cost (:mod:`upliftlab.budget`) are all checked first. A command that needs an optional
dependency says which extra to install. Every output folder gets a completion marker written
last (``upliftlab-run.json``); a folder that holds a different run is not overwritten without
``--force``. The library raises; this package alone turns what it raises into exit codes
(:mod:`.exits`): 0 done, 1 a verification, report section or study check failed, 2 bad input,
3 a numerical failure (the message names the step, or the energy balance beyond its
tolerance; no space left on device: the unfinished file removed), 130 interrupted.

**Interruptions.** Ctrl-C and SIGTERM end every command the same way, at any moment: one line
that says what was kept and the command that resumes the run (:func:`.exits.interrupted_line`),
the output folder unlocked and without its completion marker, no part file, and every worker
process the command started ended (:func:`upliftlab.workers.process_pool`). Finished points of
a study stay in its store, so the same command resumes it. A continuum dynamic run turns the
interruption into a flag its time loop checks and writes what it computed, marked incomplete
(:mod:`.continuum`, :mod:`.stop`). ``upliftlab run`` computes in a child process, which a
signal ends at once (a compiled loop would hold the signal off until its end), and once the
response is computed writes its data files before it ends (:func:`.commands.run_command`).
A signal while the command loads (numpy, from the package's first line:
:data:`upliftlab.COMMAND_SIGNALS`) ends it with the same line; one after the exit code is
chosen changes nothing.

BLAS and OpenMP use one thread unless the user set ``OMP_NUM_THREADS``,
``OPENBLAS_NUM_THREADS`` or ``MKL_NUM_THREADS``: the solves here are small and the machines
shared, where threaded BLAS is slower (measured in ``benchmarks/CONTINUUM_DESIGN.md``). They are
set before numpy loads (``import upliftlab`` loads nothing yet).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import sys  # noqa: E402

from .. import __version__  # noqa: E402
from ..checks import InputError  # noqa: E402
from ..log import configure  # noqa: E402
from .common import Parser, add_verbosity  # noqa: E402
from .exits import (EXIT_INPUT, EXIT_INTERRUPTED, EXIT_NUMERICS, disk_full_line,  # noqa: E402
                    exit_code, interrupted_line, one_line)
from .stop import stop_flag  # noqa: E402

__all__ = ["main", "parser"]


def parser() -> Parser:
    """The parser of every subcommand."""
    from .calibrate import add_calibrate
    from .commands import add_reduced_commands
    from .continuum import add_continuum
    from .opensees import add_opensees
    from .report import add_report
    from .store import add_store
    from .study import add_study

    p = Parser(prog="upliftlab", description=(
        "Verification suite for structures that rock and uplift on flexible foundations."))
    p.add_argument("--version", action="version", version=f"upliftlab {__version__}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=Parser)
    add_reduced_commands(sub)
    add_report(sub)
    add_continuum(sub)
    add_opensees(sub)
    add_calibrate(sub)
    add_study(sub)
    add_store(sub)
    for command in sub.choices.values():  # after the subcommand: upliftlab run X --quiet
        add_verbosity(command)
    return p


def _handler(command: str):
    from . import calibrate, commands, continuum, opensees, report, store, study

    return {"run": commands.run_command, "paper": commands.paper_command,
            "scenes": commands.scenes_command, "advise": commands.advise_command,
            "report": report.report_command, "continuum": continuum.continuum,
            "opensees": opensees.opensees_command, "study": study.study_command,
            "store": store.store, "calibrate": calibrate.calibrate_command}[command]


def main(argv: list[str] | None = None) -> int:
    """Run the command line ``argv`` (None: this process's own, as the ``upliftlab`` command);
    its exit code (:mod:`.exits`).

    SIGINT and SIGTERM raise KeyboardInterrupt while the command runs (:mod:`.stop`), so that
    every ``finally`` of the command runs, and end it with one line. One that came while the
    command loaded (:data:`upliftlab.COMMAND_SIGNALS`) or while the parser loaded the commands
    ends it before any work; one whose KeyboardInterrupt was swallowed (raised in a weakref
    callback) ends it when the command returns. Once the exit code is chosen, a signal no longer
    changes it."""
    command = argv is None
    argv = sys.argv[1:] if argv is None else list(argv)
    with stop_flag() as flag:
        if command:
            from .. import COMMAND_SIGNALS
            flag.adopt(COMMAND_SIGNALS)
        try:
            flag.defer()  # while the parser loads the commands, a signal only sets the flag
            code = _main(argv, flag)
        except KeyboardInterrupt as exc:  # also one that came while _main printed its line
            flag.deferred = True
            print(interrupted_line(exc, argv), file=sys.stderr)
            code = EXIT_INTERRUPTED
        flag.deferred = True  # the code is chosen: a signal now only sets the flag
        return code


def _main(argv: list[str], flag) -> int:
    """:func:`main` after its signal handlers are set: the exit code of the command ``argv``
    (``flag``: its :class:`.stop.StopFlag`)."""
    try:
        args = parser().parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a one-line usage error
        return exc.code if isinstance(exc.code, int) else 0
    configure(int(args.verbose) - int(args.quiet))
    args.argv = argv  # a command that names how to resume it
    try:
        flag.deferred = False  # the command's own code: a signal raises where it comes
        flag.check()
        code = _handler(args.command)(args)
        flag.check()  # a signal whose KeyboardInterrupt a weakref callback swallowed
        return code
    except InputError as exc:
        print(f"upliftlab: error: {one_line(exc)}", file=sys.stderr)
        return EXIT_INPUT
    except RuntimeError as exc:  # integration or Newton failures name step and residual
        print(f"upliftlab: error: {one_line(exc)}", file=sys.stderr)
        return exit_code(exc)
    except MemoryError:
        print("upliftlab: error: out of memory; the run's estimate was within "
              "analysis.max_memory, lower it or make the run smaller", file=sys.stderr)
        return EXIT_NUMERICS
    except KeyboardInterrupt as exc:
        flag.deferred = True  # a second signal does not cut the line short
        print(interrupted_line(exc, argv), file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # `upliftlab scenes | head`: the reader has gone
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except OSError as exc:
        if exit_code(exc) != EXIT_NUMERICS:
            raise
        print(disk_full_line(exc), file=sys.stderr)
        return EXIT_NUMERICS
