"""The study's figures as the report shows them, one question each, at page width with a
caption whose conclusion is computed from the plotted numbers (:mod:`..figure_record`):
Figs. 11 and 12 (deformation history, fixed base against uplift allowed), the ratio spectra
(where does uplift reduce the peaks?) and the peak spectra (how large are they?).

(The study's all-panel PNGs, ``fig11_12.png`` and ``spectrum.png``, are still written by
:mod:`.output` for the study's own folder.)"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...framework.figure_record import Caption, page_figure, print_style, save
from .analysis import Figure, FixedVsUplift, Spectrum
from .grid import SUPPORT_LABELS
from .summary import span_text

_COLOURS = {"fixed": "#000000", "C": "#D55E00", "A": "#0072B2"}
_FAMILY_STYLE = ("-", "--")


def write_figures(result: FixedVsUplift, directory: Path) -> list[Path]:
    """Every figure (records, SVG and PNG) into ``directory``; the files."""
    files = []
    for f in result.figures:
        files += save(directory / f"history_fig{f.number}.png", *_history_figure(f))
    if result.spectra:
        files += save(directory / "spectrum_ratio.png", *_ratio_figure(result))
        files += save(directory / "spectrum_peaks.png", *_peaks_figure(result))
    return files


def _history_figure(f: Figure):
    with print_style():
        fig, ax = page_figure(2.8)
        for s, style in (("fixed", "-"), ("C", "-")):
            ax.plot(f.time[s], f.u[s], style, color=_COLOURS[s], lw=0.9 if s == "C" else 1.3,
                    label=f"{SUPPORT_LABELS[s]} (peak {f.peak_u[s]:.3g} in)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("u (in)")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right")
    conclusion = (f"Allowing uplift changes the peak deformation from {f.peak_u['fixed']:.3g} "
                  f"in to {f.peak_u['C']:.3g} in (× {f.ratio_u:.2f}) and the peak base shear "
                  f"× {f.ratio_shear:.2f}.")
    shown = (f"Fig. {f.number} of the paper recomputed: story deformation u (in) of the "
             f"{f.building}-period building under El Centro 1940 N-S, fixed base against uplift "
             "allowed (Case C).")
    return fig, Caption(f"What does uplift do to the {f.building}-period building?", shown,
                        conclusion)


def _ratio_figure(result: FixedVsUplift):
    supports = [s for s in result.grid.supports if s != "fixed"]
    with print_style():
        fig, axes = page_figure(3.3, 1, 2, sharey=True)
        for s, ls in zip(result.spectra, _FAMILY_STYLE):
            for support in supports:
                for ax, what in zip(axes, ("shear", "u")):
                    ax.semilogx(s.periods, s.ratio(support, what), ls, color=_COLOURS[support],
                                label=f"{s.family}: {SUPPORT_LABELS[support]}")
        for ax, title in zip(axes, ("peak base shear V", "peak deformation u")):
            ax.axhline(1.0, color="grey", lw=0.8)
            ax.set_xlabel("superstructure period T (s)")
            ax.set_title(f"{title}: uplift ÷ fixed")
            ax.grid(True, which="both", alpha=0.3)
        axes[0].set_ylabel("ratio (–)")
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    parts = [_ratio_text(s) for s in result.spectra]
    shown = ("Peak base shear (left) and peak deformation (right) with uplift allowed divided "
             "by the fixed base's, against the superstructure period T (s), El Centro 1940 "
             "N-S; below 1, uplift reduces the peak.")
    return fig, Caption("Over which periods does uplift reduce the peaks?", shown,
                        " ".join(parts))


def _ratio_text(s: Spectrum) -> str:
    r = s.ranges[("C", "shear")]
    return (f"{s.family}-period family: Case C reduces the peak base shear over "
            f"{span_text(r.reduced)} (smallest ratio {r.min_ratio:.2f} at {r.min_period:g} s) "
            f"and increases it over {span_text(r.increased)}.")


def _peaks_figure(result: FixedVsUplift):
    with print_style():
        fig, axes = page_figure(3.3, 1, 2, sharex=True)
        for s, ls in zip(result.spectra, _FAMILY_STYLE):
            for support in result.grid.supports:
                label = f"{s.family}: {SUPPORT_LABELS[support]}"
                axes[0].loglog(s.periods, s.shear[support], ls, color=_COLOURS[support],
                               label=label)
                axes[1].loglog(s.periods, s.u[support], ls, color=_COLOURS[support])
        axes[0].set_ylabel("peak base shear V/W (–)")
        axes[1].set_ylabel("peak deformation u (in)")
        for ax in axes:
            ax.set_xlabel("superstructure period T (s)")
            ax.grid(True, which="both", alpha=0.3)
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=2,
                   frameon=False)
    parts = []
    for s in result.spectra:
        fixed, c = np.max(s.shear["fixed"]), np.max(s.shear["C"])
        parts.append(f"{s.family}-period family: largest V/W {fixed:.3g} fixed, {c:.3g} with "
                     "uplift (Case C).")
    shown = ("Peak base shear coefficient V/W (left) and peak deformation u (in, right) against "
             "the superstructure period T (s) for each support, El Centro 1940 N-S.")
    return fig, Caption("How large are the peaks with and without uplift?", shown,
                        " ".join(parts))
