"""The study's figures, drawn from its dataset. As the report shows them, one question each,
at page width with a caption whose conclusion is computed from the plotted numbers
(:mod:`..figure_record`): Figs. 11 and 12 (deformation history, fixed base against uplift
allowed), the ratio spectra (where does uplift reduce the peaks?) and the peak spectra (how
large are they?). And the study's own all-panel PNGs, ``fig11_12.png`` and ``spectrum.png``."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...framework.figure_record import Caption, page_figure, print_style, save
from ...framework.study import write_figure
from .analysis import figure_ratio, ratio, spectrum_ranges, spectrum_supports
from .grid import SUPPORT_LABELS
from .summary import span_text

_COLOURS = {"fixed": "#000000", "C": "#D55E00", "A": "#0072B2"}
_FAMILY_STYLE = ("-", "--")


def write_figures(ds, directory: Path) -> list[Path]:
    """Every figure (the all-panel PNGs; records, SVG and PNG) into ``directory``; the
    files."""
    files = [plot_figures(ds, directory / "fig11_12.png"),
             plot_spectra(ds, directory / "spectrum.png")]
    for building in ds.building.values.tolist():
        files += save(directory / f"history_fig{_number(ds, building)}.png",
                      *_history_figure(ds, building))
    if ds.family.size:
        files += save(directory / "spectrum_ratio.png", *_ratio_figure(ds))
        files += save(directory / "spectrum_peaks.png", *_peaks_figure(ds))
    return files


def _number(ds, building: str) -> int:
    return int(ds.figure.sel(building=building))


def _history(ds, building: str, support: str):
    """(time in s, u in in, peak u in in) of the figure run of ``building`` and ``support``."""
    one = ds.sel(building=building, support=support)
    return ds.time.values, one.u.values, float(one.peak_u)


def _history_figure(ds, building: str):
    number = _number(ds, building)
    with print_style():
        fig, ax = page_figure(2.8)
        for s in ("fixed", "C"):
            t, u, peak = _history(ds, building, s)
            ax.plot(t, u, "-", color=_COLOURS[s], lw=0.9 if s == "C" else 1.3,
                    label=f"{SUPPORT_LABELS[s]} (peak {peak:.3g} in)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("u (in)")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right")
    peak = {s: _history(ds, building, s)[2] for s in ("fixed", "C")}
    conclusion = (f"Allowing uplift changes the peak deformation from {peak['fixed']:.3g} "
                  f"in to {peak['C']:.3g} in (× {figure_ratio(ds, building, 'u'):.2f}) and the "
                  f"peak base shear × {figure_ratio(ds, building, 'shear'):.2f}.")
    shown = (f"Fig. {number} of the paper recomputed: story deformation u (in) of the "
             f"{building}-period building under El Centro 1940 N-S, fixed base against uplift "
             "allowed (Case C).")
    return fig, Caption(f"What does uplift do to the {building}-period building?", shown,
                        conclusion)


def _ratio_figure(ds):
    supports = [s for s in spectrum_supports(ds) if s != "fixed"]
    periods = ds.period.values
    with print_style():
        fig, axes = page_figure(3.3, 1, 2, sharey=True)
        for family, ls in zip(ds.family.values.tolist(), _FAMILY_STYLE):
            for support in supports:
                for ax, what in zip(axes, ("shear", "u")):
                    ax.semilogx(periods, ratio(ds, family, support, what), ls,
                                color=_COLOURS[support],
                                label=f"{family}: {SUPPORT_LABELS[support]}")
        for ax, title in zip(axes, ("peak base shear V", "peak deformation u")):
            ax.axhline(1.0, color="grey", lw=0.8)
            ax.set_xlabel("superstructure period T (s)")
            ax.set_title(f"{title}: uplift ÷ fixed")
            ax.grid(True, which="both", alpha=0.3)
        axes[0].set_ylabel("ratio (–)")
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    parts = [_ratio_text(ds, family) for family in ds.family.values.tolist()]
    shown = ("Peak base shear (left) and peak deformation (right) with uplift allowed divided "
             "by the fixed base's, against the superstructure period T (s), El Centro 1940 "
             "N-S; below 1, uplift reduces the peak.")
    return fig, Caption("Over which periods does uplift reduce the peaks?", shown,
                        " ".join(parts))


def _ratio_text(ds, family: str) -> str:
    r = spectrum_ranges(ds, family)[("C", "shear")]
    return (f"{family}-period family: Case C reduces the peak base shear over "
            f"{span_text(r.reduced)} (smallest ratio {r.min_ratio:.2f} at {r.min_period:g} s) "
            f"and increases it over {span_text(r.increased)}.")


def _peaks_figure(ds):
    periods = ds.period.values
    shear, u = ds.spectrum_shear_coefficient, ds.spectrum_peak_u
    with print_style():
        fig, axes = page_figure(3.3, 1, 2, sharex=True)
        for family, ls in zip(ds.family.values.tolist(), _FAMILY_STYLE):
            for support in spectrum_supports(ds):
                label = f"{family}: {SUPPORT_LABELS[support]}"
                at = {"family": family, "support": support}
                axes[0].loglog(periods, shear.sel(at).values, ls, color=_COLOURS[support],
                               label=label)
                axes[1].loglog(periods, u.sel(at).values, ls, color=_COLOURS[support])
        axes[0].set_ylabel("peak base shear V/W (–)")
        axes[1].set_ylabel("peak deformation u (in)")
        for ax in axes:
            ax.set_xlabel("superstructure period T (s)")
            ax.grid(True, which="both", alpha=0.3)
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    parts = []
    for family in ds.family.values.tolist():
        fixed = np.max(shear.sel(family=family, support="fixed").values)
        c = np.max(shear.sel(family=family, support="C").values)
        parts.append(f"{family}-period family: largest V/W {fixed:.3g} fixed, {c:.3g} with "
                     "uplift (Case C).")
    shown = ("Peak base shear coefficient V/W (left) and peak deformation u (in, right) against "
             "the superstructure period T (s) for each support, El Centro 1940 N-S.")
    return fig, Caption("How large are the peaks with and without uplift?", shown,
                        " ".join(parts))


def plot_figures(ds, path: Path) -> Path:
    """Figs. 11–12 in one PNG, a panel per building (the study's own folder)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    buildings = ds.building.values.tolist()
    fig, axes = plt.subplots(len(buildings), 1, figsize=(9, 3.2 * len(buildings)),
                             constrained_layout=True, squeeze=False)
    for ax, building in zip(axes[:, 0], buildings):
        for s, style in (("fixed", "k-"), ("C", "C3-")):
            t, u, peak = _history(ds, building, s)
            ax.plot(t, u, style, lw=0.8, label=f"{SUPPORT_LABELS[s]} (peak {peak:.3g} in)")
        ax.set_title(f"Fig. {_number(ds, building)}: {building}-period building, El Centro "
                     "1940 N-S", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("u (in)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    return write_figure(path, fig)


def plot_spectra(ds, path: Path) -> Path:
    """V/W, u and the ratios against the period in one PNG (the study's own folder)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(14, 4), constrained_layout=True)
    colours = {"fixed": "k", "C": "C3", "A": "C0"}
    periods = ds.period.values
    for family, ls in zip(ds.family.values.tolist(), ("-", "--")):
        for support in spectrum_supports(ds):
            lab = f"{family}: {SUPPORT_LABELS[support]}"
            at = {"family": family, "support": support}
            axes[0].loglog(periods, ds.spectrum_shear_coefficient.sel(at).values, ls,
                           color=colours[support], label=lab)
            axes[1].loglog(periods, ds.spectrum_peak_u.sel(at).values, ls,
                           color=colours[support], label=lab)
            if support != "fixed":
                axes[2].semilogx(periods, ratio(ds, family, support, "shear"), ls,
                                 color=colours[support], label=f"{lab}: V")
                axes[2].semilogx(periods, ratio(ds, family, support, "u"), ls,
                                 color=colours[support], marker=".", alpha=0.6,
                                 label=f"{lab}: u")
    axes[2].axhline(1.0, color="grey", lw=0.8)
    for ax, title in zip(axes, ("peak base shear V/W", "peak deformation u (in)",
                                "ratio uplift / fixed")):
        ax.set_xlabel("superstructure period T (s)")
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    return write_figure(path, fig)
