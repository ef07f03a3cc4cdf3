"""A reduced-model response as labelled data: an :class:`xarray.Dataset` and a
:class:`pandas.DataFrame`, so that a notebook selects by label rather than by column number.

The dataset follows the CF conventions where they apply: a coordinate variable per dimension
(``time`` in s, ``dof`` by the DOF's name, ``spring`` by its index with its ``position`` and
``kind`` as coordinates, ``component`` of the energy account by name), ``units`` and
``long_name`` on every variable (the DOFs ``q``, lengths and a rotation, have no one unit:
each DOF's is the coordinate ``dof_units``), and the contact state as
``flag_values``/``flag_meanings``.
The peaks are scalar variables with their units (``peak_theta``; the story drifts along
``story``); the ground motion as the run read it is in the dataset, on its own time axis
``record_time``. The run's information and its provenance are attributes, one per key
(:func:`~upliftlab.results.cf_attributes`). This dataset is what :meth:`Response.save` writes.
Nothing here computes: every value is one the :class:`~.response.Response` holds.
"""

from __future__ import annotations

import numpy as np

from ..labelled_data import LabelledData
from ..results import cf_attributes
from . import springs as sp

__all__ = ["to_dataset", "labelled_data", "to_frame", "SCALAR_HISTORIES", "PEAK_UNITS"]

#: The scalar histories of a response: name -> (long name, unit kind); ``sway`` only for a
#: base on a sway spring.
SCALAR_HISTORIES = {
    "u": ("superstructure deformation", "length"),
    "x": ("top displacement relative to the ground", "length"),
    "X": ("absolute top displacement", "length"),
    "theta": ("base rotation", "rad"),
    "V": ("vertical displacement of the base point O, up", "length"),
    "sway": ("horizontal displacement of the base relative to the ground", "length"),
    "base_shear": ("base shear", "force"),
    "overturning_moment": ("overturning moment about O", "moment"),
    "contact_length": ("length of the base in contact", "length"),
    "ground_displacement": ("ground displacement", "length"),
}

#: The peaks of a response: name -> (long name, unit kind).
PEAK_UNITS = {
    "u": ("peak |superstructure deformation|", "length"),
    "theta": ("peak |base rotation|", "rad"),
    "V_min": ("least vertical displacement of O (up positive)", "length"),
    "V_max": ("greatest vertical displacement of O (up positive)", "length"),
    "base_shear": ("peak |base shear|", "force"),
    "overturning_moment": ("peak |overturning moment about O|", "moment"),
    "story_drift": ("peak |story drift|", "length"),
    "uplift_left": ("peak uplift of the left edge", "length"),
    "uplift_max": ("peak uplift of any foundation spring (macro-element: the larger gap under "
                   "the base's two edges)", "length"),
    "plastic_settlement": ("plastic settlement of the macro-element's centre at the end (down "
                           "positive)", "length"),
    "spring_force_max": ("peak compression in a foundation spring", "force"),
    "residual_settlement": ("settlement of O at the end of a run that ended at rest (down "
                            "positive)", "length"),
    "weighted_plastic_settlement": ("stiffness-weighted mean plastic settlement of the "
                                    "springs at the end, sum(k*plastic)/sum(k)", "length"),
    "final_vertical_position": ("vertical displacement V of O at the end of the run (up "
                                "positive, moving or not)", "length"),
    "plastic_settlement_max": ("largest plastic settlement of a spring at the end", "length"),
    "plastic_settlement_mean": ("mean plastic settlement of the springs at the end", "length"),
    "min_contact_length": ("least length of the base in contact", "length"),
    "sway": ("peak |horizontal displacement of the base relative to the ground|", "length"),
    "sway_force": ("peak |force of the sway spring and its dashpot| (macro-element: its "
                   "horizontal force, without its dashpot)", "force"),
    "residual_sway": ("horizontal displacement of the base at the end of the run", "length"),
    "sliding": ("sliding of the base at the end of the run", "length"),
    "energy_balance_error": ("energy balance error, relative to the input", "1"),
}


def _units(response) -> dict[str, str]:
    u = response.model.scene.units
    return {"length": u.length, "force": u.force, "moment": f"{u.force}*{u.length}",
            "rad": "rad", "stiffness": f"{u.force}/{u.length}", "energy": f"{u.force}*{u.length}"}


def _dof_unit(name: str, units: dict) -> str:
    """The unit of a DOF by its name (:class:`~.compatibility.DofMap`): ``rad`` for the base
    rotation θ, ``1`` for sin θ (exact kinematics), the scene's length otherwise."""
    return {"theta": "rad", "sin_theta": "1"}.get(name, units["length"])


def _histories(response) -> dict:
    """:data:`SCALAR_HISTORIES` of this response: the sway only when it has a sway spring."""
    sways = response.model.sway_spring >= 0 or response.model.base is not None
    return {k: v for k, v in SCALAR_HISTORIES.items() if k != "sway" or sways}


def to_dataset(response):
    """The response as an :class:`xarray.Dataset` (module docstring)."""
    return labelled_data(response).to_xarray()


def labelled_data(response) -> LabelledData:
    """The response as the :class:`~upliftlab.labelled_data.LabelledData` that
    :func:`to_dataset` and the file hold (a response's ``save`` writes it without importing
    xarray)."""
    units, model = _units(response), response.model
    units["acceleration"] = f"{units['length']}/s^2"
    names = list(response.dofs.names)
    modes = sp.MODE_NAMES[sp.UPLIFT]
    coords = {
        "time": ("time", response.time, {"units": "s", "long_name": "time",
                                         "standard_name": "time", "axis": "T"}),
        "dof": ("dof", names, {"long_name": "degree of freedom"}),
        "dof_units": ("dof", [_dof_unit(name, units) for name in names],
                      {"long_name": "unit of the DOF (of its rate: this per s)"}),
        "spring": ("spring", np.arange(model.params.size),
                   {"units": "1",
                    "long_name": "spring index (stories first, then the sway spring if any, "
                                 "then the foundation)"}),
        "position": ("spring", model.params["x"],
                     {"units": units["length"], "long_name": "spring position from O"}),
        "kind": ("spring", np.asarray(model.kind, np.int8), {
            "long_name": "spring kind", "flag_values": np.array([0, 1, 2], np.int8),
            "flag_meanings": "story uplift bonded"}),
        "component": ("component", list(response.energy_names), {"long_name": "energy account"}),
    }
    data = {name: ("time", getattr(response, name),
                   {"units": units[kind], "long_name": long})
            for name, (long, kind) in _histories(response).items()}
    data.update({
        # lengths and a rotation in one array: no one unit, each DOF's is in dof_units
        "q": (("time", "dof"), response.q, {
            "long_name": "DOFs relative to the ground",
            "comment": "each DOF in its unit, the coordinate dof_units"}),
        "qd": (("time", "dof"), response.qd, {
            "long_name": "rates of the DOFs",
            "comment": "each DOF's rate in its unit (the coordinate dof_units) per s"}),
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
        "spring_stiffness": ("spring", model.params["k"] + model.params["kh"],
                             {"units": units["stiffness"], "long_name": "spring stiffness"}),
        "spring_static_force": ("spring", model.params["f0"], {
            "units": units["force"], "long_name": "static compression of a foundation spring"}),
    })
    if model.base is not None:
        data.update(_base_states(response, units, coords))
    data.update(_peaks(response, units))
    data.update(_ground_motion(response, units, coords))
    attrs = cf_attributes({
        "Conventions": "CF-1.10", "title": model.scene.title, "scene": model.scene.name,
        "units": model.scene.units.name, "gravity": model.scene.units.gravity,
        "source": "upliftlab reduced model (compatibility-matrix formulation)",
        "info": response.info, "provenance": response.provenance})
    return LabelledData.build(data, coords, attrs)


#: The macro-element's stored states (:data:`~.response.BASE_NAMES`): long name, unit kind.
BASE_STATES = {
    "V": ("vertical force on the base (compression positive, without the dashpots)", "force"),
    "H": ("horizontal force on the base (without the dashpot)", "force"),
    "M": ("moment on the base about O (without the dashpots)", "moment"),
    "v_p": ("plastic settlement of O (down positive)", "length"),
    "u_p": ("plastic sway of the base", "length"),
    "theta_p": ("plastic rotation of the base", "rad"),
    "contact_from": ("left end of the contact, from O", "length"),
    "contact_to": ("right end of the contact, from O", "length"),
    "rounding": ("rounding rho of the soil's surface under the base", "length"),
    "dissipated": ("energy the macro-element dissipated", "energy"),
}


def _base_states(response, units, coords) -> dict:
    """The macro-element's stored states, ``base_<name>`` along ``time`` (its columns in the
    order of :data:`~.response.BASE_NAMES`, which are this table's keys)."""
    return {f"base_{name}": ("time", response.base[:, k],
                             {"units": units.get(kind, kind), "long_name": long})
            for k, (name, (long, kind)) in enumerate(BASE_STATES.items())}


def _peaks(response, units) -> dict:
    """The peaks as scalar variables ``peak_<name>`` (the story drifts along ``story``)."""
    data = {}
    for name, value in response.peaks.items():
        long, kind = PEAK_UNITS[name]
        attrs = {"units": units.get(kind, kind), "long_name": long}
        if isinstance(value, list):
            data[f"peak_{name}"] = ("story", np.asarray(value, dtype=float), attrs)
            data["story"] = ("story", np.arange(1, len(value) + 1),
                             {"units": "1", "long_name": "story, counted from the base"})
        else:
            data[f"peak_{name}"] = ((), value, attrs)
    return data


def _ground_motion(response, units, coords) -> dict:
    """The ground acceleration as the run read it (the record's samples, scaled and extended),
    on ``record_time``: in the file, so that a result needs no motion file to be re-read."""
    motion = response.motion
    if motion is None:
        return {}
    coords["record_time"] = ("record_time", np.arange(motion.acceleration.size) * motion.dt,
                             {"units": "s", "long_name": "time of the ground motion's samples"})
    return {"ground_acceleration": ("record_time", motion.acceleration * response.model.g, {
        "units": units["acceleration"], "long_name": "horizontal ground acceleration",
        "motion": motion.name, "motion_source": motion.source})}


def to_frame(response):
    """The scalar histories as a :class:`pandas.DataFrame` indexed by time (s); the units are
    in ``frame.attrs["units"]``."""
    import pandas as pd

    units, histories = _units(response), _histories(response)
    frame = pd.DataFrame({name: getattr(response, name) for name in histories},
                         index=pd.Index(response.time, name="time"))
    frame.attrs["units"] = {name: units[kind] for name, (_, kind) in histories.items()}
    frame.attrs["units"]["time"] = "s"
    return frame
