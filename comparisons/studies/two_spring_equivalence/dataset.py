"""The study's data: its result record and the same as labelled datasets with CF attributes
(the convergence of the bed in N and the error maps, each over its own parameters), which
``result.to_xarray()`` gives and the NetCDF files hold."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ....results import cf_attributes
from ....units import unit_system
from ...framework.study import StudyResult, ascii_text
from .analysis import EwingConclusion, RegionStatement
from .convergence import Convergence
from .grid import FLOOR_FRACTION, Grid, METRIC_LABELS, METRICS, Options, STUDY
from .maps import ErrorMap
from .points import Base
from .statics import Statics

__all__ = ["TwoSpringEquivalence", "measure_units", "convergence_dataset", "map_dataset"]


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class TwoSpringEquivalence:
    """The study's result: files and summary (``study``), the converged N, the statics, the
    error maps and the conclusions computed from them."""

    study: StudyResult
    springs: int
    convergence: Convergence
    statics: Statics
    maps: tuple[ErrorMap, ...]
    regions: tuple[RegionStatement, ...]
    ewing: EwingConclusion
    grid: Grid
    options: Options
    record_note: str
    base: Base = None

    def map(self, name: str) -> ErrorMap:
        return next(m for m in self.maps if m.name == name)

    def __repr__(self) -> str:
        """One line: the bed's N, the maps and where the files are."""
        names = ", ".join(m.name for m in self.maps)
        return f"<TwoSpringEquivalence N = {self.springs} springs, maps: {names}; {self.study!r}>"

    def to_dataframe(self):
        """Every map's errors in long form, one row per (map, case, layout, measure and the
        map's two parameters), as a :class:`pandas.DataFrame` (column ``error``, relative; one
        column per parameter, ``h_over_b``, ``intensity``, …, empty where a map has no such
        axis)."""
        import pandas as pd

        tree = self.to_xarray()
        frames = [tree[f"map_{m.name}"].error.to_dataframe().reset_index().assign(map=m.name)
                  for m in self.maps]
        return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()

    def to_xarray(self):
        """The study's data as an :class:`xarray.DataTree`: ``convergence`` and one node per
        error map (``map_aspect``, …), the datasets its files hold, so that
        ``tree["map_aspect"].error.sel(case="C", layout="edges", measure="u")`` is one map, and
        ``…sel(h_over_b=4.0)`` one column of it: each map's dimensions are named after its
        parameters."""
        import xarray as xr

        prov, units = self.study.provenance, self.base.table["units"]
        nodes = {"convergence": convergence_dataset(self.convergence, prov, units)}
        nodes.update({f"map_{m.name}": map_dataset(m, prov, units) for m in self.maps})
        return xr.DataTree.from_dict(nodes, name=self.study.name)

    def region(self, map: str, case: str, layout: str, metric: str = "u") -> RegionStatement:
        return next(r for r in self.regions if (r.map, r.case, r.layout, r.metric)
                    == (map, case, layout, metric))


# ---------------------------------------------------------------------------------------------
# Labelled datasets
# ---------------------------------------------------------------------------------------------


def measure_units(units: str) -> dict[str, str]:
    """The unit of each compared measure (:data:`METRICS`) in the scene's unit system."""
    u = unit_system(units)
    return {"u": u.length, "theta": "rad", "uplift": u.length, "residual_settlement": u.length,
            "base_shear": u.force, "dissipated_energy": f"{u.force}*{u.length}"}


def convergence_dataset(conv: Convergence, prov: Mapping, units: str):
    """The convergence check in N as a labelled dataset over ``springs``."""
    import xarray as xr

    unit_of = measure_units(units)
    springs = ("springs",)
    data = {f"static_{key}": (springs, np.array(values, dtype=float), {
        "units": "1", "long_name": f"{key} of the uniform bed, M/(N B)"})
        for key, values in conv.static.items()}
    for case, measures in conv.dynamic.items():
        for m, values in measures.items():
            data[f"case_{case}_{m}"] = (springs, np.array(values, dtype=float), {
                "units": unit_of[m],
                "long_name": f"Case {case}: {METRIC_LABELS.get(m, m)}"})
    coords = {"springs": (springs, np.array(conv.candidates),
                          {"units": "1", "long_name": "number of springs in the bed"})}
    attrs = {"Conventions": "CF-1.10", "title": f"{STUDY}: convergence of the Winkler bed in N",
             "chosen_springs": conv.springs, "converged": conv.converged,
             "changes": conv.changes, "motion": ascii_text(conv.motion), "provenance": prov}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))


def map_dataset(emap: ErrorMap, prov: Mapping, units: str):
    """An error map as a labelled dataset: ``error`` over (case, layout, measure) and the map's
    two axes, each named after its parameter (``h_over_b``, ``intensity``, ``pulse_period``,
    ``period``, ``yield_multiple``, ``restitution``, ``record``) with its values and units, so
    that ``ds.error.sel(case="C", layout="edges", measure="u", h_over_b=4.0)`` selects by label;
    the two-spring values and the bed's reference per measure with its units (``value_u``,
    ``reference_u``)."""
    import xarray as xr

    unit_of = measure_units(units)
    x, y = emap.x.key, emap.y.key
    if x == y or x in _FIXED_DIMENSIONS or y in _FIXED_DIMENSIONS:
        raise ValueError(f"map {emap.name!r}: axes {x!r} and {y!r} must be distinct dimension "
                         f"names, none of {_FIXED_DIMENSIONS}")
    numeric_y = all(isinstance(v, (int, float)) for v in emap.y.values)
    coords = {
        "case": ("case", list(emap.cases), {"long_name": "foundation model (Case A, B or C)"}),
        "layout": ("layout", list(emap.layouts), {"long_name": "two-spring layout"}),
        "measure": ("measure", list(METRICS), {"long_name": "measure compared"}),
        x: (x, np.array(emap.x.values, dtype=float), {
            "long_name": ascii_text(emap.x.label), "units": _axis_unit(emap.x.unit)}),
        y: (y, np.array(emap.y.values, dtype=float) if numeric_y
            else [str(v) for v in emap.y.values],
            {"long_name": ascii_text(emap.y.label), "units": _axis_unit(emap.y.unit)}),
    }
    data = {
        "error": (("case", "layout", "measure", y, x), emap.errors, {
            "units": "1", "long_name": "(two-spring - bed)/max(|bed|, floor); NaN: run failed"}),
        "uplifted": (("case", y, x), emap.uplifted.astype(np.int8), {
            "long_name": "the bed separated", "flag_values": np.array([0, 1], np.int8),
            "flag_meanings": "in_contact uplifted"}),
    }
    for k, m in enumerate(METRICS):
        label = METRIC_LABELS[m]
        data[f"value_{m}"] = (("case", "layout", y, x), emap.values[:, :, k], {
            "units": unit_of[m], "long_name": f"{label} of the two springs"})
        data[f"reference_{m}"] = (("case", y, x), emap.reference[:, k], {
            "units": unit_of[m], "long_name": f"{label} of the Winkler bed ({emap.bed})"})
    attrs = {"Conventions": "CF-1.10", "title": ascii_text(emap.title), "bed": emap.bed,
             "floor_fraction": FLOOR_FRACTION, "failures": list(emap.failures),
             "energy_balance_error": emap.energy_balance_error, "provenance": prov}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))


#: The dimensions every map has besides its two axes.
_FIXED_DIMENSIONS = ("case", "layout", "measure")


def _axis_unit(unit: str) -> str:
    """An axis's unit as CF text: seconds as ``s``, a multiple of a named quantity as its name
    (e.g. ``a_up``), and ``1`` for a plain number or a label."""
    text = ascii_text(unit).strip().lstrip("x×* ").strip()
    return text or "1"
