"""The plastic-strain colours of the pictures, without matplotlib: one colour table and the
colour bar's norm, shared by the soil cells and the colour bar (so the two cannot disagree).

**The table** (:data:`TABLE`, 256 × RGB in [0, 1]) is ColorBrewer's 9-class YlOrRd
(Cynthia Brewer, colorbrewer2.org; the same anchors as matplotlib's ``"YlOrRd"``)
interpolated linearly at 256 evenly spaced points, as matplotlib builds a colour map from a
list of colours; a value ``s`` in [0, 1] takes entry ``min(⌊256 s⌋, 255)`` (matplotlib's
lookup), below 0 the first (palest), above 1 the last.

**The norm** (:func:`normalised`): logarithmic over [floor, top] when floor > 0
(:func:`~upliftlab.meshes.page.colour_range`: :data:`~upliftlab.meshes.page.DECADES`
decades below the run's largest value), else linear over [0, top].
"""

from __future__ import annotations

import numpy as np

__all__ = ["ANCHORS", "TABLE", "normalised", "colours_of", "to_bytes"]

#: ColorBrewer YlOrRd, 9 classes (hex #ffffcc … #800026), RGB in [0, 1].
ANCHORS = np.array([(0xff, 0xff, 0xcc), (0xff, 0xed, 0xa0), (0xfe, 0xd9, 0x76),
                    (0xfe, 0xb2, 0x4c), (0xfd, 0x8d, 0x3c), (0xfc, 0x4e, 0x2a),
                    (0xe3, 0x1a, 0x1c), (0xbd, 0x00, 0x26), (0x80, 0x00, 0x26)]) / 255.0
_SIZE = 256
#: The colour table (module docstring): (256, 3) RGB in [0, 1].
TABLE = np.column_stack([np.interp(np.linspace(0.0, 1.0, _SIZE),
                                   np.linspace(0.0, 1.0, len(ANCHORS)), ANCHORS[:, c])
                         for c in range(3)])


def normalised(values, floor: float, top: float) -> np.ndarray:
    """Values (any shape) on the colour scale [0, 1] (module docstring's norm); values below
    ``floor`` (log) or 0 (linear) fall below 0."""
    values = np.asarray(values, dtype=float)
    if floor > 0.0:
        with np.errstate(divide="ignore", invalid="ignore"):
            out = np.log10(values / floor) / np.log10(top / floor)
        return np.where(values > 0.0, out, -1.0)
    return values / top


def colours_of(values, floor: float, top: float) -> np.ndarray:
    """RGB (…, 3) in [0, 1] of values through the norm and the table (module docstring)."""
    s = normalised(values, floor, top)
    index = np.clip(np.floor(s * _SIZE), 0, _SIZE - 1).astype(int)
    return TABLE[index]


def to_bytes(rgb) -> np.ndarray:
    """RGB in [0, 1] as uint8 (rounded)."""
    return np.clip(np.rint(255.0 * np.asarray(rgb, dtype=float)), 0, 255).astype(np.uint8)
