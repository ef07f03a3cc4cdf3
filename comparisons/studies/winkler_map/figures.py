"""The map's figures, one question each: where is each bed within 10 % in peak θ, in edge
uplift, in residual settlement (error maps over FS_v × h/B, one row per soil, one panel per
bed); which calibration to pick for which quantity (the error distributions); how much faster
each bed is than the continuum."""

from __future__ import annotations

import textwrap
import warnings
from pathlib import Path

import numpy as np

from ...framework.study import Axis, write_figure
from .analysis import median_over_motions
from .parts import names, point_array, point_values
from ...beds import BEDS
from .energy import ENERGY_LABELS, ENERGY_SYMBOLS
from .grid import MEASURE_LABELS, MEASURES, SOIL_LABELS

__all__ = ["write_figures"]


def write_figures(ds, analysis, directory: Path) -> list[Path]:
    """The figures of the map dataset ``ds`` (``tree["map"]``) and its ``analysis`` into
    ``directory``."""
    files = [_error_map(ds, directory / f"{m}_error.png", m)
             for m in ("theta", "uplift", "residual_settlement")]
    files.append(_distributions(ds, analysis, directory / "error_distribution.png"))
    files.append(_speed(ds, analysis, directory / "speed.png"))
    return files


#: Panels per row of an error map: the map's ten beds in two rows per soil, so that the
#: figure stays near a page's proportions (it was one strip of 20 panels, 2,756 × 474 px,
#: whose long titles overlapped).
MAP_COLUMNS = 5
#: An error map's width (in): the report's figure width (840 px at 110 dpi is 7.6 in).
MAP_WIDTH_IN = 8.0


def _error_map(ds, path: Path, measure: str) -> Path:
    """|error| over FS_v × h/B: the median over the motions, the worst over the periods and
    intensities; one group of rows per soil, one panel per calibration; contours at 10 and
    20 %."""
    med = median_over_motions(ds)[..., MEASURES.index(measure)]
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a cell whose every run failed: NaN
        worst = np.nanmax(med, axis=(3, 4)) if np.isfinite(med).any() else med[:, :, :, 0, 0]
    x = Axis("fs_v", "FS_v", names(ds, "fs_v"))
    y = Axis("h_over_B", "h/B", names(ds, "h_over_B"))
    beds = names(ds, "calibration")
    groups = [(soil, [(name, worst[s, :, :, c].T) for c, name in enumerate(beds)])
              for s, soil in enumerate(names(ds, "soil"))]
    soils = "; ".join(SOIL_LABELS[s] for s in names(ds, "soil"))
    title = (f"|bed − continuum| / continuum in {MEASURE_LABELS[measure]}: median over "
             f"{ds.sizes['motion']} motions, worst over T and intensity\n({soils})")
    return write_figure(path, error_map_figure(title, x, y, groups))


def error_map_figure(title: str, x: Axis, y: Axis, groups):
    """The figure of an error map: ``groups`` is ``[(soil, [(calibration, errors), ...])]``,
    ``errors`` an array over (y, x) of relative errors. Each soil's panels fill rows of
    :data:`MAP_COLUMNS`, each titled by its bed's code with the soil at the row's left; the
    codes are spelled out under the panels. Panels of |error| (%) on an index grid (log colour
    scale 1–100 %, viridis), each cell annotated, contours at 10 % (white) and 20 % (red)
    where the grid allows them."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    ncols = min(MAP_COLUMNS, max(len(panels) for _, panels in groups))
    layout = [(soil, panels[k:k + ncols]) for soil, panels in groups
              for k in range(0, len(panels), ncols)]
    fig, axes = plt.subplots(len(layout), ncols, squeeze=False, constrained_layout=True,
                             figsize=(MAP_WIDTH_IN, 1.3 + 1.45 * len(layout)))
    norm, image = LogNorm(vmin=1.0, vmax=100.0), None
    for r, (soil, panels) in enumerate(layout):
        for c, (name, errors) in enumerate(panels):
            ax = axes[r][c]
            percent = np.clip(100.0 * np.abs(np.asarray(errors, dtype=float)), 1.0, 100.0)
            image = ax.imshow(percent, norm=norm, cmap="viridis", origin="lower",
                              aspect="auto", interpolation="nearest")
            if min(percent.shape) >= 2 and np.isfinite(percent).any():
                ax.contour(np.arange(percent.shape[1]), np.arange(percent.shape[0]), percent,
                           levels=[10.0, 20.0], colors=["white", "red"], linewidths=1.0)
            for j, i in zip(*np.nonzero(np.isfinite(percent))):
                ax.text(i, j, f"{percent[j, i]:.2g}" if percent[j, i] < 99.5 else "≥100",
                        ha="center", va="center", fontsize=6,
                        color="white" if percent[j, i] < 10 else "black")
            ax.set_title(_short(name), fontsize=8.5)
            ax.set_xticks(range(len(x.values)), [f"{v:g}" for v in x.values], fontsize=7)
            ax.set_yticks(range(len(y.values)), [f"{v:g}" for v in y.values], fontsize=7)
            ax.set_xlabel(x.label, fontsize=7, labelpad=1)
            if c == 0:
                ax.set_ylabel(f"{soil}\n{y.label}", fontsize=8)
        for c in range(len(panels), ncols):
            axes[r][c].set_visible(False)
    if image is not None:
        fig.colorbar(image, ax=axes, label="|relative error| (%)", shrink=0.6)
    fig.suptitle(title, fontsize=9)
    beds = dict.fromkeys(name for _, panels in groups for name, _ in panels)
    fig.supxlabel(textwrap.fill("; ".join(_legend_label(n) for n in beds), 150,
                                  break_on_hyphens=False), fontsize=6.5)
    return fig


def _short(name: str) -> str:
    """A calibration's abbreviation (its registry entry's), or its name."""
    entry = BEDS.get(name)
    return entry.short if entry is not None and entry.short else name


def _legend_label(name: str) -> str:
    entry = BEDS.get(name)
    return f"{_short(name)}: {entry.label}" if entry is not None else name


def _colours(count: int):
    import matplotlib

    cmap = matplotlib.colormaps["tab10" if count <= 10 else "tab20"]
    return [cmap(i) for i in range(count)]


def _distributions(ds, analysis, path: Path) -> Path:
    """Per measure and calibration: the median and 90th percentile of |error| over the map, and
    of the foundation energy E_F over the points whose continuum energy run is stored."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    beds = names(ds, "calibration")
    groups = [(MEASURE_LABELS[m], analysis.pick(m).median, analysis.pick(m).p90)
              for m in MEASURES]
    groups += [(f"{ENERGY_LABELS[e.quantity]}\n({e.points} points)", e.median, e.p90)
               for e in analysis.energy]
    fig, ax = plt.subplots(figsize=(9.5 + 1.2 * len(analysis.energy),
                                    4.2 + 0.16 * ((len(beds) + 1) // 2)),
                           constrained_layout=True)
    width = 0.8 / len(beds)
    x = np.arange(len(groups))
    for c, (name, colour) in enumerate(zip(beds, _colours(len(beds)))):
        med = [100 * g[1][name] for g in groups]
        p90 = [100 * g[2][name] for g in groups]
        ax.bar(x + (c - (len(beds) - 1) / 2) * width, med, width, color=colour,
               label=_legend_label(name))
        ax.plot(x + (c - (len(beds) - 1) / 2) * width, p90, "v", color=colour,
                markeredgecolor="k", markersize=6)
    for level in (10, 20):
        ax.axhline(level, color="k", ls=":", lw=0.8)
    ax.set_yscale("log")
    ax.set_xticks(x, [g[0] for g in groups], fontsize=8)
    ax.set_ylabel("|bed − continuum| / continuum (%)")
    best = ", ".join(f"{MEASURE_LABELS[m]}: {_short(analysis.pick(m).best)}" for m in MEASURES)
    best += "".join(f", {ENERGY_SYMBOLS[e.quantity]}: {_short(e.best)}"
                    for e in analysis.energy if e.best is not None)
    ax.set_title(f"Which calibration for which quantity? Bars: median, ▼: 90th percentile over "
                 f"{analysis.pick(MEASURES[0]).points} points\nbest: {best}", fontsize=8)
    ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.1),
              frameon=False)
    ax.grid(True, which="both", axis="y", alpha=0.3)
    return write_figure(path, fig)


def _speed(ds, analysis, path: Path) -> Path:
    """Per calibration: the continuum's wall time over the bed's, point by point."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    beds = names(ds, "calibration")
    fig, ax = plt.subplots(figsize=(7, 3.6), constrained_layout=True)
    cw = point_values(ds, "continuum_wall_time")
    for c, name in enumerate(beds):
        ratio = (cw / point_array(ds["bed_wall_time"].sel(calibration=name))).ravel()
        ratio = ratio[np.isfinite(ratio)]
        ax.plot(np.full(ratio.size, c), ratio, "o", alpha=0.5)
        ax.plot([c - 0.3, c + 0.3], [analysis.speed.median[name]] * 2, "k-")
    ax.axhline(1000, color="r", ls=":", label="1000 ×")
    ax.set_yscale("log")
    ax.set_xticks(range(len(beds)), [_short(n) for n in beds], fontsize=7)
    ax.set_ylabel("continuum wall time / bed wall time")
    ax.set_title(f"How much faster is each bed? (median: line; continuum runs: median "
                 f"{analysis.speed.continuum_median:.3g} s)", fontsize=8)
    ax.legend(fontsize=7)
    ax.grid(True, which="both", axis="y", alpha=0.3)
    return write_figure(path, fig)
