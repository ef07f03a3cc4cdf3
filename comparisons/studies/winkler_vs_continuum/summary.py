"""The study's summary: key numbers and the Markdown text computed from them."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict

from ...beds.pushover import FLOORS
from .analysis import ErrorTable, pct, signed_pct
from .dynamics import DYNAMIC_LABELS, DYNAMIC_MEASURES, DynamicComparison, run_overrides
from .options import ONSET_ANCHOR, Options, finite_or_none
from .result import WinklerVsContinuum
from .units import quantity_unit


def summary_numbers(result: WinklerVsContinuum, elapsed: float) -> dict:
    ref, t = result.reference, result.table
    return {
        "continuum": {"K_r": ref.K_r, "K_v": ref.K_v, "theta_on": ref.theta_on,
                      "N_ult": ref.N_ult, "q_ult": ref.q_ult,
                      "yield_multiple": ref.N_ult / ref.N, "dofs": ref.dofs,
                      "onset": ref.onset("monotonic"), "elastic_onset": ref.onset("elastic")},
        "calibrations": {c.name: {"layout": c.layout, "law": c.law, "springs": c.springs,
                                  "K_v": c.vertical_stiffness, "K_r": c.rocking_stiffness,
                                  "end_stiffness_ratio": c.end_stiffness_ratio,
                                  "end_length": c.end_length,
                                  "yield_multiple": c.yield_multiple if c.law != "elastic"
                                  else None, "matches": list(c.matches), "note": c.note}
                         for c in result.calibrations},
        "end_stiffening": asdict(result.calibration("end_stiffened").stiffening),
        "errors": {c: {q: (float(t.errors[i, j]) if math.isfinite(t.errors[i, j]) else None)
                       for j, q in enumerate(t.quantities)}
                   for i, c in enumerate(t.calibrations)},
        "reference_values": {q: float(t.reference[j]) for j, q in enumerate(t.quantities)},
        "best_per_quantity": result.recommendation.per_quantity,
        "best_per_question": {g: {"pick": v[0], "largest_error": finite_or_none(v[1]),
                                  "next": v[2], "next_largest_error": finite_or_none(v[3])}
                              for g, v in result.recommendation.per_group.items()},
        "anchors": result.anchors,
        "onset_ordering_holds": _ordering(result.anchors),
        "dynamic": {"available": result.dynamics.available, "text": result.dynamics.reason,
                    "peaks": result.dynamics.peaks(),
                    "refused": {f"{r.key}/{n}": b["refused"] for r in result.dynamics.runs
                                for n, b in r.beds.items() if "refused" in b}},
        "elapsed_s": elapsed,
    }


def _ordering(anchors: Mapping) -> bool:
    """Continuum uplift onset (elastic and the scene's soil) later than the Winkler bed's."""
    w = anchors["winkler_onset_e_over_B"]
    return bool(anchors["continuum_elastic_onset_e_over_B"] > w
                and anchors["continuum_monotonic_onset_e_over_B"] > w)


def summary_markdown(result: WinklerVsContinuum, fast: bool, elapsed: float) -> str:
    ref, a, sc = result.reference, result.anchors, result.scene
    u = sc.units
    soil = sc.soil
    stiff = result.calibration("end_stiffened").stiffening
    lines = [f"# Winkler beds against the continuum{' (fast)' if fast else ''}", "",
             f"Scene `{sc.name}` ({', '.join(sc.overrides) or 'no overrides'}): B = {ref.B:g} "
             f"{u.length}, N = {ref.N:g} {u.force}/{u.length}, h = {ref.h:g} {u.length}; soil "
             f"{soil.model} (E = {soil.youngs_modulus:g}, ν = {soil.poisson_ratio:g}"
             + (f", c_u = {ref.cu:g}" if ref.cu else "") + f"), {soil.interface} interface; "
             f"continuum mesh of {ref.dofs} DOFs. θ_on = 2N(1 − ν)/(πGB) = {ref.theta_on:.4g} "
             f"rad. Wall time {elapsed:.1f} s.", "",
             "## The continuum reference and its anchors", "",
             f"- K_r = {ref.K_r:.6g} ({signed_pct(a['K_r_error_vs_closed_form'])} against π G B²/"
             f"(8(1 − ν)) = {a['K_r_closed_form']:.6g}, anchors §4); K_v = {ref.K_v:.6g} in this "
             f"box (no 2D strip K_v exists: it depends on the box, anchors §4). K_r/K_v = "
             f"{a['K_r_over_K_v']:.4g} {u.length}² against b² = {a['half_width_squared']:.4g}.",
             f"- Uplift onset, elastic soil: e/B = "
             f"{a['continuum_elastic_onset_e_over_B']:.4f} (half-plane anchor 1/4: "
             f"{signed_pct(a['continuum_elastic_onset_e_over_B'] / ONSET_ANCHOR - 1.0)}); the "
             f"scene's soil: e/B = {a['continuum_monotonic_onset_e_over_B']:.4f}; uniform "
             f"Winkler bed: e/B = {a['winkler_onset_e_over_B']:.4f} (closed form 1/6, "
             f"discrete (1/6)(1 + 1/n) = {a['winkler_onset_discrete_closed_form']:.4f}). "
             f"Continuum onset later than Winkler's: **{_ordering(a)}**.",
             f"- Uniform bed against M/M_up = 3 − 2√(θ_up/θ) (anchors §3): largest deviation "
             f"{pct(a['winkler_M_error_vs_closed_form'])} over the path; contact length "
             f"within {a['winkler_contact_error']:.3g} B of c = B√(θ_up/θ), settlement within "
             f"{a['winkler_settlement_error']:.3g} × N/(kB) of its closed form.",
             f"- Elastic continuum against the half-plane closed form: largest |ΔM|/(N B) = "
             f"{a['half_plane_M_error']:.3g}."]
    if ref.cu is not None:
        lines.append(f"- Vertical capacity N_ult = {ref.N_ult:.5g} (q_ult = {ref.q_ult:.5g}; "
                     f"{signed_pct(a['N_ult_error_vs_prandtl'])} against Prandtl (2 + π) c_u B = "
                     f"{a['prandtl_N_ult']:.5g}), so FS_v = q_ult B/N = {ref.N_ult / ref.N:.4g}. "
                     f"Largest M on the pushover {a['continuum_M_max_over_NB']:.4f} N B against "
                     f"the V–M envelope (1 − v)/2 = {a['vm_envelope_M_over_NB']:.4f} N B.")
    lines += ["", "## Calibrations", "",
              f"| calibration | layout | law | K_v ({u.force}/{u.length}/{u.length}) | K_θ "
              f"({u.force}·{u.length}/{u.length} per rad) | R_k (–) | R_e (× b) | FS_v (–) | "
              "matched |",
              "|---|---|---|---|---|---|---|---|---|"]
    for c in result.calibrations:
        fs = "—" if c.law == "elastic" else f"{c.yield_multiple:.4g}"
        lines.append(f"| `{c.name}` | {c.layout} ({c.springs} springs) | {c.law} | "
                     f"{c.vertical_stiffness:.6g} | {c.rocking_stiffness:.6g} | "
                     f"{c.end_stiffness_ratio:.4g} | {c.end_length:.4g} | {fs} | "
                     f"{', '.join(c.matches)} |")
    note = result.calibration("end_stiffened").note
    lines += ["", (f"End stiffening (R_e = {result.options.end_length:.4g} b, i.e. end zones of "
                   f"{result.options.end_length * ref.B / 2:.4g} {u.length} at each edge): target "
                   f"K_r/K_v = {stiff.target:.4g}, solved R_k = {stiff.exact:.6g}; "
                   + ("feasible." if stiff.feasible else f"**infeasible** — {note}."))]
    lines += ["", "## Error table", "",
              "Signed relative error (bed − continuum)/max(|continuum|, floor); floors "
              f"{FLOORS['moment']:g} N B (moments), {FLOORS['contact']:g} B (contact), "
              f"{FLOORS['settlement']:g} × the continuum's settlement under N (settlements), "
              f"{FLOORS['energy']:g} N B θ_on (energy). — : the bed has no such value (elastic "
              "springs have no capacity).", ""]
    lines += _error_markdown(result.table, u)
    lines += ["", "## Which calibration for which question", "",
              "Computed from the table: per question, the calibration whose largest |error| "
              "over the question's quantities is smallest.", "", result.recommendation.text, "",
              "Best per quantity: " + "; ".join(
                  f"{lbl}: {', '.join(result.recommendation.per_quantity[q]) or '—'}"
                  for q, lbl in zip(result.table.quantities, result.table.labels)) + ".", "",
              "## Dynamics", "", result.dynamics.reason if not result.dynamics.available
              else _dynamic_markdown(result.dynamics, result.options, fast, u), ""]
    return "\n".join(lines)


def _error_markdown(table: ErrorTable, units) -> list[str]:
    head = ("| quantity | unit | continuum (in the unit) | "
            + " | ".join(f"{c.replace('_', ' ')} (error, %)" for c in table.calibrations)
            + " |")
    rows = [head, "|---|---|---|" + "---|" * len(table.calibrations)]
    for j, label in enumerate(table.labels):
        rows.append(f"| {label} | {quantity_unit(table.quantities[j], units)} | "
                    f"{table.reference[j]:.5g} | "
                    + " | ".join(signed_pct(table.errors[i, j])
                                 for i in range(len(table.calibrations))) + " |")
    return rows


def _dynamic_markdown(dyn: DynamicComparison, options: Options, fast: bool, units) -> str:
    """Peaks per motion: the continuum's and each bed's (errors are in the error table)."""
    overrides = ", ".join(run_overrides(options, fast))
    lines = ["The continuum's dynamic runs: `run_dynamic` with its default options (the "
             "scene's `continuum.dynamics`, explicit central differences by default; automatic "
             "step), the scene's boundaries"
             + (f", and the overrides {overrides}" if overrides else "")
             + ". The beds: the reduced model with the scene's foundation damping "
             "and impact settings. Peak edge uplift is the larger gap at x = ±b; residual "
             "settlement is the settlement of the centre at the end, from rest.", ""]
    for run in dyn.runs:
        names = list(run.beds)
        lines += [f"### {run.label}", "",
                  f"Continuum: {run.continuum['steps']} steps on {run.continuum['dofs']} DOFs. "
                  "Histories overlaid in this section's figure of the run.", "",
                  "| measure | unit | continuum | " + " | ".join(n.replace("_", " ") for n in names)
                  + " |",
                  "|---|---|---|" + "---|" * len(names)]
        for m in DYNAMIC_MEASURES:
            lines.append(f"| {DYNAMIC_LABELS[m]} | {quantity_unit('_' + m, units)} | "
                         f"{run.continuum['peaks'][m]:.4g} | "
                         + " | ".join(f"{run.beds[n]['peaks'][m]:.4g}" for n in names) + " |")
        lines.append("")
        lines += [f"- `{n}` refused by the reduced integrator: {run.beds[n]['refused']}"
                  for n in names if "refused" in run.beds[n]]
    return "\n".join(lines)
