"""The study's result record."""

from __future__ import annotations

from dataclasses import dataclass

from ..study import StudyResult
from .analysis import EwingConclusion, RegionStatement
from .convergence import Convergence
from .grid import Grid, Options
from .maps import ErrorMap
from .points import Base
from .statics import Statics


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class TwoSpringEquivalence:
    """The study's result: files and summary (``study``), the converged N, the statics, the
    error maps and the conclusions computed from them."""

    study: StudyResult
    springs: int
    convergence: Convergence
    statics: Statics
    maps: tuple[ErrorMap, ...]
    regions: tuple[RegionStatement, ...]
    ewing: EwingConclusion
    grid: Grid
    options: Options
    record_note: str
    base: Base = None

    def map(self, name: str) -> ErrorMap:
        return next(m for m in self.maps if m.name == name)

    def region(self, map: str, case: str, layout: str, metric: str = "u") -> RegionStatement:
        return next(r for r in self.regions if (r.map, r.case, r.layout, r.metric)
                    == (map, case, layout, metric))
