"""A reduced-model response as labelled data: an :class:`xarray.Dataset` and a
:class:`pandas.DataFrame`, so that a notebook selects by label rather than by column number.

The dataset follows the CF conventions where they apply: a coordinate variable per dimension
(``time`` in s, ``dof`` by the DOF's name, ``spring`` by its index with its ``position`` and
``kind`` as coordinates, ``component`` of the energy account by name), ``units`` and
``long_name`` on every variable, and the contact state as ``flag_values``/``flag_meanings``.
The peaks, the run's information and its provenance are attributes (JSON text where they are
nested). Nothing here computes: every value is one the :class:`~.response.Response` holds.
"""

from __future__ import annotations

import json

import numpy as np

from . import springs as sp

__all__ = ["to_dataset", "to_frame", "SCALAR_HISTORIES"]

#: The scalar histories of a response: name -> (long name, unit kind).
SCALAR_HISTORIES = {
    "u": ("superstructure deformation", "length"),
    "x": ("top displacement relative to the ground", "length"),
    "X": ("absolute top displacement", "length"),
    "theta": ("base rotation", "rad"),
    "V": ("vertical displacement of the base point O, up", "length"),
    "base_shear": ("base shear", "force"),
    "overturning_moment": ("overturning moment about O", "moment"),
    "contact_length": ("length of the base in contact", "length"),
}


def _units(response) -> dict[str, str]:
    u = response.model.scene.units
    return {"length": u.length, "force": u.force, "moment": f"{u.force}*{u.length}",
            "rad": "rad", "stiffness": f"{u.force}/{u.length}", "energy": f"{u.force}*{u.length}"}


def to_dataset(response):
    """The response as an :class:`xarray.Dataset` (module docstring)."""
    import xarray as xr

    from .response import ENERGY_NAMES

    units, model = _units(response), response.model
    names = list(response.dofs.names)
    modes = sp.MODE_NAMES[sp.UPLIFT]
    coords = {
        "time": ("time", response.time, {"units": "s", "long_name": "time", "axis": "T"}),
        "dof": ("dof", names, {"long_name": "degree of freedom"}),
        "spring": ("spring", np.arange(model.params.size),
                   {"long_name": "spring index (stories first, then the foundation)"}),
        "position": ("spring", model.params["x"],
                     {"units": units["length"], "long_name": "spring position from O"}),
        "kind": ("spring", model.kind, {"long_name": "spring kind", "flag_values":
                                        np.array([0, 1, 2], np.int8),
                                        "flag_meanings": "story uplift bonded"}),
        "component": ("component", list(ENERGY_NAMES), {"long_name": "energy account"}),
    }
    data = {name: ("time", getattr(response, name),
                   {"units": units[kind], "long_name": long})
            for name, (long, kind) in SCALAR_HISTORIES.items()}
    data.update({
        "q": (("time", "dof"), response.q, {"units": "scene units of each DOF",
                                            "long_name": "DOFs relative to the ground"}),
        "qd": (("time", "dof"), response.qd, {"units": "scene units of each DOF per s",
                                              "long_name": "rates of the DOFs"}),
        "spring_deformation": (("time", "spring"), response.deformation,
                               {"units": units["length"], "long_name": "spring deformation"}),
        "spring_force": (("time", "spring"), response.force,
                         {"units": units["force"], "long_name": "spring force"}),
        "spring_mode": (("time", "spring"), response.mode.astype(np.int8), {
            "long_name": "state of a foundation spring",
            "flag_values": np.array(sorted(modes), np.int8),
            "flag_meanings": " ".join(modes[k] for k in sorted(modes))}),
        "plastic_deformation": (("time", "spring"), response.plastic,
                                {"units": units["length"], "long_name": "plastic deformation"}),
        "energy": (("time", "component"), response.energy,
                   {"units": units["energy"], "long_name": "cumulative energy account"}),
    })
    attrs = {"Conventions": "CF-1.10", "title": model.scene.title, "scene": model.scene.name,
             "units": model.scene.units.name,
             "peaks": json.dumps(response.peaks, default=float),
             "info": json.dumps(response.info, default=str),
             "provenance": json.dumps(response.provenance, default=str)}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def to_frame(response):
    """The scalar histories as a :class:`pandas.DataFrame` indexed by time (s); the units are
    in ``frame.attrs["units"]``."""
    import pandas as pd

    units = _units(response)
    frame = pd.DataFrame({name: getattr(response, name) for name in SCALAR_HISTORIES},
                         index=pd.Index(response.time, name="time"))
    frame.attrs["units"] = {name: units[kind] for name, (_, kind) in SCALAR_HISTORIES.items()}
    frame.attrs["units"]["time"] = "s"
    return frame
