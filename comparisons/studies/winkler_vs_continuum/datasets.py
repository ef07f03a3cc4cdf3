"""The study's data as labelled datasets: each bed's errors against the continuum, and each
dynamic run's histories, with CF attributes (what ``result.to_xarray()`` gives and the NetCDF
files hold)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ....results import cf_attributes
from ...framework.study import ascii_text
from .analysis import ErrorTable
from .dynamics import DYNAMIC_LABELS, DYNAMIC_MEASURES, HISTORIES, DynamicRun
from .options import STUDY
from .units import quantity_unit

__all__ = ["errors_dataset", "dynamic_dataset"]


def errors_dataset(table: ErrorTable, prov: Mapping, units):
    """The error table as a labelled dataset: ``error`` over (calibration, quantity), so that
    ``ds.error.sel(calibration="uniform_plastic", quantity="onset_moment")`` is one entry, with
    each quantity's label and group as coordinates along it; the quantities mix units, so each
    has its own ``value_<quantity>`` (the beds, over calibration) and ``reference_<quantity>``
    (the continuum, its error floor as an attribute), in the scene's units per unit length."""
    import xarray as xr

    coords = {
        "calibration": ("calibration", list(table.calibrations),
                        {"long_name": "Winkler-bed calibration"}),
        "quantity": ("quantity", list(table.quantities), {"long_name": "quantity compared"}),
        "label": ("quantity", [ascii_text(s) for s in table.labels],
                  {"long_name": "what the quantity is"}),
        "group": ("quantity", [ascii_text(s) for s in table.groups],
                  {"long_name": "what the quantity belongs to"}),
    }
    data = {"error": (("calibration", "quantity"), table.errors, {
        "units": "1", "long_name": "(bed - continuum)/max(|continuum|, floor); NaN: none"})}
    for k, (key, label) in enumerate(zip(table.quantities, table.labels)):
        unit = quantity_unit(key, units, cf=True)
        data[f"value_{key}"] = ("calibration", table.values[:, k], {
            "units": unit, "long_name": ascii_text(f"{label} of the bed (inf: no capacity)")})
        data[f"reference_{key}"] = ((), table.reference[k], {
            "units": unit, "long_name": ascii_text(f"{label} of the continuum"),
            "error_floor": float(table.floors[k])})
    attrs = {"Conventions": "CF-1.10", "title": f"{STUDY}: error table", "provenance": prov}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))


def dynamic_dataset(run: DynamicRun, prov: Mapping, units):
    """One motion's overlaid histories (continuum and beds) over (model, time) and their peaks
    over (measure, model)."""
    import xarray as xr

    models = ("continuum",) + tuple(run.beds)
    length = units.length
    history_units = {"theta": ("rad", "footing rotation"), "u": (length, "story deformation"),
                     "uplift": (length, "uplift of the footing's edge"),
                     "settlement": (length, "settlement of the centre from rest (down)"),
                     "contact": (length, "length of the base in contact")}
    coords = {"model": ("model", list(models), {"long_name": "continuum or bed calibration"}),
              "time": ("time", run.time, {"units": "s", "long_name": "time", "axis": "T"}),
              "measure": ("measure", list(DYNAMIC_MEASURES), {"long_name": "peak measure"})}
    data = {}
    for key in HISTORIES:
        values = [run.continuum[key]] + [run.beds[n][key] for n in run.beds]
        unit, long = history_units[key]
        data[key] = (("model", "time"), np.array(values, dtype=float),
                     {"units": unit, "long_name": long})
    for m in DYNAMIC_MEASURES:
        values = [run.continuum["peaks"][m]] + [run.beds[n]["peaks"][m] for n in run.beds]
        unit = "rad" if m == "theta" else length
        data[f"peak_{m}"] = ("model", np.array(values, dtype=float),
                             {"units": unit, "long_name": ascii_text(DYNAMIC_LABELS[m])})
    attrs = {"Conventions": "CF-1.10", "title": ascii_text(f"{STUDY}: {run.label}"),
             "provenance": prov}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))
