"""The study's protocol: compute its dataset, write it, run, its definition and its command
line."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from ....checks import InputError
from ....provenance import provenance
from ...framework.protocol import Context, Study, StudyRun, run_study
from ...framework.store import Store
from ...framework.study import StudyResult, require_matplotlib, write_study
from ...framework.sweep import run_sweep, sweep_executor
from .analysis import cheapest, continuum_note, runs, table_note
from .dataset import runs_dataset
from .figures import write_figures
from .grid import FAST_GRID, FULL_GRID, Grid, Options, STUDY, SceneSpec, check_grid, check_options
from .points import (continuum_status, evaluate_point, load_spec, measurement_context,
                     scene_points)
from .summary import context, key_numbers, short_label, summarise
from .tables import write_tables


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


def compute(scene, ctx: Context):
    """Every point of the panel (``scene``: None for ``ctx.grid``'s panel, a scene or scene
    specs) under ``ctx.options``; ``ctx.workers`` local processes (default: the CPU count).
    The study's :class:`xarray.Dataset` (:func:`.dataset.runs_dataset`), with the measurement
    context of its runtimes, the number of measurement sessions and the continuum note as
    attributes."""
    grid = check_grid(_panel(scene, ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID)))
    options = check_options(ctx.options or Options())
    if options.figures:
        require_matplotlib(STUDY)
    scenes = [load_spec(s) for s in grid.scenes]
    nworkers = ctx.workers or (os.cpu_count() or 1)
    measured = measurement_context(nworkers)
    per_scene = [scene_points(s, grid, measured, spec.continuum_levels)
                 for spec, s in zip(grid.scenes, scenes)]
    flat = [p for pts, refs in per_scene for p in pts + refs]
    executor = ctx.executor
    with contextlib.ExitStack() as stack:
        if executor is None:
            executor = stack.enter_context(sweep_executor(ctx.scheduler, workers=nworkers))
        records = run_sweep(evaluate_point, flat, ctx.store, study=STUDY, executor=executor,
                            progress=ctx.progress)
    per_records, k = [], 0
    for pts, refs in per_scene:
        recs, k = records[k:k + len(pts)], k + len(pts)
        ref_recs, k = records[k:k + len(refs)], k + len(refs)
        per_records.append((recs, ref_recs))
    sessions = len({r.get("session", "") for r in records if "error" not in r})
    meshes = [[(int(p["springs"]), r.get("runtime"), r.get("error"))
               for p, r in zip(pts, recs) if p["model"] == "continuum"]
              for (pts, _), (recs, _) in zip(per_scene, per_records)]
    note = continuum_note(continuum_status(), [s.label for s in grid.scenes], meshes)
    return runs_dataset(grid.scenes, scenes, per_scene, per_records, grid, options,
                        {"context": measured, "sessions": sessions, "continuum": note,
                         "fast": ctx.fast})


def write(ds, ctx: Context) -> StudyResult:
    """The tables (:func:`.tables.write_tables`), a figure per scene (when the
    ``options_figures`` attribute is set), the dataset (``speed_vs_error.nc``) and the summary
    into ``ctx.out``."""
    out = Path(ctx.out)
    prov = provenance(study=STUDY, fast=ctx.fast, grid=_prefixed(ds, "grid_"),
                      options=_prefixed(ds, "options_"), context=context(ds),
                      store=str(ctx.store.root))
    files = write_tables(ds, out)
    if ds.attrs["options_figures"]:
        files += write_figures(ds, out / "figures")
    return write_study(STUDY, ds, ctx, summarise=summarise, numbers=key_numbers,
                       provenance=prov, files=files)


def _prefixed(ds, prefix: str) -> dict:
    """The dataset's attributes named ``<prefix><key>``, as {key: value}."""
    return {k.removeprefix(prefix): v for k, v in ds.attrs.items() if k.startswith(prefix)}


def run(scene: str | SceneSpec | Sequence[SceneSpec] | None = None, fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        grid: Grid | None = None, options: Options | None = None, executor=None,
        scheduler=None, progress=None, workers: int | None = None) -> StudyRun:
    """Run the study on ``scene`` (default: the panel of :data:`FULL_GRID`, or
    :data:`FAST_GRID` with ``fast``: two short pulse scenes, N = 10, 40, 160): its dataset
    (``.data``, :func:`compute`) and what it wrote (``.study``).

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


def _describe(result: StudyRun) -> list[str]:
    ds, lines = result.data, []
    for label in ds.scene.values.tolist():
        points = runs(ds, label)
        p = cheapest(points, "u", 0.05)
        best = table_note(ds, label, points, "u") or (
            "none" if p is None else f"{short_label(p)} ({p.runtime * 1e3:.3g} ms)")
        lines.append(f"{label}: reference {float(ds.reference_runtime.sel(scene=label)):.3g} "
                     f"s; cheapest within 5 % in peak u: {best}")
    return lines


DEFINITION = Study(STUDY, "Speed against error",
                   "What each model and discretisation costs for the error it leaves.", Options,
                   compute, write, describe=_describe, context_from=_context_from,
                   help_fast="two short pulses, few levels")
