"""What a continuum result must offer to be written as meshes, pictures and summaries: the
:class:`FieldHistory` duck type, and :func:`check_history`, which refuses a result that does not
fit it (or does not fit the model it is written on) before any file is touched.

A static path whose pushover recorded fields (``record_fields=True``,
:mod:`~upliftlab.continuum.statics.analyses`) and a dynamic result both offer: ``time`` (nt; s, or
the
load-step number of a static path), ``footing`` (nt, 3: u, v, θ), ``x`` (nc) the contact nodes,
``pressure`` and ``gap`` (nt, nc), ``status`` (nt, nc; the contact state of
:mod:`~upliftlab.continuum.contact.footing`), ``contact_length``, ``N``, ``M``, ``H`` (nt),
``snapshot_time`` (nk), ``displacement`` (nk, ndofs) the soil DOF vector in the model basis's
ordering, ``plastic_strain`` (nk, nelems) element averages, ``metadata`` (dict) and
``save(path)``. Optional: ``kind`` (``"dynamic"``, or the static path's kind), ``max_shear_stress``
(nk, nelems), and ``snapshot_step`` (nk), the history row of each snapshot (a dynamic result's
snapshots are otherwise matched to the nearest ``time``).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from ...checks import InputError

__all__ = ["FieldHistory", "check_history"]


class FieldHistory(Protocol):
    """The duck type the output functions read (module docstring)."""

    time: np.ndarray
    footing: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    gap: np.ndarray
    status: np.ndarray
    contact_length: np.ndarray
    N: np.ndarray
    M: np.ndarray
    H: np.ndarray
    snapshot_time: np.ndarray
    displacement: np.ndarray
    plastic_strain: np.ndarray
    metadata: dict

    def save(self, path): ...


_REQUIRED = ("time", "footing", "x", "pressure", "gap", "status", "contact_length", "N", "M",
             "H", "snapshot_time", "displacement", "plastic_strain", "metadata")


def check_history(result, model=None) -> None:
    """Refuse a result that lacks a :class:`FieldHistory` attribute or recorded no fields, or
    whose fields or footing nodes do not fit ``model``."""
    missing = [name for name in _REQUIRED if not hasattr(result, name)]
    if missing:
        raise InputError(f"result ({type(result).__name__}): lacks {', '.join(missing)}; "
                         "expected a FieldHistory (continuum.field_history)")
    if getattr(result, "displacement", None) is None or np.size(result.snapshot_time) == 0:
        raise InputError(f"result ({type(result).__name__}): no soil fields recorded (pass "
                         "record_fields=True to the pushover)")
    nk = np.size(result.snapshot_time)
    shapes = {"displacement": np.shape(result.displacement),
              "plastic_strain": np.shape(result.plastic_strain)}
    if any(len(s) != 2 or s[0] != nk for s in shapes.values()):
        raise InputError(f"result: {shapes} do not have {nk} snapshots")
    nt, nc = np.size(result.time), np.size(result.x)
    contact = {name: np.shape(getattr(result, name)) for name in ("pressure", "gap", "status")}
    if any(s != (nt, nc) for s in contact.values()):
        raise InputError(f"result: contact histories {contact} are not ({nt} steps, {nc} nodes)")
    if model is None:
        return
    if shapes["displacement"][1] != model.disc.ndofs or \
            shapes["plastic_strain"][1] != model.mesh.nelements:
        raise InputError(f"result: fields {shapes} do not fit the model ({model.disc.ndofs} "
                         f"DOFs, {model.mesh.nelements} elements)")
    if not np.array_equal(np.asarray(result.x), model.footing.x):
        raise InputError(f"result.x: {nc} footing nodes that are not the model's "
                         f"{model.footing.nodes} contact nodes")
