"""The study's summary in Markdown (:func:`summarise`), computed from its data alone (the
tree :func:`.workflow.compute` returns, or the same read back by :func:`upliftlab.open_study`);
its key numbers are :func:`.numbers.key_numbers`."""

from __future__ import annotations

import math

from ....number_text import number_text
from ...beds.pushover import FLOORS
from .analysis import ErrorTable, pct, signed_pct
from .dataset import texts
from .dynamics import DYNAMIC_LABELS, DYNAMIC_MEASURES
from .numbers import Reading, end_stiffening, ordering, read
from .options import ONSET_ANCHOR
from .units import quantity_unit

__all__ = ["summarise"]


def summarise(data) -> str:
    """The Markdown summary of the study's tree ``data``."""
    return summary_markdown(read(data))


def _scene_line(r: Reading) -> str:
    ds, u = r.ds, r.units
    overrides = ", ".join(texts(ds.attrs.get("overrides", ""))) or "no overrides"
    c_u = ds.c_u.item()
    return (f"Scene `{ds.attrs['scene']}` ({overrides}): B = {ds.B.item():g} {u.length}, N = "
            f"{ds.N.item():g} {u.force}/{u.length}, h = {ds.h.item():g} {u.length}; soil "
            f"{ds.attrs['soil_model']} (E = {float(ds.attrs['soil_youngs_modulus']):g}, ν = "
            f"{ds.nu.item():g}" + (f", c_u = {c_u:g}" if math.isfinite(c_u) and c_u else "")
            + f"), {ds.attrs['soil_interface']} interface; continuum mesh of "
            f"{int(ds.continuum_dofs)} DOFs. θ_on = 2N(1 − ν)/(πGB) = {ds.theta_on.item():.4g} "
            f"rad. Wall time {r.elapsed:.1f} s.")


def _anchor_lines(r: Reading) -> list[str]:
    ds, a, u = r.ds, r.anchors, r.units
    lines = [f"- K_r = {ds.K_r.item():.6g} ({signed_pct(a['K_r_error_vs_closed_form'])} against "
             f"π G B²/(8(1 − ν)) = {a['K_r_closed_form']:.6g}, anchors §4); K_v = "
             f"{ds.K_v.item():.6g} in this box (no 2D strip K_v exists: it depends on the box, "
             f"anchors §4). K_r/K_v = {a['K_r_over_K_v']:.4g} {u.length}² against b² = "
             f"{a['half_width_squared']:.4g}.",
             f"- Uplift onset, elastic soil: e/B = "
             f"{a['continuum_elastic_onset_e_over_B']:.4f} (half-plane anchor 1/4: "
             f"{signed_pct(a['continuum_elastic_onset_e_over_B'] / ONSET_ANCHOR - 1.0)}); the "
             f"scene's soil: e/B = {a['continuum_monotonic_onset_e_over_B']:.4f}; uniform "
             f"Winkler bed: e/B = {a['winkler_onset_e_over_B']:.4f} (closed form 1/6, "
             f"discrete (1/6)(1 + 1/n) = {a['winkler_onset_discrete_closed_form']:.4f}). "
             f"Continuum onset later than Winkler's: **{ordering(a)}**.",
             f"- Uniform bed against M/M_up = 3 − 2√(θ_up/θ) (anchors §3): largest deviation "
             f"{pct(a['winkler_M_error_vs_closed_form'])} over the path; contact length "
             f"within {a['winkler_contact_error']:.3g} B of c = B√(θ_up/θ), settlement within "
             f"{a['winkler_settlement_error']:.3g} × N/(kB) of its closed form.",
             f"- Elastic continuum against the half-plane closed form: largest |ΔM|/(N B) = "
             f"{a['half_plane_M_error']:.3g}."]
    if math.isfinite(ds.c_u.item()):
        N_ult, N, B = ds.N_ult.item(), ds.N.item(), ds.B.item()
        lines.append(f"- Vertical capacity N_ult = {N_ult:.5g} (q_ult = {N_ult / B:.5g}; "
                     f"{signed_pct(a['N_ult_error_vs_prandtl'])} against Prandtl (2 + π) c_u B = "
                     f"{a['prandtl_N_ult']:.5g}), so FS_v = q_ult B/N = {N_ult / N:.4g}. "
                     f"Largest M on the pushover {a['continuum_M_max_over_NB']:.4f} N B against "
                     f"the V–M envelope (1 − v)/2 = {a['vm_envelope_M_over_NB']:.4f} N B.")
    return lines


def _calibration_lines(r: Reading) -> list[str]:
    ds, u = r.ds, r.units
    lines = [f"| calibration | layout | law | K_v ({u.force}/{u.length}/{u.length}) | K_θ "
             f"({u.force}·{u.length}/{u.length} per rad) | R_k (–) | R_e (× b) | FS_v (–) | "
             "matched |",
             "|---|---|---|---|---|---|---|---|---|"]
    for name in ds.calibration.values:
        c = ds.sel(calibration=name)
        law = str(c.law.item())
        fs = "—" if law == "elastic" else f"{c.yield_multiple.item():.4g}"
        matches = ", ".join(m for m in str(c.matches.item()).split(",") if m)
        lines.append(f"| `{name}` | {c.layout.item()} ({int(c.springs)} springs) | {law} | "
                     f"{c.bed_vertical_stiffness.item():.6g} | "
                     f"{c.bed_rocking_stiffness.item():.6g} | "
                     f"{c.end_stiffness_ratio.item():.4g} | {c.end_length.item():.4g} | {fs} | "
                     f"{matches} |")
    end = ds.sel(calibration="end_stiffened")
    R_e, stiff = end.end_length.item(), end_stiffening(ds)
    lines += ["", (f"End stiffening (R_e = {R_e:.4g} b, i.e. end zones of "
                   f"{R_e * ds.B.item() / 2:.4g} {u.length} at each edge): target "
                   f"K_r/K_v = {stiff['target']:.4g}, solved R_k = "
                   f"{number_text(stiff['exact'], '.6g', unbounded='none (no finite R_k)')}; "
                   + ("feasible." if stiff["feasible"] else
                      f"**infeasible** — {end.note.item()}."))]
    return lines


def summary_markdown(r: Reading) -> str:
    """The Markdown text of the :class:`.numbers.Reading` ``r``."""
    ds, rec, table = r.ds, r.recommendation, r.table
    fast = bool(ds.attrs.get("fast", 0))
    lines = [f"# Winkler beds against the continuum{' (fast)' if fast else ''}", "",
             _scene_line(r), "", "## The continuum reference and its anchors", ""]
    lines += _anchor_lines(r)
    lines += ["", "## Calibrations", ""] + _calibration_lines(r)
    lines += ["", "## Error table", "",
              "Signed relative error (bed − continuum)/max(|continuum|, floor); floors "
              f"{FLOORS['moment']:g} N B (moments), {FLOORS['contact']:g} B (contact), "
              f"{FLOORS['settlement']:g} × the continuum's settlement under N (settlements), "
              f"{FLOORS['energy']:g} N B θ_on (energy). — : the bed has no such value (elastic "
              "springs have no capacity).", ""]
    lines += _error_markdown(table, r.units)
    lines += ["", "## Which calibration for which question", "",
              "Computed from the table: per question, the calibration whose largest |error| "
              "over the question's quantities is smallest.", "", rec.text, "",
              "Best per quantity: " + "; ".join(
                  f"{lbl}: {', '.join(rec.per_quantity[q]) or '—'}"
                  for q, lbl in zip(table.quantities, table.labels)) + ".", "",
              "## Dynamics", "", _dynamic_markdown(r) if bool(ds.attrs["dynamic_available"])
              else str(ds.attrs.get("dynamic_reason", "")), ""]
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


def _dynamic_markdown(r: Reading) -> str:
    """Peaks per motion: the continuum's and each bed's (errors are in the error table)."""
    overrides = ", ".join(texts(r.ds.attrs.get("dynamic_overrides", "")))
    lines = ["The continuum's dynamic runs: `run_dynamic` with its default options (the "
             "scene's `continuum.dynamics`, explicit central differences by default; automatic "
             "step), the scene's boundaries"
             + (f", and the overrides {overrides}" if overrides else "")
             + ". The beds: the reduced model with the scene's foundation damping "
             "and impact settings. Peak edge uplift is the larger gap at x = ±b; residual "
             "settlement is the settlement of the centre at the end, from rest.", ""]
    for run in r.runs:
        names = [str(n) for n in run.model.values[1:]]  # the beds, after the continuum
        lines += [f"### {run.attrs['label']}", "",
                  f"Continuum: {int(run.steps)} steps on {int(run.dofs)} DOFs. "
                  "Histories overlaid in this section's figure of the run.", "",
                  "| measure | unit | continuum | " + " | ".join(n.replace("_", " ") for n in names)
                  + " |",
                  "|---|---|---|" + "---|" * len(names)]
        for m in DYNAMIC_MEASURES:
            peak = run[f"peak_{m}"]
            lines.append(f"| {DYNAMIC_LABELS[m]} | {quantity_unit('_' + m, r.units)} | "
                         f"{peak.sel(model='continuum').item():.4g} | "
                         + " | ".join(f"{peak.sel(model=n).item():.4g}" for n in names) + " |")
        lines.append("")
        refused = dict(zip(run.model.values.tolist(), run.refused.values.tolist()))
        lines += [f"- `{n}` refused by the reduced integrator: {refused[n]}"
                  for n in names if refused[n]]
    return "\n".join(lines)
