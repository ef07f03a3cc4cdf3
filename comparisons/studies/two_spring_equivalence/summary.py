"""The study's summary: key numbers and the Markdown text computed from them."""

from __future__ import annotations

import math

from .convergence import Convergence
from .grid import ENERGY_TOLERANCE, FLOOR_FRACTION, LAYOUTS, METRICS, METRIC_LABELS
from .maps import ErrorMap
from .points import Base
from .dataset import TwoSpringEquivalence
from .statics import Statics


def summary_numbers(result: TwoSpringEquivalence, elapsed: float) -> dict:
    st, conv = result.statics, result.convergence
    return {
        "springs": result.springs,
        "converged": conv.converged,
        "convergence_changes": conv.changes,
        "statics": {s.label: {"positions_over_b": s.positions, "onset": s.onset,
                              "onset_closed_form": s.onset_closed_form,
                              "capacity": s.capacity,
                              "capacity_closed_form": s.capacity_closed_form,
                              "ultimate": s.ultimate,
                              "ultimate_closed_form": s.ultimate_closed_form}
                    for s in st.layouts},
        "onset_ratio_equivalent_vs_winkler": st.onset_ratio,
        "capacity_ratio_equivalent_vs_winkler": st.capacity_ratio,
        "regions": [{"map": r.map, "case": r.case, "layout": r.layout, "measure": r.metric,
                     "text": r.text, "passing": r.passing, "total": r.total}
                    for r in result.regions],
        "ewing": {"holds": result.ewing.holds, "elastic_holds": result.ewing.elastic_holds,
                  "share": result.ewing.share, "median": result.ewing.median,
                  "uplifting_points": result.ewing.points,
                  "bonded_error": result.ewing.bonded_error, "text": result.ewing.text},
        "points": sum(m.reference[:, 0].size * (len(LAYOUTS) + 1) for m in result.maps),
        "failures": [f for m in result.maps for f in m.failures],
        "max_energy_balance_error": max((m.energy_balance_error for m in result.maps),
                                        default=0.0),
        "elapsed_s": elapsed,
    }


def summary_markdown(result: TwoSpringEquivalence, base: Base, fast: bool, elapsed: float) -> str:
    st, conv, opt = result.statics, result.convergence, result.options
    thr = f"{100 * opt.threshold:g} %"
    lines = [f"# Two-spring equivalence{' (fast)' if fast else ''}", "",
             f"Base scene `{base.name}` (h/b = {base.h_over_b:.3g}, T = {base.period:.3g} s, "
             f"FS_v = {base.yield_multiple:g}). Intensity = PGA / a_up with a_up = g·b/(3h), "
             "the quasi-static uplift acceleration of the uniform Winkler bed (N → ∞) under a "
             f"rigid superstructure. Equivalence threshold: {thr}. Records: "
             f"{result.record_note}. Wall time {elapsed:.1f} s.", "",
             "Errors are (two-spring − Winkler)/max(|Winkler|, floor); the floor is "
             f"{FLOOR_FRACTION:g} × the measure's value at the uplift threshold: u_up = "
             "(W b/3h)/k, θ_up = W/(K_v b), the static settlement W/K_v (uplift, residual "
             "settlement), W b/(3h) (base shear) and W²/(2K_v) (dissipated energy). Peak edge "
             "gap is the gap at x = ±b over the (plastically settled) soil at the outermost "
             "spring, the same measure for every layout; plastic settlement is the "
             "stiffness-weighted mean plastic settlement of the springs at the end, Σ k_i ε_p,i "
             "/ Σ k_i (independent of any rocking left at the end).", "",
             "## Winkler bed: convergence in N", "",
             _convergence_text(conv), "",
             "## Statics (anchors §2–3)", "", *_statics_table(st), "",
             *_statics_text(st, opt.threshold), "",
             "## Where two springs can replace the bed", ""]
    for emap in result.maps:
        lines += [f"### {emap.title}", ""]
        lines += _region_table(result.regions, emap, opt.threshold)
        lines.append("")
    lines += ["## Ewing's conclusion, quantified", "", result.ewing.text, ""]
    failures = [f for m in result.maps for f in m.failures]
    balance = max((m.energy_balance_error for m in result.maps), default=0.0)
    lines += [f"Runs not used: {len(failures)} (refused by the integrator, or energy balance "
              f"off by more than {ENERGY_TOLERANCE:g} of the input; their cells are blank). "
              f"Largest energy-balance error of any run: {balance:.1e} of its input.", ""]
    lines += [f"- {f}" for f in failures[:20]]
    if len(failures) > 20:
        lines.append(f"- … and {len(failures) - 20} more (summary.json)")
    return "\n".join(lines)


def _convergence_text(conv: Convergence) -> str:
    n = conv.candidates
    pairs = ", ".join(f"{n[j]}→{n[j + 1]}" for j in range(len(n) - 1))
    rows = [f"Candidates N = {', '.join(map(str, n))}; base scene, {conv.motion}. Largest "
            f"relative change of any of the six measures on each doubling ({pairs}):"]
    for key, values in conv.changes.items():
        rows.append(f"- {key}: " + ", ".join(_pct2(v) for v in values))
    verdict = ("converged" if conv.converged else
               "NOT converged within the candidates (the largest N is used)")
    rows.append(f"\nChosen N = **{conv.springs}** ({verdict}): from it on, every doubling "
                f"changes the statics by ≤ {100 * conv.static_tolerance:g} % and the six "
                f"dynamic measures of Cases A and B by ≤ {100 * conv.tolerance:g} %.")
    if "C" in conv.changes:
        k = conv.candidates.index(conv.springs)
        after = conv.changes["C"][k] if k < len(conv.changes["C"]) else math.nan
        rows.append(f"Case C is reported, not required: doubling N = {conv.springs} still "
                    f"changes it by {_pct2(after)}. Its impact dashpots are sized per spring "
                    "(c* = multiple × 2√(k_i m_eff), stroke Δz ∝ 1/c*), so their sum grows as "
                    "√N and the Case C bed does not converge in N; its maps compare the "
                    "two-spring layouts with the bed at this N.")
    return "\n".join(rows)


def _pct2(value: float) -> str:
    return "inf" if not math.isfinite(value) else f"{100 * value:.2f} %"


def _statics_table(st: Statics) -> list[str]:
    rows = ["| foundation | positions x/b (–) | onset M/(NB) (–) | closed form (–) | "
            "capacity M/(NB) (–) | closed form (–) | "
            f"M_ult/(NB), FS_v = {st.yield_multiple:g} (–) | closed form (–) |",
            "|---|---|---|---|---|---|---|---|"]
    for s in st.layouts:
        two = len(s.positions) == 2
        pos = f"±{s.positions[-1]:.4f}" if two else f"{len(s.positions)} strips"
        rows.append(f"| {s.label} | {pos} | {s.onset:.6f} | {s.onset_closed_form:.6f} | "
                    f"{s.capacity:.6f} | {s.capacity_closed_form:.6f} | {s.ultimate:.6f} | "
                    f"{s.ultimate_closed_form:.6f} |")
    return rows


def _statics_text(st: Statics, threshold: float) -> list[str]:
    n = st.springs
    thr = f"{100 * threshold:g} %"
    out = [f"Uplift-onset ratio, equivalent / uniform bed: **{st.onset_ratio:.4f}** (anchor "
           f"1.73 = 0.288675/(1/6); the bed of {n} strips uplifts at (1/6)(1 + 1/N), so "
           f"1.7321/(1 + 1/{n}) = {math.sqrt(3) / (1 + 1 / n):.4f}). Capacity ratio: "
           f"**{st.capacity_ratio:.4f}** (anchor 0.58 = 0.288675/0.5).", ""]
    for label in ("edges", "equivalent", "calibrated (uniform)"):
        parts = []
        for which in ("elastic", "plastic"):
            limit = st.within(label, threshold, which)
            parts.append(f"{'elastic' if which == 'elastic' else 'elasto-plastic'} backbone "
                         + (f"up to θ = {limit:.3g} θ_up" if limit else
                            f"not even at θ = {st.theta[0]:.3g} θ_up"))
        out.append(f"- {label}: within {thr} of the uniform bed's: " + "; ".join(parts) + ".")
    return out


def _region_table(regions, emap: ErrorMap, threshold: float) -> list[str]:
    rows = [f"| case | layout | {METRIC_LABELS['u']}: region within {100 * threshold:g} % | "
            f"{METRIC_LABELS['all']}: region | grid points within {100 * threshold:g} % (count: "
            "u, θ, uplift, residual, shear, energy) |",
            "|---|---|---|---|---|"]
    for case in emap.cases:
        for layout in emap.layouts:
            mine = {r.metric: r for r in regions if (r.map, r.case, r.layout)
                    == (emap.name, case, layout)}
            shares = ", ".join(f"{mine[m].passing}" for m in METRICS)
            rows.append(f"| {case} | {layout} | {_short(mine['u'].text)} | "
                        f"{_short(mine['all'].text)} | {shares} of {mine['u'].total} |")
    return rows


def _short(text: str) -> str:
    """The region statement without its subject ("... stay within 10 % for X" -> "for X")."""
    return text.split("%", 1)[1].strip() if "%" in text else text
