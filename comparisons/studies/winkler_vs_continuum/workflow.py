"""The study's protocol: compute, run, its definition and its command line."""

from __future__ import annotations

import contextlib
import os
from dataclasses import replace
from pathlib import Path

from ....scenes import Scene, load_scene
from ...beds.continuum_points import evaluate_continuum
from ...beds.pushover import bed_response
from ...beds.stiffness import calibrate, end_zone
from ...framework.protocol import Context, Study, run_study
from ...framework.store import Store
from ...framework.study import require_matplotlib
from ...framework.sweep import run_sweep, sweep_executor
from .analysis import dynamic_quantities, error_table, recommend
from .closed_forms import closed_form_checks
from .dynamics import compare_dynamics, dynamic_points
from .options import FAST_OPTIONS, FULL_OPTIONS, Options, STUDY, check_options, check_scene
from .output import write
from .reference import continuum_points, continuum_reference
from .result import WinklerVsContinuum


def compute(scene: str | Scene, ctx: Context) -> WinklerVsContinuum:
    """The continuum reference, the calibrated beds, their errors and the dynamics of
    ``scene`` (with ``[soil]``) under ``ctx.options`` (default :data:`FAST_OPTIONS` or
    :data:`FULL_OPTIONS`). Every parameter is checked before anything runs."""
    fast = ctx.fast
    options = check_options(ctx.options or (FAST_OPTIONS if fast else FULL_OPTIONS))
    if options.figures:
        require_matplotlib(STUDY)
    scene = scene if isinstance(scene, Scene) else load_scene(scene)
    if fast and options.fast_overrides:
        scene = scene.with_overrides(*options.fast_overrides)
    check_scene(scene)
    end_zone(scene.foundation.half_width, options.springs, options.end_length)
    static, theta_on = continuum_points(scene, options)
    motions, dynamic, reason = dynamic_points(scene, options, fast)
    executor = ctx.executor
    with contextlib.ExitStack() as stack:
        if executor is None:  # one worker per point at most
            workers = min(os.cpu_count() or 1, len(static) + len(dynamic))
            executor = stack.enter_context(sweep_executor(ctx.scheduler, workers=workers))
        records = run_sweep(evaluate_continuum, static + dynamic, ctx.store, study=STUDY,
                            chunk=1, executor=executor, progress=ctx.progress)  # statics first
    stopped = [r["error"] for r in records[:len(static)] if "error" in r]
    if stopped:  # the study's whole comparison rests on these paths
        raise RuntimeError(f"the continuum's statics of {scene.name} did not finish: "
                           f"{stopped[0]}")
    ref = continuum_reference(scene, theta_on, records[:len(static)])
    calibrations = calibrate(ref, options)
    beds = tuple(bed_response(scene, c, ref) for c in calibrations)
    dynamics = compare_dynamics(scene, calibrations, motions, dynamic, records[len(static):],
                                reason)
    table = error_table(ref, beds, options, dynamic_quantities(ref, scene, dynamics),
                        dynamics.runs)
    return WinklerVsContinuum(None, scene, ref, calibrations, beds, table,
                              recommend(table, options.adequate), closed_form_checks(ref, beds),
                              dynamics, options)


def run(scene: str | Scene = "strip_footing_clay", fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        options: Options | None = None, executor=None, scheduler=None,
        progress=None) -> WinklerVsContinuum:
    """Run the study on ``scene`` (with ``[soil]``; its own motion is used for nothing static).

    ``fast`` applies ``options.fast_overrides`` (a coarse mesh) and the smaller
    :data:`FAST_OPTIONS` paths; full mode uses the scene's mesh and :data:`FULL_OPTIONS`.
    ``out``: output directory (default ``results/winkler_vs_continuum[-fast]``); ``store`` the
    results store (default ``<out>/store``); ``executor``/``scheduler``/``progress`` go to
    :func:`.sweep.run_sweep`. Every parameter is checked before anything runs.
    """
    return run_study(DEFINITION, scene, Context(fast=fast, out=out, store=store, options=options,
                                                executor=executor, scheduler=scheduler,
                                                progress=progress))


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _arguments(parser) -> None:
    parser.add_argument("--end-length", type=float, default=Options.end_length,
                        help="end-zone length of the end-stiffened bed, fraction of b")
    parser.add_argument("--no-dynamic", action="store_true")


def _context_from(args, ctx: Context, say) -> Context:
    base = FAST_OPTIONS if args.fast else FULL_OPTIONS
    return replace(ctx, options=replace(base, end_length=args.end_length,
                                        dynamic=not args.no_dynamic,
                                        figures=not args.no_figures))


def _describe(result: WinklerVsContinuum) -> list[str]:
    return [result.recommendation.text,
            result.dynamics.reason if not result.dynamics.available else "dynamics compared"]


DEFINITION = Study(STUDY, "Winkler against the continuum",
                   "How well the reduced model's Winkler bed matches the plane-strain continuum.",
                   Options, compute, write, scene="strip_footing_clay", describe=_describe,
                   arguments=_arguments, context_from=_context_from,
                   help_fast="coarse mesh, short paths")
