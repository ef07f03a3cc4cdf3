"""The XDMF time series of a continuum run (upliftlab.continuum.output.xdmf): what their time means,
and the contact along the footing's base on its own line mesh (footing.xdmf).

References:
- the time values are the analysis's own inputs and outputs, compared exactly (meshio writes
  repr(float)): the imposed rotations of a rotation pushover, the imposed settlements of a
  vertical pushover, the recorded times of a dynamic run (s);
- the nodal contact forces of footing.xdmf sum to the vertical load the footing carries. In a
  pushover N is an input (the scene's weight, held by the footing's equilibrium while θ is
  imposed), so the sum is checked against it to 1e-12 relative. In a dynamic run N varies; at
  t = 0 it is the scene's weight (the static state), later the result's own N = Lᵀ f_c, which
  is the same contact forces summed: that check guards the writer (nodes, weights, rows), not
  the solver;
- the trapezoid of the pressure over x (what ParaView's Integrate Variables computes on the
  line cells) is the consistent integral on a linear base (Q1: its node weights are the
  trapezoid's, to 1e-12); on a Q2 base it weights the nodes (B/8 apart on the coarse mesh)
  differently from the element's Simpson weights, an O(h) discretisation difference measured at
  3.2 / 1.6 / 0.8 % (full contact) and 6.4 / 2.2 / 0.8 % (at 10 θ_on) with 4 / 8 / 16 elements
  across B: asserted within 7 % on the coarse mesh;
- the contact conditions solved exactly (continuum/contact/footing.py): gap zero (to 1e-12 B) and
  pressure ≥ 0 where closed, gap > 0 and pressure zero where open (both to the active-set
  solve's round-off, 1e-12 of the largest pressure; about 5e-19 kN/m² is seen);
- ParaView's own XDMF reader (VTK's vtkXdmfReader) reports the same time steps.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import (OPEN, DynamicOptions, build_model, rotation_pushover,
                                 run_dynamic, vertical_pushover)
from upliftlab.continuum.output.series import (read_xdmf, rotation_schedule, time_axis,
                                               write_footing_xdmf, write_xdmf)
from upliftlab.scenes import load_scene

SCENE = "strip_footing_clay"
COARSE = ["continuum.elements_across=4"]  # Q2, 10B x 10B, 1296 DOFs, 9 base nodes


def _pushover(overrides=()):
    scene = load_scene(SCENE, overrides=[*COARSE, *overrides])
    model = build_model(scene)
    N, B, soil = scene.structure.vertical_weight, model.width, scene.soil
    theta_on = 2 * N * (1 - soil.poisson_ratio) / (math.pi * soil.shear_modulus * B)
    rotations = rotation_schedule(10 * theta_on, 8, theta_on)
    path = rotation_pushover(model, N, rotations, record_fields=True)
    return SimpleNamespace(scene=scene, model=model, N=N, rotations=rotations, path=path)


@pytest.fixture(scope="module")
def pushover(tmp_path_factory):
    """The clay scene (Tresca, FS_v = 3) rotated to 10 θ_on on the coarse Q2 mesh, both XDMF
    files written and read back."""
    run = _pushover()
    out = tmp_path_factory.mktemp("pushover")
    write_xdmf(out / "fields.xdmf", run.model, run.path)
    write_footing_xdmf(out / "footing.xdmf", run.model, run.path)
    run.out, run.fields, run.footing = out, read_xdmf(out / "fields.xdmf"), \
        read_xdmf(out / "footing.xdmf")
    return run


@pytest.fixture(scope="module")
def dynamic(tmp_path_factory):
    """The clay scene's Ricker pulse on elastic soil, 2 elements across B, 1.2 s by the implicit
    route with 13 snapshots: in full contact to 0.6 s, then lifting off (3 of 5 base nodes
    open at 0.7 s)."""
    scene = load_scene(SCENE, overrides=["continuum.elements_across=2", "soil.model=elastic",
                                         "motion.duration=1.2"])
    model = build_model(scene)
    result = run_dynamic(model, scene, scene.build_motion(),
                         DynamicOptions(method="implicit", snapshots=13))
    out = tmp_path_factory.mktemp("dynamic")
    write_xdmf(out / "fields.xdmf", model, result)
    write_footing_xdmf(out / "footing.xdmf", model, result)
    return SimpleNamespace(scene=scene, model=model, result=result,
                           fields=read_xdmf(out / "fields.xdmf"),
                           footing=read_xdmf(out / "footing.xdmf"))


def _check_contact(back, result, model, rows):
    """Every step of a footing.xdmf read back holds the result's contact at its row, and the
    contact conditions hold in it; returns the number of open nodes seen."""
    B, opened = model.width, 0
    for k, row in enumerate(rows):
        data = back["point_data"][k]
        closed = result.status[row] != OPEN
        assert np.array_equal(data["contact_pressure"], result.pressure[row])
        assert np.array_equal(data["contact_gap"], result.gap[row])
        assert np.array_equal(data["footing_contact"], closed.astype(int))
        assert np.array_equal(data["contact_state"], result.status[row])
        p, g = data["contact_pressure"], data["contact_gap"]
        scale = np.abs(p).max()
        assert np.all(np.abs(g[closed]) <= 1e-12 * B)
        assert np.all(p[closed] >= -1e-12 * scale)
        assert np.all(g[~closed] > 0.0) and np.all(np.abs(p[~closed]) <= 1e-12 * scale)
        opened += int((~closed).sum())
    return opened


# ---------------------------------------------------------------------------------------------
# Time
# ---------------------------------------------------------------------------------------------


def test_pushover_time_is_the_imposed_rotation(pushover):
    # Reference: the rotations the pushover was given, exactly.
    for back in (pushover.fields, pushover.footing):
        assert back["times"].tolist() == pushover.rotations.tolist()
        info = back["information"]
        assert info["time"] == "imposed footing rotation theta [rad]"
        assert (info["time_quantity"], info["time_units"]) == ("theta", "rad")
        assert info["kind"] == "rotation_pushover" and info["scene"] == SCENE
    assert pushover.fields["information"]["field displacement"].endswith("[m]")
    assert pushover.footing["information"]["field contact_pressure"].endswith("[kN/m^2]")
    assert "compression positive" in pushover.footing["information"]["field contact_pressure"]
    assert pushover.footing["information"]["field contact_gap"].endswith("[m]")


def test_dynamic_time_is_seconds(dynamic):
    # Reference: the recorded times of the snapshots, exactly; 13 snapshots over 1.2 s.
    r = dynamic.result
    for back in (dynamic.fields, dynamic.footing):
        assert back["times"].tolist() == r.time[r.snapshot_step].tolist()
        assert back["information"]["time"] == "time since the start of the motion [s]"
        assert back["information"]["time_units"] == "s"
    assert np.allclose(dynamic.footing["times"], np.linspace(0.0, 1.2, 13), rtol=0, atol=1e-12)


def test_vertical_pushover_time_is_the_imposed_settlement(tmp_path):
    # Reference: the settlements the pushover was given (v = −s prescribed, so −v = s exactly).
    scene = load_scene(SCENE, overrides=["continuum.elements_across=2"])
    model = build_model(scene)
    settlements = [0.001, 0.002, 0.004]
    path = vertical_pushover(model, settlements, record_fields=True)
    back = read_xdmf(write_footing_xdmf(tmp_path / "v.xdmf", model, path))
    assert back["times"].tolist() == settlements
    assert back["information"]["time"] == "imposed footing settlement -v (positive down) [m]"


def test_cyclic_pushover_falls_back_to_the_load_step(tmp_path):
    # θ = 0, +a, 0, −a repeats 0: not a time. The steps 1..4 are, and the file says so.
    scene = load_scene(SCENE, overrides=["continuum.elements_across=2", "soil.model=elastic"])
    model = build_model(scene)
    a = 1e-3
    path = rotation_pushover(model, scene.structure.vertical_weight, [0.0, a, 0.0, -a],
                             record_fields=True)
    axis = time_axis(path)
    assert axis.quantity == "load_step" and axis.values.tolist() == [1.0, 2.0, 3.0, 4.0]
    back = read_xdmf(write_xdmf(tmp_path / "c.xdmf", model, path))
    assert back["times"].tolist() == [1.0, 2.0, 3.0, 4.0]
    assert back["information"]["time"].startswith("load step number (imposed footing "
                                                  "rotation theta is not monotonic")


def test_a_result_of_unknown_kind_is_refused_before_writing(pushover, tmp_path):
    p = pushover.path
    fake = SimpleNamespace(**{name: getattr(p, name) for name in (
        "time", "footing", "x", "pressure", "gap", "status", "contact_length", "N", "M", "H",
        "snapshot_time", "snapshot_step", "displacement", "plastic_strain", "metadata")},
        kind="transient")
    with pytest.raises(InputError, match="result.kind = 'transient'"):
        write_footing_xdmf(tmp_path / "f.xdmf", pushover.model, fake)
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------------------------
# The footing's base
# ---------------------------------------------------------------------------------------------


def test_footing_mesh_is_the_base_line(pushover):
    # Reference: the model's contact nodes, sorted by x, joined by straight segments.
    f, back = pushover.model.footing, pushover.footing
    assert np.array_equal(back["points"][:, 0], f.x) and not back["points"][:, 1:].any()
    assert back["cells"][0].type == "line"
    assert back["cells"][0].data.tolist() == [[i, i + 1] for i in range(f.nodes - 1)]
    assert len(back["point_data"]) == pushover.path.theta.size


def test_pushover_contact_holds_the_result_and_its_conditions(pushover):
    opened = _check_contact(pushover.footing, pushover.path, pushover.model,
                            range(pushover.path.theta.size))
    assert opened >= 20  # it lifts off: 0, 0, 0, 1, 4, 5, ... of 9 nodes open (not vacuous)


def test_pushover_contact_forces_carry_the_applied_load(pushover):
    # Reference: N, the pushover's input, carried by the footing's equilibrium (1e-12); the
    # trapezoid within the 7 % of a coarse Q2 base (module docstring).
    N, x = pushover.N, pushover.model.footing.x
    assert pushover.path.metadata["N_applied"] == N
    for k, data in enumerate(pushover.footing["point_data"]):
        assert abs(data["contact_force"].sum() - N) <= 1e-12 * N, k
        trapezoid = np.trapezoid(data["contact_pressure"], x)
        assert abs(trapezoid / N - 1.0) <= 0.07, (k, trapezoid / N - 1.0)


def test_trapezoid_is_exact_on_a_linear_base(tmp_path):
    # Reference: a Q1 base node's weight is the trapezoid's, so the trapezoid of the pressure
    # read back is the applied N to 1e-12.
    run = _pushover(["continuum.element=Q1"])
    back = read_xdmf(write_footing_xdmf(tmp_path / "q1.xdmf", run.model, run.path))
    for data in back["point_data"]:
        assert abs(np.trapezoid(data["contact_pressure"], run.model.footing.x) - run.N) \
            <= 1e-12 * run.N
    assert (run.path.status[-1] == OPEN).any()


def test_footing_displacement_meets_the_soil_where_closed(pushover):
    # Reference: the contact condition uy = v − x θ at a closed node (gap 0, to 1e-12 m), with
    # the soil's displacement read from fields.xdmf at the same node and time.
    fields, footing, f = pushover.fields, pushover.footing, pushover.model.footing
    points = fields["points"][:, :2]
    at = [int(np.flatnonzero((points[:, 0] == x) & (points[:, 1] == 0.0))[0]) for x in f.x]
    for k in range(len(footing["times"])):
        closed = footing["point_data"][k]["footing_contact"] == 1
        base = footing["point_data"][k]["footing_displacement"]
        soil = fields["point_data"][k]["displacement"][at]
        assert np.all(np.abs(base[closed, 1] - soil[closed, 1]) <= 1e-12)


def test_dynamic_contact_holds_the_result_and_carries_the_load(dynamic):
    r, model = dynamic.result, dynamic.model
    opened = _check_contact(dynamic.footing, r, model, r.snapshot_step)
    assert opened >= 10  # lifts off in the second half of the pulse
    forces = [data["contact_force"].sum() for data in dynamic.footing["point_data"]]
    weight = dynamic.scene.structure.vertical_weight
    assert abs(forces[0] - weight) <= 1e-12 * weight  # t = 0: the static state
    assert np.allclose(forces, r.N[r.snapshot_step], rtol=1e-12, atol=0)


# ---------------------------------------------------------------------------------------------
# What ParaView reads
# ---------------------------------------------------------------------------------------------


def test_paraview_reader_sees_the_rotation_as_time(pushover):
    # Reference: VTK's vtkXdmfReader (ParaView's "XDMF Reader") on the same file: its time
    # steps are the rotations exactly; its Integrate Variables (vtkIntegrateAttributes) on the
    # line cells is numpy's trapezoid of the pressure to 1e-12.
    import vtkmodules.vtkFiltersParallel as parallel
    import vtkmodules.vtkIOXdmf2 as xdmf2
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as pipeline

    reader = xdmf2.vtkXdmfReader()
    reader.SetFileName(str(pushover.out / "footing.xdmf"))
    reader.UpdateInformation()
    steps = reader.GetOutputInformation(0).Get(pipeline.TIME_STEPS())
    assert list(steps) == pushover.rotations.tolist()
    last = steps[-1]
    reader.UpdateTimeStep(last)
    grid = reader.GetOutputDataObject(0).GetBlock(0)
    pressure = vtk_to_numpy(grid.GetPointData().GetArray("contact_pressure"))
    assert np.array_equal(pressure, pushover.path.pressure[-1])
    integrate = parallel.vtkIntegrateAttributes()
    integrate.SetInputData(grid)
    integrate.Update()
    integral = vtk_to_numpy(integrate.GetOutput().GetPointData().GetArray("contact_pressure"))
    reference = np.trapezoid(pushover.path.pressure[-1], pushover.model.footing.x)
    assert abs(integral[0] - reference) <= 1e-12 * abs(reference)
