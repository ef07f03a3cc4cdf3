"""The study's summary, computed from its data alone (:func:`.workflow.compute`, or the same
read back by :func:`upliftlab.open_study`): the Markdown text (:func:`summarise`) and the key
numbers (:func:`key_numbers`). The wall time is the data's ``elapsed_s`` attribute (s), set
when the study is written."""

from __future__ import annotations

import math

from . import statics as st
from .analysis import equivalence_regions, ewing_conclusion
from .grid import ENERGY_TOLERANCE, FLOOR_FRACTION, LAYOUTS, METRICS, METRIC_LABELS
from .views import STATICS, cases, convergence, failures, heading, layouts, maps, study_attrs


def _conclusions(tree) -> tuple[list, list, object]:
    """(the maps, their region statements, Ewing's conclusion) at the study's threshold."""
    threshold = float(study_attrs(tree)["threshold"])
    found = maps(tree)
    return found, equivalence_regions(found, threshold), ewing_conclusion(found, threshold)


def _elapsed(tree) -> float:
    return float(tree[STATICS].attrs.get("elapsed_s", math.nan))


def summarise(tree) -> str:
    """The Markdown summary of the study's data ``tree``."""
    return summary_markdown(tree, *_conclusions(tree), _elapsed(tree))


def key_numbers(tree) -> dict:
    """The key numbers of the study's data ``tree`` (``summary.json``)."""
    return summary_numbers(tree, *_conclusions(tree), _elapsed(tree))


def _statics_numbers(ds) -> dict:
    keys = ("onset", "onset_closed_form", "capacity", "capacity_closed_form", "ultimate",
            "ultimate_closed_form")
    return {label: {"positions_over_b": st.positions(ds, label),
                    **{k: st.of(ds, label, k) for k in keys}}
            for label in (str(v) for v in ds.foundation.values)}


def summary_numbers(tree, found, regions, ewing, elapsed: float) -> dict:
    conv, statics = convergence(tree), tree[STATICS].to_dataset()
    return {
        "springs": conv["springs"],
        "converged": conv["converged"],
        "convergence_changes": conv["changes"],
        "statics": _statics_numbers(statics),
        "onset_ratio_equivalent_vs_winkler": st.onset_ratio(statics),
        "capacity_ratio_equivalent_vs_winkler": st.capacity_ratio(statics),
        "regions": [{"map": r.map, "case": r.case, "layout": r.layout, "measure": r.metric,
                     "text": r.text, "passing": r.passing, "total": r.total}
                    for r in regions],
        "ewing": {"holds": ewing.holds, "elastic_holds": ewing.elastic_holds,
                  "share": ewing.share, "median": ewing.median,
                  "uplifting_points": ewing.points,
                  "bonded_error": ewing.bonded_error, "text": ewing.text},
        "points": sum(m[f"reference_{METRICS[0]}"].size * (len(LAYOUTS) + 1) for m in found),
        "failures": [f for m in found for f in failures(m)],
        "max_energy_balance_error": max((float(m.attrs["energy_balance_error"])
                                         for m in found), default=0.0),
        "elapsed_s": elapsed,
    }


def summary_markdown(tree, found, regions, ewing, elapsed: float) -> str:
    conv, statics, study = convergence(tree), tree[STATICS].to_dataset(), study_attrs(tree)
    threshold = float(study["threshold"])
    thr = f"{100 * threshold:g} %"
    lines = [f"# Two-spring equivalence{' (fast)' if study['fast'] else ''}", "",
             f"Base scene `{study['scene']}` (h/b = {study['h_over_b']:.3g}, T = "
             f"{study['period']:.3g} s, FS_v = {study['yield_multiple']:g}). Intensity = PGA / "
             "a_up with a_up = g·b/(3h), "
             "the quasi-static uplift acceleration of the uniform Winkler bed (N → ∞) under a "
             f"rigid superstructure. Equivalence threshold: {thr}. Records: "
             f"{study['record_note']}. Wall time {elapsed:.1f} s.", "",
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
             "## Statics (anchors §2–3)", "", *_statics_table(statics), "",
             *_statics_text(statics, threshold), "",
             "## Where two springs can replace the bed", ""]
    for ds in found:
        lines += [f"### {heading(ds)}", ""]
        lines += _region_table(regions, ds, threshold)
        lines.append("")
    lines += ["## Ewing's conclusion, quantified", "", ewing.text, ""]
    failed = [f for m in found for f in failures(m)]
    balance = max((float(m.attrs["energy_balance_error"]) for m in found), default=0.0)
    lines += [f"Runs not used: {len(failed)} (refused by the integrator, or energy balance "
              f"off by more than {ENERGY_TOLERANCE:g} of the input; their cells are blank). "
              f"Largest energy-balance error of any run: {balance:.1e} of its input.", ""]
    lines += [f"- {f}" for f in failed[:20]]
    if len(failed) > 20:
        lines.append(f"- … and {len(failed) - 20} more (summary.json)")
    return "\n".join(lines)


def _convergence_text(conv: dict) -> str:
    n = conv["candidates"]
    pairs = ", ".join(f"{n[j]}→{n[j + 1]}" for j in range(len(n) - 1))
    rows = [f"Candidates N = {', '.join(map(str, n))}; base scene, {conv['motion']}. Largest "
            f"relative change of any of the six measures on each doubling ({pairs}):"]
    for key, values in conv["changes"].items():
        rows.append(f"- {key}: " + ", ".join(_pct2(v) for v in values))
    verdict = ("converged" if conv["converged"] else
               "NOT converged within the candidates (the largest N is used)")
    rows.append(f"\nChosen N = **{conv['springs']}** ({verdict}): from it on, every doubling "
                f"changes the statics by ≤ {100 * conv['static_tolerance']:g} % and the six "
                f"dynamic measures of Cases A and B by ≤ {100 * conv['tolerance']:g} %.")
    changes = conv["changes"]
    if "C" in changes:
        k = n.index(conv["springs"])
        after = changes["C"][k] if k < len(changes["C"]) else math.nan
        rows.append(f"Case C is reported, not required: doubling N = {conv['springs']} still "
                    f"changes it by {_pct2(after)}. Its impact dashpots are sized per spring "
                    "(c* = multiple × 2√(k_i m_eff), stroke Δz ∝ 1/c*), so their sum grows as "
                    "√N and the Case C bed does not converge in N; its maps compare the "
                    "two-spring layouts with the bed at this N.")
    return "\n".join(rows)


def _pct2(value: float) -> str:
    return "inf" if not math.isfinite(value) else f"{100 * value:.2f} %"


def _statics_table(ds) -> list[str]:
    rows = ["| foundation | positions x/b (–) | onset M/(NB) (–) | closed form (–) | "
            "capacity M/(NB) (–) | closed form (–) | "
            f"M_ult/(NB), FS_v = {float(ds.attrs['yield_multiple']):g} (–) | closed form (–) |",
            "|---|---|---|---|---|---|---|---|"]
    for label in (str(v) for v in ds.foundation.values):
        x = st.positions(ds, label)
        pos = f"±{x[-1]:.4f}" if len(x) == 2 else f"{len(x)} strips"
        v = {k: st.of(ds, label, k) for k in ("onset", "onset_closed_form", "capacity",
                                               "capacity_closed_form", "ultimate",
                                               "ultimate_closed_form")}
        rows.append(f"| {label} | {pos} | {v['onset']:.6f} | {v['onset_closed_form']:.6f} | "
                    f"{v['capacity']:.6f} | {v['capacity_closed_form']:.6f} | "
                    f"{v['ultimate']:.6f} | {v['ultimate_closed_form']:.6f} |")
    return rows


def _statics_text(ds, threshold: float) -> list[str]:
    n = int(ds.attrs["springs"])
    thr = f"{100 * threshold:g} %"
    out = [f"Uplift-onset ratio, equivalent / uniform bed: **{st.onset_ratio(ds):.4f}** (anchor "
           f"1.73 = 0.288675/(1/6); the bed of {n} strips uplifts at (1/6)(1 + 1/N), so "
           f"1.7321/(1 + 1/{n}) = {math.sqrt(3) / (1 + 1 / n):.4f}). Capacity ratio: "
           f"**{st.capacity_ratio(ds):.4f}** (anchor 0.58 = 0.288675/0.5).", ""]
    first = float(ds.theta_over_theta_up.values[0])
    for label in ("edges", "equivalent", "calibrated (uniform)"):
        parts = []
        for which in ("elastic", "plastic"):
            limit = st.within(ds, label, threshold, which)
            parts.append(f"{'elastic' if which == 'elastic' else 'elasto-plastic'} backbone "
                         + (f"up to θ = {limit:.3g} θ_up" if limit else
                            f"not even at θ = {first:.3g} θ_up"))
        out.append(f"- {label}: within {thr} of the uniform bed's: " + "; ".join(parts) + ".")
    return out


def _region_table(regions, ds, threshold: float) -> list[str]:
    rows = [f"| case | layout | {METRIC_LABELS['u']}: region within {100 * threshold:g} % | "
            f"{METRIC_LABELS['all']}: region | grid points within {100 * threshold:g} % (count: "
            "u, θ, uplift, residual, shear, energy) |",
            "|---|---|---|---|---|"]
    name = ds.attrs["name"]
    for case in cases(ds):
        for layout in layouts(ds):
            mine = {r.metric: r for r in regions if (r.map, r.case, r.layout)
                    == (name, case, layout)}
            shares = ", ".join(f"{mine[m].passing}" for m in METRICS)
            rows.append(f"| {case} | {layout} | {_short(mine['u'].text)} | "
                        f"{_short(mine['all'].text)} | {shares} of {mine['u'].total} |")
    return rows


def _short(text: str) -> str:
    """The region statement without its subject ("... stay within 10 % for X" -> "for X")."""
    return text.split("%", 1)[1].strip() if "%" in text else text
