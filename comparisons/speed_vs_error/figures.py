"""The study's figures: runtime against error per scene."""

from __future__ import annotations

import math
from pathlib import Path

from ...reduced.integrators import METHODS
from ..study import write_figure
from .analysis import SceneResult
from .grid import LABELS, QUANTITIES


_COLOURS = {name: f"C{i}" for i, name in enumerate(METHODS)}
_MARKERS = {"edges": "s", "equivalent": "D", "winkler": "o", "continuum": "^"}


def write_scene_figure(s: SceneResult, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, axes = plt.subplots(1, len(QUANTITIES), figsize=(4.2 * len(QUANTITIES), 3.8),
                             constrained_layout=True)
    for ax, q in zip(axes, QUANTITIES):
        floor = 1e-6
        for p in s.points:
            if p.failure is None:
                ax.loglog(p.runtime, max(p.abs_error(q), floor), _MARKERS[p.model],
                          color=_COLOURS[p.integrator], ms=3 + 0.6 * math.log2(p.springs),
                          alpha=0.6, mfc="none")
        front = s.front(q)
        ax.loglog([p.runtime for p in front], [max(p.abs_error(q), floor) for p in front],
                  "k-", lw=1.2, label="Pareto front")
        ax.axvline(s.reference.runtime, color="grey", ls=":", label="reference runtime")
        ax.set_xlabel("runtime (s)")
        ax.set_ylabel(f"|error| in {LABELS[q]}")
        ax.set_title(f"{s.label}: {LABELS[q]}", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # decades only
    handles = [plt.Line2D([], [], color=c, marker="o", ls="", label=n)
               for n, c in _COLOURS.items()]
    handles += [plt.Line2D([], [], color="k", marker=m, ls="", mfc="none", label=n)
                for n, m in _MARKERS.items()]
    axes[0].legend(handles=handles, fontsize=6, title="marker size ∝ log N", title_fontsize=6)
    return write_figure(path, fig)
