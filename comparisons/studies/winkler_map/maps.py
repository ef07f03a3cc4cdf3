"""The map computed (:func:`compute_map`): the continuum's statics and dynamic runs (stored),
every bed's run of the same points (live, :mod:`.assemble`), and the errors of each bed against
the continuum, as labelled data (:mod:`.dataset`, :mod:`.statics_dataset`).
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import os
from collections.abc import Mapping, Sequence

import numpy as np

from ....log import logger
from ....scenes import load_scene
from ...beds import BASE_SCENE, base_table, bed_foundation, bed_rocking
from ...beds.continuum_points import evaluate_continuum
from ...framework.sweep import DASK_ENV, run_sweep, sweep_executor
from .assemble import assemble
from .cost import refuse_over_budget
from .dataset import map_dataset
from .energy_points import evaluate_energy
from .grid import STUDY, Grid, Options
from .impedance_points import evaluate_impedance, impedance_point, soil_impedance
from .macro_points import evaluate_macro_fit, fit_rotation_points, soil_fit_points
from .plan import (bed_needs, cells, dynamic_points, estimate_map, map_rocking_points,
                   plan_map, point_key_of, reference, scene_of)
from .points import evaluate_dynamic, point_table
from .rocking import RockingData, rocking_data, theta_onset
from .statics import evaluate_static, soil_statics, static_points
from .statics_dataset import statics_dataset

__all__ = ["compute_map", "estimate_map", "map_tree", "calibration_inputs",
           "IN_PROCESS_SECONDS"]

#: Continuum work estimated below this (s) runs in this process, one point after the other:
#: starting worker processes (imports, and the explicit loop's compilation in each, which numba
#: does not cache) would cost more than it saves.
IN_PROCESS_SECONDS = 60.0


def compute_map(grid: Grid, options: Options, calibrations: Sequence[str], motions,
                ctx):
    """The map as an :class:`xarray.DataTree` of ``map`` and ``statics`` (:mod:`.dataset`):
    the statics, the continuum runs (both through :func:`.sweep.run_sweep`, stored) and
    every bed's runs (live), after the cost estimate (logged; refused above
    ``options.budget``). The sweeps run on ``ctx.executor``, else on a Dask cluster
    (``ctx.scheduler``), else in this process when the estimate is below
    :data:`IN_PROCESS_SECONDS`, else on ``ctx.workers`` local processes."""
    store = ctx.store
    base, g, statics_points, static_records, impedance_points, estimate = plan_map(
        grid, options, calibrations, motions, store)
    impedance_stored = [store.has(point_key_of(p, evaluate_impedance)) for p in impedance_points]
    local = ctx.scheduler is None and not os.environ.get(DASK_ENV)
    in_process = ctx.executor is None and local and estimate.seconds < IN_PROCESS_SECONDS
    workers = 1 if in_process else (ctx.workers or os.cpu_count() or 1)
    # what the estimate is divided by (log and summary): not known for a cluster or an executor
    split = workers if local and ctx.executor is None else None
    logger(STUDY).info(f"{STUDY}: {estimate.text(split)}")
    refuse_over_budget(estimate, options.budget)
    with contextlib.ExitStack() as stack:
        executor = ctx.executor
        if in_process:
            executor = stack.enter_context(cf.ThreadPoolExecutor(1))  # no pool to start
        elif executor is None and (estimate.runs or estimate.checks or estimate.fits):
            n = max(1, min(workers, estimate.runs + estimate.checks + estimate.fits))
            executor = stack.enter_context(sweep_executor(ctx.scheduler, workers=n))
        sweep = {"executor": executor, "chunk": 1, "study": STUDY, "progress": ctx.progress}
        records = run_sweep(evaluate_static, statics_points, store, **sweep)
        statics = tuple(soil_statics(soil, records[2 * i:2 * i + 2])
                        for i, soil in enumerate(grid.soils))
        loads = {s.soil: s.V_ult for s in statics}
        impedances = dict(zip(grid.soils, (soil_impedance(p, r) for p, r in zip(
            impedance_points, run_sweep(evaluate_impedance, impedance_points, store, **sweep)))))
        points = dynamic_points(grid, options, motions, base, g, loads)
        before = sum(1 for p in points if store.has(point_key_of(p, evaluate_dynamic)))
        rotations = map_rocking_points(grid, options, base, loads)
        before += sum(1 for p in rotations if store.has(point_key_of(p, evaluate_continuum)))
        rocking_records = run_sweep(evaluate_continuum, rotations, store, **sweep)
        pushovers = _pushovers(grid, loads, base, rocking_records)
        if "macro" in bed_needs(calibrations, options):
            fits = _macro_fits(grid, options, base, g, statics, loads, store, sweep)
            _with_fits(pushovers, fits)
        _build_every_bed(grid, options, calibrations, motions, statics, points, impedances,
                         pushovers)
        runs = run_sweep(evaluate_dynamic, points, store, **sweep)
        if options.energy:
            before += sum(1 for p in points if store.has(point_key_of(p, evaluate_energy)))
            energy_runs = run_sweep(evaluate_energy, points, store, **sweep)
        else:  # the energy runs the store holds (checked like every stored record)
            held = [p for p in points if store.has(point_key_of(p, evaluate_energy))]
            run_sweep(evaluate_energy, held, store, **sweep)
            energy_runs = [store.get(point_key_of(p, evaluate_energy)) for p in points]
    soils_run = sum(1 for i in range(len(grid.soils))
                    if any(r is None for r in static_records[2 * i:2 * i + 2]))
    computed = (len(points) * (2 if options.energy else 1) + len(rotations) - before + soils_run
                + sum(1 for done in impedance_stored if not done))
    rocking = _rocking(grid, options, calibrations, statics, base, g, rocking_records,
                       impedances, pushovers)
    arrays, refusals, fits = assemble(grid, options, calibrations, motions, statics, points,
                                      runs, impedances, pushovers, ctx.progress, energy_runs)
    return map_tree(
        map_dataset(arrays, grid, options, motions, calibrations, refusals, estimate, computed,
                    split, ctx.fast),
        statics_dataset(statics, grid, calibrations, rocking, fits, impedances))


def map_tree(points, statics):
    """The map's :class:`xarray.DataTree` of its ``map`` and ``statics`` datasets (as
    :func:`upliftlab.open_study` reads them back from ``map.nc`` and ``statics.nc``)."""
    import xarray as xr

    return xr.DataTree.from_dict({"map": points, "statics": statics}, name=STUDY)


def calibration_inputs(grid: Grid, options: Options, calibrations: Sequence[str],
                       store) -> tuple[dict, dict, dict]:
    """What the map's beds are calibrated from, read back from ``store`` (nothing is run):
    ({soil: :class:`.statics.SoilStatics`}, {soil: the continuum's impedance, when a bed needs
    it}, {(soil, fs_v): the continuum's rotation pushovers, with the soil's macro-element fit
    when a bed needs it}); with :func:`.plan.reference`
    they build any bed of the map again. Raises KeyError for a point the store does not
    hold."""
    base = base_table()
    b = base["foundation"]["half_width"]

    def stored(point, function):
        record = store.get(point_key_of(point, function))
        if record is None:
            raise KeyError(f"{STUDY}: the store does not hold {function.__name__} of {point}")
        return record

    statics = {soil: soil_statics(soil, [stored(p, evaluate_static)
                                         for p in static_points(soil, options, b)])
               for soil in grid.soils}
    loads = {soil: st.V_ult for soil, st in statics.items()}
    needs = bed_needs(calibrations, options)
    impedances = {}
    if "impedance" in needs:
        for soil in grid.soils:
            point = impedance_point(soil, options, b)
            impedances[soil] = soil_impedance(point, stored(point, evaluate_impedance))
    rotations = map_rocking_points(grid, options, base, loads)
    pushovers = _pushovers(grid, loads, base, [stored(p, evaluate_continuum) for p in rotations])
    if "macro" in needs:
        fit_rotations = fit_rotation_points(grid.soils, options, base, loads)
        points = soil_fit_points(grid.soils, options, base, statics, fit_rotations,
                                 [stored(p, evaluate_continuum) for p in fit_rotations],
                                 [point_key_of(p, evaluate_continuum) for p in fit_rotations],
                                 load_scene(BASE_SCENE).g)
        _with_fits(pushovers, {p["soil"]: stored(p, evaluate_macro_fit) for p in points})
    return statics, impedances, pushovers


def _pushovers(grid, loads, base, records) -> dict:
    """(soil, fs_v) → the continuum's ``cyclic`` and ``monotonic`` rotation pushovers and
    their ``theta_on``, for a bed calibrated to them; where a path stopped, ``error`` says
    why (a bed that needs them is then refused, with it, before any dynamic run)."""
    B = 2.0 * base["foundation"]["half_width"]
    out = {}
    for i, (soil, fs) in enumerate((s, f) for s in grid.soils for f in grid.fs_v):
        cyclic, monotonic = records[2 * i], records[2 * i + 1]
        errors = [f"{name}: {r['error']}" for name, r in (("cyclic", cyclic),
                                                          ("monotonic", monotonic))
                  if "error" in r]
        out[soil, fs] = {"error": "; ".join(errors)} if errors else {
            "cyclic": cyclic, "monotonic": monotonic,
            "theta_on": theta_onset(loads[soil] / fs, soil, B)}
    return out


def _macro_fits(grid, options, base, g, statics, loads, store, sweep) -> dict:
    """{soil: the macro-element's stored fit} (:mod:`.macro_points`): its rotation pushovers
    at ``options.macro_fs_v`` (read from the store, or made), then the fit (read, or
    made)."""
    rotations = fit_rotation_points(grid.soils, options, base, loads)
    records = run_sweep(evaluate_continuum, rotations, store, **sweep)
    keys = [point_key_of(p, evaluate_continuum) for p in rotations]
    by_soil = {s.soil: s for s in statics}
    points = soil_fit_points(grid.soils, options, base, by_soil, rotations, records, keys, g)
    fits = run_sweep(evaluate_macro_fit, points, store, **sweep)
    return {p["soil"]: fit for p, fit in zip(points, fits)}


def _with_fits(pushovers: dict, fits: Mapping) -> None:
    """Each (soil, fs_v)'s rotation pushovers given the soil's macro-element fit (``macro``:
    its record), where :func:`.plan.reference` finds it for the ``macro`` bed."""
    for (soil, _), rocking in pushovers.items():
        rocking["macro"] = fits[soil]


def _build_every_bed(grid, options, calibrations, motions, statics, points, impedances,
                     pushovers):
    """Build every bed of every cell once (milliseconds), after the statics and before any
    further continuum run: a bed that cannot be built at some point (an impedance bed whose
    rocking frequency is outside the impedance's frequencies) is refused before that work."""
    by_soil = {s.soil: s for s in statics}
    for k, (_, (soil, fs, *_)) in enumerate(cells(grid)):
        table = points[k * len(motions)]["scene"]
        ref = reference(by_soil[soil], scene_of(table), table["structure"], impedances.get(soil),
                         pushovers[soil, fs], options.bed_stiffness)
        for name in calibrations:
            bed_foundation(name, ref, options)


def _rocking(grid, options, calibrations, statics, base, g, records, impedances,
             pushovers) -> RockingData:
    """Every bed's rocking pushovers on the continuum's rotations, per (soil, fs_v); the
    beds are built at the grid's first h/B and period (a bed's statics do not depend on
    them)."""
    by_soil = {s.soil: s for s in statics}
    loads = np.array([[by_soil[s].V_ult / fs for fs in grid.fs_v] for s in grid.soils])
    beds = []
    for i, (soil, fs) in enumerate((s, f) for s in grid.soils for f in grid.fs_v):
        table = point_table(base, soil, options.elements_across, by_soil[soil].V_ult / fs,
                            grid.h_over_B[0], grid.periods[0], g, options.reference)
        ref = reference(by_soil[soil], scene_of(table), table["structure"],
                         impedances.get(soil), pushovers[soil, fs], options.bed_stiffness)
        if "error" in records[2 * i] or "error" in records[2 * i + 1]:
            beds.append([])  # the continuum's path stopped: nothing to push the beds over on
            continue
        cyclic, monotonic = records[2 * i]["theta"], records[2 * i + 1]["theta"]
        beds.append([bed_rocking(table, ref.N, bed_foundation(name, ref, options), cyclic,
                                 monotonic) for name in calibrations])
    B = 2.0 * base["foundation"]["half_width"]
    return rocking_data(grid.soils, grid.fs_v, loads, records, beds, B, options,
                        len(calibrations))
