"""The elasto-plastic foundation law's record (Ewing's Cases B and C, Fig. 6): each spring
yields in compression at its yield force, set one of three ways."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ... import bounds
from ...checks import InputError
from ..table import Table, in_range, numbers
from .base import LawContext, LawRecord

__all__ = ["ElastoplasticLaw", "YIELD_KEYS", "read_yield_multiple"]

#: The keys that set the springs' yield forces; at most one is given.
YIELD_KEYS = ("yield_multiple", "capacity_multiple", "yield_forces")

#: The check of a multiple of the weight or of a static force (yield, capacity): > 1.
MULTIPLE = in_range(1.0, 1e6, low_open=True)


def read_yield_multiple(table: Table) -> float:
    """``foundation.yield_multiple`` (default 3, the paper's)."""
    return table.get("yield_multiple", MULTIPLE, 3.0)


@dataclass(frozen=True, eq=False, kw_only=True)
class ElastoplasticLaw(LawRecord):
    """Elasto-plastic compression-only springs: a spring yields at ``yield_multiple`` times its
    static compression (the paper's 3); or, with ``capacity_multiple``, at a uniform bearing
    pressure — the bed's capacity, that multiple of the weight, shared over the springs'
    tributary widths, whatever their stiffness; or at the given ``yield_forces`` (force), one
    per spring in the order of ``foundation.dashpots``. Exactly one of the three is set (the
    others None); with the last two the springs that reach their yield force under the weight
    start at it."""

    name: ClassVar[str] = "elastoplastic"

    yield_multiple: float | None = 3.0
    capacity_multiple: float | None = None
    yield_forces: tuple[float, ...] | None = None

    @classmethod
    def read(cls, table: Table, context: LawContext) -> ElastoplasticLaw:
        given = [key for key in YIELD_KEYS if table.has(key)]
        if len(given) > 1:
            raise InputError(f"foundation.{given[0]} with foundation.{given[1]}: each sets the "
                             "elasto-plastic springs' yield forces (a multiple of each static "
                             "compression, a uniform bearing capacity, or one force per "
                             "spring); give one of them")
        if table.has("yield_forces"):
            return cls(yield_multiple=None, yield_forces=_yield_forces(table, context))
        if table.has("capacity_multiple"):
            return cls(yield_multiple=None,
                       capacity_multiple=table.get("capacity_multiple", MULTIPLE))
        return cls(yield_multiple=read_yield_multiple(table))


def _yield_forces(table: Table, context: LawContext) -> tuple[float, ...]:
    """``foundation.yield_forces``: one force per spring, each within the physical range."""
    forces = table.get("yield_forces", numbers)
    if len(forces) != context.springs:
        raise InputError(f"foundation.yield_forces has {len(forces)} entries: give one per "
                         f"spring ({context.springs})")
    for i, f in enumerate(forces):
        bounds.check(f"foundation.yield_forces[{i}]", f, "force", context.units)
    return forces
