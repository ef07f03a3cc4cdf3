"""The study's protocol: compute, run, its definition and its command line."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from .... import checks
from ....checks import InputError
from ...framework.protocol import Context, Study, run_study
from ...framework.availability import continuum_status
from ...framework.store import Store
from ...framework.study import require_matplotlib
from .analysis import FixedVsUplift, figure_of, spectrum_of
from .figures import write_figures
from .grid import BUILDINGS, FAST_GRID, FULL_GRID, Grid, Options, STUDY, check_grid
from .output import write
from .runs import elcentro_entry, spectrum_points, spectrum_records
from .summary import span_text


def compute(scene, ctx: Context) -> FixedVsUplift:
    """The figures' runs and the spectra (``scene`` must be None: the study's scenes are the
    paper's buildings); ``ctx.grid`` (default :data:`FAST_GRID` or :data:`FULL_GRID`),
    ``ctx.options`` (:class:`Options`), ``ctx.workers`` processes of
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
    figs = tuple(figure_of(b, ctx.store, record) for b in grid.figures)
    points = spectrum_points(grid, record)
    records = spectrum_records(points, ctx.store, ctx.workers)
    per = len(grid.supports) * len(grid.periods)
    spectra = tuple(spectrum_of(f, grid, records[k * per:(k + 1) * per])
                    for k, f in enumerate(grid.families))
    _, note = continuum_status()
    note = note.replace("continuum points were not run", "the continuum comparison (stiff "
                        "bonded against unilateral-contact footing) was not run")
    return FixedVsUplift(None, figs, spectra, grid, note, options)


def run(scene: None = None, fast: bool = False, *, out: str | Path | None = None,
        store: Store | str | Path | None = None, grid: Grid | None = None,
        figures: bool = True, workers: int | None = None) -> FixedVsUplift:
    """Run the study (``scene`` must be None: the study's scenes are the paper's buildings).

    ``fast`` uses :data:`FAST_GRID` (10 periods, the short-period family) instead of
    :data:`FULL_GRID` (32 periods, both families). ``out``: output directory (default
    ``results/fixed_vs_uplift[-fast]``); ``store``: the results store (default
    ``<out>/store``); ``workers``: processes of :func:`~upliftlab.reduced.run_batch`.
    """
    return run_study(DEFINITION, scene, Context(fast=fast, out=out, store=store, grid=grid,
                                                options=Options(figures=figures),
                                                workers=workers))


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _describe(result: FixedVsUplift) -> list[str]:
    lines = [f"Fig. {f.number}: peak u fixed {f.peak_u['fixed']:.4g} in, uplift (C) "
             f"{f.peak_u['C']:.4g} in (ratio {f.ratio_u:.3f}); base shear ratio "
             f"{f.ratio_shear:.3f}" for f in result.figures]
    for s in result.spectra:
        r = s.ranges[("C", "shear")]
        lines.append(f"{s.family}: Case C reduces peak base shear over {span_text(r.reduced)} "
                     f"(min ratio {r.min_ratio:.3f} at {r.min_period:g} s)")
    return lines


def _write(result: FixedVsUplift, ctx: Context):
    """:func:`.output.write`, then the page-width figures with their captions
    (:func:`.figures.write_figures`) added to the files."""
    study = write(result, ctx)
    if not result.options.figures:
        return study
    extra = write_figures(result, Path(ctx.out) / "figures")
    return replace(study, files=tuple(study.files) + tuple(extra))


def _context_from(args, ctx: Context, say) -> Context:
    return replace(ctx, options=Options(figures=not args.no_figures))


DEFINITION = Study(STUDY, "Fixed base against uplift",
                   "What allowing uplift changes against a fixed base.", Options, compute, _write,
                   describe=_describe, context_from=_context_from,
                   help_fast="10 periods, short-period family")
