"""The sections of the map's summary, each a few Markdown lines from the map's ``map`` dataset
(``m``), its ``statics`` dataset (``st``, :mod:`.parts`) and its analysis (:mod:`.analysis`):
the notes on the mesh, the soils and the input, the statics tables, the picks, the signed
errors, the share, the speed and the cost."""

from __future__ import annotations

import math

from ...beds import BEDS
from .analysis import Pick, signed_bias, subject
from .cost import SECONDS_PER_DOF_STEP, compiled_soil_model
from .grid import MEASURE_LABELS, SOIL_LABELS, SOILS
from .parts import (capacity_fits_of, impedances_of, labels, options_of, soil_statics_of,
                    texts, worst_statics)
from .rocking import QUANTITY_GROUPS

__all__ = ["MESH_NOTE", "SOIL_NOTE", "SWAY_NOTE", "mesh_text", "speed_of_soils", "input_text",
           "impedance_text", "capacity_fit_text", "statics_table", "rocking_lines",
           "pick_table", "pick_text", "bias_lines", "short", "pct", "finite", "f4"]

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


def f4(value, digits: int = 4) -> str:
    return "n/a" if value is None or not math.isfinite(value) else f"{value:.{digits}g}"


def pct(value) -> str:
    return "n/a" if value is None or not math.isfinite(value) else f"{100 * value:.1f} %"


def finite(value):
    return float(value) if value is not None and math.isfinite(value) else None


def num(value) -> str:
    return "n/a" if value is None or not math.isfinite(value) else f"{100 * value:.1f}"


def short(name: str) -> str:
    """A calibration's abbreviation in table headers (long names break mid-word in print)."""
    entry = BEDS.get(name)
    return entry.short if entry is not None and entry.short else name


def mesh_text(m) -> str:
    n = options_of(m)["elements_across"]
    dofs = sorted({int(v) for v in m.continuum_dofs.values.ravel() if math.isfinite(v)})
    which = ("the reference mesh" if n == 16 else
             "a coarse mesh for a quick check, not the reference: its numbers are not the map's")
    return (f"The continuum runs on {n} elements across B ({', '.join(map(str, dofs))} DOFs; "
            f"{which}). " + MESH_NOTE)


def input_text(m) -> str:
    """Where the motion enters each model, with the soil column's first period."""
    from ...beds.base import base_table

    base = base_table()
    B = 2.0 * base["foundation"]["half_width"]
    depth = base.get("continuum", {}).get("domain_depth", 10.0) * B
    parts = []
    for soil in labels(m, "soil"):
        t = SOILS[soil]
        vs = math.sqrt(t["youngs_modulus"] / (2.0 * (1.0 + t["poisson_ratio"])) / t["density"])
        parts.append(f"{soil}: V_s = {vs:.0f} m/s, T_1 = 4H/V_s = {4.0 * depth / vs:.2f} s")
    where = ("as an incident S wave through the compliant base of its box (Lysmer–Kuhlemeyer "
             "dashpots)" if options_of(m)["reference"] == "half_plane"
             else "at the rigid base of its box")
    return (f"The motion enters the continuum {where}, "
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


def speed_of_soils(m) -> str:
    slow = [soil for soil in labels(m, "soil") if not compiled_soil_model(SOILS[soil]["model"])]
    if not slow:
        return " The explicit route runs every soil's return map compiled (numba)."
    ratio = SECONDS_PER_DOF_STEP[False] / SECONDS_PER_DOF_STEP[True]
    return (f" The explicit route runs the return map of {', '.join(slow)} through the "
            f"vectorised fallback, about {ratio:.0f} × slower per step and DOF than a compiled "
            "one (upliftlab.comparisons.studies.winkler_map.cost).")


def impedance_text(st) -> list[str]:
    """The soils' FE impedance dashpots (when a bed used them), a few frequencies of each."""
    impedances = impedances_of(st)
    if not impedances:
        return []
    rows = ["The impedance beds' dashpots are those of the continuum's FE impedance of each "
            "soil (linear elastic, its interface, a PML box; one stored point per soil), "
            "C_j = Im K_j/ω, linear in ω between its frequencies, taken at each point's "
            "rocking frequency on its bed:", "",
            "| soil | DOFs | a0 | ω (rad/s) | C_v (kN s/m/m) | C_r (kN m s/rad/m) |",
            "|---|---|---|---|---|---|"]
    for soil, imp in impedances.items():
        for k in range(0, imp["a0"].size, 3):
            rows.append(f"| {soil} | {imp['dofs']} | {imp['a0'][k]:.3g} | "
                        f"{imp['omega'][k]:.4g} | {imp['C_v'][k]:.5g} | {imp['C_r'][k]:.4g} |")
    return rows + [""]


def capacity_fit_text(st) -> list[str]:
    """The fitted bed's exponent β per soil and FS_v, and its misfit to the statics."""
    fits = capacity_fits_of(st)
    if not fits:
        return []
    rows = ["The fitted bed's springs yield at bearing pressures ∝ (k_i/w_i)^β (β = 0 one "
            "pressure, V_ult/B; β = 1 FS_v times each spring's static force, as the "
            "end-stiffened elasto-plastic bed), β fitted to the continuum's rotation pushovers "
            "at each N (moment and settlement on the monotonic path, settlement over the "
            "cycles; the misfit is the root-mean-square relative error):", "",
            "| soil | FS_v (1) | β (1) | misfit (1) |", "|---|---|---|---|"]
    for (soil, fs), (beta, misfit) in fits.items():
        rows.append(f"| {soil} | {fs:g} | {beta:g} | {misfit:.3g} |")
    return rows + [""]


def statics_table(m, st) -> list[str]:
    rows = ["| soil | DOFs | K_v (kN/m/m) | K_r (kN m/rad/m) | V_ult (kN/m) | last step's load "
            "rise | N at each FS_v (kN/m) | V_ult/N − FS_v |", "|---|---|---|---|---|---|---|---|"]
    N = m.vertical_load.transpose("soil", "fs_v").values
    fs_v = m.fs_v.values.tolist()
    for s, sst in enumerate(soil_statics_of(st)):
        loads = ", ".join(f"{v:.4g}" for v in N[s])
        check = max(abs(sst.V_ult / n - fs) for n, fs in zip(N[s], fs_v))
        rows.append(f"| {sst.soil} | {sst.dofs} | {sst.K_v:.6g} | {sst.K_r:.6g} | "
                    f"{sst.V_ult:.5g} | {pct(sst.plateau)} | {loads} | {check:.1e} |")
    return rows


def rocking_lines(m, st) -> list[str]:
    """The statics rows: the largest |error| of each bed per group over FS_v, per soil."""
    o = options_of(m)
    ratios = ", ".join(f"{v:g}" for v in o["theta_ratios"])
    cycles = ", ".join(f"{v:g}" for v in o["cycle_ratios"])
    lines = [f"Each bed is pushed over on the continuum's rotations at N = V_ult/FS_v: a "
             f"monotonic path to {max(o['theta_ratios']):g} θ_on (θ_on = 2N(1 − ν)/(π G B), "
             f"the elastic half-plane's uplift rotation) compared at θ/θ_on ∈ {{{ratios}}}, "
             f"and one full cycle at each of {{{cycles}}} θ_on. Each cell: the largest |error| "
             "over FS_v and the group's quantities (floors: moments 0.01 N B, contact 0.05 B, "
             "settlement 0.1 × the continuum's settlement under N, dissipated work "
             "0.01 N B θ_on).", ""]
    worst = worst_statics(st)
    groups = list(QUANTITY_GROUPS)
    for s, soil in enumerate(labels(st, "soil")):
        lines += [f"{SOIL_LABELS[soil]}:", "",
                  r"| bed (largest \|error\|, %) | " + " | ".join(groups) + " |",
                  "|---|" + "---|" * len(groups)]
        for c, name in enumerate(labels(st, "calibration")):
            lines.append(f"| {short(name)} | " + " | ".join(num(v) for v in worst[s, c]) + " |")
        lines.append("")
    lines += [f"- {f}." for f in texts(st.attrs.get("rocking_failures", ""))]
    return lines


def pick_table(calibrations, a) -> list[str]:
    head = ("| measure (error, %) | " + " | ".join(short(c) for c in calibrations)
            + " | pick |")
    rows = [head, "|---|" + "---|" * (len(calibrations) + 1)]
    for p in a.picks:
        cells = [f"{num(p.median[c])} / {num(p.p90[c])}" for c in calibrations]
        rows.append(f"| {MEASURE_LABELS[p.measure]} | " + " | ".join(cells)
                    + f" | {short(p.best)} |")
    rows.append("")
    rows.append("; ".join(f"{short(c)}: `{c}`" for c in calibrations) + ". Each cell: "
                "median / 90th percentile of |error| (%) over every point of the map "
                f"({a.picks[0].points} points); over the records alone (El Centro and FEMA "
                "P695): " + ("; ".join(
                    f"{MEASURE_LABELS[p.measure]} {pct(p.record_median[p.best])} / "
                    f"{pct(p.record_p90[p.best])} for {p.best}" for p in a.picks)
                    if any(math.isfinite(v) for v in a.picks[0].record_median.values())
                    else "no record on this grid") + ".")
    return rows


def bias_lines(m) -> list[str]:
    """Per soil: each bed's signed median error by FS_v in peak θ, edge uplift and residual
    settlement (:func:`.analysis.signed_bias`)."""
    bias = signed_bias(m)
    fs_v = m.fs_v.values.tolist()
    lines = ["The signed median error (bed − continuum, %) at each FS_v over h/B, period, "
             "intensity and motion, as peak θ / peak edge uplift / residual settlement: a "
             "large error of one sign over a whole FS_v is a mechanism the bed lacks there.", ""]
    for s, soil in enumerate(labels(m, "soil")):
        head = " | ".join(f"FS_v = {v:g}" for v in fs_v)
        lines += [f"{SOIL_LABELS[soil]}:", "", f"| bed (signed median error, %) | {head} |",
                  "|---|" + "---|" * len(fs_v)]
        for c, name in enumerate(labels(m, "calibration")):
            cells = [" / ".join("n/a" if not math.isfinite(v) else f"{100 * v:+.0f}"
                                for v in bias[s, f, c]) for f in range(len(fs_v))]
            lines.append(f"| {short(name)} | " + " | ".join(cells) + " |")
        lines.append("")
    return lines[:-1]


def pick_text(pick: Pick) -> str:
    """One sentence: the calibration to pick for a measure, with its distribution."""
    label = MEASURE_LABELS[pick.measure]
    best = pick.best
    return (f"For {label}, pick the {subject(best)}: |error| median "
            f"{pct(pick.median[best])}, 90th percentile {pct(pick.p90[best])} over "
            f"{pick.points} points")
