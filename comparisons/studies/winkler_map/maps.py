"""The map's data: the continuum's statics and dynamic runs (stored), every bed's run of the
same points (live), and the errors of each bed against the continuum.

Arrays are indexed (soil, fs_v, h_over_B, period, intensity, motion[, calibration], measure);
errors are signed, (bed − continuum)/max(|continuum|, floor), the floor
:data:`.grid.FLOOR_FRACTION` × the measure's scale (:func:`.points.scales`); NaN where a run
was refused.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import itertools
import os
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ....log import logger
from ....scenes import load_scene, scene_from_dict
from ...framework.study import relative_error
from ...framework.sweep import DASK_ENV, StderrProgress, SweepProgress, run_sweep, sweep_executor
from .bed_runs import run_bed
from .energy import ENERGIES, energies_of, energy_scale, same_run
from .energy_points import evaluate_energy
from ...beds import BASE_SCENE, BEDS, BedReference, base_table, bed_foundation, bed_rocking
from ...beds.continuum_points import evaluate_continuum
from ...beds.fitted import FITTED, fit_capacity_profile
from .cost import (Estimate, estimate_cost, impedance_dofs, refuse_over_budget, with_checks,
                   timed_dynamic_runs)
from .grid import FLOOR_FRACTION, MEASURES, STUDY, Grid, Options
from .impedance_points import evaluate_impedance, impedance_point, soil_impedance
from .motions import motion_duration
from .points import evaluate_dynamic, point_table, scales, story_constants
from .rocking import (RockingData, rocking_data, rocking_points,
                      theta_onset)
from .statics import SoilStatics, evaluate_static, soil_statics, static_points

__all__ = ["MapData", "compute_map", "estimate_map", "IN_PROCESS_SECONDS"]

#: Continuum work estimated below this (s) runs in this process, one point after the other:
#: starting worker processes (imports, and the explicit loop's compilation in each, which numba
#: does not cache) would cost more than it saves.
IN_PROCESS_SECONDS = 60.0


@dataclass(frozen=True, eq=False)
class MapData:
    """Everything the map measured (module docstring for the array layout).

    ``continuum`` (…, motion, measure) and ``beds`` (…, motion, calibration, measure) the
    measures of each model; ``errors`` like ``beds``; ``scale`` (soil, fs_v, h_over_B, period,
    measure) the floors' basis; ``continuum_wall`` (…, motion) each continuum run's own wall
    time (s, stored with it), ``bed_wall`` (…, motion, calibration) each bed run's (s, this
    run); ``steps`` and ``balance`` (…, motion) the continuum run's steps and energy balance
    error; ``N`` (soil, fs_v) the vertical load V_ult/FS_v; ``bed_K_r``, ``bed_K_v`` (soil,
    fs_v, calibration) the stiffness of each built bed; ``statics`` per soil; ``refusals``
    the bed runs the integrator refused; ``estimate`` the cost estimated before the work;
    ``computed`` the continuum runs this call made (a soil's statics count as one, as in the
    estimate, and its impedance as one more); ``impedances`` (soil, :class:`~upliftlab.
    continuum.impedance.Impedance`) pairs of the soils whose impedance a bed needed (else
    empty); ``bearing_failure`` (…, motion) where the continuum's run ended in a bearing
    failure of the soil (its measures NaN, its point counted: a bed is held to the outcome),
    ``bed_bearing_failure`` (…, motion, calibration) where a bed's base settled by
    :data:`~upliftlab.continuum.dynamics.run_control.FAILURE_SETTLEMENT` B or more in its run of
    such
    a point (it fails in bearing too); ``workers`` the local worker processes the estimate
    divided the work by (1 in this process; None: a Dask cluster or the caller's executor,
    whose count is not known); ``capacity_fits`` ((soil, fs_v), :class:`~...beds.fitted.
    CapacityFit`) pairs of the fitted bed's capacity profile (when it is compared);
    ``pushovers`` ((soil, fs_v), the continuum's rotation pushovers a bed is calibrated to, or
    why a path stopped) pairs. The energies of :data:`.energy.ENERGIES` (the foundation energy
    E_F and its part from the motion, :mod:`.energy`): ``continuum_energy`` (…, motion,
    energy) from the continuum's energy run of a point where the store holds one (NaN
    elsewhere), ``bed_energy`` (…, motion, calibration, energy), ``energy_errors`` like it
    (NaN where either is missing) and ``energy_scale`` (soil, fs_v, h_over_B, period) the
    floor's basis (:func:`.energy.energy_scale`); ``continuum_energy_left`` (…, motion) the
    energy the continuum's structure still holds at the end of its run (kinetic and story).
    """

    grid: Grid
    options: Options
    motions: tuple[dict, ...]
    calibrations: tuple[str, ...]
    statics: tuple[SoilStatics, ...]
    N: np.ndarray
    continuum: np.ndarray
    beds: np.ndarray
    errors: np.ndarray
    scale: np.ndarray
    continuum_wall: np.ndarray
    bed_wall: np.ndarray
    steps: np.ndarray
    balance: np.ndarray
    dofs: np.ndarray
    bed_K_r: np.ndarray
    bed_K_v: np.ndarray
    refusals: tuple[str, ...]
    estimate: Estimate
    computed: int
    rocking: RockingData
    impedances: tuple = ()
    bearing_failure: np.ndarray | None = None
    bed_bearing_failure: np.ndarray | None = None
    workers: int | None = 1
    capacity_fits: tuple = ()
    pushovers: tuple = ()
    continuum_energy: np.ndarray | None = None
    bed_energy: np.ndarray | None = None
    energy_errors: np.ndarray | None = None
    energy_scale: np.ndarray | None = None
    continuum_energy_left: np.ndarray | None = None

    @property
    def motion_names(self) -> tuple[str, ...]:
        return tuple(m["name"] for m in self.motions)

    @property
    def motion_kinds(self) -> tuple[str, ...]:
        return tuple(m["kind"] for m in self.motions)

    def statics_of(self, soil: str) -> SoilStatics:
        return next(s for s in self.statics if s.soil == soil)


def _cells(grid: Grid):
    """(index tuple, values) over soil × fs_v × h/B × period × intensity."""
    axes = (grid.soils, grid.fs_v, grid.h_over_B, grid.periods, grid.intensities)
    for idx in itertools.product(*(range(len(a)) for a in axes)):
        yield idx, tuple(a[i] for a, i in zip(axes, idx))


def _dynamic_points(grid, options, motions, base, g, loads) -> list[dict]:
    """Every dynamic point in array order; ``loads[soil]`` the V_ult of each soil (a
    placeholder before the statics are known: the points then serve only for the estimate)."""
    points = []
    for _, (soil, fs, hb, period, intensity) in _cells(grid):
        table = point_table(base, soil, options.elements_across, loads[soil] / fs, hb, period, g)
        for motion in motions:
            points.append({"scene": table, "motion": motion, "intensity": float(intensity)})
    return points


_FREE = {"type": "free", "velocity": 1.0, "duration": 1.0}  # a scene's motion, unused


def _key(point, function) -> str:
    from ...framework.store import point_key

    return point_key(STUDY, function, point)


def _scene(table: Mapping):
    """The validated scene of a point's table (its motion unused)."""
    return scene_from_dict({**table, "motion": dict(_FREE)}, merged=True)


def _rocking_points(grid, options, base, loads) -> list[dict]:
    """The continuum's rotation pushovers, two per (soil, fs_v) in array order."""
    return [p for soil in grid.soils for fs in grid.fs_v
            for p in rocking_points(base, soil, loads[soil] / fs, options)]


def _estimate(grid, options, motions, base, g, store, statics_points, loads,
              impedance_points) -> Estimate:
    """The cost of what is not stored yet. A soil whose statics are not stored has no vertical
    load yet: its dynamic points and its rotation pushovers all count as still to run. The
    rates are those of the grid's stored dynamic runs, else of the store's others."""
    static_records = [store.get(_key(p, evaluate_static)) for p in statics_points]
    impedance_records = [store.get(_key(p, evaluate_impedance)) for p in impedance_points]
    impedance_rows = [(soil, impedance_dofs(p), len(p["impedance"]["a0"]), r is not None)
                      for soil, p, r in zip(grid.soils, impedance_points, impedance_records)]
    static_rows = []
    for i, soil in enumerate(grid.soils):
        point = statics_points[2 * i]
        table = {**base, "soil": point["soil"],
                 "continuum": {**base.get("continuum", {}), **point["continuum"]}}
        static_rows.append((soil, _scene(table), soil in loads))
    rotations = _rocking_points(grid, options, base, {s: loads.get(s, 1.0) for s in grid.soils})
    for k, point in enumerate(rotations):
        soil = grid.soils[k // (2 * len(grid.fs_v))]
        stored = soil in loads and store.has(_key(point, evaluate_continuum))
        static_rows.append((soil, _scene(point["scene"]), stored,
                            len(point["rotations"]) / (options.vertical_steps + 1)))
    dynamic = _dynamic_points(grid, options, motions, base, g,
                              {s: loads.get(s, 1.0) for s in grid.soils})
    durations = {m["name"]: motion_duration(m) for m in motions}
    scenes, rows, records = {}, [], []
    soils = [soil for _, (soil, *_) in _cells(grid) for _ in motions]
    for soil, point in zip(soils, dynamic):
        record = store.get(_key(point, evaluate_dynamic)) if soil in loads else None
        records.append(record)
        if soil not in scenes:
            scenes[soil] = _scene(point["scene"])
        rows.append((soil, scenes[soil], durations[point["motion"]["name"]], record is not None))
        if options.energy:  # the same run again, with E_F
            rows.append((soil, scenes[soil], durations[point["motion"]["name"]],
                         soil in loads and store.has(_key(point, evaluate_energy))))
    pairs = [static_records[i:i + 2] for i in range(0, len(static_records), 2)]
    stored_static = [{"dofs": a["dofs"], "wall_time_s": a["wall_time_s"] + b["wall_time_s"]}
                     for a, b in pairs if a is not None and b is not None]
    timed = [r for r in records if r is not None and "error" not in r] or timed_dynamic_runs(store)
    estimate = estimate_cost(static_rows, rows, stored_static, timed,
                             impedance_rows, [r for r in impedance_records if r is not None])
    keyed = [(_key(p, f), f) for points, f in (
        (statics_points, evaluate_static), (impedance_points, evaluate_impedance),
        (rotations if loads else [], evaluate_continuum), (dynamic if loads else [],
                                                           evaluate_dynamic),
        (dynamic if loads else [], evaluate_energy)) for p in points]
    return with_checks(estimate, store, keyed)


def estimate_map(grid: Grid, options: Options, calibrations: Sequence[str], motions,
                 store) -> Estimate:
    """What the map of ``grid`` would cost with ``store``: the continuum runs it holds and
    those it would still make, estimated as :func:`compute_map` does before its first run
    (nothing is run or written)."""
    return _plan(grid, options, calibrations, motions, store)[-1]


def _plan(grid, options, calibrations, motions, store) -> tuple:
    """The base table and g, the statics points and their stored records, the impedance
    points and the estimate."""
    base = base_table()
    g = load_scene(BASE_SCENE).g
    b = base["foundation"]["half_width"]
    statics_points = [p for soil in grid.soils for p in static_points(soil, options, b)]
    static_records = [store.get(_key(p, evaluate_static)) for p in statics_points]
    loads = {soil: static_records[2 * i + 1]["capacity"] for i, soil in enumerate(grid.soils)
             if static_records[2 * i] is not None and static_records[2 * i + 1] is not None}
    needs = {n for c in calibrations for n in BEDS[c].needs}
    impedance_points = ([impedance_point(soil, options, b) for soil in grid.soils]
                        if "impedance" in needs else [])
    estimate = _estimate(grid, options, motions, base, g, store, statics_points, loads,
                         impedance_points)
    return base, g, statics_points, static_records, impedance_points, estimate


def compute_map(grid: Grid, options: Options, calibrations: Sequence[str], motions,
                ctx) -> MapData:
    """The statics, the continuum runs (both through :func:`.sweep.run_sweep`, stored) and
    every bed's runs (live), after the cost estimate (logged; refused above
    ``options.budget``). The sweeps run on ``ctx.executor``, else on a Dask cluster
    (``ctx.scheduler``), else in this process when the estimate is below
    :data:`IN_PROCESS_SECONDS`, else on ``ctx.workers`` local processes."""
    store = ctx.store
    base, g, statics_points, static_records, impedance_points, estimate = _plan(
        grid, options, calibrations, motions, store)
    impedance_stored = [store.has(_key(p, evaluate_impedance)) for p in impedance_points]
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
        elif executor is None and (estimate.runs or estimate.checks):
            n = max(1, min(workers, estimate.runs + estimate.checks))
            executor = stack.enter_context(sweep_executor(ctx.scheduler, workers=n))
        sweep = {"executor": executor, "chunk": 1, "study": STUDY, "progress": ctx.progress}
        records = run_sweep(evaluate_static, statics_points, store, **sweep)
        statics = tuple(soil_statics(soil, records[2 * i:2 * i + 2])
                        for i, soil in enumerate(grid.soils))
        loads = {s.soil: s.V_ult for s in statics}
        impedances = dict(zip(grid.soils, (soil_impedance(p, r) for p, r in zip(
            impedance_points, run_sweep(evaluate_impedance, impedance_points, store, **sweep)))))
        points = _dynamic_points(grid, options, motions, base, g, loads)
        before = sum(1 for p in points if store.has(_key(p, evaluate_dynamic)))
        rotations = _rocking_points(grid, options, base, loads)
        before += sum(1 for p in rotations if store.has(_key(p, evaluate_continuum)))
        rocking_records = run_sweep(evaluate_continuum, rotations, store, **sweep)
        pushovers = _pushovers(grid, loads, base, rocking_records)
        _build_every_bed(grid, options, calibrations, motions, statics, points, impedances,
                         pushovers)
        runs = run_sweep(evaluate_dynamic, points, store, **sweep)
        if options.energy:
            before += sum(1 for p in points if store.has(_key(p, evaluate_energy)))
            energy_runs = run_sweep(evaluate_energy, points, store, **sweep)
        else:  # the energy runs the store holds (checked like every stored record)
            held = [p for p in points if store.has(_key(p, evaluate_energy))]
            run_sweep(evaluate_energy, held, store, **sweep)
            energy_runs = [store.get(_key(p, evaluate_energy)) for p in points]
    soils_run = sum(1 for i in range(len(grid.soils))
                    if any(r is None for r in static_records[2 * i:2 * i + 2]))
    computed = (len(points) * (2 if options.energy else 1) + len(rotations) - before + soils_run
                + sum(1 for done in impedance_stored if not done))
    rocking = _rocking(grid, options, calibrations, statics, base, g, rocking_records,
                       impedances, pushovers)
    return _assemble(grid, options, calibrations, motions, statics, points, runs, estimate,
                     computed, rocking, impedances, split, pushovers, ctx.progress, energy_runs)


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


def _reference(st: SoilStatics, scene, structure: Mapping, impedance=None,
               rocking=None) -> BedReference:
    """The continuum numbers a bed is calibrated from, at a point's scene: its numbers, the
    soil's statics, and in ``extra`` the soil's density, the point's ``[structure]`` table,
    the soil's impedance (when a bed needs it) and the continuum's rotation pushovers at the
    point's N (``rocking``, where they ran to their end)."""
    extra = {"density": scene.soil.density, "structure": dict(structure),
             "settlement": st.settlement, "load": st.load}
    if impedance is not None:
        extra["impedance"] = impedance
    if rocking is not None:
        extra["rocking"] = rocking
    return BedReference(st.soil, scene.structure.weight, scene.foundation.width,
                        scene.structure.height, st.K_v, st.K_r, st.V_ult,
                        scene.soil.shear_modulus, scene.soil.poisson_ratio, extra=extra)


def _build_every_bed(grid, options, calibrations, motions, statics, points, impedances,
                     pushovers):
    """Build every bed of every cell once (milliseconds), after the statics and before any
    further continuum run: a bed that cannot be built at some point (an impedance bed whose
    rocking frequency is outside the impedance's frequencies) is refused before that work."""
    by_soil = {s.soil: s for s in statics}
    for k, (_, (soil, fs, *_)) in enumerate(_cells(grid)):
        table = points[k * len(motions)]["scene"]
        ref = _reference(by_soil[soil], _scene(table), table["structure"], impedances.get(soil),
                         pushovers[soil, fs])
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
                            grid.h_over_B[0], grid.periods[0], g)
        ref = _reference(by_soil[soil], _scene(table), table["structure"],
                         impedances.get(soil), pushovers[soil, fs])
        if "error" in records[2 * i] or "error" in records[2 * i + 1]:
            beds.append([])  # the continuum's path stopped: nothing to push the beds over on
            continue
        cyclic, monotonic = records[2 * i]["theta"], records[2 * i + 1]["theta"]
        beds.append([bed_rocking(table, ref.N, bed_foundation(name, ref, options), cyclic,
                                 monotonic) for name in calibrations])
    B = 2.0 * base["foundation"]["half_width"]
    return rocking_data(grid.soils, grid.fs_v, loads, records, beds, B, options,
                        len(calibrations))


def _assemble(grid, options, calibrations, motions, statics, points, runs, estimate,
              computed, rocking, impedances, workers, pushovers, progress=None,
              energy_runs=None) -> MapData:
    """Every bed's run of every point (live, in this process) against the continuum's stored
    run, and its E_F against the continuum's energy run where ``energy_runs`` has one (None
    items: not stored). ``progress`` as :func:`.sweep.run_sweep`'s (None: a line on stderr
    every 10 s of a long pass, with the time left; False: silent): the beds of the whole grid
    take minutes."""
    from ....continuum.dynamics.run_control import FAILURE_SETTLEMENT

    report = StderrProgress() if progress is None else (progress or None)
    start, done = time.perf_counter(), 0

    shape = (len(grid.soils), len(grid.fs_v), len(grid.h_over_B), len(grid.periods),
             len(grid.intensities), len(motions))
    nb, nm = len(calibrations), len(MEASURES)
    continuum = np.full(shape + (nm,), np.nan)
    beds = np.full(shape + (nb, nm), np.nan)
    errors = np.full_like(beds, np.nan)
    scale = np.full(shape[:4] + (nm,), np.nan)
    cwall, steps, balance, dofs = (np.full(shape, np.nan) for _ in range(4))
    bwall = np.full(shape + (nb,), np.nan)
    bearing, bed_bearing = np.zeros(shape, bool), np.zeros(shape + (nb,), bool)
    N = np.full(shape[:2], np.nan)
    bed_K_r = np.full(shape[:2] + (nb,), np.nan)
    bed_K_v = np.full_like(bed_K_r, np.nan)
    refusals, warmed = [], set()
    ne = len(ENERGIES)
    cen, ben = np.full(shape + (ne,), np.nan), np.full(shape + (nb, ne), np.nan)
    eerr, escale = np.full(shape + (nb, ne), np.nan), np.full(shape[:4], np.nan)
    left = np.full(shape, np.nan)
    energy_runs = energy_runs if energy_runs is not None else [None] * len(points)
    it = iter(zip(points, runs, energy_runs))
    by_soil = {s.soil: s for s in statics}
    for idx, (soil, fs, hb, period, intensity) in _cells(grid):
        st = by_soil[soil]
        for m in range(len(motions)):
            point, run, erun = next(it)
            done = _tick(report, done, len(points), start)
            at = idx + (m,)
            scene = _scene(point["scene"])
            B, h = scene.foundation.width, scene.structure.height
            ref = _reference(st, scene, point["scene"]["structure"], impedances.get(soil),
                             pushovers[soil, fs])
            k_story, _ = story_constants(scene)
            scl = scales(ref.N, B, h, st.K_v, st.K_r, k_story)
            scale[idx[:4]] = [scl[q] for q in MEASURES]
            escale[idx[:4]] = energy_scale(ref.N, B, st.K_r)
            N[idx[:2]] = ref.N
            failed = run.get("failure") == "bearing"
            if "error" in run:  # the continuum's run failed: nothing to compare a bed with
                refusals.append(f"{_where(soil, fs, hb, period, intensity, motions[m])}, the "
                                f"continuum: {run['error']}")
                if not failed:  # the solver gave up: the point is left out
                    continue
                bearing[at] = True  # its wall time is a part run's: not in the speed
            else:
                continuum[at] = [run["measures"][q] for q in MEASURES]
                cwall[at], steps[at], balance[at] = (run["wall_time_s"], run["steps"],
                                                     run["energy_balance_error"])
                dofs[at] = run["dofs"]
                if erun is not None and "error" not in erun:
                    same_run(erun, run, _where(soil, fs, hb, period, intensity, motions[m]))
                    terms = erun["energy_terms"]
                    cen[at] = energies_of(terms)
                    left[at] = terms["kinetic"] + terms["story"]
            for c, name in enumerate(calibrations):
                foundation = bed_foundation(name, ref, options)
                if name not in warmed:  # the first run compiles the kernels: not timed
                    run_bed(point, foundation)
                    warmed.add(name)
                if np.isnan(bed_K_r[idx[:2] + (c,)]):
                    bed_K_r[idx[:2] + (c,)], bed_K_v[idx[:2] + (c,)] = _bed_stiffness(
                        point, foundation)
                bed = run_bed(point, foundation)
                bwall[at + (c,)] = bed["wall_time_s"]
                if "refused" in bed:
                    refusals.append(f"{_where(soil, fs, hb, period, intensity, motions[m])}, "
                                    f"{name}: {bed['refused']}")
                    continue
                beds[at + (c,)] = [bed["measures"][q] for q in MEASURES]
                ben[at + (c,)] = energies_of(bed["energy"])
                if failed:  # the bed is held to the outcome: does it fail in bearing too?
                    bed_bearing[at + (c,)] = bed["peak_settlement"] >= FAILURE_SETTLEMENT * B
                    continue
                for q, measure in enumerate(MEASURES):
                    errors[at + (c, q)] = relative_error(beds[at + (c, q)],
                                                         run["measures"][measure],
                                                         FLOOR_FRACTION * scl[measure])
                for k in range(ne):
                    if np.isfinite(cen[at + (k,)]):
                        eerr[at + (c, k)] = relative_error(ben[at + (c, k)], cen[at + (k,)],
                                                           FLOOR_FRACTION * escale[idx[:4]])
    _tick(report, done, len(points), start)
    fits = ()
    if FITTED in calibrations:  # the fitted bed's profile per (soil, fs_v): built above, cached
        fits = tuple(((soil, fs), fit_capacity_profile(_reference(
            by_soil[soil], _scene(point["scene"]), point["scene"]["structure"],
            impedances.get(soil), pushovers[soil, fs]), options))
            for (_, (soil, fs, *_)), point in zip(_cells(grid), points[::len(motions)]))
        fits = tuple(dict(fits).items())
    return MapData(grid, options, tuple(motions), tuple(calibrations), tuple(statics), N,
                   continuum, beds, errors, scale, cwall, bwall, steps, balance, dofs, bed_K_r,
                   bed_K_v, tuple(refusals), estimate, computed, rocking,
                   tuple(impedances.items()), bearing, bed_bearing, workers, fits,
                   tuple(pushovers.items()), cen, ben, eerr, escale, left)


def _tick(report, done: int, total: int, start: float) -> int:
    """Report ``done`` of ``total`` points' beds run (``report`` None: silent); one more."""
    if report:
        report(SweepProgress(f"{STUDY} beds", done, total, done, time.perf_counter() - start))
    return done + 1


def _where(soil, fs, hb, period, intensity, motion) -> str:
    return (f"{soil}, FS_v = {fs:g}, h/B = {hb:g}, T = {period:g} s, {intensity:g} × a_up, "
            f"{motion['name']}")


def _bed_stiffness(point: Mapping, foundation: Mapping) -> tuple[float, float]:
    """(K_r, K_v) of the built bed: Σ k_i x_i² and Σ k_i of the reduced model's layout."""
    from ....reduced import build_model

    data = {k: v for k, v in point["scene"].items() if k not in ("soil", "continuum")}
    data["foundation"] = dict(foundation)
    data["motion"] = dict(_FREE)
    layout = build_model(scene_from_dict(data, merged=True)).layout
    return float(layout.rocking_stiffness), float(layout.vertical_stiffness)

