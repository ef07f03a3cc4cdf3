"""The reduced model's foundation laws, found by name (:data:`LAWS`).

Each law is one module (the q–z law, larger, one folder): its builder, which turns the scene's
record of the law (:mod:`upliftlab.scenes.laws`, the law's own keys of ``[foundation]``) into
the bed's rows of the spring table, and its compiled forms, side by side; :class:`~.base.Law`
is its entry here. :mod:`.elastic` and :mod:`.elastoplastic` (Ewing's Cases A–C; the elastic
springs are the elasto-plastic ones with Fy = ∞, and share their compiled forms), :mod:`.qz`
(hysteretic q–z springs), and :mod:`.macro` (the macro-element: one element on the base's
three DOFs instead of springs, :mod:`.macro.element`). :mod:`.spring` holds the spring record
they all fill.

The spring record and the history (:data:`SPRING_DTYPE`, :data:`HISTORY_DTYPE`) are the base
fields of :mod:`.spring` followed by the fields of each law that has its own. The compiled
integrators reach a law's forms through :mod:`upliftlab.reduced.kernels.laws`, which
dispatches a spring on its kind: a law whose springs are of an existing kind (the elastic law,
or a plug-in that builds elasto-plastic springs its own way) plugs in here alone; a law with
forms of its own also adds its kind to that dispatch.

A law defined outside upliftlab (a plug-in, or a test) registers its scene record and its
entry at once with :func:`register`.
"""

from __future__ import annotations

import numpy as np

from ...checks import InputError
from ...scenes import laws as scene_laws
from . import elastic, elastoplastic, qz
from .base import Base, Bed, Law
from .macro import element as macro_element
from .spring import HISTORY_FIELDS, SPRING_FIELDS

__all__ = ["LAWS", "Law", "Bed", "Base", "SPRING_DTYPE", "HISTORY_DTYPE", "law_of", "register",
           "initial_history", "curved_kinds"]

#: The foundation laws of the reduced model, by the name a scene gives them.
LAWS: dict[str, Law] = {law.name: law for law in (elastic.LAW, elastoplastic.LAW, qz.LAW,
                                                    macro_element.LAW)}


def _dtype(base, own) -> np.dtype:
    fields = list(base)
    for law in LAWS.values():
        fields += [f for f in own(law) if f[0] not in {name for name, _ in fields}]
    return np.dtype(fields, align=True)


#: One spring's parameters: the base fields and every law's own columns.
SPRING_DTYPE = _dtype(SPRING_FIELDS, lambda law: law.columns)
#: One spring's history: the base fields and every law's own.
HISTORY_DTYPE = _dtype(HISTORY_FIELDS, lambda law: law.history)


def law_of(record: scene_laws.LawRecord) -> Law:
    """The law of a scene's ``foundation.law`` record."""
    law = LAWS.get(record.name)
    if law is None or law.record is not type(record):
        raise InputError(f"foundation.law = {record.name!r}: the reduced model has no such law "
                         f"(its laws: {', '.join(LAWS)})")
    return law


def register(law: Law) -> None:
    """Register a law defined outside upliftlab: its scene record (so that scenes read it) and
    its entry here. Its own columns and history fields must be among those of the spring
    record and history, which are fixed when this package is imported."""
    missing = [n for n, _ in law.columns if n not in SPRING_DTYPE.names]
    missing += [n for n, _ in law.history if n not in HISTORY_DTYPE.names]
    if missing:
        raise ValueError(f"law {law.name!r}: fields {missing} are not in the spring record")
    scene_laws.register(law.record)
    LAWS[law.name] = law


def initial_history(params: np.ndarray) -> np.ndarray:
    """The springs' history at the start of a run: zeros, and each spring of a law that has a
    state at rest (a q–z spring: on its virgin backbone at F0) in that state."""
    H = np.zeros(params.size, dtype=HISTORY_DTYPE)
    for law in LAWS.values():
        if law.start is not None:
            for j in np.flatnonzero(np.isin(params["kind"], law.kinds)):
                law.start(params[j], H[j])
    return H


def curved_kinds() -> tuple[int, ...]:
    """The spring kinds of the laws the event stepper cannot tabulate."""
    return tuple(k for law in LAWS.values() if not law.tabulated for k in law.kinds)
