"""Outputs of continuum analyses: an XDMF time series of the soil fields for ParaView, the
uplift-zone pictures (through :mod:`upliftlab.meshes.render`), the M–θ figure of a pushover,
and one-line summaries.

**What a result must offer** (:class:`FieldHistory`, duck typed). A static path whose pushover
recorded fields (``record_fields=True``, :mod:`~upliftlab.continuum.statics`) and a dynamic
result both offer: ``time`` (nt; s, or the load-step number of a static path), ``footing``
(nt, 3: u, v, θ), ``x`` (nc) the contact nodes, ``pressure`` and ``gap`` (nt, nc),
``contact_length``, ``N``, ``M``, ``H`` (nt), ``snapshot_time`` (nk), ``displacement``
(nk, ndofs) the soil DOF vector in the model basis's ordering, ``plastic_strain`` (nk, nelems)
element averages, ``metadata`` (dict) and ``save(path)``. Optional: ``max_shear_stress``
(nk, nelems), and ``snapshot_step`` (nk), the history row of each snapshot (static paths; a
dynamic result's snapshots are matched to the nearest ``time``).

**XDMF** (:func:`write_xdmf`): meshio's time series (XDMF 3 with one ``.h5`` of the same stem
beside it), written on the **linear sub-mesh** of the basis: each Q2 quad split into four quads
on its nine nodes, each P2 triangle into four triangles on its six nodes
(:func:`~upliftlab.meshes.frames.linear_submesh`), so every nodal value is written exactly.
Per snapshot, at time ``snapshot_time``: point data ``displacement`` (3 components, z = 0, so
ParaView's *Warp By Vector* applies) and ``displacement_magnitude``; cell data
``equivalent_plastic_strain`` and, if the result has it, ``max_shear_stress`` (each element's
value on its four sub-cells). Both files are written in a private directory beside the target
and moved into place, the ``.h5`` first: they appear complete or not at all, and nothing is
written to the working directory (meshio 5.3.5 would put the ``.h5`` there).

**M–θ figure** (:func:`moment_rotation_figure`): M, contact length c/B and settlement against θ,
with the closed forms computed here (``upliftlab.continuum`` never imports the reduced
model): the tensionless uniform Winkler bed of a scene whose foundation is one (the rigid strip on
compression-only springs: M/M_up = 3 − 2√(θ_up/θ), c/B = √(θ_up/θ), θ_up = 2N/(kB²), k = K_v/B),
the rigid strip on an elastic half-plane (M = K_r θ to θ_on = 2N(1 − ν)/(πGB), then M/(NB) = 1/2 −
θ_on/(4θ), c/B = θ_on/θ), and for undrained soil the V–M capacity M = B V_ult v(1 − v)/2 (the
effective-width capacity of a strip on Tresca soil, Meyerhof 1953).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Protocol

import numpy as np

from ..anchors import half_plane_rocking, prandtl_capacity, winkler_rocking  # noqa: F401
from ..checks import InputError
from ..meshes.render import linear_submesh, snapshot_rows
from ..results import atomic_path
from .summaries import (dynamic_summary, pushover_summary, rotation_schedule,  # noqa: F401
                        summary_line)

__all__ = ["FieldHistory", "check_history", "write_xdmf", "read_xdmf", "winkler_rocking",
           "half_plane_rocking", "moment_rotation_figure", "save_figure", "rotation_schedule",
           "pushover_summary",
           "dynamic_summary", "summary_line", "write_outputs"]


class FieldHistory(Protocol):
    """The duck type the output functions read (module docstring)."""

    time: np.ndarray
    footing: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    contact_length: np.ndarray
    N: np.ndarray
    M: np.ndarray
    H: np.ndarray
    snapshot_time: np.ndarray
    displacement: np.ndarray
    plastic_strain: np.ndarray
    metadata: dict

    def save(self, path): ...


_REQUIRED = ("time", "footing", "x", "pressure", "gap", "contact_length", "N", "M", "H",
             "snapshot_time", "displacement", "plastic_strain", "metadata")


def check_history(result, model=None) -> None:
    """Refuse a result that lacks a :class:`FieldHistory` attribute or recorded no fields, or
    whose fields do not fit ``model``."""
    missing = [name for name in _REQUIRED if not hasattr(result, name)]
    if missing:
        raise InputError(f"result ({type(result).__name__}): lacks {', '.join(missing)}; "
                         "expected a FieldHistory (continuum.output)")
    if getattr(result, "displacement", None) is None or np.size(result.snapshot_time) == 0:
        raise InputError(f"result ({type(result).__name__}): no soil fields recorded (pass "
                         "record_fields=True to the pushover)")
    nk = np.size(result.snapshot_time)
    shapes = {"displacement": np.shape(result.displacement),
              "plastic_strain": np.shape(result.plastic_strain)}
    if any(len(s) != 2 or s[0] != nk for s in shapes.values()):
        raise InputError(f"result: {shapes} do not have {nk} snapshots")
    if model is not None and (shapes["displacement"][1] != model.disc.ndofs
                              or shapes["plastic_strain"][1] != model.mesh.nelements):
        raise InputError(f"result: fields {shapes} do not fit the model ({model.disc.ndofs} "
                         f"DOFs, {model.mesh.nelements} elements)")


# ---------------------------------------------------------------------------------------------
# XDMF
# ---------------------------------------------------------------------------------------------


def _writer_class():
    import meshio

    class _Writer(meshio.xdmf.TimeSeriesWriter):
        """meshio's time-series writer with its ``.h5`` beside the ``.xdmf`` (an absolute
        path), not in the working directory; the ``.xdmf`` refers to it by base name."""

        def __enter__(self):
            import h5py

            self.h5_filename = str(self.filename.with_suffix(".h5").resolve())
            self.h5_file = h5py.File(self.h5_filename, "w")
            return self

    return _Writer


def write_xdmf(path, model, result) -> Path:
    """Write the soil fields of every snapshot of ``result`` (a :class:`FieldHistory`) on
    ``model``'s mesh to ``path`` (``.xdmf``) and its ``.h5`` (module docstring). Returns the
    path of the ``.xdmf``."""
    path = Path(path)
    if path.suffix.lower() != ".xdmf":
        raise InputError(f"path = {str(path)!r}: expected a .xdmf file")
    check_history(result, model)
    sub = linear_submesh(model.disc.basis)
    points = np.column_stack((sub.points, np.zeros(len(sub.points))))
    shear = getattr(result, "max_shear_stress", None)
    path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix=f".{path.name}.", dir=path.parent) as tmp:
        inner = Path(tmp) / path.name
        with _writer_class()(inner) as writer:
            writer.write_points_cells(points, [(sub.cell_type, sub.cells)])
            for k, t in enumerate(np.asarray(result.snapshot_time, dtype=float)):
                u = sub.vectors(result.displacement[k])
                vector = np.column_stack((u, np.zeros(len(u))))
                cells = {"equivalent_plastic_strain": [sub.cell_values(result.plastic_strain[k])]}
                if shear is not None:
                    cells["max_shear_stress"] = [sub.cell_values(shear[k])]
                writer.write_data(float(t), point_data={
                    "displacement": vector,
                    "displacement_magnitude": np.linalg.norm(u, axis=1)}, cell_data=cells)
        h5 = inner.with_suffix(".h5")
        if not h5.is_file():
            raise RuntimeError(f"meshio wrote no {h5.name} beside {inner}")
        os.replace(h5, path.with_suffix(".h5"))
        os.replace(inner, path)
    return path


def read_xdmf(path) -> dict:
    """Read a time series written by :func:`write_xdmf`: ``points`` (np, 3), ``cells``
    (list of meshio cell blocks), ``times`` (nk), ``point_data`` and ``cell_data`` (one dict per
    step; cell data as single arrays)."""
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
    return {"points": points, "cells": cells, "times": np.array(times),
            "point_data": point_data, "cell_data": cell_data}


def _soil(metadata: dict) -> dict:
    soil = metadata.get("soil", {})
    if isinstance(soil, str):
        import json
        soil = json.loads(soil)
    return soil or {}


def _units(metadata: dict) -> dict:
    units = metadata.get("units", {})
    if isinstance(units, str):
        import json
        units = json.loads(units)
    return units or {}


def _brackets(unit: str) -> str:
    unit = unit.replace("^2", "²").replace("*", "·")
    return f" [{unit}]" if unit else ""


def moment_rotation_figure(path, scene=None):
    """The matplotlib figure of a rotation (or moment) pushover ``path``: M, c/B and
    settlement against θ, with the closed forms of the module docstring (the Winkler bed only
    if ``scene.foundation`` is a uniform ``winkler`` layout)."""
    from matplotlib.figure import Figure

    if not str(getattr(path, "kind", "")).endswith(("rotation_pushover", "moment_pushover")):
        raise InputError(f"path.kind = {getattr(path, 'kind', None)!r}: the M–θ figure needs a "
                         "rotation or moment pushover")
    theta, N, B = np.asarray(path.theta), float(np.median(path.N)), float(path.width)
    soil, units = _soil(path.metadata), _units(path.metadata)
    fine = np.linspace(min(0.0, theta.min()), theta.max(), 400)
    fig = Figure(figsize=(7.5, 9.0), dpi=100)
    ax_m, ax_c, ax_s = fig.subplots(3, 1, sharex=True)
    ax_m.plot(theta, path.M, "o-", color="black", ms=3, label="continuum (FE)")
    ax_c.plot(theta, path.contact_length / B, "o-", color="black", ms=3, label="continuum (FE)")
    ax_s.plot(theta, -np.asarray(path.v), "o-", color="black", ms=3, label="continuum (FE)")
    if soil.get("youngs_modulus"):
        E, nu = float(soil["youngs_modulus"]), float(soil["poisson_ratio"])
        ref = half_plane_rocking(fine, N, B, E / (2 * (1 + nu)), nu)
        ax_m.plot(fine, ref["M"], ":", color="tab:blue", lw=2, label="elastic half-plane")
        ax_c.plot(fine, ref["c"] / B, ":", color="tab:blue", lw=2, label="elastic half-plane")
    foundation = getattr(scene, "foundation", None)
    if foundation is not None and foundation.layout == "winkler" and foundation.support == "uplift":
        k = foundation.stiffness / foundation.width
        ref = winkler_rocking(fine, N, B, k)
        label = f"tensionless Winkler bed, k = K_v/B = {k:.4g}"
        ax_m.plot(fine, ref["M"], "--", color="tab:red", lw=1.5, label=label)
        ax_c.plot(fine, ref["c"] / B, "--", color="tab:red", lw=1.5, label=label)
        ax_s.plot(fine, ref["settlement"], "--", color="tab:red", lw=1.5, label=label)
    cu = soil.get("undrained_strength")
    if soil.get("model") in ("tresca", "von_mises") and cu:
        V_ult = prandtl_capacity(float(cu), B)
        v = N / V_ult
        if 0.0 < v < 1.0:
            ax_m.axhline(B * V_ult * v * (1 - v) / 2, color="tab:green", ls="-.",
                         label=f"V–M capacity at v = {v:.2f}")
    ax_m.set_ylabel(f"M{_brackets(units.get('moment/length', ''))}")
    ax_c.set_ylabel("contact length c/B [–]")
    ax_c.set_ylim(0.0, 1.05)
    ax_s.set_ylabel(f"settlement −v{_brackets(units.get('length', ''))}")
    ax_s.set_xlabel("footing rotation θ [rad]")
    for ax in (ax_m, ax_c, ax_s):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    meta = path.metadata
    fig.suptitle(f"{meta.get('scene', '')}: rotation pushover at N = {N:.4g}"
                 f"{_brackets(units.get('force/length', ''))}\n{meta.get('element', '')}, "
                 f"{meta.get('dofs', '')} DOFs, soil {soil.get('model', '')}", fontsize=11)
    fig.tight_layout()
    return fig


def save_figure(fig, path) -> Path:
    """Write a matplotlib figure to PNG atomically."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png")
    return Path(path)


# ---------------------------------------------------------------------------------------------
# Everything a run writes
# ---------------------------------------------------------------------------------------------


def write_outputs(directory, model, result, *, scene=None, renders: bool = True,
                  scale: float | None = None, progress=None) -> dict[str, Path]:
    """Write a run's files into ``directory``: ``result.nc`` (``result.save``), ``fields.xdmf``
    and ``fields.h5``, ``uplift.png`` (the snapshot of largest |θ|) and ``uplift.gif`` (every
    snapshot; skipped if not ``renders``), and for a pushover ``moment_rotation.png``.
    ``progress(message)`` reports each file. Returns {name: path}."""
    from ..meshes.render import animate_uplift, render_uplift

    check_history(result, model)
    directory = Path(directory)
    say = progress or (lambda message: None)
    written: dict[str, Path] = {}
    written["result.nc"] = Path(result.save(directory / "result.nc"))
    say(f"wrote {written['result.nc']}")
    written["fields.xdmf"] = write_xdmf(directory / "fields.xdmf", model, result)
    written["fields.h5"] = directory / "fields.h5"
    say(f"wrote {written['fields.xdmf']} and fields.h5 ({np.size(result.snapshot_time)} steps)")
    if str(getattr(result, "kind", "")).endswith(("rotation_pushover", "moment_pushover")):
        fig = moment_rotation_figure(result, scene=scene)
        written["moment_rotation.png"] = save_figure(fig, directory / "moment_rotation.png")
        say(f"wrote {written['moment_rotation.png']}")
    if renders:
        title = result.metadata.get("scene", "") or (scene.name if scene else "")
        rows = snapshot_rows(result)
        peak = int(np.argmax(np.abs(np.asarray(result.footing)[rows, 2])))
        written["uplift.png"] = Path(render_uplift(directory / "uplift.png", result,
                                                   model.disc.basis, model.width,
                                                   snapshot=peak, scale=scale, title=title))
        say(f"wrote {written['uplift.png']}")
        written["uplift.gif"] = Path(animate_uplift(directory / "uplift.gif", result,
                                                    model.disc.basis, model.width, scale=scale,
                                                    title=title))
        say(f"wrote {written['uplift.gif']} ({np.size(result.snapshot_time)} frames)")
    return written

