"""Outputs of the continuum model: recorded soil fields, XDMF time series, renders, the M–θ
figure and the ``upliftlab continuum`` command (upliftlab.continuum.output.series,
upliftlab.meshes.render, upliftlab.cli).

References:
- recording fields is bookkeeping: every history equals the unrecorded run's exactly, and the
  recorded displacement of a closed contact node equals the footing's motion there,
  uy = v − x θ (the contact condition, solved exactly);
- the Tresca criterion bounds the element-averaged (σ1 − σ3)/2 by c_u;
- the XDMF file read back by meshio equals what was written (same steps, times and fields; a
  pushover's time is its rotation θ: tests/test_continuum_xdmf.py checks the footing's file);
- the linear sub-mesh tiles the domain: its cell areas sum to the box area, all positive;
- the tensionless Winkler closed form (compression-only springs) and the half-plane onset M = N B/4.
Figures are checked by numbers (size, colour content, frame count), never by pixel comparison.
"""

from __future__ import annotations

import math
import os
from types import SimpleNamespace

import numpy as np
import pytest

from upliftlab import cli
from upliftlab.checks import InputError
from upliftlab.continuum import OPEN, build_model, make_model, rotation_pushover
from upliftlab.continuum.output.series import (figure_title, half_plane_rocking,
                                               moment_rotation_figure, pushover_summary, read_xdmf,
                                               rotation_schedule, save_figure, winkler_rocking,
                                               write_xdmf)
from upliftlab.meshes import soil_mesh
from upliftlab.meshes.render import (animate_uplift, linear_submesh, render_uplift,
                                     snapshot_rows)
from upliftlab.scenes import ContinuumOptions, Soil, load_scene
from upliftlab.anchors import prandtl_capacity

import imageio.v3 as imageio

SCENE = "strip_footing_clay"
COARSE = ["continuum.elements_across=4"]  # Q2, 10B x 10B, 162 elements, 1296 DOFs


@pytest.fixture(scope="module")
def run():
    """A rotation pushover of the clay scene (Tresca, FS_v = 3) on a coarse mesh to 10 θ_on,
    with and without recorded fields."""
    scene = load_scene(SCENE, overrides=COARSE)
    model = build_model(scene)
    N, B, soil = scene.structure.vertical_weight, model.width, scene.soil
    theta_on = 2 * N * (1 - soil.poisson_ratio) / (math.pi * soil.shear_modulus * B)
    rotations = rotation_schedule(10 * theta_on, 8, theta_on)  # 0, 0.4, 0.8, 1.25, ... θ_on
    path = rotation_pushover(model, N, rotations, record_fields=True)
    plain = rotation_pushover(model, N, rotations)
    return SimpleNamespace(scene=scene, model=model, path=path, plain=plain)


def test_recording_fields_changes_no_result(run):
    # Reference: bookkeeping only; histories equal bit for bit.
    for name in ("u", "v", "theta", "H", "N", "M", "contact_length", "pressure", "gap",
                 "status", "iterations"):
        assert np.array_equal(getattr(run.path, name), getattr(run.plain, name)), name
    assert run.plain.displacement is None and not run.plain.has_fields
    n, model = run.path.theta.size, run.model
    assert run.path.displacement.shape == (n, model.disc.ndofs)
    assert run.path.plastic_strain.shape == (n, model.mesh.nelements)
    assert np.array_equal(run.path.snapshot_time, np.arange(1.0, n + 1.0))


def test_recorded_displacement_follows_the_footing_at_closed_nodes(run):
    # Reference: gap g_i = (v − x_i θ) − uy_i = 0 at closed nodes (exact contact, to 1e-12 m);
    # the fields of snapshot k belong to history row k.
    f = run.model.footing
    for k, row in enumerate(snapshot_rows(run.path)):
        u, v, theta = run.path.footing[row]
        closed = run.path.status[row] != OPEN
        uy = run.path.displacement[k][f.uy]
        assert np.max(np.abs((v - f.x * theta - uy)[closed])) <= 1e-12
        assert np.allclose((v - f.x * theta - uy)[~closed], run.path.gap[row][~closed],
                           atol=1e-12)


def test_plastic_fields_respect_the_tresca_criterion(run):
    # Reference: (σ1 − σ3)/2 ≤ c_u = 50 kPa at every quadrature point, so in every element
    # average (to 1e-9 relative); the plastic zone grows (ε̄p never decreases in a monotonic
    # pushover) and reaches c_u at the last step.
    cu = run.scene.soil.undrained_strength
    assert run.path.max_shear_stress.max() <= cu * (1 + 1e-9)
    assert run.path.max_shear_stress[-1].max() >= cu * (1 - 1e-6)
    assert run.path.plastic_strain.min() >= 0.0
    assert np.all(np.diff(run.path.plastic_strain, axis=0) >= -1e-12)
    assert run.path.plastic_strain[-1].max() > 0.0


def test_record_fields_picks_steps_and_refuses_bad_indices(run):
    N = run.scene.structure.vertical_weight
    picked = rotation_pushover(run.model, N, run.path.theta[:3], record_fields=[0, -1])
    assert picked.snapshot_step.tolist() == [0, 2]
    assert np.array_equal(picked.displacement[1], run.path.displacement[2])
    for bad in ([3], [0.5], []):
        with pytest.raises(InputError, match="record_fields"):
            rotation_pushover(run.model, N, run.path.theta[:3], record_fields=bad)


def test_xdmf_round_trip_inside_the_run_directory(run, tmp_path, monkeypatch):
    # Reference: meshio reads back what was written; nothing lands in the working directory.
    cwd = tmp_path / "elsewhere"
    cwd.mkdir()
    monkeypatch.chdir(cwd)
    target = tmp_path / "run" / "fields.xdmf"
    write_xdmf(target, run.model, run.path)
    assert sorted(p.name for p in target.parent.iterdir()) == ["fields.h5", "fields.xdmf"]
    assert list(cwd.iterdir()) == []
    back = read_xdmf(target)
    sub = linear_submesh(run.model.disc.basis)
    n = run.path.theta.size
    assert back["times"].tolist() == run.path.theta.tolist()  # a pushover's time is θ (rad)
    assert len(back["point_data"]) == n
    assert np.array_equal(back["points"][:, :2], sub.points)
    assert back["cells"][0].type == "quad" and len(back["cells"][0].data) == 4 * 162
    for k in range(n):
        u = sub.vectors(run.path.displacement[k])
        assert np.array_equal(back["point_data"][k]["displacement"][:, :2], u)
        assert np.array_equal(back["point_data"][k]["displacement"][:, 2], np.zeros(len(u)))
        assert np.allclose(back["point_data"][k]["displacement_magnitude"],
                           np.linalg.norm(u, axis=1), rtol=1e-15)
        cells = back["cell_data"][k]
        assert np.array_equal(cells["equivalent_plastic_strain"],
                              sub.cell_values(run.path.plastic_strain[k]))
        assert np.array_equal(cells["max_shear_stress"],
                              sub.cell_values(run.path.max_shear_stress[k]))


@pytest.mark.parametrize("element, per_element", [("Q2", 4), ("P2", 4), ("Q1", 1), ("P1", 1)])
def test_linear_submesh_tiles_the_domain(element, per_element):
    # Reference: exact geometry: the sub-cells cover the 3B x 1.5B box (area 18 m²) once,
    # each counter-clockwise, and every basis node is a point.
    import skfem

    mesh = soil_mesh(2.0, element=element, elements_across=4, domain_width=3, domain_depth=1.5)
    basis = skfem.Basis(mesh.mesh, skfem.ElementVector(mesh.skfem_element))
    sub = linear_submesh(basis)
    p = sub.points[sub.cells]  # (nc, k, 2)
    x, y = p[..., 0], p[..., 1]
    areas = 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)
    assert len(sub.cells) == per_element * mesh.mesh.nelements
    assert areas.min() > 0.0
    assert abs(areas.sum() - 18.0) <= 1e-12 * 18.0
    assert len(sub.points) == basis.N // 2


def test_render_writes_a_legible_png(run, tmp_path):
    # Numbers, not pixels: a page of at least 700 × 600 pixels whose soil panel is colour
    # mapped (over 10 % strongly coloured pixels, many distinct colours).
    target = tmp_path / "uplift.png"
    render_uplift(target, run.path, run.model.disc.basis, run.model.width, title=SCENE)
    image = imageio.imread(target)
    assert image.shape[0] >= 600 and image.shape[1] >= 700 and image.shape[2] in (3, 4)
    rgb = image[..., :3].astype(int)
    colourful = (rgb.max(axis=-1) - rgb.min(axis=-1)) > 40
    assert colourful.mean() > 0.10
    assert len(np.unique(rgb.reshape(-1, 3), axis=0)) > 200


def test_gif_has_one_frame_per_snapshot(run, tmp_path):
    target = tmp_path / "uplift.gif"
    animate_uplift(target, run.path, run.model.disc.basis, run.model.width)
    frames = imageio.imread(target, index=None)
    assert frames.shape[0] == run.path.snapshot_time.size


def test_winkler_closed_form_matches_the_anchor_table():
    # Reference: the closed form of a rigid footing on compression-only springs (θ/θ_up -> M/(N B),
    # c/B), to 1e-6.
    N, B, k = 100.0, 2.0, 5e4
    theta_up = 2 * N / (k * B ** 2)
    ref = winkler_rocking(np.array([0.5, 1.5, 3.0, 10.0]) * theta_up, N, B, k)
    assert np.allclose(ref["M"] / (N * B), [0.083333, 0.227834, 0.307550, 0.394591], atol=1e-6)
    assert np.allclose(ref["c"] / B, [1.0, 0.816497, 0.577350, 0.316228], atol=1e-6)
    assert abs(ref["settlement"][0] - N / (k * B)) <= 1e-15  # full contact: N/(kB)


def test_half_plane_closed_form_is_continuous_at_uplift():
    # Reference: M = N B/4 at θ_on from both branches (tests/test_continuum_contact.py).
    N, B, G, nu = 171.39, 2.0, 50e3 / 2.6, 0.3
    theta_on = half_plane_rocking(0.0, N, B, G, nu)["theta_on"]
    below, above = half_plane_rocking(theta_on * np.array([1 - 1e-12, 1 + 1e-12]), N, B, G, nu)["M"]
    assert abs(below / (N * B) - 0.25) <= 1e-9 and abs(above / (N * B) - 0.25) <= 1e-9


def test_moment_rotation_figure_is_written(run, tmp_path):
    fig = moment_rotation_figure(run.path, scene=run.scene)
    labels = [line.get_label() for ax in fig.axes for line in ax.get_lines()]
    assert any("Winkler" in label for label in labels)
    assert any("half-plane" in label for label in labels)
    target = save_figure(fig, tmp_path / "moment_rotation.png")
    image = imageio.imread(target)
    assert image.shape[0] >= 600 and image.shape[1] >= 500


def test_a_dynamic_shaped_result_matches_snapshots_to_the_nearest_time(run, tmp_path):
    # A DynamicResult's duck type (no snapshot_step): snapshots at times between samples map to
    # the nearest row, and the XDMF carries their times.
    p = run.path
    fake = SimpleNamespace(time=0.01 * np.arange(p.theta.size), footing=p.footing, x=p.x,
                           pressure=p.pressure, gap=p.gap, status=p.status, kind="dynamic",
                           contact_length=p.contact_length,
                           N=p.N, M=p.M, H=p.H, snapshot_time=np.array([0.0, 0.0149, 0.061]),
                           displacement=p.displacement[[0, 1, 6]],
                           plastic_strain=p.plastic_strain[[0, 1, 6]], metadata=p.metadata)
    assert snapshot_rows(fake).tolist() == [0, 1, 6]
    write_xdmf(tmp_path / "d.xdmf", run.model, fake)
    assert read_xdmf(tmp_path / "d.xdmf")["times"].tolist() == [0.0, 0.0149, 0.061]


def test_pushover_summary_reports_onset_peak_and_contact_loss(run):
    # Reference: onset eccentricity near the half-plane B/4 (plasticity under the toe lowers it
    # on this coarse mesh: asserted within 10 %), the peak moment below the V–M capacity
    # B V_ult/9 + 10 % (Meyerhof's effective width, v = 1/3), and contact lost over more than half
    # the base.
    s = pushover_summary(run.path)
    assert abs(s["onset_e_over_B"] / 0.25 - 1.0) <= 0.10
    v_ult = prandtl_capacity(50.0, 2.0)
    assert 0.9 <= s["peak_M"] / (2.0 * v_ult / 9.0) <= 1.10
    assert 0.5 <= s["max_contact_loss"] < 1.0


def test_cli_pushover_writes_every_file_and_prints_the_summary(tmp_path, capsys):
    out = tmp_path / "run"
    code = cli.main(["continuum", SCENE, "--mesh", "elements_across=4", "--steps", "6",
                     "--out", str(out)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    names = sorted(p.name for p in out.iterdir())
    assert names == ["fields.h5", "fields.xdmf", "footing.h5", "footing.xdmf",
                     "moment_rotation.png", "result.nc", "uplift.gif", "uplift.png",
                     "upliftlab-run.json"]
    lines = captured.out.strip().splitlines()
    assert len(lines) == 1 and "uplift onset at e = " in lines[0] and "peak M = " in lines[0]
    assert "max contact loss" in lines[0]
    steps = 6 + 1 + 2  # θ = 0, six steps, 0.4 and 0.8 θ_on (rotation_schedule)
    assert f"step {steps}/{steps}" in captured.err
    fields, footing = read_xdmf(out / "fields.xdmf"), read_xdmf(out / "footing.xdmf")
    assert len(fields["times"]) == steps
    # both series share their time values: the rotation θ (rad), from 0, increasing
    assert footing["times"].tolist() == fields["times"].tolist()
    assert fields["times"][0] == 0.0 and np.all(np.diff(fields["times"]) > 0.0)
    assert fields["information"]["time"] == footing["information"]["time"] == \
        "imposed footing rotation theta [rad]"
    assert "time = imposed footing rotation theta [rad]" in captured.err
    assert imageio.imread(out / "uplift.gif", index=None).shape[0] == steps


@pytest.mark.parametrize("args, message", [
    (["--mesh", "elemnts_across=4"], "--mesh 'elemnts_across': unknown mesh key"),
    (["--mesh", "elements_across"], "--mesh 'elements_across': expected KEY=VALUE"),
    (["--mesh", "elements_across=1"], "continuum.elements_across"),
    (["--theta-max", "0"], "--theta-max = 0: valid range is (0, 0.1]"),
    (["--theta-max", "-0.01"], "--theta-max = -0.01"),
    (["--theta-max", "big"], "--theta-max = 'big': expected a number"),
    (["--analysis", "static"], "--analysis = 'static': must be one of pushover, dynamic"),
    (["--steps", "1"], "--steps = 1"),
    (["--set", "soil.poisson_ratio=0.5"], "soil.poisson_ratio"),
])
def test_cli_bad_input_exits_2_before_any_work(args, message, tmp_path, capsys, monkeypatch):
    import upliftlab.continuum as continuum

    def no_work(*_a, **_k):
        raise AssertionError("a model was built")

    monkeypatch.setattr(continuum, "build_model", no_work)
    out = tmp_path / "run"
    code = cli.main(["continuum", SCENE, "--out", str(out), *args])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert len(err) == 1 and err[0].startswith("upliftlab: error: ") and message in err[0], err
    assert not out.exists()


def test_unrecorded_path_is_refused_by_the_writers(run, tmp_path):
    with pytest.raises(InputError, match="no soil fields recorded"):
        write_xdmf(tmp_path / "f.xdmf", run.model, run.plain)
    assert not (tmp_path / "f.xdmf").exists()


def test_elastic_soil_renders_without_plasticity(tmp_path):
    # Elastic soil: no plastic strain; the picture still writes, its colour bar says so.
    soil = Soil(youngs_modulus=50e3, poisson_ratio=0.3, model="elastic")
    model = make_model(soil, 2.0, ContinuumOptions(elements_across=4, domain_width=4,
                                                   domain_depth=3))
    path = rotation_pushover(model, 100.0, [0.0, 0.002, 0.004], record_fields=[-1])
    assert path.plastic_strain.max() == 0.0
    render_uplift(tmp_path / "e.png", path, model.disc.basis, model.width)
    assert os.path.getsize(tmp_path / "e.png") > 10_000


@pytest.mark.parametrize("metadata, title", [
    ({"scene": "sand"}, "sand"),
    ({"scene": "sand", "incomplete": 1, "completed_until": 4.5},
     "sand (incomplete: until t = 4.5 s)"),
    ({"scene": "sand", "incomplete": 1, "completed_until": 11.3424, "failure": "bearing",
      "failure_time": 11.34353}, "sand (failed in bearing at t = 11.34 s)"),
])
def test_a_figure_of_a_run_that_did_not_finish_says_so(metadata, title):
    # Reference: the metadata written by the time loops for a finished, an interrupted and a
    # failed run; the title is what a reader of the picture alone sees.
    assert figure_title(SimpleNamespace(metadata=metadata)) == title
