"""The report's figures, one by one: printed size and text size (:mod:`comparisons.figure_record`),
the error maps' colour scale and contours (:mod:`comparisons.map_figures`), the numbers their
captions state, the frame subset of the frame slider and the print helper's page size.

References: the printed text width of A4 (210 mm) and Letter (8.5 in) less the report's 14 mm
print margins, 7.17 in and 7.40 in (the figures' 6.5 in must fit both); 9 pt as the smallest
readable printed text (the issue's requirement); hand counts on small arrays for the caption
numbers; matplotlib's own records of what it drew (the Figure's size and Text artists, the
contour sets' levels, the colour map's name) and the SVG file's own width and font sizes.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

import matplotlib
matplotlib.use("Agg")

from upliftlab.comparisons.framework import figure_record as fr  # noqa: E402
from upliftlab.comparisons.framework import map_figures as mf  # noqa: E402
from upliftlab.comparisons.report.printing import PAPERS, with_page_size  # noqa: E402
from upliftlab.comparisons.framework.study import Axis  # noqa: E402
from upliftlab.checks import InputError  # noqa: E402
from upliftlab.meshes.render import frame_subset  # noqa: E402

MARGIN_IN = 14 / 25.4  # the report's @page margin


def test_page_width_fits_a4_and_letter():
    # A4 text width 210 mm − 2 × 14 mm = 7.17 in, Letter 8.5 in − 2 × 14 mm = 7.40 in.
    for paper, (_, (width_pt, _)) in PAPERS.items():
        assert fr.PAGE_WIDTH_IN <= width_pt / 72.0 - 2 * MARGIN_IN, paper
    assert PAPERS["A4"][1] == pytest.approx((595.28, 841.89), abs=0.01)  # 210 × 297 mm
    assert PAPERS["Letter"][1] == (612.0, 792.0)  # 8.5 × 11 in


def _svg_sizes(path) -> tuple[float, list[float]]:
    text = path.read_text()
    width = float(re.search(r'<svg[^>]*\bwidth="([\d.]+)pt"', text).group(1))
    return width, [float(s) for s in re.findall(r"font-size:\s*([\d.]+)px", text)]


def test_save_writes_svg_png_and_caption_and_refuses_unreadable_figures(tmp_path):
    caption = fr.Caption("What is it?", "A line (m against s).", "It rises by 2 m.")
    with fr.print_style():
        fig, ax = fr.page_figure(3.0)
        ax.loglog([1e-3, 1, 100], [0.1, 1, 2])  # log ticks: plain labels, no 70 % exponents
        ax.set_xlabel("t (s)")
        ax.set_ylabel("x (m)")
        ax.set_title("a line")
    record, svg, png = fr.save(tmp_path / "line.png", fig, caption)
    assert record.name == "line.figure.json" and svg.suffix == ".svg" and png.is_file()
    assert fr.read(record) == fr.FigureRecord(svg, png, caption)
    width, sizes = _svg_sizes(svg)
    # the SVG's user unit is the point: 6.5 in = 468 pt, text kept as text at ≥ 9 pt
    assert width == pytest.approx(72 * fr.PAGE_WIDTH_IN, abs=0.01)
    assert sizes and min(sizes) >= fr.MIN_FONT_PT
    # 8 pt text or a figure wider than the page is refused, naming what is wrong
    with fr.print_style():
        fig, ax = fr.page_figure(3.0)
        ax.set_title("too small", fontsize=8)
    with pytest.raises(ValueError, match="below 9 pt: 'too small' 8 pt"):
        fr.save(tmp_path / "small.png", fig, caption)
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(7.0, 3.0))
    with pytest.raises(ValueError, match="7.00 in wide"):
        fr.save(tmp_path / "wide.png", fig, caption)
    assert not (tmp_path / "small.svg").exists() and not (tmp_path / "wide.svg").exists()


def test_share_within_and_worst_cell_by_hand():
    # 6 cells, one NaN (a failed run): |e| ≤ 0.10 in 3 of the 5 finite ones.
    errors = np.array([[0.05, -0.10, 0.3], [np.nan, 0.02, -0.8]])
    assert mf.share_within(errors, 0.10) == pytest.approx(3 / 5, abs=1e-15)
    assert mf.share_within(errors, 0.20) == pytest.approx(3 / 5, abs=1e-15)
    x = Axis("h_over_b", "h/b", (2.0, 4.0, 6.0))
    y = Axis("intensity", "intensity", (0.5, 1.0), " × a_up")
    value, where = mf.worst_cell(errors, x, y)
    assert value == pytest.approx(0.8, abs=1e-15)
    assert where == "h/b = 6, intensity = 1 × a_up"
    assert np.isnan(mf.share_within(np.full((2, 2), np.nan), 0.1))


def test_error_maps_are_viridis_with_10_and_20_percent_contours_and_readable():
    # An error field rising across the map crosses both 10 % and 20 %: each panel carries one
    # contour set per level, the scale is viridis from 0.1 % to 100 %, and the figure is the
    # page width with no text below 9 pt.
    from matplotlib.contour import ContourSet

    x = Axis("h_over_b", "h/b", (1.5, 2.0, 2.8, 4.0, 6.0))
    y = Axis("intensity", "intensity", (0.5, 1.0, 2.0, 4.0), " × a_up")
    field = np.outer(np.linspace(0.01, 0.2, 4), np.linspace(1.0, 3.0, 5))
    with fr.print_style():
        fig = mf.layout_maps(x, y, [("edges", field), ("equivalent", field / 2)])
    assert tuple(fig.get_size_inches()) == pytest.approx((fr.PAGE_WIDTH_IN, fig.get_size_inches()[1]))
    assert fr.small_text(fig) == []
    axes = [a for a in fig.axes if a.get_title() in ("edges", "equivalent")]
    for ax in axes:
        meshes = [c for c in ax.collections if hasattr(c, "get_cmap") and
                  not isinstance(c, ContourSet)]
        assert meshes[0].get_cmap().name == "viridis"
        assert meshes[0].norm.vmin == 0.1 and meshes[0].norm.vmax == 100.0
    levels = sorted(float(c.levels[0]) for c in axes[0].collections
                    if isinstance(c, ContourSet))
    assert levels == [10.0, 20.0]


def test_dense_maps_keep_every_panel_at_page_width():
    x = Axis("a", "a", (1.0, 2.0, 3.0))
    y = Axis("b", "b", (1.0, 2.0))
    rows = [(f"measure {k}", [np.full((2, 3), 0.01 * (k + 1))] * 3) for k in range(6)]
    with fr.print_style():
        fig = mf.dense_maps(x, y, ("edges", "equivalent", "calibrated"), rows)
    assert fig.get_size_inches()[0] == pytest.approx(fr.PAGE_WIDTH_IN)
    assert fr.small_text(fig) == []
    assert sum(1 for a in fig.axes if a.get_visible() and a.get_label() != "<colorbar>") >= 18


def test_dense_maps_are_split_to_fit_a_printed_page():
    # With the full grid's 7 intensities, the six measures do not fit one page: each figure
    # gets at most rows_per_figure rows and stays within MAX_HEIGHT_IN (8.6 in; Letter's text
    # height is 11 in − 2 × 14 mm = 9.9 in).
    x = Axis("h_over_b", "h/b", (1.5, 2.0, 2.8, 4.0, 6.0))
    y = Axis("intensity", "intensity", (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0), " × a_up")
    per = mf.rows_per_figure(y)
    assert 1 <= per < 6
    assert mf.MAX_HEIGHT_IN <= 11 - 2 * MARGIN_IN - 1.0
    rows = [(f"measure {k}", [np.full((7, 5), 0.05)] * 3) for k in range(per)]
    with fr.print_style():
        fig = mf.dense_maps(x, y, ("edges", "equivalent", "calibrated"), rows)
    assert fig.get_size_inches()[1] <= mf.MAX_HEIGHT_IN
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_frame_subset_keeps_first_and_last():
    # Evenly spaced indices round(k (n − 1)/(m − 1)), k = 0…m−1.
    assert frame_subset(5, 24) == [0, 1, 2, 3, 4]
    assert frame_subset(41, 5) == [0, 10, 20, 30, 40]
    assert frame_subset(100, 16)[0] == 0 and frame_subset(100, 16)[-1] == 99
    assert len(frame_subset(100, 16)) == 16
    with pytest.raises(InputError, match="limit = 1"):
        frame_subset(10, 1)


def test_page_size_rule_is_added_to_the_head():
    page = "<html><head><title>x</title></head><body></body></html>"
    assert "<style>@page{size:A4}</style></head>" in with_page_size(page, "A4")
    assert "@page{size:letter}" in with_page_size(page, "Letter")
    with pytest.raises(InputError, match="paper = 'A3'"):
        with_page_size(page, "A3")


def test_animation_record_round_trips(tmp_path):
    frames = []
    for k in range(3):
        p = tmp_path / "frames" / f"frame_{k:03d}.png"
        p.parent.mkdir(exist_ok=True)
        p.write_bytes(b"\x89PNG")
        frames.append((p, f"step {k}"))
    caption = fr.Caption("How?", "Frames.", "Contact 41 %.")
    record = fr.read(fr.save_frames(tmp_path / "animation.png", frames, caption))
    assert record.frames == tuple(frames) and record.image == frames[-1][0]
    data = json.loads((tmp_path / "animation.figure.json").read_text())
    assert data["frames"][0] == {"image": "frames/frame_000.png", "label": "step 0"}
