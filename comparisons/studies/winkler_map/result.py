"""The study's result record."""

from __future__ import annotations

from dataclasses import dataclass

from ...framework.study import StudyResult
from .analysis import Analysis
from .maps import MapData


@dataclass(frozen=True, eq=False)
class WinklerMap:
    """The map's result: files and summary (``study``), the ``data`` (every run's measures and
    errors) and the ``analysis`` (regions, picks, share, speed) computed from it."""

    study: StudyResult
    data: MapData
    analysis: Analysis

    def __repr__(self) -> str:
        """One line: the grid's size, the best calibration's share and where the files are."""
        d, s = self.data, self.analysis.share
        return (f"<WinklerMap {d.continuum_wall.size} points × {len(d.calibrations)} beds; "
                f"best ({s.best}) within {100 * s.threshold:g} % in peak θ and edge uplift at "
                f"{100 * s.best_share:.0f} %; {self.study!r}>")

    def to_xarray(self):
        """The map as an :class:`xarray.DataTree`: ``map`` (over soil, fs_v, h_over_B, period,
        intensity, motion, calibration, measure) and ``statics`` (per soil), the datasets its
        files hold: ``tree["map"].error.sel(calibration="uniform", measure="theta")``."""
        import xarray as xr

        from .output import map_dataset, statics_dataset

        prov = self.study.provenance if self.study is not None else {}
        return xr.DataTree.from_dict({"map": map_dataset(self.data, prov),
                                      "statics": statics_dataset(self.data, prov)},
                                     name="winkler_map")
