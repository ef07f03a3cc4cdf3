"""Drawing primitives of the raster pages (:mod:`~upliftlab.meshes.sheet`), on Pillow alone:
a panel's data-to-pixel map, tick positions and labels, fonts, and text (also turned by 90°).

**Sizes** follow matplotlib's defaults so that the raster reads like the figure of
:mod:`~upliftlab.meshes.page`: a size in points is ``points × dpi / 72`` pixels; the font is
DejaVu Sans (the copy matplotlib installs, found without importing matplotlib, else the
system's, else Pillow's own).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Panel", "font", "pixels_of", "ticks", "tick_label", "text", "turned_text",
           "text_box", "grid", "GREY"]

#: Grey levels (RGB bytes) of the raster: text and frames, the page.
GREY = {"ink": (0, 0, 0), "white": (255, 255, 255)}


def pixels_of(points: float, dpi: float) -> int:
    """A length in points as whole pixels (at least 1)."""
    return max(1, int(round(points * dpi / 72.0)))


@functools.lru_cache(maxsize=None)
def _font_file() -> str | None:
    import importlib.util
    from pathlib import Path

    spec = importlib.util.find_spec("matplotlib")
    places = [Path(p) / "mpl-data" / "fonts" / "ttf" for p in
              (spec.submodule_search_locations or [])] if spec else []
    places.append(Path("/usr/share/fonts/truetype/dejavu"))
    for place in places:
        if (place / "DejaVuSans.ttf").is_file():
            return str(place / "DejaVuSans.ttf")
    return None


@functools.lru_cache(maxsize=None)
def font(size_px: int):
    """DejaVu Sans (module docstring) at ``size_px`` pixels."""
    from PIL import ImageFont

    name = _font_file()
    return (ImageFont.truetype(name, size_px) if name
            else ImageFont.load_default(size=size_px))


@dataclass(frozen=True)
class Panel:
    """A panel's pixel box (``left``, ``top``, ``right``, ``bottom``; rows grow downwards)
    showing data ``xlim`` × ``ylim``."""

    left: int
    top: int
    right: int
    bottom: int
    xlim: tuple[float, float]
    ylim: tuple[float, float]

    @property
    def size(self) -> tuple[int, int]:
        return self.right - self.left, self.bottom - self.top

    def xy(self, x, y) -> np.ndarray:
        """Pixel coordinates (…, 2), relative to the panel's top-left corner, of data
        points."""
        (x0, x1), (y0, y1) = self.xlim, self.ylim
        w, h = self.size
        return np.stack(((np.asarray(x, float) - x0) * (w / (x1 - x0)),
                         (y1 - np.asarray(y, float)) * (h / (y1 - y0))), axis=-1)


def ticks(lo: float, hi: float, most: int = 9) -> np.ndarray:
    """Tick values in [lo, hi]: multiples of the smallest step of 1, 2, 2.5, 5 × 10^k giving
    at most ``most`` + 1 ticks."""
    span = hi - lo
    if not span > 0.0:
        return np.array([lo])
    power = 10.0 ** math.floor(math.log10(span / most))
    step = next(s * power for s in (1.0, 2.0, 2.5, 5.0, 10.0) if span / (s * power) <= most)
    first = math.ceil(lo / step - 1e-9)
    values = (first + np.arange(int(math.floor(hi / step + 1e-9)) - first + 1)) * step
    return np.where(np.abs(values) < 1e-9 * step, 0.0, values)


def tick_label(value: float, values: np.ndarray) -> str:
    """``value`` written with as many decimals as its tick set needs (minus sign −)."""
    step = float(np.min(np.diff(values))) if len(values) > 1 else abs(value) or 1.0
    decimals = 0
    while decimals < 6 and abs(round(step, decimals) - step) > 1e-9 * abs(step):
        decimals += 1
    return f"{value:.{decimals}f}".replace("-", "−")


def text(draw, xy, words: str, size_px: int, *, anchor: str = "la", fill=GREY["ink"],
         align: str = "left") -> None:
    """Text (several lines allowed) with its ``anchor`` (Pillow's) at pixel ``xy``."""
    draw.multiline_text(tuple(map(float, xy)), words, font=font(size_px), fill=fill,
                        anchor=anchor, align=align, spacing=max(2, size_px // 4))


def turned_text(image, xy, words: str, size_px: int, *, fill=GREY["ink"],
                angle: int = 90, align: str = "center") -> None:
    """Text turned by ``angle`` (90: reading upwards; −90: downwards) and centred on pixel
    ``xy`` of ``image`` (RGB)."""
    from PIL import Image, ImageDraw

    face = font(size_px)
    spacing = max(2, size_px // 4)
    box = ImageDraw.Draw(Image.new("L", (1, 1))).multiline_textbbox(
        (0, 0), words, font=face, spacing=spacing, align=align)
    box = [int(round(v)) for v in box]
    mask = Image.new("L", (box[2] - box[0] + 2, box[3] - box[1] + 2), 0)
    ImageDraw.Draw(mask).multiline_text((1 - box[0], 1 - box[1]), words, font=face, fill=255,
                                        spacing=spacing, align=align)
    mask = mask.rotate(angle, expand=True)
    corner = (int(round(xy[0] - mask.width / 2)), int(round(xy[1] - mask.height / 2)))
    image.paste(Image.new("RGB", mask.size, fill), corner, mask)


def text_box(lines: list[str], size_px: int, pad: int, *, keys=None, key_width: int = 0):
    """A white box of ``lines`` of text as a small RGB image; with ``keys``, each line has a
    key ``key_width`` wide drawn by ``keys(draw, k, left, middle, right, size_px)`` on its
    left, and the box a light grey border (a legend)."""
    from PIL import Image, ImageDraw

    face = font(size_px)
    width = max(ImageDraw.Draw(Image.new("L", (1, 1))).textlength(s, font=face) for s in lines)
    step = int(1.4 * size_px)
    box = Image.new("RGB", (int(width) + key_width + 3 * pad, step * len(lines) + 2 * pad),
                    GREY["white"])
    draw = ImageDraw.Draw(box)
    for k, words in enumerate(lines):
        middle = pad + step * k + step / 2
        text(draw, (2 * pad + key_width, middle), words, size_px, anchor="lm")
        if keys is not None:
            keys(draw, k, pad, middle, pad + key_width, size_px)
    if keys is not None:
        draw.rectangle([0, 0, box.width - 1, box.height - 1], outline=(204, 204, 204))
    return box


def grid(image, panel: Panel, columns, rows, *, grey: float = 176.0,
         alpha: float = 0.3) -> None:
    """Grid lines one pixel wide at the panel's pixel ``columns`` and ``rows`` (relative to
    its corner), grey level ``grey`` at ``alpha`` over what ``image`` (RGB) shows."""
    from PIL import Image

    page = np.asarray(image).astype(float)
    area = page[panel.top:panel.bottom, panel.left:panel.right]  # a view
    w, h = panel.size
    for col in np.clip(np.rint(columns).astype(int), 0, w - 1):
        area[:, col] = (1.0 - alpha) * area[:, col] + alpha * grey
    for row in np.clip(np.rint(rows).astype(int), 0, h - 1):
        area[row, :] = (1.0 - alpha) * area[row, :] + alpha * grey
    image.paste(Image.fromarray(np.rint(page).astype(np.uint8)))
