"""The map's plan: its points in array order (the statics, the impedance, the rotation
pushovers and the dynamic runs, each a point of :func:`.sweep.run_sweep`), their store keys,
the reference numbers a bed is calibrated from, and the cost of what is not stored yet,
estimated before any run (:func:`estimate_map`)."""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import replace

from ....scenes import load_scene, scene_from_dict
from ...beds import BASE_SCENE, BEDS, BedReference, base_table
from ...beds.continuum_points import evaluate_continuum
from ...beds.rocking_stiffness import stiffness_reference
from ...framework.store import point_key
from .cost import Estimate, estimate_cost, impedance_dofs, timed_dynamic_runs, with_checks
from .energy_points import evaluate_energy
from .grid import STUDY, Grid, Options
from .impedance_points import evaluate_impedance, impedance_point
from .motions import motion_duration
from .points import evaluate_dynamic, point_table
from .rocking import rocking_points
from .macro_points import (evaluate_macro_fit, fit_rotation_fs, fit_rotation_points,
                           fit_seconds, soil_fit_points)
from .statics import SoilStatics, evaluate_static, soil_statics, static_points

__all__ = ["cells", "dynamic_points", "point_key_of", "scene_of", "map_rocking_points",
           "reference", "bed_needs", "estimate_map", "plan_map", "FREE_MOTION"]


def cells(grid: Grid):
    """(index tuple, values) over soil × fs_v × h/B × period × intensity."""
    axes = (grid.soils, grid.fs_v, grid.h_over_B, grid.periods, grid.intensities)
    for idx in itertools.product(*(range(len(a)) for a in axes)):
        yield idx, tuple(a[i] for a, i in zip(axes, idx))


def dynamic_points(grid, options, motions, base, g, loads) -> list[dict]:
    """Every dynamic point in array order; ``loads[soil]`` the V_ult of each soil (a
    placeholder before the statics are known: the points then serve only for the estimate)."""
    points = []
    for _, (soil, fs, hb, period, intensity) in cells(grid):
        table = point_table(base, soil, options.elements_across, loads[soil] / fs, hb, period, g,
                            options.reference)
        for motion in motions:
            points.append({"scene": table, "motion": motion, "intensity": float(intensity)})
    return points


FREE_MOTION = {"type": "free", "velocity": 1.0, "duration": 1.0}  # a scene's motion, unused


def point_key_of(point, function) -> str:
    """The store key of ``point`` of the map's point ``function``."""
    return point_key(STUDY, function, point)


def scene_of(table: Mapping):
    """The validated scene of a point's table (its motion unused)."""
    return scene_from_dict({**table, "motion": dict(FREE_MOTION)}, merged=True)


def map_rocking_points(grid, options, base, loads) -> list[dict]:
    """The continuum's rotation pushovers, two per (soil, fs_v) in array order."""
    return [p for soil in grid.soils for fs in grid.fs_v
            for p in rocking_points(base, soil, loads[soil] / fs, options)]


def _estimate(grid, options, motions, base, g, store, statics_points, loads,
              impedance_points, macro: bool = False) -> Estimate:
    """The cost of what is not stored yet. A soil whose statics are not stored has no vertical
    load yet: its dynamic points and its rotation pushovers all count as still to run. The
    rates are those of the grid's stored dynamic runs, else of the store's others. With
    ``macro``: the macro-element's rotation pushovers at FS_v the grid lacks, and its fits
    (:func:`_macro_fits`)."""
    static_records = [store.get(point_key_of(p, evaluate_static)) for p in statics_points]
    impedance_records = [store.get(point_key_of(p, evaluate_impedance)) for p in impedance_points]
    impedance_rows = [(soil, impedance_dofs(p), len(p["impedance"]["a0"]), r is not None)
                      for soil, p, r in zip(grid.soils, impedance_points, impedance_records)]
    static_rows = []
    for i, soil in enumerate(grid.soils):
        point = statics_points[2 * i]
        table = {**base, "soil": point["soil"],
                 "continuum": {**base.get("continuum", {}), **point["continuum"]}}
        static_rows.append((soil, scene_of(table), soil in loads))
    rotations = map_rocking_points(grid, options, base, {s: loads.get(s, 1.0) for s in grid.soils})
    for k, point in enumerate(rotations):
        soil = grid.soils[k // (2 * len(grid.fs_v))]
        stored = soil in loads and store.has(point_key_of(point, evaluate_continuum))
        static_rows.append((soil, scene_of(point["scene"]), stored,
                            len(point["rotations"]) / (options.vertical_steps + 1)))
    fit_keys = []
    fits = (_macro_fits(grid, options, base, g, store, loads, static_rows, fit_keys)
            if macro else [])
    dynamic = dynamic_points(grid, options, motions, base, g,
                              {s: loads.get(s, 1.0) for s in grid.soils})
    durations = {m["name"]: motion_duration(m) for m in motions}
    scenes, rows, records = {}, [], []
    soils = [soil for _, (soil, *_) in cells(grid) for _ in motions]
    for soil, point in zip(soils, dynamic):
        record = store.get(point_key_of(point, evaluate_dynamic)) if soil in loads else None
        records.append(record)
        if soil not in scenes:
            scenes[soil] = scene_of(point["scene"])
        rows.append((soil, scenes[soil], durations[point["motion"]["name"]], record is not None))
        if options.energy:  # the same run again, with E_F
            rows.append((soil, scenes[soil], durations[point["motion"]["name"]],
                         soil in loads and store.has(point_key_of(point, evaluate_energy))))
    pairs = [static_records[i:i + 2] for i in range(0, len(static_records), 2)]
    stored_static = [{"dofs": a["dofs"], "wall_time_s": a["wall_time_s"] + b["wall_time_s"]}
                     for a, b in pairs if a is not None and b is not None]
    timed = [r for r in records if r is not None and "error" not in r] or timed_dynamic_runs(store)
    estimate = estimate_cost(static_rows, rows, stored_static, timed,
                             impedance_rows, [r for r in impedance_records if r is not None])
    keyed = [(point_key_of(p, f), f) for points, f in (
        (statics_points, evaluate_static), (impedance_points, evaluate_impedance),
        (rotations if loads else [], evaluate_continuum), (dynamic if loads else [],
                                                           evaluate_dynamic),
        (dynamic if loads else [], evaluate_energy)) for p in points]
    keyed += [(key, evaluate_macro_fit) for key in fit_keys]
    if fits:
        seconds = sum(f for _, f in fits)
        by_soil = dict(estimate.by_soil)
        for soil, f in fits:
            by_soil[soil] = by_soil.get(soil, 0.0) + f
        estimate = replace(estimate, fits=len(fits), fit_seconds=seconds, by_soil=by_soil,
                           seconds=estimate.seconds + seconds)
    return with_checks(estimate, store, keyed)


def _macro_fits(grid, options, base, g, store, loads, static_rows,
                keys: list) -> list[tuple[str, float]]:
    """The macro-element's work not yet stored: its rotation pushovers (at the FS_v of
    ``options.macro_fs_v``, and the repeated cycles) that the grid does not push over,
    appended to ``static_rows``, and
    (soil, estimated seconds) of each soil's fit the store does not hold; the store keys of
    the fits whose inputs it holds are appended to ``keys``."""
    rotations = fit_rotation_points(grid.soils, options, base,
                                    {s: loads.get(s, 1.0) for s in grid.soils})
    kinds = fit_rotation_fs(options)
    per_soil = len(kinds)
    todo = []
    for i, soil in enumerate(grid.soils):
        mine = rotations[i * per_soil:(i + 1) * per_soil]
        records = []
        for k, point in enumerate(mine):
            record = store.get(point_key_of(point, evaluate_continuum)) if soil in loads else None
            records.append(record)
            if not (kinds[k][1] and kinds[k][0] in grid.fs_v):
                static_rows.append((soil, scene_of(point["scene"]), record is not None,
                                    len(point["rotations"]) / (options.vertical_steps + 1)))
        if all(r is not None for r in records) and soil in loads:
            statics = {soil: _loads_statics(store, soil, options, base)}
            rotation_keys = [point_key_of(p, evaluate_continuum) for p in mine]
            point = soil_fit_points([soil], options, base, statics, mine, records,
                                    rotation_keys, g)[0]
            keys.append(point_key_of(point, evaluate_macro_fit))
            if store.has(keys[-1]):
                continue
        todo.append((soil, fit_seconds(mine, options.macro_evaluations)))
    return todo


def _loads_statics(store, soil, options, base) -> SoilStatics:
    """The soil's stored statics (both records are in ``store``)."""
    b = base["foundation"]["half_width"]
    return soil_statics(soil, [store.get(point_key_of(p, evaluate_static))
                               for p in static_points(soil, options, b)])


def estimate_map(grid: Grid, options: Options, calibrations: Sequence[str], motions,
                 store) -> Estimate:
    """What the map of ``grid`` would cost with ``store``: the continuum runs it holds and
    those it would still make, estimated as :func:`compute_map` does before its first run
    (nothing is run or written)."""
    return plan_map(grid, options, calibrations, motions, store)[-1]


def plan_map(grid, options, calibrations, motions, store) -> tuple:
    """The base table and g, the statics points and their stored records, the impedance
    points and the estimate."""
    base = base_table()
    g = load_scene(BASE_SCENE).g
    b = base["foundation"]["half_width"]
    statics_points = [p for soil in grid.soils for p in static_points(soil, options, b)]
    static_records = [store.get(point_key_of(p, evaluate_static)) for p in statics_points]
    loads = {soil: static_records[2 * i + 1]["capacity"] for i, soil in enumerate(grid.soils)
             if static_records[2 * i] is not None and static_records[2 * i + 1] is not None}
    needs = bed_needs(calibrations, options)
    impedance_points = ([impedance_point(soil, options, b) for soil in grid.soils]
                        if "impedance" in needs else [])
    estimate = _estimate(grid, options, motions, base, g, store, statics_points, loads,
                         impedance_points, "macro" in needs)
    return base, g, statics_points, static_records, impedance_points, estimate


def bed_needs(calibrations, options) -> set:
    """The stored continuum quantities beyond the statics that the beds ``calibrations`` need
    (their registry entries' ``needs``), and the impedance when ``options.bed_stiffness`` is
    not ``static`` (:mod:`...beds.rocking_stiffness`)."""
    needs = {n for c in calibrations for n in BEDS[c].needs}
    if options.bed_stiffness != "static":
        needs.add("impedance")
    return needs


def reference(st: SoilStatics, scene, structure: Mapping, impedance=None,
              rocking=None, bed_stiffness: str = "static") -> BedReference:
    """The continuum numbers a bed is calibrated from, at a point's scene: its numbers, the
    soil's statics (N the whole weight on the footing, the structure's ``vertical_weight``:
    on the half-plane the footing carries a share of it), and in ``extra`` the soil's density,
    the footing's ``sway_stiffness`` where the reference's footing sways on a tie, the point's
    ``[structure]`` table,
    the soil's impedance (when a bed needs it) and the continuum's rotation pushovers at the
    point's N (``rocking``, where they ran to their end). ``bed_stiffness`` (``options.
    bed_stiffness``) ``static``: K_v and K_r are the soil's statics (the box's); ``rocking``:
    the half-plane impedance's at the structure's rocking frequency
    (:func:`...beds.rocking_stiffness.stiffness_reference`)."""
    extra = {"density": scene.soil.density, "structure": dict(structure),
             "settlement": st.settlement, "load": st.load}
    tie = scene.continuum.horizontal_tie if scene.continuum is not None else None
    if tie is not None:  # the half-plane's footing sways on its tie, and so do the beds
        extra["sway_stiffness"] = float(tie)
    if impedance is not None:
        extra["impedance"] = impedance
    if rocking is not None:
        extra["rocking"] = rocking
        if "macro" in rocking:  # the soil's macro-element fit (the map's stored record)
            extra["macro"] = rocking["macro"]
    ref = BedReference(st.soil, scene.structure.vertical_weight, scene.foundation.width,
                       scene.structure.height, st.K_v, st.K_r, st.V_ult,
                       scene.soil.shear_modulus, scene.soil.poisson_ratio, extra=extra)
    return stiffness_reference(ref, bed_stiffness, scene.g)
