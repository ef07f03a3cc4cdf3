"""The map's summary, read from its data alone (the :class:`xarray.DataTree` of ``map`` and
``statics``, as computed or as :func:`upliftlab.open_study` opens its folder again):
:func:`key_numbers` (``summary.json``) and :func:`summarise` (``summary.md``)."""

from __future__ import annotations

import math

import numpy as np

from ...beds import BEDS
from .analysis import BIAS_MEASURES, RECORD_KINDS, analyse, signed_bias
from .energy import energy_lines, energy_numbers
from .goal import goal_text
from .holdout import holdout_lines, holdout_numbers, out_of_sample
from .grid import FLOOR_FRACTION, SOIL_LABELS
from .parts import (capacity_fits_of, estimate_of, impedances_of, labels, map_of,
                    options_of, soil_statics_of, statics_of, texts, worst_statics)
from .rocking import QUANTITY_GROUPS
from .sections import (SOIL_NOTE, bias_lines, capacity_fit_text, f4, finite,
                       impedance_text, input_text, mesh_text, pct, pick_table, pick_text,
                       rocking_lines, speed_of_soils, statics_table)
from .verdicts import sway_note, verdict_counts, verdict_lines

__all__ = ["key_numbers", "summarise", "share_text", "speed_text", "cost_text", "wall_total"]


def _clean(mapping: dict) -> dict:
    return {k: finite(v) for k, v in mapping.items()}


def _elapsed(m) -> float:
    return float(m.attrs.get("elapsed_s", math.nan))


def key_numbers(tree) -> dict:
    """The map's key numbers (``summary.json``): the statics, the regions, the picks, the
    share, the goal, the speed, the cost, the foundation energy and the runs that failed."""
    m, st = map_of(tree), statics_of(tree)
    a = analyse(m)
    statics = soil_statics_of(st)
    calibrations = labels(m, "calibration")
    ratio = np.array([s.V_ult for s in statics])[:, None] / m.vertical_load.transpose(
        "soil", "fs_v").values
    worst = worst_statics(st)
    estimate = estimate_of(m)
    balance = m.energy_balance_error.values
    return {
        "elements_across": options_of(m)["elements_across"],
        "statics_worst_error": {
            soil: {name: dict(zip(QUANTITY_GROUPS, (finite(v) for v in worst[s, c])))
                   for c, name in enumerate(calibrations)}
            for s, soil in enumerate(labels(st, "soil"))},
        "signed_bias": _bias_numbers(m, calibrations),
        "points": int(m.continuum_wall_time.size),
        "calibrations": calibrations,
        "motions": labels(m, "motion"),
        "statics": {s.soil: {"K_v": s.K_v, "K_r": s.K_r, "V_ult": s.V_ult, "plateau": s.plateau,
                             "dofs": s.dofs, "wall_time_s": s.wall_time_s} for s in statics},
        "fs_v_measured": ratio.tolist(),
        "regions": [{"calibration": r.calibration, "soil": r.soil, "text": r.text,
                     "passing": r.passing, "total": r.total} for r in a.regions],
        "picks": {p.measure: {"best": p.best, "median": _clean(p.median), "p90": _clean(p.p90),
                              "record_median": _clean(p.record_median),
                              "record_p90": _clean(p.record_p90), "refused": p.refused,
                              "points": p.points} for p in a.picks},
        "share": {"threshold": a.share.threshold, "points": a.share.points,
                  "by_calibration": a.share.by_bed, "best": a.share.best,
                  "best_share": a.share.best_share, "any_share": a.share.any_share,
                  "bearing_failures": a.share.bearing_failures,
                  "bearing_failures_called": a.share.called},
        "goal": {"met": a.goal.met, "calibration": a.goal.bed, "share": a.goal.share,
                 "median_speedup": finite(a.goal.speedup), "share_needed": a.goal.share_needed,
                 "speedup_needed": a.goal.speedup_needed,
                 "share_by_soil_fs_v": {f"{soil} FS_v={fs:g}": finite(v)
                                        for (soil, fs), v in a.goal.by_soil_fs_v.items()},
                 "misses": a.goal.misses, "misses_over": finite(a.goal.over),
                 "misses_under": finite(a.goal.under)},
        "out_of_sample": holdout_numbers(out_of_sample(m)),
        "speed": {"median": _clean(a.speed.median), "minimum": _clean(a.speed.minimum),
                  "continuum_median_s": finite(a.speed.continuum_median),
                  "bed_median_s": _clean(a.speed.bed_median)},
        "cost": {"estimated_runs": estimate.runs, "estimated_s": estimate.seconds,
                 "estimate_source": estimate.source, "computed_runs": int(m.attrs["computed"]),
                 "continuum_wall_s": wall_total(m, st)},
        "capacity_fits": {f"{soil} FS_v={fs:g}": {"beta": beta, "misfit": misfit}
                          for (soil, fs), (beta, misfit) in capacity_fits_of(st).items()},
        "impedance": {soil: {"a0": [float(v) for v in imp["a0"]],
                             "omega": [float(v) for v in imp["omega"]],
                             "C_v": [float(v) for v in imp["C_v"]],
                             "C_r": [float(v) for v in imp["C_r"]], "dofs": imp["dofs"],
                             "wall_time_s": imp["wall_time_s"]}
                      for soil, imp in impedances_of(st).items()},
        "max_energy_balance_error": (finite(float(np.nanmax(balance)))
                                     if np.isfinite(balance).any() else None),
        "foundation_energy": energy_numbers(a.energy),
        "refusals": list(texts(m.attrs.get("refusals", ""))),
        "continuum_verdicts": verdict_counts(m),
        "elapsed_s": _elapsed(m),
    }


def _bias_numbers(m, calibrations) -> dict:
    """{soil: {calibration: {measure: [signed median per FS_v]}}} (fractions)."""
    bias = signed_bias(m)
    return {soil: {name: {q: [finite(float(v)) for v in bias[s, :, c, k]]
                          for k, q in enumerate(BIAS_MEASURES)}
                   for c, name in enumerate(calibrations)}
            for s, soil in enumerate(labels(m, "soil"))}


def _values(ds, dim: str) -> str:
    return ", ".join(f"{v:g}" for v in ds[dim].values.tolist())


def summarise(tree) -> str:
    """The map's ``summary.md``, every number from its data."""
    m, st = map_of(tree), statics_of(tree)
    a = analyse(m)
    o = options_of(m)
    calibrations = labels(m, "calibration")
    kinds = labels(m, "motion_kind")
    refusals = texts(m.attrs.get("refusals", ""))
    records = sum(1 for k in kinds if k in RECORD_KINDS)
    fast = bool(int(m.attrs.get("fast", 0)))
    lines = [f"# Winkler beds against the continuum: the map{' (fast)' if fast else ''}", "",
             f"{m.continuum_wall_time.size} points: soils "
             f"{', '.join(SOIL_LABELS[s] for s in labels(m, 'soil'))}; "
             f"FS_v ∈ {{{_values(m, 'fs_v')}}} on the continuum's own vertical "
             f"capacity (N = V_ult/FS_v); h/B ∈ {{{_values(m, 'h_over_B')}}}; "
             f"fixed-base period T ∈ {{{_values(m, 'period')}}} s; intensity "
             f"∈ {{{_values(m, 'intensity')}}} × a_up, where a_up = g B/(6h) "
             "is the quasi-static uplift acceleration of a rigid block on a uniform tensionless "
             f"Winkler bed (e = B/6); motions ({len(kinds)}, {records} records, each run in "
             f"full): {', '.join(labels(m, 'motion'))}. Beds of {o['springs']} springs: "
             + "; ".join(f"`{c}` {BEDS[c].label}" for c in calibrations if c in BEDS) + ".",
             "", mesh_text(m), "", SOIL_NOTE + speed_of_soils(m), "", input_text(m),
             "", sway_note(m), "",
             "Errors are (bed − continuum)/max(|continuum|, floor), the floor "
             f"{FLOOR_FRACTION:g} × the measure at a uniform bed's uplift threshold (θ_up = "
             "N B/(6 K_r), the settlement N/K_v, the shear N B/(6h) and the story deformation "
             "under it). Both models are measured alike: peak |θ|, peak edge uplift (the larger "
             "gap of the two footing edges), residual settlement (the centre's settlement when "
             "the base is flattest in the last quarter of the run), residual rotation (the mean "
             "θ over the last quarter), peak |u| and peak story shear |k u + c u̇|; and the "
             "foundation energy E_F where the continuum's energy run is stored (below).", "",
             f"Wall time {_elapsed(m):.1f} s.", "",
             *verdict_lines(m),
             "## The continuum statics", "",
             "K_v and K_r (every contact node tied to the footing, elastic soil) and V_ult (the "
             f"largest load of a vertical pushover to {o['settlement_ratio']:g} B) do not "
             "depend on N: one pair of stored static runs per soil serves every FS_v, N = "
             "V_ult/FS_v.", "",
             *statics_table(m, st), "", *impedance_text(st), *capacity_fit_text(st),
             "## The beds' statics against the continuum's", "",
             *rocking_lines(m, st), "",
             "## Where each bed is enough", "",
             f"A cell (FS_v, h/B) of a soil passes when, at every period and intensity, the "
             f"median over the motions of |error| is within {100 * o['theta_tolerance']:g} % in "
             f"peak θ and in peak edge uplift and within {100 * o['settlement_tolerance']:g} % "
             "in residual settlement.", ""]
    lines += [f"- {r.text}." for r in a.regions]
    lines += ["", "## Which calibration for which quantity", "",
              *pick_table(calibrations, a), "", *[f"- {pick_text(p)}." for p in a.picks], "",
              "## Foundation energy", "", *energy_lines(m, a.energy), "",
              "## Where the beds miss", "", *bias_lines(m), "",
              "## How much of the map a calibrated bed covers", "", share_text(a), "",
              goal_text(a.goal), "",
              "## Out of sample", "", *holdout_lines(m, out_of_sample(m)),
              "## Speed", "", speed_text(a), "", "## Cost", "", cost_text(m, st), ""]
    if refusals:
        lines += [f"Runs that failed: {len(refusals)} (a bed refused by its integrator, a "
                  "continuum run its solver gave up on, whose point then has no bed compared, "
                  "or a continuum run that ended in a bearing failure of the soil; their "
                  "errors are NaN and every statistic above leaves them out, except the "
                  "bearing failures, which the share and the regions hold the beds to):",
                  ""] + [f"- {r}" for r in refusals[:20]] + [""]
    return "\n".join(lines)


def share_text(a) -> str:
    s = a.share
    thr = f"{100 * s.threshold:g} %"
    by_bed = ", ".join(f"{k} {pct(v)}" for k, v in s.by_bed.items())
    text = (f"Of the map's {s.points} points (cells × motions), the best single calibration "
            f"({s.best}) is within {thr} of the continuum in both peak θ and peak edge uplift "
            f"at **{pct(s.best_share)}**; the best calibration chosen point by point at "
            f"{pct(s.any_share)}. Per calibration: {by_bed}.")
    if s.bearing_failures:
        from ....continuum.dynamics.run_control import FAILURE_SETTLEMENT

        called = ", ".join(f"{k} {v}" for k, v in s.called.items())
        text += (f" {s.bearing_failures} of the points ended in a bearing failure of the "
                 f"continuum's soil (its footing settled {FAILURE_SETTLEMENT:g} B or more in a "
                 "mechanism): each is a hit for a bed whose base settles "
                 f"{FAILURE_SETTLEMENT:g} B too and a miss for the others; beds that failed "
                 f"with it: {called}.")
    return text


def speed_text(a) -> str:
    sp = a.speed
    parts = ", ".join(f"{k} {f4(v, 3)} × (at least {f4(sp.minimum[k], 3)} ×; median run "
                      f"{f4(sp.bed_median[k], 3)} s)" for k, v in sp.median.items())
    return (f"The continuum's wall time over each bed's, point by point on this machine (the "
            f"continuum's stored with its run, median {f4(sp.continuum_median, 3)} s; the "
            f"beds' measured in this run): median {parts}.")


def wall_total(m, st) -> float:
    """The wall time (s) of every continuum run the map read: its dynamic runs, the soils'
    statics and their impedances."""
    return (float(np.nansum(m.continuum_wall_time.values))
            + sum(s.wall_time_s for s in soil_statics_of(st))
            + sum(imp["wall_time_s"] or 0.0 for imp in impedances_of(st).values()))


def cost_text(m, st) -> str:
    workers = int(m.attrs["workers"]) if "workers" in m.attrs else None
    return (f"Estimated before any work: {estimate_of(m).text(workers)}. This run computed "
            f"{int(m.attrs['computed'])} continuum runs; the continuum's stored runs took "
            f"{wall_total(m, st):.1f} s of wall time in all.")
