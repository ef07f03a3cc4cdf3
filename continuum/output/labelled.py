"""A continuum result as labelled data: an :class:`xarray.Dataset` of the footing's histories
and its contact along the base (a dynamic run against time, a static path against its load
step), so that a notebook selects by label.

CF conventions where they apply: coordinate variables ``time`` (s), ``node`` (the footing's
contact nodes, with their ``x``) and ``component`` (of the energy account); ``units`` and
``long_name`` on every variable; the contact state as ``flag_values``/``flag_meanings``. The soil
fields of the snapshots are here too, as the model's DOF vector and element averages along
``snapshot``, located by the coordinates ``dof_x``, ``dof_y``, ``dof_direction`` and
``element_x``, ``element_y`` (the XDMF output draws them on the mesh); the run's metadata
and provenance are attributes, one per key (:func:`~upliftlab.results.cf_attributes`). A
dynamic run's far field (the soil columns at the box's sides) is along ``side`` and ``layer``
(:func:`_far_field`). The data are built as a
:class:`~upliftlab.labelled_data.LabelledData` (:func:`labelled_data`), which the results'
``save`` writes without importing xarray (on disk as :mod:`upliftlab.cf` says; read back
by :func:`upliftlab.open_result`). Nothing here computes: every value is one the result holds.
"""

from __future__ import annotations

import numpy as np

from ...labelled_data import LabelledData
from ...results import cf_attributes
from ..contact.footing import OPEN, SLIP_NEGATIVE, SLIP_POSITIVE, STICK

__all__ = ["to_dataset", "labelled_data", "path_to_dataset", "path_labelled_data",
           "to_frame"]


def _footing_and_contact(result, dim: str) -> tuple[dict, dict]:
    """The variables and coordinates a dynamic result and a static path share, along ``dim``
    (time or load step): the footing's u, v, loads and contact length, and per base node the
    pressure, gap and contact state."""
    units = result.metadata["units"]  # every run's provenance has them
    length, force, moment = units["length"], units["force/length"], units["moment/length"]
    node = (dim, "node")
    data = {
        "u": (dim, result.footing[:, 0], {"units": length, "long_name": "footing sliding"}),
        "v": (dim, result.footing[:, 1], {"units": length,
                                           "long_name": "footing settlement (up positive)"}),
        "H": (dim, result.H, {"units": force, "long_name": "horizontal load on the footing"}),
        "N": (dim, result.N, {"units": force,
                              "long_name": "vertical load on the footing (compression positive)"}),
        "M": (dim, result.M, {"units": moment, "long_name": "moment about the base centre"}),
        "contact_length": (dim, result.contact_length,
                           {"units": length, "long_name": "length of the base in contact"}),
        "pressure": (node, result.pressure, {
            "units": units["stress"], "long_name": "contact pressure (compression positive)"}),
        "gap": (node, result.gap, {"units": length, "long_name": "gap under the base"}),
        "status": (node, result.status.astype(np.int8), {
            "long_name": "contact state of a base node",
            "flag_values": np.array([OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE], np.int8),
            "flag_meanings": "open stick slip_positive slip_negative"}),
    }
    coords = {"node": ("node", np.arange(result.x.size),
                       {"units": "1", "long_name": "base node index"}),
              "x": ("node", result.x, {"units": length,
                                       "long_name": "position along the base from its centre"})}
    return data, coords


def _snapshots(result, data: dict, coords: dict, time_units: str, time_meaning: str) -> None:
    """Add the soil fields at the snapshots: the DOF vector and the element averages."""
    units = result.metadata["units"]
    snap, step = "snapshot", "time" if "time" in coords else "step"
    coords["snapshot"] = ("snapshot", np.arange(result.snapshot_step.size),
                          {"units": "1", "long_name": "snapshot index"})
    data.update({
        "snapshot_step": (snap, result.snapshot_step, {
            "units": "1", "long_name": f"index along {step} of the snapshot"}),
        "snapshot_time": (snap, result.snapshot_time, {"units": time_units,
                                                       "long_name": time_meaning}),
        "displacement": ((snap, "dof"), result.displacement, {
            "units": units["length"],
            "long_name": "soil displacement DOF vector in the model basis's ordering"}),
        "plastic_strain": ((snap, "element"), result.plastic_strain, {
            "units": "1", "long_name": "element-averaged equivalent plastic strain"}),
        "max_shear_stress": ((snap, "element"), result.max_shear_stress, {
            "units": units["stress"], "long_name": "element-averaged (s1 - s3)/2"}),
    })
    if getattr(result, "dof_xy", None) is not None:
        coords.update(_field_coordinates(result, units["length"]))


def _field_coordinates(result, length: str) -> dict:
    """Where the soil fields live: each DOF's node (x, y) and direction, each element's
    centroid (x, y), as coordinates along ``dof`` and ``element``."""
    where = "of the node of the displacement DOF"
    return {
        "dof_x": ("dof", result.dof_xy[:, 0], {"units": length, "long_name": f"x {where}"}),
        "dof_y": ("dof", result.dof_xy[:, 1], {"units": length,
                                              "long_name": f"y {where} (up; surface 0)"}),
        "dof_direction": ("dof", result.dof_direction.astype(np.int8), {
            "long_name": "direction of the displacement DOF",
            "flag_values": np.array([0, 1], np.int8), "flag_meanings": "x y"}),
        "element_x": ("element", result.element_xy[:, 0],
                      {"units": length, "long_name": "x of the element's centroid"}),
        "element_y": ("element", result.element_xy[:, 1],
                      {"units": length, "long_name": "y of the element's centroid"}),
    }


def _labelled(result, data: dict, coords: dict) -> LabelledData:
    scene = result.metadata.get("scene") or "a footing"
    attrs = cf_attributes({
        "Conventions": "CF-1.10", "title": f"{result.kind} of {scene} (upliftlab continuum)",
        "source": "upliftlab continuum model (plane strain)",
        "kind": result.kind, "width": result.width, **result.metadata})
    return LabelledData.build(data, coords, attrs)


def to_dataset(result):
    """The histories of ``result`` (a DynamicResult) as an :class:`xarray.Dataset`."""
    return labelled_data(result).to_xarray()


def labelled_data(result) -> LabelledData:
    """The histories of ``result`` (a DynamicResult) as the
    :class:`~upliftlab.labelled_data.LabelledData` that :func:`to_dataset` and the file hold."""
    data, coords = _footing_and_contact(result, "time")
    units = result.metadata["units"]
    length, force = units["length"], units["force/length"]
    data.update({
        "theta": ("time", result.footing[:, 2], {"units": "rad", "long_name": "footing rotation"}),
        "structure_u": ("time", result.structure_u, {"units": length,
                                                     "long_name": "story deformation"}),
        "structure_velocity": ("time", result.structure_velocity, {
            "units": f"{length}/s", "long_name": "rate of the story deformation"}),
        "iterations": ("time", result.iterations, {"units": "1",
                                                   "long_name": "iterations of the step"}),
        "refactored": ("time", result.refactored.astype(np.int8), {
            "long_name": "iteration matrix refactored at the step",
            "flag_values": np.array([0, 1], np.int8), "flag_meanings": "kept refactored"}),
        "ground_acceleration": ("time", result.ground_acceleration,
                                {"units": f"{length}/s^2", "long_name": "ground acceleration"}),
        "energy": (("time", "component"), result.energy,
                   {"units": f"{force}*{length}", "long_name": "cumulative energy account"}),
    })
    coords.update({"time": ("time", result.time, {"units": "s", "long_name": "time",
                                                  "standard_name": "time", "axis": "T"}),
                   "component": ("component", list(result.energy_names),
                                 {"long_name": "energy account"})})
    _snapshots(result, data, coords, "s", "time of the snapshot")
    _far_field(result, data, coords, length)
    return _labelled(result, data, coords)


def _far_field(result, data: dict, coords: dict, length: str) -> None:
    """Add the far field's peaks per ``side`` (left, right) and ``layer`` of cells, located by
    ``layer_top`` and ``layer_bottom`` (depth, down from the surface)
    (:class:`~upliftlab.continuum.dynamics.far_field.FarFieldResponse`); nothing for a result
    without them."""
    far = getattr(result, "far_field", None)
    if far is None:
        return
    dims = ("side", "layer")
    coords.update({
        "side": ("side", ["left", "right"], {"long_name": "side of the box"}),
        "layer": ("layer", np.arange(far.top.size),
                  {"units": "1", "long_name": "layer of cells of the far-field column"}),
        "layer_top": ("layer", far.top, {"units": length, "positive": "down",
                                         "long_name": "depth of the layer's top"}),
        "layer_bottom": ("layer", far.bottom, {"units": length, "positive": "down",
                                               "long_name": "depth of the layer's bottom"})})
    data.update({
        "far_field_shear_strain": (dims, far.shear_strain, {
            "units": "1", "long_name": "peak engineering shear strain |gamma_xy - gamma_xy(0)| "
                                       "of the far-field column"}),
        "far_field_plastic_strain": (dims, far.plastic_strain, {
            "units": "1", "long_name": "peak equivalent plastic strain of the far-field column"}),
        "far_field_plastic_strain_static": (dims, far.plastic_strain_static, {
            "units": "1", "long_name": "equivalent plastic strain of the far-field column at "
                                       "t = 0"}),
        "far_field_yielded": ("layer", far.yielded.astype(np.int8), {
            "long_name": "the layer yielded under the motion on either side",
            "flag_values": np.array([0, 1], np.int8), "flag_meanings": "elastic yielded"})})


def path_to_dataset(path):
    """:func:`path_labelled_data` as an :class:`xarray.Dataset`;
    ``ds.swap_dims(step="theta")`` makes a rotation pushover selectable by θ."""
    return path_labelled_data(path).to_xarray()


def path_labelled_data(path) -> LabelledData:
    """A static path (a StaticPath: a pushover) as a
    :class:`~upliftlab.labelled_data.LabelledData` over its load ``step``, with the footing's
    rotation, settlement and loads as variables and the contact per base node."""
    data, coords = _footing_and_contact(path, "step")
    data.update({
        "shear": (("step", "node"), path.shear, {"units": path.metadata["units"]["stress"],
                                                 "long_name": "shear traction on the soil"}),
        "iterations": ("step", path.iterations, {"units": "1", "long_name": "Newton iterations"}),
        "cuts": ("step", path.cuts, {"units": "1", "long_name": "step cuts"}),
    })
    coords.update({"step": ("step", np.arange(1, path.theta.size + 1),
                            {"units": "1", "long_name": "load step"}),
                   "theta": ("step", path.theta, {"units": "rad",
                                                  "long_name": "footing rotation"})})
    if path.has_fields:
        _snapshots(path, data, coords, "1", "load-step number of the snapshot")
    return _labelled(path, data, coords)


def to_frame(dataset, index: str):
    """The one-dimensional variables along ``index`` (``time`` or ``step``) of a result's
    dataset as a :class:`pandas.DataFrame`; their units are in ``frame.attrs["units"]``."""
    names = [name for name, var in dataset.data_vars.items() if var.dims == (index,)]
    names += [name for name, var in dataset.coords.items()
              if var.dims == (index,) and name != index]
    frame = dataset[names].to_dataframe()[names]
    frame.attrs["units"] = {name: dataset[name].attrs.get("units", "") for name in names}
    frame.attrs["units"][index] = dataset[index].attrs.get("units", "1")
    return frame
