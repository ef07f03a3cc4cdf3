"""Bad input, the strip-footing scene, and result files of upliftlab.continuum.

References: the project's input rule ("a scene or motion that makes no sense gets an error that
names the field, the value and the valid range, before any work starts"; results are records saved
atomically with provenance); the scene's stated design numbers (FS_v = 3 on (2 + π) c_u B, T = 0.3
s, I0 of a 2 m × 4 m block, a Winkler bed with the continuum's K_r).
"""

from __future__ import annotations

import dataclasses
import copy
import math

import numpy as np
import pytest
import skfem

from upliftlab.checks import InputError
from upliftlab.continuum import (Envelope, build_model, make_model, model as model_module,
                                 rotation_pushover)
from upliftlab.continuum import geostatic
from upliftlab.meshes import soil_mesh
from upliftlab.results import read_netcdf
from upliftlab.scenes import ContinuumOptions, Soil, load_scene, scene_from_dict
from upliftlab.anchors import prandtl_capacity

B = 2.0
SOIL = Soil(youngs_modulus=50e3, poisson_ratio=0.3, density=1.8, model="tresca",
            undrained_strength=50.0)


@pytest.fixture
def no_meshing(monkeypatch):
    """Fail loudly if a mesh is built: bad input must be refused before any work."""
    def refuse(*args, **kwargs):
        raise AssertionError("a mesh was built before the input was checked")
    monkeypatch.setattr(model_module, "from_options", refuse)


@pytest.mark.parametrize("change, message", [
    (dict(poisson_ratio=0.5), r"^soil.poisson_ratio = 0.5: valid range is \(-1, 0.5\)"),
    (dict(poisson_ratio=0.7), r"^soil.poisson_ratio = 0.7: valid range is \(-1, 0.5\)"),
    (dict(undrained_strength=-10.0), r"^soil.undrained_strength = -10: must be > 0"),
    (dict(model="mohr_coulomb", cohesion=5.0, friction_angle=60.0),
     r"^soil.friction_angle = 60: valid range is \[0, 60\)"),
    (dict(model="mohr_coulomb", cohesion=5.0, friction_angle=-5.0),
     r"^soil.friction_angle = -5: valid range is \[0, 60\)"),
    (dict(interface="coulomb", interface_friction=0.0), r"^soil.interface_friction = 0: "),
    (dict(k0=-0.5), r"^soil.k0 = -0.5: valid range is \(0, 10\]"),
])
def test_bad_soil_is_refused_before_meshing(no_meshing, change, message):
    # Reference: the project's input rule: field, value and valid range, before any work.
    with pytest.raises(InputError, match=message):
        make_model(dataclasses.replace(SOIL, **change), B)


def test_footing_wider_than_the_domain_is_refused(no_meshing):
    # Reference: the project's input rule; the domain must be wider than the footing (domain_width
    # > 1 B).
    with pytest.raises(InputError, match=r"^continuum.domain_width = 0.8: the footing"):
        make_model(SOIL, B, ContinuumOptions(domain_width=0.8))


def test_footing_that_does_not_fit_a_given_mesh_is_refused():
    # Reference: the project's input rule; the mesh's footing boundary must span [-b, b].
    mesh = soil_mesh(B, elements_across=4, domain_width=3, domain_depth=1)
    with pytest.raises(InputError, match=r"^foundation.half_width = 2: the mesh's footing"):
        make_model(SOIL, 4.0, mesh=mesh)


def test_mesh_without_named_boundaries_is_refused():
    # Reference: meshes.BOUNDARIES: footing, surface, sides and bottom.
    bare = skfem.MeshQuad1.init_tensor(np.linspace(-3, 3, 7), np.linspace(-2, 0, 3))
    with pytest.raises(InputError, match=r"^mesh.boundaries = \[\]: missing footing, surface"):
        make_model(SOIL, B, mesh=bare)
    full = soil_mesh(B, elements_across=4, domain_width=3, domain_depth=1).mesh
    partial = skfem.MeshQuad1(full.p, full.t).with_boundaries(
        {"footing": full.boundaries["footing"]})
    with pytest.raises(InputError, match=r"missing surface, sides, bottom"):
        make_model(SOIL, B, mesh=partial)


def test_geostatic_stress_outside_the_yield_surface_is_refused():
    # Reference: with K0 = 0.3 the geostatic deviator (1 − K0) ρ g |y|/2 exceeds c_u = 50 kPa
    # below 50/(0.35 × 17.65) = 8.1 m, inside the 20 m deep box.
    model = make_model(dataclasses.replace(SOIL, k0=0.3), B,
                       ContinuumOptions(elements_across=2))
    with pytest.raises(InputError, match=r"^soil.k0 = 0.3: the geostatic stress violates"):
        geostatic(model)


@pytest.mark.parametrize("table, key, value, message", [
    ("soil", "k0", 0.0, r"^soil.k0 = 0: valid range is \(0, 10\]"),
    ("soil", "poisson_ratio", 0.5, r"^soil.poisson_ratio = 0.5: valid range is \(-1, 0.5\)"),
    ("soil", "undrained_strength", -1.0, r"^soil.undrained_strength = -1: must be > 0"),
    ("continuum", "intorder", 0, r"^continuum.intorder = 0: must be an integer >= 1"),
    ("continuum", "domain_width", 1.0, r"^continuum.domain_width = 1: valid range"),
    ("continuum", "spam", 1, r"^continuum.spam: unknown key"),
])
def test_scene_tables_refuse_bad_continuum_keys(table, key, value, message):
    # Reference: scenes.py, unknown keys and out-of-range values are errors naming the field.
    data = copy.deepcopy(load_scene("strip_footing_clay").data)  # a scene's data is read-only
    data[table][key] = value
    with pytest.raises(InputError, match=message):
        scene_from_dict(data, merged=True)


def test_strip_footing_scene_loads_in_both_models():
    # Reference: the scene's design numbers (its description): FS_v = (2 + π) c_u B / N = 3,
    # fixed-base T = 2π √(m/k) = 0.3 s, I0 = m (B² + H²)/12, K_v = 3 K_r/b² with
    # K_r = π G B²/(8(1 − ν)); all to 1e-4.
    from upliftlab.reduced import build_model as build_reduced

    scene = load_scene("strip_footing_clay")
    s, f, soil = scene.structure, scene.foundation, scene.soil
    m = s.weight / scene.g
    assert abs(prandtl_capacity(soil.undrained_strength, f.width) / s.weight / 3 - 1) <= 1e-4
    assert abs(2 * math.pi * math.sqrt(m / s.stories[0].stiffness) / 0.3 - 1) <= 1e-4
    assert abs(s.rotary_inertia / (m * (2.0 ** 2 + 4.0 ** 2) / 12) - 1) <= 1e-4
    k_r = math.pi * soil.shear_modulus * f.width ** 2 / (8 * (1 - soil.poisson_ratio))
    assert abs(f.stiffness / (3 * k_r / f.half_width ** 2) - 1) <= 1e-4
    assert build_reduced(scene).weight == s.weight
    model = build_model(scene)
    assert model.dofs == 20160 and model.disc.element == "Q2" and model.disc.intorder == 2
    assert model.k0 == 1.0 and model.width == f.width


def test_build_model_needs_soil():
    # Reference: the project's input rule; a scene without [soil] cannot run in the continuum.
    scene = load_scene("strip_footing_clay")
    with pytest.raises(InputError, match=r"^soil is missing"):
        build_model(dataclasses.replace(scene, soil=None))


def test_pushover_saves_netcdf_with_provenance(tmp_path):
    # Reference: the project's rule for results: a record saved atomically (no partial files),
    # readable, carrying provenance (scene digest, mesh, DOFs).
    scene = load_scene("strip_footing_clay", overrides=(
        "soil.model=elastic", "soil.undrained_strength=", "continuum.elements_across=4"))
    model = build_model(scene)
    path = rotation_pushover(model, scene.structure.vertical_weight, [0.001, 0.002])
    target = path.save(tmp_path / "out" / "pushover.nc")
    variables, attrs = read_netcdf(target)
    assert np.array_equal(variables["M"], path.M) and variables["pressure"].shape == (2, 9)
    assert attrs["scene_digest"] == scene.digest and attrs["dofs"] == model.dofs
    assert attrs["kind"] == "rotation_pushover"
    assert [p.name for p in target.parent.iterdir()] == ["pushover.nc"]


def test_envelope_saves_netcdf(tmp_path):
    # Reference: the project's rule for results; the normalised envelope v = V/V_ult, m = M/(B
    # V_ult).
    envelope = Envelope(V=np.array([100.0, 200.0]), M=np.array([30.0, 40.0]), V_ult=400.0,
                        width=2.0, metadata={"analysis": "vm_envelope"})
    variables, attrs = read_netcdf(envelope.save(tmp_path / "envelope.nc"))
    assert np.allclose(variables["v"], [0.25, 0.5]) and np.allclose(variables["m"], [0.0375, 0.05])
    assert attrs["V_ult"] == 400.0 and attrs["analysis"] == "vm_envelope"
