"""The study's protocol: compute, write, run, its definition and its command line."""

from __future__ import annotations

import contextlib
from dataclasses import asdict, replace
from pathlib import Path

from ....provenance import provenance
from ....results import write_dataset
from ....scenes import Scene
from ...framework.protocol import Context, Study, run_study
from ...framework.store import Store
from ...framework.study import StudyResult, require_matplotlib, write_summary
from ...framework.sweep import sweep_executor
from .analysis import equivalence_regions, ewing_conclusion
from .convergence import check_convergence
from .dataset import TwoSpringEquivalence, convergence_dataset, map_dataset
from .figures import write_figures
from .grid import FAST_GRID, FULL_GRID, Grid, Options, RECORD_SETS, STUDY, check_grid, check_options
from .maps import MapContext, compute_maps
from .motions import study_motions
from .points import load_base
from .statics import compute_statics
from .summary import summary_markdown, summary_numbers
from .tables import write_statics


def compute(scene: str | Scene, ctx: Context) -> TwoSpringEquivalence:
    """The convergence check, the error maps, the statics and the conclusions of ``scene``
    (a one-story scene; its own motion is not used), with ``ctx.grid`` (default
    :data:`FAST_GRID` or :data:`FULL_GRID`) and ``ctx.options`` (:class:`Options`). Every
    parameter is checked before anything runs."""
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
        maps_ctx = MapContext(base, grid, options, convergence.springs, reference, records)
        maps = tuple(compute_maps(maps_ctx, store, sweep))
    statics = compute_statics(base, convergence.springs, options, grid.backbone_points)
    regions = tuple(equivalence_regions(maps, options.threshold))
    ewing = ewing_conclusion(maps, options.threshold)
    return TwoSpringEquivalence(None, convergence.springs, convergence, statics, maps, regions,
                                ewing, grid, options, record_note, base)


def write(result: TwoSpringEquivalence, ctx: Context) -> StudyResult:
    """Statics (CSV), convergence and maps (NetCDF, :mod:`.dataset`), figures and the summary
    into ``ctx.out``."""
    base, fast, out, store = result.base, ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, scene=base.name, fast=fast, grid=asdict(result.grid),
                      options=asdict(result.options), springs=result.springs,
                      store=str(store.root))
    units = base.table["units"]
    files = [write_statics(result.statics, out / "statics.csv"),
             write_dataset(out / "convergence.nc",
                           convergence_dataset(result.convergence, prov, units))]
    files += [write_dataset(out / f"map_{m.name}.nc", map_dataset(m, prov, units))
              for m in result.maps]
    if result.options.figures:
        files += write_figures(result, out / "figures")
    elapsed = ctx.elapsed()
    numbers = summary_numbers(result, elapsed)
    text = summary_markdown(result, base, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def run(scene: str | Scene = "short_period_elcentro", fast: bool = False, *,
        out: str | Path | None = None, store: Store | str | Path | None = None,
        grid: Grid | None = None, options: Options | None = None, executor=None,
        scheduler=None, progress=None) -> TwoSpringEquivalence:
    """Run the study on ``scene`` (a one-story scene; its own motion is not used).

    ``fast`` uses :data:`FAST_GRID` (pulses only, small maps: seconds) instead of
    :data:`FULL_GRID` (El Centro, the record set, minutes). ``out``: output directory (default
    ``results/two_spring_equivalence[-fast]``); ``store``: the results store (default
    ``<out>/store``); ``executor``/``scheduler``/``progress`` go to :func:`.sweep.run_sweep`.
    Every parameter is checked before anything runs.
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


def _describe(result: TwoSpringEquivalence) -> list[str]:
    return [f"{STUDY}: N = {result.springs}; onset ratio {result.statics.onset_ratio:.4f}, "
            f"capacity ratio {result.statics.capacity_ratio:.4f}", result.ewing.text]


DEFINITION = Study(STUDY, "Two-spring equivalence",
                   "When can a Winkler bed be replaced by two springs? Maps of the relative "
                   "error of each two-spring layout against a converged bed.", Options, compute,
                   write, scene="short_period_elcentro", describe=_describe,
                   arguments=_arguments, context_from=_context_from,
                   help_fast="small grids, pulses only")
