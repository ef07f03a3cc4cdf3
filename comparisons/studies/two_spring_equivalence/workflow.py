"""The study's protocol: compute (the labelled data), write, run, its definition and its
command line."""

from __future__ import annotations

import contextlib
import json
from dataclasses import asdict, replace
from pathlib import Path

from ....provenance import provenance
from ....scenes import Scene
from ...framework.protocol import Context, Study, StudyRun, run_study
from ...framework.store import Store
from ...framework.study import StudyResult, require_matplotlib, write_study
from ...framework.sweep import sweep_executor
from . import statics as st
from .convergence import check_convergence
from .dataset import study_tree
from .figures import write_figures
from .grid import FAST_GRID, FULL_GRID, Grid, Options, RECORD_SETS, STUDY, check_grid, check_options
from .maps import MapContext, compute_maps
from .motions import study_motions
from .points import load_base
from .statics import compute_statics
from .summary import key_numbers, summarise
from .tables import write_statics
from .views import STATICS, study_attrs


def compute(scene: str | Scene, ctx: Context):
    """The study's :class:`xarray.DataTree` (:func:`.dataset.study_tree`): the convergence
    check, the statics and the error maps of ``scene`` (a one-story scene; its own motion is
    not used), with ``ctx.grid`` (default :data:`FAST_GRID` or :data:`FULL_GRID`) and
    ``ctx.options`` (:class:`Options`). The study's own attributes go on the statics node:
    the base scene's name, h/b and period (s), the ``threshold``, ``fast``, the
    ``record_note``, whether to draw ``figures``, and the ``grid`` and ``options`` as JSON
    (the provenance of what was asked). Every parameter is checked before anything runs."""
    grid = check_grid(ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID))
    options = check_options(ctx.options or Options())
    if options.figures:
        require_matplotlib(STUDY)
    base = load_base(scene)
    store, executor = ctx.store, ctx.executor
    reference, records, record_note = study_motions(grid, options, ctx.out)
    with contextlib.ExitStack() as stack:  # one pool (or Dask client) for both sweeps
        if executor is None:
            executor = stack.enter_context(sweep_executor(ctx.scheduler))
        sweep = {"executor": executor, "progress": ctx.progress}
        convergence = check_convergence(base, grid, options, reference, store, sweep)
        springs = int(convergence.attrs["chosen_springs"])
        maps_ctx = MapContext(base, grid, options, springs, reference, records)
        maps = compute_maps(maps_ctx, store, sweep)
    statics = compute_statics(base, springs, options, grid.backbone_points)
    attrs = {"scene": base.name, "h_over_b": base.h_over_b, "period": base.period,
             "threshold": options.threshold, "fast": bool(ctx.fast),
             "record_note": record_note, "figures": options.figures,
             "grid": json.dumps(asdict(grid)), "options": json.dumps(asdict(options))}
    return study_tree(convergence, statics, maps, attrs)


def write(tree, ctx: Context) -> StudyResult:
    """Statics (CSV), the data (NetCDF, one file per node of :mod:`.dataset`), figures and the
    summary into ``ctx.out``."""
    out, study = Path(ctx.out), study_attrs(tree)
    statics = tree[STATICS].to_dataset()
    prov = provenance(study=STUDY, scene=study["scene"], fast=ctx.fast,
                      grid=json.loads(study["grid"]), options=json.loads(study["options"]),
                      springs=int(statics.attrs["springs"]), store=str(ctx.store.root))
    files = [write_statics(statics, out / "statics.csv")]
    if study.get("figures"):
        files += write_figures(tree, out / "figures")
    return write_study(STUDY, tree, ctx, summarise=summarise, numbers=key_numbers,
                       provenance=prov, files=files)


def run(scene: str | Scene = "short_period_elcentro", fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        grid: Grid | None = None, options: Options | None = None, executor=None,
        scheduler=None, progress=None) -> StudyRun:
    """Run the study on ``scene`` (a one-story scene; its own motion is not used).

    ``fast`` uses :data:`FAST_GRID` (pulses only, small maps: seconds) instead of
    :data:`FULL_GRID` (El Centro, the record set, minutes). ``out``: output directory (default
    ``results/two_spring_equivalence[-fast]``); ``store``: the results store (default
    ``<out>/store``); ``executor``/``scheduler``/``progress`` go to :func:`.sweep.run_sweep`.
    Every parameter is checked before anything runs. Returns the data (``.data``, the
    :class:`xarray.DataTree`) and what was written (``.study``).
    """
    return run_study(DEFINITION, scene, Context(
        fast=fast, out=out, store=store, grid=grid, options=options, executor=executor,
        scheduler=scheduler, progress=progress))


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _arguments(parser) -> None:
    parser.add_argument("--threshold", type=float, default=Options.threshold,
                        help="equivalence threshold, a fraction (default 0.10)")
    parser.add_argument("--records", default=Options.records, choices=RECORD_SETS)


def _context_from(args, ctx: Context, say) -> Context:
    options = Options(threshold=args.threshold, records=args.records,
                      figures=not args.no_figures)
    if options.figures:
        from ....extras import need_extra
        need_extra(f"upliftlab study {STUDY}", "matplotlib",
                   why="or add --no-figures")
    return replace(ctx, options=options)


def _describe(run: StudyRun) -> list[str]:
    statics, numbers = run.data[STATICS].to_dataset(), run.study.numbers
    return [f"{STUDY}: N = {int(statics.attrs['springs'])}; onset ratio "
            f"{st.onset_ratio(statics):.4f}, capacity ratio {st.capacity_ratio(statics):.4f}",
            numbers["ewing"]["text"]]


DEFINITION = Study(STUDY, "Two-spring equivalence",
                   "When can a Winkler bed be replaced by two springs? Maps of the relative "
                   "error of each two-spring layout against a converged bed.", Options, compute,
                   write, scene="short_period_elcentro", describe=_describe,
                   arguments=_arguments, context_from=_context_from,
                   help_fast="small grids, pulses only")
