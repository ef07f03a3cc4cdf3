"""The study's result record."""

from __future__ import annotations

from dataclasses import dataclass

from ...framework.study import StudyResult
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

    def __repr__(self) -> str:
        """One line: the bed's N, the maps and where the files are."""
        names = ", ".join(m.name for m in self.maps)
        return f"<TwoSpringEquivalence N = {self.springs} springs, maps: {names}; {self.study!r}>"

    def to_dataframe(self):
        """Every map's errors in long form, one row per (map, case, layout, measure and the
        map's two parameters), as a :class:`pandas.DataFrame` (column ``error``, relative; one
        column per parameter, ``h_over_b``, ``intensity``, …, empty where a map has no such
        axis)."""
        import pandas as pd

        tree = self.to_xarray()
        frames = [tree[f"map_{m.name}"].error.to_dataframe().reset_index().assign(map=m.name)
                  for m in self.maps]
        return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()

    def to_xarray(self):
        """The study's data as an :class:`xarray.DataTree`: ``convergence`` and one node per
        error map (``map_aspect``, …), the datasets its files hold, so that
        ``tree["map_aspect"].error.sel(case="C", layout="edges", measure="u")`` is one map, and
        ``…sel(h_over_b=4.0)`` one column of it: each map's dimensions are named after its
        parameters."""
        import xarray as xr

        from .datasets import convergence_dataset, map_dataset

        prov, units = self.study.provenance, self.base.table["units"]
        nodes = {"convergence": convergence_dataset(self.convergence, prov, units)}
        nodes.update({f"map_{m.name}": map_dataset(m, prov, units) for m in self.maps})
        return xr.DataTree.from_dict(nodes, name=self.study.name)

    def region(self, map: str, case: str, layout: str, metric: str = "u") -> RegionStatement:
        return next(r for r in self.regions if (r.map, r.case, r.layout, r.metric)
                    == (map, case, layout, metric))
