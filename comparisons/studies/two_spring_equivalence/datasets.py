"""The study's data as labelled datasets: the convergence of each layout and the error maps,
with CF attributes (what ``result.to_xarray()`` gives and the NetCDF files hold)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ....results import cf_attributes
from ....units import unit_system
from .convergence import Convergence
from ...framework.study import ascii_text
from .grid import FLOOR_FRACTION, METRIC_LABELS, METRICS, STUDY
from .maps import ErrorMap

__all__ = ["measure_units", "convergence_dataset", "map_dataset"]


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
