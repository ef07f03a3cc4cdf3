"""The study's figures: backbones, convergence and the error maps."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..study import plot_error_maps, write_figure
from .convergence import Convergence
from .grid import METRICS, METRIC_LABELS
from .result import TwoSpringEquivalence
from .statics import Statics


def write_figures(result: TwoSpringEquivalence, directory: Path) -> list[Path]:
    files = [_backbone_figure(result.statics, directory / "backbones.png"),
             _convergence_figure(result.convergence, directory / "convergence.png")]
    levels = tuple(sorted({0.05, 0.10, result.options.threshold}))
    for emap in result.maps:
        for case in emap.cases:
            rows = [[(f"{layout}: {METRIC_LABELS[m]}", emap.error(case, layout, m))
                     for m in (*METRICS, "all")] for layout in emap.layouts]
            slug = case.replace("/", "")
            files.append(plot_error_maps(directory / f"{emap.name}_{slug}.png",
                                         f"{emap.title}, case {case}: |two-spring − Winkler| "
                                         f"/ Winkler (N = {result.springs})", emap.x, emap.y,
                                         rows, levels=levels))
    return files


def _backbone_figure(statics: Statics, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    t = statics.theta
    closed = np.where(t <= 1.0, t / 6.0, (3.0 - 2.0 * np.sqrt(1.0 / np.maximum(t, 1.0))) / 6.0)
    for ax, which in zip(axes, ("elastic", "plastic")):
        for s in statics.layouts:
            ax.semilogx(t, getattr(s, which), label=s.label)
        if which == "elastic":
            ax.semilogx(t, closed, "k:", label="closed form (anchor §3)")
        else:
            fs = statics.yield_multiple
            ax.axhline(0.5 * (1 - 1 / fs), color="k", ls=":",
                       label=f"M_ult = (NB/2)(1 − 1/FS_v), FS_v = {fs:g}")
        ax.set_xlabel("θ / θ_up")
        ax.set_ylabel("M / (N B)")
        ax.set_title(f"{'elastic' if which == 'elastic' else 'elasto-plastic'} springs, "
                     f"N = {statics.springs}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    return write_figure(path, fig)


def _convergence_figure(conv: Convergence, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    cases = list(conv.dynamic)
    fig, axes = plt.subplots(1, len(cases) + 1, figsize=(4 * (len(cases) + 1), 3.6),
                             constrained_layout=True)
    n = np.array(conv.candidates)
    for key, values in conv.static.items():
        v = np.array(values)
        axes[0].semilogx(n, v / v[-1], "o-", label=key)
    axes[0].set_title("statics")
    for ax, case in zip(axes[1:], cases):
        for m, values in conv.dynamic[case].items():
            v = np.array(values, dtype=float)
            ax.semilogx(n, v / v[-1] if v[-1] else v, "o-", label=METRIC_LABELS[m])
        ax.set_title(f"Case {case}")
    fig.suptitle(f"Winkler bed against N: value ÷ value at the largest N; dynamics: "
                 f"{conv.motion}", fontsize=9)
    axes[0].set_ylabel("value / value at largest N")
    for ax in axes:
        ax.axvline(conv.springs, color="k", ls=":")
        ax.set_xlabel("N springs")
        ax.set_xticks(n, [str(k) for k in conv.candidates])
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    return write_figure(path, fig)
