"""Result files follow the CF-1.10 conventions, and open as tables that do not cross their
dimensions.

Reference: the IOOS compliance checker (``compliance-checker --test cf:1.10``, version 6.1,
which ships the CF standard-name table and UDUNITS and runs offline) finds no failing
required (high-priority) check, and no check that raised instead of running, in every kind of
file upliftlab writes here: a reduced run (a one-story building, a three-story frame), a
continuum rotation pushover with its soil fields, a continuum dynamic run, an impedance
sweep. The studies' files are checked in their own test modules, on the files their module
fixtures write (``test_fixed_vs_uplift``, ``test_speed_vs_error``). For the tables: the row
count of each node of :func:`upliftlab.open_result` is the product of its own dimensions (the
time steps for the histories), and the soil fields' coordinates are the mesh's own vertices
and element centroids (the mean of a rectangle's four corners).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from upliftlab import cli, load_scene, open_result
from upliftlab.continuum import build_model, rotation_pushover
from upliftlab.reduced import run
from upliftlab.reduced.labelled import SCALAR_HISTORIES
from upliftlab.results import read_dataset

CLAY = "strip_footing_clay"
COARSE = ("continuum.elements_across=2",)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """{kind: path} of one file of each kind, written as ``upliftlab`` writes them."""
    out = tmp_path_factory.mktemp("cf")
    written = {}
    for name, scene, case in (("reduced", "short_period_free", "C"),
                              ("frame", "three_story_frame", "fixed")):
        folder = out / name
        assert cli.main(["run", scene, "--case", case, "--set", "motion.duration=0.3",
                         "--no-figure", "-q", "--out", str(folder)]) == 0
        written[name] = next(folder.glob("*.nc"))
    for name, extra in (("dynamic", ["--set", "analysis.duration=0.03", "--set", COARSE[0]]),
                        ("impedance", ["--set", "soil.model=elastic", "--set",
                                       "soil.undrained_strength=", "--a0", "0.2"])):
        folder = out / name
        assert cli.main(["continuum", CLAY, "--analysis", name, "--no-render", "-q", "--out",
                         str(folder), *extra]) == 0
        written[name] = next(folder.glob("*.nc"))
    written["pushover"] = _pushover().save(out / "pushover.nc")
    return written


def _model():
    return build_model(load_scene(CLAY, overrides=COARSE))


def _pushover():
    model = _model()
    return rotation_pushover(model, model.scene.structure.vertical_weight, [0.001, 0.004],
                             record_fields=True)


@pytest.mark.parametrize("kind", ["reduced", "frame", "pushover", "dynamic", "impedance"])
def test_every_result_file_passes_the_cf_checker(files, kind, cf_failures):
    required, errors = cf_failures(files[kind])
    assert required == [] and errors == []


def test_a_vm_envelope_file_passes_the_cf_checker(tmp_path, cf_failures):
    # The continuum's V–M envelope (continuum.statics.Envelope.save, units as a scene's
    # result_metadata gives them in kN-m-s): no failing required check; values as given.
    from upliftlab.continuum.statics.results import Envelope

    units = {"length": "m", "force/length": "kN/m", "moment/length": "kN*m/m"}
    envelope = Envelope(V=np.array([10.0, 20.0]), M=np.array([3.0, 4.0]), V_ult=40.0,
                        width=2.0, metadata={"units": units, "analysis": "vm_envelope"})
    path = envelope.save(tmp_path / "envelope.nc")
    assert cf_failures(path) == ([], [])
    back = read_dataset(path)
    assert back.m.values.tolist() == [3.0 / 80.0, 4.0 / 80.0] and back.v.values.tolist() == \
        [0.25, 0.5]


def test_a_reduced_file_reads_back_as_the_run_holds_it(files):
    """The values on disk are the run's, bit for bit; the time axis reads back in s and the
    DOF labels as the index (the file holds CF's forms: dates, ``dof_label``)."""
    import xarray as xr

    scene = load_scene("short_period_free", case="C", overrides=["motion.duration=0.3"])
    memory = run(scene).to_xarray()
    back = read_dataset(files["reduced"])
    for name, var in memory.variables.items():
        np.testing.assert_array_equal(back[name].values, var.values, err_msg=name)
    assert back.time.attrs["units"] == "s" and back.q.sel(dof="theta").size == back.time.size
    with xr.open_dataset(files["reduced"], decode_times=False) as raw:
        assert raw.time.attrs["units"] == "seconds since 1970-01-01 00:00:00"
        assert "dof" not in raw.variables and list(raw.dof_label.values) == list(memory.dof.values)


def test_a_reduced_result_opens_as_tables_that_do_not_cross(files):
    tree = open_result(files["reduced"])
    histories = tree["time"].to_dataset().to_dataframe()
    raw = read_dataset(files["reduced"])
    assert histories.shape == (raw.sizes["time"], len(SCALAR_HISTORIES) - 1)  # no sway spring
    assert set(histories.columns) == set(SCALAR_HISTORIES) - {"sway"}
    np.testing.assert_array_equal(histories.index.values, raw.time.values)
    np.testing.assert_array_equal(histories["theta"].values, raw.theta.values)
    crossed, sizes = math.prod(raw.sizes.values()), dict(raw.sizes)
    rows = 0
    for node in tree.subtree:
        data = node.to_dataset()
        if data.data_vars and data.sizes:
            frame = data.to_dataframe()
            assert len(frame) == math.prod(data.sizes.values()), node.path
            rows += len(frame)
    # the tables: time steps × (1 history row + DOFs + springs + energy components), the
    # springs' constants, the peak drift per story, the motion's samples; not their product
    assert rows == sizes["time"] * (1 + sizes["dof"] + sizes["spring"] + sizes["component"]) \
        + sizes["spring"] + sizes["story"] + sizes["record_time"] and rows * 300 < crossed
    assert float(tree.peak_u) == float(raw.peak_u) and tree.attrs["scene"] == raw.attrs["scene"]
    springs = tree["time/spring"].to_dataset().to_dataframe()
    assert springs.index.names == ["time", "spring"] and "position" in springs.columns


def test_the_soil_fields_carry_their_nodes(files):
    model = _model()
    tree = open_result(files["pushover"])
    dofs = tree["snapshot/dof"].to_dataset()
    assert dofs.dof_x.attrs["units"] == "m" and dofs.dof_y.attrs["units"] == "m"
    located = {(round(x, 9), round(y, 9), int(d)) for x, y, d in
               zip(dofs.dof_x.values, dofs.dof_y.values, dofs.dof_direction.values)}
    vertices = model.mesh.p.T
    assert all((round(x, 9), round(y, 9), d) in located for x, y in vertices for d in (0, 1))
    assert dofs.dof_y.max() == 0.0  # the surface
    elements = tree["snapshot/element"].to_dataset()
    corners = vertices[model.mesh.t]  # (4, nelems, 2)
    np.testing.assert_allclose(elements.element_x.values, corners[..., 0].mean(axis=0),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(elements.element_y.values, corners[..., 1].mean(axis=0),
                               rtol=0, atol=1e-12)
    table = dofs.to_dataframe()
    assert len(table) == dofs.sizes["snapshot"] * dofs.sizes["dof"]
    assert {"displacement", "dof_x", "dof_y", "dof_direction"} <= set(table.columns)


def test_a_continuum_dynamic_run_opens_with_a_row_per_step(files):
    tree = open_result(files["dynamic"])
    frame = tree["time"].to_dataset().to_dataframe()
    raw = read_dataset(files["dynamic"])
    assert len(frame) == raw.sizes["time"] and {"u", "v", "theta", "M"} <= set(frame.columns)
    assert "dof_x" in tree["snapshot/dof"].to_dataset().coords


def test_open_result_refuses_a_folder(tmp_path):
    from upliftlab.checks import InputError

    with pytest.raises(InputError, match="is not a file"):
        open_result(tmp_path)


def test_labels_round_trip_beside_a_studys_own_label(tmp_path, cf_failures):
    # Reference: the dataset written, read back by upliftlab.results.read_dataset (identical);
    # a study that labels its calibration keys by a calibration_label of its own (the Winkler
    # map does) keeps it, and the keys go to calibration_key; a file written before the CF
    # forms (text coordinate variables, time in s) reads back unchanged.
    import xarray as xr

    from upliftlab.results import write_dataset

    ds = xr.Dataset(
        {"error": (("calibration", "case"), np.arange(4.0).reshape(2, 2),
                   {"units": "1", "long_name": "relative error"})},
        coords={"calibration": ("calibration", ["uniform", "es_f"], {"long_name": "bed key"}),
                "calibration_label": ("calibration", ["U", "ES-f"], {"long_name": "bed"}),
                "case": ("case", ["A", "B"], {"long_name": "case"})},
        attrs={"title": "labels"})
    path = write_dataset(tmp_path / "labels.nc", ds)
    assert cf_failures(path) == ([], [])
    with xr.open_dataset(path) as raw:
        assert {"calibration_key", "calibration_label", "case_label"} <= set(raw.variables)
        assert "calibration" not in raw.variables and "case" not in raw.variables
    xr.testing.assert_identical(read_dataset(path).drop_attrs(deep=True),
                                ds.drop_attrs(deep=True))
    old = ds.assign_coords(time=("time", [0.0, 0.5], {"units": "s", "long_name": "time"}))
    old.to_netcdf(tmp_path / "old.nc", engine="h5netcdf")
    back = read_dataset(tmp_path / "old.nc")
    assert list(back.calibration.values) == ["uniform", "es_f"]
    assert back.time.attrs["units"] == "s" and back.time.values.tolist() == [0.0, 0.5]
