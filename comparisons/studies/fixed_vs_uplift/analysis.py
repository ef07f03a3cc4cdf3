"""What the runs say, read from the study's dataset: Figs. 11–12's ratios, and the period
ranges over which uplift reduces each peak."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ....checks import InputError
from .grid import NO_CHANGE


def figure_ratio(ds, building: str, what: str) -> float:
    """Peak ``what`` (``u`` or ``shear``) of Case C over the fixed base's in the figure of
    ``building``."""
    peak = ds.peak_u if what == "u" else ds.peak_base_shear
    one = peak.sel(building=building)
    return float(one.sel(support="C") / one.sel(support="fixed"))


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


def spectrum_supports(ds) -> list[str]:
    """The supports the spectrum ran, the fixed base first."""
    value = ds.attrs["spectrum_supports"]
    return [value] if isinstance(value, str) else [str(v) for v in value]


def ratio(ds, family: str, support: str, what: str) -> np.ndarray:
    """Spectrum of ``family``: peak ``what`` (``u`` or ``shear``) of ``support`` over the
    fixed base's, against the period."""
    values = ds.spectrum_peak_u if what == "u" else ds.spectrum_shear_coefficient
    one = values.sel(family=family)
    return one.sel(support=support).values / one.sel(support="fixed").values


def at(ds, family: str, support: str, what: str, period: float) -> float:
    """:func:`ratio` at the grid period nearest ``period`` (s)."""
    i = int(np.argmin(np.abs(ds.period.values - period)))
    return float(ratio(ds, family, support, what)[i])


def spectrum_ranges(ds, family: str) -> dict:
    """{(support, "shear" | "u"): :class:`Ranges`} of each uplift case of ``family``."""
    out = {}
    for support in spectrum_supports(ds):
        if support != "fixed":
            for what in ("shear", "u"):
                out[(support, what)] = reduction_ranges(ds.period.values,
                                                        ratio(ds, family, support, what))
    return out
