"""The continuum dynamic result as labelled data (upliftlab.continuum.output.labelled).

Reference: the DynamicResult's own arrays, held unchanged (exactly) under labels; the CF
conventions' attributes (units and long_name, or flag_values with flag_meanings).
"""

from __future__ import annotations

import numpy as np
import pytest

from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.scenes import load_scene


@pytest.fixture(scope="module")
def result():
    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4",
                                                        "analysis.duration=0.3"])
    return run_dynamic(build_model(scene), scene, scene.build_motion(),
                       DynamicOptions(snapshots=0))


def test_the_dataset_selects_by_label_and_holds_the_result(result):
    ds = result.to_xarray()
    assert np.array_equal(ds.theta.values, result.theta)
    edge = int(np.argmin(result.x))
    assert np.array_equal(ds.pressure.sel(node=edge).values, result.pressure[:, edge])
    assert float(ds.x.sel(node=edge)) == pytest.approx(-0.5 * result.width, rel=1e-12)
    assert np.array_equal(ds.energy.sel(component="input").values, result.energy[:, 3])
    assert ds.attrs["Conventions"].startswith("CF-")


def test_every_variable_has_units_or_flags_and_a_long_name(result):
    ds = result.to_xarray()
    for name in list(ds.data_vars) + ["time", "x"]:
        assert ds[name].attrs.get("long_name"), name
        assert ds[name].attrs.get("units") or "flag_values" in ds[name].attrs, name
    assert ds.status.attrs["flag_meanings"].split()[0] == "open"


def test_a_pushover_selects_by_rotation():
    # Reference: the StaticPath's own arrays; the rotations asked for (the pushover's schedule).
    from upliftlab.continuum import rotation_pushover

    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4"])
    model = build_model(scene)
    rotations = np.array([0.0, 0.002, 0.004, 0.006])
    path = rotation_pushover(model, scene.structure.vertical_weight, rotations)
    ds = path.to_xarray().swap_dims(step="theta")
    assert np.array_equal(ds.M.values, path.M)
    assert float(ds.M.sel(theta=0.004, method="nearest")) == path.M[
        np.argmin(np.abs(path.theta - 0.004))]
    assert ds.theta.values[-1] == pytest.approx(0.006, rel=1e-9)
    for name in ds.data_vars:
        assert ds[name].attrs.get("long_name"), name
        assert ds[name].attrs.get("units") or "flag_values" in ds[name].attrs, name


def test_the_repr_is_one_short_line_with_the_peaks(result):
    # Reference: the result's own arrays (peak |θ| and the settlement at the end).
    text = repr(result)
    assert "\n" not in text and len(text) < 300, text
    assert f"{np.max(np.abs(result.theta)):.4g} rad" in text
    assert f"{-result.footing[-1, 1]:.4g} m" in text and text.startswith("<DynamicResult ")


def test_the_frame_holds_the_scalar_histories_by_time(result):
    # Reference: the result's own arrays, by label; units from the dataset's attributes.
    frame = result.to_dataframe()
    assert frame.index.name == "time" and np.array_equal(frame.index.values, result.time)
    assert np.array_equal(frame["theta"].values, result.theta)
    assert np.array_equal(frame["M"].values, result.M)
    assert frame.attrs["units"]["theta"] == "rad" and frame.attrs["units"]["time"] == "s"
    assert "pressure" not in frame  # per node: in the dataset, not in the table
