"""The study's protocol: compute (the map's labelled data), write, run, its definition and its
command line."""

from __future__ import annotations

import shutil
from dataclasses import replace
from pathlib import Path

from ....checks import InputError
from ....provenance import provenance
from ...beds import BEDS, bed_names
from ...framework.protocol import CHECKOUT, Context, Study, StudyRun, run_study
from ...framework.store import Store
from ...framework.study import StudyResult, require_matplotlib, write_study
from .analysis import analyse
from .grid import (FAST_GRID, FAST_OPTIONS, FULL_GRID, FULL_OPTIONS, Grid, Options, STUDY,
                   check_grid, check_options, grid_with)
from .maps import compute_map
from .motions import study_motions
from .parts import map_of
from .summary import key_numbers, summarise

#: Where the full grid's continuum runs are kept with the repository (relative to the checkout):
#: the report's full build and the README's map commands resume from it.
KEPT_STORE = "benchmarks/winkler_map_store"
#: Each continuum reference's own kept store (:mod:`.reference`), beside the box's: the two
#: references share no folder, so that neither's records can be taken for the other's.
KEPT_STORES = {"box": KEPT_STORE, "half_plane": "benchmarks/winkler_map_halfplane_store"}


def compute(scene, ctx: Context):
    """The map as an :class:`xarray.DataTree` of its ``map`` and ``statics`` datasets
    (:mod:`.dataset`, :mod:`.statics_dataset`): the map of ``ctx.grid`` (default
    :data:`FAST_GRID` or :data:`FULL_GRID`) under
    ``ctx.options`` (default :data:`FAST_OPTIONS` or :data:`FULL_OPTIONS`): every parameter
    checked, the motions found and the cost estimated (and refused above ``options.budget``)
    before any run; ``ctx.budget`` (the report's) applies when the options set none.
    ``scene`` is not used: the map builds its own scenes."""
    grid = check_grid(ctx.grid or (FAST_GRID if ctx.fast else FULL_GRID))
    options = ctx.options or (FAST_OPTIONS if ctx.fast else FULL_OPTIONS)
    if isinstance(options, Options) and options.budget is None and ctx.budget is not None:
        options = replace(options, budget=ctx.budget)
    options = check_options(options, tuple(BEDS))
    calibrations = bed_names(options)  # a bed named on a reference it does not stand on: refused
    _check_store_reference(ctx.store, options.reference)
    if options.figures:
        require_matplotlib(STUDY)
    out = Path(ctx.out)
    fresh = [p for p in (out, out / "motions") if not p.exists()]
    motions = study_motions(grid, options, out)
    try:
        tree = compute_map(grid, options, calibrations, motions, ctx)
    except InputError:  # refused: leave no copied records behind, and no empty folders
        if out / "motions" in fresh:
            shutil.rmtree(out / "motions", ignore_errors=True)
        if out in fresh:
            _remove_empty_folders(out)
        raise
    return tree


def _check_store_reference(store, reference: str) -> None:
    """Refuse (one :class:`InputError` line) a store that is another reference's kept store
    (:data:`KEPT_STORES`)."""
    root = store.root if isinstance(store, Store) else store
    if root is None:
        return
    here = Path(root).resolve()
    for other, folder in KEPT_STORES.items():
        if other != reference and here == (CHECKOUT / folder).resolve():
            raise InputError(f"store = {str(root)!r}: the kept store of the {other!r} reference; "
                             f"valid for options.reference = {reference!r}: another folder, "
                             f"e.g. {KEPT_STORES[reference]}")


def write(tree, ctx: Context) -> StudyResult:
    """The figures (when the options make them), the map's data (``map.nc`` and
    ``statics.nc``) and its summary (:func:`.summary.summarise`, :func:`.summary.key_numbers`)
    into ``ctx.out``."""
    m = map_of(tree)
    grid = {k.removeprefix("grid_"): v for k, v in m.attrs.items() if k.startswith("grid_")}
    options = {k.removeprefix("options_"): v for k, v in m.attrs.items()
               if k.startswith("options_")}
    prov = provenance(study=STUDY, fast=ctx.fast, grid=grid, options=options,
                      store=str(ctx.store.root))
    files = []
    if int(m.attrs["options_figures"]):
        from .figures import write_figures

        files = write_figures(m, analyse(m), Path(ctx.out) / "figures")
    return write_study(STUDY, tree, ctx, summarise=summarise, numbers=key_numbers,
                       provenance=prov, files=files)


def _remove_empty_folders(root: Path) -> None:
    """Remove ``root`` and the folders below it that hold no file (a store with records
    stays)."""
    for folder in sorted((p for p in root.rglob("*") if p.is_dir()), reverse=True) + [root]:
        try:
            folder.rmdir()
        except OSError:
            pass


def run(fast: bool = False, *, out: str | Path | None = None,
        store: Store | str | Path | None = None, grid: Grid | None = None,
        options: Options | None = None, executor=None, scheduler=None, workers=None,
        progress=None) -> StudyRun:
    """Run the map. ``fast``: :data:`FAST_GRID` and :data:`FAST_OPTIONS` (one soil, two FS_v,
    one short pulse on 4 elements across) instead of the full grid on the reference mesh.
    ``out``: output directory (default ``results/winkler_map[-fast]``); ``store`` the results
    store (default ``<out>/store``); ``executor``/``scheduler``/``workers``/``progress`` go to
    :func:`.sweep.run_sweep`. Every parameter is checked before anything runs. Returns the
    map's tree (``.data``) and what was written (``.study``)."""
    return run_study(DEFINITION, None, Context(
        fast=fast, out=out, store=store, grid=grid, options=options, executor=executor,
        scheduler=scheduler, workers=workers, progress=progress))


# ---------------------------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------------------------


def _arguments(parser) -> None:
    parser.add_argument("--budget", type=float, default=None,
                        help="refuse (exit 2) a run whose estimated continuum cost exceeds "
                             "this many seconds of one worker")
    parser.add_argument("--grid", action="append", default=[], metavar="FIELD=VALUES",
                        help="replace one axis of the grid (repeatable), e.g. soils=clay, "
                             "fs_v=2,3,5,10, h_over_B=1.5, periods=0.5, intensities=1.5,3, "
                             "pulse_periods=0.25,0.6, elcentro=true, fema_components=2")
    parser.add_argument("--energy", action="store_true", default=None,
                        help="also make the continuum's foundation-energy run of every point "
                             "(one more continuum run each, stored), so that the map compares "
                             "E_F everywhere; without it, E_F is compared where the store "
                             "holds those runs (the fast map always makes them)")
    parser.add_argument("--reference", default=None, metavar="NAME",
                        help="the continuum reference: box (default; the closed box on a rigid "
                             "base, the kept store's) or half_plane (a compliant base, the "
                             "footing's horizontal tie, the clay's strength growing with depth, "
                             "1 %% small-strain damping of the soil and in the beds; "
                             f"kept in {KEPT_STORES['half_plane']})")
    parser.add_argument("--beds", default=None, metavar="NAME,NAME",
                        help="compare only these calibrations (names of the bed registry, "
                             "e.g. end_stiffened_plastic,qz; default: every one)")
    parser.add_argument("--bed-stiffness", choices=("static", "rocking"), default=None,
                        help="what the beds' K_v and K_r are calibrated to: the continuum box's "
                             "statics (static, the default) or the half-plane impedance's at "
                             "each structure's rocking frequency (rocking)")


def _context_from(args, ctx: Context, say) -> Context:
    base = FAST_OPTIONS if args.fast else FULL_OPTIONS
    options = replace(base, budget=args.budget, figures=not args.no_figures,
                      energy=bool(args.energy) or base.energy)
    if args.reference is not None:
        options = replace(options, reference=args.reference)
    check_options(options, tuple(BEDS))
    if args.beds is not None:
        options = replace(options, beds=tuple(b.strip() for b in args.beds.split(",")
                                              if b.strip()))
    if args.bed_stiffness is not None:
        options = replace(options, bed_stiffness=args.bed_stiffness)
    if options.figures:
        from ....extras import need_extra
        need_extra(f"upliftlab study {STUDY}", "matplotlib",
                   why="or add --no-figures")
    grid = check_grid(grid_with(FAST_GRID if args.fast else FULL_GRID, args.grid))
    return replace(ctx, options=options, grid=grid)


def _describe(run: StudyRun) -> list[str]:
    m = map_of(run.data)
    s = analyse(m).share
    return [f"{STUDY}: {m.continuum_wall_time.size} points; the best calibration "
            f"({s.best}) is within {100 * s.threshold:g} % in peak θ and edge uplift at "
            f"{100 * s.best_share:.0f} % of them"]


DEFINITION = Study(STUDY, "Winkler beds against the continuum: the map",
                   "Where is a calibrated bed of springs enough? Every calibration against the "
                   "continuum over soil, FS_v, h/B, period, intensity and motion.", Options,
                   compute, write, describe=_describe, arguments=_arguments,
                   context_from=_context_from, kept_store=KEPT_STORE,
                   help_fast="one soil, two FS_v, one short pulse, 4 elements across")
