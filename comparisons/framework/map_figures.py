"""Error maps that print readably: one question per figure at page width.

An error map is |relative error| (%) over two parameters of a study (:class:`.study.Axis`),
drawn on an index grid (uneven parameter steps read as equal steps; ticks carry the values)
as vector cells. The colour scale is viridis (perceptually uniform, ordered in lightness, so it
reads in greyscale and with the common colour-vision deficiencies) on a logarithmic scale from
0.1 % to 100 %: the sign of the error is not what a map asks, so no diverging scale. The 10 %
and 20 % contours (and any other levels asked for) are white lines with a black halo, solid,
dashed and dotted in that order, so they show on the dark and the light end of the scale and
without colour.

:func:`layout_maps` answers one question — where does each layout stay within the levels of
the reference? — with one panel per layout in a row. :func:`dense_maps` is the all-panel
grid (a row per measure) that the report keeps behind an expandable section.
:func:`share_within` and :func:`worst_cell` are the numbers a caption states.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .figure_record import page_figure
from .study import Axis

__all__ = ["LEVELS", "MAX_HEIGHT_IN", "share_within", "worst_cell", "layout_maps", "dense_maps",
           "rows_per_figure"]

#: Contour levels (fractions) drawn on every error map.
LEVELS = (0.10, 0.20)
_LOW, _HIGH = 0.1, 100.0  # the colour scale (%)
_STYLES = ("solid", "dashed", "dotted", "dashdot")


def share_within(errors: np.ndarray, level: float) -> float:
    """Fraction of the map's finite cells with |error| ≤ ``level`` (NaN if none is finite)."""
    e = np.abs(np.asarray(errors, dtype=float))
    finite = np.isfinite(e)
    return float(np.mean(e[finite] <= level)) if finite.any() else float("nan")


def worst_cell(errors: np.ndarray, x: Axis, y: Axis) -> tuple[float, str]:
    """The largest |error| of a map and where it is ("h/b = 4, intensity = 6 × a_up")."""
    e = np.abs(np.asarray(errors, dtype=float))
    if not np.isfinite(e).any():
        return float("nan"), "nowhere (every run failed)"
    iy, ix = np.unravel_index(np.nanargmax(e), e.shape)
    return float(e[iy, ix]), f"{x.label} = {x.format(x.values[ix])}, " \
                             f"{y.label} = {y.format(y.values[iy])}"


def _levels(levels: Sequence[float]) -> tuple[float, ...]:
    return tuple(sorted(set(LEVELS) | set(levels)))


def _panel(ax, errors: np.ndarray, x: Axis, y: Axis, levels, *, left: bool, bottom: bool):
    import matplotlib.patheffects as pe
    from matplotlib.colors import LogNorm

    percent = np.clip(100.0 * np.abs(np.asarray(errors, dtype=float)), _LOW, _HIGH)
    ny, nx = percent.shape
    mesh = ax.pcolormesh(np.arange(nx + 1) - 0.5, np.arange(ny + 1) - 0.5,
                         np.ma.masked_invalid(percent), norm=LogNorm(_LOW, _HIGH),
                         cmap="viridis", shading="flat")
    ax.set_facecolor("0.85")  # failed runs (NaN) show as grey
    if nx >= 2 and ny >= 2 and np.isfinite(percent).sum() >= 4:
        filled = np.where(np.isfinite(percent), percent, _HIGH)
        for level, style in zip(levels, _STYLES):
            if filled.min() < 100 * level < filled.max():
                cs = ax.contour(np.arange(nx), np.arange(ny), filled, levels=[100 * level],
                                colors="white", linewidths=1.4, linestyles=style)
                cs.set(path_effects=[pe.withStroke(linewidth=2.8, foreground="black")])
    ax.set_xticks(range(nx), [x.format(v).replace(x.unit, "") if bottom else "" for v in
                              x.values], rotation=90 if nx > 4 else 0)
    ax.set_yticks(range(ny), [y.format(v).replace(y.unit, "") if left else "" for v in y.values])
    ax.set_xlim(-0.5, nx - 0.5)
    ax.set_ylim(-0.5, ny - 0.5)
    if bottom:
        ax.set_xlabel(f"{x.label}{' (' + x.unit.strip() + ')' if x.unit.strip() else ''}")
    if left:
        ax.set_ylabel(f"{y.label}{' (' + y.unit.strip() + ')' if y.unit.strip() else ''}")
    return mesh


def _legend(fig, axes, mesh, levels, shrink: float = 0.95) -> None:
    import matplotlib.patheffects as pe
    from matplotlib.lines import Line2D

    fig.colorbar(mesh, ax=axes, label="|relative error| (%)", shrink=shrink)
    handles = [Line2D([], [], color="white", lw=1.4, ls=style,
                      path_effects=[pe.withStroke(linewidth=2.8, foreground="black")],
                      label=f"{100 * level:g} % contour")
               for level, style in zip(levels, _STYLES)]
    fig.legend(handles=handles, loc="outside lower center", ncols=len(handles), frameon=False)


def layout_maps(x: Axis, y: Axis, panels: Sequence[tuple[str, np.ndarray]],
                levels: Sequence[float] = LEVELS):
    """One row of error maps, one panel per (title, errors (len(y), len(x)) fractions) with a
    shared colour bar and the contour legend; the figure (call inside
    :func:`.figure_record.print_style`)."""
    levels = _levels(levels)
    height = 1.3 + 0.22 * max(len(y.values), 4) + (0.35 if len(x.values) > 4 else 0.0)
    fig, axes = page_figure(height, 1, len(panels), squeeze=False)
    mesh = None
    for k, (name, errors) in enumerate(panels):
        ax = axes[0][k]
        mesh = _panel(ax, errors, x, y, levels, left=k == 0, bottom=True)
        ax.set_title(name)
    _legend(fig, axes, mesh, levels)
    return fig


#: Tallest figure (in): fits the printed text height of Letter (11 in − 2 × 14 mm = 9.9 in)
#: and A4 with its caption, so no figure is scaled down (and its text below 9 pt) in print.
MAX_HEIGHT_IN = 8.6


def _row_height(y: Axis) -> float:
    return 0.75 + 0.16 * max(len(y.values), 4)


def rows_per_figure(y: Axis) -> int:
    """How many rows of :func:`dense_maps` panels fit in :data:`MAX_HEIGHT_IN`."""
    return max(1, int((MAX_HEIGHT_IN - 0.9) // _row_height(y)))


def dense_maps(x: Axis, y: Axis, columns: Sequence[str],
               rows: Sequence[tuple[str, Sequence[np.ndarray]]],
               levels: Sequence[float] = LEVELS):
    """Every panel: one column per name of ``columns`` (titled on the top row), one row per
    (row name, errors per column) of ``rows`` (the row name above the y label); page width,
    tall (give it at most :func:`rows_per_figure` rows to stay within
    :data:`MAX_HEIGHT_IN`); the figure."""
    levels = _levels(levels)
    ncols = len(columns)
    fig, axes = page_figure(0.9 + _row_height(y) * len(rows), len(rows), ncols, squeeze=False)
    mesh = None
    for r, (row_name, panels) in enumerate(rows):
        for c, errors in enumerate(panels):
            ax = axes[r][c]
            mesh = _panel(ax, errors, x, y, levels, left=c == 0, bottom=r == len(rows) - 1)
            if r == 0:
                ax.set_title(columns[c])
            if c == 0:
                ax.set_ylabel(f"{row_name}\n{ax.get_ylabel()}")
    _legend(fig, axes, mesh, levels, shrink=0.35)
    return fig
