"""The records of the paper's conclusions: a piece of evidence, and a conclusion with its
verdict (the study's result is their dataset, :mod:`.dataset`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass


STUDY = "paper"
BUILDINGS = ("short_period", "long_period")


@dataclass(frozen=True)
class Evidence:
    """One measured fact for a conclusion: ``source`` (model and scene), what it ``says``, the
    ``values`` that decide it (``unit``), and whether it ``supports`` the conclusion."""

    source: str
    says: str
    values: Mapping[str, float]
    unit: str
    supports: bool


@dataclass(frozen=True)
class Conclusion:
    """A statement of the paper and the evidence for it. ``verdict``: ``holds`` (all evidence
    supports it), ``does not hold`` (none does), ``holds in part``, or ``not tested`` (no
    evidence: ``note`` says why). ``why``: where our results differ, the reason found."""

    number: int
    statement: str
    evidence: tuple[Evidence, ...]
    note: str = ""
    why: str = ""

    @property
    def verdict(self) -> str:
        if not self.evidence:
            return "not tested"
        support = [e.supports for e in self.evidence]
        return "holds" if all(support) else "does not hold" if not any(support) \
            else "holds in part"
