"""Opening a study's output folder again (:func:`upliftlab.open_study`): one node per NetCDF
file by its path, labelled coordinates and their units as written, the summary's numbers as
the root's attributes; the points' store and unfinished writes left out; a folder that is not
a study's refused in one line. (A study's own folder is opened in its tests, e.g.
``tests/test_fixed_vs_uplift.py``.)"""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

import upliftlab
from upliftlab.checks import InputError
from upliftlab.comparisons.framework.study import write_data
from upliftlab.results import write_dataset


def _map(h_over_b):
    return xr.Dataset({"error": (("h_over_B",), np.linspace(0.1, 0.3, len(h_over_b)),
                                 {"units": "1"})},
                      coords={"h_over_B": ("h_over_B", np.array(h_over_b, float),
                                           {"units": "1", "long_name": "aspect ratio h/B"})})


def test_open_study_reads_every_file_by_its_path(tmp_path):
    tree = xr.DataTree.from_dict({"map_aspect": _map([1.0, 2.0, 4.0]),
                                  "beds/clay": _map([1.0, 2.0])})
    files = write_data(tmp_path, tree, "unused")
    assert sorted(p.relative_to(tmp_path).as_posix() for p in files) == [
        "beds/clay.nc", "map_aspect.nc"]
    write_dataset(tmp_path / "store" / "point.nc", _map([9.0]))  # the points' store
    write_dataset(tmp_path / ".map_aspect.nc.part.nc", _map([9.0]))  # an unfinished write
    (tmp_path / "summary.json").write_text(json.dumps(
        {"numbers": {"largest_error": 0.3, "passed": True}, "provenance": {"code": "x"}}))
    opened = upliftlab.open_study(tmp_path)
    assert sorted(opened.to_dict()) == ["/", "/beds", "/beds/clay", "/map_aspect"]
    error = opened["map_aspect"].error.sel(h_over_B=2.0)
    assert float(error) == 0.2
    assert opened["beds/clay"].h_over_B.attrs["units"] == "1"
    assert opened.attrs["largest_error"] == 0.3 and opened.attrs["passed"] is True
    assert opened.attrs["provenance"] == {"code": "x"}


def test_a_single_dataset_is_one_file_named_by_the_study(tmp_path):
    write_data(tmp_path, _map([1.0, 3.0]), "my_study")
    opened = upliftlab.open_study(tmp_path)
    assert list(opened.children) == ["my_study"]
    assert opened["my_study"].error.sel(h_over_B=3.0).item() == 0.3
    assert opened.attrs == {}  # no summary.json: no numbers


def test_a_study_without_netcdf_files_opens_as_its_numbers(tmp_path):
    # the paper's conclusions write summary.json alone
    (tmp_path / "summary.json").write_text(json.dumps({"numbers": {"passed": True}}))
    opened = upliftlab.open_study(tmp_path)
    assert not opened.children and opened.attrs == {"passed": True}


@pytest.mark.parametrize("make, message", [
    (lambda p: p / "missing", "is not a folder"),
    (lambda p: p, "holds neither a NetCDF file nor summary.json"),
])
def test_what_is_not_a_study_folder_is_refused(tmp_path, make, message):
    with pytest.raises(InputError, match=message):
        upliftlab.open_study(make(tmp_path))
