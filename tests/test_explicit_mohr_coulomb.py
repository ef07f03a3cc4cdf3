"""The compiled Mohr–Coulomb return map of the explicit route
(continuum/materials/mohr_coulomb.py, ``mohr_coulomb_point``) and the explicit runs it serves.

References, one per test:
- the one-point return: the vectorised map ``mohr_coulomb.mohr_coulomb`` (an independent
  implementation: LAPACK eigh of the 3×3 trial stress, batched matrix returns onto the planes
  with a 2×2 inverse, tensor rotation by einsum), whose region codes show that every branch
  (elastic, main plane, both edges, apex) is hit;
- the explicit run: the Python loop with that vectorised map and the sparse Bᵀσ assembly
  (the fallback every material without a compiled map takes), on the same scene;
- the energy account of that run: conservation, closed by central differences to O(dt²).
"""

from __future__ import annotations

import numpy as np
import pytest

from upliftlab.continuum import build_model
from upliftlab.continuum.dynamics.run import DynamicOptions, run_dynamic
from upliftlab.continuum.materials import MohrCoulomb, Region, point_return
from upliftlab.scenes import load_scene

#: The Winkler map's frictional soil (comparisons/studies/winkler_map/grid.py SOILS["sand"]) on the
#: clay scene's footing and structure, 4 elements across, 0.4 s of its 0.6 g Ricker pulse.
SAND = ["soil.model=mohr_coulomb", "soil.cohesion=5", "soil.friction_angle=30",
        "soil.dilation_angle=30", "continuum.elements_across=4", "motion.duration=0.4",
        "motion.amplitude=0.6"]


def _components(tensor):
    """(n, 4) components xx, yy, zz, xy of (3, 3, n) tensors."""
    return np.stack([tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1]], axis=1)


@pytest.mark.parametrize("dilation", [30.0, 10.0])
def test_compiled_mohr_coulomb_matches_the_vectorised_return(dilation):
    # Reference: the vectorised mohr_coulomb at 600 random plane-strain strains from a
    # plastic history (a first update at 70 % of the strain, so the kernel starts from a
    # nonzero plastic strain); a shared random volumetric part spreads the trial stresses
    # from compression (main plane, edges) to tension (apex). Stress and plastic strain to
    # 1e-9 relative (measured 1.1e-15 at most: the same closed forms, other round-off).
    material = MohrCoulomb(50e3, 0.3, 5.0, 30.0, dilation)
    rng = np.random.default_rng(11)
    n = 600
    e = rng.normal(scale=1e-3, size=(4, n))
    volumetric = rng.normal(scale=1e-3, size=n)
    strain = np.zeros((3, 3, n))
    strain[0, 0], strain[1, 1] = e[0] + volumetric, e[1] + volumetric
    strain[2, 2] = 0.3 * (e[2] + volumetric)
    strain[0, 1] = strain[1, 0] = e[3]
    _, _, old = material(0.7 * strain, material.initial_state(n))
    stress, _, new = material(strain, old)
    constants = material.kernel_constants()
    assert constants[3:] == (material.sin_phi, material.cos_phi, material.sin_psi)
    p = old.plastic_strain
    got = np.array([point_return(
        constants, strain[0, 0, i], strain[1, 1, i], strain[2, 2, i], strain[0, 1, i],
        p[0, 0, i], p[1, 1, i], p[2, 2, i], p[0, 1, i], old.equivalent_plastic_strain[i])
        for i in range(n)])
    ref_stress = _components(stress)
    ref_plastic = _components(new.plastic_strain - p)
    ref_bar = new.equivalent_plastic_strain - old.equivalent_plastic_strain
    assert np.abs(got[:, :4] - ref_stress).max() <= 1e-9 * np.abs(ref_stress).max()
    assert np.abs(got[:, 4:8] - ref_plastic).max() <= 1e-9 * np.abs(ref_plastic).max()
    assert np.abs(got[:, 8] - ref_bar).max() <= 1e-9 * ref_bar.max()
    counts = np.bincount(new.region, minlength=len(Region))
    # every branch is hit, each at least 20 times (measured 23–270 each)
    assert counts.min() >= 20, dict(zip([r.name for r in Region], counts))
    apex = new.region == Region.APEX
    c_cot = material.cohesion * material.cos_phi / material.sin_phi
    assert np.abs(got[apex, :3] - c_cot).max() <= 1e-12 * c_cot
    assert np.abs(got[apex, 3]).max() <= 1e-12 * c_cot


def test_compiled_mohr_coulomb_run_repeats_the_vectorised_fallback(monkeypatch):
    # Reference: the same explicit run through the Python loop with the vectorised return map
    # and the sparse assembly (MohrCoulomb's compiled constants taken away: the fallback of
    # every material without a compiled map). The two evaluate the same formulas in another
    # order (closed-form principal values against LAPACK, element sums against a sparse
    # product), ~1e-16 per evaluation; 480 steps of a dissipative plastic run do not amplify
    # that much (measured 2.3e-13 of each history's peak): the histories agree to 1e-10 of
    # their peaks, the contact states exactly. Gaps are round-off around a closed contact
    # (1e-18 m), so they are compared to the displacement's peak.
    scene = load_scene("strip_footing_clay", overrides=SAND)
    model, motion = build_model(scene), scene.build_motion()
    compiled = run_dynamic(model, scene, motion, DynamicOptions(method="explicit", snapshots=2))
    monkeypatch.setattr(MohrCoulomb, "Constants", None)
    fallback = run_dynamic(model, scene, motion, DynamicOptions(method="explicit", snapshots=2))
    assert compiled.metadata["compiled"] and not fallback.metadata["compiled"]
    for name in ("footing", "pressure", "structure_u", "displacement", "plastic_strain",
                 "energy"):
        x, y = getattr(fallback, name), getattr(compiled, name)
        assert np.abs(x - y).max() <= 1e-10 * np.abs(x).max(), name
    scale = np.abs(fallback.displacement).max()
    assert np.abs(fallback.gap - compiled.gap).max() <= 1e-10 * scale
    assert np.array_equal(fallback.status, compiled.status)
    # the run is plastic during the motion: more yielded elements and a larger ε̄p at the end
    # than after gravity (measured 18 -> 28 elements, 0.0033 -> 0.0059)
    eps = compiled.plastic_strain
    assert np.count_nonzero(eps[-1]) > np.count_nonzero(eps[0]) > 0
    assert eps[-1].max() > 1.5 * eps[0].max()
    # Energy: the route's own check (continuum.energy_tolerance) passed, and the balance
    # closes to O(dt²) as the Tresca pulse's does (measured 1.4e-4 of the input).
    error = compiled.energy_balance_error
    assert error <= compiled.metadata["energy_tolerance"]
    assert error < 1e-3
    assert compiled.energy[:, 1].max() > 0.1 * compiled.energy[:, 3].max()


def test_the_winkler_map_estimates_mohr_coulomb_at_the_compiled_rate():
    # Reference: the cost model of comparisons/studies/winkler_map/cost.py written out by hand,
    # seconds = F·dofs + R·dofs·steps: the frictional soil's fixed part F (its gravity state)
    # with the compiled per-step rate R; steps = ⌈duration V_p / (0.3 h_min)⌉ (the Courant
    # estimate), V_p = √((λ + 2G)/ρ) = 193.37 m/s of E = 50 MPa, ν = 0.3, ρ = 1.8 t/m³, and the
    # 4-across mesh's DOFs and element size as the estimate counts them without meshing: 18 × 9
    # Q2 elements of the box's grid lines, 2 · 37 · 19 = 1406 DOFs, 0.5 m under the footing.
    # The clay (Tresca) has the undrained soil's fixed part, Drucker–Prager the fallback's
    # rate. A stored record without a soil model (stored before the compiled Mohr–Coulomb)
    # counts as frictional when its map was not compiled.
    import math

    from upliftlab.comparisons.studies.winkler_map import cost

    sand = load_scene("strip_footing_clay", overrides=SAND)
    drucker = load_scene("strip_footing_clay", overrides=SAND + ["soil.model=drucker_prager"])
    clay = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4"])
    vp = math.sqrt(50e3 * 0.7 / (1.3 * 0.4) / 1.8)
    steps = math.ceil(2.0 * vp / (0.3 * 0.5))
    for scene, fixed, rate in ((sand, 1.1e-3, 1.0e-7), (drucker, 1.1e-3, 6.1e-6),
                               (clay, 4.0e-4, 1.0e-7)):
        estimate = cost.estimate_cost([], [("sand", scene, 2.0, False)], [], [])
        assert estimate.per_run == pytest.approx(fixed * 1406 + rate * 1406 * steps, rel=1e-12)
    old = {"dofs": 1406, "steps": 1000, "duration": 1.0, "compiled": False,
           "wall_time_s": 1.1e-3 * 1406 + 2e-6 * 1406 * 1000}
    new = {**old, "compiled": True, "soil_model": "mohr_coulomb",
           "wall_time_s": 1.1e-3 * 1406 + 2e-7 * 1406 * 1000}
    estimate = cost.estimate_cost([], [("sand", sand, 1.0, False)], [], [old, new])
    assert estimate.per_run == pytest.approx(1.1e-3 * 1406 + 2e-7 * 1406 * 1000, rel=1e-12)
    estimate = cost.estimate_cost([], [("sand", drucker, 1.0, False)], [], [old, new])
    assert estimate.per_run == pytest.approx(1.1e-3 * 1406 + 2e-6 * 1406 * 1000, rel=1e-12)
