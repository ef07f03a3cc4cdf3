"""``benchmarks/macro_map_slice.py`` counts a model's failed run as a miss, never as a point
taken out of the comparison, and lists the element's refusals. Reference: a four-point
dataset built here by hand, whose shares are counted by hand in each test's docstring."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def _slice():
    spec = importlib.util.spec_from_file_location("macro_map_slice_counts",
                                                  BENCH / "macro_map_slice.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _dataset(refusals):
    """One soil, one cell, four motions (two pulses, two records); two models. Errors, θ and
    uplift alike: the element 5 %, NaN (its run failed), 5 %, 50 %; the bed 5 % at every
    point. A fifth motion where every model is NaN stands for a continuum run left out."""
    import xarray as xr

    from upliftlab.comparisons.studies.winkler_map.grid import MEASURES

    element = [0.05, np.nan, 0.05, 0.50, np.nan]
    bed = [0.05, 0.05, 0.05, 0.05, np.nan]
    error = np.empty((1, 1, 1, 1, 1, 5, 2, len(MEASURES)))
    for m in range(5):
        error[..., m, 0, :] = element[m]
        error[..., m, 1, :] = bed[m]
    dims = ("soil", "fs_v", "h_over_B", "period", "intensity", "motion", "calibration",
            "measure")
    walls = np.ones(error.shape[:-1])
    return xr.Dataset(
        {"error": (dims, error), "bed_wall_time": (dims[:-1], walls)},
        coords={"soil_label": ("soil", ["clay"]), "fs_v": [3.0], "h_over_B": [1.0],
                "period": [0.5], "intensity": [1.5],
                "motion_kind": ("motion", ["ricker", "ricker", "fema_p695", "fema_p695",
                                           "fema_p695"]),
                "calibration_key": ("calibration", ["macro", "uniform"]),
                "measure_key": ("measure", list(MEASURES))},
        attrs={"refusals": refusals})


def _rows(tmp_path, refusals) -> tuple[dict, str]:
    """({model: {column: cell}} of the slice's table, its whole text) for ``refusals``."""
    bench = _slice()
    path = tmp_path / "map.nc"
    _dataset(refusals).to_netcdf(path)
    out = tmp_path / "out"
    assert bench.main(["--map", str(path), "--out", str(out)]) == 0
    text = (out / "MACRO_MAP_SLICE.md").read_text()
    header, _, *lines = [line for line in text.splitlines() if line.startswith("|")]
    names = [c.strip() for c in header.strip("|").split("|")]
    rows = {}
    for line in lines:
        cells = [c.strip() for c in line.strip("|").split("|")]
        rows[cells[0]] = dict(zip(names, cells))
    return rows, text


@pytest.mark.parametrize("refusals", [
    ["clay, FS_v = 3, ricker_T0.6s, macro: newmark: the contact's iterations did not converge",
     "clay, FS_v = 3, FF-09a, the continuum: beyond the small-strain reference"],
    "clay, FS_v = 3, ricker_T0.6s, macro: newmark: the contact's iterations did not converge\n"
    "clay, FS_v = 3, FF-09a, the continuum: beyond the small-strain reference"])
def test_a_failed_element_run_is_a_miss_and_is_listed(tmp_path, refusals):
    """Four compared points (the fifth has no model's error): the element is within 10 % at
    2 of 4 (its failed run a miss: 50 %, not 2 of 3), 1 of 2 on the pulses and 1 of 2 on the
    records, 1 run failed, and its refusal listed whether the netCDF keeps the refusals as a
    list or as one string; the bed, whose runs all completed, at 4 of 4."""
    rows, text = _rows(tmp_path, refusals)
    element, bed = rows["macro-element"], rows["uniform"]
    assert element["points"] == "4" and element["runs failed"] == "1"
    assert element["θ and uplift within 10 %: all"] == "50%"
    assert element["θ and uplift within 10 %: pulses"] == "50%"
    assert element["records"] == "50%"
    assert "Refused runs of the macro-element" in text
    assert "contact's iterations did not converge" in text
    assert "beyond the small-strain reference" not in text.split("Refused runs")[1]
    assert bed["points"] == "4" and bed["runs failed"] == "0"
    assert bed["θ and uplift within 10 %: all"] == "100%"
