"""XDMF time series of a continuum result for ParaView: the soil fields on the mesh
(:func:`write_xdmf`, ``fields.xdmf``) and the contact along the footing's base on a line mesh
(:func:`write_footing_xdmf`, ``footing.xdmf``), at the same steps with the same time values, so
that ParaView animates both together.

**Time** (:func:`time_axis`). A step's XDMF time value is what drives the analysis: in a dynamic
run the time in seconds; in a rotation (or moment) pushover the footing's rotation θ in rad (the
imposed rotation, or the moment pushover's response); in a vertical pushover the settlement −v
(length, positive down). A value that is not strictly monotonic along the recorded steps (a
cyclic pushover) cannot be a time (ParaView would merge its repeated values), so such a path
falls back to the load-step number 1, 2, … and says so. The values written are the result's
own, unrounded: meshio writes ``repr(float)``, which reads back exactly.

**What the file says it holds.** XDMF 3 allows ``<Information Name=… Value=…/>`` under
``Domain``; each file carries ``time`` (e.g. ``imposed footing rotation theta [rad]``),
``time_quantity``, ``time_units``, ``kind``, ``scene`` and, per field, ``field <name>``: its
meaning, sign and unit. meshio's reader and VTK's XDMF reader read past these elements (neither
shows them); they are there for a reader of the XML and for :func:`read_xdmf`
(``information``). ParaView shows the time value itself.

**Soil fields** (``fields.xdmf`` + ``fields.h5``), on the **linear sub-mesh** of the basis: each
Q2 quad split into four quads on its nine nodes, each P2 triangle into four triangles on its six
nodes (:func:`~upliftlab.meshes.frames.linear_submesh`), so every nodal value is written exactly.
Per snapshot: point data ``displacement`` (3 components, z = 0, so *Warp By Vector* applies) and
``displacement_magnitude``; cell data ``equivalent_plastic_strain`` and, if the result has it,
``max_shear_stress`` (each element's value on its four sub-cells).

**Footing base** (``footing.xdmf`` + ``footing.h5``): the footing's contact nodes at (x, 0, 0),
sorted by x, joined by straight line cells (ParaView's *Plot Data*, X array Points_X, draws
them over x; its *Integrate Variables* integrates line cells by the trapezoid rule and skips
quadratic ones, which is why the cells are straight). Per snapshot, the values the result holds at
that step,
in the signs of :mod:`~upliftlab.continuum.contact.footing` (``upliftlab/docs/conventions.md``):
``contact_pressure`` p_i (force/length², compression positive, zero where open),
``contact_gap`` g_i (length, ≥ 0, zero where closed; both zeros to the contact solve's
round-off, written as the result holds them), ``footing_contact`` (1 closed, 0 open),
``contact_state`` (0 open, 1 stick, 2 slip +x, 3 slip −x), ``contact_force`` P_i = p_i w_i
(force/length; w_i the node's weight ∫ φ_i ds, so Σ P_i is exactly the vertical load N the base
carries, while the trapezoid of p over x only approximates it on a quadratic base), and
``footing_displacement`` (u, v − x θ, 0), the rigid base's motion there.

Each file and its ``.h5`` are written in a private directory beside the target and moved into
place, the ``.h5`` first: they appear complete or not at all, and nothing is written to the
working directory (meshio 5.3.5 would put the ``.h5`` there).
"""

from __future__ import annotations

import io
import json
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...checks import InputError
from ...meshes.frames import linear_submesh, snapshot_rows
from ...results import move_into_place, staging_folder
from .field_history import check_history
from ..contact.footing import OPEN

__all__ = ["TimeAxis", "time_axis", "write_xdmf", "write_footing_xdmf", "read_xdmf"]

ROCKING = ("rotation_pushover", "moment_pushover")


@dataclass(frozen=True, eq=False)
class TimeAxis:
    """The XDMF time values of a result's snapshots: ``values`` (nk), the ``quantity`` they are
    (``time``, ``theta``, ``settlement`` or ``load_step``), its ``units`` and its ``meaning``."""

    values: np.ndarray
    quantity: str
    units: str
    meaning: str

    @property
    def description(self) -> str:
        """``meaning [units]``, the ``time`` Information of the files."""
        return f"{self.meaning} [{self.units}]"


def _units(metadata) -> dict:
    units = metadata.get("units", {}) if isinstance(metadata, dict) else {}
    return json.loads(units) if isinstance(units, str) else (units or {})


def _monotonic(values: np.ndarray) -> bool:
    steps = np.diff(values)
    return bool(np.all(steps > 0.0) or np.all(steps < 0.0))


def time_axis(result) -> TimeAxis:
    """The time values of the snapshots of ``result`` (module docstring): seconds for a
    ``dynamic`` result, θ (rad) for a rotation or moment pushover, the settlement for a
    vertical pushover, the load-step number where those are not strictly monotonic."""
    kind = str(getattr(result, "kind", ""))
    if kind == "dynamic":
        return TimeAxis(np.asarray(result.snapshot_time, dtype=float), "time", "s",
                        "time since the start of the motion")
    footing = np.asarray(result.footing, dtype=float)[snapshot_rows(result)]
    if kind.endswith(ROCKING):
        meaning = ("imposed footing rotation theta" if kind.endswith("rotation_pushover")
                   else "footing rotation theta under the imposed moment")
        axis = TimeAxis(footing[:, 2], "theta", "rad", meaning)
    elif kind.endswith("vertical_pushover"):
        axis = TimeAxis(-footing[:, 1], "settlement", _units(result.metadata).get("length", ""),
                        "imposed footing settlement -v (positive down)")
    else:
        raise InputError(f"result.kind = {kind!r}: expected 'dynamic' or a static path "
                         "(rotation_pushover, moment_pushover, vertical_pushover)")
    if _monotonic(axis.values):
        return axis
    return TimeAxis(np.asarray(result.snapshot_time, dtype=float), "load_step", "1",
                    f"load step number ({axis.meaning} is not monotonic along this path)")


# ---------------------------------------------------------------------------------------------
# Writing
# ---------------------------------------------------------------------------------------------


def _writer_class():
    import meshio
    from meshio.xdmf.time_series import write_xml

    class _Writer(meshio.xdmf.TimeSeriesWriter):
        """meshio's time-series writer with its ``.h5`` beside the ``.xdmf`` (an absolute
        path), not in the working directory; the ``.xdmf`` refers to it by base name. The
        ``.h5`` is made in memory and written by Python when the writer closes
        (:mod:`upliftlab.results`: HDF5 does not survive a full disk)."""

        def __enter__(self):
            import h5py

            self.h5_filename = str(self.filename.with_suffix(".h5").resolve())
            self.h5_buffer = io.BytesIO()
            self.h5_file = h5py.File(self.h5_buffer, "w")
            return self

        def __exit__(self, kind, *_):
            self.h5_file.close()
            if kind is None:
                write_xml(self.filename, self.xdmf_file)
                with open(self.h5_filename, "wb") as fh:
                    fh.write(self.h5_buffer.getbuffer())
                    fh.flush()
                    os.fsync(fh.fileno())

    return _Writer


def _information(result, axis: TimeAxis, fields: dict[str, str]) -> list[tuple[str, str]]:
    meta = result.metadata if isinstance(result.metadata, dict) else {}
    items = [("time", axis.description), ("time_quantity", axis.quantity),
             ("time_units", axis.units), ("kind", str(getattr(result, "kind", ""))),
             ("scene", str(meta.get("scene", "")))]
    return items + [(f"field {name}", text) for name, text in fields.items()]


def _write_series(path, points, cells, steps, axis: TimeAxis, information) -> Path:
    """Write ``steps`` (one (point_data, cell_data) per time value of ``axis``) on the mesh
    (``points``, meshio ``cells``) to ``path`` and its ``.h5``, atomically, with the
    ``information`` (Name, Value) pairs under the Domain."""
    path = Path(path)
    if path.suffix.lower() != ".xdmf":
        raise InputError(f"path = {str(path)!r}: expected a .xdmf file")
    with staging_folder(path) as tmp:
        inner = tmp / path.name
        with _writer_class()(inner) as writer:
            for i, (name, value) in enumerate(information):
                writer.domain.insert(i, ET.Element("Information", Name=name, Value=value))
            writer.write_points_cells(points, cells)
            for t, (point_data, cell_data) in zip(axis.values, steps, strict=True):
                writer.write_data(float(t), point_data=point_data, cell_data=cell_data)
        h5 = inner.with_suffix(".h5")
        if not h5.is_file():
            raise RuntimeError(f"meshio wrote no {h5.name} beside {inner}")
        move_into_place(h5, path.with_suffix(".h5"))
        move_into_place(inner, path)
    return path


def write_xdmf(path, model, result) -> Path:
    """Write the soil fields of every snapshot of ``result`` (a FieldHistory) on ``model``'s
    mesh to ``path`` (``.xdmf``) and its ``.h5`` (module docstring). Returns the path of the
    ``.xdmf``."""
    check_history(result, model)
    axis = time_axis(result)
    units = _units(result.metadata)
    length, stress = units.get("length", ""), units.get("stress", "")
    sub = linear_submesh(model.disc.basis)
    points = np.column_stack((sub.points, np.zeros(len(sub.points))))
    shear = getattr(result, "max_shear_stress", None)
    fields = {"displacement": f"soil displacement (x, y up, z = 0) [{length}]",
              "displacement_magnitude": f"length of the soil displacement [{length}]",
              "equivalent_plastic_strain": "element-averaged equivalent plastic strain [1]"}
    if shear is not None:
        fields["max_shear_stress"] = f"element-averaged (s1 - s3)/2 [{stress}]"

    def steps():
        for k in range(np.size(result.snapshot_time)):
            u = sub.vectors(result.displacement[k])
            cells = {"equivalent_plastic_strain": [sub.cell_values(result.plastic_strain[k])]}
            if shear is not None:
                cells["max_shear_stress"] = [sub.cell_values(shear[k])]
            yield ({"displacement": np.column_stack((u, np.zeros(len(u)))),
                    "displacement_magnitude": np.linalg.norm(u, axis=1)}, cells)

    return _write_series(path, points, [(sub.cell_type, sub.cells)], steps(), axis,
                         _information(result, axis, fields))


def write_footing_xdmf(path, model, result) -> Path:
    """Write the contact along the footing's base at every snapshot of ``result`` on a line
    mesh of its contact nodes to ``path`` (``.xdmf``) and its ``.h5`` (module docstring), with
    the time values of :func:`write_xdmf`. Returns the path of the ``.xdmf``."""
    check_history(result, model)
    axis = time_axis(result)
    units = _units(result.metadata)
    length, stress = units.get("length", ""), units.get("stress", "")
    force = units.get("force/length", "")
    f = model.footing
    x = np.asarray(result.x, dtype=float)
    points = np.column_stack((x, np.zeros((x.size, 2))))
    lines = np.column_stack((np.arange(x.size - 1), np.arange(1, x.size)))
    fields = {
        "contact_pressure": f"normal pressure of the footing on the soil, compression "
                            f"positive, zero where open [{stress}]",
        "contact_gap": f"gap between the footing's base and the soil surface, zero where "
                       f"closed [{length}]",
        "footing_contact": "1 where the node is in contact, 0 where open [1]",
        "contact_state": "0 open, 1 stick (or closed, frictionless), 2 slip +x, 3 slip -x [1]",
        "contact_force": f"nodal normal force contact_pressure x node weight; its sum over the "
                         f"nodes is the vertical load N on the base [{force}]",
        "footing_displacement": f"rigid base motion (u, v - x theta, 0) at the node [{length}]",
    }

    def steps():
        for row in snapshot_rows(result):
            pressure = np.asarray(result.pressure[row], dtype=float)
            status = np.asarray(result.status[row]).astype(np.int32)
            u, v, theta = np.asarray(result.footing[row], dtype=float)
            yield ({"contact_pressure": pressure,
                    "contact_gap": np.asarray(result.gap[row], dtype=float),
                    "footing_contact": (status != OPEN).astype(np.int32),
                    "contact_state": status,
                    "contact_force": pressure * f.weight,
                    "footing_displacement": np.column_stack(
                        (np.full(x.size, u), v - x * theta, np.zeros(x.size)))}, {})

    return _write_series(path, points, [("line", lines)], steps(), axis,
                         _information(result, axis, fields))


# ---------------------------------------------------------------------------------------------
# Reading
# ---------------------------------------------------------------------------------------------


def read_xdmf(path) -> dict:
    """Read a time series written by :func:`write_xdmf` or :func:`write_footing_xdmf`:
    ``points`` (np, 3), ``cells`` (list of meshio cell blocks), ``times`` (nk), ``point_data``
    and ``cell_data`` (one dict per step; cell data as single arrays) and ``information``
    ({Name: Value} of the Domain's Information elements)."""
    import meshio

    path = Path(path)
    if not path.is_file():
        raise InputError(f"path = {str(path)!r}: no such file")
    with meshio.xdmf.TimeSeriesReader(path) as reader:
        points, cells = reader.read_points_cells()
        times, point_data, cell_data = [], [], []
        for k in range(reader.num_steps):
            t, pd, cd = reader.read_data(k)
            times.append(t)
            point_data.append(pd)
            cell_data.append({name: np.concatenate(blocks) for name, blocks in cd.items()})
        information = {item.get("Name"): item.get("Value")
                       for item in reader.domain.findall("Information")}
    return {"points": points, "cells": cells, "times": np.array(times),
            "point_data": point_data, "cell_data": cell_data, "information": information}
