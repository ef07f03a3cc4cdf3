"""Soil fields of a continuum result: element averages of quadrature-point fields, the maximum
shear stress, the steps at which fields are recorded, and the provenance every result carries.

The pushovers take ``record_fields``: ``True`` records every step, a sequence of step indices
records those (negative indices count from the end). Each recorded step keeps the soil
displacement DOF vector (the model basis's ordering), and the element averages (quadrature
weights × Jacobians) of the equivalent plastic strain and of the maximum shear stress
(σ1 − σ3)/2 of the total stress (geostatic included). They are what
:mod:`~upliftlab.continuum.output.series` writes to XDMF and renders. Recording changes no result.
"""

from __future__ import annotations

from dataclasses import asdict

import numpy as np

from ...checks import InputError
from ...provenance import provenance

__all__ = ["element_average", "max_shear_stress", "snapshot_steps", "field_coordinates",
           "field_snapshots",
           "result_metadata"]


def element_average(model, values: np.ndarray) -> np.ndarray:
    """The area-weighted average per element of a quadrature-point field (…, nelems, nqp)."""
    dx = model.disc.dx
    return np.sum(values * dx, axis=-1) / np.sum(dx, axis=-1)


def max_shear_stress(stress: np.ndarray) -> np.ndarray:
    """(σ1 − σ3)/2 of a stress field (3, 3, …), from its principal values."""
    batch = stress.shape[2:]
    flat = np.moveaxis(stress.reshape(3, 3, -1), -1, 0)
    principal = np.linalg.eigvalsh(0.5 * (flat + np.swapaxes(flat, 1, 2)))
    return (0.5 * (principal[:, -1] - principal[:, 0])).reshape(batch)


def snapshot_steps(record_fields, steps: int) -> np.ndarray | None:
    """The step indices ``record_fields`` asks for (None: none), checked before any work."""
    if record_fields is None or record_fields is False:
        return None
    if record_fields is True:
        return np.arange(steps)
    try:
        chosen = np.asarray(list(record_fields))
    except TypeError:
        chosen = np.asarray([record_fields])
    if chosen.ndim != 1 or chosen.size == 0 or chosen.dtype.kind not in "iu":
        raise InputError(f"record_fields = {record_fields!r}: expected True, False or a "
                         "non-empty list of step indices")
    if chosen.min() < -steps or chosen.max() >= steps:
        raise InputError(f"record_fields = {chosen.tolist()}: step indices must lie in "
                         f"[{-steps}, {steps - 1}] for {steps} steps")
    return np.unique(np.where(chosen < 0, chosen + steps, chosen))


def field_coordinates(model) -> dict:
    """Where the soil fields live, as the keyword arguments of a result record: ``dof_xy``
    (ndofs, 2) the (x, y) of each displacement DOF's node (length), ``dof_direction`` (ndofs)
    0 for an x and 1 for a y displacement, and ``element_xy`` (nelems, 2) each element's
    centroid (the area-weighted mean of its quadrature points)."""
    basis = model.disc.basis
    direction = np.zeros(basis.N, dtype=np.int8)
    direction[basis.split_indices()[1]] = 1
    return dict(dof_xy=np.asarray(basis.doflocs).T.copy(), dof_direction=direction,
                element_xy=element_average(model, model.disc.qp_coordinates).T.copy())


def field_snapshots(model, states, snapshots: np.ndarray | None) -> dict:
    """The recorded fields of ``states`` at the steps ``snapshots`` (None: none) and where they
    live (:func:`field_coordinates`), as the keyword arguments of a result record."""
    if snapshots is None:
        return {}
    chosen = [states[k] for k in snapshots]
    return dict(
        **field_coordinates(model),
        snapshot_step=snapshots,
        displacement=np.array([s.u for s in chosen]),
        plastic_strain=np.array([element_average(model, s.material.equivalent_plastic_strain)
                                 for s in chosen]),
        max_shear_stress=np.array([element_average(model, max_shear_stress(s.stress))
                                   for s in chosen]))


def result_metadata(model, kind: str, extra) -> dict:
    """The provenance of a continuum result of analysis ``kind``: scene, soil, options, mesh,
    element, DOFs, K0 and units, with ``extra`` entries."""
    scene = model.scene
    units = {}
    if scene is not None:
        u = scene.units
        units = {"length": u.length, "force/length": f"{u.force}/{u.length}",
                 "moment/length": f"{u.force}*{u.length}/{u.length}",
                 "stress": f"{u.force}/{u.length}^2"}
    return provenance(analysis=kind, model="continuum", scene=scene.name if scene else "",
                      scene_digest=scene.digest if scene else "", soil=asdict(model.soil),
                      options=asdict(model.options), mesh=model.mesh_parameters,
                      element=model.disc.element, intorder=model.disc.intorder,
                      dofs=model.dofs, k0=model.k0, units=units, **(extra or {}))
