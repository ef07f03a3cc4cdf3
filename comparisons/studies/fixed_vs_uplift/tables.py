"""The study's CSV tables, read from its dataset: the histories of Figs. 11–12 and the
spectrum of each family (one row per period)."""

from __future__ import annotations

from pathlib import Path

from ....results import write_csv
from .analysis import spectrum_supports
from .grid import STUDY


def write_tables(ds, directory: Path) -> list[Path]:
    """``fig<N>.csv`` (time in s, u in in, fixed base and Case C) per building and
    ``spectrum_<family>.csv`` (peak u in in, V/W, uplifted 0/1 per support) per family, into
    ``directory``; the files."""
    files = []
    for building, number in zip(ds.building.values.tolist(), ds.figure.values.tolist()):
        u = ds.u.sel(building=building)
        files.append(write_csv(directory / f"fig{number}.csv",
                               {"time_s": ds.time.values, "u_fixed": u.sel(support="fixed").values,
                                "u_uplift_case_C": u.sel(support="C").values},
                               header=f"{STUDY}: Fig. {number}, {building}-period "
                                      "building, El Centro 1940 N-S; u in inches"))
    for family in ds.family.values.tolist():
        one = ds.sel(family=family)
        cols = {"period_s": ds.period.values}
        for support in spectrum_supports(ds):
            at = one.sel(support=support)
            cols[f"u_{support}"] = at.spectrum_peak_u.values
            cols[f"shear_coefficient_{support}"] = at.spectrum_shear_coefficient.values
            cols[f"uplifted_{support}"] = at.spectrum_uplifted.values.astype(float)
        files.append(write_csv(directory / f"spectrum_{family}.csv", cols,
                               header=f"{STUDY}: peak u (in) and base shear V/W against the "
                                      f"superstructure period, {family}-period building's "
                                      "base body, El Centro 1940 N-S"))
    return files
