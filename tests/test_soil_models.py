"""The soil models as plug-ins (upliftlab.continuum.materials): the registry, and each model's
compiled point return (the explicit route's) against its vectorised return map.

References, one per test:
- the registry: the scene format's list of soil models and the strength each reads
  (upliftlab/scenes/soil.py ``SOIL_MODELS``, which the core reads without the continuum);
- the compiled point returns: the model's vectorised return map (an independent implementation:
  tensors, LAPACK eigenvectors for the principal-space returns, batched numpy), step by step
  along strain paths at one point that cross every return region of the model (elastic,
  yielding, unloading, both edges, the apex); and a closed form at one point per model;
- the compiled element loop of each model: the vectorised map with the sparse Bᵀσ assembly
  (ContinuumModel.respond) on a coarse mesh;
- numba's cache: the cache's own hit and miss counters in a second process.
Units: kPa and strain; E = 50 MPa, ν = 0.3 (the clay scene's soil). Tension positive.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.continuum import materials as mat
from upliftlab.scenes import load_scene
from upliftlab.scenes.soil import FRICTIONAL, SOIL_MODELS, UNDRAINED

E, NU, CU = 5.0e4, 0.3, 50.0
G = E / (2 * (1 + NU))
K = E / (3 * (1 - 2 * NU))
LAM = K - 2 * G / 3
EPS = np.finfo(float).eps

#: The records each compiled model is checked with (Mohr–Coulomb at φ = 20°: at φ = 30° and
#: ν = 0.3 it never yields in oedometric compression, which needs sin φ < 1 − 2ν), and the
#: return regions its strain paths must cross. A model registered with a compiled point return
#: is added here.
COMPILED = {
    "elastic": ([mat.Elastic(E, NU)], {mat.Region.ELASTIC}),
    "tresca": ([mat.Tresca(E, NU, CU)],
               {mat.Region.ELASTIC, mat.Region.SMOOTH, mat.Region.EDGE_COMPRESSION,
                mat.Region.EDGE_EXTENSION}),
    "von_mises": ([mat.VonMises(E, NU, CU), mat.VonMises(E, NU, CU, 2.0e3)],
                  {mat.Region.ELASTIC, mat.Region.SMOOTH}),
    "mohr_coulomb": ([mat.MohrCoulomb(E, NU, 10.0, 20.0, 20.0),
                      mat.MohrCoulomb(E, NU, 10.0, 20.0, 5.0)], set(mat.Region)),
}
CASES = [(name, i) for name in mat.compiled_models() for i in range(len(COMPILED[name][0]))]


# ---------------------------------------------------------------------------------------------
# The registry
# ---------------------------------------------------------------------------------------------

def test_the_registry_implements_exactly_the_scene_models():
    # Reference: the scene format's list (core), names and order, and the strength each reads:
    # an undrained model's record has undrained_strength, a frictional one is Frictional
    # (c, φ, ψ), a model without strength has neither.
    assert list(mat.SOIL_MODELS) == list(SOIL_MODELS)
    for name, record in mat.SOIL_MODELS.items():
        assert record.name == name
        fields = record.__dataclass_fields__
        undrained = "undrained_strength" in fields
        frictional = issubclass(record, mat.Frictional)
        assert (undrained, frictional) == (SOIL_MODELS[name] == UNDRAINED,
                                           SOIL_MODELS[name] == FRICTIONAL), name
        assert callable(record.update)
    # the models with a compiled point return, and the one that falls back (Drucker–Prager)
    assert mat.compiled_models() == ("elastic", "tresca", "von_mises", "mohr_coulomb")
    assert mat.hardening_models() == ("von_mises",)
    assert mat.DruckerPrager(E, NU, 10.0, 30.0, 30.0).kernel_constants() is None


def test_the_scene_refuses_an_unknown_model_naming_every_valid_one():
    # Reference: the project's input rule (field, value, valid range), the valid range being
    # the registry's names.
    with pytest.raises(InputError) as info:
        load_scene("strip_footing_clay", overrides=["soil.model=cam_clay"])
    message = str(info.value)
    assert message.startswith("soil.model = 'cam_clay'")
    for name in mat.SOIL_MODELS:
        assert repr(name) in message


def test_kernel_constants_are_the_records_own_numbers():
    # Reference: the record's properties (λ, G, strengths, sin/cos of its angles), each field
    # of the constants the attribute of that name.
    for records, _ in COMPILED.values():
        for record in records:
            constants = record.kernel_constants()
            assert type(constants).point is not None
            for field, value in zip(constants._fields, constants):
                assert value == getattr(record, field)


# ---------------------------------------------------------------------------------------------
# Compiled point return against the vectorised map, along strain paths
# ---------------------------------------------------------------------------------------------

def strain_paths(record) -> dict[str, np.ndarray]:
    """Strain paths (n, 3, 3) at one point: plane-strain simple shear to 12 yield strains from
    an isotropic precompression of 80 kPa (yield on the smooth surface or main plane),
    oedometric compression past yield and back (the compression edge, then elastic
    unloading), oedometric extension (the extension edge), and for a frictional model
    isotropic tension to 3 times the apex with a little shear (the apex)."""
    strength = getattr(record, "undrained_strength", None) or getattr(record, "cohesion", CU)
    gammas = np.linspace(0.0, 12.0 * strength / G, 25)
    shear = np.zeros((len(gammas), 3, 3))
    shear[:, 0, 1] = shear[:, 1, 0] = gammas / 2
    shear[:, [0, 1, 2], [0, 1, 2]] += -80.0 / (3 * K)
    e = np.concatenate([np.linspace(0.0, -0.02, 21)[1:], -0.02 + np.linspace(0.0, 1e-3, 6)[1:]])
    oedometer = np.zeros((len(e), 3, 3))
    oedometer[:, 0, 0] = e
    extension = np.zeros((20, 3, 3))
    extension[:, 0, 0] = np.linspace(0.0, 0.01, 21)[1:]
    paths = {"shear": shear, "oedometer": oedometer, "extension": extension}
    if isinstance(record, mat.Frictional):
        apex = record.cohesion * record.cos_phi / record.sin_phi / (3 * K)
        tension = np.zeros((12, 3, 3))
        tension[:, [0, 1, 2], [0, 1, 2]] = np.linspace(0.0, 3.0 * apex, 13)[1:, None]
        tension[:, 0, 1] = tension[:, 1, 0] = 1e-5
        paths["tension"] = tension
    return paths


def four(tensor) -> np.ndarray:
    """(xx, yy, zz, xy) of a 3×3 tensor."""
    return np.array([tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1]])


def compiled_step(constants, strain, state) -> np.ndarray:
    """The compiled point return of ``strain`` from a vectorised ``state`` (9 numbers)."""
    p = state.plastic_strain
    return np.array(mat.point_return(constants, strain[0, 0], strain[1, 1], strain[2, 2],
                                     strain[0, 1], p[0, 0], p[1, 1], p[2, 2], p[0, 1],
                                     float(state.equivalent_plastic_strain)))


@pytest.mark.parametrize("name, index", CASES, ids=[f"{n}-{i}" for n, i in CASES])
def test_compiled_point_return_matches_the_vectorised_map_along_paths(name, index):
    # Reference: the model's vectorised map, at every step of every path from the same
    # converged state. The two evaluate the same closed forms in another order (the
    # principal-space returns with LAPACK eigenvectors against closed-form in-plane principal
    # values), so they agree to machine precision ε: the stress to 16 ε of the path's stress
    # scale, the plastic increments (Ce⁻¹ of a stress difference) to 16 ε of that scale over
    # 2G (measured at most 2.4 ε and 6.2 ε); elastic soil, whose arithmetic is the same, bit
    # for bit. The paths cross every return region of the model.
    records, regions = COMPILED[name]
    record = records[index]
    constants = record.kernel_constants()
    crossed, worst_stress, worst_plastic = set(), 0.0, 0.0
    for path in strain_paths(record).values():
        state = record.initial_state()
        got, ref = [], []
        for strain in path:
            stress, _, new = record(strain, state)
            got.append(compiled_step(constants, strain, state))
            ref.append(np.concatenate([four(stress), four(new.plastic_strain
                                                          - state.plastic_strain),
                                       [new.equivalent_plastic_strain
                                        - state.equivalent_plastic_strain]]))
            crossed.add(mat.Region(int(new.region)))
            state = new
        got, ref = np.array(got), np.array(ref)
        scale = np.abs(ref[:, :4]).max()
        worst_stress = max(worst_stress, np.abs(got[:, :4] - ref[:, :4]).max() / scale)
        worst_plastic = max(worst_plastic,
                            np.abs(got[:, 4:] - ref[:, 4:]).max() / (scale / (2 * G)))
    assert crossed == regions
    if name == "elastic":
        assert worst_stress == 0.0 and worst_plastic == 0.0
    assert worst_stress <= 16 * EPS
    assert worst_plastic <= 16 * EPS


# ---------------------------------------------------------------------------------------------
# Each compiled point return against a closed form at one point
# ---------------------------------------------------------------------------------------------

def point(record, strain, state=None) -> np.ndarray:
    """The compiled point return of a 3×3 ``strain`` from ``state`` (None: virgin)."""
    return compiled_step(record.kernel_constants(), strain,
                         state if state is not None else record.initial_state())


def test_elastic_point_is_hookes_law():
    # Reference: σ = λ tr ε 𝟏 + 2G ε (closed form), to 1e-14 of the stress.
    strain = np.array([[-2e-3, 5e-4, 0.0], [5e-4, 1e-3, 0.0], [0.0, 0.0, 3e-4]])
    got = point(mat.Elastic(E, NU), strain)
    ref = four(LAM * np.trace(strain) * np.eye(3) + 2 * G * strain)
    assert np.abs(got[:4] - ref).max() <= 1e-14 * np.abs(ref).max()
    assert np.all(got[4:] == 0.0)


def test_tresca_point_yields_at_two_cu():
    # Reference: closed forms. Plane-strain simple shear far past yield, from the virgin
    # state in one step: the main plane gives σ1 − σ3 = 2 c_u, so τ = c_u, no normal stress,
    # and γp = γ − c_u/G. Oedometric compression ε_xx = e returns to the compression edge:
    # σ_xx = K e − 4c_u/3, σ_yy = σ_zz = K e + 2c_u/3. Both to 1e-12 relative.
    tresca = mat.Tresca(E, NU, CU)
    gamma = 10 * CU / G
    shear = np.zeros((3, 3))
    shear[0, 1] = shear[1, 0] = gamma / 2
    got = point(tresca, shear)
    assert abs(got[3] - CU) <= 1e-12 * CU
    assert np.abs(got[:3]).max() <= 1e-12 * CU
    assert abs(2 * got[7] - (gamma - CU / G)) <= 1e-12 * gamma
    e = -0.02
    got = point(tresca, np.diag([e, 0.0, 0.0]))
    ref = [K * e - 4 * CU / 3, K * e + 2 * CU / 3, K * e + 2 * CU / 3]
    assert np.abs(got[:3] - ref).max() <= 1e-12 * abs(K * e)
    assert got[0] - got[1] == pytest.approx(-2 * CU, rel=1e-12)


def test_von_mises_point_hardens_along_simple_shear():
    # Reference: closed form of plane-strain simple shear with linear hardening, radial return
    # exact from the virgin state: τ = c_u + H γp/3, γp = (Gγ − c_u)/(G + H/3), to 1e-12.
    H = 2.0e3
    vm = mat.VonMises(E, NU, CU, H)
    gamma = 10 * CU / G
    shear = np.zeros((3, 3))
    shear[0, 1] = shear[1, 0] = gamma / 2
    got = point(vm, shear)
    gamma_p = (G * gamma - CU) / (G + H / 3)
    assert abs(got[3] - (CU + H * gamma_p / 3)) <= 1e-12 * CU
    assert abs(2 * got[7] - gamma_p) <= 1e-12 * gamma_p
    assert abs(got[8] - gamma_p / math.sqrt(3)) <= 1e-12 * gamma_p  # ε̄p = γp/√3


def test_mohr_coulomb_point_on_a_known_stress_path():
    # Reference: closed forms. Isotropic precompression p0, then plane-strain simple shear with
    # ψ = 0 (isochoric flow: the mean stress stays −p0), driven through the compiled point with
    # its own history: τ saturates at c cos φ + p0 sin φ (1e-10). Isotropic tension past the
    # apex returns to σ = c cot φ 𝟏 (1e-12).
    p0 = 80.0
    mc = mat.MohrCoulomb(E, NU, 10.0, 30.0, 0.0)
    constants = mc.kernel_constants()
    plastic, ebar = np.zeros(4), 0.0
    for gamma in np.linspace(0.0, 0.02, 41)[1:]:
        e = [-p0 / (3 * K)] * 3 + [gamma / 2]
        got = np.array(mat.point_return(constants, *e, *plastic, ebar))
        plastic, ebar = plastic + got[4:8], ebar + got[8]
    limit = mc.cohesion * mc.cos_phi + p0 * mc.sin_phi
    assert abs(got[3] - limit) <= 1e-10 * limit
    assert abs(got[:3].mean() + p0) <= 1e-10 * p0
    apex = mc.cohesion / math.tan(math.radians(mc.friction_angle))
    got = point(mc, np.eye(3) * 3 * apex / (3 * K))
    assert np.abs(got[:3] - apex).max() <= 1e-12 * apex and got[3] == 0.0


# ---------------------------------------------------------------------------------------------
# The compiled element loop of each model
# ---------------------------------------------------------------------------------------------

SCENE_SOILS = {
    "elastic": ["soil.model=elastic"],
    "tresca": [],
    "von_mises": ["soil.model=von_mises", "soil.hardening_modulus=2000"],
    "mohr_coulomb": ["soil.model=mohr_coulomb", "soil.cohesion=5", "soil.friction_angle=30",
                     "soil.dilation_angle=10"],
}


@pytest.mark.parametrize("name", mat.compiled_models())
def test_each_models_element_loop_matches_the_assembly(name):
    # Reference: ContinuumModel.respond (the model's vectorised map, sparse Bᵀσ) from the
    # geostatic state at a random displacement that yields most points of a plastic soil, on
    # 2 elements across; forces to 1e-12 of their peak (measured ~1e-15: the same formulas in
    # another order), ε̄p to 1e-14.
    from upliftlab.continuum import build_model, geostatic
    from upliftlab.continuum.dynamics.soil_force import SoilForce

    scene = load_scene("strip_footing_clay",
                       overrides=SCENE_SOILS[name] + ["continuum.elements_across=2"])
    model = build_model(scene)
    assert type(model.material).name == name
    state = geostatic(model)
    u = np.random.default_rng(5).normal(scale=2e-3, size=model.disc.ndofs)
    response = model.respond(u, state.material, state.eigenstrain)
    force = SoilForce(model, state)
    assert force.compiled
    got = force(u)
    ref = response.residual + model.body_force
    assert np.abs(got - ref).max() <= 1e-12 * np.abs(ref).max()
    assert np.abs(force.material.equivalent_plastic_strain
                  - response.material.equivalent_plastic_strain).max() <= 1e-14
    if name != "elastic":
        assert np.mean(response.material.region > 0) > 0.5


_CACHE_PROBE = """
import numpy as np
from upliftlab.continuum import materials as mat
from upliftlab.continuum.dynamics import kernels
for record in (mat.Tresca(5e4, 0.3, 50.0), mat.MohrCoulomb(5e4, 0.3, 5.0, 30.0, 30.0)):
    one = np.ones((1, 1, 1))
    kernels._elements_serial(np.zeros((1, 2)), np.zeros((1, 1), np.int64), one, one,
                             np.ones((1, 1)), np.zeros((1, 1, 4)), np.zeros((1, 1, 4)),
                             np.zeros((1, 1)), record.kernel_constants(), np.zeros((1, 1)),
                             np.zeros((1, 1, 4)), np.zeros((1, 1, 2)))
stats = kernels._elements_serial.stats
print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))
"""


def test_each_models_element_loop_is_cached(tmp_path):
    # Reference: numba's own counters. A first process compiles the element loop for two
    # soil models (two signatures, the constants' types) and writes them to an empty cache;
    # a second process loads both from it and compiles nothing.
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    runs = [subprocess.run([sys.executable, "-c", _CACHE_PROBE], env=env, capture_output=True,
                           text=True, check=True).stdout.split() for _ in range(2)]
    assert runs == [["0", "2"], ["2", "0"]]
