"""The study's result record."""

from __future__ import annotations

from dataclasses import dataclass

from ....scenes import Scene
from ...framework.study import StudyResult
from .analysis import ErrorTable, Recommendation
from ...beds.pushover import BedResponse
from ...beds.stiffness import Calibration
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

    def __repr__(self) -> str:
        """One line: the scene, the calibrations, the motions and where the files are."""
        motions = ", ".join(run.key for run in self.dynamics.runs) or "none"
        return (f"<WinklerVsContinuum {self.scene.name}: {len(self.calibrations)} calibrations, "
                f"{len(self.table.quantities)} quantities, motions: {motions}; {self.study!r}>")

    def to_dataframe(self):
        """The error table as a :class:`pandas.DataFrame`: calibrations as rows, quantities
        as columns (relative errors; NaN where a bed has no such value)."""
        return self.to_xarray()["errors"].error.to_pandas()

    def to_xarray(self):
        """The study's data as an :class:`xarray.DataTree`: ``errors`` (the error table over
        calibration and quantity) and one node per motion (``dynamic_<key>``), the datasets its
        files hold: ``tree["errors"].error.sel(calibration="uniform_plastic")``."""
        import xarray as xr

        from .datasets import dynamic_dataset, errors_dataset

        prov, units = self.study.provenance, self.scene.units
        nodes = {"errors": errors_dataset(self.table, prov, units)}
        nodes.update({f"dynamic_{run.key}": dynamic_dataset(run, prov, units)
                      for run in self.dynamics.runs})
        return xr.DataTree.from_dict(nodes, name=self.study.name)

    def bed(self, name: str) -> BedResponse:
        return next(b for b in self.beds if b.calibration.name == name)
