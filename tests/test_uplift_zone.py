"""The uplift-zone study keeps its pushover as data (issue 34 §4): compute gives a Dataset,
and the files and summary are written from that Dataset alone.

References: the pushover as the continuum returns it (every array read back bit for bit, the
scene's digest unchanged), and the files the continuum writes for it
(:func:`upliftlab.continuum.output.series.write_outputs`).
"""

from __future__ import annotations

import json

import numpy as np

from upliftlab.comparisons.studies import uplift_zone
from upliftlab.continuum import build_model, rotation_pushover
from upliftlab.continuum.statics.results import StaticPath
from upliftlab.results import read_dataset
from upliftlab.scenes import load_scene

ARRAYS = ("u", "v", "theta", "H", "N", "M", "contact_length", "x", "pressure", "shear", "gap",
          "status", "iterations", "cuts", "snapshot_step", "displacement", "plastic_strain",
          "max_shear_stress", "dof_xy", "dof_direction", "element_xy")


def test_a_path_comes_back_from_its_dataset_bit_for_bit():
    scene = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4"])
    model = build_model(scene)
    path = rotation_pushover(model, scene.structure.vertical_weight,
                             np.linspace(0.0, 2e-3, 4), record_fields=True)
    back = StaticPath.from_xarray(path.to_xarray(), path.metadata)
    for name in ARRAYS:
        assert np.array_equal(getattr(back, name), getattr(path, name)), name
    assert (back.kind, back.width, back.metadata) == (path.kind, path.width, path.metadata)


def test_the_study_writes_its_files_from_the_dataset(tmp_path):
    run = uplift_zone.run(fast=True, out=tmp_path / "z")
    ds = run.data
    scene, model, path = uplift_zone.pushover_of(ds)
    assert scene.digest == load_scene("strip_footing_clay",
                                      overrides=["continuum.elements_across=8"]).digest
    # every step converged; the path starts at θ = 0 under N alone
    assert ds.sizes["step"] == int(ds.attrs["rotation_steps"]) + 1 >= 13
    assert ds.theta.values[0] == 0.0
    written = read_dataset(run.study.directory / "result.nc")
    for name in ("theta", "M", "contact_length", "pressure"):
        assert np.array_equal(written[name].values, ds[name].values), name
    assert run.study.summary == uplift_zone.summarise(ds, scene, model, path)
    assert "(coarse mesh: fast mode)" in run.study.summary
    assert json.loads(ds.attrs["run_metadata"])["scene"] == "strip_footing_clay"
    assert {p.name for p in run.study.files} >= {"uplift.png", "moment_rotation.png",
                                                  "result.nc", "fields.xdmf"}
