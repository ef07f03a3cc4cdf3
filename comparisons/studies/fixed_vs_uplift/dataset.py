"""The study's data as one labelled dataset: Figs. 11–12 (histories and peaks by ``building``
and ``support``) and the spectrum (peaks by ``family``, ``support`` and ``period``), built
from the runs' records (:mod:`.runs`)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from ....results import cf_attributes
from .grid import FIGURES, OUTPUT_DT, SUPPORTS, SUPPORT_LABELS, Grid

#: The supports of Figs. 11–12: the fixed base against uplift allowed in Case C.
FIGURE_SUPPORTS = ("fixed", "C")


def _histories(figures: Mapping[str, Mapping]) -> tuple[np.ndarray, dict]:
    """The common time axis (s, every :data:`OUTPUT_DT` up to the shortest run) and each
    building's u per support on it (linear interpolation, exact at the stored samples)."""
    end = min((r["time"][-1] for runs in figures.values() for r in runs.values()),
              default=0.0)
    t = np.arange(0.0, end, OUTPUT_DT)
    return t, {b: {s: np.interp(t, r["time"], r["u"]) for s, r in runs.items()}
               for b, runs in figures.items()}


def _spectrum(grid: Grid, records: Sequence[Mapping], supports: Sequence[str]):
    """Peak u, V/W and whether the base uplifted, over (family, support, period)."""
    shape = (len(grid.families), len(supports), len(grid.periods))
    u, shear = np.full(shape, np.nan), np.full(shape, np.nan)
    uplifted = np.zeros(shape, dtype=np.int8)
    it = iter(records)
    for f in range(len(grid.families)):
        for support in grid.supports:
            k = supports.index(support)
            for i in range(len(grid.periods)):
                r = next(it)
                u[f, k, i] = r.get("u", math.nan)
                shear[f, k, i] = (r.get("base_shear", math.nan) / r["weight"]
                                  if "error" not in r else math.nan)
                uplifted[f, k, i] = r.get("uplift", 0.0) > 0.0
    return u, shear, uplifted


def study_dataset(grid: Grid, figures: Mapping[str, Mapping], records: Sequence[Mapping],
                  attrs: Mapping):
    """The study's :class:`xarray.Dataset`. ``figures``: {building: {support: the record of
    :func:`.runs.figure_run`}} of Figs. 11–12; ``records``: the spectrum's records in the order
    of :func:`.runs.spectrum_points`. Variables: ``u`` (in) over (building, support, time),
    ``peak_u`` (in), ``peak_base_shear`` (kip) and ``peak_uplift`` (in) over (building,
    support); ``spectrum_peak_u`` (in), ``spectrum_shear_coefficient`` (V/W) and
    ``spectrum_uplifted`` over (family, support, period). A support a part did not run is NaN
    there; ``spectrum_supports`` names those the spectrum ran. ``attrs`` are added."""
    import xarray as xr

    supports = [s for s in SUPPORTS if s in grid.supports or s in FIGURE_SUPPORTS]
    buildings = list(figures)
    time, u = _histories(figures)
    history = np.full((len(buildings), len(supports), time.size), np.nan)
    peaks = {k: np.full((len(buildings), len(supports)), np.nan)
             for k in ("peak_u", "base_shear", "uplift")}
    for b, building in enumerate(buildings):
        for support, r in figures[building].items():
            k = supports.index(support)
            history[b, k] = u[building][support]
            for key in peaks:
                peaks[key][b, k] = r[key]
    spectrum_u, shear, uplifted = _spectrum(grid, records, supports)
    fig, spec = ("building", "support"), ("family", "support", "period")
    flag = {"flag_values": np.array([0, 1], np.int8), "flag_meanings": "in_contact uplifted"}
    data = {
        "u": (fig + ("time",), history, {"units": "in", "long_name": "story deformation"}),
        "peak_u": (fig, peaks["peak_u"], {"units": "in", "long_name": "peak story deformation"}),
        "peak_base_shear": (fig, peaks["base_shear"], {"units": "kip",
                                                       "long_name": "peak base shear"}),
        "peak_uplift": (fig, peaks["uplift"], {"units": "in",
                                               "long_name": "peak uplift of the left spring"}),
        "spectrum_peak_u": (spec, spectrum_u, {"units": "in",
                                               "long_name": "peak story deformation"}),
        "spectrum_shear_coefficient": (spec, shear, {
            "units": "1", "long_name": "peak base shear over the weight, V/W"}),
        "spectrum_uplifted": (spec, uplifted, {"long_name": "the base uplifted", **flag})}
    coords = {
        "building": ("building", buildings, {"long_name": "building of Figs. 11-12"}),
        "figure": ("building", np.array([FIGURES[b] for b in buildings]),
                   {"long_name": "figure of the paper"}),
        "support": ("support", supports, {"long_name": "; ".join(
            f"{s}: {SUPPORT_LABELS[s]}" for s in supports)}),
        "family": ("family", list(grid.families),
                   {"long_name": "building whose base body the spectrum keeps"}),
        "period": ("period", np.array(grid.periods, dtype=float), {
            "units": "s", "long_name": "fixed-base period of the superstructure"}),
        "time": ("time", time, {"units": "s", "long_name": "time", "axis": "T"})}
    attrs = {"Conventions": "CF-1.10", "motion": "El Centro 1940 N-S",
             "title": "fixed base against uplift allowed: Figs. 11-12 and the spectrum",
             "spectrum_supports": list(grid.supports), **attrs}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))
