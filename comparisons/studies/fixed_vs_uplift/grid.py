"""The fixed-against-uplift study's parameters: buildings, supports, the period grid and
options, and their checks."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .... import checks
from ....checks import InputError


STUDY = "fixed_vs_uplift"
BUILDINGS = {"short": "short_period_elcentro", "long": "long_period_elcentro"}
FIGURES = {"short": 11, "long": 12}
SUPPORTS = ("fixed", "C", "A")
SUPPORT_LABELS = {"fixed": "fixed base", "C": "uplift allowed, Case C",
                  "A": "uplift allowed, Case A (elastic, 40 %)"}
#: Fig. 11 as read from the paper (in): peak deformation with uplift allowed and fixed base.
PAPER_FIG11_PEAK_U = {"C": 0.055, "fixed": 0.164}
PAPER_PERIODS = (0.15, 0.59)
OUTPUT_DT = 0.005  # s, histories of Figs. 11-12 (peaks are tracked at every step)
NO_CHANGE = 0.02  # ratios within 2 % of one count as "no change" (no or negligible uplift)


@dataclass(frozen=True)
class Grid:
    """``periods`` (s, ascending) of the spectrum, the building ``families`` whose base body is
    kept (``short``: I₀ = 7694, ``long``: I₀ = 1740 kip·in·s²), the ``supports`` (cases), and
    ``figures`` (the buildings of Figs. 11–12 to run)."""

    periods: tuple[float, ...]
    families: tuple[str, ...] = ("short", "long")
    supports: tuple[str, ...] = SUPPORTS
    figures: tuple[str, ...] = ("short", "long")


def log_periods(count: int) -> tuple[float, ...]:
    grid = {round(float(t), 4) for t in np.geomspace(0.05, 3.0, count)}
    return tuple(sorted(grid | set(PAPER_PERIODS)))


FULL_GRID = Grid(periods=log_periods(30))
FAST_GRID = Grid(periods=log_periods(8), families=("short",))


@dataclass(frozen=True)
class Options:
    """``figures``: write the PNGs (needs matplotlib)."""

    figures: bool = True


def check_grid(grid: Grid) -> Grid:
    """Validate the grid; an :class:`InputError` names the field, value and valid range."""
    p = grid.periods
    if isinstance(p, (str, bytes)) or not isinstance(p, Sequence) or len(p) < 2:
        raise InputError(f"grid.periods = {p!r}: expected at least two periods (s)")
    for i, t in enumerate(p):
        checks.in_range(f"grid.periods[{i}]", t, 0.02, 10.0)
    if any(b <= a for a, b in zip(p, p[1:])):
        raise InputError(f"grid.periods = {list(p)!r}: values must strictly ascend")
    for name, values, valid in (("families", grid.families, BUILDINGS),
                                ("supports", grid.supports, SUPPORTS),
                                ("figures", grid.figures, BUILDINGS)):
        if isinstance(values, str) or not isinstance(values, Sequence):
            raise InputError(f"grid.{name} = {values!r}: expected a list from {list(valid)}")
        for i, v in enumerate(values):
            checks.one_of(f"grid.{name}[{i}]", v, tuple(valid))
    if "fixed" not in grid.supports or len(grid.supports) < 2:
        raise InputError(f"grid.supports = {list(grid.supports)!r}: needs 'fixed' and at least "
                         "one uplift case ('C' or 'A') to compare")
    return grid
