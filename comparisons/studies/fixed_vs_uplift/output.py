"""The study's files (histories, spectra, figures) and its write step."""

from __future__ import annotations

from dataclasses import asdict
from pathlib import Path

import numpy as np

from ....provenance import provenance
from ....results import write_csv
from ...framework.protocol import Context
from ...framework.study import StudyResult, write_figure, write_summary
from .analysis import FixedVsUplift
from .grid import OUTPUT_DT, STUDY, SUPPORT_LABELS
from .summary import summary_markdown, summary_numbers

# ---------------------------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------------------------


def write(result: FixedVsUplift, ctx: Context) -> StudyResult:
    """Histories, spectra, figures and the summary into ``ctx.out``."""
    fast, out, store = ctx.fast, ctx.out, ctx.store
    prov = provenance(study=STUDY, fast=fast, grid=asdict(result.grid), store=str(store.root))
    files = []
    for f in result.figures:
        t = np.arange(0.0, min(f.time["fixed"][-1], f.time["C"][-1]), OUTPUT_DT)
        files.append(write_csv(out / f"fig{f.number}.csv",
                               {"time_s": t, "u_fixed": np.interp(t, f.time["fixed"],
                                                                  f.u["fixed"]),
                                "u_uplift_case_C": np.interp(t, f.time["C"], f.u["C"])},
                               header=f"{STUDY}: Fig. {f.number}, {f.building}-period "
                                      "building, El Centro 1940 N-S; u in inches"))
    for s in result.spectra:
        cols = {"period_s": s.periods}
        for support in result.grid.supports:
            cols[f"u_{support}"] = s.u[support]
            cols[f"shear_coefficient_{support}"] = s.shear[support]
            cols[f"uplifted_{support}"] = s.uplifted[support].astype(float)
        files.append(write_csv(out / f"spectrum_{s.family}.csv", cols,
                               header=f"{STUDY}: peak u (in) and base shear V/W against the "
                                      f"superstructure period, {s.family}-period building's "
                                      "base body, El Centro 1940 N-S"))
    if result.options.figures:
        files += [plot_figures(result, out / "figures" / "fig11_12.png"),
                  plot_spectra(result, out / "figures" / "spectrum.png")]
    elapsed = ctx.elapsed()
    numbers = summary_numbers(result, elapsed)
    text = summary_markdown(result, fast, elapsed)
    files += list(write_summary(out, text, {"numbers": numbers, "provenance": prov}))
    return StudyResult(STUDY, fast, out, tuple(files), text, numbers, prov, elapsed)


def plot_figures(result: FixedVsUplift, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(result.figures), 1, figsize=(9, 3.2 * len(result.figures)),
                             constrained_layout=True, squeeze=False)
    for ax, f in zip(axes[:, 0], result.figures):
        for s, style in (("fixed", "k-"), ("C", "C3-")):
            ax.plot(f.time[s], f.u[s], style, lw=0.8,
                    label=f"{SUPPORT_LABELS[s]} (peak {f.peak_u[s]:.3g} in)")
        ax.set_title(f"Fig. {f.number}: {f.building}-period building, El Centro 1940 N-S",
                     fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("u (in)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    return write_figure(path, fig)


def plot_spectra(result: FixedVsUplift, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(14, 4), constrained_layout=True)
    colours = {"fixed": "k", "C": "C3", "A": "C0"}
    for s, ls in zip(result.spectra, ("-", "--")):
        for support in result.grid.supports:
            lab = f"{s.family}: {SUPPORT_LABELS[support]}"
            axes[0].loglog(s.periods, s.shear[support], ls, color=colours[support], label=lab)
            axes[1].loglog(s.periods, s.u[support], ls, color=colours[support], label=lab)
            if support != "fixed":
                axes[2].semilogx(s.periods, s.ratio(support, "shear"), ls,
                                 color=colours[support], label=f"{lab}: V")
                axes[2].semilogx(s.periods, s.ratio(support, "u"), ls, color=colours[support],
                                 marker=".", alpha=0.6, label=f"{lab}: u")
    axes[2].axhline(1.0, color="grey", lw=0.8)
    for ax, title in zip(axes, ("peak base shear V/W", "peak deformation u (in)",
                                "ratio uplift / fixed")):
        ax.set_xlabel("superstructure period T (s)")
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    return write_figure(path, fig)
