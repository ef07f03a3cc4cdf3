"""The ``upliftlab`` command (also ``python -m upliftlab``).

    upliftlab run SCENE [--case C] [--motion NAME|PATH] [--set KEY=VALUE ...] [--out DIR] [--json]
    upliftlab paper [--out DIR] [--motion PATH]
    upliftlab scenes
    upliftlab advise SCENE --quantity peak_u --tol 5% [--case C] [--set KEY=VALUE ...] [--fast]
                     [--json]
    upliftlab report [--fast] [--out DIR] [--scheduler ADDR]
    upliftlab continuum SCENE [--analysis pushover|dynamic] [--case C] [--set KEY=VALUE ...]
                        [--mesh KEY=VALUE[,KEY=VALUE ...] ...] [--theta-max RAD] [--steps N]
                        [--motion NAME|PATH] [--scale S] [--threads N] [--out DIR]
                        [--no-render] [--json]

Bad input ends with one line naming the field, the value and the valid range (exit code 2),
before any file is written. A failed computation (Newton, contact, or an energy balance beyond
its tolerance) ends with one line and exit code 3; an interrupted continuum dynamic run
(Ctrl-C or SIGTERM) writes what it computed, marked incomplete, and exits with code 130.

BLAS and OpenMP use one thread unless the user set ``OMP_NUM_THREADS``,
``OPENBLAS_NUM_THREADS`` or ``MKL_NUM_THREADS``: the solves here are small and the machines
shared, where threaded BLAS is slower (continuum-notes: 2–4 times on a loaded 2-core machine).
They are set before numpy loads (``import upliftlab`` loads nothing yet).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import signal  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from . import __version__  # noqa: E402
from .checks import InputError  # noqa: E402

__all__ = ["main", "parser"]

EXIT_INPUT, EXIT_NUMERICS, EXIT_INTERRUPTED = 2, 3, 130


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

    a = sub.add_parser("advise", help="measure a ladder of models and discretizations on a "
                                      "scene and recommend the cheapest within a tolerance")
    a.add_argument("scene", help="a packaged scene name or a TOML path")
    a.add_argument("--quantity", default="peak_u",
                   help="peak_u, peak_theta, peak_uplift or residual_settlement")
    a.add_argument("--tol", default="5%", help="tolerance, e.g. 5%% or 0.05 (default 5%%)")
    a.add_argument("--case", help="a case of the scene, e.g. A, B or C")
    a.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    a.add_argument("--fast", action="store_true", help="reference N = 160, ladder up to N = 80")
    a.add_argument("--json", action="store_true", help="print the advice as one JSON object")

    rp = sub.add_parser("report", help="one self-contained HTML report: verification anchors, "
                                       "convergence orders and every comparison study")
    rp.add_argument("--fast", action="store_true", help="small grids and coarse meshes")
    rp.add_argument("--out", help="output directory (default results/report[-fast])")
    rp.add_argument("--scheduler", help="Dask scheduler address for the studies' sweeps")

    c = sub.add_parser("continuum", help="run one scene in the continuum model: a rotation "
                                         "pushover or a dynamic run, with XDMF and pictures")
    c.add_argument("scene", help="a packaged scene name or a TOML path (needs a [soil] table)")
    c.add_argument("--analysis", default="pushover",
                   help=f"{' or '.join(CONTINUUM_ANALYSES)} (default pushover: rotation at "
                        "constant N = the structure's vertical weight)")
    c.add_argument("--case", help="a case of the scene")
    c.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene field by its dotted TOML key (repeatable)")
    c.add_argument("--mesh", action="append", default=[], metavar="KEY=VALUE[,KEY=VALUE]",
                   help=f"mesh options ({', '.join(MESH_KEYS)}), e.g. "
                        "elements_across=8,grading=2,element=Q2 (repeatable)")
    c.add_argument("--theta-max", help="largest rotation of the pushover (rad, > 0; default "
                                       "10 times the elastic half-plane's uplift rotation)")
    c.add_argument("--steps", default="40", help="rotation steps of the pushover (default 40; "
                                                 "two more below uplift if they are coarse)")
    c.add_argument("--motion", help="dynamic: a record name on UPLIFTLAB_MOTIONS or a path; "
                                    "replaces the scene's motion")
    c.add_argument("--scale", help="displacement magnification of the pictures (default: "
                                   "automatic, stated in each picture)")
    c.add_argument("--threads", default="1",
                   help="dynamic, explicit: threads of the compiled soil kernels (default 1; "
                        "more pays only on an otherwise idle machine)")
    c.add_argument("--out", help="output directory (default results/<scene>-continuum-"
                                 "<analysis>)")
    c.add_argument("--no-render", action="store_true", help="skip the PNG and GIF renders")
    c.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    return p


CONTINUUM_ANALYSES = ("pushover", "dynamic")
#: ``--mesh`` keys: the [continuum] fields that shape the mesh and its quadrature.
MESH_KEYS = ("elements_across", "grading", "element", "domain_width", "domain_depth",
             "intorder")


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


def _mesh_overrides(items: list[str]) -> list[str]:
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


def _number(name: str, text: str | None, *, integer: bool = False, low: float = 0.0):
    """A number > ``low`` (or an integer >= ``low``) given on the command line, or None."""
    if text is None:
        return None
    try:
        value = int(text) if integer else float(text)
    except ValueError:
        kind = "an integer" if integer else "a number"
        raise InputError(f"{name} = {text!r}: expected {kind}") from None
    if integer and value < low:
        raise InputError(f"{name} = {value}: must be an integer >= {low:g}")
    if not integer and not (value > low and math.isfinite(value)):
        raise InputError(f"{name} = {text}: must be a finite number > {low:g}")
    return value


def _say(message: str) -> None:
    print(f"upliftlab continuum: {message}", file=sys.stderr, flush=True)


def _continuum(args) -> int:
    from .scenes import load_scene

    if args.analysis not in CONTINUUM_ANALYSES:
        raise InputError(f"--analysis = {args.analysis!r}: must be one of "
                         f"{', '.join(CONTINUUM_ANALYSES)}")
    overrides = list(args.overrides) + _mesh_overrides(args.mesh)
    theta_max = _number("--theta-max", args.theta_max)
    steps = _number("--steps", args.steps, integer=True, low=2)
    scale = _number("--scale", args.scale)
    threads = _number("--threads", args.threads, integer=True, low=1)
    if args.analysis == "pushover" and args.motion is not None:
        raise InputError("--motion: only the dynamic analysis takes a motion")
    scene = load_scene(args.scene, case=args.case, overrides=overrides,
                       motion=args.motion if args.analysis == "dynamic" else None)
    if scene.soil is None:
        raise InputError(f"scene {scene.name!r}: soil is missing; the continuum model needs a "
                         "[soil] table")
    if args.analysis == "dynamic":
        try:
            from .continuum.dynamics import DynamicOptions
        except ImportError as exc:
            raise InputError(f"--analysis dynamic: upliftlab.continuum.dynamics cannot be "
                             f"imported ({exc})") from None
        motion = scene.build_motion()  # reads and checks the record before any meshing
    from .continuum import build_model

    out = Path(args.out or Path("results") / f"{scene.name}-continuum-{args.analysis}")
    started = time.perf_counter()
    model = build_model(scene)
    _say(f"{scene.name}: {model.disc.element}, {model.mesh.nelements} elements, "
         f"{model.dofs} DOFs, soil {scene.soil.model}")
    if args.analysis == "pushover":
        result = _pushover(model, scene, theta_max, steps)
    else:
        duration = scene.analysis.duration or motion.duration
        _say(f"{model.options.dynamics} dynamics, {duration:g} s of {motion.name} "
             f"(continuum.dynamics; --set analysis.duration=T runs the first T s)")
        result = _dynamic(model, scene, motion, DynamicOptions(threads=threads), out,
                          _dynamic_progress(duration, started))
        if isinstance(result, int):
            return result
    _say(f"solved in {time.perf_counter() - started:.1f} s")
    from .continuum.output import (dynamic_summary, pushover_summary, summary_line,
                                   write_outputs)

    write_outputs(out, model, result, scene=scene, renders=not args.no_render, scale=scale,
                  progress=_say)
    summary = (pushover_summary(result) if args.analysis == "pushover"
               else dynamic_summary(result, width=model.width))
    if args.json:
        print(json.dumps(summary))
    else:
        units = {"length": scene.units.length,
                 "moment/length": f"{scene.units.force}*{scene.units.length}/{scene.units.length}"}
        print(summary_line(summary, units))
    return 0


def _dynamic(model, scene, motion, options, out: Path, progress):
    """The dynamic run, or the exit code of a run that was interrupted (its partial result
    written, marked incomplete) or failed its energy check (its result written, marked
    failed)."""
    from .continuum.dynamics import run_dynamic
    from .continuum.run_control import EnergyBalanceError, Interrupted

    def terminate(signum, frame):
        raise KeyboardInterrupt(f"signal {signum}")

    previous = signal.signal(signal.SIGTERM, terminate)
    try:
        return run_dynamic(model, scene, motion, options, progress=progress)
    except Interrupted as exc:
        path = exc.result.save(out / "result.nc")
        until = exc.result.metadata["completed_until"]
        print(f"upliftlab: interrupted at t = {until:.4g} s of the motion; wrote the rows "
              f"computed so far to {path} (attribute incomplete = 1, completed_until = "
              f"{until:.4g} s)", file=sys.stderr)
        return EXIT_INTERRUPTED
    except EnergyBalanceError as exc:
        exc.result.metadata["energy_check"] = "failed"
        path = exc.result.save(out / "result.nc")
        print(f"upliftlab: error: {exc} (result written to {path}, energy_check = failed)",
              file=sys.stderr)
        return EXIT_NUMERICS
    finally:
        signal.signal(signal.SIGTERM, previous)


def _dynamic_progress(duration: float, started: float):
    """A ``progress(k, n, state)`` that reports every 5 % of a dynamic run: simulated time,
    elapsed wall time and the ETA from the rate of the time loop so far."""
    first = {}

    def progress(k, n, state):
        now = time.perf_counter()
        first.setdefault("time", (now, k))
        tick = 20 * k // max(n, 1)
        if k and k != n and tick <= first.get("tick", -1):
            return
        first["tick"] = tick
        t0, k0 = first["time"]
        rate = (now - t0) / (k - k0) if k > k0 else math.nan
        eta = rate * (n - k)
        _say(f"t = {duration * k / max(n, 1):.3f} of {duration:g} s ({k / max(n, 1):.0%}), "
             f"elapsed {now - started:.1f} s, ETA {eta:.0f} s"
             + ("" if math.isfinite(eta) else " (measuring)")
             + f": θ = {state.q[2]:.4g} rad, N = {state.N:.4g}")
    return progress


def _pushover(model, scene, theta_max, steps):
    from .continuum import rotation_pushover
    from .continuum.output import rotation_schedule

    soil, N, B = scene.soil, scene.structure.vertical_weight, model.width
    theta_on = 2.0 * N * (1.0 - soil.poisson_ratio) / (math.pi * soil.shear_modulus * B)
    theta_max = 10.0 * theta_on if theta_max is None else theta_max
    rotations = rotation_schedule(theta_max, steps, theta_on)
    _say(f"rotation pushover at N = {N:g} to θ = {theta_max:.4g} rad in {rotations.size - 1} "
         f"steps (elastic half-plane uplift at θ_on = {theta_on:.4g} rad)")

    def progress(k, n, state):
        _say(f"step {k + 1}/{n}: θ = {state.q[2]:.4g} rad, M = {state.M:.4g}, "
             f"{state.iterations} Newton iterations")

    return rotation_pushover(model, N, rotations, record_fields=True, progress=progress)


def _report(args) -> int:
    from .comparisons.report import command

    return command(args)  # 0: verification passed; 1: a verification row failed


def _advise(args) -> int:
    from .comparisons.advise import advise, format_advice

    advice = advise(args.scene, args.quantity, args.tol, case=args.case,
                    overrides=args.overrides, fast=args.fast)
    print(json.dumps(advice.to_dict()) if args.json else format_advice(advice))
    return 0 if advice.recommendation is not None else EXIT_NUMERICS


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    handler = {"run": _run, "paper": _paper, "scenes": _scenes, "report": _report,
               "continuum": _continuum, "advise": _advise}[args.command]
    try:
        return handler(args)
    except InputError as exc:
        print(f"upliftlab: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        print("upliftlab: interrupted before any result was computed; nothing written",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    except RuntimeError as exc:  # integration or Newton failures name step and residual
        print(f"upliftlab: error: {exc}", file=sys.stderr)
        return EXIT_NUMERICS
