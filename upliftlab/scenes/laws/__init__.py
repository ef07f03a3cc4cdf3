"""The foundation laws a scene can name (``foundation.law``): one record each, found by name.

A law's record (:class:`~.base.LawRecord`) holds what a scene says about that law — its own keys
of the ``[foundation]`` table, read and checked with the same messages as every other field —
and nothing of the other laws. A :class:`~upliftlab.scenes.Foundation` carries its law's record
in ``foundation.law``, tagged by ``foundation.law.name``; a key of another law is refused.

What a model does with a law lives with the model, found there by the same name: the reduced
model's spring builder and compiled forms in :mod:`upliftlab.reduced.laws`. The records live
here, in the scene package, because a scene is read before, and without, any model, and a model
imports the scene (dependencies point one way).

Adding a law: its record module here and its entry in :data:`LAWS`, its model module and entry
in :data:`upliftlab.reduced.laws.LAWS`, and its tests. A law defined outside upliftlab (a
plug-in, or a test) is one module and registers both halves at once
(:func:`upliftlab.reduced.laws.register`).
"""

from __future__ import annotations

from ...checks import InputError
from ..table import Table, choice
from .base import LawContext, LawRecord
from .elastic import ElasticLaw
from .elastoplastic import YIELD_KEYS, ElastoplasticLaw
from .macro import MacroLaw
from .qz import QZ_ELASTIC_RANGE_MAX, QZ_EXPONENT_MAX, QZ_SOIL_NAMES, SUCTION_MAX, QzLaw

__all__ = ["LAWS", "LawContext", "LawRecord", "ElasticLaw", "ElastoplasticLaw", "QzLaw",
           "MacroLaw", "YIELD_KEYS", "QZ_SOIL_NAMES", "QZ_EXPONENT_MAX", "QZ_ELASTIC_RANGE_MAX",
           "SUCTION_MAX", "register", "read_law", "check_overrides", "curved_law"]

#: The laws by name, in the order their names are listed.
LAWS: dict[str, type[LawRecord]] = {law.name: law for law in (ElasticLaw, ElastoplasticLaw,
                                                               QzLaw, MacroLaw)}


def register(record: type[LawRecord]) -> None:
    """Add a law's record class to :data:`LAWS` (a name already taken by another is refused)."""
    if not record.name or LAWS.get(record.name, record) is not record:
        raise ValueError(f"law name {record.name!r}: empty, or taken by "
                         f"{LAWS.get(record.name)!r}")
    LAWS[record.name] = record


def read_law(table: Table, context: LawContext) -> LawRecord:
    """The record of ``foundation.law`` (default ``elastic``) from a ``[foundation]`` table:
    a key of another law is refused, then the law reads its own."""
    law = LAWS[table.get("law", choice(tuple(LAWS)), "elastic")]
    _refuse_foreign_keys(table, law)
    record = law.read(table, context)
    table.used.update(law.keys())
    return record


def _refuse_foreign_keys(table: Table, law: type[LawRecord]) -> None:
    own = set(law.keys())
    for other in LAWS.values():
        for key in other.keys():
            if key not in own and table.has(key):
                readers = " or ".join(repr(n) for n, r in LAWS.items() if key in r.keys())
                raise InputError(f"foundation.{key} is read only with foundation.law = "
                                 f"{readers} (law is {law.name!r}); remove it or set the law")


def check_overrides(law: LawRecord, overrides) -> None:
    """Refuse a ``--set`` override of a key the scene's law reads but that does not act on it
    (``foundation.yield_multiple`` with an elastic law): it would have no effect."""
    for item in overrides:
        key = item.split("=", 1)[0].strip()
        if key.startswith("foundation.") and key[len("foundation."):] in law.inert:
            raise InputError(f"--set {item!r}: has no effect: "
                             f"{law.inert[key[len('foundation.'):]]}")


def curved_law(name) -> type[LawRecord] | None:
    """The record class of law ``name`` if the event stepper cannot tabulate it, else None."""
    law = LAWS.get(name) if isinstance(name, str) else None
    return law if law is not None and law.curved else None
