"""The ``upliftlab`` command (also ``python -m upliftlab``).

    upliftlab run SCENE [--case C] [--motion NAME|PATH] [--set KEY=VALUE ...] [--out DIR] [--json]
    upliftlab paper [--out DIR] [--motion PATH]
    upliftlab scenes

Bad input ends with one line naming the field, the value and the valid range (exit code 2),
before any file is written.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from . import __version__
from .checks import InputError

__all__ = ["main", "parser"]

EXIT_INPUT, EXIT_NUMERICS = 2, 3


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="upliftlab", description=(
        "Verification suite for structures that rock and uplift on flexible foundations."))
    p.add_argument("--version", action="version", version=f"upliftlab {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    r = sub.add_parser("run", help="run one scene in the reduced model")
    r.add_argument("scene", help="a packaged scene name (see `upliftlab scenes`) or a TOML path")
    r.add_argument("--case", help="a case of the scene, e.g. A, B or C")
    r.add_argument("--motion", help="a record name on UPLIFTLAB_MOTIONS or a file path; "
                                    "replaces the scene's motion")
    r.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    r.add_argument("--integrator", choices=["events", "rk4", "abm4", "newmark", "hht"])
    r.add_argument("--dt", type=float, help="time step (s); default: chosen from the scene")
    r.add_argument("--out", help="output directory (default results/<scene>)")
    r.add_argument("--csv", action="store_true", help="also write the histories as CSV")
    r.add_argument("--no-figure", action="store_true", help="skip the PNG figure")
    r.add_argument("--json", action="store_true", help="print the summary as one JSON object")

    pp = sub.add_parser("paper", help="Ewing's reduced-model study: Figs. 4, 5, 7-12 and a "
                                      "summary of the peaks (the main job)")
    pp.add_argument("--out", default="results/paper", help="output directory")
    pp.add_argument("--motion", help="path of the El Centro 1940 N-S record, if it is not on "
                                     "UPLIFTLAB_MOTIONS")

    sub.add_parser("scenes", help="list the packaged scenes")
    return p


def _run(args) -> int:
    from .reduced import run
    from .reduced.figures import response_figure, save
    from .scenes import load_scene

    scene = load_scene(args.scene, case=args.case, overrides=args.overrides, motion=args.motion)
    if args.dt is not None and not args.dt > 0:
        raise InputError(f"--dt = {args.dt:g}: must be > 0")
    response = run(scene, integrator=args.integrator, dt=args.dt)
    out = Path(args.out) if args.out else Path("results") / scene.name
    written = response.save(out / f"{scene.name}.nc", csv=args.csv)
    if not args.no_figure:
        written.append(save(response_figure(response), out / f"{scene.name}.png"))
    for path in written:
        print(f"upliftlab run: wrote {path}", file=sys.stderr)
    if args.json:
        print(json.dumps(response.summary()))
    else:
        print(response.summary_line())
    return 0


def _paper(args) -> int:
    from .reduced.paper import main as paper_main

    summary = paper_main(args.out, motion=args.motion)
    holds = sum(c["holds"] for c in summary["claims"])
    print(f"upliftlab paper: {len(summary['figures'])} figures and summary.md in {args.out}; "
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


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    handler = {"run": _run, "paper": _paper, "scenes": _scenes}[args.command]
    try:
        return handler(args)
    except InputError as exc:
        print(f"upliftlab: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except RuntimeError as exc:  # integration or Newton failures name step and residual
        print(f"upliftlab: error: {exc}", file=sys.stderr)
        return EXIT_NUMERICS
