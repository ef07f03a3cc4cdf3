"""The study's protocol: compute (the labelled dataset), write, run, its definition and its
command line."""

from __future__ import annotations

from dataclasses import asdict, replace
from pathlib import Path

from .... import checks
from ....checks import InputError
from ....provenance import provenance
from ...framework.availability import continuum_status
from ...framework.protocol import Context, Study, StudyRun, run_study
from ...framework.store import Store
from ...framework.study import StudyResult, require_matplotlib, write_study
from .analysis import figure_ratio, spectrum_ranges, spectrum_supports
from .dataset import study_dataset
from .figures import write_figures
from .grid import BUILDINGS, FAST_GRID, FULL_GRID, Grid, Options, STUDY, check_grid
from .runs import elcentro_entry, figure_records, spectrum_points, spectrum_records
from .summary import key_numbers, span_text, summarise
from .tables import write_tables


def compute(scene, ctx: Context):
    """The study's :class:`xarray.Dataset` (:func:`.dataset.study_dataset`): the figures' runs
    and the spectra (``scene`` must be None: the study's scenes are the paper's buildings);
    ``ctx.grid`` (default :data:`FAST_GRID` or :data:`FULL_GRID`), ``ctx.options``
    (:class:`Options`, kept as the ``figures`` attribute), ``ctx.workers`` processes of
    :func:`~upliftlab.reduced.run_batch`."""
    if scene is not None:
        raise InputError(f"scene = {scene!r}: this study runs the paper's buildings "
                         f"({', '.join(BUILDINGS.values())}); pass scene=None")
    grid = check_grid(ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID))
    options = ctx.options or Options()
    checks.boolean("figures", options.figures)
    if options.figures:
        require_matplotlib(STUDY)
    if ctx.workers is not None:
        checks.integer_at_least("workers", ctx.workers, 1)
    record = elcentro_entry()
    figs = {b: figure_records(b, ctx.store, record) for b in grid.figures}
    records = spectrum_records(spectrum_points(grid, record), ctx.store, ctx.workers)
    _, note = continuum_status()
    note = note.replace("continuum points were not run", "the continuum comparison (stiff "
                        "bonded against unilateral-contact footing) was not run")
    return study_dataset(grid, figs, records, {"fast": ctx.fast, "continuum": note,
                                               "figures": options.figures})


def write(ds, ctx: Context) -> StudyResult:
    """The tables, the figures (when the ``figures`` attribute is set), the dataset
    (``fixed_vs_uplift.nc``) and the summary into ``ctx.out``."""
    out = Path(ctx.out)
    grid = Grid(periods=tuple(ds.period.values.tolist()),
                families=tuple(ds.family.values.tolist()), supports=tuple(spectrum_supports(ds)),
                figures=tuple(ds.building.values.tolist()))
    prov = provenance(study=STUDY, fast=ctx.fast, grid=asdict(grid), store=str(ctx.store.root))
    files = write_tables(ds, out)
    if ds.attrs["figures"]:
        files += write_figures(ds, out / "figures")
    return write_study(STUDY, ds, ctx, summarise=summarise, numbers=key_numbers,
                       provenance=prov, files=files)


def run(scene: None = None, fast: bool = False, *, out: str | Path | None = None,
        store: Store | str | Path | None = None, grid: Grid | None = None,
        figures: bool = True, workers: int | None = None) -> StudyRun:
    """Run the study (``scene`` must be None: the study's scenes are the paper's buildings).

    ``fast`` uses :data:`FAST_GRID` (10 periods, the short-period family) instead of
    :data:`FULL_GRID` (32 periods, both families). ``out``: output directory (default
    ``results/fixed_vs_uplift[-fast]``); ``store``: the results store (default
    ``<out>/store``); ``workers``: processes of :func:`~upliftlab.reduced.run_batch`.
    Returns the dataset (``.data``) and what was written (``.study``).
    """
    return run_study(DEFINITION, scene, Context(fast=fast, out=out, store=store, grid=grid,
                                                options=Options(figures=figures),
                                                workers=workers))


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _describe(run: StudyRun) -> list[str]:
    ds = run.data
    lines = []
    for building, number in zip(ds.building.values.tolist(), ds.figure.values.tolist()):
        peak = ds.peak_u.sel(building=building)
        lines.append(f"Fig. {number}: peak u fixed {float(peak.sel(support='fixed')):.4g} in, "
                     f"uplift (C) {float(peak.sel(support='C')):.4g} in (ratio "
                     f"{figure_ratio(ds, building, 'u'):.3f}); base shear ratio "
                     f"{figure_ratio(ds, building, 'shear'):.3f}")
    for family in ds.family.values.tolist():
        r = spectrum_ranges(ds, family)[("C", "shear")]
        lines.append(f"{family}: Case C reduces peak base shear over {span_text(r.reduced)} "
                     f"(min ratio {r.min_ratio:.3f} at {r.min_period:g} s)")
    return lines


def _context_from(args, ctx: Context, say) -> Context:
    return replace(ctx, options=Options(figures=not args.no_figures))


DEFINITION = Study(STUDY, "Fixed base against uplift",
                   "What allowing uplift changes against a fixed base.", Options, compute, write,
                   describe=_describe, context_from=_context_from,
                   help_fast="10 periods, short-period family")
