"""A continuum result as labelled data: an :class:`xarray.Dataset` of the footing's histories
and its contact along the base (a dynamic run against time, a static path against its load
step), so that a notebook selects by label.

CF conventions where they apply: coordinate variables ``time`` (s), ``node`` (the footing's
contact nodes, with their ``x``) and ``component`` (of the energy account); ``units`` and
``long_name`` on every variable; the contact state as ``flag_values``/``flag_meanings``. The soil
fields of the snapshots stay in the XDMF output (a mesh, not a table). Nothing here computes:
every value is one the :class:`~.dynamic_result.DynamicResult` holds.
"""

from __future__ import annotations

import json

import numpy as np

from .dynamic_result import ENERGY
from .footing import OPEN, SLIP_NEGATIVE, SLIP_POSITIVE, STICK

__all__ = ["to_dataset", "path_to_dataset"]


def to_dataset(result):
    """The histories of ``result`` (a DynamicResult) as an :class:`xarray.Dataset`."""
    import xarray as xr

    units = result.metadata["units"]  # every run's provenance has them
    length, force, moment = units["length"], units["force/length"], units["moment/length"]
    stress = units["stress"]
    t, node = "time", ("time", "node")
    data = {
        "u": (t, result.footing[:, 0], {"units": length, "long_name": "footing sliding"}),
        "v": (t, result.footing[:, 1], {"units": length, "positive": "up",
                                         "long_name": "footing settlement (up positive)"}),
        "theta": (t, result.footing[:, 2], {"units": "rad", "long_name": "footing rotation"}),
        "structure_u": (t, result.structure_u, {"units": length,
                                                "long_name": "story deformation"}),
        "ground_acceleration": (t, result.ground_acceleration,
                                {"units": f"{length}/s^2", "long_name": "ground acceleration"}),
        "H": (t, result.H, {"units": force, "long_name": "horizontal reaction"}),
        "N": (t, result.N, {"units": force, "positive": "compression",
                            "long_name": "vertical reaction"}),
        "M": (t, result.M, {"units": moment, "long_name": "moment reaction about the centre"}),
        "contact_length": (t, result.contact_length,
                           {"units": length, "long_name": "length of the base in contact"}),
        "pressure": (node, result.pressure, {"units": stress, "positive": "compression",
                                             "long_name": "contact pressure"}),
        "gap": (node, result.gap, {"units": length, "long_name": "gap under the base"}),
        "status": (node, result.status.astype(np.int8), {
            "long_name": "contact state of a base node",
            "flag_values": np.array([OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE], np.int8),
            "flag_meanings": "open stick slip_positive slip_negative"}),
        "energy": (("time", "component"), result.energy,
                   {"units": f"{force}*{length}", "long_name": "cumulative energy account"}),
    }
    coords = {"time": (t, result.time, {"units": "s", "long_name": "time", "axis": "T"}),
              "node": ("node", np.arange(result.x.size), {"long_name": "base node index"}),
              "x": ("node", result.x, {"units": length,
                                       "long_name": "position along the base from its centre"}),
              "component": ("component", list(ENERGY), {"long_name": "energy account"})}
    attrs = {"Conventions": "CF-1.10", "kind": result.kind, "width": result.width,
             "metadata": json.dumps(result.metadata, default=str)}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def path_to_dataset(path):
    """A static path (a StaticPath: a pushover) as an :class:`xarray.Dataset` over its load
    ``step``, with the footing's rotation, settlement and loads as variables and the contact per
    base node; ``ds.swap_dims(step="theta")`` makes a rotation pushover selectable by θ."""
    import xarray as xr

    units = path.metadata["units"]
    length, force, moment = units["length"], units["force/length"], units["moment/length"]
    stress = units["stress"]
    s, node = "step", ("step", "node")
    data = {
        "u": (s, path.u, {"units": length, "long_name": "footing sliding"}),
        "v": (s, path.v, {"units": length, "positive": "up",
                          "long_name": "footing settlement (up positive)"}),
        "H": (s, path.H, {"units": force, "long_name": "horizontal load"}),
        "N": (s, path.N, {"units": force, "positive": "compression",
                          "long_name": "vertical load"}),
        "M": (s, path.M, {"units": moment, "long_name": "moment about the centre"}),
        "contact_length": (s, path.contact_length,
                           {"units": length, "long_name": "length of the base in contact"}),
        "pressure": (node, path.pressure, {"units": stress, "positive": "compression",
                                           "long_name": "contact pressure"}),
        "shear": (node, path.shear, {"units": stress, "long_name": "shear traction on the soil"}),
        "gap": (node, path.gap, {"units": length, "long_name": "gap under the base"}),
        "status": (node, path.status.astype(np.int8), {
            "long_name": "contact state of a base node",
            "flag_values": np.array([OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE], np.int8),
            "flag_meanings": "open stick slip_positive slip_negative"}),
        "iterations": (s, path.iterations, {"units": "1", "long_name": "Newton iterations"}),
    }
    coords = {"step": (s, np.arange(1, path.theta.size + 1), {"long_name": "load step"}),
              "theta": (s, path.theta, {"units": "rad", "long_name": "footing rotation"}),
              "node": ("node", np.arange(path.x.size), {"long_name": "base node index"}),
              "x": ("node", path.x, {"units": length,
                                     "long_name": "position along the base from its centre"})}
    attrs = {"Conventions": "CF-1.10", "kind": path.kind, "width": path.width,
             "metadata": json.dumps(path.metadata, default=str)}
    return xr.Dataset(data, coords=coords, attrs=attrs)
