"""The map's summary: key numbers and the Markdown text, computed from the data."""

from __future__ import annotations

import math

import numpy as np

from .analysis import RECORD_KINDS, pick_text
from ...beds import BEDS
from .cost import SECONDS_PER_DOF_STEP, compiled_soil_model
from .energy import energy_lines, energy_numbers
from .goal import goal_text
from .grid import MEASURE_LABELS, SOIL_LABELS, FLOOR_FRACTION

__all__ = ["summary_numbers", "summary_markdown", "MESH_NOTE", "SOIL_NOTE",
           "SWAY_NOTE"]

#: Why the full map runs on 16 elements across (the measured mesh differences of
#: benchmarks/CONTINUUM_CONVERGENCE.md, 10 s of El Centro on the clay, explicit route).
MESH_NOTE = ("The reference mesh is 16 elements across B: against 32 across it differs by "
             "+0.24 % in peak θ, +0.06 % in peak edge uplift and −1.4 % in residual settlement, "
             "while 8 across differs by −1.1 %, −1.1 % and −7.0 % "
             "(the project's mesh-convergence benchmark of the explicit route, 10 s of El "
             "Centro on the clay): no coarser "
             "mesh is within 1 %, so the full map runs on 16 across.")
SWAY_NOTE = ("No bed has a sway spring or a horizontal dashpot: the map's soils have a "
             "frictionless interface, and with it the continuum's explicit route holds the "
             "footing's horizontal displacement to the base's (the footing's u relative to the "
             "moving base is zero at every step), so the continuum footing does not sway and a "
             "sway spring would have nothing to match.")
SOIL_NOTE = ("The continuum's soil has one Young's modulus everywhere: its stiffness does not "
             "grow with confinement (the frictional soil's strength does, through φ).")


def _f(value, digits: int = 4) -> str:
    return "n/a" if value is None or not math.isfinite(value) else f"{value:.{digits}g}"


def _pct(value) -> str:
    return "n/a" if value is None or not math.isfinite(value) else f"{100 * value:.1f} %"


def _finite(value):
    return float(value) if value is not None and math.isfinite(value) else None


def summary_numbers(result, elapsed: float) -> dict:
    d, a = result.data, result.analysis
    statics = {s.soil: {"K_v": s.K_v, "K_r": s.K_r, "V_ult": s.V_ult, "plateau": s.plateau,
                        "dofs": s.dofs, "wall_time_s": s.wall_time_s} for s in d.statics}
    ratio = np.array([s.V_ult for s in d.statics])[:, None] / d.N
    from .rocking import QUANTITY_GROUPS

    worst = d.rocking.group_worst()
    rocking = {soil: {name: dict(zip(QUANTITY_GROUPS, (_finite(v) for v in worst[s, c])))
                      for c, name in enumerate(d.calibrations)}
               for s, soil in enumerate(d.grid.soils)}
    return {
        "elements_across": d.options.elements_across,
        "statics_worst_error": rocking,
        "signed_bias": _bias_numbers(d),
        "points": int(d.continuum_wall.size),
        "calibrations": list(d.calibrations),
        "motions": list(d.motion_names),
        "statics": statics,
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
                 "median_speedup": _finite(a.goal.speedup), "share_needed": a.goal.share_needed,
                 "speedup_needed": a.goal.speedup_needed,
                 "share_by_soil_fs_v": {f"{soil} FS_v={fs:g}": _finite(v)
                                        for (soil, fs), v in a.goal.by_soil_fs_v.items()},
                 "misses": a.goal.misses, "misses_over": _finite(a.goal.over),
                 "misses_under": _finite(a.goal.under)},
        "speed": {"median": _clean(a.speed.median), "minimum": _clean(a.speed.minimum),
                  "continuum_median_s": _finite(a.speed.continuum_median),
                  "bed_median_s": _clean(a.speed.bed_median)},
        "cost": {"estimated_runs": d.estimate.runs, "estimated_s": d.estimate.seconds,
                 "estimate_source": d.estimate.source, "computed_runs": d.computed,
                 "continuum_wall_s": float(np.nansum(d.continuum_wall))
                 + sum(s.wall_time_s for s in d.statics)
                 + sum(imp.metadata.get("wall_time_s", 0.0) for _, imp in d.impedances)},
        "capacity_fits": {f"{soil} FS_v={fs:g}": {"beta": fit.beta, "misfit": fit.misfit}
                          for (soil, fs), fit in d.capacity_fits},
        "impedance": {soil: {"a0": [float(v) for v in imp.a0],
                             "omega": [float(v) for v in imp.omega],
                             "C_v": [float(v) for v in imp.dashpot("v")],
                             "C_r": [float(v) for v in imp.dashpot("r")], "dofs": imp.dofs,
                             "wall_time_s": imp.metadata.get("wall_time_s")}
                      for soil, imp in d.impedances},
        "max_energy_balance_error": (_finite(float(np.nanmax(d.balance)))
                                     if np.isfinite(d.balance).any() else None),
        "foundation_energy": energy_numbers(a.energy),
        "refusals": list(d.refusals),
        "elapsed_s": elapsed,
    }


def _bias_numbers(d) -> dict:
    """{soil: {calibration: {measure: [signed median per FS_v]}}} (fractions)."""
    from .analysis import BIAS_MEASURES, signed_bias

    bias = signed_bias(d)
    return {soil: {name: {m: [_finite(float(v)) for v in bias[s, :, c, k]]
                          for k, m in enumerate(BIAS_MEASURES)}
                   for c, name in enumerate(d.calibrations)}
            for s, soil in enumerate(d.grid.soils)}


def _clean(mapping: dict) -> dict:
    return {k: _finite(v) for k, v in mapping.items()}


def summary_markdown(result, fast: bool, elapsed: float) -> str:
    d, a = result.data, result.analysis
    g, o = d.grid, d.options
    motions = ", ".join(d.motion_names)
    records = sum(1 for k in d.motion_kinds if k in RECORD_KINDS)
    lines = [f"# Winkler beds against the continuum: the map{' (fast)' if fast else ''}", "",
             f"{d.continuum_wall.size} points: soils {', '.join(SOIL_LABELS[s] for s in g.soils)}; "
             f"FS_v ∈ {{{', '.join(f'{v:g}' for v in g.fs_v)}}} on the continuum's own vertical "
             f"capacity (N = V_ult/FS_v); h/B ∈ {{{', '.join(f'{v:g}' for v in g.h_over_B)}}}; "
             f"fixed-base period T ∈ {{{', '.join(f'{v:g}' for v in g.periods)}}} s; intensity "
             f"∈ {{{', '.join(f'{v:g}' for v in g.intensities)}}} × a_up, where a_up = g B/(6h) "
             "is the quasi-static uplift acceleration of a rigid block on a uniform tensionless "
             f"Winkler bed (e = B/6); motions ({len(d.motions)}, {records} records, each run in "
             f"full): {motions}. Beds of {o.springs} springs: "
             + "; ".join(f"`{c}` {BEDS[c].label}" for c in d.calibrations if c in BEDS) + ".",
             "", _mesh_text(d, fast), "", SOIL_NOTE + _speed_of_soils(d), "", _input_text(d),
             "", SWAY_NOTE, "",
             "Errors are (bed − continuum)/max(|continuum|, floor), the floor "
             f"{FLOOR_FRACTION:g} × the measure at a uniform bed's uplift threshold (θ_up = "
             "N B/(6 K_r), the settlement N/K_v, the shear N B/(6h) and the story deformation "
             "under it). Both models are measured alike: peak |θ|, peak edge uplift (the larger "
             "gap of the two footing edges), residual settlement (the centre's settlement when "
             "the base is flattest in the last quarter of the run), residual rotation (the mean "
             "θ over the last quarter), peak |u| and peak story shear |k u + c u̇|; and the "
             "foundation energy E_F where the continuum's energy run is stored (below).", "",
             f"Wall time {elapsed:.1f} s.", "",
             "## The continuum statics", "",
             "K_v and K_r (every contact node tied to the footing, elastic soil) and V_ult (the "
             f"largest load of a vertical pushover to {o.settlement_ratio:g} B) do not depend on "
             "N: one pair of stored static runs per soil serves every FS_v, N = V_ult/FS_v.", "",
             *_statics_table(d), "", *_impedance_text(d), *_capacity_fit_text(d),
             "## The beds' statics against the continuum's", "",
             *_rocking_lines(d), "",
             "## Where each bed is enough", "",
             f"A cell (FS_v, h/B) of a soil passes when, at every period and intensity, the "
             f"median over the motions of |error| is within {100 * o.theta_tolerance:g} % in peak "
             f"θ and in peak edge uplift and within {100 * o.settlement_tolerance:g} % in "
             "residual settlement.", ""]
    lines += [f"- {r.text}." for r in a.regions]
    lines += ["", "## Which calibration for which quantity", "",
              *_pick_table(d, a), "", *[f"- {pick_text(p)}." for p in a.picks], "",
              "## Foundation energy", "", *energy_lines(d, a.energy), "",
              "## Where the beds miss", "", *_bias_lines(d), "",
              "## How much of the map a calibrated bed covers", "", _share_text(a), "",
              goal_text(a.goal), "",
              "## Speed", "", _speed_text(a), "", "## Cost", "", _cost_text(d), ""]
    if d.refusals:
        lines += [f"Runs that failed: {len(d.refusals)} (a bed refused by its integrator, a "
                  "continuum run its solver gave up on, whose point then has no bed compared, "
                  "or a continuum run that ended in a bearing failure of the soil; their "
                  "errors are NaN and every statistic above leaves them out, except the "
                  "bearing failures, which the share and the regions hold the beds to):",
                  ""] + [f"- {r}" for r in d.refusals[:20]] + [""]
    return "\n".join(lines)


def _mesh_text(d, fast: bool) -> str:
    n = d.options.elements_across
    dofs = sorted({int(v) for v in d.dofs.ravel() if math.isfinite(v)})
    which = ("the reference mesh" if n == 16 else
             "a coarse mesh for a quick check, not the reference: its numbers are not the map's")
    return (f"The continuum runs on {n} elements across B ({', '.join(map(str, dofs))} DOFs; "
            f"{which}). " + MESH_NOTE)


def _input_text(d) -> str:
    """Where the motion enters each model, with the soil column's first period."""
    from .grid import SOILS
    from ...beds.base import base_table

    base = base_table()
    B = 2.0 * base["foundation"]["half_width"]
    depth = base.get("continuum", {}).get("domain_depth", 10.0) * B
    parts = []
    for soil in d.grid.soils:
        t = SOILS[soil]
        vs = math.sqrt(t["youngs_modulus"] / (2.0 * (1.0 + t["poisson_ratio"])) / t["density"])
        parts.append(f"{soil}: V_s = {vs:.0f} m/s, T_1 = 4H/V_s = {4.0 * depth / vs:.2f} s")
    return ("The motion enters the continuum at the rigid base of its box, "
            f"{depth:g} m below the footing (its sides a free-field column: u_x free, u_y "
            "held; a rigid container instead squeezes the soil against its sides and makes it "
            "yield where a site would not), and "
            "the reduced model at the footing. The structure feels the same horizontal "
            "acceleration in both: through the frictionless interface the soil cannot push the "
            "footing sideways, and the continuum holds the footing's u to the base's (next "
            "paragraph). What the soil column does on the way up (a free column of that depth "
            f"would have {'; '.join(parts)}) still reaches the footing through its stresses: "
            "the shaking column's shear adds to what the soil under the edges carries and "
            "where it yields, which a bed does not have, and that is part of every error.")


def _speed_of_soils(d) -> str:
    from .grid import SOILS

    slow = [soil for soil in d.grid.soils if not compiled_soil_model(SOILS[soil]["model"])]
    if not slow:
        return " The explicit route runs every soil's return map compiled (numba)."
    ratio = SECONDS_PER_DOF_STEP[False] / SECONDS_PER_DOF_STEP[True]
    return (f" The explicit route runs the return map of {', '.join(slow)} through the "
            f"vectorised fallback, about {ratio:.0f} × slower per step and DOF than a compiled "
            "one (upliftlab.comparisons.studies.winkler_map.cost).")


def _impedance_text(d) -> list[str]:
    """The soils' FE impedance dashpots (when a bed used them), a few frequencies of each."""
    if not d.impedances:
        return []
    rows = ["The impedance beds' dashpots are those of the continuum's FE impedance of each "
            "soil (linear elastic, its interface, a PML box; one stored point per soil), "
            "C_j = Im K_j/ω, linear in ω between its frequencies, taken at each point's "
            "rocking frequency on its bed:", "",
            "| soil | DOFs | a0 | ω (rad/s) | C_v (kN s/m/m) | C_r (kN m s/rad/m) |",
            "|---|---|---|---|---|---|"]
    for soil, imp in d.impedances:
        C_v, C_r = imp.dashpot("v"), imp.dashpot("r")
        for k in range(0, imp.a0.size, 3):
            rows.append(f"| {soil} | {imp.dofs} | {imp.a0[k]:.3g} | {imp.omega[k]:.4g} | "
                        f"{C_v[k]:.5g} | {C_r[k]:.4g} |")
    return rows + [""]


def _capacity_fit_text(d) -> list[str]:
    """The fitted bed's exponent β per soil and FS_v, and its misfit to the statics."""
    if not d.capacity_fits:
        return []
    rows = ["The fitted bed's springs yield at bearing pressures ∝ (k_i/w_i)^β (β = 0 one "
            "pressure, V_ult/B; β = 1 FS_v times each spring's static force, as the "
            "end-stiffened elasto-plastic bed), β fitted to the continuum's rotation pushovers "
            "at each N (moment and settlement on the monotonic path, settlement over the "
            "cycles; the misfit is the root-mean-square relative error):", "",
            "| soil | FS_v (1) | β (1) | misfit (1) |", "|---|---|---|---|"]
    for (soil, fs), fit in d.capacity_fits:
        rows.append(f"| {soil} | {fs:g} | {fit.beta:g} | {fit.misfit:.3g} |")
    return rows + [""]


def _statics_table(d) -> list[str]:
    rows = ["| soil | DOFs | K_v (kN/m/m) | K_r (kN m/rad/m) | V_ult (kN/m) | last step's load "
            "rise | N at each FS_v (kN/m) | V_ult/N − FS_v |", "|---|---|---|---|---|---|---|---|"]
    for s, st in enumerate(d.statics):
        loads = ", ".join(f"{v:.4g}" for v in d.N[s])
        check = max(abs(st.V_ult / n - fs) for n, fs in zip(d.N[s], d.grid.fs_v))
        rows.append(f"| {st.soil} | {st.dofs} | {st.K_v:.6g} | {st.K_r:.6g} | {st.V_ult:.5g} | "
                    f"{_pct(st.plateau)} | {loads} | {check:.1e} |")
    return rows


def _rocking_lines(d) -> list[str]:
    """The statics rows: the largest |error| of each bed per group over FS_v, per soil."""
    from .rocking import QUANTITY_GROUPS

    r, o = d.rocking, d.options
    ratios = ", ".join(f"{v:g}" for v in o.theta_ratios)
    cycles = ", ".join(f"{v:g}" for v in o.cycle_ratios)
    lines = [f"Each bed is pushed over on the continuum's rotations at N = V_ult/FS_v: a "
             f"monotonic path to {max(o.theta_ratios):g} θ_on (θ_on = 2N(1 − ν)/(π G B), the "
             f"elastic half-plane's uplift rotation) compared at θ/θ_on ∈ {{{ratios}}}, and one "
             f"full cycle at each of {{{cycles}}} θ_on. Each cell: the largest |error| over "
             "FS_v and the group's quantities (floors: moments 0.01 N B, contact 0.05 B, "
             "settlement 0.1 × the continuum's settlement under N, dissipated work "
             "0.01 N B θ_on).", ""]
    worst = r.group_worst()
    groups = list(QUANTITY_GROUPS)
    for s, soil in enumerate(d.grid.soils):
        lines += [f"{SOIL_LABELS[soil]}:", "",
                  r"| bed (largest \|error\|, %) | " + " | ".join(groups) + " |",
                  "|---|" + "---|" * len(groups)]
        for c, name in enumerate(d.calibrations):
            lines.append(f"| {_short(name)} | "
                         + " | ".join(_num(v) for v in worst[s, c]) + " |")
        lines.append("")
    lines += [f"- {f}." for f in r.failures]
    return lines


def _short(name: str) -> str:
    """A calibration's abbreviation in table headers (long names break mid-word in print)."""
    entry = BEDS.get(name)
    return entry.short if entry is not None and entry.short else name


def _pick_table(d, a) -> list[str]:
    head = ("| measure (error, %) | " + " | ".join(_short(c) for c in d.calibrations)
            + " | pick |")
    rows = [head, "|---|" + "---|" * (len(d.calibrations) + 1)]
    for p in a.picks:
        cells = [f"{_num(p.median[c])} / {_num(p.p90[c])}" for c in d.calibrations]
        rows.append(f"| {MEASURE_LABELS[p.measure]} | " + " | ".join(cells)
                    + f" | {_short(p.best)} |")
    rows.append("")
    rows.append("; ".join(f"{_short(c)}: `{c}`" for c in d.calibrations) + ". Each cell: "
                "median / 90th percentile of |error| (%) over every point of the map "
                f"({a.picks[0].points} points); over the records alone (El Centro and FEMA "
                "P695): " + ("; ".join(
                    f"{MEASURE_LABELS[p.measure]} {_pct(p.record_median[p.best])} / "
                    f"{_pct(p.record_p90[p.best])} for {p.best}" for p in a.picks)
                    if any(math.isfinite(v) for v in a.picks[0].record_median.values())
                    else "no record on this grid") + ".")
    return rows


def _bias_lines(d) -> list[str]:
    """Per soil: each bed's signed median error by FS_v in peak θ, edge uplift and residual
    settlement (:func:`.analysis.signed_bias`)."""
    from .analysis import signed_bias

    bias = signed_bias(d)
    lines = ["The signed median error (bed − continuum, %) at each FS_v over h/B, period, "
             "intensity and motion, as peak θ / peak edge uplift / residual settlement: a "
             "large error of one sign over a whole FS_v is a mechanism the bed lacks there.", ""]
    for s, soil in enumerate(d.grid.soils):
        head = " | ".join(f"FS_v = {v:g}" for v in d.grid.fs_v)
        lines += [f"{SOIL_LABELS[soil]}:", "", f"| bed (signed median error, %) | {head} |",
                  "|---|" + "---|" * len(d.grid.fs_v)]
        for c, name in enumerate(d.calibrations):
            cells = [" / ".join("n/a" if not math.isfinite(v) else f"{100 * v:+.0f}"
                                for v in bias[s, f, c]) for f in range(len(d.grid.fs_v))]
            lines.append(f"| {_short(name)} | " + " | ".join(cells) + " |")
        lines.append("")
    return lines[:-1]


def _num(value) -> str:
    return "n/a" if value is None or not math.isfinite(value) else f"{100 * value:.1f}"


def _share_text(a) -> str:
    s = a.share
    thr = f"{100 * s.threshold:g} %"
    by_bed = ", ".join(f"{k} {_pct(v)}" for k, v in s.by_bed.items())
    text = (f"Of the map's {s.points} points (cells × motions), the best single calibration "
            f"({s.best}) is within {thr} of the continuum in both peak θ and peak edge uplift "
            f"at **{_pct(s.best_share)}**; the best calibration chosen point by point at "
            f"{_pct(s.any_share)}. Per calibration: {by_bed}.")
    if s.bearing_failures:
        from ....continuum.dynamics.run_control import FAILURE_SETTLEMENT

        called = ", ".join(f"{k} {v}" for k, v in s.called.items())
        text += (f" {s.bearing_failures} of the points ended in a bearing failure of the "
                 f"continuum's soil (its footing settled {FAILURE_SETTLEMENT:g} B or more in a "
                 "mechanism): each is a hit for a bed whose base settles "
                 f"{FAILURE_SETTLEMENT:g} B too and a miss for the others; beds that failed "
                 f"with it: {called}.")
    return text


def _speed_text(a) -> str:
    sp = a.speed
    parts = ", ".join(f"{k} {_f(v, 3)} × (at least {_f(sp.minimum[k], 3)} ×; median run "
                      f"{_f(sp.bed_median[k], 3)} s)" for k, v in sp.median.items())
    return (f"The continuum's wall time over each bed's, point by point on this machine (the "
            f"continuum's stored with its run, median {_f(sp.continuum_median, 3)} s; the "
            f"beds' measured in this run): median {parts}.")


def _cost_text(d) -> str:
    e = d.estimate
    total = (float(np.nansum(d.continuum_wall)) + sum(s.wall_time_s for s in d.statics)
             + sum(imp.metadata.get("wall_time_s", 0.0) for _, imp in d.impedances))
    return (f"Estimated before any work: {e.text(d.workers)}. This run computed {d.computed} "
            f"continuum runs; the continuum's stored runs took {total:.1f} s of wall time in all.")
