"""The raster page of the pictures a run writes (PNG, GIF frames), drawn with Pillow alone:
what it shows is :mod:`~upliftlab.meshes.render`'s docstring, laid out as the matplotlib
:class:`~upliftlab.meshes.page.Page` (same :func:`~upliftlab.meshes.page.layout`).

**Built once.** A :class:`Sheet` draws the unchanging part of the page once: the soil panel's
ticks and y label, the colour bar (each pixel row coloured by
:func:`~upliftlab.meshes.colours.colours_of` at its value: the same table and norm as the
cells, so the two cannot disagree) with its decade ticks and label, the contact panel's
footing band, ticks, labels (pressure left, gap right) and the legend and magnification note
as small images. **Per frame** (:meth:`Sheet.show`) it draws on a copy: the soil's sub-cells
(filled polygons, one colour per element, no anti-aliasing), the element outlines, the footing
block, the note and the frame; the contact pressure (filled, translucent blue over the band),
the grid, the pressure and gap lines, the legend; and the title. Sub-cells that no frame can
bring into the window are left out (:func:`~upliftlab.meshes.page.visible_cells`).
"""

from __future__ import annotations

import numpy as np

from .colours import TABLE, colours_of, to_bytes
from .frames import Frame, SubMesh, View
from .page import (FIGURE_WIDTH_IN, OUTLINE_GREY, _unit, colour_range, footing_outline,
                   layout, visible_cells)
from .raster import (GREY, Panel, grid, pixels_of, text, text_box, tick_label, ticks,
                     turned_text)

__all__ = ["Sheet", "BLUE", "RED", "FOOTING", "FILL", "FILL_ON_WHITE"]

#: Accent colours (RGB in [0, 1]): pressure blue, gap red, the footing block, and the
#: pressure fill (blue at α 0.35 over the footing band's grey 0.93, and over white).
BLUE, RED, FOOTING = (0.122, 0.467, 0.706), (0.839, 0.153, 0.157), (0.55, 0.6, 0.7)
BAND = 0.93
FILL = tuple(0.35 * c + 0.65 * BAND for c in BLUE)
FILL_ON_WHITE = tuple(0.35 * c + 0.65 for c in BLUE)
_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _rgb(colour) -> tuple[int, int, int]:
    return tuple(int(v) for v in to_bytes(colour))


def _panel(rect, size, xlim, ylim) -> Panel:
    """The :class:`Panel` of a rectangle (figure fractions) on a page ``size`` (w, h)."""
    w, h = size
    left, bottom, width, height = rect
    return Panel(int(round(left * w)), int(round((1 - bottom - height) * h)),
                 int(round((left + width) * w)), int(round((1 - bottom) * h)), xlim, ylim)


class Sheet:
    """The raster page of a run's frames (module docstring): ``sub`` the drawn sub-mesh,
    ``view`` the run's fixed view, ``reach`` the largest magnified nodal displacement of any
    frame (length), ``dpi`` and ``width_in`` the raster size."""

    def __init__(self, sub: SubMesh, view: View, reach: float, *, dpi: int = 100,
                 width_in: float = FIGURE_WIDTH_IN):
        from PIL import Image, ImageDraw

        self.sub, self.view, self.dpi = sub, view, dpi
        height, soil, contact, bar = layout(width_in, view)
        self.size = (int(round(width_in * dpi)), int(round(height * dpi)))
        xmin, xmax, ymin, ymax = view.window
        self.soil = _panel(soil, self.size, (xmin, xmax), (ymin, ymax))
        self.pressure_top = 1.1 * view.pressure_max if view.pressure_max > 0 else 1.0
        self.gap_top = 1.1 * view.gap_max if view.gap_max > 0 else 1.0
        self.contact = _panel(contact, self.size, (xmin, xmax), (0.0, self.pressure_top))
        self.bar = _panel(bar, self.size, (0.0, 1.0), (0.0, 1.0))
        self.rows = visible_cells(sub.points, sub.cells, view.window, reach)
        self.cells = sub.cells[self.rows]
        self.edges = sub.edges[visible_cells(sub.points, sub.edges, view.window, reach)]
        self.floor, self.top = colour_range(view)
        self.px = lambda points: pixels_of(points, dpi)
        self.image = Image.new("RGB", self.size, GREY["white"])
        draw = ImageDraw.Draw(self.image)
        self._soil_axes(draw)
        self._colour_bar(draw)
        self._contact_axes(draw)
        self.background = self.image.copy()
        self.note = text_box([f"deformation × {view.scale:g}"], self.px(10), self.px(3))
        self.legend = text_box(["pressure p", "gap g"], self.px(9), self.px(3),
                               keys=self._keys, key_width=self.px(20))

    # -- the unchanging part ---------------------------------------------------------------
    def _ticks_y(self, draw, panel: Panel, lo: float, hi: float, *, right=False,
                 scale=1.0) -> None:
        """Ticks and labels (values / ``scale``) of [lo, hi] on the panel's left or right."""
        values = ticks(lo, hi)
        length, size = self.px(3.5), self.px(10)
        x = panel.right if right else panel.left
        sign = 1 if right else -1
        for v in values:
            row = panel.top + (hi - v) / (hi - lo) * (panel.bottom - panel.top)
            draw.line([(x, row), (x + sign * length, row)], fill=GREY["ink"], width=1)
            text(draw, (x + sign * (length + self.px(3.5)), row),
                 tick_label(v / scale, values / scale), size,
                 anchor="lm" if right else "rm")

    def _ticks_x(self, draw, panel: Panel, *, labels: bool) -> None:
        lo, hi = panel.xlim
        values = ticks(lo, hi)
        length, size = self.px(3.5), self.px(10)
        for v in values:
            col = panel.left + (v - lo) / (hi - lo) * (panel.right - panel.left)
            draw.line([(col, panel.bottom), (col, panel.bottom + length)], fill=GREY["ink"])
            if labels:
                text(draw, (col, panel.bottom + length + self.px(3.5)),
                     tick_label(v, values), size, anchor="ma")

    def _soil_axes(self, draw) -> None:
        panel = self.soil
        self._ticks_y(draw, panel, *panel.ylim)
        self._ticks_x(draw, panel, labels=False)
        turned_text(self.image, (panel.left - self.px(48), (panel.top + panel.bottom) / 2),
                    f"y{_unit(self.view.length_unit)}", self.px(10))

    def _colour_bar(self, draw) -> None:
        from PIL import Image

        bar, floor, top = self.bar, self.floor, self.top
        w, h = bar.size
        s = 1.0 - (np.arange(h) + 0.5) / h  # each pixel row's place on the scale
        values = floor * (top / floor) ** s if floor > 0.0 else top * s
        column = to_bytes(colours_of(values, floor, top))  # (h, 3)
        self.image.paste(Image.fromarray(np.repeat(column[:, None], w, axis=1)),
                         (bar.left, bar.top))
        if floor > 0.0:  # extend="min": a triangle of the palest colour below the bar
            tip = bar.bottom + int(round(0.05 * h))
            draw.polygon([(bar.left, bar.bottom), (bar.right - 1, bar.bottom),
                          ((bar.left + bar.right - 1) / 2, tip)], fill=_rgb(TABLE[0]),
                         outline=GREY["ink"])
            marks = [10.0 ** k for k in range(int(np.ceil(np.log10(floor) - 1e-9)),
                                              int(np.floor(np.log10(top) + 1e-9)) + 1)]
            words = [f"10{str(int(round(np.log10(m)))).translate(_SUPERSCRIPT)}"
                     for m in marks]
            places = [np.log10(m / floor) / np.log10(top / floor) for m in marks]
        else:
            marks = ticks(0.0, top)
            words, places = [tick_label(m, marks) for m in marks], list(marks / top)
        draw.rectangle([bar.left, bar.top, bar.right - 1, bar.bottom - 1], outline=GREY["ink"])
        for word, place in zip(words, places):
            row = bar.bottom - place * h
            draw.line([(bar.right, row), (bar.right + self.px(3.5), row)], fill=GREY["ink"])
            text(draw, (bar.right + self.px(7), row), word, self.px(10), anchor="lm")
        label = ("plastic strain ε̄ᵖ [–]" + (f"\n(log; < {floor:.1e}: palest)" if floor
                                             else "\n(none: elastic)"))
        turned_text(self.image, (bar.right + self.px(60), (bar.top + bar.bottom) / 2), label,
                    self.px(9))

    def _contact_axes(self, draw) -> None:
        panel, view = self.contact, self.view
        band = panel.xy(np.array([-0.5, 0.5]) * view.footing_width, [0.0, 0.0])[:, 0]
        draw.rectangle([panel.left + band[0], panel.top, panel.left + band[1],
                        panel.bottom - 1], fill=_rgb((BAND,) * 3))
        across, up = ticks(*panel.xlim), ticks(0.0, self.pressure_top)[1:]
        grid(self.image, panel, panel.xy(across, 0.0 * across)[:, 0],
             panel.xy(0.0 * up, up)[:, 1])
        self._ticks_x(draw, panel, labels=True)
        self._ticks_y(draw, panel, 0.0, self.pressure_top)
        gap_power = int(np.floor(np.log10(np.max(ticks(0.0, self.gap_top)))))
        scale = 10.0 ** gap_power if not -2 < gap_power < 3 else 1.0  # matplotlib's rule
        self._ticks_y(draw, panel, 0.0, self.gap_top, right=True, scale=scale)
        if scale != 1.0:
            text(draw, (panel.right, panel.top - self.px(3)), f"1e{gap_power}".replace(
                "-", "−"), self.px(10), anchor="rd")
        middle = (panel.top + panel.bottom) / 2
        text(draw, ((panel.left + panel.right) / 2, panel.bottom + self.px(24)),
             f"x{_unit(view.length_unit)}", self.px(10), anchor="ma")
        turned_text(self.image, (panel.left - self.px(48), middle),
                    f"contact pressure p{_unit(view.stress_unit)}", self.px(10),
                    fill=_rgb(BLUE))
        turned_text(self.image, (panel.right + self.px(50), middle),
                    f"gap g{_unit(view.length_unit)}", self.px(10), fill=_rgb(RED))

    def _keys(self, draw, k: int, left: int, middle: float, right: int, size: int) -> None:
        """The legend's key ``k``: the pressure fill, the gap line."""
        if k == 0:
            draw.rectangle([left, middle - size / 3, right, middle + size / 3],
                           fill=_rgb(FILL_ON_WHITE), outline=_rgb(BLUE))
        else:
            draw.line([(left, middle), (right, middle)], fill=_rgb(RED), width=self.px(1.8))

    # -- per frame ---------------------------------------------------------------------------
    def show(self, frame: Frame) -> None:
        """Draw ``frame`` on a copy of the unchanging page."""
        from PIL import ImageDraw

        image = self.background.copy()
        draw = ImageDraw.Draw(image)
        self._soil_frame(image, frame)
        self._contact_frame(image, draw, frame)
        view = self.view
        text(draw, (self.size[0] / 2, self.px(0.12 * 72)),
             f"{view.title}: {frame.label}\nθ = {frame.footing[2]:.3g} rad,  M = "
             f"{frame.M:.4g}{_unit(view.moment_unit)},  N = {frame.N:.4g}"
             f"{_unit(view.force_unit)},  contact "
             f"{frame.contact_length / view.footing_width:.0%} of B", self.px(11),
             anchor="ma", align="center")
        self.image = image

    def _soil_frame(self, image, frame: Frame) -> None:
        from PIL import Image, ImageDraw

        panel, view = self.soil, self.view
        soil = Image.new("RGB", panel.size, GREY["white"])
        draw = ImageDraw.Draw(soil)
        moved = self.sub.points + view.scale * frame.displacement
        xy = panel.xy(moved[:, 0], moved[:, 1])
        values = self.sub.cell_values(frame.plastic_strain)[self.rows]
        colours = map(tuple, to_bytes(colours_of(values, self.floor, self.top)).tolist())
        for corners, colour in zip(xy[self.cells].reshape(len(self.cells), -1).tolist(),
                                   colours):
            draw.polygon(corners, fill=colour)
        grey = _rgb((OUTLINE_GREY,) * 3)
        for segment in xy[self.edges].reshape(len(self.edges), -1).tolist():
            draw.line(segment, fill=grey, width=1)
        outline = footing_outline(frame, view)
        draw.polygon(panel.xy(outline[:, 0], outline[:, 1]).ravel().tolist(),
                     fill=_rgb(FOOTING), outline=GREY["ink"], width=self.px(1.5))
        w, h = panel.size
        soil.paste(self.note, (int(0.01 * w), int(0.98 * h) - self.note.height))
        draw.rectangle([0, 0, w - 1, h - 1], outline=GREY["ink"])
        image.paste(soil, (panel.left, panel.top))

    def _contact_frame(self, image, draw, frame: Frame) -> None:
        from PIL import Image, ImageDraw

        panel = self.contact
        x, p = np.asarray(frame.x, float), np.asarray(frame.pressure, float)
        corner = np.array([panel.left, panel.top])
        fill = np.vstack(([x[0], 0.0], np.column_stack((x, p)), [x[-1], 0.0]))
        xy = panel.xy(fill[:, 0], fill[:, 1]) + corner
        lo, hi = np.floor(xy.min(axis=0)).astype(int), np.ceil(xy.max(axis=0)).astype(int) + 1
        mask = Image.new("L", tuple(hi - lo), 0)  # α 0.35 over the band and the grid
        ImageDraw.Draw(mask).polygon((xy - lo).ravel().tolist(), fill=int(0.35 * 255))
        image.paste(_rgb(BLUE), (*lo, *hi), mask)
        draw.line((panel.xy(x, p) + corner).ravel().tolist(), fill=_rgb(BLUE),
                  width=self.px(1.5))
        gap = np.asarray(frame.gap, float) * (self.pressure_top / self.gap_top)
        draw.line((panel.xy(x, gap) + corner).ravel().tolist(), fill=_rgb(RED),
                  width=self.px(1.8))
        image.paste(self.legend, (panel.left + self.px(5), panel.top + self.px(5)))
        draw.rectangle([panel.left, panel.top, panel.right - 1, panel.bottom - 1],
                       outline=GREY["ink"])

    def picture(self):
        """The Pillow RGB image of the page as :meth:`show` left it (not to be changed)."""
        return self.image

    def pixels(self) -> np.ndarray:
        """The RGB page (h, w, 3) as :meth:`show` left it."""
        return np.asarray(self.image)
