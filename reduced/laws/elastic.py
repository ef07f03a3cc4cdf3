"""The elastic foundation law (Ewing's Case A): linear springs at their bonded static
compressions that never yield. Its springs are the elasto-plastic law's with Fy = ∞, so its
compiled forms are that law's (:mod:`.elastoplastic`)."""

from __future__ import annotations

import numpy as np

from ...scenes.laws import ElasticLaw
from .base import Bed, Law
from .elastoplastic import BONDED, UPLIFT, elastic_static_forces, support_kind

__all__ = ["LAW", "springs"]


def springs(law: ElasticLaw, bed: Bed, table: np.ndarray) -> tuple[np.ndarray, float]:
    """The bed's springs: F0 from the bonded equilibrium under the weight, no yield."""
    F0, theta = elastic_static_forces(bed)
    table["kind"] = support_kind(bed.support)
    table["f0"] = F0
    table["fy"] = np.inf
    return table, theta


LAW = Law(record=ElasticLaw, springs=springs, kinds=(UPLIFT, BONDED))
