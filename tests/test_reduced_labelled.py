"""The reduced response as labelled data (upliftlab.reduced.labelled).

Reference: the Response's own arrays, which the dataset and the frame must hold unchanged
(exactly), under labels a notebook user selects by; and the CF conventions' required
attributes (units and long_name on every variable, flag_values with flag_meanings).
"""

from __future__ import annotations

import numpy as np
import pytest

from upliftlab.reduced import run
from upliftlab.reduced.labelled import SCALAR_HISTORIES
from upliftlab.scenes import load_scene


@pytest.fixture(scope="module")
def response():
    return run(load_scene("wall_free", overrides=["analysis.duration=1"]))


def test_the_dataset_selects_by_label_and_holds_the_response(response):
    ds = response.to_xarray()
    assert np.array_equal(ds.theta.values, response.theta)
    assert np.array_equal(ds.spring_force.sel(spring=3).values, response.force[:, 3])
    assert np.array_equal(ds.energy.sel(component="input").values, response.energy[:, 0])
    assert np.array_equal(ds.q.sel(dof=response.dofs.names[-1]).values, response.q[:, -1])
    # the leftmost of N equal strips under a base of half-width b sits at its centre, −b + b/N
    f = response.model.scene.foundation
    left = ds.spring_deformation.where(ds.kind == 1, drop=True).isel(spring=0)
    assert float(left.position) == pytest.approx(-f.half_width * (1 - 1 / f.springs), rel=1e-12)
    at = ds.u.sel(time=0.5, method="nearest")
    assert float(at) == response.u[np.argmin(np.abs(response.time - 0.5))]


def test_every_variable_has_units_and_a_long_name(response):
    ds = response.to_xarray()
    for name in list(ds.data_vars) + ["time", "position"]:
        assert ds[name].attrs.get("long_name"), name
        # CF: a flag variable carries flag_values and flag_meanings instead of units; the DOFs
        # (lengths and a rotation) one unit each, in the coordinate dof_units
        per_dof = "dof_units" in ds[name].attrs.get("comment", "")
        assert ds[name].attrs.get("units") or "flag_values" in ds[name].attrs or per_dof, name
    assert [name for name in ds.data_vars if "units" not in ds[name].attrs
            and "flag_values" not in ds[name].attrs] == ["q", "qd"]
    # the wall's DOFs: the story x1 (length), θ (rad), V (length); the scene is in kip-in-s
    assert ds.dof_units.values.tolist() == ["in", "rad", "in"]
    mode = ds.spring_mode.attrs
    assert len(mode["flag_values"]) == len(mode["flag_meanings"].split())
    assert "contact" in mode["flag_meanings"].split()


def test_the_frame_holds_the_scalar_histories_by_time(response):
    frame = response.to_dataframe()
    assert list(frame.columns) == [k for k in SCALAR_HISTORIES if k != "sway"]  # no sway spring
    assert np.array_equal(frame.index.values, response.time)
    assert np.array_equal(frame["overturning_moment"].values, response.overturning_moment)
    assert frame.attrs["units"]["theta"] == "rad"


def test_the_repr_is_one_short_line_with_the_peaks(response):
    # Reference: the response's own peaks and verdict.
    text = repr(response)
    assert "\n" not in text and len(text) < 400, text
    assert f"peak theta = {response.peaks['theta']:.4g} rad" in text
    assert text.endswith(f"{response.verdict}>")
