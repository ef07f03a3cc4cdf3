"""One motion's dynamic comparison as a labelled dataset: the continuum's and each bed's
histories over (model, time), their peaks over model, and what each run was (the study's
``dynamic_<motion>`` node, :mod:`.dataset`)."""

from __future__ import annotations

import numpy as np

from ....results import cf_attributes
from ...framework.study import ascii_text
from .dynamics import DYNAMIC_LABELS, DYNAMIC_MEASURES, HISTORIES, DynamicRun
from .options import STUDY

__all__ = ["dynamic_dataset"]


def dynamic_dataset(run: DynamicRun, units):
    """The overlaid histories of ``run`` (continuum and beds) over (model, time), their peaks
    ``peak_<measure>`` over model (from the full-resolution histories), the continuum's
    ``steps`` and ``dofs``, and ``refused``: why the reduced integrator refused a bed's run
    ('' when it ran; its histories and peaks are NaN then). Attributes ``motion`` (the key)
    and ``label``."""
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
    data["steps"] = ((), int(run.continuum["steps"]),
                     {"units": "1", "long_name": "steps of the continuum's run"})
    data["dofs"] = ((), int(run.continuum["dofs"]),
                    {"units": "1", "long_name": "degrees of freedom of the continuum's mesh"})
    data["refused"] = ("model", [""] + [run.beds[n].get("refused", "") for n in run.beds],
                       {"long_name": "why the reduced integrator refused the run ('': it ran)"})
    attrs = {"Conventions": "CF-1.10", "title": ascii_text(f"{STUDY}: {run.label}"),
             "motion": run.key, "label": run.label}
    return xr.Dataset(data, coords=coords, attrs=cf_attributes(attrs))
