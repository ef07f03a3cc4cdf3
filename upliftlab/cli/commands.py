"""The reduced model's commands: ``upliftlab run``, ``paper``, ``scenes`` and ``advise``.

Each reads and checks its scene, options and output folder before any work
(:mod:`upliftlab.outdir`), then runs and writes; the library raises, and
:func:`upliftlab.cli.main` turns what it raises into the exit code (:mod:`.exits`).
"""

from __future__ import annotations

import json
import shlex
import sys
import warnings

from .. import bounds
from ..budget import MAX_BUDGET_SECONDS
from ..extras import need_extra
from ..log import logger
from ..outdir import claim
from ..scenes.motion import INTEGRATORS
from ..workers import in_child
from .common import (FORCE_HELP, default_out, number, refuse_without_effect, say_if_rounded,
                     say_if_step_changed)
from .exits import EXIT_INTERRUPTED, EXIT_NUMERICS, EXIT_OK
from .stop import stop_flag

__all__ = ["add_reduced_commands", "run_command", "paper_command", "scenes_command",
           "advise_command", "paper_outputs", "REDUCED_KEYS",
           "ADVISE_KEYS"]


def add_reduced_commands(sub) -> None:
    """The parsers of ``run``, ``paper``, ``scenes`` and ``advise``."""
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
    r.add_argument("--force", action="store_true",
                   help=FORCE_HELP)
    r.add_argument("--budget", metavar="SECONDS",
                   help="refuse (exit 2) before any integration a run estimated to take "
                        "longer than this (default 3600 s); raise it to run one on purpose")

    pp = sub.add_parser("paper", help="Ewing's reduced-model study: Figs. 4, 5, 7-12 and a "
                                      "summary of the peaks (the main job)")
    pp.add_argument("--out", default=None, help="output directory (default results/paper)")
    pp.add_argument("--motion", help="path of the El Centro 1940 N-S record, if it is not on "
                                     "UPLIFTLAB_MOTIONS")
    pp.add_argument("--force", action="store_true", help=FORCE_HELP)

    sub.add_parser("scenes", help="list the packaged scenes")

    a = sub.add_parser("advise", help="measure a ladder of models and discretizations on a "
                                      "scene and recommend the cheapest within a tolerance")
    a.add_argument("scene", help="a packaged scene name or a TOML path")
    a.add_argument("--quantity", default="peak_u",
                   help="peak_u, peak_theta, peak_uplift or weighted_plastic_settlement "
                        "(Σ k_i ε_p,i / Σ k_i, as `upliftlab run` reports it)")
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
    a.add_argument("--macro-calibration", metavar="PATH",
                   help="scene with [soil]: `upliftlab calibrate`'s calibration.json of its "
                        "soil and footing, which puts the macro-element in the continuum ladder")
    a.add_argument("--json", action="store_true", help="print the advice as one JSON object")


#: What the reduced model reads of a scene (the continuum's tables are not its business).
REDUCED_KEYS = ("schema", "units", "title", "description", "reference", "structure*",
                "foundation*", "motion*", "analysis*")


def run_command(args) -> int:
    """``upliftlab run``: check everything, claim the folder, run the scene, write its files.

    An interruption (:mod:`.stop`) before the run is computed ends it at once with nothing
    written: the run is computed in a child process (:func:`upliftlab.workers.in_child`), since
    its compiled time loop would hold off a signal until its end. Once the response is here, a
    signal lets its data files be written (the figure is skipped), leaves the folder without
    its completion marker and ends with one line and exit 130. After the marker the run is
    complete: a signal then changes nothing."""
    with stop_flag() as flag:
        flag.defer()  # a signal only sets the flag, checked between the steps below
        return _run(args, flag)


def _run(args, flag) -> int:
    """:func:`run_command` with its ``flag`` (deferred)."""
    from ..scenes import load_scene

    if not args.no_figure:
        need_extra("upliftlab run", "matplotlib", why="or add --no-figure")
    scene = load_scene(args.scene, case=args.case, overrides=args.overrides, motion=args.motion)
    refuse_without_effect(args.overrides, "the reduced model", REDUCED_KEYS)
    dt = number("--dt", args.dt, high=bounds.KINDS["step"].high)
    budget = number("--budget", args.budget, high=MAX_BUDGET_SECONDS)  # not in the folder's name
    variant = {"overrides": list(args.overrides), "motion": args.motion, "dt": dt,
               "integrator": args.integrator}
    settings = {"command": "run", "scene": scene.name, "scene_digest": scene.digest,
                "overrides": list(scene.overrides), "motion": args.motion, "dt": dt,
                "integrator": args.integrator}
    motion = scene.build_motion()  # the record is read and checked before the folder
    outputs = [f"{scene.name}{suffix}" for suffix, wanted in
               ((".nc", True), (".csv", args.csv), (".png", not args.no_figure)) if wanted]
    flag.check()
    with claim(args.out, default_out(scene.name, variant), settings=settings,
               force=args.force, outputs=outputs) as out:
        response = in_child(_run_quietly, scene, motion, args.integrator, dt, budget,
                            check=flag.check)  # ends the child, raises, if a signal came
        for note in response.info.get("notes", []):
            logger("cli").warning(f"upliftlab run: note: {note}")
        duration = scene.analysis.duration or motion.duration
        say_if_rounded("upliftlab run", duration, response.info["steps"], response.info["dt"])
        say_if_step_changed("upliftlab run", "--dt" if dt is not None else "analysis.dt",
                            dt if dt is not None else scene.analysis.dt, response.info["dt"],
                            duration)
        say_if_step_changed("upliftlab run", "analysis.output_dt", scene.analysis.output_dt,
                            response.info["output_dt"], duration)
        out.start_writing()
        written = response.save(out.path / f"{scene.name}.nc", csv=args.csv)
        if not args.no_figure and not flag.stopped:
            from ..reduced.figures import response_figure, save
            written.append(save(response_figure(response), out.path / f"{scene.name}.png"))
        if flag.stopped:  # every data file written, no completion marker
            names = ", ".join(sorted(p.name for p in written))
            skipped = "" if args.no_figure else " (figure skipped)"
            print(f"upliftlab: interrupted ({flag.name}) after the run was computed; wrote "
                  f"{names} to {out.path}{skipped}, not marked complete; resume with: "
                  f"{shlex.join(['upliftlab', *args.argv])}", file=sys.stderr)
            return EXIT_INTERRUPTED
        out.complete(written)
        for path in written:
            logger("cli").info(f"upliftlab run: wrote {path}")
        if args.json:
            print(json.dumps(response.summary(), allow_nan=False))
        else:
            print(response.summary_line())
    return EXIT_OK


def _run_quietly(scene, motion, integrator, dt, budget):
    """The reduced model's response of ``scene`` (:func:`upliftlab.reduced.run`), its warnings
    silenced: the command prints the model's notes as notes."""
    from ..reduced import run

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return run(scene, motion=motion, integrator=integrator, dt=dt, budget=budget)


def paper_command(args) -> int:
    from ..reduced.paper import main as paper_main, record_for

    need_extra("upliftlab paper", "matplotlib")
    record = record_for(args.motion)  # the record is read and checked before any work
    settings = {"command": "paper", "motion": None if record is None else record.source}
    with claim(args.out, "results/paper", settings=settings, force=args.force,
               outputs=paper_outputs(record)) as out:
        summary = paper_main(out.path, record=record, claim=out)
    holds = sum(c["holds"] for c in summary["claims"])
    print(f"upliftlab paper: {len(summary['figures'])} figures and summary.md in {out.path}; "
          f"{holds} of {len(summary['claims'])} statements of the paper hold")
    if summary["note"]:
        print(f"upliftlab paper: {summary['note']}")
    return EXIT_OK


def paper_outputs(record) -> list[str]:
    """The files ``upliftlab paper`` writes with ``record`` (None: no El Centro record), named
    in its folder: a run per case the record allows (``runs/<key>.nc``), a figure per figure
    whose cases all ran, ``summary.json`` and ``summary.md``. Derived from the study's own
    table (:data:`~upliftlab.reduced.paper.FIGURES`) as :func:`~upliftlab.reduced.paper.
    paper_study` derives them, so that each is checked before any work."""
    from ..reduced.paper import FIGURES

    ran = {c.key for f in FIGURES for c in f.cases if record is not None or not c.needs_record}
    figures = [f"fig{f.number:02d}.png" for f in FIGURES if all(c.key in ran for c in f.cases)]
    return [*(f"runs/{key}.nc" for key in sorted(ran)), *figures, "summary.json", "summary.md"]


def scenes_command(_args) -> int:
    from ..scenes import load_scene, packaged_scenes

    for name in sorted(packaged_scenes()):
        scene = load_scene(name)
        cases = f" (cases: {', '.join(scene.cases)})" if scene.cases else ""
        print(f"{name}: {scene.title}{cases}")
    return EXIT_OK


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


def advise_command(args) -> int:
    from ..comparisons.advise.ladder import advise, format_advice

    refuse_without_effect(args.overrides, "upliftlab advise (it chooses the integrator and "
                          "step of the reduced model, the continuum's mesh and route)",
                          ADVISE_KEYS)
    budget = number("--budget", args.budget, high=1e9)
    advice = advise(args.scene, args.quantity, args.tol, case=args.case,
                    overrides=args.overrides, fast=args.fast, budget=budget,
                    map_path=args.map_path, macro_calibration=args.macro_calibration)
    print(json.dumps(advice.to_dict()) if args.json else format_advice(advice))
    return EXIT_OK if advice.certified else EXIT_NUMERICS
