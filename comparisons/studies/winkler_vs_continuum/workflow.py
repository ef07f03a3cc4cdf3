"""The study's protocol: compute (the labelled data), write, run, its definition and its
command line."""

from __future__ import annotations

import contextlib
import os
from dataclasses import asdict, replace
from pathlib import Path

from ....provenance import provenance
from ....scenes import Scene, load_scene
from ...beds.continuum_points import evaluate_continuum
from ...beds.pushover import bed_response
from ...beds.stiffness import calibrate, end_zone
from ...framework.protocol import Context, Study, StudyRun, run_study
from ...framework.store import Store
from ...framework.study import StudyResult, require_matplotlib, write_study
from ...framework.sweep import run_sweep, sweep_executor
from .analysis import error_table, texts
from .dataset import comparison, study_dataset
from .dynamics import compare_dynamics, dynamic_points
from .figures import write_figures
from .numbers import key_numbers, read
from .options import FAST_OPTIONS, FULL_OPTIONS, Options, STUDY, check_options, check_scene
from .reference import continuum_points, continuum_reference
from .summary import summarise
from .tables import write_tables


def _options(ctx: Context) -> Options:
    """The study's options: ``ctx.options``, else :data:`FAST_OPTIONS` or :data:`FULL_OPTIONS`
    (checked)."""
    return check_options(ctx.options or (FAST_OPTIONS if ctx.fast else FULL_OPTIONS))


def compute(scene: str | Scene, ctx: Context):
    """The study's :class:`xarray.DataTree` (:func:`.dataset.study_dataset`): the continuum
    reference, the calibrated beds, their errors and the dynamics of ``scene`` (with
    ``[soil]``) under ``ctx.options`` (default :data:`FAST_OPTIONS` or :data:`FULL_OPTIONS`).
    Every parameter is checked before anything runs."""
    fast = ctx.fast
    options = _options(ctx)
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
    table = error_table(ref, beds, options, scene, dynamics.runs)
    return study_dataset(scene, options, fast, ref, calibrations, beds, table, dynamics)


def write(data, ctx: Context) -> StudyResult:
    """The tables, the figures (when ``options.figures``), the data (``comparison.nc`` and
    ``dynamic_<motion>.nc``) and the summary into ``ctx.out``."""
    options, ds = _options(ctx), comparison(data)
    attrs = ds.attrs
    prov = provenance(study=STUDY, scene=attrs["scene"], scene_digest=attrs["scene_digest"],
                      overrides=texts(attrs.get("overrides", "")), fast=ctx.fast,
                      options=asdict(options), store=str(ctx.store.root),
                      continuum_dofs=int(ds.continuum_dofs))
    out = Path(ctx.out)
    files = write_tables(ds, out)
    if options.figures:
        files += write_figures(data, out / "figures")
    return write_study(STUDY, data, ctx, summarise=summarise, numbers=key_numbers,
                       provenance=prov, files=files)


def run(scene: str | Scene = "strip_footing_clay", fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        options: Options | None = None, executor=None, scheduler=None,
        progress=None) -> StudyRun:
    """Run the study on ``scene`` (with ``[soil]``; its own motion is used for nothing static).

    ``fast`` applies ``options.fast_overrides`` (a coarse mesh) and the smaller
    :data:`FAST_OPTIONS` paths; full mode uses the scene's mesh and :data:`FULL_OPTIONS`.
    ``out``: output directory (default ``results/winkler_vs_continuum[-fast]``); ``store`` the
    results store (default ``<out>/store``); ``executor``/``scheduler``/``progress`` go to
    :func:`.sweep.run_sweep`. Every parameter is checked before anything runs. Returns the
    data (``.data``, :func:`compute`) and what was written (``.study``).
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


def _describe(run: StudyRun) -> list[str]:
    reading = read(run.data)
    attrs = reading.ds.attrs
    return [reading.recommendation.text, "dynamics compared" if attrs["dynamic_available"]
            else str(attrs.get("dynamic_reason", ""))]


DEFINITION = Study(STUDY, "Winkler against the continuum",
                   "How well the reduced model's Winkler bed matches the plane-strain continuum.",
                   Options, compute, write, scene="strip_footing_clay", describe=_describe,
                   arguments=_arguments, context_from=_context_from,
                   help_fast="coarse mesh, short paths")
