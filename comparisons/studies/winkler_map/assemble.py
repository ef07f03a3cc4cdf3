"""Every bed's run of every point of the map (live, in this process) against the continuum's
stored run: the measures, the signed errors (bed − continuum)/max(|continuum|, floor), the
floor :data:`.grid.FLOOR_FRACTION` × the measure's scale (:func:`.points.scales`), the
timings and the energies, filled into :class:`.dataset.PointArrays` (NaN where a run was
refused)."""

from __future__ import annotations

import time
from collections.abc import Mapping

import numpy as np

from ....continuum.dynamics.validity import BEYOND, SMALL_STRAIN_LIMIT
from ....scenes import scene_from_dict
from ...beds import bed_foundation
from ...beds.fitted import FITTED, fit_capacity_profile
from ...framework.study import relative_error
from ...framework.sweep import StderrProgress, SweepProgress
from .bed_runs import element_analysis, run_bed
from .dataset import PointArrays
from .energy import ENERGIES, energies_of, energy_scale, same_run
from .grid import FLOOR_FRACTION, MEASURES, STUDY
from .plan import FREE_MOTION, cells, reference, scene_of
from .points import scales, story_constants

__all__ = ["assemble"]

def assemble(grid, options, calibrations, motions, statics, points, runs, impedances,
             pushovers, progress=None, energy_runs=None) -> tuple[PointArrays, list, dict]:
    """Every bed's run of every point (live, in this process) against the continuum's stored
    run, and its E_F against the continuum's energy run where ``energy_runs`` has one (None
    items: not stored): the arrays, the runs that failed (texts) and the fitted bed's capacity
    profile per (soil, fs_v) (when it is compared). ``progress`` as
    :func:`.sweep.run_sweep`'s (None: a line on stderr every 10 s of a long pass, with the time
    left; False: silent): the beds of the whole grid take minutes."""
    report = StderrProgress() if progress is None else (progress or None)
    start, done = time.perf_counter(), 0
    shape = (len(grid.soils), len(grid.fs_v), len(grid.h_over_B), len(grid.periods),
             len(grid.intensities), len(motions))
    a = PointArrays.empty(shape, len(calibrations))
    refusals, warmed = [], set()
    energy_runs = energy_runs if energy_runs is not None else [None] * len(points)
    it = iter(zip(points, runs, energy_runs))
    by_soil = {s.soil: s for s in statics}
    for idx, (soil, fs, hb, period, intensity) in cells(grid):
        st = by_soil[soil]
        for m in range(len(motions)):
            point, run, erun = next(it)
            done = _tick(report, done, len(points), start)
            at = idx + (m,)
            where = _where(soil, fs, hb, period, intensity, motions[m])
            scene = scene_of(point["scene"])
            ref = reference(st, scene, point["scene"]["structure"], impedances.get(soil),
                            pushovers[soil, fs], options.bed_stiffness)
            k_story, _ = story_constants(scene)
            scl = scales(ref.N, scene.foundation.width, scene.structure.height, st.K_v, st.K_r,
                         k_story)
            a.scale[idx[:4]] = [scl[q] for q in MEASURES]
            a.energy_scale[idx[:4]] = energy_scale(ref.N, scene.foundation.width, st.K_r)
            a.N[idx[:2]] = ref.N
            if not _continuum_into(a, at, run, erun, where, refusals):
                continue
            for c, name in enumerate(calibrations):
                foundation = bed_foundation(name, ref, options)
                analysis = (element_analysis(options) if foundation.get("law") == "macro"
                            else None)
                if name not in warmed:  # the first run compiles the kernels: not timed
                    run_bed(point, foundation, analysis)
                    warmed.add(name)
                if np.isnan(a.bed_K_r[idx[:4] + (c,)]):
                    a.bed_K_r[idx[:4] + (c,)], a.bed_K_v[idx[:4] + (c,)] = _bed_stiffness(
                        point, foundation)
                bed = run_bed(point, foundation, analysis)
                a.bed_wall[at + (c,)] = bed["wall_time_s"]
                if "refused" in bed:
                    refusals.append(f"{where}, {name}: {bed['refused']}")
                    continue
                _bed_into(a, at, c, bed, run, scl, scene.foundation.width)
    _tick(report, done, len(points), start)
    return a, refusals, _fits(grid, options, calibrations, motions, by_soil, points,
                              impedances, pushovers)


def _continuum_into(a: PointArrays, at: tuple, run: Mapping, erun, where: str,
                    refusals: list) -> bool:
    """The continuum's run (and energy run) of point ``at`` into ``a``; False where its solver
    gave up (the point is left out, with a refusal); a bearing failure is marked, and its
    beds are still run (each is held to the outcome). A run beyond the small-strain reference
    (its record's ``validity``, :mod:`~upliftlab.continuum.dynamics.validity`) is marked and
    left out like a refused one: no bed error, and no outcome a bed is held to. Records made
    before the verdict was stored carry none and read as before, whatever their
    ``max_plastic_strain``. Whether the run's far field yielded (its record's ``far_field``)
    is marked for every run that stored it; the point is compared all the same."""
    far = run.get("far_field")
    if far:  # "elastic" or "from z1 to z2"; records made before it carry none
        a.far_yield[at] = far != "elastic"
    if "error" in run:  # the continuum's run failed: nothing to compare a bed with
        refusals.append(f"{where}, the continuum: {run['error']}")
        if run.get("failure") != "bearing":  # the solver gave up: the point is left out
            return False
        a.bearing[at] = True  # its wall time is a part run's: not in the speed
        return True
    if run.get("validity") == BEYOND:  # only records that carry the verdict (module docstring)
        refusals.append(f"{where}, the continuum: {BEYOND} (largest plastic strain "
                        f"{run['max_plastic_strain']:.3g} > {SMALL_STRAIN_LIMIT:g})")
        a.beyond[at] = True
        return False
    a.continuum[at] = [run["measures"][q] for q in MEASURES]
    a.continuum_wall[at], a.steps[at], a.balance[at] = (run["wall_time_s"], run["steps"],
                                                        run["energy_balance_error"])
    a.dofs[at] = run["dofs"]
    if erun is not None and "error" not in erun:
        same_run(erun, run, where)
        terms = erun["energy_terms"]
        a.continuum_energy[at] = energies_of(terms)
        a.energy_left[at] = terms["kinetic"] + terms["story"]
    return True


def _bed_into(a: PointArrays, at: tuple, c: int, bed: Mapping, run: Mapping, scl: Mapping,
              B: float) -> None:
    """Bed ``c``'s run of point ``at`` into ``a``: its measures and energies, and its errors
    against the continuum's run; at a bearing failure of the continuum, whether the bed's
    base settled by the failure settlement too."""
    from ....continuum.dynamics.run_control import FAILURE_SETTLEMENT

    a.beds[at + (c,)] = [bed["measures"][q] for q in MEASURES]
    a.bed_energy[at + (c,)] = energies_of(bed["energy"])
    if run.get("failure") == "bearing":
        a.bed_bearing[at + (c,)] = bed["peak_settlement"] >= FAILURE_SETTLEMENT * B
        return
    for q, measure in enumerate(MEASURES):
        a.errors[at + (c, q)] = relative_error(a.beds[at + (c, q)], run["measures"][measure],
                                               FLOOR_FRACTION * scl[measure])
    for k in range(len(ENERGIES)):
        if np.isfinite(a.continuum_energy[at + (k,)]):
            a.energy_errors[at + (c, k)] = relative_error(
                a.bed_energy[at + (c, k)], a.continuum_energy[at + (k,)],
                FLOOR_FRACTION * a.energy_scale[at[:4]])


def _fits(grid, options, calibrations, motions, by_soil, points, impedances,
          pushovers) -> dict:
    """The fitted bed's capacity profile per (soil, fs_v) (built above, cached; {} when the
    fitted bed is not compared)."""
    if FITTED not in calibrations:
        return {}
    fits = (((soil, fs), fit_capacity_profile(reference(
        by_soil[soil], scene_of(point["scene"]), point["scene"]["structure"],
        impedances.get(soil), pushovers[soil, fs], options.bed_stiffness), options))
        for (_, (soil, fs, *_)), point in zip(cells(grid), points[::len(motions)]))
    return dict(fits)


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
    data["motion"] = dict(FREE_MOTION)
    layout = build_model(scene_from_dict(data, merged=True)).layout
    return float(layout.rocking_stiffness), float(layout.vertical_stiffness)

