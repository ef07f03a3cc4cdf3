"""The study's summary: key numbers and the Markdown text computed from them."""

from __future__ import annotations

import numpy as np

from .analysis import FixedVsUplift, Ranges
from .grid import NO_CHANGE, PAPER_FIG11_PEAK_U, PAPER_PERIODS, SUPPORT_LABELS


def ranges_dict(r: Ranges) -> dict:
    return {"reduced": r.reduced, "increased": r.increased, "min_ratio": r.min_ratio,
            "min_period": r.min_period, "max_ratio": r.max_ratio, "max_period": r.max_period,
            "median_ratio": r.median, "periods_reduced": r.count_reduced, "periods": r.total}


def summary_numbers(result: FixedVsUplift, elapsed: float) -> dict:
    figs = {f"fig{f.number}": {"building": f.building, "peak_u": f.peak_u,
                                "peak_base_shear": f.base_shear, "peak_uplift": f.uplift,
                                "ratio_u": f.ratio_u, "ratio_base_shear": f.ratio_shear}
            for f in result.figures}
    if "fig11" in figs:
        figs["fig11"]["paper_peak_u"] = PAPER_FIG11_PEAK_U
    spectra = {s.family: {f"{support}_{what}": ranges_dict(r)
                          for (support, what), r in s.ranges.items()} for s in result.spectra}
    largest = {s.family: {k: float(np.nanmax(v)) for k, v in s.shear.items()}
               for s in result.spectra}
    at = {s.family: {f"{support}_{what}_T{t:g}": s.at(support, what, t)
                     for (support, what) in s.ranges for t in PAPER_PERIODS}
          for s in result.spectra}
    return {"figures": figs, "spectra": spectra, "ratios_at_paper_periods": at,
            "largest_shear_coefficient": largest,
            "periods": list(result.grid.periods), "continuum": result.continuum,
            "elapsed_s": elapsed}


def span_text(runs) -> str:
    if not runs:
        return "nowhere on the grid"
    return ", ".join(f"{a:g}–{b:g} s" if a != b else f"{a:g} s" for a, b in runs)


def summary_markdown(result: FixedVsUplift, fast: bool, elapsed: float) -> str:
    lines = [f"# Fixed base against uplift allowed{' (fast)' if fast else ''}", "",
             f"El Centro 1940 N-S. Wall time {elapsed:.1f} s. Continuum: {result.continuum}.",
             "", "## Figs. 11–12 (reduced model, Winkler bed of 12 springs)", "",
             "The scenes' beds of 12 springs, as drawn in Fig. 1(b). Case C's impact dashpots "
             "are sized per spring, so its peaks depend on N (the speed_vs_error study measures "
             "by how much); the comparison is the paper's, at the paper's N.", "",
             "| figure | building | peak u fixed (in) | peak u uplift C (in) | ratio (–) | "
             "peak V fixed (kip) | peak V uplift C (kip) | ratio (–) |",
             "|---|---|---|---|---|---|---|---|"]
    for f in result.figures:
        lines.append(f"| {f.number} | {f.building}-period | {f.peak_u['fixed']:.4g} | "
                     f"{f.peak_u['C']:.4g} | {f.ratio_u:.3f} | {f.base_shear['fixed']:.4g} | "
                     f"{f.base_shear['C']:.4g} | {f.ratio_shear:.3f} |")
    if any(f.building == "short" for f in result.figures):
        f = result.figure("short")
        p = PAPER_FIG11_PEAK_U
        lines += ["", f"Fig. 11 as read from the paper: {p['C']:g} in (uplift) against "
                  f"{p['fixed']:g} in (fixed); here {f.peak_u['C']:.4g} and "
                  f"{f.peak_u['fixed']:.4g} in ({100 * (f.peak_u['C'] / p['C'] - 1):+.1f} % "
                  f"and {100 * (f.peak_u['fixed'] / p['fixed'] - 1):+.1f} %)."]
    lines += ["", "## Spectrum: uplift / fixed against the superstructure period", "",
              f"{len(result.grid.periods)} periods from {result.grid.periods[0]:g} to "
              f"{result.grid.periods[-1]:g} s; h/b = 2.8, weights, base body and foundation "
              f"held. A ratio within {100 * NO_CHANGE:g} % of one counts as no change.", ""]
    for s in result.spectra:
        peaks = ", ".join(f"{SUPPORT_LABELS[k]} {np.nanmax(v):.3f} (at "
                          f"{s.periods[int(np.nanargmax(v))]:g} s)" for k, v in s.shear.items())
        lines += [f"### {s.family}-period building's base body", "",
                  f"Largest base-shear coefficient V/W over the periods: {peaks}.", "",
                  "| uplift case | quantity | reduced over (periods T in s) | by up to (min "
                  "ratio (–), at T) | median ratio (–) | increased over (T in s) | max ratio "
                  "(–) (at T) | ratio at T = 0.15 s (–) | ratio at T = 0.59 s (–) |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for (support, what), r in s.ranges.items():
            name = "peak base shear" if what == "shear" else "peak deformation"
            lines.append(f"| {SUPPORT_LABELS[support]} | {name} | {span_text(r.reduced)} "
                         f"({r.count_reduced} of {r.total}) | {100 * (1 - r.min_ratio):.0f} % "
                         f"({r.min_ratio:.3f}, {r.min_period:g} s) | {r.median:.3f} | "
                         f"{span_text(r.increased)} | {r.max_ratio:.3f} ({r.max_period:g} s) | "
                         f"{s.at(support, what, 0.15):.3f} | {s.at(support, what, 0.59):.3f} |")
        lines.append("")
    return "\n".join(lines)
