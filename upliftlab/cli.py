"""The ``upliftlab`` command (also ``python -m upliftlab``).

    upliftlab run SCENE [--case C] [--motion NAME|PATH] [--set KEY=VALUE ...] [--out DIR] [--json]
                  [--force]
    upliftlab paper [--out DIR] [--motion PATH] [--force]
    upliftlab scenes
    upliftlab advise SCENE --quantity peak_u --tol 5% [--case C] [--set KEY=VALUE ...] [--fast]
                     [--budget SECONDS] [--map PATH] [--json]
    upliftlab report [--fast] [--out DIR] [--scheduler ADDR] [--force] [--budget SECONDS]
    upliftlab continuum SCENE [--analysis pushover|dynamic|impedance] [--case C]
                        [--set KEY=VALUE ...] [--mesh KEY=VALUE[,KEY=VALUE ...] ...]
                        [--theta-max RAD] [--steps N] [--motion NAME|PATH] [--a0 LIST]
                        [--boundary pml|lysmer] [--scale S] [--threads N] [--out DIR]
                        [--no-render] [--json] [--force]
    upliftlab opensees SCENE [--case A|B] [--set KEY=VALUE ...] [--out DIR] [--run] [--json]
                       [--force]
    upliftlab store verify|migrate|pack DIR [--sample N] [--name NAME]

Bad input ends with one line naming the field, the value and the valid range (exit code 2),
before any work and before any file is written: the scene, the options, the overrides (one
that the command would ignore is refused), the output folder (:mod:`upliftlab.outdir`) and the
run's cost (:mod:`upliftlab.budget`) are all checked first. A command that needs an optional
dependency says which extra to install. Every output folder gets a completion marker written
last (``upliftlab-run.json``); a folder that holds a different run is not overwritten without
``--force``. Exit codes: 0 done, 1 a verification or report section failed, 2 bad input,
3 a numerical failure (the message names the step, or the energy balance beyond its
tolerance), 130 interrupted (a continuum dynamic run writes what it computed, marked
incomplete).

BLAS and OpenMP use one thread unless the user set ``OMP_NUM_THREADS``,
``OPENBLAS_NUM_THREADS`` or ``MKL_NUM_THREADS``: the solves here are small and the machines
shared, where threaded BLAS is slower (measured in ``benchmarks/CONTINUUM_DESIGN.md``). They are
set before numpy loads (``import upliftlab`` loads nothing yet).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import fnmatch  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

from . import __version__, bounds  # noqa: E402
from .checks import InputError  # noqa: E402
from .log import configure, logger  # noqa: E402
from .outdir import claim, settings_digest  # noqa: E402
from .scene_motion import INTEGRATORS  # noqa: E402

__all__ = ["main", "parser", "EXIT_INPUT", "EXIT_FAILED", "EXIT_NUMERICS", "EXIT_INTERRUPTED",
           "need_extra"]

EXIT_FAILED, EXIT_INPUT, EXIT_NUMERICS, EXIT_INTERRUPTED = 1, 2, 3, 130


class _Parser(argparse.ArgumentParser):
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


def parser() -> argparse.ArgumentParser:
    from .cli_continuum import add_continuum
    from .cli_store import add_store

    p = _Parser(prog="upliftlab", description=(
        "Verification suite for structures that rock and uplift on flexible foundations."))
    p.add_argument("--version", action="version", version=f"upliftlab {__version__}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    r = sub.add_parser("run", help="run one scene in the reduced model")
    r.add_argument("scene", help="a packaged scene name (see `upliftlab scenes`) or a TOML path")
    r.add_argument("--case", help="a case of the scene, e.g. A, B or C")
    r.add_argument("--motion", help="a record name on UPLIFTLAB_MOTIONS or a file path; "
                                    "replaces the scene's motion")
    r.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    r.add_argument("--integrator", choices=list(INTEGRATORS))
    r.add_argument("--dt", help="time step (s); default: chosen from the scene")
    r.add_argument("--out", help="output directory (default results/<scene>-<case>, with a "
                                 "digest of the overrides when there are any)")
    r.add_argument("--csv", action="store_true", help="also write the histories as CSV")
    r.add_argument("--no-figure", action="store_true", help="skip the PNG figure")
    r.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    r.add_argument("--force", action="store_true", help="replace a different run in --out")

    pp = sub.add_parser("paper", help="Ewing's reduced-model study: Figs. 4, 5, 7-12 and a "
                                      "summary of the peaks (the main job)")
    pp.add_argument("--out", default=None, help="output directory (default results/paper)")
    pp.add_argument("--motion", help="path of the El Centro 1940 N-S record, if it is not on "
                                     "UPLIFTLAB_MOTIONS")
    pp.add_argument("--force", action="store_true", help="replace a different run in --out")

    sub.add_parser("scenes", help="list the packaged scenes")

    a = sub.add_parser("advise", help="measure a ladder of models and discretizations on a "
                                      "scene and recommend the cheapest within a tolerance")
    a.add_argument("scene", help="a packaged scene name or a TOML path")
    a.add_argument("--quantity", default="peak_u",
                   help="peak_u, peak_theta, peak_uplift or residual_settlement "
                        "(the permanent settlement Σ k_i ε_p,i / Σ k_i)")
    a.add_argument("--tol", default="5%", help="tolerance, e.g. 5%% or 0.05 (default 5%%)")
    a.add_argument("--case", help="a case of the scene, e.g. A, B or C")
    a.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    a.add_argument("--fast", action="store_true", help="reference N = 160, ladder up to N = 80; "
                   "continuum meshes 2, 4, 8 elements across instead of 4, 8, 16")
    a.add_argument("--budget", help="scene with [soil]: refuse (exit 2) before any run when the "
                                    "continuum ladder's estimated cost exceeds this many seconds "
                                    "(unless a Winkler map covers the scene: its evidence then)")
    a.add_argument("--map", dest="map_path", metavar="PATH",
                   help="a Winkler map's map.nc (default results/winkler_map/map.nc if present)")
    a.add_argument("--json", action="store_true", help="print the advice as one JSON object")

    rp = sub.add_parser("report", help="one self-contained HTML report: verification anchors, "
                                       "convergence orders and every comparison study")
    rp.add_argument("--fast", action="store_true", help="small grids and coarse meshes")
    rp.add_argument("--out", help="output directory (default results/report[-fast])")
    rp.add_argument("--scheduler", help="Dask scheduler address for the studies' sweeps")
    rp.add_argument("--force", action="store_true", help="replace a different run in --out")
    rp.add_argument("--budget", metavar="SECONDS",
                    help="refuse a study whose continuum runs are estimated above this many "
                         "seconds of one worker (default 3600; the Winkler map's kept runs "
                         "cost nothing)")

    add_continuum(sub)
    add_store(sub)

    o = sub.add_parser("opensees", help="write a standalone OpenSeesPy script of the scene (a "
                                        "BNWF model); with --run, run it beside upliftlab")
    o.add_argument("scene", help="a packaged scene name or a TOML path")
    o.add_argument("--case", help="a case of the scene: A or B (C has no OpenSees equivalent)")
    o.add_argument("--motion", help="a record name on UPLIFTLAB_MOTIONS or a file path")
    o.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    o.add_argument("--out", help="output directory (default results/<scene>-opensees)")
    o.add_argument("--dt", help="OpenSees Newmark step (s; default analysis.dt, else the record "
                                "step / n, 60 steps per shortest bonded period)")
    o.add_argument("--dashpots", default="clipped", help="foundation dashpots in OpenSees: "
                   "clipped (default, as upliftlab's), detaching or parallel")
    o.add_argument("--run", action="store_true", help="run it (the 'opensees' extra) and "
                   "upliftlab; write both models' peaks and histories side by side")
    o.add_argument("--timeout", default="3600", help="of the OpenSees run (s, default 3600)")
    o.add_argument("--json", action="store_true", help="with --run: print one JSON object "
                   "{\"upliftlab\": {...}, \"opensees\": {...}}")
    o.add_argument("--force", action="store_true", help="replace a different run in --out")
    for command in sub.choices.values():  # after the subcommand: upliftlab run X --quiet
        add_verbosity(command)
    return p


# ---------------------------------------------------------------------------------------------
# Shared checks
# ---------------------------------------------------------------------------------------------

#: The optional dependencies: import name -> (extra, what needs it).
EXTRAS = {"matplotlib": "plot", "skfem": "continuum", "meshio": "continuum",
          "pyvista": "render", "imageio": "render",
          "openseespy": "opensees", "distributed": "dask"}


def need_extra(command: str, *modules: str, why: str = "") -> None:
    """Refuse, in one line naming the extra to install, a command whose optional dependencies
    are missing."""
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        extras = sorted({EXTRAS[m] for m in missing})
        spec = ",".join(extras)
        raise InputError(f"{command} needs {', '.join(missing)} (the optional extra "
                         f"{' and '.join(extras)}): pip install 'upliftlab[{spec}]'"
                         + (f"; {why}" if why else ""))


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
        kind = "an integer" if integer else "a number"
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


def _short(settings: dict) -> str:
    return settings_digest(settings)[:8]


def default_out(stem: str, variant: dict) -> Path:
    """``results/<stem>``, with a digest of ``variant`` when it changes the scene's defaults
    (overrides, motion, step), so that different runs do not share a folder."""
    extra = {k: v for k, v in variant.items() if v}
    return Path("results") / (f"{stem}-{_short(extra)}" if extra else stem)


# ---------------------------------------------------------------------------------------------
# Commands
# ---------------------------------------------------------------------------------------------

#: What the reduced model reads of a scene (the continuum's tables are not its business).
REDUCED_KEYS = ("schema", "units", "title", "description", "reference", "structure*",
                "foundation*", "motion*", "analysis*")


def _run(args) -> int:
    from .scenes import load_scene

    if not args.no_figure:
        need_extra("upliftlab run", "matplotlib", why="or add --no-figure")
    scene = load_scene(args.scene, case=args.case, overrides=args.overrides, motion=args.motion)
    refuse_without_effect(args.overrides, "the reduced model", REDUCED_KEYS)
    dt = number("--dt", args.dt, high=bounds.KINDS["step"].high)
    variant = {"overrides": list(args.overrides), "motion": args.motion, "dt": dt,
               "integrator": args.integrator}
    settings = {"command": "run", "scene": scene.name, "scene_digest": scene.digest,
                "overrides": list(scene.overrides), "motion": args.motion, "dt": dt,
                "integrator": args.integrator}
    motion = scene.build_motion()  # the record is read and checked before the folder
    with claim(args.out, default_out(scene.name, variant), settings=settings,
               force=args.force) as out:
        from .reduced import run
        with warnings.catch_warnings():  # the model's notes are printed as notes, below
            warnings.simplefilter("ignore")
            response = run(scene, motion=motion, integrator=args.integrator, dt=dt)
        for note in response.info.get("notes", []):
            logger("cli").warning(f"upliftlab run: note: {note}")
        say_if_rounded("upliftlab run", scene.analysis.duration or motion.duration,
                       response.info["steps"], response.info["dt"])
        out.start_writing()
        written = response.save(out.path / f"{scene.name}.nc", csv=args.csv)
        if not args.no_figure:
            from .reduced.figures import response_figure, save
            written.append(save(response_figure(response), out.path / f"{scene.name}.png"))
        out.complete(written)
    for path in written:
        logger("cli").info(f"upliftlab run: wrote {path}")
    if args.json:
        print(json.dumps(response.summary(), allow_nan=False))
    else:
        print(response.summary_line())
    return 0


def _paper(args) -> int:
    from .reduced.paper import main as paper_main, record_for

    need_extra("upliftlab paper", "matplotlib")
    record = record_for(args.motion)  # the record is read and checked before any work
    settings = {"command": "paper", "motion": None if record is None else record.source}
    with claim(args.out, "results/paper", settings=settings, force=args.force) as out:
        summary = paper_main(out.path, record=record, claim=out)
    holds = sum(c["holds"] for c in summary["claims"])
    print(f"upliftlab paper: {len(summary['figures'])} figures and summary.md in {out.path}; "
          f"{holds} of {len(summary['claims'])} statements of the paper hold")
    if summary["note"]:
        print(f"upliftlab paper: {summary['note']}")
    return 0


def _scenes(_args) -> int:
    from .scenes import load_scene, packaged_scenes

    for name in sorted(packaged_scenes()):
        scene = load_scene(name)
        cases = f" (cases: {', '.join(scene.cases)})" if scene.cases else ""
        print(f"{name}: {scene.title}{cases}")
    return 0


def _report(args) -> int:
    need_extra("upliftlab report", "matplotlib", "skfem", "meshio", "pyvista",
               "imageio")
    if args.scheduler is not None:
        need_extra("upliftlab report --scheduler", "distributed")
    from .comparisons.report import command

    return command(args)  # 0: report written, every section ok; 1: a section failed


#: What the advisor reads of a scene: it chooses the foundation model, integrator and step.
ADVISE_KEYS = ("schema", "units", "title", "description", "reference", "structure*",
               *(f"foundation.{k}" for k in ("support", "half_width", "stiffness",
                                             "vertical_period", "law", "yield_multiple",
                                             "damping_ratio", "restitution", "impact_multiple",
                                             "impact_mass", "sway_stiffness", "sway_damping",
                                             "sliding_friction")),
               "motion*", "analysis.duration", "analysis.max_steps", "analysis.max_memory",
               "soil.*", *(f"continuum.{k}" for k in ("domain_width", "domain_depth", "element",
                                                      "grading", "base", "boundary", "intorder",
                                                      "energy_tolerance")))


def _advise(args) -> int:
    from .comparisons.advise import advise, format_advice

    refuse_without_effect(args.overrides, "upliftlab advise (it chooses the integrator and "
                          "step of the reduced model, the continuum's mesh and route)",
                          ADVISE_KEYS)
    budget = number("--budget", args.budget, high=1e9)
    advice = advise(args.scene, args.quantity, args.tol, case=args.case,
                    overrides=args.overrides, fast=args.fast, budget=budget,
                    map_path=args.map_path)
    print(json.dumps(advice.to_dict()) if args.json else format_advice(advice))
    return 0 if advice.certified else EXIT_NUMERICS


def _opensees(args) -> int:
    from .comparisons.opensees.command import command

    return command(args)  # 3 (RuntimeError) when a run fails


def main(argv: list[str] | None = None) -> int:
    try:
        args = parser().parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a one-line usage error
        return exc.code if isinstance(exc.code, int) else 0
    from .cli_continuum import continuum
    from .cli_store import store

    configure(int(args.verbose) - int(args.quiet))
    handler = {"run": _run, "paper": _paper, "scenes": _scenes, "report": _report,
               "continuum": continuum, "advise": _advise, "opensees": _opensees,
               "store": store}[args.command]
    try:
        return handler(args)
    except InputError as exc:
        print(f"upliftlab: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_INPUT
    except RuntimeError as exc:  # integration or Newton failures name step and residual
        print(f"upliftlab: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_NUMERICS
    except MemoryError:
        print("upliftlab: error: out of memory; the run's estimate was within "
              "analysis.max_memory, lower it or make the run smaller", file=sys.stderr)
        return EXIT_NUMERICS
    except KeyboardInterrupt:
        print("upliftlab: interrupted before any result was computed; nothing written",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # `upliftlab scenes | head`: the reader has gone
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())
