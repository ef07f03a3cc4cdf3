"""What every foundation law's record is: a frozen dataclass whose fields are the law's own keys
of the scene's ``[foundation]`` table, tagged by the law's ``name``.

A record is read from the table by its :meth:`LawRecord.read` (every check names the field, the
value and the valid range), written back by :meth:`LawRecord.table` (its fields that are set),
and checked against the rest of the foundation by :meth:`LawRecord.check`. It says what a scene
asks for; what a model makes of it lives with the model (:mod:`upliftlab.reduced.laws`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import ClassVar

from ..table import Table
from ...units import UnitSystem

__all__ = ["LawContext", "LawRecord"]


@dataclass(frozen=True)
class LawContext:
    """What a law's reader may need of the rest of the foundation: its ``support``, its number
    of ``springs`` and the scene's ``units``."""

    support: str
    springs: int
    units: UnitSystem


def _plain(value):
    return [_plain(v) for v in value] if isinstance(value, tuple) else value


class LawRecord:
    """Base of the law records (each a ``@dataclass(frozen=True, eq=False, kw_only=True)``).

    Class attributes: ``name`` the law's name (``foundation.law``); ``curved`` why the event
    stepper cannot tabulate it ("" for a law that is piecewise affine in each of its modes);
    ``inert`` the keys it reads and keeps (a scene's cases may switch to a law they act on)
    but that do not act on it, each with the reason an override of it is refused.

    A record equals a record of the same law with the same fields. Comparing one with a name
    (``foundation.law == "qz"``, the form of the flat records before them) is a mistake that
    would quietly be false: it raises, and ``foundation.law.name`` is the name.
    """

    name: ClassVar[str] = ""
    curved: ClassVar[str] = ""
    inert: ClassVar[dict[str, str]] = {}

    @classmethod
    def keys(cls) -> tuple[str, ...]:
        """The law's own keys of ``[foundation]``: its fields, in the order it writes them."""
        return tuple(f.name for f in dataclasses.fields(cls))

    @classmethod
    def read(cls, table: Table, context: LawContext) -> LawRecord:
        """The record of the law's keys in ``table`` (a law without keys: its only record)."""
        return cls()

    def table(self) -> dict:
        """The law's keys as a scene file holds them: every field that is set (not None)."""
        return {k: _plain(getattr(self, k)) for k in self.keys() if getattr(self, k) is not None}

    def check(self, foundation) -> None:
        """Refuse a foundation whose other fields this law cannot take (an :class:`InputError`);
        called once the whole ``[foundation]`` table is read."""

    def _values(self) -> tuple:
        return tuple(getattr(self, k) for k in self.keys())

    def __eq__(self, other):
        if isinstance(other, str):
            raise TypeError(f"foundation.law is a law record ({type(self).__name__}), not a "
                            f"name: compare foundation.law.name with {other!r}")
        if type(other) is not type(self):
            return NotImplemented
        return self._values() == other._values()

    def __hash__(self):
        return hash((type(self), self._values()))
