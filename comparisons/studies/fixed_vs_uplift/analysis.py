"""What the runs say: Figs. 11–12's peaks and ratios, and the period ranges over which uplift
reduces each peak."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ....checks import InputError
from ...framework.store import Store
from ...framework.study import StudyResult
from .grid import FIGURES, Grid, NO_CHANGE, Options
from .runs import building_scene, cached_run


# ---------------------------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Figure:
    """Fig. 11 or 12: ``time`` (s) and ``u`` (length) per support, and the peaks."""

    building: str
    number: int
    time: dict
    u: dict
    peak_u: dict
    base_shear: dict
    uplift: dict

    @property
    def ratio_u(self) -> float:
        return self.peak_u["C"] / self.peak_u["fixed"]

    @property
    def ratio_shear(self) -> float:
        return self.base_shear["C"] / self.base_shear["fixed"]


@dataclass(frozen=True)
class Ranges:
    """Where a ratio (uplift/fixed) is below 1 − :data:`NO_CHANGE`: ``reduced`` as (T_from,
    T_to) runs of consecutive grid periods (s), ``increased`` likewise above 1 + NO_CHANGE;
    the smallest ratio ``min_ratio`` at ``min_period``, the largest ``max_ratio`` at
    ``max_period`` and the ``median`` over the grid."""

    reduced: tuple[tuple[float, float], ...]
    increased: tuple[tuple[float, float], ...]
    min_ratio: float
    min_period: float
    max_ratio: float
    max_period: float
    median: float
    count_reduced: int
    total: int


@dataclass(frozen=True, eq=False)
class Spectrum:
    """Peak values against period for one building family: ``u`` (length), ``shear`` (V/W)
    and ``uplifted`` per support (arrays over ``periods``), and the ratio statements."""

    family: str
    periods: np.ndarray
    u: dict
    shear: dict
    uplifted: dict
    ranges: dict  # (support, "shear" | "u") -> Ranges

    def ratio(self, support: str, what: str) -> np.ndarray:
        values = self.shear if what == "shear" else self.u
        return values[support] / values["fixed"]

    def at(self, support: str, what: str, period: float) -> float:
        i = int(np.argmin(np.abs(self.periods - period)))
        return float(self.ratio(support, what)[i])


def period_runs(mask: np.ndarray, periods: np.ndarray) -> tuple[tuple[float, float], ...]:
    out, start = [], None
    for i, m in enumerate(mask):
        if m and start is None:
            start = i
        if start is not None and (not m or i == mask.size - 1):
            end = i if m else i - 1
            out.append((float(periods[start]), float(periods[end])))
            start = None
    return tuple(out)


def reduction_ranges(periods: Sequence[float], ratio: Sequence[float]) -> Ranges:
    """The period ranges over which ``ratio`` (uplift/fixed) is below or above one (by more
    than :data:`NO_CHANGE`), and its extremes; NaN ratios (failed runs) belong to neither."""
    t, r = np.asarray(periods, float), np.asarray(ratio, float)
    ok = np.isfinite(r)
    if not ok.any():
        raise InputError("ratio: no finite value; every run failed")
    lo, hi = int(np.nanargmin(r)), int(np.nanargmax(r))
    return Ranges(period_runs(ok & (r < 1 - NO_CHANGE), t),
                  period_runs(ok & (r > 1 + NO_CHANGE), t),
                  float(r[lo]), float(t[lo]), float(r[hi]), float(t[hi]),
                  float(np.nanmedian(r)), int(np.sum(ok & (r < 1 - NO_CHANGE))), int(ok.sum()))


def spectrum_of(family: str, grid: Grid, records: Sequence[Mapping]) -> Spectrum:
    n = len(grid.periods)
    u, shear, up = {}, {}, {}
    for k, support in enumerate(grid.supports):
        rows = records[k * n:(k + 1) * n]
        u[support] = np.array([r.get("u", math.nan) for r in rows])
        shear[support] = np.array([r.get("base_shear", math.nan) / r["weight"]
                                   if "error" not in r else math.nan for r in rows])
        up[support] = np.array([r.get("uplift", 0.0) > 0.0 for r in rows])
    periods = np.array(grid.periods)
    ranges = {}
    for support in grid.supports:
        if support != "fixed":
            for what, values in (("shear", shear), ("u", u)):
                ranges[(support, what)] = reduction_ranges(periods,
                                                           values[support] / values["fixed"])
    return Spectrum(family, periods, u, shear, up, ranges)


@dataclass(frozen=True, eq=False)
class FixedVsUplift:
    """The study's result: files and summary (``study``), Figs. 11–12, the spectra."""

    study: StudyResult
    figures: tuple[Figure, ...]
    spectra: tuple[Spectrum, ...]
    grid: Grid
    continuum: str
    options: Options = None

    def figure(self, building: str) -> Figure:
        return next(f for f in self.figures if f.building == building)

    def spectrum(self, family: str) -> Spectrum:
        return next(s for s in self.spectra if s.family == family)


def figure_of(building: str, store: Store, record: dict) -> Figure:
    runs = {s: cached_run(store, "figure_run",
                          {"scene": building_scene(building, s).data, **record})
            for s in ("fixed", "C")}
    return Figure(building, FIGURES[building], {s: np.array(r["time"]) for s, r in runs.items()},
                  {s: np.array(r["u"]) for s, r in runs.items()},
                  {s: r["peak_u"] for s, r in runs.items()},
                  {s: r["base_shear"] for s, r in runs.items()},
                  {s: r["uplift"] for s, r in runs.items()})
