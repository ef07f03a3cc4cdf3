"""An animated GIF written frame by frame against one fixed palette.

**The palette** (:func:`palette`, 256 colours) is fixed before the first frame, from what the
raster pages of :mod:`~upliftlab.meshes.sheet` are drawn with: the plastic-strain colour table
(:data:`~upliftlab.meshes.colours.TABLE`, 136 of its 256 entries, evenly spaced), 40 greys
(text, ticks, outlines, grid), and ramps from white to each accent colour (pressure blue, its
translucent fill on the footing band's grey, gap red, footing blue-grey, and the fill on white:
16 each; text in colour is anti-aliased on white). Every frame maps each pixel to its nearest
palette colour, without dithering (no per-frame palette search, and the colours of a frame do not
flicker between frames). Pillow finds the nearest colour of a pixel's value rounded down to a
multiple of 4; it is given the palette rounded down alike (so that a pixel of a palette
colour keeps that colour exactly, white stays white), and the file gets the true palette.

**Streaming.** :class:`GifWriter` writes each frame as it comes (Pillow's GIF encoder,
through its public ``getheader``/``getdata``), so no list of frames is held; the file appears
complete at its path or not at all (:func:`~upliftlab.results.atomic_path`).
"""

from __future__ import annotations

import contextlib

import numpy as np

from ..results import atomic_path
from .colours import TABLE
from .sheet import BLUE as _BLUE, FILL as _FILL, FILL_ON_WHITE as _ON_WHITE, FOOTING as _FOOTING
from .sheet import RED as _RED

__all__ = ["palette", "GifWriter", "write_gif"]



def palette() -> np.ndarray:
    """The fixed palette (256, 3) uint8 (module docstring)."""
    ramp = np.linspace(0.0, 1.0, 16)[:, None]
    white = np.ones(3)
    accents = [_BLUE, _RED, _FOOTING, _FILL, _ON_WHITE]
    table = TABLE[np.rint(np.linspace(0, len(TABLE) - 1, 136)).astype(int)]
    parts = [table, np.repeat(np.linspace(0.0, 1.0, 40)[:, None], 3, axis=1)]
    parts += [white + ramp * (np.asarray(c) - white) for c in accents]
    colours = np.vstack(parts)
    assert colours.shape == (256, 3)
    return np.clip(np.rint(255.0 * colours), 0, 255).astype(np.uint8)


class GifWriter:
    """Frames (RGB arrays, all of one size) appended to an open binary file ``stream``, each
    shown ``seconds_per_frame``; the animation loops. :meth:`close` ends the file."""

    def __init__(self, stream, seconds_per_frame: float):
        from PIL import Image

        self.stream, self.count = stream, 0
        self.duration = int(round(1000 * seconds_per_frame))
        self._colours = palette().ravel().tolist()
        self._search = Image.new("P", (1, 1))
        self._search.putpalette([c & 0xFC for c in self._colours])

    def add(self, rgb) -> None:
        """Append a frame: a Pillow RGB image or an RGB array (h, w, 3)."""
        from PIL import GifImagePlugin, Image

        if not isinstance(rgb, Image.Image):
            rgb = Image.fromarray(np.ascontiguousarray(rgb, dtype=np.uint8), "RGB")
        image = rgb.quantize(palette=self._search, dither=Image.Dither.NONE)
        image.putpalette(self._colours)
        if self.count == 0:
            header, _ = GifImagePlugin.getheader(image, info={"loop": 0,
                                                              "duration": self.duration})
            self.stream.write(b"".join(header))
        self.stream.write(b"".join(GifImagePlugin.getdata(image, duration=self.duration)))
        self.count += 1

    def close(self) -> None:
        self.stream.write(b";")


@contextlib.contextmanager
def write_gif(path, seconds_per_frame: float):
    """A :class:`GifWriter` on ``path``, written atomically when the block ends."""
    with atomic_path(path) as tmp, open(tmp, "wb") as stream:
        writer = GifWriter(stream, seconds_per_frame)
        yield writer
        writer.close()
