"""The elastic foundation law's record (Ewing's Case A): linear compression-only springs."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ..table import Table
from .base import LawContext, LawRecord
from .elastoplastic import read_yield_multiple

__all__ = ["ElasticLaw"]


@dataclass(frozen=True, eq=False, kw_only=True)
class ElasticLaw(LawRecord):
    """Linear springs that never yield. ``yield_multiple`` is read and kept, as a scene's cases
    may switch the law to elasto-plastic (whose yield multiple it is), but it does not act."""

    name: ClassVar[str] = "elastic"
    inert: ClassVar[dict[str, str]] = {
        "yield_multiple": "the yield multiple acts only with foundation.law = 'elastoplastic' "
                          "(this scene's law is 'elastic')"}

    yield_multiple: float = 3.0

    @classmethod
    def read(cls, table: Table, context: LawContext) -> ElasticLaw:
        return cls(yield_multiple=read_yield_multiple(table))
