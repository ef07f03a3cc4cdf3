"""The Winkler map's error maps stay readable: the map's twenty panels (two soils × ten beds)
are laid out as a grid near a page's proportions, not one strip (it was 2,756 × 474 px with
overlapping titles), and no title or label of the figure overlaps another.

Reference: the text's bounding boxes as matplotlib's own renderer draws them (Agg, the
backend that writes the PNG), compared pairwise."""

from __future__ import annotations

import itertools

import numpy as np

from upliftlab.comparisons.beds import BEDS
from upliftlab.comparisons.framework.study import Axis
from upliftlab.comparisons.studies.winkler_map.figures import MAP_COLUMNS, error_map_figure

#: The resolution the studies write at (comparisons/framework/study.py, write_figure).
DPI = 110


def _figure():
    """An error map of the full map's shape: 2 soils × every registered bed over 4 FS_v × 3
    h/B, errors from 0 to 150 % (cells annotated, some "≥100")."""
    rng = np.random.default_rng(7)
    x = Axis("fs_v", "FS_v", [2.0, 3.0, 5.0, 10.0])
    y = Axis("h_over_B", "h/B", [1.0, 1.5, 2.5])
    groups = [(soil, [(name, rng.uniform(0.0, 1.5, (3, 4))) for name in BEDS])
              for soil in ("clay", "sand")]
    title = ("|bed − continuum| / continuum in peak θ: median over 13 motions, worst over T "
             "and intensity\n(clay: Tresca, c_u = 50 kPa; sand: Mohr–Coulomb, φ = 35°)")
    return error_map_figure(title, x, y, groups), len(groups) * len(BEDS)


def _texts(fig):
    """(kind, text, bounding box in px) of every visible title and label, as drawn (tick
    labels of ticks inside their axis' limits: a log colour bar keeps labels of ticks beyond
    its range, which are not drawn)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    out = [("suptitle", fig._suptitle), ("supxlabel", fig._supxlabel)]
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        out += [("title", ax.title), ("xlabel", ax.xaxis.label), ("ylabel", ax.yaxis.label)]
        (x0, x1), (y0, y1) = sorted(ax.get_xbound()), sorted(ax.get_ybound())
        out += [("tick", t) for t in ax.get_xticklabels() if x0 <= t.get_position()[0] <= x1]
        out += [("tick", t) for t in ax.get_yticklabels() if y0 <= t.get_position()[1] <= y1]
    return [(kind, t.get_text(), t.get_window_extent(renderer)) for kind, t in out
            if t is not None and t.get_visible() and t.get_text()]


def test_the_error_map_is_a_grid_of_page_proportions():
    # Every panel is drawn, each soil's in rows of at most MAP_COLUMNS; the figure is at most
    # 1,000 px wide at the studies' 110 dpi, and between 0.6 and 1.6 times as tall as wide (the
    # strip was 0.17).
    import matplotlib.pyplot as plt

    fig, panels = _figure()
    try:
        heat = [ax for ax in fig.axes if ax.get_visible() and ax.images
                and ax.get_label() != "<colorbar>"]
        assert len(heat) == panels
        rows = {round(ax.get_position().y0, 3) for ax in heat}
        assert len(rows) == 2 * -(-len(BEDS) // MAP_COLUMNS)  # each soil's beds from a new row
        width, height = fig.get_size_inches() * DPI
        assert width <= 1000 and 0.6 <= height / width <= 1.6, (width, height)
    finally:
        plt.close(fig)


def test_no_title_or_label_of_the_error_map_overlaps_another():
    # Titles (the bed's code), axis labels, tick labels, the figure's title and its legend of
    # codes: no two bounding boxes intersect (1 px of slack), and every one lies inside the
    # figure. Each panel's title is the bed's short code, and every code is spelled out.
    import matplotlib.pyplot as plt

    fig, _ = _figure()
    try:
        texts = _texts(fig)
        width, height = fig.canvas.get_width_height()
        titles = [text for kind, text, _ in texts if kind == "title"]
        assert set(titles) == {entry.short for entry in BEDS.values()}
        legend = next(text for kind, text, _ in texts if kind == "supxlabel")
        for entry in BEDS.values():
            assert f"{entry.short}: {entry.label}" in " ".join(legend.split()), entry.short
        for kind, text, box in texts:
            assert box.x0 >= -1 and box.y0 >= -1 and box.x1 <= width + 1 and \
                box.y1 <= height + 1, (kind, text)
        clashes = [(a[:2], b[:2]) for a, b in itertools.combinations(texts, 2)
                   if a[2].x0 < b[2].x1 - 1 and b[2].x0 < a[2].x1 - 1
                   and a[2].y0 < b[2].y1 - 1 and b[2].y0 < a[2].y1 - 1]
        assert clashes == []
    finally:
        plt.close(fig)
