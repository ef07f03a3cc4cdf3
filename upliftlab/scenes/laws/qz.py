"""The q–z foundation law's record: hysteretic springs of the QzSimple class (the law itself:
:mod:`upliftlab.reduced.laws.qz`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ... import bounds
from ...checks import InputError
from ..table import Table, choice, in_range
from .base import LawContext, LawRecord
from .elastoplastic import MULTIPLE, read_yield_multiple

__all__ = ["QzLaw", "QZ_SOIL_NAMES", "QZ_EXPONENT_MAX", "QZ_ELASTIC_RANGE_MAX", "SUCTION_MAX"]

QZ_SOIL_NAMES = ("clay", "sand")  # the backbone shapes (upliftlab.reduced.laws.qz.QZ_SOILS)
QZ_EXPONENT_MAX = 50.0  # n of a q–z backbone: > 1 (the hyperbola's work integral), ≤ 50
QZ_ELASTIC_RANGE_MAX = 0.95  # elast of a q–z backbone: its pristine half-range, below q_ult
SUCTION_MAX = 0.1  # the drag capacity QzSimple allows, as a fraction of q_ult


@dataclass(frozen=True, eq=False, kw_only=True)
class QzLaw(LawRecord):
    """Hysteretic q–z springs: the bed's bearing capacity is ``capacity_multiple`` times the
    weight, shared over the springs' tributary widths; ``z50`` (length) the base's settlement
    at half capacity under a centred load; ``suction`` the gap's drag as a fraction of
    capacity; ``qz_soil`` the backbone's shape, ``clay`` or ``sand``, whose hyperbola exponent
    n and initial elastic half-range (fraction of q_ult) ``qz_exponent`` and
    ``qz_elastic_range`` replace where given, e.g. fitted to a continuum's vertical pushover;
    ``qz_zref`` (length) gives the springs' near-field reference instead of ``z50``, which
    cannot fix it when the elastic ranges alone carry half the capacity (exactly one of the
    two is set). ``yield_multiple`` is read and kept but does not act.

    The spring opens a gap on uplift (``support`` must be ``uplift``), has no impact damper
    (``restitution`` must be 1: its hysteresis dissipates the landing) and is curved (the
    event stepper cannot tabulate it: a scene that names no integrator takes ``rk4``)."""

    name: ClassVar[str] = "qz"
    curved: ClassVar[str] = "the q–z spring is curved"
    inert: ClassVar[dict[str, str]] = {
        "yield_multiple": "the yield multiple acts only with foundation.law = 'elastoplastic' "
                          "(this scene's law is 'qz', whose capacity is "
                          "foundation.capacity_multiple)"}

    yield_multiple: float = 3.0
    capacity_multiple: float
    z50: float | None = None
    suction: float = 0.0
    qz_soil: str = "clay"
    qz_exponent: float | None = None
    qz_elastic_range: float | None = None
    qz_zref: float | None = None

    @classmethod
    def read(cls, table: Table, context: LawContext) -> QzLaw:
        if context.support != "uplift":
            raise InputError(f"foundation.support = {context.support!r} with foundation.law = "
                             "'qz': the q–z spring opens a gap on uplift; valid: 'uplift'")
        length = bounds.checker("length", context.units)
        zref = table.get("qz_zref", length, None)
        if zref is not None and table.has("z50"):
            raise InputError("foundation.z50 with foundation.qz_zref: each fixes the springs' "
                             "near-field reference; give one of them")
        return cls(
            capacity_multiple=table.get("capacity_multiple", MULTIPLE),
            z50=table.get("z50", length) if zref is None else None,
            qz_zref=zref,
            suction=table.get("suction", in_range(0.0, SUCTION_MAX), 0.0),
            qz_soil=table.get("qz_soil", choice(QZ_SOIL_NAMES), "clay"),
            qz_exponent=table.get("qz_exponent", in_range(1.0, QZ_EXPONENT_MAX, low_open=True),
                                  None),
            qz_elastic_range=table.get("qz_elastic_range", in_range(0.0, QZ_ELASTIC_RANGE_MAX),
                                       None),
            yield_multiple=read_yield_multiple(table))

    def check(self, foundation) -> None:
        if foundation.restitution < 1.0:
            raise InputError(f"foundation.restitution = {foundation.restitution:g} with "
                             "foundation.law = 'qz': the q–z spring has no impact damper (its "
                             "hysteresis dissipates the landing); valid: 1")
