"""The study's figures: runtime against error per scene, a 2 × 2 grid of the four quantities
at page width, with a caption whose conclusion is computed from the plotted points
(:mod:`..figure_record`)."""

from __future__ import annotations

import math
from pathlib import Path

from ....reduced.integrators import METHODS
from ...framework.figure_record import Caption, page_figure, print_style, save
from .analysis import cheapest, front, runs
from .grid import LABELS, QUANTITIES

# Okabe–Ito colours (told apart with colour-vision deficiencies), cycled over the integrators
_OKABE_ITO = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000",
              "#F0E442")
_COLOURS = {name: _OKABE_ITO[i % len(_OKABE_ITO)] for i, name in enumerate(METHODS)}
_MARKERS = {"edges": "s", "equivalent": "D", "winkler": "o", "continuum": "^"}
#: The error a caption asks the cheapest run for (fraction).
TOLERANCE = 0.01


def write_figures(ds, directory: Path) -> list[Path]:
    """The figure of every scene of the study's dataset ``ds`` into ``directory`` (record, SVG
    and PNG, named by the scene); the records' paths."""
    return [save(directory / f"{label}.png", *scene_figure(ds, label))[0]
            for label in ds.scene.values.tolist()]


def _short(label: str) -> str:
    return label.split(" (")[0]


def scene_figure(ds, label: str):
    """(figure, caption) of scene ``label`` of the study's dataset ``ds``."""
    import matplotlib.ticker

    points = runs(ds, label)
    reference_runtime = float(ds.reference_runtime.sel(scene=label))
    floor = 1e-6
    with print_style():
        fig, axes = page_figure(6.2, 2, 2, sharex=True)
        for ax, q in zip(axes.flat, QUANTITIES):
            for p in points:
                if p.failure is None:
                    ax.loglog(p.runtime, max(p.abs_error(q), floor), _MARKERS[p.model],
                              color=_COLOURS[p.integrator], ms=3 + 0.6 * math.log2(p.springs),
                              alpha=0.7, mfc="none")
            best = front(points, q)
            ax.loglog([p.runtime for p in best], [max(p.abs_error(q), floor) for p in best],
                      "k-", lw=1.2)
            ax.axvline(reference_runtime, color="grey", ls=":")
            ax.axhline(TOLERANCE, color="grey", lw=0.8)
            ax.set_title(_short(LABELS[q]))
            ax.grid(True, which="both", alpha=0.3)
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # decades only
        for ax in axes[1]:
            ax.set_xlabel("runtime (s)")
        for ax in axes[:, 0]:
            ax.set_ylabel("|relative error| (–)")
        handles = [matplotlib.lines.Line2D([], [], color=c, marker="o", ls="", label=n)
                   for n, c in _COLOURS.items()]
        handles += [matplotlib.lines.Line2D([], [], color="k", marker=m, ls="", mfc="none",
                                            label=n) for n, m in _MARKERS.items()]
        handles += [matplotlib.lines.Line2D([], [], color="k", label="Pareto front"),
                    matplotlib.lines.Line2D([], [], color="grey", ls=":",
                                            label="reference runtime")]
        fig.legend(handles=handles, loc="outside lower center", ncols=4, frameon=False)
    parts = []
    for q in QUANTITIES:
        p = cheapest(points, q, TOLERANCE)
        if p is None:
            parts.append(f"{_short(LABELS[q])}: no run within {100 * TOLERANCE:g} %")
        else:
            parts.append(f"{_short(LABELS[q])}: {p.integrator}, {p.model} with N = {p.springs},"
                         f" {p.runtime:.2g} s ({reference_runtime / p.runtime:.3g} × faster "
                         "than the reference)")
    conclusion = (f"The fastest run within {100 * TOLERANCE:g} % of the reference — "
                  + "; ".join(parts) + ".")
    shown = (f"{label}: |relative error| of every discretization (integrator by colour, "
             "foundation model by marker, marker size growing with log N) against its runtime "
             f"(s, median of repeats), for the four quantities; the black line is the Pareto "
             f"front, the grey line {100 * TOLERANCE:g} % error.")
    return fig, Caption(f"What does accuracy cost? {label}", shown, conclusion)
