"""The study's summary, computed from its dataset alone (:func:`.workflow.compute`, or the
same read back by :func:`upliftlab.open_study`): the Markdown text (:func:`summarise`) and the
key numbers (:func:`key_numbers`). The wall time is the dataset's ``elapsed_s`` attribute (s),
set when the study is written."""

from __future__ import annotations

import math

import numpy as np

from .analysis import Ranges, at, figure_ratio, spectrum_ranges, spectrum_supports
from .dataset import FIGURE_SUPPORTS
from .grid import NO_CHANGE, PAPER_FIG11_PEAK_U, PAPER_PERIODS, SUPPORT_LABELS


def ranges_dict(r: Ranges) -> dict:
    return {"reduced": r.reduced, "increased": r.increased, "min_ratio": r.min_ratio,
            "min_period": r.min_period, "max_ratio": r.max_ratio, "max_period": r.max_period,
            "median_ratio": r.median, "periods_reduced": r.count_reduced, "periods": r.total}


def _peaks(ds, name: str, building: str) -> dict:
    return {s: float(ds[name].sel(building=building, support=s)) for s in FIGURE_SUPPORTS}


def _figures(ds):
    """(building, figure number) of Figs. 11–12 in the dataset."""
    return zip(ds.building.values.tolist(), ds.figure.values.tolist())


def _ranges(ds) -> dict:
    """{family: {(support, "shear" | "u"): :class:`Ranges`}} of the spectrum."""
    return {f: spectrum_ranges(ds, f) for f in ds.family.values.tolist()}


def _elapsed(ds) -> float:
    return float(ds.attrs.get("elapsed_s", math.nan))


def summarise(ds) -> str:
    """The Markdown summary of the study's dataset ``ds``."""
    return summary_markdown(ds, _ranges(ds), _elapsed(ds))


def key_numbers(ds) -> dict:
    """The key numbers of the study's dataset ``ds`` (``summary.json``)."""
    return summary_numbers(ds, _ranges(ds), _elapsed(ds))


def summary_numbers(ds, ranges: dict, elapsed: float) -> dict:
    figs = {f"fig{n}": {"building": b, "peak_u": _peaks(ds, "peak_u", b),
                        "peak_base_shear": _peaks(ds, "peak_base_shear", b),
                        "peak_uplift": _peaks(ds, "peak_uplift", b),
                        "ratio_u": figure_ratio(ds, b, "u"),
                        "ratio_base_shear": figure_ratio(ds, b, "shear")}
            for b, n in _figures(ds)}
    if "fig11" in figs:
        figs["fig11"]["paper_peak_u"] = PAPER_FIG11_PEAK_U
    spectra = {family: {f"{support}_{what}": ranges_dict(r)
                        for (support, what), r in rs.items()} for family, rs in ranges.items()}
    shear = ds.spectrum_shear_coefficient
    largest = {f: {s: float(np.nanmax(shear.sel(family=f, support=s).values))
                   for s in spectrum_supports(ds)} for f in ranges}
    ratios = {f: {f"{support}_{what}_T{t:g}": at(ds, f, support, what, t)
                  for (support, what) in rs for t in PAPER_PERIODS}
              for f, rs in ranges.items()}
    return {"figures": figs, "spectra": spectra, "ratios_at_paper_periods": ratios,
            "largest_shear_coefficient": largest,
            "periods": [float(t) for t in ds.period.values], "continuum": ds.attrs["continuum"],
            "elapsed_s": elapsed}


def span_text(runs) -> str:
    if not runs:
        return "nowhere on the grid"
    return ", ".join(f"{a:g}–{b:g} s" if a != b else f"{a:g} s" for a, b in runs)


def summary_markdown(ds, ranges: dict, elapsed: float) -> str:
    fast = bool(ds.attrs.get("fast", 0))
    periods = ds.period.values
    lines = [f"# Fixed base against uplift allowed{' (fast)' if fast else ''}", "",
             f"El Centro 1940 N-S. Wall time {elapsed:.1f} s. Continuum: "
             f"{ds.attrs['continuum']}.",
             "", "## Figs. 11–12 (reduced model, Winkler bed of 12 springs)", "",
             "The scenes' beds of 12 springs, as drawn in Fig. 1(b). Case C's impact dashpots "
             "are sized per spring, so its peaks depend on N (the speed_vs_error study measures "
             "by how much); the comparison is the paper's, at the paper's N.", "",
             "| figure | building | peak u fixed (in) | peak u uplift C (in) | ratio (–) | "
             "peak V fixed (kip) | peak V uplift C (kip) | ratio (–) |",
             "|---|---|---|---|---|---|---|---|"]
    for b, n in _figures(ds):
        u, v = _peaks(ds, "peak_u", b), _peaks(ds, "peak_base_shear", b)
        lines.append(f"| {n} | {b}-period | {u['fixed']:.4g} | {u['C']:.4g} | "
                     f"{figure_ratio(ds, b, 'u'):.3f} | {v['fixed']:.4g} | {v['C']:.4g} | "
                     f"{figure_ratio(ds, b, 'shear'):.3f} |")
    if "short" in ds.building.values:
        u, p = _peaks(ds, "peak_u", "short"), PAPER_FIG11_PEAK_U
        lines += ["", f"Fig. 11 as read from the paper: {p['C']:g} in (uplift) against "
                  f"{p['fixed']:g} in (fixed); here {u['C']:.4g} and "
                  f"{u['fixed']:.4g} in ({100 * (u['C'] / p['C'] - 1):+.1f} % "
                  f"and {100 * (u['fixed'] / p['fixed'] - 1):+.1f} %)."]
    lines += ["", "## Spectrum: uplift / fixed against the superstructure period", "",
              f"{len(periods)} periods from {periods[0]:g} to "
              f"{periods[-1]:g} s; h/b = 2.8, weights, base body and foundation "
              f"held. A ratio within {100 * NO_CHANGE:g} % of one counts as no change.", ""]
    shear = ds.spectrum_shear_coefficient
    for family, rs in ranges.items():
        peaks = []
        for k in spectrum_supports(ds):
            v = shear.sel(family=family, support=k).values
            peaks.append(f"{SUPPORT_LABELS[k]} {np.nanmax(v):.3f} (at "
                         f"{periods[int(np.nanargmax(v))]:g} s)")
        lines += [f"### {family}-period building's base body", "",
                  f"Largest base-shear coefficient V/W over the periods: {', '.join(peaks)}.",
                  "", "| uplift case | quantity | reduced over (periods T in s) | by up to (min "
                  "ratio (–), at T) | median ratio (–) | increased over (T in s) | max ratio "
                  "(–) (at T) | ratio at T = 0.15 s (–) | ratio at T = 0.59 s (–) |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for (support, what), r in rs.items():
            name = "peak base shear" if what == "shear" else "peak deformation"
            lines.append(f"| {SUPPORT_LABELS[support]} | {name} | {span_text(r.reduced)} "
                         f"({r.count_reduced} of {r.total}) | {100 * (1 - r.min_ratio):.0f} % "
                         f"({r.min_ratio:.3f}, {r.min_period:g} s) | {r.median:.3f} | "
                         f"{span_text(r.increased)} | {r.max_ratio:.3f} ({r.max_period:g} s) | "
                         f"{at(ds, family, support, what, 0.15):.3f} | "
                         f"{at(ds, family, support, what, 0.59):.3f} |")
        lines.append("")
    return "\n".join(lines)
