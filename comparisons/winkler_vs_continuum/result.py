"""The study's result record."""

from __future__ import annotations

from dataclasses import dataclass

from ...scenes import Scene
from ..study import StudyResult
from .analysis import ErrorTable, Recommendation
from .calibration import BedResponse, Calibration
from .dynamics import DynamicComparison
from .options import Options
from .reference import ContinuumReference


# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class WinklerVsContinuum:
    """The study's result: files and summary (``study``), the continuum ``reference``, the
    ``calibrations`` and their ``beds``, the error ``table``, the ``recommendation``, the
    ``anchors`` checked on the way, and the ``dynamics``."""

    study: StudyResult
    scene: Scene
    reference: ContinuumReference
    calibrations: tuple[Calibration, ...]
    beds: tuple[BedResponse, ...]
    table: ErrorTable
    recommendation: Recommendation
    anchors: dict
    dynamics: DynamicComparison
    options: Options

    def calibration(self, name: str) -> Calibration:
        return next(c for c in self.calibrations if c.name == name)

    def bed(self, name: str) -> BedResponse:
        return next(b for b in self.beds if b.calibration.name == name)
