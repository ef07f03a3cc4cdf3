"""The study's protocol: compute, run, its definition and its command line."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from ....checks import InputError
from ...framework.protocol import Context, Study, run_study
from ...framework.store import Store
from ...framework.study import require_matplotlib
from ...framework.sweep import run_sweep, sweep_executor
from .analysis import SpeedVsError, continuum_note, scene_result
from .grid import FAST_GRID, FULL_GRID, Grid, Options, STUDY, SceneSpec, check_grid, check_options
from .output import write
from .points import evaluate_point, load_spec, measurement_context, scene_points
from .summary import short_label, table_note


def _panel(scene, grid: Grid) -> Grid:
    if scene is None:
        return grid
    if isinstance(scene, SceneSpec):
        return replace(grid, scenes=(scene,))
    if isinstance(scene, str):
        return replace(grid, scenes=(SceneSpec(scene, scene),))
    if isinstance(scene, Sequence):
        return replace(grid, scenes=tuple(scene))
    raise InputError(f"scene = {scene!r}: expected None (the panel), a scene name or a "
                     "SceneSpec, or a list of SceneSpec")


def compute(scene, ctx: Context) -> SpeedVsError:
    """Every point of the panel (``scene``: None for ``ctx.grid``'s panel, a scene or scene
    specs) under ``ctx.options``; ``ctx.workers`` local processes (default: the CPU count)."""
    grid = check_grid(_panel(scene, ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID)))
    options = check_options(ctx.options or Options())
    if options.figures:
        require_matplotlib(STUDY)
    scenes = [load_spec(s) for s in grid.scenes]
    nworkers = ctx.workers or (os.cpu_count() or 1)
    context = measurement_context(nworkers)
    per_scene = [scene_points(s, grid, context, spec.continuum_levels)
                 for spec, s in zip(grid.scenes, scenes)]
    flat = [p for pts, refs in per_scene for p in pts + refs]
    executor = ctx.executor
    with contextlib.ExitStack() as stack:
        if executor is None:
            executor = stack.enter_context(sweep_executor(ctx.scheduler, workers=nworkers))
        records = run_sweep(evaluate_point, flat, ctx.store, study=STUDY, executor=executor,
                            progress=ctx.progress)
    results, k = [], 0
    for spec, s, (pts, refs) in zip(grid.scenes, scenes, per_scene):
        recs, k = records[k:k + len(pts)], k + len(pts)
        ref_recs, k = records[k:k + len(refs)], k + len(refs)
        results.append(scene_result(spec, s, pts, recs, refs, ref_recs, grid, options))
    sessions = len({r.get("session", "") for r in records if "error" not in r})
    return SpeedVsError(None, tuple(results), grid, options, context,
                        continuum_note(grid, results), sessions)


def run(scene: str | SceneSpec | Sequence[SceneSpec] | None = None, fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        grid: Grid | None = None, options: Options | None = None, executor=None,
        scheduler=None, progress=None, workers: int | None = None) -> SpeedVsError:
    """Run the study on ``scene`` (default: the panel of :data:`FULL_GRID`, or
    :data:`FAST_GRID` with ``fast``: two short pulse scenes, N = 10, 40, 160).

    ``out``: output directory (default ``results/speed_vs_error[-fast]``); ``store``: the
    results store (default ``<out>/store``); ``executor``/``scheduler``/``progress`` go to
    :func:`.sweep.run_sweep`; ``workers`` local processes (default: the CPU count). Every
    parameter and scene is checked before anything runs.
    """
    return run_study(DEFINITION, scene, Context(
        fast=fast, out=out, store=store, grid=grid, options=options, executor=executor,
        scheduler=scheduler, progress=progress, workers=workers))


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _context_from(args, ctx: Context, say) -> Context:
    return replace(ctx, options=Options(figures=not args.no_figures))


def _describe(result: SpeedVsError) -> list[str]:
    lines = []
    for s in result.scenes:
        p = s.cheapest("u", 0.05)
        best = table_note(s, "u") or ("none" if p is None else
                                       f"{short_label(p)} ({p.runtime * 1e3:.3g} ms)")
        lines.append(f"{s.label}: reference {s.reference.runtime:.3g} s; cheapest within 5 % "
                     f"in peak u: {best}")
    return lines


DEFINITION = Study(STUDY, "Speed against error",
                   "What each model and discretisation costs for the error it leaves.", Options,
                   compute, write, describe=_describe, context_from=_context_from,
                   help_fast="two short pulses, few levels")
